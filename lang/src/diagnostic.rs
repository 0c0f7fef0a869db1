//! The one diagnostic type of gcs, and its rendering with codespan-reporting.
//!
//! Every stage reports problems as [`Diagnostic`]s and collects all of them rather than stopping
//! at the first. Library crates never print: the CLI renders, with colour when it can; tests
//! render to plain text with [`render_plain`].

use crate::source::{SourceFile, Span};
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// Worth knowing; does not stop compilation.
    Warning,
    /// The model cannot be compiled.
    Error,
}

/// A span with a short message, pointing into the source.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What about it (may be empty).
    pub message: String,
}

/// A problem found in a model: a message, the span it is about, other spans that explain it,
/// and notes (for example the size of a conflict, or a suggestion).
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The headline, a sentence without a final period.
    pub message: String,
    /// The span the message is about.
    pub primary: Label,
    /// Related spans: the earlier declaration of a duplicate, the constraint a conflict fights.
    pub secondary: Vec<Label>,
    /// Further lines: why, by how much, how to fix it.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            primary: Label {
                span,
                message: String::new(),
            },
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(span, message)
        }
    }

    /// Sets the message under the primary span.
    pub fn with_label(mut self, message: impl Into<String>) -> Diagnostic {
        self.primary.message = message.into();
        self
    }

    /// Adds a secondary span.
    pub fn with_secondary(mut self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.secondary.push(Label {
            span,
            message: message.into(),
        });
        self
    }

    /// Adds a note.
    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Whether this is an error (rather than a warning).
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// The codespan-reporting form of this diagnostic, for a renderer at the edge.
    pub fn to_codespan(&self) -> cs::Diagnostic<()> {
        let head = match self.severity {
            Severity::Error => cs::Diagnostic::error(),
            Severity::Warning => cs::Diagnostic::warning(),
        };
        let mut labels = vec![cs::Label::primary((), self.primary.span.range())
            .with_message(self.primary.message.clone())];
        labels.extend(
            self.secondary
                .iter()
                .map(|l| cs::Label::secondary((), l.span.range()).with_message(l.message.clone())),
        );
        head.with_message(self.message.clone())
            .with_labels(labels)
            .with_notes(self.notes.clone())
    }
}

/// Whether any of `diagnostics` is an error.
pub fn has_errors(diagnostics: &[Diagnostic]) -> bool {
    diagnostics.iter().any(Diagnostic::is_error)
}

/// The codespan file for a source, shared by renderers.
pub fn codespan_file(source: &SourceFile) -> SimpleFile<&str, &str> {
    SimpleFile::new(source.name(), source.text())
}

/// Renders diagnostics as plain text (no colour), in the order given, as rustc would print them.
pub fn render_plain(source: &SourceFile, diagnostics: &[Diagnostic]) -> String {
    let file = codespan_file(source);
    let config = term::Config::default();
    let mut out = String::new();
    for d in diagnostics {
        match term::emit_into_string(&config, &file, &d.to_codespan()) {
            Ok(s) => out.push_str(&s),
            // A span outside the file is a bug of ours; still show the message.
            Err(_) => {
                out.push_str(&format!("error: {}\n", d.message));
            }
        }
    }
    out
}
