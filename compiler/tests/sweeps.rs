//! Sweeps: the four-bar and the crank-rocker over a full turn of the crank, in 1-degree steps,
//! on each fixed `elbow` branch.
//!
//! At every step where the loop closes, the solution must satisfy every constraint (verify's
//! residual at most 1e-12 times the model's size), stay on the side of the directed line
//! `crank.b -> D` that its branch index means (no flip), and equal an independent closed-form
//! construction written here: the intersection of the circle about `crank.b` with the coupler's
//! length and the circle about `D` with the rocker's length. Where the loop cannot close, the
//! solve must fail with `NoIntersection` on `elbow`, with the true gap.
//!
//! The closed form reads only the model's sketch (member coordinates in their body's frame,
//! fixed points, params), never the compiler's configuration or plan.

use gcs_compiler::analyse;
use gcs_compiler::analysis::Analysis;
use gcs_lang::model::Sketch;
use gcs_lang::Model;
use gcs_runtime::error::ErrorKind;

type P = [f64; 2];

fn load(path: &str) -> Model {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    let (_, model, diags) = gcs_lang::load(path, &bytes);
    assert!(diags.iter().all(|d| !d.is_error()), "{path}: {diags:?}");
    model.unwrap_or_else(|| panic!("{path}: no model"))
}

fn example(name: &str) -> String {
    format!("{}/../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"))
}

/// The sketch coordinates of a point geom or member (local to its body for a member), or the
/// sketch direction of a vector, evaluated with `params`.
fn sketch(model: &Model, name: &str, params: &[f64]) -> P {
    let id = model
        .geom_named(name)
        .unwrap_or_else(|| panic!("no geom {name}"));
    let c = match &model.geoms[id].sketch {
        Sketch::Point(c) | Sketch::Vector(c) => c,
        other => panic!("{name} is not a point or vector: {other:?}"),
    };
    assert_eq!(c.len(), 2, "{name} is not 2d");
    [
        model.exprs.eval(c[0], params),
        model.exprs.eval(c[1], params),
    ]
}

fn param(model: &Model, name: &str) -> usize {
    let id = model
        .param_named(name)
        .unwrap_or_else(|| panic!("no param {name}"));
    id.into_raw().into_u32() as usize
}

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}
fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}
fn scale(a: P, k: f64) -> P {
    [a[0] * k, a[1] * k]
}
fn norm(a: P) -> f64 {
    a[0].hypot(a[1])
}
fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
/// `v` rotated counter-clockwise by the angle whose cosine and sine are `c` and `s`.
fn rot(v: P, c: f64, s: f64) -> P {
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}
fn dist(a: P, b: P) -> f64 {
    norm(sub(a, b))
}

/// What the closed form says about one crank angle.
enum Closed {
    /// The loop closes: `c` is the joint `coupler.c` = `rocker.c`, `p` the coupler point (if
    /// the model has one).
    Assembles { b: P, c: P, p: Option<P> },
    /// The circles miss by `gap`.
    Misses { gap: f64 },
}

