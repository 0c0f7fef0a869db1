//! The configuration of a model: every top-level geom as a rigid frame plus its dimension,
//! and every member's local coordinates, evaluated from the sketch with given params.
//!
//! This is the numerical model of paper 000: actions move frames; measurements read the global
//! position of a feature through its geom's frame. Members and parts never move on their own.
//!
//! One struct for both spaces, generic over the space's frame ([`Frames`]): the plane's
//! `Frame2` (the default, `Config`) and space's `Frame3` (`Config<D3>`). What a feature is
//! (a member's point through its frame, a segment's end along its x axis) is said once, over
//! the [`RigidFrame`] trait; reading the sketch is per space, as its forms differ.

use gcs_lang::model::{GeomId, GeomKind, Owner, Part, PlanePlacement, Sketch};
use gcs_lang::Model;
use gcs_runtime::frame::{rotation_onto_x, rotation_onto_z, rotation_zx};
use gcs_runtime::frame::{Frame2, Frame3};
use nalgebra::{Point2, Point3, UnitComplex, UnitQuaternion, Vector2, Vector3};
use std::collections::HashMap;

/// A point of the plane.
pub type P2 = Point2<f64>;
/// A vector of the plane.
pub type V2 = Vector2<f64>;
/// A point of space.
pub type P3 = Point3<f64>;
/// A vector of space.
pub type V3 = Vector3<f64>;

/// A rigid frame of one space, as the configuration reads and moves it.
pub trait RigidFrame: Copy + std::fmt::Debug + PartialEq {
    /// A point of the space.
    type P: Copy + std::fmt::Debug + PartialEq;
    /// A vector of the space.
    type V: Copy + std::fmt::Debug + PartialEq + std::ops::Mul<f64, Output = Self::V>;
    /// The global frame.
    fn identity() -> Self;
    /// Its origin.
    fn origin(&self) -> Self::P;
    /// Its x axis (a line's or segment's direction).
    fn x_axis(&self) -> Self::V;
    /// A local point, globally.
    fn point_to_global(&self, local: &Self::P) -> Self::P;
    /// A local direction, globally.
    fn vector_to_global(&self, local: &Self::V) -> Self::V;
    /// Moves it by `v`.
    fn translate(&mut self, v: &Self::V);
    /// `p + v`.
    fn offset(p: Self::P, v: Self::V) -> Self::P;
    /// The local origin and x axis, for members without a sketch of their own.
    fn origin_point() -> Self::P;
    /// The local x axis.
    fn x() -> Self::V;
    /// `v` along `dir` measured from `p`: the foot of `p + v` on the line through `p` along
    /// the unit `dir`.
    fn foot(base: Self::P, dir: Self::V, p: Self::P) -> Self::P;
    /// Coordinates, for scales and reports.
    fn coords(p: &Self::P) -> Vec<f64>;
}

impl RigidFrame for Frame2 {
    type P = P2;
    type V = V2;
    fn identity() -> Self {
        Frame2::identity()
    }
    fn origin(&self) -> P2 {
        self.origin
    }
    fn x_axis(&self) -> V2 {
        Frame2::x_axis(self)
    }
    fn point_to_global(&self, local: &P2) -> P2 {
        Frame2::point_to_global(self, local)
    }
    fn vector_to_global(&self, local: &V2) -> V2 {
        Frame2::vector_to_global(self, local)
    }
    fn translate(&mut self, v: &V2) {
        Frame2::translate(self, v)
    }
    fn offset(p: P2, v: V2) -> P2 {
        p + v
    }
    fn origin_point() -> P2 {
        P2::origin()
    }
    fn x() -> V2 {
        V2::x()
    }
    fn foot(base: P2, dir: V2, p: P2) -> P2 {
        base + dir * (p - base).dot(&dir)
    }
    fn coords(p: &P2) -> Vec<f64> {
        vec![p.x, p.y]
    }
}

