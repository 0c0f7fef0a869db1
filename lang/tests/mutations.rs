//! Property test: `gcs_lang::load` never panics, overflows the stack or hangs on random mutations
//! of the example models, and what it returns is consistent.
//!
//! Each proptest case applies a short sequence of mutations to one example and loads the result.
//! The case counts of the four proptest functions below sum to 10,200 loaded mutants (about
//! 35,000 single mutations), besides the fixed inputs of `extremes` and `oddities`.
//!
//! Loads run on the test thread (2 MiB of stack by default), which is a realistic bound: deep
//! nesting that overflows it is a bug.

use gcs_lang::diagnostic::render_plain;
use gcs_lang::{load, Diagnostic};
use proptest::prelude::*;
use proptest::sample::Index;

const EXAMPLES: &[(&str, &str)] = &[
    ("fourbar.gcs", include_str!("../../examples/fourbar.gcs")),
    ("brick.gcs", include_str!("../../examples/brick.gcs")),
    ("circle.gcs", include_str!("../../examples/circle.gcs")),
    (
        "slider_crank.gcs",
        include_str!("../../examples/slider_crank.gcs"),
    ),
    (
        "points_planes.gcs",
        include_str!("../../examples/points_planes.gcs"),
    ),
];

/// Language tokens worth inserting: punctuation, comment markers, units, malformed numbers,
/// keywords, constraint names, and whole small statements.
const TOKENS: &[&str] = &[
    ";",
    "{",
    "}",
    "(",
    ")",
    ",",
    "->",
    "/*",
    "*/",
    "//",
    "\n",
    " ",
    "=",
    ":",
    "deg",
    "rad",
    "^",
    "-",
    "+",
    "*",
    "/",
    ".",
    "..",
    "1e",
    "1e-",
    "1e999",
    "1.2.3",
    "0",
    "0.0",
    ".5",
    "3x",
    "pi",
    "_",
    "fixed",
    "space",
    "space 3d;",
    "space 2d;",
    "space 4d;",
    "param",
    "body",
    "marker",
    "output",
    "at",
    "rotated",
    "about",
    "point",
    "vector",
    "line",
    "segment",
    "circle",
    "plane",
    "center",
    "radius",
    "normal",
    "offset",
    "z",
    "x",
    "sqrt",
    "sin",
    "cos",
    "atan2",
    "coincident",
    "distance",
    "on",
    "tangent",
    "angle",
    "parallel",
    "perpendicular",
    "horizontal",
    "vertical",
    "length",
    "equal",
    "midpoint",
    "symmetric",
    "symmetric(A, q, L);",
    "in_line",
    "in_plane",
    "parallel_z",
    "offset_z",
    "offset_x",
    "helical",
    "revolute",
    "prismatic",
    "cylindrical",
    "spherical",
    "planar",
    "weld",
    "param q = 1;",
    "point q = (0, 0);",
    "point q = (0, 0, 0);",
    "fixed point A = (1, 1);",
    "body b { }",
    "body b { point p = (0, 0); }",
    "coincident(A, A);",
    "distance(A, A) = 0;",
    "output A;",
    "\u{0}",
    "\u{feff}",
    "é",
    "\u{1F600}",
    "\r\n",
    "\t",
];

/// A byte worth writing: anything, with extra weight on NUL, non-UTF-8 bytes and punctuation.
fn byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        3 => any::<u8>(),
        1 => Just(0u8),
        2 => 0x80u8..=0xff,
        3 => prop::sample::select(b";{}(),-^./*=:+ \n0123456789eE_ab".to_vec()),
    ]
}

/// A count that is random over `lo..=hi` but often lands next to the limits the parser enforces
/// (nesting 48, expression depth 200, 1000 operators), where off-by-one bugs live.
fn count(lo: usize, hi: usize) -> impl Strategy<Value = usize> {
    let near: Vec<usize> = [
        47, 48, 49, 50, 199, 200, 201, 202, 498, 499, 500, 501, 998, 999, 1000, 1001, 1002,
    ]
    .into_iter()
    .filter(|n| (lo..=hi).contains(n))
    .collect();
    prop_oneof![
        2 => lo..=hi,
        1 => prop::sample::select(near),
    ]
}

