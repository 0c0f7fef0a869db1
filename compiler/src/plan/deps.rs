//! What depends on what in a plan, said once: the configuration state each op reads
//! ([`Op::measures`]) and changes ([`Op::moves`]), beside the registers it reads
//! ([`Op::reads`]); the backward slice over the straight line ([`Plan::slice`]), which pruning
//! to outputs and [`Plan::support`] share; and the support of a step, the user's constraints
//! and fixed geoms that what it reads rests on.
//!
//! A register depends on the registers its step reads and, for a measurement, on the state of
//! the top-level geom it measures at that point; that state depends on every earlier step that
//! moved the geom (a translation, a rotation, a dimension set), and on what those steps read.
//! Kramer's actions never undo an earlier one's invariants, so a geom's state rests on all of
//! them. The analysis's forward tracing of defaults (`close_iterations`) reads the same
//! [`Op::measures`] and [`Op::moves`].

use super::{Op, Plan, Reg, Step};
use gcs_lang::expr::ExprId;
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;
use std::collections::{BTreeSet, HashMap};

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
            | Op::RotateDir { geoms, .. } => geoms,
            Op::SetDim { geom, .. } => std::slice::from_ref(geom),
            _ => &[],
        }
    }

    /// The constraint the op names itself (an intersection, an `Onto`, a check or a close is
    /// for one), if any.
    pub fn constraint(&self) -> Option<ConstraintId> {
        match self {
            Op::Intersect { constraint, .. }
            | Op::Onto { constraint, .. }
            | Op::Check { constraint, .. }
            | Op::Close { constraint, .. }
            | Op::Size { constraint, .. } => Some(*constraint),
            _ => None,
        }
    }
}

/// A backward slice of a plan: the steps that some values at a point of the plan depend on.
#[derive(Clone, Debug, PartialEq)]
pub struct Slice {
    /// Whether each step before the slice's end is in it.
    pub keep: Vec<bool>,
    /// For each step that moves geoms, those of them whose later state the slice needs.
    pub moved: Vec<Vec<GeomId>>,
    /// The top-level geoms whose state a step of the slice measures.
    pub read: BTreeSet<GeomId>,
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

impl Support {
    /// Whether it names nothing.
    pub fn is_empty(&self) -> bool {
        self.constraints.is_empty() && self.fixed.is_empty()
    }
}

impl Plan {
    /// The backward slice of the steps before `end` on which the registers `regs` and the
    /// states of the top-level geoms `live` depend, at `end`. A step is in it when it defines
    /// a register a later step of the slice reads, when it moves a geom whose later state the
    /// slice measures (or that is in `live`), or when `root` says so (given the geoms live
    /// after it); `grow` may add to the live geoms what a step taken into it stands for
    /// beyond its registers. One pass backward over the straight line.
    pub fn slice(
        &self,
        model: &Model,
        end: usize,
        regs: impl IntoIterator<Item = Reg>,
        live: BTreeSet<GeomId>,
        root: impl Fn(&Step, &BTreeSet<GeomId>) -> bool,
        grow: impl Fn(&Step, &mut BTreeSet<GeomId>),
    ) -> Slice {
        let end = end.min(self.steps.len());
        let mut needed = vec![false; self.regs as usize];
        fn need(needed: &mut [bool], r: Reg) {
            if let Some(slot) = needed.get_mut(r.0 as usize) {
                *slot = true;
            }
        }
        for r in regs {
            need(&mut needed, r);
        }
        let mut live = live;
        let mut read = BTreeSet::new();
        let mut keep = vec![false; end];
        let mut moved = vec![Vec::new(); end];
        for (i, step) in self.steps[..end].iter().enumerate().rev() {
            let moves = step.op.moves();
            let kept = if moves.is_empty() {
                root(step, &live)
                    || step
                        .out
                        .is_some_and(|(r, _)| needed.get(r.0 as usize) == Some(&true))
            } else {
                moved[i] = moves.iter().copied().filter(|g| live.contains(g)).collect();
                !moved[i].is_empty()
            };
            if !kept {
                continue;
            }
            keep[i] = true;
            for r in step.op.reads() {
                need(&mut needed, r);
            }
            if let Some(f) = step.op.measures() {
                let top = model.top_level_of(f);
                live.insert(top);
                read.insert(top);
            }
            grow(step, &mut live);
        }
        Slice { keep, moved, read }
    }

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
        let Some(step) = self.steps.get(i) else {
            return Support::default();
        };
        let geoms_of = |step: &Step, live: &mut BTreeSet<GeomId>| {
            for c in step_constraints(step) {
                live.extend((model.constraints[c].args.iter()).map(|&g| model.top_level_of(g)));
            }
        };
        let mut live: BTreeSet<GeomId> = (step.op.measures())
            .map(|f| model.top_level_of(f))
            .into_iter()
            .collect();
        geoms_of(step, &mut live);
        let slice = self.slice(model, i, step.op.reads(), live, |_, _| false, geoms_of);
        let value_of: HashMap<ExprId, ConstraintId> = (model.constraints.iter())
            .filter_map(|(id, c)| Some((c.value?, id)))
            .collect();
        let mut out = Support::default();
        for (s, _) in self.steps.iter().zip(&slice.keep).filter(|(_, k)| **k) {
            out.constraints.extend(step_constraints(s));
            if let Op::Expr(e) = &s.op {
                out.constraints.extend(value_of.get(e).copied());
            }
        }
        for &g in &slice.read {
            if model.geoms[g].fixed {
                out.fixed.insert(g);
            }
        }
        out.grounded = self.grounded.filter(|g| slice.read.contains(g));
        for c in step_constraints(step).chain(step.works_for) {
            out.constraints.remove(&c);
        }
        out
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
