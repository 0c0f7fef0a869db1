//! A large model's solver as a few functions and tables of their data (issue 22).
//!
//! The flat solve is one straight function, a group of steps after another; rustc's time on
//! one function grows faster than its length, so a chain of 10,000 four-bars (a million lines)
//! does not build. But a large model is a few local problems repeated: its groups differ only
//! in which geoms they read and move, in their constants and in the names their errors give.
//! So the flat solve's declarations and step groups, taken `PIECE_GROUPS` at a time (what
//! crosses groups inside a piece stays in its locals, and one call does the work of several),
//! are cut out as *pieces*, each reduced to its *shape*: its tokens with the locals it reads
//! from earlier pieces, its number and string literals, and its reads of params, branches and
//! defaults abstracted.
//! Pieces of one shape become one function, written from the first of them (its
//! *representative*, whose comment it keeps); the rest is data: a table row per piece (the
//! slots it reads and writes in the solve's store, its constants, its error names) and the
//! order in which `solve_into` calls them. The generated text grows with the number of
//! distinct shapes, plus the tables.
//!
//! What crosses pieces lives in a `Store`, one boxed slice per Rust type, which the
//! `Solution` owns: a piece loads what it reads, runs its representative's code unchanged,
//! and stores what it moves and what later pieces read. The `Solution`, `Branches` and
//! `Defaults` of a large model read and set values by name through sorted tables and list
//! each kind in model order; their layout is not one field per value.
//!
//! Only plans without outer iterations are laid out so (their trial closure is not a
//! sequence of pieces), and only when every value that crosses pieces has a type the store
//! holds; any other plan keeps the flat solve, whatever its size.
//!
//! [`super::Form::Auto`] tables a plan whose flat solve's steps would be `TABLED_LINES` lines
//! or more: there the flat solve outgrows the instruction cache and rustc's patience, while
//! below it a piece's call costs more than it saves. Tables are arrays of numbers: every
//! string (error names, dotted names, branch meanings) is one `STRINGS` literal with offsets,
//! since rustc's time grows with string literals; a row's comment gives its constraint with
//! `file:line`, and the data follows a `format::DATA` line, which `format` leaves as written. A
//! piece stores back only what its code may change (assigns, lends `&mut`, or moves with a
//! runtime frame method); anything else it loads is bound without `mut`, so a change missed
//! there is a compile error, not a lost write.

use super::api::{self, Layout, Ty as ApiTy};
use super::context::Context;
use super::solve::{self, Parts};
use super::writer::{float, lit, Writer};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// `Form::Auto` lays out as tables a plan whose flat solve would have at least this many
/// lines of steps (before rustfmt, which makes them two to three times as many), and keeps
/// smaller ones flat: readable, a comment a step. Measured with `gcs bench --form`
/// (docs/BENCHMARKS.md, "Large models build in seconds"), pieces of `PIECE_GROUPS` groups: the
/// flat solve is 1.17x faster for the closed profile of 64 arcs (about 4,200 lines), the tabled
/// one 1.3x faster for the chain of 128 four-bars (2,500 lines), 2.8x for the closed profile
/// of 256 arcs (17,000) and 2.2x for the chain of 1,024 (19,900), whose flat solve also takes
/// two minutes to build in debug.
pub(super) const TABLED_LINES: usize = 12_000;

/// Plans of fewer steps are never laid out as tables by `Form::Auto`: too small to reach
/// [`TABLED_LINES`], and then not worth writing the flat solve's parts twice to find out.
pub(super) const TABLED_STEPS: usize = 1024;

/// How many declarations or step groups one piece holds.
const PIECE_GROUPS: usize = 8;

/// The kinds of a token of the generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tok {
    Ident,
    Float,
    Int,
    Str,
    Punct,
    Comment,
}

/// A token: its kind and its byte range in the text.
#[derive(Clone, Copy, Debug)]
struct Token {
    kind: Tok,
    start: usize,
    end: usize,
}

/// The tokens of generated Rust code, whitespace left out (it stays between the ranges).
fn tokens(text: &str) -> Vec<Token> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    while i < b.len() {
        let c = b[i];
        let start = i;
        let kind = if c.is_ascii_whitespace() {
            i += 1;
            continue;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            Tok::Comment
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            Tok::Str
        } else if c.is_ascii_digit() {
            let mut float = false;
            while i < b.len() {
                let d = b[i];
                if d.is_ascii_digit() || d == b'_' {
                    i += 1;
                } else if d == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit) && !float {
                    float = true;
                    i += 1;
                } else if (d == b'e' || d == b'E')
                    && (b.get(i + 1).is_some_and(u8::is_ascii_digit)
                        || (matches!(b.get(i + 1), Some(b'-' | b'+'))
                            && b.get(i + 2).is_some_and(u8::is_ascii_digit)))
                {
                    float = true;
                    i += 2;
                } else {
                    break;
                }
            }
            // A suffix (`1u8`) makes the literal typed: it is not a constant of the table.
            let suffixed = i < b.len() && ident(b[i]);
            while i < b.len() && ident(b[i]) {
                i += 1;
            }
            match (float, suffixed) {
                (true, false) => Tok::Float,
                _ => Tok::Int,
            }
        } else if ident(c) {
            while i < b.len() && ident(b[i]) {
                i += 1;
            }
            Tok::Ident
        } else if c == b'\'' {
            i += 1;
            while i < b.len() && ident(b[i]) {
                i += 1;
            }
            Tok::Punct
        } else if c == b':' && b.get(i + 1) == Some(&b':') {
            i += 2;
            Tok::Punct
        } else {
            // One character; a multi-byte one whole.
            i += text[i..].chars().next().map_or(1, char::len_utf8);
            Tok::Punct
        };
        out.push(Token {
            kind,
            start,
            end: i,
        });
    }
    out
}

/// Words that are never a value's name. A primitive type's name (`f32`) can be one: a geom
/// called so has a local of that name, and the type keeps its own namespace.
const KEYWORDS: [&str; 19] = [
    "as", "break", "continue", "else", "false", "fn", "for", "if", "in", "let", "loop", "match",
    "move", "mut", "ref", "return", "self", "true", "while",
];

/// The inputs a piece reads by field: `params.x`, `branches.x`, `defaults.x`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Input {
    Param,
    Branch,
    Default,
}

/// What a token of a piece is, for its shape.
#[derive(Clone, Debug, PartialEq)]
enum Role {
    /// Code as it is.
    Code,
    /// A comment: not part of the shape.
    Comment,
    /// The `n`th value the piece reads from an earlier piece.
    Outer(usize),
    /// The `n`th local of the piece (its own `let`s, closure arguments).
    Local(usize),
    /// The `n`th number literal.
    Constant(usize),
    /// The `n`th string literal.
    Text(usize),
    /// The `n`th input read by field, spanning three tokens (`params`, `.`, the field).
    Input(usize, Input),
    /// The second or third token of an input.
    Covered,
}

/// A piece cut into the roles of its tokens.
struct Cut {
    text: String,
    /// The comment lines that open it (the constraints its steps satisfy), apart.
    comment: Vec<String>,
    tokens: Vec<Token>,
    roles: Vec<Role>,
    /// Names of the values read from earlier pieces, in order of first read.
    outer: Vec<String>,
    /// The piece's locals, in order of first appearance, and which of them it binds with
    /// `let`.
    locals: Vec<String>,
    declared: HashSet<String>,
    /// Declared with `let mut`.
    mutable: HashSet<String>,
    constants: Vec<String>,
    texts: Vec<String>,
    /// Each input's kind and field name.
    inputs: Vec<(Input, String)>,
    /// Its shape but for what it stores, once known.
    key: Option<String>,
    /// The constraint (and `file:line`) of each group it holds.
    constraints: Vec<String>,
    /// Whether it has code (a group whose steps move nothing has only its comment).
    has_code: bool,
}

