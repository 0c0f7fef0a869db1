//! The generated solvers: `gcs compile`'s output for every model the analysis covers, of the
//! examples (`examples/`) and of the test models (`tests/models/`), is golden
//! (`tests/trybuild/generated/<stem>.rs`), and trybuild compiles each one and runs a driver
//! that compares it with the interpreter and re-checks every constraint
//! (`tests/trybuild/driver.rs`). A compile-fail case shows that misuse reads well. Regenerate
//! the goldens (or create a new model's) with
//! `UPDATE_EXPECT=1 cargo test -p gcs-tests --test generated`, and the expected compiler output
//! with `TRYBUILD=overwrite`.

use expect_test::expect_file;
use std::path::{Path, PathBuf};

mod discover {
    include!("../../examples/discover.rs");
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The models whose generated solvers are golden and run.
fn models() -> Vec<discover::Found> {
    discover::models(root().parent().expect("the workspace"))
        .into_iter()
        .filter(|m| {
            (m.folder.is_example() || m.folder == discover::Folder::TestModels) && m.is_analysed()
        })
        .collect()
}

fn golden(stem: &str) -> PathBuf {
    root().join(format!("trybuild/generated/{stem}.rs"))
}

#[test]
fn generated_solvers_are_golden() {
    for m in models() {
        let c = gcs_compiler::compile(&m.file_name(), m.text.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e:?}", m.relative()));
        let code = gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(
            &c.model,
            &c.analysis.plan,
        ));
        assert!(
            code.starts_with("// @generated"),
            "{}: no @generated header",
            m.relative()
        );
        expect_file![golden(&m.stem)].assert_eq(&code);
    }
}

/// The tabled form of a small chain, golden so that a change to how large models are laid
/// out shows in review (every model's tabled module is run against the interpreter below).
#[test]
fn a_tabled_solver_is_golden() {
    let m = discover::models(root().parent().expect("the workspace"))
        .into_iter()
        .find(|m| m.stem == "fourbar_chain_16")
        .expect("examples/families/fourbar_chain_16.gcs");
    let c = gcs_compiler::compile(&m.file_name(), m.text.as_bytes())
        .unwrap_or_else(|e| panic!("{}: {e:?}", m.relative()));
    let code = gcs_compiler::codegen::format(&gcs_compiler::codegen::generate_as(
        &c.model,
        &c.analysis.plan,
        gcs_compiler::codegen::Form::Tabled,
    ));
    assert!(code.contains("pub fn solve_into("), "not tabled");
    expect_file![root().join("trybuild/tabled/fourbar_chain_16.rs")].assert_eq(&code);
}

/// A golden whose model is gone (or no longer analysed) is stale: remove it with its model.
#[test]
fn every_golden_belongs_to_a_model() {
    let models = models();
    for entry in std::fs::read_dir(root().join("trybuild/generated")).expect("the goldens") {
        let name = entry.expect("a golden").file_name();
        let name = name.to_string_lossy();
        let stem = name.strip_suffix(".rs").unwrap_or(&name);
        assert!(
            models.iter().any(|m| m.stem == stem),
            "trybuild/generated/{name} has no model the analysis covers in examples/ or tests/models/"
        );
    }
}

/// The trybuild case that runs one model's golden solver against the interpreter; its
/// `solve_all` too, where it has one (a model with too many branch combinations has none).
fn run_case(m: &discover::Found) -> String {
    let text = std::fs::read_to_string(golden(&m.stem)).unwrap_or_default();
    case_text(m, &golden(&m.stem), &text)
}

/// The trybuild case that runs the solver `module` (its text `code`) of model `m`.
fn case_text(m: &discover::Found, module: &Path, code: &str) -> String {
    let path = |p: &Path| format!("{:?}", p.display().to_string());
    let has_solve_all = code.contains("pub fn solve_all(");
    // The solve whose allocations are counted: a tabled module's `solve_into`, on a
    // `Solution` made before, or `solve`.
    let solve = if code.contains("pub fn solve_into(") {
        "let mut solution = solver::Solution::new();\n    \
         let region = stats_alloc::Region::new(ALLOCATOR);\n    \
         let solved = solver::solve_into(p, b, d, &mut solution);\n    \
         let change = region.change();\n    \
         (solved.map(|()| solution), (change.allocations, change.reallocations))"
    } else {
        "let region = stats_alloc::Region::new(ALLOCATOR);\n    \
         let solved = solver::solve(p, b, d);\n    \
         let change = region.change();\n    \
         (solved, (change.allocations, change.reallocations))"
    };
    let all = if has_solve_all {
        format!(
            "include!({});\n",
            path(&root().join("trybuild/driver_all.rs"))
        )
    } else {
        "// No `solve_all`: too many branch combinations to list.\n\
         fn all_assemblies<M, P, S>(_: &M, _: &P, _: &S, _: &[String]) -> usize {\n    0\n}\n"
            .to_string()
    };
    format!(
        "// Runs the generated solver of `{relative}` against the interpreter.\n\
         #![deny(warnings)]\n\
         \n\
         mod solver {{\n    \
         include!({golden});\n\
         }}\n\
         \n\
         const NAME: &str = \"{file}\";\n\
         const MODEL: &str = include_str!({model});\n\
         \n\
         include!({driver});\n\
         {all}\n\
         fn generated_solve(\n    \
         p: &solver::Params,\n    \
         b: &solver::Branches,\n    \
         d: &solver::Defaults,\n\
         ) -> (Result<solver::Solution, gcs_runtime::error::SolveError>, (usize, usize)) {{\n    \
         {solve}\n\
         }}\n",
        relative = m.relative(),
        golden = path(module),
        file = m.file_name(),
        model = path(&m.path),
        driver = path(&root().join("trybuild/driver.rs")),
    )
}

#[test]
fn generated_solvers_agree_with_the_interpreter() {
    // The cases, written from one template; the directory outlives `t`, which runs them when
    // it is dropped. A case is rewritten only when it changes, so trybuild's build of it stays
    // fresh.
    let cases = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gcs-trybuild-run");
    std::fs::create_dir_all(&cases).expect("create the cases' directory");
    let t = trybuild::TestCases::new();
    let write = |path: &Path, text: &str| {
        if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
            std::fs::write(path, text).expect("write a trybuild case");
        }
    };
    for m in models() {
        let case = cases.join(format!("run_{}.rs", m.stem));
        write(&case, &run_case(&m));
        t.pass(case);
        // The same model's tabled module (what a large model gets), where its plan allows
        // one: every model's pieces, shapes and tables checked as the flat solver is.
        let c = gcs_compiler::compile(&m.file_name(), m.text.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e:?}", m.relative()));
        let tabled = gcs_compiler::codegen::generate_as(
            &c.model,
            &c.analysis.plan,
            gcs_compiler::codegen::Form::Tabled,
        );
        let golden_is_tabled = std::fs::read_to_string(golden(&m.stem))
            .is_ok_and(|text| text.contains("pub fn solve_into("));
        if tabled.contains("pub fn solve_into(") && !golden_is_tabled {
            let module = cases.join(format!("tabled_{}.rs", m.stem));
            write(&module, &tabled);
            let case = cases.join(format!("run_tabled_{}.rs", m.stem));
            write(&case, &case_text(&m, &module, &tabled));
            t.pass(case);
        }
    }
    t.pass("trybuild/pass/*.rs");
    t.compile_fail("trybuild/ui/*.rs");
}
