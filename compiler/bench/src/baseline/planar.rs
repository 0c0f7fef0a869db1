//! The 2d baseline: unknowns and equations of a planar model.
//!
//! **Unknowns** are exactly the freedom [`Config`] has, per non-fixed top-level geom in
//! declaration order: a point's `x, y`; a vector's angle; a line's angle and its offset `h`
//! along the normal from its first sketch point (two numbers, so that a line has no gauge
//! freedom: its origin is the foot of the perpendicular from that sketch point, which is
//! `L.point`); a segment's origin, angle and length; a circle's centre and radius; a body's
//! origin and angle. Fixed geoms (and their members) are constants. If the model fixes nothing,
//! the top-level geom with the most DOF (then the first by name) is held at its sketch — the
//! param-free rule; a model left free to turn about it is solved in the least-squares sense.
//!
//! **Equations** are the signed, smooth forms of what [`gcs_compiler::verify`] measures, one or two
//! per constraint. Choices the language leaves to the geometry (the side of a line or circle a
//! tangency or a distance is on, internal or external circle tangency) are read from the start
//! configuration of each solve, as a numeric CAD solver does. Angles are differences of frame
//! rotations, wrapped to (-pi, pi]. Everything is precompiled to flat arrays: each equation
//! knows the two frames it reads and the local coordinates of its features; constants (member
//! coordinates, fixed geoms, values) are re-evaluated from the params at the start of a solve.
//!
//! **Jacobian**: analytic, assembled in O(nnz): each equation's gradient with respect to the
//! (origin, angle, dimension) of the frames it reads, carried to the unknowns of each frame.
//! The linear algebra, the scaling and the iteration are the shared ones ([`super`]); the
//! length scale of a 2d start is the largest of the spread of the frame origins, the offsets of
//! the features the equations read, frame dimensions and the equations' distances.

use super::solver::{Equations, Linear, Options, Outcome, Solver};
use gcs_compiler::config::{BadSketch, Config};
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::expr::{ExprId, Exprs};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Sketch, Space};
use gcs_lang::Model;
use nalgebra::Point2;
use std::time::Instant;

/// How to compute a constant of a solve from the params.
#[derive(Clone, Copy, Debug)]
enum Recipe {
    Const(f64),
    Expr(ExprId),
    /// The angle of the vector `(x, y)`.
    Atan2(ExprId, ExprId),
    /// A component of the unit vector along `(x, y)`: x if the flag is false.
    Unit(ExprId, ExprId, bool),
    /// The angle of `b - a`.
    AngleTo([ExprId; 4]),
    /// `|b - a|`.
    DistTo([ExprId; 4]),
}

impl Recipe {
    fn eval(self, e: &Exprs, p: &[f64]) -> f64 {
        match self {
            Recipe::Const(c) => c,
            Recipe::Expr(x) => e.eval(x, p),
            Recipe::Atan2(x, y) => e.eval(y, p).atan2(e.eval(x, p)),
            Recipe::Unit(x, y, second) => {
                let (x, y) = (e.eval(x, p), e.eval(y, p));
                let n = x.hypot(y);
                if second {
                    y / n
                } else {
                    x / n
                }
            }
            Recipe::AngleTo([ax, ay, bx, by]) => {
                (e.eval(by, p) - e.eval(ay, p)).atan2(e.eval(bx, p) - e.eval(ax, p))
            }
            Recipe::DistTo([ax, ay, bx, by]) => {
                (e.eval(by, p) - e.eval(ay, p)).hypot(e.eval(bx, p) - e.eval(ax, p))
            }
        }
    }
}

/// How a top-level geom's frame reads its four slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    /// Slots are origin x, origin y, angle, dimension.
    Frame,
    /// A free line: slots are the sketch point x, y (constants), the angle and the offset `h`
    /// along the normal; the origin is `s + h n(angle)`.
    Line,
}

#[derive(Clone, Copy, Debug)]
struct Geom {
    shape: Shape,
    /// Indices into `z` (unknowns first, then constants).
    q: [usize; 4],
}

/// A frame evaluated at the current unknowns.
#[derive(Clone, Copy, Debug, Default)]
struct Fr {
    ox: f64,
    oy: f64,
    th: f64,
    c: f64,
    s: f64,
    dim: f64,
    /// For a line: the offset along the normal.
    h: f64,
}

/// A point feature: `o + R(th) (l + dim m e_x)`; `l` read from `z`.
#[derive(Clone, Copy, Debug)]
struct Pt {
    g: usize,
    lx: usize,
    ly: usize,
    m: f64,
}

/// A direction feature: `R(th) l` with `l` a unit vector of angle `phi`, read from `z`.
#[derive(Clone, Copy, Debug)]
struct Dir {
    g: usize,
    lx: usize,
    ly: usize,
    phi: usize,
}

#[derive(Clone, Copy, Debug)]
enum Eq {
    Diff {
        a: Pt,
        b: Pt,
        y: bool,
    },
    Dist {
        a: Pt,
        b: Pt,
        d: usize,
    },
    PointLine {
        p: Pt,
        base: Pt,
        dir: Dir,
        d: usize,
    },
    PointCircle {
        p: Pt,
        c: Pt,
        d: usize,
    },
    LineCircle {
        base: Pt,
        dir: Dir,
        c: Pt,
        d: usize,
    },
    CircleCircle {
        a: Pt,
        b: Pt,
        d: usize,
    },
    Angle {
        u: Dir,
        v: Dir,
        a: usize,
    },
    Cross {
        u: Dir,
        v: Dir,
    },
    Dot {
        u: Dir,
        v: Dir,
    },
    Comp {
        u: Dir,
        y: bool,
    },
    Dim {
        g: usize,
        v: usize,
    },
    /// Two frames' dimensions are equal.
    SameDim {
        a: usize,
        b: usize,
    },
    /// The midpoint of `p` and `q` on the line through `base` along `dir` (signed distance).
    MirrorMid {
        p: Pt,
        q: Pt,
        base: Pt,
        dir: Dir,
    },
    /// `q - p` perpendicular to `dir` (its component along it).
    MirrorPerp {
        p: Pt,
        q: Pt,
        dir: Dir,
    },
}

