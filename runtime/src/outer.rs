//! What a generated solver does at an outer iteration: solve it ([`Newton`], the plain solve)
//! or list every root of its error ([`Scan`], for `solve_all`).
//!
//! A generated solver with outer iterations writes its plan once, as a function generic over
//! [`Outer`]; each iteration of the plan is a call of [`Outer::iterate`] with the closure that
//! assembles the iteration's region for a trial of its defaults. `solve` passes [`Newton`],
//! which is [`iterate::solve`] and compiles to the same code as calling it directly. `solve_all`
//! first passes a [`Scan`], which stops the solve at its first iteration once it has listed
//! every root of that iteration's error over a turn, and then solves from each root. The plan's
//! steps before the iteration run once per scan, not once per sample.

use crate::iterate::{self, Converged, Failure, RootScan, Settings};

/// The most roots a [`Scan`] lists.
pub const MAX_ROOTS: usize = 64;

/// Samples of the turn a [`Scan`] takes before refining: half a degree apart.
pub const ANGLE_SAMPLES: u32 = 720;

/// How a generated solve treats an outer iteration.
pub trait Outer {
    /// Drives the iteration whose residuals `f` computes, from `trial`: `Ok` (with `trial` at
    /// the answer) to go on with the solve, `Err` to stop it with that failure.
    ///
    /// # Errors
    ///
    /// [`Failure`] when the iteration does not converge (or, for a [`Scan`], always: the scan
    /// ends the solve).
    fn iterate<const N: usize, E: iterate::Gap>(
        &mut self,
        trial: &mut [f64; N],
        scale: &[f64; N],
        settings: &Settings,
        f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<Converged, Failure<E>>;
}

/// Solves each iteration from its starting defaults: [`iterate::solve`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Newton;

impl Outer for Newton {
    #[inline(always)]
    fn iterate<const N: usize, E: iterate::Gap>(
        &mut self,
        trial: &mut [f64; N],
        scale: &[f64; N],
        settings: &Settings,
        f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<Converged, Failure<E>> {
        iterate::solve(trial, scale, settings, f)
    }
}

/// Solves each iteration from its starting defaults as one start of many
/// ([`Settings::searching`]): a failure is not told apart and no mode is held, since a search
/// for every assembly reads neither, and pays the telling at every start that fails.
#[derive(Clone, Copy, Debug, Default)]
pub struct Search;

impl Outer for Search {
    #[inline(always)]
    fn iterate<const N: usize, E: iterate::Gap>(
        &mut self,
        trial: &mut [f64; N],
        scale: &[f64; N],
        settings: &Settings,
        f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<Converged, Failure<E>> {
        iterate::solve(trial, scale, &settings.searching(), f)
    }
}

/// Lists every root of the first iteration's error over a turn of its default, an angle, and
/// ends the solve there (with [`Failure::NoConvergence`] and no iterations taken).
///
/// Only an iteration over one default is scanned: with several, the scan lists nothing and
/// says so ([`Scan::scanned`] stays false). Which roots the scan finds, double roots and roots
/// where the assembly stops existing included, is [`iterate::all_roots`]'s documentation: on
/// [`ANGLE_SAMPLES`] samples, two roots closer than a sample spacing with the error above the
/// tolerance between them are the only ones it can miss.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scan {
    roots: RootScan<MAX_ROOTS>,
    scanned: bool,
}

impl Scan {
    /// The roots found, ascending in `[-pi, pi)`.
    pub fn roots(&self) -> &[f64] {
        self.roots.roots()
    }

    /// Whether an iteration over one default was reached and scanned.
    pub fn scanned(&self) -> bool {
        self.scanned
    }

    /// Whether more than [`MAX_ROOTS`] roots were found (the list keeps the first).
    pub fn truncated(&self) -> bool {
        self.roots.truncated()
    }
}

impl Outer for Scan {
    fn iterate<const N: usize, E: iterate::Gap>(
        &mut self,
        _trial: &mut [f64; N],
        _scale: &[f64; N],
        settings: &Settings,
        mut f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<Converged, Failure<E>> {
        if N == 1 && !self.scanned {
            let pi = core::f64::consts::PI;
            let mut point = [0.0; N];
            let mut residual = [0.0; N];
            self.roots = iterate::all_roots(-pi, pi, true, ANGLE_SAMPLES, settings, |x: f64| {
                point[0] = x;
                f(&point, &mut residual).map(|()| residual[0])
            });
            self.scanned = true;
        }
        Err(Failure::NoConvergence {
            residual: f64::NAN,
            iterations: 0,
        })
    }
}

/// Every real assembly a generated `solve_all` found, each once, in the order found: a
/// fixed-capacity list of at most `N`, so that listing them allocates nothing. Each generated
/// module names it `Assemblies` for its own `Solution`.
#[derive(Clone, Copy, Debug)]
pub struct Assemblies<S, const N: usize> {
    solutions: [Option<S>; N],
    len: usize,
    complete: bool,
}

impl<S: Copy, const N: usize> Assemblies<S, N> {
    /// No assembly yet; `complete` when the search that fills it is exhaustive.
    pub fn new(complete: bool) -> Self {
        Self {
            solutions: [None; N],
            len: 0,
            complete,
        }
    }

