//! Example `.gcs` models (in this folder) and programs that embed their generated solvers.
//!
//! `build.rs` compiles every 2d model with `gcs_compiler::build::compile_models`; each module
//! below brings one generated solver in with `gcs_runtime::include_solver!`. Every module has
//! the same shape: `Params`, `Branches` and `Defaults` (each with `Default`, the model's values),
//! `Solution` with accessors named after the model, and
//! `solve(&Params, &Branches, &Defaults) -> Result<Solution, SolveError>`.
//!
//! The programs in `src/bin/`: `fourbar_sweep` (the coupler curve of `crank_rocker` as CSV and
//! SVG) and `throughput` (solves per second of `fourbar` on one core and on all of them).

/// `fourbar.gcs`: a planar four-bar linkage driven by its crank angle `theta`; branch `elbow`;
/// outputs `coupler.c`.
pub mod fourbar {
    gcs_runtime::include_solver!("fourbar");
}

/// `circle.gcs`: Kramer's circle problem, a parabola locus meeting a circle locus; branch
/// `meet`.
pub mod circle {
    gcs_runtime::include_solver!("circle");
}

/// `tenbar.gcs`: Kramer's ten-bar, a four-bar whose coupler is a four-bar whose coupler is a
/// four-bar, driven by `theta1`, `theta2` and `theta3`.
pub mod tenbar {
    gcs_runtime::include_solver!("tenbar");
}

/// `slider_crank_2d.gcs`: a planar slider-crank of markers and joints, driven by the crank angle
/// `phi`; outputs `slider.s`.
pub mod slider_crank_2d {
    gcs_runtime::include_solver!("slider_crank_2d");
}

/// `crank_rocker.gcs`: a Grashof crank-rocker whose coupler point `coupler.p` draws the coupler
/// curve as `theta` turns; branch `elbow`.
pub mod crank_rocker {
    gcs_runtime::include_solver!("crank_rocker");
}

/// `sixbar.gcs`: a Watt II six-bar driven by `theta`; branches `first` and `second`; outputs
/// `follower`.
pub mod sixbar {
    gcs_runtime::include_solver!("sixbar");
}

/// `jansen_leg.gcs`: Theo Jansen's walking-machine leg driven by the crank angle `theta`;
/// outputs `foot`.
pub mod jansen_leg {
    gcs_runtime::include_solver!("jansen_leg");
}

/// `sketch_profile.gcs`: a CAD sketch profile (a rectangle with a filleted corner) sized by `w`,
/// `h` and `r`.
pub mod sketch_profile {
    gcs_runtime::include_solver!("sketch_profile");
}

/// `families/fourbar_chain_16.gcs`: 16 four-bars in series (paper 000, Fig. 10), driven by
/// `theta`; outputs `rocker16.b`.
pub mod fourbar_chain_16 {
    gcs_runtime::include_solver!("fourbar_chain_16");
}

/// `families/fourbar_chain_128.gcs`: 128 four-bars in series, driven by `theta`; outputs
/// `rocker128.b`.
pub mod fourbar_chain_128 {
    gcs_runtime::include_solver!("fourbar_chain_128");
}

/// `families/sketch_profile_16.gcs`: 16 segments joined by 16 tangent fillet arcs, sized by
/// `len` and `r`; outputs `f15`.
pub mod sketch_profile_16 {
    gcs_runtime::include_solver!("sketch_profile_16");
}

/// `families/truss_16.gcs`: a Warren truss of 16 triangles with bars of length `bar`; outputs
/// `p17`.
pub mod truss_16 {
    gcs_runtime::include_solver!("truss_16");
}
