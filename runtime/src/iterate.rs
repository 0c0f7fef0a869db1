//! Outer iterations: the values of a plan's defaults at which its closing residuals vanish.
//!
//! A plan with defaults assembles its region for given values of a few redundant coordinates
//! (an angle about a pivot, a position along a line) and measures the constraints those values
//! displace (see [`crate::error::ErrorAccumulator`]). This module varies the defaults until the
//! residuals vanish. The assembly may fail for some values (two circles that no longer meet):
//! the residual function then returns `Err`, and the iteration treats the point as unusable
//! rather than as a root. A NaN or infinite residual counts the same.
//!
//! # [`solve`]: one answer near the start
//!
//! - **One default** (`N = 1`): first the plain iteration of a start near its root (a sweep's
//!   last answer): Newton's step on a forward difference, then secant steps (the slope of the
//!   parabola through the last three points), each at most half the default's scale and each
//!   required to halve the residual; the first step that does not, or whose assembly fails,
//!   hands the best point reached to the safeguarded search: Newton's method with a
//!   forward-difference derivative, within the same bound. Once two values of opposite sign
//!   have been seen, their bracket is kept and every later point stays inside it: a Newton
//!   step that would leave the bracket, or that failed to halve the residual, is replaced by
//!   an Illinois step (false position with halving of the retained end's value), and three
//!   steps that do not halve the bracket force a bisection. So the convergence is Newton's where Newton works, and that of
//!   bracketing (guaranteed, superlinear) where it does not. Before any sign change, a step
//!   that fails or does not reduce the residual is halved; and when the derivative changes
//!   sign between two successive points while `f` keeps its sign, the iteration has passed a
//!   local minimum of `|f|`, which damped Newton cannot leave: Brent's minimization between
//!   the two points finds its bottom, a (double) root if `|f|` is within the tolerance there, a
//!   bracket if `f` crosses zero, and otherwise the end of the iteration: no root near here.
//! - **Several defaults**: Powell's dogleg trust-region method (as MINPACK's `hybrd`) on the
//!   fixed-size system, in variables divided by their scales. The Jacobian comes from forward
//!   differences with steps `sqrt(eps) max(|x_i|, scale_i)`; the Newton step from nalgebra's LU
//!   inversion of the statically sized Jacobian (`SMatrix`, no allocation). When the Newton step
//!   is longer than the trust radius, the step follows the dogleg path through the Cauchy point
//!   (steepest descent of the squared residual norm), which also replaces a singular Jacobian.
//!   The radius starts at, and never exceeds, half a scale: a step moves no default by more than
//!   half its scale, so the iteration stays on the assembly it starts on. A step whose
//!   residual norm does not fall, or where the assembly fails, is retried with half the radius;
//!   a radius shrunk to rounding level ends the iteration (a minimum of the residual norm that
//!   is not a root).
//! - **Full precision**: once every residual is within [`Settings::tolerance`], up to
//!   three more steps (one evaluation each: secant steps for one default, Newton steps with
//!   the last Jacobian for several) are taken while each at least halves the largest residual,
//!   so answers end at rounding level, as closed forms do, rather than just inside the
//!   tolerance. An answer already within [`Settings::rounding`] is left as it is: a step from
//!   there changes less than the noise of evaluating the residual, and costs an evaluation.
//! - **Failures**: a start where the assembly fails is first moved (one default) to the
//!   nearest point where it does not, probed at `scale * 2^-12` up to half a scale on either
//!   side (a sweep's last answer can lie just past the edge of the stretch where its assembly
//!   exists, one step on). With none, or with several defaults, a start whose error is a
//!   miss with a gap ([`Gap`]: two circles that miss by `d`, zero where they touch) descends
//!   on that gap, by Newton's method with its gradient from differences, each step aimed a
//!   tenth past where the gap closes and at most half a scale, to where the assembly exists,
//!   and the iteration goes on from there; so it starts from any default whose loci can be
//!   brought to meet. Otherwise it is [`Failure::Start`] with its error. A
//!   non-finite start, or a non-finite residual at the start, is [`Failure::NoConvergence`]
//!   with a NaN (or that infinite) residual, without a call (resp. after one call). A failing
//!   trial point halves the step back toward the last good point; the budget of evaluations
//!   ([`Settings::max_evaluations`]) bounds every loop, so nothing runs forever.
//! - **What a failure says**: an iteration that ends without a root is then told, at a cost
//!   only a failure pays (out of line, cold), as one of three:
//!   1. [`Failure::NoAssembly`], no assembly at all: one default, an angle
//!      ([`Settings::span`] is [`Span::Turn`]), whose error [`all_roots`] finds no root of
//!      over the whole turn, on the grid of `outer::Scan`. Its magnitude is the smallest `|f|`
//!      the scan found ([`RootScan::least`]). The claim is the scan's: what its documentation
//!      says it cannot miss (in practice, a pair of roots closer than a sample spacing with
//!      `|f|` above the tolerance between them). A length is not searched ([`Span`] says
//!      why).
//!   2. [`Failure::NoAssemblyNear`], no assembly near the start: the iteration stopped in the
//!      valley of a local minimum of its closing errors whose bottom is not zero. From the
//!      best point reached, Newton's method on the squared norm of the errors, with its exact
//!      curvature from differences, finds the bottom, then again with differences sixteen
//!      times shorter (`nonzero_minimum`): a bottom has a positive definite Hessian and a
//!      Newton step that lowers the square by at most [`tol::MINIMUM_CONFIRM_REL`] of it, and
//!      keeps at least half its height with the shorter steps (the corner of a magnitude's V,
//!      a distance's root, which the differences straddle, looks like a bottom that falls
//!      with the step: it is none). For one default, this also confirms (and polishes) a
//!      valley the search settled in (`settle`), whose bottom its budget may have cut short.
//!      Its magnitude is the errors' norm at the bottom, to about the last digits: near it, no
//!      value of the defaults brings them closer to zero. This is the fold of a sweep: the
//!      assembly followed meets another and both end, leaving a valley whose bottom rises
//!      from zero as the params move on. Where the descent from the best point leads to
//!      a root instead (another assembly, or the same one missed), or away over a slope, an
//!      edge or past the budget, nothing is claimed, and no answer is taken from there: a
//!      plain solve never jumps to another assembly.
//!   3. [`Failure::NoConvergence`] otherwise, with the smallest largest-residual reached.
//!
//!   For several defaults no range is searched (a grid over several defaults would be costly
//!   and still not a proof), so a failure is at most [`Failure::NoAssemblyNear`]. The test
//!   for a minimum has a budget of its own, [`Settings::max_evaluations`] more, and the scan
//!   that of [`all_roots`] (its samples, and the budget per refinement).
//!
//! # [`all_roots`]: every root of one default over an interval
//!
//! The function is sampled on a uniform grid of `n = max(samples, 8)` points, spacing
//! `h = (hi - lo) / (n - 1)` (periodic: `(hi - lo) / n`, the last interval wrapping to the first
//! sample). Then, between adjacent samples where the function is defined:
//!
//! 1. **Sign changes** are bracketed and refined by Brent's method (inverse quadratic
//!    interpolation and secant steps, safeguarded by bisection) to rounding level; the root is
//!    kept when its residual is within the tolerance (a pole or a jump through zero is not a
//!    root).
//! 2. **Local minima of |f|** among the samples, with no sign change next to them (the left
//!    neighbour strictly larger in magnitude, the right one at least as large, so a tie is
//!    refined once), are refined by Brent's minimization of `sign * f` over the two spacings
//!    around the sample, to about `sqrt(eps) |x|`, and then, should `f` be a magnitude (a
//!    distance, whose minimum is the corner of a V that the minimization finds only to that
//!    resolution), where the lines through a point either side of it meet. A minimum with
//!    `|f| <= tolerance` is a **double root** (a magnitude's root is one). If the minimization finds a point where `f` has crossed zero by more than
//!    the tolerance, the dip holds two simple roots, and both are refined.
//! 3. **Shallow dips**: a sample with `|f| <= tolerance` whose two neighbours have the opposite
//!    sign is refined the same way (the deepest point of the dip): if the dip stays within the
//!    tolerance of zero, its two crossings are one double root there, not two roots.
//!    Consequently, two simple roots whose dip between them is at most the tolerance deep are
//!    reported as **one double root** at the bottom of the dip (two roots `1e-6` apart of a
//!    function with curvature about 1 dip by `2.5e-13`: one double root), and deeper pairs as
//!    two roots; this is the kernel's rule for tangencies ([`crate::tol::TANGENT_REL`]) applied
//!    to the residual.
//! 4. **Where the assembly fails**: between a defined sample and a failing one, bisection
//!    finds the last defined point to rounding level. That point joins the samples (so sign
//!    changes and minima next to it are refined too) and is itself a root, flagged
//!    [`RootScan::is_boundary`], when its `|f|` is within the tolerance: the assembly became
//!    tangent there. This relies on the residual at the last defined point being within the
//!    tolerance of its limit, which holds for the kernel's intersections (a tangency within
//!    [`crate::tol::TANGENT_REL`] meets in one double root) but not for a function with a
//!    square-root singularity computed without such a snap. Such an edge, where `|f|` has
//!    fallen to a sixteenth or less of its value at the sample beside it with the same sign
//!    and `f / sqrt(d)` (`d` the distance from the edge) agrees within a factor of two at
//!    `1e-6` and `1e-4` of the way to that sample (an error that reaches zero as a square root
//!    does at a tangency, whose last defined point lies in the tangency's band; one that only
//!    comes near zero differs tenfold), is a boundary root too: a start that the solve from
//!    it confirms or not, as every root is. The ends of a non-periodic interval are
//!    treated alike. A failing stretch between two defined samples, met by a refinement of a
//!    sign change, is split off the same way: its edges are found from both sides, and each
//!    side is refined on its own (up to four nested splits); so is one met by the
//!    minimization of rule 2 (a stretch narrower than the grid inside a valley of `|f|`).
//! 5. **A window between failing samples**: where the function fails with a gap ([`Gap`]:
//!    loci that miss by it), a failing sample whose gap is a local minimum of the sampled
//!    gaps between two failing samples is refined by Brent's minimization of the gap over
//!    the two spacings around it. If it meets a point where `f` is defined (the loci meet
//!    over a stretch narrower than the grid), the stretch's edges are found by bisection and
//!    the stretch is swept on a grid of its own of 16 samples by these same rules (windows
//!    inside it too, two deep).
//!
//! Roots closer than `1e-9 (hi - lo)` (across the wrap when periodic) are one root, the one
//! with the smaller residual. Each refinement uses at most [`Settings::max_evaluations`]
//! evaluations; `f` is only called at points of `[lo, hi]`.
//!
//! ## Completeness: what the samples guarantee and what they do not
//!
//! In exact arithmetic, for `f` continuous where it is defined, and counting two roots between
//! which `|f|` never exceeds the tolerance as the one double root that rules 2 and 3 make of
//! them:
//!
//! - Every interval between adjacent defined samples whose values have opposite signs yields
//!   a root (or, if the refinement meets a failing stretch in it, what rule 4 finds on either
//!   side of the stretch). Hence if `f` is defined on the whole interval and its roots are of
//!   odd multiplicity and pairwise more than `h` apart, **every root is found**: each grid
//!   interval then holds at most one root, and a root inside it shows as a sign change (a
//!   root at a sample is its zero value). An interval holding three roots yields only one.
//! - A root `r` of even multiplicity (no sign change) is found when, within `2h` of `r` (and
//!   `[lo, hi]`), `f` is defined and `|f|` strictly decreases up to `r` and strictly increases
//!   after it, and `|f| <= tolerance` within the minimizer's resolution of `r` (about
//!   `sqrt(eps) (|r| + 1e-3 (hi - lo))`): then one of the two samples around `r` is a local
//!   minimum of the sampled `|f|`, and Brent's minimization over the two spacings around it
//!   converges to `r`.
//! - **Missed**: a pair of roots closer than `h` with no sample between them and next to no
//!   sample that is a local minimum of the sampled `|f|` (for instance a dip on a steep
//!   slope, or next to a third root's sign change); more generally, any dip of `f` through
//!   zero between two samples of the same sign neither of which is such a minimum (also when
//!   one of the two sign changes lies inside a failing stretch that no sample hits); a defined
//!   stretch lying strictly between two failing samples, unless their failures have gaps
//!   that dip toward it (rule 5), and then the roots its own grid misses; roots a refinement would reach only
//!   through more than four nested failing stretches. With rounding, also a root where `f` is
//!   so steep that no double near it has `|f| <= tolerance` (it is then no root at this
//!   tolerance).
//!
//! The sample count sets `h`, so it guarantees only what the statements above say for that
//! `h`. For a trigonometric polynomial of degree `d` in the angle (`f(lo + t) = sum over
//! k <= d of a_k cos(2 pi k t / P) + b_k sin(2 pi k t / P)`, period `P = hi - lo`) with
//! `M = max |f|`, Bernstein's inequality gives `|f''| <= (2 pi d / P)^2 M`, so `f` differs from
//! the chord between two samples by at most `pi^2 d^2 M / (2 n^2)`: a root can hide in an
//! interval without a sign change only if one of its two samples is at most that small in
//! magnitude. And it has at most `2d` roots per period counted with multiplicity, so a scan
//! that reports `2d` (a double root counting twice) has found them all, up to the tolerance.
//! `n >= 2d + 1` samples determine such an `f`, but do not by themselves make its roots show:
//! `cos(t - h/2) - cos(e)` on `[0, 2 pi)` has two roots `2e` apart between the first two
//! samples for every `n` (this one is found, through the minimum of `|f|` at the samples: as
//! two roots when `1 - cos(e)` exceeds the tolerance, else as one double root). Measured on
//! random trigonometric polynomials of degree up to 4 with 24 samples, with and without
//! a random failing stretch (test `scan_misses_only_roots_sharing_a_grid_interval`, 100,000
//! cases): every root missed shared its grid interval with another sign change of `f`, the
//! other one sometimes inside the failing stretch.
//!
//! Nothing here allocates or panics, for any input.

use std::borrow::Cow;

use nalgebra::{SMatrix, SVector};

use crate::error::{ErrorKind, SolveError};
use crate::mode::Orientation;
use crate::num::is_finite;
use crate::tol;

