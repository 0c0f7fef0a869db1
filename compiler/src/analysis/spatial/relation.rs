//! Constraints of a 3d model decomposed into relations between features.
//!
//! As in the plane, a feature is a point (a point geom, a member point, a marker's point) or
//! a direction (a vector, a marker's z or x axis, a line's `dir`, a plane's normal) that a
//! geom carries. TLA's joints (003) are the conjunctions LANGUAGE.md gives them: a revolute
//! joint is a coincidence and parallel z axes, a prismatic one a point on a line, parallel z
//! axes and the x axes' twist about them, a weld a coincidence, z axes parallel in the same
//! sense (not the sketch's: the frames coincide) and no twist, and so on; a constraint is
//! satisfied when its last relation is. Choices the language leaves to the sketch (the sense
//! of parallel axes) are read from the sketch here, once.
//!
//! Constraints are point-point, point-line, point-plane, parallel (the sense from the sketch;
//! either, for two circles' planes), angle, twist and helix relations, and sizes
//! ([`Relation::Size`] for `length` and `radius`, [`Relation::SameSize`] for `equal`). A line
//! (or segment) at a distance from a circle, or tangent to it, is its direction square to the
//! circle's normal, its point in the circle's plane, and the circle's centre at the radius
//! plus the gap from it; two circles are parallel normals, one centre in the other's plane and
//! their centres apart by the radii and the gap as the sketch nests them (a distance made of
//! radii, [`Length::Radii`], read once the radii are known). A second such constraint with a
//! fixed circle in the plane of a first adds only its distance, and with one in a parallel
//! plane its plane and its distance (fixed circles' planes read from their constants), so that
//! no turn about a normal parallel to itself and no plane meeting itself is planned.

use super::Rel;
use crate::analysis::Unsupported;
use crate::config::{Config, D3};
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::expr::ExprId;
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch};
use gcs_lang::Model;
use gcs_runtime::tol;

/// A relation between features of space.
#[derive(Clone, Debug, PartialEq)]
pub enum Relation {
    /// `|a - b| = d` (`d` absent: coincidence).
    PointPoint {
        /// First point feature.
        a: GeomId,
        /// Second point feature.
        b: GeomId,
        /// The distance, or none for zero.
        d: Option<Length>,
    },
    /// Point `p` is at distance `d` from the line through point `base` along direction `dir`
    /// (absent: on it).
    PointLine {
        /// The point feature.
        p: GeomId,
        /// A point feature on the line.
        base: GeomId,
        /// The line's direction feature.
        dir: GeomId,
        /// The distance, or none for zero.
        d: Option<Length>,
    },
    /// The signed distance of point `p` from the plane through `base` with normal `normal`
    /// is `d` (absent: zero).
    PointPlane {
        /// The point feature.
        p: GeomId,
        /// A point feature on the plane (a plane geom stands for its own point).
        base: GeomId,
        /// The plane's normal feature.
        normal: GeomId,
        /// The signed distance, or none for zero.
        d: Option<ExprId>,
    },
    /// Directions `u` and `v` are parallel, `v` along `sense * u` (+1 or -1, the sketch's; 0
    /// for either, as two circles' normals are for their planes to be one).
    Parallel {
        /// First direction.
        u: GeomId,
        /// Second direction.
        v: GeomId,
        /// Same sense (+1), opposite (-1), or either (0).
        sense: f64,
    },
    /// Point `p` is at distance `d` from circle `circle` (absent: on it, in its plane at its
    /// radius from its centre).
    PointCircle {
        /// The point feature.
        p: GeomId,
        /// The circle.
        circle: GeomId,
        /// The distance, or none for zero.
        d: Option<ExprId>,
    },
    /// The unsigned angle between directions `u` and `v` is `angle` (in [0, pi]).
    Angle {
        /// First direction.
        u: GeomId,
        /// Second direction.
        v: GeomId,
        /// The angle: a model expression, or a constant (perpendicular: pi/2).
        angle: AngleValue,
    },
    /// A helical joint's coupling, `axis` (the first marker's z) parallel to the second's:
    /// the angle from `u` (the first marker's x) to `v` (the second's), counter-clockwise
    /// about `axis`, is `2pi s / pitch` modulo a turn, `s` the advance `(q - p) . axis` from
    /// the first marker's point `p` to the second's `q`.
    Helix {
        /// The first marker's z axis.
        axis: GeomId,
        /// The first marker's x axis.
        u: GeomId,
        /// The second marker's x axis.
        v: GeomId,
        /// The first marker's point.
        p: GeomId,
        /// The second marker's point.
        q: GeomId,
        /// The advance per turn.
        pitch: ExprId,
    },
    /// With `axis` (the first marker's z) parallel to the second's, the angle from `u` (the
    /// first marker's x) to `v` (the second's), counter-clockwise about `axis`, is `angle`
    /// (absent: zero).
    Twist {
        /// The first marker's z axis.
        axis: GeomId,
        /// The first marker's x axis.
        u: GeomId,
        /// The second marker's x axis.
        v: GeomId,
        /// The angle, or none for zero.
        angle: Option<ExprId>,
    },
    /// Point `p` is the midpoint of points `a` and `b` (a segment's ends).
    Midpoint {
        /// The midpoint.
        p: GeomId,
        /// One end.
        a: GeomId,
        /// The other end.
        b: GeomId,
    },
    /// The size of `geom`, a segment's length or a circle's radius, is `value`.
    Size {
        /// The segment or circle.
        geom: GeomId,
        /// Its length or radius.
        value: ExprId,
    },
    /// Two segments' lengths, or two circles' radii, are equal, whatever they are.
    SameSize {
        /// One segment or circle.
        a: GeomId,
        /// The other.
        b: GeomId,
    },
    /// Point `q` is the mirror image of point `p` across the plane through `base` with normal
    /// `normal`.
    Mirror {
        /// The point mirrored.
        p: GeomId,
        /// Its image.
        q: GeomId,
        /// A point feature of the mirror plane.
        base: GeomId,
        /// The mirror plane's normal feature.
        normal: GeomId,
    },
}

