//! Where a large model's solve keeps what crosses its pieces, and what each piece reads and
//! hands on: all of it from the plan's steps and the model, never from code.
//!
//! The solve is cut into pieces: the sketch of `PIECE_GROUPS` geoms at a time (their frames,
//! dimensions and the local coordinates params set, stored for the steps and the `Solution`),
//! then runs of `PIECE_GROUPS` groups of steps, a group ending at the step that satisfies a
//! constraint. A piece loads the frames and dimensions of the geoms its steps read or move and
//! the registers earlier pieces define, and stores the frames it moves, the dimensions it sets
//! and the registers later pieces read. The store has a slice per kind of value, its slots
//! chosen by the plan's types.

use super::super::api::{self, Holds, Ty as ApiTy};
use super::super::context::Context;
use super::super::sketch::dimension_name;
use super::super::space::Space;
use crate::plan::{Op, PlanarOp, Reg, SpatialOp, Ty};
use gcs_lang::model::GeomId;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::BTreeMap;
use std::ops::Range;

/// How many geoms' sketches, or groups of steps, one piece holds.
pub(super) const PIECE_GROUPS: usize = 8;

/// A slice of the store: the values of one kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(in crate::codegen) enum Slice {
    Frame,
    Scalar,
    Point,
    Vector,
    Line,
    Circle,
    Conic,
    Plane,
    Sphere,
    Cylinder,
    Torus,
}

impl Slice {
    /// The slice that holds registers of plan type `ty`.
    pub(super) fn of(ty: Ty) -> Slice {
        match ty {
            Ty::Scalar => Slice::Scalar,
            Ty::Point => Slice::Point,
            Ty::Vector => Slice::Vector,
            Ty::Line => Slice::Line,
            Ty::Circle => Slice::Circle,
            Ty::Conic => Slice::Conic,
            Ty::Plane => Slice::Plane,
            Ty::Sphere => Slice::Sphere,
            Ty::Cylinder => Slice::Cylinder,
            Ty::Torus => Slice::Torus,
            Ty::Values => unreachable!("bug in gcs: a plan with a linear system is not tabled"),
        }
    }

    /// The store's field.
    pub(super) fn field(self) -> &'static str {
        match self {
            Slice::Frame => "frame",
            Slice::Scalar => "scalar",
            Slice::Point => "point",
            Slice::Vector => "vector",
            Slice::Line => "line",
            Slice::Circle => "circle",
            Slice::Conic => "conic",
            Slice::Plane => "plane",
            Slice::Sphere => "sphere",
            Slice::Cylinder => "cylinder",
            Slice::Torus => "torus",
        }
    }

    /// The Rust type of its values in the model's space.
    pub(super) fn rust(self, space: &dyn Space) -> &'static str {
        let (line, circle) = space.line_circle();
        match self {
            Slice::Frame => space.rust(ApiTy::Frame),
            Slice::Scalar => space.rust(ApiTy::Scalar),
            Slice::Point => space.rust(ApiTy::Point),
            Slice::Vector => space.rust(ApiTy::Vector),
            Slice::Line => line,
            Slice::Circle => circle,
            Slice::Conic => "Conic",
            Slice::Plane => "Plane",
            Slice::Sphere => "Sphere",
            Slice::Cylinder => "Cylinder",
            Slice::Torus => "Torus",
        }
    }

    /// The value a slot starts at, before the solve writes it.
    pub(super) fn zero(self) -> &'static str {
        match self {
            Slice::Scalar => "0.0",
            _ => "Default::default()",
        }
    }
}

/// A slot of the store.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct Slot {
    pub(super) slice: Slice,
    pub(super) index: u32,
}

/// What a piece does.
#[derive(Clone, Debug)]
pub(super) enum Work {
    /// Declares the sketch of these top-level geoms and stores it.
    Sketch(Vec<GeomId>),
    /// Runs the plan's steps in this range: whole groups.
    Steps(Range<usize>),
}

