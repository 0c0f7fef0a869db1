//! Issue 18: sweeps of the two examples whose plans iterate, the triad six-bar (crank `theta`
//! a whole turn) and the 3-RPR (`leg1` from 13 to 16), each solve started from the previous
//! answer's defaults (warm), as a caller following one assembly does.
//!
//! The plan runs in the interpreter, whose outer iteration is the runtime's `iterate::solve`,
//! the call the generated solvers make (and they agree with the interpreter to 1e-14, as
//! `tests/tests/generated.rs` checks). At every step the answer is checked three ways, none
//! of which shares code with the plan:
//! - `verify`: its largest residual is at most `1e-12` times its size (its largest coordinate);
//! - agreement: the baseline's Newton on the raw equations, started from the answer (every
//!   coordinate), converges, and to the same configuration (within `1e-9` of its size);
//! - no flip: the baseline's Newton started from the previous step's answer, at this step's
//!   params, converges to this answer (within `1e-9` of its size): the motion is continuous.
//!
//! The 3-RPR's assembly reaches, at `leg1 = 15.3728`, the configuration where the second leg's
//! circles are tangent (`platform.p1`, `platform.p2` and `B2` collinear), and past it the
//! motion goes on on the other branch of `l2`; a solve with fixed branches has no root there,
//! and fails (an error, never another assembly). The sweeps below show both: with `l2` fixed,
//! and with the caller flipping `l2` when a solve fails, which follows the motion to 16.
//! `the_3rpr_motion_crosses_the_tangency_of_l2_onto_its_other_branch` measures the crossing.
//! `cargo test -p gcs-bench --release --test iterated_sweeps -- --nocapture` prints the numbers
//! docs/BENCHMARKS.md records.

use gcs_bench::baseline::{Baseline, Method, Options};
use gcs_compiler::config::Config;
use gcs_compiler::interp::{self, Choice};
use gcs_compiler::plan::Plan;
use gcs_compiler::solution::Solution;
use gcs_compiler::verify;
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use gcs_runtime::error::{ErrorKind, SolveError};
use std::collections::BTreeSet;

/// An example's model, its whole plan, and the param a sweep drives.
struct Example {
    model: Model,
    plan: Plan,
    all: BTreeSet<GeomId>,
    driver: usize,
    driver_name: String,
}

