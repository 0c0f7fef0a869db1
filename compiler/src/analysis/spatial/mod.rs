//! Space's module of the analysis: the geometry vocabulary of 3d models, after TLA (003).
//!
//! A cluster's record is TLA's: its translational DOF with the invariant point or the locus
//! a feature is held on ([`Trans`]: free, a feature on a line, circle, plane or sphere, a
//! pivot, fixed) and its rotational DOF with the invariant axis ([`Turn`]: free, about one
//! axis, known). Action analysis moves the side of a relation that is not known with the
//! freedom its record leaves, by the brick's fragments: translate a point onto a point or
//! the nearest point of a locus; rotate about the pivot around `v1 x v2` (the shortest turn)
//! to bring a point onto a point or onto where its sphere meets a locus; rotate about the
//! invariant axis by the angle between perpendiculars; turn a direction onto a direction, or
//! about the axis to it; slide a feature along its locus to where it meets another. The same
//! point on two loci of space is where they meet (the runtime's 3d intersection table), with
//! a branch variable where there are two roots.
//!
//! Covered so far: bodies with markers and member points, free points and vectors, against
//! fixed points, lines, planes and other bodies, with coincident, distance (point-point,
//! point-plane), `on` (a point on a line or plane), in-line, in-plane, parallel-z, offset-x
//! and the lower pairs built of them (revolute, prismatic, cylindrical, spherical, planar).
//! What is not (angles between directions of space, helical joints, segments, circles and
//! planes that move, loops of partially fixed bodies, defaults) is reported per constraint,
//! never dropped.

mod check;
mod joint;
mod locus;
mod point;
mod record;
pub mod relation;
mod turn;

use super::driver::Builder;
use super::geometry::{self, Geometry, Invariants};
use super::Unsupported;
use crate::config::{Config, D3};
use crate::plan::{Meet, Op, Reg, Residual, RotationAxis, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part, Sketch};
use gcs_lang::Model;
use gcs_runtime::tol;
pub use record::{Locus, Record, Shape, Trans, Turn};
use relation::{AngleValue, Relation};

/// A relation of space with its constraint.
pub(crate) type Rel = geometry::Rel<Relation>;

/// The geometry of space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spatial;

impl Geometry for Spatial {
    type Record = Record;
    type Relation = Relation;

    /// SOLVE-LOOP's limit in space (000, Appendix A.2).
    const MAX_LOOP: usize = 6;

    fn decompose(model: &Model) -> Result<(Vec<Rel>, Vec<Unsupported>), String> {
        let params = model.default_params();
        let sketch = Config::<D3>::from_sketch(model, &params).map_err(|b| {
            format!(
                "the sketch of `{}` is invalid: {}",
                model.geoms[b.geom].name, b.what
            )
        })?;
        Ok(relation::decompose(model, &sketch))
    }

    fn features(relation: &Relation) -> Vec<GeomId> {
        relation.features()
    }

    fn is_dimension(_: &Relation) -> bool {
        false
    }

    fn record(model: &Model, g: GeomId) -> Record {
        Record::new(model, g)
    }

    fn action(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.action(r)
    }

    fn implied(b: &Builder<'_, Self>, r: &Relation) -> bool {
        b.implied(r)
    }

    fn locus(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.locus(r)
    }

    fn residual(b: &mut Builder<'_, Self>, relation: &Relation) -> Residual {
        b.residual(relation)
    }

    fn ground(b: &mut Builder<'_, Self>) {
        b.ground_if_nothing_fixed();
    }

    fn default(b: &mut Builder<'_, Self>, candidates: &[usize]) -> bool {
        candidates.iter().any(|&k| b.default_on(k))
    }
}

/// A member point's or marker's constant local coordinates in its body.
fn local_point(model: &Model, f: GeomId) -> Option<[f64; 3]> {
    let g = &model.geoms[f];
    let Owner::Member(_) = g.owner else {
        return None;
    };
    match &g.sketch {
        Sketch::Point(c) | Sketch::Marker { origin: c, .. } => constant(model, c),
        _ => None,
    }
}

/// A direction feature's constant local direction in its body (not normalized): a member
/// vector, or a marker's z axis or its x axis made perpendicular to z.
fn local_dir(model: &Model, v: GeomId) -> Option<[f64; 3]> {
    let g = &model.geoms[v];
    match (g.owner, &g.sketch) {
        (Owner::Member(_), Sketch::Vector(c)) => constant(model, c),
        (Owner::Part(marker, part), _) => {
            let Sketch::Marker { z, x, .. } = &model.geoms[marker].sketch else {
                return None;
            };
            let z = constant(model, z.as_ref()?)?;
            match part {
                Part::AxisZ => Some(z),
                Part::AxisX => {
                    let x = constant(model, x)?;
                    let k = dot(x, z) / dot(z, z);
                    Some([x[0] - k * z[0], x[1] - k * z[1], x[2] - k * z[2]])
                }
                _ => None,
            }
        }
        _ => None,
    }
}

