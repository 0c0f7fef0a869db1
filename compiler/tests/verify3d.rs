//! The verifier on 3d models: every constraint's residual on hand-made solutions, one that
//! satisfies it and ones that miss by an amount worked out by hand.

use gcs_compiler::solution::Solution;
use gcs_compiler::verify::residuals;
use gcs_lang::Model;
use std::f64::consts::{FRAC_PI_2, PI};

const TOL: f64 = 1e-12;

fn model(src: &str) -> Model {
    match gcs_compiler::load("verify3d.gcs", src.as_bytes()) {
        Ok(l) => l.model,
        Err(r) => panic!("{src}\ndoes not load: {:?}", r.diagnostics),
    }
}

/// A solution with these points, vectors and scalars.
fn sol(
    points: &[(&str, [f64; 3])],
    vectors: &[(&str, [f64; 3])],
    scalars: &[(&str, f64)],
) -> Solution {
    let own = |v: &[(&str, [f64; 3])]| -> Vec<(String, Vec<f64>)> {
        v.iter().map(|(n, p)| (n.to_string(), p.to_vec())).collect()
    };
    Solution {
        points: own(points),
        vectors: own(vectors),
        scalars: scalars.iter().map(|(n, x)| (n.to_string(), *x)).collect(),
        ..Default::default()
    }
}

/// `s` with the point or vector `name` moved to `v`, or the scalar `name` set to `v[0]`.
fn set(mut s: Solution, name: &str, v: [f64; 3]) -> Solution {
    for (n, x) in s.points.iter_mut().chain(s.vectors.iter_mut()) {
        if n == name {
            *x = v.to_vec();
            return s;
        }
    }
    for (n, x) in &mut s.scalars {
        if n == name {
            *x = v[0];
            return s;
        }
    }
    panic!("no value {name}");
}

/// The residual of the constraint labelled `label`.
fn residual(m: &Model, s: &Solution, label: &str) -> f64 {
    let rs = residuals(m, s, &m.default_params());
    match rs
        .iter()
        .find(|r| m.constraints[r.constraint].name == label)
    {
        Some(r) => r.value,
        None => panic!("no constraint {label}"),
    }
}

#[track_caller]
fn assert_near(got: f64, want: f64) {
    assert!(
        (got - want).abs() <= TOL,
        "residual {got}, expected {want} (off by {:e})",
        got - want
    );
}

/// A unit vector at `t` radians from `a` towards `b` (orthonormal).
fn turned(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    let (s, c) = t.sin_cos();
    [
        a[0] * c + b[0] * s,
        a[1] * c + b[1] * s,
        a[2] * c + b[2] * s,
    ]
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

#[test]
fn coincident_and_spherical_are_the_distance_between_points() {
    let m = model(
        "space 3d;
         point P = (0, 0, 0); point Q = (1, 1, 1);
         body A { marker k = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); }
         c: coincident(P, Q);
         s: spherical(A.k, Q);",
    );
    let s = sol(
        &[
            ("P", [1.0, 2.0, 3.0]),
            ("Q", [1.0, 2.0, 3.0]),
            ("A.k", [1.0, 2.0, 3.0]),
        ],
        &[("A.k.z", Z), ("A.k.x", X)],
        &[],
    );
    assert_near(residual(&m, &s, "c"), 0.0);
    assert_near(residual(&m, &s, "s"), 0.0);
    let s = set(s, "Q", [4.0, 6.0, 3.0]);
    assert_near(residual(&m, &s, "c"), 5.0);
    assert_near(residual(&m, &s, "s"), 5.0);
}

