//! The resolved model: params, geoms (with their members and sub-geoms), constraints and
//! outputs, in arenas with typed ids. It is immutable once built; later stages keep their own
//! state in side tables keyed by these ids.

use crate::constraints::{ConstraintKind, ConstraintSpec, JointValue};
use crate::expr::{Dim, ExprId, Exprs, ParamId};
use crate::source::{SourceFile, Span};
use la_arena::{Arena, Idx};
use std::collections::{BTreeMap, HashMap};
use std::fmt;

/// A geom, member or sub-geom, in the model's geom arena.
pub type GeomId = Idx<Geom>;

/// A constraint, in the model's constraint arena.
pub type ConstraintId = Idx<Constraint>;

/// The space a model lives in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Space {
    /// The XY plane: two coordinates.
    D2,
    /// Space: three coordinates.
    D3,
}

impl Space {
    /// The number of coordinates of a point.
    pub fn coords(self) -> usize {
        match self {
            Space::D2 => 2,
            Space::D3 => 3,
        }
    }

    /// `2d` or `3d`.
    pub fn name(self) -> &'static str {
        match self {
            Space::D2 => "2d",
            Space::D3 => "3d",
        }
    }
}

/// A run-time parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// Its name.
    pub name: String,
    /// Its default, as written (it may read other params' defaults).
    pub default_expr: ExprId,
    /// The default's value.
    pub default: f64,
    /// What it holds: an angle (radians, its default has a unit), a length (a length uses
    /// it) or a plain number.
    pub dim: Dim,
    /// The name's span in its declaration.
    pub span: Span,
}

/// The kinds of geom, members and sub-geoms included.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GeomKind {
    /// A point.
    Point,
    /// A direction (unit vector).
    Vector,
    /// An infinite directed line.
    Line,
    /// A segment of variable length.
    Segment,
    /// A circle of variable radius.
    Circle,
    /// An oriented plane (3d).
    Plane,
    /// A rigid body.
    Body,
    /// A point with axes on a body.
    Marker,
}

impl GeomKind {
    /// The kind with its article, for messages: "a point", "an infinite line".
    pub fn noun(self) -> &'static str {
        match self {
            GeomKind::Point => "a point",
            GeomKind::Vector => "a vector",
            GeomKind::Line => "a line",
            GeomKind::Segment => "a segment",
            GeomKind::Circle => "a circle",
            GeomKind::Plane => "a plane",
            GeomKind::Body => "a body",
            GeomKind::Marker => "a marker",
        }
    }

    /// The keyword that declares it.
    pub fn keyword(self) -> &'static str {
        match self {
            GeomKind::Point => "point",
            GeomKind::Vector => "vector",
            GeomKind::Line => "line",
            GeomKind::Segment => "segment",
            GeomKind::Circle => "circle",
            GeomKind::Plane => "plane",
            GeomKind::Body => "body",
            GeomKind::Marker => "marker",
        }
    }

    /// The degrees of freedom of a free geom of this kind in `space` (the table of
    /// LANGUAGE.md). Members and sub-geoms move with their owner and have none of their own.
    pub fn dof(self, space: Space) -> usize {
        match (self, space) {
            (GeomKind::Point, Space::D2) => 2,
            (GeomKind::Point, Space::D3) => 3,
            (GeomKind::Vector, Space::D2) => 1,
            (GeomKind::Vector, Space::D3) => 2,
            (GeomKind::Line, Space::D2) => 2,
            (GeomKind::Line, Space::D3) => 4,
            (GeomKind::Segment, Space::D2) => 4,
            (GeomKind::Segment, Space::D3) => 6,
            (GeomKind::Circle, Space::D2) => 3,
            (GeomKind::Circle, Space::D3) => 6,
            (GeomKind::Plane, _) => 3,
            (GeomKind::Body, Space::D2) => 3,
            (GeomKind::Body, Space::D3) => 6,
            (GeomKind::Marker, _) => 0,
        }
    }

    /// Whether it stands for a position (a point, or a marker's point).
    pub fn is_pointlike(self) -> bool {
        matches!(self, GeomKind::Point | GeomKind::Marker)
    }
}

/// A named part of a geom: `S.start`, `L.dir`, `C.center`, `k.z`, ...
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    /// `L.point`: the foot of the perpendicular from the line's first sketch point.
    BasePoint,
    /// `S.start`
    Start,
    /// `S.end`
    End,
    /// `L.dir`, `S.dir`
    Dir,
    /// `C.center`
    Center,
    /// `C.normal` (3d), `Q.normal`
    Normal,
    /// `k.z` (3d)
    AxisZ,
    /// `k.x`
    AxisX,
}

