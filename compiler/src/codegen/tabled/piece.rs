//! One piece of a large model's solve, written by the ordinary step emitter (`Solve::step`)
//! on what the piece loads from the store: the sketch of some geoms, or a run of groups of
//! steps. The same function writes a piece's canonical form and its representative's code
//! (see `lift`): what differs between the two is only how names and data are spelled.

use super::layout::{Layout, Piece, Slice, Slot, Work};
use crate::codegen::context::Context;
use crate::codegen::facts::{FrameFacts, Value};
use crate::codegen::lift;
use crate::codegen::names::Namer;
use crate::codegen::sketch::dimension_name;
use crate::codegen::solve::Solve;
use crate::codegen::writer::Writer;
use crate::plan::{Op, Reg};
use gcs_lang::model::GeomId;
use rustc_hash::FxHashMap as HashMap;

/// How a register reaches the pieces after the one that defines it.
#[derive(Clone, Debug)]
pub(super) enum Handed {
    /// A literal the defining piece computed: the value itself, and its name (for what is
    /// derived from it).
    Literal(Value, Option<String>),
    /// A local stored in a slot.
    Stored(Slot),
}

/// What codegen knows of a register handed on besides its value.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Known {
    finite: bool,
    size: bool,
    unit: bool,
}

/// What the pieces written so far hand on, and the sketch's facts of each frame (read once,
/// outside any lift scope: a seed is a fact, not code).
pub(super) struct Handoff {
    pub(super) regs: HashMap<Reg, (Handed, Known)>,
    pub(super) seeds: HashMap<GeomId, FrameFacts>,
}

impl Handoff {
    pub(super) fn new(cx: &Context<'_>, layout: &Layout) -> Handoff {
        let seeds = (layout.worked.iter())
            .map(|&g| (g, cx.sketch_frame(g).1))
            .collect();
        Handoff {
            regs: HashMap::default(),
            seeds,
        }
    }
}

/// The names the pieces' functions take, which no local may shadow.
pub(super) const RESERVED: [&str; 10] = [
    "params",
    "branches",
    "defaults",
    "tol",
    "tol_scale",
    "store",
    "row",
    "p",
    "text",
    "solution",
];

/// How a piece is spelled: its canonical form, or its representative's code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Spelling {
    Canonical,
    Representative,
}

/// Writes piece `piece`: its loads, its steps (or sketch) and its stores. In canonical
/// spelling, the registers it hands on are entered in `handoff` and given slots in `layout`.
pub(super) fn write(
    cx: &Context<'_>,
    layout: &mut Layout,
    handoff: &mut Handoff,
    piece: &Piece,
    spelling: Spelling,
) -> Writer {
    let mut names = match spelling {
        Spelling::Canonical => Namer::numbered(),
        Spelling::Representative => Namer::default(),
    };
    for reserved in RESERVED {
        names.reserve(reserved);
    }
    let mut s = Solve::new(cx, names);
    let comments = spelling == Spelling::Representative;
    match &piece.work {
        Work::Sketch(geoms) => sketch(&mut s, layout, geoms, comments),
        Work::Steps(range) => steps(&mut s, layout, handoff, piece, range.clone(), comments),
    }
}

