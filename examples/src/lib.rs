//! Example `.gcs` models (in this folder) and programs that embed their generated solvers.
//!
//! `build.rs` compiles every example model the analysis covers (today the 2d ones), and every
//! family model under `families/`, with `gcs_compiler::build::compile_models`; each module
//! below, one per model and named after its file, brings one generated solver in with
//! `gcs_runtime::include_solver!`. Every module has the same shape: `Params`, `Branches` and
//! `Defaults` (each with `Default`, the model's values), `Solution` with accessors named after
//! the model, and `solve(&Params, &Branches, &Defaults) -> Result<Solution, SolveError>`.
//! [`for_each_example!`] names the examples' modules to a macro.
//!
//! The programs in `src/bin/`: `fourbar_sweep` (the coupler curve of `crank_rocker` as CSV and
//! SVG) and `throughput` (solves per second of `fourbar` on one core and on all of them).

include!(concat!(env!("OUT_DIR"), "/gcs-examples-modules.rs"));
