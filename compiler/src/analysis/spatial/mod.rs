//! Space's module of the analysis: the geometry vocabulary of 3d models, after TLA (003).
//!
//! A cluster's record is TLA's: its translational DOF with the invariant point or the locus a
//! feature is held on ([`Trans`]: free, a feature on a [`Locus`] (a line, circle, plane,
//! sphere, cylinder, that is a point at a distance from a line, or torus), a pivot, fixed) and
//! its rotational DOF with the invariant axis ([`Turn`]: free, about one axis, known);
//! [`Shape`] says what the cluster's own geometry leaves free besides (a plane, a line, a
//! segment of free length, a circle of free size and normal). Action analysis moves the side of
//! a relation that is not known with the freedom its record leaves, by the brick's fragments:
//! translate a point onto a point or the nearest point of a locus; rotate about the pivot
//! around `v1 x v2` (the shortest turn) to bring a point onto a point or onto where its sphere
//! meets a locus; rotate about the invariant axis by the angle between perpendiculars; turn a
//! direction onto a direction, or about the axis to it; slide a feature along its locus to
//! where it meets another. The same point on two loci of space is where they meet (the
//! runtime's 3d intersection table), with a branch variable where there are two roots.
//!
//! Covered: bodies with markers and member points, points, vectors, lines, planes, segments
//! and circles of space, fixed or moving, with every 3d constraint form of the language (the
//! joints as the conjunctions [`relation`] makes of them). The 3d construction checker
//! (`compiler/bench/tests/construction3d.rs`, its table in `docs/FRAGMENTS3D.md`) lists what the
//! analysis does for each state and form. A constraint the analysis cannot cover is reported
//! per constraint as not analysed in 3d yet, never dropped.
//!
//! # Records
//!
//! A record also keeps invariant the directions and points it does not name: a body's
//! features parallel to its axis feature, its points on the axis through its pivot. A line
//! that moves (`Shape::Line`) has four DOF (sliding along and turning about itself move
//! nothing); a segment of free length or a circle of free size (`Shape::Segment`,
//! `Shape::Circle`: centre, normal, radius) has six until it is sized.
//!
//! # Action analysis, the brick's fragments and their kin
//!
//! - `move_point`: translate onto a point or the nearest point of a locus; rotate about the
//!   pivot around `v1 x v2` (`RotationAxis::Shortest`) to where its sphere meets the target;
//!   rotate about the invariant axis (`RotationAxis::Along`) to where its circle meets it;
//!   slide a feature held on a locus to where the locus, moved with it, meets the target (a
//!   branch where there are two roots).
//! - `turn_onto`: a direction onto a direction, by the shortest turn or about the axis,
//!   checked where the axis' cone must agree. A free vector's, plane's or line's angle to a
//!   known direction turns it the least onto the cone (`SpatialOp::ConeTurn`), then about that
//!   direction.
//! - Turns a z axis cannot decide alone. A turn about an axis that must take a marker's z and x
//!   axes to theirs (offset_x, prismatic, weld, and a helical joint on a body held at a point, the
//!   x axis' target at the advance where the z axis' turn takes the marker) reads its angle off
//!   both (`SpatialOp::AngleAboutBoth`). One that must take a joint's point onto a line or a plane,
//!   where the slide the cluster has left brings it home, refines its angle on the point too
//!   (`SpatialOp::TurnReaching`; a helical joint's coupling likewise, `plan::Reach::Helix`; on a
//!   screw, where the helix's slide for each trial turn carries the point or marker,
//!   `runtime::fragment3::Screw`). A z axis nearly along the turn's axis then does not decide the
//!   turn alone; the turn is made by the angle measured (`SpatialOp::RotateBy`).
//! - Midpoints and mirror planes: a known segment's middle, an end reflected through a known
//!   midpoint, an image across a known plane.
//! - Planes that move (`Shape::Plane`): at a distance from a known point a plane may only turn
//!   about it, from a second one about the line through both, and a third places it, a
//!   branch: 004's point-plane clusters in closed form (`SpatialOp::PlaneTurn`,
//!   `SpatialOp::PlaneAxisTurn`).
//! - Lines that move: through a known point a line may only turn about it, onto a second
//!   (`SpatialOp::Aligned` keeps its sense); parallel to a known direction it is placed by a point.
//!   A line whose direction is known passes at a distance from a known point by sliding onto the
//!   cylinder about the point along its direction; held in a plane along its direction, onto one of
//!   the two lines the plane cuts the cylinder in (`Meet::PlaneCylinder`, a branch). A line that
//!   only turns about an axis through a known point of it (a segment held at an end, a line through
//!   a point) turns until it passes a circle's centre at the distance (`SpatialOp::PassingAngle`);
//!   turned square to a circle's normal about a pivot, it lies in the circle's plane when the pivot
//!   does (a check).
//! - Segments of free length: an end to a point translates the segment, the other end to a
//!   point then turns it about the first, sets its length (`Op::SetDim`) and, when the end
//!   held was its end, moves it back; a `length` sets it the same way (`Relation::Size`).
//! - Circles that move: a centre moves one, a normal turns it (turning about its normal then
//!   moves nothing), a `radius` or an `equal` with a sized circle sets its radius
//!   (`Relation::Size`, `Relation::SameSize`, also for segments); with its centre held it
//!   passes through a known point by the least turn that puts the point in its plane and the
//!   radius that reaches it (`circle_through`). A sized circle whose normal is known is carried
//!   by the least translation through a point or to a distance from it (`carry_circle`), and
//!   one held at its centre tilts the least to put a point at a distance (`tilt_circle`,
//!   `SpatialOp::TiltToDistance`).
//!
//! # Locus analysis
//!
//! 003's locus table (`locus_of`: the pivot's sphere, the axis' circle, the locus a feature is
//! held on); two of them met, a pseudo-marker, each cluster then moved to it. A point on a
//! fixed circle of space has that circle as its locus. A line meets a circle of space where it
//! crosses the circle's plane (one root, refused off the circle), and through the circle's
//! sphere only when it lies in that plane (`runtime::intersect3d::line_circle`).
//!
//! # Defaults and grounding
//!
//! Each default has a meaning and is read from where the constraints leave it: the idle turn about
//! an axis (`{body}_spin_angle`); a free point's coordinates; a feature's two coordinates on the
//! plane, sphere or cylinder it is held on (`runtime::locus3d::Surface`, `SpatialOp::SurfaceParam`,
//! `SpatialOp::SurfacePoint`); a body's turns about the world's axes; a free direction's two turns
//! across itself (`{geom}_tilt_angle`, `{geom}_roll_angle`; a third, about itself, would move
//! nothing), for a vector, a line, a plane or a sized circle's normal; a plane's place along its
//! normal; a segment's length or a circle's radius first, and none while a relation still to come
//! can set it. Each turn by a default is an `SpatialOp::RotateBy`.
//!
//! A model with nothing fixed is grounded at a point, with the direction to a second and the
//! plane of a third held as sketched; its branches on that line and plane are `symmetric`
//! (the same assembly turned: the search for every assembly keeps the sketch's).
//!
//! The module is split by concern, each file an `impl Builder<'_, Spatial>` block of its own:
//! `record.rs` the record; `action.rs` action analysis, one helper per kind of relation, over
//! the fragments of `point.rs` (point moves), `turn.rs` (direction turns), `joint.rs` (what a
//! joint's other relations ask of a turn about an axis), `plane.rs` (planes that move, lines
//! in a plane), `circle.rs` (circles that move), `size.rs` (lengths and radii) and
//! `sketcher.rs` (midpoints and mirrors); `locus.rs` locus analysis and the loci of space;
//! `check.rs` the relations that are run-time checks and the registers relations read;
//! `defaults.rs` and `ground.rs` the freedoms no constraint fixes. This file keeps the
//! `Geometry` impl and a body's constant geometry (its local points and directions).

