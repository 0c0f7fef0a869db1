//! Loci in space as types: point, line, plane, sphere, circle with its axis, cylinder, cone and
//! ellipse (the section of a cylinder by a plane).
//!
//! Directions and normals are stored as unit vectors; the constructors normalize them and keep
//! a zero vector zero (an intersection then reports [`crate::Contact::ZeroRadius`]). Each locus
//! implements [`Locus3`], whose [`Locus3::distance`] is the Euclidean distance from a point to
//! the locus: zero exactly on it, so tests can check that a root lies on both loci. Nothing here
//! allocates or panics; non-finite input gives NaN or infinite distances.

use nalgebra::{Point3, Vector3};

/// The midpoint of `a` and `b`.
#[inline]
pub fn midpoint(a: Point3<f64>, b: Point3<f64>) -> Point3<f64> {
    Point3::from((a.coords + b.coords) * 0.5)
}

/// The point reflection of `p` through `centre`: the point whose midpoint with `p` is
/// `centre`. Exact when `p` is `centre`.
#[inline]
pub fn reflect_through(p: Point3<f64>, centre: Point3<f64>) -> Point3<f64> {
    centre + (centre - p)
}

/// The mirror image of `p` across the plane through `base` with unit `normal`: `p` moved
/// twice its signed distance from the plane against the normal. A point of the plane is its
/// own image (to rounding).
#[inline]
pub fn mirror(base: Point3<f64>, normal: Vector3<f64>, p: Point3<f64>) -> Point3<f64> {
    p - normal * (2.0 * normal.dot(&(p - base)))
}

/// A locus in space: a set of points with a distance.
pub trait Locus3 {
    /// The Euclidean distance from `p` to the nearest point of the locus (non-negative).
    fn distance(&self, p: &Point3<f64>) -> f64;
}

/// `v / |v|`, or the zero vector when `v` is zero.
#[inline]
pub(crate) fn unit_or_zero(v: &Vector3<f64>) -> Vector3<f64> {
    let n = v.norm();
    if n > 0.0 {
        v / n
    } else {
        Vector3::zeros()
    }
}

impl Locus3 for Point3<f64> {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        (p - self).norm()
    }
}

/// A line: the points `point + t * dir` for every real `t`; `dir` is a unit vector (or zero for
/// a degenerate line). The sign of `dir` orients the line: branch indices of line intersections
/// follow increasing `t`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Line3 {
    /// A point of the line (its `t = 0`).
    pub point: Point3<f64>,
    /// Unit direction (zero when degenerate).
    pub dir: Vector3<f64>,
}

impl Line3 {
    /// The line through `point` with direction `dir`, normalized (zero stays zero).
    #[inline]
    pub fn new(point: Point3<f64>, dir: Vector3<f64>) -> Self {
        Self {
            point,
            dir: unit_or_zero(&dir),
        }
    }

    /// The line from `a` towards `b` (`t = 0` at `a`, degenerate when `a == b`).
    #[inline]
    pub fn through(a: &Point3<f64>, b: &Point3<f64>) -> Self {
        Self::new(*a, b - a)
    }

    /// The point of parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> Point3<f64> {
        self.point + self.dir * t
    }

    /// The parameter of the foot of the perpendicular from `p`.
    #[inline]
    pub fn param(&self, p: &Point3<f64>) -> f64 {
        self.dir.dot(&(p - self.point))
    }

    /// The point of the line nearest to `p`.
    #[inline]
    pub fn closest(&self, p: &Point3<f64>) -> Point3<f64> {
        self.at(self.param(p))
    }
}

impl Locus3 for Line3 {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        let w = p - self.point;
        (w - self.dir * self.dir.dot(&w)).norm()
    }
}

/// A plane: the points `p` with `normal . p = offset`; `normal` is a unit vector (or zero for a
/// degenerate plane). The normal orients the plane (its positive side).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Plane {
    /// Unit normal (zero when degenerate).
    pub normal: Vector3<f64>,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f64,
}