#[test]
fn point_point_and_point_line_distances_are_unsigned() {
    let m = model(
        "space 3d;
         point P = (0, 0, 0); point Q = (0, 3, 4); point R = (5, 0, 2);
         line L = (0, 0, 0) -> (1, 0, 0);
         segment S = (0, 0, 1) -> (1, 0, 1);
         pp: distance(P, Q) = 5;
         pl: distance(R, L) = 2;
         ps: distance(R, S) = 1;",
    );
    let s = sol(
        &[
            ("P", [0.0, 0.0, 0.0]),
            ("Q", [0.0, 3.0, 4.0]),
            ("R", [5.0, 1.2, -1.6]),
            ("L.point", [-3.0, 0.0, 0.0]),
            ("S.start", [0.0, 0.0, 1.0]),
            ("S.end", [1.0, 0.0, 1.0]),
        ],
        &[("L.dir", X), ("S.dir", X)],
        &[("S.length", 1.0)],
    );
    assert_near(residual(&m, &s, "pp"), 0.0);
    assert_near(residual(&m, &s, "pl"), 0.0);
    // R is (1.2, -2.6) across the segment's line: sqrt(1.44 + 6.76) = sqrt(8.2) from it.
    assert_near(residual(&m, &s, "ps"), 8.2f64.sqrt() - 1.0);
    let s = set(s, "Q", [2.0, 3.0, 6.0]);
    assert_near(residual(&m, &s, "pp"), 2.0);
    let s = set(s, "R", [5.0, 0.0, 2.5]);
    assert_near(residual(&m, &s, "pl"), 0.5);
    // Beyond the segment's end, on its supporting line's measure.
    assert_near(residual(&m, &s, "ps"), 0.5);
}

#[test]
fn point_plane_distance_is_signed() {
    let m = model(
        "space 3d;
         point P = (3, 4, 1.5);
         point p1 = (0, 0, 0);
         plane F = normal (0, 0, 1) offset 1;
         plane W = normal (0.6, 0.8, 0) offset 5;
         d: distance(P, F) = 0.5;
         w: distance(p1, W) = -5;
         o: on(P, F);",
    );
    let s = sol(
        &[("P", [3.0, 4.0, 1.5]), ("p1", [0.0, 0.0, 0.0])],
        &[("F.normal", Z), ("W.normal", [0.6, 0.8, 0.0])],
        &[("F.offset", 1.0), ("W.offset", 5.0)],
    );
    assert_near(residual(&m, &s, "d"), 0.0);
    assert_near(residual(&m, &s, "w"), 0.0);
    assert_near(residual(&m, &s, "o"), 0.5);
    // The mirror image of a satisfied point: the wrong sign, off by twice the distance.
    let s = set(s, "P", [3.0, 4.0, 0.5]);
    assert_near(residual(&m, &s, "d"), 1.0);
    assert_near(residual(&m, &s, "o"), 0.5);
    let s = set(s, "P", [3.0, 4.0, 1.3]);
    assert_near(residual(&m, &s, "o"), 0.3);
    let s = set(s, "p1", [0.0, 0.0, 7.0]);
    assert_near(residual(&m, &s, "w"), 0.0);
    let s = set(s, "p1", [0.6, 0.8, 0.0]);
    assert_near(residual(&m, &s, "w"), 1.0);
    // A missing offset is a failure, not a pass.
    let mut s = s;
    s.scalars.retain(|(n, _)| n != "W.offset");
    assert!(residual(&m, &s, "w").is_nan());
}

#[test]
fn point_circle_distance_is_to_the_nearest_point_of_the_circle() {
    let m = model(
        "space 3d;
         point P = (2, 0, 1);
         circle C = center (0, 0, 0) radius 2 normal (0, 0, 1);
         d: distance(P, C) = 1;
         o: on(P, C);",
    );
    let s = sol(
        &[("P", [2.0, 0.0, 1.0]), ("C.center", [0.0, 0.0, 0.0])],
        &[("C.normal", Z)],
        &[("C.radius", 2.0)],
    );
    assert_near(residual(&m, &s, "d"), 0.0);
    assert_near(residual(&m, &s, "o"), 1.0);
    // Inside, in the plane, and on the axis (every point of the circle is sqrt(1.5² + 2²)).
    let s = set(s, "P", [0.0, 1.0, 0.0]);
    assert_near(residual(&m, &s, "d"), 0.0);
    let s = set(s, "P", [0.0, 0.0, 1.5]);
    assert_near(residual(&m, &s, "d"), 1.5);
    assert_near(residual(&m, &s, "o"), 2.5);
    // On: out of the plane, off the radius, and both (a 3-4-5 triangle scaled by 0.1).
    let s = set(s, "P", [0.0, 2.0, 0.0]);
    assert_near(residual(&m, &s, "o"), 0.0);
    let s = set(s, "P", [0.0, 2.0, 0.3]);
    assert_near(residual(&m, &s, "o"), 0.3);
    let s = set(s, "P", [0.0, -2.4, 0.0]);
    assert_near(residual(&m, &s, "o"), 0.4);
    let s = set(s, "P", [0.0, 2.3, 0.4]);
    assert_near(residual(&m, &s, "o"), 0.5);
    // A tilted circle: its normal along x, the point on it in the yz plane.
    let s = set(set(s, "C.normal", X), "P", [0.0, 1.2, -1.6]);
    assert_near(residual(&m, &s, "o"), 0.0);
}

