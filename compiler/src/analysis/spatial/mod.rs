//! Space's module of the analysis: the geometry vocabulary of 3d models, after TLA (003).
//!
//! A cluster's record is TLA's: its translational DOF with the invariant point or the locus
//! a feature is held on ([`Trans`]: free, a feature on a line, circle, plane or sphere, a
//! pivot, fixed) and its rotational DOF with the invariant axis ([`Turn`]: free, about one
//! axis, known). Action analysis moves the side of a relation that is not known with the
//! freedom its record leaves, by the brick's fragments: translate a point onto a point or
//! the nearest point of a locus; rotate about the pivot around `v1 x v2` (the shortest turn)
//! to bring a point onto a point or onto where its sphere meets a locus; rotate about the
//! invariant axis by the angle between perpendiculars; turn a direction onto a direction, or
//! about the axis to it; slide a feature along its locus to where it meets another. The same
//! point on two loci of space is where they meet (the runtime's 3d intersection table), with
//! a branch variable where there are two roots.
//!
//! Covered so far: bodies with markers and member points, free points and vectors, against
//! fixed points, lines, planes and other bodies, with coincident, distance (point-point,
//! point-plane), `on` (a point on a line or plane), in-line, in-plane, parallel-z, offset-x
//! and the lower pairs built of them (revolute, prismatic, cylindrical, spherical, planar).
//! What is not (angles between directions of space, helical joints, segments, circles and
//! planes that move, loops of partially fixed bodies, defaults) is reported per constraint,
//! never dropped.
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

    fn decompose(model: &Model) -> Result<(Vec<Rel>, Vec<Unsupported>), String> {
        let params = model.default_params();
        let sketch = Config::<D3>::from_sketch(model, &params).map_err(|b| {
            format!(
                "the sketch of `{}` is invalid: {}",
                model.geoms[b.geom].name, b.what
            )
        })?;
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

    fn default(b: &mut Builder<'_, Self>, candidates: &[usize]) -> bool {
        candidates.iter().any(|&k| b.default_on(k))
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
fn same_direction(model: &Model, a: GeomId, b: GeomId) -> bool {
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
