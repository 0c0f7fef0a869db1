//! Residuals of constraints for a plan's run-time checks: how far an implied constraint is
//! from holding, in the constraint's units. The interpreter and generated solvers share them.

use crate::locus2d::{P2, V2};

/// The signed distance of `p` from the line through `base` along unit `dir`, positive to its
/// left.
#[inline]
pub fn signed_distance(base: P2, dir: V2, p: P2) -> f64 {
    let v = p - base;
    dir.x * v.y - dir.y * v.x
}

/// The counter-clockwise angle from `u` to `v`, in (-pi, pi].
#[inline]
pub fn angle(u: V2, v: V2) -> f64 {
    (u.x * v.y - u.y * v.x).atan2(u.dot(&v))
}

/// `|a - b|` modulo a full turn, in [0, pi].
#[inline]
pub fn angle_gap(a: f64, b: f64) -> f64 {
    let t = (a - b).rem_euclid(std::f64::consts::TAU);
    t.min(std::f64::consts::TAU - t)
}

/// How far two circles are from being `gap` apart at their perimeters, reading them as apart
/// or nested, whichever is nearer.
#[inline]
pub fn circles(c1: P2, r1: f64, c2: P2, r2: f64, gap: f64) -> f64 {
    let d = (c1 - c2).norm();
    (d - r1 - r2 - gap)
        .abs()
        .min(((r1 - r2).abs() - d - gap).abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residuals_measure_what_they_say() {
        let (o, x) = (P2::new(0.0, 0.0), V2::new(1.0, 0.0));
        assert_eq!(signed_distance(o, x, P2::new(3.0, 2.0)), 2.0);
        assert!((angle(x, V2::new(0.0, 1.0)) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!(angle_gap(3.1, -3.1) < 0.1);
        assert_eq!(circles(o, 1.0, P2::new(3.0, 0.0), 1.0, 1.0), 0.0);
        assert_eq!(circles(o, 3.0, P2::new(1.0, 0.0), 1.0, 0.0), 1.0);
    }
}
