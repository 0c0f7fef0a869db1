//! Errors of a solve and the error accumulator of plans with defaults.
//!
//! A [`SolveError`] names the user's constraint by its label and source text, says what went
//! wrong ([`ErrorKind`]) and by how much. Generated solvers build it from string literals
//! (`Cow::Borrowed`, no allocation); the interpreter may pass owned strings.
//!
//! An [`ErrorAccumulator`] measures how far an assembly is from closing when a plan had to
//! default some degrees of freedom (paper 000, section 5.2.1): see its documentation for how an
//! outer iteration uses it.

use std::borrow::Cow;
use std::fmt;

use crate::roots::Contact;

/// What kind of failure a [`SolveError`] reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// Two loci do not meet: the magnitude is the gap by which they miss.
    NoIntersection,
    /// The constraint contradicts those already met (e.g. a distance that differs from one
    /// already fixed): the magnitude is the size of the contradiction.
    Inconsistent,
    /// The configuration is degenerate (coincident or zero-size loci, a zero axis): the
    /// constraint does not determine the geom. The magnitude is the offending size, often 0.
    Degenerate,
    /// An outer iteration did not converge, and nothing more could be said: the magnitude is
    /// the residual it reached. Where the iteration could tell why, it is
    /// [`ErrorKind::NoAssembly`] or [`ErrorKind::NoAssemblyNear`] instead.
    NoConvergence,
    /// An outer iteration over one default, an angle, found no value of it at which the
    /// constraint it closes closes, over the whole turn: no assembly exists here with the
    /// branches chosen and the other defaults as given (a default that parameterises a free
    /// motion keeps its value). The magnitude is the smallest closing error found over the
    /// turn: how far the constraint stays from closing.
    NoAssembly,
    /// An outer iteration came to a minimum of its closing errors that is not zero, near the
    /// defaults it started from: the assembly it follows from there does not exist here (in a
    /// sweep, the one followed ended at a fold between the last answer and here), though
    /// another may, from other defaults. The magnitude is the errors' norm at that minimum
    /// (the root of the sum of their squares; with one default, its one error): near there, no
    /// value of the defaults brings the constraints closer to closing.
    NoAssemblyNear,
    /// An input is invalid, such as a NaN or infinite parameter, or a sketch the params make
    /// non-finite: the magnitude is the value.
    InvalidInput,
    /// A constraint's value, computed from finite params, cannot be used: an angle or distance
    /// that is not finite (`theta * 1e300`), or a negative size. The magnitude is the value.
    InvalidValue,
    /// A default parameter's given value cannot be used: a length or a radius it fixes is
    /// negative. The label is the default's name, the text what it fixes; the magnitude is
    /// the value.
    InvalidDefault,
    /// A param's value cannot be used: a constraint takes it as a size (a length, a distance,
    /// a radius) and it is negative. The label is the param's name, the text the constraint's;
    /// the magnitude is the value.
    InvalidParam,
    /// The loci meet, but not in the chosen branch: the magnitude is how many real roots the
    /// intersection has. The solver never takes another branch instead.
    NoSuchBranch,
    /// A profile cannot close with its segments running as sketched: the length a segment
    /// needs to reach where its end must be (along its own direction, or from a linear stage
    /// of free lengths) is negative, though a segment keeps the direction its sketch gives
    /// it. The label is the constraint that gives that length; the magnitude is the length.
    CannotClose,
    /// An outer iteration started from the sketch's defaults closes here only in another
    /// assembly mode than the sketch's (`crate::mode`): every root it found has the other
    /// orientation, across a fold from the sketch's. The label is the iteration's first
    /// close; the magnitude is how many such roots were found. Solving from other defaults
    /// (a root of `solve_all`) takes one.
    OtherMode,
}

/// The failure of a solve, naming the user's constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveError {
    /// The constraint's label (for [`ErrorKind::InvalidInput`], the parameter's or the
    /// geom's name).
    pub label: Cow<'static, str>,
    /// The constraint's source text, e.g. `coincident(coupler.c, rocker.c)`; may be empty.
    pub text: Cow<'static, str>,
    /// What went wrong.
    pub kind: ErrorKind,
    /// The magnitude of the violation, in the constraint's units (length or radians).
    pub magnitude: f64,
}

