//! Issue 19: the everyday sketches (`examples/sketches/`) and the mechanisms with sliders on
//! moving bodies solve in closed form (no default, no iteration) and follow one assembly as a
//! dimension or the input moves.
//!
//! Each sketch's first param is swept from 90% to 110% of its value, each mechanism's crank a
//! whole turn, in 41 samples, through `gcs bench`'s comparison (`gcs_bench::bench::run`, the
//! plan in the interpreter, which the generated solvers equal to 1e-14). At every sample:
//! - the plan solves, and `verify` (which shares nothing with the plan) finds every constraint
//!   met to `1e-12` times the model's size;
//! - no flip: the baseline's Newton on the raw equations, continued from the previous sample's
//!   answer, reaches this answer (the bench's continuity count is zero);
//! - the baseline's Newton, warm-started along the same sweep, is reported beside it (its
//!   failures: the concentric circles' raw distance equation is singular where the centres
//!   coincide, which the plan never differentiates).
//!
//! `cargo test -p gcs-bench --release --test closed_form_sweeps -- --nocapture` prints a line
//! per model.

use gcs_bench::bench::{self, Settings, Sweep};
use gcs_lang::expr::Dim;
use gcs_lang::Model;

mod discover {
    include!("../../../examples/discover.rs");
}

/// The mechanisms of issue 19 (in `examples/`), each driven a whole turn by its crank.
const MECHANISMS: [&str; 4] = [
    "inverted_slider_crank",
    "whitworth",
    "scotch_yoke",
    "pin_in_slot",
];

const SAMPLES: usize = 41;

/// The first param from 90% to 110% of its value.
fn dimension_sweep(model: &Model) -> Sweep {
    let base = model.default_params();
    let (_, param) = model.params.iter().next().expect("a sketch with a param");
    let v = base[0];
    let params = (0..SAMPLES)
        .map(|k| {
            let mut p = base.clone();
            p[0] = v * (0.9 + 0.2 * k as f64 / (SAMPLES - 1) as f64);
            p
        })
        .collect();
    Sweep {
        driver: Some(param.name.clone()),
        range: (0.9 * v, 1.1 * v),
        params,
    }
}

fn check(found: &discover::Found, sweep_of: impl Fn(&Model) -> Sweep) -> String {
    let name = &found.stem;
    let (_, model, diags) = gcs_lang::load(&found.relative(), found.text.as_bytes());
    let model = model.unwrap_or_else(|| panic!("{name}: {diags:?}"));
    let analysis = gcs_compiler::analyse(&model).expect("analysis");
    assert!(analysis.unsolved.is_empty(), "{name}: unsolved constraints");
    assert!(
        analysis.plan.defaults.is_empty() && analysis.plan.iterations.is_empty(),
        "{name}: its plan is not closed-form ({} defaults)",
        analysis.plan.defaults.len()
    );
    let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
    let sweep = sweep_of(&model);
    let scope = model.top_level().map(|(id, _)| id).collect();
    let compiled = bench::interpreted(&model, &analysis.plan, &scope, &branches, &sweep, 1.0);
    let settings = Settings {
        budget_ns: 1.0,
        ..Settings::default()
    };
    let report = bench::run(
        &model,
        &analysis.plan,
        &branches,
        sweep,
        compiled,
        &settings,
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    let size = model
        .default_params()
        .iter()
        .fold(1.0f64, |m, v| m.max(v.abs()))
        .max(10.0);
    assert_eq!(report.compiled_failures, 0, "{name}: samples failed");
    assert_eq!(report.branch_flips, 0, "{name}: the plan flipped");
    assert!(
        report.compiled_max_residual <= 1e-12 * size,
        "{name}: residual {:e}",
        report.compiled_max_residual
    );
    format!(
        "{name:32} {:>3} samples of `{}`: max residual {:.1e}, flips 0; baseline: failures {}, warm flips {}, cold on another assembly {}",
        SAMPLES,
        report.sweep.driver.as_deref().unwrap_or("-"),
        report.compiled_max_residual,
        report.baseline.failures,
        report.baseline.branch_flips,
        report.baseline.cold_branch_flips,
    )
}

#[test]
fn sketches_solve_in_closed_form_along_a_dimension_without_a_flip() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let sketches: Vec<_> = discover::models(&root)
        .into_iter()
        .filter(|m| m.folder == discover::Folder::Sketches)
        .collect();
    assert!(sketches.len() >= 20, "{} sketches", sketches.len());
    for s in &sketches {
        println!("{}", check(s, dimension_sweep));
    }
}

#[test]
fn sliders_on_moving_bodies_turn_a_whole_turn_in_closed_form_without_a_flip() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let models = discover::models(&root);
    for name in MECHANISMS {
        let found = (models.iter())
            .find(|m| m.stem == name)
            .unwrap_or_else(|| panic!("no example {name}"));
        let line = check(found, |model| {
            assert!(
                model.params.iter().any(|(_, p)| p.dim == Dim::Angle),
                "{name}: a crank angle"
            );
            bench::sweep(model, SAMPLES)
        });
        println!("{line}");
    }
}

/// The closed profile of `n` segments and `n` fillet arcs, its last two edge lengths free
/// (`gcs_bench::families::closed_profile`): closed-form at every size, every tangency and
/// incidence to `1e-12` of its size, and no flip as the edges' length moves.
#[test]
fn the_closed_fillet_profile_closes_in_closed_form_at_every_size() {
    for n in [4, 16, 64] {
        let text = gcs_bench::families::closed_profile(n);
        let found = discover::Found {
            stem: format!("closed_profile_{n}"),
            folder: discover::Folder::Families,
            path: std::path::PathBuf::from(format!("closed_profile_{n}.gcs")),
            space: gcs_lang::model::Space::D2,
            text,
        };
        println!("{}", check(&found, dimension_sweep));
    }
}
