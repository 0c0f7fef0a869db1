//! Named tolerances, in one place, scaled to the magnitude of the inputs.
//!
//! Every comparison against "zero" in the kernel goes through this module, so that a model drawn
//! in micrometres behaves exactly like the same model drawn in kilometres. A tolerance is always
//! *relative*: it is multiplied by a [`scale`] computed from the inputs of the operation.

/// Relative tolerance under which two lengths are the same, or a length is zero:
/// about 64 units in the last place of the inputs.
pub const LENGTH_REL: f64 = 64.0 * f64::EPSILON;

/// Absolute tolerance under which an angle (radians) or the sine of one is zero, and two unit
/// vectors are parallel.
pub const ANGLE: f64 = 1e-12;

/// Relative tolerance (times one plus the largest coordinate involved) under which a point
/// given by the model's constants lies in a plane given by them: its height above the plane is
/// zero. The analysis reads by it whether two fixed circles lie in one plane or in parallel
/// planes apart, before any plan runs.
pub const COPLANAR_REL: f64 = 1e-12;

/// Relative tolerance of a plan's run-time checks (an implied constraint re-measured, a point
/// that must lie on a locus), times one plus the model's scale: far above rounding, far below
/// any violation a user would call small.
pub const CHECK_REL: f64 = 1e-9;

/// Relative tolerance on the error functions of an outer iteration (times `1 + scale`): a
/// thousandth of a check's, so that a plan that iterates meets its constraints as closely as
/// one in closed form; `iterate::solve` then polishes to rounding level where it can.
pub const ITERATION_REL: f64 = 1e-12;

/// Relative size (times `1 + scale`) of a residual that is rounding: two units in the last
/// place of the model's size. An outer iteration that reaches it takes no polishing step, as
/// the next step's change would be as small as the noise of evaluating the residual.
pub const ROUNDING_REL: f64 = 2.0 * f64::EPSILON;

/// Relative tolerance of a tangency: loci whose gap or overlap is below this, relative to the
/// scale, touch in one double root rather than missing each other or crossing twice. It is a
/// few units of rounding: loci built by earlier steps of a plan carry that much, and a gap any
/// larger is real (the stress sweeps report it as an error with its size rather than answer
/// with a residual of half of it).
pub const TANGENT_REL: f64 = 32.0 * f64::EPSILON;

/// Relative tolerance under which a polynomial's value counts as zero, in units of its running
/// error bound: `|p(x)| <= POLY_ZERO_REL * degree * sum |c_i| |x|^i` is indistinguishable from
/// zero by Horner evaluation (and by the rounding of coefficients built from their roots), so a
/// critical point with such a value is reported as a multiple root.
pub const POLY_ZERO_REL: f64 = 8.0 * f64::EPSILON;

/// Relative tolerance under which two solutions of one model are one assembly: every point
/// within this times `1 + ` the largest coordinate of the first solution's points, every
/// (unit) vector within this. It is a check's ([`CHECK_REL`]) size: two solutions that differ
/// by less both satisfy the same constraints as closely as a plan checks them.
pub const SAME_ASSEMBLY_REL: f64 = 1e-9;

/// Relative tolerance (times `1 + radius`) under which the verifier counts a segment's end as
/// joined to a circle, for a tangency's touching point (a fillet's joint): an end solved onto
/// the circle lies there to rounding, while a free end a distance `t` along the tangent from
/// the touching point lies `t² / 2r` from the circle. At 1e-6, a free end 2e-3 from the
/// touching point of a circle of radius 2 counted as a joint; at 1e-9 only ends within about
/// 1e-4 do.
pub const JOINED_REL: f64 = 1e-9;

/// Absolute length (in drawing units) under which a direction projected into a drawing's
/// view is seen end on: an arrow or a line along it is not drawn.
pub const END_ON: f64 = 1e-9;

/// The magnitude of a set of inputs: the largest absolute value among them, never below 1e-300
/// so that a tolerance scaled by it is never zero.
#[inline]
pub fn scale(values: &[f64]) -> f64 {
    // A plain comparison, not `f64::max`: it skips a NaN just the same and compiles to one
    // instruction, where `max` needs several to order signed zeros and NaNs.
    let mut s: f64 = 1e-300;
    for v in values {
        let a = v.abs();
        if a > s {
            s = a;
        }
    }
    s
}

/// Whether `x` is zero relative to `scale`, with relative tolerance `rel`.
#[inline]
pub fn is_zero(x: f64, scale: f64, rel: f64) -> bool {
    x.abs() <= rel * scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_is_never_zero_and_tracks_magnitude() {
        assert!(scale(&[0.0, 0.0]) > 0.0);
        assert_eq!(scale(&[1e6, -3e6, 2.0]), 3e6);
        assert!(is_zero(1e-10, 1e6, LENGTH_REL));
        assert!(!is_zero(1e-10, 1.0, LENGTH_REL));
    }
}
