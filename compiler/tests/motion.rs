//! `--least-motion global` (`motion::globally_least`): under-constrained sketches, each started
//! from a sketch a user's drag left off its constraints, solved with the free defaults chosen
//! step by step and chosen together. The global choice never moves the points more in total,
//! every constraint still holds, and no small change of a free default moves them less (a
//! minimum of the total motion, measured here by the sum of squared displacements, computed
//! from the solution and the model's sketch alone).

use gcs_compiler::solution::Solution;
use std::collections::BTreeSet;

/// The sum of squared displacements of `s`'s points from the sketch.
fn motion(model: &gcs_lang::Model, s: &Solution) -> f64 {
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let sketch = Solution::of_sketch(model, &model.default_params(), &all).expect("a sketch");
    (s.points.iter())
        .map(|(n, p)| {
            let q = &sketch
                .points
                .iter()
                .find(|(m, _)| m == n)
                .expect("a point")
                .1;
            p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum::<f64>()
        })
        .sum()
}

mod under_constrained;
use under_constrained::MODELS;

#[test]
fn the_global_choice_moves_least_and_meets_every_constraint() {
    for text in MODELS {
        let c = gcs_compiler::compile("m.gcs", text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
        let (model, plan) = (&c.model, &c.analysis.plan);
        assert!(
            !c.analysis.free_defaults().is_empty(),
            "{text}: no free motion"
        );
        let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let params = model.default_params();
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        let defaults = plan.sketch_defaults();
        let step = gcs_compiler::solve_plan_with(model, plan, &all, &params, &branches, &defaults)
            .unwrap_or_else(|e| panic!("{text}: {e}"));
        let held = vec![false; plan.defaults.len()];
        let global = gcs_compiler::motion::globally_least(
            model, plan, &all, &params, &branches, &defaults, &held,
        )
        .unwrap_or_else(|e| panic!("{text}: {e}"));
        assert!(
            global.max_residual <= 1e-12,
            "{text}: {}",
            global.max_residual
        );
        let (ms, mg) = (motion(model, &step), motion(model, &global));
        println!("motion step by step {ms:.6}, together {mg:.6}");
        assert!(mg <= ms * (1.0 + 1e-12), "{text}: global {mg} > step {ms}");
        // A minimum: no small change of a free default moves the points less.
        let at: Vec<f64> = (plan.defaults.iter())
            .map(|d| {
                (global.defaults.iter())
                    .find(|(n, _)| *n == d.name)
                    .map_or(d.sketch, |(_, v)| *v)
            })
            .collect();
        for d in c.analysis.free_defaults() {
            for h in [1e-4, -1e-4] {
                let mut moved = at.clone();
                moved[d.0 as usize] += h * (1.0 + moved[d.0 as usize].abs());
                if let Ok(s) =
                    gcs_compiler::solve_plan_with(model, plan, &all, &params, &branches, &moved)
                {
                    assert!(
                        motion(model, &s) >= mg * (1.0 - 1e-9),
                        "{text}: default {} moved by {h} moves less",
                        plan.defaults[d.0 as usize].name
                    );
                }
            }
        }
    }
}
