//! The Plan: Kramer's metaphorical assembly plan as one straight-line program.
//!
//! A plan is a list of steps over typed registers. Measurements read the current configuration
//! (the global position of a member point, the direction of a member vector), constructions
//! build loci, intersections pick a root by branch variable, actions move geoms (translate,
//! rotate, scale) and checks re-measure constraints that earlier steps already imply. Every step
//! names the constraints it satisfies and carries its explanation, with the model's names bound.
//!
//! The three consumers (interpreter, code generator, explainer) read the same plan.

use gcs_lang::expr::ExprId;
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;
use std::fmt::Write as _;

/// A register: the result of one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Reg(pub u32);

/// A branch variable: which root of a finite intersection to take.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BranchId(pub u32);

/// The type of a register's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ty {
    /// A real number.
    Scalar,
    /// A point of the plane.
    Point,
    /// A unit direction of the plane.
    Vector,
    /// A directed line.
    Line,
    /// A circle.
    Circle,
    /// A conic (parabola, ellipse, hyperbola branch).
    Conic,
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
    /// The index the sketch has.
    pub default: usize,
}

/// Which sort of 2d locus intersection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Meet {
    /// Two circles: branch 0 left of the directed line between centres.
    CircleCircle,
    /// A line and a circle: order along the line.
    LineCircle,
    /// Two lines: one root.
    LineLine,
    /// A circle and a conic: order along the conic.
    CircleConic,
    /// A line and a conic: order along the line.
    LineConic,
}

/// One operation.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// Evaluates an expression of the model (params are inputs).
    Expr(ExprId),
    /// A constant chosen at analysis (0 or pi for parallel, from the sketch).
    Const(f64),
    /// `-x`.
    Neg(Reg),
    /// The current dimension of a geom (a segment's length, a circle's radius).
    DimOf(GeomId),
    /// A linear combination of scalars.
    Sum(Vec<(f64, Reg)>),
    /// The signed distance from point `from` to point `to` along direction `dir`.
    Along { from: Reg, dir: Reg, to: Reg },
    /// The unit direction from point `from` to point `to`.
    DirectionTo { from: Reg, to: Reg },
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
    /// The global position of a point feature (a point geom, member, marker or part).
    PointOf(GeomId),
    /// The global direction of a vector feature (a vector geom, member, axis or `dir`).
    DirOf(GeomId),
    /// A constant direction (the X or Y axis).
    Axis(f64, f64),
    /// `dir` rotated counter-clockwise by `angle`.
    Rotated { dir: Reg, angle: Reg },
    /// The circle about `center` with `radius`.
    Circle { center: Reg, radius: Reg },
    /// The circle about `center` through `through`.
    /// `rigid` names the two features (at the centre, and the one moving) when they belong to
    /// one rigid geom: the radius is then their distance in it, known when generating code.
    CircleThrough {
        center: Reg,
        through: Reg,
        rigid: Option<(GeomId, GeomId)>,
    },
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
    /// Rotates `geoms` rigidly about `pivot` by the angle from `from - pivot` to `to - pivot`
    /// (points), so that `from` lands on `to`.
    RotatePoint {
        geoms: Vec<GeomId>,
        pivot: Reg,
        from: Reg,
        to: Reg,
    },
    /// Rotates `geoms` rigidly about `pivot` by the angle from direction `from` to `to`.
    RotateDir {
        geoms: Vec<GeomId>,
        pivot: Reg,
        from: Reg,
        to: Reg,
    },
    /// Sets a geom's dimension (a segment's length, a circle's radius), keeping its origin.
    SetDim { geom: GeomId, value: Reg },
    /// Re-measures a constraint already implied by earlier steps: it must hold within
    /// tolerance, or the model is inconsistent by the residual's size.
    Check { constraint: ConstraintId },
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
    /// The explanation, with the model's names bound.
    pub explain: String,
}

/// A complete plan.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    /// The steps, in execution order.
    pub steps: Vec<Step>,
    /// The branch variables, indexed by [`BranchId`].
    pub branches: Vec<BranchVar>,
    /// The geom grounded at its sketch because nothing was fixed, if any.
    pub grounded: Option<GeomId>,
    /// When the grounded geom has no orientation: the two points whose sketch direction is
    /// held too, so that only a rigid motion is factored out.
    pub grounded_direction: Option<(GeomId, GeomId)>,
    /// The number of registers.
    pub regs: u32,
}

