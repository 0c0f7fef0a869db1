//! Plan fragments for planes that move, and lines held in a plane. A plane at a distance from
//! a known point slides along its normal, then turns about the point, then about the line to
//! it (three points place a plane). A line whose point is held in a plane along its direction
//! (a line in a circle's plane) goes onto the lines where that plane cuts a cylinder, and is
//! in the plane once its pivot is.

use super::relation::{AngleValue, Relation};
use super::{Locus, Rel, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Meet, Op, Reg, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::{GeomId, GeomKind};

/// A plane of a cluster (through `base`, unit `normal`) to be at signed distance `d` from
/// known point `point`.
#[derive(Clone, Copy, Debug)]
pub(super) struct PlaneAtDistance {
    pub(super) base: Reg,
    pub(super) normal: Reg,
    pub(super) point: Reg,
    pub(super) d: Reg,
}

impl Builder<'_, Spatial> {
    /// A plane `q` (its normal `normal`) to be at signed distance `d` from known point `p`,
    /// its normal not known: free, it slides along its normal to that distance, and may then
    /// only turn about `p` (which keeps it); about a point, it turns the least onto the cone of
    /// normals that also keep `p`'s distance, and may then only turn about the line from
    /// there to `p`; about that line, it turns to where the cone meets its turn (a branch).
    /// Three points at known distances place a plane (004's point-plane cluster) in closed form.
    pub(super) fn plane_at_distance(
        &mut self,
        q: GeomId,
        normal: GeomId,
        p: GeomId,
        d: Option<gcs_lang::expr::ExprId>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(q);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let (qname, pname, c) = (self.name(q), self.name(p), self.cname(r.constraint));
        let dist = match d {
            Some(e) => self.expr(e),
            None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
        };
        match (rec.trans, rec.turn) {
            (Trans::Free, _) => {
                let (x, n) = (self.point(p), self.direction(normal));
                let words = format!("minus {}", self.word(dist));
                let back = self.value(Op::Neg(dist), Ty::Scalar, words);
                let words = format!("{qname} moved along its normal to its distance from {pname}");
                let target = self.value(
                    SpatialOp::Plane {
                        point: x,
                        normal: n,
                        offset: Some(back),
                    },
                    Ty::Plane,
                    words,
                );
                let from = self.point(q);
                let words = format!("the point of that plane nearest {qname}'s");
                let to = self.value(
                    Op::Nearest {
                        locus: target,
                        point: from,
                    },
                    Ty::Point,
                    words,
                );
                let explain = format!(
                    "{qname} is free to move along its normal: move it so that {pname} is at its distance from it ({c}); it may then only turn about {pname}."
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.trans = Trans::Pivot { at: x, feature: p };
                true
            }
            (Trans::Pivot { at, feature }, Turn::Free) if feature != p => {
                let (b, n, x) = (self.point(q), self.direction(normal), self.point(p));
                let words = format!(
                    "the normal {qname} takes, turned the least about {}, to be at its distance from {pname}",
                    self.word(at)
                );
                let to = self.value(
                    SpatialOp::PlaneTurn {
                        base: b,
                        normal: n,
                        pivot: at,
                        point: x,
                        d: dist,
                        constraint: r.constraint,
                    },
                    Ty::Vector,
                    words,
                );
                let explain = format!(
                    "{qname} may only turn about {}: turn it the least so that {pname} is at its distance from it ({c}); it may then only turn about the line through both.",
                    self.word(at)
                );
                self.emit(
                    Op::RotateDir {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Shortest,
                        from: n,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let words = format!("the line from {} through {pname}", self.word(at));
                let axis = self.value(Op::DirectionTo { from: at, to: x }, Ty::Vector, words);
                self.clusters[k].record.turn = Turn::Axis {
                    axis,
                    feature: None,
                };
                true
            }
            (Trans::Pivot { at, feature }, Turn::Axis { axis, .. }) if feature != p => {
                let (b, n, x) = (self.point(q), self.direction(normal), self.point(p));
                let meanings = vec![
                    format!(
                        "{qname}'s normal turned counter-clockwise about {} from its turn nearest the direction to {pname}",
                        self.word(axis)
                    ),
                    "turned clockwise from there".to_string(),
                ];
                let words = format!(
                    "the normal {qname} takes, turned about {}, to be at its distance from {pname}",
                    self.word(axis)
                );
                let explain = format!(
                    "{qname} may only turn about {}: turn it so that {pname} is at its distance from it ({c}).",
                    self.word(axis)
                );
                let satisfies = self.satisfies(r);
                self.turn_plane_about_axis(
                    k,
                    PlaneAtDistance {
                        base: b,
                        normal: n,
                        point: x,
                        d: dist,
                    },
                    (at, axis),
                    (r.constraint, meanings, words),
                    (satisfies, explain),
                );
                true
            }
            _ => false,
        }
    }

    /// Turns cluster `k`, which only turns about `axis` through `pivot`, so that `plane` (a
    /// plane of it) is at its distance from its point: where that turn meets the cone of
    /// normals that keep the distance (`SpatialOp::PlaneAxisTurn`), the root of a branch of
    /// `constraint` with `meanings`, `words` naming the normal it takes. The cluster is then
    /// fixed. Shared by a plane at a distance from a point and a planar sub-chain's plane.
    pub(super) fn turn_plane_about_axis(
        &mut self,
        k: usize,
        plane: PlaneAtDistance,
        (pivot, axis): (Reg, Reg),
        (constraint, meanings, words): (gcs_lang::model::ConstraintId, Vec<String>, String),
        (satisfies, explain): (Vec<gcs_lang::model::ConstraintId>, String),
    ) {
        let branch = self.branch(constraint, meanings);
        let to = self.value(
            SpatialOp::PlaneAxisTurn {
                base: plane.base,
                normal: plane.normal,
                pivot,
                point: plane.point,
                d: plane.d,
                axis,
                branch,
                constraint,
            },
            Ty::Vector,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                axis: RotationAxis::Along(axis),
                from: plane.normal,
                to,
            },
            None,
            satisfies,
            explain,
        );
        let rec = &mut self.clusters[k].record;
        rec.turn = Turn::Known;
        rec.trans = Trans::Fixed;
    }

    /// Whether a relation has turned direction `dir` square to direction `normal` (a line
    /// into a circle's plane, `relation::decompose`).
    fn made_square(&self, dir: GeomId, normal: GeomId) -> bool {
        self.is_done(&Relation::Angle {
            u: dir,
            v: normal,
            angle: AngleValue::Const(std::f64::consts::FRAC_PI_2),
        })
    }

    /// The plane that holds point `base` (its record's locus) when that plane is known to hold
    /// direction `dir` too: its normal is a direction a relation already turned `dir` square
    /// to (a line in a circle's plane).
    pub(super) fn plane_along(&self, base: GeomId, dir: GeomId) -> Option<Reg> {
        let Trans::On {
            feature,
            locus: Locus::Plane(q),
        } = self.record(base).trans
        else {
            return None;
        };
        let defined = |reg: Reg| {
            (self.plan.steps.iter().rev())
                .find(|s| s.out.is_some_and(|(o, _)| o == reg))
                .map(|s| &s.op)
        };
        let Some(Op::Spatial(SpatialOp::Plane { normal, .. })) = defined(q) else {
            return None;
        };
        let Some(&Op::DirOf(m)) = defined(*normal) else {
            return None;
        };
        (feature == base && self.made_square(dir, m)).then_some(q)
    }

    /// Moves the line whose point `base` is held in plane `q`, parallel to cylinder `c`'s axis
    /// (the line's direction), onto the cylinder: the plane cuts it in two lines along the
    /// direction (a branch), and the line slides across itself within the plane onto one, which
    /// places it.
    pub(super) fn onto_cylinder_lines(&mut self, q: Reg, c: Reg, base: GeomId, r: &Rel) -> bool {
        let k = self.cluster(base);
        if !self.clusters[k].record.movable() {
            return false;
        }
        let (wq, wc) = (self.word(q), self.word(c));
        let meanings = vec![
            format!("the line where {wq} cuts {wc} first across its axis"),
            "the other line, second across the axis".to_string(),
        ];
        let branch = self.branch(r.constraint, meanings);
        let from = self.point(base);
        let words = format!("the line where {wq} cuts {wc}");
        let line = self.value(
            Op::Intersect {
                meet: Meet::PlaneCylinder,
                a: q,
                b: c,
                branch,
                constraint: r.constraint,
                near: from,
            },
            Ty::Line,
            words,
        );
        let bname = self.name(base);
        let words = format!("the point of {} nearest {bname}", self.word(line));
        let to = self.value(
            Op::Nearest {
                locus: line,
                point: from,
            },
            Ty::Point,
            words,
        );
        let geoms = self.clusters[k].geoms.clone();
        let explain = format!(
            "{} can only slide {bname} in {wq}: slide it onto {} ({}).",
            self.group_name(&geoms),
            self.word(line),
            self.cname(r.constraint)
        );
        self.emit(
            Op::Translate { geoms, from, to },
            None,
            self.satisfies(r),
            explain,
        );
        self.placed(k, base, to, Target::On(Locus::Line(line)));
        true
    }

    /// For a line's point `p` that must lie in a plane of normal `normal` (a line in a
    /// circle's plane, `r`'s relation): the other point of the line its cluster pivots about,
    /// when the cluster only turns about that normal and the same constraint has already turned
    /// the line square to it. Every point of the line then stays at the pivot's height along
    /// the normal, whatever the turn and the segment's length, so the relation holds exactly
    /// when the pivot lies in the plane: no motion can bring it about, and none is needed.
    pub(super) fn pivot_in_plane(&mut self, r: &Rel, p: GeomId, normal: GeomId) -> Option<GeomId> {
        let k = self.cluster(p);
        let rec = self.clusters[k].record.clone();
        let (Trans::Pivot { feature: q, .. }, Turn::Axis { axis, .. }) = (rec.trans, rec.turn)
        else {
            return None;
        };
        let line = self.model.top_level_of(p);
        let line_like = matches!(
            self.model.geoms[line].kind,
            GeomKind::Line | GeomKind::Segment
        );
        if q == p || !line_like || self.model.top_level_of(q) != line || !self.dir_known(normal) {
            return None;
        }
        // The line's constraint with a circle (`relation::decompose`), its direction already
        // turned square to the normal.
        let c = &self.model.constraints[r.constraint];
        use gcs_lang::constraints::ConstraintKind as K;
        let with_circle = matches!(c.kind, K::Distance | K::Tangent)
            && c.args.first() == Some(&line)
            && (c.args.get(1)).is_some_and(|&b| self.model.geoms[b].kind == GeomKind::Circle);
        let dir = self.model.dir_feature(line)?;
        (with_circle && self.made_square(dir, normal) && self.direction(normal) == axis)
            .then_some(q)
    }
}
