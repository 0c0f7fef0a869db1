//! The outer iterations: Newton with brackets on one default, the trust region on several, and
//! the scan for every root, on functions with known roots, failing stretches, no roots, and
//! non-finite input.
//!
//! Bounds: simple roots of well-separated polynomials and of small geometric systems to 1e-13
//! (what a closed form gives); double roots, whose position a residual fixes only to about
//! sqrt(eps), to 1e-6.
#![allow(clippy::unwrap_used)]

use std::cell::Cell;
use std::f64::consts::{PI, TAU};

use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::intersect2d::circle_circle;
use gcs_runtime::iterate::{all_roots, solve, Converged, Failure, RootScan, Settings, Span};
use gcs_runtime::locus2d::{Circle, P2};
use proptest::prelude::*;

/// `cases` cases (`PROPTEST_CASES` overrides them); the bound on rejections (a failing stretch
/// drawn over a root) grows with them.
fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(cases);
    ProptestConfig {
        max_global_rejects: 4 * cases,
        ..ProptestConfig::with_cases(cases)
    }
}

/// The product `c * prod (x - r_i)`, the double roots twice: accurate to a few roundings
/// relative to its value, so that a root is as sharp as the float it is.
fn product(c: f64, simple: &[f64], double: &[f64], x: f64) -> f64 {
    let mut p = c;
    for r in simple {
        p *= x - r;
    }
    for r in double {
        p *= (x - r) * (x - r);
    }
    p
}

/// `count` roots from `start`, consecutive gaps from `gaps` (each in its range).
fn spaced(start: f64, gaps: &[f64], count: usize) -> Vec<f64> {
    let mut roots = vec![start];
    for g in gaps.iter().take(count.saturating_sub(1)) {
        let last = *roots.last().unwrap();
        roots.push(last + g);
    }
    roots
}

fn solve1(
    x0: f64,
    scale: f64,
    f: impl Fn(f64) -> Result<f64, ()>,
) -> (f64, Result<Converged, Failure<()>>) {
    let mut x = [x0];
    let out = solve(&mut x, &[scale], &Settings::default(), |p, r| {
        r[0] = f(p[0])?;
        Ok(())
    });
    (x[0], out)
}

#[test]
fn default_settings() {
    let s = Settings::default();
    assert_eq!(s.tolerance, 1e-10);
    assert_eq!(s.rounding, 0.0);
    assert_eq!(s.max_evaluations, 200);
}

proptest! {
    #![proptest_config(config(512))]

    /// From within 5% of the gap to its neighbours, Newton converges to that root, to the last
    /// bits: the product form is exact at the float nearest the root.
    #[test]
    fn newton_converges_to_the_root_near_the_start(
        start in -2.0f64..-1.0,
        gaps in prop::collection::vec(0.2f64..0.8, 4),
        degree in 1usize..=5,
        pick in 0usize..5,
        offset in -0.05f64..0.05,
        c in prop_oneof![0.5f64..4.0, -4.0f64..-0.5],
    ) {
        let roots = spaced(start, &gaps, degree);
        let k = pick % roots.len();
        let x0 = roots[k] + offset * 0.2;
        let (x, out) = solve1(x0, 1.0, |x| Ok(product(c, &roots, &[], x)));
        let done = out.unwrap();
        prop_assert!((x - roots[k]).abs() <= 1e-13, "{x} vs {}: {done:?}", roots[k]);
        prop_assert!(done.residual <= 1e-13, "{done:?}");
        prop_assert!(done.evaluations <= 30, "{done:?}");
    }

    /// The scan finds exactly the known roots of a polynomial with simple roots and at most one
    /// double root, all at least 0.3 apart (so the sample spacing, 3/63, guarantees them).
    #[test]
    fn scan_finds_exactly_the_known_roots(
        start in -1.4f64..-1.0,
        gaps in prop::collection::vec(0.3f64..0.6, 4),
        count in 1usize..=5,
        double_at in 0usize..8,
        c in prop_oneof![0.5f64..4.0, -4.0f64..-0.5],
    ) {
        let all = spaced(start, &gaps, count);
        // `double_at` past the roots: no double root.
        let double: Vec<f64> = all.get(double_at).copied().into_iter().collect();
        let simple: Vec<f64> = all.iter().copied().filter(|r| !double.contains(r)).collect();
        let scan: RootScan<8> = all_roots(-1.5, 1.5, false, 64, &Settings::default(), |x| {
            Ok::<f64, ()>(product(c, &simple, &double, x))
        });
        prop_assert_eq!(scan.roots().len(), all.len(), "{:?} vs {:?}", scan.roots(), all);
        prop_assert!(!scan.truncated());
        for (i, (&found, &known)) in scan.roots().iter().zip(&all).enumerate() {
            let is_double = double.contains(&known);
            prop_assert_eq!(scan.is_double(i), is_double, "{:?}", scan);
            let bound = if is_double { 1e-6 } else { 1e-12 };
            prop_assert!((found - known).abs() <= bound, "{found} vs {known}: {:?}", scan);
            prop_assert!(scan.residual(i) <= 1e-10);
        }
    }

    /// Two roots 1e-6 apart dip by about 2.5e-13, within the tolerance: one double root at the
    /// bottom of the dip, wherever the pair sits between the samples. Pairs 1e-4 or more
    /// apart dip by 2.5e-9 or more: two simple roots.
    #[test]
    fn close_pairs_by_the_depth_of_their_dip(a in -0.6f64..0.6, c in 0.5f64..2.0) {
        let near = all_roots::<4, ()>(-1.0, 1.0, false, 32, &Settings::default(), |x| {
            Ok(product(c, &[a, a + 1e-6, -0.8], &[], x))
        });
        prop_assert_eq!(near.roots().len(), 2, "{:?}", near);
        prop_assert!((near.roots()[0] + 0.8).abs() <= 1e-12);
        prop_assert!((near.roots()[1] - (a + 5e-7)).abs() <= 1e-6, "{:?}", near);
        prop_assert!(near.is_double(1) && !near.is_double(0));
        for gap in [1e-4, 1e-3, 1e-2] {
            let far = all_roots::<4, ()>(-1.0, 1.0, false, 32, &Settings::default(), |x| {
                Ok(product(c, &[a, a + gap, -0.8], &[], x))
            });
            prop_assert_eq!(far.roots().len(), 3, "{}: {:?}", gap, far);
            prop_assert!((far.roots()[1] - a).abs() <= 1e-12, "{gap}: {:?}", far);
            prop_assert!((far.roots()[2] - (a + gap)).abs() <= 1e-12, "{gap}: {:?}", far);
            prop_assert!(!far.is_double(1) && !far.is_double(2));
        }
    }

    /// Roots at least 0.2 apart (twice the spacing) and a failing stretch holding no root,
    /// possibly starting exactly at a root: every root is found; the one at the stretch's edge
    /// is flagged as a boundary root when a sample falls in the stretch (otherwise the stretch
    /// hides inside a sign change, where the refinement finds the root either way).
    #[test]
    fn scan_finds_the_roots_around_a_failing_stretch(
        start in -1.4f64..-1.0,
        gaps in prop::collection::vec(0.2f64..0.5, 4),
        count in 1usize..=5,
        c in prop_oneof![0.5f64..4.0, -4.0f64..-0.5],
        edge_at in 0usize..8,
        u in -1.5f64..1.5,
        w in 0.005f64..0.19,
    ) {
        let roots = spaced(start, &gaps, count);
        let u = roots.get(edge_at).copied().unwrap_or(u);
        prop_assume!(roots.iter().all(|&r| !(r > u && r < u + w)));
        let fails = |x: f64| x > u && x < u + w;
        let scan: RootScan<8> = all_roots(-1.5, 1.5, false, 32, &Settings::default(), |x| {
            if fails(x) { Err(()) } else { Ok(product(c, &roots, &[], x)) }
        });
        prop_assert_eq!(scan.roots().len(), roots.len(), "{:?} vs {:?}", scan.roots(), roots);
        let sampled = (0..32).any(|i| fails(-1.5 + 3.0 * f64::from(i) / 31.0));
        for (i, (&found, &known)) in scan.roots().iter().zip(&roots).enumerate() {
            prop_assert!((found - known).abs() <= 1e-12, "{found} vs {known}: {:?}", scan);
            prop_assert!(!scan.is_double(i));
            if sampled || known != u {
                prop_assert_eq!(scan.is_boundary(i), known == u, "{:?}", scan);
            }
        }
    }

    /// Random circle pairs: from a start near one intersection (within a fifth of the half
    /// chord), the trust region converges to that intersection, not the other.
    #[test]
    fn two_circles_converge_to_the_intersection_near_the_start(
        r1 in 0.5f64..3.0,
        r2 in 0.5f64..3.0,
        t in 0.1f64..0.9,
        angle in 0.0f64..TAU,
        push in (0.0f64..TAU, 0.0f64..0.2),
        upper in any::<bool>(),
    ) {
        // Centres at distance d between |r1 - r2| and r1 + r2, so that they cross.
        let (lo, hi) = ((r1 - r2).abs(), r1 + r2);
        let d = lo + t * (hi - lo);
        let (c, s) = (angle.cos(), angle.sin());
        let c2 = [d * c, d * s];
        let along = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
        let half = (r1 * r1 - along * along).max(0.0).sqrt();
        let side = if upper { 1.0 } else { -1.0 };
        let root = [along * c - side * half * s, along * s + side * half * c];
        let start = [
            root[0] + 0.2 * push.1 * half * push.0.cos(),
            root[1] + 0.2 * push.1 * half * push.0.sin(),
        ];
        let mut x = start;
        let done = solve(&mut x, &[1.0, 1.0], &Settings::default(), |p, r| {
            r[0] = p[0] * p[0] + p[1] * p[1] - r1 * r1;
            r[1] = (p[0] - c2[0]).powi(2) + (p[1] - c2[1]).powi(2) - r2 * r2;
            Ok::<(), ()>(())
        });
        let done = done.unwrap();
        // The root itself moves by rounding over the conditioning of the crossing.
        let bound = 1e-13 * (1.0 + 1.0 / (half / r1.min(r2)));
        prop_assert!((x[0] - root[0]).hypot(x[1] - root[1]) <= bound, "{x:?} vs {root:?}: {done:?}");
        prop_assert!(done.evaluations <= 40, "{done:?}");
    }

    /// Non-finite or extreme starts, scales, intervals and tolerances never panic and stay
    /// within the budget (twice it when the iteration fails: the test for a minimum that is
    /// not zero has a budget of its own); a non-finite start is a NaN residual without a call.
    #[test]
    fn arbitrary_starts_and_scales_do_not_panic(
        x0 in any::<f64>(),
        y0 in any::<f64>(),
        s0 in any::<f64>(),
        s1 in any::<f64>(),
        tolerance in prop_oneof![Just(1e-10), any::<f64>()],
        samples in 0u32..40,
    ) {
        let calls = Cell::new(0u32);
        let settings = Settings { tolerance, max_evaluations: 60, ..Settings::default() };
        let mut x = [x0];
        let out = solve(&mut x, &[s0], &settings, |p, r| {
            calls.set(calls.get() + 1);
            r[0] = p[0] * p[0] - 2.0;
            Ok::<(), ()>(())
        });
        let budget = if out.is_ok() { 60 } else { 120 };
        prop_assert!(calls.get() <= budget);
        if !x0.is_finite() {
            prop_assert_eq!(calls.get(), 0);
            let nan = matches!(out, Err(Failure::NoConvergence { residual, .. }) if residual.is_nan());
            prop_assert!(nan);
        }
        calls.set(0);
        let mut x = [x0, y0];
        let out = solve(&mut x, &[s0, s1], &settings, |p, r| {
            calls.set(calls.get() + 1);
            r[0] = p[0] * p[1] - 1.0;
            r[1] = p[0] - p[1].sin();
            Ok::<(), ()>(())
        });
        let budget = if out.is_ok() { 60 } else { 120 };
        prop_assert!(calls.get() <= budget);
        let mut x = [x0, y0, s0];
        let _ = solve(&mut x, &[s1; 3], &settings, |p, r| {
            r[0] = p[0] + p[1] * p[2];
            r[1] = p[1].exp() - p[2];
            r[2] = p[2].sqrt() - p[0];
            Ok::<(), ()>(())
        });
        let lo = x0.min(y0);
        let hi = x0.max(y0);
        let scan = all_roots::<4, ()>(lo, hi, s0 > 0.0, samples, &settings, |t| {
            Ok((t * s1).sin())
        });
        prop_assert!(scan.roots().iter().all(|r| *r >= lo && *r <= hi));
    }
}

