//! Properties of `turn3d`, the bodies turning about known axes (IK-Geo's subproblems), on
//! random instances built from known angles by a forward rotation written apart from the
//! solver (nalgebra's `Rotation3::from_axis_angle`), at scales from 1e-3 to 1e3, and on
//! near-degenerate families: the point on or near its axis, parallel and intersecting axes,
//! targets at and just inside or outside the edge of reach. The number of solutions is checked
//! against an independent count (dense sampling with bisection for one angle, Newton's method
//! from a dense grid of starts for two).
//!
//! `worst_errors_are_documented` prints the worst errors measured over 20,000 seeded instances
//! of each subproblem (scales 1e-3 to 1e3). Measured: the known angle recovered to at most
//! 1.3e-15 (SP1), 4e-14 (SP3, SP4, onto a line), 2.2e-13 (SP2: skew, intersecting, parallel
//! axes), 4.3e-13 (SP5: general, axes 1-2 or 2-3 intersecting or parallel) and 1.3e-13 (SP6)
//! where the problem is not ill-conditioned (a slope or singular-value ratio below 1e-2, 1 to
//! 12 percent of instances, is left out of the angle's bound but not of the residual's); every
//! root returned meets its equation to 2.9e-14 of the inputs' size at worst.

use std::f64::consts::{PI, TAU};

use gcs_runtime::locus3d::{Line3, Plane};
use gcs_runtime::tol::TANGENT_REL;
use gcs_runtime::turn3d::*;
use gcs_runtime::{Contact, Intersection};
use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};
use proptest::prelude::*;

/// Bound on an angle recovered where the problem is well conditioned, and on every root's
/// residual relative to the inputs' size.
const ANGLE_TOL: f64 = 1e-12;
const RESIDUAL_REL: f64 = 1e-12;
/// Below this slope (relative: the turned point's speed across the target over the scale),
/// the known angle is recovered only to rounding over the slope; the residual is still checked.
const WELL_CONDITIONED: f64 = 1e-2;

/// A tenth of the work in an unoptimised build (what the workspace's test command runs):
/// the figures in this module's doc are measured in release, at the full counts.
fn scaled(full: u64) -> u64 {
    if cfg!(debug_assertions) {
        (full / 10).max(1)
    } else {
        full
    }
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: scaled(256) as u32,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// The folds' tests run on fixed seeds: whether a close pair of a quartic's roots is one
/// double root is decided on its coefficients, good to about 1e-11 of the scale near an
/// ill-conditioned fold, and about one SP5 fold in 6,000 random ones loses its double root
/// there (an open defect, measured with random seeds). Fixed seeds keep CI deterministic;
/// `PROPTEST_RNG_SEED` is ignored here, so a search for that case edits the seed.
fn fold_config() -> ProptestConfig {
    ProptestConfig {
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x9e37_79b9_7f4a_7c15),
        ..config()
    }
}

// ---------------------------------------------------------------------------------------------
// A seeded generator, so that proptest cases and the measurement loop share one builder.

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn f(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f()
    }
    fn vec(&mut self) -> Vector3<f64> {
        Vector3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
    }
    fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = self.vec();
            if v.norm() > 0.2 && v.norm() <= 1.0 {
                return v.normalize();
            }
        }
    }
    fn angle(&mut self) -> f64 {
        self.range(-PI, PI)
    }
    fn point(&mut self, s: f64) -> Point3<f64> {
        Point3::from(self.vec() * s)
    }
    fn axis(&mut self, s: f64) -> Line3 {
        Line3::new(self.point(s), self.unit())
    }
    /// A point at least `0.2 s` from `axis`.
    fn off_axis(&mut self, axis: &Line3, s: f64) -> Point3<f64> {
        loop {
            let p = self.point(s);
            if across(axis, &p).norm() > 0.2 * s {
                return p;
            }
        }
    }
    fn scale(&mut self) -> f64 {
        10f64.powf(self.range(-3.0, 3.0))
    }
}

/// The reference turn: nalgebra's rotation about the axis, apart from the solver's.
fn rot(axis: &Line3, t: f64, p: &Point3<f64>) -> Point3<f64> {
    let r = Rotation3::from_axis_angle(&Unit::new_normalize(axis.dir), t);
    axis.point + r * (p - axis.point)
}

fn across(axis: &Line3, p: &Point3<f64>) -> Vector3<f64> {
    let w = p - axis.point;
    w - axis.dir * axis.dir.dot(&w)
}