/// A deeply nested or very long expression (or body).
#[derive(Clone, Debug)]
enum Deep {
    /// `((((1))))`, `n` pairs.
    Parens(usize),
    /// `((((1` with no closing parentheses.
    OpenParens(usize),
    /// `1 op 1 op ... 1`, `n` terms.
    Chain(&'static str, usize),
    /// `-----1`, `n` signs.
    Negs(usize),
    /// `1 deg deg deg`, `n` units.
    Units(usize),
    /// `f(f(f(1)))`, `n` calls.
    Calls(usize),
    /// `-(-(-(1)))`, `n` levels.
    NegParens(usize),
    /// `(1,(1,(1, ...)))`: nested tuples.
    Tuples(usize),
    /// A body with `n` members.
    HugeBody(usize),
    /// `{{{{`, `n` braces.
    Braces(usize),
}

impl Deep {
    fn render(&self) -> String {
        match *self {
            Deep::Parens(n) => format!("{}1{}", "(".repeat(n), ")".repeat(n)),
            Deep::OpenParens(n) => format!("{}1", "(".repeat(n)),
            Deep::Chain(op, n) => {
                let mut s = String::with_capacity(n * (op.len() + 1));
                s.push('2');
                for _ in 1..n {
                    s.push_str(op);
                    s.push('2');
                }
                s
            }
            Deep::Negs(n) => format!("{}1", "-".repeat(n)),
            Deep::Units(n) => format!("1{}", " deg".repeat(n)),
            Deep::Calls(n) => format!("{}1{}", "sqrt(".repeat(n), ")".repeat(n)),
            Deep::NegParens(n) => format!("{}1{}", "-(".repeat(n), ")".repeat(n)),
            Deep::Tuples(n) => format!("{}1{}", "(1, ".repeat(n), ")".repeat(n)),
            Deep::HugeBody(n) => {
                let mut s = String::from("body huge at (0, 0) {\n");
                for i in 0..n {
                    s.push_str(&format!("  point m{i} = ({i}, -{i});\n"));
                }
                s.push('}');
                s
            }
            Deep::Braces(n) => "{".repeat(n),
        }
    }
}

fn deep() -> impl Strategy<Value = Deep> {
    let op = prop::sample::select(vec![
        "+", "-", "*", "/", "^", " + ", "^-", "*-", "+-", " deg + ",
    ]);
    prop_oneof![
        count(10, 5000).prop_map(Deep::Parens),
        count(10, 5000).prop_map(Deep::OpenParens),
        (op, count(2, 20_000)).prop_map(|(op, n)| Deep::Chain(op, n)),
        count(2, 20_000).prop_map(Deep::Negs),
        count(2, 5000).prop_map(Deep::Units),
        count(10, 5000).prop_map(Deep::Calls),
        count(10, 5000).prop_map(Deep::NegParens),
        count(10, 5000).prop_map(Deep::Tuples),
        (1usize..3000).prop_map(Deep::HugeBody),
        count(10, 5000).prop_map(Deep::Braces),
    ]
}

#[derive(Clone, Debug)]
enum Mutation {
    /// Overwrite one byte.
    Flip(Index, u8),
    /// Delete 1..=8 bytes.
    Delete(Index, usize),
    /// Insert random bytes.
    InsertBytes(Index, Vec<u8>),
    /// Insert a language token.
    InsertToken(Index, &'static str),
    /// Swap two whitespace-separated tokens.
    SwapTokens(Index, Index),
    /// Cut the file at a point.
    Truncate(Index),
    /// Copy a statement (up to and including a `;`) to another place.
    DupStatement(Index, Index),
    /// Copy a statement right after itself `n` times.
    RepeatStatement(Index, usize),
    /// Remove one statement.
    DeleteStatement(Index),
    /// Replace a number (or insert at a point when there is none) with a deep expression.
    Nest(Index, Deep),
    /// Make a word or number (a name, a label, a keyword, a literal) `n` characters longer by
    /// repeating its last character; everywhere it occurs when the flag is set, so that a long
    /// name stays declared and used.
    Lengthen(Index, usize, bool),
}

fn byte_mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<Index>(), byte()).prop_map(|(i, b)| Mutation::Flip(i, b)),
        3 => (any::<Index>(), 1usize..=8).prop_map(|(i, n)| Mutation::Delete(i, n)),
        3 => (any::<Index>(), prop::collection::vec(byte(), 1..8))
            .prop_map(|(i, v)| Mutation::InsertBytes(i, v)),
        1 => any::<Index>().prop_map(Mutation::Truncate),
    ]
}