#[test]
fn on_a_line_and_a_segment_is_the_distance_to_the_supporting_line() {
    let m = model(
        "space 3d;
         point P = (7, 0, 0);
         line L = (0, 0, 0) -> (1, 1, 1);
         segment S = (0, 0, 0) -> (1, 1, 1);
         l: on(P, L);
         s: on(P, S);",
    );
    let d = [1.0 / 3f64.sqrt(); 3];
    let s = sol(
        &[
            ("P", [7.0, 7.0, 7.0]),
            ("L.point", [1.0, 1.0, 1.0]),
            ("S.start", [0.0, 0.0, 0.0]),
            ("S.end", [1.0, 1.0, 1.0]),
        ],
        &[("L.dir", d), ("S.dir", d)],
        &[],
    );
    assert_near(residual(&m, &s, "l"), 0.0);
    assert_near(residual(&m, &s, "s"), 0.0);
    // 0.3 and 0.4 along two directions across the line.
    let a = [1.0 / 2f64.sqrt(), -1.0 / 2f64.sqrt(), 0.0];
    let b = [1.0 / 6f64.sqrt(), 1.0 / 6f64.sqrt(), -2.0 / 6f64.sqrt()];
    let p = [
        7.0 + 0.3 * a[0] + 0.4 * b[0],
        7.0 + 0.3 * a[1] + 0.4 * b[1],
        7.0 + 0.3 * a[2] + 0.4 * b[2],
    ];
    let s = set(s, "P", p);
    assert_near(residual(&m, &s, "l"), 0.5);
    assert_near(residual(&m, &s, "s"), 0.5);
}

/// A circle of radius 2 about the origin in the XY plane, a line, a segment and a second
/// circle about it.
const CIRCLES: &str = "space 3d;
     circle C = center (0, 0, 0) radius 2 normal (0, 0, 1);
     circle D = center (3, 0, 0) radius 1 normal (0, 0, 1);
     line L = (0, 2, 0) -> (1, 2, 0);
     segment S = (0, 2, 0) -> (3, 2, 0);
     tl: tangent(L, C);
     ts: tangent(S, C);
     tc: tangent(C, D);
     dl: distance(L, C) = 0.5;
     dc: distance(C, D) = 1;";

fn circles() -> Solution {
    sol(
        &[
            ("C.center", [0.0, 0.0, 0.0]),
            ("D.center", [3.0, 0.0, 0.0]),
            ("L.point", [0.0, 2.0, 0.0]),
            ("S.start", [0.0, 2.0, 0.0]),
            ("S.end", [3.0, 2.0, 0.0]),
        ],
        &[("C.normal", Z), ("D.normal", Z), ("L.dir", X), ("S.dir", X)],
        &[("C.radius", 2.0), ("D.radius", 1.0), ("S.length", 3.0)],
    )
}

