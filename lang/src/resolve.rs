//! Name resolution and checking: syntax tree to [`Model`].
//!
//! Three passes: declare every name (so that declarations may come in any order), lower every
//! expression, sketch and constraint against the constraint table, then check what needs
//! values: params' defaults (recursion, division by zero, NaN), units, zero vectors and marker
//! axes. Every problem becomes a diagnostic; resolution goes on to find the next one.

use crate::constraints::{self, ArgClass, ConstraintKind, JointValue, ValueKind};
use crate::diagnostic::Diagnostic;
use crate::expr::{Dim, ExprId, ExprNode, Exprs, Func, ParamId};
use crate::model::*;
use crate::source::{SourceFile, Span};
use crate::syntax::{self, AngleUnit, ExprKind, GeomDecl, SpecPart, SpecValue, StatementKind};
use la_arena::Arena;
use std::collections::{BTreeMap, HashMap, HashSet};

/// Words that can never name anything.
pub const RESERVED: &[&str] = &[
    "space", "param", "fixed", "point", "vector", "line", "segment", "circle", "plane", "body",
    "marker", "output", "deg", "rad", "pi",
];

/// Resolves a parsed file. `complete` is false when some statements were dropped for syntax
/// errors: names they would have declared are then not reported as unknown.
pub fn resolve(
    source: &SourceFile,
    file: &syntax::File,
    complete: bool,
) -> (Option<Model>, Vec<Diagnostic>) {
    let mut r = Resolver {
        source,
        complete,
        diags: Vec::new(),
        space: Space::D2,
        params: Arena::new(),
        exprs: Exprs::default(),
        geoms: Arena::new(),
        constraints: Arena::new(),
        outputs: Vec::new(),
        names: BTreeMap::new(),
        top: BTreeMap::new(),
        labels: BTreeMap::new(),
        spans: HashMap::new(),
        slots: Vec::new(),
        param_syntax: Vec::new(),
        vector_checks: Vec::new(),
        poisoned: HashSet::new(),
        refused: HashSet::new(),
        joint_uses: Vec::new(),
    };
    r.header(file);
    r.declare(file);
    r.lower(file);
    r.check_params();
    r.check_values();
    r.check_units();
    r.check_unused_params();
    let has_errors = r.diags.iter().any(Diagnostic::is_error);
    let diags = std::mem::take(&mut r.diags);
    if has_errors {
        return (None, diags);
    }
    let model = Model {
        param_index: ParamIndex::new(&r.params),
        source: source.clone(),
        space: r.space,
        params: r.params,
        exprs: r.exprs,
        geoms: r.geoms,
        constraints: r.constraints,
        outputs: r.outputs,
        names: r.names,
    };
    (Some(model), diags)
}

/// An entry of the top-level namespace.
#[derive(Clone, Copy, Debug)]
enum TopName {
    Param(ParamId),
    Geom(GeomId),
}

/// What a slot of the syntax needs its expression to be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Need {
    Length,
    Angle,
}

/// A vector-valued sketch that must not be zero, or a marker whose axes must be orthogonal.
#[derive(Clone, Debug)]
enum VectorCheck {
    NonZero {
        coords: Coords,
        span: Span,
        what: &'static str,
    },
    Distinct {
        from: Coords,
        to: Coords,
        span: Span,
        what: &'static str,
    },
    Orthogonal {
        z: Coords,
        x: Coords,
        span: Span,
    },
    NonNegative {
        value: ExprId,
        span: Span,
        what: &'static str,
    },
}

struct Resolver<'a> {
    source: &'a SourceFile,
    complete: bool,
    diags: Vec<Diagnostic>,
    space: Space,
    params: Arena<Param>,
    exprs: Exprs,
    geoms: Arena<Geom>,
    constraints: Arena<Constraint>,
    outputs: Vec<Output>,
    names: BTreeMap<String, GeomId>,
    top: BTreeMap<String, (TopName, Span)>,
    labels: BTreeMap<String, Span>,
    /// The source span of every lowered expression node.
    spans: HashMap<ExprId, Span>,
    /// Expressions whose dimension is constrained by where they stand.
    slots: Vec<(ExprId, Need)>,
    /// Each param's default as written, by param id order.
    param_syntax: Vec<(ParamId, Option<&'a syntax::Expr>)>,
    vector_checks: Vec<VectorCheck>,
    /// Params whose default is already reported as wrong: expressions that read them are
    /// not reported again.
    poisoned: HashSet<ParamId>,
    /// Names of top-level declarations refused for their kind (a plane in 2d, a marker
    /// outside a body): uses of them are not reported again.
    refused: HashSet<String>,
    /// References that may name a joint's value (`J.angle`) where a geom or a number is
    /// needed: reported once every constraint is named (see [`Resolver::joint_use`]).
    joint_uses: Vec<(syntax::Path, JointUse)>,
}

/// Where a reference that may name a joint's value stands, other than in `output`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum JointUse {
    /// A constraint's argument.
    Argument,
    /// An expression.
    Expression,
}