proptest! {
    // A dense reference grid per case: fewer cases.
    #![proptest_config(config(64))]

    /// Random trigonometric polynomials of degree up to 4 over a turn, sampled 24 times, with
    /// or without a failing stretch: every sign change a dense grid (20,000 points) sees
    /// outside the stretch is found, unless another one (possibly inside the stretch) shares
    /// its grid interval (the documented miss), and every root found is one (|f| within the
    /// tolerance).
    #[test]
    fn scan_misses_only_roots_sharing_a_grid_interval(
        coefficients in prop::collection::vec(-1.0f64..1.0, 10),
        degree in 1usize..=4,
        stretch in prop::option::of((0.0f64..TAU, 0.05f64..0.8)),
    ) {
        let f = |t: f64| {
            (0..=degree)
                .map(|k| {
                    let kt = k as f64 * t;
                    coefficients[2 * k] * kt.cos() + coefficients[2 * k + 1] * kt.sin()
                })
                .sum::<f64>()
        };
        let fails = |t: f64| {
            stretch.is_some_and(|(u, w)| {
                let d = (t - u).rem_euclid(TAU);
                d > 0.0 && d < w
            })
        };
        let samples = 24;
        let scan: RootScan<16> = all_roots(0.0, TAU, true, samples, &Settings::default(), |t| {
            if fails(t) { Err(()) } else { Ok(f(t)) }
        });
        for i in 0..scan.len() {
            prop_assert!(scan.residual(i) <= 1e-10);
            prop_assert!(!fails(scan.roots()[i]));
        }
        let dense = 20_000;
        let step = TAU / f64::from(dense);
        // Sign changes where the function is defined, and all of them (those inside the
        // stretch can pair with one outside in a grid interval, hiding both).
        let mut changes = vec![];
        let mut all_changes = vec![];
        for i in 0..dense {
            let (a, b) = (step * f64::from(i), step * f64::from(i + 1));
            if f(a) * f(b) < 0.0 {
                all_changes.push(0.5 * (a + b));
                if !fails(a) && !fails(b) {
                    changes.push(0.5 * (a + b));
                }
            }
        }
        let cell = |t: f64| (t / (TAU / f64::from(samples))).floor();
        for &r in &changes {
            let found = scan.roots().iter().any(|&x| {
                let d = (x - r).abs();
                d.min(TAU - d) <= step
            });
            let shares = all_changes.iter().filter(|&&q| cell(q) == cell(r)).count() > 1;
            prop_assert!(found || shares, "{r} in {changes:?}: {:?}", scan.roots());
        }
    }
}

#[test]
fn solve_backs_off_where_the_assembly_fails() {
    // Like a circle's height over a chord: no assembly past |x| = 1. Newton from 0.5 steps to
    // 1.0 and then to 1.157, both failing, and backs off.
    let failures = Cell::new(0);
    let (x, out) = solve1(0.5, 1.0, |x| {
        if x * x >= 1.0 {
            failures.set(failures.get() + 1);
            Err(())
        } else {
            Ok((1.0 - x * x).sqrt() - 0.2)
        }
    });
    let done = out.unwrap();
    assert!(failures.get() >= 2, "{}", failures.get());
    assert!((x - 0.96f64.sqrt()).abs() <= 1e-13, "{x}: {done:?}");
    assert!(done.residual <= 1e-13);
}

