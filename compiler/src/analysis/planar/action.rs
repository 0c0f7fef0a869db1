//! Action analysis in the plane: a relation one of whose sides is known ("fixed enough")
//! moves the other side's cluster with the freedom its record leaves. `action` dispatches on
//! the kind of relation: points onto points or lines, directions turned to an angle,
//! dimensions set (`dimension`); circles, equal dimensions, midpoints and mirrors have
//! fragments of their own (`circle.rs`, `sketcher.rs`). A relation already implied is a
//! run-time check instead.

use super::relation::{AngleValue, Dir, Relation};
use super::{Locus, Planar, Rel, Target};
use crate::analysis::driver::Builder;
use crate::plan::{Op, PlanarOp, Ty};
use gcs_lang::model::GeomKind;

impl Builder<'_, Planar> {
    /// A dimension constraint on a geom whose dimension is free (`action` checks a fixed one):
    /// scale the geom.
    fn dimension(&mut self, r: &Rel) {
        let Relation::Dim { geom, value } = r.relation else {
            return;
        };
        let k = self.cluster(geom);
        let v = self.expr(value);
        let what = if self.model.geoms[geom].kind == GeomKind::Circle {
            "radius"
        } else {
            "length"
        };
        let explain = format!(
            "Scale {} so that its {what} is {} ({}). This fixes its dimension.",
            self.name(geom),
            self.word(v),
            self.cname(r.constraint)
        );
        self.emit(
            Op::SetDim { geom, value: v },
            None,
            self.satisfies(r),
            explain,
        );
        let rec = &mut self.clusters[k].record;
        rec.free_dim = None;
        rec.fixed_dims.push(geom);
    }

    /// Action analysis: one side known enough, the other side moved. Returns whether the
    /// relation was satisfied (or became a check).
    pub(super) fn action(&mut self, r: &Rel) -> bool {
        if self.implied(&r.relation) {
            self.check(r);
            return true;
        }
        match r.relation.clone() {
            Relation::PointPoint { a, b, d } => {
                let (ka, kb) = (self.point_known(a), self.point_known(b));
                let (known, free) = match (ka, kb) {
                    (true, false) => (a, b),
                    (false, true) => (b, a),
                    _ => return false,
                };
                let at = self.point(known);
                let target = match d {
                    None => Target::Point(at),
                    Some(d) => {
                        let radius = self.expr(d);
                        let words = format!(
                            "the circle of radius {} about {}",
                            self.word(radius),
                            self.word(at)
                        );
                        let c =
                            self.value(PlanarOp::Circle { center: at, radius }, Ty::Circle, words);
                        self.centers.insert(c, self.word(at));
                        Target::On(Locus::Circle(c))
                    }
                };
                self.move_feature(free, target, r)
            }
            Relation::PointLine { p, base, dir, d } => {
                let on_line = self.line_point(base);
                let line_known = self.line_fixed(base, dir);
                let base = on_line.unwrap_or(base);
                let p_known = self.point_known(p);
                if self.cluster(p) == self.cluster(base) {
                    // Within one cluster whose free dimension still moves the point: wait.
                    return false;
                }
                if line_known {
                    let bp = self.point(base);
                    let dv = self.dir(Dir::Feature(dir));
                    let offset = d.map(|d| self.expr(d));
                    let words = match offset {
                        Some(o) => format!(
                            "the line along {} at distance {} from {}",
                            self.name(dir),
                            self.word(o),
                            self.name(base)
                        ),
                        None => format!(
                            "the line through {} along {}",
                            self.name(base),
                            self.name(dir)
                        ),
                    };
                    let line = self.value(
                        Op::Line {
                            point: bp,
                            dir: dv,
                            offset,
                        },
                        Ty::Line,
                        words,
                    );
                    return self.move_feature(p, Target::On(Locus::Line(line)), r);
                }
                if p_known {
                    let d = d.map(|d| self.expr(d));
                    return self.move_line_to_point(p, base, dir, d, r);
                }
                d.is_none() && self.common_line(p, base, dir, r)
            }
            Relation::Angle { u, v, angle } => {
                let (ku, kv) = (self.dir_known(u), self.dir_known(v));
                let a = self.angle(angle);
                match (ku, kv, u, v) {
                    (true, false, _, Dir::Feature(fv)) if angle == AngleValue::Const(0.0) => {
                        let base = self.dir(u);
                        self.turn(fv, base, r)
                    }
                    (false, true, Dir::Feature(fu), _) if angle == AngleValue::Const(0.0) => {
                        let base = self.dir(v);
                        self.turn(fu, base, r)
                    }
                    (true, false, _, Dir::Feature(fv)) => {
                        let base = self.dir(u);
                        let words = format!("{} turned by {}", self.word(base), self.word(a));
                        let target = self.value(
                            PlanarOp::Rotated {
                                dir: base,
                                angle: a,
                            },
                            Ty::Vector,
                            words,
                        );
                        self.turn(fv, target, r)
                    }
                    (false, true, Dir::Feature(fu), _) => {
                        let base = self.dir(v);
                        let words = format!("{} turned back by {}", self.word(base), self.word(a));
                        let minus = self.neg(a);
                        let target = self.value(
                            PlanarOp::Rotated {
                                dir: base,
                                angle: minus,
                            },
                            Ty::Vector,
                            words,
                        );
                        self.turn(fu, target, r)
                    }
                    _ => false,
                }
            }
            Relation::Dim { .. } => {
                self.dimension(r);
                true
            }
            Relation::PointCircle { .. }
            | Relation::CircleLine { .. }
            | Relation::CircleCircle { .. } => self.circle_relation(r),
            Relation::Equal { .. } => self.equal(r),
            Relation::Midpoint { .. } => self.midpoint(r),
            Relation::Mirror { .. } => self.mirror(r),
        }
    }
}
