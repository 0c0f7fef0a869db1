//! Named tolerances, in one place, scaled to the magnitude of the inputs: the runtime's
//! (`gcs_runtime::tol`), and the language's checks of a model's constants. A crate of its own,
//! with no dependency, so that `gcs-lang` uses them without depending on the runtime.
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

/// Absolute tolerance under which the cosine of the angle between a marker's two axes, as
/// the model gives them, is zero: the axes are orthogonal.
pub const ORTHOGONAL: f64 = 1e-9;

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

/// How far the analysis moves each default (relative to one plus its size) to see which
/// run-time checks move with the defaults: small enough that the plan still assembles on the
/// sketch's branches, large enough that a residual that depends on a default moves far past
/// rounding.
pub const PROBE_MOVE: f64 = 1e-3;

/// Relative change (times one plus the model's size) under which a residual has not moved
/// when the defaults moved by [`PROBE_MOVE`]: rounding, a few hundred units in the last place.
/// A residual that moves at all, however little (near a tangency), depends on the defaults;
/// one built along a line it is measured across (a point displaced along the very line it
/// must lie on) moves by nothing or by rounding.
pub const PROBE_STILL: f64 = 1e-13;

/// Absolute length (in drawing units) under which a direction projected into a drawing's
/// view is seen end on: an arrow or a line along it is not drawn.
pub const END_ON: f64 = 1e-9;

/// One unit in the last place, relative to 1 (`f64::EPSILON`): twice the relative rounding of
/// one operation. Error bounds that count rounding in ulps use it by this name: Brent's
/// `2 ULP |b|` of a bracket's end, Horner's `2 n ULP` of a polynomial's magnitude, a Newton step
/// below one ulp of the point it moves (adding it changes nothing).
pub const ULP: f64 = f64::EPSILON;

/// `sqrt(f64::EPSILON)`: the relative size of a forward-difference step (it balances the
/// truncation error of the difference against the rounding of the two values), and the
/// relative precision to which a minimum's location can be found from function values.
pub const SQRT_EPS: f64 = 1.490_116_119_384_765_6e-8;

/// The absolute part of the tolerance on a root's or a minimum's location in `iterate`, as a
/// fraction of the relative one ([`ULP`] or [`SQRT_EPS`]) times the span or scale: a thousandth,
/// so that a location at or near zero is still found to well below the relative precision of
/// the locations around it, without iterating forever on one exactly at zero.
pub const LOCATE_ABS: f64 = 1e-3;

/// The step, in a default's scales (times `max(|y|, 1)` of the scaled default `y`), of the
/// central differences that measure the slope and the curvature of an outer iteration's closing
/// errors where it failed (`iterate`'s test for a minimum that is not zero): their truncation
/// (`h^2` times the errors' third derivatives) and the rounding of a second difference
/// (`eps / h^2` of the errors' size) are then both about `1e-8`. The test looks again with
/// steps sixteen times shorter, where the rounding is still below `1e-5`.
pub const CURVATURE_STEP: f64 = 1e-4;

/// A minimum of an outer iteration's squared closing errors is found when Newton's step would
/// lower their sum of squares by at most this fraction of it: their norm at the point is then
/// within half of this, relatively, of their norm at the bottom; far above the precision of the
/// differences' gradient there (whose error is proportional to the errors themselves).
pub const MINIMUM_CONFIRM_REL: f64 = 1e-6;

/// A step (or trust radius) at most this relative to the size of what it moves is at the
/// rounding level, four units in the last place: it no longer changes the point, and an
/// iteration stops there.
pub const STEP_STOP_REL: f64 = 4.0 * f64::EPSILON;

/// Roots of `iterate::all_roots` closer than this times `hi - lo` (across the wrap when
/// periodic) are the same root: a check's ([`CHECK_REL`]) size, far above the precision to
/// which a root is located, far below any distance between two roots a model means.
pub const SAME_ROOT_REL: f64 = 1e-9;

/// The default tolerance of an outer iteration (`iterate::Settings::default`), absolute in the
/// model's units: far above the rounding of an assembly of a model of size up to about 1e3
/// (whose residuals end near 1e-13), far below any error a drawing shows; the answer is
/// polished to rounding level past it anyway.
pub const OUTER_DEFAULT: f64 = 1e-10;

/// The trust-region iteration accepts a step when the reduction of the squared residual it
/// achieves is at least this fraction of the one its linear model predicted: the customary
/// small value, which rejects only a step that made things worse or nearly no better, so that
/// an accurate Jacobian's step is never thrown away for a rounding-level shortfall.
pub const TRUST_ACCEPT: f64 = 1e-4;

