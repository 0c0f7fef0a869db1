//! The sketch as values: where every geom starts (its frame's constructor and what is known of
//! it), members' local coordinates, dimensions, and the constants a constant sketch gives,
//! computed here the way the interpreter's configuration computes them, to the bit.

use super::context::Context;
use super::facts::{FrameFacts, Value};
use super::writer::float;
use crate::config::SketchFault;
use gcs_lang::expr::ExprId;
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};

/// The word for a geom kind's dimension (`length`, `radius`), which its locals and fields are
/// named after; `None` for a kind without one.
pub(super) fn dimension_name(kind: GeomKind) -> Option<&'static str> {
    match kind {
        GeomKind::Segment => Some("length"),
        GeomKind::Circle => Some("radius"),
        _ => None,
    }
}

/// Local coordinates of a member that params set: the solution stores them for a geom it
/// reports, and the solve declares them where it needs them.
pub(super) struct ParamLocal {
    /// The member, or a marker's x axis.
    pub(super) feature: GeomId,
    /// What the local and the field are called after.
    pub(super) name: String,
    /// A direction (normalised), not a point.
    pub(super) vector: bool,
    /// The code of their sketch value.
    pub(super) value: String,
}

impl Context<'_> {
    /// [`Context::sketch_checks`] in the plane.
    pub(super) fn sketch_checks2(&self) -> Vec<(GeomId, String, SketchFault)> {
        let m = self.model;
        let constant = |e: &ExprId| m.exprs.is_constant(*e);
        let surely_finite = |e: &ExprId| {
            let mut e = *e;
            while let gcs_lang::expr::ExprNode::Neg(a) = m.exprs.node(e) {
                e = *a;
            }
            constant(&e) || matches!(m.exprs.node(e), gcs_lang::expr::ExprNode::Param(_))
        };
        // `!is_finite(x) || ...` over the coordinates that may not be finite.
        let not_finite = |es: &[&ExprId]| -> Vec<String> {
            es.iter()
                .filter(|e| !surely_finite(e))
                .map(|&&e| format!("!gcs_runtime::num::is_finite({})", self.expr(e)))
                .collect()
        };
        let mut out = Vec::new();
        for (id, g) in m.geoms.iter() {
            let member = matches!(g.owner, Owner::Member(_));
            let (mut tests, fault) = match &g.sketch {
                Sketch::Point(c) => (
                    not_finite(&c.iter().collect::<Vec<_>>()),
                    SketchFault::Position,
                ),
                Sketch::Vector(c) if !c.iter().all(constant) => {
                    let mut t = not_finite(&c.iter().collect::<Vec<_>>());
                    t.push(format!("{}.norm() == 0.0", self.vector_lit(c)));
                    (t, SketchFault::Direction)
                }
                Sketch::Line { from, to } | Sketch::Segment { from, to }
                    if !member && !from.iter().chain(to).all(constant) =>
                {
                    let mut t = not_finite(&from.iter().chain(to).collect::<Vec<_>>());
                    t.push(format!(
                        "({} - {}).norm() == 0.0",
                        self.point_lit(to),
                        self.point_lit(from)
                    ));
                    (t, SketchFault::Points)
                }
                Sketch::Circle { center, radius, .. } if !member => {
                    let mut t = not_finite(&center.iter().chain([radius]).collect::<Vec<_>>());
                    if !constant(radius) {
                        t.push(format!("{} < 0.0", self.expr(*radius)));
                    }
                    (t, SketchFault::Circle)
                }
                Sketch::Body { at, angle, .. } if !member => {
                    let coords: Vec<&ExprId> = at.iter().flatten().chain(angle.iter()).collect();
                    (not_finite(&coords), SketchFault::Placement)
                }
                Sketch::Marker { origin, x, .. } if member => {
                    let mut t = not_finite(&origin.iter().chain(x).collect::<Vec<_>>());
                    if !x.iter().all(constant) {
                        t.push(format!("{}.norm() == 0.0", self.vector_lit(x)));
                    }
                    (t, SketchFault::Marker)
                }
                _ => (Vec::new(), SketchFault::Position),
            };
            if !tests.is_empty() {
                tests.dedup();
                out.push((id, tests.join(" || "), fault));
            }
        }
        out
    }

    /// The members of top-level geom `g` whose local coordinates params set, found once per
    /// geom (a body with a member per stage is asked by every piece of a large model). Only
    /// the members are kept: their code is written anew where asked for, in the scope of the
    /// caller (see `lift`).
    pub(super) fn param_members(&self, g: GeomId) -> Vec<GeomId> {
        if let Some(known) = self.param_members_of.borrow().get(&g) {
            return known.clone();
        }
        let m = self.model;
        let found: Vec<GeomId> = (m.geoms[g].parts.iter().copied())
            .filter(|&part| matches!(m.geoms[part].owner, Owner::Member(_)))
            .filter(|&part| self.space.local_is_param(self, part))
            .collect();
        self.param_members_of.borrow_mut().insert(g, found.clone());
        found
    }

    /// [`Context::param_locals`] in the plane.
    pub(super) fn param_locals2(&self, g: GeomId) -> Vec<ParamLocal> {
        let m = self.model;
        let mut out = Vec::new();
        for part in self.param_members(g) {
            let p = &m.geoms[part];
            let local = |feature, suffix: &str, vector, value| ParamLocal {
                feature,
                name: format!("{}_{suffix}", p.name),
                vector,
                value,
            };
            match &p.sketch {
                Sketch::Point(c) | Sketch::Marker { origin: c, .. } => {
                    out.push(local(part, "local", false, self.point_lit(c)));
                }
                Sketch::Vector(c) => {
                    let value = format!("{}.normalize()", self.vector_lit(c));
                    out.push(local(part, "local", true, value));
                }
                _ => {}
            }
            if let (Sketch::Marker { x, .. }, Some(&ax)) = (&p.sketch, p.parts.first()) {
                let value = format!("{}.normalize()", self.vector_lit(x));
                out.push(local(ax, "x_local", true, value));
            }
        }
        out
    }

    /// Whether a member's local coordinates depend on params (then the solution stores them).
    pub(super) fn local_is_param2(&self, g: GeomId) -> bool {
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
    pub(super) fn constant_value(&self, g: GeomId) -> Option<Value> {
        let m = self.model;
        let geom = &m.geoms[g];
        if self.moved(g) || self.space.reports_every_frame() {
            return None;
        }
        let value = |c: &[ExprId], i: usize| c.get(i).map(|&e| m.exprs.eval(e, &[]));
        match (&geom.kind, &geom.sketch) {
            (GeomKind::Point, Sketch::Point(c)) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                Some(Value::Point(value(c, 0)?, value(c, 1)?))
            }
            (GeomKind::Vector, Sketch::Vector(c)) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                let (cos, sin) = self.constant_direction(c);
                Some(Value::Vector(cos, sin))
            }
            _ => None,
        }
    }

    /// A member's local coordinates as a literal (constant sketch).
    pub(super) fn local_literal(&self, g: GeomId, point: bool) -> Value {
        let (x, y) = self.literal_coords(g, point);
        if point {
            Value::Point(x, y)
        } else {
            Value::Vector(x, y)
        }
    }

    /// The constant sketch of a member's local coordinates; a vector normalised exactly as the
    /// interpreter's configuration does, to the bit.
    pub(super) fn literal_coords(&self, g: GeomId, point: bool) -> (f64, f64) {
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
    pub(super) fn zero_coordinate(&self, g: GeomId) -> Option<usize> {
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

    /// A point of the sketch: a literal when every coordinate is a constant (a missing one is
    /// zero), else the expressions params give it.
    pub(super) fn sketch_point(&self, c: &[ExprId]) -> Value {
        let m = self.model;
        if c.iter().all(|&e| m.exprs.is_constant(e)) {
            let v = |i: usize| c.get(i).map_or(0.0, |&e| m.exprs.eval(e, &[]));
            return Value::Point(v(0), v(1));
        }
        Value::Sketched([c.first().copied(), c.get(1).copied()], self.point_lit(c))
    }

    /// [`Context::sketch_dim`] in the plane.
    pub(super) fn sketch_dim2(&self, g: GeomId) -> Option<String> {
        match &self.model.geoms[g].sketch {
            Sketch::Segment { from, to } => {
                // Two literal ends: the length here, as the solve would compute it.
                if let (Value::Point(tx, ty), Value::Point(fx, fy)) =
                    (self.sketch_point(to), self.sketch_point(from))
                {
                    let length =
                        (nalgebra::Point2::new(tx, ty) - nalgebra::Point2::new(fx, fy)).norm();
                    return Some(float(length));
                }
                Some(format!(
                    "({} - {}).norm()",
                    self.point_lit(to),
                    self.point_lit(from)
                ))
            }
            Sketch::Circle { radius, .. } => Some(self.expr(*radius)),
            _ => None,
        }
    }

    /// [`Context::sketch_frame`] in the plane: no rotation, a direction, or an angle.
    pub(super) fn sketch_frame2(&self, g: GeomId) -> (String, FrameFacts) {
        let m = self.model;
        let facts = |identity: bool, origin: Value| FrameFacts {
            identity,
            origin: Some(origin),
            literal3: None,
        };
        let zero = || Value::Point(0.0, 0.0);
        match &m.geoms[g].sketch {
            Sketch::Point(c) | Sketch::Circle { center: c, .. } => {
                let origin = self.sketch_point(c);
                (
                    format!("Frame2::at({})", origin.code()),
                    facts(true, origin),
                )
            }
            Sketch::Vector(c) if c.iter().all(|&e| m.exprs.is_constant(e)) => {
                let (cos, sin) = self.constant_direction(c);
                let identity = (cos, sin) == (1.0, 0.0);
                let ctor = if identity {
                    "Frame2::at(Point2::origin())".to_string()
                } else {
                    format!(
                        "Frame2::from_cos_sin(Point2::origin(), {}, {})",
                        float(cos),
                        float(sin)
                    )
                };
                (ctor, facts(identity, zero()))
            }
            Sketch::Vector(c) => {
                let ctor = format!("Frame2::along(Point2::origin(), {})", self.vector_lit(c));
                (ctor, facts(false, zero()))
            }
            Sketch::Line { from, to } | Sketch::Segment { from, to } => {
                let origin = self.sketch_point(from);
                let (a, b) = (origin.code(), self.point_lit(to));
                (
                    format!("Frame2::along({a}, {b} - {a})"),
                    facts(false, origin),
                )
            }
            Sketch::Body {
                at: place, angle, ..
            } => {
                let (code, origin) = match place {
                    Some(c) => {
                        let origin = self.sketch_point(c);
                        (origin.code(), origin)
                    }
                    None => ("Point2::origin()".to_string(), zero()),
                };
                let angle = angle.map(|e| match m.exprs.is_constant(e) {
                    true => Ok(m.exprs.eval(e, &[])),
                    false => Err(e),
                });
                let (ctor, identity) = match angle {
                    None | Some(Ok(0.0)) => (format!("Frame2::at({code})"), true),
                    Some(Ok(a)) => {
                        let (sin, cos) = a.sin_cos();
                        let ctor = format!(
                            "Frame2::from_cos_sin({code}, {}, {})",
                            float(cos),
                            float(sin)
                        );
                        (ctor, false)
                    }
                    Some(Err(e)) => (format!("Frame2::new({code}, {})", self.expr(e)), false),
                };
                (ctor, facts(identity, origin))
            }
            _ => ("Frame2::at(Point2::origin())".into(), facts(true, zero())),
        }
    }

    /// [`Context::sketch_dim_declared`] in the plane.
    pub(super) fn sketch_dim_declared2(&self, g: GeomId) -> String {
        let m = self.model;
        match &m.geoms[g].sketch {
            Sketch::Segment { from, to }
                if from.iter().chain(to).all(|&e| m.exprs.is_constant(e)) =>
            {
                let v = |c: &[ExprId], i: usize| c.get(i).map_or(0.0, |&e| m.exprs.eval(e, &[]));
                float((v(to, 0) - v(from, 0)).hypot(v(to, 1) - v(from, 1)))
            }
            _ => self.sketch_dim(g).unwrap_or_else(|| "0.0".into()),
        }
    }
}
