//! Relations that are run-time checks, and the registers relations read. A relation whose
//! sides are both known, or that one rigid cluster holds, is implied (`implied`): the plan
//! measures its residual (`residual`) instead of moving anything. What is known of a line or
//! a direction (`line_fixed`, `line_point`, `dir_known`) and the registers of directions and
//! angles (`dir`, `angle`, `neg`) are read here for checks and moves alike.

use super::relation::{AngleValue, Dir, Relation};
use super::{angle_words, pinned_at_midpoint, Planar, Pos, Rot};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, PlanarOp, Reg, Residual, Ty};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part};

impl Builder<'_, Planar> {
    /// The register of a direction: a feature's current direction, or a world axis.
    pub(super) fn dir(&mut self, d: Dir) -> Reg {
        match d {
            Dir::Feature(g) => self.direction(g),
            Dir::World(x, y) => {
                let words = if x != 0.0 { "the X axis" } else { "the Y axis" }.to_string();
                self.value(PlanarOp::Axis(x, y), Ty::Vector, words)
            }
        }
    }

    /// The registers and residual of a relation's run-time check.
    pub(super) fn residual(&mut self, relation: &Relation) -> Residual {
        let model = self.model;
        match *relation {
            Relation::PointPoint { a, b, d } => Residual::PointPoint {
                a: self.point(a),
                b: self.point(b),
                d: d.map(|d| self.expr(d)),
            },
            Relation::PointLine { p, base, dir, d } => Residual::PointLine {
                p: self.point(p),
                base: self.point(base),
                dir: self.direction(dir),
                d: d.map(|d| self.expr(d)),
            },
            Relation::Angle { u, v, angle } => Residual::Angle {
                u: self.dir(u),
                v: self.dir(v),
                angle: self.angle(angle),
            },
            Relation::CircleLine {
                circle,
                base,
                dir,
                gap,
                side,
            } => Residual::CircleLine {
                centre: self.point(model.point_feature(circle)),
                radius: self.dim_of(circle),
                base: self.point(base),
                dir: self.direction(dir),
                gap: gap.map(|g| self.expr(g)),
                side,
            },
            Relation::PointCircle {
                p,
                circle,
                gap,
                outside,
            } => Residual::PointCircle {
                p: self.point(p),
                centre: self.point(model.point_feature(circle)),
                radius: self.dim_of(circle),
                gap: gap.map(|g| self.expr(g)),
                outside,
            },
            Relation::CircleCircle { a, b, gap, mode } => Residual::CircleCircle {
                c1: self.point(model.point_feature(a)),
                r1: self.dim_of(a),
                c2: self.point(model.point_feature(b)),
                r2: self.dim_of(b),
                gap: gap.map(|g| self.expr(g)),
                nesting: mode,
            },
            Relation::Dim { geom, value } => Residual::Dim {
                value: self.dim_of(geom),
                target: self.expr(value),
            },
            Relation::Equal { a, b } => Residual::Dim {
                value: self.dim_of(b),
                target: self.dim_of(a),
            },
            Relation::Midpoint { p, a, b } => Residual::Midpoint {
                p: self.point(p),
                a: self.point(a),
                b: self.point(b),
            },
            Relation::Mirror {
                p, q, base, dir, ..
            } => Residual::Mirror {
                p: self.point(p),
                q: self.point(q),
                base: self.point(base),
                dir: self.direction(dir),
            },
        }
    }

    /// The register of an angle a relation asks for.
    pub(super) fn angle(&mut self, angle: AngleValue) -> Reg {
        match angle {
            AngleValue::Expr(e) => self.expr(e),
            AngleValue::Const(c) => self.value(Op::Const(c), Ty::Scalar, angle_words(c)),
        }
    }

    /// Whether a relation is implied by what is known (both its sides, or one rigid cluster
    /// holding both): then it only needs a run-time check.
    pub(super) fn implied(&self, relation: &Relation) -> bool {
        let rigid_together = |a: GeomId, b: GeomId| {
            self.cluster(a) == self.cluster(b)
                && self.clusters[self.cluster(a)].record.free_dim.is_none()
        };
        let line_known = |base: GeomId, dir: GeomId| self.line_fixed(base, dir);
        let placed = |circle: GeomId| self.record(circle).grounded();
        match *relation {
            Relation::PointPoint { a, b, .. } => {
                (self.point_known(a) && self.point_known(b)) || rigid_together(a, b)
            }
            Relation::PointLine { p, base, dir, .. } => {
                (line_known(base, dir) && self.point_known(p)) || rigid_together(p, base)
            }
            Relation::Angle { u, v, .. } => {
                (self.dir_known(u) && self.dir_known(v))
                    || matches!((u, v), (Dir::Feature(x), Dir::Feature(y)) if self.cluster(x) == self.cluster(y))
            }
            Relation::Dim { geom, .. } => self.record(geom).free_dim != Some(geom),
            Relation::PointCircle { p, circle, .. } => placed(circle) && self.point_known(p),
            Relation::CircleLine {
                circle, base, dir, ..
            } => placed(circle) && line_known(base, dir),
            Relation::CircleCircle { a, b, .. } => placed(a) && placed(b),
            Relation::Equal { a, b } => self.dim_known(a) && self.dim_known(b),
            Relation::Midpoint { p, a, b } => {
                (self.point_known(p) && self.point_known(a) && self.point_known(b))
                    || (rigid_together(p, a) && rigid_together(a, b))
                    // Its segment already pinned at its midpoint: that midpoint is known.
                    || (self.point_known(p)
                        && matches!(self.record(a).pos,
                            Pos::Pivot { feature, .. } if feature == self.model.top_level_of(a)
                                && self.model.geoms[feature].kind == GeomKind::Segment))
            }
            Relation::Mirror {
                p, q, base, dir, ..
            } => {
                (line_known(base, dir) && self.point_known(p) && self.point_known(q))
                    || (rigid_together(p, q) && rigid_together(p, base))
            }
        }
    }

    /// Whether the line through `base` along `dir` is known: a known point on it and its
    /// direction, or a cluster that can only slide along it.
    pub(super) fn line_fixed(&self, base: GeomId, dir: GeomId) -> bool {
        self.dir_known(Dir::Feature(dir))
            && (self.line_point(base).is_some() || self.record(base).along == Some(dir))
    }

    /// A point on the line of (`base`, its direction) whose place on it is known, or that
    /// is on it wherever the line's freedom takes it: `base` itself, or the other end of the
    /// same segment, or the start of a segment pinned at its midpoint.
    pub(super) fn line_point(&self, base: GeomId) -> Option<GeomId> {
        if self.point_known(base) {
            return Some(base);
        }
        // A segment pinned at its midpoint, its length free: its line goes through the
        // midpoint whatever its length, so wherever its start is now is on it.
        if let Some((_, seg)) = pinned_at_midpoint(self.model, self.record(base)) {
            if self.model.part(seg, Part::Start) == Some(base) {
                return Some(base);
            }
        }
        match self.model.geoms[base].owner {
            Owner::Part(s, Part::Start) => self
                .model
                .part(s, Part::End)
                .filter(|&e| self.point_known(e)),
            _ => None,
        }
    }

    /// Whether a direction is known: a world axis, or a feature of a cluster whose rotation
    /// is invariant (or that has none).
    pub(super) fn dir_known(&self, d: Dir) -> bool {
        match d {
            Dir::World(..) => true,
            Dir::Feature(g) => matches!(self.record(g).rot, Rot::Known | Rot::None),
        }
    }

    /// `-a`.
    pub(super) fn neg(&mut self, a: Reg) -> Reg {
        let words = format!("-{}", self.word(a));
        self.value(Op::Neg(a), Ty::Scalar, words)
    }
}
