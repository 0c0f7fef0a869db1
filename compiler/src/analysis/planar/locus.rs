//! Locus analysis in the plane (003, Example 2) and the loci it intersects. A point feature of
//! a partially fixed cluster lies on a curve its freedom sweeps (`locus_of`: the circle about
//! its pivot, or the locus it is held on moved with it, `shifted`); two such points to
//! coincide go where their curves meet (`locus`, `intersect`: a pseudo-point, a branch
//! variable where two), and each cluster is then moved there with its one remaining motion
//! (`reach`). `meet` is where a feature moving on a locus meets its target.

use super::relation::Relation;
use super::{
    depends_on_dim, locus_reg, pinned_at_midpoint, pivot_name, Locus, Planar, Pos, Rel, Rot, Target,
};
use crate::analysis::driver::Builder;
use crate::plan::{Meet, Op, PlanarOp, Reg, RotationAxis, Ty};
use gcs_lang::model::{ConstraintId, GeomId};

impl Builder<'_, Planar> {
    /// The circle about `at` through the current position `from` of feature `f`.
    pub(super) fn circle_through(&mut self, at: Reg, from: Reg, f: GeomId, pivot: GeomId) -> Reg {
        // Both on one rigid geom with a constant sketch of them: the radius is their distance
        // in it, known now.
        let radius = self.model.constant_distance(pivot, f);
        let words = format!(
            "the circle about {} through {}",
            self.word(at),
            self.name(f)
        );
        let c = self.value(
            PlanarOp::CircleThrough {
                center: at,
                through: from,
                radius,
            },
            Ty::Circle,
            words,
        );
        self.centers.insert(c, self.word(at));
        c
    }

    /// The locus `lg` (of feature `g`) moved by `f - g`: where `f` goes when the cluster
    /// translates keeping `g` on `lg`.
    pub(super) fn shifted(&mut self, lg: Locus, g: GeomId, f: GeomId) -> Reg {
        let pg = self.point(g);
        let pf = self.point(f);
        let fname = self.name(f);
        match lg {
            Locus::Line(l) => {
                let words = format!("the parallel to {} through {fname}", self.word(l));
                self.value(
                    Op::ParallelLine {
                        line: l,
                        through: pf,
                    },
                    Ty::Line,
                    words,
                )
            }
            // Only a circle's own centre rides on a conic: nothing else of it to shift.
            Locus::Conic(c) => c,
            Locus::Circle(c) => {
                let words = format!("{} moved with {fname}", self.word(c));
                self.value(
                    Op::ShiftedCircle {
                        circle: c,
                        from: pg,
                        to: pf,
                    },
                    Ty::Circle,
                    words,
                )
            }
        }
    }

    /// Where a feature moving on `own` meets `target`: an intersection (a branch variable), or
    /// the target point itself, which must lie on `own`.
    pub(super) fn meet(&mut self, own: Reg, target: Target, near: Reg, r: &Rel) -> Reg {
        match target {
            Target::Point(x) => {
                let words = self.word(x);
                self.value(
                    Op::Onto {
                        locus: own,
                        point: x,
                        constraint: r.constraint,
                    },
                    Ty::Point,
                    words,
                )
            }
            Target::On(locus) => {
                let other = locus_reg(locus);
                let own_ty = self.ty(own);
                let (meet, a, b) = match (own_ty, locus) {
                    (Ty::Circle, Locus::Circle(c)) => (Meet::CircleCircle, own, c),
                    (Ty::Circle, Locus::Line(l)) => (Meet::LineCircle, l, own),
                    (Ty::Line, Locus::Circle(c)) => (Meet::LineCircle, own, c),
                    (Ty::Circle, Locus::Conic(q)) => (Meet::CircleConic, own, q),
                    (Ty::Line, Locus::Conic(q)) => (Meet::LineConic, own, q),
                    (Ty::Conic, Locus::Circle(c)) => (Meet::CircleConic, c, own),
                    (Ty::Conic, Locus::Line(l)) => (Meet::LineConic, l, own),
                    (Ty::Conic, Locus::Conic(q)) => (Meet::ConicConic, own, q),
                    _ => (Meet::LineLine, own, other),
                };
                self.intersect(meet, a, b, near, r.constraint)
            }
        }
    }

    /// Intersects two loci: the root of a new branch variable for `constraint`, each index with
    /// its geometric meaning.
    fn intersect(
        &mut self,
        meet: Meet,
        a: Reg,
        b: Reg,
        near: Reg,
        constraint: ConstraintId,
    ) -> Reg {
        let (wa, wb, wn) = (self.word(a), self.word(b), self.word(near));
        let centre = |s: &Self, r: Reg| {
            s.centers
                .get(&r)
                .cloned()
                .unwrap_or_else(|| format!("the centre of {}", s.word(r)))
        };
        let (ca, cb) = (centre(self, a), centre(self, b));
        let meanings = match meet {
            Meet::CircleCircle => vec![
                format!("{wn} to the left of the line from {ca} to {cb}"),
                format!("{wn} to the right of the line from {ca} to {cb}"),
            ],
            Meet::LineCircle | Meet::LineConic => vec![
                format!("the first crossing of {wa} with {wb}, along the line"),
                "the second crossing, along the line".to_string(),
            ],
            Meet::LineLine => vec![format!("the crossing of {wa} and {wb}")],
            Meet::CircleConic => (0..4)
                .map(|i| format!("root {i} in increasing parameter along {wb}"))
                .collect(),
            Meet::ConicConic => (0..4)
                .map(|i| format!("root {i} in increasing parameter along {wa}"))
                .collect(),
            spatial => unreachable!("the plane's fragments never meet {spatial:?}"),
        };
        let branch = self.branch(constraint, meanings);
        let words = format!("the meeting point of {wa} and {wb}");
        self.value(
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            },
            Ty::Point,
            words,
        )
    }

    /// The locus table: where feature `f` of a partially fixed cluster can lie, if on a curve.
    fn locus_of(&mut self, f: GeomId) -> Option<Reg> {
        let rec = self.record(f).clone();
        if rec.free_dim.is_some() && depends_on_dim(self.model, f)
            || pinned_at_midpoint(self.model, &rec).is_some()
        {
            return None;
        }
        match rec.pos {
            Pos::On { feature, locus } if rec.rot != Rot::Free => Some(if feature == f {
                locus_reg(locus)
            } else {
                self.shifted(locus, feature, f)
            }),
            Pos::Pivot { at, feature } if feature != f => {
                let from = self.point(f);
                Some(self.circle_through(at, from, f, feature))
            }
            _ => None,
        }
    }

    /// Locus analysis: a coincidence between features of two partially fixed clusters, each on
    /// a curve: intersect the curves (a pseudo-point, 003 Example 2) and move both clusters.
    pub(super) fn locus(&mut self, r: &Rel) -> bool {
        let Relation::PointPoint { a, b, d: None } = r.relation else {
            return false;
        };
        let (ka, kb) = (self.cluster(a), self.cluster(b));
        if ka == kb {
            return false;
        }
        let ready = |s: &Self, f: GeomId| {
            let rec = s.record(f);
            (rec.free_dim.is_none() || !depends_on_dim(s.model, f))
                && pinned_at_midpoint(s.model, rec).is_none()
                && match rec.pos {
                    Pos::On { .. } => rec.rot != Rot::Free,
                    Pos::Pivot { feature, .. } => feature != f,
                    _ => false,
                }
        };
        // A segment end its free length slides along a line is on that line; the length
        // then takes it to the meeting point.
        let (slide_a, slide_b) = (self.sliding_end(a), self.sliding_end(b));
        if !(ready(self, a) || slide_a.is_some()) || !(ready(self, b) || slide_b.is_some()) {
            return false;
        }
        let locus = |s: &mut Self, f: GeomId, slide: Option<GeomId>| match slide {
            Some(anchor) => Some(s.sliding_line(f, anchor)),
            None => s.locus_of(f),
        };
        let (Some(la), Some(lb)) = (locus(self, a, slide_a), locus(self, b, slide_b)) else {
            return false;
        };
        let near = self.point(b);
        // The intersection table wants (line, circle), (circle, conic), (line, conic).
        let rank = |t: Ty| match t {
            Ty::Line => 0,
            Ty::Circle => 1,
            _ => 2,
        };
        let (x, y) = if rank(self.ty(la)) <= rank(self.ty(lb)) {
            (la, lb)
        } else {
            (lb, la)
        };
        let meet = match (self.ty(x), self.ty(y)) {
            (Ty::Circle, Ty::Circle) => Meet::CircleCircle,
            (Ty::Line, Ty::Line) => Meet::LineLine,
            (Ty::Line, Ty::Circle) => Meet::LineCircle,
            (Ty::Line, Ty::Conic) => Meet::LineConic,
            (Ty::Circle, Ty::Conic) => Meet::CircleConic,
            _ => return false,
        };
        let pseudo = self.intersect(meet, x, y, near, r.constraint);
        // The pseudo-point lies on both loci: move a's cluster there, then b's (which
        // satisfies the constraint), each with its one remaining motion.
        if let Some(anchor) = slide_a {
            self.slide_end_to(a, anchor, pseudo, r, false);
        } else {
            self.reach(a, pseudo, &[]);
        }
        if let Some(anchor) = slide_b {
            self.slide_end_to(b, anchor, pseudo, r, true);
        } else {
            let sat = self.satisfies(r);
            self.reach(b, pseudo, &sat);
        }
        true
    }

    /// Moves the cluster of `f`, whose one-DOF motion is known to reach `x`, so that `f` is at
    /// `x`: a rotation about its pivot, or a translation along its locus.
    fn reach(&mut self, f: GeomId, x: Reg, satisfies: &[ConstraintId]) {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let from = self.point(f);
        let fname = self.name(f);
        let to = self.word(x);
        match rec.pos {
            Pos::Pivot { at, feature } => {
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that {fname} reaches {to}.",
                    pivot_name(self.model, feature)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from,
                        to: x,
                    },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.rot = Rot::Known;
                rec.pos = Pos::Fixed;
            }
            _ => {
                let explain = format!("{names} may only slide along its locus: translate it so that {fname} reaches {to}.");
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
            }
        }
        self.settle(k);
    }
}
