//! The finiteness test of the kernel's solve paths, in one place; the sine and cosine every
//! turn by an angle uses ([`sin_cos`], inlined, and [`sin_cos_small`] for small angles), shared
//! by the interpreter and generated code so that both agree to the bit; and the one way a
//! number is written in a message.

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

/// `(sin x, cos x)`, as [`f64::sin_cos`] to within an ulp, in about a third of its time for the
/// angles a plan turns by (|x| up to about 8e5; beyond, and for non-finite `x`, it is
/// [`f64::sin_cos`]).
///
/// An outer iteration over an angle evaluates it once per trial, and the system library's
/// `sincos` (a call of about 100 instructions with its argument reduction for any `x`) was a
/// quarter of a warm triad solve. Here `x` is reduced by `pi/2` in a Cody-Waite scheme of two
/// rounds (the remainder good to about 118 bits, so angles near a multiple of `pi/2` keep full
/// relative accuracy), and the remainder's sine and cosine are the minimax polynomials of
/// FreeBSD's msun (`__kernel_sin`, `__kernel_cos`), inlined. The coefficients and the
/// reduction's constants are msun's, whose notice reads: "Copyright (C) 1993 by Sun
/// Microsystems, Inc. All rights reserved. Developed at SunPro, a Sun Microsystems, Inc.
/// business. Permission to use, copy, modify, and distribute this software is freely granted,
/// provided that this notice is preserved."
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // 2/pi, and pi/2 split in two parts of 33 bits each (so their products with a quotient
    // below 2^20 are exact) and a tail; msun's constants, by their bits.
    const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
    const PIO2_1: f64 = f64::from_bits(0x3FF921FB54400000);
    const PIO2_2: f64 = f64::from_bits(0x3DD0B4611A600000);
    const PIO2_2T: f64 = f64::from_bits(0x3BA3198A2E037073);
    // Adding and subtracting 1.5 * 2^52 rounds to the nearest integer (for |v| < 2^51).
    const TO_INT: f64 = 1.5 / f64::EPSILON;
    // Beyond this the quotient reaches 2^19 and the two-part products stop being exact.
    const MEDIUM: f64 = 8.0e5;
    if x.abs() > MEDIUM || x.is_nan() {
        return x.sin_cos();
    }
    let n = (x * TWO_OVER_PI + TO_INT) - TO_INT;
    let r = x - n * PIO2_1;
    let w = n * PIO2_2;
    let y0 = r - w;
    let tail = n * PIO2_2T - ((r - y0) - w);
    let y = y0 - tail;
    let dy = (y0 - y) - tail;
    let (s, c) = (kernel_sin(y, dy), kernel_cos(y, dy));
    // `n` is an integer below 2^20 in magnitude: its quadrant is its value modulo 4.
    match (n as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// The largest angle [`sin_cos_small`] takes: 1/64 radian (0.9 degrees), where its
/// polynomials' first dropped terms are below 1e-19 of their results.
pub const SMALL_ANGLE: f64 = 0.015_625;

/// `(sin x, cos x)` for `|x| <=` [`SMALL_ANGLE`], within an ulp of [`sin_cos`]: the Taylor
/// polynomials through `x^7` and `x^6`, with no argument reduction (the turn between two trials
/// of an outer iteration, [`crate::frame::DirectionsNear`]). Evaluated in two halves side by
/// side (Estrin's scheme), so that the processor waits on fewer products in a row.
#[inline(always)]
pub fn sin_cos_small(x: f64) -> (f64, f64) {
    let z = x * x;
    let w = z * z;
    let sin = x + x * (z * (-1.0 / 6.0) + w * (1.0 / 120.0 - z * (1.0 / 5040.0)));
    let cos = 1.0 - 0.5 * z + w * (1.0 / 24.0 - z * (1.0 / 720.0));
    (sin, cos)
}

/// `sin(y + dy)` for `|y| <= pi/4` and `|dy|` below half an ulp of `y` (msun's
/// `__kernel_sin` with its tail).
#[inline(always)]
fn kernel_sin(y: f64, dy: f64) -> f64 {
    const S1: f64 = f64::from_bits(0xBFC5555555555549);
    const S2: f64 = f64::from_bits(0x3F8111111110F8A6);
    const S3: f64 = f64::from_bits(0xBF2A01A019C161D5);
    const S4: f64 = f64::from_bits(0x3EC71DE357B1FE7D);
    const S5: f64 = f64::from_bits(0xBE5AE5E68A2B9CEB);
    const S6: f64 = f64::from_bits(0x3DE5D93A5ACFD57C);
    let z = y * y;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * y;
    y - ((z * (0.5 * dy - v * r) - dy) - v * S1)
}

/// `cos(y + dy)` for `|y| <= pi/4` and `|dy|` below half an ulp of `y` (msun's
/// `__kernel_cos`).
#[inline(always)]
fn kernel_cos(y: f64, dy: f64) -> f64 {
    const C1: f64 = f64::from_bits(0x3FA555555555554C);
    const C2: f64 = f64::from_bits(0xBF56C16C16C15177);
    const C3: f64 = f64::from_bits(0x3EFA01A019CB1590);
    const C4: f64 = f64::from_bits(0xBE927E4F809C52AD);
    const C5: f64 = f64::from_bits(0x3E21EE9EBDB4B1C4);
    const C6: f64 = f64::from_bits(0xBDA8FAE9BE8838D4);
    let z = y * y;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let one_minus = 1.0 - hz;
    one_minus + (((1.0 - one_minus) - hz) + (z * r - y * dy))
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
    use proptest::prelude::*;

    /// How far `a` is from `b` in units of `b`'s last place (of `f64::MIN_POSITIVE` for
    /// zero or subnormal `b`).
    fn ulps(a: f64, b: f64) -> f64 {
        (a - b).abs() / (b.abs().max(f64::MIN_POSITIVE) * f64::EPSILON)
    }

    /// Within two units in the last place of the system library's sine and cosine (which are
    /// within one of the true values), so within three of the truth.
    fn close_to_std(x: f64) -> Result<(), TestCaseError> {
        let (s, c) = super::sin_cos(x);
        let (s0, c0) = x.sin_cos();
        prop_assert!(ulps(s, s0) <= 2.0, "sin {x:e}: {s:e} against {s0:e}");
        prop_assert!(ulps(c, c0) <= 2.0, "cos {x:e}: {c:e} against {c0:e}");
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        #[test]
        fn sin_cos_matches_the_system_library(x in -1e3f64..1e3) {
            close_to_std(x)?;
        }

        #[test]
        fn sin_cos_matches_it_over_its_whole_reduced_range(x in -8.0e5f64..8.0e5) {
            close_to_std(x)?;
        }

        /// Near a multiple of pi/2 the reduction cancels: the remainder keeps its relative
        /// accuracy (a result near zero is as accurate as one near one).
        #[test]
        fn sin_cos_keeps_its_accuracy_near_multiples_of_half_pi(
            k in -2000i32..2000,
            offset in prop_oneof![-1e-6f64..1e-6, -1e-12f64..1e-12, Just(0.0)],
        ) {
            close_to_std(f64::from(k) * std::f64::consts::FRAC_PI_2 + offset)?;
        }

        #[test]
        fn sin_cos_is_tiny_angles_own_sine(x in -1e-8f64..1e-8) {
            close_to_std(x)?;
        }

        /// The polynomials of a small angle: within an ulp of the system library (which is
        /// within one of the truth), down to tiny angles, where the sine is the angle.
        #[test]
        fn sin_cos_small_matches_the_system_library(
            x in prop_oneof![
                -super::SMALL_ANGLE..=super::SMALL_ANGLE,
                -1e-6f64..1e-6,
                -1e-300f64..1e-300,
            ],
        ) {
            let (s, c) = super::sin_cos_small(x);
            let (s0, c0) = x.sin_cos();
            prop_assert!(ulps(s, s0) <= 1.0, "sin {x:e}: {s:e} against {s0:e}");
            prop_assert!(ulps(c, c0) <= 1.0, "cos {x:e}: {c:e} against {c0:e}");
        }
    }

    #[test]
    fn sin_cos_outside_its_range_is_the_system_librarys() {
        for x in [8.0e5 + 1.0, -1e9, 1e300, f64::MAX] {
            assert_eq!(super::sin_cos(x), x.sin_cos());
        }
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let (s, c) = super::sin_cos(x);
            assert!(s.is_nan() && c.is_nan());
        }
        assert_eq!(super::sin_cos(0.0), (0.0, 1.0));
        assert!(super::sin_cos(-0.0).0.is_sign_negative());
        for x in [super::SMALL_ANGLE, -super::SMALL_ANGLE] {
            let ((s, c), (s0, c0)) = (super::sin_cos_small(x), x.sin_cos());
            assert!(ulps(s, s0) <= 1.0 && ulps(c, c0) <= 1.0, "{x}");
        }
    }

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
