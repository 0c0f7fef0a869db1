//! The code generator: a plan as one Rust module that depends on the runtime crate alone.
//!
//! The module has `Params`, `Branches` and `Defaults` (each `Default` from the file), a
//! `Solution` with accessors named after the model, and `solve`, a straight line of the plan's
//! steps with a comment quoting, for each action, the constraint it satisfies and its
//! `file:line`. Every identifier comes from the model's names through one [`Namer`]
//! (keyword-safe, never an index); the text is written through a small indenting writer, so it is
//! deterministic and rustfmt-clean. `solve` never panics and allocates nothing: every failure is
//! a `SolveError` built from string literals.
//!
//! The pieces: `context` holds what all of them read (the model, the pruned plan, field
//! names, facts about the plan); `api` writes the structs a caller touches; `solve` writes
//! the skeleton of `solve`, `steps` each step of the plan in it, `residual` the residual of
//! a run-time check, all three from what `facts` knows at each step (`features`: what a step
//! reads of the frames) and the sketch's values (`sketch`, `expr`); `ledger` records each local
//! declared and read as the code is written, which `scopes` asks to keep a long solve's scopes
//! shallow (generated text is never read back); `writer` and
//! `names` spell the text; `format` runs rustfmt on it. `spatial` writes a 3d model's sketch
//! and steps under the same skeleton; `all` writes `solve_all`; `tabled` lays a large model's
//! solve out as functions and tables ([`Form`]). Each type lives in one module and modules
//! import one another in one direction: `impl Solve` is spread over `features`, `steps`,
//! `spatial` and `residual`, which import `solve`, never the reverse.
//!
//! [`generate`] prunes the plan to the model's outputs first. [`name_clashes`], the model's
//! names that would become one public identifier, runs for every command (the pipeline calls
//! it), so a cheap test over a superset of the public names (every param, branch, default and
//! geom name) decides first whether the exact check, which builds the pruned module's layout,
//! can find anything. No inner attributes are written, so the module works through
//! `include!`; the setters and accessors allow dead code, so that a caller that reads one
//! output builds under `deny(warnings)`.

mod all;
mod api;
mod context;
mod expr;
mod facts;
mod features;
mod fork;
mod format;
mod ledger;
mod lift;
mod names;
mod residual;
mod scopes;
mod sketch;
mod sketch3;
mod solve;
mod space;
mod spatial;
mod steps;
mod tabled;
mod writer;

pub use format::{format, Module};
pub use names::{Clash, Namer};
pub use tabled::Untabled;

use crate::plan::Plan;
use context::Context;
use gcs_lang::Model;
use writer::Writer;

/// The generated module for a model's plan, pruned to its `output` statements. The plan must
/// be valid, as the pipeline's are: a register no step defines is a bug in gcs, and panics
/// saying so rather than writing a made-up value.
pub fn generate(model: &Model, plan: &Plan) -> Module {
    let (plan, scope) = crate::prune::prune(model, plan);
    let cx = Context::new(model, &plan, &scope);
    let layout = api::Layout::new(&cx);
    auto(&cx, &layout)
}

/// How the generated module lays out `solve`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// Flat unless the flat solve's steps would be [`TABLED_LINES`] lines or more (a chain
    /// of about 600 four-bars, a closed profile of about 180 arcs), tabled then.
    Auto,
    /// One straight `solve`, a group of steps after another, each with its comment.
    Flat,
    /// Each piece of the solve a call of the function of its shape with its row of data (see
    /// `tabled`); an error ([`Untabled`]) where the plan does not allow it (outer iterations).
    Tabled,
}

/// The length of the flat solve's steps, in lines, from which [`Form::Auto`] writes a
/// tabled module.
pub const TABLED_LINES: usize = tabled::TABLED_LINES;

