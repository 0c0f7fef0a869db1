//! What else a joint asks of a turn about an axis. A lower pair or a helical joint is several
//! relations of one constraint; when its z axes are turned onto each other about an axis, the
//! relations still to come (its x axes' coupling, its point on a line or in a plane, its
//! helix) decide the turn with the z axis (`twin_x_axes`, `reach`), which a z axis nearly
//! along the turn's axis fixes only to rounding. Also where a twist takes a marker's x axis
//! (`twist_target`).

use super::relation::Relation;
use super::{Locus, Rel, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{HelixRegs, Op, Reach, Reg, ScrewRegs, SpatialOp, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    /// The x axis a joint's coupling of x axes (offset_x, prismatic, weld: a [`Relation::Twist`] of
    /// constraint `r`, still to come) gives the marker whose z axis `z` is being turned onto
    /// `z_target`: `(that x axis now, its target)`. A turn about an axis that takes the z axis
    /// onto its target also takes the x axis onto its own, so both decide the turn: a z axis
    /// nearly along the turn's axis fixes it only to rounding over its distance from the axis,
    /// and the x axis, perpendicular to it, is then across the axis. `None` without such a
    /// coupling.
    pub(super) fn twin_x_axes(&mut self, r: &Rel, z: GeomId, z_target: Reg) -> Option<(Reg, Reg)> {
        if let Some(twin) = self.helix_x_axes(r, z, z_target) {
            return Some(twin);
        }
        let (axis, u, v, angle) = self.pending.iter().find_map(|p| match p.relation {
            Relation::Twist { axis, u, v, angle } if p.constraint == r.constraint => {
                Some((axis, u, v, angle))
            }
            _ => None,
        })?;
        let k = self.cluster(z);
        let by = self.angle(angle);
        if self.cluster(v) == k && self.dir_known(axis) && self.dir_known(u) {
            // The second marker turns: its x axis goes to the first's turned by the angle.
            let (a, x) = (self.direction(axis), self.direction(u));
            let about = self.name(axis);
            let to = self.twist_target((u, x), (a, about), by, false);
            Some((self.direction(v), to))
        } else if self.cluster(u) == k && self.dir_known(v) {
            // The first turns: its x axis goes to the second's turned back about the first's
            // z axis as it will be.
            let x = self.direction(v);
            let about = self.word(z_target);
            let to = self.twist_target((v, x), (z_target, about), by, true);
            Some((self.direction(u), to))
        } else {
            None
        }
    }

    /// The point of cluster `k` that a joint's position (a coincidence, a point on a line or
    /// in a plane: a relation of constraint `r`, still to come) must take onto a known locus
    /// by the turn about `axis` now being made, and that locus: where the point must be for
    /// the cluster's remaining slide to bring it home (none: the joint's own line or plane, or
    /// a line along the axis through its target; along a line: the line through the target
    /// parallel to it; in a plane: the plane through the target parallel to it). The point
    /// off the axis then decides the turn with the z axis (see `SpatialOp::TurnReaching`). `None`
    /// without such a relation, or when the slide and the joint's locus together leave the
    /// point a surface no record holds.
    pub(super) fn reach(
        &mut self,
        r: &Rel,
        k: usize,
        axis: Reg,
        (v, target): (GeomId, Reg),
    ) -> Option<(Reach, Option<ScrewRegs>)> {
        if let Some(screwed) = self.reach_on_screw(r, k) {
            return Some(screwed);
        }
        self.reach_sliding(r, k, axis, (v, target))
            .map(|(point, locus)| (Reach::Point { point, locus }, None))
    }

    /// The registers of a helical coupling whose first marker `a` (z axis `za`, x axis `xa`)
    /// is known and whose second `b` (x axis `xb`) turns with the cluster.
    fn helix_regs(
        &mut self,
        (za, xa, a): (GeomId, GeomId, GeomId),
        (xb, b): (GeomId, GeomId),
        pitch: gcs_lang::expr::ExprId,
    ) -> HelixRegs {
        HelixRegs {
            axis: self.direction(za),
            x_from: self.direction(xa),
            origin: self.point(a),
            x: self.direction(xb),
            point: self.point(b),
            pitch: self.expr(pitch),
        }
    }

    /// As [`Builder::reach`] for a cluster that rides a screw (it slides along a line, and a
    /// helical coupling of another constraint, still to come, ties that slide to the turn): a
    /// joint's point must then reach its line or plane where the screw takes it, which
    /// `SpatialOp::TurnReaching` follows with the screw's registers.
    fn reach_on_screw(&mut self, r: &Rel, k: usize) -> Option<(Reach, Option<ScrewRegs>)> {
        let Trans::On {
            locus: Locus::Line(slide),
            ..
        } = self.clusters[k].record.trans
        else {
            return None;
        };
        let (za, xa, xb, a, b, pitch) = self.pending.iter().find_map(|p| match p.relation {
            Relation::Helix {
                axis,
                u,
                v,
                p: a,
                q: b,
                pitch,
            } if p.constraint != r.constraint => Some((axis, u, v, a, b, pitch)),
            _ => None,
        })?;
        if !(self.dir_known(za) && self.dir_known(xa) && self.point_known(a))
            || self.cluster(xb) != k
            || self.cluster(b) != k
        {
            return None;
        }
        let relation = self.pending_of(r, |rel| {
            matches!(
                rel,
                Relation::PointLine { d: None, .. }
                    | Relation::PointPlane { d: None, .. }
                    | Relation::Helix { .. }
            )
        })?;
        let reach = match relation {
            // A helical joint itself: its coupling, where the screw takes its second marker.
            Relation::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } if self.dir_known(axis)
                && self.dir_known(u)
                && self.point_known(p)
                && self.cluster(v) == k
                && self.cluster(q) == k =>
            {
                Reach::Helix(self.helix_regs((axis, u, p), (v, q), pitch))
            }
            Relation::Helix { .. } => return None,
            joint => {
                let (point, locus) = self.joint_locus(&joint, k)?;
                Reach::Point { point, locus }
            }
        };
        let helix = self.helix_regs((za, xa, a), (xb, b), pitch);
        Some((reach, Some(ScrewRegs { helix, slide })))
    }

    /// [`Builder::reach`] for a cluster whose slide after the turn is free.
    fn reach_sliding(
        &mut self,
        r: &Rel,
        k: usize,
        axis: Reg,
        (v, target): (GeomId, Reg),
    ) -> Option<(Reg, Reg)> {
        let relation = self.pending_of(r, |rel| {
            matches!(
                rel,
                Relation::PointPoint { d: None, .. }
                    | Relation::PointLine { d: None, .. }
                    | Relation::PointPlane { d: None, .. }
            )
        })?;
        let trans = self.clusters[k].record.trans;
        let still = matches!(trans, Trans::Pivot { .. } | Trans::Fixed);
        match relation {
            Relation::PointPoint { a, b, .. } => {
                let (p, q) = if self.cluster(a) == k && self.point_known(b) {
                    (a, b)
                } else if self.cluster(b) == k && self.point_known(a) {
                    (b, a)
                } else {
                    return None;
                };
                let (at, to) = (self.point(p), self.point(q));
                let qname = self.name(q);
                let locus = match trans {
                    _ if still => {
                        let words = format!("the line through {qname} along {}", self.word(axis));
                        self.line(to, axis, words)
                    }
                    Trans::On {
                        locus: Locus::Line(l),
                        ..
                    } => {
                        let words = format!("{} moved through {qname}", self.word(l));
                        self.value(
                            Op::ParallelLine {
                                line: l,
                                through: to,
                            },
                            Ty::Line,
                            words,
                        )
                    }
                    Trans::On {
                        locus: Locus::Plane(plane),
                        ..
                    } => {
                        let words = format!("{} moved through {qname}", self.word(plane));
                        self.value(
                            SpatialOp::ParallelPlane { plane, through: to },
                            Ty::Plane,
                            words,
                        )
                    }
                    _ => return None,
                };
                Some((at, locus))
            }
            Relation::PointLine { p, base, dir, .. }
                if still && dir == v && self.cluster(base) == k && self.point_known(p) =>
            {
                // The line turns with the cluster (a helical joint's second marker): its point
                // must reach the line through the known point along the direction's target.
                let (at, point) = (self.point(base), self.point(p));
                let words = format!(
                    "the line through {} along {}",
                    self.name(p),
                    self.word(target)
                );
                Some((at, self.line(point, target, words)))
            }
            joint if still => self.joint_locus(&joint, k),
            _ => None,
        }
    }

    /// The relation of constraint `r` still to come that `wanted` picks.
    fn pending_of(&self, r: &Rel, wanted: impl Fn(&Relation) -> bool) -> Option<Relation> {
        (self.pending.iter())
            .find(|p| p.constraint == r.constraint && wanted(&p.relation))
            .map(|p| p.relation.clone())
    }

    /// A joint's point of cluster `k` and the known line or plane a `PointLine` or
    /// `PointPlane` relation puts it on.
    fn joint_locus(&mut self, joint: &Relation, k: usize) -> Option<(Reg, Reg)> {
        match *joint {
            Relation::PointLine { p, base, dir, .. }
                if self.cluster(p) == k && self.point_known(base) && self.dir_known(dir) =>
            {
                let (at, point, dir) = (self.point(p), self.point(base), self.direction(dir));
                let words = format!(
                    "the line through {} along {}",
                    self.name(base),
                    self.word(dir)
                );
                Some((at, self.line(point, dir, words)))
            }
            Relation::PointPlane {
                p, base, normal, ..
            } if self.cluster(p) == k && self.point_known(base) && self.dir_known(normal) => {
                let words = self.plane_words(base, normal, None);
                let (at, point, normal) = (self.point(p), self.point(base), self.direction(normal));
                let op = Op::Spatial(SpatialOp::Plane {
                    point,
                    normal,
                    offset: None,
                });
                Some((at, self.value(op, Ty::Plane, words)))
            }
            _ => None,
        }
    }

    /// As [`Builder::twin_x_axes`] for a helical joint (a [`Relation::Helix`] of `r`) whose
    /// first marker is known and whose second turns with the cluster about its axis, the
    /// cluster held at a point (so that nothing moves it along the axis after the turn): the
    /// second's x axis must reach the first's turned by the helix's turn for the advance, the
    /// distance along the first's z axis between the two markers' points. The advance is
    /// measured where the z axis' own turn takes the second point (`z` onto `z_target` about
    /// the cluster's axis): nearly along the axis, that turn is off by rounding over its
    /// distance from it, but the advance then changes with the turn only as much as that
    /// distance, so it is exact to rounding; and well across the axis the turn is exact.
    fn helix_x_axes(&mut self, r: &Rel, z: GeomId, z_target: Reg) -> Option<(Reg, Reg)> {
        let (za, xa, xb, a, b, pitch) = self.pending.iter().find_map(|p| match p.relation {
            Relation::Helix {
                axis,
                u,
                v,
                p: a,
                q: b,
                pitch,
            } if p.constraint == r.constraint => Some((axis, u, v, a, b, pitch)),
            _ => None,
        })?;
        let k = self.cluster(z);
        let rec = &self.clusters[k].record;
        // Held at a point: the advance after the turn is where the turn leaves it (a slide
        // after the turn would change it).
        let (
            Turn::Axis {
                axis: turn_axis, ..
            },
            Trans::Pivot { .. } | Trans::Fixed,
        ) = (rec.turn, rec.trans)
        else {
            return None;
        };
        if !(self.dir_known(za) && self.dir_known(xa) && self.point_known(a))
            || self.cluster(xb) != k
            || self.cluster(b) != k
        {
            return None;
        }
        let pivot = self.pivot_of(k);
        let (z_now, za_reg, pa, pb) = (
            self.direction(z),
            self.direction(za),
            self.point(a),
            self.point(b),
        );
        let (zname, bname, aname) = (self.name(z), self.name(b), self.name(a));
        let words = format!(
            "the angle about {} taking {zname} to {}",
            self.word(turn_axis),
            self.word(z_target)
        );
        let turn = self.value(
            SpatialOp::AngleAbout {
                u: z_now,
                v: z_target,
                axis: turn_axis,
            },
            Ty::Scalar,
            words,
        );
        let words = format!("minus {}", self.word(turn));
        let back = self.value(Op::Neg(turn), Ty::Scalar, words);
        let words = format!("{} turned back by it", self.name(za));
        let za_back = self.value(
            SpatialOp::TurnedAbout {
                dir: za_reg,
                axis: turn_axis,
                angle: back,
            },
            Ty::Vector,
            words,
        );
        let words = format!("the advance of the pivot from {aname}");
        let to_pivot = self.value(
            Op::Along {
                from: pa,
                dir: za_reg,
                to: pivot,
            },
            Ty::Scalar,
            words,
        );
        let words = format!("the advance of {bname} from the pivot once turned");
        let from_pivot = self.value(
            Op::Along {
                from: pivot,
                dir: za_back,
                to: pb,
            },
            Ty::Scalar,
            words,
        );
        let words = format!("the advance of {bname} from {aname} once turned");
        let advance = self.value(
            Op::Sum(vec![(1.0, to_pivot), (1.0, from_pivot)]),
            Ty::Scalar,
            words,
        );
        let pitch = self.expr(pitch);
        let words = format!("the helix's turn for {}", self.word(advance));
        let by = self.value(SpatialOp::HelixTurn { advance, pitch }, Ty::Scalar, words);
        let about = self.name(za);
        let xa_reg = self.direction(xa);
        let to = self.twist_target((xa, xa_reg), (za_reg, about), by, false);
        Some((self.direction(xb), to))
    }

    /// Where a twist (offset_x, prismatic, weld) takes the moving marker's x axis: the known x axis
    /// `g` (its direction in `x`) turned about `axis` by the angle `by` (the second marker's),
    /// or back by it (`back`: the first's).
    pub(super) fn twist_target(
        &mut self,
        (g, x): (GeomId, Reg),
        (axis, about): (Reg, String),
        by: Reg,
        back: bool,
    ) -> Reg {
        // No twist (a weld's, an offset written as a constant zero): the known x axis itself.
        let exprs = &self.model.exprs;
        let zero = match self.def(by).map(|s| &s.op) {
            Some(Op::Const(c)) => *c == 0.0,
            Some(Op::Expr(e)) => exprs.is_constant(*e) && exprs.eval(*e, &[]) == 0.0,
            _ => false,
        };
        if zero {
            return x;
        }
        let angle = if back {
            let words = format!("minus {}", self.word(by));
            self.value(Op::Neg(by), Ty::Scalar, words)
        } else {
            by
        };
        let words = format!(
            "{} turned {}by {} about {about}",
            self.name(g),
            if back { "back " } else { "" },
            self.word(by)
        );
        self.value(
            SpatialOp::TurnedAbout {
                dir: x,
                axis,
                angle,
            },
            Ty::Vector,
            words,
        )
    }
}
