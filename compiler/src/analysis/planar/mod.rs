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
//! free length ([`segment`]) have fragments of their own.

pub mod circle;
mod defaults;
mod record;
pub mod relation;
pub mod segment;
mod sketcher;

use super::driver::Builder;
use super::geometry::{self, Geometry, Invariants};
use super::Unsupported;
use crate::config::{Config, V2};
use crate::plan::{Meet, Op, Reg, Residual, RotationAxis, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part};
use gcs_lang::Model;
pub use record::{Locus, Pass, Pos, Record, Rot};
use relation::{AngleValue, Dir, Relation};

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

    fn decompose(model: &Model) -> Result<(Vec<Rel>, Vec<Unsupported>), String> {
        let params = model.default_params();
        let sketch = Config::from_sketch(model, &params).map_err(|b| {
            format!(
                "the sketch of `{}` is invalid: {}",
                model.geoms[b.geom].name, b.what
            )
        })?;
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

impl Builder<'_, Planar> {
    /// The register of a direction: a feature's current direction, or a world axis.
    fn dir(&mut self, d: Dir) -> Reg {
        match d {
            Dir::Feature(g) => self.direction(g),
            Dir::World(x, y) => {
                let words = if x != 0.0 { "the X axis" } else { "the Y axis" }.to_string();
                self.value(Op::Axis(x, y), Ty::Vector, words)
            }
        }
    }

    /// The registers and residual of a relation's run-time check.
    fn residual(&mut self, relation: &Relation) -> Residual {
        let model = self.model;
        match *relation {
            Relation::PointPoint { a, b, d } => Residual::PointPoint {
                a: self.point(a),
                b: self.point(b),
                d: d.map(|d| self.expr(d)),
            },
            Relation::PointLine { p, base, dir, d } => Residual::PointLine {
                p: self.point(p),
                base: self.point(base),
                dir: self.direction(dir),
                d: d.map(|d| self.expr(d)),
            },
            Relation::Angle { u, v, angle } => Residual::Angle {
                u: self.dir(u),
                v: self.dir(v),
                angle: self.angle(angle),
            },
            Relation::CircleLine {
                circle,
                base,
                dir,
                gap,
                side,
            } => Residual::CircleLine {
                centre: self.point(model.point_feature(circle)),
                radius: self.dim_of(circle),
                base: self.point(base),
                dir: self.direction(dir),
                gap: gap.map(|g| self.expr(g)),
                side,
            },
            Relation::PointCircle {
                p,
                circle,
                gap,
                outside,
            } => Residual::PointCircle {
                p: self.point(p),
                centre: self.point(model.point_feature(circle)),
                radius: self.dim_of(circle),
                gap: gap.map(|g| self.expr(g)),
                outside,
            },
            Relation::CircleCircle { a, b, gap, mode } => Residual::CircleCircle {
                c1: self.point(model.point_feature(a)),
                r1: self.dim_of(a),
                c2: self.point(model.point_feature(b)),
                r2: self.dim_of(b),
                gap: gap.map(|g| self.expr(g)),
                nesting: mode,
            },
            Relation::Dim { geom, value } => Residual::Dim {
                value: self.dim_of(geom),
                target: self.expr(value),
            },
            Relation::Equal { a, b } => Residual::Dim {
                value: self.dim_of(b),
                target: self.dim_of(a),
            },
            Relation::Midpoint { p, a, b } => Residual::Midpoint {
                p: self.point(p),
                a: self.point(a),
                b: self.point(b),
            },
            Relation::Mirror {
                p, q, base, dir, ..
            } => Residual::Mirror {
                p: self.point(p),
                q: self.point(q),
                base: self.point(base),
                dir: self.direction(dir),
            },
        }
    }

    /// The register of an angle a relation asks for.
    fn angle(&mut self, angle: AngleValue) -> Reg {
        match angle {
            AngleValue::Expr(e) => self.expr(e),
            AngleValue::Const(c) => self.value(Op::Const(c), Ty::Scalar, angle_words(c)),
        }
    }

    /// Whether a relation is implied by what is known (both its sides, or one rigid cluster
    /// holding both): then it only needs a run-time check.
    fn implied(&self, relation: &Relation) -> bool {
        let rigid_together = |a: GeomId, b: GeomId| {
            self.cluster(a) == self.cluster(b)
                && self.clusters[self.cluster(a)].record.free_dim.is_none()
        };
        let line_known = |base: GeomId, dir: GeomId| self.line_fixed(base, dir);
        let placed = |circle: GeomId| self.record(circle).grounded();
        match *relation {
            Relation::PointPoint { a, b, .. } => {
                (self.point_known(a) && self.point_known(b)) || rigid_together(a, b)
            }
            Relation::PointLine { p, base, dir, .. } => {
                (line_known(base, dir) && self.point_known(p)) || rigid_together(p, base)
            }
            Relation::Angle { u, v, .. } => {
                (self.dir_known(u) && self.dir_known(v))
                    || matches!((u, v), (Dir::Feature(x), Dir::Feature(y)) if self.cluster(x) == self.cluster(y))
            }
            Relation::Dim { geom, .. } => self.record(geom).free_dim != Some(geom),
            Relation::PointCircle { p, circle, .. } => placed(circle) && self.point_known(p),
            Relation::CircleLine {
                circle, base, dir, ..
            } => placed(circle) && line_known(base, dir),
            Relation::CircleCircle { a, b, .. } => placed(a) && placed(b),
            Relation::Equal { a, b } => self.dim_known(a) && self.dim_known(b),
            Relation::Midpoint { p, a, b } => {
                (self.point_known(p) && self.point_known(a) && self.point_known(b))
                    || (rigid_together(p, a) && rigid_together(a, b))
                    // Its segment already pinned at its midpoint: that midpoint is known.
                    || (self.point_known(p)
                        && matches!(self.record(a).pos,
                            Pos::Pivot { feature, .. } if feature == self.model.top_level_of(a)
                                && self.model.geoms[feature].kind == GeomKind::Segment))
            }
            Relation::Mirror {
                p, q, base, dir, ..
            } => {
                (line_known(base, dir) && self.point_known(p) && self.point_known(q))
                    || (rigid_together(p, q) && rigid_together(p, base))
            }
        }
    }

    /// Whether the line through `base` along `dir` is known: a known point on it and its
    /// direction, or a cluster that can only slide along it.
    fn line_fixed(&self, base: GeomId, dir: GeomId) -> bool {
        self.dir_known(Dir::Feature(dir))
            && (self.line_point(base).is_some() || self.record(base).along == Some(dir))
    }

    /// A point on the line of (`base`, its direction) whose place on it is known, or that
    /// is on it wherever the line's freedom takes it: `base` itself, or the other end of the
    /// same segment, or the start of a segment pinned at its midpoint.
    fn line_point(&self, base: GeomId) -> Option<GeomId> {
        if self.point_known(base) {
            return Some(base);
        }
        // A segment pinned at its midpoint, its length free: its line goes through the
        // midpoint whatever its length, so wherever its start is now is on it.
        if let Some((_, seg)) = pinned_at_midpoint(self.model, self.record(base)) {
            if self.model.part(seg, Part::Start) == Some(base) {
                return Some(base);
            }
        }
        match self.model.geoms[base].owner {
            Owner::Part(s, Part::Start) => self
                .model
                .part(s, Part::End)
                .filter(|&e| self.point_known(e)),
            _ => None,
        }
    }

    /// Whether a direction is known: a world axis, or a feature of a cluster whose rotation
    /// is invariant (or that has none).
    fn dir_known(&self, d: Dir) -> bool {
        match d {
            Dir::World(..) => true,
            Dir::Feature(g) => matches!(self.record(g).rot, Rot::Known | Rot::None),
        }
    }

    /// Grounds a model with nothing fixed: holds the geom with the most DOF (then the first
    /// name) at its sketch, so that the rest is solved relative to it.
    fn ground_if_nothing_fixed(&mut self) {
        // Deterministically: the geom with the most DOF, then the first name.
        let mut best: Option<(usize, String, usize)> = None;
        for (i, c) in self.clusters.iter().enumerate() {
            let key = (c.record.dof(), self.model.geoms[c.geoms[0]].name.clone());
            if best
                .as_ref()
                .is_none_or(|b| key.0 > b.0 || (key.0 == b.0 && key.1 < b.1))
            {
                best = Some((key.0, key.1, i));
            }
        }
        // Horizontal and vertical constraints refer to the world's axes: they anchor the
        // rotation, so only the position of the chosen geom is held.
        let anchored = self.pending.iter().any(|r| {
            matches!(
                r.relation,
                Relation::Angle {
                    u: Dir::World(..),
                    ..
                } | Relation::Angle {
                    v: Dir::World(..),
                    ..
                }
            )
        });
        if let Some((_, _, i)) = best {
            if anchored && self.clusters[i].record.rot == Rot::Free {
                if let Some(f) = self.first_point_feature(i) {
                    let at = self.point(f);
                    self.clusters[i].record.pos = Pos::Pivot { at, feature: f };
                    self.insert_known(f, at);
                    self.plan.grounded = Some(self.clusters[i].geoms[0]);
                    return;
                }
            }
            let had_rotation = self.clusters[i].record.rot == Rot::Free;
            self.clusters[i].record.hold();
            self.plan.grounded = Some(self.clusters[i].geoms[0]);
            if !had_rotation {
                self.ground_direction(i);
            }
        }
    }

    /// The first point feature of a cluster: a line's base, a segment's start, a body's first
    /// point or marker.
    fn first_point_feature(&self, k: usize) -> Option<GeomId> {
        let g = *self.clusters[k].geoms.first()?;
        match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Point => Some(g),
            GeomKind::Segment => self.model.part(g, Part::Start),
            GeomKind::Circle => self.model.part(g, Part::Center),
            GeomKind::Body => self.model.geoms[g]
                .parts
                .iter()
                .copied()
                .find(|&m| self.model.geoms[m].kind.is_pointlike()),
            _ => None,
        }
    }

    /// A geom without orientation (a point, a circle) held at its sketch leaves the model free
    /// to turn about it: hold the direction to the first point related to it (in name order)
    /// as the sketch has it too, so that the model is solved up to a rigid motion only.
    fn ground_direction(&mut self, i: usize) {
        let held = |s: &Self, f: GeomId| s.cluster(f) == i;
        let mut pair = None;
        for r in &self.pending {
            if let Relation::PointPoint { a, b, .. } = r.relation {
                let (ka, kb) = (self.cluster(a), self.cluster(b));
                if held(self, a) && kb != i && self.clusters[kb].record.pos == Pos::Free {
                    pair = Some((a, b));
                } else if held(self, b) && ka != i && self.clusters[ka].record.pos == Pos::Free {
                    pair = Some((b, a));
                }
                if pair.is_some() {
                    break;
                }
            }
        }
        let Some((at, other)) = pair else { return };
        let a = self.point(at);
        let o = self.point(other);
        let words = format!(
            "the direction from {} to {} in the sketch",
            self.name(at),
            self.name(other)
        );
        let d = self.value(Op::DirectionTo { from: a, to: o }, Ty::Vector, words);
        let words = format!(
            "the line from {} through {} as sketched",
            self.name(at),
            self.name(other)
        );
        let line = self.value(
            Op::Line {
                point: a,
                dir: d,
                offset: None,
            },
            Ty::Line,
            words,
        );
        let k = self.cluster(other);
        self.clusters[k].record.pos = Pos::On {
            feature: other,
            locus: Locus::Line(line),
        };
        self.plan.grounded_direction = Some((at, other));
    }

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
    fn action(&mut self, r: &Rel) -> bool {
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
                        let c = self.value(Op::Circle { center: at, radius }, Ty::Circle, words);
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
                false
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
                            Op::Rotated {
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
                            Op::Rotated {
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

    /// `-a`.
    fn neg(&mut self, a: Reg) -> Reg {
        let words = format!("-{}", self.word(a));
        self.value(Op::Neg(a), Ty::Scalar, words)
    }

    /// Moves the cluster of feature `f` so that `f` meets `target`, with the freedom its record
    /// leaves (the plan fragment table for a rigid frame in the plane).
    fn move_feature(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        if let Some(done) = self.segment_fragment(f, target, r) {
            return done;
        }
        if self.clusters[k].record.free_dim.is_some() && depends_on_dim(self.model, f) {
            // The feature moves with the free dimension: wait until it is fixed.
            return false;
        }
        let moved = self.move_feature_rigidly(f, target, r);
        if moved {
            self.settle(k);
        }
        moved
    }

    /// The fragments of a rigid frame in the plane (the free dimension, if any, does not move
    /// `f`).
    fn move_feature_rigidly(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let fname = self.name(f);
        match (rec.pos, target) {
            (Pos::Free, Target::Point(x)) => {
                let from = self.point(f);
                let explain = format!(
                    "{names} is free to translate: translate it so that {fname} lands on {} ({c}).",
                    self.word(x)
                );
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = if rec.rot == Rot::Free {
                    Pos::Pivot { at: x, feature: f }
                } else {
                    Pos::Fixed
                };
                if rec.pos == Pos::Fixed {
                    rec.rot = if rec.rot == Rot::None {
                        Rot::None
                    } else {
                        Rot::Known
                    };
                }
                self.insert_known(f, x);
                true
            }
            (Pos::Free, Target::On(locus)) => {
                let from = self.point(f);
                let lreg = locus_reg(locus);
                let to = self.value(
                    Op::Nearest {
                        locus: lreg,
                        point: from,
                    },
                    Ty::Point,
                    format!("the point of {} nearest {fname}", self.word(lreg)),
                );
                let explain = format!(
                    "{names} is free to translate: translate it by the least motion that puts {fname} on {} ({c}).",
                    self.word(lreg)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                if rec.line {
                    // A line through a point of a locus: with its direction known it is fixed.
                    rec.pos = if rec.rot == Rot::Known {
                        Pos::Fixed
                    } else {
                        Pos::Pivot { at: to, feature: f }
                    };
                    if rec.pos == Pos::Fixed {
                        return true;
                    }
                    self.insert_known(f, to);
                } else {
                    rec.pos = Pos::On { feature: f, locus };
                }
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if rec.rot != Rot::Free => {
                // Translation along the locus: f moves on the locus shifted by f - g.
                let from = self.point(f);
                let own = if g == f {
                    locus_reg(lg)
                } else {
                    self.shifted(lg, g, f)
                };
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} can only slide so that {} stays on {}: move it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if g == f => {
                // Rotation free, f already on a locus: put it at the locus' meeting point.
                let from = self.point(f);
                let to = self.meet(locus_reg(lg), target, from, r);
                let explain = format!(
                    "{fname} must stay on {}: translate {names} so that it reaches {} ({c}); {names} may still rotate about it.",
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Pivot { at: to, feature: f };
                self.insert_known(f, to);
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                Target::Point(x),
            ) if g != f => {
                // Free to turn while g slides on its locus, f to reach a point: g must be where
                // its locus meets the circle about x of radius |f - g|. Slide g there, then
                // turn about it (the pivot fragment) so that f lands on x.
                let (pg, pf) = (self.point(g), self.point(f));
                let about_g = self.circle_through(pg, pf, f, g);
                let words = format!(
                    "the circle about {} through where {fname} must be",
                    self.word(x)
                );
                let about_x = self.value(
                    Op::ShiftedCircle {
                        circle: about_g,
                        from: pg,
                        to: x,
                    },
                    Ty::Circle,
                    words,
                );
                self.centers.insert(about_x, self.word(x));
                let to = self.meet(locus_reg(lg), Target::On(Locus::Circle(about_x)), pg, r);
                let explain = format!(
                    "{names} can slide {} along {} and turn about it; {fname} must reach {}: slide it so that {} is at {} ({c}).",
                    self.name(g),
                    self.word(locus_reg(lg)),
                    self.word(x),
                    self.name(g),
                    self.word(to)
                );
                self.emit(
                    Op::Translate {
                        geoms: geoms.clone(),
                        from: pg,
                        to,
                    },
                    None,
                    Vec::new(),
                    explain,
                );
                // f is now on the circle about g that reaches x: turn it there (no check that x
                // is on that circle: it is, by construction).
                let from = self.point(f);
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(x)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: to,
                        axis: RotationAxis::Normal,
                        from,
                        to: x,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = Pos::Fixed;
                rec.rot = Rot::Known;
                true
            }
            (Pos::Pivot { at, feature: g }, target) if g != f => {
                let from = self.point(f);
                let own = self.circle_through(at, from, f, g);
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} may only rotate about {} ({}): rotate it so that {fname} reaches {} ({c}).",
                    pivot_name(self.model, g),
                    self.word(at),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = Pos::Fixed;
                rec.rot = Rot::Known;
                true
            }
            _ => false,
        }
    }

    /// The circle about `at` through the current position `from` of feature `f`.
    fn circle_through(&mut self, at: Reg, from: Reg, f: GeomId, pivot: GeomId) -> Reg {
        // Both on one rigid geom with a constant sketch of them: the radius is their distance
        // in it, known now.
        let radius = self.model.constant_distance(pivot, f);
        let words = format!(
            "the circle about {} through {}",
            self.word(at),
            self.name(f)
        );
        let c = self.value(
            Op::CircleThrough {
                center: at,
                through: from,
                radius,
            },
            Ty::Circle,
            words,
        );
        self.centers.insert(c, self.word(at));
        c
    }

    /// The locus `lg` (of feature `g`) moved by `f - g`: where `f` goes when the cluster
    /// translates keeping `g` on `lg`.
    fn shifted(&mut self, lg: Locus, g: GeomId, f: GeomId) -> Reg {
        let pg = self.point(g);
        let pf = self.point(f);
        let fname = self.name(f);
        match lg {
            Locus::Line(l) => {
                let words = format!("the parallel to {} through {fname}", self.word(l));
                self.value(
                    Op::ParallelLine {
                        line: l,
                        through: pf,
                    },
                    Ty::Line,
                    words,
                )
            }
            // Only a circle's own centre rides on a conic: nothing else of it to shift.
            Locus::Conic(c) => c,
            Locus::Circle(c) => {
                let words = format!("{} moved with {fname}", self.word(c));
                self.value(
                    Op::ShiftedCircle {
                        circle: c,
                        from: pg,
                        to: pf,
                    },
                    Ty::Circle,
                    words,
                )
            }
        }
    }

    /// Where a feature moving on `own` meets `target`: an intersection (a branch variable), or
    /// the target point itself, which must lie on `own`.
    fn meet(&mut self, own: Reg, target: Target, near: Reg, r: &Rel) -> Reg {
        match target {
            Target::Point(x) => {
                let words = self.word(x);
                self.value(
                    Op::Onto {
                        locus: own,
                        point: x,
                        constraint: r.constraint,
                    },
                    Ty::Point,
                    words,
                )
            }
            Target::On(locus) => {
                let other = locus_reg(locus);
                let own_ty = self.ty(own);
                let (meet, a, b) = match (own_ty, locus) {
                    (Ty::Circle, Locus::Circle(c)) => (Meet::CircleCircle, own, c),
                    (Ty::Circle, Locus::Line(l)) => (Meet::LineCircle, l, own),
                    (Ty::Line, Locus::Circle(c)) => (Meet::LineCircle, own, c),
                    (Ty::Circle, Locus::Conic(q)) => (Meet::CircleConic, own, q),
                    (Ty::Line, Locus::Conic(q)) => (Meet::LineConic, own, q),
                    (Ty::Conic, Locus::Circle(c)) => (Meet::CircleConic, c, own),
                    (Ty::Conic, Locus::Line(l)) => (Meet::LineConic, l, own),
                    (Ty::Conic, Locus::Conic(q)) => (Meet::ConicConic, own, q),
                    _ => (Meet::LineLine, own, other),
                };
                self.intersect(meet, a, b, near, r.constraint)
            }
        }
    }

    /// Intersects two loci: the root of a new branch variable for `constraint`, each index with
    /// its geometric meaning.
    fn intersect(
        &mut self,
        meet: Meet,
        a: Reg,
        b: Reg,
        near: Reg,
        constraint: ConstraintId,
    ) -> Reg {
        let (wa, wb, wn) = (self.word(a), self.word(b), self.word(near));
        let centre = |s: &Self, r: Reg| {
            s.centers
                .get(&r)
                .cloned()
                .unwrap_or_else(|| format!("the centre of {}", s.word(r)))
        };
        let (ca, cb) = (centre(self, a), centre(self, b));
        let meanings = match meet {
            Meet::CircleCircle => vec![
                format!("{wn} to the left of the line from {ca} to {cb}"),
                format!("{wn} to the right of the line from {ca} to {cb}"),
            ],
            Meet::LineCircle | Meet::LineConic => vec![
                format!("the first crossing of {wa} with {wb}, along the line"),
                "the second crossing, along the line".to_string(),
            ],
            Meet::LineLine => vec![format!("the crossing of {wa} and {wb}")],
            Meet::CircleConic => (0..4)
                .map(|i| format!("root {i} in increasing parameter along {wb}"))
                .collect(),
            Meet::ConicConic => (0..4)
                .map(|i| format!("root {i} in increasing parameter along {wa}"))
                .collect(),
            spatial => unreachable!("the plane's fragments never meet {spatial:?}"),
        };
        let branch = self.branch(constraint, meanings);
        let words = format!("the meeting point of {wa} and {wb}");
        self.value(
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            },
            Ty::Point,
            words,
        )
    }

    /// Turns the cluster of direction feature `v` so that it points along `target`.
    fn turn(&mut self, v: GeomId, target: Reg, r: &Rel) -> bool {
        let k = self.cluster(v);
        let rec = self.clusters[k].record.clone();
        if rec.rot != Rot::Free {
            return false;
        }
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let (pivot, about) = match rec.pos {
            Pos::Pivot { at, feature } => (at, pivot_name(self.model, feature)),
            Pos::On { feature, .. } => (self.point(feature), self.name(feature)),
            _ => {
                let origin = geoms[0];
                (
                    self.point(origin),
                    format!("the origin of {}", self.name(origin)),
                )
            }
        };
        let from = self.dir(Dir::Feature(v));
        let explain = format!(
            "Rotate {names} about {about} so that {} points along {} ({c}). This fixes its rotation.",
            self.name(v),
            self.word(target)
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                axis: RotationAxis::Normal,
                from,
                to: target,
            },
            None,
            self.satisfies(r),
            explain,
        );
        let model = self.model;
        let rec = &mut self.clusters[k].record;
        rec.rot = Rot::Known;
        // Rotation known about a pivot: fixed, unless the pivot is a segment's end that its
        // free length still slides (the start then moves along the line), or the midpoint of
        // a segment of free length (both ends then move along the line).
        let sized_about_pivot = pinned_at_midpoint(model, rec).is_some();
        if matches!(rec.pos, Pos::Pivot { feature, .. } if !depends_on_dim(model, feature))
            && !sized_about_pivot
        {
            rec.pos = Pos::Fixed;
        }
        self.place_by_passes(k, v);
        true
    }

    /// A lone line whose direction has just become known, with a recorded [`Pass`]: moved
    /// across itself until it passes that point at its distance, which satisfies the
    /// recorded constraint.
    pub(super) fn place_by_passes(&mut self, k: usize, dir: GeomId) {
        let rec = &mut self.clusters[k].record;
        if rec.rot != Rot::Known || rec.pos != Pos::Free {
            return;
        }
        let Some(first) = rec.passes.first().copied() else {
            return;
        };
        rec.passes.clear();
        let Some(&base) = (self.clusters[k].geoms.first())
            .and_then(|&g| self.model.part(g, Part::BasePoint))
            .as_ref()
        else {
            return;
        };
        let dv = self.dir(Dir::Feature(dir));
        let offset = self.neg(first.d);
        let line = self.value(
            Op::Line {
                point: first.at,
                dir: dv,
                offset: Some(offset),
            },
            Ty::Line,
            format!(
                "the line along {} passing {} at its distance",
                self.name(dir),
                self.word(first.at)
            ),
        );
        let held = Rel {
            relation: Relation::PointLine {
                p: base,
                base,
                dir,
                d: None,
            },
            constraint: first.constraint,
            last: first.last,
            duplicate: false,
        };
        self.move_feature(base, Target::On(Locus::Line(line)), &held);
    }

    /// A point feature `p` is known; the line (`base`, `dir`) of another cluster must pass at
    /// signed distance `d` from it.
    fn move_line_to_point(
        &mut self,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(base);
        let rec = self.clusters[k].record.clone();
        if let (Pos::Pivot { at: pivot, feature }, Rot::Free) = (rec.pos, rec.rot) {
            // Turning about a known point: the line's direction is one of the two that pass
            // `p` at the distance (a free length, which slides an end along the line, moves
            // neither the line nor the pivot).
            return self.turn_line_past(pivot, feature, p, base, dir, d, r);
        }
        if rec.free_dim.is_some() && (rec.rot != Rot::Known || depends_on_dim(self.model, base)) {
            return false;
        }
        let at = self.point(p);
        if rec.rot == Rot::Known {
            // Its direction is known: the base must lie on the parallel at the right offset.
            let dv = self.dir(Dir::Feature(dir));
            let offset = d.map(|d| self.neg(d));
            let words = format!(
                "the line along {} placing {} at the right distance",
                self.name(dir),
                self.name(p)
            );
            let line = self.value(
                Op::Line {
                    point: at,
                    dir: dv,
                    offset,
                },
                Ty::Line,
                words,
            );
            let moved = self.move_feature(base, Target::On(Locus::Line(line)), r);
            let rec = &mut self.clusters[k].record;
            if moved && matches!(rec.pos, Pos::On { feature, .. } if feature == base) {
                rec.along = Some(dir);
            }
            return moved;
        }
        if rec.line
            && rec.pos == Pos::Free
            && rec.rot == Rot::Free
            && (d.is_some() || !rec.passes.is_empty())
        {
            // A lone line free to turn and move, passing a known point at a distance: record
            // it; with a second, the line's direction is the one that passes the second point
            // at the difference of the distances from the first.
            let d = match d {
                Some(d) => d,
                None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
            };
            let pass = Pass {
                at,
                d,
                constraint: r.constraint,
                last: r.last,
            };
            let Some(&first) = rec.passes.first() else {
                self.clusters[k].record.passes.push(pass);
                return true;
            };
            let offset = self.sum(vec![(1.0, d), (-1.0, first.d)]);
            let dv = self.dir(Dir::Feature(dir));
            let (pn, dn) = (self.name(p), self.name(dir));
            let from = self.word(first.at);
            let branch = self.branch(
                r.constraint,
                vec![
                    format!("{pn} ahead of {from} along {dn}"),
                    format!("{pn} behind {from} along {dn}"),
                ],
            );
            let to = self.value(
                Op::PassingDir {
                    pivot: first.at,
                    base: first.at,
                    dir: dv,
                    point: at,
                    offset: Some(offset),
                    branch,
                    constraint: r.constraint,
                },
                Ty::Vector,
                format!("the direction of {dn} that passes {pn} and {from} at their distances"),
            );
            return self.turn(dir, to, r);
        }
        if rec.line && d.is_none() && rec.pos == Pos::Free {
            // A lone line with free direction through a known point: slide its base there.
            return self.move_feature(base, Target::Point(at), r);
        }
        false
    }

    /// Turns the cluster of line (`base`, `dir`), which may only rotate about `pivot` (at
    /// feature `about`), until the line passes known point `p` at signed distance `d` (none:
    /// through it): a line through a point tangent to a circle, a slotted link through a pin.
    /// Two directions do; a branch variable says which, `p` ahead of the pivot along the line
    /// or behind it, as in the sketch.
    #[allow(clippy::too_many_arguments)]
    fn turn_line_past(
        &mut self,
        pivot: Reg,
        about: GeomId,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let point = self.point(p);
        let bp = self.point(base);
        let dv = self.dir(Dir::Feature(dir));
        // The pivot as the plan knows it (a line's own point is named after the line).
        let an = if self.model.geoms[about].kind == GeomKind::Line {
            self.word(pivot)
        } else {
            self.name(about)
        };
        let (pn, dn) = (self.name(p), self.name(dir));
        let branch = self.branch(
            r.constraint,
            vec![
                format!("{pn} ahead of {an} along {dn}"),
                format!("{pn} behind {an} along {dn}"),
            ],
        );
        let words = match d {
            Some(o) => format!("the direction of {dn} that passes {pn} at {}", self.word(o)),
            None => format!("the direction of {dn} that passes through {pn}"),
        };
        let to = self.value(
            Op::PassingDir {
                pivot,
                base: bp,
                dir: dv,
                point,
                offset: d,
                branch,
                constraint: r.constraint,
            },
            Ty::Vector,
            words,
        );
        self.turn(dir, to, r)
    }

    /// The locus table: where feature `f` of a partially fixed cluster can lie, if on a curve.
    fn locus_of(&mut self, f: GeomId) -> Option<Reg> {
        let rec = self.record(f).clone();
        if rec.free_dim.is_some() && depends_on_dim(self.model, f)
            || pinned_at_midpoint(self.model, &rec).is_some()
        {
            return None;
        }
        match rec.pos {
            Pos::On { feature, locus } if rec.rot != Rot::Free => Some(if feature == f {
                locus_reg(locus)
            } else {
                self.shifted(locus, feature, f)
            }),
            Pos::Pivot { at, feature } if feature != f => {
                let from = self.point(f);
                Some(self.circle_through(at, from, f, feature))
            }
            _ => None,
        }
    }

    /// Locus analysis: a coincidence between features of two partially fixed clusters, each on
    /// a curve: intersect the curves (a pseudo-point, 003 Example 2) and move both clusters.
    fn locus(&mut self, r: &Rel) -> bool {
        let Relation::PointPoint { a, b, d: None } = r.relation else {
            return false;
        };
        let (ka, kb) = (self.cluster(a), self.cluster(b));
        if ka == kb {
            return false;
        }
        let ready = |s: &Self, f: GeomId| {
            let rec = s.record(f);
            (rec.free_dim.is_none() || !depends_on_dim(s.model, f))
                && pinned_at_midpoint(s.model, rec).is_none()
                && match rec.pos {
                    Pos::On { .. } => rec.rot != Rot::Free,
                    Pos::Pivot { feature, .. } => feature != f,
                    _ => false,
                }
        };
        // A segment end its free length slides along a line is on that line; the length
        // then takes it to the meeting point.
        let (slide_a, slide_b) = (self.sliding_end(a), self.sliding_end(b));
        if !(ready(self, a) || slide_a.is_some()) || !(ready(self, b) || slide_b.is_some()) {
            return false;
        }
        let locus = |s: &mut Self, f: GeomId, slide: Option<GeomId>| match slide {
            Some(anchor) => Some(s.sliding_line(f, anchor)),
            None => s.locus_of(f),
        };
        let (Some(la), Some(lb)) = (locus(self, a, slide_a), locus(self, b, slide_b)) else {
            return false;
        };
        let near = self.point(b);
        // The intersection table wants (line, circle), (circle, conic), (line, conic).
        let rank = |t: Ty| match t {
            Ty::Line => 0,
            Ty::Circle => 1,
            _ => 2,
        };
        let (x, y) = if rank(self.ty(la)) <= rank(self.ty(lb)) {
            (la, lb)
        } else {
            (lb, la)
        };
        let meet = match (self.ty(x), self.ty(y)) {
            (Ty::Circle, Ty::Circle) => Meet::CircleCircle,
            (Ty::Line, Ty::Line) => Meet::LineLine,
            (Ty::Line, Ty::Circle) => Meet::LineCircle,
            (Ty::Line, Ty::Conic) => Meet::LineConic,
            (Ty::Circle, Ty::Conic) => Meet::CircleConic,
            _ => return false,
        };
        let pseudo = self.intersect(meet, x, y, near, r.constraint);
        // The pseudo-point lies on both loci: move a's cluster there, then b's (which
        // satisfies the constraint), each with its one remaining motion.
        if let Some(anchor) = slide_a {
            self.slide_end_to(a, anchor, pseudo, r, false);
        } else {
            self.reach(a, pseudo, &[]);
        }
        if let Some(anchor) = slide_b {
            self.slide_end_to(b, anchor, pseudo, r, true);
        } else {
            let sat = self.satisfies(r);
            self.reach(b, pseudo, &sat);
        }
        true
    }

    /// Moves the cluster of `f`, whose one-DOF motion is known to reach `x`, so that `f` is at
    /// `x`: a rotation about its pivot, or a translation along its locus.
    fn reach(&mut self, f: GeomId, x: Reg, satisfies: &[ConstraintId]) {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let from = self.point(f);
        let fname = self.name(f);
        let to = self.word(x);
        match rec.pos {
            Pos::Pivot { at, feature } => {
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that {fname} reaches {to}.",
                    pivot_name(self.model, feature)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        axis: RotationAxis::Normal,
                        from,
                        to: x,
                    },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.rot = Rot::Known;
                rec.pos = Pos::Fixed;
            }
            _ => {
                let explain = format!("{names} may only slide along its locus: translate it so that {fname} reaches {to}.");
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
            }
        }
        self.settle(k);
    }
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