impl Eq {
    /// The frames it reads, by side (`usize::MAX`: none); most read two, a mirror three.
    fn geoms(&self) -> [usize; 3] {
        const NONE: usize = usize::MAX;
        match *self {
            Eq::Diff { a, b, .. } | Eq::Dist { a, b, .. } | Eq::CircleCircle { a, b, .. } => {
                [a.g, b.g, NONE]
            }
            Eq::PointLine { p, base, .. } => [p.g, base.g, NONE],
            Eq::PointCircle { p, c, .. } => [p.g, c.g, NONE],
            Eq::LineCircle { base, c, .. } => [base.g, c.g, NONE],
            Eq::Angle { u, v, .. } | Eq::Cross { u, v } | Eq::Dot { u, v } => [u.g, v.g, NONE],
            Eq::Comp { u, .. } => [u.g, NONE, NONE],
            Eq::Dim { g, .. } => [g, NONE, NONE],
            Eq::SameDim { a, b } => [a, b, NONE],
            Eq::MirrorMid { p, q, base, .. } => [p.g, q.g, base.g],
            Eq::MirrorPerp { p, q, dir } => [p.g, q.g, dir.g],
        }
    }
}

type G4 = [f64; 4];

fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let r = a.rem_euclid(t);
    if r > std::f64::consts::PI {
        r - t
    } else {
        r
    }
}

/// A point feature's position and its offset from the frame origin.
#[inline]
fn point(f: &Fr, z: &[f64], p: &Pt) -> ([f64; 2], [f64; 2]) {
    let ax = z[p.lx] + p.m * f.dim;
    let ay = z[p.ly];
    let q = [f.c * ax - f.s * ay, f.s * ax + f.c * ay];
    ([f.ox + q[0], f.oy + q[1]], q)
}

/// Adds the gradient `gp` with respect to a point feature to its frame's gradient.
#[inline]
fn push_point(g: &mut G4, f: &Fr, q: [f64; 2], m: f64, gp: [f64; 2]) {
    g[0] += gp[0];
    g[1] += gp[1];
    g[2] += -gp[0] * q[1] + gp[1] * q[0];
    g[3] += m * (gp[0] * f.c + gp[1] * f.s);
}

#[inline]
fn dir(f: &Fr, z: &[f64], d: &Dir) -> [f64; 2] {
    let (lx, ly) = (z[d.lx], z[d.ly]);
    [f.c * lx - f.s * ly, f.s * lx + f.c * ly]
}

/// Adds the gradient `gu` with respect to a direction feature `u` to its frame's gradient.
#[inline]
fn push_dir(g: &mut G4, u: [f64; 2], gu: [f64; 2]) {
    g[2] += -gu[0] * u[1] + gu[1] * u[0];
}

/// The equations of a 2d model and the state they are evaluated at: the unknowns, then the
/// constants of the current solve, in one array `z`.
struct Planar {
    model: Model,
    n: usize,
    m: usize,
    geoms: Vec<Geom>,
    eqs: Vec<Eq>,
    /// The side each equation's sign choice took at the start of the solve (0 means the
    /// external form for circle pairs).
    side: Vec<f64>,
    /// Constant recipes, for `z[n..]`.
    consts: Vec<Recipe>,
    /// Cold-start recipes, for `z[..n]`.
    start: Vec<Recipe>,
    z: Vec<f64>,
    frames: Vec<Fr>,
    // Jacobian entries: per equation a range of (side, slot, position in J).
    ent_ptr: Vec<usize>,
    ent_side: Vec<u8>,
    ent_k: Vec<u8>,
    ent_pos: Vec<usize>,
}

/// The solver for one 2d model, built once and reused for every solve.
pub struct Baseline {
    eq: Planar,
    solver: Solver,
}

impl std::fmt::Debug for Baseline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Baseline")
            .field("unknowns", &self.eq.n)
            .field("equations", &self.eq.m)
            .field("sparse", &self.solver.is_sparse())
            .finish_non_exhaustive()
    }
}

/// The builder's state: constants allocated after the unknowns.
struct Build<'a> {
    model: &'a Model,
    n: usize,
    consts: Vec<Recipe>,
    geom_index: std::collections::HashMap<GeomId, usize>,
    geoms: Vec<Geom>,
}

