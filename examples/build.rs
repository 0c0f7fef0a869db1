//! Compiles every 2d example model into a solver module in `OUT_DIR`, which `src/lib.rs` brings
//! in with `gcs_runtime::include_solver!`.

/// The 2d example models, by file stem. The 3d ones (`brick`, `points_planes`, `slider_crank`)
/// are left out on purpose: the degrees-of-freedom analysis covers 2d models only, and 3d lands
/// with its own issue.
const MODELS: &[&str] = &[
    "fourbar",
    "circle",
    "tenbar",
    "slider_crank_2d",
    "crank_rocker",
    "sixbar",
    "jansen_leg",
    "sketch_profile",
];

fn main() -> Result<(), gcs_compiler::build::BuildError> {
    let paths: Vec<String> = MODELS.iter().map(|m| format!("{m}.gcs")).collect();
    gcs_compiler::build::compile_models(&paths)
}
