//! The public API of the generated module: `Params`, `Branches` and `Defaults` (each `Default`
//! from the file, with setters by the model's names), and `Solution` with accessors named after
//! the model and every value by dotted name (`points()`, `vectors()`, `scalars()`). Everything
//! a caller touches is here; how `solve` computes it is not.

use super::context::Context;
use super::facts::{direction_in, point_in, Value};
use super::names::Namer;
use super::scopes;
use super::sketch::dimension_name;
use super::writer::{float, lit, Writer};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};
use std::collections::HashMap;

pub(super) fn params(w: &mut Writer, cx: &Context<'_>) {
    let m = cx.model;
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
            w.line(&format!("pub {}: f64,", cx.params[&id]));
        }
        w.close("}");
    }
    w.line("");
    let fields: Vec<String> = m
        .params
        .iter()
        .map(|(id, _)| cx.params[&id].clone())
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
                cx.params[&id]
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
            w.line(&format!("{}: {},", cx.params[&id], float(p.default)));
        }
        w.close("}");
    }
    w.close("}");
    w.close("}");
    w.line("");
}

pub(super) fn branches(w: &mut Writer, cx: &Context<'_>) {
    w.line("/// Which assembly: one field per branch variable, each an index with a geometric meaning.");
    w.line(&scopes::derives(cx.branches.len(), true));
    if cx.plan.branches.is_empty() {
        w.line("pub struct Branches {}");
    } else {
        w.open("pub struct Branches {");
        for (b, name) in cx.plan.branches.iter().zip(&cx.branches) {
            w.line(&format!("/// `{}`:", b.name));
            for (i, meaning) in b.meanings.iter().enumerate() {
                w.line(&format!("/// - {i}: {meaning}"));
            }
            w.line(&format!("pub {name}: u8,"));
        }
        w.close("}");
    }
    w.line("");
    scopes::field_by_field_eq(w, "Branches", &cx.branches, true);
    w.line("#[allow(dead_code)]");
    w.open("impl Branches {");
    w.line(
        "/// Sets the branch variable called `name` (as in the model); `false` when there is none.",
    );
    w.open("pub fn set(&mut self, name: &str, index: u8) -> bool {");
    if cx.plan.branches.is_empty() {
        w.line("let _ = (name, index);");
        w.line("false");
    } else {
        w.open("match name {");
        for (b, field) in cx.plan.branches.iter().zip(&cx.branches) {
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
    if cx.plan.branches.is_empty() {
        w.line("Branches {}");
    } else {
        w.open("Branches {");
        for (b, name) in cx.plan.branches.iter().zip(&cx.branches) {
            w.line(&format!("{name}: {},", b.default));
        }
        w.close("}");
    }
    w.close("}");
    w.close("}");
    w.line("");
}

/// `Defaults`: the degrees of freedom the analysis had to default, none so far.
pub(super) fn defaults(w: &mut Writer) {
    w.line(
        "/// Values of the degrees of freedom the analysis had to default (none for this model).",
    );
    w.line("#[derive(Clone, Copy, Debug, Default, PartialEq)]");
    w.line("pub struct Defaults {}");
    w.line("");
}

/// The Rust type of a value the solution holds or gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Ty {
    Frame,
    Scalar,
    Point,
    Vector,
}

impl Ty {
    fn rust(self) -> &'static str {
        match self {
            Ty::Frame => "Frame2",
            Ty::Scalar => "f64",
            Ty::Point => "Point2<f64>",
            Ty::Vector => "Vector2<f64>",
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
}

/// One field of `Solution`.
#[derive(Debug)]
pub(super) struct Field {
    pub(super) name: String,
    ty: Ty,
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
            index: HashMap::new(),
            constants: HashMap::new(),
        };
        let mut names = Namer::default();
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
            for &part in &geom.parts {
                let p = &m.geoms[part];
                if !matches!(p.owner, Owner::Member(_)) || !cx.local_is_param(part) {
                    continue;
                }
                let ty = match p.kind {
                    GeomKind::Vector => Ty::Vector,
                    _ => Ty::Point,
                };
                add(
                    &mut layout,
                    &format!("{}_local", p.name),
                    ty,
                    Holds::Local(part),
                );
                if let (GeomKind::Marker, Some(&ax)) = (p.kind, p.parts.first()) {
                    let name = format!("{}_x_local", p.name);
                    add(&mut layout, &name, Ty::Vector, Holds::Local(ax));
                }
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
struct Accessor {
    /// The dotted name.
    name: String,
    doc: String,
    ty: Ty,
    body: String,
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
    w.line(&scopes::derives(layout.fields.len(), false));
    if layout.fields.is_empty() {
        w.line("pub struct Solution {}");
    } else {
        w.open("pub struct Solution {");
        for f in &layout.fields {
            w.line(&format!("{}: {},", f.name, f.ty.rust()));
        }
        w.close("}");
    }
    w.line("");
    let names: Vec<String> = layout.fields.iter().map(|f| f.name.clone()).collect();
    scopes::field_by_field_eq(w, "Solution", &names, false);
    w.line("#[allow(dead_code)]");
    w.open("impl Solution {");
    let mut accessors = Namer::default();
    for reserved in ["points", "vectors", "scalars"] {
        accessors.reserve(reserved);
    }
    let mut by_ty: HashMap<Ty, Vec<(String, String)>> = HashMap::new();
    for g in cx.solved() {
        for a in geom_accessors(cx, layout, g) {
            let accessor = accessors.fresh(&a.name);
            w.line(&format!("/// {}", a.doc));
            w.line("#[inline]");
            w.open(&format!("pub fn {accessor}(&self) -> {} {{", a.ty.rust()));
            w.line(&a.body);
            w.close("}");
            w.line("");
            by_ty.entry(a.ty).or_default().push((a.name, accessor));
        }
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
            ty.rust(),
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

/// The accessors of reported top-level geom `g` and of its members and parts, in model order.
fn geom_accessors(cx: &Context<'_>, layout: &Layout, g: GeomId) -> Vec<Accessor> {
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
        GeomKind::Circle => items.push(Accessor::new(
            &format!("{name}.radius"),
            format!("The radius of `{name}`."),
            Ty::Scalar,
            dim.clone(),
        )),
        GeomKind::Segment => items.push(Accessor::new(
            &format!("{name}.length"),
            format!("The length of `{name}`."),
            Ty::Scalar,
            dim.clone(),
        )),
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
                // The foot of the perpendicular from the first sketch point.
                if let Sketch::Line { from, .. } = &geom.sketch {
                    if from.iter().all(|&e| m.exprs.is_constant(e)) {
                        let s = cx.point_lit(from);
                        let doc = format!("Point `{pname}`: the foot of the perpendicular from the line's first sketch point.");
                        let body = format!("{frame}.origin + {frame}.x_axis() * ({s} - {frame}.origin).dot(&{frame}.x_axis())");
                        items.push(Accessor::new(pname, doc, Ty::Point, body));
                    }
                }
            }
            _ => {}
        }
    }
    items
}