proptest! {
    #![proptest_config(config(256))]

    /// A root hugging the edge of the stretch where the assembly exists, as where two circles
    /// inside an iterated region come to touch: `f = a + c sqrt(edge - x)`, failing past the
    /// edge, its root 1e-9 to 1e-6 inside it, far closer than the step a slope sets (the
    /// 3-RPR's past `l2`'s tangency is about 1e-9 in). From a start well inside, the iteration
    /// reaches it by halving failing steps down to rounding. Deeper roots are steeper than the
    /// tolerance can resolve: at 1e-12 in, `f` changes by 2e-10 over one rounding of `x`.
    #[test]
    fn a_root_beside_the_edge_of_the_assembly_is_reached(
        edge in -1.0f64..1.0,
        exponent in 6.0f64..9.0,
        c in 0.2f64..5.0,
        inside in 1e-4f64..0.3,
    ) {
        let depth = 10f64.powf(-exponent);
        let a = -c * depth.sqrt();
        let f = |x: f64| if x > edge { Err(()) } else { Ok(a + c * (edge - x).sqrt()) };
        let (x, out) = solve1(edge - inside, 1.0, f);
        let done = out.map_err(|e| TestCaseError::fail(format!("{e:?} at {x}")))?;
        prop_assert!(done.residual <= 1e-10, "{done:?}");
        prop_assert!(x <= edge && (x - (edge - depth)).abs() <= 1e-3 * depth + 4e-16, "{x}");
    }
}

#[test]
fn nan_residuals_count_as_failures() {
    // NaN past 1, as an unguarded sqrt would give.
    let (x, out) = solve1(0.5, 1.0, |x| Ok((1.0 - x * x).sqrt() - 0.2));
    assert!(out.is_ok(), "{out:?}");
    assert!((x - 0.96f64.sqrt()).abs() <= 1e-13);
    // Infinite past 1.
    let (x, out) = solve1(0.5, 1.0, |x| {
        Ok(if x >= 1.0 { f64::INFINITY } else { x - 0.9 })
    });
    assert!(out.is_ok() && (x - 0.9).abs() <= 1e-15, "{x} {out:?}");
}

#[test]
fn solve_keeps_a_bracket_where_newton_overshoots() {
    // atan from far away: plain Newton overshoots ever more; the trust region and the bracket
    // hold.
    let (x, out) = solve1(3.0, 1.0, |x| Ok(x.atan()));
    assert!(out.is_ok() && x.abs() <= 1e-15, "{x}: {out:?}");
    // The cube root: every Newton step lands twice as far on the other side (x -> -2x), so
    // only the bracket converges.
    let (x, out) = solve1(0.1, 1.0, |x| Ok(x.cbrt()));
    assert!(out.is_ok() && x.abs() <= 1e-30, "{x}: {out:?}");
    // x^3 - 2x + 2 from -1.2, with its root at -1.769.
    let f = |x: f64| x * x * x - 2.0 * x + 2.0;
    let (x, out) = solve1(-1.2, 1.0, |x| Ok(f(x)));
    assert!(out.is_ok() && f(x).abs() <= 1e-14, "{x}: {out:?}");
    // A steep root (slope 1e6) and a flat one (slope 1e-6), scale 1.
    let (x, out) = solve1(0.3, 1.0, |x| Ok(1e6 * (x - 0.25)));
    assert!(out.is_ok() && (x - 0.25).abs() <= 1e-16, "{x}: {out:?}");
    let (x, out) = solve1(0.3, 1.0, |x| Ok(1e-6 * (x - 0.25)));
    assert!(out.is_ok() && (x - 0.25).abs() <= 1e-4, "{x}: {out:?}");
}

#[test]
fn solve_settles_a_minimum_of_the_residual() {
    // |x|^0.75 + c from 0.4: Newton steps over the minimum at 0 (to -0.1) without a
    // sign change; the derivative's change of sign sends the iteration to the bottom of the
    // valley, which crosses zero: two roots at +-1e-4^(4/3), bracketed from the bottom.
    let root = 1e-4f64.powf(4.0 / 3.0);
    let (x, out) = solve1(0.4, 1.0, |x| Ok(x.abs().powf(0.75) - 1e-4));
    let done = out.unwrap();
    assert!((x.abs() - root).abs() <= 1e-18, "{x} vs {root}: {done:?}");
    // x^2 + 1e-2 from 0.5: Newton crosses 0 and back; the valley stays above zero: no root
    // near the start, its bottom 1e-2 from zero, found in a few dozen evaluations.
    let calls = Cell::new(0);
    let (x, out) = solve1(0.5, 1.0, |x| {
        calls.set(calls.get() + 1);
        Ok(x * x + 1e-2)
    });
    let residual = match out {
        Err(Failure::NoAssemblyNear { residual, .. }) => residual,
        other => panic!("{other:?}"),
    };
    assert!(
        (residual - 1e-2).abs() <= 1e-12 && x.abs() <= 1e-6,
        "{residual} {x}"
    );
    assert!(calls.get() <= 60, "{}", calls.get());
    // (x - 0.3)^2 from 0.8: Newton approaches a double root from one side, halving the error
    // each step; the residual is met within the tolerance.
    let (x, out) = solve1(0.8, 1.0, |x| Ok((x - 0.3) * (x - 0.3)));
    let done = out.unwrap();
    assert!(
        (x - 0.3).abs() <= 1e-5 && done.residual <= 1e-10,
        "{x}: {done:?}"
    );
}

#[test]
fn solve_stays_local_rather_than_jump() {
    // x^3 - 2x + 2 from 0: plain Newton cycles 0, 1, 0, ...; the damped iteration settles in
    // the local minimum of |f| at sqrt(2/3), which is not a root, and says so (no root near
    // the start) rather than jumping 1.8 to the root at -1.769 (all_roots is the global
    // search).
    let calls = Cell::new(0);
    let f = |x: f64| x * x * x - 2.0 * x + 2.0;
    let (x, out) = solve1(0.0, 1.0, |x| {
        calls.set(calls.get() + 1);
        Ok(f(x))
    });
    let bottom = (2.0f64 / 3.0).sqrt();
    match out {
        Err(Failure::NoAssemblyNear { residual, .. }) => {
            assert!((residual - f(bottom)).abs() <= 1e-12, "{residual}");
            assert!((x - bottom).abs() <= 1e-6, "{x}");
        }
        other => panic!("{other:?}"),
    }
    assert!(calls.get() <= 40, "{}", calls.get());
}

#[test]
fn scale_bounds_the_steps() {
    // Roots at 0 and 10 of x (x - 10); from 4 the Newton step is long (-8). With scale 1 every
    // step is at most 0.5 (and a difference step of 1.5e-8 on top, between calls).
    let calls = Cell::new(0);
    let mut largest_step: f64 = 0.0;
    let mut last = 4.0;
    let mut x = [4.0];
    let out = solve(&mut x, &[1.0], &Settings::default(), |p, r| {
        calls.set(calls.get() + 1);
        largest_step = largest_step.max((p[0] - last).abs());
        last = p[0];
        r[0] = p[0] * (p[0] - 10.0);
        Ok::<(), ()>(())
    });
    assert!(out.is_ok(), "{out:?}");
    assert!(x[0].abs() <= 1e-15, "{x:?}");
    assert!(largest_step <= 0.5 + 1e-7, "{largest_step}");
}

