//! Compiles every 2d example model into a solver module in `OUT_DIR`, which `src/lib.rs` brings
//! in with `gcs_runtime::include_solver!`.

include!("examples_2d.rs");

fn main() -> Result<(), gcs_compiler::build::BuildError> {
    let paths: Vec<String> = EXAMPLES_2D.iter().map(|m| format!("{m}.gcs")).collect();
    gcs_compiler::build::compile_models(&paths)
}
