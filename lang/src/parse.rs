//! Source text to syntax tree: split into statements, parse each (a plain one by `fast.rs`,
//! any other with pest), build the tree.
//!
//! Splitting first (at `;` and at the `}` that closes a body) lets one syntax error be reported
//! without hiding the next, and lets the splitter catch what pest reports badly: an unterminated
//! block comment, an unbalanced brace, nesting too deep for a bounded parser.

use crate::diagnostic::Diagnostic;
use crate::expr::Dim;
use crate::source::Span;
use crate::syntax::*;
use pest::iterators::{Pair, Pairs};
use pest::pratt_parser::{Assoc, Op, PrattParser};
use pest::Parser as _;
use std::sync::OnceLock;

#[derive(pest_derive::Parser)]
#[grammar = "grammar.pest"]
struct GcsParser;

/// How deep parentheses may nest in one statement. Deeper input is refused with a diagnostic
/// before the parser, whose recursion it bounds, ever sees it.
pub const MAX_NESTING: usize = 48;

/// How many operators one declaration (or one body member) may hold. This bounds the recursion
/// of the parser and of every later walk over an expression tree.
pub const MAX_OPERATORS: usize = 1000;

/// How deep an expression tree may grow.
pub const MAX_EXPR_DEPTH: usize = 200;

/// Parses a whole file. Statements with syntax errors are reported and left out of the tree.
pub fn parse(text: &str) -> (File, Vec<Diagnostic>) {
    parse_with(text, true)
}