impl Build<'_> {
    fn konst(&mut self, r: Recipe) -> usize {
        self.consts.push(r);
        self.n + self.consts.len() - 1
    }
    fn zero(&self) -> usize {
        self.n
    }
    fn one(&self) -> usize {
        self.n + 1
    }
    fn top(&self, g: GeomId) -> Result<usize, String> {
        let t = self.model.top_level_of(g);
        self.geom_index
            .get(&t)
            .copied()
            .ok_or_else(|| format!("{} has no frame", self.model.geoms[t].name))
    }
    fn xy(&self, c: &[ExprId], what: &str) -> Result<(ExprId, ExprId), String> {
        match c {
            [x, y] => Ok((*x, *y)),
            _ => Err(format!("{what} is not 2d")),
        }
    }
    /// A point argument: a point, marker, part or circle (its centre).
    fn pt(&mut self, g: GeomId) -> Result<Pt, String> {
        let model = self.model;
        let geom = &model.geoms[g];
        let top = self.top(g)?;
        let (zero, name) = (self.zero(), geom.name.clone());
        let at = |lx, ly, m| Pt { g: top, lx, ly, m };
        match (geom.kind, geom.owner, &geom.sketch) {
            (GeomKind::Point | GeomKind::Circle, Owner::TopLevel, _) => Ok(at(zero, zero, 0.0)),
            (GeomKind::Point | GeomKind::Marker, Owner::Member(_), Sketch::Point(c))
            | (GeomKind::Marker, Owner::Member(_), Sketch::Marker { origin: c, .. }) => {
                let (x, y) = self.xy(c, &name)?;
                let lx = self.konst(Recipe::Expr(x));
                let ly = self.konst(Recipe::Expr(y));
                Ok(at(lx, ly, 0.0))
            }
            (GeomKind::Point, Owner::Part(_, Part::End), _) => Ok(at(zero, zero, 1.0)),
            (GeomKind::Point, Owner::Part(_, Part::Start | Part::Center | Part::BasePoint), _) => {
                Ok(at(zero, zero, 0.0))
            }
            _ => Err(format!("{name} is not a 2d point the baseline can read")),
        }
    }
    /// A direction argument: a vector, marker axis, line or segment; a marker reads its x axis.
    fn dir(&mut self, g: GeomId) -> Result<Dir, String> {
        let model = self.model;
        let geom = &model.geoms[g];
        let top = self.top(g)?;
        let name = geom.name.clone();
        let fixed_x = Dir {
            g: top,
            lx: self.one(),
            ly: self.zero(),
            phi: self.zero(),
        };
        let local = |b: &mut Self, c: &[ExprId]| -> Result<Dir, String> {
            let (x, y) = b.xy(c, &name)?;
            Ok(Dir {
                g: top,
                lx: b.konst(Recipe::Unit(x, y, false)),
                ly: b.konst(Recipe::Unit(x, y, true)),
                phi: b.konst(Recipe::Atan2(x, y)),
            })
        };
        match (geom.kind, geom.owner, &geom.sketch) {
            (GeomKind::Vector | GeomKind::Line | GeomKind::Segment, Owner::TopLevel, _) => {
                Ok(fixed_x)
            }
            (GeomKind::Vector, Owner::Part(_, Part::Dir), _) => Ok(fixed_x),
            (GeomKind::Vector, Owner::Member(_), Sketch::Vector(c)) => local(self, c),
            (GeomKind::Vector, Owner::Part(marker, Part::AxisX), _) => {
                match &model.geoms[marker].sketch {
                    Sketch::Marker { x, .. } => local(self, x),
                    _ => Err(format!("{name} is not a marker axis")),
                }
            }
            (GeomKind::Marker, Owner::Member(_), Sketch::Marker { x, .. }) => local(self, x),
            _ => Err(format!(
                "{name} is not a 2d direction the baseline can read"
            )),
        }
    }
    /// The equation "`x` is at distance `d` from `y`" for the kinds of the two (`None` for a
    /// pair it has no form for): points, lines and circles, a circle measured from its centre
    /// by the equation's own form. `distance`, `on` (`d` zero) and `tangent` share it.
    fn distance(
        &mut self,
        x: GeomId,
        kx: Option<GeomKind>,
        y: GeomId,
        ky: Option<GeomKind>,
        d: usize,
    ) -> Result<Option<Eq>, String> {
        use GeomKind::{Circle, Line, Marker, Point, Segment};
        Ok(Some(match (kx, ky) {
            (Some(Point | Marker), Some(Point | Marker)) => Eq::Dist {
                a: self.pt(x)?,
                b: self.pt(y)?,
                d,
            },
            (Some(Point | Marker), Some(Line | Segment)) => {
                let p = self.pt(x)?;
                let (base, dir) = self.line(y)?;
                Eq::PointLine { p, base, dir, d }
            }
            (Some(Point | Marker), Some(Circle)) => Eq::PointCircle {
                p: self.pt(x)?,
                c: self.pt(y)?,
                d,
            },
            (Some(Line | Segment), Some(Circle)) => {
                let (base, dir) = self.line(x)?;
                let c = self.pt(y)?;
                Eq::LineCircle { base, dir, c, d }
            }
            (Some(Circle), Some(Circle)) => Eq::CircleCircle {
                a: self.pt(x)?,
                b: self.pt(y)?,
                d,
            },
            _ => return Ok(None),
        }))
    }
    /// A line argument: a point on it and its direction.
    fn line(&mut self, g: GeomId) -> Result<(Pt, Dir), String> {
        Ok((self.pt_or_origin(g)?, self.dir(g)?))
    }
    /// The origin of a line or segment, or a marker's point.
    fn pt_or_origin(&mut self, g: GeomId) -> Result<Pt, String> {
        match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Segment => Ok(Pt {
                g: self.top(g)?,
                lx: self.zero(),
                ly: self.zero(),
                m: 0.0,
            }),
            _ => self.pt(g),
        }
    }
}

/// The frame slots of a top-level geom's sketch: origin x, y, angle, dimension.
fn sketch_recipes(model: &Model, g: GeomId) -> Result<[Recipe; 4], String> {
    let geom = &model.geoms[g];
    let z = Recipe::Const(0.0);
    let two = |c: &[ExprId]| match c {
        [x, y] => Ok((*x, *y)),
        _ => Err(format!("{} is not 2d", geom.name)),
    };
    Ok(match &geom.sketch {
        Sketch::Point(c) => {
            let (x, y) = two(c)?;
            [Recipe::Expr(x), Recipe::Expr(y), z, z]
        }
        Sketch::Vector(c) => {
            let (x, y) = two(c)?;
            [z, z, Recipe::Atan2(x, y), z]
        }
        Sketch::Line { from, to } | Sketch::Segment { from, to } => {
            let (ax, ay) = two(from)?;
            let (bx, by) = two(to)?;
            let dim = if geom.kind == GeomKind::Segment {
                Recipe::DistTo([ax, ay, bx, by])
            } else {
                z
            };
            [
                Recipe::Expr(ax),
                Recipe::Expr(ay),
                Recipe::AngleTo([ax, ay, bx, by]),
                dim,
            ]
        }
        Sketch::Circle { center, radius, .. } => {
            let (x, y) = two(center)?;
            [Recipe::Expr(x), Recipe::Expr(y), z, Recipe::Expr(*radius)]
        }
        Sketch::Body { at, angle, .. } => {
            let (x, y) = match at {
                Some(c) => {
                    let (x, y) = two(c)?;
                    (Recipe::Expr(x), Recipe::Expr(y))
                }
                None => (z, z),
            };
            [x, y, angle.map_or(z, Recipe::Expr), z]
        }
        _ => {
            return Err(format!(
                "{} ({}) is not a 2d geom the baseline covers",
                geom.name,
                geom.kind.noun()
            ))
        }
    })
}

/// Which of a geom's four frame slots are free, by kind.
fn free_slots(kind: GeomKind) -> [bool; 4] {
    match kind {
        GeomKind::Point => [true, true, false, false],
        GeomKind::Vector => [false, false, true, false],
        GeomKind::Line => [false, false, true, true],
        GeomKind::Segment => [true, true, true, true],
        GeomKind::Circle => [true, true, false, true],
        _ => [true, true, true, false],
    }
}

