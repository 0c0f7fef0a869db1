//! The 3d baseline: unknowns and equations of a spatial model, solved by the shared
//! iteration ([`super`]).
//!
//! **Unknowns** are exactly the freedom [`Config<D3>`] has, per non-fixed top-level geom in
//! declaration order, each geom a rigid frame (origin, rotation, dimension) as the
//! configuration holds it:
//!
//! | geom | unknowns | DOF |
//! | --- | --- | --- |
//! | point | origin `x, y, z` | 3 |
//! | vector | direction (the frame's x axis) | 2 |
//! | line | direction, offset `(h1, h2)` from `s` | 4 |
//! | segment | origin (its start), direction, length | 6 |
//! | circle | centre, normal (the frame's z axis), radius | 6 |
//! | plane | normal (the frame's z axis), offset `h` from `s` | 3 |
//! | body | origin, rotation | 6 |
//!
//! A line's origin is `s + h1 y + h2 z`, with `s` its first sketch point and `y, z` the frame's
//! other axes: the foot of the perpendicular from `s` (which is `L.point`), so a line has no
//! gauge freedom along itself, as in 2d; a plane's origin moves only along its normal from its
//! sketch point, for the same reason (its `s`: the point written, or the normal times the
//! offset). Fixed geoms (and their members) are constants. If the model fixes nothing, the
//! top-level geom with the most DOF (a point before a plane of as many, then the first by name,
//! the analysis' rule) is held at its sketch; the model is then free to turn about it, and is
//! solved in the least-squares sense (the regularised normal equations take the short step).
//!
//! **Rotations.** Inside a solve, a rotation is `R = exp([r]×) R0`: `R0` is the rotation at
//! the start of the solve and the unknowns are the rotation vector `r` (three numbers for a
//! body; for a direction, two: `r` in the plane normal to the axis at the start, so that the
//! direction's roll, which nothing reads, is not an unknown). Every solve starts at `r = 0`,
//! where the map is the identity to first order: the Jacobian's rotation columns are
//! `J_l(r) b`, with `J_l` the left Jacobian of SO(3) (exact, analytic, and within a factor
//! `2/pi` of orthonormal for turns up to a half turn, so a solve may turn a body by anything
//! short of a full turn without loss of conditioning), and the steps are plain additions to
//! `r`, as the shared iteration takes them. Between solves the unknowns `x` hold absolute
//! values: a body's rotation vector (its angle in `[0, pi]`) and a direction's azimuth and
//! elevation, read back into a fresh `R0` at the start of the next solve. The unknowns
//! mean the same configuration whatever the params, so a warm start carries over from one
//! solve to the next, and [`Baseline3::config`] and [`Baseline3::unknowns_from_config`]
//! convert both ways without loss.
//!
//! **Equations** are the signed, smooth forms of what [`gcs_compiler::verify`] measures in 3d
//! (its `spatial` residuals), one or more per constraint (a joint is the conjunction of its
//! parts):
//!
//! - `coincident`, `spherical`, `midpoint`: the three components of the difference;
//! - `distance` between points `|a - b| - |d|`; from a plane, signed, `n · (p - o) - d`; from a
//!   line `|u × (p - base)| - d`; from a circle `hypot(n · w, |n × w| - r) - d` (`w = p - c`);
//!   a zero distance (a constant 0) is incidence, below;
//! - `on` a line: the offset from the line along two perpendiculars fixed in its frame (two
//!   equations, smooth on the line, where `|u × w|` is not); on a plane: `n · (p - o)`; on a
//!   circle: the height `n · w` and the radial gap `|n × w| - r`;
//! - `tangent` or `distance` between a line and a circle: the line in the circle's plane
//!   (`u · n`, `n · (base - c)`) and the signed in-plane gap `side (c - base) · (n × u) - r - d`,
//!   the side read from the start; between two circles: their normals parallel (two tilts,
//!   below), the second centre in the first's plane, and the 2d gap of their centres, external
//!   or nested as the start has it;
//! - a parallel axis `v` of `u` (`parallel`, `parallel_z` and the joints'): two tilts
//!   `atan2(v · e_k, sigma v · u)`, with `e_1, e_2` perpendiculars fixed in `u`'s frame (a
//!   marker's other two axes) and `sigma` the sense the start has (`angle` 0 or pi: that sense);
//! - `angle` and `offset_z`, unsigned: `atan2(|u × v|, u · v) - |wrap(a)|`; `perpendicular`:
//!   `u · v`;
//! - `offset_x`: with the z axes parallel, the turn from `x1` to `x2` about `z1` less the target,
//!   `atan2(x2 · y1, x2 · x1)` turned back by the target (wrapped to (-pi, pi]); `helical`: the
//!   same with the target `2 pi (z1 · (p2 - p1)) / pitch`;
//! - `in_line`: the offset of `m1` from `m2`'s z axis along `m2`'s x and y; `in_plane`: along
//!   its z; `prismatic`, `cylindrical`, `planar`, `revolute`: their parts;
//! - `symmetric` across a plane: the midpoint on it, and `q - p` along its normal (zero along
//!   two perpendiculars fixed in the plane's frame);
//! - `length`, `radius`, `equal`: differences of dimensions.
//!
//! Lengths are in the model's units and angles in radians, so the tolerance reads like
//! `verify`'s residuals; where a constraint's form is a sine rather than an angle (`u · v`),
//! the two agree to first order at a solution.
//!
//! **Jacobian**: analytic. Each equation's gradient is taken with respect to the frames it
//! reads (origin, rotation increment `omega` with `dR = [omega]× R`, dimension: seven numbers
//! a frame), and carried to the unknowns by each unknown's tangent (how the frame moves per
//! unit of it): a point feature `p = o + q` gives `dF/do = g`, `dF/domega = q × g`; a
//! direction `u`, `dF/domega = u × g`. An origin unknown moves the origin along its axis; a
//! rotation unknown turns the frame by `omega = J_l(r) b` (`b` its axis of increment) and a
//! line's or plane's origin about its sketch point with it; an offset moves the origin along
//! the frame's axis; a dimension is itself. The linear algebra, the equilibration and the
//! iteration are the shared ones; the length scale of a 3d start is the largest of the spread
//! of the origins of the frames that have a position (all but vectors'), the offsets of the
//! features the equations read, the dimensions and the equations' lengths.
//!
//! **Left out**: a segment's tangency to a circle is the tangency of its supporting line, as in
//! 2d: where an end of the segment is on the circle, `verify` also asks that end to be the
//! touching point, which no equation here says. Every constraint of the language has a form;
//! one with arguments the forms above do not cover is refused by [`Baseline3::new`], naming
//! it.

use super::solver::{Equations, Linear, Options, Outcome, Solver};
use gcs_compiler::config::{BadSketch, Config, D3};
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::expr::{ExprId, Exprs};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, PlanePlacement, Sketch, Space};
use gcs_lang::Model;
use gcs_runtime::frame::Frame3;
use nalgebra::{Matrix3, Point3, Rotation3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::{PI, TAU};
use std::time::Instant;

type V = [f64; 3];
/// A rotation by its columns: the frame's x, y and z axes, globally.
type Mat = [V; 3];
/// A gradient with respect to a frame: origin (3), rotation increment (3), dimension (1).
type G7 = [f64; 7];

const NONE: usize = usize::MAX;
const IDENTITY: Mat = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V) -> f64 {
    a[0].hypot(a[1]).hypot(a[2])
}
/// `a` over its norm; zero for a zero vector.
fn unit(a: V) -> V {
    let l = norm(a);
    if l > 0.0 {
        scale(a, 1.0 / l)
    } else {
        [0.0; 3]
    }
}
/// `m l`: a local vector, globally.
fn apply(m: &Mat, l: V) -> V {
    add(add(scale(m[0], l[0]), scale(m[1], l[1])), scale(m[2], l[2]))
}

fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

/// The coefficients `sin t / t` and `(1 - cos t) / t^2` of Rodrigues' formula, and
/// `(t - sin t) / t^3` of the left Jacobian, for `t = |r|`, without cancellation near 0.
fn rodrigues(r: V) -> (f64, f64, f64) {
    let t2 = dot(r, r);
    let t = t2.sqrt();
    if t < 1e-2 {
        (
            1.0 - t2 / 6.0 * (1.0 - t2 / 20.0),
            0.5 - t2 / 24.0 * (1.0 - t2 / 30.0),
            1.0 / 6.0 - t2 / 120.0 * (1.0 - t2 / 42.0),
        )
    } else {
        let (s, h) = (t.sin(), (0.5 * t).sin());
        (s / t, 2.0 * h * h / t2, (t - s) / (t2 * t))
    }
}

/// `exp([r]×) v`.
fn rotate(r: V, a: f64, b: f64, v: V) -> V {
    let rv = cross(r, v);
    add(add(v, scale(rv, a)), scale(cross(r, rv), b))
}

/// `exp([r]×) m`.
fn exp_times(r: V, m: &Mat) -> Mat {
    let (a, b, _) = rodrigues(r);
    [
        rotate(r, a, b, m[0]),
        rotate(r, a, b, m[1]),
        rotate(r, a, b, m[2]),
    ]
}

/// `J_l(r) v`, with `J_l` the left Jacobian of SO(3): `exp(r + d) = exp(J_l(r) d) exp(r)` to
/// first order.
fn left_jacobian(r: V, v: V) -> V {
    let (_, b, c) = rodrigues(r);
    let rv = cross(r, v);
    add(add(v, scale(rv, b)), scale(cross(r, rv), c))
}

/// The frame whose x axis points at azimuth `az` and elevation `el`: `Rz(az) Ry(-el)`.
fn canonical_x(az: f64, el: f64) -> Mat {
    let (sa, ca) = az.sin_cos();
    let (se, ce) = el.sin_cos();
    [
        [ce * ca, ce * sa, se],
        [-sa, ca, 0.0],
        [-se * ca, -se * sa, ce],
    ]
}

/// The frame whose z axis points at azimuth `az` and elevation `el` (the axes of
/// [`canonical_x`] in turn: y, z, x).
fn canonical_z(az: f64, el: f64) -> Mat {
    let [x, y, z] = canonical_x(az, el);
    [y, z, x]
}

/// The azimuth and elevation of a direction.
fn az_el(u: V) -> (f64, f64) {
    (u[1].atan2(u[0]), u[2].atan2(u[0].hypot(u[1])))
}

fn mat_of(q: &UnitQuaternion<f64>) -> Mat {
    let m = q.to_rotation_matrix();
    let c = |k: usize| {
        let v = m.matrix().column(k);
        [v[0], v[1], v[2]]
    };
    [c(0), c(1), c(2)]
}

