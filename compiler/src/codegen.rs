//! The code generator: a plan as one Rust module that depends on the runtime crate alone.
//!
//! The module has `Params`, `Branches` and `Defaults` (each `Default` from the file), a
//! `Solution` with accessors named after the model, and `solve`, a straight line of the plan's
//! steps with a comment quoting, for each action, the constraint it satisfies and its
//! `file:line`. Every identifier comes from the model's names through one [`Namer`]
//! (keyword-safe, never an index); the text is written through a small indenting writer, so it is
//! deterministic and rustfmt-clean. `solve` never panics and allocates nothing: every failure is
//! a `SolveError` built from string literals.

use crate::plan::{Meet, Op, Plan, Reg};
use gcs_lang::expr::{ExprId, ExprNode, Func};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part, Sketch};
use gcs_lang::syntax::{AngleUnit, BinaryOp};
use gcs_lang::Model;
use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap, HashSet};

mod scopes;
use scopes::Binding;

/// The generated module for a model's plan, pruned to its `output` statements. The plan must
/// be valid (the pipeline's are).
pub fn generate(model: &Model, plan: &Plan) -> String {
    let (plan, scope) = crate::prune::prune(model, plan);
    Gen::new(model, &plan, &scope).module()
}

/// Makes every identifier of the generated module: snake case, keyword-safe, unique within its
/// scope, derived from the model's names (repeats get `_2`, `_3`, ... in order of first use).
#[derive(Debug, Default)]
pub struct Namer {
    used: HashSet<String>,
    /// For a base, the suffix its last fresh name took: names are never released, so the
    /// next search for that base starts there instead of at `_2`.
    last: HashMap<String, usize>,
}

const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

impl Namer {
    /// `text` as a snake-case identifier (not yet unique).
    pub fn snake(text: &str) -> String {
        let mut out = String::new();
        for c in text.chars() {
            if c.is_ascii_alphanumeric() {
                out.push(c.to_ascii_lowercase());
            } else if !out.ends_with('_') {
                out.push('_');
            }
        }
        let mut out = out.trim_matches('_').to_string();
        if out.is_empty() {
            out = "value".into();
        }
        if out.starts_with(|c: char| c.is_ascii_digit()) {
            out.insert_str(0, "v_");
        }
        if KEYWORDS.contains(&out.as_str()) {
            out.push('_');
        }
        out
    }

    /// A fresh identifier from `text`.
    pub fn fresh(&mut self, text: &str) -> String {
        let base = Self::snake(text);
        let mut n = self.last.get(&base).copied().unwrap_or(1);
        let mut name = if n == 1 {
            base.clone()
        } else {
            format!("{base}_{n}")
        };
        while self.used.contains(&name) {
            n += 1;
            name = format!("{base}_{n}");
        }
        self.used.insert(name.clone());
        self.last.insert(base, n);
        name
    }

    /// Marks a name as taken.
    pub fn reserve(&mut self, name: &str) {
        self.used.insert(name.to_string());
    }
}

/// An indenting writer over a `String`: infallible, so no `unwrap` on every line.
#[derive(Debug, Default)]
struct Writer {
    out: String,
    indent: usize,
}

impl Writer {
    fn line(&mut self, text: &str) {
        if text.is_empty() {
            self.out.push('\n');
            return;
        }
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }
    fn open(&mut self, text: &str) {
        self.line(text);
        self.indent += 1;
    }
    fn close(&mut self, text: &str) {
        self.indent = self.indent.saturating_sub(1);
        self.line(text);
    }
}

/// A struct field initialiser, in shorthand when the names agree.
fn field_init(field: &str, value: &str) -> String {
    if field == value {
        format!("{field},")
    } else {
        format!("{field}: {value},")
    }
}

/// A Rust string literal.
fn lit(s: &str) -> String {
    format!("{s:?}")
}

/// A float literal: shortest round-trip form, always with a decimal point or exponent.
fn float(v: f64) -> String {
    if v.is_nan() {
        return "f64::NAN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 {
            "f64::INFINITY".into()
        } else {
            "f64::NEG_INFINITY".into()
        };
    }
    for (c, name) in [
        (std::f64::consts::PI, "std::f64::consts::PI"),
        (std::f64::consts::FRAC_PI_2, "std::f64::consts::FRAC_PI_2"),
        (std::f64::consts::FRAC_PI_3, "std::f64::consts::FRAC_PI_3"),
        (std::f64::consts::FRAC_PI_4, "std::f64::consts::FRAC_PI_4"),
        (std::f64::consts::FRAC_PI_6, "std::f64::consts::FRAC_PI_6"),
        (std::f64::consts::TAU, "std::f64::consts::TAU"),
    ] {
        if v == c {
            return name.into();
        }
        if v == -c {
            return format!("-{name}");
        }
    }
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") {
        s
    } else {
        format!("{s}.0")
    }
}

/// What codegen knows of a frame at the current step of the solve, so that it writes the same
/// values with less work: a rotation still the identity needs no product, an origin known to
/// equal a literal or an immutable local needs no reading, and an action that cannot move
/// the frame is left out.
#[derive(Clone, Debug, Default)]
struct FrameFacts {
    /// The rotation is exactly the identity (nothing has turned the frame yet).
    identity: bool,
    /// Code whose value is the frame's origin, to the bit.
    origin: Option<Origin>,
}

/// Code equal to a frame's origin.
#[derive(Clone, Debug, PartialEq)]
enum Origin {
    /// A constant point, which later constant offsets fold into.
    Literal(f64, f64),
    /// An immutable local, or an expression of params.
    Code(String),
}

impl Origin {
    fn code(&self) -> String {
        match self {
            Origin::Literal(x, y) => format!("Point2::new({}, {})", float(*x), float(*y)),
            Origin::Code(c) => c.clone(),
        }
    }
}

/// A binding of the solve's sketch: a frame's, declared (and `mut`) once the steps show
/// whether the frame is read or moved, or any other.
enum Decl {
    Frame(GeomId, Binding),
    Value(Binding),
}

/// Whether generated code is a plain identifier (a local), not a literal or an expression.
fn is_ident(code: &str) -> bool {
    !code.is_empty()
        && !code.starts_with(|c: char| c.is_ascii_digit())
        && code.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Code for the point at local coordinates `local` of frame `f`, with origin `origin`: the
/// rotation's products by a zero coordinate left out (the compiler may not fold them, as a
/// NaN times zero is NaN), and nothing at all for the origin itself.
fn point_in(f: &str, origin: &str, local: (f64, f64)) -> String {
    match local {
        (0.0, 0.0) => origin.to_string(),
        (x, 0.0) => offset(origin, &format!("{f}.x_axis() * {}", float(x))),
        (0.0, y) => offset(origin, &format!("{f}.y_axis() * {}", float(y))),
        (x, y) => format!(
            "{f}.point_to_global(&Point2::new({}, {}))",
            float(x),
            float(y)
        ),
    }
}

/// Code for the sum of `coefficient * value` terms, leaving out the zero coefficients (the
/// compiler may not fold them: a NaN times zero is NaN) and writing a unit one as the value.
fn linear(terms: &[(f64, String)]) -> String {
    let mut code = String::new();
    for (k, v) in terms.iter().filter(|(k, _)| *k != 0.0) {
        let term = match *k {
            1.0 => v.clone(),
            -1.0 => format!("-{v}"),
            k => format!("{v} * {}", float(k)),
        };
        if code.is_empty() {
            code = term;
        } else if let Some(minus) = term.strip_prefix('-') {
            code = format!("{code} - {minus}");
        } else {
            code = format!("{code} + {term}");
        }
    }
    if code.is_empty() {
        "0.0".into()
    } else {
        code
    }
}

/// Code for the point `origin + v`; just `v` as a point when the origin is the literal zero.
fn offset(origin: &str, v: &str) -> String {
    if origin == "Point2::new(0.0, 0.0)" {
        format!("Point2::from({v})")
    } else {
        format!("{origin} + {v}")
    }
}

/// Code for the direction at local unit vector `local` of frame `f` (see [`point_in`]).
fn direction_in(f: &str, local: (f64, f64)) -> String {
    match local {
        (1.0, 0.0) => format!("{f}.x_axis()"),
        (0.0, 1.0) => format!("{f}.y_axis()"),
        (x, y) => format!(
            "{f}.vector_to_global(&Vector2::new({}, {}))",
            float(x),
            float(y)
        ),
    }
}

struct Gen<'a> {
    model: &'a Model,
    plan: &'a Plan,
    scope: &'a BTreeSet<GeomId>,
    names: Namer,
    /// The Rust expression of each register (a local's name, or an inline expression).
    regs: HashMap<Reg, String>,
    /// Locals of frames and dimensions by top-level geom.
    frames: HashMap<GeomId, String>,
    dims: HashMap<GeomId, String>,
    /// Locals (or literals) of members' local coordinates.
    locals: HashMap<GeomId, String>,
    /// Param field names.
    params: HashMap<gcs_lang::expr::ParamId, String>,
    /// Branch field names by branch index.
    branches: Vec<String>,
    /// Default field names by default index.
    defaults: Vec<String>,
    file: String,
    /// Dimensions declared where the plan sets them (nothing reads their sketch value).
    deferred: HashSet<GeomId>,
    /// Reported points and vectors the plan never moves and whose sketch is constant: the
    /// solution returns them as literals instead of storing them.
    constant: HashSet<GeomId>,
    /// Registers some generated step reads (an intersection's `near` is for the sketch's
    /// branch only, so it is not among them).
    used: HashSet<Reg>,
    /// What the plan does to each geom, indexed once (the plan is fixed).
    index: PlanIndex,
    /// What is known of each frame at the step being written.
    facts: HashMap<GeomId, FrameFacts>,
    /// Frames the solve's code reads, and frames it moves: one that is neither is not
    /// declared, and only a moved one is `mut`.
    frame_reads: RefCell<HashSet<GeomId>>,
    frame_writes: HashSet<GeomId>,
    /// Registers that hold the x axis `(1, 0)` exactly.
    unit_x: HashSet<Reg>,
    /// Scalar registers known to be finite: a param (checked on entry), a finite literal, or
    /// a value checked where it is computed. Their uses need no test of their own.
    finite: HashSet<Reg>,
    /// Registers that hold a finite unit direction by construction (`direction_at` of a
    /// finite angle): a rotation onto one needs no test.
    unit_dirs: HashSet<Reg>,
    /// Point registers read while their frame was unturned, with an origin whose code stays
    /// its value: that code and the point's constant local coordinates. The vector between
    /// two such points of one frame is a constant, known here.
    at_offset: HashMap<Reg, (String, (f64, f64))>,
    /// The constant radius of the circle about a pivot through a point of the same rigid
    /// geom, by its (centre, through) registers: a rotation onto that circle knows it.
    circle_radius: HashMap<(Reg, Reg), f64>,
    /// Names for registers that are a literal rather than a local (to name what is derived
    /// from them).
    reg_names: HashMap<Reg, String>,
    /// The code of each circle register's centre.
    circle_centers: HashMap<Reg, String>,
    /// Points some rotation turns a rigid point onto (`RotatePoint`'s `to`).
    rotated_onto: HashSet<Reg>,
    /// Circle-circle roots kept with their chord, so that a rotation about either centre onto
    /// the root reads it from that centre (`root_from_a`, `root_from_b`).
    chord_roots: HashMap<Reg, ChordRoot>,
}

