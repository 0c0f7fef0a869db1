//! The construction checker in space (paper 000, section 4.3; issue 20) and the generated
//! fragment table of 3d models (`docs/FRAGMENTS3D.md`): `tests/construction.rs`'s method,
//! adapted to the records and fragments of `analysis/spatial`.
//!
//! # How the table is enumerated
//!
//! For every 3d geom kind the probe declares one free geom `P` and a list of *states*: a
//! prefix of constraints between `P` and fixed geoms that brings `P` into a given record
//! (TLA's `Trans` and `Turn`). A body `P` carries three markers `m`, `n`, `k` and member
//! points `a`, `b` and `c` (`c` on `m`'s z axis) at random local places; the prefix
//! constrains `m` (and `k`, `b` where it needs more than one feature), the last constraint
//! `n`, `a`, `c` or `m` itself. Body states: free; a pivot (`m` coincident with a fixed
//! point); a pivot and parallel z axes, and a revolute joint (a turn about one axis); `m` on
//! a fixed line (in_line); on a fixed plane (in_plane, or `on` a fixed plane); in_line and
//! parallel z, and a cylindrical joint; in_plane and parallel z, and a planar joint; parallel
//! z alone (a turn about an axis, free to translate); the orientation known (parallel z and
//! offset_x), alone, with a point on a line, with a point on a plane; a prismatic joint; a
//! screw (cylindrical and helical); a point at a distance from a fixed point (on a sphere);
//! fully fixed, by a pivot and an orientation and by three points (Kramer's brick). A point
//! `P`: free; on a plane; on a line (given, or two planes); on a sphere; on a circle (two
//! spheres, a sphere and a plane); fixed. A vector `P`: free; on a cone (an angle to a fixed
//! vector); known. A line `P`: free; through a point; its direction known; on a cone;
//! placed. A segment `P`: free; its start held; its end held. A circle `P`: free; its centre
//! held; square to a direction; placed (centre, normal and radius). Planes that move are
//! probed free, to list what the analysis says of them.
//!
//! Then, for every state, every constraint form of the language in 3d that applies to a
//! feature of `P` (coincident, spherical, distance point-point and signed point-plane, `on` a
//! line or plane, in_line, in_plane, parallel_z, offset_x, revolute, prismatic, cylindrical,
//! planar, helical, parallel; and the forms the analysis does not cover yet: distance
//! point-line and point-circle, `on` a circle, midpoint, symmetric, angle, perpendicular,
//! offset_z, and for the other kinds `on`, distance, tangent, length, radius, equal) is added
//! as the last constraint `z` between that feature and new fixed geoms. Constraints are
//! labelled `p0`, `p1`, ... and `z`, so that the analysis, which takes constraints in name
//! order, meets the prefix first.
//!
//! Each entry is analysed on a canonical instance and classified by what the analysis did for
//! `z`, as in the plane: *fragment* (the op kinds of its steps, from the step after the
//! previous one that satisfied a constraint through the one that satisfies `z`), *check* (a
//! run-time check: `z` is implied), or *not yet* (in `Analysis::unsolved`, with the reason the
//! analysis gives). *Before* and *after* are the signature (Kramer's `IR[...]`) and DOF of
//! `P`'s cluster.
//!
//! # The checker
//!
//! For every fragment and check entry, random instances that have a solution are built: a
//! random target configuration of `P` is drawn (position, rotation, dimension), every fixed
//! geom and value is derived from it (a fixed point at the target position of a feature, a
//! plane through it, a fixed marker whose z axis is the feature's target z axis, in either
//! sense, an offset angle or a helix pitch measured in the target, ...), and `P`'s sketch is
//! the target moved by a random rigid motion (turns below 0.6 rad, so the sketch keeps the
//! target's sense of every pair of parallel axes). Near-degenerate instances add:
//! - *tangent* and *near-tangent* (by 1e-9 to 1e-4 rad): the new locus (a line, plane or
//!   sphere) tangent to the motion the prefix leaves the feature. That motion is computed
//!   from the prefix at the target, as the velocities of the feature under the twists the
//!   prefix allows: a curve (a circle about an axis, a line, a helix) or a surface (a sphere
//!   about a pivot, a plane, a cylinder); the new line then runs along the curve or in the
//!   surface's tangent plane, the new plane contains the curve's tangent or is the tangent
//!   plane, the new sphere touches the curve or the surface (inside or out): a sphere barely
//!   touching a line, a plane or a circle;
//! - *nearly parallel axes*: `n`'s z axis at 1e-9 to 1e-4 rad from `m`'s, the axis the
//!   prefix holds, so that a turn about it barely moves `n`'s axis;
//! - *coincident markers*: `n` and `a` at `m`'s point (half the time `n` is `m`'s frame);
//! - the sketch exactly at the target, or 1e-9 (relative) from it; scales 1e-3 and 1e3.
//!
//! Each instance is solved on the default branches and on every other branch combination
//! (at most 64). A run that returns a solution must satisfy every constraint its plan claims
//! (every step's `satisfies`), measured by `verify` to 1e-12 relative to the instance's scale
//! (its largest coordinate or length), or to the answer's own magnitude when larger, and to
//! 1e-12 rad for angles. A joint's residual is the larger of a length and an angle, so each
//! joint is measured by `verify` once more on a twin model where it is written as the
//! constraints LANGUAGE.md makes it of (revolute as coincident and parallel_z, prismatic as
//! in_line and offset_x 0, cylindrical as in_line and parallel_z, planar as in_plane and
//! parallel_z), each part to its own tolerance. Anything else is a *wrong* run. A
//! `SolveError` is never wrong, but an instance no branch solves is reported *not solved*.
//! Inconsistent instances of check entries (the prefix derived from a target moved by 1e-2)
//! must be refused; they are reported, not asserted.
//!
//! Every plan comes from the pipeline's `analyse`, which validates it; a malformed plan or a
//! panic is a wrong run.
//!
//! # Default fragments
//!
//! Each state's prefix alone, with the defaults the analysis adds for the freedom it leaves
//! `P` (000, section 5.2.1): as many as `P`'s DOF (or the freedom refused and reported); at
//! the sketch's defaults, an instance whose sketch satisfies the prefix does not move (least
//! motion); on random instances every constraint holds at the sketch's defaults and with each
//! default moved, and each default moves `P`.
//!
//! # The report
//!
//! `GCS_WRITE_FRAGMENTS=1` writes `docs/FRAGMENTS3D.md` (totals, the table, the not-yet
//! entries by reason, the instances no branch solved by error and by mode, the entries that
//! solve fewer than half of their random instances, the failures by known cause, the
//! defaults); without it the test checks that the committed file is current. The file holds
//! no timing (the test prints its run time). The test fails on a wrong run (or a failed
//! analysis) that [`KNOWN_WRONG`] does not list, on a listed entry that is no longer wrong in
//! its cause's modes, and on a wrong default.
//!
//! Debugging aids: `GCS_PROBE=model.gcs` prints one model's plan and its solves on every
//! branch; `GCS_ENTRY=n GCS_INSTANCE=i` prints instance `i` of entry `n` (0 the canonical one,
//! 1 to `N_RANDOM` random, then the near-degenerate ones in `harness::degenerate`'s order,
//! 1000 and up inconsistent) with its plan and solves (`-- --nocapture`).
//!
//! The probing, the checker, the defaults' checker and the table writer are shared with the
//! checker in the plane (`construction.rs`): `construction/harness.rs`. This file has the
//! kinds, states, constraint forms and instances of space, and what its plans and tables say
//! ([`Spatial`]).

#[path = "construction/harness.rs"]
mod harness;

use gcs_bench::baseline::Baseline3;