fn token_mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        5 => (any::<Index>(), prop::sample::select(TOKENS))
            .prop_map(|(i, t)| Mutation::InsertToken(i, t)),
        3 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::SwapTokens(a, b)),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::DupStatement(a, b)),
        1 => (any::<Index>(), 1usize..50).prop_map(|(a, n)| Mutation::RepeatStatement(a, n)),
        2 => any::<Index>().prop_map(Mutation::DeleteStatement),
    ]
}

/// A length around the one that once panicked `gcs check` (65,536 characters, past the widths
/// `format!` takes), or anything up to it.
fn long() -> impl Strategy<Value = usize> {
    prop_oneof![
        1 => 1usize..70_000,
        1 => prop::sample::select(vec![65_534usize, 65_535, 65_536, 70_000]),
    ]
}

fn lengthen() -> impl Strategy<Value = Mutation> {
    (any::<Index>(), long(), any::<bool>()).prop_map(|(i, n, all)| Mutation::Lengthen(i, n, all))
}

fn any_mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        10 => byte_mutation(),
        10 => token_mutation(),
        1 => (any::<Index>(), deep()).prop_map(|(i, d)| Mutation::Nest(i, d)),
    ]
}

/// The byte ranges of the maximal runs of non-whitespace bytes.
fn tokens(s: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < s.len() {
        if s[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        while i < s.len() && !s[i].is_ascii_whitespace() {
            i += 1;
        }
        out.push((start, i));
    }
    out
}

/// The byte ranges of the maximal runs of word bytes (letters, digits, `_`, `.`): names,
/// dotted paths, labels, keywords and numbers.
fn words(s: &[u8]) -> Vec<(usize, usize)> {
    let is_word = |b: u8| b.is_ascii_alphanumeric() || b == b'_' || b == b'.';
    let mut out = Vec::new();
    let mut i = 0;
    while i < s.len() {
        if !is_word(s[i]) {
            i += 1;
            continue;
        }
        let start = i;
        while i < s.len() && is_word(s[i]) {
            i += 1;
        }
        out.push((start, i));
    }
    out
}

/// The byte ranges of statements: text up to and including each `;` (or the end).
fn statements(s: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &b) in s.iter().enumerate() {
        if b == b';' || b == b'}' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < s.len() {
        out.push((start, s.len()));
    }
    out
}

/// A position in `0..=len`.
fn pos(i: &Index, len: usize) -> usize {
    i.index(len + 1)
}

fn apply(m: &Mutation, s: &mut Vec<u8>) {
    match m {
        Mutation::Flip(i, b) => {
            if !s.is_empty() {
                let at = i.index(s.len());
                s[at] = *b;
            }
        }
        Mutation::Delete(i, n) => {
            if !s.is_empty() {
                let at = i.index(s.len());
                let end = (at + n).min(s.len());
                s.drain(at..end);
            }
        }
        Mutation::InsertBytes(i, v) => {
            let at = pos(i, s.len());
            s.splice(at..at, v.iter().copied());
        }
        Mutation::InsertToken(i, t) => {
            let at = pos(i, s.len());
            s.splice(at..at, t.bytes());
        }
        Mutation::SwapTokens(a, b) => {
            let toks = tokens(s);
            if toks.len() >= 2 {
                let (x, y) = (a.index(toks.len()), b.index(toks.len()));
                let (x, y) = (x.min(y), x.max(y));
                if x != y {
                    let (a, b) = (toks[x], toks[y]);
                    let mut out = Vec::with_capacity(s.len());
                    out.extend_from_slice(&s[..a.0]);
                    out.extend_from_slice(&s[b.0..b.1]);
                    out.extend_from_slice(&s[a.1..b.0]);
                    out.extend_from_slice(&s[a.0..a.1]);
                    out.extend_from_slice(&s[b.1..]);
                    *s = out;
                }
            }
        }
        Mutation::Truncate(i) => {
            let at = pos(i, s.len());
            s.truncate(at);
        }
        Mutation::DupStatement(a, b) => {
            let stmts = statements(s);
            if !stmts.is_empty() {
                let (from, to) = stmts[a.index(stmts.len())];
                let copy = s[from..to].to_vec();
                let at = pos(b, s.len());
                s.splice(at..at, copy);
            }
        }
        Mutation::RepeatStatement(a, n) => {
            let stmts = statements(s);
            if !stmts.is_empty() {
                let (from, to) = stmts[a.index(stmts.len())];
                let copy = s[from..to].repeat(*n);
                s.splice(to..to, copy);
            }
        }
        Mutation::DeleteStatement(a) => {
            let stmts = statements(s);
            if !stmts.is_empty() {
                let (from, to) = stmts[a.index(stmts.len())];
                s.drain(from..to);
            }
        }
        Mutation::Nest(i, d) => {
            let text = d.render();
            // Numbers: maximal runs of ASCII digits and dots.
            let mut nums = Vec::new();
            let mut k = 0;
            while k < s.len() {
                if s[k].is_ascii_digit() && (k == 0 || !s[k - 1].is_ascii_alphanumeric()) {
                    let start = k;
                    while k < s.len() && (s[k].is_ascii_digit() || s[k] == b'.') {
                        k += 1;
                    }
                    nums.push((start, k));
                } else {
                    k += 1;
                }
            }
            if nums.is_empty() || matches!(d, Deep::HugeBody(_)) {
                // Put it at the start of a statement so that it reaches the parser.
                let stmts = statements(s);
                let at = if stmts.is_empty() {
                    s.len()
                } else {
                    stmts[i.index(stmts.len())].1
                };
                s.splice(at..at, format!("\n{text}\n").into_bytes());
            } else {
                let (from, to) = nums[i.index(nums.len())];
                s.splice(from..to, text.into_bytes());
            }
        }
        Mutation::Lengthen(i, n, all) => {
            let count = words(s).len();
            if count > 0 {
                lengthen_word(s, i.index(count), *n, *all);
            }
        }
    }
}

/// Makes the `k`-th word of `s` `n` characters longer by repeating its last character; every
/// occurrence of it when `all` is set.
fn lengthen_word(s: &mut Vec<u8>, k: usize, n: usize, all: bool) {
    let ws = words(s);
    let Some(&(from, to)) = ws.get(k) else {
        return;
    };
    let word = s[from..to].to_vec();
    let mut long = word.clone();
    long.extend(std::iter::repeat_n(word[word.len() - 1], n));
    let targets: Vec<(usize, usize)> = if all {
        ws.into_iter()
            .filter(|&(a, b)| s[a..b] == word[..])
            .collect()
    } else {
        vec![(from, to)]
    };
    // From the end, so that earlier ranges stay valid.
    for &(a, b) in targets.iter().rev() {
        s.splice(a..b, long.iter().copied());
    }
}

/// Loads `bytes` and checks what comes back. Panics (failing the case) on any inconsistency.
fn check(bytes: &[u8]) {
    let (source, model, diags) = load("mutant.gcs", bytes);
    let errors = diags.iter().filter(|d| d.is_error()).count();
    match &model {
        Some(_) => assert_eq!(
            errors, 0,
            "a model came back with error diagnostics: {diags:#?}"
        ),
        None => assert!(
            errors > 0,
            "no model but no error diagnostic either: {diags:#?}"
        ),
    }
    let text = source.text();
    let utf8 = std::str::from_utf8(bytes).is_ok();
    for d in &diags {
        check_span(d, d.primary.span, bytes, text, utf8);
        for l in &d.secondary {
            check_span(d, l.span, bytes, text, utf8);
        }
        assert!(!d.message.is_empty(), "diagnostic without a message");
    }
    // The diagnostics must render (codespan slices the text at the spans).
    if utf8 && bytes.len() < 50_000 {
        let _ = render_plain(&source, &diags);
    }
}

fn check_span(d: &Diagnostic, span: gcs_lang::Span, bytes: &[u8], text: &str, utf8: bool) {
    assert!(
        span.start <= span.end && span.end <= bytes.len(),
        "span {span:?} out of the input (len {}): {d:#?}",
        bytes.len()
    );
    if utf8 {
        assert!(
            text.is_char_boundary(span.start) && text.is_char_boundary(span.end),
            "span {span:?} splits a character: {d:#?}"
        );
    }
}

fn example() -> impl Strategy<Value = &'static str> {
    prop::sample::select(EXAMPLES.iter().map(|(_, t)| *t).collect::<Vec<_>>())
}

