//! Constraints decomposed into relations between features.
//!
//! A feature is a point or a direction that a geom carries: a point geom, a member point, a
//! marker, `S.start`, `C.center`; a vector geom, a member vector, `L.dir`, a marker axis. Every
//! 2d constraint of the language becomes one or more relations between features (and
//! dimensions), and action analysis works on relations only. A constraint is satisfied when its
//! last relation is.

use super::Rel;
use crate::analysis::Unsupported;
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::expr::ExprId;
use gcs_lang::model::{GeomId, GeomKind, Part};
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
    /// Circle `circle` lies on side `side` (+1 left, -1 right) of the line through `base` along
    /// `dir`, its perimeter `gap` from it: `side * sd(centre) = radius + gap` (tangent: no gap).
    CircleLine {
        /// The circle.
        circle: GeomId,
        /// A point feature on the line.
        base: GeomId,
        /// The line's direction.
        dir: GeomId,
        /// The gap, or none for tangency.
        gap: Option<ExprId>,
        /// Which side, from the sketch.
        side: f64,
    },
    /// The distance of point `p` from circle `circle`'s perimeter is `gap` (none: `p` on the
    /// circle), outside or inside as in the sketch.
    PointCircle {
        /// The point feature.
        p: GeomId,
        /// The circle.
        circle: GeomId,
        /// The gap, or none for incidence.
        gap: Option<ExprId>,
        /// Whether `p` is outside the circle.
        outside: bool,
    },
    /// Two circles at perimeter distance `gap` (none: tangent), externally or one inside the
    /// other as in the sketch.
    CircleCircle {
        /// First circle.
        a: GeomId,
        /// Second circle.
        b: GeomId,
        /// The gap, or none for tangency.
        gap: Option<ExprId>,
        /// How they sit.
        mode: Nesting,
    },
    /// A geom's dimension (segment length, circle radius) is `value`.
    Dim {
        /// The geom.
        geom: GeomId,
        /// Its value.
        value: ExprId,
    },
    /// Two geoms' dimensions (segment lengths, circle radii) are equal, whatever they are:
    /// once one is known, the other follows it; neither is known from it alone.
    Equal {
        /// First geom.
        a: GeomId,
        /// Second geom.
        b: GeomId,
    },
    /// Point `p` is the midpoint of a segment's ends `a` (its start) and `b` (its end).
    Midpoint {
        /// The point feature.
        p: GeomId,
        /// The segment's start.
        a: GeomId,
        /// The segment's end.
        b: GeomId,
    },
    /// Points `p` and `q` are mirror images across the line through `base` along `dir`.
    Mirror {
        /// One point feature.
        p: GeomId,
        /// The other.
        q: GeomId,
        /// A point feature on the mirror line.
        base: GeomId,
        /// The mirror line's direction.
        dir: GeomId,
        /// Which way the line's direction turns from the direction from `p` to `q`, as the
        /// sketch has it (+1 counter-clockwise, -1 clockwise): the line built as the
        /// perpendicular bisector of `p` and `q` points that way.
        sense: f64,
    },
}

impl Relation {
    /// The features (and geoms with a dimension) the relation involves.
    pub fn features(&self) -> Vec<GeomId> {
        match self {
            Relation::PointPoint { a, b, .. } => vec![*a, *b],
            Relation::PointLine { p, base, dir, .. } => vec![*p, *base, *dir],
            Relation::Angle { u, v, .. } => [u, v]
                .into_iter()
                .filter_map(|d| match d {
                    Dir::Feature(g) => Some(*g),
                    Dir::World(..) => None,
                })
                .collect(),
            Relation::Dim { geom, .. } => vec![*geom],
            Relation::CircleLine {
                circle, base, dir, ..
            } => vec![*circle, *base, *dir],
            Relation::PointCircle { p, circle, .. } => vec![*p, *circle],
            Relation::CircleCircle { a, b, .. } | Relation::Equal { a, b } => vec![*a, *b],
            Relation::Midpoint { p, a, b } => vec![*p, *a, *b],
            Relation::Mirror {
                p, q, base, dir, ..
            } => vec![*p, *q, *base, *dir],
        }
    }
}

/// How two circles sit, read from the sketch: the runtime's reading, which a check of the
/// relation measures.
pub use gcs_runtime::check::Nesting;

