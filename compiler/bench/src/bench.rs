//! `gcs bench`: the compiled plan against the numeric baseline on a sweep of a model's params.
//!
//! Both solve the same samples. The compiled side is the generated solver when the caller
//! could build one (it hands in its timings and answers as a [`CompiledRun`]) and the
//! interpreter otherwise; the baseline is [`crate::baseline`]'s Newton solver of the model's
//! space, warm-started from its previous answer as a numeric solver in a sweep is. Every answer of both is re-checked
//! by [`gcs_compiler::verify`], so the residuals compare like with like. Branch flips are counted
//! against a continuation: the baseline started from the compiled plan's previous answer and
//! run to convergence on the next sample lands on the assembly continuous with it.

use crate::baseline::{Baseline, Baseline3, Linear, Method, Numeric, Options as NewtonOptions};
use gcs_compiler::plan::Plan;
use gcs_compiler::solution::Solution;
use gcs_lang::expr::Dim;
use gcs_lang::model::{GeomId, Space};
use gcs_lang::Model;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::time::Instant;

/// The params of every sample of a sweep.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The param the sweep drives, if the model has params.
    pub driver: Option<String>,
    /// Its range: from, to.
    pub range: (f64, f64),
    /// The params of each sample, in the model's param order.
    pub params: Vec<Vec<f64>>,
}

/// A sweep of `samples` points: the first angle param through a full turn from its default
/// (a crank's revolution), else the first param from 90% to 110% of its default.
///
/// # Panics
///
/// When `samples` is under 2 (`gcs bench` refuses it on the command line).
pub fn sweep(model: &Model, samples: usize) -> Sweep {
    let base = model.default_params();
    assert!(samples >= 2, "a sweep has two samples or more, its ends");
    let driver = model
        .params
        .iter()
        .enumerate()
        .find(|(_, (_, p))| p.dim == Dim::Angle)
        .or_else(|| model.params.iter().enumerate().next());
    let Some((index, (_, param))) = driver else {
        return Sweep {
            driver: None,
            range: (0.0, 0.0),
            params: vec![base; samples],
        };
    };
    let v = base[index];
    let (from, to) = if param.dim == Dim::Angle {
        (
            v,
            v + std::f64::consts::TAU * (samples - 1) as f64 / samples as f64,
        )
    } else if v == 0.0 {
        (-0.1, 0.1)
    } else {
        (0.9 * v, 1.1 * v)
    };
    let params = (0..samples)
        .map(|k| {
            let mut p = base.clone();
            p[index] = from + (to - from) * k as f64 / (samples - 1) as f64;
            p
        })
        .collect();
    Sweep {
        driver: Some(param.name.clone()),
        range: (from, to),
        params,
    }
}

/// Per-solve times of one solver over a sweep.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// Median over the samples, in nanoseconds.
    pub median_ns: f64,
    /// 90th percentile over the samples, in nanoseconds.
    pub p90_ns: f64,
}

impl Timing {
    /// The median and 90th percentile of per-sample times.
    pub fn of(ns: &[f64]) -> Timing {
        let mut v: Vec<f64> = ns.iter().copied().filter(|t| t.is_finite()).collect();
        if v.is_empty() {
            return Timing::default();
        }
        v.sort_by(f64::total_cmp);
        let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
        Timing {
            median_ns: at(0.5),
            p90_ns: at(0.9),
        }
    }
}

/// The compiled side's answers: per-sample solve time and solution (or its error's text).
#[derive(Clone, Debug)]
pub struct CompiledRun {
    /// `generated` or `interpreted`.
    pub kind: &'static str,
    /// Nanoseconds per solve, by sample.
    pub ns: Vec<f64>,
    /// The solution of each sample, with its residual measured by [`gcs_compiler::verify`].
    pub solutions: Vec<Result<Solution, String>>,
    /// Samples where a warm sweep found no assembly near the last answer (the one it followed
    /// ended at a fold) and went on with the assembly nearest its last answer.
    pub restarts: usize,
}

/// How far a solution's points moved from the sketch's: the sum of their squared
/// displacements (what least motion minimises; a radius is no point). Every point of `s` must
/// be in `sketch`.
pub fn squared_motion(sketch: &Solution, s: &Solution) -> f64 {
    (s.points.iter())
        .map(|(n, p)| {
            let q = &sketch
                .points
                .iter()
                .find(|(m, _)| m == n)
                .expect("a point")
                .1;
            p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum::<f64>()
        })
        .sum()
}

