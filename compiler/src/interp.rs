//! The interpreter: runs a [`Plan`] on a model's sketch with given params and branches.
//!
//! It is the reference the generated solvers are compared with, and what `gcs solve` uses.
//! Every failure is a [`SolveError`] naming the user's constraint: a locus intersection that
//! does not exist (with the gap), a check that does not hold (with the residual), a degenerate
//! configuration, or a non-finite param.

use crate::config::{Config, P2, V2};
use crate::plan::{Meet, Op, Plan};
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::model::{ConstraintId, GeomKind, Part};
use gcs_lang::Model;
use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::locus2d::{self, Circle, Conic, Line, Sense};
use gcs_runtime::{check, intersect2d};
use gcs_runtime::{Contact, Roots};
use nalgebra::UnitComplex;

/// How to choose the root of each intersection.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Choice {
    /// The index given for each branch variable (by [`crate::plan::BranchId`] order).
    Given(Vec<usize>),
    /// The root nearest to the moving feature's position before the move (used once, on the
    /// sketch, to find each branch's default).
    Nearest,
}

/// A finished run.
#[derive(Clone, Debug)]
pub struct Run {
    /// The configuration reached.
    pub config: Config,
    /// The index taken at each branch variable, if its intersection ran.
    pub chosen: Vec<Option<usize>>,
}

#[derive(Clone, Copy, Debug)]
enum Val {
    S(f64),
    P(P2),
    V(V2),
    L(Line),
    C(Circle),
    Q(Conic),
}

fn err(model: &Model, c: ConstraintId, kind: ErrorKind, magnitude: f64) -> SolveError {
    let con = &model.constraints[c];
    SolveError::new(con.name.clone(), con.text.clone(), kind, magnitude)
}

