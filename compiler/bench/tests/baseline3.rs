//! The 3d numeric baseline (Newton-Raphson and Levenberg-Marquardt on the raw equations of a
//! spatial model) against the independent verifier and against the interpreter: every 3d
//! example (found by `examples/discover.rs`) solved cold from its sketch, from its sketch
//! jiggled, and warm from the interpreter's answer with its driving param moved a little (to
//! the interpreter's answer there); Kramer's brick from random sketches; a chain of 16 spatial
//! four-bars on the sparse path; scale invariance; and every 3d example through `gcs bench`'s
//! comparison.
//!
//! `cargo test -p gcs-bench --release --test baseline3 -- --nocapture` prints the iterations.

use gcs_bench::baseline::{Baseline, Baseline3, Linear, Method, Options, Outcome};
use gcs_compiler::analyse;
use gcs_compiler::config::D3;
use gcs_compiler::interp::{run_in, Choice};
use gcs_compiler::solution::Solution;
use gcs_compiler::verify;
use gcs_lang::expr::Dim;
use gcs_lang::model::Space;
use gcs_lang::Model;
use std::collections::BTreeSet;
use std::fmt::Write as _;

fn load_text(name: &str, text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{name}: {diags:?}");
    model.unwrap_or_else(|| panic!("{name}: no model"))
}

mod discover {
    include!("../../../examples/discover.rs");
}

/// Every 3d example, by name.
fn examples() -> Vec<(String, Model)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    discover::analysed(&root, discover::Folder::Examples)
        .into_iter()
        .filter(|m| m.space == Space::D3)
        .map(|m| {
            let model = load_text(&m.relative(), &m.text);
            (m.stem, model)
        })
        .collect()
}

/// Whether the model keeps a free motion: a default of its plan that no outer iteration
/// varies (a point's place on a plane, an idle spin). Its answers are then one of a family:
/// the plan keeps the free motion where the sketch has it, the baseline's Newton moves it as
/// its steps fall, and both are right.
fn free_motion(model: &Model) -> bool {
    let plan = analyse(model).expect("analysis").plan;
    let varied: BTreeSet<_> = plan
        .iterations
        .iter()
        .flat_map(|it| it.defaults.clone())
        .collect();
    (0..plan.defaults.len()).any(|d| !varied.contains(&gcs_compiler::plan::DefaultId(d as u32)))
}

/// Whether the model's constraints are redundant in part (the plan checks a relation the
/// others imply: a SCARA's weld to an upright target fixes its tilt twice over). The
/// baseline's equations then have a rank-deficient Jacobian at every solution, where Newton's
/// method converges only linearly and stalls a little above its tolerance.
fn redundant(model: &Model) -> bool {
    let plan = analyse(model).expect("analysis").plan;
    (plan.steps.iter()).any(|s| matches!(s.op, gcs_compiler::plan::Op::Check { guard: false, .. }))
}

/// The baseline's solution, read like the interpreter's, with its verified residual.
fn read(model: &Model, b: &Baseline3, params: &[f64], x: &[f64]) -> (Solution, f64) {
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let cfg = b.config(params, x).expect("config");
    let s = Solution::read_space(model, &cfg, &all);
    let r = verify::max_residual(&verify::residuals(model, &s, params));
    (s, r)
}

/// The size of a solution: its largest coordinate, at least 1.
fn size(s: &Solution) -> f64 {
    s.points
        .iter()
        .flat_map(|(_, p)| p.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()))
}

/// The largest difference between two solutions over every point, vector and scalar.
fn difference(a: &Solution, b: &Solution) -> f64 {
    let b = b.by_name();
    let mut d = 0.0f64;
    let nan = [f64::NAN; 3];
    for (name, p) in &a.points {
        for (x, y) in p.iter().zip(b.point(name).unwrap_or(&nan)) {
            d = d.max((x - y).abs());
        }
    }
    for (name, p) in &a.vectors {
        for (x, y) in p.iter().zip(b.vector(name).unwrap_or(&nan)) {
            d = d.max((x - y).abs());
        }
    }
    for (name, v) in &a.scalars {
        d = d.max((v - b.scalar(name).unwrap_or(f64::NAN)).abs());
    }
    if d.is_nan() {
        f64::INFINITY
    } else {
        d
    }
}