use gcs_compiler::plan::{DefaultVar, Op, RotationAxis, SpatialOp};
use harness::{
    angular, ConstraintForm, GeomKind, Instance, Known, Mode, Out, Rng, Solved, Space, Statements,
    Table, REL,
};
use std::f64::consts::PI;

#[test]
fn construction_checker_3d() {
    harness::check::<Spatial>();
}

/// The wrong entries known so far, by cause. The test passes over a wrong run of a listed entry
/// in a listed mode (it is still counted and shown in `docs/FRAGMENTS3D.md`), fails on any
/// other, and fails when a listed entry no longer has a wrong run in the cause's modes, so that
/// the list shrinks as the analysis is fixed.
const KNOWN_WRONG: &[Known] = &[
    // Empty: the last cause (a direction turned about an axis it nearly lies along, within
    // 1e-9 to 1e-4 rad, a joint's z axis on a body turning about another z, which fixes the
    // turn only to rounding over that distance) is gone. The joint's x axes
    // (`frame::signed_angle3_both`: offset_x, prismatic, and a helical joint on a body held
    // at a point), its point onto a line or plane, or its helix (`SpatialOp::TurnReaching`, on a
    // screw too: `runtime::fragment3::Screw`) decide such a turn with the z axis.
];

/// The valid sketches known to be refused as degenerate, by cause: instances no branch solves,
/// the first error `Degenerate`, where the numeric baseline from the sketch finds an isolated
/// assembly near it (`harness::Judged::Near`). The test fails on any other, and when a listed
/// entry's sketch is no longer refused in the cause's modes.
const KNOWN_DEGENERATE: &[Known] = &[
    // Empty: the last causes (a plan that defaulted the freedom the constraints fix and left
    // the one they free to an intersection of parallel loci: a body on a line with a point on
    // a plane across its turn, a planar joint with a helical one) are gone. A point held on a
    // line and turned about an axis slides to a plane across that axis (`move_point`), and a
    // helix whose second marker's advance the record holds turns it (`advance_held`).
];

// ---------------------------------------------------------------- small maths

type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn mul(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}
fn unit(a: V) -> V {
    mul(a, 1.0 / norm(a))
}
/// A unit vector perpendicular to `a`.
fn any_perp(a: V) -> V {
    let t = if a[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    unit(cross(a, t))
}
/// `v` turned by `angle` about the unit `axis`, right-handed (Rodrigues).
fn turn(v: V, axis: V, angle: f64) -> V {
    let (s, c) = angle.sin_cos();
    add(
        add(mul(v, c), mul(cross(axis, v), s)),
        mul(axis, dot(axis, v) * (1.0 - c)),
    )
}
/// The unit `a` tilted by `eps` towards the unit `b` perpendicular to it.
fn tilt(a: V, b: V, eps: f64) -> V {
    unit(add(mul(a, eps.cos()), mul(b, eps.sin())))
}
/// The unsigned angle between `u` and `v`.
fn angle_between(u: V, v: V) -> f64 {
    norm(cross(u, v)).atan2(dot(u, v))
}
/// The angle from `x1` to `x2` counter-clockwise about the unit `z` (both across it).
fn angle_about(z: V, x1: V, x2: V) -> f64 {
    dot(z, cross(x1, x2)).atan2(dot(x1, x2))
}

/// A unit quaternion `[w, x, y, z]`.
type Q = [f64; 4];

fn q_axis(axis: V, angle: f64) -> Q {
    let (s, c) = (0.5 * angle).sin_cos();
    let a = unit(axis);
    [c, a[0] * s, a[1] * s, a[2] * s]
}
fn q_mul(a: Q, b: Q) -> Q {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}
fn q_rot(q: Q, v: V) -> V {
    let u = [q[1], q[2], q[3]];
    let t = mul(cross(u, v), 2.0);
    add(add(v, mul(t, q[0])), cross(u, t))
}
/// The rotation as an axis and an angle in `[0, pi]`.
fn q_axis_angle(q: Q) -> (V, f64) {
    let q = if q[0] < 0.0 {
        [-q[0], -q[1], -q[2], -q[3]]
    } else {
        q
    };
    let u = [q[1], q[2], q[3]];
    let s = norm(u);
    if s == 0.0 {
        return ([1.0, 0.0, 0.0], 0.0);
    }
    (mul(u, 1.0 / s), 2.0 * s.atan2(q[0]))
}

// ---------------------------------------------------------------- random draws in space

impl Rng {
    /// A uniform unit vector.
    fn unit(&mut self) -> V {
        let z = self.range(-1.0, 1.0);
        let t = self.angle();
        let r = (1.0 - z * z).sqrt();
        [r * t.cos(), r * t.sin(), z]
    }
    /// A unit vector perpendicular to the unit `a`, uniform about it.
    fn across(&mut self, a: V) -> V {
        let t = self.angle();
        turn(any_perp(a), a, t)
    }
    fn point(&mut self, s: f64) -> V {
        [self.range(-s, s), self.range(-s, s), self.range(-s, s)]
    }
    fn rotation(&mut self) -> Q {
        let axis = self.unit();
        let angle = self.range(0.0, PI);
        q_axis(axis, angle)
    }
}

// ---------------------------------------------------------------- the probed geom

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Point,
    Vector,
    Body,
    Line,
    Segment,
    Circle,
    Plane,
}

const KINDS: [Kind; 7] = [
    Kind::Point,
    Kind::Vector,
    Kind::Body,
    Kind::Line,
    Kind::Segment,
    Kind::Circle,
    Kind::Plane,
];

impl GeomKind for Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Point => "point",
            Kind::Vector => "vector",
            Kind::Body => "body",
            Kind::Line => "line",
            Kind::Segment => "segment",
            Kind::Circle => "circle",
            Kind::Plane => "plane",
        }
    }
}

/// A point feature of `P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pt {
    Own,
    M,
    N,
    K,
    A,
    B,
    /// A member point on `m`'s z axis.
    C,
    Start,
    End,
    Center,
}

impl Pt {
    fn text(self) -> &'static str {
        match self {
            Pt::Own => "P",
            Pt::M => "P.m",
            Pt::N => "P.n",
            Pt::K => "P.k",
            Pt::A => "P.a",
            Pt::B => "P.b",
            Pt::C => "P.c",
            Pt::Start => "P.start",
            Pt::End => "P.end",
            Pt::Center => "P.center",
        }
    }
}

/// A direction feature of `P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Di {
    /// A vector's own direction, a line's or segment's, a plane's normal.
    Own,
    Mz,
    Mx,
    Nz,
    Nx,
    /// A circle's normal.
    Normal,
}

impl Di {
    fn text(self) -> &'static str {
        match self {
            Di::Own => "P",
            Di::Mz => "P.m.z",
            Di::Mx => "P.m.x",
            Di::Nz => "P.n.z",
            Di::Nx => "P.n.x",
            Di::Normal => "P.normal",
        }
    }
}

/// A marker of a body probe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mk {
    M,
    N,
}

impl Mk {
    fn text(self) -> &'static str {
        match self {
            Mk::M => "P.m",
            Mk::N => "P.n",
        }
    }
}

/// A marker's local frame: point, z axis, x axis (orthonormal).
#[derive(Clone, Copy, Debug)]
struct Frame {
    o: V,
    z: V,
    x: V,
}

/// The local members of a body probe.
#[derive(Clone, Copy, Debug)]
struct Members {
    m: Frame,
    n: Frame,
    k: Frame,
    a: V,
    b: V,
    c: V,
}