/// [`parse`], with or without the fast path for plain statements (the tests compare both).
pub(crate) fn parse_with(text: &str, fast: bool) -> (File, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let chunks = split(text, &mut diags);
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(chunks.len() / STATEMENTS_PER_THREAD)
        .max(1);
    let mut file = File::default();
    if threads == 1 {
        parse_chunks(text, &chunks, fast, &mut file, &mut diags);
        return (file, diags);
    }
    // Statements parse independently (the splitter made them so), and each thread takes a
    // contiguous run of them: joined in order, the statements and diagnostics are exactly
    // those of one thread.
    let per_thread = chunks.len().div_ceil(threads);
    let parts: Vec<(File, Vec<Diagnostic>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = chunks
            .chunks(per_thread)
            .map(|run| {
                scope.spawn(move || {
                    let mut part = (File::default(), Vec::new());
                    parse_chunks(text, run, fast, &mut part.0, &mut part.1);
                    part
                })
            })
            .collect();
        (handles.into_iter())
            .map(|h| {
                h.join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .collect()
    });
    for (part, part_diags) in parts {
        file.statements.extend(part.statements);
        diags.extend(part_diags);
    }
    (file, diags)
}

/// How many statements make it worth another thread: pest takes about 10 µs a statement, and a
/// thread about 20 µs to start.
const STATEMENTS_PER_THREAD: usize = 2048;

/// Parses the statements in `chunks`, in order.
fn parse_chunks(
    text: &str,
    chunks: &[Span],
    fast: bool,
    file: &mut File,
    diags: &mut Vec<Diagnostic>,
) {
    for &chunk in chunks {
        match fast.then(|| crate::fast::statement(text, chunk)).flatten() {
            Some(s) => file.statements.push(s),
            None => parse_chunk(text, chunk, file, diags),
        }
    }
}

/// Parses the statement(s) in `span`, recovering from a missing `;` by reporting it and parsing
/// the rest as a new statement.
fn parse_chunk(text: &str, mut span: Span, file: &mut File, diags: &mut Vec<Diagnostic>) {
    loop {
        let chunk = &text[span.range()];
        match GcsParser::parse(Rule::single, chunk) {
            Ok(mut pairs) => {
                let single = pairs.next();
                if let Some(stmt) = single.and_then(|s| s.into_inner().next()) {
                    let b = Builder {
                        offset: span.start,
                        diags,
                    };
                    if let Some(s) = b.statement(stmt) {
                        file.statements.push(s);
                    }
                }
                return;
            }
            Err(err) => {
                if let Some(d) = non_ascii(text, span).or_else(|| misspelled_keyword(text, span)) {
                    diags.push(d);
                    return;
                }
                let (diag, resume) = syntax_error(text, span, &err);
                diags.push(diag);
                match resume {
                    Some(at) if at > span.start && at < span.end => span = Span::new(at, span.end),
                    _ => return,
                }
            }
        }
    }
}

/// Turns a pest error into a diagnostic in the user's words. Returns where to resume parsing
/// when the error is a missing `;` before what looks like a new statement.
fn syntax_error(
    text: &str,
    chunk: Span,
    err: &pest::error::Error<Rule>,
) -> (Diagnostic, Option<usize>) {
    let pos = match err.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    } + chunk.start;
    let positives: Vec<Rule> = match &err.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => positives.clone(),
        pest::error::ErrorVariant::CustomError { .. } => Vec::new(),
    };
    let found = describe_token(text, pos, chunk.end);
    let found_span = token_span(text, pos, chunk.end);

    if positives.contains(&Rule::semi) {
        // Point just after the previous token, as rustc does.
        let before = text[chunk.start..pos].trim_end_matches(is_space_or_comment_char);
        let at = chunk.start + before.len();
        if let Some(d) = unknown_unit(text, before, found_span, chunk.end) {
            return (d, None);
        }
        let mut d = Diagnostic::error(Span::empty(at), format!("expected `;`, found {found}"))
            .with_label("add `;` here");
        if found_span.end > found_span.start {
            d = d.with_secondary(found_span, "unexpected here");
        }
        let resume = starts_statement(&text[pos..chunk.end]).then_some(pos);
        return (d, resume);
    }

    // A missing `,` or `)` says more than the operators that could also continue.
    let structural = positives
        .iter()
        .any(|r| matches!(r, Rule::comma | Rule::close));
    let mut wanted: Vec<&'static str> = Vec::new();
    for r in positives
        .iter()
        .filter(|r| !structural || matches!(r, Rule::comma | Rule::close))
    {
        let w = describe_rule(*r);
        if !wanted.contains(&w) {
            wanted.push(w);
        }
    }
    let message = match wanted.as_slice() {
        [] => format!("unexpected {found}"),
        [one] => format!("expected {one}, found {found}"),
        many => {
            let (last, rest) = many.split_last().unwrap_or((&"", &[]));
            format!("expected {} or {last}, found {found}", rest.join(", "))
        }
    };
    let span = if found_span.end > found_span.start {
        found_span
    } else {
        Span::empty(pos)
    };
    let mut d = Diagnostic::error(span, message);
    // `fixed: ...` and the like: a reserved word where a label stands.
    if text.get(found_span.range()) == Some(":") {
        let before = text[chunk.start..pos].trim_end();
        let word = before
            .rsplit(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .next()
            .unwrap_or("");
        if crate::resolve::RESERVED.contains(&word) {
            let at = chunk.start + before.len() - word.len();
            d = Diagnostic::error(
                Span::new(at, at + word.len()),
                format!("`{word}` is a reserved word and cannot be a label"),
            )
            .with_label("reserved word")
            .with_note("choose another label");
        }
    }
    (d, None)
}

/// A word right after a number where the statement could end (`param w = 25 mm;`): a unit the
/// language does not have.
fn unknown_unit(text: &str, before: &str, word: Span, end: usize) -> Option<Diagnostic> {
    let w = text.get(word.range())?;
    let after = text.get(word.end..end)?.trim_start();
    let is_word = w.starts_with(|c: char| c.is_ascii_alphabetic());
    let after_number = before.ends_with(|c: char| c.is_ascii_digit() || c == '.');
    let ends_value = after.is_empty() || after.starts_with([';', ',', ')']);
    (is_word && after_number && ends_value).then(|| Diagnostic::unknown_unit(word, w))
}

