//! The numeric baseline: Newton-Raphson and Levenberg-Marquardt on the raw constraint
//! equations of a model, the way a numeric CAD solver (SolveSpace, PlaneGCS) solves them:
//! [`Baseline`] for 2d models, [`Baseline3`] for 3d ones, with the same API.
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