/// A configuration of `P`: position (a point, a body's origin, a line's base, a segment's
/// start, a circle's centre, a plane's point), rotation (a line's direction is its x axis, a
/// circle's or plane's normal its z axis), dimension (length, radius).
#[derive(Clone, Copy, Debug)]
struct Conf {
    pos: V,
    q: Q,
    dim: f64,
}

const EX: V = [1.0, 0.0, 0.0];
const EZ: V = [0.0, 0.0, 1.0];

fn frame(c: &Conf, f: &Frame) -> Frame {
    Frame {
        o: add(c.pos, q_rot(c.q, f.o)),
        z: q_rot(c.q, f.z),
        x: q_rot(c.q, f.x),
    }
}

fn marker(c: &Conf, m: &Members, k: Mk) -> Frame {
    match k {
        Mk::M => frame(c, &m.m),
        Mk::N => frame(c, &m.n),
    }
}

fn pt(c: &Conf, m: &Members, p: Pt) -> V {
    let at = |l: V| add(c.pos, q_rot(c.q, l));
    match p {
        Pt::Own | Pt::Start | Pt::Center => c.pos,
        Pt::End => add(c.pos, mul(q_rot(c.q, EX), c.dim)),
        Pt::M => at(m.m.o),
        Pt::N => at(m.n.o),
        Pt::K => at(m.k.o),
        Pt::A => at(m.a),
        Pt::B => at(m.b),
        Pt::C => at(m.c),
    }
}

fn di(kind: Kind, c: &Conf, m: &Members, d: Di) -> V {
    let local = match (d, kind) {
        (Di::Own, Kind::Plane) | (Di::Normal, _) => EZ,
        (Di::Own, _) => EX,
        (Di::Mz, _) => m.m.z,
        (Di::Mx, _) => m.m.x,
        (Di::Nz, _) => m.n.z,
        (Di::Nx, _) => m.n.x,
    };
    q_rot(c.q, local)
}

// ---------------------------------------------------------------- constraint forms

/// A constraint between a feature of `P` and a new fixed geom (or a unary one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Form {
    Coincident(Pt),
    Spherical(Pt),
    DistPP(Pt),
    DistPlane(Pt),
    OnLine(Pt),
    OnPlane(Pt),
    InLine(Pt),
    InPlane(Pt),
    ParallelZ(Mk),
    OffsetX(Mk),
    Revolute(Mk),
    Prismatic(Mk),
    Cylindrical(Mk),
    Planar(Mk),
    Helical(Mk),
    Parallel(Di),
    DistPL(Pt),
    OnCircle(Pt),
    DistPC(Pt),
    Midpoint(Pt),
    Mirror(Pt),
    Angle(Di),
    Perpendicular(Di),
    OffsetZ(Mk),
    /// `on(point, P)`: a fixed point on `P` (a line, segment, circle or plane).
    OnP,
    /// `distance(point, P) = d`.
    DistP,
    /// `tangent(P, circle)`.
    TangentP,
    /// `distance(P, circle) = d`: a line in the circle's plane `d` outside it, or a circle
    /// in its plane `d` apart from it.
    GapP,
    Length,
    Radius,
    /// `equal(P, segment or circle)`.
    EqualP,
    /// `midpoint(point, P)`.
    SegMidpoint,
    /// `symmetric(point, point, P)`.
    MirrorPlane,
}

impl ConstraintForm for Form {
    fn text(self) -> String {
        match self {
            Form::Coincident(p) => format!("coincident({}, point)", p.text()),
            Form::Spherical(p) => format!("spherical({}, point)", p.text()),
            Form::DistPP(p) => format!("distance({}, point) = d", p.text()),
            Form::DistPlane(p) => format!("distance({}, plane) = d", p.text()),
            Form::OnLine(p) => format!("on({}, line)", p.text()),
            Form::OnPlane(p) => format!("on({}, plane)", p.text()),
            Form::InLine(p) => format!("in_line({}, marker)", p.text()),
            Form::InPlane(p) => format!("in_plane({}, marker)", p.text()),
            Form::ParallelZ(k) => format!("parallel_z({}, marker)", k.text()),
            Form::OffsetX(k) => format!("offset_x(marker, {}) = a", k.text()),
            Form::Revolute(k) => format!("revolute({}, marker)", k.text()),
            Form::Prismatic(k) => format!("prismatic({}, marker)", k.text()),
            Form::Cylindrical(k) => format!("cylindrical({}, marker)", k.text()),
            Form::Planar(k) => format!("planar({}, marker)", k.text()),
            Form::Helical(k) => format!("helical(marker, {}) = pitch", k.text()),
            Form::Parallel(d) => format!("parallel(vector, {})", d.text()),
            Form::DistPL(p) => format!("distance({}, line) = d", p.text()),
            Form::OnCircle(p) => format!("on({}, circle)", p.text()),
            Form::DistPC(p) => format!("distance({}, circle) = d", p.text()),
            Form::Midpoint(p) => format!("midpoint({}, segment)", p.text()),
            Form::Mirror(p) => format!("symmetric({}, point, plane)", p.text()),
            Form::Angle(d) => format!("angle(vector, {}) = a", d.text()),
            Form::Perpendicular(d) => format!("perpendicular(vector, {})", d.text()),
            Form::OffsetZ(k) => format!("offset_z(marker, {}) = a", k.text()),
            Form::OnP => "on(point, P)".into(),
            Form::DistP => "distance(point, P) = d".into(),
            Form::TangentP => "tangent(P, circle)".into(),
            Form::GapP => "distance(P, circle) = d".into(),
            Form::Length => "length(P) = l".into(),
            Form::Radius => "radius(P) = r".into(),
            Form::EqualP => "equal(P, fixed)".into(),
            Form::SegMidpoint => "midpoint(point, P)".into(),
            Form::MirrorPlane => "symmetric(point, point, P)".into(),
        }
    }
}

impl Form {
    /// The point feature it puts on a new locus (line, plane or sphere), for tangent
    /// near-degenerate instances.
    fn locus_point(self) -> Option<Pt> {
        match self {
            Form::DistPP(p)
            | Form::DistPlane(p)
            | Form::OnLine(p)
            | Form::OnPlane(p)
            | Form::InLine(p)
            | Form::InPlane(p) => Some(p),
            _ => None,
        }
    }
}

/// What a prefix constraint holds at the target, for the motion it leaves (the velocities of
/// `P` it allows): a feature point at `x` held, on a line along `e`, on a plane of normal `n`,
/// on a sphere about `c`; a direction held along `d`; the orientation held; a screw.
#[derive(Clone, Copy, Debug)]
enum Loc {
    Pin(V),
    Line(V, V),
    Plane(V, V),
    Sphere(V, V),
    Axis(V),
    Orient,
    /// The feature at `x`, advancing along the unit axis `a` by `pitch` per turn about it.
    Helix(V, V, f64),
}

/// The motion a prefix leaves a feature point, near which a new locus is made tangent.
#[derive(Clone, Copy, Debug)]
enum Motion {
    /// Along a curve with this unit tangent.
    Curve(V),
    /// On a surface with this unit normal.
    Surface(V),
}

/// An orthonormal basis of the span of `vs` (vectors of length `N`), dropping those within
/// `tol` of the span of the previous ones.
fn orthonormal<const N: usize>(vs: &[[f64; N]], tol: f64) -> Vec<[f64; N]> {
    let mut out: Vec<[f64; N]> = Vec::new();
    for v in vs {
        let n0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n0 == 0.0 {
            continue;
        }
        let mut w = v.map(|x| x / n0);
        for b in &out {
            let k: f64 = w.iter().zip(b).map(|(x, y)| x * y).sum();
            for (x, y) in w.iter_mut().zip(b) {
                *x -= k * y;
            }
        }
        let n = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > tol {
            out.push(w.map(|x| x / n));
        }
    }
    out
}