impl Cut {
    fn new(text: String, is_outer: &dyn Fn(&str) -> bool) -> Cut {
        // The opening comment lines go to the doc of the piece's function.
        let mut comment = Vec::new();
        let mut body_at = 0;
        for line in text.split_inclusive('\n') {
            let trimmed = line.trim();
            if trimmed.is_empty() && comment.is_empty() {
                body_at += line.len();
                continue;
            }
            match trimmed.strip_prefix("// ") {
                Some(c) if !c.starts_with("Already true") => {
                    comment.push(c.to_string());
                    body_at += line.len();
                }
                _ => break,
            }
        }
        let text = text[body_at..].to_string();
        let tokens = tokens(&text);
        let word = |k: usize| -> &str {
            match tokens.get(k) {
                Some(t) => &text[t.start..t.end],
                None => "",
            }
        };
        // The code tokens around token `k`, comments skipped.
        let code_before = |k: usize| {
            (0..k)
                .rev()
                .find(|&j| tokens[j].kind != Tok::Comment)
                .map_or("", word)
        };
        let mut cut = Cut {
            comment,
            roles: Vec::with_capacity(tokens.len()),
            outer: Vec::new(),
            locals: Vec::new(),
            declared: HashSet::default(),
            mutable: HashSet::default(),
            constants: Vec::new(),
            texts: Vec::new(),
            inputs: Vec::new(),
            tokens: Vec::new(),
            text: String::new(),
            key: None,
            constraints: Vec::new(),
            has_code: false,
        };
        let mut outer_at: HashMap<String, usize> = HashMap::default();
        let mut local_at: HashMap<String, usize> = HashMap::default();
        let mut k = 0;
        while k < tokens.len() {
            let t = tokens[k];
            let w = word(k);
            let role = match t.kind {
                Tok::Comment => Role::Comment,
                Tok::Float => {
                    cut.constants.push(w.to_string());
                    Role::Constant(cut.constants.len() - 1)
                }
                Tok::Str => {
                    cut.texts.push(w.to_string());
                    Role::Text(cut.texts.len() - 1)
                }
                // A negated number is one constant, sign and all, so that pieces alike but
                // for the signs of their numbers (directions in every quadrant) share a
                // shape; not before a method call, which binds tighter than the sign.
                Tok::Punct
                    if w == "-"
                        && tokens.get(k + 1).is_some_and(|t| t.kind == Tok::Float)
                        && word(k + 2) != "."
                        && matches!(code_before(k), "(" | "," | "[" | "=" | "{") =>
                {
                    cut.constants.push(format!("-{}", word(k + 1)));
                    cut.roles.push(Role::Constant(cut.constants.len() - 1));
                    cut.roles.push(Role::Covered);
                    k += 2;
                    continue;
                }
                Tok::Int | Tok::Punct => Role::Code,
                Tok::Ident => {
                    let before = code_before(k);
                    let (next, after) = (word(k + 1), word(k + 2));
                    let input = match w {
                        "params" => Some(Input::Param),
                        "branches" => Some(Input::Branch),
                        "defaults" => Some(Input::Default),
                        _ => None,
                    };
                    if let (Some(input), ".", true, false) = (
                        input,
                        next,
                        tokens.get(k + 2).is_some_and(|t| t.kind == Tok::Ident),
                        before == ".",
                    ) {
                        cut.inputs.push((input, after.to_string()));
                        let n = cut.inputs.len() - 1;
                        cut.roles.push(Role::Input(n, input));
                        cut.roles.push(Role::Covered);
                        cut.roles.push(Role::Covered);
                        k += 3;
                        continue;
                    }
                    let first = w.as_bytes()[0];
                    let is_code = first.is_ascii_uppercase()
                        || KEYWORDS.contains(&w)
                        || before == "."
                        || before == "::"
                        || next == "::"
                        || next == "!"
                        || (next == "(" && !local_at.contains_key(w));
                    if is_code {
                        Role::Code
                    } else if is_outer(w) && !local_at.contains_key(w) {
                        let n = cut.outer.len();
                        let n = *outer_at.entry(w.to_string()).or_insert(n);
                        if n == cut.outer.len() {
                            cut.outer.push(w.to_string());
                        }
                        Role::Outer(n)
                    } else {
                        if before == "let" || (before == "mut" && code_before(k - 1) == "let") {
                            cut.declared.insert(w.to_string());
                            if before == "mut" {
                                cut.mutable.insert(w.to_string());
                            }
                        }
                        let n = cut.locals.len();
                        let n = *local_at.entry(w.to_string()).or_insert(n);
                        if n == cut.locals.len() {
                            cut.locals.push(w.to_string());
                        }
                        Role::Local(n)
                    }
                }
            };
            cut.roles.push(role);
            k += 1;
        }
        cut.tokens = tokens;
        cut.text = text;
        cut
    }

    /// Whether the code may change the `n`th value it reads: assigns it (or a field of it),
    /// lends it `&mut`, or calls a method of the runtime's that moves a frame on it. The
    /// others are not stored back.
    fn writes(&self, n: usize) -> bool {
        const MOVES: [&str; 7] = [
            "place_origin",
            "rotate_about",
            "rotate_about_by",
            "scale_about",
            "set_rotation",
            "translate",
            "turn_by",
        ];
        let code: Vec<usize> = (0..self.tokens.len())
            .filter(|&k| self.roles[k] != Role::Comment)
            .collect();
        let word = |i: usize| code.get(i).map_or("", |&k| self.word(k));
        (0..code.len()).any(|i| {
            if self.roles[code[i]] != Role::Outer(n) {
                return false;
            }
            if i >= 2 && word(i - 1) == "mut" && word(i - 2) == "&" {
                return true;
            }
            // Past its fields (`x.origin.y`) to what follows.
            let mut j = i + 1;
            while word(j) == "." && !MOVES.contains(&word(j + 1)) && word(j + 2) != "(" {
                j += 2;
            }
            let assigned = (word(j) == "=" && word(j + 1) != "=")
                || (matches!(word(j), "+" | "-" | "*" | "/") && word(j + 1) == "=");
            assigned || (word(j) == "." && MOVES.contains(&word(j + 1)))
        })
    }

    /// The text of token `k`.
    fn word(&self, k: usize) -> &str {
        let t = self.tokens[k];
        &self.text[t.start..t.end]
    }
}

/// Where a value that crosses pieces lives: the store's slice of its type and its index.
#[derive(Clone, Debug)]
struct Slot {
    ty: &'static str,
    index: usize,
    mutable: bool,
}

/// The store's slice of values of Rust type `ty`, with the value it starts at; `None` for a
/// type it does not hold.
fn store_slice(ty: &str) -> Option<(&'static str, &'static str)> {
    Some(match ty {
        "Frame2" => ("frame2", "Frame2::default()"),
        "Frame3" => ("frame3", "Frame3::default()"),
        "f64" => ("scalar", "0.0"),
        "Point2<f64>" => ("point2", "Point2::origin()"),
        "Point3<f64>" => ("point3", "Point3::origin()"),
        "Vector2<f64>" => ("vector2", "Vector2::zeros()"),
        "Vector3<f64>" => ("vector3", "Vector3::zeros()"),
        "gcs_runtime::locus2d::Line" => ("line2", "Default::default()"),
        "gcs_runtime::locus2d::Circle" => ("circle2", "Default::default()"),
        "gcs_runtime::locus3d::Line3" => ("line3", "Default::default()"),
        "gcs_runtime::locus3d::Circle3" => ("circle3", "Default::default()"),
        "gcs_runtime::locus3d::Plane" => ("plane3", "Default::default()"),
        "gcs_runtime::locus3d::Sphere" => ("sphere3", "Default::default()"),
        "gcs_runtime::locus3d::Cylinder" => ("cylinder3", "Default::default()"),
        "gcs_runtime::locus3d::Torus" => ("torus3", "Default::default()"),
        _ => return None,
    })
}

/// The Rust type of a register of plan type `ty`, if the store holds it.
fn register_type(ty: crate::plan::Ty, d3: bool) -> Option<&'static str> {
    use crate::plan::Ty;
    Some(match (ty, d3) {
        (Ty::Scalar, _) => "f64",
        (Ty::Point, false) => "Point2<f64>",
        (Ty::Point, true) => "Point3<f64>",
        (Ty::Vector, false) => "Vector2<f64>",
        (Ty::Vector, true) => "Vector3<f64>",
        (Ty::Line, false) => "gcs_runtime::locus2d::Line",
        (Ty::Circle, false) => "gcs_runtime::locus2d::Circle",
        (Ty::Line, true) => "gcs_runtime::locus3d::Line3",
        (Ty::Circle, true) => "gcs_runtime::locus3d::Circle3",
        (Ty::Plane, _) => "gcs_runtime::locus3d::Plane",
        (Ty::Sphere, _) => "gcs_runtime::locus3d::Sphere",
        (Ty::Cylinder, _) => "gcs_runtime::locus3d::Cylinder",
        (Ty::Torus, _) => "gcs_runtime::locus3d::Torus",
        _ => return None,
    })
}

/// One piece placed: its shape's number, and its row of that shape's table.
struct Placed {
    shape: usize,
    row: usize,
}