impl Part {
    /// The word after the dot.
    pub fn name(self) -> &'static str {
        match self {
            Part::BasePoint => "point",
            Part::Start => "start",
            Part::End => "end",
            Part::Dir => "dir",
            Part::Center => "center",
            Part::Normal => "normal",
            Part::AxisZ => "z",
            Part::AxisX => "x",
        }
    }
}

/// Where a geom sits in the hierarchy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// Declared at top level.
    TopLevel,
    /// A member declared in a body's block.
    Member(GeomId),
    /// A sub-geom of a geom (`S.start`) or of a marker (`k.z`).
    Part(GeomId, Part),
}

/// Coordinates as written (2 or 3 expressions, per the space).
pub type Coords = Vec<ExprId>;

/// The sketch of a geom: its starting configuration as written. Members are in their body's
/// local frame; everything else is global. Not a constraint.
#[derive(Clone, Debug, PartialEq)]
pub enum Sketch {
    /// `point P = (x, y[, z]);`
    Point(Coords),
    /// `vector v = (...);` normalised when evaluated.
    Vector(Coords),
    /// `line L = (...) -> (...);`
    Line {
        /// First point.
        from: Coords,
        /// Second point.
        to: Coords,
    },
    /// `segment S = (...) -> (...);`
    Segment {
        /// Start point.
        from: Coords,
        /// End point.
        to: Coords,
    },
    /// `circle C = center (...) radius r [normal (...)];`
    Circle {
        /// Centre.
        center: Coords,
        /// Radius.
        radius: ExprId,
        /// Normal of its plane, in 3d.
        normal: Option<Coords>,
    },
    /// `plane Q = normal (...) offset d;` or `plane Q = point (...) normal (...);`
    Plane {
        /// Normal.
        normal: Coords,
        /// Offset or a point on it.
        placement: PlanePlacement,
    },
    /// `body B [at (...)] [rotated a [about (...)]] { ... }`
    Body {
        /// Position of its frame's origin; the origin when absent.
        at: Option<Coords>,
        /// Rotation angle (radians); none when absent.
        angle: Option<ExprId>,
        /// Rotation axis (3d); the z axis when absent.
        axis: Option<Coords>,
    },
    /// `marker k = (...) [z (...)] x (...);`
    Marker {
        /// Its point.
        origin: Coords,
        /// Its z axis (3d only; in 2d it is out of the plane).
        z: Option<Coords>,
        /// Its x axis.
        x: Coords,
    },
    /// A sub-geom: defined by its owner's sketch.
    Derived,
}

/// How a plane's position is written.
#[derive(Clone, Debug, PartialEq)]
pub enum PlanePlacement {
    /// `offset d`: the plane holds the points p with normal . p = d.
    Offset(ExprId),
    /// `point (...)`: a point on the plane.
    Point(Coords),
}

/// A geom, body member or sub-geom.
#[derive(Clone, Debug, PartialEq)]
pub struct Geom {
    /// The dotted name: `A`, `crank.b`, `S.start`, `ground.o.z`.
    pub name: String,
    /// Its kind.
    pub kind: GeomKind,
    /// Top level, member or part.
    pub owner: Owner,
    /// Whether it is grounded: declared `fixed`, or owned by a fixed geom.
    pub fixed: bool,
    /// The span of its name where declared (the owner's, for sub-geoms).
    pub span: Span,
    /// Its sketch.
    pub sketch: Sketch,
    /// Its members and sub-geoms, in declaration order.
    pub parts: Vec<GeomId>,
}

/// A constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    /// Which constraint.
    pub kind: ConstraintKind,
    /// Its arguments, in the order the table's form lists them (a symmetric constraint written
    /// the other way round is normalised, for example `distance(L, p)` to `distance(p, L)`).
    pub args: Vec<GeomId>,
    /// Its value, if it takes one.
    pub value: Option<ExprId>,
    /// The label, if written.
    pub label: Option<String>,
    /// The label, or the stable name derived from the statement when there is none.
    pub name: String,
    /// The whole statement.
    pub span: Span,
    /// The statement as written, without label and `;`, whitespace collapsed.
    pub text: String,
}

impl Constraint {
    /// The table row of its kind.
    pub fn spec(&self) -> &'static ConstraintSpec {
        self.kind.spec()
    }
}