/// The motion of the feature at `x` under the twists (turn `w`, translation `v` of `P`'s
/// point `o`) the prefix's holds allow at the target: the span of the velocities
/// `v + w x (x - o)`. One dimension is a curve, two a surface; none (held) or three (free)
/// give no tangent locus.
fn motion_at(o: V, holds: &[Loc], rotates: bool, x: V) -> Option<Motion> {
    let mut rows: Vec<[f64; 6]> = Vec::new();
    // The velocity of the point at `at` along `w`, as a row over (turn, translation).
    let vel = |at: V, w: V| {
        let r = cross(sub(at, o), w);
        [r[0], r[1], r[2], w[0], w[1], w[2]]
    };
    let turn_row = |w: V| [w[0], w[1], w[2], 0.0, 0.0, 0.0];
    let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if !rotates {
        rows.extend(axes.map(turn_row));
    }
    for h in holds {
        match *h {
            Loc::Pin(at) => rows.extend(axes.map(|w| vel(at, w))),
            Loc::Line(at, e) => {
                let p = any_perp(e);
                rows.push(vel(at, p));
                rows.push(vel(at, cross(e, p)));
            }
            Loc::Plane(at, n) => rows.push(vel(at, n)),
            Loc::Sphere(at, c) => rows.push(vel(at, unit(sub(at, c)))),
            Loc::Axis(d) => {
                let p = any_perp(d);
                rows.push(turn_row(p));
                rows.push(turn_row(cross(d, p)));
            }
            Loc::Orient => rows.extend(axes.map(turn_row)),
            Loc::Helix(at, a, pitch) => {
                // a . velocity = pitch / 2 pi * (w . a)
                let mut r = vel(at, a);
                for i in 0..3 {
                    r[i] -= pitch / (2.0 * PI) * a[i];
                }
                rows.push(r);
            }
        }
    }
    let basis = orthonormal(&rows, 1e-9);
    let mut all = basis.clone();
    let mut null = Vec::new();
    for i in 0..6 {
        let mut e = [0.0; 6];
        e[i] = 1.0;
        let before = all.len();
        all = orthonormal(&[all.clone(), vec![e]].concat(), 1e-6);
        if all.len() > before {
            null.push(all[all.len() - 1]);
        }
    }
    let images: Vec<V> = null
        .iter()
        .map(|n| add([n[3], n[4], n[5]], cross([n[0], n[1], n[2]], sub(x, o))))
        .collect();
    let big = images.iter().map(|v| norm(*v)).fold(0.0, f64::max);
    if big == 0.0 {
        return None;
    }
    let span = orthonormal(
        &images
            .iter()
            .filter(|v| norm(**v) > 1e-9 * big)
            .copied()
            .collect::<Vec<_>>(),
        1e-8,
    );
    match span.len() {
        1 => Some(Motion::Curve(span[0])),
        2 => Some(Motion::Surface(unit(cross(span[0], span[1])))),
        _ => None,
    }
}

type State = harness::State<Spatial>;
type Entry = harness::Entry<Spatial>;

fn st(name: &'static str, prefix: Vec<Form>) -> State {
    State {
        name,
        prefix,
        motion: (),
    }
}

/// The forms of the language the analysis covers, on a point feature.
fn point_forms(p: Pt) -> Vec<Form> {
    use Form::*;
    vec![
        Coincident(p),
        Spherical(p),
        DistPP(p),
        DistPlane(p),
        OnLine(p),
        OnPlane(p),
        InLine(p),
        InPlane(p),
    ]
}

/// The forms on a point feature that the analysis does not cover yet.
fn point_forms_not_yet(p: Pt) -> Vec<Form> {
    use Form::*;
    vec![DistPL(p), OnCircle(p), DistPC(p), Midpoint(p), Mirror(p)]
}

fn marker_forms(k: Mk) -> Vec<Form> {
    use Form::*;
    vec![
        ParallelZ(k),
        OffsetX(k),
        Revolute(k),
        Prismatic(k),
        Cylindrical(k),
        Planar(k),
        Helical(k),
    ]
}

/// The states of each kind, and the last-constraint forms that apply to it.
fn catalogue(kind: Kind) -> (Vec<State>, Vec<Form>) {
    use Form::*;
    match kind {
        Kind::Point => {
            let mut forms = point_forms(Pt::Own);
            forms.extend(point_forms_not_yet(Pt::Own));
            let p = Pt::Own;
            (
                vec![
                    st("free", vec![]),
                    st("on a plane", vec![OnPlane(p)]),
                    st("on a line", vec![OnLine(p)]),
                    st("on a line (two planes)", vec![OnPlane(p), DistPlane(p)]),
                    st("on a sphere", vec![DistPP(p)]),
                    st("on a circle (two spheres)", vec![DistPP(p), DistPP(p)]),
                    st(
                        "on a circle (sphere and plane)",
                        vec![DistPP(p), OnPlane(p)],
                    ),
                    st("fixed", vec![Coincident(p)]),
                ],
                forms,
            )
        }
        Kind::Vector => (
            vec![
                st("free", vec![]),
                st("on a cone (an angle)", vec![Angle(Di::Own)]),
                st("known", vec![Parallel(Di::Own)]),
            ],
            vec![Parallel(Di::Own), Angle(Di::Own), Perpendicular(Di::Own)],
        ),
        Kind::Body => {
            let mut forms = point_forms(Pt::N);
            forms.extend([
                Coincident(Pt::A),
                DistPP(Pt::A),
                DistPlane(Pt::A),
                OnLine(Pt::A),
                OnPlane(Pt::A),
            ]);
            forms.extend([
                Coincident(Pt::C),
                DistPP(Pt::C),
                OnLine(Pt::C),
                OnPlane(Pt::C),
            ]);
            forms.extend([
                Coincident(Pt::M),
                DistPP(Pt::M),
                OnLine(Pt::M),
                OnPlane(Pt::M),
                InLine(Pt::M),
                InPlane(Pt::M),
            ]);
            forms.extend(marker_forms(Mk::N));
            forms.extend(marker_forms(Mk::M));
            forms.extend([
                Parallel(Di::Nz),
                Parallel(Di::Nx),
                Parallel(Di::Mz),
                Parallel(Di::Mx),
            ]);
            forms.extend(point_forms_not_yet(Pt::N));
            forms.extend([Angle(Di::Nz), Perpendicular(Di::Nz), OffsetZ(Mk::N)]);
            let m = Pt::M;
            let k = Mk::M;
            (
                vec![
                    st("free", vec![]),
                    st("pivot", vec![Coincident(m)]),
                    st("pivot, parallel z", vec![Coincident(m), ParallelZ(k)]),
                    st("revolute joint", vec![Revolute(k)]),
                    st("on a line (in_line)", vec![InLine(m)]),
                    st("on a plane (in_plane)", vec![InPlane(m)]),
                    st("on a plane (on)", vec![OnPlane(m)]),
                    st("in_line, parallel z", vec![InLine(m), ParallelZ(k)]),
                    st("cylindrical joint", vec![Cylindrical(k)]),
                    st("in_plane, parallel z", vec![InPlane(m), ParallelZ(k)]),
                    st("planar joint", vec![Planar(k)]),
                    st("parallel z", vec![ParallelZ(k)]),
                    st("orientation known", vec![ParallelZ(k), OffsetX(k)]),
                    st(
                        "orientation known, a point on a line",
                        vec![ParallelZ(k), OffsetX(k), OnLine(Pt::B)],
                    ),
                    st(
                        "orientation known, a point on a plane",
                        vec![ParallelZ(k), OffsetX(k), OnPlane(Pt::B)],
                    ),
                    st("prismatic joint", vec![Prismatic(k)]),
                    st(
                        "screw (cylindrical, helical)",
                        vec![Cylindrical(k), Helical(k)],
                    ),
                    st("a point on a sphere", vec![DistPP(Pt::B)]),
                    st(
                        "fixed (pivot, orientation)",
                        vec![Coincident(m), OffsetX(k)],
                    ),
                    st(
                        "fixed (three points)",
                        vec![Coincident(m), Coincident(Pt::K), Coincident(Pt::B)],
                    ),
                ],
                forms,
            )
        }
        Kind::Line => (
            vec![
                st("free", vec![]),
                st("through a point", vec![OnP]),
                st("direction known", vec![Parallel(Di::Own)]),
                st("on a cone (an angle)", vec![Angle(Di::Own)]),
                st("placed", vec![Parallel(Di::Own), OnP]),
            ],
            vec![
                OnP,
                DistP,
                TangentP,
                GapP,
                Parallel(Di::Own),
                Angle(Di::Own),
                Perpendicular(Di::Own),
            ],
        ),
        Kind::Segment => (
            vec![
                st("free", vec![]),
                st("start held", vec![Coincident(Pt::Start)]),
                st("end held", vec![Coincident(Pt::End)]),
            ],
            vec![
                Coincident(Pt::Start),
                Coincident(Pt::End),
                OnP,
                DistP,
                TangentP,
                GapP,
                Parallel(Di::Own),
                Angle(Di::Own),
                Length,
                EqualP,
                SegMidpoint,
            ],
        ),
        Kind::Circle => (
            vec![
                st("free", vec![]),
                st("centre held", vec![Coincident(Pt::Center)]),
                st("square to a direction", vec![Parallel(Di::Normal)]),
                st(
                    "placed (centre, normal, radius)",
                    vec![Coincident(Pt::Center), Parallel(Di::Normal), Radius],
                ),
            ],
            vec![
                Coincident(Pt::Center),
                OnP,
                DistP,
                TangentP,
                GapP,
                Parallel(Di::Normal),
                Radius,
                EqualP,
            ],
        ),
        Kind::Plane => (
            vec![st("free", vec![])],
            vec![
                OnP,
                DistP,
                Parallel(Di::Own),
                Angle(Di::Own),
                Perpendicular(Di::Own),
                MirrorPlane,
            ],
        ),
    }
}