/// The param a sweep drives (the first angle, else the first param) and a small move of it:
/// 2 degrees, or 1% of its value.
fn nudge(model: &Model, params: &[f64]) -> Vec<f64> {
    let mut p = params.to_vec();
    let driver = (model.params.iter().enumerate())
        .find(|(_, (_, q))| q.dim == Dim::Angle)
        .or_else(|| model.params.iter().enumerate().next());
    if let Some((i, (_, q))) = driver {
        p[i] += if q.dim == Dim::Angle {
            2f64.to_radians()
        } else {
            0.01 * p[i].abs().max(1.0)
        };
    }
    p
}

/// The interpreter's answer on the default branches, and the configuration it reached.
fn interpreted(model: &Model, params: &[f64]) -> (Solution, gcs_compiler::config::Config<D3>) {
    let analysis = analyse(model).expect("analysis");
    assert!(analysis.unsolved.is_empty(), "{:?}", analysis.unsolved);
    let plan = &analysis.plan;
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let run = run_in::<D3>(
        model,
        plan,
        params,
        &plan.sketch_defaults(),
        &Choice::Given(branches),
    )
    .expect("the interpreter solves it");
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    (Solution::read_space(model, &run.config, &all), run.config)
}

#[test]
fn every_3d_example_solves_cold_from_its_sketch_and_verifies() {
    let mut report = String::new();
    let list = examples();
    assert!(list.len() >= 11, "{} 3d examples", list.len());
    for (name, model) in &list {
        let params = model.default_params();
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            for linear in [Linear::Dense, Linear::Sparse] {
                let mut b = Baseline3::with_linear(model, linear).expect("baseline");
                assert_eq!(b.is_sparse(), linear == Linear::Sparse);
                let mut x = b.start_from_sketch(&params);
                let opts = Options {
                    method,
                    max_iterations: 200,
                    ..Options::default()
                };
                let out = b.solve(&params, &mut x, &opts);
                assert!(
                    out.converged,
                    "{name} {method:?} {linear:?}: {out:?} ({} unknowns, {} equations)",
                    b.unknowns(),
                    b.equations()
                );
                let (s, r) = read(model, &b, &params, &x);
                let bound = 1e-10 * size(&s);
                assert!(
                    r <= bound,
                    "{name} {method:?} {linear:?}: verify says {r:e} (bound {bound:e})"
                );
                let _ = writeln!(
                    report,
                    "{name:18} {method:?}/{linear:?}: {} unknowns, {} equations, {} iterations, \
                     residual {:.1e}, verify {r:.1e}",
                    b.unknowns(),
                    b.equations(),
                    out.iterations,
                    out.max_residual,
                );
            }
        }
    }
    println!("{report}");
}

