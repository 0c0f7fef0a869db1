//! Pruning a plan to a model's `output` statements: only the steps the outputs depend on stay.
//!
//! A backward slice over the straight-line program. An output needs its top-level geom; a geom
//! needs every action that moved it; an action needs the registers it reads; a measurement
//! needs the geom it measures (as moved by the actions before it). Actions keep only the geoms
//! that are needed; branch variables of pruned intersections disappear.

use crate::plan::{BranchId, Op, Plan, Reg};
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
    let mut geoms: BTreeSet<GeomId> = model
        .outputs
        .iter()
        .map(|o| model.top_level_of(o.geom))
        .collect();
    let mut regs: BTreeSet<Reg> = BTreeSet::new();
    let mut keep = vec![false; plan.steps.len()];
    // Iterate to a fixpoint: a measurement found needed late can make earlier actions needed.
    loop {
        let before = (geoms.len(), regs.len());
        for (i, step) in plan.steps.iter().enumerate().rev() {
            let needed = match &step.op {
                Op::Translate { geoms: gs, .. }
                | Op::RotatePoint { geoms: gs, .. }
                | Op::RotateDir { geoms: gs, .. } => gs.iter().any(|g| geoms.contains(g)),
                Op::SetDim { geom, .. } => geoms.contains(geom),
                Op::Check { constraint } => model.constraints[*constraint]
                    .args
                    .iter()
                    .all(|a| geoms.contains(&model.top_level_of(*a))),
                _ => step.out.is_some_and(|(r, _)| regs.contains(&r)),
            };
            if !needed {
                continue;
            }
            keep[i] = true;
            regs.extend(Plan::reads(&step.op));
            match &step.op {
                Op::PointOf(f) | Op::DirOf(f) | Op::DimOf(f) => {
                    geoms.insert(model.top_level_of(*f));
                }
                Op::Check { constraint } => {
                    for a in &model.constraints[*constraint].args {
                        geoms.insert(model.top_level_of(*a));
                    }
                }
                _ => {}
            }
        }
        if (geoms.len(), regs.len()) == before {
            break;
        }
    }
    // Rebuild: keep the needed steps, drop unneeded geoms from actions, renumber branches.
    let mut branch_map: HashMap<BranchId, BranchId> = HashMap::new();
    let mut out = Plan {
        regs: plan.regs,
        grounded: plan.grounded,
        ..Plan::default()
    };
    for (step, k) in plan.steps.iter().zip(&keep) {
        if !k {
            continue;
        }
        let mut s = step.clone();
        match &mut s.op {
            Op::Translate { geoms: gs, .. }
            | Op::RotatePoint { geoms: gs, .. }
            | Op::RotateDir { geoms: gs, .. } => {
                gs.retain(|g| geoms.contains(g));
            }
            Op::Intersect { branch, .. } => {
                let next = BranchId(branch_map.len() as u32);
                let new = *branch_map.entry(*branch).or_insert(next);
                if new == next {
                    out.branches.push(plan.branches[branch.0 as usize].clone());
                }
                *branch = new;
            }
            _ => {}
        }
        out.steps.push(s);
    }
    (out, geoms)
}