/// The first character of the statement in `chunk`, outside comments, that is not ASCII: names,
/// numbers and the language's symbols are all ASCII, so pest's "expected ..." would only puzzle.
fn non_ascii(text: &str, chunk: Span) -> Option<Diagnostic> {
    let s = &text[chunk.range()];
    let mut rest = s.char_indices().peekable();
    while let Some((i, c)) = rest.next() {
        if c == '/' && s[i..].starts_with("//") {
            let line_end = s[i..].find('\n').map_or(s.len(), |k| i + k);
            while rest.peek().is_some_and(|&(j, _)| j < line_end) {
                rest.next();
            }
        } else if c == '/' && s[i..].starts_with("/*") {
            let close = s[i + 2..].find("*/").map_or(s.len(), |k| i + 2 + k + 2);
            while rest.peek().is_some_and(|&(j, _)| j < close) {
                rest.next();
            }
        } else if !c.is_ascii() {
            let at = chunk.start + i;
            let in_name = s[..i].ends_with(|b: char| b.is_ascii_alphanumeric() || b == '_');
            let message = if in_name {
                format!("`{c}` cannot be part of a name: names are ASCII")
            } else {
                format!("unexpected character `{c}`: gcs models are ASCII outside comments")
            };
            let note = if in_name {
                "names are ASCII letters, digits and `_`, starting with a letter or `_`"
            } else {
                "other characters may stand only in comments"
            };
            return Some(
                Diagnostic::error(Span::new(at, at + c.len_utf8()), message)
                    .with_label(format!("U+{:04X}", u32::from(c)))
                    .with_note(note),
            );
        }
    }
    None
}

/// Words that start a statement.
const STATEMENT_KEYWORDS: &[&str] = &[
    "space", "param", "fixed", "point", "vector", "line", "segment", "circle", "plane", "body",
    "marker", "output",
];

/// A statement that starts with two words, the first a misspelt keyword (`pointt B = ...`).
fn misspelled_keyword(text: &str, chunk: Span) -> Option<Diagnostic> {
    let s = &text[chunk.range()];
    let word_len = |t: &str| {
        t.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(t.len())
    };
    let first = &s[..word_len(s)];
    let rest = s[first.len()..].trim_start();
    let second = &rest[..word_len(rest)];
    let starts_name = |w: &str| w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
    if !starts_name(first)
        || !starts_name(second)
        || rest.len() == s.len() - first.len()
        || STATEMENT_KEYWORDS.contains(&first)
    {
        return None;
    }
    let keyword = crate::resolve::suggest(first, STATEMENT_KEYWORDS.iter().copied())?;
    Some(
        Diagnostic::error(
            Span::new(chunk.start, chunk.start + first.len()),
            format!("unknown keyword `{first}`"),
        )
        .with_label(format!("did you mean `{keyword}`?"))
        .with_note(
            "a statement starts with `space`, `param`, a geom kind (`point`, `vector`, `line`, \
             `segment`, `circle`, `plane`, `marker`), `body`, `fixed`, `output`, a label, or a \
             constraint",
        ),
    )
}

fn is_space_or_comment_char(c: char) -> bool {
    c.is_whitespace()
}

/// Whether `rest` begins with a word that starts a statement, so that a missing `;` before it
/// can be recovered from.
fn starts_statement(rest: &str) -> bool {
    let word: String = rest
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    !word.is_empty() && !word.starts_with(|c: char| c.is_ascii_digit())
}

/// The token at `pos`, described for a message: "`word`", "`(`" or "end of file".
fn describe_token(text: &str, pos: usize, end: usize) -> String {
    let s = token_span(text, pos, end);
    if s.start >= s.end {
        if pos >= text.len() {
            "end of file".to_string()
        } else {
            "end of statement".to_string()
        }
    } else {
        format!("`{}`", &text[s.range()])
    }
}

/// The span of the token starting at `pos`: a word, a number, or one character.
fn token_span(text: &str, pos: usize, end: usize) -> Span {
    let rest = text.get(pos..end).unwrap_or("");
    let mut chars = rest.char_indices();
    match chars.next() {
        None => Span::empty(pos),
        Some((_, c)) if c.is_ascii_alphanumeric() || c == '_' || c == '.' => {
            let len = rest
                .char_indices()
                .find(|&(_, c)| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
                .map_or(rest.len(), |(i, _)| i);
            Span::new(pos, pos + len)
        }
        Some((_, c)) if c == '-' && rest.starts_with("->") => Span::new(pos, pos + 2),
        Some((_, c)) => Span::new(pos, pos + c.len_utf8()),
    }
}

/// What a grammar rule looks like to a user.
fn describe_rule(rule: Rule) -> &'static str {
    match rule {
        Rule::semi => "`;`",
        Rule::comma => "`,`",
        Rule::close => "`)`",
        Rule::expr | Rule::number | Rule::bad_number | Rule::call | Rule::paren | Rule::neg => {
            "an expression"
        }
        Rule::path | Rule::word | Rule::name | Rule::label => "a name",
        Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow => "an operator",
        Rule::unit => "a unit (`deg` or `rad`)",
        Rule::space_dim => "`2d` or `3d`",
        Rule::tuple => "a coordinate tuple such as `(0, 0)`",
        Rule::spec
        | Rule::tagged
        | Rule::spec_value
        | Rule::spec_tag
        | Rule::point_tag
        | Rule::tuple_value
        | Rule::arrow => "a coordinate tuple or a value",
        Rule::member => "a member declaration (`point`, `vector` or `marker`)",
        Rule::at_clause | Rule::kw_at => "`at`",
        Rule::rotated_clause | Rule::kw_rotated => "`rotated`",
        Rule::kw_about => "`about`",
        Rule::geom_kw => "a geom kind",
        Rule::kw_marker => "`marker`",
        Rule::fixed_kw => "`fixed`",
        Rule::kw_space => "`space`",
        Rule::kw_param => "`param`",
        Rule::kw_body => "`body`",
        Rule::kw_output => "`output`",
        Rule::kw_pi => "`pi`",
        Rule::EOI => "end of statement",
        _ => "a statement",
    }
}

