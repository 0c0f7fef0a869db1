//! The generated solvers: `gcs compile`'s output for every model the analysis covers, of the
//! examples (`examples/`), of the test models (`tests/models/`) and of ik-geo's arms
//! (`ikgeo/models/`), is golden
//! (`tests/trybuild/generated/<stem>.rs`), and trybuild compiles each one and runs a driver
//! that compares it with the interpreter and re-checks every constraint
//! (`tests/trybuild/driver.rs`), with the model's tabled module beside it in the same binary;
//! so are the large families at 1,000 stages, as `gcs compile` writes them (tabled). A
//! compile-fail case shows that misuse reads well. Regenerate
//! the goldens (or create a new model's) with
//! `UPDATE_EXPECT=1 cargo test -p gcs-tests --test generated`, and the expected compiler output
//! with `TRYBUILD=overwrite`.

use expect_test::expect_file;
use gcs_compiler::families::Family;
use std::path::{Path, PathBuf};

mod discover {
    include!("../../examples/discover.rs");
}

/// The large families whose generated solvers (tabled) are run: each at 1,000 stages. The
/// first three repeat one piece; `mixed`'s pieces mostly differ (298 functions).
const LARGE: [(Family, usize); 4] = [
    (Family::FourBarChain, 1000),
    (Family::SketchProfile, 1000),
    (Family::Truss, 1000),
    (Family::Mixed, 1000),
];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The models whose generated solvers are golden and run.
fn models() -> Vec<discover::Found> {
    discover::models(root().parent().expect("the workspace"))
        .into_iter()
        .filter(|m| {
            let tested = [discover::Folder::TestModels, discover::Folder::Arms];
            (m.folder.is_example() || tested.contains(&m.folder)) && m.is_analysed()
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
    let code = gcs_compiler::codegen::format(
        &gcs_compiler::codegen::generate_as(
            &c.model,
            &c.analysis.plan,
            gcs_compiler::codegen::Form::Tabled,
        )
        .unwrap_or_else(|why| panic!("not tabled: {why}")),
    );
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
            "trybuild/generated/{name} has no model the analysis covers in examples/, tests/models/ or ikgeo/models/"
        );
    }
}

/// The model a trybuild case runs.
struct Subject {
    /// How the case names it: `examples/fourbar.gcs`, or a family's `fourbar_chain 1000`.
    shown: String,
    /// Its file name, as the generated solver was compiled with it.
    file: String,
    /// Where its text is, for the case's `include_str!`.
    path: PathBuf,
    /// How many params, branch variables and defaults the driver moves, each kind: all of
    /// them (`usize::MAX`), or a few spread over a large family.
    spread: usize,
    /// How much the agreement asked of the generated solver and the interpreter is loosened:
    /// 1, or more for a long chain of dependent stages, where each side's rounding grows.
    tol_growth: f64,
}

impl Subject {
    fn of(m: &discover::Found) -> Subject {
        Subject {
            shown: m.relative(),
            file: m.file_name(),
            path: m.path.clone(),
            spread: usize::MAX,
            tol_growth: 1.0,
        }
    }
}

/// One solver of a trybuild case: the module `form` holding the solver `module` (its text
/// `code`) of model `m`, the driver that runs it against the interpreter, and its `solve_all`
/// check where it has one (a model with too many branch combinations has none).
fn solver_module(form: &str, m: &Subject, module: &Path, code: &str) -> String {
    let path = |p: &Path| format!("{:?}", p.display().to_string());
    let has_solve_all = code.contains("pub fn solve_all(");
    // The solve whose allocations are counted: a tabled module's `solve_into`, on a
    // `Solution` made before, or `solve`.
    let solve = if code.contains("pub fn solve_into(") {
        "let mut solution = solver::Solution::new();\n        \
         let region = stats_alloc::Region::new(crate::ALLOCATOR);\n        \
         let solved = solver::solve_into(p, b, d, &mut solution);\n        \
         let change = region.change();\n        \
         (solved.map(|()| solution), (change.allocations, change.reallocations))"
    } else {
        "let region = stats_alloc::Region::new(crate::ALLOCATOR);\n        \
         let solved = solver::solve(p, b, d);\n        \
         let change = region.change();\n        \
         (solved, (change.allocations, change.reallocations))"
    };
    let all = if has_solve_all {
        format!(
            "include!({});\n",
            path(&root().join("trybuild/driver_all.rs"))
        )
    } else {
        "// No `solve_all`: too many branch combinations to list.\n    \
         fn all_assemblies<M, P, S>(_: &M, _: &P, _: &S, _: &[String]) -> usize {\n        0\n    }\n"
            .to_string()
    };
    format!(
        "mod {form} {{\n    \
         mod solver {{\n        \
         include!({module});\n    \
         }}\n\
         \n    \
         const NAME: &str = \"{file}\";\n    \
         const MODEL: &str = include_str!({model});\n    \
         const SPREAD: usize = {spread};\n    \
         const TOL_GROWTH: f64 = {tol_growth:?};\n\
         \n    \
         include!({driver});\n    \
         {all}\n    \
         fn generated_solve(\n        \
         p: &solver::Params,\n        \
         b: &solver::Branches,\n        \
         d: &solver::Defaults,\n    \
         ) -> (Result<solver::Solution, gcs_runtime::error::SolveError>, (usize, usize)) {{\n        \
         {solve}\n    \
         }}\n\
         }}\n",
        module = path(module),
        file = m.file,
        model = path(&m.path),
        tol_growth = m.tol_growth,
        spread = if m.spread == usize::MAX {
            "usize::MAX".to_string()
        } else {
            m.spread.to_string()
        },
        driver = path(&root().join("trybuild/driver.rs")),
    )
}