impl Plan {
    /// The registers an operation reads.
    pub fn reads(op: &Op) -> Vec<Reg> {
        match op {
            Op::Expr(_)
            | Op::Const(_)
            | Op::PointOf(_)
            | Op::DirOf(_)
            | Op::Axis(..)
            | Op::Check { .. } => {
                vec![]
            }
            Op::Neg(x) | Op::Reversed(x) => vec![*x],
            Op::DimOf(_) => vec![],
            Op::Sum(terms) => terms.iter().map(|t| t.1).collect(),
            Op::Along { from, dir, to } => vec![*from, *dir, *to],
            Op::DirectionTo { from, to } => vec![*from, *to],
            Op::OffsetLine { line, by } => vec![*line, *by],
            Op::CentresLineLine { l1, a1, l2, a2 } => vec![*l1, *a1, *l2, *a2],
            Op::CentresLinePoint { line, a, at, b, .. } => vec![*line, *a, *at, *b],
            Op::CentresPointPoint { c1, b1, c2, b2, .. } => vec![*c1, *b1, *c2, *b2],
            Op::RadiusFromLine { line, a, centre } => vec![*line, *a, *centre],
            Op::RadiusFromPoint { at, b, centre, .. } => vec![*at, *b, *centre],
            Op::Rotated { dir, angle } => vec![*dir, *angle],
            Op::Circle { center, radius } => vec![*center, *radius],
            Op::CircleThrough {
                center, through, ..
            } => vec![*center, *through],
            Op::Line { point, dir, offset } => {
                let mut v = vec![*point, *dir];
                v.extend(*offset);
                v
            }
            Op::ParallelLine { line, through } => vec![*line, *through],
            Op::ShiftedCircle { circle, from, to } => vec![*circle, *from, *to],
            Op::Nearest { locus, point } | Op::Onto { locus, point, .. } => vec![*locus, *point],
            Op::Intersect { a, b, near, .. } => vec![*a, *b, *near],
            Op::Translate { from, to, .. } => vec![*from, *to],
            Op::RotatePoint {
                pivot, from, to, ..
            }
            | Op::RotateDir {
                pivot, from, to, ..
            } => {
                vec![*pivot, *from, *to]
            }
            Op::SetDim { value, .. } => vec![*value],
        }
    }

    /// The top-level geoms the plan reads or moves.
    pub fn touched(&self, model: &Model) -> std::collections::BTreeSet<GeomId> {
        let mut out = std::collections::BTreeSet::new();
        for s in &self.steps {
            match &s.op {
                Op::PointOf(f) | Op::DirOf(f) | Op::DimOf(f) => {
                    out.insert(model.top_level_of(*f));
                }
                Op::Translate { geoms, .. }
                | Op::RotatePoint { geoms, .. }
                | Op::RotateDir { geoms, .. } => {
                    out.extend(geoms.iter().copied());
                }
                Op::SetDim { geom, .. } => {
                    out.insert(*geom);
                }
                Op::Check { constraint } => {
                    out.extend(
                        model.constraints[*constraint]
                            .args
                            .iter()
                            .map(|a| model.top_level_of(*a)),
                    );
                }
                _ => {}
            }
        }
        out
    }

    /// The constraint step `i` works for, to name it in errors: the one it satisfies, else the
    /// next step's that satisfies or intersects for one, else the previous such step's.
    pub fn constraint_of(&self, i: usize) -> Option<ConstraintId> {
        let of = |s: &Step| {
            s.satisfies.first().copied().or(match &s.op {
                Op::Intersect { constraint, .. }
                | Op::Onto { constraint, .. }
                | Op::Check { constraint } => Some(*constraint),
                _ => None,
            })
        };
        let later = self.steps.get(i..).unwrap_or(&[]).iter().find_map(of);
        later.or_else(|| self.steps.get(..i).unwrap_or(&[]).iter().rev().find_map(of))
    }