/// A shape: its representative piece and the rows of every piece of that shape.
struct Shape {
    representative: Cut,
    /// Per row: the slots of the values read, then of those written; constants; texts;
    /// input indices.
    rows: Vec<Row>,
    /// The locals it declares that later pieces read (stored after its code).
    written: Vec<String>,
}

/// One piece's data in its shape's table.
struct Row {
    /// The first line of the piece's opening comment (its constraint and `file:line`).
    comment: Option<String>,
    slots: Vec<usize>,
    constants: Vec<String>,
    texts: Vec<String>,
    inputs: Vec<usize>,
}

/// The whole module of a large model, or `None` when its plan is not laid out as tables.
pub(super) fn module(cx: &Context<'_>, layout: &Layout, min_lines: usize) -> Option<String> {
    let parts = solve::parts(cx, layout)?;
    let lines: usize = parts.groups.iter().map(|g| g.lines().count()).sum();
    if lines < min_lines {
        return None;
    }
    let Parts {
        sketch_checks,
        bindings,
        tol,
        tol_terms,
        groups,
        fields,
        typed,
        dims,
    } = parts;
    let d3 = cx.d3;
    // The pieces in order: the sketch's declarations, the tolerance, the groups, and a
    // last piece per solution field whose value is code, not a local.
    let mut texts: Vec<(String, Option<&'static str>, bool)> = Vec::new();
    for (b, ty) in &bindings {
        let m = if b.mutable { "mut " } else { "" };
        texts.push((
            format!("let {m}{} = {};\n", b.name, b.value),
            Some(ty),
            b.mutable,
        ));
    }
    // The tolerance: a literal, or the scale of the sketch's geoms taken geom by geom, as a
    // running maximum (the same value: `tol::scale` is the largest magnitude).
    match tol.as_deref().map(|t| (t, literal_tol(t))) {
        None => {}
        Some((_, Some(value))) => {
            texts.push((format!("let tol = {};\n", float(value)), Some("f64"), false));
        }
        Some((_, None)) => {
            texts.push((
                "let mut tol_scale: f64 = 1e-300;\n".to_string(),
                Some("f64"),
                true,
            ));
            for terms in tol_terms.iter().filter(|t| !t.is_empty()) {
                texts.push((
                    format!(
                        "tol_scale = tol_scale.max(gcs_runtime::tol::scale(&[{}]));\n",
                        terms.join(", ")
                    ),
                    None,
                    false,
                ));
            }
            texts.push((
                "let tol = gcs_runtime::tol::CHECK_REL * (1.0 + tol_scale);\n".to_string(),
                Some("f64"),
                false,
            ));
        }
    }
    for g in groups {
        texts.push((g, None, false));
    }
    let mut field_names = Vec::new();
    let mut extra = 0;
    for (field, value) in layout.fields.iter().zip(&fields) {
        let is_local = value
            .bytes()
            .all(|c| c.is_ascii_alphanumeric() || c == b'_');
        if is_local {
            field_names.push(value.clone());
        } else {
            let name = format!("field_value_{extra}");
            extra += 1;
            let ty = field.ty.rust(d3);
            texts.push((format!("let {name} = {value};\n"), Some(ty), false));
            field_names.push(name);
        }
    }
    // The type of what each declaration declares (its first `let`).
    let mut known: HashMap<String, (&'static str, bool)> = HashMap::default();
    for (text, ty, mutable) in &texts {
        if let Some(ty) = ty {
            let rest = text.trim_start().strip_prefix("let ").unwrap_or("");
            let rest = rest.strip_prefix("mut ").unwrap_or(rest);
            let name: String = (rest.chars())
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            known.insert(name, (ty, *mutable));
        }
    }
    // Pieces of `PIECE_GROUPS` declarations or groups each, each with the constraint of every
    // group it holds: what crosses groups inside a piece stays in its locals, and a call
    // does the work of several.
    let mut pieces: Vec<(String, Vec<String>)> = Vec::new();
    for window in texts.chunks(PIECE_GROUPS) {
        let text: String = window.iter().map(|(t, ..)| t.as_str()).collect();
        let constraints = (window.iter())
            .filter_map(|(t, ..)| {
                let line = t.trim_start().lines().next()?;
                line.strip_prefix("// ").map(str::to_string)
            })
            .filter(|c| c.ends_with(')'))
            .collect();
        pieces.push((text, constraints));
    }
    // Pass one: what each piece declares and reads, so that only values read later (or
    // reported) are stored.
    let mut declared_by: HashMap<String, (&'static str, bool)> = HashMap::default();
    let mut cuts = Vec::with_capacity(pieces.len());
    let mut earlier: HashMap<String, Slot> = HashMap::default();
    // The piece that declares each name: what piece `i` reads from before it.
    let mut declared_in: HashMap<String, usize> = HashMap::default();
    for (i, (text, constraints)) in pieces.into_iter().enumerate() {
        let mut cut = Cut::new(text, &|w| earlier.contains_key(w));
        cut.constraints = constraints;
        for name in &cut.declared {
            let (ty, mutable) = match known.get(name) {
                Some(&known) => known,
                None if dims.contains(name) => ("f64", false),
                None => (
                    typed
                        .get(name)
                        .and_then(|&t| register_type(t, d3))
                        .unwrap_or("?"),
                    false,
                ),
            };
            let m = mutable || cut.mutable.contains(name);
            declared_by.insert(name.clone(), (ty, m));
            declared_in.insert(name.clone(), i);
            earlier.insert(
                name.clone(),
                Slot {
                    ty,
                    index: 0,
                    mutable: m,
                },
            );
        }
        // Its shape but for what it stores (known once every piece is read); its tokens are
        // cut again for the first piece of each shape only: a large model keeps no more.
        cut.key = shape_key(&cut, &earlier);
        cut.has_code = cut.roles.iter().any(|r| *r != Role::Comment);
        cut.tokens = Vec::new();
        cut.roles = Vec::new();
        cuts.push(cut);
    }
    let mut read: HashSet<&str> = field_names.iter().map(String::as_str).collect();
    for cut in &cuts {
        read.extend(cut.outer.iter().map(String::as_str));
    }
    // Slots for the values read across pieces, in order of declaration.
    let mut slots: HashMap<String, Slot> = HashMap::default();
    let mut counts: BTreeMap<&'static str, usize> = BTreeMap::new();
    for cut in &cuts {
        let mut names: Vec<&String> = cut
            .locals
            .iter()
            .filter(|n| cut.declared.contains(*n))
            .collect();
        names.retain(|n| read.contains(n.as_str()));
        for name in names {
            let (ty, mutable) = declared_by[name];
            store_slice(ty)?;
            let count = counts.entry(ty).or_default();
            slots.insert(
                name.clone(),
                Slot {
                    ty,
                    index: *count,
                    mutable,
                },
            );
            *count += 1;
        }
    }
    // Pass two: shapes and rows.
    let params: HashMap<&str, usize> = (cx.model.params.iter().enumerate())
        .map(|(k, (id, _))| (cx.params[&id].as_str(), k))
        .collect();
    let branch_at: HashMap<&str, usize> = (cx.branches.iter().enumerate())
        .map(|(k, f)| (f.as_str(), k))
        .collect();
    let default_at: HashMap<&str, usize> = (cx.defaults.iter().enumerate())
        .map(|(k, f)| (f.as_str(), k))
        .collect();
    let mut shapes: Vec<Shape> = Vec::new();
    let mut by_key: HashMap<String, usize> = HashMap::default();
    let mut order: Vec<Placed> = Vec::new();
    for (i, cut) in cuts.into_iter().enumerate() {
        // A group whose steps move nothing has no code: no piece.
        if !cut.has_code {
            continue;
        }
        let written: Vec<String> = (cut.locals.iter())
            .filter(|n| cut.declared.contains(*n) && slots.contains_key(*n))
            .cloned()
            .collect();
        let mut key = cut.key.clone()?;
        for name in &written {
            let local = cut.locals.iter().position(|l| l == name)?;
            let _ = write!(key, "| $l{local}:{}", slots[name].ty);
        }
        let mut row = Row {
            comment: (!cut.constraints.is_empty()).then(|| cut.constraints.join("; ")),
            slots: Vec::new(),
            constants: cut.constants.clone(),
            texts: cut.texts.clone(),
            inputs: Vec::new(),
        };
        for name in cut.outer.iter().chain(&written) {
            row.slots.push(slots.get(name)?.index);
        }
        for (input, field) in &cut.inputs {
            let at = match input {
                Input::Param => params.get(field.as_str()),
                Input::Branch => branch_at.get(field.as_str()),
                Input::Default => default_at.get(field.as_str()),
            };
            row.inputs.push(*at?);
        }
        let shape = *by_key.entry(key).or_insert_with(|| {
            let mut representative = Cut::new(cut.text.clone(), &|w| {
                declared_in.get(w).is_some_and(|&j| j < i)
            });
            representative.comment = cut.comment.clone();
            shapes.push(Shape {
                representative,
                rows: Vec::new(),
                written,
            });
            shapes.len() - 1
        });
        order.push(Placed {
            shape,
            row: shapes[shape].rows.len(),
        });
        shapes[shape].rows.push(row);
    }
    let accessors = accessor_shapes(cx, layout, &field_names, &slots)?;
    let mut w = Writer::default();
    api::params(&mut w, cx);
    let mut tables = String::new();
    let mut strings = Strings::default();
    inputs(&mut w, &mut tables, &mut strings, cx, true);
    inputs(&mut w, &mut tables, &mut strings, cx, false);
    solution(
        &mut w,
        &mut tables,
        cx,
        &counts,
        &accessors,
        &slots,
        &mut strings,
    );
    solve(
        &mut w,
        &mut tables,
        cx,
        &sketch_checks,
        (&shapes, &order),
        &slots,
        &mut strings,
    );
    strings.write(&mut w, &mut tables);
    // The tables last, after the line that tells `format` to leave them as written.
    w.line(super::format::DATA);
    w.line("");
    w.out.push_str(&tables);
    Some(w.out)
}

/// The tolerance's value when the flat solve computes it from constants alone.
fn literal_tol(line: &str) -> Option<f64> {
    let rest = line.strip_prefix("let tol = ")?;
    let value = rest.split(';').next()?;
    value.trim().parse().ok()
}

/// The shape of a piece but for what it stores: its tokens with values read, locals,
/// literals and inputs abstracted.
fn shape_key(cut: &Cut, slots: &HashMap<String, Slot>) -> Option<String> {
    let mut key = String::new();
    for (k, role) in cut.roles.iter().enumerate() {
        match role {
            Role::Code => key.push_str(cut.word(k)),
            Role::Comment | Role::Covered => continue,
            Role::Outer(n) => {
                let slot = slots.get(&cut.outer[*n])?;
                let _ = write!(key, "$o{n}:{}:{}", slot.ty, slot.mutable);
            }
            Role::Local(n) => {
                let _ = write!(key, "$l{n}");
            }
            Role::Constant(_) => key.push_str("$k"),
            Role::Text(_) => key.push_str("$t"),
            Role::Input(_, input) => {
                let _ = write!(key, "$i{input:?}");
            }
        }
        key.push(' ');
    }
    Some(key)
}

/// The accessors of a large model's solution, by kind: each a shape of the accessor bodies
/// of the flat API (`self.field` abstracted to a slot, numbers to constants) and a table of
/// the values of that kind, by dotted name.
struct Accessors {
    kinds: Vec<AccessKind>,
}

struct AccessKind {
    ty: ApiTy,
    /// Each shape: its body, with `{at}` and `{k}` placeholders replaced when written.
    shapes: Vec<Cut>,
    /// Per value: its dotted name, its shape, its slots and constants.
    rows: Vec<(String, usize, Vec<usize>, Vec<String>)>,
}

fn accessor_shapes(
    cx: &Context<'_>,
    layout: &Layout,
    field_names: &[String],
    slots: &HashMap<String, Slot>,
) -> Option<Accessors> {
    // `self.field` becomes the field's local in the solve, whose slot is known.
    let field_local: HashMap<&str, &str> = (layout.fields.iter())
        .zip(field_names)
        .map(|(f, n)| (f.name.as_str(), n.as_str()))
        .collect();
    let mut kinds: Vec<AccessKind> = Vec::new();
    let all = api::accessors(cx, layout).0;
    for ty in [ApiTy::Frame, ApiTy::Point, ApiTy::Vector, ApiTy::Scalar] {
        let mut kind = AccessKind {
            ty,
            shapes: Vec::new(),
            rows: Vec::new(),
        };
        let mut by_key: HashMap<String, usize> = HashMap::default();
        for (a, _) in &all {
            if a.ty != ty {
                continue;
            }
            // `self.x` as the local `x` of the solve.
            let mut body = a.body.clone();
            let toks = tokens(&body);
            let mut out = String::new();
            let mut at = 0;
            let mut k = 0;
            while k < toks.len() {
                let t = toks[k];
                let w = &body[t.start..t.end];
                if w == "self"
                    && toks
                        .get(k + 1)
                        .is_some_and(|t| &body[t.start..t.end] == ".")
                    && toks.get(k + 2).is_some()
                {
                    let f = toks[k + 2];
                    let field = &body[f.start..f.end];
                    if let Some(local) = field_local.get(field) {
                        out.push_str(&body[at..t.start]);
                        out.push_str(local);
                        at = f.end;
                        k += 3;
                        continue;
                    }
                }
                k += 1;
            }
            out.push_str(&body[at..]);
            body = out;
            let cut = Cut::new(format!("{body}\n"), &|w| slots.contains_key(w));
            let key = shape_key(&cut, slots)?;
            let row_slots: Option<Vec<usize>> = cut
                .outer
                .iter()
                .map(|n| slots.get(n).map(|s| s.index))
                .collect();
            let row = (a.name.clone(), 0, row_slots?, cut.constants.clone());
            let n = *by_key.entry(key).or_insert_with(|| {
                kind.shapes.push(cut);
                kind.shapes.len() - 1
            });
            kind.rows.push((row.0, n, row.2, row.3));
        }
        kinds.push(kind);
    }
    Some(Accessors { kinds })
}

/// The code of a piece's representative, each literal and input read from its row where
/// `*_at` gives its place there (`None`: the same in every row, written as it is), and its
/// values read by the names it had (loaded before it runs).
fn body(cut: &Cut, k_at: &[Option<usize>], t_at: &[Option<usize>], in_at: &[InputAt]) -> String {
    let mut out = String::new();
    let mut at = 0;
    for (k, role) in cut.roles.iter().enumerate() {
        let t = cut.tokens[k];
        let replacement = match role {
            Role::Constant(n) => k_at[*n].map(|i| format!("row.k[{i}]")),
            Role::Text(n) => t_at[*n].map(|i| format!("text(row.text[{i}])")),
            Role::Input(n, input) => {
                let field = &cut.inputs[*n].1;
                let index = match in_at[*n] {
                    InputAt::Row(i) => format!("row.input[{i}] as usize"),
                    InputAt::Fixed(i) => i.to_string(),
                };
                Some(match (input, in_at[*n]) {
                    (Input::Param, InputAt::Fixed(_)) => format!("params.{field}"),
                    (Input::Param, InputAt::Row(_)) => format!("p[{index}]"),
                    (Input::Branch, _) => format!("branches.indices[{index}]"),
                    (Input::Default, _) => format!("defaults.values[{index}]"),
                })
            }
            _ => None,
        };
        let Some(replacement) = replacement else {
            continue;
        };
        out.push_str(&cut.text[at..t.start]);
        out.push_str(&replacement);
        at = t.end;
        match role {
            // The input spans three tokens.
            Role::Input(..) => at = cut.tokens[k + 2].end,
            // A negated number spans two.
            Role::Constant(_) if cut.roles.get(k + 1) == Some(&Role::Covered) => {
                at = cut.tokens[k + 1].end;
            }
            _ => {}
        }
    }
    out.push_str(&cut.text[at..]);
    out
}

/// Where a piece's function finds an input: the same for every row, or in the row.
#[derive(Clone, Copy, Debug)]
enum InputAt {
    Fixed(usize),
    Row(usize),
}

/// For each of `n` values, its place among the values that differ between `rows` (`None`
/// when all rows have the same); values equal to an earlier one in every row share its place.
fn varying<T: PartialEq>(
    n: usize,
    rows: &[Row],
    get: impl Fn(&Row, usize) -> T,
) -> Vec<Option<usize>> {
    let mut places: Vec<Option<usize>> = Vec::with_capacity(n);
    let mut next = 0;
    for i in 0..n {
        let first = get(&rows[0], i);
        if rows.iter().all(|r| get(r, i) == first) {
            places.push(None);
            continue;
        }
        let same =
            (0..i).find(|&j| places[j].is_some() && rows.iter().all(|r| get(r, i) == get(r, j)));
        match same {
            Some(j) => places.push(places[j]),
            None => {
                places.push(Some(next));
                next += 1;
            }
        }
    }
    places
}

/// The values of `row` at the places `at` gives, each place once, in place order.
fn at_places<T: Clone>(at: &[Option<usize>], values: &[T]) -> Vec<T> {
    let mut out: Vec<(usize, T)> = Vec::new();
    for (i, place) in at.iter().enumerate() {
        if let Some(p) = place {
            if !out.iter().any(|(q, _)| q == p) {
                out.push((*p, values[i].clone()));
            }
        }
    }
    out.sort_by_key(|(p, _)| *p);
    out.into_iter().map(|(_, v)| v).collect()
}

/// `Branches` (`branch`) or `Defaults` of a large model: the values in an array in model
/// order, set and read by name through a sorted table.
fn inputs(
    w: &mut Writer,
    tables: &mut String,
    strings: &mut Strings,
    cx: &Context<'_>,
    branch: bool,
) {
    let (name, ty, what, list): (&str, &str, &str, Vec<(String, String)>) = if branch {
        let list = (cx.plan.branches.iter())
            .map(|b| (b.name.clone(), b.default.to_string()))
            .collect();
        ("Branches", "u8", "branch variable", list)
    } else {
        let sketch = cx.plan.sketch_defaults();
        let list = (cx.plan.defaults.iter().zip(sketch))
            .map(|(d, v)| (d.name.clone(), float(v)))
            .collect();
        ("Defaults", "f64", "default", list)
    };
    let upper = name.to_uppercase();
    let field = if branch { "indices" } else { "values" };
    let n = list.len();
    let eq = if branch { ", Eq" } else { "" };
    if branch {
        w.line("/// Which assembly: an index per branch variable, in model order, each with a geometric");
        w.line("/// meaning (`Branches::meaning`). Set and read by the variable's name.");
    } else {
        w.line("/// Values of the degrees of freedom the analysis had to default, in model order. Set and");
        w.line("/// read by the default's name.");
    }
    w.line(&format!("#[derive(Clone, Copy, Debug, PartialEq{eq})]"));
    w.open(&format!("pub struct {name} {{"));
    w.line(&format!("{field}: [{ty}; {n}],"));
    w.close("}");
    w.line("");
    w.line("#[allow(dead_code)]");
    w.open(&format!("impl {name} {{"));
    w.line(&format!(
        "/// Sets the {what} called `name` (as in the model); `false` when there is none."
    ));
    w.open(&format!(
        "pub fn set(&mut self, name: &str, value: {ty}) -> bool {{"
    ));
    w.open(&format!("match find(&{upper}_BY_NAME, name) {{"));
    w.open("Some(k) => {");
    w.line(&format!("self.{field}[k] = value;"));
    w.line("true");
    w.close("}");
    w.line("None => false,");
    w.close("}");
    w.close("}");
    w.line("");
    w.line(&format!("/// The {what} called `name`, if there is one."));
    w.open(&format!("pub fn get(&self, name: &str) -> Option<{ty}> {{"));
    w.line(&format!(
        "find(&{upper}_BY_NAME, name).map(|k| self.{field}[k])"
    ));
    w.close("}");
    w.line("");
    w.line(&format!(
        "/// Every {what}'s value, in model order (`{name}::names`)."
    ));
    w.open(&format!("pub fn as_slice(&self) -> &[{ty}] {{"));
    w.line(&format!("&self.{field}"));
    w.close("}");
    w.line("");
    w.line(&format!(
        "/// Every {what}'s value, in model order, to set."
    ));
    w.open(&format!("pub fn as_mut_slice(&mut self) -> &mut [{ty}] {{"));
    w.line(&format!("&mut self.{field}"));
    w.close("}");
    w.line("");
    w.line(&format!("/// The {what}s' names, in model order."));
    w.open("pub fn names() -> impl Iterator<Item = &'static str> {");
    w.line(&format!("{upper}_NAMES.iter().map(|&id| text(id))"));
    w.close("}");
    if branch {
        w.line("");
        w.line("/// What index `index` of the branch variable called `name` means, if it has one.");
        w.open("pub fn meaning(name: &str, index: u8) -> Option<&'static str> {");
        w.line("let k = find(&BRANCHES_BY_NAME, name)?;");
        w.line("let first = *BRANCHES_MEANING_AT.get(k)? as usize;");
        w.line("let end = *BRANCHES_MEANING_AT.get(k + 1)? as usize;");
        w.line("let at = first + usize::from(index);");
        w.line("(at < end).then(|| text(BRANCHES_MEANING[at]))");
        w.close("}");
    }
    w.close("}");
    w.line("");
    w.open(&format!("impl Default for {name} {{"));
    w.line(if branch {
        "/// The sketch's assembly."
    } else {
        "/// The sketch's values."
    });
    w.open("fn default() -> Self {");
    w.line(&format!("{name} {{ {field}: {upper}_SKETCH }}"));
    w.close("}");
    w.close("}");
    w.line("");
    // The tables.
    let mut t = String::new();
    let names: Vec<String> = list
        .iter()
        .map(|(n, _)| strings.id(n).to_string())
        .collect();
    table(&mut t, &format!("{upper}_NAMES"), "u32", &names);
    let values: Vec<String> = list.iter().map(|(_, v)| v.clone()).collect();
    table(&mut t, &format!("{upper}_SKETCH"), ty, &values);
    let sorted = by_name(list.iter().map(|(n, _)| n.as_str()), strings);
    table(&mut t, &format!("{upper}_BY_NAME"), "[u32; 2]", &sorted);
    if branch {
        // The meanings of branch `k`: `BRANCHES_MEANING[BRANCHES_MEANING_AT[k]..][..count]`.
        let (mut at, mut ids) = (vec!["0".to_string()], Vec::new());
        for b in &cx.plan.branches {
            ids.extend(b.meanings.iter().map(|m| strings.id(m).to_string()));
            at.push(ids.len().to_string());
        }
        table(&mut t, "BRANCHES_MEANING_AT", "u32", &at);
        table(&mut t, "BRANCHES_MEANING", "u32", &ids);
    }
    tables.push_str(&t);
}

/// The entries `[name's string id, index in model order]` sorted by name, for `find`.
fn by_name<'n>(names: impl Iterator<Item = &'n str>, strings: &mut Strings) -> Vec<String> {
    let mut sorted: Vec<(&str, usize)> = names.enumerate().map(|(k, n)| (n, k)).collect();
    sorted.sort();
    sorted
        .iter()
        .map(|(n, k)| format!("[{}, {k}]", strings.id(n)))
        .collect()
}

/// A static table, one entry a line, left as it is by rustfmt.
fn table(out: &mut String, name: &str, ty: &str, entries: &[String]) {
    let _ = writeln!(out, "#[rustfmt::skip]");
    let _ = writeln!(out, "static {name}: [{ty}; {}] = [", entries.len());
    for e in entries {
        // An entry may end with its comma and a comment.
        let comma = if e.ends_with(',') || e.contains(", //") {
            ""
        } else {
            ","
        };
        let _ = writeln!(out, "    {e}{comma}");
    }
    let _ = writeln!(out, "];\n");
}

/// Every string the tables hold, once: one literal (`STRINGS`) and the byte offset where each
/// starts (`STRING_AT`), read by `text(id)`. rustc's time grows with the number of string
/// literals it is given; one literal of a million names costs little.
#[derive(Default)]
struct Strings {
    text: String,
    at: Vec<u32>,
    ids: HashMap<String, u32>,
}

impl Strings {
    /// The id of string `s` (its content, not a literal).
    fn id(&mut self, s: &str) -> u32 {
        if let Some(&id) = self.ids.get(s) {
            return id;
        }
        if self.at.is_empty() {
            self.at.push(0);
        }
        self.text.push_str(s);
        self.at.push(self.text.len() as u32);
        let id = self.ids.len() as u32;
        self.ids.insert(s.to_string(), id);
        id
    }

    /// The id of the string a generated literal (`"a \"b\""`, as `lit` writes it) holds.
    fn id_of_literal(&mut self, literal: &str) -> u32 {
        self.id(&unescape(literal))
    }

    /// The tables and `text`.
    fn write(&self, w: &mut Writer, tables: &mut String) {
        w.line("/// String `id` of the tables (`STRINGS`, `STRING_AT`).");
        w.open("fn text(id: u32) -> &'static str {");
        w.line("let i = id as usize;");
        w.open("match (STRING_AT.get(i), STRING_AT.get(i + 1)) {");
        w.line(
            "(Some(&from), Some(&to)) => STRINGS.get(from as usize..to as usize).unwrap_or(\"\"),",
        );
        w.line("_ => \"\",");
        w.close("}");
        w.close("}");
        w.line("");
        let _ = writeln!(tables, "#[rustfmt::skip]");
        let _ = writeln!(tables, "static STRINGS: &str = {};\n", lit(&self.text));
        let at: Vec<String> = self.at.iter().map(u32::to_string).collect();
        table(tables, "STRING_AT", "u32", &at);
    }
}

/// The content of a string literal as `lit` (Rust's `Debug`) writes it.
fn unescape(literal: &str) -> String {
    let inner = literal
        .strip_prefix('"')
        .and_then(|l| l.strip_suffix('"'))
        .unwrap_or(literal);
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some('t') => out.push('\t'),
            Some('0') => out.push('\0'),
            Some('u') => {
                let code: String = chars.by_ref().skip(1).take_while(|&c| c != '}').collect();
                if let Some(c) = u32::from_str_radix(&code, 16).ok().and_then(char::from_u32) {
                    out.push(c);
                }
            }
            Some(other) => out.push(other),
            None => {}
        }
    }
    out
}