/// An angle a relation asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AngleValue {
    /// The value of a model expression (radians).
    Expr(ExprId),
    /// A constant of the constraint (a right angle).
    Const(f64),
}

/// A distance a relation asks for: a model expression, or one made of circles' radii (the
/// distance between the centres of two tangent circles, from a centre to a tangent line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// The value of a model expression.
    Expr(ExprId),
    /// `sign * radius(circle)`, plus `sign * radius(circle)` of a second circle, plus
    /// `sign * expr` (a gap): each circle's radius must be known (sized) for the relation to
    /// act.
    Radii {
        /// The first circle's radius, with its sign.
        first: (f64, GeomId),
        /// The second circle's, if any.
        second: Option<(f64, GeomId)>,
        /// The gap the constraint asks for, if any, with its sign.
        gap: Option<(f64, ExprId)>,
    },
}

impl Length {
    /// The circles whose radii the length reads.
    pub fn circles(self) -> Vec<GeomId> {
        match self {
            Length::Expr(_) => Vec::new(),
            Length::Radii { first, second, .. } => std::iter::once(first.1)
                .chain(second.map(|s| s.1))
                .collect(),
        }
    }
}

impl Relation {
    /// The circles whose radii a relation's distance reads (`Length::Radii`).
    pub fn radii(&self) -> Vec<GeomId> {
        match *self {
            Relation::PointPoint { d: Some(l), .. } | Relation::PointLine { d: Some(l), .. } => {
                l.circles()
            }
            _ => Vec::new(),
        }
    }

    /// The features a relation involves.
    pub fn features(&self) -> Vec<GeomId> {
        match *self {
            Relation::PointPoint { a, b, d } => {
                let mut f = vec![a, b];
                f.extend(d.map_or_else(Vec::new, Length::circles));
                f
            }
            Relation::PointLine { p, base, dir, d } => {
                let mut f = vec![p, base, dir];
                f.extend(d.map_or_else(Vec::new, Length::circles));
                f
            }
            Relation::PointPlane {
                p, base, normal, ..
            } => vec![p, base, normal],
            Relation::Parallel { u, v, .. } | Relation::Angle { u, v, .. } => vec![u, v],
            Relation::PointCircle { p, circle, .. } => vec![p, circle],
            Relation::Twist { axis, u, v, .. } => vec![axis, u, v],
            Relation::Helix {
                axis, u, v, p, q, ..
            } => vec![axis, u, v, p, q],
            Relation::Midpoint { p, a, b } => vec![p, a, b],
            Relation::Mirror { p, q, base, normal } => vec![p, q, base, normal],
            Relation::Size { geom, .. } => vec![geom],
            Relation::SameSize { a, b } => vec![a, b],
        }
    }
}

