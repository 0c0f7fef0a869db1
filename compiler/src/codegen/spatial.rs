//! Codegen in space: each spatial step of the plan lowered to the runtime's 3d calls
//! (`locus3d`, `intersect3d`, `frame`, `fragment3`, `check::space`): values here, actions in
//! `actions.rs`, checks in `residual.rs`; the sketch of a 3d model as `Frame3`s is
//! `sketch3.rs`.
//!
//! The skeleton of `solve` (params, sketch, tolerance, groups of steps with their comments,
//! outer iterations, the `Solution`) and the steps that do not depend on the space (scalars,
//! translations, dimensions, closes) are the plane's. What is here mirrors the interpreter's
//! `interp/spatial.rs` call for call, so that both give the same values to the bit: where a
//! computation is more than one call, it is one function of the runtime that both call
//! (`frame::plane_turn`, `frame::helix_advance`, `intersect3d::line_circle`,
//! `Circle3::angle_of`). A sketch's rotation is a literal quaternion where the sketch is
//! constant, and otherwise the runtime's `rotation_onto_x`/`rotation_onto_z`/`rotation_zx`/
//! `rotation_sketched`, which the configuration calls too. Checks go through
//! `check::space`; the accessors are those `Solution::read_space` reports (points with three
//! coordinates, marker axes and normals, a plane's offset, a body's `Frame3`).
//!
//! Facts (see `facts`) are mostly the plane's optimisations; space takes three. A frame known
//! to the bit (`FrameFacts::literal3`: a constant sketch moved only by literal translations
//! and rotations) is moved at compile time by the runtime's own functions and declared where
//! those moves leave it, so that what it carries is a literal; the same locus built twice is
//! one local (`Facts::computed`); and a root of an intersection is not re-tested on a locus it
//! came from. Every other frame is read and moved as it is, and every other register is a
//! local.

mod actions;
mod residual;

use super::facts::{Made, Value};
use super::sketch3::frame3;
use super::solve::Solve;
use super::writer::{float, lit, Writer};
use crate::plan::{BranchId, Meet, Op, Reg, SpatialOp};
use gcs_lang::model::{ConstraintId, GeomId, Owner, Part};

/// The kind of a register's value in space, as the step that defines it makes it: what a
/// locus-generic step (a nearest point, a parameter along a locus) calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Line,
    Circle,
    Plane,
    Sphere,
    Cylinder,
    Torus,
    Other,
}

