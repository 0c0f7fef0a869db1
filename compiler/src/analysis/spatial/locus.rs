//! Locus analysis (003's locus table) and the loci of space. A point feature of a partially
//! fixed cluster sweeps a curve or surface with the freedom its record leaves (`locus_of`):
//! the sphere about its pivot, the circle about its axis, or the locus it is held on, moved
//! with it (`shifted`). Two such points to coincide go where their loci meet (`locus`,
//! `meet`): a root of the runtime's 3d intersection table, with a branch variable where there
//! are two. Two directions of clusters that each turn about a known axis, to be parallel (a
//! wrist's middle joint), meet where their cones about those axes do (`turn.rs`,
//! `parallel_about_two_axes`). The lines, planes and cylinders relations put a point on are
//! built here too.

use super::relation::{Length, Relation};
use super::{Locus, Rel, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Meet, Op, Reg, SpatialOp, Ty};
use gcs_lang::model::{GeomId, GeomKind};

impl Builder<'_, Spatial> {
    /// Locus analysis: a point of each of two partially fixed clusters to coincide. Each
    /// lies on the locus its cluster's freedom sweeps (003's locus table): the pivot's sphere
    /// or the axis' circle, the line, circle, plane or sphere it is held on (moved with it);
    /// where the two loci meet is a pseudo-marker (a branch variable where two), to which
    /// each cluster is then moved by action analysis. Two parallel directions, each turning
    /// about a known axis, meet on their cones in the same way.
    pub(super) fn locus(&mut self, r: &Rel) -> bool {
        if let Relation::Parallel { u, v, sense } = r.relation {
            return self.parallel_about_two_axes(u, v, sense, r);
        }
        let Relation::PointPoint { a, b, d: None } = r.relation else {
            return false;
        };
        if self.together(a, b) {
            return false;
        }
        let (Some(la), Some(lb)) = (self.locus_of(a), self.locus_of(b)) else {
            return false;
        };
        let near = self.point(a);
        let Some(Target::Point(p)) = self.meet(la, Target::On(lb), near, r) else {
            return false;
        };
        let first = Rel {
            last: false,
            ..r.clone()
        };
        self.move_point(a, Target::Point(p), &first) && self.move_point(b, Target::Point(p), r)
    }

    /// The locus point feature `f` sweeps with the freedom its cluster has, if it is a curve
    /// or surface of the table (not the whole of space).
    fn locus_of(&mut self, f: GeomId) -> Option<Locus> {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        if !rec.movable() || self.point_known(f) {
            return None;
        }
        match (rec.trans, rec.turn) {
            (Trans::On { feature, locus }, _) if feature == f => Some(locus),
            (Trans::On { feature, locus }, Turn::Known | Turn::None) => {
                Some(self.shifted(locus, feature, f))
            }
            (Trans::Pivot { at, feature }, Turn::Free) => {
                let from = self.point(f);
                Some(Locus::Sphere(self.pivot_sphere(at, feature, f, from)))
            }
            (Trans::Pivot { at, .. }, Turn::Axis { axis, .. }) => {
                let from = self.point(f);
                Some(Locus::Circle(self.orbit(at, axis, f, from)))
            }
            _ => None,
        }
    }

    /// The sphere about pivot `at` (of feature `g`) that point `f`, now at `from`, keeps to
    /// while its cluster turns about the pivot.
    pub(super) fn pivot_sphere(&mut self, at: Reg, g: GeomId, f: GeomId, from: Reg) -> Reg {
        let radius = self.model.constant_distance(g, f);
        let words = format!(
            "the sphere about {} through {}",
            self.word(at),
            self.name(f)
        );
        self.value(
            SpatialOp::SphereThrough {
                center: at,
                through: from,
                radius,
            },
            Ty::Sphere,
            words,
        )
    }

    /// The circle point `f`, now at `from`, sweeps turning about the axis through `at`.
    pub(super) fn orbit(&mut self, at: Reg, axis: Reg, f: GeomId, from: Reg) -> Reg {
        let words = format!(
            "the circle {} sweeps about the axis through {} along {}",
            self.name(f),
            self.word(at),
            self.word(axis)
        );
        self.value(
            SpatialOp::Orbit {
                pivot: at,
                axis,
                through: from,
            },
            Ty::Circle,
            words,
        )
    }

    pub(super) fn plane_words(&self, base: GeomId, normal: GeomId, offset: Option<Reg>) -> String {
        let moved = offset.map_or(String::new(), |o| {
            format!(" moved {} along it", self.word(o))
        });
        if self.model.geoms[base].kind == GeomKind::Plane {
            format!("plane {}{moved}", self.name(base))
        } else {
            format!(
                "the plane through {} normal to {}{moved}",
                self.name(base),
                self.name(normal)
            )
        }
    }

    pub(super) fn line(&mut self, point: Reg, dir: Reg, words: String) -> Reg {
        self.value(
            Op::Line {
                point,
                dir,
                offset: None,
            },
            Ty::Line,
            words,
        )
    }

    /// Locus `locus` of feature `g`, moved by `f - g`: where `f` goes when the cluster
    /// translates keeping `g` on it.
    pub(super) fn shifted(&mut self, locus: Locus, g: GeomId, f: GeomId) -> Locus {
        let (pg, pf) = (self.point(g), self.point(f));
        let words = format!("{} moved with {}", self.word(locus.reg()), self.name(f));
        match locus {
            Locus::Line(l) => Locus::Line(self.value(
                Op::ParallelLine {
                    line: l,
                    through: pf,
                },
                Ty::Line,
                words,
            )),
            Locus::Plane(p) => Locus::Plane(self.value(
                SpatialOp::ParallelPlane {
                    plane: p,
                    through: pf,
                },
                Ty::Plane,
                words,
            )),
            Locus::Sphere(s) => Locus::Sphere(self.value(
                SpatialOp::ShiftedSphere {
                    sphere: s,
                    from: pg,
                    to: pf,
                },
                Ty::Sphere,
                words,
            )),
            Locus::Circle(c) => Locus::Circle(self.value(
                Op::ShiftedCircle {
                    circle: c,
                    from: pg,
                    to: pf,
                },
                Ty::Circle,
                words,
            )),
            Locus::Cylinder(c) => Locus::Cylinder(self.value(
                SpatialOp::ShiftedCylinder {
                    cylinder: c,
                    from: pg,
                    to: pf,
                },
                Ty::Cylinder,
                words,
            )),
            Locus::Torus(t) => Locus::Torus(self.value(
                SpatialOp::ShiftedTorus {
                    torus: t,
                    from: pg,
                    to: pf,
                },
                Ty::Torus,
                words,
            )),
        }
    }

    /// Where a feature on locus `own` meets `target`: the target point (which must be on it,
    /// or the constraint is inconsistent by the gap), a root of their intersection (a branch
    /// variable where two), or the curve two surfaces share. `None` for pairs with no
    /// construction here (two curves of space, which meet only by accident).
    pub(super) fn meet(
        &mut self,
        own: Locus,
        target: Target,
        near: Reg,
        r: &Rel,
    ) -> Option<Target> {
        self.meet_held(own, target, near, r, false)
    }

    /// [`Builder::meet`]; `held`: `own` is the line or plane a model with nothing fixed is
    /// held by, whose roots are one assembly turned as a whole (a symmetric branch).
    pub(super) fn meet_held(
        &mut self,
        own: Locus,
        target: Target,
        near: Reg,
        r: &Rel,
        held: bool,
    ) -> Option<Target> {
        let other = match target {
            Target::Point(x) => {
                let words = self.word(x);
                let at = self.value(
                    Op::Onto {
                        locus: own.reg(),
                        point: x,
                        constraint: r.constraint,
                    },
                    Ty::Point,
                    words,
                );
                return Some(Target::Point(at));
            }
            Target::On(l) => l,
        };
        use Locus as L;
        let (meet, a, b) = match (own, other) {
            (L::Line(a), L::Plane(b)) | (L::Plane(b), L::Line(a)) => (Meet::LinePlane, a, b),
            (L::Line(a), L::Sphere(b)) | (L::Sphere(b), L::Line(a)) => (Meet::LineSphere, a, b),
            (L::Circle(a), L::Plane(b)) | (L::Plane(b), L::Circle(a)) => (Meet::CirclePlane, a, b),
            (L::Circle(a), L::Sphere(b)) | (L::Sphere(b), L::Circle(a)) => {
                (Meet::CircleSphere, a, b)
            }
            (L::Sphere(a), L::Sphere(b)) => (Meet::SphereSphere, a, b),
            (L::Sphere(a), L::Plane(b)) | (L::Plane(b), L::Sphere(a)) => (Meet::SpherePlane, a, b),
            (L::Plane(a), L::Plane(b)) => (Meet::PlanePlane, a, b),
            (L::Circle(a), L::Circle(b)) => (Meet::CircleCircle, a, b),
            (L::Line(a), L::Circle(b)) | (L::Circle(b), L::Line(a)) => (Meet::LineCircle, a, b),
            (L::Line(a), L::Cylinder(b)) | (L::Cylinder(b), L::Line(a)) => {
                (Meet::LineCylinder, a, b)
            }
            _ => return None,
        };
        let (wa, wb, wn) = (self.word(a), self.word(b), self.word(near));
        let meanings = match meet {
            Meet::LineSphere | Meet::LineCylinder => vec![
                format!("where {wa} enters {wb}, along the line"),
                format!("where {wa} leaves {wb}, along the line"),
            ],
            Meet::CirclePlane => vec![
                format!("the crossing of {wa} with {wb} first along the common line of their planes"),
                "the other crossing, second along that line".to_string(),
            ],
            Meet::CircleSphere => vec![
                format!("the crossing of {wa} with {wb} counter-clockwise of the sphere's centre about the circle's axis"),
                "the other crossing, clockwise of it".to_string(),
            ],
            Meet::CircleCircle => vec![
                format!("the crossing of {wa} and {wb} to the left of the line of their centres, seen down the first's axis (or first along the line their planes share)"),
                "the other crossing".to_string(),
            ],
            Meet::LineCircle => vec![
                format!("the first crossing of {wa} with {wb}, along the line"),
                "the second crossing, along the line".to_string(),
            ],
            _ => vec![format!("where {wa} and {wb} meet")],
        };
        let b = if meet == Meet::CircleCircle {
            self.coplanar_orbits(a, b, r)
        } else {
            b
        };
        let branch = self.branch(r.constraint, meanings);
        if held {
            self.plan.branches[branch.0 as usize].symmetric = true;
        }
        let ty = meet.result();
        let words = match ty {
            Ty::Point if meet == Meet::LinePlane => format!("where {wa} crosses {wb}"),
            Ty::Point => format!("the meeting point of {wa} and {wb} nearest {wn} in the sketch"),
            Ty::Circle => format!("the circle where {wa} and {wb} meet"),
            _ => format!("the line where {wa} and {wb} meet"),
        };
        let x = self.value(
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint: r.constraint,
                near,
            },
            ty,
            words,
        );
        // A line meets a circle of space where it meets the circle's sphere: the root must
        // then be on the circle itself (it is when they are coplanar), or the loci miss.
        let x = if meet == Meet::LineCircle {
            let words = self.word(x);
            self.value(
                Op::Onto {
                    locus: b,
                    point: x,
                    constraint: r.constraint,
                },
                Ty::Point,
                words,
            )
        } else {
            x
        };
        Some(match Locus::of(x, ty) {
            Some(curve) => Target::On(curve),
            None => Target::Point(x),
        })
    }

    /// Two circles of space meet only by accident, unless their planes are one: two orbits
    /// about axes the model keeps parallel (a planar sub-chain's joints, each body's axes
    /// parallel in it and every revolute keeping its two parallel) lie in parallel planes,
    /// which must be one plane for them to meet. That is one equation. Where a default
    /// displaced it (the sub-chain's plane turned with an arm's base), it is measured signed
    /// before the circles are met, the distance of the second circle's point from the
    /// first's plane, and closes the iteration: a scan of the default's turn brackets every
    /// root, while the circles' meeting exists only at the roots.
    ///
    /// With no default under them, the plan met the plane's equation already (a sub-chain's
    /// plane turned onto its point, a chain's ends closed): the circles are coplanar by
    /// construction, to the rounding of the steps that made them. Near a singular pose that
    /// rounding is amplified past the tolerance two circles of space meet with (a turn about an
    /// axis that the chain's axis is nearly along): so the second circle is taken in the first's
    /// plane, its point brought onto it, which must be within the checks' tolerance.
    ///
    /// Returns the second circle to meet.
    fn coplanar_orbits(&mut self, a: Reg, b: Reg, r: &Rel) -> Reg {
        let orbit = |k: Reg| match self.def(k).map(|s| &s.op) {
            Some(Op::Spatial(SpatialOp::Orbit {
                pivot,
                axis,
                through,
            })) => Some((*pivot, *axis, *through)),
            _ => None,
        };
        let (Some((_, axis_a, through_a)), Some((pivot_b, axis_b, through_b))) =
            (orbit(a), orbit(b))
        else {
            return b;
        };
        let feature = |k: Reg| match self.def(k).map(|s| &s.op) {
            Some(Op::DirOf(g)) => Some(*g),
            _ => None,
        };
        let (Some(fa), Some(fb)) = (feature(axis_a), feature(axis_b)) else {
            return b;
        };
        if !self.kept_parallel(fa, fb) {
            return b;
        }
        if !self.depends_on_default(&[a, b]) {
            let (wa, wb) = (self.word(a), self.word(b));
            let plane = self.value(
                SpatialOp::Plane {
                    point: through_a,
                    normal: axis_a,
                    offset: None,
                },
                Ty::Plane,
                format!("the plane of {wa}"),
            );
            let words = self.word(through_b);
            let on = self.value(
                Op::Onto {
                    locus: plane,
                    point: through_b,
                    constraint: r.constraint,
                },
                Ty::Point,
                words.clone(),
            );
            let moved = self.value(
                Op::Nearest {
                    locus: plane,
                    point: on,
                },
                Ty::Point,
                format!("{words} in the plane of {wa}"),
            );
            return self.value(
                SpatialOp::Orbit {
                    pivot: pivot_b,
                    axis: axis_b,
                    through: moved,
                },
                Ty::Circle,
                format!("{wb}, in the plane of {wa}"),
            );
        }
        let explain = format!(
            "Check that {} and {} lie in one plane, square to their parallel axes ({}).",
            self.word(a),
            self.word(b),
            self.cname(r.constraint)
        );
        self.emit(
            Op::Check {
                constraint: r.constraint,
                residual: crate::plan::Residual::PointPlane {
                    p: through_b,
                    base: through_a,
                    normal: axis_a,
                    d: None,
                },
                guard: false,
            },
            None,
            Vec::new(),
            explain,
        );
        b
    }

    /// See [`crate::analysis::geometry::Geometry::kept_in_orbit_plane`]: `point` is a marker
    /// whose z axis the model keeps parallel to `axis`.
    pub(super) fn kept_in_orbit_plane(&self, axis: GeomId, point: GeomId) -> bool {
        self.z_of(point)
            .is_some_and(|z| self.kept_parallel(axis, z))
    }

    /// Whether the model keeps unit direction features `a` and `b` (marker axes) parallel
    /// whatever it does: linked by parallel relations (a revolute's axes, a `parallel`
    /// constraint) and by axes parallel within one body.
    fn kept_parallel(&self, a: GeomId, b: GeomId) -> bool {
        use super::relation::Relation;
        let model = self.model;
        let is_axis = |g: GeomId| matches!(model.geoms[g].owner, gcs_lang::model::Owner::Part(..));
        if !is_axis(a) || !is_axis(b) {
            return false;
        }
        let links: Vec<(GeomId, GeomId)> = (model.constraints.iter())
            .flat_map(|(c, _)| self.relations_of(c))
            .filter_map(|r| match r {
                Relation::Parallel { u, v, .. } => Some((u, v)),
                _ => None,
            })
            .collect();
        let joined = |x: GeomId, y: GeomId| x == y || super::same_direction(model, x, y);
        let mut reached = vec![a];
        let mut grew = true;
        while grew {
            if reached.iter().any(|&x| joined(x, b)) {
                return true;
            }
            grew = false;
            for &(u, v) in &links {
                let has_u = reached.iter().any(|&x| joined(x, u));
                let has_v = reached.iter().any(|&x| joined(x, v));
                if has_u != has_v {
                    reached.push(if has_u { v } else { u });
                    grew = true;
                }
            }
        }
        false
    }

    /// The cylinder of radius `length` about the line through known point `at` along known
    /// direction `dir`: where a point at that distance from the line lies.
    pub(super) fn cylinder_about(&mut self, at: GeomId, dir: GeomId, length: Length) -> Reg {
        let (point, d) = (self.point(at), self.direction(dir));
        let radius = self.length(length);
        let words = format!(
            "the cylinder of radius {} about the line through {} along {}",
            self.word(radius),
            self.name(at),
            self.name(dir)
        );
        let op = Op::Spatial(SpatialOp::Cylinder {
            point,
            dir: d,
            radius,
        });
        self.value(op, Ty::Cylinder, words)
    }
}
