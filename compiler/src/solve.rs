//! Solving a model by running its plan in the interpreter: the whole plan ([`solve`]) or one
//! pruned to some geoms ([`solve_plan`]), read back as a [`solution::Solution`] and measured
//! by the verifier.

use crate::{analysis, config, interp, plan, solution, verify};
use gcs_lang::model::GeomId;
use gcs_runtime::error::SolveError;
use std::collections::BTreeSet;

/// Solves a model with its whole plan: every geom. `branches` are indices by branch order.
pub fn solve(
    model: &gcs_lang::Model,
    analysis: &analysis::Analysis,
    params: &[f64],
    branches: &[usize],
) -> Result<solution::Solution, SolveError> {
    // An incomplete plan never produces an answer: a constraint it cannot satisfy, or a geom
    // it leaves free, is an error naming it.
    if let Some(u) = analysis.unsolved.first() {
        let c = &model.constraints[u.constraint];
        let dof: usize = analysis.free_geoms().iter().map(|(_, d)| d).sum();
        return Err(SolveError::new(
            c.name.clone(),
            c.text.clone(),
            gcs_runtime::error::ErrorKind::Degenerate,
            dof as f64,
        ));
    }
    if let Some((g, dof)) = analysis.free_geoms().first() {
        return Err(SolveError::new(
            model.geoms[*g].name.clone(),
            "under-constrained".to_string(),
            gcs_runtime::error::ErrorKind::Degenerate,
            *dof as f64,
        ));
    }
    let all: BTreeSet<GeomId> = model.top_level().map(|(id, _)| id).collect();
    solve_plan(model, &analysis.plan, &all, params, branches)
}

/// Runs `plan` (whole or pruned to `scope`, the top-level geoms it computes) and reads the
/// solution of those geoms; its `max_residual` covers every constraint among them, measured
/// independently of the plan.
pub fn solve_plan(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
) -> Result<solution::Solution, SolveError> {
    solve_plan_with(
        model,
        plan,
        scope,
        params,
        branches,
        &plan.sketch_defaults(),
    )
}

/// [`solve_plan`] with `defaults` (indexed like the plan's): the values of the defaults that
/// parameterize free motions, and where the outer iterations start.
pub fn solve_plan_with(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<solution::Solution, SolveError> {
    let choice = interp::Choice::Given(branches.to_vec());
    let (mut s, run_defaults, iterations) = match model.space {
        gcs_lang::model::Space::D2 => {
            let run = interp::run_with(model, plan, params, defaults, &choice)?;
            let s = solution::Solution::read(model, &run.config, scope);
            (s, run.defaults, run.iterations)
        }
        gcs_lang::model::Space::D3 => {
            let run = interp::run_in::<config::D3>(model, plan, params, defaults, &choice)?;
            let s = solution::Solution::read_space(model, &run.config, scope);
            (s, run.defaults, run.iterations)
        }
    };
    s.branches = plan
        .branches
        .iter()
        .zip(branches)
        .map(|(b, i)| (b.name.clone(), *i))
        .collect();
    s.defaults = (plan.defaults.iter())
        .zip(&run_defaults)
        .map(|(d, v)| (d.name.clone(), *v))
        .collect();
    s.iterations = iterations;
    s.grounded = plan.grounded.map(|g| model.geoms[g].name.clone());
    let residuals = verify::residuals_in(model, &s, params, scope);
    s.max_residual = verify::max_residual(&residuals);
    off_by(model, &s, &residuals)?;
    Ok(s)
}

/// Nothing off is `Ok`: the error of the constraint the verifier finds furthest from met, when
/// that is past a run-time check's tolerance ([`gcs_runtime::tol::CHECK_REL`] times one plus
/// the solution's size). A plan meets every constraint by construction or checks it, so this
/// fires only where a plan is wrong (an iteration that closed on an error that does not
/// measure what it displaced); the verifier shares nothing with the plan, so it sees that.
fn off_by(
    model: &gcs_lang::Model,
    s: &solution::Solution,
    residuals: &[verify::Residual],
) -> Result<(), SolveError> {
    let size = (s.points.iter().flat_map(|(_, p)| p.iter()))
        .chain(s.scalars.iter().map(|(_, x)| x))
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = gcs_runtime::tol::CHECK_REL * (1.0 + size);
    if s.max_residual.is_finite() && s.max_residual <= tol {
        return Ok(());
    }
    let worst = (residuals.iter())
        .map(|r| {
            (
                if r.value.is_nan() {
                    f64::INFINITY
                } else {
                    r.value
                },
                r,
            )
        })
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match worst {
        Some((off, r)) if off > tol => {
            let c = &model.constraints[r.constraint];
            Err(SolveError::new(
                c.name.clone(),
                c.text.clone(),
                gcs_runtime::error::ErrorKind::Inconsistent,
                off,
            ))
        }
        _ => Ok(()),
    }
}
