//! The build-script API end to end: `gcs_compiler::build` compiles an example model into an
//! output directory, as a `build.rs` would into `OUT_DIR`, and leaves an unchanged module alone.

use gcs_compiler::build::Builder;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples")
        .join(name)
}

#[test]
fn compile_models_writes_a_generated_module_and_does_not_rewrite_it() {
    let out = tempfile::tempdir().expect("tempdir");
    let models = [example("fourbar.gcs")];
    let builder = Builder::new().out_dir(out.path()).quiet(true);

    let first = builder.compile(&models).expect("fourbar.gcs compiles");
    let file = out.path().join("fourbar.rs");
    assert_eq!(first.len(), 1);
    assert_eq!(first[0].file, file);
    assert!(first[0].written);
    let text = std::fs::read_to_string(&file).expect("the generated module");
    assert!(
        text.starts_with("// @generated"),
        "no @generated header:\n{}",
        text.lines().take(3).collect::<Vec<_>>().join("\n")
    );
    assert!(text.contains("pub fn solve("));

    // Backdate the module; a rewrite would move its modification time forward again.
    let old = SystemTime::now() - Duration::from_secs(3600);
    std::fs::File::options()
        .write(true)
        .open(&file)
        .and_then(|f| f.set_modified(old))
        .expect("set the modification time");
    let second = builder.compile(&models).expect("compiles again");
    assert!(!second[0].written);
    let modified = std::fs::metadata(&file)
        .and_then(|m| m.modified())
        .expect("modification time");
    assert_eq!(modified, old, "the unchanged module was rewritten");
    assert_eq!(std::fs::read_to_string(&file).expect("module"), text);
}

#[test]
fn compile_models_fails_on_a_model_with_errors() {
    let dir = tempfile::tempdir().expect("tempdir");
    let model = dir.path().join("broken.gcs");
    std::fs::write(
        &model,
        "space 2d;\nfixed point A = (0, 0);\ncoincident(A, Q);\n",
    )
    .expect("write the model");
    let err = Builder::new()
        .out_dir(dir.path())
        .quiet(true)
        .compile(&[&model])
        .expect_err("a model with an unknown name fails");
    let message = format!("{err:?}");
    assert!(
        message.contains("could not compile 1 gcs model"),
        "{message}"
    );
    assert!(message.contains("broken.gcs: 1 error"), "{message}");
    assert!(!dir.path().join("broken.rs").exists());
}