impl RigidFrame for Frame3 {
    type P = P3;
    type V = V3;
    fn identity() -> Self {
        Frame3::identity()
    }
    fn origin(&self) -> P3 {
        self.origin
    }
    fn x_axis(&self) -> V3 {
        Frame3::x_axis(self)
    }
    fn point_to_global(&self, local: &P3) -> P3 {
        Frame3::point_to_global(self, local)
    }
    fn vector_to_global(&self, local: &V3) -> V3 {
        Frame3::vector_to_global(self, local)
    }
    fn translate(&mut self, v: &V3) {
        Frame3::translate(self, v)
    }
    fn offset(p: P3, v: V3) -> P3 {
        p + v
    }
    fn origin_point() -> P3 {
        P3::origin()
    }
    fn x() -> V3 {
        V3::x()
    }
    fn foot(base: P3, dir: V3, p: P3) -> P3 {
        base + dir * (p - base).dot(&dir)
    }
    fn coords(p: &P3) -> Vec<f64> {
        vec![p.x, p.y, p.z]
    }
}

/// The frames of one space: which frame a configuration holds, and how its sketch reads.
pub trait Frames: Clone + std::fmt::Debug + Sized {
    /// The space's rigid frame.
    type Frame: RigidFrame;
    /// Evaluates the sketch of every geom with `params`.
    fn read(model: &Model, params: &[f64]) -> Result<Config<Self>, BadSketch>;
}

/// The plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct D2;
/// Space.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct D3;

impl Frames for D2 {
    type Frame = Frame2;
    fn read(model: &Model, params: &[f64]) -> Result<Config<D2>, BadSketch> {
        Config::read_plane(model, params)
    }
}
impl Frames for D3 {
    type Frame = Frame3;
    fn read(model: &Model, params: &[f64]) -> Result<Config<D3>, BadSketch> {
        Config::read_space(model, params)
    }
}

type Pt<S> = <<S as Frames>::Frame as RigidFrame>::P;
type Vc<S> = <<S as Frames>::Frame as RigidFrame>::V;

/// Frames, dimensions and local coordinates of a model of one space (the plane by default).
#[derive(Clone, Debug)]
pub struct Config<S: Frames = D2> {
    /// The frame of every top-level geom. A 3d circle's or plane's z axis is its normal.
    pub frames: HashMap<GeomId, S::Frame>,
    /// The dimension of segments (length) and circles (radius).
    pub dims: HashMap<GeomId, f64>,
    /// Local coordinates of member points and markers.
    local_points: HashMap<GeomId, Pt<S>>,
    /// Local directions of member vectors and marker axes.
    local_dirs: HashMap<GeomId, Vc<S>>,
    /// The first sketch point of each line, for `L.point`.
    line_sketch: HashMap<GeomId, Pt<S>>,
}

impl<S: Frames> Config<S> {
    /// Evaluates the sketch of every geom with `params`, in the space `S` (the model's).
    pub fn from_sketch(model: &Model, params: &[f64]) -> Result<Self, BadSketch> {
        S::read(model, params)
    }

    fn empty() -> Self {
        Config {
            frames: HashMap::new(),
            dims: HashMap::new(),
            local_points: HashMap::new(),
            local_dirs: HashMap::new(),
            line_sketch: HashMap::new(),
        }
    }

    /// The frame of the top-level geom `g` belongs to.
    pub fn frame(&self, model: &Model, g: GeomId) -> S::Frame {
        let top = model.top_level_of(g);
        self.frames
            .get(&top)
            .copied()
            .unwrap_or_else(S::Frame::identity)
    }

    /// The dimension of a segment or circle (0 for other geoms).
    pub fn dim(&self, g: GeomId) -> f64 {
        self.dims.get(&g).copied().unwrap_or(0.0)
    }

    /// The global position of a point feature.
    pub fn point(&self, model: &Model, g: GeomId) -> Pt<S> {
        let f = self.frame(model, g);
        match model.geoms[g].owner {
            Owner::TopLevel => f.origin(),
            Owner::Member(_) => f.point_to_global(
                &self
                    .local_points
                    .get(&g)
                    .copied()
                    .unwrap_or_else(S::Frame::origin_point),
            ),
            Owner::Part(owner, part) => match part {
                Part::End => S::Frame::offset(f.origin(), f.x_axis() * self.dim(owner)),
                Part::AxisX | Part::AxisZ | Part::Dir | Part::Normal => f.origin(),
                Part::Start | Part::Center | Part::BasePoint => f.origin(),
            },
        }
    }

    /// A member's local coordinates in its body's frame, as the sketch gives them.
    pub fn local_point(&self, g: GeomId) -> Option<Pt<S>> {
        self.local_points.get(&g).copied()
    }

