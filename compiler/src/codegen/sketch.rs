//! The sketch as values: where every geom starts (its frame's constructor and what is known of
//! it), members' local coordinates, dimensions, and the constants a constant sketch gives,
//! computed here the way the interpreter's configuration computes them, to the bit.

use super::context::Context;
use super::facts::{FrameFacts, Origin};
use super::writer::float;
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

impl Context<'_> {
    /// Whether a member's local coordinates depend on params (then the solution stores them).
    pub(super) fn local_is_param(&self, g: GeomId) -> bool {
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
    pub(super) fn constant_direction(&self, c: &[ExprId]) -> (f64, f64) {
        let v = |i: usize| c.get(i).map_or(0.0, |&e| self.model.exprs.eval(e, &[]));
        let f = gcs_runtime::frame::Frame2::along(
            nalgebra::Point2::origin(),
            nalgebra::Vector2::new(v(0), v(1)),
        );
        (f.rotation.re, f.rotation.im)
    }

    /// The literal value of a reported point or vector that stays where its constant sketch
    /// puts it (a fixed reference, typically), computed as the solve's sketch frame would be.
    pub(super) fn constant_value(&self, g: GeomId) -> Option<String> {
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

    /// A member's local coordinates as a literal (constant sketch).
    pub(super) fn local_literal(&self, g: GeomId, point: bool) -> String {
        let (x, y) = self.literal_coords(g, point);
        let kind = if point { "Point2" } else { "Vector2" };
        format!("{kind}::new({}, {})", float(x), float(y))
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

    /// A point's constant coordinates, when every one is a constant.
    pub(super) fn point_value(&self, c: &[ExprId]) -> Option<(f64, f64)> {
        let m = self.model;
        if !c.iter().all(|&e| m.exprs.is_constant(e)) {
            return None;
        }
        let v = |i: usize| c.get(i).map_or(0.0, |&e| m.exprs.eval(e, &[]));
        Some((v(0), v(1)))
    }

    /// The sketch value of a segment's length or a circle's radius, as code.
    pub(super) fn sketch_dim(&self, g: GeomId) -> Option<String> {
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

    /// The constructor of top-level geom `g`'s frame where the sketch puts it, and what is
    /// known of the frame then. The same construction as the interpreter's configuration, so
    /// that both agree to the last bits: no rotation, a direction, or an angle.
    pub(super) fn sketch_frame(&self, g: GeomId) -> (String, FrameFacts) {
        let m = self.model;
        let at = |origin: String, identity: bool, value: Option<(f64, f64)>| {
            let facts = FrameFacts {
                identity,
                origin: Some(
                    value.map_or(Origin::Code(origin.clone()), |(x, y)| Origin::Literal(x, y)),
                ),
            };
            (origin, facts)
        };
        match &m.geoms[g].sketch {
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
        }
    }

    /// The declared value of a segment's length or a circle's radius where the sketch puts it:
    /// a literal when the sketch is constant.
    pub(super) fn sketch_dim_declared(&self, g: GeomId) -> String {
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