mod action;
mod chain_ends;
mod check;
mod circle;
mod defaults;
mod ground;
mod joint;
mod locus;
mod plane;
mod point;
mod record;
pub mod relation;
mod size;
mod sketcher;
mod subchain;
mod three_circles;
mod turn;

use super::driver::Builder;
use super::geometry::{self, Geometry, Invariants};
use super::Unsupported;
use crate::config::{Config, D3};
use crate::plan::{Reg, Residual};
use gcs_lang::model::{GeomId, Owner, Part, Sketch};
use gcs_lang::Model;
use gcs_runtime::tol;
pub use record::{Locus, Record, Shape, Trans, Turn};
use relation::Relation;

/// A relation of space with its constraint.
pub(crate) type Rel = geometry::Rel<Relation>;

/// The geometry of space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spatial;

impl Geometry for Spatial {
    type Record = Record;
    type Relation = Relation;

    /// SOLVE-LOOP's limit in space (000, Appendix A.2).
    const MAX_LOOP: usize = 6;

    fn decompose(
        model: &Model,
    ) -> Result<(Vec<Rel>, Vec<Unsupported>), crate::analysis::Unreadable> {
        let params = model.default_params();
        let sketch = Config::<D3>::from_sketch(model, &params)
            .map_err(|b| crate::analysis::Unreadable::sketch(model, b))?;
        Ok(relation::decompose(model, &sketch))
    }

