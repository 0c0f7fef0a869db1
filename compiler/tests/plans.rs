//! Every example model and family model (`examples/`, `examples/families/`) checks clean and
//! says what it is; every one the analysis covers analyses completely, validates, solves at its
//! defaults to 1e-12 and reports no problem; the others (`discover::NOT_YET`) are refused with
//! a reason.
//! (The test models of `tests/models/` are the generated-code tests' own.)

use gcs_compiler::analyse;
use gcs_lang::Model;
use std::path::Path;

mod discover {
    include!("../../examples/discover.rs");
}

/// The example and family models, in name order.
fn models() -> Vec<discover::Found> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    discover::models(&root)
        .into_iter()
        .filter(|m| m.folder != discover::Folder::TestModels)
        .collect()
}

fn load(m: &discover::Found) -> Model {
    let (_, model, diags) = gcs_lang::load(&m.file_name(), m.text.as_bytes());
    assert!(diags.is_empty(), "{}: {diags:?}", m.relative());
    model.unwrap_or_else(|| panic!("{}: no model", m.relative()))
}

#[test]
fn every_model_loads_without_a_diagnostic_and_says_what_it_is() {
    let models = models();
    for m in &models {
        load(m);
        // The examples crate documents each solver module with these lines.
        assert!(
            !m.description().is_empty(),
            "{} has no leading `//` comment saying what it is",
            m.relative()
        );
    }
    // The examples are found where the tests and the examples crate look for them.
    for stem in ["fourbar", "brick"] {
        assert!(
            models
                .iter()
                .any(|m| m.stem == stem && m.folder.is_example()),
            "examples/{stem}.gcs was not found"
        );
    }
}

#[test]
fn every_analysed_model_has_a_complete_valid_plan_that_solves() {
    for m in models().iter().filter(|m| m.is_analysed()) {
        let name = m.relative();
        let model = load(m);
        let a = analyse(&model).unwrap_or_else(|e| panic!("{name}: {e}"));
        let unsolved: Vec<_> = a
            .unsolved
            .iter()
            .map(|u| {
                (
                    model.constraints[u.constraint].name.clone(),
                    u.reason.clone(),
                )
            })
            .collect();
        assert!(unsolved.is_empty(), "{name}: unsolved {unsolved:?}");
        if let Err(errs) = a.plan.validate(&model) {
            panic!("{name}: {errs}\n{}", a.plan.dump(&model));
        }
        assert_eq!(a.plan.unsatisfied(&model), [], "{name}");
        for b in &a.plan.branches {
            assert!(
                b.default < b.count,
                "{name}: branch {} default {} of {}",
                b.name,
                b.default,
                b.count
            );
            assert_eq!(
                b.meanings.len(),
                b.count,
                "{name}: branch {} meanings {:?}",
                b.name,
                b.meanings
            );
        }
        let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
        let s = gcs_compiler::solve(&model, &a, &model.default_params(), &branches)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let max = gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(
            &model,
            &s,
            &model.default_params(),
        ));
        assert!(max <= 1e-12, "{name}: max residual {max:e}");
        assert!(
            s.max_residual <= 1e-12,
            "{name}: solution's max residual {:e}",
            s.max_residual
        );
        // Under-constrained models are warned about (each free motion and its default);
        // nothing else may be reported.
        let problems = gcs_compiler::report::problems(&model, &a);
        let errors: Vec<_> = problems.iter().filter(|d| d.is_error()).collect();
        assert!(errors.is_empty(), "{name}: problems {problems:#?}");
        assert_eq!(
            problems.len(),
            a.free_defaults().len(),
            "{name}: a warning for each free default, no other: {problems:#?}"
        );
        eprintln!(
            "{name}: {} steps, {} branches, {} redundant, max residual {max:e}",
            a.plan.steps.len(),
            a.plan.branches.len(),
            a.redundant.len()
        );
    }
}

#[test]
fn the_models_not_solved_yet_are_refused_with_a_reason() {
    // A model of `discover::NOT_YET` that the analysis solves fails here: take it off the list,
    // and it is checked above and golden everywhere.
    for m in models().iter().filter(|m| !m.is_analysed()) {
        let name = m.relative();
        let model = load(m);
        match analyse(&model) {
            Err(_) => {}
            Ok(a) => {
                let free = a
                    .clusters
                    .iter()
                    .any(|c| c.dof > 0 && !c.freedom.is_empty());
                assert!(
                    !a.unsolved.is_empty() || free,
                    "{name}: the analysis now solves it: take it off `NOT_YET`"
                );
                assert!(
                    a.unsolved.iter().all(|u| !u.reason.is_empty()),
                    "{name}: an unsolved constraint without a reason"
                );
            }
        }
    }
}
