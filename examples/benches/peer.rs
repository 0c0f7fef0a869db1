//! gcs against a numeric peer in the same run: kcl-ezpz, a 2d constraint solver in Rust (damped
//! Gauss-Newton on sparse matrices) that a CAD product uses, on the four-bar sweep and on the
//! sketch family of size 16. `cargo bench -p gcs-examples --bench peer`.
//!
//! Each group first checks that ezpz and gcs land on the same assembly (printing any branch
//! flip), then times both with its own `Instant` loop and prints the ratio ezpz / gcs of the
//! medians (criterion prints times, not ratios), then lets criterion measure each variant.
//!
//! ezpz is warm-started from its previous solution, as a numeric solver in a sweep would be
//! (`ezpz_warm`), and started from the model's sketch at every step (`ezpz_cold`). Its cost
//! includes what a user of its API pays per solve: the constraint list is rebuilt with the new
//! dimension (ezpz's constraints carry their values) and `kcl_ezpz::solve` builds its sparse
//! model (symbolic LU included) on every call; it has no API to keep a model across solves.
//!
//! On the sketch, ezpz runs in two forms (see [`Form`]): `ezpz_warm`/`ezpz_cold` with each
//! fillet joint as point-on-circle + radius perpendicular to the segment (well posed; agrees with
//! gcs to 1e-6), and `ezpz_literal_*` with the model's `tangent` + `on` word for word, which is
//! singular at the solution: ezpz needs ~70 iterations (more than its default 35, so these get
//! 200) and stops ~7e-3 away from the exact tangent points.

use criterion::{criterion_group, criterion_main, Criterion};
use gcs_examples as ex;
use kcl_ezpz::datatypes::inputs::{DatumCircle, DatumDistance, DatumLineSegment, DatumPoint};
use kcl_ezpz::datatypes::{Angle, AngleKind};
use kcl_ezpz::{Config, Constraint, ConstraintRequest, Id, IdGenerator};
use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::Instant;

/// Steps of the four-bar sweep, around the circle.
const FOURBAR_STEPS: usize = 64;
/// Steps of the sketch sweep: `len` from 8 to 12 and back, so that each step is a small change.
const SKETCH_STEPS: usize = 32;
/// Segments (and fillets) of the sketch family.
const SKETCH_N: usize = 16;
/// Agreement wanted between ezpz and gcs on a point. ezpz stops when every residual is at most
/// 1e-8 (its default `Config`), Newton's last step makes the error far smaller than that.
const AGREE: f64 = 1e-6;

fn req(c: Constraint) -> ConstraintRequest {
    ConstraintRequest::highest_priority(c)
}

fn fix(p: DatumPoint, x: f64, y: f64) -> [ConstraintRequest; 2] {
    [
        req(Constraint::Fixed(p.id_x(), x)),
        req(Constraint::Fixed(p.id_y(), y)),
    ]
}

/// Runs ezpz from `guess` (one value per variable, in id order) and writes its answer back into
/// `guess`. Its Gauss-Newton iterations, or `None` if it failed or left a constraint unsatisfied.
fn ezpz_solve(requests: &[ConstraintRequest], guess: &mut [f64], config: Config) -> Option<usize> {
    let guesses: Vec<(Id, f64)> = guess
        .iter()
        .enumerate()
        .map(|(i, &v)| (i as Id, v))
        .collect();
    match kcl_ezpz::solve(requests, guesses, config) {
        Ok(out) if out.is_satisfied() => {
            guess.copy_from_slice(out.final_values());
            Some(out.iterations())
        }
        _ => None,
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Median time of one call of `f`, in nanoseconds: batches of at least 5 ms, median of 11.
fn median_ns(mut f: impl FnMut()) -> f64 {
    let mut n = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..n {
            f();
        }
        if t.elapsed().as_secs_f64() >= 5e-3 {
            break;
        }
        n *= 2;
    }
    let mut per_call: Vec<f64> = (0..11)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}

fn show_ns(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{ns:.1} ns")
    }
}

