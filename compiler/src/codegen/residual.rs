//! The residual of a run-time check: a constraint the plan already implies, measured again on
//! the frames at that step by the runtime's `check` functions.

use super::expr::Prec;
use super::solve::Solve;
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Part};

impl Solve<'_> {
    /// The residual of a constraint, measured on the frames now (run-time checks).
    pub(super) fn residual_code(&self, c: ConstraintId) -> String {
        let m = self.cx.model;
        let con = &m.constraints[c];
        let value = con
            .value
            .map_or("0.0".to_string(), |e| self.cx.wrap(e, Prec::Product));
        let kind = |g: GeomId| m.geoms[g].kind;
        let point_code = |g: GeomId| self.point_value(g).code();
        let dir_code = |g: GeomId| self.dir_value(g).code();
        let part = |g, p| crate::analysis::relation::part(m, g, p).unwrap_or(g);
        let pt = |g: GeomId| {
            let g = if kind(g) == GeomKind::Circle {
                part(g, Part::Center)
            } else {
                g
            };
            point_code(g)
        };
        let dir = |g: GeomId| {
            let g = if matches!(kind(g), GeomKind::Line | GeomKind::Segment) {
                part(g, Part::Dir)
            } else {
                g
            };
            dir_code(g)
        };
        let line = |g: GeomId| -> (String, String) {
            match kind(g) {
                GeomKind::Segment => (point_code(part(g, Part::Start)), dir(g)),
                GeomKind::Marker => (point_code(g), dir_code(part(g, Part::AxisX))),
                _ => (point_code(g), dir(g)),
            }
        };
        let radius = |g: GeomId| self.dims.get(&g).cloned().unwrap_or_else(|| "0.0".into());
        let sd =
            |(p, d): (String, String), q: String| format!("check::signed_distance({p}, {d}, {q})");
        let angle = |u: String, v: String| format!("check::angle({u}, {v})");
        let circles = |x: GeomId, y: GeomId, gap: &str| {
            format!(
                "check::circles({}, {}, {}, {}, {gap})",
                pt(x),
                radius(x),
                pt(y),
                radius(y)
            )
        };
        let (a, b) = (con.args.first().copied(), con.args.get(1).copied());
        match (con.kind, a, b) {
            (K::Coincident | K::Spherical | K::Revolute, Some(a), Some(b)) => {
                format!("({} - ({})).norm()", pt(a), pt(b))
            }
            (K::Distance, Some(a), Some(b)) => match (kind(a), kind(b)) {
                (GeomKind::Line | GeomKind::Segment, GeomKind::Circle) => format!(
                    "({}.abs() - {} - {value}).abs()",
                    sd(line(a), pt(b)),
                    radius(b)
                ),
                (GeomKind::Circle, GeomKind::Circle) => circles(a, b, &value),
                (_, GeomKind::Line | GeomKind::Segment) => {
                    format!("({} - {value}).abs()", sd(line(b), pt(a)))
                }
                (_, GeomKind::Circle) => format!(
                    "((({} - ({})).norm() - {}).abs() - {value}).abs()",
                    pt(a),
                    pt(b),
                    radius(b)
                ),
                _ => format!(
                    "(({} - ({})).norm() - f64::abs({value})).abs()",
                    pt(a),
                    pt(b)
                ),
            },
            (K::On, Some(a), Some(b)) => match kind(b) {
                GeomKind::Circle => {
                    format!("(({} - ({})).norm() - {}).abs()", pt(a), pt(b), radius(b))
                }
                _ => format!("{}.abs()", sd(line(b), pt(a))),
            },
            (K::Tangent, Some(a), Some(b)) => match kind(a) {
                GeomKind::Circle => circles(a, b, "0.0"),
                _ => format!("({}.abs() - {}).abs()", sd(line(a), pt(b)), radius(b)),
            },
            (K::Angle, Some(a), Some(b)) => {
                format!("check::angle_gap({}, {value})", angle(dir(a), dir(b)))
            }
            (K::Horizontal, Some(a), _) => format!("{}.y.abs()", dir(a)),
            (K::Vertical, Some(a), _) => format!("{}.x.abs()", dir(a)),
            (K::Parallel, Some(a), Some(b)) => {
                format!("check::angle({}, {}).sin().abs()", dir(a), dir(b))
            }
            (K::Perpendicular, Some(a), Some(b)) => format!("{}.dot(&{}).abs()", dir(a), dir(b)),
            (K::Length | K::Radius, Some(a), _) => format!("({} - {value}).abs()", radius(a)),
            (K::InLine, Some(a), Some(b)) => format!("{}.abs()", sd(line(b), pt(a))),
            (K::OffsetX | K::Prismatic, Some(a), Some(b)) => {
                let target = if con.kind == K::OffsetX {
                    value.clone()
                } else {
                    "0.0".into()
                };
                let turn = format!(
                    "check::angle_gap({}, {target})",
                    angle(line(a).1, line(b).1)
                );
                if con.kind == K::Prismatic {
                    format!("{turn}.max({}.abs())", sd(line(b), pt(a)))
                } else {
                    turn
                }
            }
            _ => "f64::INFINITY".into(),
        }
    }
}
