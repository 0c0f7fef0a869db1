//! The Plan: Kramer's metaphorical assembly plan as one straight-line program, and the one
//! boundary between the analysis and its consumers.
//!
//! A plan is a list of steps over typed registers. Measurements read the current configuration
//! (the global position of a member point, the direction of a member vector), constructions
//! build loci, intersections pick a root by branch variable, actions move geoms (translate,
//! rotate, scale) and checks re-measure relations that earlier steps already imply. Every step
//! names the constraints it satisfies and carries its explanation, with the model's names bound.
//!
//! The three consumers (interpreter, code generator, explainer) read the same plan, and only
//! the plan: what they need of the analysis is in it. [`Plan::validate`] states and checks its
//! invariants; a consumer given a plan that fails them has a bug to report, not an answer.
//!
//! Both spaces' plans are written in it, and the analysis emits all of it: registers of the
//! plane (conics) and of space (planes, spheres, cylinders, tori) beside those of both ([`Ty`]);
//! the locus intersections of either space ([`Meet`]: the plane's pairs from
//! `analysis::planar`, space's from `analysis::spatial`, each checked by the validator to
//! belong to the plan's space); rotations about the plane's normal, about an axis in a register
//! or the shortest ([`RotationAxis`]); and, for models with no closed form, default parameters
//! ([`DefaultVar`], read by `Op::Default`) with the iterated regions that close them
//! ([`Iteration`], whose `Op::Close` steps an outer iteration drives to zero). [`Residual`] is
//! the one table of checks: the relation a check holds, over registers, one kind per residual
//! function of `gcs_runtime::check`.

mod deps;
mod dump;
mod planar;
mod search;
mod spatial;
mod validate;

pub use deps::{by_position, nearest, support_words, Deps, Slice, Support, Supporter, Walk, SHOWN};
pub use planar::{Coef, LinearRow, LinearSystem, LinearTerm, PlanarOp};
pub use search::{grid, GRID, MAX_COMBINATIONS};
pub use spatial::{HelixRegs, Reach, ScrewRegs, SpatialOp};
pub use validate::Malformed;

use gcs_lang::expr::ExprId;
use gcs_lang::model::{ConstraintId, GeomId, Space};
use gcs_lang::Model;
use gcs_runtime::check::Nesting;

/// A register: the result of one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Reg(pub u32);

/// A branch variable: which root of a finite intersection to take.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BranchId(pub u32);

/// A default parameter: a degree of freedom the analysis fixed by a redundant constraint,
/// whose value is an input (000, section 5.2.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DefaultId(pub u32);

/// The type of a register's value. Points, vectors, lines and circles are those of the plan's
/// space; conics exist only in the plane, planes, spheres and cylinders only in space.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ty {
    /// A real number.
    Scalar,
    /// A point.
    Point,
    /// A unit direction.
    Vector,
    /// A directed line.
    Line,
    /// A circle (in space, with its axis).
    Circle,
    /// A conic of the plane (parabola, ellipse, hyperbola branch).
    Conic,
    /// A plane of space.
    Plane,
    /// A sphere.
    Sphere,
    /// A cylinder.
    Cylinder,
    /// A torus: the points at a distance from a circle of space.
    Torus,
    /// Several answers of one step (a linear system's, `PlanarOp::Linear`; the three-circle
    /// problem's angles, `SpatialOp::ThreeCircles`), read one by one (`Op::Unknown`).
    Values,
}

impl Ty {
    /// Whether a value of this type exists in `space`.
    pub fn in_space(self, space: Space) -> bool {
        match self {
            Ty::Conic => space == Space::D2,
            Ty::Plane | Ty::Sphere | Ty::Cylinder | Ty::Torus => space == Space::D3,
            _ => true,
        }
    }
}

