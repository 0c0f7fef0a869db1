//! The plan's invariants, stated once and checked: what every consumer may rely on.
//!
//! Each operation declares the types of the registers it reads ([`Op::operands`]) and of the
//! value it defines ([`Op::output`]); [`Plan::validate`] checks that every register is defined
//! once, before it is read, with a type its reader accepts and that exists in the plan's
//! space; that every branch variable is used by exactly one intersection, with as many roots
//! as its meet has; that defaults are used and iterated regions are well formed; and that no
//! constraint is satisfied twice. [`Plan::unsatisfied`] lists the constraints no step
//! satisfies or checks, which the pipeline compares with what the analysis reports unsolved.

use super::{BranchId, Op, Plan, PlanarOp, Reg, Residual, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::{ConstraintId, Space};
use gcs_lang::Model;
use std::collections::HashMap;
use std::fmt;

/// The types a reader accepts.
type Accepts = &'static [Ty];

const SCALAR: Accepts = &[Ty::Scalar];
const POINT: Accepts = &[Ty::Point];
const VECTOR: Accepts = &[Ty::Vector];
const LINE: Accepts = &[Ty::Line];
const CIRCLE: Accepts = &[Ty::Circle];
/// A linear system's answers.
const VALUES: Accepts = &[Ty::Values];
/// What the nearest point of a locus is taken on.
const NEAREST_LOCUS: Accepts = &[
    Ty::Line,
    Ty::Circle,
    Ty::Plane,
    Ty::Sphere,
    Ty::Cylinder,
    Ty::Torus,
];
const PLANE: Accepts = &[Ty::Plane];
const SPHERE: Accepts = &[Ty::Sphere];
/// A point's locus a turn takes it onto (`SpatialOp::TurnReaching`).
const LINE_OR_PLANE: Accepts = &[Ty::Line, Ty::Plane];
/// What has a parameter along it (a place, or an implicit error): the loci a default slides on.
const PARAM_LOCUS: Accepts = &[Ty::Line, Ty::Circle, Ty::Conic];
/// What a point held by two coordinates lies on.
const SURFACE: Accepts = &[Ty::Plane, Ty::Sphere, Ty::Cylinder, Ty::Torus];
/// What an implicit function measures a point's offset from: the loci a default slides on,
/// and in space the sphere, plane and cylinder an `onto` can displace a point from.
const IMPLICIT_LOCUS: Accepts = &[
    Ty::Line,
    Ty::Circle,
    Ty::Conic,
    Ty::Plane,
    Ty::Sphere,
    Ty::Cylinder,
    Ty::Torus,
];
/// What a point can be tested to lie on.
const ANY_LOCUS: Accepts = &[
    Ty::Line,
    Ty::Circle,
    Ty::Conic,
    Ty::Plane,
    Ty::Sphere,
    Ty::Cylinder,
    Ty::Torus,
];

/// Why a plan is malformed: every broken invariant, one sentence each. A consumer never gets
/// such a plan from the pipeline; if one does, it is a bug in gcs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Malformed(pub Vec<String>);

impl fmt::Display for Malformed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "the assembly plan is malformed: {}", self.0.join("; "))
    }
}

impl std::error::Error for Malformed {}