/// Repeats `solve` until about `budget_ns` have passed (at least once) and returns the time
/// of one call; the caller's closure should `black_box` what it computes.
pub fn time_per_call(budget_ns: f64, mut solve: impl FnMut()) -> f64 {
    let start = Instant::now();
    solve();
    let once = start.elapsed().as_nanos() as f64;
    let reps = ((budget_ns / once.max(1.0)) as usize).clamp(1, 1_000_000);
    let start = Instant::now();
    for _ in 0..reps {
        solve();
    }
    start.elapsed().as_nanos() as f64 / reps as f64
}

/// How `gcs bench` measures: the time spent repeating each sample's solve (1 ns means one
/// solve per sample, for tests), and the baseline's linear algebra. The default, 2 ms, holds
/// dozens of solves of a long chain: at 200 µs a solve of 50 µs was timed three times, and
/// read 30-60% slower than over hundreds of solves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Nanoseconds of repeated solves per sample.
    pub budget_ns: f64,
    /// Dense, sparse, or as the size demands.
    pub linear: Linear,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            budget_ns: 2_000_000.0,
            linear: Linear::Auto,
        }
    }
}

/// The compiled plan run by the interpreter on every sample.
pub fn interpreted(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    branches: &[usize],
    sweep: &Sweep,
    budget_ns: f64,
) -> CompiledRun {
    let choice = gcs_compiler::interp::Choice::Given(branches.to_vec());
    let defaults = plan.sketch_defaults();
    let mut ns = Vec::new();
    let mut solutions = Vec::new();
    for params in &sweep.params {
        ns.push(time_per_call(budget_ns, || {
            let ok = match model.space {
                Space::D2 => gcs_compiler::interp::run(model, plan, params, &choice).is_ok(),
                Space::D3 => gcs_compiler::interp::run_in::<gcs_compiler::config::D3>(
                    model, plan, params, &defaults, &choice,
                )
                .is_ok(),
            };
            std::hint::black_box(ok);
        }));
        solutions.push(
            gcs_compiler::solve_plan(model, plan, scope, params, branches)
                .map_err(|e| e.to_string()),
        );
    }
    CompiledRun {
        kind: "interpreted",
        ns,
        solutions,
        restarts: 0,
    }
}

/// The baseline's side of the report.
#[derive(Clone, Debug, Default)]
pub struct BaselineSide {
    /// Per-solve times, warm-started along the sweep.
    pub timing: Timing,
    /// The largest residual of its answers, by [`gcs_compiler::verify`].
    pub max_residual: f64,
    /// Samples where it did not converge.
    pub failures: usize,
    /// Times its warm-started answer moved to another assembly than the compiled plan's.
    pub branch_flips: usize,
    /// Samples whose cold start (from the sketch) ended on another assembly than the plan's.
    pub cold_branch_flips: usize,
    /// Unknowns and equations.
    pub size: (usize, usize),
    /// Whether its linear algebra is sparse.
    pub sparse: bool,
    /// Whether it starts from its previous answer (a sweep) or from the sketch every time (a
    /// model without params, whose samples are all the same solve).
    pub warm: bool,
}

/// One point of the baseline's run time against error: after `iterations`, this residual.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorPoint {
    /// Newton iterations run.
    pub iterations: usize,
    /// Time of the run, in nanoseconds.
    pub ns: f64,
    /// Its largest residual, by [`gcs_compiler::verify`].
    pub residual: f64,
}

/// The report of `gcs bench`.
#[derive(Clone, Debug)]
pub struct Report {
    /// The model's file.
    pub model: String,
    /// The sweep.
    pub sweep: Sweep,
    /// `generated` or `interpreted`.
    pub compiled_kind: &'static str,
    /// The compiled plan's per-solve times.
    pub compiled: Timing,
    /// Its largest residual over the sweep.
    pub compiled_max_residual: f64,
    /// Samples where it returned an error.
    pub compiled_failures: usize,
    /// Samples where its warm sweep went on with the assembly nearest its last answer, the one it followed
    /// having ended at a fold ([`CompiledRun::restarts`]).
    pub compiled_restarts: usize,
    /// Jumps of the compiled plan away from the assembly continuous with its previous answer.
    pub branch_flips: usize,
    /// The baseline.
    pub baseline: BaselineSide,
    /// Baseline median over compiled median.
    pub ratio: f64,
    /// The baseline's run time against error, cold from the sketch at the first sample.
    pub cold_curve: Vec<ErrorPoint>,
    /// The same, warm from the answer of the sample before (the second sample).
    pub warm_curve: Vec<ErrorPoint>,
    /// The baseline run again to the compiled plan's accuracy, when its own stopping
    /// tolerance left it less accurate: what "as fast at the same accuracy" compares with.
    pub equal_accuracy: Option<EqualAccuracy>,
}