/// What the decomposition asks of the sketch: angles between directions, and positions and
/// radii, to choose the sense of parallelism, the side of a tangency, and nesting.
pub trait SketchView {
    /// The counter-clockwise angle from `u` to `v` in the sketch.
    fn angle(&self, u: Dir, v: Dir) -> f64;
    /// The position of a point feature in the sketch.
    fn point(&self, p: GeomId) -> [f64; 2];
    /// The direction of a vector feature in the sketch.
    fn dir(&self, v: GeomId) -> [f64; 2];
    /// The radius of a circle in the sketch.
    fn radius(&self, c: GeomId) -> f64;
}

/// Decomposes every constraint of a 2d model. Constraints the analysis does not cover yet are
/// returned as [`Unsupported`], never dropped.
pub fn decompose(model: &Model, sketch: &dyn SketchView) -> (Vec<Rel>, Vec<Unsupported>) {
    let sketch_angle = |u: Dir, v: Dir| sketch.angle(u, v);
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
                out.push(Relation::PointPoint {
                    a: model.point_feature(a),
                    b: model.point_feature(b),
                    d: None,
                });
            }
            // The frames coincide: the points, then the x axes at angle 0 (offset_x(0)).
            (K::Weld, Some(a), Some(b)) => {
                out.push(Relation::PointPoint {
                    a: model.point_feature(a),
                    b: model.point_feature(b),
                    d: None,
                });
                match (model.part(a, Part::AxisX), model.part(b, Part::AxisX)) {
                    (Some(u), Some(v)) => out.push(Relation::Angle {
                        u: Dir::Feature(u),
                        v: Dir::Feature(v),
                        angle: AngleValue::Const(0.0),
                    }),
                    _ => missing("a weld needs two markers"),
                }
            }
            (K::Distance, Some(a), Some(b)) => match kinds {
                (Some(ka), Some(kb)) if ka.is_pointlike() && kb.is_pointlike() => {
                    out.push(Relation::PointPoint { a, b, d: c.value });
                }
                (Some(ka), Some(GeomKind::Line | GeomKind::Segment)) if ka.is_pointlike() => {
                    match model.line_features(b) {
                        Some((base, dir)) => out.push(Relation::PointLine {
                            p: a,
                            base,
                            dir,
                            d: c.value,
                        }),
                        None => missing("line without features"),
                    }
                }
                (Some(ka), Some(GeomKind::Circle)) if ka.is_pointlike() => {
                    out.push(point_circle(model, sketch, a, b, c.value));
                }
                (Some(GeomKind::Line | GeomKind::Segment), Some(GeomKind::Circle)) => {
                    match circle_line(model, sketch, b, a, c.value) {
                        Some(rel) => out.push(rel),
                        None => missing("line without features"),
                    }
                }
                (Some(GeomKind::Circle), Some(GeomKind::Circle)) => {
                    out.push(circle_circle(model, sketch, a, b, c.value))
                }
                _ => missing("not a distance of the language"),
            },
            (K::On, Some(a), Some(b)) => match kinds.1 {
                Some(GeomKind::Line | GeomKind::Segment) => match model.line_features(b) {
                    Some((base, dir)) => out.push(Relation::PointLine {
                        p: a,
                        base,
                        dir,
                        d: None,
                    }),
                    None => missing("line without features"),
                },
                Some(GeomKind::Circle) => out.push(point_circle(model, sketch, a, b, None)),
                _ => missing("not an incidence of 2d"),
            },
            (K::InLine | K::Prismatic, Some(a), Some(b)) => match model.line_features(b) {
                Some((base, dir)) => {
                    out.push(Relation::PointLine {
                        p: model.point_feature(a),
                        base,
                        dir,
                        d: None,
                    });
                    if c.kind == K::Prismatic {
                        match model.part(a, Part::AxisX) {
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
                match (model.dir_feature(a), model.dir_feature(b)) {
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
            (K::Horizontal | K::Vertical, Some(a), None) => match model.dir_feature(a) {
                Some(v) => {
                    let axis = if c.kind == K::Horizontal {
                        Dir::World(1.0, 0.0)
                    } else {
                        Dir::World(0.0, 1.0)
                    };
                    let v = Dir::Feature(v);
                    out.push(Relation::Angle {
                        u: axis,
                        v,
                        angle: AngleValue::Const(snap(axis, v, &[0.0, PI])),
                    });
                }
                None => missing("needs a direction"),
            },
            (K::OffsetX, Some(a), Some(b)) => {
                match (model.part(a, Part::AxisX), model.part(b, Part::AxisX)) {
                    (Some(u), Some(v)) => match c.value {
                        Some(e) => out.push(Relation::Angle {
                            u: Dir::Feature(u),
                            v: Dir::Feature(v),
                            angle: AngleValue::Expr(e),
                        }),
                        None => missing("offset_x needs a value"),
                    },
                    _ => missing("offset_x needs two markers"),
                }
            }
            (K::Length | K::Radius, Some(a), None) => match c.value {
                Some(value) => out.push(Relation::Dim { geom: a, value }),
                None => missing("needs a value"),
            },
            (K::Tangent, Some(a), Some(b)) => match kinds {
                (Some(GeomKind::Line | GeomKind::Segment), Some(GeomKind::Circle)) => {
                    match circle_line(model, sketch, b, a, None) {
                        Some(rel) => out.push(rel),
                        None => missing("line without features"),
                    }
                }
                _ => out.push(circle_circle(model, sketch, a, b, None)),
            },
            (K::Equal, Some(a), Some(b)) => out.push(Relation::Equal { a, b }),
            (K::Midpoint, Some(p), Some(s)) => {
                match (model.part(s, Part::Start), model.part(s, Part::End)) {
                    (Some(a), Some(b)) => out.push(Relation::Midpoint {
                        p: model.point_feature(p),
                        a,
                        b,
                    }),
                    _ => missing("a midpoint needs a segment"),
                }
            }
            (K::Symmetric, Some(p), Some(q)) => {
                match c.args.get(2).and_then(|&l| model.line_features(l)) {
                    Some((base, dir)) => {
                        let (p, q) = (model.point_feature(p), model.point_feature(q));
                        let pq = sub(sketch.point(q), sketch.point(p));
                        let d = sketch.dir(dir);
                        let sense = if pq[0] * d[1] - pq[1] * d[0] < 0.0 {
                            -1.0
                        } else {
                            1.0
                        };
                        out.push(Relation::Mirror {
                            p,
                            q,
                            base,
                            dir,
                            sense,
                        });
                    }
                    None => missing("a mirror needs a line"),
                }
            }
            _ => missing("not valid in 2d"),
        }
        let n = out.len();
        for (i, relation) in out.into_iter().enumerate() {
            rels.push(Rel {
                relation,
                constraint: id,
                last: i + 1 == n,
                duplicate: false,
            });
        }
    }
    (rels, unsupported)
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn circle_line(
    model: &Model,
    sketch: &dyn SketchView,
    circle: GeomId,
    line: GeomId,
    gap: Option<ExprId>,
) -> Option<Relation> {
    let (base, dir) = model.line_features(line)?;
    let centre = model.point_feature(circle);
    let d = sketch.dir(dir);
    let v = sub(sketch.point(centre), sketch.point(base));
    let sd = d[0] * v[1] - d[1] * v[0];
    let side = if sd < 0.0 { -1.0 } else { 1.0 };
    Some(Relation::CircleLine {
        circle,
        base,
        dir,
        gap,
        side,
    })
}

fn point_circle(
    model: &Model,
    sketch: &dyn SketchView,
    p: GeomId,
    circle: GeomId,
    gap: Option<ExprId>,
) -> Relation {
    let c = sketch.point(model.point_feature(circle));
    let q = sketch.point(p);
    let dist = sub(q, c);
    let outside = dist[0].hypot(dist[1]) >= sketch.radius(circle);
    Relation::PointCircle {
        p,
        circle,
        gap,
        outside,
    }
}

fn circle_circle(
    model: &Model,
    sketch: &dyn SketchView,
    a: GeomId,
    b: GeomId,
    gap: Option<ExprId>,
) -> Relation {
    let (ca, cb) = (
        sketch.point(model.point_feature(a)),
        sketch.point(model.point_feature(b)),
    );
    let d = sub(ca, cb);
    let d = d[0].hypot(d[1]);
    let (ra, rb) = (sketch.radius(a), sketch.radius(b));
    // The reading the sketch is closest to.
    let readings = [
        (Nesting::Apart, (d - ra - rb).abs()),
        (
            Nesting::FirstInside,
            (d - (rb - ra)).abs() + if ra <= rb { 0.0 } else { f64::INFINITY },
        ),
        (
            Nesting::SecondInside,
            (d - (ra - rb)).abs() + if rb <= ra { 0.0 } else { f64::INFINITY },
        ),
    ];
    let mode = readings
        .iter()
        .fold(readings[0], |best, r| if r.1 < best.1 { *r } else { best })
        .0;
    Relation::CircleCircle { a, b, gap, mode }
}

/// The distance between two angles, modulo a full turn.
pub fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}