fn quat_of(m: &Mat) -> UnitQuaternion<f64> {
    let cols = m.map(|c| Vector3::new(c[0], c[1], c[2]));
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(Matrix3::from_columns(
        &cols,
    )))
}

/// The rotation vector of `m`, of angle in `[0, pi]`.
fn log_of(m: &Mat) -> V {
    let r = quat_of(m).scaled_axis();
    [r.x, r.y, r.z]
}

fn v3(v: V) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2])
}

/// A top-level geom's frame as its sketch has it: origin, rotation, dimension, and its
/// sketch point (a line's first point, a plane's origin; the origin otherwise). It reads the
/// sketch as `Config::<D3>::from_sketch` does; a sketch that is not finite gives NaNs, which
/// a solve reports as [`super::Stop::NotFinite`].
fn sketch_frame(model: &Model, g: GeomId, p: &[f64]) -> (V, Mat, f64, V) {
    let e = &model.exprs;
    let c3 = |c: &[ExprId]| -> V {
        let at = |i: usize| c.get(i).map_or(f64::NAN, |&x| e.eval(x, p));
        [at(0), at(1), at(2)]
    };
    let along = |from: V, to: V| -> Mat {
        let q =
            gcs_runtime::frame::rotation_between3(&Vector3::x(), &v3(sub(to, from)), &Vector3::z());
        mat_of(&q)
    };
    let normal = |n: V| -> Mat {
        let q = gcs_runtime::frame::rotation_between3(&Vector3::z(), &v3(n), &Vector3::x());
        mat_of(&q)
    };
    let nan = [f64::NAN; 3];
    match &model.geoms[g].sketch {
        Sketch::Point(c) => {
            let o = c3(c);
            (o, IDENTITY, 0.0, o)
        }
        Sketch::Vector(c) => ([0.0; 3], along([0.0; 3], c3(c)), 0.0, [0.0; 3]),
        Sketch::Line { from, to } | Sketch::Segment { from, to } => {
            let (a, b) = (c3(from), c3(to));
            let dim = if model.geoms[g].kind == GeomKind::Segment {
                norm(sub(b, a))
            } else {
                0.0
            };
            (a, along(a, b), dim, a)
        }
        Sketch::Circle {
            center,
            radius,
            normal: n,
        } => {
            let o = c3(center);
            let n = n.as_ref().map_or([0.0, 0.0, 1.0], |n| c3(n));
            (o, normal(n), e.eval(*radius, p), o)
        }
        Sketch::Plane {
            normal: n,
            placement,
        } => {
            let m = normal(c3(n));
            let o = match placement {
                PlanePlacement::Offset(d) => scale(m[2], e.eval(*d, p)),
                PlanePlacement::Point(c) => c3(c),
            };
            (o, m, 0.0, o)
        }
        Sketch::Body { at, angle, axis } => {
            let o = at.as_ref().map_or([0.0; 3], |c| c3(c));
            let a = angle.map_or(0.0, |x| e.eval(x, p));
            let ax = axis.as_ref().map_or([0.0, 0.0, 1.0], |c| c3(c));
            let m = if a == 0.0 {
                IDENTITY
            } else {
                match Unit::try_new(v3(ax), 0.0) {
                    Some(u) => mat_of(&UnitQuaternion::from_axis_angle(&u, a)),
                    None => [nan; 3],
                }
            };
            (o, m, 0.0, o)
        }
        _ => (nan, [nan; 3], f64::NAN, nan),
    }
}

/// How a constant of a solve is computed from the params: one number or three.
#[derive(Clone, Copy, Debug)]
enum Recipe {
    /// Three numbers.
    Const(V),
    /// An expression.
    Expr(ExprId),
    /// `|wrap(e)|`: the target of an unsigned angle.
    AbsAngle(ExprId),
    /// Three coordinates as written.
    Coords([ExprId; 3]),
    /// A local direction normalised (0), or one of two perpendiculars to it (1, 2).
    Axes([ExprId; 3], usize),
    /// A marker's local x (0), y (1) or z (2) axis: z normalised, x made perpendicular to it.
    Marker(Option<[ExprId; 3]>, [ExprId; 3], usize),
}

impl Recipe {
    fn width(self) -> usize {
        match self {
            Recipe::Expr(_) | Recipe::AbsAngle(_) => 1,
            _ => 3,
        }
    }

    fn eval(self, e: &Exprs, p: &[f64], out: &mut [f64]) {
        let c3 = |c: [ExprId; 3]| [e.eval(c[0], p), e.eval(c[1], p), e.eval(c[2], p)];
        let v = match self {
            Recipe::Const(v) => v,
            Recipe::Expr(x) => {
                out[0] = e.eval(x, p);
                return;
            }
            Recipe::AbsAngle(x) => {
                out[0] = wrap(e.eval(x, p)).abs();
                return;
            }
            Recipe::Coords(c) => c3(c),
            Recipe::Axes(c, k) => {
                let u = unit(c3(c));
                // Across the coordinate axis along which u is smallest.
                let (ax, ay, az) = (u[0].abs(), u[1].abs(), u[2].abs());
                let a = if ax <= ay && ax <= az {
                    [1.0, 0.0, 0.0]
                } else if ay <= az {
                    [0.0, 1.0, 0.0]
                } else {
                    [0.0, 0.0, 1.0]
                };
                let e1 = unit(cross(u, a));
                [u, e1, cross(u, e1)][k]
            }
            Recipe::Marker(z, x, k) => {
                let z = unit(z.map_or([0.0, 0.0, 1.0], c3));
                let x = c3(x);
                let x = unit(sub(x, scale(z, dot(z, x))));
                [x, cross(z, x), z][k]
            }
        };
        out[..3].copy_from_slice(&v);
    }
}

/// The rotational freedom of a geom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rot {
    /// None: a point, or a constant geom.
    Fixed,
    /// Three: a body.
    Full,
    /// Two: its x axis turns (a vector, line or segment).
    AxisX,
    /// Two: its z axis turns (a circle or plane).
    AxisZ,
}

/// How a geom's origin is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Origin {
    /// Constant: the sketch's, or none that matters (a vector).
    Fixed,
    /// Three unknowns.
    Free,
    /// `s + h1 y + h2 z`: a line.
    Line,
    /// `s + h z`: a plane.
    Plane,
}

/// A top-level geom and where its unknowns are: in this order, its origin (3), rotation (2
/// or 3), offset (2 for a line, 1 for a plane) and dimension (1), as far as it has them.
#[derive(Clone, Copy, Debug)]
struct Geom {
    id: GeomId,
    origin: Origin,
    rot: Rot,
    /// Whether its dimension is an unknown.
    dim: bool,
    /// Its first unknown, and how many it has (0 for a constant geom).
    first: usize,
    count: usize,
}

impl Geom {
    fn rot_cols(&self) -> usize {
        match self.rot {
            Rot::Fixed => 0,
            Rot::Full => 3,
            Rot::AxisX | Rot::AxisZ => 2,
        }
    }
    /// The column of its first rotation unknown.
    fn rot_at(&self) -> usize {
        self.first + if self.origin == Origin::Free { 3 } else { 0 }
    }
    /// The column of its first offset unknown.
    fn off_at(&self) -> usize {
        self.rot_at() + self.rot_cols()
    }
    /// The column of its dimension.
    fn dim_at(&self) -> usize {
        self.first + self.count - 1
    }
}

/// A geom's frame at the start of a solve: the rotation the increments turn, the sketch point
/// a line or plane is offset from (the origin of a constant geom), a constant dimension.
#[derive(Clone, Copy, Debug)]
struct Base {
    r0: Mat,
    s: V,
    dim: f64,
}

/// A frame evaluated at the current unknowns.
#[derive(Clone, Copy, Debug)]
struct Fr {
    o: V,
    r: Mat,
    dim: f64,
    /// The rotation vector of the increment from the start of the solve.
    rv: V,
}

/// A point feature: `o + R (l + m dim e_x)`, `l` read from `z`.
#[derive(Clone, Copy, Debug)]
struct Pt {
    g: usize,
    l: usize,
    m: f64,
}

/// A direction feature: `R l`, the unit `l` read from `z`.
#[derive(Clone, Copy, Debug)]
struct Dir {
    g: usize,
    l: usize,
}

/// A marker pair's advance for a screw: `z1 · (p2 - p1)`.
#[derive(Clone, Copy, Debug)]
struct Screw {
    p1: Pt,
    p2: Pt,
    z1: Dir,
}

/// One scalar equation. Each reads up to three frames ([`Eq::geoms`]); the comments say
/// which feature is read through which.
#[derive(Clone, Copy, Debug)]
enum Eq {
    /// Component `k` of `a - b` (a, b).
    Diff { a: Pt, b: Pt, k: usize },
    /// `|a - b| - |d|` (a, b).
    Dist { a: Pt, b: Pt, d: usize },
    /// `(p - base) · e - d` (p, base, e).
    Proj { p: Pt, base: Pt, e: Dir, d: usize },
    /// `((p + q) / 2 - base) · e` (p, q, base and e).
    Mid { p: Pt, q: Pt, base: Pt, e: Dir },
    /// `|u × (p - base)| - d` (p, base and u).
    LineDist { p: Pt, base: Pt, u: Dir, d: usize },
    /// `|n × (p - c)| - r` (p, the circle c, n).
    Radial { p: Pt, c: Pt, n: Dir },
    /// `hypot(n · w, |n × w| - r) - d`, `w = p - c` (p, the circle c, n).
    CircleDist { p: Pt, c: Pt, n: Dir, d: usize },
    /// `side (c - base) · (n × u) - r - d` (the line base, u; the circle c, n).
    LineCircle {
        base: Pt,
        u: Dir,
        c: Pt,
        n: Dir,
        d: usize,
    },
    /// External, `|a - b| - ra - rb - d`, or nested, `side (ra - rb) - |a - b| - d` (the
    /// circles a, b).
    CircleCircle { a: Pt, b: Pt, d: usize },
    /// `atan2(|u × v|, u · v) - a` (u, v).
    Angle { u: Dir, v: Dir, a: usize },
    /// `atan2(v · e, sense v · u)`: the tilt of `v` from the axis `u` towards `e` (u and e,
    /// v); `sense` is fixed if not 0, else read from the start.
    Tilt { u: Dir, e: Dir, v: Dir, sense: f64 },
    /// `u · v` (u, v).
    Dot { u: Dir, v: Dir },
    /// The turn from `x1` to `x2` about `x1 × y1`, less the target `a` (or, for a screw, `2 pi
    /// advance / a`), wrapped (x1, y1 and the screw's p1, z1; x2 and p2).
    Turn {
        x1: Dir,
        y1: Dir,
        x2: Dir,
        a: usize,
        screw: Option<Screw>,
    },
    /// `dim - v` (g).
    Dim { g: usize, v: usize },
    /// `dim_a - dim_b` (a, b).
    SameDim { a: usize, b: usize },
}