#[test]
fn a_line_tangent_to_a_circle_lies_in_its_plane_and_touches_it() {
    let m = model(CIRCLES);
    let s = circles();
    assert_near(residual(&m, &s, "tl"), 0.0);
    assert_near(residual(&m, &s, "ts"), 0.0);
    // In the plane, 2.5 from the centre: 0.5 off tangency, and at distance 0.5.
    let s = set(s, "L.point", [0.0, -2.5, 0.0]);
    assert_near(residual(&m, &s, "tl"), 0.5);
    assert_near(residual(&m, &s, "dl"), 0.0);
    // Parallel to the plane, 0.3 above it: it touches nothing.
    let s = set(s, "L.point", [5.0, 2.0, 0.3]);
    assert_near(residual(&m, &s, "tl"), 0.3);
    // Through the touching point, tilted 0.1 rad out of the plane: it crosses the circle.
    let s = set(
        set(s, "L.point", [0.0, 2.0, 0.0]),
        "L.dir",
        turned(X, Z, 0.1),
    );
    assert_near(residual(&m, &s, "tl"), 0.1);
    // A segment's end on the circle must be the touching point: here its line is 0.8 inside
    // the circle, and its start on the circle 1.6 along from the centre's foot (its end, 3.4
    // along, is off the circle and not measured).
    let s = set(
        set(s, "S.start", [-1.6, 1.2, 0.0]),
        "S.end",
        [3.4, 1.2, 0.0],
    );
    assert_near(residual(&m, &s, "ts"), 1.6);
}

#[test]
fn tangent_circles_lie_in_one_plane_and_touch() {
    let m = model(CIRCLES);
    let s = circles();
    assert_near(residual(&m, &s, "tc"), 0.0);
    // Inside, touching; and with the second circle's normal reversed (the same circle).
    let s = set(s, "D.center", [1.0, 0.0, 0.0]);
    assert_near(residual(&m, &s, "tc"), 0.0);
    let s = set(s, "D.normal", [0.0, 0.0, -1.0]);
    assert_near(residual(&m, &s, "tc"), 0.0);
    // Raised 0.2 off the plane, 3 from the centre along it.
    let s = set(s, "D.center", [3.0, 0.0, 0.2]);
    assert_near(residual(&m, &s, "tc"), 0.2);
    // In place, but turned 0.1 rad about the line of centres: they cross, not touch.
    let s = set(
        set(s, "D.center", [3.0, 0.0, 0.0]),
        "D.normal",
        turned(Z, Y, 0.1),
    );
    assert_near(residual(&m, &s, "tc"), 0.1);
    // In the plane, 0.25 apart.
    let s = set(set(s, "D.normal", Z), "D.center", [0.0, 3.25, 0.0]);
    assert_near(residual(&m, &s, "tc"), 0.25);
}

#[test]
fn line_circle_and_circle_circle_distances_are_measured_in_the_circles_plane() {
    let m = model(CIRCLES);
    let s = set(circles(), "L.point", [0.0, 2.5, 0.0]);
    assert_near(residual(&m, &s, "dl"), 0.0);
    let s = set(s, "L.point", [0.0, 3.0, 0.0]);
    assert_near(residual(&m, &s, "dl"), 0.5);
    // 2.5 from the centre, but 0.4 above the plane.
    let s = set(s, "L.point", [0.0, 2.5, 0.4]);
    assert_near(residual(&m, &s, "dl"), 0.4);
    let s = set(s, "D.center", [4.0, 0.0, 0.0]);
    assert_near(residual(&m, &s, "dc"), 0.0);
    let s = set(s, "D.center", [4.5, 0.0, 0.0]);
    assert_near(residual(&m, &s, "dc"), 0.5);
    let s = set(s, "D.center", [0.0, -4.0, 0.3]);
    assert_near(residual(&m, &s, "dc"), 0.3);
}

