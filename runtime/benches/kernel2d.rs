//! Micro-benchmarks of the 2d intersection table and the polynomial root finders, in ns per
//! call: `cargo bench -p gcs-runtime --bench kernel2d`.
#![allow(clippy::unwrap_used, missing_docs)]

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use gcs_runtime::intersect2d::*;
use gcs_runtime::locus2d::*;
use gcs_runtime::poly;

fn bench(c: &mut Criterion) {
    let p = P2::new;
    let l1 = Line::new(p(0.0, 0.0), V2::new(1.0, 0.2)).unwrap();
    let l2 = Line::new(p(0.0, 3.0), V2::new(1.0, -1.0)).unwrap();
    let r1 = Ray::new(p(-5.0, 0.5), V2::new(1.0, 0.0)).unwrap();
    let r2 = Ray::new(p(1.0, -5.0), V2::new(0.0, 1.0)).unwrap();
    let c1 = Circle::new(p(0.0, 0.0), 2.0).unwrap();
    let c2 = Circle::new(p(2.5, 0.5), 1.5).unwrap();
    let l = Line::new(p(0.0, -4.0), V2::x()).unwrap();
    // Kramer's circle problem: the parabola of centres and the circle of the segment's end.
    let par: Conic = centres_line_circle(&l, 0.0, p(0.0, 0.0), Sense::Plus, 2.0)
        .unwrap()
        .into();
    let end = Circle::new(p(6.0, 3.0), 3.0).unwrap();
    let ell = centres_circle_circle(
        p(0.0, 0.0),
        Sense::Minus,
        10.0,
        p(3.0, 0.0),
        Sense::Plus,
        1.0,
    )
    .unwrap();
    let hyp = centres_circle_circle(p(0.0, 0.0), Sense::Plus, 1.0, p(5.0, 0.0), Sense::Plus, 2.0)
        .unwrap();

    let mut g = c.benchmark_group("intersect2d");
    g.bench_function("line_line", |b| {
        b.iter(|| line_line(black_box(&l1), black_box(&l2)))
    });
    g.bench_function("line_ray", |b| {
        b.iter(|| line_ray(black_box(&l1), black_box(&r2)))
    });
    g.bench_function("ray_ray", |b| {
        b.iter(|| ray_ray(black_box(&r1), black_box(&r2)))
    });
    g.bench_function("line_circle", |b| {
        b.iter(|| line_circle(black_box(&l1), black_box(&c1)))
    });
    g.bench_function("ray_circle", |b| {
        b.iter(|| ray_circle(black_box(&r1), black_box(&c1)))
    });
    g.bench_function("circle_circle", |b| {
        b.iter(|| circle_circle(black_box(&c1), black_box(&c2)))
    });
    for (name, k) in [("parabola", &par), ("ellipse", &ell), ("hyperbola", &hyp)] {
        g.bench_function(format!("line_{name}"), |b| {
            b.iter(|| line_conic(black_box(&l1), black_box(k)))
        });
        g.bench_function(format!("ray_{name}"), |b| {
            b.iter(|| ray_conic(black_box(&r1), black_box(k)))
        });
        g.bench_function(format!("circle_{name}"), |b| {
            b.iter(|| circle_conic(black_box(&end), black_box(k)))
        });
    }
    g.bench_function("parabola_ellipse", |b| {
        b.iter(|| conic_conic(black_box(&par), black_box(&ell)))
    });
    g.bench_function("ellipse_hyperbola", |b| {
        b.iter(|| conic_conic(black_box(&ell), black_box(&hyp)))
    });
    g.bench_function("hyperbola_parabola", |b| {
        b.iter(|| conic_conic(black_box(&hyp), black_box(&par)))
    });
    g.finish();

    let mut g = c.benchmark_group("poly");
    g.bench_function("quadratic", |b| {
        b.iter(|| poly::quadratic(black_box(1.0), black_box(-3.0), black_box(2.0)))
    });
    g.bench_function("cubic", |b| {
        b.iter(|| {
            poly::cubic(
                black_box(1.0),
                black_box(-6.0),
                black_box(11.0),
                black_box(-6.0),
            )
        })
    });
    g.bench_function("quartic", |b| {
        b.iter(|| {
            poly::quartic(
                black_box(1.0),
                black_box(-10.0),
                black_box(35.0),
                black_box(-50.0),
                black_box(24.0),
            )
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
