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
        if let Some((at, _)) = super::pinned_at_midpoint(self.model, &rec) {
            return Some(self.span_about_midpoint(seg, at, f, target, r));
        }
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
            // End pinned, direction free: the start reaches the target point, the segment
            // turns towards the end from there, and its length is what is left.
            (false, Rot::Free, Pos::Pivot { at, feature }, Target::Point(x))
                if feature == end && f == start =>
            {
                let d = self.dir(Dir::Feature(dir));
                let from = self.point(start);
                let words = format!("the direction from {} to {}", self.word(x), self.name(end));
                let to = self.value(Op::DirectionTo { from: x, to: at }, Ty::Vector, words);
                let explain = format!(
                    "{name}'s end is pinned at {}: translate it so that {} lands on {} ...",
                    self.word(at),
                    self.name(start),
                    self.word(x)
                );
                self.emit(
                    Op::Translate {
                        geoms: geoms.clone(),
                        from,
                        to: x,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                let explain = format!(
                    "... rotate it about {} towards {} ...",
                    self.name(start),
                    self.word(at)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot: x,
                        axis: RotationAxis::Normal,
                        from: d,
                        to,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                let words = format!("the distance from {} to {}", self.word(x), self.name(end));
                let len = self.value(
                    Op::Along {
                        from: x,
                        dir: to,
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
                let rec = &mut self.clusters[k].record;
                rec.rot = Rot::Known;
                rec.pos = Pos::Fixed;
                self.finish_length(k, seg);
                Some(true)
            }
            _ if is_end || matches!(rec.pos, Pos::Pivot { feature, .. } if feature == end) => {
                Some(false)
            }
            _ => None,
        }
    }

    /// A segment pinned at its midpoint `at` with its length free: its end `f` reaches the
    /// target, the other end its reflection through the midpoint. With its direction free the
    /// target must be a point (a locus leaves a freedom: not yet); with its direction known,
    /// the end meets the target on the segment's line.
    fn span_about_midpoint(
        &mut self,
        seg: GeomId,
        at: Reg,
        f: GeomId,
        target: Target,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(seg);
        let rot = self.clusters[k].record.rot;
        let (Some(start), Some(dir)) = (
            self.model.part(seg, Part::Start),
            self.model.part(seg, Part::Dir),
        ) else {
            return false;
        };
        let name = self.name(seg);
        let d = self.dir(Dir::Feature(dir));
        let x = match (rot, target) {
            (Rot::Free, Target::Point(x)) => x,
            (Rot::Known, target) => {
                let words = format!("the line of {name} through its midpoint");
                let line = self.value(
                    Op::Line {
                        point: at,
                        dir: d,
                        offset: None,
                    },
                    Ty::Line,
                    words,
                );
                let near = self.point(f);
                self.meet(line, target, near, r)
            }
            _ => return false,
        };
        let words = format!("{} reflected through the midpoint of {name}", self.word(x));
        let other = self.value(
            Op::Reflect {
                point: x,
                through: at,
            },
            Ty::Point,
            words,
        );
        let (a, b) = if f == start { (x, other) } else { (other, x) };
        let c = self.cname(r.constraint);
        let geoms = vec![seg];
        let from = self.point(start);
        let explain = format!(
            "{name} is pinned at its midpoint {}, its length free: translate it so that {} lands on {} ...",
            self.word(at),
            self.name(start),
            self.word(a)
        );
        self.emit(
            Op::Translate {
                geoms: geoms.clone(),
                from,
                to: a,
            },
            None,
            Vec::new(),
            explain,
        );
        let along = if rot == Rot::Free {
            let words = format!("the direction from {} to {}", self.word(a), self.word(b));
            let to = self.value(Op::DirectionTo { from: a, to: b }, Ty::Vector, words);
            let explain = format!(
                "... rotate it about {} towards {} ...",
                self.name(start),
                self.word(b)
            );
            self.emit(
                Op::RotateDir {
                    geoms,
                    pivot: a,
                    axis: RotationAxis::Normal,
                    from: d,
                    to,
                },
                None,
                Vec::new(),
                explain,
            );
            to
        } else {
            d
        };
        let words = format!("the distance from {} to {}", self.word(a), self.word(b));
        let len = self.value(
            Op::Along {
                from: a,
                dir: along,
                to: b,
            },
            Ty::Scalar,
            words,
        );
        let explain = format!(
            "... and size it so that its end lands on {} ({c}).",
            self.word(b)
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
        let rec = &mut self.clusters[k].record;
        rec.rot = Rot::Known;
        rec.pos = Pos::Fixed;
        self.finish_length(k, seg);
        true
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