/// A circle-circle root whose chord is a local: the chord, the branch index's code, and the
/// code of each circle's centre.
#[derive(Clone, Debug)]
struct ChordRoot {
    chord: String,
    index: String,
    centers: [String; 2],
}

/// Per-geom facts about a plan, each from one pass over its steps, so that asking them of every
/// geom costs no scan of the plan.
#[derive(Default)]
struct PlanIndex {
    /// [`Plan::touched`].
    touched: BTreeSet<GeomId>,
    /// Geoms some action moves.
    moved: HashSet<GeomId>,
    /// Geoms whose dimension some step sets.
    dim_set: HashSet<GeomId>,
    /// Features a `PointOf` or `DirOf` reads.
    read: HashSet<GeomId>,
    /// The arguments of checked constraints.
    checked: HashSet<GeomId>,
    /// For a geom, whether the first step that decides it sets its dimension (see
    /// [`Gen::dim_set_before_read`]).
    dim_first: HashMap<GeomId, bool>,
}

impl PlanIndex {
    fn new(model: &Model, plan: &Plan, used: &HashSet<Reg>) -> PlanIndex {
        let mut ix = PlanIndex {
            touched: plan.touched(model),
            ..PlanIndex::default()
        };
        for step in &plan.steps {
            match &step.op {
                Op::Translate { geoms, .. }
                | Op::RotatePoint { geoms, .. }
                | Op::RotateDir { geoms, .. } => ix.moved.extend(geoms.iter().copied()),
                Op::SetDim { geom, .. } => {
                    ix.dim_set.insert(*geom);
                    ix.dim_first.entry(*geom).or_insert(true);
                }
                Op::DimOf(x) => {
                    ix.dim_first.entry(*x).or_insert(false);
                }
                Op::PointOf(f) => {
                    ix.read.insert(*f);
                    if matches!(model.geoms[*f].owner, Owner::Part(_, Part::End))
                        && step.out.is_some_and(|o| used.contains(&o.0))
                    {
                        ix.dim_first.entry(model.top_level_of(*f)).or_insert(false);
                    }
                }
                Op::DirOf(f) => {
                    ix.read.insert(*f);
                }
                _ => {}
            }
        }
        ix
    }
}

impl<'a> Gen<'a> {
    fn new(model: &'a Model, plan: &'a Plan, scope: &'a BTreeSet<GeomId>) -> Self {
        let mut names = Namer::default();
        for reserved in ["params", "branches", "defaults", "tol", "solution"] {
            names.reserve(reserved);
        }
        let mut field_names = Namer::default();
        let params = model
            .params
            .iter()
            .map(|(id, p)| (id, field_names.fresh(&p.name)))
            .collect();
        let mut branch_names = Namer::default();
        let branches = plan
            .branches
            .iter()
            .map(|b| branch_names.fresh(&b.name))
            .collect();
        let mut default_names = Namer::default();
        let defaults = plan
            .defaults
            .iter()
            .map(|d| default_names.fresh(&d.name))
            .collect();
        let file = std::path::Path::new(model.source.name())
            .file_name()
            .map_or_else(
                || model.source.name().to_string(),
                |f| f.to_string_lossy().into_owned(),
            );
        let mut used = HashSet::new();
        for step in &plan.steps {
            match &step.op {
                Op::Intersect { a, b, .. } => {
                    used.insert(*a);
                    used.insert(*b);
                }
                Op::CircleThrough {
                    center,
                    through,
                    radius,
                } => {
                    used.insert(*center);
                    if radius.is_none() {
                        used.insert(*through);
                    }
                }
                op => used.extend(op.reads()),
            }
        }
        let index = PlanIndex::new(model, plan, &used);
        let rotated_onto = plan
            .steps
            .iter()
            .filter_map(|s| match &s.op {
                Op::RotatePoint { to, .. } => Some(*to),
                _ => None,
            })
            .collect();
        Gen {
            circle_centers: HashMap::new(),
            rotated_onto,
            chord_roots: HashMap::new(),
            index,
            deferred: HashSet::new(),
            constant: HashSet::new(),
            used,
            model,
            plan,
            scope,
            names,
            regs: HashMap::new(),
            frames: HashMap::new(),
            dims: HashMap::new(),
            locals: HashMap::new(),
            params,
            branches,
            defaults,
            file,
            facts: HashMap::new(),
            frame_reads: RefCell::new(HashSet::new()),
            frame_writes: HashSet::new(),
            unit_x: HashSet::new(),
            finite: HashSet::new(),
            unit_dirs: HashSet::new(),
            at_offset: HashMap::new(),
            circle_radius: HashMap::new(),
            reg_names: HashMap::new(),
        }
    }

    // ------------------------------------------------------------ expressions

    /// The Rust code of an expression, with the precedence of its outermost operator
    /// (1: sum, 2: product, 3: negation, 4: an atom or method call).
    fn expr_prec(&self, e: ExprId) -> (String, u8) {
        let m = self.model;
        if m.exprs.is_constant(e) {
            let v = m.exprs.eval(e, &[]);
            return (float(v), if v < 0.0 { 3 } else { 4 });
        }
        match m.exprs.node(e) {
            ExprNode::Const(v) => (float(*v), if *v < 0.0 { 3 } else { 4 }),
            ExprNode::Param(p) => (format!("params.{}", self.params[p]), 4),
            ExprNode::Neg(a) => (format!("-{}", self.wrap(*a, 3)), 3),
            ExprNode::Binary(op, a, b) => match op {
                BinaryOp::Add => (format!("{} + {}", self.wrap(*a, 1), self.wrap(*b, 2)), 1),
                BinaryOp::Sub => (format!("{} - {}", self.wrap(*a, 1), self.wrap(*b, 2)), 1),
                BinaryOp::Mul => (format!("{} * {}", self.wrap(*a, 2), self.wrap(*b, 3)), 2),
                BinaryOp::Div => (format!("{} / {}", self.wrap(*a, 2), self.wrap(*b, 3)), 2),
                BinaryOp::Pow => (format!("{}.powf({})", self.receiver(*a), self.expr(*b)), 4),
            },
            ExprNode::Call(f, a, b) => {
                let method = match f {
                    Func::Sqrt => "sqrt",
                    Func::Abs => "abs",
                    Func::Sin => "sin",
                    Func::Cos => "cos",
                    Func::Tan => "tan",
                    Func::Asin => "asin",
                    Func::Acos => "acos",
                    Func::Atan => "atan",
                    Func::Atan2 => "atan2",
                    Func::Min => "min",
                    Func::Max => "max",
                };
                match b {
                    Some(b) => (
                        format!("{}.{method}({})", self.receiver(*a), self.expr(*b)),
                        4,
                    ),
                    None => (format!("{}.{method}()", self.receiver(*a)), 4),
                }
            }
            ExprNode::Unit(AngleUnit::Deg, a) => (format!("{}.to_radians()", self.receiver(*a)), 4),
            ExprNode::Unit(AngleUnit::Rad, a) => self.expr_prec(*a),
        }
    }

    fn expr(&self, e: ExprId) -> String {
        self.expr_prec(e).0
    }

    /// The expression, parenthesised if its precedence is below `at`.
    fn wrap(&self, e: ExprId, at: u8) -> String {
        let (code, prec) = self.expr_prec(e);
        if prec < at {
            format!("({code})")
        } else {
            code
        }
    }

    /// The expression as the receiver of a method call: an atom, and a typed literal.
    fn receiver(&self, e: ExprId) -> String {
        let (code, prec) = self.expr_prec(e);
        if prec < 4 {
            return format!("({code})");
        }
        if code.starts_with(|c: char| c.is_ascii_digit()) {
            return format!("{code}_f64");
        }
        code
    }

    fn point_lit(&self, c: &[ExprId]) -> String {
        let x = c.first().map_or("0.0".into(), |&e| self.expr(e));
        let y = c.get(1).map_or("0.0".into(), |&e| self.expr(e));
        format!("Point2::new({x}, {y})")
    }

    fn vector_lit(&self, c: &[ExprId]) -> String {
        let x = c.first().map_or("0.0".into(), |&e| self.expr(e));
        let y = c.get(1).map_or("0.0".into(), |&e| self.expr(e));
        format!("Vector2::new({x}, {y})")
    }

    // ------------------------------------------------------------ the module

    fn module(mut self) -> String {
        let mut w = Writer::default();
        let m = self.model;
        w.line(&format!(
            "// @generated by gcs from {}. Do not edit: edit the model and regenerate.",
            self.file
        ));
        w.line("//");
        w.line("// The solver's steps follow the model's assembly plan; `gcs explain` prints it in words.");
        w.line("");
        // No inner attributes or `//!` docs: the module must be usable through `include!`.
        w.line(&format!(
            "// Solver for `{}`. Call `solve` with `Params`, `Branches` and `Defaults`, and read",
            self.file
        ));
        w.line("// the result through the accessors of `Solution`. It never panics and allocates nothing.");
        w.line("// A caller uses what it needs of this API: the setters and accessors allow dead code.");
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
        self.params_struct(&mut w);
        self.branches_struct(&mut w);
        self.defaults_struct(&mut w);
        let solution_fields = self.solution_struct(&mut w);
        self.solve_fn(&mut w, &solution_fields);
        let _ = m;
        w.out
    }

    fn params_struct(&self, w: &mut Writer) {
        let m = self.model;
        w.line("/// The run-time inputs: one field per `param` of the model.");
        w.line(&scopes::derives(m.params.len(), false));
        if m.params.is_empty() {
            w.line("pub struct Params {}");
        } else {
            w.open("pub struct Params {");
            for (id, p) in m.params.iter() {
                let unit = if p.dim == gcs_lang::expr::Dim::Angle {
                    " (radians)"
                } else {
                    ""
                };
                w.line(&format!("/// `{}`{unit}, line {}.", p.name, m.line(p.span)));
                w.line(&format!("pub {}: f64,", self.params[&id]));
            }
            w.close("}");
        }
        w.line("");
        let fields: Vec<String> = m
            .params
            .iter()
            .map(|(id, _)| self.params[&id].clone())
            .collect();
        scopes::field_by_field_eq(w, "Params", &fields, false);
        w.line("#[allow(dead_code)]");
        w.open("impl Params {");
        w.line("/// Sets the param called `name` (as in the model); `false` when there is none.");
        if m.params.is_empty() {
            w.open("pub fn set(&mut self, name: &str, value: f64) -> bool {");
            w.line("let _ = (name, value);");
            w.line("false");
        } else {
            w.open("pub fn set(&mut self, name: &str, value: f64) -> bool {");
            w.open("match name {");
            for (id, p) in m.params.iter() {
                w.line(&format!(
                    "{} => self.{} = value,",
                    lit(&p.name),
                    self.params[&id]
                ));
            }
            w.line("_ => return false,");
            w.close("}");
            w.line("true");
        }
        w.close("}");
        w.close("}");
        w.line("");
        w.open("impl Default for Params {");
        w.line("/// The values the model gives.");
        w.open("fn default() -> Self {");
        if m.params.is_empty() {
            w.line("Params {}");
        } else {
            w.open("Params {");
            for (id, p) in m.params.iter() {
                w.line(&format!("{}: {},", self.params[&id], float(p.default)));
            }
            w.close("}");
        }
        w.close("}");
        w.close("}");
        w.line("");
    }