/// The Solution of a large model: the store the solve works in, read by name.
fn solution(
    w: &mut Writer,
    tables: &mut String,
    cx: &Context<'_>,
    counts: &BTreeMap<&'static str, usize>,
    accessors: &Accessors,
    slots: &HashMap<String, Slot>,
    strings: &mut Strings,
) {
    let d3 = cx.d3;
    w.line("/// Where the solve keeps the values that cross its pieces: a slice per type.");
    w.line("#[derive(Clone, Debug, PartialEq)]");
    w.open("struct Store {");
    for ty in counts.keys() {
        if let Some((slice, _)) = store_slice(ty) {
            w.line(&format!("{slice}: Box<[{ty}]>,"));
        }
    }
    w.close("}");
    w.line("");
    w.open("impl Store {");
    w.open("fn new() -> Store {");
    w.open("Store {");
    for (ty, n) in counts {
        if let Some((slice, zero)) = store_slice(ty) {
            w.line(&format!("{slice}: vec![{zero}; {n}].into_boxed_slice(),"));
        }
    }
    w.close("}");
    w.close("}");
    w.close("}");
    w.line("");
    w.line("/// The solved configuration of every geom the outputs need, read by dotted name (`point`,");
    w.line("/// `vector`, `scalar`, `frame`) or all of one kind in model order (`points`, ...). Made once");
    w.line(
        "/// by `Solution::new` (which allocates its storage) and solved into any number of times.",
    );
    w.line("#[derive(Clone, Debug, PartialEq)]");
    w.open("pub struct Solution {");
    w.line("store: Store,");
    w.line("branches: Branches,");
    w.line("defaults: Defaults,");
    w.close("}");
    w.line("");
    w.line("#[allow(dead_code)]");
    w.open("impl Solution {");
    w.line(
        "/// A solution to solve into: its storage, allocated once, at the sketch's branches and",
    );
    w.line("/// defaults.");
    w.open("pub fn new() -> Solution {");
    w.line("Solution { store: Store::new(), branches: Branches::default(), defaults: Defaults::default() }");
    w.close("}");
    w.line("");
    w.line("/// The branch variables this assembly is on: those given to the solve.");
    w.open("pub fn branches(&self) -> Branches {");
    w.line("self.branches");
    w.close("}");
    w.line("");
    w.line("/// The defaults this assembly has: those given to the solve.");
    w.open("pub fn defaults(&self) -> Defaults {");
    w.line("self.defaults");
    w.close("}");
    for kind in &accessors.kinds {
        let (what, ty) = match kind.ty {
            ApiTy::Frame => ("frame", if d3 { "Frame3" } else { "Frame2" }),
            ApiTy::Point => ("point", kind.ty.rust(d3)),
            ApiTy::Vector => ("vector", kind.ty.rust(d3)),
            ApiTy::Scalar => ("scalar", "f64"),
        };
        let upper = what.to_uppercase();
        let at_len = (kind.shapes.iter())
            .map(|c| c.outer.len())
            .max()
            .unwrap_or(0);
        let k_len = (kind.shapes.iter())
            .map(|c| c.constants.len())
            .max()
            .unwrap_or(0);
        w.line("");
        w.line(&format!(
            "/// Every {what} of the solution, by its dotted name in the model, in model order."
        ));
        w.open(&format!(
            "pub fn {what}s(&self) -> impl Iterator<Item = (&'static str, {ty})> + '_ {{"
        ));
        w.line(&format!(
            "{upper}_NAME.iter().enumerate().map(|(k, &name)| (text(name), self.{what}_at(k)))"
        ));
        w.close("}");
        w.line("");
        w.line(&format!(
            "/// The {what} called `name` (its dotted name in the model), if the solution has it."
        ));
        w.open(&format!(
            "pub fn {what}(&self, name: &str) -> Option<{ty}> {{"
        ));
        w.line(&format!(
            "find(&{upper}_BY_NAME, name).map(|k| self.{what}_at(k))"
        ));
        w.close("}");
        w.line("");
        w.line(&format!(
            "/// The {what} at `k` in model order: the shape of the code that computes it"
        ));
        w.line(&format!(
            "/// (`{upper}_SHAPE`), the store's slots it reads (`{upper}_AT`) and its constants (`{upper}_K`)."
        ));
        w.line("#[allow(unused_variables, clippy::match_single_binding)]");
        w.open(&format!("fn {what}_at(&self, k: usize) -> {ty} {{"));
        let table_or_empty = |name: &str, len: usize, zero: &str| match len {
            0 => format!("[{zero}; 0]"),
            _ => format!("{name}[k]"),
        };
        w.line(&format!(
            "let at = {};",
            table_or_empty(&format!("{upper}_AT"), at_len, "0u32")
        ));
        w.line(&format!(
            "let c = {};",
            table_or_empty(&format!("{upper}_K"), k_len, "0.0f64")
        ));
        w.open(&format!("match {upper}_SHAPE[k] {{"));
        let count = kind.shapes.len();
        for (n, cut) in kind.shapes.iter().enumerate() {
            let arm = if n + 1 == count {
                "_".to_string()
            } else {
                n.to_string()
            };
            w.open(&format!("{arm} => {{"));
            for (i, name) in cut.outer.iter().enumerate() {
                let slice = slots
                    .get(name)
                    .and_then(|s| store_slice(s.ty))
                    .map_or("", |s| s.0);
                w.line(&format!(
                    "let {name} = self.store.{slice}[at[{i}] as usize];"
                ));
            }
            let k_at: Vec<Option<usize>> = (0..cut.constants.len()).map(Some).collect();
            let code = body(cut, &k_at, &[], &[]).replace("row.k[", "c[");
            w.line(code.trim());
            w.close("}");
        }
        if count == 0 {
            w.line(&format!("_ => {},", zero_of(ty)));
        }
        w.close("}");
        w.close("}");
        // Its tables.
        let names: Vec<String> = (kind.rows.iter())
            .map(|(name, ..)| strings.id(name).to_string())
            .collect();
        table(tables, &format!("{upper}_NAME"), "u32", &names);
        let shapes: Vec<String> = kind
            .rows
            .iter()
            .map(|(_, shape, ..)| shape.to_string())
            .collect();
        table(tables, &format!("{upper}_SHAPE"), "u16", &shapes);
        if at_len > 0 {
            let rows: Vec<String> = (kind.rows.iter())
                .map(|(_, _, at, _)| {
                    let at: Vec<String> = (0..at_len)
                        .map(|i| at.get(i).map_or("0".to_string(), |a| a.to_string()))
                        .collect();
                    format!("[{}]", at.join(", "))
                })
                .collect();
            table(
                tables,
                &format!("{upper}_AT"),
                &format!("[u32; {at_len}]"),
                &rows,
            );
        }
        if k_len > 0 {
            let rows: Vec<String> = (kind.rows.iter())
                .map(|(_, _, _, k)| {
                    let k: Vec<String> = (0..k_len)
                        .map(|i| k.get(i).cloned().unwrap_or_else(|| "0.0".to_string()))
                        .collect();
                    format!("[{}]", k.join(", "))
                })
                .collect();
            table(
                tables,
                &format!("{upper}_K"),
                &format!("[f64; {k_len}]"),
                &rows,
            );
        }
        let sorted = by_name(kind.rows.iter().map(|(n, ..)| n.as_str()), strings);
        table(tables, &format!("{upper}_BY_NAME"), "[u32; 2]", &sorted);
    }
    w.close("}");
    w.line("");
    w.line("/// The index, in model order, of the entry called `name` of a table sorted by name");
    w.line("/// (`[name's string id, index]`).");
    w.open("fn find(by_name: &[[u32; 2]], name: &str) -> Option<usize> {");
    w.line("let k = by_name.binary_search_by(|&[n, _]| text(n).cmp(name)).ok()?;");
    w.line("Some(by_name[k][1] as usize)");
    w.close("}");
    w.line("");
}