fn example(name: &str, driver_name: &str) -> Example {
    let path = format!("{}/../../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    let (diags, model, _) = gcs_lang::load(&path, &bytes);
    let model = model.unwrap_or_else(|| panic!("{path}: {diags:?}"));
    let analysis = gcs_compiler::analyse(&model).expect("analysis");
    assert!(analysis.unsolved.is_empty(), "{name}: unsolved constraints");
    assert!(
        !analysis.plan.iterations.is_empty(),
        "{name}: its plan iterates"
    );
    let all = model.top_level().map(|(id, _)| id).collect();
    let driver = model
        .param_named(driver_name)
        .unwrap_or_else(|| panic!("{name}: no param {driver_name}"))
        .into_raw()
        .into_u32() as usize;
    Example {
        model,
        plan: analysis.plan,
        all,
        driver,
        driver_name: driver_name.to_string(),
    }
}

impl Example {
    /// The model's params with the driver at `value`.
    fn params(&self, value: f64) -> Vec<f64> {
        let mut p = self.model.default_params();
        p[self.driver] = value;
        p
    }

    /// The index of branch variable `name`.
    fn branch(&self, name: &str) -> usize {
        (self.plan.branches.iter())
            .position(|b| b.name == name)
            .unwrap_or_else(|| panic!("no branch variable {name}"))
    }
}

/// One answer of the plan.
#[derive(Clone, Debug)]
struct Answer {
    params: Vec<f64>,
    config: Config,
    solution: Solution,
    branches: Vec<usize>,
    defaults: Vec<f64>,
    /// Steps of the outer iteration.
    iterations: u32,
}

/// The plan run by the interpreter with `branches`, its iterations started at `defaults`;
/// the answer read by name, with `verify`'s largest residual.
fn solve(
    ex: &Example,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<Answer, SolveError> {
    let choice = Choice::Given(branches.to_vec());
    let run = interp::run_with(&ex.model, &ex.plan, params, defaults, &choice)?;
    let mut solution = Solution::read(&ex.model, &run.config, &ex.all);
    solution.max_residual = verify::max_residual(&verify::residuals(&ex.model, &solution, params));
    Ok(Answer {
        params: params.to_vec(),
        config: run.config,
        solution,
        branches: branches.to_vec(),
        defaults: run.defaults,
        iterations: run.iterations,
    })
}

/// The largest coordinate magnitude of a solution's points, at least 1: its size.
fn size(s: &Solution) -> f64 {
    (s.points.iter())
        .flat_map(|(_, p)| p.iter())
        .fold(1.0, |m, x| m.max(x.abs()))
}

/// The largest difference between same-named points of two solutions, over the first's size.
fn distance(a: &Solution, b: &Solution) -> f64 {
    let b = b.by_name();
    let mut d: f64 = 0.0;
    for (name, p) in &a.points {
        let q = b.point(name).unwrap_or(&[f64::NAN, f64::NAN]);
        for (x, y) in p.iter().zip(q) {
            d = d.max((x - y).abs());
        }
    }
    if d.is_nan() {
        f64::INFINITY
    } else {
        d / size(a)
    }
}

/// Two configurations are the same to this, relative to their size.
const SAME: f64 = 1e-9;

/// The residual `verify` allows, relative to an answer's size.
const RESIDUAL: f64 = 1e-12;

/// The baseline's Newton on the raw equations, started from configuration `from` (every
/// coordinate) at params `at`, and run at `params`: where it converges, read like the plan's
/// answers, with its configuration and the Newton steps it took; `None` when it does not
/// converge. It stops at `1e-14` of the start's size, below every residual `verify` allows,
/// so that an answer short of that is moved.
fn newton(
    ex: &Example,
    baseline: &mut Baseline,
    (at, from): (&[f64], &Config),
    params: &[f64],
) -> Option<(Solution, Config, usize)> {
    let mut x = baseline.unknowns_from_config(at, from);
    let start = Solution::read(&ex.model, from, &ex.all);
    let opts = Options {
        method: Method::Newton,
        tolerance: 1e-14 * size(&start),
        ..Options::default()
    };
    let outcome = baseline.solve(params, &mut x, &opts);
    if !outcome.converged {
        return None;
    }
    let cfg = baseline.config(params, &x).ok()?;
    Some((
        Solution::read(&ex.model, &cfg, &ex.all),
        cfg,
        outcome.iterations,
    ))
}

/// What a sweep measured.
#[derive(Debug, Default)]
struct Tally {
    steps: usize,
    answered: usize,
    /// The driver's values where the plan returned an error.
    failed: Vec<f64>,
    /// The largest `verify` residual over the answer's size.
    residual: f64,
    /// The largest `verify` residual.
    residual_abs: f64,
    /// The largest distance between an answer and the baseline's Newton from it.
    agreement: f64,
    /// Steps where that Newton moved (took a step) before converging.
    moved: usize,
    /// The largest distance between an answer and the baseline's continuation from the
    /// previous answer.
    continuation: f64,
    /// Where the caller flipped a branch, to which index.
    flips: Vec<(f64, String, usize)>,
    /// Steps of the outer iteration, per answer.
    iterations: Vec<u32>,
}

impl Tally {
    /// The median and the largest number of outer-iteration steps of an answer.
    fn iterations(&self) -> (u32, u32) {
        let mut v = self.iterations.clone();
        v.sort_unstable();
        (
            v.get(v.len() / 2).copied().unwrap_or(0),
            v.last().copied().unwrap_or(0),
        )
    }
}

/// Sweeps `ex` over `values`: the first step from the assembly `gcs solve` picks (the least
/// motion from the sketch), each next one from the previous answer's defaults and branches.
/// With `flip`, a step whose solve fails is solved again from the same defaults with one
/// branch variable flipped (first to last), as a caller can do; the answer is kept only if it
/// is continuous with the previous one. Every answer is checked (module documentation); a
/// failing check panics. Returns the tally and the last answer.
fn sweep(ex: &Example, values: &[f64], flip: bool) -> (Tally, Option<Answer>) {
    let mut baseline = Baseline::new(&ex.model).expect("baseline");
    let branches: Vec<usize> = ex.plan.branches.iter().map(|b| b.default).collect();
    let mut tally = Tally {
        steps: values.len(),
        ..Tally::default()
    };
    let mut last: Option<Answer> = None;
    for &value in values {
        let params = ex.params(value);
        let at = |e: &dyn std::fmt::Display| format!("{} = {value}: {e}", ex.driver_name);
        let solved = match &last {
            None => {
                let first = gcs_compiler::all::least_motion(
                    &ex.model,
                    &ex.plan,
                    &ex.all,
                    &params,
                    &branches,
                    &ex.plan.sketch_defaults(),
                )
                .unwrap_or_else(|e| panic!("{}", at(&e)));
                let defaults: Vec<f64> = first.defaults.iter().map(|(_, v)| *v).collect();
                solve(ex, &params, &branches, &defaults)
            }
            Some(last) => solve(ex, &params, &last.branches, &last.defaults),
        };
        // The continuation from the previous answer: where the motion goes.
        let continued = last.as_ref().map(|last| {
            newton(ex, &mut baseline, (&last.params, &last.config), &params)
                .unwrap_or_else(|| panic!("{}", at(&"the baseline's continuation fails")))
                .0
        });
        let answer = match (solved, &last) {
            (Ok(a), _) => Some(a),
            (Err(e), Some(last)) if flip => {
                let retried = (0..last.branches.len()).find_map(|i| {
                    let count = ex.plan.branches[i].count;
                    let mut branches = last.branches.clone();
                    branches[i] = (branches[i] + 1) % count.max(1);
                    let a = solve(ex, &params, &branches, &last.defaults).ok()?;
                    let joined = continued
                        .as_ref()
                        .is_some_and(|c| distance(&a.solution, c) <= SAME);
                    joined.then_some((i, a))
                });
                let (i, a) = retried.unwrap_or_else(|| panic!("{}", at(&e)));
                tally
                    .flips
                    .push((value, ex.plan.branches[i].name.clone(), a.branches[i]));
                Some(a)
            }
            (Err(e), _) => {
                // An error, never an answer on another assembly.
                assert!(
                    matches!(e.kind, ErrorKind::NoConvergence | ErrorKind::NoIntersection),
                    "{}",
                    at(&e)
                );
                tally.failed.push(value);
                None
            }
        };
        let Some(answer) = answer else { continue };
        let s = &answer.solution;
        let residual = s.max_residual / size(s);
        assert!(
            residual <= RESIDUAL,
            "{}",
            at(&format!("verify: {residual:e} of its size"))
        );
        let (agreed, _, steps) = newton(ex, &mut baseline, (&params, &answer.config), &params)
            .unwrap_or_else(|| panic!("{}", at(&"the baseline from the answer does not converge")));
        let agreement = distance(s, &agreed);
        assert!(
            agreement <= SAME,
            "{}",
            at(&format!("the baseline from the answer moves {agreement:e}"))
        );
        if let Some(c) = &continued {
            let d = distance(s, c);
            assert!(
                d <= SAME,
                "{}",
                at(&format!("a flip: the motion goes {d:e} away"))
            );
            tally.continuation = tally.continuation.max(d);
        }
        tally.answered += 1;
        tally.residual = tally.residual.max(residual);
        tally.residual_abs = tally.residual_abs.max(s.max_residual);
        tally.agreement = tally.agreement.max(agreement);
        tally.moved += usize::from(steps > 0);
        tally.iterations.push(answer.iterations);
        last = Some(answer);
    }
    (tally, last)
}

fn print(name: &str, t: &Tally) {
    let (median, max) = t.iterations();
    println!(
        "{name}: {} steps, {} answered, {} failed (from {:?}); outer iterations median {median}, \
         max {max}; verify at most {:.1e} ({:.1e} of the size); the baseline from the answer lands \
         {:.1e} away at most (it moved on {} steps); the continuation from the previous answer \
         {:.1e}; flips {:?}",
        t.steps,
        t.answered,
        t.failed.len(),
        t.failed.first(),
        t.residual_abs,
        t.residual,
        t.agreement,
        t.moved,
        t.continuation,
        t.flips
    );
}

fn turn() -> Vec<f64> {
    (0..=360).map(|d| f64::from(d).to_radians()).collect()
}

fn legs() -> Vec<f64> {
    (0..=300).map(|k| 13.0 + 0.01 * f64::from(k)).collect()
}

#[test]
fn the_triad_six_bar_sweeps_a_whole_turn_in_agreement_with_the_baseline() {
    let ex = example("triad_sixbar", "theta");
    let (t, _) = sweep(&ex, &turn(), false);
    print("triad_sixbar", &t);
    assert_eq!(t.answered, 361, "{t:?}");
    assert!(t.failed.is_empty() && t.flips.is_empty(), "{t:?}");
}

#[test]
fn the_3rpr_sweep_with_l2_fixed_stops_at_the_tangency_with_an_error() {
    let ex = example("rpr3", "leg1");
    let (t, _) = sweep(&ex, &legs(), false);
    print("rpr3, l2 fixed", &t);
    // Answers from 13 to 15.37, each checked; from 15.38 on, where the followed assembly is
    // on the other branch of `l2`, errors.
    assert_eq!(t.answered, 238, "{t:?}");
    assert_eq!(t.failed.len(), 63, "{t:?}");
    assert!((t.failed[0] - 15.38).abs() < 1e-9, "{t:?}");
}

#[test]
fn the_3rpr_sweep_follows_the_motion_to_16_when_the_caller_flips_l2() {
    let ex = example("rpr3", "leg1");
    let (t, _) = sweep(&ex, &legs(), true);
    print("rpr3, l2 flipped on failure", &t);
    assert_eq!(t.answered, 301, "{t:?}");
    let l2 = ex.branch("l2");
    assert_eq!(t.flips.len(), 1, "{t:?}");
    let (at, name, to) = &t.flips[0];
    assert!(
        (at - 15.38).abs() < 1e-9 && name == &ex.plan.branches[l2].name && *to == 1,
        "{t:?}"
    );
}

/// The sine of the angle from the directed line `platform.p1` -> `B2` to `platform.p2`:
/// positive when `platform.p2` is on the left (branch 0 of `l2`), negative on the right
/// (branch 1), zero where the second leg's circles are tangent.
fn side(s: &Solution) -> f64 {
    let b = s.by_name();
    let at = |n: &str| b.point(n).unwrap_or_else(|| panic!("no point {n}"));
    let (p1, p2, b2) = (at("platform.p1"), at("platform.p2"), at("B2"));
    let (ax, ay) = (b2[0] - p1[0], b2[1] - p1[1]);
    let (qx, qy) = (p2[0] - p1[0], p2[1] - p1[1]);
    (ax * qy - ay * qx) / (ax.hypot(ay) * qx.hypot(qy))
}

/// The error the 3-RPR's iteration closes (`l3`) with `platform.p1_angle` at `angle` on
/// branch `l2` of the second leg's circles, or `None` where they do not meet.
fn error_at(ex: &Example, params: &[f64], angle: f64, l2: usize) -> Option<f64> {
    let choice = Choice::Given(vec![l2]);
    let errors = interp::errors_at(&ex.model, &ex.plan, params, &[angle], &choice).ok()?;
    errors.first().copied()
}

/// The last angle, from `inside` (where the second leg's circles meet) toward `outside`
/// (where they do not), at which they meet: the edge of the stretch where `l2` exists, to
/// rounding level. Both branches of `l2` meet there.
fn edge(ex: &Example, params: &[f64], mut inside: f64, mut outside: f64) -> f64 {
    assert!(
        error_at(ex, params, inside, 0).is_some() && error_at(ex, params, outside, 0).is_none()
    );
    loop {
        let mid = 0.5 * (inside + outside);
        if mid == inside || mid == outside {
            return inside;
        }
        if error_at(ex, params, mid, 0).is_some() {
            inside = mid;
        } else {
            outside = mid;
        }
    }
}

/// Issue 18's open question: the 3-RPR sweep with `l2` fixed stops after `leg1 = 15.37`;
/// does the motion go on, and on which branch of `l2`? Measured three ways:
/// - the baseline's Newton continued from the plan's answer at 15.37 in steps of 1e-4 goes
///   on smoothly to 16, and `platform.p2` crosses the line from `platform.p1` to `B2` (the
///   second leg's circles tangent) once, at `leg1*` between 15.3728 and 15.3729, from the
///   left (`l2 = 0`) to the right (`l2 = 1`);
/// - the error the iteration closes, at the edge of the stretch of `platform.p1_angle` where
///   the second leg's circles meet (where both branches of `l2` take the same value),
///   changes sign at that same `leg1*`: before it, branch 0's error function has its root
///   just inside the edge; after it, branch 0's has none there (its error keeps one sign up
///   to the edge) and branch 1's has it. The followed root reaches the edge of its branch's
///   existence interval and goes on on the other branch: the two branches of a
///   circle-circle intersection meet at tangency;
/// - at 15.38 `--all-solutions` (`all::solve_all`) lists the baseline's continued
///   configuration on `l2 = 1`, and no assembly on `l2 = 0` anywhere near it.
#[test]
fn the_3rpr_motion_crosses_the_tangency_of_l2_onto_its_other_branch() {
    let ex = example("rpr3", "leg1");
    assert_eq!((ex.plan.branches.len(), ex.plan.defaults.len()), (1, 1));
    let before: Vec<f64> = legs().into_iter().take(238).collect();
    let (t, last) = sweep(&ex, &before, false);
    assert_eq!(t.answered, 238, "{t:?}");
    let last = last.expect("an answer at 15.37");
    assert!((last.params[ex.driver] - 15.37).abs() < 1e-9);
    assert_eq!(last.branches, vec![0]);
    assert!(
        side(&last.solution) > 0.0,
        "l2 = 0 is platform.p2 left of p1 -> B2"
    );
    let angle = last.defaults[0];

    // The error at the edge, as `leg1` moves: both branches' value there.
    let at_edge = |leg1: f64| -> (f64, f64, f64) {
        let params = ex.params(leg1);
        let e = edge(&ex, &params, angle - 0.01, angle + 0.01);
        let (e0, e1) = (error_at(&ex, &params, e, 0), error_at(&ex, &params, e, 1));
        (
            e,
            e0.expect("l2 = 0 at the edge"),
            e1.expect("l2 = 1 at the edge"),
        )
    };
    let (edge_37, e0_37, e1_37) = at_edge(15.37);
    let (edge_38, e0_38, e1_38) = at_edge(15.38);
    println!(
        "leg1 = 15.37: edge of l2 at p1_angle {edge_37:.12}, error there {e0_37:+.6e} (l2 = 0), \
         {e1_37:+.6e} (l2 = 1); the followed root {angle:.12}, {:.2e} rad inside",
        edge_37 - angle
    );
    println!(
        "leg1 = 15.38: edge of l2 at p1_angle {edge_38:.12}, error there {e0_38:+.6e} (l2 = 0), \
         {e1_38:+.6e} (l2 = 1)"
    );
    // The two branches coincide at the edge.
    assert!((e0_37 - e1_37).abs() < 1e-4 && (e0_38 - e1_38).abs() < 1e-4);
    // At 15.37 the followed root is just inside the edge, where branch 0's error changes sign.
    assert!(edge_37 > angle && edge_37 - angle < 1e-6);
    assert!(e0_37 > 0.0);
    let p37 = ex.params(15.37);
    assert!(error_at(&ex, &p37, edge_37 - 1e-6, 0).is_some_and(|e| e < 0.0));
    // At 15.38 the edge's error has the other sign: on branch 0 the error keeps its sign from
    // 0.01 rad inside up to the edge (no root there), on branch 1 it changes sign.
    assert!(e0_38 < 0.0);
    let p38 = ex.params(15.38);
    let mut sign_change_1 = None;
    for k in 2..=12 {
        let a = edge_38 - 10f64.powi(-k);
        let f0 = error_at(&ex, &p38, a, 0).expect("inside");
        let f1 = error_at(&ex, &p38, a, 1).expect("inside");
        println!(
            "leg1 = 15.38, p1_angle = edge - 1e-{k}: error {f0:+.6e} (l2 = 0), {f1:+.6e} (l2 = 1)"
        );
        assert!(f0 < 0.0, "l2 = 0 has no root near the edge at 15.38");
        if f1 < 0.0 && sign_change_1.is_none() {
            sign_change_1 = Some(k);
        }
    }
    assert!(error_at(&ex, &p38, edge_38 - 1e-2, 1).is_some_and(|e| e > 0.0));
    assert!(
        sign_change_1.is_some(),
        "l2 = 1 has a root near the edge at 15.38"
    );

    // Where the edge's error is zero: the root on the edge.
    let (mut lo, mut hi) = (15.37, 15.38);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if at_edge(mid).1 > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let star = 0.5 * (lo + hi);
    println!(
        "leg1* = {star:.10}: the root of l2 = 0 reaches the edge, error there {:+.1e}",
        at_edge(star).1
    );
    assert!((15.3728..15.3729).contains(&star), "{star}");

    // The baseline continued from the answer at 15.37 to 16 in steps of 1e-4: where p2 changes
    // side.
    let mut baseline = Baseline::new(&ex.model).expect("baseline");
    let (mut at, mut from) = (last.params.clone(), last.config.clone());
    let mut solution = last.solution.clone();
    let mut crossings = Vec::new();
    let mut at_38 = None;
    for k in 1..=6300 {
        let leg1 = 15.37 + 1e-4 * f64::from(k);
        let params = ex.params(leg1);
        let (s, cfg, _) = newton(&ex, &mut baseline, (&at, &from), &params)
            .unwrap_or_else(|| panic!("leg1 = {leg1}: the continuation does not converge"));
        let step = distance(&s, &solution);
        assert!(step < 1e-4, "leg1 = {leg1}: the continuation jumped {step}");
        if (side(&s) > 0.0) != (side(&solution) > 0.0) {
            crossings.push((leg1 - 1e-4, side(&solution), leg1, side(&s)));
        }
        if k == 100 {
            at_38 = Some(s.clone());
        }
        (at, from, solution) = (params, cfg, s);
    }
    println!(
        "platform.p2 changes side of platform.p1 -> B2 (leg1, sine before, leg1, sine after): \
         {crossings:?}"
    );
    assert_eq!(crossings.len(), 1, "{crossings:?}");
    let (a, sa, b, sb) = crossings[0];
    assert!(
        sa > 0.0 && sb < 0.0 && a <= star && star <= b,
        "{crossings:?}, leg1* {star}"
    );

    // What `gcs solve --set leg1=15.38 --all-solutions` lists: the continued configuration on
    // l2 = 1, and nothing on l2 = 0 near it.
    let continued = at_38.expect("the continuation at 15.38");
    let all = gcs_compiler::all::solve_all(
        &ex.model,
        &ex.plan,
        &ex.all,
        &p38,
        &ex.plan.sketch_defaults(),
    );
    assert!(all.complete && all.solutions.len() == 6, "{all:?}");
    let nearest = (all.solutions.iter())
        .min_by(|a, b| distance(a, &continued).total_cmp(&distance(b, &continued)))
        .expect("assemblies");
    assert!(distance(nearest, &continued) <= SAME, "{nearest:?}");
    assert_eq!(nearest.branches, vec![("l2".to_string(), 1)]);
    for s in all.solutions.iter().filter(|s| s.branches[0].1 == 0) {
        assert!(distance(s, &continued) > 1e-2, "{s:?}");
    }
}
