//! Plan fragments for the constraints every sketcher has: equal dimensions, midpoints and
//! mirror symmetry. Each is a relation of its own ([`Relation::Equal`],
//! [`Relation::Midpoint`], [`Relation::Mirror`]) rather than a rewrite into others, because
//! each becomes constructive in its own way:
//!
//! - `equal(a, b)`: an equal dimension is not a known one. Once either dimension is known
//!   (dimensioned, placed, or given by a default), the other is set to it, as a `length` or
//!   `radius` sets it, with the value measured from the first at run time; before that the
//!   relation waits. A segment pinned at its end is sized and moved back onto that end; a
//!   circle holding one fixed distance has its centre put on the locus that distance becomes.
//! - `midpoint(p, s)`: once both ends of `s` are known, `p` goes to their midpoint; once `p`
//!   and one end are known, the other end goes to the reflection of the known end through
//!   `p` (the segment's own fragments turn and size it there); a segment of known length with
//!   neither end known is translated so that its midpoint lands on `p`, and may then only
//!   turn about it. A segment of free length with only its midpoint known waits: the
//!   defaults size it first (see `defaults.rs`), so that its free motions are its length and
//!   its angle about its midpoint.
//! - `symmetric(p, q, l)`: once the mirror line and one of the points are known, the other
//!   point goes to the mirror image; once both points are known, the line is placed on their
//!   perpendicular bisector, directed as the sketch has it: turned to the bisector's
//!   direction, then moved onto it. What of that the line's record already fixed (its
//!   direction, or a point it passes through) is not constructed but checked at run time,
//!   right after.
//!
//! When all of a relation's features are known already it is a run-time check, as every
//! implied relation is (`Builder::implied`).

use super::relation::Relation;
use super::{Dir, Locus, Planar, Pos, Rel, Rot, Target};
use crate::analysis::driver::Builder;
use crate::plan::{Op, PlanarOp, Reg, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Part};