/// [`generate`] in the given form; `Form::Tabled` says why when the plan cannot be laid out
/// as tables.
pub fn generate_as(model: &Model, plan: &Plan, form: Form) -> Result<Module, Untabled> {
    let (plan, scope) = crate::prune::prune(model, plan);
    let cx = Context::new(model, &plan, &scope);
    let layout = api::Layout::new(&cx);
    match form {
        Form::Auto => Ok(auto(&cx, &layout)),
        Form::Flat => Ok(flat(&cx, &layout)),
        Form::Tabled => {
            let module = tabled::module(&cx, &layout, 0)?;
            Ok(module.unwrap_or_else(|| flat(&cx, &layout)))
        }
    }
}

/// Tabled when the flat solve's steps would be [`TABLED_LINES`] lines or more, else flat.
fn auto(cx: &Context<'_>, layout: &api::Layout) -> Module {
    if cx.plan.steps.len() >= tabled::TABLED_STEPS {
        if let Ok(Some(module)) = tabled::module(cx, layout, TABLED_LINES) {
            return module;
        }
    }
    flat(cx, layout)
}

/// The flat module: one straight `solve`.
fn flat(cx: &Context<'_>, layout: &api::Layout) -> Module {
    let mut w = Writer::default();
    api::header(&mut w, &cx.file, cx.space);
    api::params(&mut w, cx);
    api::branches(&mut w, cx);
    api::defaults(&mut w, cx);
    api::solution(&mut w, cx, layout);
    solve::solve(&mut w, cx, layout);
    w.line("");
    all::solve_all(&mut w, cx, layout);
    Module::code(w.out)
}

/// The names of the model that become one identifier of the generated module's public API
/// (params, branch variables, defaults, accessors): each an error naming both, with their
/// spans. Without it the second would take a `_2` suffix, and a caller setting one field
/// could be setting the other constraint's branch.
pub fn name_clashes(model: &Model, plan: &Plan) -> Vec<gcs_lang::Diagnostic> {
    if !may_clash(model, plan) {
        return Vec::new();
    }
    let (plan, scope) = crate::prune::prune(model, plan);
    let cx = Context::new(model, &plan, &scope);
    let layout = api::Layout::new(&cx);
    let accessors = api::accessors(&cx, &layout).1;
    let clashes = cx.clashes.iter().cloned().chain(
        accessors
            .into_iter()
            .map(|c| (context::Public::Accessor, c)),
    );
    clashes
        .map(|(public, c)| clash_diagnostic(model, public, &c))
        .collect()
}

/// Whether any two names of the model could become one public identifier: a cheap test over a
/// superset of the names each public namer sees (all params, all branches and defaults before
/// pruning, every geom's accessor texts), so that the exact check, which builds the pruned
/// module's layout, runs only when it may find something. Sound because a namer whose texts
/// all have distinct identifiers, none of them reserved, never suffixes and never clashes, and
/// neither does any subset of its texts.
fn may_clash(model: &Model, plan: &Plan) -> bool {
    fn distinct<'t>(texts: impl Iterator<Item = &'t str>, reserved: &[&str]) -> bool {
        let mut seen: std::collections::HashSet<String> =
            reserved.iter().map(|r| r.to_string()).collect();
        let mut texts_seen = std::collections::HashSet::new();
        texts.into_iter().all(|t| {
            // The same text twice is one name (a repeat takes `_2` and may then meet a text
            // that snakes to that suffix): let the exact check decide.
            texts_seen.insert(t) && seen.insert(Namer::snake(t))
        })
    }
    let params = model.params.iter().map(|(_, p)| p.name.as_str());
    let branches = plan.branches.iter().map(|b| b.name.as_str());
    let defaults = plan.defaults.iter().map(|d| d.name.as_str());
    let accessors: Vec<String> = api::accessor_texts(model).collect();
    !(distinct(params, &[])
        && distinct(branches, &[])
        && distinct(defaults, &[])
        && distinct(
            accessors.iter().map(String::as_str),
            &api::RESERVED_ACCESSORS,
        ))
}