#[test]
fn no_root_is_no_assembly_near_within_the_budget() {
    let calls = Cell::new(0u32);
    let (x, out) = solve1(0.7, 1.0, |x| {
        calls.set(calls.get() + 1);
        Ok(x * x + 1.0)
    });
    match out {
        Err(Failure::NoAssemblyNear { residual, .. }) => {
            assert!((1.0..1.0 + 1e-12).contains(&residual), "{residual}");
            assert!(x.abs() < 1e-6, "{x}");
        }
        other => panic!("{other:?}"),
    }
    // Found to be a minimum of |f| that is not a root, well within the budget.
    assert!(calls.get() <= 60, "{}", calls.get());
    // Two defaults: a minimum of the norm that is not a root, confirmed by the test for one
    // (its own budget: 200 more at most), and its bottom, 1, to the test's precision.
    calls.set(0);
    let mut x = [0.4, -0.3];
    let out = solve(&mut x, &[1.0, 1.0], &Settings::default(), |p, r| {
        calls.set(calls.get() + 1);
        r[0] = p[0] * p[0] + 1.0;
        r[1] = p[1];
        Ok::<(), ()>(())
    });
    match out {
        Err(Failure::NoAssemblyNear { residual, .. }) => {
            assert!((1.0..1.0 + 1e-6).contains(&residual), "{residual}");
        }
        other => panic!("{other:?}"),
    }
    assert!(calls.get() <= 400);
    // A small budget is respected exactly by the iteration, and by the test for a minimum.
    calls.set(0);
    let mut x = [0.7];
    let settings = Settings {
        tolerance: 1e-10,
        max_evaluations: 7,
        ..Settings::default()
    };
    let out = solve(&mut x, &[1.0], &settings, |p, r| {
        calls.set(calls.get() + 1);
        r[0] = p[0] * p[0] + 1.0;
        Ok::<(), ()>(())
    });
    assert!(
        matches!(
            out,
            Err(Failure::NoConvergence { .. } | Failure::NoAssemblyNear { .. })
        ),
        "{out:?}"
    );
    assert!(calls.get() <= 14);
}

#[test]
fn failing_start_is_reported_with_its_error() {
    let calls = Cell::new(0);
    let mut x = [2.0];
    let out = solve(&mut x, &[1.0], &Settings::default(), |_, _| {
        calls.set(calls.get() + 1);
        Err("circles miss")
    });
    assert_eq!(out, Err(Failure::Start("circles miss")));
    // One default: the start, then 24 probes out to half a scale on either side.
    assert_eq!(calls.get(), 25);
    assert_eq!(x, [2.0]);
    let mut x = [2.0, 1.0, 0.0];
    let out = solve(&mut x, &[1.0; 3], &Settings::default(), |_, _| {
        Err("no gap")
    });
    assert_eq!(out, Err(Failure::Start("no gap")));
    // A NaN residual at the start has no error to report.
    let out = solve(&mut [1.0], &[1.0], &Settings::default(), |_, r| {
        r[0] = f64::NAN;
        Ok::<(), ()>(())
    });
    assert!(
        matches!(out, Err(Failure::NoConvergence { residual, iterations: 0 }) if residual.is_nan())
    );
}

/// A start just outside the stretch where the assembly exists (a sweep's last answer, one
/// step on) moves to the nearest point where it does, and converges there, on the root of
/// that stretch; a stretch more than half a scale away is still a failed start.
#[test]
fn a_start_just_outside_the_assembly_steps_back_in() {
    // Defined on [0, 1] only, root at 0.999: the start 1.0001 fails.
    let f = |x: &[f64; 1], r: &mut [f64; 1]| {
        if (0.0..=1.0).contains(&x[0]) {
            r[0] = x[0] - 0.999;
            Ok(())
        } else {
            Err("the circles miss")
        }
    };
    let mut x = [1.0001];
    let done = solve(&mut x, &[1.0], &Settings::default(), f).expect("steps back in");
    assert!((x[0] - 0.999).abs() < 1e-13, "{x:?} {done:?}");
    let mut x = [1.7];
    assert_eq!(
        solve(&mut x, &[1.0], &Settings::default(), f),
        Err(Failure::Start("the circles miss"))
    );
}

#[test]
fn no_defaults_is_one_evaluation() {
    let mut x: [f64; 0] = [];
    let done = solve(&mut x, &[], &Settings::default(), |_, _| Ok::<(), ()>(()));
    assert_eq!(
        done,
        Ok(Converged {
            iterations: 0,
            evaluations: 1,
            residual: 0.0
        })
    );
    let failed = solve(&mut x, &[], &Settings::default(), |_, _| Err("no assembly"));
    assert_eq!(failed, Err(Failure::Start("no assembly")));
}

#[test]
fn converged_start_is_polished() {
    // Within the tolerance at the start: a slope and a step take it to rounding level.
    let (x, out) = solve1(0.25 + 3e-11, 1.0, |x| Ok(x - 0.25));
    let done = out.unwrap();
    assert!((x - 0.25).abs() <= 1e-16, "{x}");
    assert!(done.evaluations <= 4, "{done:?}");
    assert_eq!(done.residual, 0.0);
}

#[test]
fn an_answer_at_rounding_level_is_not_polished() {
    // A start within rounding of the root: converged at once, with no step; one a little
    // further (within the tolerance, above rounding) is still polished.
    let settings = Settings::for_size(10.0);
    assert_eq!(settings.tolerance, 1e-12 * 11.0);
    assert_eq!(settings.rounding, 2.0 * f64::EPSILON * 11.0);
    let run = |x0: f64| {
        let mut x = [x0];
        let out = solve(&mut x, &[1.0], &settings, |p, r| {
            r[0] = 3.0 * (p[0] - 0.25);
            Ok::<(), ()>(())
        });
        (x[0], out.unwrap())
    };
    let (x, done) = run(0.25 + 1e-15);
    assert_eq!((x, done.evaluations, done.iterations), (0.25 + 1e-15, 1, 0));
    let (x, done) = run(0.25 + 1e-12);
    assert!(
        (x - 0.25).abs() <= 1e-16 && done.evaluations >= 2,
        "{x} {done:?}"
    );
    // With `rounding` zero (the default), the first start is polished too.
    let (x, done) = solve1(0.25 + 1e-15, 1.0, |x| Ok(3.0 * (x - 0.25)));
    assert!((x - 0.25).abs() <= 1e-16 && done.unwrap().evaluations >= 2);
}

#[test]
fn two_circles_stay_on_the_branch_of_the_start() {
    let circles = |p: &[f64; 2], r: &mut [f64; 2]| {
        r[0] = p[0] * p[0] + p[1] * p[1] - 4.0;
        r[1] = (p[0] - 2.0) * (p[0] - 2.0) + p[1] * p[1] - 4.0;
        Ok::<(), ()>(())
    };
    let s3 = 3f64.sqrt();
    for (start, root) in [
        ([0.5, 1.0], [1.0, s3]),
        ([1.2, -0.4], [1.0, -s3]),
        ([1.9, 0.3], [1.0, s3]),
        ([0.2, -2.5], [1.0, -s3]),
    ] {
        let mut x = start;
        let done = solve(&mut x, &[2.0, 2.0], &Settings::default(), circles).unwrap();
        assert!(
            (x[0] - root[0]).abs() <= 1e-15 && (x[1] - root[1]).abs() <= 4e-16,
            "{start:?}: {x:?} vs {root:?}: {done:?}"
        );
        assert!(done.residual <= 1e-15, "{done:?}");
    }
}

#[test]
fn three_equations_converge_to_the_nearby_root() {
    // Root (1, 2, 3): a sphere, a product, an exponential.
    let system = |p: &[f64; 3], r: &mut [f64; 3]| {
        let [x, y, z] = *p;
        r[0] = x * x + y * y + z * z - 14.0;
        r[1] = x * y - 2.0 + z - 3.0;
        r[2] = (x - 1.0).exp() + y * z - 7.0;
        Ok::<(), ()>(())
    };
    for start in [[1.2, 2.2, 2.8], [0.8, 1.7, 3.3], [1.3, 2.0, 3.0]] {
        let mut x = start;
        let done = solve(&mut x, &[1.0; 3], &Settings::default(), system).unwrap();
        let error = (x[0] - 1.0)
            .abs()
            .max((x[1] - 2.0).abs())
            .max((x[2] - 3.0).abs());
        assert!(error <= 1e-14, "{start:?}: {x:?}: {done:?}");
        assert!(done.residual <= 1e-14, "{done:?}");
    }
}

