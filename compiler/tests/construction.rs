//! The construction checker (paper 000, section 4.3) and the generated fragment table
//! (`docs/FRAGMENTS.md`).
//!
//! # How the table is enumerated
//!
//! The table is probed from the analysis, not written by hand. For every 2d geom kind that
//! moves (point, vector, line, segment, circle, and a body with point, vector and marker
//! members) the probe declares one free geom `P` and a list of *states*. A state is a prefix of
//! constraints between `P` and fixed geoms that brings `P` into a given invariants record:
//! free; a point or an end pinned; a rotation known; a point on a line or on a circle; a free
//! length or radius; fixed-distance lines and points of a circle and the centre loci they make
//! (bisector, parabola, conics); a dimension fixed, or equal to a fixed one; a segment pinned
//! at its midpoint; combinations of those; fully fixed. Then,
//! for every constraint form of the language in 2d that applies to the kind (coincident,
//! distance point-point / point-line / point-circle / line-circle / circle-circle, on, tangent,
//! angle, parallel, perpendicular, horizontal, vertical, length, radius, equal, midpoint (a
//! feature of `P` at a fixed segment's midpoint, or a fixed point at `P`'s), symmetric (a
//! feature of `P` the mirror image of a fixed point, or `P` the mirror line of two), in_line,
//! offset_x, revolute, prismatic, spherical), one last constraint `z` is added between a
//! feature of `P` and new fixed geoms. Constraints are labelled `p0`, `p1`, ... and `z`, so that the
//! analysis, which takes constraints in name order, meets the prefix first. Dimensions
//! (`length`, `radius`) are solved before everything else, so they are probed as the last
//! constraint only in states made of dimensions.
//!
//! Each entry is analysed once on a canonical instance and classified by what the analysis did
//! for `z`:
//! - *fragment*: the op kinds of the steps the analysis emitted for it (from the step after the
//!   previous step that satisfied a constraint, through the step that satisfies `z`, and the
//!   actions right after it that close the record, such as a circle's radius set when its centre
//!   is placed);
//! - *check*: a run-time check was emitted (the constraint is implied);
//! - *recorded*: no step satisfies it yet; it is kept in the record (a circle's fixed distance),
//!   and satisfied by the step that places the circle;
//! - *not yet*: it is in `Analysis::unsolved`, with the reason.
//!
//! The signature of `P`'s cluster is read before (from the prefix alone) and after.
//!
//! # The checker
//!
//! For every *fragment* and *check* entry, random instances that have a solution are built:
//! a random target configuration of `P` is drawn, every fixed geom and every value is derived
//! from it (a fixed point at the target position of a member, a distance measured in the
//! target, ...), and `P`'s sketch is the target moved by a random rigid motion (and its length
//! or radius changed). Near-degenerate instances add: the new locus tangent to the motion the
//! prefix leaves (collinear pivots, tangent circles, a line along the motion), nearly tangent
//! (by 1e-9 to 1e-4 rad), the sketch exactly at the target or 1e-9 away from it, and scales
//! 1e-3 and 1e3. Each instance is solved on the default branches and on every other branch
//! combination. A run that returns a solution must satisfy every constraint its plan claims
//! (every step's `satisfies`: the new constraint and every earlier invariant), measured by
//! `verify`, to 1e-12 relative to the instance's scale, or to the answer's own magnitude when
//! it lies farther out (a root far along a parabola's arm), and 1e-12 rad for angles; anything
//! else is a *wrong fragment* and fails the test. A `SolveError` is never wrong, but an instance that no
//! branch solves is reported as *not solved*.
//!
//! Every plan comes from the pipeline's `analyse`, which validates it (`Plan::validate`, and
//! that only the constraints reported unsolved or recorded have no step): a malformed plan
//! panics there, and a panic is a wrong run.
//!
//! # Default fragments
//!
//! For every state, its prefix alone leaves `P` some freedom, which the analysis parameterizes
//! with defaults (000, section 5.2.1). The table's last section lists them per state, and
//! checks them: as many defaults as `P` has DOF left (or the freedom refused and reported);
//! on instances whose sketch satisfies the prefix, the sketch's defaults move nothing (least
//! motion); on random instances, every constraint holds at the sketch's defaults and with each
//! default moved, and each default moves `P`. A fragment entry whose step satisfying `z`
//! comes after a default says so ("after a default").
//!
//! `GCS_WRITE_FRAGMENTS=1` writes `docs/FRAGMENTS.md`; without it the test checks that the
//! committed file is current. The file holds no timing (the test prints its run time).

use gcs_compiler::analyse;
use gcs_compiler::analysis::Analysis;
use gcs_compiler::plan::Op;
use gcs_lang::constraints::ConstraintKind as CK;
use gcs_lang::model::ConstraintId;
use gcs_lang::Model;
use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write as _;

// ---------------------------------------------------------------- small maths

type V = [f64; 2];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}
fn mul(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn cross(a: V, b: V) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn norm(a: V) -> f64 {
    a[0].hypot(a[1])
}
fn unit(a: V) -> V {
    mul(a, 1.0 / norm(a))
}
fn perp(a: V) -> V {
    [-a[1], a[0]]
}
fn dir(t: f64) -> V {
    [t.cos(), t.sin()]
}
fn rot(a: V, t: f64) -> V {
    let (s, c) = t.sin_cos();
    [c * a[0] - s * a[1], s * a[0] + c * a[1]]
}
fn heading(a: V) -> f64 {
    a[1].atan2(a[0])
}
fn angle_from(u: V, v: V) -> f64 {
    cross(u, v).atan2(dot(u, v))
}

// ---------------------------------------------------------------- a deterministic RNG

/// xorshift64*, seeded through splitmix64.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        Rng(z | 1)
    }
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn f(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f()
    }
    fn sign(&mut self) -> f64 {
        if self.next() & 1 == 0 {
            1.0
        } else {
            -1.0
        }
    }
    fn angle(&mut self) -> f64 {
        self.range(-PI, PI)
    }
    fn unit(&mut self) -> V {
        dir(self.angle())
    }
    fn point(&mut self, s: f64) -> V {
        [self.range(-s, s), self.range(-s, s)]
    }
    fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.f()).exp()
    }
}

// ---------------------------------------------------------------- the probed geom

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Point,
    Vector,
    Line,
    Segment,
    Circle,
    Body,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Point => "point",
            Kind::Vector => "vector",
            Kind::Line => "line",
            Kind::Segment => "segment",
            Kind::Circle => "circle",
            Kind::Body => "body",
        }
    }
}

/// A point feature of `P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pt {
    Own,
    Start,
    End,
    Center,
    A,
    B,
    K,
}

impl Pt {
    fn text(self) -> &'static str {
        match self {
            Pt::Own => "P",
            Pt::Start => "P.start",
            Pt::End => "P.end",
            Pt::Center => "P.center",
            Pt::A => "P.a",
            Pt::B => "P.b",
            Pt::K => "P.k",
        }
    }
}

/// A direction feature of `P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Di {
    Own,
    V,
    Kx,
}

impl Di {
    fn text(self) -> &'static str {
        match self {
            Di::Own => "P",
            Di::V => "P.v",
            Di::Kx => "P.k.x",
        }
    }
}

/// The local members of a body probe.
#[derive(Clone, Copy, Debug)]
struct Members {
    a: V,
    b: V,
    v: V,
    k: V,
    kx: V,
}

/// A configuration of `P`: position (point, line base, segment start, circle centre, body
/// origin), rotation, dimension (segment length, circle radius).
#[derive(Clone, Copy, Debug)]
struct Conf {
    pos: V,
    ang: f64,
    dim: f64,
}

fn pt(c: &Conf, m: &Members, p: Pt) -> V {
    match p {
        Pt::Own | Pt::Start | Pt::Center => c.pos,
        Pt::End => add(c.pos, mul(dir(c.ang), c.dim)),
        Pt::A => add(c.pos, rot(m.a, c.ang)),
        Pt::B => add(c.pos, rot(m.b, c.ang)),
        Pt::K => add(c.pos, rot(m.k, c.ang)),
    }
}

fn local_dir(m: &Members, d: Di) -> V {
    match d {
        Di::Own => [1.0, 0.0],
        Di::V => m.v,
        Di::Kx => m.kx,
    }
}

fn di(c: &Conf, m: &Members, d: Di) -> V {
    rot(local_dir(m, d), c.ang)
}

// ---------------------------------------------------------------- constraint forms

/// A constraint between a feature of `P` and a new fixed geom (or a unary one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Form {
    Coincident(Pt),
    DistPP(Pt),
    DistPL(Pt),
    OnPL(Pt),
    OnPC(Pt),
    DistPC(Pt),
    Spherical(Pt),
    InLine(Pt),
    Revolute,
    Prismatic,
    Angle(Di),
    Parallel(Di),
    Perpendicular(Di),
    Horizontal(Di),
    Vertical(Di),
    OffsetX,
    LineOn,
    LineDist,
    LineTangent,
    LineCircleDist,
    InLineRev,
    CircleOn,
    CircleDist,
    CircleTangentLine,
    CircleDistLine,
    CircleTangentCircle,
    CircleDistCircle,
    Length,
    Radius,
    /// `midpoint(P.x, segment)`: a feature of `P` at the midpoint of a fixed segment.
    Midpoint(Pt),
    /// `symmetric(P.x, point, line)`: a feature of `P` the mirror image of a fixed point.
    Mirror(Pt),
    /// `midpoint(point, P)`: a fixed point at the midpoint of `P`.
    SegMidpoint,
    /// `equal(P, segment)`: `P`'s length that of a fixed segment.
    EqualSegment,
    /// `equal(P, circle)`: `P`'s radius that of a fixed circle.
    EqualCircle,
    /// `symmetric(point, point, P)`: `P` the mirror line of two fixed points.
    MirrorLine,
}

