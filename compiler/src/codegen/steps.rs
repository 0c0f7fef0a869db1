//! Each step of the plan as code: a measurement, locus, intersection, action or check lowered to
//! the runtime's calls, with what is known at that step (see `facts`) deciding the cheapest
//! code that gives the same value.

use super::facts::{ChordRoot, Value};
use super::names::Namer;
use super::solve::Solve;
use super::writer::{float, linear, lit, Writer};
use crate::plan::{BranchId, Meet, Op, PlanarOp, Reg, Residual, SpatialOp, Step};
use gcs_lang::expr::{ExprId, ExprNode};
use gcs_lang::model::{ConstraintId, GeomId};

impl Solve<'_> {
    /// Writes step `i` of the plan.
    pub(super) fn step(&mut self, w: &mut Writer, i: usize, step: &Step) {
        self.step_start = (self.ledger.borrow().mark(), self.cx.errors_made.get());
        match &step.op {
            Op::Translate { geoms, from, to } => {
                let space = self.cx.space;
                space.translate(self, w, geoms, *from, *to)
            }
            Op::RotatePoint {
                geoms,
                pivot,
                axis,
                from,
                to,
            } => {
                let space = self.cx.space;
                space.rotate(self, w, geoms, (*pivot, *axis), (*from, *to), true)
            }
            Op::RotateDir {
                geoms,
                pivot,
                axis,
                from,
                to,
            } => {
                let space = self.cx.space;
                space.rotate(self, w, geoms, (*pivot, *axis), (*from, *to), false)
            }
            Op::Spatial(SpatialOp::RotateBy {
                geoms,
                pivot,
                axis,
                angle,
            }) => self.rotate_by(w, geoms, (*pivot, *axis), *angle),
            Op::SetDim { geom, value } => self.set_dim(w, i, *geom, *value),
            Op::Check {
                constraint,
                residual,
                ..
            } => self.check(w, *constraint, residual),
            Op::Close {
                constraint,
                residual,
            } => self.close(w, *constraint, *residual),
            op => match step.out {
                // A value no generated step reads (an intersection's `near`, the point a
                // circle of constant radius goes through) is not written: its code would read
                // frames for nothing, and declare them.
                Some((r, _))
                    if self.cx.used.contains(&r)
                        && !(self.converged && self.error_only.contains(&r)) =>
                {
                    self.value(w, i, r, op)
                }
                // A circle not written still tells its radius to the turns onto it.
                _ => {
                    if let Op::Planar(PlanarOp::CircleThrough {
                        center,
                        through,
                        radius: Some(k),
                    }) = op
                    {
                        self.facts.circle_radius.insert((*center, *through), *k);
                    }
                }
            },
        }
    }

    /// Writes the value of register `r`, which step `i` computes with `op`: a scalar the same
    /// way in both spaces, anything else as the model's space writes it.
    fn value(&mut self, w: &mut Writer, i: usize, r: Reg, op: &Op) {
        match op {
            Op::Expr(e) => self.expr_value(w, i, r, *e),
            Op::Size { expr, constraint } => self.size_value(w, r, *expr, *constraint),
            Op::Const(c) => {
                self.facts.regs.insert(r, Value::Scalar(*c));
            }
            Op::Neg(x) => {
                // A literal's negation is a literal (and `--5.0` would not build).
                if let Value::Scalar(c) = self.facts.value(*x) {
                    let minus = Value::Scalar(-c);
                    self.facts.regs.insert(r, minus);
                    return;
                }
                if self.facts.is_finite(*x) {
                    self.facts.known_finite.insert(r);
                }
                let code = format!("-{}", self.r(*x));
                self.define(w, r, "minus", &code);
            }
            Op::DimOf(g) => {
                let d = self.dim_local(*g);
                self.facts.regs.insert(r, Value::Local(d));
            }
            Op::Sum(terms) => {
                let code = self.sum(terms);
                self.define_finite(w, i, r, "sum", &code);
            }
            Op::Unknown { of, index } => {
                let code = format!("{}[{index}]", self.r(*of));
                let name = (self.unknown_names.get(of))
                    .and_then(|names| names.get(*index as usize).cloned())
                    .unwrap_or_else(|| "change".to_string());
                self.define(w, r, &name, &code);
            }
            Op::Default(d) => {
                // An input, like a param: `solve` checks it finite on entry. One an iteration
                // varies is its trial's entry.
                let value = match self.iterated.get(d) {
                    Some((trial, k)) => Value::Entry(trial.clone(), *k),
                    None => Value::Default(d.0 as usize, self.cx.defaults[d.0 as usize].clone()),
                };
                self.facts.regs.insert(r, value);
            }
            _ => {
                let space = self.cx.space;
                space.value(self, w, i, r, op)
            }
        }
    }

    /// Writes the value of register `r`, which step `i` computes with `op`, in the plane.
    pub(super) fn value2(&mut self, w: &mut Writer, i: usize, r: Reg, op: &Op) {
        let m = self.cx.model;
        let degenerate = || self.cx.error(i, "Degenerate", "0.0");
        match op {
            Op::PointOf(g) => {
                if let Some(at) = self.offset_from_origin(*g) {
                    self.facts.at_offset.insert(r, at);
                }
                let value = self.point_value(*g);
                self.define_or_alias(w, r, &m.geoms[*g].name, value);
            }
            Op::DirOf(g) => {
                let value = self.dir_value(*g);
                let n = &m.geoms[*g].name;
                let n = if n.ends_with(".dir") {
                    n.clone()
                } else {
                    format!("{n}_dir")
                };
                self.define_or_alias(w, r, &n, value);
            }
            Op::Error {
                residual,
                component,
            } => {
                if !self.converged {
                    let code = if *component == crate::plan::MAGNITUDE {
                        self.residual_code(residual)
                    } else {
                        self.error_code(residual, *component)
                    };
                    self.define(w, r, "error", &code);
                }
            }
            Op::Midpoint { a, b } => {
                let code = format!("locus2d::midpoint({}, {})", self.r(*a), self.r(*b));
                self.define(w, r, "midpoint", &code);
            }
            Op::Reflect { point, through } => {
                let code = format!(
                    "locus2d::reflect_through({}, {})",
                    self.r(*point),
                    self.r(*through)
                );
                let n = self.prefixed("reflected", *point);
                self.define(w, r, &n, &code);
            }
            Op::LocusPoint { locus, at } => {
                let code = format!("{}.at({})", self.r(*locus), self.r(*at));
                let n = self.prefixed("on", *locus);
                self.define(w, r, &n, &code);
            }
            Op::Implicit { locus, point } => {
                if !self.converged {
                    let code = format!("{}.closing_error({})", self.r(*locus), self.r(*point));
                    self.define(w, r, "error", &code);
                }
            }
            Op::LocusParam { locus, point } => {
                let code = format!("{}.param_of({})", self.r(*locus), self.r(*point));
                self.define(w, r, "param", &code);
            }
            Op::Along { from, dir, to } => {
                let (f, d, t) = (self.r(*from), self.r(*dir), self.r(*to));
                self.define(w, r, "length", &format!("({t} - {f}).dot(&{d})"));
            }
            Op::DirectionTo { from, to } => {
                let (f, t) = (self.r(*from), self.r(*to));
                let code = format!(
                    "({t} - {f}).try_normalize(0.0).ok_or_else(|| {})?",
                    degenerate()
                );
                self.define(w, r, "direction", &code);
            }
            Op::Line { point, dir, offset } => {
                let mut code = format!(
                    "Line::new({}, {}).ok_or_else(|| {})?",
                    self.r(*point),
                    self.r(*dir),
                    degenerate()
                );
                if let Some(o) = offset {
                    code = format!("{code}.offset({})", self.r(*o));
                }
                let n = self.prefixed("line", *point);
                self.define(w, r, &n, &code);
            }
            Op::ParallelLine { line, through } => {
                let code = format!(
                    "Line::new({}, {}.dir()).ok_or_else(|| {})?",
                    self.r(*through),
                    self.r(*line),
                    degenerate()
                );
                let n = self.prefixed("parallel", *through);
                self.define(w, r, &n, &code);
            }
            Op::ShiftedCircle { circle, from, to } => {
                let c = self.r(*circle);
                let code = format!(
                    "Circle::new({c}.center() + ({} - {}), {c}.radius()).ok_or_else(|| {})?",
                    self.r(*to),
                    self.r(*from),
                    degenerate()
                );
                let n = self.derived_name(*circle, "_moved", "circle_moved");
                self.define(w, r, &n, &code);
            }
            Op::Nearest { locus, point } => {
                if self.cx.turned_toward.contains(&r) {
                    // Only turns about the circle's centre read it, and they need only the
                    // direction from the centre, which the point itself has: no projection
                    // (its square root and division) on the solve's path.
                    let point = self.facts.value(*point).clone();
                    self.facts.regs.insert(r, point);
                    return;
                }
                let code = format!("{}.nearest({})", self.r(*locus), self.r(*point));
                let n = self.prefixed("nearest", *point);
                self.define(w, r, &n, &code);
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => self.onto(w, r, *locus, *point, *constraint),
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                ..
            } => self.intersect(w, r, *meet, (*a, *b), *branch, *constraint),
            // Actions and checks define no register: `step` writes them.
            Op::Translate { .. }
            | Op::RotatePoint { .. }
            | Op::RotateDir { .. }
            | Op::SetDim { .. }
            | Op::Check { .. }
            | Op::Close { .. } => {}
            Op::Planar(op) => self.planar_value(w, i, r, op),
            Op::Spatial(_) => {
                unreachable!("bug in gcs: step {i} is an operation of space in a planar plan")
            }
            Op::Expr(_)
            | Op::Size { .. }
            | Op::Const(_)
            | Op::Neg(_)
            | Op::DimOf(_)
            | Op::Sum(_)
            | Op::Unknown { .. }
            | Op::Default(_) => unreachable!("bug in gcs: step {i}'s scalar is written by `value`"),
        }
    }

    /// Writes the value of register `r`, which step `i` computes with an operation of the
    /// plane.
    fn planar_value(&mut self, w: &mut Writer, i: usize, r: Reg, op: &PlanarOp) {
        let degenerate = || self.cx.error(i, "Degenerate", "0.0");
        match op {
            PlanarOp::Axis(x, y) => {
                self.facts.regs.insert(r, Value::Vector(*x, *y));
            }
            PlanarOp::Rotated { dir, angle } => self.rotated(w, r, *dir, *angle),
            PlanarOp::AngleOf(dir) => {
                let d = self.r(*dir);
                self.define(w, r, "angle", &format!("{d}.y.atan2({d}.x)"));
            }
            PlanarOp::PointXY { x, y } => {
                let code = format!("Point2::new({}, {})", self.r(*x), self.r(*y));
                self.define(w, r, "point", &code);
            }
            PlanarOp::Mirror { point, line } => {
                let code = format!("{}.mirror({})", self.r(*line), self.r(*point));
                let n = self.prefixed("mirrored", *point);
                self.define(w, r, &n, &code);
            }
            PlanarOp::Circle { center, radius } => self.circle(w, i, r, *center, *radius),
            PlanarOp::CircleThrough {
                center,
                through,
                radius,
            } => self.circle_through(w, i, r, *center, *through, *radius),
            PlanarOp::LineDir(x) => {
                let code = format!("{}.dir()", self.r(*x));
                let n = self.derived_name(*x, "_dir", "line_dir");
                self.define(w, r, &n, &code);
            }
            PlanarOp::Linear(system) => self.linear_system(w, r, system),
            PlanarOp::Reversed(x) => {
                let code = format!("{}.reversed()", self.r(*x));
                let n = self.derived_name(*x, "_reversed", "reversed");
                self.define(w, r, &n, &code);
            }
            PlanarOp::OffsetLine { line, by } => {
                let code = format!("{}.offset({})", self.r(*line), self.r(*by));
                let n = self.derived_name(*line, "_offset", "offset");
                self.define(w, r, &n, &code);
            }
            PlanarOp::CentresLineLine { l1, a1, l2, a2 } => {
                let code = format!(
                    "locus2d::centres_line_line(&{}, {}, &{}, {}).ok_or_else(|| {})?",
                    self.r(*l1),
                    self.r(*a1),
                    self.r(*l2),
                    self.r(*a2),
                    degenerate()
                );
                self.define(w, r, "bisector", &code);
            }
            PlanarOp::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => {
                let code = format!(
                    "Conic::Parabola(locus2d::centres_line_circle(&{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?)",
                    self.r(*line),
                    self.r(*a),
                    self.r(*at),
                    sense(*plus),
                    self.r(*b),
                    degenerate()
                );
                self.define(w, r, "parabola", &code);
            }
            PlanarOp::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => {
                let code = format!(
                    "locus2d::centres_circle_circle({}, Sense::{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?",
                    self.r(*c1),
                    sense(*p1),
                    self.r(*b1),
                    self.r(*c2),
                    sense(*p2),
                    self.r(*b2),
                    degenerate()
                );
                self.define(w, r, "conic", &code);
            }
            PlanarOp::RadiusFromLine { line, a, centre } => {
                let code = format!(
                    "{}.signed_distance({}) - {}",
                    self.r(*line),
                    self.r(*centre),
                    self.r(*a)
                );
                self.define(w, r, "radius", &code);
            }
            PlanarOp::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => {
                let d = format!("({} - {}).norm()", self.r(*centre), self.r(*at));
                let code = if *plus {
                    format!("{d} - {}", self.r(*b))
                } else {
                    format!("{} - {d}", self.r(*b))
                };
                self.define(w, r, "radius", &code);
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
                let line = (*pivot, *base, *dir);
                self.passing_dir(w, r, line, *point, *offset, *branch, *constraint)
            }
        }
    }

    /// `let {name} = {code};` for register `reg`.
    /// Solves a linear stage's system (`gcs_runtime::linear`): its shape a constant, its
    /// coefficients and right-hand sides read from the directions and errors before it, a
    /// singular row an error naming that row's constraint.
    fn linear_system(&mut self, w: &mut Writer, r: Reg, system: &crate::plan::LinearSystem) {
        use crate::plan::Coef;
        let (row_start, term_unknown) = system.shape();
        let list = |v: &mut dyn Iterator<Item = String>| v.collect::<Vec<_>>().join(", ");
        let n = system.unknowns as usize;
        let work = n * (system.tears.len() + 1);
        let shape = self.names.fresh("system");
        w.comment(&format!(
            "One linear system in the {n} slides and free lengths left (`gcs_runtime::linear`):"
        ));
        w.comment(&match system.tears.len() {
            0 => "each pivot row gives one unknown from those before.".to_string(),
            k => format!(
                "each pivot row gives one unknown from those before, and the closures fix the \
                 {k} torn."
            ),
        });
        w.line(&format!(
            "const {}: gcs_runtime::linear::Torn<'static> = gcs_runtime::linear::Torn {{",
            shape.to_uppercase()
        ));
        w.line(&format!("unknowns: {n},"));
        w.line(&format!(
            "row_start: &[{}],",
            list(&mut row_start.iter().map(u32::to_string))
        ));
        w.line(&format!(
            "term_unknown: &[{}],",
            list(&mut term_unknown.iter().map(u16::to_string))
        ));
        w.line(&format!(
            "tears: &[{}],",
            list(&mut system.tears.iter().map(u16::to_string))
        ));
        w.line(&format!(
            "pivots: &[{}],",
            list(&mut system.pivots.iter().map(|(a, b)| format!("({a}, {b})")))
        ));
        w.line(&format!(
            "closures: &[{}],",
            list(&mut system.closures.iter().map(u16::to_string))
        ));
        w.line("};");
        let component = |s: &Self, v: Reg, x: bool| match s.facts.value(v) {
            Value::Vector(a, b) => float(if x { *a } else { *b }),
            _ => format!("{}.{}", s.r(v), if x { "x" } else { "y" }),
        };
        let mut coefs = Vec::new();
        let mut rhs = Vec::new();
        for row in &system.rows {
            rhs.push(format!("-{}", self.r(row.error)));
            for t in &row.terms {
                let c = match t.coef {
                    Coef::One => {
                        coefs.push(float(t.scale));
                        continue;
                    }
                    Coef::X(v) => component(self, v, true),
                    Coef::Y(v) => component(self, v, false),
                    Coef::Dot(a, b) => format!("{}.dot(&{})", self.r(a), self.r(b)),
                    Coef::Cross(a, b) => format!("{}.perp(&{})", self.r(a), self.r(b)),
                };
                coefs.push(if t.scale == 1.0 {
                    c
                } else if t.scale == -1.0 {
                    format!("-{c}")
                } else {
                    format!("{} * {c}", float(t.scale))
                });
            }
        }
        // A singular row names its own constraint.
        let mut blame: Vec<(gcs_lang::model::ConstraintId, Vec<usize>)> = Vec::new();
        for (k, row) in system.rows.iter().enumerate() {
            match blame.iter_mut().find(|(c, _)| *c == row.constraint) {
                Some((_, rows)) => rows.push(k),
                None => blame.push((row.constraint, vec![k])),
            }
        }
        let mut arms = Vec::new();
        for (k, (c, rows)) in blame.iter().enumerate() {
            let pattern = if k + 1 == blame.len() {
                "_".to_string()
            } else {
                list(&mut rows.iter().map(usize::to_string)).replace(", ", " | ")
            };
            arms.push(format!(
                "{pattern} => {},",
                self.cx.error_of(*c, "Degenerate", "0.0")
            ));
        }
        let local = self.names.fresh("changes");
        let code = format!(
            "{}.solve::<{n}, {work}>(&[{}], &[{}]).map_err(|singular| match singular.row {{ {} }})?",
            shape.to_uppercase(),
            coefs.join(", "),
            rhs.join(", "),
            arms.join(" ")
        );
        self.let_line(w, &local, &local, &code);
        self.facts.regs.insert(r, Value::Local(local));
        self.unknown_names.insert(r, system.names.clone());
    }

    pub(super) fn define(&mut self, w: &mut Writer, reg: Reg, name: &str, code: &str) {
        let local = self.names.fresh(name);
        self.let_line(w, &local, &local, code);
        self.facts.regs.insert(reg, Value::Local(local));
    }

    /// Like [`Solve::define`] for a scalar the params give, which can overflow however finite
    /// they are (`theta * 1e300`): the step's constraint cannot be met with a value that is
    /// not finite, so the solve says so rather than going on with garbage.
    pub(super) fn define_finite(
        &mut self,
        w: &mut Writer,
        i: usize,
        reg: Reg,
        name: &str,
        code: &str,
    ) {
        self.define(w, reg, name, code);
        let v = self.r(reg);
        w.open(&format!("if !gcs_runtime::num::is_finite({v}) {{"));
        w.line(&format!(
            "return Err({});",
            self.cx.error(i, "InvalidValue", &v)
        ));
        w.close("}");
        self.facts.known_finite.insert(reg);
    }

    /// Like [`Solve::define`], but a local or a literal needs no new local: the register is
    /// that value (a literal named `name` for what derives from it).
    pub(super) fn define_or_alias(&mut self, w: &mut Writer, reg: Reg, name: &str, value: Value) {
        if !value.is_atom() {
            self.define(w, reg, name, &self.code(&value));
            return;
        }
        if value.is_literal() {
            self.facts.literal_names.insert(reg, Namer::snake(name));
        }
        self.facts.regs.insert(reg, value);
    }

    /// A name derived from register `r`: `{name}{suffix}` after its local or the literal it
    /// names, else `fallback`.
    fn derived_name(&self, r: Reg, suffix: &str, fallback: &str) -> String {
        let name = self.facts.literal_names.get(&r).cloned();
        match name.or_else(|| self.facts.value(r).local()) {
            Some(name) => format!("{name}{suffix}"),
            None => fallback.to_string(),
        }
    }

    /// `{prefix}_{name}` after register `r` (see [`Solve::derived_name`]), or just `prefix`.
    fn prefixed(&self, prefix: &str, r: Reg) -> String {
        let n = self.derived_name(r, "", "");
        if n.is_empty() {
            prefix.to_string()
        } else {
            format!("{prefix}_{n}")
        }
    }

    /// The value of a model expression: a param or a constant as it is (a param is checked
    /// finite on entry), anything else in a local checked finite.
    fn expr_value(&mut self, w: &mut Writer, i: usize, r: Reg, e: ExprId) {
        let m = self.cx.model;
        if let ExprNode::Param(p) = m.exprs.node(e) {
            let field = self.cx.params[p].clone();
            let index = p.into_raw().into_u32() as usize;
            self.facts.regs.insert(r, Value::Param(index, field));
        } else if m.exprs.is_constant(e) {
            let v = m.exprs.eval(e, &[]);
            self.facts.regs.insert(r, Value::Scalar(v));
        } else {
            let code = self.cx.expr(e);
            self.define_finite(w, i, r, "value", &code);
        }
    }

    /// The value of `constraint`, a size: a param or an expression, and an invalid value error
    /// when it is negative (or, for an expression, not finite). A constant is known valid: a
    /// negative one fails the analysis' run on the sketch.
    fn size_value(&mut self, w: &mut Writer, r: Reg, e: ExprId, constraint: ConstraintId) {
        let m = self.cx.model;
        let test = if let ExprNode::Param(p) = m.exprs.node(e) {
            // Params are checked finite on entry.
            let field = self.cx.params[p].clone();
            let index = p.into_raw().into_u32() as usize;
            self.facts.regs.insert(r, Value::Param(index, field));
            format!("{} < 0.0", self.r(r))
        } else if m.exprs.is_constant(e) && m.exprs.eval(e, &[]) >= 0.0 {
            self.facts
                .regs
                .insert(r, Value::Scalar(m.exprs.eval(e, &[])));
            return;
        } else {
            let code = self.cx.expr(e);
            self.define(w, r, "value", &code);
            self.facts.known_finite.insert(r);
            let v = self.r(r);
            format!("!gcs_runtime::num::is_finite({v}) || {v} < 0.0")
        };
        let con = &m.constraints[constraint];
        w.comment(&format!(
            "{}: {} is zero or more.",
            con.name,
            size_noun(m, constraint)
        ));
        // A size that is a param alone is the param's fault.
        let error = match m.exprs.node(e) {
            ExprNode::Param(p) => {
                self.cx
                    .error_with(&m.params[*p].name, &con.text, "InvalidParam", &self.r(r))
            }
            _ => self.cx.error_of(constraint, "InvalidValue", &self.r(r)),
        };
        w.open(&format!("if {test} {{"));
        w.line(&format!("return Err({error});"));
        w.close("}");
        self.facts.known_sizes.insert(r);
    }

    /// `dir` turned by `angle`: a direction at that angle when `dir` is the x axis (a finite
    /// unit direction when the angle is finite).
    ///
    /// A literal angle is turned here, by the runtime's own `direction_at` (the bits the solve
    /// would compute), so that a table of pieces holds the direction, not the angle to take
    /// the sine and cosine of at each solve.
    fn rotated(&mut self, w: &mut Writer, r: Reg, dir: Reg, angle: Reg) {
        let (d, a) = (self.r(dir), self.r(angle));
        let literal = match *self.facts.value(angle) {
            Value::Scalar(a) if a.is_finite() => {
                let v = gcs_runtime::frame::direction_at(a);
                Some(Value::Vector(v.x, v.y))
            }
            _ => None,
        };
        if let Some(turned) = literal {
            let n = self.derived_name(dir, "_turned", "direction");
            if self.facts.value(dir).is_x_axis() {
                self.facts.unit_dirs.insert(r);
                self.define_or_alias(w, r, &n, turned);
            } else {
                let code = format!("rotation_from_x_unit(&{}) * {d}", turned.code());
                self.define(w, r, &n, &code);
            }
            return;
        }
        // An iteration's trial angle: turned from the iteration's start (`DirectionsNear`).
        let near = match self.facts.value(angle) {
            Value::Entry(trial, k) => {
                let key = (trial.clone(), *k);
                self.trial_directions.get_mut(&key).map(|t| {
                    t.used = true;
                    t.name.clone()
                })
            }
            _ => None,
        };
        let near = near.map(|name| {
            self.note_read(&name);
            format!("{name}.at({a})")
        });
        let turned = near.unwrap_or_else(|| format!("direction_at({a})"));
        let code = if self.facts.value(dir).is_x_axis() {
            if self.facts.is_finite(angle) {
                self.facts.unit_dirs.insert(r);
            }
            turned
        } else {
            format!("rotation_from_x_unit(&{turned}) * {d}")
        };
        let n = self.derived_name(dir, "_turned", "direction");
        self.define(w, r, &n, &code);
    }

    /// The code of a linear combination of scalar registers.
    fn sum(&self, terms: &[(f64, Reg)]) -> String {
        let mut code = String::new();
        for (k, (s, x)) in terms.iter().enumerate() {
            let v = self.r(*x);
            let (first, unit, minus) = (k == 0, *s == 1.0, *s == -1.0);
            let term = match (first, unit, minus) {
                (true, true, _) => v,
                (true, _, true) => format!("-{v}"),
                (true, _, _) => format!("{} * {v}", float(*s)),
                (false, true, _) => format!(" + {v}"),
                (false, _, true) => format!(" - {v}"),
                (false, _, _) => format!(" + {} * {v}", float(*s)),
            };
            code.push_str(&term);
        }
        code
    }

    /// The circle about `center` with `radius`; a radius not known to be non-negative (a
    /// constant, or a size its constraint has already tested) is tested first.
    fn circle(&mut self, w: &mut Writer, i: usize, r: Reg, center: Reg, radius: Reg) {
        let rad = self.r(radius);
        let non_negative = matches!(self.facts.value(radius), Value::Scalar(v) if *v >= 0.0)
            || self.facts.known_sizes.contains(&radius);
        if !non_negative {
            w.open(&format!("if {rad} < 0.0 {{"));
            w.line(&format!(
                "return Err({});",
                self.cx.error(i, "NoIntersection", &format!("-{rad}"))
            ));
            w.close("}");
        }
        let code = format!(
            "Circle::new({}, {rad}).ok_or_else(|| {})?",
            self.r(center),
            self.cx.error(i, "Degenerate", "0.0")
        );
        let n = self.prefixed("circle", center);
        self.define(w, r, &n, &code);
        let center = self.facts.value(center).clone();
        self.facts.circle_centers.insert(r, center);
    }

    /// The circle about `center` through `through`; when the plan knows its radius (both are
    /// features of one rigid geom with constant local coordinates), that number.
    fn circle_through(
        &mut self,
        w: &mut Writer,
        i: usize,
        r: Reg,
        center: Reg,
        through: Reg,
        known: Option<f64>,
    ) {
        let c = self.r(center);
        if let Some(k) = known {
            self.facts.circle_radius.insert((center, through), k);
        }
        // A known radius needs no point: `through` is then never written.
        let radius = known.map_or_else(|| format!("({} - {c}).norm()", self.r(through)), float);
        let code = format!(
            "Circle::new({c}, {radius}).ok_or_else(|| {})?",
            self.cx.error(i, "Degenerate", "0.0")
        );
        // Named after its centre and the point it goes through, when these are locals (a
        // constant radius needs no point).
        let about = self.derived_name(center, "", "");
        let point = match known {
            None => self.facts.value(through).local(),
            Some(_) => None,
        };
        let n = match (about.is_empty(), point) {
            (false, Some(point)) => format!("circle_{about}_{point}"),
            (false, None) => format!("circle_{about}"),
            (true, _) => "circle".into(),
        };
        self.define(w, r, &n, &code);
        let center = self.facts.value(center).clone();
        self.facts.circle_centers.insert(r, center);
    }

    /// `point`, which must lie on `locus` within the tolerance.
    fn onto(&mut self, w: &mut Writer, r: Reg, locus: Reg, point: Reg, c: ConstraintId) {
        let gap = self.names.fresh("gap");
        let code = format!("{}.residual({})", self.r(locus), self.r(point));
        self.let_read(w, &gap, &code);
        self.cx.reads_tol.set(true);
        w.open(&format!("if {gap}.is_nan() || {gap} > tol {{"));
        w.line(&format!("return Err({});", self.inconsistent(c, &gap)));
        w.close("}");
        let p = self.facts.value(point).clone();
        self.facts.regs.insert(r, p);
    }

    /// `SolveError::new(..)` of constraint `c`, inconsistent by `magnitude`.
    fn inconsistent(&self, c: ConstraintId, magnitude: &str) -> String {
        let con = &self.cx.model.constraints[c];
        format!(
            "SolveError::new({}, {}, ErrorKind::Inconsistent, {magnitude})",
            lit(&con.name),
            lit(&con.text)
        )
    }

    /// The root of `branch` of the intersection of loci `a` and `b`, for constraint `c`.
    fn intersect(
        &mut self,
        w: &mut Writer,
        r: Reg,
        meet: Meet,
        (a, b): (Reg, Reg),
        branch: BranchId,
        c: ConstraintId,
    ) {
        let con = &self.cx.model.constraints[c];
        let (label, text) = (lit(&con.name), lit(&con.text));
        let index = self.branch_index(branch);
        let f = match meet {
            Meet::CircleCircle => return self.circle_circle(w, r, (a, b), (index, branch), c),
            Meet::LineCircle => "line_circle",
            Meet::LineLine => "line_line",
            Meet::CircleConic => "circle_conic",
            Meet::LineConic => "line_conic",
            Meet::ConicConic => "conic_conic",
            spatial => panic!(
                "bug in gcs: the spatial intersection {spatial:?} reached the planar code generator"
            ),
        };
        let meeting = self.names.fresh(&format!("{}_meeting", con.name));
        let code = format!("intersect2d::{f}(&{}, &{})", self.r(a), self.r(b));
        self.let_read(w, &meeting, &code);
        w.open(&format!(
            "if let Some(e) = SolveError::from_contact({label}, {text}, {meeting}.contact) {{"
        ));
        w.line("return Err(e);");
        w.close("}");
        let code = format!(
            "{meeting}.branch({index}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, {meeting}.roots.len() as f64))?"
        );
        self.fork(w, branch);
        self.define(w, r, &con.name, &code);
    }

    /// The root index branch variable `branch` selects: its field of `Branches`, or 0 for a
    /// variable with one root.
    pub(super) fn branch_index(&self, branch: BranchId) -> String {
        match self.cx.branches.get(branch.0 as usize) {
            Some(field) if self.cx.plan.branches[branch.0 as usize].count > 1 => {
                let field = super::lift::branch(branch.0 as usize, field);
                format!("usize::from({field})")
            }
            _ => "0".into(),
        }
    }

    /// The direction of line (`base`, `dir`) turned about `pivot` until it passes `point` at
    /// `offset`: the runtime's `passing_directions`, the root of `branch`.
    #[allow(clippy::too_many_arguments)]
    fn passing_dir(
        &mut self,
        w: &mut Writer,
        r: Reg,
        (pivot, base, dir): (Reg, Reg, Reg),
        point: Reg,
        offset: Option<Reg>,
        branch: BranchId,
        c: ConstraintId,
    ) {
        let con = &self.cx.model.constraints[c];
        let (label, text) = (lit(&con.name), lit(&con.text));
        let index = self.branch_index(branch);
        let (o, b) = (self.r(pivot), self.r(base));
        let mut terms: Vec<String> = offset.map(|d| self.r(d)).into_iter().collect();
        if !(self.facts.value(base)).same(self.facts.value(pivot), self.cx) {
            // The base's offset from the pivot turns with the line.
            terms.push(format!(
                "gcs_runtime::locus2d::cross({}, {b} - {o})",
                self.r(dir)
            ));
        }
        let e = if terms.is_empty() {
            "0.0".to_string()
        } else {
            terms.join(" + ")
        };
        let lines = self.names.fresh(&format!("{}_lines", con.name));
        let code = format!(
            "intersect2d::passing_directions({o}, {}, {e})",
            self.r(point)
        );
        self.let_read(w, &lines, &code);
        w.open(&format!(
            "if let Some(e) = SolveError::from_contact({label}, {text}, {lines}.contact) {{"
        ));
        w.line("return Err(e);");
        w.close("}");
        let code = format!(
            "{lines}.branch({index}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, {lines}.roots.len() as f64))?"
        );
        self.fork(w, branch);
        self.facts.unit_dirs.insert(r);
        self.define(w, r, &format!("{}_dir", con.name), &code);
    }

    /// The root at `index` of two circles `a` and `b`, for constraint `c`: only that root is
    /// computed. When a rotation turns a point onto it, the chord is kept, so that the
    /// rotation reads the root from its centre, to the last bits.
    fn circle_circle(
        &mut self,
        w: &mut Writer,
        r: Reg,
        (a, b): (Reg, Reg),
        (index, branch): (String, BranchId),
        c: ConstraintId,
    ) {
        let con = &self.cx.model.constraints[c];
        let (label, text) = (lit(&con.name), lit(&con.text));
        let chord = format!(
            "intersect2d::circle_circle_chord(&{}, &{}).map_err(|miss| SolveError::from_miss({label}, {text}, miss))?",
            self.r(a),
            self.r(b),
        );
        let root = format!(
            ".root({index}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, 2.0))?"
        );
        // In `solve_all`'s tree the chord is found once, before the loop over its roots.
        let forks = self.forking.is_some();
        if !self.cx.rotated_onto.contains(&r) && !forks {
            self.define(w, r, &con.name, &format!("{chord}{root}"));
            return;
        }
        let local = self.names.fresh(&format!("{}_chord", con.name));
        self.let_read(w, &local, &chord);
        self.fork(w, branch);
        self.define(w, r, &con.name, &format!("{local}{root}"));
        if !self.cx.rotated_onto.contains(&r) {
            return;
        }
        let center = |c: Reg| self.facts.circle_centers.get(&c).cloned();
        let kept = ChordRoot {
            chord: local,
            index,
            centers: [center(a), center(b)],
        };
        self.facts.chord_roots.insert(r, kept);
    }

    /// Translates `geoms` so that point `from` lands on `to`: nothing when they are one value,
    /// the origin placed when it is the point moved, else a shift.
    pub(super) fn translate(&mut self, w: &mut Writer, geoms: &[GeomId], from: Reg, to: Reg) {
        let (from, to) = (self.facts.value(from).clone(), self.facts.value(to).clone());
        if from.same(&to, self.cx) {
            // From a point onto itself: nothing moves.
            return;
        }
        let (f, t) = (from.code(), to.code());
        let mut shift: Option<String> = None;
        for &g in geoms {
            let frame = self.frame_local(g);
            let facts = self.facts.frames.entry(g).or_default();
            let at_origin = (facts.origin.as_ref()).is_some_and(|o| o.same(&from, self.cx));
            if at_origin {
                // The point brought onto `to` is the origin: it lands there exactly.
                facts.origin = Some(to.clone());
                self.note(&to);
                w.line(&format!("{frame}.place_origin(&{t});"));
            } else {
                facts.origin = None;
                let shift = match &shift {
                    Some(name) => name.clone(),
                    None => {
                        let name = self.names.fresh("shift");
                        self.note(&to);
                        self.note(&from);
                        self.let_read(w, &name, &format!("{t} - {f}"));
                        shift.insert(name).clone()
                    }
                };
                w.line(&format!("{frame}.translate(&{shift});"));
            }
            self.frame_writes.insert(g);
        }
    }

    /// Rotates `geoms` about `pivot` so that point `from` lands on `to`.
    pub(super) fn rotate_point(
        &mut self,
        w: &mut Writer,
        geoms: &[GeomId],
        pivot: Reg,
        from: Reg,
        to: Reg,
    ) {
        let (p, f, t) = (self.r(pivot), self.r(from), self.r(to));
        // From the pivot to the target: read from the chord when the target is a root of a
        // circle about the pivot (the same vector, without the cancellation of a difference of
        // points far from the origin).
        let pivot_value = self.facts.value(pivot);
        let from_chord = self.facts.chord_roots.get(&to).and_then(|root| {
            let side = root
                .centers
                .iter()
                .position(|c| c.as_ref().is_some_and(|c| c.same(pivot_value, self.cx)))?;
            let f = ["root_from_a", "root_from_b"][side];
            self.note_read(&root.chord);
            Some(format!(
                "{}.{f}({}).unwrap_or({t} - {p})",
                root.chord, root.index
            ))
        });
        let to_target = match &from_chord {
            Some(code) => format!("&{code}"),
            None => format!("&({t} - {p})"),
        };
        let radius = self.facts.circle_radius.get(&(pivot, from)).copied();
        let code = match (radius, self.constant_arm(pivot, from)) {
            // A point of a rigid geom turned onto its circle about the pivot, from where the
            // sketch put it: the arm and the circle's radius are constants, so the rotation's
            // cosine and sine are `(arm . reach, arm x reach) / radius²` with constant
            // coefficients.
            (Some(radius), Some((ax, ay))) if radius > 0.0 => {
                let reach = self.names.fresh(&self.derived_name(to, "_reach", "reach"));
                let code = from_chord.unwrap_or_else(|| format!("{t} - {p}"));
                self.let_read(w, &reach, &code);
                let k = 1.0 / (radius * radius);
                let (kx, ky) = (ax * k, ay * k);
                let c = linear(&[(kx, format!("{reach}.x")), (ky, format!("{reach}.y"))]);
                let s = linear(&[(kx, format!("{reach}.y")), (-ky, format!("{reach}.x"))]);
                // The arm itself is read only when the lengths disagree with the radius, off
                // the fast path.
                format!("rotation_on_circle_from({c}, {s}, &({f} - {p}), &{reach})")
            }
            // A point of a rigid geom turned onto its circle about the pivot: the circle's
            // radius is known, and with it the rotation's scale.
            (Some(radius), _) => format!(
                "rotation_on_circle(&({f} - {p}), {to_target}, {})",
                float(radius)
            ),
            (None, _) => format!("rotation_between2(&({f} - {p}), {to_target})"),
        };
        self.rotate(w, geoms, pivot, &code);
    }

    /// Rotates `geoms` about `pivot` so that direction `from` turns onto `to`.
    pub(super) fn rotate_dir(
        &mut self,
        w: &mut Writer,
        geoms: &[GeomId],
        pivot: Reg,
        from: Reg,
        to: Reg,
    ) {
        let (f, t) = (self.r(from), self.r(to));
        let from_x = self.facts.value(from).is_x_axis();
        let code = if from_x && self.facts.unit_dirs.contains(&to) {
            // A finite unit direction: it is the rotation, with nothing to test.
            format!("rotation_from_x_unit(&{t})")
        } else if from_x {
            format!("rotation_from_x(&{t})")
        } else {
            format!("rotation_between_units(&{f}, &{t})")
        };
        self.rotate(w, geoms, pivot, &code);
    }

    /// Rotates `geoms` about `pivot` by the rotation `code` computes: the frame's rotation
    /// set outright while it is the identity, and its origin left alone when it is the pivot.
    fn rotate(&mut self, w: &mut Writer, geoms: &[GeomId], pivot: Reg, code: &str) {
        let pivot = self.facts.value(pivot).clone();
        let turn = self.names.fresh("turn");
        self.let_read(w, &turn, code);
        for &g in geoms {
            let frame = self.frame_local(g);
            let facts = self.facts.frames.entry(g).or_default();
            let about_origin = facts
                .origin
                .as_ref()
                .is_some_and(|o| o.same(&pivot, self.cx));
            let identity = facts.identity;
            if !about_origin {
                facts.origin = None;
            }
            facts.identity = false;
            match (about_origin, identity) {
                (true, true) => w.line(&format!("{frame}.set_rotation(&{turn});")),
                (true, false) => w.line(&format!("{frame}.turn_by(&{turn});")),
                (false, _) => {
                    let pivot = self.code(&pivot);
                    w.line(&format!("{frame}.rotate_about_by(&{pivot}, &{turn});"));
                }
            }
            self.frame_writes.insert(g);
        }
    }

    /// Sets geom `g`'s dimension to register `value`, tested first unless it is known to be
    /// finite and non-negative; declared here when nothing read it before.
    fn set_dim(&mut self, w: &mut Writer, i: usize, g: GeomId, value: Reg) {
        let mut v = self.r(value);
        let known_good = self.facts.known_sizes.contains(&value)
            || matches!(self.facts.value(value), Value::Scalar(x) if x.is_finite() && *x >= 0.0);
        let closing = (!known_good)
            .then(|| self.cx.plan.closing_length(i))
            .flatten();
        if let Some(c) = closing {
            // A length a linear stage solves for: negative, the profile cannot close.
            if !self.facts.is_finite(value) {
                let error = self.cx.error(i, "InvalidValue", &v);
                w.open(&format!("if !gcs_runtime::num::is_finite({v}) {{"));
                w.line(&format!("return Err({error});"));
                w.close("}");
            }
            // Within rounding of zero, it is zero (as the interpreter takes it).
            let error = self.cx.error_of(c, "CannotClose", &v);
            self.cx.reads_tol.set(true);
            w.open(&format!("if {v} < -tol {{"));
            w.line(&format!("return Err({error});"));
            w.close("}");
            v = format!("{v}.max(0.0)");
        } else if !known_good {
            let test = if self.facts.is_finite(value) {
                format!("if {v} < 0.0 {{")
            } else {
                format!("if !gcs_runtime::num::is_finite({v}) || {v} < 0.0 {{")
            };
            // A size given as a default is the default's fault, not the constraint's.
            let error = match self.facts.value(value) {
                Value::Default(k, _) => {
                    let d = &self.cx.plan.defaults[*k];
                    self.cx
                        .error_with(&d.name, &d.meaning, "InvalidDefault", &v)
                }
                _ => self.cx.error(i, "InvalidValue", &v),
            };
            w.open(&test);
            w.line(&format!("return Err({error});"));
            w.close("}");
        }
        let d = self.dim_local(g);
        // Inside an iteration's trial, a binding of its own: the trial works on a copy.
        // So too in a fork of `solve_all`'s tree: each root sets its own.
        if self.deferred.remove(&g) || self.closing.is_some() || self.in_fork() {
            self.let_line(w, &d, &d, &v);
        } else {
            self.dims_assigned.insert(g);
            self.note_read(&d);
            w.line(&format!("{d} = {v};"));
        }
    }

    /// A run-time check of a relation of constraint `c`: its residual within the tolerance.
    fn check(&mut self, w: &mut Writer, c: ConstraintId, residual: &Residual) {
        let residual = self.cx.space.residual_code(self, residual);
        let name = self.names.fresh("residual");
        self.let_read(w, &name, &residual);
        self.cx.reads_tol.set(true);
        w.open(&format!("if {name}.is_nan() || {name} > tol {{"));
        w.line(&format!("return Err({});", self.inconsistent(c, &name)));
        w.close("}");
    }

    /// An error function of an iteration: with the defaults given, constraint `c` must close.
    fn close(&mut self, w: &mut Writer, c: ConstraintId, residual: Reg) {
        if self.closing.is_some() {
            // Inside an iteration's trial: an error function it drives to zero.
            let value = self.r(residual);
            if let Some((errors, k)) = self.closing.as_mut() {
                w.line(&format!("{errors}[{k}] = {value};"));
                *k += 1;
            }
            return;
        }
        if self.converged {
            // Converged: the iteration met the tolerance.
            return;
        }
        let name = self.names.fresh("closing");
        self.let_read(w, &name, &format!("{}.abs()", self.r(residual)));
        self.cx.reads_tol.set(true);
        w.open(&format!("if {name}.is_nan() || {name} > tol {{"));
        let con = &self.cx.model.constraints[c];
        w.line(&format!(
            "return Err(SolveError::new({}, {}, ErrorKind::NoConvergence, {name}));",
            lit(&con.name),
            lit(&con.text)
        ));
        w.close("}");
    }
}

/// The `Sense` of a circle's radius in a locus of centres.
fn sense(plus: bool) -> &'static str {
    if plus {
        "Plus"
    } else {
        "Minus"
    }
}

/// What a size constraint's value is, for comments: `a distance`, `a length`, `a radius`.
fn size_noun(model: &gcs_lang::Model, c: ConstraintId) -> &'static str {
    match model.constraints[c].kind {
        gcs_lang::constraints::ConstraintKind::Length => "a length",
        gcs_lang::constraints::ConstraintKind::Radius => "a radius",
        _ => "a distance",
    }
}
