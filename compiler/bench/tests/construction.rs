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
//! # Degenerate refusals
//!
//! An instance no branch solves whose first error is `Degenerate` is given to the numeric
//! baseline (`gcs_bench::baseline`), which shares nothing with the plan: Newton, then
//! Levenberg-Marquardt, from the instance's sketch, the answer verified as a plan's (every
//! constraint to 1e-12 relative). If it finds an assembly within half the instance's scale of
//! the sketch, the harness measures the dimension of the assemblies around it (the baseline put
//! off it along random directions lands off it in proportion to the push only along a
//! continuum); an assembly *isolated* but for the plan's free defaults is a valid sketch the plan
//! refused, and fails the test unless the space's `KNOWN_DEGENERATE` lists its cause. A
//! continuum wider than the plan's defaults (a point on two coincident lines, a line in a
//! plane) has no isolated solution: the refusal stands, and is counted. That is why the
//! checkers live in gcs-bench: gcs-compiler cannot depend on the baseline.
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
//!
//! The probing, the checker, the defaults' checker and the table writer are shared with the
//! checker in space (`construction3d.rs`): `construction/harness.rs`. This file has the plane's
//! kinds, states, constraint forms and instances, and what its plans and tables say ([`Planar`]).

#[path = "construction/harness.rs"]
mod harness;

use gcs_bench::baseline::Baseline;

use gcs_compiler::plan::{DefaultVar, Op, PlanarOp};
use gcs_lang::constraints::ConstraintKind as CK;
use harness::{
    angular, ConstraintForm, GeomKind, Instance, Mode, Out, Rng, Solved, Space, Statements, Table,
    REL,
};
use std::f64::consts::{FRAC_PI_2, PI};

#[test]
fn construction_checker() {
    harness::check::<Planar>();
}

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

// ---------------------------------------------------------------- random draws in the plane