/// One piece of the solve.
#[derive(Clone, Debug)]
pub(super) struct Piece {
    pub(super) work: Work,
    /// The top-level geoms whose frames (and dimensions) its steps read or move, in model
    /// order.
    pub(super) geoms: Vec<GeomId>,
    /// Of those, the ones no earlier step moved: their frames are where the sketch put them.
    pub(super) at_sketch: HashSet<GeomId>,
    /// Of those, the ones it moves or whose dimension it sets (their frame or dimension is
    /// stored after it).
    pub(super) moves: Vec<GeomId>,
    pub(super) sets_dim: Vec<GeomId>,
    /// Registers its steps read that an earlier piece defines, in register order.
    pub(super) imports: Vec<Reg>,
    /// Registers it defines that a later piece reads, in register order.
    pub(super) exports: Vec<Reg>,
}

/// The pieces and the store of a large model's solve.
#[derive(Debug)]
pub(super) struct Layout {
    pub(super) pieces: Vec<Piece>,
    /// The geoms whose sketch the store holds, in model order: those the steps read or move
    /// and those the solution reports (but for constants).
    pub(super) worked: Vec<GeomId>,
    /// Each worked geom's frame.
    pub(super) frame: HashMap<GeomId, u32>,
    /// Each worked geom's dimension (a segment's length, a circle's radius).
    pub(super) dim: HashMap<GeomId, u32>,
    /// What else the solution reads: local coordinates params set, a line's sketch point.
    pub(super) held: HashMap<Holds, Slot>,
    /// The slot of each register a later piece loads (literals are handed on as such).
    pub(super) reg: HashMap<Reg, Slot>,
    /// The number of slots of each slice.
    pub(super) counts: BTreeMap<Slice, u32>,
    /// The plan type of each register.
    pub(super) types: HashMap<Reg, Ty>,
    /// Whether any step checks at run time (then the sketch scales the checks' tolerance).
    pub(super) checked: bool,
}

impl Layout {
    /// The pieces of the pruned plan of `cx` and the store's slots for the sketch.
    pub(super) fn new(cx: &Context<'_>, api: &api::Layout) -> Layout {
        let (m, plan) = (cx.model, cx.plan);
        let worked: Vec<GeomId> = (m.top_level())
            .map(|(id, _)| id)
            .filter(|&g| (cx.scope.contains(&g) && !api.is_constant(g)) || cx.touched(g))
            .collect();
        let mut layout = Layout {
            pieces: Vec::new(),
            worked: worked.clone(),
            frame: HashMap::default(),
            dim: HashMap::default(),
            held: HashMap::default(),
            reg: HashMap::default(),
            counts: BTreeMap::new(),
            checked: plan
                .steps
                .iter()
                .any(|st| matches!(st.op, Op::Check { .. } | Op::Onto { .. } | Op::Close { .. })),
            types: (plan.steps.iter()).filter_map(|s| s.out).collect(),
        };
        // What the solution reads besides frames and dimensions, by the geom that holds it.
        let mut held_by: HashMap<GeomId, Vec<&api::Field>> = HashMap::default();
        for field in &api.fields {
            match field.holds {
                Holds::Local(f) => held_by.entry(m.top_level_of(f)).or_default().push(field),
                Holds::LineSketch(h) => held_by.entry(h).or_default().push(field),
                _ => {}
            }
        }
        for &g in &worked {
            let slot = layout.allocate(Slice::Frame);
            layout.frame.insert(g, slot.index);
            if dimension_name(m.geoms[g].kind).is_some() {
                let slot = layout.allocate(Slice::Scalar);
                layout.dim.insert(g, slot.index);
            }
            for field in held_by.get(&g).into_iter().flatten() {
                let slice = match (field.holds, field.ty) {
                    (Holds::Local(_), api::Ty::Vector) => Slice::Vector,
                    _ => Slice::Point,
                };
                let slot = layout.allocate(slice);
                layout.held.insert(field.holds, slot);
            }
        }
        for chunk in worked.chunks(PIECE_GROUPS) {
            layout.pieces.push(Piece {
                work: Work::Sketch(chunk.to_vec()),
                geoms: chunk.to_vec(),
                at_sketch: chunk.iter().copied().collect(),
                moves: Vec::new(),
                sets_dim: Vec::new(),
                imports: Vec::new(),
                exports: Vec::new(),
            });
        }
        layout.step_pieces(cx);
        layout
    }

    /// A new slot of `slice`.
    pub(super) fn allocate(&mut self, slice: Slice) -> Slot {
        let count = self.counts.entry(slice).or_default();
        let slot = Slot {
            slice,
            index: *count,
        };
        *count += 1;
        slot
    }

