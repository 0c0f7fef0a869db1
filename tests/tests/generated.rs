//! The generated solvers: `gcs compile`'s output for every 2d example is golden
//! (`tests/trybuild/generated/`), and trybuild compiles each one and runs a driver that compares
//! it with the interpreter and re-checks every constraint (`tests/trybuild/driver.rs`). A
//! compile-fail case shows that misuse reads well. Regenerate the goldens with
//! `UPDATE_EXPECT=1 cargo test -p gcs-tests --test generated`, and the expected compiler
//! output with `TRYBUILD=overwrite`.

use expect_test::expect_file;
use std::path::Path;

include!("../../examples/examples_2d.rs");

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn generated_solvers_are_golden() {
    for m in EXAMPLES_2D {
        let path = root().join(format!("../examples/{m}.gcs"));
        let bytes = std::fs::read(&path).expect("example");
        let (_, model, diags) = gcs_lang::load(&format!("{m}.gcs"), &bytes);
        let model = model.unwrap_or_else(|| panic!("{m}: {diags:?}"));
        let analysis = gcs_compiler::analyse(&model).expect("analysis");
        let code =
            gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(&model, &analysis.plan));
        assert!(
            code.starts_with("// @generated"),
            "{m}: no @generated header"
        );
        expect_file![root().join(format!("trybuild/generated/{m}.rs"))].assert_eq(&code);
    }
}

#[test]
fn generated_solvers_agree_with_the_interpreter() {
    let t = trybuild::TestCases::new();
    for m in EXAMPLES_2D {
        t.pass(format!("trybuild/run_{m}.rs"));
    }
    t.compile_fail("trybuild/ui/*.rs");
}