#[test]
fn every_3d_example_follows_the_interpreter_from_a_warm_start() {
    let mut report = String::new();
    for (name, model) in &examples() {
        let params = model.default_params();
        let redundant = redundant(model);
        let (_, at_start) = interpreted(model, &params);
        let moved = nudge(model, &params);
        let (answer, _) = interpreted(model, &moved);
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            for linear in [Linear::Dense, Linear::Sparse] {
                let mut b = Baseline3::with_linear(model, linear).expect("baseline");
                let mut x = b.unknowns_from_config(&params, &at_start);
                // The interpreter's answer is a solution of the baseline's equations.
                let mut same = x.clone();
                let out = b.solve(&params, &mut same, &Options::default());
                assert!(out.converged, "{name}: the interpreter's answer: {out:?}");
                let opts = Options {
                    method,
                    ..Options::default()
                };
                let out = b.solve(&moved, &mut x, &opts);
                assert!(out.converged, "{name} {method:?} {linear:?} warm: {out:?}");
                let (s, r) = read(model, &b, &moved, &x);
                let bound = 1e-10 * size(&s);
                assert!(
                    r <= bound,
                    "{name} {method:?} {linear:?} warm: verify says {r:e}"
                );
                let diff = difference(&answer, &s);
                // The same assembly, unless a free motion lets the baseline end elsewhere in
                // its family (verified above all the same).
                // Redundant equations: Newton stalls linearly near the answer, to 1e-7.
                assert!(
                    diff <= 1e-9 || free_motion(model) || (diff <= 1e-7 && redundant),
                    "{name} {method:?} {linear:?}: {diff:e} from the interpreter's answer"
                );
                let _ = writeln!(
                    report,
                    "{name:18} {method:?}/{linear:?}: warm {} iterations, {diff:.1e} from the \
                     interpreter's answer",
                    out.iterations
                );
            }
        }
    }
    println!("{report}");
}

/// The unknowns read back from the configuration they describe are the same unknowns, and a
/// 2d model is refused by the 3d baseline (and a 3d one by the 2d baseline).
#[test]
fn unknowns_and_configurations_convert_both_ways_and_spaces_are_kept_apart() {
    for (name, model) in &examples() {
        let params = model.default_params();
        let b = Baseline3::new(model).expect("baseline");
        let x = b.start_from_sketch(&params);
        let cfg = b.config(&params, &x).expect("config");
        let back = b.unknowns_from_config(&params, &cfg);
        for (i, (u, v)) in x.iter().zip(&back).enumerate() {
            assert!(
                (u - v).abs() <= 1e-12 * (1.0 + u.abs()),
                "{name}: unknown {i}: {u} then {v}"
            );
        }
        assert!(Baseline::new(model).is_err(), "{name}");
    }
    let planar = load_text(
        "planar.gcs",
        "space 2d; fixed point A = (0, 0); point B = (1, 1); coincident(A, B);",
    );
    let err = Baseline3::new(&planar).expect_err("a 2d model");
    assert!(err.contains("3d"), "{err}");
}

