//! The one diagnostic type of gcs, and its rendering with codespan-reporting.
//!
//! Every stage reports problems as [`Diagnostic`]s and collects all of them rather than stopping
//! at the first. Library crates never print: the CLI renders, with colour when it can; tests
//! render to plain text with [`render_plain`]. Both show what [`shown`] keeps: every error, and
//! the first [`SHOWN_PER_KIND`] warnings of each kind with the rest counted in one line.

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
    /// A word where a unit would stand (`25 mm`, `1.5in`) that is not one: the language's
    /// units, said once for the parser and the resolver.
    pub fn unknown_unit(span: Span, word: &str) -> Self {
        Diagnostic::error(span, format!("unknown unit `{word}`"))
            .with_label("not a unit of the language")
            .with_note(
                "the units are `deg` and `rad`, on angles; a length is a plain number, in the \
                 model's own unit",
            )
    }

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

/// Renders diagnostics as plain text (no colour), in the order given, as rustc would print them:
/// what [`shown`] keeps, then a line for each kind of warning it counted instead.
pub fn render_plain(source: &SourceFile, diagnostics: &[Diagnostic]) -> String {
    let file = codespan_file(source);
    let config = term::Config::default();
    let mut out = String::new();
    let shown = shown(diagnostics);
    for d in shown.diagnostics {
        match term::emit_into_string(&config, &file, &d.to_codespan()) {
            Ok(s) => out.push_str(&s),
            // A span outside the file is a bug of ours; still show the message.
            Err(_) => {
                out.push_str(&format!("error: {}\n", d.message));
            }
        }
    }
    for e in &shown.elided {
        match term::emit_into_string(&config, &file, &e.to_codespan()) {
            Ok(s) => out.push_str(&s),
            Err(_) => out.push_str(&format!("warning: {}\n", e.message())),
        }
    }
    out
}

/// How many warnings of one kind are shown before the rest are counted instead.
pub const SHOWN_PER_KIND: usize = 10;

/// The diagnostics worth rendering from a list, and the warnings counted instead of shown.
///
/// A model can earn a warning per declaration: a table of 170,000 params, most of them unused,
/// printed 1.2 million lines that hid everything else. So only the first [`SHOWN_PER_KIND`]
/// warnings of each kind (see [`kind`]) are shown; the others are counted, a line per kind.
/// Errors are never left out: each stops the model from compiling and is fixed where it
/// stands, which a count cannot point to, and the resolver already drops the cascades that
/// would repeat one.
#[derive(Debug)]
pub struct Shown<'a> {
    /// What to render, in the order given.
    pub diagnostics: Vec<&'a Diagnostic>,
    /// The warnings left out, a count per kind, in the order the kinds first appear.
    pub elided: Vec<Elided>,
}

/// Warnings of one kind left out of a rendering.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Elided {
    /// Their kind, as [`kind`] writes it: `param `…` is never used`.
    pub kind: String,
    /// How many are left out.
    pub count: usize,
}

impl Elided {
    /// The line that stands for them: `169,990 more warnings like "param `…` is never used"`.
    pub fn message(&self) -> String {
        let plural = if self.count == 1 { "" } else { "s" };
        format!(
            "{} more warning{plural} like \"{}\" not shown",
            grouped(self.count),
            self.kind
        )
    }

    /// The codespan-reporting form of the line, a warning without a span.
    pub fn to_codespan(&self) -> cs::Diagnostic<()> {
        cs::Diagnostic::warning().with_message(self.message())
    }
}

/// The kind of a diagnostic, for counting repeats: its message with every `quoted` part (the
/// names and values it is about) replaced by `…`, so that "param `a` is never used" and
/// "param `b` is never used" are one kind.
pub fn kind(message: &str) -> String {
    let parts: Vec<&str> = message.split('`').collect();
    let mut out = String::with_capacity(message.len());
    for (i, part) in parts.iter().enumerate() {
        if i > 0 {
            out.push('`');
        }
        // Odd parts lie between backquotes; a last one without its closing quote is kept.
        let quoted = i % 2 == 1 && i + 1 < parts.len();
        out.push_str(if quoted { "…" } else { part });
    }
    out
}

/// What of `diagnostics` to render: every error, and the first [`SHOWN_PER_KIND`] warnings of
/// each kind; the rest are counted in [`Shown::elided`].
pub fn shown(diagnostics: &[Diagnostic]) -> Shown<'_> {
    let mut seen: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    let mut order: Vec<String> = Vec::new();
    let mut kept = Vec::with_capacity(diagnostics.len().min(1024));
    for d in diagnostics {
        if d.is_error() {
            kept.push(d);
            continue;
        }
        let k = kind(&d.message);
        let n = seen.entry(k.clone()).or_insert(0);
        *n += 1;
        if *n <= SHOWN_PER_KIND {
            kept.push(d);
        } else if *n == SHOWN_PER_KIND + 1 {
            order.push(k);
        }
    }
    let elided = order
        .into_iter()
        .map(|k| {
            let count = seen[&k] - SHOWN_PER_KIND;
            Elided { kind: k, count }
        })
        .collect();
    Shown {
        diagnostics: kept,
        elided,
    }
}

/// A count with its thousands grouped by commas, as the docs write them: `169,990`.
fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn warning(message: &str) -> Diagnostic {
        Diagnostic::warning(Span::new(0, 1), message)
    }

    #[test]
    fn kinds_ignore_what_they_quote() {
        assert_eq!(kind("param `p1` is never used"), "param `…` is never used");
        assert_eq!(kind("`a` and `b` clash"), "`…` and `…` clash");
        assert_eq!(kind("no quotes"), "no quotes");
        assert_eq!(kind("an open `quote"), "an open `quote");
        assert_eq!(kind(""), "");
    }

    #[test]
    fn counts_group_thousands() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(169_990), "169,990");
        assert_eq!(grouped(1_234_567), "1,234,567");
    }

    #[test]
    fn repeated_warnings_are_counted_and_errors_all_shown() {
        let mut diags = Vec::new();
        for i in 0..25 {
            diags.push(warning(&format!("param `p{i}` is never used")));
            diags.push(Diagnostic::error(Span::new(0, 1), format!("bad `{i}`")));
        }
        diags.push(warning("something else"));
        let shown = shown(&diags);
        let errors = shown.diagnostics.iter().filter(|d| d.is_error()).count();
        assert_eq!(errors, 25);
        assert_eq!(shown.diagnostics.len(), 25 + SHOWN_PER_KIND + 1);
        assert_eq!(
            shown.elided,
            vec![Elided {
                kind: "param `…` is never used".to_string(),
                count: 15
            }]
        );
        assert_eq!(
            shown.elided[0].message(),
            "15 more warnings like \"param `…` is never used\" not shown"
        );
    }

    #[test]
    fn a_few_warnings_are_all_shown() {
        let diags: Vec<Diagnostic> = (0..SHOWN_PER_KIND)
            .map(|i| warning(&format!("param `p{i}` is never used")))
            .collect();
        let shown = shown(&diags);
        assert_eq!(shown.diagnostics.len(), SHOWN_PER_KIND);
        assert!(shown.elided.is_empty());
    }
}
