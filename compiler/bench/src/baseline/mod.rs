//! The numeric baseline: Newton-Raphson and Levenberg-Marquardt on the raw constraint
//! equations of a model, the way a numeric CAD solver (SolveSpace, PlaneGCS) solves them:
//! [`Baseline`] for 2d models, [`Baseline3`] for 3d ones, with the same API ([`Numeric`], as
//! `gcs bench` drives either).
//!
//! It exists for two reasons: it is the speed baseline the compiled plans are measured
//! against, and it is an independent cross-check of the degrees-of-freedom analysis (same
//! model, same branch, same answer). It shares nothing with the plan: it only reads the model.
//!
//! Each space says what its unknowns and equations are ([`planar`] and [`spatial`]: their docs);
//! the linear algebra and the iteration are shared (the private module `solver`):
//!
//! **Unknowns** are exactly the freedom the model's [`gcs_compiler::config::Config`] has, per
//! non-fixed top-level geom in declaration order; fixed geoms (and their members) are
//! constants, and a model that fixes nothing holds one geom at its sketch.
//!
//! **Equations** are the signed, smooth forms of what [`gcs_compiler::verify`] measures, one or
//! more per constraint. Choices the language leaves to the geometry (a side, a sense) are read
//! from the start configuration of each solve, as a numeric CAD solver does. Everything is
//! precompiled to flat arrays; constants (member coordinates, fixed geoms, values) are
//! re-evaluated from the params at the start of a solve. A constraint a space cannot express
//! is refused by `new`, naming it: never dropped.
//!
//! **Jacobian**: analytic, assembled in O(nnz). Dense (in-place LU with partial pivoting,
//! Cholesky for normal equations) up to [`DENSE_MAX`] unknowns; above it sparse, with `faer`'s
//! sparse LU (COLAMD ordering) for square Newton steps and its sparse Cholesky (AMD ordering)
//! for normal equations. The symbolic factorisations are computed once, in `new`; the
//! iteration loop allocates nothing.
//!
//! **Scaling**: each solve equilibrates the system by dimension: with `L` the length scale of
//! the start configuration, length equations are divided by `L` and length unknowns measured
//! in units of `L`, so the iteration runs on the dimensionless `W J C d = -W F`, `dx = C d`.
//! The merit function `|W F|^2`, the LU's pivot threshold, the regularisation and every floor
//! are then the same for a model and for that model scaled by any factor: Newton takes the
//! same steps at unit scale and at 1e6 (an unweighted `|F|^2` adds squared lengths to squared
//! radians, and at large scale the O(L theta^2) curvature error of a full step in lengths
//! dwarfs the angle residual it removes, so backtracking cut every step to almost nothing).
//! The tolerance stays on the raw largest residual.
//!
//! **Methods**: Newton takes full steps (LU on a square system; regularised normal equations
//! when the system is not square or the LU is singular) with Armijo backtracking on `|W F|^2`.
//! Levenberg-Marquardt solves `(JᵀJ + mu D) d = -JᵀF` (of the equilibrated system) with
//! Marquardt's scaling `D = diag(JᵀJ)` and Nielsen's damping update. There is no branch
//! steering: from a warm start Newton stays on the nearby assembly, from a cold start it lands
//! where it lands.

pub mod planar;
mod solver;
pub mod spatial;

pub use planar::Baseline;
pub use solver::{Linear, Method, Options, Outcome, Stop, DENSE_MAX};
pub use spatial::Baseline3;

use gcs_compiler::config::Config;
use gcs_compiler::solution::Solution;

/// A baseline of either space, as `gcs bench` drives it: [`Baseline`] for 2d models,
/// [`Baseline3`] for 3d ones (their methods of the same names).
pub trait Numeric {
    /// The model's space, whose configurations the interpreter reaches.
    type Space: gcs_compiler::interp::Space;
    /// The number of unknowns.
    fn unknowns(&self) -> usize;
    /// The number of scalar equations.
    fn equations(&self) -> usize;
    /// Whether the sparse linear algebra is in use.
    fn is_sparse(&self) -> bool;
    /// The cold start: the unknowns as the sketch has them, with `params`.
    fn start_from_sketch(&self, params: &[f64]) -> Vec<f64>;
    /// The unknowns that describe configuration `cfg`.
    fn unknowns_from_config(&self, params: &[f64], cfg: &Config<Self::Space>) -> Vec<f64>;
    /// Solves in place from the start `x`.
    fn solve(&mut self, params: &[f64], x: &mut [f64], opts: &Options) -> Outcome;
    /// Every geom of the model as the unknowns `x` place it, read by the model's names
    /// (its `max_residual` unset); `None` when the sketch is unusable with `params`.
    fn solution(&self, params: &[f64], x: &[f64]) -> Option<Solution>;
}

impl Numeric for Baseline {
    type Space = gcs_compiler::config::D2;
    fn unknowns(&self) -> usize {
        Baseline::unknowns(self)
    }
    fn equations(&self) -> usize {
        Baseline::equations(self)
    }
    fn is_sparse(&self) -> bool {
        Baseline::is_sparse(self)
    }
    fn start_from_sketch(&self, params: &[f64]) -> Vec<f64> {
        Baseline::start_from_sketch(self, params)
    }
    fn unknowns_from_config(&self, params: &[f64], cfg: &Config) -> Vec<f64> {
        Baseline::unknowns_from_config(self, params, cfg)
    }
    fn solve(&mut self, params: &[f64], x: &mut [f64], opts: &Options) -> Outcome {
        Baseline::solve(self, params, x, opts)
    }
    fn solution(&self, params: &[f64], x: &[f64]) -> Option<Solution> {
        let model = self.model();
        let all = model.top_level().map(|(id, _)| id).collect();
        let cfg = self.config(params, x).ok()?;
        Some(Solution::read(model, &cfg, &all))
    }
}

impl Numeric for Baseline3 {
    type Space = gcs_compiler::config::D3;
    fn unknowns(&self) -> usize {
        Baseline3::unknowns(self)
    }
    fn equations(&self) -> usize {
        Baseline3::equations(self)
    }
    fn is_sparse(&self) -> bool {
        Baseline3::is_sparse(self)
    }
    fn start_from_sketch(&self, params: &[f64]) -> Vec<f64> {
        Baseline3::start_from_sketch(self, params)
    }
    fn unknowns_from_config(
        &self,
        params: &[f64],
        cfg: &Config<gcs_compiler::config::D3>,
    ) -> Vec<f64> {
        Baseline3::unknowns_from_config(self, params, cfg)
    }
    fn solve(&mut self, params: &[f64], x: &mut [f64], opts: &Options) -> Outcome {
        Baseline3::solve(self, params, x, opts)
    }
    fn solution(&self, params: &[f64], x: &[f64]) -> Option<Solution> {
        let model = self.model();
        let all = model.top_level().map(|(id, _)| id).collect();
        let cfg = self.config(params, x).ok()?;
        Some(Solution::read_space(model, &cfg, &all))
    }
}
