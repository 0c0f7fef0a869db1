//! The interpreter's steps in space: the same machine as the plane's (registers, branches,
//! defaults, outer iterations, checks), over 3d points, unit directions and the loci of
//! space (lines, planes, spheres, circles with their axis), moving `Frame3`s.

use super::{err, malformed, Machine, Space, Val};
use crate::config::{D3, P3, V3};
use crate::plan::{Meet, Op, Reg, Residual, RotationAxis, SpatialOp, Step};
use gcs_lang::model::ConstraintId;
use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::locus3d::{
    self, Circle3, Cylinder, Line3, Locus3, Plane, Shift, Sphere, Surface, Torus,
};
use gcs_runtime::{check, fragment3, frame, intersect3d, turn3d, Contact, Roots};
use nalgebra::UnitQuaternion;

impl Space for D3 {
    fn step(m: &mut Machine<'_, '_, D3>, i: usize, step: &Step) -> Result<(), SolveError> {
        m.step_spatial(i, step)
    }
}

impl Machine<'_, '_, D3> {
    fn p3(&self, r: Reg) -> P3 {
        match self.get(r) {
            Some(&Val::P3(x)) => x,
            v => malformed(r, "a point of space", v),
        }
    }
    fn v3(&self, r: Reg) -> V3 {
        match self.get(r) {
            Some(&Val::V3(x)) => x,
            v => malformed(r, "a direction of space", v),
        }
    }
    fn line3(&self, r: Reg) -> Line3 {
        match self.get(r) {
            Some(&Val::L3(x)) => x,
            v => malformed(r, "a line of space", v),
        }
    }
    fn circle3(&self, r: Reg) -> Circle3 {
        match self.get(r) {
            Some(&Val::C3(x)) => x,
            v => malformed(r, "a circle of space", v),
        }
    }
    fn plane(&self, r: Reg) -> Plane {
        match self.get(r) {
            Some(&Val::Plane(x)) => x,
            v => malformed(r, "a plane", v),
        }
    }
    fn sphere(&self, r: Reg) -> Sphere {
        match self.get(r) {
            Some(&Val::Sphere(x)) => x,
            v => malformed(r, "a sphere", v),
        }
    }
    /// The translation from point `from` to point `to`.
    fn shift(&self, from: Reg, to: Reg) -> V3 {
        self.p3(to) - self.p3(from)
    }
    fn surface(&self, r: Reg) -> &dyn Surface {
        match self.get(r) {
            Some(Val::Plane(x)) => x,
            Some(Val::Sphere(x)) => x,
            Some(Val::Cylinder(x)) => x,
            Some(Val::Torus(x)) => x,
            v => malformed(r, "a surface of space", v),
        }
    }
    fn cylinder(&self, r: Reg) -> Cylinder {
        match self.get(r) {
            Some(&Val::Cylinder(x)) => x,
            v => malformed(r, "a cylinder", v),
        }
    }

    /// A unit direction, or step `i` is degenerate.
    fn unit(&self, i: usize, v: V3) -> Result<V3, SolveError> {
        frame::unit3(&v).ok_or_else(|| self.degenerate(i))
    }

    /// See [`frame::plane_cone`].
    fn plane_cone(&self, base: Reg, n: V3, pivot: Reg, point: Reg, d: Reg) -> (V3, f64) {
        let (b, p0, q) = (self.p3(base), self.p3(pivot), self.p3(point));
        frame::plane_cone(&b, &n, &p0, &q, self.s(d))
    }

    /// The distance from `p` to the locus in register `r`.
    fn gap(&self, r: Reg, p: &P3) -> f64 {
        match self.get(r) {
            Some(Val::L3(l)) => l.distance(p),
            Some(Val::C3(c)) => c.distance(p),
            Some(Val::Plane(q)) => q.distance(p),
            Some(Val::Sphere(s)) => s.distance(p),
            Some(Val::Cylinder(c)) => c.distance(p),
            Some(Val::Torus(t)) => t.distance(p),
            v => malformed(r, "a locus of space", v),
        }
    }

    /// The axis through the point in `pivot` along the direction in `dir`, made unit.
    fn axis(&self, i: usize, [pivot, dir]: [Reg; 2]) -> Result<Line3, SolveError> {
        Ok(Line3::new(self.p3(pivot), self.unit(i, self.v3(dir))?))
    }