impl<'a> Resolver<'a> {
    fn push(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    // ---------------------------------------------------------------- header

    fn header(&mut self, file: &syntax::File) {
        let mut first: Option<Span> = None;
        for (i, stmt) in file.statements.iter().enumerate() {
            let StatementKind::Space { dim } = &stmt.kind else {
                continue;
            };
            if let Some(prev) = first {
                self.push(
                    Diagnostic::error(stmt.span, "repeated `space` header")
                        .with_label("a second header")
                        .with_secondary(prev, "the space is already set here")
                        .with_note("a model has exactly one `space` header, first"),
                );
                continue;
            }
            first = Some(stmt.span);
            match dim.text.as_str() {
                "2d" => self.space = Space::D2,
                "3d" => self.space = Space::D3,
                other => {
                    let d = Diagnostic::error(dim.span, format!("unknown space `{other}`"))
                        .with_label("expected `2d` or `3d`");
                    self.push(d);
                }
            }
            if i != 0 {
                let d = Diagnostic::error(stmt.span, "the `space` header must come first")
                    .with_secondary(file.statements[0].span, "this statement comes before it");
                self.push(d);
            }
        }
        if first.is_none() && self.complete {
            if file.statements.is_empty() {
                let end = self.source.text().len();
                let d = Diagnostic::error(Span::empty(end), "empty model")
                    .with_note("a model starts with `space 2d;` or `space 3d;`, then declares geoms and constraints");
                self.push(d);
            } else {
                let at = file.statements[0].span;
                let d = Diagnostic::error(Span::empty(at.start), "missing `space` header")
                    .with_label("expected `space 2d;` or `space 3d;` here")
                    .with_note("every model says first which space it lives in");
                self.push(d);
            }
        }
    }

    // ---------------------------------------------------------------- declarations

    fn check_name(&mut self, name: &syntax::Ident, what: &str) -> bool {
        if RESERVED.contains(&name.text.as_str()) {
            let d = Diagnostic::error(
                name.span,
                format!("`{}` is a reserved word and cannot name {what}", name.text),
            )
            .with_label("reserved word")
            .with_note(format!("reserved words: {}", RESERVED.join(" ")));
            self.push(d);
            return false;
        }
        true
    }

    fn declare_top(&mut self, name: &syntax::Ident, entry: TopName) -> bool {
        if let Some((_, prev)) = self.top.get(&name.text) {
            let prev = *prev;
            let d = Diagnostic::error(name.span, format!("`{}` is declared twice", name.text))
                .with_label("second declaration")
                .with_secondary(prev, "first declared here")
                .with_note("params, geoms and bodies share one namespace");
            self.push(d);
            return false;
        }
        self.top.insert(name.text.clone(), (entry, name.span));
        true
    }

    fn declare(&mut self, file: &'a syntax::File) {
        for stmt in &file.statements {
            match &stmt.kind {
                StatementKind::Param { name, value } => {
                    if let Some(f) = stmt.fixed {
                        self.fixed_means_nothing(
                            f,
                            "a param is a run-time input; it cannot be fixed",
                        );
                    }
                    if !self.check_name(name, "a param") {
                        continue;
                    }
                    let placeholder = self.exprs.alloc(ExprNode::Const(f64::NAN));
                    let id = self.params.alloc(Param {
                        name: name.text.clone(),
                        default_expr: placeholder,
                        default: f64::NAN,
                        dim: Dim::Number,
                        span: name.span,
                    });
                    if self.declare_top(name, TopName::Param(id)) {
                        self.param_syntax.push((id, Some(value)));
                    } else {
                        self.param_syntax.push((id, None));
                    }
                }
                StatementKind::Geom(decl) => {
                    if !self.check_name(&decl.name, "a geom") {
                        continue;
                    }
                    let Some(kind) = self.geom_kind(decl, false) else {
                        // Reported: its uses are not reported again.
                        self.refused.insert(decl.name.text.clone());
                        continue;
                    };
                    let fixed = decl.fixed.is_some();
                    let id = self.new_geom(
                        decl.name.text.clone(),
                        kind,
                        Owner::TopLevel,
                        fixed,
                        decl.name.span,
                    );
                    if self.declare_top(&decl.name, TopName::Geom(id)) {
                        self.names.insert(decl.name.text.clone(), id);
                        self.add_parts(id);
                    }
                }
                StatementKind::Body { name, members, .. } => {
                    if !self.check_name(name, "a body") {
                        continue;
                    }
                    let fixed = stmt.fixed.is_some();
                    let id = self.new_geom(
                        name.text.clone(),
                        GeomKind::Body,
                        Owner::TopLevel,
                        fixed,
                        name.span,
                    );
                    if !self.declare_top(name, TopName::Geom(id)) {
                        continue;
                    }
                    self.names.insert(name.text.clone(), id);
                    let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
                    for m in members {
                        if let Some(f) = m.fixed {
                            self.fixed_means_nothing(
                                f,
                                "members move with their body; write `fixed` before `body` to ground the body",
                            );
                        }
                        if !self.check_name(&m.name, "a member") {
                            continue;
                        }
                        let Some(kind) = self.geom_kind(m, true) else {
                            continue;
                        };
                        if let Some(prev) = seen.get(m.name.text.as_str()) {
                            let d = Diagnostic::error(
                                m.name.span,
                                format!("`{}.{}` is declared twice", name.text, m.name.text),
                            )
                            .with_label("second declaration")
                            .with_secondary(*prev, "first declared here");
                            self.push(d);
                            continue;
                        }
                        seen.insert(&m.name.text, m.name.span);
                        let full = format!("{}.{}", name.text, m.name.text);
                        let mid = self.new_geom(
                            full.clone(),
                            kind,
                            Owner::Member(id),
                            fixed,
                            m.name.span,
                        );
                        self.geoms[id].parts.push(mid);
                        self.names.insert(full, mid);
                        self.add_parts(mid);
                    }
                }
                _ => {}
            }
        }
    }

    fn fixed_means_nothing(&mut self, span: Span, note: &str) {
        let d = Diagnostic::error(span, "`fixed` means nothing here").with_note(note.to_string());
        self.push(d);
    }

    /// The kind a declaration keyword declares, or a diagnostic if it cannot stand there.
    fn geom_kind(&mut self, decl: &GeomDecl, member: bool) -> Option<GeomKind> {
        let kind = match decl.keyword.text.as_str() {
            "point" => GeomKind::Point,
            "vector" => GeomKind::Vector,
            "line" => GeomKind::Line,
            "segment" => GeomKind::Segment,
            "circle" => GeomKind::Circle,
            "plane" => GeomKind::Plane,
            "marker" => GeomKind::Marker,
            _ => return None,
        };
        if member && !matches!(kind, GeomKind::Point | GeomKind::Vector | GeomKind::Marker) {
            let d = Diagnostic::error(decl.keyword.span, format!("a body cannot hold {}", kind.noun()))
                .with_label("not a body member")
                .with_note("body members are points, vectors and markers; declare other geoms at top level and constrain them to the body");
            self.push(d);
            return None;
        }
        if !member && kind == GeomKind::Marker {
            let d = Diagnostic::error(decl.keyword.span, "a marker belongs to a body")
                .with_label("marker outside a body")
                .with_note("declare it inside a body: `body B { marker k = (0, 0) x (1, 0); }`");
            self.push(d);
            return None;
        }
        if kind == GeomKind::Plane && self.space == Space::D2 {
            let d = Diagnostic::error(decl.keyword.span, "a plane is not valid in 2d")
                .with_label("planes exist only in 3d")
                .with_note("in 2d every geom lies in the XY plane; use a line");
            self.push(d);
            return None;
        }
        Some(kind)
    }

    fn new_geom(
        &mut self,
        name: String,
        kind: GeomKind,
        owner: Owner,
        fixed: bool,
        span: Span,
    ) -> GeomId {
        self.geoms.alloc(Geom {
            name,
            kind,
            owner,
            fixed,
            span,
            sketch: Sketch::Derived,
            parts: Vec::new(),
        })
    }

    /// Creates the sub-geoms of a geom: `S.start`, `L.dir`, `k.z`, ...
    fn add_parts(&mut self, id: GeomId) {
        let d3 = self.space == Space::D3;
        let parts: &[(Part, GeomKind)] = match self.geoms[id].kind {
            GeomKind::Line => &[
                (Part::Dir, GeomKind::Vector),
                (Part::BasePoint, GeomKind::Point),
            ],
            GeomKind::Segment => &[
                (Part::Start, GeomKind::Point),
                (Part::End, GeomKind::Point),
                (Part::Dir, GeomKind::Vector),
            ],
            GeomKind::Circle if d3 => &[
                (Part::Center, GeomKind::Point),
                (Part::Normal, GeomKind::Vector),
            ],
            GeomKind::Circle => &[(Part::Center, GeomKind::Point)],
            GeomKind::Plane => &[(Part::Normal, GeomKind::Vector)],
            GeomKind::Marker if d3 => &[
                (Part::AxisZ, GeomKind::Vector),
                (Part::AxisX, GeomKind::Vector),
            ],
            GeomKind::Marker => &[(Part::AxisX, GeomKind::Vector)],
            _ => &[],
        };
        for &(part, kind) in parts {
            let owner = &self.geoms[id];
            let name = format!("{}.{}", owner.name, part.name());
            let (fixed, span) = (owner.fixed, owner.span);
            let pid = self.new_geom(name.clone(), kind, Owner::Part(id, part), fixed, span);
            self.geoms[id].parts.push(pid);
            self.names.insert(name, pid);
        }
    }

    // ---------------------------------------------------------------- lowering

    fn lower(&mut self, file: &'a syntax::File) {
        let mut outputs: Vec<&syntax::Path> = Vec::new();
        let syntaxes: Vec<(ParamId, Option<&syntax::Expr>)> = self.param_syntax.clone();
        for (id, e) in syntaxes {
            match e.and_then(|e| self.expr(e)) {
                Some(x) => self.params[id].default_expr = x,
                None => {
                    self.poisoned.insert(id);
                }
            }
        }
        for stmt in &file.statements {
            match &stmt.kind {
                StatementKind::Geom(decl) => {
                    if let Some(id) = self.declared(&decl.name) {
                        let sketch = self.sketch(decl, id);
                        self.geoms[id].sketch = sketch;
                    }
                }
                StatementKind::Body {
                    name,
                    at,
                    rotated,
                    repeated_placement,
                    members,
                } => {
                    for s in repeated_placement {
                        let d = Diagnostic::error(*s, "repeated placement clause")
                            .with_note("a body has at most one `at` and one `rotated`");
                        self.push(d);
                    }
                    let Some(id) = self.declared(name) else {
                        continue;
                    };
                    let at = at
                        .as_ref()
                        .and_then(|v| self.coords(v, "the body's position"));
                    let (mut angle, mut axis) = (None, None);
                    if let Some(rot) = rotated {
                        angle = self.expr(&rot.angle);
                        if let Some(a) = angle {
                            self.slots.push((a, Need::Angle));
                        }
                        if let Some(about) = &rot.about {
                            if self.space == Space::D2 {
                                let d =
                                    Diagnostic::error(about.span(), "`about` is not valid in 2d")
                                        .with_label("a 2d body rotates about the z axis")
                                        .with_note("drop `about (...)`");
                                self.push(d);
                            } else {
                                axis = self.coords(about, "the rotation axis");
                                if let Some(c) = &axis {
                                    self.vector_checks.push(VectorCheck::NonZero {
                                        coords: c.clone(),
                                        span: about.span(),
                                        what: "rotation axis",
                                    });
                                }
                            }
                        }
                    }
                    self.geoms[id].sketch = Sketch::Body { at, angle, axis };
                    for m in members {
                        let full = format!("{}.{}", name.text, m.name.text);
                        let Some(&mid) = self.names.get(&full) else {
                            continue;
                        };
                        if self.geoms[mid].span != m.name.span {
                            continue;
                        }
                        let sketch = self.sketch(m, mid);
                        self.geoms[mid].sketch = sketch;
                    }
                }
                StatementKind::Constraint {
                    label,
                    name,
                    args,
                    args_span,
                    value,
                } => {
                    self.constraint(stmt, label.as_ref(), name, args, *args_span, value.as_ref());
                }
                // Resolved once every constraint is named: an output may name a joint's value
                // by its constraint's derived name.
                StatementKind::Output { refs } => outputs.extend(refs),
                StatementKind::Space { .. } | StatementKind::Param { .. } => {}
            }
        }
        self.derive_names();
        let constraints: HashMap<String, ConstraintId> = (self.constraints.iter())
            .map(|(id, c)| (c.name.clone(), id))
            .collect();
        for p in outputs {
            self.output(p, &constraints);
        }
        for (p, used) in std::mem::take(&mut self.joint_uses) {
            self.joint_used(&p, used, &constraints);
        }
    }

    /// The geom declared by this very name token (not a duplicate of it).
    fn declared(&self, name: &syntax::Ident) -> Option<GeomId> {
        match self.top.get(&name.text) {
            Some((TopName::Geom(id), span)) if *span == name.span => Some(*id),
            _ => None,
        }
    }

    fn expr(&mut self, e: &syntax::Expr) -> Option<ExprId> {
        let node = match &e.kind {
            ExprKind::Number(v) => ExprNode::Const(*v),
            ExprKind::BadNumber(text) => {
                let d = match unit_after_number(text) {
                    // `1.5in`, `25mm`: a number, then a word.
                    Some((number, unit)) => {
                        let at = e.span.start + number.len();
                        Diagnostic::unknown_unit(Span::new(at, e.span.end), unit)
                    }
                    None => Diagnostic::error(e.span, format!("malformed number `{text}`"))
                        .with_label("not a number")
                        .with_note("numbers are written `12`, `1.5`, `1e-3` or `.5`"),
                };
                self.push(d);
                return None;
            }
            ExprKind::Pi => ExprNode::Const(std::f64::consts::PI),
            ExprKind::Path(p) => return self.expr_path(p),
            ExprKind::Neg(a) => ExprNode::Neg(self.expr(a)?),
            ExprKind::Paren(a) => return self.expr(a),
            ExprKind::Binary(op, a, b) => {
                let a = self.expr(a);
                let b = self.expr(b);
                ExprNode::Binary(*op, a?, b?)
            }
            ExprKind::Unit(a, unit, _) => ExprNode::Unit(*unit, self.expr(a)?),
            ExprKind::Call(name, args) => {
                let lowered: Vec<Option<ExprId>> = args.iter().map(|a| self.expr(a)).collect();
                let Some(f) = Func::from_name(&name.text) else {
                    let names: Vec<&str> = Func::ALL.iter().map(|f| f.name()).collect();
                    let mut d =
                        Diagnostic::error(name.span, format!("unknown function `{}`", name.text))
                            .with_label("not a function of the language");
                    d = match suggest(&name.text, names.iter().copied()) {
                        Some(s) => d.with_note(format!("did you mean `{s}`?")),
                        None => d.with_note(format!("the functions are {}", names.join(" "))),
                    };
                    self.push(d);
                    return None;
                };
                if args.len() != f.arity() {
                    let plural = if f.arity() == 1 { "" } else { "s" };
                    let d = Diagnostic::error(
                        e.span,
                        format!(
                            "`{}` takes {} argument{plural}, found {}",
                            f.name(),
                            f.arity(),
                            args.len()
                        ),
                    )
                    .with_label("wrong number of arguments");
                    self.push(d);
                    return None;
                }
                let mut it = lowered.into_iter();
                let a = it.next().flatten()?;
                let b = match it.next() {
                    Some(b) => Some(b?),
                    None => None,
                };
                ExprNode::Call(f, a, b)
            }
        };
        let id = self.exprs.alloc(node);
        self.spans.insert(id, e.span);
        Some(id)
    }

    fn expr_path(&mut self, p: &syntax::Path) -> Option<ExprId> {
        if self.joint_use(p, JointUse::Expression) {
            return None;
        }
        self.expr_path_reported(p)
    }

    /// [`Resolver::expr_path`] without the deferral of a joint's value.
    fn expr_path_reported(&mut self, p: &syntax::Path) -> Option<ExprId> {
        let dotted = p.dotted();
        if p.parts.len() == 1 {
            match self.top.get(&dotted) {
                Some((TopName::Param(id), _)) => {
                    let e = self.exprs.alloc(ExprNode::Param(*id));
                    self.spans.insert(e, p.span);
                    return Some(e);
                }
                Some((TopName::Geom(id), _)) => {
                    let kind = self.geoms[*id].kind;
                    let d = Diagnostic::error(
                        p.span,
                        format!("`{dotted}` is {}, not a number", kind.noun()),
                    )
                    .with_label("expressions may use params, numbers and `pi`")
                    .with_note("constrain geoms with constraints, such as `distance(a, b) = d;`");
                    self.push(d);
                    return None;
                }
                None => {}
            }
        }
        if self.names.contains_key(&dotted) {
            let d = Diagnostic::error(p.span, format!("`{dotted}` is a geom, not a number"))
                .with_label("expressions may use params, numbers and `pi`");
            self.push(d);
            return None;
        }
        if self.complete {
            let params: Vec<String> = self
                .top
                .iter()
                .filter(|(_, (t, _))| matches!(t, TopName::Param(_)))
                .map(|(n, _)| n.clone())
                .collect();
            let mut d = Diagnostic::error(p.span, format!("unknown name `{dotted}`"))
                .with_label("no param has this name");
            if let Some(s) = suggest(&dotted, params.iter().map(String::as_str)) {
                d = d.with_note(format!("did you mean `{s}`?"));
            }
            self.push(d);
        }
        None
    }

    /// A tuple of coordinates of the space's dimension.
    fn coords(&mut self, v: &SpecValue, what: &str) -> Option<Coords> {
        let n = self.space.coords();
        match v {
            SpecValue::Tuple(items, span) => {
                if items.len() != n {
                    let d = Diagnostic::error(
                        *span,
                        format!(
                            "expected {n} coordinates in {}, found {}",
                            self.space,
                            items.len()
                        ),
                    )
                    .with_label(format!("{what} needs {n} coordinates"));
                    self.push(d);
                    return None;
                }
                let mut out = Vec::with_capacity(n);
                let mut ok = true;
                for e in items {
                    match self.expr(e) {
                        Some(x) => {
                            self.slots.push((x, Need::Length));
                            out.push(x);
                        }
                        None => ok = false,
                    }
                }
                ok.then_some(out)
            }
            SpecValue::Expr(e) => {
                let example = if n == 2 { "(x, y)" } else { "(x, y, z)" };
                let d = Diagnostic::error(
                    e.span,
                    format!("expected coordinates {example}, found a single value"),
                )
                .with_label(format!("{what} needs {n} coordinates"));
                self.push(d);
                None
            }
        }
    }

    fn scalar(&mut self, v: &SpecValue, need: Need, what: &str) -> Option<ExprId> {
        match v {
            SpecValue::Expr(e) => {
                let x = self.expr(e)?;
                self.slots.push((x, need));
                Some(x)
            }
            SpecValue::Tuple(_, span) => {
                let d = Diagnostic::error(
                    *span,
                    format!("expected a single value for {what}, found coordinates"),
                );
                self.push(d);
                None
            }
        }
    }

    /// The sketch of a declaration, checked against its kind's form.
    fn sketch(&mut self, decl: &GeomDecl, id: GeomId) -> Sketch {
        let kind = self.geoms[id].kind;
        let d3 = self.space == Space::D3;
        let n = self.space.coords();
        let pt = if n == 2 { "(x, y)" } else { "(x, y, z)" };
        // Sort the parts into positional values, arrows and tags.
        let mut values: Vec<&SpecValue> = Vec::new();
        let mut arrows = 0;
        let mut tags: Vec<(&syntax::Ident, &SpecValue)> = Vec::new();
        for part in &decl.spec {
            match part {
                SpecPart::Arrow(_) => arrows += 1,
                SpecPart::Value(v) => values.push(v),
                SpecPart::Tagged { tag, value } => tags.push((tag, value)),
            }
        }
        let form = match kind {
            GeomKind::Point => format!("point P = {pt};"),
            GeomKind::Vector => format!("vector v = {pt};"),
            GeomKind::Line => format!("line L = {pt} -> {pt};"),
            GeomKind::Segment => format!("segment S = {pt} -> {pt};"),
            GeomKind::Circle if d3 => format!("circle C = center {pt} radius r normal (a, b, c);"),
            GeomKind::Circle => format!("circle C = center {pt} radius r;"),
            GeomKind::Plane => "plane Q = normal (a, b, c) offset d;` or `plane Q = point (x, y, z) normal (a, b, c);".to_string(),
            GeomKind::Marker if d3 => "marker k = (x, y, z) z (a, b, c) x (a, b, c);".to_string(),
            GeomKind::Marker => "marker k = (x, y) x (a, b);".to_string(),
            GeomKind::Body => String::new(),
        };
        let bad_form = |this: &mut Self| {
            let d = Diagnostic::error(
                decl.spec_span,
                format!("malformed {} declaration", kind.keyword()),
            )
            .with_label(format!("not the form of {}", kind.noun()))
            .with_note(format!("write `{form}`"));
            this.push(d);
            Sketch::Derived
        };
        // Tags allowed per kind, each at most once.
        let allowed: &[&str] = match kind {
            GeomKind::Circle if d3 => &["center", "radius", "normal"],
            GeomKind::Circle => &["center", "radius"],
            GeomKind::Plane => &["normal", "offset", "point"],
            GeomKind::Marker if d3 => &["z", "x"],
            GeomKind::Marker => &["x"],
            _ => &[],
        };
        let mut tagged: BTreeMap<&str, &SpecValue> = BTreeMap::new();
        for (tag, value) in &tags {
            if !allowed.contains(&tag.text.as_str()) {
                let mut d = Diagnostic::error(
                    tag.span,
                    format!(
                        "`{}` is not part of {} declaration",
                        tag.text,
                        kind.keyword()
                    ),
                )
                .with_note(format!("write `{form}`"));
                if kind == GeomKind::Circle && tag.text == "normal" {
                    d = d.with_label("a 2d circle lies in the XY plane and takes no normal");
                } else if kind == GeomKind::Marker && tag.text == "z" {
                    d = d.with_label(
                        "in 2d a marker has only its x axis; its z axis is out of the plane",
                    );
                }
                self.push(d);
                return Sketch::Derived;
            }
            if tagged.insert(tag.text.as_str(), value).is_some() {
                let d = Diagnostic::error(tag.span, format!("`{}` is given twice", tag.text));
                self.push(d);
                return Sketch::Derived;
            }
        }
        let name = self.geoms[id].name.clone();
        match kind {
            GeomKind::Point | GeomKind::Vector => {
                if values.len() != 1 || arrows != 0 || !tags.is_empty() {
                    return bad_form(self);
                }
                let Some(c) = self.coords(values[0], &format!("`{name}`")) else {
                    return Sketch::Derived;
                };
                if kind == GeomKind::Vector {
                    self.vector_checks.push(VectorCheck::NonZero {
                        coords: c.clone(),
                        span: values[0].span(),
                        what: "vector",
                    });
                    Sketch::Vector(c)
                } else {
                    Sketch::Point(c)
                }
            }
            GeomKind::Line | GeomKind::Segment => {
                if values.len() != 2 || arrows != 1 || !tags.is_empty() {
                    return bad_form(self);
                }
                let from = self.coords(values[0], "the first point");
                let to = self.coords(values[1], "the second point");
                let (Some(from), Some(to)) = (from, to) else {
                    return Sketch::Derived;
                };
                let what = if kind == GeomKind::Line {
                    "line"
                } else {
                    "segment"
                };
                self.vector_checks.push(VectorCheck::Distinct {
                    from: from.clone(),
                    to: to.clone(),
                    span: decl.spec_span,
                    what,
                });
                if kind == GeomKind::Line {
                    Sketch::Line { from, to }
                } else {
                    Sketch::Segment { from, to }
                }
            }
            GeomKind::Circle => {
                let (Some(c), Some(r)) = (tagged.get("center"), tagged.get("radius")) else {
                    return bad_form(self);
                };
                if !values.is_empty() || arrows != 0 || (d3 && !tagged.contains_key("normal")) {
                    if d3 && !tagged.contains_key("normal") && values.is_empty() {
                        let d = Diagnostic::error(decl.spec_span, "a 3d circle needs a normal")
                            .with_label("add `normal (a, b, c)`")
                            .with_note(format!("write `{form}`"));
                        self.push(d);
                        return Sketch::Derived;
                    }
                    return bad_form(self);
                }
                let center = self.coords(c, "the centre");
                let radius = self.scalar(r, Need::Length, "the radius");
                if let Some(value) = radius {
                    self.vector_checks.push(VectorCheck::NonNegative {
                        value,
                        span: r.span(),
                        what: "radius",
                    });
                }
                let normal = match tagged.get("normal") {
                    Some(v) => {
                        let c = self.coords(v, "the normal");
                        if let Some(c) = &c {
                            self.vector_checks.push(VectorCheck::NonZero {
                                coords: c.clone(),
                                span: v.span(),
                                what: "normal",
                            });
                        }
                        Some(c)
                    }
                    None => None,
                };
                match (center, radius, normal) {
                    (Some(center), Some(radius), None) => Sketch::Circle {
                        center,
                        radius,
                        normal: None,
                    },
                    (Some(center), Some(radius), Some(Some(n))) => Sketch::Circle {
                        center,
                        radius,
                        normal: Some(n),
                    },
                    _ => Sketch::Derived,
                }
            }
            GeomKind::Plane => {
                if !values.is_empty() || arrows != 0 {
                    return bad_form(self);
                }
                let Some(nv) = tagged.get("normal") else {
                    return bad_form(self);
                };
                let placement = match (tagged.get("offset"), tagged.get("point")) {
                    (Some(o), None) => self
                        .scalar(o, Need::Length, "the offset")
                        .map(PlanePlacement::Offset),
                    (None, Some(p)) => self.coords(p, "the point").map(PlanePlacement::Point),
                    _ => return bad_form(self),
                };
                let normal = self.coords(nv, "the normal");
                match (normal, placement) {
                    (Some(normal), Some(placement)) => {
                        self.vector_checks.push(VectorCheck::NonZero {
                            coords: normal.clone(),
                            span: nv.span(),
                            what: "normal",
                        });
                        Sketch::Plane { normal, placement }
                    }
                    _ => Sketch::Derived,
                }
            }
            GeomKind::Marker => {
                if values.len() != 1 || arrows != 0 {
                    return bad_form(self);
                }
                let Some(xv) = tagged.get("x") else {
                    let d = Diagnostic::error(decl.spec_span, "a marker needs its x axis")
                        .with_note(format!("write `{form}`"));
                    self.push(d);
                    return Sketch::Derived;
                };
                let zv = tagged.get("z").copied();
                if d3 && zv.is_none() {
                    let d = Diagnostic::error(decl.spec_span, "a 3d marker needs its z axis")
                        .with_note(format!("write `{form}`"));
                    self.push(d);
                    return Sketch::Derived;
                }
                let origin = self.coords(values[0], "the marker's point");
                let x = self.coords(xv, "the x axis");
                let z = zv.map(|v| self.coords(v, "the z axis"));
                let (Some(origin), Some(x)) = (origin, x) else {
                    return Sketch::Derived;
                };
                self.vector_checks.push(VectorCheck::NonZero {
                    coords: x.clone(),
                    span: xv.span(),
                    what: "x axis",
                });
                let z = match z {
                    Some(Some(z)) => {
                        if let Some(zv) = zv {
                            self.vector_checks.push(VectorCheck::NonZero {
                                coords: z.clone(),
                                span: zv.span(),
                                what: "z axis",
                            });
                        }
                        self.vector_checks.push(VectorCheck::Orthogonal {
                            z: z.clone(),
                            x: x.clone(),
                            span: decl.spec_span,
                        });
                        Some(z)
                    }
                    Some(None) => return Sketch::Derived,
                    None => None,
                };
                Sketch::Marker { origin, z, x }
            }
            GeomKind::Body => Sketch::Derived,
        }
    }

    // ---------------------------------------------------------------- constraints

    fn constraint(
        &mut self,
        stmt: &syntax::Statement,
        label: Option<&syntax::Ident>,
        name: &syntax::Ident,
        args: &[syntax::Expr],
        args_span: Span,
        value: Option<&syntax::Expr>,
    ) {
        if let Some(f) = stmt.fixed {
            self.fixed_means_nothing(
                f,
                "constraints are not grounded; `fixed` goes before a geom or body declaration",
            );
        }
        if let Some(l) = label {
            if self.check_name(l, "a label") {
                if let Some(prev) = self.labels.get(&l.text) {
                    let d = Diagnostic::error(l.span, format!("label `{}` is used twice", l.text))
                        .with_label("second use")
                        .with_secondary(*prev, "first used here")
                        .with_note(
                            "labels name branch variables and errors, so each must be unique",
                        );
                    self.push(d);
                } else {
                    self.labels.insert(l.text.clone(), l.span);
                }
            }
        }
        let Some(spec) = constraints::lookup(&name.text) else {
            let mut d = Diagnostic::error(name.span, format!("unknown constraint `{}`", name.text))
                .with_label("not a constraint of the language");
            if let Some(s) = suggest(&name.text, constraints::TABLE.iter().map(|s| s.name)) {
                d = d.with_note(format!("did you mean `{s}`?"));
            }
            self.push(d);
            return;
        };
        if !spec.spaces.allows(self.space) {
            let mut d = Diagnostic::error(
                name.span,
                format!("`{}` is not valid in {}", spec.name, self.space),
            )
            .with_label(format!(
                "only valid in {}",
                if self.space == Space::D2 { "3d" } else { "2d" }
            ));
            d = match spec.kind {
                ConstraintKind::Horizontal | ConstraintKind::Vertical => {
                    d.with_note("in 3d, constrain the direction with `angle` or `parallel` against a fixed vector")
                }
                ConstraintKind::InPlane | ConstraintKind::ParallelZ | ConstraintKind::Planar | ConstraintKind::Cylindrical => {
                    d.with_note("in 2d every marker's z axis is out of the plane, so this says nothing")
                }
                _ => d,
            };
            self.push(d);
            return;
        }
        // Arguments: each must name a geom.
        let mut resolved: Vec<(GeomId, Span)> = Vec::new();
        let mut ok = true;
        for a in args {
            match self.arg(a) {
                Some(g) => resolved.push((g, a.span)),
                None => ok = false,
            }
        }
        let arity = spec.forms.first().map_or(0, |f| f.len());
        if args.len() != arity {
            let plural = if arity == 1 { "" } else { "s" };
            let d = Diagnostic::error(
                args_span,
                format!(
                    "`{}` takes {arity} argument{plural}, found {}",
                    spec.name,
                    args.len()
                ),
            )
            .with_label("wrong number of arguments");
            self.push(d);
            return;
        }
        // The value.
        let value_id = match (spec.value, value) {
            (ValueKind::None, Some(v)) => {
                let d = Diagnostic::error(v.span, format!("`{}` takes no value", spec.name))
                    .with_label("remove `= ...`");
                self.push(d);
                ok = false;
                None
            }
            (ValueKind::None, None) => None,
            (vk, Some(v)) => {
                let x = self.expr(v);
                if let (Some(x), Some(dim)) = (x, vk.dim()) {
                    let need = if dim == Dim::Angle {
                        Need::Angle
                    } else {
                        Need::Length
                    };
                    self.slots.push((x, need));
                }
                if x.is_none() {
                    ok = false;
                }
                x
            }
            (vk, None) => {
                let what = if vk == ValueKind::Angle {
                    "an angle"
                } else {
                    "a length"
                };
                let example = format!(
                    "{}({}) = ...",
                    spec.name,
                    if arity == 1 { "x" } else { "a, b" }
                );
                let d = Diagnostic::error(stmt.span, format!("`{}` needs a value", spec.name))
                    .with_label(format!("missing `= {what}`"))
                    .with_note(format!("write `{example};`"));
                self.push(d);
                ok = false;
                None
            }
        };
        if !ok {
            return;
        }
        // Kinds, against the table's forms (in either order for symmetric constraints).
        let kinds: Vec<GeomKind> = resolved.iter().map(|(g, _)| self.geoms[*g].kind).collect();
        let fits = |form: &[ArgClass], kinds: &[GeomKind]| {
            form.iter().zip(kinds).all(|(c, k)| c.accepts(*k))
        };
        // Only the forms valid in this space (`symmetric` mirrors across a line in 2d, a
        // plane in 3d).
        let forms = forms_in(spec, self.space);
        let mut order: Option<Vec<usize>> = None;
        if forms.iter().any(|f| fits(f, &kinds)) {
            order = Some((0..kinds.len()).collect());
        } else if spec.symmetric && kinds.len() == 2 {
            let swapped = [kinds[1], kinds[0]];
            if forms.iter().any(|f| fits(f, &swapped)) {
                order = Some(vec![1, 0]);
            }
        }
        let Some(order) = order else {
            self.kind_error(spec, &forms, &resolved, &kinds);
            return;
        };
        let args: Vec<GeomId> = order.iter().map(|&i| resolved[i].0).collect();
        // `L.point` depends on where the sketch put the line's first point: an output, never
        // something to constrain.
        if let Some((g, span)) = resolved
            .iter()
            .find(|(g, _)| matches!(self.geoms[*g].owner, Owner::Part(_, Part::BasePoint)))
        {
            let name = self.geoms[*g].name.clone();
            let line = name.trim_end_matches(".point").to_string();
            let d = Diagnostic::error(
                *span,
                format!("`{name}` is an output, not a constraint argument"),
            )
            .with_label("the foot of the perpendicular from the line's first sketch point")
            .with_note(format!(
                "to put a point on the line, write `on(P, {line});`"
            ));
            self.push(d);
            return;
        }
        if spec.kind == ConstraintKind::Symmetric && args[0] == args[1] {
            let (p, l) = (&self.geoms[args[0]].name, &self.geoms[args[2]].name);
            let d = Diagnostic::error(
                args_span,
                format!("`symmetric` mirrors `{p}` onto itself"),
            )
            .with_label("the two points are the same geom")
            .with_note(format!(
                "a point is its own mirror image only on the mirror: to put it there, write `on({p}, {l});`"
            ));
            self.push(d);
            return;
        }
        if spec.kind == ConstraintKind::Midpoint
            && matches!(
                self.geoms[args[0]].owner,
                Owner::Part(s, Part::Start | Part::End) if s == args[1]
            )
        {
            let (p, s) = (&self.geoms[args[0]].name, &self.geoms[args[1]].name);
            let d = Diagnostic::error(
                resolved[order[0]].1,
                format!("`{p}` is an end of `{s}`, not its midpoint"),
            )
            .with_label(format!("an end of `{s}`"))
            .with_note("a segment's end is its midpoint only when its length is zero");
            self.push(d);
            return;
        }
        if args.len() == 2 && args[0] == args[1] {
            let d = Diagnostic::error(
                args_span,
                format!("`{}` is constrained to itself", self.geoms[args[0]].name),
            )
            .with_label("both arguments name the same geom");
            self.push(d);
            return;
        }
        if spec.kind == ConstraintKind::OffsetZ {
            if let Some(v) = value_id {
                if self.exprs.is_constant(v) && self.exprs.eval(v, &[]) == 0.0 {
                    let span = value.map_or(stmt.span, |v| v.span);
                    let d = Diagnostic::error(span, "`offset_z` needs a non-zero angle")
                        .with_note("for parallel z axes, use `parallel_z(m1, m2);`");
                    self.push(d);
                    return;
                }
            }
        }
        let text = constraint_text(self.source, name.span.start, stmt.span.end);
        self.constraints.alloc(Constraint {
            kind: spec.kind,
            args,
            value: value_id,
            label: label.map(|l| l.text.clone()),
            name: String::new(),
            span: stmt.span,
            text,
        });
    }

    /// Reports the first argument whose kind no form of the constraint accepts.
    fn kind_error(
        &mut self,
        spec: &constraints::ConstraintSpec,
        valid: &[&'static [ArgClass]],
        args: &[(GeomId, Span)],
        kinds: &[GeomKind],
    ) {
        let accepts = accepts_text(spec, valid, self.space);
        // Narrow the forms position by position; report at the first position that empties
        // them (position 0 of a symmetric pair may hold either class).
        let mut forms: Vec<&[ArgClass]> = valid.to_vec();
        for (i, (&kind, (g, span))) in kinds.iter().zip(args).enumerate() {
            let candidates: Vec<&[ArgClass]> = forms
                .iter()
                .copied()
                .filter(|f| {
                    f.get(i).is_some_and(|c| c.accepts(kind))
                        || (spec.symmetric
                            && f.len() == 2
                            && f.get(1 - i).is_some_and(|c| c.accepts(kind)))
                })
                .collect();
            if candidates.is_empty() {
                let mut wanted: Vec<&str> = Vec::new();
                for f in &forms {
                    let mut classes = vec![f.get(i).copied()];
                    if spec.symmetric && f.len() == 2 {
                        classes.push(f.get(1 - i).copied());
                    }
                    for c in classes.into_iter().flatten() {
                        let n = c.noun();
                        if !wanted.contains(&n) {
                            wanted.push(n);
                        }
                    }
                }
                let wanted = join_or(&wanted);
                let geom = &self.geoms[*g];
                let mut d = Diagnostic::error(
                    *span,
                    format!("expected {wanted}, found {}", geom.kind.noun()),
                )
                .with_label(format!("`{}` is {}", geom.name, geom.kind.noun()))
                .with_note(accepts.clone());
                if geom.kind == GeomKind::Body {
                    d = d.with_note(format!("a body is not itself a point or a line: name one of its members, such as `{}.…`", geom.name));
                }
                self.push(d);
                return;
            }
            forms = candidates;
        }
        // Each argument fits some form, but no single form fits them all.
        let names: Vec<String> = args
            .iter()
            .map(|(g, _)| format!("{} `{}`", self.geoms[*g].kind.noun(), self.geoms[*g].name))
            .collect();
        let span = args
            .first()
            .map(|a| a.1)
            .unwrap_or_default()
            .to(args.last().map(|a| a.1).unwrap_or_default());
        let d = Diagnostic::error(
            span,
            format!("`{}` does not relate {}", spec.name, names.join(" and ")),
        )
        .with_note(accepts);
        self.push(d);
    }

    /// A constraint argument: a name or dotted name of a geom.
    fn arg(&mut self, a: &syntax::Expr) -> Option<GeomId> {
        let ExprKind::Path(p) = &a.kind else {
            let d = Diagnostic::error(a.span, "expected the name of a geom, found an expression")
                .with_label("constraint arguments are geoms, members or sub-geoms");
            self.push(d);
            return None;
        };
        if self.joint_use(p, JointUse::Argument) {
            return None;
        }
        self.geom_path(p, "geom")
    }

    /// Whether `p` may name a joint's value (`J.angle`, `J.travel`: a word that names no
    /// geom or param, then a joint value's word) where a geom or number is needed: then its
    /// diagnostic waits until every constraint is named, and the caller treats it as
    /// reported. A joint's value is an output only.
    fn joint_use(&mut self, p: &syntax::Path, used: JointUse) -> bool {
        let [first, last] = p.parts.as_slice() else {
            return false;
        };
        let maybe = JointValue::named(&last.text).is_some()
            && !self.top.contains_key(&first.text)
            && !self.names.contains_key(&p.dotted());
        if maybe {
            self.joint_uses.push((p.clone(), used));
        }
        maybe
    }

    /// Reports a reference [`Resolver::joint_use`] held back: a joint's value where a geom or
    /// a number is needed, or else what the reference would have been reported as.
    fn joint_used(
        &mut self,
        p: &syntax::Path,
        used: JointUse,
        constraints: &HashMap<String, ConstraintId>,
    ) {
        let [first, last] = p.parts.as_slice() else {
            return;
        };
        let dotted = p.dotted();
        if constraints.contains_key(&first.text) {
            let (what, label) = match used {
                JointUse::Argument => (
                    "an output, not a constraint argument",
                    "constraint arguments are geoms, members or sub-geoms",
                ),
                JointUse::Expression => (
                    "an output, not a number",
                    "expressions may use params, numbers and `pi`",
                ),
            };
            let d = Diagnostic::error(
                p.span,
                format!(
                    "`{dotted}` is the {} of joint `{}`: {what}",
                    last.text, first.text
                ),
            )
            .with_label(label)
            .with_note(format!(
                "a joint's value is measured on the solved model: name it in `output {dotted};`"
            ));
            self.push(d);
            return;
        }
        if self.labels.contains_key(&first.text) {
            // A labelled constraint dropped for an error, which is reported already.
            return;
        }
        match used {
            JointUse::Argument => {
                self.geom_path(p, "geom");
            }
            JointUse::Expression => {
                self.expr_path_reported(p);
            }
        }
    }

    fn geom_path(&mut self, p: &syntax::Path, what: &str) -> Option<GeomId> {
        // A plain name, the common case, is looked up as written.
        if let [one] = p.parts.as_slice() {
            if let Some(&g) = self.names.get(one.text.as_str()) {
                return Some(g);
            }
        }
        let dotted = p.dotted();
        if let Some(&g) = self.names.get(&dotted) {
            return Some(g);
        }
        if let Some((TopName::Param(_), _)) = self.top.get(&dotted) {
            let d = Diagnostic::error(p.span, format!("`{dotted}` is a param, not a {what}"))
                .with_label("params are numbers");
            self.push(d);
            return None;
        }
        let first_known = p
            .parts
            .first()
            .is_some_and(|f| self.top.contains_key(&f.text));
        if !self.complete && !first_known {
            // The name may be declared by a statement dropped for a syntax error.
            return None;
        }
        if p.parts
            .first()
            .is_some_and(|f| self.refused.contains(&f.text))
        {
            // Its declaration is reported already.
            return None;
        }
        // Where did the path stop resolving? Suggest among the names in that scope.
        let mut d;
        let (scope_prefix, last) = match dotted.rsplit_once('.') {
            Some((prefix, last)) => (Some(prefix.to_string()), last.to_string()),
            None => (None, dotted.clone()),
        };
        match &scope_prefix {
            Some(prefix) if self.names.contains_key(prefix) => {
                let owner = self.names[prefix];
                let g = &self.geoms[owner];
                let members: Vec<String> = g
                    .parts
                    .iter()
                    .map(|&c| {
                        self.geoms[c]
                            .name
                            .rsplit('.')
                            .next()
                            .unwrap_or("")
                            .to_string()
                    })
                    .collect();
                let is_dimension = matches!(
                    (g.kind, last.as_str()),
                    (GeomKind::Circle, "radius")
                        | (GeomKind::Segment, "length")
                        | (GeomKind::Plane, "offset")
                );
                let noun = if g.kind == GeomKind::Body {
                    "member"
                } else {
                    "part"
                };
                d = if is_dimension {
                    Diagnostic::error(p.span, format!("`{dotted}` is a dimension, not a geom"))
                } else {
                    Diagnostic::error(p.span, format!("`{prefix}` has no {noun} `{last}`"))
                };
                if is_dimension {
                    d = d.with_label("dimensions are not geoms").with_note(format!(
                        "constrain it with `{}({prefix}) = ...`",
                        if last == "radius" {
                            "radius"
                        } else if last == "length" {
                            "length"
                        } else {
                            "distance"
                        }
                    ));
                } else if let Some(s) = suggest(&last, members.iter().map(String::as_str)) {
                    d = d
                        .with_label(format!("unknown member of {}", g.kind.noun()))
                        .with_note(format!("did you mean `{prefix}.{s}`?"));
                } else if members.is_empty() {
                    d = d.with_label(format!("{} has no members", g.kind.noun()));
                } else {
                    d = d
                        .with_label(format!("unknown member of {}", g.kind.noun()))
                        .with_note(format!(
                            "`{prefix}` has {}",
                            members
                                .iter()
                                .map(|m| format!("`{prefix}.{m}`"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ));
                }
            }
            _ => {
                let first = p.parts.first().map(|i| i.text.clone()).unwrap_or_default();
                d = Diagnostic::error(p.span, format!("unknown name `{dotted}`"));
                let geoms: Vec<&str> = self
                    .top
                    .iter()
                    .filter(|(_, (t, _))| matches!(t, TopName::Geom(_)))
                    .map(|(n, _)| n.as_str())
                    .collect();
                let target = if scope_prefix.is_some() {
                    first.as_str()
                } else {
                    dotted.as_str()
                };
                d = d.with_label(format!("no {what} has this name"));
                if let Some(s) = suggest(target, geoms.iter().copied()) {
                    let rest = dotted.strip_prefix(&first).unwrap_or("");
                    d = d.with_note(format!("did you mean `{s}{rest}`?"));
                }
            }
        }
        self.push(d);
        None
    }

    fn output(&mut self, p: &syntax::Path, constraints: &HashMap<String, ConstraintId>) {
        let dotted = p.dotted();
        // Dimensions are outputs of the geom that holds them.
        if let Some((prefix, last)) = dotted.rsplit_once('.') {
            if let Some(&g) = self.names.get(prefix) {
                let kind = self.geoms[g].kind;
                if matches!(
                    (kind, last),
                    (GeomKind::Circle, "radius")
                        | (GeomKind::Segment, "length")
                        | (GeomKind::Plane, "offset")
                ) {
                    self.outputs.push(Output {
                        of: OutputOf::Geom(g),
                        path: dotted,
                        span: p.span,
                    });
                    return;
                }
            }
        }
        // A joint's value, `J.angle` or `J.travel`, where no geom has the name.
        if let [first, last] = p.parts.as_slice() {
            if !self.names.contains_key(&dotted) {
                if let Some(&c) = constraints.get(&first.text) {
                    if let Some(value) = self.joint_value(p, c, last) {
                        self.outputs.push(Output {
                            of: OutputOf::Joint(c, value),
                            path: dotted,
                            span: p.span,
                        });
                    }
                    return;
                }
                let named =
                    self.top.contains_key(&first.text) || self.refused.contains(&first.text);
                if !named && JointValue::named(&last.text).is_some() {
                    if self.complete && !self.labels.contains_key(&first.text) {
                        self.unknown_joint(p, constraints);
                    }
                    return;
                }
            }
        }
        if let Some(g) = self.geom_path(p, "geom or member") {
            self.outputs.push(Output {
                of: OutputOf::Geom(g),
                path: dotted,
                span: p.span,
            });
        }
    }

    /// The value `last` names of joint constraint `c` (`p` is `J.last`), or its diagnostic: a
    /// word that is no joint value, or a value this constraint's joint does not have.
    fn joint_value(
        &mut self,
        p: &syntax::Path,
        c: ConstraintId,
        last: &syntax::Ident,
    ) -> Option<JointValue> {
        let con = &self.constraints[c];
        let (name, kind, span) = (con.name.clone(), con.kind, con.span);
        let has = kind.joint_values();
        let values = |has: &[JointValue]| {
            let each: Vec<String> = has
                .iter()
                .map(|v| format!("`{name}.{}`", v.name()))
                .collect();
            join_or(&each.iter().map(String::as_str).collect::<Vec<_>>())
        };
        let declared = format!("`{name}` is this `{}` constraint", kind.name());
        let d = match JointValue::named(&last.text) {
            Some(value) if has.contains(&value) => return Some(value),
            Some(value) => {
                let d = Diagnostic::error(
                    p.span,
                    format!(
                        "`{name}` is a `{}` constraint, which has no {}",
                        kind.name(),
                        value.name()
                    ),
                )
                .with_label(format!(
                    "`.{}` is the value of {}",
                    value.name(),
                    value.joints_text()
                ))
                .with_secondary(span, declared);
                if has.is_empty() {
                    d
                } else {
                    d.with_note(format!("its joint has {}", values(has)))
                }
            }
            None => {
                let mut d =
                    Diagnostic::error(last.span, format!("unknown joint value `{}`", last.text))
                        .with_label("a joint's value is `.angle` or `.travel`")
                        .with_secondary(span, declared);
                let words = has.iter().map(|v| v.name());
                if let Some(s) = suggest(&last.text, words) {
                    d = d.with_note(format!("did you mean `{name}.{s}`?"));
                } else if has.is_empty() {
                    d = d.with_note(format!(
                        "a `{}` constraint is not a joint with a value to output",
                        kind.name()
                    ));
                } else {
                    d = d.with_note(format!("its joint has {}", values(has)));
                }
                d
            }
        };
        self.push(d);
        None
    }

    /// The diagnostic of `J.angle` or `J.travel` where `J` names no constraint and no geom.
    fn unknown_joint(&mut self, p: &syntax::Path, constraints: &HashMap<String, ConstraintId>) {
        let (first, last) = (&p.parts[0], &p.parts[1]);
        let mut d = Diagnostic::error(
            first.span,
            format!("unknown constraint `{}`", first.text),
        )
        .with_label("no constraint or geom has this name")
        .with_note(format!(
            "`.{}` names the value of a joint by its constraint's name: its label, or the name `gcs check` prints",
            last.text
        ));
        if let Some(s) = suggest(&first.text, constraints.keys().map(String::as_str)) {
            d = d.with_note(format!("did you mean `{s}.{}`?", last.text));
        }
        self.push(d);
    }

    /// Gives every unlabelled constraint a stable name derived from its statement; repeats
    /// get `_2`, `_3`, ... in source order, and no derived name takes a label's.
    fn derive_names(&mut self) {
        let mut taken: BTreeMap<String, usize> =
            self.labels.keys().map(|k| (k.clone(), 1)).collect();
        let ids: Vec<ConstraintId> = self.constraints.iter().map(|(id, _)| id).collect();
        for id in ids {
            let c = &self.constraints[id];
            if let Some(l) = &c.label {
                let l = l.clone();
                self.constraints[id].name = l;
                continue;
            }
            let mut base = c.kind.name().to_string();
            for &a in &c.args {
                base.push('_');
                base.push_str(&self.geoms[a].name.replace('.', "_"));
            }
            let count = taken.entry(base.clone()).or_insert(0);
            *count += 1;
            let mut name = if *count == 1 {
                base.clone()
            } else {
                format!("{base}_{count}")
            };
            while self.labels.contains_key(&name) {
                let count = taken.entry(base.clone()).or_insert(0);
                *count += 1;
                name = format!("{base}_{count}");
            }
            self.constraints[id].name = name;
        }
    }

    // ---------------------------------------------------------------- values

    /// Orders params by dependency, reports recursion, and evaluates every default.
    fn check_params(&mut self) {
        let ids: Vec<ParamId> = self.params.iter().map(|(id, _)| id).collect();
        let mut state: HashMap<ParamId, u8> = HashMap::new(); // 1 = visiting, 2 = done
        let mut in_cycle: HashSet<ParamId> = HashSet::new();
        // The defaults evaluated so far, by param index (NaN until evaluated), kept up to date
        // here rather than collected for each param, which made this quadratic.
        let mut values = vec![f64::NAN; ids.len()];
        for &id in &ids {
            self.visit_param(id, &mut state, &mut Vec::new(), &mut in_cycle, &mut values);
        }
    }

    fn visit_param(
        &mut self,
        id: ParamId,
        state: &mut HashMap<ParamId, u8>,
        stack: &mut Vec<ParamId>,
        in_cycle: &mut HashSet<ParamId>,
        values: &mut Vec<f64>,
    ) {
        match state.get(&id) {
            Some(2) => return,
            Some(1) => {
                // A cycle: from `id`'s position on the stack to the top.
                let start = stack.iter().position(|&p| p == id).unwrap_or(0);
                let cycle: Vec<ParamId> = stack[start..].to_vec();
                if !in_cycle.contains(&id) {
                    in_cycle.extend(cycle.iter().copied());
                    self.poisoned.extend(cycle.iter().copied());
                    let p = &self.params[id];
                    let mut d = if cycle.len() == 1 {
                        Diagnostic::error(
                            p.span,
                            format!("param `{}` is defined in terms of itself", p.name),
                        )
                    } else {
                        Diagnostic::error(
                            p.span,
                            format!(
                                "params `{}` are defined in terms of each other",
                                cycle
                                    .iter()
                                    .map(|&c| self.params[c].name.clone())
                                    .collect::<Vec<_>>()
                                    .join("`, `")
                            ),
                        )
                    };
                    d = d.with_label("recursive definition");
                    for &c in cycle.iter().skip(1) {
                        let cp = &self.params[c];
                        d = d.with_secondary(cp.span, format!("`{}` depends on it", cp.name));
                    }
                    d = d.with_note("a param's default may use other params, but not itself");
                    self.push(d);
                }
                return;
            }
            _ => {}
        }
        state.insert(id, 1);
        stack.push(id);
        let mut deps = Vec::new();
        self.exprs.params(self.params[id].default_expr, &mut deps);
        for d in deps {
            self.visit_param(d, state, stack, in_cycle, values);
        }
        stack.pop();
        state.insert(id, 2);
        if in_cycle.contains(&id) || self.poisoned.contains(&id) {
            return;
        }
        let e = self.params[id].default_expr;
        let v = self.checked_eval(e, values);
        if !v.is_finite() {
            self.poisoned.insert(id);
        }
        self.params[id].default = v;
        values[id.into_raw().into_u32() as usize] = v;
        let dim = self.dim(e, &HashMap::new());
        self.params[id].dim = if dim == Dim::Angle {
            Dim::Angle
        } else {
            Dim::Number
        };
    }

    /// Evaluates with the default params and reports the innermost node that turns finite
    /// inputs into a non-finite value: division by zero, a square root of a negative, ...
    fn checked_eval(&mut self, e: ExprId, params: &[f64]) -> f64 {
        let mut deps = Vec::new();
        self.exprs.params(e, &mut deps);
        if deps.iter().any(|d| self.poisoned.contains(d)) {
            // The param's own definition is reported; do not blame every use of it.
            return self.exprs.eval(e, params);
        }
        let mut problem: Option<(ExprId, String)> = None;
        let v = self.eval_find(e, params, &mut problem);
        if let Some((at, msg)) = problem {
            let span = self.spans.get(&at).copied().unwrap_or_default();
            let label = if msg == "division by zero" {
                "this is zero"
            } else {
                ""
            };
            let mut d = Diagnostic::error(span, msg).with_label(label);
            if !self.exprs.is_constant(at) {
                d = d.with_note("with the params at their defaults");
            }
            self.push(d);
        }
        v
    }

    fn eval_find(&self, e: ExprId, params: &[f64], problem: &mut Option<(ExprId, String)>) -> f64 {
        let node = self.exprs.node(e).clone();
        let v = match &node {
            ExprNode::Const(v) => *v,
            ExprNode::Param(p) => params
                .get(p.into_raw().into_u32() as usize)
                .copied()
                .unwrap_or(f64::NAN),
            ExprNode::Neg(a) => -self.eval_find(*a, params, problem),
            ExprNode::Unit(unit, a) => {
                let a = self.eval_find(*a, params, problem);
                match unit {
                    AngleUnit::Deg => a.to_radians(),
                    AngleUnit::Rad => a,
                }
            }
            ExprNode::Binary(op, a, b) => {
                let x = self.eval_find(*a, params, problem);
                let y = self.eval_find(*b, params, problem);
                use crate::syntax::BinaryOp::*;
                if *op == Div && y == 0.0 && x.is_finite() && problem.is_none() {
                    *problem = Some((*b, "division by zero".to_string()));
                }
                match op {
                    Add => x + y,
                    Sub => x - y,
                    Mul => x * y,
                    Div => x / y,
                    Pow => x.powf(y),
                }
            }
            ExprNode::Call(f, a, b) => {
                let x = self.eval_find(*a, params, problem);
                let y = b.map_or(0.0, |b| self.eval_find(b, params, problem));
                f.apply(x, y)
            }
        };
        if !v.is_finite() && problem.is_none() {
            // The inputs were finite (else a problem would be recorded): this node is to blame.
            let msg = match &node {
                ExprNode::Call(Func::Sqrt, a, _) => {
                    format!(
                        "square root of a negative number ({})",
                        fmt_num(self.exprs.eval(*a, params))
                    )
                }
                ExprNode::Call(f @ (Func::Asin | Func::Acos), a, _) => {
                    format!(
                        "`{}` of {}, outside [-1, 1]",
                        f.name(),
                        fmt_num(self.exprs.eval(*a, params))
                    )
                }
                ExprNode::Binary(crate::syntax::BinaryOp::Pow, ..) if v.is_nan() => {
                    "this power is not a real number".to_string()
                }
                _ if v.is_nan() => "this expression is not a number (NaN)".to_string(),
                _ => "this expression overflows to infinity".to_string(),
            };
            *problem = Some((e, msg));
        }
        v
    }

    /// Evaluates every sketch coordinate and constraint value at the defaults (reporting
    /// NaN, infinities and divisions by zero), then checks vectors and marker axes.
    fn check_values(&mut self) {
        let values: Vec<f64> = self.params.iter().map(|(_, p)| p.default).collect();
        let slots: Vec<ExprId> = self.slots.iter().map(|s| s.0).collect();
        for e in slots {
            self.checked_eval(e, &values);
        }
        let checks = std::mem::take(&mut self.vector_checks);
        let eval = |r: &Self, c: &Coords| -> Vec<f64> {
            c.iter().map(|&e| r.exprs.eval(e, &values)).collect()
        };
        for check in checks {
            match check {
                VectorCheck::NonZero { coords, span, what } => {
                    let v = eval(self, &coords);
                    if v.iter().all(|x| x.is_finite()) && norm(&v) == 0.0 {
                        let d = Diagnostic::error(span, format!("zero-length {what}"))
                            .with_label("all components are zero")
                            .with_note("a direction needs a non-zero vector; it is normalised to unit length");
                        self.push(d);
                    }
                }
                VectorCheck::Distinct {
                    from,
                    to,
                    span,
                    what,
                } => {
                    let a = eval(self, &from);
                    let b = eval(self, &to);
                    let diff: Vec<f64> = a.iter().zip(&b).map(|(x, y)| y - x).collect();
                    if diff.iter().all(|x| x.is_finite()) && norm(&diff) == 0.0 {
                        let d = Diagnostic::error(
                            span,
                            format!("zero-length {what}: its two points coincide"),
                        )
                        .with_label("the direction is undefined")
                        .with_note(format!("sketch the {what} with two distinct points"));
                        self.push(d);
                    }
                }
                VectorCheck::NonNegative { value, span, what } => {
                    let v = self.exprs.eval(value, &values);
                    if v < 0.0 {
                        let d = Diagnostic::error(span, format!("negative {what}"))
                            .with_label(format!("this is {}", fmt_num(v)))
                            .with_note(format!("a {what} is a length, zero or more"));
                        self.push(d);
                    }
                }
                VectorCheck::Orthogonal { z, x, span } => {
                    let z = eval(self, &z);
                    let x = eval(self, &x);
                    let (nz, nx) = (norm(&z), norm(&x));
                    if nz > 0.0 && nx > 0.0 {
                        let cos = z.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>() / (nz * nx);
                        if cos.abs() > gcs_tol::ORTHOGONAL {
                            let deg = cos.clamp(-1.0, 1.0).acos().to_degrees();
                            let d = Diagnostic::error(span, "marker axes are not orthogonal")
                                .with_label(format!(
                                    "the z and x axes are {} degrees apart",
                                    fmt_num(deg)
                                ))
                                .with_note("a marker's z and x axes must be at right angles");
                            self.push(d);
                        }
                    }
                }
            }
        }
    }

    /// The dimension of an expression; `roles` gives params used as lengths elsewhere.
    fn dim(&self, e: ExprId, roles: &HashMap<ParamId, Span>) -> Dim {
        match self.exprs.node(e) {
            ExprNode::Const(_) => Dim::Number,
            ExprNode::Param(p) => {
                let d = self.params[*p].dim;
                if d == Dim::Number && roles.contains_key(p) {
                    Dim::Length
                } else {
                    d
                }
            }
            ExprNode::Neg(a) => self.dim(*a, roles),
            ExprNode::Unit(..) => Dim::Angle,
            ExprNode::Binary(op, a, b) => self.dim(*a, roles).of_binary(*op, self.dim(*b, roles)),
            ExprNode::Call(f, a, b) => f.dim(self.dim(*a, roles), b.map(|b| self.dim(b, roles))),
        }
    }

    /// Params whose value carries into the expression's value (not through a trigonometric
    /// function or a unit), and the unit nodes that do.
    fn carried(&self, e: ExprId, params: &mut Vec<ExprId>, units: &mut Vec<ExprId>) {
        match self.exprs.node(e) {
            ExprNode::Const(_) => {}
            ExprNode::Param(_) => params.push(e),
            ExprNode::Unit(..) => units.push(e),
            ExprNode::Neg(a) => self.carried(*a, params, units),
            ExprNode::Binary(op, a, b) => {
                self.carried(*a, params, units);
                if *op != crate::syntax::BinaryOp::Pow {
                    self.carried(*b, params, units);
                }
            }
            ExprNode::Call(f, a, b) => {
                if matches!(f, Func::Sqrt | Func::Abs | Func::Min | Func::Max) {
                    self.carried(*a, params, units);
                    if let Some(b) = b {
                        self.carried(*b, params, units);
                    }
                }
            }
        }
    }

    /// Units: an angle where a length is needed and the converse, a unit on an angle.
    fn check_units(&mut self) {
        let mut roles: HashMap<ParamId, Span> = HashMap::new();
        // Every unit node: its operand must be a plain number.
        let units: Vec<(ExprId, ExprId)> = self
            .exprs
            .iter()
            .filter_map(|(id, n)| match n {
                ExprNode::Unit(_, a) => Some((id, *a)),
                _ => None,
            })
            .collect();
        for (id, a) in units {
            if self.dim(a, &roles) == Dim::Angle {
                let span = self.spans.get(&id).copied().unwrap_or_default();
                let d = Diagnostic::error(span, "a unit on something that is already an angle")
                    .with_label("this is already in radians")
                    .with_note("`deg` and `rad` apply to plain numbers");
                self.push(d);
            }
        }
        // Lengths first: they give params their length role.
        let slots = self.slots.clone();
        for &(e, need) in slots.iter().filter(|s| s.1 == Need::Length) {
            let _ = need;
            let mut ps = Vec::new();
            let mut us = Vec::new();
            self.carried(e, &mut ps, &mut us);
            if self.dim(e, &roles) == Dim::Angle {
                let span = self.spans.get(&e).copied().unwrap_or_default();
                let mut d = Diagnostic::error(span, "expected a length, found an angle");
                if let Some(u) = us.first() {
                    let us = self.spans.get(u).copied().unwrap_or_default();
                    let unit_span = Span::new(us.end.saturating_sub(3), us.end);
                    d = d.with_secondary(unit_span, "an angle unit on a length");
                } else {
                    d = d.with_label("this is an angle");
                }
                for &p in &ps {
                    if let ExprNode::Param(pid) = self.exprs.node(p) {
                        let param = &self.params[*pid];
                        if param.dim == Dim::Angle {
                            d = d.with_secondary(
                                param.span,
                                format!("`{}` holds an angle", param.name),
                            );
                        }
                    }
                }
                d = if us.is_empty() {
                    d.with_note(
                        "a length cannot be computed from an angle param; declare a separate param",
                    )
                } else {
                    d.with_note("angle units (`deg`, `rad`) go only on angles")
                };
                self.push(d);
                continue;
            }
            for p in ps {
                if let ExprNode::Param(pid) = self.exprs.node(p) {
                    if self.params[*pid].dim == Dim::Number {
                        let span = self.spans.get(&p).copied().unwrap_or_default();
                        roles.entry(*pid).or_insert(span);
                    }
                }
            }
        }
        for &(e, _) in slots.iter().filter(|s| s.1 == Need::Angle) {
            if self.dim(e, &roles) == Dim::Length {
                let span = self.spans.get(&e).copied().unwrap_or_default();
                let mut d = Diagnostic::error(span, "expected an angle, found a length")
                    .with_label("an angle is required here");
                let mut ps = Vec::new();
                self.carried(e, &mut ps, &mut Vec::new());
                for p in ps {
                    if let ExprNode::Param(pid) = self.exprs.node(p) {
                        if let Some(used) = roles.get(pid) {
                            let name = self.params[*pid].name.clone();
                            d = d.with_secondary(
                                *used,
                                format!("`{name}` is used as a length here"),
                            );
                        }
                    }
                }
                d = d.with_note(
                    "a param holds either lengths or angles; declare another param for the angle",
                );
                self.push(d);
            }
        }
        // A plain-number param that a length uses holds a length: a value given later (`--set`)
        // is checked against that.
        for (pid, _) in roles {
            self.params[pid].dim = Dim::Length;
        }
    }

    fn check_unused_params(&mut self) {
        if self.diags.iter().any(Diagnostic::is_error) {
            // Uses may sit in statements that failed; the warning would mislead.
            return;
        }
        // A param used only by other params' defaults is still used.
        let ids: Vec<ParamId> = self.params.iter().map(|(id, _)| id).collect();
        let mut by_param_only: HashSet<ParamId> = HashSet::new();
        for &id in &ids {
            let mut deps = Vec::new();
            self.exprs.params(self.params[id].default_expr, &mut deps);
            by_param_only.extend(deps);
        }
        let in_slots = self.params_in_slots();
        for id in ids {
            let p = &self.params[id];
            let direct = in_slots.contains(&id);
            if !direct && !by_param_only.contains(&id) && self.complete {
                let d = Diagnostic::warning(p.span, format!("param `{}` is never used", p.name))
                    .with_label("unused")
                    .with_note("it still becomes a field of the solver's params");
                self.push(d);
            }
        }
    }

    /// Every param some slot's expression reads: collected once, not once a param.
    fn params_in_slots(&self) -> HashSet<ParamId> {
        let mut all = HashSet::new();
        let mut ps = Vec::new();
        for &(e, _) in &self.slots {
            ps.clear();
            self.exprs.params(e, &mut ps);
            all.extend(ps.iter().copied());
        }
        all
    }
}

/// `text` split into a well-formed number and the word of letters after it (`1.5in`), if it is
/// that.
fn unit_after_number(text: &str) -> Option<(&str, &str)> {
    let at = text.find(|c: char| c.is_ascii_alphabetic())?;
    let (number, word) = text.split_at(at);
    let is_word = word.chars().all(|c| c.is_ascii_alphabetic());
    // `1e5x` is no unit: `e` would be read as the exponent.
    let plain = !number.is_empty() && number.chars().all(|c| c.is_ascii_digit() || c == '.');
    (is_word && plain && number.parse::<f64>().is_ok()).then_some((number, word))
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn fmt_num(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} or {last}", rest.join(", ")),
    }
}

/// The forms of a constraint valid in `space`.
fn forms_in(spec: &constraints::ConstraintSpec, space: Space) -> Vec<&'static [ArgClass]> {
    (spec.forms.iter().enumerate())
        .filter(|&(i, _)| spec.form_allows(i, space))
        .map(|(_, f)| *f)
        .collect()
}

/// The note on a constraint's forms: `` `equal` accepts a segment and a segment; ... ``, with
/// the space when its forms differ by space.
fn accepts_text(spec: &constraints::ConstraintSpec, forms: &[&[ArgClass]], space: Space) -> String {
    let text: Vec<String> = forms.iter().map(|f| form_text(f)).collect();
    let within = if spec.form_spaces.is_empty() {
        String::new()
    } else {
        format!("in {space}, ")
    };
    format!("{within}`{}` accepts {}", spec.name, text.join("; "))
}

/// One form in words: `a point and a segment`, `a point, a point and a line`.
fn form_text(form: &[ArgClass]) -> String {
    match form.iter().map(|c| c.noun()).collect::<Vec<_>>().as_slice() {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// The constraint's text as written (from its name to before `;`), whitespace collapsed.
fn constraint_text(source: &SourceFile, start: usize, end: usize) -> String {
    let raw = source.slice(Span::new(start, end));
    let raw = raw.trim_end().trim_end_matches(';');
    let mut out = String::new();
    let mut space = false;
    for c in raw.chars() {
        if c.is_whitespace() {
            space = true;
        } else {
            if space && !out.is_empty() {
                out.push(' ');
            }
            space = false;
            out.push(c);
        }
    }
    out
}

/// Words longer than this get no suggestion: a typo in a name of a hundred characters is not
/// what a "did you mean" is for, and the edit distance costs the product of the lengths.
pub const MAX_SUGGESTED_LEN: usize = 64;

/// The candidate closest to `word` by edit distance, if it is close enough to be a typo.
pub fn suggest<'c>(word: &str, candidates: impl Iterator<Item = &'c str>) -> Option<&'c str> {
    let len = word.chars().count();
    if len > MAX_SUGGESTED_LEN {
        return None;
    }
    // One edit in three characters; short names only match up to case.
    let limit = len / 3;
    let lower = word.to_lowercase();
    candidates
        // A difference of lengths is a lower bound of the distance (and a character is at
        // most four bytes, so a candidate that long is out without counting its characters).
        .filter(|c| c.len() <= 4 * (len + limit) && c.chars().count().abs_diff(len) <= limit)
        .map(|c| (edit_distance(&lower, &c.to_lowercase()), c))
        .filter(|&(d, c)| d <= limit && c != word)
        .min_by_key(|&(d, c)| (d, c))
        .map(|(_, c)| c)
}

/// Levenshtein distance, with a swap of two neighbours counting as one edit (three rows of
/// the table at a time).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut row: Vec<usize> = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        row[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (prev[j] + 1).min(row[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(before[j - 2] + 1);
            }
            row[j] = v;
        }
        std::mem::swap(&mut before, &mut prev);
        std::mem::swap(&mut prev, &mut row);
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_catch_typos_only() {
        let names = ["coincident", "distance", "angle"];
        assert_eq!(
            suggest("coincidnet", names.iter().copied()),
            Some("coincident")
        );
        assert_eq!(suggest("distnace", names.iter().copied()), Some("distance"));
        assert_eq!(suggest("zzz", names.iter().copied()), None);
        assert_eq!(edit_distance("ab", "ba"), 1);
        assert_eq!(suggest("Q", ["P"].iter().copied()), None);
        assert_eq!(suggest("a", ["A"].iter().copied()), Some("A"));
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abcd", "acbd"), 1);
        let long = "x".repeat(70_000);
        assert_eq!(suggest(&long, [long.as_str(), "x"].iter().copied()), None);
    }

    #[test]
    fn constraint_text_collapses_whitespace() {
        let f = SourceFile::new("t", "coincident( a,\n   b );");
        assert_eq!(constraint_text(&f, 0, f.text().len()), "coincident( a, b )");
    }
}
