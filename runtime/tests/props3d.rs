//! Properties of the 3d kernel on random and near-degenerate inputs, at scales from 1e-6 to 1e6:
//! roots lie on both loci, the number of roots matches the classification, branches stay put
//! under small perturbations, and actions are rigid and keep their invariants.
//!
//! Bounds (see the `intersect3d` module docs): outside tangency a root is within `1e-13` of
//! `max(scale, |root|)` of each locus; a tangent root within `TANGENT_REL * scale / 2` (plus the
//! same rounding); a non-coplanar circle-circle root within `TANGENT_REL * scale`. Near
//! tangency, a miss of at most `TANGENT_REL * scale` touches and any overlap crosses.

use gcs_runtime::frame::{perpendicular, rotation_about_axis, Frame3};
use gcs_runtime::intersect3d::*;
use gcs_runtime::locus3d::*;
use gcs_runtime::tol::TANGENT_REL;
use gcs_runtime::{Contact, Intersection};
use nalgebra::{Point3, UnitQuaternion, Vector3};
use proptest::prelude::*;

const REL: f64 = 1e-13;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 256,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A scale `10^e`, `e` in [-6, 6].
fn scale() -> impl Strategy<Value = f64> {
    (-6.0f64..6.0).prop_map(|e| 10f64.powf(e))
}

fn vec3() -> impl Strategy<Value = Vector3<f64>> {
    prop::array::uniform3(-1.0f64..1.0).prop_map(Vector3::from)
}

/// A unit vector (a fixed one when the random vector is too short to normalize well).
fn unit() -> impl Strategy<Value = Vector3<f64>> {
    vec3().prop_map(|v| {
        if v.norm() > 0.1 {
            v.normalize()
        } else {
            Vector3::new(0.6, 0.0, 0.8)
        }
    })
}

/// A signed offset of magnitude in [1e-15, 1e-6] (log-uniform).
fn tiny() -> impl Strategy<Value = f64> {
    ((-15.0f64..-6.0), any::<bool>())
        .prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) })
}

/// A unit vector perpendicular to `n`, picked by `v`.
fn perp_to(n: &Vector3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
    let w = v - n * n.dot(v);
    if w.norm() > 1e-3 {
        // Once more: one projection leaves a component along `n` of rounding times |v| / |w|,
        // up to 1000 times rounding here, enough to take a circle "through" a point off it.
        let w = w - n * n.dot(&w);
        w.normalize()
    } else {
        perpendicular(n).normalize()
    }
}

fn inf_norm(p: &Point3<f64>) -> f64 {
    p.coords.amax()
}

/// The scale the kernel uses for these inputs: the largest absolute coordinate or radius.
fn mag(points: &[Point3<f64>], lengths: &[f64]) -> f64 {
    let mut m: f64 = 0.0;
    for p in points {
        m = m.max(inf_norm(p));
    }
    for l in lengths {
        m = m.max(l.abs());
    }
    m
}

/// Checks the roots of a point intersection: count against contact, and distance to both loci.
fn check_points<const N: usize>(
    x: &Intersection<Point3<f64>, N>,
    a: &dyn Locus3,
    b: &dyn Locus3,
    s: f64,
    loose: f64,
) -> Result<(), TestCaseError> {
    let roots = x.roots.as_slice();
    match x.contact {
        Contact::Crossing => prop_assert_eq!(roots.len(), N),
        Contact::Tangent => {
            prop_assert_eq!(roots.len(), N);
            prop_assert!(roots.iter().all(|r| r == &roots[0]));
        }
        Contact::Disjoint { gap } | Contact::Parallel { gap } => {
            prop_assert!(roots.is_empty());
            prop_assert!(gap >= 0.0, "gap {}", gap);
        }
        Contact::Coincident | Contact::ZeroRadius => prop_assert!(roots.is_empty()),
    }
    for r in roots {
        let bound = if x.contact == Contact::Tangent {
            0.5 * TANGENT_REL * s + REL * s
        } else {
            loose.max(REL * s.max(inf_norm(r)))
        };
        let (da, db) = (a.distance(r), b.distance(r));
        prop_assert!(
            da <= bound && db <= bound,
            "{:?}: {} {} > {} (s {})",
            x.contact,
            da,
            db,
            bound,
            s
        );
    }
    Ok(())
}

/// Sample points of a circle.
fn circle_samples(c: &Circle3) -> [Point3<f64>; 6] {
    let u = perpendicular(&c.normal).normalize();
    let w = c.normal.cross(&u);
    let mut out = [c.center; 6];
    for (i, o) in out.iter_mut().enumerate() {
        let t = i as f64 * 1.1;
        *o = c.center + (u * t.cos() + w * t.sin()) * c.radius;
    }
    out
}