    /// The pieces of steps, each with what it reads and hands on.
    fn step_pieces(&mut self, cx: &Context<'_>) {
        let (m, plan) = (cx.model, cx.plan);
        // Groups: up to and including each step that satisfies a constraint.
        let mut groups = Vec::new();
        let mut start = 0;
        for (i, step) in plan.steps.iter().enumerate() {
            if !step.satisfies.is_empty() {
                groups.push(start..i + 1);
                start = i + 1;
            }
        }
        if start < plan.steps.len() {
            groups.push(start..plan.steps.len());
        }
        let first = self.pieces.len();
        for chunk in groups.chunks(PIECE_GROUPS) {
            let range = chunk[0].start..chunk[chunk.len() - 1].end;
            self.pieces.push(Piece {
                work: Work::Steps(range),
                geoms: Vec::new(),
                at_sketch: HashSet::default(),
                moves: Vec::new(),
                sets_dim: Vec::new(),
                imports: Vec::new(),
                exports: Vec::new(),
            });
        }
        // The piece of each step.
        let mut piece_of = vec![0usize; plan.steps.len()];
        for (k, piece) in self.pieces.iter().enumerate().skip(first) {
            if let Work::Steps(range) = &piece.work {
                piece_of[range.clone()].iter_mut().for_each(|p| *p = k);
            }
        }
        let mut moved: HashSet<GeomId> = HashSet::default();
        let mut exports: Vec<HashSet<Reg>> = vec![HashSet::default(); self.pieces.len()];
        for k in first..self.pieces.len() {
            let Work::Steps(range) = self.pieces[k].work.clone() else {
                continue;
            };
            let mut geoms = std::collections::BTreeSet::new();
            let mut moves = std::collections::BTreeSet::new();
            let mut sets_dim = std::collections::BTreeSet::new();
            let mut imports = std::collections::BTreeSet::new();
            let mut at_sketch = HashSet::default();
            for i in range.clone() {
                let op = &plan.steps[i].op;
                if let Some(f) = op.measures() {
                    let g = m.top_level_of(f);
                    geoms.insert(g);
                    if !moved.contains(&g) {
                        at_sketch.insert(g);
                    }
                }
                for &g in op.moves() {
                    geoms.insert(g);
                    if !moved.contains(&g) {
                        at_sketch.insert(g);
                    }
                    match op {
                        Op::SetDim { .. } => sets_dim.insert(g),
                        _ => moves.insert(g),
                    };
                }
                for r in generated_reads(op) {
                    if let Some(&d) = cx.defined_at.get(&r) {
                        if d < range.start {
                            imports.insert(r);
                            exports[piece_of[d]].insert(r);
                        }
                    }
                }
                for &g in op.moves() {
                    if !matches!(op, Op::SetDim { .. }) {
                        moved.insert(g);
                    }
                }
            }
            let piece = &mut self.pieces[k];
            // In model order, as the flat solve declares them.
            piece.geoms = geoms.into_iter().collect();
            piece.geoms.sort_by_key(|g| model_order(*g));
            piece.at_sketch = at_sketch;
            piece.moves = moves.into_iter().collect();
            piece.sets_dim = sets_dim.into_iter().collect();
            piece.imports = imports.into_iter().collect();
        }
        for (piece, out) in self.pieces.iter_mut().zip(exports) {
            let mut out: Vec<Reg> = out.into_iter().collect();
            out.sort();
            piece.exports = out;
        }
    }
}

/// A geom's place in model order (its arena index).
fn model_order(g: GeomId) -> u32 {
    g.into_raw().into_u32()
}

/// The registers the generated code of `op` reads: its operands but an intersection's `near`
/// (the sketch's branch is chosen at analysis) and the point a circle or sphere of constant
/// radius goes through.
pub(in crate::codegen) fn generated_reads(op: &Op) -> Vec<Reg> {
    match op {
        Op::Intersect { a, b, .. } => vec![*a, *b],
        Op::Planar(PlanarOp::CircleThrough {
            center,
            through,
            radius,
        })
        | Op::Spatial(SpatialOp::SphereThrough {
            center,
            through,
            radius,
        }) => match radius {
            Some(_) => vec![*center],
            None => vec![*center, *through],
        },
        op => op.reads(),
    }
}
