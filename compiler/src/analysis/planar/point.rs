//! Moving a point feature onto a point or a locus with the freedom its cluster's record leaves
//! (the plan fragment table of a rigid frame in the plane): free, onto the point or the
//! nearest point of the locus; held on a locus, a slide along it to where it meets the target;
//! about a pivot, the turn onto where its circle meets the target. A segment of free length
//! has fragments of its own first (`segment.rs`); a feature its free dimension moves waits.

use super::{depends_on_dim, locus_reg, pivot_name, Locus, Planar, Pos, Rel, Rot, Target};
use crate::analysis::driver::Builder;
use crate::plan::{Op, RotationAxis, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Planar> {
    /// Moves the cluster of feature `f` so that `f` meets `target`, with the freedom its record
    /// leaves (the plan fragment table for a rigid frame in the plane).
    pub(super) fn move_feature(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        if let Some(done) = self.segment_fragment(f, target, r) {
            return done;
        }
        if self.clusters[k].record.free_dim.is_some() && depends_on_dim(self.model, f) {
            // The feature moves with the free dimension: wait until it is fixed.
            return false;
        }
        let moved = self.move_feature_rigidly(f, target, r);
        if moved {
            self.settle(k);
        }
        moved
    }

    /// The fragments of a rigid frame in the plane (the free dimension, if any, does not move
    /// `f`).
    fn move_feature_rigidly(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let fname = self.name(f);
        match (rec.pos, target) {
            (Pos::Free, Target::Point(x)) => {
                let from = self.point(f);
                let explain = format!(
                    "{names} is free to translate: translate it so that {fname} lands on {} ({c}).",
                    self.word(x)
                );
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = if rec.rot == Rot::Free {
                    Pos::Pivot { at: x, feature: f }
                } else {
                    Pos::Fixed
                };
                if rec.pos == Pos::Fixed {
                    rec.rot = if rec.rot == Rot::None {
                        Rot::None
                    } else {
                        Rot::Known
                    };
                }
                self.insert_known(f, x);
                true
            }
            (Pos::Free, Target::On(locus)) => {
                let from = self.point(f);
                let lreg = locus_reg(locus);
                let to = self.value(
                    Op::Nearest {
                        locus: lreg,
                        point: from,
                    },
                    Ty::Point,
                    format!("the point of {} nearest {fname}", self.word(lreg)),
                );
                let explain = format!(
                    "{names} is free to translate: translate it by the least motion that puts {fname} on {} ({c}).",
                    self.word(lreg)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                if rec.line {
                    // A line through a point of a locus: with its direction known it is fixed.
                    rec.pos = if rec.rot == Rot::Known {
                        Pos::Fixed
                    } else {
                        Pos::Pivot { at: to, feature: f }
                    };
                    if rec.pos == Pos::Fixed {
                        return true;
                    }
                    self.insert_known(f, to);
                } else {
                    rec.pos = Pos::On { feature: f, locus };
                }
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if rec.rot != Rot::Free => {
                // Translation along the locus: f moves on the locus shifted by f - g.
                let from = self.point(f);
                let own = if g == f {
                    locus_reg(lg)
                } else {
                    self.shifted(lg, g, f)
                };
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} can only slide so that {} stays on {}: move it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if g == f => {
                // Rotation free, f already on a locus: put it at the locus' meeting point.
                let from = self.point(f);
                let to = self.meet(locus_reg(lg), target, from, r);
                let explain = format!(
                    "{fname} must stay on {}: translate {names} so that it reaches {} ({c}); {names} may still rotate about it.",
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Pivot { at: to, feature: f };
                self.insert_known(f, to);
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                Target::Point(x),
            ) if g != f => {
                // Free to turn while g slides on its locus, f to reach a point: g must be where
                // its locus meets the circle about x of radius |f - g|. Slide g there, then
                // turn about it (the pivot fragment) so that f lands on x.
                let (pg, pf) = (self.point(g), self.point(f));
                let about_g = self.circle_through(pg, pf, f, g);
                let words = format!(
                    "the circle about {} through where {fname} must be",
                    self.word(x)
                );
                let about_x = self.value(
                    Op::ShiftedCircle {
                        circle: about_g,
                        from: pg,
                        to: x,
                    },
                    Ty::Circle,
                    words,
                );
                self.centers.insert(about_x, self.word(x));
                let to = self.meet(locus_reg(lg), Target::On(Locus::Circle(about_x)), pg, r);
                let explain = format!(
                    "{names} can slide {} along {} and turn about it; {fname} must reach {}: slide it so that {} is at {} ({c}).",
                    self.name(g),
                    self.word(locus_reg(lg)),
                    self.word(x),
                    self.name(g),
                    self.word(to)
                );
                self.emit(
                    Op::Translate {
                        geoms: geoms.clone(),
                        from: pg,
                        to,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                // f is now on the circle about g that reaches x: turn it there (no check that x
                // is on that circle: it is, by construction).
                let from = self.point(f);
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(x)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: to,
                        axis: RotationAxis::Normal,
                        from,
                        to: x,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = Pos::Fixed;
                rec.rot = Rot::Known;
                true
            }
            (Pos::Pivot { at, feature: g }, target) if g != f => {
                let from = self.point(f);
                let own = self.circle_through(at, from, f, g);
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} may only rotate about {} ({}): rotate it so that {fname} reaches {} ({c}).",
                    pivot_name(self.model, g),
                    self.word(at),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = Pos::Fixed;
                rec.rot = Rot::Known;
                true
            }
            _ => false,
        }
    }
}
