//! Residuals of a plan's run-time checks: one function per kind of relation a check holds,
//! shared by the interpreter and every generated solver, so that both measure a check with
//! the same arithmetic and agree to the bit.
//!
//! A check re-measures a relation that earlier steps already imply. Each function returns how
//! far the relation is from holding, as a non-negative magnitude in the relation's units
//! (a length, or radians); a check fails when it exceeds the plan's tolerance, with that
//! magnitude in its error. A relation holds the reading the sketch gave it where the language
//! leaves a choice to the sketch (the sense of a parallel, the side of a tangency, internal or
//! external tangency): the plan relies on that reading, so the check measures that reading and
//! no other.

use crate::locus2d::{P2, V2};

/// How two circles sit, as the sketch has them: what a circle-circle distance measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Nesting {
    /// Each outside the other: `|c1 - c2| = r1 + r2 + gap`.
    Apart,
    /// The first inside the second: `|c1 - c2| = r2 - r1 - gap`.
    FirstInside,
    /// The second inside the first: `|c1 - c2| = r1 - r2 - gap`.
    SecondInside,
}

/// The signed distance of `p` from the line through `base` along unit `dir`, positive to its
/// left.
#[inline]
pub fn signed_distance(base: P2, dir: V2, p: P2) -> f64 {
    let v = p - base;
    dir.x * v.y - dir.y * v.x
}

/// `|a - b| = d` (a coincidence when `d` is 0): how far the distance is from `d`.
#[inline]
pub fn point_point(a: P2, b: P2, d: f64) -> f64 {
    error::point_point(a, b, d).abs()
}

/// The signed distance of `p` from the line through `base` along unit `dir` is `d`
/// (positive to the left; 0 for incidence).
#[inline]
pub fn point_line(p: P2, base: P2, dir: V2, d: f64) -> f64 {
    error::point_line(p, base, dir, d).abs()
}

/// The counter-clockwise angle from unit `u` to unit `v` is `angle`: how far `v` is from `u`
/// turned by `angle`, in radians (at most pi). Turning `u` by the target's cosine and sine,
/// rather than subtracting the target from a measured angle, keeps the residual exact for any
/// finite target (`1e300 - a` is `1e300` whatever `a` is).
#[inline]
pub fn angle(u: V2, v: V2, angle: f64) -> f64 {
    error::angle(u, v, angle).abs()
}

/// A circle (`centre`, `radius`) on side `side` (+1 left, -1 right) of the line through `base`
/// along unit `dir`, its perimeter `gap` from the line (0: tangent):
/// `side * sd(centre) = radius + gap`.
#[inline]
pub fn circle_line(centre: P2, radius: f64, base: P2, dir: V2, gap: f64, side: f64) -> f64 {
    error::circle_line(centre, radius, base, dir, gap, side).abs()
}

/// Point `p` at distance `gap` from the perimeter of the circle (`centre`, `radius`), outside
/// it or inside it (0: on it): `|p - centre| = radius ± gap`.
#[inline]
pub fn point_circle(p: P2, centre: P2, radius: f64, gap: f64, outside: bool) -> f64 {
    error::point_circle(p, centre, radius, gap, outside).abs()
}

/// Two circles whose perimeters are `gap` apart (0: tangent), sitting as `nesting` says.
#[inline]
pub fn circle_circle(c1: P2, r1: f64, c2: P2, r2: f64, gap: f64, nesting: Nesting) -> f64 {
    error::circle_circle(c1, r1, c2, r2, gap, nesting).abs()
}

/// A dimension (a segment's length, a circle's radius) `value` is `target`.
#[inline]
pub fn dimension(value: f64, target: f64) -> f64 {
    error::dimension(value, target).abs()
}

/// `p` is the midpoint of `a` and `b`: how far it is from it.
#[inline]
pub fn midpoint(p: P2, a: P2, b: P2) -> f64 {
    (crate::locus2d::midpoint(a, b) - p).norm()
}

/// `q` is the mirror image of `p` across the line through `base` along unit `dir`: how far it
/// is from that image.
#[inline]
pub fn mirror(p: P2, q: P2, base: P2, dir: V2) -> f64 {
    (q - crate::locus2d::mirror(base, dir, p)).norm()
}

/// The signed errors of the residuals above, zero when the relation holds: the error
/// functions an outer iteration drives to zero (its sign tells a root finder which side it
/// is on). Each residual above is the magnitude of its error, computed by it.
pub mod error {
    use super::{signed_distance, Nesting, P2, V2};