#[test]
fn angles_are_unsigned_and_compared_by_turning() {
    let m = model(
        "space 3d;
         vector u = (1, 0, 0); vector v = (1, 1, 0);
         line L = (0, 0, 0) -> (1, 0, 0);
         fixed plane F = normal (0, 0, 1) offset 0;
         fixed plane W = normal (1, 0, 0) offset 0;
         a: angle(u, v) = 60 deg;
         n: angle(u, v) = -60 deg;
         w: angle(u, v) = 300 deg;
         big: angle(u, v) = 1e100;
         pl: angle(F, W) = 90 deg;
         ln: angle(L, F) = 90 deg;",
    );
    let s = sol(
        &[("L.point", [0.0, 0.0, 0.0])],
        &[
            ("u", X),
            ("v", turned(X, Y, PI / 3.0)),
            ("L.dir", X),
            ("F.normal", Z),
            ("W.normal", X),
        ],
        &[("F.offset", 0.0), ("W.offset", 0.0)],
    );
    for label in ["a", "n", "w", "pl", "ln"] {
        assert_near(residual(&m, &s, label), 0.0);
    }
    // A huge target is compared by turning: subtracting it would leave -1e100.
    let (st, ct) = 1e100f64.sin_cos();
    let big = set(s.clone(), "v", turned(X, Y, st.atan2(ct).abs()));
    assert_near(residual(&m, &big, "big"), 0.0);
    // Unsigned: the same angle in another plane, and the other way round.
    let s = set(s, "v", turned(X, [0.0, -0.6, 0.8], PI / 3.0));
    for label in ["a", "n", "w"] {
        assert_near(residual(&m, &s, label), 0.0);
    }
    let s = set(s, "v", turned(X, Z, 70f64.to_radians()));
    for label in ["a", "n", "w"] {
        assert_near(residual(&m, &s, label), 10f64.to_radians());
    }
    let s = set(s, "L.dir", turned(X, Z, 0.25));
    assert_near(residual(&m, &s, "ln"), 0.25);
    let s = set(s, "W.normal", [0.0, -1.0, 0.0]);
    assert_near(residual(&m, &s, "pl"), 0.0);
    let s = set(s, "W.normal", [0.0, 0.0, -1.0]);
    assert_near(residual(&m, &s, "pl"), FRAC_PI_2);
}

#[test]
fn parallel_takes_either_sense_and_perpendicular_the_right_angle() {
    let m = model(
        "space 3d;
         vector u = (1, 0, 0); vector v = (1, 0, 0); vector w = (0, 0, 1);
         segment S = (0, 0, 0) -> (0, 0, 1);
         pa: parallel(u, v);
         pe: perpendicular(u, w);
         ps: perpendicular(S, v);",
    );
    let s = sol(
        &[("S.start", [0.0; 3]), ("S.end", Z)],
        &[("u", X), ("v", [-1.0, 0.0, 0.0]), ("w", Z), ("S.dir", Z)],
        &[("S.length", 1.0)],
    );
    for label in ["pa", "pe", "ps"] {
        assert_near(residual(&m, &s, label), 0.0);
    }
    let s = set(set(s, "v", turned(X, Y, 0.1)), "w", turned(Z, X, 0.1));
    assert_near(residual(&m, &s, "pa"), 0.1);
    assert_near(residual(&m, &s, "pe"), 0.1);
    assert_near(residual(&m, &s, "ps"), 0.0);
    let s = set(s, "v", turned(X, Y, PI - 0.1));
    assert_near(residual(&m, &s, "pa"), 0.1);
    let s = set(s, "v", turned(Y, Z, 0.3));
    assert_near(residual(&m, &s, "pa"), FRAC_PI_2);
    assert_near(residual(&m, &s, "ps"), 0.3);
}

#[test]
fn dimensions_equal_and_midpoint_in_space() {
    let m = model(
        "space 3d;
         segment S = (0, 0, 0) -> (0, 3, 4);
         segment T = (1, 1, 1) -> (1, 4, 5);
         circle C = center (0, 0, 0) radius 2 normal (0, 0, 1);
         circle D = center (5, 0, 0) radius 2 normal (0, 1, 0);
         point M = (0, 1.5, 2);
         l: length(S) = 5;
         r: radius(C) = 2;
         es: equal(S, T);
         ec: equal(C, D);
         mid: midpoint(M, S);",
    );
    let s = sol(
        &[
            ("S.start", [0.0; 3]),
            ("S.end", [0.0, 3.0, 4.0]),
            ("T.start", [1.0, 1.0, 1.0]),
            ("T.end", [6.0, 1.0, 1.0]),
            ("C.center", [0.0; 3]),
            ("D.center", [5.0, 0.0, 0.0]),
            ("M", [0.0, 1.5, 2.0]),
        ],
        &[
            ("S.dir", [0.0, 0.6, 0.8]),
            ("T.dir", X),
            ("C.normal", Z),
            ("D.normal", Y),
        ],
        &[
            ("C.radius", 2.0),
            ("D.radius", 2.0),
            ("S.length", 5.0),
            ("T.length", 5.0),
        ],
    );
    for label in ["l", "r", "es", "ec", "mid"] {
        assert_near(residual(&m, &s, label), 0.0);
    }
    let s = set(s, "S.end", [0.0, 0.0, 6.0]);
    assert_near(residual(&m, &s, "l"), 1.0);
    assert_near(residual(&m, &s, "es"), 1.0);
    // M is now 1.5 across from the midpoint (0, 0, 3) and 1 below it.
    assert_near(residual(&m, &s, "mid"), 3.25f64.sqrt());
    let s = set(s, "C.radius", [2.5, 0.0, 0.0]);
    assert_near(residual(&m, &s, "r"), 0.5);
    assert_near(residual(&m, &s, "ec"), 0.5);
}

