//! The residuals of a 2d model: points and vectors of two coordinates, angles signed
//! counter-clockwise.

use crate::solution::ByName;
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::model::{Constraint, GeomKind};
use gcs_lang::Model;

type V = [f64; 2];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn cross(a: V, b: V) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn norm(a: V) -> f64 {
    a[0].hypot(a[1])
}
fn unit(a: V) -> V {
    let n = norm(a);
    [a[0] / n, a[1] / n]
}
/// How far the angle from `u` to `v` is from `target`, in radians (at most pi): the angle
/// between `v` and `u` turned by `target`. Turning by the target's sine and cosine, rather than
/// subtracting it from the measured angle, keeps the residual exact for any finite target:
/// `1e300 - a` is `1e300` whatever `a` is.
fn angle_off(u: V, v: V, target: f64) -> f64 {
    let (s, c) = target.sin_cos();
    let w = [u[0] * c - u[1] * s, u[0] * s + u[1] * c];
    cross(w, v).atan2(dot(w, v)).abs()
}

/// Named lookups that yield NaN for anything missing, so a missing value is a failure, not a
/// pass.
struct Look<'a> {
    model: &'a Model,
    s: &'a ByName<'a>,
}

impl Look<'_> {
    fn p(&self, name: &str) -> V {
        match self.s.point(name) {
            Some([x, y, ..]) => [*x, *y],
            _ => [f64::NAN, f64::NAN],
        }
    }
    fn v(&self, name: &str) -> V {
        match self.s.vector(name) {
            Some([x, y, ..]) => unit([*x, *y]),
            _ => [f64::NAN, f64::NAN],
        }
    }
    fn x(&self, name: &str) -> f64 {
        self.s.scalar(name).unwrap_or(f64::NAN)
    }
    /// A point argument: a point or marker by its name; a circle by its centre.
    fn point_arg(&self, g: gcs_lang::model::GeomId) -> V {
        let geom = &self.model.geoms[g];
        match geom.kind {
            GeomKind::Circle => self.p(&format!("{}.center", geom.name)),
            _ => self.p(&geom.name),
        }
    }
    /// A line argument: (a point on it, its unit direction).
    fn line_arg(&self, g: gcs_lang::model::GeomId) -> (V, V) {
        let n = &self.model.geoms[g].name;
        match self.model.geoms[g].kind {
            GeomKind::Line => (self.p(&format!("{n}.point")), self.v(&format!("{n}.dir"))),
            GeomKind::Segment => (self.p(&format!("{n}.start")), self.v(&format!("{n}.dir"))),
            GeomKind::Marker => (self.p(n), self.v(&format!("{n}.x"))),
            _ => ([f64::NAN; 2], [f64::NAN; 2]),
        }
    }
    /// A direction argument: a vector, or the direction of a line or segment.
    fn dir_arg(&self, g: gcs_lang::model::GeomId) -> V {
        let n = &self.model.geoms[g].name;
        match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Segment => self.v(&format!("{n}.dir")),
            _ => self.v(n),
        }
    }
    /// A dimension: a segment's length (from its ends), a circle's radius.
    fn dim(&self, g: gcs_lang::model::GeomId) -> f64 {
        let n = &self.model.geoms[g].name;
        match self.model.geoms[g].kind {
            GeomKind::Segment => norm(sub(
                self.p(&format!("{n}.end")),
                self.p(&format!("{n}.start")),
            )),
            GeomKind::Circle => self.x(&format!("{n}.radius")),
            _ => f64::NAN,
        }
    }
    fn circle_arg(&self, g: gcs_lang::model::GeomId) -> (V, f64) {
        let n = &self.model.geoms[g].name;
        (
            self.p(&format!("{n}.center")),
            self.x(&format!("{n}.radius")),
        )
    }
}

