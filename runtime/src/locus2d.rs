//! Two-dimensional loci as types: point, line, ray, circle, and the conics that locus analysis
//! produces as the centres of a circle of variable radius (paper 000, section 4.2; paper 002,
//! RR-1).
//!
//! Conventions:
//! - A [`Line`] is directed; its unit normal [`Line::normal`] points to its **left**, and the
//!   signed distance of a point is positive to the left of the direction, as in the `.gcs`
//!   language.
//! - Every type keeps its fields private and is built by a constructor that checks its invariant
//!   (finite values, unit direction, radius ≥ 0, a non-degenerate conic) and returns `None`
//!   otherwise, so that an intersection never meets a NaN, a zero direction or a negative radius.
//! - Each curve has an *implicit* function (zero exactly on the locus, in length units), a
//!   *parametrisation* `at(t)` with its inverse `param_of(p)` (the parameter orders roots), and
//!   a *residual*: the distance of a point from the locus, exact for line, ray and circle and to
//!   first order (implicit value over gradient length) for the conics.
//!
//! Locus of centres: [`centres_line_circle`], [`centres_circle_circle`] and
//! [`centres_line_line`] give the locus of the centre `X` of a circle of radius `ρ` held at fixed
//! distances from two fixed loci. The distance conditions are written with signs so that one
//! formula covers tangency on either side, inside or outside:
//! - to a line `L`: `sd_L(X) = ρ + a`: the circle lies on the **left** of `L` with a gap `a`
//!   between its perimeter and `L` (`a = 0`: tangent). Pass [`Line::reversed`] for the right.
//! - to a point or circle with centre `C`: `|X - C| = ρ + b` ([`Sense::Plus`]: outside, e.g.
//!   externally tangent to a circle of radius `b`, or a point at distance `b` from the perimeter;
//!   `b < 0` when `C`'s circle lies inside the variable one) or `|X - C| = b - ρ`
//!   ([`Sense::Minus`]: the variable circle inside a circle of radius `b`).

use nalgebra::{Point2, Vector2};

use crate::num::is_finite;
use crate::tol;

/// A point of the plane.
pub type P2 = Point2<f64>;
/// A vector of the plane.
pub type V2 = Vector2<f64>;

/// The vector turned a quarter turn counter-clockwise (to the left).
#[inline]
pub fn perp(v: V2) -> V2 {
    V2::new(-v.y, v.x)
}

/// The 2d cross product `a.x b.y - a.y b.x` (the sine of the angle from `a` to `b` times the
/// lengths).
#[inline]
pub fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The midpoint of `a` and `b`: `(a + b) / 2`, the same bits whichever comes first. Exact
/// when `a` and `b` coincide; finite for every pair of points up to `f64::MAX / 2` in
/// magnitude (the solve paths keep coordinates far below: [`crate::num::MAX_MAGNITUDE`]).
#[inline]
pub fn midpoint(a: P2, b: P2) -> P2 {
    P2::from((a.coords + b.coords) * 0.5)
}

/// The point reflection of `p` through `centre`: `2 centre - p`, the point whose midpoint
/// with `p` is `centre` (a segment's other end, from one end and its midpoint). Exact when
/// `p` is `centre`.
#[inline]
pub fn reflect_through(p: P2, centre: P2) -> P2 {
    centre + (centre - p)
}

/// The mirror image of `p` across the line through `base` along unit `dir`: `p` moved twice
/// its signed distance from the line against the line's left normal. A point on the line is
/// its own image (to rounding: its signed distance is then a few ulps of the scale); the
/// image is as far from the line and from `base` as `p` is, and the segment from `p` to it is
/// perpendicular to the line with its midpoint on the line. `dir` must be a unit vector (a
/// [`Line`]'s is): no degenerate case remains.
#[inline]
pub fn mirror(base: P2, dir: V2, p: P2) -> P2 {
    let sd = cross(dir, p - base);
    p - perp(dir) * (2.0 * sd)
}

#[inline]
pub(crate) fn finite_p(p: P2) -> bool {
    is_finite(p.x) && is_finite(p.y)
}

#[inline]
fn unit(v: V2) -> Option<V2> {
    let n = v.norm();
    if n > 0.0 && is_finite(n) && is_finite(v.x) && is_finite(v.y) {
        Some(v / n)
    } else {
        None
    }
}

/// A directed line: a point on it and a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    point: P2,
    dir: V2,
}

impl Default for Line {
    /// The x axis: what a generated solver's store holds before a step writes a line there.
    fn default() -> Self {
        Line {
            point: P2::origin(),
            dir: V2::x(),
        }
    }
}

impl Line {
    /// The point of the line nearest to `p` (the foot of the perpendicular): least motion.
    #[inline]
    pub fn nearest(&self, p: P2) -> P2 {
        self.at(self.param_of(p))
    }

    /// The line through `point` along `dir` (normalised). `None` when `dir` is zero or a value
    /// is not finite.
    #[inline(always)]
    pub fn new(point: P2, dir: V2) -> Option<Self> {
        if !finite_p(point) {
            return None;
        }
        Some(Line {
            point,
            dir: unit(dir)?,
        })
    }

    /// The line from `a` towards `b`. `None` when they coincide or are not finite.
    #[inline]
    pub fn through(a: P2, b: P2) -> Option<Self> {
        Line::new(a, b - a)
    }