/// Splits `text` into statement spans at `;` and at the `}` closing a top-level block (with its
/// optional `;`), skipping comments. Reports unterminated comments, unbalanced braces and
/// statements nested too deeply; the offending statement is dropped.
fn split(text: &str, diags: &mut Vec<Diagnostic>) -> Vec<Span> {
    let bytes = text.as_bytes();
    let mut chunks = Vec::new();
    let mut start: Option<usize> = None; // first non-blank byte of the current statement
    let mut braces: Vec<usize> = Vec::new(); // positions of open `{`
    let mut parens = 0usize;
    let mut deepest = 0usize;
    let mut deepest_at = 0usize;
    // Operators in the current declaration or member, and the most in any of this statement's.
    let mut ops = 0usize;
    let mut max_ops = 0usize;
    // A UTF-8 byte-order mark, which some editors write, is not part of the text.
    let mut i = if text.starts_with('\u{FEFF}') { 3 } else { 0 };

    let mut finish = |start: &mut Option<usize>,
                      end: usize,
                      deepest: &mut usize,
                      deepest_at: usize,
                      max_ops: &mut usize,
                      diags: &mut Vec<Diagnostic>| {
        if let Some(s) = start.take() {
            let span = Span::new(s, end);
            if *deepest > MAX_NESTING {
                diags.push(
                    Diagnostic::error(
                        Span::new(deepest_at, deepest_at + 1),
                        "expression nested too deeply",
                    )
                    .with_label(format!("nesting depth {} here", *deepest))
                    .with_note(format!("parentheses may nest at most {MAX_NESTING} deep")),
                );
            } else if *max_ops > MAX_OPERATORS {
                diags.push(
                    Diagnostic::error(span, "statement too long").with_note(format!(
                        "one declaration may hold at most {MAX_OPERATORS} operators"
                    )),
                );
            } else {
                chunks.push(span);
            }
        }
        *deepest = 0;
        *max_ops = 0;
    };

    while i < bytes.len() {
        let b = bytes[i];
        // Comments.
        if b == b'/' && bytes.get(i + 1) == Some(&b'/') {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        if b == b'/' && bytes.get(i + 1) == Some(&b'*') {
            match text[i + 2..].find("*/") {
                Some(k) => {
                    i = i + 2 + k + 2;
                    continue;
                }
                None => {
                    diags.push(
                        Diagnostic::error(Span::new(i, i + 2), "unterminated block comment")
                            .with_label("this comment is never closed")
                            .with_note("close it with `*/`; block comments do not nest"),
                    );
                    // The rest of the file is comment: finish what came before it.
                    if braces.is_empty() {
                        finish(&mut start, i, &mut deepest, deepest_at, &mut max_ops, diags);
                    }
                    return chunks;
                }
            }
        }
        if b.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if start.is_none() {
            start = Some(i);
        }
        match b {
            b'{' => braces.push(i),
            b'}' => {
                if braces.pop().is_none() {
                    diags.push(
                        Diagnostic::error(Span::new(i, i + 1), "unexpected closing brace `}`")
                            .with_label("no `{` is open here"),
                    );
                    // Drop what came before in this statement: it cannot be parsed.
                    start = None;
                    deepest = 0;
                    max_ops = 0;
                } else if braces.is_empty() {
                    // A block closed: the statement ends here, with an optional `;`.
                    let mut end = i + 1;
                    let mut j = end;
                    while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                        j += 1;
                    }
                    if bytes.get(j) == Some(&b';') {
                        end = j + 1;
                    }
                    finish(
                        &mut start,
                        end,
                        &mut deepest,
                        deepest_at,
                        &mut max_ops,
                        diags,
                    );
                    i = end;
                    parens = 0;
                    continue;
                }
            }
            b'(' => {
                parens += 1;
                if parens > deepest {
                    deepest = parens;
                    deepest_at = i;
                }
            }
            b')' => parens = parens.saturating_sub(1),
            b'^' | b'+' | b'*' | b'/' => {
                ops += 1;
                max_ops = max_ops.max(ops);
            }
            b'-' if bytes.get(i + 1) != Some(&b'>') => {
                ops += 1;
                max_ops = max_ops.max(ops);
            }
            b';' if braces.is_empty() => {
                ops = 0;
                finish(
                    &mut start,
                    i + 1,
                    &mut deepest,
                    deepest_at,
                    &mut max_ops,
                    diags,
                );
                parens = 0;
            }
            b';' => ops = 0,
            _ => {}
        }
        i += 1;
    }
    if let Some(&open) = braces.first() {
        diags.push(
            Diagnostic::error(Span::new(open, open + 1), "unclosed brace `{`")
                .with_label("this `{` is never closed")
                .with_note("the file ends before the matching `}`"),
        );
    } else {
        finish(
            &mut start,
            bytes.len(),
            &mut deepest,
            deepest_at,
            &mut max_ops,
            diags,
        );
    }
    chunks
}

