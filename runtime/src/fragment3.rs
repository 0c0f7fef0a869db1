//! The closed-form solutions of the 3d plan fragments that need more than one call: a turn
//! about an axis that takes a direction onto another and meets a joint's second condition
//! ([`turn_reaching_line`], [`turn_reaching_plane`], [`turn_reaching_helix`], with the helical
//! couplings [`Helix`] and [`Screw`]), and the tilt and passing angles that put a circle or a
//! line at a distance from a point ([`tilt_to_distance`], [`passing_angle`]).
//!
//! They are built on the frames and actions of [`crate::frame`], the loci of
//! [`crate::locus3d`] and the intersections of [`crate::intersect3d`], which depend on nothing
//! here. Like them, nothing here allocates or panics.

use nalgebra::{Point3, Vector3};

use crate::frame::{helix_advance, signed_angle3, turn_across};
use crate::intersect3d;
use crate::locus3d::{Line3, Plane};
use crate::roots::{Contact, Intersection};
use crate::tol;

/// At most this many Gauss-Newton steps refine a turn that a point decides: one or two from
/// the directions' angle, off by rounding over their distance from the axis; more from a
/// direction exactly along the axis, which leaves the angle to the point alone (a flange
/// bolted off a shaft's axis).
const REACHING_STEPS: usize = 8;

/// The angle about the unit `axis` through `pivot` that turns direction `u` onto `v` and
/// takes `point` onto the line `line` (a joint's point, which the cluster's remaining slide
/// along the line then brings home). See [`turn_reaching_plane`] for the method.
#[inline]
pub fn turn_reaching_line(
    [u, v]: [&Vector3<f64>; 2],
    (pivot, axis): (&Point3<f64>, &Vector3<f64>),
    point: &Point3<f64>,
    line: &Line3,
    screw: Option<&Screw>,
) -> f64 {
    let d = line.dir;
    let scale = point.coords.norm().max(line.point.coords.norm());
    turn_reaching(
        [u, v],
        (pivot, axis),
        (point, screw),
        scale,
        |x| {
            let off = x - line.point;
            off - d * d.dot(&off)
        },
        |w| w - d * d.dot(w),
    )
}

/// The angle about the unit `axis` through `pivot` that turns direction `u` onto `v` and
/// takes `point` into the plane `plane` (where the cluster's remaining slide within the plane
/// brings it home).
///
/// A turn about an axis onto a direction that lies within `delta` rad of the axis is fixed by
/// that direction only to rounding over `delta` (a joint's z axis turned about a z axis it
/// nearly shares: 1e-16 / 1e-9 = 1e-7 rad), which moves a point at distance `rho` from the
/// axis by `rho` times that. The point is then what decides the turn.
///
/// From the directions' angle, Gauss-Newton steps (at most `REACHING_STEPS`) on both residuals
/// together: the direction's miss, and the point's miss of the locus (the part of its offset
/// across the line, or along the plane's normal) divided by the size of the coordinates, so
/// that each weighs by the inverse of its rounding. When the directions lie well across the
/// axis ([`tol::DIRECTIONS_DECIDE`]), or the point moves across the locus no faster than the
/// directions turn, their angle stands. Where both hold at the same turn (a consistent joint),
/// the result is that turn to rounding; otherwise a compromise, which the checks after it
/// measure. Zero when `axis` is zero.
#[inline]
pub fn turn_reaching_plane(
    [u, v]: [&Vector3<f64>; 2],
    (pivot, axis): (&Point3<f64>, &Vector3<f64>),
    point: &Point3<f64>,
    plane: &Plane,
    screw: Option<&Screw>,
) -> f64 {
    let n = plane.normal;
    let scale = point.coords.norm().max(plane.offset.abs());
    turn_reaching(
        [u, v],
        (pivot, axis),
        (point, screw),
        scale,
        |x| n * (n.dot(&x.coords) - plane.offset),
        |w| n * n.dot(w),
    )
}

/// A helical coupling of a marker that turns with the cluster (the riding marker) to a known
/// one: the angle from `x_from` to the riding marker's x axis about `axis` is `2 pi / pitch`
/// times its advance along `axis` from `origin` (LANGUAGE.md's `helical`, modulo a turn).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Helix {
    /// The unit axis the helix is measured about (the known marker's z axis).
    pub axis: Vector3<f64>,
    /// The x axis its turn is measured from (the known marker's).
    pub x_from: Vector3<f64>,
    /// Where its advance is measured from (the known marker's point).
    pub origin: Point3<f64>,
    /// The riding marker's x axis, before the turn.
    pub x: Vector3<f64>,
    /// The riding marker's point, before the turn.
    pub point: Point3<f64>,
    /// The advance per turn.
    pub pitch: f64,
}

