//! Assembly modes of an outer iteration: which of its roots a solve from the sketch may take.
//!
//! An iteration's closing errors `e(x)` vanish at each of its roots. At a regular root their
//! Jacobian `J = de/dx` is invertible, and the sign of its determinant, the root's
//! [`Orientation`], cannot change along a path of roots (a sweep of the params) without
//! passing a fold, where `J` is singular and two roots meet. The roots of one orientation are
//! one *assembly mode*, in the sense parallel mechanisms give the word (the aspects of a
//! 3-RPR, separated by its singularities). A plan's iteration records the orientation of the
//! root the sketch sits on ([`Settings::hold`](crate::iterate::Settings::hold)); a solve that
//! starts from the sketch's defaults (a cold solve) keeps it, so that it lands on the
//! sketch's mode or says that mode has no assembly here ([`keep`]), rather than taking
//! whichever root Newton's method reaches first.
//!
//! A closing error that is a magnitude at its root (a point's distance from a line it crosses,
//! whose root is the corner of a V) has no derivative there, and a root where `J` is singular
//! (a tangency) lies on no one side: [`orientation`] is `None` for both, and no mode is held
//! there.
//!
//! The search for a root of the kept orientation when the first one reached has the other
//! ([`keep`]) is the failing path's only: a solve whose root is of the sketch's orientation
//! pays `2N + 1` evaluations of its region for the test, and nothing else.

use crate::iterate::{self, all_roots, Converged, Failure, Gap, RootScan, Settings, Span};
use crate::num::is_finite;

/// The sign of the determinant of an iteration's closing errors' Jacobian in its defaults at a
/// root: which assembly mode the root is on (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// A positive determinant (with one default: the error rises with it).
    Positive,
    /// A negative determinant (with one default: the error falls as it rises).
    Negative,
}

impl Orientation {
    /// The other orientation.
    #[must_use]
    pub const fn flipped(self) -> Self {
        match self {
            Orientation::Positive => Orientation::Negative,
            Orientation::Negative => Orientation::Positive,
        }
    }
}

/// The difference step of [`orientation`], in units of each default's scale: far above the
/// rounding of an assembly (whose errors end near `1e-13` of the model's size), far below the
/// distance to another root or a fold the sign could change across.
const STEP: f64 = 1e-6;

/// A column of the one-sided differences that changes by more than this fraction between the
/// two sides has no derivative at the root: the corner of a magnitude's V, which flips every
/// entry it has (a smooth error changes by about the step, `1e-6` of itself).
const KINK: f64 = 0.25;

/// How small the determinant may be, against the product of its columns' lengths (Hadamard's
/// bound on it), for its sign still to count: below, the root is at a fold (a tangency), on
/// neither side.
const SINGULAR: f64 = 1e-7;

/// The search for a root of the kept orientation with several defaults starts from a grid of
/// these offsets of each default, in units of its scale, nearest first: about the whole turn
/// for an angle (whose scale is a radian), three model sizes either side for a length.
const GRID: [f64; 9] = [0.0, -0.5, 0.5, -1.0, 1.0, -2.0, 2.0, -3.0, 3.0];

/// The most evaluations of the region that the search with several defaults spends, in all.
const SEARCH_BUDGET: u32 = 40_000;

/// Samples of the window a length's search scans: four scales either side of the start.
const LENGTH_SAMPLES: u32 = 257;