/// Times gcs against ezpz warm and cold on one sweep: the medians printed with their
/// ratios, then each as a criterion bench of `group`.
fn time_three(
    c: &mut Criterion,
    group: &str,
    mut gcs_step: impl FnMut() -> bool,
    mut warm_step: impl FnMut() -> Option<usize>,
    mut cold_step: impl FnMut() -> Option<usize>,
) {
    let gcs = median_ns(|| {
        gcs_step();
    });
    let warm = median_ns(|| {
        warm_step();
    });
    let cold = median_ns(|| {
        cold_step();
    });
    eprintln!(
        "{group} medians: gcs {}, ezpz_warm {} (ratio ezpz/gcs {:.0}), ezpz_cold {} (ratio {:.0})",
        show_ns(gcs),
        show_ns(warm),
        warm / gcs,
        show_ns(cold),
        cold / gcs
    );
    let mut g = c.benchmark_group(group);
    g.bench_function("gcs", |b| b.iter(&mut gcs_step));
    g.bench_function("ezpz_warm", |b| b.iter(&mut warm_step));
    g.bench_function("ezpz_cold", |b| b.iter(&mut cold_step));
    g.finish();
}

// ---------------------------------------------------------------------------------------------
// The four-bar of examples/fourbar.gcs.

/// The four-bar in ezpz's terms: points A and D fixed, B the crank's tip, C the coupler-rocker
/// joint; distances |AB| = 1.5, |BC| = 4, |DC| = 3. ezpz has no fixed direction, so the drive
/// `angle(X, crank.u) = theta` is an angle between lines, from a reference segment A→E with E
/// fixed at (1, 0) to the crank A→B, as an ezpz user would write it.
struct EzFourBar {
    a: DatumPoint,
    e: DatumPoint,
    d: DatumPoint,
    b: DatumPoint,
    c: DatumPoint,
}

impl EzFourBar {
    const VARS: usize = 10;

    fn new() -> Self {
        let mut ids = IdGenerator::default();
        let (a, e, d) = (
            DatumPoint::new(&mut ids),
            DatumPoint::new(&mut ids),
            DatumPoint::new(&mut ids),
        );
        let (b, c) = (DatumPoint::new(&mut ids), DatumPoint::new(&mut ids));
        EzFourBar { a, e, d, b, c }
    }

    fn requests(&self, theta: f64) -> Vec<ConstraintRequest> {
        let mut r = Vec::with_capacity(10);
        r.extend(fix(self.a, 0.0, 0.0));
        r.extend(fix(self.e, 1.0, 0.0));
        r.extend(fix(self.d, 4.0, 0.0));
        r.push(req(Constraint::Distance(self.a, self.b, 1.5)));
        r.push(req(Constraint::LinesAtAngle(
            DatumLineSegment::new(self.a, self.e),
            DatumLineSegment::new(self.a, self.b),
            AngleKind::Other(Angle::from_radians(theta)),
        )));
        r.push(req(Constraint::Distance(self.b, self.c, 4.0)));
        r.push(req(Constraint::Distance(self.d, self.c, 3.0)));
        r
    }

    /// The model's sketch: crank tip at (1.5, 0), the joint where the rocker has it, (4, 3).
    fn sketch() -> [f64; Self::VARS] {
        [0.0, 0.0, 1.0, 0.0, 4.0, 0.0, 1.5, 0.0, 4.0, 3.0]
    }

    fn solve(&self, theta: f64, guess: &mut [f64; Self::VARS]) -> Option<usize> {
        ezpz_solve(&self.requests(theta), guess, Config::default())
    }

    fn c_of(&self, v: &[f64]) -> [f64; 2] {
        [v[self.c.id_x() as usize], v[self.c.id_y() as usize]]
    }
}

fn gcs_fourbar(theta: f64) -> Option<[f64; 2]> {
    let params = ex::fourbar::Params {
        theta,
        ..Default::default()
    };
    ex::fourbar::solve(
        &params,
        &ex::fourbar::Branches::default(),
        &ex::fourbar::Defaults::default(),
    )
    .ok()
    .map(|s| {
        let c = s.coupler_c();
        [c.x, c.y]
    })
}

