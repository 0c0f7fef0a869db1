//! The plane's module of the analysis: the geometry vocabulary of 2d models.
//!
//! The record of a cluster is kept in the canonical form of a rigid frame in the plane: its
//! rotation ([`Rot`]) and its position ([`Pos`]), with a free dimension and the fixed
//! distances of a circle of free radius; [`Record`]'s `table2` gives the slots of Kramer's
//! Table 2. Action analysis takes a relation one of whose sides is known ("fixed enough") and
//! moves the other side's cluster with the freedom its record leaves (translate, rotate about
//! a pivot, slide along a locus, scale), then updates the record. Locus analysis takes a
//! coincidence between two partially fixed clusters, asks the locus table where each feature
//! can lie, and intersects the two loci (a branch variable). Relations whose both sides are
//! already known become run-time checks. Circles of free radius ([`circle`]) and segments of
//! free length ([`segment`]) have fragments of their own, as have `equal`, `midpoint` and
//! `symmetric` (`sketcher.rs`) and the defaults (`defaults.rs`); [`relation`] decomposes the
//! constraints.
//!
//! The fragments here, by what they move: `move_feature` translates, rotates about a pivot,
//! slides along a locus, or takes the least motion; `turn` turns a direction onto a
//! direction; `turn_line_past` turns a line about a pivot until it passes a point at a
//! distance (`PlanarOp::PassingDir`); a cluster sliding on a locus and turning is taken to a point
//! where its locus meets a circle; a lone line that must pass two known points at distances
//! records each as a [`Pass`] until the second fixes its direction. Locus analysis is
//! `locus_of` (the locus table, and the segment ends that a free length slides along a known
//! line) and `intersect`, each branch with its geometric meaning. A model with nothing fixed is
//! grounded (`ground`).
//!
//! A record remembers what makes a later contact exact: a cluster put on its own line keeps
//! that line known while it slides (`along`); a circle keeps the lines made tangent to it and
//! the joint it passes through (`tangent`, `joint`), and a segment the circle its end was put
//! on (`on_circle`). A touching contact is then built as the foot of a perpendicular, not as
//! the double root of an intersection, whose rounding grows to its square root.
//!
//! The module is split by concern, each file an `impl Builder<'_, Planar>` block of its own:
//! `record.rs` the record; `action.rs` action analysis, over the fragments of `point.rs`
//! (point moves), `turn.rs` (direction turns, lines placed by the points they pass),
//! [`circle`], [`segment`] and `sketcher.rs` (equal dimensions, midpoints, mirrors);
//! `locus.rs` locus analysis and the loci it intersects; `check.rs` the relations that are
//! run-time checks and the registers relations read; `defaults.rs` and `ground.rs` the
//! freedoms no constraint fixes. This file keeps the `Geometry` impl, the sketch as the
//! decomposition sees it, and small helpers the files share.

mod action;
mod check;
pub mod circle;
mod defaults;
mod ground;
mod linear;
mod locus;
mod point;
mod record;
pub mod relation;
pub mod segment;
mod sketcher;
mod turn;

use super::driver::Builder;
use super::geometry::{self, Geometry};
use super::Unsupported;
use crate::config::{Config, V2};
use crate::plan::{Reg, Residual};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part};
use gcs_lang::Model;
pub use record::{Locus, Pass, Pos, Record, Rot};
use relation::{Dir, Relation};

/// A relation of the plane with its constraint.
pub(crate) type Rel = geometry::Rel<Relation>;

/// The geometry of the plane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Planar;

impl Geometry for Planar {
    type Record = Record;
    type Relation = Relation;

    /// SOLVE-LOOP's limit in the plane (000, Appendix A.2).
    const MAX_LOOP: usize = 3;

    fn decompose(
        model: &Model,
    ) -> Result<(Vec<Rel>, Vec<Unsupported>), crate::analysis::Unreadable> {
        let params = model.default_params();
        let sketch = Config::from_sketch(model, &params)
            .map_err(|b| crate::analysis::Unreadable::sketch(model, b))?;
        let view = SketchOf {
            model,
            config: &sketch,
        };
        Ok(relation::decompose(model, &view))
    }