impl Form {
    /// The form as it reads in the table (fixed geoms by their kind).
    fn text(self) -> String {
        match self {
            Form::Coincident(p) => format!("coincident({}, point)", p.text()),
            Form::DistPP(p) => format!("distance({}, point) = d", p.text()),
            Form::DistPL(p) => format!("distance({}, line) = d", p.text()),
            Form::OnPL(p) => format!("on({}, line)", p.text()),
            Form::OnPC(p) => format!("on({}, circle)", p.text()),
            Form::DistPC(p) => format!("distance({}, circle) = d", p.text()),
            Form::Spherical(p) => format!("spherical({}, point)", p.text()),
            Form::InLine(p) => format!("in_line({}, marker)", p.text()),
            Form::Revolute => "revolute(P.k, marker)".into(),
            Form::Prismatic => "prismatic(P.k, marker)".into(),
            Form::Angle(d) => format!("angle(vector, {}) = a", d.text()),
            Form::Parallel(d) => format!("parallel(vector, {})", d.text()),
            Form::Perpendicular(d) => format!("perpendicular(vector, {})", d.text()),
            Form::Horizontal(d) => format!("horizontal({})", d.text()),
            Form::Vertical(d) => format!("vertical({})", d.text()),
            Form::OffsetX => "offset_x(marker, P.k) = a".into(),
            Form::LineOn => "on(point, P)".into(),
            Form::LineDist => "distance(point, P) = d".into(),
            Form::LineTangent => "tangent(P, circle)".into(),
            Form::LineCircleDist => "distance(P, circle) = d".into(),
            Form::InLineRev => "in_line(marker, P.k)".into(),
            Form::CircleOn => "on(point, P)".into(),
            Form::CircleDist => "distance(point, P) = d".into(),
            Form::CircleTangentLine => "tangent(line, P)".into(),
            Form::CircleDistLine => "distance(line, P) = d".into(),
            Form::CircleTangentCircle => "tangent(circle, P)".into(),
            Form::CircleDistCircle => "distance(circle, P) = d".into(),
            Form::Length => "length(P) = l".into(),
            Form::Radius => "radius(P) = r".into(),
            Form::Midpoint(p) => format!("midpoint({}, segment)", p.text()),
            Form::Mirror(p) => format!("symmetric({}, point, line)", p.text()),
            Form::SegMidpoint => "midpoint(point, P)".into(),
            Form::EqualSegment => "equal(P, segment)".into(),
            Form::EqualCircle => "equal(P, circle)".into(),
            Form::MirrorLine => "symmetric(point, point, P)".into(),
        }
    }

    /// The point feature it places, if any (for near-degenerate instances).
    fn point(self) -> Option<Pt> {
        match self {
            Form::Coincident(p)
            | Form::DistPP(p)
            | Form::DistPL(p)
            | Form::OnPL(p)
            | Form::OnPC(p)
            | Form::DistPC(p)
            | Form::Spherical(p)
            | Form::InLine(p)
            | Form::Midpoint(p)
            | Form::Mirror(p) => Some(p),
            Form::Revolute | Form::Prismatic => Some(Pt::K),
            _ => None,
        }
    }

    fn is_dim(self) -> bool {
        matches!(self, Form::Length | Form::Radius)
    }

    /// The world axis the form forces on a direction of `P`, if any.
    fn world(self) -> Option<(Di, f64)> {
        match self {
            Form::Horizontal(d) => Some((d, 0.0)),
            Form::Vertical(d) => Some((d, FRAC_PI_2)),
            _ => None,
        }
    }
}

/// Where a prefix constraint leaves the feature it constrains, in the target.
#[derive(Clone, Copy, Debug)]
enum Loc {
    None,
    Point(V),
    Line(V),
    Circle(V),
}

/// The one motion a state leaves (for tangent near-degenerate instances).
#[derive(Clone, Copy, Debug)]
enum Motion {
    /// Two or more DOF, or none: no tangent direction.
    Free,
    /// Rotation about the point prefix constraint `i` pins.
    Rotate(usize),
    /// Translation keeping feature `p` on the locus of prefix constraint `i`.
    Slide(usize, Pt),
}

struct State {
    name: &'static str,
    prefix: Vec<Form>,
    motion: Motion,
}

fn st(name: &'static str, prefix: Vec<Form>, motion: Motion) -> State {
    State {
        name,
        prefix,
        motion,
    }
}

/// The states of each kind, and the last-constraint forms that apply to it.
fn catalogue(kind: Kind) -> (Vec<State>, Vec<Form>) {
    use Form::*;
    use Motion::*;
    let point_forms = |p: Pt| {
        vec![
            Coincident(p),
            DistPP(p),
            DistPL(p),
            OnPL(p),
            OnPC(p),
            DistPC(p),
            Midpoint(p),
            Mirror(p),
        ]
    };
    let dir_forms = |d: Di| {
        vec![
            Angle(d),
            Parallel(d),
            Perpendicular(d),
            Horizontal(d),
            Vertical(d),
        ]
    };
    let line_forms = vec![LineOn, LineDist, LineTangent, LineCircleDist, MirrorLine];
    match kind {
        Kind::Point => {
            let mut forms = point_forms(Pt::Own);
            forms.extend([Spherical(Pt::Own), InLine(Pt::Own)]);
            (
                vec![
                    st("free", vec![], Free),
                    st("on a line", vec![OnPL(Pt::Own)], Slide(0, Pt::Own)),
                    st("on a circle", vec![DistPP(Pt::Own)], Slide(0, Pt::Own)),
                    st("fixed", vec![Coincident(Pt::Own)], Free),
                ],
                forms,
            )
        }
        Kind::Vector => (
            vec![
                st("free", vec![], Free),
                st("known", vec![Angle(Di::Own)], Free),
            ],
            dir_forms(Di::Own),
        ),
        Kind::Line => {
            let mut forms = dir_forms(Di::Own);
            forms.extend(line_forms);
            (
                vec![
                    st("free", vec![], Free),
                    st("direction known", vec![Angle(Di::Own)], Free),
                    st("through a point", vec![LineOn], Rotate(0)),
                    st("fixed", vec![Angle(Di::Own), LineOn], Free),
                ],
                forms,
            )
        }
        Kind::Segment => {
            let mut forms = point_forms(Pt::Start);
            forms.extend(point_forms(Pt::End));
            forms.extend(dir_forms(Di::Own));
            forms.extend(line_forms);
            forms.extend([Length, SegMidpoint, EqualSegment]);
            (
                vec![
                    st("free", vec![], Free),
                    st("length fixed", vec![Length], Free),
                    st("direction known", vec![Angle(Di::Own)], Free),
                    st("start pinned", vec![Coincident(Pt::Start)], Free),
                    st("end pinned", vec![Coincident(Pt::End)], Free),
                    st("start on a line", vec![OnPL(Pt::Start)], Free),
                    st(
                        "start pinned, direction known",
                        vec![Coincident(Pt::Start), Angle(Di::Own)],
                        Free,
                    ),
                    st(
                        "end pinned, direction known",
                        vec![Coincident(Pt::End), Angle(Di::Own)],
                        Free,
                    ),
                    st(
                        "length fixed, start pinned",
                        vec![Length, Coincident(Pt::Start)],
                        Rotate(1),
                    ),
                    st(
                        "length fixed, end pinned",
                        vec![Length, Coincident(Pt::End)],
                        Rotate(1),
                    ),
                    st(
                        "length fixed, direction known",
                        vec![Length, Angle(Di::Own)],
                        Free,
                    ),
                    st(
                        "length fixed, start on a line",
                        vec![Length, OnPL(Pt::Start)],
                        Free,
                    ),
                    st(
                        "length fixed, direction known, start on a line",
                        vec![Length, Angle(Di::Own), OnPL(Pt::Start)],
                        Slide(2, Pt::Start),
                    ),
                    st(
                        "length fixed, direction known, start on a circle",
                        vec![Length, Angle(Di::Own), DistPP(Pt::Start)],
                        Slide(2, Pt::Start),
                    ),
                    st("midpoint pinned", vec![SegMidpoint], Free),
                    st(
                        "direction known, midpoint pinned",
                        vec![Angle(Di::Own), SegMidpoint],
                        Free,
                    ),
                    st(
                        "length fixed, midpoint pinned",
                        vec![Length, SegMidpoint],
                        Rotate(1),
                    ),
                    st("length equal to a fixed one", vec![EqualSegment], Free),
                    st(
                        "fixed",
                        vec![Length, Coincident(Pt::Start), Angle(Di::Own)],
                        Free,
                    ),
                ],
                forms,
            )
        }
        Kind::Circle => {
            let mut forms = point_forms(Pt::Center);
            forms.extend([
                CircleOn,
                CircleDist,
                CircleTangentLine,
                CircleDistLine,
                CircleTangentCircle,
                CircleDistCircle,
                Radius,
                EqualCircle,
            ]);
            (
                vec![
                    st("free", vec![], Free),
                    st("radius fixed", vec![Radius], Free),
                    st("centre pinned", vec![Coincident(Pt::Center)], Free),
                    st("one fixed-distance line", vec![CircleTangentLine], Free),
                    st("one fixed-distance point", vec![CircleOn], Free),
                    st("one fixed-distance circle", vec![CircleTangentCircle], Free),
                    st(
                        "two fixed-distance lines (bisector)",
                        vec![CircleTangentLine, CircleDistLine],
                        Free,
                    ),
                    st(
                        "fixed-distance line and point (parabola)",
                        vec![CircleTangentLine, CircleOn],
                        Free,
                    ),
                    st(
                        "fixed-distance line and circle (parabola)",
                        vec![CircleTangentLine, CircleTangentCircle],
                        Free,
                    ),
                    st(
                        "two fixed-distance points (conic)",
                        vec![CircleOn, CircleDist],
                        Free,
                    ),
                    st(
                        "two fixed-distance circles (conic)",
                        vec![CircleTangentCircle, CircleDistCircle],
                        Free,
                    ),
                    st(
                        "radius fixed, centre on a line",
                        vec![Radius, OnPL(Pt::Center)],
                        Slide(1, Pt::Center),
                    ),
                    st(
                        "radius fixed, centre on a circle",
                        vec![Radius, DistPP(Pt::Center)],
                        Slide(1, Pt::Center),
                    ),
                    st(
                        "radius fixed, one fixed-distance line",
                        vec![Radius, CircleTangentLine],
                        Slide(1, Pt::Center),
                    ),
                    st(
                        "radius fixed, one fixed-distance circle",
                        vec![Radius, CircleTangentCircle],
                        Slide(1, Pt::Center),
                    ),
                    st(
                        "centre pinned, radius fixed",
                        vec![Radius, Coincident(Pt::Center)],
                        Free,
                    ),
                    st("radius equal to a fixed one", vec![EqualCircle], Free),
                ],
                forms,
            )
        }
        Kind::Body => {
            let mut forms = point_forms(Pt::B);
            forms.extend([Coincident(Pt::A), DistPP(Pt::A), OnPL(Pt::A)]);
            forms.extend([Spherical(Pt::B), InLine(Pt::K), Revolute, Prismatic]);
            forms.extend(dir_forms(Di::V));
            forms.extend([Angle(Di::Kx), OffsetX, InLineRev]);
            (
                vec![
                    st("free", vec![], Free),
                    st("pivot", vec![Coincident(Pt::A)], Rotate(0)),
                    st("rotation known", vec![Angle(Di::V)], Free),
                    st("point on a line", vec![OnPL(Pt::A)], Free),
                    st("point on a circle", vec![DistPP(Pt::A)], Free),
                    st(
                        "rotation known, point on a line",
                        vec![Angle(Di::V), OnPL(Pt::A)],
                        Slide(1, Pt::A),
                    ),
                    st(
                        "rotation known, point on a circle",
                        vec![Angle(Di::V), DistPP(Pt::A)],
                        Slide(1, Pt::A),
                    ),
                    st("prismatic joint", vec![Prismatic], Slide(0, Pt::K)),
                    st("revolute joint", vec![Revolute], Rotate(0)),
                    st("fixed", vec![Coincident(Pt::A), Angle(Di::V)], Free),
                ],
                forms,
            )
        }
    }
}

