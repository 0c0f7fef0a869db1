//! The residuals of a 3d model: points and vectors of three coordinates, angles unsigned.
//!
//! Every residual is a length or an angle in radians, measured from the constraint's meaning in
//! LANGUAGE.md; a constraint made of several conditions (a joint, a tangency) reports the
//! largest of their errors. Where the contract leaves the 3d meaning open, the definition used
//! is written on the function that measures it:
//!
//! - a point's distance from a circle is its distance from the nearest point of the circle
//!   ([`point_circle`]);
//! - a line's or a circle's distance from a circle, and so their tangency, is the 2d one in the
//!   circle's plane, which they must lie in ([`line_circle`], [`circle_circle`]);
//! - an angle is unsigned: a target `a` is met by the directions at `|a|` (wrapped to
//!   `[0, pi]`), as a turn by `a` about an axis is a turn by `-a` about the opposite one
//!   ([`unsigned_angle_off`]);
//! - two axes are parallel in either sense ([`parallel_off`]), as the sketch may have them
//!   opposite; but a weld's z axes in the same sense, its frames being one.

use crate::solution::ByName;
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::model::{Constraint, GeomId, GeomKind, Part};
use gcs_lang::Model;
use std::f64::consts::PI;

type V = [f64; 3];

const NAN3: V = [f64::NAN; 3];

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
fn unit(a: V) -> V {
    scale(a, 1.0 / norm(a))
}
fn midpoint(a: V, b: V) -> V {
    scale(add(a, b), 0.5)
}

/// How far the angle whose cosine and sine are proportional to `c` and `s` is from `target`,
/// in radians (at most pi): the angle is turned back by the target's sine and cosine and
/// measured with `atan2`, which wraps it to (-pi, pi]. Turning rather than subtracting the
/// target from the measured angle keeps the residual exact for any finite target: `1e300 - a`
/// is `1e300` whatever `a` is.
fn turn_off(c: f64, s: f64, target: f64) -> f64 {
    let (st, ct) = target.sin_cos();
    (s * ct - c * st).atan2(c * ct + s * st).abs()
}

/// How far the unsigned angle between `u` and `v` (in `[0, pi]`, `atan2(|u×v|, u·v)`) is from
/// `target`. The directions at angle `a` from `u` are those at `-a` and at `a + 2 pi`, so the
/// residual is the smaller of the turns to `target` and to `-target`: `| angle - |wrap(target)| |`
/// with `wrap` to (-pi, pi], and exactly `|angle - target|` for a target in `[0, pi]`.
fn unsigned_angle_off(u: V, v: V, target: f64) -> f64 {
    let (c, s) = (dot(u, v), norm(cross(u, v)));
    turn_off(c, s, target).min(turn_off(c, s, -target))
}

/// How far `u` and `v` are from parallel, in either sense: the smaller of their angle and its
/// supplement, `atan2(|u×v|, |u·v|)`.
fn parallel_off(u: V, v: V) -> f64 {
    norm(cross(u, v)).atan2(dot(u, v).abs())
}

/// How far `u` and `v` are from perpendicular: their angle's deviation from pi/2,
/// `atan2(|u·v|, |u×v|)`.
fn perpendicular_off(u: V, v: V) -> f64 {
    dot(u, v).abs().atan2(norm(cross(u, v)))
}

/// How far the angle from `x1` to `x2` counter-clockwise about `z` (right-handed: a quarter
/// turn takes `x1` to `z × x1`) is from `target`. `x1` is taken perpendicular to `z` (a
/// marker's axes are orthogonal); `x2` is measured by its projection on the plane normal to
/// `z`, its components along `x1` and `z × x1`.
fn turn_about_off(z: V, x1: V, x2: V, target: f64) -> f64 {
    turn_off(dot(x1, x2), dot(z, cross(x1, x2)), target)
}

/// The largest of a constraint's errors, NaN if any is: `f64::max` drops a NaN, and a value
/// missing must fail, not pass.
fn largest(errors: &[f64]) -> f64 {
    (errors.iter()).fold(0.0, |m: f64, &e| {
        if m.is_nan() || e.is_nan() {
            f64::NAN
        } else {
            m.max(e)
        }
    })
}

/// The distance from `p` to the line through `base` along the unit `dir`.
fn point_line(p: V, base: V, dir: V) -> f64 {
    norm(cross(dir, sub(p, base)))
}