impl Plane {
    /// The plane `normal . p = offset`, both divided by `|normal|` (a zero normal stays zero).
    #[inline]
    pub fn new(normal: Vector3<f64>, offset: f64) -> Self {
        let n = normal.norm();
        if n > 0.0 {
            Self {
                normal: normal / n,
                offset: offset / n,
            }
        } else {
            Self {
                normal: Vector3::zeros(),
                offset,
            }
        }
    }

    /// The plane through `point` with normal `normal` (normalized).
    #[inline]
    pub fn from_point_normal(point: &Point3<f64>, normal: &Vector3<f64>) -> Self {
        let n = unit_or_zero(normal);
        Self {
            normal: n,
            offset: n.dot(&point.coords),
        }
    }

    /// Signed distance of `p` from the plane, positive on the side `normal` points to.
    #[inline]
    pub fn signed_distance(&self, p: &Point3<f64>) -> f64 {
        self.normal.dot(&p.coords) - self.offset
    }

    /// The foot of the perpendicular from `p` onto the plane.
    #[inline]
    pub fn project(&self, p: &Point3<f64>) -> Point3<f64> {
        p - self.normal * self.signed_distance(p)
    }

    /// The point of the plane nearest to the origin.
    #[inline]
    pub fn origin_point(&self) -> Point3<f64> {
        Point3::from(self.normal * self.offset)
    }
}

impl Locus3 for Plane {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        self.signed_distance(p).abs()
    }
}

/// A sphere: the points at distance `radius` from `center`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Point3<f64>,
    /// Radius (zero or negative: degenerate).
    pub radius: f64,
}

impl Sphere {
    /// The sphere of centre `center` and radius `radius`.
    #[inline]
    pub fn new(center: Point3<f64>, radius: f64) -> Self {
        Self { center, radius }
    }

    /// The point of the sphere nearest `p`; `None` when `p` is its centre (every point is).
    #[inline]
    pub fn nearest(&self, p: &Point3<f64>) -> Option<Point3<f64>> {
        let v = p - self.center;
        let n = v.norm();
        (n > 0.0 && n.is_finite()).then(|| self.center + v * (self.radius / n))
    }
}

impl Locus3 for Sphere {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        ((p - self.center).norm() - self.radius).abs()
    }
}

/// A circle in space with its axis: the points of the plane through `center` perpendicular to
/// `normal` at distance `radius` from `center`. `normal` (a unit vector) orients the circle:
/// angles about it are counter-clockwise seen from its tip.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Circle3 {
    /// Centre.
    pub center: Point3<f64>,
    /// Unit normal of the circle's plane, the direction of its axis (zero when degenerate).
    pub normal: Vector3<f64>,
    /// Radius (zero or negative: degenerate).
    pub radius: f64,
}

impl Circle3 {
    /// The circle of centre `center`, axis `normal` (normalized) and radius `radius`.
    #[inline]
    pub fn new(center: Point3<f64>, normal: Vector3<f64>, radius: f64) -> Self {
        Self {
            center,
            normal: unit_or_zero(&normal),
            radius,
        }
    }

    /// The plane of the circle.
    #[inline]
    pub fn plane(&self) -> Plane {
        Plane {
            normal: self.normal,
            offset: self.normal.dot(&self.center.coords),
        }
    }

    /// The circle's axis: the line through the centre along the normal.
    #[inline]
    pub fn axis(&self) -> Line3 {
        Line3 {
            point: self.center,
            dir: self.normal,
        }
    }

    /// The point of the circle nearest `p`; `None` when `p` is on its axis (every point is).
    #[inline]
    pub fn nearest(&self, p: &Point3<f64>) -> Option<Point3<f64>> {
        let w = p - self.center;
        let radial = w - self.normal * self.normal.dot(&w);
        let n = radial.norm();
        (n > 0.0 && n.is_finite()).then(|| self.center + radial * (self.radius / n))
    }

