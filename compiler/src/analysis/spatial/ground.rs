//! Grounding a model of space in which nothing is fixed: one cluster is held where the sketch
//! has it; a point held so leaves the model free to turn about it, so the direction to the
//! next point and the plane of the next two are held as sketched too. The model is then
//! solved up to a rigid motion only.

use super::relation::Relation;
use super::{Locus, Shape, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, SpatialOp, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    /// Grounds a model in which nothing is fixed: the cluster with the most DOF (a point
    /// before a plane of as many: its turns are then held by the points related to it), then
    /// the first name, is held where the sketch has it.
    pub(super) fn ground_if_nothing_fixed(&mut self) {
        let mut best: Option<((usize, bool), String, usize)> = None;
        for (i, c) in self.clusters.iter().enumerate() {
            let rank = (c.record.dof(), c.record.shape == Shape::Point);
            let key = (rank, self.model.geoms[c.geoms[0]].name.clone());
            if best
                .as_ref()
                .is_none_or(|b| key.0 > b.0 || (key.0 == b.0 && key.1 < b.1))
            {
                best = Some((key.0, key.1, i));
            }
        }
        if let Some((_, _, i)) = best {
            // Held where the sketch places it, but not sized: a segment's length or a
            // circle's radius is no part of a placement (as in the plane), and stays free.
            let shape = self.clusters[i].record.shape;
            self.clusters[i].record.hold();
            self.clusters[i].record.shape = shape;
            self.plan.grounded = Some(self.clusters[i].geoms[0]);
            if self.clusters[i].record.turn == Turn::None {
                self.ground_turns(i);
            }
        }
    }

    /// A point held at its sketch leaves the model free to turn about it (three DOF): hold
    /// the direction to the first free point related to it (in name order) as the sketch
    /// has it (two), and the plane of those two and the next free point related to either
    /// (one), so that the model is solved up to a rigid motion only.
    fn ground_turns(&mut self, i: usize) {
        let free = |s: &Self, k: usize| {
            s.clusters[k].record.trans == Trans::Free && s.clusters[k].record.movable()
        };
        // The first pending point-point relation from the held clusters to a free one.
        let next = |s: &Self, held: &[usize]| -> Option<(GeomId, GeomId)> {
            s.pending.iter().find_map(|r| {
                // A coincidence has no direction (nor a plane): a zero vector.
                let Relation::PointPoint { a, b, d: Some(_) } = r.relation else {
                    return None;
                };
                let (ka, kb) = (s.cluster(a), s.cluster(b));
                if held.contains(&ka) && !held.contains(&kb) && free(s, kb) {
                    Some((a, b))
                } else if held.contains(&kb) && !held.contains(&ka) && free(s, ka) {
                    Some((b, a))
                } else {
                    None
                }
            })
        };
        let Some((at, other)) = next(self, &[i]) else {
            return;
        };
        let (a, o) = (self.point(at), self.point(other));
        let (an, on) = (self.name(at), self.name(other));
        let words = format!("the direction from {an} to {on} in the sketch");
        let d = self.value(Op::DirectionTo { from: a, to: o }, Ty::Vector, words);
        let line = self.line(a, d, format!("the line from {an} through {on} as sketched"));
        let k = self.cluster(other);
        self.clusters[k].record.trans = Trans::On {
            feature: other,
            locus: Locus::Line(line),
        };
        self.plan.grounded_direction = Some((at, other));
        let Some((_, third)) = next(self, &[i, k]) else {
            return;
        };
        let t = self.point(third);
        let tn = self.name(third);
        let words = format!("the normal of the plane through {an}, {on} and {tn} in the sketch");
        let n = self.value(SpatialOp::PlaneNormal { a, b: o, c: t }, Ty::Vector, words);
        let words = format!("the plane through {an}, {on} and {tn} as sketched");
        let plane = self.value(
            SpatialOp::Plane {
                point: a,
                normal: n,
                offset: None,
            },
            Ty::Plane,
            words,
        );
        let k = self.cluster(third);
        self.clusters[k].record.trans = Trans::On {
            feature: third,
            locus: Locus::Plane(plane),
        };
        self.plan.grounded_plane = Some(third);
    }
}
