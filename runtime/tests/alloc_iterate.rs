//! The outer iterations allocate nothing: a counting global allocator around the system one
//! sees no allocation while `solve` (one and three defaults, converging, backing off from
//! failures, and failing) and `all_roots` run.
//!
//! In a file of its own, for the reason `alloc2d.rs` gives: the counters are process-wide, so
//! no other test (proptest allocates freely) may run beside this one; the harness's own thread
//! still may allocate, which the test allows for by counting the fewest of three runs.

#![allow(clippy::unwrap_used)]

use std::alloc::System;
use std::f64::consts::TAU;

use gcs_runtime::iterate::{all_roots, solve, RootScan, Settings};
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

#[test]
fn outer_iterations_allocate_nothing() {
    let settings = Settings::default();
    let run = || {
        let mut sink = 0u64;
        for _ in 0..3 {
            // One default: converging, and backing off where the assembly fails.
            let mut x = [0.5];
            let done = solve(&mut x, &[1.0], &settings, |p, r| {
                if p[0] * p[0] >= 1.0 {
                    return Err("no assembly");
                }
                r[0] = (1.0 - p[0] * p[0]).sqrt() - 0.2;
                Ok(())
            });
            sink += u64::from(done.map_or(0, |d| d.evaluations));
            // One default, no root: the failure path.
            let mut x = [0.7];
            let failed = solve(&mut x, &[1.0], &settings, |p, r| {
                r[0] = p[0] * p[0] + 1.0;
                Ok::<(), ()>(())
            });
            sink += u64::from(failed.is_err());
            // Three defaults.
            let mut x = [1.2, 2.2, 2.8];
            let done = solve(&mut x, &[1.0; 3], &settings, |p, r| {
                let [x, y, z] = *p;
                if x < 0.0 {
                    return Err(());
                }
                r[0] = x * x + y * y + z * z - 14.0;
                r[1] = x * y - 2.0 + z - 3.0;
                r[2] = (x - 1.0).exp() + y * z - 7.0;
                Ok(())
            });
            sink += u64::from(done.map_or(0, |d| d.evaluations));
            // Every root: periodic, with a failing stretch and a double root.
            let scan: RootScan<8> = all_roots(0.0, TAU, true, 32, &settings, |t| {
                if (2.0..2.3).contains(&t) {
                    Err(())
                } else {
                    Ok((3.0 * t).cos() - 0.5)
                }
            });
            sink += scan.roots().len() as u64;
            let scan: RootScan<8> = all_roots(-1.0, 1.0, false, 24, &settings, |x| {
                Ok::<f64, ()>((x - 0.3) * (x - 0.3) * (x + 0.6))
            });
            sink += scan.roots().len() as u64 + u64::from(scan.is_double(1));
        }
        sink
    };
    let mut fewest = usize::MAX;
    for _ in 0..3 {
        let region = Region::new(GLOBAL);
        let sink = run();
        let stats = region.change();
        assert!(sink > 0);
        fewest = fewest.min(stats.allocations + stats.reallocations);
    }
    assert_eq!(fewest, 0, "the outer iterations allocated in every run");
}
