//! The public API of the generated module: `Params`, `Branches` and `Defaults` (each `Default`
//! from the file, with setters by the model's names), and `Solution` with accessors named after
//! the model and every value by dotted name (`points()`, `vectors()`, `scalars()`). Everything
//! a caller touches is here; how `solve` computes it is not.
//!
//! One writer serves the three input structs. The `Solution`'s fields are one [`Layout`],
//! each field saying what it holds (a frame, a dimension, local coordinates, or a line's
//! sketch point that params set), read by the struct, its accessors and `solve`'s
//! initialiser, so that these agree by construction.

use super::context::Context;
use super::facts::{direction_in, point_in, Value};
use super::names::{Clash, Namer};
use super::scopes;
use super::sketch::dimension_name;
use super::writer::{float, lit, Writer};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};
use rustc_hash::FxHashMap as HashMap;

/// A struct of run-time inputs (`Params`, `Branches`): a field per input, set by the input's
/// name in the model, and `Default` with the model's values.
struct Inputs {
    name: &'static str,
    doc: &'static str,
    /// The fields' type, and the setter's argument.
    ty: &'static str,
    argument: &'static str,
    /// What an input is called in the setter's doc.
    what: &'static str,
    /// The doc of `default`.
    defaults: &'static str,
    /// Whether the struct is `Eq` too.
    eq: bool,
    fields: Vec<Input>,
}

/// One field of [`Inputs`].
struct Input {
    docs: Vec<String>,
    field: String,
    /// The input's name in the model.
    name: String,
    /// The default value's code.
    default: String,
}

/// `Params`: the run-time inputs.
pub(super) fn params(w: &mut Writer, cx: &Context<'_>) {
    let m = cx.model;
    let fields = m
        .params
        .iter()
        .map(|(id, p)| {
            let unit = match p.dim {
                gcs_lang::expr::Dim::Angle => " (radians)",
                _ => "",
            };
            Input {
                docs: vec![format!("`{}`{unit}, line {}.", p.name, m.line(p.span))],
                field: cx.params[&id].clone(),
                name: p.name.clone(),
                default: float(p.default),
            }
        })
        .collect();
    write_inputs(
        w,
        &Inputs {
            name: "Params",
            doc: "The run-time inputs: one field per `param` of the model.",
            ty: "f64",
            argument: "value",
            what: "param",
            defaults: "The values the model gives.",
            eq: false,
            fields,
        },
    );
}

/// `Branches`: which assembly.
pub(super) fn branches(w: &mut Writer, cx: &Context<'_>) {
    let fields = cx
        .plan
        .branches
        .iter()
        .zip(&cx.branches)
        .map(|(b, field)| {
            let meanings = b.meanings.iter().enumerate();
            Input {
                docs: std::iter::once(format!("`{}`:", b.name))
                    .chain(meanings.map(|(i, meaning)| format!("- {i}: {meaning}")))
                    .collect(),
                field: field.clone(),
                name: b.name.clone(),
                default: b.default.to_string(),
            }
        })
        .collect();
    write_inputs(
        w,
        &Inputs {
            name: "Branches",
            doc: "Which assembly: one field per branch variable, each an index with a geometric meaning.",
            ty: "u8",
            argument: "index",
            what: "branch variable",
            defaults: "The sketch's assembly.",
            eq: true,
            fields,
        },
    );
}

/// An inputs struct, its setter by name and its `Default`.
fn write_inputs(w: &mut Writer, s: &Inputs) {
    let name = s.name;
    w.line(&format!("/// {}", s.doc));
    w.line(&scopes::derives(s.fields.len(), s.eq));
    if s.fields.is_empty() {
        w.line(&format!("pub struct {name} {{}}"));
    } else {
        w.open(&format!("pub struct {name} {{"));
        for f in &s.fields {
            for doc in &f.docs {
                w.line(&format!("/// {doc}"));
            }
            w.line(&format!("pub {}: {},", f.field, s.ty));
        }
        w.close("}");
    }
    w.line("");
    let fields: Vec<String> = s.fields.iter().map(|f| f.field.clone()).collect();
    scopes::field_by_field_eq(w, name, &fields, s.eq);
    w.line("#[allow(dead_code)]");
    w.open(&format!("impl {name} {{"));
    w.line(&format!(
        "/// Sets the {} called `name` (as in the model); `false` when there is none.",
        s.what
    ));
    let argument = s.argument;
    w.open(&format!(
        "pub fn set(&mut self, name: &str, {argument}: {}) -> bool {{",
        s.ty
    ));
    if s.fields.is_empty() {
        w.line(&format!("let _ = (name, {argument});"));
        w.line("false");
    } else {
        w.open("match name {");
        for f in &s.fields {
            w.line(&format!(
                "{} => self.{} = {argument},",
                lit(&f.name),
                f.field
            ));
        }
        w.line("_ => return false,");
        w.close("}");
        w.line("true");
    }
    w.close("}");
    w.close("}");
    w.line("");
    w.open(&format!("impl Default for {name} {{"));
    w.line(&format!("/// {}", s.defaults));
    w.open("fn default() -> Self {");
    if s.fields.is_empty() {
        w.line(&format!("{name} {{}}"));
    } else {
        w.open(&format!("{name} {{"));
        for f in &s.fields {
            w.line(&format!("{}: {},", f.field, f.default));
        }
        w.close("}");
    }
    w.close("}");
    w.close("}");
    w.line("");
}