/// How an intersection's branch index reads, for explanations and generated comments.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchVar {
    /// The variable's name: the constraint's label or derived name.
    pub name: String,
    /// The constraint whose intersection it chooses.
    pub constraint: ConstraintId,
    /// How many roots the intersection may have.
    pub count: usize,
    /// The geometric meaning of each index, in index order.
    pub meanings: Vec<String>,
    /// The index the sketch has, where [`BranchVar::from_sketch`]; else 0.
    pub default: usize,
    /// Whether `default` is the sketch's: the root nearest the sketch, the plan run on the
    /// sketch (`pipeline::analyse`). False where that run stops before this intersection (a
    /// step before it fails on the sketch), and for a plan the pipeline has not seen.
    pub from_sketch: bool,
    /// Whether its roots are one assembly turned as a whole: a root on the line or plane a
    /// model with nothing fixed is held by (`Plan::grounded_direction`, `grounded_plane`),
    /// whose other root is the sketch's turned half a turn. The search for every assembly
    /// keeps the sketch's.
    pub symmetric: bool,
}

/// A default parameter of the plan: its name and meaning, and the value the sketch gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct DefaultVar {
    /// Its name, after what it fixes (`crank_angle`).
    pub name: String,
    /// What it fixes, in words.
    pub meaning: String,
    /// The top-level geom whose freedom it fixes, if one.
    pub geom: Option<GeomId>,
    /// Its value in the sketch: where a solve starts when the caller gives none.
    pub sketch: f64,
    /// The register that holds, when the plan runs on the sketch, the value with which the
    /// default moves nothing (least motion): the sketch value is read from it. Analysis only:
    /// pruning drops it.
    pub measure: Option<Reg>,
    /// For a default an outer iteration varies: its value in the sketch's assembly at the
    /// model's params on the sketch's branches (the real assembly that moves the points least
    /// from the sketch, which sets the iteration's mode), found once by the pipeline so that a
    /// cold solve follows that assembly from there without searching for it again. `None`
    /// for a free motion's default, or where no assembly was found.
    pub assembled: Option<f64>,
}

impl DefaultVar {
    /// Whether it is an angle (in radians), rather than a length or a coordinate.
    pub fn is_angle(&self) -> bool {
        self.name.ends_with("_angle")
    }
}

/// A region of steps run again for each trial of its defaults: an outer iteration varies
/// `defaults` until every `Close` step of the region measures zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// The defaults the iteration varies.
    pub defaults: Vec<DefaultId>,
    /// The first step of the region.
    pub start: usize,
    /// One past the last step of the region.
    pub end: usize,
    /// The orientation of the root the sketch sits on (its assembly mode,
    /// [`gcs_runtime::mode`]), which a solve from the sketch's defaults keeps; `None` where the
    /// sketch's root has none (a closing error that is a magnitude at its root, a fold) or the
    /// plan was not run on the sketch.
    pub mode: Option<gcs_runtime::mode::Orientation>,
}

impl Iteration {
    /// Its assembly mode in words: the sign its closing errors' Jacobian has at the sketch.
    pub fn mode_words(&self) -> Option<&'static str> {
        use gcs_runtime::mode::Orientation;
        Some(match (self.mode?, self.defaults.len()) {
            (Orientation::Positive, 1) => "its closing error rising with its default",
            (Orientation::Negative, 1) => "its closing error falling as its default rises",
            (Orientation::Positive, _) => {
                "its closing errors' Jacobian in its defaults with a positive determinant"
            }
            (Orientation::Negative, _) => {
                "its closing errors' Jacobian in its defaults with a negative determinant"
            }
        })
    }
}

/// The `component` of an [`Op::Error`] that is the relation's residual, the magnitude its
/// check measures, rather than one coordinate of its error.
pub const MAGNITUDE: u8 = u8::MAX;

/// Which locus intersection: the pair of loci, in the order of the intersection table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Meet {
    /// Two circles: in the plane, branch 0 left of the directed line between centres.
    CircleCircle,
    /// A line and a circle of the plane: order along the line.
    LineCircle,
    /// Two lines of the plane: one root.
    LineLine,
    /// A circle and a conic: order along the conic.
    CircleConic,
    /// A line and a conic: order along the line.
    LineConic,
    /// Two conics: order along the first.
    ConicConic,
    /// A line and a plane: one root.
    LinePlane,
    /// A line and a sphere: order along the line.
    LineSphere,
    /// A line and a cylinder: order along the line.
    LineCylinder,
    /// A circle and a plane of space.
    CirclePlane,
    /// A circle and a sphere.
    CircleSphere,
    /// Two spheres: their circle.
    SphereSphere,
    /// A sphere and a plane: their circle.
    SpherePlane,
    /// Two planes: their line.
    PlanePlane,
    /// A plane parallel to a cylinder's axis and the cylinder: their lines, in order across
    /// the axis (`intersect3d::plane_cylinder_lines`).
    PlaneCylinder,
}