    /// The angles of a chain of turns (`found`) that `branch` takes, or that move the chain
    /// least by `moved` on the sketch, as step `i`'s answers; an error naming `constraint` when
    /// there are none.
    fn angles_of<const K: usize, const N: usize>(
        &mut self,
        i: usize,
        found: &gcs_runtime::Intersection<[f64; K], N>,
        (branch, constraint): (crate::plan::BranchId, ConstraintId),
        moved: impl Fn(&[f64; K]) -> f64,
    ) -> Result<Val, SolveError>
    where
        [f64; K]: Default,
    {
        let model = self.model;
        if let Some(e) = SolveError::from_contact("", "", found.contact) {
            return Err(err(model, constraint, e.kind, e.magnitude));
        }
        let index = self.choose(branch, |_| {
            (found.roots.as_slice().iter().enumerate())
                .min_by(|(_, x), (_, y)| moved(x).total_cmp(&moved(y)))
                .map(|(k, _)| k)
        });
        let angles = found.roots.get(index).ok_or_else(|| {
            err(
                model,
                constraint,
                ErrorKind::NoSuchBranch,
                found.roots.len() as f64,
            )
        })?;
        Ok(self.answers(i, angles.to_vec()))
    }

    /// The rotation about `axis` that takes `from` (a vector from the pivot, or a direction) to
    /// `to`: the shortest one, or the one about the axis in a register by the angle between
    /// the two's components across it.
    fn rotation(&self, axis: RotationAxis, from: V3, to: V3) -> UnitQuaternion<f64> {
        match axis {
            RotationAxis::Shortest => {
                frame::rotation_between3(&from, &to, &frame::perpendicular(&from))
            }
            RotationAxis::Along(a) => {
                let a = self.v3(a);
                frame::turn_about_axis(&a, &from, &to)
            }
            RotationAxis::Normal => {
                panic!("bug in gcs: a rotation about the plane's normal reached the spatial interpreter")
            }
        }
    }