    /// A member vector's, or a marker axis', unit local direction, as the sketch gives it.
    pub fn local_dir(&self, g: GeomId) -> Option<Vc<S>> {
        self.local_dirs.get(&g).copied()
    }

    /// `L.point` of a line: the foot of the perpendicular from its first sketch point.
    pub fn line_point(&self, line: GeomId) -> Pt<S> {
        let f = self
            .frames
            .get(&line)
            .copied()
            .unwrap_or_else(S::Frame::identity);
        let s = self.line_sketch.get(&line).copied().unwrap_or(f.origin());
        S::Frame::foot(f.origin(), f.x_axis(), s)
    }

    /// Translates a top-level geom.
    pub fn translate(&mut self, g: GeomId, v: Vc<S>) {
        if let Some(f) = self.frames.get_mut(&g) {
            f.translate(&v);
        }
    }
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

impl Config<D2> {
    fn read_plane(model: &Model, params: &[f64]) -> Result<Config, BadSketch> {
        let mut cfg = Config::empty();
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

    /// Rotates a top-level geom about a point.
    pub fn rotate(&mut self, g: GeomId, pivot: P2, rotation: UnitComplex<f64>) {
        if let Some(f) = self.frames.get_mut(&g) {
            f.rotate_about_by(&pivot, &rotation);
        }
    }
}

fn coords3(model: &Model, c: &[gcs_lang::expr::ExprId], params: &[f64]) -> V3 {
    let at = |i: usize| c.get(i).map_or(f64::NAN, |&e| model.exprs.eval(e, params));
    V3::new(at(0), at(1), at(2))
}

fn finite3(v: &V3) -> bool {
    v.iter().all(|x| x.is_finite())
}

impl Config<D3> {
    fn read_space(model: &Model, params: &[f64]) -> Result<Config<D3>, BadSketch> {
        let mut cfg = Config::<D3>::empty();
        for (id, g) in model.geoms.iter() {
            let bad = |fault: SketchFault| BadSketch {
                geom: id,
                what: fault.what().to_string(),
            };
            match (&g.sketch, g.owner) {
                (Sketch::Point(c), Owner::TopLevel) => {
                    let p = coords3(model, c, params);
                    if !finite3(&p) {
                        return Err(bad(SketchFault::Position));
                    }
                    cfg.frames
                        .insert(id, Frame3::new(P3::from(p), UnitQuaternion::identity()));
                }
                (Sketch::Vector(c), Owner::TopLevel) => {
                    let v = coords3(model, c, params);
                    let rot = finite3(&v).then(|| rotation_onto_x(&v)).flatten();
                    let Some(rot) = rot else {
                        return Err(bad(SketchFault::Direction));
                    };
                    cfg.frames.insert(id, Frame3::new(P3::origin(), rot));
                }
                (Sketch::Line { from, to } | Sketch::Segment { from, to }, Owner::TopLevel) => {
                    let a = coords3(model, from, params);
                    let b = coords3(model, to, params);
                    let d = b - a;
                    let rot = (finite3(&a) && finite3(&b))
                        .then(|| rotation_onto_x(&d))
                        .flatten();
                    let Some(rot) = rot else {
                        return Err(bad(SketchFault::Points));
                    };
                    cfg.frames.insert(id, Frame3::new(P3::from(a), rot));
                    if g.kind == GeomKind::Segment {
                        cfg.dims.insert(id, d.norm());
                    } else {
                        cfg.line_sketch.insert(id, P3::from(a));
                    }
                }
                (
                    Sketch::Circle {
                        center,
                        radius,
                        normal,
                    },
                    Owner::TopLevel,
                ) => {
                    let c = coords3(model, center, params);
                    let r = model.exprs.eval(*radius, params);
                    let n = normal
                        .as_ref()
                        .map_or(V3::z(), |n| coords3(model, n, params));
                    let rot = (finite3(&c) && r.is_finite() && r >= 0.0 && finite3(&n))
                        .then(|| rotation_onto_z(&n))
                        .flatten();
                    let Some(rot) = rot else {
                        return Err(bad(SketchFault::Circle));
                    };
                    cfg.frames.insert(id, Frame3::new(P3::from(c), rot));
                    cfg.dims.insert(id, r);
                }
                (Sketch::Plane { normal, placement }, Owner::TopLevel) => {
                    let n = coords3(model, normal, params);
                    let rot = finite3(&n).then(|| rotation_onto_z(&n)).flatten();
                    let Some(rot) = rot else {
                        return Err(bad(SketchFault::Direction));
                    };
                    let unit = rot * V3::z();
                    // The plane's origin is its point nearest the global origin, or the
                    // point written.
                    let o = match placement {
                        PlanePlacement::Offset(d) => P3::from(unit * model.exprs.eval(*d, params)),
                        PlanePlacement::Point(c) => P3::from(coords3(model, c, params)),
                    };
                    if !finite3(&o.coords) {
                        return Err(bad(SketchFault::Position));
                    }
                    cfg.frames.insert(id, Frame3::new(o, rot));
                }
                (
                    Sketch::Body {
                        at, angle, axis, ..
                    },
                    Owner::TopLevel,
                ) => {
                    let o = at
                        .as_ref()
                        .map_or(V3::zeros(), |c| coords3(model, c, params));
                    let a = angle.map_or(0.0, |e| model.exprs.eval(e, params));
                    let ax = axis.as_ref().map_or(V3::z(), |c| coords3(model, c, params));
                    if !finite3(&o) || !a.is_finite() || !finite3(&ax) {
                        return Err(bad(SketchFault::Placement));
                    }
                    let Some(rot) = gcs_runtime::frame::rotation_sketched(&ax, a) else {
                        return Err(bad(SketchFault::Placement));
                    };
                    cfg.frames.insert(id, Frame3::new(P3::from(o), rot));
                }
                (Sketch::Point(c), Owner::Member(_)) => {
                    let p = coords3(model, c, params);
                    if !finite3(&p) {
                        return Err(bad(SketchFault::Position));
                    }
                    cfg.local_points.insert(id, P3::from(p));
                }
                (Sketch::Vector(c), Owner::Member(_)) => {
                    let v = coords3(model, c, params);
                    let Some(u) = finite3(&v).then(|| v.try_normalize(0.0)).flatten() else {
                        return Err(bad(SketchFault::Direction));
                    };
                    cfg.local_dirs.insert(id, u);
                }
                (Sketch::Marker { origin, z, x }, Owner::Member(_)) => {
                    let p = coords3(model, origin, params);
                    let xv = coords3(model, x, params);
                    let zv = z.as_ref().map_or(V3::z(), |z| coords3(model, z, params));
                    let rot = (finite3(&p) && finite3(&xv) && finite3(&zv))
                        .then(|| rotation_zx(&zv, &xv))
                        .flatten();
                    let Some(rot) = rot else {
                        return Err(bad(SketchFault::Marker));
                    };
                    cfg.local_points.insert(id, P3::from(p));
                    for &part in &g.parts {
                        match model.geoms[part].owner {
                            Owner::Part(_, Part::AxisZ) => {
                                cfg.local_dirs.insert(part, rot * V3::z());
                            }
                            Owner::Part(_, Part::AxisX) => {
                                cfg.local_dirs.insert(part, rot * V3::x());
                            }
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
        }
        Ok(cfg)
    }

    /// The global direction of a vector feature: a member's or marker axis's through its
    /// body's frame, a circle's or plane's normal (its frame's z axis), else the frame's x axis.
    pub fn dir(&self, model: &Model, g: GeomId) -> V3 {
        let f = self.frame(model, g);
        match model.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX | Part::AxisZ) => {
                f.vector_to_global(&self.local_dirs.get(&g).copied().unwrap_or_else(V3::x))
            }
            Owner::Part(_, Part::Normal) => f.z_axis(),
            _ => f.x_axis(),
        }
    }

    /// A plane's signed offset: the plane holds the points `p` with `normal . p = offset`.
    pub fn plane_offset(&self, plane: GeomId) -> f64 {
        let f = self.frames.get(&plane).copied().unwrap_or_default();
        f.z_axis().dot(&f.origin.coords)
    }

    /// Rotates a top-level geom about a point.
    pub fn rotate(&mut self, g: GeomId, pivot: P3, rotation: UnitQuaternion<f64>) {
        if let Some(f) = self.frames.get_mut(&g) {
            f.rotate_about_by(&pivot, &rotation);
        }
    }
}