/// The diagnostic of one clash.
fn clash_diagnostic(model: &Model, public: context::Public, c: &Clash) -> gcs_lang::Diagnostic {
    use context::Public;
    let span = |name: &str| -> gcs_lang::Span {
        let geom = |n: &str| model.geom_named(n).map(|g| model.geoms[g].span);
        let found = match public {
            Public::Param => model.param_named(name).map(|p| model.params[p].span),
            Public::Branch => (model.constraints.iter())
                .find(|(_, k)| k.name == name)
                .map(|(_, k)| k.span),
            // `G.radius` and `S.length` name their geom's dimension; `q1.angle` is the output
            // that names a joint's value.
            Public::Accessor => geom(name)
                .or_else(|| geom(name.rsplit_once('.')?.0))
                .or_else(|| Some(model.outputs.iter().find(|o| o.path == name)?.span)),
            Public::Default => None,
        };
        found.unwrap_or_default()
    };
    let (what, place) = match public {
        Public::Param => ("param", "a field of `Params`"),
        Public::Branch => ("branch variable", "a field of `Branches`"),
        Public::Default => ("default", "a field of `Defaults`"),
        Public::Accessor => ("value", "an accessor of `Solution`"),
    };
    let id = &c.identifier;
    let d = match &c.first {
        Some(first) => gcs_lang::Diagnostic::error(
            span(&c.second),
            format!(
                "the {what}s `{first}` and `{}` both become `{id}`, {place}, in the generated solver",
                c.second
            ),
        )
        .with_label(format!("`{}` becomes `{id}`", c.second))
        .with_secondary(span(first), format!("`{first}` becomes `{id}` too")),
        None => gcs_lang::Diagnostic::error(
            span(&c.second),
            format!(
                "the {what} `{}` becomes `{id}`, which the generated solver's API already has",
                c.second
            ),
        )
        .with_label(format!("`{}` becomes `{id}`", c.second)),
    };
    d.with_note(
        "a name becomes its snake case in generated code (lower case, `_` for anything else): \
         rename one so that each is its own identifier",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pre-check is sound (every model with a clash may clash) and useful (no model of the
    /// examples, which have none, pays for the exact check).
    #[test]
    fn the_clash_pre_check_passes_exactly_the_models_without_clashes() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        let mut models = Vec::new();
        for dir in ["examples", "tests/models"] {
            for entry in std::fs::read_dir(format!("{root}/{dir}")).expect("directory") {
                let path = entry.expect("entry").path();
                if path.extension().is_some_and(|e| e == "gcs") {
                    models.push((
                        path.display().to_string(),
                        std::fs::read(&path).expect("a model"),
                    ));
                }
            }
        }
        let clashing = [
            "space 2d;\nparam k = 1;\nparam K = 2;\nfixed point A = (0, 0);\n",
            "space 2d;\nfixed point A = (0, 0);\nfixed point a = (1, 0);\n",
            "space 2d;\nfixed point points = (0, 0);\n",
            "space 2d;\nfixed circle c = center (0, 0) radius 1;\nfixed point c_radius = (0, 0);\n",
            "space 2d;\nparam Self = 1;\nparam self_ = 2;\n",
        ];
        models.extend(
            clashing
                .iter()
                .map(|t| ("inline".to_string(), t.as_bytes().to_vec())),
        );
        let mut exact_runs = 0;
        for (name, bytes) in &models {
            let Ok(loaded) = crate::pipeline::load(name, bytes) else {
                continue;
            };
            let Ok(analysis) = crate::pipeline::analyse(&loaded.model) else {
                continue;
            };
            let (model, plan) = (&loaded.model, &analysis.plan);
            let may = may_clash(model, plan);
            let (pruned, scope) = crate::prune::prune(model, plan);
            let cx = Context::new(model, &pruned, &scope);
            let layout = api::Layout::new(&cx);
            let exact = !cx.clashes.is_empty() || !api::accessors(&cx, &layout).1.is_empty();
            assert!(may || !exact, "{name}: a clash the pre-check missed");
            assert_eq!(
                may, exact,
                "{name}: the pre-check says {may}, the exact check {exact}"
            );
            exact_runs += usize::from(may);
        }
        assert_eq!(exact_runs, clashing.len());
    }
}