/// The directions' turn in `fragment3` is taken alone when their projections across the axis
/// multiply to at least this (each then lies over 0.1 rad from the axis): its angle is then
/// exact to about `eps / 0.1`, and a point could only add its own rounding.
pub const DIRECTIONS_DECIDE: f64 = 1e-2;

/// How far from 1 a rotation's `c² + s²` may be for one Newton step on the norm,
/// `(c, s) (3 - n) / 2`, to make it unit to rounding: the step leaves about `(3/8) off²`,
/// `(3/8) 1e-16` here, below one ulp. Past it (lengths that differ by more than about 5e-9
/// relative each) the rotation is normalised exactly, by a square root.
pub const NEWTON_UNIT: f64 = 1e-8;

/// A rotation's `|c² + s² - 1|` at most this is unit to rounding (four units in the last place,
/// as a cosine and sine computed from a point on its circle are): it is used as it is.
pub const UNIT_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// The smallest magnitude counted as nonzero: a scale (see [`scale`]) is never below it, and a
/// gradient no longer than it vanishes (a first-order distance `|f| / |∇f|` is then `|f|`). A
/// normal number far below any model's size, so that a tolerance scaled by it is never zero
/// and a division by a length above it does not overflow for any finite numerator of a model.
pub const TINY: f64 = 1e-300;

/// Newton's polishing of a point where two 2D curves cross is skipped when the sine of the
/// angle between their gradients is at most this: the curves are then nearly tangent, the
/// step's error grows as the inverse of that sine, and the point as found is kept.
pub const POLISH_MIN_SIN: f64 = 1e-6;

/// A line meets a conic in a close pair of roots that may be one tangency when half their
/// distance is at most this, relative to the point's magnitude: the cheap test before the
/// tangency's own test ([`TANGENT_REL`] on the residual), wide enough for any pair a rounding
/// of [`TANGENT_REL`] size splits a double root into (the split grows as its square root).
pub const TANGENT_SPLIT_REL: f64 = 1e-4;

/// A root of two conics' crossing within this (relative to the larger of the scale and the
/// tangent point's magnitude) of a tangent point found for the same pair is that tangency's
/// close partner, absorbed into it: a double root split by rounding lies about the square root
/// of [`TANGENT_REL`] from it, well within.
pub const TANGENT_ABSORB_REL: f64 = 1e-4;

/// The floor, as a fraction of the largest coefficient magnitude, under each coefficient's own
/// magnitude when two conics are tested for coincidence (every coefficient of one substituted
/// into the other within [`TANGENT_REL`] of it): a coefficient whose terms all nearly vanish is
/// judged against a thousandth of the largest, not against its own rounding alone.
pub const COINCIDENT_FLOOR_REL: f64 = 1e-3;

/// A cubic's discriminant is clearly away from zero (its roots well separated and accurate)
/// when it exceeds this times the size of its terms (and the shift's): far above the rounding
/// in the reduced coefficients and in the discriminant itself.
pub const CUBIC_CLEAR_REL: f64 = 1e-10;

/// A polynomial root's Newton step is final when its error, about `step² p'' / 2p'`, is at most
/// this times the root times `|p'|`: a quarter unit in the last place, so that the step's result
/// is the root rounded and no further evaluation could move it.
pub const QUARTER_ULP: f64 = 0.25 * f64::EPSILON;

/// A polynomial root's Newton step at most this relative to the point is at the rounding
/// level (two units in the last place): the root is polished.
pub const POLY_STEP_REL: f64 = 2.0 * f64::EPSILON;

/// Where a circle's closing error is first-order (`locus2d::Circle::closing_error`): the power
/// within this fraction of the radius squared (the distance within about half of it times the
/// radius). Within it the power over the diameter is the distance to within 0.25%, so that a
/// miss an iteration reports is the distance to that much; outside it the exact distance costs
/// one square root, on a trial far from closing anyway.
pub const CIRCLE_FIRST_ORDER: f64 = 1e-2;

/// The magnitude of a set of inputs: the largest absolute value among them, never below [`TINY`]
/// (1e-300) so that a tolerance scaled by it is never zero.
#[inline]
pub fn scale(values: &[f64]) -> f64 {
    // A plain comparison, not `f64::max`: it skips a NaN just the same and compiles to one
    // instruction, where `max` needs several to order signed zeros and NaNs.
    let mut s: f64 = TINY;
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

/// Relative tolerance under which a pivot of a linear stage's system vanishes, next to the
/// largest coefficient of its row (coefficients are dot and cross products of unit
/// directions): a constraint that does not fix the slide or length it was to fix. Rounding
/// leaves a structural zero near `1e-16`; a real near-parallel configuration stays far above.
pub const LINEAR_PIVOT_REL: f64 = 1e-12;

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