// ---------------------------------------------------------------- instances

impl Out {
    /// A fixed body's marker at `o` with z axis `z` (x any across it, or `x`).
    fn marker(&mut self, name: String, o: V, z: V, x: Option<V>) -> String {
        let x = x.unwrap_or_else(|| any_perp(z));
        format!(
            "fixed body {name} {{ marker r = {} z {} x {}; }}",
            self.p(o),
            self.d(z),
            self.d(x)
        )
    }
}

/// What `derive` makes of a form.
struct Derived {
    decls: Vec<String>,
    /// The constraint, unlabelled.
    text: String,
    /// A joint's parts (empty for any other constraint).
    parts: Vec<String>,
    holds: Vec<Loc>,
}

/// A direction for a new line, tangent to `degen`'s motion (off it by its angle) when given.
fn line_dir(rng: &mut Rng, degen: Option<(Motion, f64)>) -> V {
    match degen {
        Some((Motion::Curve(t), eps)) => {
            let p = rng.across(t);
            tilt(t, p, eps * rng.sign())
        }
        Some((Motion::Surface(n), eps)) => {
            let e = rng.across(n);
            tilt(e, n, eps * rng.sign())
        }
        None => rng.unit(),
    }
}

/// A normal for a new plane or sphere at a point, tangent to `degen`'s motion there (off it by
/// its angle) when given.
fn normal_dir(rng: &mut Rng, degen: Option<(Motion, f64)>) -> V {
    match degen {
        Some((Motion::Curve(t), eps)) => {
            let n = rng.across(t);
            tilt(n, t, eps * rng.sign())
        }
        Some((Motion::Surface(n), eps)) => {
            let p = rng.across(n);
            mul(tilt(n, p, eps * rng.sign()), rng.sign())
        }
        None => rng.unit(),
    }
}