/// The independent construction: crank by rotation, then circle-circle intersection on the
/// side `branch` means (0: left of the directed line `crank.b -> D`, 1: right).
fn closed_form(model: &Model, params: &[f64], branch: usize) -> Closed {
    let theta = params[param(model, "theta")];
    let a_fixed = sketch(model, "A", params);
    let d_fixed = sketch(model, "D", params);
    let x = sketch(model, "X", params);
    // The crank turns so that crank.u points along X rotated by theta; crank.a sits on A.
    let (ca, cb, cu) = (
        sketch(model, "crank.a", params),
        sketch(model, "crank.b", params),
        sketch(model, "crank.u", params),
    );
    let phi = theta + x[1].atan2(x[0]) - cu[1].atan2(cu[0]);
    let b = add(a_fixed, rot(sub(cb, ca), phi.cos(), phi.sin()));
    let (kb, kc) = (
        sketch(model, "coupler.b", params),
        sketch(model, "coupler.c", params),
    );
    let (rd, rc) = (
        sketch(model, "rocker.d", params),
        sketch(model, "rocker.c", params),
    );
    let r1 = dist(kc, kb);
    let r2 = dist(rc, rd);
    let d = dist(d_fixed, b);
    if d > r1 + r2 {
        return Closed::Misses { gap: d - (r1 + r2) };
    }
    if d < (r1 - r2).abs() {
        return Closed::Misses {
            gap: (r1 - r2).abs() - d,
        };
    }
    let u = scale(sub(d_fixed, b), 1.0 / d);
    let left = [-u[1], u[0]];
    let along = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - along * along).max(0.0).sqrt();
    let side = if branch == 0 { 1.0 } else { -1.0 };
    let c = add(add(b, scale(u, along)), scale(left, side * h));
    // The coupler point by the rigid motion taking coupler.b -> b and coupler.c -> c.
    let p = model.geom_named("coupler.p").map(|_| {
        let kp = sketch(model, "coupler.p", params);
        let from = sub(kc, kb);
        let to = sub(c, b);
        let (cos, sin) = (dot(from, to) / (r1 * r1), cross(from, to) / (r1 * r1));
        add(b, rot(sub(kp, kb), cos, sin))
    });
    Closed::Assembles { b, c, p }
}

/// The model's size: the largest sketch coordinate or link length.
fn model_size(model: &Model, params: &[f64]) -> f64 {
    let mut size: f64 = 1.0;
    for name in [
        "A",
        "D",
        "crank.a",
        "crank.b",
        "coupler.b",
        "coupler.c",
        "rocker.d",
        "rocker.c",
    ] {
        let p = sketch(model, name, params);
        size = size.max(p[0].abs()).max(p[1].abs());
    }
    for (a, b) in [
        ("crank.a", "crank.b"),
        ("coupler.b", "coupler.c"),
        ("rocker.d", "rocker.c"),
    ] {
        size = size.max(dist(sketch(model, a, params), sketch(model, b, params)));
    }
    size
}

fn get(s: &gcs_compiler::solution::Solution, name: &str) -> P {
    let p = s
        .by_name()
        .point(name)
        .unwrap_or_else(|| panic!("solution has no point {name}"));
    [p[0], p[1]]
}

/// Counts for one sweep.
#[derive(Debug, Default)]
struct Counts {
    assembled: usize,
    dead: usize,
    runs: usize,
}

