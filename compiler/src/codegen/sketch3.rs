//! The sketch of a 3d model as codegen writes it, the counterpart of `sketch.rs` in the plane:
//! each geom's `Frame3` (a literal where the sketch is constant, else the runtime's
//! `rotation_onto_x`/`rotation_onto_z`/`rotation_zx`/`rotation_sketched`, which the
//! configuration calls too), its dimension, the sketch's checks, the local coordinates params
//! set, and the literals of points, vectors and rotations of space.

use super::context::Context;
use super::facts::FrameFacts;
use super::sketch::ParamLocal;
use super::writer::float;
use crate::config::{SketchFault, D3};
use gcs_lang::expr::ExprId;
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, PlanePlacement, Sketch};

/// `Point3::new(x, y, z)` of literal coordinates.
pub(super) fn point3(p: &nalgebra::Point3<f64>) -> String {
    format!(
        "Point3::new({}, {}, {})",
        float(p.x),
        float(p.y),
        float(p.z)
    )
}

/// `Vector3::new(x, y, z)` of literal coordinates (the unit axes by name).
pub(super) fn vector3(v: &nalgebra::Vector3<f64>) -> String {
    let bits = |a: f64, b: f64| a.to_bits() == b.to_bits();
    let is = |x: f64, y: f64, z: f64| bits(v.x, x) && bits(v.y, y) && bits(v.z, z);
    if is(1.0, 0.0, 0.0) {
        "Vector3::x()".into()
    } else if is(0.0, 1.0, 0.0) {
        "Vector3::y()".into()
    } else if is(0.0, 0.0, 1.0) {
        "Vector3::z()".into()
    } else {
        format!(
            "Vector3::new({}, {}, {})",
            float(v.x),
            float(v.y),
            float(v.z)
        )
    }
}

/// A frame literal, to the bit.
pub(super) fn frame3(f: &gcs_runtime::frame::Frame3) -> String {
    format!(
        "Frame3::new({}, {})",
        point3(&f.origin),
        rotation3(&f.rotation)
    )
}

/// A rotation literal: its quaternion's coordinates, to the bit.
pub(super) fn rotation3(q: &nalgebra::UnitQuaternion<f64>) -> String {
    if *q == nalgebra::UnitQuaternion::identity() {
        return "UnitQuaternion::identity()".into();
    }
    let c = q.quaternion().coords;
    // `Quaternion::new` takes w first; its coordinates are stored i, j, k, w.
    format!(
        "UnitQuaternion::new_unchecked(Quaternion::new({}, {}, {}, {}))",
        float(c[3]),
        float(c[0]),
        float(c[1]),
        float(c[2])
    )
}