/// Checks ezpz (warm sweep and cold) against gcs at every theta; prints the worst distance,
/// the branch flips and ezpz's mean iterations. Panics if ezpz fails, since then the timings
/// would not compare.
fn check_fourbar(ez: &EzFourBar, thetas: &[f64]) {
    let mut warm = EzFourBar::sketch();
    let (mut worst_warm, mut worst_cold) = (0.0f64, 0.0f64);
    let (mut flips_warm, mut flips_cold) = (0, 0);
    let (mut its_warm, mut its_cold) = (0, 0);
    for &theta in thetas {
        let g = gcs_fourbar(theta).expect("gcs solves the four-bar");
        its_warm += ez
            .solve(theta, &mut warm)
            .unwrap_or_else(|| panic!("ezpz (warm) fails at theta {theta}"));
        let mut cold = EzFourBar::sketch();
        its_cold += ez
            .solve(theta, &mut cold)
            .unwrap_or_else(|| panic!("ezpz (cold) fails at theta {theta}"));
        let (dw, dc) = (dist(ez.c_of(&warm), g), dist(ez.c_of(&cold), g));
        if dw > AGREE {
            flips_warm += 1;
        } else {
            worst_warm = worst_warm.max(dw);
        }
        if dc > AGREE {
            flips_cold += 1;
        } else {
            worst_cold = worst_cold.max(dc);
        }
    }
    let n = thetas.len();
    eprintln!(
        "peer_fourbar check over {n} thetas: ezpz_warm agrees with gcs's coupler.c to \
         {worst_warm:.1e} ({flips_warm} on the other assembly, {:.1} iterations on average), \
         ezpz_cold to {worst_cold:.1e} ({flips_cold} on the other assembly, {:.1} iterations)",
        its_warm as f64 / n as f64,
        its_cold as f64 / n as f64,
    );
}

fn bench_fourbar(c: &mut Criterion) {
    let thetas: Vec<f64> = (0..FOURBAR_STEPS)
        .map(|i| i as f64 * TAU / FOURBAR_STEPS as f64)
        .collect();
    let ez = EzFourBar::new();
    check_fourbar(&ez, &thetas);

    let branches = ex::fourbar::Branches::default();
    let defaults = ex::fourbar::Defaults::default();
    let gcs_step = {
        let thetas = thetas.clone();
        let mut params = ex::fourbar::Params::default();
        let mut i = 0;
        move || {
            i = (i + 1) % FOURBAR_STEPS;
            params.theta = black_box(thetas[i]);
            black_box(ex::fourbar::solve(&params, &branches, &defaults).map(|s| s.coupler_c()))
                .is_ok()
        }
    };
    let warm_step = {
        let thetas = thetas.clone();
        let ez = EzFourBar::new();
        let mut vals = EzFourBar::sketch();
        let mut i = 0;
        move || {
            i = (i + 1) % FOURBAR_STEPS;
            black_box(ez.solve(black_box(thetas[i]), &mut vals))
        }
    };
    let cold_step = {
        let thetas = thetas.clone();
        let ez = EzFourBar::new();
        let mut i = 0;
        move || {
            i = (i + 1) % FOURBAR_STEPS;
            let mut vals = EzFourBar::sketch();
            black_box(ez.solve(black_box(thetas[i]), &mut vals))
        }
    };

    time_three(c, "peer_fourbar", gcs_step, warm_step, cold_step);
}

// ---------------------------------------------------------------------------------------------
// The sketch family: examples/families/sketch_profile_16.gcs.

/// How a segment's end meets its fillet.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Form {
    /// Word for word as the model has it: `tangent(s, f)` as `LineTangentToCircle` and
    /// `on(s.end, f)` as a distance from the centre equal to the radius. At the solution the
    /// second is stationary along the line (the tangent point is the line's nearest point to
    /// the centre), so the Jacobian is singular there: Gauss-Newton converges only linearly,
    /// needs more than the default 35 iterations, and its stopping test on residuals (1e-8)
    /// leaves the point ~sqrt(2 r 1e-8) ≈ 2e-4 along the line per joint.
    Literal,
    /// What an ezpz user does for a well-posed fillet joint: the point on the circle, and the
    /// radius to it perpendicular to the segment (`LinesAtAngle(.., Perpendicular)`), which
    /// together say the same as tangent + on (the side coming from the start values).
    Perpendicular,
}

impl Form {
    /// The literal form needs more iterations than ezpz's default 35 (it takes ~70).
    fn config(self) -> Config {
        match self {
            Form::Literal => Config::default().with_max_iterations(200),
            Form::Perpendicular => Config::default(),
        }
    }
}