/// Applies the mutations one after the other and loads the result.
fn run(base: &str, ms: &[Mutation]) {
    let mut s = base.as_bytes().to_vec();
    for m in ms {
        apply(m, &mut s);
    }
    check(&s);
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        // Failures are recorded by hand in `regressions.rs`.
        failure_persistence: None,
        max_shrink_iters: 2000,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(3500))]

    /// Byte flips (any value, NUL and non-UTF-8 included), deletions, insertions, truncation.
    #[test]
    fn byte_mutations(base in example(), ms in prop::collection::vec(byte_mutation(), 1..6)) {
        run(base, &ms);
    }
}

proptest! {
    #![proptest_config(config(3000))]

    /// Token insertions, token swaps, statement duplication and deletion.
    #[test]
    fn token_mutations(base in example(), ms in prop::collection::vec(token_mutation(), 1..6)) {
        run(base, &ms);
    }
}

proptest! {
    #![proptest_config(config(3000))]

    /// Everything mixed, with the occasional deep expression.
    #[test]
    fn mixed_mutations(base in example(), ms in prop::collection::vec(any_mutation(), 1..10)) {
        run(base, &ms);
    }
}

proptest! {
    #![proptest_config(config(700))]

    /// Deep nesting and long chains put in place of a number, then lightly mutated.
    #[test]
    fn deep_nesting(
        base in example(),
        at in any::<Index>(),
        d in deep(),
        ms in prop::collection::vec(token_mutation(), 0..3),
    ) {
        let mut s = base.as_bytes().to_vec();
        apply(&Mutation::Nest(at, d), &mut s);
        for m in &ms {
            apply(m, &mut s);
        }
        check(&s);
    }
}

