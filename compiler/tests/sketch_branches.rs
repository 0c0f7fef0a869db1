//! The sketch's assembly is a promise, or gcs says it broke it: where the constraints cannot
//! be met on the sketch's branches, `solve_near_sketch` takes the combination nearest the
//! sketch, names every branch it changed (with the sketch's index and the meaning of the one
//! taken) and how far the points those branches place lie from their sketch; a branch the
//! caller holds is never changed; a model solvable on the sketch's branches changes none. Each
//! answer is judged by `verify`, which shares nothing with the plan, and by plain distances.
//! The command line's side is `compiler/cli/tests/sketch_branches.rs`.

use gcs_compiler::analysis::Analysis;
use gcs_compiler::solve::Kept;
use gcs_compiler::{analyse, solve_near_sketch, solve_plan};
use gcs_lang::Model;
use gcs_runtime::error::ErrorKind;
use std::collections::BTreeSet;

/// A strip of unit triangles sketched straight, whose `closing` needs it folded.
const FOLDED: &str = include_str!("models/folded_strip.gcs");

fn analysed(name: &str, text: &str) -> (Model, Analysis) {
    let (_, model, diagnostics) = gcs_lang::load(name, text.as_bytes());
    let model = model.unwrap_or_else(|| panic!("{name} does not load: {diagnostics:?}"));
    let analysis = analyse(&model).expect("analysed");
    (model, analysis)
}

/// `solve_near_sketch` of the whole plan at the default params, from the sketch's branches,
/// `held` those named.
fn near_sketch(
    model: &Model,
    a: &Analysis,
    held: &[&str],
) -> Result<Kept, gcs_runtime::error::SolveError> {
    let plan = &a.plan;
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let held: Vec<bool> = (plan.branches.iter())
        .map(|b| held.contains(&b.name.as_str()))
        .collect();
    solve_near_sketch(
        model,
        plan,
        &scope,
        &model.default_params(),
        &branches,
        &held,
        &plan.sketch_defaults(),
        false,
    )
}

/// A point of a solution by name.
fn point(s: &gcs_compiler::solution::Solution, name: &str) -> (f64, f64) {
    let p = &s.points.iter().find(|(n, _)| n == name).expect("a point").1;
    (p[0], p[1])
}

#[test]
fn the_folded_strip_cannot_keep_the_sketch_s_branches_and_says_which_it_changed() {
    let (model, a) = analysed("folded_strip.gcs", FOLDED);
    let plan = &a.plan;
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let params = model.default_params();
    let sketch: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    // On the sketch's branches the strip runs straight, and p7 cannot be one from p0 and p5.
    let strict = solve_plan(&model, plan, &scope, &params, &sketch).expect_err("no assembly");
    assert_eq!(strict.kind, ErrorKind::NoIntersection, "{strict}");

    let kept = near_sketch(&model, &a, &[]).expect("the folded strip solves");
    let s = &kept.solution;
    assert!(kept.changed());
    assert_eq!(kept.not_kept.as_ref(), Some(&strict));
    // Every constraint holds, by the verifier and by plain distances.
    let residuals = gcs_compiler::verify::residuals(&model, s, &params);
    assert_eq!(residuals.len(), model.constraints.len());
    let worst = gcs_compiler::verify::max_residual(&residuals);
    assert!(worst <= 1e-12, "a constraint is off by {worst}");
    for (_, c) in model.constraints.iter() {
        let names: Vec<&str> = (c.args.iter())
            .map(|&g| model.geoms[g].name.as_str())
            .collect();
        let (p, q) = (point(s, names[0]), point(s, names[1]));
        let d = (p.0 - q.0).hypot(p.1 - q.1);
        assert!((d - 1.0).abs() <= 1e-12, "{}: {d}", c.text);
    }
    // Each branch changed is named with the sketch's index, the one used and its meaning.
    let used: Vec<usize> = (plan.branches.iter())
        .map(|b| {
            s.branches
                .iter()
                .find(|(n, _)| *n == b.name)
                .expect("listed")
                .1
        })
        .collect();
    let differ: Vec<&str> = (plan.branches.iter().zip(&used))
        .filter(|(b, &u)| u != b.default)
        .map(|(b, _)| b.name.as_str())
        .collect();
    let named: Vec<&str> = s.branches_changed.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(named, differ);
    for c in &s.branches_changed {
        let b = plan
            .branches
            .iter()
            .find(|b| b.name == c.name)
            .expect("a branch");
        assert_eq!(c.sketch, b.default);
        assert_ne!(c.used, c.sketch);
        assert_eq!(c.meaning, b.meanings[c.used]);
    }
    // The answer nearest the sketch changes one branch: p5 folds back onto p2.
    assert_eq!(named, ["distance_p4_p5"]);
    // The points that branch places, with their distances from the sketch, farthest first.
    assert_eq!(kept.moved.len(), 1);
    let moved: Vec<&str> = kept.moved[0]
        .points
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    let mut by_name = moved.clone();
    by_name.sort_unstable();
    assert_eq!(by_name, ["p5", "p6", "p7"]);
    let at = gcs_compiler::solution::Solution::of_sketch(&model, &params, &scope).expect("sketch");
    for (n, d) in &kept.moved[0].points {
        let (p, q) = (point(s, n), point(&at, n));
        assert!(
            (d - (p.0 - q.0).hypot(p.1 - q.1)).abs() <= 1e-12,
            "{n}: {d}"
        );
    }
    assert_eq!(kept.farthest().map(|(n, _)| n), Some("p7"));
    assert!((kept.farthest().expect("one").1 - 3.0).abs() <= 1e-12);
}