/// `Defaults`: the degrees of freedom the analysis had to default, each with its meaning and
/// its sketch value.
pub(super) fn defaults(w: &mut Writer, cx: &Context<'_>) {
    if cx.plan.defaults.is_empty() {
        w.line(
            "/// Values of the degrees of freedom the analysis had to default (none for this model).",
        );
        w.line("#[derive(Clone, Copy, Debug, Default, PartialEq)]");
        w.line("pub struct Defaults {}");
        w.line("");
        // The same shape as a model's with defaults, as `Branches` has with none.
        w.line("#[allow(dead_code)]");
        w.open("impl Defaults {");
        w.line("/// Sets the default called `name` (as in the model); `false` when there is none.");
        w.open("pub fn set(&mut self, name: &str, value: f64) -> bool {");
        w.line("let _ = (name, value);");
        w.line("false");
        w.close("}");
        w.close("}");
        w.line("");
        return;
    }
    let fields = cx
        .plan
        .defaults
        .iter()
        .zip(&cx.defaults)
        .map(|(d, field)| Input {
            docs: vec![format!(
                "`{}`: {}; the sketch's value is {}.",
                d.name,
                d.meaning,
                float(d.sketch)
            )],
            field: field.clone(),
            name: d.name.clone(),
            default: float(d.sketch),
        })
        .collect();
    write_inputs(
        w,
        &Inputs {
            name: "Defaults",
            doc: "The degrees of freedom the analysis had to default: where an iteration starts, or the value of a motion the constraints leave free.",
            ty: "f64",
            argument: "value",
            what: "default",
            defaults: "The sketch's values.",
            eq: false,
            fields,
        },
    );
}

/// The Rust type of a value the solution holds or gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Ty {
    Frame,
    Scalar,
    Point,
    Vector,
}

impl Ty {
    /// The type in the plane, or in space (`d3`).
    pub(super) fn rust(self, d3: bool) -> &'static str {
        match (self, d3) {
            (Ty::Frame, false) => "Frame2",
            (Ty::Frame, true) => "Frame3",
            (Ty::Scalar, _) => "f64",
            (Ty::Point, false) => "Point2<f64>",
            (Ty::Point, true) => "Point3<f64>",
            (Ty::Vector, false) => "Vector2<f64>",
            (Ty::Vector, true) => "Vector3<f64>",
        }
    }
}

/// What a field of `Solution` holds; `solve` initialises it from its local of that.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Holds {
    /// The frame of top-level geom `g`.
    Frame(GeomId),
    /// The dimension of top-level geom `g`: a segment's length, a circle's radius.
    Dim(GeomId),
    /// The local coordinates of member `g`, or of marker axis `g`, which params set.
    Local(GeomId),
    /// The first sketch point of line `g`, which params set: `L.point` is the foot of the
    /// perpendicular from it.
    LineSketch(GeomId),
}

/// One field of `Solution`.
#[derive(Debug)]
pub(super) struct Field {
    pub(super) name: String,
    pub(super) ty: Ty,
    pub(super) holds: Holds,
}

/// The fields of `Solution`, made once and read by the struct, its accessors and the
/// initialiser at the end of `solve`, so that these agree by construction.
#[derive(Debug)]
pub(super) struct Layout {
    /// In order: for each reported geom, its frame, its dimension, its members' local
    /// coordinates that params set.
    pub(super) fields: Vec<Field>,
    /// Each field's place in `fields`, by what it holds.
    index: HashMap<Holds, usize>,
    /// Reported points and vectors the plan never moves and whose sketch is constant: no
    /// field holds them, their accessor returns this literal.
    constants: HashMap<GeomId, Value>,
}