impl Rng {
    fn unit(&mut self) -> V {
        dir(self.angle())
    }
    fn point(&mut self, s: f64) -> V {
        [self.range(-s, s), self.range(-s, s)]
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

impl GeomKind for Kind {
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

impl ConstraintForm for Form {
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
}

impl Form {
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

type State = harness::State<Planar>;
type Entry = harness::Entry<Planar>;

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

// ---------------------------------------------------------------- instances

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
    let s = harness::size(&mut rng, mode);
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
    let mut stmts = Statements::default();
    let mut locs = Vec::new();
    let tp = harness::prefix_target(mode, t, |t| Conf {
        pos: add(t.pos, mul(rng.unit(), 1e-2 * s)),
        ang: t.ang + 1e-2 * rng.sign(),
        dim: t.dim * 1.01,
    });
    for (i, &f) in e.prefix.iter().enumerate() {
        let (d, c, loc) = derive(f, i, &tp, &members, s, &mut rng, None, &mut o);
        stmts.decls.extend(d);
        stmts.prefix.push(format!("p{i}: {c};"));
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
    let degen = harness::off_tangent(mode, tangent, &mut rng);
    let n = e.prefix.len();
    let (d, c, _) = derive(e.last, n, &t, &members, s, &mut rng, degen, &mut o);
    stmts.decls.extend(d);
    stmts.last.push(format!("z: {c};"));
    // The sketch: the target moved.
    let mag = harness::sketch_motion(mode, &mut rng);
    let q = add(t.pos, rng.point(s));
    let turn = mag * rng.range(-0.6, 0.6);
    let shift = mul(rng.point(s), mag);
    let sk = Conf {
        pos: add(add(q, rot(sub(t.pos, q), turn)), shift),
        ang: t.ang + turn,
        dim: t.dim * (mag * rng.range(-0.5, 0.5)).exp(),
    };
    let probe = probe_decl(e.kind, &sk, &members, s, &mut o);
    stmts.instance("space 2d;\nfixed point O = (0, 0);", &probe, o.scale)
}

// ---------------------------------------------------------------- the plane's checker

/// The construction checker in the plane.
struct Planar;

impl Space for Planar {
    type Kind = Kind;
    type Form = Form;
    type Baseline = Baseline;
    type StateMotion = Motion;

    const KINDS: &'static [Kind] = &[
        Kind::Point,
        Kind::Vector,
        Kind::Line,
        Kind::Segment,
        Kind::Circle,
        Kind::Body,
    ];
    const N_RANDOM: usize = 20;
    const TABLE: Table = Table {
        test: "construction",
        command: "GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-bench --test construction",
        file: "FRAGMENTS.md",
        title: "Plan fragment table and construction checker",
        members: "",
        degenerate: "",
        last: "",
        unsolved: ", usually because the sketch's reading of a side, sense or nesting differs \
                   from the target's, or a locus meets at a tangency. One example per entry.",
        defaults_source: "compiler/src/analysis/planar/defaults.rs",
        refused_example: " (a segment held by its end with its length free)",
        validated: true,
        detailed: false,
    };

    fn catalogue(kind: Kind) -> (Vec<State>, Vec<Form>) {
        catalogue(kind)
    }
    fn probed(prefix: &[Form], last: Form) -> bool {
        // Dimensions are solved first: probe them only after dimensions.
        !last.is_dim() || prefix.iter().all(|p| p.is_dim())
    }
    fn make(e: &Entry, seed: u64, mode: Mode) -> Instance {
        make(e, seed, mode)
    }

    fn op_name(op: &Op) -> Option<String> {
        Some(match op {
            Op::RotatePoint { .. } => "rotate to point".into(),
            Op::RotateDir { .. } => "rotate to direction".into(),
            Op::Planar(PlanarOp::CentresLineLine { .. }) => "bisector locus".into(),
            Op::Planar(PlanarOp::CentresLinePoint { .. }) => "parabola locus".into(),
            Op::Planar(PlanarOp::CentresPointPoint { .. }) => "conic locus".into(),
            Op::Planar(PlanarOp::RadiusFromLine { .. })
            | Op::Planar(PlanarOp::RadiusFromPoint { .. }) => "radius from distance".into(),
            Op::Along { .. } => "length along".into(),
            Op::Planar(PlanarOp::OffsetLine { .. }) => "offset line".into(),
            Op::Planar(PlanarOp::PointXY { .. }) => "point".into(),
            Op::Midpoint { .. } => "midpoint".into(),
            Op::Reflect { .. } => "reflect through a point".into(),
            Op::Planar(PlanarOp::Mirror { .. }) => "mirror across a line".into(),
            _ => return harness::op_name(op),
        })
    }

    /// A circle's radius set when its centre is placed, or a point read off its geom.
    fn settles(op: &Op) -> bool {
        matches!(
            op,
            Op::SetDim { .. }
                | Op::Planar(PlanarOp::RadiusFromLine { .. })
                | Op::Planar(PlanarOp::RadiusFromPoint { .. })
                | Op::PointOf(_)
        )
    }

    /// Measured by `verify` on the model itself, each claimed constraint to its tolerance (a
    /// prismatic joint's to at least `REL`), relative to the instance's largest length.
    fn violations(v: &Solved<'_>) -> Vec<(f64, String)> {
        let tol_len = v.tol_len();
        let params = v.model.default_params();
        let res = gcs_compiler::verify::residuals(v.model, v.sol, &params);
        res.iter()
            .filter(|r| v.claimed.contains(&r.constraint))
            .filter(|r| {
                let kind = v.model.constraints[r.constraint].kind;
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
                let words = format!(
                    "{} residual {:.3e} (scale {:.3e}, relative {:.3e})",
                    v.model.constraints[r.constraint].text,
                    r.value,
                    v.scale,
                    r.value / v.scale
                );
                (r.value / v.scale.max(1.0), words)
            })
            .collect()
    }

    fn angle_default(d: &DefaultVar) -> bool {
        d.is_angle()
    }

    fn baseline(model: &gcs_lang::Model) -> Result<Baseline, String> {
        Baseline::new(model)
    }
}