/// The trybuild case of model `m`: each of its `solvers` (a module name, the solver's file and
/// text) run against the interpreter by one binary. One binary a model, not one a solver: each
/// links the compiler, and trybuild builds every case twice.
fn case_text(m: &Subject, solvers: &[(&str, PathBuf, String)]) -> String {
    let modules: String = solvers
        .iter()
        .map(|(form, module, code)| format!("\n{}", solver_module(form, m, module, code)))
        .collect();
    let runs: String = solvers
        .iter()
        .map(|(form, ..)| {
            format!(
                "    if std::panic::catch_unwind({form}::run).is_err() {{\n        \
                 eprintln!(\"{}: the {form} solver failed (above)\");\n        \
                 std::process::exit(101);\n    \
                 }}\n",
                m.shown
            )
        })
        .collect();
    format!(
        "// Runs the generated solvers of `{relative}` against the interpreter.\n\
         #![deny(warnings)]\n\
         \n\
         // Counts allocations, to show that a generated solve allocates nothing.\n\
         #[global_allocator]\n\
         static ALLOCATOR: &stats_alloc::StatsAlloc<std::alloc::System> =\n    \
         &stats_alloc::INSTRUMENTED_SYSTEM;\n\
         {modules}\n\
         fn main() {{\n\
         {runs}\
         }}\n",
        relative = m.shown,
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
        let golden_text = std::fs::read_to_string(golden(&m.stem)).unwrap_or_default();
        let golden_is_tabled = golden_text.contains("pub fn solve_into(");
        let mut solvers = vec![("golden", golden(&m.stem), golden_text)];
        // The same model's tabled module (what a large model gets), where its plan allows
        // one: every model's pieces, shapes and tables checked as the flat solver is.
        let c = gcs_compiler::compile(&m.file_name(), m.text.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e:?}", m.relative()));
        let tabled = gcs_compiler::codegen::generate_as(
            &c.model,
            &c.analysis.plan,
            gcs_compiler::codegen::Form::Tabled,
        );
        if let (Ok(tabled), false) = (tabled, golden_is_tabled) {
            let module = cases.join(format!("tabled_{}.rs", m.stem));
            write(&module, &tabled);
            solvers.push(("tabled", module, tabled.into()));
        }
        let case = cases.join(format!("run_{}.rs", m.stem));
        write(&case, &case_text(&Subject::of(&m), &solvers));
        t.pass(case);
    }
    // Large families, as `gcs compile` writes them (tabled): the same checks, moving a few
    // params, branch variables and defaults spread over the model, with every stage solved
    // and every constraint re-checked each time.
    for (family, n) in LARGE {
        let stem = format!("{}_{n}", family.name());
        let path = cases.join(format!("{stem}.gcs"));
        let text = family.model(n);
        write(&path, &text);
        let file = format!("{stem}.gcs");
        let c = gcs_compiler::compile(&file, text.as_bytes())
            .unwrap_or_else(|e| panic!("{stem}: {e:?}"));
        let code = gcs_compiler::codegen::generate(&c.model, &c.analysis.plan);
        assert!(code.contains("pub fn solve_into("), "{stem} is not tabled");
        let module = cases.join(format!("{stem}.rs"));
        write(&module, &code);
        let subject = Subject {
            shown: format!("the family {} at {n} stages", family.name()),
            file,
            path,
            spread: 4,
            tol_growth: 100.0,
        };
        let case = cases.join(format!("run_{stem}.rs"));
        write(
            &case,
            &case_text(&subject, &[("tabled", module, code.into())]),
        );
        t.pass(case);
    }
    t.pass("trybuild/pass/*.rs");
    t.compile_fail("trybuild/ui/*.rs");
}
