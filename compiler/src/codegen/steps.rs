//! Each step of the plan as code: a measurement, locus, intersection, action or check lowered to
//! the runtime's calls, with what is known at that step (see `facts`) deciding the cheapest
//! code that gives the same value.

use super::facts::{is_ident, ChordRoot, Origin};
use super::names::Namer;
use super::solve::Solve;
use super::writer::{float, linear, lit, Writer};
use crate::plan::{Meet, Op, Reg};
use gcs_lang::expr::ExprNode;
use gcs_lang::model::GeomId;

impl Solve<'_> {
    fn define(&mut self, w: &mut Writer, reg: Reg, name: &str, code: &str) {
        if !self.cx.used.contains(&reg) {
            return;
        }
        let local = self.names.fresh(name);
        w.line(&format!("let {local} = {code};"));
        self.facts.regs.insert(reg, local);
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
        if !self.cx.used.contains(&reg) {
            return;
        }
        let v = self.r(reg);
        w.open(&format!("if !gcs_runtime::num::is_finite({v}) {{"));
        w.line(&format!(
            "return Err({});",
            self.cx.error(i, "InvalidValue", &v)
        ));
        w.close("}");
        self.facts.finite.insert(reg);
    }

    /// Like [`Solve::define`], but a literal or a local needs no new local: the register is
    /// that code.
    pub(super) fn define_or_alias(&mut self, w: &mut Writer, reg: Reg, name: &str, code: String) {
        let literal = (code.starts_with("Point2::new(") || code.starts_with("Vector2::new("))
            && code.matches('(').count() == 1
            && !code.contains("params.");
        if is_ident(&code) || literal {
            if literal {
                self.facts.reg_names.insert(reg, Namer::snake(name));
            }
            self.facts.regs.insert(reg, code);
        } else {
            self.define(w, reg, name, &code);
        }
    }

    /// A name derived from register `r`: `{name}{suffix}` after its local or what it names,
    /// else `fallback`.
    pub(super) fn derived_name(&self, r: Reg, suffix: &str, fallback: &str) -> String {
        let code = self.r(r);
        match self.facts.reg_names.get(&r) {
            Some(name) => format!("{name}{suffix}"),
            None if is_ident(&code) => format!("{code}{suffix}"),
            None => fallback.to_string(),
        }
    }

    /// `{prefix}_{name}` after register `r` (see [`Solve::derived_name`]), or just `prefix`.
    pub(super) fn prefixed(&self, prefix: &str, r: Reg) -> String {
        let n = self.derived_name(r, "", "");
        if n.is_empty() {
            prefix.to_string()
        } else {
            format!("{prefix}_{n}")
        }
    }

    /// Rotates `geoms` about `pivot` by the rotation `code` computes: the frame's rotation
    /// set outright while it is the identity, and its origin left alone when it is the pivot.
    pub(super) fn rotate(&mut self, w: &mut Writer, geoms: &[GeomId], pivot: &str, code: &str) {
        let turn = self.names.fresh("turn");
        w.line(&format!("let {turn} = {code};"));
        for &g in geoms {
            let frame = self.frames.get(&g).cloned().unwrap_or_default();
            let facts = self.facts.frames.entry(g).or_default();
            let about_origin = facts.origin.as_ref().is_some_and(|o| o.code() == pivot);
            match (about_origin, facts.identity) {
                (true, true) => w.line(&format!("{frame}.set_rotation(&{turn});")),
                (true, false) => w.line(&format!("{frame}.turn_by(&{turn});")),
                (false, _) => {
                    facts.origin = None;
                    w.line(&format!("{frame}.rotate_about_by(&{pivot}, &{turn});"));
                }
            }
            facts.identity = false;
            self.frame_writes.insert(g);
        }
    }

    pub(super) fn step(&mut self, w: &mut Writer, i: usize, step: &crate::plan::Step) {
        let m = self.cx.model;
        let out = step.out.map(|o| o.0);
        let name_of = |g: GeomId| m.geoms[g].name.clone();
        match &step.op {
            Op::Expr(e) => {
                let code = self.cx.expr(*e);
                if let (Some(r), ExprNode::Param(_)) = (out, m.exprs.node(*e)) {
                    // Params are checked finite on entry.
                    self.facts.finite.insert(r);
                    self.facts.regs.insert(r, code);
                } else if let Some(r) = out {
                    if m.exprs.is_constant(*e) {
                        if m.exprs.eval(*e, &[]).is_finite() {
                            self.facts.finite.insert(r);
                        }
                        self.facts.regs.insert(r, code);
                    } else {
                        self.define_finite(w, i, r, "value", &code);
                    }
                }
            }
            Op::Const(c) => {
                if let Some(r) = out {
                    if c.is_finite() {
                        self.facts.finite.insert(r);
                    }
                    self.facts.regs.insert(r, float(*c));
                }
            }
            Op::Neg(x) => {
                if let Some(r) = out {
                    if self.facts.finite.contains(x) {
                        self.facts.finite.insert(r);
                    }
                    let code = format!("-{}", self.r(*x));
                    self.define(w, r, "minus", &code);
                }
            }
            Op::PointOf(g) => {
                if let Some(r) = out {
                    if let Some(at) = self.offset_from_origin(*g) {
                        self.facts.at_offset.insert(r, at);
                    }
                    let code = self.point_code(*g);
                    self.define_or_alias(w, r, &name_of(*g), code);
                }
            }
            Op::DirOf(g) => {
                if let Some(r) = out {
                    let code = self.dir_code(*g);
                    if code == "Vector2::new(1.0, 0.0)" {
                        self.facts.unit_x.insert(r);
                    }
                    let n = name_of(*g);
                    let n = if n.ends_with(".dir") {
                        n
                    } else {
                        format!("{n}_dir")
                    };
                    self.define_or_alias(w, r, &n, code);
                }
            }
            Op::DimOf(g) => {
                if let Some(r) = out {
                    let d = self.dims.get(g).cloned().unwrap_or_default();
                    self.facts.regs.insert(r, d);
                }
            }
            Op::Axis(x, y) => {
                if let Some(r) = out {
                    if (*x, *y) == (1.0, 0.0) {
                        self.facts.unit_x.insert(r);
                    }
                    let code = format!("Vector2::new({}, {})", float(*x), float(*y));
                    self.facts.regs.insert(r, code);
                }
            }
            Op::Rotated { dir, angle } => {
                if let Some(r) = out {
                    let (d, a) = (self.r(*dir), self.r(*angle));
                    let code = if self.facts.unit_x.contains(dir) {
                        if self.facts.finite.contains(angle) {
                            self.facts.unit_dirs.insert(r);
                        }
                        format!("direction_at({a})")
                    } else {
                        format!("UnitComplex::new({a}) * {d}")
                    };
                    let n = self.derived_name(*dir, "_turned", "direction");
                    self.define(w, r, &n, &code);
                }
            }
            Op::Sum(terms) => {
                if let Some(r) = out {
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
                    self.define_finite(w, i, r, "sum", &code);
                }
            }
            Op::Along { from, dir, to } => {
                if let Some(r) = out {
                    let code = format!(
                        "({} - {}).dot(&{})",
                        self.r(*to),
                        self.r(*from),
                        self.r(*dir)
                    );
                    self.define(w, r, "length", &code);
                }
            }
            Op::DirectionTo { from, to } => {
                if let Some(r) = out {
                    let err = self.cx.error(i, "Degenerate", "0.0");
                    let code = format!(
                        "({} - {}).try_normalize(0.0).ok_or_else(|| {err})?",
                        self.r(*to),
                        self.r(*from)
                    );
                    self.define(w, r, "direction", &code);
                }
            }
            Op::Circle { center, radius } => {
                if let Some(r) = out {
                    let rad = self.r(*radius);
                    if !rad.parse::<f64>().is_ok_and(|x| x >= 0.0) {
                        w.open(&format!("if {rad} < 0.0 {{"));
                        w.line(&format!(
                            "return Err({});",
                            self.cx.error(i, "NoIntersection", &format!("-{rad}"))
                        ));
                        w.close("}");
                    }
                    let code = format!(
                        "Circle::new({}, {rad}).ok_or_else(|| {})?",
                        self.r(*center),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    let n = self.prefixed("circle", *center);
                    self.define(w, r, &n, &code);
                    self.facts.circle_centers.insert(r, self.r(*center));
                }
            }
            Op::CircleThrough {
                center,
                through,
                rigid,
            } => {
                if let Some(r) = out {
                    let (c, t) = (self.r(*center), self.r(*through));
                    // Two features of one rigid geom with constant local coordinates: their
                    // distance is known now.
                    let known = rigid.and_then(|(a, b)| crate::plan::constant_distance(m, a, b));
                    if let Some(k) = known {
                        self.facts.circle_radius.insert((*center, *through), k);
                    }
                    let radius = known.map_or_else(|| format!("({t} - {c}).norm()"), float);
                    let code = format!(
                        "Circle::new({c}, {radius}).ok_or_else(|| {})?",
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    // Named after its centre and the point it goes through, when these are
                    // locals (a constant radius needs no point).
                    let about = self.derived_name(*center, "", "");
                    let n = match (about.is_empty(), known.is_none() && is_ident(&t)) {
                        (false, true) => format!("circle_{about}_{t}"),
                        (false, false) => format!("circle_{about}"),
                        (true, _) => "circle".into(),
                    };
                    self.define(w, r, &n, &code);
                    self.facts.circle_centers.insert(r, c);
                }
            }
            Op::Line { point, dir, offset } => {
                if let Some(r) = out {
                    let mut code = format!(
                        "Line::new({}, {}).ok_or_else(|| {})?",
                        self.r(*point),
                        self.r(*dir),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    if let Some(o) = offset {
                        code = format!("{code}.offset({})", self.r(*o));
                    }
                    let n = self.prefixed("line", *point);
                    self.define(w, r, &n, &code);
                }
            }
            Op::ParallelLine { line, through } => {
                if let Some(r) = out {
                    let code = format!(
                        "Line::new({}, {}.dir()).ok_or_else(|| {})?",
                        self.r(*through),
                        self.r(*line),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    let n = self.prefixed("parallel", *through);
                    self.define(w, r, &n, &code);
                }
            }
            Op::ShiftedCircle { circle, from, to } => {
                if let Some(r) = out {
                    let c = self.r(*circle);
                    let code = format!(
                        "Circle::new({c}.center() + ({} - {}), {c}.radius()).ok_or_else(|| {})?",
                        self.r(*to),
                        self.r(*from),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    let n = self.derived_name(*circle, "_moved", "circle_moved");
                    self.define(w, r, &n, &code);
                }
            }
            Op::Reversed(x) => {
                if let Some(r) = out {
                    let code = format!("{}.reversed()", self.r(*x));
                    let n = self.derived_name(*x, "_reversed", "reversed");
                    self.define(w, r, &n, &code);
                }
            }
            Op::OffsetLine { line, by } => {
                if let Some(r) = out {
                    let code = format!("{}.offset({})", self.r(*line), self.r(*by));
                    let n = self.derived_name(*line, "_offset", "offset");
                    self.define(w, r, &n, &code);
                }
            }
            Op::CentresLineLine { l1, a1, l2, a2 } => {
                if let Some(r) = out {
                    let code = format!(
                        "locus2d::centres_line_line(&{}, {}, &{}, {}).ok_or_else(|| {})?",
                        self.r(*l1),
                        self.r(*a1),
                        self.r(*l2),
                        self.r(*a2),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "bisector", &code);
                }
            }
            Op::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => {
                if let Some(r) = out {
                    let code = format!(
                        "Conic::Parabola(locus2d::centres_line_circle(&{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?)",
                        self.r(*line),
                        self.r(*a),
                        self.r(*at),
                        if *plus { "Plus" } else { "Minus" },
                        self.r(*b),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "parabola", &code);
                }
            }
            Op::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => {
                if let Some(r) = out {
                    let code = format!(
                        "locus2d::centres_circle_circle({}, Sense::{}, {}, {}, Sense::{}, {}).ok_or_else(|| {})?",
                        self.r(*c1),
                        if *p1 { "Plus" } else { "Minus" },
                        self.r(*b1),
                        self.r(*c2),
                        if *p2 { "Plus" } else { "Minus" },
                        self.r(*b2),
                        self.cx.error(i, "Degenerate", "0.0")
                    );
                    self.define(w, r, "conic", &code);
                }
            }
            Op::RadiusFromLine { line, a, centre } => {
                if let Some(r) = out {
                    let code = format!(
                        "{}.signed_distance({}) - {}",
                        self.r(*line),
                        self.r(*centre),
                        self.r(*a)
                    );
                    self.define(w, r, "radius", &code);
                }
            }
            Op::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => {
                if let Some(r) = out {
                    let d = format!("({} - {}).norm()", self.r(*centre), self.r(*at));
                    let code = if *plus {
                        format!("{d} - {}", self.r(*b))
                    } else {
                        format!("{} - {d}", self.r(*b))
                    };
                    self.define(w, r, "radius", &code);
                }
            }
            Op::Nearest { locus, point } => {
                if let Some(r) = out {
                    let code = format!("{}.nearest({})", self.r(*locus), self.r(*point));
                    let n = self.prefixed("nearest", *point);
                    self.define(w, r, &n, &code);
                }
            }
            Op::Onto {
                locus,
                point,
                constraint,
            } => {
                if let Some(r) = out {
                    let gap = self.names.fresh("gap");
                    w.line(&format!(
                        "let {gap} = {}.residual({});",
                        self.r(*locus),
                        self.r(*point)
                    ));
                    w.open(&format!("if {gap}.is_nan() || {gap} > tol {{"));
                    let con = &m.constraints[*constraint];
                    w.line(&format!(
                        "return Err(SolveError::new({}, {}, ErrorKind::Inconsistent, {gap}));",
                        lit(&con.name),
                        lit(&con.text)
                    ));
                    w.close("}");
                    let p = self.r(*point);
                    self.facts.regs.insert(r, p);
                }
            }
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                ..
            } => {
                if let Some(r) = out {
                    let con = &m.constraints[*constraint];
                    let f = match meet {
                        Meet::CircleCircle => "circle_circle",
                        Meet::LineCircle => "line_circle",
                        Meet::LineLine => "line_line",
                        Meet::CircleConic => "circle_conic",
                        Meet::LineConic => "line_conic",
                    };
                    let index = match self.cx.branches.get(branch.0 as usize) {
                        Some(field) if self.cx.plan.branches[branch.0 as usize].count > 1 => {
                            format!("usize::from(branches.{field})")
                        }
                        _ => "0".into(),
                    };
                    if *meet == Meet::CircleCircle {
                        // Only the chosen root is computed.
                        let (label, text) = (lit(&con.name), lit(&con.text));
                        let chord = format!(
                            "intersect2d::circle_circle_chord(&{}, &{}).map_err(|miss| SolveError::from_miss({label}, {text}, miss))?",
                            self.r(*a),
                            self.r(*b),
                        );
                        let root = format!(
                            ".root({index}).ok_or_else(|| SolveError::new({label}, {text}, ErrorKind::NoSuchBranch, 2.0))?"
                        );
                        if !self.cx.rotated_onto.contains(&r) {
                            self.define(w, r, &con.name, &format!("{chord}{root}"));
                            return;
                        }
                        // A rotation turns a point onto this root: the chord is kept, so that
                        // the rotation reads the root from its centre, to the last bits.
                        let local = self.names.fresh(&format!("{}_chord", con.name));
                        w.line(&format!("let {local} = {chord};"));
                        self.define(w, r, &con.name, &format!("{local}{root}"));
                        let center = |c: &Reg| {
                            self.facts
                                .circle_centers
                                .get(c)
                                .cloned()
                                .unwrap_or_default()
                        };
                        let centers = [center(a), center(b)];
                        let kept = ChordRoot {
                            chord: local,
                            index,
                            centers,
                        };
                        self.facts.chord_roots.insert(r, kept);
                        return;
                    }
                    let meeting = self.names.fresh(&format!("{}_meeting", con.name));
                    w.line(&format!(
                        "let {meeting} = intersect2d::{f}(&{}, &{});",
                        self.r(*a),
                        self.r(*b)
                    ));
                    w.open(&format!(
                        "if let Some(e) = SolveError::from_contact({}, {}, {meeting}.contact) {{",
                        lit(&con.name),
                        lit(&con.text)
                    ));
                    w.line("return Err(e);");
                    w.close("}");
                    let code = format!(
                        "{meeting}.branch({index}).ok_or_else(|| SolveError::new({}, {}, ErrorKind::NoSuchBranch, {meeting}.roots.len() as f64))?",
                        lit(&con.name),
                        lit(&con.text)
                    );
                    self.define(w, r, &con.name, &code);
                }
            }
            Op::Translate { geoms, from, to } => {
                let (f, t) = (self.r(*from), self.r(*to));
                if f == t {
                    // From a point onto itself: nothing moves.
                    return;
                }
                let mut shift = None;
                for &g in geoms {
                    let facts = self.facts.frames.entry(g).or_default();
                    let frame = self.frames.get(&g).cloned().unwrap_or_default();
                    if facts.origin.as_ref().is_some_and(|o| o.code() == f) {
                        // The point brought onto `to` is the origin: it lands there exactly.
                        facts.origin = Some(Origin::Code(t.clone()));
                        w.line(&format!("{frame}.place_origin(&{t});"));
                    } else {
                        facts.origin = None;
                        let shift = shift.get_or_insert_with(|| {
                            let name = self.names.fresh("shift");
                            w.line(&format!("let {name} = {t} - {f};"));
                            name
                        });
                        w.line(&format!("{frame}.translate(&{shift});"));
                    }
                    self.frame_writes.insert(g);
                }
            }
            Op::RotatePoint {
                geoms,
                pivot,
                from,
                to,
            } => {
                let (p, f, t) = (self.r(*pivot), self.r(*from), self.r(*to));
                // From the pivot to the target: read from the chord when the target is a root
                // of a circle about the pivot (the same vector, without the cancellation of a
                // difference of points far from the origin).
                let from_chord = self.facts.chord_roots.get(to).and_then(|root| {
                    let side = root.centers.iter().position(|c| *c == p)?;
                    let f = ["root_from_a", "root_from_b"][side];
                    Some(format!(
                        "{}.{f}({}).unwrap_or({t} - {p})",
                        root.chord, root.index
                    ))
                });
                let to_target = match &from_chord {
                    Some(code) => format!("&{code}"),
                    None => format!("&({t} - {p})"),
                };
                let radius = self.facts.circle_radius.get(&(*pivot, *from)).copied();
                let code = match (radius, self.constant_arm(*pivot, *from)) {
                    // A point of a rigid geom turned onto its circle about the pivot, from where
                    // the sketch put it: the arm and the circle's radius are constants, so the
                    // rotation's cosine and sine are `(arm . reach, arm x reach) / radius²`
                    // with constant coefficients.
                    (Some(radius), Some((ax, ay))) if radius > 0.0 => {
                        let reach = self.names.fresh(&self.derived_name(*to, "_reach", "reach"));
                        let code = from_chord.unwrap_or_else(|| format!("{t} - {p}"));
                        w.line(&format!("let {reach} = {code};"));
                        let k = 1.0 / (radius * radius);
                        let (kx, ky) = (ax * k, ay * k);
                        let c = linear(&[(kx, format!("{reach}.x")), (ky, format!("{reach}.y"))]);
                        let s = linear(&[(kx, format!("{reach}.y")), (-ky, format!("{reach}.x"))]);
                        // The arm itself is read only when the lengths disagree with the
                        // radius, off the fast path.
                        format!("rotation_on_circle_from({c}, {s}, &({f} - {p}), &{reach})")
                    }
                    // A point of a rigid geom turned onto its circle about the pivot: the
                    // circle's radius is known, and with it the rotation's scale.
                    (Some(radius), _) => format!(
                        "rotation_on_circle(&({f} - {p}), {to_target}, {})",
                        float(radius)
                    ),
                    (None, _) => format!("rotation_between2(&({f} - {p}), {to_target})"),
                };
                self.rotate(w, geoms, &p, &code);
            }
            Op::RotateDir {
                geoms,
                pivot,
                from,
                to,
            } => {
                let (p, f, t) = (self.r(*pivot), self.r(*from), self.r(*to));
                let code = if self.facts.unit_x.contains(from) && self.facts.unit_dirs.contains(to)
                {
                    // A finite unit direction: it is the rotation, with nothing to test.
                    format!("rotation_from_x_unit(&{t})")
                } else if self.facts.unit_x.contains(from) {
                    format!("rotation_from_x(&{t})")
                } else {
                    format!("rotation_between_units(&{f}, &{t})")
                };
                self.rotate(w, geoms, &p, &code);
            }
            Op::SetDim { geom, value } => {
                let v = self.r(*value);
                let known_good = v.parse::<f64>().is_ok_and(|x| x.is_finite() && x >= 0.0);
                if !known_good {
                    let test = if self.facts.finite.contains(value) {
                        format!("if {v} < 0.0 {{")
                    } else {
                        format!("if !gcs_runtime::num::is_finite({v}) || {v} < 0.0 {{")
                    };
                    w.open(&test);
                    w.line(&format!(
                        "return Err({});",
                        self.cx.error(i, "InvalidValue", &v)
                    ));
                    w.close("}");
                }
                let d = self.dims.get(geom).cloned().unwrap_or_default();
                if self.deferred.remove(geom) {
                    w.line(&format!("let {d} = {v};"));
                } else {
                    w.line(&format!("{d} = {v};"));
                }
            }
            Op::Check { constraint } => {
                let residual = self.residual_code(*constraint);
                let name = self.names.fresh("residual");
                w.line(&format!("let {name} = {residual};"));
                w.open(&format!("if {name}.is_nan() || {name} > tol {{"));
                let con = &m.constraints[*constraint];
                w.line(&format!(
                    "return Err(SolveError::new({}, {}, ErrorKind::Inconsistent, {name}));",
                    lit(&con.name),
                    lit(&con.text)
                ));
                w.close("}");
            }
        }
    }
}