impl Meet {
    /// The types of its two loci, in order.
    pub fn operands(self) -> (Ty, Ty) {
        use Ty::*;
        match self {
            Meet::CircleCircle => (Circle, Circle),
            Meet::LineCircle => (Line, Circle),
            Meet::LineLine => (Line, Line),
            Meet::CircleConic => (Circle, Conic),
            Meet::LineConic => (Line, Conic),
            Meet::ConicConic => (Conic, Conic),
            Meet::LinePlane => (Line, Plane),
            Meet::LineSphere => (Line, Sphere),
            Meet::LineCylinder => (Line, Cylinder),
            Meet::CirclePlane => (Circle, Plane),
            Meet::CircleSphere => (Circle, Sphere),
            Meet::SphereSphere => (Sphere, Sphere),
            Meet::SpherePlane => (Sphere, Plane),
            Meet::PlanePlane => (Plane, Plane),
            Meet::PlaneCylinder => (Plane, Cylinder),
        }
    }

    /// What it yields: a point of a finite set of roots, or (in space) a locus.
    pub fn result(self) -> Ty {
        match self {
            Meet::SphereSphere | Meet::SpherePlane => Ty::Circle,
            Meet::PlanePlane | Meet::PlaneCylinder => Ty::Line,
            _ => Ty::Point,
        }
    }

    /// Whether it belongs to `space`: two circles and a line and a circle meet in both (in
    /// space, circles with their axes: a line meets a circle where it meets the circle's
    /// sphere, and a later step checks that the root is on the circle).
    pub fn in_space(self, space: Space) -> bool {
        match self {
            Meet::CircleCircle | Meet::LineCircle => true,
            Meet::LineLine | Meet::CircleConic | Meet::LineConic | Meet::ConicConic => {
                space == Space::D2
            }
            _ => space == Space::D3,
        }
    }
}

/// The axis of a rotation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotationAxis {
    /// The plane's normal: the one axis a rotation of the plane has.
    Normal,
    /// In space, the unit direction in a register.
    Along(Reg),
    /// In space, the axis perpendicular to the vectors turned from and to: the shortest
    /// rotation between them.
    Shortest,
}