/// The sketch in ezpz's terms: each segment `s{k}` a line segment of two points, each fillet
/// `f{k}` a circle (centre and radius variable).
///
/// - `coincident(s0.start, origin)`: `PointsCoincident` with a fixed point at the origin.
/// - `angle(X, s{k}) = ±20 deg`: ezpz has no fixed direction, so an angle between lines, from a
///   reference segment fixed from (0, 0) to (1, 0) to `s{k}`.
/// - `length(s{k}) = len`: `Distance` between its ends.
/// - `radius(f{k}) = r`: `CircleRadius`.
/// - `on(s.end, f)`, `on(s.start, f)`: ezpz's point-on-curve is for arcs (`PointArcCoincident`),
///   so a point on a circle is `DistanceVar` from the centre equal to the radius variable.
/// - `tangent(s, f)`, [`Form::Literal`]: `LineTangentToCircle`, which is signed: the circle lies
///   left of the line from its first point to its second. The fillet is on the side the sketch
///   has it (the inside of the turn: right of both of its segments after a +20 degree segment,
///   left after a -20), so the segment is given reversed when the circle is on its right.
/// - `tangent(s, f)`, [`Form::Perpendicular`]: the radius to the joint perpendicular to `s`.
struct EzSketch {
    origin: DatumPoint,
    x_end: DatumPoint,
    segs: Vec<DatumLineSegment>,
    fillets: Vec<DatumCircle>,
    vars: usize,
}

impl EzSketch {
    fn new(n: usize) -> Self {
        let mut ids = IdGenerator::default();
        let origin = DatumPoint::new(&mut ids);
        let x_end = DatumPoint::new(&mut ids);
        let mut segs = Vec::with_capacity(n);
        let mut fillets = Vec::with_capacity(n);
        for _ in 0..n {
            let p0 = DatumPoint::new(&mut ids);
            let p1 = DatumPoint::new(&mut ids);
            segs.push(DatumLineSegment::new(p0, p1));
            let center = DatumPoint::new(&mut ids);
            let radius = DatumDistance::new(ids.next_id());
            fillets.push(DatumCircle { center, radius });
        }
        let vars = ids.next_id() as usize;
        EzSketch {
            origin,
            x_end,
            segs,
            fillets,
            vars,
        }
    }

    fn requests(&self, len: f64, r: f64, form: Form) -> Vec<ConstraintRequest> {
        let mut q = Vec::with_capacity(5 + 7 * self.segs.len());
        q.extend(fix(self.origin, 0.0, 0.0));
        q.extend(fix(self.x_end, 1.0, 0.0));
        let x = DatumLineSegment::new(self.origin, self.x_end);
        q.push(req(Constraint::PointsCoincident(
            self.segs[0].p0,
            self.origin,
        )));
        // Segment `s` meets fillet `j` at its point `p`.
        let joint = |q: &mut Vec<ConstraintRequest>, s: DatumLineSegment, j: usize, p| {
            let f: DatumCircle = self.fillets[j];
            q.push(req(match form {
                // Oriented so that the fillet is on its left.
                Form::Literal if j.is_multiple_of(2) => {
                    Constraint::LineTangentToCircle(DatumLineSegment::new(s.p1, s.p0), f)
                }
                Form::Literal => Constraint::LineTangentToCircle(s, f),
                Form::Perpendicular => {
                    Constraint::lines_perpendicular([s, DatumLineSegment::new(f.center, p)])
                }
            }));
            q.push(req(Constraint::DistanceVar(p, f.center, f.radius)));
        };
        for (k, (&s, &f)) in self.segs.iter().zip(&self.fillets).enumerate() {
            let deg = if k % 2 == 0 { 20.0 } else { -20.0 };
            q.push(req(Constraint::LinesAtAngle(
                x,
                s,
                AngleKind::Other(Angle::from_degrees(deg)),
            )));
            q.push(req(Constraint::Distance(s.p0, s.p1, len)));
            q.push(req(Constraint::CircleRadius(f, r)));
            joint(&mut q, s, k, s.p1);
            if k > 0 {
                joint(&mut q, s, k - 1, s.p0);
            }
        }
        q
    }

