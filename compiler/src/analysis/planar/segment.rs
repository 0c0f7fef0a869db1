//! Plan fragments for segments of free length: moves that scale (paper 002: a segment's
//! signatures include its length). While the length is free, a segment's end moves with it;
//! these fragments pin the end, or place it along the segment's line and set the length.

use super::{Dir, Planar, Pos, Rel, Rot, Target};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reg, RotationAxis, Ty};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part};

impl Builder<'_, Planar> {
    /// The fragments of a lone segment whose length is free, for a target on its start or end.
    /// `None` when they do not concern `f`; `Some(false)` when no fragment applies yet.
    pub(super) fn segment_fragment(&mut self, f: GeomId, target: Target, r: &Rel) -> Option<bool> {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let seg = rec.free_dim?;
        if self.model.geoms[seg].kind != GeomKind::Segment || self.clusters[k].geoms.len() != 1 {
            return None;
        }
        let (start, end, dir) = (
            self.model.part(seg, Part::Start)?,
            self.model.part(seg, Part::End)?,
            self.model.part(seg, Part::Dir)?,
        );
        let is_end = matches!(self.model.geoms[f].owner, Owner::Part(_, Part::End));
        let geoms = vec![seg];
        let name = self.name(seg);
        let c = self.cname(r.constraint);
        match (is_end, rec.rot, rec.pos, target) {
            // The end reaches a point while the segment is free to translate: translate it
            // there and keep the length free; the end is now pinned.
            (true, _, Pos::Free, Target::Point(x)) => {
                let from = self.point(end);
                let explain = format!("{name} is free to translate: translate it so that {} lands on {} ({c}); its length stays free.", self.name(end), self.word(x));
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Pivot {
                    at: x,
                    feature: end,
                };
                self.insert_known(end, x);
                Some(true)
            }
            // Start and direction known: the end runs along the line; the target fixes where,
            // and the length follows.
            (true, Rot::Known, _, target) if self.point_known(start) => {
                let s = self.point(start);
                let d = self.dir(Dir::Feature(dir));
                let words = format!("the line of {name}");
                let line = self.value(
                    Op::Line {
                        point: s,
                        dir: d,
                        offset: None,
                    },
                    Ty::Line,
                    words,
                );
                let near = self.point(end);
                let x = self.meet(line, target, near, r);
                let words = format!("the distance from {} to {}", self.name(start), self.word(x));
                let len = self.value(
                    Op::Along {
                        from: s,
                        dir: d,
                        to: x,
                    },
                    Ty::Scalar,
                    words,
                );
                let explain = format!(
                    "Scale {name} about {} so that {} reaches {} ({c}).",
                    self.name(start),
                    self.name(end),
                    self.word(x)
                );
                self.emit(
                    Op::SetDim {
                        geom: seg,
                        value: len,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.finish_length(k, seg);
                Some(true)
            }
            // Start known, direction free: turn towards the target point and scale.
            (true, Rot::Free, Pos::Pivot { at, feature }, Target::Point(x)) if feature == start => {
                let d = self.dir(Dir::Feature(dir));
                let words = format!(
                    "the direction from {} to {}",
                    self.name(start),
                    self.word(x)
                );
                let to = self.value(Op::DirectionTo { from: at, to: x }, Ty::Vector, words);
                let explain = format!(
                    "Rotate {name} about {} towards {}.",
                    self.name(start),
                    self.word(x)
                );
                self.emit(
                    Op::RotateDir {
                        geoms: geoms.clone(),
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from: d,
                        to,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                let words = format!("the distance from {} to {}", self.name(start), self.word(x));
                let len = self.value(
                    Op::Along {
                        from: at,
                        dir: to,
                        to: x,
                    },
                    Ty::Scalar,
                    words,
                );
                let explain = format!(
                    "Scale {name} so that {} lands on {} ({c}).",
                    self.name(end),
                    self.word(x)
                );
                self.emit(
                    Op::SetDim {
                        geom: seg,
                        value: len,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.rot = Rot::Known;
                self.clusters[k].record.pos = Pos::Fixed;
                self.finish_length(k, seg);
                Some(true)
            }
            // End pinned, direction free: turn about the end so that the line runs from the
            // target point to it; the start then reaches the target as below.
            (false, Rot::Free, Pos::Pivot { at, feature }, Target::Point(x))
                if feature == end && f == start =>
            {
                let d = self.dir(Dir::Feature(dir));
                let words = format!("the direction from {} to {}", self.word(x), self.name(end));
                let to = self.value(Op::DirectionTo { from: x, to: at }, Ty::Vector, words);
                let explain = format!(
                    "Rotate {name} about {} so that it points from {} to it.",
                    self.name(end),
                    self.word(x)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from: d,
                        to,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                self.clusters[k].record.rot = Rot::Known;
                self.segment_fragment(f, target, r)
            }
            // End pinned and direction known: the start runs along the line through the end;
            // the target fixes where, the length follows.
            (false, Rot::Known, Pos::Pivot { at, feature }, target)
                if feature == end && f == start =>
            {
                let d = self.dir(Dir::Feature(dir));
                let words = format!("the line of {name} through {}", self.name(end));
                let line = self.value(
                    Op::Line {
                        point: at,
                        dir: d,
                        offset: None,
                    },
                    Ty::Line,
                    words,
                );
                let near = self.point(start);
                let x = self.meet(line, target, near, r);
                let explain = format!(
                    "{name}'s end is pinned at {}: translate it so that {} reaches {} ...",
                    self.word(at),
                    self.name(start),
                    self.word(x)
                );
                self.emit(
                    Op::Translate {
                        geoms,
                        from: near,
                        to: x,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                let words = format!("the distance from {} to {}", self.word(x), self.name(end));
                let len = self.value(
                    Op::Along {
                        from: x,
                        dir: d,
                        to: at,
                    },
                    Ty::Scalar,
                    words,
                );
                let explain = format!(
                    "... and scale it so that its end is back on {} ({c}).",
                    self.word(at)
                );
                self.emit(
                    Op::SetDim {
                        geom: seg,
                        value: len,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
                self.finish_length(k, seg);
                Some(true)
            }
            _ if is_end || matches!(rec.pos, Pos::Pivot { feature, .. } if feature == end) => {
                Some(false)
            }
            _ => None,
        }
    }

    /// The end of a lone segment of free length that the length slides along a known line
    /// (its other end and its direction known), with that other end: `f` and where the line
    /// is anchored. `None` for any other feature.
    pub(super) fn sliding_end(&self, f: GeomId) -> Option<GeomId> {
        let k = self.cluster(f);
        let rec = &self.clusters[k].record;
        let seg = rec.free_dim?;
        if self.model.geoms[seg].kind != GeomKind::Segment
            || self.clusters[k].geoms.len() != 1
            || rec.rot != Rot::Known
        {
            return None;
        }
        let (start, end) = (
            self.model.part(seg, Part::Start)?,
            self.model.part(seg, Part::End)?,
        );
        if f == end && self.point_known(start) {
            Some(start)
        } else if f == start && matches!(rec.pos, Pos::Pivot { feature, .. } if feature == end) {
            Some(end)
        } else {
            None
        }
    }

    /// The line a [`Self::sliding_end`] runs along: through the known end along the segment.
    pub(super) fn sliding_line(&mut self, f: GeomId, anchor: GeomId) -> Reg {
        let seg = self.model.top_level_of(f);
        let dir = self.model.part(seg, Part::Dir).unwrap_or(seg);
        let at = self.point(anchor);
        let d = self.dir(Dir::Feature(dir));
        let words = format!(
            "the line of {} through {}",
            self.name(seg),
            self.name(anchor)
        );
        self.value(
            Op::Line {
                point: at,
                dir: d,
                offset: None,
            },
            Ty::Line,
            words,
        )
    }

    /// Moves [`Self::sliding_end`] `f` (anchored at `anchor`) to `x`, a point of its line: the
    /// length follows (and, for a start, the segment slides so that its end stays put).
    pub(super) fn slide_end_to(&mut self, f: GeomId, anchor: GeomId, x: Reg, r: &Rel, last: bool) {
        let c = self.cname(r.constraint);
        let satisfies = if last { self.satisfies(r) } else { Vec::new() };
        let k = self.cluster(f);
        let seg = self.model.top_level_of(f);
        let dir = self.model.part(seg, Part::Dir).unwrap_or(seg);
        let name = self.name(seg);
        let d = self.dir(Dir::Feature(dir));
        let at = self.point(anchor);
        let (fname, aname, to) = (self.name(f), self.name(anchor), self.word(x));
        let len = if matches!(self.model.geoms[f].owner, Owner::Part(_, Part::End)) {
            let words = format!("the distance from {aname} to {to}");
            self.value(
                Op::Along {
                    from: at,
                    dir: d,
                    to: x,
                },
                Ty::Scalar,
                words,
            )
        } else {
            let from = self.point(f);
            let explain = format!(
                "{name}'s end is pinned: translate it so that {fname} reaches {to} ({c}) ..."
            );
            self.emit(
                Op::Translate {
                    geoms: vec![seg],
                    from,
                    to: x,
                },
                None,
                Vec::new(),
                explain,
            );
            let words = format!("the distance from {to} to {aname}");
            self.value(
                Op::Along {
                    from: x,
                    dir: d,
                    to: at,
                },
                Ty::Scalar,
                words,
            )
        };
        let explain = if matches!(self.model.geoms[f].owner, Owner::Part(_, Part::End)) {
            format!("Scale {name} about {aname} so that {fname} reaches {to} ({c}).")
        } else {
            format!("... and scale it so that its end is back on {aname} ({c}).")
        };
        self.emit(
            Op::SetDim {
                geom: seg,
                value: len,
            },
            None,
            satisfies,
            explain,
        );
        self.clusters[k].record.pos = Pos::Fixed;
        self.finish_length(k, seg);
    }

    fn finish_length(&mut self, k: usize, seg: GeomId) {
        let rec = &mut self.clusters[k].record;
        rec.free_dim = None;
        rec.fixed_dims.push(seg);
    }
}
