//! What the commands share: the params, branches and defaults of `--set`, `--branch` and
//! `--default` (or the page's same words, for `gcs serve`), the solve that reads them, and the
//! words of a failure and of a model that does not load. Nothing here prints: the command line
//! prints what it returns, and the page shows it.

use gcs_compiler::analysis::Analysis;
use gcs_compiler::plan::Plan;
use gcs_compiler::solve::Kept;
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use gcs_runtime::error::SolveError;
use std::collections::BTreeSet;

/// The params, branches (indexed like the whole plan's) and defaults a command's `--set`,
/// `--branch` and `--default` give, over the model's and the sketch's.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs {
    pub params: Vec<f64>,
    pub branches: Vec<usize>,
    pub defaults: Vec<f64>,
}

/// Reads `--set NAME=EXPR`, `--branch NAME=INDEX` and `--default NAME=EXPR`; the first value
/// that is wrong is an error in words, naming the flag as written.
pub fn inputs(
    model: &Model,
    analysis: &Analysis,
    set: &[String],
    branch: &[String],
    default: &[String],
) -> Result<Inputs, String> {
    let mut params = model.default_params();
    for s in set {
        let Some((name, value)) = s.split_once('=') else {
            return Err(format!("`--set {s}`: expected NAME=VALUE"));
        };
        let Some(id) = model.param_named(name.trim()) else {
            let names: Vec<&str> = model.params.iter().map(|(_, p)| p.name.as_str()).collect();
            return Err(format!(
                "`--set {s}`: no param `{}`; the params are: {}",
                name.trim(),
                names.join(", ")
            ));
        };
        match gcs_lang::parse::param_value(model, id, value) {
            Ok(v) => params[id.into_raw().into_u32() as usize] = v,
            Err(e) => return Err(format!("`--set {s}`: {e}")),
        }
    }
    let mut branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
    for b in branch {
        let parsed = b
            .split_once('=')
            .and_then(|(n, i)| Some((n.trim(), i.trim().parse::<usize>().ok()?)));
        let Some((name, index)) = parsed else {
            return Err(format!("`--branch {b}`: expected NAME=INDEX"));
        };
        match analysis.plan.branches.iter().position(|x| x.name == name) {
            Some(i) if index < analysis.plan.branches[i].count => branches[i] = index,
            Some(i) => {
                return Err(format!(
                    "`--branch {b}`: `{name}` has indices 0 to {}",
                    analysis.plan.branches[i].count - 1
                ))
            }
            None => {
                let names: Vec<&str> = (analysis.plan.branches.iter())
                    .map(|x| x.name.as_str())
                    .collect();
                return Err(format!(
                    "`--branch {b}`: no branch `{name}`; the branches are: {}",
                    listed(&names)
                ));
            }
        }
    }
    let mut defaults = analysis.plan.sketch_defaults();
    for s in default {
        let Some((name, value)) = s.split_once('=') else {
            return Err(format!("`--default {s}`: expected NAME=VALUE"));
        };
        let defaults_of = &analysis.plan.defaults;
        let Some(i) = defaults_of.iter().position(|d| d.name == name.trim()) else {
            let names: Vec<&str> = defaults_of.iter().map(|d| d.name.as_str()).collect();
            return Err(format!(
                "`--default {s}`: no default `{}`; the defaults are: {}",
                name.trim(),
                listed(&names)
            ));
        };
        let var = &defaults_of[i];
        let dim = if var.is_angle() {
            gcs_lang::expr::Dim::Angle
        } else {
            gcs_lang::expr::Dim::Length
        };
        match gcs_lang::parse::value_for(model, &var.name, dim, value) {
            Ok(v) => defaults[i] = v,
            Err(e) => return Err(format!("`--default {s}`: {e}")),
        }
    }
    Ok(Inputs {
        params,
        branches,
        defaults,
    })
}

/// Names joined by commas, or `(none)`.
fn listed(names: &[&str]) -> String {
    if names.is_empty() {
        "(none)".to_string()
    } else {
        names.join(", ")
    }
}

/// Which of `plan`'s branches `--branch NAME=INDEX` gives (by name, so that it holds for a
/// pruned plan too): those a solve never changes.
pub fn held(plan: &Plan, branch: &[String]) -> Vec<bool> {
    let given: BTreeSet<&str> = (branch.iter())
        .filter_map(|b| b.split_once('=').map(|(n, _)| n.trim()))
        .collect();
    (plan.branches.iter())
        .map(|b| given.contains(b.name.as_str()))
        .collect()
}

/// Solves `plan` over `scope` as `gcs solve` does: from the defaults given when `given`, else
/// (an iterated plan) the assembly that moves least from the sketch; on the branches given,
/// and where the constraints cannot be met on the sketch's, on the others nearest the sketch,
/// saying which it changed (never one `held`: given by `--branch`).
pub fn solve(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    (params, branches, defaults): (&[f64], &[usize], &[f64]),
    given: bool,
    held: &[bool],
) -> Result<Kept, SolveError> {
    gcs_compiler::solve_near_sketch(model, plan, scope, params, branches, held, defaults, given)
}

/// Why a solve failed, one message a line (without the `error: ` the command line puts before
/// each). A check that fails does not hide the others: with the plan run past them, every
/// inconsistent redundant constraint is said, then what stopped it.
pub fn failure(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    branches: Vec<usize>,
    e: &SolveError,
) -> Vec<String> {
    let audit = gcs_compiler::interp::audit(
        model,
        plan,
        params,
        defaults,
        &gcs_compiler::interp::Choice::Given(branches),
    );
    if audit.failed.iter().any(|f| f.error == *e) {
        (audit.failed.iter().chain(&audit.stopped))
            .map(|f| f.error.to_string())
            .collect()
    } else {
        vec![e.to_string()]
    }
}

/// `s` when `n` is not one.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// What `gcs` says of a model that did not load, after its diagnostics.
pub fn not_loaded(name: &str, diagnostics: &[gcs_lang::Diagnostic]) -> String {
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    format!(
        "could not load `{name}` due to {errors} previous error{}",
        plural(errors)
    )
}

/// What `gcs check` says of a model whose analysis found errors, after its diagnostics.
pub fn analysis_errors(name: &str, diagnostics: &[gcs_lang::Diagnostic]) -> String {
    let n = diagnostics.iter().filter(|d| d.is_error()).count();
    format!("`{name}` has {n} analysis error{}", plural(n))
}
