//! The public API of the generated module: `Params`, `Branches` and `Defaults` (each `Default`
//! from the file, with setters by the model's names), and `Solution` with accessors named after
//! the model and every value by dotted name (`points()`, `vectors()`, `scalars()`). Everything
//! a caller touches is here; how `solve` computes it is not.

use super::context::Context;
use super::facts::{direction_in, point_in};
use super::names::Namer;
use super::scopes;
use super::writer::{float, lit, Writer};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};
use std::collections::{HashMap, HashSet};

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

/// The fields of `Solution`, and the reported geoms it returns as literals instead.
pub(super) struct SolutionFields {
    /// (name, type), in order.
    pub(super) fields: Vec<(String, String)>,
    /// Reported points and vectors the plan never moves and whose sketch is constant.
    pub(super) constant: HashSet<GeomId>,
}

/// The solution struct and its accessors.
pub(super) fn solution(w: &mut Writer, cx: &Context<'_>) -> SolutionFields {
    let m = cx.model;
    let mut constant = HashSet::new();
    let mut fields: Vec<(String, String)> = Vec::new(); // (field, type)
    let mut field_names = Namer::default();
    let mut frame_field: HashMap<GeomId, String> = HashMap::new();
    let mut dim_field: HashMap<GeomId, String> = HashMap::new();
    let mut local_field: HashMap<GeomId, String> = HashMap::new();
    for g in cx.solved() {
        let geom = &m.geoms[g];
        if let Some(value) = cx.constant_value(g) {
            constant.insert(g);
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
            if matches!(p.owner, Owner::Member(_)) && cx.local_is_param(part) {
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
    w.line(
        "/// The solved configuration of every geom the outputs need: frames and dimensions, read",
    );
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
    for g in cx.solved() {
        let geom = &m.geoms[g];
        let frame = format!("self.{}", frame_field[&g]);
        let mut items: Vec<(String, String, String, String)> = Vec::new(); // (name, doc, type, body)
        match geom.kind {
            GeomKind::Point if constant.contains(&g) => items.push((
                geom.name.clone(),
                format!("Point `{}`, which the solve never moves.", geom.name),
                "Point2<f64>".into(),
                frame_field[&g].clone(),
            )),
            GeomKind::Vector if constant.contains(&g) => items.push((
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
                                let at = cx.literal_coords(part, true);
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
                                    None => direction_in(&frame, cx.literal_coords(ax, false)),
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
                            None => direction_in(&frame, cx.literal_coords(part, false)),
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
                            let s = cx.point_lit(from);
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
    if w.out.ends_with("\n\n") {
        w.out.pop();
    }
    w.close("}");
    w.line("");
    SolutionFields { fields, constant }
}
