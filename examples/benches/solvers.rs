//! Generated solvers against the interpreter on every example, and the four-bar against a
//! closed-form solve written by hand, in one run. `cargo bench -p gcs-examples --bench solvers`.
//!
//! After criterion's groups, the four-bar's two solves are also timed interleaved (see
//! [`four_bar_interleaved`]): criterion times one after the other, and on a shared machine a
//! slow spell that falls on one of them moves their ratio by half. So is the chain of 128
//! four-bars against the same chain by hand ([`chain_interleaved`]); a filter naming `chain`
//! runs only that.

use criterion::{criterion_group, Criterion};
use gcs_examples as ex;
use std::hint::black_box;

/// The same generated four-bar, included into this crate as the README shows a user doing it
/// (`include_solver!` in their own crate), where `ex::fourbar` is called across crates: within
/// one crate the compiler may specialise the call (its arguments, what the caller reads).
mod fourbar_here {
    gcs_runtime::include_solver!("fourbar");
}

/// The lengths of examples/fourbar.gcs's crank, coupler and rocker.
const CRANK: f64 = 1.5;
const COUPLER: f64 = 4.0;
const ROCKER: f64 = 3.0;

/// The crank's end at angle `theta`, and the vector from it to the rocker's pivot `(4, 0)`:
/// where both hand-written solves start.
#[inline(always)]
fn crank_end_and_reach(theta: f64) -> ([f64; 2], [f64; 2]) {
    let (s, c) = theta.sin_cos();
    let (bx, by) = (CRANK * c, CRANK * s);
    ([bx, by], [4.0 - bx, 0.0 - by])
}

/// A four-bar solved by hand, in closed form: the crank's end, then the coupler's far joint as
/// the intersection of two circles, on the side the model's `elbow` = 0 means (left of the line
/// from the crank's end to the rocker's pivot). Same geometry as examples/fourbar.gcs, and the
/// same answer as its output `coupler.c`.
fn four_bar_by_hand(theta: f64) -> Option<(f64, f64)> {
    let (coupler, rocker) = (COUPLER, ROCKER);
    let ([bx, by], [ux, uy]) = crank_end_and_reach(theta);
    let d2 = ux * ux + uy * uy;
    let d = d2.sqrt();
    let a = (coupler * coupler - rocker * rocker + d2) / (2.0 * d);
    let h2 = coupler * coupler - a * a;
    if h2 < 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let (ex_, ey) = (ux / d, uy / d);
    Some((bx + a * ex_ - h * ey, by + a * ey + h * ex_))
}

/// The same four-bar by hand, with the formula of the runtime's circle-circle chord: the
/// coupler's joint as multiples of the vector between the centres and its perpendicular, from
/// that vector's squared length, with one square root and one division that run side by side
/// (where the textbook form above takes a square root for the distance, then another for the
/// half chord). A stricter yardstick than the textbook: what a person writes who knows the
/// generated solver's formula.
fn four_bar_by_hand_from_d2(theta: f64) -> Option<(f64, f64)> {
    let (b, reach) = crank_end_and_reach(theta);
    coupler_joint_from_d2(b, reach)
}

/// The coupler's joint of a four-bar by hand, from the coupler's end `b` and the vector from
/// it to the rocker's pivot, with the runtime chord's formula (see above); on the side
/// `elbow` = 0 means.
#[inline(always)]
fn coupler_joint_from_d2([bx, by]: [f64; 2], [ux, uy]: [f64; 2]) -> Option<(f64, f64)> {
    let d2 = ux * ux + uy * uy;
    let (sum, diff) = (COUPLER + ROCKER, COUPLER - ROCKER);
    let area16 = (sum * sum - d2) * (d2 - diff * diff);
    if area16 < 0.0 {
        return None;
    }
    let inv = 0.5 / d2;
    let along = (d2 + sum * diff) * inv;
    let h = area16.sqrt() * inv;
    Some((bx + along * ux - h * uy, by + along * uy + h * ux))
}