#[test]
fn symmetric_points_mirror_across_a_plane() {
    let m = model(
        "space 3d;
         fixed plane Q = normal (1, 0, 0) offset 1;
         point P = (0, 2, 3); point R = (2, 2, 3);
         s: symmetric(P, R, Q);",
    );
    let s = sol(
        &[("P", [0.0, 2.0, 3.0]), ("R", [2.0, 2.0, 3.0])],
        &[("Q.normal", X)],
        &[("Q.offset", 1.0)],
    );
    assert_near(residual(&m, &s, "s"), 0.0);
    // Midpoint on the plane, but slanted 0.4 across its normal.
    let s = set(s, "R", [2.0, 2.0, 3.4]);
    assert_near(residual(&m, &s, "s"), 0.4);
    // Along the normal, the midpoint 0.3 off the plane.
    let s = set(s, "R", [2.6, 2.0, 3.0]);
    assert_near(residual(&m, &s, "s"), 0.3);
    // A point on the plane is its own image.
    let s = set(set(s, "P", [1.0, 5.0, -1.0]), "R", [1.0, 5.0, -1.0]);
    assert_near(residual(&m, &s, "s"), 0.0);
}

/// Two bodies with one marker each, and constraints between them.
const MARKERS: &str = "space 3d;
     fixed body A { marker m = (1, 1, 0) z (0, 0, 1) x (1, 0, 0); }
     body B { marker m = (1, 1, 5) z (0, 0, 1) x (1, 0, 0); }
     point P = (4, 5, 0);
     il: in_line(B.m, A.m);
     ip: in_plane(P, A.m);
     pz: parallel_z(B.m, A.m);
     oz: offset_z(A.m, B.m) = 30 deg;
     ox: offset_x(A.m, B.m) = 30 deg;
     h: helical(A.m, B.m) = 2;
     hn: helical(B.m, A.m) = -2;
     h0: helical(A.m, B.m) = 0;
     rv: revolute(B.m, A.m);
     pr: prismatic(B.m, A.m);
     cy: cylindrical(B.m, A.m);
     pn: planar(B.m, A.m);
     wd: weld(B.m, A.m);";

/// A's marker at (1, 1, 0) with z up and x along X; B's `dz` above it, its x turned `turn`
/// about z, its z as given.
fn markers(dz: f64, turn: f64, bz: [f64; 3]) -> Solution {
    sol(
        &[
            ("A.m", [1.0, 1.0, 0.0]),
            ("B.m", [1.0, 1.0, dz]),
            ("P", [4.0, 5.0, 0.0]),
        ],
        &[
            ("A.m.z", Z),
            ("A.m.x", X),
            ("B.m.z", bz),
            ("B.m.x", turned(X, Y, turn)),
        ],
        &[],
    )
}

#[test]
fn in_line_and_in_plane_follow_the_second_markers_z_axis() {
    let m = model(MARKERS);
    let s = markers(5.0, 0.0, Z);
    assert_near(residual(&m, &s, "il"), 0.0);
    assert_near(residual(&m, &s, "ip"), 0.0);
    let s = set(s, "B.m", [1.3, 1.4, 5.0]);
    assert_near(residual(&m, &s, "il"), 0.5);
    let s = set(s, "P", [4.0, 5.0, 0.3]);
    assert_near(residual(&m, &s, "ip"), 0.3);
    // A's z along X: its line is y = 1, z = 0; its plane x = 1.
    let s = set(set(s, "A.m.z", X), "A.m.x", Y);
    let s = set(set(s, "B.m", [-7.0, 1.0, 0.0]), "P", [1.0, 9.0, 9.0]);
    assert_near(residual(&m, &s, "il"), 0.0);
    assert_near(residual(&m, &s, "ip"), 0.0);
    let s = set(s, "P", [0.8, 9.0, 9.0]);
    assert_near(residual(&m, &s, "ip"), 0.2);
}