#[test]
fn system_backs_off_where_the_assembly_fails() {
    // The circles' system, failing left of x = 0.9 (the solution is at x = 1): a start at
    // (1.5, 1.0) whose first Newton step lands at x < 0.9 backs off.
    let failures = Cell::new(0);
    let mut x = [1.6, 1.0];
    let done = solve(&mut x, &[2.0, 2.0], &Settings::default(), |p, r| {
        if p[0] < 0.9 {
            failures.set(failures.get() + 1);
            return Err(());
        }
        r[0] = p[0] * p[0] + p[1] * p[1] - 4.0;
        r[1] = (p[0] - 2.0) * (p[0] - 2.0) + p[1] * p[1] - 4.0;
        Ok(())
    })
    .unwrap();
    assert!(
        (x[0] - 1.0).abs() <= 1e-15 && (x[1] - 3f64.sqrt()).abs() <= 1e-15,
        "{x:?}: {done:?}"
    );
}

#[test]
fn scan_finds_roots_on_both_sides_of_a_failing_stretch_and_at_its_edge() {
    // Defined except on (0.2, 0.7): roots at -0.8, 1.2, and 0.7, the edge of the failing
    // stretch, where the assembly would become tangent.
    let f = |x: f64| {
        if x > 0.2 && x < 0.7 {
            Err("no assembly")
        } else {
            Ok((x + 0.8) * (x - 0.7) * (x - 1.2))
        }
    };
    let scan: RootScan<8> = all_roots(-1.0, 1.5, false, 24, &Settings::default(), f);
    assert_eq!(scan.roots().len(), 3, "{scan:?}");
    assert!((scan.roots()[0] + 0.8).abs() <= 1e-15, "{scan:?}");
    assert_eq!(scan.roots()[1], 0.7, "{scan:?}");
    assert!((scan.roots()[2] - 1.2).abs() <= 1e-15, "{scan:?}");
    assert!(scan.is_boundary(1) && !scan.is_boundary(0) && !scan.is_boundary(2));
    // A stretch failing up to the end, with the residual reaching zero at its edge as an
    // assembly that becomes tangent does (the kernel snaps the last point to the tangency):
    // found, flagged as a boundary root.
    let tangent = |x: f64| if x > 0.55 { Err(()) } else { Ok(0.55 - x) };
    let scan: RootScan<4> = all_roots(0.0, 1.0, false, 16, &Settings::default(), tangent);
    assert_eq!(scan.roots().len(), 1, "{scan:?}");
    assert!(
        (scan.roots()[0] - 0.55).abs() <= 1e-15 && scan.is_boundary(0),
        "{scan:?}"
    );
    // A failing stretch whose edge is not a root: nothing there.
    let gap = |x: f64| if x > 0.55 { Err(()) } else { Ok(x + 1.0) };
    let scan: RootScan<4> = all_roots(0.0, 1.0, false, 16, &Settings::default(), gap);
    assert!(scan.is_empty(), "{scan:?}");
}

/// A crank of length 1 about the origin at angle `theta`, a coupler of length 1.5 from its tip,
/// a rocker of length 1 about (3, 0): the joint `b` of coupler and rocker (branch 0), and the
/// closing residual `b.y - target`. The assembly fails where the crank tip is more than 2.5
/// from the rocker's pivot (`cos theta < 0.625`), as a plan's would.
fn four_bar(theta: f64, target: f64) -> Result<f64, SolveError> {
    let tip = P2::new(theta.cos(), theta.sin());
    let coupler = Circle::new(tip, 1.5)
        .ok_or_else(|| SolveError::new("c", "", ErrorKind::InvalidValue, 0.0))?;
    let rocker = Circle::new(P2::new(3.0, 0.0), 1.0)
        .ok_or_else(|| SolveError::new("r", "", ErrorKind::InvalidValue, 0.0))?;
    let meeting = circle_circle(&coupler, &rocker);
    if let Some(e) = SolveError::from_contact("joint", "", meeting.contact) {
        return Err(e);
    }
    match meeting.roots.get(0) {
        Some(b) => Ok(b.y - target),
        None => Err(SolveError::new("joint", "", ErrorKind::NoIntersection, 0.0)),
    }
}

#[test]
fn four_bar_closures_through_the_kernel() {
    let settings = Settings::default();
    // The tangent configuration, where the assembly stops: the crank at acos(0.625), the joint
    // on the line of the crank tip and the pivot.
    let edge = 0.625f64.acos();
    let tangent_y = 0.4 * edge.sin();
    for target in [0.2, -0.1, tangent_y] {
        let scan: RootScan<8> = all_roots(-PI, PI, true, 32, &settings, |t| four_bar(t, target));
        assert!(!scan.is_empty(), "{target}: {scan:?}");
        for (i, &r) in scan.roots().iter().enumerate() {
            let residual = four_bar(r, target).map(f64::abs);
            assert!(
                residual.as_ref().is_ok_and(|v| *v <= 1e-13),
                "{target}: {r}: {residual:?}"
            );
            // solve from a nearby start converges to the same root, not the other.
            if !scan.is_boundary(i) && !scan.is_double(i) {
                let mut x = [r + 0.02];
                let done = solve(&mut x, &[1.0], &settings, |p, out| {
                    out[0] = four_bar(p[0], target)?;
                    Ok::<(), SolveError>(())
                });
                assert!(
                    done.is_ok() && (x[0] - r).abs() <= 1e-13,
                    "{r}: {x:?} {done:?}"
                );
            }
        }
        // Against a dense grid: every sign change where the assembly holds is found.
        let dense = 20_000;
        for k in 0..dense {
            let a = -PI + TAU * f64::from(k) / f64::from(dense);
            let b = a + TAU / f64::from(dense);
            if let (Ok(fa), Ok(fb)) = (four_bar(a, target), four_bar(b, target)) {
                if fa * fb < 0.0 {
                    let found = scan
                        .roots()
                        .iter()
                        .any(|&r| r >= a - 1e-12 && r <= b + 1e-12);
                    assert!(found, "{target}: a sign change in [{a}, {b}]: {scan:?}");
                }
            }
        }
    }
    // The target met exactly at the tangency: a root at the edge of the failing stretch,
    // where the kernel's snap to tangency keeps the residual within the tolerance.
    let scan: RootScan<8> = all_roots(-PI, PI, true, 32, &settings, |t| four_bar(t, tangent_y));
    let at_edge = (0..scan.len()).find(|&i| (scan.roots()[i] - edge).abs() <= 1e-6);
    assert!(at_edge.is_some_and(|i| scan.is_boundary(i)), "{scan:?}");
}

#[test]
fn double_roots_survive_rounding_noise() {
    // (x - 0.3)^2 (x + 0.6) expanded: near 0.3 Horner's rule gives values of either sign at
    // the level of rounding, a dip far within the tolerance: one double root.
    let (a, b) = (0.3, -0.6);
    let coeffs = [1.0, -(2.0 * a + b), a * a + 2.0 * a * b, -a * a * b];
    let scan: RootScan<4> = all_roots(-1.0, 1.0, false, 40, &Settings::default(), |x| {
        Ok::<f64, ()>(coeffs.iter().fold(0.0, |p, c| p * x + c))
    });
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert!(
        (scan.roots()[0] - b).abs() <= 1e-14 && !scan.is_double(0),
        "{scan:?}"
    );
    assert!(
        (scan.roots()[1] - a).abs() <= 1e-6 && scan.is_double(1),
        "{scan:?}"
    );
}