/// Derives the fixed geoms and the statement of form `f` (number `i`) from the target `t`.
#[allow(clippy::too_many_arguments)]
fn derive(
    f: Form,
    i: usize,
    kind: Kind,
    t: &Conf,
    m: &Members,
    s: f64,
    rng: &mut Rng,
    degen: Option<(Motion, f64)>,
    o: &mut Out,
) -> Derived {
    let mut decls = Vec::new();
    let mut parts = Vec::new();
    let mut holds = Vec::new();
    let plane_decl = |o: &mut Out, name: String, at: V, n: V, k: f64| {
        format!(
            "fixed plane {name} = point {} normal {};",
            o.p(at),
            o.d(mul(n, k))
        )
    };
    let text = match f {
        Form::Coincident(p) | Form::Spherical(p) => {
            let x = pt(t, m, p);
            decls.push(format!("fixed point A{i} = {};", o.p(x)));
            holds.push(Loc::Pin(x));
            let name = if matches!(f, Form::Coincident(_)) {
                "coincident"
            } else {
                "spherical"
            };
            format!("{name}({}, A{i})", p.text())
        }
        Form::DistPP(p) => {
            let x = pt(t, m, p);
            let u = normal_dir(rng, degen);
            let c = add(x, mul(u, s * rng.range(0.3, 2.0)));
            decls.push(format!("fixed point A{i} = {};", o.p(c)));
            holds.push(Loc::Sphere(x, c));
            format!("distance({}, A{i}) = {}", p.text(), o.l(norm(sub(x, c))))
        }
        Form::DistPlane(p) | Form::OnPlane(p) => {
            let x = pt(t, m, p);
            let n = normal_dir(rng, degen);
            let h = if matches!(f, Form::DistPlane(_)) {
                rng.sign() * s * rng.range(0.2, 1.5)
            } else {
                0.0
            };
            let at = add(
                sub(x, mul(n, h)),
                mul(rng.across(n), s * rng.range(0.0, 1.0)),
            );
            let k = rng.range(0.5, 2.0);
            decls.push(plane_decl(o, format!("Q{i}"), at, n, k));
            holds.push(Loc::Plane(x, n));
            if matches!(f, Form::DistPlane(_)) {
                format!("distance({}, Q{i}) = {}", p.text(), o.l(dot(n, sub(x, at))))
            } else {
                format!("on({}, Q{i})", p.text())
            }
        }
        Form::OnLine(p) => {
            let x = pt(t, m, p);
            let e = line_dir(rng, degen);
            let base = add(x, mul(e, s * rng.range(-1.0, 1.0)));
            let end = add(base, mul(e, s * rng.range(0.5, 2.0)));
            decls.push(format!("fixed line L{i} = {} -> {};", o.p(base), o.p(end)));
            holds.push(Loc::Line(x, e));
            format!("on({}, L{i})", p.text())
        }
        Form::InLine(p) => {
            let x = pt(t, m, p);
            let e = line_dir(rng, degen);
            let at = add(x, mul(e, s * rng.range(-1.0, 1.0)));
            decls.push(o.marker(format!("G{i}"), at, e, None));
            holds.push(Loc::Line(x, e));
            format!("in_line({}, G{i}.r)", p.text())
        }
        Form::InPlane(p) => {
            let x = pt(t, m, p);
            let n = normal_dir(rng, degen);
            let at = add(x, mul(rng.across(n), s * rng.range(0.0, 1.0)));
            decls.push(o.marker(format!("G{i}"), at, n, None));
            holds.push(Loc::Plane(x, n));
            format!("in_plane({}, G{i}.r)", p.text())
        }
        Form::ParallelZ(k)
        | Form::OffsetX(k)
        | Form::Revolute(k)
        | Form::Prismatic(k)
        | Form::Cylindrical(k)
        | Form::Planar(k)
        | Form::Helical(k) => {
            let fr = marker(t, m, k);
            // Either sense: the sketch, turned less than 0.6 rad, has the target's.
            let z = mul(fr.z, rng.sign());
            let g = format!("G{i}.r");
            let pk = k.text();
            holds.push(Loc::Axis(fr.z));
            match f {
                Form::ParallelZ(_) => {
                    let at = add(t.pos, rng.point(2.0 * s));
                    decls.push(o.marker(format!("G{i}"), at, z, None));
                    format!("parallel_z({pk}, {g})")
                }
                Form::OffsetX(_) => {
                    let at = add(t.pos, rng.point(2.0 * s));
                    let x = rng.across(z);
                    decls.push(o.marker(format!("G{i}"), at, z, Some(x)));
                    holds.push(Loc::Orient);
                    let a = angle_about(z, x, fr.x);
                    format!("offset_x({g}, {pk}) = {}", o.a(a))
                }
                Form::Revolute(_) => {
                    let x = rng.across(z);
                    decls.push(o.marker(format!("G{i}"), fr.o, z, Some(x)));
                    holds.push(Loc::Pin(fr.o));
                    parts.push(format!("coincident({pk}, {g})"));
                    parts.push(format!("parallel_z({pk}, {g})"));
                    format!("revolute({pk}, {g})")
                }
                Form::Prismatic(_) => {
                    let at = add(fr.o, mul(z, s * rng.range(-1.0, 1.0)));
                    decls.push(o.marker(format!("G{i}"), at, z, Some(fr.x)));
                    holds.push(Loc::Line(fr.o, fr.z));
                    holds.push(Loc::Orient);
                    parts.push(format!("in_line({pk}, {g})"));
                    parts.push(format!("offset_x({pk}, {g}) = 0"));
                    format!("prismatic({pk}, {g})")
                }
                Form::Cylindrical(_) => {
                    let at = add(fr.o, mul(z, s * rng.range(-1.0, 1.0)));
                    let x = rng.across(z);
                    decls.push(o.marker(format!("G{i}"), at, z, Some(x)));
                    holds.push(Loc::Line(fr.o, fr.z));
                    parts.push(format!("in_line({pk}, {g})"));
                    parts.push(format!("parallel_z({pk}, {g})"));
                    format!("cylindrical({pk}, {g})")
                }
                Form::Planar(_) => {
                    let at = add(fr.o, mul(rng.across(z), s * rng.range(0.0, 1.0)));
                    let x = rng.across(z);
                    decls.push(o.marker(format!("G{i}"), at, z, Some(x)));
                    holds.push(Loc::Plane(fr.o, fr.z));
                    parts.push(format!("in_plane({pk}, {g})"));
                    parts.push(format!("parallel_z({pk}, {g})"));
                    format!("planar({pk}, {g})")
                }
                _ => {
                    // A screw: the advance of P's marker along the fixed marker's z, and the
                    // turn of its x axis from the fixed one's, 2 pi advance / pitch.
                    let at = add(fr.o, rng.point(s));
                    let advance = dot(z, sub(fr.o, at));
                    let pitch = rng.sign() * s * rng.range(0.5, 3.0);
                    let x = turn(fr.x, z, -2.0 * PI * advance / pitch);
                    decls.push(o.marker(format!("G{i}"), at, z, Some(x)));
                    holds.push(Loc::Helix(fr.o, z, pitch));
                    format!("helical({g}, {pk}) = {}", o.l(pitch))
                }
            }
        }
        Form::Parallel(d) | Form::Angle(d) | Form::Perpendicular(d) => {
            let v = di(kind, t, m, d);
            let (x, text) = match f {
                Form::Parallel(_) => {
                    holds.push(Loc::Axis(v));
                    (mul(v, rng.sign()), format!("parallel(X{i}, {})", d.text()))
                }
                Form::Angle(_) => {
                    let x = rng.unit();
                    let a = angle_between(x, v);
                    (x, format!("angle(X{i}, {}) = {}", d.text(), o.a(a)))
                }
                _ => (rng.across(v), format!("perpendicular(X{i}, {})", d.text())),
            };
            let k = rng.range(0.5, 2.0);
            decls.push(format!("fixed vector X{i} = {};", o.d(mul(x, k))));
            text
        }
        Form::OffsetZ(k) => {
            let fr = marker(t, m, k);
            let z = rng.unit();
            let at = add(t.pos, rng.point(2.0 * s));
            decls.push(o.marker(format!("G{i}"), at, z, None));
            format!(
                "offset_z(G{i}.r, {}) = {}",
                k.text(),
                o.a(angle_between(z, fr.z))
            )
        }
        Form::DistPL(p) => {
            let x = pt(t, m, p);
            let e = rng.unit();
            let d = s * rng.range(0.2, 1.5);
            let base = add(
                add(x, mul(rng.across(e), d)),
                mul(e, s * rng.range(-1.0, 1.0)),
            );
            let end = add(base, mul(e, s));
            decls.push(format!("fixed line L{i} = {} -> {};", o.p(base), o.p(end)));
            format!("distance({}, L{i}) = {}", p.text(), o.l(d))
        }
        Form::OnCircle(p) | Form::DistPC(p) => {
            let x = pt(t, m, p);
            let u = rng.unit();
            let n = rng.across(u);
            let r = s * rng.range(0.3, 2.0);
            let g = if matches!(f, Form::DistPC(_)) {
                s * rng.range(0.1, 1.0)
            } else {
                0.0
            };
            let c = sub(x, mul(u, r + g));
            decls.push(format!(
                "fixed circle C{i} = center {} radius {} normal {};",
                o.p(c),
                o.l(r),
                o.d(n)
            ));
            if matches!(f, Form::DistPC(_)) {
                format!("distance({}, C{i}) = {}", p.text(), o.l(g))
            } else {
                format!("on({}, C{i})", p.text())
            }
        }
        Form::Midpoint(p) => {
            let x = pt(t, m, p);
            let e = mul(rng.unit(), s * rng.range(0.3, 1.5));
            decls.push(format!(
                "fixed segment S{i} = {} -> {};",
                o.p(sub(x, e)),
                o.p(add(x, e))
            ));
            format!("midpoint({}, S{i})", p.text())
        }
        Form::Mirror(p) => {
            let x = pt(t, m, p);
            let n = rng.unit();
            let h = s * rng.range(0.2, 1.5);
            decls.push(plane_decl(o, format!("Q{i}"), add(x, mul(n, h)), n, 1.0));
            decls.push(format!(
                "fixed point A{i} = {};",
                o.p(add(x, mul(n, 2.0 * h)))
            ));
            format!("symmetric({}, A{i}, Q{i})", p.text())
        }
        Form::OnP | Form::DistP | Form::SegMidpoint => {
            let e = q_rot(t.q, EX);
            let n = q_rot(t.q, EZ);
            let a = match (kind, f) {
                (_, Form::SegMidpoint) => add(t.pos, mul(e, 0.5 * t.dim)),
                (Kind::Circle, Form::OnP) => add(t.pos, mul(turn(e, n, rng.angle()), t.dim)),
                (Kind::Plane, _) => add(t.pos, mul(rng.across(n), s * rng.range(0.0, 1.0))),
                _ => add(t.pos, mul(e, s * rng.range(-1.0, 2.0))),
            };
            let (a, d) = match (kind, f) {
                (_, Form::DistP) => {
                    let d = s * rng.range(0.2, 1.5);
                    let off = match kind {
                        Kind::Plane => mul(n, d * rng.sign()),
                        _ => mul(rng.across(if kind == Kind::Circle { n } else { e }), d),
                    };
                    let a = add(a, off);
                    let d = match kind {
                        Kind::Plane => dot(n, sub(a, t.pos)),
                        Kind::Circle => {
                            let w = sub(a, t.pos);
                            dot(n, w).hypot(norm(cross(n, w)) - t.dim)
                        }
                        _ => norm(cross(e, sub(a, t.pos))),
                    };
                    (a, d)
                }
                _ => (a, 0.0),
            };
            decls.push(format!("fixed point A{i} = {};", o.p(a)));
            match f {
                Form::OnP => format!("on(A{i}, P)"),
                Form::DistP => format!("distance(A{i}, P) = {}", o.l(d)),
                _ => format!("midpoint(A{i}, P)"),
            }
        }
        Form::TangentP | Form::GapP => {
            let e = q_rot(t.q, EX);
            let n = q_rot(t.q, EZ);
            let rho = s * rng.range(0.2, 1.5);
            let gap = if f == Form::GapP {
                s * rng.range(0.1, 1.0)
            } else {
                0.0
            };
            let (c, normal) = if kind == Kind::Circle {
                let u = turn(e, n, rng.angle());
                (add(t.pos, mul(u, t.dim + rho + gap)), n)
            } else {
                let w = rng.across(e);
                let foot = add(t.pos, mul(e, s * rng.range(0.0, 1.0)));
                (add(foot, mul(w, rho + gap)), cross(e, w))
            };
            decls.push(format!(
                "fixed circle C{i} = center {} radius {} normal {};",
                o.p(c),
                o.l(rho),
                o.d(normal)
            ));
            if f == Form::GapP {
                format!("distance(P, C{i}) = {}", o.l(gap))
            } else {
                format!("tangent(P, C{i})")
            }
        }
        Form::Length => format!("length(P) = {}", o.l(t.dim)),
        Form::Radius => format!("radius(P) = {}", o.l(t.dim)),
        Form::EqualP => {
            let a = add(t.pos, rng.point(2.0 * s));
            if kind == Kind::Circle {
                decls.push(format!(
                    "fixed circle K{i} = center {} radius {} normal {};",
                    o.p(a),
                    o.l(t.dim),
                    o.d(rng.unit())
                ));
            } else {
                decls.push(format!(
                    "fixed segment T{i} = {} -> {};",
                    o.p(a),
                    o.p(add(a, mul(rng.unit(), t.dim)))
                ));
            }
            format!(
                "equal(P, {}{i})",
                if kind == Kind::Circle { "K" } else { "T" }
            )
        }
        Form::MirrorPlane => {
            let n = q_rot(t.q, EZ);
            let x = add(t.pos, mul(rng.across(n), s * rng.range(0.0, 1.0)));
            let h = s * rng.range(0.2, 1.5);
            decls.push(format!("fixed point A{i} = {};", o.p(add(x, mul(n, h)))));
            decls.push(format!("fixed point B{i} = {};", o.p(sub(x, mul(n, h)))));
            format!("symmetric(A{i}, B{i}, P)")
        }
    };
    Derived {
        decls,
        text,
        parts,
        holds,
    }
}