impl Layout {
    pub(super) fn new(cx: &Context<'_>) -> Layout {
        let m = cx.model;
        let mut layout = Layout {
            fields: Vec::new(),
            index: HashMap::default(),
            constants: HashMap::default(),
        };
        let mut names = Namer::default();
        // `Solution::branches` and `Solution::defaults`, when the plan has them.
        names.reserve("branches");
        names.reserve("defaults");
        let mut add = |layout: &mut Layout, name: &str, ty: Ty, holds: Holds| {
            layout.index.insert(holds, layout.fields.len());
            let name = names.fresh(name);
            layout.fields.push(Field { name, ty, holds });
        };
        for g in cx.solved() {
            let geom = &m.geoms[g];
            if let Some(value) = cx.constant_value(g) {
                layout.constants.insert(g, value);
                continue;
            }
            add(&mut layout, &geom.name, Ty::Frame, Holds::Frame(g));
            if let Some(what) = dimension_name(geom.kind) {
                let name = format!("{}_{what}", geom.name);
                add(&mut layout, &name, Ty::Scalar, Holds::Dim(g));
            }
            for local in cx.param_locals(g) {
                let ty = if local.vector { Ty::Vector } else { Ty::Point };
                add(&mut layout, &local.name, ty, Holds::Local(local.feature));
            }
            let sketched = |from: &[gcs_lang::expr::ExprId]| match cx.d3 {
                true => !from.iter().all(|&e| m.exprs.is_constant(e)),
                false => !matches!(cx.sketch_point(from), Value::Point(..)),
            };
            if line_sketch(cx, g).is_some_and(sketched) {
                let name = format!("{}_sketch", geom.name);
                add(&mut layout, &name, Ty::Point, Holds::LineSketch(g));
            }
        }
        layout
    }

    /// Whether reported geom `g` is a constant, which no field holds.
    pub(super) fn is_constant(&self, g: GeomId) -> bool {
        self.constants.contains_key(&g)
    }

    /// `self.{field}` of the field that holds `holds`, if one does.
    fn read(&self, holds: Holds) -> Option<String> {
        let field = &self.fields[*self.index.get(&holds)?];
        Some(format!("self.{}", field.name))
    }
}

/// An accessor of `Solution`: one value by its dotted name in the model.
pub(super) struct Accessor {
    /// The dotted name.
    pub(super) name: String,
    pub(super) doc: String,
    pub(super) ty: Ty,
    pub(super) body: String,
}

impl Accessor {
    fn new(name: &str, doc: String, ty: Ty, body: String) -> Accessor {
        Accessor {
            name: name.to_string(),
            doc,
            ty,
            body,
        }
    }
}