    /// Runs one step of a spatial plan.
    fn step_spatial(&mut self, i: usize, step: &Step) -> Result<(), SolveError> {
        let model = self.model;
        if let Some(value) = self.scalar(i, &step.op)? {
            self.store(step, value);
            return Ok(());
        }
        let value = match &step.op {
            Op::PointOf(g) => Val::P3(self.config.point(model, *g)),
            Op::DirOf(g) => Val::V3(self.config.dir(model, *g)),
            Op::Along { from, dir, to } => {
                Val::S((self.p3(*to) - self.p3(*from)).dot(&self.v3(*dir)))
            }
            Op::DirectionTo { from, to } => Val::V3(self.unit(i, self.p3(*to) - self.p3(*from))?),
            Op::Midpoint { a, b } => Val::P3(locus3d::midpoint(self.p3(*a), self.p3(*b))),
            Op::Reflect { point, through } => {
                Val::P3(locus3d::reflect_through(self.p3(*point), self.p3(*through)))
            }
            Op::LocusParam { locus, point } => {
                let q = self.p3(*point);
                Val::S(match self.get(*locus) {
                    Some(&Val::L3(l)) => (q - l.point).dot(&l.dir),
                    Some(&Val::C3(c)) => c.angle_of(&q),
                    v => malformed(*locus, "a line or circle of space", v),
                })
            }
            Op::LocusPoint { locus, at } => {
                let t = self.s(*at);
                Val::P3(match self.get(*locus) {
                    Some(&Val::L3(l)) => l.point + l.dir * t,
                    Some(&Val::C3(c)) => c.point_at(t),
                    v => malformed(*locus, "a line or circle of space", v),
                })
            }
            Op::Line {
                point,
                dir,
                offset: None,
            } => Val::L3(Line3::new(self.p3(*point), self.unit(i, self.v3(*dir))?)),
            Op::ParallelLine { line, through } => {
                Val::L3(Line3::new(self.p3(*through), self.line3(*line).dir))
            }
            Op::ShiftedCircle { circle, from, to } => {
                Val::C3(self.circle3(*circle).shifted(&self.shift(*from, *to)))
            }
            Op::Nearest { locus, point } => {
                let q = self.p3(*point);
                Val::P3(match self.get(*locus) {
                    Some(&Val::L3(l)) => l.closest(&q),
                    Some(&Val::Plane(p)) => p.project(&q),
                    Some(&Val::Sphere(s)) => s.nearest(&q).ok_or_else(|| self.degenerate(i))?,
                    Some(&Val::C3(c)) => c.nearest(&q).ok_or_else(|| self.degenerate(i))?,
                    Some(&Val::Cylinder(c)) => c.nearest(&q).ok_or_else(|| self.degenerate(i))?,
                    Some(&Val::Torus(t)) => t.nearest(&q).ok_or_else(|| self.degenerate(i))?,
                    v => malformed(*locus, "a locus of space", v),
                })
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                let q = self.p3(*point);
                let gap = self.gap(*locus, &q);
                self.onto(i, *constraint, gap)?;
                Val::P3(q)
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            } => self.intersect3(*meet, (*a, *b), *branch, *constraint, *near)?,
            Op::Translate { geoms, from, to } => {
                let d = self.p3(*to) - self.p3(*from);
                for g in geoms {
                    self.config.translate(*g, d);
                }
                return Ok(());
            }
            Op::RotatePoint {
                geoms,
                pivot,
                axis,
                from,
                to,
            } => {
                let c = self.p3(*pivot);
                let rot = self.rotation(*axis, self.p3(*from) - c, self.p3(*to) - c);
                for g in geoms {
                    self.config.rotate(*g, c, rot);
                }
                return Ok(());
            }
            Op::RotateDir {
                geoms,
                pivot,
                axis,
                from,
                to,
            } => {
                let c = self.p3(*pivot);
                let rot = self.rotation(*axis, self.v3(*from), self.v3(*to));
                for g in geoms {
                    self.config.rotate(*g, c, rot);
                }
                return Ok(());
            }
            Op::SetDim { geom, value } => return self.set_dim(i, *geom, *value),
            Op::Check {
                constraint,
                residual,
                ..
            } => {
                let r = self.residual3(residual);
                return self.checked(i, *constraint, r);
            }
            Op::Error {
                residual,
                component: crate::plan::MAGNITUDE,
            } => Val::S(self.residual3(residual)),
            Op::Error {
                residual,
                component,
            } => Val::S(self.error_of3(residual, *component)),
            // Signed where the locus has two sides (zero on it, smooth across it); a line's or
            // circle's distance in space is not.
            Op::Implicit { locus, point } => {
                let q = self.p3(*point);
                Val::S(match self.get(*locus) {
                    Some(&Val::Plane(p)) => p.signed_distance(&q),
                    Some(&Val::Sphere(s)) => (q - s.center).norm() - s.radius,
                    Some(&Val::Cylinder(c)) => c.signed_distance(&q),
                    Some(&Val::Torus(t)) => t.signed_distance(&q),
                    _ => self.gap(*locus, &q),
                })
            }
            Op::Close {
                constraint,
                residual,
            } => return self.closed(*constraint, *residual),
            Op::Spatial(op) => match self.spatial(i, op)? {
                Some(value) => value,
                None => return Ok(()),
            },
            Op::Line {
                offset: Some(_), ..
            } => unreachable!("bug in gcs: step {i} offsets a line of space, which has no left"),
            Op::Planar(_) => {
                unreachable!("bug in gcs: step {i} is an operation of the plane in a spatial plan")
            }
            Op::Expr(_)
            | Op::Size { .. }
            | Op::Const(_)
            | Op::Default(_)
            | Op::Neg(_)
            | Op::DimOf(_)
            | Op::Sum(_)
            | Op::Unknown { .. } => {
                unreachable!("bug in gcs: step {i}'s scalar was evaluated above")
            }
        };
        self.store(step, value);
        Ok(())
    }