impl Context<'_> {
    /// The sketch of a 3d model evaluated once, for what does not depend on params: the frames,
    /// dimensions and local coordinates of constant sketches, to the bit the interpreter's.
    pub(super) fn sketch3(&self) -> &crate::config::Config<D3> {
        self.sketch3
            .as_ref()
            .expect("bug in gcs: the sketch of a 3d model was not read (its analysis passed)")
    }

    /// The code of `Point3::new(..)` of a sketch's coordinates (a missing one is not a
    /// number, as the interpreter's configuration reads it).
    pub(super) fn point_lit3(&self, c: &[ExprId]) -> String {
        let (x, y, z) = self.coords3(c);
        format!("Point3::new({x}, {y}, {z})")
    }

    /// `Vector3::new(..)` of a sketch's coordinates.
    pub(super) fn vector_lit3(&self, c: &[ExprId]) -> String {
        let (x, y, z) = self.coords3(c);
        format!("Vector3::new({x}, {y}, {z})")
    }

    pub(super) fn coords3(&self, c: &[ExprId]) -> (String, String, String) {
        let at = |i: usize| c.get(i).map_or("f64::NAN".into(), |&e| self.expr(e));
        (at(0), at(1), at(2))
    }

    pub(super) fn all_constant(&self, es: &[ExprId]) -> bool {
        es.iter().all(|&e| self.model.exprs.is_constant(e))
    }

    /// Every expression of a top-level geom's own sketch.
    pub(super) fn sketch_exprs(&self, g: GeomId) -> Vec<ExprId> {
        let mut out = Vec::new();
        match &self.model.geoms[g].sketch {
            Sketch::Point(c) | Sketch::Vector(c) => out.extend(c),
            Sketch::Line { from, to } | Sketch::Segment { from, to } => {
                out.extend(from);
                out.extend(to);
            }
            Sketch::Circle {
                center,
                radius,
                normal,
            } => {
                out.extend(center);
                out.push(*radius);
                out.extend(normal.iter().flatten());
            }
            Sketch::Plane { normal, placement } => {
                out.extend(normal);
                match placement {
                    PlanePlacement::Offset(d) => out.push(*d),
                    PlanePlacement::Point(c) => out.extend(c),
                }
            }
            Sketch::Body {
                at, angle, axis, ..
            } => {
                out.extend(at.iter().flatten());
                out.extend(angle.iter());
                out.extend(axis.iter().flatten());
            }
            Sketch::Marker { origin, z, x } => {
                out.extend(origin);
                out.extend(z.iter().flatten());
                out.extend(x);
            }
            _ => {}
        }
        out
    }

    /// The constructor of top-level geom `g`'s `Frame3` where the sketch puts it: a literal
    /// when its sketch is constant, else the runtime's construction from the params (which
    /// `solve` has checked usable), as the interpreter's configuration builds it.
    pub(super) fn sketch_frame3(&self, g: GeomId) -> (String, FrameFacts) {
        let facts = FrameFacts::default();
        if self.all_constant(&self.sketch_exprs(g)) {
            let frame = (self.sketch3().frames.get(&g).copied()).unwrap_or_default();
            let facts = FrameFacts {
                literal3: Some(frame),
                ..facts
            };
            return (frame3(&frame), facts);
        }
        let checked = ".unwrap_or_else(UnitQuaternion::identity)";
        let ctor = match &self.model.geoms[g].sketch {
            Sketch::Point(c) => format!(
                "Frame3::new({}, UnitQuaternion::identity())",
                self.point_lit3(c)
            ),
            Sketch::Vector(c) => format!(
                "Frame3::new(Point3::origin(), frame::rotation_onto_x(&{}){checked})",
                self.vector_lit3(c)
            ),
            Sketch::Line { from, to } | Sketch::Segment { from, to } => format!(
                "{{ let start = {}; Frame3::new(start, frame::rotation_onto_x(&({} - start)){checked}) }}",
                self.point_lit3(from),
                self.point_lit3(to)
            ),
            Sketch::Circle { center, normal, .. } => {
                let n = normal
                    .as_ref()
                    .map_or("Vector3::z()".into(), |n| self.vector_lit3(n));
                format!(
                    "Frame3::new({}, frame::rotation_onto_z(&{n}){checked})",
                    self.point_lit3(center)
                )
            }
            Sketch::Plane { normal, placement } => {
                let rot = format!(
                    "frame::rotation_onto_z(&{}){checked}",
                    self.vector_lit3(normal)
                );
                match placement {
                    // The plane's origin is its point nearest the global origin.
                    PlanePlacement::Offset(d) => format!(
                        "{{ let turn = {rot}; Frame3::new(Point3::from(turn * Vector3::z() * {}), turn) }}",
                        self.expr(*d)
                    ),
                    PlanePlacement::Point(c) => {
                        format!("Frame3::new({}, {rot})", self.point_lit3(c))
                    }
                }
            }
            Sketch::Body {
                at, angle, axis, ..
            } => {
                let o = at
                    .as_ref()
                    .map_or("Point3::origin()".into(), |c| self.point_lit3(c));
                let a = angle.map_or("0.0".into(), |e| self.expr(e));
                let ax = axis
                    .as_ref()
                    .map_or("Vector3::z()".into(), |c| self.vector_lit3(c));
                format!("Frame3::new({o}, frame::rotation_sketched(&{ax}, {a}){checked})")
            }
            _ => "Frame3::identity()".into(),
        };
        (ctor, facts)
    }

    /// The sketch value of a 3d segment's length or circle's radius when its sketch is
    /// constant.
    pub(super) fn sketch_dim_value3(&self, g: GeomId) -> Option<f64> {
        let constant = self.all_constant(&self.sketch_exprs(g));
        (self.sketch3.as_ref())
            .filter(|_| constant)
            .map(|s| s.dim(g))
    }

    /// The sketch value of a 3d segment's length or circle's radius: a literal when constant.
    pub(super) fn sketch_dim3(&self, g: GeomId) -> Option<String> {
        let geom = &self.model.geoms[g];
        if !matches!(geom.kind, GeomKind::Segment | GeomKind::Circle) {
            return None;
        }
        if let Some(d) = self.sketch_dim_value3(g) {
            return Some(float(d));
        }
        match &geom.sketch {
            Sketch::Segment { from, to } => Some(format!(
                "({} - {}).norm()",
                self.point_lit3(to),
                self.point_lit3(from)
            )),
            Sketch::Circle { radius, .. } => Some(self.expr(*radius)),
            _ => None,
        }
    }

    /// The sketches of a 3d model that some params make unusable, in the model's order, with
    /// the interpreter's tests (see `Config::<D3>::read_space`).
    pub(super) fn sketch_checks3(&self) -> Vec<(GeomId, String, SketchFault)> {
        let m = self.model;
        let surely_finite = |e: ExprId| {
            let mut e = e;
            while let gcs_lang::expr::ExprNode::Neg(a) = m.exprs.node(e) {
                e = *a;
            }
            m.exprs.is_constant(e) || matches!(m.exprs.node(e), gcs_lang::expr::ExprNode::Param(_))
        };
        let not_finite = |es: &[ExprId]| -> Vec<String> {
            es.iter()
                .filter(|e| !surely_finite(**e))
                .map(|&e| format!("!gcs_runtime::num::is_finite({})", self.expr(e)))
                .collect()
        };
        let mut out = Vec::new();
        let mut push = |g: GeomId, mut tests: Vec<String>, fault: SketchFault| {
            if !tests.is_empty() {
                tests.dedup();
                out.push((g, tests.join(" || "), fault));
            }
        };
        for (id, g) in m.geoms.iter() {
            let top = matches!(g.owner, Owner::TopLevel);
            let member = matches!(g.owner, Owner::Member(_));
            let exprs = self.sketch_exprs(id);
            if (!top && !member) || self.all_constant(&exprs) {
                continue;
            }
            let mut tests = not_finite(&exprs);
            let fault = match (&g.sketch, top) {
                (Sketch::Point(_), _) => SketchFault::Position,
                (Sketch::Vector(c), true) => {
                    tests.push(format!(
                        "frame::rotation_onto_x(&{}).is_none()",
                        self.vector_lit3(c)
                    ));
                    SketchFault::Direction
                }
                (Sketch::Vector(c), false) => {
                    tests.push(format!("{}.norm() == 0.0", self.vector_lit3(c)));
                    SketchFault::Direction
                }
                (Sketch::Line { from, to } | Sketch::Segment { from, to }, true) => {
                    tests.push(format!(
                        "frame::rotation_onto_x(&({} - {})).is_none()",
                        self.point_lit3(to),
                        self.point_lit3(from)
                    ));
                    SketchFault::Points
                }
                (Sketch::Circle { radius, normal, .. }, true) => {
                    if !m.exprs.is_constant(*radius) {
                        tests.push(format!("{} < 0.0", self.expr(*radius)));
                    }
                    if let Some(n) = normal {
                        tests.push(format!(
                            "frame::rotation_onto_z(&{}).is_none()",
                            self.vector_lit3(n)
                        ));
                    }
                    SketchFault::Circle
                }
                (Sketch::Plane { normal, placement }, true) => {
                    // The normal first, then the origin it places, as the interpreter reads
                    // them.
                    let mut first = not_finite(normal);
                    first.push(format!(
                        "frame::rotation_onto_z(&{}).is_none()",
                        self.vector_lit3(normal)
                    ));
                    push(id, first, SketchFault::Direction);
                    let origin = match placement {
                        PlanePlacement::Offset(d) => format!(
                            "(frame::rotation_onto_z(&{}).unwrap_or_else(UnitQuaternion::identity) * Vector3::z() * {})",
                            self.vector_lit3(normal),
                            self.expr(*d)
                        ),
                        PlanePlacement::Point(c) => format!("{}.coords", self.point_lit3(c)),
                    };
                    tests = vec![format!("!{origin}.iter().all(|x| x.is_finite())")];
                    SketchFault::Position
                }
                (Sketch::Body { angle, axis, .. }, true) => {
                    let ax = axis
                        .as_ref()
                        .map_or("Vector3::z()".into(), |c| self.vector_lit3(c));
                    let a = angle.map_or("0.0".into(), |e| self.expr(e));
                    tests.push(format!("frame::rotation_sketched(&{ax}, {a}).is_none()"));
                    SketchFault::Placement
                }
                (Sketch::Marker { z, x, .. }, false) => {
                    let zv = z
                        .as_ref()
                        .map_or("Vector3::z()".into(), |c| self.vector_lit3(c));
                    tests.push(format!(
                        "frame::rotation_zx(&{zv}, &{}).is_none()",
                        self.vector_lit3(x)
                    ));
                    SketchFault::Marker
                }
                _ => continue,
            };
            push(id, tests, fault);
        }
        out
    }

    /// Whether a 3d member's local coordinates (or a marker's axes) depend on params.
    pub(super) fn local_is_param3(&self, g: GeomId) -> bool {
        let m = self.model;
        let owner = match m.geoms[g].owner {
            Owner::Part(marker, Part::AxisX | Part::AxisZ) => marker,
            _ => g,
        };
        matches!(m.geoms[owner].owner, Owner::Member(_))
            && !self.all_constant(&self.sketch_exprs(owner))
    }

    /// The local coordinates params set among the members of 3d top-level geom `g`: a member
    /// point's or vector's, and a marker's origin, z axis and x axis.
    pub(super) fn param_locals3(&self, g: GeomId) -> Vec<ParamLocal> {
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
                Sketch::Point(c) => out.push(local(part, "local", false, self.point_lit3(c))),
                Sketch::Vector(c) => {
                    let value = format!("{}.normalize()", self.vector_lit3(c));
                    out.push(local(part, "local", true, value));
                }
                Sketch::Marker { origin, z, x } => {
                    out.push(local(part, "local", false, self.point_lit3(origin)));
                    let zv = z
                        .as_ref()
                        .map_or("Vector3::z()".into(), |c| self.vector_lit3(c));
                    let turn = format!(
                        "frame::rotation_zx(&{zv}, &{}).unwrap_or_else(UnitQuaternion::identity)",
                        self.vector_lit3(x)
                    );
                    for &axis in &p.parts {
                        let (suffix, unit) = match m.geoms[axis].owner {
                            Owner::Part(_, Part::AxisZ) => ("z_local", "z"),
                            Owner::Part(_, Part::AxisX) => ("x_local", "x"),
                            _ => continue,
                        };
                        let value = format!("{turn} * Vector3::{unit}()");
                        out.push(local(axis, suffix, true, value));
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// The local coordinates of a 3d member point (or marker) whose sketch is constant.
    pub(super) fn local_point3(&self, g: GeomId) -> String {
        let p = self
            .sketch3()
            .local_point(g)
            .unwrap_or_else(nalgebra::Point3::origin);
        point3(&p)
    }

    /// The unit local direction of a 3d member vector or marker axis whose sketch is constant.
    pub(super) fn local_dir3(&self, g: GeomId) -> String {
        let v = self
            .sketch3()
            .local_dir(g)
            .unwrap_or_else(nalgebra::Vector3::x);
        vector3(&v)
    }
}