fn pratt() -> &'static PrattParser<Rule> {
    static PRATT: OnceLock<PrattParser<Rule>> = OnceLock::new();
    PRATT.get_or_init(|| {
        PrattParser::new()
            .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
            .op(Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left))
            .op(Op::prefix(Rule::neg))
            .op(Op::infix(Rule::pow, Assoc::Right))
            .op(Op::postfix(Rule::unit))
    })
}

/// Builds syntax-tree nodes from pest pairs of one statement, shifting spans to file offsets.
struct Builder<'d> {
    offset: usize,
    diags: &'d mut Vec<Diagnostic>,
}

impl Builder<'_> {
    fn span(&self, pair: &Pair<'_, Rule>) -> Span {
        let s = pair.as_span();
        Span::new(s.start() + self.offset, s.end() + self.offset)
    }

    fn ident(&self, pair: Pair<'_, Rule>) -> Ident {
        Ident {
            text: pair.as_str().to_string(),
            span: self.span(&pair),
        }
    }

    fn statement(mut self, pair: Pair<'_, Rule>) -> Option<Statement> {
        let span = self.span(&pair);
        let rule = pair.as_rule();
        let mut inner = pair.into_inner().peekable();
        let mut fixed = None;
        if inner.peek().map(|p| p.as_rule()) == Some(Rule::fixed_kw) {
            fixed = inner.next().map(|p| self.span(&p));
        }
        let kind = match rule {
            Rule::space_decl => {
                let _kw = inner.next();
                StatementKind::Space {
                    dim: self.ident(inner.next()?),
                }
            }
            Rule::param_decl => {
                let _kw = inner.next();
                let name = self.ident(inner.next()?);
                let value = self.expr(inner.next()?);
                StatementKind::Param { name, value }
            }
            Rule::geom_decl => StatementKind::Geom(self.geom_decl(fixed, span, inner)?),
            Rule::body_decl => {
                let _kw = inner.next();
                let name = self.ident(inner.next()?);
                let mut at = None;
                let mut rotated = None;
                let mut repeated_placement = Vec::new();
                let mut members = Vec::new();
                for p in inner {
                    match p.as_rule() {
                        Rule::at_clause => {
                            let s = self.span(&p);
                            let v = p.into_inner().nth(1).map(|v| self.spec_value(v));
                            if at.is_some() {
                                repeated_placement.push(s);
                            } else {
                                at = v;
                            }
                        }
                        Rule::rotated_clause => {
                            let s = self.span(&p);
                            let mut parts = p.into_inner();
                            let _kw = parts.next();
                            let angle = self.expr(parts.next()?);
                            let about = parts.nth(1).map(|v| self.spec_value(v));
                            if rotated.is_some() {
                                repeated_placement.push(s);
                            } else {
                                rotated = Some(Rotated {
                                    angle,
                                    about,
                                    span: s,
                                });
                            }
                        }
                        Rule::member => {
                            let mspan = self.span(&p);
                            let mut m = p.into_inner().peekable();
                            let mut mfixed = None;
                            if m.peek().map(|p| p.as_rule()) == Some(Rule::fixed_kw) {
                                mfixed = m.next().map(|p| self.span(&p));
                            }
                            members.push(self.geom_decl(mfixed, mspan, m)?);
                        }
                        _ => {}
                    }
                }
                StatementKind::Body {
                    name,
                    at,
                    rotated,
                    repeated_placement,
                    members,
                }
            }
            Rule::output_stmt => {
                let refs = inner
                    .filter(|p| p.as_rule() == Rule::path)
                    .map(|p| self.path(p))
                    .collect();
                StatementKind::Output { refs }
            }
            Rule::constraint_stmt => {
                let mut label = None;
                let mut name = None;
                let mut args = Vec::new();
                let mut args_span = span;
                let mut value = None;
                for p in inner {
                    match p.as_rule() {
                        Rule::label => label = Some(self.ident(p)),
                        Rule::name => name = Some(self.ident(p)),
                        Rule::args => {
                            args_span = self.span(&p);
                            args = p
                                .into_inner()
                                .filter(|e| e.as_rule() == Rule::expr)
                                .map(|e| self.expr(e))
                                .collect();
                        }
                        Rule::value => value = p.into_inner().next().map(|e| self.expr(e)),
                        _ => {}
                    }
                }
                StatementKind::Constraint {
                    label,
                    name: name?,
                    args,
                    args_span,
                    value,
                }
            }
            _ => return None,
        };
        Some(Statement { kind, span, fixed })
    }

    fn geom_decl<'i>(
        &mut self,
        fixed: Option<Span>,
        span: Span,
        mut inner: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Option<GeomDecl> {
        let keyword = self.ident(inner.next()?);
        let name = self.ident(inner.next()?);
        let spec_pair = inner.next()?;
        let spec_span = self.span(&spec_pair);
        let spec = spec_pair
            .into_inner()
            .map(|p| match p.as_rule() {
                Rule::arrow => SpecPart::Arrow(self.span(&p)),
                Rule::tagged => {
                    let mut t = p.into_inner();
                    let tag = t.next().map(|t| {
                        // `point_tag` includes the blanks before its `(`.
                        let mut id = self.ident(t);
                        let word = id.text.trim_end().len();
                        id.text.truncate(word);
                        id.span = Span::new(id.span.start, id.span.start + word);
                        id
                    });
                    let value = t.next().map(|v| self.spec_value(v));
                    match (tag, value) {
                        (Some(tag), Some(value)) => SpecPart::Tagged { tag, value },
                        _ => SpecPart::Arrow(spec_span),
                    }
                }
                _ => SpecPart::Value(self.spec_value(p)),
            })
            .collect();
        Some(GeomDecl {
            keyword,
            name,
            spec,
            spec_span,
            fixed,
            span,
        })
    }

    fn spec_value(&mut self, pair: Pair<'_, Rule>) -> SpecValue {
        let span = self.span(&pair);
        let mut inner = pair.into_inner().next();
        if let Some(p) = inner.clone().filter(|p| p.as_rule() == Rule::tuple_value) {
            inner = p.into_inner().next();
        }
        match inner {
            Some(p) if p.as_rule() == Rule::tuple => {
                let tspan = self.span(&p);
                let items = p.into_inner().filter(|e| e.as_rule() == Rule::expr);
                SpecValue::Tuple(items.map(|e| self.expr(e)).collect(), tspan)
            }
            Some(p) => SpecValue::Expr(self.expr(p)),
            None => SpecValue::Expr(Expr {
                kind: ExprKind::Number(f64::NAN),
                span,
            }),
        }
    }

    fn path(&self, pair: Pair<'_, Rule>) -> Path {
        let span = self.span(&pair);
        Path {
            parts: pair.into_inner().map(|w| self.ident(w)).collect(),
            span,
        }
    }

    fn expr(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        let e = self.expr_pairs(pair.into_inner());
        if depth(&e) > MAX_EXPR_DEPTH {
            self.diags.push(
                Diagnostic::error(span, "expression too deep").with_note(format!(
                    "an expression may nest at most {MAX_EXPR_DEPTH} operations deep"
                )),
            );
            return Expr {
                kind: ExprKind::Number(0.0),
                span,
            };
        }
        e
    }

    fn expr_pairs(&self, pairs: Pairs<'_, Rule>) -> Expr {
        let off = self.offset;
        fn sp(off: usize, p: &Pair<'_, Rule>) -> Span {
            let s = p.as_span();
            Span::new(s.start() + off, s.end() + off)
        }
        pratt()
            .map_primary(move |p| self.primary(p))
            .map_prefix(move |op, rhs| {
                let span = sp(off, &op).to(rhs.span);
                Expr {
                    kind: ExprKind::Neg(Box::new(rhs)),
                    span,
                }
            })
            .map_postfix(move |lhs, op| {
                let uspan = sp(off, &op);
                let unit = if op.as_str() == "deg" {
                    AngleUnit::Deg
                } else {
                    AngleUnit::Rad
                };
                let span = lhs.span.to(uspan);
                Expr {
                    kind: ExprKind::Unit(Box::new(lhs), unit, uspan),
                    span,
                }
            })
            .map_infix(move |lhs, op, rhs| {
                let o = match op.as_rule() {
                    Rule::add => BinaryOp::Add,
                    Rule::sub => BinaryOp::Sub,
                    Rule::mul => BinaryOp::Mul,
                    Rule::div => BinaryOp::Div,
                    _ => BinaryOp::Pow,
                };
                let span = lhs.span.to(rhs.span);
                Expr {
                    kind: ExprKind::Binary(o, Box::new(lhs), Box::new(rhs)),
                    span,
                }
            })
            .parse(pairs)
    }

    fn primary(&self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::number => match pair.as_str().parse::<f64>() {
                Ok(v) => ExprKind::Number(v),
                Err(_) => ExprKind::BadNumber(pair.as_str().to_string()),
            },
            Rule::bad_number => ExprKind::BadNumber(pair.as_str().to_string()),
            Rule::kw_pi => ExprKind::Pi,
            Rule::path => ExprKind::Path(self.path(pair)),
            Rule::paren => {
                let inner = pair.into_inner().find(|e| e.as_rule() == Rule::expr);
                match inner {
                    Some(e) => ExprKind::Paren(Box::new(self.expr_pairs(e.into_inner()))),
                    None => ExprKind::Number(f64::NAN),
                }
            }
            Rule::call => {
                let mut it = pair.into_inner();
                let name = it.next().map(|w| self.ident(w));
                let args = it
                    .filter(|e| e.as_rule() == Rule::expr)
                    .map(|e| self.expr_pairs(e.into_inner()))
                    .collect();
                match name {
                    Some(name) => ExprKind::Call(name, args),
                    None => ExprKind::Number(f64::NAN),
                }
            }
            _ => ExprKind::BadNumber(pair.as_str().to_string()),
        };
        Expr { kind, span }
    }
}

