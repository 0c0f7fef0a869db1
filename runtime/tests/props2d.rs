//! Properties of the 2d intersection table on random and near-degenerate inputs, at scales from
//! 1e-6 to 1e6.
//!
//! Bounds, relative to the scale `s` of the inputs (largest coordinate or radius):
//! - transversal roots of line, ray and circle pairs lie on both loci within 1e-13 s; a far
//!   crossing of nearly parallel lines within 1e-13 of its own distance from the origin;
//! - roots involving conics within 1e-12 s: their residual is first-order (implicit value over
//!   gradient), whose evaluation costs a few more roundings than a circle's;
//! - tangent roots within [`tol::TANGENT_REL`] s of both loci (the classification tolerance).
#![allow(clippy::unwrap_used)]

use gcs_runtime::intersect2d::*;
use gcs_runtime::locus2d::*;
use gcs_runtime::{tol, Contact, Intersection};
use proptest::prelude::*;

fn p(x: f64, y: f64) -> P2 {
    P2::new(x, y)
}

/// A scale 10^e for e in [-6, 6].
fn scale() -> impl Strategy<Value = f64> {
    (-6i32..=6).prop_map(|e| 10f64.powi(e))
}

/// A unit-range value.
fn u() -> impl Strategy<Value = f64> {
    -1.0f64..1.0
}

/// `cases` cases (`PROPTEST_CASES` overrides them). The branch-stability tests keep only
/// crossing inputs, about half of them: the bound on rejections grows with the cases, so that
/// a long run (`PROPTEST_CASES=50000`) tests rather than aborts.
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

/// An offset magnitude from 1e-15 to 1e-6 (log-uniform), with a sign.
fn tiny() -> impl Strategy<Value = f64> {
    (-15.0f64..-6.0, any::<bool>())
        .prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) })
}

fn count_matches<const N: usize>(i: &Intersection<P2, N>) -> bool {
    match i.contact {
        Contact::Crossing => !i.roots.is_empty(),
        Contact::Tangent => i.roots.len() >= 2,
        _ => i.roots.is_empty(),
    }
}

fn check_roots<const N: usize>(
    i: &Intersection<P2, N>,
    s: f64,
    transversal: f64,
    ra: impl Fn(P2) -> f64,
    rb: impl Fn(P2) -> f64,
) -> Result<(), TestCaseError> {
    prop_assert!(count_matches(i), "{i:?}");
    for &x in i.roots.as_slice() {
        // Relative to the inputs' scale, or to the root's own magnitude when it lies farther out
        // (a parabola's arm): its coordinates carry rounding relative to that.
        let m = s.max(x.coords.norm());
        let b = match i.contact {
            Contact::Tangent => tol::TANGENT_REL * m,
            _ => transversal * m,
        };
        prop_assert!(
            ra(x) <= b && rb(x) <= b,
            "{x} {:e} {:e} bound {b:e} {i:?}",
            ra(x),
            rb(x)
        );
    }
    Ok(())
}

