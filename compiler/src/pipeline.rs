//! The pipeline every caller uses: load a model, analyse it into a plan, choose each branch's
//! default, validate the plan, and report the model's problems. The build-script API, the
//! command line, the benchmark driver and the tests all go through here, so that every back
//! end (interpreter, code generator, explainer) receives a validated [`Plan`].
//!
//! ```text
//! bytes ─load─▶ Model ─analyse─▶ Analysis { plan, .. } ─▶ interp / codegen / explain
//!                       (degrees of freedom, branch defaults, validation)
//! ```

use crate::analysis::{self, Analysis};
use crate::plan::{Malformed, Plan};
use gcs_lang::{Diagnostic, Model, SourceFile};
use std::fmt;

/// A model that loaded, with its warnings.
#[derive(Debug)]
pub struct Loaded {
    /// The file.
    pub source: SourceFile,
    /// The model.
    pub model: Model,
    /// Its warnings (a model with errors does not load).
    pub diagnostics: Vec<Diagnostic>,
}

/// A model that did not load: its diagnostics, errors among them.
#[derive(Debug)]
pub struct Rejected {
    /// The file.
    pub source: SourceFile,
    /// Every diagnostic.
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses and resolves a model.
pub fn load(name: &str, bytes: &[u8]) -> Result<Loaded, Rejected> {
    let (source, model, diagnostics) = gcs_lang::load(name, bytes);
    match model {
        Some(model) => Ok(Loaded {
            source,
            model,
            diagnostics,
        }),
        None => Err(Rejected {
            source,
            diagnostics,
        }),
    }
}

/// Why a loaded model has no plan.
#[derive(Clone, Debug, PartialEq)]
pub enum AnalysisError {
    /// Its sketch cannot be read.
    Uncovered(analysis::Unreadable),
    /// The analysis produced a plan that breaks the plan's invariants: a bug in gcs.
    Malformed(Malformed),
}

impl fmt::Display for AnalysisError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnalysisError::Uncovered(why) => write!(f, "{why}"),
            AnalysisError::Malformed(m) => {
                write!(f, "internal error: {m} (a bug in gcs: please report it)")
            }
        }
    }
}

impl std::error::Error for AnalysisError {}

/// Analyses a model into a validated plan: degrees-of-freedom analysis, then each branch
/// variable's default from the sketch (the plan run on the sketch, taking at each
/// intersection the root nearest to where the sketch has the moving feature), then the plan's
/// invariants, and that only the constraints the analysis reports unsolved (or recorded) are
/// left without a step.
pub fn analyse(model: &Model) -> Result<Analysis, AnalysisError> {
    let mut analysis = analysis::analyse(model, moving_checks, crate::interp::sketch_values)
        .map_err(AnalysisError::Uncovered)?;
    choose_branch_defaults(model, &mut analysis.plan);
    choose_iteration_modes(model, &mut analysis.plan);
    validate(model, &analysis).map_err(AnalysisError::Malformed)?;
    Ok(analysis)
}

/// For each step of `plan` (defaults, no iterations yet), whether a run-time check's residual
/// or an `Onto`'s gap moves with the defaults: the plan run on the sketch (its branches and
/// defaults' sketch values), then with every default moved a little at once, twice (random
/// signs, two sizes). A residual that stays within rounding of its sketch value both times
/// depends on none of them. `None` for every step when a run fails.
fn moving_checks(model: &Model, plan: &Plan) -> Vec<Option<bool>> {
    use gcs_runtime::tol::{PROBE_MOVE, PROBE_STILL};
    let mut out = vec![None; plan.steps.len()];
    if plan.defaults.is_empty() {
        return out;
    }
    let (chosen, reached) = crate::interp::sketch_choices(model, plan);
    let choice = crate::interp::Choice::Given(chosen.iter().map(|b| b.unwrap_or(0)).collect());
    let sketch: Vec<f64> = (reached.iter()).map(|v| v.unwrap_or(0.0)).collect();
    let at = |defaults: &[f64]| crate::interp::residuals_at(model, plan, defaults, &choice);
    let Ok((base, scale)) = at(&sketch) else {
        return out;
    };
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut moved = |size: f64| -> Vec<f64> {
        (sketch.iter())
            .map(|x| {
                let sign = if crate::families::xorshift(&mut seed) & 1 == 0 {
                    1.0
                } else {
                    -1.0
                };
                x + sign * size * (1.0 + x.abs())
            })
            .collect()
    };
    let (small, large) = (moved(PROBE_MOVE), moved(3.0 * PROBE_MOVE));
    let (Ok((a, _)), Ok((b, _))) = (at(&small), at(&large)) else {
        return out;
    };
    if a.len() != base.len() || b.len() != base.len() {
        return out;
    }
    for ((&(i, r0), &(_, ra)), &(_, rb)) in base.iter().zip(&a).zip(&b) {
        // Only rounding: a residual that moves at all, however little (near a tangency), is
        // an error its default can close.
        let still = |r: f64| (r - r0).abs() <= PROBE_STILL * (1.0 + scale);
        out[i] = Some(!(still(ra) && still(rb)));
    }
    out
}