/// The distance from `p` to the circle of centre `c`, unit normal `n` and radius `r`: to its
/// nearest point. With `h` the height of `p` above the circle's plane and `rho` its distance
/// from the circle's axis, it is `hypot(h, rho - r)` (a point on the axis is `hypot(h, r)` from
/// every point of the circle).
fn point_circle(p: V, (c, n, r): (V, V, f64)) -> f64 {
    let d = sub(p, c);
    dot(n, d).hypot(norm(cross(n, d)) - r)
}

/// How far a line is from lying in a circle's plane at `gap` outside the circle: the 2d
/// line-circle distance (the centre's distance from the line less the radius), measured in the
/// circle's plane. A line that touches a circle in 3d without lying in its plane crosses it: it
/// is not tangent, and has no distance from it in this sense; the residual is then the larger
/// of the line's tilt out of the plane (radians), the height above the plane of the foot of the
/// centre on the line, and the in-plane gap's error.
fn line_circle((base, dir): (V, V), (c, n, r): (V, V, f64), gap: f64) -> f64 {
    let foot = add(base, scale(dir, dot(dir, sub(c, base))));
    let tilt = perpendicular_off(dir, n);
    let height = dot(n, sub(foot, c)).abs();
    let off = (norm(cross(dir, sub(c, base))) - r - gap).abs();
    tilt.max(height).max(off)
}

/// How far two circles are from lying in one plane at `gap` from each other: the 2d
/// circle-circle distance in their common plane (outside each other, `d - r1 - r2`, or one
/// inside the other, `|r1 - r2| - d`, whichever is nearer `gap`, as the 2d verifier measures
/// it). Circles in different planes have no distance in this sense; the residual is the larger
/// of the angle between their planes (either sense of the normals), the height of either centre
/// above the other's plane, and the in-plane gap's error.
fn circle_circle((c1, n1, r1): (V, V, f64), (c2, n2, r2): (V, V, f64), gap: f64) -> f64 {
    let tilt = parallel_off(n1, n2);
    let d = sub(c2, c1);
    let height = dot(n1, d).abs().max(dot(n2, d).abs());
    let outside = norm(d) - r1 - r2;
    let nested = (r1 - r2).abs() - norm(d);
    let off = (outside - gap).abs().min((nested - gap).abs());
    tilt.max(height).max(off)
}

/// Named lookups that yield NaN for anything missing (or with fewer than three coordinates),
/// so a missing value is a failure, not a pass.
struct Look<'a> {
    model: &'a Model,
    s: &'a ByName<'a>,
}

impl Look<'_> {
    fn p(&self, name: &str) -> V {
        match self.s.point(name) {
            Some([x, y, z, ..]) => [*x, *y, *z],
            _ => NAN3,
        }
    }
    fn v(&self, name: &str) -> V {
        match self.s.vector(name) {
            Some([x, y, z, ..]) => unit([*x, *y, *z]),
            _ => NAN3,
        }
    }
    fn x(&self, name: &str) -> f64 {
        self.s.scalar(name).unwrap_or(f64::NAN)
    }
    fn name(&self, g: GeomId) -> &str {
        &self.model.geoms[g].name
    }
    /// The point that part `part` of `g` names, NaN if `g` has no such part.
    fn part_p(&self, g: GeomId, part: Part) -> V {
        self.model
            .part(g, part)
            .map_or(NAN3, |q| self.p(self.name(q)))
    }
    /// The unit vector that part `part` of `g` names, NaN if `g` has no such part.
    fn part_v(&self, g: GeomId, part: Part) -> V {
        self.model
            .part(g, part)
            .map_or(NAN3, |q| self.v(self.name(q)))
    }
    /// A point argument: a point or a marker (its point) by its name; a circle by its centre.
    fn point_arg(&self, g: GeomId) -> V {
        match self.model.geoms[g].kind {
            GeomKind::Circle => self.part_p(g, Part::Center),
            _ => self.p(self.name(g)),
        }
    }
    /// A direction argument: a vector (marker axes included), the direction of a line or
    /// segment, the normal of a plane; a marker stands for its z axis.
    fn dir_arg(&self, g: GeomId) -> V {
        match self.model.geoms[g].kind {
            GeomKind::Vector => self.v(self.name(g)),
            GeomKind::Line | GeomKind::Segment => self.part_v(g, Part::Dir),
            GeomKind::Plane => self.part_v(g, Part::Normal),
            GeomKind::Marker => self.part_v(g, Part::AxisZ),
            _ => NAN3,
        }
    }
    /// A line argument: (a point on it, its unit direction). A line by its solved base point,
    /// a segment by its start; a marker is the line through its point along its z axis.
    fn line_arg(&self, g: GeomId) -> (V, V) {
        match self.model.geoms[g].kind {
            GeomKind::Line => (self.part_p(g, Part::BasePoint), self.part_v(g, Part::Dir)),
            GeomKind::Segment => (self.part_p(g, Part::Start), self.part_v(g, Part::Dir)),
            GeomKind::Marker => (self.p(self.name(g)), self.part_v(g, Part::AxisZ)),
            _ => (NAN3, NAN3),
        }
    }
    /// A circle argument: (centre, unit normal, radius).
    fn circle_arg(&self, g: GeomId) -> (V, V, f64) {
        if self.model.geoms[g].kind != GeomKind::Circle {
            return (NAN3, NAN3, f64::NAN);
        }
        (
            self.part_p(g, Part::Center),
            self.part_v(g, Part::Normal),
            self.x(&format!("{}.radius", self.name(g))),
        )
    }
    /// A plane argument: (unit normal, offset); it holds the points `p` with
    /// `normal · p = offset`.
    fn plane_arg(&self, g: GeomId) -> (V, f64) {
        if self.model.geoms[g].kind != GeomKind::Plane {
            return (NAN3, f64::NAN);
        }
        (
            self.part_v(g, Part::Normal),
            self.x(&format!("{}.offset", self.name(g))),
        )
    }
    /// A segment's ends.
    fn ends(&self, g: GeomId) -> (V, V) {
        (self.part_p(g, Part::Start), self.part_p(g, Part::End))
    }
    /// A dimension: a segment's length (from its ends), a circle's radius.
    fn dim(&self, g: GeomId) -> f64 {
        match self.model.geoms[g].kind {
            GeomKind::Segment => {
                let (a, b) = self.ends(g);
                norm(sub(b, a))
            }
            GeomKind::Circle => self.circle_arg(g).2,
            _ => f64::NAN,
        }
    }
    /// A marker's (z, x) axes.
    fn axes(&self, g: GeomId) -> (V, V) {
        (self.part_v(g, Part::AxisZ), self.part_v(g, Part::AxisX))
    }
}