fn circle_at(s: f64, x: f64, y: f64, r: f64) -> Circle {
    Circle::new(p(x * s, y * s), r.abs() * s).unwrap()
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn circle_circle_roots_on_both(s in scale(), x1 in u(), y1 in u(), r1 in 0.05f64..1.0,
                                   x2 in u(), y2 in u(), r2 in 0.05f64..1.0) {
        let (a, b) = (circle_at(s, x1, y1, r1), circle_at(s, x2, y2, r2));
        let i = circle_circle(&a, &b);
        check_roots(&i, s, 1e-13, |x| a.residual(x), |x| b.residual(x))?;
        if i.contact == Contact::Crossing {
            // Branch 0 is left of the line of centres.
            let l = Line::through(a.center(), b.center()).unwrap();
            prop_assert!(l.signed_distance(i.branch(0).unwrap()) >= 0.0);
            prop_assert!(l.signed_distance(i.branch(1).unwrap()) <= 0.0);
        }
        // Scaling by a power of two scales the answer exactly.
        let k = 1024.0;
        let (ak, bk) = (circle_at(s * k, x1, y1, r1), circle_at(s * k, x2, y2, r2));
        let ik = circle_circle(&ak, &bk);
        prop_assert_eq!(i.roots.len(), ik.roots.len());
        for (x, xk) in i.roots.as_slice().iter().zip(ik.roots.as_slice()) {
            prop_assert_eq!(*x * k, *xk);
        }
    }

    #[test]
    fn circle_circle_near_tangency(s in scale(), x1 in u(), y1 in u(), r1 in 0.05f64..1.0,
                                   r2 in 0.05f64..1.0, angle in -3.2f64..3.2,
                                   delta in tiny(), internal in any::<bool>()) {
        let d = if internal { (r1 - r2).abs() } else { r1 + r2 } + delta;
        prop_assume!(d > 0.0);
        let a = circle_at(s, x1, y1, r1);
        let b = Circle::new(a.center() + V2::new(angle.cos(), angle.sin()) * (d * s), r2 * s).unwrap();
        let i = circle_circle(&a, &b);
        check_roots(&i, s, 1e-13, |x| a.residual(x), |x| b.residual(x))?;
        // The true gap is `delta` (external) or `-delta` (internal), up to rounding of the
        // centre coordinates.
        let gap = if internal { -delta } else { delta } * s;
        let noise = 1e-14 * s;
        let t = tol::TANGENT_REL * tol::scale(&[a.center().x, a.center().y, b.center().x, b.center().y, r1 * s, r2 * s]);
        // Missing by at most the tolerance is a tangency; overlapping at all is a crossing.
        match i.contact {
            Contact::Tangent => prop_assert!(gap >= -noise && gap <= t + noise),
            Contact::Disjoint { gap: g } => prop_assert!(gap > t - noise && (g - gap).abs() <= noise),
            Contact::Crossing => prop_assert!(gap < noise),
            c => prop_assert!(false, "{c:?}"),
        }
    }

    #[test]
    fn circle_circle_nearly_coincident(s in scale(), x1 in u(), y1 in u(), r in 0.05f64..1.0,
                                       dx in tiny(), dr in tiny()) {
        let a = circle_at(s, x1, y1, r);
        let b = Circle::new(a.center() + V2::new(dx * s, 0.0), (r + dr) * s).unwrap();
        let i = circle_circle(&a, &b);
        check_roots(&i, s, 1e-13, |x| a.residual(x), |x| b.residual(x))?;
    }

    #[test]
    fn circle_circle_branches_are_stable(s in scale(), x1 in u(), y1 in u(), r1 in 0.2f64..1.0,
                                         x2 in u(), y2 in u(), r2 in 0.2f64..1.0,
                                         ex in u(), ey in u()) {
        let (a, b) = (circle_at(s, x1, y1, r1), circle_at(s, x2, y2, r2));
        let i = circle_circle(&a, &b);
        prop_assume!(i.contact == Contact::Crossing);
        let (l, r) = (i.branch(0).unwrap(), i.branch(1).unwrap());
        prop_assume!((l - r).norm() > 1e-3 * s);
        let b2 = Circle::new(b.center() + V2::new(ex, ey) * (1e-7 * s), b.radius()).unwrap();
        let j = circle_circle(&a, &b2);
        prop_assert_eq!(j.contact, Contact::Crossing);
        prop_assert_eq!(nearest(&j.roots, l), Some(0));
        prop_assert_eq!(nearest(&j.roots, r), Some(1));
    }

    #[test]
    fn circle_circle_chord_is_its_roots(s in scale(), x1 in u(), y1 in u(), r1 in 0.05f64..1.0,
                                        angle in -3.2f64..3.2, r2 in 0.05f64..1.0,
                                        near in 0u8..3, t in tiny()) {
        // Crossing, near external tangency, or near internal tangency.
        let d = match near {
            0 => (r1 + r2) * (0.5 + t.abs() * 1e5),
            1 => (r1 + r2) * (1.0 + t),
            _ => (r1 - r2).abs() * (1.0 + t),
        };
        let a = circle_at(s, x1, y1, r1);
        let b = circle_at(s, x1 + d * angle.cos(), y1 + d * angle.sin(), r2);
        let i = circle_circle(&a, &b);
        match circle_circle_chord(&a, &b) {
            Ok(chord) => {
                for k in 0..3 {
                    prop_assert_eq!(chord.root(k), i.branch(k));
                }
                let touching = chord.half == V2::zeros();
                prop_assert_eq!(i.contact, if touching { Contact::Tangent } else { Contact::Crossing });
            }
            Err(contact) => {
                prop_assert_eq!(contact, i.contact);
                prop_assert!(i.roots.is_empty());
            }
        }
    }

    /// A root from either centre is that circle's radius to a few roundings of the sizes
    /// involved (the radii and the distance, relative to this radius), however far the circles
    /// are from the origin (up to 10^4 times their size), where the root minus the centre
    /// loses the digits the coordinates take; and it is that difference to their rounding.
    #[test]
    fn chord_roots_from_each_centre(s in scale(), x1 in u(), y1 in u(), r1 in 0.05f64..1.0,
                                    angle in -3.2f64..3.2, r2 in 0.05f64..1.0,
                                    along in 0.05f64..0.95, far in 0f64..1e4) {
        let (lo, hi) = ((r1 - r2).abs(), r1 + r2);
        let d = lo + (hi - lo) * along;
        let a = circle_at(s, x1 + far, y1, r1);
        let b = circle_at(s, x1 + far + d * angle.cos(), y1 + d * angle.sin(), r2);
        let chord = circle_circle_chord(&a, &b);
        prop_assume!(chord.is_ok());
        let chord = chord.unwrap();
        for k in 0..2 {
            let root = chord.root(k).unwrap();
            for (c, from_c) in [(&a, chord.root_from_a(k)), (&b, chord.root_from_b(k))] {
                let v = from_c.unwrap();
                let sizes = (r1 + r2 + d) * s / c.radius();
                prop_assert!((v.norm() / c.radius() - 1.0).abs() <= 4.0 * f64::EPSILON * sizes,
                    "|{v:?}| = {} against {}", v.norm(), c.radius());
                let coordinates = c.center().coords.norm() + c.radius();
                prop_assert!((v - (root - c.center())).norm() <= 4.0 * f64::EPSILON * coordinates);
            }
        }
        prop_assert_eq!(chord.root_from_a(2), None);
        prop_assert_eq!(chord.root_from_b(2), None);
    }

    #[test]
    fn line_circle_roots_and_branches(s in scale(), px in u(), py in u(), angle in -3.2f64..3.2,
                                      cx in u(), cy in u(), r in 0.05f64..1.0, e in u()) {
        let l = Line::new(p(px * s, py * s), V2::new(angle.cos(), angle.sin())).unwrap();
        let c = circle_at(s, cx, cy, r);
        let i = line_circle(&l, &c);
        check_roots(&i, s, 1e-13, |x| l.residual(x), |x| c.residual(x))?;
        if i.contact == Contact::Crossing {
            let (a, b) = (i.branch(0).unwrap(), i.branch(1).unwrap());
            prop_assert!(l.param_of(a) < l.param_of(b));
            if (a - b).norm() > 1e-3 * s {
                let l2 = Line::new(l.point() + l.normal() * (1e-7 * s * e), V2::new((angle + 1e-9).cos(), (angle + 1e-9).sin())).unwrap();
                let j = line_circle(&l2, &c);
                prop_assert_eq!(nearest(&j.roots, a), Some(0));
                prop_assert_eq!(nearest(&j.roots, b), Some(1));
            }
        }
        // The ray from the line's point keeps the line's slots.
        let ray = Ray::new(l.point(), l.dir()).unwrap();
        let ri = ray_circle(&ray, &c);
        if !ri.roots.is_empty() {
            prop_assert_eq!(ri.roots.len(), i.roots.len());
            for (slot, x) in ri.roots.as_slice().iter().zip(i.roots.as_slice()) {
                if let Some(y) = slot {
                    prop_assert_eq!(y, x);
                    prop_assert!(l.param_of(*x) >= -1e-13 * s);
                }
            }
        }
    }

    #[test]
    fn line_circle_near_tangency(s in scale(), cx in u(), cy in u(), r in 0.05f64..1.0,
                                 angle in -3.2f64..3.2, delta in tiny()) {
        let c = circle_at(s, cx, cy, r);
        let n = V2::new(-angle.sin(), angle.cos());
        let l = Line::new(c.center() - n * ((r + delta) * s), V2::new(angle.cos(), angle.sin())).unwrap();
        let i = line_circle(&l, &c);
        check_roots(&i, s, 1e-13, |x| l.residual(x), |x| c.residual(x))?;
        let t = tol::TANGENT_REL
            * tol::scale(&[l.point().x, l.point().y, c.center().x, c.center().y, c.radius()]);
        // Missing by at most the tolerance is a tangency; overlapping at all is a crossing.
        let noise = 1e-14 * s;
        match i.contact {
            Contact::Tangent => prop_assert!(delta * s >= -noise && delta * s <= 2.0 * t),
            Contact::Disjoint { .. } => prop_assert!(delta * s > 0.5 * t),
            Contact::Crossing => prop_assert!(delta * s < noise),
            other => prop_assert!(false, "{other:?}"),
        }
    }

    #[test]
    fn nearly_parallel_lines(s in scale(), px in u(), py in u(), angle in -3.2f64..3.2,
                             gap in u(), tilt in tiny()) {
        let a = Line::new(p(px * s, py * s), V2::new(angle.cos(), angle.sin())).unwrap();
        let b = Line::new(a.point() + a.normal() * (gap * s), V2::new((angle + tilt).cos(), (angle + tilt).sin())).unwrap();
        let i = line_line(&a, &b);
        prop_assert!(count_matches(&i));
        if let Some(x) = i.branch(0) {
            let m = s.max(x.coords.norm());
            prop_assert!(a.residual(x) <= 1e-13 * m && b.residual(x) <= 1e-13 * m,
                "{x} {:e} {:e}", a.residual(x), b.residual(x));
        } else {
            let parallel = matches!(i.contact, Contact::Parallel { .. } | Contact::Coincident);
            prop_assert!(parallel, "{:?}", i);
        }
        // Rays along them agree with the lines where they cross.
        let (ra, rb) = (Ray::new(a.point(), a.dir()).unwrap(), Ray::new(b.point(), b.dir()).unwrap());
        let j = ray_ray(&ra, &rb);
        prop_assert!(j.roots.len() <= 1);
        let k = line_ray(&a, &rb);
        prop_assert!(k.roots.len() <= 1);
    }
}

