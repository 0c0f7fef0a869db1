//! The configuration of a 2d model: every top-level geom as a rigid frame plus its dimension,
//! and every member's local coordinates, evaluated from the sketch with given params.
//!
//! This is the numerical model of paper 000: actions move frames; measurements read the global
//! position of a feature through its geom's frame. Members and parts never move on their own.

use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};
use gcs_lang::Model;
use gcs_runtime::frame::Frame2;
use nalgebra::{Point2, UnitComplex, Vector2};
use std::collections::HashMap;

/// A point of the plane.
pub type P2 = Point2<f64>;
/// A vector of the plane.
pub type V2 = Vector2<f64>;

/// Frames, dimensions and local coordinates of a 2d model.
#[derive(Clone, Debug)]
pub struct Config {
    /// The frame of every top-level geom.
    pub frames: HashMap<GeomId, Frame2>,
    /// The dimension of segments (length) and circles (radius).
    pub dims: HashMap<GeomId, f64>,
    /// Local coordinates of member points and markers.
    local_points: HashMap<GeomId, P2>,
    /// Local directions of member vectors and marker axes.
    local_dirs: HashMap<GeomId, V2>,
    /// The first sketch point of each line, for `L.point`.
    line_sketch: HashMap<GeomId, P2>,
}

/// What makes a sketch that params give unusable, by the kind of sketch: one wording for the
/// interpreter (which reads the whole sketch before the first step) and the generated solve
/// (which checks the sketches that depend on params, in the same order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SketchFault {
    /// A point's position is not finite.
    Position,
    /// A direction is zero or not finite.
    Direction,
    /// A line's or segment's two points coincide or are not finite.
    Points,
    /// A circle's centre or radius is not finite, or its radius is negative.
    Circle,
    /// A body's placement is not finite.
    Placement,
    /// A marker's point or axis is not finite or zero.
    Marker,
}

impl SketchFault {
    /// The error's words, after the geom's name.
    pub fn what(self) -> &'static str {
        match self {
            SketchFault::Position => "its position is not finite",
            SketchFault::Direction => "its direction is zero or not finite",
            SketchFault::Points => "its two points coincide or are not finite",
            SketchFault::Circle => "its centre or radius is not finite, or the radius is negative",
            SketchFault::Placement => "its placement is not finite",
            SketchFault::Marker => "its point or axis is not finite or zero",
        }
    }
}

/// A sketch value that is not finite, or a zero direction, found while evaluating.
#[derive(Clone, Debug, PartialEq)]
pub struct BadSketch {
    /// The geom whose sketch is bad.
    pub geom: GeomId,
    /// What is wrong.
    pub what: String,
}

fn coords(model: &Model, c: &[gcs_lang::expr::ExprId], params: &[f64]) -> V2 {
    let x = c.first().map_or(f64::NAN, |&e| model.exprs.eval(e, params));
    let y = c.get(1).map_or(f64::NAN, |&e| model.exprs.eval(e, params));
    V2::new(x, y)
}