impl Residual {
    /// The registers a check reads, with the types it accepts for each.
    pub fn operands(&self) -> Vec<(Reg, Accepts)> {
        let mut out = Vec::new();
        let opt = |r: &Option<Reg>, out: &mut Vec<(Reg, Accepts)>| {
            if let Some(r) = r {
                out.push((*r, SCALAR));
            }
        };
        match self {
            Residual::PointPoint { a, b, d } => {
                out.extend([(*a, POINT), (*b, POINT)]);
                opt(d, &mut out);
            }
            Residual::PointLine { p, base, dir, d } => {
                out.extend([(*p, POINT), (*base, POINT), (*dir, VECTOR)]);
                opt(d, &mut out);
            }
            Residual::Angle { u, v, angle } => {
                out.extend([(*u, VECTOR), (*v, VECTOR), (*angle, SCALAR)]);
            }
            Residual::CircleLine {
                centre,
                radius,
                base,
                dir,
                gap,
                ..
            } => {
                out.extend([
                    (*centre, POINT),
                    (*radius, SCALAR),
                    (*base, POINT),
                    (*dir, VECTOR),
                ]);
                opt(gap, &mut out);
            }
            Residual::PointCircle {
                p,
                centre,
                radius,
                gap,
                ..
            } => {
                out.extend([(*p, POINT), (*centre, POINT), (*radius, SCALAR)]);
                opt(gap, &mut out);
            }
            Residual::CircleCircle {
                c1,
                r1,
                c2,
                r2,
                gap,
                ..
            } => {
                out.extend([(*c1, POINT), (*r1, SCALAR), (*c2, POINT), (*r2, SCALAR)]);
                opt(gap, &mut out);
            }
            Residual::Dim { value, target } => out.extend([(*value, SCALAR), (*target, SCALAR)]),
            Residual::Midpoint { p, a, b } => out.extend([(*p, POINT), (*a, POINT), (*b, POINT)]),
            Residual::PointPlane { p, base, normal, d } => {
                out.extend([(*p, POINT), (*base, POINT), (*normal, VECTOR)]);
                opt(d, &mut out);
            }
            Residual::Parallel { u, v, .. } => out.extend([(*u, VECTOR), (*v, VECTOR)]),
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d,
            } => {
                out.extend([
                    (*p, POINT),
                    (*centre, POINT),
                    (*normal, VECTOR),
                    (*radius, SCALAR),
                ]);
                opt(d, &mut out);
            }
            Residual::AngleBetween { u, v, angle } => {
                out.extend([(*u, VECTOR), (*v, VECTOR), (*angle, SCALAR)])
            }
            Residual::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } => out.extend([
                (*axis, VECTOR),
                (*u, VECTOR),
                (*v, VECTOR),
                (*p, POINT),
                (*q, POINT),
                (*pitch, SCALAR),
            ]),
            Residual::Cone { axis, u, v } => {
                out.extend([(*axis, VECTOR), (*u, VECTOR), (*v, VECTOR)])
            }
            Residual::Twist { axis, u, v, angle } => out.extend([
                (*axis, VECTOR),
                (*u, VECTOR),
                (*v, VECTOR),
                (*angle, SCALAR),
            ]),
            Residual::Mirror { p, q, base, dir } => {
                out.extend([(*p, POINT), (*q, POINT), (*base, POINT), (*dir, VECTOR)])
            }
            Residual::MirrorPlane { p, q, base, normal } => {
                out.extend([(*p, POINT), (*q, POINT), (*base, POINT), (*normal, VECTOR)])
            }
        }
        out
    }
}

impl Op {
    /// The registers the operation reads, with the types it accepts for each.
    pub fn operands(&self) -> Vec<(Reg, Accepts)> {
        match self {
            Op::Expr(_)
            | Op::Size { .. }
            | Op::Const(_)
            | Op::Default(_)
            | Op::PointOf(_)
            | Op::DirOf(_)
            | Op::DimOf(_) => vec![],
            Op::Neg(x) => vec![(*x, SCALAR)],
            Op::Sum(terms) => terms.iter().map(|t| (t.1, SCALAR)).collect(),
            Op::Unknown { of, .. } => vec![(*of, VALUES)],
            Op::Along { from, dir, to } => vec![(*from, POINT), (*dir, VECTOR), (*to, POINT)],
            Op::DirectionTo { from, to } => vec![(*from, POINT), (*to, POINT)],
            Op::Midpoint { a, b } => vec![(*a, POINT), (*b, POINT)],
            Op::Reflect { point, through } => vec![(*point, POINT), (*through, POINT)],
            Op::LocusPoint { locus, at } => vec![(*locus, PARAM_LOCUS), (*at, SCALAR)],
            Op::LocusParam { locus, point } => vec![(*locus, PARAM_LOCUS), (*point, POINT)],
            Op::Implicit { locus, point } => vec![(*locus, IMPLICIT_LOCUS), (*point, POINT)],
            Op::Line { point, dir, offset } => {
                let mut v = vec![(*point, POINT), (*dir, VECTOR)];
                v.extend(offset.map(|o| (o, SCALAR)));
                v
            }
            Op::ParallelLine { line, through } => vec![(*line, LINE), (*through, POINT)],
            Op::ShiftedCircle { circle, from, to } => {
                vec![(*circle, CIRCLE), (*from, POINT), (*to, POINT)]
            }
            Op::Nearest { locus, point } => vec![(*locus, NEAREST_LOCUS), (*point, POINT)],
            Op::Onto { locus, point, .. } => vec![(*locus, ANY_LOCUS), (*point, POINT)],
            Op::Intersect {
                meet, a, b, near, ..
            } => {
                let (ta, tb) = meet.operands();
                vec![(*a, accepts(ta)), (*b, accepts(tb)), (*near, POINT)]
            }
            Op::Translate { from, to, .. } => vec![(*from, POINT), (*to, POINT)],
            Op::RotatePoint {
                pivot,
                axis,
                from,
                to,
                ..
            } => rotation(*pivot, *axis, (*from, POINT), (*to, POINT)),
            Op::RotateDir {
                pivot,
                axis,
                from,
                to,
                ..
            } => rotation(*pivot, *axis, (*from, VECTOR), (*to, VECTOR)),
            Op::SetDim { value, .. } => vec![(*value, SCALAR)],
            Op::Check { residual, .. } | Op::Error { residual, .. } => residual.operands(),
            Op::Close { residual, .. } => vec![(*residual, SCALAR)],
            Op::Planar(op) => op.operands(),
            Op::Spatial(op) => op.operands(),
        }
    }