proptest! {
    #![proptest_config(config(2048))]

    /// Each direction is unit, passes the point at the offset asked (to 1e-13 of the scale),
    /// and sits on its branch's side; the two are the line's two senses when the offset is 0.
    #[test]
    fn passing_directions_pass_at_the_offset(s in scale(), px in u(), py in u(), qx in u(),
                                             qy in u(), k in -1.0f64..1.0) {
        let (pivot, point) = (p(px * s, py * s), p(qx * s, qy * s));
        let rho = (point - pivot).norm();
        prop_assume!(rho > 1e-3 * s);
        let offset = k * rho;
        let i = passing_directions(pivot, point, offset);
        prop_assert!(matches!(i.contact, Contact::Crossing | Contact::Tangent), "{i:?}");
        for (b, u) in i.roots.as_slice().iter().enumerate() {
            prop_assert!((u.norm() - 1.0).abs() <= 1e-15 * 4.0, "{u}");
            let passes = cross(*u, point - pivot) - offset;
            prop_assert!(passes.abs() <= 1e-13 * s, "branch {b}: {passes:e}");
            let ahead = u.dot(&(point - pivot));
            let on_its_side = if b == 0 { ahead >= -1e-13 * s } else { ahead <= 1e-13 * s };
            prop_assert!(on_its_side, "branch {b}: {ahead:e}");
        }
        if offset == 0.0 {
            prop_assert!((i.roots.as_slice()[0] + i.roots.as_slice()[1]).norm() <= 1e-15 * 4.0);
        }
    }

    /// Near the tangency (the pivot on the circle about the point, to within `delta`): a
    /// miss within the tolerance is one tangent direction, exactly perpendicular; an overlap
    /// crosses, with both directions passing at the offset; beyond, the gap is reported.
    #[test]
    fn passing_directions_near_tangency(s in scale(), px in u(), py in u(), angle in -3.2f64..3.2,
                                        r in 0.05f64..1.0, delta in tiny(), left in any::<bool>()) {
        let pivot = p(px * s, py * s);
        let point = pivot + V2::new(angle.cos(), angle.sin()) * (r * s);
        let offset = (r + delta) * s * if left { 1.0 } else { -1.0 };
        let i = passing_directions(pivot, point, offset);
        let t = tol::TANGENT_REL * tol::scale(&[pivot.x, pivot.y, point.x, point.y, offset]);
        let noise = 1e-14 * s;
        match i.contact {
            Contact::Tangent => {
                prop_assert!(delta * s >= -noise && delta * s <= 2.0 * t);
                let u = i.roots.as_slice()[0];
                prop_assert!(u.dot(&(point - pivot)) == 0.0 || (u.dot(&(point - pivot)) / s).abs() <= 1e-15);
                prop_assert!(cross(u, point - pivot) * offset > 0.0);
            }
            Contact::Crossing => {
                prop_assert!(delta * s < noise);
                for u in i.roots.as_slice() {
                    prop_assert!((cross(*u, point - pivot) - offset).abs() <= 1e-13 * s);
                }
            }
            Contact::Disjoint { gap } => {
                prop_assert!(delta * s > 0.5 * t);
                prop_assert!((gap - delta * s).abs() <= 1e-13 * s, "{gap:e} {:e}", delta * s);
            }
            other => prop_assert!(false, "{other:?}"),
        }
    }
}