/// The relation a run-time check holds, over registers. Each kind has one residual function
/// in `gcs_runtime::check`, which the interpreter and generated code both call.
#[derive(Clone, Debug, PartialEq)]
pub enum Residual {
    /// `|a - b| = d` (absent: a coincidence).
    PointPoint { a: Reg, b: Reg, d: Option<Reg> },
    /// The signed distance of `p` from the line through `base` along `dir` is `d` (positive
    /// to the left; absent: zero).
    PointLine {
        p: Reg,
        base: Reg,
        dir: Reg,
        d: Option<Reg>,
    },
    /// The counter-clockwise angle from `u` to `v` is `angle`.
    Angle { u: Reg, v: Reg, angle: Reg },
    /// The circle (`centre`, `radius`) on side `side` (+1 left, -1 right) of the line through
    /// `base` along `dir`, its perimeter `gap` from it (absent: tangent).
    CircleLine {
        centre: Reg,
        radius: Reg,
        base: Reg,
        dir: Reg,
        gap: Option<Reg>,
        side: f64,
    },
    /// `p` at `gap` from the perimeter of the circle (`centre`, `radius`) (absent: on it),
    /// outside or inside.
    PointCircle {
        p: Reg,
        centre: Reg,
        radius: Reg,
        gap: Option<Reg>,
        outside: bool,
    },
    /// Two circles `gap` apart at their perimeters (absent: tangent), sitting as `nesting`.
    CircleCircle {
        c1: Reg,
        r1: Reg,
        c2: Reg,
        r2: Reg,
        gap: Option<Reg>,
        nesting: Nesting,
    },
    /// A dimension `value` is `target`.
    Dim { value: Reg, target: Reg },
    /// `p` is the midpoint of `a` and `b`.
    Midpoint { p: Reg, a: Reg, b: Reg },
    /// `q` is the mirror image of `p` across the line through `base` along `dir`.
    Mirror { p: Reg, q: Reg, base: Reg, dir: Reg },
    /// In space: `q` is the mirror image of `p` across the plane through `base` with unit
    /// normal `normal`.
    MirrorPlane {
        p: Reg,
        q: Reg,
        base: Reg,
        normal: Reg,
    },
    /// In space: the signed distance of `p` from the plane through `base` with unit normal
    /// `normal` is `d` (absent: zero).
    PointPlane {
        p: Reg,
        base: Reg,
        normal: Reg,
        d: Option<Reg>,
    },
    /// In space: directions `u` and `v` are parallel, `v` along `sense * u` (+1 or -1; 0:
    /// either).
    Parallel { u: Reg, v: Reg, sense: f64 },
    /// In space: `p` is at distance `d` (absent: 0, on it) from the circle about `centre`
    /// with unit `normal` and `radius`.
    OnCircle {
        p: Reg,
        centre: Reg,
        normal: Reg,
        radius: Reg,
        d: Option<Reg>,
    },
    /// In space: the unsigned angle between directions `u` and `v` is `angle`.
    AngleBetween { u: Reg, v: Reg, angle: Reg },
    /// In space: unit directions `u` and `v` make the same angle with unit `axis`, as a turn
    /// about `axis` needs to take one onto the other. Its error is `(u - v) . axis`, signed.
    Cone { axis: Reg, u: Reg, v: Reg },
    /// In space: the angle from `u` to `v` counter-clockwise about `axis` is `2pi s / pitch`
    /// (modulo a turn), `s` the advance `(q - p) . axis` (a helical joint).
    Helix {
        axis: Reg,
        u: Reg,
        v: Reg,
        p: Reg,
        q: Reg,
        pitch: Reg,
    },
    /// In space: the angle from `u` to `v`, counter-clockwise about `axis` (to which both are
    /// perpendicular), is `angle`.
    Twist {
        axis: Reg,
        u: Reg,
        v: Reg,
        angle: Reg,
    },
}

