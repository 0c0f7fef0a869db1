//! What depends on what in a plan, said once: the configuration state each op reads
//! ([`Op::measures`]) and changes ([`Op::moves`]), beside the registers it reads
//! ([`Op::reads`]); the plan's dependences indexed ([`Plan::deps`]) and the backward slice
//! walked over them ([`Deps::walk`]), which pruning to outputs and [`Plan::support`] share;
//! and the support of a step, the user's constraints and fixed geoms that what it reads rests
//! on.
//!
//! A register depends on the registers its step reads and, for a measurement, on the state of
//! the top-level geom it measures at that point; that state depends on every earlier step that
//! moved the geom (a translation, a rotation, a dimension set), and on what those steps read.
//! Kramer's actions never undo an earlier one's invariants, so a geom's state rests on all of
//! them. The analysis's forward tracing of defaults (`close_iterations`) reads the same
//! [`Op::measures`] and [`Op::moves`].

use super::{Op, Plan, PlanarOp, Reg, SpatialOp, Step};
use gcs_lang::expr::ExprId;
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;
use rustc_hash::FxHashSet;
use std::collections::{BTreeMap, BTreeSet, HashMap};

impl Op {
    /// The feature or geom whose current state the op reads from the configuration (a
    /// position, a direction, a dimension), if any: its top-level geom's state at that step.
    pub fn measures(&self) -> Option<GeomId> {
        match self {
            Op::PointOf(f) | Op::DirOf(f) | Op::DimOf(f) => Some(*f),
            _ => None,
        }
    }

    /// The top-level geoms whose state the op changes: those an action moves rigidly, or the
    /// one whose dimension it sets.
    pub fn moves(&self) -> &[GeomId] {
        match self {
            Op::Translate { geoms, .. }
            | Op::RotatePoint { geoms, .. }
            | Op::RotateDir { geoms, .. }
            | Op::Spatial(SpatialOp::RotateBy { geoms, .. }) => geoms,
            Op::SetDim { geom, .. } => std::slice::from_ref(geom),
            _ => &[],
        }
    }

    /// The constraint the op names itself, if any: the one an intersection, an `Onto`, a
    /// check or a close is for, or whose value a size is.
    pub fn constraint(&self) -> Option<ConstraintId> {
        match self {
            Op::Intersect { constraint, .. }
            | Op::Planar(PlanarOp::PassingDir { constraint, .. })
            | Op::Onto { constraint, .. }
            | Op::Check { constraint, .. }
            | Op::Close { constraint, .. }
            | Op::Size { constraint, .. } => Some(*constraint),
            _ => None,
        }
    }
}

/// The plan's dependences, indexed once: the step that defines each register, and the steps
/// that move each top-level geom, in plan order. A slice walks them from what it needs to what
/// that rests on, and visits only its own steps: the support of each of many checks costs the
/// size of that support, not of the plan.
#[derive(Clone, Debug)]
pub struct Deps<'p> {
    model: &'p Model,
    plan: &'p Plan,
    /// The step defining each register, by register number.
    def: Vec<Option<usize>>,
    /// The steps moving each top-level geom, in plan order.
    moves: HashMap<GeomId, Vec<usize>>,
}

/// A backward slice of a plan: the steps that some values at some points of the plan depend
/// on ([`Deps::walk`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Slice {
    /// Its steps, in plan order.
    pub steps: Vec<usize>,
    /// Each top-level geom whose state it needs, with the step before which it needs it: every
    /// step before that one that moves the geom is in the slice.
    pub live: BTreeMap<GeomId, usize>,
    /// The top-level geoms that a step of the slice measures.
    pub read: BTreeSet<GeomId>,
}

/// A slice being walked: steps taken, and those whose operands are still to be followed.
#[derive(Debug)]
pub struct Walk<'d, 'p> {
    deps: &'d Deps<'p>,
    taken: FxHashSet<usize>,
    todo: Vec<usize>,
    live: BTreeMap<GeomId, usize>,
    read: BTreeSet<GeomId>,
}

impl Plan {
    /// The plan's dependences, indexed.
    pub fn deps<'p>(&'p self, model: &'p Model) -> Deps<'p> {
        let mut def = vec![None; self.regs as usize];
        let mut moves: HashMap<GeomId, Vec<usize>> = HashMap::new();
        for (i, s) in self.steps.iter().enumerate() {
            if let Some(slot) = s.out.and_then(|(r, _)| def.get_mut(r.0 as usize)) {
                *slot = Some(i);
            }
            for g in s.op.moves() {
                moves.entry(*g).or_default().push(i);
            }
        }
        Deps {
            model,
            plan: self,
            def,
            moves,
        }
    }
}