    /// The circle's in-plane basis: where its angles are measured from
    /// ([`crate::frame::perpendicular`] of its normal) and the direction a quarter turn on.
    #[inline]
    pub fn basis(&self) -> (Vector3<f64>, Vector3<f64>) {
        crate::frame::across(&self.normal)
    }

    /// The angle of `p` about the circle's axis, from [`Circle3::basis`]'s first direction.
    #[inline]
    pub fn angle_of(&self, p: &Point3<f64>) -> f64 {
        let (e1, e2) = self.basis();
        let w = p - self.center;
        w.dot(&e2).atan2(w.dot(&e1))
    }

    /// The point of the circle at angle `t` (see [`Circle3::angle_of`]).
    #[inline]
    pub fn point_at(&self, t: f64) -> Point3<f64> {
        let (e1, e2) = self.basis();
        let (s, co) = t.sin_cos();
        self.center + (e1 * co + e2 * s) * self.radius
    }

    /// The circle that `p` sweeps turning about the line through `pivot` along `axis` (not
    /// necessarily unit): centred at `p`'s foot on the axis. A zero `axis` gives a degenerate
    /// circle (zero normal).
    #[inline]
    pub fn orbit(pivot: &Point3<f64>, axis: &Vector3<f64>, p: &Point3<f64>) -> Self {
        let a = unit_or_zero(axis);
        let center = pivot + a * a.dot(&(p - pivot));
        Self {
            center,
            normal: a,
            radius: (p - center).norm(),
        }
    }
}

impl Locus3 for Circle3 {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        let w = p - self.center;
        let h = self.normal.dot(&w);
        let rho = (w - self.normal * h).norm();
        h.hypot(rho - self.radius)
    }
}

/// A torus: the points at distance `tube` from circle `circle` (a spindle torus when the tube
/// is wider than the circle's radius). What `distance(p, circle) = d` holds a point to.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Torus {
    /// The circle at its core.
    pub circle: Circle3,
    /// The distance from the circle.
    pub tube: f64,
}

impl Torus {
    /// The torus at distance `tube` from `circle`.
    #[inline]
    pub fn new(circle: Circle3, tube: f64) -> Self {
        Self { circle, tube }
    }

    /// The point of the torus nearest `p`: along the line from the circle's point nearest `p`;
    /// `None` when `p` is on the circle's axis or on the circle (no one nearest point).
    #[inline]
    pub fn nearest(&self, p: &Point3<f64>) -> Option<Point3<f64>> {
        let c = self.circle.nearest(p)?;
        let w = p - c;
        let n = w.norm();
        (n > 0.0 && n.is_finite()).then(|| c + w * (self.tube / n))
    }

    /// The signed distance of `p` from the torus: its distance from the circle less the tube.
    #[inline]
    pub fn signed_distance(&self, p: &Point3<f64>) -> f64 {
        self.circle.distance(p) - self.tube
    }
}

impl Locus3 for Torus {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        self.signed_distance(p).abs()
    }
}

/// A locus of space moved by a translation: where a feature held on it goes when its body
/// translates keeping another feature on its own locus. Each is rebuilt through its
/// constructor, as a locus built there anew would be.
pub trait Shift {
    /// The locus translated by `v`.
    fn shifted(&self, v: &Vector3<f64>) -> Self;
}

impl Shift for Sphere {
    fn shifted(&self, v: &Vector3<f64>) -> Self {
        Sphere::new(self.center + v, self.radius)
    }
}

impl Shift for Circle3 {
    fn shifted(&self, v: &Vector3<f64>) -> Self {
        Circle3::new(self.center + v, self.normal, self.radius)
    }
}

impl Shift for Cylinder {
    fn shifted(&self, v: &Vector3<f64>) -> Self {
        Cylinder::new(Line3::new(self.axis.point + v, self.axis.dir), self.radius)
    }
}