    /// The registers the operation reads.
    pub fn reads(&self) -> Vec<Reg> {
        self.operands().into_iter().map(|(r, _)| r).collect()
    }

    /// The branch variable whose root the operation takes, if it takes one: every op that
    /// chooses among roots, said once (validation counts each branch's uses, pruning
    /// renumbers them).
    pub fn branch_mut(&mut self) -> Option<&mut BranchId> {
        match self {
            Op::Intersect { branch, .. }
            | Op::Planar(PlanarOp::PassingDir { branch, .. })
            | Op::Spatial(
                SpatialOp::AngleTurn { branch, .. }
                | SpatialOp::PlaneAxisTurn { branch, .. }
                | SpatialOp::ThreeCircles { branch, .. }
                | SpatialOp::PlanarChainEnds { branch, .. },
            ) => Some(branch),
            _ => None,
        }
    }

    /// The branch variable whose root the operation takes, if it takes one
    /// ([`Op::branch_mut`]).
    pub fn branch(&self) -> Option<BranchId> {
        match self {
            Op::Intersect { branch, .. }
            | Op::Planar(PlanarOp::PassingDir { branch, .. })
            | Op::Spatial(
                SpatialOp::AngleTurn { branch, .. }
                | SpatialOp::PlaneAxisTurn { branch, .. }
                | SpatialOp::ThreeCircles { branch, .. }
                | SpatialOp::PlanarChainEnds { branch, .. },
            ) => Some(*branch),
            _ => None,
        }
    }

    /// The type of the value it defines, if it defines one.
    pub fn output(&self) -> Option<Ty> {
        Some(match self {
            Op::Expr(_)
            | Op::Size { .. }
            | Op::Const(_)
            | Op::Default(_)
            | Op::Neg(_)
            | Op::DimOf(_)
            | Op::Sum(_)
            | Op::Unknown { .. }
            | Op::Along { .. }
            | Op::LocusParam { .. }
            | Op::Error { .. }
            | Op::Implicit { .. } => Ty::Scalar,
            Op::DirectionTo { .. } | Op::DirOf(_) => Ty::Vector,
            Op::Line { .. } | Op::ParallelLine { .. } => Ty::Line,
            Op::PointOf(_)
            | Op::Nearest { .. }
            | Op::Onto { .. }
            | Op::Midpoint { .. }
            | Op::Reflect { .. }
            | Op::LocusPoint { .. } => Ty::Point,
            Op::ShiftedCircle { .. } => Ty::Circle,
            Op::Intersect { meet, .. } => meet.result(),
            Op::Translate { .. }
            | Op::RotatePoint { .. }
            | Op::RotateDir { .. }
            | Op::SetDim { .. }
            | Op::Check { .. }
            | Op::Close { .. } => return None,
            Op::Planar(op) => op.output(),
            Op::Spatial(op) => return op.output(),
        })
    }
}

impl PlanarOp {
    /// The registers the operation reads, with the types it accepts for each.
    pub fn operands(&self) -> Vec<(Reg, Accepts)> {
        match self {
            PlanarOp::Axis(..) => vec![],
            PlanarOp::Reversed(x) | PlanarOp::LineDir(x) => vec![(*x, LINE)],
            PlanarOp::Linear(system) => (system.rows.iter())
                .flat_map(|row| {
                    std::iter::once((row.error, SCALAR)).chain(
                        (row.terms.iter())
                            .flat_map(|t| t.coef.regs())
                            .map(|r| (r, VECTOR)),
                    )
                })
                .collect(),
            PlanarOp::OffsetLine { line, by } => vec![(*line, LINE), (*by, SCALAR)],
            PlanarOp::CentresLineLine { l1, a1, l2, a2 } => {
                vec![(*l1, LINE), (*a1, SCALAR), (*l2, LINE), (*a2, SCALAR)]
            }
            PlanarOp::CentresLinePoint { line, a, at, b, .. } => {
                vec![(*line, LINE), (*a, SCALAR), (*at, POINT), (*b, SCALAR)]
            }
            PlanarOp::CentresPointPoint { c1, b1, c2, b2, .. } => {
                vec![(*c1, POINT), (*b1, SCALAR), (*c2, POINT), (*b2, SCALAR)]
            }
            PlanarOp::RadiusFromLine { line, a, centre } => {
                vec![(*line, LINE), (*a, SCALAR), (*centre, POINT)]
            }
            PlanarOp::RadiusFromPoint { at, b, centre, .. } => {
                vec![(*at, POINT), (*b, SCALAR), (*centre, POINT)]
            }
            PlanarOp::Rotated { dir, angle } => vec![(*dir, VECTOR), (*angle, SCALAR)],
            PlanarOp::AngleOf(dir) => vec![(*dir, VECTOR)],
            PlanarOp::PointXY { x, y } => vec![(*x, SCALAR), (*y, SCALAR)],
            PlanarOp::Mirror { point, line } => vec![(*point, POINT), (*line, LINE)],
            PlanarOp::Circle { center, radius } => vec![(*center, POINT), (*radius, SCALAR)],
            PlanarOp::CircleThrough {
                center, through, ..
            } => vec![(*center, POINT), (*through, POINT)],
            PlanarOp::PassingDir {
                pivot,
                base,
                dir,
                point,
                offset,
                ..
            } => {
                let mut v = vec![
                    (*pivot, POINT),
                    (*base, POINT),
                    (*dir, VECTOR),
                    (*point, POINT),
                ];
                v.extend(offset.map(|o| (o, SCALAR)));
                v
            }
        }
    }

