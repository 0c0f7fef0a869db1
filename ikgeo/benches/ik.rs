//! gcs's generated arm solvers against ik-geo 0.1.2 (`cargo bench` in ikgeo/).
//!
//! For each of ik-geo's arms (`ur5`, `irb6640`, `spherical_bot`, `three_parallel_bot`, all in
//! closed form in gcs; `two_parallel_bot`, searched on both sides and timed interleaved only,
//! every pose once a side), the same N = 1,000 poses (random
//! joint angles through this crate's forward kinematics, written from ik-geo's `h` and `p`
//! apart from both solvers; the check's poses), and per pose:
//!
//! - `gcs_solve_all`: the generated `solve_all` (every solution; its body frames),
//! - `gcs_solve`: the generated `solve` on the sketch's branches (one solution; a pose where
//!   those branches have none still counts, as a failed solve),
//! - `ik_geo_ik`: ik-geo's `Robot::ik` (every solution, least-squares ones included, as
//!   joint angles).
//!
//! Criterion times each in turn, one pose a call, cycling over the poses. After criterion's
//! groups the same sides are timed interleaved, so that a busy spell of a shared machine falls
//! on every side alike: each round solves the next block of 50 poses on every side, in an order
//! that rotates from round to round (400 rounds: every pose 20 times a side), and the ratios are
//! printed: each round's ik-geo time over the gcs side's, the median over the rounds with its
//! quartiles. One more side there, `gcs_solve_all + angles`, adds reading the joint angles
//! from gcs's frames, which is what a caller wanting ik-geo's output pays.

use criterion::Criterion;
use gcs_ikgeo::arms::{
    Arm, Pose, IRB6640, SPHERICAL_BOT, THREE_PARALLEL_BOT, TWO_PARALLEL_BOT, UR5,
};
use gcs_ikgeo::check::seed;
use gcs_ikgeo::{
    ik_geo_robot, Angles, Gcs, Irb6640, SphericalBot, ThreeParallelBot, TwoParallelBot, Ur5,
};
use ik_geo::robot::IKSolver;
use std::hint::black_box;
use std::time::Instant;

/// Poses an arm.
const N: usize = 1000;
/// Poses a block of the interleaved timing, and its rounds (each one block on every side).
const BLOCK: usize = 50;
const ROUNDS: usize = 400;

fn poses(arm: &Arm) -> Vec<Pose> {
    gcs_ikgeo::arms::poses(arm, N, seed(arm))
}

fn bench_arm<G: Gcs>(c: &mut Criterion, arm: &Arm) {
    let poses = poses(arm);
    let params: Vec<G::Params> = poses.iter().map(G::params).collect();
    let robot = ik_geo_robot(arm);
    let mut group = c.benchmark_group(arm.name);
    group.bench_function("gcs_solve_all", |b| {
        let mut i = 0;
        b.iter(|| {
            let p = &params[i % N];
            i += 1;
            black_box(G::time_all(black_box(p)))
        })
    });
    group.bench_function("gcs_solve", |b| {
        let mut i = 0;
        b.iter(|| {
            let p = &params[i % N];
            i += 1;
            black_box(G::time_one(black_box(p)))
        })
    });
    group.bench_function("ik_geo_ik", |b| {
        let mut i = 0;
        b.iter(|| {
            let pose = &poses[i % N];
            i += 1;
            black_box(robot.ik(black_box(pose.r), black_box(pose.t)))
        })
    });
    group.finish();
}

fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[((s.len() - 1) as f64 * q).round() as usize]
}

/// Seconds a pose, over the block of `BLOCK` poses that starts at `from`.
fn per_pose(from: usize, mut f: impl FnMut(usize) -> usize) -> f64 {
    let t = Instant::now();
    let mut sum = 0;
    for i in from..from + BLOCK {
        sum += f(i);
    }
    black_box(sum);
    t.elapsed().as_secs_f64() / BLOCK as f64
}

