//! Turning a direction onto a known one (`turn`), and lone lines placed by the known points
//! they pass: a line to pass a point at a distance slides onto the parallel at that offset
//! when its direction is known, or turns about its pivot (a branch); free to turn and move,
//! it records the point ([`Pass`]) until a second one gives its direction, or its direction
//! becomes known (`place_by_passes`).

use super::relation::{Dir, Relation};
use super::{
    depends_on_dim, pinned_at_midpoint, pivot_name, Locus, Pass, Planar, Pos, Rel, Rot, Target,
};
use crate::analysis::driver::Builder;
use crate::plan::{Op, PlanarOp, Reg, RotationAxis, Ty};
use gcs_lang::model::{GeomId, GeomKind, Part};

impl Builder<'_, Planar> {
    /// Turns the cluster of direction feature `v` so that it points along `target`.
    pub(super) fn turn(&mut self, v: GeomId, target: Reg, r: &Rel) -> bool {
        let k = self.cluster(v);
        let rec = self.clusters[k].record.clone();
        if rec.rot != Rot::Free {
            return false;
        }
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let (pivot, about) = match rec.pos {
            Pos::Pivot { at, feature } => (at, pivot_name(self.model, feature)),
            Pos::On { feature, .. } => (self.point(feature), self.name(feature)),
            _ => {
                let origin = geoms[0];
                (
                    self.point(origin),
                    format!("the origin of {}", self.name(origin)),
                )
            }
        };
        let from = self.dir(Dir::Feature(v));
        let explain = format!(
            "Rotate {names} about {about} so that {} points along {} ({c}). This fixes its rotation.",
            self.name(v),
            self.word(target)
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                axis: RotationAxis::Normal,
                from,
                to: target,
            },
            None,
            self.satisfies(r),
            explain,
        );
        let model = self.model;
        let rec = &mut self.clusters[k].record;
        rec.rot = Rot::Known;
        // Rotation known about a pivot: fixed, unless the pivot is a segment's end that its
        // free length still slides (the start then moves along the line), or the midpoint of
        // a segment of free length (both ends then move along the line).
        let sized_about_pivot = pinned_at_midpoint(model, rec).is_some();
        if matches!(rec.pos, Pos::Pivot { feature, .. } if !depends_on_dim(model, feature))
            && !sized_about_pivot
        {
            rec.pos = Pos::Fixed;
        }
        self.place_by_passes(k, v);
        true
    }

    /// A lone line whose direction has just become known, with a recorded [`Pass`]: moved
    /// across itself until it passes that point at its distance, which satisfies the
    /// recorded constraint.
    pub(super) fn place_by_passes(&mut self, k: usize, dir: GeomId) {
        let rec = &mut self.clusters[k].record;
        if rec.rot != Rot::Known || rec.pos != Pos::Free {
            return;
        }
        let Some(first) = rec.passes.first().copied() else {
            return;
        };
        rec.passes.clear();
        let Some(&base) = (self.clusters[k].geoms.first())
            .and_then(|&g| self.model.part(g, Part::BasePoint))
            .as_ref()
        else {
            return;
        };
        let dv = self.dir(Dir::Feature(dir));
        let offset = self.neg(first.d);
        let line = self.value(
            Op::Line {
                point: first.at,
                dir: dv,
                offset: Some(offset),
            },
            Ty::Line,
            format!(
                "the line along {} passing {} at its distance",
                self.name(dir),
                self.word(first.at)
            ),
        );
        let held = Rel {
            relation: Relation::PointLine {
                p: base,
                base,
                dir,
                d: None,
            },
            constraint: first.constraint,
            last: first.last,
            duplicate: false,
        };
        self.move_feature(base, Target::On(Locus::Line(line)), &held);
    }

    /// A point feature `p` is known; the line (`base`, `dir`) of another cluster must pass at
    /// signed distance `d` from it.
    pub(super) fn move_line_to_point(
        &mut self,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(base);
        let rec = self.clusters[k].record.clone();
        if let (Pos::Pivot { at: pivot, feature }, Rot::Free) = (rec.pos, rec.rot) {
            // Turning about a known point: the line's direction is one of the two that pass
            // `p` at the distance (a free length, which slides an end along the line, moves
            // neither the line nor the pivot).
            return self.turn_line_past(pivot, feature, p, base, dir, d, r);
        }
        if rec.free_dim.is_some() && (rec.rot != Rot::Known || depends_on_dim(self.model, base)) {
            return false;
        }
        let at = self.point(p);
        if rec.rot == Rot::Known {
            // Its direction is known: the base must lie on the parallel at the right offset.
            let dv = self.dir(Dir::Feature(dir));
            let offset = d.map(|d| self.neg(d));
            let words = format!(
                "the line along {} placing {} at the right distance",
                self.name(dir),
                self.name(p)
            );
            let line = self.value(
                Op::Line {
                    point: at,
                    dir: dv,
                    offset,
                },
                Ty::Line,
                words,
            );
            let moved = self.move_feature(base, Target::On(Locus::Line(line)), r);
            let rec = &mut self.clusters[k].record;
            if moved && matches!(rec.pos, Pos::On { feature, .. } if feature == base) {
                rec.along = Some(dir);
            }
            return moved;
        }
        if rec.line
            && rec.pos == Pos::Free
            && rec.rot == Rot::Free
            && (d.is_some() || !rec.passes.is_empty())
        {
            // A lone line free to turn and move, passing a known point at a distance: record
            // it; with a second, the line's direction is the one that passes the second point
            // at the difference of the distances from the first.
            let d = match d {
                Some(d) => d,
                None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
            };
            let pass = Pass {
                at,
                d,
                constraint: r.constraint,
                last: r.last,
            };
            let Some(&first) = rec.passes.first() else {
                self.clusters[k].record.passes.push(pass);
                return true;
            };
            let offset = self.sum(vec![(1.0, d), (-1.0, first.d)]);
            let dv = self.dir(Dir::Feature(dir));
            let (pn, dn) = (self.name(p), self.name(dir));
            let from = self.word(first.at);
            let branch = self.branch(
                r.constraint,
                vec![
                    format!("{pn} ahead of {from} along {dn}"),
                    format!("{pn} behind {from} along {dn}"),
                ],
            );
            let to = self.value(
                PlanarOp::PassingDir {
                    pivot: first.at,
                    base: first.at,
                    dir: dv,
                    point: at,
                    offset: Some(offset),
                    branch,
                    constraint: r.constraint,
                },
                Ty::Vector,
                format!("the direction of {dn} that passes {pn} and {from} at their distances"),
            );
            return self.turn(dir, to, r);
        }
        if rec.line && d.is_none() && rec.pos == Pos::Free {
            // A lone line with free direction through a known point: slide its base there.
            return self.move_feature(base, Target::Point(at), r);
        }
        false
    }

    /// Turns the cluster of line (`base`, `dir`), which may only rotate about `pivot` (at
    /// feature `about`), until the line passes known point `p` at signed distance `d` (none:
    /// through it): a line through a point tangent to a circle, a slotted link through a pin.
    /// Two directions do; a branch variable says which, `p` ahead of the pivot along the line
    /// or behind it, as in the sketch.
    #[allow(clippy::too_many_arguments)]
    fn turn_line_past(
        &mut self,
        pivot: Reg,
        about: GeomId,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let point = self.point(p);
        let bp = self.point(base);
        let dv = self.dir(Dir::Feature(dir));
        // The pivot as the plan knows it (a line's own point is named after the line).
        let an = if self.model.geoms[about].kind == GeomKind::Line {
            self.word(pivot)
        } else {
            self.name(about)
        };
        let (pn, dn) = (self.name(p), self.name(dir));
        let branch = self.branch(
            r.constraint,
            vec![
                format!("{pn} ahead of {an} along {dn}"),
                format!("{pn} behind {an} along {dn}"),
            ],
        );
        let words = match d {
            Some(o) => format!("the direction of {dn} that passes {pn} at {}", self.word(o)),
            None => format!("the direction of {dn} that passes through {pn}"),
        };
        let to = self.value(
            PlanarOp::PassingDir {
                pivot,
                base: bp,
                dir: dv,
                point,
                offset: d,
                branch,
                constraint: r.constraint,
            },
            Ty::Vector,
            words,
        );
        self.turn(dir, to, r)
    }
}
