//! Action analysis in space (003): a relation one of whose sides is known moves the other
//! side's cluster with the freedom its record leaves. `action` dispatches on the kind of
//! relation; each kind has its helper here, which picks the known side and the target (a
//! point, a locus, a direction) and hands it to the fragments of the other files (point moves,
//! turns, planes, circles, sizes). A relation already implied is a run-time check instead.

use super::relation::{AngleValue, Length, Relation};
use super::{Locus, Rel, Shape, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, SpatialOp, Ty};
use gcs_lang::expr::ExprId;
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    /// Action analysis: the relation's unknown side moved onto its known side.
    pub(super) fn action(&mut self, r: &Rel) -> bool {
        if !self.radii_known(&r.relation) {
            return false;
        }
        if self.implied(&r.relation) {
            self.check(r);
            return true;
        }
        match r.relation {
            Relation::Midpoint { p, a, b } => self.midpoint(p, a, b, r),
            Relation::Mirror { p, q, base, normal } => self.mirror(p, q, (base, normal), r),
            Relation::Size { geom, value } => {
                let size = self.expr(value);
                self.set_size(geom, size, r)
            }
            Relation::SameSize { a, b } => self.action_same_size(a, b, r),
            Relation::PointPoint { a, b, d } => self.action_point_point(a, b, d, r),
            Relation::PointLine {
                p,
                base,
                dir,
                d: Some(l),
            } => self.action_point_line_at(p, base, dir, l, r),
            Relation::PointLine { p, base, dir, .. } => self.action_point_line(p, base, dir, r),
            Relation::PointPlane { p, base, normal, d } => {
                self.action_point_plane(p, base, normal, d, r)
            }
            Relation::Parallel { u, v, sense } => self.action_parallel(u, v, sense, r),
            Relation::PointCircle { p, circle, d } => self.action_point_circle(p, circle, d, r),
            Relation::Angle { u, v, angle } => self.action_angle(u, v, angle, r),
            Relation::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } => {
                // The second marker moves for the first's, or the first for the second's: the
                // angle from the second to the first about the same axis is the opposite, for
                // the opposite advance, so the same coupling with the roles swapped.
                self.helix(axis, (u, p), (v, q), pitch, r)
                    || self.helix(axis, (v, q), (u, p), pitch, r)
            }
            Relation::Twist { axis, u, v, angle } => self.action_twist(axis, u, v, angle, r),
        }
    }

    /// `equal(a, b)` of sizes: once one is set and the other free, the other takes it.
    fn action_same_size(&mut self, a: GeomId, b: GeomId, r: &Rel) -> bool {
        for (known, free) in [(a, b), (b, a)] {
            if !self.record(known).shape.size_free() && self.record(free).shape.size_free() {
                let size = self.size_of(known);
                return self.set_size(free, size, r);
            }
        }
        false
    }

    /// Points `a` and `b` to coincide, or to be `d` apart: the one not known goes onto the known
    /// one, or onto the sphere of that radius about it.
    fn action_point_point(&mut self, a: GeomId, b: GeomId, d: Option<Length>, r: &Rel) -> bool {
        for (known, moving) in [(a, b), (b, a)] {
            if self.point_known(known) && !self.point_known(moving) {
                if d.is_some() && self.pinned_later(moving) {
                    return false;
                }
                let x = self.point(known);
                let target = match d {
                    None => Target::Point(x),
                    Some(l) => {
                        let radius = self.length(l);
                        let words = format!(
                            "the sphere about {} of radius {}",
                            self.name(known),
                            self.word(radius)
                        );
                        let s =
                            self.value(SpatialOp::Sphere { center: x, radius }, Ty::Sphere, words);
                        Target::On(Locus::Sphere(s))
                    }
                };
                return self.move_point(moving, target, r);
            }
        }
        false
    }

    /// Whether the cluster of point `moving`, free to move, has a coincidence with a known
    /// point still to come: it pins the cluster at that point (a pivot), which a distance taken
    /// first would only put on a sphere, leaving a cluster no locus then reaches (an arm's rod
    /// taken before its hinge). The distance waits; the coincidence moves the cluster, and
    /// the distance is tried again.
    fn pinned_later(&self, moving: GeomId) -> bool {
        let k = self.cluster(moving);
        if !self.clusters[k].record.loose() {
            return false;
        }
        self.pending.iter().any(|p| match p.relation {
            Relation::PointPoint { a, b, d: None } => [(a, b), (b, a)]
                .iter()
                .any(|&(x, y)| self.cluster(x) == k && self.cluster(y) != k && self.point_known(y)),
            _ => false,
        })
    }

    /// Point `p` at distance `l` from the line through `base` along `dir`: the point onto the
    /// cylinder about the known line, or the line moved or turned to pass at that distance from
    /// the known point.
    fn action_point_line_at(
        &mut self,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        l: Length,
        r: &Rel,
    ) -> bool {
        // At a distance from a known line: on the cylinder about it.
        if self.point_known(base) && self.dir_known(dir) && !self.point_known(p) {
            let c = self.cylinder_about(base, dir, l);
            return self.move_point(p, Target::On(Locus::Cylinder(c)), r);
        }
        // The line moves, its direction known: its point slides onto the cylinder of
        // that radius about the line through the known point along it (a point sliding
        // along the line moves nothing).
        if self.point_known(p) && self.dir_known(dir) && self.together(base, dir) {
            let c = self.cylinder_about(p, dir, l);
            // Its point held in a plane that holds its direction (a line in a circle's
            // plane): the plane cuts the cylinder in two lines along the direction, and
            // the point goes to the nearer of the branch's.
            if let Some(q) = self.plane_along(base, dir) {
                return self.onto_cylinder_lines(q, c, base, r);
            }
            return self.move_point(base, Target::On(Locus::Cylinder(c)), r);
        }
        // The line turns about an axis through a point of it that is known: it turns
        // until it passes at the distance from the known point.
        if self.point_known(p) && !self.dir_known(dir) && self.together(base, dir) {
            return self.turn_line_past(base, dir, p, l, r);
        }
        false
    }

    /// Point `p` on the line through `base` along `dir`: the point onto the known line, or the
    /// line slid, turned or moved through the known point.
    fn action_point_line(&mut self, p: GeomId, base: GeomId, dir: GeomId, r: &Rel) -> bool {
        if self.point_known(base) && self.dir_known(dir) && !self.point_known(p) {
            let (b, d) = (self.point(base), self.direction(dir));
            let words = format!(
                "the line through {} along {}",
                self.name(base),
                self.name(dir)
            );
            let l = self.line(b, d, words);
            return self.move_point(p, Target::On(Locus::Line(l)), r);
        }
        // The line moves: with its direction known, its point slides onto the line
        // through the known point along it.
        if self.point_known(p) && self.dir_known(dir) && self.together(base, dir) {
            let (x, d) = (self.point(p), self.direction(dir));
            let words = format!("the line through {} along {}", self.name(p), self.name(dir));
            let l = self.line(x, d, words);
            return self.move_point(base, Target::On(Locus::Line(l)), r);
        }
        // A line or segment through a known point (its own, or the point it is held
        // at), its direction not known: it turns about that point onto the line
        // through both, keeping its sense.
        let pivot = match self.record(base).trans {
            Trans::Pivot { at, .. } => Some(at),
            _ => None,
        };
        if self.point_known(p)
            && (pivot.is_some() || self.point_known(base))
            && self.together(base, dir)
            && matches!(self.record(base).shape, Shape::Line | Shape::Segment { .. })
        {
            let at = match pivot {
                Some(at) => at,
                None => self.point(base),
            };
            let (x, d) = (self.point(p), self.direction(dir));
            let (pname, lname) = (self.name(p), self.name(base));
            let words = format!("the direction from {lname}'s point to {pname}");
            let to = self.value(Op::DirectionTo { from: at, to: x }, Ty::Vector, words);
            let words = format!("that direction, or its opposite, nearer {lname}'s");
            let to = self.value(SpatialOp::Aligned { dir: to, near: d }, Ty::Vector, words);
            return self.turn_onto(dir, to, r, false);
        }
        // A line free to translate, its direction not known: it moves (across itself,
        // its point sliding along it moves nothing) through the known point, and may
        // then only turn about it.
        if self.point_known(p)
            && self.together(base, dir)
            && self.record(base).shape == Shape::Line
            && self.record(base).trans == Trans::Free
        {
            let x = self.point(p);
            return self.move_point(base, Target::Point(x), r);
        }
        false
    }

    /// Point `p` in the plane through `base` normal to `normal`, or at signed distance `d` from
    /// it: the point onto the known plane, or the plane slid or turned to hold the known point.
    fn action_point_plane(
        &mut self,
        p: GeomId,
        base: GeomId,
        normal: GeomId,
        d: Option<ExprId>,
        r: &Rel,
    ) -> bool {
        if let Some(q) = self.pivot_in_plane(r, p, normal) {
            // The line lies in the plane once its pivot does: a check of the pivot.
            let relation = Relation::PointPlane {
                p: q,
                base,
                normal,
                d,
            };
            self.check(&Rel { relation, ..*r });
            return true;
        }
        if self.point_known(base) && self.dir_known(normal) && !self.point_known(p) {
            let (b, n) = (self.point(base), self.direction(normal));
            let offset = d.map(|e| self.expr(e));
            let words = self.plane_words(base, normal, offset);
            let q = self.value(
                SpatialOp::Plane {
                    point: b,
                    normal: n,
                    offset,
                },
                Ty::Plane,
                words,
            );
            return self.move_point(p, Target::On(Locus::Plane(q)), r);
        }
        // The plane moves: with its normal known, its point slides onto the plane
        // through the known point, moved back by the distance.
        if self.point_known(p) && self.dir_known(normal) && self.together(base, normal) {
            let (x, n) = (self.point(p), self.direction(normal));
            let offset = d.map(|e| {
                let v = self.expr(e);
                let words = format!("minus {}", self.word(v));
                self.value(Op::Neg(v), Ty::Scalar, words)
            });
            let words = format!(
                "the plane through {} normal to {}{}",
                self.name(p),
                self.name(normal),
                offset.map_or(String::new(), |o| format!(" moved {}", self.word(o)))
            );
            let q = self.value(
                SpatialOp::Plane {
                    point: x,
                    normal: n,
                    offset,
                },
                Ty::Plane,
                words,
            );
            return self.move_point(base, Target::On(Locus::Plane(q)), r);
        }
        // A plane whose normal still turns: held at the distance from the point, then
        // turned about it.
        if self.point_known(p)
            && self.together(base, normal)
            && self.record(base).shape == Shape::Plane
        {
            return self.plane_at_distance(base, normal, p, d, r);
        }
        false
    }

    /// Directions `u` and `v` parallel, in `sense`: the one not known turned onto the known one
    /// (or its opposite).
    fn action_parallel(&mut self, u: GeomId, v: GeomId, sense: f64, r: &Rel) -> bool {
        for (known, moving) in [(u, v), (v, u)] {
            if self.dir_known(known) && !self.dir_known(moving) {
                let k = self.direction(known);
                let target = if sense < 0.0 {
                    self.in_sense(k, known, sense)
                } else if sense == 0.0 {
                    // Either sense: the nearer (the least turn).
                    let now = self.direction(moving);
                    let words = format!(
                        "{} or its opposite, nearer {}",
                        self.name(known),
                        self.name(moving)
                    );
                    self.value(SpatialOp::Aligned { dir: k, near: now }, Ty::Vector, words)
                } else {
                    k
                };
                // Only a turn about an axis has its angle decided by the x axis too.
                let about_axis = matches!(
                    self.clusters[self.cluster(moving)].record.turn,
                    Turn::Axis { feature, .. } if feature != Some(moving)
                );
                let x = if about_axis {
                    self.twin_x_axes(r, moving, target)
                } else {
                    None
                };
                return self.turn_onto_with(moving, target, x, r, false);
            }
        }
        false
    }

    /// Point `p` on circle `circle`, or at distance `d` from it: the circle moved or sized to
    /// pass the known point, or the point onto the known circle or the torus about it.
    fn action_point_circle(
        &mut self,
        p: GeomId,
        circle: GeomId,
        d: Option<ExprId>,
        r: &Rel,
    ) -> bool {
        let rec = self.record(circle);
        let moves = !rec.grounded() || rec.shape.size_free();
        if d.is_none() && self.point_known(p) && moves && self.circle_through(circle, p, r) {
            return true;
        }
        if self.point_known(p) && !self.record(circle).grounded() {
            return self.carry_circle(circle, p, d, r)
                || d.is_some_and(|d| self.tilt_circle(circle, p, d, r));
        }
        if !self.record(circle).grounded() || self.point_known(p) {
            return false;
        }
        let (center, normal, radius) = self.circle_parts(circle);
        let words = self.name(circle);
        let locus = self.value(
            SpatialOp::Circle3 {
                center,
                normal,
                radius,
            },
            Ty::Circle,
            words,
        );
        // At a distance from the circle: on the torus about it.
        let target = match d {
            None => Locus::Circle(locus),
            Some(e) => {
                let tube = self.expr(e);
                let words = format!(
                    "the torus at {} from {}",
                    self.word(tube),
                    self.name(circle)
                );
                Locus::Torus(self.value(
                    SpatialOp::Torus {
                        circle: locus,
                        tube,
                    },
                    Ty::Torus,
                    words,
                ))
            }
        };
        self.move_point(p, Target::On(target), r)
    }

    /// Directions `u` and `v` at `angle`: the one not known turned onto the cone about the known
    /// one, or about its axis to the angle.
    fn action_angle(&mut self, u: GeomId, v: GeomId, angle: AngleValue, r: &Rel) -> bool {
        for (known, moving) in [(u, v), (v, u)] {
            if self.dir_known(known) && !self.dir_known(moving) {
                return self.turn_onto_cone(known, moving, angle, r)
                    || self.turn_to_angle(known, moving, angle, r);
            }
        }
        false
    }

    /// A twist of `v` from `u` about `axis` by `angle` (offset_x, prismatic, weld): the x axis not
    /// known turned about the z axis to the known one turned by the angle.
    fn action_twist(
        &mut self,
        axis: GeomId,
        u: GeomId,
        v: GeomId,
        angle: Option<ExprId>,
        r: &Rel,
    ) -> bool {
        // The second marker's x axis turns about the first's z to the first's x turned
        // by the angle; or the first's to the second's turned back.
        if self.dir_known(axis) && self.dir_known(u) && !self.dir_known(v) {
            let (a, x) = (self.direction(axis), self.direction(u));
            let by = self.angle(angle);
            let about = self.name(axis);
            let target = self.twist_target((u, x), (a, about), by, false);
            return self.turn_onto(v, target, r, true);
        }
        if self.dir_known(v) && !self.dir_known(u) {
            let (a, x) = (self.direction(axis), self.direction(v));
            let by = self.angle(angle);
            let about = self.name(axis);
            let target = self.twist_target((v, x), (a, about), by, true);
            return self.turn_onto(u, target, r, true);
        }
        false
    }

    /// Whether the advance along `axis` of point `q` (a helix's second marker, `v` its x axis)
    /// is held by its cluster's record though `q` still moves: the cluster turns only about an
    /// axis along the joint's z axes (its own z axis along the helix's held by the joint, not
    /// pending), and slides only across it (held at a pivot, or in a plane square to the
    /// axis). The advance then fixes the turn, which the helix takes, and leaves the slide.
    fn advance_held(&self, axis: GeomId, (v, q): (GeomId, GeomId), r: &Rel) -> bool {
        let Some(z) = self.model.part(q, gcs_lang::model::Part::AxisZ) else {
            return false;
        };
        let rec = self.record(q);
        let along = matches!(rec.turn, Turn::Axis { feature: Some(f), .. }
            if f == z || super::same_direction(self.model, f, z));
        let parallel_pending = self.pending.iter().any(|p| {
            p.constraint == r.constraint
                && matches!(p.relation, Relation::Parallel { u, v: w, .. }
                    if [u, w].contains(&axis) || [u, w].contains(&z))
        });
        let across = match rec.trans {
            Trans::Pivot { .. } | Trans::Fixed => true,
            Trans::On {
                locus: Locus::Plane(plane),
                ..
            } => self.across_turn_axis(rec, plane),
            _ => false,
        };
        along && !parallel_pending && across && self.cluster(v) == self.cluster(q)
    }

    /// A helical joint's coupling of turn and advance about `axis`: one side known, the other
    /// placed along the axis for its turn (the advance nearest where it is: the turns are a
    /// pitch apart), or turned about the axis for its advance.
    fn helix(
        &mut self,
        axis: GeomId,
        (u, p): (GeomId, GeomId),
        (v, q): (GeomId, GeomId),
        pitch: gcs_lang::expr::ExprId,
        r: &Rel,
    ) -> bool {
        if !(self.dir_known(axis) && self.dir_known(u) && self.point_known(p)) {
            return false;
        }
        let (z, x, at) = (self.direction(axis), self.direction(u), self.point(p));
        let pitch = self.expr(pitch);
        let (qname, vname) = (self.name(q), self.name(v));
        if self.dir_known(v) && !self.point_known(q) {
            // Turned: slide to the advance of that turn nearest where it is.
            let to = self.point(q);
            let w = self.direction(v);
            let words = format!("the advance of {qname} along {}", self.name(axis));
            let now = self.value(
                Op::Along {
                    from: at,
                    dir: z,
                    to,
                },
                Ty::Scalar,
                words,
            );
            let words = format!("the turn of {vname} about {}", self.name(axis));
            let turn = self.value(
                SpatialOp::AngleAbout {
                    u: x,
                    v: w,
                    axis: z,
                },
                Ty::Scalar,
                words,
            );
            let words = format!("the advance of that turn nearest {qname}'s");
            let advance = self.value(
                SpatialOp::HelixAdvance { now, turn, pitch },
                Ty::Scalar,
                words,
            );
            let words = format!(
                "the plane across {} at that advance from {}",
                self.name(axis),
                self.name(p)
            );
            let plane = self.value(
                SpatialOp::Plane {
                    point: at,
                    normal: z,
                    offset: Some(advance),
                },
                Ty::Plane,
                words,
            );
            return self.move_point(q, Target::On(Locus::Plane(plane)), r);
        }
        if (self.point_known(q) || self.advance_held(axis, (v, q), r)) && !self.dir_known(v) {
            // Placed along the axis, or held at its advance: turn to that advance's angle.
            let to = self.point(q);
            let words = format!("the advance of {qname} along {}", self.name(axis));
            let advance = self.value(
                Op::Along {
                    from: at,
                    dir: z,
                    to,
                },
                Ty::Scalar,
                words,
            );
            let words = "the turn of that advance".to_string();
            let turn = self.value(SpatialOp::HelixTurn { advance, pitch }, Ty::Scalar, words);
            let words = format!(
                "{} turned by that angle about {}",
                self.name(u),
                self.name(axis)
            );
            let target = self.value(
                SpatialOp::TurnedAbout {
                    dir: x,
                    axis: z,
                    angle: turn,
                },
                Ty::Vector,
                words,
            );
            return self.turn_onto(v, target, r, true);
        }
        false
    }
}
