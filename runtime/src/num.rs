//! The finiteness test of the kernel's solve paths, in one place; and the one way a number
//! is written in a message.

use std::fmt;

/// Whether `x` is finite (neither infinite nor NaN): the answer of [`f64::is_finite`], written
/// as `|x| <= f64::MAX`, one mask and one compare in the floating-point unit.
///
/// `f64::is_finite` compiles to integer operations on the bits, with 64-bit masks that each
/// take a general register; in a generated solve, whose values live across the call to
/// `sin_cos`, those were three callee-saved registers pushed and popped on every solve (13
/// instructions of the four-bar's 300, measured with callgrind).
#[inline(always)]
pub fn is_finite(x: f64) -> bool {
    x.abs() <= f64::MAX
}

/// The largest magnitude a solve takes as an input (a param, a default): the kernel's
/// intersections square lengths and coordinates and add a few squares, which stays far below
/// `f64::MAX` (about 1.8e308) for values up to this, and overflows past about 1e154. A larger
/// input is refused as such, rather than surfacing as an infinite or degenerate intersection.
pub const MAX_MAGNITUDE: f64 = 1e150;

/// Whether `x` is finite and at most [`MAX_MAGNITUDE`] in magnitude: the same one compare as
/// [`is_finite`], with a smaller bound.
#[inline(always)]
pub fn in_range(x: f64) -> bool {
    x.abs() <= MAX_MAGNITUDE
}

/// An angle brought into `(-π, π]`: how an outer iteration reports an angle default it
/// converged to (a turn more or less is the same assembly). An angle already in that range,
/// or not finite, is returned as it is, to the bit.
#[inline]
pub fn wrap_angle(t: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if !t.is_finite() || (-PI < t && t <= PI) {
        return t;
    }
    let w = t - TAU * (t / TAU).round();
    if w <= -PI {
        w + TAU
    } else if w > PI {
        w - TAU
    } else {
        w
    }
}

/// A number as messages write it (errors, diagnostics, reports): the shortest form that reads
/// back to the same `f64`, in exponent form past `1e15` or under `1e-4` (so that `1e308` is not
/// 309 digits), and zero without a sign.
///
/// ```
/// use gcs_runtime::num::Shown;
/// assert_eq!(Shown(3.0).to_string(), "3");
/// assert_eq!(Shown(-0.0).to_string(), "0");
/// assert_eq!(Shown(0.1 + 0.2).to_string(), "0.30000000000000004");
/// assert_eq!(Shown(1e308).to_string(), "1e308");
/// assert_eq!(Shown(-2.5e-7).to_string(), "-2.5e-7");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown(pub f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if x == 0.0 {
            f.write_str("0")
        } else if !x.is_finite() || (1e-4..1e15).contains(&a) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn wrap_angle_keeps_the_range_and_the_direction() {
        use std::f64::consts::PI;
        for t in [0.0, 1.0, -1.0, PI, -3.0, 3.1] {
            assert_eq!(super::wrap_angle(t).to_bits(), t.to_bits());
        }
        assert_eq!(super::wrap_angle(-PI), PI);
        for t in [-4.854430208822, 7.0, -20.0, 1e6, 4.0 * PI] {
            let w = super::wrap_angle(t);
            assert!(-PI < w && w <= PI, "{t} -> {w}");
            assert!((w.sin() - t.sin()).abs() < 1e-9 && (w.cos() - t.cos()).abs() < 1e-9);
        }
        assert!(super::wrap_angle(f64::NAN).is_nan());
    }

    use super::*;

    #[test]
    fn agrees_with_the_standard_test() {
        let cases = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 8.0,
            f64::EPSILON,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::from_bits(0x7ff0_0000_0000_0001),
            f64::from_bits(0xfff8_0000_0000_0001),
        ];
        for x in cases {
            assert_eq!(is_finite(x), x.is_finite(), "{x:e} ({:#x})", x.to_bits());
        }
    }

    #[test]
    fn shown_reads_back_and_stays_short() {
        for x in [
            1.0,
            -3.5,
            1e-4,
            9.99e14,
            1e15,
            1e-5,
            1e308,
            -1e-300,
            5e-324,
            f64::MAX,
            0.1,
        ] {
            let text = Shown(x).to_string();
            assert_eq!(text.parse::<f64>().ok(), Some(x), "{text}");
            assert!(text.len() <= 24, "{text}");
        }
        assert_eq!(Shown(f64::INFINITY).to_string(), "inf");
        assert_eq!(Shown(f64::NAN).to_string(), "NaN");
        assert_eq!(Shown(1e15).to_string(), "1e15");
        assert_eq!(Shown(123456.0).to_string(), "123456");
    }
}