    /// The value of an operation of space; `None` for an action, which moves geoms.
    fn spatial(&mut self, i: usize, op: &SpatialOp) -> Result<Option<Val>, SolveError> {
        let model = self.model;
        Ok(Some(match op {
            SpatialOp::Opposite(d) => Val::V3(-self.v3(*d)),
            SpatialOp::Across(d) => Val::V3(self.unit(i, frame::perpendicular(&self.v3(*d)))?),
            SpatialOp::AngleAbout { u, v, axis } => Val::S(frame::signed_angle3(
                &self.v3(*u),
                &self.v3(*v),
                &self.v3(*axis),
            )),
            SpatialOp::AngleAboutBoth { u, v, axis } => Val::S(frame::signed_angle3_both(
                [&self.v3(u[0]), &self.v3(u[1])],
                [&self.v3(v[0]), &self.v3(v[1])],
                &self.v3(*axis),
            )),
            SpatialOp::TurnReaching {
                u,
                v,
                axis,
                pivot,
                reach,
                screw,
            } => {
                let (dirs, at) = (
                    [&self.v3(*u), &self.v3(*v)],
                    (&self.p3(*pivot), &self.v3(*axis)),
                );
                let helix = |h: &crate::plan::HelixRegs| fragment3::Helix {
                    axis: self.v3(h.axis),
                    x_from: self.v3(h.x_from),
                    origin: self.p3(h.origin),
                    x: self.v3(h.x),
                    point: self.p3(h.point),
                    pitch: self.s(h.pitch),
                };
                let screw = screw.map(|s| fragment3::Screw {
                    helix: helix(&s.helix),
                    slide: self.line3(s.slide).dir,
                });
                let screw = screw.as_ref();
                Val::S(match reach {
                    crate::plan::Reach::Helix(h) => {
                        fragment3::turn_reaching_helix(dirs, at, &helix(h), screw)
                    }
                    crate::plan::Reach::Point { point, locus } => {
                        let p = self.p3(*point);
                        match self.get(*locus) {
                            Some(&Val::Plane(plane)) => {
                                fragment3::turn_reaching_plane(dirs, at, &p, &plane, screw)
                            }
                            _ => {
                                let line = self.line3(*locus);
                                fragment3::turn_reaching_line(dirs, at, &p, &line, screw)
                            }
                        }
                    }
                })
            }
            SpatialOp::HelixAdvance { now, turn, pitch } => {
                let advance = frame::helix_advance(self.s(*now), self.s(*turn), self.s(*pitch));
                Val::S(self.finite(i, advance)?)
            }
            SpatialOp::Aligned { dir, near } => {
                Val::V3(frame::aligned(&self.v3(*dir), &self.v3(*near)))
            }
            SpatialOp::PassingAngle {
                from,
                to,
                d,
                now,
                constraint,
            } => {
                let (a, b, n) = (self.p3(*from), self.p3(*to), self.v3(*now));
                let i = fragment3::passing_angle(&a, &b, self.s(*d), &n);
                if let Some(e) = SolveError::from_contact("", "", i.contact) {
                    return Err(err(model, *constraint, e.kind, e.magnitude));
                }
                Val::S(
                    i.roots
                        .get(0)
                        .ok_or_else(|| err(model, *constraint, ErrorKind::Degenerate, 0.0))?,
                )
            }
            SpatialOp::TiltToDistance {
                centre,
                point,
                radius,
                d,
                now,
                constraint,
            } => {
                let (c, p, n) = (self.p3(*centre), self.p3(*point), self.v3(*now));
                let i = fragment3::tilt_to_distance(&c, &p, self.s(*radius), self.s(*d), &n);
                if let Some(e) = SolveError::from_contact("", "", i.contact) {
                    return Err(err(model, *constraint, e.kind, e.magnitude));
                }
                Val::S(
                    i.roots
                        .get(0)
                        .ok_or_else(|| err(model, *constraint, ErrorKind::Degenerate, 0.0))?,
                )
            }
            SpatialOp::ConeTurn { axis, angle, dir } => Val::V3(frame::plane_turn(
                &self.v3(*axis),
                self.s(*angle).cos(),
                &self.v3(*dir),
            )),
            SpatialOp::AngleTurn {
                u,
                v,
                axis,
                angle,
                branch,
                constraint,
            } => {
                let (dir, a) = (self.v3(*v), self.v3(*axis));
                let i3 = frame::turns_to_angle(&self.v3(*u), &dir, &a, self.s(*angle));
                if let Some(e) = SolveError::from_contact("", "", i3.contact) {
                    return Err(err(model, *constraint, e.kind, e.magnitude));
                }
                let index =
                    self.choose(*branch, |_| i3.roots.nearest_to(dir, |x, y| (x - y).norm()));
                Val::V3(i3.roots.get(index).ok_or_else(|| {
                    err(
                        model,
                        *constraint,
                        ErrorKind::NoSuchBranch,
                        i3.roots.len() as f64,
                    )
                })?)
            }
            SpatialOp::PlaneTurn {
                base,
                normal,
                pivot,
                point,
                d,
                constraint,
            } => {
                let n = self.v3(*normal);
                let (w, c) = self.plane_cone(*base, n, *pivot, *point, *d);
                let len = w.norm();
                if len.is_nan() || len <= 0.0 {
                    return Err(err(model, *constraint, ErrorKind::Degenerate, 0.0));
                }
                if c.abs() > 1.0 + gcs_runtime::tol::LENGTH_REL || c.is_nan() {
                    return Err(err(
                        model,
                        *constraint,
                        ErrorKind::NoIntersection,
                        (c.abs() - 1.0) * len,
                    ));
                }
                Val::V3(frame::plane_turn(&(w / len), c.clamp(-1.0, 1.0), &n))
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
                let n = self.v3(*normal);
                let (w, c) = self.plane_cone(*base, n, *pivot, *point, *d);
                let Some(wh) = w.try_normalize(0.0) else {
                    return Err(err(model, *constraint, ErrorKind::Degenerate, 0.0));
                };
                let angle = c.clamp(-1.0, 1.0).acos();
                let gap = (c.abs() - 1.0).max(0.0) * w.norm();
                let i3 = frame::turns_to_angle(&wh, &n, &self.v3(*axis), angle);
                if let Some(e) = SolveError::from_contact("", "", i3.contact) {
                    return Err(err(model, *constraint, e.kind, e.magnitude.max(gap)));
                }
                if gap > gcs_runtime::tol::LENGTH_REL * (1.0 + w.norm()) {
                    return Err(err(model, *constraint, ErrorKind::NoIntersection, gap));
                }
                let index = self.choose(*branch, |_| i3.roots.nearest_to(n, |x, y| (x - y).norm()));
                Val::V3(i3.roots.get(index).ok_or_else(|| {
                    err(
                        model,
                        *constraint,
                        ErrorKind::NoSuchBranch,
                        i3.roots.len() as f64,
                    )
                })?)
            }
            SpatialOp::MirrorPlane {
                point,
                base,
                normal,
            } => Val::P3(locus3d::mirror(
                self.p3(*base),
                self.v3(*normal),
                self.p3(*point),
            )),
            SpatialOp::PlaneNormal { a, b, c } => {
                let a = self.p3(*a);
                Val::V3(self.unit(i, (self.p3(*b) - a).cross(&(self.p3(*c) - a)))?)
            }
            SpatialOp::WorldAxis(i) => {
                let mut v = V3::zeros();
                v[usize::from(*i).min(2)] = 1.0;
                Val::V3(v)
            }
            SpatialOp::Coordinate { point, axis } => {
                Val::S(self.p3(*point)[usize::from(*axis).min(2)])
            }
            SpatialOp::PointAt { x, y, z } => Val::P3(P3::new(self.s(*x), self.s(*y), self.s(*z))),
            SpatialOp::SurfaceParam {
                locus,
                point,
                component,
            } => {
                let uv = self.surface(*locus).coordinates(&self.p3(*point));
                Val::S(uv[usize::from(*component).min(1)])
            }
            SpatialOp::SurfacePoint { locus, u, v } => {
                Val::P3(self.surface(*locus).at([self.s(*u), self.s(*v)]))
            }
            SpatialOp::HelixTurn { advance, pitch } => {
                Val::S(self.finite(i, frame::helix_turn(self.s(*advance), self.s(*pitch)))?)
            }
            SpatialOp::TurnedAbout { dir, axis, angle } => {
                let q = frame::rotation_about_axis(&self.v3(*axis), self.s(*angle));
                Val::V3(q * self.v3(*dir))
            }
            SpatialOp::Plane {
                point,
                normal,
                offset,
            } => {
                let n = self.unit(i, self.v3(*normal))?;
                let at = self.p3(*point) + n * self.s_or_zero(*offset);
                Val::Plane(Plane::from_point_normal(&at, &n))
            }
            SpatialOp::ParallelPlane { plane, through } => Val::Plane(Plane::from_point_normal(
                &self.p3(*through),
                &self.plane(*plane).normal,
            )),
            SpatialOp::Circle3 {
                center,
                normal,
                radius,
            } => Val::C3(Circle3::new(
                self.p3(*center),
                self.unit(i, self.v3(*normal))?,
                self.s(*radius),
            )),
            SpatialOp::Sphere { center, radius } => {
                Val::Sphere(Sphere::new(self.p3(*center), self.s(*radius)))
            }
            SpatialOp::Cylinder { point, dir, radius } => Val::Cylinder(Cylinder::new(
                Line3::new(self.p3(*point), self.unit(i, self.v3(*dir))?),
                self.s(*radius),
            )),
            SpatialOp::Torus { circle, tube } => {
                Val::Torus(Torus::new(self.circle3(*circle), self.s(*tube)))
            }
            SpatialOp::ShiftedTorus { torus, from, to } => {
                let t = match self.get(*torus) {
                    Some(&Val::Torus(t)) => t,
                    v => malformed(*torus, "a torus", v),
                };
                Val::Torus(t.shifted(&self.shift(*from, *to)))
            }
            SpatialOp::ShiftedCylinder { cylinder, from, to } => {
                Val::Cylinder(self.cylinder(*cylinder).shifted(&self.shift(*from, *to)))
            }
            SpatialOp::SphereThrough {
                center,
                through,
                radius,
            } => {
                let c = self.p3(*center);
                let r = radius.unwrap_or_else(|| (self.p3(*through) - c).norm());
                Val::Sphere(Sphere::new(c, r))
            }
            SpatialOp::ShiftedSphere { sphere, from, to } => {
                Val::Sphere(self.sphere(*sphere).shifted(&self.shift(*from, *to)))
            }
            SpatialOp::Orbit {
                pivot,
                axis,
                through,
            } => {
                let a = self.unit(i, self.v3(*axis))?;
                Val::C3(Circle3::orbit(&self.p3(*pivot), &a, &self.p3(*through)))
            }
            SpatialOp::ThreeCircles {
                first,
                a,
                second,
                third,
                b,
                near,
                branch,
                constraint,
            } => {
                let (l1, l2, l3) = (
                    self.axis(i, *first)?,
                    self.axis(i, *second)?,
                    self.axis(i, *third)?,
                );
                let found = turn3d::three_circles(&l1, &self.p3(*a), &l2, &l3, &self.p3(*b));
                // The root that leaves the chain's two joints nearest where they are (the
                // second's pivot) and were (the third's, before the chain was assembled).
                let (second_now, third_was) = (l2.point, self.p3(*near));
                let moved = |&[t1, t2, _]: &[f64; 3]| {
                    let second_to = turn3d::turn_point(&l1, -t1, &second_now);
                    let third_to =
                        turn3d::turn_point(&l1, -t1, &turn3d::turn_point(&l2, t2, &l3.point));
                    (second_to - second_now).norm() + (third_to - third_was).norm()
                };
                self.angles_of(i, &found, (*branch, *constraint), moved)?
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
                let (l1, lj, l6) = (
                    self.axis(i, *first)?,
                    self.axis(i, *joint)?,
                    self.axis(i, *last)?,
                );
                let found = turn3d::planar_chain_ends(
                    &l1,
                    &self.v3(*h),
                    &self.p3(*base),
                    &lj,
                    &self.v3(*far),
                    &l6,
                    self.s(*offset),
                    *sense,
                );
                // The least turn of both from where they are.
                let turn = |t: &[f64; 2]| t[0].abs() + t[1].abs();
                self.angles_of(i, &found, (*branch, *constraint), turn)?
            }
            SpatialOp::RotateBy {
                geoms,
                pivot,
                axis,
                angle,
            } => {
                let c = self.p3(*pivot);
                let rot = frame::rotation_about_axis(&self.v3(*axis), self.s(*angle));
                for g in geoms {
                    self.config.rotate(*g, c, rot);
                }
                return Ok(None);
            }
        }))
    }