fn check_circle(
    x: &Intersection<Circle3, 1>,
    a: &dyn Locus3,
    b: &dyn Locus3,
    s: f64,
) -> Result<(), TestCaseError> {
    let n = x.roots.len();
    match x.contact {
        Contact::Crossing | Contact::Tangent => prop_assert_eq!(n, 1),
        _ => prop_assert_eq!(n, 0),
    }
    if let Some(c) = x.branch(0) {
        let bound = if x.contact == Contact::Tangent {
            (0.5 * TANGENT_REL + REL) * s
        } else {
            REL * s
        };
        for p in circle_samples(&c) {
            prop_assert!(
                a.distance(&p) <= bound && b.distance(&p) <= bound,
                "{:?} {} {} > {}",
                x.contact,
                a.distance(&p),
                b.distance(&p),
                bound
            );
        }
    }
    Ok(())
}

/// Branch `i` of `y` is the nearest root of `y` to branch `i` of `x`, and close to it.
fn same_branches<const N: usize>(
    x: &Intersection<Point3<f64>, N>,
    y: &Intersection<Point3<f64>, N>,
    close: f64,
) -> Result<(), TestCaseError> {
    prop_assert_eq!(x.roots.len(), y.roots.len());
    for (i, r) in x.roots.as_slice().iter().enumerate() {
        let q = y.roots.as_slice()[i];
        prop_assert!(
            (q - r).norm() <= close,
            "branch {} moved by {}",
            i,
            (q - r).norm()
        );
    }
    Ok(())
}

/// The contact of loci built with a signed gap `gap` (negative: overlapping), which rounding
/// of the inputs moves by at most `noise`: a miss of at most the tolerance `t` touches, any
/// overlap crosses, a larger miss reports its gap. `noise` is kept well below `t`, so that an
/// overlap snapped to a tangency fails.
fn classified(contact: Contact, gap: f64, t: f64, noise: f64) -> Result<(), TestCaseError> {
    match contact {
        Contact::Tangent => prop_assert!(
            gap >= -noise && gap <= t + noise,
            "tangent at gap {:e} (tolerance {:e})",
            gap,
            t
        ),
        Contact::Crossing => prop_assert!(gap <= noise, "crossing at gap {:e}", gap),
        Contact::Disjoint { gap: g } | Contact::Parallel { gap: g } => {
            prop_assert!(
                gap >= t - noise,
                "apart at gap {:e} (tolerance {:e})",
                gap,
                t
            );
            prop_assert!((g - gap).abs() <= noise, "gap {:e} for {:e}", g, gap);
        }
        other => prop_assert!(false, "{:?} at gap {:e}", other, gap),
    }
    Ok(())
}

/// Rounding of the inputs built at kernel scale `m`: 8 units in the last place, a quarter of
/// the tangency tolerance.
fn noise(m: f64) -> f64 {
    8.0 * f64::EPSILON * m
}