    /// The point the line was built with (parameter 0).
    #[inline]
    pub fn point(&self) -> P2 {
        self.point
    }

    /// The unit direction.
    #[inline]
    pub fn dir(&self) -> V2 {
        self.dir
    }

    /// The unit normal pointing to the left of the direction.
    #[inline]
    pub fn normal(&self) -> V2 {
        perp(self.dir)
    }

    /// The point at parameter `t` (signed length along the direction from [`Line::point`]).
    #[inline]
    pub fn at(&self, t: f64) -> P2 {
        self.point + self.dir * t
    }

    /// The parameter of the foot of `p` on the line.
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        self.dir.dot(&(p - self.point))
    }

    /// The signed distance of `p`: positive to the left of the direction. Also the implicit
    /// function of the line.
    #[inline]
    pub fn signed_distance(&self, p: P2) -> f64 {
        cross(self.dir, p - self.point)
    }

    /// The implicit function of the line, as every locus has one: [`Line::signed_distance`].
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        self.signed_distance(p)
    }

    /// The distance of `p` from the line (the residual).
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        self.signed_distance(p).abs()
    }

    /// The error of an outer iteration that closes on the line: [`Line::signed_distance`].
    #[inline]
    pub fn closing_error(&self, p: P2) -> f64 {
        self.signed_distance(p)
    }

    /// The parallel line displaced by `d` to the left (to the right for negative `d`), with the
    /// same direction. A non-finite `d` leaves the line unchanged.
    #[inline]
    pub fn offset(&self, d: f64) -> Line {
        let d = if d.is_finite() { d } else { 0.0 };
        Line {
            point: self.point + self.normal() * d,
            dir: self.dir,
        }
    }

    /// The mirror image of `p` across the line ([`mirror`]).
    #[inline]
    pub fn mirror(&self, p: P2) -> P2 {
        mirror(self.point, self.dir, p)
    }

    /// The same line with the opposite direction (left and right swap).
    #[inline]
    pub fn reversed(&self) -> Line {
        Line {
            point: self.point,
            dir: -self.dir,
        }
    }
}

/// A ray: an origin and a unit direction; the points at parameter `t ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    origin: P2,
    dir: V2,
}

impl Ray {
    /// The ray from `origin` along `dir` (normalised). `None` when `dir` is zero or a value is
    /// not finite.
    #[inline]
    pub fn new(origin: P2, dir: V2) -> Option<Self> {
        let l = Line::new(origin, dir)?;
        Some(Ray { origin, dir: l.dir })
    }

    /// The origin.
    pub fn origin(&self) -> P2 {
        self.origin
    }

    /// The unit direction.
    #[inline]
    pub fn dir(&self) -> V2 {
        self.dir
    }

    /// The supporting line, directed like the ray, with the origin at parameter 0.
    pub fn line(&self) -> Line {
        Line {
            point: self.origin,
            dir: self.dir,
        }
    }

    /// The point at parameter `t` (distance from the origin; on the ray for `t ≥ 0`).
    #[inline]
    pub fn at(&self, t: f64) -> P2 {
        self.origin + self.dir * t
    }

    /// The parameter of the foot of `p` on the supporting line (negative behind the origin).
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        self.dir.dot(&(p - self.origin))
    }

    /// The distance of `p` from the ray: from its foot when that is ahead of the origin, else
    /// from the origin.
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        if self.param_of(p) >= 0.0 {
            self.line().residual(p)
        } else {
            (p - self.origin).norm()
        }
    }
}

/// A circle: a centre and a radius `≥ 0`. Parameter: the angle from the +x axis,
/// counter-clockwise, in `(-π, π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    center: P2,
    radius: f64,
}

impl Default for Circle {
    /// The unit circle about the origin: what a generated solver's store holds before a step
    /// writes a circle there.
    fn default() -> Self {
        Circle {
            center: P2::origin(),
            radius: 1.0,
        }
    }
}

impl Circle {
    /// The point of the circle nearest to `p`: least motion. For `p` at the centre, where
    /// every point is nearest, the point at angle 0.
    #[inline]
    pub fn nearest(&self, p: P2) -> P2 {
        let d = p - self.center;
        let n = d.norm();
        let u = if n > 0.0 { d / n } else { V2::x() };
        self.center + u * self.radius
    }

    /// The circle about `center` with `radius`. `None` when the radius is negative or a value is
    /// not finite. A zero radius is accepted (intersections classify it as
    /// [`crate::Contact::ZeroRadius`]).
    #[inline]
    pub fn new(center: P2, radius: f64) -> Option<Self> {
        if finite_p(center) && is_finite(radius) && radius >= 0.0 {
            Some(Circle { center, radius })
        } else {
            None
        }
    }

    /// The centre.
    #[inline]
    pub fn center(&self) -> P2 {
        self.center
    }

    /// The radius.
    #[inline]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The point at angle `theta` from the +x axis.
    #[inline]
    pub fn at(&self, theta: f64) -> P2 {
        self.center + V2::new(theta.cos(), theta.sin()) * self.radius
    }