impl Shift for Torus {
    fn shifted(&self, v: &Vector3<f64>) -> Self {
        Torus::new(self.circle.shifted(v), self.tube)
    }
}

/// A surface of space with two coordinates on it: where a point held on it is placed by two
/// defaults. `coordinates` and `at` are inverse on the surface; each surface's doc says what
/// its two numbers mean.
pub trait Surface {
    /// The coordinates of the point of the surface nearest `p` (of `p` itself when on it).
    fn coordinates(&self, p: &Point3<f64>) -> [f64; 2];
    /// The point of the surface at coordinates `uv`.
    fn at(&self, uv: [f64; 2]) -> Point3<f64>;
}

use crate::frame::across;

/// A plane's coordinates: along the pair across its normal ([`across`]) from its point nearest
/// the origin.
impl Surface for Plane {
    fn coordinates(&self, p: &Point3<f64>) -> [f64; 2] {
        let (e1, e2) = across(&self.normal);
        let w = p - self.origin_point();
        [w.dot(&e1), w.dot(&e2)]
    }
    fn at(&self, [u, v]: [f64; 2]) -> Point3<f64> {
        let (e1, e2) = across(&self.normal);
        self.origin_point() + e1 * u + e2 * v
    }
}

/// A sphere's coordinates: longitude about the global z axis from x, and latitude from the
/// x-y plane, in radians, about its centre.
impl Surface for Sphere {
    fn coordinates(&self, p: &Point3<f64>) -> [f64; 2] {
        let w = p - self.center;
        [w.y.atan2(w.x), w.z.atan2(w.x.hypot(w.y))]
    }
    fn at(&self, [u, v]: [f64; 2]) -> Point3<f64> {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        self.center + Vector3::new(cv * cu, cv * su, sv) * self.radius
    }
}

/// A torus's coordinates: the angle about its circle's axis from the circle's first direction
/// ([`Circle3::basis`]), and the angle about the circle from outward in its plane towards its
/// normal, in radians.
impl Surface for Torus {
    fn coordinates(&self, p: &Point3<f64>) -> [f64; 2] {
        let c = &self.circle;
        let (e1, e2) = c.basis();
        let w = p - c.center;
        let h = w.dot(&c.normal);
        let radial = w - c.normal * h;
        [
            w.dot(&e2).atan2(w.dot(&e1)),
            h.atan2(radial.norm() - c.radius),
        ]
    }
    fn at(&self, [u, v]: [f64; 2]) -> Point3<f64> {
        let c = &self.circle;
        let (e1, e2) = c.basis();
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        c.center + (e1 * cu + e2 * su) * (c.radius + self.tube * cv) + c.normal * (self.tube * sv)
    }
}

/// A cylinder's coordinates: the angle about its axis from the first direction across it
/// ([`across`]), in radians, and the distance along the axis from its point.
impl Surface for Cylinder {
    fn coordinates(&self, p: &Point3<f64>) -> [f64; 2] {
        let (e1, e2) = across(&self.axis.dir);
        let w = p - self.axis.point;
        [w.dot(&e2).atan2(w.dot(&e1)), w.dot(&self.axis.dir)]
    }
    fn at(&self, [u, v]: [f64; 2]) -> Point3<f64> {
        let (e1, e2) = across(&self.axis.dir);
        let (s, c) = u.sin_cos();
        self.axis.point + self.axis.dir * v + (e1 * c + e2 * s) * self.radius
    }
}

/// A (circular, infinite) cylinder: the points at distance `radius` from the line `axis`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Cylinder {
    /// The axis.
    pub axis: Line3,
    /// Radius (zero or negative: degenerate).
    pub radius: f64,
}

impl Cylinder {
    /// The cylinder of axis `axis` and radius `radius`.
    #[inline]
    pub fn new(axis: Line3, radius: f64) -> Self {
        Self { axis, radius }
    }