/// A chain of `n` spatial four-bars (RSSR): rocker `l{i}` turns about a ground axis at
/// `(4i, 0, 0)` tilted by +-0.3 rad about x; coupler `k{i}`, a body with spherical joints at
/// both ends, joins `l{i}.b` to `l{i+1}.c`, so the rocker of each four-bar is the crank of the
/// next; `l0` is driven. The couplers' lengths are those of an assembly at the turns
/// `phi_i`, which the sketch has perturbed, so a cold start has work to do. Each coupler
/// keeps its free spin about its own axis (a passive DOF), so the system is not square.
fn chain(n: usize) -> String {
    let mut s = String::from("space 3d;\n");
    let tilt = |i: usize| if i.is_multiple_of(2) { 0.3f64 } else { -0.3 };
    let phi = |i: usize| 0.5 + 0.2 * (i as f64).sin();
    let _ = writeln!(s, "param theta = {};", phi(0));
    s.push_str("fixed body ground {\n");
    for i in 0..=n {
        let (sn, cs) = tilt(i).sin_cos();
        let _ = writeln!(
            s,
            "  marker g{i} = ({}, 0, 0) z (0, {sn}, {cs}) x (1, 0, 0);",
            4 * i
        );
    }
    s.push_str("}\n");
    // A rocker's point at local `l`, turned by phi about its axis.
    let turned = |i: usize, l: [f64; 3]| -> [f64; 3] {
        let (sn, cs) = tilt(i).sin_cos();
        let a = [0.0, sn, cs];
        let (sp, cp) = phi(i).sin_cos();
        let d = a[0] * l[0] + a[1] * l[1] + a[2] * l[2];
        let c = [
            a[1] * l[2] - a[2] * l[1],
            a[2] * l[0] - a[0] * l[2],
            a[0] * l[1] - a[1] * l[0],
        ];
        [0, 1, 2].map(|k| {
            let o = if k == 0 { 4.0 * i as f64 } else { 0.0 };
            o + l[k] * cp + c[k] * sp + a[k] * d * (1.0 - cp)
        })
    };
    let c_local = |i: usize| {
        let (sn, cs) = tilt(i).sin_cos();
        [0.0, 3.0 * cs, -3.0 * sn]
    };
    for i in 0..=n {
        let (sn, cs) = tilt(i).sin_cos();
        let j = 0.03 * (i as f64 * 1.7).sin();
        let c = c_local(i);
        let _ = writeln!(
            s,
            "body l{i} at ({}, {j}, {j}) rotated {} about ({j}, {sn}, {cs}) {{\n  \
             marker o = (0, 0, 0) z (0, {sn}, {cs}) x (1, 0, 0);\n  \
             point b = (1.5, 0, 0);\n  point c = ({}, {}, {});\n}}",
            4.0 * i as f64 + j,
            phi(i) + j,
            c[0],
            c[1],
            c[2]
        );
    }
    for i in 0..n {
        let b = turned(i, [1.5, 0.0, 0.0]);
        let c = turned(i + 1, c_local(i + 1));
        let j = 0.03 * (i as f64 * 2.3).cos();
        let _ = writeln!(
            s,
            "body k{i} at ({}, {}, {}) rotated {j} about (1, 1, 1) {{\n  \
             point a = (0, 0, 0);\n  point b = ({}, {}, {});\n}}",
            b[0] - j,
            b[1] + j,
            b[2],
            c[0] - b[0],
            c[1] - b[1],
            c[2] - b[2]
        );
    }
    for i in 0..=n {
        let _ = writeln!(s, "revolute(l{i}.o, ground.g{i});");
    }
    s.push_str("drive: offset_x(ground.g0, l0.o) = theta;\n");
    for i in 0..n {
        let _ = writeln!(s, "spherical(k{i}.a, l{i}.b);");
        let _ = writeln!(s, "spherical(k{i}.b, l{}.c);", i + 1);
    }
    s
}

#[test]
fn a_chain_of_16_spatial_four_bars_solves_on_the_sparse_path() {
    let model = load_text("chain16.gcs", &chain(16));
    let params = model.default_params();
    let mut answers: Vec<Solution> = Vec::new();
    for linear in [Linear::Auto, Linear::Dense] {
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            let mut b = Baseline3::with_linear(&model, linear).expect("baseline");
            assert_eq!(
                b.is_sparse(),
                linear == Linear::Auto,
                "{} unknowns",
                b.unknowns()
            );
            assert_eq!(b.unknowns(), 6 * 17 + 6 * 16);
            let mut x = b.start_from_sketch(&params);
            let out = b.solve(
                &params,
                &mut x,
                &Options {
                    method,
                    max_iterations: 200,
                    ..Options::default()
                },
            );
            assert!(out.converged, "{linear:?} {method:?}: {out:?}");
            println!(
                "chain of 16, {linear:?} {method:?}: {} unknowns, {} equations, cold {} \
                 iterations",
                b.unknowns(),
                b.equations(),
                out.iterations
            );
            let (s, r) = read(&model, &b, &params, &x);
            assert!(
                r <= 1e-10 * size(&s),
                "{linear:?} {method:?}: verify says {r:e}"
            );
            // Warm: a small change of the drive converges in a few Newton steps.
            let mut p2 = params.clone();
            p2[0] += 0.01;
            let mut x2 = x.clone();
            let warm: Outcome = b.solve(&p2, &mut x2, &Options::default());
            assert!(
                warm.converged && warm.iterations <= 6,
                "{linear:?} {method:?} warm: {warm:?}"
            );
            let (_, r) = read(&model, &b, &p2, &x2);
            assert!(r <= 1e-9, "{linear:?} {method:?} warm: verify says {r:e}");
            println!("  then warm {} iterations", warm.iterations);
            answers.push(s);
        }
    }
    // The same assembly on both paths.
    for s in &answers[1..] {
        let mut pts = s.clone();
        pts.vectors.clear();
        let d = difference(&pts, &answers[0]);
        assert!(d <= 1e-8, "the paths differ by {d:e}");
    }
}

