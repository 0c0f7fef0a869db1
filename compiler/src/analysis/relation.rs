//! Constraints decomposed into relations between features.
//!
//! A feature is a point or a direction that a geom carries: a point geom, a member point, a
//! marker, `S.start`, `C.center`; a vector geom, a member vector, `L.dir`, a marker axis. Every
//! 2d constraint of the language becomes one or more relations between features (and
//! dimensions), and action analysis works on relations only. A constraint is satisfied when its
//! last relation is.

use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::expr::ExprId;
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part};
use gcs_lang::Model;

/// A direction: a vector feature of some geom, or a fixed axis of the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dir {
    /// A vector feature.
    Feature(GeomId),
    /// A constant world direction (horizontal, vertical).
    World(f64, f64),
}

/// The angle a direction relation asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AngleValue {
    /// The value of a model expression (radians).
    Expr(ExprId),
    /// A constant chosen when the model was analysed (parallel: 0 or pi from the sketch).
    Const(f64),
}

/// A relation between features.
#[derive(Clone, Debug, PartialEq)]
pub enum Relation {
    /// `|a - b| = d` (`d` absent: coincidence).
    PointPoint {
        /// First point feature.
        a: GeomId,
        /// Second point feature.
        b: GeomId,
        /// The distance, or none for zero.
        d: Option<ExprId>,
    },
    /// The signed distance of point `p` from the line through `base` along `dir` is `d`
    /// (positive to the left; absent: zero).
    PointLine {
        /// The point feature.
        p: GeomId,
        /// A point feature on the line.
        base: GeomId,
        /// The line's direction feature.
        dir: GeomId,
        /// The signed distance, or none for zero.
        d: Option<ExprId>,
    },
    /// The counter-clockwise angle from `u` to `v` is `angle`.
    Angle {
        /// From.
        u: Dir,
        /// To.
        v: Dir,
        /// How much.
        angle: AngleValue,
    },
    /// A geom's dimension (segment length, circle radius) is `value`.
    Dim {
        /// The geom.
        geom: GeomId,
        /// Its value.
        value: ExprId,
    },
}

/// One relation with the constraint it comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct Rel {
    /// The relation.
    pub relation: Relation,
    /// The constraint.
    pub constraint: ConstraintId,
    /// Whether it is the constraint's last relation (its step satisfies the constraint).
    pub last: bool,
}

/// Why a constraint has no relations yet.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsupported {
    /// The constraint.
    pub constraint: ConstraintId,
    /// What is missing.
    pub reason: String,
}

/// The point feature of a geom used as a point: itself for points and markers, the centre of a
/// circle.
fn point_feature(model: &Model, g: GeomId) -> GeomId {
    match model.geoms[g].kind {
        GeomKind::Circle => part(model, g, Part::Center).unwrap_or(g),
        _ => g,
    }
}

/// The part `p` of geom `g`.
pub fn part(model: &Model, g: GeomId, p: Part) -> Option<GeomId> {
    model.geoms[g]
        .parts
        .iter()
        .copied()
        .find(|&c| model.geoms[c].owner == Owner::Part(g, p))
}

/// The (base point, direction) features of something line-like: a line, a segment, a marker's
/// x axis line.
fn line_features(model: &Model, g: GeomId) -> Option<(GeomId, GeomId)> {
    match model.geoms[g].kind {
        GeomKind::Line => Some((g, part(model, g, Part::Dir)?)),
        GeomKind::Segment => Some((part(model, g, Part::Start)?, part(model, g, Part::Dir)?)),
        GeomKind::Marker => Some((g, part(model, g, Part::AxisX)?)),
        _ => None,
    }
}

/// The direction feature of something with a direction.
fn dir_feature(model: &Model, g: GeomId) -> Option<GeomId> {
    match model.geoms[g].kind {
        GeomKind::Vector => Some(g),
        GeomKind::Line | GeomKind::Segment => part(model, g, Part::Dir),
        _ => None,
    }
}