    /// The point of the cylinder nearest `p`: along the perpendicular from the axis through
    /// `p`; `None` when `p` is on the axis (every point of the circle about it is).
    #[inline]
    pub fn nearest(&self, p: &Point3<f64>) -> Option<Point3<f64>> {
        let foot = self.axis.closest(p);
        let radial = p - foot;
        let n = radial.norm();
        (n > 0.0 && n.is_finite()).then(|| foot + radial * (self.radius / n))
    }

    /// The signed distance of `p` from the cylinder: positive outside, zero on it.
    #[inline]
    pub fn signed_distance(&self, p: &Point3<f64>) -> f64 {
        self.axis.distance(p) - self.radius
    }
}

impl Locus3 for Cylinder {
    #[inline]
    fn distance(&self, p: &Point3<f64>) -> f64 {
        (self.axis.distance(p) - self.radius).abs()
    }
}

/// A (single-nappe, infinite) circular cone: the points `p` for which the angle between
/// `p - apex` and `axis` is `half_angle`, and the apex itself. Joints that keep a line through a
/// fixed point at a fixed angle to a fixed direction (paper 003's angle constraints) sweep one.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Cone {
    /// The apex.
    pub apex: Point3<f64>,
    /// Unit direction of the axis, into the nappe (zero when degenerate).
    pub axis: Vector3<f64>,
    /// Angle between the axis and every generator, in `[0, pi]` radians.
    pub half_angle: f64,
}

impl Cone {
    /// The cone of apex `apex`, axis direction `axis` (normalized) and `half_angle` radians.
    #[inline]
    pub fn new(apex: Point3<f64>, axis: Vector3<f64>, half_angle: f64) -> Self {
        Self {
            apex,
            axis: unit_or_zero(&axis),
            half_angle,
        }
    }
}

impl Locus3 for Cone {
    fn distance(&self, p: &Point3<f64>) -> f64 {
        let w = p - self.apex;
        let h = self.axis.dot(&w);
        let rho = (w - self.axis * h).norm();
        let (s, c) = self.half_angle.sin_cos();
        // In the half-plane through the axis and p, the generator is the ray (c, s) * t, t >= 0.
        if h * c + rho * s >= 0.0 {
            (h * s - rho * c).abs()
        } else {
            w.norm()
        }
    }
}

/// An ellipse in space: the points `center + a cos(u) major + b sin(u) minor`, with `major` and
/// `minor = normal x major` unit vectors of its plane. A plane cuts a cylinder of radius `r` in
/// one with `b = r` along the direction perpendicular to the cylinder's axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Ellipse3 {
    /// Centre.
    pub center: Point3<f64>,
    /// Unit normal of the ellipse's plane.
    pub normal: Vector3<f64>,
    /// Unit direction of the first semi-axis (`a`).
    pub major: Vector3<f64>,
    /// Unit direction of the second semi-axis (`b`), `normal x major`.
    pub minor: Vector3<f64>,
    /// Semi-axis along `major` (the larger one for a section of a cylinder).
    pub a: f64,
    /// Semi-axis along `minor`.
    pub b: f64,
}

impl Ellipse3 {
    /// The point of parameter `u` (radians): `center + a cos(u) major + b sin(u) minor`.
    #[inline]
    pub fn point_at(&self, u: f64) -> Point3<f64> {
        let (s, c) = u.sin_cos();
        self.center + self.major * (self.a * c) + self.minor * (self.b * s)
    }
}

impl Locus3 for Ellipse3 {
    fn distance(&self, p: &Point3<f64>) -> f64 {
        let w = p - self.center;
        let out = self.normal.dot(&w);
        let x = self.major.dot(&w).abs();
        let y = self.minor.dot(&w).abs();
        let (e0, e1, y0, y1) = if self.a.abs() >= self.b.abs() {
            (self.a.abs(), self.b.abs(), x, y)
        } else {
            (self.b.abs(), self.a.abs(), y, x)
        };
        out.hypot(ellipse_distance_2d(e0, e1, y0, y1))
    }
}

