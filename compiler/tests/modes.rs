//! An iterated region keeps the sketch's assembly mode from a cold start (issue 37): the
//! orientation of its closing errors' Jacobian at the sketch's root (`gcs_runtime::mode`).
//!
//! On the 3-RPR (`examples/rpr3.gcs`), one default, `platform.p1_angle`, closes `l3`: the
//! distance from `B3` to `platform.p3`, a function `reach(t)` of the angle that the tests
//! compute themselves (`common/rpr3.rs`: two circles, the platform's frame) and whose roots
//! they find by a dense grid, sharing nothing with the plan.
//!
//! - `leg3` swept: every solve from the sketch's defaults lands on a root where `reach` has
//!   the slope's sign of the sketch's mode, the one Newton's method reaches when it has, and
//!   the nearest such root otherwise, or, where every root has the other, says so
//!   (`OtherMode`, with their count).
//! - `leg1` swept: the sketch's assembly followed warm from the sketch's value, outward both
//!   ways, and each sample solved cold from the sketch: the same assembly at every sample.

use gcs_compiler::analyse;
use gcs_runtime::error::ErrorKind;
use std::f64::consts::PI;

#[path = "common/rpr3.rs"]
mod rpr3;

use rpr3::{model as rpr3, LEG1};

/// `rpr3::reach` on the sketch's branch of `l2`, 0.
fn reach(t: f64) -> Option<f64> {
    rpr3::reach(t, 0)
}

/// A root of `reach(t) = leg3`: its angle and whether `reach` falls there.
#[derive(Clone, Copy, Debug)]
struct Root {
    t: f64,
    falling: bool,
}

/// Every root of `reach(t) = leg3` over the turn, by sign changes on a grid of 40,000 samples
/// refined by bisection; `None` when one is ambiguous (within a few samples of where the
/// circles stop meeting, or two roots within a few samples of each other: a near tangency).
fn roots(leg3: f64) -> Option<Vec<Root>> {
    let n = 40_000;
    let h = 2.0 * PI / f64::from(n);
    let at = |i: u32| -PI + h * f64::from(i % n);
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (at(i), at(i) + h);
        let (fa, fb) = match (reach(a), reach(b)) {
            (Some(fa), Some(fb)) => (fa, fb),
            (None, None) => continue,
            // An edge of the stretch where the circles meet: a root between the last sample
            // and the edge (where `reach` is steep) is ambiguous on this grid.
            (one, _) => {
                let (mut inside, mut outside) = if one.is_some() { (a, b) } else { (b, a) };
                for _ in 0..60 {
                    let mid = 0.5 * (inside + outside);
                    if reach(mid).is_some() {
                        inside = mid;
                    } else {
                        outside = mid;
                    }
                }
                let (near, edge) = (reach(if one.is_some() { a } else { b }), reach(inside));
                if let (Some(near), Some(edge)) = (near, edge) {
                    if (near - leg3).signum() != (edge - leg3).signum() {
                        return None;
                    }
                }
                continue;
            }
        };
        let (ga, gb) = (fa - leg3, fb - leg3);
        if ga == 0.0 || ga.signum() == gb.signum() {
            continue;
        }
        // Ambiguous: the stretch ends within a few samples, or the slope is nearly flat.
        if (1..=4)
            .any(|k| reach(a - f64::from(k) * h).is_none() || reach(b + f64::from(k) * h).is_none())
        {
            return None;
        }
        if ((gb - ga) / h).abs() < 1e-3 {
            return None;
        }
        let (mut lo, mut hi) = (a, b);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let gm = reach(mid).expect("defined inside the stretch") - leg3;
            if gm.signum() == ga.signum() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        out.push(Root {
            t: 0.5 * (lo + hi),
            falling: gb < ga,
        });
    }
    for w in out.windows(2) {
        if w[1].t - w[0].t < 10.0 * h {
            return None;
        }
    }
    Some(out)
}

