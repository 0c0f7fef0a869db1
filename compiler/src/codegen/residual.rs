//! The residual of a run-time check: the relation it holds, over the registers of its
//! features, measured by the runtime's `check` function of that relation's kind, which the
//! interpreter calls too.

use super::solve::Solve;
use super::writer::float;
use crate::plan::{Reg, Residual};

impl Solve<'_> {
    /// The call of the runtime's signed error of a relation (`component` of a coincidence, a
    /// midpoint or a mirror image).
    pub(super) fn error_code(&self, residual: &Residual, component: u8) -> String {
        match residual {
            Residual::PointPoint { a, b, d: None } => format!(
                "check::error::coincidence({}, {}, {component})",
                self.r(*a),
                self.r(*b)
            ),
            Residual::Midpoint { p, a, b } => format!(
                "check::error::midpoint({}, {}, {}, {component})",
                self.r(*p),
                self.r(*a),
                self.r(*b)
            ),
            Residual::Mirror { p, q, base, dir } => format!(
                "check::error::mirror({}, {}, {}, {}, {component})",
                self.r(*p),
                self.r(*q),
                self.r(*base),
                self.r(*dir)
            ),
            _ => {
                format!("check::error::{}", self.residual_call(residual))
            }
        }
    }

    /// The call of the runtime's residual of a check's relation.
    pub(super) fn residual_code(&self, residual: &Residual) -> String {
        format!("check::{}", self.residual_call(residual))
    }

    /// The call of a check's residual, by its name in `check` (and in `check::error`).
    fn residual_call(&self, residual: &Residual) -> String {
        let r = |x: &Reg| self.r(*x);
        let or_zero = |x: &Option<Reg>| x.as_ref().map_or_else(|| "0.0".to_string(), r);
        match residual {
            Residual::PointPoint { a, b, d } => {
                format!("point_point({}, {}, {})", r(a), r(b), or_zero(d))
            }
            Residual::PointLine { p, base, dir, d } => format!(
                "point_line({}, {}, {}, {})",
                r(p),
                r(base),
                r(dir),
                or_zero(d)
            ),
            Residual::Angle { u, v, angle } => {
                format!("angle({}, {}, {})", r(u), r(v), r(angle))
            }
            Residual::CircleLine {
                centre,
                radius,
                base,
                dir,
                gap,
                side,
            } => format!(
                "circle_line({}, {}, {}, {}, {}, {})",
                r(centre),
                r(radius),
                r(base),
                r(dir),
                or_zero(gap),
                float(*side)
            ),
            Residual::PointCircle {
                p,
                centre,
                radius,
                gap,
                outside,
            } => format!(
                "point_circle({}, {}, {}, {}, {outside})",
                r(p),
                r(centre),
                r(radius),
                or_zero(gap)
            ),
            Residual::CircleCircle {
                c1,
                r1,
                c2,
                r2,
                gap,
                nesting,
            } => format!(
                "circle_circle({}, {}, {}, {}, {}, check::Nesting::{nesting:?})",
                r(c1),
                r(r1),
                r(c2),
                r(r2),
                or_zero(gap)
            ),
            Residual::Dim { value, target } => {
                format!("dimension({}, {})", r(value), r(target))
            }
            Residual::Midpoint { p, a, b } => {
                format!("midpoint({}, {}, {})", r(p), r(a), r(b))
            }
            Residual::Mirror { p, q, base, dir } => {
                format!("mirror({}, {}, {}, {})", r(p), r(q), r(base), r(dir))
            }
            Residual::PointPlane { .. }
            | Residual::Parallel { .. }
            | Residual::Twist { .. }
            | Residual::Cone { .. }
            | Residual::AngleBetween { .. }
            | Residual::OnCircle { .. }
            | Residual::MirrorPlane { .. }
            | Residual::Helix { .. } => {
                unreachable!("bug in gcs: a spatial check reached the planar code generator")
            }
        }
    }
}