    /// The angle of `p` about the centre, in `(-π, π]` (0 at the centre itself).
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        let d = p - self.center;
        d.y.atan2(d.x)
    }

    /// The implicit function `|p - center| - radius`: positive outside.
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        (p - self.center).norm() - self.radius
    }

    /// The distance of `p` from the circle.
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        self.implicit(p).abs()
    }

    /// The error of an outer iteration that closes on the circle: [`Circle::implicit`],
    /// except within [`tol::CIRCLE_FIRST_ORDER`] of the circle, where it is the power of `p`
    /// over the diameter, `(|p - center|² - radius²) / (2 radius)`: no square root on the
    /// path from one trial to the next (about a tenth of a warm triad's solve). The two have
    /// the same sign and root and agree to first order: the power is the distance times
    /// `(|p - center| + radius) / (2 radius)`, within 0.25% of it there, so that a miss an
    /// iteration reports is the distance to that much, and exactly beyond.
    #[inline]
    pub fn closing_error(&self, p: P2) -> f64 {
        let squared = (p - self.center).norm_squared();
        let power = squared - self.radius * self.radius;
        if power.abs() < tol::CIRCLE_FIRST_ORDER * self.radius * self.radius {
            power * (0.5 / self.radius)
        } else {
            Self::far_error(squared, self.radius)
        }
    }

    /// [`Circle::closing_error`] away from the circle: the distance itself. Out of line, so
    /// that the compiler branches to it rather than computing both sides and selecting (which
    /// would put the square root back on the path).
    #[cold]
    #[inline(never)]
    fn far_error(squared: f64, radius: f64) -> f64 {
        squared.sqrt() - radius
    }
}

/// A parabola: the points equidistant from a focus and a directed directrix, on the directrix's
/// left, `|X - F| = sd_D(X)`.
///
/// Parameter `t`: the signed coordinate along the directrix direction measured from the vertex,
/// `X(t) = V + t D + t² / (2k) N` where `k` is the distance from focus to directrix, `D` the
/// directrix direction and `N` its left normal (the axis, from the directrix to the focus).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parabola {
    focus: P2,
    directrix: Line,
}

impl Parabola {
    /// The parabola with this focus and directrix. `None` unless the focus lies strictly to the
    /// left of the directrix (beyond [`tol::LENGTH_REL`] of the coordinates): a focus on the
    /// directrix degenerates to a ray, and one on its right gives an empty locus.
    #[inline]
    pub fn new(focus: P2, directrix: Line) -> Option<Self> {
        if !finite_p(focus) {
            return None;
        }
        let k = directrix.signed_distance(focus);
        let s = tol::scale(&[focus.x, focus.y, directrix.point.x, directrix.point.y]);
        if k > tol::LENGTH_REL * s {
            Some(Parabola { focus, directrix })
        } else {
            None
        }
    }

    /// The focus.
    pub fn focus(&self) -> P2 {
        self.focus
    }

    /// The directrix.
    pub fn directrix(&self) -> Line {
        self.directrix
    }

    /// The distance `k > 0` from the focus to the directrix (twice the focal length).
    pub fn focal_distance(&self) -> f64 {
        self.directrix.signed_distance(self.focus)
    }

    /// The vertex, halfway between focus and directrix.
    pub fn vertex(&self) -> P2 {
        self.focus - self.directrix.normal() * (0.5 * self.focal_distance())
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> P2 {
        let k = self.focal_distance();
        self.vertex() + self.directrix.dir * t + self.directrix.normal() * (t * t / (2.0 * k))
    }

    /// The parameter of the point of the parabola nearest in `t` to `p` (exact for points on
    /// it): the coordinate of `p` along the directrix from the vertex.
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        self.directrix.dir.dot(&(p - self.vertex()))
    }

    /// The implicit function `|p - F| - sd_D(p)`: negative inside (on the focus side).
    ///
    /// Evaluated without cancellation far along the arms: with `p - F = a D + b N` and
    /// `sd_D(p) = k + b`, it is `(a² - k (k + 2b)) / (|p - F| + k + b)`.
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        let d = p - self.focus;
        let k = self.focal_distance();
        let (a, b) = (self.directrix.dir.dot(&d), self.directrix.normal().dot(&d));
        let (dist, sd) = (d.norm(), k + b);
        let den = dist + sd;
        if den > 0.5 * dist {
            (a * a - k * (k + 2.0 * b)) / den
        } else {
            dist - sd
        }
    }

    /// The distance of `p` from the parabola to first order: the implicit value over the length
    /// of its gradient.
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        let g = unit(p - self.focus).unwrap_or_else(V2::zeros) - self.directrix.normal();
        first_order(self.implicit(p), g.norm())
    }
}

/// An ellipse: `|X - F1| + |X - F2| = sum`, `sum > |F1 F2|`. Equal foci give a circle.
///
/// Parameter `θ`: the eccentric angle from the major axis `u` (from `F1` to `F2`, or +x when the
/// foci coincide) towards `v = perp(u)`: `X(θ) = M + a cos θ u + b sin θ v`, `θ ∈ (-π, π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipse {
    f1: P2,
    f2: P2,
    sum: f64,
}