/// Runs `plan` with `params` (indexed like the model's params).
pub fn run(model: &Model, plan: &Plan, params: &[f64], choice: &Choice) -> Result<Run, SolveError> {
    for ((_, p), v) in model.params.iter().zip(params) {
        if !v.is_finite() {
            return Err(SolveError::new(
                p.name.clone(),
                String::new(),
                ErrorKind::InvalidInput,
                *v,
            ));
        }
    }
    let mut config = Config::from_sketch(model, params).map_err(|b| {
        SolveError::new(
            model.geoms[b.geom].name.clone(),
            b.what,
            ErrorKind::InvalidInput,
            f64::NAN,
        )
    })?;
    let scale = config_scale(&config, &plan.touched(model));
    let tol = gcs_runtime::tol::CHECK_REL * (1.0 + scale);
    let mut regs: Vec<Val> = vec![Val::S(0.0); plan.regs as usize];
    let mut chosen = vec![None; plan.branches.len()];
    let get = |regs: &[Val], r: crate::plan::Reg| {
        regs.get(r.0 as usize).copied().unwrap_or(Val::S(f64::NAN))
    };
    for step in &plan.steps {
        let s = |r| match get(&regs, r) {
            Val::S(x) => x,
            _ => f64::NAN,
        };
        let p = |r| match get(&regs, r) {
            Val::P(x) => x,
            _ => P2::new(f64::NAN, f64::NAN),
        };
        let v = |r| match get(&regs, r) {
            Val::V(x) => x,
            _ => V2::new(f64::NAN, f64::NAN),
        };
        let out: Option<Val> = match &step.op {
            // A value the params give, finite one by one, can still overflow (`theta * 1e300`):
            // the constraint it belongs to cannot be met, rather than met by garbage.
            Op::Expr(e) => Some(Val::S(finite_value(
                model,
                plan,
                step,
                model.exprs.eval(*e, params),
            )?)),
            Op::Const(c) => Some(Val::S(*c)),
            Op::Neg(x) => Some(Val::S(-s(*x))),
            Op::DimOf(g) => Some(Val::S(config.dim(*g))),
            Op::Along { from, dir, to } => Some(Val::S((p(*to) - p(*from)).dot(&v(*dir)))),
            Op::DirectionTo { from, to } => {
                let d = p(*to) - p(*from);
                let n = d.norm();
                if n.is_nan() || n <= 0.0 {
                    return Err(bad_step(model, plan, step));
                }
                Some(Val::V(d / n))
            }
            Op::Sum(terms) => Some(Val::S(finite_value(
                model,
                plan,
                step,
                terms.iter().map(|(k, r)| k * s(*r)).sum(),
            )?)),
            Op::Reversed(x) => match get(&regs, *x) {
                Val::L(l) => Some(Val::L(l.reversed())),
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::OffsetLine { line, by } => match get(&regs, *line) {
                Val::L(l) => Some(Val::L(l.offset(s(*by)))),
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::CentresLineLine { l1, a1, l2, a2 } => match (get(&regs, *l1), get(&regs, *l2)) {
                (Val::L(x), Val::L(y)) => {
                    let l = locus2d::centres_line_line(&x, s(*a1), &y, s(*a2))
                        .ok_or_else(|| bad_step(model, plan, step))?;
                    Some(Val::L(l))
                }
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => match get(&regs, *line) {
                Val::L(l) => {
                    let q = locus2d::centres_line_circle(&l, s(*a), p(*at), sense(*plus), s(*b))
                        .ok_or_else(|| bad_step(model, plan, step))?;
                    Some(Val::Q(Conic::Parabola(q)))
                }
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => {
                let q = locus2d::centres_circle_circle(
                    p(*c1),
                    sense(*p1),
                    s(*b1),
                    p(*c2),
                    sense(*p2),
                    s(*b2),
                )
                .ok_or_else(|| bad_step(model, plan, step))?;
                Some(Val::Q(q))
            }
            Op::RadiusFromLine { line, a, centre } => match get(&regs, *line) {
                Val::L(l) => Some(Val::S(l.signed_distance(p(*centre)) - s(*a))),
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => {
                let d = (p(*centre) - p(*at)).norm();
                Some(Val::S(if *plus { d - s(*b) } else { s(*b) - d }))
            }
            Op::PointOf(g) => Some(Val::P(config.point(model, *g))),
            Op::DirOf(g) => Some(Val::V(config.dir(model, *g))),
            Op::Axis(x, y) => Some(Val::V(V2::new(*x, *y))),
            Op::Rotated { dir, angle } => Some(Val::V(UnitComplex::new(s(*angle)) * v(*dir))),
            Op::Circle { center, radius } => {
                let rr = s(*radius);
                if rr < 0.0 {
                    // A locus circle of negative radius: the distance cannot be met.
                    return Err(match constraint_of(plan, step) {
                        Some(c) => err(model, c, ErrorKind::NoIntersection, -rr),
                        None => bad_step(model, plan, step),
                    });
                }
                let c = Circle::new(p(*center), rr).ok_or_else(|| bad_step(model, plan, step))?;
                Some(Val::C(c))
            }
            Op::CircleThrough {
                center,
                through,
                rigid,
            } => {
                let c = p(*center);
                let known = rigid.and_then(|(a, b)| crate::plan::constant_distance(model, a, b));
                let circle = Circle::new(c, known.unwrap_or_else(|| (p(*through) - c).norm()))
                    .ok_or_else(|| bad_step(model, plan, step))?;
                Some(Val::C(circle))
            }
            Op::Line { point, dir, offset } => {
                let l = Line::new(p(*point), v(*dir)).ok_or_else(|| bad_step(model, plan, step))?;
                Some(Val::L(match offset {
                    Some(o) => l.offset(s(*o)),
                    None => l,
                }))
            }
            Op::ParallelLine { line, through } => match get(&regs, *line) {
                Val::L(l) => Some(Val::L(
                    Line::new(p(*through), l.dir()).ok_or_else(|| bad_step(model, plan, step))?,
                )),
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::ShiftedCircle { circle, from, to } => match get(&regs, *circle) {
                Val::C(c) => {
                    let moved = Circle::new(c.center() + (p(*to) - p(*from)), c.radius());
                    Some(Val::C(moved.ok_or_else(|| bad_step(model, plan, step))?))
                }
                _ => return Err(bad_step(model, plan, step)),
            },
            Op::Nearest { locus, point } => {
                let q = p(*point);
                Some(Val::P(match get(&regs, *locus) {
                    Val::L(l) => l.nearest(q),
                    Val::C(c) => c.nearest(q),
                    _ => return Err(bad_step(model, plan, step)),
                }))
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                let q = p(*point);
                let gap = match get(&regs, *locus) {
                    Val::L(l) => l.residual(q),
                    Val::C(c) => c.residual(q),
                    Val::Q(k) => k.residual(q),
                    _ => f64::NAN,
                };
                if gap.is_nan() || gap > tol {
                    return Err(err(model, *constraint, ErrorKind::Inconsistent, gap));
                }
                Some(Val::P(q))
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            } => {
                let (roots, contact): (Roots<P2, 4>, Contact) =
                    match (meet, get(&regs, *a), get(&regs, *b)) {
                        (Meet::CircleCircle, Val::C(x), Val::C(y)) => {
                            let i = intersect2d::circle_circle(&x, &y);
                            (Roots::from_slice(i.roots.as_slice()), i.contact)
                        }
                        (Meet::LineCircle, Val::L(x), Val::C(y)) => {
                            let i = intersect2d::line_circle(&x, &y);
                            (Roots::from_slice(i.roots.as_slice()), i.contact)
                        }
                        (Meet::CircleConic, Val::C(x), Val::Q(y)) => {
                            let i = intersect2d::circle_conic(&x, &y);
                            (i.roots, i.contact)
                        }
                        (Meet::LineConic, Val::L(x), Val::Q(y)) => {
                            let i = intersect2d::line_conic(&x, &y);
                            (Roots::from_slice(i.roots.as_slice()), i.contact)
                        }
                        (Meet::LineLine, Val::L(x), Val::L(y)) => {
                            let i = intersect2d::line_line(&x, &y);
                            (Roots::from_slice(i.roots.as_slice()), i.contact)
                        }
                        _ => return Err(bad_step(model, plan, step)),
                    };
                match contact {
                    Contact::Crossing | Contact::Tangent => {}
                    Contact::Disjoint { gap } | Contact::Parallel { gap } => {
                        return Err(err(model, *constraint, ErrorKind::NoIntersection, gap));
                    }
                    Contact::Coincident | Contact::ZeroRadius => {
                        return Err(err(model, *constraint, ErrorKind::Degenerate, 0.0));
                    }
                }
                let index = match choice {
                    Choice::Given(b) => b.get(branch.0 as usize).copied().unwrap_or(0),
                    Choice::Nearest => {
                        let n = p(*near);
                        roots.nearest_to(n, |x, y| (x - y).norm()).unwrap_or(0)
                    }
                };
                if let Some(slot) = chosen.get_mut(branch.0 as usize) {
                    *slot = Some(index);
                }
                match roots.get(index) {
                    Some(x) => Some(Val::P(x)),
                    None => {
                        // The chosen branch has no root here: say so, never take another.
                        return Err(err(
                            model,
                            *constraint,
                            ErrorKind::NoSuchBranch,
                            roots.len() as f64,
                        ));
                    }
                }
            }
            Op::Translate { geoms, from, to } => {
                let d = p(*to) - p(*from);
                for g in geoms {
                    config.translate(*g, d);
                }
                None
            }
            Op::RotatePoint {
                geoms,
                pivot,
                from,
                to,
            } => {
                let c = p(*pivot);
                let rot = gcs_runtime::frame::rotation_between2(&(p(*from) - c), &(p(*to) - c));
                for g in geoms {
                    config.rotate(*g, c, rot);
                }
                None
            }
            Op::RotateDir {
                geoms,
                pivot,
                from,
                to,
            } => {
                let c = p(*pivot);
                let rot = gcs_runtime::frame::rotation_between_units(&v(*from), &v(*to));
                for g in geoms {
                    config.rotate(*g, c, rot);
                }
                None
            }
            Op::SetDim { geom, value } => {
                let x = s(*value);
                if !x.is_finite() || x < 0.0 {
                    return Err(step_error(model, plan, step, ErrorKind::InvalidValue, x));
                }
                config.dims.insert(*geom, x);
                None
            }
            Op::Check { constraint } => {
                let r = residual(model, &config, *constraint, params);
                if r.is_nan() || r > tol {
                    return Err(err(model, *constraint, ErrorKind::Inconsistent, r));
                }
                None
            }
        };
        if let (Some(val), Some((r, _))) = (out, step.out) {
            if let Some(slot) = regs.get_mut(r.0 as usize) {
                *slot = val;
            }
        }
    }
    Ok(Run { config, chosen })
}

fn sense(plus: bool) -> Sense {
    if plus {
        Sense::Plus
    } else {
        Sense::Minus
    }
}

/// The constraint a step works for (see [`Plan::constraint_of`]).
fn constraint_of(plan: &Plan, step: &crate::plan::Step) -> Option<ConstraintId> {
    let i = plan.steps.iter().position(|s| std::ptr::eq(s, step))?;
    plan.constraint_of(i)
}

/// `x` when it is finite, otherwise the [`ErrorKind::InvalidValue`] error of the step's
/// constraint.
fn finite_value(
    model: &Model,
    plan: &Plan,
    step: &crate::plan::Step,
    x: f64,
) -> Result<f64, SolveError> {
    if x.is_finite() {
        return Ok(x);
    }
    Err(step_error(model, plan, step, ErrorKind::InvalidValue, x))
}

/// The error of the step's constraint, or of the plan when the step has none.
fn step_error(
    model: &Model,
    plan: &Plan,
    step: &crate::plan::Step,
    kind: ErrorKind,
    magnitude: f64,
) -> SolveError {
    match constraint_of(plan, step) {
        Some(c) => err(model, c, kind, magnitude),
        None => SolveError::new("plan", String::new(), kind, magnitude),
    }
}

fn bad_step(model: &Model, plan: &Plan, step: &crate::plan::Step) -> SolveError {
    step_error(model, plan, step, ErrorKind::Degenerate, 0.0)
}

/// The largest coordinate or dimension of the given geoms in a configuration: what tolerances
/// scale with.
pub fn config_scale(
    config: &Config,
    geoms: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
) -> f64 {
    let mut s: f64 = 0.0;
    for (g, f) in &config.frames {
        if geoms.contains(g) {
            s = s.max(f.origin.x.abs()).max(f.origin.y.abs());
        }
    }
    for (g, d) in &config.dims {
        if geoms.contains(g) {
            s = s.max(d.abs());
        }
    }
    s
}

/// The residual of a constraint on a configuration, for run-time checks of implied
/// constraints: every constraint of the 2d language, measured through the configuration. (The
/// independent verifier is [`crate::verify`], which shares none of this.)
fn residual(model: &Model, cfg: &Config, c: ConstraintId, params: &[f64]) -> f64 {
    use gcs_lang::model::GeomId;
    let con = &model.constraints[c];
    let value = con.value.map_or(0.0, |e| model.exprs.eval(e, params));
    let a = con.args.first().copied();
    let b = con.args.get(1).copied();
    let kind = |g: GeomId| model.geoms[g].kind;
    let pt = |g| cfg.point(model, center_of(model, g));
    let dir = |g| cfg.dir(model, dir_of(model, g));
    let part = |g, p| model.part(g, p).unwrap_or(g);
    // A line-like argument: a point on it and its direction (a marker: its x axis).
    let line = |g: GeomId| match kind(g) {
        GeomKind::Segment => (cfg.point(model, part(g, Part::Start)), dir(g)),
        GeomKind::Marker => (cfg.point(model, g), cfg.dir(model, part(g, Part::AxisX))),
        _ => (cfg.point(model, g), dir(g)),
    };
    let radius = |g| cfg.dim(g);
    let sd = |(p, d): (P2, V2), q: P2| check::signed_distance(p, d, q);
    let circles =
        |x: GeomId, y: GeomId, gap: f64| check::circles(pt(x), radius(x), pt(y), radius(y), gap);
    match (con.kind, a, b) {
        (K::Coincident | K::Spherical | K::Revolute, Some(a), Some(b)) => (pt(a) - pt(b)).norm(),
        (K::Distance, Some(a), Some(b)) => match (kind(a), kind(b)) {
            (GeomKind::Line | GeomKind::Segment, GeomKind::Circle) => {
                (sd(line(a), pt(b)).abs() - radius(b) - value).abs()
            }
            (GeomKind::Circle, GeomKind::Circle) => circles(a, b, value),
            (_, GeomKind::Line | GeomKind::Segment) => (sd(line(b), pt(a)) - value).abs(),
            (_, GeomKind::Circle) => (((pt(a) - pt(b)).norm() - radius(b)).abs() - value).abs(),
            _ => ((pt(a) - pt(b)).norm() - value.abs()).abs(),
        },
        (K::On, Some(a), Some(b)) => match kind(b) {
            GeomKind::Circle => ((pt(a) - pt(b)).norm() - radius(b)).abs(),
            _ => sd(line(b), pt(a)).abs(),
        },
        (K::Tangent, Some(a), Some(b)) => match kind(a) {
            GeomKind::Circle => circles(a, b, 0.0),
            _ => (sd(line(a), pt(b)).abs() - radius(b)).abs(),
        },
        (K::Angle, Some(a), Some(b)) => check::angle_gap(check::angle(dir(a), dir(b)), value),
        (K::Horizontal, Some(a), _) => dir(a).y.abs(),
        (K::Vertical, Some(a), _) => dir(a).x.abs(),
        (K::Parallel, Some(a), Some(b)) => cross(dir(a), dir(b)).abs(),
        (K::Perpendicular, Some(a), Some(b)) => dir(a).dot(&dir(b)).abs(),
        (K::Length | K::Radius, Some(a), _) => (cfg.dim(a) - value).abs(),
        (K::InLine, Some(a), Some(b)) => sd(line(b), pt(a)).abs(),
        (K::OffsetX | K::Prismatic, Some(a), Some(b)) => {
            let (u, v) = (line(a).1, line(b).1);
            let target = if con.kind == K::OffsetX { value } else { 0.0 };
            let turn = check::angle_gap(check::angle(u, v), target);
            if con.kind == K::Prismatic {
                turn.max(sd(line(b), pt(a)).abs())
            } else {
                turn
            }
        }
        // Every 2d constraint is above; anything else cannot be checked, so it fails.
        _ => f64::INFINITY,
    }
}

fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

fn center_of(model: &Model, g: gcs_lang::model::GeomId) -> gcs_lang::model::GeomId {
    if model.geoms[g].kind == GeomKind::Circle {
        model.part(g, Part::Center).unwrap_or(g)
    } else {
        g
    }
}

fn dir_of(model: &Model, g: gcs_lang::model::GeomId) -> gcs_lang::model::GeomId {
    match model.geoms[g].kind {
        GeomKind::Line | GeomKind::Segment => model.part(g, Part::Dir).unwrap_or(g),
        _ => g,
    }
}
