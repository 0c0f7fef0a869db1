//! Pruning a plan to a model's `output` statements: only the steps the outputs depend on stay.
//!
//! A backward slice over the straight-line program. An output needs its top-level geom's final
//! state (a joint's value, `J.angle` or `J.travel`, the final states of the top-level geoms of
//! its two markers); a measurement needs the state of the geom it reads at that point, so the
//! actions before it; an action is kept for the geoms whose later state is read, and dropped
//! after the last read of a geom that is not an output (a rocker need not be turned into place
//! once the coupler has been placed from it). Only geoms the pruned plan places completely are
//! reported; branch variables of pruned intersections disappear, and branches and defaults are
//! renumbered and iterated regions moved to match.
//!
//! A check stays when every geom it measures is computed anyway or fixed, so that a pruned
//! solve refuses what the whole plan refuses wherever the outputs depend on it (a check
//! against a fixed stop guards the outputs). A pruned plan is validated in debug builds.

use crate::plan::{BranchId, DefaultId, DefaultVar, Iteration, Op, Plan, SpatialOp};
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use std::collections::{BTreeSet, HashMap};

/// The plan restricted to what `outputs` need, and the top-level geoms it computes. With no
/// outputs, the plan is returned whole.
pub fn prune(model: &Model, plan: &Plan) -> (Plan, BTreeSet<GeomId>) {
    let all: BTreeSet<GeomId> = model.top_level().map(|(id, _)| id).collect();
    if model.outputs.is_empty() {
        return (plan.clone(), all);
    }
    // One backward slice, from the outputs' final state: a geom is live while its state
    // after the current step is still read (by an output, or by a kept measurement or check).
    // A joint's value is measured on its two markers: both bodies' final states.
    let outputs: BTreeSet<GeomId> = (model.outputs.iter())
        .flat_map(|o| model.output_geoms(o))
        .map(|&g| model.top_level_of(g))
        .collect();
    let tops = |c: &gcs_lang::model::ConstraintId| -> Vec<GeomId> {
        model.constraints[*c]
            .args
            .iter()
            .map(|a| model.top_level_of(*a))
            .collect()
    };
    let n = plan.steps.len();
    let deps = plan.deps(model);
    let mut walk = deps.walk();
    for &g in &outputs {
        walk.live(g, n);
    }
    // What an iteration closes decides every answer of its region: always kept.
    for (i, step) in plan.steps.iter().enumerate() {
        if let Op::Close { .. } = step.op {
            walk.take(i);
        }
    }
    walk.run(|_, _| {});
    // A check is kept when everything it measures is computed anyway: live after it, or fixed
    // (a fixed geom is known without a step; a check against it guards the outputs, as a stop
    // a screw must reach decides which of its turns a pitch apart the answer is). What a check
    // takes in lies before it, so the checks are decided last to first, each once.
    for (i, step) in plan.steps.iter().enumerate().rev() {
        if let Op::Check { constraint, .. } = &step.op {
            if (tops(constraint).iter()).all(|&g| model.geoms[g].fixed || walk.is_live_after(g, i))
            {
                walk.take(i);
                walk.run(|_, _| {});
            }
        }
    }
    let slice = walk.finish();
    let mut keep = vec![false; n];
    for &i in &slice.steps {
        keep[i] = true;
    }
    // Each action moves, in the pruned plan, the geoms whose state is read after it.
    let moved: Vec<Vec<GeomId>> = (plan.steps.iter().enumerate())
        .map(|(i, s)| {
            (s.op.moves().iter().copied())
                .filter(|g| slice.live.get(g).is_some_and(|&before| before > i))
                .collect()
        })
        .collect();
    let mut touched: BTreeSet<GeomId> = outputs;
    touched.extend(slice.read);
    // The geoms the pruned plan places completely: read somewhere, and never left behind by a
    // move or a scaling the whole plan makes. Only these are reported.
    let mut geoms = touched;
    for (i, step) in plan.steps.iter().enumerate() {
        match &step.op {
            Op::Translate { geoms: gs, .. }
            | Op::RotatePoint { geoms: gs, .. }
            | Op::RotateDir { geoms: gs, .. }
            | Op::Spatial(SpatialOp::RotateBy { geoms: gs, .. }) => {
                for g in gs {
                    if !moved[i].contains(g) {
                        geoms.remove(g);
                    }
                }
            }
            Op::SetDim { geom, .. } if !keep[i] => {
                geoms.remove(geom);
            }
            _ => {}
        }
    }
    // Rebuild: the kept steps, actions on the geoms that need them, branches and defaults
    // renumbered, iterated regions moved to the kept steps' positions.
    let mut branch_map: HashMap<BranchId, BranchId> = HashMap::new();
    let mut default_map: HashMap<DefaultId, DefaultId> = HashMap::new();
    let mut out = Plan {
        regs: plan.regs,
        grounded: plan.grounded,
        grounded_direction: plan.grounded_direction,
        grounded_plane: plan.grounded_plane,
        grounded_dof: plan.grounded_dof,
        ..Plan::new(plan.space)
    };
    for (i, step) in plan.steps.iter().enumerate() {
        if !keep[i] {
            continue;
        }
        let mut s = step.clone();
        if let Some(branch) = s.op.branch_mut() {
            let next = BranchId(branch_map.len() as u32);
            let new = *branch_map.entry(*branch).or_insert(next);
            if new == next {
                out.branches.push(plan.branches[branch.0 as usize].clone());
            }
            *branch = new;
        }
        match &mut s.op {
            Op::Translate { geoms: gs, .. }
            | Op::RotatePoint { geoms: gs, .. }
            | Op::RotateDir { geoms: gs, .. }
            | Op::Spatial(SpatialOp::RotateBy { geoms: gs, .. }) => {
                gs.retain(|g| moved[i].contains(g));
            }
            Op::Default(d) => {
                let next = DefaultId(default_map.len() as u32);
                let new = *default_map.entry(*d).or_insert(next);
                if new == next {
                    let measure = None; // the pruned plan's registers are others
                    (out.defaults).push(DefaultVar {
                        measure,
                        ..plan.defaults[d.0 as usize].clone()
                    });
                }
                *d = new;
            }
            _ => {}
        }
        out.steps.push(s);
    }
    // The kept steps before each step of the whole plan: where it would be in the pruned one.
    let mut position = Vec::with_capacity(keep.len() + 1);
    let mut kept = 0;
    for k in &keep {
        position.push(kept);
        kept += usize::from(*k);
    }
    position.push(kept);
    for it in &plan.iterations {
        let (start, end) = (position[it.start], position[it.end]);
        if start < end {
            let defaults: Vec<DefaultId> = (it.defaults.iter())
                .filter_map(|d| default_map.get(d).copied())
                .collect();
            // An orientation is of the whole Jacobian: a region that lost a default has
            // another one.
            let mode = it.mode.filter(|_| defaults.len() == it.defaults.len());
            out.iterations.push(Iteration {
                defaults,
                start,
                end,
                mode,
            });
        }
    }
    // A pruned plan is a plan like any other: a back end may rely on its invariants.
    debug_assert_eq!(out.validate(model), Ok(()), "the pruned plan is malformed");
    (out, geoms)
}