/// The depth of an expression tree.
pub fn depth(e: &Expr) -> usize {
    match &e.kind {
        ExprKind::Number(_) | ExprKind::BadNumber(_) | ExprKind::Pi | ExprKind::Path(_) => 1,
        ExprKind::Neg(a) | ExprKind::Unit(a, _, _) | ExprKind::Paren(a) => 1 + depth(a),
        ExprKind::Binary(_, a, b) => 1 + depth(a).max(depth(b)),
        ExprKind::Call(_, args) => 1 + args.iter().map(depth).max().unwrap_or(0),
    }
}

/// Evaluates one expression of the language given as text, such as a `--set` value, with the
/// model's params at their defaults. A unit makes it an angle (radians); a bare number is
/// itself. Returns the value and what it measures.
pub fn eval_expression(model: &crate::Model, text: &str) -> Result<(f64, Dim), String> {
    if text.len() > 4096 {
        return Err("expression too long".into());
    }
    if text.bytes().filter(|&b| b == b'(').count() > MAX_NESTING {
        return Err("expression nested too deeply".into());
    }
    let mut pairs = GcsParser::parse(Rule::single_expr, text).map_err(|e| {
        let (d, _) = syntax_error(text, Span::new(0, text.len()), &e);
        d.message
    })?;
    let expr_pair = pairs
        .next()
        .and_then(|p| p.into_inner().find(|p| p.as_rule() == Rule::expr))
        .ok_or_else(|| "empty expression".to_string())?;
    let mut diags = Vec::new();
    let e = Builder {
        offset: 0,
        diags: &mut diags,
    }
    .expr(expr_pair);
    if let Some(d) = diags.first() {
        return Err(d.message.clone());
    }
    let (v, dim) = eval_syntax(model, &e)?;
    if v.is_finite() {
        Ok((v, dim))
    } else {
        Err(format!("`{}` is {v}, not a finite number", text.trim()))
    }
}