/// Sweeps `theta` over 0..360 degrees on branch `branch` with `overrides` applied to the
/// default params.
fn sweep(
    name: &str,
    model: &Model,
    analysis: &Analysis,
    overrides: &[(&str, f64)],
    branch: usize,
) -> Counts {
    let branches: Vec<usize> = analysis
        .plan
        .branches
        .iter()
        .map(|b| if b.name == "elbow" { branch } else { b.default })
        .collect();
    assert!(
        analysis.plan.branches.iter().any(|b| b.name == "elbow"),
        "{name}: no branch `elbow`"
    );
    let mut params = model.default_params();
    for (p, v) in overrides {
        params[param(model, p)] = *v;
    }
    let size = model_size(model, &params);
    let theta = param(model, "theta");
    let mut counts = Counts::default();
    // The side of the joint relative to crank.b -> D within the current run of assembled steps.
    let mut run_side: Option<f64> = None;
    for deg in 0..360 {
        params[theta] = (deg as f64).to_radians();
        let at = format!("{name}, elbow = {branch}, theta = {deg} deg");
        let result = gcs_compiler::solve(model, analysis, &params, &branches);
        match closed_form(model, &params, branch) {
            Closed::Misses { gap } => {
                counts.dead += 1;
                run_side = None;
                let e = match result {
                    Ok(s) => panic!(
                        "{at}: the loop cannot close (gap {gap}), but solve returned {:?}",
                        s.points
                    ),
                    Err(e) => e,
                };
                assert_eq!(e.kind, ErrorKind::NoIntersection, "{at}: {e}");
                assert_eq!(e.label, "elbow", "{at}: {e}");
                assert!(
                    (e.magnitude - gap).abs() <= 1e-12 * size,
                    "{at}: gap {} reported, {gap} expected",
                    e.magnitude
                );
            }
            Closed::Assembles { b, c, p } => {
                counts.assembled += 1;
                let s = result.unwrap_or_else(|e| panic!("{at}: the loop closes, but {e}"));
                // The residual, measured by verify on its own.
                let max = gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(
                    model, &s, &params,
                ));
                assert!(max <= 1e-12 * size, "{at}: max residual {max:e}");
                assert!(
                    s.max_residual <= 1e-12 * size,
                    "{at}: solution's max residual {:e}",
                    s.max_residual
                );
                assert_eq!(
                    s.branches,
                    vec![("elbow".to_string(), branch)],
                    "{at}: branches"
                );
                // The closed form.
                let close = |what: &str, got: P, want: P| {
                    assert!(
                        dist(got, want) <= 1e-12,
                        "{at}: {what} = {got:?}, closed form {want:?} (off by {:e})",
                        dist(got, want)
                    );
                };
                close("crank.b", get(&s, "crank.b"), b);
                close("coupler.b", get(&s, "coupler.b"), b);
                close("coupler.c", get(&s, "coupler.c"), c);
                close("rocker.c", get(&s, "rocker.c"), c);
                if let Some(p) = p {
                    close("coupler.p", get(&s, "coupler.p"), p);
                }
                // No flip: the side of rocker.c relative to crank.b -> D is the branch's
                // meaning and never changes within a run.
                let d_fixed = get(&s, "D");
                let side = cross(
                    sub(d_fixed, get(&s, "crank.b")),
                    sub(get(&s, "rocker.c"), get(&s, "crank.b")),
                );
                let want = if branch == 0 { 1.0 } else { -1.0 };
                assert!(
                    side * want > 0.0,
                    "{at}: rocker.c is on the wrong side of crank.b -> D (cross {side:e})"
                );
                let side = side.signum();
                match run_side {
                    None => {
                        counts.runs += 1;
                        run_side = Some(side);
                    }
                    Some(prev) => assert_eq!(prev, side, "{at}: branch flip within a run"),
                }
            }
        }
    }
    eprintln!(
        "{name} {overrides:?}, elbow = {branch}: {} assembled steps, {} dead steps, {} runs",
        counts.assembled, counts.dead, counts.runs
    );
    counts
}

#[test]
fn fourbar_sweeps_on_both_branches() {
    let model = load(&example("fourbar"));
    let analysis = analyse(&model).expect("analyse");
    for branch in [0, 1] {
        let counts = sweep("fourbar", &model, &analysis, &[], branch);
        // The example's four-bar is Grashof with the crank shortest (1.5 + 4 <= 4 + 3): it
        // assembles at every angle. The dead zones are in the variant below.
        assert_eq!(
            (counts.assembled, counts.dead),
            (360, 0),
            "fourbar, elbow = {branch}: {counts:?}"
        );
    }
}

#[test]
fn fourbar_with_a_long_crank_has_dead_zones() {
    // crank_len = 3.5: |crank.b - D| runs from 0.5 to 7.5, but the coupler (4) and rocker (3)
    // reach only between 1 and 7, so the loop breaks around 0 and 180 degrees.
    let model = load(&example("fourbar"));
    let analysis = analyse(&model).expect("analyse");
    for branch in [0, 1] {
        let counts = sweep("fourbar", &model, &analysis, &[("crank_len", 3.5)], branch);
        assert_eq!(counts.assembled + counts.dead, 360);
        assert!(counts.dead > 0, "no dead zone: {counts:?}");
        assert!(counts.assembled > 0, "never assembles: {counts:?}");
        assert_eq!(
            counts.runs, 2,
            "two runs between two dead zones: {counts:?}"
        );
    }
}

