//! The interpreter's steps in the plane: points, unit directions, lines, circles and conics
//! of `locus2d`, moving `Frame2`s.

use super::{err, malformed, Machine, Space, Val};
use crate::config::{D2, P2, V2};
use crate::plan::{Meet, Op, PlanarOp, Reg, Residual, RotationAxis, Step};
use gcs_lang::model::ConstraintId;
use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::locus2d::{self, Circle, Conic, Line, Sense};
use gcs_runtime::{check, frame, intersect2d, Contact, Roots};

impl Space for D2 {
    fn step(m: &mut Machine<'_, '_, D2>, i: usize, step: &Step) -> Result<(), SolveError> {
        m.step_planar(i, step)
    }
}

impl Machine<'_, '_, D2> {
    fn p(&self, r: Reg) -> P2 {
        match self.get(r) {
            Some(&Val::P(x)) => x,
            v => malformed(r, "a point", v),
        }
    }
    fn v(&self, r: Reg) -> V2 {
        match self.get(r) {
            Some(&Val::V(x)) => x,
            v => malformed(r, "a direction", v),
        }
    }
    fn line(&self, r: Reg) -> Line {
        match self.get(r) {
            Some(&Val::L(x)) => x,
            v => malformed(r, "a line", v),
        }
    }
    fn circle(&self, r: Reg) -> Circle {
        match self.get(r) {
            Some(&Val::C(x)) => x,
            v => malformed(r, "a circle", v),
        }
    }
    fn conic(&self, r: Reg) -> Conic {
        match self.get(r) {
            Some(&Val::Q(x)) => x,
            v => malformed(r, "a conic", v),
        }
    }
    /// Solves the linear system of step `i` (as generated code does, to the bit).
    fn linear_system(
        &mut self,
        i: usize,
        system: &crate::plan::LinearSystem,
    ) -> Result<Val, SolveError> {
        use crate::plan::Coef;
        let mut coef = Vec::new();
        let mut rhs = Vec::with_capacity(system.rows.len());
        for row in &system.rows {
            rhs.push(-self.s(row.error));
            for t in &row.terms {
                let c = match t.coef {
                    Coef::One => 1.0,
                    Coef::X(v) => self.v(v).x,
                    Coef::Y(v) => self.v(v).y,
                    Coef::Dot(a, b) => self.v(a).dot(&self.v(b)),
                    Coef::Cross(a, b) => {
                        let (a, b) = (self.v(a), self.v(b));
                        a.x * b.y - a.y * b.x
                    }
                };
                coef.push(t.scale * c);
            }
        }
        let (row_start, term_unknown) = system.shape();
        let torn = gcs_runtime::linear::Torn {
            unknowns: system.unknowns as usize,
            row_start: &row_start,
            term_unknown: &term_unknown,
            tears: &system.tears,
            pivots: &system.pivots,
            closures: &system.closures,
        };
        let n = system.unknowns as usize;
        let mut forms = vec![0.0; n * (system.tears.len() + 1)];
        let mut x = vec![0.0; n];
        if let Err(s) = torn.solve_into(&coef, &rhs, &mut forms, &mut x) {
            let c = system.rows.get(s.row).map(|r| r.constraint);
            return Err(match c {
                Some(c) => err(self.model, c, ErrorKind::Degenerate, 0.0),
                None => self.degenerate(i),
            });
        }
        Ok(self.answers(i, x))
    }

