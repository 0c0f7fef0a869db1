//! The `.gcs` language: grammar, syntax tree, name resolution into an immutable [`Model`], and
//! the diagnostics of every step.
//!
//! The pipeline is three plain functions: [`parse::parse`] (text to [`syntax::File`]),
//! [`resolve::resolve`] (syntax to [`Model`]) and [`load`], which runs both on a file's bytes.
//! Nothing here prints or exits; callers render [`Diagnostic`]s.

pub mod constraints;
pub mod diagnostic;
pub mod expr;
mod fast;
pub mod model;
pub mod parse;
pub mod resolve;
pub mod source;
pub mod syntax;

pub use diagnostic::{Diagnostic, Severity};
pub use model::Model;
pub use source::{SourceFile, Span};

/// The diagnostic for bytes that are not text at all (a NUL byte, or an invalid byte on a line
/// too long to show), given the offset of the first invalid UTF-8 byte; `None` for text with
/// a stray byte, whose line is worth showing.
fn binary(bytes: &[u8], bad: usize) -> Option<Diagnostic> {
    const LONGEST_SHOWN_LINE: usize = 400;
    let line_start = bytes[..bad]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line_end = bytes[bad..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| bad + i);
    let nul = bytes.iter().position(|&b| b == 0);
    let label = match nul {
        Some(at) => format!("a NUL byte at offset {at}"),
        None if line_end - line_start > LONGEST_SHOWN_LINE => {
            format!(
                "an invalid UTF-8 byte at offset {bad}, on a line of {} bytes",
                line_end - line_start
            )
        }
        None => return None,
    };
    Some(
        Diagnostic::error(Span::empty(0), "this is a binary file, not a gcs model")
            .with_label(label)
            .with_note("gcs reads models as UTF-8 text"),
    )
}

/// Parses and resolves a file given as bytes. Returns the model (when there is no error) and
/// every diagnostic, warnings included. A file that is not UTF-8 or holds no statement is an
/// error with a span, like any other.
pub fn load(name: &str, bytes: &[u8]) -> (SourceFile, Option<Model>, Vec<Diagnostic>) {
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t.to_string(),
        Err(e) => {
            let at = e.valid_up_to();
            if let Some(d) = binary(bytes, at) {
                // Echo none of it: the diagnostic stands on an empty text.
                return (SourceFile::new(name, String::new()), None, vec![d]);
            }
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
    drop_large(file);
    diags.extend(more);
    diags.sort_by_key(|d| (d.primary.span.start, d.primary.span.end));
    let model = if diagnostic::has_errors(&diags) {
        None
    } else {
        model
    };
    (source, model, diags)
}

/// Frees a large syntax tree on another thread: a million small allocations take a tenth of a
/// second that the analysis need not wait for. A small tree is freed here.
fn drop_large(file: syntax::File) {
    const LARGE: usize = 10_000;
    if file.statements.len() < LARGE {
        return;
    }
    let spawned = std::thread::Builder::new().spawn(move || drop(file));
    // Without a thread (the system refuses one), the tree came back dropped with the error.
    drop(spawned);
}