/// A tiny deterministic generator (xorshift), so the jiggled starts are the same each run.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Every 3d example from its sketch with every unknown jiggled by up to 0.1 (a length, or
/// radians): where the sketch already assembles (`bennett`, `points_planes`), the cold start
/// above does nothing, and this is the test that makes it work. Every run converges and
/// verifies; which assembly it lands on is a numeric solver's business.
#[test]
fn every_3d_example_solves_from_a_jiggled_sketch() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut report = String::new();
    for (name, model) in &examples() {
        let params = model.default_params();
        let redundant = redundant(model);
        let mut its = Vec::new();
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            let mut b = Baseline3::new(model).expect("baseline");
            for trial in 0..5 {
                let mut x = b.start_from_sketch(&params);
                for v in x.iter_mut() {
                    *v += 0.2 * (rng.next() - 0.5);
                }
                let opts = Options {
                    method,
                    max_iterations: 200,
                    ..Options::default()
                };
                let out = b.solve(&params, &mut x, &opts);
                // Redundant equations: Newton may stall just above its tolerance (verified
                // below all the same).
                let stalled = out.max_residual <= 1e-10 && redundant;
                assert!(
                    out.converged || stalled,
                    "{name} {method:?} trial {trial}: {out:?}"
                );
                let (s, r) = read(model, &b, &params, &x);
                let bound = 1e-10 * size(&s);
                assert!(
                    r <= bound,
                    "{name} {method:?} trial {trial}: verify says {r:e}"
                );
                its.push(out.iterations);
            }
        }
        let _ = writeln!(report, "{name:18} Newton, then LM: {its:?} iterations");
    }
    println!("{report}");
}

/// `gcs bench`'s comparison (`gcs_bench::bench::run`) on every 3d example, the plan in the
/// interpreter against the 3d baseline along a sweep of the driving param (a whole turn of an
/// angle in 13 samples, else 90% to 110% of the first param): the plan never jumps from one
/// assembly to another between neighbouring samples (the baseline's continuation from one
/// answer reaches the next), every answer of the baseline verifies, and where the plan
/// assembles all along, so does the baseline, warm from its previous answer.
///
/// Where the plan does not assemble, the baseline may (`door` beyond a half turn, whose
/// unsigned angle target `a` is met at `2 pi - a`, as `verify` measures it) or may not (the
/// Stewart platform past a pose with no assembly on its branch, from which Newton, warm from
/// the last answer, does not find the next).
#[test]
fn the_bench_measures_every_3d_example_against_the_3d_baseline() {
    use gcs_bench::bench::{self, Settings};
    for (name, model) in &examples() {
        let analysis = analyse(model).expect("analysis");
        let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let sweep = bench::sweep(model, 13);
        let scope = model.top_level().map(|(id, _)| id).collect();
        let compiled = bench::interpreted(model, &analysis.plan, &scope, &branches, &sweep, 1.0);
        let settings = Settings {
            budget_ns: 1.0,
            ..Settings::default()
        };
        let report = bench::run(model, &analysis.plan, &branches, sweep, compiled, &settings)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let b = &report.baseline;
        // A free motion that the baseline moves differently is no jump of the plan.
        if !free_motion(model) {
            assert_eq!(report.branch_flips, 0, "{name}: the plan jumped");
        }
        assert!(
            b.max_residual <= 1e-9,
            "{name}: the baseline's residual {:e}",
            b.max_residual
        );
        if report.compiled_failures == 0 {
            assert_eq!(
                b.failures, 0,
                "{name}: the baseline failed where the plan did not"
            );
        }
        println!(
            "{name:18} {:?} unknowns/equations, plan failures {}, flips {}, residual {:.1e}; \
             baseline failures {}, residual {:.1e}, warm flips {}, cold on another assembly {}",
            b.size,
            report.compiled_failures,
            report.branch_flips,
            report.compiled_max_residual,
            b.failures,
            b.max_residual,
            b.branch_flips,
            b.cold_branch_flips
        );
    }
}

