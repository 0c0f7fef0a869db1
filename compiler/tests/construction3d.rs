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
//! 1 to `N_RANDOM` random, then the near-degenerate ones in `DEGENERATE`'s order, 1000 and up
//! inconsistent) with its plan and solves (`-- --nocapture`).

/// A known cause of wrong runs: what the plans do wrong, the instance modes its wrong runs
/// show in (`analysis` for a plan the analysis could not build), and the entries it makes
/// wrong, by `kind | state | constraint form` as the table writes them.
struct Known {
    why: &'static str,
    modes: &'static [&'static str],
    entries: &'static [&'static str],
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
    // at a point), its point onto a line or plane, or its helix (`Op::TurnReaching`, on a
    // screw too: `runtime::fragment3::Screw`) decide such a turn with the z axis.
];

use gcs_compiler::analyse;
use gcs_compiler::analysis::Analysis;
use gcs_compiler::plan::{Op, RotationAxis};
use gcs_lang::constraints::ConstraintKind as CK;
use gcs_lang::model::ConstraintId;
use gcs_lang::Model;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::fmt::Write as _;

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
    fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.f()).exp()
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

impl Kind {
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

impl Form {
    /// The form as it reads in the table (fixed geoms by their kind).
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

struct State {
    name: &'static str,
    prefix: Vec<Form>,
}

fn st(name: &'static str, prefix: Vec<Form>) -> State {
    State { name, prefix }
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

struct Entry {
    kind: Kind,
    state: &'static str,
    prefix: Vec<Form>,
    last: Form,
}

impl Entry {
    /// The key `KNOWN_WRONG` lists it by.
    fn key(&self) -> String {
        format!(
            "{} | {} | {}",
            self.kind.name(),
            self.state,
            self.last.text()
        )
    }
}

fn entries() -> Vec<Entry> {
    let mut out = Vec::new();
    for kind in KINDS {
        let (states, forms) = catalogue(kind);
        for s in &states {
            for &f in &forms {
                out.push(Entry {
                    kind,
                    state: s.name,
                    prefix: s.prefix.clone(),
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
    /// `n`'s z axis nearly parallel to `m`'s.
    NearParallel,
    /// `n` and `a` at `m`'s point.
    Coincident,
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
            Mode::NearParallel => "nearly parallel axes".into(),
            Mode::Coincident => "coincident markers".into(),
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
    /// The model with every joint written as its parts (labelled `{label}__{i}`).
    split_text: String,
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
        format!("({}, {}, {})", self.l(p[0]), self.l(p[1]), self.l(p[2]))
    }
    fn a(&mut self, x: f64) -> String {
        format!("{x:?}")
    }
    fn d(&mut self, v: V) -> String {
        format!("({:?}, {:?}, {:?})", v[0], v[1], v[2])
    }
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
    let k = match mode {
        Mode::Scale(k) => k,
        _ => 1.0,
    };
    let s = k * rng.range(0.5, 2.0);
    let mem = members(&mut rng, s, mode);
    let t = Conf {
        pos: rng.point(3.0 * s),
        q: rng.rotation(),
        dim: s * rng.range(0.5, 2.0),
    };
    let mut o = Out { scale: 0.0 };
    let mut decls = Vec::new();
    let mut lines = Vec::new();
    let mut split = Vec::new();
    let mut holds = Vec::new();
    // An inconsistent instance: the prefix places P slightly elsewhere than z wants it.
    let tp = if mode == Mode::Inconsistent {
        Conf {
            pos: add(t.pos, mul(rng.unit(), 1e-2 * s)),
            q: q_mul(q_axis(rng.unit(), 1e-2), t.q),
            dim: t.dim * 1.01,
        }
    } else {
        t
    };
    let mut push = |label: String, d: Derived, lines: &mut Vec<String>| {
        decls.extend(d.decls);
        lines.push(format!("{label}: {};", d.text));
        if d.parts.is_empty() {
            split.push(format!("{label}: {};", d.text));
        }
        for (j, part) in d.parts.iter().enumerate() {
            split.push(format!("{label}__{j}: {part};"));
        }
        d.holds
    };
    for (i, &f) in e.prefix.iter().enumerate() {
        let d = derive(f, i, e.kind, &tp, &mem, s, &mut rng, None, &mut o);
        holds.extend(push(format!("p{i}"), d, &mut lines));
    }
    // The motion the prefix leaves the last constraint's feature, for tangent instances.
    let motion = e.last.locus_point().and_then(|p| {
        let x = pt(&t, &mem, p);
        motion_at(t.pos, &holds, e.kind != Kind::Point, x)
    });
    let degen = match (mode, motion) {
        (Mode::Tangent, Some(mo)) => Some((mo, 0.0)),
        (Mode::NearTangent, Some(mo)) => Some((mo, rng.log_range(1e-9, 1e-4))),
        _ => None,
    };
    let n = e.prefix.len();
    let d = derive(e.last, n, e.kind, &t, &mem, s, &mut rng, degen, &mut o);
    let mut last = Vec::new();
    push("z".into(), d, &mut last);
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
    let about = add(t.pos, rng.point(s));
    let spin = q_axis(rng.unit(), mag * rng.range(-0.6, 0.6));
    let shift = mul(rng.point(s), mag);
    let sk = Conf {
        pos: add(add(about, q_rot(spin, sub(t.pos, about))), shift),
        q: q_mul(spin, t.q),
        dim: t.dim * (mag * rng.range(-0.5, 0.5)).exp(),
    };
    let probe = probe_decl(e.kind, &sk, &mem, s, &mut o);
    // A fixed origin, so that no model is grounded at its probe's sketch.
    let head = format!(
        "space 3d;\nfixed point O = (0, 0, 0);\n{}\n{probe}\n",
        decls.join("\n")
    );
    let prefix_text = format!("{head}{}\n", lines.join("\n"));
    let text = format!("{prefix_text}{}\n", last.join("\n"));
    let split_text = format!("{head}{}\n", split.join("\n"));
    Instance {
        text,
        prefix_text,
        split_text,
        scale: o.scale,
    }
}

// ---------------------------------------------------------------- classification

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("probe.gcs", text.as_bytes());
    match model {
        Some(m) if !diags.iter().any(|d| d.is_error()) => m,
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

fn axis_words(a: &RotationAxis) -> &'static str {
    match a {
        RotationAxis::Shortest => " (shortest)",
        RotationAxis::Along(_) => " (about the axis)",
        RotationAxis::Normal => " (about the normal)",
    }
}

fn op_name(op: &Op) -> Option<String> {
    Some(match op {
        Op::Intersect { meet, .. } => format!("intersect {meet:?}"),
        Op::Onto { .. } => "onto".into(),
        Op::Nearest { .. } => "nearest".into(),
        Op::Translate { .. } => "translate".into(),
        Op::RotatePoint { axis, .. } => format!("rotate to point{}", axis_words(axis)),
        Op::RotateDir { axis, .. } => format!("rotate to direction{}", axis_words(axis)),
        Op::RotateBy { .. } => "rotate by the angle (about the axis)".into(),
        Op::TurnReaching { .. } => "angle about (direction and point)".into(),
        Op::Check { .. } => "check".into(),
        Op::Line { .. } => "line".into(),
        Op::Plane { .. } => "plane".into(),
        Op::Sphere { .. } => "sphere".into(),
        Op::SphereThrough { .. } => "sphere through".into(),
        Op::Orbit { .. } => "orbit".into(),
        Op::ParallelLine { .. } => "parallel line".into(),
        Op::ParallelPlane { .. } => "parallel plane".into(),
        Op::ShiftedSphere { .. } => "shifted sphere".into(),
        Op::ShiftedCircle { .. } => "shifted circle".into(),
        Op::Opposite(_) => "opposite".into(),
        Op::TurnedAbout { .. } => "turned about".into(),
        Op::AngleAbout { .. } => "angle about".into(),
        Op::AngleAboutBoth { .. } => "angle about (z and x)".into(),
        Op::ConeTurn { .. } => "onto cone".into(),
        Op::Aligned { .. } => "aligned".into(),
        Op::SetDim { .. } => "set dimension".into(),
        Op::HelixAdvance { .. } => "helix advance".into(),
        Op::HelixTurn { .. } => "helix turn".into(),
        Op::Along { .. } => "advance along".into(),
        Op::DirectionTo { .. } => "direction to".into(),
        Op::Default(_) => "default".into(),
        Op::LocusPoint { .. } => "point on locus".into(),
        Op::PointAt { .. } => "point".into(),
        Op::Close { .. } => "close by iteration".into(),
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
    /// The analysis failed (a malformed plan): a bug, counted as wrong.
    Failed(String),
}

impl Outcome {
    fn text(&self) -> String {
        match self {
            Outcome::Fragment(ops) => format!("fragment: {ops}"),
            Outcome::Check => "check".into(),
            Outcome::Recorded => "recorded (satisfied when placed)".into(),
            Outcome::NotYet(r) => format!("not yet: {r}"),
            Outcome::Unreached(r) => format!("state not reached: {r}"),
            Outcome::Failed(r) => format!("**analysis failed**: {r}"),
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
    let model = load(&inst.text);
    let failed = |why: String| Class {
        outcome: Outcome::Failed(why),
        before: "?".into(),
        after: "?".into(),
        note: String::new(),
    };
    let pa = match analyse(&pm) {
        Ok(a) => a,
        Err(err) => return failed(format!("the prefix: {err}")),
    };
    let before = record_of(&pm, &pa);
    let a = match analyse(&model) {
        Ok(a) => a,
        Err(err) => return failed(err.to_string()),
    };
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
        // A turn about an axis checked where the cone must agree is a fragment and a check.
        let turned = steps[..j]
            .iter()
            .rev()
            .take_while(|s| s.satisfies.is_empty())
            .any(|s| {
                matches!(
                    s.op,
                    Op::RotateDir { .. } | Op::RotatePoint { .. } | Op::RotateBy { .. }
                )
            });
        if !turned {
            return Class {
                outcome: Outcome::Check,
                before,
                after,
                note,
            };
        }
    }
    // The fragment starts after the prefix's own steps.
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
    let ops: Vec<String> = steps[start..=j]
        .iter()
        .filter_map(|s| op_name(&s.op))
        .collect();
    let prefix_ids: Vec<ConstraintId> = (0..e.prefix.len())
        .filter_map(|i| label(&model, &format!("p{i}")))
        .collect();
    if steps[j + 1..]
        .iter()
        .any(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)))
    {
        let _ = write!(note, "runs before part of the prefix");
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

const N_RANDOM: usize = 16;
const DEGENERATE: [Mode; 11] = [
    Mode::Tangent,
    Mode::Tangent,
    Mode::NearTangent,
    Mode::NearTangent,
    Mode::NearParallel,
    Mode::NearParallel,
    Mode::Coincident,
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
    /// Random instances (of `N_RANDOM`) some branch solved.
    random_solved: usize,
    /// Instances no branch solved, by error kind.
    unsolved: BTreeMap<String, usize>,
    /// Instances no branch solved, by mode.
    unsolved_modes: BTreeMap<String, usize>,
    /// Instances whose analysis did not claim `z` (classified otherwise).
    reclassified: usize,
    /// Wrong runs: the largest relative residual, the instance's mode, and the details.
    wrong: Vec<(f64, String, String)>,
    /// Inconsistent instances of a check: run, refused, and accepted ones.
    inconsistent: usize,
    inconsistent_refused: usize,
    inconsistent_accepted: Vec<String>,
    /// An example of an unsolved instance.
    unsolved_example: Option<String>,
}

fn angular(k: CK) -> bool {
    matches!(
        k,
        CK::Angle
            | CK::Parallel
            | CK::Perpendicular
            | CK::ParallelZ
            | CK::OffsetZ
            | CK::OffsetX
            | CK::Helical
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

/// The claimed constraints' residuals beyond tolerance, measured by `verify` on the twin
/// model where every joint is written as its parts: `(relative residual, words)`.
fn violations(
    model: &Model,
    split: &Model,
    sol: &gcs_compiler::solution::Solution,
    claimed: &[ConstraintId],
    scale: f64,
) -> Vec<(f64, String)> {
    let tol_len = (REL * scale.max(f64::MIN_POSITIVE)).max(REL * magnitude_of(sol));
    let claimed_labels: Vec<&str> = claimed
        .iter()
        .filter_map(|c| model.constraints[*c].label.as_deref())
        .collect();
    let params = split.default_params();
    let res = gcs_compiler::verify::residuals(split, sol, &params);
    res.iter()
        .filter(|r| {
            let l = split.constraints[r.constraint]
                .label
                .as_deref()
                .unwrap_or("");
            let base = l.split("__").next().unwrap_or(l);
            claimed_labels.contains(&base)
        })
        .filter_map(|r| {
            let c = &split.constraints[r.constraint];
            let tol = if angular(c.kind) { REL } else { tol_len };
            if !(r.value.is_nan() || r.value > tol) {
                return None;
            }
            let rel = if angular(c.kind) {
                r.value
            } else {
                r.value / scale.max(f64::MIN_POSITIVE)
            };
            let rel = if rel.is_nan() { f64::INFINITY } else { rel };
            Some((
                rel,
                format!(
                    "`{}` residual {:.3e} ({}, scale {:.3e})",
                    c.text,
                    r.value,
                    if angular(c.kind) { "rad" } else { "length" },
                    scale
                ),
            ))
        })
        .collect()
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

type Verdict = Result<(), Result<(f64, String), String>>;

fn run_instance(entry_id: &str, seed: u64, mode: Mode, inst: &Instance, stats: &mut Stats) {
    stats.instances += 1;
    let model = load(&inst.text);
    let split = load(&inst.split_text);
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let a = analyse(&model).map_err(|e| e.to_string())?;
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
        let mut results: Vec<(Vec<usize>, Verdict)> = Vec::new();
        for combo in combos(&counts, &defaults) {
            // The plan as it is, even when it leaves geoms free: the fragments are checked.
            let r = gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo);
            let verdict = match r {
                Ok(sol) => {
                    let bad = violations(&model, &split, &sol, &claimed, inst.scale);
                    if bad.is_empty() {
                        Ok(())
                    } else {
                        let worst = bad.iter().map(|b| b.0).fold(0.0, f64::max);
                        let words: Vec<String> = bad.into_iter().map(|b| b.1).collect();
                        Err(Ok((worst, words.join("; "))))
                    }
                }
                Err(e) => Err(Err(format!("{:?} {:.3e}", e.kind, e.magnitude))),
            };
            results.push((combo, verdict));
        }
        Ok::<_, String>((claimed.contains(&z), results))
    }));
    let failure = match outcome {
        Ok(Ok(x)) => Ok(x),
        Ok(Err(e)) => Err(format!("analysis failed: {e}")),
        Err(p) => Err(format!("panic: {}", panic_text(p))),
    };
    let (claims_z, results) = match failure {
        Ok(x) => x,
        Err(msg) => {
            stats.wrong.push((
                f64::INFINITY,
                mode.name(),
                format!(
                    "{entry_id}: seed {seed} ({}): {msg}\n```gcs\n{}```",
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
            Err(Ok((worst, msg))) => {
                stats.wrong.push((
                    *worst,
                    mode.name(),
                    format!(
                        "{entry_id}: seed {seed} ({}), branches {combo:?}: {msg}\n```gcs\n{}```",
                        mode.name(),
                        inst.text
                    ),
                ));
            }
            Err(Err(msg)) => {
                if first_err.is_none() {
                    first_err = Some(msg.clone());
                }
            }
        }
    }
    if any {
        stats.solved += 1;
        if mode == Mode::Random {
            stats.random_solved += 1;
        }
    } else {
        let e =
            first_err.unwrap_or_else(|| "Wrong (every run violated a claimed constraint)".into());
        let kind = e.split(' ').next().unwrap_or("").to_string();
        *stats.unsolved.entry(kind).or_default() += 1;
        *stats.unsolved_modes.entry(mode.name()).or_default() += 1;
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
/// return a solution that violates the checked constraint. Reported, not asserted.
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
        let Ok(Ok(sol)) = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo)
        })) else {
            continue;
        };
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
    stats.inconsistent_refused += 1;
}

const N_INCONSISTENT: usize = 4;

// ---------------------------------------------------------------- the test and the report

struct Row {
    id: String,
    key: String,
    kind: Kind,
    state: &'static str,
    form: String,
    class: Class,
    stats: Option<Stats>,
}

impl Row {
    /// Its wrong runs' modes (`analysis` for a failed analysis).
    fn wrong_modes(&self) -> Vec<String> {
        let mut modes: Vec<String> = (self.stats.iter())
            .flat_map(|s| s.wrong.iter().map(|w| w.1.clone()))
            .collect();
        if matches!(self.class.outcome, Outcome::Failed(_)) {
            modes.push("analysis".into());
        }
        modes
    }
    fn wrong(&self) -> usize {
        self.wrong_modes().len()
    }
    /// Whether a wrong run in `mode` is known.
    fn known(&self, mode: &str) -> bool {
        KNOWN_WRONG
            .iter()
            .any(|k| k.entries.contains(&self.key.as_str()) && k.modes.contains(&mode))
    }
    /// Its wrong runs that no known cause lists.
    fn unexpected(&self) -> usize {
        self.wrong_modes().iter().filter(|m| !self.known(m)).count()
    }
}

fn row(n: usize, e: &Entry) -> Row {
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
    Row {
        id,
        key: e.key(),
        kind: e.kind,
        state: e.state,
        form: e.last.text(),
        class,
        stats,
    }
}

/// Runs `f` on every item on a few threads, keeping the items' order.
fn parallel_map<T: Sync, R: Send>(items: &[T], f: impl Fn(usize, &T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .clamp(1, 8);
    let mut out: Vec<(usize, R)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let f = &f;
                scope.spawn(move || {
                    (k..items.len())
                        .step_by(threads)
                        .map(|i| (i, f(i, &items[i])))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a checker thread"))
            .collect()
    });
    out.sort_by_key(|(i, _)| *i);
    out.into_iter().map(|(_, r)| r).collect()
}

#[test]
fn construction_checker_3d() {
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
    let rows = parallel_map(&entries, row);
    let defaults = default_rows();
    let elapsed = t0.elapsed().as_secs_f64();
    let report = report(&rows) + &defaults_report(&defaults);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/FRAGMENTS3D.md");
    println!("{}- runtime {elapsed:.1} s", summary(&rows));
    if std::env::var("GCS_WRITE_FRAGMENTS").as_deref() == Ok("1") {
        std::fs::write(&path, &report).expect("write docs/FRAGMENTS3D.md");
    }
    let mut unexpected = 0;
    for r in &rows {
        if r.unexpected() == 0 {
            continue;
        }
        unexpected += r.unexpected();
        if let Outcome::Failed(why) = &r.class.outcome {
            println!(
                "WRONG {} {} [analysis]: analysis failed: {why}",
                r.id, r.key
            );
        }
        for (_, mode, w) in r.stats.iter().flat_map(|s| &s.wrong) {
            if !r.known(mode) {
                println!("WRONG {} {} [{mode}]: {w}", r.id, r.key);
            }
        }
    }
    let stale: Vec<String> = KNOWN_WRONG
        .iter()
        .flat_map(|k| k.entries.iter().map(move |e| (k, e)))
        .filter(|(k, e)| {
            !rows.iter().any(|r| {
                r.key == **e
                    && r.wrong_modes()
                        .iter()
                        .any(|m| k.modes.contains(&m.as_str()))
            })
        })
        .map(|(k, e)| format!("{e} ({})", k.modes.join(", ")))
        .collect();
    assert_eq!(
        unexpected, 0,
        "wrong runs not in KNOWN_WRONG: see the WRONG lines above"
    );
    assert!(
        stale.is_empty(),
        "entries in KNOWN_WRONG that are no longer wrong in its modes (remove them): {stale:?}"
    );
    for r in &defaults {
        for w in &r.wrong {
            println!("WRONG DEFAULT {} {}: {w}", r.kind.name(), r.state);
        }
        // Fewer defaults than the record's DOF when a relation pending at the first default
        // is solved after it (the screw's helical joint); never more.
        assert!(
            r.refused || r.defaults.len() <= r.dof,
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
        "docs/FRAGMENTS3D.md is out of date: regenerate it with GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-compiler --release --test construction3d"
    );
}

/// Whether a checked entry solves fewer than half of its random instances.
fn rarely(r: &Row) -> bool {
    r.stats
        .as_ref()
        .is_some_and(|s| 2 * s.random_solved < N_RANDOM)
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
        "- analysis failed (a malformed plan): {}",
        count(&|x| matches!(x, Outcome::Failed(_)))
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
        "- checked entries that solve fewer than half of their random instances: {}",
        rows.iter().filter(|r| rarely(r)).count()
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
    let wrong_entries = rows.iter().filter(|r| r.wrong() > 0).count();
    let known = rows
        .iter()
        .filter(|r| r.wrong() > 0 && r.unexpected() == 0)
        .count();
    let _ = writeln!(
        o,
        "- entries with a wrong run (or a failed analysis): {wrong_entries}, all of whose wrong runs the test's KNOWN_WRONG lists: {known}"
    );
    let inc: usize = stats.iter().map(|s| s.inconsistent).sum();
    let refused: usize = stats.iter().map(|s| s.inconsistent_refused).sum();
    let accepted: usize = stats.iter().map(|s| s.inconsistent_accepted.len()).sum();
    let _ = writeln!(
        o,
        "- inconsistent instances of check entries (reported, not asserted): {inc}; refused with an error: {refused}; accepted with the checked constraint violated: {accepted}"
    );
    o
}

fn report(rows: &[Row]) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# Plan fragment table and construction checker in space\n"
    );
    let _ = writeln!(
        o,
        "Generated by `compiler/tests/construction3d.rs` (`GCS_WRITE_FRAGMENTS=1 cargo test -p gcs-compiler --release --test construction3d`); do not edit.\n\
         Each entry probes one free geom `P` of a kind, brought into a state by a prefix of constraints with fixed geoms, \
         and one more constraint between a feature of `P` and a fixed geom. A body `P` has markers `m`, `n`, `k` and \
         points `a`, `b`, `c` (`c` on `m`'s z axis); the prefix holds `m` (and `k`, `b`). The outcome is what the analysis does for \
         that constraint; *before* and *after* are the signature (Kramer's `IR[...]`) and DOF of `P`'s cluster. \
         For every fragment and check, random solvable instances (and near-degenerate ones: tangent and nearly tangent \
         loci, nearly parallel axes, coincident markers, the sketch at the target, scales 1e-3 and 1e3) are solved on \
         every branch and verified independently (`verify`); see the test's header for the method. \
         The 2d table is `docs/FRAGMENTS.md`.\n"
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
                    if r.unexpected() == 0 {
                        t.push_str(" (known)");
                    }
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
         (on every branch) refused. One example for the first few entries.\n"
    );
    let mut examples = 0;
    for r in rows {
        if let Some(s) = &r.stats {
            let n: usize = s.unsolved.values().sum();
            if n > 0 {
                let _ = writeln!(
                    o,
                    "- {} {} ({}), `{}`: {n} of {} {:?}, by mode {:?}",
                    r.id,
                    r.kind.name(),
                    r.state,
                    r.form,
                    s.instances,
                    s.unsolved,
                    s.unsolved_modes
                );
                if examples < 5 {
                    if let Some(ex) = &s.unsolved_example {
                        examples += 1;
                        let _ = writeln!(o, "  - {}", ex.replace('\n', "\n    "));
                    }
                }
            }
        }
    }
    let _ = writeln!(o, "\n## Entries that rarely solve\n");
    let _ = writeln!(
        o,
        "Fragment and check entries whose plan solves fewer than half of their {N_RANDOM} random instances \
         (each solvable by construction): not wrong, but a construction that rarely applies.\n"
    );
    for r in rows.iter().filter(|r| rarely(r)) {
        if let Some(s) = &r.stats {
            let _ = writeln!(
                o,
                "- {} `{}`: {} of {N_RANDOM} random instances solved; not solved: {:?}",
                r.id, r.key, s.random_solved, s.unsolved
            );
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
                let w = if none {
                    w.clone()
                } else {
                    w.split("\n```").next().unwrap_or("").to_string()
                };
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
    // By known cause: its entries, and the first wrong run of the first with its model.
    for (i, k) in KNOWN_WRONG.iter().enumerate() {
        any = true;
        let _ = writeln!(o, "### Known cause {}\n\n{}\n", i + 1, k.why);
        let _ = writeln!(o, "Modes: {}.\n", k.modes.join(", "));
        let mut example = None;
        for r in rows.iter().filter(|r| k.entries.contains(&r.key.as_str())) {
            let runs: Vec<&(f64, String, String)> = (r.stats.iter())
                .flat_map(|s| &s.wrong)
                .filter(|w| k.modes.contains(&w.1.as_str()))
                .collect();
            let worst = runs.iter().map(|w| w.0).fold(0.0, f64::max);
            if let Outcome::Failed(why) = &r.class.outcome {
                let _ = writeln!(o, "- {} `{}`: analysis failed: {why}", r.id, r.key);
            } else {
                let _ = writeln!(
                    o,
                    "- {} `{}`: {} wrong runs, worst relative residual {worst:.1e}",
                    r.id,
                    r.key,
                    runs.len()
                );
            }
            if example.is_none() {
                example = runs.first().map(|w| w.2.clone());
            }
        }
        if let Some(w) = example {
            let _ = writeln!(o, "\nFirst wrong run: {w}");
        }
        let _ = writeln!(o);
    }
    // Wrong runs no known cause lists, each with its model.
    let mut first = true;
    for r in rows.iter().filter(|r| r.unexpected() > 0) {
        if first {
            let _ = writeln!(o, "### Not in KNOWN_WRONG\n");
            first = false;
        }
        any = true;
        if let Outcome::Failed(why) = &r.class.outcome {
            let _ = writeln!(o, "- {} `{}`: analysis failed: {why}", r.id, r.key);
        }
        for (rel, mode, w) in r.stats.iter().flat_map(|s| &s.wrong) {
            if r.known(mode) {
                continue;
            }
            let class = if *rel <= 1e-9 {
                "precision (relative residual at most 1e-9)"
            } else {
                "wrong result"
            };
            let _ = writeln!(o, "- `{}` [{mode}], {class}: {w}", r.key);
        }
    }
    if !any {
        let _ = writeln!(o, "None: every solved instance verifies.");
    }
    o
}

/// Debugging aid: `GCS_PROBE=model.gcs cargo test -p gcs-compiler --release --test
/// construction3d -- --nocapture` prints the plan of one model and its solve on every branch.
fn probe() {
    let path = std::env::var("GCS_PROBE").expect("GCS_PROBE=model.gcs");
    let text = std::fs::read_to_string(path).expect("read");
    show(&text);
}

fn show(text: &str) {
    let model = load(text);
    let a = match analyse(&model) {
        Ok(a) => a,
        Err(e) => {
            println!("analysis failed: {e}");
            return;
        }
    };
    println!("{}", a.plan.dump(&model));
    println!("unsolved: {:?}", a.unsolved);
    println!("record of P: {}", record_of(&model, &a));
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    for combo in combos(&counts, &defaults) {
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

/// Debugging aid: `GCS_ENTRY=n GCS_INSTANCE=i cargo test -p gcs-compiler --release --test
/// construction3d -- --nocapture` prints instance `i` of entry `n` (0: the canonical one) and
/// its plan.
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
        i if i <= N_RANDOM => Mode::Random,
        i if i >= 1000 => Mode::Inconsistent,
        i => DEGENERATE[i - 1 - N_RANDOM],
    };
    let inst = make(e, ((n as u64) << 32) | i as u64, mode);
    println!("{}: {}\n{}", e.key(), mode.name(), inst.text);
    show(&inst.text);
}

// ---------------------------------------------------------------- default fragments

/// What the analysis does with the freedom a state leaves (000, section 5.2.1): the defaults it
/// adds for `P`, probed on the prefix alone.
struct DefaultRow {
    kind: Kind,
    state: &'static str,
    before: String,
    dof: usize,
    defaults: Vec<String>,
    refused: bool,
    still: (usize, usize),
    moved: (usize, usize),
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
/// lengths (angles absolute; a joint's, which mixes both, relative).
fn worst_residual(model: &Model, s: &gcs_compiler::solution::Solution, scale: f64) -> f64 {
    let params = model.default_params();
    (gcs_compiler::verify::residuals(model, s, &params).iter())
        .map(|r| {
            if r.value.is_nan() {
                f64::INFINITY
            } else if angular(model.constraints[r.constraint].kind) {
                r.value
            } else {
                r.value / scale.max(1.0)
            }
        })
        .fold(0.0, f64::max)
}

/// Whether default `name` is an angle (a turn, a spin, a place on a circle counts as one).
fn angle_default(name: &str) -> bool {
    name.ends_with("_angle") || name.ends_with("_spin") || name.contains("_turn_")
}

fn default_row(kind: Kind, state: &State, last: Form, n: usize) -> DefaultRow {
    let entry = Entry {
        kind,
        state: state.name,
        prefix: state.prefix.clone(),
        last,
    };
    let canonical = make(&entry, (n as u64) << 40, Mode::Random);
    let model = load(&canonical.prefix_text);
    let a = analyse(&model).expect("the prefix analysed");
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
            let a = analyse(&model).expect("the prefix analysed");
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
                    "seed {seed} ({}): a constraint off by {worst:e} at the sketch's defaults\n```gcs\n{}```",
                    mode.name(),
                    inst.prefix_text
                ));
                continue;
            }
            if mode == Mode::Exact {
                row.still.1 += 1;
                let sketch = gcs_compiler::solution::Solution::of_sketch(&model, &params, &scope)
                    .expect("a finite sketch");
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
                given[k] += if angle_default(&d.name) {
                    0.25
                } else {
                    0.25 * scale
                };
                let Ok(s) = solve(&given) else {
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

fn default_rows() -> Vec<DefaultRow> {
    let mut states = Vec::new();
    for kind in KINDS {
        let (list, forms) = catalogue(kind);
        for s in list {
            states.push((kind, s, forms[0]));
        }
    }
    parallel_map(&states, |i, (kind, s, f)| default_row(*kind, s, *f, i + 1))
}

fn defaults_report(rows: &[DefaultRow]) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "\n## Defaults\n");
    let _ = writeln!(
        o,
        "Each state's prefix alone, with the freedom it leaves `P`: the defaults the analysis adds \
         (000, section 5.2.1; `compiler/src/analysis/spatial/mod.rs`). Checked on instances \
         whose sketch already satisfies the prefix (*still*: solved at the sketch's defaults, \
         `P` must not move: least motion) and on random ones (*moved*: at the sketch's defaults \
         and with each default moved by 0.25 rad or 0.25 of the size, every constraint must hold \
         to 1e-12 relative and the moved default must move `P`). *Refused*: the analysis leaves \
         the freedom unparameterized, and `gcs check` reports it.\n"
    );
    let total = rows.len();
    let with = rows.iter().filter(|r| !r.defaults.is_empty()).count();
    let refused = rows.iter().filter(|r| r.refused).count();
    let fixed = (rows.iter())
        .filter(|r| !r.refused && r.defaults.is_empty())
        .count();
    let overstated = (rows.iter())
        .filter(|r| !r.refused && r.defaults.len() != r.dof)
        .count();
    let wrong: usize = rows.iter().map(|r| r.wrong.len()).sum();
    let _ = writeln!(
        o,
        "- states: {total}; with defaults: {with}; fully fixed by their prefix: {fixed}; refused: {refused}"
    );
    let _ = writeln!(
        o,
        "- states whose defaults are not as many as `P`'s DOF left: {overstated} (fewer: a relation pending when the first default is taken, and solved after it, which the record's DOF does not count)"
    );
    let _ = writeln!(o, "- wrong runs: {wrong}\n");
    let _ = writeln!(o, "| kind | state | before | defaults | still | moved |");
    let _ = writeln!(o, "|---|---|---|---|---:|---:|");
    for r in rows {
        let defaults = if r.refused {
            if r.defaults.is_empty() {
                "refused".to_string()
            } else {
                format!(
                    "refused (after {})",
                    r.defaults
                        .iter()
                        .map(|d| format!("`{d}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
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