/// One operation: those of both spaces, then each space's own, so that a back end matches
/// only its space's.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Evaluates an expression of the model (params are inputs).
    Expr(ExprId),
    /// Evaluates `constraint`'s value, a size (a length, a radius, an unsigned distance):
    /// a negative one is an invalid value of that constraint, not a pair of loci that miss.
    Size {
        /// The value.
        expr: ExprId,
        /// The constraint it is the value of, which an error names.
        constraint: ConstraintId,
    },
    /// A constant chosen at analysis (0 or pi for parallel, from the sketch).
    Const(f64),
    /// The value of a default parameter (an input, like a param).
    Default(DefaultId),
    /// `-x`.
    Neg(Reg),
    /// The current dimension of a geom (a segment's length, a circle's radius).
    DimOf(GeomId),
    /// A linear combination of scalars.
    Sum(Vec<(f64, Reg)>),
    /// Answer `index` of a step's several answers `of` (`Ty::Values`): an unknown of a
    /// linear system, or an angle of the three-circle problem.
    Unknown { of: Reg, index: u16 },
    /// The signed distance from point `from` to point `to` along direction `dir`.
    Along { from: Reg, dir: Reg, to: Reg },
    /// The unit direction from point `from` to point `to`.
    DirectionTo { from: Reg, to: Reg },
    /// The global position of a point feature (a point geom, member, marker or part).
    PointOf(GeomId),
    /// The global direction of a vector feature (a vector geom, member, axis or `dir`).
    DirOf(GeomId),
    /// The midpoint of points `a` and `b`.
    Midpoint { a: Reg, b: Reg },
    /// The reflection of `point` through `through`: `2 through - point` (a segment's other
    /// end, from one end and its midpoint).
    Reflect { point: Reg, through: Reg },
    /// The point of a line or circle `locus` at parameter `at`: the signed distance along a
    /// line from its base point, the angle about a circle's centre from the x axis.
    LocusPoint { locus: Reg, at: Reg },
    /// The parameter of `point`'s nearest point on a line or circle `locus` (the inverse of
    /// [`Op::LocusPoint`]).
    LocusParam { locus: Reg, point: Reg },
    /// The line through `point` along `dir`, moved `offset` to its left.
    Line {
        point: Reg,
        dir: Reg,
        offset: Option<Reg>,
    },
    /// The line parallel to line `line` through `through`.
    ParallelLine { line: Reg, through: Reg },
    /// Circle `circle` moved by the vector from `from` to `to`.
    ShiftedCircle { circle: Reg, from: Reg, to: Reg },
    /// The point of `locus` nearest to `point` (least motion).
    Nearest { locus: Reg, point: Reg },
    /// `point`, which must lie on `locus` (a 1-DOF motion can reach it only then); otherwise
    /// an error naming `constraint` with the distance.
    Onto {
        locus: Reg,
        point: Reg,
        constraint: ConstraintId,
    },
    /// The intersection of two loci; the root of `branch`, or an error naming `constraint`.
    /// `near` is the moving feature's position before the move: the sketch's branch is the
    /// root nearest to it.
    Intersect {
        meet: Meet,
        a: Reg,
        b: Reg,
        branch: BranchId,
        constraint: ConstraintId,
        near: Reg,
    },
    /// Translates `geoms` rigidly by the vector from `from` to `to`.
    Translate {
        geoms: Vec<GeomId>,
        from: Reg,
        to: Reg,
    },
    /// Rotates `geoms` rigidly about `pivot` around `axis` by the angle from `from - pivot` to
    /// `to - pivot` (points), so that `from` lands on `to`.
    RotatePoint {
        geoms: Vec<GeomId>,
        pivot: Reg,
        axis: RotationAxis,
        from: Reg,
        to: Reg,
    },
    /// Rotates `geoms` rigidly about `pivot` around `axis` by the angle from direction `from`
    /// to `to`.
    RotateDir {
        geoms: Vec<GeomId>,
        pivot: Reg,
        axis: RotationAxis,
        from: Reg,
        to: Reg,
    },
    /// Sets a geom's dimension (a segment's length, a circle's radius), keeping its origin.
    SetDim { geom: GeomId, value: Reg },
    /// Re-measures a relation of `constraint` already implied by earlier steps: it must hold
    /// within tolerance, or the model is inconsistent by the residual's size.
    Check {
        constraint: ConstraintId,
        residual: Residual,
        /// A guard, not a redundancy: a relation of a constraint an iterated region claims,
        /// re-measured once the plan has run, so that an iteration closed on an error that
        /// does not measure all its default displaced is never an answer.
        guard: bool,
    },
    /// The signed error of a relation already implied (zero when it holds): what a `Close`
    /// drives to zero. A coincidence has two, `component` 0 and 1 (x and y); others one. A
    /// point on a line of space (`Residual::PointLine` at no distance) has, besides its
    /// distance (0), its offset across the line as two signed coordinates: 1 along
    /// `runtime::frame::perpendicular` of the line's direction, 2 along the direction
    /// crossed with that.
    /// [`MAGNITUDE`] is its residual instead, the unsigned distance a coincidence, a midpoint
    /// or a mirror image is off by: the one error of such a relation one default displaced.
    Error { residual: Residual, component: u8 },
    /// The implicit function of a line, circle or conic `locus` at `point`, zero on it (a
    /// line's signed distance, `|point - centre| - radius` or to first order near a circle:
    /// the runtime's `closing_error`): the error of an `Onto` a default displaced.
    Implicit { locus: Reg, point: Reg },
    /// An error function of an iteration: `residual`, which the iteration drives to zero,
    /// closes `constraint` (the constraint a default displaced).
    Close {
        constraint: ConstraintId,
        residual: Reg,
    },
    /// An operation of the plane only.
    Planar(PlanarOp),
    /// An operation of space only.
    Spatial(SpatialOp),
}

impl From<PlanarOp> for Op {
    fn from(op: PlanarOp) -> Op {
        Op::Planar(op)
    }
}

impl From<SpatialOp> for Op {
    fn from(op: SpatialOp) -> Op {
        Op::Spatial(op)
    }
}