    /// How many assemblies were found.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether none was: no real assembly exists at these params (on any branches).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The `i`th assembly found.
    pub fn get(&self, i: usize) -> Option<&S> {
        self.solutions.get(i)?.as_ref()
    }

    /// The assemblies, in the order found.
    pub fn iter(&self) -> impl Iterator<Item = &S> {
        self.solutions.iter().flatten()
    }

    /// Whether every real assembly is listed: the search was exhaustive, and neither it nor
    /// the list overflowed.
    pub fn is_complete(&self) -> bool {
        self.complete
    }

    /// Says the list is not known to hold every assembly (a scan that kept only its first
    /// roots).
    pub fn mark_incomplete(&mut self) {
        self.complete = false;
    }

    /// Adds `s` unless `same` says the list has its assembly already; past the capacity,
    /// marks the list incomplete.
    pub fn push(&mut self, s: S, same: impl Fn(&S, &S) -> bool) {
        if self.iter().any(|t| same(t, &s)) {
            return;
        }
        match self.solutions.get_mut(self.len) {
            Some(slot) => {
                *slot = Some(s);
                self.len += 1;
            }
            None => self.complete = false,
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn assemblies_keep_each_once_and_say_when_they_overflow() {
        let same = |a: &f64, b: &f64| (a - b).abs() < 1e-9;
        let mut list = Assemblies::<f64, 2>::new(true);
        list.push(1.0, same);
        list.push(1.0 + 1e-12, same);
        assert_eq!((list.len(), list.is_complete()), (1, true));
        list.push(2.0, same);
        list.push(3.0, same);
        assert_eq!(list.iter().copied().collect::<Vec<_>>(), [1.0, 2.0]);
        assert!(!list.is_complete());
        assert_eq!(list.get(1), Some(&2.0));
        assert_eq!(list.get(2), None);
    }

    use super::*;

    /// The error of a one-default iteration with three roots on the turn, and a stretch where
    /// the assembly fails.
    fn error(t: &[f64; 1], r: &mut [f64; 1]) -> Result<(), ()> {
        if (2.0..2.5).contains(&t[0]) {
            return Err(());
        }
        r[0] = (3.0 * t[0]).sin();
        Ok(())
    }

    #[test]
    fn newton_is_the_plain_iteration() {
        let mut a = [0.2];
        let mut b = [0.2];
        let s = Settings::default();
        let by_trait = Newton.iterate(&mut a, &[1.0], &s, error);
        let direct = iterate::solve(&mut b, &[1.0], &s, error);
        assert_eq!(by_trait, direct);
        assert_eq!(a, b);
        assert!(a[0].abs() < 1e-15, "{a:?}");
    }

    #[test]
    fn a_scan_lists_every_root_of_the_turn_and_stops_the_solve() {
        let mut scan = Scan::default();
        let out = scan.iterate(&mut [0.0], &[1.0], &Settings::default(), error);
        assert!(matches!(out, Err(Failure::NoConvergence { .. })));
        assert!(scan.scanned());
        // sin(3t) = 0 at multiples of pi/3 in [-pi, pi), except 2pi/3 ~ 2.09 (no assembly).
        let pi = core::f64::consts::PI;
        let expected = [-pi, -2.0 * pi / 3.0, -pi / 3.0, 0.0, pi / 3.0];
        let roots = scan.roots();
        assert_eq!(roots.len(), expected.len(), "{roots:?}");
        for (r, e) in roots.iter().zip(expected) {
            assert!((r - e).abs() < 1e-12, "{roots:?}");
        }
        // A second iteration of the same solve is not scanned again.
        let again = scan.iterate(&mut [0.0], &[1.0], &Settings::default(), |_, _| Err(()));
        assert!(again.is_err());
        assert_eq!(scan.roots().len(), expected.len());
    }

    #[test]
    fn several_defaults_are_not_scanned() {
        let mut scan = Scan::default();
        let out = scan.iterate(
            &mut [0.0, 0.0],
            &[1.0, 1.0],
            &Settings::default(),
            |_, _| Ok::<(), ()>(()),
        );
        assert!(out.is_err());
        assert!(!scan.scanned());
        assert!(scan.roots().is_empty());
    }
}