fn angle_apart(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

#[test]
fn a_cold_solve_keeps_the_sketch_s_mode_or_says_it_has_no_assembly() {
    let model = rpr3();
    let analysis = analyse(&model).expect("analyses");
    let plan = &analysis.plan;
    assert_eq!(plan.iterations.len(), 1);
    // The sketch is drawn off its constraints: its assembly is the one that moves it least,
    // whose root has `reach` rising with the angle (its error rises with its default).
    let mode = plan.iterations[0]
        .mode
        .expect("the sketch's root has a mode");
    let wanted_falling = mode == gcs_runtime::mode::Orientation::Negative;
    let leg3 = model
        .param_named("leg3")
        .expect("leg3")
        .into_raw()
        .into_u32() as usize;
    let (mut kept, mut moved_on, mut none, mut skipped) = (0, 0, 0, 0);
    for k in 0..=400 {
        let value = 2.0 + 38.0 * f64::from(k) / 400.0;
        let Some(found) = roots(value) else {
            skipped += 1;
            continue;
        };
        let mut params = model.default_params();
        params[leg3] = value;
        let falling: Vec<Root> = (found.iter().copied())
            .filter(|r| r.falling == wanted_falling)
            .collect();
        match gcs_compiler::solve(&model, &analysis, &params, &[0]) {
            Ok(s) => {
                let t = s.defaults[0].1;
                let Some(root) = found.iter().find(|r| angle_apart(r.t, t) < 1e-8) else {
                    // A root where the circles of `l2` are about to stop meeting, on the
                    // square-root edge the grid does not resolve: checked by its value.
                    let edge = (1..=8).any(|k| {
                        let d = 2.0 * PI / 40_000.0 * f64::from(k);
                        reach(t - d).is_none() || reach(t + d).is_none()
                    });
                    let on = reach(t).is_some_and(|r| (r - value).abs() < 1e-9);
                    assert!(edge && on, "leg3 {value}: {t} is no root of {found:?}");
                    skipped += 1;
                    continue;
                };
                assert_eq!(root.falling, wanted_falling, "leg3 {value}: the root {t}");
                // Newton's root where it falls, else the nearest falling root.
                let sketch = plan.defaults[0].sketch;
                let nearest = (falling.iter())
                    .map(|r| angle_apart(r.t, sketch))
                    .fold(f64::INFINITY, f64::min);
                if angle_apart(t, sketch) <= nearest + 1e-9 {
                    kept += 1;
                } else {
                    moved_on += 1;
                }
            }
            Err(e) if e.kind == ErrorKind::OtherMode => {
                assert!(
                    falling.is_empty(),
                    "leg3 {value}: {falling:?} are of the mode"
                );
                assert!(!found.is_empty(), "leg3 {value}: no root at all");
                assert_eq!(e.magnitude, found.len() as f64, "leg3 {value}");
                none += 1;
            }
            Err(e) => {
                assert!(
                    falling.is_empty(),
                    "leg3 {value}: {e} where {falling:?} are of the mode"
                );
            }
        }
    }
    eprintln!(
        "the root nearest the sketch {kept}, another of the mode {moved_on}, other mode only {none}, ambiguous {skipped}"
    );
    assert!(kept > 100, "{kept}");
    assert!(none > 0, "some leg3 has only rising roots: {none}");
}

#[test]
fn a_cold_sweep_lands_on_the_assembly_followed_from_the_sketch() {
    let model = rpr3();
    let analysis = analyse(&model).expect("analyses");
    let plan = &analysis.plan;
    let leg1 = model
        .param_named("leg1")
        .expect("leg1")
        .into_raw()
        .into_u32() as usize;
    let values: Vec<f64> = (0..60).map(|i| 13.0 + 3.0 * f64::from(i) / 59.0).collect();
    let first = (0..values.len())
        .min_by(|&a, &b| {
            (values[a] - LEG1)
                .abs()
                .total_cmp(&(values[b] - LEG1).abs())
        })
        .expect("samples");
    let at = |v: f64| {
        let mut params = model.default_params();
        params[leg1] = v;
        params
    };
    let seed = gcs_compiler::solve(&model, &analysis, &at(LEG1), &[0]).expect("the sketch");
    let mut warm: Vec<Option<Vec<f64>>> = vec![None; values.len()];
    let down: Vec<usize> = (0..first).rev().collect();
    for order in [(first..values.len()).collect::<Vec<_>>(), down] {
        let mut last: Option<Vec<f64>> = Some(seed.defaults.iter().map(|(_, v)| *v).collect());
        for i in order {
            last = last.and_then(|d| {
                let all = model.top_level().map(|(id, _)| id).collect();
                gcs_compiler::solve_plan_with(&model, plan, &all, &at(values[i]), &[0], &d)
                    .ok()
                    .map(|s| s.defaults.iter().map(|(_, v)| *v).collect())
            });
            warm[i] = last.clone();
        }
    }
    let mut compared = 0;
    for (i, &v) in values.iter().enumerate() {
        let Some(w) = &warm[i] else { continue };
        let cold = gcs_compiler::solve(&model, &analysis, &at(v), &[0])
            .unwrap_or_else(|e| panic!("leg1 {v}: the warm sweep solves, cold: {e}"));
        let c = cold.defaults[0].1;
        assert!(
            angle_apart(c, w[0]) < 1e-8,
            "leg1 {v}: cold {c}, warm {}",
            w[0]
        );
        compared += 1;
    }
    // Below about leg1 = 13.6 the assembly followed from the sketch has ended (its fold).
    assert!(compared >= 40, "{compared}");
}

/// Where `l2`'s two circles stop meeting on its branch 0 (they touch there) as the angle
/// rises: the first such edge of a stretch where `reach` is defined, found from the grid and
/// bisected, with `reach` there.
fn an_edge() -> (f64, f64) {
    let n = 40_000;
    let h = 2.0 * PI / f64::from(n);
    for i in 0..n {
        let (a, b) = (-PI + h * f64::from(i), -PI + h * f64::from(i + 1));
        if reach(a).is_some() && reach(b).is_none() {
            let (mut inside, mut outside) = (a, b);
            for _ in 0..80 {
                let mid = 0.5 * (inside + outside);
                if reach(mid).is_some() {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            let value = reach(inside).expect("defined inside");
            return (inside, value);
        }
    }
    panic!("no edge on the turn");
}

/// A sweep that carries an assembly past the tangency of `l2`'s circles, which lies inside the
/// iteration's region: on `l2`'s branch the assembly ends there, and goes on along the other
/// root. The solve from the last answer's defaults on the sketch's branch fails, and the
/// search over branches `gcs solve` runs finds the assembly on `l2`'s other branch, beside the
/// tangency, and names the branch changed.
#[test]
fn past_a_tangency_inside_the_region_the_assembly_goes_on_along_the_other_branch() {
    let model = rpr3();
    let analysis = analyse(&model).expect("analyses");
    let plan = &analysis.plan;
    assert_eq!(plan.branches.len(), 1);
    let leg3 = model
        .param_named("leg3")
        .expect("leg3")
        .into_raw()
        .into_u32() as usize;
    let (edge, at_edge) = an_edge();
    // Inside the stretch, 1e-3 before the edge: the assembly followed.
    let t_in = edge - 1e-3;
    let before = reach(t_in).expect("defined");
    let past = at_edge + (at_edge - before);
    let with = |value: f64| {
        let mut params = model.default_params();
        params[leg3] = value;
        params
    };
    let all: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let followed = gcs_compiler::solve_plan_with(&model, plan, &all, &with(before), &[0], &[t_in])
        .expect("the assembly followed");
    assert!(angle_apart(followed.defaults[0].1, t_in) < 1e-9);
    // Past the tangency value, on the same branch from the same defaults: no assembly near.
    let same = gcs_compiler::solve_plan_with(&model, plan, &all, &with(past), &[0], &[t_in]);
    if let Ok(s) = &same {
        assert!(
            angle_apart(s.defaults[0].1, edge) > 1e-2,
            "branch 0 still has a root beside the edge: {}",
            s.defaults[0].1
        );
    }
    // The search over branches: `l2` flipped, the root beside the edge.
    let kept = gcs_compiler::solve_near_sketch(
        &model,
        plan,
        &all,
        &with(past),
        &[0],
        &[false],
        &[t_in],
        true,
    )
    .expect("the assembly goes on along the other branch");
    let t = kept.solution.defaults[0].1;
    assert!(
        angle_apart(t, edge) < 1e-2,
        "{t} is not beside the tangency at {edge}"
    );
    assert_eq!(kept.solution.branches_changed.len(), 1, "{kept:?}");
    assert_eq!(kept.solution.branches_changed[0].name, "l2");
    assert_eq!(kept.solution.branches_changed[0].used, 1);
    assert!(kept.solution.max_residual < 1e-9);
}

/// `gcs solve`'s cold solve of an iterated plan follows the sketch's assembly from the model's
/// params (`all::sketch_assembly`): over `leg1` from 13 to 16 each sample solved alone lies on
/// one continuous path of assemblies (no two neighbouring samples' angles more than 0.05 rad
/// apart, where a jump to another assembly moves it by a radian or more), and past the
/// tangency of `l2`'s circles the path goes on along `l2`'s other root, which the solution
/// names as a changed branch, saying where it passed: between the last sample on the
/// sketch's root and the first on the other, the same place from every sample past it. The
/// samples include 15.5, where the root on the other side hugs the edge of the stretch where
/// `l2`'s circles meet (within 1e-9 rad of it just past the tangency).
#[test]
fn a_cold_solve_follows_the_sketch_s_assembly_through_a_tangency() {
    let model = rpr3();
    let analysis = analyse(&model).expect("analyses");
    let plan = &analysis.plan;
    let leg1 = model
        .param_named("leg1")
        .expect("leg1")
        .into_raw()
        .into_u32() as usize;
    let all: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let sketch = plan.sketch_defaults();
    let mut previous: Option<f64> = None;
    let mut flipped = 0;
    let mut last_kept = f64::NEG_INFINITY;
    let mut passed_at: Option<f64> = None;
    let samples = (0..60).map(|i| 13.0 + 3.0 * f64::from(i) / 59.0);
    for value in samples.chain([15.5, 15.373, 15.38]) {
        let mut params = model.default_params();
        params[leg1] = value;
        let gcs_compiler::all::Followed {
            solution: s,
            passed,
        } = gcs_compiler::all::sketch_assembly(
            &model,
            plan,
            &all,
            &params,
            &[0],
            &sketch,
            &[false],
        )
        .unwrap_or_else(|e| panic!("leg1 {value}: {e}"));
        assert!(s.max_residual < 1e-9, "leg1 {value}: {}", s.max_residual);
        assert_eq!(s.sketch_assembly_ended, None, "leg1 {value}");
        let t = s.defaults[0].1;
        if value <= 16.0 {
            if let Some(p) = previous {
                assert!(angle_apart(t, p) < 0.05, "leg1 {value}: {p} then {t}");
            }
            previous = Some(t);
        }
        match s.branches_changed.first() {
            Some(change) => {
                assert_eq!((change.name.as_str(), change.used), ("l2", 1));
                assert_eq!(passed.len(), 1, "leg1 {value}: {passed:?}");
                let (branch, left, took) = (passed[0].branch, passed[0].left, passed[0].took);
                assert_eq!((branch, left, took), (0, 0, 1), "leg1 {value}");
                let at = passed[0].params[leg1];
                assert!(at <= value, "leg1 {value}: passed at {at}");
                if let Some(p) = passed_at {
                    assert!(
                        (at - p).abs() < 0.01,
                        "leg1 {value}: passed at {at}, else {p}"
                    );
                }
                passed_at = Some(at);
                flipped += 1;
            }
            None => {
                assert!(passed.is_empty(), "leg1 {value}: {passed:?}");
                last_kept = last_kept.max(value);
            }
        }
    }
    assert!(flipped > 0, "the path never passed l2's tangency");
    let at = passed_at.expect("passed");
    assert!(
        last_kept < at,
        "kept the sketch's root at {last_kept}, past {at}"
    );
}

/// Past a fold the sketch's assembly ends, and a cold solve says so. The Stewart platform's
/// assembly, followed from the sketch's `l1` upward, ends at a fold (shown independently by
/// `compiler/bench/tests/stewart_fold.rs`: the baseline's own Newton finds no assembly near
/// the last answer past it). Here the fold is located by a warm sweep in steps of 0.002 from
/// the sketch; a cold solve past it returns another assembly with `sketch_assembly_ended` at
/// that fold (between the sweep's last answer and its first failure, or a step short of it), and
/// the warning that says so; a cold solve
/// short of the fold says nothing and lands where the warm sweep does.
#[test]
fn past_a_fold_a_cold_solve_says_the_sketch_s_assembly_ended() {
    let path = format!("{}/../examples/stewart.gcs", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    let (_, model, diags) = gcs_lang::load(&path, &bytes);
    let model = model.unwrap_or_else(|| panic!("{diags:?}"));
    let plan = analyse(&model).expect("analyses").plan;
    let l1 = model.param_named("l1").expect("l1").into_raw().into_u32() as usize;
    let sketch_l1 = model.default_params()[l1];
    let all: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let choice = gcs_compiler::interp::Choice::Given(branches.clone());
    // The warm sweep, from the sketch's assembly.
    let mut params = model.default_params();
    let mut warm = plan.sketch_defaults();
    let mut warm_at = Vec::new();
    let fold = loop {
        params[l1] += 0.002;
        assert!(params[l1] < sketch_l1 + 0.5, "no fold up to {}", params[l1]);
        match gcs_compiler::interp::run_in::<gcs_compiler::config::D3>(
            &model, &plan, &params, &warm, &choice,
        ) {
            Ok(run) => {
                warm = run.defaults.clone();
                warm_at.push((params[l1], run.defaults));
            }
            Err(_) => break params[l1] - 0.002,
        }
    };
    let cold = |value: f64| {
        let mut p = model.default_params();
        p[l1] = value;
        gcs_compiler::solve::solve_near_sketch(
            &model,
            &plan,
            &all,
            &p,
            &branches,
            &vec![false; branches.len()],
            &plan.sketch_defaults(),
            false,
        )
        .unwrap_or_else(|e| panic!("l1 {value}: {e}"))
    };
    let past = cold(fold + 0.1);
    let ended = (past.solution.sketch_assembly_ended.as_ref()).expect("the assembly ended");
    let at = ended.iter().find(|(n, _)| n == "l1").expect("l1").1;
    // The warm sweep's last answer is at `fold`, its first failure a step on.
    assert!(
        at < fold + 0.002 && at >= fold - 0.004,
        "ended at {at}, the warm sweep's last answer at {fold}"
    );
    let warning = gcs_compiler::report::sketch_assembly_ended(&model, &plan, &past.solution)
        .expect("a warning");
    assert!(gcs_compiler::report::is_sketch_branches(&warning));
    assert!(
        warning.notes.iter().any(|n| n.contains("near l1 = ")),
        "{warning:?}"
    );
    // Short of the fold: the warm sweep's assembly, said to be the sketch's.
    let (value, defaults) = &warm_at[warm_at.len() / 2];
    let short = cold(*value);
    assert_eq!(short.solution.sketch_assembly_ended, None, "l1 {value}");
    assert!(gcs_compiler::report::sketch_assembly_ended(&model, &plan, &short.solution).is_none());
    // The same pose (the platform's three angles reach each pose by two triples: compare
    // the points).
    let mut p = model.default_params();
    p[l1] = *value;
    let warm = gcs_compiler::solve::solve_plan_with(&model, &plan, &all, &p, &branches, defaults)
        .expect("the warm answer");
    let at = warm.by_name();
    for (name, got) in &short.solution.points {
        let want = at.point(name).expect("the same points");
        let apart = (got.iter().zip(want)).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(apart < 1e-6, "l1 {value}: {name} {got:?}, warm {want:?}");
    }
}