impl Ellipse {
    /// The ellipse with foci `f1`, `f2` and sum of focal distances `sum`. `None` unless `sum`
    /// exceeds the focal distance by more than [`tol::LENGTH_REL`] of the scale (at equality
    /// the locus is the segment between the foci, below it empty), or when a value is not
    /// finite.
    #[inline]
    pub fn new(f1: P2, f2: P2, sum: f64) -> Option<Self> {
        if !finite_p(f1) || !finite_p(f2) || !sum.is_finite() {
            return None;
        }
        let s = tol::scale(&[f1.x, f1.y, f2.x, f2.y, sum]);
        if sum - (f2 - f1).norm() > tol::LENGTH_REL * s {
            Some(Ellipse { f1, f2, sum })
        } else {
            None
        }
    }

    /// The foci.
    pub fn foci(&self) -> (P2, P2) {
        (self.f1, self.f2)
    }

    /// The sum of the distances to the foci (the major axis length).
    pub fn sum(&self) -> f64 {
        self.sum
    }

    /// The centre, the semi-axes `a ≥ b > 0` and the unit major axis direction `u`.
    pub fn axes(&self) -> (P2, f64, f64, V2) {
        let m = nalgebra::center(&self.f1, &self.f2);
        let c = 0.5 * (self.f2 - self.f1).norm();
        let a = 0.5 * self.sum;
        let b = ((a - c) * (a + c)).sqrt();
        (m, a, b, unit(self.f2 - self.f1).unwrap_or_else(V2::x))
    }

    /// The point at eccentric angle `theta`.
    #[inline]
    pub fn at(&self, theta: f64) -> P2 {
        let (m, a, b, u) = self.axes();
        m + u * (a * theta.cos()) + perp(u) * (b * theta.sin())
    }

    /// The eccentric angle of `p` (exact for points on the ellipse).
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        let (m, a, b, u) = self.axes();
        let d = p - m;
        (perp(u).dot(&d) / b).atan2(u.dot(&d) / a)
    }

    /// The implicit function `|p - F1| + |p - F2| - sum`: positive outside.
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        (p - self.f1).norm() + (p - self.f2).norm() - self.sum
    }

    /// The distance of `p` from the ellipse to first order.
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        let g = unit(p - self.f1).unwrap_or_else(V2::zeros)
            + unit(p - self.f2).unwrap_or_else(V2::zeros);
        first_order(self.implicit(p), g.norm())
    }
}

/// One branch of a hyperbola: `|X - F1| - |X - F2| = diff`, `|diff| < |F1 F2|`; the branch
/// around `F2` for `diff > 0`, around `F1` for `diff < 0`. `diff = 0` is the perpendicular
/// bisector of the foci (a line), which every function here handles.
///
/// Parameter `t ∈ ℝ`: `X(t) = M + (diff/2) cosh t u + b sinh t v`, with `u` the unit vector from
/// `F1` to `F2`, `v = perp(u)`, `b = √(c² - diff²/4)`, `c = |F1 F2| / 2`; `t` grows towards `v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyperbola {
    f1: P2,
    f2: P2,
    diff: f64,
}

impl Hyperbola {
    /// The branch with foci `f1`, `f2` and difference of focal distances `diff`. `None` unless
    /// `|diff|` is below the focal distance by more than [`tol::LENGTH_REL`] of the scale (at
    /// equality the locus is a ray, above it empty), or when a value is not finite.
    #[inline]
    pub fn new(f1: P2, f2: P2, diff: f64) -> Option<Self> {
        if !finite_p(f1) || !finite_p(f2) || !diff.is_finite() {
            return None;
        }
        let s = tol::scale(&[f1.x, f1.y, f2.x, f2.y, diff]);
        if (f2 - f1).norm() - diff.abs() > tol::LENGTH_REL * s {
            Some(Hyperbola { f1, f2, diff })
        } else {
            None
        }
    }

    /// The foci.
    pub fn foci(&self) -> (P2, P2) {
        (self.f1, self.f2)
    }

    /// The difference of the distances to the foci.
    pub fn diff(&self) -> f64 {
        self.diff
    }

    /// The centre, the signed semi-axis `a = diff / 2`, the semi-axis `b > 0` and the unit
    /// transverse axis direction `u` (from `F1` to `F2`).
    pub fn axes(&self) -> (P2, f64, f64, V2) {
        let m = nalgebra::center(&self.f1, &self.f2);
        let c = 0.5 * (self.f2 - self.f1).norm();
        let a = 0.5 * self.diff;
        let b = ((c - a.abs()) * (c + a.abs())).sqrt();
        (m, a, b, unit(self.f2 - self.f1).unwrap_or_else(V2::x))
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> P2 {
        let (m, a, b, u) = self.axes();
        m + u * (a * t.cosh()) + perp(u) * (b * t.sinh())
    }

    /// The parameter of `p` (exact for points on the branch): `asinh(v·(p - M) / b)`.
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        let (m, _, b, u) = self.axes();
        (perp(u).dot(&(p - m)) / b).asinh()
    }

    /// The implicit function `|p - F1| - |p - F2| - diff`, evaluated without cancellation far
    /// from the foci as `2 (F2 - F1)·(p - M) / (|p - F1| + |p - F2|) - diff`.
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        let (d1, d2) = ((p - self.f1).norm(), (p - self.f2).norm());
        let m = nalgebra::center(&self.f1, &self.f2);
        let den = d1 + d2;
        if den > 0.0 {
            2.0 * (self.f2 - self.f1).dot(&(p - m)) / den - self.diff
        } else {
            -self.diff
        }
    }

    /// The distance of `p` from the branch to first order (points near the other branch are
    /// far from this one: their distance is not small).
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        let g = unit(p - self.f1).unwrap_or_else(V2::zeros)
            - unit(p - self.f2).unwrap_or_else(V2::zeros);
        let r = first_order(self.implicit(p), g.norm());
        // Points on the other branch satisfy the squared equation; the implicit function
        // already separates them (its value there is -2 diff), so nothing more is needed.
        r
    }
}