impl SolveError {
    /// An error for the constraint `label` with source `text` (string literals or owned
    /// strings; literals do not allocate). Cold and out of line: a solve's error paths are
    /// then a call each, laid out away from the straight line of its steps.
    #[cold]
    #[inline(never)]
    pub fn new(
        label: impl Into<Cow<'static, str>>,
        text: impl Into<Cow<'static, str>>,
        kind: ErrorKind,
        magnitude: f64,
    ) -> Self {
        Self {
            label: label.into(),
            text: text.into(),
            kind,
            magnitude,
        }
    }

    /// The error for loci that miss each other, as an intersection that reports only its
    /// misses (such as [`crate::intersect2d::circle_circle_chord`]) gives it: the error of
    /// [`SolveError::from_contact`].
    #[inline]
    pub fn from_miss(label: &'static str, text: &'static str, contact: Contact) -> Self {
        match contact {
            Contact::Disjoint { gap } | Contact::Parallel { gap } => {
                Self::new(label, text, ErrorKind::NoIntersection, gap)
            }
            // Coincident, zero radius; and a meeting, which a miss never is.
            _ => Self::new(label, text, ErrorKind::Degenerate, 0.0),
        }
    }

    /// The error an intersection's classification means for the constraint, if any:
    /// `Disjoint` and `Parallel` are [`ErrorKind::NoIntersection`] with the gap, `Coincident`
    /// and `ZeroRadius` are [`ErrorKind::Degenerate`] (magnitude 0); `Crossing` and `Tangent`
    /// are no error.
    #[inline]
    pub fn from_contact(label: &'static str, text: &'static str, contact: Contact) -> Option<Self> {
        match contact {
            Contact::Crossing | Contact::Tangent => None,
            miss => Some(Self::from_miss(label, text, miss)),
        }
    }
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = crate::num::Shown(self.magnitude);
        if self.kind == ErrorKind::InvalidInput {
            // A parameter has no text; a geom's sketch says what is wrong with it.
            return if self.text.is_empty() && self.magnitude.is_finite() {
                write!(
                    f,
                    "parameter `{}` is invalid: {m} is past {}, the largest magnitude a solve \
                     takes (squares of lengths past it overflow)",
                    self.label,
                    crate::num::Shown(crate::num::MAX_MAGNITUDE)
                )
            } else if self.text.is_empty() {
                write!(
                    f,
                    "parameter `{}` is invalid: {m} is not a finite number",
                    self.label
                )
            } else {
                write!(
                    f,
                    "the sketch of `{}` is invalid: {}",
                    self.label, self.text
                )
            };
        }
        if self.kind == ErrorKind::InvalidDefault {
            return write!(
                f,
                "default `{}` is invalid: its value, {m}, is negative, and it fixes {}, which is zero or more",
                self.label, self.text
            );
        }
        if self.kind == ErrorKind::InvalidParam {
            return write!(
                f,
                "parameter `{}` is invalid: its value, {m}, is negative, and `{}` takes it as a distance, a length or a radius, which is zero or more",
                self.label, self.text
            );
        }
        write!(f, "constraint `{}`", self.label)?;
        if !self.text.is_empty() {
            write!(f, " ({})", self.text)?;
        }
        match self.kind {
            ErrorKind::NoIntersection => {
                write!(f, " cannot be met: no intersection, the loci miss by {m}")
            }
            ErrorKind::Inconsistent => {
                write!(f, " cannot be met: it is inconsistent with the constraints already met, by {m}")
            }
            ErrorKind::Degenerate => write!(
                f,
                " cannot be met: the configuration is degenerate (coincident or zero-size loci), size {m}"
            ),
            ErrorKind::NoConvergence => {
                write!(f, " cannot be met: the iteration did not converge, residual {m}")
            }
            ErrorKind::NoAssembly => write!(
                f,
                " cannot be met: no assembly exists here with the branches and the other defaults given; over the whole turn of the angle the iteration varies, it stays at least {m} from closing"
            ),
            ErrorKind::NoAssemblyNear => write!(
                f,
                " cannot be met: the assembly followed from the defaults the iteration started from does not exist here; near them the constraints it closes stay at least {m} from closing (the least norm of their errors there)"
            ),
            ErrorKind::InvalidValue if self.magnitude.is_finite() => {
                write!(f, " cannot be met: its value, {m}, is negative; a distance, a length or a radius is zero or more")
            }
            ErrorKind::InvalidValue => {
                write!(f, " cannot be met: its value, {m}, is not a finite number")
            }
            ErrorKind::InvalidInput | ErrorKind::InvalidDefault | ErrorKind::InvalidParam => {
                Ok(())
            }
            ErrorKind::NoSuchBranch => write!(
                f,
                " cannot be met on the chosen branch: the loci meet in only {m} real point(s) here"
            ),
            ErrorKind::CannotClose => write!(
                f,
                " cannot be met: the profile it closes cannot close with its segments running as sketched; it would give one a length of {m} (its end behind its start), so the lengths it closes on do not fit"
            ),
            ErrorKind::OtherMode => write!(
                f,
                " cannot be met in the sketch's assembly mode: the iteration that closes it finds {m} closure(s) here, all in the other mode (across a fold from the sketch's); solve from other defaults to take one"
            ),
        }
    }
}