/// The generated four-bar of solver module `$m` as a function of the crank angle, doing the
/// same work and giving the same answer as by hand: the coupler point, or none.
macro_rules! four_bar_generated {
    ($($m:ident)::+) => {{
        let (branches, defaults) = (
            $($m)::+::Branches::default(),
            $($m)::+::Defaults::default(),
        );
        let mut params = $($m)::+::Params::default();
        move |theta: f64| {
            params.theta = theta;
            let solution = $($m)::+::solve(&params, &branches, &defaults);
            solution.ok().map(|s| {
                let c = s.coupler_c();
                (c.x, c.y)
            })
        }
    }};
}

fn interpreted(name: &str) -> (gcs_lang::Model, gcs_compiler::analysis::Analysis) {
    let path = format!("{}/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).expect("example");
    let (_, model, _) = gcs_lang::load(&path, &bytes);
    let model = model.expect("model");
    let analysis = gcs_compiler::analyse(&model).expect("analysis");
    (model, analysis)
}

fn bench_four_bar(c: &mut Criterion) {
    let mut g = c.benchmark_group("fourbar");
    let thetas: Vec<f64> = (0..64).map(|i| i as f64 * 0.098).collect();
    g.bench_function("by_hand", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            black_box(four_bar_by_hand(black_box(thetas[i])))
        })
    });
    g.bench_function("generated", |b| {
        let mut solve = four_bar_generated!(ex::fourbar);
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            black_box(solve(black_box(thetas[i])))
        })
    });
    let (model, analysis) = interpreted("fourbar");
    let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let theta = model
        .param_named("theta")
        .map_or(0, |p| p.into_raw().into_u32() as usize);
    g.bench_function("interpreted", |b| {
        let mut params = model.default_params();
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            params[theta] = black_box(thetas[i]);
            black_box(
                gcs_compiler::interp::run(
                    &model,
                    &plan,
                    &params,
                    &gcs_compiler::interp::Choice::Given(branches.clone()),
                )
                .is_ok(),
            )
        })
    });
    let _ = scope;
    g.finish();
}

macro_rules! generated_vs_interpreted {
    // `bench_four_bar` times the four-bar, against its closed form too.
    (@one $c:expr, fourbar) => {};
    (@one $c:expr, $m:ident) => {{
        let mut g = $c.benchmark_group(stringify!($m));
        g.bench_function("generated", |b| {
            let (p, br, d) = (ex::$m::Params::default(), ex::$m::Branches::default(), ex::$m::Defaults::default());
            // The whole result, so that an inlined solve computes all of it.
            b.iter(|| black_box(ex::$m::solve(black_box(&p), &br, &d)))
        });
        let (model, analysis) = interpreted(stringify!($m));
        let (plan, _) = gcs_compiler::prune::prune(&model, &analysis.plan);
        let choice = gcs_compiler::interp::Choice::Given(plan.branches.iter().map(|b| b.default).collect());
        let params = model.default_params();
        g.bench_function("interpreted", |b| {
            b.iter(|| black_box(gcs_compiler::interp::runs(&model, &plan, black_box(&params), &choice).is_ok()))
        });
        g.finish();
    }};
    ($c:expr; $($m:ident),*) => {$(generated_vs_interpreted!(@one $c, $m);)*};
}

/// Every example but the four-bar: its generated solver against the interpreter.
fn bench_examples(c: &mut Criterion) {
    ex::for_each_example!(generated_vs_interpreted!(c;));
}

/// The value at `at` (0 to 1) of the sorted times or ratios `v`.
fn quantile(v: &[f64], at: f64) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * at).round() as usize]
}

/// The mean time per solve of `n` solves at the crank angles `thetas`, in turn. Generic, so
/// that each side's solve is compiled into its own loop, as it would be in a caller's.
fn time_solves(
    n: usize,
    thetas: &[f64; 64],
    mut solve: impl FnMut(f64) -> Option<(f64, f64)>,
) -> f64 {
    let t = std::time::Instant::now();
    for k in 0..n {
        black_box(solve(black_box(thetas[k & 63])));
    }
    t.elapsed().as_secs_f64() / n as f64
}

