//! Degrees-of-freedom analysis of a `.gcs` [`gcs_lang::Model`] into a metaphorical assembly
//! plan, and the plan's consumers: the interpreter (`gcs solve`), the code generator
//! (`gcs compile`, build scripts) and the explainer (`gcs explain`).
//!
//! The pipeline ([`pipeline`]): [`load`] reads a model, [`analyse`] builds a validated
//! [`plan::Plan`] from it by degrees-of-freedom analysis, and [`compile`] does both and reports
//! the model's problems. The [`plan::Plan`] is the one boundary: [`interp::run`] executes it
//! with given params and branches, [`codegen::generate`] writes it as Rust, and
//! [`explain::explain`] in words. [`solution::Solution`] reads a result by the model's names;
//! [`verify`] re-checks every constraint on a solution without sharing code with the plan.
//! Like every library crate here, it never prints or exits (but for the build-script API).

pub mod all;
pub mod analysis;
pub mod build;
pub mod codegen;
pub mod config;
pub mod draw;
pub mod explain;
pub mod families;
pub mod interp;
pub mod motion;
pub mod nominal;
pub mod pipeline;
pub mod plan;
pub mod prune;
pub mod report;
pub mod solution;
pub mod solve;
pub mod verify;

pub use pipeline::{analyse, compile, load};
pub use solve::{solve, solve_near_sketch, solve_plan, solve_plan_with};