/// An `output` reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// What it names.
    pub of: OutputOf,
    /// The reference as written, its words joined by dots (`crank.b`, `q1.angle`).
    pub path: String,
    /// Where.
    pub span: Span,
}

/// What an `output` names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputOf {
    /// A geom, member or part; for `G.radius`, `S.length` and `Q.offset`, the geom holding the
    /// dimension.
    Geom(GeomId),
    /// A value of joint constraint `J` (`J.angle`, `J.travel`), measured on its arguments:
    /// the kind is one whose [`ConstraintKind::joint_values`] hold the value.
    Joint(ConstraintId, JointValue),
}

/// A resolved `.gcs` model.
#[derive(Clone, Debug)]
pub struct Model {
    /// The file it came from.
    pub source: SourceFile,
    /// `2d` or `3d`.
    pub space: Space,
    /// Params, in declaration order.
    pub params: Arena<Param>,
    /// Every expression.
    pub exprs: Exprs,
    /// Geoms, members and sub-geoms; owners come before their parts.
    pub geoms: Arena<Geom>,
    /// Constraints, in source order.
    pub constraints: Arena<Constraint>,
    /// Output references, in source order; empty means everything.
    pub outputs: Vec<Output>,
    pub(crate) names: BTreeMap<String, GeomId>,
    pub(crate) param_index: ParamIndex,
}

/// The params indexed once, when the model is built: looking one up by name and evaluating at
/// the defaults then cost the name or the expression, not the number of params (a report
/// evaluates every constraint's value, and a scan there made `gcs check` quadratic).
#[derive(Clone, Debug, Default)]
pub(crate) struct ParamIndex {
    by_name: HashMap<String, ParamId>,
    /// Every param's default, indexed like the arena: the slice [`Exprs::eval`] reads.
    defaults: Vec<f64>,
}

impl ParamIndex {
    /// The index of `params`; of two params with one name (a model with errors), the first.
    pub(crate) fn new(params: &Arena<Param>) -> ParamIndex {
        let mut by_name = HashMap::with_capacity(params.len());
        for (id, p) in params.iter() {
            by_name.entry(p.name.clone()).or_insert(id);
        }
        ParamIndex {
            by_name,
            defaults: params.iter().map(|(_, p)| p.default).collect(),
        }
    }
}

impl Model {
    /// The geom with dotted name `name`.
    pub fn geom_named(&self, name: &str) -> Option<GeomId> {
        self.names.get(name).copied()
    }

    /// The param called `name`.
    pub fn param_named(&self, name: &str) -> Option<ParamId> {
        self.param_index.by_name.get(name).copied()
    }

    /// Top-level geoms, in declaration order.
    pub fn top_level(&self) -> impl Iterator<Item = (GeomId, &Geom)> {
        self.geoms
            .iter()
            .filter(|(_, g)| g.owner == Owner::TopLevel)
    }

    /// The geoms output `o` needs solved: the geom it names, or the two arguments of its joint
    /// (markers, or for `in_line` a point and a marker).
    pub fn output_geoms<'a>(&'a self, o: &'a Output) -> &'a [GeomId] {
        match &o.of {
            OutputOf::Geom(g) => std::slice::from_ref(g),
            OutputOf::Joint(c, _) => &self.constraints[*c].args,
        }
    }

    /// The joint values the outputs name, each once, in the order first named: the value's
    /// name as written (`q1.angle`), its constraint and which value.
    pub fn joint_outputs(&self) -> Vec<(&str, ConstraintId, JointValue)> {
        let mut seen = std::collections::HashSet::new();
        (self.outputs.iter())
            .filter_map(|o| match o.of {
                OutputOf::Joint(c, v) if seen.insert((c, v)) => Some((o.path.as_str(), c, v)),
                _ => None,
            })
            .collect()
    }

    /// The top-level geom that moves `id` (itself, its body, or its owner's owner).
    pub fn top_level_of(&self, mut id: GeomId) -> GeomId {
        loop {
            match self.geoms[id].owner {
                Owner::TopLevel => return id,
                Owner::Member(o) | Owner::Part(o, _) => id = o,
            }
        }
    }

    /// The default value of every param, indexed like the param arena.
    pub fn default_params(&self) -> Vec<f64> {
        self.param_index.defaults.clone()
    }

    /// The value of an expression with the default params.
    pub fn eval_default(&self, e: ExprId) -> f64 {
        self.exprs.eval(e, &self.param_index.defaults)
    }

    /// The 1-based source line of a span's start.
    pub fn line(&self, span: Span) -> usize {
        self.source.line(span.start)
    }

