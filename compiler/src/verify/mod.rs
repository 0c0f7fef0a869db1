//! The verifier: every constraint of the file re-evaluated on a [`Solution`], by plain
//! arithmetic on the solution's named values.
//!
//! It shares no code with the plan, the fragments, the configuration or the runtime's
//! intersections: it reads points, vectors and dimensions by name and measures each
//! constraint's violation from its definition in LANGUAGE.md. A plan bug therefore cannot hide
//! itself here. The arithmetic is the space's: `planar` for 2d models, `spatial` for 3d.

mod planar;
mod spatial;

/// How near a circle (relative to `1 + radius`) a segment's end must lie to count as joined to
/// it: [`gcs_runtime::tol::JOINED_REL`], which says why.
const JOINED: f64 = gcs_runtime::tol::JOINED_REL;

use crate::solution::Solution;
use gcs_lang::model::{ConstraintId, Space};
use gcs_lang::Model;

/// The violation of one constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct Residual {
    /// The constraint.
    pub constraint: ConstraintId,
    /// How far from satisfied (length or radians); NaN when a value it needs is missing.
    pub value: f64,
}

/// The residual of every constraint of the model on `solution`, with `params` for values.
pub fn residuals(model: &Model, solution: &Solution, params: &[f64]) -> Vec<Residual> {
    let s = solution.by_name();
    model
        .constraints
        .iter()
        .map(|(id, c)| {
            let value = c.value.map_or(0.0, |e| model.exprs.eval(e, params));
            let r = match model.space {
                Space::D2 => planar::residual(model, &s, c, value),
                Space::D3 => spatial::residual(model, &s, c, value),
            };
            Residual {
                constraint: id,
                value: r,
            }
        })
        .collect()
}

/// The largest residual (NaN-aware: a NaN residual is infinite).
pub fn max_residual(residuals: &[Residual]) -> f64 {
    residuals
        .iter()
        .map(|r| {
            if r.value.is_nan() {
                f64::INFINITY
            } else {
                r.value
            }
        })
        .fold(0.0, f64::max)
}

/// The residuals of the constraints among the top-level geoms of `scope` (those a plan pruned
/// to the model's outputs computes).
pub fn residuals_in(
    model: &Model,
    solution: &Solution,
    params: &[f64],
    scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
) -> Vec<Residual> {
    residuals(model, solution, params)
        .into_iter()
        .filter(|r| {
            model.constraints[r.constraint]
                .args
                .iter()
                .all(|a| scope.contains(&model.top_level_of(*a)))
        })
        .collect()
}

/// The largest residual of the constraints among the top-level geoms of `scope`.
pub fn max_residual_in(
    model: &Model,
    solution: &Solution,
    params: &[f64],
    scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
) -> f64 {
    max_residual(&residuals_in(model, solution, params, scope))
}