struct Entry {
    kind: Kind,
    state: &'static str,
    prefix: Vec<Form>,
    motion: Motion,
    last: Form,
}

fn entries() -> Vec<Entry> {
    let mut out = Vec::new();
    for kind in [
        Kind::Point,
        Kind::Vector,
        Kind::Line,
        Kind::Segment,
        Kind::Circle,
        Kind::Body,
    ] {
        let (states, forms) = catalogue(kind);
        for s in &states {
            for &f in &forms {
                // Dimensions are solved first: probe them only after dimensions.
                if f.is_dim() && !s.prefix.iter().all(|p| p.is_dim()) {
                    continue;
                }
                out.push(Entry {
                    kind,
                    state: s.name,
                    prefix: s.prefix.clone(),
                    motion: s.motion,
                    last: f,
                });
            }
        }
    }
    out
}

// ---------------------------------------------------------------- instances

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// A random rigid motion of the sketch (moderate or small), and a dimension change.
    Random,
    /// The new locus tangent to the motion the prefix leaves.
    Tangent,
    /// Nearly tangent.
    NearTangent,
    /// The sketch exactly at the target.
    Exact,
    /// The sketch 1e-9 (relative) from the target.
    Tiny,
    /// Everything scaled.
    Scale(f64),
    /// The prefix derived from a target moved by 1e-2: no solution (for checks only).
    Inconsistent,
}

impl Mode {
    fn name(self) -> String {
        match self {
            Mode::Random => "random".into(),
            Mode::Tangent => "tangent".into(),
            Mode::NearTangent => "near-tangent".into(),
            Mode::Exact => "exact".into(),
            Mode::Tiny => "tiny".into(),
            Mode::Scale(k) => format!("scale {k:e}"),
            Mode::Inconsistent => "inconsistent".into(),
        }
    }
}

struct Instance {
    text: String,
    prefix_text: String,
    scale: f64,
}

/// Writes numbers, tracking the largest length for the tolerance.
struct Out {
    scale: f64,
}

impl Out {
    fn l(&mut self, x: f64) -> String {
        self.scale = self.scale.max(x.abs());
        format!("{x:?}")
    }
    fn p(&mut self, p: V) -> String {
        format!("({}, {})", self.l(p[0]), self.l(p[1]))
    }
    fn a(&mut self, x: f64) -> String {
        format!("{x:?}")
    }
    fn d(&mut self, v: V) -> String {
        format!("({:?}, {:?})", v[0], v[1])
    }
}