/// The solution struct and its accessors.
pub(super) fn solution(w: &mut Writer, cx: &Context<'_>, layout: &Layout) {
    w.line(
        "/// The solved configuration of every geom the outputs need: frames and dimensions, read",
    );
    w.line("/// through accessors named after the model.");
    let has_defaults = !cx.plan.defaults.is_empty();
    let has_branches = !cx.plan.branches.is_empty();
    let mut names: Vec<String> = layout.fields.iter().map(|f| f.name.clone()).collect();
    if has_branches {
        names.push("branches".to_string());
    }
    if has_defaults {
        names.push("defaults".to_string());
    }
    w.line(&scopes::derives(names.len(), false));
    if names.is_empty() {
        w.line("pub struct Solution {}");
    } else {
        w.open("pub struct Solution {");
        for f in &layout.fields {
            w.line(&format!("{}: {},", f.name, f.ty.rust(cx.d3)));
        }
        if has_branches {
            w.line("branches: Branches,");
        }
        if has_defaults {
            w.line("defaults: Defaults,");
        }
        w.close("}");
    }
    w.line("");
    scopes::field_by_field_eq(w, "Solution", &names, false);
    w.line("#[allow(dead_code)]");
    w.open("impl Solution {");
    if has_branches {
        w.line("/// The branch variables this assembly is on: those given to `solve`.");
        w.line("#[inline]");
        w.open("pub fn branches(&self) -> Branches {");
        w.line("self.branches");
        w.close("}");
        w.line("");
    }
    if has_defaults {
        w.line(
            "/// The defaults this assembly has: as given, or as the outer iteration converged to.",
        );
        w.line("/// Pass them to the next solve of a sweep to follow this assembly.");
        w.line("#[inline]");
        w.open("pub fn defaults(&self) -> Defaults {");
        w.line("self.defaults");
        w.close("}");
        w.line("");
    }
    let mut by_ty: HashMap<Ty, Vec<(String, String)>> = HashMap::default();
    for (a, accessor) in accessors(cx, layout).0 {
        w.line(&format!("/// {}", a.doc));
        w.line("#[inline]");
        w.open(&format!(
            "pub fn {accessor}(&self) -> {} {{",
            a.ty.rust(cx.d3)
        ));
        w.line(&a.body);
        w.close("}");
        w.line("");
        by_ty.entry(a.ty).or_default().push((a.name, accessor));
    }
    // Every value by its dotted name, for callers that iterate (and for the test driver).
    for (what, ty) in [
        ("point", Ty::Point),
        ("vector", Ty::Vector),
        ("scalar", Ty::Scalar),
    ] {
        let list = by_ty.get(&ty).map_or(&[][..], Vec::as_slice);
        w.line(&format!(
            "/// Every {what} of the solution, by its dotted name in the model."
        ));
        w.open(&format!(
            "pub fn {what}s(&self) -> [(&'static str, {}); {}] {{",
            ty.rust(cx.d3),
            list.len()
        ));
        w.open("[");
        for (name, accessor) in list {
            w.line(&format!("({}, self.{accessor}()),", lit(name)));
        }
        w.close("]");
        w.close("}");
        w.line("");
    }
    w.unblank();
    w.close("}");
    w.line("");
}

/// Every accessor of `Solution` with its identifier, in model order, and the model's names
/// that became one identifier (`points`, `vectors` and `scalars` are the API's own).
pub(super) fn accessors(
    cx: &Context<'_>,
    layout: &Layout,
) -> (Vec<(Accessor, String)>, Vec<Clash>) {
    let mut names = Namer::default();
    for reserved in RESERVED_ACCESSORS {
        names.reserve(reserved);
    }
    let mut out = Vec::new();
    for g in cx.solved() {
        for a in geom_accessors(cx, layout, g) {
            let identifier = names.fresh(&a.name);
            out.push((a, identifier));
        }
    }
    (out, names.clashes().to_vec())
}