/// The longest step, in units of each default's scale: half an angle's radian, half a model's
/// size. Newton steps longer than this usually mean the start is far from the root, and the
/// bound keeps the iteration on the assembly (branch) it started on.
const MAX_STEP: f64 = 0.5;

/// Steps taken after the residuals are within the tolerance (secant steps for one default,
/// Newton steps with the last Jacobian for several), while each at least halves the residual
/// ([`POLISH_GAIN`]): with a derivative accurate to `sqrt(eps)` or better, one step takes a
/// residual of 1e-10 to rounding level, so two or three are plenty.
const POLISH_STEPS: u32 = 3;

/// The longest last step, in scales, after which a secant replaces a finite difference.
const SECANT_REACH: f64 = 0.05;

/// The factor by which a polishing step must reduce the residual for the next to be tried.
const POLISH_GAIN: f64 = 0.5;

/// The fewest samples [`all_roots`] takes: fewer could not tell a minimum from a slope.
const MIN_SAMPLES: u32 = 8;

/// The most Newton steps [`descend`] takes on the squared closing error (each within
/// the budget too): from where an iteration stopped, in the valley of a minimum, Newton's
/// method with the exact curvature reaches its bottom in a handful.
const MINIMUM_STEPS: u32 = 16;

/// How many times a refinement in [`all_roots`] splits off a failing stretch (each split
/// refines the sides, which may split again): a bound on the work spent in a bracket that
/// failing stretches riddle.
const MAX_SPLITS: u32 = 4;

/// How an outer iteration stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Converged when every residual's magnitude is at most this (absolute, in the model's
    /// units).
    pub tolerance: f64,
    /// A residual at most this (absolute) is at rounding level: once there, no polishing step
    /// is taken. Zero polishes every answer.
    pub rounding: f64,
    /// At most this many evaluations of the residual function (each is one assembly of the
    /// plan's region); a failure is then told by searches with budgets of their own (module
    /// documentation, "What a failure says").
    pub max_evaluations: u32,
    /// What the default of an iteration over one default ranges over, searched for a root
    /// when the iteration fails (module documentation, "What a failure says"). Ignored for
    /// several defaults.
    pub span: Span,
    /// The orientation of the sketch's root to keep (the sketch's assembly mode,
    /// [`crate::mode`]), for a solve from the sketch's defaults; `None` takes the root the
    /// iteration reaches, whatever its orientation.
    pub hold: Option<Orientation>,
    /// Whether a failure is told apart (module documentation, "What a failure says"): false
    /// for the many starts of a search for every assembly, where a start that fails costs
    /// only its own iteration and says nothing anyone reads.
    pub classify: bool,
}

/// The range of the one default of an iteration, which [`solve`] searches for a root when the
/// iteration fails: none found is [`Failure::NoAssembly`].
///
/// Only an angle's range is searched. A length or a coordinate has no range of its own, and
/// its error may vary on any scale (a screw's pitch sets it): no grid of a size fixed in
/// advance sees every root. Measured: a screw of pitch 0.007 in a model of size 0.001, whose
/// root 0.0003 from the start a grid of 720 samples over four of its scales either side
/// stepped over, where "no assembly" would have been false. A length's failure is told near
/// the start only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Span {
    /// Not an angle (or not said): a failure is not searched.
    #[default]
    Unknown,
    /// An angle in radians: the whole turn, `[-pi, pi)`, periodic, on the grid of
    /// [`crate::outer::Scan`] (so that a solve and `solve_all` agree on whether a root exists),
    /// what the closing errors of the plans' angles are smooth on: trigonometric in the angle
    /// through the plan's rotations, with the failing stretches and tangencies
    /// [`all_roots`] finds the edges of.
    Turn,
}

impl Default for Settings {
    /// Tolerance [`tol::OUTER_DEFAULT`] (`1e-10`): far above the rounding of an assembly of a
    /// model of size up to about 1e3 (whose residuals end near 1e-13), far below any error a
    /// drawing shows; the answer is polished to rounding level past it anyway. Budget `200`: a converging Newton iteration
    /// needs under ten steps of `N + 1` evaluations, bracketing about sixty halvings of a whole
    /// turn to reach rounding level, so 200 is ample for both and still bounds a failing
    /// iteration to a fraction of a millisecond of assemblies.
    fn default() -> Self {
        Self {
            tolerance: tol::OUTER_DEFAULT,
            rounding: 0.0,
            max_evaluations: 200,
            span: Span::Unknown,
            hold: None,
            classify: true,
        }
    }
}

impl Settings {
    /// The settings of a plan's iteration on a model whose geoms have size `size` (its
    /// largest coordinate or dimension): converged at [`tol::ITERATION_REL`] and at rounding
    /// level at [`tol::ROUNDING_REL`], each times `1 + size`; the default budget.
    pub fn for_size(size: f64) -> Self {
        Self {
            tolerance: tol::ITERATION_REL * (1.0 + size),
            rounding: tol::ROUNDING_REL * (1.0 + size),
            ..Self::default()
        }
    }

    /// These settings for an iteration over one default that ranges over `span`.
    #[must_use]
    pub const fn spanning(self, span: Span) -> Self {
        Self { span, ..self }
    }

    /// These settings keeping the orientation `hold` (none: any root).
    #[must_use]
    pub const fn holding(self, hold: Option<Orientation>) -> Self {
        Self { hold, ..self }
    }

    /// These settings for one start of many: no failure told, no mode held.
    #[must_use]
    pub const fn searching(self) -> Self {
        Self {
            hold: None,
            classify: false,
            ..self
        }
    }
}

/// A converged iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Converged {
    /// Newton (or bracketing) steps taken.
    pub iterations: u32,
    /// Evaluations of the residual function, including finite differences.
    pub evaluations: u32,
    /// The largest residual magnitude at the answer.
    pub residual: f64,
}

/// Why an iteration failed.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure<E> {
    /// The assembly fails at the starting defaults: its error.
    Start(E),
    /// No convergence within the budget, and neither of the two failures below could be
    /// told: the smallest largest-residual reached, and steps taken.
    NoConvergence {
        /// The smallest largest-residual magnitude reached (NaN when the start was not finite).
        residual: f64,
        /// Steps taken.
        iterations: u32,
    },
    /// One default over a known [`Span`]: its error has no root over the whole range, so no
    /// assembly exists (on the branches its region took).
    NoAssembly {
        /// The smallest residual magnitude found over the range: how far the assembly stays
        /// from closing.
        least: f64,
        /// Steps taken before the search.
        iterations: u32,
    },
    /// The iteration stopped in the valley of a local minimum of its closing errors whose
    /// bottom is not zero: no assembly near the start (in a sweep, the one followed ended at a
    /// fold), though one may exist elsewhere.
    NoAssemblyNear {
        /// The errors' norm (the root of the sum of their squares) at the minimum.
        residual: f64,
        /// Steps taken.
        iterations: u32,
    },
    /// The iteration held the sketch's orientation ([`Settings::hold`]) and found no root of
    /// it, only roots of the other ([`crate::mode::keep`] says where it searched).
    OtherMode {
        /// The roots of the other orientation found (at least one).
        others: u32,
        /// Steps taken before the search.
        iterations: u32,
    },
}

impl<E> Failure<E> {
    /// The kind of error a failure other than [`Failure::Start`] is, and its magnitude.
    pub fn kind(&self) -> Option<(ErrorKind, f64)> {
        Some(match *self {
            Failure::Start(_) => return None,
            Failure::NoConvergence { residual, .. } => (ErrorKind::NoConvergence, residual),
            Failure::NoAssembly { least, .. } => (ErrorKind::NoAssembly, least),
            Failure::NoAssemblyNear { residual, .. } => (ErrorKind::NoAssemblyNear, residual),
            Failure::OtherMode { others, .. } => (ErrorKind::OtherMode, f64::from(others)),
        })
    }
}

impl Failure<SolveError> {
    /// The error a solve reports for this failure: the assembly's own at the start, otherwise
    /// the error of [`Failure::kind`] for the constraint `label` with source `text` (an
    /// iteration's first close).
    #[cold]
    #[inline(never)]
    pub fn into_error(
        self,
        label: impl Into<Cow<'static, str>>,
        text: impl Into<Cow<'static, str>>,
    ) -> SolveError {
        let (kind, magnitude) = match self {
            Failure::Start(error) => return error,
            Failure::NoConvergence { residual, .. } => (ErrorKind::NoConvergence, residual),
            Failure::NoAssembly { least, .. } => (ErrorKind::NoAssembly, least),
            Failure::NoAssemblyNear { residual, .. } => (ErrorKind::NoAssemblyNear, residual),
            Failure::OtherMode { others, .. } => (ErrorKind::OtherMode, f64::from(others)),
        };
        SolveError::new(label, text, kind, magnitude)
    }
}

