//! Turning a direction onto a known one (`turn`), and lone lines placed by the known points
//! they pass: a line to pass a point at a distance slides onto the parallel at that offset
//! when its direction is known, or turns about its pivot (a branch); free to turn and move,
//! it records the point ([`Pass`]) until a second one gives its direction, or its direction
//! becomes known (`place_by_passes`). Two rockers whose lines must be one (a prismatic joint
//! between them) turn onto a common tangent of the circles about their pivots
//! (`common_line`).

use super::relation::{AngleValue, Dir, Relation};
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

    /// Point `p` on line (`base`, `dir`) where each lies in a cluster that may only turn about
    /// a known pivot, and a pending relation keeps `p`'s cluster's direction `ax` along `dir`
    /// (a prismatic joint between two rockers: the inverted slider-crank). The line through
    /// `p` along `ax` is rigid in `p`'s cluster, so it passes that cluster's pivot at a known
    /// signed distance; once the two directions agree, the two lines are one. So the line's
    /// cluster turns about its pivot until its line passes the other pivot at that distance
    /// (the common tangent of two circles about the pivots, the offsets their radii: two
    /// roots, a branch); the pending angle then turns `p`'s cluster, which puts `p` on the
    /// line.
    pub(super) fn common_line(&mut self, p: GeomId, base: GeomId, dir: GeomId, r: &Rel) -> bool {
        let (kp, kl) = (self.cluster(p), self.cluster(base));
        if kp == kl {
            return false;
        }
        let (rp, rl) = (&self.clusters[kp].record, &self.clusters[kl].record);
        let (
            Pos::Pivot { at: pivot_p, .. },
            Pos::Pivot {
                at: pivot_l,
                feature: about,
            },
        ) = (rp.pos, rl.pos)
        else {
            return false;
        };
        if rp.rot != Rot::Free
            || rl.rot != Rot::Free
            || rp.free_dim.is_some()
            || rl.free_dim.is_some()
        {
            return false;
        }
        // The direction of `p`'s cluster a pending relation sets along `dir`.
        let along = |u: &Dir, v: &Dir| match (u, v) {
            (Dir::Feature(a), Dir::Feature(b)) if *b == dir => Some(*a),
            _ => None,
        };
        let ax = self.pending.iter().find_map(|q| match &q.relation {
            Relation::Angle {
                u,
                v,
                angle: AngleValue::Const(c),
            } if *c == 0.0 => along(u, v)
                .or_else(|| along(v, u))
                .filter(|&a| self.cluster(a) == kp),
            _ => None,
        });
        let Some(ax) = ax else {
            return false;
        };
        // The signed distance of `p`'s pivot from the line through `p` along `ax` (to its
        // left positive): what the common line's will be.
        let at = self.point(p);
        let axis = self.dir(Dir::Feature(ax));
        let words = format!("the left of {}", self.name(ax));
        let left = self.quarter_turned(axis, 1.0, words);
        let offset = self.value(
            Op::Along {
                from: at,
                dir: left,
                to: pivot_p,
            },
            Ty::Scalar,
            format!(
                "the distance of {} from the line through {} along {}",
                self.word(pivot_p),
                self.name(p),
                self.name(ax)
            ),
        );
        let name = self.word(pivot_p);
        self.turn_line_past_point(pivot_l, about, pivot_p, &name, base, dir, Some(offset), r)
    }

    /// Direction `dir` turned a quarter turn counter-clockwise (`sense` 1) or clockwise (-1).
    pub(super) fn quarter_turned(&mut self, dir: Reg, sense: f64, words: String) -> Reg {
        let quarter = self.value(
            Op::Const(sense * std::f64::consts::FRAC_PI_2),
            Ty::Scalar,
            if sense > 0.0 { "pi/2" } else { "-pi/2" }.into(),
        );
        self.value(
            PlanarOp::Rotated {
                dir,
                angle: quarter,
            },
            Ty::Vector,
            words,
        )
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
        let pn = self.name(p);
        self.turn_line_past_point(pivot, about, point, &pn, base, dir, d, r)
    }

    /// [`Self::turn_line_past`] to a known point `point`, called `pn`.
    #[allow(clippy::too_many_arguments)]
    fn turn_line_past_point(
        &mut self,
        pivot: Reg,
        about: GeomId,
        point: Reg,
        pn: &str,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let bp = self.point(base);
        let dv = self.dir(Dir::Feature(dir));
        // The pivot as the plan knows it (a line's own point is named after the line).
        let an = if self.model.geoms[about].kind == GeomKind::Line {
            self.word(pivot)
        } else {
            self.name(about)
        };
        let dn = self.name(dir);
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