/// Kramer's brick from random sketches (anywhere in a box of side 40, turned by up to a half
/// turn about any axis, as `compiler/tests/spatial.rs` places it for the plan): Newton and
/// Levenberg-Marquardt both bring its three points onto the three fixed points, which the
/// test knows without the baseline or the plan.
#[test]
fn the_brick_lands_on_its_three_points_from_random_sketches() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut range = |lo: f64, hi: f64| lo + (hi - lo) * rng.next();
    let mut worst = 0;
    for trial in 0..50 {
        let at = [range(-20.0, 20.0), range(-20.0, 20.0), range(-20.0, 20.0)];
        let axis = [range(-1.0, 1.0), range(-1.0, 1.0), range(-1.0, 1.0)];
        let angle = range(-180.0, 180.0);
        let text = format!(
            "space 3d;\nfixed point g1 = (0, 0, 0);\nfixed point g2 = (4, 0, 0);\n\
             fixed point g3 = (0, 3, 0);\n\
             body brick at ({}, {}, {}) rotated {angle} deg about ({}, {}, {}) {{\n\
             point b1 = (0, 0, 0);\npoint b2 = (4, 0, 0);\npoint b3 = (0, 3, 0);\n}}\n\
             coincident(brick.b1, g1);\ncoincident(brick.b2, g2);\ncoincident(brick.b3, g3);\n",
            at[0], at[1], at[2], axis[0], axis[1], axis[2]
        );
        let model = load_text("brick.gcs", &text);
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            let mut b = Baseline3::new(&model).expect("baseline");
            let mut x = b.start_from_sketch(&[]);
            let opts = Options {
                method,
                max_iterations: 100,
                ..Options::default()
            };
            let out = b.solve(&[], &mut x, &opts);
            assert!(out.converged, "trial {trial} {method:?}: {out:?}");
            worst = worst.max(out.iterations);
            let (s, _) = read(&model, &b, &[], &x);
            let by = s.by_name();
            for (p, g) in [
                ("brick.b1", [0.0, 0.0, 0.0]),
                ("brick.b2", [4.0, 0.0, 0.0]),
                ("brick.b3", [0.0, 3.0, 0.0]),
            ] {
                let q = by.point(p).expect("a point");
                let off = (0..3).fold(0.0f64, |m, k| m.max((q[k] - g[k]).abs()));
                assert!(
                    off <= 1e-12 * 30.0,
                    "trial {trial} {method:?}: {p} is {off:e} off"
                );
            }
        }
    }
    println!("the brick from 50 random sketches: at most {worst} iterations");
}

/// Every number of a model that has only lengths (no angle), times `s`: after the header,
/// each numeric literal is multiplied (the leg names `l1`... are not numbers).
fn scaled(text: &str, s: f64) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        if code.trim_start().starts_with("space") {
            out.push_str(code);
            out.push('\n');
            continue;
        }
        let mut word = String::new();
        let flush = |word: &mut String, out: &mut String| {
            if let Ok(v) = word.parse::<f64>() {
                let _ = write!(out, "{:?}", v * s);
            } else {
                out.push_str(word);
            }
            word.clear();
        };
        for c in code.chars() {
            let starts_number = word.is_empty() && (c.is_ascii_digit() || c == '.');
            let continues = !word.is_empty() && (c.is_ascii_alphanumeric() || c == '.' || c == '_');
            if starts_number || continues || (word.is_empty() && (c.is_alphabetic() || c == '_')) {
                word.push(c);
            } else {
                flush(&mut word, &mut out);
                out.push(c);
            }
        }
        flush(&mut word, &mut out);
        out.push('\n');
    }
    out
}