impl Baseline {
    /// Compiles the equations of a 2d model, choosing dense or sparse linear algebra by size.
    pub fn new(model: &Model) -> Result<Baseline, String> {
        Baseline::with_linear(model, Linear::Auto)
    }

    /// Like [`Baseline::new`], forcing the linear algebra (to compare the two paths).
    pub fn with_linear(model: &Model, linear: Linear) -> Result<Baseline, String> {
        if model.space != Space::D2 {
            return Err("the numeric baseline covers 2d models only".into());
        }
        let tops: Vec<(GeomId, &gcs_lang::model::Geom)> = model.top_level().collect();
        // Ground: fixed geoms; if none, the one with the most DOF, then by name.
        let any_fixed = tops.iter().any(|(_, g)| g.fixed);
        let held = if any_fixed {
            None
        } else {
            tops.iter()
                .max_by(|a, b| {
                    let da = a.1.kind.dof(Space::D2);
                    let db = b.1.kind.dof(Space::D2);
                    da.cmp(&db).then_with(|| b.1.name.cmp(&a.1.name))
                })
                .map(|(id, _)| *id)
        };
        let mut b = Build {
            model,
            n: 0,
            consts: vec![Recipe::Const(0.0), Recipe::Const(1.0)],
            geom_index: Default::default(),
            geoms: Vec::new(),
        };
        let mut recipes = Vec::new();
        let mut start = Vec::new();
        // Unknowns first.
        let mut slots: Vec<[Option<usize>; 4]> = Vec::new();
        for (id, g) in &tops {
            let r = sketch_recipes(model, *id)?;
            let constant = g.fixed || Some(*id) == held;
            let mut s = [None; 4];
            for (k, f) in free_slots(g.kind).iter().enumerate() {
                if *f && !constant {
                    s[k] = Some(start.len());
                    start.push(if g.kind == GeomKind::Line && k == 3 {
                        Recipe::Const(0.0)
                    } else {
                        r[k]
                    });
                }
            }
            slots.push(s);
            recipes.push(r);
        }
        b.n = start.len();
        for (i, (id, g)) in tops.iter().enumerate() {
            let free_line = g.kind == GeomKind::Line && slots[i][2].is_some();
            let mut q = [0; 4];
            for k in 0..4 {
                q[k] = match slots[i][k] {
                    Some(u) => u,
                    None => b.konst(recipes[i][k]),
                };
            }
            b.geom_index.insert(*id, i);
            b.geoms.push(Geom {
                shape: if free_line { Shape::Line } else { Shape::Frame },
                q,
            });
        }
        let mut eqs = Vec::new();
        for (_, c) in model.constraints.iter() {
            let val = c.value.map(|e| b.konst(Recipe::Expr(e)));
            let d = val.unwrap_or(b.n);
            let (a0, a1) = (c.args.first().copied(), c.args.get(1).copied());
            let kind = |g: Option<GeomId>| g.map(|g| model.geoms[g].kind);
            let bad = || format!("the baseline cannot express {} ({})", c.name, c.text);
            match (c.kind, a0, a1) {
                (K::Coincident | K::Spherical | K::Revolute, Some(x), Some(y)) => {
                    let (a, bb) = (b.pt(x)?, b.pt(y)?);
                    eqs.push(Eq::Diff { a, b: bb, y: false });
                    eqs.push(Eq::Diff { a, b: bb, y: true });
                }
                (K::Distance, Some(x), Some(y)) => {
                    eqs.push(b.distance(x, kind(a0), y, kind(a1), d)?.ok_or_else(bad)?)
                }
                // A point on a line or circle: its distance from it is zero.
                (K::On, Some(x), Some(y)) => {
                    let point = Some(GeomKind::Point);
                    eqs.push(b.distance(x, point, y, kind(a1), d)?.ok_or_else(bad)?)
                }
                (K::Tangent, Some(x), Some(y))
                    if !matches!(kind(a0), Some(GeomKind::Point | GeomKind::Marker)) =>
                {
                    eqs.push(b.distance(x, kind(a0), y, kind(a1), d)?.ok_or_else(bad)?)
                }
                (K::Angle | K::OffsetX, Some(x), Some(y)) => eqs.push(Eq::Angle {
                    u: b.dir(x)?,
                    v: b.dir(y)?,
                    a: d,
                }),
                (K::Parallel, Some(x), Some(y)) => eqs.push(Eq::Cross {
                    u: b.dir(x)?,
                    v: b.dir(y)?,
                }),
                (K::Perpendicular, Some(x), Some(y)) => eqs.push(Eq::Dot {
                    u: b.dir(x)?,
                    v: b.dir(y)?,
                }),
                (K::Horizontal, Some(x), _) => eqs.push(Eq::Comp {
                    u: b.dir(x)?,
                    y: true,
                }),
                (K::Vertical, Some(x), _) => eqs.push(Eq::Comp {
                    u: b.dir(x)?,
                    y: false,
                }),
                (K::Length | K::Radius, Some(x), _) => eqs.push(Eq::Dim { g: b.top(x)?, v: d }),
                (K::Equal, Some(x), Some(y)) => eqs.push(Eq::SameDim {
                    a: b.top(x)?,
                    b: b.top(y)?,
                }),
                // The point and the segment's own point at half its length.
                (K::Midpoint, Some(x), Some(y)) => {
                    let (p, zero) = (b.pt(x)?, b.zero());
                    let m = Pt {
                        g: b.top(y)?,
                        lx: zero,
                        ly: zero,
                        m: 0.5,
                    };
                    eqs.push(Eq::Diff {
                        a: p,
                        b: m,
                        y: false,
                    });
                    eqs.push(Eq::Diff {
                        a: p,
                        b: m,
                        y: true,
                    });
                }
                (K::Symmetric, Some(x), Some(y)) => {
                    let l = c.args.get(2).copied().ok_or_else(bad)?;
                    let (p, q) = (b.pt(x)?, b.pt(y)?);
                    let (base, dir) = b.line(l)?;
                    eqs.push(Eq::MirrorMid { p, q, base, dir });
                    eqs.push(Eq::MirrorPerp { p, q, dir });
                }
                (K::InLine, Some(x), Some(y)) => {
                    let p = b.pt(x)?;
                    let (base, dir) = b.line(y)?;
                    eqs.push(Eq::PointLine {
                        p,
                        base,
                        dir,
                        d: b.n,
                    });
                }
                // The frames coincide: the points, and the x axes at angle 0.
                (K::Weld, Some(x), Some(y)) => {
                    let (a, bb) = (b.pt(x)?, b.pt(y)?);
                    eqs.push(Eq::Diff { a, b: bb, y: false });
                    eqs.push(Eq::Diff { a, b: bb, y: true });
                    let (u, v) = (b.dir(x)?, b.dir(y)?);
                    eqs.push(Eq::Angle { u, v, a: b.n });
                }
                (K::Prismatic, Some(x), Some(y)) => {
                    let (u, v) = (b.dir(x)?, b.dir(y)?);
                    eqs.push(Eq::Angle { u, v, a: b.n });
                    let p = b.pt(x)?;
                    let (base, dir) = b.line(y)?;
                    eqs.push(Eq::PointLine {
                        p,
                        base,
                        dir,
                        d: b.n,
                    });
                }
                _ => return Err(bad()),
            }
        }
        let n = b.n;
        let m = eqs.len();
        let nz = n + b.consts.len();
        let mut eq = Planar {
            model: model.clone(),
            n,
            m,
            geoms: b.geoms,
            side: vec![1.0; m],
            eqs,
            consts: b.consts,
            start,
            z: vec![0.0; nz],
            frames: vec![Fr::default(); tops.len()],
            ent_ptr: vec![0],
            ent_side: Vec::new(),
            ent_k: Vec::new(),
            ent_pos: Vec::new(),
        };
        let solver = eq.structure(linear.sparse(n))?;
        Ok(Baseline { eq, solver })
    }