    fn features(relation: &Relation) -> Vec<GeomId> {
        relation.features()
    }

    fn is_dimension(_: &Relation) -> bool {
        false
    }

    fn record(model: &Model, g: GeomId) -> Record {
        Record::new(model, g)
    }

    fn action(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.action(r)
    }

    fn implied(b: &Builder<'_, Self>, r: &Relation) -> bool {
        b.implied(r)
    }

    fn locus(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.locus(r)
    }

    fn residual(b: &mut Builder<'_, Self>, relation: &Relation) -> Residual {
        b.residual(relation)
    }

    fn ground(b: &mut Builder<'_, Self>) {
        b.ground_if_nothing_fixed();
    }

    fn share_pivot(b: &Builder<'_, Self>, a: usize, other: usize) -> bool {
        b.share_pivot(a, other)
    }

    fn subchains(b: &mut Builder<'_, Self>) -> bool {
        b.planar_subchain()
            || b.pivoted_pair()
            || b.three_circle_chain()
            || b.planar_chain_between_turns()
    }

    const LOOK_AHEAD: bool = true;

    fn kept_in_orbit_plane(b: &Builder<'_, Self>, axis: GeomId, point: GeomId) -> bool {
        b.kept_in_orbit_plane(axis, point)
    }

    fn default(b: &mut Builder<'_, Self>, candidates: &[usize]) -> bool {
        candidates.iter().any(|&k| b.default_on(k))
    }

    fn default_leaves_degenerate(b: &Builder<'_, Self>, k: usize) -> bool {
        b.default_leaves_degenerate(k)
    }
}

impl Builder<'_, Spatial> {
    /// For each pair of a direction feature and a register holding a direction (or a line),
    /// the absolute cosine of their angle when the plan written so far runs on the sketch
    /// (NaN where either has no length there). Measuring the features writes steps, so it is
    /// done on a copy whose plan is only read. `None` where the plan does not run. What a
    /// choice the analysis is about to make reads of the sketch (whether what follows is
    /// regular there).
    pub(super) fn sketch_cosines(&self, pairs: &[(GeomId, Reg)]) -> Option<Vec<f64>> {
        let probe = self.values?;
        let mut trial = self.clone();
        let regs: Vec<Reg> = (pairs.iter())
            .flat_map(|&(g, r)| [trial.direction(g), r])
            .collect();
        let values = probe(self.model, &trial.plan, &regs)?;
        Some(
            (values.chunks(2))
                .map(|pair| {
                    let norms = dot(pair[0], pair[0]).sqrt() * dot(pair[1], pair[1]).sqrt();
                    if norms > 0.0 {
                        dot(pair[0], pair[1]).abs() / norms
                    } else {
                        f64::NAN
                    }
                })
                .collect(),
        )
    }
}