/// `|f| / |∇f|`, the first-order distance to the zero set; `|f|` where the gradient vanishes.
#[inline]
fn first_order(f: f64, grad: f64) -> f64 {
    if grad > tol::TINY {
        f.abs() / grad
    } else {
        f.abs()
    }
}

/// One of the conics of locus analysis, for the intersection functions that accept any.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Conic {
    /// A parabola.
    Parabola(Parabola),
    /// An ellipse.
    Ellipse(Ellipse),
    /// One branch of a hyperbola.
    Hyperbola(Hyperbola),
}

impl From<Parabola> for Conic {
    fn from(p: Parabola) -> Self {
        Conic::Parabola(p)
    }
}

impl From<Ellipse> for Conic {
    fn from(e: Ellipse) -> Self {
        Conic::Ellipse(e)
    }
}

impl From<Hyperbola> for Conic {
    fn from(h: Hyperbola) -> Self {
        Conic::Hyperbola(h)
    }
}

impl Conic {
    /// The point at parameter `t` (see each conic for its parameter).
    #[inline]
    pub fn at(&self, t: f64) -> P2 {
        match self {
            Conic::Parabola(c) => c.at(t),
            Conic::Ellipse(c) => c.at(t),
            Conic::Hyperbola(c) => c.at(t),
        }
    }

    /// The parameter of a point on the conic.
    #[inline]
    pub fn param_of(&self, p: P2) -> f64 {
        match self {
            Conic::Parabola(c) => c.param_of(p),
            Conic::Ellipse(c) => c.param_of(p),
            Conic::Hyperbola(c) => c.param_of(p),
        }
    }

    /// The implicit function (length units, zero on the locus).
    #[inline]
    pub fn implicit(&self, p: P2) -> f64 {
        match self {
            Conic::Parabola(c) => c.implicit(p),
            Conic::Ellipse(c) => c.implicit(p),
            Conic::Hyperbola(c) => c.implicit(p),
        }
    }

    /// The error of an outer iteration that closes on the conic: [`Conic::implicit`].
    #[inline]
    pub fn closing_error(&self, p: P2) -> f64 {
        self.implicit(p)
    }

    /// The first-order distance of `p` from the conic.
    #[inline]
    pub fn residual(&self, p: P2) -> f64 {
        match self {
            Conic::Parabola(c) => c.residual(p),
            Conic::Ellipse(c) => c.residual(p),
            Conic::Hyperbola(c) => c.residual(p),
        }
    }

    /// The magnitude of the conic's defining values, for scaled tolerances.
    pub(crate) fn scale(&self) -> f64 {
        match self {
            Conic::Parabola(c) => tol::scale(&[
                c.focus.x,
                c.focus.y,
                c.directrix.point.x,
                c.directrix.point.y,
                c.focal_distance(),
            ]),
            Conic::Ellipse(c) => tol::scale(&[c.f1.x, c.f1.y, c.f2.x, c.f2.y, c.sum]),
            Conic::Hyperbola(c) => tol::scale(&[c.f1.x, c.f1.y, c.f2.x, c.f2.y, c.diff]),
        }
    }

    /// The focal form `μ |X - F| = w·(X - F) + k` of the conic (or of the whole hyperbola whose
    /// branch has `w·(X - F) + k ≥ 0`); `μ = 0` for the line `diff = 0`.
    pub(crate) fn focal(&self) -> Focal {
        match self {
            Conic::Parabola(c) => Focal {
                f: c.focus,
                mu: 1.0,
                w: c.directrix.normal(),
                k: c.focal_distance(),
            },
            Conic::Ellipse(c) => {
                let d = c.f2 - c.f1;
                Focal {
                    f: c.f2,
                    mu: 2.0 * c.sum,
                    w: -d * 2.0,
                    k: (c.sum - d.norm()) * (c.sum + d.norm()),
                }
            }
            Conic::Hyperbola(c) => {
                let (near, d) = if c.diff >= 0.0 {
                    (c.f2, c.f2 - c.f1)
                } else {
                    (c.f1, c.f1 - c.f2)
                };
                let e = c.diff.abs();
                Focal {
                    f: near,
                    mu: 2.0 * e,
                    w: d * 2.0,
                    k: (d.norm() - e) * (d.norm() + e),
                }
            }
        }
    }