    /// Runs one step of a planar plan.
    fn step_planar(&mut self, i: usize, step: &Step) -> Result<(), SolveError> {
        let model = self.model;
        if let Some(value) = self.scalar(i, &step.op)? {
            self.store(step, value);
            return Ok(());
        }
        let value = match &step.op {
            Op::Along { from, dir, to } => Val::S((self.p(*to) - self.p(*from)).dot(&self.v(*dir))),
            Op::DirectionTo { from, to } => {
                let d = self.p(*to) - self.p(*from);
                let n = d.norm();
                if n.is_nan() || n <= 0.0 {
                    return Err(self.degenerate(i));
                }
                Val::V(d / n)
            }
            Op::PointOf(g) => Val::P(self.config.point(model, *g)),
            Op::DirOf(g) => Val::V(self.config.dir(model, *g)),
            Op::Error {
                residual,
                component: crate::plan::MAGNITUDE,
            } => Val::S(self.residual(residual)),
            Op::Error {
                residual,
                component,
            } => Val::S(self.error_of(residual, *component)),
            Op::Midpoint { a, b } => Val::P(locus2d::midpoint(self.p(*a), self.p(*b))),
            Op::Reflect { point, through } => {
                Val::P(locus2d::reflect_through(self.p(*point), self.p(*through)))
            }
            Op::LocusPoint { locus, at } => {
                let t = self.s(*at);
                Val::P(match self.get(*locus) {
                    Some(&Val::L(l)) => l.at(t),
                    Some(&Val::C(c)) => c.at(t),
                    Some(&Val::Q(q)) => q.at(t),
                    v => malformed(*locus, "a line, a circle or a conic", v),
                })
            }
            Op::Implicit { locus, point } => {
                let q = self.p(*point);
                Val::S(match self.get(*locus) {
                    Some(&Val::L(l)) => l.closing_error(q),
                    Some(&Val::C(c)) => c.closing_error(q),
                    Some(&Val::Q(k)) => k.closing_error(q),
                    v => malformed(*locus, "a line, a circle or a conic", v),
                })
            }
            Op::LocusParam { locus, point } => {
                let q = self.p(*point);
                Val::S(match self.get(*locus) {
                    Some(&Val::L(l)) => l.param_of(q),
                    Some(&Val::C(c)) => c.param_of(q),
                    Some(&Val::Q(k)) => k.param_of(q),
                    v => malformed(*locus, "a line, a circle or a conic", v),
                })
            }
            Op::Line { point, dir, offset } => {
                let l =
                    Line::new(self.p(*point), self.v(*dir)).ok_or_else(|| self.degenerate(i))?;
                Val::L(match offset {
                    Some(o) => l.offset(self.s(*o)),
                    None => l,
                })
            }
            Op::ParallelLine { line, through } => Val::L(
                Line::new(self.p(*through), self.line(*line).dir())
                    .ok_or_else(|| self.degenerate(i))?,
            ),
            Op::ShiftedCircle { circle, from, to } => {
                let c = self.circle(*circle);
                let moved = Circle::new(c.center() + (self.p(*to) - self.p(*from)), c.radius());
                Val::C(moved.ok_or_else(|| self.degenerate(i))?)
            }
            Op::Nearest { locus, point } => {
                let q = self.p(*point);
                Val::P(match self.get(*locus) {
                    Some(&Val::L(l)) => l.nearest(q),
                    Some(&Val::C(c)) => c.nearest(q),
                    v => malformed(*locus, "a line or a circle", v),
                })
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                let q = self.p(*point);
                let gap = match self.get(*locus) {
                    Some(&Val::L(l)) => l.residual(q),
                    Some(&Val::C(c)) => c.residual(q),
                    Some(&Val::Q(k)) => k.residual(q),
                    v => malformed(*locus, "a locus", v),
                };
                self.onto(i, *constraint, gap)?;
                Val::P(q)
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            } => Val::P(self.intersect(*meet, (*a, *b), *branch, *constraint, *near)?),
            Op::Translate { geoms, from, to } => {
                let d = self.p(*to) - self.p(*from);
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
                planar_axis(*axis);
                let c = self.p(*pivot);
                let rot =
                    gcs_runtime::frame::rotation_between2(&(self.p(*from) - c), &(self.p(*to) - c));
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
                planar_axis(*axis);
                let c = self.p(*pivot);
                let rot = gcs_runtime::frame::rotation_between_units(&self.v(*from), &self.v(*to));
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
                let r = self.residual(residual);
                return self.checked(i, *constraint, r);
            }
            Op::Close {
                constraint,
                residual,
            } => return self.closed(*constraint, *residual),
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
            Op::Planar(op) => self.planar(i, op)?,
            Op::Spatial(_) => {
                unreachable!("bug in gcs: step {i} is an operation of space in a planar plan")
            }
        };
        self.store(step, value);
        Ok(())
    }