    /// The type of the value it defines: every one defines one.
    pub fn output(&self) -> Ty {
        match self {
            PlanarOp::AngleOf(_)
            | PlanarOp::RadiusFromLine { .. }
            | PlanarOp::RadiusFromPoint { .. } => Ty::Scalar,
            PlanarOp::Axis(..)
            | PlanarOp::Rotated { .. }
            | PlanarOp::PassingDir { .. }
            | PlanarOp::LineDir(_) => Ty::Vector,
            PlanarOp::Linear(_) => Ty::Values,
            PlanarOp::Reversed(_)
            | PlanarOp::OffsetLine { .. }
            | PlanarOp::CentresLineLine { .. } => Ty::Line,
            PlanarOp::CentresLinePoint { .. } | PlanarOp::CentresPointPoint { .. } => Ty::Conic,
            PlanarOp::PointXY { .. } | PlanarOp::Mirror { .. } => Ty::Point,
            PlanarOp::Circle { .. } | PlanarOp::CircleThrough { .. } => Ty::Circle,
        }
    }
}

impl SpatialOp {
    /// The registers the operation reads, with the types it accepts for each.
    pub fn operands(&self) -> Vec<(Reg, Accepts)> {
        match self {
            SpatialOp::MirrorPlane {
                point,
                base,
                normal,
            } => vec![(*point, POINT), (*base, POINT), (*normal, VECTOR)],
            SpatialOp::SurfaceParam { locus, point, .. } => {
                vec![(*locus, SURFACE), (*point, POINT)]
            }
            SpatialOp::SurfacePoint { locus, u, v } => {
                vec![(*locus, SURFACE), (*u, SCALAR), (*v, SCALAR)]
            }
            SpatialOp::Plane {
                point,
                normal,
                offset,
            } => {
                let mut v = vec![(*point, POINT), (*normal, VECTOR)];
                v.extend(offset.map(|o| (o, SCALAR)));
                v
            }
            SpatialOp::ParallelPlane { plane, through } => vec![(*plane, PLANE), (*through, POINT)],
            SpatialOp::Sphere { center, radius } => vec![(*center, POINT), (*radius, SCALAR)],
            SpatialOp::Cylinder { point, dir, radius } => {
                vec![(*point, POINT), (*dir, VECTOR), (*radius, SCALAR)]
            }
            SpatialOp::ShiftedCylinder { cylinder, from, to } => {
                vec![(*cylinder, &[Ty::Cylinder]), (*from, POINT), (*to, POINT)]
            }
            SpatialOp::Torus { circle, tube } => vec![(*circle, CIRCLE), (*tube, SCALAR)],
            SpatialOp::ShiftedTorus { torus, from, to } => {
                vec![(*torus, &[Ty::Torus]), (*from, POINT), (*to, POINT)]
            }
            SpatialOp::Circle3 {
                center,
                normal,
                radius,
            } => vec![(*center, POINT), (*normal, VECTOR), (*radius, SCALAR)],
            SpatialOp::SphereThrough {
                center, through, ..
            } => vec![(*center, POINT), (*through, POINT)],
            SpatialOp::ShiftedSphere { sphere, from, to } => {
                vec![(*sphere, SPHERE), (*from, POINT), (*to, POINT)]
            }
            SpatialOp::Orbit {
                pivot,
                axis,
                through,
            } => vec![(*pivot, POINT), (*axis, VECTOR), (*through, POINT)],
            SpatialOp::Opposite(d) | SpatialOp::Across(d) => vec![(*d, VECTOR)],
            SpatialOp::AngleAbout { u, v, axis } => {
                vec![(*u, VECTOR), (*v, VECTOR), (*axis, VECTOR)]
            }
            SpatialOp::AngleAboutBoth { u, v, axis } => vec![
                (u[0], VECTOR),
                (v[0], VECTOR),
                (u[1], VECTOR),
                (v[1], VECTOR),
                (*axis, VECTOR),
            ],
            SpatialOp::TurnReaching {
                u,
                v,
                axis,
                pivot,
                reach,
                screw,
            } => {
                let helix = |h: &crate::plan::HelixRegs| {
                    [
                        (h.axis, VECTOR),
                        (h.x_from, VECTOR),
                        (h.origin, POINT),
                        (h.x, VECTOR),
                        (h.point, POINT),
                        (h.pitch, SCALAR),
                    ]
                };
                let mut operands =
                    vec![(*u, VECTOR), (*v, VECTOR), (*axis, VECTOR), (*pivot, POINT)];
                match reach {
                    crate::plan::Reach::Point { point, locus } => {
                        operands.extend([(*point, POINT), (*locus, LINE_OR_PLANE)])
                    }
                    crate::plan::Reach::Helix(h) => operands.extend(helix(h)),
                }
                if let Some(s) = screw {
                    operands.extend(helix(&s.helix));
                    operands.push((s.slide, LINE));
                }
                operands
            }
            SpatialOp::HelixAdvance { now, turn, pitch } => {
                vec![(*now, SCALAR), (*turn, SCALAR), (*pitch, SCALAR)]
            }
            SpatialOp::HelixTurn { advance, pitch } => vec![(*advance, SCALAR), (*pitch, SCALAR)],
            SpatialOp::WorldAxis(_) => vec![],
            SpatialOp::PlaneNormal { a, b, c } => vec![(*a, POINT), (*b, POINT), (*c, POINT)],
            SpatialOp::PlaneTurn {
                base,
                normal,
                pivot,
                point,
                d,
                ..
            } => vec![
                (*base, POINT),
                (*normal, VECTOR),
                (*pivot, POINT),
                (*point, POINT),
                (*d, SCALAR),
            ],
            SpatialOp::PlaneAxisTurn {
                base,
                normal,
                pivot,
                point,
                d,
                axis,
                ..
            } => vec![
                (*base, POINT),
                (*normal, VECTOR),
                (*pivot, POINT),
                (*point, POINT),
                (*d, SCALAR),
                (*axis, VECTOR),
            ],
            SpatialOp::Aligned { dir, near } => vec![(*dir, VECTOR), (*near, VECTOR)],
            SpatialOp::ConeTurn { axis, angle, dir } => {
                vec![(*axis, VECTOR), (*angle, SCALAR), (*dir, VECTOR)]
            }
            SpatialOp::PassingAngle {
                from, to, d, now, ..
            } => vec![(*from, POINT), (*to, POINT), (*d, SCALAR), (*now, VECTOR)],
            SpatialOp::TiltToDistance {
                centre,
                point,
                radius,
                d,
                now,
                ..
            } => vec![
                (*centre, POINT),
                (*point, POINT),
                (*radius, SCALAR),
                (*d, SCALAR),
                (*now, VECTOR),
            ],
            SpatialOp::AngleTurn {
                u, v, axis, angle, ..
            } => vec![
                (*u, VECTOR),
                (*v, VECTOR),
                (*axis, VECTOR),
                (*angle, SCALAR),
            ],
            SpatialOp::Coordinate { point, .. } => vec![(*point, POINT)],
            SpatialOp::PointAt { x, y, z } => vec![(*x, SCALAR), (*y, SCALAR), (*z, SCALAR)],
            SpatialOp::RotateBy {
                pivot, axis, angle, ..
            } => vec![(*pivot, POINT), (*axis, VECTOR), (*angle, SCALAR)],
            SpatialOp::ThreeCircles {
                first,
                a,
                second,
                third,
                b,
                near,
                ..
            } => vec![
                (first[0], POINT),
                (first[1], VECTOR),
                (*a, POINT),
                (second[0], POINT),
                (second[1], VECTOR),
                (third[0], POINT),
                (third[1], VECTOR),
                (*b, POINT),
                (*near, POINT),
            ],
            SpatialOp::PlanarChainEnds {
                first,
                h,
                base,
                joint,
                far,
                last,
                offset,
                ..
            } => vec![
                (first[0], POINT),
                (first[1], VECTOR),
                (*h, VECTOR),
                (*base, POINT),
                (joint[0], POINT),
                (joint[1], VECTOR),
                (*far, VECTOR),
                (last[0], POINT),
                (last[1], VECTOR),
                (*offset, SCALAR),
            ],
            SpatialOp::TurnedAbout { dir, axis, angle } => {
                vec![(*dir, VECTOR), (*axis, VECTOR), (*angle, SCALAR)]
            }
        }
    }

