//! The numeric kernel that generated gcs solvers call, and that the interpreter shares:
//! frames and Kramer's actions, loci, the locus intersection table with branch selection, the
//! closed-form solutions of the 3d plan fragments built on them, the turns of bodies about
//! known axes that bring their points onto loci (`turn3d`), polynomial roots, error
//! accounting, named tolerances, and the outer iterations that solve for a plan's defaults
//! (Newton with brackets, a trust region, and a scan for every root).
//!
//! Architecture invariants: this crate depends on nalgebra and `gcs-tol` (the tolerances) only;
//! nothing in it panics on finite or non-finite input; nothing on a solve path allocates.
#![deny(missing_docs)]

pub mod check;
pub mod error;
pub mod fragment3;
pub mod frame;
pub mod intersect2d;
pub mod intersect3d;
pub mod iterate;
pub mod linear;
pub mod locus2d;
pub mod locus3d;
pub mod mode;
pub mod num;
pub mod outer;
pub mod poly;
pub mod roots;
pub mod turn3d;
/// Every tolerance, by name (its own crate, so that the language's checks use them too).
pub use gcs_tol as tol;

pub use roots::{Contact, Intersection, Roots};

/// The linear algebra crate the kernel is built on, re-exported so that generated solvers
/// depend on this crate alone.
pub use nalgebra;

/// Brings in a solver that a build script generated with `gcs_compiler::build::compile_models`:
/// `include_solver!("fourbar")` includes `$OUT_DIR/fourbar.rs`, the module generated from a
/// model file named `fourbar.gcs`.
///
/// Use it as the body of a module, so that the solver's items (`Params`, `Branches`,
/// `Defaults`, `Solution`, `solve`) live under the name you choose:
///
/// ```ignore
/// pub mod fourbar {
///     gcs_runtime::include_solver!("fourbar");
/// }
///
/// let solution = fourbar::solve(
///     &fourbar::Params { theta: 0.5, ..Default::default() },
///     &fourbar::Branches::default(),
///     &fourbar::Defaults::default(),
/// )?;
/// ```
#[macro_export]
macro_rules! include_solver {
    ($name:literal) => {
        include!(concat!(env!("OUT_DIR"), "/", $name, ".rs"));
    };
}