/// Distance from `(y0, y1)` (both >= 0) to the ellipse with semi-axes `e0 >= e1 >= 0`, by
/// Eberly's robust bisection ("Distance from a point to an ellipse", Geometric Tools).
fn ellipse_distance_2d(e0: f64, e1: f64, y0: f64, y1: f64) -> f64 {
    if e1.is_nan() || e1 <= 0.0 {
        // Degenerate: the segment from (-e0, 0) to (e0, 0).
        return (y0 - y0.min(e0)).hypot(y1);
    }
    if y1 > 0.0 {
        if y0 > 0.0 {
            let z0 = y0 / e0;
            let z1 = y1 / e1;
            let g = z0 * z0 + z1 * z1 - 1.0;
            if g == 0.0 {
                return 0.0;
            }
            let r0 = (e0 / e1) * (e0 / e1);
            let sbar = bisect_root(r0, z0, z1, g);
            let x0 = r0 * y0 / (sbar + r0);
            let x1 = y1 / (sbar + 1.0);
            (x0 - y0).hypot(x1 - y1)
        } else {
            (y1 - e1).abs()
        }
    } else {
        let numer0 = e0 * y0;
        let denom0 = e0 * e0 - e1 * e1;
        if numer0 < denom0 {
            let xde0 = numer0 / denom0;
            let x0 = e0 * xde0;
            let x1 = e1 * (1.0 - xde0 * xde0).max(0.0).sqrt();
            (x0 - y0).hypot(x1)
        } else {
            (y0 - e0).abs()
        }
    }
}