#[test]
fn parallel_z_and_offset_z_compare_the_z_axes() {
    let m = model(MARKERS);
    let s = markers(5.0, 0.0, Z);
    assert_near(residual(&m, &s, "pz"), 0.0);
    assert_near(residual(&m, &s, "oz"), PI / 6.0);
    let s = set(s, "B.m.z", [0.0, 0.0, -1.0]);
    assert_near(residual(&m, &s, "pz"), 0.0);
    let s = set(s, "B.m.z", turned(Z, X, 0.1));
    assert_near(residual(&m, &s, "pz"), 0.1);
    let s = set(s, "B.m.z", turned(Z, [0.6, 0.8, 0.0], PI / 6.0));
    assert_near(residual(&m, &s, "oz"), 0.0);
    let s = set(s, "B.m.z", turned(Z, Y, 40f64.to_radians()));
    assert_near(residual(&m, &s, "oz"), 10f64.to_radians());
}

#[test]
fn offset_x_is_the_turn_about_the_first_z_axis_with_the_z_axes_parallel() {
    let m = model(MARKERS);
    let s = markers(5.0, PI / 6.0, Z);
    assert_near(residual(&m, &s, "ox"), 0.0);
    let s = markers(5.0, PI / 6.0 + 0.1, Z);
    assert_near(residual(&m, &s, "ox"), 0.1);
    // Clockwise is the other way: 60 degrees off.
    let s = markers(5.0, -PI / 6.0, Z);
    assert_near(residual(&m, &s, "ox"), PI / 3.0);
    // The right turn, but B's z tilted 0.2 rad.
    let s = markers(5.0, PI / 6.0, turned(Z, Y, 0.2));
    assert_near(residual(&m, &s, "ox"), 0.2);
    // About a z axis along X: counter-clockwise takes Y towards Z.
    let s = sol(
        &[("A.m", [0.0; 3]), ("B.m", [0.0; 3]), ("P", [0.0; 3])],
        &[
            ("A.m.z", X),
            ("A.m.x", Y),
            ("B.m.z", X),
            ("B.m.x", turned(Y, Z, PI / 6.0)),
        ],
        &[],
    );
    assert_near(residual(&m, &s, "ox"), 0.0);
    let s = set(s, "B.m.x", turned(Y, Z, -PI / 6.0));
    assert_near(residual(&m, &s, "ox"), PI / 3.0);
}

#[test]
fn helical_turns_a_full_turn_per_pitch_of_advance() {
    let m = model(MARKERS);
    // Pitch 2, advance 0.5: a quarter turn.
    let s = markers(0.5, FRAC_PI_2, Z);
    assert_near(residual(&m, &s, "h"), 0.0);
    let s = markers(0.5, 0.0, Z);
    assert_near(residual(&m, &s, "h"), FRAC_PI_2);
    // Advance 2.5: a turn and a quarter, the same x axis.
    let s = markers(2.5, FRAC_PI_2, Z);
    assert_near(residual(&m, &s, "h"), 0.0);
    let s = markers(0.5, FRAC_PI_2 + 0.1, Z);
    assert_near(residual(&m, &s, "h"), 0.1);
    // From B, with pitch -2: A advances -0.5 along B's z, so A's x is a quarter turn
    // counter-clockwise from B's (B's x a quarter turn clockwise from A's).
    let s = markers(0.5, -FRAC_PI_2, Z);
    assert_near(residual(&m, &s, "hn"), 0.0);
    let s = markers(0.5, FRAC_PI_2, Z);
    assert_near(residual(&m, &s, "hn"), PI);
    // The z axes must be parallel.
    let s = markers(0.5, FRAC_PI_2, turned(Z, X, 0.2));
    assert_near(residual(&m, &s, "h"), 0.2);
    // A zero pitch has no turn per advance.
    assert!(residual(&m, &s, "h0").is_nan());
}