/// The baseline's sweep with its tolerance at the compiled plan's largest residual.
#[derive(Clone, Debug, Default)]
pub struct EqualAccuracy {
    /// The tolerance it ran to.
    pub tolerance: f64,
    /// Per-solve times, warm-started along the sweep as in [`BaselineSide`].
    pub timing: Timing,
    /// The largest residual of its answers, by [`gcs_compiler::verify`].
    pub max_residual: f64,
    /// Samples where it did not reach the tolerance.
    pub failures: usize,
    /// Its median over the compiled plan's.
    pub ratio: f64,
}

/// The thresholds of the run-time-against-error table.
pub const ERROR_LEVELS: [f64; 3] = [1e-4, 1e-8, 1e-12];

/// The largest distance between same-named points of two solutions, over a scale: how far
/// apart two assemblies are.
fn distance(a: &Solution, b: &Solution) -> f64 {
    let mut d: f64 = 0.0;
    let mut scale: f64 = f64::MIN_POSITIVE;
    let index: std::collections::HashMap<&str, &[f64]> = b
        .points
        .iter()
        .map(|(n, v)| (n.as_str(), v.as_slice()))
        .collect();
    for (name, p) in &a.points {
        if let Some(q) = index.get(name.as_str()) {
            for (x, y) in p.iter().zip(q.iter()) {
                d = d.max((x - y).abs());
                scale = scale.max(x.abs());
            }
        }
    }
    d / scale
}

/// Two answers on different assemblies: farther apart, relative to their size, than any
/// solver's stopping tolerance and rounding can take them, even on a badly conditioned
/// problem (a point where nearly parallel lines meet moves by an ulp over their angle); a flip
/// moves a point by a fraction of the mechanism's size.
const SAME_ASSEMBLY: f64 = 1e-5;

/// Runs the bench: the compiled side's answers against the baseline on the same sweep.
/// `plan` is the whole plan (not pruned to the outputs) with the branch indices the compiled
/// side used: the continuation that counts flips starts from every geom's place. The
/// baseline is the model's space's: [`Baseline`] or [`Baseline3`].
pub fn run(
    model: &Model,
    plan: &Plan,
    branches: &[usize],
    sweep: Sweep,
    compiled: CompiledRun,
    settings: &Settings,
) -> Result<Report, String> {
    match model.space {
        Space::D2 => {
            let baseline = Baseline::with_linear(model, settings.linear)?;
            run_with(baseline, model, plan, branches, sweep, compiled, settings)
        }
        Space::D3 => {
            let baseline = Baseline3::with_linear(model, settings.linear)?;
            run_with(baseline, model, plan, branches, sweep, compiled, settings)
        }
    }
}

