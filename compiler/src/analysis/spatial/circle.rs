//! Plan fragments for circles of space that move: a sized circle carried to pass through a
//! known point (or at a distance from it) by translating its centre, or tilted about its
//! centre to do so; a circle of free radius with its centre held turned so that its plane
//! holds a known point, then given the radius that reaches it.

use super::{Locus, Rel, Shape, Spatial, Target, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reg, Residual, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::{ConstraintId, GeomId, Part};

impl Builder<'_, Spatial> {
    /// A sized circle whose normal is known and whose centre is free carried (by the least
    /// translation) to pass through known point `p`, or at distance `d` from it: its centre
    /// goes onto the circle of its radius about `p` in a plane parallel to its own, or onto the
    /// torus at `d` about that circle (a circle's distance from a point is the centre's from
    /// that circle, turned about `p`'s axis). Turning it, or resizing it, would move the point
    /// off it in a way its record cannot follow: a circle whose size or normal is free is not
    /// carried (its size's default comes first; a free normal, not yet).
    pub(super) fn carry_circle(
        &mut self,
        circle: GeomId,
        p: GeomId,
        d: Option<gcs_lang::expr::ExprId>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let Some(center) = self.model.part(circle, Part::Center) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.turn != Turn::Known
            || rec.shape.size_free()
            || self.point_known(center)
        {
            return false;
        }
        let at = self.point(p);
        let (_, normal, radius) = self.circle_parts(circle);
        let (cname, pname) = (self.name(circle), self.name(p));
        let words = format!("the circle of {cname}'s radius about {pname}, parallel to {cname}");
        let about = self.value(
            SpatialOp::Circle3 {
                center: at,
                normal,
                radius,
            },
            Ty::Circle,
            words,
        );
        let locus = match d {
            None => Locus::Circle(about),
            Some(e) => {
                let tube = self.expr(e);
                let words = format!("the torus at {} from {}", self.word(tube), self.word(about));
                Locus::Torus(self.value(
                    SpatialOp::Torus {
                        circle: about,
                        tube,
                    },
                    Ty::Torus,
                    words,
                ))
            }
        };
        self.move_point(center, Target::On(locus), r)
    }

    /// A sized circle held at its centre, free to turn, tilted the least about its centre so
    /// that known point `p` lies `d` from it: its normal onto the cone about the direction to
    /// `p` whose angle puts `p` there (`SpatialOp::TiltToDistance`, on the side of the plane `p` is
    /// on now). It may then only turn about the line from its centre to `p`.
    pub(super) fn tilt_circle(
        &mut self,
        circle: GeomId,
        p: GeomId,
        d: gcs_lang::expr::ExprId,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let (Some(center), Some(normal)) = (
            self.model.part(circle, Part::Center),
            self.model.part(circle, Part::Normal),
        ) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.turn != Turn::Free
            || rec.shape.size_free()
            || !self.point_known(center)
        {
            return false;
        }
        let (c, at, n) = (self.point(center), self.point(p), self.direction(normal));
        let radius = self.size_of(circle);
        let d = self.expr(d);
        let (cname, pname, con) = (self.name(circle), self.name(p), self.cname(r.constraint));
        let words = format!("the direction from the centre of {cname} to {pname}");
        let toward = self.value(Op::DirectionTo { from: c, to: at }, Ty::Vector, words);
        let words = format!(
            "the angle from {cname}'s normal to {pname} that puts {pname} {} from it",
            self.word(d)
        );
        let angle = self.value(
            SpatialOp::TiltToDistance {
                centre: c,
                point: at,
                radius,
                d,
                now: n,
                constraint: r.constraint,
            },
            Ty::Scalar,
            words,
        );
        let words = format!("the normal nearest {}'s at that angle", self.name(normal));
        let explain = format!(
            "Tilt {cname} the least about its centre so that {pname} lies {} from it ({con}); it may then only turn about the line from its centre to {pname}.",
            self.word(d)
        );
        let satisfies = self.satisfies(r);
        self.turn_normal_onto_cone(k, (c, n), (toward, angle), words, explain, satisfies);
        true
    }

    /// Turns circle cluster `k` (its centre at `c`, its normal `n`) the least about its centre
    /// so that its normal makes `angle` with `toward`: onto the cone about `toward` nearest it
    /// (`SpatialOp::ConeTurn`). It may then only turn about `toward`.
    fn turn_normal_onto_cone(
        &mut self,
        k: usize,
        (c, n): (Reg, Reg),
        (toward, angle): (Reg, Reg),
        words: String,
        explain: String,
        satisfies: Vec<ConstraintId>,
    ) {
        let to = self.value(
            SpatialOp::ConeTurn {
                axis: toward,
                angle,
                dir: n,
            },
            Ty::Vector,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        self.emit(
            Op::RotateDir {
                geoms,
                pivot: c,
                axis: RotationAxis::Shortest,
                from: n,
                to,
            },
            None,
            satisfies,
            explain,
        );
        self.clusters[k].record.turn = Turn::Axis {
            axis: toward,
            feature: None,
        };
    }

    /// Circle `circle`, its centre held and its radius free, passes through the known point
    /// `p`: free to turn, it turns the least about its centre so that its plane holds the
    /// point (its normal onto the cone square to the direction from the centre to the point),
    /// and may then only turn about that direction; with its normal known, the point must lie
    /// in its plane (a check). Then it takes the radius that reaches the point.
    pub(super) fn circle_through(&mut self, circle: GeomId, p: GeomId, r: &Rel) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let (Some(center), Some(normal)) = (
            self.model.part(circle, Part::Center),
            self.model.part(circle, Part::Normal),
        ) else {
            return false;
        };
        if self.clusters[k].geoms != [circle]
            || rec.shape != (Shape::Circle { sized: false })
            || !self.point_known(center)
            || !matches!(rec.turn, Turn::Free | Turn::Known)
        {
            return false;
        }
        let (c, at, n) = (self.point(center), self.point(p), self.direction(normal));
        let (cname, pname, con) = (self.name(circle), self.name(p), self.cname(r.constraint));
        let words = format!("the direction from the centre of {cname} to {pname}");
        let toward = self.value(Op::DirectionTo { from: c, to: at }, Ty::Vector, words);
        if rec.turn == Turn::Free {
            let square = self.value(
                Op::Const(std::f64::consts::FRAC_PI_2),
                Ty::Scalar,
                "a right angle".into(),
            );
            let words = format!("the normal nearest {}'s square to it", self.name(normal));
            let explain = format!(
                "Rotate {cname} the least about its centre so that its plane holds {pname} ({con}); it may then only turn about the line from its centre to {pname}."
            );
            self.turn_normal_onto_cone(k, (c, n), (toward, square), words, explain, Vec::new());
        } else {
            let residual = Residual::PointPlane {
                p: at,
                base: c,
                normal: n,
                d: None,
            };
            let explain = format!("Check that {pname} lies in the plane of {cname} ({con}).");
            self.emit(
                Op::Check {
                    constraint: r.constraint,
                    residual,
                    guard: false,
                },
                None,
                Vec::new(),
                explain,
            );
        }
        let words = format!("the distance from the centre of {cname} to {pname}");
        let radius = self.value(
            Op::Along {
                from: c,
                dir: toward,
                to: at,
            },
            Ty::Scalar,
            words,
        );
        let explain = format!(
            "... and give {cname} the radius that reaches {pname}: {} ({con}).",
            self.word(radius)
        );
        let satisfies = self.satisfies(r);
        self.resize(circle, radius, None, explain, satisfies);
        self.clusters[k].record.shape = Shape::Circle { sized: true };
        true
    }
}