    /// The model's sketch, as `gcs_bench::families::sketch_profile` draws it: segments of
    /// length 10 a unit apart, fillet centres 2 from each segment's end, radius 2.
    fn sketch(&self) -> Vec<f64> {
        let mut v = vec![0.0; self.vars];
        let mut set = |p: DatumPoint, x: f64, y: f64| {
            v[p.id_x() as usize] = x;
            v[p.id_y() as usize] = y;
        };
        set(self.origin, 0.0, 0.0);
        set(self.x_end, 1.0, 0.0);
        let (mut x, mut y) = (0.0f64, 0.0f64);
        for (k, (s, f)) in self.segs.iter().zip(&self.fillets).enumerate() {
            let deg: f64 = if k % 2 == 0 { 20.0 } else { -20.0 };
            let (dy, dx) = deg.to_radians().sin_cos();
            let (ex_, ey) = (x + 10.0 * dx, y + 10.0 * dy);
            let side = if deg > 0.0 { -1.0 } else { 1.0 };
            set(s.p0, x, y);
            set(s.p1, ex_, ey);
            set(f.center, ex_ - side * 2.0 * dy, ey + side * 2.0 * dx);
            x = ex_ + 1.0;
            y = ey;
        }
        for f in &self.fillets {
            v[f.radius.id as usize] = 2.0;
        }
        v
    }

    fn point(&self, v: &[f64], p: DatumPoint) -> [f64; 2] {
        [v[p.id_x() as usize], v[p.id_y() as usize]]
    }

    /// The points compared with gcs: every segment's end, and the last fillet's centre.
    fn outputs(&self, v: &[f64]) -> Vec<[f64; 2]> {
        let mut out: Vec<[f64; 2]> = self.segs.iter().map(|s| self.point(v, s.p1)).collect();
        out.push(self.point(v, self.fillets[self.segs.len() - 1].center));
        out
    }
}

fn gcs_sketch(len: f64) -> Vec<[f64; 2]> {
    use ex::sketch_profile_16 as m;
    let params = m::Params {
        len,
        ..Default::default()
    };
    let s = m::solve(&params, &m::Branches::default(), &m::Defaults::default())
        .expect("gcs solves the sketch");
    let p = |p: gcs_runtime::nalgebra::Point2<f64>| [p.x, p.y];
    vec![
        p(s.s0_end()),
        p(s.s1_end()),
        p(s.s2_end()),
        p(s.s3_end()),
        p(s.s4_end()),
        p(s.s5_end()),
        p(s.s6_end()),
        p(s.s7_end()),
        p(s.s8_end()),
        p(s.s9_end()),
        p(s.s10_end()),
        p(s.s11_end()),
        p(s.s12_end()),
        p(s.s13_end()),
        p(s.s14_end()),
        p(s.s15_end()),
        p(s.f15_center()),
    ]
}

/// Checks ezpz in `form` (warm sweep and cold) against gcs at every `len`; prints the worst
/// distance over the compared points and ezpz's mean iterations. Panics if ezpz fails.
fn check_sketch(ez: &EzSketch, lens: &[f64], form: Form) {
    let mut warm = ez.sketch();
    let (mut worst_warm, mut worst_cold) = (0.0f64, 0.0f64);
    let (mut off_warm, mut off_cold) = (0, 0);
    let (mut its_warm, mut its_cold) = (0, 0);
    for &len in lens {
        let g = gcs_sketch(len);
        let q = ez.requests(len, 2.0, form);
        its_warm += ezpz_solve(&q, &mut warm, form.config())
            .unwrap_or_else(|| panic!("ezpz {form:?} (warm) fails at len {len}"));
        let mut cold = ez.sketch();
        its_cold += ezpz_solve(&q, &mut cold, form.config())
            .unwrap_or_else(|| panic!("ezpz {form:?} (cold) fails at len {len}"));
        let d = |v: &[f64]| {
            ez.outputs(v)
                .iter()
                .zip(&g)
                .map(|(a, b)| dist(*a, *b))
                .fold(0.0, f64::max)
        };
        let (dw, dc) = (d(&warm), d(&cold));
        off_warm += usize::from(dw > AGREE);
        off_cold += usize::from(dc > AGREE);
        worst_warm = worst_warm.max(dw);
        worst_cold = worst_cold.max(dc);
    }
    let n = lens.len();
    eprintln!(
        "peer_sketch check ({form:?}) over {n} lens, 16 segment ends and f15's centre each: \
         ezpz_warm within {worst_warm:.1e} of gcs ({off_warm} steps off by more than {AGREE:.0e}, \
         {:.1} iterations on average), ezpz_cold within {worst_cold:.1e} ({off_cold} off, {:.1} \
         iterations)",
        its_warm as f64 / n as f64,
        its_cold as f64 / n as f64,
    );
}