/// [`run`] with the model's baseline.
fn run_with<B: Numeric>(
    mut baseline: B,
    model: &Model,
    plan: &Plan,
    branches: &[usize],
    sweep: Sweep,
    compiled: CompiledRun,
    settings: &Settings,
) -> Result<Report, String> {
    let choice = gcs_compiler::interp::Choice::Given(branches.to_vec());
    let defaults = plan.sketch_defaults();
    // The whole plan's configuration at a sample, to start the baseline's continuation from
    // (the generated solver equals it to 1e-14 on what it computes, as its tests show).
    let plan_config = |params: &[f64]| {
        gcs_compiler::interp::run_in::<B::Space>(model, plan, params, &defaults, &choice)
            .ok()
            .map(|r| r.config)
    };
    // Converged at 1e-12 relative to the model's size: an absolute 1e-12 is out of reach at
    // size 1e6 and loose at 1e-6. The floor is for angle equations, whose residuals stop at a
    // few ulps of pi.
    let size = baseline
        .start_from_sketch(&sweep.params[0])
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let newton = NewtonOptions {
        method: Method::Newton,
        tolerance: (1e-12 * size).max(1e-14),
        ..NewtonOptions::default()
    };
    let read = |b: &B, params: &[f64], x: &[f64]| -> Solution {
        let Some(mut s) = b.solution(params, x) else {
            return Solution {
                max_residual: f64::INFINITY,
                ..Solution::default()
            };
        };
        s.max_residual =
            gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(model, &s, params));
        s
    };
    let compiled_ok: Vec<Option<&Solution>> =
        compiled.solutions.iter().map(|s| s.as_ref().ok()).collect();

    // The baseline along the sweep, warm-started from its previous answer (cold from the
    // sketch every time for a model without params: its samples are all the same solve).
    let mut side = BaselineSide {
        size: (baseline.unknowns(), baseline.equations()),
        sparse: baseline.is_sparse(),
        warm: sweep.driver.is_some(),
        ..BaselineSide::default()
    };
    let mut ns = Vec::new();
    let mut previous = baseline.start_from_sketch(&sweep.params[0]);
    let mut agreed_before = true;
    let mut x = previous.clone();
    for (k, params) in sweep.params.iter().enumerate() {
        ns.push(time_per_call(settings.budget_ns, || {
            x.copy_from_slice(&previous);
            std::hint::black_box(baseline.solve(params, &mut x, &newton).converged);
        }));
        x.copy_from_slice(&previous);
        let outcome = baseline.solve(params, &mut x, &newton);
        if !outcome.converged {
            side.failures += 1;
            continue;
        }
        let s = read(&baseline, params, &x);
        side.max_residual = side.max_residual.max(s.max_residual);
        if let Some(c) = compiled_ok[k] {
            let agrees = distance(c, &s) <= SAME_ASSEMBLY;
            if !agrees && agreed_before {
                side.branch_flips += 1;
            }
            agreed_before = agrees;
        }
        if side.warm {
            previous.copy_from_slice(&x);
        }
    }
    side.timing = Timing::of(&ns);

    // The same sweep to the compiled plan's accuracy, when the baseline stopped short of it:
    // its tolerance at the plan's largest residual (never below a few ulps of the size, which
    // rounding does not let Newton reach).
    let compiled_max_residual = compiled_ok
        .iter()
        .flatten()
        .map(|s| s.max_residual)
        .fold(0.0, f64::max);
    let equal_accuracy =
        (side.max_residual > compiled_max_residual && side.failures == 0).then(|| {
            let tolerance = compiled_max_residual.max(4.0 * f64::EPSILON * size.max(1.0));
            let tight = NewtonOptions {
                tolerance,
                ..newton
            };
            let mut equal = EqualAccuracy {
                tolerance,
                ..EqualAccuracy::default()
            };
            let mut ns = Vec::new();
            let mut previous = baseline.start_from_sketch(&sweep.params[0]);
            let mut x = previous.clone();
            for params in &sweep.params {
                ns.push(time_per_call(settings.budget_ns, || {
                    x.copy_from_slice(&previous);
                    std::hint::black_box(baseline.solve(params, &mut x, &tight).converged);
                }));
                x.copy_from_slice(&previous);
                if !baseline.solve(params, &mut x, &tight).converged {
                    equal.failures += 1;
                }
                equal.max_residual = equal
                    .max_residual
                    .max(read(&baseline, params, &x).max_residual);
                if side.warm {
                    previous.copy_from_slice(&x);
                }
            }
            equal.timing = Timing::of(&ns);
            equal
        });

    // Cold starts from the sketch: where a numeric solver lands without a previous answer.
    for (k, params) in sweep.params.iter().enumerate() {
        let mut x = baseline.start_from_sketch(params);
        if baseline.solve(params, &mut x, &newton).converged {
            if let Some(c) = compiled_ok[k] {
                if distance(c, &read(&baseline, params, &x)) > SAME_ASSEMBLY {
                    side.cold_branch_flips += 1;
                }
            }
        }
    }

    // Continuity of the compiled plan: its answers at two neighbouring samples must be joined
    // by the baseline's continuation from one to the other, forward or backward. Both are
    // tried because from a singular configuration (a change point, where two assemblies
    // meet) the forward continuation may take either way, while the backward one, from a
    // regular configuration, is unique.
    let mut branch_flips = 0;
    // The plan's configuration of the compiled answer at sample `k`: run from that answer's
    // own defaults (a warm sweep's, which may follow another assembly than the sketch's).
    let answer_config = |k: usize| {
        let mut defaults = defaults.clone();
        if let Some(s) = compiled_ok[k] {
            for (d, value) in plan.defaults.iter().zip(defaults.iter_mut()) {
                if let Some((_, v)) = s.defaults.iter().find(|(n, _)| *n == d.name) {
                    *value = *v;
                }
            }
        }
        gcs_compiler::interp::run_in::<B::Space>(model, plan, &sweep.params[k], &defaults, &choice)
            .ok()
            .map(|r| r.config)
    };
    let joined = |from: usize, to: usize, baseline: &mut B| -> bool {
        let (Some(start), Some(answer)) = (answer_config(from), compiled_ok[to]) else {
            return true;
        };
        let mut x = baseline.unknowns_from_config(&sweep.params[from], &start);
        let params = &sweep.params[to];
        !baseline.solve(params, &mut x, &newton).converged
            || distance(answer, &read(baseline, params, &x)) <= SAME_ASSEMBLY
    };
    for k in 1..sweep.params.len() {
        if compiled_ok[k - 1].is_some()
            && !joined(k - 1, k, &mut baseline)
            && !joined(k, k - 1, &mut baseline)
        {
            branch_flips += 1;
        }
    }

    // Run time against error: Newton stopped after 1, 2, ... iterations.
    let curve = |baseline: &mut B, params: &[f64], start: &[f64]| -> Vec<ErrorPoint> {
        let mut out = Vec::new();
        for iterations in 0..=30 {
            let opts = NewtonOptions {
                method: Method::Newton,
                tolerance: 0.0,
                max_iterations: iterations,
                ..NewtonOptions::default()
            };
            let mut x = start.to_vec();
            let ns = time_per_call(settings.budget_ns, || {
                x.copy_from_slice(start);
                std::hint::black_box(baseline.solve(params, &mut x, &opts).converged);
            });
            x.copy_from_slice(start);
            baseline.solve(params, &mut x, &opts);
            let residual = read(baseline, params, &x).max_residual;
            out.push(ErrorPoint {
                iterations,
                ns,
                residual,
            });
            if residual <= 1e-15 || !residual.is_finite() {
                break;
            }
            if out.len() > 3 && residual >= out[out.len() - 3].residual {
                // Stalled: no further iteration will help.
                break;
            }
        }
        out
    };
    let p0 = &sweep.params[0];
    let cold_start = baseline.start_from_sketch(p0);
    let cold_curve = curve(&mut baseline, p0, &cold_start);
    let warm_curve = match plan_config(p0) {
        Some(first) if sweep.params.len() > 1 => {
            let start = baseline.unknowns_from_config(p0, &first);
            curve(&mut baseline, &sweep.params[1], &start)
        }
        _ => Vec::new(),
    };

    let compiled_timing = Timing::of(&compiled.ns);
    let ratio = side.timing.median_ns / compiled_timing.median_ns;
    let equal_accuracy = equal_accuracy.map(|e| EqualAccuracy {
        ratio: e.timing.median_ns / compiled_timing.median_ns,
        ..e
    });
    Ok(Report {
        model: model.source.name().to_string(),
        sweep,
        compiled_kind: compiled.kind,
        compiled: compiled_timing,
        compiled_max_residual,
        compiled_failures: compiled.solutions.iter().filter(|s| s.is_err()).count(),
        compiled_restarts: compiled.restarts,
        branch_flips,
        baseline: side,
        ratio,
        cold_curve,
        warm_curve,
        equal_accuracy,
    })
}