    fn defaults_struct(&self, w: &mut Writer) {
        if self.plan.defaults.is_empty() {
            w.line("/// Values of the degrees of freedom the analysis had to default (none for this model).");
            w.line("#[derive(Clone, Copy, Debug, Default, PartialEq)]");
            w.line("pub struct Defaults {}");
            w.line("");
            return;
        }
        w.line("/// Values of the degrees of freedom the analysis had to default: where a solve starts,");
        w.line("/// or the value of a motion the constraints leave free. `Default` is the sketch.");
        w.line(&scopes::derives(self.defaults.len(), false));
        w.open("pub struct Defaults {");
        for (d, name) in self.plan.defaults.iter().zip(&self.defaults) {
            w.line(&format!("/// `{}`: {}.", d.name, d.meaning));
            w.line(&format!("pub {name}: f64,"));
        }
        w.close("}");
        w.line("");
        scopes::field_by_field_eq(w, "Defaults", &self.defaults, false);
        w.line("#[allow(dead_code)]");
        w.open("impl Defaults {");
        w.line("/// Sets the default called `name` (as in the plan); `false` when there is none.");
        w.open("pub fn set(&mut self, name: &str, value: f64) -> bool {");
        w.open("match name {");
        for (d, field) in self.plan.defaults.iter().zip(&self.defaults) {
            w.line(&format!("{} => self.{field} = value,", lit(&d.name)));
        }
        w.line("_ => return false,");
        w.close("}");
        w.line("true");
        w.close("}");
        w.close("}");
        w.line("");
        w.open("impl Default for Defaults {");
        w.line("/// The sketch's values.");
        w.open("fn default() -> Self {");
        w.open("Defaults {");
        for (d, name) in self.plan.defaults.iter().zip(&self.defaults) {
            w.line(&format!("{name}: {},", float(d.sketch)));
        }
        w.close("}");
        w.close("}");
        w.close("}");
        w.line("");
    }

    fn branches_struct(&self, w: &mut Writer) {
        w.line("/// Which assembly: one field per branch variable, each an index with a geometric meaning.");
        w.line(&scopes::derives(self.branches.len(), true));
        if self.plan.branches.is_empty() {
            w.line("pub struct Branches {}");
        } else {
            w.open("pub struct Branches {");
            for (b, name) in self.plan.branches.iter().zip(&self.branches) {
                w.line(&format!("/// `{}`:", b.name));
                for (i, meaning) in b.meanings.iter().enumerate() {
                    w.line(&format!("/// - {i}: {meaning}"));
                }
                w.line(&format!("pub {name}: u8,"));
            }
            w.close("}");
        }
        w.line("");
        scopes::field_by_field_eq(w, "Branches", &self.branches, true);
        w.line("#[allow(dead_code)]");
        w.open("impl Branches {");
        w.line("/// Sets the branch variable called `name` (as in the model); `false` when there is none.");
        w.open("pub fn set(&mut self, name: &str, index: u8) -> bool {");
        if self.plan.branches.is_empty() {
            w.line("let _ = (name, index);");
            w.line("false");
        } else {
            w.open("match name {");
            for (b, field) in self.plan.branches.iter().zip(&self.branches) {
                w.line(&format!("{} => self.{field} = index,", lit(&b.name)));
            }
            w.line("_ => return false,");
            w.close("}");
            w.line("true");
        }
        w.close("}");
        w.close("}");
        w.line("");
        w.open("impl Default for Branches {");
        w.line("/// The sketch's assembly.");
        w.open("fn default() -> Self {");
        if self.plan.branches.is_empty() {
            w.line("Branches {}");
        } else {
            w.open("Branches {");
            for (b, name) in self.plan.branches.iter().zip(&self.branches) {
                w.line(&format!("{name}: {},", b.default));
            }
            w.close("}");
        }
        w.close("}");
        w.close("}");
        w.line("");
    }

    /// The top-level geoms the solver computes, in model order.
    fn solved(&self) -> Vec<GeomId> {
        self.model
            .top_level()
            .map(|(id, _)| id)
            .filter(|id| self.scope.contains(id))
            .collect()
    }

    /// Whether a member's local coordinates depend on params (then the solution stores them).
    fn local_is_param(&self, g: GeomId) -> bool {
        match &self.model.geoms[g].sketch {
            Sketch::Point(c) | Sketch::Vector(c) => {
                c.iter().any(|&e| !self.model.exprs.is_constant(e))
            }
            Sketch::Marker { origin, x, .. } => origin
                .iter()
                .chain(x)
                .any(|&e| !self.model.exprs.is_constant(e)),
            _ => false,
        }
    }

    /// The solution struct and its accessors; returns the field names (frames, dims, locals).
    fn solution_struct(&mut self, w: &mut Writer) -> Vec<(String, String)> {
        let m = self.model;
        let mut fields: Vec<(String, String)> = Vec::new(); // (field, type)
        let mut field_names = Namer::default();
        let mut frame_field: HashMap<GeomId, String> = HashMap::new();
        let mut dim_field: HashMap<GeomId, String> = HashMap::new();
        let mut local_field: HashMap<GeomId, String> = HashMap::new();
        for g in self.solved() {
            let geom = &m.geoms[g];
            if let Some(value) = self.constant_value(g) {
                self.constant.insert(g);
                frame_field.insert(g, value);
                continue;
            }
            let f = field_names.fresh(&geom.name);
            fields.push((f.clone(), "Frame2".into()));
            frame_field.insert(g, f);
            if matches!(geom.kind, GeomKind::Segment | GeomKind::Circle) {
                let what = if geom.kind == GeomKind::Circle {
                    "radius"
                } else {
                    "length"
                };
                let f = field_names.fresh(&format!("{}_{what}", geom.name));
                fields.push((f.clone(), "f64".into()));
                dim_field.insert(g, f);
            }
            for &part in &geom.parts {
                let p = &m.geoms[part];
                if matches!(p.owner, Owner::Member(_)) && self.local_is_param(part) {
                    let f = field_names.fresh(&format!("{}_local", p.name));
                    let ty = if p.kind == GeomKind::Vector {
                        "Vector2<f64>"
                    } else {
                        "Point2<f64>"
                    };
                    fields.push((f.clone(), ty.into()));
                    local_field.insert(part, f.clone());
                    if p.kind == GeomKind::Marker {
                        if let Some(&ax) = p.parts.first() {
                            let f = field_names.fresh(&format!("{}_x_local", p.name));
                            fields.push((f.clone(), "Vector2<f64>".into()));
                            local_field.insert(ax, f);
                        }
                    }
                }
            }
        }
        w.line("/// The solved configuration of every geom the outputs need: frames and dimensions, read");
        w.line("/// through accessors named after the model.");
        w.line(&scopes::derives(fields.len(), false));
        if fields.is_empty() {
            w.line("pub struct Solution {}");
        } else {
            w.open("pub struct Solution {");
            for (f, ty) in &fields {
                w.line(&format!("{f}: {ty},"));
            }
            w.close("}");
        }
        w.line("");
        let names: Vec<String> = fields.iter().map(|(f, _)| f.clone()).collect();
        scopes::field_by_field_eq(w, "Solution", &names, false);
        w.line("#[allow(dead_code)]");
        w.open("impl Solution {");
        let mut accessors = Namer::default();
        for reserved in ["points", "vectors", "scalars"] {
            accessors.reserve(reserved);
        }
        let mut all_points: Vec<(String, String)> = Vec::new();
        let mut all_vectors: Vec<(String, String)> = Vec::new();
        let mut all_scalars: Vec<(String, String)> = Vec::new();
        for g in self.solved() {
            let geom = &m.geoms[g];
            let frame = format!("self.{}", frame_field[&g]);
            let mut items: Vec<(String, String, String, String)> = Vec::new(); // (name, doc, type, body)
            match geom.kind {
                GeomKind::Point if self.constant.contains(&g) => items.push((
                    geom.name.clone(),
                    format!("Point `{}`, which the solve never moves.", geom.name),
                    "Point2<f64>".into(),
                    frame_field[&g].clone(),
                )),
                GeomKind::Vector if self.constant.contains(&g) => items.push((
                    geom.name.clone(),
                    format!("Vector `{}`, which the solve never moves.", geom.name),
                    "Vector2<f64>".into(),
                    frame_field[&g].clone(),
                )),
                GeomKind::Body => {
                    items.push((
                        geom.name.clone(),
                        format!("The frame of body `{}`.", geom.name),
                        "Frame2".into(),
                        frame.clone(),
                    ));
                }
                GeomKind::Point => items.push((
                    geom.name.clone(),
                    format!("Point `{}`.", geom.name),
                    "Point2<f64>".into(),
                    format!("{frame}.origin"),
                )),
                GeomKind::Vector => items.push((
                    geom.name.clone(),
                    format!("Vector `{}`.", geom.name),
                    "Vector2<f64>".into(),
                    format!("{frame}.x_axis()"),
                )),
                GeomKind::Circle => {
                    items.push((
                        format!("{}.radius", geom.name),
                        format!("The radius of `{}`.", geom.name),
                        "f64".into(),
                        format!("self.{}", dim_field[&g]),
                    ));
                }
                GeomKind::Segment => {
                    items.push((
                        format!("{}.length", geom.name),
                        format!("The length of `{}`.", geom.name),
                        "f64".into(),
                        format!("self.{}", dim_field[&g]),
                    ));
                }
                _ => {}
            }
            for &part in &geom.parts {
                let p = &m.geoms[part];
                match (p.owner, p.kind) {
                    (Owner::Member(_), GeomKind::Point | GeomKind::Marker) => {
                        items.push((
                            p.name.clone(),
                            format!("Point `{}`.", p.name),
                            "Point2<f64>".into(),
                            match local_field.get(&part) {
                                Some(f) => format!("{frame}.point_to_global(&self.{f})"),
                                None => {
                                    let at = self.literal_coords(part, true);
                                    point_in(&frame, &format!("{frame}.origin"), at)
                                }
                            },
                        ));
                        if p.kind == GeomKind::Marker {
                            if let Some(&ax) = p.parts.first() {
                                let n = &m.geoms[ax].name;
                                items.push((
                                    n.clone(),
                                    format!("Axis `{n}`."),
                                    "Vector2<f64>".into(),
                                    match local_field.get(&ax) {
                                        Some(f) => format!("{frame}.vector_to_global(&self.{f})"),
                                        None => {
                                            direction_in(&frame, self.literal_coords(ax, false))
                                        }
                                    },
                                ));
                            }
                        }
                    }
                    (Owner::Member(_), GeomKind::Vector) => {
                        items.push((
                            p.name.clone(),
                            format!("Vector `{}`.", p.name),
                            "Vector2<f64>".into(),
                            match local_field.get(&part) {
                                Some(f) => format!("{frame}.vector_to_global(&self.{f})"),
                                None => direction_in(&frame, self.literal_coords(part, false)),
                            },
                        ));
                    }
                    (Owner::Part(_, Part::Start | Part::Center), _) => items.push((
                        p.name.clone(),
                        format!("Point `{}`.", p.name),
                        "Point2<f64>".into(),
                        format!("{frame}.origin"),
                    )),
                    (Owner::Part(_, Part::End), _) => items.push((
                        p.name.clone(),
                        format!("Point `{}`.", p.name),
                        "Point2<f64>".into(),
                        format!("{frame}.origin + {frame}.x_axis() * self.{}", dim_field[&g]),
                    )),
                    (Owner::Part(_, Part::Dir), _) => items.push((
                        p.name.clone(),
                        format!("Direction `{}`.", p.name),
                        "Vector2<f64>".into(),
                        format!("{frame}.x_axis()"),
                    )),
                    (Owner::Part(_, Part::BasePoint), _) => {
                        // The foot of the perpendicular from the first sketch point.
                        if let Sketch::Line { from, .. } = &geom.sketch {
                            if from.iter().all(|&e| m.exprs.is_constant(e)) {
                                let s = self.point_lit(from);
                                items.push((p.name.clone(), format!("Point `{}`: the foot of the perpendicular from the line's first sketch point.", p.name), "Point2<f64>".into(),
                                    format!("{frame}.origin + {frame}.x_axis() * ({s} - {frame}.origin).dot(&{frame}.x_axis())")));
                            }
                        }
                    }
                    _ => {}
                }
            }
            for (name, doc, ty, body) in items {
                let accessor = accessors.fresh(&name);
                w.line(&format!("/// {doc}"));
                w.line("#[inline]");
                w.open(&format!("pub fn {accessor}(&self) -> {ty} {{"));
                w.line(&body);
                w.close("}");
                w.line("");
                match ty.as_str() {
                    "Point2<f64>" => all_points.push((name, accessor)),
                    "Vector2<f64>" => all_vectors.push((name, accessor)),
                    "f64" => all_scalars.push((name, accessor)),
                    _ => {}
                }
            }
        }
        // Every value by its dotted name, for callers that iterate (and for the test driver).
        for (what, ty, list) in [
            ("point", "Point2<f64>", &all_points),
            ("vector", "Vector2<f64>", &all_vectors),
            ("scalar", "f64", &all_scalars),
        ] {
            w.line(&format!(
                "/// Every {what} of the solution, by its dotted name in the model."
            ));
            w.open(&format!(
                "pub fn {what}s(&self) -> [(&'static str, {ty}); {}] {{",
                list.len()
            ));
            w.open("[");
            for (name, accessor) in list.iter() {
                w.line(&format!("({}, self.{accessor}()),", lit(name)));
            }
            w.close("]");
            w.close("}");
            w.line("");
        }
        if self.out_trailing_blank(w) {
            w.out.pop();
        }
        w.close("}");
        w.line("");
        self.frames = frame_field;
        self.dims = dim_field;
        self.locals = local_field;
        fields
    }