impl<'p> Deps<'p> {
    /// An empty slice, to be seeded and walked.
    pub fn walk(&self) -> Walk<'_, 'p> {
        Walk {
            deps: self,
            taken: FxHashSet::default(),
            todo: Vec::new(),
            live: BTreeMap::new(),
            read: BTreeSet::new(),
        }
    }
}

impl Walk<'_, '_> {
    /// Takes step `i` into the slice.
    pub fn take(&mut self, i: usize) {
        if i < self.deps.plan.steps.len() && self.taken.insert(i) {
            self.todo.push(i);
        }
    }

    /// Needs the value of register `r`: takes the step defining it.
    pub fn need(&mut self, r: Reg) {
        if let Some(&Some(i)) = self.deps.def.get(r.0 as usize) {
            self.take(i);
        }
    }

    /// Needs the state of top-level geom `g` before step `before`: takes every step before it
    /// that moves `g`.
    pub fn live(&mut self, g: GeomId, before: usize) {
        let since = match self.live.get(&g) {
            Some(&b) if b >= before => return,
            Some(&b) => b,
            None => 0,
        };
        self.live.insert(g, before);
        let deps = self.deps;
        let Some(steps) = deps.moves.get(&g) else {
            return;
        };
        let from = steps.partition_point(|&a| a < since);
        for &a in steps[from..].iter().take_while(|&&a| a < before) {
            self.take(a);
        }
    }

    /// Whether the state of `g` is needed after step `i`.
    pub fn is_live_after(&self, g: GeomId, i: usize) -> bool {
        self.live.get(&g).is_some_and(|&before| before > i)
    }

    /// Follows what the steps taken read, until nothing is left: the registers they read,
    /// the state of the geom a measurement reads, and what `grow` says a step needs beyond
    /// its registers (geoms live before it).
    pub fn run(&mut self, grow: impl Fn(&Step, &mut Vec<GeomId>)) {
        let deps = self.deps;
        let mut more = Vec::new();
        while let Some(i) = self.todo.pop() {
            let step = &deps.plan.steps[i];
            for r in step.op.reads() {
                self.need(r);
            }
            if let Some(f) = step.op.measures() {
                let top = deps.model.top_level_of(f);
                self.read.insert(top);
                self.live(top, i);
            }
            grow(step, &mut more);
            for g in more.drain(..) {
                self.live(g, i);
            }
        }
    }

    /// The slice walked.
    pub fn finish(self) -> Slice {
        let mut steps: Vec<usize> = self.taken.into_iter().collect();
        steps.sort_unstable();
        Slice {
            steps,
            live: self.live,
            read: self.read,
        }
    }
}

/// What a step rests on: the user's constraints whose steps placed what it reads, and the
/// fixed geoms it reads. For a check, the constraints that imply the one it holds.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Support {
    /// The constraints, the step's own left out.
    pub constraints: BTreeSet<ConstraintId>,
    /// The fixed top-level geoms read.
    pub fixed: BTreeSet<GeomId>,
    /// The geom grounded at its sketch (nothing being fixed), if the step reads it.
    pub grounded: Option<GeomId>,
}

impl Plan {
    /// The support of step `i`: the constraints whose steps placed what it reads (the
    /// actions that moved the geoms it measures, through everything they read in turn, and
    /// the constraints whose values it reads), the fixed geoms it reads, and the grounded one
    /// if it reads that. The step's own constraints are left out: for a check, what remains
    /// is what implies the constraint it holds; for an intersection, where its loci come from.
    ///
    /// A step that works for a constraint reads the state of that constraint's geoms, even
    /// where a register stands for one of them: once an action has put a feature onto a
    /// point, the analysis reads the feature's position from that point's register (a
    /// revolute's marker from the fixed point it is pinned to). So the geoms of every
    /// constraint of the slice, and of the step's own, are live too: the action that put the
    /// feature there, and its constraint, are in the support.
    pub fn support(&self, model: &Model, i: usize) -> Support {
        self.supports(model, &[i]).pop().unwrap_or_default()
    }