/// The sketch of `geoms`: each frame, dimension and local coordinates params set, stored for
/// the steps and the solution, and their scale folded into the tolerance's (`tol_scale`).
fn sketch(s: &mut Solve<'_>, layout: &Layout, geoms: &[GeomId], comments: bool) -> Writer {
    let cx = s.cx;
    let mut w = Writer::at(1);
    w.no_comments = !comments;
    let checked = layout.checked;
    for &g in geoms {
        let geom = &cx.model.geoms[g];
        let name = s.names.fresh(&geom.name);
        let (ctor, _) = cx.sketch_frame(g);
        w.line(&format!("let {name} = {ctor};"));
        w.line(&format!(
            "store.frame[{}] = {name};",
            lift::slot(layout.frame[&g])
        ));
        let mut dim = None;
        if let (Some(what), Some(&slot)) = (dimension_name(geom.kind), layout.dim.get(&g)) {
            // A dimension the plan sets before reading it starts where that step sets it.
            let value = match cx.dim_set_before_read(g) {
                true => None,
                false => Some(cx.sketch_dim_declared(g)),
            };
            if let Some(value) = value {
                let d = s.names.fresh(&format!("{}_{what}", geom.name));
                w.line(&format!("let {d} = {value};"));
                w.line(&format!("store.scalar[{}] = {d};", lift::slot(slot)));
                dim = Some(d);
            } else {
                dim = cx.sketch_dim(g);
            }
        }
        for local in cx.param_locals(g) {
            let holds = crate::codegen::api::Holds::Local(local.feature);
            if let Some(slot) = layout.held.get(&holds) {
                w.line(&format!(
                    "store.{}[{}] = {};",
                    slot.slice.field(),
                    lift::slot(slot.index),
                    local.value
                ));
            }
        }
        let holds = crate::codegen::api::Holds::LineSketch(g);
        if let (Some(slot), Some(from)) = (
            layout.held.get(&holds),
            crate::codegen::api::line_sketch(cx, g),
        ) {
            let value = cx.point_code(from);
            w.line(&format!(
                "store.point[{}] = {value};",
                lift::slot(slot.index)
            ));
        }
        // The tolerance of run-time checks scales with the sketch of what the plan works on,
        // as the flat solve's does.
        if checked && cx.touched(g) {
            let coordinates = cx.space.coordinates().iter();
            let mut terms: Vec<String> =
                coordinates.map(|x| format!("{name}.origin.{x}")).collect();
            terms.extend(dim);
            w.line(&format!(
                "*tol_scale = tol_scale.max(gcs_runtime::tol::scale(&[{}]));",
                terms.join(", ")
            ));
        }
    }
    w
}