/// The time the curve first reaches `level`, if it does.
pub fn time_to(curve: &[ErrorPoint], level: f64) -> Option<f64> {
    curve.iter().find(|p| p.residual <= level).map(|p| p.ns)
}

fn json_num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        "null".into()
    }
}

fn json_opt(v: Option<f64>) -> String {
    v.map_or("null".into(), json_num)
}

fn escape(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out
}

impl Report {
    /// One JSON object: `ratio`, `compiled.{median_ns, p90_ns, max_residual, ...}`,
    /// `baseline.{...}`, `branch_flips`, and the run time against error.
    pub fn to_json(&self) -> String {
        let b = &self.baseline;
        let curve = |c: &[ErrorPoint]| -> String {
            let items: Vec<String> = c
                .iter()
                .map(|p| {
                    format!(
                        "{{\"iterations\": {}, \"ns\": {}, \"residual\": {}}}",
                        p.iterations,
                        json_num(p.ns),
                        json_num(p.residual)
                    )
                })
                .collect();
            format!("[{}]", items.join(", "))
        };
        let levels = |c: &[ErrorPoint]| -> String {
            let items: Vec<String> = ERROR_LEVELS
                .iter()
                .map(|&l| format!("\"{l:e}\": {}", json_opt(time_to(c, l))))
                .collect();
            format!("{{{}}}", items.join(", "))
        };
        format!(
            concat!(
                "{{\"model\": \"{}\", \"samples\": {}, \"driver\": {}, \"range\": [{}, {}], ",
                "\"ratio\": {}, \"branch_flips\": {}, ",
                "\"compiled\": {{\"kind\": \"{}\", \"median_ns\": {}, \"p90_ns\": {}, ",
                "\"max_residual\": {}, \"failures\": {}, \"restarts\": {}}}, ",
                "\"baseline\": {{\"method\": \"newton\", \"start\": \"{}\", \"linear\": \"{}\", \"unknowns\": {}, ",
                "\"equations\": {}, \"median_ns\": {}, \"p90_ns\": {}, \"max_residual\": {}, ",
                "\"failures\": {}, \"branch_flips\": {}, \"cold_branch_flips\": {}}}, ",
                "\"time_to_error\": {{\"cold\": {}, \"warm\": {}, ",
                "\"cold_curve\": {}, \"warm_curve\": {}}}, \"equal_accuracy\": {}}}"
            ),
            escape(&self.model),
            self.sweep.params.len(),
            self.sweep
                .driver
                .as_ref()
                .map_or("null".into(), |d| format!("\"{}\"", escape(d))),
            json_num(self.sweep.range.0),
            json_num(self.sweep.range.1),
            json_num(self.ratio),
            self.branch_flips,
            self.compiled_kind,
            json_num(self.compiled.median_ns),
            json_num(self.compiled.p90_ns),
            json_num(self.compiled_max_residual),
            self.compiled_failures,
            self.compiled_restarts,
            if b.warm { "warm" } else { "cold" },
            if b.sparse { "sparse" } else { "dense" },
            b.size.0,
            b.size.1,
            json_num(b.timing.median_ns),
            json_num(b.timing.p90_ns),
            json_num(b.max_residual),
            b.failures,
            b.branch_flips,
            b.cold_branch_flips,
            levels(&self.cold_curve),
            levels(&self.warm_curve),
            curve(&self.cold_curve),
            curve(&self.warm_curve),
            self.equal_accuracy.as_ref().map_or("null".to_string(), |e| format!(
                "{{\"tolerance\": {}, \"median_ns\": {}, \"p90_ns\": {}, \"max_residual\": {}, \"failures\": {}, \"ratio\": {}}}",
                json_num(e.tolerance),
                json_num(e.timing.median_ns),
                json_num(e.timing.p90_ns),
                json_num(e.max_residual),
                e.failures,
                json_num(e.ratio)
            )),
        )
    }