    /// The stable text dump of the plan, one step a line, with names from the model.
    pub fn dump(&self, model: &Model) -> String {
        let name = |g: &GeomId| model.geoms[*g].name.clone();
        let names = |gs: &[GeomId]| gs.iter().map(name).collect::<Vec<_>>().join(" ");
        let cname = |c: &ConstraintId| model.constraints[*c].name.clone();
        let mut out = String::new();
        if let Some(g) = self.grounded {
            let _ = writeln!(out, "ground {} at its sketch", name(&g));
        }
        if let Some((a, b)) = self.grounded_direction {
            let _ = writeln!(
                out,
                "hold the sketch direction from {} to {}",
                name(&a),
                name(&b)
            );
        }
        for b in &self.branches {
            let _ = writeln!(
                out,
                "branch {} ({} roots, default {}): {}",
                b.name,
                b.count,
                b.default,
                b.meanings.join("; ")
            );
        }
        for s in &self.steps {
            let lhs = match s.out {
                Some((r, ty)) => format!("r{} : {:?} = ", r.0, ty),
                None => String::new(),
            };
            let r = |r: &Reg| format!("r{}", r.0);
            let op = match &s.op {
                Op::Expr(e) => format!("expr {}", expr_text(model, *e)),
                Op::Const(c) => format!("const {}", fmt_f64(*c)),
                Op::Neg(x) => format!("neg {}", r(x)),
                Op::DimOf(g) => format!("dim_of {}", name(g)),
                Op::Sum(terms) => format!(
                    "sum {}",
                    terms
                        .iter()
                        .map(|(s, x)| format!("{}*{}", fmt_f64(*s), r(x)))
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
                Op::Reversed(x) => format!("reversed {}", r(x)),
                Op::Along { from, dir, to } => format!("along {} {} {}", r(from), r(dir), r(to)),
                Op::DirectionTo { from, to } => format!("direction_to {} {}", r(from), r(to)),
                Op::OffsetLine { line, by } => format!("offset_line {} by {}", r(line), r(by)),
                Op::CentresLineLine { l1, a1, l2, a2 } => {
                    format!("centres_line_line {} {} {} {}", r(l1), r(a1), r(l2), r(a2))
                }
                Op::CentresLinePoint {
                    line,
                    a,
                    at,
                    b,
                    plus,
                } => format!(
                    "centres_line_point {} {} {} {} {}",
                    r(line),
                    r(a),
                    r(at),
                    r(b),
                    if *plus { "plus" } else { "minus" }
                ),
                Op::CentresPointPoint {
                    c1,
                    b1,
                    p1,
                    c2,
                    b2,
                    p2,
                } => format!(
                    "centres_point_point {} {} {} {} {} {}",
                    r(c1),
                    r(b1),
                    if *p1 { "plus" } else { "minus" },
                    r(c2),
                    r(b2),
                    if *p2 { "plus" } else { "minus" }
                ),
                Op::RadiusFromLine { line, a, centre } => {
                    format!("radius_from_line {} {} {}", r(line), r(a), r(centre))
                }
                Op::RadiusFromPoint {
                    at,
                    b,
                    plus,
                    centre,
                } => format!(
                    "radius_from_point {} {} {} {}",
                    r(at),
                    r(b),
                    if *plus { "plus" } else { "minus" },
                    r(centre)
                ),
                Op::PointOf(g) => format!("point_of {}", name(g)),
                Op::DirOf(g) => format!("dir_of {}", name(g)),
                Op::Axis(x, y) => format!("axis ({x}, {y})"),
                Op::Rotated { dir, angle } => format!("rotated {} by {}", r(dir), r(angle)),
                Op::Circle { center, radius } => format!("circle {} {}", r(center), r(radius)),
                Op::CircleThrough {
                    center, through, ..
                } => {
                    format!("circle_through {} {}", r(center), r(through))
                }
                Op::Line { point, dir, offset } => match offset {
                    Some(o) => format!("line {} {} offset {}", r(point), r(dir), r(o)),
                    None => format!("line {} {}", r(point), r(dir)),
                },
                Op::ParallelLine { line, through } => {
                    format!("parallel_line {} through {}", r(line), r(through))
                }
                Op::ShiftedCircle { circle, from, to } => {
                    format!("shifted_circle {} {} -> {}", r(circle), r(from), r(to))
                }
                Op::Nearest { locus, point } => format!("nearest {} {}", r(locus), r(point)),
                Op::Onto {
                    locus,
                    point,
                    constraint,
                } => {
                    format!("onto {} {} for {}", r(locus), r(point), cname(constraint))
                }
                Op::Intersect {
                    meet,
                    a,
                    b,
                    branch,
                    constraint,
                    ..
                } => format!(
                    "intersect {:?} {} {} branch {} for {}",
                    meet,
                    r(a),
                    r(b),
                    self.branches
                        .get(branch.0 as usize)
                        .map_or("?", |b| b.name.as_str()),
                    cname(constraint)
                ),
                Op::Translate { geoms, from, to } => {
                    format!("translate [{}] {} -> {}", names(geoms), r(from), r(to))
                }
                Op::RotatePoint {
                    geoms,
                    pivot,
                    from,
                    to,
                } => {
                    format!(
                        "rotate [{}] about {} {} -> {}",
                        names(geoms),
                        r(pivot),
                        r(from),
                        r(to)
                    )
                }
                Op::RotateDir {
                    geoms,
                    pivot,
                    from,
                    to,
                } => format!(
                    "rotate [{}] about {} dir {} -> {}",
                    names(geoms),
                    r(pivot),
                    r(from),
                    r(to)
                ),
                Op::SetDim { geom, value } => format!("set_dim {} {}", name(geom), r(value)),
                Op::Check { constraint } => format!("check {}", cname(constraint)),
            };
            let sat = if s.satisfies.is_empty() {
                String::new()
            } else {
                format!(
                    "   ; {}",
                    s.satisfies.iter().map(cname).collect::<Vec<_>>().join(", ")
                )
            };
            let _ = writeln!(out, "{lhs}{op}{sat}");
        }
        out
    }

    /// Checks the plan's invariants: every register is defined once, before it is read, with
    /// the type its reader expects; every constraint of the model is satisfied by exactly one
    /// step or verified by one check; every branch variable is used by exactly one intersection.
    pub fn validate(&self, model: &Model) -> Result<(), Vec<String>> {
        let mut errors = Vec::new();
        let mut defined: std::collections::HashMap<Reg, Ty> = Default::default();
        let mut satisfied: std::collections::HashMap<ConstraintId, usize> = Default::default();
        let mut branch_uses = vec![0usize; self.branches.len()];
        for (i, s) in self.steps.iter().enumerate() {
            for r in Self::reads(&s.op) {
                if !defined.contains_key(&r) {
                    errors.push(format!("step {i} reads r{} before it is defined", r.0));
                }
            }
            if let Op::Intersect { branch, .. } = &s.op {
                match branch_uses.get_mut(branch.0 as usize) {
                    Some(n) => *n += 1,
                    None => errors.push(format!("step {i} uses an undeclared branch")),
                }
            }
            if let Some((r, ty)) = s.out {
                if defined.insert(r, ty).is_some() {
                    errors.push(format!("step {i} redefines r{}", r.0));
                }
            }
            for c in &s.satisfies {
                *satisfied.entry(*c).or_default() += 1;
            }
        }
        for (id, c) in model.constraints.iter() {
            match satisfied.get(&id).copied().unwrap_or(0) {
                1 => {}
                0 => errors.push(format!(
                    "constraint {} is neither satisfied nor checked",
                    c.name
                )),
                n => errors.push(format!("constraint {} is satisfied by {n} steps", c.name)),
            }
        }
        for (b, n) in self.branches.iter().zip(&branch_uses) {
            if *n != 1 {
                errors.push(format!("branch {} is used {n} times", b.name));
            }
        }
        if errors.is_empty() {
            Ok(())
        } else {
            Err(errors)
        }
    }
}

/// The distance between two point features of one body whose local coordinates do not depend
/// on params: known when the plan is built. A circle through one about the other has this
/// radius; the interpreter and generated code both use it, so that they agree to the bit.
pub fn constant_distance(model: &Model, a: GeomId, b: GeomId) -> Option<f64> {
    use gcs_lang::model::{Owner, Sketch};
    let local = |f: GeomId| -> Option<(f64, f64)> {
        match (&model.geoms[f].sketch, model.geoms[f].owner) {
            (Sketch::Point(c) | Sketch::Marker { origin: c, .. }, Owner::Member(_))
                if c.iter().all(|&e| model.exprs.is_constant(e)) =>
            {
                let v = |i: usize| c.get(i).map_or(0.0, |&e| model.exprs.eval(e, &[]));
                Some((v(0), v(1)))
            }
            _ => None,
        }
    };
    let ((ax, ay), (bx, by)) = (local(a)?, local(b)?);
    if model.top_level_of(a) != model.top_level_of(b) {
        return None;
    }
    Some(nalgebra::Vector2::new(ax - bx, ay - by).norm())
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