impl Solve<'_> {
    /// The local coordinates of member `g` (point or direction): the local params set, or the
    /// constant literal.
    fn local3(&self, g: GeomId, point: bool) -> String {
        match self.locals.get(&g) {
            Some(local) => local.clone(),
            None if point => self.cx.local_point3(g),
            None => self.cx.local_dir3(g),
        }
    }

    /// The global position of point feature `g`, read from its frame now.
    fn point_value3(&self, g: GeomId) -> String {
        let m = self.cx.model;
        let f = self.frame(m.top_level_of(g));
        match m.geoms[g].owner {
            Owner::TopLevel => format!("{f}.origin"),
            Owner::Member(_) => format!("{f}.point_to_global(&{})", self.local3(g, true)),
            Owner::Part(owner, Part::End) => {
                format!("{f}.origin + {f}.x_axis() * {}", self.dim(owner))
            }
            Owner::Part(..) => format!("{f}.origin"),
        }
    }

    /// The global direction of vector feature `g`, read from its frame now.
    fn dir_value3(&self, g: GeomId) -> String {
        let m = self.cx.model;
        let f = self.frame(m.top_level_of(g));
        match m.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX | Part::AxisZ) => {
                format!("{f}.vector_to_global(&{})", self.local3(g, false))
            }
            Owner::Part(_, Part::Normal) => format!("{f}.z_axis()"),
            _ => format!("{f}.x_axis()"),
        }
    }

    /// The frame of top-level geom `g` to the bit, while it is known so.
    fn literal_frame3(&self, g: GeomId) -> Option<gcs_runtime::frame::Frame3> {
        self.facts.frames.get(&g).and_then(|f| f.literal3)
    }

    /// The global position of point feature `g` when its frame and local coordinates are
    /// known to the bit: computed here as the interpreter's configuration computes it.
    fn literal_point3(&self, g: GeomId) -> Option<nalgebra::Point3<f64>> {
        let (cx, m) = (self.cx, self.cx.model);
        let f = self.literal_frame3(m.top_level_of(g))?;
        Some(match m.geoms[g].owner {
            Owner::TopLevel => f.origin,
            Owner::Member(_) if cx.local_is_param3(g) => return None,
            Owner::Member(_) => f.point_to_global(
                &(cx.sketch3().local_point(g)).unwrap_or_else(nalgebra::Point3::origin),
            ),
            Owner::Part(owner, Part::End) if cx.dim_set(owner) => return None,
            Owner::Part(owner, Part::End) => f.origin + f.x_axis() * cx.sketch3().dim(owner),
            Owner::Part(..) => f.origin,
        })
    }

    /// The global direction of vector feature `g` when known to the bit (see
    /// [`Solve::literal_point3`]).
    fn literal_dir3(&self, g: GeomId) -> Option<nalgebra::Vector3<f64>> {
        let (cx, m) = (self.cx, self.cx.model);
        let f = self.literal_frame3(m.top_level_of(g))?;
        Some(match m.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX | Part::AxisZ)
                if cx.local_is_param3(g) =>
            {
                return None
            }
            Owner::Member(_) | Owner::Part(_, Part::AxisX | Part::AxisZ) => f.vector_to_global(
                &(cx.sketch3().local_dir(g)).unwrap_or_else(nalgebra::Vector3::x),
            ),
            Owner::Part(_, Part::Normal) => f.z_axis(),
            _ => f.x_axis(),
        })
    }

    /// From here on the code holds frame `g`: if it was known to the bit, its local starts
    /// where the moves computed here left it (no code has read or moved it yet).
    fn materialize(&mut self, g: GeomId) {
        let Some(facts) = self.facts.frames.get_mut(&g) else {
            return;
        };
        if let Some(f) = facts.literal3.take() {
            self.declared_at.insert(g, frame3(&f));
        }
    }

    /// The kind of register `r`'s value, from the step that defines it.
    fn kind3(&self, r: Reg) -> Kind {
        let Some(&i) = self.cx.defined_at.get(&r) else {
            return Kind::Other;
        };
        match &self.cx.plan.steps[i].op {
            Op::Line { .. } | Op::ParallelLine { .. } => Kind::Line,
            Op::ShiftedCircle { .. } => Kind::Circle,
            Op::Spatial(op) => match op {
                SpatialOp::Circle3 { .. } | SpatialOp::Orbit { .. } => Kind::Circle,
                SpatialOp::Plane { .. } | SpatialOp::ParallelPlane { .. } => Kind::Plane,
                SpatialOp::Sphere { .. }
                | SpatialOp::SphereThrough { .. }
                | SpatialOp::ShiftedSphere { .. } => Kind::Sphere,
                SpatialOp::Cylinder { .. } | SpatialOp::ShiftedCylinder { .. } => Kind::Cylinder,
                SpatialOp::Torus { .. } | SpatialOp::ShiftedTorus { .. } => Kind::Torus,
                _ => Kind::Other,
            },
            Op::Intersect { meet, .. } => match meet {
                Meet::SphereSphere | Meet::SpherePlane => Kind::Circle,
                Meet::PlanePlane | Meet::PlaneCylinder => Kind::Line,
                _ => Kind::Other,
            },
            _ => Kind::Other,
        }
    }

    /// Register `r` (of step `i`) as the one root of the intersection `call` returns, named
    /// `names.0` (the intersection) and `names.1` (the root); a contact without one is an
    /// error naming constraint `c`.
    fn only_root(
        &mut self,
        w: &mut Writer,
        (i, r): (usize, Reg),
        c: ConstraintId,
        names: (&str, &str),
        call: &str,
    ) {
        let local = self.names.fresh(names.0);
        self.let_read(w, &local, call);
        self.fail_on_contact(w, c, &local, None);
        let code = format!("{local}.roots.get(0){}", self.or_degenerate(i));
        self.define(w, r, names.1, &code);
    }

    /// `.ok_or_else(|| degenerate)?` for step `i`.
    fn or_degenerate(&self, i: usize) -> String {
        format!(".ok_or_else(|| {})?", self.cx.error(i, "Degenerate", "0.0"))
    }

    /// `frame::unit3(&v)`, or step `i` is degenerate.
    fn unit3(&self, i: usize, v: &str) -> String {
        format!("frame::unit3(&{v}){}", self.or_degenerate(i))
    }

    /// [`Solve::unit3`] of register `v`: a literal when `v` is one (the runtime's own
    /// function, run here).
    fn unit3_of(&self, i: usize, v: Reg) -> String {
        if let Value::Vector3(c) = self.facts.value(v) {
            if let Some(u) = gcs_runtime::frame::unit3(&nalgebra::Vector3::from(*c)) {
                return Value::Vector3(u.into()).code();
            }
        }
        self.unit3(i, &self.r(v))
    }

    /// Writes the value of register `r`, which step `i` computes with the spatial `op`.
    pub(super) fn value3(&mut self, w: &mut Writer, i: usize, r: Reg, op: &Op) {
        let m = self.cx.model;
        match op {
            Op::PointOf(g) => {
                // A top-level geom's name is its frame's.
                let n = &m.geoms[*g].name;
                let n = match m.geoms[*g].owner {
                    Owner::TopLevel => format!("{n}_origin"),
                    _ => n.clone(),
                };
                let value = match self.literal_point3(*g) {
                    Some(p) => Value::Point3(p.coords.into()),
                    None => {
                        self.materialize(m.top_level_of(*g));
                        Value::Expr(self.point_value3(*g))
                    }
                };
                self.define_or_alias(w, r, &n, value);
            }
            Op::DirOf(g) => {
                let n = &m.geoms[*g].name;
                let n = if n.contains('.') {
                    n.clone()
                } else {
                    format!("{n}_dir")
                };
                let value = match self.literal_dir3(*g) {
                    Some(v) => Value::Vector3(v.into()),
                    None => {
                        self.materialize(m.top_level_of(*g));
                        Value::Expr(self.dir_value3(*g))
                    }
                };
                self.define_or_alias(w, r, &n, value);
            }
            Op::Along { from, dir, to } => {
                let code = format!(
                    "({} - {}).dot(&{})",
                    self.r(*to),
                    self.r(*from),
                    self.r(*dir)
                );
                self.define_pure(w, r, "length", &code);
            }
            Op::DirectionTo { from, to } => {
                let code = self.unit3(i, &format!("({} - {})", self.r(*to), self.r(*from)));
                self.define_pure(w, r, "direction", &code);
            }
            Op::Midpoint { a, b } => {
                let code = format!("locus3d::midpoint({}, {})", self.r(*a), self.r(*b));
                self.define_pure(w, r, "midpoint", &code);
            }
            Op::Reflect { point, through } => {
                let code = format!(
                    "locus3d::reflect_through({}, {})",
                    self.r(*point),
                    self.r(*through)
                );
                self.define_pure(w, r, "reflected", &code);
            }
            Op::LocusParam { locus, point } => {
                let (l, q) = (self.r(*locus), self.r(*point));
                let code = match self.kind3(*locus) {
                    Kind::Circle => format!("{l}.angle_of(&{q})"),
                    _ => format!("({q} - {l}.point).dot(&{l}.dir)"),
                };
                self.define_pure(w, r, "param", &code);
            }
            Op::LocusPoint { locus, at } => {
                let (l, t) = (self.r(*locus), self.r(*at));
                let code = match self.kind3(*locus) {
                    Kind::Circle => format!("{l}.point_at({t})"),
                    _ => format!("{l}.point + {l}.dir * {t}"),
                };
                self.define_pure(w, r, "on_locus", &code);
            }
            Op::Line {
                point,
                dir,
                offset: None,
            } => {
                let code = format!("Line3::new({}, {})", self.r(*point), self.unit3_of(i, *dir));
                self.define_pure(w, r, "line", &code);
            }
            Op::ParallelLine { line, through } => {
                let code = format!("Line3::new({}, {}.dir)", self.r(*through), self.r(*line));
                self.define_pure(w, r, "line", &code);
            }
            // A locus moved with its body: the runtime's `Shift`, as the interpreter moves it.
            Op::ShiftedCircle {
                circle: locus,
                from,
                to,
            } => {
                let code = format!(
                    "{}.shifted(&({} - {}))",
                    self.r(*locus),
                    self.r(*to),
                    self.r(*from)
                );
                let name = match self.kind3(r) {
                    Kind::Torus => "torus_moved",
                    Kind::Cylinder => "cylinder_moved",
                    Kind::Sphere => "sphere_moved",
                    _ => "circle_moved",
                };
                self.define_pure(w, r, name, &code);
            }
            Op::Nearest { locus, point } => {
                let (l, q) = (self.r(*locus), self.r(*point));
                let code = match self.kind3(*locus) {
                    Kind::Line => format!("{l}.closest(&{q})"),
                    Kind::Plane => format!("{l}.project(&{q})"),
                    _ => format!("{l}.nearest(&{q}){}", self.or_degenerate(i)),
                };
                self.define_pure(w, r, "nearest", &code);
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } if self.root_of(*point, *locus) => {
                // A root of an intersection with this very locus lies on it to a few ulps
                // (the runtime's intersections promise it, far below `tol`): nothing to test.
                let _ = constraint;
                let p = self.facts.value(*point).clone();
                self.facts.regs.insert(r, p);
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                let gap = self.names.fresh("gap");
                let code = format!("{}.distance(&{})", self.r(*locus), self.r(*point));
                self.let_read(w, &gap, &code);
                self.cx.reads_tol.set(true);
                w.open(&format!("if {gap}.is_nan() || {gap} > tol {{"));
                w.line(&format!(
                    "return Err({});",
                    self.cx.error_of(*constraint, "Inconsistent", &gap)
                ));
                w.close("}");
                let p = self.facts.value(*point).clone();
                self.facts.regs.insert(r, p);
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                ..
            } => self.intersect3(w, r, *meet, (*a, *b), *branch, *constraint),
            Op::Implicit { locus, point } => {
                if !self.converged {
                    let (l, q) = (self.r(*locus), self.r(*point));
                    let code = match self.kind3(*locus) {
                        Kind::Plane => format!("{l}.signed_distance(&{q})"),
                        Kind::Sphere => format!("({q} - {l}.center).norm() - {l}.radius"),
                        Kind::Cylinder | Kind::Torus => format!("{l}.signed_distance(&{q})"),
                        _ => format!("{l}.distance(&{q})"),
                    };
                    self.define_pure(w, r, "error", &code);
                }
            }
            Op::Error {
                residual,
                component,
            } => {
                if !self.converged {
                    let code = if *component == crate::plan::MAGNITUDE {
                        self.residual_code3(residual)
                    } else {
                        self.error_code3(residual, *component)
                    };
                    self.define_pure(w, r, "error", &code);
                }
            }
            Op::Spatial(op) => self.spatial_value(w, i, r, op),
            Op::Planar(_) => {
                unreachable!("bug in gcs: step {i} is an operation of the plane in a spatial plan")
            }
            // Scalars are written by `value`, actions and checks by `step`.
            op => panic!("bug in gcs: step {i} ({op:?}) is no value of a spatial plan"),
        }
    }

    /// Writes the value of register `r`, which step `i` computes with an operation of space.
    fn spatial_value(&mut self, w: &mut Writer, i: usize, r: Reg, op: &SpatialOp) {
        let m = self.cx.model;
        match op {
            // An action defines no value: `step` writes it.
            SpatialOp::RotateBy { .. } => {
                panic!("bug in gcs: step {i} defines a value by a rotation")
            }
            SpatialOp::ThreeCircles {
                first,
                a,
                second,
                third,
                b,
                branch,
                constraint,
                ..
            } => {
                let found = self.names.fresh("three_circles");
                // Only the root read is polished, unless `solve_all`'s tree reads them all.
                let only = if self.varies(*branch) {
                    "None".to_string()
                } else {
                    format!("Some({})", self.branch_index(*branch))
                };
                let code = format!(
                    "gcs_runtime::turn3d::three_circles_polishing(&{}, &{}, &{}, &{}, &{}, {only})",
                    self.axis_line(i, *first),
                    self.r(*a),
                    self.axis_line(i, *second),
                    self.axis_line(i, *third),
                    self.r(*b)
                );
                let names = ["first_angle", "second_angle", "third_angle"];
                self.angles_of(w, r, (&found, &code), (*branch, *constraint), &names);
            }
            SpatialOp::PlanarChainEnds {
                first,
                h,
                base,
                joint,
                far,
                last,
                offset,
                sense,
                branch,
                constraint,
            } => {
                let found = self.names.fresh("chain_ends");
                let code = format!(
                    "gcs_runtime::turn3d::planar_chain_ends(&{}, &{}, &{}, &{}, &{}, &{}, {}, {})",
                    self.axis_line(i, *first),
                    self.r(*h),
                    self.r(*base),
                    self.axis_line(i, *joint),
                    self.r(*far),
                    self.axis_line(i, *last),
                    self.r(*offset),
                    float(*sense)
                );
                let names = ["base_angle", "joint_angle"];
                self.angles_of(w, r, (&found, &code), (*branch, *constraint), &names);
            }
            SpatialOp::Opposite(d) => {
                let code = format!("-{}", self.r(*d));
                self.define_pure(w, r, "opposite", &code);
            }
            SpatialOp::Across(d) => {
                let code = self.unit3(i, &format!("frame::perpendicular(&{})", self.r(*d)));
                self.define_pure(w, r, "across", &code);
            }
            SpatialOp::AngleAbout { u, v, axis } => {
                let code = format!(
                    "frame::signed_angle3(&{}, &{}, &{})",
                    self.r(*u),
                    self.r(*v),
                    self.r(*axis)
                );
                self.define_pure(w, r, "angle", &code);
            }
            SpatialOp::AngleAboutBoth { u, v, axis } => {
                let code = format!(
                    "frame::signed_angle3_both([&{}, &{}], [&{}, &{}], &{})",
                    self.r(u[0]),
                    self.r(u[1]),
                    self.r(v[0]),
                    self.r(v[1]),
                    self.r(*axis)
                );
                self.define_pure(w, r, "angle", &code);
            }
            SpatialOp::TurnReaching {
                u,
                v,
                axis,
                pivot,
                reach,
                screw,
            } => {
                let helix = |h: &crate::plan::HelixRegs| {
                    format!(
                        "fragment3::Helix {{ axis: {}, x_from: {}, origin: {}, x: {}, point: {}, pitch: {} }}",
                        self.r(h.axis),
                        self.r(h.x_from),
                        self.r(h.origin),
                        self.r(h.x),
                        self.r(h.point),
                        self.r(h.pitch)
                    )
                };
                let screw = screw.map_or("None".to_string(), |s| {
                    format!(
                        "Some(&fragment3::Screw {{ helix: {}, slide: {}.dir }})",
                        helix(&s.helix),
                        self.r(s.slide)
                    )
                });
                let (onto, target) = match reach {
                    crate::plan::Reach::Helix(h) => ("helix", format!("&{}", helix(h))),
                    crate::plan::Reach::Point { point, locus } => (
                        match self.kind3(*locus) {
                            Kind::Plane => "plane",
                            _ => "line",
                        },
                        format!("&{}, &{}", self.r(*point), self.r(*locus)),
                    ),
                };
                let code = format!(
                    "fragment3::turn_reaching_{onto}([&{}, &{}], (&{}, &{}), {target}, {screw})",
                    self.r(*u),
                    self.r(*v),
                    self.r(*pivot),
                    self.r(*axis)
                );
                self.define_pure(w, r, "angle", &code);
            }
            SpatialOp::HelixAdvance { now, turn, pitch } => {
                let code = format!(
                    "frame::helix_advance({}, {}, {})",
                    self.r(*now),
                    self.r(*turn),
                    self.r(*pitch)
                );
                self.define_finite(w, i, r, "advance", &code);
            }
            SpatialOp::HelixTurn { advance, pitch } => {
                let code = format!(
                    "frame::helix_turn({}, {})",
                    self.r(*advance),
                    self.r(*pitch)
                );
                self.define_finite(w, i, r, "turn", &code);
            }
            SpatialOp::Aligned { dir, near } => {
                let code = format!("frame::aligned(&{}, &{})", self.r(*dir), self.r(*near));
                self.define_pure(w, r, "aligned", &code);
            }
            SpatialOp::PassingAngle {
                from,
                to,
                d,
                now,
                constraint,
            } => {
                let call = format!(
                    "fragment3::passing_angle(&{}, &{}, {}, &{})",
                    self.r(*from),
                    self.r(*to),
                    self.r(*d),
                    self.r(*now)
                );
                self.only_root(w, (i, r), *constraint, ("passing", "passing_angle"), &call);
            }
            SpatialOp::TiltToDistance {
                centre,
                point,
                radius,
                d,
                now,
                constraint,
            } => {
                let call = format!(
                    "fragment3::tilt_to_distance(&{}, &{}, {}, {}, &{})",
                    self.r(*centre),
                    self.r(*point),
                    self.r(*radius),
                    self.r(*d),
                    self.r(*now)
                );
                self.only_root(w, (i, r), *constraint, ("tilt", "tilt_angle"), &call);
            }
            SpatialOp::ConeTurn { axis, angle, dir } => {
                let code = format!(
                    "frame::plane_turn(&{}, f64::cos({}), &{})",
                    self.r(*axis),
                    self.r(*angle),
                    self.r(*dir)
                );
                self.define_pure(w, r, "turned", &code);
            }
            SpatialOp::AngleTurn {
                u,
                v,
                axis,
                angle,
                branch,
                constraint,
            } => {
                let turns = self.names.fresh("turns");
                let code = format!(
                    "frame::turns_to_angle(&{}, &{}, &{}, {})",
                    self.r(*u),
                    self.r(*v),
                    self.r(*axis),
                    self.r(*angle)
                );
                self.let_read(w, &turns, &code);
                self.fail_on_contact(w, *constraint, &turns, None);
                let code = self.root(&turns, *branch, *constraint);
                self.fork(w, *branch);
                self.define_pure(w, r, "turned", &code);
            }
            SpatialOp::PlaneTurn {
                base,
                normal,
                pivot,
                point,
                d,
                constraint,
            } => {
                let cone = self.plane_cone(w, (*base, *normal, *pivot, *point, *d));
                let con = &m.constraints[*constraint];
                let (label, text) = (lit(&con.name), lit(&con.text));
                let len = self.names.fresh("reach");
                self.let_read(w, &len, &format!("{cone}.0.norm()"));
                w.open(&format!("if {len}.is_nan() || {len} <= 0.0 {{"));
                w.line(&format!(
                    "return Err(SolveError::new({label}, {text}, ErrorKind::Degenerate, 0.0));"
                ));
                w.close("}");
                w.open(&format!(
                    "if {cone}.1.abs() > 1.0 + gcs_runtime::tol::LENGTH_REL || {cone}.1.is_nan() {{"
                ));
                w.line(&format!(
                    "return Err(SolveError::new({label}, {text}, ErrorKind::NoIntersection, ({cone}.1.abs() - 1.0) * {len}));"
                ));
                w.close("}");
                let code = format!(
                    "frame::plane_turn(&({cone}.0 / {len}), {cone}.1.clamp(-1.0, 1.0), &{})",
                    self.r(*normal)
                );
                self.define_pure(w, r, "normal", &code);
            }
            SpatialOp::PlaneAxisTurn {
                base,
                normal,
                pivot,
                point,
                d,
                axis,
                branch,
                constraint,
            } => {
                let cone = self.plane_cone(w, (*base, *normal, *pivot, *point, *d));
                let con = &m.constraints[*constraint];
                let (label, text) = (lit(&con.name), lit(&con.text));
                let reach = self.names.fresh("reach");
                self.let_read(w, &reach, &format!(
                    "{cone}.0.try_normalize(0.0).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::Degenerate, 0.0))?"
                ));
                let gap = self.names.fresh("gap");
                self.let_read(
                    w,
                    &gap,
                    &format!("({cone}.1.abs() - 1.0).max(0.0) * {cone}.0.norm()"),
                );
                let turns = self.names.fresh("turns");
                let code = format!(
                    "frame::turns_to_angle(&{reach}, &{}, &{}, {cone}.1.clamp(-1.0, 1.0).acos())",
                    self.r(*normal),
                    self.r(*axis)
                );
                self.let_read(w, &turns, &code);
                self.fail_on_contact(w, *constraint, &turns, Some(&gap));
                w.open(&format!(
                    "if {gap} > gcs_runtime::tol::LENGTH_REL * (1.0 + {cone}.0.norm()) {{"
                ));
                w.line(&format!(
                    "return Err(SolveError::new({label}, {text}, ErrorKind::NoIntersection, {gap}));"
                ));
                w.close("}");
                let code = self.root(&turns, *branch, *constraint);
                self.fork(w, *branch);
                self.define_pure(w, r, "normal", &code);
            }
            SpatialOp::MirrorPlane {
                point,
                base,
                normal,
            } => {
                let code = format!(
                    "locus3d::mirror({}, {}, {})",
                    self.r(*base),
                    self.r(*normal),
                    self.r(*point)
                );
                self.define_pure(w, r, "mirrored", &code);
            }
            SpatialOp::PlaneNormal { a, b, c } => {
                let code = self.unit3(
                    i,
                    &format!(
                        "({} - {a}).cross(&({} - {a}))",
                        self.r(*b),
                        self.r(*c),
                        a = self.r(*a)
                    ),
                );
                self.define_pure(w, r, "normal", &code);
            }
            SpatialOp::WorldAxis(k) => {
                let code = ["Vector3::x()", "Vector3::y()", "Vector3::z()"][usize::from(*k).min(2)];
                self.define_pure(w, r, "world_axis", code);
            }
            SpatialOp::Coordinate { point, axis } => {
                let c = ["x", "y", "z"][usize::from(*axis).min(2)];
                let code = format!("{}.{c}", self.r(*point));
                self.define_pure(w, r, c, &code);
            }
            SpatialOp::PointAt { x: a, y, z } => {
                let code = format!(
                    "Point3::new({}, {}, {})",
                    self.r(*a),
                    self.r(*y),
                    self.r(*z)
                );
                self.define_pure(w, r, "point", &code);
            }
            SpatialOp::SurfaceParam {
                locus,
                point,
                component,
            } => {
                let code = format!(
                    "{}.coordinates(&{})[{}]",
                    self.r(*locus),
                    self.r(*point),
                    component.min(&1)
                );
                self.define_pure(w, r, "coordinate", &code);
            }
            SpatialOp::SurfacePoint { locus, u, v } => {
                let code = format!("{}.at([{}, {}])", self.r(*locus), self.r(*u), self.r(*v));
                self.define_pure(w, r, "on_surface", &code);
            }
            SpatialOp::TurnedAbout { dir, axis, angle } => {
                let code = format!(
                    "frame::rotation_about_axis(&{}, {}) * {}",
                    self.r(*axis),
                    self.r(*angle),
                    self.r(*dir)
                );
                self.define_pure(w, r, "turned", &code);
            }
            SpatialOp::Plane {
                point,
                normal,
                offset,
            } => {
                let n = self.names.fresh("normal");
                let code = self.unit3_of(i, *normal);
                self.let_read(w, &n, &code);
                let at = match offset {
                    Some(o) => format!("({} + {n} * {})", self.r(*point), self.r(*o)),
                    None => self.r(*point),
                };
                let code = format!("Plane::from_point_normal(&{at}, &{n})");
                self.define_pure(w, r, "plane", &code);
            }
            SpatialOp::ParallelPlane { plane, through } => {
                let code = format!(
                    "Plane::from_point_normal(&{}, &{}.normal)",
                    self.r(*through),
                    self.r(*plane)
                );
                self.define_pure(w, r, "plane", &code);
            }
            SpatialOp::Circle3 {
                center,
                normal,
                radius,
            } => {
                let code = format!(
                    "Circle3::new({}, {}, {})",
                    self.r(*center),
                    self.unit3_of(i, *normal),
                    self.r(*radius)
                );
                self.define_pure(w, r, "circle", &code);
            }
            SpatialOp::Sphere { center, radius } => {
                let code = format!("Sphere::new({}, {})", self.r(*center), self.r(*radius));
                self.define_pure(w, r, "sphere", &code);
            }
            SpatialOp::Cylinder { point, dir, radius } => {
                let code = format!(
                    "Cylinder::new(Line3::new({}, {}), {})",
                    self.r(*point),
                    self.unit3_of(i, *dir),
                    self.r(*radius)
                );
                self.define_pure(w, r, "cylinder", &code);
            }
            SpatialOp::Torus { circle, tube } => {
                let code = format!("Torus::new({}, {})", self.r(*circle), self.r(*tube));
                self.define_pure(w, r, "torus", &code);
            }
            // A locus moved with its body: the runtime's `Shift`, as the interpreter moves it.
            SpatialOp::ShiftedTorus {
                torus: locus,
                from,
                to,
            }
            | SpatialOp::ShiftedCylinder {
                cylinder: locus,
                from,
                to,
            }
            | SpatialOp::ShiftedSphere {
                sphere: locus,
                from,
                to,
            } => {
                let code = format!(
                    "{}.shifted(&({} - {}))",
                    self.r(*locus),
                    self.r(*to),
                    self.r(*from)
                );
                let name = match self.kind3(r) {
                    Kind::Torus => "torus_moved",
                    Kind::Cylinder => "cylinder_moved",
                    Kind::Sphere => "sphere_moved",
                    _ => "circle_moved",
                };
                self.define_pure(w, r, name, &code);
            }
            SpatialOp::SphereThrough {
                center,
                through,
                radius,
            } => {
                let c = self.r(*center);
                let rad = match radius {
                    Some(k) => float(*k),
                    None => format!("({} - {c}).norm()", self.r(*through)),
                };
                self.define_pure(w, r, "sphere", &format!("Sphere::new({c}, {rad})"));
            }
            SpatialOp::Orbit {
                pivot,
                axis,
                through,
            } => {
                let code = format!(
                    "Circle3::orbit(&{}, &{}, &{})",
                    self.r(*pivot),
                    self.unit3_of(i, *axis),
                    self.r(*through)
                );
                self.define_pure(w, r, "orbit", &code);
            }
        }
    }

    /// Whether register `point` is a root of an intersection one of whose loci is the value
    /// of register `locus`.
    fn root_of(&self, point: Reg, locus: Reg) -> bool {
        let Some(&i) = self.cx.defined_at.get(&point) else {
            return false;
        };
        // A line's crossing with a circle of space is on the circle only to rounding over
        // the line's slope across its plane: that one is tested.
        let Op::Intersect { a, b, meet, .. } = self.cx.plan.steps[i].op else {
            return false;
        };
        if meet == Meet::LineCircle {
            return false;
        }
        let l = self.facts.value(locus);
        [a, b]
            .iter()
            .any(|x| self.facts.regs.get(x).is_some_and(|v| v.same(l, self.cx)))
    }

    /// `let {name} = {code};` for register `r`, a value of locals alone: the local that
    /// already holds it when one does (the same locus built twice, for an action and for the
    /// check that the point it reached is on it).
    fn define_pure(&mut self, w: &mut Writer, r: Reg, name: &str, code: &str) {
        let made = self.made(r);
        if let Some(local) = made.as_ref().and_then(|m| self.facts.computed.get(m)) {
            let value = Value::Local(local.clone());
            self.facts.regs.insert(r, value);
            return;
        }
        self.define(w, r, name, code);
        if let (Some(made), Value::Local(local)) = (made, self.facts.value(r)) {
            let local = local.clone();
            self.facts.computed.insert(made, local);
        }
    }

    /// What register `r`, of a value of locals alone, is made from (see [`Made`]): none when
    /// its step declared a local of its own, which its code reads.
    fn made(&self, r: Reg) -> Option<Made> {
        let i = self.cx.defined_at[&r];
        let (at, errors) = self.step_start;
        if self.ledger.borrow().declares_since(at) {
            return None;
        }
        let op = &self.cx.plan.steps[i].op;
        let reads = op.reads();
        // A register no step wrote (an intersection's `near`) is not in the code.
        let operands: Vec<(&Value, u8)> = (reads.iter())
            .filter_map(|x| Some((self.facts.regs.get(x)?, self.kind3(*x) as u8)))
            .collect();
        let fails = (self.cx.errors_made.get() > errors)
            .then(|| self.cx.plan.constraint_of(i))
            .flatten();
        Made::new(op, &operands, fails)
    }

    /// The cone a turning plane's normal must lie on (see `frame::plane_cone`), in a local.
    fn plane_cone(
        &mut self,
        w: &mut Writer,
        (base, normal, pivot, point, d): (Reg, Reg, Reg, Reg, Reg),
    ) -> String {
        let cone = self.names.fresh("cone");
        let code = format!(
            "frame::plane_cone(&{}, &{}, &{}, &{}, {})",
            self.r(base),
            self.r(normal),
            self.r(pivot),
            self.r(point),
            self.r(d)
        );
        self.let_read(w, &cone, &code);
        cone
    }

    /// Returns the error of constraint `c` where intersection `local` misses (its magnitude
    /// at least `at_least`, when given).
    fn fail_on_contact(
        &self,
        w: &mut Writer,
        c: ConstraintId,
        local: &str,
        at_least: Option<&str>,
    ) {
        let con = &self.cx.model.constraints[c];
        let (label, text) = (lit(&con.name), lit(&con.text));
        let e = if at_least.is_some() { "mut e" } else { "e" };
        w.open(&format!(
            "if let Some({e}) = SolveError::from_contact({label}, {text}, {local}.contact) {{"
        ));
        if let Some(g) = at_least {
            w.line(&format!("e.magnitude = e.magnitude.max({g});"));
        }
        w.line("return Err(e);");
        w.close("}");
    }

    /// The axis through the point in `pivot` along the direction in `dir`, made unit.
    fn axis_line(&self, i: usize, [pivot, dir]: [Reg; 2]) -> String {
        format!("Line3::new({}, {})", self.r(pivot), self.unit3_of(i, dir))
    }

    /// Defines `r`, the angles of a chain of turns: the root of `branch` of what `code` finds
    /// (in local `found`), or the error of `c`; `solve_all`'s tree forks there. `names` are
    /// the angles' locals, read by `Op::Unknown`.
    fn angles_of(
        &mut self,
        w: &mut Writer,
        r: Reg,
        (found, code): (&str, &str),
        (branch, c): (BranchId, ConstraintId),
        names: &[&str],
    ) {
        self.let_read(w, found, code);
        self.fail_on_contact(w, c, found, None);
        let root = self.root(found, branch, c);
        self.fork(w, branch);
        (self.unknown_names).insert(r, names.iter().map(|n| n.to_string()).collect());
        self.define(w, r, "angles", &root);
    }

    /// The root of `branch` of intersection `local`, or the error of constraint `c` that the
    /// branch has no root here.
    fn root(&self, local: &str, branch: BranchId, c: ConstraintId) -> String {
        let con = &self.cx.model.constraints[c];
        let (label, text) = (lit(&con.name), lit(&con.text));
        format!(
            "{local}.roots.get({}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, {local}.roots.len() as f64))?",
            self.branch_index(branch)
        )
    }

    /// The root of `branch` of the intersection of loci `a` and `b` in space, for constraint
    /// `c`: a point, or (two spheres, a sphere and a plane, two planes) a locus.
    fn intersect3(
        &mut self,
        w: &mut Writer,
        r: Reg,
        meet: Meet,
        (a, b): (Reg, Reg),
        branch: BranchId,
        c: ConstraintId,
    ) {
        let f = match meet {
            Meet::LinePlane => "line_plane",
            Meet::LineSphere => "line_sphere",
            Meet::CirclePlane => "circle_plane",
            Meet::CircleSphere => "circle_sphere",
            Meet::CircleCircle => "circle_circle",
            Meet::LineCircle => "line_circle",
            Meet::LineCylinder => "line_cylinder",
            Meet::SphereSphere => "sphere_sphere",
            Meet::SpherePlane => "sphere_plane",
            Meet::PlanePlane => "plane_plane",
            Meet::PlaneCylinder => "plane_cylinder_lines",
            planar => panic!(
                "bug in gcs: the planar intersection {planar:?} reached the spatial code generator"
            ),
        };
        let con = &self.cx.model.constraints[c];
        let meeting = self.names.fresh(&format!("{}_meeting", con.name));
        let code = format!("intersect3d::{f}(&{}, &{})", self.r(a), self.r(b));
        self.let_read(w, &meeting, &code);
        self.fail_on_contact(w, c, &meeting, None);
        let code = if matches!(
            meet,
            Meet::SphereSphere | Meet::SpherePlane | Meet::PlanePlane
        ) {
            // A locus: one root, whatever the branch.
            let (label, text) = (lit(&con.name), lit(&con.text));
            format!(
                "{meeting}.roots.get(0).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, 0.0))?"
            )
        } else {
            self.fork(w, branch);
            self.root(&meeting, branch, c)
        };
        let name = con.name.clone();
        self.define(w, r, &name, &code);
    }
}
