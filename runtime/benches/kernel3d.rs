//! Micro-benchmarks of the 3d intersection table, the actions and frame queries, in ns per
//! call: `cargo bench -p gcs-runtime --bench kernel3d`.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use gcs_runtime::error::ErrorAccumulator;
use gcs_runtime::frame::*;
use gcs_runtime::intersect3d::*;
use gcs_runtime::locus3d::*;
use nalgebra::{Point2, Point3, Vector2, Vector3};

fn intersections(c: &mut Criterion) {
    let s1 = Sphere::new(Point3::new(0.0, 0.0, 0.0), 2.0);
    let s2 = Sphere::new(Point3::new(2.0, 0.5, 0.3), 1.5);
    let pa = Plane::new(Vector3::new(0.1, 0.0, 1.0), 0.5);
    let pb = Plane::new(Vector3::new(1.0, 0.2, 0.2), 1.0);
    let l = Line3::new(Point3::new(-3.0, 0.2, 0.1), Vector3::new(1.0, 0.1, 0.05));
    let cy = Cylinder::new(
        Line3::new(Point3::origin(), Vector3::new(0.0, 0.1, 1.0)),
        1.0,
    );
    let c1 = Circle3::new(Point3::origin(), Vector3::z(), 2.0);
    let c2 = Circle3::new(Point3::new(2.5, 0.3, 0.0), Vector3::z(), 1.0);
    let c3 = Circle3::new(Point3::new(1.0, 0.0, 0.0), Vector3::y(), 2.0);
    let par = Plane::new(Vector3::x(), 0.5);

    let mut g = c.benchmark_group("intersect3d");
    g.bench_function("sphere_sphere", |b| {
        b.iter(|| sphere_sphere(black_box(&s1), black_box(&s2)))
    });
    g.bench_function("sphere_plane", |b| {
        b.iter(|| sphere_plane(black_box(&s1), black_box(&pa)))
    });
    g.bench_function("plane_plane", |b| {
        b.iter(|| plane_plane(black_box(&pa), black_box(&pb)))
    });
    g.bench_function("line_plane", |b| {
        b.iter(|| line_plane(black_box(&l), black_box(&pb)))
    });
    g.bench_function("line_sphere", |b| {
        b.iter(|| line_sphere(black_box(&l), black_box(&s1)))
    });
    g.bench_function("line_cylinder", |b| {
        b.iter(|| line_cylinder(black_box(&l), black_box(&cy)))
    });
    g.bench_function("circle_plane", |b| {
        b.iter(|| circle_plane(black_box(&c1), black_box(&pb)))
    });
    g.bench_function("circle_sphere", |b| {
        b.iter(|| circle_sphere(black_box(&c1), black_box(&s2)))
    });
    g.bench_function("circle_circle_coplanar", |b| {
        b.iter(|| circle_circle(black_box(&c1), black_box(&c2)))
    });
    g.bench_function("circle_circle_spatial", |b| {
        b.iter(|| circle_circle(black_box(&c1), black_box(&c3)))
    });
    g.bench_function("plane_cylinder_ellipse", |b| {
        b.iter(|| plane_cylinder(black_box(&pb), black_box(&cy)))
    });
    g.bench_function("plane_cylinder_lines", |b| {
        b.iter(|| {
            plane_cylinder(
                black_box(&par),
                black_box(&Cylinder::new(
                    Line3::new(Point3::origin(), Vector3::z()),
                    1.0,
                )),
            )
        })
    });
    g.finish();
}

fn actions(c: &mut Criterion) {
    let f3 = Frame3::new(
        Point3::new(10.0, 5.0, 2.0),
        rotation_about_axis(&Vector3::new(1.0, 1.0, 0.0), 0.7),
    );
    let f2 = Frame2::new(Point2::new(1.0, 2.0), 0.3);
    let p3 = Point3::new(1.0, 2.0, 3.0);
    let v3 = Vector3::new(0.3, -0.2, 0.9);
    let axis = Vector3::new(0.0, 1.0, 1.0);
    let p2 = Point2::new(1.0, -2.0);
    let v2 = Vector2::new(0.3, 0.4);

    let mut g = c.benchmark_group("frame3");
    g.bench_function("translate", |b| {
        b.iter(|| {
            let mut f = black_box(f3);
            f.translate(black_box(&v3));
            f
        })
    });
    g.bench_function("rotate_about", |b| {
        b.iter(|| {
            let mut f = black_box(f3);
            f.rotate_about(black_box(&p3), black_box(&axis), black_box(0.4));
            f
        })
    });
    g.bench_function("scale_about", |b| {
        b.iter(|| {
            let mut f = black_box(f3);
            let mut dims = [1.0];
            f.scale_about(black_box(&p3), black_box(1.5), &mut dims);
            (f, dims)
        })
    });
    g.bench_function("point_to_global", |b| {
        b.iter(|| black_box(&f3).point_to_global(black_box(&p3)))
    });
    g.bench_function("point_to_local", |b| {
        b.iter(|| black_box(&f3).point_to_local(black_box(&p3)))
    });
    g.bench_function("vector_to_global", |b| {
        b.iter(|| black_box(&f3).vector_to_global(black_box(&v3)))
    });
    g.bench_function("signed_angle3", |b| {
        b.iter(|| signed_angle3(black_box(&v3), black_box(&Vector3::x()), black_box(&axis)))
    });
    g.bench_function("rotation_between3", |b| {
        b.iter(|| rotation_between3(black_box(&v3), black_box(&axis), black_box(&Vector3::z())))
    });
    g.bench_function("rotation_about_axis", |b| {
        b.iter(|| rotation_about_axis(black_box(&axis), black_box(0.4)))
    });
    g.finish();

    let mut g = c.benchmark_group("frame2");
    g.bench_function("translate", |b| {
        b.iter(|| {
            let mut f = black_box(f2);
            f.translate(black_box(&v2));
            f
        })
    });
    g.bench_function("rotate_about", |b| {
        b.iter(|| {
            let mut f = black_box(f2);
            f.rotate_about(black_box(&p2), black_box(0.4));
            f
        })
    });
    g.bench_function("scale_about", |b| {
        b.iter(|| {
            let mut f = black_box(f2);
            let mut dims = [1.0];
            f.scale_about(black_box(&p2), black_box(1.5), &mut dims);
            (f, dims)
        })
    });
    g.bench_function("point_to_global", |b| {
        b.iter(|| black_box(&f2).point_to_global(black_box(&p2)))
    });
    g.bench_function("signed_angle2", |b| {
        b.iter(|| signed_angle2(black_box(&v2), black_box(&Vector2::x())))
    });
    g.finish();

    let mut g = c.benchmark_group("error");
    g.bench_function("accumulator_add", |b| {
        b.iter(|| {
            let mut acc: ErrorAccumulator = ErrorAccumulator::new();
            acc.add("a", black_box(1e-3));
            acc.add("b", black_box(-2e-3));
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, intersections, actions);
criterion_main!(benches);