/// What a helix measures once the cluster has turned: the riding marker's advance and turn,
/// and their rates of change with the cluster's turn.
struct HelixAt {
    advance: f64,
    turn: f64,
    advance_rate: f64,
    turn_rate: f64,
}

impl Helix {
    /// The helix measured after the cluster turns (`turn` applied to a vector) about the unit
    /// `a` through `pivot`.
    #[inline]
    fn at(
        &self,
        turn: impl Fn(&Vector3<f64>) -> Vector3<f64>,
        a: &Vector3<f64>,
        pivot: &Point3<f64>,
    ) -> HelixAt {
        let z = self.axis;
        let (x, arm) = (turn(&self.x), turn(&(self.point - pivot)));
        // The turn of x about z as the cluster turns about a.
        let across = x - z * z.dot(&x);
        HelixAt {
            advance: (pivot + arm - self.origin).dot(&z),
            turn: signed_angle3(&self.x_from, &x, &z),
            advance_rate: z.dot(&a.cross(&arm)),
            turn_rate: z.dot(&across.cross(&a.cross(&x))) / across.norm_squared(),
        }
    }
}

/// A helical coupling the cluster rides on after a turn (a screw): the cluster then slides
/// along `slide` until the riding marker's advance is the helix's advance for its turn (as
/// [`helix_advance`], the advance nearest where it is). With it, where a joint's point ends up
/// depends on the turn through the pitch, and [`turn_reaching_plane`], [`turn_reaching_line`]
/// and [`turn_reaching_helix`] follow it there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screw {
    /// The coupling.
    pub helix: Helix,
    /// The unit direction the cluster slides along.
    pub slide: Vector3<f64>,
}

impl Screw {
    /// The slide after the cluster turns by `turn` about the unit `a` through `pivot`, and its
    /// rate of change with the turn.
    #[inline]
    fn slide_after(
        &self,
        turn: impl Fn(&Vector3<f64>) -> Vector3<f64>,
        a: &Vector3<f64>,
        pivot: &Point3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let h = &self.helix;
        let m = h.at(turn, a, pivot);
        let along = self.slide.dot(&h.axis);
        let by = (helix_advance(m.advance, m.turn, h.pitch) - m.advance) / along;
        let rate = (h.pitch / std::f64::consts::TAU * m.turn_rate - m.advance_rate) / along;
        (self.slide * by, self.slide * rate)
    }
}

/// The angle about the unit `axis` through `pivot` that turns direction `u` onto `v` and
/// meets the helical coupling `helix` (a helical joint whose second marker turns with the
/// cluster), on the `screw` the cluster rides after the turn if any: as
/// [`turn_reaching_plane`], the helix's miss in radians (its turn off the turn of its advance,
/// wrapped) weighed by its rounding, `eps (1 + 2 pi size / pitch)`.
#[inline]
pub fn turn_reaching_helix(
    [u, v]: [&Vector3<f64>; 2],
    (pivot, axis): (&Point3<f64>, &Vector3<f64>),
    helix: &Helix,
    screw: Option<&Screw>,
) -> f64 {
    let size = (helix.point.coords.norm())
        .max(helix.origin.coords.norm())
        .max(pivot.coords.norm());
    let tau = std::f64::consts::TAU;
    let weight = 1.0 / (1.0 + tau * size / helix.pitch.abs());
    refine_turn(
        [u, v],
        (pivot, axis),
        screw,
        weight,
        |turn, a, (slid, rate)| {
            let m = helix.at(turn, a, pivot);
            let advance = m.advance + helix.axis.dot(&slid);
            let miss = crate::num::wrap_angle(m.turn - tau * advance / helix.pitch);
            let rate = m.turn_rate - tau / helix.pitch * (m.advance_rate + helix.axis.dot(&rate));
            (rate * miss, rate * rate)
        },
    )
}

/// The method of [`turn_reaching_plane`] and [`turn_reaching_line`]: `miss(x)` is the offset
/// of `x` from the locus across it, `across(w)` the part of a velocity `w` that changes it.
#[inline]
fn turn_reaching(
    [u, v]: [&Vector3<f64>; 2],
    (pivot, axis): (&Point3<f64>, &Vector3<f64>),
    (point, screw): (&Point3<f64>, Option<&Screw>),
    scale: f64,
    miss: impl Fn(&Point3<f64>) -> Vector3<f64>,
    across: impl Fn(&Vector3<f64>) -> Vector3<f64>,
) -> f64 {
    let arm = point - pivot;
    let size = scale.max(pivot.coords.norm()).max(arm.norm());
    refine_turn(
        [u, v],
        (pivot, axis),
        screw,
        1.0 / size,
        |turn, a, (slid, rate)| {
            let w = turn(&arm);
            let (r, j) = (miss(&(pivot + w + slid)), across(&(a.cross(&w) + rate)));
            (j.dot(&r), j.norm_squared())
        },
    )
}

