//! Sizes of space: a segment's length, a circle's radius. While free, a move that scales sets
//! it (`set_size`, `span`: a segment held at one end turned and sized to reach a point); a new
//! length keeps a segment's start, so an end held elsewhere is moved back (`resize`).

use super::{Rel, Shape, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reg, RotationAxis, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Part};

impl Builder<'_, Spatial> {
    /// The size of a segment or circle: its length or radius, as it is now.
    pub(super) fn size_of(&mut self, g: GeomId) -> Reg {
        let what = if self.model.geoms[g].kind == GeomKind::Circle {
            "radius"
        } else {
            "length"
        };
        let words = format!("the {what} of {}", self.name(g));
        self.value(Op::DimOf(g), Ty::Scalar, words)
    }

    /// Segment or circle `seg` of free size takes size `length`: a segment keeps its start
    /// (when its end is the point held, it moves back so that the end stays), a circle its
    /// centre. It is then rigid.
    pub(super) fn set_size(&mut self, seg: GeomId, length: Reg, r: &Rel) -> bool {
        let k = self.cluster(seg);
        let rec = self.clusters[k].record.clone();
        if !rec.shape.size_free() || self.clusters[k].geoms != [seg] {
            return false;
        }
        let (sname, c) = (self.name(seg), self.cname(r.constraint));
        let what = match rec.shape {
            Shape::Circle { .. } => "radius",
            _ => "length",
        };
        let held_end = self.held_end(k, seg);
        let explain = format!(
            "{sname}'s {what} is free: give it {} ({c}).",
            self.word(length)
        );
        let satisfies = self.satisfies(r);
        self.resize(seg, length, held_end, explain, satisfies);
        self.clusters[k].record.shape = rec.shape.sized();
        true
    }

    /// The end of segment `seg` (of cluster `k`) that its record holds at a point or on a
    /// locus, and where it is: a new length keeps the start, so that end must be moved back
    /// (else it leaves its locus).
    pub(super) fn held_end(&mut self, k: usize, seg: GeomId) -> Option<(GeomId, Reg)> {
        let end = self.model.part(seg, Part::End);
        match self.clusters[k].record.trans {
            Trans::Pivot { at, feature } if Some(feature) == end => Some((feature, at)),
            Trans::On { feature, .. } if Some(feature) == end => {
                Some((feature, self.point(feature)))
            }
            _ => None,
        }
    }

    /// Sets segment `seg`'s length to `length` (which keeps its start), then, when its end is
    /// the point held (`held_end`: the end, and where), moves it back there. The last step
    /// satisfies `satisfies`.
    pub(super) fn resize(
        &mut self,
        seg: GeomId,
        length: Reg,
        held_end: Option<(GeomId, Reg)>,
        explain: String,
        satisfies: Vec<ConstraintId>,
    ) {
        let (now, after) = if held_end.is_none() {
            (satisfies, Vec::new())
        } else {
            (Vec::new(), satisfies)
        };
        self.emit(
            Op::SetDim {
                geom: seg,
                value: length,
            },
            None,
            now,
            explain,
        );
        if let Some((end, at)) = held_end {
            // Measured anew: the record still holds the end at `at`, where this brings it.
            let words = format!("{} after the new length", self.name(end));
            let from = self.value(Op::PointOf(end), Ty::Point, words);
            let explain = format!(
                "... and move it back so that {} is at {}.",
                self.name(end),
                self.word(at)
            );
            self.emit(
                Op::Translate {
                    geoms: vec![seg],
                    from,
                    to: at,
                },
                None,
                after,
                explain,
            );
        }
    }

    /// Segment cluster `k`, its end `g` held at `at`, its other end to reach `x`: it turns
    /// about `at` so that it points from the start toward the end's place, takes the length
    /// between them, and (when the end held is its end, not its start, which a new length
    /// would move) moves back so that `g` is at `at`. It is then placed.
    pub(super) fn span(&mut self, k: usize, (g, at): (GeomId, Reg), x: Reg, r: &Rel) -> bool {
        let seg = self.clusters[k].geoms[0];
        let (Some(start), Some(dir)) = (
            self.model.part(seg, Part::Start),
            self.model.part(seg, Part::Dir),
        ) else {
            return false;
        };
        let held_start = g == start;
        let (from_pt, to_pt) = if held_start { (at, x) } else { (x, at) };
        let (sname, c) = (self.name(seg), self.cname(r.constraint));
        let words = format!(
            "the direction from {} to {}",
            self.word(from_pt),
            self.word(to_pt)
        );
        let target = self.value(
            Op::DirectionTo {
                from: from_pt,
                to: to_pt,
            },
            Ty::Vector,
            words,
        );
        let d = self.direction(dir);
        let explain = format!(
            "{sname}'s length is free: rotate it about {} so that it points from {} to {} ({c}) ...",
            self.word(at),
            self.word(from_pt),
            self.word(to_pt)
        );
        self.emit(
            Op::RotateDir {
                geoms: vec![seg],
                pivot: at,
                axis: RotationAxis::Shortest,
                from: d,
                to: target,
            },
            None,
            Vec::new(),
            explain,
        );
        let words = format!(
            "the distance from {} to {}",
            self.word(from_pt),
            self.word(to_pt)
        );
        let length = self.value(
            Op::Along {
                from: from_pt,
                dir: target,
                to: to_pt,
            },
            Ty::Scalar,
            words,
        );
        let explain = "... and give it the length between them.".to_string();
        let held_end = (!held_start).then_some((g, at));
        let satisfies = self.satisfies(r);
        self.resize(seg, length, held_end, explain, satisfies);
        let rec = &mut self.clusters[k].record;
        rec.shape = Shape::Segment { sized: true };
        rec.turn = Turn::Known;
        rec.trans = Trans::Fixed;
        true
    }
}