/// The orientation of the root `x` of the closing errors `f` (scales `scale`, as the
/// iteration's): the sign of the determinant of their Jacobian, from differences on both sides
/// of `x`. `None` where the errors have no derivative there (a column that differs between
/// the two sides by more than [`KINK`] of itself), where the determinant is within
/// [`SINGULAR`] of vanishing against Hadamard's bound (a fold), or where the assembly fails or
/// is not finite beside `x`. `2N + 1` evaluations.
pub fn orientation<const N: usize, E>(
    x: &[f64; N],
    scale: &[f64; N],
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Option<Orientation> {
    let mut at = [0.0; N];
    f(x, &mut at).ok()?;
    let mut jacobian = [[0.0; N]; N];
    let mut bound = 1.0;
    for k in 0..N {
        let h = STEP * sane(scale[k], x[k]);
        let (mut up, mut down) = (*x, *x);
        up[k] += h;
        down[k] -= h;
        let (mut above, mut below) = ([0.0; N], [0.0; N]);
        f(&up, &mut above).ok()?;
        f(&down, &mut below).ok()?;
        let (mut change, mut length) = (0.0f64, 0.0f64);
        for i in 0..N {
            let forward = (above[i] - at[i]) / h;
            let backward = (at[i] - below[i]) / h;
            change = change.max((forward - backward).abs());
            length = length.max(forward.abs()).max(backward.abs());
            jacobian[i][k] = 0.5 * (forward + backward);
        }
        if !(is_finite(length) && length > 0.0) || change > KINK * length {
            return None;
        }
        bound *= (0..N).map(|i| jacobian[i][k].powi(2)).sum::<f64>().sqrt();
    }
    let det = determinant(jacobian);
    if !is_finite(det) || det.abs() <= SINGULAR * bound {
        return None;
    }
    Some(if det > 0.0 {
        Orientation::Positive
    } else {
        Orientation::Negative
    })
}

/// The determinant of `m`, by Gaussian elimination with partial pivoting: the product of the
/// pivots, its sign flipped for each row swap.
fn determinant<const N: usize>(mut m: [[f64; N]; N]) -> f64 {
    let mut det = 1.0;
    for c in 0..N {
        let pivot = (c..N)
            .max_by(|&a, &b| m[a][c].abs().total_cmp(&m[b][c].abs()))
            .unwrap_or(c);
        if m[pivot][c] == 0.0 {
            return 0.0;
        }
        if pivot != c {
            m.swap(pivot, c);
            det = -det;
        }
        det *= m[c][c];
        let (above, below) = m.split_at_mut(c + 1);
        let pivot = &above[c];
        for row in below {
            let factor = row[c] / pivot[c];
            for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                *x -= factor * p;
            }
        }
    }
    det
}

/// A scale that is finite and positive: the default's own size otherwise, at least 1.
fn sane(scale: f64, x: f64) -> f64 {
    if is_finite(scale) && scale > 0.0 {
        scale
    } else {
        x.abs().max(1.0)
    }
}