    /// [`Plan::support`] of each of `steps`, the plan indexed once for all.
    pub fn supports(&self, model: &Model, steps: &[usize]) -> Vec<Support> {
        let deps = self.deps(model);
        let value_of: HashMap<ExprId, ConstraintId> = (model.constraints.iter())
            .filter_map(|(id, c)| Some((c.value?, id)))
            .collect();
        let geoms_of = |step: &Step, live: &mut Vec<GeomId>| {
            for c in step_constraints(step) {
                live.extend((model.constraints[c].args.iter()).map(|&g| model.top_level_of(g)));
            }
        };
        let one = |i: usize| -> Support {
            let Some(step) = self.steps.get(i) else {
                return Support::default();
            };
            // The step's operands as a step of its own slice reads them, without the step.
            let mut walk = deps.walk();
            for r in step.op.reads() {
                walk.need(r);
            }
            let mut live: Vec<GeomId> = (step.op.measures())
                .map(|f| model.top_level_of(f))
                .into_iter()
                .collect();
            geoms_of(step, &mut live);
            for g in live {
                walk.live(g, i);
            }
            walk.run(geoms_of);
            let slice = walk.finish();
            let mut out = Support::default();
            for s in slice.steps.iter().filter_map(|&j| self.steps.get(j)) {
                out.constraints.extend(step_constraints(s));
                if let Op::Expr(e) = &s.op {
                    out.constraints.extend(value_of.get(e).copied());
                }
            }
            for &g in slice.live.keys() {
                if model.geoms[g].fixed {
                    out.fixed.insert(g);
                }
            }
            out.grounded = self.grounded.filter(|g| slice.read.contains(g));
            for c in step_constraints(step).chain(step.works_for) {
                out.constraints.remove(&c);
            }
            out
        };
        steps.iter().map(|&i| one(i)).collect()
    }
}

/// The constraints a step works for, as a support reads them: those an action satisfies or
/// moves its geoms for, and the one an operation names (an intersection, an `Onto`, a check,
/// a close, a constraint's value).
fn step_constraints(step: &Step) -> impl Iterator<Item = ConstraintId> + '_ {
    let action = !step.op.moves().is_empty();
    (step.satisfies.iter().copied())
        .chain(step.works_for.filter(|_| action))
        .chain(step.op.constraint())
}

/// `a`, `a and b`, `a, b and c`.
fn listed(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The most members of a support a message names or marks: a message about a large model
/// fits a screen, and says how many more there are.
pub const SHOWN: usize = 12;

/// A support in words: `a, b and c (with fixed A and fixed B)`, `fixed A and fixed B`, or
/// the grounded geom's placement when nothing else; `None` when it names nothing. Of a large
/// support, the [`SHOWN`] members nearest `near` in the source (the constraint it is about),
/// then how many more.
pub fn support_words(model: &Model, support: &Support, near: gcs_lang::Span) -> Option<String> {
    let (shown, more) = nearest(model, support, near);
    let (mut constraints, mut fixed) = (Vec::new(), Vec::new());
    for (_, who) in shown {
        match who {
            Supporter::Constraint(c) => constraints.push(model.constraints[c].name.clone()),
            Supporter::Fixed(g) => fixed.push(format!("fixed {}", model.geoms[g].name)),
        }
    }
    if more > 0 {
        constraints.push(format!("{more} more"));
    }
    match (constraints.is_empty(), fixed.is_empty()) {
        (false, false) => Some(format!(
            "{} (with {})",
            listed(&constraints),
            listed(&fixed)
        )),
        (false, true) => Some(listed(&constraints)),
        (true, false) => Some(listed(&fixed)),
        (true, true) => support
            .grounded
            .map(|g| format!("where the sketch places {}, grounded", model.geoms[g].name)),
    }
}

/// At most [`SHOWN`] members of a support, in source order: its fixed geoms first, then the
/// constraints nearest `near` in the source; and how many are left out.
pub fn nearest(
    model: &Model,
    support: &Support,
    near: gcs_lang::Span,
) -> (Vec<(gcs_lang::Span, Supporter)>, usize) {
    let all = by_position(model, support);
    if all.len() <= SHOWN {
        return (all, 0);
    }
    let (mut fixed, mut constraints): (Vec<_>, Vec<_>) =
        (all.into_iter()).partition(|(_, who)| matches!(who, Supporter::Fixed(_)));
    let dropped = fixed.len().saturating_sub(SHOWN / 2);
    fixed.truncate(SHOWN / 2);
    let room = SHOWN - fixed.len();
    let distance = |span: &gcs_lang::Span| span.start.abs_diff(near.start);
    constraints.sort_by_key(|(span, _)| (distance(span), span.start));
    let more = dropped + constraints.len().saturating_sub(room);
    constraints.truncate(room);
    let mut shown: Vec<_> = fixed.into_iter().chain(constraints).collect();
    shown.sort_by_key(|(span, _)| (span.start, span.end));
    (shown, more)
}

/// One member of a support.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Supporter {
    /// A constraint whose steps placed what the step reads.
    Constraint(ConstraintId),
    /// A fixed geom the step reads.
    Fixed(GeomId),
}

/// The members of a support with their spans, in source order.
pub fn by_position(model: &Model, support: &Support) -> Vec<(gcs_lang::Span, Supporter)> {
    let mut out: Vec<(gcs_lang::Span, Supporter)> = (support.constraints.iter())
        .map(|&c| (model.constraints[c].span, Supporter::Constraint(c)))
        .chain((support.fixed.iter()).map(|&g| (model.geoms[g].span, Supporter::Fixed(g))))
        .collect();
    out.sort_by_key(|(span, _)| (span.start, span.end));
    out
}
