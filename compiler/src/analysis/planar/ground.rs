//! Grounding a model of the plane in which nothing is fixed: the geom with the most DOF is
//! held where the sketch has it (only its position when horizontal and vertical constraints
//! anchor the rotation); a geom without orientation held so leaves the model free to turn
//! about it, so the direction to the next point is held as sketched too. The model is then
//! solved up to a rigid motion only.

use super::relation::{Dir, Relation};
use super::{Locus, Planar, Pos, Rot};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, Ty};
use gcs_lang::model::{GeomId, GeomKind, Part};

impl Builder<'_, Planar> {
    /// Grounds a model with nothing fixed: holds the geom with the most DOF (then the first
    /// name) at its sketch, so that the rest is solved relative to it.
    pub(super) fn ground_if_nothing_fixed(&mut self) {
        // Deterministically: the geom with the most DOF, then the first name.
        let mut best: Option<(usize, String, usize)> = None;
        for (i, c) in self.clusters.iter().enumerate() {
            let key = (c.record.dof(), self.model.geoms[c.geoms[0]].name.clone());
            if best
                .as_ref()
                .is_none_or(|b| key.0 > b.0 || (key.0 == b.0 && key.1 < b.1))
            {
                best = Some((key.0, key.1, i));
            }
        }
        // Horizontal and vertical constraints refer to the world's axes: they anchor the
        // rotation, so only the position of the chosen geom is held.
        let anchored = self.pending.iter().any(|r| {
            matches!(
                r.relation,
                Relation::Angle {
                    u: Dir::World(..),
                    ..
                } | Relation::Angle {
                    v: Dir::World(..),
                    ..
                }
            )
        });
        if let Some((_, _, i)) = best {
            if anchored && self.clusters[i].record.rot == Rot::Free {
                if let Some(f) = self.first_point_feature(i) {
                    let at = self.point(f);
                    self.clusters[i].record.pos = Pos::Pivot { at, feature: f };
                    self.insert_known(f, at);
                    self.plan.grounded = Some(self.clusters[i].geoms[0]);
                    return;
                }
            }
            let had_rotation = self.clusters[i].record.rot == Rot::Free;
            self.clusters[i].record.hold();
            self.plan.grounded = Some(self.clusters[i].geoms[0]);
            if !had_rotation {
                self.ground_direction(i);
            }
        }
    }

    /// The first point feature of a cluster: a line's base, a segment's start, a body's first
    /// point or marker.
    pub(super) fn first_point_feature(&self, k: usize) -> Option<GeomId> {
        let g = *self.clusters[k].geoms.first()?;
        match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Point => Some(g),
            GeomKind::Segment => self.model.part(g, Part::Start),
            GeomKind::Circle => self.model.part(g, Part::Center),
            GeomKind::Body => self.model.geoms[g]
                .parts
                .iter()
                .copied()
                .find(|&m| self.model.geoms[m].kind.is_pointlike()),
            _ => None,
        }
    }

    /// A geom without orientation (a point, a circle) held at its sketch leaves the model free
    /// to turn about it: hold the direction to the first point related to it (in name order)
    /// as the sketch has it too, so that the model is solved up to a rigid motion only.
    fn ground_direction(&mut self, i: usize) {
        let held = |s: &Self, f: GeomId| s.cluster(f) == i;
        let mut pair = None;
        for r in &self.pending {
            // A coincidence has no direction: the direction to a point held on the grounded
            // one would be that of a zero vector.
            if let Relation::PointPoint { a, b, d: Some(_) } = r.relation {
                let (ka, kb) = (self.cluster(a), self.cluster(b));
                if held(self, a) && kb != i && self.clusters[kb].record.pos == Pos::Free {
                    pair = Some((a, b));
                } else if held(self, b) && ka != i && self.clusters[ka].record.pos == Pos::Free {
                    pair = Some((b, a));
                }
                if pair.is_some() {
                    break;
                }
            }
        }
        let Some((at, other)) = pair else { return };
        let a = self.point(at);
        let o = self.point(other);
        let words = format!(
            "the direction from {} to {} in the sketch",
            self.name(at),
            self.name(other)
        );
        let d = self.value(Op::DirectionTo { from: a, to: o }, Ty::Vector, words);
        let words = format!(
            "the line from {} through {} as sketched",
            self.name(at),
            self.name(other)
        );
        let line = self.value(
            Op::Line {
                point: a,
                dir: d,
                offset: None,
            },
            Ty::Line,
            words,
        );
        let k = self.cluster(other);
        self.clusters[k].record.pos = Pos::On {
            feature: other,
            locus: Locus::Line(line),
        };
        self.plan.grounded_direction = Some((at, other));
    }
}