impl Config {
    /// Evaluates the sketch of every geom with `params`.
    pub fn from_sketch(model: &Model, params: &[f64]) -> Result<Config, BadSketch> {
        let mut cfg = Config {
            frames: HashMap::new(),
            dims: HashMap::new(),
            local_points: HashMap::new(),
            local_dirs: HashMap::new(),
            line_sketch: HashMap::new(),
        };
        for (id, g) in model.geoms.iter() {
            let bad = |fault: SketchFault| BadSketch {
                geom: id,
                what: fault.what().to_string(),
            };
            let finite = |v: &V2| v.x.is_finite() && v.y.is_finite();
            match (&g.sketch, g.owner) {
                (Sketch::Point(c), Owner::TopLevel) => {
                    let p = coords(model, c, params);
                    if !finite(&p) {
                        return Err(bad(SketchFault::Position));
                    }
                    cfg.frames.insert(id, Frame2::at(Point2::from(p)));
                }
                (Sketch::Vector(c), Owner::TopLevel) => {
                    let v = coords(model, c, params);
                    if !finite(&v) || v.norm() == 0.0 {
                        return Err(bad(SketchFault::Direction));
                    }
                    cfg.frames.insert(id, Frame2::along(P2::origin(), v));
                }
                (Sketch::Line { from, to } | Sketch::Segment { from, to }, Owner::TopLevel) => {
                    let a = coords(model, from, params);
                    let b = coords(model, to, params);
                    let d = b - a;
                    if !finite(&a) || !finite(&b) || d.norm() == 0.0 {
                        return Err(bad(SketchFault::Points));
                    }
                    cfg.frames.insert(id, Frame2::along(Point2::from(a), d));
                    if g.kind == GeomKind::Segment {
                        cfg.dims.insert(id, d.norm());
                    } else {
                        cfg.line_sketch.insert(id, Point2::from(a));
                    }
                }
                (Sketch::Circle { center, radius, .. }, Owner::TopLevel) => {
                    let c = coords(model, center, params);
                    let r = model.exprs.eval(*radius, params);
                    if !finite(&c) || !r.is_finite() || r < 0.0 {
                        return Err(bad(SketchFault::Circle));
                    }
                    cfg.frames.insert(id, Frame2::at(Point2::from(c)));
                    cfg.dims.insert(id, r);
                }
                (Sketch::Body { at, angle, .. }, Owner::TopLevel) => {
                    let o = at
                        .as_ref()
                        .map_or(V2::zeros(), |c| coords(model, c, params));
                    let a = angle.map_or(0.0, |e| model.exprs.eval(e, params));
                    if !finite(&o) || !a.is_finite() {
                        return Err(bad(SketchFault::Placement));
                    }
                    cfg.frames.insert(id, Frame2::new(Point2::from(o), a));
                }
                (Sketch::Point(c), Owner::Member(_)) => {
                    let p = coords(model, c, params);
                    if !finite(&p) {
                        return Err(bad(SketchFault::Position));
                    }
                    cfg.local_points.insert(id, Point2::from(p));
                }
                (Sketch::Vector(c), Owner::Member(_)) => {
                    let v = coords(model, c, params);
                    if !finite(&v) || v.norm() == 0.0 {
                        return Err(bad(SketchFault::Direction));
                    }
                    cfg.local_dirs.insert(id, v.normalize());
                }
                (Sketch::Marker { origin, x, .. }, Owner::Member(_)) => {
                    let p = coords(model, origin, params);
                    let v = coords(model, x, params);
                    if !finite(&p) || !finite(&v) || v.norm() == 0.0 {
                        return Err(bad(SketchFault::Marker));
                    }
                    cfg.local_points.insert(id, Point2::from(p));
                    if let Some(ax) = g.parts.first() {
                        cfg.local_dirs.insert(*ax, v.normalize());
                    }
                }
                _ => {}
            }
        }
        Ok(cfg)
    }

    fn frame(&self, model: &Model, g: GeomId) -> Frame2 {
        let top = model.top_level_of(g);
        self.frames
            .get(&top)
            .copied()
            .unwrap_or_else(Frame2::identity)
    }

    /// The dimension of a segment or circle (0 for other geoms).
    pub fn dim(&self, g: GeomId) -> f64 {
        self.dims.get(&g).copied().unwrap_or(0.0)
    }

    /// The global position of a point feature.
    pub fn point(&self, model: &Model, g: GeomId) -> P2 {
        let f = self.frame(model, g);
        match model.geoms[g].owner {
            Owner::TopLevel => f.origin,
            Owner::Member(_) => f.point_to_global(
                &self
                    .local_points
                    .get(&g)
                    .copied()
                    .unwrap_or_else(P2::origin),
            ),
            Owner::Part(owner, part) => match part {
                Part::End => f.origin + f.x_axis() * self.dim(owner),
                Part::AxisX | Part::AxisZ | Part::Dir | Part::Normal => f.origin,
                Part::Start | Part::Center | Part::BasePoint => f.origin,
            },
        }
    }

    /// The global direction of a vector feature.
    pub fn dir(&self, model: &Model, g: GeomId) -> V2 {
        let f = self.frame(model, g);
        match model.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX) => {
                f.vector_to_global(&self.local_dirs.get(&g).copied().unwrap_or_else(V2::x))
            }
            _ => f.x_axis(),
        }
    }

    /// `L.point` of a line: the foot of the perpendicular from its first sketch point.
    pub fn line_point(&self, line: GeomId) -> P2 {
        let f = self
            .frames
            .get(&line)
            .copied()
            .unwrap_or_else(Frame2::identity);
        let s = self.line_sketch.get(&line).copied().unwrap_or(f.origin);
        let x = f.x_axis();
        f.origin + x * (s - f.origin).dot(&x)
    }

    /// Translates a top-level geom.
    pub fn translate(&mut self, g: GeomId, v: V2) {
        if let Some(f) = self.frames.get_mut(&g) {
            f.translate(&v);
        }
    }

    /// Rotates a top-level geom about a point.
    pub fn rotate(&mut self, g: GeomId, pivot: P2, rotation: UnitComplex<f64>) {
        if let Some(f) = self.frames.get_mut(&g) {
            f.rotate_about_by(&pivot, &rotation);
        }
    }
}