/// One step: an operation, the register it defines (if any), what it satisfies, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// What it does.
    pub op: Op,
    /// The register it defines.
    pub out: Option<(Reg, Ty)>,
    /// The constraints this step satisfies (for actions) or verifies (for checks).
    pub satisfies: Vec<ConstraintId>,
    /// The constraint whose relation the analysis was working on when it wrote the step, if
    /// any (none for a default's or grounding's steps). An action on a constraint's earlier
    /// relation satisfies nothing yet, but still moves its geoms for that constraint:
    /// [`Plan::support`] reads it.
    pub works_for: Option<ConstraintId>,
    /// The explanation, with the model's names bound.
    pub explain: String,
}

/// A complete plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The space its values live in.
    pub space: Space,
    /// The steps, in execution order.
    pub steps: Vec<Step>,
    /// The branch variables, indexed by [`BranchId`].
    pub branches: Vec<BranchVar>,
    /// The default parameters, indexed by [`DefaultId`].
    pub defaults: Vec<DefaultVar>,
    /// The iterated regions, in step order, disjoint.
    pub iterations: Vec<Iteration>,
    /// The geom grounded at its sketch because nothing was fixed, if any.
    pub grounded: Option<GeomId>,
    /// When the grounded geom has no orientation: the two points whose sketch direction is
    /// held too, so that only a rigid motion is factored out.
    pub grounded_direction: Option<(GeomId, GeomId)>,
    /// In space, when the grounded geom has no orientation: the third point whose sketch
    /// plane with the two of `grounded_direction` is held too.
    pub grounded_plane: Option<GeomId>,
    /// The DOF the grounding holds: a rigid placement's (3 in the plane, 6 in space), less
    /// any the constraints anchor to the world; 0 when something is fixed.
    pub grounded_dof: usize,
    /// The number of registers.
    pub regs: u32,
}

impl Plan {
    /// The constraint that closes a profile with the length step `i` (a `SetDim`) gives its
    /// segment: a length measured along the segment's own direction to where its end must be
    /// (`Along`: the step's own constraint), or its sketch's length plus an unknown of a linear
    /// stage (the constraint of the row that gives it). A negative one means the profile
    /// cannot close with its segments running as sketched
    /// ([`gcs_runtime::error::ErrorKind::CannotClose`]). `None` for any other step or length.
    /// Each value is looked for backwards from where it is read, which is near: a length's
    /// own steps come just before it.
    pub fn closing_length(&self, i: usize) -> Option<ConstraintId> {
        let Op::SetDim { value, .. } = self.steps.get(i)?.op else {
            return None;
        };
        let before = |at: usize, r: Reg| {
            (self.steps[..at].iter().enumerate().rev())
                .find(|(_, s)| s.out.is_some_and(|(o, _)| o == r))
        };
        let (at, def) = before(i, value)?;
        let terms = match &def.op {
            Op::Along { .. } => return self.constraint_of(i),
            Op::Sum(terms) => terms,
            _ => return None,
        };
        terms.iter().find_map(|&(_, t)| {
            let (at, def) = before(at, t)?;
            let Op::Unknown { of, index } = def.op else {
                return None;
            };
            let Op::Planar(PlanarOp::Linear(system)) = &before(at, of)?.1.op else {
                return None;
            };
            let row = match system.pivots.iter().find(|(u, _)| *u == index) {
                Some(&(_, row)) => row,
                None => {
                    let k = system.tears.iter().position(|&u| u == index)?;
                    *system.closures.get(k)?
                }
            };
            Some(system.rows.get(usize::from(row))?.constraint)
        })
    }

    /// The default whose given value register `r` holds: defined by [`Op::Default`] of a
    /// default no iteration varies (an iteration's trial values are its own to bound).
    pub fn given_default(&self, r: Reg) -> Option<DefaultId> {
        let step = self
            .steps
            .iter()
            .find(|s| s.out.is_some_and(|(o, _)| o == r))?;
        let Op::Default(d) = step.op else {
            return None;
        };
        let iterated = (self.iterations.iter()).any(|it| it.defaults.contains(&d));
        (!iterated).then_some(d)
    }