    /// The part `p` of geom `g` (`S.start`, `L.dir`, `C.center`, `k.x`), if it has one.
    pub fn part(&self, g: GeomId, p: Part) -> Option<GeomId> {
        self.geoms[g]
            .parts
            .iter()
            .copied()
            .find(|&c| self.geoms[c].owner == Owner::Part(g, p))
    }

    /// The point a geom stands for where a constraint takes a point: a circle's centre, and
    /// any other geom itself (a point, a marker's point).
    pub fn point_feature(&self, g: GeomId) -> GeomId {
        match self.geoms[g].kind {
            GeomKind::Circle => self.part(g, Part::Center).unwrap_or(g),
            _ => g,
        }
    }

    /// The direction a geom stands for where a constraint takes a direction: a vector itself,
    /// the `dir` of a line or segment, the normal of a plane.
    pub fn dir_feature(&self, g: GeomId) -> Option<GeomId> {
        match self.geoms[g].kind {
            GeomKind::Vector => Some(g),
            GeomKind::Line | GeomKind::Segment => self.part(g, Part::Dir),
            GeomKind::Plane => self.part(g, Part::Normal),
            _ => None,
        }
    }

    /// The (point on it, direction) features of something line-like where a constraint takes
    /// a line: a line's base point or a segment's start, and its `dir`; a marker's point and
    /// its x axis.
    pub fn line_features(&self, g: GeomId) -> Option<(GeomId, GeomId)> {
        match self.geoms[g].kind {
            GeomKind::Line => Some((g, self.part(g, Part::Dir)?)),
            GeomKind::Segment => Some((self.part(g, Part::Start)?, self.part(g, Part::Dir)?)),
            GeomKind::Marker => Some((g, self.part(g, Part::AxisX)?)),
            _ => None,
        }
    }

    /// Whether constraint `c`'s value is a size, zero or more: a length, a radius or an
    /// unsigned distance (point-point, point-circle, line-circle, circle-circle, and
    /// point-line in 3d). A negative value of it is invalid, not a miss. Signed distances
    /// (point-line in 2d, point-plane) and the other values are not sizes.
    pub fn value_is_size(&self, c: ConstraintId) -> bool {
        let c = &self.constraints[c];
        let kind = |i: usize| c.args.get(i).map(|&g| self.geoms[g].kind);
        match c.kind {
            ConstraintKind::Length | ConstraintKind::Radius => true,
            ConstraintKind::Distance => match kind(1) {
                Some(GeomKind::Plane) => false,
                Some(GeomKind::Line | GeomKind::Segment) => self.space == Space::D3,
                _ => true,
            },
            _ => false,
        }
    }

    /// The distance between two point members (points or markers) of one body whose local
    /// coordinates are constants: known without params. Computed as `sqrt(dx² + dy²)`, the
    /// arithmetic of a vector's norm, so that every consumer gets the same bits.
    pub fn constant_distance(&self, a: GeomId, b: GeomId) -> Option<f64> {
        // In 2d the third coordinate is absent, read as 0: the sum is the plane's, exactly.
        let local = |f: GeomId| -> Option<[f64; 3]> {
            match (&self.geoms[f].sketch, self.geoms[f].owner) {
                (Sketch::Point(c) | Sketch::Marker { origin: c, .. }, Owner::Member(_))
                    if c.iter().all(|&e| self.exprs.is_constant(e)) =>
                {
                    let v = |i: usize| c.get(i).map_or(0.0, |&e| self.exprs.eval(e, &[]));
                    Some([v(0), v(1), v(2)])
                }
                _ => None,
            }
        };
        if self.top_level_of(a) != self.top_level_of(b) {
            return None;
        }
        let (pa, pb) = (local(a)?, local(b)?);
        let (dx, dy, dz) = (pa[0] - pb[0], pa[1] - pb[1], pa[2] - pb[2]);
        Some((dx * dx + dy * dy + dz * dz).sqrt())
    }

    /// The nominal DOF of a constraint: what it removes if independent of the others, with
    /// its value at the default params (a zero distance removes more than a non-zero one).
    pub fn nominal_dof_removed(&self, c: ConstraintId) -> usize {
        let c = &self.constraints[c];
        let kinds: Vec<GeomKind> = c.args.iter().map(|&a| self.geoms[a].kind).collect();
        let value = c.value.map(|v| self.eval_default(v));
        c.kind.nominal_dof(self.space, &kinds, value)
    }
}

impl fmt::Display for Space {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