/// Sets each branch variable's default to the sketch's branch, and each default's sketch
/// value to the one that moves nothing on the sketch (least motion). A branch whose
/// intersection the run on the sketch does not reach keeps 0, and is not the sketch's
/// ([`crate::plan::BranchVar::from_sketch`]).
fn choose_branch_defaults(model: &Model, plan: &mut Plan) {
    let (chosen, reached) = crate::interp::sketch_choices(model, plan);
    for (b, index) in plan.branches.iter_mut().zip(chosen) {
        b.from_sketch = index.is_some();
        if let Some(i) = index {
            b.default = i;
        }
    }
    for (d, value) in plan.defaults.iter_mut().zip(reached) {
        if let Some(x) = value.filter(|x| x.is_finite()) {
            d.sketch = x;
        }
    }
}

/// Each iteration's assembly mode, which a solve from the sketch keeps: the orientation of its
/// root in the sketch's assembly, the one that moves the sketch least at the model's params
/// on the branches just chosen (DESIGN, "Which assembly an iterated plan returns"): the sketch
/// itself where it is drawn assembled, the nearest assembly where it is drawn off.
fn choose_iteration_modes(model: &Model, plan: &mut Plan) {
    if plan.iterations.is_empty() {
        return;
    }
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let params = model.default_params();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let sketch = plan.sketch_defaults();
    let Ok(assembly) = crate::all::least_motion(model, plan, &scope, &params, &branches, &sketch)
    else {
        return;
    };
    let at: Vec<f64> = assembly.defaults.iter().map(|(_, v)| *v).collect();
    let modes = crate::interp::modes_at(model, plan, &params, &at, &branches);
    let iterated: Vec<usize> = (plan.iterations.iter())
        .flat_map(|it| it.defaults.iter().map(|d| d.0 as usize))
        .collect();
    for d in iterated {
        plan.defaults[d].assembled = at.get(d).copied();
    }
    for (it, mode) in plan.iterations.iter_mut().zip(modes) {
        // Several angles turning one body (a rotation's three turns) reach each pose by two
        // triples, whose Jacobians' determinants have opposite signs (the two charts differ
        // by a reflection of the middle angle): there the orientation names no mode.
        let geoms: Vec<_> = (it.defaults.iter())
            .filter_map(|d| plan.defaults[d.0 as usize].geom)
            .collect();
        let one_chart = (geoms.iter().enumerate()).all(|(i, g)| !geoms[..i].contains(g));
        it.mode = mode.filter(|_| one_chart);
    }
}