#[test]
fn crank_rocker_traces_its_coupler_curve_on_both_branches() {
    let model = load(&example("crank_rocker"));
    let analysis = analyse(&model).expect("analyse");
    for branch in [0, 1] {
        let counts = sweep("crank_rocker", &model, &analysis, &[], branch);
        assert_eq!(
            (counts.assembled, counts.dead, counts.runs),
            (360, 0, 1),
            "crank_rocker is Grashof, elbow = {branch}: {counts:?}"
        );
    }
}

/// The inverted slider-crank whose slot passes neither pin (pyslvs' form): the slot is a
/// common tangent of two circles about the pins, built in closed form (no default, no
/// iteration). Every one-degree sample solved on its own lands on the sketch's assembly: the
/// slot's direction moves continuously, and the block's offset from the slot is the one the
/// sketch gives it (read here from the sketch, not the plan).
#[test]
fn inverted_slider_crank_with_offsets_is_closed_form_and_keeps_its_assembly() {
    let model = load(&example("inverted_slider_crank_offset"));
    let analysis = analyse(&model).expect("analysed");
    assert!(
        analysis.plan.defaults.is_empty(),
        "{:?}",
        analysis.plan.defaults
    );
    assert!(analysis.plan.iterations.is_empty());
    let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
    let mut params = model.default_params();
    let theta = param(&model, "theta");
    // The pins' signed distances from the slot (left positive), in their bodies' frames as
    // the example's sketch gives them: L2's marker at (0.2, 0.5) along (1, 0) about its pin at
    // the origin, L3's at (-1, 0.8) along (-0.9, 0.3) about its pivot at the origin.
    let offset = |origin: P, x: P| cross(scale(x, 1.0 / norm(x)), sub([0.0, 0.0], origin));
    let (block, rocker) = (
        offset([0.2, 0.5], [1.0, 0.0]),
        offset([-1.0, 0.8], [-0.9, 0.3]),
    );
    let mut last: Option<P> = None;
    for deg in 0..360 {
        params[theta] = (deg as f64).to_radians();
        let s = gcs_compiler::solve(&model, &analysis, &params, &branches)
            .unwrap_or_else(|e| panic!("theta = {deg} deg: {e}"));
        assert!(
            s.max_residual < 1e-12,
            "theta = {deg} deg: {}",
            s.max_residual
        );
        let dir = s.by_name().vector("L3.s.x").expect("the slot's direction");
        let u = [dir[0], dir[1]];
        // Each pin at its body's offset from the one slot.
        let (tip, b) = (get(&s, "crank.tip"), get(&s, "B"));
        let slot = get(&s, "L2.m");
        assert!(
            (cross(u, sub(tip, slot)) - block).abs() < 1e-12,
            "theta = {deg} deg"
        );
        assert!(
            (cross(u, sub(b, slot)) - rocker).abs() < 1e-12,
            "theta = {deg} deg"
        );
        if let Some(prev) = last {
            assert!(dist(prev, u) < 0.1, "theta = {deg} deg: the slot jumped");
        }
        last = Some(u);
    }
}