#[test]
fn joints_take_the_largest_of_their_conditions() {
    let m = model(MARKERS);
    // Coincident, z opposite, x turned: revolute; not on the same x: prismatic 0.7 off.
    let s = sol(
        &[
            ("A.m", [1.0, 1.0, 0.0]),
            ("B.m", [1.0, 1.0, 0.0]),
            ("P", [0.0; 3]),
        ],
        &[
            ("A.m.z", Z),
            ("A.m.x", X),
            ("B.m.z", [0.0, 0.0, -1.0]),
            ("B.m.x", turned(X, Y, 0.7)),
        ],
        &[],
    );
    for label in ["rv", "cy", "pn"] {
        assert_near(residual(&m, &s, label), 0.0);
    }
    assert_near(residual(&m, &s, "pr"), 0.7);
    // Up A's z axis by 3: in line, not coincident, out of A's plane.
    let s = set(s, "B.m", [1.0, 1.0, 3.0]);
    assert_near(residual(&m, &s, "rv"), 3.0);
    assert_near(residual(&m, &s, "cy"), 0.0);
    assert_near(residual(&m, &s, "pn"), 3.0);
    let s = set(s, "B.m.x", X);
    assert_near(residual(&m, &s, "pr"), 0.0);
    // 0.2 off the axis, z tilted 0.1: the larger.
    let s = set(set(s, "B.m", [1.2, 1.0, 3.0]), "B.m.z", turned(Z, Y, 0.1));
    assert_near(residual(&m, &s, "cy"), 0.2);
    assert_near(residual(&m, &s, "pr"), 0.2);
    let s = set(s, "B.m", [1.05, 1.0, 0.0]);
    assert_near(residual(&m, &s, "rv"), 0.1);
    assert_near(residual(&m, &s, "pn"), 0.1);
}

#[test]
fn a_weld_is_met_by_one_frame_only() {
    let m = model(MARKERS);
    // B's marker on A's, with A's axes.
    assert_near(residual(&m, &markers(0.0, 0.0, Z), "wd"), 0.0);
    // Up A's z axis by 0.3; x turned 0.2 about z; z tilted 0.1 (x still square to it).
    assert_near(residual(&m, &markers(0.3, 0.0, Z), "wd"), 0.3);
    assert_near(residual(&m, &markers(0.0, 0.2, Z), "wd"), 0.2);
    assert_near(
        residual(&m, &markers(0.0, 0.0, turned(Z, Y, 0.1)), "wd"),
        0.1,
    );
    // The largest of them.
    assert_near(residual(&m, &markers(0.3, 0.2, Z), "wd"), 0.3);
    assert_near(residual(&m, &markers(0.1, 0.2, Z), "wd"), 0.2);
    assert_near(
        residual(&m, &markers(0.1, 0.0, turned(Z, Y, 0.15)), "wd"),
        0.15,
    );
    // z opposite, x the same: a prismatic joint's axes (offset_x(0) in either sense), but
    // not one frame: pi off.
    let s = markers(0.0, 0.0, [0.0, 0.0, -1.0]);
    assert_near(residual(&m, &s, "pr"), 0.0);
    assert_near(residual(&m, &s, "wd"), PI);
    // A missing axis or point fails rather than passes.
    for name in ["B.m.x", "B.m.z"] {
        let mut s = markers(0.0, 0.0, Z);
        s.vectors.retain(|(n, _)| n != name);
        assert!(residual(&m, &s, "wd").is_nan(), "{name}");
    }
    let mut s = markers(0.0, 0.0, Z);
    s.points.retain(|(n, _)| n != "B.m");
    assert!(residual(&m, &s, "wd").is_nan());
}

#[test]
fn a_point_with_two_coordinates_is_missing_in_3d() {
    let m = model(
        "space 3d;
         point P = (0, 0, 0); point Q = (0, 0, 0);
         c: coincident(P, Q);",
    );
    let mut s = sol(&[("P", [0.0; 3]), ("Q", [0.0; 3])], &[], &[]);
    assert_near(residual(&m, &s, "c"), 0.0);
    s.points[1].1 = vec![0.0, 0.0];
    assert!(residual(&m, &s, "c").is_nan());
    s.points.pop();
    assert!(residual(&m, &s, "c").is_nan());
}
