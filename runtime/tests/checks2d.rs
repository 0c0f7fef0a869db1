//! Properties of the run-time check residuals (`gcs_runtime::check`) on random and
//! near-degenerate inputs, at scales from 1e-6 to 1e6: a configuration built to satisfy a
//! relation measures (near) zero, and one moved off it by a known amount measures that amount,
//! within a few ulps of the scale.
#![allow(clippy::unwrap_used)]

use gcs_runtime::check::{self, Nesting};
use gcs_runtime::locus2d::{P2, V2};
use proptest::prelude::*;

/// A scale 10^e for e in [-6, 6].
fn scale() -> impl Strategy<Value = f64> {
    (-6i32..=6).prop_map(|e| 10f64.powi(e))
}

/// A unit-range value.
fn u() -> impl Strategy<Value = f64> {
    -1.0f64..1.0
}

/// An angle in (-pi, pi].
fn heading() -> impl Strategy<Value = f64> {
    -std::f64::consts::PI..std::f64::consts::PI
}

/// An offset of the relation: zero, near-degenerate (1e-15 to 1e-6 of the scale), or large.
fn off() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-15.0f64..-6.0, any::<bool>()).prop_map(|(e, n)| if n {
            -(10f64.powf(e))
        } else {
            10f64.powf(e)
        }),
        -1.0f64..1.0,
    ]
}

fn dir(t: f64) -> V2 {
    V2::new(t.cos(), t.sin())
}

fn left(d: V2) -> V2 {
    V2::new(-d.y, d.x)
}

/// What a residual may be off by, for a configuration of scale `s` built with a few roundings.
fn close(measured: f64, expected: f64, s: f64) -> bool {
    (measured - expected).abs() <= 1e-13 * s.max(expected.abs())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn point_point_measures_the_distance_error(
        s in scale(), (x, y) in (u(), u()), t in heading(), d in 0.0f64..1.0, e in off()
    ) {
        let a = P2::new(x * s, y * s);
        let b = a + dir(t) * ((d + e.abs()) * s);
        prop_assert!(close(check::point_point(a, b, d * s), e.abs() * s, s));
    }

    #[test]
    fn point_line_measures_the_signed_offset(
        s in scale(), (x, y) in (u(), u()), t in heading(), along in u(), d in u(), e in off()
    ) {
        let base = P2::new(x * s, y * s);
        let l = dir(t);
        let p = base + l * (along * s) + left(l) * ((d + e) * s);
        prop_assert!(close(check::point_line(p, base, l, d * s), e.abs() * s, s));
    }

    #[test]
    fn angle_holds_its_sense(u0 in heading(), a in heading(), e in -3.0f64..3.0) {
        let v = dir(u0 + a + e);
        let r = check::angle(dir(u0), v, a);
        prop_assert!((r - e.abs()).abs() <= 1e-12, "{r} vs {e}");
    }

    #[test]
    fn circle_line_holds_its_side(
        s in scale(), t in heading(), along in u(), r in 0.0f64..1.0, gap in 0.0f64..1.0,
        side in prop_oneof![Just(1.0), Just(-1.0)], e in off()
    ) {
        let base = P2::new(0.3 * s, -0.2 * s);
        let l = dir(t);
        let centre = base + l * (along * s) + left(l) * (side * (r + gap + e) * s);
        let m = check::circle_line(centre, r * s, base, l, gap * s, side);
        prop_assert!(close(m, e.abs() * s, s));
        // The other side is off by twice the centre's distance.
        let other = check::circle_line(centre, r * s, base, l, gap * s, -side);
        prop_assert!(close(other, (2.0 * (r + gap) + e).abs() * s, s));
    }

    #[test]
    fn point_circle_holds_inside_or_outside(
        s in scale(), t in heading(), r in 0.5f64..1.0, gap in 0.0f64..0.4, e in off(),
        outside in any::<bool>()
    ) {
        let c = P2::new(-0.1 * s, 0.7 * s);
        let reach = if outside { r + gap } else { r - gap };
        prop_assume!(reach + e >= 0.0);
        let p = c + dir(t) * ((reach + e) * s);
        let m = check::point_circle(p, c, r * s, gap * s, outside);
        prop_assert!(close(m, e.abs() * s, s));
    }

    #[test]
    fn circle_circle_holds_its_nesting(
        s in scale(), t in heading(), r1 in 0.1f64..1.0, r2 in 0.1f64..1.0, gap in 0.0f64..0.05,
        e in off(), n in 0usize..3
    ) {
        let nesting = [Nesting::Apart, Nesting::FirstInside, Nesting::SecondInside][n];
        let (r1, r2) = match nesting {
            Nesting::FirstInside => (r1.min(r2) * 0.5, r1.max(r2)),
            Nesting::SecondInside => (r1.max(r2), r1.min(r2) * 0.5),
            Nesting::Apart => (r1, r2),
        };
        let d = match nesting {
            Nesting::Apart => r1 + r2 + gap,
            Nesting::FirstInside => r2 - r1 - gap,
            Nesting::SecondInside => r1 - r2 - gap,
        };
        prop_assume!(d + e > 0.0);
        let c1 = P2::new(0.2 * s, 0.1 * s);
        let c2 = c1 + dir(t) * ((d + e) * s);
        let m = check::circle_circle(c1, r1 * s, c2, r2 * s, gap * s, nesting);
        prop_assert!(close(m, e.abs() * s, s));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn midpoint_measures_the_offset(
        s in scale(), (ax, ay) in (u(), u()), (bx, by) in (u(), u()), t in heading(), e in off()
    ) {
        let (a, b) = (P2::new(ax * s, ay * s), P2::new(bx * s, by * s));
        let p = gcs_runtime::locus2d::midpoint(a, b) + dir(t) * (e * s);
        prop_assert!(close(check::midpoint(p, a, b), e.abs() * s, s));
        // The signed errors are the offset's coordinates.
        let v = dir(t) * (e * s);
        prop_assert!(close(check::error::midpoint(p, a, b, 0), v.x, s));
        prop_assert!(close(check::error::midpoint(p, a, b, 1), v.y, s));
    }

    #[test]
    fn mirror_measures_the_offset(
        s in scale(), (x, y) in (u(), u()), t in heading(), along in u(), d in u(),
        w in heading(), e in off()
    ) {
        let base = P2::new(x * s, y * s);
        let l = dir(t);
        let p = base + l * (along * s) + left(l) * (d * s);
        // The image is as far along and as far on the other side.
        let image = base + l * (along * s) - left(l) * (d * s);
        let q = image + dir(w) * (e * s);
        prop_assert!(close(check::mirror(p, q, base, l), e.abs() * s, s));
        let v = dir(w) * (e * s);
        prop_assert!(close(check::error::mirror(p, q, base, l, 0), v.x, s));
        prop_assert!(close(check::error::mirror(p, q, base, l, 1), v.y, s));
        // p on the mirror is its own image.
        let on = base + l * (along * s);
        prop_assert!(close(check::mirror(on, on, base, l), 0.0, s));
    }
}