#[test]
fn passing_directions_degenerate_cases() {
    let o = p(1.0, 2.0);
    // The pivot is the point: every line passes it.
    assert_eq!(passing_directions(o, o, 0.0).contact, Contact::Coincident);
    // ... but none at a distance.
    assert_eq!(
        passing_directions(o, o, 0.5).contact,
        Contact::Disjoint { gap: 0.5 }
    );
    // The pivot inside the circle about the point: no tangent line.
    let i = passing_directions(o, p(2.0, 2.0), -3.0);
    assert_eq!(i.contact, Contact::Disjoint { gap: 2.0 });
    assert!(i.roots.is_empty());
    // Through two points: ahead is towards the point, behind is away.
    let i = passing_directions(o, p(4.0, 6.0), 0.0);
    assert_eq!(
        i.roots.as_slice(),
        &[V2::new(0.6, 0.8), V2::new(-0.6, -0.8)]
    );
    // A line at distance 1 from a point 2 away, with the point to its left.
    let i = passing_directions(p(0.0, 0.0), p(2.0, 0.0), 1.0);
    let half = 3f64.sqrt() / 2.0;
    let [a, b] = [i.roots.as_slice()[0], i.roots.as_slice()[1]];
    assert!((a - V2::new(half, -0.5)).norm() < 1e-15 && (b - V2::new(-half, -0.5)).norm() < 1e-15);
    // Non-finite offsets never give roots.
    assert!(passing_directions(o, p(2.0, 2.0), f64::NAN)
        .roots
        .is_empty());
}