/// Derives the fixed geom and the statement of form `f` (number `i`) from the target `t`.
/// `degen` is the tangent direction of the motion at the feature and the angle off it, for
/// near-degenerate instances. Returns the declarations, the constraint, and where it leaves
/// the feature.
#[allow(clippy::too_many_arguments)]
fn derive(
    f: Form,
    i: usize,
    t: &Conf,
    m: &Members,
    s: f64,
    rng: &mut Rng,
    degen: Option<(V, f64)>,
    o: &mut Out,
) -> (Vec<String>, String, Loc) {
    let mut decls = Vec::new();
    // A direction for a new locus: tangent to the motion when degenerate.
    let along = |rng: &mut Rng| match degen {
        Some((tv, eps)) => rot(tv, eps * rng.sign()),
        None => rng.unit(),
    };
    let line_decl = |o: &mut Out, name: String, base: V, e: V, len: f64| {
        format!(
            "fixed line {name} = {} -> {};",
            o.p(base),
            o.p(add(base, mul(e, len)))
        )
    };
    let (text, loc) = match f {
        Form::Coincident(p) | Form::Spherical(p) => {
            let x = pt(t, m, p);
            decls.push(format!("fixed point A{i} = {};", o.p(x)));
            let name = if matches!(f, Form::Coincident(_)) {
                "coincident"
            } else {
                "spherical"
            };
            (format!("{name}({}, A{i})", p.text()), Loc::Point(x))
        }
        Form::DistPP(p) => {
            let x = pt(t, m, p);
            let d = s * rng.range(0.3, 2.0);
            let u = perp(along(rng));
            let a = add(x, mul(u, d));
            decls.push(format!("fixed point A{i} = {};", o.p(a)));
            let dd = norm(sub(x, a));
            (
                format!("distance({}, A{i}) = {}", p.text(), o.l(dd)),
                Loc::Circle(a),
            )
        }
        Form::DistPL(p) | Form::OnPL(p) => {
            let x = pt(t, m, p);
            let e = along(rng);
            let h = if matches!(f, Form::DistPL(_)) {
                rng.sign() * s * rng.range(0.2, 1.5)
            } else {
                0.0
            };
            let base = add(sub(x, mul(perp(e), h)), mul(e, s * rng.range(-1.0, 1.0)));
            decls.push(line_decl(
                o,
                format!("L{i}"),
                base,
                e,
                s * rng.range(0.5, 2.0),
            ));
            let sd = cross(e, sub(x, base));
            let text = if matches!(f, Form::DistPL(_)) {
                format!("distance({}, L{i}) = {}", p.text(), o.l(sd))
            } else {
                format!("on({}, L{i})", p.text())
            };
            (text, Loc::Line(e))
        }
        Form::OnPC(p) | Form::DistPC(p) => {
            let x = pt(t, m, p);
            let rho = s * rng.range(0.3, 2.0);
            let u = perp(along(rng));
            let c = add(x, mul(u, rho));
            let (r, text) = if matches!(f, Form::OnPC(_)) {
                (rho, format!("on({}, C{i})", p.text()))
            } else if rng.sign() > 0.0 {
                let r = rho * rng.range(0.2, 0.8);
                (
                    r,
                    format!("distance({}, C{i}) = {}", p.text(), o.l(rho - r)),
                )
            } else {
                let r = rho * rng.range(1.2, 2.0);
                (
                    r,
                    format!("distance({}, C{i}) = {}", p.text(), o.l(r - rho)),
                )
            };
            decls.push(format!(
                "fixed circle C{i} = center {} radius {};",
                o.p(c),
                o.l(r)
            ));
            (text, Loc::Circle(c))
        }
        Form::InLine(p) => {
            let x = pt(t, m, p);
            let e = along(rng);
            let at = add(x, mul(e, s * rng.range(-1.0, 1.0)));
            decls.push(format!(
                "fixed body G{i} {{ marker r = {} x {}; }}",
                o.p(at),
                o.d(e)
            ));
            (format!("in_line({}, G{i}.r)", p.text()), Loc::Line(e))
        }
        Form::Revolute => {
            let x = pt(t, m, Pt::K);
            let u = rng.unit();
            decls.push(format!(
                "fixed body G{i} {{ marker m = {} x {}; }}",
                o.p(x),
                o.d(u)
            ));
            (format!("revolute(P.k, G{i}.m)"), Loc::Point(x))
        }
        Form::Prismatic => {
            let x = pt(t, m, Pt::K);
            let e = di(t, m, Di::Kx);
            let at = add(x, mul(e, s * rng.range(-1.0, 1.0)));
            decls.push(format!(
                "fixed body G{i} {{ marker r = {} x {}; }}",
                o.p(at),
                o.d(e)
            ));
            (format!("prismatic(P.k, G{i}.r)"), Loc::Line(e))
        }
        Form::Angle(d) | Form::Parallel(d) | Form::Perpendicular(d) => {
            let v = di(t, m, d);
            let (x, text) = match f {
                Form::Angle(_) => {
                    let x = rng.unit();
                    let a = angle_from(x, v);
                    (x, format!("angle(X{i}, {}) = {}", d.text(), o.a(a)))
                }
                Form::Parallel(_) => (mul(v, rng.sign()), format!("parallel(X{i}, {})", d.text())),
                _ => (
                    rot(v, rng.sign() * FRAC_PI_2),
                    format!("perpendicular(X{i}, {})", d.text()),
                ),
            };
            let k = rng.range(0.5, 2.0);
            decls.push(format!("fixed vector X{i} = {};", o.d(mul(x, k))));
            (text, Loc::None)
        }
        Form::Horizontal(d) => (format!("horizontal({})", d.text()), Loc::None),
        Form::Vertical(d) => (format!("vertical({})", d.text()), Loc::None),
        Form::OffsetX => {
            let v = di(t, m, Di::Kx);
            let u = rng.unit();
            let at = add(t.pos, rng.point(s));
            decls.push(format!(
                "fixed body G{i} {{ marker m = {} x {}; }}",
                o.p(at),
                o.d(u)
            ));
            (
                format!("offset_x(G{i}.m, P.k) = {}", o.a(angle_from(u, v))),
                Loc::None,
            )
        }
        Form::LineOn | Form::LineDist => {
            let e = dir(t.ang);
            let h = if f == Form::LineDist {
                rng.sign() * s * rng.range(0.2, 1.5)
            } else {
                0.0
            };
            let a = add(
                add(t.pos, mul(e, s * rng.range(-1.0, 2.0))),
                mul(perp(e), h),
            );
            decls.push(format!("fixed point A{i} = {};", o.p(a)));
            let text = if f == Form::LineDist {
                format!("distance(A{i}, P) = {}", o.l(cross(e, sub(a, t.pos))))
            } else {
                format!("on(A{i}, P)")
            };
            (text, Loc::Point(a))
        }
        Form::LineTangent | Form::LineCircleDist => {
            let e = dir(t.ang);
            let rho = s * rng.range(0.2, 1.5);
            let g = if f == Form::LineCircleDist {
                s * rng.range(0.1, 1.0)
            } else {
                0.0
            };
            let c = add(
                add(t.pos, mul(e, s * rng.range(-1.0, 2.0))),
                mul(perp(e), rng.sign() * (rho + g)),
            );
            decls.push(format!(
                "fixed circle C{i} = center {} radius {};",
                o.p(c),
                o.l(rho)
            ));
            let text = if f == Form::LineCircleDist {
                format!("distance(P, C{i}) = {}", o.l(g))
            } else {
                format!("tangent(P, C{i})")
            };
            (text, Loc::None)
        }
        Form::InLineRev => {
            let x = pt(t, m, Pt::K);
            let e = di(t, m, Di::Kx);
            let at = add(x, mul(e, s * rng.range(-1.5, 1.5)));
            decls.push(format!(
                "fixed body G{i} {{ marker m = {} x {}; }}",
                o.p(at),
                o.d(rng.unit())
            ));
            (format!("in_line(G{i}.m, P.k)"), Loc::Point(at))
        }
        Form::CircleOn | Form::CircleDist => {
            let (c, r) = (t.pos, t.dim);
            let u = rng.unit();
            let (rho, text) = if f == Form::CircleOn {
                (r, format!("on(A{i}, P)"))
            } else {
                let rho = if rng.sign() > 0.0 {
                    r + s * rng.range(0.1, 1.0)
                } else {
                    r * rng.range(0.0, 0.9)
                };
                (rho, format!("distance(A{i}, P) = {}", o.l((rho - r).abs())))
            };
            let a = add(c, mul(u, rho));
            decls.push(format!("fixed point A{i} = {};", o.p(a)));
            (text, Loc::Circle(a))
        }
        Form::CircleTangentLine | Form::CircleDistLine => {
            let (c, r) = (t.pos, t.dim);
            let e = rng.unit();
            let g = if f == Form::CircleDistLine {
                s * rng.range(0.1, 1.0)
            } else {
                0.0
            };
            let side = rng.sign();
            let base = add(
                sub(c, mul(perp(e), side * (r + g))),
                mul(e, s * rng.range(-1.0, 1.0)),
            );
            decls.push(line_decl(
                o,
                format!("L{i}"),
                base,
                e,
                s * rng.range(0.5, 2.0),
            ));
            let text = if f == Form::CircleDistLine {
                format!("distance(L{i}, P) = {}", o.l(g))
            } else {
                format!("tangent(L{i}, P)")
            };
            (text, Loc::Line(e))
        }
        Form::CircleTangentCircle | Form::CircleDistCircle => {
            let (c, r) = (t.pos, t.dim);
            let g = if f == Form::CircleDistCircle {
                s * rng.range(0.05, 0.5)
            } else {
                0.0
            };
            let u = rng.unit();
            // Apart, P inside the fixed circle, or the fixed circle inside P.
            let (rho, dist) = match rng.next() % 3 {
                0 => {
                    let rho = s * rng.range(0.2, 1.5);
                    (rho, r + rho + g)
                }
                1 => {
                    let rho = r + g + s * rng.range(0.2, 1.5);
                    (rho, rho - r - g)
                }
                _ => {
                    let rho = (r - g) * rng.range(0.1, 0.8);
                    (rho, (r - rho - g).max(0.0))
                }
            };
            let cc = add(c, mul(u, dist));
            decls.push(format!(
                "fixed circle C{i} = center {} radius {};",
                o.p(cc),
                o.l(rho)
            ));
            let text = if f == Form::CircleDistCircle {
                format!("distance(C{i}, P) = {}", o.l(g))
            } else {
                format!("tangent(C{i}, P)")
            };
            (text, Loc::Circle(cc))
        }
        Form::Length => (format!("length(P) = {}", o.l(t.dim)), Loc::None),
        Form::Radius => (format!("radius(P) = {}", o.l(t.dim)), Loc::None),
        Form::Midpoint(p) => {
            let x = pt(t, m, p);
            let e = rng.unit();
            let h = s * rng.range(0.3, 1.5);
            decls.push(format!(
                "fixed segment S{i} = {} -> {};",
                o.p(sub(x, mul(e, h))),
                o.p(add(x, mul(e, h)))
            ));
            (format!("midpoint({}, S{i})", p.text()), Loc::Point(x))
        }
        Form::Mirror(p) => {
            let x = pt(t, m, p);
            let e = rng.unit();
            let h = rng.sign() * s * rng.range(0.2, 1.5);
            let base = add(add(x, mul(perp(e), h)), mul(e, s * rng.range(-1.0, 1.0)));
            decls.push(line_decl(
                o,
                format!("L{i}"),
                base,
                e,
                s * rng.range(0.5, 2.0),
            ));
            // `x` is `h` to the right of the line: its image is `h` to the left.
            decls.push(format!(
                "fixed point A{i} = {};",
                o.p(add(x, mul(perp(e), 2.0 * h)))
            ));
            (
                format!("symmetric({}, A{i}, L{i})", p.text()),
                Loc::Point(x),
            )
        }
        Form::SegMidpoint => {
            let x = add(t.pos, mul(dir(t.ang), 0.5 * t.dim));
            decls.push(format!("fixed point A{i} = {};", o.p(x)));
            (format!("midpoint(A{i}, P)"), Loc::Point(x))
        }
        Form::EqualSegment => {
            let a = add(t.pos, rng.point(s));
            let e = rng.unit();
            decls.push(format!(
                "fixed segment T{i} = {} -> {};",
                o.p(a),
                o.p(add(a, mul(e, t.dim)))
            ));
            (format!("equal(P, T{i})"), Loc::None)
        }
        Form::EqualCircle => {
            decls.push(format!(
                "fixed circle K{i} = center {} radius {};",
                o.p(add(t.pos, rng.point(3.0 * s))),
                o.l(t.dim)
            ));
            (format!("equal(P, K{i})"), Loc::None)
        }
        Form::MirrorLine => {
            let e = dir(t.ang);
            let along = mul(e, s * rng.range(-1.0, 2.0));
            let h = rng.sign() * s * rng.range(0.2, 1.5);
            let a = add(add(t.pos, along), mul(perp(e), h));
            let b = sub(add(t.pos, along), mul(perp(e), h));
            decls.push(format!("fixed point A{i} = {};", o.p(a)));
            decls.push(format!("fixed point B{i} = {};", o.p(b)));
            (format!("symmetric(A{i}, B{i}, P)"), Loc::None)
        }
    };
    (decls, text, loc)
}

/// The declaration of `P` with configuration `c`.
fn probe_decl(kind: Kind, c: &Conf, m: &Members, s: f64, o: &mut Out) -> String {
    match kind {
        Kind::Point => format!("point P = {};", o.p(c.pos)),
        Kind::Vector => format!("vector P = {};", o.d(mul(dir(c.ang), 1.5))),
        Kind::Line => format!(
            "line P = {} -> {};",
            o.p(c.pos),
            o.p(add(c.pos, mul(dir(c.ang), s)))
        ),
        Kind::Segment => format!(
            "segment P = {} -> {};",
            o.p(c.pos),
            o.p(add(c.pos, mul(dir(c.ang), c.dim)))
        ),
        Kind::Circle => format!(
            "circle P = center {} radius {};",
            o.p(c.pos),
            o.l(c.dim)
        ),
        Kind::Body => format!(
            "body P at {} rotated ({}) {{ point a = {}; point b = {}; vector v = {}; marker k = {} x {}; }}",
            o.p(c.pos),
            o.a(c.ang),
            o.p(m.a),
            o.p(m.b),
            o.d(m.v),
            o.p(m.k),
            o.d(m.kx)
        ),
    }
}