    /// The report for people: a table of both sides and the run time against error.
    pub fn to_text(&self) -> String {
        let b = &self.baseline;
        let mut s = String::new();
        let _ = writeln!(s, "bench {}", self.model);
        match &self.sweep.driver {
            Some(d) => {
                let _ = writeln!(
                    s,
                    "  sweep: {} samples of `{d}` from {:.6} to {:.6}",
                    self.sweep.params.len(),
                    self.sweep.range.0,
                    self.sweep.range.1
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "  sweep: {} solves at the defaults (no params)",
                    self.sweep.params.len()
                );
            }
        }
        let _ = writeln!(
            s,
            "\n  {:<46} {:>12} {:>12} {:>13} {:>9} {:>6}",
            "solver", "median", "p90", "max residual", "failures", "flips"
        );
        let mut row = |name: String, t: &Timing, residual: f64, failures: usize, flips: usize| {
            let _ = writeln!(
                s,
                "  {name:<46} {:>12} {:>12} {residual:>13.3e} {failures:>9} {flips:>6}",
                human_ns(t.median_ns),
                human_ns(t.p90_ns),
            );
        };
        row(
            format!("compiled plan ({})", self.compiled_kind),
            &self.compiled,
            self.compiled_max_residual,
            self.compiled_failures,
            self.branch_flips,
        );
        row(
            format!(
                "baseline (Newton, {}, {}; {} unknowns)",
                if b.warm { "warm" } else { "cold" },
                if b.sparse { "sparse" } else { "dense" },
                b.size.0
            ),
            &b.timing,
            b.max_residual,
            b.failures,
            b.branch_flips,
        );
        if let Some(e) = &self.equal_accuracy {
            row(
                format!("baseline to the plan's accuracy ({:.1e})", e.tolerance),
                &e.timing,
                e.max_residual,
                e.failures,
                0,
            );
        }
        if self.compiled_restarts > 0 {
            let _ = writeln!(
                s,
                "\n  the compiled plan's warm sweep went on with the assembly nearest its last answer at {} sample{}, where the one it followed ended (a fold: no assembly near the last answer)",
                self.compiled_restarts,
                if self.compiled_restarts == 1 { "" } else { "s" }
            );
        }
        let _ = writeln!(
            s,
            "\n  ratio (baseline median / compiled median): {:.1}x",
            self.ratio
        );
        if let Some(e) = &self.equal_accuracy {
            let _ = writeln!(s, "  ratio at the plan's accuracy: {:.1}x", e.ratio);
        }
        let _ = writeln!(
            s,
            "  baseline cold from the sketch: {} of {} samples on another assembly",
            b.cold_branch_flips,
            self.sweep.params.len()
        );
        let _ = writeln!(
            s,
            "\n  run time against error (baseline Newton; the compiled plan: {} at {:.1e})",
            human_ns(self.compiled.median_ns),
            self.compiled_max_residual
        );
        let _ = writeln!(s, "  {:<10} {:>12} {:>12}", "residual", "cold", "warm");
        for level in ERROR_LEVELS {
            let show = |c: &[ErrorPoint]| time_to(c, level).map_or("never".into(), human_ns);
            let _ = writeln!(
                s,
                "  {:<10} {:>12} {:>12}",
                format!("{level:.0e}"),
                show(&self.cold_curve),
                show(&self.warm_curve)
            );
        }
        s
    }