    /// The model it solves.
    pub fn model(&self) -> &Model {
        &self.eq.model
    }

    /// The number of unknowns.
    pub fn unknowns(&self) -> usize {
        self.eq.n
    }

    /// The number of scalar equations.
    pub fn equations(&self) -> usize {
        self.eq.m
    }

    /// Whether the sparse linear algebra is in use.
    pub fn is_sparse(&self) -> bool {
        self.solver.is_sparse()
    }

    /// The cold start: the unknowns as the sketch has them, with `params`.
    pub fn start_from_sketch(&self, params: &[f64]) -> Vec<f64> {
        self.eq
            .start
            .iter()
            .map(|r| r.eval(&self.eq.model.exprs, params))
            .collect()
    }

    /// The unknowns that describe configuration `cfg` (the plan's answer, say): a start on
    /// the assembly `cfg` is on, for a continuation.
    pub fn unknowns_from_config(&self, params: &[f64], cfg: &Config) -> Vec<f64> {
        let n = self.eq.n;
        let mut z = self.eq.z.clone();
        for (k, r) in self.eq.consts.iter().enumerate() {
            z[n + k] = r.eval(&self.eq.model.exprs, params);
        }
        for ((id, _), g) in self.eq.model.top_level().zip(&self.eq.geoms) {
            let Some(f) = cfg.frames.get(&id) else {
                continue;
            };
            let th = f.rotation.angle();
            let dim = cfg.dims.get(&id).copied();
            let (sx, sy) = (z[g.q[0]], z[g.q[1]]);
            let mut put = |slot: usize, v: f64| {
                if g.q[slot] < n {
                    z[g.q[slot]] = v;
                }
            };
            match g.shape {
                Shape::Frame => {
                    put(0, f.origin.x);
                    put(1, f.origin.y);
                    put(2, th);
                    if let Some(d) = dim {
                        put(3, d);
                    }
                }
                Shape::Line => {
                    // The offset of the line from its sketch point, along its normal.
                    let (s, c) = th.sin_cos();
                    let h = -s * (f.origin.x - sx) + c * (f.origin.y - sy);
                    put(2, th);
                    put(3, h);
                }
            }
        }
        z.truncate(n);
        z
    }

    /// The configuration the unknowns `x` describe, to read a
    /// [`gcs_compiler::solution::Solution`] and re-check it with [`gcs_compiler::verify`].
    pub fn config(&self, params: &[f64], x: &[f64]) -> Result<Config, BadSketch> {
        let mut cfg = Config::from_sketch(&self.eq.model, params)?;
        let mut z = self.eq.z.clone();
        z[..self.eq.n].copy_from_slice(&x[..self.eq.n]);
        for (k, r) in self.eq.consts.iter().enumerate() {
            z[self.eq.n + k] = r.eval(&self.eq.model.exprs, params);
        }
        for ((id, _), g) in self.eq.model.top_level().zip(&self.eq.geoms) {
            let f = frame(g, &z);
            if let Some(fr) = cfg.frames.get_mut(&id) {
                *fr = gcs_runtime::frame::Frame2::new(Point2::new(f.ox, f.oy), f.th);
            }
            if let Some(d) = cfg.dims.get_mut(&id) {
                *d = f.dim;
            }
        }
        Ok(cfg)
    }

    /// Solves in place: `x` holds the start (warm, or [`Baseline::start_from_sketch`]) and
    /// receives the result. After the first call, the iteration allocates nothing (unless a
    /// trace is asked for).
    pub fn solve(&mut self, params: &[f64], x: &mut [f64], opts: &Options) -> Outcome {
        let t0 = Instant::now();
        let eq = &mut self.eq;
        let n = eq.n;
        for (k, r) in eq.consts.iter().enumerate() {
            eq.z[n + k] = r.eval(&eq.model.exprs, params);
        }
        eq.z[..n].copy_from_slice(&x[..n]);
        eq.choose_sides();
        self.solver.equilibrate(eq.length_scale());
        let out = self.solver.iterate(eq, opts, t0);
        x[..n].copy_from_slice(&eq.z[..n]);
        out
    }
}

impl Equations for Planar {
    fn unknowns_mut(&mut self) -> &mut [f64] {
        &mut self.z[..self.n]
    }