    /// An empty plan of `space`.
    pub fn new(space: Space) -> Plan {
        Plan {
            space,
            steps: Vec::new(),
            branches: Vec::new(),
            defaults: Vec::new(),
            iterations: Vec::new(),
            grounded: None,
            grounded_direction: None,
            grounded_plane: None,
            grounded_dof: 0,
            regs: 0,
        }
    }

    /// The top-level geoms the plan reads or moves.
    pub fn touched(&self, model: &Model) -> std::collections::BTreeSet<GeomId> {
        let mut out = std::collections::BTreeSet::new();
        for s in &self.steps {
            out.extend(s.op.measures().map(|f| model.top_level_of(f)));
            out.extend(s.op.moves().iter().copied());
        }
        out
    }

    /// The constraint step `i` works for, to name it in errors: the one it satisfies, else the
    /// next step's that satisfies or intersects for one, else the previous such step's.
    pub fn constraint_of(&self, i: usize) -> Option<ConstraintId> {
        let of = |s: &Step| {
            s.satisfies.first().copied().or(match &s.op {
                Op::Intersect { constraint, .. }
                | Op::Planar(PlanarOp::PassingDir { constraint, .. })
                | Op::Onto { constraint, .. }
                | Op::Check { constraint, .. }
                | Op::Close { constraint, .. } => Some(*constraint),
                _ => None,
            })
        };
        let later = self.steps.get(i..).unwrap_or(&[]).iter().find_map(of);
        later.or_else(|| self.steps.get(..i).unwrap_or(&[]).iter().rev().find_map(of))
    }

    /// The names of the defaults iteration `it` varies.
    pub fn varied(&self, it: &Iteration) -> Vec<&str> {
        (it.defaults.iter())
            .filter_map(|d| self.defaults.get(d.0 as usize).map(|d| d.name.as_str()))
            .collect()
    }

    /// The constraints iteration `it` closes: those of the `Close` steps of its region.
    pub fn closes(&self, it: &Iteration) -> Vec<ConstraintId> {
        let region = self.steps.get(it.start..it.end.min(self.steps.len()));
        (region.unwrap_or(&[]).iter())
            .filter_map(|s| match s.op {
                Op::Close { constraint, .. } => Some(constraint),
                _ => None,
            })
            .collect()
    }

    /// The value of every default in the sketch, indexed by [`DefaultId`].
    pub fn sketch_defaults(&self) -> Vec<f64> {
        self.defaults.iter().map(|d| d.sketch).collect()
    }
}

impl Residual {
    /// The registers it reads.
    pub fn reads(&self) -> Vec<Reg> {
        self.operands().into_iter().map(|(r, _)| r).collect()
    }
}

/// An expression as text, for dumps and explanations.
pub fn expr_text(model: &Model, e: ExprId) -> String {
    use gcs_lang::expr::ExprNode as N;
    use gcs_lang::syntax::{AngleUnit, BinaryOp};
    match model.exprs.node(e) {
        N::Const(v) => fmt_f64(*v),
        N::Param(p) => model.params[*p].name.clone(),
        N::Neg(a) => format!("-{}", expr_text(model, *a)),
        N::Binary(op, a, b) => {
            let o = match op {
                BinaryOp::Add => "+",
                BinaryOp::Sub => "-",
                BinaryOp::Mul => "*",
                BinaryOp::Div => "/",
                BinaryOp::Pow => "^",
            };
            format!("({} {o} {})", expr_text(model, *a), expr_text(model, *b))
        }
        N::Call(f, a, b) => match b {
            Some(b) => format!(
                "{}({}, {})",
                f.name(),
                expr_text(model, *a),
                expr_text(model, *b)
            ),
            None => format!("{}({})", f.name(), expr_text(model, *a)),
        },
        N::Unit(u, a) => {
            let unit = if *u == AngleUnit::Deg { "deg" } else { "rad" };
            format!("{} {unit}", expr_text(model, *a))
        }
    }
}

/// A float for dumps: shortest round-trip form.
pub fn fmt_f64(v: f64) -> String {
    if v == v.trunc() && v.abs() < 1e15 {
        format!("{v:.0}")
    } else {
        format!("{v}")
    }
}