#[test]
fn periodic_scan_of_cos_3t() {
    let scan: RootScan<8> = all_roots(0.0, TAU, true, 32, &Settings::default(), |t| {
        Ok::<f64, ()>((3.0 * t).cos() - 0.5)
    });
    let expected = [1.0, 5.0, 7.0, 11.0, 13.0, 17.0].map(|k| k * PI / 9.0);
    assert_eq!(scan.roots().len(), 6, "{scan:?}");
    for (i, (r, e)) in scan.roots().iter().zip(expected).enumerate() {
        assert!((r - e).abs() <= 1e-14, "{r} vs {e}");
        assert!(!scan.is_double(i) && !scan.is_boundary(i));
    }
    // Degree 3: at most 6 roots a turn, and 6 were found, so all of them.
    assert!(!scan.truncated());
    // With a failing stretch across the wrap, [2 pi - 0.2, 2 pi) and [0, 0.15): the same.
    let scan: RootScan<8> = all_roots(0.0, TAU, true, 32, &Settings::default(), |t| {
        if !(0.15..TAU - 0.2).contains(&t) {
            Err(())
        } else {
            Ok((3.0 * t).cos() - 0.5)
        }
    });
    assert_eq!(scan.roots().len(), 6, "{scan:?}");
    for (r, e) in scan.roots().iter().zip(expected) {
        assert!((r - e).abs() <= 1e-14, "{r} vs {e}");
    }
    // Too small a list keeps the smallest roots, and says so.
    let two: RootScan<2> = all_roots(0.0, TAU, true, 32, &Settings::default(), |t| {
        Ok::<f64, ()>((3.0 * t).cos() - 0.5)
    });
    assert!(two.truncated());
    assert_eq!(two.roots(), &scan.roots()[..2]);
}

#[test]
fn a_root_at_the_wrap_is_found_once() {
    let settings = Settings::default();
    let h = TAU / 16.0;
    // Exactly at the first sample.
    let scan: RootScan<4> = all_roots(0.0, TAU, true, 16, &settings, |t| Ok::<f64, ()>(t.sin()));
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert_eq!(scan.roots()[0], 0.0);
    assert!((scan.roots()[1] - PI).abs() <= 1e-15);
    // At the wrap of [-pi, pi), where sin(-pi) is -1.2e-16 rather than 0.
    let scan: RootScan<4> = all_roots(-PI, PI, true, 16, &settings, |t| Ok::<f64, ()>(t.sin()));
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert!(scan.roots()[1].abs() <= 1e-15, "{scan:?}");
    assert!((scan.roots()[0].abs() - PI).abs() <= 1e-15, "{scan:?}");
    // Between the last sample and the wrap, and a tiny bit before the wrap.
    for shift in [0.5 * h, 1e-13] {
        let scan: RootScan<4> = all_roots(0.0, TAU, true, 16, &settings, |t| {
            Ok::<f64, ()>((t + shift).sin())
        });
        assert_eq!(scan.roots().len(), 2, "{shift}: {scan:?}");
        assert!(
            (scan.roots()[1] - (TAU - shift)).abs() <= 1e-14,
            "{shift}: {scan:?}"
        );
        assert!(
            (scan.roots()[0] - (PI - shift)).abs() <= 1e-14,
            "{shift}: {scan:?}"
        );
    }
    // An interval that does not start at 0, where lo + (hi - lo) rounds: roots at pi and
    // 2 pi, and one exactly at lo.
    let scan: RootScan<4> = all_roots(0.1, 0.1 + TAU, true, 16, &settings, |t| {
        Ok::<f64, ()>(t.sin())
    });
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert!((scan.roots()[0] - PI).abs() <= 1e-15 && (scan.roots()[1] - TAU).abs() <= 1e-15);
    let scan: RootScan<4> = all_roots(0.1, 0.1 + TAU, true, 16, &settings, |t| {
        Ok::<f64, ()>((t - 0.1).sin())
    });
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert!(scan.roots()[0] == 0.1 && (scan.roots()[1] - 0.1 - PI).abs() <= 1e-15);
    // A double root at the wrap, on a sample and between the last sample and the first.
    for shift in [0.0, 0.5 * h, 0.3 * h] {
        let scan: RootScan<4> = all_roots(0.0, TAU, true, 16, &settings, |t| {
            Ok::<f64, ()>(1.0 - (t + shift).cos())
        });
        assert_eq!(scan.roots().len(), 1, "{shift}: {scan:?}");
        let r = scan.roots()[0];
        let distance = (r - (TAU - shift)).abs().min((r + shift).abs());
        assert!(distance <= 1e-6 && scan.is_double(0), "{shift}: {scan:?}");
    }
}

#[test]
fn poles_are_not_roots() {
    // tan changes sign across its poles, where the bracket collapses with |f| huge.
    let scan: RootScan<8> = all_roots(0.0, TAU, true, 20, &Settings::default(), |t| {
        Ok::<f64, ()>(t.tan())
    });
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    assert!(
        scan.roots()[0] == 0.0 && (scan.roots()[1] - PI).abs() <= 1e-15,
        "{scan:?}"
    );
    let scan: RootScan<8> = all_roots(-1.0, 1.0, false, 20, &Settings::default(), |x| {
        Ok::<f64, ()>(1.0 / (x - 0.123))
    });
    assert!(scan.is_empty(), "{scan:?}");
}

#[test]
fn scan_of_an_empty_or_invalid_interval_is_empty() {
    let settings = Settings::default();
    for (lo, hi) in [
        (1.0, 1.0),
        (2.0, 1.0),
        (f64::NAN, 1.0),
        (0.0, f64::INFINITY),
        (-1e308, 1e308),
    ] {
        let scan: RootScan<4> = all_roots(lo, hi, false, 16, &settings, Ok::<f64, ()>);
        assert!(
            scan.is_empty() && scan.evaluations() == 0,
            "{lo} {hi}: {scan:?}"
        );
    }
    // A function that fails everywhere, or is NaN everywhere.
    let scan: RootScan<4> = all_roots(0.0, 1.0, true, 16, &settings, |_| Err::<f64, ()>(()));
    assert!(scan.is_empty());
    let scan: RootScan<4> = all_roots(0.0, 1.0, false, 16, &settings, |_| Ok::<f64, ()>(f64::NAN));
    assert!(scan.is_empty());
    // Out-of-range indices answer, not panic.
    assert!(!scan.is_double(3) && !scan.is_boundary(9) && scan.residual(0).is_nan());
}

/// Measured costs on the test problems, printed with `--nocapture`, and bounded so that a
/// slower method shows.
#[test]
fn evaluation_counts() {
    let settings = Settings::default();
    let count = |f: &dyn Fn(f64) -> f64, x0: f64| {
        let mut x = [x0];
        solve(&mut x, &[1.0], &settings, |p, r| {
            r[0] = f(p[0]);
            Ok::<(), ()>(())
        })
        .unwrap()
        .evaluations
    };
    let cubic = count(&|x| (x + 0.7) * (x - 0.4) * (x - 1.3), 0.5);
    let sqrt = count(&|x| (1.0 - x * x).sqrt() - 0.2, 0.5);
    let cos = count(&|t| (3.0 * t).cos() - 0.5, 0.3);
    let mut x = [0.5, 1.0];
    let circles = solve(&mut x, &[2.0, 2.0], &settings, |p, r| {
        r[0] = p[0] * p[0] + p[1] * p[1] - 4.0;
        r[1] = (p[0] - 2.0) * (p[0] - 2.0) + p[1] * p[1] - 4.0;
        Ok::<(), ()>(())
    })
    .unwrap();
    let mut x = [1.2, 2.2, 2.8];
    let three = solve(&mut x, &[1.0; 3], &settings, |p, r| {
        let [x, y, z] = *p;
        r[0] = x * x + y * y + z * z - 14.0;
        r[1] = x * y - 2.0 + z - 3.0;
        r[2] = (x - 1.0).exp() + y * z - 7.0;
        Ok::<(), ()>(())
    })
    .unwrap();
    let scan: RootScan<8> = all_roots(0.0, TAU, true, 32, &settings, |t| {
        Ok::<f64, ()>((3.0 * t).cos() - 0.5)
    });
    let poly: RootScan<8> = all_roots(-1.5, 1.5, false, 64, &settings, |x| {
        Ok::<f64, ()>(product(1.0, &[-1.1, 0.2, 1.3], &[-0.5], x))
    });
    let stretch: RootScan<8> = all_roots(-1.0, 1.5, false, 24, &settings, |x| {
        if x > 0.2 && x < 0.7 {
            Err(())
        } else {
            Ok((x + 0.8) * (x - 0.7) * (x - 1.2))
        }
    });
    let calls = Cell::new(0);
    let no_root = solve(&mut [0.7], &[1.0], &settings, |p, r| {
        calls.set(calls.get() + 1);
        r[0] = p[0] * p[0] + 1.0;
        Ok::<(), ()>(())
    });
    assert!(no_root.is_err());
    eprintln!(
        "evaluations: solve, one default: cubic {cubic}, sqrt with failures {sqrt}, cos 3t \
         {cos}, x^2 + 1 (no root) {}; two circles {} ({} steps), 3x3 {} ({} steps); \
         all_roots: cos 3t {} (32 samples), quintic with a double root {} (64 samples), cubic \
         with a failing stretch {} (24 samples)",
        calls.get(),
        circles.evaluations,
        circles.iterations,
        three.evaluations,
        three.iterations,
        scan.evaluations(),
        poly.evaluations(),
        stretch.evaluations(),
    );
    assert!(
        cubic <= 14 && sqrt <= 20 && cos <= 14 && calls.get() <= 60,
        "{cubic} {sqrt} {cos} {}",
        calls.get()
    );
    assert!(circles.evaluations <= 25 && three.evaluations <= 30);
    assert!(scan.evaluations() <= 32 + 6 * 12, "{}", scan.evaluations());
    assert!(
        poly.evaluations() <= 64 + 3 * 12 + 40,
        "{}",
        poly.evaluations()
    );
    assert!(
        stretch.evaluations() <= 24 + 2 * 60 + 2 * 12,
        "{}",
        stretch.evaluations()
    );
}