/// Solves f(x) = 0 for x in R^N starting from `x` (overwritten with the answer, or with the best
/// point reached on failure).
///
/// `scale[i]` is the natural size of default i (1 for an angle in radians, the model's size for
/// a length): it sets finite-difference steps and bounds each step (a trust region), so the
/// iteration stays on the assembly it starts on and does not jump to another. A scale that is
/// not finite and positive is replaced by `max(|x_i|, 1)`.
///
/// `f(x, r)` writes the N residuals into r, or returns Err when the plan cannot assemble at x
/// (then the iteration backs off: shorter steps toward the last good point). See the module
/// documentation for the methods, and for what a failure says ("Failures").
pub fn solve<const N: usize, E: Gap>(
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    mut f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<Converged, Failure<E>> {
    let start = *x;
    let outcome = if N == 1 {
        let mut point = [0.0; N];
        let mut residual = [0.0; N];
        let mut root = x[0];
        let outcome = solve_scalar(&mut root, scale[0], settings, |t| {
            point[0] = t;
            f(&point, &mut residual).map(|()| residual[0])
        });
        x[0] = root;
        outcome
    } else {
        solve_system(x, scale, settings, &mut f)
    };
    match outcome {
        Ok(converged) => match settings.hold {
            Some(want) => crate::mode::keep(want, &start, x, scale, settings, converged, &mut f),
            None => Ok(converged),
        },
        Err(Failure::NoConvergence {
            residual,
            iterations,
        }) if settings.classify => {
            // Held from the sketch: a root of the sketch's mode elsewhere is the answer, and
            // roots of the other mode only are said as such.
            if let Some(want) = settings.hold {
                let mut y = *x;
                match crate::mode::search(want, &start, &mut y, scale, settings, &mut f) {
                    Ok(residual) => {
                        *x = y;
                        return Ok(Converged {
                            iterations,
                            evaluations: settings.max_evaluations,
                            residual,
                        });
                    }
                    Err(others) if others > 0 => {
                        return Err(Failure::OtherMode { others, iterations })
                    }
                    Err(_) => {}
                }
            }
            let failure = Failure::NoConvergence {
                residual,
                iterations,
            };
            Err(classify(&start, x, scale, settings, &mut f, failure))
        }
        outcome => outcome,
    }
}

// ---------------------------------------------------------------------------------------------
// A start where the assembly fails.

/// An assembly's error that may say how far its loci miss: a gap that closes continuously,
/// zero where they touch (two circles that miss by `d` touch when moved `d` closer), so that
/// an iteration started where its assembly fails can descend on it to where it exists.
pub trait Gap {
    /// The gap, if the error is a miss that closes continuously.
    fn gap(&self) -> Option<f64> {
        None
    }
}

impl Gap for SolveError {
    fn gap(&self) -> Option<f64> {
        (self.kind == ErrorKind::NoIntersection
            && is_finite(self.magnitude)
            && self.magnitude > 0.0)
            .then_some(self.magnitude)
    }
}

impl Gap for () {}
impl Gap for &str {}
impl Gap for String {}

/// At most this many steps of the descent on a start's gap ([`reach_assembly`]).
const GAP_STEPS: usize = 40;

/// From a start `x` where the assembly fails with a gap (`first`), the nearest stretch where
/// it exists, by Newton's method on the gap: its gradient by forward differences, each step
/// aimed a tenth past where the gap would close, at most half a scale per default, halved
/// until the gap falls. The answer's residuals, with `x` moved there; else the start's error.
/// So an iteration starts from any default whose loci can be brought to meet (a sketch drawn
/// where two circles miss), not only from one beside the stretch where they do.
#[cold]
#[inline(never)]
fn reach_assembly<const N: usize, E: Gap>(
    x: &mut [f64; N],
    scale: &[f64; N],
    budget: &mut Budget,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    first: E,
) -> Result<[f64; N], E> {
    let mut r = [0.0; N];
    // A descent that fails reports the start's own error: what the defaults given meet, the
    // same in every build (a stalled descent's last gap depends on rounding).
    let error = first;
    let Some(mut gap) = error.gap() else {
        return Err(error);
    };
    let usable = |r: &[f64; N]| r.iter().all(|v| is_finite(*v));
    for _ in 0..GAP_STEPS {
        let mut gradient = [0.0; N];
        for i in 0..N {
            let s = sane_scale(scale[i], x[i]);
            let h = f64::EPSILON.sqrt() * x[i].abs().max(s);
            let mut y = *x;
            y[i] += h;
            if !budget.take() {
                return Err(error);
            }
            match f(&y, &mut r) {
                Ok(()) if usable(&r) => {
                    *x = y;
                    return Ok(r);
                }
                Ok(()) => {}
                Err(e) => {
                    if let Some(g) = e.gap() {
                        gradient[i] = (g - gap) / h;
                    }
                }
            }
        }
        let norm2: f64 = gradient.iter().map(|g| g * g).sum();
        if !(is_finite(norm2) && norm2 > 0.0) {
            return Err(error);
        }
        let mut step = [0.0; N];
        let mut shrink: f64 = 1.0;
        for i in 0..N {
            step[i] = -1.1 * gap * gradient[i] / norm2;
            let bound = 0.5 * sane_scale(scale[i], x[i]);
            if step[i].abs() > bound {
                shrink = shrink.min(bound / step[i].abs());
            }
        }
        let mut t = shrink;
        let mut fell = false;
        for _ in 0..20 {
            let mut y = *x;
            for i in 0..N {
                y[i] += t * step[i];
            }
            if !budget.take() {
                return Err(error);
            }
            match f(&y, &mut r) {
                Ok(()) if usable(&r) => {
                    *x = y;
                    return Ok(r);
                }
                Ok(()) => {}
                Err(e) => {
                    if let Some(g) = e.gap().filter(|&g| g < gap) {
                        *x = y;
                        gap = g;
                        fell = true;
                        break;
                    }
                }
            }
            t *= 0.5;
        }
        if !fell {
            return Err(error);
        }
    }
    Err(error)
}

// ---------------------------------------------------------------------------------------------
// What a failure says.

/// Tells, of an iteration from `start` that stopped at `best` without converging (`failure`),
/// whether no assembly exists at all (one default over a known span: no root over it), or none
/// near the start (a minimum of the closing error that is not zero), else leaves it
/// [`Failure::NoConvergence`]. Only a failure pays for this: out of line, and cold.
#[cold]
#[inline(never)]
fn classify<const N: usize, E: Gap>(
    start: &[f64; N],
    best: &[f64; N],
    scale: &[f64; N],
    settings: &Settings,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    failure: Failure<E>,
) -> Failure<E> {
    let Failure::NoConvergence {
        residual,
        iterations,
    } = failure
    else {
        return failure;
    };
    // A start that is not finite, or whose residual is not: nothing to search from.
    if !is_finite(residual) || start.iter().any(|v| !is_finite(*v)) {
        return failure;
    }
    // One angle: its whole turn, for a root anywhere.
    if N == 1 && settings.span == Span::Turn {
        let (mut point, mut r) = ([0.0; N], [0.0; N]);
        let pi = core::f64::consts::PI;
        let samples = crate::outer::ANGLE_SAMPLES;
        let scan: RootScan<1> = all_roots(-pi, pi, true, samples, settings, |t| {
            point[0] = t;
            f(&point, &mut r).map(|()| r[0])
        });
        if scan.is_empty() && is_finite(scan.least()) {
            return Failure::NoAssembly {
                least: scan.least(),
                iterations,
            };
        }
    }
    // A minimum that is not zero where the iteration stopped, confirmed and found to the last
    // digits (the scalar search's `settle` may have stopped at one already, but its bottom
    // may be cut short by the search's budget, or be the corner of a magnitude's V that its
    // minimization did not resolve: it is confirmed like any other).
    let minimum = nonzero_minimum(best, scale, settings, |p: &[f64; N]| {
        let mut r = [0.0; N];
        f(p, &mut r).ok().map(|()| r)
    });
    match minimum {
        Some(residual) => Failure::NoAssemblyNear {
            residual,
            iterations,
        },
        None => failure,
    }
}

/// Whether `start`, where an iteration stopped short of a root, lies in the valley of a local
/// minimum of the closing errors whose bottom is not zero: `Some(their norm there)`, the root of
/// the sum of their squares, else `None` (a root, a slope, a saddle, an edge of the stretch where
/// the assembly exists, or a budget spent before the bottom was found).
///
/// Newton's method on `phi = |r|^2 / 2` ([`descend`]) finds the bottom with differences of step
/// [`tol::CURVATURE_STEP`], then again from there with steps sixteen times shorter: a smooth
/// bottom is the same at both (to the last digits), while the corner of a magnitude's V (a
/// distance, whose root is a kink) straddled by the differences looks like a bottom about a
/// step's slope above zero, which the shorter steps see fall by about their ratio. A bottom
/// that falls by more than half is no bottom: `None`. Both share the settings' budget. Out of
/// line and cold: a failure's only.
#[cold]
#[inline(never)]
fn nonzero_minimum<const N: usize>(
    start: &[f64; N],
    scale: &[f64; N],
    settings: &Settings,
    mut residuals: impl FnMut(&[f64; N]) -> Option<[f64; N]>,
) -> Option<f64> {
    let mut budget = Budget::new(settings.max_evaluations);
    let mut s = SVector::<f64, N>::zeros();
    for i in 0..N {
        s[i] = sane_scale(scale[i], start[i]);
    }
    // The residuals at the point `y` (scaled); `None` where the assembly fails, one is not
    // finite, or the budget is spent.
    let mut at = |y: &SVector<f64, N>| -> Option<SVector<f64, N>> {
        let x = y.component_mul(&s);
        if !budget.take() || x.iter().any(|v| !is_finite(*v)) {
            return None;
        }
        let r = residuals(&x.into())?;
        r.iter().all(|v| is_finite(*v)).then(|| SVector::from(r))
    };
    let y = SVector::from(*start).component_div(&s);
    let (y, coarse) = descend(y, tol::CURVATURE_STEP, settings.tolerance, &mut at)?;
    let (_, fine) = descend(y, tol::CURVATURE_STEP / 16.0, settings.tolerance, &mut at)?;
    (fine.norm() >= 0.5 * coarse.norm()).then(|| fine.norm())
}

/// Newton's method on `phi = |r|^2 / 2` from the point `y` (in variables divided by their
/// scales), with the residuals `at` gives: the bottom of the valley it lies in and the residuals
/// there, or `None` (see [`nonzero_minimum`]).
///
/// The gradient `J^T r` and the Hessian `J^T J + sum r_k H_k` (`H_k` the second derivatives of
/// residual `k`) come from central differences of the residuals (steps `step` times
/// `max(|y_i|, 1)`; the four points around each pair for a mixed derivative): `2 N^2 + 1`
/// evaluations a step, [`MINIMUM_STEPS`] steps at most. The curvature is `phi`'s own, not the
/// Gauss-Newton `J^T J`, which at a fold is singular in just the direction that matters; and
/// both the gradient's and the curvature's errors from the differences are proportional to
/// `|r|`, so that a smooth bottom is told from a slope however near zero it lies. A step must
/// lower `phi` (halved up to six times), and is at most [`MAX_STEP`] scales long. The bottom
/// is found where the Hessian is positive definite (a Cholesky factorisation exists) and
/// Newton's step would lower `phi` by at most [`tol::MINIMUM_CONFIRM_REL`] of it; that step,
/// one evaluation more, is kept if it is lower still, so that the residuals returned are the
/// bottom's to about the last digits. It is a root instead, and `None`, when the largest
/// residual falls within `tolerance` on the way.
fn descend<const N: usize>(
    mut y: SVector<f64, N>,
    step: f64,
    tolerance: f64,
    at: &mut impl FnMut(&SVector<f64, N>) -> Option<SVector<f64, N>>,
) -> Option<(SVector<f64, N>, SVector<f64, N>)> {
    let mut r0 = at(&y)?;
    for _ in 0..MINIMUM_STEPS {
        if largest(r0.as_slice()) <= tolerance {
            return None;
        }
        let p0 = 0.5 * r0.norm_squared();
        let mut h = SVector::<f64, N>::zeros();
        for i in 0..N {
            h[i] = step * y[i].abs().max(1.0);
        }
        let along = |i: usize, k: f64| {
            let mut d = SVector::<f64, N>::zeros();
            d[i] = k * h[i];
            d
        };
        let mut jacobian = SMatrix::<f64, N, N>::zeros();
        let mut hessian = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            let plus = at(&(y + along(i, 1.0)))?;
            let minus = at(&(y + along(i, -1.0)))?;
            jacobian.set_column(i, &((plus - minus) / (2.0 * h[i])));
            let second = ((plus - r0) + (minus - r0)) / (h[i] * h[i]);
            hessian[(i, i)] = r0.dot(&second);
        }
        for i in 0..N {
            for j in i + 1..N {
                let mut corners = [SVector::<f64, N>::zeros(); 4];
                for (c, (a, b)) in
                    corners
                        .iter_mut()
                        .zip([(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)])
                {
                    *c = at(&(y + along(i, a) + along(j, b)))?;
                }
                let second =
                    ((corners[0] - corners[1]) - (corners[2] - corners[3])) / (4.0 * h[i] * h[j]);
                let mixed = r0.dot(&second);
                hessian[(i, j)] = mixed;
                hessian[(j, i)] = mixed;
            }
        }
        hessian += jacobian.transpose() * jacobian;
        let gradient = jacobian.transpose() * r0;
        let cholesky = hessian.cholesky()?;
        let mut newton = -cholesky.solve(&gradient);
        let decrease = -0.5 * gradient.dot(&newton);
        if !is_finite(decrease) {
            return None;
        }
        if decrease <= tol::MINIMUM_CONFIRM_REL * p0 {
            // One more step takes the bottom to the last digits (Newton's convergence is
            // quadratic), kept if it is lower.
            let last = at(&(y + newton)).filter(|r| r.norm_squared() < r0.norm_squared());
            return Some(match last {
                Some(r) => (y + newton, r),
                None => (y, r0),
            });
        }
        let length = newton.norm();
        if length > MAX_STEP {
            newton *= MAX_STEP / length;
        }
        let mut accepted = false;
        for _ in 0..6 {
            if let Some(r) = at(&(y + newton)) {
                if r.norm_squared() < r0.norm_squared() {
                    (y, r0) = (y + newton, r);
                    accepted = true;
                    break;
                }
            }
            newton *= 0.5;
        }
        if !accepted {
            return None;
        }
    }
    None
}

/// A count of evaluations against a limit.
#[derive(Clone, Copy, Debug)]
struct Budget {
    used: u32,
    limit: u32,
}

impl Budget {
    fn new(limit: u32) -> Self {
        Self { used: 0, limit }
    }

    /// Spends one evaluation; `false` when none is left.
    fn take(&mut self) -> bool {
        if self.used < self.limit {
            self.used += 1;
            true
        } else {
            false
        }
    }
}

/// The outcome of one evaluation inside an iteration.
#[derive(Clone, Copy, Debug)]
enum Probe<T> {
    /// Finite residuals.
    Good(T),
    /// The assembly failed, or a residual or the point is not finite.
    Bad,
    /// The budget is spent: nothing was evaluated.
    Exhausted,
}

/// The natural size of a default: `scale` when finite and positive, else `max(|x|, 1)`.
fn sane_scale(scale: f64, x: f64) -> f64 {
    if is_finite(scale) && scale > 0.0 {
        scale
    } else {
        x.abs().max(1.0)
    }
}

/// The largest magnitude among `values`, NaN if any is NaN (so a NaN never looks small).
fn largest(values: &[f64]) -> f64 {
    let mut m: f64 = 0.0;
    for &v in values {
        if v.is_nan() {
            return f64::NAN;
        }
        m = m.max(v.abs());
    }
    m
}

// ---------------------------------------------------------------------------------------------
// Brackets of the scalar iteration.

/// Which end of a bracket moved.
#[derive(Clone, Copy, Debug, PartialEq)]
enum End {
    Lo,
    Hi,
}

/// An interval whose ends have residuals of opposite signs, so that it holds a root (when `f`
/// is continuous there). Narrowed by the points evaluated inside it.
#[derive(Clone, Copy, Debug)]
struct Bracket {
    lo: f64,
    f_lo: f64,
    hi: f64,
    f_hi: f64,
    /// The values the false-position step uses: the residuals, except that the Illinois rule
    /// halves the value of an end that stayed put twice, so that both ends converge.
    weight_lo: f64,
    weight_hi: f64,
    last_moved: Option<End>,
    /// The width three narrowings ago; when three narrowings have not halved it, the next
    /// proposal bisects (the guard against slow one-sided convergence).
    width_mark: f64,
    narrowings: u8,
    bisect_next: bool,
}

impl Bracket {
    /// The bracket of `a` and `b`, if their finite residuals have strictly opposite signs.
    fn new(a: f64, fa: f64, b: f64, fb: f64) -> Option<Self> {
        let opposite = fa * fb < 0.0;
        if !opposite || !is_finite(a) || !is_finite(b) || a == b {
            return None;
        }
        let ((lo, f_lo), (hi, f_hi)) = if a < b {
            ((a, fa), (b, fb))
        } else {
            ((b, fb), (a, fa))
        };
        Some(Self {
            lo,
            f_lo,
            hi,
            f_hi,
            weight_lo: f_lo,
            weight_hi: f_hi,
            last_moved: None,
            width_mark: hi - lo,
            narrowings: 0,
            bisect_next: false,
        })
    }

    /// Whether `t` lies strictly inside.
    fn contains(&self, t: f64) -> bool {
        self.lo < t && t < self.hi
    }

    /// The midpoint, without overflow.
    fn midpoint(&self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }

    /// Whether no double lies strictly inside: the root is found to the last bit.
    fn is_collapsed(&self) -> bool {
        !self.contains(self.midpoint())
    }

    /// The end with the smaller residual, and its residual.
    fn best(&self) -> (f64, f64) {
        if self.f_lo.abs() <= self.f_hi.abs() {
            (self.lo, self.f_lo)
        } else {
            (self.hi, self.f_hi)
        }
    }

    /// The next point to evaluate: the Illinois false-position point, or the midpoint when that
    /// falls outside or the bracket has been shrinking slowly.
    fn propose(&self) -> f64 {
        let mid = self.midpoint();
        if self.bisect_next {
            return mid;
        }
        let t =
            self.lo - self.weight_lo * ((self.hi - self.lo) / (self.weight_hi - self.weight_lo));
        if self.contains(t) {
            t
        } else {
            mid
        }
    }