/// The residual of constraint `c` of a 2d model on the solution's values `s`, its value
/// evaluated: how far from satisfied, as a length or in radians; NaN when a value it needs is
/// missing.
pub(super) fn residual(model: &Model, s: &ByName<'_>, c: &Constraint, value: f64) -> f64 {
    let look = Look { model, s };
    let a = c.args.first().copied();
    let b = c.args.get(1).copied();
    let kind = |g: Option<gcs_lang::model::GeomId>| g.map(|g| model.geoms[g].kind);
    match (c.kind, a, b) {
        (K::Coincident | K::Spherical | K::Revolute, Some(a), Some(b)) => {
            norm(sub(look.point_arg(a), look.point_arg(b)))
        }
        (K::Distance, Some(a), Some(b)) => match (kind(Some(a)), kind(Some(b))) {
            (
                Some(GeomKind::Point | GeomKind::Marker),
                Some(GeomKind::Point | GeomKind::Marker),
            ) => (norm(sub(look.point_arg(a), look.point_arg(b))) - value.abs()).abs(),
            (_, Some(GeomKind::Line | GeomKind::Segment)) => {
                let (base, dir) = look.line_arg(b);
                (cross(dir, sub(look.point_arg(a), base)) - value).abs()
            }
            (Some(GeomKind::Point | GeomKind::Marker), Some(GeomKind::Circle)) => {
                let (c, r) = look.circle_arg(b);
                ((norm(sub(look.point_arg(a), c)) - r).abs() - value).abs()
            }
            (Some(GeomKind::Line | GeomKind::Segment), Some(GeomKind::Circle)) => {
                let (base, dir) = look.line_arg(a);
                let (c, r) = look.circle_arg(b);
                (cross(dir, sub(c, base)).abs() - r - value).abs()
            }
            (Some(GeomKind::Circle), Some(GeomKind::Circle)) => {
                let (c1, r1) = look.circle_arg(a);
                let (c2, r2) = look.circle_arg(b);
                let d = norm(sub(c1, c2));
                let outside = d - r1 - r2;
                let nested = (r1 - r2).abs() - d;
                (outside - value).abs().min((nested - value).abs())
            }
            _ => f64::NAN,
        },
        (K::On, Some(a), Some(b)) => match kind(Some(b)) {
            Some(GeomKind::Line | GeomKind::Segment) => {
                let (base, dir) = look.line_arg(b);
                cross(dir, sub(look.point_arg(a), base)).abs()
            }
            Some(GeomKind::Circle) => {
                let (c, r) = look.circle_arg(b);
                (norm(sub(look.point_arg(a), c)) - r).abs()
            }
            _ => f64::NAN,
        },
        (K::Tangent, Some(a), Some(b)) => match kind(Some(a)) {
            Some(GeomKind::Line | GeomKind::Segment) => {
                let (base, dir) = look.line_arg(a);
                let (c, r) = look.circle_arg(b);
                let gap = (cross(dir, sub(c, base)).abs() - r).abs();
                // A segment's end on the circle (a fillet's joint) must be the touching
                // point: its distance along the line from the centre's foot. The gap
                // above is second order in that distance, and hides it. "On" is within
                // `JOINED`: an end solved onto the circle is there to rounding, while a free
                // end `t` from the touching point is `t² / 2r` from the circle, and at a
                // looser bound a free end near it would count as a joint.
                let joints = if model.geoms[a].kind == GeomKind::Segment {
                    let n = &model.geoms[a].name;
                    [look.p(&format!("{n}.start")), look.p(&format!("{n}.end"))]
                        .into_iter()
                        .filter(|e| (norm(sub(*e, c)) - r).abs() <= super::JOINED * (1.0 + r))
                        .map(|e| dot(dir, sub(e, c)).abs())
                        .fold(0.0f64, f64::max)
                } else {
                    0.0
                };
                gap.max(joints)
            }
            _ => {
                let (c1, r1) = look.circle_arg(a);
                let (c2, r2) = look.circle_arg(b);
                let d = norm(sub(c1, c2));
                (d - r1 - r2).abs().min((d - (r1 - r2).abs()).abs())
            }
        },
        (K::Angle, Some(a), Some(b)) => {
            let (u, v) = (look.dir_arg(a), look.dir_arg(b));
            angle_off(u, v, value)
        }
        (K::Parallel, Some(a), Some(b)) => cross(look.dir_arg(a), look.dir_arg(b)).abs(),
        (K::Perpendicular, Some(a), Some(b)) => dot(look.dir_arg(a), look.dir_arg(b)).abs(),
        (K::Horizontal, Some(a), _) => look.dir_arg(a)[1].abs(),
        (K::Vertical, Some(a), _) => look.dir_arg(a)[0].abs(),
        (K::Length, Some(a), _) => {
            let n = &model.geoms[a].name;
            let len = norm(sub(
                look.p(&format!("{n}.end")),
                look.p(&format!("{n}.start")),
            ));
            (len - value).abs()
        }
        (K::Radius, Some(a), _) => (look.circle_arg(a).1 - value).abs(),
        (K::Equal, Some(a), Some(b)) => (look.dim(a) - look.dim(b)).abs(),
        (K::Midpoint, Some(p), Some(s)) => {
            let n = &model.geoms[s].name;
            let (a, b) = (look.p(&format!("{n}.start")), look.p(&format!("{n}.end")));
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            norm(sub(look.point_arg(p), m))
        }
        // Mirror images: the midpoint of the two on the line, and the segment between
        // them perpendicular to it.
        (K::Symmetric, Some(p), Some(q)) => {
            let (base, dir) = c
                .args
                .get(2)
                .map_or(([f64::NAN; 2], [f64::NAN; 2]), |&l| look.line_arg(l));
            let (x, y) = (look.point_arg(p), look.point_arg(q));
            let m = [(x[0] + y[0]) / 2.0, (x[1] + y[1]) / 2.0];
            let off = cross(dir, sub(m, base)).abs();
            let slant = dot(dir, sub(y, x)).abs();
            off.max(slant)
        }
        // The frames coincide: the points, and the x axes at angle 0 (offset_x(0)).
        (K::Weld, Some(a), Some(b)) => {
            let (na, nb) = (&model.geoms[a].name, &model.geoms[b].name);
            let (u, v) = (look.v(&format!("{na}.x")), look.v(&format!("{nb}.x")));
            let (off, turn) = (
                norm(sub(look.point_arg(a), look.point_arg(b))),
                angle_off(u, v, 0.0),
            );
            // NaN if either is: `f64::max` would drop it, and a value missing must fail.
            if off.is_nan() || turn.is_nan() {
                f64::NAN
            } else {
                off.max(turn)
            }
        }
        (K::InLine, Some(a), Some(b)) => {
            let (base, dir) = look.line_arg(b);
            cross(dir, sub(look.point_arg(a), base)).abs()
        }
        (K::OffsetX | K::Prismatic, Some(a), Some(b)) => {
            let (na, nb) = (&model.geoms[a].name, &model.geoms[b].name);
            let (u, v) = (look.v(&format!("{na}.x")), look.v(&format!("{nb}.x")));
            let target = if c.kind == K::OffsetX { value } else { 0.0 };
            let angle = angle_off(u, v, target);
            if c.kind == K::Prismatic {
                let (base, dir) = look.line_arg(b);
                angle.max(cross(dir, sub(look.point_arg(a), base)).abs())
            } else {
                angle
            }
        }
        _ => f64::NAN,
    }
}