/// A value of Rust type `ty` for an empty table's match.
fn zero_of(ty: &str) -> &'static str {
    store_slice(ty).map_or("Default::default()", |(_, z)| z)
}

/// `solve_into` and `solve`, the pieces' functions, and their tables.
fn solve(
    w: &mut Writer,
    tables: &mut String,
    cx: &Context<'_>,
    sketch_checks: &str,
    (shapes, order): (&[Shape], &[Placed]),
    slots: &HashMap<String, Slot>,
    strings: &mut Strings,
) {
    let m = cx.model;
    let np = m.params.len();
    w.line(
        "/// Solves the model into `solution`: the assembly plan's steps, in order, each a call of",
    );
    w.line("/// the piece it is an instance of with its row of data (`ORDER`). Never panics, allocates");
    w.line("/// nothing. After an error, `solution` holds the steps done before it.");
    w.line("///");
    w.line("/// # Errors");
    w.line("///");
    w.line("/// A [`SolveError`] naming the constraint that cannot be met (no intersection, inconsistent,");
    w.line("/// degenerate, or a branch with no assembly here) and by how much, or a non-finite param.");
    w.open("pub fn solve_into(params: &Params, branches: &Branches, defaults: &Defaults, solution: &mut Solution) -> Result<(), SolveError> {");
    let list: Vec<String> = (m.params.iter())
        .map(|(id, p)| format!("({}, params.{})", lit(&p.name), cx.params[&id]))
        .collect();
    if !list.is_empty() {
        w.line(&format!(
            "gcs_runtime::error::check_all_finite(&[{}])?;",
            list.join(", ")
        ));
    }
    if !cx.plan.defaults.is_empty() {
        w.open("for (&name, value) in DEFAULTS_NAMES.iter().zip(defaults.values.iter()) {");
        w.line("gcs_runtime::error::check_all_finite(&[(text(name), *value)])?;");
        w.close("}");
    }
    w.out.push_str(sketch_checks);
    let fields: Vec<String> = (m.params.iter())
        .map(|(id, _)| format!("params.{}", cx.params[&id]))
        .collect();
    w.line(&format!("let p: [f64; {np}] = [{}];", fields.join(", ")));
    w.line("let store = &mut solution.store;");
    w.open("for &[shape, row] in ORDER.iter() {");
    w.line("let row = row as usize;");
    w.open("match shape {");
    // Where each shape's rows hold what, found once.
    let places: Vec<Places> = shapes.iter().map(Places::of).collect();
    for (n, place) in places.iter().enumerate() {
        let arm = if n + 1 == shapes.len() {
            "_".to_string()
        } else {
            n.to_string()
        };
        let widths = place.widths;
        let field = |name: &str, width: usize| match width {
            0 => format!("{name}: &[]"),
            _ => format!("{name}: &PIECE_{n}_{}[row]", name.to_uppercase()),
        };
        w.line(&format!(
            "{arm} => piece_{n}(store, params, &p, branches, defaults, Row {{ {}, {}, {}, {} }})?,",
            field("at", widths.0),
            field("k", widths.1),
            field("text", widths.2),
            field("input", widths.3),
        ));
    }
    if shapes.is_empty() {
        w.line("_ => {}");
    }
    w.close("}");
    w.close("}");
    w.line("solution.branches = *branches;");
    w.line("solution.defaults = *defaults;");
    w.line("Ok(())");
    w.close("}");
    w.line("");
    w.line("/// Solves the model into a new [`Solution`], which this allocates; [`solve_into`] reuses one.");
    w.line("///");
    w.line("/// # Errors");
    w.line("///");
    w.line("/// As [`solve_into`].");
    w.line("#[allow(dead_code)]");
    w.open("pub fn solve(params: &Params, branches: &Branches, defaults: &Defaults) -> Result<Solution, SolveError> {");
    w.line("let mut solution = Solution::new();");
    w.line("solve_into(params, branches, defaults, &mut solution)?;");
    w.line("Ok(solution)");
    w.close("}");
    w.line("");
    w.line(
        "/// A piece's data: the store's slots it reads then writes, its constants, the names its",
    );
    w.line("/// errors give, and the params, branch variables or defaults it reads.");
    w.line("/// Each its row of the piece's tables (`PIECE_n_AT`, `_K`, `_TEXT`, `_INPUT`).");
    w.line("#[derive(Clone, Copy, Debug)]");
    w.open("struct Row<'r, const A: usize, const K: usize, const T: usize, const I: usize> {");
    w.line("at: &'r [u32; A],");
    w.line("k: &'r [f64; K],");
    w.line("text: &'r [u32; T],");
    w.line("input: &'r [u32; I],");
    w.close("}");
    w.line("");
    let mut order_rows: Vec<String> = Vec::with_capacity(order.len());
    for p in order {
        order_rows.push(format!("[{}, {}]", p.shape, p.row));
    }
    for (n, (shape, places)) in shapes.iter().zip(&places).enumerate() {
        piece(w, tables, strings, n, (shape, places), slots);
    }
    table(tables, "ORDER", "[u32; 2]", &order_rows);
}