    /// The type of the value it defines, if it defines one.
    pub fn output(&self) -> Option<Ty> {
        Some(match self {
            SpatialOp::SurfaceParam { .. }
            | SpatialOp::AngleAbout { .. }
            | SpatialOp::AngleAboutBoth { .. }
            | SpatialOp::TurnReaching { .. }
            | SpatialOp::HelixAdvance { .. }
            | SpatialOp::HelixTurn { .. }
            | SpatialOp::TiltToDistance { .. }
            | SpatialOp::PassingAngle { .. }
            | SpatialOp::Coordinate { .. } => Ty::Scalar,
            SpatialOp::TurnedAbout { .. }
            | SpatialOp::Opposite(_)
            | SpatialOp::Across(_)
            | SpatialOp::WorldAxis(_)
            | SpatialOp::AngleTurn { .. }
            | SpatialOp::ConeTurn { .. }
            | SpatialOp::Aligned { .. }
            | SpatialOp::PlaneNormal { .. }
            | SpatialOp::PlaneTurn { .. }
            | SpatialOp::PlaneAxisTurn { .. } => Ty::Vector,
            SpatialOp::Plane { .. } | SpatialOp::ParallelPlane { .. } => Ty::Plane,
            SpatialOp::Sphere { .. }
            | SpatialOp::SphereThrough { .. }
            | SpatialOp::ShiftedSphere { .. } => Ty::Sphere,
            SpatialOp::Cylinder { .. } | SpatialOp::ShiftedCylinder { .. } => Ty::Cylinder,
            SpatialOp::Torus { .. } | SpatialOp::ShiftedTorus { .. } => Ty::Torus,
            SpatialOp::Orbit { .. } | SpatialOp::Circle3 { .. } => Ty::Circle,
            SpatialOp::PointAt { .. }
            | SpatialOp::MirrorPlane { .. }
            | SpatialOp::SurfacePoint { .. } => Ty::Point,
            SpatialOp::ThreeCircles { .. } | SpatialOp::PlanarChainEnds { .. } => Ty::Values,
            SpatialOp::RotateBy { .. } => return None,
        })
    }
}