fn make(e: &Entry, seed: u64, mode: Mode) -> Instance {
    let mut rng = Rng::new(seed);
    let k = match mode {
        Mode::Scale(k) => k,
        _ => 1.0,
    };
    let s = k * rng.range(0.5, 2.0);
    let members = Members {
        a: rng.point(s),
        b: rng.point(s),
        v: rng.unit(),
        k: rng.point(s),
        kx: rng.unit(),
    };
    let mut t = Conf {
        pos: rng.point(3.0 * s),
        ang: rng.angle(),
        dim: s * rng.range(0.5, 2.0),
    };
    // Horizontal and vertical constrain the target itself.
    for f in e.prefix.iter().chain([&e.last]) {
        if let Some((d, axis)) = f.world() {
            t.ang =
                axis + if rng.sign() > 0.0 { 0.0 } else { PI } - heading(local_dir(&members, d));
        }
    }
    let mut o = Out { scale: 0.0 };
    let mut decls = Vec::new();
    let mut lines = Vec::new();
    let mut locs = Vec::new();
    // An inconsistent instance: the prefix places P slightly elsewhere than z wants it.
    let tp = if mode == Mode::Inconsistent {
        Conf {
            pos: add(t.pos, mul(rng.unit(), 1e-2 * s)),
            ang: t.ang + 1e-2 * rng.sign(),
            dim: t.dim * 1.01,
        }
    } else {
        t
    };
    for (i, &f) in e.prefix.iter().enumerate() {
        let (d, c, loc) = derive(f, i, &tp, &members, s, &mut rng, None, &mut o);
        decls.extend(d);
        lines.push(format!("p{i}: {c};"));
        locs.push(loc);
    }
    // The motion the prefix leaves, at the last constraint's feature.
    let tangent = e.last.point().and_then(|p| {
        let x = pt(&t, &members, p);
        let tv = match e.motion {
            Motion::Free => None,
            Motion::Rotate(i) => match locs.get(i) {
                Some(Loc::Point(o)) if norm(sub(x, *o)) > 1e-6 * s => Some(perp(sub(x, *o))),
                _ => None,
            },
            Motion::Slide(i, g) => match locs.get(i) {
                Some(Loc::Line(e)) => Some(*e),
                Some(Loc::Circle(c)) => Some(perp(sub(pt(&t, &members, g), *c))),
                _ => None,
            },
        };
        tv.map(unit)
    });
    let degen = match (mode, tangent) {
        (Mode::Tangent, Some(tv)) => Some((tv, 0.0)),
        (Mode::NearTangent, Some(tv)) => Some((tv, rng.log_range(1e-9, 1e-4))),
        _ => None,
    };
    let n = e.prefix.len();
    let (d, c, _) = derive(e.last, n, &t, &members, s, &mut rng, degen, &mut o);
    decls.extend(d);
    let last = format!("z: {c};");
    // The sketch: the target moved.
    let mag = match mode {
        Mode::Exact => 0.0,
        Mode::Tiny => 1e-9,
        Mode::Inconsistent => 1e-3,
        _ => {
            if rng.sign() > 0.0 {
                rng.range(0.05, 1.0)
            } else {
                rng.log_range(1e-4, 1e-2)
            }
        }
    };
    let q = add(t.pos, rng.point(s));
    let turn = mag * rng.range(-0.6, 0.6);
    let shift = mul(rng.point(s), mag);
    let sk = Conf {
        pos: add(add(q, rot(sub(t.pos, q), turn)), shift),
        ang: t.ang + turn,
        dim: t.dim * (mag * rng.range(-0.5, 0.5)).exp(),
    };
    let probe = probe_decl(e.kind, &sk, &members, s, &mut o);
    // A fixed origin, so that no model is grounded at its probe's sketch.
    let head = format!(
        "space 2d;\nfixed point O = (0, 0);\n{}\n{probe}\n",
        decls.join("\n")
    );
    let prefix_text = format!("{head}{}\n", lines.join("\n"));
    let text = format!("{prefix_text}{last}\n");
    Instance {
        text,
        prefix_text,
        scale: o.scale,
    }
}

// ---------------------------------------------------------------- classification

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("probe.gcs", text.as_bytes());
    match model {
        Some(m)
            if !diags
                .iter()
                .any(|d| d.severity == gcs_lang::diagnostic::Severity::Error) =>
        {
            m
        }
        _ => panic!(
            "the checker wrote an invalid model: {:?}\n{text}",
            diags.iter().map(|d| d.message.clone()).collect::<Vec<_>>()
        ),
    }
}

fn label(model: &Model, l: &str) -> Option<ConstraintId> {
    model
        .constraints
        .iter()
        .find(|(_, c)| c.label.as_deref() == Some(l))
        .map(|(id, _)| id)
}

/// The record of `P`'s cluster: signature and DOF.
fn record_of(model: &Model, a: &Analysis) -> String {
    let p = model.geom_named("P").expect("P");
    match a.undefaulted.iter().find(|c| c.geoms.contains(&p)) {
        Some(c) => format!("{} ({} DOF)", c.signature(), c.dof),
        None => "?".into(),
    }
}

fn op_name(op: &Op) -> Option<String> {
    Some(match op {
        Op::Intersect { meet, .. } => format!("intersect {meet:?}"),
        Op::Onto { .. } => "onto".into(),
        Op::Nearest { .. } => "nearest".into(),
        Op::Translate { .. } => "translate".into(),
        Op::RotatePoint { .. } => "rotate to point".into(),
        Op::RotateDir { .. } => "rotate to direction".into(),
        Op::SetDim { .. } => "set dimension".into(),
        Op::Check { .. } => "check".into(),
        Op::CentresLineLine { .. } => "bisector locus".into(),
        Op::CentresLinePoint { .. } => "parabola locus".into(),
        Op::CentresPointPoint { .. } => "conic locus".into(),
        Op::RadiusFromLine { .. } | Op::RadiusFromPoint { .. } => "radius from distance".into(),
        Op::DirectionTo { .. } => "direction to".into(),
        Op::Along { .. } => "length along".into(),
        Op::ShiftedCircle { .. } => "shifted circle".into(),
        Op::ParallelLine { .. } => "parallel line".into(),
        Op::OffsetLine { .. } => "offset line".into(),
        Op::Default(_) => "default".into(),
        Op::LocusPoint { .. } => "point on locus".into(),
        Op::PointXY { .. } => "point".into(),
        Op::Close { .. } => "close by iteration".into(),
        Op::Midpoint { .. } => "midpoint".into(),
        Op::Reflect { .. } => "reflect through a point".into(),
        Op::Mirror { .. } => "mirror across a line".into(),
        _ => return None,
    })
}

#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Outcome {
    Fragment(String),
    Check,
    Recorded,
    NotYet(String),
    /// The prefix does not reach the state.
    Unreached(String),
}

impl Outcome {
    fn text(&self) -> String {
        match self {
            Outcome::Fragment(ops) => format!("fragment: {ops}"),
            Outcome::Check => "check".into(),
            Outcome::Recorded => "recorded (satisfied when placed)".into(),
            Outcome::NotYet(r) => format!("not yet: {r}"),
            Outcome::Unreached(r) => format!("state not reached: {r}"),
        }
    }
    fn checked(&self) -> bool {
        matches!(self, Outcome::Fragment(_) | Outcome::Check)
    }
}

struct Class {
    outcome: Outcome,
    before: String,
    after: String,
    note: String,
}

fn classify(e: &Entry, inst: &Instance) -> Class {
    let pm = load(&inst.prefix_text);
    let pa = analyse(&pm).expect("2d");
    let before = record_of(&pm, &pa);
    let model = load(&inst.text);
    let a = analyse(&model).expect("2d");
    let after = record_of(&model, &a);
    let z = label(&model, "z").expect("z");
    let mut note = String::new();
    if let Some(u) = pa.unsolved.first() {
        return Class {
            outcome: Outcome::Unreached(format!(
                "{}: {}",
                pm.constraints[u.constraint].text, u.reason
            )),
            before,
            after,
            note,
        };
    }
    if let Some(u) = a.unsolved.iter().find(|u| u.constraint == z) {
        return Class {
            outcome: Outcome::NotYet(u.reason.clone()),
            before,
            after,
            note,
        };
    }
    if let Some(u) = a.unsolved.first() {
        let _ = write!(
            note,
            "prefix constraint {} no longer solved",
            model.constraints[u.constraint].text
        );
    }
    let steps = &a.plan.steps;
    // The first default the analysis adds for the freedom left: a step satisfying z after it
    // is a fragment that needs the default (the defaults alone are probed below).
    let defaulted = (steps.iter())
        .position(|s| matches!(s.op, Op::Default(_)))
        .unwrap_or(steps.len());
    let Some(j) = steps.iter().position(|s| s.satisfies.contains(&z)) else {
        assert!(
            a.recorded.contains(&z),
            "z is neither satisfied nor recorded"
        );
        return Class {
            outcome: Outcome::Recorded,
            before,
            after,
            note,
        };
    };
    if matches!(steps[j].op, Op::Check { .. }) {
        return Class {
            outcome: Outcome::Check,
            before,
            after,
            note,
        };
    }
    // The fragment starts after the prefix's own steps: after the last step that satisfied
    // something, and after the steps the prefix alone emits (a circle's centre locus).
    let common = steps
        .iter()
        .zip(&pa.plan.steps)
        .take_while(|(x, y)| x == y)
        .count();
    let start = steps[..j]
        .iter()
        .rposition(|s| !s.satisfies.is_empty())
        .map_or(0, |i| i + 1)
        .max(common.min(j));
    let mut ops: Vec<String> = steps[start..=j]
        .iter()
        .filter_map(|s| op_name(&s.op))
        .collect();
    let prefix_ids: Vec<ConstraintId> = (0..e.prefix.len())
        .filter_map(|i| label(&model, &format!("p{i}")))
        .collect();
    let last_prefix = steps
        .iter()
        .rposition(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)));
    match last_prefix {
        Some(i) if i > j => {
            // Only the record closing right after z (a settle) belongs to it.
            let settle = steps[j + 1..]
                .iter()
                .take_while(|s| {
                    matches!(
                        s.op,
                        Op::SetDim { .. }
                            | Op::RadiusFromLine { .. }
                            | Op::RadiusFromPoint { .. }
                            | Op::PointOf(_)
                    )
                })
                .count();
            let after_ops: Vec<String> = steps[j + 1..j + 1 + settle]
                .iter()
                .filter(|s| !s.satisfies.is_empty() || s.out.is_some())
                .filter_map(|s| op_name(&s.op))
                .collect();
            let closes = steps[j + 1..j + 1 + settle]
                .iter()
                .any(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)));
            if closes && !after_ops.is_empty() {
                ops.push(format!("then {}", after_ops.join(" + ")));
            }
            if steps[j + 1 + settle..]
                .iter()
                .any(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)))
            {
                let _ = write!(note, "runs before part of the prefix");
            }
        }
        _ => {}
    }
    if j > defaulted {
        if !note.is_empty() {
            note.push_str("; ");
        }
        note.push_str("after a default");
    }
    Class {
        outcome: Outcome::Fragment(ops.join(" + ")),
        before,
        after,
        note,
    }
}

// ---------------------------------------------------------------- the checker

const N_RANDOM: usize = 20;
const DEGENERATE: [Mode; 8] = [
    Mode::Tangent,
    Mode::Tangent,
    Mode::NearTangent,
    Mode::NearTangent,
    Mode::Exact,
    Mode::Tiny,
    Mode::Scale(1e-3),
    Mode::Scale(1e3),
];
const REL: f64 = 1e-12;

