//! Relations that are run-time checks, and the registers relations read. A relation whose
//! features are all known already, or move together, is implied (`implied`): the plan
//! measures its residual (`residual`) instead of moving anything. The distances, angles and
//! circle parts a relation asks for (`length`, `angle_value`, `angle`, `circle_parts`) are
//! read here for checks and moves alike; a distance that adds a circle's radius waits until
//! that radius is known (`radii_known`).

use super::relation::{AngleValue, Length, Relation};
use super::Spatial;
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, Reg, Residual, SpatialOp, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    pub(super) fn implied(&self, relation: &Relation) -> bool {
        if !self.radii_known(relation) {
            return false;
        }
        match *relation {
            Relation::PointPoint { a, b, .. } => {
                (self.point_known(a) && self.point_known(b)) || self.together(a, b)
            }
            Relation::PointLine { p, base, dir, .. } => {
                (self.point_known(p) && self.point_known(base) && self.dir_known(dir))
                    || (self.together(p, base) && self.together(p, dir))
            }
            Relation::PointPlane {
                p, base, normal, ..
            } => {
                (self.point_known(p) && self.point_known(base) && self.dir_known(normal))
                    || (self.together(p, base) && self.together(p, normal))
            }
            Relation::Parallel { u, v, .. } | Relation::Angle { u, v, .. } => {
                (self.dir_known(u) && self.dir_known(v)) || self.together(u, v)
            }
            Relation::PointCircle { p, circle, .. } => {
                (self.point_known(p) && self.record(circle).grounded()) || self.together(p, circle)
            }
            Relation::Twist { axis, u, v, .. } => {
                (self.dir_known(axis) && self.dir_known(u) && self.dir_known(v))
                    || (self.together(axis, v) && self.together(u, v))
            }
            Relation::Helix {
                axis, u, v, p, q, ..
            } => {
                (self.dir_known(axis)
                    && self.dir_known(u)
                    && self.dir_known(v)
                    && self.point_known(p)
                    && self.point_known(q))
                    || (self.together(u, v) && self.together(p, q) && self.together(u, p))
            }
            Relation::Midpoint { p, a, b } => {
                (self.point_known(p) && self.point_known(a) && self.point_known(b))
                    || (self.together(p, a) && self.together(p, b))
            }
            Relation::Mirror { p, q, base, normal } => {
                (self.point_known(p)
                    && self.point_known(q)
                    && self.point_known(base)
                    && self.dir_known(normal))
                    || (self.together(p, q) && self.together(p, base) && self.together(p, normal))
            }
            // Its size set (or held): a check.
            Relation::Size { geom, .. } => !self.record(geom).shape.size_free(),
            Relation::SameSize { a, b } => {
                !self.record(a).shape.size_free() && !self.record(b).shape.size_free()
            }
        }
    }

    pub(super) fn residual(&mut self, relation: &Relation) -> Residual {
        match *relation {
            Relation::Midpoint { p, a, b } => Residual::Midpoint {
                p: self.point(p),
                a: self.point(a),
                b: self.point(b),
            },
            Relation::Mirror { p, q, base, normal } => Residual::MirrorPlane {
                p: self.point(p),
                q: self.point(q),
                base: self.point(base),
                normal: self.direction(normal),
            },
            Relation::Size { geom, value } => Residual::Dim {
                value: self.size_of(geom),
                target: self.expr(value),
            },
            Relation::SameSize { a, b } => Residual::Dim {
                value: self.size_of(a),
                target: self.size_of(b),
            },
            Relation::PointPoint { a, b, d } => {
                let (a, b) = (self.point(a), self.point(b));
                let d = d.map(|l| self.length(l));
                Residual::PointPoint { a, b, d }
            }
            Relation::PointLine { p, base, dir, d } => Residual::PointLine {
                p: self.point(p),
                base: self.point(base),
                dir: self.direction(dir),
                d: d.map(|l| self.length(l)),
            },
            Relation::PointPlane { p, base, normal, d } => {
                let (p, base, normal) = (self.point(p), self.point(base), self.direction(normal));
                let d = d.map(|e| self.expr(e));
                Residual::PointPlane { p, base, normal, d }
            }
            Relation::Parallel { u, v, sense } => Residual::Parallel {
                u: self.direction(u),
                v: self.direction(v),
                sense,
            },
            Relation::Angle { u, v, angle } => {
                let (u, v) = (self.direction(u), self.direction(v));
                let angle = self.angle_value(angle);
                Residual::AngleBetween { u, v, angle }
            }
            Relation::PointCircle { p, circle, d } => {
                let p = self.point(p);
                let (centre, normal, radius) = self.circle_parts(circle);
                let d = d.map(|e| self.expr(e));
                Residual::OnCircle {
                    p,
                    centre,
                    normal,
                    radius,
                    d,
                }
            }
            Relation::Twist { axis, u, v, angle } => {
                let (axis, u, v) = (self.direction(axis), self.direction(u), self.direction(v));
                let angle = self.angle(angle);
                Residual::Twist { axis, u, v, angle }
            }
            Relation::Helix {
                axis,
                u,
                v,
                p,
                q,
                pitch,
            } => {
                let (axis, u, v) = (self.direction(axis), self.direction(u), self.direction(v));
                let (p, q) = (self.point(p), self.point(q));
                let pitch = self.expr(pitch);
                Residual::Helix {
                    axis,
                    u,
                    v,
                    p,
                    q,
                    pitch,
                }
            }
        }
    }

    /// A circle of space's centre, unit normal and radius, measured now.
    pub(super) fn circle_parts(&mut self, circle: GeomId) -> (Reg, Reg, Reg) {
        let centre = match self.model.part(circle, gcs_lang::model::Part::Center) {
            Some(c) => self.point(c),
            None => self.point(circle),
        };
        let normal = match self.model.part(circle, gcs_lang::model::Part::Normal) {
            Some(n) => self.direction(n),
            None => self.value(SpatialOp::WorldAxis(2), Ty::Vector, "the Z axis".into()),
        };
        let radius = self.size_of(circle);
        (centre, normal, radius)
    }

    /// The register of a distance a relation asks for: its expression's, or its circles'
    /// radii (each known by now: see [`Builder::radii_known`]) summed with its gap.
    pub(super) fn length(&mut self, length: Length) -> Reg {
        let (first, second, gap) = match length {
            Length::Expr(e) => return self.expr(e),
            Length::Radii { first, second, gap } => (first, second, gap),
        };
        let mut terms = Vec::new();
        let mut words = Vec::new();
        for (sign, circle) in std::iter::once(first).chain(second) {
            terms.push((sign, self.size_of(circle)));
            words.push((sign, format!("the radius of {}", self.name(circle))));
        }
        if let Some((sign, e)) = gap {
            let g = self.expr(e);
            words.push((sign, self.word(g)));
            terms.push((sign, g));
        }
        if let [(1.0, one)] = terms.as_slice() {
            return *one;
        }
        let mut text = String::new();
        for (i, (sign, w)) in words.iter().enumerate() {
            match (i, *sign < 0.0) {
                (0, false) => text.push_str(w),
                (0, true) => text.push_str(&format!("minus {w}")),
                (_, false) => text.push_str(&format!(" plus {w}")),
                (_, true) => text.push_str(&format!(" minus {w}")),
            }
        }
        self.value(Op::Sum(terms), Ty::Scalar, text)
    }

    /// Whether the radii a relation's distance reads are known: a circle whose size is still
    /// free cannot give one (its size comes first, from its own constraints or a default).
    pub(super) fn radii_known(&self, relation: &Relation) -> bool {
        (relation.radii().into_iter()).all(|c| !self.record(c).shape.size_free())
    }

    /// The register of an angle a relation asks for.
    pub(super) fn angle_value(&mut self, angle: AngleValue) -> Reg {
        match angle {
            AngleValue::Expr(e) => self.expr(e),
            AngleValue::Const(c) => {
                // A whole number of degrees (a right angle, a body's own 90) reads as one.
                let deg = c.to_degrees();
                let words = if (deg - deg.round()).abs() <= 1e-9 {
                    format!("{} degrees", deg.round())
                } else {
                    crate::plan::fmt_f64(c)
                };
                self.value(Op::Const(c), Ty::Scalar, words)
            }
        }
    }

    /// The register of an angle value: its expression's, or zero.
    pub(super) fn angle(&mut self, angle: Option<gcs_lang::expr::ExprId>) -> Reg {
        match angle {
            Some(e) => self.expr(e),
            None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
        }
    }
}