/// The one-type set of `ty`.
fn accepts(ty: Ty) -> Accepts {
    match ty {
        Ty::Scalar => SCALAR,
        Ty::Point => POINT,
        Ty::Vector => VECTOR,
        Ty::Line => LINE,
        Ty::Circle => CIRCLE,
        Ty::Conic => &[Ty::Conic],
        Ty::Plane => &[Ty::Plane],
        Ty::Sphere => &[Ty::Sphere],
        Ty::Cylinder => &[Ty::Cylinder],
        Ty::Torus => &[Ty::Torus],
        Ty::Values => VALUES,
    }
}

/// The operands of a rotation about `pivot` around `axis`.
fn rotation(
    pivot: Reg,
    axis: RotationAxis,
    from: (Reg, Accepts),
    to: (Reg, Accepts),
) -> Vec<(Reg, Accepts)> {
    let mut v = vec![(pivot, POINT), from, to];
    if let RotationAxis::Along(a) = axis {
        v.push((a, VECTOR));
    }
    v
}

impl Plan {
    /// Checks the plan's invariants (see the module's documentation); every broken one is
    /// reported.
    pub fn validate(&self, model: &Model) -> Result<(), Malformed> {
        let mut errors = Vec::new();
        let mut defined: Vec<Option<Ty>> = vec![None; self.regs as usize];
        let mut satisfied: HashMap<ConstraintId, usize> = HashMap::new();
        let mut branch_uses = vec![0usize; self.branches.len()];
        let mut default_uses = vec![0usize; self.defaults.len()];
        for (i, s) in self.steps.iter().enumerate() {
            for (r, accepted) in s.op.operands() {
                match defined.get(r.0 as usize).copied().flatten() {
                    None => errors.push(format!("step {i} reads r{} before it is defined", r.0)),
                    Some(ty) if !accepted.contains(&ty) => errors.push(format!(
                        "step {i} reads r{} as {accepted:?} but it holds a {ty:?}",
                        r.0
                    )),
                    Some(_) => {}
                }
            }
            self.validate_op(i, &s.op, &mut branch_uses, &mut default_uses, &mut errors);
            match (s.out, s.op.output()) {
                (Some((r, ty)), Some(want)) => {
                    if ty != want {
                        errors.push(format!(
                            "step {i} defines r{} as a {ty:?}, not a {want:?}",
                            r.0
                        ));
                    }
                    if !ty.in_space(self.space) {
                        errors.push(format!("step {i} defines a {ty:?} in {}", self.space));
                    }
                    match defined.get_mut(r.0 as usize) {
                        Some(slot @ None) => *slot = Some(ty),
                        Some(Some(_)) => errors.push(format!("step {i} redefines r{}", r.0)),
                        None => {
                            errors.push(format!("step {i} defines r{} past the registers", r.0))
                        }
                    }
                }
                (None, None) => {}
                (Some((r, _)), None) => {
                    errors.push(format!("step {i} defines r{} but computes no value", r.0))
                }
                (None, Some(_)) => {
                    errors.push(format!("step {i} computes a value it keeps nowhere"))
                }
            }
            for c in &s.satisfies {
                *satisfied.entry(*c).or_default() += 1;
            }
        }
        for (id, c) in model.constraints.iter() {
            if let Some(n @ 2..) = satisfied.get(&id).copied() {
                errors.push(format!("constraint {} is satisfied by {n} steps", c.name));
            }
        }
        for (b, n) in self.branches.iter().zip(&branch_uses) {
            if *n != 1 {
                errors.push(format!("branch {} is used {n} times", b.name));
            }
        }
        for (d, n) in self.defaults.iter().zip(&default_uses) {
            if *n == 0 {
                errors.push(format!("default {} is never used", d.name));
            }
        }
        self.validate_iterations(&mut errors);
        if errors.is_empty() {
            Ok(())
        } else {
            Err(Malformed(errors))
        }
    }

