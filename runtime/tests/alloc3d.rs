//! Frames, actions, 3d intersections and error accounting allocate nothing: a counting global
//! allocator around the system one sees no allocation while they run.
//!
//! The workspace forbids `unsafe_code`, and a `GlobalAlloc` impl is unsafe, so the counting
//! wrapper around `System` is `stats_alloc`'s (a dev-dependency). Its counters are global: this
//! file holds one test, so no other test thread allocates meanwhile; the harness's own thread
//! still may, which the test allows for by counting the fewest of three runs.

use std::alloc::System;
use std::hint::black_box;

use gcs_runtime::error::{check_all_finite, check_finite, ErrorAccumulator, ErrorKind, SolveError};
use gcs_runtime::frame::*;
use gcs_runtime::intersect3d::*;
use gcs_runtime::locus3d::*;
use gcs_runtime::Contact;
use nalgebra::{Point2, Point3, Vector2, Vector3};
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// Runs everything once; returns a checksum so nothing is optimized away.
fn run_all() -> f64 {
    let mut acc = 0.0;
    // Frames and actions, 2d.
    let mut f2 = Frame2::new(Point2::new(1.0, 2.0), 0.3);
    f2.translate(&Vector2::new(0.5, -1.0));
    f2.rotate_about(&Point2::new(3.0, 1.0), 0.7);
    let mut dims = [1.0, 2.0];
    f2.scale_about(&Point2::new(0.0, 1.0), 1.5, &mut dims);
    let g = f2.point_to_global(&Point2::new(1.0, 1.0));
    acc += f2.point_to_local(&g).x + f2.vector_to_global(&Vector2::x()).y;
    acc += f2.vector_to_local(&Vector2::y()).x + f2.angle() + f2.x_axis().x + f2.y_axis().y;
    acc += signed_angle2(&Vector2::x(), &Vector2::new(1.0, 1.0));
    acc += scale_point2_about(&Point2::new(1.0, 1.0), &Point2::origin(), 2.0).x;
    // Frames and actions, 3d.
    let mut f3 = Frame3::new(
        Point3::new(10.0, 5.0, 2.0),
        rotation_about_axis(&Vector3::new(1.0, 1.0, 0.0), 0.7),
    );
    f3.translate(&Vector3::new(-10.0, -5.0, -2.0));
    f3.rotate_about(
        &Point3::new(1.0, 0.0, 0.0),
        &Vector3::new(0.0, 1.0, 1.0),
        0.4,
    );
    f3.scale_about(&Point3::new(0.0, 1.0, 0.0), 0.5, &mut dims);
    let q = rotation_between3(&Vector3::x(), &Vector3::y(), &Vector3::z());
    f3.rotate_about_by(&Point3::origin(), &q);
    let q = rotation_between3(&Vector3::x(), &-Vector3::x(), &Vector3::z());
    f3.rotate_about_by(&Point3::origin(), &q);
    let g = f3.point_to_global(&Point3::new(1.0, 2.0, 3.0));
    acc += f3.point_to_local(&g).z + f3.vector_to_global(&Vector3::x()).y;
    acc += f3.vector_to_local(&Vector3::z()).x + f3.x_axis().x + f3.y_axis().y + f3.z_axis().z;
    acc += signed_angle3(&Vector3::x(), &Vector3::y(), &Vector3::z());
    acc += scale_point3_about(&Point3::new(1.0, 1.0, 1.0), &Point3::origin(), 2.0).x;
    acc += scale_factor(2.0, 3.0).unwrap_or(0.0) + perpendicular(&Vector3::x()).y;
    // Loci and intersections, 3d.
    let s1 = Sphere::new(Point3::new(0.0, 0.0, 0.0), 2.0);
    let s2 = Sphere::new(Point3::new(2.0, 0.5, 0.0), 1.5);
    let pa = Plane::new(Vector3::new(0.0, 0.0, 1.0), 0.5);
    let pb = Plane::new(Vector3::new(1.0, 0.0, 0.2), 1.0);
    let l = Line3::new(Point3::new(-3.0, 0.2, 0.1), Vector3::new(1.0, 0.1, 0.0));
    let cy = Cylinder::new(Line3::new(Point3::origin(), Vector3::z()), 1.0);
    let c1 = Circle3::new(Point3::origin(), Vector3::z(), 2.0);
    let c2 = Circle3::new(Point3::new(2.5, 0.0, 0.0), Vector3::z(), 1.0);
    let c3 = Circle3::new(Point3::new(1.0, 0.0, 0.0), Vector3::y(), 2.0);
    let cone = Cone::new(Point3::origin(), Vector3::z(), 0.5);
    if let Some(c) = sphere_sphere(&s1, &s2).branch(0) {
        acc += c.radius + c.distance(&Point3::origin());
    }
    if let Some(c) = sphere_plane(&s1, &pa).branch(0) {
        acc += c.radius;
    }
    if let Some(k) = plane_plane(&pa, &pb).branch(0) {
        acc += k.point.x + k.distance(&Point3::origin());
    }
    for r in line_plane(&l, &pb).roots.as_slice() {
        acc += r.x;
    }
    for r in line_sphere(&l, &s1).roots.as_slice() {
        acc += r.x + s1.distance(r);
    }
    for r in line_cylinder(&l, &cy).roots.as_slice() {
        acc += r.x + cy.distance(r);
    }
    for r in circle_plane(&c1, &pb).roots.as_slice() {
        acc += r.y + pb.distance(r);
    }
    for r in circle_sphere(&c1, &s2).roots.as_slice() {
        acc += r.y;
    }
    for r in circle_circle(&c1, &c2).roots.as_slice() {
        acc += r.y;
    }
    for r in circle_circle(&c1, &c3).roots.as_slice() {
        acc += r.x;
    }
    let x = circle_circle(
        &c1,
        &Circle3::new(Point3::new(3.0, 0.0, 0.0), Vector3::y(), 0.5),
    );
    if let Contact::Disjoint { gap } = x.contact {
        acc += gap;
    }
    for s in plane_cylinder(&pb, &cy).roots.as_slice() {
        if let CylinderSection::Ellipse(e) = s {
            acc += e.a + e.distance(&Point3::new(3.0, 1.0, 0.0));
        }
    }
    acc += plane_cylinder(&Plane::new(Vector3::x(), 0.5), &cy)
        .roots
        .len() as f64;
    acc += cone.distance(&Point3::new(1.0, 1.0, 1.0));
    // Bodies turning about known axes.
    acc += turns(acc);
    // Error accounting.
    let mut errs: ErrorAccumulator = ErrorAccumulator::new();
    errs.add("loop", 1e-3);
    errs.add("other", -2e-3);
    acc += errs.max() + errs.sum_squares() + errs.rms() + errs.count() as f64;
    acc += errs.worst().map_or(0.0, |w| w.len() as f64);
    acc += check_finite("len", 2.0).unwrap_or(0.0);
    acc += check_all_finite(&[("a", 1.0), ("b", 2.0)]).map_or(0.0, |()| 1.0);
    let e = SolveError::new("elbow", "coincident(a, b)", ErrorKind::NoIntersection, 0.3);
    acc += e.magnitude;
    if let Some(e) = SolveError::from_contact("elbow", "coincident(a, b)", x.contact) {
        acc += e.magnitude;
    }
    if let Err(e) = check_finite("len", f64::NAN) {
        acc += e.label.len() as f64;
    }
    black_box(acc)
}