/// Where a shape's function finds each constant, text and input in its row, and the widths
/// of its rows: slots, constants, texts, inputs.
struct Places {
    k_at: Vec<Option<usize>>,
    t_at: Vec<Option<usize>>,
    inputs_at: Vec<Option<usize>>,
    widths: (usize, usize, usize, usize),
}

impl Places {
    fn of(shape: &Shape) -> Places {
        let (cut, rows) = (&shape.representative, &shape.rows);
        let k_at = varying(cut.constants.len(), rows, |r, i| r.constants[i].clone());
        let t_at = varying(cut.texts.len(), rows, |r, i| r.texts[i].clone());
        let inputs_at = varying(cut.inputs.len(), rows, |r, i| r.inputs[i]);
        let count = |at: &[Option<usize>]| at.iter().flatten().max().map_or(0, |m| m + 1);
        let widths = (
            cut.outer.len() + shape.written.len(),
            count(&k_at),
            count(&t_at),
            count(&inputs_at),
        );
        Places {
            k_at,
            t_at,
            inputs_at,
            widths,
        }
    }
}

/// The function of shape `n` and its tables.
fn piece(
    w: &mut Writer,
    tables: &mut String,
    strings: &mut Strings,
    n: usize,
    (shape, places): (&Shape, &Places),
    slots: &HashMap<String, Slot>,
) {
    let cut = &shape.representative;
    let rows = &shape.rows;
    let Places {
        k_at,
        t_at,
        inputs_at,
        widths,
    } = places;
    let (a, k, t, i) = *widths;
    // An input read the same by every row is written as it is (a param as `params.x`); one
    // that differs is an index in the row.
    let in_at: Vec<InputAt> = (inputs_at.iter().enumerate())
        .map(|(i, at)| match at {
            None => InputAt::Fixed(rows[0].inputs[i]),
            Some(place) => InputAt::Row(*place),
        })
        .collect();
    let row_ty = format!("Row<'_, {a}, {k}, {t}, {i}>");
    for line in &cut.comment {
        w.line(&format!("/// {line}"));
    }
    if rows.len() > 1 {
        if !cut.comment.is_empty() {
            w.line("///");
        }
        w.line(&format!(
            "/// And {} more pieces like it: the rows of `PIECE_{n}_*`, each with its constraint.",
            rows.len() - 1
        ));
    }
    w.line(
        "#[allow(unused_mut, unused_variables, unused_assignments, clippy::too_many_arguments)]",
    );
    w.open(&format!("fn piece_{n}(store: &mut Store, params: &Params, p: &[f64], branches: &Branches, defaults: &Defaults, row: {row_ty}) -> Result<(), SolveError> {{"));
    let slice = |name: &str| {
        slots
            .get(name)
            .and_then(|s| store_slice(s.ty))
            .map_or("", |s| s.0)
    };
    // What the code changes is stored back; what it only reads is not.
    let written: Vec<bool> = (0..cut.outer.len())
        .map(|j| slots.get(&cut.outer[j]).is_some_and(|s| s.mutable) && cut.writes(j))
        .collect();
    for (j, name) in cut.outer.iter().enumerate() {
        let m = if written[j] { "mut " } else { "" };
        w.line(&format!(
            "let {m}{name} = store.{}[row.at[{j}] as usize];",
            slice(name)
        ));
    }
    let code = body(cut, k_at, t_at, &in_at);
    for line in code.trim_end().lines() {
        if line.trim().is_empty() {
            w.line("");
        } else {
            w.line(line.strip_prefix("    ").unwrap_or(line));
        }
    }
    for (j, name) in cut.outer.iter().enumerate() {
        if written[j] {
            w.line(&format!(
                "store.{}[row.at[{j}] as usize] = {name};",
                slice(name)
            ));
        }
    }
    for (j, name) in shape.written.iter().enumerate() {
        let j = cut.outer.len() + j;
        w.line(&format!(
            "store.{}[row.at[{j}] as usize] = {name};",
            slice(name)
        ));
    }
    w.line("Ok(())");
    w.close("}");
    w.line("");
    // The tables: a row a piece, the first table's with the piece's constraint.
    let mut columns: Vec<(&str, String, Vec<Vec<String>>)> = Vec::new();
    if a > 0 {
        let at = (rows.iter())
            .map(|r| r.slots.iter().map(usize::to_string).collect())
            .collect();
        columns.push(("AT", format!("[u32; {a}]"), at));
    }
    if k > 0 {
        let ks = rows.iter().map(|r| at_places(k_at, &r.constants)).collect();
        columns.push(("K", format!("[f64; {k}]"), ks));
    }
    if t > 0 {
        let ts = (rows.iter())
            .map(|r| {
                let ids: Vec<String> = (r.texts.iter())
                    .map(|l| strings.id_of_literal(l).to_string())
                    .collect();
                at_places(t_at, &ids)
            })
            .collect();
        columns.push(("TEXT", format!("[u32; {t}]"), ts));
    }
    if i > 0 {
        let is = (rows.iter())
            .map(|r| {
                let inputs: Vec<String> = r.inputs.iter().map(usize::to_string).collect();
                at_places(inputs_at, &inputs)
            })
            .collect();
        columns.push(("INPUT", format!("[u32; {i}]"), is));
    }
    for (c, (name, ty, values)) in columns.into_iter().enumerate() {
        let entries: Vec<String> = (values.iter().zip(rows))
            .map(|(v, r)| {
                let comment = match (&r.comment, c) {
                    (Some(comment), 0) => format!(", // {comment}"),
                    _ => String::new(),
                };
                format!("[{}]{comment}", v.join(", "))
            })
            .collect();
        table(tables, &format!("PIECE_{n}_{name}"), &ty, &entries);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<(Tok, &str)> {
        tokens(text)
            .into_iter()
            .map(|t| (t.kind, &text[t.start..t.end]))
            .collect()
    }

    #[test]
    fn tokens_tell_numbers_strings_paths_and_comments_apart() {
        let text = r#"let x = a.y * -1.5e-3 + f64::NAN; // "not a string"
g("a \"q\" b", 2u8, 3, x.0, 1e300);"#;
        let toks = kinds(text);
        assert!(toks.contains(&(Tok::Float, "1.5e-3")));
        assert!(toks.contains(&(Tok::Float, "1e300")));
        assert!(
            toks.contains(&(Tok::Int, "2u8")),
            "a suffixed literal is typed: {toks:?}"
        );
        assert!(toks.contains(&(Tok::Int, "3")));
        assert!(toks.contains(&(Tok::Int, "0")), "a tuple field: {toks:?}");
        assert!(toks.contains(&(Tok::Punct, "::")));
        assert!(toks.contains(&(Tok::Comment, "// \"not a string\"")));
        assert!(toks.contains(&(Tok::Str, r#""a \"q\" b""#)));
    }

    /// A number's sign is part of the constant, not of the shape; a minus between two values
    /// is code.
    #[test]
    fn numbers_of_either_sign_are_one_shape_and_keep_their_sign() {
        let outer = |_: &str| false;
        let piece = |x: &str, y: &str| {
            format!("let d = Vector2::new({x}, {y});\nlet e = d.x - 2.0;\nlet f = -3.5 * e;\n")
        };
        let a = Cut::new(piece("0.5", "-0.25"), &outer);
        let b = Cut::new(piece("-0.5", "0.75"), &outer);
        let none = HashMap::default();
        assert_eq!(shape_key(&a, &none), shape_key(&b, &none));
        assert_eq!(a.constants, ["0.5", "-0.25", "2.0", "-3.5"]);
        assert_eq!(b.constants, ["-0.5", "0.75", "2.0", "-3.5"]);
        let at: Vec<Option<usize>> = vec![Some(0), Some(1), None, None];
        assert_eq!(
            body(&b, &at, &[], &[]),
            "let d = Vector2::new(row.k[0], row.k[1]);\nlet e = d.x - 2.0;\nlet f = -3.5 * e;\n"
        );
    }

    /// Two pieces that differ only in the locals they name, the earlier values they read,
    /// their constants and their error names have one shape; a different call does not.
    #[test]
    fn pieces_alike_but_for_names_and_literals_have_one_shape() {
        let earlier: HashMap<String, Slot> = ["crank_b", "rocker1", "rocker1_b", "rocker2", "f32"]
            .into_iter()
            .map(|n| {
                let slot = Slot {
                    ty: if n.ends_with("_b") {
                        "Point2<f64>"
                    } else {
                        "Frame2"
                    },
                    index: 0,
                    mutable: !n.ends_with("_b"),
                };
                (n.to_string(), slot)
            })
            .collect();
        let outer = |w: &str| earlier.contains_key(w);
        let piece = |point: &str, frame: &str, x: &str, label: &str| {
            format!(
                "// {label}: coincident(...) (m.gcs:3)\nlet circle_{point} = Circle::new({point}, 4.0).ok_or_else(|| SolveError::new(\"{label}\", \"text\", ErrorKind::Degenerate, 0.0))?;\nlet c = Point2::new({x}, 0.0);\n{frame}.place_origin(&c);\nlet r = usize::from(branches.{label});\n"
            )
        };
        let a = Cut::new(piece("crank_b", "rocker1", "4.0", "elbow1"), &outer);
        let b = Cut::new(piece("rocker1_b", "rocker2", "8.0", "elbow2"), &outer);
        let c = Cut::new(
            piece("rocker1_b", "rocker2", "8.0", "elbow2").replace("place_origin", "turn_by"),
            &outer,
        );
        let (ka, kb, kc) = (
            shape_key(&a, &earlier),
            shape_key(&b, &earlier),
            shape_key(&c, &earlier),
        );
        assert!(ka.is_some());
        assert_eq!(ka, kb);
        assert_ne!(kb, kc);
        assert_eq!(a.comment, ["elbow1: coincident(...) (m.gcs:3)"]);
        assert_eq!(a.outer, ["crank_b", "rocker1"]);
        assert_eq!(b.constants, ["4.0", "0.0", "8.0", "0.0"]);
        assert_eq!(b.inputs, [(Input::Branch, "elbow2".to_string())]);
        // A geom called `f32` is a value read like any other.
        let d = Cut::new("f32.place_origin(&p);\n".to_string(), &outer);
        assert_eq!(d.outer, ["f32"]);
    }

    #[test]
    fn a_value_is_stored_back_only_where_the_code_may_change_it() {
        let outer = |w: &str| ["a", "b", "c", "d", "e", "f"].contains(&w);
        let cut = Cut::new(
            "let t = a.origin.x + b.x_axis().y;\nc.set_rotation(&t);\nd.origin.y = 1.0;\nmove_it(&mut e);\nlet g = f == 2.0;\n"
                .to_string(),
            &outer,
        );
        let writes: Vec<(&str, bool)> = (0..cut.outer.len())
            .map(|n| (cut.outer[n].as_str(), cut.writes(n)))
            .collect();
        assert_eq!(
            writes,
            [
                ("a", false),
                ("b", false),
                ("c", true),
                ("d", true),
                ("e", true),
                ("f", false)
            ]
        );
    }

    #[test]
    fn a_value_the_same_in_every_row_is_written_in_place() {
        let row = |k: &[&str]| Row {
            comment: None,
            slots: Vec::new(),
            constants: k.iter().map(|s| s.to_string()).collect(),
            texts: Vec::new(),
            inputs: Vec::new(),
        };
        let rows = [
            row(&["4.0", "1.0", "4.0", "2.0"]),
            row(&["8.0", "1.0", "8.0", "3.0"]),
        ];
        let places = varying(4, &rows, |r, i| r.constants[i].clone());
        // The first and third always agree: one place; the second never varies.
        assert_eq!(places, [Some(0), None, Some(0), Some(1)]);
        assert_eq!(at_places(&places, &rows[1].constants), ["8.0", "3.0"]);
    }
}