/// The plan's invariants, and its coverage against the analysis's report.
fn validate(model: &Model, analysis: &Analysis) -> Result<(), Malformed> {
    let plan = &analysis.plan;
    let mut errors = match plan.validate(model) {
        Ok(()) => Vec::new(),
        Err(Malformed(errors)) => errors,
    };
    let waiting: Vec<_> = (analysis.unsolved.iter().map(|u| u.constraint))
        .chain(analysis.recorded.iter().copied())
        .collect();
    for c in plan.unsatisfied(model) {
        if !waiting.contains(&c) {
            let name = &model.constraints[c].name;
            errors.push(format!(
                "constraint {name} is neither satisfied nor checked"
            ));
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(Malformed(errors))
    }
}

/// A model through the whole pipeline.
#[derive(Debug)]
pub struct Compiled {
    /// The file.
    pub source: SourceFile,
    /// The model.
    pub model: Model,
    /// Its analysis, with the validated plan.
    pub analysis: Analysis,
    /// The model's warnings, then the analysis's problems (constraints without a plan, geoms
    /// left free, constraints that conflict at the default params), then names that would
    /// become one identifier of the generated solver.
    pub diagnostics: Vec<Diagnostic>,
}

impl Compiled {
    /// Whether a diagnostic is an error: then the model cannot be solved.
    pub fn has_errors(&self) -> bool {
        gcs_lang::diagnostic::has_errors(&self.diagnostics)
    }
}

/// Why a model did not get through the pipeline.
#[derive(Debug)]
pub enum CompileError {
    /// It did not load.
    Load(Rejected),
    /// It loaded, but has no plan.
    Analysis(Box<Unanalysed>),
}

/// A model that loaded but has no plan.
#[derive(Debug)]
pub struct Unanalysed {
    /// The file.
    pub source: SourceFile,
    /// The model.
    pub model: Model,
    /// Its warnings.
    pub diagnostics: Vec<Diagnostic>,
    /// Why it has no plan.
    pub error: AnalysisError,
}

/// How many constraints make it worth checking names on a thread of their own while the
/// problems are reported (each takes about a microsecond a constraint).
const PARALLEL_REPORTS: usize = 10_000;

/// Loads and analyses a model, and reports its problems.
pub fn compile(name: &str, bytes: &[u8]) -> Result<Compiled, CompileError> {
    let loaded = load(name, bytes).map_err(CompileError::Load)?;
    match analyse(&loaded.model) {
        Ok(analysis) => {
            let mut diagnostics = loaded.diagnostics;
            let (model, plan) = (&loaded.model, &analysis.plan);
            // Both only read the model and the plan: a large model has them on two threads.
            let (problems, clashes) = if model.constraints.len() < PARALLEL_REPORTS {
                (
                    crate::report::problems(model, &analysis),
                    crate::codegen::name_clashes(model, plan),
                )
            } else {
                std::thread::scope(|scope| {
                    let clashes = scope.spawn(|| crate::codegen::name_clashes(model, plan));
                    let problems = crate::report::problems(model, &analysis);
                    let clashes = clashes
                        .join()
                        .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                    (problems, clashes)
                })
            };
            diagnostics.extend(problems);
            diagnostics.extend(clashes);
            Ok(Compiled {
                source: loaded.source,
                model: loaded.model,
                analysis,
                diagnostics,
            })
        }
        Err(error) => Err(CompileError::Analysis(Box::new(Unanalysed {
            source: loaded.source,
            model: loaded.model,
            diagnostics: loaded.diagnostics,
            error,
        }))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compiles_a_model_into_a_validated_plan_with_the_sketch_branches() {
        let text = include_str!("../../examples/fourbar.gcs");
        let c = compile("fourbar.gcs", text.as_bytes()).expect("compiles");
        assert!(!c.has_errors(), "{:?}", c.diagnostics);
        assert_eq!(c.analysis.plan.validate(&c.model), Ok(()));
        let elbow = &c.analysis.plan.branches[0];
        assert_eq!((elbow.name.as_str(), elbow.default), ("elbow", 0));
    }

    #[test]
    fn a_model_that_does_not_load_says_why_and_a_3d_one_is_analysed() {
        let Err(CompileError::Load(r)) = compile("bad.gcs", b"space 2d;\ncoincident(A, B);\n")
        else {
            panic!("loads")
        };
        assert!(gcs_lang::diagnostic::has_errors(&r.diagnostics));
        let text = include_str!("../../examples/brick.gcs");
        let Ok(c) = compile("brick.gcs", text.as_bytes()) else {
            panic!("the brick is not analysed")
        };
        assert!(!c.has_errors());
        assert_eq!(c.analysis.plan.validate(&c.model), Ok(()));
    }
}