/// Every subproblem of `turn3d`, once each.
fn turns(seed: f64) -> f64 {
    use gcs_runtime::turn3d::*;
    let mut acc = 0.0;
    let ax = |p: [f64; 3], d: [f64; 3]| Line3::new(Point3::from(p), Vector3::from(d));
    let (a1, a2, a3) = (
        ax([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ax([1.0, 0.0, 0.5], [0.0, 1.0, 0.0]),
        ax([0.0, 2.0, 0.0], [1.0, 0.0, 1.0]),
    );
    let p = Point3::new(1.0, 0.5 + seed * 0.0, 0.3);
    let q = Point3::new(-0.5, 1.0, 0.3);
    acc += turn_onto_point(&a1, &p, &q)
        .roots
        .as_slice()
        .iter()
        .sum::<f64>();
    acc += nearest_turn(&a1, &p, &q).map_or(0.0, |n| n.miss);
    acc += turn_to_distance(&a1, &p, &q, 1.0).roots.len() as f64;
    acc += turn_onto_plane(&a1, &p, &Plane::new(Vector3::x(), 0.2))
        .roots
        .len() as f64;
    acc += turn_onto_line(&a1, &p, &a2).roots.len() as f64;
    acc += turns_meeting(&a1, &p, &a2, &q).roots.len() as f64;
    acc += three_circles(&a1, &p, &a2, &a3, &q).roots.len() as f64;
    let t = Term {
        axis: a1,
        point: p,
        along: Vector3::x(),
    };
    let u = Term {
        axis: a2,
        point: q,
        along: Vector3::y(),
    };
    acc += four_terms(&[[t, u, u, t], [u, t, t, u]], [0.3, 0.1])
        .roots
        .len() as f64;
    acc + turn_point(&a3, 0.4, &p).x
}

#[test]
fn actions_frames_intersections_and_errors_allocate_nothing() {
    // A warm-up run, so that any lazy one-time initialisation is not counted.
    let warm = run_all();
    assert!(warm.is_finite());
    // The counters are process-wide, and the test harness's own thread may allocate while
    // this one runs. What the kernel allocates shows in every run: the fewest of three runs
    // is its count.
    let mut fewest = usize::MAX;
    for _ in 0..3 {
        let region = Region::new(GLOBAL);
        let sum = run_all();
        let stats = region.change();
        assert!(sum.is_finite());
        fewest = fewest.min(stats.allocations + stats.reallocations);
    }
    assert_eq!(fewest, 0, "the 3d kernel allocated in every run");
}
