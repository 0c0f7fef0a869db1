//! A cluster's invariants record in the plane, in the canonical form of a rigid frame: its
//! rotation ([`Rot`]) and its position ([`Pos`]: free, a feature on a [`Locus`], a pivot,
//! fixed), with a free dimension, the fixed distances of a circle of free radius and the
//! points a lone line must pass ([`Pass`]). [`Record`] counts its DOF and Kramer's Table 2
//! slots from them; the fragments of the other files read it and update it as they move the
//! cluster.

use super::{circle, depends_on_dim, pivot_name};
use crate::analysis::geometry::Invariants;
use crate::plan::Reg;
use gcs_lang::model::{ConstraintId, GeomId, GeomKind};
use gcs_lang::Model;

/// What a cluster's rotation is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rot {
    /// Still free (one DOF).
    Free,
    /// Invariant: an invariant vector fixes it.
    Known,
    /// The cluster has no orientation (a point, a circle).
    None,
}

/// A world locus held in a register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Locus {
    /// A line.
    Line(Reg),
    /// A circle.
    Circle(Reg),
    /// A conic (parabola, ellipse or hyperbola branch) from locus analysis of a circle.
    Conic(Reg),
}

/// What a cluster's position is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pos {
    /// Free to translate (two DOF; one for a line, whose slide along itself is no motion).
    Free,
    /// A feature is on a 1-dimensional locus (one DOF).
    On {
        /// The feature.
        feature: GeomId,
        /// Its locus.
        locus: Locus,
    },
    /// The cluster may only rotate about a known point (an invariant point).
    Pivot {
        /// The pivot's position.
        at: Reg,
        /// The feature at the pivot: a point feature, or a segment of known length pinned at
        /// its midpoint (which is no feature of it: the segment stands for it).
        feature: GeomId,
    },
    /// Position invariant.
    Fixed,
    /// The cluster has no position (a vector).
    None,
}

/// A cluster's invariants record.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Rotation.
    pub rot: Rot,
    /// Position.
    pub pos: Pos,
    /// The geom with a free dimension (segment length, circle radius), if still free.
    pub free_dim: Option<GeomId>,
    /// Fixed-distance lines and points of a circle whose radius is still free (Table 2's last
    /// slots): each ties its centre to its radius.
    pub fd: Vec<circle::Fd>,
    /// Whether the position is the centre locus those fixed distances make (RR-1 and kin):
    /// then they fix the radius once the centre is placed, and count once, not twice.
    pub fd_locus: bool,
    /// Invariant dimensions.
    pub fixed_dims: Vec<GeomId>,
    /// Whether the cluster is a lone line (its slide along itself is a symmetry).
    pub line: bool,
    /// The direction feature whose own line the cluster can only slide along, once it has
    /// been put on it: that line is known while the cluster is not (a segment's side of a
    /// profile, placed before its ends are).
    pub along: Option<GeomId>,
    /// Known points a lone line of free direction and place must pass at a distance, recorded
    /// until a second one (or its direction) fixes it: each removes one DOF.
    pub passes: Vec<Pass>,
    /// For a circle: the direction features of the lines made tangent to it. A point of such
    /// a line put on the circle is their touching point, built as the foot of the centre on
    /// the line rather than as the double root of an intersection (whose rounding would grow
    /// to its square root).
    pub tangent: Vec<GeomId>,
    /// For a circle of known radius whose centre was put on the circle about a known point
    /// it passes through: that point (a fillet's joint, before its tangency).
    pub joint: Option<GeomId>,
    /// A segment end put on a known circle, with that circle: when the segment's line is then
    /// made tangent to it, the end is their touching point.
    pub on_circle: Option<(GeomId, GeomId)>,
}

/// A known point `at` that a lone line must pass at signed distance `d` (positive: `at` to
/// its left), recorded with its constraint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pass {
    /// The point.
    pub at: Reg,
    /// The signed distance.
    pub d: Reg,
    /// The constraint it records.
    pub constraint: ConstraintId,
    /// Whether that is the constraint's last relation.
    pub last: bool,
}

