//! The operations of the plane only: its lines' offsets and reversal, the conics of circles'
//! centres, angles from the x axis, and a line turned onto a point.

use super::{BranchId, Reg};
use gcs_lang::model::ConstraintId;

/// An operation only a planar plan holds.
#[derive(Clone, Debug, PartialEq)]
pub enum PlanarOp {
    /// A line with its direction reversed (left and right swap).
    Reversed(Reg),
    /// Line `line` moved `by` to its left.
    OffsetLine { line: Reg, by: Reg },
    /// The centres `X` of circles of any radius `r` with `sd_l1(X) = r + a1` and
    /// `sd_l2(X) = r + a2`: an angular bisector (002, RR-1).
    CentresLineLine { l1: Reg, a1: Reg, l2: Reg, a2: Reg },
    /// The centres with `sd_line(X) = r + a` and `|X - at| = r + b` (`plus`) or `b - r`: a
    /// parabola.
    CentresLinePoint {
        line: Reg,
        a: Reg,
        at: Reg,
        b: Reg,
        plus: bool,
    },
    /// The centres with `|X - c1| = ±r + b1` and `|X - c2| = ±r + b2`: a hyperbola branch or an
    /// ellipse.
    CentresPointPoint {
        c1: Reg,
        b1: Reg,
        p1: bool,
        c2: Reg,
        b2: Reg,
        p2: bool,
    },
    /// The radius `sd_line(centre) - a`.
    RadiusFromLine { line: Reg, a: Reg, centre: Reg },
    /// The radius `|centre - at| - b` (`plus`) or `b - |centre - at|`.
    RadiusFromPoint {
        at: Reg,
        b: Reg,
        plus: bool,
        centre: Reg,
    },
    /// A constant direction (the X or Y axis).
    Axis(f64, f64),
    /// `dir` rotated counter-clockwise by `angle`.
    Rotated { dir: Reg, angle: Reg },
    /// The counter-clockwise angle of direction `dir` from the x axis, in (-pi, pi].
    AngleOf(Reg),
    /// The point with coordinates `x` and `y`.
    PointXY { x: Reg, y: Reg },
    /// The mirror image of `point` across line `line`.
    Mirror { point: Reg, line: Reg },
    /// The circle about `center` with `radius`.
    Circle { center: Reg, radius: Reg },
    /// The circle about `center` through `through`. `radius` is its radius when the analysis
    /// knows it (the two points belong to one rigid geom whose sketch of them is constant):
    /// the consumers then use that number, and agree to the bit.
    CircleThrough {
        center: Reg,
        through: Reg,
        radius: Option<f64>,
    },
    /// The direction of line (`base`, `dir`) once its cluster has turned about `pivot` until the
    /// line passes `point` at signed distance `offset` (absent: through it; positive: `point`
    /// to the line's left): the root of `branch` (0: `point` ahead of the pivot along the
    /// line, 1: behind), or an error naming `constraint`. The sketch's branch is the root
    /// nearest `dir`. A line through a point tangent to a circle; a crank's slot through a pin.
    PassingDir {
        pivot: Reg,
        base: Reg,
        dir: Reg,
        point: Reg,
        offset: Option<Reg>,
        branch: BranchId,
        constraint: ConstraintId,
    },
}