    /// Narrows to the side of `t` where the sign changes (`ft` finite); a zero makes the
    /// bracket the single point `t`. Points outside are ignored.
    fn narrow(&mut self, t: f64, ft: f64) {
        if !self.contains(t) || !is_finite(ft) {
            return;
        }
        if ft == 0.0 {
            (self.lo, self.hi, self.f_lo, self.f_hi) = (t, t, 0.0, 0.0);
            return;
        }
        let end = if (ft < 0.0) == (self.f_lo < 0.0) {
            End::Lo
        } else {
            End::Hi
        };
        match end {
            End::Lo => {
                (self.lo, self.f_lo, self.weight_lo) = (t, ft, ft);
                if self.last_moved == Some(End::Lo) {
                    self.weight_hi *= 0.5;
                }
            }
            End::Hi => {
                (self.hi, self.f_hi, self.weight_hi) = (t, ft, ft);
                if self.last_moved == Some(End::Hi) {
                    self.weight_lo *= 0.5;
                }
            }
        }
        self.last_moved = Some(end);
        self.bisect_next = false;
        self.narrowings += 1;
        if self.narrowings >= 3 {
            let width = self.hi - self.lo;
            self.bisect_next = width > 0.5 * self.width_mark;
            self.width_mark = width;
            self.narrowings = 0;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One default.

/// Solves a scalar equation: the `N = 1` case of [`solve`].
fn solve_scalar<E: Gap>(
    x: &mut f64,
    scale: f64,
    settings: &Settings,
    mut f: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Converged, Failure<E>> {
    let mut budget = Budget::new(settings.max_evaluations);
    if !is_finite(*x) || !budget.take() {
        return Err(Failure::NoConvergence {
            residual: f64::NAN,
            iterations: 0,
        });
    }
    let fx = match f(*x) {
        Ok(v) => v,
        Err(e) => {
            // A start just outside the stretch where the assembly exists (a sweep's last
            // answer, one step on): the nearest point where it does, at most half a scale
            // away on either side, so that the iteration stays on that assembly.
            let s = sane_scale(scale, *x);
            let mut found = None;
            'probe: for j in 0..12 {
                let d = s * 0.5f64.powi(12 - j);
                for t in [*x + d, *x - d] {
                    if !budget.take() {
                        break 'probe;
                    }
                    if let Ok(v) = f(t) {
                        if is_finite(v) {
                            found = Some((t, v));
                            break 'probe;
                        }
                    }
                }
            }
            match found {
                Some((t, v)) => {
                    *x = t;
                    v
                }
                // None beside it: descend on the start's gap to where the assembly exists.
                None => {
                    let mut point = [*x];
                    let mut g = |p: &[f64; 1], r: &mut [f64; 1]| f(p[0]).map(|v| r[0] = v);
                    match reach_assembly(&mut point, &[s], &mut budget, &mut g, e) {
                        Ok(r) => {
                            *x = point[0];
                            r[0]
                        }
                        Err(e) => return Err(Failure::Start(e)),
                    }
                }
            }
        }
    };
    if !is_finite(fx) {
        return Err(Failure::NoConvergence {
            residual: fx.abs(),
            iterations: 0,
        });
    }
    // The common case first: a start near the root, where a Newton step and then secant steps
    // each halve the residual. Only when one does not is the safeguarded search needed, from
    // the best point reached.
    let scale = sane_scale(scale, *x);
    let (fx, quick_iterations) = match quick(x, fx, scale, settings, &mut budget, &mut f) {
        Quick::Converged {
            residual,
            iterations,
        } => {
            return Ok(Converged {
                iterations,
                evaluations: budget.used,
                residual,
            })
        }
        Quick::Handover { f, iterations } => (f, iterations),
    };
    let mut search = Scalar {
        f: |t: f64| f(t).ok(),
        budget,
        scale,
        best_x: *x,
        best_f: fx,
        bracket: None,
        slope: None,
        previous_best: None,
        earlier_best: None,
        previous: None,
        iterations: 0,
    };
    let converged = search.run(settings.tolerance);
    if converged && search.best_f.abs() > settings.rounding {
        search.polish();
    }
    *x = search.best_x;
    let residual = search.best_f.abs();
    let iterations = quick_iterations + search.iterations;
    if converged {
        Ok(Converged {
            iterations,
            evaluations: search.budget.used,
            residual,
        })
    } else {
        Err(Failure::NoConvergence {
            residual,
            iterations,
        })
    }
}

/// The slope at `x1` of the parabola through `earlier`, `(x0, f0)` and `(x1, f1)`: exact to
/// second order, so that steps on it converge with order about 1.8. Their secant's without
/// `earlier` or where the parabola's is not usable; `None` when neither is (not finite, or
/// zero).
fn local_slope(
    earlier: Option<(f64, f64)>,
    (x0, f0): (f64, f64),
    (x1, f1): (f64, f64),
) -> Option<f64> {
    let dx = x1 - x0;
    let secant = (f1 - f0) * (1.0 / dx);
    let usable = |d: f64| is_finite(d) && d != 0.0;
    let parabola = (earlier.filter(|&(xm, _)| xm != x0)).map(|(xm, fm)| {
        let curvature = (secant - (f0 - fm) * (1.0 / (x0 - xm))) * (1.0 / (x1 - xm));
        secant + curvature * dx
    });
    parabola
        .filter(|&d| usable(d))
        .or_else(|| usable(secant).then_some(secant))
}

/// How [`quick`] ended.
enum Quick {
    /// Within the tolerance, and polished as [`Scalar::polish`] would: the answer is in `x`.
    Converged { residual: f64, iterations: u32 },
    /// A step that did not halve the residual, or an assembly that failed: the best point is in
    /// `x`, its residual `f`, for the safeguarded search to go on from.
    Handover { f: f64, iterations: u32 },
}

/// The iteration of a start near its root (a sweep's last answer, one step on), with none of
/// the safeguarded search's bookkeeping: Newton's step on a forward difference, then secant
/// steps (the slope of the parabola through the last three points, the forward difference's
/// among them at first, as [`Scalar::secant_slope`]), each at most [`MAX_STEP`] scales. Every step must halve the
/// residual; the first that does not, or fails to assemble, hands the best point over to the
/// safeguarded search. Within the tolerance, steps go on while each at least halves the
/// residual, at most [`POLISH_STEPS`] of them, until rounding level: the same answers as the
/// search's polish, for a fifth of its work per step.
fn quick<E>(
    x: &mut f64,
    fx: f64,
    scale: f64,
    settings: &Settings,
    budget: &mut Budget,
    f: &mut impl FnMut(f64) -> Result<f64, E>,
) -> Quick {
    let mut eval = |t: f64, budget: &mut Budget| -> Option<f64> {
        if !is_finite(t) || !budget.take() {
            return None;
        }
        f(t).ok().filter(|v| is_finite(*v))
    };
    // Ends at the point `(t, ft)`: the answer when within the tolerance, else the search's
    // start.
    let stop = |x: &mut f64, (t, ft): (f64, f64), iterations: u32| {
        *x = t;
        if ft.abs() <= settings.tolerance {
            Quick::Converged {
                residual: ft.abs(),
                iterations,
            }
        } else {
            Quick::Handover { f: ft, iterations }
        }
    };
    let radius = MAX_STEP * scale;
    let (mut xb, mut fb) = (*x, fx);
    if fb.abs() <= settings.rounding {
        return stop(x, (xb, fb), 0);
    }
    let h = tol::SQRT_EPS * xb.abs().max(scale);
    let Some(fh) = eval(xb + h, budget) else {
        // No slope here: the search tries the other side.
        return Quick::Handover {
            f: fb,
            iterations: 0,
        };
    };
    let mut slope = (fh - fb) / h;
    // The point before the best, for the parabola's slope: at first the difference's, so that
    // the first secant step already takes the parabola's slope (the second step's error is
    // then of third order in the first's, not of second).
    let mut earlier: Option<(f64, f64)> = Some((xb + h, fh));
    let (mut iterations, mut polished) = (0, 0);
    loop {
        let within = fb.abs() <= settings.tolerance;
        if fb == 0.0 || (within && (fb.abs() <= settings.rounding || polished == POLISH_STEPS)) {
            return stop(x, (xb, fb), iterations);
        }
        let step = (-fb / slope).clamp(-radius, radius);
        let t = xb + step;
        if !is_finite(step) || t == xb {
            return stop(x, (xb, fb), iterations);
        }
        let Some(ft) = eval(t, budget) else {
            return stop(x, (xb, fb), iterations);
        };
        iterations += 1;
        polished += u32::from(within);
        if ft.abs() > POLISH_GAIN * fb.abs() {
            // Not halved. A step past the bottom of a magnitude's V is retried on the slope of
            // the best point's own side (within the tolerance, as a polishing step).
            if !within || polished < POLISH_STEPS {
                if let Some((u, fu, d)) =
                    v_step((xb, fb), (t, ft), slope, radius, |u| eval(u, budget))
                {
                    iterations += 1;
                    polished += u32::from(within);
                    (xb, fb, slope, earlier) = (u, fu, d, None);
                    continue;
                }
            }
            // The better of the two ends it (the answer within the tolerance, the search's
            // start before it).
            let best = if ft.abs() < fb.abs() {
                (t, ft)
            } else {
                (xb, fb)
            };
            return stop(x, best, iterations);
        }
        slope = match local_slope(earlier, (xb, fb), (t, ft)) {
            Some(d) => d,
            None => return stop(x, (t, ft), iterations),
        };
        earlier = Some((xb, fb));
        (xb, fb) = (t, ft);
    }
}

/// The retry of a step from `(x, fx)` to `t` that did not halve the residual although `f(t)`
/// has the sign of `fx`: the residual may be a magnitude (a point's distance from a line, a
/// circle or a point of space, which a default moves it across), V-shaped at its root, whose
/// slope changes sign there, so that a step on the slope of one side, or a secant through
/// points on both, misses the bottom. The bottom lies either toward `t` (the step crossed it:
/// `|f(x)| + |f(t)|` is the V's slope times `|t - x|`) or away from it (the step went up the
/// other side: `|f(t)| - |f(x)|` is); of the two slopes these give, the one nearer `slope`, the
/// magnitude of the slope the step was taken on, tells which, and the bottom is tried where the
/// V of that slope through the two points has it. For a residual with a sign the try is one
/// more step like another, kept only if it halves `fx`, and like every step at most `radius`
/// long. `Some((point, residual, slope))` when it does, the slope signed for a step from `x`'s
/// side; `None` otherwise, or when `f(t)` has the other sign (a crossing, which the secant
/// handles).
fn v_step(
    (x, fx): (f64, f64),
    (t, ft): (f64, f64),
    slope: f64,
    radius: f64,
    mut eval: impl FnMut(f64) -> Option<f64>,
) -> Option<(f64, f64, f64)> {
    if ft * fx <= 0.0 || t == x || !is_finite(slope) {
        return None;
    }
    let (a, b, dt) = (fx.abs(), ft.abs(), (t - x).abs());
    let toward = (t - x).signum();
    let (k_crossed, k_up) = ((a + b) / dt, (b - a).abs() / dt);
    let crossed = (k_crossed - slope.abs()).abs() < (k_up - slope.abs()).abs();
    let (k, direction) = if crossed {
        (k_crossed, toward)
    } else {
        (k_up, -toward)
    };
    if !(is_finite(k) && k > 0.0) {
        return None;
    }
    let u = x + direction * (a / k);
    if !is_finite(u) || u == x || a / k > radius {
        return None;
    }
    let fu = eval(u)?;
    // On `x`'s side the residual's magnitude falls toward the bottom.
    let signed = -direction * k * fx.signum();
    (fu.abs() <= POLISH_GAIN * a).then_some((u, fu, signed))
}

/// The state of a scalar iteration.
struct Scalar<F> {
    /// The residual function, `None` where the assembly fails.
    f: F,
    budget: Budget,
    scale: f64,
    /// The point with the smallest residual magnitude so far, and its residual.
    best_x: f64,
    best_f: f64,
    /// A sign change, once one has been seen.
    bracket: Option<Bracket>,
    /// The last finite-difference derivative.
    slope: Option<f64>,
    /// The best point before the current one, for the secant slope of the polishing steps.
    previous_best: Option<(f64, f64)>,
    /// The best point before that, for the parabola's slope.
    earlier_best: Option<(f64, f64)>,
    /// Before any sign change: the last base point and the derivative there, to see the
    /// derivative change sign (a local minimum of `|f|` passed).
    previous: Option<(f64, f64)>,
    iterations: u32,
}

impl<F: FnMut(f64) -> Option<f64>> Scalar<F> {
    fn probe(&mut self, t: f64) -> Probe<f64> {
        if !self.budget.take() {
            return Probe::Exhausted;
        }
        if !is_finite(t) {
            return Probe::Bad;
        }
        match (self.f)(t) {
            Some(v) if is_finite(v) => Probe::Good(v),
            _ => Probe::Bad,
        }
    }

    /// [`Scalar::probe`]'s residual, `None` for every other outcome.
    fn value(&mut self, t: f64) -> Option<f64> {
        match self.probe(t) {
            Probe::Good(v) => Some(v),
            _ => None,
        }
    }

    /// The point steps start from: the better end of the bracket once there is one.
    fn base(&self) -> (f64, f64) {
        match self.bracket {
            Some(b) => b.best(),
            None => (self.best_x, self.best_f),
        }
    }

    /// The shortest step worth taking from `x`: below the finite-difference step the
    /// derivative says nothing.
    fn min_step(&self, x: f64) -> f64 {
        tol::SQRT_EPS * x.abs().max(self.scale)
    }

    /// The shortest step taken back from a point where the assembly fails: a few units of
    /// rounding at `x`, so that a root beside the edge of the stretch where it exists is
    /// reached however close to that edge it lies.
    fn edge_step(&self, x: f64) -> f64 {
        4.0 * f64::EPSILON * x.abs().max(self.scale)
    }

    /// Records a good point: the bracket, and the best point.
    fn record(&mut self, t: f64, ft: f64) {
        match &mut self.bracket {
            Some(b) => b.narrow(t, ft),
            None => self.bracket = Bracket::new(self.best_x, self.best_f, t, ft),
        }
        if ft.abs() < self.best_f.abs() {
            self.earlier_best = self.previous_best;
            self.previous_best = Some((self.best_x, self.best_f));
            (self.best_x, self.best_f) = (t, ft);
        }
    }

    /// Steps until the best residual is within `tolerance` (`true`), or the iteration cannot go
    /// on (`false`: budget spent, stalled, or a collapsed bracket above the tolerance).
    fn run(&mut self, tolerance: f64) -> bool {
        let mut stalled = false;
        loop {
            if self.best_f.abs() <= tolerance {
                return true;
            }
            if self.bracket.is_some_and(|b| b.is_collapsed()) || !self.measure_slope() {
                return false;
            }
            if self.best_f.abs() <= tolerance {
                return true;
            }
            if self.bracket.is_none() {
                let here = self.slope.map(|s| (self.best_x, s));
                if let (Some((x0, s0)), Some((_, s1))) = (self.previous, here) {
                    if s0 * s1 < 0.0 {
                        self.iterations += 1;
                        if !self.settle(x0, tolerance) {
                            return false;
                        }
                        continue;
                    }
                }
                self.previous = here;
            }
            let progress = match self.bracket {
                Some(b) => self.bracketed_step(b, stalled),
                None => self.search_step(),
            };
            match progress {
                Some(halved) => stalled = !halved,
                None => return false,
            }
            self.iterations += 1;
        }
    }

    /// The derivative changed sign between `x0` and the best point without `f` changing sign:
    /// a minimum of `|f|` lies between, which damped Newton cannot leave. Brent's minimization
    /// finds its bottom: `true` when that is within the tolerance (a double root), or when the
    /// valley crosses zero (a bracket, to go on with); `false` otherwise: no root here.
    fn settle(&mut self, x0: f64, tolerance: f64) -> bool {
        let (x1, f1) = (self.best_x, self.best_f);
        let sign = f1.signum();
        let abs_tol = tol::LOCATE_ABS * tol::SQRT_EPS * self.scale;
        let found = valley(
            x0.min(x1),
            x0.max(x1),
            (x1, f1),
            sign,
            tolerance,
            abs_tol,
            |u| self.probe(u),
        );
        match found {
            Valley::Crossing { x, f } => {
                self.record(x, f);
                true
            }
            Valley::Bottom { x, g } => {
                self.record(x, sign * g);
                g <= tolerance
            }
        }
    }

    /// The derivative at the base point: the secant through it and the best point before it
    /// once the iteration converges fast (see [`Scalar::secant_slope`]), else a forward
    /// difference (backward when forward fails, inward when bracketed), whose point is
    /// recorded too. `false` when the budget is spent.
    fn measure_slope(&mut self) -> bool {
        if let Some(d) = self.secant_slope() {
            self.slope = Some(d);
            return true;
        }
        let (x, fx) = self.base();
        let mut h = self.min_step(x);
        if let Some(b) = self.bracket {
            h = h.min(0.5 * (b.hi - b.lo));
            if x >= b.hi {
                h = -h;
            }
        }
        self.slope = None;
        if h == 0.0 {
            return true;
        }
        for dx in [h, -h] {
            match self.probe(x + dx) {
                Probe::Good(ft) => {
                    self.slope = Some((ft - fx) / dx);
                    self.record(x + dx, ft);
                    return true;
                }
                Probe::Bad => {}
                Probe::Exhausted => return false,
            }
        }
        true
    }

    /// The secant slope through the best point and the best before it, when the last step
    /// at least quartered the residual and was short (at most [`SECANT_REACH`] of the scale):
    /// then the two points are close to the root, the secant is as good a derivative as a
    /// forward difference there, and it costs no evaluation (the secant method's order, 1.6,
    /// for one evaluation a step, against Newton's 2 for two). Elsewhere `None`.
    fn secant_slope(&self) -> Option<f64> {
        let (x0, f0) = self.previous_best?;
        let (x1, f1) = self.base();
        let dx = x1 - x0;
        if f1.abs() > 0.25 * f0.abs() || dx.abs() > SECANT_REACH * self.scale {
            return None;
        }
        // With a third point near, the parabola through the three.
        let near =
            (self.earlier_best).filter(|&(xm, _)| (x1 - xm).abs() <= SECANT_REACH * self.scale);
        local_slope(near, (x0, f0), (x1, f1))
    }

    /// The Newton step from `(x, fx)`, bounded by the trust region; `None` without a usable
    /// derivative.
    fn newton_step(&self, fx: f64) -> Option<f64> {
        let radius = MAX_STEP * self.scale;
        let slope = self.slope?;
        let step = -fx / slope;
        if is_finite(step) && step != 0.0 {
            Some(step.clamp(-radius, radius))
        } else if slope * fx > 0.0 {
            // A derivative so large the step underflows, or infinite: go downhill by the radius.
            Some(-radius)
        } else {
            Some(radius)
        }
    }

    /// A damped Newton step before any sign change: a step that fails or does not reduce the
    /// residual (without crossing zero) is halved. `Some(halved the residual)`, or `None` when
    /// the step shrank below use or the budget is spent.
    fn search_step(&mut self) -> Option<bool> {
        let (x, fx) = (self.best_x, self.best_f);
        let mut step = self.newton_step(fx)?;
        let min_step = self.min_step(x);
        loop {
            match self.probe(x + step) {
                Probe::Good(ft) => {
                    let crossed = (ft < 0.0) != (fx < 0.0) || ft == 0.0;
                    if crossed || ft.abs() < fx.abs() {
                        self.record(x + step, ft);
                        return Some(self.best_f.abs() <= 0.5 * fx.abs());
                    }
                    // Past the bottom of a V, perhaps (see `v_step`).
                    let slope = self.slope.unwrap_or(0.0);
                    let radius = MAX_STEP * self.scale;
                    let v = v_step((x, fx), (x + step, ft), slope, radius, |u| self.value(u));
                    if let Some((u, fu, d)) = v {
                        self.record(u, fu);
                        self.slope = Some(d);
                        return Some(true);
                    }
                }
                Probe::Bad => {
                    // Past the edge of the stretch where the assembly exists: a root may lie
                    // closer to that edge than any step the slope sets (where two circles of
                    // the region come to touch, the root leaves through the edge), so the
                    // step is halved toward it down to rounding.
                    step *= 0.5;
                    if step.abs() < self.edge_step(x) {
                        return None;
                    }
                    continue;
                }
                Probe::Exhausted => return None,
            }
            step *= 0.5;
            if step.abs() < min_step {
                return None;
            }
        }
    }

    /// A step inside the bracket: Newton's when it stays inside and the last step made
    /// progress, else the bracket's (Illinois or bisection). A failing point backs off toward
    /// the base. `Some(halved the residual)`, or `None` when the budget is spent or backing off
    /// found no good point.
    fn bracketed_step(&mut self, bracket: Bracket, stalled: bool) -> Option<bool> {
        let (x, fx) = bracket.best();
        let mut t = match self.newton_step(fx) {
            Some(step) if !stalled && bracket.contains(x + step) => x + step,
            _ => bracket.propose(),
        };
        loop {
            match self.probe(t) {
                Probe::Good(ft) => {
                    self.record(t, ft);
                    break;
                }
                Probe::Bad => {
                    // Toward the base, down to rounding: as in `search_step`, the root may
                    // hug the edge of the stretch where the assembly exists.
                    t = x + 0.5 * (t - x);
                    if (t - x).abs() < self.edge_step(x) {
                        return None;
                    }
                }
                Probe::Exhausted => return None,
            }
        }
        Some(self.base().1.abs() <= 0.5 * fx.abs())
    }

    /// Up to [`POLISH_STEPS`] secant steps from the best point, while each at least halves the
    /// residual; only improvements are kept. The first slope is the secant through the best
    /// point and the one before it (the last step, so it is as local as the answer), else the
    /// last difference, else a new one.
    fn polish(&mut self) {
        let usable = |d: f64| is_finite(d) && d != 0.0;
        let secant = |(x0, f0): (f64, f64), (x1, f1): (f64, f64)| (f1 - f0) / (x1 - x0);
        let mut slope = self
            .previous_best
            .map(|p| secant(p, (self.best_x, self.best_f)))
            .filter(|d| usable(*d))
            .or(self.slope.filter(|d| usable(*d)));
        for _ in 0..POLISH_STEPS {
            let (x, fx) = (self.best_x, self.best_f);
            if fx == 0.0 {
                return;
            }
            let d = match slope {
                Some(d) => d,
                None => {
                    let h = self.min_step(x);
                    match self.probe(x + h) {
                        Probe::Good(fh) if usable((fh - fx) / h) => (fh - fx) / h,
                        _ => return,
                    }
                }
            };
            let t = x - fx / d;
            if !is_finite(t) || t == x {
                return;
            }
            match self.probe(t) {
                Probe::Good(ft) => {
                    self.iterations += 1;
                    slope = Some(secant((x, fx), (t, ft))).filter(|d| usable(*d));
                    if ft.abs() > POLISH_GAIN * fx.abs() {
                        // Past the bottom of a V, perhaps: the slope of the best point's side.
                        let radius = MAX_STEP * self.scale;
                        let retried = v_step((x, fx), (t, ft), d, radius, |u| self.value(u));
                        match retried {
                            Some((u, fu, d)) => {
                                self.iterations += 1;
                                (self.best_x, self.best_f) = (u, fu);
                                slope = Some(d);
                                continue;
                            }
                            None => {
                                if ft.abs() < fx.abs() {
                                    (self.best_x, self.best_f) = (t, ft);
                                }
                                return;
                            }
                        }
                    }
                    (self.best_x, self.best_f) = (t, ft);
                }
                _ => return,
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Several defaults.

/// Solves a square system: the `N != 1` case of [`solve`].
pub(crate) fn solve_system<const N: usize, E: Gap>(
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<Converged, Failure<E>> {
    let mut budget = Budget::new(settings.max_evaluations);
    if x.iter().any(|v| !is_finite(*v)) || !budget.take() {
        return Err(Failure::NoConvergence {
            residual: f64::NAN,
            iterations: 0,
        });
    }
    let mut r = [0.0; N];
    if let Err(e) = f(x, &mut r) {
        // A start where the assembly fails: descend on its gap to where it exists.
        match reach_assembly(x, scale, &mut budget, f, e) {
            Ok(found) => r = found,
            Err(e) => return Err(Failure::Start(e)),
        }
    }
    let residual = largest(&r);
    if !is_finite(residual) {
        return Err(Failure::NoConvergence {
            residual,
            iterations: 0,
        });
    }
    let mut sane = [1.0; N];
    for i in 0..N {
        sane[i] = sane_scale(scale[i], x[i]);
    }
    let start = SVector::from(*x);
    let r = SVector::from(r);
    let mut system = System {
        f: |p: &[f64; N], out: &mut [f64; N]| f(p, out).is_ok(),
        budget,
        scale: SVector::from(sane),
        x: start,
        r,
        best_x: start,
        best_r: r,
        best_max: residual,
        radius: MAX_STEP,
        inverse: None,
        iterations: 0,
    };
    let converged = system.run(settings.tolerance);
    if converged && system.best_max > settings.rounding {
        system.polish();
    }
    *x = system.best_x.into();
    if converged {
        Ok(Converged {
            iterations: system.iterations,
            evaluations: system.budget.used,
            residual: system.best_max,
        })
    } else {
        Err(Failure::NoConvergence {
            residual: system.best_max,
            iterations: system.iterations,
        })
    }
}

/// The state of a trust-region iteration on `N` defaults. Steps and the Jacobian are in
/// scaled variables (each default divided by its scale), residuals in the model's units.
struct System<F, const N: usize> {
    /// The residual function: `false` where the assembly fails.
    f: F,
    budget: Budget,
    scale: SVector<f64, N>,
    /// The current point (each accepted step reduces the residual norm) and its residuals.
    x: SVector<f64, N>,
    r: SVector<f64, N>,
    /// The point with the smallest largest residual so far.
    best_x: SVector<f64, N>,
    best_r: SVector<f64, N>,
    best_max: f64,
    /// The trust radius, in scaled units, at most [`MAX_STEP`].
    radius: f64,
    /// The inverse of the last scaled Jacobian, for the polishing steps.
    inverse: Option<SMatrix<f64, N, N>>,
    iterations: u32,
}

impl<F: FnMut(&[f64; N], &mut [f64; N]) -> bool, const N: usize> System<F, N> {
    fn probe(&mut self, point: &SVector<f64, N>) -> Probe<SVector<f64, N>> {
        if !self.budget.take() {
            return Probe::Exhausted;
        }
        if point.iter().any(|v| !is_finite(*v)) {
            return Probe::Bad;
        }
        let p: [f64; N] = (*point).into();
        let mut out = [0.0; N];
        if (self.f)(&p, &mut out) && out.iter().all(|v| is_finite(*v)) {
            Probe::Good(SVector::from(out))
        } else {
            Probe::Bad
        }
    }

    /// The Jacobian at the current point, by forward differences (backward where forward
    /// fails; a zero column where both fail), times the scales. `None` when the budget is
    /// spent.
    fn jacobian(&mut self) -> Option<SMatrix<f64, N, N>> {
        let mut jacobian = SMatrix::<f64, N, N>::zeros();
        for j in 0..N {
            let h = tol::SQRT_EPS * self.x[j].abs().max(self.scale[j]);
            for dx in [h, -h] {
                let mut p = self.x;
                p[j] += dx;
                match self.probe(&p) {
                    Probe::Good(rp) => {
                        jacobian.set_column(j, &((rp - self.r) * (self.scale[j] / dx)));
                        break;
                    }
                    Probe::Bad => {}
                    Probe::Exhausted => return None,
                }
            }
        }
        Some(jacobian)
    }

    /// The smallest trust radius worth trying: a step below it does not change the point.
    fn min_radius(&self) -> f64 {
        let mut size: f64 = 1.0;
        for i in 0..N {
            size = size.max((self.x[i] / self.scale[i]).abs());
        }
        tol::STEP_STOP_REL * size
    }

    fn accept(&mut self, x: SVector<f64, N>, r: SVector<f64, N>) {
        self.x = x;
        self.r = r;
        let m = largest(r.as_slice());
        if m < self.best_max {
            (self.best_x, self.best_r, self.best_max) = (x, r, m);
        }
    }

    /// Iterates until the largest residual is within `tolerance` (`true`) or the iteration
    /// cannot go on (`false`).
    fn run(&mut self, tolerance: f64) -> bool {
        loop {
            if self.best_max <= tolerance {
                return true;
            }
            let Some(jacobian) = self.jacobian() else {
                return false;
            };
            let mut inverse = SMatrix::<f64, N, N>::zeros();
            let newton = if nalgebra::linalg::try_invert_to(jacobian, &mut inverse) {
                Some(-(inverse * self.r)).filter(|n| n.iter().all(|v| is_finite(*v)))
            } else {
                None
            };
            self.inverse = newton.map(|_| inverse);
            let gradient = jacobian.transpose() * self.r;
            let cauchy_length = gradient.norm_squared() / (jacobian * gradient).norm_squared();
            let norm2 = self.r.norm_squared();
            // Retry with smaller radii until a step reduces the residual norm.
            loop {
                let Some(step) = dogleg(newton, &gradient, cauchy_length, self.radius) else {
                    return false;
                };
                let length = step.norm();
                let trial = self.x + step.component_mul(&self.scale);
                let predicted = norm2 - (self.r + jacobian * step).norm_squared();
                match self.probe(&trial) {
                    Probe::Good(rt) => {
                        let actual = norm2 - rt.norm_squared();
                        let ratio = actual / predicted;
                        if actual > 0.0 && (predicted <= 0.0 || ratio >= tol::TRUST_ACCEPT) {
                            if ratio < 0.25 {
                                self.radius = 0.25 * length;
                            } else if ratio > 0.75 && length >= 0.99 * self.radius {
                                self.radius = (2.0 * self.radius).min(MAX_STEP);
                            }
                            self.accept(trial, rt);
                            self.iterations += 1;
                            break;
                        }
                        self.radius = 0.5 * length;
                    }
                    Probe::Bad => self.radius = 0.5 * length,
                    Probe::Exhausted => return false,
                }
                if self.radius.is_nan() || self.radius < self.min_radius() {
                    return false;
                }
            }
        }
    }

    /// Up to [`POLISH_STEPS`] Newton steps from the best point with the last Jacobian (one
    /// evaluation each), while each at least halves the largest residual.
    fn polish(&mut self) {
        if self.best_max == 0.0 {
            return;
        }
        let inverse = match self.inverse {
            Some(inverse) => inverse,
            None => {
                // Converged at the start: one Jacobian, there.
                (self.x, self.r) = (self.best_x, self.best_r);
                let Some(jacobian) = self.jacobian() else {
                    return;
                };
                let mut inverse = SMatrix::<f64, N, N>::zeros();
                if !nalgebra::linalg::try_invert_to(jacobian, &mut inverse) {
                    return;
                }
                inverse
            }
        };
        for _ in 0..POLISH_STEPS {
            let before = self.best_max;
            if before == 0.0 {
                return;
            }
            let trial = self.best_x - (inverse * self.best_r).component_mul(&self.scale);
            if trial == self.best_x {
                return;
            }
            match self.probe(&trial) {
                Probe::Good(rt) => {
                    self.iterations += 1;
                    self.accept(trial, rt);
                    if largest(rt.as_slice()) > POLISH_GAIN * before {
                        return;
                    }
                }
                _ => return,
            }
        }
    }
}

/// Powell's dogleg step for trust radius `radius`: the Newton step when it fits, else the
/// point at distance `radius` on the path from the origin through the Cauchy point (the
/// minimum of the linear model along steepest descent, `-cauchy_length * gradient`) to the
/// Newton step. Without a Newton step, the Cauchy point cut to the radius. `None` when there is
/// no direction at all (zero gradient and no Newton step).
fn dogleg<const N: usize>(
    newton: Option<SVector<f64, N>>,
    gradient: &SVector<f64, N>,
    cauchy_length: f64,
    radius: f64,
) -> Option<SVector<f64, N>> {
    if let Some(n) = newton {
        if n.norm() <= radius {
            return Some(n);
        }
    }
    let g = gradient.norm();
    if !(g > 0.0 && is_finite(g)) {
        return newton.map(|n| n * (radius / n.norm()));
    }
    let cauchy = gradient * -cauchy_length;
    if !is_finite(cauchy_length) || cauchy.norm() >= radius {
        return Some(gradient * (-radius / g));
    }
    let Some(n) = newton else {
        return Some(cauchy);
    };
    // |cauchy + t (n - cauchy)| = radius for t in [0, 1]: a quadratic a t² + b t + c with
    // c < 0 (the Cauchy point is inside) and a > 0, so exactly one root is positive.
    let d = n - cauchy;
    let a = d.norm_squared();
    let b = 2.0 * cauchy.dot(&d);
    let c = cauchy.norm_squared() - radius * radius;
    let q = -0.5 * (b + b.signum() * (b * b - 4.0 * a * c).max(0.0).sqrt());
    let t = (q / a).max(c / q);
    let t = if is_finite(t) { t.clamp(0.0, 1.0) } else { 1.0 };
    Some(cauchy + d * t)
}

// ---------------------------------------------------------------------------------------------
// Every root over an interval.

/// The roots [`all_roots`] found, ascending, in fixed arrays (no allocation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootScan<const CAP: usize> {
    roots: [f64; CAP],
    residuals: [f64; CAP],
    doubles: [bool; CAP],
    boundaries: [bool; CAP],
    len: usize,
    truncated: bool,
    evaluations: u32,
    least: f64,
}

impl<const CAP: usize> Default for RootScan<CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const CAP: usize> RootScan<CAP> {
    /// No roots.
    pub const fn new() -> Self {
        Self {
            roots: [0.0; CAP],
            residuals: [0.0; CAP],
            doubles: [false; CAP],
            boundaries: [false; CAP],
            len: 0,
            truncated: false,
            evaluations: 0,
            least: f64::INFINITY,
        }
    }

    /// The roots, ascending (periodic: in `[lo, hi)`).
    pub fn roots(&self) -> &[f64] {
        &self.roots[..self.len]
    }

    /// The number of roots kept.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no root was found.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether more than `CAP` roots were found: the largest ones were dropped.
    pub fn truncated(&self) -> bool {
        self.truncated
    }

    /// Whether root `i` is a double (tangent) root: a minimum of `|f|` within the tolerance of
    /// zero, with no sign change (or a dip across zero no deeper than the tolerance). `false`
    /// for an index past the end.
    pub fn is_double(&self, i: usize) -> bool {
        i < self.len && self.doubles[i]
    }

    /// Whether root `i` is the last point where the function is defined next to a point where
    /// it fails (or an end of a non-periodic interval), accepted because `|f|` is within the
    /// tolerance there. `false` for an index past the end.
    pub fn is_boundary(&self, i: usize) -> bool {
        i < self.len && self.boundaries[i]
    }

    /// `|f|` at root `i` (NaN for an index past the end).
    pub fn residual(&self, i: usize) -> f64 {
        if i < self.len {
            self.residuals[i]
        } else {
            f64::NAN
        }
    }

    /// The evaluations of the function the scan made.
    pub fn evaluations(&self) -> u32 {
        self.evaluations
    }

    /// The smallest `|f|` the scan evaluated (infinite where `f` was defined nowhere): the
    /// samples, the bottoms of the minima of `|f|` among them refined (rule 2), the edges of
    /// failing stretches and the points of every refinement. Over an interval with no root,
    /// how close to zero the function comes, to the sampling's resolution: a minimum between
    /// two samples neither of which is a sampled minimum is seen only at those samples.
    pub fn least(&self) -> f64 {
        self.least
    }

    /// Adds a root, merging it with one closer than `same` (measured around the circle of
    /// length `period` when periodic): the one with the smaller residual stays.
    fn insert(&mut self, root: Found, same: f64, period: Option<f64>) {
        for i in 0..self.len {
            let mut d = (self.roots[i] - root.x).abs();
            if let Some(p) = period {
                d = d.min(p - d);
            }
            if d <= same {
                if root.residual < self.residuals[i] {
                    self.remove(i);
                    self.place(root);
                }
                return;
            }
        }
        self.place(root);
    }

    fn remove(&mut self, i: usize) {
        for j in i..self.len.saturating_sub(1) {
            self.roots[j] = self.roots[j + 1];
            self.residuals[j] = self.residuals[j + 1];
            self.doubles[j] = self.doubles[j + 1];
            self.boundaries[j] = self.boundaries[j + 1];
        }
        self.len -= 1;
    }

    /// Inserts in order; when full, the largest root is dropped and the scan marked truncated.
    fn place(&mut self, root: Found) {
        let at = self.roots[..self.len].partition_point(|&r| r < root.x);
        if self.len == CAP {
            self.truncated = true;
            if at == CAP {
                return;
            }
            self.len -= 1;
        }
        let mut j = self.len;
        while j > at {
            self.roots[j] = self.roots[j - 1];
            self.residuals[j] = self.residuals[j - 1];
            self.doubles[j] = self.doubles[j - 1];
            self.boundaries[j] = self.boundaries[j - 1];
            j -= 1;
        }
        self.roots[at] = root.x;
        self.residuals[at] = root.residual;
        self.doubles[at] = root.double;
        self.boundaries[at] = root.boundary;
        self.len += 1;
    }
}

/// A root as the scan finds it.
#[derive(Clone, Copy, Debug)]
struct Found {
    x: f64,
    residual: f64,
    double: bool,
    boundary: bool,
}

/// Every root of a scalar function of one default over [lo, hi] (periodic: the function has
/// period hi - lo, e.g. an angle over a turn), into a fixed-capacity list sorted ascending (at
/// most CAP kept; [`RootScan::truncated`] says if more were found).
///
/// `samples` evaluations on a uniform grid first (at least 8). An interval that is not finite
/// or not increasing (`hi <= lo`) has no roots. The method, and exactly which roots it finds,
/// are in the module documentation.
pub fn all_roots<const CAP: usize, E: Gap>(
    lo: f64,
    hi: f64,
    periodic: bool,
    samples: u32,
    settings: &Settings,
    mut f: impl FnMut(f64) -> Result<f64, E>,
) -> RootScan<CAP> {
    let mut scan = RootScan::new();
    let span = hi - lo;
    if !(is_finite(lo) && is_finite(hi) && is_finite(span) && span > 0.0) {
        return scan;
    }
    let n = samples.max(MIN_SAMPLES);
    let mut sweep = Sweep {
        f: |t: f64| f(t).map_err(|e| e.gap()),
        lo,
        hi,
        span,
        periodic,
        tolerance: settings.tolerance,
        limit: settings.max_evaluations,
        scan: &mut scan,
        before: None,
        centre: None,
        pushed: 0,
        first: None,
        second: None,
        nested: 0,
    };
    let intervals = if periodic { n } else { n - 1 };
    for i in 0..n {
        let x = if !periodic && i == n - 1 {
            hi
        } else {
            lo + span * (f64::from(i) / f64::from(intervals))
        };
        let node = sweep.sample(x);
        sweep.push_sample(node);
    }
    if periodic {
        sweep.close_the_circle();
    } else {
        sweep.finish();
    }
    scan
}

/// A point of the scan: a grid sample, or the last defined point next to a failing one.
#[derive(Clone, Copy, Debug)]
struct Node {
    x: f64,
    /// `None` where the function fails.
    f: Option<f64>,
    /// The last defined point before a failing stretch.
    boundary: bool,
    /// A dip across zero within the tolerance, reported as one double root: the sign changes
    /// on either side are not roots of their own.
    shallow_dip: bool,
    /// Where the function fails with a gap ([`Gap`]): how far its loci miss.
    gap: Option<f64>,
}

/// What a minimization of `sign * f` found.
#[derive(Clone, Copy, Debug)]
enum Valley {
    /// A point where `sign * f < -tolerance`: the valley crosses zero, with a root on each side.
    Crossing { x: f64, f: f64 },
    /// The lowest point found, and `sign * f` there.
    Bottom { x: f64, g: f64 },
}

/// The state of [`all_roots`]: a window of three consecutive nodes slides over the grid (with
/// boundary points inserted between defined and failing samples). The centre of the window is
/// classified when its right neighbour arrives, and the interval to its left is bracketed then,
/// once both its ends are classified.
struct Sweep<'a, F, const CAP: usize> {
    f: F,
    lo: f64,
    hi: f64,
    span: f64,
    periodic: bool,
    tolerance: f64,
    /// Evaluations allowed to each refinement.
    limit: u32,
    scan: &'a mut RootScan<CAP>,
    before: Option<Node>,
    centre: Option<Node>,
    /// Nodes pushed so far.
    pushed: u32,
    /// Periodic: the first node, and the second once classified; they are classified (resp.
    /// bracketed against the first) again after the last sample, when their left neighbour is
    /// known.
    first: Option<Node>,
    second: Option<Node>,
    /// How many sweeps of windows this one is inside ([`Self::gap_window`]).
    nested: u32,
}

/// How many times smaller `|f|` at the last defined point before a failing stretch must be
/// than at the sample beside it for that edge to be tested as a square root's zero
/// ([`Sweep::square_root_edge`]).
const EDGE_FALL: f64 = 16.0;

/// The samples of a window found between two failing samples ([`Sweep::gap_window`]).
const WINDOW_SAMPLES: u32 = 16;

/// How deep windows are searched inside windows.
const MAX_NESTED: u32 = 2;

impl<F: FnMut(f64) -> Result<f64, Option<f64>>, const CAP: usize> Sweep<'_, F, CAP> {
    /// `f` at `x` (mapped into `[lo, hi]` when periodic: a turn on, or back, and clamped
    /// against the rounding of that), `None` where it fails or is not finite, and outside
    /// `[lo, hi]`.
    fn eval(&mut self, x: f64) -> Option<f64> {
        self.eval_or_gap(x).ok()
    }

    /// A grid sample at `x`: its value, or where it fails, its gap if it has one.
    fn sample(&mut self, x: f64) -> Node {
        let (f, gap) = match self.eval_or_gap(x) {
            Ok(v) => (Some(v), None),
            Err(gap) => (None, gap),
        };
        Node {
            x,
            f,
            boundary: false,
            shallow_dip: false,
            gap,
        }
    }

    /// [`Self::eval`], and where `f` fails, its gap if it has one (finite and positive).
    fn eval_or_gap(&mut self, x: f64) -> Result<f64, Option<f64>> {
        let t = if !self.periodic {
            x
        } else if x >= self.hi {
            (x - self.span).clamp(self.lo, self.hi)
        } else if x < self.lo {
            (x + self.span).clamp(self.lo, self.hi)
        } else {
            x
        };
        self.scan.evaluations = self.scan.evaluations.saturating_add(1);
        if !(t >= self.lo && t <= self.hi) {
            return Err(None);
        }
        match (self.f)(t) {
            Ok(v) if is_finite(v) => {
                self.scan.least = self.scan.least.min(v.abs());
                Ok(v)
            }
            Ok(_) => Err(None),
            Err(gap) => Err(gap.filter(|g| is_finite(*g) && *g > 0.0)),
        }
    }

    /// `f` at `x` within `budget`; `Exhausted` when it is spent.
    fn probe(&mut self, budget: &mut Budget, x: f64) -> Probe<f64> {
        if !budget.take() {
            return Probe::Exhausted;
        }
        match self.eval(x) {
            Some(v) => Probe::Good(v),
            None => Probe::Bad,
        }
    }

    fn record(&mut self, x: f64, residual: f64, double: bool, boundary: bool) {
        let mut x = x;
        if self.periodic {
            if x >= self.hi {
                x -= self.span;
            }
            if !(x >= self.lo && x < self.hi) {
                x = self.lo;
            }
        } else {
            x = x.clamp(self.lo, self.hi);
        }
        let found = Found {
            x,
            residual,
            double,
            boundary,
        };
        let period = self.periodic.then_some(self.span);
        self.scan
            .insert(found, tol::SAME_ROOT_REL * self.span, period);
    }

    /// Adds a grid sample, with a boundary point before it when exactly one of it and the
    /// previous sample is defined.
    fn push_sample(&mut self, node: Node) {
        if let Some(previous) = self.centre {
            match (previous.f, node.f) {
                (Some(v), None) => {
                    let b = self.boundary(previous.x, v, node.x);
                    self.push_node(b);
                }
                (None, Some(v)) => {
                    let b = self.boundary(node.x, v, previous.x);
                    self.push_node(b);
                }
                _ => {}
            }
        }
        self.push_node(node);
    }

    /// Slides the window: classifies the centre now that its right neighbour is known, and
    /// brackets the interval to its left.
    fn push_node(&mut self, node: Node) {
        if let Some(centre) = self.centre {
            let index = self.pushed - 1;
            // Periodic: the first node's left neighbour is the last sample; it is classified,
            // and its interval to the right bracketed, when the circle closes.
            if !(self.periodic && index == 0) {
                let centre = self.classify(self.before, centre, Some(node));
                self.centre = Some(centre);
                if self.periodic && index == 1 {
                    self.second = Some(centre);
                } else if let Some(left) = self.before {
                    self.bracket(left, centre);
                }
            }
        }
        if self.pushed == 0 {
            self.first = Some(node);
        }
        self.before = self.centre;
        self.centre = Some(node);
        self.pushed = self.pushed.saturating_add(1);
    }

    /// Non-periodic: classifies the last node, whose right is the end of the interval.
    fn finish(&mut self) {
        if let Some(centre) = self.centre {
            let centre = self.classify(self.before, centre, None);
            if let Some(left) = self.before {
                self.bracket(left, centre);
            }
        }
    }

    /// Periodic: the first two nodes again, one period on, so that the first is classified
    /// with its left neighbour (the last sample) and the intervals across the wrap are
    /// bracketed, each once.
    fn close_the_circle(&mut self) {
        let (Some(first), Some(second)) = (self.first, self.second) else {
            return;
        };
        let span = self.span;
        self.push_sample(Node {
            x: first.x + span,
            ..first
        });
        let second = Node {
            x: second.x + span,
            ..second
        };
        self.push_node(second);
        if let Some(first) = self.before {
            self.bracket(first, second);
        }
    }

    /// The last point where `f` is defined between `good` (where it is, value `value`) and
    /// `bad` (where it fails), by bisection to rounding level.
    fn boundary(&mut self, good: f64, value: f64, bad: f64) -> Node {
        let mut budget = Budget::new(self.limit);
        let (mut good, mut value, mut bad) = (good, value, bad);
        loop {
            let mid = 0.5 * good + 0.5 * bad;
            if mid == good || mid == bad {
                break;
            }
            match self.probe(&mut budget, mid) {
                Probe::Good(v) => (good, value) = (mid, v),
                Probe::Bad => bad = mid,
                Probe::Exhausted => break,
            }
        }
        Node {
            x: good,
            f: Some(value),
            boundary: true,
            shallow_dip: false,
            gap: None,
        }
    }

    /// Classifies `centre` given its neighbours (`None`: the end of the interval): a zero, a
    /// root at a boundary or an end, a local minimum of `|f|` (refined), a shallow dip.
    fn classify(&mut self, left: Option<Node>, centre: Node, right: Option<Node>) -> Node {
        let Some(fc) = centre.f else {
            if let (Some(left), Some(right)) = (left, right) {
                self.gap_window(left, centre, right);
            }
            return centre;
        };
        let left = left.and_then(|n| n.f.map(|v| (n.x, v)));
        let right = right.and_then(|n| n.f.map(|v| (n.x, v)));
        if fc == 0.0 {
            let double = matches!((left, right), (Some((_, l)), Some((_, r))) if l * r > 0.0);
            self.record(centre.x, 0.0, double, centre.boundary);
            return centre;
        }
        let tolerance = self.tolerance;
        let run_end = left.is_none() || right.is_none();
        if run_end && fc.abs() <= tolerance {
            self.record(centre.x, fc.abs(), false, centre.boundary);
        } else if run_end && centre.boundary {
            // Where the assembly ends at a tangency of its loci, `f` may reach zero there as a
            // square root does: its last defined point, in the tangency's tolerance band, is
            // then further from zero than the tolerance (`Self::square_root_edge`).
            if let Some(beside) = left.or(right) {
                if self.square_root_edge((centre.x, fc), beside) {
                    self.record(centre.x, fc.abs(), false, true);
                }
            }
        }
        let same_and_above = |v: f64, strict: bool| {
            v * fc > 0.0
                && if strict {
                    v.abs() > fc.abs()
                } else {
                    v.abs() >= fc.abs()
                }
        };
        let is_minimum = !(left.is_none() && right.is_none())
            && left.is_none_or(|(_, v)| same_and_above(v, true))
            && right.is_none_or(|(_, v)| same_and_above(v, false));
        if is_minimum {
            let (a, fa) = left.unwrap_or((centre.x, fc));
            let (b, fb) = right.unwrap_or((centre.x, fc));
            let (valley, bad) = self.minimize_seeing(a, b, centre.x, fc, fc.signum());
            // The valley's bottom may be a failing stretch narrower than the grid (loci that
            // stop meeting between two samples): its edges are roots where `f` reaches zero
            // there, as at any boundary.
            if let (Valley::Bottom { g, .. }, Some(bad), false) = (valley, bad, run_end) {
                if g > tolerance && a < bad && bad < b {
                    let near = if bad < centre.x {
                        (a, fa)
                    } else {
                        (centre.x, fc)
                    };
                    let far = if bad < centre.x {
                        (centre.x, fc)
                    } else {
                        (b, fb)
                    };
                    self.split(near, bad, far, 0);
                    return centre;
                }
            }
            match valley {
                Valley::Crossing { x, f } => {
                    for (u, fu, v, fv) in [(a, fa, x, f), (x, f, b, fb)] {
                        self.refine(u, fu, v, fv, 0);
                    }
                }
                Valley::Bottom { x, g } if g <= tolerance => {
                    let at_end = run_end && x == centre.x;
                    self.record(x, g.abs(), !at_end, at_end && centre.boundary);
                }
                Valley::Bottom { .. } => {}
            }
            return centre;
        }
        if let (Some((a, fa)), Some((b, fb))) = (left, right) {
            if fa * fc < 0.0 && fb * fc < 0.0 && fc.abs() <= tolerance {
                // A dip across zero within the tolerance: how deep does it go?
                if let Valley::Bottom { x, g } = self.minimize(a, b, centre.x, fc, -fc.signum()) {
                    self.record(x, g.abs(), true, false);
                    return Node {
                        shallow_dip: true,
                        ..centre
                    };
                }
            }
        }
        centre
    }

    /// Brackets the interval between two classified nodes when their values have opposite
    /// signs (and neither is a shallow dip already reported).
    fn bracket(&mut self, left: Node, right: Node) {
        if let (Some(fl), Some(fr)) = (left.f, right.f) {
            if fl * fr < 0.0 && !left.shallow_dip && !right.shallow_dip {
                self.refine(left.x, fl, right.x, fr, 0);
            }
        }
    }

    /// Records the root in a sign change, refined by Brent's method (inverse quadratic
    /// interpolation, secant and bisection steps) to rounding level, if its `|f|` is within the
    /// tolerance. A point where the function fails splits the failing stretch off
    /// ([`Self::split`]).
    fn refine(&mut self, a: f64, fa: f64, b: f64, fb: f64, depth: u32) {
        let opposite = fa * fb < 0.0;
        if !opposite {
            return;
        }
        let mut budget = Budget::new(self.limit);
        let abs_tol = tol::LOCATE_ABS * tol::ULP * self.span;
        // `b` is the best point, `c` the other end of the bracket, `a` the previous `b`.
        let (mut a, mut fa, mut b, mut fb) = (a, fa, b, fb);
        let (mut c, mut fc) = (a, fa);
        let mut d = b - a;
        let mut e = d;
        loop {
            if fc.abs() < fb.abs() {
                (a, fa) = (b, fb);
                (b, fb) = (c, fc);
                (c, fc) = (a, fa);
            }
            let tol1 = 2.0 * tol::ULP * b.abs() + 0.5 * abs_tol;
            let half = 0.5 * (c - b);
            if half.abs() <= tol1 || fb == 0.0 {
                break;
            }
            let mut step = half;
            if e.abs() >= tol1 && fa.abs() > fb.abs() {
                let s = fb / fa;
                let (mut p, mut q) = if a == c {
                    (2.0 * half * s, 1.0 - s)
                } else {
                    let q = fa / fc;
                    let r = fb / fc;
                    (
                        s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0)),
                        (q - 1.0) * (r - 1.0) * (s - 1.0),
                    )
                };
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * half * q - (tol1 * q).abs()).min((e * q).abs()) {
                    e = d;
                    step = p / q;
                } else {
                    e = half;
                }
            } else {
                e = half;
            }
            if step.abs() <= tol1 {
                step = tol1.copysign(half);
            }
            // The trial point. Where the function fails, the failing stretch is split off
            // (its edges found from both sides); past the depth of splits, the step backs off
            // toward `b` instead.
            let value = loop {
                match self.probe(&mut budget, b + step) {
                    Probe::Good(v) => break Some(v),
                    Probe::Bad if depth < MAX_SPLITS => {
                        return self.split((b, fb), b + step, (c, fc), depth);
                    }
                    Probe::Bad if step.abs() > tol1 => step *= 0.5,
                    _ => break None,
                }
            };
            let Some(value) = value else {
                break;
            };
            d = step;
            (a, fa) = (b, fb);
            (b, fb) = (b + step, value);
            if (fb > 0.0) == (fc > 0.0) {
                (c, fc) = (a, fa);
                d = b - a;
                e = d;
            }
        }
        if fb.abs() <= self.tolerance {
            self.record(b, fb.abs(), false, false);
        }
    }

    /// Whether `f` reaches zero at `edge` (the last defined point before a failing stretch,
    /// `(x, f)`) as a square root does, from the defined point `beside` on the same side: `|f|`
    /// falls by [`EDGE_FALL`] or more from `beside` to the edge, keeping its sign, and
    /// `f / sqrt(d)`, `d` the distance from the edge, is the same to within a factor of two at
    /// `1e-4` and `1e-6` of the way to `beside` (where a function that only comes near zero,
    /// `f0 + s d` with `f0` not zero, has it ten times larger at the nearer point). Such an
    /// edge is a root for the solve from it to confirm, as every root is.
    fn square_root_edge(&mut self, (xe, fe): (f64, f64), (xb, fb): (f64, f64)) -> bool {
        if !(fb * fe > 0.0 && fb.abs() >= EDGE_FALL * fe.abs()) {
            return false;
        }
        let at = |t: f64| xe + (xb - xe) * t;
        let (near, far) = (1e-6, 1e-4);
        let (Some(f_near), Some(f_far)) = (self.eval(at(near)), self.eval(at(far))) else {
            return false;
        };
        if !(f_near * fe > 0.0 && f_far * fe > 0.0) {
            return false;
        }
        // f / sqrt(d) at each, d in units of the whole distance (the ratio does not depend
        // on them).
        let ratio = (f_near / near.sqrt()) / (f_far / far.sqrt());
        (0.5..=2.0).contains(&ratio)
    }

    /// A failing point `bad` between defined points `near` and `far` (each `(x, f)`; a sign
    /// change a refinement met, or a valley's bottom no sample hit): the failing stretch's
    /// edges are found from both sides (by bisection, as between samples), each is a boundary
    /// root if its `|f|` is within the tolerance or falls steeply to it ([`EDGE_FALL`], as at
    /// a tangency), and each side with a sign change of its own is refined. (The sign may also
    /// change across the stretch, where there is no root.)
    fn split(&mut self, near: (f64, f64), bad: f64, far: (f64, f64), depth: u32) {
        for (x, fx) in [near, far] {
            let edge = self.boundary(x, fx, bad);
            if let Some(fe) = edge.f {
                if fe.abs() <= self.tolerance || self.square_root_edge((edge.x, fe), (x, fx)) {
                    self.record(edge.x, fe.abs(), false, true);
                }
                self.refine(x, fx, edge.x, fe, depth + 1);
            }
        }
    }

    /// A failing sample whose gap is a local minimum of the sampled gaps, between two failing
    /// samples: the loci may meet between them over a stretch narrower than the grid (a
    /// circle that grazes a sphere as the default turns), which no sample hits. Brent's
    /// minimization of the gap over the two spacings looks for a point where `f` is defined;
    /// from one, the stretch's edges are found by bisection and the stretch is swept on a
    /// grid of its own ([`WINDOW_SAMPLES`]), so that its roots are found as the grid's are.
    fn gap_window(&mut self, left: Node, centre: Node, right: Node) {
        let (Some(gl), Some(gc), Some(gr)) = (left.gap, centre.gap, right.gap) else {
            return;
        };
        if self.nested >= MAX_NESTED || !(gl > gc && gr >= gc) {
            return;
        }
        let mut budget = Budget::new(self.limit);
        let abs_tol = tol::LOCATE_ABS * tol::SQRT_EPS * self.span;
        let mut inside: Option<(f64, f64)> = None;
        // A defined point ends the search: it counts as far below zero.
        let found = valley(left.x, right.x, (centre.x, gc), 1.0, 0.0, abs_tol, |u| {
            if !budget.take() {
                return Probe::Exhausted;
            }
            match self.eval_or_gap(u) {
                Ok(v) => {
                    inside = Some((u, v));
                    Probe::Good(f64::NEG_INFINITY)
                }
                Err(Some(g)) => Probe::Good(g),
                Err(None) => Probe::Bad,
            }
        });
        let (Valley::Crossing { .. }, Some((x, v))) = (found, inside) else {
            return;
        };
        let (l, r) = (self.boundary(x, v, left.x), self.boundary(x, v, right.x));
        // In the periodic scan's own range, where the windows' roots are recorded.
        let shift = if self.periodic && r.x > self.hi {
            -self.span
        } else {
            0.0
        };
        let (lo, hi) = (l.x + shift, r.x + shift);
        if hi.partial_cmp(&lo) != Some(core::cmp::Ordering::Greater) {
            if let Some(f) = l.f.filter(|f| f.abs() <= self.tolerance) {
                self.record(l.x, f.abs(), true, true);
            }
            return;
        }
        let (periodic, span, outer) = (self.periodic, self.span, (self.lo, self.hi));
        let f = &mut self.f;
        // The outer scan's function, a turn on or back where the window crosses its end; of
        // one type at every depth (`dyn`), so that windows in windows instantiate nothing new.
        let mut wrapped = |t: f64| {
            let t = if periodic && t > outer.1 {
                t - span
            } else if periodic && t < outer.0 {
                t + span
            } else {
                t
            };
            f(t)
        };
        let wrapped: &mut dyn FnMut(f64) -> Result<f64, Option<f64>> = &mut wrapped;
        let mut window = Sweep {
            f: wrapped,
            lo,
            hi,
            span: hi - lo,
            periodic: false,
            tolerance: self.tolerance,
            limit: self.limit,
            scan: &mut *self.scan,
            before: None,
            centre: None,
            pushed: 0,
            first: None,
            second: None,
            nested: self.nested + 1,
        };
        let intervals = WINDOW_SAMPLES - 1;
        for i in 0..WINDOW_SAMPLES {
            let x = if i == intervals {
                hi
            } else {
                lo + (hi - lo) * (f64::from(i) / f64::from(intervals))
            };
            let mut node = window.sample(x);
            node.boundary = i == 0 || i == intervals;
            window.push_sample(node);
        }
        window.finish();
    }

    /// [`Self::minimize`], and a point where `f` failed on the way, if one did.
    fn minimize_seeing(
        &mut self,
        a: f64,
        b: f64,
        x0: f64,
        f0: f64,
        sign: f64,
    ) -> (Valley, Option<f64>) {
        let mut budget = Budget::new(self.limit);
        let abs_tol = tol::LOCATE_ABS * tol::SQRT_EPS * self.span;
        let tolerance = self.tolerance;
        let mut bad = None;
        let found = valley(a, b, (x0, f0), sign, tolerance, abs_tol, |u| {
            let p = self.probe(&mut budget, u);
            if matches!(p, Probe::Bad) && bad.is_none() {
                bad = Some(u);
            }
            p
        });
        (found, bad)
    }

    /// The bottom of the valley of `sign * f` over `[a, b]` from `x0` where `f = f0`: see
    /// [`valley`].
    fn minimize(&mut self, a: f64, b: f64, x0: f64, f0: f64, sign: f64) -> Valley {
        self.minimize_seeing(a, b, x0, f0, sign).0
    }
}

/// Brent's minimization (golden section and parabolic steps) of `g = sign * f` over `[a, b]`
/// from the known point `start = (x0, f(x0))`, to about `sqrt(eps) |x| + abs_tol`: the bottom
/// of the valley of `|f|` on the side of `sign`. A failing point counts as `g = +inf`. Stops
/// early at a point where `g < -tolerance`: the valley crosses zero, with a root on each side.
fn valley(
    a: f64,
    b: f64,
    start: (f64, f64),
    sign: f64,
    tolerance: f64,
    abs_tol: f64,
    mut probe: impl FnMut(f64) -> Probe<f64>,
) -> Valley {
    // The golden section ratio (3 - sqrt 5) / 2.
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    let (x0, f0) = start;
    let g0 = sign * f0;
    let (mut a, mut b) = (a.min(b), a.max(b));
    let (mut x, mut w, mut v) = (x0, x0, x0);
    let (mut gx, mut gw, mut gv) = (g0, g0, g0);
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    loop {
        let mid = 0.5 * (a + b);
        let tol1 = tol::SQRT_EPS * x.abs() + abs_tol;
        let tol2 = 2.0 * tol1;
        if (x - mid).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 && is_finite(gw) && is_finite(gv) {
            // A parabola through x, w, v.
            let r = (x - w) * (gx - gv);
            let mut q = (x - v) * (gx - gw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let previous = e;
            e = d;
            if p.abs() < (0.5 * q * previous).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(mid - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= mid { a - x } else { b - x };
            d = GOLDEN * e;
        }
        let u = x + if d.abs() >= tol1 { d } else { tol1.copysign(d) };
        let gu = match probe(u) {
            Probe::Good(value) => sign * value,
            Probe::Bad => f64::INFINITY,
            Probe::Exhausted => break,
        };
        if gu < -tolerance {
            return Valley::Crossing { x: u, f: sign * gu };
        }
        if gu <= gx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, gv, w, gw, x, gx) = (w, gw, x, gx, u, gu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if gu <= gw || w == x {
                (v, gv, w, gw) = (w, gw, u, gu);
            } else if gu <= gv || v == x || v == w {
                (v, gv) = (u, gu);
            }
        }
    }
    // A magnitude (a distance) meets zero in the corner of a V, which the minimization finds
    // only to its resolution: a step either side gives the V's slope, and where its sides
    // meet is tried (for a smooth bottom, one more point near it).
    if gx > tolerance {
        let h = 2.0 * (tol::SQRT_EPS * x.abs() + abs_tol);
        let mut sides = [0.0; 2];
        for (side, t) in sides.iter_mut().zip([x - h, x + h]) {
            match probe(t) {
                Probe::Good(value) if sign * value < -tolerance => {
                    return Valley::Crossing { x: t, f: value };
                }
                Probe::Good(value) => *side = sign * value,
                _ => return Valley::Bottom { x, g: gx },
            }
        }
        let k = (sides[0] + sides[1]) / (2.0 * h);
        let u = x - h + sides[0] / k;
        if is_finite(u) && x - h < u && u < x + h {
            if let Probe::Good(value) = probe(u) {
                let gu = sign * value;
                if gu < -tolerance {
                    return Valley::Crossing { x: u, f: value };
                }
                if gu < gx {
                    (x, gx) = (u, gu);
                }
            }
        }
    }
    Valley::Bottom { x, g: gx }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An error that is a miss by `gap`, as two circles that do not meet report it.
    fn miss(gap: f64) -> SolveError {
        SolveError::new("c", "", ErrorKind::NoIntersection, gap)
    }

    /// A start where the assembly fails with a gap, further than the probe beside it reaches,
    /// descends on the gap to where the assembly exists and then converges: with two defaults
    /// (the assembly exists inside the unit disc, and misses by how far outside it a point
    /// is) and with one (it exists below 1). An error with no gap is the start's error.
    #[test]
    fn a_start_where_the_assembly_fails_descends_on_its_gap() {
        let settings = Settings::for_size(1.0);
        let mut disc = |x: &[f64; 2], r: &mut [f64; 2]| {
            let norm = (x[0] * x[0] + x[1] * x[1]).sqrt();
            if norm > 1.0 {
                return Err(miss(norm - 1.0));
            }
            r[0] = x[0] - 0.5;
            r[1] = x[1] + 0.2 * x[0] - 0.1;
            Ok(())
        };
        let mut x = [3.0, -4.0];
        solve(&mut x, &[1.0, 1.0], &settings, &mut disc).expect("reaches the disc, then closes");
        assert!((x[0] - 0.5).abs() < 1e-12 && x[1].abs() < 1e-12, "{x:?}");

        let mut below = |x: &[f64; 1], r: &mut [f64; 1]| {
            if x[0] > 1.0 {
                return Err(miss(x[0] - 1.0));
            }
            r[0] = x[0] * x[0] - 0.09;
            Ok(())
        };
        let mut x = [6.0];
        solve(&mut x, &[1.0], &settings, &mut below).expect("reaches 1, then closes");
        assert!((x[0] - 0.3).abs() < 1e-12, "{x:?}");

        let mut degenerate = |x: &[f64; 2], r: &mut [f64; 2]| {
            if x[0] > 1.0 {
                return Err(SolveError::new("c", "", ErrorKind::Degenerate, 0.0));
            }
            r[0] = x[0];
            r[1] = x[1];
            Ok(())
        };
        let mut x = [3.0, 0.0];
        let out = solve(&mut x, &[1.0, 1.0], &settings, &mut degenerate);
        assert!(
            matches!(&out, Err(Failure::Start(e)) if e.kind == ErrorKind::Degenerate),
            "{out:?}"
        );
    }

    fn found(x: f64, residual: f64) -> Found {
        Found {
            x,
            residual,
            double: false,
            boundary: false,
        }
    }

    /// A warm start on a smooth function is solved by `quick` alone: a difference, a Newton
    /// step, secant steps to rounding level; a start from which Newton's step overshoots (it
    /// does not halve the residual) is handed to the search at the better point, and the
    /// search still finds the root.
    #[test]
    fn quick_solves_a_warm_start_and_hands_an_overshoot_to_the_search() {
        let settings = Settings::for_size(1.0);
        let mut budget = Budget::new(settings.max_evaluations);
        let mut cube = |t: f64| -> Result<f64, ()> { Ok(t * t * t - 2.0) };
        let mut x = 1.25;
        let f0 = x * x * x - 2.0;
        let done = quick(&mut x, f0, 1.0, &settings, &mut budget, &mut cube);
        assert!(matches!(done, Quick::Converged { .. }));
        assert!((x - 2f64.cbrt()).abs() <= 4.0 * f64::EPSILON, "{x}");
        assert!(budget.used <= 6, "{} evaluations", budget.used);

        // atan's Newton step from 1.5 lands beyond -1.5: not halved, so the search takes over.
        let mut budget = Budget::new(settings.max_evaluations);
        let mut atan = |t: f64| -> Result<f64, ()> { Ok(t.atan()) };
        let mut x = 1.5;
        let done = quick(
            &mut x,
            1.5f64.atan(),
            10.0,
            &settings,
            &mut budget,
            &mut atan,
        );
        assert!(matches!(done, Quick::Handover { .. }));
        assert_eq!(x, 1.5, "the better point was the start");
        let mut x = [1.5];
        let converged = solve(&mut x, &[10.0], &settings, |t, r| {
            r[0] = t[0].atan();
            Ok::<(), ()>(())
        })
        .expect("the search finds the root");
        assert!(x[0].abs() <= settings.tolerance, "{x:?} {converged:?}");
    }

    #[test]
    fn bracket_narrows_to_the_root_from_both_sides() {
        // A strongly curved function, on which plain false position creeps from one side.
        let f = |x: f64| x.exp() - 10.0;
        let mut b = Bracket::new(0.0, f(0.0), 5.0, f(5.0)).unwrap_or_else(|| unreachable!());
        let mut steps = 0;
        while !b.is_collapsed() && b.best().1 != 0.0 && steps < 100 {
            let t = b.propose();
            assert!(b.contains(t));
            b.narrow(t, f(t));
            steps += 1;
        }
        assert!((b.best().0 - 10f64.ln()).abs() <= 1e-15, "{b:?}");
        assert!(steps <= 16, "{steps}");
        // No bracket without a strict sign change.
        assert!(Bracket::new(0.0, 1.0, 1.0, 0.0).is_none());
        assert!(Bracket::new(0.0, 1.0, 1.0, f64::NAN).is_none());
        assert!(Bracket::new(1.0, -1.0, 1.0, 1.0).is_none());
    }

    #[test]
    fn dogleg_stays_within_the_radius() {
        let gradient = SVector::<f64, 2>::new(1.0, 0.0);
        let newton = SVector::<f64, 2>::new(-3.0, 4.0);
        // Newton inside: Newton.
        assert_eq!(dogleg(Some(newton), &gradient, 0.5, 6.0), Some(newton));
        // Cauchy point outside: steepest descent cut to the radius.
        assert_eq!(
            dogleg(Some(newton), &gradient, 0.5, 0.25),
            Some(SVector::<f64, 2>::new(-0.25, 0.0))
        );
        // In between: on the segment from the Cauchy point to Newton, at the radius.
        let step = dogleg(Some(newton), &gradient, 0.5, 2.0).unwrap_or_else(|| unreachable!());
        assert!((step.norm() - 2.0).abs() <= 1e-15, "{step}");
        assert!(step.y > 0.0 && step.x < -0.5);
        // No Newton step: the Cauchy point; nothing at all: none.
        assert_eq!(
            dogleg(None, &gradient, 0.5, 2.0),
            Some(SVector::<f64, 2>::new(-0.5, 0.0))
        );
        assert_eq!(
            dogleg(None, &SVector::<f64, 2>::zeros(), f64::NAN, 2.0),
            None
        );
    }

    #[test]
    fn scan_keeps_roots_sorted_merged_and_bounded() {
        let mut scan = RootScan::<3>::new();
        for x in [0.5, 0.1, 0.9] {
            scan.insert(found(x, 1e-12), 1e-6, None);
        }
        assert_eq!(scan.roots(), &[0.1, 0.5, 0.9]);
        // A near duplicate with a smaller residual replaces the root.
        scan.insert(found(0.5 + 1e-7, 1e-15), 1e-6, None);
        assert_eq!(scan.roots(), &[0.1, 0.5 + 1e-7, 0.9]);
        assert_eq!(scan.residual(1), 1e-15);
        // A worse one does not.
        scan.insert(found(0.5, 1e-11), 1e-6, None);
        assert_eq!(scan.roots(), &[0.1, 0.5 + 1e-7, 0.9]);
        assert!(!scan.truncated());
        // Full: a smaller root pushes out the largest; a larger one is dropped.
        scan.insert(found(0.0, 0.0), 1e-6, None);
        assert_eq!(scan.roots(), &[0.0, 0.1, 0.5 + 1e-7]);
        assert!(scan.truncated());
        scan.insert(found(2.0, 0.0), 1e-6, None);
        assert_eq!(scan.roots(), &[0.0, 0.1, 0.5 + 1e-7]);
        // Periodic: roots on either side of the wrap are one.
        let mut wrap = RootScan::<2>::new();
        wrap.insert(found(1e-9, 1e-14), 1e-8, Some(1.0));
        wrap.insert(found(1.0 - 1e-9, 1e-13), 1e-8, Some(1.0));
        assert_eq!(wrap.roots(), &[1e-9]);
        // No capacity: everything is truncated, nothing panics.
        let mut none = RootScan::<0>::new();
        none.insert(found(1.0, 0.0), 1e-6, None);
        assert!(none.is_empty() && none.truncated());
    }

    #[test]
    fn largest_never_hides_a_nan() {
        assert_eq!(largest(&[1.0, -3.0, 2.0]), 3.0);
        assert!(largest(&[1.0, f64::NAN, 2.0]).is_nan());
        assert_eq!(largest(&[1.0, f64::NEG_INFINITY]), f64::INFINITY);
        assert_eq!(largest(&[]), 0.0);
    }
}