/// The value of `param` given as text (`--set NAME=VALUE`), checked as the file checks a
/// default: a finite number, an angle only for an angle param, a length only for a param that
/// holds lengths or plain numbers.
pub fn param_value(
    model: &crate::Model,
    param: crate::expr::ParamId,
    text: &str,
) -> Result<f64, String> {
    let p = &model.params[param];
    value_for(model, &p.name, p.dim, text)
}

/// The value of something named `name` that holds `want` (a param, a default), given as text
/// on the command line, checked as [`param_value`] checks a param's.
pub fn value_for(model: &crate::Model, name: &str, want: Dim, text: &str) -> Result<f64, String> {
    let (v, dim) = eval_expression(model, text)?;
    let p = (name, want);
    let fits = dim == Dim::Number || p.1 == Dim::Number || dim == p.1;
    if fits {
        Ok(v)
    } else {
        let hint = match dim {
            Dim::Angle => "give a length, without `deg` or `rad`",
            _ => "give an angle, in radians or with `deg`",
        };
        Err(format!(
            "`{}` is {}, but `{}` holds {}; {hint}",
            text.trim(),
            dim.noun(),
            p.0,
            p.1.noun()
        ))
    }
}

/// The names of numbers that are not finite, which a user might write for one.
fn not_finite_word(name: &str) -> bool {
    matches!(
        name.to_ascii_lowercase().as_str(),
        "nan" | "inf" | "infinity" | "infty"
    )
}