    /// An SVG plot of run time (log) against residual (log): the baseline's cold and warm
    /// curves, one point per iteration, and the compiled plan's single point.
    pub fn to_svg(&self) -> String {
        const W: f64 = 640.0;
        const H: f64 = 420.0;
        // Margins: left, right, top, bottom.
        const L: f64 = 70.0;
        const R: f64 = 20.0;
        const T: f64 = 30.0;
        const B: f64 = 50.0;
        // The legend's band under the plot.
        const LEGEND: f64 = 50.0;
        let floor = 1e-17;
        let pts = self
            .cold_curve
            .iter()
            .chain(&self.warm_curve)
            .map(|p| (p.ns, p.residual.max(floor)))
            .chain([(
                self.compiled.median_ns,
                self.compiled_max_residual.max(floor),
            )])
            .filter(|(t, r)| t.is_finite() && *t > 0.0 && r.is_finite());
        let (mut t0, mut t1, mut r0, mut r1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for (t, r) in pts {
            t0 = t0.min(t.log10());
            t1 = t1.max(t.log10());
            r0 = r0.min(r.log10());
            r1 = r1.max(r.log10());
        }
        if t0 > t1 {
            (t0, t1, r0, r1) = (0.0, 1.0, -16.0, 0.0);
        }
        // Whole decades, with room around the extreme points so none sits on the frame.
        let (t0, t1) = ((t0 - 0.3).floor(), (t1 + 0.3).ceil());
        let (r0, r1) = ((r0 - 0.5).floor(), (r1 + 0.5).ceil());
        let x = |t: f64| L + (t.log10() - t0) / (t1 - t0) * (W - L - R);
        let y = |r: f64| T + (r1 - r.max(floor).log10()) / (r1 - r0) * (H - T - B);
        let mut s = String::new();
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"11\">",
            H + LEGEND
        );
        let _ = writeln!(
            s,
            "<rect width=\"{W}\" height=\"{}\" fill=\"white\"/>",
            H + LEGEND
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">{}: run time against error</text>",
            W / 2.0,
            escape_xml(&self.model)
        );
        // Axes with a tick per decade.
        let _ = writeln!(
            s,
            "<path d=\"M{L},{T} V{} H{}\" stroke=\"black\" fill=\"none\"/>",
            H - B,
            W - R
        );
        for e in (t0 as i32)..=(t1 as i32) {
            let px = x(10f64.powi(e));
            let _ = writeln!(
                s,
                "<line x1=\"{px:.1}\" y1=\"{}\" x2=\"{px:.1}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{px:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                T,
                H - B,
                H - B + 15.0,
                human_ns(10f64.powi(e))
            );
        }
        for e in (r0 as i32)..=(r1 as i32) {
            if (e - r0 as i32) % 2 != 0 && r1 - r0 > 8.0 {
                continue;
            }
            let py = y(10f64.powi(e));
            let _ = writeln!(
                s,
                "<line x1=\"{L}\" y1=\"{py:.1}\" x2=\"{}\" y2=\"{py:.1}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">1e{e}</text>",
                W - R,
                L - 5.0,
                py + 4.0
            );
        }
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">time per solve</text>",
            (L + W - R) / 2.0,
            H - 12.0
        );
        let _ = writeln!(
            s,
            "<text x=\"15\" y=\"{}\" transform=\"rotate(-90 15 {})\" text-anchor=\"middle\">max residual</text>",
            (T + H - B) / 2.0,
            (T + H - B) / 2.0
        );
        for (curve, colour, label) in [
            (
                &self.cold_curve,
                "#d62728",
                "baseline Newton, cold from the sketch",
            ),
            (
                &self.warm_curve,
                "#ff7f0e",
                "baseline Newton, warm from the previous sample",
            ),
        ] {
            let path: Vec<String> = curve
                .iter()
                .filter(|p| p.ns > 0.0 && p.residual.is_finite())
                .map(|p| format!("{:.1},{:.1}", x(p.ns), y(p.residual)))
                .collect();
            if path.is_empty() {
                continue;
            }
            let _ = writeln!(
                s,
                "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>",
                path.join(" ")
            );
            for p in &path {
                let (px, py) = p.split_once(',').unwrap_or(("0", "0"));
                let _ = writeln!(
                    s,
                    "<circle cx=\"{px}\" cy=\"{py}\" r=\"2.5\" fill=\"{colour}\"/>"
                );
            }
            let _ = label;
        }
        let (cx, cy) = (
            x(self.compiled.median_ns),
            y(self.compiled_max_residual.max(floor)),
        );
        let _ = writeln!(
            s,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"8\" height=\"8\" fill=\"#1f77b4\"/>",
            cx - 4.0,
            cy - 4.0
        );
        // Legend.
        let legend = [
            (
                "#1f77b4",
                format!("gcs compiled plan ({})", self.compiled_kind),
            ),
            (
                "#d62728",
                "baseline Newton, cold from the sketch".to_string(),
            ),
            (
                "#ff7f0e",
                "baseline Newton, warm from the previous sample".to_string(),
            ),
        ];
        // Below the plot, so that it hides no point.
        for (i, (colour, text)) in legend.iter().enumerate() {
            let ly = H + 5.0 + 15.0 * i as f64;
            let _ = writeln!(
                s,
                "<rect x=\"{}\" y=\"{}\" width=\"10\" height=\"10\" fill=\"{colour}\"/><text x=\"{}\" y=\"{}\">{}</text>",
                L + 10.0,
                ly - 9.0,
                L + 25.0,
                ly,
                escape_xml(text)
            );
        }
        s.push_str("</svg>\n");
        s
    }
}