/// The residual of constraint `c` of a 3d model on the solution's values `s`, its value
/// evaluated: how far from satisfied, as a length or in radians; NaN when a value it needs is
/// missing, and for `horizontal` and `vertical`, which are 2d only.
pub(super) fn residual(model: &Model, s: &ByName<'_>, c: &Constraint, value: f64) -> f64 {
    let look = Look { model, s };
    let kind = |g: GeomId| model.geoms[g].kind;
    let (a, b) = match (c.args.first(), c.args.get(1)) {
        (Some(&a), Some(&b)) => (a, b),
        (Some(&a), None) => (a, a),
        _ => return f64::NAN,
    };
    // m1's point on the line through m2's point along m2's z axis / in the plane through it
    // normal to it.
    let in_line = || point_line(look.point_arg(a), look.point_arg(b), look.axes(b).0);
    let in_plane = || {
        let off = sub(look.point_arg(a), look.point_arg(b));
        dot(look.axes(b).0, off).abs()
    };
    let parallel_z = || parallel_off(look.axes(a).0, look.axes(b).0);
    // The angle from m1's x to m2's x about m1's z, off `target`, with the z axes parallel.
    let offset_x = |target: f64| {
        let ((z1, x1), (z2, x2)) = (look.axes(a), look.axes(b));
        parallel_off(z1, z2).max(turn_about_off(z1, x1, x2, target))
    };
    match c.kind {
        K::Coincident | K::Spherical => norm(sub(look.point_arg(a), look.point_arg(b))),
        K::Revolute => norm(sub(look.point_arg(a), look.point_arg(b))).max(parallel_z()),
        K::Distance => match (kind(a), kind(b)) {
            (GeomKind::Point | GeomKind::Marker, GeomKind::Point | GeomKind::Marker) => {
                (norm(sub(look.point_arg(a), look.point_arg(b))) - value.abs()).abs()
            }
            // Unsigned in 3d.
            (_, GeomKind::Line | GeomKind::Segment) => {
                let (base, dir) = look.line_arg(b);
                (point_line(look.point_arg(a), base, dir) - value).abs()
            }
            // Signed: normal · p - offset.
            (_, GeomKind::Plane) => {
                let (n, offset) = look.plane_arg(b);
                (dot(n, look.point_arg(a)) - offset - value).abs()
            }
            (GeomKind::Point | GeomKind::Marker, GeomKind::Circle) => {
                (point_circle(look.point_arg(a), look.circle_arg(b)) - value).abs()
            }
            (GeomKind::Line | GeomKind::Segment, GeomKind::Circle) => {
                line_circle(look.line_arg(a), look.circle_arg(b), value)
            }
            (GeomKind::Circle, GeomKind::Circle) => {
                circle_circle(look.circle_arg(a), look.circle_arg(b), value)
            }
            _ => f64::NAN,
        },
        K::On => match kind(b) {
            GeomKind::Line | GeomKind::Segment => {
                let (base, dir) = look.line_arg(b);
                point_line(look.point_arg(a), base, dir)
            }
            GeomKind::Plane => {
                let (n, offset) = look.plane_arg(b);
                (dot(n, look.point_arg(a)) - offset).abs()
            }
            // In the circle's plane at its radius from the centre: the distance to the circle.
            GeomKind::Circle => point_circle(look.point_arg(a), look.circle_arg(b)),
            _ => f64::NAN,
        },
        // Distance 0, with the distances above: a line or circle in the circle's plane,
        // touching it.
        K::Tangent => match kind(a) {
            GeomKind::Line | GeomKind::Segment => {
                let (base, dir) = look.line_arg(a);
                let circle = look.circle_arg(b);
                let gap = line_circle((base, dir), circle, 0.0);
                // A segment's end on the circle must be the touching point, as in 2d: its
                // distance along the line from the centre's foot. The gap above is second
                // order in that distance, and hides it. "On" is within `JOINED`, as in 2d.
                let joints = if kind(a) == GeomKind::Segment {
                    let (start, end) = look.ends(a);
                    let (center, _, r) = circle;
                    [start, end]
                        .into_iter()
                        .filter(|&e| point_circle(e, circle) <= super::JOINED * (1.0 + r))
                        .map(|e| dot(dir, sub(e, center)).abs())
                        .fold(0.0f64, f64::max)
                } else {
                    0.0
                };
                gap.max(joints)
            }
            _ => circle_circle(look.circle_arg(a), look.circle_arg(b), 0.0),
        },
        K::Angle => unsigned_angle_off(look.dir_arg(a), look.dir_arg(b), value),
        K::Parallel => parallel_off(look.dir_arg(a), look.dir_arg(b)),
        K::Perpendicular => perpendicular_off(look.dir_arg(a), look.dir_arg(b)),
        // 2d only: the language refuses them in 3d.
        K::Horizontal | K::Vertical => f64::NAN,
        K::Length => (look.dim(a) - value).abs(),
        K::Radius => (look.circle_arg(a).2 - value).abs(),
        K::Equal => (look.dim(a) - look.dim(b)).abs(),
        K::Midpoint => {
            let (start, end) = look.ends(b);
            norm(sub(look.point_arg(a), midpoint(start, end)))
        }
        // Mirror images across a plane: their midpoint on the plane, and the segment between
        // them along its normal (its component across the normal is zero).
        K::Symmetric => {
            let (n, offset) = c
                .args
                .get(2)
                .map_or((NAN3, f64::NAN), |&q| look.plane_arg(q));
            let (p, q) = (look.point_arg(a), look.point_arg(b));
            let off = (dot(n, midpoint(p, q)) - offset).abs();
            let slant = norm(cross(n, sub(q, p)));
            off.max(slant)
        }
        K::InLine => in_line(),
        K::InPlane => in_plane(),
        K::ParallelZ => parallel_z(),
        K::OffsetZ => unsigned_angle_off(look.axes(a).0, look.axes(b).0, value),
        K::OffsetX => offset_x(value),
        // A screw: with s = (m2 - m1) · z1 the advance of m2 along m1's z axis, the angle from
        // m1's x to m2's x about m1's z is 2 pi s / pitch (modulo a turn). A zero pitch gives
        // no angle (the screw would turn without bound per unit advance): NaN, not a guess.
        K::Helical => {
            if value == 0.0 {
                return f64::NAN;
            }
            let advance = dot(look.axes(a).0, sub(look.point_arg(b), look.point_arg(a)));
            offset_x(2.0 * PI * advance / value)
        }
        K::Prismatic => in_line().max(offset_x(0.0)),
        K::Cylindrical => in_line().max(parallel_z()),
        K::Planar => in_plane().max(parallel_z()),
        // The frames coincide: the points, and offset_x(0) with the z axes in the same sense
        // (their angle, which is at least `parallel_off`'s: z axes opposite are pi off).
        K::Weld => {
            let ((z1, x1), (z2, x2)) = (look.axes(a), look.axes(b));
            largest(&[
                norm(sub(look.point_arg(a), look.point_arg(b))),
                norm(cross(z1, z2)).atan2(dot(z1, z2)),
                turn_about_off(z1, x1, x2, 0.0),
            ])
        }
    }
}