/// Decomposes every constraint of a 2d model. Constraints the analysis does not cover yet are
/// returned as [`Unsupported`], never dropped.
pub fn decompose(
    model: &Model,
    sketch_angle: impl Fn(Dir, Dir) -> f64,
) -> (Vec<Rel>, Vec<Unsupported>) {
    let mut rels = Vec::new();
    let mut unsupported = Vec::new();
    for (id, c) in model.constraints.iter() {
        let a = c.args.first().copied();
        let b = c.args.get(1).copied();
        let kinds = (
            a.map(|g| model.geoms[g].kind),
            b.map(|g| model.geoms[g].kind),
        );
        let mut out: Vec<Relation> = Vec::new();
        let mut missing = |reason: &str| {
            unsupported.push(Unsupported {
                constraint: id,
                reason: reason.to_string(),
            });
        };
        // The sign of a parallel or perpendicular constraint: the sketch's.
        let snap = |u: Dir, v: Dir, choices: &[f64]| -> f64 {
            let s = sketch_angle(u, v);
            let mut best = choices[0];
            for &ch in choices {
                if angle_gap(s, ch) < angle_gap(s, best) {
                    best = ch;
                }
            }
            best
        };
        use std::f64::consts::{FRAC_PI_2, PI};
        match (c.kind, a, b) {
            (K::Coincident | K::Spherical | K::Revolute, Some(a), Some(b)) => {
                out.push(Relation::PointPoint { a: point_feature(model, a), b: point_feature(model, b), d: None });
            }
            (K::Distance, Some(a), Some(b)) => match kinds {
                (Some(ka), Some(kb)) if ka.is_pointlike() && kb.is_pointlike() => {
                    out.push(Relation::PointPoint { a, b, d: c.value });
                }
                (Some(ka), Some(GeomKind::Line | GeomKind::Segment)) if ka.is_pointlike() => {
                    match line_features(model, b) {
                        Some((base, dir)) => out.push(Relation::PointLine { p: a, base, dir, d: c.value }),
                        None => missing("line without features"),
                    }
                }
                _ => missing("distances involving circles need the circle records (fixed-distance invariants)"),
            },
            (K::On, Some(a), Some(b)) => match kinds.1 {
                Some(GeomKind::Line | GeomKind::Segment) => match line_features(model, b) {
                    Some((base, dir)) => out.push(Relation::PointLine { p: a, base, dir, d: None }),
                    None => missing("line without features"),
                },
                _ => missing("incidence with a circle needs the circle records"),
            },
            (K::InLine | K::Prismatic, Some(a), Some(b)) => match line_features(model, b) {
                Some((base, dir)) => {
                    out.push(Relation::PointLine { p: point_feature(model, a), base, dir, d: None });
                    if c.kind == K::Prismatic {
                        match part(model, a, Part::AxisX) {
                            Some(ax) => out.push(Relation::Angle {
                                u: Dir::Feature(ax),
                                v: Dir::Feature(dir),
                                angle: AngleValue::Const(0.0),
                            }),
                            None => missing("a prismatic joint needs two markers"),
                        }
                    }
                }
                None => missing("the second argument has no line"),
            },
            (K::Angle | K::Parallel | K::Perpendicular, Some(a), Some(b)) => {
                match (dir_feature(model, a), dir_feature(model, b)) {
                    (Some(u), Some(v)) => {
                        let (u, v) = (Dir::Feature(u), Dir::Feature(v));
                        let angle = match c.kind {
                            K::Angle => match c.value {
                                Some(e) => AngleValue::Expr(e),
                                None => AngleValue::Const(0.0),
                            },
                            K::Parallel => AngleValue::Const(snap(u, v, &[0.0, PI])),
                            _ => AngleValue::Const(snap(u, v, &[FRAC_PI_2, -FRAC_PI_2])),
                        };
                        out.push(Relation::Angle { u, v, angle });
                    }
                    _ => missing("angles need directions"),
                }
            }
            (K::Horizontal | K::Vertical, Some(a), None) => match dir_feature(model, a) {
                Some(v) => {
                    let axis = if c.kind == K::Horizontal { Dir::World(1.0, 0.0) } else { Dir::World(0.0, 1.0) };
                    let v = Dir::Feature(v);
                    out.push(Relation::Angle { u: axis, v, angle: AngleValue::Const(snap(axis, v, &[0.0, PI])) });
                }
                None => missing("needs a direction"),
            },
            (K::OffsetX, Some(a), Some(b)) => match (part(model, a, Part::AxisX), part(model, b, Part::AxisX)) {
                (Some(u), Some(v)) => match c.value {
                    Some(e) => out.push(Relation::Angle { u: Dir::Feature(u), v: Dir::Feature(v), angle: AngleValue::Expr(e) }),
                    None => missing("offset_x needs a value"),
                },
                _ => missing("offset_x needs two markers"),
            },
            (K::Length | K::Radius, Some(a), None) => match c.value {
                Some(value) => out.push(Relation::Dim { geom: a, value }),
                None => missing("needs a value"),
            },
            (K::Tangent, _, _) => missing("tangency needs the circle records (fixed-distance invariants)"),
            _ => missing("not valid in 2d"),
        }
        let n = out.len();
        for (i, relation) in out.into_iter().enumerate() {
            rels.push(Rel {
                relation,
                constraint: id,
                last: i + 1 == n,
            });
        }
    }
    (rels, unsupported)
}

/// The distance between two angles, modulo a full turn.
pub fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}