    /// The invariants of one operation beyond its registers' types.
    fn validate_op(
        &self,
        i: usize,
        op: &Op,
        branch_uses: &mut [usize],
        default_uses: &mut [usize],
        errors: &mut Vec<String>,
    ) {
        // A plan holds its own space's operations and meets only: each back end matches no
        // other's.
        match op {
            Op::Planar(_) if self.space != Space::D2 => errors.push(format!(
                "step {i} is an operation of the plane in {}",
                self.space
            )),
            Op::Spatial(_) if self.space != Space::D3 => errors.push(format!(
                "step {i} is an operation of space in {}",
                self.space
            )),
            Op::Intersect { meet, .. } if !meet.in_space(self.space) => {
                errors.push(format!("step {i} intersects {meet:?} in {}", self.space));
            }
            _ => {}
        }
        if let Some(branch) = op.branch() {
            match branch_uses.get_mut(branch.0 as usize) {
                Some(n) => *n += 1,
                None => errors.push(format!("step {i} uses an undeclared branch")),
            }
        }
        match op {
            Op::Default(d) => match default_uses.get_mut(d.0 as usize) {
                Some(n) => *n += 1,
                None => errors.push(format!("step {i} reads an undeclared default")),
            },
            Op::RotatePoint { axis, .. } | Op::RotateDir { axis, .. } => {
                let planar = *axis == RotationAxis::Normal;
                if planar != (self.space == Space::D2) {
                    errors.push(format!("step {i} rotates about {axis:?} in {}", self.space));
                }
            }
            Op::Close { .. }
                if !self
                    .iterations
                    .iter()
                    .any(|it| (it.start..it.end).contains(&i)) =>
            {
                errors.push(format!(
                    "step {i} closes an iteration outside every iterated region"
                ));
            }
            _ => {}
        }
    }

    /// Iterated regions: in step order, disjoint, inside the plan, each varying declared
    /// defaults and closing at least one constraint.
    fn validate_iterations(&self, errors: &mut Vec<String>) {
        let mut after = 0;
        for (k, it) in self.iterations.iter().enumerate() {
            if it.start < after || it.start >= it.end || it.end > self.steps.len() {
                errors.push(format!(
                    "iteration {k} covers steps {}..{}, out of order or outside the plan",
                    it.start, it.end
                ));
            }
            after = it.end;
            if it.defaults.is_empty()
                || it
                    .defaults
                    .iter()
                    .any(|d| d.0 as usize >= self.defaults.len())
            {
                errors.push(format!("iteration {k} varies no declared default"));
            }
            if self.closes(it).is_empty() {
                errors.push(format!("iteration {k} closes nothing"));
            }
        }
    }