impl std::error::Error for SolveError {}

/// `Ok(value)` when `value` is finite and within [`crate::num::MAX_MAGNITUDE`], otherwise an
/// [`ErrorKind::InvalidInput`] error naming the parameter `name`, whose magnitude is the
/// offending value (NaN, infinite, or past the range).
#[inline]
pub fn check_finite(name: &'static str, value: f64) -> Result<f64, SolveError> {
    if crate::num::in_range(value) {
        Ok(value)
    } else {
        Err(SolveError::new(name, "", ErrorKind::InvalidInput, value))
    }
}

/// Checks every `(name, value)` pair with [`check_finite`], reporting the first non-finite one.
#[inline]
pub fn check_all_finite(params: &[(&'static str, f64)]) -> Result<(), SolveError> {
    for &(name, value) in params {
        check_finite(name, value)?;
    }
    Ok(())
}

/// How far an assembly is from closing: the residuals of the constraints a plan with defaults
/// could only measure, not satisfy by construction (paper 000, section 5.2.1).
///
/// When degrees of freedom analysis cannot solve a loop in closed form, the plan assigns
/// default values to a few variables (an angle, a distance), runs its actions, and at the end
/// measures the constraints left open. An outer iteration (Newton, secant or bracketing on
/// those few variables) then:
///
/// 1. resets the accumulator and runs the plan with its current guesses;
/// 2. calls [`ErrorAccumulator::add`] with each open constraint's signed residual;
/// 3. stops when [`ErrorAccumulator::max`] is below its tolerance, otherwise updates the
///    guesses from the residuals (or [`ErrorAccumulator::sum_squares`] for a minimizer) and
///    repeats, at most a bounded number of times;
/// 4. on failure reports [`ErrorKind::NoConvergence`] for [`ErrorAccumulator::worst`] with
///    magnitude [`ErrorAccumulator::max`], or, where it can tell why,
///    [`ErrorKind::NoAssembly`] (no root over an angle's turn) or
///    [`ErrorKind::NoAssemblyNear`] (a minimum of the residuals that is not zero) with how far
///    the constraints stay from closing.
///
/// The key `K` names a constraint: `&'static str` labels in generated code, an index in the
/// interpreter. Adding is a few flops; nothing allocates. A NaN residual counts as infinite, so
/// it can never look closed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorAccumulator<K: Copy = &'static str> {
    sum_squares: f64,
    max: f64,
    worst: Option<K>,
    count: usize,
}

impl<K: Copy> Default for ErrorAccumulator<K> {
    fn default() -> Self {
        Self::new()
    }
}

impl<K: Copy> ErrorAccumulator<K> {
    /// An empty accumulator: closed, with no residual.
    #[inline]
    pub const fn new() -> Self {
        Self {
            sum_squares: 0.0,
            max: 0.0,
            worst: None,
            count: 0,
        }
    }

    /// Forgets every residual.
    #[inline]
    pub fn reset(&mut self) {
        *self = Self::new();
    }

    /// Records the residual of constraint `key` (its sign is ignored; NaN counts as infinite).
    #[inline]
    pub fn add(&mut self, key: K, residual: f64) {
        let r = if residual.is_nan() {
            f64::INFINITY
        } else {
            residual.abs()
        };
        self.sum_squares += r * r;
        self.count += 1;
        if self.worst.is_none() || r > self.max {
            self.max = r;
            self.worst = Some(key);
        }
    }

    /// The sum of the squared residuals.
    #[inline]
    pub fn sum_squares(&self) -> f64 {
        self.sum_squares
    }

    /// The largest absolute residual (0 when none was added).
    #[inline]
    pub fn max(&self) -> f64 {
        self.max
    }

    /// The constraint with the largest residual (the first one on ties), if any.
    #[inline]
    pub fn worst(&self) -> Option<K> {
        self.worst
    }

    /// The number of residuals added.
    #[inline]
    pub fn count(&self) -> usize {
        self.count
    }

    /// The root mean square of the residuals (0 when none was added).
    #[inline]
    pub fn rms(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            (self.sum_squares / self.count as f64).sqrt()
        }
    }

    /// Whether every residual is at most `tolerance`.
    #[inline]
    pub fn is_closed(&self, tolerance: f64) -> bool {
        self.max <= tolerance
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_reads_as_a_sentence() {
        let e = SolveError::new(
            "elbow",
            "coincident(coupler.c, rocker.c)",
            ErrorKind::NoIntersection,
            0.3,
        );
        assert_eq!(
            e.to_string(),
            "constraint `elbow` (coincident(coupler.c, rocker.c)) cannot be met: no intersection, the loci miss by 0.3"
        );
        let owned = SolveError::new(
            String::from("a"),
            String::new(),
            ErrorKind::Inconsistent,
            2.0,
        );
        assert_eq!(
            owned.to_string(),
            "constraint `a` cannot be met: it is inconsistent with the constraints already met, by 2"
        );
        for kind in [
            ErrorKind::Degenerate,
            ErrorKind::NoConvergence,
            ErrorKind::NoAssembly,
            ErrorKind::NoAssemblyNear,
        ] {
            let s = SolveError::new("k", "t", kind, 1.0).to_string();
            assert!(s.starts_with("constraint `k` (t) cannot be met: "), "{s}");
        }
        let err: Box<dyn std::error::Error> = Box::new(e);
        assert!(err.to_string().contains("elbow"));
    }

    /// The three ways an outer iteration fails say three different things: that it did not
    /// converge, that no assembly exists, that the one followed does not exist here.
    #[test]
    fn iterations_that_fail_say_why() {
        let text = |kind, m| SolveError::new("leg4", "distance(p4, b4) = l4", kind, m).to_string();
        assert_eq!(
            text(ErrorKind::NoConvergence, 0.25),
            "constraint `leg4` (distance(p4, b4) = l4) cannot be met: the iteration did not \
             converge, residual 0.25"
        );
        assert_eq!(
            text(ErrorKind::NoAssembly, 0.5),
            "constraint `leg4` (distance(p4, b4) = l4) cannot be met: no assembly exists here \
             with the branches and the other defaults given; over the whole turn of the \
             angle the iteration varies, it stays at least 0.5 from closing"
        );
        assert_eq!(
            text(ErrorKind::NoAssemblyNear, 0.0033),
            "constraint `leg4` (distance(p4, b4) = l4) cannot be met: the assembly followed \
             from the defaults the iteration started from does not exist here; near them the \
             constraints it closes stay at least 0.0033 from closing (the least norm of their \
             errors there)"
        );
    }

    #[test]
    fn a_negative_param_or_default_is_blamed_on_itself() {
        let param = SolveError::new("d", "distance(A, B) = d", ErrorKind::InvalidParam, -5.0);
        assert_eq!(
            param.to_string(),
            "parameter `d` is invalid: its value, -5, is negative, and `distance(A, B) = d` takes it as a distance, a length or a radius, which is zero or more"
        );
        let default = SolveError::new(
            "left_length",
            "the length of left",
            ErrorKind::InvalidDefault,
            -5.0,
        );
        assert_eq!(
            default.to_string(),
            "default `left_length` is invalid: its value, -5, is negative, and it fixes the length of left, which is zero or more"
        );
    }

    #[test]
    fn invalid_values_and_sketches_say_what_is_wrong() {
        let angle = SolveError::new(
            "drive",
            "angle(X, u) = t * 1e300",
            ErrorKind::InvalidValue,
            f64::INFINITY,
        );
        assert_eq!(
            angle.to_string(),
            "constraint `drive` (angle(X, u) = t * 1e300) cannot be met: its value, inf, is not a finite number"
        );
        let size = SolveError::new("height", "length(left) = h", ErrorKind::InvalidValue, -1.0);
        assert_eq!(
            size.to_string(),
            "constraint `height` (length(left) = h) cannot be met: its value, -1, is negative; a distance, a length or a radius is zero or more"
        );
        let sketch = SolveError::new(
            "crank",
            "its placement is not finite",
            ErrorKind::InvalidInput,
            f64::NAN,
        );
        assert_eq!(
            sketch.to_string(),
            "the sketch of `crank` is invalid: its placement is not finite"
        );
    }

    #[test]
    fn finite_checks_name_the_parameter() {
        assert_eq!(check_finite("len", 2.0), Ok(2.0));
        let e = check_finite("len", f64::NAN).err();
        let e = e
            .as_ref()
            .map(|e| (e.kind, e.label.as_ref(), e.to_string()));
        assert_eq!(
            e,
            Some((
                ErrorKind::InvalidInput,
                "len",
                "parameter `len` is invalid: NaN is not a finite number".to_string()
            ))
        );
        let e = check_all_finite(&[("a", 1.0), ("b", f64::INFINITY), ("c", f64::NAN)]).err();
        assert_eq!(e.map(|e| e.label), Some(Cow::Borrowed("b")));
        assert_eq!(check_all_finite(&[("a", 1.0)]), Ok(()));
        // Past the range: refused, and said so.
        assert_eq!(check_finite("len", -1e150), Ok(-1e150));
        let e = check_finite("len", 1e151).err();
        assert_eq!(e.as_ref().map(|e| e.kind), Some(ErrorKind::InvalidInput));
        assert_eq!(
            e.map(|e| e.to_string()).unwrap_or_default(),
            "parameter `len` is invalid: 1e151 is past 1e150, the largest magnitude a solve \
             takes (squares of lengths past it overflow)"
        );
    }

    #[test]
    fn contact_maps_to_kinds() {
        assert_eq!(SolveError::from_contact("l", "t", Contact::Crossing), None);
        assert_eq!(SolveError::from_contact("l", "t", Contact::Tangent), None);
        let e = SolveError::from_contact("l", "t", Contact::Disjoint { gap: 0.5 });
        assert_eq!(
            e.map(|e| (e.kind, e.magnitude)),
            Some((ErrorKind::NoIntersection, 0.5))
        );
        let e = SolveError::from_contact("l", "t", Contact::Parallel { gap: 0.25 });
        assert_eq!(
            e.map(|e| (e.kind, e.magnitude)),
            Some((ErrorKind::NoIntersection, 0.25))
        );
        let e = SolveError::from_contact("l", "t", Contact::Coincident);
        assert_eq!(e.map(|e| e.kind), Some(ErrorKind::Degenerate));
        let e = SolveError::from_contact("l", "t", Contact::ZeroRadius);
        assert_eq!(e.map(|e| e.kind), Some(ErrorKind::Degenerate));
    }

    #[test]
    fn accumulator_tracks_sum_max_and_worst() {
        let mut acc: ErrorAccumulator = ErrorAccumulator::new();
        assert!(acc.is_closed(0.0));
        assert_eq!(acc.rms(), 0.0);
        acc.add("a", 0.1);
        acc.add("b", -0.4);
        acc.add("c", 0.4);
        assert!((acc.sum_squares() - 0.33).abs() < 1e-15);
        assert_eq!(acc.max(), 0.4);
        assert_eq!(acc.worst(), Some("b"));
        assert_eq!(acc.count(), 3);
        assert!((acc.rms() - 0.11f64.sqrt()).abs() < 1e-15);
        assert!(!acc.is_closed(0.3));
        acc.add("d", f64::NAN);
        assert_eq!(acc.worst(), Some("d"));
        assert!(!acc.is_closed(1e300));
        acc.reset();
        assert_eq!(acc, ErrorAccumulator::default());
        let mut by_index: ErrorAccumulator<usize> = ErrorAccumulator::new();
        by_index.add(7, 1e-3);
        assert_eq!(by_index.worst(), Some(7));
    }
}
