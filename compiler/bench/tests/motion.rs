//! The motion from a sketch drawn off its constraints to the answer: gcs's, with the free
//! defaults chosen step by step and chosen together (`--least-motion global`), against the
//! baseline's (Levenberg-Marquardt on the raw equations from the sketch, whose steps are the
//! least-norm corrections of its linearisation). The measure is the sum of squared
//! displacements of every point. Printed, for BENCHMARKS.md; asserted: the global choice comes
//! within 1.05x of the baseline's motion.
//!
//! `cargo test -p gcs-bench --release --test motion -- --nocapture`

#[path = "../../tests/under_constrained/mod.rs"]
mod under_constrained;

use gcs_bench::baseline::{Baseline, Method, Options};
use gcs_compiler::solution::Solution;
use std::collections::BTreeSet;

use gcs_bench::bench::squared_motion as motion;

#[test]
fn the_global_choice_moves_about_as_little_as_the_baseline() {
    for text in under_constrained::MODELS {
        let c = gcs_compiler::compile("m.gcs", text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
        let (model, plan) = (&c.model, &c.analysis.plan);
        let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let params = model.default_params();
        let sketch = Solution::of_sketch(model, &params, &all).expect("a sketch");
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        let defaults = plan.sketch_defaults();
        let step = gcs_compiler::solve_plan_with(model, plan, &all, &params, &branches, &defaults)
            .expect("a step-by-step solve");
        let held = vec![false; plan.defaults.len()];
        let global = gcs_compiler::motion::globally_least(
            model, plan, &all, &params, &branches, &defaults, &held,
        )
        .expect("a global solve");
        let mut b = Baseline::new(model).expect("a baseline");
        let mut x = b.start_from_sketch(&params);
        let out = b.solve(
            &params,
            &mut x,
            &Options {
                method: Method::LevenbergMarquardt,
                max_iterations: 500,
                tolerance: 1e-12,
                ..Options::default()
            },
        );
        assert!(out.converged, "{text}: {out:?}");
        let base = Solution::read(model, &b.config(&params, &x).expect("config"), &all);
        let (ms, mg, mb) = (
            motion(&sketch, &step),
            motion(&sketch, &global),
            motion(&sketch, &base),
        );
        println!(
            "{}: step by step {ms:.4}, together {mg:.4}, baseline {mb:.4} (together / baseline {:.3})",
            text.lines().nth(2).unwrap_or(""),
            mg / mb
        );
        assert!(
            mg <= 1.05 * mb,
            "{text}: global {mg} against the baseline's {mb}"
        );
    }
}