/// The distance between two angles, modulo a turn.
fn adist(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

fn mag(points: &[Point3<f64>], lengths: &[f64]) -> f64 {
    let mut m: f64 = 0.0;
    for p in points {
        m = m.max(p.coords.amax());
    }
    for l in lengths {
        m = m.max(l.abs());
    }
    m
}

/// What one random instance measured: the error of the known angle(s) (`None` when the
/// instance is too ill-conditioned for it to be expected), and the worst residual of any root,
/// relative to the inputs' size.
#[derive(Clone, Copy, Debug, Default)]
struct Measured {
    angle: Option<f64>,
    residual: f64,
}

/// Checks the shape of an intersection (count against contact) and returns its roots.
fn shape<T: Copy + Default + PartialEq + std::fmt::Debug, const N: usize>(
    x: &Intersection<T, N>,
) -> Result<&[T], String> {
    let r = x.roots.as_slice();
    let ok = match x.contact {
        Contact::Crossing => !r.is_empty(),
        Contact::Tangent => !r.is_empty(),
        Contact::Disjoint { gap } | Contact::Parallel { gap } => r.is_empty() && gap >= 0.0,
        Contact::Coincident | Contact::ZeroRadius => r.is_empty(),
    };
    if ok {
        Ok(r)
    } else {
        Err(format!("{x:?}"))
    }
}

// ---------------------------------------------------------------------------------------------
// One angle.

fn sp1(seed: u64) -> Result<Measured, String> {
    let mut g = Rng(seed);
    let s = g.scale();
    let axis = g.axis(s);
    let p = g.off_axis(&axis, s);
    let t = g.angle();
    let q = rot(&axis, t, &p);
    let m = mag(&[axis.point, p, q], &[]);
    let x = turn_onto_point(&axis, &p, &q);
    let roots = shape(&x)?;
    if x.contact != Contact::Crossing || roots.len() != 1 {
        return Err(format!("{x:?}"));
    }
    let residual = (rot(&axis, roots[0], &p) - q).norm() / m;
    Ok(Measured {
        angle: Some(adist(roots[0], t)),
        residual,
    })
}

fn sp3(seed: u64) -> Result<Measured, String> {
    let mut g = Rng(seed);
    let s = g.scale();
    let axis = g.axis(s);
    let p = g.off_axis(&axis, s);
    let t = g.angle();
    let x0 = rot(&axis, t, &p);
    let q = g.point(s);
    let d = (x0 - q).norm();
    let m = mag(&[axis.point, p, q], &[d]);
    let x = turn_to_distance(&axis, &p, &q, d);
    let roots = shape(&x)?;
    if roots.len() != 2 {
        return Err(format!("{x:?}"));
    }
    let residual = roots
        .iter()
        .map(|&r| ((rot(&axis, r, &p) - q).norm() - d).abs() / m)
        .fold(0.0, f64::max);
    // The distance's rate of change with the angle, over the scale.
    let slope = (x0 - q).dot(&axis.dir.cross(&across(&axis, &x0))).abs() / (d * m);
    let err = roots
        .iter()
        .map(|&r| adist(r, t))
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (slope >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

fn sp4(seed: u64) -> Result<Measured, String> {
    let mut g = Rng(seed);
    let s = g.scale();
    let axis = g.axis(s);
    let p = g.off_axis(&axis, s);
    let t = g.angle();
    let x0 = rot(&axis, t, &p);
    let n = g.unit();
    let plane = Plane::new(n, n.dot(&x0.coords));
    let m = mag(&[axis.point, p], &[plane.offset]);
    let x = turn_onto_plane(&axis, &p, &plane);
    let roots = shape(&x)?;
    if roots.len() != 2 {
        return Err(format!("{x:?}"));
    }
    let residual = roots
        .iter()
        .map(|&r| plane.signed_distance(&rot(&axis, r, &p)).abs() / m)
        .fold(0.0, f64::max);
    let slope = n.dot(&axis.dir.cross(&across(&axis, &x0))).abs() / m;
    let err = roots
        .iter()
        .map(|&r| adist(r, t))
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (slope >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

fn onto_line(seed: u64) -> Result<Measured, String> {
    let mut g = Rng(seed);
    let s = g.scale();
    let axis = g.axis(s);
    let p = g.off_axis(&axis, s);
    let t = g.angle();
    let x0 = rot(&axis, t, &p);
    let line = Line3::new(x0 + g.vec() * s, g.unit());
    let line = Line3::new(line.closest(&x0) + (x0 - line.closest(&x0)), line.dir);
    let m = mag(&[axis.point, p, line.point], &[]);
    let x = turn_onto_line(&axis, &p, &line);
    let roots = shape(&x)?;
    if roots.is_empty() {
        return Err(format!("{x:?}"));
    }
    let dist = |r: f64| {
        let y = rot(&axis, r, &p);
        let w = y - line.point;
        (w - line.dir * line.dir.dot(&w)).norm()
    };
    // A line nearly in the orbit's plane meets it where rounding over the sine of their angle
    // puts it (as `line_circle` says): the residual is measured times that sine.
    let steep = line.dir.dot(&axis.dir).abs();
    let residual = roots.iter().map(|&r| dist(r) / m).fold(0.0, f64::max) * steep.min(1.0);
    let err = roots
        .iter()
        .map(|&r| adist(r, t))
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (steep >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

// ---------------------------------------------------------------------------------------------
// Two and three angles.

/// How the axes of a two- or three-axis instance relate.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Axes {
    General,
    /// The first two (SP2) or `first` and `second` (SP5) intersect.
    Intersecting,
    /// ... are parallel (or anti-parallel).
    Parallel,
    /// SP5's `second` and `third` intersect.
    IntersectingLater,
    /// SP5's `second` and `third` are parallel.
    ParallelLater,
}

const AXES: [Axes; 5] = [
    Axes::General,
    Axes::Intersecting,
    Axes::Parallel,
    Axes::IntersectingLater,
    Axes::ParallelLater,
];

/// An axis related to `a` as `how` says (`Intersecting`: through a point of `a`; `Parallel`:
/// along `±a.dir`), its pivot anywhere on it.
fn related(g: &mut Rng, a: &Line3, s: f64, how: bool, parallel: bool) -> Line3 {
    let mut b = g.axis(s);
    if how {
        if parallel {
            b.dir = if g.f() < 0.5 { a.dir } else { -a.dir };
        } else {
            b.point = a.at(g.range(-1.0, 1.0) * s) + b.dir * (g.range(-1.0, 1.0) * s);
        }
    }
    b
}

fn sp2(seed: u64, how: Axes) -> Result<Measured, String> {
    let mut g = Rng(seed);
    let s = g.scale();
    let first = g.axis(s);
    let second = related(
        &mut g,
        &first,
        s,
        how != Axes::General,
        how == Axes::Parallel,
    );
    let x0 = g.point(s);
    let (t1, t2) = (g.angle(), g.angle());
    let p = rot(&first, -t1, &x0);
    let q = rot(&second, -t2, &x0);
    if across(&first, &p).norm() < 0.1 * s || across(&second, &q).norm() < 0.1 * s {
        return Ok(Measured::default());
    }
    let m = mag(&[first.point, second.point, p, q], &[]);
    let x = turns_meeting(&first, &p, &second, &q);
    let roots = shape(&x)?;
    if roots.is_empty() {
        return Err(format!("{x:?}"));
    }
    let residual = roots
        .iter()
        .map(|r| (rot(&first, r[0], &p) - rot(&second, r[1], &q)).norm() / m)
        .fold(0.0, f64::max);
    // The sine of the angle at which the orbits cross at the known point.
    let (v1, v2) = (
        first.dir.cross(&across(&first, &x0)).normalize(),
        second.dir.cross(&across(&second, &x0)).normalize(),
    );
    let cond = v1.cross(&v2).norm();
    let err = roots
        .iter()
        .map(|r| adist(r[0], t1).max(adist(r[1], t2)))
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (cond >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

/// SP5's instance: its axes, points and angles.
struct Five {
    first: Line3,
    second: Line3,
    third: Line3,
    a: Point3<f64>,
    b: Point3<f64>,
    t: [f64; 3],
    s: f64,
}

fn five(seed: u64, how: Axes) -> Five {
    let mut g = Rng(seed);
    let s = g.scale();
    let second = g.axis(s);
    let first = related(
        &mut g,
        &second,
        s,
        matches!(how, Axes::Intersecting | Axes::Parallel),
        how == Axes::Parallel,
    );
    let third = related(
        &mut g,
        &second,
        s,
        matches!(how, Axes::IntersectingLater | Axes::ParallelLater),
        how == Axes::ParallelLater,
    );
    let b = g.off_axis(&third, s);
    let t = [g.angle(), g.angle(), g.angle()];
    let x0 = rot(&second, t[1], &rot(&third, t[2], &b));
    let a = rot(&first, -t[0], &x0);
    Five {
        first,
        second,
        third,
        a,
        b,
        t,
        s,
    }
}

fn five_meet(f: &Five, t: [f64; 3]) -> Vector3<f64> {
    rot(&f.first, t[0], &f.a) - rot(&f.second, t[1], &rot(&f.third, t[2], &f.b))
}

/// The reduced equations of SP5 in `θ1`, `θ3`, written from the meaning: a turn about `second`
/// keeps the distance from its pivot and the height along it.
fn five_reduced(f: &Five, t1: f64, t3: f64) -> [f64; 2] {
    let o = f.second.point;
    let u = rot(&f.first, t1, &f.a) - o;
    let v = rot(&f.third, t3, &f.b) - o;
    [
        (u.norm_squared() - v.norm_squared()) / (2.0 * f.s),
        f.second.dir.dot(&(u - v)),
    ]
}

fn sp5(seed: u64, how: Axes) -> Result<Measured, String> {
    let f = five(seed, how);
    if across(&f.first, &f.a).norm() < 0.1 * f.s {
        return Ok(Measured::default());
    }
    let m = mag(
        &[f.first.point, f.second.point, f.third.point, f.a, f.b],
        &[],
    );
    let x = three_circles(&f.first, &f.a, &f.second, &f.third, &f.b);
    let roots = shape(&x)?;
    if roots.is_empty() {
        return Err(format!("{x:?}"));
    }
    let residual = roots
        .iter()
        .map(|&r| five_meet(&f, r).norm() / m)
        .fold(0.0, f64::max);
    // The three equations' conditioning: the ratio of the extreme singular values of their
    // Jacobian in the three angles (by central differences).
    let h = 1e-6;
    let mut j = Matrix3::zeros();
    for k in 0..3 {
        let (mut up, mut down) = (f.t, f.t);
        up[k] += h;
        down[k] -= h;
        j.set_column(k, &((five_meet(&f, up) - five_meet(&f, down)) / (2.0 * h)));
    }
    let sv = j.singular_values();
    let cond = sv.min() / sv.max();
    let err = roots
        .iter()
        .map(|r| {
            adist(r[0], f.t[0])
                .max(adist(r[1], f.t[1]))
                .max(adist(r[2], f.t[2]))
        })
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (cond >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

/// The relative conditioning `|det J| / |J|²` of two equations in two angles at a point, by
/// central differences.
fn conditioning2(f: impl Fn(f64, f64) -> [f64; 2], a: f64, b: f64, s: f64) -> f64 {
    let h = 1e-6;
    let (fa1, fa0) = (f(a + h, b), f(a - h, b));
    let (fb1, fb0) = (f(a, b + h), f(a, b - h));
    let j = [
        [(fa1[0] - fa0[0]) / (2.0 * h), (fb1[0] - fb0[0]) / (2.0 * h)],
        [(fa1[1] - fa0[1]) / (2.0 * h), (fb1[1] - fb0[1]) / (2.0 * h)],
    ];
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let n2 = j.iter().flatten().map(|v| v * v).sum::<f64>();
    if n2 <= 1e-30 * s * s {
        0.0
    } else {
        det.abs() / n2
    }
}

/// SP6's instance.
struct Six {
    terms: [[Term; 4]; 2],
    d: [f64; 2],
    t: [f64; 2],
    s: f64,
}

fn six_value(terms: &[[Term; 4]; 2], t: [f64; 2]) -> [f64; 2] {
    let h = |term: &Term, a: f64| term.along.dot(&rot(&term.axis, a, &term.point).coords);
    let row = |r: &[Term; 4]| h(&r[0], t[0]) + h(&r[1], t[0]) + h(&r[2], t[1]) + h(&r[3], t[1]);
    [row(&terms[0]), row(&terms[1])]
}

fn six(seed: u64) -> Six {
    let mut g = Rng(seed);
    let s = g.scale();
    let mut terms = [[Term::default(); 4]; 2];
    for term in terms.iter_mut().flatten() {
        let axis = g.axis(s);
        *term = Term {
            axis,
            point: g.point(s),
            along: g.unit(),
        };
    }
    let t = [g.angle(), g.angle()];
    let d = six_value(&terms, t);
    Six { terms, d, t, s }
}

fn sp6(seed: u64) -> Result<Measured, String> {
    let f = six(seed);
    let m = f.s;
    let x = four_terms(&f.terms, f.d);
    let roots = shape(&x)?;
    if roots.is_empty() {
        return Err(format!("{x:?}"));
    }
    let residual = roots
        .iter()
        .map(|&r| {
            let v = six_value(&f.terms, r);
            (v[0] - f.d[0]).hypot(v[1] - f.d[1]) / m
        })
        .fold(0.0, f64::max);
    let cond = conditioning2(
        |a, b| {
            let v = six_value(&f.terms, [a, b]);
            [v[0] / f.s, v[1] / f.s]
        },
        f.t[0],
        f.t[1],
        1.0,
    );
    let err = roots
        .iter()
        .map(|r| adist(r[0], f.t[0]).max(adist(r[1], f.t[1])))
        .fold(f64::INFINITY, f64::min);
    Ok(Measured {
        angle: (cond >= WELL_CONDITIONED).then_some(err),
        residual,
    })
}

fn check(m: Result<Measured, String>) -> Result<(), TestCaseError> {
    let m = m.map_err(TestCaseError::fail)?;
    prop_assert!(m.residual <= RESIDUAL_REL, "residual {:e}", m.residual);
    if let Some(e) = m.angle {
        prop_assert!(e <= ANGLE_TOL, "angle error {:e}", e);
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn sp1_recovers_the_angle(seed in any::<u64>()) { check(sp1(seed))?; }

    #[test]
    fn sp3_recovers_the_angle(seed in any::<u64>()) { check(sp3(seed))?; }

    #[test]
    fn sp4_recovers_the_angle(seed in any::<u64>()) { check(sp4(seed))?; }

    #[test]
    fn onto_a_line_recovers_the_angle(seed in any::<u64>()) { check(onto_line(seed))?; }

    #[test]
    fn sp2_recovers_the_angles(seed in any::<u64>(), how in 0usize..3) {
        check(sp2(seed, AXES[how]))?;
    }

    #[test]
    fn sp5_recovers_the_angles(seed in any::<u64>(), how in 0usize..5) {
        check(sp5(seed, AXES[how]))?;
    }

    #[test]
    fn sp6_recovers_the_angles(seed in any::<u64>()) { check(sp6(seed))?; }

    /// A caller reading one root of SP5 (`three_circles_polishing`, which polishes only it)
    /// gets that root to the bit, in the same slot, with the same count and contact.
    #[test]
    fn sp5_one_root_alone_is_as_among_all(seed in any::<u64>(), how in 0usize..5) {
        let f = five(seed, AXES[how]);
        let x = three_circles(&f.first, &f.a, &f.second, &f.third, &f.b);
        for k in 0..x.roots.len() {
            let one = three_circles_polishing(&f.first, &f.a, &f.second, &f.third, &f.b, Some(k));
            prop_assert_eq!(one.roots.len(), x.roots.len());
            prop_assert_eq!(one.roots.as_slice()[k], x.roots.as_slice()[k]);
            prop_assert_eq!(format!("{:?}", one.contact), format!("{:?}", x.contact));
        }
    }
}

#[test]
fn worst_errors_are_documented() {
    let n = scaled(20_000);
    type Case = (&'static str, Box<dyn Fn(u64) -> Result<Measured, String>>);
    let cases: Vec<Case> = vec![
        ("SP1", Box::new(sp1)),
        ("SP3", Box::new(sp3)),
        ("SP4", Box::new(sp4)),
        ("line", Box::new(onto_line)),
        ("SP2 general", Box::new(|s| sp2(s, Axes::General))),
        ("SP2 intersecting", Box::new(|s| sp2(s, Axes::Intersecting))),
        ("SP2 parallel", Box::new(|s| sp2(s, Axes::Parallel))),
        ("SP5 general", Box::new(|s| sp5(s, Axes::General))),
        (
            "SP5 1-2 intersecting",
            Box::new(|s| sp5(s, Axes::Intersecting)),
        ),
        ("SP5 1-2 parallel", Box::new(|s| sp5(s, Axes::Parallel))),
        (
            "SP5 2-3 intersecting",
            Box::new(|s| sp5(s, Axes::IntersectingLater)),
        ),
        (
            "SP5 2-3 parallel",
            Box::new(|s| sp5(s, Axes::ParallelLater)),
        ),
        ("SP6", Box::new(sp6)),
    ];
    let mut failed = Vec::new();
    for (name, f) in &cases {
        let (mut angle, mut residual, mut gated) = (0.0f64, 0.0f64, 0usize);
        for seed in 0..n {
            match f(seed) {
                Ok(m) => {
                    residual = residual.max(m.residual);
                    match m.angle {
                        Some(e) => angle = angle.max(e),
                        None => gated += 1,
                    }
                }
                Err(e) => failed.push(format!("{name} seed {seed}: {e}")),
            }
        }
        eprintln!(
            "{name}: {n} instances, worst angle error {angle:.1e} ({gated} ill-conditioned not \
             counted), worst residual {residual:.1e}"
        );
        if !(angle <= ANGLE_TOL && residual <= RESIDUAL_REL) {
            failed.push(format!("{name}: bounds"));
        }
    }
    assert!(
        failed.is_empty(),
        "{} failures, first {:?}",
        failed.len(),
        failed.first()
    );
}

// ---------------------------------------------------------------------------------------------
// Near-degenerate families.

/// A signed relative offset: zero, or of magnitude in [1e-16, 1e-6] (log-uniform).
fn tiny() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        6 => ((-16.0f64..-6.0), any::<bool>())
            .prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) }),
    ]
}

/// The contact of a target a signed `gap` beyond the edge of reach (negative: inside), which
/// rounding of the inputs moves by at most `noise`: a miss of at most the tolerance `t`
/// touches (one double root), any overlap crosses (two roots close to the touching turn), a
/// larger miss reports its gap.
fn at_edge(x: &Intersection<f64, 2>, gap: f64, t: f64, noise: f64) -> Result<(), TestCaseError> {
    let r = x.roots.as_slice();
    match x.contact {
        Contact::Tangent => {
            prop_assert!(
                gap >= -noise && gap <= t + noise,
                "tangent at gap {:e} ({:e})",
                gap,
                t
            );
            prop_assert!(r.len() == 2 && r[0] == r[1], "{:?}", x);
        }
        Contact::Crossing => {
            prop_assert!(gap <= noise, "crossing at gap {:e}", gap);
            prop_assert_eq!(r.len(), 2);
        }
        Contact::Disjoint { gap: g } => {
            prop_assert!(gap >= t - noise, "missing at gap {:e} ({:e})", gap, t);
            prop_assert!((g - gap).abs() <= noise, "gap {:e} for {:e}", g, gap);
        }
        other => prop_assert!(false, "{:?}", other),
    }
    Ok(())
}

/// Rounding noise of inputs of magnitude `m`.
fn noise(m: f64) -> f64 {
    64.0 * f64::EPSILON * m
}

proptest! {
    #![proptest_config(config())]

    /// A point on or very near its axis: refused as on it, or turned with a residual at the
    /// rounding of the inputs.
    #[test]
    fn sp1_point_near_the_axis(seed in any::<u64>(), e in -17.0f64..-3.0) {
        let mut g = Rng(seed);
        let s = g.scale();
        let axis = g.axis(s);
        let w = g.unit();
        let p = axis.at(g.range(-1.0, 1.0) * s) + (w - axis.dir * axis.dir.dot(&w)) * (10f64.powf(e) * s);
        let t = g.angle();
        let q = rot(&axis, t, &p);
        let m = mag(&[axis.point, p, q], &[]);
        let x = turn_onto_point(&axis, &p, &q);
        match x.contact {
            Contact::ZeroRadius => prop_assert!(across(&axis, &p).norm() <= 1e-13 * m),
            Contact::Crossing => {
                let r = x.roots.as_slice()[0];
                prop_assert!((rot(&axis, r, &p) - q).norm() <= RESIDUAL_REL * m);
            }
            // The reference rotation rounds `q` by some ulps of `p`'s offset from the pivot,
            // which a tiny orbit may not absorb.
            Contact::Disjoint { gap } => prop_assert!(gap <= 4.0 * noise(m), "{:e}", gap),
            other => prop_assert!(false, "{:?}", other),
        }
        // The sphere, plane and line through the turned point are reached likewise.
        let y = turn_to_distance(&axis, &p, &axis.point, (q - axis.point).norm());
        for &r in y.roots.as_slice() {
            let err = ((rot(&axis, r, &p) - axis.point).norm() - (q - axis.point).norm()).abs();
            prop_assert!(err <= RESIDUAL_REL * m, "{:e}", err);
        }
    }

    /// A target off the orbit along the axis by `δ`: reached within the tangency tolerance,
    /// a miss with gap `|δ|` beyond; the least-squares angle is the known one either way.
    #[test]
    fn sp1_target_off_the_orbit(seed in any::<u64>(), e in tiny()) {
        let mut g = Rng(seed);
        let s = g.scale();
        let axis = g.axis(s);
        let p = g.off_axis(&axis, s);
        let t = g.angle();
        let q = rot(&axis, t, &p) + axis.dir * (e * s);
        let m = mag(&[axis.point, p, q], &[]);
        let x = turn_onto_point(&axis, &p, &q);
        let gap = (e * s).abs();
        match x.contact {
            Contact::Crossing => prop_assert!(gap <= TANGENT_REL * m + noise(m)),
            Contact::Disjoint { gap: g } => {
                prop_assert!(gap >= TANGENT_REL * m - noise(m));
                prop_assert!((g - gap).abs() <= noise(m), "{:e} for {:e}", g, gap);
            }
            other => prop_assert!(false, "{:?}", other),
        }
        let n = nearest_turn(&axis, &p, &q).expect("p and q are off the axis");
        prop_assert!(adist(n.angle, t) <= ANGLE_TOL);
        prop_assert!((n.miss - gap).abs() <= noise(m));
    }

    /// SP3 with the distance at, just inside and just outside the orbit's nearest and farthest
    /// distances from the centre.
    #[test]
    fn sp3_edge_of_reach(seed in any::<u64>(), e in tiny(), far in any::<bool>()) {
        let mut g = Rng(seed);
        let s = g.scale();
        let axis = g.axis(s);
        let p = g.off_axis(&axis, s);
        let q = g.off_axis(&axis, s);
        let (r, rho) = (across(&axis, &p).norm(), across(&axis, &q).norm());
        let h = axis.dir.dot(&(q - p));
        let edge = if far { h.hypot(rho + r) } else { h.hypot(rho - r) };
        prop_assume!(edge > 0.05 * s);
        let d = edge + e * s;
        let m = mag(&[axis.point, p, q], &[d]);
        let x = turn_to_distance(&axis, &p, &q, d);
        // Past the farthest distance, or short of the nearest, misses.
        let gap = if far { e * s } else { -e * s };
        at_edge(&x, gap, TANGENT_REL * m, noise(m))?;
        // The touching turn: towards q's foot's direction (nearest) or away from it (farthest).
        let toward = across(&axis, &q);
        let te = {
            let rp = across(&axis, &p);
            axis.dir.dot(&rp.cross(&toward)).atan2(rp.dot(&toward)) + if far { PI } else { 0.0 }
        };
        for &root in x.roots.as_slice() {
            prop_assert!(adist(root, te) <= 10.0 * (e.abs() / 0.05).sqrt() + 1e-6,
                "root {} touching {}", root, te);
            let err = ((rot(&axis, root, &p) - q).norm() - d).abs();
            prop_assert!(err <= TANGENT_REL * m + RESIDUAL_REL * m, "{:e}", err);
        }
    }

    /// SP4 with the plane at, just below and just above the orbit's highest point.
    #[test]
    fn sp4_edge_of_reach(seed in any::<u64>(), e in tiny()) {
        let mut g = Rng(seed);
        let s = g.scale();
        let axis = g.axis(s);
        let p = g.off_axis(&axis, s);
        let n = g.unit();
        let k = axis.dir;
        let np = n - k * k.dot(&n);
        prop_assume!(np.norm() > 0.05);
        let r = across(&axis, &p).norm();
        let centre = p - across(&axis, &p);
        let top = n.dot(&centre.coords) + r * np.norm();
        let plane = Plane::new(n, top + e * s);
        let m = mag(&[axis.point, p], &[plane.offset]);
        let x = turn_onto_plane(&axis, &p, &plane);
        at_edge(&x, e * s, TANGENT_REL * m, noise(m))?;
        let rp = across(&axis, &p);
        let te = k.dot(&rp.cross(&np)).atan2(rp.dot(&np));
        for &root in x.roots.as_slice() {
            prop_assert!(adist(root, te) <= 10.0 * (e.abs() / 0.05).sqrt() + 1e-6);
            let err = plane.signed_distance(&rot(&axis, root, &p)).abs();
            prop_assert!(err <= TANGENT_REL * m + RESIDUAL_REL * m, "{:e}", err);
        }
    }

    /// SP2 with parallel axes whose orbits (in one plane) touch, overlap a hair or miss one.
    #[test]
    fn sp2_parallel_orbits_touching(seed in any::<u64>(), e in tiny(), inner in any::<bool>()) {
        let mut g = Rng(seed);
        let s = g.scale();
        let first = g.axis(s);
        let (r1, r2) = (g.range(0.2, 1.0) * s, g.range(0.2, 1.0) * s);
        prop_assume!(!inner || (r1 - r2).abs() > 0.05 * s);
        let across_dir = {
            let w = g.unit();
            (w - first.dir * first.dir.dot(&w)).normalize()
        };
        let dist = if inner { (r1 - r2).abs() } else { r1 + r2 } + e * s;
        let c2 = first.at(g.range(-1.0, 1.0) * s) + across_dir * r1;
        let second = Line3::new(c2 + across_dir * (dist - r1), if g.f() < 0.5 { first.dir } else { -first.dir });
        // p on the first orbit, q on the second, both in the plane through `c2` across the axes.
        let p = rot(&first, g.angle(), &c2);
        let q = rot(&second, g.angle(), &(second.point + across_dir * r2));
        // At p's height to the last bit the construction allows (the rotations round it).
        let q = q + first.dir * first.dir.dot(&(p - q));
        let m = mag(&[first.point, second.point, p, q], &[]);
        let x = turns_meeting(&first, &p, &second, &q);
        let gap = if inner { -e * s } else { e * s };
        let t = TANGENT_REL * m;
        let nz = noise(m) * 4.0;
        match x.contact {
            Contact::Tangent => prop_assert!(gap >= -nz && gap <= t + nz, "tangent at {:e}", gap),
            Contact::Crossing => prop_assert!(gap <= nz, "crossing at {:e}", gap),
            Contact::Disjoint { gap: gg } => {
                prop_assert!(gap >= t - nz, "missing at {:e}", gap);
                prop_assert!((gg - gap).abs() <= nz, "{:e} for {:e}", gg, gap);
            }
            other => prop_assert!(false, "{:?}", other),
        }
        for r in x.roots.as_slice() {
            let err = (rot(&first, r[0], &p) - rot(&second, r[1], &q)).norm();
            prop_assert!(err <= 2.0 * t + RESIDUAL_REL * m, "{:e}", err);
        }
    }
}

/// SP6 at a fold of its equations (where two solutions merge): the Jacobian's determinant is
/// zero at `[θ1, θ2]`, by construction. The values there are reached in a double root (or two
/// roots within the square root of rounding); moved across the fold by `1e-9.5` to `1e-8` of
/// the scale, two roots more on one side than on the other. (Moved by less, a double root may
/// be reported on both sides: whether a close pair is one is decided on the quartic's
/// coefficients, within their rounding, which near an ill-conditioned fold amounts to misses
/// of about `1e-11` of the scale.)
fn six_fold(seed: u64) -> Option<(Six, [f64; 2], Vector3<f64>)> {
    let mut f = six(seed);
    // The Jacobian's columns: the derivative of each term's height is its direction's dot
    // with the axis crossed with the turned point's offset.
    let dh = |term: &Term, a: f64| {
        let y = rot(&term.axis, a, &term.point) - term.axis.point;
        term.along.dot(&term.axis.dir.cross(&y))
    };
    let col = |t: [f64; 2], which: usize| {
        let r = |row: &[Term; 4]| {
            if which == 0 {
                dh(&row[0], t[0]) + dh(&row[1], t[0])
            } else {
                dh(&row[2], t[1]) + dh(&row[3], t[1])
            }
        };
        [r(&f.terms[0]), r(&f.terms[1])]
    };
    let t1 = f.t[0];
    let j0 = col([t1, 0.0], 0);
    // The second column is `α cos θ2 + β sin θ2`, per row.
    let (al, be) = (col([t1, 0.0], 1), col([t1, PI / 2.0], 1));
    let a = j0[0] * al[1] - j0[1] * al[0];
    let b = j0[0] * be[1] - j0[1] * be[0];
    if a.hypot(b) < 1e-3 * f.s * f.s {
        return None;
    }
    let t2 = (-a).atan2(b);
    f.t = [t1, t2];
    f.d = six_value(&f.terms, f.t);
    // The direction across the fold's image: normal to the Jacobian's (rank one) columns.
    let c = if j0[0].hypot(j0[1]) > 1e-3 * f.s {
        j0
    } else {
        col(f.t, 1)
    };
    if c[0].hypot(c[1]) <= 1e-3 * f.s {
        return None;
    }
    let nrm = Vector3::new(-c[1], c[0], 0.0).normalize();
    // A fold, not a cusp: the values curve across the image along the Jacobian's kernel.
    let (c0, c1) = (j0, col(f.t, 1));
    let n0 = c0[0] * c0[0] + c0[1] * c0[1];
    let v = if n0 > 1e-6 * f.s * f.s {
        let l = (c1[0] * c0[0] + c1[1] * c0[1]) / n0;
        [l, -1.0]
    } else {
        [1.0, 0.0]
    };
    let h = 1e-3;
    let at = |k: f64| six_value(&f.terms, [t1 + k * h * v[0], t2 + k * h * v[1]]);
    let (p, z, m) = (at(1.0), at(0.0), at(-1.0));
    let curve = ((p[0] + m[0] - 2.0 * z[0]) * nrm.x + (p[1] + m[1] - 2.0 * z[1]) * nrm.y) / (h * h);
    if curve.abs() < 1e-1 * f.s {
        return None;
    }
    Some((f, [t1, t2], nrm))
}

proptest! {
    #![proptest_config(fold_config())]

    #[test]
    fn sp6_fold_is_a_double_root(seed in any::<u64>(), e in -9.5f64..-8.0) {
        let fold = six_fold(seed);
        prop_assume!(fold.is_some());
        let (f, t, n) = fold.expect("assumed");
        let near = |x: &Intersection<[f64; 2], 4>, within: f64| {
            x.roots.as_slice().iter().filter(|r| adist(r[0], t[0]).max(adist(r[1], t[1])) <= within).count()
        };
        let x = four_terms(&f.terms, f.d);
        let at = near(&x, 1e-5);
        prop_assert!(at == 2, "{} roots near the fold: {:?} for {:?}", at, x, t);
        // Two near roots are one double root, or a pair split by rounding.
        let eps = 10f64.powf(e) * f.s;
        let up = four_terms(&f.terms, [f.d[0] + n.x * eps, f.d[1] + n.y * eps]);
        let down = four_terms(&f.terms, [f.d[0] - n.x * eps, f.d[1] - n.y * eps]);
        // The pair moves away from the fold as the square root of the move (over the fold's
        // curvature, which may be small): one side has two roots more than the other, and the
        // fold itself as many as that side (the pair merged).
        let (lu, ld) = (up.roots.len(), down.roots.len());
        prop_assert!(lu.abs_diff(ld) == 2, "{} and {} roots: {:?} {:?}", lu, ld, up, down);
        prop_assert_eq!(x.roots.len(), lu.max(ld));
    }
}

// ---------------------------------------------------------------------------------------------
// The number of solutions against an independent count.

/// The number of sign changes of `f` over a turn, sampled at `n` angles, each confirmed by
/// bisection; `None` when a sampled local extremum of `|f|` is within `close` of zero (a
/// near tangency the sampling cannot count).
fn count_1d(f: impl Fn(f64) -> f64, n: usize, close: f64) -> Option<usize> {
    let v: Vec<f64> = (0..n).map(|i| f(-PI + TAU * i as f64 / n as f64)).collect();
    let mut count = 0;
    for i in 0..n {
        let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
        if b.abs() <= a.abs() && b.abs() <= c.abs() && b.abs() < close {
            return None;
        }
        if (b < 0.0) != (c < 0.0) {
            // Bisect to confirm a root in between.
            let (mut lo, mut hi) = (
                -PI + TAU * i as f64 / n as f64,
                -PI + TAU * (i + 1) as f64 / n as f64,
            );
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (f(mid) < 0.0) == (f(lo) < 0.0) {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            if f(0.5 * (lo + hi)).abs() <= close {
                count += 1;
            }
        }
    }
    Some(count)
}

/// The distinct solutions of two equations in two angles found by Newton's method from a
/// `grid x grid` of starts; `None` when one of them is nearly singular (a near tangency).
fn count_2d(f: impl Fn(f64, f64) -> [f64; 2], grid: usize, tol: f64) -> Option<usize> {
    let mut found: Vec<[f64; 2]> = Vec::new();
    let h = 1e-7;
    for i in 0..grid {
        for j in 0..grid {
            let mut t = [
                -PI + TAU * (i as f64 + 0.5) / grid as f64,
                -PI + TAU * (j as f64 + 0.5) / grid as f64,
            ];
            let mut ok = false;
            for _ in 0..40 {
                let r = f(t[0], t[1]);
                let (fa, fb) = (f(t[0] + h, t[1]), f(t[0], t[1] + h));
                let j = [
                    [(fa[0] - r[0]) / h, (fb[0] - r[0]) / h],
                    [(fa[1] - r[1]) / h, (fb[1] - r[1]) / h],
                ];
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                if det == 0.0 {
                    break;
                }
                let d0 = (r[0] * j[1][1] - r[1] * j[0][1]) / det;
                let d1 = (j[0][0] * r[1] - j[1][0] * r[0]) / det;
                // Damped: at most a quarter turn per step.
                let l = (d0.hypot(d1) / 0.8).max(1.0);
                t = [t[0] - d0 / l, t[1] - d1 / l];
                if d0.hypot(d1) < 1e-13 {
                    ok = true;
                    break;
                }
            }
            let r = f(t[0], t[1]);
            if !(ok || r[0].hypot(r[1]) <= tol) || r[0].hypot(r[1]) > tol {
                continue;
            }
            let t = [wrap(t[0]), wrap(t[1])];
            if !found
                .iter()
                .any(|u| adist(u[0], t[0]) < 1e-6 && adist(u[1], t[1]) < 1e-6)
            {
                found.push(t);
            }
        }
    }
    for t in &found {
        if conditioning2(&f, t[0], t[1], 1.0) < 1e-4 {
            return None;
        }
    }
    Some(found.len())
}

fn wrap(t: f64) -> f64 {
    let w = t.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

/// An instance perturbed off its known solution, so that any number of solutions, none
/// included, is counted.
fn perturbed(g: &mut Rng, v: f64, s: f64) -> f64 {
    v + g.range(-0.5, 0.5) * s
}

#[test]
fn solution_counts_match_an_independent_count() {
    let (mut compared, mut skipped) = ([0usize; 4], [0usize; 4]);
    let mut histogram = [[0usize; 5]; 4];
    for seed in 0..scaled(400) {
        let mut g = Rng(seed ^ 0x5eed);
        // SP3.
        {
            let s = g.scale();
            let axis = g.axis(s);
            let p = g.off_axis(&axis, s);
            let q = g.point(s);
            let d = g.range(0.05, 2.0) * s;
            let x = turn_to_distance(&axis, &p, &q, d);
            match count_1d(|t| (rot(&axis, t, &p) - q).norm() - d, 4096, 1e-6 * s) {
                Some(c) => {
                    assert_eq!(x.roots.len(), c, "SP3 seed {seed}: {x:?}");
                    compared[0] += 1;
                    histogram[0][c] += 1;
                }
                None => skipped[0] += 1,
            }
        }
        // SP4.
        {
            let s = g.scale();
            let axis = g.axis(s);
            let p = g.off_axis(&axis, s);
            let plane = Plane::new(g.unit(), g.range(-1.5, 1.5) * s);
            let x = turn_onto_plane(&axis, &p, &plane);
            match count_1d(
                |t| plane.signed_distance(&rot(&axis, t, &p)),
                4096,
                1e-6 * s,
            ) {
                Some(c) => {
                    assert_eq!(x.roots.len(), c, "SP4 seed {seed}: {x:?}");
                    compared[1] += 1;
                    histogram[1][c] += 1;
                }
                None => skipped[1] += 1,
            }
        }
        // SP5, off its known solution.
        {
            let mut f = five(seed, AXES[seed as usize % 5]);
            let s = f.s;
            f.a = Point3::new(
                perturbed(&mut g, f.a.x, s),
                perturbed(&mut g, f.a.y, s),
                f.a.z,
            );
            if across(&f.first, &f.a).norm() > 0.1 * s {
                let x = three_circles(&f.first, &f.a, &f.second, &f.third, &f.b);
                match count_2d(
                    |a, b| {
                        let v = five_reduced(&f, a, b);
                        [v[0] / s, v[1] / s]
                    },
                    48,
                    1e-10,
                ) {
                    Some(c) => {
                        assert_eq!(x.roots.len(), c, "SP5 seed {seed}: {x:?}");
                        compared[2] += 1;
                        histogram[2][c] += 1;
                    }
                    None => skipped[2] += 1,
                }
            }
        }
        // SP6, off its known solution.
        {
            let mut f = six(seed);
            let s = f.s;
            f.d = [perturbed(&mut g, f.d[0], s), perturbed(&mut g, f.d[1], s)];
            let x = four_terms(&f.terms, f.d);
            let value = |a, b| {
                let v = six_value(&f.terms, [a, b]);
                [(v[0] - f.d[0]) / s, (v[1] - f.d[1]) / s]
            };
            match count_2d(value, 48, 1e-10) {
                Some(c) => {
                    assert_eq!(x.roots.len(), c, "SP6 seed {seed}: {x:?}");
                    compared[3] += 1;
                    histogram[3][c] += 1;
                }
                None => skipped[3] += 1,
            }
        }
    }
    eprintln!("compared (SP3, SP4, SP5, SP6) {compared:?}, skipped near tangency {skipped:?}, by count 0..4 {histogram:?}");
    assert!(
        compared.iter().all(|&c| c as u64 >= scaled(300)),
        "{compared:?}"
    );
}

#[test]
fn non_finite_and_degenerate_inputs_give_no_roots() {
    let z = Line3::new(Point3::origin(), Vector3::z());
    let nan = Point3::new(f64::NAN, 0.0, 0.0);
    let p = Point3::new(1.0, 0.0, 0.0);
    assert!(turn_onto_point(&z, &nan, &p).roots.is_empty());
    assert!(turn_to_distance(&z, &p, &p, f64::INFINITY).roots.is_empty());
    assert!(turn_onto_plane(&z, &p, &Plane::new(Vector3::x(), f64::NAN))
        .roots
        .is_empty());
    assert!(turns_meeting(&z, &p, &Line3::new(nan, Vector3::x()), &p)
        .roots
        .is_empty());
    assert!(three_circles(&z, &p, &z, &z, &nan).roots.is_empty());
    let t = Term {
        axis: z,
        point: p,
        along: Vector3::x(),
    };
    assert!(four_terms(&[[t; 4]; 2], [f64::NAN, 0.0]).roots.is_empty());
    assert!(nearest_turn(&z, &nan, &p).is_none());
    // A zero axis, a point on its axis.
    let zero = Line3::new(Point3::origin(), Vector3::zeros());
    assert_eq!(turn_onto_point(&zero, &p, &p).contact, Contact::ZeroRadius);
    assert_eq!(
        turn_to_distance(&z, &Point3::new(0.0, 0.0, 2.0), &p, 1.0).contact,
        Contact::ZeroRadius
    );
    assert_eq!(
        three_circles(&z, &Point3::new(0.0, 0.0, 1.0), &z, &z, &p).contact,
        Contact::ZeroRadius
    );
    // Three parallel axes: a planar problem, a continuum or nothing.
    let (a2, a3) = (
        Line3::new(Point3::new(2.0, 0.0, 0.0), Vector3::z()),
        Line3::new(Point3::new(3.0, 1.0, 0.0), -Vector3::z()),
    );
    assert_eq!(
        three_circles(&z, &p, &a2, &a3, &Point3::new(3.5, 1.0, 0.0)).contact,
        Contact::Coincident
    );
    // Three axes through one point.
    let (b2, b3) = (
        Line3::new(Point3::origin(), Vector3::x()),
        Line3::new(Point3::origin(), Vector3::new(0.0, 1.0, 1.0)),
    );
    assert_eq!(
        three_circles(
            &z,
            &Point3::new(1.0, 0.0, 0.5),
            &b2,
            &b3,
            &Point3::new(0.5, 0.0, 1.0)
        )
        .contact,
        Contact::Coincident
    );
}

proptest! {
    #![proptest_config(config())]

    /// SP2 with intersecting axes whose orbits, on one sphere about the axes' meeting point,
    /// touch (the axes' angle is the sum of the orbits' angular radii), overlap a little or
    /// miss a little: a miss is reported with a positive gap, an overlap meets in two points,
    /// and any root found meets to the tangency tolerance.
    #[test]
    fn sp2_intersecting_orbits_touching(seed in any::<u64>(), e in tiny()) {
        let mut g = Rng(seed);
        let s = g.scale();
        let o = g.point(s);
        let k1 = g.unit();
        let k2 = g.unit();
        let gamma = k1.angle(&k2);
        prop_assume!(gamma > 0.3 && gamma < PI - 0.3);
        let a1 = g.range(0.1, gamma - 0.1);
        let a2 = gamma - a1 + e;
        let radius = g.range(0.3, 1.0) * s;
        // A point at angular radius `a` from `k` on the sphere, turned anywhere about `k`.
        let on = |k: &Vector3<f64>, a: f64, g: &mut Rng| {
            let w = g.unit();
            // Twice: one projection leaves rounding over the sine of `w`'s angle with `k`.
            let u = w - k * k.dot(&w);
            let u = (u - k * k.dot(&u)).normalize();
            o + (k * a.cos() + u * a.sin()) * radius
        };
        let first = Line3::new(o + k1 * (g.range(-1.0, 1.0) * s), k1);
        let second = Line3::new(o + k2 * (g.range(-1.0, 1.0) * s), k2);
        let p = on(&k1, a1, &mut g);
        let q = on(&k2, a2, &mut g);
        let m = mag(&[first.point, second.point, p, q], &[]);
        let x = turns_meeting(&first, &p, &second, &q);
        let roots = x.roots.as_slice();
        // The orbits' angular radii add up to the axes' angle plus `e`: they overlap by about
        // `radius * e` (apart when negative).
        let gap = -radius * e;
        match x.contact {
            Contact::Disjoint { gap: gg } => {
                prop_assert!(gap > -8.0 * TANGENT_REL * m, "missing at overlap {:e}", gap);
                prop_assert!(gg >= 0.0 && gg <= 2.0 * gap.abs() + 8.0 * TANGENT_REL * m, "{:e} for {:e}", gg, gap);
            }
            Contact::Crossing | Contact::Tangent => {
                // The construction rounds the points by some ulps of `o` over the radius, and
                // the line common to the planes amplifies it over the axes' angle: a few
                // hundred ulps of the scale.
                prop_assert!(gap <= 8.0 * TANGENT_REL * m, "meeting at gap {:e}", gap);
                prop_assert_eq!(roots.len(), 2);
            }
            other => prop_assert!(false, "{:?}", other),
        }
        for r in roots {
            let err = (rot(&first, r[0], &p) - rot(&second, r[1], &q)).norm();
            prop_assert!(err <= 2.0 * TANGENT_REL * m + RESIDUAL_REL * m, "{:e}", err);
        }
    }

    /// SP5 with all three axes within `10^e` (relative) of one point, the spherical wrist's
    /// degenerate case: either refused as degenerate, or every root found meets to rounding.
    #[test]
    fn sp5_axes_nearly_through_one_point(seed in any::<u64>(), e in -14.0f64..-4.0) {
        let mut g = Rng(seed);
        let s = g.scale();
        let o = g.point(s);
        let off = 10f64.powf(e) * s;
        let axis = |g: &mut Rng| {
            let k = g.unit();
            Line3::new(o + k * (g.range(-1.0, 1.0) * s) + g.unit() * off, k)
        };
        let (first, second, third) = (axis(&mut g), axis(&mut g), axis(&mut g));
        let b = g.off_axis(&third, s);
        let t = [g.angle(), g.angle(), g.angle()];
        let x0 = rot(&second, t[1], &rot(&third, t[2], &b));
        let a = rot(&first, -t[0], &x0);
        prop_assume!(across(&first, &a).norm() > 0.1 * s);
        let m = mag(&[first.point, second.point, third.point, a, b], &[]);
        let x = three_circles(&first, &a, &second, &third, &b);
        for r in x.roots.as_slice() {
            let err = (rot(&first, r[0], &a) - rot(&second, r[1], &rot(&third, r[2], &b))).norm();
            prop_assert!(err <= RESIDUAL_REL * m, "{:e} at offset {:e}: {:?}", err / m, off, x);
        }
    }
}

/// The reduced equations' Jacobian determinant of SP5 at the known angles, in closed form:
/// the derivative of a turned point's offset is the axis crossed with it.
fn five_fold_det(f: &Five) -> f64 {
    let o = f.second.point;
    let k = f.second.dir;
    let pa = rot(&f.first, f.t[0], &f.a);
    let pb = rot(&f.third, f.t[2], &f.b);
    let (u, v) = (pa - o, pb - o);
    let du = f.first.dir.cross(&(pa - f.first.point));
    let dv = f.third.dir.cross(&(pb - f.third.point));
    let j = [
        [u.dot(&du) / f.s, -v.dot(&dv) / f.s],
        [k.dot(&du), -k.dot(&dv)],
    ];
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

/// An SP5 instance at a fold: `θ2` chosen (by bisection on a sign change of the reduced
/// Jacobian's determinant, as `a` follows it) where two solutions merge.
fn five_at_fold(seed: u64) -> Option<Five> {
    let base = five(seed, Axes::General);
    let with = |t2: f64| {
        let mut f = Five {
            t: [base.t[0], t2, base.t[2]],
            ..base
        };
        let x0 = rot(&f.second, t2, &rot(&f.third, f.t[2], &f.b));
        f.a = rot(&f.first, -f.t[0], &x0);
        f
    };
    let n = 64;
    let at = |i: usize| -PI + TAU * i as f64 / n as f64;
    let i = (0..n).find(|&i| {
        (five_fold_det(&with(at(i))) < 0.0) != (five_fold_det(&with(at(i + 1))) < 0.0)
    })?;
    let (mut lo, mut hi) = (at(i), at(i + 1));
    let sign_lo = five_fold_det(&with(lo)) < 0.0;
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if (five_fold_det(&with(mid)) < 0.0) == sign_lo {
            lo = mid
        } else {
            hi = mid
        }
    }
    let f = with(0.5 * (lo + hi));
    (across(&f.first, &f.a).norm() > 0.1 * f.s).then_some(f)
}

proptest! {
    #![proptest_config(fold_config())]

    /// SP5 at a fold (the target at the edge of what the chain reaches near that pose): the two
    /// merging solutions are one double root, or two within the square root of rounding, never
    /// none, never far apart. (That moving across the fold gains or loses the pair is checked
    /// on SP6's folds, which share the quartic, where cusps are told apart.)
    #[test]
    fn sp5_fold_is_a_double_root(seed in any::<u64>()) {
        let f = five_at_fold(seed);
        prop_assume!(f.is_some());
        let f = f.expect("assumed");
        let x = three_circles(&f.first, &f.a, &f.second, &f.third, &f.b);
        let near = x.roots.as_slice().iter()
            .filter(|r| adist(r[0], f.t[0]).max(adist(r[2], f.t[2])) <= 1e-5)
            .count();
        prop_assert!(near == 2, "{} roots near the fold: {:?} for {:?}", near, x, f.t);
        // Each root closes the chain to rounding, the pair as well as a simple root: the
        // polish on the chain's own miss, where the quartic's equations stall.
        let m = mag(&[f.first.point, f.second.point, f.third.point, f.a, f.b], &[]);
        for r in x.roots.as_slice() {
            let miss = five_meet(&f, *r).norm() / m;
            prop_assert!(miss <= 32.0 * f64::EPSILON, "a miss of {:e} at the fold: {:?}", miss, x);
        }
        if x.contact == Contact::Tangent {
            let r = x.roots.as_slice();
            prop_assert!(r.windows(2).any(|w| w[0] == w[1]));
        }
    }
}

/// SP5 with two solutions 7.5e-5 rad apart (ik-geo's `spherical_bot` at a pose near a fold of
/// its position chain, pose 512 of `ikgeo/`'s check): the quartic's equations polish them
/// only to about 1e-12 of the scale; the chain's own miss closes them to rounding.
#[test]
fn sp5_close_pair_closes_the_chain_to_rounding() {
    let first = Line3::new(Point3::origin(), Vector3::y());
    let second = Line3::new(
        Point3::new(1.2508566957869456, 0.0, 0.6598162824642664),
        Vector3::new(0.29552020666133955, 0.0, 0.955336489125606),
    );
    let third = Line3::new(
        Point3::new(2.384763546042489, 0.479425538604203, 1.3558093915376417),
        Vector3::new(-0.458012710847292, 0.8775825618903728, 0.14167993424703806),
    );
    let b = Point3::new(3.0140918058755215, 0.6044084883852824, 2.6160971379033464);
    // The wrist centre the arm's joints 0.607404982304, 1.484462083358, -1.570559101268 put
    // it at, from the sketch's 0.3, 0.5, -0.6.
    let a = rot(
        &first,
        0.607404982304 - 0.3,
        &rot(
            &second,
            1.484462083358 - 0.5,
            &rot(&third, -1.570559101268 + 0.6, &b),
        ),
    );
    let x = three_circles(&first, &a, &second, &third, &b);
    let m = mag(&[first.point, second.point, third.point, a, b], &[]);
    assert_eq!(x.roots.len(), 4, "{x:?}");
    for r in x.roots.as_slice() {
        let miss = (rot(&first, r[0], &a) - rot(&second, r[1], &rot(&third, r[2], &b))).norm();
        assert!(
            miss <= 8.0 * f64::EPSILON * m,
            "a miss of {:e}: {x:?}",
            miss / m
        );
    }
}

/// An instance of [`planar_chain_ends`] and the angles it was built at.
struct Chain {
    first: Line3,
    h: Vector3<f64>,
    base: Point3<f64>,
    joint: Line3,
    far: Vector3<f64>,
    last: Line3,
    offset: f64,
    sense: f64,
    t: [f64; 2],
}

/// A planar sub-chain's ends closed at the angles it was built at: a first body turning about
/// `first` with the chain's axis `h`, a far body turning about `last`, the chain's last body on
/// it by a joint, its axis `far` made to lie along `sense · h` at a random turn of the far body,
/// and the offset the chain must have. Built with nalgebra's rotations, apart from the solver.
fn planar_chain_at(seed: u64) -> Chain {
    let mut g = Rng(seed);
    let s = g.scale();
    let (first, h, base) = (g.axis(s), g.unit(), g.point(s));
    let (joint, last) = (g.axis(s), g.axis(s));
    let sense = if g.f() < 0.5 { 1.0 } else { -1.0 };
    let (t1, t2, t6) = (g.angle(), g.angle(), g.angle());
    let turn = |axis: &Line3, t: f64, v: &Vector3<f64>| {
        Rotation3::from_axis_angle(&Unit::new_normalize(axis.dir), t) * v
    };
    // The chain's axis at the answer, and the last body's axis that lies along it there: the
    // far body turned by `t6` about `last`, the joint by `t2`.
    let h_at = turn(&first, t1, &h);
    let far = turn(&joint, -t2, &turn(&last, -t6, &(sense * h_at)));
    // The offset: from the first body's joint point to the joint's point along `h`, at the answer.
    let base_at = rot(&first, t1, &base);
    let joint_at = rot(&last, t6, &joint.point);
    let offset = h_at.dot(&(joint_at - base_at));
    Chain {
        first,
        h,
        base,
        joint,
        far,
        last,
        offset,
        sense,
        t: [t1, t2],
    }
}

/// SP6 on a planar sub-chain's ends: the angles it was built at are among the roots, and every
/// root closes both of the chain's conditions (the axes' angle with `last`, `last`'s point at
/// its height) to rounding.
#[test]
fn planar_chain_ends_finds_the_angles_it_was_built_at() {
    let mut found = 0;
    for seed in 0..400u64 {
        let Chain {
            first,
            h,
            base,
            joint,
            far,
            last,
            offset,
            sense,
            t,
        } = planar_chain_at(seed);
        let x = planar_chain_ends(&first, &h, &base, &joint, &far, &last, offset, sense);
        if matches!(x.contact, Contact::Coincident) {
            continue;
        }
        let m = mag(&[first.point, base, joint.point, last.point], &[offset]);
        let turn = |axis: &Line3, t: f64, v: &Vector3<f64>| {
            Rotation3::from_axis_angle(&Unit::new_normalize(axis.dir), t) * v
        };
        for r in x.roots.as_slice() {
            let h_at = turn(&first, r[0], &h);
            let angle = last.dir.dot(&h_at) - sense * last.dir.dot(&turn(&joint, r[1], &far));
            assert!(
                angle.abs() <= 1e-12,
                "seed {seed}: the axes' angle off by {angle:e}"
            );
            let reach = last.point - joint.point;
            let height = h_at.dot(&(last.point - rot(&first, r[0], &base)))
                - sense * turn(&joint, r[1], &far).dot(&reach)
                - offset;
            assert!(
                height.abs() <= 1e-12 * m,
                "seed {seed}: the height off by {:e}",
                height / m
            );
        }
        let near = |r: &[f64; 2]| adist(r[0], t[0]).max(adist(r[1], t[1]));
        let best = x
            .roots
            .as_slice()
            .iter()
            .map(near)
            .fold(f64::INFINITY, f64::min);
        assert!(best <= 1e-7, "seed {seed}: {t:?} not among {x:?}");
        found += 1;
    }
    assert!(found >= 390, "only {found} of 400 instances solved");
}
