//! Degrees-of-freedom analysis of a `.gcs` [`gcs_lang::Model`] into a metaphorical assembly
//! plan, and the plan's consumers: the interpreter (`gcs solve`) and the explainer
//! (`gcs explain`).
//!
//! The pipeline: [`analysis::analyse`] builds a [`plan::Plan`] from the model by action and
//! locus analysis; [`interp::run`] executes it on the sketch with given params and branches;
//! [`solution::Solution`] reads the result by the model's names; [`verify`] re-checks every
//! constraint on a solution without sharing code with the plan. Like every library crate here,
//! it never prints or exits.

pub mod analysis;
pub mod config;
pub mod explain;
pub mod interp;
pub mod nominal;
pub mod plan;
pub mod report;
pub mod solution;
pub mod verify;

use gcs_runtime::error::SolveError;

/// Solves a model with its analysis, params (indexed like the model's params) and branch
/// indices (by branch id; the defaults when `None`), and measures the residual of every
/// constraint independently.
pub fn solve(
    model: &gcs_lang::Model,
    analysis: &analysis::Analysis,
    params: &[f64],
    branches: &[usize],
) -> Result<solution::Solution, SolveError> {
    let run = interp::run(
        model,
        &analysis.plan,
        params,
        &interp::Choice::Given(branches.to_vec()),
    )?;
    let mut s = solution::Solution::read(model, &run.config);
    s.branches = analysis
        .plan
        .branches
        .iter()
        .zip(branches)
        .map(|(b, i)| (b.name.clone(), *i))
        .collect();
    s.grounded = analysis.plan.grounded.map(|g| model.geoms[g].name.clone());
    s.max_residual = verify::max_residual(&verify::residuals(model, &s, params));
    Ok(s)
}