    fn values(&mut self, f: &mut [f64]) {
        self.update_frames();
        for (e, v) in f.iter_mut().enumerate() {
            *v = self.eval(e, false).0;
        }
    }

    fn jacobian(&mut self, jv: &mut [f64]) {
        self.update_frames();
        for e in 0..self.m {
            let (_, gr) = self.eval(e, true);
            let gs = self.eqs[e].geoms();
            for t in self.ent_ptr[e]..self.ent_ptr[e + 1] {
                let side = self.ent_side[t] as usize;
                let k = self.ent_k[t] as usize;
                let gi = gs[side];
                let gg = &gr[side];
                let val = match self.geoms[gi].shape {
                    Shape::Frame => gg[k],
                    Shape::Line => {
                        let f = &self.frames[gi];
                        if k == 2 {
                            gg[0] * (-f.h * f.c) + gg[1] * (-f.h * f.s) + gg[2]
                        } else {
                            gg[0] * (-f.s) + gg[1] * f.c
                        }
                    }
                };
                jv[self.ent_pos[t]] += val;
            }
        }
    }
}

impl Planar {
    /// Builds the Jacobian's pattern and this model's entry positions in it, and the solver
    /// on it.
    fn structure(&mut self, sparse_path: bool) -> Result<Solver, String> {
        let (n, m) = (self.n, self.m);
        // Dimensions: slot 2 of a frame is its angle; every other slot is a length.
        let mut col_len = vec![false; n];
        for g in &self.geoms {
            for (k, &col) in g.q.iter().enumerate() {
                if col < n {
                    col_len[col] = k != 2;
                }
            }
        }
        let row_len = self
            .eqs
            .iter()
            .map(|e| {
                !matches!(
                    e,
                    Eq::Angle { .. } | Eq::Cross { .. } | Eq::Dot { .. } | Eq::Comp { .. }
                )
            })
            .collect();
        // Columns of each equation, by (side, slot).
        let mut rows: Vec<Vec<(u8, u8, usize)>> = Vec::with_capacity(m);
        for e in &self.eqs {
            let mut r = Vec::new();
            for (side, &g) in e.geoms().iter().enumerate() {
                if g == usize::MAX {
                    continue;
                }
                for k in 0..4 {
                    let col = self.geoms[g].q[k];
                    if col < n {
                        r.push((side as u8, k as u8, col));
                    }
                }
            }
            rows.push(r);
        }
        let ucols: Vec<Vec<usize>> = rows
            .iter()
            .map(|r| {
                let mut c: Vec<usize> = r.iter().map(|e| e.2).collect();
                c.sort_unstable();
                c.dedup();
                c
            })
            .collect();
        let solver = Solver::new(n, &ucols, row_len, col_len, sparse_path)?;
        for (e, r) in rows.iter().enumerate() {
            for &(side, k, col) in r {
                self.ent_side.push(side);
                self.ent_k.push(k);
                self.ent_pos.push(solver.position(e, col));
            }
            self.ent_ptr.push(self.ent_pos.len());
        }
        Ok(solver)
    }

    /// Evaluates every frame from `z`.
    fn update_frames(&mut self) {
        for (f, g) in self.frames.iter_mut().zip(&self.geoms) {
            *f = frame(g, &self.z);
        }
    }

    /// Picks each sign choice from the start configuration.
    fn choose_sides(&mut self) {
        self.update_frames();
        for e in 0..self.m {
            self.side[e] = 1.0;
            let z = &self.z;
            let fr = &self.frames;
            match self.eqs[e] {
                Eq::PointCircle { p, c, .. } => {
                    let (pp, _) = point(&fr[p.g], z, &p);
                    let (cc, _) = point(&fr[c.g], z, &c);
                    let r = fr[c.g].dim;
                    let s = (pp[0] - cc[0]).hypot(pp[1] - cc[1]) - r;
                    self.side[e] = if s < 0.0 { -1.0 } else { 1.0 };
                }
                Eq::LineCircle {
                    base, dir: dd, c, ..
                } => {
                    let (b, _) = point(&fr[base.g], z, &base);
                    let u = dir(&fr[dd.g], z, &dd);
                    let (cc, _) = point(&fr[c.g], z, &c);
                    let s = u[0] * (cc[1] - b[1]) - u[1] * (cc[0] - b[0]);
                    self.side[e] = if s < 0.0 { -1.0 } else { 1.0 };
                }
                Eq::CircleCircle { a, b, d } => {
                    let (ca, _) = point(&fr[a.g], z, &a);
                    let (cb, _) = point(&fr[b.g], z, &b);
                    let (ra, rb) = (fr[a.g].dim, fr[b.g].dim);
                    let dist = (ca[0] - cb[0]).hypot(ca[1] - cb[1]);
                    let outside = dist - ra - rb - z[d];
                    let nested = (ra - rb).abs() - dist - z[d];
                    self.side[e] = if outside.abs() <= nested.abs() {
                        0.0
                    } else if ra >= rb {
                        1.0
                    } else {
                        -1.0
                    };
                }
                _ => {}
            }
        }
    }