/// The direction a geom stands for in a spatial constraint on directions: a marker's z axis,
/// else what the model says (a vector, a line's `dir`, a plane's normal).
fn direction(model: &Model, g: GeomId) -> Option<GeomId> {
    match model.geoms[g].kind {
        GeomKind::Marker => model.part(g, Part::AxisZ),
        _ => model.dir_feature(g),
    }
}

/// The (point, direction) of a line in space: a marker's point and z axis, or the model's
/// line features of a line or segment.
fn line(model: &Model, g: GeomId) -> Option<(GeomId, GeomId)> {
    match model.geoms[g].kind {
        GeomKind::Marker => Some((g, model.part(g, Part::AxisZ)?)),
        GeomKind::Line | GeomKind::Segment => model.line_features(g),
        _ => None,
    }
}

/// The (point, normal) of a plane in space: a marker's point and z axis, or a plane geom
/// (its own point) and its normal.
fn plane(model: &Model, g: GeomId) -> Option<(GeomId, GeomId)> {
    match model.geoms[g].kind {
        GeomKind::Marker => Some((g, model.part(g, Part::AxisZ)?)),
        GeomKind::Plane => Some((g, model.part(g, Part::Normal)?)),
        _ => None,
    }
}

/// The plane of a fixed circle whose centre and normal are constants (no param moves it):
/// its centre and unit normal.
fn fixed_plane(model: &Model, c: GeomId) -> Option<([f64; 3], [f64; 3])> {
    let g = &model.geoms[c];
    let Sketch::Circle {
        center,
        normal: Some(normal),
        ..
    } = &g.sketch
    else {
        return None;
    };
    let (centre, n) = (
        super::constant(model, center)?,
        super::constant(model, normal)?,
    );
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (g.fixed && g.owner == Owner::TopLevel && len > 0.0)
        .then(|| (centre, [n[0] / len, n[1] / len, n[2] / len]))
}

/// How fixed circles `a` and `b` lie, their constants say, to rounding: `Some(true)` in one
/// plane, `Some(false)` in parallel planes apart, `None` otherwise.
fn coplanar(model: &Model, a: GeomId, b: GeomId) -> Option<bool> {
    let (Some((ca, na)), Some((cb, nb))) = (fixed_plane(model, a), fixed_plane(model, b)) else {
        return None;
    };
    let cross = [
        na[1] * nb[2] - na[2] * nb[1],
        na[2] * nb[0] - na[0] * nb[2],
        na[0] * nb[1] - na[1] * nb[0],
    ];
    if (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt() > tol::ANGLE {
        return None;
    }
    let w = [cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]];
    let scale = 1.0 + ca.iter().chain(&cb).fold(0.0f64, |m, x| m.max(x.abs()));
    let height = (na[0] * w[0] + na[1] * w[1] + na[2] * w[2]).abs();
    Some(height <= tol::COPLANAR_REL * scale)
}

/// For a distance or tangency between `x` (a line, segment or circle) and fixed circle `c`:
/// how another such constraint, tying `x` to a fixed circle parallel to `c` first (by name, so
/// that the order of statements does not matter), has already placed `x`: `Some(true)` in
/// `c`'s plane (this constraint adds only its distance), `Some(false)` square to `c`'s normal
/// (it adds its plane and its distance). Its own direction relation would be a turn about a
/// normal parallel to itself, and its plane in the first case a plane meeting itself, which no
/// construction can make.
fn placed_already(model: &Model, x: GeomId, c: GeomId) -> Option<bool> {
    use GeomKind as G;
    let name = |g: GeomId| model.geoms[g].name.as_str();
    (model.constraints.iter())
        .filter_map(|(_, other)| {
            let (&p, &q) = (other.args.first()?, other.args.get(1)?);
            let circle = match (p == x, q == x) {
                (true, false) => q,
                (false, true) => p,
                _ => return None,
            };
            let earlier = matches!(other.kind, K::Distance | K::Tangent)
                && model.geoms[circle].kind == G::Circle
                && circle != c
                && name(circle) < name(c);
            earlier.then(|| coplanar(model, circle, c)).flatten()
        })
        .max()
}

