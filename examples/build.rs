//! Compiles every 2d example model, and the family models under `families/`, into solver
//! modules in `OUT_DIR`, which `src/lib.rs` brings in with `gcs_runtime::include_solver!`.

include!("examples_2d.rs");
include!("examples_families.rs");

fn main() -> Result<(), gcs_compiler::build::BuildError> {
    let paths: Vec<String> = EXAMPLES_2D
        .iter()
        .map(|m| format!("{m}.gcs"))
        .chain(
            EXAMPLES_FAMILIES
                .iter()
                .map(|(name, n)| format!("families/{name}_{n}.gcs")),
        )
        .collect();
    gcs_compiler::build::compile_models(&paths)
}