impl Record {
    /// The record of top-level geom `g` before any constraint: free, unless it is `fixed`.
    pub(super) fn new(model: &Model, g: GeomId) -> Record {
        let geom = &model.geoms[g];
        let (rot, pos) = match geom.kind {
            GeomKind::Point | GeomKind::Circle => (Rot::None, Pos::Free),
            GeomKind::Vector => (Rot::Free, Pos::None),
            _ => (Rot::Free, Pos::Free),
        };
        let free_dim = matches!(geom.kind, GeomKind::Segment | GeomKind::Circle).then_some(g);
        let mut record = Record {
            rot,
            pos,
            free_dim,
            fd: Vec::new(),
            fd_locus: false,
            fixed_dims: Vec::new(),
            line: geom.kind == GeomKind::Line,
            along: None,
            passes: Vec::new(),
            tangent: Vec::new(),
            joint: None,
            on_circle: None,
        };
        if geom.fixed {
            record.hold();
            if let Some(d) = record.free_dim.take() {
                record.fixed_dims.push(d);
            }
        }
        record
    }
}

impl Invariants for Record {
    fn dof(&self) -> usize {
        let rot = usize::from(self.rot == Rot::Free);
        let pos = match self.pos {
            Pos::Free if self.line => 1,
            Pos::Free => 2,
            Pos::On { .. } => 1,
            Pos::Pivot { .. } | Pos::Fixed | Pos::None => 0,
        };
        // Each fixed distance ties the free radius to the centre: one DOF less, except those
        // already folded into the centre's locus.
        let tied = if self.fd_locus {
            self.fd.len().saturating_sub(1)
        } else {
            self.fd.len()
        };
        (rot + pos + usize::from(self.free_dim.is_some())).saturating_sub(tied + self.passes.len())
    }

    fn rigid(&self) -> bool {
        self.free_dim.is_none() && self.fd.is_empty()
    }

    fn loose(&self) -> bool {
        matches!(self.rot, Rot::Free | Rot::None) && self.pos == Pos::Free
    }

    fn hold(&mut self) {
        if self.rot == Rot::Free {
            self.rot = Rot::Known;
        }
        if self.pos != Pos::None {
            self.pos = Pos::Fixed;
        }
    }

    fn point_known(&self, model: &Model, f: GeomId) -> bool {
        self.grounded()
            || matches!(self.pos, Pos::Pivot { feature, .. }
                if feature == f || model.constant_distance(feature, f) == Some(0.0))
            || (self.pos == Pos::Fixed && self.rot != Rot::Free && !depends_on_dim(model, f))
    }

    /// In the plane there are no 2D-constrained points (a point on a 2D locus is free), no
    /// 1D-constrained vectors (a direction is free or invariant) and no fixed-distance planes:
    /// those slots are always 0.
    fn table2(&self) -> [usize; 9] {
        let (inv_pts, pts_1d) = match self.pos {
            Pos::Pivot { .. } => (1, 0),
            Pos::Fixed => (if self.rot == Rot::Known { 2 } else { 1 }, 0),
            Pos::On { .. } => (0, 1),
            _ => (0, 0),
        };
        let inv_vec = usize::from(self.rot == Rot::Known);
        let circle_fd_pts = self.fd.iter().filter(|f| !f.is_line()).count();
        let fd_lines = self.fd.len() - circle_fd_pts;
        let fd_pts = circle_fd_pts + self.passes.len();
        [
            inv_pts,
            pts_1d,
            0,
            inv_vec,
            0,
            self.fixed_dims.len(),
            fd_pts,
            fd_lines,
            0,
        ]
    }

    fn recorded(&self) -> Vec<ConstraintId> {
        (self.fd.iter().filter_map(circle::Fd::satisfies))
            .chain(self.passes.iter().filter(|p| p.last).map(|p| p.constraint))
            .collect()
    }

    fn freedom(&self, model: &Model, g: GeomId) -> String {
        let name = |f: GeomId| model.geoms[f].name.clone();
        let mut parts = Vec::new();
        match (self.rot, self.pos) {
            (Rot::Free, Pos::Pivot { feature, .. }) => parts.push(format!(
                "it may still rotate about {}",
                pivot_name(model, feature)
            )),
            (Rot::Free, Pos::Free) => parts.push("it may still translate and rotate".into()),
            (Rot::Free, Pos::On { feature, .. }) => parts.push(format!(
                "it may still slide {} along its locus and rotate about it",
                name(feature)
            )),
            (Rot::Free, _) => parts.push("it may still rotate".into()),
            (_, Pos::Free) if self.line => parts.push("it may still move sideways".into()),
            (_, Pos::Free) => parts.push("it may still translate".into()),
            (_, Pos::On { feature, .. }) => parts.push(format!(
                "it may still slide {} along its locus",
                name(feature)
            )),
            _ => {}
        }
        if self.free_dim.is_some() {
            let what = if model.geoms[g].kind == GeomKind::Circle {
                "radius"
            } else {
                "length"
            };
            parts.push(format!("its {what} is free"));
        }
        parts.join(", and ")
    }
}
