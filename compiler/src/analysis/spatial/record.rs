//! A cluster's invariants record in space, after TLA (003): what is invariant of its position
//! ([`Trans`]: free, a feature held on a [`Locus`], a pivot, fixed), what is invariant of its
//! orientation ([`Turn`]: free, about one axis, known), and what it moves ([`Shape`]: a body,
//! a point, a direction, a plane, a line, a segment or circle with its size). [`Record`] counts
//! its DOF and Kramer's Table 2 slots from them; the fragments of the other files read it and
//! update it as they move the cluster.

use super::on_axis;
use crate::analysis::geometry::Invariants;
use crate::plan::{Reg, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind};
use gcs_lang::Model;

/// A locus of space a point feature is held on, in a register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Locus {
    /// A line (one DOF).
    Line(Reg),
    /// A circle (one DOF).
    Circle(Reg),
    /// A plane (two DOF).
    Plane(Reg),
    /// A sphere (two DOF).
    Sphere(Reg),
    /// A cylinder (two DOF).
    Cylinder(Reg),
    /// A torus (two DOF).
    Torus(Reg),
}

impl Locus {
    /// Its register.
    pub fn reg(self) -> Reg {
        match self {
            Locus::Line(r)
            | Locus::Circle(r)
            | Locus::Plane(r)
            | Locus::Sphere(r)
            | Locus::Cylinder(r)
            | Locus::Torus(r) => r,
        }
    }

    /// The DOF a point on it has.
    pub fn dof(self) -> usize {
        match self {
            Locus::Line(_) | Locus::Circle(_) => 1,
            Locus::Plane(_) | Locus::Sphere(_) | Locus::Cylinder(_) | Locus::Torus(_) => 2,
        }
    }

    /// The locus in register `r` of type `ty`.
    pub(super) fn of(r: Reg, ty: Ty) -> Option<Locus> {
        match ty {
            Ty::Line => Some(Locus::Line(r)),
            Ty::Circle => Some(Locus::Circle(r)),
            Ty::Plane => Some(Locus::Plane(r)),
            Ty::Sphere => Some(Locus::Sphere(r)),
            Ty::Cylinder => Some(Locus::Cylinder(r)),
            Ty::Torus => Some(Locus::Torus(r)),
            _ => None,
        }
    }

    fn words(self) -> &'static str {
        match self {
            Locus::Line(_) => "line",
            Locus::Circle(_) => "circle",
            Locus::Plane(_) => "plane",
            Locus::Sphere(_) => "sphere",
            Locus::Cylinder(_) => "cylinder",
            Locus::Torus(_) => "torus",
        }
    }
}

/// TLA's translational state: what is invariant of a cluster's position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trans {
    /// Free to translate (three DOF).
    Free,
    /// A feature is held on a locus (one or two DOF).
    On {
        /// The feature.
        feature: GeomId,
        /// Its locus.
        locus: Locus,
    },
    /// A feature is invariant: the cluster may only rotate about it.
    Pivot {
        /// Where.
        at: Reg,
        /// The feature.
        feature: GeomId,
    },
    /// Position invariant.
    Fixed,
    /// The cluster has no position (a vector).
    None,
}

/// TLA's rotational state: what is invariant of a cluster's orientation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    /// Free to rotate (three DOF for a body, two for a vector).
    Free,
    /// The cluster may only rotate about an invariant axis (one DOF).
    Axis {
        /// The axis' unit direction.
        axis: Reg,
        /// The direction feature that lies along it, if one does.
        feature: Option<GeomId>,
    },
    /// Orientation invariant.
    Known,
    /// The cluster has no orientation (a point).
    None,
}