#[derive(Default)]
struct Stats {
    instances: usize,
    runs: usize,
    /// Instances some branch solved, all verified.
    solved: usize,
    /// Instances the default branches solved.
    default_solved: usize,
    /// Instances no branch solved, by error kind.
    unsolved: BTreeMap<String, usize>,
    /// Instances whose analysis did not claim `z` (classified otherwise).
    reclassified: usize,
    /// Wrong runs: the largest relative residual, and the details.
    wrong: Vec<(f64, String)>,
    /// Inconsistent instances of a check (no solution): run, refused with an error, and the
    /// accepted ones (a solution violating the check's constraint).
    inconsistent: usize,
    inconsistent_refused: usize,
    inconsistent_accepted: Vec<String>,
    /// An example of an unsolved instance.
    unsolved_example: Option<String>,
}

fn angular(k: CK) -> bool {
    matches!(
        k,
        CK::Angle | CK::Parallel | CK::Perpendicular | CK::Horizontal | CK::Vertical | CK::OffsetX
    )
}

/// Every branch combination (at most 64; beyond, a deterministic sample).
fn combos(counts: &[usize], defaults: &[usize]) -> Vec<Vec<usize>> {
    let mut out = vec![defaults.to_vec()];
    let total: usize = counts.iter().map(|c| (*c).max(1)).product();
    let step = total.div_ceil(64).max(1);
    let mut n = 0;
    while n < total {
        let mut idx = Vec::with_capacity(counts.len());
        let mut r = n;
        for &c in counts {
            let c = c.max(1);
            idx.push(r % c);
            r /= c;
        }
        if idx != defaults {
            out.push(idx);
        }
        n += step;
    }
    out
}

/// The largest coordinate or dimension of a solution.
fn magnitude_of(s: &gcs_compiler::solution::Solution) -> f64 {
    (s.points.iter().flat_map(|(_, x)| x.iter()))
        .chain(s.scalars.iter().map(|(_, x)| x))
        .fold(0.0, |m: f64, x| m.max(x.abs()))
}

fn run_instance(entry_id: &str, seed: u64, mode: Mode, inst: &Instance, stats: &mut Stats) {
    stats.instances += 1;
    let model = load(&inst.text);
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let a = analyse(&model).expect("2d");
        let z = label(&model, "z").expect("z");
        let claimed: Vec<ConstraintId> = a
            .plan
            .steps
            .iter()
            .flat_map(|s| s.satisfies.iter().copied())
            .collect();
        let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
        let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
        let params = model.default_params();
        let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let tol_len = REL * inst.scale.max(f64::MIN_POSITIVE);
        let mut results = Vec::new();
        for combo in combos(&counts, &defaults) {
            // The plan as it is, even when it leaves geoms free (`solve` refuses those): the
            // fragments are what is checked.
            let r = gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo);
            let verdict = match r {
                Ok(sol) => {
                    // Relative to the inputs' scale, or to the answer's own magnitude when it
                    // lies farther out (a root far along a parabola's arm, met by a line
                    // nearly tangent to it): its coordinates carry rounding relative to that.
                    let tol_len = tol_len.max(REL * magnitude_of(&sol));
                    let res = gcs_compiler::verify::residuals(&model, &sol, &params);
                    let mut worst: f64 = 0.0;
                    let bad: Vec<String> = res
                        .iter()
                        .filter(|r| claimed.contains(&r.constraint))
                        .filter(|r| {
                            let kind = model.constraints[r.constraint].kind;
                            let tol = if angular(kind) {
                                REL
                            } else if kind == CK::Prismatic {
                                tol_len.max(REL)
                            } else {
                                tol_len
                            };
                            r.value.is_nan() || r.value > tol
                        })
                        .map(|r| {
                            worst = worst.max(r.value / inst.scale.max(1.0));
                            format!(
                                "{} residual {:.3e} (scale {:.3e}, relative {:.3e})",
                                model.constraints[r.constraint].text,
                                r.value,
                                inst.scale,
                                r.value / inst.scale
                            )
                        })
                        .collect();
                    if bad.is_empty() {
                        Ok(())
                    } else {
                        Err(Some(format!("{worst:e}|{}", bad.join("; "))))
                    }
                }
                Err(e) => Err(Some(format!("ERR {:?} {:.3e}", e.kind, e.magnitude))),
            };
            results.push((combo, verdict));
        }
        (claimed.contains(&z), results)
    }));
    let (claims_z, results) = match outcome {
        Ok(x) => x,
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            stats.wrong.push((
                f64::INFINITY,
                format!(
                    "{entry_id}: seed {seed} ({}): panic: {msg}\n```gcs\n{}```",
                    mode.name(),
                    inst.text
                ),
            ));
            return;
        }
    };
    if !claims_z {
        stats.reclassified += 1;
    }
    let mut any = false;
    let mut first_err = None;
    for (i, (combo, v)) in results.iter().enumerate() {
        stats.runs += 1;
        match v {
            Ok(()) => {
                any = true;
                if i == 0 {
                    stats.default_solved += 1;
                }
            }
            Err(Some(msg)) if !msg.starts_with("ERR ") => {
                let (worst, msg) = msg.split_once('|').unwrap_or(("inf", msg));
                stats.wrong.push((
                    worst.parse().unwrap_or(f64::INFINITY),
                    format!(
                        "{entry_id}: seed {seed} ({}), branches {combo:?}: {msg}\n```gcs\n{}```",
                        mode.name(),
                        inst.text
                    ),
                ));
            }
            Err(Some(msg)) => {
                if first_err.is_none() {
                    first_err = Some(msg.trim_start_matches("ERR ").to_string());
                }
            }
            Err(None) => {}
        }
    }
    if any {
        stats.solved += 1;
    } else {
        let e =
            first_err.unwrap_or_else(|| "Wrong (every run violated a claimed constraint)".into());
        let kind = e.split(' ').next().unwrap_or("").to_string();
        *stats.unsolved.entry(kind).or_default() += 1;
        if stats.unsolved_example.is_none() {
            stats.unsolved_example = Some(format!(
                "seed {seed} ({}): {e}\n```gcs\n{}```",
                mode.name(),
                inst.text
            ));
        }
    }
}

/// Inconsistent instances of a check entry: the plan must refuse them (a `SolveError`), never
/// return a solution that violates the checked constraint. Reported, not asserted: the checker's
/// bar is the solvable instances.
fn run_inconsistent(entry_id: &str, seed: u64, inst: &Instance, stats: &mut Stats) {
    let model = load(&inst.text);
    let Ok(a) = analyse(&model) else { return };
    let z = label(&model, "z").expect("z");
    if !a
        .plan
        .steps
        .iter()
        .any(|s| s.satisfies.contains(&z) && matches!(s.op, Op::Check { .. }))
    {
        return;
    }
    stats.inconsistent += 1;
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    for combo in combos(&counts, &defaults) {
        if let Ok(sol) = gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo) {
            let res = gcs_compiler::verify::residuals(&model, &sol, &params);
            let rz = res
                .iter()
                .find(|r| r.constraint == z)
                .map_or(0.0, |r| r.value);
            if rz.is_nan() || rz > 1e-9 * inst.scale.max(1.0) {
                stats.inconsistent_accepted.push(format!(
                    "{entry_id}: seed {seed}, branches {combo:?}: `{}` checked but violated by {rz:.3e}\n```gcs\n{}```",
                    model.constraints[z].text,
                    inst.text
                ));
                return;
            }
        }
    }
    stats.inconsistent_refused += 1;
}

const N_INCONSISTENT: usize = 4;

// ---------------------------------------------------------------- the test and the report

struct Row {
    id: String,
    kind: Kind,
    state: &'static str,
    form: String,
    class: Class,
    stats: Option<Stats>,
}

#[test]
fn construction_checker() {
    // Debugging aids: print one model's plan and solves instead of running the checker.
    if std::env::var("GCS_PROBE").is_ok() {
        probe();
        return;
    }
    if std::env::var("GCS_ENTRY").is_ok() {
        instance();
        return;
    }
    let t0 = std::time::Instant::now();
    let entries = entries();
    let mut rows = Vec::new();
    for (n, e) in entries.iter().enumerate() {
        let id = format!("#{n}");
        let canonical = make(e, (n as u64) << 32, Mode::Random);
        let class = classify(e, &canonical);
        let stats = class.outcome.checked().then(|| {
            let mut stats = Stats::default();
            let modes = std::iter::repeat_n(Mode::Random, N_RANDOM).chain(DEGENERATE);
            for (i, mode) in modes.enumerate() {
                let seed = ((n as u64) << 32) | (i as u64 + 1);
                let inst = make(e, seed, mode);
                run_instance(&id, seed, mode, &inst, &mut stats);
            }
            if class.outcome == Outcome::Check {
                for i in 0..N_INCONSISTENT {
                    let seed = ((n as u64) << 32) | (1000 + i as u64);
                    let inst = make(e, seed, Mode::Inconsistent);
                    run_inconsistent(&id, seed, &inst, &mut stats);
                }
            }
            stats
        });
        rows.push(Row {
            id,
            kind: e.kind,
            state: e.state,
            form: e.last.text(),
            class,
            stats,
        });
    }
    let defaults = default_rows();
    let elapsed = t0.elapsed().as_secs_f64();
    let report = report(&rows) + &defaults_report(&defaults);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/FRAGMENTS.md");
    let wrong: usize = rows
        .iter()
        .filter_map(|r| r.stats.as_ref())
        .map(|s| s.wrong.len())
        .sum();
    println!("{}- runtime {elapsed:.1} s", summary(&rows));
    if std::env::var("GCS_WRITE_FRAGMENTS").as_deref() == Ok("1") {
        std::fs::write(&path, &report).expect("write docs/FRAGMENTS.md");
    }
    for r in &rows {
        if let Some(s) = &r.stats {
            for (_, w) in &s.wrong {
                println!("WRONG {w}");
            }
        }
    }
    assert_eq!(wrong, 0, "wrong fragments: see the WRONG lines above");
    for r in &defaults {
        for w in &r.wrong {
            println!("WRONG DEFAULT {} {}: {w}", r.kind.name(), r.state);
        }
        assert!(
            r.refused || r.defaults.len() == r.dof,
            "{} {}: {} defaults for {} DOF",
            r.kind.name(),
            r.state,
            r.defaults.len(),
            r.dof
        );
    }
    let wrong_defaults: usize = defaults.iter().map(|r| r.wrong.len()).sum();
    assert_eq!(
        wrong_defaults, 0,
        "wrong default fragments: see the WRONG DEFAULT lines above"
    );
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == report,
        "docs/FRAGMENTS.md is out of date: regenerate it with GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-compiler --test construction"
    );
}

