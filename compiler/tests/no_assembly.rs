//! An outer iteration that fails says why: no assembly at all (`ErrorKind::NoAssembly`), none
//! near where it started (`ErrorKind::NoAssemblyNear`: the assembly it follows ended), or, when
//! it cannot tell, that it did not converge (`ErrorKind::NoConvergence`).
//!
//! Measured on the 3-RPR of `examples/rpr3.gcs`, whose plan iterates on one angle,
//! `platform.p1_angle` (of `platform.p1` on its circle about `B1`), and closes `l3`, the
//! distance from `B3` to `platform.p3`:
//! - with `leg3` shorter than `platform.p3` ever comes to `B3` as `platform.p1` goes round (on
//!   either branch of `l2`), no assembly exists: `NoAssembly` on `l3`, its magnitude the gap
//!   between `leg3` and the nearest `platform.p3` comes, and its message says so;
//! - with `leg3` just past a local maximum of that distance that is not the largest, a solve
//!   started from the assembly near the maximum (a sweep's last answer) finds none near it:
//!   `NoAssemblyNear`, its magnitude how far `leg3` is past the maximum; from the sketch,
//!   other assemblies exist.
//!
//! The distance is computed in closed form from the example's numbers (`common/rpr3.rs`, the
//! circle of `platform.p1`, the circle-circle intersection that places `platform.p2` on branch
//! `l2`, the platform's rigid triangle), never from the plan or the runtime.

use gcs_compiler::analyse;
use gcs_compiler::interp::{self, Choice};
use gcs_lang::Model;
use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::num::Shown;
use std::f64::consts::PI;

#[path = "common/rpr3.rs"]
mod rpr3;

use rpr3::{model as rpr3, reach};

/// The extremum of `reach` on branch `l2` (its least value with `sign` 1, its greatest with
/// -1) within `[lo, hi]`, where it is defined throughout: a grid, then golden sections.
fn extremum(l2: usize, lo: f64, hi: f64, sign: f64) -> (f64, f64) {
    let g = |t: f64| sign * reach(t, l2).expect("defined on the bracket");
    let n = 20_000;
    let (mut best, mut at) = (f64::INFINITY, lo);
    for i in 0..=n {
        let t = lo + (hi - lo) * f64::from(i) / f64::from(n);
        if g(t) < best {
            (best, at) = (g(t), t);
        }
    }
    let step = (hi - lo) / f64::from(n);
    let (mut a, mut b) = ((at - step).max(lo), (at + step).min(hi));
    while b - a > 1e-13 {
        let (u, v) = (a + 0.382 * (b - a), a + 0.618 * (b - a));
        if g(u) < g(v) {
            b = v;
        } else {
            a = u;
        }
    }
    let t = 0.5 * (a + b);
    (t, sign * g(t))
}

/// The params of the example with `leg3` at `value`.
fn params(model: &Model, value: f64) -> Vec<f64> {
    let mut p = model.default_params();
    let leg3 = model
        .param_named("leg3")
        .expect("leg3")
        .into_raw()
        .into_u32() as usize;
    p[leg3] = value;
    p
}

fn expect_error(kind: ErrorKind, run: Result<impl std::fmt::Debug, SolveError>) -> SolveError {
    let e = run.expect_err("no assembly");
    assert_eq!((e.label.as_ref(), e.kind), ("l3", kind), "{e}");
    assert_eq!(e.text, "distance(B3, platform.p3) = leg3", "{e}");
    e
}

/// `leg3 = 1`: `platform.p3` never comes nearer `B3` than 1.77 (branch 0 of `l2`) or 4.47
/// (branch 1), both at a smooth minimum of the distance away from where the branch stops
/// existing; on each branch the solve says no assembly exists, by the gap.
#[test]
fn a_leg_too_short_for_any_assembly_is_no_assembly_by_the_gap() {
    let model = rpr3();
    let a = analyse(&model).expect("analyse");
    assert_eq!(a.plan.defaults.len(), 1);
    assert!(a.plan.defaults[0].is_angle());
    let params = params(&model, 1.0);
    // The failing stretch of either branch lies within 0.09 of angle 0 (`platform.p1` too
    // near `B2` for the circles to meet): each minimum is on the rest of the turn.
    for (l2, lo, hi) in [(0, -1.0, -0.1), (1, -PI, -2.5)] {
        let (at, nearest) = extremum(l2, lo, hi, 1.0);
        assert!(at > lo + 0.01 && at < hi - 0.01, "a minimum inside: {at}");
        let gap = nearest - 1.0;
        let e = expect_error(
            ErrorKind::NoAssembly,
            gcs_compiler::solve(&model, &a, &params, &[l2]),
        );
        assert!(
            (e.magnitude - gap).abs() <= 1e-9 * gap,
            "branch {l2}: {} against the gap {gap}",
            e.magnitude
        );
        assert_eq!(
            e.to_string(),
            format!(
                "constraint `l3` (distance(B3, platform.p3) = leg3) cannot be met: no assembly \
                 exists here with the branches and the other defaults given; over the whole \
                 turn of the angle the iteration varies, it stays at least {} from closing",
                Shown(e.magnitude)
            )
        );
        // `--all-solutions` lists none either.
        let all = gcs_compiler::all::solve_all(
            &model,
            &a.plan,
            &model.top_level().map(|(id, _)| id).collect(),
            &params,
            &a.plan.sketch_defaults(),
        );
        assert!(all.solutions.is_empty(), "{:?}", all.solutions.len());
    }
}