/// One step of an ezpz sweep over `lens`: warm from the previous answer, or cold from the sketch.
fn ezpz_sketch_step(lens: &[f64], form: Form, warm: bool) -> impl FnMut() -> bool {
    let lens = lens.to_vec();
    let ez = EzSketch::new(SKETCH_N);
    let sketch = ez.sketch();
    let mut vals = sketch.clone();
    let mut i = 0;
    move || {
        i = (i + 1) % lens.len();
        let q = ez.requests(black_box(lens[i]), 2.0, form);
        if !warm {
            vals.copy_from_slice(&sketch);
        }
        black_box(ezpz_solve(&q, &mut vals, form.config()).is_some())
    }
}

fn bench_sketch(c: &mut Criterion) {
    use ex::sketch_profile_16 as m;
    // 8 → 12 → 8 in steps of 0.25.
    let lens: Vec<f64> = (0..SKETCH_STEPS)
        .map(|i| {
            let half = SKETCH_STEPS / 2;
            let k = if i <= half { i } else { SKETCH_STEPS - i };
            8.0 + 4.0 * k as f64 / half as f64
        })
        .collect();
    let ez = EzSketch::new(SKETCH_N);
    check_sketch(&ez, &lens, Form::Literal);
    check_sketch(&ez, &lens, Form::Perpendicular);

    let branches = m::Branches::default();
    let defaults = m::Defaults::default();
    let mut gcs_step = {
        let lens = lens.clone();
        let mut params = m::Params::default();
        let mut i = 0;
        move || {
            i = (i + 1) % SKETCH_STEPS;
            params.len = black_box(lens[i]);
            black_box(m::solve(&params, &branches, &defaults).map(|s| s.f15_center())).is_ok()
        }
    };
    let variants = [
        ("ezpz_warm", Form::Perpendicular, true),
        ("ezpz_cold", Form::Perpendicular, false),
        ("ezpz_literal_warm", Form::Literal, true),
        ("ezpz_literal_cold", Form::Literal, false),
    ];
    let mut steps: Vec<_> = variants
        .iter()
        .map(|&(_, form, warm)| ezpz_sketch_step(&lens, form, warm))
        .collect();

    let gcs = median_ns(|| {
        gcs_step();
    });
    let mut line = format!("peer_sketch medians: gcs {}", show_ns(gcs));
    for ((name, _, _), step) in variants.iter().zip(&mut steps) {
        let t = median_ns(|| {
            step();
        });
        line += &format!(", {name} {} (ratio ezpz/gcs {:.0})", show_ns(t), t / gcs);
    }
    eprintln!("{line}");

    let mut g = c.benchmark_group("peer_sketch");
    g.bench_function("gcs", |b| b.iter(&mut gcs_step));
    for ((name, _, _), step) in variants.iter().zip(&mut steps) {
        g.bench_function(*name, |b| b.iter(&mut *step));
    }
    g.finish();
}

// ---------------------------------------------------------------------------------------------
// The closed rectangle of examples/sketches/rectangle.gcs (issue 19).

/// The rectangle in ezpz's terms: corners `p0` (fixed at the origin) to `p3`, the sides
/// horizontal and vertical, the bottom `width` and the left `height` long.
struct EzRectangle {
    p: [DatumPoint; 4],
}

impl EzRectangle {
    const VARS: usize = 8;
    const STEPS: usize = 32;

    fn new() -> Self {
        let mut ids = IdGenerator::default();
        EzRectangle {
            p: std::array::from_fn(|_| DatumPoint::new(&mut ids)),
        }
    }

    fn requests(&self, width: f64) -> Vec<ConstraintRequest> {
        let [p0, p1, p2, p3] = self.p;
        let side = DatumLineSegment::new;
        let mut r = Vec::with_capacity(8);
        r.extend(fix(p0, 0.0, 0.0));
        r.push(req(Constraint::Horizontal(side(p0, p1))));
        r.push(req(Constraint::Vertical(side(p1, p2))));
        r.push(req(Constraint::Horizontal(side(p2, p3))));
        r.push(req(Constraint::Vertical(side(p3, p0))));
        r.push(req(Constraint::Distance(p0, p1, width)));
        r.push(req(Constraint::Distance(p3, p0, 2.5)));
        r
    }

    /// The model's sketch of the corners.
    fn sketch() -> [f64; Self::VARS] {
        [0.0, 0.0, 4.2, 0.1, 4.1, 2.9, 0.1, 3.1]
    }

    fn solve(&self, width: f64, guess: &mut [f64; Self::VARS]) -> Option<usize> {
        ezpz_solve(&self.requests(width), guess, Config::default())
    }