/// A random conic of each kind at scale `s`.
fn conic(kind: u8, s: f64, a: f64, b: f64, c: f64, d: f64, e: f64) -> Option<Conic> {
    let f1 = p(a * s, b * s);
    match kind % 3 {
        0 => {
            let dir = V2::new(c.cos(), c.sin());
            let l = Line::new(f1 + perp(dir) * (-(0.1 + d.abs()) * s), dir)?;
            Parabola::new(f1, l).map(Conic::from)
        }
        1 => {
            let f2 = p(c * s, d * s);
            Ellipse::new(f1, f2, (f2 - f1).norm() + (0.1 + e.abs()) * s).map(Conic::from)
        }
        _ => {
            let f2 = p(c * s, d * s + 0.2 * s);
            Hyperbola::new(f1, f2, (f2 - f1).norm() * e * 0.95).map(Conic::from)
        }
    }
}

fn conic_strategy() -> impl Strategy<Value = (u8, f64, f64, f64, f64, f64)> {
    (0u8..3, u(), u(), -3.2f64..3.2, u(), u())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn line_conic_roots_on_both(s in scale(), (kind, a, b, c, d, e) in conic_strategy(),
                                px in u(), py in u(), angle in -3.2f64..3.2) {
        let Some(k) = conic(kind, s, a, b, c, d, e) else { return Ok(()) };
        let l = Line::new(p(px * s, py * s), V2::new(angle.cos(), angle.sin())).unwrap();
        let i = line_conic(&l, &k);
        check_roots(&i, 3.5 * s, 1e-12, |x| l.residual(x), |x| k.residual(x))?;
        if i.roots.len() == 2 && i.contact == Contact::Crossing {
            prop_assert!(l.param_of(i.branch(0).unwrap()) < l.param_of(i.branch(1).unwrap()));
        }
    }

    #[test]
    fn line_conic_near_tangency(s in scale(), (kind, a, b, c, d, e) in conic_strategy(),
                                t in u(), delta in tiny()) {
        let Some(k) = conic(kind, s, a, b, c, d, e) else { return Ok(()) };
        // The tangent at a point of the conic, moved off by delta along the normal.
        // A parabola's parameter is a length: scale it.
        let (t, h) = if kind % 3 == 0 { (t * s, 1e-6 * s) } else { (t, 1e-6) };
        let x = k.at(t);
        let tan = (k.at(t + h) - k.at(t - h)).normalize();
        let l = Line::new(x + perp(tan) * (delta * s), tan).unwrap();
        let i = line_conic(&l, &k);
        check_roots(&i, 3.5 * s, 1e-12, |x| l.residual(x), |x| k.residual(x))?;
    }

    #[test]
    fn circle_conic_roots_on_both(s in scale(), (kind, a, b, c, d, e) in conic_strategy(),
                                  cx in u(), cy in u(), r in 0.05f64..1.5) {
        let Some(k) = conic(kind, s, a, b, c, d, e) else { return Ok(()) };
        let circ = circle_at(s, cx, cy, r);
        let i = circle_conic(&circ, &k);
        check_roots(&i, 3.5 * s, 1e-12, |x| circ.residual(x), |x| k.residual(x))?;
        // Ordered by the conic's parameter.
        let ts: Vec<f64> = i.roots.as_slice().iter().map(|&x| k.param_of(x)).collect();
        prop_assert!(ts.windows(2).all(|w| w[0] <= w[1] + 1e-9), "{ts:?}");
    }

    #[test]
    fn circle_conic_near_tangency(s in scale(), (kind, a, b, c, d, e) in conic_strategy(),
                                  t in u(), r in 0.05f64..1.5, delta in tiny()) {
        let Some(k) = conic(kind, s, a, b, c, d, e) else { return Ok(()) };
        // A circle touching the conic at X(t) from its normal side, moved by delta.
        // A parabola's parameter is a length: scale it.
        let (t, h) = if kind % 3 == 0 { (t * s, 1e-6 * s) } else { (t, 1e-6) };
        let x = k.at(t);
        let tan = (k.at(t + h) - k.at(t - h)).normalize();
        let circ = Circle::new(x + perp(tan) * ((r + delta) * s), r * s).unwrap();
        let i = circle_conic(&circ, &k);
        check_roots(&i, 3.5 * s, 1e-12, |x| circ.residual(x), |x| k.residual(x))?;
    }

    #[test]
    fn conic_conic_roots_on_both(s in scale(), (k1, a, b, c, d, e) in conic_strategy(),
                                 (k2, a2, b2, c2, d2, e2) in conic_strategy()) {
        let Some(ka) = conic(k1, s, a, b, c, d, e) else { return Ok(()) };
        let Some(kb) = conic(k2, s, a2, b2, c2, d2, e2) else { return Ok(()) };
        let i = conic_conic(&ka, &kb);
        check_roots(&i, 3.5 * s, 1e-12, |x| ka.residual(x), |x| kb.residual(x))?;
        let ts: Vec<f64> = i.roots.as_slice().iter().map(|&x| ka.param_of(x)).collect();
        prop_assert!(ts.windows(2).all(|w| w[0] <= w[1] + 1e-9), "{ts:?}");
    }

    #[test]
    fn conic_branches_are_stable(s in scale(), (kind, a, b, c, d, e) in conic_strategy(),
                                 cx in u(), cy in u(), r in 0.05f64..1.5, ex in u(), ey in u()) {
        let Some(k) = conic(kind, s, a, b, c, d, e) else { return Ok(()) };
        let circ = circle_at(s, cx, cy, r);
        let i = circle_conic(&circ, &k);
        prop_assume!(i.contact == Contact::Crossing && i.roots.len() >= 2);
        let xs = i.roots.as_slice();
        let sep = xs.windows(2).map(|w| (w[0] - w[1]).norm()).fold(f64::INFINITY, f64::min);
        prop_assume!(sep > 1e-3 * s);
        // Ellipse parameters wrap at π: stay away from it.
        prop_assume!(xs.iter().all(|&x| (k.param_of(x).abs() - std::f64::consts::PI).abs() > 1e-3));
        let c2 = Circle::new(circ.center() + V2::new(ex, ey) * (1e-9 * s), circ.radius()).unwrap();
        let j = circle_conic(&c2, &k);
        prop_assert_eq!(j.roots.len(), i.roots.len());
        for (n, &x) in xs.iter().enumerate() {
            prop_assert_eq!(nearest(&j.roots, x), Some(n));
        }
    }
}