    /// The constraints of the model that no step satisfies or checks: those the analysis
    /// left unsolved, and none other, in a plan from the pipeline.
    pub fn unsatisfied(&self, model: &Model) -> Vec<ConstraintId> {
        let mut satisfied = vec![false; model.constraints.len()];
        for s in &self.steps {
            for c in &s.satisfies {
                if let Some(slot) = satisfied.get_mut(c.into_raw().into_u32() as usize) {
                    *slot = true;
                }
            }
        }
        model
            .constraints
            .iter()
            .filter(|(id, _)| !satisfied[id.into_raw().into_u32() as usize])
            .map(|(id, _)| id)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{BranchId, BranchVar, DefaultId, DefaultVar, Iteration, Meet, Step};

    fn model() -> Model {
        let text = "space 2d;\nfixed point A = (0, 0);\npoint B = (1, 0);\ncoincident(B, A);\n";
        let (_, model, diags) = gcs_lang::load("t.gcs", text.as_bytes());
        model.unwrap_or_else(|| panic!("{diags:?}"))
    }

    fn step(op: Op, out: Option<(u32, Ty)>) -> Step {
        Step {
            op,
            out: out.map(|(r, t)| (Reg(r), t)),
            satisfies: vec![],
            works_for: None,
            explain: String::new(),
        }
    }

    fn plan(steps: Vec<Step>) -> Plan {
        let mut p = Plan::new(Space::D2);
        p.regs = steps.iter().filter(|s| s.out.is_some()).count() as u32;
        p.steps = steps;
        p
    }

    fn errors(p: &Plan) -> Vec<String> {
        match p.validate(&model()) {
            Ok(()) => vec![],
            Err(Malformed(e)) => e,
        }
    }

    #[test]
    fn a_register_read_as_the_wrong_type_is_malformed() {
        let m = model();
        let a = m.geom_named("A").expect("A");
        let p = plan(vec![
            step(Op::PointOf(a), Some((0, Ty::Point))),
            step(Op::Neg(Reg(0)), Some((1, Ty::Scalar))),
        ]);
        assert_eq!(
            errors(&p),
            ["step 1 reads r0 as [Scalar] but it holds a Point"]
        );
    }

    #[test]
    fn reads_before_definitions_and_wrong_outputs_are_malformed() {
        let p = plan(vec![
            step(Op::Neg(Reg(1)), Some((0, Ty::Scalar))),
            step(Op::Const(1.0), Some((1, Ty::Point))),
        ]);
        assert_eq!(
            errors(&p),
            [
                "step 0 reads r1 before it is defined",
                "step 1 defines r1 as a Point, not a Scalar"
            ]
        );
    }

    #[test]
    fn spatial_operations_are_malformed_in_the_plane() {
        let m = model();
        let (a, b) = (m.geom_named("A").expect("A"), m.geom_named("B").expect("B"));
        let c = m.constraints.iter().next().expect("constraint").0;
        let mut p = plan(vec![
            step(Op::PointOf(a), Some((0, Ty::Point))),
            step(Op::PointOf(b), Some((1, Ty::Point))),
            step(
                Op::RotatePoint {
                    geoms: vec![b],
                    pivot: Reg(0),
                    axis: RotationAxis::Shortest,
                    from: Reg(1),
                    to: Reg(0),
                },
                None,
            ),
            step(
                Op::Intersect {
                    meet: Meet::LineSphere,
                    a: Reg(0),
                    b: Reg(1),
                    branch: BranchId(0),
                    constraint: c,
                    near: Reg(1),
                },
                Some((2, Ty::Point)),
            ),
        ]);
        p.branches.push(BranchVar {
            name: "x".into(),
            constraint: c,
            count: 2,
            meanings: vec![],
            default: 0,
            from_sketch: false,
            symmetric: false,
        });
        assert_eq!(
            errors(&p),
            [
                "step 2 rotates about Shortest in 2d",
                "step 3 reads r0 as [Line] but it holds a Point",
                "step 3 reads r1 as [Sphere] but it holds a Point",
                "step 3 intersects LineSphere in 2d"
            ]
        );
    }

    #[test]
    fn defaults_and_iterations_are_checked() {
        let m = model();
        let c = m.constraints.iter().next().expect("constraint").0;
        let mut p = plan(vec![
            step(Op::Default(DefaultId(0)), Some((0, Ty::Scalar))),
            step(
                Op::Close {
                    constraint: c,
                    residual: Reg(0),
                },
                None,
            ),
        ]);
        p.defaults = vec![
            DefaultVar {
                name: "a".into(),
                meaning: "the angle of a".into(),
                sketch: 0.5,
                measure: None,
                geom: None,
                assembled: None,
            },
            DefaultVar {
                name: "b".into(),
                meaning: "never read".into(),
                sketch: 0.0,
                measure: None,
                geom: None,
                assembled: None,
            },
        ];
        assert_eq!(
            errors(&p),
            [
                "step 1 closes an iteration outside every iterated region",
                "default b is never used"
            ]
        );
        p.defaults.pop();
        p.iterations.push(Iteration {
            defaults: vec![DefaultId(0)],
            start: 0,
            end: 2,
            mode: None,
        });
        assert_eq!(errors(&p), Vec::<String>::new());
        assert_eq!(p.sketch_defaults(), [0.5]);
    }
}