/// What a record moves: how many DOF its freedoms count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A rigid body, or a geom moved as one.
    Body,
    /// A point.
    Point,
    /// A direction.
    Vector,
    /// A plane: its offset along its normal (one DOF) and its normal (two); sliding within
    /// itself and turning about its normal move nothing. A plane held at a distance from a
    /// known point (`Trans::Pivot` at that point) keeps it while turning about the point.
    Plane,
    /// A line: its place across its direction (two DOF) and its direction (two); sliding
    /// along itself and turning about itself move nothing (its reported point is the foot of
    /// the perpendicular from its sketch's first point, wherever its frame's origin slid).
    Line,
    /// A segment: its start (three DOF), its direction (two; turning about itself moves
    /// nothing) and, until `sized`, its length (one), which a move that scales sets.
    Segment {
        /// Whether its length is set (it is then rigid).
        sized: bool,
    },
    /// A circle: its centre (three DOF), its normal (two; turning about it moves nothing)
    /// and, until `sized`, its radius (one), which a move that scales sets.
    Circle {
        /// Whether its radius is set (it is then rigid).
        sized: bool,
    },
    /// A geom of space the analysis does not move yet, with its DOF.
    Other(usize),
}

impl Shape {
    /// Whether its orientation is one direction (a vector, a plane's normal, a line's or a
    /// segment's), so that a turn about that direction moves nothing: two turning DOF.
    pub(super) fn one_direction(self) -> bool {
        matches!(
            self,
            Shape::Vector
                | Shape::Plane
                | Shape::Line
                | Shape::Segment { .. }
                | Shape::Circle { .. }
        )
    }

    /// Whether it has a size still free (a segment's length, a circle's radius).
    pub(super) fn size_free(self) -> bool {
        matches!(
            self,
            Shape::Segment { sized: false } | Shape::Circle { sized: false }
        )
    }

    /// The same shape with its size set.
    pub(super) fn sized(self) -> Shape {
        match self {
            Shape::Segment { .. } => Shape::Segment { sized: true },
            Shape::Circle { .. } => Shape::Circle { sized: true },
            shape => shape,
        }
    }
}

/// A cluster's invariants record in space.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Translation.
    pub trans: Trans,
    /// Rotation.
    pub turn: Turn,
    /// What it moves.
    pub shape: Shape,
    /// Whether it is held where it is (fixed, or a temporary ground).
    pub held: bool,
}

impl Record {
    /// The record of top-level geom `g` before any constraint: free, unless it is `fixed`.
    pub(super) fn new(model: &Model, g: GeomId) -> Record {
        let geom = &model.geoms[g];
        let (trans, turn, shape) = match geom.kind {
            GeomKind::Point => (Trans::Free, Turn::None, Shape::Point),
            GeomKind::Vector => (Trans::None, Turn::Free, Shape::Vector),
            GeomKind::Body => (Trans::Free, Turn::Free, Shape::Body),
            GeomKind::Plane => (Trans::Free, Turn::Free, Shape::Plane),
            GeomKind::Line => (Trans::Free, Turn::Free, Shape::Line),
            GeomKind::Segment => (Trans::Free, Turn::Free, Shape::Segment { sized: false }),
            GeomKind::Circle => (Trans::Free, Turn::Free, Shape::Circle { sized: false }),
            kind => (Trans::Free, Turn::Free, Shape::Other(kind.dof(model.space))),
        };
        let mut record = Record {
            trans,
            turn,
            shape,
            held: false,
        };
        if geom.fixed {
            record.hold();
        }
        record
    }

    /// Whether the record can be moved by the fragments of this module.
    pub(super) fn movable(&self) -> bool {
        !matches!(self.shape, Shape::Other(_))
    }
}