    /// `|a - b| - d`.
    #[inline]
    pub fn point_point(a: P2, b: P2, d: f64) -> f64 {
        (a - b).norm() - d
    }

    /// One coordinate (`axis` 0 for x, 1 for y) of `b - a`: a coincidence closes two errors.
    #[inline]
    pub fn coincidence(a: P2, b: P2, axis: u8) -> f64 {
        let v = b - a;
        if axis == 0 {
            v.x
        } else {
            v.y
        }
    }

    /// The signed distance of `p` from the line through `base` along unit `dir`, minus `d`.
    #[inline]
    pub fn point_line(p: P2, base: P2, dir: V2, d: f64) -> f64 {
        signed_distance(base, dir, p) - d
    }

    /// The counter-clockwise angle from `u` turned by `angle` to `v`, in (-pi, pi].
    #[inline]
    pub fn angle(u: V2, v: V2, angle: f64) -> f64 {
        let (s, c) = angle.sin_cos();
        let w = V2::new(u.x * c - u.y * s, u.x * s + u.y * c);
        (w.x * v.y - w.y * v.x).atan2(w.dot(&v))
    }

    /// `side * sd(centre) - radius - gap`.
    #[inline]
    pub fn circle_line(centre: P2, radius: f64, base: P2, dir: V2, gap: f64, side: f64) -> f64 {
        side * signed_distance(base, dir, centre) - radius - gap
    }

    /// `|p - centre| - (radius ± gap)`.
    #[inline]
    pub fn point_circle(p: P2, centre: P2, radius: f64, gap: f64, outside: bool) -> f64 {
        let reach = if outside { radius + gap } else { radius - gap };
        (p - centre).norm() - reach
    }

    /// `|c1 - c2|` minus the distance of centres `nesting` and `gap` ask for.
    #[inline]
    pub fn circle_circle(c1: P2, r1: f64, c2: P2, r2: f64, gap: f64, nesting: Nesting) -> f64 {
        let apart = match nesting {
            Nesting::Apart => r1 + r2 + gap,
            Nesting::FirstInside => r2 - r1 - gap,
            Nesting::SecondInside => r1 - r2 - gap,
        };
        (c1 - c2).norm() - apart
    }

    /// `value - target`.
    #[inline]
    pub fn dimension(value: f64, target: f64) -> f64 {
        value - target
    }

    /// One coordinate (`axis` 0 for x, 1 for y) of `p` less the midpoint of `a` and `b`: a
    /// midpoint closes two errors, as a coincidence does.
    #[inline]
    pub fn midpoint(p: P2, a: P2, b: P2, axis: u8) -> f64 {
        coincidence(crate::locus2d::midpoint(a, b), p, axis)
    }