    /// The value of an operation of the plane.
    fn planar(&mut self, i: usize, op: &PlanarOp) -> Result<Val, SolveError> {
        let model = self.model;
        Ok(match op {
            PlanarOp::Reversed(x) => Val::L(self.line(*x).reversed()),
            PlanarOp::LineDir(x) => Val::V(self.line(*x).dir()),
            PlanarOp::Linear(system) => self.linear_system(i, system)?,
            PlanarOp::OffsetLine { line, by } => Val::L(self.line(*line).offset(self.s(*by))),
            PlanarOp::CentresLineLine { l1, a1, l2, a2 } => Val::L(
                locus2d::centres_line_line(
                    &self.line(*l1),
                    self.s(*a1),
                    &self.line(*l2),
                    self.s(*a2),
                )
                .ok_or_else(|| self.degenerate(i))?,
            ),
            PlanarOp::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => {
                let q = locus2d::centres_line_circle(
                    &self.line(*line),
                    self.s(*a),
                    self.p(*at),
                    sense(*plus),
                    self.s(*b),
                )
                .ok_or_else(|| self.degenerate(i))?;
                Val::Q(Conic::Parabola(q))
            }
            PlanarOp::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => Val::Q(
                locus2d::centres_circle_circle(
                    self.p(*c1),
                    sense(*p1),
                    self.s(*b1),
                    self.p(*c2),
                    sense(*p2),
                    self.s(*b2),
                )
                .ok_or_else(|| self.degenerate(i))?,
            ),
            PlanarOp::RadiusFromLine { line, a, centre } => {
                Val::S(self.line(*line).signed_distance(self.p(*centre)) - self.s(*a))
            }
            PlanarOp::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => {
                let d = (self.p(*centre) - self.p(*at)).norm();
                Val::S(if *plus {
                    d - self.s(*b)
                } else {
                    self.s(*b) - d
                })
            }
            PlanarOp::Axis(x, y) => Val::V(V2::new(*x, *y)),
            PlanarOp::Rotated { dir, angle } => {
                // The turn generated code makes, to the bit: `direction_at`'s sine and cosine.
                let turn = frame::rotation_from_x_unit(&frame::direction_at(self.s(*angle)));
                Val::V(turn * self.v(*dir))
            }
            PlanarOp::AngleOf(dir) => {
                let d = self.v(*dir);
                Val::S(d.y.atan2(d.x))
            }
            PlanarOp::PointXY { x, y } => Val::P(P2::new(self.s(*x), self.s(*y))),
            PlanarOp::Mirror { point, line } => Val::P(self.line(*line).mirror(self.p(*point))),
            PlanarOp::Circle { center, radius } => {
                let rr = self.s(*radius);
                if rr < 0.0 {
                    // A locus circle of negative radius: the distance cannot be met.
                    return Err(self.error(i, ErrorKind::NoIntersection, -rr));
                }
                Val::C(Circle::new(self.p(*center), rr).ok_or_else(|| self.degenerate(i))?)
            }
            PlanarOp::CircleThrough {
                center,
                through,
                radius,
            } => {
                let c = self.p(*center);
                let r = radius.unwrap_or_else(|| (self.p(*through) - c).norm());
                Val::C(Circle::new(c, r).ok_or_else(|| self.degenerate(i))?)
            }
            PlanarOp::PassingDir {
                pivot,
                base,
                dir,
                point,
                offset,
                branch,
                constraint,
            } => {
                let (o, u) = (self.p(*pivot), self.v(*dir));
                // The base's own offset from the pivot turns with the line: the line through
                // the pivot must pass the point that much further.
                let e = self.s_or_zero(*offset) + locus2d::cross(u, self.p(*base) - o);
                let i = intersect2d::passing_directions(o, self.p(*point), e);
                if let Some(e) = SolveError::from_contact("", "", i.contact) {
                    return Err(err(model, *constraint, e.kind, e.magnitude));
                }
                let index = self.choose(*branch, |_| i.roots.nearest_to(u, |x, y| (x - y).norm()));
                Val::V(i.roots.get(index).ok_or_else(|| {
                    err(
                        model,
                        *constraint,
                        ErrorKind::NoSuchBranch,
                        i.roots.len() as f64,
                    )
                })?)
            }
        })
    }