/// The distance of `(cos t, sin t, 0.3 t)`, a point a default moves along a helix, from the line
/// through `(cos r, sin r, 0.3 r)` along `(1, 2, 0.5)`: a magnitude, V-shaped at its root `r`.
fn helix_line_distance(t: f64, r: f64) -> f64 {
    let p = [t.cos(), t.sin(), 0.3 * t];
    let q = [r.cos(), r.sin(), 0.3 * r];
    let d = [1.0f64, 2.0, 0.5];
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let e = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let c = [
        (e[1] * d[2] - e[2] * d[1]) / n,
        (e[2] * d[0] - e[0] * d[2]) / n,
        (e[0] * d[1] - e[1] * d[0]) / n,
    ];
    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
}

#[test]
fn a_magnitude_is_polished_past_the_bottom_of_its_v() {
    // A residual that is a distance has no sign: secant steps across its root see a slope of
    // about zero. The polish must still end at rounding level, from either side and from
    // starts near and far.
    let settings = Settings::for_size(1.0);
    for (r, x0) in [
        (0.7, 0.9),
        (0.7, 0.5),
        (0.7, 0.7 + 1e-7),
        (-2.0, -1.2),
        (1.3, 1.3 - 3e-3),
        (0.2, 0.2 + 0.4),
    ] {
        let mut x = [x0];
        let out = solve(&mut x, &[1.0], &settings, |p, res| {
            res[0] = helix_line_distance(p[0], r);
            Ok::<(), ()>(())
        })
        .unwrap();
        assert!(
            out.residual <= 4.0 * f64::EPSILON && (x[0] - r).abs() <= 1e-15,
            "root {r} from {x0}: {:e} off, {out:?}",
            x[0] - r
        );
    }
}

#[test]
fn a_magnitude_is_solved_when_a_step_crosses_its_root_early() {
    // `|g|` for a `g` that bends toward zero: Newton's first step from the right lands past
    // the root, where the magnitude rises again: far outside the tolerance from the first
    // starts, within it (1e-12 past) from the last ones, where the secant through the two
    // points then steps the wrong way.
    let settings = Settings::for_size(1.0);
    for (r, x0) in [
        (0.4, 0.5),
        (0.4, 0.45),
        (-1.0, -0.8),
        (2.0, 2.3),
        (0.4, 0.4 + 1e-6),
        (0.4, 0.4 + 1.5e-6),
        (-1.0, -1.0 + 1.2e-6),
    ] {
        let g = |t: f64| (t - r) - 0.5 * (t - r) * (t - r);
        let mut x = [x0];
        let out = solve(&mut x, &[1.0], &settings, |p, res| {
            res[0] = g(p[0]).abs();
            Ok::<(), ()>(())
        });
        let out = out.unwrap_or_else(|e| panic!("root {r} from {x0}: {e:?} at {}", x[0]));
        assert!(
            out.residual <= 4.0 * f64::EPSILON && (x[0] - r).abs() <= 1e-15,
            "root {r} from {x0}: {:e} off, {out:?}",
            x[0] - r
        );
    }
}