fn eval_syntax(model: &crate::Model, e: &Expr) -> Result<(f64, Dim), String> {
    Ok(match &e.kind {
        ExprKind::Number(v) => (*v, Dim::Number),
        ExprKind::BadNumber(t) => return Err(format!("malformed number `{t}`")),
        ExprKind::Pi => (std::f64::consts::PI, Dim::Number),
        ExprKind::Path(p) => {
            let name = p.dotted();
            match model.param_named(&name) {
                Some(id) => (model.params[id].default, model.params[id].dim),
                None if not_finite_word(&name) => {
                    return Err(format!(
                        "`{name}` is not a finite number; a value must be finite"
                    ))
                }
                None => return Err(format!("unknown param `{name}`")),
            }
        }
        ExprKind::Neg(a) => {
            let (v, d) = eval_syntax(model, a)?;
            (-v, d)
        }
        ExprKind::Paren(a) => eval_syntax(model, a)?,
        ExprKind::Unit(a, u, _) => {
            let (v, _) = eval_syntax(model, a)?;
            let v = match u {
                AngleUnit::Deg => v.to_radians(),
                AngleUnit::Rad => v,
            };
            (v, Dim::Angle)
        }
        ExprKind::Binary(op, a, b) => {
            let ((x, dx), (y, dy)) = (eval_syntax(model, a)?, eval_syntax(model, b)?);
            let v = match op {
                BinaryOp::Add => x + y,
                BinaryOp::Sub => x - y,
                BinaryOp::Mul => x * y,
                BinaryOp::Div => x / y,
                BinaryOp::Pow => x.powf(y),
            };
            (v, dx.of_binary(*op, dy))
        }
        ExprKind::Call(name, args) => {
            let f = crate::expr::Func::from_name(&name.text)
                .ok_or_else(|| format!("unknown function `{}`", name.text))?;
            if args.len() != f.arity() {
                return Err(format!("`{}` takes {} arguments", f.name(), f.arity()));
            }
            let (a, da) = eval_syntax(model, &args[0])?;
            let (b, db) = match args.get(1) {
                Some(b) => {
                    let (b, db) = eval_syntax(model, b)?;
                    (b, Some(db))
                }
                None => (0.0, None),
            };
            (f.apply(a, b), f.dim(da, db))
        }
    })
}
