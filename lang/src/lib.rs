//! The `.gcs` language: grammar, syntax tree, name resolution into an immutable [`Model`], and
//! the diagnostics of every step.
//!
//! The pipeline is three plain functions: [`parse::parse`] (text to [`syntax::File`]),
//! [`resolve::resolve`] (syntax to [`Model`]) and [`load`], which runs both on a file's bytes.
//! Nothing here prints or exits; callers render [`Diagnostic`]s.

pub mod constraints;
pub mod diagnostic;
pub mod expr;
pub mod model;
pub mod parse;
pub mod resolve;
pub mod source;
pub mod syntax;

pub use diagnostic::{Diagnostic, Severity};
pub use model::Model;
pub use source::{SourceFile, Span};

/// Parses and resolves a file given as bytes. Returns the model (when there is no error) and
/// every diagnostic, warnings included. A file that is not UTF-8 or holds no statement is an
/// error with a span, like any other.
pub fn load(name: &str, bytes: &[u8]) -> (SourceFile, Option<Model>, Vec<Diagnostic>) {
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t.to_string(),
        Err(e) => {
            let at = e.valid_up_to();
            let source = SourceFile::new(name, String::from_utf8_lossy(bytes).into_owned());
            let bad_len = e.error_len().unwrap_or(1);
            let d = Diagnostic::error(Span::new(at, at + bad_len), "file is not valid UTF-8")
                .with_label(format!("invalid byte at offset {at}"))
                .with_note("gcs reads models as UTF-8 text");
            return (source, None, vec![d]);
        }
    };
    let source = SourceFile::new(name, text);
    let (file, mut diags) = parse::parse(source.text());
    let (model, more) = resolve::resolve(&source, &file, !diagnostic::has_errors(&diags));
    diags.extend(more);
    diags.sort_by_key(|d| (d.primary.span.start, d.primary.span.end));
    let model = if diagnostic::has_errors(&diags) {
        None
    } else {
        model
    };
    (source, model, diags)
}