/// The distance between the centres of circles `a` and `b` at `gap` (none: tangent), as the
/// sketch nests them (the reading nearest the sketch, as in the plane): apart, `ra + rb + gap`;
/// `a` inside `b`, `rb - ra - gap`; `b` inside `a`, `ra - rb - gap`.
fn nested_radii(
    model: &Model,
    sketch: &Config<D3>,
    (a, b): (GeomId, GeomId),
    gap: Option<ExprId>,
) -> Length {
    let d = (sketch.point(model, model.point_feature(a))
        - sketch.point(model, model.point_feature(b)))
    .norm();
    let (ra, rb) = (sketch.dim(a), sketch.dim(b));
    let readings = [
        ((1.0, 1.0), (d - ra - rb).abs()),
        (
            (-1.0, 1.0),
            (d - (rb - ra)).abs() + if ra <= rb { 0.0 } else { f64::INFINITY },
        ),
        (
            (1.0, -1.0),
            (d - (ra - rb)).abs() + if rb <= ra { 0.0 } else { f64::INFINITY },
        ),
    ];
    let ((sa, sb), _) =
        (readings.iter().skip(1)).fold(readings[0], |best, r| if r.1 < best.1 { *r } else { best });
    // The gap adds to the centres' distance when apart, and takes from it when nested.
    let sign = if sa > 0.0 && sb > 0.0 { 1.0 } else { -1.0 };
    Length::Radii {
        first: (sa, a),
        second: Some((sb, b)),
        gap: gap.map(|e| (sign, e)),
    }
}