    /// The root of the intersection of loci `a` and `b` that `branch` (or the choice) takes.
    fn intersect(
        &mut self,
        meet: Meet,
        (a, b): (Reg, Reg),
        branch: crate::plan::BranchId,
        constraint: ConstraintId,
        near: Reg,
    ) -> Result<P2, SolveError> {
        let (roots, contact): (Roots<P2, 4>, Contact) = match meet {
            Meet::CircleCircle => {
                let i = intersect2d::circle_circle(&self.circle(a), &self.circle(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::LineCircle => {
                let i = intersect2d::line_circle(&self.line(a), &self.circle(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::CircleConic => {
                let i = intersect2d::circle_conic(&self.circle(a), &self.conic(b));
                (i.roots, i.contact)
            }
            Meet::LineConic => {
                let i = intersect2d::line_conic(&self.line(a), &self.conic(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            Meet::ConicConic => {
                let i = intersect2d::conic_conic(&self.conic(a), &self.conic(b));
                (i.roots, i.contact)
            }
            Meet::LineLine => {
                let i = intersect2d::line_line(&self.line(a), &self.line(b));
                (Roots::from_slice(i.roots.as_slice()), i.contact)
            }
            spatial => panic!(
                "bug in gcs: the spatial intersection {spatial:?} reached the planar interpreter"
            ),
        };
        let model = self.model;
        match contact {
            Contact::Crossing | Contact::Tangent => {}
            Contact::Disjoint { gap } | Contact::Parallel { gap } => {
                return Err(err(model, constraint, ErrorKind::NoIntersection, gap));
            }
            Contact::Coincident | Contact::ZeroRadius => {
                return Err(err(model, constraint, ErrorKind::Degenerate, 0.0));
            }
        }
        let index = self.choose(branch, |s| {
            roots.nearest_to(s.p(near), |x, y| (x - y).norm())
        });
        // The chosen branch has no root here: say so, never take another.
        roots.get(index).ok_or_else(|| {
            err(
                model,
                constraint,
                ErrorKind::NoSuchBranch,
                roots.len() as f64,
            )
        })
    }

    /// How far a check's relation is from holding: the runtime's residual of its kind.
    /// The signed error of a relation (the residual is its magnitude).
    fn error_of(&self, residual: &Residual, component: u8) -> f64 {
        use check::error as e;
        match *residual {
            Residual::PointPoint { a, b, d: None } => {
                e::coincidence(self.p(a), self.p(b), component)
            }
            Residual::PointPoint { a, b, d } => {
                e::point_point(self.p(a), self.p(b), self.s_or_zero(d))
            }
            Residual::PointLine { p, base, dir, d } => {
                e::point_line(self.p(p), self.p(base), self.v(dir), self.s_or_zero(d))
            }
            Residual::Angle { u, v, angle } => e::angle(self.v(u), self.v(v), self.s(angle)),
            Residual::CircleLine {
                centre,
                radius,
                base,
                dir,
                gap,
                side,
            } => e::circle_line(
                self.p(centre),
                self.s(radius),
                self.p(base),
                self.v(dir),
                self.s_or_zero(gap),
                side,
            ),
            Residual::PointCircle {
                p,
                centre,
                radius,
                gap,
                outside,
            } => e::point_circle(
                self.p(p),
                self.p(centre),
                self.s(radius),
                self.s_or_zero(gap),
                outside,
            ),
            Residual::CircleCircle {
                c1,
                r1,
                c2,
                r2,
                gap,
                nesting,
            } => e::circle_circle(
                self.p(c1),
                self.s(r1),
                self.p(c2),
                self.s(r2),
                self.s_or_zero(gap),
                nesting,
            ),
            Residual::Dim { value, target } => e::dimension(self.s(value), self.s(target)),
            Residual::Midpoint { p, a, b } => {
                e::midpoint(self.p(p), self.p(a), self.p(b), component)
            }
            Residual::Mirror { p, q, base, dir } => {
                e::mirror(self.p(p), self.p(q), self.p(base), self.v(dir), component)
            }
            Residual::PointPlane { .. }
            | Residual::Parallel { .. }
            | Residual::Twist { .. }
            | Residual::Cone { .. }
            | Residual::AngleBetween { .. }
            | Residual::OnCircle { .. }
            | Residual::MirrorPlane { .. }
            | Residual::Helix { .. } => {
                panic!("bug in gcs: a spatial check reached the planar interpreter")
            }
        }
    }

    /// The residual of a check: the magnitude of its relation's error (a coincidence's, a
    /// midpoint's or a mirror image's is the distance, of which its two errors are the
    /// components).
    fn residual(&self, residual: &Residual) -> f64 {
        match *residual {
            Residual::PointPoint { a, b, d: None } => check::point_point(self.p(a), self.p(b), 0.0),
            Residual::Midpoint { p, a, b } => check::midpoint(self.p(p), self.p(a), self.p(b)),
            Residual::Mirror { p, q, base, dir } => {
                check::mirror(self.p(p), self.p(q), self.p(base), self.v(dir))
            }
            _ => self.error_of(residual, 0).abs(),
        }
    }
}

/// A rotation of the plane turns about its normal; any other axis is a spatial plan's.
fn planar_axis(axis: RotationAxis) {
    if axis != RotationAxis::Normal {
        panic!("bug in gcs: a rotation about {axis:?} reached the planar interpreter");
    }
}

fn sense(plus: bool) -> Sense {
    if plus {
        Sense::Plus
    } else {
        Sense::Minus
    }
}