fn bisect_root(r0: f64, z0: f64, z1: f64, g0: f64) -> f64 {
    let n0 = r0 * z0;
    let mut s0 = z1 - 1.0;
    let mut s1 = if g0 < 0.0 { 0.0 } else { n0.hypot(z1) - 1.0 };
    let mut s = 0.0;
    for _ in 0..1200 {
        s = 0.5 * (s0 + s1);
        if s == s0 || s == s1 {
            break;
        }
        let ratio0 = n0 / (s + r0);
        let ratio1 = z1 / (s + 1.0);
        let g = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
        if g > 0.0 {
            s0 = s;
        } else if g < 0.0 {
            s1 = s;
        } else {
            break;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_coordinates_and_points_are_inverse() {
        let plane =
            Plane::from_point_normal(&Point3::new(1.0, 2.0, 3.0), &Vector3::new(1.0, -2.0, 0.5));
        let sphere = Sphere::new(Point3::new(-1.0, 0.5, 2.0), 3.0);
        let cylinder = Cylinder::new(
            Line3::new(Point3::new(0.5, 1.0, -2.0), Vector3::new(0.3, 0.4, 1.0)),
            1.5,
        );
        let torus = Torus::new(
            Circle3::new(
                Point3::new(1.0, -1.0, 0.5),
                Vector3::new(0.2, 1.0, 0.3),
                2.0,
            ),
            0.7,
        );
        let surfaces: [&dyn Surface; 4] = [&plane, &sphere, &cylinder, &torus];
        let loci: [&dyn Locus3; 4] = [&plane, &sphere, &cylinder, &torus];
        for (s, l) in surfaces.iter().zip(loci) {
            for uv in [[0.3, -0.7], [-2.0, 1.2], [2.9, 0.1]] {
                let p = s.at(uv);
                assert!(l.distance(&p) < 1e-14, "{p:?} off its surface");
                let back = s.coordinates(&p);
                assert!((back[0] - uv[0]).abs() < 1e-13 && (back[1] - uv[1]).abs() < 1e-13);
            }
        }
    }

    #[test]
    fn distances_vanish_on_the_locus() {
        let p = Point3::new(1.0, 2.0, 3.0);
        assert_eq!(p.distance(&Point3::new(1.0, 2.0, 5.0)), 2.0);
        let l = Line3::through(&Point3::origin(), &Point3::new(0.0, 0.0, 2.0));
        assert_eq!(l.distance(&Point3::new(3.0, 4.0, 7.0)), 5.0);
        assert_eq!(
            l.closest(&Point3::new(3.0, 4.0, 7.0)),
            Point3::new(0.0, 0.0, 7.0)
        );
        let pl = Plane::new(Vector3::new(0.0, 0.0, 2.0), 4.0);
        assert_eq!(pl.offset, 2.0);
        assert_eq!(pl.signed_distance(&Point3::new(9.0, 9.0, 1.0)), -1.0);
        assert_eq!(
            pl.project(&Point3::new(9.0, 9.0, 1.0)),
            Point3::new(9.0, 9.0, 2.0)
        );
        assert_eq!(pl.origin_point(), Point3::new(0.0, 0.0, 2.0));
        let pl2 = Plane::from_point_normal(&Point3::new(0.0, 0.0, 2.0), &Vector3::z());
        assert_eq!(pl, pl2);
        let s = Sphere::new(Point3::origin(), 2.0);
        assert_eq!(s.distance(&Point3::new(0.0, 3.0, 0.0)), 1.0);
        let c = Circle3::new(Point3::origin(), Vector3::z() * 3.0, 1.0);
        assert_eq!(c.distance(&Point3::new(1.0, 0.0, 0.0)), 0.0);
        assert!((c.distance(&Point3::new(4.0, 0.0, 4.0)) - 5.0).abs() < 1e-15);
        assert_eq!(c.plane(), Plane::new(Vector3::z(), 0.0));
        assert_eq!(c.axis().dir, Vector3::z());
        let cy = Cylinder::new(Line3::new(Point3::origin(), Vector3::z()), 1.0);
        assert_eq!(cy.distance(&Point3::new(0.0, 3.0, -8.0)), 2.0);
        let co = Cone::new(Point3::origin(), Vector3::z(), std::f64::consts::FRAC_PI_4);
        assert!(co.distance(&Point3::new(1.0, 0.0, 1.0)) < 1e-15);
        assert!((co.distance(&Point3::new(0.0, 0.0, -1.0)) - 1.0).abs() < 1e-15);
        assert!((co.distance(&Point3::new(0.0, 0.0, 2.0)) - 2f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn ellipse_distance_matches_parametric_points() {
        let e = Ellipse3 {
            center: Point3::new(1.0, 1.0, 1.0),
            normal: Vector3::z(),
            major: Vector3::x(),
            minor: Vector3::y(),
            a: 3.0,
            b: 1.0,
        };
        for i in 0..16 {
            let p = e.point_at(i as f64 * 0.4);
            assert!(e.distance(&p) < 1e-14, "{i}");
        }
        assert!((e.distance(&Point3::new(1.0, 1.0, 1.0)) - 1.0).abs() < 1e-15);
        assert!((e.distance(&Point3::new(1.0, 1.0, 3.0)) - 5f64.sqrt()).abs() < 1e-15);
        assert!((e.distance(&Point3::new(5.0, 1.0, 1.0)) - 1.0).abs() < 1e-15);
        // Brute-force check off the axes.
        let q = Point3::new(2.5, 2.2, 1.3);
        let mut best = f64::INFINITY;
        for i in 0..200_000 {
            best = best.min((e.point_at(i as f64 * std::f64::consts::TAU / 200_000.0) - q).norm());
        }
        assert!((e.distance(&q) - best).abs() < 1e-9);
    }

    #[test]
    fn degenerate_constructors_stay_finite() {
        assert_eq!(
            Line3::new(Point3::origin(), Vector3::zeros()).dir,
            Vector3::zeros()
        );
        assert_eq!(Plane::new(Vector3::zeros(), 1.0).normal, Vector3::zeros());
        assert!(Sphere::new(Point3::origin(), f64::NAN)
            .distance(&Point3::origin())
            .is_nan());
    }
}