proptest! {
    #![proptest_config(config(512))]

    /// The rotation between two vectors turns the first onto the direction of the second and is
    /// unit to rounding, whether their lengths are equal to rounding (the plan's case, taken
    /// without a square root), nearly equal, or far apart (the exact path).
    #[test]
    fn rotation_between_is_unit_and_exact(s in scale(), angle in -3.2f64..3.2, turn in -3.2f64..3.2,
                                          stretch in prop_oneof![Just(0.0), tiny(), -0.9f64..9.0]) {
        use gcs_runtime::frame::rotation_between2;
        use gcs_runtime::nalgebra::UnitComplex;
        let a = UnitComplex::new(angle) * V2::new(s, 0.0);
        let b = (UnitComplex::new(turn) * a) * (1.0 + stretch);
        let r = rotation_between2(&a, &b);
        prop_assert!((r.re * r.re + r.im * r.im - 1.0).abs() <= 4.0 * f64::EPSILON);
        // Unit to 4 ulps leaves the turned radius up to 2 eps long or short; turning and
        // scaling it, and normalising `b`, round by up to 4 eps more.
        let turned = r * a / s;
        let want = b / b.norm();
        prop_assert!((turned - want).norm() <= 6.0 * f64::EPSILON, "{} vs {}", turned, want);
    }

    #[test]
    fn rotation_on_circle_is_unit_and_exact(s in scale(), angle in -3.2f64..3.2, turn in -3.2f64..3.2,
                                            stretch in prop_oneof![Just(0.0), tiny(), -0.9f64..9.0],
                                            radius_off in prop_oneof![Just(0.0), tiny()]) {
        // A radius of the circle turned onto another, of its length to rounding or not at
        // all, with the radius as the plan knows it (itself off by rounding or more).
        use gcs_runtime::frame::{direction_at, rotation_from_x, rotation_on_circle};
        use gcs_runtime::nalgebra::UnitComplex;
        let a = UnitComplex::new(angle) * V2::new(s, 0.0);
        let b = (UnitComplex::new(turn) * a) * (1.0 + stretch);
        let r = rotation_on_circle(&a, &b, s * (1.0 + radius_off));
        prop_assert!((r.re * r.re + r.im * r.im - 1.0).abs() <= 4.0 * f64::EPSILON);
        // Unit to 4 ulps leaves the turned radius up to 2 eps long or short; turning and
        // scaling it, and normalising `b`, round by up to 4 eps more.
        let turned = r * a / s;
        let want = b / b.norm();
        prop_assert!((turned - want).norm() <= 6.0 * f64::EPSILON, "{} vs {}", turned, want);
        // The x axis turned by `angle`, and the rotation that does it.
        // (`direction_at`'s sine and cosine are within 2 ulps of the system library's.)
        let d = direction_at(angle);
        prop_assert!((d - UnitComplex::new(angle) * V2::x()).norm() <= 4.0 * f64::EPSILON);
        prop_assert_eq!(rotation_from_x(&d) * V2::x(), d);
    }
}

