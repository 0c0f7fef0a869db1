//! The check (`cargo run --release` in ikgeo/): for 1,000 random poses of each arm, ik-geo's
//! and gcs's solution sets agree (see `gcs_ikgeo::check`). gcs solves all four in closed form.
//! Exits 1 on any mismatch of the two arms whose steps are circles and spheres (UR5, IRB 6640),
//! and, for the two whose position chain is a quartic (subproblems 5 and 6, where near a fold
//! the two sides find a root to different accuracy: ik-geo's own solutions there miss their
//! pose by up to 4e-7), on a solution ik-geo finds to machine precision that gcs has nothing
//! within `NEAR` of, or a gcs solution that misses its pose. The same for `two_parallel_bot`,
//! which has no closed form: gcs scans its last joint's turn, ik-geo searches its base's.
//! `cargo run --release -- N` compares N poses an arm.

use gcs_ikgeo::arms::{IRB6640, SPHERICAL_BOT, THREE_PARALLEL_BOT, TWO_PARALLEL_BOT, UR5};
use gcs_ikgeo::check::{check, TOL};
use gcs_ikgeo::{Irb6640, SphericalBot, ThreeParallelBot, TwoParallelBot, Ur5};

fn main() {
    let n = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("a number of poses"))
        .unwrap_or(1000);
    println!("joint angles compared to {TOL:e} rad, {n} poses an arm");
    println!("closed form, circles and spheres (gcs: no default, no iteration):");
    let closed = [check::<Ur5>(&UR5, n), check::<Irb6640>(&IRB6640, n)];
    for r in &closed {
        print!("{}", r.text());
    }
    println!("closed form, a quartic (gcs: the three-circle problem; a planar sub-chain's ends):");
    let mut quartic = vec![
        check::<SphericalBot>(&SPHERICAL_BOT, n),
        check::<ThreeParallelBot>(&THREE_PARALLEL_BOT, n),
    ];
    for r in &quartic {
        print!("{}", r.text());
    }
    println!("no closed form (gcs: a scan of the last joint's turn, subproblem 6 inside):");
    let searched = check::<TwoParallelBot>(&TWO_PARALLEL_BOT, n);
    print!("{}", searched.text());
    quartic.push(searched);
    let failed: Vec<&str> = closed
        .iter()
        .filter(|r| !r.agrees())
        .map(|r| r.arm)
        .collect();
    let mismatches: usize = closed
        .iter()
        .map(|r| r.ik_geo_unmatched + r.gcs_unmatched)
        .sum();
    println!("circles and spheres: {mismatches} mismatches");
    let missed: usize = quartic.iter().map(|r| r.missed_in_complete).sum();
    let wrong: usize = quartic.iter().map(|r| r.gcs_wrong).sum();
    let unclaimed: usize = quartic
        .iter()
        .map(|r| r.gcs_missed - r.missed_in_complete)
        .sum();
    println!(
        "quartic and searched arms: {missed} solutions missed where a list says it is complete, \
         {wrong} wrong ({unclaimed} missed where it does not)"
    );
    let failed_quartic: Vec<&str> = (quartic.iter())
        .filter(|r| !r.nothing_missed_or_wrong())
        .map(|r| r.arm)
        .collect();
    if !failed.is_empty() || !failed_quartic.is_empty() {
        eprintln!(
            "mismatches on {}; missed or wrong on {}",
            failed.join(", "),
            failed_quartic.join(", ")
        );
        std::process::exit(1);
    }
}