    /// One coordinate (`axis` 0 for x, 1 for y) of `q` less the mirror image of `p` across the
    /// line through `base` along unit `dir`.
    #[inline]
    pub fn mirror(p: P2, q: P2, base: P2, dir: V2, axis: u8) -> f64 {
        coincidence(crate::locus2d::mirror(base, dir, p), q, axis)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn residuals_measure_what_they_say() {
        let (o, x) = (P2::new(0.0, 0.0), V2::new(1.0, 0.0));
        let y = V2::new(0.0, 1.0);
        assert_eq!(signed_distance(o, x, P2::new(3.0, 2.0)), 2.0);
        assert_eq!(point_point(o, P2::new(3.0, 4.0), 5.0), 0.0);
        assert_eq!(point_point(o, P2::new(3.0, 4.0), 0.0), 5.0);
        assert_eq!(point_line(P2::new(3.0, 2.0), o, x, 2.0), 0.0);
        assert_eq!(point_line(P2::new(3.0, -2.0), o, x, 2.0), 4.0);
        assert!(angle(x, y, FRAC_PI_2) < 1e-15);
        assert!((angle(x, y, -FRAC_PI_2) - PI).abs() < 1e-15);
        // The sense the relation holds: anti-parallel is pi away from parallel.
        assert!((angle(x, -x, 0.0) - PI).abs() < 1e-15);
        assert!(angle(x, -x, PI) < 1e-15);
        assert_eq!(circle_line(P2::new(0.0, 2.0), 1.0, o, x, 1.0, 1.0), 0.0);
        assert_eq!(circle_line(P2::new(0.0, -2.0), 1.0, o, x, 1.0, 1.0), 4.0);
        assert_eq!(circle_line(P2::new(0.0, -2.0), 1.0, o, x, 1.0, -1.0), 0.0);
        assert_eq!(point_circle(P2::new(3.0, 0.0), o, 2.0, 1.0, true), 0.0);
        assert_eq!(point_circle(P2::new(1.0, 0.0), o, 2.0, 1.0, false), 0.0);
        assert_eq!(point_circle(P2::new(1.0, 0.0), o, 2.0, 1.0, true), 2.0);
        let c = P2::new(3.0, 0.0);
        assert_eq!(circle_circle(o, 1.0, c, 1.0, 1.0, Nesting::Apart), 0.0);
        assert_eq!(
            circle_circle(o, 1.0, c, 5.0, 1.0, Nesting::FirstInside),
            0.0
        );
        assert_eq!(
            circle_circle(o, 5.0, c, 1.0, 1.0, Nesting::SecondInside),
            0.0
        );
        assert_eq!(circle_circle(o, 5.0, c, 1.0, 1.0, Nesting::Apart), 4.0);
        assert_eq!(dimension(2.5, 2.0), 0.5);
        let (a, b) = (P2::new(1.0, 1.0), P2::new(3.0, 5.0));
        assert_eq!(midpoint(P2::new(2.0, 3.0), a, b), 0.0);
        assert_eq!(midpoint(P2::new(2.0, 6.0), a, b), 3.0);
        assert_eq!(error::midpoint(P2::new(2.0, 6.0), a, b, 1), 3.0);
        assert_eq!(mirror(P2::new(3.0, 2.0), P2::new(3.0, -2.0), o, x), 0.0);
        assert_eq!(mirror(P2::new(3.0, 2.0), P2::new(3.0, 2.0), o, x), 4.0);
        assert_eq!(
            error::mirror(P2::new(3.0, 2.0), P2::new(3.0, 2.0), o, x, 1),
            4.0
        );
        assert_eq!(
            error::mirror(P2::new(3.0, 2.0), P2::new(3.0, 2.0), o, x, 0),
            0.0
        );
        // Across the y axis, the x coordinate changes sign.
        assert_eq!(mirror(P2::new(3.0, 2.0), P2::new(-3.0, 2.0), o, y), 0.0);
    }

    #[test]
    fn a_huge_angle_is_measured_exactly() {
        let t = 1e300_f64;
        let (s, c) = t.sin_cos();
        let u = V2::new(0.6, 0.8);
        let v = V2::new(u.x * c - u.y * s, u.x * s + u.y * c);
        assert!(angle(u, v, t) < 1e-15);
    }
}

/// The residuals of checks in space: the same contract as the plane's, over 3d points and
/// unit directions.
pub mod space {
    use nalgebra::{Point3, Vector3};

    type P3 = Point3<f64>;
    type V3 = Vector3<f64>;

    /// `|a - b| = d` (a coincidence when `d` is 0): how far the distance is from `d`.
    #[inline]
    pub fn point_point(a: P3, b: P3, d: f64) -> f64 {
        ((a - b).norm() - d).abs()
    }

    /// `p` at distance `d` from the line through `base` along unit `dir` (on it when `d` is
    /// 0): how far its distance is from `d`.
    #[inline]
    pub fn point_line(p: P3, base: P3, dir: V3, d: f64) -> f64 {
        ((p - base).cross(&dir).norm() - d).abs()
    }

    /// `p`'s offset across the line through `base` along `dir`: its two signed coordinates
    /// along `frame::perpendicular` of the unit direction and along the direction crossed
    /// with that (both zero on the line). Where a point on a line closes two defaults of an
    /// iteration, these are its two errors.
    #[inline]
    pub fn across_line(p: P3, base: P3, dir: V3) -> [f64; 2] {
        let dir = dir.normalize();
        let across = crate::frame::perpendicular(&dir);
        let w = p - base;
        [w.dot(&across), w.dot(&dir.cross(&across))]
    }

    /// The signed distance of `p` from the plane through `base` with unit `normal` is `d`.
    #[inline]
    pub fn point_plane(p: P3, base: P3, normal: V3, d: f64) -> f64 {
        ((p - base).dot(&normal) - d).abs()
    }