/// A point's distance from the origin, at least the scale: what its coordinates round
/// relative to.
fn magnitude(s: f64, points: &[P2]) -> f64 {
    points.iter().fold(s, |m, x| m.max(x.coords.norm()))
}

proptest! {
    #![proptest_config(config(512))]

    /// The mirror image across a line: an involution that keeps the distance from the line
    /// (on the other side) and from any point of it, whose segment with the point is
    /// perpendicular to the line and bisected by it, for points anywhere, near the line, on
    /// it, and far out along it.
    #[test]
    fn mirror_across_a_line(s in scale(), bx in u(), by in u(), angle in -3.2f64..3.2,
                            along in prop_oneof![u(), -1e6f64..1e6],
                            off in prop_oneof![Just(0.0), tiny(), u()]) {
        let line = Line::new(p(bx * s, by * s), V2::new(angle.cos(), angle.sin())).unwrap();
        let x = line.at(along * s) + line.normal() * (off * s);
        let q = line.mirror(x);
        let m = magnitude(s, &[x, q]);
        let eps = 1e-13 * m;
        prop_assert!((line.signed_distance(q) + line.signed_distance(x)).abs() <= eps,
            "{:e} {:e}", line.signed_distance(q), line.signed_distance(x));
        prop_assert!((line.mirror(q) - x).norm() <= eps);
        prop_assert!(line.signed_distance(midpoint(x, q)).abs() <= eps);
        prop_assert!((q - x).dot(&line.dir()).abs() <= eps);
        let base = line.point();
        prop_assert!(((q - base).norm() - (x - base).norm()).abs() <= eps);
        // Twice the offset apart, across the line.
        prop_assert!(((q - x).norm() - 2.0 * (off * s).abs()).abs() <= eps);
        // The base point is its own image, exactly; the free function is the method.
        prop_assert_eq!(line.mirror(base), base);
        prop_assert_eq!(mirror(base, line.dir(), x), q);
    }

    /// The midpoint and the reflection through a point: the midpoint is the same whichever
    /// point comes first, as far from each, and a point reflected through the midpoint is the
    /// other one; a point reflected through a centre has that centre as its midpoint with it.
    #[test]
    fn midpoint_and_reflection_through_a_point(s in scale(), ax in u(), ay in u(),
                                               bx in u(), by in u(),
                                               near in prop_oneof![Just(0.0), tiny(), u()]) {
        let a = p(ax * s, ay * s);
        // `b` anywhere, close to `a`, or at `a`.
        let b = a + (p(bx * s, by * s) - a) * near;
        let mid = midpoint(a, b);
        let m = magnitude(s, &[a, b]);
        let eps = 4.0 * f64::EPSILON * m;
        prop_assert_eq!(mid, midpoint(b, a));
        prop_assert!(((mid - a).norm() - (mid - b).norm()).abs() <= eps);
        prop_assert!((reflect_through(a, mid) - b).norm() <= eps);
        prop_assert!((midpoint(a, reflect_through(a, b)) - b).norm() <= eps);
        prop_assert!((reflect_through(reflect_through(a, b), b) - a).norm() <= eps);
        prop_assert_eq!(midpoint(a, a), a);
        prop_assert_eq!(reflect_through(a, a), a);
    }
}

proptest! {
    #![proptest_config(config(20_000))]

    /// An outer iteration's trial directions, turned from its start by small-angle
    /// polynomials: within four units in the last place of `direction_at` (the turn's
    /// rounding on top of each sine's and cosine's ulp), and unit to as much, for starts
    /// anywhere on the turn and trials from tiny differences to the polynomials' reach and
    /// beyond it (where `direction_at` itself answers).
    #[test]
    fn directions_near_a_start_are_direction_at(
        start in -10.0f64..10.0,
        turn in prop_oneof![
            -gcs_runtime::frame::DirectionsNear::REACH..=gcs_runtime::frame::DirectionsNear::REACH,
            -1e-9f64..1e-9,
            -1.0f64..1.0,
        ],
    ) {
        use gcs_runtime::frame::{direction_at, DirectionsNear};
        let near = DirectionsNear::new(start);
        let (got, want) = (near.at(start + turn), direction_at(start + turn));
        prop_assert!((got - want).norm() <= 4.0 * f64::EPSILON, "{start} {turn}: {got:?} {want:?}");
        prop_assert!((got.norm() - 1.0).abs() <= 4.0 * f64::EPSILON);
    }
}