/// The 3d baseline is scale-invariant, as the 2d one: the Stewart platform with every length
/// times 1e-6, 1e-3, 1e3 and 1e6 takes the same Newton steps from its sketch as at unit scale
/// (to a tolerance of 1e-12 times its scale, which every scale can reach) and lands on the
/// same pose, scaled.
#[test]
fn the_3d_baseline_is_scale_invariant() {
    let path = format!("{}/../../examples/stewart.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("stewart.gcs");
    let mut unit: Option<(usize, Solution)> = None;
    for s in [1.0, 1e-6, 1e-3, 1e3, 1e6] {
        let model = load_text("stewart.gcs", &scaled(&text, s));
        let params = model.default_params();
        for linear in [Linear::Dense, Linear::Sparse] {
            let mut b = Baseline3::with_linear(&model, linear).expect("baseline");
            let mut x = b.start_from_sketch(&params);
            let opts = Options {
                tolerance: 1e-12 * s,
                ..Options::default()
            };
            let out = b.solve(&params, &mut x, &opts);
            assert!(out.converged, "s = {s} {linear:?}: {out:?}");
            let (sol, _) = read(&model, &b, &params, &x);
            match &unit {
                None => unit = Some((out.iterations, sol)),
                Some((its, at_one)) => {
                    assert_eq!(out.iterations, *its, "s = {s} {linear:?}");
                    let by = sol.by_name();
                    for (name, p) in &at_one.points {
                        let q = by.point(name).expect("the same points");
                        for (a, u) in q.iter().zip(p) {
                            assert!(
                                (a / s - u).abs() <= 1e-9,
                                "s = {s} {linear:?} {name}: {a} vs {u} * {s}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// A tool welded to a marker of a fixed cell (turned about a skew axis and moved), sketched
/// elsewhere, with its marker's z axis within 17 degrees of the target's: the baseline's
/// equations of `weld` take it where the plan does, and `verify` agrees.
#[test]
fn a_welded_tool_lands_where_the_plan_puts_it() {
    let model = load_text(
        "weld.gcs",
        "space 3d;
         fixed body cell at (1, -2, 0.5) rotated 35 deg about (1, 2, 3) {
             marker target = (0.4, 1.2, -0.7) z (1, 1, 0) x (1, -1, 2);
         }
         body tool at (5, 3, -1) rotated -20 deg about (0, 1, 0) {
             marker m = (0.1, 0.2, 0.3) z (0, 1, 0) x (1, 0, 0);
             point tip = (0.5, 0, 1.5);
         }
         weld(tool.m, cell.target);",
    );
    let (planned, _) = interpreted(&model, &[]);
    for method in [Method::Newton, Method::LevenbergMarquardt] {
        let mut b = Baseline3::new(&model).expect("baseline");
        assert_eq!(
            b.equations(),
            3 + 2 + 1,
            "a coincidence, two tilts and a turn"
        );
        let mut x = b.start_from_sketch(&[]);
        let opts = Options {
            method,
            max_iterations: 100,
            ..Options::default()
        };
        let out = b.solve(&[], &mut x, &opts);
        assert!(out.converged, "{method:?}: {out:?}");
        let (s, r) = read(&model, &b, &[], &x);
        assert!(r <= 1e-10 * size(&s), "{method:?}: verify says {r:e}");
        let d = difference(&s, &planned);
        assert!(d <= 1e-9, "{method:?}: {d:e} from the plan's answer");
    }
}