    /// A rational quadratic parametrisation `X = origin + (P0 + P1 s + P2 s²) / (w0 + w1 s +
    /// w2 s²)` in a parameter `s` related to [`Conic::at`]'s `t` by [`Conic::param_from_s`]:
    /// parabola `s = t`; hyperbola `s = e^t` (`s > 0`); ellipse `s = tan((θ - θ0) / 2)`, which
    /// misses the point `θ0 + π` only.
    pub(crate) fn rational(&self, theta0: f64) -> Rational {
        match self {
            Conic::Parabola(c) => {
                let k = c.focal_distance();
                Rational {
                    origin: c.vertex(),
                    p: [
                        V2::zeros(),
                        c.directrix.dir,
                        c.directrix.normal() / (2.0 * k),
                    ],
                    w: [1.0, 0.0, 0.0],
                }
            }
            Conic::Ellipse(c) => {
                let (m, a, b, u) = c.axes();
                // Rotate the start so that s = 0 is at θ0.
                let (s0, c0) = theta0.sin_cos();
                let e1 = u * (a * c0) + perp(u) * (b * s0); // X(θ0) - M
                let e2 = -u * (a * s0) + perp(u) * (b * c0); // X'(θ0)
                Rational {
                    origin: m,
                    p: [e1, e2 * 2.0, -e1],
                    w: [1.0, 0.0, 1.0],
                }
            }
            Conic::Hyperbola(c) => {
                let (m, a, b, u) = c.axes();
                let v = perp(u);
                Rational {
                    origin: m,
                    p: [
                        u * (0.5 * a) - v * (0.5 * b),
                        V2::zeros(),
                        u * (0.5 * a) + v * (0.5 * b),
                    ],
                    w: [0.0, 1.0, 0.0],
                }
            }
        }
    }

    /// Converts the rational parameter `s` of [`Conic::rational`] to the parameter of
    /// [`Conic::at`]; `None` where `s` is outside the curve's range (hyperbola `s ≤ 0`).
    pub(crate) fn param_from_s(&self, s: f64, theta0: f64) -> Option<f64> {
        match self {
            Conic::Parabola(_) => Some(s),
            Conic::Ellipse(_) => {
                let t = theta0 + 2.0 * s.atan();
                Some(wrap_angle(t))
            }
            Conic::Hyperbola(_) => (s > 0.0).then(|| s.ln()),
        }
    }
}

/// The angle brought into `(-π, π]`.
pub(crate) fn wrap_angle(t: f64) -> f64 {
    let w = t.sin().atan2(t.cos());
    if w == -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        w
    }
}

/// `μ |X - f| = w·(X - f) + k`; the locus is where the right side is `≥ 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Focal {
    pub(crate) f: P2,
    pub(crate) mu: f64,
    pub(crate) w: V2,
    pub(crate) k: f64,
}

impl Focal {
    /// The right side `w·(X - f) + k`, whose sign selects the hyperbola's branch.
    pub(crate) fn h(&self, x: P2) -> f64 {
        self.w.dot(&(x - self.f)) + self.k
    }
}

/// `X = origin + (Σ p_i s^i) / (Σ w_i s^i)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rational {
    pub(crate) origin: P2,
    pub(crate) p: [V2; 3],
    pub(crate) w: [f64; 3],
}

impl Rational {
    pub(crate) fn at(&self, s: f64) -> Option<P2> {
        let [p0, p1, p2] = self.p;
        let [w0, w1, w2] = self.w;
        let num = p0 + (p1 + p2 * s) * s;
        let den = w0 + (w1 + w2 * s) * s;
        let x = self.origin + num / den;
        finite_p(x).then_some(x)
    }
}

/// Whether a distance grows or shrinks with the variable radius `ρ`: [`Sense::Plus`] is
/// `|X - C| = ρ + b`, [`Sense::Minus`] is `|X - C| = b - ρ`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sense {
    /// `|X - C| = ρ + b`: outside the fixed circle of radius `b` (or containing it, `b < 0`).
    Plus,
    /// `|X - C| = b - ρ`: inside the fixed circle of radius `b`.
    Minus,
}

/// The locus of the centre `X` of a circle of radius `ρ` with `sd_L(X) = ρ + a` (on the left of
/// `line`, perimeter `a` from it) and `|X - C| = ±ρ + b` (see [`Sense`]): a parabola.
///
/// [`Sense::Plus`]: focus `C`, directrix `line` displaced by `a - b` to the left;
/// [`Sense::Minus`]: focus `C`, directrix `line` reversed and displaced so that
/// `sd = a + b - sd_L`. The radius at a centre `X` is `ρ = sd_L(X) - a`; the caller rejects
/// centres with `ρ < 0` if they matter. `None` when the focus is not strictly on the directrix's
/// left (the locus is then a ray or empty) or a value is not finite.
///
/// Kramer's circle problem: circle `G` tangent to line `L` (on its left) and externally tangent
/// to circle `C` of radius `r`: `centres_line_circle(&L, 0.0, c, Sense::Plus, r)`.
pub fn centres_line_circle(
    line: &Line,
    a: f64,
    centre: P2,
    sense: Sense,
    b: f64,
) -> Option<Parabola> {
    if !a.is_finite() || !b.is_finite() {
        return None;
    }
    let directrix = match sense {
        Sense::Plus => line.offset(a - b),
        // sd_D(X) = a + b - sd_L(X): D is L reversed, offset by -(a + b) to its left.
        Sense::Minus => line.reversed().offset(-(a + b)),
    };
    Parabola::new(centre, directrix)
}