/// Keeps `want`, the orientation of the sketch's root, for an iteration from `start` that
/// converged (`converged`) to `x`: unchanged when `x`'s orientation is `want` or none
/// ([`orientation`]); otherwise the root of orientation `want` nearest `start`, with `x` moved
/// there, found by a search:
///
/// - one angle ([`Span::Turn`]): every root over the turn ([`all_roots`] on the grid of
///   [`crate::outer::Scan`]), so that none found is a claim as complete as the scan's;
/// - one length: every root within four scales of the start;
/// - several defaults: the iteration from a grid of starts ([`GRID`] of each default's scale,
///   the nearest shell first; the first shell that yields a root of the orientation wanted
///   gives the nearest of its roots), within [`SEARCH_BUDGET`] evaluations.
///
/// None found is [`Failure::OtherMode`] with the number of roots of the other orientation
/// found (at least the one reached). Out of line and cold: the first root's orientation is the
/// sketch's in every solve that stays on the sketch's mode.
#[cold]
#[inline(never)]
pub(crate) fn keep<const N: usize, E: Gap>(
    want: Orientation,
    start: &[f64; N],
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    converged: Converged,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<Converged, Failure<E>> {
    let Some(found) = orientation(x, scale, f) else {
        return Ok(converged);
    };
    if found == want {
        return Ok(converged);
    }
    match search(want, start, x, scale, settings, f) {
        Ok(residual) => Ok(Converged {
            residual,
            ..converged
        }),
        Err(others) => Err(Failure::OtherMode {
            others: others.max(1),
            iterations: converged.iterations,
        }),
    }
}

/// The search of [`keep`], also run where an iteration that holds a mode failed from its start
/// (a cold start in a valley of its errors, where a root of the mode may still exist):
/// `Ok(residual)` with `x` at the root of orientation `want` nearest `start`, else
/// `Err(the number of roots of the other orientation found)`. Cold.
#[cold]
#[inline(never)]
pub(crate) fn search<const N: usize, E: Gap>(
    want: Orientation,
    start: &[f64; N],
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<f64, u32> {
    // The search's own iterations tell no failure and hold no mode.
    let plain = settings.searching();
    if N == 1 {
        keep_one(want, start, x, scale, &plain, f)
    } else {
        keep_several(want, start, x, scale, &plain, f)
    }
}

/// [`keep`] with one default: `Ok(residual)` with `x` at the nearest root of orientation
/// `want`, else `Err(roots of the other orientation found)`.
fn keep_one<const N: usize, E: Gap>(
    want: Orientation,
    start: &[f64; N],
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<f64, u32> {
    let s = sane(scale[0], start[0]);
    let turn = settings.span == Span::Turn;
    let pi = core::f64::consts::PI;
    let scan: RootScan<{ crate::outer::MAX_ROOTS }> = {
        let (mut point, mut r) = ([0.0; N], [0.0; N]);
        let one = |t: f64| {
            point[0] = t;
            f(&point, &mut r).map(|()| r[0])
        };
        if turn {
            all_roots(-pi, pi, true, crate::outer::ANGLE_SAMPLES, settings, one)
        } else {
            let (lo, hi) = (start[0] - 4.0 * s, start[0] + 4.0 * s);
            all_roots(lo, hi, false, LENGTH_SAMPLES, settings, one)
        }
    };
    let mut best: Option<(f64, f64, f64)> = None;
    let mut others = 0;
    for (i, &root) in scan.roots().iter().enumerate() {
        if scan.is_double(i) || scan.is_boundary(i) {
            continue;
        }
        let mut point = [0.0; N];
        point[0] = root;
        match orientation(&point, scale, f) {
            Some(o) if o == want => {
                let d = if turn {
                    crate::num::wrap_angle(root - start[0]).abs()
                } else {
                    (root - start[0]).abs()
                };
                if best.is_none_or(|(_, nearest, _)| d < nearest) {
                    best = Some((root, d, scan.residual(i)));
                }
            }
            Some(_) => others += 1,
            None => {}
        }
    }
    match best {
        Some((root, _, residual)) => {
            x[0] = root;
            Ok(residual)
        }
        None => Err(others),
    }
}

/// [`keep`] with several defaults: the iteration from the grid's starts, shell by shell.
fn keep_several<const N: usize, E: Gap>(
    want: Orientation,
    start: &[f64; N],
    x: &mut [f64; N],
    scale: &[f64; N],
    settings: &Settings,
    f: &mut impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
) -> Result<f64, u32> {
    let cells = (GRID.len() as u32).saturating_pow(N as u32);
    let mut spent = 0u32;
    let mut others = 0u32;
    // Shell `level` holds the starts whose largest offset index, halved up, is `level`: the
    // start itself, then the half scale, one, two and three scales away.
    for level in 0..=GRID.len().div_ceil(2) {
        let mut best: Option<([f64; N], f64, f64)> = None;
        for cell in 0..cells {
            let mut rest = cell;
            let mut index = [0usize; N];
            for slot in index.iter_mut() {
                *slot = (rest % GRID.len() as u32) as usize;
                rest /= GRID.len() as u32;
            }
            if index.iter().map(|i| i.div_ceil(2)).max() != Some(level) {
                continue;
            }
            if spent >= SEARCH_BUDGET {
                break;
            }
            let mut y = *start;
            for k in 0..N {
                y[k] += GRID[index[k]] * sane(scale[k], start[k]);
            }
            let outcome = iterate::solve_system(&mut y, scale, settings, f);
            spent = spent.saturating_add(
                outcome
                    .as_ref()
                    .map_or(settings.max_evaluations, |c| c.evaluations),
            );
            let Ok(converged) = outcome else {
                continue;
            };
            match orientation(&y, scale, f) {
                Some(o) if o == want => {
                    let d: f64 = (0..N)
                        .map(|k| ((y[k] - start[k]) / sane(scale[k], start[k])).powi(2))
                        .sum();
                    if best.is_none_or(|(_, nearest, _)| d < nearest) {
                        best = Some((y, d, converged.residual));
                    }
                }
                Some(_) => others += 1,
                None => {}
            }
        }
        if let Some((root, _, residual)) = best {
            *x = root;
            return Ok(residual);
        }
    }
    Err(others)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_error() -> Settings {
        Settings::for_size(1.0)
    }

    #[test]
    fn one_default_orientation_is_the_slope_sign_and_none_at_a_kink_or_fold() {
        let mut rising = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = x[0].sin();
            Ok(())
        };
        assert_eq!(
            orientation(&[0.0], &[1.0], &mut rising),
            Some(Orientation::Positive)
        );
        assert_eq!(
            orientation(&[core::f64::consts::PI], &[1.0], &mut rising),
            Some(Orientation::Negative)
        );
        let mut v = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = (x[0] - 0.3).abs();
            Ok(())
        };
        assert_eq!(orientation(&[0.3], &[1.0], &mut v), None);
        let mut fold = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = x[0] * x[0];
            Ok(())
        };
        assert_eq!(orientation(&[0.0], &[1.0], &mut fold), None);
    }

    #[test]
    fn two_defaults_orientation_is_the_determinant_sign() {
        // e = (x + y, x - y): det = -2; swapping the errors' order flips it.
        let mut f = |p: &[f64; 2], r: &mut [f64; 2]| -> Result<(), ()> {
            *r = [p[0] + p[1], p[0] - p[1]];
            Ok(())
        };
        assert_eq!(
            orientation(&[0.0, 0.0], &[1.0, 1.0], &mut f),
            Some(Orientation::Negative)
        );
        let mut g = |p: &[f64; 2], r: &mut [f64; 2]| -> Result<(), ()> {
            *r = [p[0] - p[1], p[0] + p[1]];
            Ok(())
        };
        assert_eq!(
            orientation(&[0.0, 0.0], &[1.0, 1.0], &mut g),
            Some(Orientation::Positive)
        );
    }

    #[test]
    fn a_held_turn_takes_the_nearest_root_of_its_orientation_or_says_none() {
        // sin has roots at 0 (rising) and pi (falling); a start at 2.5 reaches pi first.
        let sin = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = x[0].sin();
            Ok(())
        };
        let settings = no_error()
            .spanning(Span::Turn)
            .holding(Some(Orientation::Positive));
        let mut x = [2.5];
        let converged = iterate::solve(&mut x, &[1.0], &settings, sin).expect("a root");
        assert!(x[0].abs() < 1e-12, "the rising root at 0, not pi: {x:?}");
        assert!(converged.residual < 1e-12);
        // Unheld, the same start takes the root nearest it.
        let mut y = [2.5];
        iterate::solve(&mut y, &[1.0], &settings.holding(None), sin).expect("a root");
        assert!((y[0] - core::f64::consts::PI).abs() < 1e-12, "{y:?}");
        // 0.5 - cos has roots falling at -pi/3 and rising at pi/3: a start at -1.2 reaches
        // the falling one first.
        let g = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = 0.5 - x[0].cos();
            Ok(())
        };
        let mut z = [-1.2];
        let held = settings.holding(Some(Orientation::Positive));
        iterate::solve(&mut z, &[1.0], &held, g).expect("a root");
        assert!((z[0] - core::f64::consts::FRAC_PI_3).abs() < 1e-12, "{z:?}");
        // A function whose every root falls: the held mode has none.
        let falling = |x: &[f64; 1], r: &mut [f64; 1]| -> Result<(), ()> {
            r[0] = -x[0];
            Ok(())
        };
        let mut w = [0.2];
        let lengths = no_error().holding(Some(Orientation::Positive));
        match iterate::solve(&mut w, &[1.0], &lengths, falling) {
            Err(Failure::OtherMode { others, .. }) => assert_eq!(others, 1),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn several_defaults_held_find_a_root_of_the_orientation_from_the_grid() {
        // The roots of (x^2 - 1, y - x): J = [[2x, 0], [-1, 1]], det 2x, positive at (1, 1)
        // and negative at (-1, -1), which the start is nearer.
        let f = |p: &[f64; 2], r: &mut [f64; 2]| -> Result<(), ()> {
            *r = [p[0] * p[0] - 1.0, p[1] - p[0]];
            Ok(())
        };
        let held = no_error().holding(Some(Orientation::Positive));
        let mut x = [-0.9, -0.8];
        iterate::solve(&mut x, &[1.0, 1.0], &held, f).expect("a root");
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
            "{x:?}"
        );
        let mut y = [-0.9, -0.8];
        iterate::solve(&mut y, &[1.0, 1.0], &held.holding(None), f).expect("a root");
        assert!((y[0] + 1.0).abs() < 1e-12, "{y:?}");
    }
}