/// The accessors of reported top-level geom `g` and of its members and parts, in model order.
fn geom_accessors(cx: &Context<'_>, layout: &Layout, g: GeomId) -> Vec<Accessor> {
    if cx.d3 {
        return geom_accessors3(cx, layout, g);
    }
    let m = cx.model;
    let geom = &m.geoms[g];
    let name = &geom.name;
    if let Some(value) = layout.constants.get(&g) {
        let (what, ty) = match geom.kind {
            GeomKind::Vector => ("Vector", Ty::Vector),
            _ => ("Point", Ty::Point),
        };
        let doc = format!("{what} `{name}`, which the solve never moves.");
        return vec![Accessor::new(name, doc, ty, value.code())];
    }
    let Some(frame) = layout.read(Holds::Frame(g)) else {
        return Vec::new();
    };
    let dim = layout.read(Holds::Dim(g)).unwrap_or_default();
    let mut items = Vec::new();
    match geom.kind {
        GeomKind::Body => items.push(Accessor::new(
            name,
            format!("The frame of body `{name}`."),
            Ty::Frame,
            frame.clone(),
        )),
        GeomKind::Point => items.push(Accessor::new(
            name,
            format!("Point `{name}`."),
            Ty::Point,
            format!("{frame}.origin"),
        )),
        GeomKind::Vector => items.push(Accessor::new(
            name,
            format!("Vector `{name}`."),
            Ty::Vector,
            format!("{frame}.x_axis()"),
        )),
        GeomKind::Circle | GeomKind::Segment => {
            if let Some((accessor, what)) = dimension_accessor(name, geom.kind) {
                let doc = format!("The {what} of `{name}`.");
                items.push(Accessor::new(&accessor, doc, Ty::Scalar, dim.clone()));
            }
        }
        _ => {}
    }
    // A member's position or direction from its local coordinates: a field's when params set
    // them, else the literal.
    let point = |f: GeomId| match layout.read(Holds::Local(f)) {
        Some(local) => format!("{frame}.point_to_global(&{local})"),
        None => {
            let origin = Value::Expr(format!("{frame}.origin"));
            point_in(|| frame.clone(), &origin, cx.literal_coords(f, true)).code()
        }
    };
    let direction = |f: GeomId| match layout.read(Holds::Local(f)) {
        Some(local) => format!("{frame}.vector_to_global(&{local})"),
        None => direction_in(&frame, cx.literal_coords(f, false)),
    };
    for &part in &geom.parts {
        let p = &m.geoms[part];
        let pname = &p.name;
        let point_doc = format!("Point `{pname}`.");
        match (p.owner, p.kind) {
            (Owner::Member(_), GeomKind::Point | GeomKind::Marker) => {
                items.push(Accessor::new(pname, point_doc, Ty::Point, point(part)));
                if let (GeomKind::Marker, Some(&ax)) = (p.kind, p.parts.first()) {
                    let n = &m.geoms[ax].name;
                    let doc = format!("Axis `{n}`.");
                    items.push(Accessor::new(n, doc, Ty::Vector, direction(ax)));
                }
            }
            (Owner::Member(_), GeomKind::Vector) => {
                let doc = format!("Vector `{pname}`.");
                items.push(Accessor::new(pname, doc, Ty::Vector, direction(part)));
            }
            (Owner::Part(_, Part::Start | Part::Center), _) => {
                let body = format!("{frame}.origin");
                items.push(Accessor::new(pname, point_doc, Ty::Point, body));
            }
            (Owner::Part(_, Part::End), _) => {
                let body = format!("{frame}.origin + {frame}.x_axis() * {dim}");
                items.push(Accessor::new(pname, point_doc, Ty::Point, body));
            }
            (Owner::Part(_, Part::Dir), _) => {
                let doc = format!("Direction `{pname}`.");
                let body = format!("{frame}.x_axis()");
                items.push(Accessor::new(pname, doc, Ty::Vector, body));
            }
            (Owner::Part(_, Part::BasePoint), _) => {
                // The foot of the perpendicular from the first sketch point: a literal, or the
                // field that holds it when params set it.
                if let Some(from) = line_sketch(cx, g) {
                    let s = layout
                        .read(Holds::LineSketch(g))
                        .unwrap_or_else(|| cx.point_lit(from));
                    let doc = format!("Point `{pname}`: the foot of the perpendicular from the line's first sketch point.");
                    let body = format!("{frame}.origin + {frame}.x_axis() * ({s} - {frame}.origin).dot(&{frame}.x_axis())");
                    items.push(Accessor::new(pname, doc, Ty::Point, body));
                }
            }
            _ => {}
        }
    }
    items
}