fn summary(rows: &[Row]) -> String {
    let mut o = String::new();
    let count = |f: &dyn Fn(&Outcome) -> bool| rows.iter().filter(|r| f(&r.class.outcome)).count();
    let stats: Vec<&Stats> = rows.iter().filter_map(|r| r.stats.as_ref()).collect();
    let verified = rows
        .iter()
        .filter(|r| {
            r.stats
                .as_ref()
                .is_some_and(|s| s.wrong.is_empty() && s.solved > 0)
        })
        .count();
    let keys: std::collections::BTreeSet<(Kind, String, String)> = rows
        .iter()
        .filter(|r| !matches!(r.class.outcome, Outcome::Unreached(_)))
        .map(|r| (r.kind, r.class.before.clone(), r.form.clone()))
        .collect();
    let _ = writeln!(o, "- entries: {}", rows.len());
    let _ = writeln!(
        o,
        "- distinct (geom kind, signature, constraint form) keys: {}",
        keys.len()
    );
    let _ = writeln!(
        o,
        "- fragment: {}",
        count(&|x| matches!(x, Outcome::Fragment(_)))
    );
    let _ = writeln!(o, "- check: {}", count(&|x| *x == Outcome::Check));
    let _ = writeln!(
        o,
        "- recorded (kept in the record, satisfied when the geom is placed): {}",
        count(&|x| *x == Outcome::Recorded)
    );
    let _ = writeln!(
        o,
        "- not yet: {}",
        count(&|x| matches!(x, Outcome::NotYet(_)))
    );
    let _ = writeln!(
        o,
        "- state not reached by its prefix: {}",
        count(&|x| matches!(x, Outcome::Unreached(_)))
    );
    let _ = writeln!(
        o,
        "- entries checked (fragment or check): {}; verified (no wrong run, at least one instance solved): {verified}",
        stats.len()
    );
    let inst: usize = stats.iter().map(|s| s.instances).sum();
    let runs: usize = stats.iter().map(|s| s.runs).sum();
    let solved: usize = stats.iter().map(|s| s.solved).sum();
    let dsolved: usize = stats.iter().map(|s| s.default_solved).sum();
    let recl: usize = stats.iter().map(|s| s.reclassified).sum();
    let wrong: usize = stats.iter().map(|s| s.wrong.len()).sum();
    let mut unsolved: BTreeMap<String, usize> = BTreeMap::new();
    for s in &stats {
        for (k, v) in &s.unsolved {
            *unsolved.entry(k.clone()).or_default() += v;
        }
    }
    let _ = writeln!(
        o,
        "- instances: {inst} ({N_RANDOM} random and {} near-degenerate per entry); solves (instance x branch combination): {runs}",
        DEGENERATE.len()
    );
    let _ = writeln!(
        o,
        "- instances solved and verified: {solved} (on the default branches: {dsolved}); not solved by any branch: {} {:?}",
        inst - solved,
        unsolved
    );
    let _ = writeln!(
        o,
        "- instances whose plan did not claim the probed constraint (classified otherwise on that sketch): {recl}"
    );
    let _ = writeln!(o, "- wrong runs (solved, but a claimed constraint violated beyond 1e-12 relative, or a panic): {wrong}");
    let precision: usize = stats
        .iter()
        .map(|s| s.wrong.iter().filter(|w| w.0 <= 1e-9).count())
        .sum();
    let _ = writeln!(
        o,
        "  - of which precision losses (relative residual between 1e-12 and 1e-9): {precision}; wrong results beyond 1e-9: {}",
        wrong - precision
    );
    let wrong_entries = stats.iter().filter(|s| !s.wrong.is_empty()).count();
    let _ = writeln!(o, "- entries with a wrong run: {wrong_entries}");
    let inc: usize = stats.iter().map(|s| s.inconsistent).sum();
    let refused: usize = stats.iter().map(|s| s.inconsistent_refused).sum();
    let accepted: usize = stats.iter().map(|s| s.inconsistent_accepted.len()).sum();
    let _ = writeln!(
        o,
        "- inconsistent instances of check entries (reported, not asserted): {inc}; refused with an error: {refused}; accepted with the checked constraint violated: {accepted}"
    );
    let _ = writeln!(
        o,
        "- every plan analysed here (entries and instances) passed the plan validator"
    );
    o
}

fn report(rows: &[Row]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "# Plan fragment table and construction checker\n");
    let _ = writeln!(
        o,
        "Generated by `compiler/tests/construction.rs` (`GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-compiler --test construction`); do not edit.\n\
         Each entry probes one free geom `P` of a kind, brought into a state by a prefix of constraints with fixed geoms, \
         and one more constraint between a feature of `P` and a fixed geom. The outcome is what the analysis does for \
         that constraint; *before* and *after* are the signature (Kramer's `IR[...]`) and DOF of `P`'s cluster. \
         For every fragment and check, random solvable instances (and near-degenerate ones) are solved on every branch \
         and verified independently (`verify`); see the test's header for the method.\n"
    );
    let _ = writeln!(o, "## Totals\n");
    o.push_str(&summary(rows));
    let _ = writeln!(o, "\n## Table\n");
    let mut kind = None;
    for r in rows {
        if kind != Some(r.kind) {
            kind = Some(r.kind);
            let _ = writeln!(o, "\n### {}\n", r.kind.name());
            let _ = writeln!(
                o,
                "| id | state | before | constraint | outcome | after | instances: solved / run |"
            );
            let _ = writeln!(o, "| --- | --- | --- | --- | --- | --- | --- |");
        }
        let inst = match &r.stats {
            Some(s) => {
                let mut t = format!("{} / {}", s.solved, s.instances);
                if !s.wrong.is_empty() {
                    let _ = write!(t, ", **{} wrong**", s.wrong.len());
                }
                t
            }
            None => String::new(),
        };
        let mut outcome = r.class.outcome.text();
        if !r.class.note.is_empty() {
            let _ = write!(outcome, " ({})", r.class.note);
        }
        let _ = writeln!(
            o,
            "| {} | {} | {} | `{}` | {} | {} | {} |",
            r.id,
            r.state,
            r.class.before,
            r.form,
            outcome.replace('|', "\\|"),
            r.class.after,
            inst
        );
    }
    let _ = writeln!(o, "\n## Not yet, by reason\n");
    let mut by: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for r in rows {
        if let Outcome::NotYet(reason) | Outcome::Unreached(reason) = &r.class.outcome {
            let key = match &r.class.outcome {
                Outcome::Unreached(_) => format!("state not reached: {reason}"),
                _ => reason.clone(),
            };
            by.entry(key).or_default().push(format!(
                "{} {} ({}): `{}`",
                r.id,
                r.kind.name(),
                r.state,
                r.form
            ));
        }
    }
    for (reason, list) in &by {
        let _ = writeln!(o, "- **{reason}** ({}):", list.len());
        for l in list {
            let _ = writeln!(o, "  - {l}");
        }
    }
    let _ = writeln!(o, "\n## Instances no branch solved\n");
    let _ = writeln!(
        o,
        "A `SolveError` is never a wrong answer; these are instances built from a solvable target that the plan \
         (on every branch) refused, usually because the sketch's reading of a side, sense or nesting differs from \
         the target's, or a locus meets at a tangency. One example per entry.\n"
    );
    for r in rows {
        if let Some(s) = &r.stats {
            let n: usize = s.unsolved.values().sum();
            if n > 0 {
                let _ = writeln!(
                    o,
                    "- {} {} ({}), `{}`: {n} of {} {:?}",
                    r.id,
                    r.kind.name(),
                    r.state,
                    r.form,
                    s.instances,
                    s.unsolved
                );
            }
        }
    }
    let _ = writeln!(o, "\n## Checks that accept inconsistent instances\n");
    let _ = writeln!(
        o,
        "An inconsistent instance of a check entry has no solution; the check must refuse it. One example per entry.\n"
    );
    let mut none = true;
    for r in rows {
        if let Some(s) = &r.stats {
            if let Some(w) = s.inconsistent_accepted.first() {
                // The model text of the first few only.
                let w = if none {
                    w.clone()
                } else {
                    w.split("\n```").next().unwrap_or("").to_string()
                };
                let w = &w;
                none = false;
                let _ = writeln!(
                    o,
                    "- {} {} ({}), `{}`: {} of {} accepted. {w}",
                    r.id,
                    r.kind.name(),
                    r.state,
                    r.form,
                    s.inconsistent_accepted.len(),
                    s.inconsistent
                );
            }
        }
    }
    if none {
        let _ = writeln!(o, "None.");
    }
    let _ = writeln!(o, "\n## Failures\n");
    let mut any = false;
    for r in rows {
        if let Some(s) = &r.stats {
            for (rel, w) in &s.wrong {
                any = true;
                let class = if *rel <= 1e-9 {
                    "precision (relative residual at most 1e-9)"
                } else {
                    "wrong result"
                };
                let _ = writeln!(o, "- {class}: {w}");
            }
        }
    }
    if !any {
        let _ = writeln!(o, "None: every solved instance verifies.");
    }
    o
}

/// Debugging aid: `GCS_PROBE=model.gcs cargo test -p gcs-compiler --test construction --
/// --nocapture` prints the plan of one model and its solve on every branch.
fn probe() {
    let path = std::env::var("GCS_PROBE").expect("GCS_PROBE=model.gcs");
    let text = std::fs::read_to_string(path).expect("read");
    let model = load(&text);
    let a = analyse(&model).expect("2d");
    println!("{}", a.plan.dump(&model));
    println!("unsolved: {:?}", a.unsolved);
    println!("record of P: {}", record_of(&model, &a));
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    for combo in combos(&counts, &defaults) {
        let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        match gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo) {
            Ok(s) => {
                println!("{combo:?}: max residual {:.3e}", s.max_residual);
                for r in gcs_compiler::verify::residuals(&model, &s, &params) {
                    println!("  {} {:.3e}", model.constraints[r.constraint].text, r.value);
                }
            }
            Err(e) => println!("{combo:?}: {e:?}"),
        }
    }
}

