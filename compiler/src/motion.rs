//! The globally least motion from the sketch (`gcs solve --least-motion global`).
//!
//! An under-constrained model's free motions are its free defaults (those no outer iteration
//! varies): by default each takes its own least-motion value, the one that moves nothing at
//! the step that reads it. That is least motion step by step: a free default chosen early can
//! make later steps move their geoms further than another choice would. The global option
//! chooses the free defaults together, to minimise the sum of squared displacements of every
//! point from its sketch: the answer a numeric solver's minimum-norm step approaches, but on
//! the plan's own assemblies, each solve still closed form. The search is Levenberg-Marquardt
//! over the free defaults (a handful: the model's mobility), each Jacobian column by central
//! differences of the plan run, from the step-by-step answer, which it never makes worse.

use crate::plan::{DefaultId, Plan};
use crate::solution::Solution;
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use gcs_runtime::error::SolveError;
use std::collections::BTreeSet;

/// The most Levenberg-Marquardt steps the search takes.
const MAX_STEPS: usize = 100;

/// The relative size of a central difference's step.
const STEP: f64 = 1e-6;

/// `solve_plan_with` at `defaults`, but with the free defaults no `held` marks (given by the
/// user) chosen together so that the points move least, in total, from their sketch.
///
/// # Errors
///
/// The solve's error at the step-by-step defaults; a trial that fails is only a rejected step.
pub fn globally_least(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
    held: &[bool],
) -> Result<Solution, SolveError> {
    let solve = |d: &[f64]| crate::solve_plan_with(model, plan, scope, params, branches, d);
    let start = solve(defaults)?;
    let free: Vec<usize> = (0..plan.defaults.len())
        .filter(|&i| !held.get(i).copied().unwrap_or(false))
        .filter(|&i| {
            let id = DefaultId(i as u32);
            !plan.iterations.iter().any(|it| it.defaults.contains(&id))
        })
        .collect();
    let Some(sketch) = Solution::of_sketch(model, params, scope) else {
        return Ok(start);
    };
    if free.is_empty() {
        return Ok(start);
    }
    // The displacement of every point from its sketch, flattened.
    let displacement = |s: &Solution| -> Vec<f64> {
        (s.points.iter())
            .flat_map(|(n, p)| {
                let q = sketch.points.iter().find(|(m, _)| m == n).map(|(_, q)| q);
                (p.iter().enumerate()).map(move |(k, a)| q.map_or(0.0, |q| a - q[k]))
            })
            .collect()
    };
    let cost = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    let mut x: Vec<f64> = defaults.to_vec();
    let mut best = start;
    let mut r = displacement(&best);
    let mut c = cost(&r);
    let mut lambda = 1e-3;
    for _ in 0..MAX_STEPS {
        // The Jacobian of the displacements in the free defaults, by central differences.
        let mut jac: Vec<Vec<f64>> = Vec::with_capacity(free.len());
        for &i in &free {
            let h = STEP * (1.0 + x[i].abs());
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[i] += h;
            minus[i] -= h;
            let (Ok(a), Ok(b)) = (solve(&plus), solve(&minus)) else {
                return Ok(best);
            };
            let (ra, rb) = (displacement(&a), displacement(&b));
            if ra.len() != r.len() || rb.len() != r.len() {
                return Ok(best);
            }
            jac.push(
                ra.iter()
                    .zip(&rb)
                    .map(|(p, m)| (p - m) / (2.0 * h))
                    .collect(),
            );
        }
        let k = free.len();
        // The normal equations, damped: (JᵀJ + λ diag JᵀJ) δ = -Jᵀ r.
        let jtj = nalgebra::DMatrix::from_fn(k, k, |a, b| {
            jac[a].iter().zip(&jac[b]).map(|(p, q)| p * q).sum::<f64>()
        });
        let jtr = nalgebra::DVector::from_fn(k, |a, _| {
            -jac[a].iter().zip(&r).map(|(p, q)| p * q).sum::<f64>()
        });
        let mut improved = false;
        for _ in 0..20 {
            let mut damped = jtj.clone();
            for a in 0..k {
                damped[(a, a)] += lambda * jtj[(a, a)].max(1e-12);
            }
            let Some(delta) = damped.lu().solve(&jtr) else {
                lambda *= 10.0;
                continue;
            };
            let mut trial = x.clone();
            for (a, &i) in free.iter().enumerate() {
                trial[i] += delta[a];
            }
            if let Ok(s) = solve(&trial) {
                let rt = displacement(&s);
                let ct = cost(&rt);
                if rt.len() == r.len() && ct < c {
                    let small =
                        delta.norm() <= 1e-12 * (1.0 + x.iter().map(|v| v.abs()).sum::<f64>());
                    x = trial;
                    best = s;
                    r = rt;
                    improved = c - ct > 1e-15 * (1.0 + c) && !small;
                    c = ct;
                    lambda = (lambda / 3.0).max(1e-12);
                    break;
                }
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    Ok(best)
}