fn escape_xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A duration in the unit that reads best.
pub fn human_ns(ns: f64) -> String {
    if !ns.is_finite() {
        "-".into()
    } else if ns < 1e3 {
        format!("{ns:.1} ns")
    } else if ns < 1e6 {
        format!("{:.2} µs", ns / 1e3)
    } else if ns < 1e9 {
        format!("{:.2} ms", ns / 1e6)
    } else {
        format!("{:.2} s", ns / 1e9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timing_takes_median_and_p90() {
        let ns: Vec<f64> = (1..=100).map(f64::from).collect();
        let t = Timing::of(&ns);
        assert_eq!(t.median_ns, 51.0);
        assert_eq!(t.p90_ns, 90.0);
        assert_eq!(Timing::of(&[]), Timing::default());
    }

    #[test]
    fn time_to_finds_the_first_point_below() {
        let c = [
            ErrorPoint {
                iterations: 0,
                ns: 10.0,
                residual: 1.0,
            },
            ErrorPoint {
                iterations: 1,
                ns: 20.0,
                residual: 1e-5,
            },
            ErrorPoint {
                iterations: 2,
                ns: 30.0,
                residual: 1e-13,
            },
        ];
        assert_eq!(time_to(&c, 1e-4), Some(20.0));
        assert_eq!(time_to(&c, 1e-8), Some(30.0));
        assert_eq!(time_to(&c, 1e-16), None);
    }
}
