//! Throughput of a generated solver: the four-bar of `fourbar.gcs`, solved a million times with
//! its crank angle spread over the circle, on one core and then on all cores.
//!
//! Usage: `cargo run --release -p gcs-examples --bin throughput [-- SOLVES]`
//!
//! `SOLVES` defaults to 1000000. For each run it prints the solves per second, the number of
//! failed solves, and a checksum of the solved `coupler.c` (so that no solve is optimised away;
//! the two checksums agree up to the order of summation). The generated `solve` is a plain
//! function of its arguments, so it is `Send + Sync` by construction and the threads share
//! nothing but the read-only branch and default choices.

use gcs_examples::fourbar::{solve, Branches, Defaults, Params};
use std::process::ExitCode;
use std::time::Instant;

/// What one run of solves adds up to.
#[derive(Debug, Default, Clone, Copy)]
struct Tally {
    /// Sum of `coupler.c`'s coordinates over the successful solves.
    checksum: f64,
    /// Solves that returned an error.
    failed: u64,
}

impl Tally {
    fn merge(self, other: Tally) -> Tally {
        Tally {
            checksum: self.checksum + other.checksum,
            failed: self.failed + other.failed,
        }
    }
}

/// Solves the four-bar for the crank angles of `range` out of `n` steps around the circle.
fn solve_range(range: std::ops::Range<u64>, n: u64) -> Tally {
    let branches = Branches::default();
    let defaults = Defaults::default();
    let mut params = Params::default();
    let mut tally = Tally::default();
    let step = std::f64::consts::TAU / n as f64;
    for i in range {
        params.theta = i as f64 * step;
        match solve(&params, &branches, &defaults) {
            Ok(s) => {
                let c = s.coupler_c();
                tally.checksum += c.x + c.y;
            }
            Err(_) => tally.failed += 1,
        }
    }
    tally
}

/// Solves `n` crank angles split over `threads` scoped threads.
fn solve_parallel(n: u64, threads: u64) -> Tally {
    let chunk = n.div_ceil(threads);
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let range = (t * chunk).min(n)..((t + 1) * chunk).min(n);
                scope.spawn(move || solve_range(range, n))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .fold(Tally::default(), Tally::merge)
    })
}

/// Prints one run's line.
fn report(what: &str, n: u64, seconds: f64, tally: Tally) {
    println!(
        "{what:<12} {n} solves in {seconds:.3} s: {:>12.0} solves/s ({:.1} ns/solve), {} failed, checksum {:.9e}",
        n as f64 / seconds,
        seconds * 1e9 / n as f64,
        tally.failed,
        tally.checksum
    );
}

fn main() -> ExitCode {
    let n = match std::env::args().nth(1).map(|a| a.parse::<u64>()) {
        None => 1_000_000,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            eprintln!("usage: throughput [SOLVES]  (a positive integer; default 1000000)");
            return ExitCode::from(2);
        }
    };
    let threads = std::thread::available_parallelism().map_or(1, |p| p.get() as u64);

    let start = Instant::now();
    let one = solve_range(0..n, n);
    report("1 core", n, start.elapsed().as_secs_f64(), one);

    let start = Instant::now();
    let all = solve_parallel(n, threads);
    report(
        &format!("{threads} cores"),
        n,
        start.elapsed().as_secs_f64(),
        all,
    );
    ExitCode::SUCCESS
}
