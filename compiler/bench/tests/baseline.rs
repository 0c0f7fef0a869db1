//! The numeric baseline (Newton-Raphson and Levenberg-Marquardt on the raw equations) against
//! the independent verifier and against the compiled plans: every example the analysis covers
//! (found by `examples/discover.rs`) solved cold from its sketch, a warm-started four-bar sweep
//! on the plan's `elbow = 0` branch, and a chain of 200 four-bars on the sparse path.

use gcs_bench::baseline::{Baseline, Linear, Method, Options, Stop};
use gcs_compiler::analyse;
use gcs_compiler::solution::Solution;
use gcs_compiler::verify;
use gcs_lang::Model;
use std::collections::BTreeSet;
use std::fmt::Write as _;

fn load_text(name: &str, text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{name}: {diags:?}");
    model.unwrap_or_else(|| panic!("{name}: no model"))
}

fn load(name: &str) -> Model {
    let path = format!("{}/../../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    load_text(&path, &String::from_utf8(bytes).expect("utf-8"))
}

fn param(model: &Model, name: &str) -> usize {
    let id = model
        .param_named(name)
        .unwrap_or_else(|| panic!("no param {name}"));
    id.into_raw().into_u32() as usize
}

/// The baseline's solution, read like the plan's, with its verified residual.
fn read(model: &Model, b: &Baseline, params: &[f64], x: &[f64]) -> (Solution, f64) {
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let cfg = b.config(params, x).expect("config");
    let s = Solution::read(model, &cfg, &all);
    let r = verify::max_residual(&verify::residuals(model, &s, params));
    (s, r)
}

/// The largest difference between two solutions over every point, vector and scalar.
fn difference(a: &Solution, b: &Solution) -> f64 {
    let b = b.by_name();
    let mut d = 0.0f64;
    for (name, p) in &a.points {
        let q = b.point(name).unwrap_or(&[f64::NAN, f64::NAN]);
        for (x, y) in p.iter().zip(q) {
            d = d.max((x - y).abs());
        }
    }
    for (name, p) in &a.vectors {
        let q = b.vector(name).unwrap_or(&[f64::NAN, f64::NAN]);
        for (x, y) in p.iter().zip(q) {
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

mod discover {
    include!("../../../examples/discover.rs");
}

#[test]
fn every_example_solves_cold_from_its_sketch_and_verifies() {
    let mut report = String::new();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    // The planar baseline: 3d models have their own.
    let planar = discover::analysed(&root, discover::Folder::Examples)
        .into_iter()
        .filter(|m| m.space == gcs_lang::model::Space::D2);
    for example in planar {
        let name = example.stem.as_str();
        let model = load_text(&example.relative(), &example.text);
        let analysis = analyse(&model).expect("analysis");
        let params = model.default_params();
        let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let plan = gcs_compiler::solve(&model, &analysis, &params, &branches).expect("plan");
        for method in [Method::Newton, Method::LevenbergMarquardt] {
            for linear in [Linear::Dense, Linear::Sparse] {
                let mut b = Baseline::with_linear(&model, linear).expect("baseline");
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
                let (s, r) = read(&model, &b, &params, &x);
                // Every constraint to 1e-10, but a tangency's own error: where a segment's end
                // is on the circle it touches (a fillet's joint), the raw equations (distance
                // form, point on circle) are singular along the line, so Newton leaves the
                // joint about the square root of its tolerance from the touching point, which
                // `verify` measures.
                for res in verify::residuals(&model, &s, &params) {
                    let c = &model.constraints[res.constraint];
                    let bound = if c.kind == gcs_lang::constraints::ConstraintKind::Tangent {
                        1e-5
                    } else {
                        1e-10
                    };
                    assert!(
                        res.value <= bound,
                        "{name} {method:?} {linear:?}: verify says `{}` is off by {:e} (largest {r:e})",
                        c.text,
                        res.value
                    );
                }
                let diff = difference(&plan, &s);
                let _ = writeln!(
                    report,
                    "{name:16} {method:?}/{linear:?}: {} unknowns, {} equations, {} iterations, \
                     residual {:.1e}, verify {r:.1e}, differs from the plan's default branches by {diff:.1e}",
                    b.unknowns(),
                    b.equations(),
                    out.iterations,
                    out.max_residual,
                );
                if name == "fourbar" {
                    assert!(
                        diff <= 1e-9,
                        "fourbar: baseline and plan differ by {diff:e}"
                    );
                }
            }
        }
    }
    println!("{report}");
}

#[test]
fn a_warm_four_bar_sweep_stays_on_the_plans_elbow_0_branch() {
    let model = load("fourbar");
    let analysis = analyse(&model).expect("analysis");
    let elbow = analysis
        .plan
        .branches
        .iter()
        .position(|b| b.name == "elbow")
        .expect("elbow");
    let mut branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
    branches[elbow] = 0;
    let theta = param(&model, "theta");
    let mut params = model.default_params();
    let mut b = Baseline::new(&model).expect("baseline");
    assert!(!b.is_sparse());
    // Start on the plan's branch at theta = 0: cold from the sketch, then checked.
    params[theta] = 0.0;
    let mut x = b.start_from_sketch(&params);
    let opts = Options::default();
    let mut worst = 0.0f64;
    for step in 0..=360 {
        params[theta] = (step as f64).to_radians();
        let out = b.solve(&params, &mut x, &opts);
        assert!(out.converged, "theta = {step} deg: {out:?}");
        let plan = gcs_compiler::solve(&model, &analysis, &params, &branches).expect("plan");
        let (s, r) = read(&model, &b, &params, &x);
        assert!(r <= 1e-10, "theta = {step} deg: verify says {r:e}");
        let (p, q) = (
            plan.by_name().point("coupler.c").expect("plan coupler.c"),
            s.by_name().point("coupler.c").expect("baseline coupler.c"),
        );
        let d = (p[0] - q[0]).hypot(p[1] - q[1]);
        worst = worst.max(d);
        assert!(
            d <= 1e-9,
            "theta = {step} deg: coupler.c {q:?} but the plan's elbow = 0 gives {p:?}"
        );
    }
    println!("warm sweep: worst |coupler.c - plan| = {worst:.1e}");
}

/// A chain of `n` four-bars on ground pivots `(4i, 0)`: body `l{i}` turns about pivot `i`
/// (its point `b` at 1.5, `c` at 3 and 90 degrees), coupler `k{i}` (length 4) joins `l{i}.b`
/// to `l{i+1}.c`, so the rocker of each four-bar is the crank of the next. `l0` is driven.
/// The sketch is a true assembly (upper circle intersections) at `theta` with every
/// placement perturbed, so a cold start has work to do.
fn chain(n: usize, theta: f64) -> String {
    let mut s = String::from("space 2d;\n");
    let _ = writeln!(s, "param theta = {theta};");
    s.push_str("fixed vector X = (1, 0);\n");
    for i in 0..=n {
        let _ = writeln!(s, "fixed point g{i} = ({}, 0);", 4 * i);
    }
    let mut phi = theta;
    let mut bodies = String::new();
    for i in 0..=n {
        let pivot = [4.0 * i as f64, 0.0];
        let jiggle = 0.03 * ((i as f64) * 1.7).sin();
        let _ = writeln!(
            bodies,
            "body l{i} at ({}, {}) rotated {} {{ point o = (0, 0); point b = (1.5, 0); point c = (0, 3); vector u = (1, 0); }}",
            pivot[0] + jiggle,
            jiggle,
            phi + jiggle
        );
        if i == n {
            break;
        }
        // The next rocker: |C - B| = 4, |C - P'| = 3, upper intersection.
        let bpt = [pivot[0] + 1.5 * phi.cos(), pivot[1] + 1.5 * phi.sin()];
        let next = [pivot[0] + 4.0, 0.0];
        let (ux, uy) = (next[0] - bpt[0], next[1] - bpt[1]);
        let d = ux.hypot(uy);
        let a = (16.0 - 9.0 + d * d) / (2.0 * d);
        let h = (16.0 - a * a).max(0.0).sqrt();
        let (ex, ey) = (ux / d, uy / d);
        let c = [bpt[0] + a * ex - h * ey, bpt[1] + a * ey + h * ex];
        let k = (c[1] - bpt[1]).atan2(c[0] - bpt[0]);
        let _ = writeln!(
            bodies,
            "body k{i} at ({}, {}) rotated {} {{ point b = (0, 0); point c = (4, 0); }}",
            bpt[0] - jiggle,
            bpt[1] + jiggle,
            k - jiggle
        );
        phi = (c[1] - next[1]).atan2(c[0] - next[0]) - std::f64::consts::FRAC_PI_2;
    }
    s.push_str(&bodies);
    s.push_str("drive: angle(X, l0.u) = theta;\n");
    for i in 0..=n {
        let _ = writeln!(s, "coincident(l{i}.o, g{i});");
    }
    for i in 0..n {
        let _ = writeln!(s, "coincident(k{i}.b, l{i}.b);");
        let _ = writeln!(s, "coincident(k{i}.c, l{}.c);", i + 1);
    }
    s
}

#[test]
fn a_chain_of_200_four_bars_solves_on_the_sparse_path() {
    let model = load_text("chain200", &chain(200, 0.5));
    let params = model.default_params();
    for method in [Method::Newton, Method::LevenbergMarquardt] {
        let mut b = Baseline::new(&model).expect("baseline");
        assert!(b.is_sparse(), "{} unknowns", b.unknowns());
        assert_eq!(b.unknowns(), 6 * 200 + 3);
        assert_eq!(b.equations(), b.unknowns());
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
        assert!(out.converged, "{method:?}: {out:?}");
        let (_, r) = read(&model, &b, &params, &x);
        assert!(r <= 1e-9, "{method:?}: verify says {r:e}");
        // Warm: a small change of the drive converges in a few Newton steps.
        let mut p2 = params.clone();
        p2[0] += 0.01;
        let out = b.solve(&p2, &mut x, &Options::default());
        assert!(
            out.converged && out.iterations <= 6,
            "{method:?} warm: {out:?}"
        );
        let (_, r) = read(&model, &b, &p2, &x);
        assert!(r <= 1e-9, "{method:?} warm: verify says {r:e}");
    }
}

#[test]
fn the_trace_records_every_iteration_and_errors_name_what_is_missing() {
    let model = load("fourbar");
    let params = model.default_params();
    let mut b = Baseline::new(&model).expect("baseline");
    let mut x = b.start_from_sketch(&params);
    let out = b.solve(
        &params,
        &mut x,
        &Options {
            trace: true,
            ..Options::default()
        },
    );
    assert_eq!(out.stop, Stop::Converged);
    assert_eq!(out.trace.len(), out.iterations + 1);
    assert!(out.trace.windows(2).all(|w| w[0].0 <= w[1].0));
    let three = load("brick");
    assert!(Baseline::new(&three).is_err());
}

/// The four-bar of `/examples/fourbar.gcs` with every length multiplied by `s` (ground 4,
/// crank 1.5, coupler 4, rocker 3: a Grashof crank-rocker, so the crank turns a full turn).
fn scaled_fourbar(s: f64) -> String {
    let l = |v: f64| format!("{}", v * s);
    format!(
        "space 2d;\n\
         param theta = 0;\n\
         fixed point A = (0, 0);\n\
         fixed point D = ({g}, 0);\n\
         fixed vector X = (1, 0);\n\
         body crank at (0, 0) {{ point a = (0, 0); point b = ({c}, 0); vector u = (1, 0); }}\n\
         body coupler at ({c}, 0) {{ point b = (0, 0); point c = ({g}, 0); }}\n\
         body rocker at ({g}, 0) {{ point d = (0, 0); point c = (0, {r}); }}\n\
         coincident(crank.a, A);\n\
         drive: angle(X, crank.u) = theta;\n\
         coincident(crank.b, coupler.b);\n\
         elbow: coincident(coupler.c, rocker.c);\n\
         coincident(rocker.d, D);\n\
         output coupler.c;\n",
        g = l(4.0),
        c = l(1.5),
        r = l(3.0),
    )
}

/// Newton is scale-invariant: the four-bar at every scale from 1e-6 to 1e6, swept warm over a
/// full turn of the crank in 10-degree steps, converges at every step within 10 iterations on
/// both linear-algebra paths, with the same iteration counts and the same (scaled) answer.
///
/// The tolerance is on the raw largest residual, which mixes lengths (of size `s`) and
/// radians, so it is `1e-12 max(1, s)`: 1e-12 relative on lengths (and absolute 1e-12 rad on
/// angles, at most) for `s >= 1`, 1e-12 rad on angles (and 1e-12 absolute, at most, on lengths)
/// for `s <= 1`. It is attainable at every scale: the floor of the length residuals is a few
/// ulps of the coordinates, about 1e-15 s, that of the angle residuals about 1e-15. As the
/// tolerance alone is loose on lengths for small `s`, the answer is also checked against the
/// unit-scale one times `s`, to 1e-9 relative.
#[test]
fn newton_is_scale_invariant_on_a_warm_four_bar_sweep() {
    // Unit scale first: the reference answer.
    let scales = [1.0, 1e-6, 1e-3, 1e3, 1e6];
    let mut unit: Vec<Vec<(String, Vec<f64>)>> = Vec::new();
    let mut report = String::new();
    let mut counts: Vec<Vec<usize>> = Vec::new();
    for linear in [Linear::Dense, Linear::Sparse] {
        for &s in &scales {
            let model = load_text("scaled_fourbar.gcs", &scaled_fourbar(s));
            let mut b = Baseline::with_linear(&model, linear).expect("baseline");
            assert_eq!(b.is_sparse(), linear == Linear::Sparse);
            let th = param(&model, "theta");
            let mut p = model.default_params();
            let opts = Options {
                tolerance: (1e-12 * s).max(1e-14),
                ..Default::default()
            };
            let mut x = b.start_from_sketch(&p);
            let cold = b.solve(&p, &mut x, &opts);
            assert!(cold.converged, "{linear:?} s={s}: cold {cold:?}");
            let mut its = Vec::new();
            for k in 0..=36 {
                p[th] = (10.0 * k as f64).to_radians();
                let o = b.solve(&p, &mut x, &opts);
                assert!(
                    o.converged && o.iterations <= 10,
                    "{linear:?} s={s} theta={k}0deg: {o:?}"
                );
                its.push(o.iterations);
                let (sol, _) = read(&model, &b, &p, &x);
                let pts = sol.points;
                if s == 1.0 && linear == Linear::Dense {
                    unit.push(pts);
                } else if !unit.is_empty() {
                    for ((n, q), (nu, qu)) in pts.iter().zip(&unit[k]) {
                        assert_eq!(n, nu);
                        for (a, u) in q.iter().zip(qu) {
                            assert!(
                                (a / s - u).abs() <= 1e-7,
                                "{linear:?} s={s} theta={k}0deg {n}: {a} vs {u} * {s}"
                            );
                        }
                    }
                }
            }
            let total: usize = its.iter().sum();
            let max = its.iter().max().copied().unwrap_or(0);
            writeln!(
                report,
                "{linear:?} s={s:e}: cold {} its, sweep max {max} total {total}: {its:?}",
                cold.iterations
            )
            .expect("write to a String");
            counts.push(its);
        }
    }
    eprintln!("{report}");
    // Scale-invariance: where the tolerance is the same relative one (1e-12 s), every scale
    // takes the same number of iterations at every step; below s = 1e-2 it is looser, and no
    // step takes more than at unit scale.
    for (i, c) in counts.iter().enumerate() {
        let s = scales[i % scales.len()];
        let same = 1e-12 * s >= 1e-14;
        for (a, u) in c.iter().zip(&counts[0]) {
            assert!(
                if same { a == u } else { a <= u },
                "iteration counts differ across scales:\n{report}"
            );
        }
    }
}

/// A part welded to a fixed seat (turned and moved), sketched elsewhere: the baseline's
/// equations of `weld` take it where the plan does, and `verify` agrees.
#[test]
fn a_welded_part_lands_where_the_plan_puts_it() {
    let model = load_text(
        "weld.gcs",
        "space 2d;
         fixed body ground at (1, 2) rotated 30 deg { marker seat = (0.5, -0.3) x (0.6, 0.8); }
         body part at (-3, 4) rotated -70 deg { marker m = (0.2, 0.1) x (1, 0);
                                                point tip = (1.2, 0.6); }
         weld(part.m, ground.seat);",
    );
    let analysis = analyse(&model).expect("analysis");
    let planned = gcs_compiler::solve(&model, &analysis, &[], &[]).expect("the plan solves it");
    for method in [Method::Newton, Method::LevenbergMarquardt] {
        let mut b = Baseline::new(&model).expect("baseline");
        assert_eq!(b.equations(), 2 + 1, "a coincidence and an angle");
        let mut x = b.start_from_sketch(&[]);
        let opts = Options {
            method,
            max_iterations: 100,
            ..Options::default()
        };
        let out = b.solve(&[], &mut x, &opts);
        assert!(out.converged, "{method:?}: {out:?}");
        let (s, r) = read(&model, &b, &[], &x);
        assert!(r <= 1e-10, "{method:?}: verify says {r:e}");
        let d = difference(&s, &planned);
        assert!(d <= 1e-9, "{method:?}: {d:e} from the plan's answer");
    }
}