/// Roots well apart: away from tangency, where branches are meaningful.
fn separated<const N: usize>(x: &Intersection<Point3<f64>, N>, s: f64) -> bool {
    let r = x.roots.as_slice();
    x.contact == Contact::Crossing && r.len() == 2 && (r[0] - r[1]).norm() > 1e-2 * s
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn sphere_sphere_random(s in scale(), ca in vec3(), cb in vec3(), ra in 0.05f64..2.0, rb in 0.05f64..2.0) {
        let (a, b) = (Sphere::new(Point3::from(ca * s), ra * s), Sphere::new(Point3::from(cb * s), rb * s));
        let x = sphere_sphere(&a, &b);
        check_circle(&x, &a, &b, mag(&[a.center, b.center], &[a.radius, b.radius]))?;
        let d = (b.center - a.center).norm();
        if let Contact::Disjoint { gap } = x.contact {
            let expect = (d - a.radius - b.radius).max((a.radius - b.radius).abs() - d);
            prop_assert!((gap - expect).abs() <= REL * 4.0 * s);
        }
    }

    #[test]
    fn sphere_sphere_near_tangent(s in scale(), ca in vec3(), dir in unit(), ra in 0.05f64..2.0, rb in 0.05f64..2.0, eps in tiny(), inner in any::<bool>()) {
        let (ra, rb) = (ra * s, rb * s);
        let dist = if inner { (ra - rb).abs() } else { ra + rb } + eps * s;
        let a = Sphere::new(Point3::from(ca * s), ra);
        let b = Sphere::new(a.center + dir * dist, rb);
        prop_assume!(dist > 1e-3 * s);
        let x = sphere_sphere(&a, &b);
        let m = mag(&[a.center, b.center], &[a.radius, b.radius]);
        check_circle(&x, &a, &b, m)?;
        let gap = if inner { -eps * s } else { eps * s };
        classified(x.contact, gap, TANGENT_REL * m, noise(m))?;
    }

    #[test]
    fn sphere_nearly_coincident(s in scale(), ca in vec3(), dir in unit(), r in 0.05f64..2.0, e1 in tiny(), e2 in tiny()) {
        let a = Sphere::new(Point3::from(ca * s), r * s);
        let b = Sphere::new(a.center + dir * (e1 * s), r * s * (1.0 + e2));
        let x = sphere_sphere(&a, &b);
        check_circle(&x, &a, &b, mag(&[a.center, b.center], &[a.radius, b.radius]))?;
    }

    #[test]
    fn sphere_plane_random(s in scale(), c in vec3(), r in 0.05f64..2.0, n in unit(), off in -2.0f64..2.0, eps in tiny(), tangent in any::<bool>()) {
        let sp = Sphere::new(Point3::from(c * s), r * s);
        let o = if tangent { n.dot(&sp.center.coords) + sp.radius + eps * s } else { off * s };
        let pl = Plane::new(n, o);
        let m = mag(&[sp.center], &[sp.radius, pl.offset]);
        let x = sphere_plane(&sp, &pl);
        check_circle(&x, &sp, &pl, m)?;
        if tangent {
            classified(x.contact, eps * s, TANGENT_REL * m, noise(m))?;
        }
    }

    #[test]
    fn plane_plane_nearly_parallel(s in scale(), na in unit(), v in vec3(), oa in -1.0f64..1.0, ob in -1.0f64..1.0, eps in tiny(), random in any::<bool>(), nr in unit()) {
        let nb = if random { nr } else { (na + perp_to(&na, &v) * eps).normalize() };
        let (a, b) = (Plane::new(na, oa * s), Plane::new(nb, ob * s));
        let x = plane_plane(&a, &b);
        match x.contact {
            Contact::Crossing => {
                let l = x.branch(0).unwrap_or_default();
                let bound = REL * s.max(inf_norm(&l.point));
                prop_assert!(a.distance(&l.point) <= bound && b.distance(&l.point) <= bound);
                prop_assert!(l.dir.dot(&a.normal).abs() <= REL && l.dir.dot(&b.normal).abs() <= REL);
                prop_assert!((l.dir.norm() - 1.0).abs() <= REL);
            }
            Contact::Parallel { gap } => prop_assert!((gap - (a.offset - b.offset * a.normal.dot(&b.normal).signum()).abs()).abs() <= REL * s),
            Contact::Coincident => {}
            other => prop_assert!(false, "{:?}", other),
        }
    }

    #[test]
    fn line_plane_nearly_parallel(s in scale(), q in vec3(), n in unit(), v in vec3(), off in -1.0f64..1.0, eps in tiny(), random in any::<bool>(), dr in unit()) {
        let dir = if random { dr } else { (perp_to(&n, &v) + n * eps).normalize() };
        let l = Line3::new(Point3::from(q * s), dir);
        let pl = Plane::new(n, off * s);
        let x = line_plane(&l, &pl);
        match x.contact {
            Contact::Crossing => check_points(&x, &l, &pl, mag(&[l.point], &[pl.offset]), 0.0)?,
            Contact::Parallel { gap } => prop_assert!((gap - pl.distance(&l.point)).abs() <= REL * s),
            Contact::Coincident => prop_assert!(pl.distance(&l.point) <= 1e-9 * s),
            other => prop_assert!(false, "{:?}", other),
        }
    }

    #[test]
    fn line_sphere_random_and_near_tangent(s in scale(), c in vec3(), r in 0.05f64..2.0, dir in unit(), v in vec3(), m in 0.0f64..2.5, eps in tiny(), tangent in any::<bool>(), t0 in -3.0f64..3.0) {
        let sp = Sphere::new(Point3::from(c * s), r * s);
        let side = perp_to(&dir, &v);
        let dist = if tangent { sp.radius + eps * s } else { m * s };
        let l = Line3::new(sp.center + side * dist + dir * (t0 * s), dir);
        let x = line_sphere(&l, &sp);
        let mg = mag(&[l.point, sp.center], &[sp.radius]);
        check_points(&x, &l, &sp, mg, 0.0)?;
        if tangent {
            classified(x.contact, eps * s, TANGENT_REL * mg, noise(mg))?;
        }
        if let Contact::Disjoint { gap } = x.contact {
            prop_assert!((gap - (l.distance(&sp.center) - sp.radius)).abs() <= REL * 4.0 * s);
        }
        if x.contact == Contact::Crossing {
            let r = x.roots.as_slice();
            prop_assert!(l.param(&r[0]) <= l.param(&r[1]));
        }
    }

    #[test]
    fn line_cylinder_random_and_degenerate(s in scale(), o in vec3(), a in unit(), r in 0.05f64..2.0, dir in unit(), v in vec3(), m in 0.0f64..2.5, eps in tiny(), mode in 0u8..3, t0 in -3.0f64..3.0) {
        let cy = Cylinder::new(Line3::new(Point3::from(o * s), a), r * s);
        let radial = perp_to(&a, &v);
        let (ldir, dist) = match mode {
            0 => (dir, m * s),
            1 => (perp_to(&radial, &dir), cy.radius + eps * s), // near tangency
            _ => ((a + perp_to(&a, &dir) * eps).normalize(), m * s), // nearly parallel to the axis
        };
        let l = Line3::new(cy.axis.point + radial * dist + a * (t0 * s), ldir);
        let x = line_cylinder(&l, &cy);
        let mg = mag(&[l.point, cy.axis.point], &[cy.radius]);
        check_points(&x, &l, &cy, mg, 0.0)?;
        // Near tangency, unless the line is along the axis (then `Parallel`, checked above).
        if mode == 1 && l.dir.cross(&a).norm() > 1e-3 {
            classified(x.contact, eps * s, TANGENT_REL * mg, noise(mg))?;
        }
        if x.contact == Contact::Crossing {
            let r = x.roots.as_slice();
            prop_assert!(l.param(&r[0]) <= l.param(&r[1]));
        }
    }

    #[test]
    fn circle_plane_random_and_near_tangent(s in scale(), c in vec3(), nc in unit(), r in 0.05f64..2.0, np in unit(), off in -2.0f64..2.0, eps in tiny(), tangent in any::<bool>()) {
        let ci = Circle3::new(Point3::from(c * s), nc, r * s);
        let pl = if tangent {
            // The plane touching the circle at its point farthest along np's in-plane part.
            let g = perp_to(&nc, &np);
            let t = ci.center + g * (ci.radius + eps * s);
            Plane::from_point_normal(&t, &np)
        } else {
            Plane::new(np, np.dot(&ci.center.coords) + off * s)
        };
        let x = circle_plane(&ci, &pl);
        let m = mag(&[ci.center], &[ci.radius, pl.offset]);
        check_points(&x, &ci, &pl, m, 0.0)?;
        if tangent {
            // The plane is `eps s` beyond the circle's point along `g`, measured along `g`:
            // its distance from the plane is that times the cosine between `g` and `np`.
            let su = nc.cross(&pl.normal).norm();
            prop_assume!(su > 1e-3);
            classified(x.contact, eps * s * su, TANGENT_REL * m, noise(m))?;
        }
    }

    #[test]
    fn circle_sphere_random_and_near_tangent(s in scale(), c in vec3(), nc in unit(), rc in 0.05f64..2.0, q in vec3(), rs in 0.05f64..3.0, eps in tiny(), tangent in any::<bool>()) {
        let ci = Circle3::new(Point3::from(c * s), nc, rc * s);
        let cs = ci.center + q * s;
        let sp = if tangent {
            // Radius equal to the distance to the circle's nearest point, plus a tiny offset.
            let w = cs - ci.center;
            let h = nc.dot(&w);
            let rho = (w - nc * h).norm();
            Sphere::new(cs, h.hypot(rho - ci.radius) + eps * s)
        } else {
            Sphere::new(cs, rs * s)
        };
        let x = circle_sphere(&ci, &sp);
        let m = mag(&[ci.center, sp.center], &[ci.radius, sp.radius]);
        check_points(&x, &ci, &sp, m, 0.0)?;
        if tangent {
            // The sphere reaches `eps s` beyond the circle's nearest point: an overlap.
            prop_assume!((cs - ci.center).cross(&nc).norm() > 1e-3 * s);
            classified(x.contact, -eps * s, TANGENT_REL * m, noise(m))?;
        }
    }

    #[test]
    fn circle_circle_coplanar(s in scale(), c in vec3(), n in unit(), ra in 0.05f64..2.0, rb in 0.05f64..2.0, v in vec3(), d in 0.0f64..4.0, eps in tiny(), mode in 0u8..3, flip in any::<bool>()) {
        let e = perp_to(&n, &v);
        let (ra, rb) = (ra * s, rb * s);
        let dist = match mode { 0 => d * s, 1 => ra + rb + eps * s, _ => (ra - rb).abs() + eps * s };
        let a = Circle3::new(Point3::from(c * s), n, ra);
        let b = Circle3::new(a.center + e * dist, if flip { -n } else { n }, rb);
        let x = circle_circle(&a, &b);
        let m = mag(&[a.center, b.center], &[a.radius, b.radius]);
        check_points(&x, &a, &b, m, 0.0)?;
        if mode != 0 && dist > 1e-3 * s {
            // Apart by `eps s` (external), or nested by `-eps s` (internal).
            let gap = if mode == 1 { eps * s } else { -eps * s };
            classified(x.contact, gap, TANGENT_REL * m, noise(m))?;
        }
    }

    #[test]
    fn circle_circle_nearly_coincident(s in scale(), c in vec3(), n in unit(), r in 0.05f64..2.0, v in vec3(), e1 in tiny(), e2 in tiny()) {
        let a = Circle3::new(Point3::from(c * s), n, r * s);
        let b = Circle3::new(a.center + perp_to(&n, &v) * (e1 * s), n, r * s * (1.0 + e2));
        let x = circle_circle(&a, &b);
        check_points(&x, &a, &b, mag(&[a.center, b.center], &[a.radius, b.radius]), 0.0)?;
    }

    #[test]
    fn circle_circle_spatial_through_a_common_point(s in scale(), p in vec3(), na in unit(), nb in unit(), va in vec3(), vb in vec3(), ra in 0.05f64..2.0, rb in 0.05f64..2.0) {
        prop_assume!(na.cross(&nb).norm() > 1e-3);
        let p = Point3::from(p * s);
        let a = Circle3::new(p - perp_to(&na, &va) * (ra * s), na, ra * s);
        let b = Circle3::new(p - perp_to(&nb, &vb) * (rb * s), nb, rb * s);
        let x = circle_circle(&a, &b);
        prop_assert!(matches!(x.contact, Contact::Crossing | Contact::Tangent), "{:?}", x.contact);
        let m = mag(&[a.center, b.center], &[a.radius, b.radius]);
        check_points(&x, &a, &b, m, (TANGENT_REL + REL) * m)?;
        let near = x.roots.as_slice().iter().map(|r| (r - p).norm()).fold(f64::INFINITY, f64::min);
        prop_assert!(near <= 1e-9 * s, "common point missed by {}", near);
    }

    #[test]
    fn circle_circle_spatial_random(s in scale(), ca in vec3(), cb in vec3(), na in unit(), nb in unit(), ra in 0.05f64..2.0, rb in 0.05f64..2.0) {
        let a = Circle3::new(Point3::from(ca * s), na, ra * s);
        let b = Circle3::new(Point3::from(cb * s), nb, rb * s);
        let x = circle_circle(&a, &b);
        let m = mag(&[a.center, b.center], &[a.radius, b.radius]);
        check_points(&x, &a, &b, m, (TANGENT_REL + REL) * m)?;
        if let Contact::Disjoint { gap } = x.contact {
            // The gap is a distance between actual points of the circles: an upper bound.
            prop_assert!(gap.is_finite() && gap > 0.0);
        }
    }

    #[test]
    fn plane_cylinder_sections(s in scale(), o in vec3(), a in unit(), r in 0.05f64..2.0, n in unit(), v in vec3(), off in -3.0f64..3.0, eps in tiny(), mode in 0u8..3) {
        let cy = Cylinder::new(Line3::new(Point3::from(o * s), a), r * s);
        let (normal, offset) = match mode {
            0 => (n, n.dot(&cy.axis.point.coords) + off * s),
            1 => { let m = perp_to(&a, &v); (m, m.dot(&cy.axis.point.coords) + off * s) } // parallel
            _ => { let m = perp_to(&a, &v); (m, m.dot(&cy.axis.point.coords) + cy.radius + eps * s) } // tangent
        };
        let pl = Plane::new(normal, offset);
        let x = plane_cylinder(&pl, &cy);
        let roots = x.roots.as_slice();
        match x.contact {
            Contact::Crossing => prop_assert!(!roots.is_empty()),
            Contact::Tangent => prop_assert!(roots.len() == 2 && roots[0] == roots[1]),
            _ => prop_assert!(roots.is_empty()),
        }
        let m = mag(&[cy.axis.point], &[pl.offset, cy.radius]);
        if mode == 2 {
            classified(x.contact, eps * s, TANGENT_REL * m, noise(m))?;
        }
        let bound = if x.contact == Contact::Tangent { (0.5 * TANGENT_REL + REL) * m } else { 0.0 };
        for sec in roots {
            let pts: [Point3<f64>; 5] = match sec {
                CylinderSection::Ellipse(e) => [e.point_at(0.0), e.point_at(1.0), e.point_at(2.0), e.point_at(3.0), e.point_at(4.5)],
                CylinderSection::Line(l) => [l.at(0.0), l.at(s), l.at(-s), l.at(3.0 * s), l.at(-5.0 * s)],
            };
            for p in &pts {
                let b = bound.max(REL * m.max(inf_norm(p)));
                prop_assert!(pl.distance(p) <= b && cy.distance(p) <= b, "{} {} > {}", pl.distance(p), cy.distance(p), b);
            }
        }
    }

    #[test]
    fn branches_are_stable_under_small_perturbations(s in scale(), c in vec3(), n in unit(), r in 0.2f64..2.0, q in vec3(), rs in 0.2f64..3.0, dir in unit(), np in unit(), off in -1.0f64..1.0, jiggle in vec3()) {
        let j = jiggle * (1e-9 * s);
        let close = 1e-5 * s;
        // Circle-sphere.
        let ci = Circle3::new(Point3::from(c * s), n, r * s);
        let sp = Sphere::new(ci.center + q * s, rs * s);
        let x = circle_sphere(&ci, &sp);
        if separated(&x, s) {
            let y = circle_sphere(&ci, &Sphere::new(sp.center + j, sp.radius));
            same_branches(&x, &y, close)?;
        }
        // Circle-plane.
        let pl = Plane::new(np, np.dot(&ci.center.coords) + off * r * s);
        let x = circle_plane(&ci, &pl);
        if separated(&x, s) {
            let y = circle_plane(&Circle3::new(ci.center + j, ci.normal, ci.radius), &pl);
            same_branches(&x, &y, close)?;
        }
        // Line-sphere.
        let l = Line3::new(sp.center + q * (0.5 * rs * s), dir);
        let x = line_sphere(&l, &sp);
        if separated(&x, s) {
            let y = line_sphere(&Line3::new(l.point + j, l.dir), &sp);
            same_branches(&x, &y, close)?;
        }
        // Coplanar circle-circle.
        let b = Circle3::new(ci.center + perp_to(&n, &q) * (q.norm() * 2.0 * s), n, rs * s);
        let x = circle_circle(&ci, &b);
        if separated(&x, s) {
            let y = circle_circle(&ci, &Circle3::new(b.center + j - n * n.dot(&j), n, b.radius));
            same_branches(&x, &y, close)?;
        }
    }

    #[test]
    fn actions_are_rigid_and_keep_invariants(s in scale(), o in vec3(), axis0 in unit(), a0 in -3.0f64..3.0, p1 in vec3(), p2 in vec3(), pivot in vec3(), axis in vec3(), angle in -7.0f64..7.0, t in vec3(), k in 0.1f64..10.0) {
        let mut f = Frame3::new(Point3::from(o * s), rotation_about_axis(&axis0, a0));
        let (l1, l2) = (Point3::from(p1 * s), Point3::from(p2 * s));
        let d = (f.point_to_global(&l1) - f.point_to_global(&l2)).norm();
        // Translate: distances kept.
        f.translate(&(t * s));
        prop_assert!(((f.point_to_global(&l1) - f.point_to_global(&l2)).norm() - d).abs() <= REL * 8.0 * s);
        // Rotate about a point and axis: distances kept, the pivot and the axis line fixed.
        let c = Point3::from(pivot * s);
        let lc = f.point_to_local(&c);
        let la = f.point_to_local(&(c + axis * s));
        f.rotate_about(&c, &axis, angle);
        prop_assert!(((f.point_to_global(&l1) - f.point_to_global(&l2)).norm() - d).abs() <= REL * 8.0 * s);
        prop_assert!((f.point_to_global(&lc) - c).norm() <= REL * 8.0 * s);
        prop_assert!((f.point_to_global(&la) - (c + axis * s)).norm() <= REL * 8.0 * s);
        prop_assert!((f.rotation.norm() - 1.0).abs() <= REL);
        // Scale about a point: the centre fixed, distances from it scaled.
        let before = f.origin - c;
        let mut dims = [s];
        f.scale_about(&c, k, &mut dims);
        prop_assert!(((f.origin - c) - before * k).norm() <= REL * 16.0 * s * k.max(1.0));
        prop_assert!((dims[0] - s * k).abs() <= REL * s * k);
        // Local and global round trip.
        let g = f.point_to_global(&l1);
        prop_assert!((f.point_to_local(&g) - l1).norm() <= REL * 64.0 * s * k.max(1.0));
        let q: UnitQuaternion<f64> = f.rotation;
        prop_assert!((q * (q.inverse() * axis) - axis).norm() <= REL);
    }
}