/// Decomposes every constraint of a 3d model, reading the sketch where the language leaves
/// a choice to it. Constraints the analysis does not cover yet are returned as
/// [`Unsupported`], never dropped.
pub fn decompose(model: &Model, sketch: &Config<D3>) -> (Vec<Rel>, Vec<Unsupported>) {
    let mut rels = Vec::new();
    let mut unsupported = Vec::new();
    for (id, c) in model.constraints.iter() {
        let a = c.args.first().copied();
        let b = c.args.get(1).copied();
        let kind = |g: GeomId| model.geoms[g].kind;
        let mut out: Vec<Relation> = Vec::new();
        let mut missing = |reason: &str| {
            unsupported.push(Unsupported {
                constraint: id,
                reason: reason.to_string(),
            });
        };
        // The sense of parallel directions: the sketch's.
        let parallel = |u: GeomId, v: GeomId| Relation::Parallel {
            u,
            v,
            sense: if sketch.dir(model, u).dot(&sketch.dir(model, v)) < 0.0 {
                -1.0
            } else {
                1.0
            },
        };
        let point = |g: GeomId| model.point_feature(g);
        match (c.kind, a, b) {
            (K::Coincident | K::Spherical, Some(a), Some(b)) => out.push(Relation::PointPoint {
                a: point(a),
                b: point(b),
                d: None,
            }),
            (K::Distance, Some(a), Some(b)) if kind(a).is_pointlike() && kind(b).is_pointlike() => {
                out.push(Relation::PointPoint {
                    a,
                    b,
                    d: c.value.map(Length::Expr),
                })
            }
            (K::Distance | K::On, Some(a), Some(b))
                if kind(a).is_pointlike() && kind(b) == GeomKind::Plane =>
            {
                match plane(model, b) {
                    Some((base, normal)) => out.push(Relation::PointPlane {
                        p: point(a),
                        base,
                        normal,
                        d: if c.kind == K::Distance { c.value } else { None },
                    }),
                    None => missing("a plane without its normal"),
                }
            }
            // A line at a distance from a circle, or tangent to it, lies in the circle's plane
            // (its direction square to the normal, its point in the plane), at the radius plus
            // the gap from the centre (LANGUAGE.md): the line's point last, at that distance.
            (K::Distance | K::Tangent, Some(a), Some(b))
                if matches!(kind(a), GeomKind::Line | GeomKind::Segment)
                    && kind(b) == GeomKind::Circle =>
            {
                match (line(model, a), model.part(b, Part::Normal)) {
                    (Some((base, dir)), Some(normal)) => {
                        let centre = point(b);
                        let placed = placed_already(model, a, b);
                        if placed.is_none() {
                            out.push(Relation::Angle {
                                u: dir,
                                v: normal,
                                angle: AngleValue::Const(std::f64::consts::FRAC_PI_2),
                            });
                        }
                        if placed != Some(true) {
                            out.push(Relation::PointPlane {
                                p: base,
                                base: centre,
                                normal,
                                d: None,
                            });
                        }
                        out.push(Relation::PointLine {
                            p: centre,
                            base,
                            dir,
                            d: Some(Length::Radii {
                                first: (1.0, b),
                                second: None,
                                gap: c.value.map(|e| (1.0, e)),
                            }),
                        });
                    }
                    _ => missing("a line and a circle need their directions"),
                }
            }
            // Two circles at a distance or tangent are coplanar (parallel normals, in the sense
            // of the sketch, and the second centre in the first's plane), their centres apart
            // by the radii and the gap as the sketch nests them: apart, or one inside the other.
            (K::Distance | K::Tangent, Some(a), Some(b))
                if kind(a) == GeomKind::Circle && kind(b) == GeomKind::Circle =>
            {
                match (model.part(a, Part::Normal), model.part(b, Part::Normal)) {
                    (Some(na), Some(nb)) => {
                        let (ca, cb) = (point(a), point(b));
                        let placed = placed_already(model, a, b).max(placed_already(model, b, a));
                        if placed.is_none() {
                            out.push(Relation::Parallel {
                                u: na,
                                v: nb,
                                sense: 0.0,
                            });
                        }
                        if placed != Some(true) {
                            out.push(Relation::PointPlane {
                                p: cb,
                                base: ca,
                                normal: na,
                                d: None,
                            });
                        }
                        out.push(Relation::PointPoint {
                            a: ca,
                            b: cb,
                            d: Some(nested_radii(model, sketch, (a, b), c.value)),
                        });
                    }
                    _ => missing("two circles need their normals"),
                }
            }
            (K::Distance, Some(a), Some(b))
                if kind(a).is_pointlike() && kind(b) == GeomKind::Circle =>
            {
                out.push(Relation::PointCircle {
                    p: point(a),
                    circle: b,
                    d: c.value,
                })
            }
            (K::Distance, Some(a), Some(b))
                if kind(a).is_pointlike()
                    && matches!(kind(b), GeomKind::Line | GeomKind::Segment) =>
            {
                match line(model, b) {
                    Some((base, dir)) => out.push(Relation::PointLine {
                        p: point(a),
                        base,
                        dir,
                        d: c.value.map(Length::Expr),
                    }),
                    None => missing("a line without its direction"),
                }
            }
            (K::On, Some(a), Some(b)) if kind(a).is_pointlike() && kind(b) == GeomKind::Circle => {
                out.push(Relation::PointCircle {
                    p: point(a),
                    circle: b,
                    d: None,
                })
            }
            (K::On, Some(a), Some(b))
                if kind(a).is_pointlike()
                    && matches!(kind(b), GeomKind::Line | GeomKind::Segment) =>
            {
                match line(model, b) {
                    Some((base, dir)) => out.push(Relation::PointLine {
                        p: point(a),
                        base,
                        dir,
                        d: None,
                    }),
                    None => missing("a line without its direction"),
                }
            }
            (K::InLine | K::Cylindrical | K::Prismatic, Some(a), Some(b)) => match line(model, b) {
                Some((base, dir)) => out.push(Relation::PointLine {
                    p: point(a),
                    base,
                    dir,
                    d: None,
                }),
                None => missing("in-line needs a marker to give the line"),
            },
            (K::InPlane | K::Planar, Some(a), Some(b)) => match plane(model, b) {
                Some((base, normal)) => out.push(Relation::PointPlane {
                    p: point(a),
                    base,
                    normal,
                    d: None,
                }),
                None => missing("in-plane needs a marker to give the plane"),
            },
            (K::Revolute | K::Weld, Some(a), Some(b)) => out.push(Relation::PointPoint {
                a: point(a),
                b: point(b),
                d: None,
            }),
            _ => {}
        }
        // The axes of TLA's joints, after their points.
        match (c.kind, a, b) {
            (
                K::ParallelZ
                | K::Helical
                | K::Revolute
                | K::Cylindrical
                | K::Planar
                | K::Prismatic
                | K::OffsetX,
                Some(a),
                Some(b),
            ) => match (direction(model, a), direction(model, b)) {
                (Some(u), Some(v)) => out.push(parallel(u, v)),
                _ => missing("a joint's z axes need two markers"),
            },
            // A weld's frames coincide: its z axes in the same sense, whatever the sketch.
            (K::Weld, Some(a), Some(b)) => match (direction(model, a), direction(model, b)) {
                (Some(u), Some(v)) => out.push(Relation::Parallel { u, v, sense: 1.0 }),
                _ => missing("a weld's z axes need two markers"),
            },
            (K::Parallel, Some(a), Some(b)) => match (direction(model, a), direction(model, b)) {
                (Some(u), Some(v)) => out.push(parallel(u, v)),
                _ => missing("parallel needs two directions"),
            },
            (K::Angle | K::Perpendicular | K::OffsetZ, Some(a), Some(b)) => {
                match (direction(model, a), direction(model, b)) {
                    (Some(u), Some(v)) => out.push(Relation::Angle {
                        u,
                        v,
                        angle: match (c.kind, c.value) {
                            (K::Perpendicular, _) | (_, None) => {
                                AngleValue::Const(std::f64::consts::FRAC_PI_2)
                            }
                            (_, Some(e)) => AngleValue::Expr(e),
                        },
                    }),
                    _ => missing("an angle needs two directions"),
                }
            }
            _ => {}
        }
        // The couplings of x axes about the z axes, after the axes: a helix or a twist.
        let x_axes = |a: GeomId, b: GeomId| {
            Some((
                model.part(a, Part::AxisZ)?,
                model.part(a, Part::AxisX)?,
                model.part(b, Part::AxisX)?,
            ))
        };
        if let (K::Helical | K::Prismatic | K::OffsetX | K::Weld, Some(a), Some(b)) = (c.kind, a, b)
        {
            match (x_axes(a, b), c.kind, c.value) {
                (Some((axis, u, v)), K::Helical, Some(pitch)) => out.push(Relation::Helix {
                    axis,
                    u,
                    v,
                    p: a,
                    q: b,
                    pitch,
                }),
                (Some((axis, u, v)), K::Prismatic | K::OffsetX | K::Weld, _) => {
                    out.push(Relation::Twist {
                        axis,
                        u,
                        v,
                        angle: if c.kind == K::OffsetX { c.value } else { None },
                    })
                }
                _ => missing("the coupling of x axes needs two markers (and a helix its pitch)"),
            }
        }
        match (c.kind, a, b) {
            (K::Length, Some(s), _) if kind(s) == GeomKind::Segment => match c.value {
                Some(value) => out.push(Relation::Size { geom: s, value }),
                None => missing("a length needs its value"),
            },
            (K::Radius, Some(s), _) if kind(s) == GeomKind::Circle => match c.value {
                Some(value) => out.push(Relation::Size { geom: s, value }),
                None => missing("a radius needs its value"),
            },
            (K::Equal, Some(a), Some(b))
                if kind(a) == kind(b)
                    && matches!(kind(a), GeomKind::Segment | GeomKind::Circle) =>
            {
                out.push(Relation::SameSize { a, b })
            }
            (K::Midpoint, Some(p), Some(s)) if kind(p).is_pointlike() => {
                match (model.part(s, Part::Start), model.part(s, Part::End)) {
                    (Some(a), Some(b)) => out.push(Relation::Midpoint { p: point(p), a, b }),
                    _ => missing("a midpoint needs a segment"),
                }
            }
            (K::Symmetric, Some(p), Some(q)) => {
                match c.args.get(2).and_then(|&m| plane(model, m)) {
                    Some((base, normal)) => out.push(Relation::Mirror {
                        p: point(p),
                        q: point(q),
                        base,
                        normal,
                    }),
                    None => missing("a mirror in space needs a plane"),
                }
            }
            _ => {}
        }
        if out.is_empty() {
            missing(match c.kind {
                K::Distance | K::On | K::Tangent => {
                    "this distance or incidence between lines, circles or planes is not analysed in 3d yet"
                }
                K::Length | K::Radius | K::Equal | K::Midpoint | K::Symmetric => {
                    "segments, circles and mirror planes of space are not analysed in 3d yet"
                }
                _ => "not analysed in 3d yet",
            });
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