    /// One equation's value and its gradient with respect to its frames' (ox, oy, th, dim),
    /// by side ([`Eq::geoms`]).
    #[inline]
    fn eval(&self, e: usize, grad: bool) -> (f64, [G4; 3]) {
        let z = &self.z;
        let fr = &self.frames;
        let mut gr = [[0.0; 4]; 3];
        let side = self.side[e];
        let v = match self.eqs[e] {
            Eq::Diff { a, b, y } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                let k = usize::from(y);
                if grad {
                    let gp = if y { [0.0, 1.0] } else { [1.0, 0.0] };
                    push_point(&mut gr[0], fa, qa, a.m, gp);
                    push_point(&mut gr[1], fb, qb, b.m, [-gp[0], -gp[1]]);
                }
                pa[k] - pb[k]
            }
            Eq::Dist { a, b, d } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                let w = [pa[0] - pb[0], pa[1] - pb[1]];
                let len = w[0].hypot(w[1]);
                if grad && len > 0.0 {
                    let gp = [w[0] / len, w[1] / len];
                    push_point(&mut gr[0], fa, qa, a.m, gp);
                    push_point(&mut gr[1], fb, qb, b.m, [-gp[0], -gp[1]]);
                }
                len - z[d].abs()
            }
            Eq::PointLine {
                p,
                base,
                dir: dd,
                d,
            } => {
                let (fp, fl) = (&fr[p.g], &fr[base.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pb, qb) = point(fl, z, &base);
                let u = dir(fl, z, &dd);
                let w = [pp[0] - pb[0], pp[1] - pb[1]];
                // cross(u, w) = u.x w.y - u.y w.x
                if grad {
                    let gw = [-u[1], u[0]];
                    push_point(&mut gr[0], fp, qp, p.m, gw);
                    push_point(&mut gr[1], fl, qb, base.m, [-gw[0], -gw[1]]);
                    push_dir(&mut gr[1], u, [w[1], -w[0]]);
                }
                u[0] * w[1] - u[1] * w[0] - z[d]
            }
            Eq::PointCircle { p, c, d } => {
                let (fp, fc) = (&fr[p.g], &fr[c.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pc, qc) = point(fc, z, &c);
                let w = [pp[0] - pc[0], pp[1] - pc[1]];
                let len = w[0].hypot(w[1]);
                if grad && len > 0.0 {
                    let gp = [side * w[0] / len, side * w[1] / len];
                    push_point(&mut gr[0], fp, qp, p.m, gp);
                    push_point(&mut gr[1], fc, qc, c.m, [-gp[0], -gp[1]]);
                    gr[1][3] -= side;
                }
                side * (len - fc.dim) - z[d]
            }
            Eq::LineCircle {
                base,
                dir: dd,
                c,
                d,
            } => {
                let (fl, fc) = (&fr[base.g], &fr[c.g]);
                let (pb, qb) = point(fl, z, &base);
                let u = dir(fl, z, &dd);
                let (pc, qc) = point(fc, z, &c);
                let w = [pc[0] - pb[0], pc[1] - pb[1]];
                if grad {
                    let gw = [-side * u[1], side * u[0]];
                    push_point(&mut gr[1], fc, qc, c.m, gw);
                    push_point(&mut gr[0], fl, qb, base.m, [-gw[0], -gw[1]]);
                    push_dir(&mut gr[0], u, [side * w[1], -side * w[0]]);
                    gr[1][3] -= 1.0;
                }
                side * (u[0] * w[1] - u[1] * w[0]) - fc.dim - z[d]
            }
            Eq::CircleCircle { a, b, d } => {
                let (fa, fb) = (&fr[a.g], &fr[b.g]);
                let (pa, qa) = point(fa, z, &a);
                let (pb, qb) = point(fb, z, &b);
                let w = [pa[0] - pb[0], pa[1] - pb[1]];
                let len = w[0].hypot(w[1]);
                // External: len - ra - rb - d; nested: side (ra - rb) - len - d.
                let sgn = if side == 0.0 { 1.0 } else { -1.0 };
                if grad && len > 0.0 {
                    let gp = [sgn * w[0] / len, sgn * w[1] / len];
                    push_point(&mut gr[0], fa, qa, a.m, gp);
                    push_point(&mut gr[1], fb, qb, b.m, [-gp[0], -gp[1]]);
                    if side == 0.0 {
                        gr[0][3] -= 1.0;
                        gr[1][3] -= 1.0;
                    } else {
                        gr[0][3] += side;
                        gr[1][3] -= side;
                    }
                }
                if side == 0.0 {
                    len - fa.dim - fb.dim - z[d]
                } else {
                    side * (fa.dim - fb.dim) - len - z[d]
                }
            }
            Eq::Angle { u, v, a } => {
                if grad {
                    gr[0][2] -= 1.0;
                    gr[1][2] += 1.0;
                }
                wrap(fr[v.g].th + z[v.phi] - fr[u.g].th - z[u.phi] - z[a])
            }
            Eq::Cross { u, v } => {
                let (uu, vv) = (dir(&fr[u.g], z, &u), dir(&fr[v.g], z, &v));
                if grad {
                    push_dir(&mut gr[0], uu, [vv[1], -vv[0]]);
                    push_dir(&mut gr[1], vv, [-uu[1], uu[0]]);
                }
                uu[0] * vv[1] - uu[1] * vv[0]
            }
            Eq::Dot { u, v } => {
                let (uu, vv) = (dir(&fr[u.g], z, &u), dir(&fr[v.g], z, &v));
                if grad {
                    push_dir(&mut gr[0], uu, vv);
                    push_dir(&mut gr[1], vv, uu);
                }
                uu[0] * vv[0] + uu[1] * vv[1]
            }
            Eq::Comp { u, y } => {
                let uu = dir(&fr[u.g], z, &u);
                if grad {
                    push_dir(&mut gr[0], uu, if y { [0.0, 1.0] } else { [1.0, 0.0] });
                }
                uu[usize::from(y)]
            }
            Eq::Dim { g, v } => {
                if grad {
                    gr[0][3] = 1.0;
                }
                fr[g].dim - z[v]
            }
            Eq::SameDim { a, b } => {
                if grad {
                    gr[0][3] = 1.0;
                    gr[1][3] = -1.0;
                }
                fr[a].dim - fr[b].dim
            }
            Eq::MirrorMid {
                p,
                q,
                base,
                dir: dd,
            } => {
                let (fp, fq, fl) = (&fr[p.g], &fr[q.g], &fr[base.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pq, qq) = point(fq, z, &q);
                let (pb, qb) = point(fl, z, &base);
                let u = dir(fl, z, &dd);
                let w = [0.5 * (pp[0] + pq[0]) - pb[0], 0.5 * (pp[1] + pq[1]) - pb[1]];
                if grad {
                    let gm = [-u[1], u[0]];
                    let half = [0.5 * gm[0], 0.5 * gm[1]];
                    push_point(&mut gr[0], fp, qp, p.m, half);
                    push_point(&mut gr[1], fq, qq, q.m, half);
                    push_point(&mut gr[2], fl, qb, base.m, [-gm[0], -gm[1]]);
                    push_dir(&mut gr[2], u, [w[1], -w[0]]);
                }
                u[0] * w[1] - u[1] * w[0]
            }
            Eq::MirrorPerp { p, q, dir: dd } => {
                let (fp, fq, fl) = (&fr[p.g], &fr[q.g], &fr[dd.g]);
                let (pp, qp) = point(fp, z, &p);
                let (pq, qq) = point(fq, z, &q);
                let u = dir(fl, z, &dd);
                let w = [pq[0] - pp[0], pq[1] - pp[1]];
                if grad {
                    push_point(&mut gr[0], fp, qp, p.m, [-u[0], -u[1]]);
                    push_point(&mut gr[1], fq, qq, q.m, u);
                    push_dir(&mut gr[2], u, w);
                }
                u[0] * w[0] + u[1] * w[1]
            }
        };
        (v, gr)
    }

    /// The length scale `L` of the start configuration, for [`Solver::equilibrate`]: the
    /// largest of the spread of the frame origins, the offsets of the features the equations
    /// read, frame dimensions and the equations' distances (1 if all are zero); it is
    /// translation-invariant.
    fn length_scale(&self) -> f64 {
        let z = &self.z;
        let fr = &self.frames;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut l = 0.0f64;
        for f in fr {
            lo = [lo[0].min(f.ox), lo[1].min(f.oy)];
            hi = [hi[0].max(f.ox), hi[1].max(f.oy)];
            l = l.max(f.dim.abs()).max(f.h.abs());
        }
        let off = |p: &Pt| {
            let (_, q) = point(&fr[p.g], z, p);
            q[0].hypot(q[1])
        };
        for e in &self.eqs {
            let (a, b, d) = match *e {
                Eq::Diff { a, b, .. } => (off(&a), off(&b), 0.0),
                Eq::Dist { a, b, d } | Eq::CircleCircle { a, b, d } => (off(&a), off(&b), z[d]),
                Eq::PointLine { p, base, d, .. } => (off(&p), off(&base), z[d]),
                Eq::PointCircle { p, c, d } => (off(&p), off(&c), z[d]),
                Eq::LineCircle { base, c, d, .. } => (off(&base), off(&c), z[d]),
                Eq::Dim { v, .. } => (0.0, 0.0, z[v]),
                Eq::SameDim { .. } => (0.0, 0.0, 0.0),
                Eq::MirrorMid { p, q, base, .. } => (off(&p).max(off(&q)), off(&base), 0.0),
                Eq::MirrorPerp { p, q, .. } => (off(&p), off(&q), 0.0),
                Eq::Angle { .. } | Eq::Cross { .. } | Eq::Dot { .. } | Eq::Comp { .. } => {
                    (0.0, 0.0, 0.0)
                }
            };
            l = l.max(a).max(b).max(d.abs());
        }
        if !fr.is_empty() {
            l = l.max(hi[0] - lo[0]).max(hi[1] - lo[1]);
        }
        l
    }
}

/// A geom's frame from `z`.
#[inline]
fn frame(g: &Geom, z: &[f64]) -> Fr {
    let th = z[g.q[2]];
    let (s, c) = th.sin_cos();
    match g.shape {
        Shape::Frame => Fr {
            ox: z[g.q[0]],
            oy: z[g.q[1]],
            th,
            c,
            s,
            dim: z[g.q[3]],
            h: 0.0,
        },
        Shape::Line => {
            let h = z[g.q[3]];
            Fr {
                ox: z[g.q[0]] - h * s,
                oy: z[g.q[1]] + h * c,
                th,
                c,
                s,
                dim: 0.0,
                h,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The analytic Jacobian of the equations of `equal`, `midpoint` and `symmetric` (three
    /// frames each, a free line's offset among them) is their derivative: central differences
    /// of the equilibrated residual agree with it column by column.
    #[test]
    fn the_jacobian_of_the_sketcher_constraints_is_their_derivative() {
        let text = "space 2d;
            fixed point O = (0, 0);
            body B at (1, 2) rotated 0.3 { point p = (0.5, -0.2); point q = (2, 1); }
            line L = (0.2, 0.1) -> (1.1, 1.5);
            segment S = (-1, 0.5) -> (2, 1.2);
            segment T = (0, -1) -> (1, -2);
            circle C = center (3, 3) radius 1;
            circle D = center (-3, 3) radius 0.5;
            point P = (1.5, 0.9);
            symmetric(B.p, P, L);
            symmetric(S.start, S.end, L);
            midpoint(B.q, S);
            midpoint(P, T);
            equal(S, T);
            equal(C, D);";
        let (_, model, diags) = gcs_lang::load("jacobian.gcs", text.as_bytes());
        let model = model.unwrap_or_else(|| panic!("{diags:?}"));
        let Baseline {
            eq: mut b,
            mut solver,
        } = Baseline::with_linear(&model, Linear::Dense).expect("baseline");
        let params = model.default_params();
        let (n, m) = (b.n, b.m);
        assert_eq!(m, 2 + 2 + 2 + 2 + 1 + 1);
        for (k, r) in b.consts.iter().enumerate() {
            b.z[n + k] = r.eval(&b.model.exprs, &params);
        }
        let start: Vec<f64> = b
            .start
            .iter()
            .map(|r| r.eval(&model.exprs, &params))
            .collect();
        for (i, x) in start.iter().enumerate() {
            // Off the sketch, so that nothing sits at a special point.
            b.z[i] = x + 0.05 * (i as f64 + 1.0).sin();
        }
        b.choose_sides();
        solver.equilibrate(b.length_scale());
        solver.jacobian(&mut b);
        let analytic = solver.jacobian_values().to_vec();
        for c in 0..n {
            let (x, h) = (b.z[c], 1e-6);
            b.z[c] = x + h;
            solver.residual(&mut b);
            let plus = solver.trial_values().to_vec();
            b.z[c] = x - h;
            solver.residual(&mut b);
            let minus = solver.trial_values().to_vec();
            b.z[c] = x;
            for e in 0..m {
                let numeric = (plus[e] - minus[e]) / (2.0 * h) * solver.column_scale(c);
                let exact = analytic[e * n + c];
                assert!(
                    (numeric - exact).abs() <= 1e-6 * (1.0 + exact.abs()),
                    "equation {e} ({:?}), unknown {c}: {exact} analytic, {numeric} numeric",
                    b.eqs[e]
                );
            }
        }
    }
}
