//! The public API of the generated module: `Params`, `Branches` and `Defaults` (each `Default`
//! from the file, with setters by the model's names), and `Solution` with accessors named after
//! the model and every value by dotted name (`points()`, `vectors()`, `scalars()`; the joint
//! values the outputs name, `q1.angle`, are scalars measured on the markers' frames by the
//! runtime's `frame::joint_*`). Everything a caller touches is here; how `solve` computes it
//! is not.
//!
//! One writer serves the three input structs. The `Solution`'s fields are one [`Layout`],
//! each field saying what it holds (a frame, a dimension, local coordinates, or a line's
//! sketch point that params set), read by the struct, its accessors and `solve`'s
//! initialiser, so that these agree by construction.

use super::context::Context;
use super::facts::Value;
use super::names::{Clash, Namer};
use super::scopes;
use super::sketch::dimension_name;
use super::writer::{float, lit, Writer};
use gcs_lang::constraints::JointValue;
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
    /// The type in the model's space.
    pub(super) fn rust(self, cx: &Context<'_>) -> &'static str {
        cx.space.rust(self)
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
            let sketched = |from: &[gcs_lang::expr::ExprId]| !cx.all_constant(from);
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
    pub(super) fn read(&self, holds: Holds) -> Option<String> {
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
    /// The top-level geom it reads.
    pub(super) geom: GeomId,
    /// What of that geom it reads.
    pub(super) reads: Reads,
}

/// What an accessor reads of its top-level geom's frame, dimension and local coordinates:
/// its value as data, which [`Accessor::body`] writes as code from where the solution holds
/// them (a field of the flat `Solution`, a slot of a large model's store).
#[derive(Clone, Debug)]
pub(super) enum Reads {
    /// A value the solve never moves, whose sketch is constant.
    Constant(Value),
    /// The frame itself (a body's).
    Frame,
    /// The frame's origin.
    Origin,
    /// The frame's x axis (a vector's, a line's direction).
    XAxis,
    /// In space, the frame's z axis (a plane's or a circle's normal).
    ZAxis,
    /// In space, a plane's signed distance from the origin along its normal.
    PlaneOffset,
    /// The dimension (a segment's length, a circle's radius).
    Dim,
    /// A segment's end: the origin plus the x axis times the length.
    End,
    /// Member point (or marker) `f` at its local coordinates.
    MemberPoint(GeomId),
    /// Member vector (or marker axis) `f` at its local direction.
    MemberDir(GeomId),
    /// A line's base point: the foot of the perpendicular from its first sketch point.
    BasePoint,
    /// A joint's value (`J.angle`, `J.travel`): the runtime's `frame::{function}` of what is
    /// read of its markers, each value read of its own top-level geom (the angle in space of
    /// the first marker's z and x axes and the second's x axis; the travel of the two points and
    /// the second marker's sliding axis).
    Joint {
        function: &'static str,
        args: Vec<(GeomId, Reads)>,
    },
}

impl Accessor {
    fn new(name: &str, doc: String, ty: Ty, geom: GeomId, reads: Reads) -> Accessor {
        Accessor {
            name: name.to_string(),
            doc,
            ty,
            geom,
            reads,
        }
    }

    /// The code of its value, where `read` gives the code of what the solution holds (`None`
    /// for what it does not: a dimension never set, constant local coordinates).
    pub(super) fn body(
        &self,
        cx: &Context<'_>,
        read: &mut dyn FnMut(Holds) -> Option<String>,
    ) -> String {
        value_code(cx, self.geom, &self.reads, read)
    }
}

/// The code of what `reads` reads of top-level geom `g`, where `read` gives the code of what
/// the solution holds.
fn value_code(
    cx: &Context<'_>,
    g: GeomId,
    reads: &Reads,
    read: &mut dyn FnMut(Holds) -> Option<String>,
) -> String {
    match reads {
        Reads::Constant(value) => return value.code(),
        Reads::Joint { function, args } => {
            let args: Vec<String> = (args.iter())
                .map(|(g, reads)| value_code(cx, *g, reads, read))
                .collect();
            return format!("gcs_runtime::frame::{function}({})", args.join(", "));
        }
        _ => {}
    }
    let frame = read(Holds::Frame(g)).unwrap_or_default();
    let origin = format!("{frame}.origin");
    let x_axis = format!("{frame}.x_axis()");
    match reads {
        Reads::Constant(_) | Reads::Joint { .. } => unreachable!("written above"),
        Reads::Frame => frame,
        Reads::Origin => origin,
        Reads::XAxis => x_axis,
        Reads::ZAxis => format!("{frame}.z_axis()"),
        Reads::PlaneOffset => format!("{frame}.z_axis().dot(&{frame}.origin.coords)"),
        Reads::Dim => read(Holds::Dim(g)).unwrap_or_default(),
        Reads::End => {
            let dim = read(Holds::Dim(g)).unwrap_or_default();
            format!("{origin} + {x_axis} * {dim}")
        }
        Reads::MemberPoint(f) => match read(Holds::Local(*f)) {
            Some(local) => format!("{frame}.point_to_global(&{local})"),
            None => cx.space.member_point(cx, &frame, &origin, *f),
        },
        Reads::MemberDir(f) => match read(Holds::Local(*f)) {
            Some(local) => format!("{frame}.vector_to_global(&{local})"),
            None => cx.space.member_dir(cx, &frame, *f),
        },
        Reads::BasePoint => {
            // The foot of the perpendicular from the first sketch point: a literal, or the
            // value that holds it when params set it.
            let from = line_sketch(cx, g).unwrap_or(&[]);
            let s = read(Holds::LineSketch(g)).unwrap_or_else(|| cx.point_code(from));
            format!("{origin} + {x_axis} * ({s} - {origin}).dot(&{x_axis})")
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
            w.line(&format!("{}: {},", f.name, f.ty.rust(cx)));
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
        w.open(&format!("pub fn {accessor}(&self) -> {} {{", a.ty.rust(cx)));
        w.line(&a.body(cx, &mut |holds| layout.read(holds)));
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
            ty.rust(cx),
            list.len()
        ));
        w.open("[");
        for (name, accessor) in list {
            w.line(&format!("({}, self.{accessor}()),", lit(name)));
        }
        w.close("]");
        w.close("}");
        if ty != Ty::Scalar {
            w.line("");
        }
    }
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
    for a in joint_accessors(cx, layout) {
        let identifier = names.fresh(&a.name);
        out.push((a, identifier));
    }
    (out, names.clashes().to_vec())
}

/// The accessors of the joint values the outputs name (`q1.angle`, `slide.travel`) whose two
/// markers are solved, in the order first named: scalars, measured as the interpreter's
/// `Solution` measures them, by the same runtime function.
fn joint_accessors(cx: &Context<'_>, layout: &Layout) -> Vec<Accessor> {
    let m = cx.model;
    let d3 = m.space == gcs_lang::model::Space::D3;
    let mut items = Vec::new();
    for (name, c, value) in m.joint_outputs() {
        let con = &m.constraints[c];
        let (Some(&m1), Some(&m2)) = (con.args.first(), con.args.get(1)) else {
            continue;
        };
        if !(con.args.iter()).all(|&a| cx.scope.contains(&m.top_level_of(a))) {
            continue;
        }
        // What is read of a marker (or of `in_line`'s point): its point, or an axis.
        let point = |f: GeomId| feature_read(cx, layout, f, false);
        let axis =
            |f: GeomId, part: Part| m.part(f, part).map(|a| feature_read(cx, layout, a, true));
        let (n1, n2) = (&m.geoms[m1].name, &m.geoms[m2].name);
        let (function, args, doc) = match value {
            JointValue::Angle => {
                let (function, axes) = if d3 {
                    let axes = [
                        axis(m1, Part::AxisZ),
                        axis(m1, Part::AxisX),
                        axis(m2, Part::AxisX),
                    ];
                    ("joint_angle3", axes.into_iter().collect::<Option<Vec<_>>>())
                } else {
                    let axes = [axis(m1, Part::AxisX), axis(m2, Part::AxisX)];
                    ("joint_angle2", axes.into_iter().collect::<Option<Vec<_>>>())
                };
                let about = if d3 {
                    format!("counter-clockwise about `{n1}`'s z axis")
                } else {
                    "counter-clockwise".to_string()
                };
                let doc = format!(
                    "The angle of joint `{}` (`{}`, line {}): from `{n1}`'s x axis to `{n2}`'s, {about}, in (-pi, pi].",
                    con.name,
                    con.text,
                    m.line(con.span)
                );
                (function, axes, doc)
            }
            JointValue::Travel => {
                let (function, slide, along) = if d3 {
                    ("joint_travel3", axis(m2, Part::AxisZ), "z")
                } else {
                    ("joint_travel2", axis(m2, Part::AxisX), "x")
                };
                let args = slide.map(|slide| vec![point(m1), point(m2), slide]);
                let doc = format!(
                    "The travel of joint `{}` (`{}`, line {}): the signed distance from `{n2}` to `{n1}` along `{n2}`'s {along} axis.",
                    con.name,
                    con.text,
                    m.line(con.span)
                );
                (function, args, doc)
            }
        };
        let Some(args) = args else {
            continue;
        };
        let reads = Reads::Joint { function, args };
        items.push(Accessor::new(
            name,
            doc,
            Ty::Scalar,
            m.top_level_of(m1),
            reads,
        ));
    }
    items
}

/// What an accessor reads of its top-level geom for feature `f`, as [`geom_accessors`] reads
/// it: a marker's axis if `dir`; else a point: a constant, the top-level geom's origin (its own,
/// a segment's start, a circle's centre), a segment's end, or a member at its local coordinates.
fn feature_read(cx: &Context<'_>, layout: &Layout, f: GeomId, dir: bool) -> (GeomId, Reads) {
    let g = cx.model.top_level_of(f);
    let reads = match (dir, cx.model.geoms[f].owner) {
        (true, _) => Reads::MemberDir(f),
        (false, Owner::TopLevel) => match layout.constants.get(&g) {
            Some(value) => Reads::Constant(value.clone()),
            None => Reads::Origin,
        },
        (false, Owner::Member(_)) => Reads::MemberPoint(f),
        (false, Owner::Part(_, Part::End)) => Reads::End,
        (false, Owner::Part(..)) => Reads::Origin,
    };
    (g, reads)
}

/// The accessors of reported top-level geom `g` and of its members and parts, in model order:
/// in space, the values the interpreter's `Solution::read_space` reports, read from the frame
/// as it reads them.
fn geom_accessors(cx: &Context<'_>, layout: &Layout, g: GeomId) -> Vec<Accessor> {
    let m = cx.model;
    let geom = &m.geoms[g];
    let name = &geom.name;
    let mut items = Vec::new();
    let mut add = |name: &str, doc: String, ty: Ty, reads: Reads| {
        items.push(Accessor::new(name, doc, ty, g, reads));
    };
    if let Some(value) = layout.constants.get(&g) {
        let (what, ty) = match geom.kind {
            GeomKind::Vector => ("Vector", Ty::Vector),
            _ => ("Point", Ty::Point),
        };
        let doc = format!("{what} `{name}`, which the solve never moves.");
        add(name, doc, ty, Reads::Constant(value.clone()));
        return items;
    }
    if layout.read(Holds::Frame(g)).is_none() {
        return items;
    }
    match geom.kind {
        GeomKind::Body => add(name, cx.space.body_frame_doc(name), Ty::Frame, Reads::Frame),
        GeomKind::Point => add(name, format!("Point `{name}`."), Ty::Point, Reads::Origin),
        GeomKind::Vector => add(name, format!("Vector `{name}`."), Ty::Vector, Reads::XAxis),
        GeomKind::Plane => {
            if let Some((accessor, _)) = dimension_accessor(name, geom.kind) {
                let doc = format!("The offset of plane `{name}`: its signed distance from the origin along its normal.");
                add(&accessor, doc, Ty::Scalar, Reads::PlaneOffset);
            }
        }
        GeomKind::Circle | GeomKind::Segment => {
            if let Some((accessor, what)) = dimension_accessor(name, geom.kind) {
                let doc = format!("The {what} of `{name}`.");
                add(&accessor, doc, Ty::Scalar, Reads::Dim);
            }
        }
        _ => {}
    }
    // A member's position or direction from its local coordinates: a field's when params set
    // them, else the literal.
    for &part in &geom.parts {
        let p = &m.geoms[part];
        let pname = &p.name;
        let point_doc = format!("Point `{pname}`.");
        let vector_doc = format!("Direction `{pname}`.");
        match (p.owner, p.kind) {
            (Owner::Member(_), GeomKind::Point | GeomKind::Marker) => {
                add(pname, point_doc, Ty::Point, Reads::MemberPoint(part));
                // A marker's axes: its x axis in the plane, all three in space.
                for &axis in &p.parts {
                    let n = &m.geoms[axis].name;
                    add(
                        n,
                        format!("Axis `{n}`."),
                        Ty::Vector,
                        Reads::MemberDir(axis),
                    );
                }
            }
            (Owner::Member(_), GeomKind::Vector) => {
                add(
                    pname,
                    format!("Vector `{pname}`."),
                    Ty::Vector,
                    Reads::MemberDir(part),
                );
            }
            (Owner::Part(_, Part::Start | Part::Center), _) => {
                add(pname, point_doc, Ty::Point, Reads::Origin);
            }
            (Owner::Part(_, Part::End), _) => add(pname, point_doc, Ty::Point, Reads::End),
            (Owner::Part(_, Part::Dir), _) => add(pname, vector_doc, Ty::Vector, Reads::XAxis),
            // Only in space: a plane's or a circle's.
            (Owner::Part(_, Part::Normal), _) => {
                add(pname, vector_doc, Ty::Vector, Reads::ZAxis);
            }
            (Owner::Part(_, Part::BasePoint), _) if line_sketch(cx, g).is_some() => {
                let doc = format!("Point `{pname}`: the foot of the perpendicular from the line's first sketch point.");
                add(pname, doc, Ty::Point, Reads::BasePoint);
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
/// (members and parts have their own, `B.m`, `S.start`, `k.z`), each dimension's accessor and
/// each joint value the outputs name (`q1.angle`). The API's own names (`points`, ...) are in
/// [`RESERVED_ACCESSORS`].
pub(super) fn accessor_texts(model: &gcs_lang::Model) -> impl Iterator<Item = String> + '_ {
    let geoms = model.geoms.iter().flat_map(|(_, geom)| {
        let dimension = dimension_accessor(&geom.name, geom.kind).map(|(name, _)| name);
        std::iter::once(geom.name.clone()).chain(dimension)
    });
    let joints = (model.joint_outputs().into_iter()).map(|(name, ..)| name.to_string());
    geoms.chain(joints)
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

/// The module's header comments and imports. No inner attributes or `//!` docs: the module must
/// be usable through `include!`.
pub(super) fn header(w: &mut Writer, file: &str, space: &dyn super::space::Space) {
    w.line(&format!(
        "// @generated by gcs from {file}. Do not edit: edit the model and regenerate."
    ));
    w.line("//");
    w.line(
        "// The solver's steps follow the model's assembly plan; `gcs explain` prints it in words.",
    );
    w.line("");
    w.line(&format!(
        "// Solver for `{file}`. Call `solve` with `Params`, `Branches` and `Defaults`, and read"
    ));
    w.line(
        "// the result through the accessors of `Solution`. It never panics and allocates nothing.",
    );
    w.line(
        "// A caller uses what it needs of this API: the setters and accessors allow dead code.",
    );
    w.line("");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::error::{ErrorKind, SolveError};");
    w.line("#[allow(unused_imports)]");
    w.line("use gcs_runtime::check;");
    for import in space.imports() {
        w.line("#[allow(unused_imports)]");
        w.line(import);
    }
    w.line("");
}