/// The generated four-bar over the hand-written one, timed in alternating blocks so that all
/// sides see the same machine: in each of 42 rounds, 100,000 solves by each side (the
/// textbook by hand, the solver included in this crate, the one called across crates, and
/// by hand with the generated solver's formula), the same crank angles on every side, in an
/// order that rotates from round to round. Prints each side's median ratio to the textbook
/// by hand over the rounds, its quartiles, and the median time per solve of each side.
fn four_bar_interleaved() {
    let thetas: [f64; 64] = std::array::from_fn(|i| i as f64 * 0.098);
    let n = 100_000;
    let by_hand = || time_solves(n, &thetas, four_bar_by_hand);
    let here = || time_solves(n, &thetas, four_bar_generated!(fourbar_here));
    let across = || time_solves(n, &thetas, four_bar_generated!(ex::fourbar));
    let from_d2 = || time_solves(n, &thetas, four_bar_by_hand_from_d2);
    let sides: [(&str, &dyn Fn() -> f64); 4] = [
        ("by hand (textbook)", &by_hand),
        (
            "generated, included in this crate (as the README embeds it)",
            &here,
        ),
        (
            "generated, called across crates (gcs_examples::fourbar)",
            &across,
        ),
        ("by hand with the generated solver's formula", &from_d2),
    ];
    // Every side gives the same answer at every angle, so they do the same work.
    let mut generated = four_bar_generated!(ex::fourbar);
    for &theta in &thetas {
        let assembled = "the four-bar assembles at every angle";
        let want = four_bar_by_hand(theta).expect(assembled);
        for (x, y) in
            [generated(theta), four_bar_by_hand_from_d2(theta)].map(|r| r.expect(assembled))
        {
            assert!(
                (x - want.0).abs() + (y - want.1).abs() < 1e-12,
                "{theta}: {x}, {y}"
            );
        }
    }
    // Warm up every side, then measure.
    for (_, side) in sides {
        side();
    }
    let mut times: [Vec<f64>; 4] = Default::default();
    for round in 0..42 {
        let mut this_round = [0.0; 4];
        for k in 0..sides.len() {
            let i = (round + k) % sides.len();
            this_round[i] = sides[i].1();
        }
        for (all, t) in times.iter_mut().zip(this_round) {
            all.push(t);
        }
    }
    let median_ns = |v: &[f64]| quantile(v, 0.5) * 1e9;
    // Round by round, the time of side `a` over that of side `b`.
    let ratios = |a: usize, b: usize| -> Vec<f64> {
        times[a].iter().zip(&times[b]).map(|(x, y)| x / y).collect()
    };
    println!(
        "fourbar/interleaved     {} {:.1} ns over 42 rounds",
        sides[0].0,
        median_ns(&times[0])
    );
    for i in 1..sides.len() {
        let ratios = ratios(i, 0);
        println!(
            "fourbar/interleaved     {}: {:.1} ns, {:.2}x by hand (quartiles {:.2}x-{:.2}x)",
            sides[i].0,
            median_ns(&times[i]),
            quantile(&ratios, 0.5),
            quantile(&ratios, 0.25),
            quantile(&ratios, 0.75),
        );
    }
    // The generated solver against the stricter yardstick, round by round.
    let strict = ratios(1, 3);
    println!(
        "fourbar/interleaved     generated (this crate) over by hand with its formula: {:.2}x \
         (quartiles {:.2}x-{:.2}x)",
        quantile(&strict, 0.5),
        quantile(&strict, 0.25),
        quantile(&strict, 0.75),
    );
}