#[test]
fn a_scan_finds_the_roots_of_a_magnitude() {
    // The distance of a point turning on a circle from a line through the circle's plane's
    // axis: `|sin(t - 0.3)|`, times a radius, with a slope on both sides of each root and no
    // sign change. Each bottom is a V, which a minimization alone finds only to about
    // sqrt(eps), its residual then far above the tolerance.
    let scan: RootScan<4> = all_roots(-PI, PI, true, 24, &Settings::default(), |t| {
        Ok::<f64, ()>(2.0 * (t - 0.3).sin().abs())
    });
    let expected = [0.3 - PI, 0.3];
    assert_eq!(scan.roots().len(), 2, "{scan:?}");
    for (i, (r, e)) in scan.roots().iter().zip(expected).enumerate() {
        assert!((r - e).abs() <= 1e-14, "{r} vs {e}");
        assert!(scan.residual(i) <= 1e-15, "{scan:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// What a failure says: no assembly at all, none near the start, or no convergence.

/// `2 + cos t` has no root over the turn: an angle's iteration (`Span::Turn`) says no assembly
/// exists, by its least value over the turn, 1 (at `t = pi`), wherever it starts; without a
/// span it can only say none is near (the bottom of the valley it came to, the same 1 here).
#[test]
fn no_root_over_the_turn_is_no_assembly_by_the_least_error() {
    let f = |t: f64| 2.0 + t.cos();
    for x0 in [0.3, -2.0, 3.0, 7.5] {
        let mut x = [x0];
        let settings = Settings::default().spanning(Span::Turn);
        let out = solve(&mut x, &[1.0], &settings, |p, r| {
            r[0] = f(p[0]);
            Ok::<(), ()>(())
        });
        match out {
            Err(Failure::NoAssembly { least, .. }) => {
                assert!((least - 1.0).abs() <= 1e-14, "from {x0}: {least}");
            }
            other => panic!("from {x0}: {other:?}"),
        }
        let mut x = [x0];
        let out = solve(&mut x, &[1.0], &Settings::default(), |p, r| {
            r[0] = f(p[0]);
            Ok::<(), ()>(())
        });
        match out {
            Err(Failure::NoAssemblyNear { residual, .. }) => {
                assert!((residual - 1.0).abs() <= 1e-14, "from {x0}: {residual}");
            }
            other => panic!("from {x0}: {other:?}"),
        }
    }
    // The kinds and magnitudes the back ends report.
    let failure: Failure<SolveError> = Failure::NoAssembly {
        least: 1.0,
        iterations: 3,
    };
    assert_eq!(failure.kind(), Some((ErrorKind::NoAssembly, 1.0)));
    let e = failure.into_error("l3", "distance(B3, p3) = leg3");
    assert_eq!((e.kind, e.magnitude), (ErrorKind::NoAssembly, 1.0));
    let start: Failure<SolveError> = Failure::Start(e.clone());
    assert_eq!(start.kind(), None);
    assert_eq!(start.into_error("x", "y"), e);
}

/// `0.1 + 2 s (1 - 1.5 s)` with `s = sin^2(t/2)`: a valley about `t = 0` whose bottom is 0.1,
/// and roots at `t = +-2.01` on the same turn. From 0.3 the iteration comes to the bottom of
/// the valley; the turn holds roots, so the failure is no assembly near the start (not none at
/// all), by the bottom, with or without the turn searched.
#[test]
fn a_root_elsewhere_on_the_turn_is_no_assembly_near_the_start() {
    let f = |t: f64| {
        let s = (0.5 * t).sin().powi(2);
        0.1 + 2.0 * s * (1.0 - 1.5 * s)
    };
    let scan: RootScan<4> = all_roots(-PI, PI, true, 720, &Settings::default(), |t| {
        Ok::<f64, ()>(f(t))
    });
    assert_eq!(scan.len(), 2, "{scan:?}");
    for span in [Span::Turn, Span::Unknown] {
        let mut x = [0.3];
        let settings = Settings::default().spanning(span);
        let out = solve(&mut x, &[1.0], &settings, |p, r| {
            r[0] = f(p[0]);
            Ok::<(), ()>(())
        });
        match out {
            Err(Failure::NoAssemblyNear { residual, .. }) => {
                assert!((residual - 0.1).abs() <= 1e-15, "{span:?}: {residual}");
            }
            other => panic!("{span:?}: {other:?}"),
        }
        assert!(
            x[0].abs() < 1e-3,
            "the best point reached, in the valley: {x:?}"
        );
    }
}

/// A fold of two defaults: the parabola `y = x^2` and the line `y = -c` meet in two points for
/// `c < 0`, touch at `c = 0`, and miss for `c > 0`, where the residuals `(y - x^2, y + c)` have
/// a minimum of norm `c / sqrt 2` at `(0, -c/2)` whose Jacobian is singular (the fold). A
/// sweep of `c` from -0.01, each solve from the last answer, converges up to the fold, and past
/// it says no assembly is near, by that norm; the Gauss-Newton curvature alone, singular there,
/// could not tell.
#[test]
fn a_fold_of_two_defaults_is_no_assembly_near_by_the_least_norm() {
    let mut x = [0.2, 0.03];
    for k in 0..=6 {
        let c = -0.01 + 0.004 * f64::from(k);
        let out = solve(&mut x, &[1.0, 1.0], &Settings::default(), |p, r| {
            r[0] = p[1] - p[0] * p[0];
            r[1] = p[1] + c;
            Ok::<(), ()>(())
        });
        if c < 0.0 {
            let done = out.unwrap_or_else(|e| panic!("c = {c}: {e:?}"));
            assert!(done.residual <= 1e-15, "c = {c}: {done:?}");
            assert!((x[0] - (-c).sqrt()).abs() <= 1e-12, "c = {c}: {x:?}");
            continue;
        }
        match out {
            Err(Failure::NoAssemblyNear { residual, .. }) => {
                let least = c / 2.0f64.sqrt();
                assert!(
                    (residual - least).abs() <= 1e-12 * least.max(1e-3),
                    "c = {c}: {residual} vs {least}"
                );
            }
            other => panic!("c = {c}: {other:?}"),
        }
        // The answer is not taken from elsewhere: `x` is the best point the iteration reached.
        assert!(x[0].abs() < 0.2, "c = {c}: {x:?}");
        break;
    }
}

/// A root within reach that the budget does not reach: the test for a minimum, on the same
/// budget, goes downhill toward it and confirms no bottom, so the failure stays no convergence
/// (with the best residual the iteration reached); so does one whose budget cannot take a
/// single Newton step of the test.
#[test]
fn a_budget_short_of_a_root_stays_no_convergence() {
    for limit in [12, 5] {
        let settings = Settings {
            max_evaluations: limit,
            ..Settings::default()
        };
        let mut x = [0.0, 0.0];
        let out = solve(&mut x, &[1.0, 1.0], &settings, |p, r| {
            r[0] = p[0] - 3.0;
            r[1] = p[1] - 3.0 + 0.1 * p[0] * p[0];
            Ok::<(), ()>(())
        });
        assert!(
            matches!(out, Err(Failure::NoConvergence { residual, .. }) if residual > 1.0),
            "budget {limit}: {out:?}"
        );
    }
}

/// Fails where two loci miss, with the gap they miss by: an assembly's error outside its
/// stretch.
fn missing(gap: f64) -> SolveError {
    SolveError::new("c", "", ErrorKind::NoIntersection, gap)
}

/// Loci that meet only over a stretch narrower than the grid's spacing (a circle grazing a
/// sphere as the default turns), with two roots inside: the failing samples' gaps dip toward
/// it, and the window between them is found and swept, wherever it sits between the samples.
#[test]
fn a_window_narrower_than_the_grid_is_found_by_its_gaps() {
    let spacing = TAU / 64.0;
    for k in 0..40 {
        let c = -3.0 + 6.0 * f64::from(k) / 40.0 + 0.013 * f64::from(k % 7);
        let w = 0.15 * spacing;
        let (r1, r2) = (c - 0.5 * w, c + 0.3 * w);
        let scan: RootScan<8> = all_roots(-PI, PI, true, 64, &Settings::default(), |t| {
            let d = num_wrap(t - c).abs();
            if d >= w {
                Err(missing(d - w + 1e-3))
            } else {
                Ok((t - r1) * (t - r2))
            }
        });
        assert_eq!(scan.roots().len(), 2, "window at {c}: {scan:?}");
        assert!((scan.roots()[0] - r1).abs() <= 1e-12, "{scan:?}");
        assert!((scan.roots()[1] - r2).abs() <= 1e-12, "{scan:?}");
    }
}

/// The same window without gaps (a failure that says nothing of how far): not found, as the
/// module documentation says; an empty scan, no invented root.
#[test]
fn a_window_between_failures_without_gaps_stays_unseen() {
    let spacing = TAU / 64.0;
    let (c, w) = (0.4 + 0.37 * spacing, 0.15 * spacing);
    let scan: RootScan<8> = all_roots(-PI, PI, true, 64, &Settings::default(), |t| {
        if (t - c).abs() >= w {
            Err(())
        } else {
            Ok((t - c) * (t - c - 0.1 * w))
        }
    });
    assert!(scan.is_empty(), "{scan:?}");
}

/// A failing stretch narrower than the grid, between samples where `f` keeps its sign, and
/// `f` reaching zero at both its edges as a square root does (two branches that merge where
/// the loci stop meeting): both edges are roots, flagged as boundaries.
#[test]
fn edges_of_a_hidden_stretch_where_f_falls_to_zero_are_roots() {
    let spacing = 3.0 / 31.0;
    for k in 0..20 {
        let c = -1.0 + 2.0 * f64::from(k) / 20.0 + 0.011 * f64::from(k % 5);
        let w = 0.2 * spacing;
        let scan: RootScan<8> = all_roots(-1.5, 1.5, false, 32, &Settings::default(), |x| {
            let d = (x - c).abs() - w;
            if d <= 0.0 {
                Err(())
            } else {
                Ok(-(d.sqrt()) * (1.0 + x * x))
            }
        });
        assert_eq!(scan.roots().len(), 2, "stretch at {c}: {scan:?}");
        for (i, edge) in [c - w, c + w].into_iter().enumerate() {
            assert!((scan.roots()[i] - edge).abs() <= 1e-9, "{edge}: {scan:?}");
            assert!(scan.is_boundary(i), "{scan:?}");
        }
    }
}

/// A hidden stretch whose edges `f` does not approach zero at (the loci stop meeting, and
/// the error stays away from zero): no root.
#[test]
fn edges_of_a_hidden_stretch_away_from_zero_are_no_roots() {
    let spacing = 3.0 / 31.0;
    let (c, w) = (0.3 + 0.41 * spacing, 0.2 * spacing);
    let scan: RootScan<8> = all_roots(-1.5, 1.5, false, 32, &Settings::default(), |x| {
        let d = (x - c).abs() - w;
        if d <= 0.0 {
            Err(())
        } else {
            Ok(-(0.5 + d.sqrt()) * (1.0 + x * x))
        }
    });
    assert!(scan.is_empty(), "{scan:?}");
}

/// `x` wrapped to (-pi, pi].
fn num_wrap(x: f64) -> f64 {
    gcs_runtime::num::wrap_angle(x)
}