    fn features(relation: &Relation) -> Vec<GeomId> {
        relation.features()
    }

    fn is_dimension(relation: &Relation) -> bool {
        matches!(relation, Relation::Dim { .. })
    }

    fn record(model: &Model, g: GeomId) -> Record {
        Record::new(model, g)
    }

    fn action(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.no_double_root(r, |b, r| b.action(r))
    }

    fn implied(b: &Builder<'_, Self>, r: &Relation) -> bool {
        b.implied(r)
    }

    fn locus(b: &mut Builder<'_, Self>, r: &Rel) -> bool {
        b.no_double_root(r, |b, r| b.locus(r))
    }

    fn residual(b: &mut Builder<'_, Self>, relation: &Relation) -> Residual {
        b.residual(relation)
    }

    fn ground(b: &mut Builder<'_, Self>) {
        b.ground_if_nothing_fixed();
    }

    fn linear(b: &mut Builder<'_, Self>) -> bool {
        b.linear_stage()
    }

    fn default(b: &mut Builder<'_, Self>, candidates: &[usize]) -> bool {
        b.add_default(candidates)
    }
}

/// The sketch configuration, as the decomposition sees it.
struct SketchOf<'a> {
    model: &'a Model,
    config: &'a Config,
}

impl relation::SketchView for SketchOf<'_> {
    fn angle(&self, u: Dir, v: Dir) -> f64 {
        let d = |x: Dir| match x {
            Dir::Feature(g) => self.config.dir(self.model, g),
            Dir::World(x, y) => V2::new(x, y),
        };
        let (a, b) = (d(u), d(v));
        (a.x * b.y - a.y * b.x).atan2(a.dot(&b))
    }
    fn point(&self, p: GeomId) -> [f64; 2] {
        let q = self.config.point(self.model, p);
        [q.x, q.y]
    }
    fn dir(&self, v: GeomId) -> [f64; 2] {
        let d = self.config.dir(self.model, v);
        [d.x, d.y]
    }
    fn radius(&self, c: GeomId) -> f64 {
        self.config.dim(c)
    }
}

/// A target for a feature: a point or a locus.
#[derive(Clone, Copy, Debug)]
enum Target {
    Point(Reg),
    On(Locus),
}

/// The register holding a locus.
fn locus_reg(l: Locus) -> Reg {
    match l {
        Locus::Line(r) | Locus::Circle(r) | Locus::Conic(r) => r,
    }
}

/// How a sentence names the feature a cluster is pinned at ([`Pos::Pivot`]): a point feature
/// by its name; a segment pinned at its midpoint (by `midpoint`), which is no feature of it,
/// is its own pivot feature, named for its midpoint.
fn pivot_name(model: &Model, f: GeomId) -> String {
    let g = &model.geoms[f];
    if g.kind == GeomKind::Segment {
        format!("the midpoint of {}", g.name)
    } else {
        g.name.clone()
    }
}

/// The segment a record holds pinned at its midpoint (by `midpoint`, at the register given)
/// while its length is still free: it then turns about that midpoint and is sized about it,
/// so neither end is on a circle about it, and its line is known once its direction is.
fn pinned_at_midpoint(model: &Model, rec: &Record) -> Option<(Reg, GeomId)> {
    match rec.pos {
        Pos::Pivot { at, feature }
            if rec.free_dim == Some(feature) && model.geoms[feature].kind == GeomKind::Segment =>
        {
            Some((at, feature))
        }
        _ => None,
    }
}

/// Whether a feature's position depends on its geom's dimension (a segment's end).
fn depends_on_dim(model: &Model, f: GeomId) -> bool {
    matches!(model.geoms[f].owner, Owner::Part(_, Part::End))
}

/// An angle constant in words: `0`, `pi`, `pi/2`, `-pi/2`.
fn angle_words(c: f64) -> String {
    use std::f64::consts::{FRAC_PI_2, PI};
    if c == 0.0 {
        "0".into()
    } else if c == PI {
        "pi".into()
    } else if c == FRAC_PI_2 {
        "pi/2".into()
    } else if c == -FRAC_PI_2 {
        "-pi/2".into()
    } else {
        crate::plan::fmt_f64(c)
    }
}