/// The accessors of reported top-level geom `g` of a 3d model and of its members and parts,
/// in model order: the values the interpreter's `Solution::read_space` reports, read from the
/// frame as it reads them.
fn geom_accessors3(cx: &Context<'_>, layout: &Layout, g: GeomId) -> Vec<Accessor> {
    let m = cx.model;
    let geom = &m.geoms[g];
    let name = &geom.name;
    let Some(frame) = layout.read(Holds::Frame(g)) else {
        return Vec::new();
    };
    let dim = layout.read(Holds::Dim(g)).unwrap_or_default();
    let mut items = Vec::new();
    let origin = format!("{frame}.origin");
    let x_axis = format!("{frame}.x_axis()");
    match geom.kind {
        GeomKind::Body => items.push(Accessor::new(
            name,
            format!("The frame of body `{name}`: its origin and its axes."),
            Ty::Frame,
            frame.clone(),
        )),
        GeomKind::Point => {
            let doc = format!("Point `{name}`.");
            items.push(Accessor::new(name, doc, Ty::Point, origin.clone()));
        }
        GeomKind::Vector => {
            let doc = format!("Vector `{name}`.");
            items.push(Accessor::new(name, doc, Ty::Vector, x_axis.clone()));
        }
        GeomKind::Circle | GeomKind::Segment | GeomKind::Plane => {
            if let Some((accessor, what)) = dimension_accessor(name, geom.kind) {
                let (doc, body) = if geom.kind == GeomKind::Plane {
                    let doc = format!("The offset of plane `{name}`: its signed distance from the origin along its normal.");
                    (doc, format!("{frame}.z_axis().dot(&{frame}.origin.coords)"))
                } else {
                    (format!("The {what} of `{name}`."), dim.clone())
                };
                items.push(Accessor::new(&accessor, doc, Ty::Scalar, body));
            }
        }
        _ => {}
    }
    // A member's position or direction from its local coordinates: a field's when params set
    // them, else the literal.
    let point = |f: GeomId| {
        let local = layout
            .read(Holds::Local(f))
            .unwrap_or_else(|| cx.local_point3(f));
        format!("{frame}.point_to_global(&{local})")
    };
    let direction = |f: GeomId| {
        let local = layout
            .read(Holds::Local(f))
            .unwrap_or_else(|| cx.local_dir3(f));
        format!("{frame}.vector_to_global(&{local})")
    };
    for &part in &geom.parts {
        let p = &m.geoms[part];
        let pname = &p.name;
        let point_doc = format!("Point `{pname}`.");
        let vector_doc = format!("Direction `{pname}`.");
        match (p.owner, p.kind) {
            (Owner::Member(_), GeomKind::Point | GeomKind::Marker) => {
                items.push(Accessor::new(pname, point_doc, Ty::Point, point(part)));
                for &axis in &p.parts {
                    let n = &m.geoms[axis].name;
                    let doc = format!("Axis `{n}`.");
                    items.push(Accessor::new(n, doc, Ty::Vector, direction(axis)));
                }
            }
            (Owner::Member(_), GeomKind::Vector) => {
                let doc = format!("Vector `{pname}`.");
                items.push(Accessor::new(pname, doc, Ty::Vector, direction(part)));
            }
            (Owner::Part(_, Part::Start | Part::Center), _) => {
                items.push(Accessor::new(pname, point_doc, Ty::Point, origin.clone()));
            }
            (Owner::Part(_, Part::End), _) => {
                let body = format!("{origin} + {x_axis} * {dim}");
                items.push(Accessor::new(pname, point_doc, Ty::Point, body));
            }
            (Owner::Part(_, Part::Dir), _) => {
                items.push(Accessor::new(pname, vector_doc, Ty::Vector, x_axis.clone()));
            }
            (Owner::Part(_, Part::Normal), _) => {
                let body = format!("{frame}.z_axis()");
                items.push(Accessor::new(pname, vector_doc, Ty::Vector, body));
            }
            (Owner::Part(_, Part::BasePoint), _) => {
                if let Some(from) = line_sketch(cx, g) {
                    let s = layout
                        .read(Holds::LineSketch(g))
                        .unwrap_or_else(|| cx.point_lit3(from));
                    let doc = format!("Point `{pname}`: the foot of the perpendicular from the line's first sketch point.");
                    let body = format!("{origin} + {x_axis} * ({s} - {origin}).dot(&{x_axis})");
                    items.push(Accessor::new(pname, doc, Ty::Point, body));
                }
            }
            _ => {}
        }
    }
    items
}

/// The accessor of a circle's radius (`G.radius`) or a segment's length (`S.length`), with
/// the word for it.
fn dimension_accessor(name: &str, kind: GeomKind) -> Option<(String, &'static str)> {
    let what = match kind {
        GeomKind::Circle => "radius",
        GeomKind::Segment => "length",
        GeomKind::Plane => "offset",
        _ => return None,
    };
    Some((format!("{name}.{what}"), what))
}

/// Every text an accessor could be named from, whatever the pruning keeps: each geom's name
/// (members and parts have their own, `B.m`, `S.start`, `k.z`) and each dimension's accessor.
/// The API's own names (`points`, ...) are in [`RESERVED_ACCESSORS`].
pub(super) fn accessor_texts(model: &gcs_lang::Model) -> impl Iterator<Item = String> + '_ {
    model.geoms.iter().flat_map(|(_, geom)| {
        let dimension = dimension_accessor(&geom.name, geom.kind).map(|(name, _)| name);
        std::iter::once(geom.name.clone()).chain(dimension)
    })
}

/// The accessors of `Solution` that the API itself has.
pub(super) const RESERVED_ACCESSORS: [&str; 5] =
    ["points", "vectors", "scalars", "branches", "defaults"];

/// The first sketch point of line `g` (where its `L.point` is measured from), if it is a line.
pub(super) fn line_sketch<'m>(cx: &Context<'m>, g: GeomId) -> Option<&'m [gcs_lang::expr::ExprId]> {
    match &cx.model.geoms[g].sketch {
        Sketch::Line { from, .. } => Some(from),
        _ => None,
    }
}
