//! What `gcs bench` measures, kept out of `gcs-compiler` so that a build script that compiles
//! models does not also build a sparse linear-algebra library, a benchmark driver and an SVG
//! plotter.
//!
//! - [`baseline`]: the numeric baseline, Newton-Raphson and Levenberg-Marquardt on the raw
//!   constraint equations of a 2d or a 3d model (dense LU, or faer's sparse LU and Cholesky on
//!   large models): the speed baseline and an independent cross-check of the plan.
//! - [`bench`](mod@bench): a sweep of a model's params, the compiled side against the
//!   baseline on it, and the report as text, JSON and an SVG plot.
//! - [`families`]: the compiler's generators of model families of any size (a chain of
//!   four-bars, a sketch profile, a Warren truss; many params, many points), re-exported: the
//!   workloads of the scaling, stress and peer benchmarks.
//!
//! Like every library crate here, it never prints or exits.

pub mod baseline;
pub mod bench;
pub use gcs_compiler::families;
