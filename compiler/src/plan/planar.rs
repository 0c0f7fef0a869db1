//! The operations of the plane only: its lines' offsets and reversal, the conics of circles'
//! centres, angles from the x axis, a line turned onto a point, and the linear systems of
//! clusters whose directions are all known.

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
    /// The unit direction of line `line`.
    LineDir(Reg),
    /// The slides and free lengths of clusters whose directions are all known, where every
    /// constraint left between them is linear in those: a closed profile of horizontal and
    /// vertical segments with fillets. The answers of the system (`Ty::Values`), solved by
    /// `gcs_runtime::linear`, or an error naming the constraint whose row is singular.
    Linear(Box<LinearSystem>),
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

/// A linear system of a plan's linear stage, torn as `gcs_runtime::linear::Torn` solves it:
/// row `r` reads `sum(term.scale * term.coef * x[term.unknown]) = -error_r`, each unknown an
/// increment (a slide along a known direction, a change of length) from where it is now.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearSystem {
    /// The number of unknowns.
    pub unknowns: u16,
    /// Each unknown's name, an identifier (`bottom_dx`, `tl_slide`, `left_stretch`).
    pub names: Vec<String>,
    /// The rows.
    pub rows: Vec<LinearRow>,
    /// The unknowns taken as parameters, fixed by the `closures`.
    pub tears: Vec<u16>,
    /// Each other unknown with the row that gives it, in the order they are solved.
    pub pivots: Vec<(u16, u16)>,
    /// The rows that fix the tears, one per tear.
    pub closures: Vec<u16>,
}

/// One equation of a [`LinearSystem`]: a relation of `constraint`, linear in the unknowns.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearRow {
    /// The constraint the relation belongs to, which a singular row names.
    pub constraint: ConstraintId,
    /// Its signed error as things stand (zero when it holds).
    pub error: Reg,
    /// How the error changes with each unknown.
    pub terms: Vec<LinearTerm>,
}

/// A term of a [`LinearRow`]: `scale * coef` times unknown `unknown`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearTerm {
    /// The unknown.
    pub unknown: u16,
    /// A constant factor (a side, a sign).
    pub scale: f64,
    /// The coefficient, read from known directions.
    pub coef: Coef,
}

/// A coefficient of a linear row, from unit directions (registers of `Ty::Vector`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coef {
    /// 1.
    One,
    /// The x coordinate of a direction.
    X(Reg),
    /// The y coordinate of a direction.
    Y(Reg),
    /// The dot product of two directions.
    Dot(Reg, Reg),
    /// The cross product `a.x * b.y - a.y * b.x` of two directions.
    Cross(Reg, Reg),
}

impl Coef {
    /// The registers it reads.
    pub fn regs(&self) -> impl Iterator<Item = Reg> {
        let (a, b) = match *self {
            Coef::One => (None, None),
            Coef::X(v) | Coef::Y(v) => (Some(v), None),
            Coef::Dot(u, v) | Coef::Cross(u, v) => (Some(u), Some(v)),
        };
        a.into_iter().chain(b)
    }
}

impl LinearSystem {
    /// The runtime's row starts and terms' unknowns.
    pub fn shape(&self) -> (Vec<u32>, Vec<u16>) {
        let mut row_start = vec![0u32];
        let mut term_unknown = Vec::new();
        for row in &self.rows {
            term_unknown.extend(row.terms.iter().map(|t| t.unknown));
            row_start.push(term_unknown.len() as u32);
        }
        (row_start, term_unknown)
    }
}
