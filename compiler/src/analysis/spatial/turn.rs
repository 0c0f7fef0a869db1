//! Turning a direction feature: onto a known direction (the shortest turn when its cluster is
//! free to turn, the turn about its axis otherwise, decided with a second direction or a
//! joint's point when the axis alone leaves it to rounding), onto the cone of directions at an
//! angle from a known one, to an angle about an axis, or (a line turning about a point of it)
//! until it passes at a distance from a point. Each turn updates the record (`turned`).

use super::relation::{AngleValue, Length};
use super::{Rel, Shape, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reach, Reg, Residual, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::{GeomId, GeomKind};

impl Builder<'_, Spatial> {
    /// A free direction (a vector, a plane's normal, a line's or a segment's) to make `angle`
    /// with known direction `u`:
    /// it turns the least onto the cone of directions about `u` at that angle, and may then
    /// only turn about `u`, which keeps the angle (one freedom, the cone's; a vector's, a
    /// plane's or a line's turn about itself moves nothing). A body's direction keeps a second freedom,
    /// its spin about itself, which no record holds yet.
    pub(super) fn turn_onto_cone(
        &mut self,
        u: GeomId,
        v: GeomId,
        angle: AngleValue,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(v);
        let rec = self.clusters[k].record.clone();
        if !(rec.movable() && rec.turn == Turn::Free && rec.shape.one_direction()) {
            return false;
        }
        let (ur, vr) = (self.direction(u), self.direction(v));
        let angle = self.angle_value(angle);
        let (uname, vname) = (self.name(u), self.name(v));
        let words = format!(
            "the direction nearest {vname} at {} from {uname}",
            self.word(angle)
        );
        let to = self.value(
            SpatialOp::ConeTurn {
                axis: ur,
                angle,
                dir: vr,
            },
            Ty::Vector,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let pivot = self.pivot_of(k);
        let explain = format!(
            "Rotate {names} the least so that {vname} makes its angle with {uname}, on the plane through both ({}); it may then only turn about {uname}.",
            self.cname(r.constraint)
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                axis: RotationAxis::Shortest,
                from: vr,
                to,
            },
            None,
            self.satisfies(r),
            explain,
        );
        self.clusters[k].record.turn = Turn::Axis {
            axis: ur,
            feature: None,
        };
        true
    }

    /// Direction `v` to make an angle with known `u`: its cluster, turning about one axis,
    /// turns to where `v`'s cone about the axis meets `u`'s cone of that angle (two turns, a
    /// branch). Free to turn, it waits: the angle alone leaves it two freedoms.
    pub(super) fn turn_to_angle(
        &mut self,
        u: GeomId,
        v: GeomId,
        angle: AngleValue,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(v);
        let Turn::Axis { axis, .. } = self.clusters[k].record.turn else {
            return false;
        };
        let (ur, vr) = (self.direction(u), self.direction(v));
        let angle = self.angle_value(angle);
        let (uname, vname) = (self.name(u), self.name(v));
        let meanings = vec![
            format!(
                "{vname} turned counter-clockwise about {} from its turn nearest {uname}",
                self.word(axis)
            ),
            "turned clockwise from there".to_string(),
        ];
        let branch = self.branch(r.constraint, meanings);
        let words = format!(
            "where {vname} turns about {} to {} from {uname}",
            self.word(axis),
            self.word(angle)
        );
        let target = self.value(
            SpatialOp::AngleTurn {
                u: ur,
                v: vr,
                axis,
                angle,
                branch,
                constraint: r.constraint,
            },
            Ty::Vector,
            words,
        );
        self.turn_onto(v, target, r, true)
    }

    /// Directions `u` and `v` to be parallel (`v` along `sense * u`), each on a body that only
    /// turns about a known axis (a wrist's middle joint between the joints before and after
    /// it): `v` keeps its angle with its own axis, a constant of its body, so `u` must make
    /// that angle with it. `u`'s body turns to where `u`'s cone about its axis meets that cone
    /// (two turns, a branch: the wrist flipped or not), and `v`'s then turns onto it.
    pub(super) fn parallel_about_two_axes(
        &mut self,
        u: GeomId,
        v: GeomId,
        sense: f64,
        r: &Rel,
    ) -> bool {
        if self.together(u, v) || sense == 0.0 {
            return false;
        }
        for (first, second) in [(u, v), (v, u)] {
            let axis_feature = |b: &Self, g: GeomId| match b.record(g).turn {
                Turn::Axis {
                    feature: Some(f), ..
                } if b.record(g).movable() => Some(f),
                _ => None,
            };
            let (Some(_), Some(f)) = (axis_feature(self, first), axis_feature(self, second)) else {
                continue;
            };
            // `second`'s angle with its body's axis, from the body's own geometry.
            let model = self.model;
            if model.top_level_of(f) != model.top_level_of(second) {
                continue;
            }
            let (Some(a), Some(b)) = (super::local_dir(model, f), super::local_dir(model, second))
            else {
                continue;
            };
            let cos = super::dot(a, b) / (super::dot(a, a) * super::dot(b, b)).sqrt();
            let beta = cos.clamp(-1.0, 1.0).acos();
            let angle = if sense < 0.0 {
                std::f64::consts::PI - beta
            } else {
                beta
            };
            let part = Rel {
                last: false,
                ..r.clone()
            };
            if !self.turn_to_angle(f, first, AngleValue::Const(angle), &part) {
                continue;
            }
            // `second` then turns onto `first` (or its opposite), on its cone by construction.
            let known = self.direction(first);
            let target = self.in_sense(known, first, sense);
            return self.turn_onto(second, target, r, true);
        }
        false
    }

    /// Direction `dir`, the register of feature `of`, in `sense`: itself, or its opposite
    /// for a negative sense (a parallel relation's or a joint's sketched sense).
    pub(super) fn in_sense(&mut self, dir: Reg, of: GeomId, sense: f64) -> Reg {
        if sense < 0.0 {
            let words = format!("the opposite of {}", self.name(of));
            self.value(SpatialOp::Opposite(dir), Ty::Vector, words)
        } else {
            dir
        }
    }

    /// A line (its point `base`, direction `dir`) that only turns about an axis through a known
    /// point of it (`base` itself, or the point its cluster pivots about, another point of the
    /// line), turned about that axis until it passes `length` from known point `p`: its
    /// direction at the angle from the direction to `p` whose sine is the distance over theirs
    /// (`SpatialOp::PassingAngle`, keeping its sense), where its turn meets that cone (a branch).
    pub(super) fn turn_line_past(
        &mut self,
        base: GeomId,
        dir: GeomId,
        p: GeomId,
        length: Length,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(dir);
        let rec = self.clusters[k].record.clone();
        let Turn::Axis { axis, .. } = rec.turn else {
            return false;
        };
        let line = self.model.top_level_of(base);
        let through = match rec.trans {
            _ if self.point_known(base) => self.point(base),
            Trans::Pivot { at, feature } if self.model.top_level_of(feature) == line => at,
            _ => return false,
        };
        if !matches!(
            self.model.geoms[line].kind,
            GeomKind::Line | GeomKind::Segment
        ) {
            return false;
        }
        let (to, now) = (self.point(p), self.direction(dir));
        let d = self.length(length);
        let (dname, pname) = (self.name(dir), self.name(p));
        let words = format!("the direction from the line's pivot to {pname}");
        let toward = self.value(Op::DirectionTo { from: through, to }, Ty::Vector, words);
        let words = format!(
            "the angle from that direction at which the line passes {} from {pname}",
            self.word(d)
        );
        let angle = self.value(
            SpatialOp::PassingAngle {
                from: through,
                to,
                d,
                now,
                constraint: r.constraint,
            },
            Ty::Scalar,
            words,
        );
        let meanings = vec![
            format!(
                "{dname} turned counter-clockwise about {} from its turn nearest the direction to {pname}",
                self.word(axis)
            ),
            "turned clockwise from there".to_string(),
        ];
        let branch = self.branch(r.constraint, meanings);
        let words = format!(
            "where {dname} turns about {} to pass {} from {pname}",
            self.word(axis),
            self.word(d)
        );
        let target = self.value(
            SpatialOp::AngleTurn {
                u: toward,
                v: now,
                axis,
                angle,
                branch,
                constraint: r.constraint,
            },
            Ty::Vector,
            words,
        );
        self.turn_onto(dir, target, r, true)
    }

    /// The point about which cluster `k` may rotate: its pivot, the feature it holds on a
    /// locus, or (free to translate) its first geom's origin.
    pub(super) fn pivot_of(&mut self, k: usize) -> Reg {
        match self.clusters[k].record.trans {
            Trans::Pivot { at, .. } => at,
            Trans::On { feature, .. } => self.point(feature),
            _ => {
                let g = self.clusters[k].geoms[0];
                let words = format!("the origin of {}", self.name(g));
                self.value(Op::PointOf(g), Ty::Point, words)
            }
        }
    }

    /// Turns the cluster of direction feature `v` so that it points along `target`: the
    /// shortest turn when free (then it may still turn about `target`), the turn about its
    /// axis otherwise. About an axis, `v` reaches `target` only if both make the same angle
    /// with it: unless that holds by construction (`across`: both are perpendicular to the
    /// axis, as a twist's x axes are to their z), the relation is then checked.
    pub(super) fn turn_onto(&mut self, v: GeomId, target: Reg, r: &Rel, across: bool) -> bool {
        self.turn_onto_with(v, target, None, r, across)
    }

    /// [`Builder::turn_onto`]; `also`: another direction of `v`'s cluster and its target (a
    /// marker's x axis with its z), which a turn about an axis must reach as well and which
    /// decides it together with `v` (see [`Builder::twin_x_axes`]).
    pub(super) fn turn_onto_with(
        &mut self,
        v: GeomId,
        target: Reg,
        also: Option<(Reg, Reg)>,
        r: &Rel,
        across: bool,
    ) -> bool {
        let k = self.cluster(v);
        let rec = self.clusters[k].record.clone();
        if !rec.movable() {
            return false;
        }
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let vname = self.name(v);
        match rec.turn {
            Turn::Free => {
                let pivot = self.pivot_of(k);
                let from = self.direction(v);
                let explain = format!(
                    "Rotate {names} about {} so that {vname} points along {} ({c}).",
                    self.word(pivot),
                    self.word(target)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot,
                        axis: RotationAxis::Shortest,
                        from,
                        to: target,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                // A vector, or a line along its direction: turning about itself moves nothing.
                self.clusters[k].record.turn = if matches!(
                    rec.shape,
                    Shape::Vector | Shape::Line | Shape::Segment { .. } | Shape::Circle { .. }
                ) {
                    Turn::Known
                } else {
                    Turn::Axis {
                        axis: target,
                        feature: Some(v),
                    }
                };
                true
            }
            Turn::Axis { axis, feature } => {
                if feature == Some(v) {
                    return false;
                }
                let pivot = self.pivot_of(k);
                let from = self.direction(v);
                let reach = if also.is_none() && !across {
                    self.reach(r, k, axis, (v, target))
                } else {
                    None
                };
                // A second pair decides the angle with the direction: the turn is by it.
                // What the joint's point or coupling must reach, in words.
                let reaching = reach.map(|(reach, screw)| {
                    let what = match reach {
                        Reach::Point { point, locus } => {
                            format!("{} onto {}", self.word(point), self.word(locus))
                        }
                        Reach::Helix(h) => {
                            format!("{}'s x axis to its helix's turn", self.word(h.x))
                        }
                    };
                    let riding = if screw.is_some() {
                        " where the screw it rides takes it"
                    } else {
                        ""
                    };
                    format!("{what}{riding}")
                });
                let angle = if let (Some((reach, screw)), Some(reaching)) = (reach, &reaching) {
                    // The joint's point or coupling decides the turn with the direction.
                    let words = format!(
                        "the angle about {} taking {vname} to {} and {reaching}",
                        self.word(axis),
                        self.word(target)
                    );
                    let op = Op::Spatial(SpatialOp::TurnReaching {
                        u: from,
                        v: target,
                        axis,
                        pivot,
                        reach,
                        screw,
                    });
                    Some(self.value(op, Ty::Scalar, words))
                } else if let Some((x, x_target)) = also {
                    let words = format!(
                        "the angle about {} taking {vname} to {} and its x axis to {}",
                        self.word(axis),
                        self.word(target),
                        self.word(x_target)
                    );
                    let op = Op::Spatial(SpatialOp::AngleAboutBoth {
                        u: [from, x],
                        v: [target, x_target],
                        axis,
                    });
                    Some(self.value(op, Ty::Scalar, words))
                } else {
                    None
                };
                let how = if let Some(reaching) = &reaching {
                    format!(
                        "the angle that takes {vname} to {} and {reaching} together (the joint decides the turn when {vname} lies nearly along the axis)",
                        self.word(target)
                    )
                } else if let Some((x, x_target)) = also {
                    format!(
                        "the angle that takes {vname} to {} and {} to {} together, each weighed by how far across the axis it lies",
                        self.word(target),
                        self.word(x),
                        self.word(x_target)
                    )
                } else {
                    format!(
                        "the angle between the perpendiculars from {vname} and {} to it",
                        self.word(target)
                    )
                };
                let explain = format!(
                    "{names} may only rotate about {}: rotate it about that axis by {how} ({c}{}).",
                    self.word(axis),
                    if across {
                        ""
                    } else {
                        ", then checked: both must make the same angle with the axis"
                    }
                );
                let op = match angle {
                    Some(angle) => Op::Spatial(SpatialOp::RotateBy {
                        geoms,
                        pivot,
                        axis,
                        angle,
                    }),
                    None => Op::RotateDir {
                        geoms,
                        pivot,
                        axis: RotationAxis::Along(axis),
                        from,
                        to: target,
                    },
                };
                let satisfies = if across {
                    self.satisfies(r)
                } else {
                    Vec::new()
                };
                self.emit(op, None, satisfies, explain);
                self.turned(k);
                if across {
                    return true;
                }
                // Under a default, how far `v` is off the target's cone about the axis, signed
                // (a turn about the axis keeps it): the error that closes the iteration (as
                // `close_iterations` makes it), where the relation's own residual, an angle,
                // only touches zero at the roots.
                if self.depends_on_default(&[from, target, axis]) {
                    let explain = format!(
                        "... and check that {vname} and {} make the same angle with {} ({c}).",
                        self.word(target),
                        self.word(axis)
                    );
                    self.emit(
                        Op::Check {
                            constraint: r.constraint,
                            residual: Residual::Cone {
                                axis,
                                u: from,
                                v: target,
                            },
                            guard: false,
                        },
                        None,
                        Vec::new(),
                        explain,
                    );
                }
                // The turn about the axis reaches the target only on the axis' cone: measure.
                let residual = self.residual(&r.relation);
                let explain = format!("... and check that {c} holds.");
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
                true
            }
            Turn::Known | Turn::None => false,
        }
    }

    /// Cluster `k`'s orientation is now known: about a pivot, it is placed.
    pub(super) fn turned(&mut self, k: usize) {
        let rec = &mut self.clusters[k].record;
        rec.turn = Turn::Known;
        if let Trans::Pivot { .. } = rec.trans {
            rec.trans = Trans::Fixed;
        }
    }
}