    /// The corner opposite the origin.
    fn far_corner(&self, v: &[f64]) -> [f64; 2] {
        [v[self.p[2].id_x() as usize], v[self.p[2].id_y() as usize]]
    }
}

fn gcs_rectangle(width: f64) -> Option<[f64; 2]> {
    let params = ex::rectangle::Params {
        width,
        ..Default::default()
    };
    ex::rectangle::solve(
        &params,
        &ex::rectangle::Branches::default(),
        &ex::rectangle::Defaults::default(),
    )
    .ok()
    .map(|s| {
        let c = s.right_end();
        [c.x, c.y]
    })
}

/// The rectangle's width from 3.6 to 4.4 and back: ezpz warm and cold against gcs, checked
/// on the same assembly first, then timed.
fn bench_rectangle(c: &mut Criterion) {
    let n = EzRectangle::STEPS;
    let widths: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 / (n / 2) as f64;
            3.6 + 0.8 * if t <= 1.0 { t } else { 2.0 - t }
        })
        .collect();
    let ez = EzRectangle::new();
    let mut warm = EzRectangle::sketch();
    let (mut worst, mut flips) = (0.0f64, 0);
    for &w in &widths {
        let g = gcs_rectangle(w).expect("gcs solves the rectangle");
        ez.solve(w, &mut warm)
            .unwrap_or_else(|| panic!("ezpz (warm) fails at width {w}"));
        let d = dist(ez.far_corner(&warm), g);
        if d > AGREE {
            flips += 1;
        } else {
            worst = worst.max(d);
        }
    }
    eprintln!(
        "peer_rectangle check over {n} widths: ezpz_warm agrees with gcs's far corner to \
         {worst:.1e} ({flips} on another assembly)"
    );
    let gcs_step = {
        let widths = widths.clone();
        let (branches, defaults) = (
            ex::rectangle::Branches::default(),
            ex::rectangle::Defaults::default(),
        );
        let mut params = ex::rectangle::Params::default();
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            params.width = black_box(widths[i]);
            black_box(ex::rectangle::solve(&params, &branches, &defaults).map(|s| s.right_end()))
                .is_ok()
        }
    };
    let warm_step = {
        let widths = widths.clone();
        let ez = EzRectangle::new();
        let mut vals = EzRectangle::sketch();
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            black_box(ez.solve(black_box(widths[i]), &mut vals))
        }
    };
    let cold_step = {
        let widths = widths.clone();
        let ez = EzRectangle::new();
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            let mut vals = EzRectangle::sketch();
            black_box(ez.solve(black_box(widths[i]), &mut vals))
        }
    };
    time_three(c, "peer_rectangle", gcs_step, warm_step, cold_step);
}

// ---------------------------------------------------------------------------------------------
// The slot of examples/sketches/slot.gcs (issue 19).

/// The slot in ezpz's terms: circles `left` (centre fixed at the origin, radius `width / 2`)
/// and `right` (centre 5 from it, radius free), a horizontal `top` from `left` to `right` and
/// a horizontal `bottom` back. Each of the four joints is a point on a circle (`DistanceVar`
/// to the radius) with the radius to it perpendicular to the segment, the well-posed form of
/// tangent + on (see [`Form::Perpendicular`]).
struct EzSlot {
    left: DatumCircle,
    right: DatumCircle,
    top: DatumLineSegment,
    bottom: DatumLineSegment,
}

impl EzSlot {
    const VARS: usize = 14;
    const STEPS: usize = 32;

    fn new() -> Self {
        let mut ids = IdGenerator::default();
        let circle = |ids: &mut IdGenerator| {
            let center = DatumPoint::new(ids);
            let radius = DatumDistance::new(ids.next_id());
            DatumCircle { center, radius }
        };
        let (left, right) = (circle(&mut ids), circle(&mut ids));
        let segment = |ids: &mut IdGenerator| {
            let (p0, p1) = (DatumPoint::new(ids), DatumPoint::new(ids));
            DatumLineSegment::new(p0, p1)
        };
        let (top, bottom) = (segment(&mut ids), segment(&mut ids));
        EzSlot {
            left,
            right,
            top,
            bottom,
        }
    }