impl Builder<'_, Planar> {
    /// Whether the dimension of `g` (a segment's length, a circle's radius) is known.
    pub(super) fn dim_known(&self, g: GeomId) -> bool {
        self.record(g).free_dim != Some(g)
    }

    /// `equal(a, b)`: the free dimension follows the known one.
    pub(super) fn equal(&mut self, r: &Rel) -> bool {
        let Relation::Equal { a, b } = r.relation else {
            return false;
        };
        let (known, free) = match (self.dim_known(a), self.dim_known(b)) {
            (true, false) => (a, b),
            (false, true) => (b, a),
            _ => return false,
        };
        let value = self.dim_of(known);
        self.resize(free, value, known, r)
    }

    /// Sets the free dimension of `g` to `value`, the dimension of `like`, keeping what its
    /// record holds: a segment pinned at its end is moved back onto that end; a circle that
    /// holds one fixed distance has its centre put on the locus that distance becomes. A
    /// segment whose end is on a locus, or a circle on the conic of two fixed distances,
    /// waits.
    fn resize(&mut self, g: GeomId, value: Reg, like: GeomId, r: &Rel) -> bool {
        let model = self.model;
        let k = self.cluster(g);
        let rec = self.clusters[k].record.clone();
        if let (Some(_), [first, _], Pos::On { feature, locus }) = (
            rec.free_dim.filter(|d| *d == g && rec.fd_locus),
            rec.fd.as_slice(),
            rec.pos,
        ) {
            // A circle on the locus of centres of two fixed distances, its radius now known:
            // the first distance is a locus of its own, which meets that one.
            let first = *first;
            let c = self.cname(r.constraint);
            let (gname, lname) = (self.name(g), self.name(like));
            let explain =
                format!("Size {gname} so that its radius is the radius of {lname} ({c}).");
            self.emit(
                Op::SetDim { geom: g, value },
                None,
                self.satisfies(r),
                explain,
            );
            let rec = &mut self.clusters[k].record;
            rec.free_dim = None;
            rec.fixed_dims.push(g);
            let other = self.fd_locus(g, first);
            let from = self.point(feature);
            let own = super::locus_reg(locus);
            let to = self.meet(own, Target::On(other), from, r);
            let held: Vec<_> = rec_fd_satisfies(&self.clusters[k].record.fd);
            let explain = format!(
                "The centre of {gname} must be on {} and on {}: translate {gname} to where they meet.",
                self.word(own),
                self.word(super::locus_reg(other))
            );
            let geoms = self.clusters[k].geoms.clone();
            self.emit(Op::Translate { geoms, from, to }, None, held, explain);
            let rec = &mut self.clusters[k].record;
            rec.fd.clear();
            rec.fd_locus = false;
            rec.pos = Pos::Fixed;
            return true;
        }
        if rec.free_dim != Some(g) || rec.fd_locus || rec.fd.len() > 1 {
            return false;
        }
        let end = model.part(g, Part::End);
        let midpoint = super::pinned_at_midpoint(model, &rec);
        let pinned_end = match rec.pos {
            Pos::Pivot { at, feature } if Some(feature) == end => Some((at, feature)),
            Pos::On { feature, .. } if Some(feature) == end => return false,
            _ => None,
        };
        let what = if model.geoms[g].kind == GeomKind::Circle {
            "radius"
        } else {
            "length"
        };
        let c = self.cname(r.constraint);
        let (gname, lname) = (self.name(g), self.name(like));
        match (pinned_end, midpoint) {
            (None, Some((at, seg))) => {
                let explain = format!(
                    "{gname} is pinned at its midpoint {}: size it so that its length is the length of {lname} ...",
                    self.word(at)
                );
                self.emit(Op::SetDim { geom: g, value }, None, Vec::new(), explain);
                let done = self.satisfies(r);
                self.back_to_midpoint(k, seg, at, done, &format!(" ({c})"));
            }
            (None, None) => {
                let explain =
                    format!("Size {gname} so that its {what} is the {what} of {lname} ({c}).");
                self.emit(
                    Op::SetDim { geom: g, value },
                    None,
                    self.satisfies(r),
                    explain,
                );
            }
            (Some((at, end)), _) => {
                let explain = format!(
                    "{gname}'s end is pinned at {}: size it so that its length is the length of {lname} ...",
                    self.word(at)
                );
                self.emit(Op::SetDim { geom: g, value }, None, Vec::new(), explain);
                // Where the sizing took the end (not the pinned place a cache would give).
                let from = self.value(
                    Op::PointOf(end),
                    Ty::Point,
                    format!("{} as sized", self.name(end)),
                );
                let explain = format!(
                    "... and translate it so that its end is back on {} ({c}).",
                    self.word(at)
                );
                let geoms = self.clusters[k].geoms.clone();
                self.emit(
                    Op::Translate {
                        geoms,
                        from,
                        to: at,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
            }
        }
        let rec = &mut self.clusters[k].record;
        rec.free_dim = None;
        rec.fixed_dims.push(g);
        let Some(fd) = rec.fd.pop() else {
            return true;
        };
        // The fixed distance the circle held is a locus of its centre now: put it there, which
        // satisfies that distance's constraint.
        rec.fd_locus = false;
        let (constraint, last) = fd.constraint();
        let centre = model.part(g, Part::Center).unwrap_or(g);
        let locus = self.fd_locus(g, fd);
        let held = Rel {
            relation: r.relation.clone(),
            constraint,
            last,
            duplicate: false,
        };
        self.move_feature(centre, Target::On(locus), &held)
    }

    /// `midpoint(p, s)`, with `a` and `b` the ends of `s`.
    pub(super) fn midpoint(&mut self, r: &Rel) -> bool {
        let Relation::Midpoint { p, a, b } = r.relation else {
            return false;
        };
        let s = self.model.top_level_of(a);
        let sname = self.name(s);
        let (ka, kb) = (self.point_known(a), self.point_known(b));
        if ka && kb {
            let (pa, pb) = (self.point(a), self.point(b));
            let mid = self.value(
                Op::Midpoint { a: pa, b: pb },
                Ty::Point,
                format!("the midpoint of {sname}"),
            );
            return self.move_feature(p, Target::Point(mid), r);
        }
        if !self.point_known(p) {
            return false;
        }
        let at = self.point(p);
        if ka || kb {
            let (known, free) = if ka { (a, b) } else { (b, a) };
            let from = self.point(known);
            let x = self.value(
                Op::Reflect {
                    point: from,
                    through: at,
                },
                Ty::Point,
                format!("{} reflected through {}", self.name(known), self.name(p)),
            );
            return self.move_feature(free, Target::Point(x), r);
        }
        // Neither end known: a segment of known length, free to translate, takes its
        // midpoint to `p`, and may then only turn about it.
        let k = self.cluster(s);
        let rec = self.clusters[k].record.clone();
        if rec.pos != Pos::Free {
            return rec.free_dim.is_none() && self.move_midpoint(k, s, at, r);
        }
        let (pa, pb) = (self.point(a), self.point(b));
        let mid = self.value(
            Op::Midpoint { a: pa, b: pb },
            Ty::Point,
            format!("the midpoint of {sname}"),
        );
        let geoms = self.clusters[k].geoms.clone();
        let explain = format!(
            "{} is free to translate: translate it so that the midpoint of {sname} lands on {} ({}).",
            self.group_name(&geoms),
            self.name(p),
            self.cname(r.constraint)
        );
        self.emit(
            Op::Translate {
                geoms,
                from: mid,
                to: at,
            },
            None,
            self.satisfies(r),
            explain,
        );
        // Pinned at its midpoint: it may still turn about it, and a free length sizes about
        // it (`pinned_at_midpoint`); with its direction and length known it is placed.
        let rec = &mut self.clusters[k].record;
        rec.pos = if rec.rot == Rot::Free || rec.free_dim.is_some() {
            Pos::Pivot { at, feature: s }
        } else {
            Pos::Fixed
        };
        true
    }

    /// A segment `s` of known length in cluster `k`, partly fixed, neither end known: its one
    /// motion takes its midpoint to `at`. Sliding with a feature on a locus (its direction
    /// known), the midpoint runs on that locus shifted to it; turning about a pivot, on the
    /// circle about the pivot through it. `at` must be on that curve (it is a point the
    /// motion reaches only there), or the constraint is inconsistent by the gap.
    fn move_midpoint(&mut self, k: usize, s: GeomId, at: Reg, r: &Rel) -> bool {
        let rec = self.clusters[k].record.clone();
        let (Some(a), Some(b)) = (
            self.model.part(s, Part::Start),
            self.model.part(s, Part::End),
        ) else {
            return false;
        };
        let sname = self.name(s);
        let (pa, pb) = (self.point(a), self.point(b));
        let mid = self.value(
            Op::Midpoint { a: pa, b: pb },
            Ty::Point,
            format!("the midpoint of {sname}"),
        );
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        match (rec.pos, rec.rot) {
            (Pos::On { feature, locus }, Rot::Known | Rot::None) => {
                let pf = self.point(feature);
                let own = match locus {
                    Locus::Line(l) => self.value(
                        Op::ParallelLine {
                            line: l,
                            through: mid,
                        },
                        Ty::Line,
                        format!(
                            "the parallel to {} through the midpoint of {sname}",
                            self.word(l)
                        ),
                    ),
                    Locus::Circle(circle) => self.value(
                        Op::ShiftedCircle {
                            circle,
                            from: pf,
                            to: mid,
                        },
                        Ty::Circle,
                        format!("{} moved with the midpoint of {sname}", self.word(circle)),
                    ),
                    Locus::Conic(_) => return false,
                };
                let to = self.meet(own, Target::Point(at), mid, r);
                let explain = format!(
                    "{names} can only slide so that {} stays on its locus: move it so that the midpoint of {sname} reaches {} ({c}).",
                    self.name(feature),
                    self.word(to)
                );
                self.emit(
                    Op::Translate {
                        geoms,
                        from: mid,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
            }
            (Pos::Pivot { at: pivot, feature }, Rot::Free) => {
                let words = format!(
                    "the circle about {} through the midpoint of {sname}",
                    self.word(pivot)
                );
                let own = self.value(
                    PlanarOp::CircleThrough {
                        center: pivot,
                        through: mid,
                        radius: None,
                    },
                    Ty::Circle,
                    words,
                );
                self.centers.insert(own, self.word(pivot));
                let to = self.meet(own, Target::Point(at), mid, r);
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that the midpoint of {sname} reaches {} ({c}).",
                    super::pivot_name(self.model, feature),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot,
                        axis: crate::plan::RotationAxis::Normal,
                        from: mid,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.rot = Rot::Known;
            }
            (Pos::On { feature: g, locus }, Rot::Free) if !matches!(locus, Locus::Conic(_)) => {
                // Free to turn while g slides on its locus: g must be where the locus meets
                // the circle about `at` of radius |mid - g|. Slide it there, then turn about
                // it so that the midpoint lands on `at`.
                let pg = self.point(g);
                let about_g = self.value(
                    PlanarOp::CircleThrough {
                        center: pg,
                        through: mid,
                        radius: None,
                    },
                    Ty::Circle,
                    format!(
                        "the circle about {} through the midpoint of {sname}",
                        self.name(g)
                    ),
                );
                let about_at = self.value(
                    Op::ShiftedCircle {
                        circle: about_g,
                        from: pg,
                        to: at,
                    },
                    Ty::Circle,
                    format!(
                        "the circle about {} through where {} must be",
                        self.word(at),
                        self.name(g)
                    ),
                );
                self.centers.insert(about_at, self.word(at));
                let to = self.meet(
                    super::locus_reg(locus),
                    Target::On(Locus::Circle(about_at)),
                    pg,
                    r,
                );
                let explain = format!(
                    "{names} can slide {} along {} and turn about it; the midpoint of {sname} must reach {}: slide it so that {} is at {} ({c}).",
                    self.name(g),
                    self.word(super::locus_reg(locus)),
                    self.word(at),
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
                let (pa, pb) = (self.point(a), self.point(b));
                let mid = self.value(
                    Op::Midpoint { a: pa, b: pb },
                    Ty::Point,
                    format!("the midpoint of {sname} as slid"),
                );
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that the midpoint of {sname} reaches {} ({c}).",
                    self.name(g),
                    self.word(at)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: to,
                        axis: crate::plan::RotationAxis::Normal,
                        from: mid,
                        to: at,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.rot = Rot::Known;
            }
            _ => return false,
        }
        self.clusters[k].record.pos = Pos::Fixed;
        true
    }

    /// A segment pinned at its midpoint `at` that a sizing just moved (sizing keeps its
    /// start): translate it back so that its midpoint is at `at`.
    pub(super) fn back_to_midpoint(
        &mut self,
        k: usize,
        seg: GeomId,
        at: Reg,
        satisfies: Vec<ConstraintId>,
        why: &str,
    ) {
        let (Some(start), Some(end)) = (
            self.model.part(seg, Part::Start),
            self.model.part(seg, Part::End),
        ) else {
            return;
        };
        let (a, b) = (self.point(start), self.point(end));
        let sname = self.name(seg);
        let mid = self.value(
            Op::Midpoint { a, b },
            Ty::Point,
            format!("the midpoint of {sname} as sized"),
        );
        let geoms = self.clusters[k].geoms.clone();
        let explain = format!(
            "... and move {sname} back so that its midpoint is on {}{why}.",
            self.word(at)
        );
        self.emit(
            Op::Translate {
                geoms,
                from: mid,
                to: at,
            },
            None,
            satisfies,
            explain,
        );
    }

    /// `symmetric(p, q, l)`: the mirror image of a known point, or the mirror line from two.
    pub(super) fn mirror(&mut self, r: &Rel) -> bool {
        let Relation::Mirror {
            p, q, base, dir, ..
        } = r.relation
        else {
            return false;
        };
        let (kp, kq) = (self.point_known(p), self.point_known(q));
        let on_line = self.line_point(base);
        let line_known = on_line.is_some() && self.dir_known(Dir::Feature(dir));
        if !line_known {
            return kp && kq && self.bisector(r);
        }
        let (known, free) = match (kp, kq) {
            (true, false) => (p, q),
            (false, true) => (q, p),
            _ => return false,
        };
        let lname = self.name(self.model.top_level_of(dir));
        let bp = self.point(on_line.unwrap_or(base));
        let dv = self.dir(Dir::Feature(dir));
        let line = self.value(
            Op::Line {
                point: bp,
                dir: dv,
                offset: None,
            },
            Ty::Line,
            format!("the line of {lname}"),
        );
        let from = self.point(known);
        let x = self.value(
            PlanarOp::Mirror { point: from, line },
            Ty::Point,
            format!("the mirror image of {} across {lname}", self.name(known)),
        );
        self.move_feature(free, Target::Point(x), r)
    }

    /// Both points known, the mirror line not: put the line on their perpendicular bisector,
    /// directed as the sketch has it. A direction or a point of the line that its record
    /// fixed already is checked instead, right after (a known direction is not turned: the
    /// line is moved through the points' midpoint along it, and the check measures the rest).
    fn bisector(&mut self, r: &Rel) -> bool {
        let Relation::Mirror {
            p,
            q,
            base,
            dir,
            sense,
        } = r.relation
        else {
            return false;
        };
        let (pname, qname) = (self.name(p), self.name(q));
        let lname = self.name(self.model.top_level_of(dir));
        let (pp, pq) = (self.point(p), self.point(q));
        // Each step satisfies the constraint only if it completes the construction: a part
        // the record fixed already is checked after.
        let partial = Rel {
            last: false,
            ..r.clone()
        };
        // The line's direction: turned along the bisector's, directed as sketched (from p to q
        // turned a quarter turn the sketch's way), or known already.
        let turned = self.record(dir).rot == Rot::Free;
        let along = if turned {
            let across = self.value(
                Op::DirectionTo { from: pp, to: pq },
                Ty::Vector,
                format!("the direction from {pname} to {qname}"),
            );
            let words =
                format!("the direction of the perpendicular bisector of {pname} and {qname}");
            let along = self.quarter_turned(across, sense, words);
            if !self.turn(dir, along, &partial) {
                return false;
            }
            along
        } else {
            self.dir(Dir::Feature(dir))
        };
        // Its place: through the midpoint of p and q, or through a point it went through already.
        let through = self.line_point(base).is_some();
        let given = match (turned, through) {
            (true, false) => None,
            (false, _) => Some(format!(
                "{lname}'s direction was known before it was moved through the midpoint of {pname} and {qname}"
            )),
            (true, true) => Some(format!(
                "{lname} went through a known point before it was turned along the bisector"
            )),
        };
        if !through {
            let mid = self.value(
                Op::Midpoint { a: pp, b: pq },
                Ty::Point,
                format!("the midpoint of {pname} and {qname}"),
            );
            let words = if turned {
                format!("the perpendicular bisector of {pname} and {qname}")
            } else {
                format!("the line along {lname} through the midpoint of {pname} and {qname}")
            };
            let line = self.value(
                Op::Line {
                    point: mid,
                    dir: along,
                    offset: None,
                },
                Ty::Line,
                words,
            );
            let step = if given.is_none() { r } else { &partial };
            if !self.move_feature(base, Target::On(Locus::Line(line)), step) {
                return false;
            }
        }
        if let Some(given) = given {
            let residual = self.residual(&r.relation);
            let explain = format!("Check that {} holds: {given}.", self.cname(r.constraint));
            self.emit(
                Op::Check {
                    constraint: r.constraint,
                    residual,
                    guard: false,
                },
                None,
                self.satisfies(r),
                explain,
            );
        }
        true
    }
}

/// The constraints the fixed distances `fds` satisfy once their circle is placed.
fn rec_fd_satisfies(fds: &[super::circle::Fd]) -> Vec<gcs_lang::model::ConstraintId> {
    fds.iter()
        .filter_map(super::circle::Fd::satisfies)
        .collect()
}