    /// The unit direction (cosine, sine) of a vector with a constant sketch: the frame the
    /// runtime would build, computed once here, so the solve and the `Solution` agree to the bit.
    fn constant_direction(&self, c: &[ExprId]) -> (f64, f64) {
        let v = |i: usize| c.get(i).map_or(0.0, |&e| self.model.exprs.eval(e, &[]));
        let f = gcs_runtime::frame::Frame2::along(
            nalgebra::Point2::origin(),
            nalgebra::Vector2::new(v(0), v(1)),
        );
        (f.rotation.re, f.rotation.im)
    }

    /// The literal value of a reported point or vector that stays where its constant sketch
    /// puts it (a fixed reference, typically), computed as the solve's sketch frame would be.
    fn constant_value(&self, g: GeomId) -> Option<String> {
        let m = self.model;
        let geom = &m.geoms[g];
        if self.moved(g) {
            return None;
        }
        let value = |c: &[ExprId], i: usize| c.get(i).map(|&e| m.exprs.eval(e, &[]));
        match (&geom.kind, &geom.sketch) {
            (GeomKind::Point, Sketch::Point(c)) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                Some(format!(
                    "Point2::new({}, {})",
                    float(value(c, 0)?),
                    float(value(c, 1)?)
                ))
            }
            (GeomKind::Vector, Sketch::Vector(c)) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                let (cos, sin) = self.constant_direction(c);
                Some(format!("Vector2::new({}, {})", float(cos), float(sin)))
            }
            _ => None,
        }
    }

    fn out_trailing_blank(&self, w: &Writer) -> bool {
        w.out.ends_with("\n\n")
    }

    /// A member's local coordinates as a literal (constant sketch).
    fn local_literal(&self, g: GeomId, point: bool) -> String {
        let (x, y) = self.literal_coords(g, point);
        let kind = if point { "Point2" } else { "Vector2" };
        format!("{kind}::new({}, {})", float(x), float(y))
    }

    /// A member's local coordinates when they are a literal, `None` when params set them (a
    /// local of the solve then holds them).
    fn local_value(&self, g: GeomId, point: bool) -> Option<(f64, f64)> {
        if self.locals.contains_key(&g) {
            return None;
        }
        Some(self.literal_coords(g, point))
    }

    /// The constant sketch of a member's local coordinates; a vector normalised exactly as the
    /// interpreter's configuration does, to the bit.
    fn literal_coords(&self, g: GeomId, point: bool) -> (f64, f64) {
        let m = self.model;
        let coords: Vec<f64> = match &m.geoms[g].sketch {
            Sketch::Point(c) | Sketch::Vector(c) => {
                c.iter().map(|&e| m.exprs.eval(e, &[])).collect()
            }
            Sketch::Marker { origin, .. } => origin.iter().map(|&e| m.exprs.eval(e, &[])).collect(),
            Sketch::Derived => match m.geoms[g].owner {
                Owner::Part(owner, Part::AxisX) => match &m.geoms[owner].sketch {
                    Sketch::Marker { x, .. } => x.iter().map(|&e| m.exprs.eval(e, &[])).collect(),
                    _ => vec![1.0, 0.0],
                },
                _ => vec![0.0, 0.0],
            },
            _ => vec![0.0, 0.0],
        };
        let (x, y) = (
            coords.first().copied().unwrap_or(0.0),
            coords.get(1).copied().unwrap_or(0.0),
        );
        if point {
            (x, y)
        } else {
            let u = nalgebra::Vector2::new(x, y).normalize();
            (u.x, u.y)
        }
    }

    /// Which coordinate (0 for x, 1 for y) of a member point's sketch is the constant zero, if
    /// one is.
    fn zero_coordinate(&self, g: GeomId) -> Option<usize> {
        let m = self.model;
        let c = match &m.geoms[g].sketch {
            Sketch::Point(c) | Sketch::Marker { origin: c, .. } => c,
            _ => return None,
        };
        let zero = |i: usize| {
            c.get(i)
                .is_some_and(|&e| m.exprs.is_constant(e) && m.exprs.eval(e, &[]) == 0.0)
        };
        (0..2).find(|&i| zero(i))
    }

    /// A point's constant coordinates, when every one is a constant.
    fn point_value(&self, c: &[ExprId]) -> Option<(f64, f64)> {
        let m = self.model;
        if !c.iter().all(|&e| m.exprs.is_constant(e)) {
            return None;
        }
        let v = |i: usize| c.get(i).map_or(0.0, |&e| m.exprs.eval(e, &[]));
        Some((v(0), v(1)))
    }

    // ------------------------------------------------------------ solve

    fn solve_fn(&mut self, w: &mut Writer, fields: &[(String, String)]) {
        let m = self.model;
        w.line("/// Solves the model: the assembly plan's steps, in order. Never panics, allocates nothing.");
        w.line("///");
        w.line("/// # Errors");
        w.line("///");
        w.line("/// A [`SolveError`] naming the constraint that cannot be met (no intersection, inconsistent,");
        w.line("/// degenerate, or a branch with no assembly here) and by how much, or a non-finite param.");
        // `#[inline]` lets a caller in another crate inline a small solve (a four-bar: its
        // answer then stays in registers instead of a `Solution` in memory); LLVM still weighs
        // its size, so a long solve stays a call.
        w.line("#[inline]");
        w.open("pub fn solve(params: &Params, branches: &Branches, defaults: &Defaults) -> Result<Solution, SolveError> {");
        w.line("let _ = (params, branches, defaults);");
        // Params must be finite.
        if !m.params.is_empty() {
            let list: Vec<String> = m
                .params
                .iter()
                .map(|(id, p)| format!("({}, params.{})", lit(&p.name), self.params[&id]))
                .collect();
            w.line(&format!(
                "gcs_runtime::error::check_all_finite(&[{}])?;",
                list.join(", ")
            ));
        }
        // The sketch: frames, dimensions and members' local coordinates.
        w.line("// The sketch: where every geom starts.");
        let solved = self.solved();
        // Every geom the plan reads or moves gets a frame; the solution reports `solved` ones.
        let worked: Vec<GeomId> = self
            .model
            .top_level()
            .map(|(id, _)| id)
            .filter(|id| (solved.contains(id) && !self.constant.contains(id)) || self.touched(*id))
            .collect();
        // Declarations wait for the steps: a frame the code never reads or moves is left out,
        // and only a moved one is `mut`.
        let mut decls = Vec::new();
        for &g in &worked {
            let geom = &m.geoms[g];
            let name = self.names.fresh(&geom.name);
            // The same construction as the interpreter's configuration, so that both agree to
            // the last bits: no rotation, a direction, or an angle.
            let at = |origin: String, identity: bool, value: Option<(f64, f64)>| {
                let facts = FrameFacts {
                    identity,
                    origin: Some(
                        value.map_or(Origin::Code(origin.clone()), |(x, y)| Origin::Literal(x, y)),
                    ),
                };
                (origin, facts)
            };
            let (ctor, facts) = match &geom.sketch {
                Sketch::Point(c) | Sketch::Circle { center: c, .. } => {
                    let (o, facts) = at(self.point_lit(c), true, self.point_value(c));
                    (format!("Frame2::at({o})"), facts)
                }
                Sketch::Vector(c) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                    let (cos, sin) = self.constant_direction(c);
                    let identity = (cos, sin) == (1.0, 0.0);
                    let (_, facts) = at("Point2::origin()".into(), identity, Some((0.0, 0.0)));
                    if identity {
                        ("Frame2::at(Point2::origin())".to_string(), facts)
                    } else {
                        let ctor = format!(
                            "Frame2::from_cos_sin(Point2::origin(), {}, {})",
                            float(cos),
                            float(sin)
                        );
                        (ctor, facts)
                    }
                }
                Sketch::Vector(c) => {
                    let (_, facts) = at("Point2::origin()".into(), false, Some((0.0, 0.0)));
                    let ctor = format!("Frame2::along(Point2::origin(), {})", self.vector_lit(c));
                    (ctor, facts)
                }
                Sketch::Line { from, to } | Sketch::Segment { from, to } => {
                    let (a, facts) = at(self.point_lit(from), false, self.point_value(from));
                    let b = self.point_lit(to);
                    (format!("Frame2::along({a}, {b} - {a})"), facts)
                }
                Sketch::Body {
                    at: place, angle, ..
                } => {
                    let (origin, value) = match place {
                        Some(c) => (self.point_lit(c), self.point_value(c)),
                        None => ("Point2::origin()".into(), Some((0.0, 0.0))),
                    };
                    let angle = angle.map(|e| match m.exprs.is_constant(e) {
                        true => Ok(m.exprs.eval(e, &[])),
                        false => Err(e),
                    });
                    let identity = matches!(angle, None | Some(Ok(0.0)));
                    let (origin, facts) = at(origin, identity, value);
                    let ctor = match angle {
                        None | Some(Ok(0.0)) => format!("Frame2::at({origin})"),
                        Some(Ok(a)) => {
                            let (sin, cos) = a.sin_cos();
                            format!(
                                "Frame2::from_cos_sin({origin}, {}, {})",
                                float(cos),
                                float(sin)
                            )
                        }
                        Some(Err(e)) => format!("Frame2::new({origin}, {})", self.expr(e)),
                    };
                    (ctor, facts)
                }
                _ => {
                    let (_, facts) = at("Point2::origin()".into(), true, Some((0.0, 0.0)));
                    ("Frame2::at(Point2::origin())".into(), facts)
                }
            };
            decls.push(Decl::Frame(
                g,
                Binding {
                    mutable: false,
                    name: name.clone(),
                    value: ctor,
                },
            ));
            self.facts.insert(g, facts);
            self.frames.insert(g, name);
            if matches!(geom.kind, GeomKind::Segment | GeomKind::Circle) {
                let what = if geom.kind == GeomKind::Circle {
                    "radius"
                } else {
                    "length"
                };
                let dname = self.names.fresh(&format!("{}_{what}", geom.name));
                let value = match &geom.sketch {
                    Sketch::Segment { from, to }
                        if from.iter().chain(to).all(|&e| m.exprs.is_constant(e)) =>
                    {
                        let v = |c: &[ExprId], i: usize| {
                            c.get(i).map_or(0.0, |&e| m.exprs.eval(e, &[]))
                        };
                        float((v(to, 0) - v(from, 0)).hypot(v(to, 1) - v(from, 1)))
                    }
                    Sketch::Segment { from, to } => {
                        format!("({} - {}).norm()", self.point_lit(to), self.point_lit(from))
                    }
                    Sketch::Circle { radius, .. } => self.expr(*radius),
                    _ => "0.0".into(),
                };
                if self.dim_set_before_read(g) {
                    // Set once by the plan before anything reads it: declared there.
                    self.deferred.insert(g);
                } else {
                    decls.push(Decl::Value(Binding {
                        mutable: self.dim_set(g),
                        name: dname.clone(),
                        value,
                    }));
                }
                self.dims.insert(g, dname);
            }
            for &part in &geom.parts {
                let p = &m.geoms[part];
                if !matches!(p.owner, Owner::Member(_)) || !self.local_is_param(part) {
                    continue;
                }
                // The solution stores the locals of the geoms it reports; other geoms need a
                // local only where a step reads it.
                let reported = solved.contains(&g);
                let axis = p.parts.first().copied();
                let wanted = |s: &Self, f: GeomId| reported || s.reads_feature(f);
                match &p.sketch {
                    Sketch::Point(c) | Sketch::Marker { origin: c, .. } if wanted(self, part) => {
                        let lname = self.names.fresh(&format!("{}_local", p.name));
                        decls.push(Decl::Value(Binding {
                            mutable: false,
                            name: lname.clone(),
                            value: self.point_lit(c),
                        }));
                        self.locals.insert(part, lname);
                    }
                    Sketch::Vector(c) if wanted(self, part) => {
                        let lname = self.names.fresh(&format!("{}_local", p.name));
                        decls.push(Decl::Value(Binding {
                            mutable: false,
                            name: lname.clone(),
                            value: format!("{}.normalize()", self.vector_lit(c)),
                        }));
                        self.locals.insert(part, lname);
                    }
                    _ => {}
                }
                if let (Sketch::Marker { x, .. }, Some(ax)) = (&p.sketch, axis) {
                    if wanted(self, ax) {
                        let xname = self.names.fresh(&format!("{}_x_local", p.name));
                        decls.push(Decl::Value(Binding {
                            mutable: false,
                            name: xname.clone(),
                            value: format!("{}.normalize()", self.vector_lit(x)),
                        }));
                        self.locals.insert(ax, xname);
                    }
                }
            }
        }
        // Tolerance of run-time checks: relative to the model's scale. It reads the frames and
        // dimensions, so it is declared after them.
        let mut tol = None;
        if self
            .plan
            .steps
            .iter()
            .any(|s| matches!(s.op, Op::Check { .. } | Op::Onto { .. }))
        {
            let mut terms = Vec::new();
            // The scale of the geoms the plan works on, as the interpreter measures it.
            for &g in worked.iter().filter(|g| self.index.touched.contains(g)) {
                let f = self.frame(g);
                terms.push(format!("{f}.origin.x"));
                terms.push(format!("{f}.origin.y"));
                if let Some(d) = self.dims.get(&g) {
                    if self.deferred.contains(&g) {
                        // Not declared yet: its sketch value, as the interpreter has it now.
                        if let Some(v) = self.sketch_dim(g) {
                            terms.push(v);
                        }
                    } else {
                        terms.push(d.clone());
                    }
                }
            }
            tol = Some(format!(
                "let tol = gcs_runtime::tol::CHECK_REL * (1.0 + gcs_runtime::tol::scale(&[{}]));",
                terms.join(", ")
            ));
        }
        // Each group of steps, up to the one that satisfies a constraint, opens with a comment
        // quoting that constraint and its place in the file.
        let mut body = Writer {
            out: String::new(),
            indent: w.indent,
        };
        let w_outer = w;
        let w = &mut body;
        let mut group_start = true;
        // Where the current group's code starts: a group whose steps all turn out to move
        // nothing says so under its comment.
        let mut group_code = 0;
        // Where each group starts, so that a long solve can be put in blocks.
        let mut group_starts = Vec::new();
        for (i, step) in self.plan.steps.iter().enumerate() {
            if group_start {
                group_starts.push(w.out.len());
                if let Some(end) = self.plan.steps[i..]
                    .iter()
                    .find(|s| !s.satisfies.is_empty())
                {
                    w.line("");
                    for c in &end.satisfies {
                        let con = &m.constraints[*c];
                        let label = con
                            .label
                            .as_ref()
                            .map_or(String::new(), |l| format!("{l}: "));
                        w.line(&format!(
                            "// {label}{} ({}:{})",
                            con.text,
                            self.file,
                            m.line(con.span)
                        ));
                    }
                }
                group_start = false;
                group_code = w.out.len();
            }
            self.step(w, i, step);
            if !step.satisfies.is_empty() {
                if w.out.len() == group_code {
                    w.line("// Already true where the sketch puts the geoms: nothing moves.");
                }
                group_start = true;
            }
        }
        let steps = std::mem::take(&mut w.out);
        let groups: Vec<String> = group_starts
            .iter()
            .zip(group_starts.iter().skip(1).chain([&steps.len()]))
            .map(|(&from, &to)| steps[from..to].to_string())
            .collect();
        // The solution.
        w.line("");
        w.open("Ok(Solution {");
        let frames = self.frames.clone();
        let dims = self.dims.clone();
        let locals = self.locals.clone();
        let mut field_iter = fields.iter();
        for g in solved {
            if self.constant.contains(&g) {
                continue;
            }
            if let Some((f, _)) = field_iter.next() {
                self.frame_reads.borrow_mut().insert(g);
                w.line(&field_init(f, &frames[&g]));
            }
            if dims.contains_key(&g) {
                if let Some((f, _)) = field_iter.next() {
                    w.line(&field_init(f, &dims[&g]));
                }
            }
            for &part in &m.geoms[g].parts {
                let p = &m.geoms[part];
                if matches!(p.owner, Owner::Member(_)) && self.local_is_param(part) {
                    if let Some((f, _)) = field_iter.next() {
                        w.line(&field_init(f, &locals[&part]));
                    }
                    if p.kind == GeomKind::Marker {
                        if let (Some(&ax), Some((f, _))) = (p.parts.first(), field_iter.next()) {
                            w.line(&field_init(f, &locals[&ax]));
                        }
                    }
                }
            }
        }
        w.close("})");
        let mut bindings = Vec::new();
        for decl in decls {
            match decl {
                Decl::Frame(g, frame) => {
                    let mutable = self.frame_writes.contains(&g);
                    if mutable || self.frame_reads.borrow().contains(&g) {
                        bindings.push(Binding { mutable, ..frame });
                    }
                }
                Decl::Value(binding) => bindings.push(binding),
            }
        }
        scopes::declare(w_outer, &bindings);
        if let Some(tol) = tol {
            w_outer.line(&tol);
        }
        w_outer
            .out
            .push_str(&scopes::in_blocks(&groups, &body.out, body.indent));
        w_outer.out.push_str(&body.out);
        w_outer.close("}");
    }

    /// Whether a step reads feature `f` (a member point, vector, marker or marker axis).
    fn reads_feature(&self, f: GeomId) -> bool {
        let m = self.model;
        let owner = match m.geoms[f].owner {
            Owner::Part(o, _) => Some(o),
            _ => None,
        };
        self.index.read.contains(&f)
            || self.index.checked.contains(&f)
            || owner.is_some_and(|o| self.index.checked.contains(&o))
    }

    /// The sketch value of a segment's length or a circle's radius, as code.
    fn sketch_dim(&self, g: GeomId) -> Option<String> {
        match &self.model.geoms[g].sketch {
            Sketch::Segment { from, to } => Some(format!(
                "({} - {}).norm()",
                self.point_lit(to),
                self.point_lit(from)
            )),
            Sketch::Circle { radius, .. } => Some(self.expr(*radius)),
            _ => None,
        }
    }

    /// Whether any step reads or moves geom `g`.
    fn touched(&self, g: GeomId) -> bool {
        self.index.touched.contains(&g)
    }

    /// Whether any step moves geom `g`.
    fn moved(&self, g: GeomId) -> bool {
        self.index.moved.contains(&g)
    }

    /// Whether the plan sets geom `g`'s dimension before any step reads it.
    fn dim_set_before_read(&self, g: GeomId) -> bool {
        self.index.dim_first.get(&g).copied().unwrap_or(false)
    }

    fn dim_set(&self, g: GeomId) -> bool {
        self.index.dim_set.contains(&g)
    }

    /// The constraint a step works for: its own, or that of the next step that satisfies one.
    fn constraint_of(&self, i: usize) -> Option<ConstraintId> {
        self.plan.constraint_of(i)
    }

    /// `SolveError::new(label, text, kind, magnitude)` for the constraint of step `i`.
    fn error(&self, i: usize, kind: &str, magnitude: &str) -> String {
        let (label, text) = match self.constraint_of(i) {
            Some(c) => (
                self.model.constraints[c].name.clone(),
                self.model.constraints[c].text.clone(),
            ),
            None => ("plan".to_string(), String::new()),
        };
        format!(
            "SolveError::new({}, {}, ErrorKind::{kind}, {magnitude})",
            lit(&label),
            lit(&text)
        )
    }

    fn r(&self, r: Reg) -> String {
        self.regs
            .get(&r)
            .cloned()
            .unwrap_or_else(|| "f64::NAN".into())
    }

    /// The local of top-level geom `g`'s frame, noted as read.
    fn frame(&self, g: GeomId) -> String {
        self.frame_reads.borrow_mut().insert(g);
        self.frames.get(&g).cloned().unwrap_or_default()
    }

    /// Code for the origin of top-level geom `g`'s frame now: what is known of it, or a read.
    fn origin_code(&self, g: GeomId) -> String {
        match self.facts.get(&g).and_then(|f| f.origin.as_ref()) {
            Some(o) => o.code(),
            None => format!("{}.origin", self.frame(g)),
        }
    }

    /// For a point of a frame not yet turned, whose origin's code stays its value: that code
    /// and the point's constant offset from it (the local coordinates themselves).
    fn offset_from_origin(&self, g: GeomId) -> Option<(String, (f64, f64))> {
        let m = self.model;
        let top = m.top_level_of(g);
        let facts = self.facts.get(&top)?;
        let origin = facts.origin.as_ref().filter(|_| facts.identity)?;
        let local = match m.geoms[g].owner {
            Owner::Member(_) => self.local_value(g, true)?,
            Owner::TopLevel => (0.0, 0.0),
            Owner::Part(..) => return None,
        };
        Some((origin.code(), local))
    }

    /// The vector from register `pivot` to register `from` when it is a constant: two points
    /// read from one unturned frame, or a point of it and the frame's origin.
    fn constant_arm(&self, pivot: Reg, from: Reg) -> Option<(f64, f64)> {
        let (origin, (fx, fy)) = self.at_offset.get(&from)?;
        let (px, py) = match self.at_offset.get(&pivot) {
            Some((o, local)) if o == origin => *local,
            _ if self.r(pivot) == *origin => (0.0, 0.0),
            _ => return None,
        };
        Some((fx - px, fy - py))
    }

    /// The global position of a point feature, read from the frames now.
    fn point_code(&self, g: GeomId) -> String {
        let m = self.model;
        let top = m.top_level_of(g);
        let facts = self.facts.get(&top).cloned().unwrap_or_default();
        match m.geoms[g].owner {
            Owner::Member(_) => {
                let value = self.local_value(g, true);
                match (facts.identity, &facts.origin, value) {
                    // Not turned yet: the origin plus the local coordinates, a literal when both are.
                    (true, Some(Origin::Literal(ox, oy)), Some((x, y))) => {
                        format!("Point2::new({}, {})", float(ox + x), float(oy + y))
                    }
                    (true, _, Some((0.0, 0.0))) => self.origin_code(top),
                    (true, _, Some((x, y))) => format!(
                        "{} + Vector2::new({}, {})",
                        self.origin_code(top),
                        float(x),
                        float(y)
                    ),
                    (true, _, None) => {
                        format!(
                            "{} + {}.coords",
                            self.origin_code(top),
                            self.local_code(g, true)
                        )
                    }
                    (false, _, Some(local)) => {
                        let origin = self.origin_code(top);
                        point_in(&self.frame(top), &origin, local)
                    }
                    (false, _, None) => {
                        // Set by params, but one coordinate may still be a literal zero.
                        let (f, l) = (self.frame(top), self.local_code(g, true));
                        match self.zero_coordinate(g) {
                            Some(1) => {
                                offset(&self.origin_code(top), &format!("{f}.x_axis() * {l}.x"))
                            }
                            Some(0) => {
                                offset(&self.origin_code(top), &format!("{f}.y_axis() * {l}.y"))
                            }
                            _ => format!("{f}.point_to_global(&{l})"),
                        }
                    }
                }
            }
            Owner::Part(owner, Part::End) => {
                let dim = self.dims.get(&owner).cloned().unwrap_or_default();
                let origin = self.origin_code(top);
                if facts.identity {
                    format!("{origin} + Vector2::new({dim}, 0.0)")
                } else {
                    format!("{origin} + {}.x_axis() * {dim}", self.frame(top))
                }
            }
            Owner::TopLevel | Owner::Part(..) => self.origin_code(top),
        }
    }

    fn local_code(&self, g: GeomId, point: bool) -> String {
        match self.locals.get(&g) {
            Some(l) => l.clone(),
            None => self.local_literal(g, point),
        }
    }

    /// The global direction of a vector feature, read from the frames now.
    fn dir_code(&self, g: GeomId) -> String {
        let m = self.model;
        let top = m.top_level_of(g);
        let identity = self.facts.get(&top).is_some_and(|f| f.identity);
        let literal = |(x, y): (f64, f64)| format!("Vector2::new({}, {})", float(x), float(y));
        match m.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX) => {
                match (identity, self.local_value(g, false)) {
                    (true, Some(local)) => literal(local),
                    (true, None) => self.local_code(g, false),
                    (false, Some(local)) => direction_in(&self.frame(top), local),
                    (false, None) => format!(
                        "{}.vector_to_global(&{})",
                        self.frame(top),
                        self.local_code(g, false)
                    ),
                }
            }
            _ if identity => literal((1.0, 0.0)),
            _ => format!("{}.x_axis()", self.frame(top)),
        }
    }

    fn define(&mut self, w: &mut Writer, reg: Reg, name: &str, code: &str) {
        if !self.used.contains(&reg) {
            return;
        }
        let local = self.names.fresh(name);
        w.line(&format!("let {local} = {code};"));
        self.regs.insert(reg, local);
    }

    /// Like [`Gen::define`] for a scalar the params give, which can overflow however finite
    /// they are (`theta * 1e300`): the step's constraint cannot be met with a value that is
    /// not finite, so the solve says so rather than going on with garbage.
    fn define_finite(&mut self, w: &mut Writer, i: usize, reg: Reg, name: &str, code: &str) {
        self.define(w, reg, name, code);
        if !self.used.contains(&reg) {
            return;
        }
        let v = self.r(reg);
        w.open(&format!("if !gcs_runtime::num::is_finite({v}) {{"));
        w.line(&format!(
            "return Err({});",
            self.error(i, "InvalidValue", &v)
        ));
        w.close("}");
        self.finite.insert(reg);
    }

    /// Like [`Gen::define`], but a literal or a local needs no new local: the register is
    /// that code.
    fn define_or_alias(&mut self, w: &mut Writer, reg: Reg, name: &str, code: String) {
        let literal = (code.starts_with("Point2::new(") || code.starts_with("Vector2::new("))
            && code.matches('(').count() == 1
            && !code.contains("params.");
        if is_ident(&code) || literal {
            if literal {
                self.reg_names.insert(reg, Namer::snake(name));
            }
            self.regs.insert(reg, code);
        } else {
            self.define(w, reg, name, &code);
        }
    }

    /// A name derived from register `r`: `{name}{suffix}` after its local or what it names,
    /// else `fallback`.
    fn derived_name(&self, r: Reg, suffix: &str, fallback: &str) -> String {
        let code = self.r(r);
        match self.reg_names.get(&r) {
            Some(name) => format!("{name}{suffix}"),
            None if is_ident(&code) => format!("{code}{suffix}"),
            None => fallback.to_string(),
        }
    }

    /// `{prefix}_{name}` after register `r` (see [`Gen::derived_name`]), or just `prefix`.
    fn prefixed(&self, prefix: &str, r: Reg) -> String {
        let n = self.derived_name(r, "", "");
        if n.is_empty() {
            prefix.to_string()
        } else {
            format!("{prefix}_{n}")
        }
    }

    /// Rotates `geoms` about `pivot` by the rotation `code` computes: the frame's rotation
    /// set outright while it is the identity, and its origin left alone when it is the pivot.
    fn rotate(&mut self, w: &mut Writer, geoms: &[GeomId], pivot: &str, code: &str) {
        let turn = self.names.fresh("turn");
        w.line(&format!("let {turn} = {code};"));
        for &g in geoms {
            let frame = self.frames.get(&g).cloned().unwrap_or_default();
            let facts = self.facts.entry(g).or_default();
            let about_origin = facts.origin.as_ref().is_some_and(|o| o.code() == pivot);
            match (about_origin, facts.identity) {
                (true, true) => w.line(&format!("{frame}.set_rotation(&{turn});")),
                (true, false) => w.line(&format!("{frame}.turn_by(&{turn});")),
                (false, _) => {
                    facts.origin = None;
                    w.line(&format!("{frame}.rotate_about_by(&{pivot}, &{turn});"));
                }
            }
            facts.identity = false;
            self.frame_writes.insert(g);
        }
    }

    fn step(&mut self, w: &mut Writer, i: usize, step: &crate::plan::Step) {
        let m = self.model;
        let out = step.out.map(|o| o.0);
        let name_of = |g: GeomId| m.geoms[g].name.clone();
        match &step.op {
            Op::Expr(e) => {
                let code = self.expr(*e);
                if let (Some(r), ExprNode::Param(_)) = (out, m.exprs.node(*e)) {
                    // Params are checked finite on entry.
                    self.finite.insert(r);
                    self.regs.insert(r, code);
                } else if let Some(r) = out {
                    if m.exprs.is_constant(*e) {
                        if m.exprs.eval(*e, &[]).is_finite() {
                            self.finite.insert(r);
                        }
                        self.regs.insert(r, code);
                    } else {
                        self.define_finite(w, i, r, "value", &code);
                    }
                }
            }
            Op::Const(c) => {
                if let Some(r) = out {
                    if c.is_finite() {
                        self.finite.insert(r);
                    }
                    self.regs.insert(r, float(*c));
                }
            }
            Op::Neg(x) => {
                if let Some(r) = out {
                    if self.finite.contains(x) {
                        self.finite.insert(r);
                    }
                    let code = format!("-{}", self.r(*x));
                    self.define(w, r, "minus", &code);
                }
            }
            Op::PointOf(g) => {
                if let Some(r) = out {
                    if let Some(at) = self.offset_from_origin(*g) {
                        self.at_offset.insert(r, at);
                    }
                    let code = self.point_code(*g);
                    self.define_or_alias(w, r, &name_of(*g), code);
                }
            }
            Op::DirOf(g) => {
                if let Some(r) = out {
                    let code = self.dir_code(*g);
                    if code == "Vector2::new(1.0, 0.0)" {
                        self.unit_x.insert(r);
                    }
                    let n = name_of(*g);
                    let n = if n.ends_with(".dir") {
                        n
                    } else {
                        format!("{n}_dir")
                    };
                    self.define_or_alias(w, r, &n, code);
                }
            }
            Op::DimOf(g) => {
                if let Some(r) = out {
                    let d = self.dims.get(g).cloned().unwrap_or_default();
                    self.regs.insert(r, d);
                }
            }
            Op::Axis(x, y) => {
                if let Some(r) = out {
                    if (*x, *y) == (1.0, 0.0) {
                        self.unit_x.insert(r);
                    }
                    let code = format!("Vector2::new({}, {})", float(*x), float(*y));
                    self.regs.insert(r, code);
                }
            }
            Op::Rotated { dir, angle } => {
                if let Some(r) = out {
                    let (d, a) = (self.r(*dir), self.r(*angle));
                    let code = if self.unit_x.contains(dir) {
                        if self.finite.contains(angle) {
                            self.unit_dirs.insert(r);
                        }
                        format!("direction_at({a})")
                    } else {
                        format!("UnitComplex::new({a}) * {d}")
                    };
                    let n = self.derived_name(*dir, "_turned", "direction");
                    self.define(w, r, &n, &code);
                }
            }
            Op::Sum(terms) => {
                if let Some(r) = out {
                    let mut code = String::new();
                    for (k, (s, x)) in terms.iter().enumerate() {
                        let v = self.r(*x);
                        let (first, unit, minus) = (k == 0, *s == 1.0, *s == -1.0);
                        let term = match (first, unit, minus) {
                            (true, true, _) => v,
                            (true, _, true) => format!("-{v}"),
                            (true, _, _) => format!("{} * {v}", float(*s)),
                            (false, true, _) => format!(" + {v}"),
                            (false, _, true) => format!(" - {v}"),
                            (false, _, _) => format!(" + {} * {v}", float(*s)),
                        };
                        code.push_str(&term);
                    }
                    self.define_finite(w, i, r, "sum", &code);
                }
            }
            Op::Along { from, dir, to } => {
                if let Some(r) = out {
                    let code = format!(
                        "({} - {}).dot(&{})",
                        self.r(*to),
                        self.r(*from),
                        self.r(*dir)
                    );
                    self.define(w, r, "length", &code);
                }
            }
            Op::DirectionTo { from, to } => {
                if let Some(r) = out {
                    let err = self.error(i, "Degenerate", "0.0");
                    let code = format!(
                        "({} - {}).try_normalize(0.0).ok_or_else(|| {err})?",
                        self.r(*to),
                        self.r(*from)
                    );
                    self.define(w, r, "direction", &code);
                }
            }
            Op::Circle { center, radius } => {
                if let Some(r) = out {
                    let rad = self.r(*radius);
                    if !rad.parse::<f64>().is_ok_and(|x| x >= 0.0) {
                        w.open(&format!("if {rad} < 0.0 {{"));
                        w.line(&format!(
                            "return Err({});",
                            self.error(i, "NoIntersection", &format!("-{rad}"))
                        ));
                        w.close("}");
                    }
                    let code = format!(
                        "Circle::new({}, {rad}).ok_or_else(|| {})?",
                        self.r(*center),
                        self.error(i, "Degenerate", "0.0")
                    );
                    let n = self.prefixed("circle", *center);
                    self.define(w, r, &n, &code);
                    self.circle_centers.insert(r, self.r(*center));
                }
            }
            Op::CircleThrough {
                center,
                through,
                radius,
            } => {
                if let Some(r) = out {
                    let (c, t) = (self.r(*center), self.r(*through));
                    // Two features of one rigid geom with constant local coordinates: their
                    // distance is known now.
                    let known = *radius;
                    if let Some(k) = known {
                        self.circle_radius.insert((*center, *through), k);
                    }
                    let radius = known.map_or_else(|| format!("({t} - {c}).norm()"), float);
                    let code = format!(
                        "Circle::new({c}, {radius}).ok_or_else(|| {})?",
                        self.error(i, "Degenerate", "0.0")
                    );
                    // Named after its centre and the point it goes through, when these are
                    // locals (a constant radius needs no point).
                    let about = self.derived_name(*center, "", "");
                    let n = match (about.is_empty(), known.is_none() && is_ident(&t)) {
                        (false, true) => format!("circle_{about}_{t}"),
                        (false, false) => format!("circle_{about}"),
                        (true, _) => "circle".into(),
                    };
                    self.define(w, r, &n, &code);
                    self.circle_centers.insert(r, c);
                }
            }
            Op::Line { point, dir, offset } => {
                if let Some(r) = out {
                    let mut code = format!(
                        "Line::new({}, {}).ok_or_else(|| {})?",
                        self.r(*point),
                        self.r(*dir),
                        self.error(i, "Degenerate", "0.0")
                    );
                    if let Some(o) = offset {
                        code = format!("{code}.offset({})", self.r(*o));
                    }
                    let n = self.prefixed("line", *point);
                    self.define(w, r, &n, &code);
                }
            }
            Op::ParallelLine { line, through } => {
                if let Some(r) = out {
                    let code = format!(
                        "Line::new({}, {}.dir()).ok_or_else(|| {})?",
                        self.r(*through),
                        self.r(*line),
                        self.error(i, "Degenerate", "0.0")
                    );
                    let n = self.prefixed("parallel", *through);
                    self.define(w, r, &n, &code);
                }
            }
            Op::ShiftedCircle { circle, from, to } => {
                if let Some(r) = out {
                    let c = self.r(*circle);
                    let code = format!(
                        "Circle::new({c}.center() + ({} - {}), {c}.radius()).ok_or_else(|| {})?",
                        self.r(*to),
                        self.r(*from),
                        self.error(i, "Degenerate", "0.0")
                    );
                    let n = self.derived_name(*circle, "_moved", "circle_moved");
                    self.define(w, r, &n, &code);
                }
            }
            Op::Reversed(x) => {
                if let Some(r) = out {
                    let code = format!("{}.reversed()", self.r(*x));
                    let n = self.derived_name(*x, "_reversed", "reversed");
                    self.define(w, r, &n, &code);
                }
            }
            Op::OffsetLine { line, by } => {
                if let Some(r) = out {
                    let code = format!("{}.offset({})", self.r(*line), self.r(*by));
                    let n = self.derived_name(*line, "_offset", "offset");
                    self.define(w, r, &n, &code);
                }
            }
            Op::CentresLineLine { l1, a1, l2, a2 } => {
                if let Some(r) = out {
                    let code = format!(
                        "locus2d::centres_line_line(&{}, {}, &{}, {}).ok_or_else(|| {})?",
                        self.r(*l1),
                        self.r(*a1),
                        self.r(*l2),
                        self.r(*a2),
                        self.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "bisector", &code);
                }
            }
            Op::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => {
                if let Some(r) = out {
                    let code = format!(
                        "Conic::Parabola(locus2d::centres_line_circle(&{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?)",
                        self.r(*line),
                        self.r(*a),
                        self.r(*at),
                        if *plus { "Plus" } else { "Minus" },
                        self.r(*b),
                        self.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "parabola", &code);
                }
            }
            Op::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => {
                if let Some(r) = out {
                    let code = format!(
                        "locus2d::centres_circle_circle({}, Sense::{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?",
                        self.r(*c1),
                        if *p1 { "Plus" } else { "Minus" },
                        self.r(*b1),
                        self.r(*c2),
                        if *p2 { "Plus" } else { "Minus" },
                        self.r(*b2),
                        self.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "conic", &code);
                }
            }
            Op::RadiusFromLine { line, a, centre } => {
                if let Some(r) = out {
                    let code = format!(
                        "{}.signed_distance({}) - {}",
                        self.r(*line),
                        self.r(*centre),
                        self.r(*a)
                    );
                    self.define(w, r, "radius", &code);
                }
            }
            Op::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => {
                if let Some(r) = out {
                    let d = format!("({} - {}).norm()", self.r(*centre), self.r(*at));
                    let code = if *plus {
                        format!("{d} - {}", self.r(*b))
                    } else {
                        format!("{} - {d}", self.r(*b))
                    };
                    self.define(w, r, "radius", &code);
                }
            }
            Op::Nearest { locus, point } => {
                if let Some(r) = out {
                    let code = format!("{}.nearest({})", self.r(*locus), self.r(*point));
                    let n = self.prefixed("nearest", *point);
                    self.define(w, r, &n, &code);
                }
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                if let Some(r) = out {
                    let gap = self.names.fresh("gap");
                    w.line(&format!(
                        "let {gap} = {}.residual({});",
                        self.r(*locus),
                        self.r(*point)
                    ));
                    w.open(&format!("if {gap}.is_nan() || {gap} > tol {{"));
                    let con = &m.constraints[*constraint];
                    w.line(&format!(
                        "return Err(SolveError::new({}, {}, ErrorKind::Inconsistent, {gap}));",
                        lit(&con.name),
                        lit(&con.text)
                    ));
                    w.close("}");
                    let p = self.r(*point);
                    self.regs.insert(r, p);
                }
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                ..
            } => {
                if let Some(r) = out {
                    let con = &m.constraints[*constraint];
                    let f = match meet {
                        Meet::CircleCircle => "circle_circle",
                        Meet::LineCircle => "line_circle",
                        Meet::LineLine => "line_line",
                        Meet::CircleConic => "circle_conic",
                        Meet::LineConic => "line_conic",
                        spatial => panic!(
                            "bug in gcs: the spatial intersection {spatial:?} reached the planar code generator"
                        ),
                    };
                    let index = match self.branches.get(branch.0 as usize) {
                        Some(field) if self.plan.branches[branch.0 as usize].count > 1 => {
                            format!("usize::from(branches.{field})")
                        }
                        _ => "0".into(),
                    };
                    if *meet == Meet::CircleCircle {
                        // Only the chosen root is computed.
                        let (label, text) = (lit(&con.name), lit(&con.text));
                        let chord = format!(
                            "intersect2d::circle_circle_chord(&{}, &{}).map_err(|miss| SolveError::from_miss({label}, {text}, miss))?",
                            self.r(*a),
                            self.r(*b),
                        );
                        let root = format!(
                            ".root({index}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, 2.0))?"
                        );
                        if !self.rotated_onto.contains(&r) {
                            self.define(w, r, &con.name, &format!("{chord}{root}"));
                            return;
                        }
                        // A rotation turns a point onto this root: the chord is kept, so that
                        // the rotation reads the root from its centre, to the last bits.
                        let local = self.names.fresh(&format!("{}_chord", con.name));
                        w.line(&format!("let {local} = {chord};"));
                        self.define(w, r, &con.name, &format!("{local}{root}"));
                        let center =
                            |c: &Reg| self.circle_centers.get(c).cloned().unwrap_or_default();
                        let centers = [center(a), center(b)];
                        let kept = ChordRoot {
                            chord: local,
                            index,
                            centers,
                        };
                        self.chord_roots.insert(r, kept);
                        return;
                    }
                    let meeting = self.names.fresh(&format!("{}_meeting", con.name));
                    w.line(&format!(
                        "let {meeting} = intersect2d::{f}(&{}, &{});",
                        self.r(*a),
                        self.r(*b)
                    ));
                    w.open(&format!(
                        "if let Some(e) = SolveError::from_contact({}, {}, {meeting}.contact) {{",
                        lit(&con.name),
                        lit(&con.text)
                    ));
                    w.line("return Err(e);");
                    w.close("}");
                    let code = format!(
                        "{meeting}.branch({index}).ok_or_else(|| SolveError::new({}, {}, ErrorKind::NoSuchBranch, {meeting}.roots.len() as f64))?",
                        lit(&con.name),
                        lit(&con.text)
                    );
                    self.define(w, r, &con.name, &code);
                }
            }
            Op::Translate { geoms, from, to } => {
                let (f, t) = (self.r(*from), self.r(*to));
                if f == t {
                    // From a point onto itself: nothing moves.
                    return;
                }
                let mut shift = None;
                for &g in geoms {
                    let facts = self.facts.entry(g).or_default();
                    let frame = self.frames.get(&g).cloned().unwrap_or_default();
                    if facts.origin.as_ref().is_some_and(|o| o.code() == f) {
                        // The point brought onto `to` is the origin: it lands there exactly.
                        facts.origin = Some(Origin::Code(t.clone()));
                        w.line(&format!("{frame}.place_origin(&{t});"));
                    } else {
                        facts.origin = None;
                        let shift = shift.get_or_insert_with(|| {
                            let name = self.names.fresh("shift");
                            w.line(&format!("let {name} = {t} - {f};"));
                            name
                        });
                        w.line(&format!("{frame}.translate(&{shift});"));
                    }
                    self.frame_writes.insert(g);
                }
            }
            Op::RotatePoint {
                geoms,
                pivot,
                from,
                to,
                ..
            } => {
                let (p, f, t) = (self.r(*pivot), self.r(*from), self.r(*to));
                // From the pivot to the target: read from the chord when the target is a root
                // of a circle about the pivot (the same vector, without the cancellation of a
                // difference of points far from the origin).
                let from_chord = self.chord_roots.get(to).and_then(|root| {
                    let side = root.centers.iter().position(|c| *c == p)?;
                    let f = ["root_from_a", "root_from_b"][side];
                    Some(format!(
                        "{}.{f}({}).unwrap_or({t} - {p})",
                        root.chord, root.index
                    ))
                });
                let to_target = match &from_chord {
                    Some(code) => format!("&{code}"),
                    None => format!("&({t} - {p})"),
                };
                let radius = self.circle_radius.get(&(*pivot, *from)).copied();
                let code = match (radius, self.constant_arm(*pivot, *from)) {
                    // A point of a rigid geom turned onto its circle about the pivot, from where
                    // the sketch put it: the arm and the circle's radius are constants, so the
                    // rotation's cosine and sine are `(arm . reach, arm x reach) / radius²`
                    // with constant coefficients.
                    (Some(radius), Some((ax, ay))) if radius > 0.0 => {
                        let reach = self.names.fresh(&self.derived_name(*to, "_reach", "reach"));
                        let code = from_chord.unwrap_or_else(|| format!("{t} - {p}"));
                        w.line(&format!("let {reach} = {code};"));
                        let k = 1.0 / (radius * radius);
                        let (kx, ky) = (ax * k, ay * k);
                        let c = linear(&[(kx, format!("{reach}.x")), (ky, format!("{reach}.y"))]);
                        let s = linear(&[(kx, format!("{reach}.y")), (-ky, format!("{reach}.x"))]);
                        // The arm itself is read only when the lengths disagree with the
                        // radius, off the fast path.
                        format!("rotation_on_circle_from({c}, {s}, &({f} - {p}), &{reach})")
                    }
                    // A point of a rigid geom turned onto its circle about the pivot: the
                    // circle's radius is known, and with it the rotation's scale.
                    (Some(radius), _) => format!(
                        "rotation_on_circle(&({f} - {p}), {to_target}, {})",
                        float(radius)
                    ),
                    (None, _) => format!("rotation_between2(&({f} - {p}), {to_target})"),
                };
                self.rotate(w, geoms, &p, &code);
            }
            Op::RotateDir {
                geoms,
                pivot,
                from,
                to,
                ..
            } => {
                let (p, f, t) = (self.r(*pivot), self.r(*from), self.r(*to));
                let code = if self.unit_x.contains(from) && self.unit_dirs.contains(to) {
                    // A finite unit direction: it is the rotation, with nothing to test.
                    format!("rotation_from_x_unit(&{t})")
                } else if self.unit_x.contains(from) {
                    format!("rotation_from_x(&{t})")
                } else {
                    format!("rotation_between_units(&{f}, &{t})")
                };
                self.rotate(w, geoms, &p, &code);
            }
            Op::SetDim { geom, value } => {
                let v = self.r(*value);
                let known_good = v.parse::<f64>().is_ok_and(|x| x.is_finite() && x >= 0.0);
                if !known_good {
                    let test = if self.finite.contains(value) {
                        format!("if {v} < 0.0 {{")
                    } else {
                        format!("if !gcs_runtime::num::is_finite({v}) || {v} < 0.0 {{")
                    };
                    w.open(&test);
                    w.line(&format!(
                        "return Err({});",
                        self.error(i, "InvalidValue", &v)
                    ));
                    w.close("}");
                }
                let d = self.dims.get(geom).cloned().unwrap_or_default();
                if self.deferred.remove(geom) {
                    w.line(&format!("let {d} = {v};"));
                } else {
                    w.line(&format!("{d} = {v};"));
                }
            }
            Op::Check {
                constraint,
                residual,
            } => {
                let residual = self.residual_code(residual);
                let name = self.names.fresh("residual");
                w.line(&format!("let {name} = {residual};"));
                w.open(&format!("if {name}.is_nan() || {name} > tol {{"));
                let con = &m.constraints[*constraint];
                w.line(&format!(
                    "return Err(SolveError::new({}, {}, ErrorKind::Inconsistent, {name}));",
                    lit(&con.name),
                    lit(&con.text)
                ));
                w.close("}");
            }
            Op::Default(d) => {
                if let Some(r) = out {
                    let field = self.defaults.get(d.0 as usize).cloned().unwrap_or_default();
                    self.finite.insert(r);
                    self.regs.insert(r, format!("defaults.{field}"));
                }
            }
            Op::Close {
                constraint,
                residual,
            } => {
                let name = self.names.fresh("closing");
                w.line(&format!("let {name} = {}.abs();", self.r(*residual)));
                w.open(&format!("if {name}.is_nan() || {name} > tol {{"));
                let con = &m.constraints[*constraint];
                w.line(&format!(
                    "return Err(SolveError::new({}, {}, ErrorKind::NoConvergence, {name}));",
                    lit(&con.name),
                    lit(&con.text)
                ));
                w.close("}");
            }
        }
    }

    /// The call of the runtime's residual of a check's relation, on its registers.
    fn residual_code(&self, residual: &crate::plan::Residual) -> String {
        use crate::plan::Residual as R;
        let r = |x: &Reg| self.r(*x);
        let opt = |x: &Option<Reg>| x.as_ref().map_or_else(|| "0.0".to_string(), r);
        match residual {
            R::PointPoint { a, b, d } => {
                format!("check::point_point({}, {}, {})", r(a), r(b), opt(d))
            }
            R::PointLine { p, base, dir, d } => format!(
                "check::point_line({}, {}, {}, {})",
                r(p),
                r(base),
                r(dir),
                opt(d)
            ),
            R::Angle { u, v, angle } => {
                format!("check::angle({}, {}, {})", r(u), r(v), r(angle))
            }
            R::CircleLine {
                centre,
                radius,
                base,
                dir,
                gap,
                side,
            } => format!(
                "check::circle_line({}, {}, {}, {}, {}, {})",
                r(centre),
                r(radius),
                r(base),
                r(dir),
                opt(gap),
                float(*side)
            ),
            R::PointCircle {
                p,
                centre,
                radius,
                gap,
                outside,
            } => format!(
                "check::point_circle({}, {}, {}, {}, {outside})",
                r(p),
                r(centre),
                r(radius),
                opt(gap)
            ),
            R::CircleCircle {
                c1,
                r1,
                c2,
                r2,
                gap,
                nesting,
            } => format!(
                "check::circle_circle({}, {}, {}, {}, {}, check::Nesting::{nesting:?})",
                r(c1),
                r(r1),
                r(c2),
                r(r2),
                opt(gap)
            ),
            R::Dim { value, target } => format!("check::dimension({}, {})", r(value), r(target)),
        }
    }
}

/// The module formatted by `rustfmt`, when a `rustfmt` is on the path (as it is wherever cargo
/// is installed with its usual components); otherwise the module as generated.
pub fn format(code: &str) -> String {
    use std::io::Write as _;
    use std::process::{Command, Stdio};
    let child = Command::new("rustfmt")
        .args(["--edition", "2021", "--emit", "stdout", "--quiet"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn();
    let Ok(mut child) = child else {
        return code.to_string();
    };
    if let Some(mut stdin) = child.stdin.take() {
        if stdin.write_all(code.as_bytes()).is_err() {
            return code.to_string();
        }
    }
    match child.wait_with_output() {
        Ok(out) if out.status.success() && !out.stdout.is_empty() => {
            String::from_utf8(out.stdout).unwrap_or_else(|_| code.to_string())
        }
        _ => code.to_string(),
    }
}