impl Eq {
    /// The frames it reads, by side (`NONE`: none).
    fn geoms(&self) -> [usize; 3] {
        match *self {
            Eq::Diff { a, b, .. } | Eq::Dist { a, b, .. } | Eq::CircleCircle { a, b, .. } => {
                [a.g, b.g, NONE]
            }
            Eq::Proj { p, base, e, .. } => [p.g, base.g, e.g],
            Eq::Mid { p, q, base, .. } => [p.g, q.g, base.g],
            Eq::LineDist { p, base, .. } => [p.g, base.g, NONE],
            Eq::Radial { p, c, .. } | Eq::CircleDist { p, c, .. } => [p.g, c.g, NONE],
            Eq::LineCircle { base, c, .. } => [base.g, c.g, NONE],
            Eq::Angle { u, v, .. } | Eq::Dot { u, v } | Eq::Tilt { u, v, .. } => [u.g, v.g, NONE],
            Eq::Turn { x1, x2, .. } => [x1.g, x2.g, NONE],
            Eq::Dim { g, .. } => [g, NONE, NONE],
            Eq::SameDim { a, b } => [a, b, NONE],
        }
    }

    /// Whether the features it reads through one side are of one frame, as [`Eq::geoms`]
    /// says (checked when the equations are built).
    fn sides_agree(&self) -> bool {
        match *self {
            Eq::Mid { base, e, .. } => base.g == e.g,
            Eq::LineDist { base, u, .. } => base.g == u.g,
            Eq::Radial { c, n, .. } | Eq::CircleDist { c, n, .. } => c.g == n.g,
            Eq::LineCircle { base, u, c, n, .. } => base.g == u.g && c.g == n.g,
            Eq::Tilt { u, e, .. } => u.g == e.g,
            Eq::Turn {
                x1, y1, x2, screw, ..
            } => {
                x1.g == y1.g
                    && screw.is_none_or(|s| s.p1.g == x1.g && s.z1.g == x1.g && s.p2.g == x2.g)
            }
            _ => true,
        }
    }

    /// Whether it is an angle (else a length).
    fn is_angle(&self) -> bool {
        matches!(
            self,
            Eq::Angle { .. } | Eq::Tilt { .. } | Eq::Dot { .. } | Eq::Turn { .. }
        )
    }
}

/// A point feature's position and its offset from the frame origin.
#[inline]
fn point(f: &Fr, z: &[f64], p: &Pt) -> (V, V) {
    let l = [z[p.l] + p.m * f.dim, z[p.l + 1], z[p.l + 2]];
    let q = apply(&f.r, l);
    (add(f.o, q), q)
}

/// Adds the gradient `gp` with respect to a point feature to its frame's gradient.
#[inline]
fn push_point(g: &mut G7, f: &Fr, q: V, m: f64, gp: V) {
    let t = cross(q, gp);
    for k in 0..3 {
        g[k] += gp[k];
        g[3 + k] += t[k];
    }
    g[6] += m * dot(gp, f.r[0]);
}

#[inline]
fn dir(f: &Fr, z: &[f64], d: &Dir) -> V {
    apply(&f.r, [z[d.l], z[d.l + 1], z[d.l + 2]])
}

/// Adds the gradient `gu` with respect to a direction feature `u` to its frame's gradient.
#[inline]
fn push_dir(g: &mut G7, u: V, gu: V) {
    let t = cross(u, gu);
    for k in 0..3 {
        g[3 + k] += t[k];
    }
}

/// The equations of a 3d model and the state they are evaluated at: the unknowns, then the
/// constants of the current solve, in one array `z`.
struct Spatial {
    model: Model,
    n: usize,
    m: usize,
    geoms: Vec<Geom>,
    base: Vec<Base>,
    frames: Vec<Fr>,
    eqs: Vec<Eq>,
    /// The side or sense each equation's choice took at the start of the solve (0 means the
    /// external form for circle pairs).
    side: Vec<f64>,
    /// Constant recipes and where they go in `z`.
    consts: Vec<(Recipe, usize)>,
    z: Vec<f64>,
    /// Per unknown, how its frame moves per unit of it (origin, rotation, dimension).
    tangent: Vec<G7>,
    // Jacobian entries: per equation a range of (side, column, position in J).
    ent_ptr: Vec<usize>,
    ent_side: Vec<u8>,
    ent_col: Vec<usize>,
    ent_pos: Vec<usize>,
}

/// The solver for one 3d model, built once and reused for every solve: the 3d twin of
/// [`super::Baseline`], with the same API on [`Config<D3>`].
pub struct Baseline3 {
    eq: Spatial,
    solver: Solver,
}

impl std::fmt::Debug for Baseline3 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Baseline3")
            .field("unknowns", &self.eq.n)
            .field("equations", &self.eq.m)
            .field("sparse", &self.solver.is_sparse())
            .finish_non_exhaustive()
    }
}

/// Where the constants every model uses are in `z`, after the `n` unknowns.
const ORIGIN: usize = 0;
const EX: usize = 3;
const EY: usize = 6;
const EZ: usize = 9;

/// The builder's state: constants allocated after the unknowns.
struct Build<'a> {
    model: &'a Model,
    n: usize,
    consts: Vec<(Recipe, usize)>,
    next: usize,
    index: std::collections::HashMap<GeomId, usize>,
}

impl Build<'_> {
    fn konst(&mut self, r: Recipe) -> usize {
        let at = self.next;
        self.consts.push((r, at));
        self.next += r.width();
        at
    }
    fn at(&self, k: usize) -> usize {
        self.n + k
    }
    fn top(&self, g: GeomId) -> Result<usize, String> {
        let t = self.model.top_level_of(g);
        self.index
            .get(&t)
            .copied()
            .ok_or_else(|| format!("{} has no frame", self.model.geoms[t].name))
    }
    fn xyz(&self, c: &[ExprId], what: GeomId) -> Result<[ExprId; 3], String> {
        match c {
            [x, y, z] => Ok([*x, *y, *z]),
            _ => Err(format!("{} is not 3d", self.model.geoms[what].name)),
        }
    }
    /// The local axes `(x, y, z)` of a marker.
    fn marker_axes(&mut self, marker: GeomId) -> Result<[usize; 3], String> {
        let Sketch::Marker { z, x, .. } = &self.model.geoms[marker].sketch else {
            return Err(format!("{} is not a marker", self.model.geoms[marker].name));
        };
        let z = match z {
            Some(z) => Some(self.xyz(z, marker)?),
            None => None,
        };
        let x = self.xyz(x, marker)?;
        Ok([0, 1, 2].map(|k| self.konst(Recipe::Marker(z, x, k))))
    }
    /// A point argument: a point, marker, part or circle (its centre).
    fn pt(&mut self, g: GeomId) -> Result<Pt, String> {
        let model = self.model;
        let geom = &model.geoms[g];
        let top = self.top(g)?;
        let zero = self.at(ORIGIN);
        let at = |l, m| Pt { g: top, l, m };
        match (geom.kind, geom.owner, &geom.sketch) {
            (GeomKind::Point | GeomKind::Circle, Owner::TopLevel, _) => Ok(at(zero, 0.0)),
            (GeomKind::Point | GeomKind::Marker, Owner::Member(_), Sketch::Point(c))
            | (GeomKind::Marker, Owner::Member(_), Sketch::Marker { origin: c, .. }) => {
                let c = self.xyz(c, g)?;
                Ok(at(self.konst(Recipe::Coords(c)), 0.0))
            }
            (GeomKind::Point, Owner::Part(_, Part::End), _) => Ok(at(zero, 1.0)),
            (GeomKind::Point, Owner::Part(_, Part::Start | Part::Center | Part::BasePoint), _) => {
                Ok(at(zero, 0.0))
            }
            _ => Err(format!(
                "{} is not a 3d point the baseline can read",
                geom.name
            )),
        }
    }
    /// A direction argument and two perpendiculars to it fixed in its frame: a vector (a
    /// member, a marker axis, `L.dir`, `C.normal`), a line or segment, a plane (its normal), a
    /// marker (its z axis).
    fn basis(&mut self, g: GeomId) -> Result<[Dir; 3], String> {
        let model = self.model;
        let geom = &model.geoms[g];
        let top = self.top(g)?;
        let d = |l: usize| Dir { g: top, l };
        let (ex, ey, ez) = (self.at(EX), self.at(EY), self.at(EZ));
        let along_x = [d(ex), d(ey), d(ez)];
        let along_z = [d(ez), d(ex), d(ey)];
        match (geom.kind, geom.owner, &geom.sketch) {
            (GeomKind::Vector | GeomKind::Line | GeomKind::Segment, Owner::TopLevel, _)
            | (GeomKind::Vector, Owner::Part(_, Part::Dir), _) => Ok(along_x),
            (GeomKind::Plane, Owner::TopLevel, _)
            | (GeomKind::Vector, Owner::Part(_, Part::Normal), _) => Ok(along_z),
            (GeomKind::Vector, Owner::Member(_), Sketch::Vector(c)) => {
                let c = self.xyz(c, g)?;
                Ok([0, 1, 2].map(|k| d(self.konst(Recipe::Axes(c, k)))))
            }
            (GeomKind::Vector, Owner::Part(marker, Part::AxisZ), _) => {
                let [x, y, z] = self.marker_axes(marker)?;
                Ok([d(z), d(x), d(y)])
            }
            (GeomKind::Vector, Owner::Part(marker, Part::AxisX), _) => {
                let [x, y, z] = self.marker_axes(marker)?;
                Ok([d(x), d(y), d(z)])
            }
            (GeomKind::Marker, Owner::Member(_), _) => {
                let [x, y, z] = self.marker_axes(g)?;
                Ok([d(z), d(x), d(y)])
            }
            _ => Err(format!(
                "{} is not a 3d direction the baseline can read",
                geom.name
            )),
        }
    }
    fn dir(&mut self, g: GeomId) -> Result<Dir, String> {
        Ok(self.basis(g)?[0])
    }
    /// A line argument: a point on it, its direction and two perpendiculars fixed in its
    /// frame. A line by its origin (`L.point`), a segment by its start, a marker is the line
    /// through its point along its z axis.
    fn line(&mut self, g: GeomId) -> Result<(Pt, [Dir; 3]), String> {
        let base = match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Segment => Pt {
                g: self.top(g)?,
                l: self.at(ORIGIN),
                m: 0.0,
            },
            _ => self.pt(g)?,
        };
        Ok((base, self.basis(g)?))
    }
    /// A circle argument: its centre and normal.
    fn circle(&mut self, g: GeomId) -> Result<(Pt, [Dir; 3]), String> {
        if self.model.geoms[g].kind != GeomKind::Circle {
            return Err(format!("{} is not a circle", self.model.geoms[g].name));
        }
        let top = self.top(g)?;
        let d = |l: usize| Dir { g: top, l };
        let c = Pt {
            g: top,
            l: self.at(ORIGIN),
            m: 0.0,
        };
        Ok((c, [d(self.at(EZ)), d(self.at(EX)), d(self.at(EY))]))
    }
    /// A plane argument: its origin and normal, and two directions in it.
    fn plane(&mut self, g: GeomId) -> Result<(Pt, [Dir; 3]), String> {
        if self.model.geoms[g].kind != GeomKind::Plane {
            return Err(format!("{} is not a plane", self.model.geoms[g].name));
        }
        let top = self.top(g)?;
        let o = Pt {
            g: top,
            l: self.at(ORIGIN),
            m: 0.0,
        };
        Ok((o, self.basis(g)?))
    }
}