proptest! {
    /// A marker's z and x axes turned together about an axis that z lies within 1e-12 to 1e-2
    /// rad of: the angle `signed_angle3_both` reads off the two pairs is the turn to about
    /// rounding, although z's own angle about the axis is fixed only to rounding over its
    /// distance from it.
    #[test]
    fn a_turn_read_off_z_and_x_together_is_exact_near_the_axis(
        axis in unit(),
        across in unit(),
        off in -12.0f64..-2.0,
        spin in -3.1f64..3.1,
        turn in -3.1f64..3.1,
    ) {
        let tilt = perp_to(&axis, &across);
        let z = (axis + tilt * 10f64.powf(off)).normalize();
        // An x axis across z, at `spin` about it.
        let x = rotation_about_axis(&z, spin) * perp_to(&z, &tilt);
        let q = rotation_about_axis(&axis, turn);
        let (z1, x1) = (q * z, q * x);
        let both = gcs_runtime::frame::signed_angle3_both([&z, &x], [&z1, &x1], &axis);
        prop_assert!((both - turn).abs() <= 1e-14, "{both} for {turn}, z {off} off the axis");
        // Either pair alone gives the same angle when it is well across the axis.
        let from_x = gcs_runtime::frame::signed_angle3(&x, &x1, &axis);
        let x_across = (x - axis * axis.dot(&x)).norm();
        if x_across > 0.5 {
            prop_assert!((from_x - turn).abs() <= 1e-14);
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// A z axis within 1e-12 to 1e-2 rad of the axis it turns about, and a point off the axis
    /// that must land on a line or in a plane after the turn (a joint's point, which a slide
    /// then brings home): the turn `turn_reaching_line` and `_plane` read off the two is the
    /// turn to rounding at the point's distance from the axis, where z's own angle is off by
    /// rounding over its distance from the axis (up to 1e-4 rad).
    #[test]
    fn a_turn_reaching_a_point_is_exact_near_the_axis(
        axis in unit(),
        across in unit(),
        off in -12.0f64..-2.0,
        turn in -3.1f64..3.1,
        size in scale(),
        pivot in vec3(),
        arm in 0.2f64..1.0,
        along in -1.0f64..1.0,
        slide in unit(),
        shift in -1.0f64..1.0,
    ) {
        let tilt = perp_to(&axis, &across);
        let z = (axis + tilt * 10f64.powf(off)).normalize();
        let pivot = Point3::from(pivot * size);
        let point = pivot + (tilt * arm + axis * along) * size;
        let q = rotation_about_axis(&axis, turn);
        let (z1, reached) = (q * z, pivot + q * (point - pivot));
        // How fast the point moves across the slide's line, and along the plane's normal.
        let velocity = axis.cross(&(reached - pivot)) / (arm * size);
        let across_line = (velocity - slide * slide.dot(&velocity)).norm();
        let along_normal = slide.dot(&velocity).abs();
        let wrap = |a: f64| (a - turn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        // Rounding at the point's distance, in angle: the coordinates' size over the arm.
        let bound = 64.0 * f64::EPSILON * (pivot.coords.norm() + 2.0 * size) / (arm * size);
        let at = (&pivot, &axis);
        if across_line > 0.3 {
            let line = Line3::new(reached + slide * shift * size, slide);
            let angle = gcs_runtime::fragment3::turn_reaching_line([&z, &z1], at, &point, &line, None);
            prop_assert!(wrap(angle).abs() <= bound, "line: {angle} for {turn}, z 1e{off} off");
        }
        if along_normal > 0.3 {
            let inside = perp_to(&slide, &tilt) * shift * size;
            let plane = Plane::new(slide, slide.dot(&(reached + inside).coords));
            let angle = gcs_runtime::fragment3::turn_reaching_plane([&z, &z1], at, &point, &plane, None);
            prop_assert!(wrap(angle).abs() <= bound, "plane: {angle} for {turn}, z 1e{off} off");
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// As above on a screw: after the turn the cluster slides along the screw's axis by the
    /// helix's advance for its turn, so where the joint's point lands depends on the turn
    /// through the pitch; `turn_reaching_plane` with the `Screw` follows it there, where the
    /// z axis (1e-12 to 1e-2 rad off the axis) decides the turn only to rounding over that.
    #[test]
    fn a_turn_reaching_a_point_on_a_screw_is_exact_near_the_axis(
        axis in unit(),
        across in unit(),
        off in -12.0f64..-2.0,
        turn in -3.0f64..3.0,
        pivot in vec3(),
        arm in 0.2f64..1.0,
        along in -1.0f64..1.0,
        normal in unit(),
        pitch in 0.2f64..2.0,
        x_spin in -3.1f64..3.1,
        start in -1.0f64..1.0,
    ) {
        use gcs_runtime::fragment3::{Helix, Screw};
        use gcs_runtime::frame::{helix_advance, signed_angle3};
        let tilt = perp_to(&axis, &across);
        let z = (axis + tilt * 10f64.powf(off)).normalize();
        let pivot = Point3::from(pivot);
        let point = pivot + tilt * arm + axis * along;
        // The helix: measured about the axis from a fixed x axis and a point on the axis; the
        // riding marker at the pivot, its x axis across the axis.
        let x_from = tilt;
        let x = rotation_about_axis(&axis, x_spin) * tilt;
        let origin = pivot - axis * start;
        let helix = Helix { axis, x_from, origin, x, point: pivot, pitch };
        let screw = Screw { helix, slide: axis };
        let q = rotation_about_axis(&axis, turn);
        let now = (pivot - origin).dot(&axis);
        let slide = helix_advance(now, signed_angle3(&x_from, &(q * x), &axis), pitch) - now;
        let reached = pivot + q * (point - pivot) + axis * slide;
        // The plane's condition must move with the turn, through the arm or the pitch.
        let rate = normal.dot(&axis.cross(&(reached - axis * slide - pivot)))
            + normal.dot(&axis) * pitch / std::f64::consts::TAU;
        prop_assume!(rate.abs() > 0.3);
        let plane = Plane::new(normal, normal.dot(&reached.coords));
        let at = (&pivot, &axis);
        let angle = gcs_runtime::fragment3::turn_reaching_plane([&z, &(q * z)], at, &point, &plane, Some(&screw));
        let wrap = |a: f64| (a - turn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        prop_assert!(wrap(angle).abs() <= 1e-12, "{angle} for {turn}, z 1e{off} off");
    }
}

proptest! {
    #![proptest_config(config())]

    /// A helical joint's coupling decides a turn its z axis (1e-12 to 1e-2 rad off the axis)
    /// fixes only to rounding: `turn_reaching_helix` gives the turn at which the riding
    /// marker's x axis makes the helix's angle for its advance.
    #[test]
    fn a_turn_meeting_a_helix_is_exact_near_the_axis(
        axis in unit(),
        across in unit(),
        off in -12.0f64..-2.0,
        turn in -3.0f64..3.0,
        pivot in vec3(),
        arm in 0.2f64..1.0,
        along in -1.0f64..1.0,
        pitch in 0.2f64..2.0,
        x_spin in -3.1f64..3.1,
    ) {
        use gcs_runtime::fragment3::Helix;
        let tilt = perp_to(&axis, &across);
        let z = (axis + tilt * 10f64.powf(off)).normalize();
        let pivot = Point3::from(pivot);
        let point = pivot + tilt * arm + axis * along;
        let x = rotation_about_axis(&axis, x_spin) * tilt;
        let origin = pivot - axis * 0.3;
        let q = rotation_about_axis(&axis, turn);
        // The known marker's x axis: the riding one's after the turn, turned back by the
        // helix's angle for the advance there.
        let advance = (pivot + q * (point - pivot) - origin).dot(&axis);
        let x_from = rotation_about_axis(&axis, -std::f64::consts::TAU * advance / pitch) * (q * x);
        let helix = Helix { axis, x_from, origin, x, point, pitch };
        let at = (&pivot, &axis);
        let angle = gcs_runtime::fragment3::turn_reaching_helix([&z, &(q * z)], at, &helix, None);
        let wrap = |a: f64| (a - turn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        prop_assert!(wrap(angle).abs() <= 1e-12, "{angle} for {turn}, z 1e{off} off");
    }
}