/// The common-tangent fragment on random inverted slider-cranks, each sketched assembled: a
/// crank about `O`, a block pinned to its tip, a rocker pivoted at `B`, and a slot line at
/// random offsets from both pins. At the sketch's crank angle the solve gives back the
/// sketch's slot (the sketch's assembly, to rounding); a few degrees either side it solves
/// with every constraint met and the slot moved continuously.
#[test]
fn random_inverted_slider_cranks_keep_their_sketched_slot() {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % 1_000_000) as f64 / 1_000_000.0
    };
    let mut solved = 0;
    for case in 0..40 {
        let theta0 = 6.0 * next();
        let crank = 0.5 + next();
        let b = [2.0 + 2.0 * next(), -1.0 + 2.0 * next()];
        let tip = [crank * theta0.cos(), crank * theta0.sin()];
        // The slot: through a random point near the two pins, along a random direction.
        let q = [b[0] * next(), -1.0 + 2.0 * next()];
        let a = 6.0 * next();
        let u = [a.cos(), a.sin()];
        let (s_block, s_rocker) = (2.0 * next() - 1.0, 2.0 * next() - 1.0);
        let on_slot = |s: f64| [q[0] + s * u[0], q[1] + s * u[1]];
        let (m, r) = (on_slot(s_block), on_slot(s_rocker));
        let text = format!(
            "space 2d;
param theta = {theta0};
fixed point O = (0, 0);
fixed point B = ({}, {});
fixed vector X = (1, 0);
body crank at (0, 0) {{ point o = (0, 0); point tip = ({crank}, 0); vector u = (1, 0); }}
body L2 at ({}, {}) {{ point pin = (0, 0); marker m = ({}, {}) x ({}, {}); }}
body L3 at ({}, {}) {{ point piv = (0, 0); marker s = ({}, {}) x ({}, {}); }}
coincident(crank.o, O);
drive: angle(X, crank.u) = theta;
coincident(L2.pin, crank.tip);
coincident(L3.piv, B);
slide: prismatic(L2.m, L3.s);
",
            b[0],
            b[1],
            tip[0],
            tip[1],
            m[0] - tip[0],
            m[1] - tip[1],
            u[0],
            u[1],
            b[0],
            b[1],
            r[0] - b[0],
            r[1] - b[1],
            u[0],
            u[1],
        );
        let (_, model, diags) = gcs_lang::load("isc.gcs", text.as_bytes());
        assert!(
            diags.iter().all(|d| !d.is_error()),
            "case {case}: {diags:?}"
        );
        let model = model.expect("a model");
        let analysis = analyse(&model).unwrap_or_else(|e| panic!("case {case}: {e}"));
        assert!(analysis.plan.defaults.is_empty(), "case {case}: a default");
        let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let theta = param(&model, "theta");
        let mut params = model.default_params();
        // The pins' offsets from the slot, as sketched: the slot exists while the crank's
        // tip stays at least their difference from B (the common tangent of the circles
        // about the pins, of those radii).
        let (o_tip, o_b) = (cross(u, sub(tip, m)), cross(u, sub(b, m)));
        let slot = |params: &[f64]| -> Option<P> {
            let t = params[theta];
            let tip = [crank * t.cos(), crank * t.sin()];
            let gap = (o_tip - o_b).abs() - dist(tip, b);
            match gcs_compiler::solve(&model, &analysis, params, &branches) {
                Ok(s) => {
                    assert!(
                        gap <= 1e-9,
                        "case {case}: solved where no slot exists ({gap})"
                    );
                    assert!(s.max_residual < 1e-12, "case {case}: {}", s.max_residual);
                    let d = s.by_name().vector("L3.s.x").expect("the slot");
                    Some([d[0], d[1]])
                }
                Err(e) => {
                    assert_eq!(e.kind, ErrorKind::NoIntersection, "case {case}: {e}");
                    assert!((e.magnitude - gap).abs() < 1e-9, "case {case}: {e} ({gap})");
                    None
                }
            }
        };
        let at_sketch = slot(&params).unwrap_or_else(|| panic!("case {case}: the sketch"));
        assert!(
            dist(at_sketch, u) < 1e-9,
            "case {case}: {at_sketch:?} against {u:?}"
        );
        let mut last = at_sketch;
        for step in 1..=5 {
            params[theta] = theta0 + (step as f64).to_radians();
            let Some(now) = slot(&params) else {
                break;
            };
            assert!(
                dist(now, last) < 0.2,
                "case {case}: the slot jumped at step {step}"
            );
            last = now;
        }
        solved += 1;
    }
    assert_eq!(solved, 40);
}