/// The locus of the centre `X` of a circle of radius `ρ` with `|X - C1| = ±ρ + b1` and
/// `|X - C2| = ±ρ + b2` (see [`Sense`]).
///
/// Equal senses give the hyperbola branch `|X - C1| - |X - C2| = b1 - b2` (the perpendicular
/// bisector when `b1 = b2`); opposite senses give the ellipse `|X - C1| + |X - C2| = b1 + b2`.
/// `None` when the conic degenerates (a ray, a segment, or empty: `|b1 - b2| ≥ |C1 C2|`, or
/// `b1 + b2 ≤ |C1 C2|`) or a value is not finite.
pub fn centres_circle_circle(
    c1: P2,
    s1: Sense,
    b1: f64,
    c2: P2,
    s2: Sense,
    b2: f64,
) -> Option<Conic> {
    if s1 == s2 {
        // Plus: |X-C1| - ρ = b1, |X-C2| - ρ = b2; Minus: |X-C1| + ρ = b1, |X-C2| + ρ = b2.
        Hyperbola::new(c1, c2, b1 - b2).map(Conic::Hyperbola)
    } else {
        Ellipse::new(c1, c2, b1 + b2).map(Conic::Ellipse)
    }
}

/// The angular bisector of paper 002's RR-1: the locus of the centre `X` of a circle of radius
/// `ρ` with `sd_L1(X) = ρ + a1` and `sd_L2(X) = ρ + a2` (on the left of both lines, perimeter at
/// `a1` and `a2` from them): the line where the displaced lines `L1.offset(a1)` and
/// `L2.offset(a2)` have equal signed distances.
///
/// The returned line is directed so that `ρ = sd_L1(X) - a1` grows along it, and its point is
/// the apex where `ρ = 0`: the centres with `ρ ≥ 0` form the ray from [`Line::point`] along
/// [`Line::dir`] (paper 002's angular-bisector ray). For antiparallel lines the locus is the
/// mid-parallel line, along which `ρ` is constant: it is directed like `L1`. `None` for parallel
/// lines with the same direction (the locus is empty or the whole plane).
pub fn centres_line_line(l1: &Line, a1: f64, l2: &Line, a2: f64) -> Option<Line> {
    if !a1.is_finite() || !a2.is_finite() {
        return None;
    }
    let (n1, n2) = (l1.normal(), l2.normal());
    let m = n1 - n2;
    let mm = m.norm_squared();
    if mm <= tol::ANGLE * tol::ANGLE {
        return None;
    }
    // m·(X - P1) = a1 - a2 + n2·(P1 - P2).
    let kappa = a1 - a2 + n2.dot(&(l1.point - l2.point));
    let x0 = l1.point + m * (kappa / mm);
    let mut e = perp(m) / mm.sqrt();
    let growth = n1.dot(&e);
    if growth.abs() <= tol::ANGLE {
        return Line::new(x0, l1.dir);
    }
    if growth < 0.0 {
        e = -e;
    }
    let rho0 = l1.signed_distance(x0) - a1;
    let apex = x0 - e * (rho0 / growth.abs());
    Line::new(if finite_p(apex) { apex } else { x0 }, e)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> P2 {
        P2::new(x, y)
    }

    #[test]
    fn line_signs_and_constructors() {
        let l = Line::new(p(0.0, 0.0), V2::new(2.0, 0.0)).unwrap();
        assert_eq!(l.dir(), V2::new(1.0, 0.0));
        assert_eq!(l.signed_distance(p(3.0, 2.0)), 2.0);
        assert_eq!(l.reversed().signed_distance(p(3.0, 2.0)), -2.0);
        assert_eq!(l.offset(1.0).signed_distance(p(3.0, 2.0)), 1.0);
        assert!(Line::new(p(0.0, 0.0), V2::zeros()).is_none());
        assert!(Line::new(p(f64::NAN, 0.0), V2::x()).is_none());
        assert!(Line::through(p(1.0, 1.0), p(1.0, 1.0)).is_none());
        assert_eq!(l.param_of(l.at(2.5)), 2.5);
        let r = Ray::new(p(0.0, 0.0), V2::x()).unwrap();
        assert_eq!(r.residual(p(-3.0, 4.0)), 5.0);
        assert_eq!(r.residual(p(3.0, 4.0)), 4.0);
        assert!(Circle::new(p(0.0, 0.0), -1.0).is_none());
        assert!(Circle::new(p(0.0, 0.0), f64::INFINITY).is_none());
        let c = Circle::new(p(1.0, 0.0), 2.0).unwrap();
        assert!(c.residual(c.at(0.7)) < 1e-15);
        assert!((c.param_of(c.at(0.7)) - 0.7).abs() < 1e-15);
    }

    #[test]
    fn conics_parametrise_their_implicit_zero_set() {
        let d = Line::new(p(0.0, -1.0), V2::x()).unwrap();
        let par = Parabola::new(p(0.0, 1.0), d).unwrap();
        assert!(Parabola::new(p(0.0, -2.0), d).is_none());
        let ell = Ellipse::new(p(-1.0, 0.5), p(2.0, 1.0), 5.0).unwrap();
        assert!(Ellipse::new(p(0.0, 0.0), p(2.0, 0.0), 2.0).is_none());
        let hyp = Hyperbola::new(p(-1.0, 0.5), p(2.0, 1.0), -1.5).unwrap();
        assert!(Hyperbola::new(p(0.0, 0.0), p(2.0, 0.0), 2.0).is_none());
        let line_h = Hyperbola::new(p(0.0, 0.0), p(2.0, 0.0), 0.0).unwrap();
        let circ = Ellipse::new(p(1.0, 1.0), p(1.0, 1.0), 4.0).unwrap();
        for c in [
            Conic::from(par),
            ell.into(),
            hyp.into(),
            line_h.into(),
            circ.into(),
        ] {
            for i in -10..=10 {
                let t = i as f64 * 0.3;
                let x = c.at(t);
                assert!(c.implicit(x).abs() < 1e-14, "{c:?} {t}");
                assert!(c.residual(x) < 1e-14);
                assert!(
                    (c.param_of(x) - t).abs() < 1e-13,
                    "{c:?} {t} {}",
                    c.param_of(x)
                );
                // The focal form holds, with the branch side non-negative.
                let f = c.focal();
                assert!(f.h(x) >= 0.0);
                assert!((f.mu * (x - f.f).norm() - f.h(x)).abs() < 1e-12 * (1.0 + f.h(x).abs()));
                // The rational form reaches the same point.
                let theta0 = 0.4;
                let r = c.rational(theta0);
                let s = match c {
                    Conic::Parabola(_) => t,
                    Conic::Ellipse(_) => ((t - theta0) / 2.0).tan(),
                    Conic::Hyperbola(_) => t.exp(),
                };
                let y = r.at(s).unwrap();
                assert!((y - x).norm() < 1e-13, "{c:?} {t} {x} {y}");
                let back = c.param_from_s(s, theta0).unwrap();
                assert!((wrap_angle(back - t)).abs() < 1e-13);
            }
            // A point off the curve by 1e-3 along the normal has residual about 1e-3.
            let x = c.at(0.5);
            let t = (c.at(0.5 + 1e-6) - c.at(0.5 - 1e-6)).normalize();
            let off = x + perp(t) * 1e-3;
            assert!(
                (c.residual(off) - 1e-3).abs() < 1e-5,
                "{c:?} {}",
                c.residual(off)
            );
        }
    }

    #[test]
    fn centres_of_variable_circles() {
        // Tangent to y = -4 on its left (above), externally tangent to the circle r = 2 at 0.
        let l = Line::new(p(0.0, -4.0), V2::x()).unwrap();
        let par = centres_line_circle(&l, 0.0, p(0.0, 0.0), Sense::Plus, 2.0).unwrap();
        for i in -5..=5 {
            let x = par.at(i as f64);
            let rho = l.signed_distance(x);
            assert!(((x - p(0.0, 0.0)).norm() - (rho + 2.0)).abs() < 1e-13);
        }
        // Inside a circle of radius 10, tangent to y = -4 from above.
        let par = centres_line_circle(&l, 0.0, p(0.0, 0.0), Sense::Minus, 10.0).unwrap();
        for i in -5..=5 {
            let x = par.at(i as f64);
            let rho = l.signed_distance(x);
            assert!(((x - p(0.0, 0.0)).norm() - (10.0 - rho)).abs() < 1e-13);
        }
        // Two circles: externally tangent to both → hyperbola; inside one, outside the other →
        // ellipse.
        let (c1, c2) = (p(0.0, 0.0), p(5.0, 0.0));
        let h = centres_circle_circle(c1, Sense::Plus, 1.0, c2, Sense::Plus, 2.0).unwrap();
        let e = centres_circle_circle(c1, Sense::Minus, 10.0, c2, Sense::Plus, 1.0).unwrap();
        for i in -5..=5 {
            let x = h.at(i as f64 * 0.4);
            let rho = (x - c1).norm() - 1.0;
            assert!(((x - c2).norm() - (rho + 2.0)).abs() < 1e-12);
            let x = e.at(i as f64 * 0.4);
            let rho = 10.0 - (x - c1).norm();
            assert!(((x - c2).norm() - (rho + 1.0)).abs() < 1e-12);
        }
        assert!(centres_circle_circle(c1, Sense::Plus, 0.0, c2, Sense::Plus, 6.0).is_none());
        // RR-1: left of the x axis (above) and left of the downward y axis (x > 0... its left is
        // +x): the bisector of the first quadrant, apex at the origin.
        let l1 = Line::new(p(0.0, 0.0), V2::x()).unwrap();
        let l2 = Line::new(p(0.0, 0.0), -V2::y()).unwrap();
        let b = centres_line_line(&l1, 0.0, &l2, 0.0).unwrap();
        assert!((b.point() - p(0.0, 0.0)).norm() < 1e-15);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!((b.dir() - V2::new(s, s)).norm() < 1e-15);
        let b = centres_line_line(&l1, 1.0, &l2, 0.5).unwrap();
        for t in [0.0, 1.0, 7.0] {
            let x = b.at(t);
            let rho = l1.signed_distance(x) - 1.0;
            assert!((l2.signed_distance(x) - 0.5 - rho).abs() < 1e-14);
            assert!((rho - t * s).abs() < 1e-14);
        }
        // Antiparallel: the mid-parallel line; parallel same direction: none.
        let l3 = Line::new(p(0.0, 4.0), -V2::x()).unwrap();
        let m = centres_line_line(&l1, 0.0, &l3, 0.0).unwrap();
        assert!((l1.signed_distance(m.point()) - 2.0).abs() < 1e-15);
        assert!(centres_line_line(&l1, 0.0, &l1.offset(1.0), 0.0).is_none());
    }
}