/// The declaration of `P` with configuration `c`.
fn probe_decl(kind: Kind, c: &Conf, m: &Members, s: f64, o: &mut Out) -> String {
    let e = q_rot(c.q, EX);
    let n = q_rot(c.q, EZ);
    match kind {
        Kind::Point => format!("point P = {};", o.p(c.pos)),
        Kind::Vector => format!("vector P = {};", o.d(mul(e, 1.5))),
        Kind::Line => format!("line P = {} -> {};", o.p(c.pos), o.p(add(c.pos, mul(e, s)))),
        Kind::Segment => format!(
            "segment P = {} -> {};",
            o.p(c.pos),
            o.p(add(c.pos, mul(e, c.dim)))
        ),
        Kind::Circle => format!(
            "circle P = center {} radius {} normal {};",
            o.p(c.pos),
            o.l(c.dim),
            o.d(n)
        ),
        Kind::Plane => format!("plane P = point {} normal {};", o.p(c.pos), o.d(n)),
        Kind::Body => {
            let (axis, angle) = q_axis_angle(c.q);
            let mk = |o: &mut Out, name: &str, f: &Frame| {
                format!(
                    "marker {name} = {} z {} x {};",
                    o.p(f.o),
                    o.d(f.z),
                    o.d(f.x)
                )
            };
            format!(
                "body P at {} rotated {} about {} {{ {} {} {} point a = {}; point b = {}; point c = {}; }}",
                o.p(c.pos),
                o.a(angle),
                o.d(axis),
                mk(o, "m", &m.m),
                mk(o, "n", &m.n),
                mk(o, "k", &m.k),
                o.p(m.a),
                o.p(m.b),
                o.p(m.c)
            )
        }
    }
}

fn random_frame(rng: &mut Rng, s: f64) -> Frame {
    let z = rng.unit();
    let x = rng.across(z);
    Frame {
        o: rng.point(s),
        z,
        x,
    }
}

fn members(rng: &mut Rng, s: f64, mode: Mode) -> Members {
    let m = random_frame(rng, s);
    let mut n = random_frame(rng, s);
    let k = random_frame(rng, s);
    let mut a = rng.point(s);
    let b = rng.point(s);
    let c = add(m.o, mul(m.z, rng.sign() * s * rng.range(0.3, 1.5)));
    match mode {
        Mode::NearParallel => {
            let eps = rng.log_range(1e-9, 1e-4);
            n.z = tilt(m.z, rng.across(m.z), eps);
            n.x = rng.across(n.z);
        }
        Mode::Coincident => {
            n.o = m.o;
            a = m.o;
            if rng.sign() > 0.0 {
                n = m;
            }
        }
        _ => {}
    }
    Members { m, n, k, a, b, c }
}

fn make(e: &Entry, seed: u64, mode: Mode) -> Instance {
    let mut rng = Rng::new(seed);
    let s = harness::size(&mut rng, mode);
    let mem = members(&mut rng, s, mode);
    let t = Conf {
        pos: rng.point(3.0 * s),
        q: rng.rotation(),
        dim: s * rng.range(0.5, 2.0),
    };
    let mut o = Out { scale: 0.0 };
    let mut stmts = Statements::default();
    let mut holds = Vec::new();
    let tp = harness::prefix_target(mode, t, |t| Conf {
        pos: add(t.pos, mul(rng.unit(), 1e-2 * s)),
        q: q_mul(q_axis(rng.unit(), 1e-2), t.q),
        dim: t.dim * 1.01,
    });
    // A constraint, its declarations, and its parts in the split model; what it holds.
    let push = |stmts: &mut Statements, label: String, d: Derived| {
        stmts.decls.extend(d.decls);
        if d.parts.is_empty() {
            stmts.split.push(format!("{label}: {};", d.text));
        }
        for (j, part) in d.parts.iter().enumerate() {
            stmts.split.push(format!("{label}__{j}: {part};"));
        }
        (format!("{label}: {};", d.text), d.holds)
    };
    for (i, &f) in e.prefix.iter().enumerate() {
        let d = derive(f, i, e.kind, &tp, &mem, s, &mut rng, None, &mut o);
        let (line, held) = push(&mut stmts, format!("p{i}"), d);
        stmts.prefix.push(line);
        holds.extend(held);
    }
    // The motion the prefix leaves the last constraint's feature, for tangent instances.
    let motion = e.last.locus_point().and_then(|p| {
        let x = pt(&t, &mem, p);
        motion_at(t.pos, &holds, e.kind != Kind::Point, x)
    });
    let degen = harness::off_tangent(mode, motion, &mut rng);
    let n = e.prefix.len();
    let d = derive(e.last, n, e.kind, &t, &mem, s, &mut rng, degen, &mut o);
    let (line, _) = push(&mut stmts, "z".into(), d);
    stmts.last.push(line);
    // The sketch: the target moved.
    let mag = harness::sketch_motion(mode, &mut rng);
    let about = add(t.pos, rng.point(s));
    let spin = q_axis(rng.unit(), mag * rng.range(-0.6, 0.6));
    let shift = mul(rng.point(s), mag);
    let sk = Conf {
        pos: add(add(about, q_rot(spin, sub(t.pos, about))), shift),
        q: q_mul(spin, t.q),
        dim: t.dim * (mag * rng.range(-0.5, 0.5)).exp(),
    };
    let probe = probe_decl(e.kind, &sk, &mem, s, &mut o);
    stmts.instance("space 3d;\nfixed point O = (0, 0, 0);", &probe, o.scale)
}