proptest! {
    #![proptest_config(config(48))]

    /// Names, labels, keywords and numbers made up to 70,000 characters long, then lightly
    /// mutated.
    #[test]
    fn long_tokens(
        base in example(),
        l in prop::collection::vec(lengthen(), 1..3),
        ms in prop::collection::vec(token_mutation(), 0..3),
    ) {
        let mut s = base.as_bytes().to_vec();
        for m in l.iter().chain(&ms) {
            apply(m, &mut s);
        }
        check(&s);
    }
}

/// Every distinct name, label, keyword and number of every example made 70,000 characters
/// longer, one at a time (each occurrence of it, so that a name stays declared), and the first
/// twenty words all at once.
#[test]
fn long_tokens_everywhere() {
    for (_, text) in EXAMPLES {
        let ws = words(text.as_bytes());
        let count = ws.len();
        let mut seen = std::collections::HashSet::new();
        for (k, &(a, b)) in ws.iter().enumerate() {
            // Each distinct word once: its every occurrence is lengthened.
            if !seen.insert(&text[a..b]) {
                continue;
            }
            let mut s = text.as_bytes().to_vec();
            lengthen_word(&mut s, k, 70_000, true);
            check(&s);
        }
        let mut s = text.as_bytes().to_vec();
        for k in (0..count.min(20)).rev() {
            lengthen_word(&mut s, k, 70_000, false);
        }
        check(&s);
    }
}

