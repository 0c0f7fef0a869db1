//! The 2d intersections and the root finders allocate nothing: a counting global allocator
//! around the system one sees no allocation while they run.
//!
//! The workspace forbids `unsafe_code`, and a `GlobalAlloc` impl is unsafe, so the counting
//! wrapper around `System` is `stats_alloc`'s (a dev-dependency). Its counters are global: this
//! file holds one test, so no other test thread allocates meanwhile; the harness's own thread
//! still may, which the test allows for by counting the fewest of three runs.

#![allow(clippy::unwrap_used)]

use std::alloc::System;

use gcs_runtime::intersect2d::*;
use gcs_runtime::locus2d::*;
use gcs_runtime::poly;
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

#[test]
fn intersections_and_roots_allocate_nothing() {
    let p = P2::new;
    let l1 = Line::new(p(0.0, 0.0), V2::new(1.0, 0.2)).unwrap();
    let l2 = Line::new(p(0.0, 3.0), V2::new(1.0, -1.0)).unwrap();
    let r1 = Ray::new(p(-5.0, 0.5), V2::new(1.0, 0.0)).unwrap();
    let r2 = Ray::new(p(1.0, -5.0), V2::new(0.0, 1.0)).unwrap();
    let c1 = Circle::new(p(0.0, 0.0), 2.0).unwrap();
    let c2 = Circle::new(p(2.5, 0.5), 1.5).unwrap();
    let l = Line::new(p(0.0, -4.0), V2::x()).unwrap();
    let par: Conic = centres_line_circle(&l, 0.0, p(0.0, 0.0), Sense::Plus, 2.0)
        .unwrap()
        .into();
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
    let end = Circle::new(p(6.0, 3.0), 3.0).unwrap();
    let conics = [par, ell, hyp];

    let run = || {
        let mut sink = 0usize;
        for _ in 0..3 {
            sink += line_line(&l1, &l2).roots.len();
            sink += line_ray(&l1, &r2).roots.len();
            sink += ray_ray(&r1, &r2).roots.len();
            sink += line_circle(&l1, &c1).roots.len();
            sink += ray_circle(&r1, &c1).roots.len();
            sink += circle_circle(&c1, &c2).roots.len();
            for k in &conics {
                sink += line_conic(&l1, k).roots.len();
                sink += ray_conic(&r1, k).roots.len();
                sink += circle_conic(&end, k).roots.len();
                for k2 in &conics {
                    sink += conic_conic(k, k2).roots.len();
                }
                sink += usize::from(k.residual(p(1.0, 1.0)) > 0.0);
            }
            sink += centres_line_line(&l1, 0.5, &l2, 0.25).map_or(0, |_| 1);
            sink += poly::quadratic(1.0, -3.0, 2.0).len();
            sink += poly::cubic(1.0, -6.0, 11.0, -6.0).len();
            sink += poly::quartic(1.0, -10.0, 35.0, -50.0, 24.0).len();
            sink += poly::real_roots(&[1.0, 0.0, -2.0, 0.0, 1.0]).len();
            sink += nearest(&circle_circle(&c1, &c2).roots, p(2.0, 2.0)).unwrap_or(0);
        }
        sink
    };
    // The counters are process-wide, and the test harness's own thread may allocate while
    // this one runs (seen once, on a loaded machine). The kernel is deterministic: what it
    // allocates shows in every run, so the fewest of three runs is its count.
    let mut fewest = usize::MAX;
    for _ in 0..3 {
        let region = Region::new(GLOBAL);
        let sink = run();
        let stats = region.change();
        assert!(sink > 0);
        fewest = fewest.min(stats.allocations + stats.reallocations);
    }
    assert_eq!(fewest, 0, "the 2d kernel allocated in every run");
}
