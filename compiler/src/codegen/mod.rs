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
//! a run-time check, all three from what `facts` knows at each step and the sketch's values
//! (`sketch`, `expr`); `scopes` keeps a long solve's scopes shallow; `writer` and
//! `names` spell the text; `format` runs rustfmt on it.

mod api;
mod context;
mod expr;
mod facts;
mod format;
mod names;
mod residual;
mod scopes;
mod sketch;
mod solve;
mod steps;
mod writer;

pub use format::format;
pub use names::{Clash, Namer};

use crate::plan::Plan;
use context::Context;
use gcs_lang::Model;
use writer::Writer;

/// The generated module for a model's plan, pruned to its `output` statements. The plan must
/// be valid, as the pipeline's are: a register no step defines is a bug in gcs, and panics
/// saying so rather than writing a made-up value.
pub fn generate(model: &Model, plan: &Plan) -> String {
    let (plan, scope) = crate::prune::prune(model, plan);
    let cx = Context::new(model, &plan, &scope);
    let mut w = Writer::default();
    header(&mut w, &cx.file);
    api::params(&mut w, &cx);
    api::branches(&mut w, &cx);
    api::defaults(&mut w, &cx);
    let layout = api::Layout::new(&cx);
    api::solution(&mut w, &cx, &layout);
    solve::solve(&mut w, &cx, &layout);
    w.out
}

/// The names of the model that become one identifier of the generated module's public API
/// (params, branch variables, defaults, accessors): each an error naming both, with their
/// spans. Without it the second would take a `_2` suffix, and a caller setting one field
/// could be setting the other constraint's branch.
pub fn name_clashes(model: &Model, plan: &Plan) -> Vec<gcs_lang::Diagnostic> {
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
            // `G.radius` and `S.length` name their geom's dimension.
            Public::Accessor => geom(name).or_else(|| geom(name.rsplit_once('.')?.0)),
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

/// The module's header comments and imports. No inner attributes or `//!` docs: the module must
/// be usable through `include!`.
fn header(w: &mut Writer, file: &str) {
    w.line(&format!(
        "// @generated by gcs from {file}. Do not edit: edit the model and regenerate."
    ));
    w.line("//");
    w.line(
        "// The solver's steps follow the model's assembly plan; `gcs explain` prints it in words.",
    );
    w.line("");
    w.line(&format!(
        "// Solver for `{file}`. Call `solve` with `Params`, `Branches` and `Defaults`, and read"
    ));
    w.line(
        "// the result through the accessors of `Solution`. It never panics and allocates nothing.",
    );
    w.line(
        "// A caller uses what it needs of this API: the setters and accessors allow dead code.",
    );
    w.line("");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::error::{ErrorKind, SolveError};");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::check;");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::frame::{direction_at, rotation_between2, rotation_between_units, rotation_from_x, rotation_from_x_unit, rotation_on_circle, rotation_on_circle_from, Frame2};");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::intersect2d;");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::locus2d::{self, Circle, Conic, Line, Sense};");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::nalgebra::{Point2, UnitComplex, Vector2};");
    w.line("");
}
