//! Every real assembly (`gcs solve --all-solutions`), checked against an independent count.
//!
//! The 3-RPR robot of `examples/rpr3.gcs` is solved by the plan as an iteration over the angle
//! of the platform's first point about its base (a default), with a branch for the second
//! point. The count here shares nothing with that plan: it scans the platform's orientation
//! `phi` over a turn on a fine grid, places the first point on both intersections of the two
//! legs' circles that `phi` allows, and counts the sign changes of the third leg's error. Each
//! assembly the plan finds must be one of those, satisfy every constraint (by `verify`), and
//! none may be missing, at Gosselin and Merlet's instance (six real assemblies), at other leg
//! lengths, and next to a double root, where two assemblies are about to merge.

use gcs_compiler::all::solve_all;
use std::collections::BTreeSet;

const MODEL: &str = include_str!("../../examples/rpr3.gcs");

/// The fixed base and the platform's local points.
const BASE: [(f64, f64); 3] = [(0.0, 0.0), (15.91, 0.0), (0.0, 10.0)];
const Q2: (f64, f64) = (17.04, 0.0);
const Q3: (f64, f64) = (15.940021741400596, 13.425362538233478);

/// The third leg's error at orientation `phi` with the first point on intersection `side`,
/// or `None` where the first two legs cannot both reach.
fn third_leg_error(legs: [f64; 3], phi: f64, side: f64) -> Option<f64> {
    let (c, s) = (phi.cos(), phi.sin());
    let turn = |(x, y): (f64, f64)| (c * x - s * y, s * x + c * y);
    // p1 on the circle (B1, leg1) and on the circle (B2 - R q2, leg2).
    let q2 = turn(Q2);
    let (cx, cy) = (BASE[1].0 - q2.0, BASE[1].1 - q2.1);
    let (dx, dy) = (cx - BASE[0].0, cy - BASE[0].1);
    let d = dx.hypot(dy);
    let (r1, r2) = (legs[0], legs[1]);
    if d == 0.0 || d > r1 + r2 || d < (r1 - r2).abs() {
        return None;
    }
    let along = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - along * along).max(0.0).sqrt();
    let (ux, uy) = (dx / d, dy / d);
    let p1 = (
        BASE[0].0 + along * ux - side * h * uy,
        BASE[0].1 + along * uy + side * h * ux,
    );
    let q3 = turn(Q3);
    let p3 = (p1.0 + q3.0, p1.1 + q3.1);
    Some((p3.0 - BASE[2].0).hypot(p3.1 - BASE[2].1) - legs[2])
}

/// The orientations of every assembly, by sign changes on a grid of `n` steps a turn.
fn independent_roots(legs: [f64; 3], n: usize) -> Vec<f64> {
    let mut roots = Vec::new();
    for side in [1.0, -1.0] {
        let mut previous: Option<(f64, f64)> = None;
        for i in 0..=n {
            let phi = std::f64::consts::TAU * i as f64 / n as f64;
            let now = third_leg_error(legs, phi, side);
            if let (Some((p, e0)), Some(e1)) = (previous, now) {
                if e0 == 0.0 || (e0 > 0.0) != (e1 > 0.0) {
                    // Refine by bisection.
                    let (mut a, mut b, mut fa) = (p, phi, e0);
                    for _ in 0..80 {
                        let m = 0.5 * (a + b);
                        match third_leg_error(legs, m, side) {
                            Some(fm) if (fm > 0.0) == (fa > 0.0) => (a, fa) = (m, fm),
                            _ => b = m,
                        }
                    }
                    roots.push(0.5 * (a + b));
                }
            }
            previous = now.map(|e| (phi, e));
        }
    }
    roots
}

/// The model with other leg lengths.
fn with_legs(legs: [f64; 3]) -> String {
    MODEL
        .replace(
            "param leg1 = 14.98;",
            &format!("param leg1 = {:?};", legs[0]),
        )
        .replace(
            "param leg2 = 15.38;",
            &format!("param leg2 = {:?};", legs[1]),
        )
        .replace("param leg3 = 12;", &format!("param leg3 = {:?};", legs[2]))
}

/// Solves every assembly with the plan and checks it against the independent roots.
fn check(legs: [f64; 3]) -> usize {
    let text = with_legs(legs);
    let c = gcs_compiler::compile("rpr3.gcs", text.as_bytes()).expect("compiles");
    assert!(!c.has_errors(), "{:?}", c.diagnostics);
    let (model, plan) = (&c.model, &c.analysis.plan);
    assert_eq!(
        plan.iterations.len(),
        1,
        "the 3-RPR iterates on one default"
    );
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let found = solve_all(
        model,
        plan,
        &scope,
        &model.default_params(),
        &plan.sketch_defaults(),
    );
    assert!(
        found.complete,
        "one angle iterated: the search is exhaustive"
    );
    let expected = independent_roots(legs, 200_000);
    let mut orientations = Vec::new();
    for s in &found.solutions {
        assert!(
            s.max_residual <= 1e-12 * 30.0,
            "{legs:?}: an assembly off by {}",
            s.max_residual
        );
        let point = |n: &str| {
            let v = &s
                .points
                .iter()
                .find(|(name, _)| name == n)
                .expect("a point")
                .1;
            (v[0], v[1])
        };
        let (p1, p2) = (point("platform.p1"), point("platform.p2"));
        let phi = (p2.1 - p1.1)
            .atan2(p2.0 - p1.0)
            .rem_euclid(std::f64::consts::TAU);
        let matched = expected.iter().any(|e| {
            let d = (e - phi).abs();
            d.min(std::f64::consts::TAU - d) < 1e-6
        });
        assert!(
            matched,
            "{legs:?}: assembly at phi = {phi} is not one of {expected:?}"
        );
        orientations.push(phi);
    }
    assert_eq!(
        found.solutions.len(),
        expected.len(),
        "{legs:?}: the plan found {orientations:?}, the independent count {expected:?}"
    );
    found.solutions.len()
}

#[test]
fn gosselin_and_merlets_instance_has_six_real_assemblies() {
    assert_eq!(check([14.98, 15.38, 12.0]), 6);
}

#[test]
fn other_leg_lengths_agree_with_the_independent_count() {
    for legs in [
        [14.98, 15.38, 10.0],
        [14.98, 15.38, 14.0],
        [16.0, 15.0, 12.0],
        [12.0, 17.0, 9.0],
        [20.0, 20.0, 20.0],
    ] {
        check(legs);
    }
}

#[test]
fn next_to_a_double_root_no_assembly_is_lost() {
    // Shorten the third leg from the six-assembly instance until the count drops: between
    // the two lengths two assemblies merge (a double root). Bisect to it, then solve just on
    // either side of it, and at it.
    let count = |l3: f64| independent_roots([14.98, 15.38, l3], 50_000).len();
    let (mut six, mut fewer) = (12.0, 12.0);
    while count(fewer) == 6 {
        fewer -= 0.25;
        assert!(fewer > 0.0, "the count never drops");
    }
    for _ in 0..40 {
        let mid = 0.5 * (six + fewer);
        if count(mid) == 6 {
            six = mid;
        } else {
            fewer = mid;
        }
    }
    assert!(six - fewer < 1e-9);
    check([14.98, 15.38, six + 1e-6]);
    check([14.98, 15.38, fewer - 1e-6]);
}