/// A member point's or marker's constant local coordinates in its body.
fn local_point(model: &Model, f: GeomId) -> Option<[f64; 3]> {
    let g = &model.geoms[f];
    let Owner::Member(_) = g.owner else {
        return None;
    };
    match &g.sketch {
        Sketch::Point(c) | Sketch::Marker { origin: c, .. } => constant(model, c),
        _ => None,
    }
}

/// A direction feature's constant local direction in its body (not normalized): a member
/// vector, or a marker's z axis or its x axis made perpendicular to z.
fn local_dir(model: &Model, v: GeomId) -> Option<[f64; 3]> {
    let g = &model.geoms[v];
    match (g.owner, &g.sketch) {
        (Owner::Member(_), Sketch::Vector(c)) => constant(model, c),
        (Owner::Part(marker, part), _) => {
            let Sketch::Marker { z, x, .. } = &model.geoms[marker].sketch else {
                return None;
            };
            let z = constant(model, z.as_ref()?)?;
            match part {
                Part::AxisZ => Some(z),
                Part::AxisX => {
                    let x = constant(model, x)?;
                    let k = dot(x, z) / dot(z, z);
                    Some([x[0] - k * z[0], x[1] - k * z[1], x[2] - k * z[2]])
                }
                _ => None,
            }
        }
        _ => None,
    }
}

fn constant(model: &Model, c: &[gcs_lang::expr::ExprId]) -> Option<[f64; 3]> {
    if !c.iter().all(|&e| model.exprs.is_constant(e)) {
        return None;
    }
    let v = |i: usize| c.get(i).map_or(0.0, |&e| model.exprs.eval(e, &[]));
    Some([v(0), v(1), v(2)])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether `a` and `b` are parallel (either sense), to rounding.
fn parallel(a: [f64; 3], b: [f64; 3]) -> bool {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    dot(c, c).sqrt() <= tol::ANGLE * dot(a, a).sqrt() * dot(b, b).sqrt()
}

/// Whether direction features `a` and `b` of one body are parallel in it, whatever it does.
pub(super) fn same_direction(model: &Model, a: GeomId, b: GeomId) -> bool {
    model.top_level_of(a) == model.top_level_of(b)
        && matches!((local_dir(model, a), local_dir(model, b)), (Some(u), Some(v)) if parallel(u, v))
}

/// Whether point `f` lies on the axis through point `g` along direction `a`, all of one body.
fn on_axis(model: &Model, g: GeomId, a: GeomId, f: GeomId) -> bool {
    let top = model.top_level_of(g);
    if model.top_level_of(a) != top || model.top_level_of(f) != top {
        return false;
    }
    match (
        local_point(model, g),
        local_point(model, f),
        local_dir(model, a),
    ) {
        (Some(p), Some(q), Some(d)) => {
            let w = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            dot(w, w) == 0.0 || parallel(w, d)
        }
        _ => false,
    }
}

/// Where a point feature must go.
#[derive(Clone, Copy, Debug)]
enum Target {
    /// A known point.
    Point(Reg),
    /// A locus.
    On(Locus),
}

impl Builder<'_, Spatial> {
    /// Whether direction feature `v` is invariant.
    fn dir_known(&self, v: GeomId) -> bool {
        let rec = self.record(v);
        rec.grounded()
            || rec.turn == Turn::Known
            || matches!(rec.turn, Turn::Axis { feature: Some(f), .. }
                if f == v || same_direction(self.model, f, v))
    }

    /// Whether features `a` and `b` move together (one cluster: rigid).
    fn together(&self, a: GeomId, b: GeomId) -> bool {
        self.cluster(a) == self.cluster(b)
    }
}