/// The Gauss-Newton refinement of a turn about `axis` through `pivot` that takes direction
/// `u` onto `v` and meets a joint's second condition, from the directions' own angle (the
/// method of [`turn_reaching_plane`]). `joint(turn, a, (slid, rate))`, given the turn (as a map
/// of vectors), the unit axis and the slide of `screw` after it with its rate, returns the
/// condition's `j . r` and `j . j` (its miss `r` and rate `j`), each to be multiplied by
/// `weight` squared: the inverse of its rounding. The condition decides only where it moves
/// faster than the directions turn.
#[inline]
fn refine_turn(
    [u, v]: [&Vector3<f64>; 2],
    (pivot, axis): (&Point3<f64>, &Vector3<f64>),
    screw: Option<&Screw>,
    weight: f64,
    joint: impl Fn(
        &dyn Fn(&Vector3<f64>) -> Vector3<f64>,
        &Vector3<f64>,
        (Vector3<f64>, Vector3<f64>),
    ) -> (f64, f64),
) -> f64 {
    let n = axis.norm();
    if n.is_nan() || n <= 0.0 {
        return 0.0;
    }
    let a = axis / n;
    let (sin, cos) = turn_across(&a, u, v);
    let mut angle = sin.atan2(cos);
    if sin.hypot(cos) >= tol::DIRECTIONS_DECIDE || !(weight > 0.0 && weight.is_finite()) {
        return angle;
    }
    let w2 = weight * weight;
    for _ in 0..REACHING_STEPS {
        let (s, c) = crate::num::sin_cos(angle);
        // Rodrigues' turn by the angle about the unit axis.
        let turn = |x: &Vector3<f64>| x * c + a.cross(x) * s + a * (a.dot(x) * (1.0 - c));
        let ut = turn(u);
        let slide = match screw {
            Some(screw) => screw.slide_after(turn, &a, pivot),
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        let (jr, jj) = joint(&turn, &a, slide);
        let (jr, by_joint) = (jr * w2, jj * w2);
        let (r_dir, j_dir) = (ut - v, a.cross(&ut));
        let by_dir = j_dir.norm_squared();
        if by_joint.is_nan() || by_joint <= by_dir {
            break;
        }
        let step = (jr + j_dir.dot(&r_dir)) / (by_joint + by_dir);
        if !step.is_finite() {
            break;
        }
        angle -= step;
        if step.abs() <= tol::STEP_STOP_REL * (1.0 + angle.abs()) {
            break;
        }
    }
    angle
}

/// The angle between the normal of a circle about `centre` of `radius` and the direction from
/// the centre to `point`, at which `point` lies `distance` from the circle: the side of the
/// circle's plane `now` (its normal now) has the point on, so that the turn there is the least.
///
/// With `L` the point's distance from the centre, the point lies `ρ = (L² + r² - d²) / 2r`
/// from the axis and `h = √(L² - ρ²)` from the plane, so the angle is `atan2(ρ, ±h)`.
/// - `Crossing`: that angle, in `[0, π]` (below a right angle when `now` points toward the
///   point).
/// - `Disjoint { gap }`: no tilt reaches the distance: it is below `|L - r|` (the point in the
///   plane) or above `√(L² + r²)` (on the axis) by `gap`.
/// - `ZeroRadius`: the radius is not positive, or the point is at the centre (every tilt
///   leaves it `r` away).
pub fn tilt_to_distance(
    centre: &Point3<f64>,
    point: &Point3<f64>,
    radius: f64,
    distance: f64,
    now: &Vector3<f64>,
) -> Intersection<f64, 1> {
    let w = point - centre;
    let l = w.norm();
    let scale = tol::scale(&[l, radius, distance]);
    let least = tol::LENGTH_REL * scale;
    if radius.is_nan() || l.is_nan() || radius <= least || l <= least {
        return Intersection::none(Contact::ZeroRadius);
    }
    let (near, far) = ((l - radius).abs(), l.hypot(radius));
    if distance < near || distance > far {
        let gap = (near - distance).max(distance - far);
        return Intersection::none(Contact::Disjoint { gap });
    }
    let rho = ((l * l + radius * radius - distance * distance) / (2.0 * radius)).clamp(0.0, l);
    let h = ((l - rho) * (l + rho)).max(0.0).sqrt();
    let h = if now.dot(&w) < 0.0 { -h } else { h };
    intersect3d::one(rho.atan2(h), Contact::Crossing)
}

/// The unsigned angle between a line through `from` and the direction from `from` to `to` at
/// which the line passes `distance` from `to`: `asin(distance / L)`, `L` the distance between
/// the points, or its supplement when `now` (the line's direction now) points away from `to`,
/// so that the line keeps its sense.
/// - `Crossing`: that angle, in `[0, π]`.
/// - `Disjoint { gap }`: the distance exceeds `L` by `gap` (no line through `from` is that far).
/// - `ZeroRadius`: the points coincide.
pub fn passing_angle(
    from: &Point3<f64>,
    to: &Point3<f64>,
    distance: f64,
    now: &Vector3<f64>,
) -> Intersection<f64, 1> {
    let w = to - from;
    let l = w.norm();
    if l.is_nan() || distance.is_nan() || l <= tol::LENGTH_REL * tol::scale(&[l, distance]) {
        return Intersection::none(Contact::ZeroRadius);
    }
    if distance > l {
        return Intersection::none(Contact::Disjoint { gap: distance - l });
    }
    let d = distance.max(0.0);
    let along = ((l - d) * (l + d)).sqrt();
    let along = if now.dot(&w) < 0.0 { -along } else { along };
    intersect3d::one(d.atan2(along), Contact::Crossing)
}

#[cfg(test)]
mod tests {
    mod tilt {
        use super::super::*;
        use crate::Contact;

        /// The circle tilted by the angle found, about any axis across the direction to the point,
        /// leaves the point at the distance asked, on the side of `now`.
        #[test]
        fn a_tilt_puts_the_point_at_the_distance() {
            let (c, a) = (Point3::new(1.0, -2.0, 0.5), Point3::new(3.0, 1.0, 2.0));
            let w = (a - c).normalize();
            let across = w.cross(&Vector3::new(0.3, 0.1, 0.9)).normalize();
            for (r, d) in [(3.0, 1.2), (2.0, 2.5), (1.0, 3.5), (4.0, 0.7)] {
                for now in [w, -w] {
                    let i = tilt_to_distance(&c, &a, r, d, &now);
                    assert_eq!(i.contact, Contact::Crossing, "{r} {d}");
                    let theta = i.roots.get(0).unwrap_or(f64::NAN);
                    let n = w * theta.cos() + across * theta.sin();
                    assert!(n.dot(&now) >= 0.0 || theta == std::f64::consts::FRAC_PI_2);
                    // The point's distance from the tilted circle.
                    let v = a - c;
                    let hh = v.dot(&n);
                    let rho = (v - n * hh).norm();
                    let dist = hh.hypot(rho - r);
                    assert!((dist - d).abs() < 1e-14, "{r} {d}: {dist}");
                }
            }
            // Out of reach: nearer than the point in the plane, farther than on the axis.
            let l = (a - c).norm();
            let i = tilt_to_distance(&c, &a, 1.0, (l - 1.0) - 0.25, &w);
            assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 0.25).abs() < 1e-12));
            let i = tilt_to_distance(&c, &a, 1.0, l.hypot(1.0) + 0.5, &w);
            assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 0.5).abs() < 1e-12));
            assert_eq!(
                tilt_to_distance(&c, &c, 1.0, 1.0, &w).contact,
                Contact::ZeroRadius
            );
        }
    }

    mod passing {
        use super::super::*;
        use crate::Contact;

        /// A line through `from` at the angle found from the direction to `to` passes at the
        /// distance asked, keeping the sense `now` has.
        #[test]
        fn a_line_at_the_passing_angle_passes_at_the_distance() {
            let (from, to) = (Point3::new(0.5, -1.0, 2.0), Point3::new(2.0, 3.0, -1.0));
            let w = (to - from).normalize();
            let across = w.cross(&Vector3::new(0.2, 0.7, 0.1)).normalize();
            for d in [0.0, 0.3, 2.5, (to - from).norm()] {
                for now in [w, -w] {
                    let i = passing_angle(&from, &to, d, &now);
                    assert_eq!(i.contact, Contact::Crossing);
                    let a = i.roots.get(0).unwrap_or(f64::NAN);
                    let dir = w * a.cos() + across * a.sin();
                    let dist = (to - from).cross(&dir).norm();
                    assert!((dist - d).abs() < 1e-14, "{d}: {dist}");
                    assert!(dir.dot(&now) >= -1e-15);
                }
            }
            let l = (to - from).norm();
            let i = passing_angle(&from, &to, l + 0.5, &w);
            assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 0.5).abs() < 1e-12));
            assert_eq!(
                passing_angle(&from, &from, 1.0, &w).contact,
                Contact::ZeroRadius
            );
        }
    }
}