/// What a constraint's value is, as far as the choice of its equations goes.
#[derive(Clone, Copy, Debug)]
struct Value {
    /// Its expression, if it has one.
    expr: Option<ExprId>,
    /// Where it is in `z` (the constant 0 if it has none).
    at: usize,
    /// Whether it is the constant 0: a distance that is an incidence.
    zero: bool,
    /// If it is a constant angle of 0 or pi: 1 or -1, the sense of a parallel.
    sense: Option<f64>,
}

impl Build<'_> {
    /// `v` parallel to the first of `u` (two tilts towards its two perpendiculars), in the
    /// sense the start has them if `sense` is 0.
    fn parallel(eqs: &mut Vec<Eq>, [u, e1, e2]: [Dir; 3], v: Dir, sense: f64) {
        for e in [e1, e2] {
            eqs.push(Eq::Tilt { u, e, v, sense });
        }
    }

    /// The three components of `a - b`.
    fn coincident(eqs: &mut Vec<Eq>, a: Pt, b: Pt) {
        for k in 0..3 {
            eqs.push(Eq::Diff { a, b, k });
        }
    }

    /// `u` and `v` at the unsigned angle `value` (two tilts for a constant 0 or pi).
    fn angle(
        &mut self,
        eqs: &mut Vec<Eq>,
        u: GeomId,
        v: GeomId,
        value: Value,
    ) -> Result<(), String> {
        let (bu, dv) = (self.basis(u)?, self.dir(v)?);
        match value.sense {
            Some(sense) => Self::parallel(eqs, bu, dv, sense),
            None => {
                let Some(e) = value.expr else {
                    return Err("an angle without a value".into());
                };
                let a = self.konst(Recipe::AbsAngle(e));
                eqs.push(Eq::Angle { u: bu[0], v: dv, a });
            }
        }
        Ok(())
    }

    /// A point `p` at distance `value` from `g` (a point, line, plane or circle).
    fn point_distance(
        &mut self,
        eqs: &mut Vec<Eq>,
        p: GeomId,
        g: GeomId,
        value: Value,
    ) -> Result<bool, String> {
        let zero = self.at(ORIGIN);
        let d = value.at;
        let pp = self.pt(p)?;
        match self.model.geoms[g].kind {
            GeomKind::Point | GeomKind::Marker => {
                let q = self.pt(g)?;
                if value.zero {
                    Self::coincident(eqs, pp, q);
                } else {
                    eqs.push(Eq::Dist { a: pp, b: q, d });
                }
            }
            GeomKind::Line | GeomKind::Segment => {
                let (base, [u, e1, e2]) = self.line(g)?;
                if value.zero {
                    for e in [e1, e2] {
                        eqs.push(Eq::Proj {
                            p: pp,
                            base,
                            e,
                            d: zero,
                        });
                    }
                } else {
                    eqs.push(Eq::LineDist { p: pp, base, u, d });
                }
            }
            GeomKind::Plane => {
                let (base, [e, _, _]) = self.plane(g)?;
                eqs.push(Eq::Proj { p: pp, base, e, d });
            }
            GeomKind::Circle => {
                let (c, [n, _, _]) = self.circle(g)?;
                if value.zero {
                    eqs.push(Eq::Proj {
                        p: pp,
                        base: c,
                        e: n,
                        d: zero,
                    });
                    eqs.push(Eq::Radial { p: pp, c, n });
                } else {
                    eqs.push(Eq::CircleDist { p: pp, c, n, d });
                }
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// A line or circle `x` at the in-plane distance at `d` from the circle `y`, in its plane.
    fn circle_distance(
        &mut self,
        eqs: &mut Vec<Eq>,
        x: GeomId,
        y: GeomId,
        d: usize,
    ) -> Result<bool, String> {
        let zero = self.at(ORIGIN);
        let (c, bc) = self.circle(y)?;
        let n = bc[0];
        match self.model.geoms[x].kind {
            GeomKind::Line | GeomKind::Segment => {
                let (base, [u, _, _]) = self.line(x)?;
                eqs.push(Eq::Dot { u, v: n });
                eqs.push(Eq::Proj {
                    p: base,
                    base: c,
                    e: n,
                    d: zero,
                });
                eqs.push(Eq::LineCircle { base, u, c, n, d });
            }
            GeomKind::Circle => {
                let (a, ba) = self.circle(x)?;
                Self::parallel(eqs, ba, n, 0.0);
                eqs.push(Eq::Proj {
                    p: c,
                    base: a,
                    e: ba[0],
                    d: zero,
                });
                eqs.push(Eq::CircleCircle { a, b: c, d });
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// `m1`'s point on the line through `m2`'s along its z axis.
    fn in_line(&mut self, eqs: &mut Vec<Eq>, m1: GeomId, m2: GeomId) -> Result<(), String> {
        let zero = self.at(ORIGIN);
        let p = self.pt(m1)?;
        let (base, [_, e1, e2]) = self.line(m2)?;
        for e in [e1, e2] {
            eqs.push(Eq::Proj {
                p,
                base,
                e,
                d: zero,
            });
        }
        Ok(())
    }

    /// `m1`'s point in the plane through `m2`'s normal to its z axis.
    fn in_plane(&mut self, eqs: &mut Vec<Eq>, m1: GeomId, m2: GeomId) -> Result<(), String> {
        let zero = self.at(ORIGIN);
        let p = self.pt(m1)?;
        let (base, [e, _, _]) = self.line(m2)?;
        eqs.push(Eq::Proj {
            p,
            base,
            e,
            d: zero,
        });
        Ok(())
    }

    /// The z axes of `m1` and `m2` parallel, in the sense the start has them.
    fn parallel_z(&mut self, eqs: &mut Vec<Eq>, m1: GeomId, m2: GeomId) -> Result<(), String> {
        let u = self.basis(m1)?;
        let v = self.dir(m2)?;
        Self::parallel(eqs, u, v, 0.0);
        Ok(())
    }

    /// The turn from `m1`'s x axis to `m2`'s about `m1`'s z is `a` (or, for a screw, `2 pi`
    /// times the advance of `m2` along `m1`'s z over the pitch `a`).
    fn turn(
        &mut self,
        eqs: &mut Vec<Eq>,
        m1: GeomId,
        m2: GeomId,
        a: usize,
        screw: bool,
    ) -> Result<(), String> {
        let [x1, y1, z1] = self.marker_axes(m1)?;
        let [x2, _, _] = self.marker_axes(m2)?;
        let (g1, g2) = (self.top(m1)?, self.top(m2)?);
        let d = |g: usize, l: usize| Dir { g, l };
        let screw = if screw {
            Some(Screw {
                p1: self.pt(m1)?,
                p2: self.pt(m2)?,
                z1: d(g1, z1),
            })
        } else {
            None
        };
        eqs.push(Eq::Turn {
            x1: d(g1, x1),
            y1: d(g1, y1),
            x2: d(g2, x2),
            a,
            screw,
        });
        Ok(())
    }

    /// The equations of constraint `c`, appended to `eqs`; an error naming it if the baseline
    /// has no form for it.
    fn constraint(
        &mut self,
        eqs: &mut Vec<Eq>,
        c: &gcs_lang::model::Constraint,
    ) -> Result<(), String> {
        let model = self.model;
        let bad = || format!("the 3d baseline cannot express {} ({})", c.name, c.text);
        let at = match c.value {
            Some(e) => self.konst(Recipe::Expr(e)),
            None => self.at(ORIGIN),
        };
        let constant = c
            .value
            .filter(|&e| model.exprs.is_constant(e))
            .map(|e| model.exprs.eval(e, &[]));
        let value = Value {
            expr: c.value,
            at,
            zero: constant == Some(0.0),
            sense: constant.map(|a| wrap(a).abs()).and_then(|a| {
                if a <= 1e-12 {
                    Some(1.0)
                } else if a >= PI - 1e-12 {
                    Some(-1.0)
                } else {
                    None
                }
            }),
        };
        let (Some(&x), y) = (c.args.first(), c.args.get(1).copied()) else {
            return Err(bad());
        };
        let y = || y.ok_or_else(bad);
        let kind = |g: GeomId| model.geoms[g].kind;
        let incidence = Value {
            expr: None,
            at: self.at(ORIGIN),
            zero: true,
            sense: None,
        };
        match c.kind {
            K::Coincident | K::Spherical => {
                let (a, b) = (self.pt(x)?, self.pt(y()?)?);
                Self::coincident(eqs, a, b);
            }
            K::Revolute => {
                let (a, b) = (self.pt(x)?, self.pt(y()?)?);
                Self::coincident(eqs, a, b);
                self.parallel_z(eqs, x, y()?)?;
            }
            K::Distance if kind(x).is_pointlike() => {
                if !self.point_distance(eqs, x, y()?, value)? {
                    return Err(bad());
                }
            }
            K::Distance | K::Tangent => {
                let d = if c.kind == K::Tangent {
                    self.at(ORIGIN)
                } else {
                    at
                };
                if !self.circle_distance(eqs, x, y()?, d)? {
                    return Err(bad());
                }
            }
            K::On => {
                if !self.point_distance(eqs, x, y()?, incidence)? {
                    return Err(bad());
                }
            }
            K::Angle | K::OffsetZ => self.angle(eqs, x, y()?, value)?,
            K::Parallel => {
                let (u, v) = (self.basis(x)?, self.dir(y()?)?);
                Self::parallel(eqs, u, v, 0.0);
            }
            K::Perpendicular => {
                let (u, v) = (self.dir(x)?, self.dir(y()?)?);
                eqs.push(Eq::Dot { u, v });
            }
            K::Length | K::Radius => eqs.push(Eq::Dim {
                g: self.top(x)?,
                v: at,
            }),
            K::Equal => eqs.push(Eq::SameDim {
                a: self.top(x)?,
                b: self.top(y()?)?,
            }),
            // The point and the segment's own point at half its length.
            K::Midpoint => {
                let p = self.pt(x)?;
                let m = Pt {
                    g: self.top(y()?)?,
                    l: self.at(ORIGIN),
                    m: 0.5,
                };
                Self::coincident(eqs, p, m);
            }
            // The midpoint on the plane, and q - p along its normal.
            K::Symmetric => {
                let plane = c.args.get(2).copied().ok_or_else(bad)?;
                if kind(plane) != GeomKind::Plane {
                    return Err(bad());
                }
                let (p, q) = (self.pt(x)?, self.pt(y()?)?);
                let (base, [e, t1, t2]) = self.plane(plane)?;
                eqs.push(Eq::Mid { p, q, base, e });
                for t in [t1, t2] {
                    eqs.push(Eq::Proj {
                        p: q,
                        base: p,
                        e: t,
                        d: self.at(ORIGIN),
                    });
                }
            }
            K::InLine => self.in_line(eqs, x, y()?)?,
            K::InPlane => self.in_plane(eqs, x, y()?)?,
            K::ParallelZ => self.parallel_z(eqs, x, y()?)?,
            K::OffsetX => {
                self.parallel_z(eqs, x, y()?)?;
                self.turn(eqs, x, y()?, at, false)?;
            }
            K::Helical => {
                self.parallel_z(eqs, x, y()?)?;
                self.turn(eqs, x, y()?, at, true)?;
            }
            K::Prismatic => {
                self.in_line(eqs, x, y()?)?;
                self.parallel_z(eqs, x, y()?)?;
                let zero = self.at(ORIGIN);
                self.turn(eqs, x, y()?, zero, false)?;
            }
            K::Cylindrical => {
                self.in_line(eqs, x, y()?)?;
                self.parallel_z(eqs, x, y()?)?;
            }
            K::Planar => {
                self.in_plane(eqs, x, y()?)?;
                self.parallel_z(eqs, x, y()?)?;
            }
            // The frames coincide: the points, the z axes in the same sense, no turn.
            K::Weld => {
                let (a, b) = (self.pt(x)?, self.pt(y()?)?);
                Self::coincident(eqs, a, b);
                let (u, v) = (self.basis(x)?, self.dir(y()?)?);
                Self::parallel(eqs, u, v, 1.0);
                let zero = self.at(ORIGIN);
                self.turn(eqs, x, y()?, zero, false)?;
            }
            K::Horizontal | K::Vertical => {
                return Err(format!("{}: horizontal and vertical are 2d only", bad()))
            }
        }
        Ok(())
    }
}

impl Baseline3 {
    /// Compiles the equations of a 3d model, choosing dense or sparse linear algebra by size.
    pub fn new(model: &Model) -> Result<Baseline3, String> {
        Baseline3::with_linear(model, Linear::Auto)
    }

    /// Like [`Baseline3::new`], forcing the linear algebra (to compare the two paths).
    pub fn with_linear(model: &Model, linear: Linear) -> Result<Baseline3, String> {
        if model.space != Space::D3 {
            return Err("the 3d baseline covers 3d models only".into());
        }
        let tops: Vec<(GeomId, &gcs_lang::model::Geom)> = model.top_level().collect();
        // Ground: fixed geoms; if none, the one with the most DOF (a point first), then by
        // name.
        let any_fixed = tops.iter().any(|(_, g)| g.fixed);
        let held = if any_fixed {
            None
        } else {
            let rank =
                |g: &gcs_lang::model::Geom| (g.kind.dof(Space::D3), g.kind == GeomKind::Point);
            tops.iter()
                .max_by(|a, b| {
                    rank(a.1)
                        .cmp(&rank(b.1))
                        .then_with(|| b.1.name.cmp(&a.1.name))
                })
                .map(|(id, _)| *id)
        };
        let mut geoms = Vec::new();
        let mut n = 0;
        for (id, g) in &tops {
            let constant = g.fixed || Some(*id) == held;
            let (origin, rot, dim) = match g.kind {
                _ if constant => (Origin::Fixed, Rot::Fixed, false),
                GeomKind::Point => (Origin::Free, Rot::Fixed, false),
                GeomKind::Vector => (Origin::Fixed, Rot::AxisX, false),
                GeomKind::Line => (Origin::Line, Rot::AxisX, false),
                GeomKind::Segment => (Origin::Free, Rot::AxisX, true),
                GeomKind::Circle => (Origin::Free, Rot::AxisZ, true),
                GeomKind::Plane => (Origin::Plane, Rot::AxisZ, false),
                GeomKind::Body => (Origin::Free, Rot::Full, false),
                GeomKind::Marker => {
                    return Err(format!("{} is a marker outside a body", g.name));
                }
            };
            let mut geom = Geom {
                id: *id,
                origin,
                rot,
                dim,
                first: n,
                count: 0,
            };
            geom.count = match origin {
                Origin::Free => 3,
                Origin::Line => 2,
                Origin::Plane => 1,
                Origin::Fixed => 0,
            } + geom.rot_cols()
                + usize::from(dim);
            n += geom.count;
            geoms.push(geom);
        }
        let mut b = Build {
            model,
            n,
            consts: Vec::new(),
            next: n,
            index: tops
                .iter()
                .enumerate()
                .map(|(i, (id, _))| (*id, i))
                .collect(),
        };
        for v in [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            b.konst(Recipe::Const(v));
        }
        let mut eqs = Vec::new();
        for (_, c) in model.constraints.iter() {
            b.constraint(&mut eqs, c)?;
        }
        debug_assert!(eqs.iter().all(Eq::sides_agree));
        let m = eqs.len();
        let frame = Fr {
            o: [0.0; 3],
            r: IDENTITY,
            dim: 0.0,
            rv: [0.0; 3],
        };
        let base = Base {
            r0: IDENTITY,
            s: [0.0; 3],
            dim: 0.0,
        };
        let mut eq = Spatial {
            model: model.clone(),
            n,
            m,
            base: vec![base; geoms.len()],
            frames: vec![frame; geoms.len()],
            geoms,
            side: vec![1.0; m],
            eqs,
            consts: b.consts,
            z: vec![0.0; b.next],
            tangent: vec![[0.0; 7]; n],
            ent_ptr: vec![0],
            ent_side: Vec::new(),
            ent_col: Vec::new(),
            ent_pos: Vec::new(),
        };
        let solver = eq.structure(linear.sparse(n))?;
        Ok(Baseline3 { eq, solver })
    }

    /// The model it solves.
    pub fn model(&self) -> &Model {
        &self.eq.model
    }

    /// The number of unknowns.
    pub fn unknowns(&self) -> usize {
        self.eq.n
    }

    /// The number of scalar equations.
    pub fn equations(&self) -> usize {
        self.eq.m
    }

    /// Whether the sparse linear algebra is in use.
    pub fn is_sparse(&self) -> bool {
        self.solver.is_sparse()
    }

    /// The cold start: the unknowns as the sketch has them, with `params`.
    pub fn start_from_sketch(&self, params: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.eq.n];
        for g in &self.eq.geoms {
            let (o, r, dim, s) = sketch_frame(&self.eq.model, g.id, params);
            put_public(g, o, &r, dim, s, &mut x);
        }
        x
    }

    /// The unknowns that describe configuration `cfg` (the plan's answer, say): a start on
    /// the assembly `cfg` is on, for a continuation.
    pub fn unknowns_from_config(&self, params: &[f64], cfg: &Config<D3>) -> Vec<f64> {
        let mut x = self.start_from_sketch(params);
        for g in &self.eq.geoms {
            let Some(f) = cfg.frames.get(&g.id) else {
                continue;
            };
            let (_, _, _, s) = sketch_frame(&self.eq.model, g.id, params);
            let o = [f.origin.x, f.origin.y, f.origin.z];
            let dim = cfg.dims.get(&g.id).copied().unwrap_or(0.0);
            put_public(g, o, &mat_of(&f.rotation), dim, s, &mut x);
        }
        x
    }

    /// The configuration the unknowns `x` describe, to read a
    /// [`gcs_compiler::solution::Solution`] (with `Solution::read_space`) and re-check it
    /// with [`gcs_compiler::verify`].
    pub fn config(&self, params: &[f64], x: &[f64]) -> Result<Config<D3>, BadSketch> {
        let mut cfg = Config::<D3>::from_sketch(&self.eq.model, params)?;
        for g in &self.eq.geoms {
            if g.count == 0 {
                continue;
            }
            let (_, _, _, s) = sketch_frame(&self.eq.model, g.id, params);
            let (o, r, dim) = public_frame(g, x, s);
            if let Some(fr) = cfg.frames.get_mut(&g.id) {
                *fr = Frame3::new(Point3::new(o[0], o[1], o[2]), quat_of(&r));
            }
            if let Some(d) = cfg.dims.get_mut(&g.id) {
                if g.dim {
                    *d = dim;
                }
            }
        }
        Ok(cfg)
    }

    /// Solves in place: `x` holds the start (warm, or [`Baseline3::start_from_sketch`]) and
    /// receives the result. After the first call, the iteration allocates nothing (unless a
    /// trace is asked for).
    pub fn solve(&mut self, params: &[f64], x: &mut [f64], opts: &Options) -> Outcome {
        let t0 = Instant::now();
        let eq = &mut self.eq;
        eq.load(params, x);
        eq.choose_sides();
        self.solver.equilibrate(eq.length_scale());
        let out = self.solver.iterate(eq, opts, t0);
        eq.store(x);
        out
    }
}

/// Writes the unknowns of `g` that describe the frame `(o, r, dim)` into `x`, a line's and a
/// plane's offsets measured from the sketch point `s`.
fn put_public(g: &Geom, o: V, r: &Mat, dim: f64, s: V, x: &mut [f64]) {
    if g.count == 0 {
        return;
    }
    if g.origin == Origin::Free {
        x[g.first..g.first + 3].copy_from_slice(&o);
    }
    let at = g.rot_at();
    let mut axes = IDENTITY;
    match g.rot {
        Rot::Fixed => {}
        Rot::Full => x[at..at + 3].copy_from_slice(&log_of(r)),
        Rot::AxisX | Rot::AxisZ => {
            let axis = if g.rot == Rot::AxisX { r[0] } else { r[2] };
            let (az, el) = az_el(axis);
            x[at] = az;
            x[at + 1] = el;
            axes = if g.rot == Rot::AxisX {
                canonical_x(az, el)
            } else {
                canonical_z(az, el)
            };
        }
    }
    let off = g.off_at();
    let w = sub(o, s);
    match g.origin {
        Origin::Line => {
            x[off] = dot(w, axes[1]);
            x[off + 1] = dot(w, axes[2]);
        }
        Origin::Plane => x[off] = dot(w, axes[2]),
        Origin::Free | Origin::Fixed => {}
    }
    if g.dim {
        x[g.dim_at()] = dim;
    }
}

/// The rotation the unknowns `x` of `g` describe (the identity for a geom without one).
fn public_rotation(g: &Geom, x: &[f64]) -> Mat {
    let at = g.rot_at();
    match g.rot {
        Rot::Fixed => IDENTITY,
        Rot::Full => exp_times([x[at], x[at + 1], x[at + 2]], &IDENTITY),
        Rot::AxisX => canonical_x(x[at], x[at + 1]),
        Rot::AxisZ => canonical_z(x[at], x[at + 1]),
    }
}

/// The frame `(origin, rotation, dimension)` the unknowns `x` of a non-constant `g` describe,
/// with `s` its sketch point.
fn public_frame(g: &Geom, x: &[f64], s: V) -> (V, Mat, f64) {
    let r = public_rotation(g, x);
    let off = g.off_at();
    let o = match g.origin {
        Origin::Free => [x[g.first], x[g.first + 1], x[g.first + 2]],
        Origin::Line => add(add(s, scale(r[1], x[off])), scale(r[2], x[off + 1])),
        Origin::Plane => add(s, scale(r[2], x[off])),
        Origin::Fixed => [0.0; 3],
    };
    let dim = if g.dim { x[g.dim_at()] } else { 0.0 };
    (o, r, dim)
}

impl Equations for Spatial {
    fn unknowns_mut(&mut self) -> &mut [f64] {
        &mut self.z[..self.n]
    }

    fn values(&mut self, f: &mut [f64]) {
        self.update_frames();
        for (e, v) in f.iter_mut().enumerate() {
            *v = self.eval(e, false).0;
        }
    }

    fn jacobian(&mut self, jv: &mut [f64]) {
        self.update_frames();
        self.tangents();
        for e in 0..self.m {
            let (_, gr) = self.eval(e, true);
            for t in self.ent_ptr[e]..self.ent_ptr[e + 1] {
                let g = &gr[self.ent_side[t] as usize];
                let tan = &self.tangent[self.ent_col[t]];
                let mut v = 0.0;
                for k in 0..7 {
                    v += g[k] * tan[k];
                }
                jv[self.ent_pos[t]] += v;
            }
        }
    }
}

impl Spatial {
    /// Builds the Jacobian's pattern and this model's entry positions in it, and the solver
    /// on it.
    fn structure(&mut self, sparse_path: bool) -> Result<Solver, String> {
        let n = self.n;
        // Rotation unknowns are angles; origins, offsets and dimensions are lengths.
        let mut col_len = vec![true; n];
        for g in &self.geoms {
            for c in col_len.iter_mut().skip(g.rot_at()).take(g.rot_cols()) {
                *c = false;
            }
        }
        let row_len = self.eqs.iter().map(|e| !e.is_angle()).collect();
        let mut rows: Vec<Vec<(u8, usize)>> = Vec::with_capacity(self.m);
        for e in &self.eqs {
            let mut r = Vec::new();
            for (side, &g) in e.geoms().iter().enumerate() {
                if g == NONE {
                    continue;
                }
                let geom = &self.geoms[g];
                for col in geom.first..geom.first + geom.count {
                    r.push((side as u8, col));
                }
            }
            rows.push(r);
        }
        let ucols: Vec<Vec<usize>> = rows
            .iter()
            .map(|r| {
                let mut c: Vec<usize> = r.iter().map(|e| e.1).collect();
                c.sort_unstable();
                c.dedup();
                c
            })
            .collect();
        let solver = Solver::new(n, &ucols, row_len, col_len, sparse_path)?;
        for (e, r) in rows.iter().enumerate() {
            for &(side, col) in r {
                self.ent_side.push(side);
                self.ent_col.push(col);
                self.ent_pos.push(solver.position(e, col));
            }
            self.ent_ptr.push(self.ent_pos.len());
        }
        Ok(solver)
    }

    /// The start of a solve: the constants from `params`, each geom's frame at the start (a
    /// constant one from its sketch, a free one from `x`), and the unknowns in `z`: `x`, with
    /// every rotation increment 0.
    fn load(&mut self, params: &[f64], x: &[f64]) {
        let n = self.n;
        for &(r, at) in &self.consts {
            r.eval(&self.model.exprs, params, &mut self.z[at..]);
        }
        self.z[..n].copy_from_slice(&x[..n]);
        for (g, base) in self.geoms.iter().zip(self.base.iter_mut()) {
            let needs_sketch = g.count == 0 || matches!(g.origin, Origin::Line | Origin::Plane);
            if needs_sketch {
                let (o, r, dim, s) = sketch_frame(&self.model, g.id, params);
                *base = if g.count == 0 {
                    Base { r0: r, s: o, dim }
                } else {
                    Base { r0: r, s, dim: 0.0 }
                };
            }
            if g.count > 0 {
                base.r0 = public_rotation(g, x);
                let at = g.rot_at();
                self.z[at..at + g.rot_cols()]
                    .iter_mut()
                    .for_each(|v| *v = 0.0);
            }
        }
    }

    /// The end of a solve: the unknowns `x` of the frames reached.
    fn store(&mut self, x: &mut [f64]) {
        self.update_frames();
        x[..self.n].copy_from_slice(&self.z[..self.n]);
        for ((g, f), base) in self.geoms.iter().zip(&self.frames).zip(&self.base) {
            put_public(g, f.o, &f.r, f.dim, base.s, x);
        }
    }

    /// Evaluates every frame from `z`.
    fn update_frames(&mut self) {
        let z = &self.z;
        for ((g, b), f) in self
            .geoms
            .iter()
            .zip(&self.base)
            .zip(self.frames.iter_mut())
        {
            if g.count == 0 {
                *f = Fr {
                    o: b.s,
                    r: b.r0,
                    dim: b.dim,
                    rv: [0.0; 3],
                };
                continue;
            }
            let at = g.rot_at();
            let rv = match g.rot {
                Rot::Fixed => [0.0; 3],
                Rot::Full => [z[at], z[at + 1], z[at + 2]],
                Rot::AxisX => add(scale(b.r0[1], z[at]), scale(b.r0[2], z[at + 1])),
                Rot::AxisZ => add(scale(b.r0[0], z[at]), scale(b.r0[1], z[at + 1])),
            };
            let r = if g.rot == Rot::Fixed {
                b.r0
            } else {
                exp_times(rv, &b.r0)
            };
            let off = g.off_at();
            let o = match g.origin {
                Origin::Free => [z[g.first], z[g.first + 1], z[g.first + 2]],
                Origin::Line => add(add(b.s, scale(r[1], z[off])), scale(r[2], z[off + 1])),
                Origin::Plane => add(b.s, scale(r[2], z[off])),
                Origin::Fixed => b.s,
            };
            let dim = if g.dim { z[g.dim_at()] } else { b.dim };
            *f = Fr { o, r, dim, rv };
        }
    }

    /// How each frame moves per unit of each of its unknowns (frames must be current): an
    /// origin unknown moves the origin along its axis; a rotation unknown turns the frame by
    /// `omega = J_l(r) b`, with `b` its axis of increment, and moves the origin of a line or
    /// plane about its sketch point with it; an offset moves the origin along its axis; a
    /// dimension is itself.
    fn tangents(&mut self) {
        for ((g, b), f) in self.geoms.iter().zip(&self.base).zip(&self.frames) {
            if g.count == 0 {
                continue;
            }
            let t = &mut self.tangent[g.first..g.first + g.count];
            t.iter_mut().for_each(|v| *v = [0.0; 7]);
            let mut k = 0;
            if g.origin == Origin::Free {
                for (i, tk) in t.iter_mut().take(3).enumerate() {
                    tk[i] = 1.0;
                }
                k = 3;
            }
            let axes: [V; 3] = match g.rot {
                Rot::Fixed | Rot::Full => IDENTITY,
                Rot::AxisX => [b.r0[1], b.r0[2], [0.0; 3]],
                Rot::AxisZ => [b.r0[0], b.r0[1], [0.0; 3]],
            };
            let arm = sub(f.o, b.s);
            let moves = matches!(g.origin, Origin::Line | Origin::Plane);
            for axis in axes.iter().take(g.rot_cols()) {
                let w = left_jacobian(f.rv, *axis);
                let d = if moves { cross(w, arm) } else { [0.0; 3] };
                t[k] = [d[0], d[1], d[2], w[0], w[1], w[2], 0.0];
                k += 1;
            }
            let offsets: &[V] = match g.origin {
                Origin::Line => &[f.r[1], f.r[2]],
                Origin::Plane => &[f.r[2]],
                Origin::Free | Origin::Fixed => &[],
            };
            for a in offsets {
                t[k] = [a[0], a[1], a[2], 0.0, 0.0, 0.0, 0.0];
                k += 1;
            }
            if g.dim {
                t[k][6] = 1.0;
            }
        }
    }

    /// The length scale `L` of the start configuration, for [`Solver::equilibrate`]: the
    /// largest of the spread of the origins of the frames that have a position (every geom
    /// but a vector), the offsets of the features the equations read, frame dimensions and
    /// the equations' lengths (1 if all are zero); it is translation-invariant.
    fn length_scale(&mut self) -> f64 {
        self.update_frames();
        let z = &self.z;
        let fr = &self.frames;
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut l = 0.0f64;
        for (f, g) in fr.iter().zip(&self.geoms) {
            if self.model.geoms[g.id].kind != GeomKind::Vector {
                for k in 0..3 {
                    lo[k] = lo[k].min(f.o[k]);
                    hi[k] = hi[k].max(f.o[k]);
                }
            }
            l = l.max(f.dim.abs());
        }
        for k in 0..3 {
            if hi[k] >= lo[k] {
                l = l.max(hi[k] - lo[k]);
            }
        }
        let off = |p: &Pt| norm(point(&fr[p.g], z, p).1);
        for e in &self.eqs {
            let (a, b, d) = match *e {
                Eq::Diff { a, b, .. } => (off(&a), off(&b), 0.0),
                Eq::Dist { a, b, d } | Eq::CircleCircle { a, b, d } => (off(&a), off(&b), z[d]),
                Eq::Proj { p, base, d, .. } | Eq::LineDist { p, base, d, .. } => {
                    (off(&p), off(&base), z[d])
                }
                Eq::Mid { p, q, base, .. } => (off(&p).max(off(&q)), off(&base), 0.0),
                Eq::Radial { p, c, .. } => (off(&p), off(&c), 0.0),
                Eq::CircleDist { p, c, d, .. } => (off(&p), off(&c), z[d]),
                Eq::LineCircle { base, c, d, .. } => (off(&base), off(&c), z[d]),
                Eq::Turn { screw, a, .. } => match screw {
                    Some(s) => (off(&s.p1), off(&s.p2), z[a]),
                    None => (0.0, 0.0, 0.0),
                },
                Eq::Dim { v, .. } => (0.0, 0.0, z[v]),
                Eq::SameDim { .. } | Eq::Angle { .. } | Eq::Tilt { .. } | Eq::Dot { .. } => {
                    (0.0, 0.0, 0.0)
                }
            };
            l = l.max(a).max(b).max(d.abs());
        }
        l
    }

    /// Picks each sign choice from the start configuration.
    fn choose_sides(&mut self) {
        self.update_frames();
        let sign = |v: f64| if v < 0.0 { -1.0 } else { 1.0 };
        for e in 0..self.m {
            let z = &self.z;
            let fr = &self.frames;
            self.side[e] = match self.eqs[e] {
                Eq::Tilt { u, v, sense, .. } => {
                    if sense != 0.0 {
                        sense
                    } else {
                        sign(dot(dir(&fr[u.g], z, &u), dir(&fr[v.g], z, &v)))
                    }
                }
                Eq::LineCircle { base, u, c, n, .. } => {
                    let (pb, _) = point(&fr[base.g], z, &base);
                    let (pc, _) = point(&fr[c.g], z, &c);
                    let (uu, nn) = (dir(&fr[u.g], z, &u), dir(&fr[n.g], z, &n));
                    sign(dot(sub(pc, pb), cross(nn, uu)))
                }
                Eq::CircleCircle { a, b, d } => {
                    let (ca, _) = point(&fr[a.g], z, &a);
                    let (cb, _) = point(&fr[b.g], z, &b);
                    let (ra, rb) = (fr[a.g].dim, fr[b.g].dim);
                    let dist = norm(sub(ca, cb));
                    let outside = dist - ra - rb - z[d];
                    let nested = (ra - rb).abs() - dist - z[d];
                    if outside.abs() <= nested.abs() {
                        0.0
                    } else if ra >= rb {
                        1.0
                    } else {
                        -1.0
                    }
                }
                _ => 1.0,
            };
        }
    }

    /// One equation's value and its gradient with respect to its frames' (origin, rotation
    /// increment, dimension), by side ([`Eq::geoms`]).
    #[inline]
    fn eval(&self, e: usize, grad: bool) -> (f64, [G7; 3]) {
        let z = &self.z;
        let fr = &self.frames;
        let mut gr = [[0.0; 7]; 3];
        let side = self.side[e];
        let v = match self.eqs[e] {
            Eq::Diff { a, b, k } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                if grad {
                    let mut gp = [0.0; 3];
                    gp[k] = 1.0;
                    push_point(&mut gr[0], fa, qa, a.m, gp);
                    push_point(&mut gr[1], fb, qb, b.m, scale(gp, -1.0));
                }
                pa[k] - pb[k]
            }
            Eq::Dist { a, b, d } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                let w = sub(pa, pb);
                let len = norm(w);
                if grad && len > 0.0 {
                    let gp = scale(w, 1.0 / len);
                    push_point(&mut gr[0], fa, qa, a.m, gp);
                    push_point(&mut gr[1], fb, qb, b.m, scale(gp, -1.0));
                }
                len - z[d].abs()
            }
            Eq::Proj { p, base, e, d } => {
                let (fp, fb) = (&fr[p.g], &fr[base.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pb, qb) = point(fb, z, &base);
                let ev = dir(&fr[e.g], z, &e);
                let w = sub(pp, pb);
                if grad {
                    push_point(&mut gr[0], fp, qp, p.m, ev);
                    push_point(&mut gr[1], fb, qb, base.m, scale(ev, -1.0));
                    push_dir(&mut gr[2], ev, w);
                }
                dot(w, ev) - z[d]
            }
            Eq::Mid { p, q, base, e } => {
                let (fp, fq, fb) = (&fr[p.g], &fr[q.g], &fr[base.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pq, qq) = point(fq, z, &q);
                let (pb, qb) = point(fb, z, &base);
                let ev = dir(fb, z, &e);
                let w = sub(scale(add(pp, pq), 0.5), pb);
                if grad {
                    let half = scale(ev, 0.5);
                    push_point(&mut gr[0], fp, qp, p.m, half);
                    push_point(&mut gr[1], fq, qq, q.m, half);
                    push_point(&mut gr[2], fb, qb, base.m, scale(ev, -1.0));
                    push_dir(&mut gr[2], ev, w);
                }
                dot(w, ev)
            }
            Eq::LineDist { p, base, u, d } => {
                let (fp, fb) = (&fr[p.g], &fr[base.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pb, qb) = point(fb, z, &base);
                let uu = dir(fb, z, &u);
                let w = sub(pp, pb);
                let k = cross(uu, w);
                let rho = norm(k);
                if grad && rho > 0.0 {
                    let kh = scale(k, 1.0 / rho);
                    let gp = cross(kh, uu);
                    push_point(&mut gr[0], fp, qp, p.m, gp);
                    push_point(&mut gr[1], fb, qb, base.m, scale(gp, -1.0));
                    push_dir(&mut gr[1], uu, cross(w, kh));
                }
                rho - z[d]
            }
            Eq::Radial { p, c, n } => {
                let (fp, fc) = (&fr[p.g], &fr[c.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pc, qc) = point(fc, z, &c);
                let nn = dir(fc, z, &n);
                let w = sub(pp, pc);
                let k = cross(nn, w);
                let rho = norm(k);
                if grad {
                    if rho > 0.0 {
                        let kh = scale(k, 1.0 / rho);
                        let gp = cross(kh, nn);
                        push_point(&mut gr[0], fp, qp, p.m, gp);
                        push_point(&mut gr[1], fc, qc, c.m, scale(gp, -1.0));
                        push_dir(&mut gr[1], nn, cross(w, kh));
                    }
                    gr[1][6] -= 1.0;
                }
                rho - fc.dim
            }
            Eq::CircleDist { p, c, n, d } => {
                let (fp, fc) = (&fr[p.g], &fr[c.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pc, qc) = point(fc, z, &c);
                let nn = dir(fc, z, &n);
                let w = sub(pp, pc);
                let h = dot(nn, w);
                let k = cross(nn, w);
                let rho = norm(k);
                let t = rho - fc.dim;
                let q = h.hypot(t);
                if grad && q > 0.0 {
                    let (a, b) = (h / q, t / q);
                    let (mut gp, mut gn) = (scale(nn, a), scale(w, a));
                    if rho > 0.0 {
                        let kh = scale(k, 1.0 / rho);
                        gp = add(gp, scale(cross(kh, nn), b));
                        gn = add(gn, scale(cross(w, kh), b));
                    }
                    push_point(&mut gr[0], fp, qp, p.m, gp);
                    push_point(&mut gr[1], fc, qc, c.m, scale(gp, -1.0));
                    push_dir(&mut gr[1], nn, gn);
                    gr[1][6] -= b;
                }
                q - z[d]
            }
            Eq::LineCircle { base, u, c, n, d } => {
                let (fl, fc) = (&fr[base.g], &fr[c.g]);
                let (pb, qb) = point(fl, z, &base);
                let (pc, qc) = point(fc, z, &c);
                let (uu, nn) = (dir(fl, z, &u), dir(fc, z, &n));
                let w = sub(pc, pb);
                let m = cross(nn, uu);
                if grad {
                    let gw = scale(m, side);
                    push_point(&mut gr[1], fc, qc, c.m, gw);
                    push_point(&mut gr[0], fl, qb, base.m, scale(gw, -1.0));
                    push_dir(&mut gr[0], uu, scale(cross(w, nn), side));
                    push_dir(&mut gr[1], nn, scale(cross(uu, w), side));
                    gr[1][6] -= 1.0;
                }
                side * dot(w, m) - fc.dim - z[d]
            }
            Eq::CircleCircle { a, b, d } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                let w = sub(pa, pb);
                let len = norm(w);
                // External: len - ra - rb - d; nested: side (ra - rb) - len - d.
                let sgn = if side == 0.0 { 1.0 } else { -1.0 };
                if grad {
                    if len > 0.0 {
                        let gp = scale(w, sgn / len);
                        push_point(&mut gr[0], fa, qa, a.m, gp);
                        push_point(&mut gr[1], fb, qb, b.m, scale(gp, -1.0));
                    }
                    if side == 0.0 {
                        gr[0][6] -= 1.0;
                        gr[1][6] -= 1.0;
                    } else {
                        gr[0][6] += side;
                        gr[1][6] -= side;
                    }
                }
                if side == 0.0 {
                    len - fa.dim - fb.dim - z[d]
                } else {
                    side * (fa.dim - fb.dim) - len - z[d]
                }
            }
            Eq::Angle { u, v, a } => {
                let (uu, vv) = (dir(&fr[u.g], z, &u), dir(&fr[v.g], z, &v));
                let c = dot(uu, vv);
                let w = cross(uu, vv);
                let s = norm(w);
                if grad {
                    let r2 = s * s + c * c;
                    let wh = unit(w);
                    let gu = scale(sub(scale(cross(vv, wh), c), scale(vv, s)), 1.0 / r2);
                    let gv = scale(sub(scale(cross(wh, uu), c), scale(uu, s)), 1.0 / r2);
                    push_dir(&mut gr[0], uu, gu);
                    push_dir(&mut gr[1], vv, gv);
                }
                s.atan2(c) - z[a]
            }
            Eq::Tilt { u, e, v, .. } => {
                let fu = &fr[u.g];
                let (uu, ev, vv) = (dir(fu, z, &u), dir(fu, z, &e), dir(&fr[v.g], z, &v));
                let (y, x) = (dot(vv, ev), side * dot(vv, uu));
                if grad {
                    let r2 = x * x + y * y;
                    push_dir(&mut gr[0], ev, scale(vv, x / r2));
                    push_dir(&mut gr[0], uu, scale(vv, -y * side / r2));
                    let gv = sub(scale(ev, x), scale(uu, y * side));
                    push_dir(&mut gr[1], vv, scale(gv, 1.0 / r2));
                }
                y.atan2(x)
            }
            Eq::Dot { u, v } => {
                let (uu, vv) = (dir(&fr[u.g], z, &u), dir(&fr[v.g], z, &v));
                if grad {
                    push_dir(&mut gr[0], uu, vv);
                    push_dir(&mut gr[1], vv, uu);
                }
                dot(uu, vv)
            }
            Eq::Turn {
                x1,
                y1,
                x2,
                a,
                screw,
            } => {
                let (f1, f2) = (&fr[x1.g], &fr[x2.g]);
                let (ux, uy, vx) = (dir(f1, z, &x1), dir(f1, z, &y1), dir(f2, z, &x2));
                let (s, c) = (dot(vx, uy), dot(vx, ux));
                let target = match screw {
                    None => z[a],
                    Some(sc) => {
                        let k = TAU / z[a];
                        let (p1, q1) = point(f1, z, &sc.p1);
                        let (p2, q2) = point(f2, z, &sc.p2);
                        let z1 = dir(f1, z, &sc.z1);
                        let w = sub(p2, p1);
                        if grad {
                            // The value falls as the target grows.
                            push_dir(&mut gr[0], z1, scale(w, -k));
                            push_point(&mut gr[1], f2, q2, sc.p2.m, scale(z1, -k));
                            push_point(&mut gr[0], f1, q1, sc.p1.m, scale(z1, k));
                        }
                        k * dot(z1, w)
                    }
                };
                if grad {
                    let r2 = s * s + c * c;
                    push_dir(&mut gr[0], ux, scale(vx, -s / r2));
                    push_dir(&mut gr[0], uy, scale(vx, c / r2));
                    push_dir(
                        &mut gr[1],
                        vx,
                        scale(sub(scale(uy, c), scale(ux, s)), 1.0 / r2),
                    );
                }
                let (st, ct) = target.sin_cos();
                (s * ct - c * st).atan2(c * ct + s * st)
            }
            Eq::Dim { g, v } => {
                if grad {
                    gr[0][6] = 1.0;
                }
                fr[g].dim - z[v]
            }
            Eq::SameDim { a, b } => {
                if grad {
                    gr[0][6] = 1.0;
                    gr[1][6] = -1.0;
                }
                fr[a].dim - fr[b].dim
            }
        };
        (v, gr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tiny deterministic generator (xorshift), so the random configurations are the same
    /// each run.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    /// Every constraint of the language in 3d on free geoms of every kind, so that every
    /// equation kind, every kind of unknown and every feature is read.
    const EVERY: &str = "space 3d;
        param pitch = 0.7;
        param a = 50 deg;
        fixed point O = (0, 0, 0);
        point P = (1, 2, 0.5);
        point Q = (-1, 0.5, 2);
        vector v = (1, 0.2, 0.3);
        line L = (0.2, 0.1, 0.3) -> (1.1, 1.5, 0.2);
        segment S = (-1, 0.5, 0.1) -> (2, 1.2, -0.4);
        segment T = (0, -1, 1) -> (1, -2, 0.5);
        circle C = center (3, 3, 1) radius 1 normal (0.1, 0.2, 1);
        circle D = center (-3, 3, 0) radius 0.5 normal (1, 0.3, 0.2);
        plane E = normal (0.2, 0.1, 1) offset 0.4;
        plane F = point (1, 1, 1) normal (1, 0.5, -0.2);
        body B at (1, 2, 3) rotated 0.3 about (1, 1, 0) {
            point p = (0.5, -0.2, 0.1);
            vector w = (0.3, 1, 0.2);
            marker k = (1, 0, 0) z (0, 0, 1) x (1, 0, 0);
            marker j = (0, 1, 0) z (0, 1, 0) x (0, 0, 1);
        }
        body G at (-1, 0, 2) rotated 1.2 about (0, 1, 1) {
            point p = (0.3, 0.4, -0.5);
            marker k = (0.2, 0.1, 0) z (1, 1, 0) x (1, -1, 0);
            marker j = (0, 0, 1) z (0, 0, 1) x (0, 1, 0);
        }
        coincident(P, B.p);
        spherical(G.p, S.end);
        distance(P, Q) = 2;
        distance(Q, L) = 1.5;
        distance(B.p, E) = -0.3;
        distance(G.p, C) = 0.4;
        distance(L, D) = 0.2;
        distance(C, D) = 0.3;
        distance(P, S) = 0;
        on(Q, S);
        on(P, F);
        on(T.start, C);
        tangent(S, C);
        tangent(C, D);
        angle(v, L) = a;
        angle(S, T) = 0;
        angle(v, E) = 180 deg;
        parallel(B.w, T);
        parallel(C.normal, F);
        perpendicular(L.dir, B.k.x);
        length(S) = 3;
        radius(C) = 1.2;
        equal(S, T);
        equal(C, D);
        midpoint(Q, T);
        symmetric(P, G.p, E);
        in_line(B.k, G.k);
        in_plane(P, B.j);
        parallel_z(B.k, G.k);
        offset_z(B.j, G.j) = 40 deg;
        offset_x(B.k, G.k) = a;
        helical(B.j, G.j) = pitch;
        revolute(B.k, G.j);
        prismatic(G.k, B.j);
        cylindrical(B.k, G.j);
        planar(G.j, B.k);
        weld(B.j, G.k);";

    /// The analytic Jacobian is the derivative of the equations: on random configurations of
    /// a model with every equation kind (random positions, directions, rotations, dimensions
    /// and offsets, and random rotation increments, so that the left Jacobian is exercised
    /// away from the identity), central differences of the equilibrated residual agree with it
    /// column by column.
    #[test]
    fn the_jacobian_of_every_equation_kind_is_its_derivative() {
        let (_, model, diags) = gcs_lang::load("every.gcs", EVERY.as_bytes());
        let model = model.unwrap_or_else(|| panic!("{diags:?}"));
        let Baseline3 {
            eq: mut b,
            mut solver,
        } = Baseline3::with_linear(&model, Linear::Dense).expect("baseline");
        let (n, m) = (b.n, b.m);
        // Every equation kind is there.
        let mut kinds: Vec<String> = b
            .eqs
            .iter()
            .map(|e| {
                format!("{e:?}")
                    .split([' ', '{'])
                    .next()
                    .unwrap_or("")
                    .to_string()
            })
            .collect();
        kinds.sort();
        kinds.dedup();
        assert_eq!(kinds.len(), 15, "{kinds:?}");
        let params = model.default_params();
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut checked = 0;
        for trial in 0..40 {
            let mut x = vec![0.0; n];
            for g in &b.geoms {
                for v in &mut x[g.first..g.first + g.count] {
                    *v = rng.range(-3.0, 3.0);
                }
                let at = g.rot_at();
                match g.rot {
                    Rot::Full => {
                        for v in &mut x[at..at + 3] {
                            *v = rng.range(-1.8, 1.8);
                        }
                    }
                    Rot::AxisX | Rot::AxisZ => {
                        x[at] = rng.range(-PI, PI);
                        x[at + 1] = rng.range(-1.4, 1.4);
                    }
                    Rot::Fixed => {}
                }
                if g.dim {
                    x[g.dim_at()] = rng.range(0.5, 2.0);
                }
            }
            b.load(&params, &x);
            for g in &b.geoms {
                for c in g.rot_at()..g.rot_at() + g.rot_cols() {
                    b.z[c] = rng.range(-1.0, 1.0);
                }
            }
            b.choose_sides();
            solver.equilibrate(b.length_scale());
            solver.jacobian(&mut b);
            let analytic = solver.jacobian_values().to_vec();
            for c in 0..n {
                let (x, h) = (b.z[c], 1e-6);
                b.z[c] = x + h;
                solver.residual(&mut b);
                let plus = solver.trial_values().to_vec();
                b.z[c] = x - h;
                solver.residual(&mut b);
                let minus = solver.trial_values().to_vec();
                b.z[c] = x;
                for e in 0..m {
                    let step = plus[e] - minus[e];
                    if step.abs() > 1.0 {
                        // An angle wrapped between the two points.
                        continue;
                    }
                    let numeric = step / (2.0 * h) * solver.column_scale(c);
                    let exact = analytic[e * n + c];
                    assert!(
                        (numeric - exact).abs() <= 1e-6 * (1.0 + exact.abs()),
                        "trial {trial}, equation {e} ({:?}), unknown {c}: {exact} analytic, \
                         {numeric} numeric",
                        b.eqs[e]
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 40 * n * m / 2, "{checked} entries checked");
    }

    /// A rotation's increment and its left Jacobian: `exp(r + d) = exp(J_l(r) d) exp(r)` to
    /// first order, on both sides of the series' threshold; Rodrigues' rotation is orthonormal.
    #[test]
    fn the_left_jacobian_is_the_derivative_of_the_exponential() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for t in [1e-9, 1e-3, 0.009, 0.011, 0.5, 2.0, 3.1] {
            let axis = unit([
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ]);
            let r = scale(axis, t);
            let m = exp_times(r, &IDENTITY);
            for i in 0..3 {
                for j in 0..3 {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((dot(m[i], m[j]) - want).abs() <= 1e-15, "t = {t}");
                }
            }
            for k in 0..3 {
                let mut d = [0.0; 3];
                d[k] = 1e-6;
                let (mp, mm) = (
                    exp_times(add(r, d), &IDENTITY),
                    exp_times(sub(r, d), &IDENTITY),
                );
                let w = left_jacobian(r, {
                    let mut e = [0.0; 3];
                    e[k] = 1.0;
                    e
                });
                for c in 0..3 {
                    // d(m e_c) = w × (m e_c)
                    let numeric = scale(sub(mp[c], mm[c]), 0.5e6);
                    let exact = cross(w, m[c]);
                    assert!(
                        norm(sub(numeric, exact)) <= 1e-8,
                        "t = {t}, k = {k}: {numeric:?} numeric, {exact:?} analytic"
                    );
                }
            }
        }
    }
}