/// A run of groups of steps: the loads, the steps with their constraints' comments, the
/// stores.
fn steps(
    s: &mut Solve<'_>,
    layout: &mut Layout,
    handoff: &mut Handoff,
    piece: &Piece,
    range: std::ops::Range<usize>,
    comments: bool,
) -> Writer {
    let cx = s.cx;
    let m = cx.model;
    // What the piece loads, named before its steps name anything.
    for &g in &piece.geoms {
        let geom = &m.geoms[g];
        let name = s.names.fresh(&geom.name);
        s.frames.insert(g, name);
        let facts = match piece.at_sketch.contains(&g) {
            true => handoff.seeds.get(&g).cloned().unwrap_or_default(),
            false => FrameFacts::default(),
        };
        s.facts.frames.insert(g, facts);
        if let Some(what) = dimension_name(geom.kind) {
            let d = s.names.fresh(&format!("{}_{what}", geom.name));
            s.dims.insert(g, d);
        }
    }
    let mut locals = Vec::new();
    for &g in &piece.geoms {
        for local in cx.param_locals(g) {
            if cx.reads_feature(local.feature) {
                let name = s.names.fresh(&local.name);
                s.locals.insert(local.feature, name.clone());
                locals.push((name, local.value));
            }
        }
    }
    let mut loads = Vec::new();
    for &r in &piece.imports {
        let Some((handed, known)) = handoff.regs.get(&r).cloned() else {
            panic!(
                "bug in gcs: a piece reads r{} before the piece that defines it hands it on",
                r.0
            );
        };
        let value = match handed {
            Handed::Literal(value, name) => {
                if let Some(name) = name {
                    s.facts.literal_names.insert(r, name);
                }
                value
            }
            Handed::Stored(slot) => {
                let name = s.names.fresh(&load_name(cx, r));
                loads.push((name.clone(), slot));
                Value::Local(name)
            }
        };
        s.facts.regs.insert(r, value);
        if known.finite {
            s.facts.known_finite.insert(r);
        }
        if known.size {
            s.facts.known_sizes.insert(r);
        }
        if known.unit {
            s.facts.unit_dirs.insert(r);
        }
    }
    // The steps, in groups each opened by its constraints' comment.
    let mut body = Writer::at(1);
    body.no_comments = !comments;
    s.groups(&mut body, range);
    // What later pieces read: a literal as it is, anything else through the store.
    let mut stores = Writer::at(1);
    for &r in &piece.exports {
        let value = s.facts.value(r).clone();
        let known = Known {
            finite: s.facts.is_finite(r),
            size: s.facts.known_sizes.contains(&r),
            unit: s.facts.unit_dirs.contains(&r),
        };
        if value.is_literal() {
            let name = s.facts.literal_names.get(&r).cloned();
            handoff
                .regs
                .insert(r, (Handed::Literal(value, name), known));
            continue;
        }
        let slot = match handoff.regs.get(&r) {
            Some((Handed::Stored(slot), _)) => *slot,
            _ => {
                let ty = layout.types[&r];
                let slot = layout.allocate(Slice::of(ty));
                layout.reg.insert(r, slot);
                slot
            }
        };
        handoff.regs.insert(r, (Handed::Stored(slot), known));
        stores.line(&format!(
            "store.{}[{}] = {};",
            slot.slice.field(),
            lift::slot(slot.index),
            s.r(r)
        ));
    }
    // A frame neither moved in code nor known anew as a constant is as it was loaded: not
    // written back.
    for &g in &piece.moves {
        let literal = s.facts.frames.get(&g).is_some_and(|f| f.literal3.is_some());
        if !s.frame_writes.contains(&g) && !literal {
            continue;
        }
        let value = s.frame_value(g);
        stores.line(&format!(
            "store.frame[{}] = {value};",
            lift::slot(layout.frame[&g])
        ));
    }
    for &g in &piece.sets_dim {
        if let Some(&slot) = layout.dim.get(&g) {
            stores.line(&format!(
                "store.scalar[{}] = {};",
                lift::slot(slot),
                s.dim(g)
            ));
        }
    }
    // The declarations, now that the steps show what they read and move.
    let mut decls = Writer::at(1);
    for &g in &piece.geoms {
        let read = s.frame_reads.borrow().contains(&g);
        let written = s.frame_writes.contains(&g);
        if read || written {
            let m = if written { "mut " } else { "" };
            let value = match s.declared_at.get(&g) {
                Some(value) => value.clone(),
                None => format!("store.frame[{}]", lift::slot(layout.frame[&g])),
            };
            decls.line(&format!("let {m}{} = {value};", s.frame_local(g)));
        }
        if let (Some(d), Some(&slot)) = (s.dims.get(&g).cloned(), layout.dim.get(&g)) {
            let m = if piece.sets_dim.contains(&g) {
                "mut "
            } else {
                ""
            };
            decls.line(&format!("let {m}{d} = store.scalar[{}];", lift::slot(slot)));
        }
    }
    for (name, value) in locals {
        decls.line(&format!("let {name} = {value};"));
    }
    for (name, slot) in loads {
        decls.line(&format!(
            "let {name} = store.{}[{}];",
            slot.slice.field(),
            lift::slot(slot.index)
        ));
    }
    decls.push(&body);
    decls.push(&stores);
    decls
}

/// A name for a register loaded from the store: after the feature it measures or the
/// constraint it serves.
fn load_name(cx: &Context<'_>, r: Reg) -> String {
    let Some(&i) = cx.defined_at.get(&r) else {
        return "value".into();
    };
    let step = &cx.plan.steps[i];
    match &step.op {
        Op::PointOf(f) | Op::DirOf(f) => cx.model.geoms[*f].name.clone(),
        _ => match cx.plan.constraint_of(i) {
            Some(c) => cx.model.constraints[c].name.clone(),
            None => "value".into(),
        },
    }
}
