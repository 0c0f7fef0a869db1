//! Moving a point feature onto a point or a locus with the freedom its cluster's record leaves
//! (003's brick fragments for points): free to translate, onto the point or the nearest point
//! of the locus; held on a locus, a slide along it to where it meets the target; about a
//! pivot, the shortest turn onto where its sphere meets the target; about a pivot and an axis,
//! the turn by the angle between perpendiculars. Each move updates the record (`placed`).

use super::{on_axis, same_direction, Locus, Record, Rel, Shape, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reg, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    /// Moves the cluster of point feature `f` so that `f` reaches `target`, with the freedom
    /// its record leaves; false when no fragment applies (yet).
    pub(super) fn move_point(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        if !rec.movable() {
            return false;
        }
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let fname = self.name(f);
        let turns = matches!(rec.turn, Turn::Free | Turn::Axis { .. });
        match (rec.trans, target) {
            // Free to translate: onto the point, or by the least motion onto the locus.
            (Trans::Free, target) => {
                let from = self.point(f);
                let (to, explain) = match target {
                    Target::Point(x) => (
                        x,
                        format!(
                            "{names} is free to translate: translate it so that {fname} lands on {} ({c}).",
                            self.word(x)
                        ),
                    ),
                    Target::On(locus) => {
                        let words = format!("the point of {} nearest {fname}", self.word(locus.reg()));
                        let to = self.value(
                            Op::Nearest {
                                locus: locus.reg(),
                                point: from,
                            },
                            Ty::Point,
                            words,
                        );
                        (
                            to,
                            format!(
                                "{names} is free to translate: translate it by the least motion that puts {fname} on {} ({c}).",
                                self.word(locus.reg())
                            ),
                        )
                    }
                };
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.placed(k, f, to, target);
                true
            }
            // Held on a locus: slide along it (shifted to `f` when the feature held is
            // another, which only a turn about an axis through both leaves there) to where it
            // meets the target.
            (Trans::On { feature: g, locus }, target)
                if g == f || !turns || self.on_turn_axis(&rec, g, f) =>
            {
                let from = self.point(f);
                let own = if g == f {
                    locus
                } else {
                    self.shifted(locus, g, f)
                };
                // The grounded point's second and third, on the line and plane holding them.
                let held = g == f
                    && (self.plan.grounded_direction.is_some_and(|(_, b)| b == f)
                        || self.plan.grounded_plane == Some(f));
                let Some(met) = self.meet_held(own, target, from, r, held) else {
                    return false;
                };
                let to = match met {
                    Target::Point(x) => x,
                    Target::On(curve) => {
                        let words =
                            format!("the point of {} nearest {fname}", self.word(curve.reg()));
                        self.value(
                            Op::Nearest {
                                locus: curve.reg(),
                                point: from,
                            },
                            Ty::Point,
                            words,
                        )
                    }
                };
                let explain = format!(
                    "{names} can only move {} on {}: slide it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(locus.reg()),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.placed(k, f, to, met);
                true
            }
            // Held on a line and turning about an axis through the held feature, onto a plane
            // across that axis: the turn keeps f's height along the axis and the slide sets it,
            // so the plane fixes the slide and leaves the turn (a turn onto the plane would
            // sweep a circle parallel to it). Slide to where f's line meets the plane; the
            // cluster then turns about the axis through the held feature, now still. A line
            // across the axis is degenerate: it never changes the height.
            (
                Trans::On {
                    feature: g,
                    locus: Locus::Line(line),
                },
                Target::On(Locus::Plane(plane)),
            ) if self.across_turn_axis(&rec, plane) => {
                let from = self.point(f);
                let own = self.shifted(Locus::Line(line), g, f);
                let Some(Target::Point(to)) = self.meet(own, target, from, r) else {
                    return false;
                };
                let explain = format!(
                    "{names} can only move {} on {} and turn about an axis through it across {}: slide it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(line),
                    self.word(plane),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let at = self.point(g);
                self.clusters[k].record.trans = Trans::Pivot { at, feature: g };
                self.insert_known(g, at);
                true
            }
            // A segment of free length, one end held: the other end reaches a point by a turn
            // about the held end and a new length.
            (Trans::Pivot { at, feature: g }, Target::Point(x))
                if rec.shape == (Shape::Segment { sized: false })
                    && rec.turn == Turn::Free
                    && g != f =>
            {
                self.span(k, (g, at), x, r)
            }
            // About a pivot, free to turn: f is on the sphere about the pivot through it.
            (Trans::Pivot { at, feature: g }, target) if rec.turn == Turn::Free && g != f => {
                let from = self.point(f);
                let sphere = self.pivot_sphere(at, g, f, from);
                let Some(Target::Point(to)) = self.meet(Locus::Sphere(sphere), target, from, r)
                else {
                    return false;
                };
                let explain = format!(
                    "{names} may only rotate about {}: rotate it about {} around the normal of the plane through {}, {fname} and {} so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(at),
                    self.word(at),
                    self.word(to),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Shortest,
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let words = format!("the line from {} through {fname}", self.name(g));
                let axis = self.value(Op::DirectionTo { from: at, to }, Ty::Vector, words);
                self.clusters[k].record.turn = Turn::Axis {
                    axis,
                    feature: None,
                };
                true
            }
            // About a pivot and an axis: f is on the circle it sweeps about the axis.
            (Trans::Pivot { at, feature: g }, target) if g != f => {
                let Turn::Axis { axis, .. } = rec.turn else {
                    return false;
                };
                let from = self.point(f);
                let orbit = self.orbit(at, axis, f, from);
                let Some(Target::Point(to)) = self.meet(Locus::Circle(orbit), target, from, r)
                else {
                    return false;
                };
                let explain = format!(
                    "{names} may only rotate about the axis through {} along {}: rotate it by the angle between the perpendiculars from {fname} and {} to the axis ({c}).",
                    self.word(at),
                    self.word(axis),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Along(axis),
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.turn = Turn::Known;
                rec.trans = Trans::Fixed;
                true
            }
            // A segment free to turn, one end held on a plane, the other to a plane parallel
            // to it: turned about the held end (which keeps its plane) onto where its sphere
            // meets the other plane. Both ends then keep their planes as the segment slides
            // on the first and turns about the planes' normal, all the turn left to it
            // (turning about itself moves nothing); a shifted plane would only meet the other
            // in the plane itself, or nowhere. A free length must not tilt the segment: so
            // the same plane, or a segment whose length is set (a default gives it first).
            (
                Trans::On {
                    feature: g,
                    locus: Locus::Plane(held),
                },
                Target::On(Locus::Plane(onto)),
            ) if rec.turn == Turn::Free && self.ends_of_one_segment(g, f) => {
                let Some((normal, same)) = self.common_normal(held, onto) else {
                    return false;
                };
                if !same && rec.shape.size_free() {
                    return false;
                }
                let at = self.point(g);
                let from = self.point(f);
                let sphere = self.pivot_sphere(at, g, f, from);
                let Some(Target::On(curve)) = self.meet(Locus::Sphere(sphere), target, from, r)
                else {
                    return false;
                };
                let words = format!("the point of {} nearest {fname}", self.word(curve.reg()));
                let to = self.value(
                    Op::Nearest {
                        locus: curve.reg(),
                        point: from,
                    },
                    Ty::Point,
                    words,
                );
                let explain = format!(
                    "{names} can only move {} on {}, and may rotate about it: rotate it about {} around the normal of the plane through {}, {fname} and {} so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(held),
                    self.word(at),
                    self.word(at),
                    self.word(to),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Shortest,
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.turn = Turn::Axis {
                    axis: normal,
                    feature: None,
                };
                true
            }
            _ => false,
        }
    }

    /// Whether point features `g` and `f` are the two ends of one segment.
    fn ends_of_one_segment(&self, g: GeomId, f: GeomId) -> bool {
        use gcs_lang::model::{Owner, Part};
        match (&self.model.geoms[g].owner, &self.model.geoms[f].owner) {
            (Owner::Part(s, a), Owner::Part(t, b)) => {
                s == t
                    && self.model.geoms[*s].kind == gcs_lang::model::GeomKind::Segment
                    && matches!((a, b), (Part::Start, Part::End) | (Part::End, Part::Start))
            }
            _ => false,
        }
    }

    /// The unit normal two plane registers share, when they are parallel by construction:
    /// built with the same normal (or the same direction feature's), one possibly a plane
    /// moved parallel to a plane so built; and whether they are one plane (built alike).
    fn common_normal(&self, a: Reg, b: Reg) -> Option<(Reg, bool)> {
        let normal = |mut p: Reg| loop {
            match self.def(p)?.op {
                Op::Spatial(SpatialOp::Plane { normal, .. }) => return Some(normal),
                Op::Spatial(SpatialOp::ParallelPlane { plane, .. }) => p = plane,
                _ => return None,
            }
        };
        let (na, nb) = (normal(a)?, normal(b)?);
        let feature = |n: Reg| match self.def(n).map(|s| &s.op) {
            Some(Op::DirOf(g)) => Some(*g),
            _ => None,
        };
        let shared = na == nb || matches!((feature(na), feature(nb)), (Some(x), Some(y)) if x == y);
        if !shared {
            return None;
        }
        let built = |p: Reg| match self.def(p).map(|s| &s.op) {
            Some(Op::Spatial(plane @ SpatialOp::Plane { .. })) => Some(plane.clone()),
            _ => None,
        };
        Some((na, a == b || built(a).is_some_and(|x| built(b) == Some(x))))
    }

    /// Whether a record turns about an axis to which plane register `plane` is square by
    /// construction (its normal a measure of the axis' direction), so that the turn keeps
    /// every point's height over the plane.
    pub(super) fn across_turn_axis(&self, rec: &Record, plane: Reg) -> bool {
        let Turn::Axis { axis, feature } = rec.turn else {
            return false;
        };
        let mut p = plane;
        let normal = loop {
            match self.def(p).map(|s| &s.op) {
                Some(Op::Spatial(SpatialOp::Plane { normal, .. })) => break *normal,
                Some(Op::Spatial(SpatialOp::ParallelPlane { plane, .. })) => p = *plane,
                _ => return false,
            }
        };
        self.parallel_by_construction(axis, normal)
            || matches!((feature, self.dir_feature(normal)), (Some(a), Some(n))
                if a == n || same_direction(self.model, a, n))
    }

    /// Whether direction registers `a` and `b` are parallel by construction: measures of one
    /// direction feature (or of two parallel in one body), either possibly reversed or
    /// aligned with another direction.
    fn parallel_by_construction(&self, a: Reg, b: Reg) -> bool {
        let (a, b) = (self.dir_root(a), self.dir_root(b));
        a == b
            || matches!((self.dir_feature(a), self.dir_feature(b)), (Some(x), Some(y))
                if x == y || same_direction(self.model, x, y))
    }

    /// Direction register `d` with its reversals and alignments taken off.
    fn dir_root(&self, mut d: Reg) -> Reg {
        loop {
            match self.def(d).map(|s| &s.op) {
                Some(Op::Spatial(SpatialOp::Opposite(x)))
                | Some(Op::Spatial(SpatialOp::Aligned { dir: x, .. })) => d = *x,
                _ => return d,
            }
        }
    }

    /// The direction feature direction register `d` measures, through reversals and
    /// alignments.
    fn dir_feature(&self, d: Reg) -> Option<GeomId> {
        match self.def(self.dir_root(d)).map(|s| &s.op) {
            Some(Op::DirOf(g)) => Some(*g),
            _ => None,
        }
    }

    /// Whether a record's turn is about an axis through its feature `g` on which `f` lies too,
    /// so that the turn moves neither.
    fn on_turn_axis(&self, rec: &Record, g: GeomId, f: GeomId) -> bool {
        matches!(rec.turn, Turn::Axis { feature: Some(a), .. } if on_axis(self.model, g, a, f))
    }

    /// The record of cluster `k` once its feature `f` is at `to`, which is `target`'s point or
    /// the nearest point of `target`'s locus.
    pub(super) fn placed(&mut self, k: usize, f: GeomId, to: Reg, target: Target) {
        let turns = matches!(self.clusters[k].record.turn, Turn::Free | Turn::Axis { .. });
        let plane = self.clusters[k].record.shape == Shape::Plane;
        let line = self.clusters[k].record.shape == Shape::Line;
        let trans = match target {
            // A plane put on a plane parallel to it is placed: sliding within itself is no
            // motion of it.
            Target::On(Locus::Plane(_)) if plane => Trans::Fixed,
            // A line's point put on the line along its known direction through a point: the
            // line is placed (its only way there, `action`'s point on a moving line).
            Target::On(Locus::Line(_)) if line => Trans::Fixed,
            Target::Point(_) if turns => Trans::Pivot { at: to, feature: f },
            Target::Point(_) => Trans::Fixed,
            Target::On(locus) => Trans::On { feature: f, locus },
        };
        self.clusters[k].record.trans = trans;
        if let Trans::Pivot { .. } | Trans::Fixed = trans {
            if self.point_known(f) {
                self.insert_known(f, to);
            }
        }
    }
}