/// Debugging aid: `GCS_ENTRY=n GCS_INSTANCE=i cargo test -p gcs-compiler --test construction
/// -- --nocapture` prints instance `i` of entry `n` (0: the canonical one)
/// and its plan.
fn instance() {
    let n: usize = std::env::var("GCS_ENTRY")
        .expect("GCS_ENTRY")
        .parse()
        .expect("n");
    let i: usize = std::env::var("GCS_INSTANCE")
        .map_or(Ok(0), |s| s.parse())
        .expect("i");
    let e = &entries()[n];
    let mode = match i {
        0 => Mode::Random,
        i if i <= N_RANDOM => Mode::Random,
        i => DEGENERATE[i - 1 - N_RANDOM],
    };
    let inst = make(e, ((n as u64) << 32) | i as u64, mode);
    println!("{}", inst.text);
    let model = load(&inst.text);
    let a = analyse(&model).expect("2d");
    println!("{}", a.plan.dump(&model));
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    for combo in combos(&counts, &defaults) {
        match gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo) {
            Ok(s) => println!("{combo:?}: max residual {:.3e}", s.max_residual),
            Err(e) => println!("{combo:?}: {e:?}"),
        }
    }
}

// ---------------------------------------------------------------- default fragments

/// What the analysis does with the freedom a state leaves (000, section 5.2.1): the defaults it
/// adds for `P`, probed on the prefix alone.
struct DefaultRow {
    kind: Kind,
    state: &'static str,
    /// `P`'s record before any default, with its DOF.
    before: String,
    dof: usize,
    /// The defaults' names, in plan order.
    defaults: Vec<String>,
    /// Whether the analysis refused to default the freedom (it stays free and is reported).
    refused: bool,
    /// Exact instances (the sketch satisfies the prefix) solved at the sketch's defaults with
    /// nothing moved, of those run.
    still: (usize, usize),
    /// Random instances solved at the sketch's defaults, and with each default moved, with
    /// every constraint verified and the moved default moving `P`, of those run.
    moved: (usize, usize),
    /// Wrong runs.
    wrong: Vec<String>,
}

/// Every point, vector and scalar of `P` in a solution, by name.
fn values_of_p(s: &gcs_compiler::solution::Solution) -> Vec<(String, Vec<f64>)> {
    let of_p = |n: &str| n == "P" || n.starts_with("P.");
    (s.points.iter().chain(&s.vectors))
        .filter(|(n, _)| of_p(n))
        .cloned()
        .chain(
            (s.scalars.iter())
                .filter(|(n, _)| of_p(n))
                .map(|(n, x)| (n.clone(), vec![*x])),
        )
        .collect()
}

/// The largest difference between same-named values.
fn largest_difference(a: &[(String, Vec<f64>)], b: &[(String, Vec<f64>)]) -> f64 {
    let mut d: f64 = 0.0;
    for (n, u) in a {
        if let Some((_, v)) = b.iter().find(|(m, _)| m == n) {
            for (x, y) in u.iter().zip(v) {
                d = d.max((x - y).abs());
            }
        }
    }
    d
}

/// The largest residual of every constraint of `model` in `s`, relative to `scale` for
/// lengths (angles absolute).
fn worst_residual(model: &Model, s: &gcs_compiler::solution::Solution, scale: f64) -> f64 {
    let params = model.default_params();
    (gcs_compiler::verify::residuals(model, s, &params).iter())
        .map(|r| {
            if angular(model.constraints[r.constraint].kind) {
                r.value
            } else {
                r.value / scale.max(1.0)
            }
        })
        .fold(0.0, f64::max)
}

/// The checker of the defaults of one state: the sketch's defaults move nothing the
/// constraints do not move, every default keeps the state's constraints, and each moves `P`.
fn default_row(kind: Kind, state: &State, last: Form, n: usize) -> DefaultRow {
    let entry = Entry {
        kind,
        state: state.name,
        prefix: state.prefix.clone(),
        motion: state.motion,
        last,
    };
    let canonical = make(&entry, (n as u64) << 40, Mode::Random);
    let model = load(&canonical.prefix_text);
    let a = analyse(&model).expect("2d");
    let p = model.geom_named("P").expect("P");
    let dof = (a.undefaulted.iter())
        .find(|c| c.geoms.contains(&p))
        .map_or(0, |c| c.dof);
    let mut row = DefaultRow {
        kind,
        state: state.name,
        before: record_of(&model, &a),
        dof,
        defaults: a.plan.defaults.iter().map(|d| d.name.clone()).collect(),
        refused: !a.free_geoms().is_empty(),
        still: (0, 0),
        moved: (0, 0),
        wrong: Vec::new(),
    };
    if row.refused || row.defaults.is_empty() {
        return row;
    }
    for i in 0..N_DEFAULT_INSTANCES {
        for mode in [Mode::Exact, Mode::Random] {
            let seed = ((n as u64) << 40) | (i as u64 + 1);
            let inst = make(&entry, seed, mode);
            let model = load(&inst.prefix_text);
            let a = analyse(&model).expect("2d");
            let params = model.default_params();
            let scope: std::collections::BTreeSet<_> =
                model.top_level().map(|(id, _)| id).collect();
            let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
            let sketch_defaults = a.plan.sketch_defaults();
            let solve = |defaults: &[f64]| {
                gcs_compiler::solve_plan_with(&model, &a.plan, &scope, &params, &branches, defaults)
            };
            let scale = inst.scale.max(1.0);
            let at_sketch = match solve(&sketch_defaults) {
                Ok(s) => s,
                Err(_) if mode == Mode::Random => continue,
                Err(e) => {
                    row.wrong
                        .push(format!("seed {seed} ({}): {e}", mode.name()));
                    continue;
                }
            };
            let worst = worst_residual(&model, &at_sketch, scale);
            if worst > REL {
                row.wrong.push(format!(
                    "seed {seed} ({}): a constraint off by {worst:e} at the sketch's defaults",
                    mode.name()
                ));
                continue;
            }
            if mode == Mode::Exact {
                row.still.1 += 1;
                let config = gcs_compiler::config::Config::from_sketch(&model, &params)
                    .expect("a finite sketch");
                let sketch = gcs_compiler::solution::Solution::read(&model, &config, &scope);
                let moved = largest_difference(&values_of_p(&at_sketch), &values_of_p(&sketch));
                if moved <= REL * scale {
                    row.still.0 += 1;
                } else {
                    row.wrong.push(format!(
                        "seed {seed} (exact): P moved {moved:e} at the sketch's defaults\n```gcs\n{}```",
                        inst.prefix_text
                    ));
                }
                continue;
            }
            row.moved.1 += 1;
            let mut ok = true;
            for (k, d) in a.plan.defaults.iter().enumerate() {
                let mut given = sketch_defaults.clone();
                given[k] += if d.is_angle() { 0.25 } else { 0.25 * scale };
                let Ok(s) = solve(&given) else {
                    // A default past where the state lets P go (a length below zero) is an
                    // error, never a wrong answer.
                    continue;
                };
                let worst = worst_residual(&model, &s, scale);
                let moved = largest_difference(&values_of_p(&s), &values_of_p(&at_sketch));
                if worst > REL || moved <= 1e-6 * scale {
                    ok = false;
                    row.wrong.push(format!(
                        "seed {seed}: default {} moved: constraints off by {worst:e}, P moved {moved:e}\n```gcs\n{}```",
                        d.name, inst.prefix_text
                    ));
                }
            }
            row.moved.0 += usize::from(ok);
        }
    }
    row
}

/// Instances of each mode per state.
const N_DEFAULT_INSTANCES: usize = 6;

/// The default fragments of every state of every kind.
fn default_rows() -> Vec<DefaultRow> {
    let mut rows = Vec::new();
    for kind in [
        Kind::Point,
        Kind::Vector,
        Kind::Line,
        Kind::Segment,
        Kind::Circle,
        Kind::Body,
    ] {
        let (states, forms) = catalogue(kind);
        for s in &states {
            let n = rows.len() + 1;
            rows.push(default_row(kind, s, forms[0], n));
        }
    }
    rows
}

/// The section of `docs/FRAGMENTS.md` on defaults.
fn defaults_report(rows: &[DefaultRow]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "\n## Defaults\n");
    let _ = writeln!(
        o,
        "Each state's prefix alone, with the freedom it leaves `P`: the defaults the analysis adds \
         (000, section 5.2.1; `compiler/src/analysis/planar/defaults.rs`). Checked on instances \
         whose sketch already satisfies the prefix (*still*: solved at the sketch's defaults, \
         `P` must not move: least motion) and on random ones (*moved*: at the sketch's defaults \
         and with each default moved by 0.25 rad or 0.25 of the size, every constraint must hold \
         to 1e-12 relative and the moved default must move `P`). *Refused*: the analysis leaves \
         the freedom unparameterized (a segment held by its end with its length free), and \
         `gcs check` reports it.\n"
    );
    let total = rows.len();
    let with = rows.iter().filter(|r| !r.defaults.is_empty()).count();
    let refused = rows.iter().filter(|r| r.refused).count();
    let overstated = (rows.iter())
        .filter(|r| !r.refused && r.defaults.len() != r.dof)
        .count();
    let wrong: usize = rows.iter().map(|r| r.wrong.len()).sum();
    let _ = writeln!(o, "- states: {total}; with defaults: {with}; fully fixed by their prefix: {}; refused: {refused}", total - with - refused);
    let _ = writeln!(
        o,
        "- states whose defaults are not as many as `P`'s DOF left: {overstated}"
    );
    let _ = writeln!(o, "- wrong runs: {wrong}\n");
    let _ = writeln!(o, "| kind | state | before | defaults | still | moved |");
    let _ = writeln!(o, "|---|---|---|---|---:|---:|");
    for r in rows {
        let defaults = if r.refused {
            "refused".to_string()
        } else if r.defaults.is_empty() {
            "none".to_string()
        } else {
            r.defaults
                .iter()
                .map(|d| format!("`{d}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let _ = writeln!(
            o,
            "| {} | {} | {} | {defaults} | {} / {} | {} / {} |",
            r.kind.name(),
            r.state,
            r.before,
            r.still.0,
            r.still.1,
            r.moved.0,
            r.moved.1
        );
    }
    o
}