/// On branch 1 of `l2` the distance has a local maximum of 28.27 near angle -0.38, below its
/// largest, 38.05: with `leg3` 0.3 past it, the assembly a sweep followed up to `leg3` 0.5
/// below it is gone (it met the other root of the maximum, at a fold), and the solve from its
/// defaults says none exists near them, by how far `leg3` is past the maximum; from the sketch,
/// the solve finds another assembly.
#[test]
fn a_leg_past_a_fold_is_no_assembly_near_the_start() {
    let model = rpr3();
    let a = analyse(&model).expect("analyse");
    let choice = Choice::Given(vec![1]);
    let (top, local_max) = extremum(1, -0.7, -0.2, -1.0);
    assert!((top + 0.38).abs() < 0.01, "{top}");
    let (_, largest) = extremum(1, 0.09, 0.5, -1.0);
    assert!(largest > local_max + 5.0, "{largest} {local_max}");

    // The assembly followed: on the left of the maximum, `leg3` 0.5 below it.
    let before = params(&model, local_max - 0.5);
    let run = interp::run_with(&model, &a.plan, &before, &[top - 0.2], &choice)
        .expect("an assembly below the maximum");
    let t = run.defaults[0];
    assert!(t < top && t > top - 0.5, "{t}");
    let d = reach(t, 1).expect("defined");
    assert!((d - (local_max - 0.5)).abs() < 1e-9, "{d}");

    // Past the maximum, from the assembly followed: none near it, by the excess over the maximum.
    let past = params(&model, local_max + 0.3);
    let e = expect_error(
        ErrorKind::NoAssemblyNear,
        interp::run_with(&model, &a.plan, &past, &[t], &choice),
    );
    assert!((e.magnitude - 0.3).abs() <= 1e-9, "{}", e.magnitude);
    assert_eq!(
        e.to_string(),
        format!(
            "constraint `l3` (distance(B3, platform.p3) = leg3) cannot be met: the assembly \
             followed from the defaults the iteration started from does not exist here; near \
             them the constraints it closes stay at least {} from closing (the least norm of \
             their errors there)",
            Shown(e.magnitude)
        )
    );
    // Elsewhere on the turn, assemblies exist: the solve from the sketch finds one.
    let other = gcs_compiler::solve(&model, &a, &past, &[1]).expect("another assembly");
    assert!(other.max_residual < 1e-9, "{}", other.max_residual);
}

/// A start where an intersection inside the region has no root is not a dead end: the
/// iteration descends on that intersection's gap to where its loci meet, and goes on from
/// there. `examples/cube_graph.gcs` iterates on two angles. Started at (-1.5, 0) on the
/// sketch's branches, its loci miss; the solve still lands on an assembly, every constraint
/// met (measured by the verifier, which shares nothing with the plan). Over a grid of starts
/// a half radian apart, 76 of 144 have loci that miss: 31 of those now solve (none did before
/// the descent). The others end where the gap has a minimum that is not a crossing (the
/// circles only touch there), or where the sketch's branches have no assembly.
#[test]
fn a_start_where_the_loci_miss_descends_on_the_gap_to_an_assembly() {
    let path = format!("{}/../examples/cube_graph.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    let c = gcs_compiler::compile("cube_graph.gcs", text.as_bytes()).expect("compiles");
    let plan = &c.analysis.plan;
    let names: Vec<&str> = plan.defaults.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["C_angle", "E_angle"]);
    let params = c.model.default_params();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let choice = Choice::Given(branches.clone());
    // The plan without its iteration: where the loci miss, it fails with the gap.
    let mut frozen = plan.clone();
    frozen.iterations.clear();
    let misses = |d: &[f64; 2]| {
        interp::run_with(&c.model, &frozen, &params, d, &choice)
            .is_err_and(|e| e.kind == ErrorKind::NoIntersection)
    };
    let all: std::collections::BTreeSet<_> = c.model.top_level().map(|(id, _)| id).collect();
    let solve = |d: &[f64; 2]| {
        gcs_compiler::solve::solve_plan_with(&c.model, plan, &all, &params, &branches, d)
    };
    assert!(misses(&[-1.5, 0.0]));
    let s = solve(&[-1.5, 0.0]).unwrap_or_else(|e| panic!("from (-1.5, 0): {e}"));
    assert!(s.max_residual < 1e-12, "residual {}", s.max_residual);
    let (mut missed, mut solved) = (0, 0);
    for i in 0..12 {
        for j in 0..12 {
            let d = [-3.0 + 0.5 * f64::from(i), -3.0 + 0.5 * f64::from(j)];
            if misses(&d) {
                missed += 1;
                if let Ok(s) = solve(&d) {
                    assert!(s.max_residual < 1e-12, "{d:?}: residual {}", s.max_residual);
                    solved += 1;
                }
            }
        }
    }
    assert_eq!(missed, 76);
    assert!(
        solved >= 25,
        "{solved} of {missed} starts where the loci miss solve"
    );
}