fn interleaved<G: Gcs>(arm: &Arm, rounds: usize) {
    let poses = poses(arm);
    let params: Vec<G::Params> = poses.iter().map(G::params).collect();
    let robot = ik_geo_robot(arm);
    let reader = Angles::new(arm);
    let ik_geo = |from| {
        per_pose(from, |i| {
            robot.ik(black_box(poses[i].r), black_box(poses[i].t)).len()
        })
    };
    let all = |from| per_pose(from, |i| G::time_all(black_box(&params[i])));
    let one = |from| per_pose(from, |i| usize::from(G::time_one(black_box(&params[i]))));
    let all_angles = |from| {
        per_pose(from, |i| {
            usize::from(G::time_all_angles(&reader, black_box(&params[i])) > 0.0)
        })
    };
    let sides: [(&str, &dyn Fn(usize) -> f64); 4] = [
        ("ik_geo_ik", &ik_geo),
        ("gcs_solve_all", &all),
        ("gcs_solve", &one),
        ("gcs_solve_all + angles", &all_angles),
    ];
    if rounds == ROUNDS {
        for (_, side) in sides {
            for from in (0..N).step_by(BLOCK) {
                side(from);
            }
        }
    }
    let mut times: [Vec<f64>; 4] = Default::default();
    for round in 0..rounds {
        let from = round * BLOCK % N;
        for k in 0..sides.len() {
            let i = (round + k) % sides.len();
            times[i].push(sides[i].1(from));
        }
    }
    let name = format!("{}/interleaved", arm.name);
    // A block's time is the same poses' on every side; over the rounds, every pose is solved
    // ROUNDS * BLOCK / N times on each side.
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    println!(
        "{name:<24} {}: {:.3} µs a pose (median of {rounds} blocks of {BLOCK} poses; mean {:.3} µs)",
        sides[0].0,
        quantile(&times[0], 0.5) * 1e6,
        mean(&times[0]) * 1e6,
    );
    for i in 1..sides.len() {
        let ratios: Vec<f64> = times[0].iter().zip(&times[i]).map(|(a, b)| a / b).collect();
        println!(
            "{name:<24} {}: {:.3} µs a pose (mean {:.3} µs); ik-geo / it {:.2}x (quartiles {:.2}x-{:.2}x)",
            sides[i].0,
            quantile(&times[i], 0.5) * 1e6,
            mean(&times[i]) * 1e6,
            quantile(&ratios, 0.5),
            quantile(&ratios, 0.25),
            quantile(&ratios, 0.75),
        );
    }
    // How many solutions each side gives, and how often `solve` has one, over the poses.
    let gcs_all: usize = params.iter().map(G::time_all).sum();
    let gcs_one = params.iter().filter(|p| G::time_one(p)).count();
    let (mut exact, mut ls) = (0, 0);
    for p in &poses {
        for (_, is_ls) in robot.ik(p.r, p.t) {
            if is_ls {
                ls += 1;
            } else {
                exact += 1;
            }
        }
    }
    println!(
        "{name:<24} solutions over {N} poses: gcs solve_all {gcs_all}, ik-geo {exact} exact + {ls} \
         least-squares; gcs solve found one at {gcs_one}"
    );
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_arm::<Ur5>(&mut c, &UR5);
    bench_arm::<Irb6640>(&mut c, &IRB6640);
    bench_arm::<SphericalBot>(&mut c, &SPHERICAL_BOT);
    bench_arm::<ThreeParallelBot>(&mut c, &THREE_PARALLEL_BOT);
    c.final_summary();
    // Criterion's filter, if any (a word that is neither an option nor a number).
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-') && a.parse::<f64>().is_err())
        .collect();
    // The interleaved timing of an arm runs with no filter, or one that names the arm or
    // `interleaved`.
    let wanted = |name: &str| {
        words.is_empty()
            || words.iter().any(|w| {
                w.contains(name) || name.contains(w.as_str()) || "interleaved".contains(w.as_str())
            })
    };
    if wanted(UR5.name) {
        interleaved::<Ur5>(&UR5, ROUNDS);
    }
    if wanted(IRB6640.name) {
        interleaved::<Irb6640>(&IRB6640, ROUNDS);
    }
    if wanted(SPHERICAL_BOT.name) {
        interleaved::<SphericalBot>(&SPHERICAL_BOT, ROUNDS);
    }
    if wanted(THREE_PARALLEL_BOT.name) {
        interleaved::<ThreeParallelBot>(&THREE_PARALLEL_BOT, ROUNDS);
    }
    // A search on both sides, each about a thousand times slower: every pose once a side.
    if wanted(TWO_PARALLEL_BOT.name) {
        interleaved::<TwoParallelBot>(&TWO_PARALLEL_BOT, N / BLOCK);
    }
}