// ---------------------------------------------------------------- the checker in space

/// The construction checker in space.
struct Spatial;

impl Space for Spatial {
    type Kind = Kind;
    type Form = Form;
    type Baseline = Baseline3;
    type StateMotion = ();

    const KINDS: &'static [Kind] = &KINDS;
    const N_RANDOM: usize = 16;
    const OWN_MODES: &'static [Mode] = &[Mode::NearParallel, Mode::NearParallel, Mode::Coincident];
    const KNOWN_WRONG: &'static [Known] = KNOWN_WRONG;
    const KNOWN_DEGENERATE: &'static [Known] = KNOWN_DEGENERATE;
    const TABLE: Table = Table {
        test: "construction3d",
        command: "GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-bench --release --test construction3d",
        file: "FRAGMENTS3D.md",
        title: "Plan fragment table and construction checker in space",
        members: "A body `P` has markers `m`, `n`, `k` and points `a`, `b`, `c` (`c` on `m`'s z \
                  axis); the prefix holds `m` (and `k`, `b`). ",
        degenerate: ": tangent and nearly tangent loci, nearly parallel axes, coincident markers, \
                     the sketch at the target, scales 1e-3 and 1e3",
        last: " The 2d table is `docs/FRAGMENTS.md`.",
        unsolved: ". One example for the first few entries.",
        defaults_source: "compiler/src/analysis/spatial/mod.rs",
        refused_example: "",
        validated: false,
        detailed: true,
    };
    /// Fewer defaults than the record's DOF when a relation pending at the first default is
    /// solved after it (the screw's helical joint); never more.
    const FEWER_DEFAULTS: bool = true;
    const SOLVE_PANIC_REFUSES: bool = true;
    const NAN_DEFAULT_WRONG: bool = true;

    fn catalogue(kind: Kind) -> (Vec<State>, Vec<Form>) {
        catalogue(kind)
    }
    fn make(e: &Entry, seed: u64, mode: Mode) -> Instance {
        make(e, seed, mode)
    }

    fn op_name(op: &Op) -> Option<String> {
        let axis_words = |a: &RotationAxis| match a {
            RotationAxis::Shortest => " (shortest)",
            RotationAxis::Along(_) => " (about the axis)",
            RotationAxis::Normal => " (about the normal)",
        };
        Some(match op {
            Op::RotatePoint { axis, .. } => format!("rotate to point{}", axis_words(axis)),
            Op::RotateDir { axis, .. } => format!("rotate to direction{}", axis_words(axis)),
            Op::Spatial(SpatialOp::RotateBy { .. }) => {
                "rotate by the angle (about the axis)".into()
            }
            Op::Spatial(SpatialOp::TurnReaching { .. }) => {
                "angle about (direction and point)".into()
            }
            Op::Line { .. } => "line".into(),
            Op::Spatial(SpatialOp::Plane { .. }) => "plane".into(),
            Op::Spatial(SpatialOp::Sphere { .. }) => "sphere".into(),
            Op::Spatial(SpatialOp::SphereThrough { .. }) => "sphere through".into(),
            Op::Spatial(SpatialOp::Orbit { .. }) => "orbit".into(),
            Op::Spatial(SpatialOp::ParallelPlane { .. }) => "parallel plane".into(),
            Op::Spatial(SpatialOp::ShiftedSphere { .. }) => "shifted sphere".into(),
            Op::Spatial(SpatialOp::Opposite(_)) => "opposite".into(),
            Op::Spatial(SpatialOp::TurnedAbout { .. }) => "turned about".into(),
            Op::Spatial(SpatialOp::AngleAbout { .. }) => "angle about".into(),
            Op::Spatial(SpatialOp::AngleAboutBoth { .. }) => "angle about (z and x)".into(),
            Op::Spatial(SpatialOp::ConeTurn { .. }) => "onto cone".into(),
            Op::Spatial(SpatialOp::Aligned { .. }) => "aligned".into(),
            Op::Spatial(SpatialOp::HelixAdvance { .. }) => "helix advance".into(),
            Op::Spatial(SpatialOp::HelixTurn { .. }) => "helix turn".into(),
            Op::Along { .. } => "advance along".into(),
            Op::Spatial(SpatialOp::PointAt { .. }) => "point".into(),
            _ => return harness::op_name(op),
        })
    }

    /// A turn about an axis checked where the cone must agree is a fragment and a check.
    fn turns(op: &Op) -> bool {
        matches!(
            op,
            Op::RotateDir { .. } | Op::RotatePoint { .. } | Op::Spatial(SpatialOp::RotateBy { .. })
        )
    }

    /// Measured by `verify` on the twin model where every joint is written as its parts, each
    /// part to its own tolerance: `REL` rad for an angle, [`Solved::tol_len`] for a length.
    fn violations(v: &Solved<'_>) -> Vec<(f64, String)> {
        let tol_len = v.tol_len();
        let claimed_labels: Vec<&str> = (v.claimed.iter())
            .filter_map(|c| v.model.constraints[*c].label.as_deref())
            .collect();
        let params = v.split.default_params();
        let res = gcs_compiler::verify::residuals(v.split, v.sol, &params);
        res.iter()
            .filter(|r| {
                let l = (v.split.constraints[r.constraint].label.as_deref()).unwrap_or("");
                let base = l.split("__").next().unwrap_or(l);
                claimed_labels.contains(&base)
            })
            .filter_map(|r| {
                let c = &v.split.constraints[r.constraint];
                let tol = if angular(c.kind) { REL } else { tol_len };
                if !(r.value.is_nan() || r.value > tol) {
                    return None;
                }
                let rel = if angular(c.kind) {
                    r.value
                } else {
                    r.value / v.scale.max(f64::MIN_POSITIVE)
                };
                let rel = if rel.is_nan() { f64::INFINITY } else { rel };
                let unit = if angular(c.kind) { "rad" } else { "length" };
                let words = format!(
                    "`{}` residual {:.3e} ({unit}, scale {:.3e})",
                    c.text, r.value, v.scale
                );
                Some((rel, words))
            })
            .collect()
    }

    /// A turn, a spin, a place on a circle count as angles.
    fn angle_default(d: &DefaultVar) -> bool {
        let name = &d.name;
        name.ends_with("_angle") || name.ends_with("_spin") || name.contains("_turn_")
    }

    fn baseline(model: &gcs_lang::Model) -> Result<Baseline3, String> {
        Baseline3::new(model)
    }
}