/// The chain of 128 four-bars (families/fourbar_chain_128.gcs) solved by hand, in closed form:
/// stage `k` has its rocker's pivot at `(4k, 0)`, its coupler (4 long) from the last stage's
/// rocker end `b` (the crank's end for the first) to the rocker's joint `c` (3 from the pivot,
/// on the side `elbow` = 0 means), and its rocker end `b` 1.5 beyond the pivot, opposite `c`.
/// Each stage is the four-bar's chord from `d²`, and then `b = pivot - (c - pivot) / 2`: no
/// rotation, where the generated solver places every rocker's frame. Returns the last `b`, the
/// model's output.
fn chain_by_hand(theta: f64, stages: usize) -> Option<(f64, f64)> {
    let (s, c) = theta.sin_cos();
    let (mut bx, mut by) = (CRANK * c, CRANK * s);
    for k in 1..=stages {
        let px = 4.0 * k as f64;
        let (cx, cy) = coupler_joint_from_d2([bx, by], [px - bx, 0.0 - by])?;
        (bx, by) = (px - 0.5 * (cx - px), -0.5 * cy);
    }
    Some((bx, by))
}

/// The generated chain of 128 as a function of the crank angle: its output `rocker128.b`.
fn chain_generated() -> impl FnMut(f64) -> Option<(f64, f64)> {
    use ex::fourbar_chain_128 as m;
    let (branches, defaults) = (m::Branches::default(), m::Defaults::default());
    let mut params = m::Params::default();
    move |theta: f64| {
        params.theta = theta;
        m::solve(&params, &branches, &defaults).ok().map(|s| {
            let b = s.rocker128_b();
            (b.x, b.y)
        })
    }
}

/// The generated chain of 128 over the same chain by hand ([`chain_by_hand`]), interleaved as
/// for the four-bar: 42 rounds of 2,000 solves by each side. The hand-written chain is about
/// the least time any closed-form solve of the chain can take on this machine: each stage needs
/// the one before (its square root and division on the critical path), so its time bounds
/// the ratio any compiled plan can reach against a baseline.
fn chain_interleaved() {
    let thetas: [f64; 64] = std::array::from_fn(|i| i as f64 * 0.098);
    let n = 2_000;
    let by_hand = || {
        time_solves(n, &thetas, |theta| {
            chain_by_hand(black_box(theta), black_box(128))
        })
    };
    // Both sides give the same answer at every angle.
    let mut generated = chain_generated();
    for &theta in &thetas {
        let (want, got) = (chain_by_hand(theta, 128), generated(theta));
        let ((x, y), (gx, gy)) = (want.expect("assembles"), got.expect("assembles"));
        assert!(
            (x - gx).abs() + (y - gy).abs() < 1e-9,
            "{theta}: {x}, {y} vs {gx}, {gy}"
        );
    }
    let generated = || time_solves(n, &thetas, chain_generated());
    let sides: [&dyn Fn() -> f64; 2] = [&by_hand, &generated];
    let mut times: [Vec<f64>; 2] = Default::default();
    for round in 0..42 {
        for k in 0..2 {
            let i = (round + k) % 2;
            times[i].push(sides[i]());
        }
    }
    let median = |v: &[f64]| quantile(v, 0.5);
    let ratios: Vec<f64> = times[1].iter().zip(&times[0]).map(|(g, h)| g / h).collect();
    println!(
        "chain128/interleaved    by hand {:.2} µs ({:.1} ns a stage), generated {:.2} µs: {:.2}x by hand",
        median(&times[0]) * 1e6,
        median(&times[0]) * 1e9 / 128.0,
        median(&times[1]) * 1e6,
        median(&ratios),
    );
}

criterion_group!(benches, bench_four_bar, bench_examples);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    // Criterion's filter, if any (a word that is neither an option nor a number): the
    // interleaved four-bar runs in a full run, and with a filter that names the four-bar.
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-') && a.parse::<f64>().is_err())
        .collect();
    if words.is_empty() || words.iter().any(|w| w.contains("fourbar")) {
        four_bar_interleaved();
    }
    if words.is_empty() || words.iter().any(|w| w.contains("chain")) {
        chain_interleaved();
    }
}