/// The extremes of the deep inputs, once each, in every place an expression may stand.
#[test]
fn extremes() {
    let deeps = [
        Deep::Parens(5000),
        Deep::Parens(48),
        Deep::Parens(49),
        Deep::OpenParens(100_000),
        Deep::Chain("+", 20_000),
        Deep::Chain("+", 1000),
        Deep::Chain("+", 1001),
        Deep::Chain("^", 20_000),
        Deep::Chain("^", 1000),
        Deep::Chain("^", 1001),
        Deep::Chain("^-", 1000),
        Deep::Chain("*-", 1000),
        Deep::Negs(20_000),
        Deep::Negs(999),
        Deep::Negs(1000),
        Deep::Negs(1001),
        Deep::Units(999),
        Deep::Units(1000),
        Deep::Units(5000),
        Deep::Calls(48),
        Deep::Calls(5000),
        Deep::NegParens(48),
        Deep::NegParens(5000),
        Deep::Tuples(48),
        Deep::Tuples(5000),
        Deep::Braces(100_000),
    ];
    let places: &[fn(&str) -> String] = &[
        |e| format!("space 2d;\nparam p = {e};\n"),
        |e| format!("space 2d;\npoint p = ({e}, 0);\n"),
        |e| format!("space 2d;\nfixed point A = (0, 0);\ndistance(A, A) = {e};\n"),
        |e| format!("space 2d;\nbody b at ({e}, 0) rotated {e} {{ point p = ({e}, {e}); }}\n"),
        |e| format!("space 3d;\nplane P = normal (0, 0, 1) offset {e};\n"),
        |e| format!("space 2d;\ncoincident({e}, {e});\n"),
        |e| format!("space 2d;\noutput {e};\n"),
        |e| e.to_string(),
    ];
    for d in &deeps {
        let e = d.render();
        for place in places {
            check(place(&e).as_bytes());
        }
    }
    check(Deep::HugeBody(20_000).render().as_bytes());
    check(format!("space 2d;\n{}", Deep::HugeBody(5000).render()).as_bytes());
    // Many statements.
    check("space 2d;\nparam p = 1;\n".repeat(20_000).as_bytes());
    check(format!("space 2d;\n{}", "fixed point A = (0, 0);\n".repeat(20_000)).as_bytes());
}

/// Small hand-picked oddities.
#[test]
fn oddities() {
    let inputs: &[&[u8]] = &[
        b"",
        b" ",
        b"\0",
        b"\xff",
        b"\xc3",
        b"space 2d;\xff",
        b"/*",
        b"/* */",
        b"*/",
        b"//",
        b";",
        b";;;;",
        b"}",
        b"{",
        b"}{",
        b"space",
        b"space 3d",
        b"space 3d;",
        b"space 2d; space 3d;",
        b"space 99999999999999999999999d;",
        b"space 2d; param p = 1e999999999;",
        b"space 2d; param p = 1e;",
        b"space 2d; param p = 0/0;",
        b"space 2d; param p = 1/0;",
        b"space 2d; param p = p;",
        b"space 2d; param p = q; param q = p;",
        b"space 2d; param p = 1 deg deg;",
        b"space 2d; param p = 18446744073709551616;",
        b"space 2d; body b { body c { } }",
        b"space 2d; body b { point p = (0, 0); } body b { }",
        b"space 2d; point p = (0, 0) -> (1, 1) -> ;",
        b"space 2d; drive: drive: angle(X, X) = 1;",
        b"space 2d; fixed fixed point p = (0, 0);",
        b"space 2d; output ;",
        b"space 2d; output a.b.c.d.e.f;",
        b"space 3d; marker k = (0,0,0) z (0,0,1) x (1,0,0);",
        b"space 3d; marker k = z x;",
        b"space 2d; \xc3\xa9 = 1;",
        b"space 2d; param \xc3\xa9 = 1;",
        b"space 2d; param p = 1;\xf0\x9f\x98\x80",
        b"space 2d; param p = (1, 2);",
        b"space 2d; param p = sqrt();",
        b"space 2d; param p = sqrt(1, 2, 3);",
        b"space 2d; param p = atan2(1);",
        b"space 2d; coincident();",
        b"space 2d; coincident(,);",
        b"space 2d; x: ;",
    ];
    for input in inputs {
        check(input);
    }
}
