//! The operations of space only: planes, spheres, cylinders and tori, turns about an axis and
//! the closed-form fragments of TLA's action analysis.

use super::{BranchId, Reg};
use gcs_lang::model::{ConstraintId, GeomId};

/// The registers of a helical coupling of a marker that turns with a cluster to a known one
/// (`runtime::fragment3::Helix`): the known marker's z axis, x axis and point, the riding
/// marker's x axis and point, and the pitch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HelixRegs {
    pub axis: Reg,
    pub x_from: Reg,
    pub origin: Reg,
    pub x: Reg,
    pub point: Reg,
    pub pitch: Reg,
}

/// A helical coupling a cluster rides on after a turn (`runtime::fragment3::Screw`), and the
/// line it slides along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScrewRegs {
    pub helix: HelixRegs,
    pub slide: Reg,
}

/// What a turn of [`SpatialOp::TurnReaching`] must reach besides its direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// `point` onto `locus`, a line or a plane.
    Point { point: Reg, locus: Reg },
    /// A helical joint's coupling.
    Helix(HelixRegs),
}

/// An operation only a spatial plan holds.
#[derive(Clone, Debug, PartialEq)]
pub enum SpatialOp {
    /// Direction `dir` turned by `angle` counter-clockwise about the unit `axis`.
    TurnedAbout { dir: Reg, axis: Reg, angle: Reg },
    /// The mirror image of `point` across the plane through `base` with unit
    /// normal `normal`.
    MirrorPlane { point: Reg, base: Reg, normal: Reg },
    /// Coordinate `component` (0 or 1) of `point` on surface `locus` (a plane, a
    /// sphere or a cylinder: `runtime::locus3d::Surface`).
    SurfaceParam {
        locus: Reg,
        point: Reg,
        component: u8,
    },
    /// The point of surface `locus` at coordinates `u`, `v`.
    SurfacePoint { locus: Reg, u: Reg, v: Reg },
    /// The plane through `point` with unit normal `normal`, moved `offset` along it.
    Plane {
        point: Reg,
        normal: Reg,
        offset: Option<Reg>,
    },
    /// The plane parallel to plane `plane` through `through`.
    ParallelPlane { plane: Reg, through: Reg },
    /// The circle about `center` with unit `normal` and `radius`.
    Circle3 {
        center: Reg,
        normal: Reg,
        radius: Reg,
    },
    /// The sphere about `center` with `radius`.
    Sphere { center: Reg, radius: Reg },
    /// The points at distance `radius` from the line through `point` along unit
    /// `dir`.
    Cylinder { point: Reg, dir: Reg, radius: Reg },
    /// `cylinder` translated by `to - from`.
    ShiftedCylinder { cylinder: Reg, from: Reg, to: Reg },
    /// The points at distance `tube` from circle `circle`.
    Torus { circle: Reg, tube: Reg },
    /// `torus` translated by `to - from`.
    ShiftedTorus { torus: Reg, from: Reg, to: Reg },
    /// The sphere about `center` through `through`; `radius` as in
    /// [`PlanarOp::CircleThrough`](super::PlanarOp::CircleThrough).
    SphereThrough {
        center: Reg,
        through: Reg,
        radius: Option<f64>,
    },
    /// Sphere `sphere` moved by the vector from `from` to `to`.
    ShiftedSphere { sphere: Reg, from: Reg, to: Reg },
    /// The circle `through` sweeps turning about the axis through `pivot` along the
    /// unit `axis`.
    Orbit { pivot: Reg, axis: Reg, through: Reg },
    /// The opposite of direction `dir`.
    Opposite(Reg),
    /// A unit direction perpendicular to the unit `axis` (`runtime::frame::
    /// perpendicular`, deterministic): where a turn about the axis is measured from.
    Across(Reg),
    /// The angle from direction `u` to `v`, counter-clockwise about the unit `axis`,
    /// in (-pi, pi].
    AngleAbout { u: Reg, v: Reg, axis: Reg },
    /// The angle about the unit `axis` that turns `u[0]` onto `v[0]` and `u[1]` onto
    /// `v[1]` together (`runtime::frame::signed_angle3_both`): a marker's z and x axes, of
    /// which the one further across the axis decides.
    AngleAboutBoth { u: [Reg; 2], v: [Reg; 2], axis: Reg },
    /// The angle about the unit `axis` through `pivot` that turns direction `u` onto
    /// `v` and meets `reach` (`runtime::fragment3::turn_reaching_line`, `_plane`, `_helix`): a
    /// joint's point onto a line or plane, which the cluster's remaining slide along it then
    /// brings home, or a helical joint's coupling, decides a turn that a z axis nearly along
    /// the axis fixes only to rounding over its distance from it. With `screw`, the cluster
    /// rides a helical coupling after the turn, and the point or marker goes where the
    /// screw's slide takes it.
    TurnReaching {
        u: Reg,
        v: Reg,
        axis: Reg,
        pivot: Reg,
        reach: Reach,
        screw: Option<ScrewRegs>,
    },
    /// A helix's advance for a turn: the advance `now + pitch / 2pi * wrap(turn - 2pi now /
    /// pitch)`, the one of the turn's advances (a pitch apart) nearest `now`.
    HelixAdvance { now: Reg, turn: Reg, pitch: Reg },
    /// A helix's turn for an advance: `2pi advance / pitch`.
    HelixTurn { advance: Reg, pitch: Reg },
    /// The normal a plane (through `base`, unit `normal`) turned about `pivot` must
    /// take to be at signed distance `d` from `point`, keeping its distance from `pivot`: of
    /// the normals on that cone about `point - pivot`, the one nearest `normal` (least
    /// motion); an error naming `constraint` when no turn reaches it.
    PlaneTurn {
        base: Reg,
        normal: Reg,
        pivot: Reg,
        point: Reg,
        d: Reg,
        constraint: ConstraintId,
    },
    /// As [`SpatialOp::PlaneTurn`], the plane turning about the unit `axis` through `pivot` only:
    /// where that turn meets the cone (`runtime::frame::turns_to_angle`), the root of
    /// `branch`.
    PlaneAxisTurn {
        base: Reg,
        normal: Reg,
        pivot: Reg,
        point: Reg,
        d: Reg,
        axis: Reg,
        branch: BranchId,
        constraint: ConstraintId,
    },
    /// The unit normal of the plane through points `a`, `b` and `c`, along
    /// `(b - a) x (c - a)`.
    PlaneNormal { a: Reg, b: Reg, c: Reg },
    /// The world's x, y or z axis (0, 1, 2).
    WorldAxis(u8),
    /// Where direction `v` turns about the unit `axis` to make the unsigned angle
    /// `angle` with `u` (`runtime::frame::turns_to_angle`): the root of `branch` (0: counter-
    /// clockwise about the axis from its turn nearest `u`, 1: clockwise), or an error naming
    /// `constraint`. The sketch's branch is the root nearest `v`.
    AngleTurn {
        u: Reg,
        v: Reg,
        axis: Reg,
        angle: Reg,
        branch: BranchId,
        constraint: ConstraintId,
    },
    /// The direction of least turn from `dir` that makes the unsigned angle `angle`
    /// with the unit `axis` (`runtime::frame::plane_turn` with its cosine): on the great circle
    /// through `axis` and `dir`, the point of the cone about `axis` nearest `dir`.
    ConeTurn { axis: Reg, angle: Reg, dir: Reg },
    /// The angle between the normal of the circle about `centre` of `radius` and the
    /// direction to `point` at which `point` is `d` from the circle, on the side `now` has it
    /// (`runtime::fragment3::tilt_to_distance`), or an error naming `constraint` with the gap.
    TiltToDistance {
        centre: Reg,
        point: Reg,
        radius: Reg,
        d: Reg,
        now: Reg,
        constraint: ConstraintId,
    },
    /// The unsigned angle from the direction `from` to `to` at which a line through
    /// `from` passes `d` from `to`, keeping the sense of `now`
    /// (`runtime::fragment3::passing_angle`), or an error naming `constraint` with the gap.
    PassingAngle {
        from: Reg,
        to: Reg,
        d: Reg,
        now: Reg,
        constraint: ConstraintId,
    },
    /// `dir` or its opposite, whichever is nearer `near` (a directed line turned
    /// onto a line through two points keeps its sense).
    Aligned { dir: Reg, near: Reg },
    /// Coordinate 0, 1 or 2 of `point`.
    Coordinate { point: Reg, axis: u8 },
    /// The point with coordinates `x`, `y` and `z`.
    PointAt { x: Reg, y: Reg, z: Reg },
    /// The three-circle problem (IK-Geo's SP5, `runtime::turn3d::three_circles`): the angles
    /// `[θ1, θ2, θ3]` (`Ty::Values`) with `turn(first, θ1, a) = turn(second, θ2,
    /// turn(third, θ3, b))`, each axis a pivot and a unit direction, `third` in its pose at
    /// `θ2 = 0`: the root of `branch` (up to four, by `θ1` ascending), or an error naming
    /// `constraint`. A chain of a body turning about a known axis, a free body and a body
    /// pivoted at a known point, joined by two revolutes. The sketch's branch is the root that
    /// leaves `second`'s pivot and `third`'s (at `near` in the sketch) nearest where they were.
    ThreeCircles {
        first: [Reg; 2],
        a: Reg,
        second: [Reg; 2],
        third: [Reg; 2],
        b: Reg,
        near: Reg,
        branch: BranchId,
        constraint: ConstraintId,
    },
    /// SP6 for a planar sub-chain between two bodies turning about known axes
    /// (`runtime::turn3d::planar_chain_ends`): the angles `[θ1, θ2]` (`Ty::Values`) of the first
    /// body's turn about `first` and of the joint `joint` between the chain's last body and the
    /// far body, which turns about `last`; `h` and `base` the chain's axis and joint point in the
    /// first body, `far` its axis in the last body (`sense` times the first's), `offset` its
    /// offset along the axes. The root of `branch` (up to four, by `θ1` ascending), or an error
    /// naming `constraint`. The sketch's branch is the root of least turn of both.
    PlanarChainEnds {
        first: [Reg; 2],
        h: Reg,
        base: Reg,
        joint: [Reg; 2],
        far: Reg,
        last: [Reg; 2],
        offset: Reg,
        sense: f64,
        branch: BranchId,
        constraint: ConstraintId,
    },
    /// Rotates `geoms` rigidly by `angle` about the line through `pivot` along the
    /// unit `axis` (a turn whose angle an earlier step measured, from more than one pair).
    RotateBy {
        geoms: Vec<GeomId>,
        pivot: Reg,
        axis: Reg,
        angle: Reg,
    },
}