impl Invariants for Record {
    fn dof(&self) -> usize {
        if let Shape::Other(n) = self.shape {
            return if self.held { 0 } else { n };
        }
        let trans = match self.trans {
            Trans::Free if self.shape == Shape::Plane => 1,
            Trans::Free if self.shape == Shape::Line => 2,
            Trans::Free => 3,
            Trans::On { locus, .. } => locus.dof(),
            Trans::Pivot { .. } | Trans::Fixed | Trans::None => 0,
        };
        let length = usize::from(self.shape.size_free());
        let turn = match (self.turn, self.shape) {
            (Turn::Free, shape) if shape.one_direction() => 2,
            (Turn::Free, _) => 3,
            (Turn::Axis { .. }, _) => 1,
            (Turn::Known | Turn::None, _) => 0,
        };
        trans + turn + length
    }

    /// No free size: a segment or circle whose length or radius is still free is not rigid
    /// (a group solved about it would freeze that size at the sketch's).
    fn rigid(&self) -> bool {
        !self.shape.size_free()
    }

    fn loose(&self) -> bool {
        matches!(self.trans, Trans::Free | Trans::None)
            && matches!(self.turn, Turn::Free | Turn::None)
    }

    fn hold(&mut self) {
        self.held = true;
        self.shape = self.shape.sized();
        if !matches!(self.turn, Turn::None) {
            self.turn = Turn::Known;
        }
        if self.trans != Trans::None {
            self.trans = Trans::Fixed;
        }
    }

    fn point_known(&self, model: &Model, f: GeomId) -> bool {
        self.grounded()
            || matches!(self.trans, Trans::Pivot { feature, .. }
                if feature == f || model.constant_distance(feature, f) == Some(0.0))
            // About a pivot and an axis: the points on the axis stay.
            || matches!((self.trans, self.turn),
                (Trans::Pivot { feature: g, .. }, Turn::Axis { feature: Some(a), .. })
                    if on_axis(model, g, a, f))
    }

    /// Kramer's slots in space: invariant points, 1D- and 2D-constrained points, invariant
    /// and 1D-constrained vectors (none of the latter yet), no dimensions or fixed distances.
    fn table2(&self) -> [usize; 9] {
        let (inv_pts, pts_1d, pts_2d) = match self.trans {
            Trans::Pivot { .. } | Trans::Fixed => (1, 0, 0),
            Trans::On { locus, .. } if locus.dof() == 1 => (0, 1, 0),
            Trans::On { .. } => (0, 0, 1),
            Trans::Free | Trans::None => (0, 0, 0),
        };
        let inv_vec = match (self.turn, self.shape) {
            (Turn::Axis { .. }, _) => 1,
            (Turn::Known, shape) if shape.one_direction() => 1,
            (Turn::Known, _) => 2,
            _ => 0,
        };
        [inv_pts, pts_1d, pts_2d, inv_vec, 0, 0, 0, 0, 0]
    }

    fn recorded(&self) -> Vec<ConstraintId> {
        Vec::new()
    }

    fn freedom(&self, model: &Model, _: GeomId) -> String {
        if let Shape::Other(_) = self.shape {
            return if self.held {
                String::new()
            } else {
                "it may still move: the analysis does not move this kind of geom in 3d yet".into()
            };
        }
        let name = |f: GeomId| model.geoms[f].name.clone();
        let mut parts = Vec::new();
        match self.trans {
            Trans::Free => parts.push("it may still translate".to_string()),
            Trans::On { feature, locus } => parts.push(format!(
                "it may still move {} on its {}",
                name(feature),
                locus.words()
            )),
            _ => {}
        }
        match (self.turn, self.trans) {
            (Turn::Free, Trans::Pivot { .. }) if self.shape == Shape::Line => {
                parts.push("it may still turn about the point it passes through".into())
            }
            (Turn::Free, Trans::Pivot { feature, .. }) => {
                parts.push(format!("it may still rotate about {}", name(feature)))
            }
            (Turn::Free, _) => parts.push("it may still rotate".into()),
            (Turn::Axis { feature, .. }, _) => parts.push(match feature {
                Some(f) => format!("it may still rotate about {}", name(f)),
                None => "it may still rotate about one axis".into(),
            }),
            _ => {}
        }
        parts.join(", and ")
    }
}