    /// `p` is the midpoint of `a` and `b`: how far it is from it.
    #[inline]
    pub fn midpoint(p: P3, a: P3, b: P3) -> f64 {
        (crate::locus3d::midpoint(a, b) - p).norm()
    }

    /// `q` is the mirror image of `p` across the plane through `base` with unit `normal`:
    /// how far it is from that image.
    #[inline]
    pub fn mirror(p: P3, q: P3, base: P3, normal: V3) -> f64 {
        (q - crate::locus3d::mirror(base, normal, p)).norm()
    }

    /// The unsigned angle between unit `u` and unit `v` is `angle`: how far it is, in
    /// radians.
    #[inline]
    pub fn angle_between(u: V3, v: V3, angle: f64) -> f64 {
        (u.cross(&v).norm().atan2(u.dot(&v)) - angle).abs()
    }

    /// Unit `v` along `sense * u` (`sense` +1 or -1, or 0 for either): the angle between
    /// them, in radians.
    #[inline]
    pub fn parallel(u: V3, v: V3, sense: f64) -> f64 {
        let sense = if sense != 0.0 {
            sense
        } else if u.dot(&v) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let w = u * sense;
        w.cross(&v).norm().atan2(w.dot(&v))
    }

    /// The angle from unit `u` to unit `v`, counter-clockwise about unit `axis`, is `angle`:
    /// how far `v` is from `u` turned so, in radians (at most pi), by turning `u` with the
    /// target's cosine and sine (Rodrigues' formula) rather than subtracting angles.
    #[inline]
    pub fn twist(axis: V3, u: V3, v: V3, angle: f64) -> f64 {
        let (s, c) = angle.sin_cos();
        let w = u * c + axis.cross(&u) * s + axis * (axis.dot(&u) * (1.0 - c));
        w.cross(&v).norm().atan2(w.dot(&v))
    }

    /// Unit `u` and unit `v` make the same angle with unit `axis` (a turn about `axis` can
    /// take one onto the other): how far apart their components along it are.
    #[inline]
    pub fn cone(axis: V3, u: V3, v: V3) -> f64 {
        (u - v).dot(&axis).abs()
    }

    /// A helix: the angle from unit `u` to unit `v` about unit `axis` is `2pi s / pitch`, `s`
    /// the advance `offset . axis`: how far `v` is from `u` turned so, in radians (modulo a
    /// turn, as [`twist`] measures it).
    #[inline]
    pub fn helix(axis: V3, u: V3, v: V3, offset: V3, pitch: f64) -> f64 {
        twist(
            axis,
            u,
            v,
            std::f64::consts::TAU * offset.dot(&axis) / pitch,
        )
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        #[test]
        fn a_helix_turns_a_quarter_for_a_quarter_pitch() {
            let x = V3::x();
            assert!(helix(V3::z(), x, V3::y(), V3::new(0.0, 0.0, 0.5), 2.0) < 1e-15);
            assert!(
                (helix(V3::z(), x, x, V3::new(0.0, 0.0, 0.5), 2.0) - std::f64::consts::FRAC_PI_2)
                    .abs()
                    < 1e-15
            );
            // A whole pitch is a whole turn.
            assert!(helix(V3::z(), x, x, V3::new(1.0, 0.0, 2.0), 2.0) < 1e-15);
        }

        #[test]
        fn residuals_measure_what_they_say() {
            let o = P3::origin();
            assert_eq!(point_point(o, P3::new(3.0, 4.0, 0.0), 5.0), 0.0);
            assert!((point_line(P3::new(1.0, 2.0, 0.0), o, V3::x(), 0.0) - 2.0).abs() < 1e-15);
            assert!((point_plane(P3::new(0.0, 0.0, 1.5), o, V3::z(), 1.0) - 0.5).abs() < 1e-15);
            assert!((parallel(V3::x(), -V3::x(), -1.0)).abs() < 1e-15);
            assert!((parallel(V3::x(), V3::y(), 1.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
            let quarter = std::f64::consts::FRAC_PI_2;
            assert!(twist(V3::z(), V3::x(), V3::y(), quarter) < 1e-15);
            assert!((twist(V3::z(), V3::x(), V3::y(), 0.0) - quarter).abs() < 1e-15);
            assert!(
                (twist(V3::z(), V3::x(), -V3::y(), quarter) - std::f64::consts::PI).abs() < 1e-12
            );
        }
    }
}