#[test]
fn a_branch_held_is_never_changed() {
    let (model, a) = analysed("folded_strip.gcs", FOLDED);
    let plan = &a.plan;
    // Held on the sketch's side, the fold moves to another branch.
    let kept = near_sketch(&model, &a, &["distance_p4_p5"]).expect("solves");
    let s = &kept.solution;
    let index = |name: &str| {
        s.branches
            .iter()
            .find(|(n, _)| n == name)
            .expect("listed")
            .1
    };
    let p45 = plan
        .branches
        .iter()
        .find(|b| b.name == "distance_p4_p5")
        .expect("a branch");
    assert_eq!(index("distance_p4_p5"), p45.default);
    assert!(kept.changed());
    assert!(s
        .branches_changed
        .iter()
        .all(|c| c.name != "distance_p4_p5"));
    let worst = gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(
        &model,
        s,
        &model.default_params(),
    ));
    assert!(worst <= 1e-12, "a constraint is off by {worst}");
    // Every branch held: the error on the sketch's branches, unchanged.
    let all: Vec<&str> = plan.branches.iter().map(|b| b.name.as_str()).collect();
    let e = near_sketch(&model, &a, &all).expect_err("no assembly on the sketch's branches");
    assert_eq!(e.kind, ErrorKind::NoIntersection);
    assert_eq!(e.label, "distance_p5_p7");
}

#[test]
fn a_model_solvable_on_the_sketch_s_branches_changes_none() {
    for (name, text) in [
        ("fourbar.gcs", include_str!("../../examples/fourbar.gcs")),
        ("sixbar.gcs", include_str!("../../examples/sixbar.gcs")),
        ("rpr3.gcs", include_str!("../../examples/rpr3.gcs")),
    ] {
        let (model, a) = analysed(name, text);
        let kept = near_sketch(&model, &a, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            !kept.changed(),
            "{name}: {:?}",
            kept.solution.branches_changed
        );
        assert!(kept.moved.is_empty() && kept.not_kept.is_none(), "{name}");
        let sketch: Vec<(String, usize)> = (a.plan.branches.iter())
            .map(|b| (b.name.clone(), b.default))
            .collect();
        assert_eq!(kept.solution.branches, sketch, "{name}");
    }
}

#[test]
fn an_error_no_branch_can_avoid_is_returned_unchanged() {
    // The four-bar's loop cannot close with a crank this long: on either side of `elbow`.
    let text =
        include_str!("../../examples/fourbar.gcs").replace("crank_len = 1.5", "crank_len = 20");
    let (model, a) = analysed("long_crank.gcs", &text);
    let plan = &a.plan;
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let sketch: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let strict = solve_plan(&model, plan, &scope, &model.default_params(), &sketch);
    let e = near_sketch(&model, &a, &[]).expect_err("no assembly");
    assert_eq!(Err(e), strict.map(|_| ()));
}

#[test]
fn the_check_warns_and_explain_says_which_default_is_not_the_sketch_s() {
    let (model, a) = analysed("folded_strip.gcs", FOLDED);
    let problems = gcs_compiler::report::problems(&model, &a);
    assert!(problems.iter().all(|d| !d.is_error()), "{problems:?}");
    let warned: Vec<_> = (problems.iter())
        .filter(|d| gcs_compiler::report::is_sketch_branches(d))
        .collect();
    assert_eq!(warned.len(), 1, "{problems:?}");
    // The plan run on the sketch stops where p7 cannot reach: the branches before are the
    // sketch's, the last is not.
    let explained = gcs_compiler::explain::explain(&model, &a.plan);
    for b in &a.plan.branches {
        let head = format!("- {} (default {}, ", b.name, b.default);
        let line = explained
            .lines()
            .find(|l| l.starts_with(&head))
            .expect("listed");
        let sketch_s = line.contains("the sketch's");
        assert_eq!(sketch_s, b.from_sketch, "{line}");
        assert_eq!(b.from_sketch, b.name != "distance_p5_p7", "{}", b.name);
    }
}