    fn requests(&self, width: f64) -> Vec<ConstraintRequest> {
        let mut q = Vec::with_capacity(14);
        q.extend(fix(self.left.center, 0.0, 0.0));
        q.push(req(Constraint::CircleRadius(self.left, width / 2.0)));
        q.push(req(Constraint::Horizontal(self.top)));
        q.push(req(Constraint::Horizontal(self.bottom)));
        q.push(req(Constraint::Distance(
            self.left.center,
            self.right.center,
            5.0,
        )));
        for (s, f, p) in [
            (self.top, self.left, self.top.p0),
            (self.top, self.right, self.top.p1),
            (self.bottom, self.right, self.bottom.p0),
            (self.bottom, self.left, self.bottom.p1),
        ] {
            q.push(req(Constraint::lines_perpendicular([
                s,
                DatumLineSegment::new(f.center, p),
            ])));
            q.push(req(Constraint::DistanceVar(p, f.center, f.radius)));
        }
        q
    }

    /// The model's sketch.
    fn sketch(&self) -> [f64; Self::VARS] {
        let mut v = [0.0; Self::VARS];
        let mut set = |p: DatumPoint, x: f64, y: f64| {
            v[p.id_x() as usize] = x;
            v[p.id_y() as usize] = y;
        };
        set(self.left.center, 0.0, 0.0);
        set(self.right.center, 5.1, 0.1);
        set(self.top.p0, 0.1, 1.0);
        set(self.top.p1, 5.0, 1.1);
        set(self.bottom.p0, 5.0, -0.9);
        set(self.bottom.p1, 0.0, -1.1);
        v[self.left.radius.id as usize] = 1.1;
        v[self.right.radius.id as usize] = 0.9;
        v
    }

    fn solve(&self, width: f64, guess: &mut [f64; Self::VARS]) -> Option<usize> {
        ezpz_solve(&self.requests(width), guess, Config::default())
    }

    /// The top's end, on the right arc.
    fn top_end(&self, v: &[f64]) -> [f64; 2] {
        [
            v[self.top.p1.id_x() as usize],
            v[self.top.p1.id_y() as usize],
        ]
    }
}

fn gcs_slot(width: f64) -> Option<[f64; 2]> {
    let params = ex::slot::Params { width };
    ex::slot::solve(
        &params,
        &ex::slot::Branches::default(),
        &ex::slot::Defaults::default(),
    )
    .ok()
    .map(|s| {
        let c = s.top_end();
        [c.x, c.y]
    })
}

/// The slot's width from 1.8 to 2.2 and back: ezpz warm and cold against gcs, checked on the
/// same assembly first, then timed.
fn bench_slot(c: &mut Criterion) {
    let n = EzSlot::STEPS;
    let widths: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 / (n / 2) as f64;
            1.8 + 0.4 * if t <= 1.0 { t } else { 2.0 - t }
        })
        .collect();
    let ez = EzSlot::new();
    let mut warm = ez.sketch();
    let (mut worst, mut flips) = (0.0f64, 0);
    for &w in &widths {
        let g = gcs_slot(w).expect("gcs solves the slot");
        ez.solve(w, &mut warm)
            .unwrap_or_else(|| panic!("ezpz (warm) fails at width {w}"));
        let d = dist(ez.top_end(&warm), g);
        if d > AGREE {
            flips += 1;
        } else {
            worst = worst.max(d);
        }
    }
    eprintln!(
        "peer_slot check over {n} widths: ezpz_warm agrees with gcs's top end to {worst:.1e} \
         ({flips} on another assembly)"
    );
    let gcs_step = {
        let widths = widths.clone();
        let (branches, defaults) = (ex::slot::Branches::default(), ex::slot::Defaults::default());
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            let params = ex::slot::Params {
                width: black_box(widths[i]),
            };
            black_box(ex::slot::solve(&params, &branches, &defaults).map(|s| s.top_end())).is_ok()
        }
    };
    let warm_step = {
        let widths = widths.clone();
        let ez = EzSlot::new();
        let mut vals = ez.sketch();
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            black_box(ez.solve(black_box(widths[i]), &mut vals))
        }
    };
    let cold_step = {
        let widths = widths.clone();
        let ez = EzSlot::new();
        let mut i = 0;
        move || {
            i = (i + 1) % n;
            let mut vals = ez.sketch();
            black_box(ez.solve(black_box(widths[i]), &mut vals))
        }
    };
    time_three(c, "peer_slot", gcs_step, warm_step, cold_step);
}

criterion_group!(
    benches,
    bench_fourbar,
    bench_sketch,
    bench_rectangle,
    bench_slot
);
criterion_main!(benches);