    /// The root of the intersection of loci `a` and `b` that `branch` (or the choice) takes:
    /// a point, or (two spheres, a sphere and a plane, two planes) a locus.
    fn intersect3(
        &mut self,
        meet: Meet,
        (a, b): (Reg, Reg),
        branch: crate::plan::BranchId,
        constraint: ConstraintId,
        near: Reg,
    ) -> Result<Val, SolveError> {
        let model = self.model;
        let fail = |contact: Contact| -> Option<SolveError> {
            match contact {
                Contact::Crossing | Contact::Tangent => None,
                Contact::Disjoint { gap } | Contact::Parallel { gap } => {
                    Some(err(model, constraint, ErrorKind::NoIntersection, gap))
                }
                Contact::Coincident | Contact::ZeroRadius => {
                    Some(err(model, constraint, ErrorKind::Degenerate, 0.0))
                }
            }
        };
        let (roots, contact): (Roots<P3, 4>, Contact) = match meet {
            Meet::LinePlane => {
                let i = intersect3d::line_plane(&self.line3(a), &self.plane(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::LineSphere => {
                let i = intersect3d::line_sphere(&self.line3(a), &self.sphere(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::CirclePlane => {
                let i = intersect3d::circle_plane(&self.circle3(a), &self.plane(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::CircleSphere => {
                let i = intersect3d::circle_sphere(&self.circle3(a), &self.sphere(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::CircleCircle => {
                let i = intersect3d::circle_circle(&self.circle3(a), &self.circle3(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::LineCircle => {
                let i = intersect3d::line_circle(&self.line3(a), &self.circle3(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::LineCylinder => {
                let i = intersect3d::line_cylinder(&self.line3(a), &self.cylinder(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            // Lines: the one the branch takes, by default the nearest the sketch's point.
            Meet::PlaneCylinder => {
                let i = intersect3d::plane_cylinder_lines(&self.plane(a), &self.cylinder(b));
                if let Some(e) = fail(i.contact) {
                    return Err(e);
                }
                let lines = i.roots;
                let index = self.choose(branch, |s| {
                    let x = s.p3(near);
                    (0..lines.len()).min_by(|&j, &k| {
                        let d = |l: usize| lines.get(l).map_or(f64::INFINITY, |l| l.distance(&x));
                        d(j).total_cmp(&d(k))
                    })
                });
                return lines.get(index).map(Val::L3).ok_or_else(|| {
                    err(
                        model,
                        constraint,
                        ErrorKind::NoSuchBranch,
                        lines.len() as f64,
                    )
                });
            }
            Meet::SphereSphere | Meet::SpherePlane | Meet::PlanePlane => {
                let (locus, contact) = match meet {
                    Meet::SphereSphere => {
                        let i = intersect3d::sphere_sphere(&self.sphere(a), &self.sphere(b));
                        (i.roots.get(0).map(Val::C3), i.contact)
                    }
                    Meet::SpherePlane => {
                        let i = intersect3d::sphere_plane(&self.sphere(a), &self.plane(b));
                        (i.roots.get(0).map(Val::C3), i.contact)
                    }
                    _ => {
                        let i = intersect3d::plane_plane(&self.plane(a), &self.plane(b));
                        (i.roots.get(0).map(Val::L3), i.contact)
                    }
                };
                if let Some(e) = fail(contact) {
                    return Err(e);
                }
                self.choose(branch, |_| Some(0));
                return locus.ok_or_else(|| err(model, constraint, ErrorKind::NoSuchBranch, 0.0));
            }
            planar => panic!(
                "bug in gcs: the planar intersection {planar:?} reached the spatial interpreter"
            ),
        };
        if let Some(e) = fail(contact) {
            return Err(e);
        }
        let index = self.choose(branch, |s| {
            roots.nearest_to(s.p3(near), |x, y| (x - y).norm())
        });
        // The chosen branch has no root here: say so, never take another.
        roots.get(index).map(Val::P3).ok_or_else(|| {
            err(
                model,
                constraint,
                ErrorKind::NoSuchBranch,
                roots.len() as f64,
            )
        })
    }

    /// The signed error of a relation in space (component: a coincidence's axis, 0 to 2).
    fn error_of3(&self, residual: &Residual, component: u8) -> f64 {
        match *residual {
            Residual::PointPoint { a, b, d: None } => {
                let v = self.p3(a) - self.p3(b);
                v[usize::from(component.min(2))]
            }
            Residual::PointPoint { a, b, d } => {
                (self.p3(a) - self.p3(b)).norm() - self.s_or_zero(d)
            }
            Residual::PointPlane { p, base, normal, d } => {
                (self.p3(p) - self.p3(base)).dot(&self.v3(normal)) - self.s_or_zero(d)
            }
            // At a distance from a circle: signed, smooth where the distance is not zero.
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d: Some(d),
            } => {
                let c = Circle3::new(self.p3(centre), self.v3(normal), self.s(radius));
                c.distance(&self.p3(p)) - self.s(d)
            }
            // At a distance from the line: signed, smooth where the distance is not zero.
            Residual::PointLine {
                p,
                base,
                dir,
                d: Some(d),
            } => (self.p3(p) - self.p3(base)).cross(&self.v3(dir)).norm() - self.s(d),
            // On the line: the offset across it, one signed coordinate (`Op::Error`).
            Residual::PointLine {
                p,
                base,
                dir,
                d: None,
            } if component == 1 || component == 2 => {
                check::space::across_line(self.p3(p), self.p3(base), self.v3(dir))
                    [usize::from(component - 1)]
            }
            Residual::Midpoint { p, a, b } => {
                let v = locus3d::midpoint(self.p3(a), self.p3(b)) - self.p3(p);
                v[usize::from(component.min(2))]
            }
            Residual::MirrorPlane { p, q, base, normal } => {
                let image = locus3d::mirror(self.p3(base), self.v3(normal), self.p3(p));
                (self.p3(q) - image)[usize::from(component.min(2))]
            }
            Residual::Cone { axis, u, v } => (self.v3(u) - self.v3(v)).dot(&self.v3(axis)),
            _ => self.residual3(residual),
        }
    }

    /// The residual of a check in space: the runtime's measure of its kind.
    fn residual3(&self, residual: &Residual) -> f64 {
        use check::space as c;
        match *residual {
            Residual::PointPoint { a, b, d } => {
                c::point_point(self.p3(a), self.p3(b), self.s_or_zero(d))
            }
            Residual::PointLine { p, base, dir, d } => {
                c::point_line(self.p3(p), self.p3(base), self.v3(dir), self.s_or_zero(d))
            }
            Residual::PointPlane { p, base, normal, d } => c::point_plane(
                self.p3(p),
                self.p3(base),
                self.v3(normal),
                self.s_or_zero(d),
            ),
            Residual::Parallel { u, v, sense } => c::parallel(self.v3(u), self.v3(v), sense),
            Residual::AngleBetween { u, v, angle } => {
                c::angle_between(self.v3(u), self.v3(v), self.s(angle))
            }
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d,
            } => {
                let c = Circle3::new(self.p3(centre), self.v3(normal), self.s(radius));
                (c.distance(&self.p3(p)) - self.s_or_zero(d)).abs()
            }
            Residual::Twist { axis, u, v, angle } => {
                c::twist(self.v3(axis), self.v3(u), self.v3(v), self.s(angle))
            }
            Residual::Cone { axis, u, v } => c::cone(self.v3(axis), self.v3(u), self.v3(v)),
            Residual::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } => c::helix(
                self.v3(axis),
                self.v3(u),
                self.v3(v),
                self.p3(q) - self.p3(p),
                self.s(pitch),
            ),
            Residual::Dim { value, target } => check::dimension(self.s(value), self.s(target)),
            Residual::Midpoint { p, a, b } => c::midpoint(self.p3(p), self.p3(a), self.p3(b)),
            Residual::MirrorPlane { p, q, base, normal } => {
                c::mirror(self.p3(p), self.p3(q), self.p3(base), self.v3(normal))
            }
            ref other => panic!("bug in gcs: the check {other:?} is no check of a spatial plan"),
        }
    }
}
