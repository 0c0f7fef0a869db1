//! The checks of space: a relation's residual and signed errors as calls of `check::space`,
//! as the interpreter's `error_of3` measures them.

use crate::codegen::solve::Solve;
use crate::codegen::writer::float;
use crate::plan::{Reg, Residual};

impl Solve<'_> {
    /// The call of the signed error of a relation in space (`component`: a coincidence's
    /// axis), as the interpreter's `error_of3` measures it.
    pub(super) fn error_code3(&self, residual: &Residual, component: u8) -> String {
        let r = |x: &Reg| self.r(*x);
        match residual {
            Residual::PointPoint { a, b, d: None } => {
                format!("({} - {})[{}]", r(a), r(b), component.min(2))
            }
            Residual::PointPoint { a, b, d: Some(d) } => {
                format!("({} - {}).norm() - {}", r(a), r(b), r(d))
            }
            Residual::PointPlane { p, base, normal, d } => {
                let d = d.as_ref().map_or_else(|| "0.0".to_string(), r);
                format!("({} - {}).dot(&{}) - {d}", r(p), r(base), r(normal))
            }
            Residual::Cone { axis, u, v } => {
                format!("({} - {}).dot(&{})", r(u), r(v), r(axis))
            }
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d: Some(d),
            } => format!(
                "Circle3::new({}, {}, {}).distance(&{}) - {}",
                r(centre),
                r(normal),
                r(radius),
                r(p),
                r(d)
            ),
            Residual::PointLine {
                p,
                base,
                dir,
                d: Some(d),
            } => format!(
                "({} - {}).cross(&{}).norm() - {}",
                r(p),
                r(base),
                r(dir),
                r(d)
            ),
            // On the line: the offset across it, one signed coordinate (`Op::Error`).
            Residual::PointLine {
                p,
                base,
                dir,
                d: None,
            } if component == 1 || component == 2 => format!(
                "check::space::across_line({}, {}, {})[{}]",
                r(p),
                r(base),
                r(dir),
                component - 1
            ),
            Residual::Midpoint { p, a, b } => format!(
                "(locus3d::midpoint({}, {}) - {})[{}]",
                r(a),
                r(b),
                r(p),
                component.min(2)
            ),
            Residual::MirrorPlane { p, q, base, normal } => format!(
                "({} - locus3d::mirror({}, {}, {}))[{}]",
                r(q),
                r(base),
                r(normal),
                r(p),
                component.min(2)
            ),
            _ => self.residual_code3(residual),
        }
    }

    /// The call of the runtime's residual of a check's relation in space.
    pub(in crate::codegen) fn residual_code3(&self, residual: &Residual) -> String {
        let r = |x: &Reg| self.r(*x);
        let or_zero = |x: &Option<Reg>| x.as_ref().map_or_else(|| "0.0".to_string(), r);
        match residual {
            Residual::PointPoint { a, b, d } => format!(
                "check::space::point_point({}, {}, {})",
                r(a),
                r(b),
                or_zero(d)
            ),
            Residual::PointLine { p, base, dir, d } => format!(
                "check::space::point_line({}, {}, {}, {})",
                r(p),
                r(base),
                r(dir),
                or_zero(d)
            ),
            Residual::PointPlane { p, base, normal, d } => format!(
                "check::space::point_plane({}, {}, {}, {})",
                r(p),
                r(base),
                r(normal),
                or_zero(d)
            ),
            Residual::Parallel { u, v, sense } => format!(
                "check::space::parallel({}, {}, {})",
                r(u),
                r(v),
                float(*sense)
            ),
            Residual::AngleBetween { u, v, angle } => format!(
                "check::space::angle_between({}, {}, {})",
                r(u),
                r(v),
                r(angle)
            ),
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d: None,
            } => format!(
                "Circle3::new({}, {}, {}).distance(&{})",
                r(centre),
                r(normal),
                r(radius),
                r(p)
            ),
            Residual::OnCircle {
                p,
                centre,
                normal,
                radius,
                d: Some(d),
            } => format!(
                "(Circle3::new({}, {}, {}).distance(&{}) - {}).abs()",
                r(centre),
                r(normal),
                r(radius),
                r(p),
                r(d)
            ),
            Residual::Cone { axis, u, v } => {
                format!("check::space::cone({}, {}, {})", r(axis), r(u), r(v))
            }
            Residual::Twist { axis, u, v, angle } => format!(
                "check::space::twist({}, {}, {}, {})",
                r(axis),
                r(u),
                r(v),
                r(angle)
            ),
            Residual::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } => format!(
                "check::space::helix({}, {}, {}, {} - {}, {})",
                r(axis),
                r(u),
                r(v),
                r(q),
                r(p),
                r(pitch)
            ),
            Residual::Dim { value, target } => {
                format!("check::dimension({}, {})", r(value), r(target))
            }
            Residual::Midpoint { p, a, b } => {
                format!("check::space::midpoint({}, {}, {})", r(p), r(a), r(b))
            }
            Residual::MirrorPlane { p, q, base, normal } => format!(
                "check::space::mirror({}, {}, {}, {})",
                r(p),
                r(q),
                r(base),
                r(normal)
            ),
            other => panic!("bug in gcs: the check {other:?} is no check of a spatial plan"),
        }
    }
}
