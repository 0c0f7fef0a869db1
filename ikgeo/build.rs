//! Compiles the five arm models of `models/` into solver modules in `OUT_DIR`, which
//! `src/lib.rs` brings in with `gcs_runtime::include_solver!`.

fn main() -> Result<(), gcs_compiler::build::BuildError> {
    gcs_compiler::build::compile_models(&[
        "models/ikgeo_ur5.gcs",
        "models/ikgeo_irb6640.gcs",
        "models/ikgeo_spherical_bot.gcs",
        "models/ikgeo_three_parallel_bot.gcs",
        "models/ikgeo_two_parallel_bot.gcs",
    ])
}