fn constant(model: &Model, c: &[gcs_lang::expr::ExprId]) -> Option<[f64; 3]> {
    if !c.iter().all(|&e| model.exprs.is_constant(e)) {
        return None;
    }
    let v = |i: usize| c.get(i).map_or(0.0, |&e| model.exprs.eval(e, &[]));
    Some([v(0), v(1), v(2)])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether `a` and `b` are parallel (either sense), to rounding.
fn parallel(a: [f64; 3], b: [f64; 3]) -> bool {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    dot(c, c).sqrt() <= tol::ANGLE * dot(a, a).sqrt() * dot(b, b).sqrt()
}

/// Whether direction features `a` and `b` of one body are parallel in it, whatever it does.
fn same_direction(model: &Model, a: GeomId, b: GeomId) -> bool {
    model.top_level_of(a) == model.top_level_of(b)
        && matches!((local_dir(model, a), local_dir(model, b)), (Some(u), Some(v)) if parallel(u, v))
}

/// Whether point `f` lies on the axis through point `g` along direction `a`, all of one body.
fn on_axis(model: &Model, g: GeomId, a: GeomId, f: GeomId) -> bool {
    let top = model.top_level_of(g);
    if model.top_level_of(a) != top || model.top_level_of(f) != top {
        return false;
    }
    match (
        local_point(model, g),
        local_point(model, f),
        local_dir(model, a),
    ) {
        (Some(p), Some(q), Some(d)) => {
            let w = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            dot(w, w) == 0.0 || parallel(w, d)
        }
        _ => false,
    }
}

/// Where a point feature must go.
#[derive(Clone, Copy, Debug)]
enum Target {
    /// A known point.
    Point(Reg),
    /// A locus.
    On(Locus),
}

impl Builder<'_, Spatial> {
    /// Whether direction feature `v` is invariant.
    fn dir_known(&self, v: GeomId) -> bool {
        let rec = self.record(v);
        rec.grounded()
            || rec.turn == Turn::Known
            || matches!(rec.turn, Turn::Axis { feature: Some(f), .. }
                if f == v || same_direction(self.model, f, v))
    }

    /// Whether features `a` and `b` move together (one cluster: rigid).
    fn together(&self, a: GeomId, b: GeomId) -> bool {
        self.cluster(a) == self.cluster(b)
    }

    /// Action analysis: the relation's unknown side moved onto its known side.
    fn action(&mut self, r: &Rel) -> bool {
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
            Relation::SameSize { a, b } => {
                for (known, free) in [(a, b), (b, a)] {
                    if !self.record(known).shape.size_free() && self.record(free).shape.size_free()
                    {
                        let size = self.size_of(known);
                        return self.set_size(free, size, r);
                    }
                }
                false
            }
            Relation::PointPoint { a, b, d } => {
                for (known, moving) in [(a, b), (b, a)] {
                    if self.point_known(known) && !self.point_known(moving) {
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
                                    self.value(Op::Sphere { center: x, radius }, Ty::Sphere, words);
                                Target::On(Locus::Sphere(s))
                            }
                        };
                        return self.move_point(moving, target, r);
                    }
                }
                false
            }
            Relation::PointLine {
                p,
                base,
                dir,
                d: Some(l),
            } => {
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
            Relation::PointLine { p, base, dir, .. } => {
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
                    let words =
                        format!("the line through {} along {}", self.name(p), self.name(dir));
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
                    let to = self.value(Op::Aligned { dir: to, near: d }, Ty::Vector, words);
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
            Relation::PointPlane { p, base, normal, d } => {
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
                        Op::Plane {
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
                        Op::Plane {
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
            Relation::Parallel { u, v, sense } => {
                for (known, moving) in [(u, v), (v, u)] {
                    if self.dir_known(known) && !self.dir_known(moving) {
                        let k = self.direction(known);
                        let target = if sense < 0.0 {
                            let words = format!("the opposite of {}", self.name(known));
                            self.value(Op::Opposite(k), Ty::Vector, words)
                        } else if sense == 0.0 {
                            // Either sense: the nearer (the least turn).
                            let now = self.direction(moving);
                            let words = format!(
                                "{} or its opposite, nearer {}",
                                self.name(known),
                                self.name(moving)
                            );
                            self.value(Op::Aligned { dir: k, near: now }, Ty::Vector, words)
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
            Relation::PointCircle { p, circle, d } => {
                let rec = self.record(circle);
                let moves = !rec.grounded() || rec.shape.size_free();
                if d.is_none() && self.point_known(p) && moves && self.circle_through(circle, p, r)
                {
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
                    Op::Circle3 {
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
                            Op::Torus {
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
            Relation::Angle { u, v, angle } => {
                for (known, moving) in [(u, v), (v, u)] {
                    if self.dir_known(known) && !self.dir_known(moving) {
                        return self.turn_onto_cone(known, moving, angle, r)
                            || self.turn_to_angle(known, moving, angle, r);
                    }
                }
                false
            }
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
            Relation::Twist { axis, u, v, angle } => {
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
        }
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
                Op::AngleAbout {
                    u: x,
                    v: w,
                    axis: z,
                },
                Ty::Scalar,
                words,
            );
            let words = format!("the advance of that turn nearest {qname}'s");
            let advance = self.value(Op::HelixAdvance { now, turn, pitch }, Ty::Scalar, words);
            let words = format!(
                "the plane across {} at that advance from {}",
                self.name(axis),
                self.name(p)
            );
            let plane = self.value(
                Op::Plane {
                    point: at,
                    normal: z,
                    offset: Some(advance),
                },
                Ty::Plane,
                words,
            );
            return self.move_point(q, Target::On(Locus::Plane(plane)), r);
        }
        if self.point_known(q) && !self.dir_known(v) {
            // Placed along the axis: turn to that advance's angle.
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
            let turn = self.value(Op::HelixTurn { advance, pitch }, Ty::Scalar, words);
            let words = format!(
                "{} turned by that angle about {}",
                self.name(u),
                self.name(axis)
            );
            let target = self.value(
                Op::TurnedAbout {
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

    /// A plane `q` (its normal `normal`) to be at signed distance `d` from known point `p`,
    /// its normal not known: free, it slides along its normal to that distance, and may then
    /// only turn about `p` (which keeps it); about a point, it turns the least onto the cone of
    /// normals that also keep `p`'s distance, and may then only turn about the line from
    /// there to `p`; about that line, it turns to where the cone meets its turn (a branch).
    /// Three points at known distances place a plane (004's point-plane cluster) in closed form.
    fn plane_at_distance(
        &mut self,
        q: GeomId,
        normal: GeomId,
        p: GeomId,
        d: Option<gcs_lang::expr::ExprId>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(q);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let (qname, pname, c) = (self.name(q), self.name(p), self.cname(r.constraint));
        let dist = match d {
            Some(e) => self.expr(e),
            None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
        };
        match (rec.trans, rec.turn) {
            (Trans::Free, _) => {
                let (x, n) = (self.point(p), self.direction(normal));
                let words = format!("minus {}", self.word(dist));
                let back = self.value(Op::Neg(dist), Ty::Scalar, words);
                let words = format!("{qname} moved along its normal to its distance from {pname}");
                let target = self.value(
                    Op::Plane {
                        point: x,
                        normal: n,
                        offset: Some(back),
                    },
                    Ty::Plane,
                    words,
                );
                let from = self.point(q);
                let words = format!("the point of that plane nearest {qname}'s");
                let to = self.value(
                    Op::Nearest {
                        locus: target,
                        point: from,
                    },
                    Ty::Point,
                    words,
                );
                let explain = format!(
                    "{qname} is free to move along its normal: move it so that {pname} is at its distance from it ({c}); it may then only turn about {pname}."
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.trans = Trans::Pivot { at: x, feature: p };
                true
            }
            (Trans::Pivot { at, feature }, Turn::Free) if feature != p => {
                let (b, n, x) = (self.point(q), self.direction(normal), self.point(p));
                let words = format!(
                    "the normal {qname} takes, turned the least about {}, to be at its distance from {pname}",
                    self.word(at)
                );
                let to = self.value(
                    Op::PlaneTurn {
                        base: b,
                        normal: n,
                        pivot: at,
                        point: x,
                        d: dist,
                        constraint: r.constraint,
                    },
                    Ty::Vector,
                    words,
                );
                let explain = format!(
                    "{qname} may only turn about {}: turn it the least so that {pname} is at its distance from it ({c}); it may then only turn about the line through both.",
                    self.word(at)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Shortest,
                        from: n,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let words = format!("the line from {} through {pname}", self.word(at));
                let axis = self.value(Op::DirectionTo { from: at, to: x }, Ty::Vector, words);
                self.clusters[k].record.turn = Turn::Axis {
                    axis,
                    feature: None,
                };
                true
            }
            (Trans::Pivot { at, feature }, Turn::Axis { axis, .. }) if feature != p => {
                let (b, n, x) = (self.point(q), self.direction(normal), self.point(p));
                let meanings = vec![
                    format!(
                        "{qname}'s normal turned counter-clockwise about {} from its turn nearest the direction to {pname}",
                        self.word(axis)
                    ),
                    "turned clockwise from there".to_string(),
                ];
                let branch = self.branch(r.constraint, meanings);
                let words = format!(
                    "the normal {qname} takes, turned about {}, to be at its distance from {pname}",
                    self.word(axis)
                );
                let to = self.value(
                    Op::PlaneAxisTurn {
                        base: b,
                        normal: n,
                        pivot: at,
                        point: x,
                        d: dist,
                        axis,
                        branch,
                        constraint: r.constraint,
                    },
                    Ty::Vector,
                    words,
                );
                let explain = format!(
                    "{qname} may only turn about {}: turn it so that {pname} is at its distance from it ({c}).",
                    self.word(axis)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Along(axis),
                        from: n,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.turn = Turn::Known;
                rec.trans = Trans::Fixed;
                true
            }
            _ => false,
        }
    }

    /// `midpoint(p, s)`, `a` and `b` the ends of `s`: with both ends known, `p` goes to their
    /// midpoint; with `p` and one end known, the other end goes to that end reflected through
    /// `p`.
    fn midpoint(&mut self, p: GeomId, a: GeomId, b: GeomId, r: &Rel) -> bool {
        let sname = self.name(self.model.top_level_of(a));
        let (ka, kb) = (self.point_known(a), self.point_known(b));
        if ka && kb && !self.point_known(p) {
            let (pa, pb) = (self.point(a), self.point(b));
            let words = format!("the midpoint of {sname}");
            let mid = self.value(Op::Midpoint { a: pa, b: pb }, Ty::Point, words);
            return self.move_point(p, Target::Point(mid), r);
        }
        if self.point_known(p) && ka != kb {
            let (known, free) = if ka { (a, b) } else { (b, a) };
            let (from, at) = (self.point(known), self.point(p));
            let words = format!("{} reflected through {}", self.name(known), self.name(p));
            let op = Op::Reflect {
                point: from,
                through: at,
            };
            let x = self.value(op, Ty::Point, words);
            return self.move_point(free, Target::Point(x), r);
        }
        false
    }

    /// `symmetric(p, q, plane)`: with the plane known, the one of `p` and `q` not known goes
    /// to the other's mirror image across it (a mirror is its own inverse).
    fn mirror(&mut self, p: GeomId, q: GeomId, (base, normal): (GeomId, GeomId), r: &Rel) -> bool {
        if !(self.point_known(base) && self.dir_known(normal)) {
            return false;
        }
        for (known, free) in [(p, q), (q, p)] {
            if self.point_known(known) && !self.point_known(free) {
                let (at, b, n) = (self.point(known), self.point(base), self.direction(normal));
                let words = format!(
                    "the mirror image of {} across {}",
                    self.name(known),
                    self.plane_words(base, normal, None)
                );
                let op = Op::MirrorPlane {
                    point: at,
                    base: b,
                    normal: n,
                };
                let image = self.value(op, Ty::Point, words);
                return self.move_point(free, Target::Point(image), r);
            }
        }
        false
    }

    /// Whether a relation has turned direction `dir` square to direction `normal` (a line
    /// into a circle's plane, `relation::decompose`).
    fn made_square(&self, dir: GeomId, normal: GeomId) -> bool {
        self.is_done(&Relation::Angle {
            u: dir,
            v: normal,
            angle: AngleValue::Const(std::f64::consts::FRAC_PI_2),
        })
    }

    /// The plane that holds point `base` (its record's locus) when that plane is known to hold
    /// direction `dir` too: its normal is a direction a relation already turned `dir` square
    /// to (a line in a circle's plane).
    fn plane_along(&self, base: GeomId, dir: GeomId) -> Option<Reg> {
        let Trans::On {
            feature,
            locus: Locus::Plane(q),
        } = self.record(base).trans
        else {
            return None;
        };
        let defined = |reg: Reg| {
            (self.plan.steps.iter().rev())
                .find(|s| s.out.is_some_and(|(o, _)| o == reg))
                .map(|s| &s.op)
        };
        let Some(Op::Plane { normal, .. }) = defined(q) else {
            return None;
        };
        let Some(&Op::DirOf(m)) = defined(*normal) else {
            return None;
        };
        (feature == base && self.made_square(dir, m)).then_some(q)
    }

    /// Moves the line whose point `base` is held in plane `q`, parallel to cylinder `c`'s axis
    /// (the line's direction), onto the cylinder: the plane cuts it in two lines along the
    /// direction (a branch), and the line slides across itself within the plane onto one, which
    /// places it.
    fn onto_cylinder_lines(&mut self, q: Reg, c: Reg, base: GeomId, r: &Rel) -> bool {
        let k = self.cluster(base);
        if !self.clusters[k].record.movable() {
            return false;
        }
        let (wq, wc) = (self.word(q), self.word(c));
        let meanings = vec![
            format!("the line where {wq} cuts {wc} first across its axis"),
            "the other line, second across the axis".to_string(),
        ];
        let branch = self.branch(r.constraint, meanings);
        let from = self.point(base);
        let words = format!("the line where {wq} cuts {wc}");
        let line = self.value(
            Op::Intersect {
                meet: Meet::PlaneCylinder,
                a: q,
                b: c,
                branch,
                constraint: r.constraint,
                near: from,
            },
            Ty::Line,
            words,
        );
        let bname = self.name(base);
        let words = format!("the point of {} nearest {bname}", self.word(line));
        let to = self.value(
            Op::Nearest {
                locus: line,
                point: from,
            },
            Ty::Point,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        let explain = format!(
            "{} can only slide {bname} in {wq}: slide it onto {} ({}).",
            self.group_name(&geoms),
            self.word(line),
            self.cname(r.constraint)
        );
        self.emit(
            Op::Translate { geoms, from, to },
            None,
            self.satisfies(r),
            explain,
        );
        self.placed(k, base, to, Target::On(Locus::Line(line)));
        true
    }

    /// For a line's point `p` that must lie in a plane of normal `normal` (a line in a
    /// circle's plane, `r`'s relation): the other point of the line its cluster pivots about,
    /// when the cluster only turns about that normal and the same constraint has already turned
    /// the line square to it. Every point of the line then stays at the pivot's height along
    /// the normal, whatever the turn and the segment's length, so the relation holds exactly
    /// when the pivot lies in the plane: no motion can bring it about, and none is needed.
    fn pivot_in_plane(&mut self, r: &Rel, p: GeomId, normal: GeomId) -> Option<GeomId> {
        let k = self.cluster(p);
        let rec = self.clusters[k].record.clone();
        let (Trans::Pivot { feature: q, .. }, Turn::Axis { axis, .. }) = (rec.trans, rec.turn)
        else {
            return None;
        };
        let line = self.model.top_level_of(p);
        let line_like = matches!(
            self.model.geoms[line].kind,
            GeomKind::Line | GeomKind::Segment
        );
        if q == p || !line_like || self.model.top_level_of(q) != line || !self.dir_known(normal) {
            return None;
        }
        // The line's constraint with a circle (`relation::decompose`), its direction already
        // turned square to the normal.
        let c = &self.model.constraints[r.constraint];
        use gcs_lang::constraints::ConstraintKind as K;
        let with_circle = matches!(c.kind, K::Distance | K::Tangent)
            && c.args.first() == Some(&line)
            && (c.args.get(1)).is_some_and(|&b| self.model.geoms[b].kind == GeomKind::Circle);
        let dir = self.model.dir_feature(line)?;
        (with_circle && self.made_square(dir, normal) && self.direction(normal) == axis)
            .then_some(q)
    }

    /// One default on cluster `k` (000, section 5.2.1), each with its geometric meaning and
    /// a sketch value that moves nothing (least motion): a feature's place along the line or
    /// circle it is held on; a turn about the one axis left (the idle spin of an RSSR's
    /// coupler about its own line); a free point's coordinates; a body's turns about the
    /// world's axes through its pivot or the feature it holds on a locus. A translation left
    /// on a plane or sphere with the orientation known, and a free direction, have none yet.
    fn default_on(&mut self, k: usize) -> bool {
        let rec = self.clusters[k].record.clone();
        if !rec.movable() {
            return false;
        }
        match (rec.trans, rec.turn) {
            // A segment's length or a circle's radius first, while the record still says which
            // point is held (a new length keeps the start: a held end is moved back).
            _ if rec.shape.size_free() && !self.size_pending(k) => self.size_default(k),
            // A direction's free turn: two turns across it (a third, about itself, would
            // move nothing).
            (_, Turn::Free) if rec.shape.one_direction() => self.orient_direction(k),
            (
                Trans::On {
                    feature,
                    locus: locus @ (Locus::Line(_) | Locus::Circle(_)),
                },
                _,
            ) => self.slide(k, feature, locus),
            (_, Turn::Axis { axis, .. }) => self.spin(k, axis),
            // A line whose direction is known: its place across itself, two coordinates on the
            // plane through its point across it (sliding along itself moves nothing).
            (Trans::Free, _) if rec.shape == Shape::Line => self.place_across(k),
            // A plane whose normal is known: its place along its normal (sliding within
            // itself moves nothing).
            (Trans::Free, _) if rec.shape == Shape::Plane => self.place_along_normal(k),
            (Trans::Free, _) => self.place(k),
            // Held on a surface with nothing left to turn: its two coordinates on it.
            (
                Trans::On {
                    feature,
                    locus:
                        locus @ (Locus::Plane(_)
                        | Locus::Sphere(_)
                        | Locus::Cylinder(_)
                        | Locus::Torus(_)),
                },
                Turn::Known | Turn::None,
            ) => self.place_on(k, feature, locus),
            // About a pivot, or a feature held on a plane or sphere: its turns first (the
            // feature stays on its locus), then what the constraints can do with them.
            (_, Turn::Free) if rec.shape == Shape::Body => self.orient(k),
            _ => false,
        }
    }

    fn assume(meaning: &str, name: &str) -> String {
        format!(
            "No constraint, chain or loop fixes this yet: assume {meaning} is the default `{name}` (the sketch's value unless given)"
        )
    }

    /// A sized circle whose normal is known and whose centre is free carried (by the least
    /// translation) to pass through known point `p`, or at distance `d` from it: its centre
    /// goes onto the circle of its radius about `p` in a plane parallel to its own, or onto the
    /// torus at `d` about that circle (a circle's distance from a point is the centre's from
    /// that circle, turned about `p`'s axis). Turning it, or resizing it, would move the point
    /// off it in a way its record cannot follow: a circle whose size or normal is free is not
    /// carried (its size's default comes first; a free normal, not yet).
    fn carry_circle(
        &mut self,
        circle: GeomId,
        p: GeomId,
        d: Option<gcs_lang::expr::ExprId>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let Some(center) = self.model.part(circle, Part::Center) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.turn != Turn::Known
            || rec.shape.size_free()
            || self.point_known(center)
        {
            return false;
        }
        let at = self.point(p);
        let (_, normal, radius) = self.circle_parts(circle);
        let (cname, pname) = (self.name(circle), self.name(p));
        let words = format!("the circle of {cname}'s radius about {pname}, parallel to {cname}");
        let about = self.value(
            Op::Circle3 {
                center: at,
                normal,
                radius,
            },
            Ty::Circle,
            words,
        );
        let locus = match d {
            None => Locus::Circle(about),
            Some(e) => {
                let tube = self.expr(e);
                let words = format!("the torus at {} from {}", self.word(tube), self.word(about));
                Locus::Torus(self.value(
                    Op::Torus {
                        circle: about,
                        tube,
                    },
                    Ty::Torus,
                    words,
                ))
            }
        };
        self.move_point(center, Target::On(locus), r)
    }

    /// A sized circle held at its centre, free to turn, tilted the least about its centre so
    /// that known point `p` lies `d` from it: its normal onto the cone about the direction to
    /// `p` whose angle puts `p` there (`Op::TiltToDistance`, on the side of the plane `p` is
    /// on now). It may then only turn about the line from its centre to `p`.
    fn tilt_circle(
        &mut self,
        circle: GeomId,
        p: GeomId,
        d: gcs_lang::expr::ExprId,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let (Some(center), Some(normal)) = (
            self.model.part(circle, Part::Center),
            self.model.part(circle, Part::Normal),
        ) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.turn != Turn::Free
            || rec.shape.size_free()
            || !self.point_known(center)
        {
            return false;
        }
        let (c, at, n) = (self.point(center), self.point(p), self.direction(normal));
        let radius = self.size_of(circle);
        let d = self.expr(d);
        let (cname, pname, con) = (self.name(circle), self.name(p), self.cname(r.constraint));
        let words = format!("the direction from the centre of {cname} to {pname}");
        let toward = self.value(Op::DirectionTo { from: c, to: at }, Ty::Vector, words);
        let words = format!(
            "the angle from {cname}'s normal to {pname} that puts {pname} {} from it",
            self.word(d)
        );
        let angle = self.value(
            Op::TiltToDistance {
                centre: c,
                point: at,
                radius,
                d,
                now: n,
                constraint: r.constraint,
            },
            Ty::Scalar,
            words,
        );
        let words = format!("the normal nearest {}'s at that angle", self.name(normal));
        let explain = format!(
            "Tilt {cname} the least about its centre so that {pname} lies {} from it ({con}); it may then only turn about the line from its centre to {pname}.",
            self.word(d)
        );
        let satisfies = self.satisfies(r);
        self.turn_normal_onto_cone(k, (c, n), (toward, angle), words, explain, satisfies);
        true
    }

    /// Turns circle cluster `k` (its centre at `c`, its normal `n`) the least about its centre
    /// so that its normal makes `angle` with `toward`: onto the cone about `toward` nearest it
    /// (`Op::ConeTurn`). It may then only turn about `toward`.
    fn turn_normal_onto_cone(
        &mut self,
        k: usize,
        (c, n): (Reg, Reg),
        (toward, angle): (Reg, Reg),
        words: String,
        explain: String,
        satisfies: Vec<ConstraintId>,
    ) {
        let to = self.value(
            Op::ConeTurn {
                axis: toward,
                angle,
                dir: n,
            },
            Ty::Vector,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        self.emit(
            Op::RotateDir {
                geoms,
                pivot: c,
                axis: RotationAxis::Shortest,
                from: n,
                to,
            },
            None,
            satisfies,
            explain,
        );
        self.clusters[k].record.turn = Turn::Axis {
            axis: toward,
            feature: None,
        };
    }

    /// Circle `circle`, its centre held and its radius free, passes through the known point
    /// `p`: free to turn, it turns the least about its centre so that its plane holds the
    /// point (its normal onto the cone square to the direction from the centre to the point),
    /// and may then only turn about that direction; with its normal known, the point must lie
    /// in its plane (a check). Then it takes the radius that reaches the point.
    fn circle_through(&mut self, circle: GeomId, p: GeomId, r: &Rel) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let (Some(center), Some(normal)) = (
            self.model.part(circle, Part::Center),
            self.model.part(circle, Part::Normal),
        ) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.shape != (Shape::Circle { sized: false })
            || !self.point_known(center)
            || !matches!(rec.turn, Turn::Free | Turn::Known)
        {
            return false;
        }
        let (c, at, n) = (self.point(center), self.point(p), self.direction(normal));
        let (cname, pname, con) = (self.name(circle), self.name(p), self.cname(r.constraint));
        let words = format!("the direction from the centre of {cname} to {pname}");
        let toward = self.value(Op::DirectionTo { from: c, to: at }, Ty::Vector, words);
        if rec.turn == Turn::Free {
            let square = self.value(
                Op::Const(std::f64::consts::FRAC_PI_2),
                Ty::Scalar,
                "a right angle".into(),
            );
            let words = format!("the normal nearest {}'s square to it", self.name(normal));
            let explain = format!(
                "Rotate {cname} the least about its centre so that its plane holds {pname} ({con}); it may then only turn about the line from its centre to {pname}."
            );
            self.turn_normal_onto_cone(k, (c, n), (toward, square), words, explain, Vec::new());
        } else {
            let residual = Residual::PointPlane {
                p: at,
                base: c,
                normal: n,
                d: None,
            };
            let explain = format!("Check that {pname} lies in the plane of {cname} ({con}).");
            self.emit(
                Op::Check {
                    constraint: r.constraint,
                    residual,
                },
                None,
                Vec::new(),
                explain,
            );
        }
        let words = format!("the distance from the centre of {cname} to {pname}");
        let radius = self.value(
            Op::Along {
                from: c,
                dir: toward,
                to: at,
            },
            Ty::Scalar,
            words,
        );
        let explain = format!(
            "... and give {cname} the radius that reaches {pname}: {} ({con}).",
            self.word(radius)
        );
        let satisfies = self.satisfies(r);
        self.resize(circle, radius, None, explain, satisfies);
        self.clusters[k].record.shape = Shape::Circle { sized: true };
        true
    }

    /// The size of a segment or circle: its length or radius, as it is now.
    fn size_of(&mut self, g: GeomId) -> Reg {
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
    fn set_size(&mut self, seg: GeomId, length: Reg, r: &Rel) -> bool {
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

    /// The end of segment `seg` (of cluster `k`) that its record holds at a point, and where:
    /// a new length keeps the start, so that end must be moved back.
    fn held_end(&self, k: usize, seg: GeomId) -> Option<(GeomId, Reg)> {
        match self.clusters[k].record.trans {
            Trans::Pivot { at, feature } if Some(feature) == self.model.part(seg, Part::End) => {
                Some((feature, at))
            }
            _ => None,
        }
    }

    /// Whether a relation still to come can set the size of cluster `k`'s segment or circle
    /// (a length or radius, an `equal`, a point on the circle): its size then takes no
    /// default, so that the relation sets it rather than being closed by an iteration.
    fn size_pending(&self, k: usize) -> bool {
        let [g] = self.clusters[k].geoms[..] else {
            return false;
        };
        self.pending.iter().any(|p| match p.relation {
            Relation::Size { geom, .. } => geom == g,
            Relation::SameSize { a, b } => a == g || b == g,
            // A circle through a known point sets its radius once its centre is held
            // (`circle_through`); carried with its centre free, it keeps it.
            Relation::PointCircle {
                circle, d: None, ..
            } => {
                circle == g
                    && (self.model.part(circle, Part::Center)).is_some_and(|c| self.point_known(c))
            }
            _ => false,
        })
    }

    /// A segment's length or a circle's radius still free: a default, the size where the
    /// constraints leave it (least motion).
    fn size_default(&mut self, k: usize) -> bool {
        let [g] = self.clusters[k].geoms[..] else {
            return false;
        };
        let what = match self.clusters[k].record.shape {
            Shape::Circle { .. } => "radius",
            _ => "length",
        };
        let gname = self.name(g);
        let measure = self.size_of(g);
        let (name, meaning) = (format!("{gname}_{what}"), format!("the {what} of {gname}"));
        let size = self.default_value(g, name.clone(), meaning.clone(), measure);
        let held_end = self.held_end(k, g);
        let explain = format!(
            "{}: give {gname} that {what}.",
            Self::assume(&meaning, &name)
        );
        self.resize(g, size, held_end, explain, Vec::new());
        let rec = &mut self.clusters[k].record;
        rec.shape = rec.shape.sized();
        true
    }

    /// Sets segment `seg`'s length to `length` (which keeps its start), then, when its end is
    /// the point held (`held_end`: the end, and where), moves it back there. The last step
    /// satisfies `satisfies`.
    fn resize(
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
    fn span(&mut self, k: usize, (g, at): (GeomId, Reg), x: Reg, r: &Rel) -> bool {
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

    /// A line (cluster `k`) whose direction is known, free to move across itself: its point's
    /// two coordinates on the plane through it across the line (`place_on`).
    fn place_across(&mut self, k: usize) -> bool {
        let line = self.clusters[k].geoms[0];
        let Some(dir) = self.model.part(line, Part::Dir) else {
            return false;
        };
        let (point, normal) = (self.point(line), self.direction(dir));
        let words = format!("the plane through {} across it", self.name(line));
        let plane = self.value(
            Op::Plane {
                point,
                normal,
                offset: None,
            },
            Ty::Plane,
            words,
        );
        self.place_on(k, line, Locus::Plane(plane))
    }

    /// A plane whose normal is known, free to translate: default its place on the line
    /// through its point along its normal.
    fn place_along_normal(&mut self, k: usize) -> bool {
        let plane = self.clusters[k].geoms[0];
        let Some(normal) = self.model.part(plane, Part::Normal) else {
            return false;
        };
        let (point, dir) = (self.point(plane), self.direction(normal));
        let words = format!("the line through {} along its normal", self.name(plane));
        let line = self.line(point, dir, words);
        self.slide(k, plane, Locus::Line(line))
    }

    /// Feature `f` of cluster `k` held on a line or circle: default its place on it (the
    /// distance along the line from its point, the angle about the circle's axis).
    fn slide(&mut self, k: usize, f: GeomId, locus: Locus) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let l = locus.reg();
        let measure = self.value(
            Op::LocusParam {
                locus: l,
                point: from,
            },
            Ty::Scalar,
            format!("the place of {fname} on {}", self.word(l)),
        );
        let meaning = format!("the place of {fname} on {}", self.word(l));
        let name = format!("{fname}_place");
        let at = self.default_value(f, name.clone(), meaning.clone(), measure);
        let to = self.value(
            Op::LocusPoint { locus: l, at },
            Ty::Point,
            format!("{fname}'s default place"),
        );
        let explain = format!(
            "{}: move {} so that {fname} is there.",
            Self::assume(&meaning, &name),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// Cluster `k` with feature `f` held on a surface (a plane, a sphere, a cylinder) and
    /// nothing left to turn: default `f`'s two coordinates on it (`runtime::locus3d::Surface`
    /// says which), where the constraints leave it.
    fn place_on(&mut self, k: usize, f: GeomId, locus: Locus) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let l = locus.reg();
        let words = match locus {
            Locus::Sphere(_) => ["longitude", "latitude"],
            Locus::Cylinder(_) => ["angle", "height"],
            Locus::Torus(_) => ["angle about its axis", "angle about its circle"],
            _ => ["first coordinate", "second coordinate"],
        };
        // An angle's name ends in `_angle`: an iteration steps and wraps it as one.
        let suffixes = match locus {
            Locus::Sphere(_) => ["longitude_angle", "latitude_angle"],
            Locus::Cylinder(_) => ["angle", "height"],
            Locus::Torus(_) => ["axis_angle", "tube_angle"],
            _ => ["u", "v"],
        };
        let mut uv = [Reg(0); 2];
        for (i, (what, suffix)) in words.into_iter().zip(suffixes).enumerate() {
            let meaning = format!("the {what} of {fname} on {}", self.word(l));
            let measure = self.value(
                Op::SurfaceParam {
                    locus: l,
                    point: from,
                    component: i as u8,
                },
                Ty::Scalar,
                meaning.clone(),
            );
            uv[i] = self.default_value(f, format!("{fname}_{suffix}"), meaning, measure);
        }
        let to = self.value(
            Op::SurfacePoint {
                locus: l,
                u: uv[0],
                v: uv[1],
            },
            Ty::Point,
            format!("{fname}'s default place on {}", self.word(l)),
        );
        let explain = format!(
            "{}: move {} so that {fname} is there.",
            Self::assume(
                &format!("the place of {fname} on {}", self.word(l)),
                &format!("{fname}_{}, {fname}_{}", suffixes[0], suffixes[1])
            ),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// Cluster `k` free to translate: default its first point's coordinates.
    fn place(&mut self, k: usize) -> bool {
        let Some(f) = self.first_point(k) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let mut coords = [Reg(0); 3];
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            let meaning = format!("the {axis} coordinate of {fname}");
            let measure = self.value(
                Op::Coordinate {
                    point: from,
                    axis: i as u8,
                },
                Ty::Scalar,
                meaning.clone(),
            );
            coords[i] = self.default_value(f, format!("{fname}_{axis}"), meaning, measure);
        }
        let to = self.value(
            Op::PointAt {
                x: coords[0],
                y: coords[1],
                z: coords[2],
            },
            Ty::Point,
            format!("{fname}'s default position"),
        );
        let explain = format!(
            "{}: translate {} so that {fname} is there.",
            Self::assume(
                &format!("the position of {fname}"),
                &format!("{fname}_x, {fname}_y, {fname}_z")
            ),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// The first point feature of cluster `k`'s geoms: a point geom itself, else a body's
    /// first member point or marker, else the body's origin.
    fn first_point(&self, k: usize) -> Option<GeomId> {
        let g = *self.clusters[k].geoms.first()?;
        let geom = &self.model.geoms[g];
        if geom.kind == GeomKind::Point {
            return Some(g);
        }
        let member =
            (geom.parts.iter().copied()).find(|&m| self.model.geoms[m].kind.is_pointlike());
        Some(member.unwrap_or(g))
    }

    /// A body about a fixed point, free to turn: default its turns about the world's x, y
    /// and z axes through that point, in that order, from where the constraints leave it.
    fn orient(&mut self, k: usize) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let gname = self.name(geoms[0]);
        let pivot = self.pivot_of(k);
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            let words = format!("the {} axis", axis.to_uppercase());
            let a = self.value(Op::WorldAxis(i as u8), Ty::Vector, words);
            self.turn_by_default(&geoms, pivot, a, format!("{gname}_{axis}_angle"));
        }
        self.turned(k);
        true
    }

    /// Turns `geoms` about the axis through `pivot` along `axis` by a default named `name`,
    /// counted from where the constraints leave them (0: least motion).
    fn turn_by_default(&mut self, geoms: &[GeomId], pivot: Reg, axis: Reg, name: String) {
        let gname = self.name(geoms[0]);
        // A world axis is named with the point it turns about; a body's own axis says it.
        let through = match self.def(axis).map(|s| &s.op) {
            Some(Op::WorldAxis(_)) => format!(" through {}", self.word(pivot)),
            _ => String::new(),
        };
        let meaning = format!(
            "the turn of {gname} about {}{through}, from where the constraints leave it",
            self.word(axis)
        );
        let zero = self.value(Op::Const(0.0), Ty::Scalar, "0".into());
        let angle = self.default_value(geoms[0], name.clone(), meaning.clone(), zero);
        let explain = format!(
            "No constraint, chain or loop fixes this yet: assume {meaning} is the default `{name}` (0, least motion, unless given): turn {} about that axis by it.",
            self.group_name(geoms)
        );
        self.emit(
            Op::RotateBy {
                geoms: geoms.to_vec(),
                pivot,
                axis,
                angle,
            },
            None,
            Vec::new(),
            explain,
        );
    }

    /// A direction free to turn (a vector's, a line's, a plane's normal, a circle's normal):
    /// two defaults, its turns about a direction across it and about the direction across
    /// both, from where the constraints leave it (turning about itself moves nothing).
    fn orient_direction(&mut self, k: usize) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let Some(dir) = self.own_direction(geoms[0]) else {
            return false;
        };
        let gname = self.name(geoms[0]);
        let pivot = self.pivot_of(k);
        let d = self.direction(dir);
        let words = format!("a direction across {}", self.name(dir));
        let across = self.value(Op::Across(d), Ty::Vector, words);
        let quarter = self.value(
            Op::Const(std::f64::consts::FRAC_PI_2),
            Ty::Scalar,
            "a right angle".into(),
        );
        let words = format!("the direction across {} and that direction", self.name(dir));
        let both = self.value(
            Op::TurnedAbout {
                dir: across,
                axis: d,
                angle: quarter,
            },
            Ty::Vector,
            words,
        );
        self.turn_by_default(&geoms, pivot, across, format!("{gname}_tilt_angle"));
        self.turn_by_default(&geoms, pivot, both, format!("{gname}_roll_angle"));
        self.turned(k);
        true
    }

    /// The direction feature that is a one-direction geom's orientation: a vector itself, a
    /// line's or segment's direction, a plane's or circle's normal.
    fn own_direction(&self, g: GeomId) -> Option<GeomId> {
        match self.model.geoms[g].kind {
            GeomKind::Vector => Some(g),
            GeomKind::Plane | GeomKind::Circle => self.model.part(g, Part::Normal),
            GeomKind::Line | GeomKind::Segment => self.model.line_features(g).map(|(_, d)| d),
            _ => None,
        }
    }

    /// A body that may only turn about `axis`: default that turn.
    fn spin(&mut self, k: usize, axis: Reg) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let pivot = self.pivot_of(k);
        let name = format!("{}_spin_angle", self.name(geoms[0]));
        self.turn_by_default(&geoms, pivot, axis, name);
        self.turned(k);
        true
    }

    /// Grounds a model in which nothing is fixed: the cluster with the most DOF (a point
    /// before a plane of as many: its turns are then held by the points related to it), then
    /// the first name, is held where the sketch has it.
    fn ground_if_nothing_fixed(&mut self) {
        let mut best: Option<((usize, bool), String, usize)> = None;
        for (i, c) in self.clusters.iter().enumerate() {
            let rank = (c.record.dof(), c.record.shape == Shape::Point);
            let key = (rank, self.model.geoms[c.geoms[0]].name.clone());
            if best
                .as_ref()
                .is_none_or(|b| key.0 > b.0 || (key.0 == b.0 && key.1 < b.1))
            {
                best = Some((key.0, key.1, i));
            }
        }
        if let Some((_, _, i)) = best {
            self.clusters[i].record.hold();
            self.plan.grounded = Some(self.clusters[i].geoms[0]);
            if self.clusters[i].record.turn == Turn::None {
                self.ground_turns(i);
            }
        }
    }

    /// A point held at its sketch leaves the model free to turn about it (three DOF): hold
    /// the direction to the first free point related to it (in name order) as the sketch
    /// has it (two), and the plane of those two and the next free point related to either
    /// (one), so that the model is solved up to a rigid motion only.
    fn ground_turns(&mut self, i: usize) {
        let free = |s: &Self, k: usize| {
            s.clusters[k].record.trans == Trans::Free && s.clusters[k].record.movable()
        };
        // The first pending point-point relation from the held clusters to a free one.
        let next = |s: &Self, held: &[usize]| -> Option<(GeomId, GeomId)> {
            s.pending.iter().find_map(|r| {
                let Relation::PointPoint { a, b, .. } = r.relation else {
                    return None;
                };
                let (ka, kb) = (s.cluster(a), s.cluster(b));
                if held.contains(&ka) && !held.contains(&kb) && free(s, kb) {
                    Some((a, b))
                } else if held.contains(&kb) && !held.contains(&ka) && free(s, ka) {
                    Some((b, a))
                } else {
                    None
                }
            })
        };
        let Some((at, other)) = next(self, &[i]) else {
            return;
        };
        let (a, o) = (self.point(at), self.point(other));
        let (an, on) = (self.name(at), self.name(other));
        let words = format!("the direction from {an} to {on} in the sketch");
        let d = self.value(Op::DirectionTo { from: a, to: o }, Ty::Vector, words);
        let line = self.line(a, d, format!("the line from {an} through {on} as sketched"));
        let k = self.cluster(other);
        self.clusters[k].record.trans = Trans::On {
            feature: other,
            locus: Locus::Line(line),
        };
        self.plan.grounded_direction = Some((at, other));
        let Some((_, third)) = next(self, &[i, k]) else {
            return;
        };
        let t = self.point(third);
        let tn = self.name(third);
        let words = format!("the normal of the plane through {an}, {on} and {tn} in the sketch");
        let n = self.value(Op::PlaneNormal { a, b: o, c: t }, Ty::Vector, words);
        let words = format!("the plane through {an}, {on} and {tn} as sketched");
        let plane = self.value(
            Op::Plane {
                point: a,
                normal: n,
                offset: None,
            },
            Ty::Plane,
            words,
        );
        let k = self.cluster(third);
        self.clusters[k].record.trans = Trans::On {
            feature: third,
            locus: Locus::Plane(plane),
        };
        self.plan.grounded_plane = Some(third);
    }
}
