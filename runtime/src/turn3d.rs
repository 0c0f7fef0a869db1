//! Bodies turning about known axes: the angles that bring a point on a turning body onto a
//! known locus (the loci of markers on bodies with rotational freedom, paper 003), and the
//! subproblems a robot arm's inverse kinematics decomposes into (IK-Geo's SP1 to SP6, Elias and
//! Wen, arXiv 2211.05737), each in closed form with every real root.
//!
//! # Conventions
//!
//! - **An axis** is a [`Line3`]: its `point` is the pivot, its `dir` the unit direction (as
//!   [`Line3::new`] normalises it; a zero direction is degenerate). A turn by `θ` about it is
//!   the rigid rotation that keeps the line fixed and turns every point **counter-clockwise by
//!   `θ` seen from the tip of `dir`** ([`turn_point`]). Every angle returned is in `[-π, π]`,
//!   and is measured from the pose given: `θ = 0` leaves a point where it is.
//! - **Results** are [`Intersection`]s: the angles in a fixed-capacity [`crate::Roots`] (slot
//!   `i` is branch `i`), with a [`Contact`]: `Crossing` (transversal roots),
//!   `Tangent` (a double root, returned in each slot it merges, so that a branch stays defined
//!   through the tangency), `Disjoint { gap }` (no root; `gap` is how far the point misses,
//!   in length units), `ZeroRadius` (degenerate: a zero axis, or the point on its axis, whose
//!   turn then moves nothing), `Coincident` (every angle, or a continuum, is a solution; none
//!   returned), `Parallel { gap }` (the point's orbit lies in a plane parallel to the target
//!   and apart). Non-finite input gives no roots and `Disjoint { gap: NaN }`.
//! - **Tangency** follows [`crate::intersect3d`]: a point whose orbit misses its target by at
//!   most `TANGENT_REL * scale` touches it (one double root); any overlap, however small,
//!   crosses in exact roots that merge continuously into the touching turn. The two-angle
//!   problems ([`three_circles`], [`four_terms`]) reduce to a quartic: a double root is one
//!   that [`crate::poly`] finds multiple within rounding, or a pair that rounding made complex
//!   where the equations miss a solution by at most `4 TANGENT_REL` times their scale (they sum
//!   eight rounded terms, see [`four_terms`]); it is returned at the quartic's
//!   critical point, to about the square root of rounding, as double roots are.
//! - **Branches** are numbered by a geometric order stated on each function. One-angle
//!   problems order their two roots by the side of a reference direction fixed by the inputs
//!   (counter-clockwise or clockwise from the orbit's point nearest the target), as the
//!   intersections they are built on do. The quartic problems order their (up to four)
//!   solutions by their first angle, ascending in `(-π, π]`: slot `i` is the `i`-th solution
//!   counter-clockwise from the half-turn away from the pose given. A quartic's roots have no
//!   finer continuous labelling: the index of a solution changes where two solutions merge (a
//!   tangency) or one passes the half-turn.
//!
//! # The subproblems in words
//!
//! - [`turn_onto_point`] (SP1): the angle that turns `p` onto `q`; with [`nearest_turn`], the
//!   least-squares angle and its miss when `q` is off `p`'s orbit.
//! - [`turn_to_distance`] (SP3): the angles that bring `p` to a distance from `q` (onto a
//!   sphere). [`turn_onto_plane`] (SP4): onto a plane. [`turn_onto_line`]: onto a line.
//! - [`turns_meeting`] (SP2): two bodies turning about two known axes, one carrying `p`, the
//!   other `q`: the two angles at which the two points meet (equivalently, a body turning about
//!   an axis carried by a body turning about another, bringing a point onto a known point).
//! - [`three_circles`] (SP5): a point on a body turning about one axis meets a point carried by
//!   two turns in series about two more: three angles, a quartic.
//! - [`four_terms`] (SP6): two angles, each turning two points, whose heights along given
//!   directions add to two given values: a quartic. [`planar_chain_ends`] writes a planar
//!   sub-chain between two bodies turning about known axes as one.
//!
//! Nothing here allocates or panics.

use nalgebra::{Point3, Vector3};

use crate::intersect3d::{circle_circle, circle_plane, circle_sphere, line_circle};
use crate::locus3d::{Circle3, Line3, Plane, Sphere};
use crate::num::{is_finite, sin_cos};
use crate::poly::{self, RealRoot};
use crate::roots::{Contact, Intersection, Roots};
use crate::tol::{self, ANGLE, LENGTH_REL, TANGENT_REL};

// ---------------------------------------------------------------------------------------------
// Helpers.

#[inline]
fn finite(values: &[f64]) -> bool {
    values.iter().all(|&v| is_finite(v))
}

#[inline]
fn finite_point(p: &Point3<f64>) -> bool {
    finite(&[p.x, p.y, p.z])
}

#[inline]
fn finite_vector(v: &Vector3<f64>) -> bool {
    finite(&[v.x, v.y, v.z])
}

#[inline]
fn finite_axis(axis: &Line3) -> bool {
    finite_point(&axis.point) && finite_vector(&axis.dir)
}

#[inline]
fn abs_max(v: &Vector3<f64>) -> f64 {
    v.x.abs().max(v.y.abs()).max(v.z.abs())
}

/// Whether a (nominally unit) direction is zero or NaN.
#[inline]
fn is_zero_dir(v: &Vector3<f64>) -> bool {
    let n = v.norm_squared();
    n.is_nan() || n < 0.25
}

#[inline]
fn not_finite<T: Copy + Default, const N: usize>() -> Intersection<T, N> {
    Intersection::none(Contact::Disjoint { gap: f64::NAN })
}

/// An angle brought into `(-π, π]`.
#[inline]
fn wrap(t: f64) -> f64 {
    crate::num::wrap_angle(t)
}

/// The offset of `p` from the axis, across it: the radius vector of its orbit.
#[inline]
fn across(axis: &Line3, p: &Point3<f64>) -> Vector3<f64> {
    let w = p - axis.point;
    w - axis.dir * axis.dir.dot(&w)
}

/// The counter-clockwise angle about the unit `k` from the across-offset `from` to the
/// direction of `to` (projected across `k`).
#[inline]
fn angle_about(k: &Vector3<f64>, from: &Vector3<f64>, to: &Vector3<f64>) -> f64 {
    let to = to - k * k.dot(to);
    k.dot(&from.cross(&to)).atan2(from.dot(&to))
}

/// The point `p` turned by `angle` counter-clockwise about `axis` (seen from the tip of its
/// unit direction), by Rodrigues' formula with [`sin_cos`]. A zero axis leaves `p` in place.
#[inline]
pub fn turn_point(axis: &Line3, angle: f64, p: &Point3<f64>) -> Point3<f64> {
    let k = axis.dir;
    let w = p - axis.point;
    let along = k * k.dot(&w);
    let r = w - along;
    let (s, c) = sin_cos(angle);
    axis.point + along + r * c + k.cross(&r) * s
}

/// `k + c cos θ + s sin θ`: the height, along a direction, of a point turning by `θ`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Harmonic {
    k: f64,
    c: f64,
    s: f64,
}

impl Harmonic {
    /// `h · turn(axis, θ, p)`.
    #[inline]
    fn of(axis: &Line3, p: &Point3<f64>, h: &Vector3<f64>) -> Self {
        let k = axis.dir;
        let w = p - axis.point;
        let along = k * k.dot(&w);
        let r = w - along;
        Self {
            k: h.dot(&(axis.point.coords + along)),
            c: h.dot(&r),
            s: h.dot(&k.cross(&r)),
        }
    }

    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            k: self.k + o.k,
            c: self.c + o.c,
            s: self.s + o.s,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One angle.

/// The least-squares turn of [`nearest_turn`]: the angle and how far the turned point misses.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Nearest {
    /// The angle, in `(-π, π]`, that brings the point nearest its target.
    pub angle: f64,
    /// The distance left between the turned point and its target: zero exactly when the target
    /// is on the point's orbit.
    pub miss: f64,
}

/// SP1, least squares: the angle about `axis` that brings `p` nearest `q`, and the distance
/// left (`sqrt(h² + (ρp - ρq)²)`, with `h` the difference of their heights along the axis and
/// `ρ` their distances from it).
///
/// `None` when the angle is undefined: a zero axis, `p` or `q` on the axis (within
/// `LENGTH_REL * scale`), or non-finite input.
pub fn nearest_turn(axis: &Line3, p: &Point3<f64>, q: &Point3<f64>) -> Option<Nearest> {
    if !(finite_axis(axis) && finite_point(p) && finite_point(q)) || is_zero_dir(&axis.dir) {
        return None;
    }
    let k = axis.dir;
    let sc = tol::scale(&[
        abs_max(&axis.point.coords),
        abs_max(&p.coords),
        abs_max(&q.coords),
    ]);
    let (rp, rq) = (across(axis, p), across(axis, q));
    let (np, nq) = (rp.norm(), rq.norm());
    if np <= LENGTH_REL * sc || nq <= LENGTH_REL * sc {
        return None;
    }
    let h = k.dot(&(q - p));
    Some(Nearest {
        angle: angle_about(&k, &rp, &rq),
        miss: h.hypot(np - nq),
    })
}

/// SP1: the angle about `axis` that turns `p` onto `q`.
///
/// - **Branch:** a single root (branch 0), the least-squares angle of [`nearest_turn`].
/// - `Crossing`: `q` is on `p`'s orbit, missing it by at most `TANGENT_REL * scale` (the
///   largest coordinate of the pivot, `p` and `q`); the turned point is then within that of `q`.
/// - `Disjoint { gap }`: `q` is off the orbit by `gap` ([`Nearest::miss`]), or `q` is on the
///   axis and `p` is not (`gap` the orbit's radius plus the heights' difference, hypot).
/// - `ZeroRadius`: a zero axis, or `p` on the axis (it does not move): the caller compares `p`
///   with `q`.
pub fn turn_onto_point(axis: &Line3, p: &Point3<f64>, q: &Point3<f64>) -> Intersection<f64, 1> {
    if !(finite_axis(axis) && finite_point(p) && finite_point(q)) {
        return not_finite();
    }
    if is_zero_dir(&axis.dir) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sc = tol::scale(&[
        abs_max(&axis.point.coords),
        abs_max(&p.coords),
        abs_max(&q.coords),
    ]);
    let rp = across(axis, p);
    if rp.norm() <= LENGTH_REL * sc {
        return Intersection::none(Contact::ZeroRadius);
    }
    match nearest_turn(axis, p, q) {
        Some(n) if n.miss <= TANGENT_REL * sc => Intersection {
            roots: Roots::from_slice(&[n.angle]),
            contact: Contact::Crossing,
        },
        Some(n) => Intersection::none(Contact::Disjoint { gap: n.miss }),
        None => {
            let h = axis.dir.dot(&(q - p));
            Intersection::none(Contact::Disjoint {
                gap: h.hypot(rp.norm()),
            })
        }
    }
}

/// The angles of two root points on `p`'s orbit about `axis`.
fn angles_of(
    axis: &Line3,
    p: &Point3<f64>,
    i: Intersection<Point3<f64>, 2>,
) -> Intersection<f64, 2> {
    let rp = across(axis, p);
    let mut roots = Roots::new();
    for x in i.roots.as_slice() {
        roots.push(angle_about(&axis.dir, &rp, &(x - axis.point)));
    }
    Intersection {
        roots,
        contact: i.contact,
    }
}

/// The orbit of `p` about `axis`, or the contact that refuses it: non-finite input, a zero
/// axis, `p` on the axis.
fn orbit(axis: &Line3, p: &Point3<f64>, others: &[f64]) -> Result<Circle3, Contact> {
    if !(finite_axis(axis) && finite_point(p) && finite(others)) {
        return Err(Contact::Disjoint { gap: f64::NAN });
    }
    if is_zero_dir(&axis.dir) {
        return Err(Contact::ZeroRadius);
    }
    let mut vals = [0.0; 8];
    vals[0] = abs_max(&axis.point.coords);
    vals[1] = abs_max(&p.coords);
    for (v, o) in vals[2..].iter_mut().zip(others) {
        *v = *o;
    }
    let sc = tol::scale(&vals);
    let c = Circle3::orbit(&axis.point, &axis.dir, p);
    if c.radius <= LENGTH_REL * sc {
        return Err(Contact::ZeroRadius);
    }
    Ok(c)
}

/// SP3: the angles about `axis` that bring `p` to the distance `d` from `q` (onto the sphere
/// about `q` of radius `d`).
///
/// - **Branch:** with `e` the point of `p`'s orbit nearest `q`, branch 0 turns `p` to the
///   sphere counter-clockwise past `e` (about the axis's direction), branch 1 clockwise past
///   it: the angles are `θe + α` and `θe - α`, `α` in `[0, π]`.
/// - `Crossing`: two angles, whenever `d` lies strictly between the distances from `q` to the
///   orbit's nearest and farthest points, however close to either. `Tangent`: `d` is outside
///   that range by at most `TANGENT_REL * scale`: the double root (the nearest or farthest
///   point's angle) in both slots.
/// - `Disjoint { gap }`: `d` is outside that range by `gap`, or `q` is on the axis and `d` is
///   not its distance to the orbit (`gap` the difference).
/// - `Coincident`: `q` on the axis at the orbit's distance (every angle). `ZeroRadius`: a zero
///   axis, `p` on the axis, or `d` at most `LENGTH_REL * scale` (use [`turn_onto_point`]).
///
/// Built on [`circle_sphere`], whose tolerances and accuracy it has.
pub fn turn_to_distance(
    axis: &Line3,
    p: &Point3<f64>,
    q: &Point3<f64>,
    d: f64,
) -> Intersection<f64, 2> {
    let c = match orbit(axis, p, &[q.x, q.y, q.z, d]) {
        Ok(c) => c,
        Err(contact) => return Intersection::none(contact),
    };
    angles_of(axis, p, circle_sphere(&c, &Sphere::new(*q, d)))
}

/// SP4: the angles about `axis` that bring `p` onto `plane`.
///
/// - **Branch:** with `e` the point of `p`'s orbit highest along the plane's normal, branch 0
///   turns `p` to the plane clockwise from `e` (about the axis's direction), branch 1
///   counter-clockwise: the angles are `θe - α` and `θe + α`, `α` in `[0, π]` (the order of
///   [`circle_plane`], along `axis × normal`).
/// - `Crossing`: two angles whenever the plane cuts the orbit, however little. `Tangent`: it
///   misses by at most `TANGENT_REL * scale`: the double root in both slots.
/// - `Disjoint { gap }`: the plane misses the orbit by `gap`.
/// - `Parallel { gap }`: the axis is along the plane's normal and the orbit `gap` off the
///   plane. `Coincident`: the orbit lies in the plane (every angle).
/// - `ZeroRadius`: a zero axis or normal, or `p` on the axis.
///
/// Built on [`circle_plane`], whose tolerances and accuracy it has.
pub fn turn_onto_plane(axis: &Line3, p: &Point3<f64>, plane: &Plane) -> Intersection<f64, 2> {
    let n = plane.normal;
    let c = match orbit(axis, p, &[plane.offset, n.x, n.y, n.z]) {
        Ok(c) => c,
        Err(contact) => return Intersection::none(contact),
    };
    angles_of(axis, p, circle_plane(&c, plane))
}

/// The angles about `axis` that bring `p` onto `line`.
///
/// - A line in the plane of `p`'s orbit (within the tangency tolerance): the angles at which
///   the orbit meets it, branch `i` in the order along the line's direction ([`line_circle`]),
///   `Crossing` or `Tangent` as it cuts or touches the orbit.
/// - A line across that plane meets it at one point: the one angle that reaches it, in both
///   slots, when that point is on the orbit to the tangency tolerance (over the sine of the
///   line's angle with the plane), with [`line_circle`]'s `Tangent`; `Disjoint { gap }`
///   (`gap` that point's distance from the orbit) otherwise.
/// - `Parallel { gap }`: the line is parallel to the orbit's plane, `gap` off it.
/// - `ZeroRadius`: a zero axis, `p` on the axis, or a zero line direction.
pub fn turn_onto_line(axis: &Line3, p: &Point3<f64>, line: &Line3) -> Intersection<f64, 2> {
    let (lp, ld) = (line.point, line.dir);
    let c = match orbit(axis, p, &[lp.x, lp.y, lp.z, ld.x, ld.y, ld.z]) {
        Ok(c) => c,
        Err(contact) => return Intersection::none(contact),
    };
    if is_zero_dir(&ld) {
        return Intersection::none(Contact::ZeroRadius);
    }
    angles_of(axis, p, line_circle(line, &c))
}

// ---------------------------------------------------------------------------------------------
// Two axes.

/// SP2: the angles `[θ1, θ2]` at which `p`, turning about `first`, and `q`, turning about
/// `second`, meet: `turn(first, θ1, p) = turn(second, θ2, q)`. The meeting point is where the
/// two orbits meet ([`circle_circle`] of the orbit of `p` about `first` and of `q` about
/// `second`). Read as one body turning about an axis carried by another, it is the turn `θ1`
/// of the carrier about `first` and `-θ2` of the carried body about `second` (in the carrier's
/// pose at `θ1 = 0`) that take `q` onto `p`.
///
/// Each crossing's angles are polished by Gauss-Newton steps on the turned points' miss.
///
/// - **Branch**, intersecting axes (not parallel, passing within `TANGENT_REL * scale` of each
///   other; IK-Geo's case, which generally meets in two points): the orbits lie on spheres
///   about the axes' meeting point `o`, which must be one, and the meeting points are where the
///   line common to the orbits' planes crosses it, in closed form. Branch 0 is the meeting
///   point on the negative side of the plane of the axes (oriented by
///   `first.dir × second.dir`), branch 1 on the positive side. `Crossing` whenever the line
///   cuts the sphere, however little; `Tangent` when it does not and the orbits are at most
///   `TANGENT_REL * scale` apart (the double root, midway between the line's point nearest
///   `o` and the sphere, in both slots). `Disjoint { gap }`: the spheres' radii
///   differ by `gap` (`|p - o|` against `|q - o|`, more than the tolerance), or the orbits on
///   the sphere are `gap` apart (the chord of the angle by which they miss).
/// - **Branch**, skew axes (the orbits in different planes, which meet only by construction):
///   order of the meeting points along `first.dir × second.dir`, branch 0 first, from
///   [`circle_circle`]. A single meeting point fills both slots (`Tangent` when an orbit
///   touches the other's plane there, `Crossing` when the orbits pass through each other's
///   plane).
/// - **Branch**, parallel axes with the orbits in one plane: branch 0 is the meeting point left
///   of the line from the first orbit's centre to the second's (seen from the tip of `first`'s
///   direction), branch 1 right of it; `Crossing`, or `Tangent` with the double root in both.
/// - `Disjoint { gap }`, skew or parallel axes: the orbits miss ([`circle_circle`]'s gap: across planes, a distance
///   between actual points of the two orbits, an upper bound of their distance). `Parallel {
///   gap }`: parallel axes, the orbits' planes `gap` apart. `Coincident`: the same orbit (every
///   `θ1` has a `θ2`). `ZeroRadius`: a zero axis, or `p` or `q` on its axis.
///
/// With skew or parallel axes, tolerances and accuracy are [`circle_circle`]'s: a meeting of
/// orbits in different planes is decided with `TANGENT_REL * scale` both ways.
pub fn turns_meeting(
    first: &Line3,
    p: &Point3<f64>,
    second: &Line3,
    q: &Point3<f64>,
) -> Intersection<[f64; 2], 2> {
    let (sp, sd) = (second.point, second.dir);
    let c1 = match orbit(first, p, &[sp.x, sp.y, sp.z, sd.x, sd.y, sd.z]) {
        Ok(c) => c,
        Err(contact) => return Intersection::none(contact),
    };
    let c2 = match orbit(second, q, &[q.x, q.y, q.z]) {
        Ok(c) => c,
        Err(contact) => return Intersection::none(contact),
    };
    let i = match axes_meeting(first, second, &[p, q]) {
        Some(o) => on_one_sphere(first, p, second, q, &o),
        None => circle_circle(&c1, &c2),
    };
    let (r1, r2) = (across(first, p), across(second, q));
    let mut roots = Roots::new();
    for x in i.roots.as_slice() {
        let t = [
            angle_about(&first.dir, &r1, &(x - first.point)),
            angle_about(&second.dir, &r2, &(x - second.point)),
        ];
        roots.push(if i.contact == Contact::Crossing {
            polish_meeting(first, p, second, q, t)
        } else {
            t
        });
    }
    Intersection {
        roots,
        contact: i.contact,
    }
}

/// Gauss-Newton steps (at most [`POLISH_STEPS`]) on the miss `turn(first, θ1, p) -
/// turn(second, θ2, q)` from `t`, each kept only while it lowers the miss: the meeting point
/// found from the orbits carries their construction's rounding, which the angles need not.
fn polish_meeting(
    first: &Line3,
    p: &Point3<f64>,
    second: &Line3,
    q: &Point3<f64>,
    mut t: [f64; 2],
) -> [f64; 2] {
    let miss = |t: [f64; 2]| turn_point(first, t[0], p) - turn_point(second, t[1], q);
    let mut r = miss(t);
    for _ in 0..POLISH_STEPS {
        let j1 = first.dir.cross(&(turn_point(first, t[0], p) - first.point));
        let j2 = -second
            .dir
            .cross(&(turn_point(second, t[1], q) - second.point));
        // The normal equations of the 3x2 system.
        let (a, b, c) = (j1.dot(&j1), j1.dot(&j2), j2.dot(&j2));
        let (g1, g2) = (j1.dot(&r), j2.dot(&r));
        let det = a.mul_add(c, -(b * b));
        if det == 0.0 || det.is_nan() {
            break;
        }
        let next = [
            t[0] - (c * g1 - b * g2) / det,
            t[1] - (a * g2 - b * g1) / det,
        ];
        let rn = miss(next);
        if rn.norm().partial_cmp(&r.norm()) != Some(std::cmp::Ordering::Less) {
            break;
        }
        t = [wrap(next[0]), wrap(next[1])];
        r = rn;
    }
    t
}

/// The point where two axes meet: they are not parallel (the sine of their angle above
/// [`tol::ANGLE`]) and pass within `TANGENT_REL * scale` of each other (the scale taking in
/// `points` too); the midpoint of their nearest points.
fn axes_meeting(a: &Line3, b: &Line3, points: &[&Point3<f64>]) -> Option<Point3<f64>> {
    let n = a.dir.cross(&b.dir);
    let sn = n.norm();
    if sn <= ANGLE {
        return None;
    }
    let mut sc = tol::scale(&[abs_max(&a.point.coords), abs_max(&b.point.coords)]);
    for p in points {
        sc = sc.max(abs_max(&p.coords));
    }
    let w = b.point - a.point;
    if (w.dot(&n) / sn).abs() > TANGENT_REL * sc {
        return None;
    }
    let n2 = sn * sn;
    let ta = w.cross(&b.dir).dot(&n) / n2;
    let tb = w.cross(&a.dir).dot(&n) / n2;
    Some(a.at(ta) + (b.at(tb) - a.at(ta)) * 0.5)
}

/// Where the orbits of `p` about `first` and of `q` about `second`, axes meeting at `o`, meet:
/// both lie on spheres about `o`, which must be one (their radii within the tangency
/// tolerance), and in planes across the axes, whose common line meets that sphere in the
/// points sought. Branch 0 is on the negative side of `first.dir × second.dir`.
fn on_one_sphere(
    first: &Line3,
    p: &Point3<f64>,
    second: &Line3,
    q: &Point3<f64>,
    o: &Point3<f64>,
) -> Intersection<Point3<f64>, 2> {
    let (k1, k2) = (first.dir, second.dir);
    let sc = tol::scale(&[
        abs_max(&first.point.coords),
        abs_max(&second.point.coords),
        abs_max(&p.coords),
        abs_max(&q.coords),
    ]);
    let tt = TANGENT_REL * sc;
    let (u, v) = (p - o, q - o);
    let (ru, rv) = (u.norm(), v.norm());
    if (ru - rv).abs() > tt {
        return Intersection::none(Contact::Disjoint {
            gap: (ru - rv).abs(),
        });
    }
    let r = 0.5 * (ru + rv);
    // The line common to the planes: `x = α k1 + β k2 + γ n` with `k1 · x = k1 · u` and
    // `k2 · x = k2 · v`.
    let n = k1.cross(&k2);
    let n2 = n.norm_squared();
    let c = k1.dot(&k2);
    let (a1, a2) = (k1.dot(&u), k2.dot(&v));
    let alpha = (a1 - c * a2) / n2;
    let beta = (a2 - c * a1) / n2;
    let foot = k1 * alpha + k2 * beta;
    let m = foot.norm();
    let g = m - r;
    if g >= 0.0 {
        // The distance between the orbits: the chord of the angle by which they miss on the
        // sphere (apart, one within the other, or past each other's far side), from their
        // angular radii `a1`, `a2` and the axes' angle `gamma`.
        let ang = |k: &Vector3<f64>, w: &Vector3<f64>| k.cross(w).norm().atan2(k.dot(w));
        let (a1, a2, gamma) = (ang(&k1, &u), ang(&k2, &v), n.norm().atan2(c));
        let apart = (gamma - a1 - a2)
            .max((a1 - a2).abs() - gamma)
            .max(a1 + a2 + gamma - std::f64::consts::TAU);
        let chord = 2.0 * r * (0.5 * apart).sin();
        if chord > tt {
            return Intersection::none(Contact::Disjoint { gap: chord });
        }
    }
    let nh = n / n2.sqrt();
    if g >= 0.0 {
        // Touching: midway between the line's point nearest `o` and the sphere.
        let t = if m > 0.0 {
            o + foot * (0.5 * (1.0 + r / m))
        } else {
            o + foot
        };
        return Intersection {
            roots: Roots::from_slice(&[t, t]),
            contact: Contact::Tangent,
        };
    }
    let h = ((r - m) * (r + m)).sqrt();
    Intersection {
        roots: Roots::from_slice(&[o + foot - nh * h, o + foot + nh * h]),
        contact: Contact::Crossing,
    }
}

// ---------------------------------------------------------------------------------------------
// Two angles, two equations: the quartic.

/// Two equations in two angles, each linear in the cosine and sine of each:
/// `m1 · (cos θ1, sin θ1) + m2 · (cos θ2, sin θ2) = d` (rows the equations).
#[derive(Clone, Copy, Debug)]
struct System {
    m1: [[f64; 2]; 2],
    m2: [[f64; 2]; 2],
    d: [f64; 2],
    /// The magnitude of the equations' terms (their coefficients and the constants they were
    /// computed from), in the units of `d`: what a tangency's tolerance is relative to.
    scale: f64,
}

/// What [`System::solve`] finds.
enum Solved {
    /// The solutions `[θ1, θ2]`, ordered by `θ1`, each flagged when it is a double root.
    Roots(Roots<([f64; 2], bool), 4>),
    /// No real solution: the pair of angles nearest to one (at a critical point of the
    /// quartic).
    Miss([f64; 2]),
    /// Neither angle's matrix is invertible.
    Degenerate,
}

#[inline]
fn det2(m: &[[f64; 2]; 2]) -> f64 {
    m[0][0].mul_add(m[1][1], -(m[0][1] * m[1][0]))
}

#[inline]
fn frob2(m: &[[f64; 2]; 2]) -> f64 {
    m[0][0] * m[0][0] + m[0][1] * m[0][1] + m[1][0] * m[1][0] + m[1][1] * m[1][1]
}

/// How well a 2x2 matrix can be inverted: `|det| / |m|²` (Frobenius), in `[0, 1/2]`: about the
/// ratio of its singular values when small; zero for a zero matrix.
#[inline]
fn conditioning(m: &[[f64; 2]; 2]) -> f64 {
    let f = frob2(m);
    if f > 0.0 {
        det2(m).abs() / f
    } else {
        0.0
    }
}

/// `a0 + a1 cos φ + b1 sin φ + a2 cos 2φ + b2 sin 2φ`.
#[derive(Clone, Copy, Debug)]
struct Trig2 {
    a0: f64,
    a1: f64,
    b1: f64,
    a2: f64,
    b2: f64,
}

impl Trig2 {
    #[inline]
    fn at(&self, phi: f64) -> f64 {
        self.at_sin_cos(sin_cos(phi))
    }

    /// The value at the angle whose sine and cosine are `(s, c)`.
    #[inline]
    fn at_sin_cos(&self, (s, c): (f64, f64)) -> f64 {
        let (s2, c2) = (2.0 * s * c, (c - s) * (c + s));
        self.a0 + self.a1 * c + self.b1 * s + self.a2 * c2 + self.b2 * s2
    }

    /// The same function of `ψ = φ - shift`, the shift's sine and cosine `(s, c)`.
    #[inline]
    fn shifted(&self, (s, c): (f64, f64)) -> Self {
        let (s2, c2) = (2.0 * s * c, (c - s) * (c + s));
        Self {
            a0: self.a0,
            a1: self.a1 * c + self.b1 * s,
            b1: self.b1 * c - self.a1 * s,
            a2: self.a2 * c2 + self.b2 * s2,
            b2: self.b2 * c2 - self.a2 * s2,
        }
    }

    /// The quartic in `t = tan(φ / 2)` whose roots are this function's zeros (times
    /// `(1 + t²)²`), highest degree first. Its leading coefficient is the value at `φ = π`.
    #[inline]
    fn quartic(&self) -> [f64; 5] {
        let Self { a0, a1, b1, a2, b2 } = *self;
        [
            a0 - a1 + a2,
            2.0 * b1 - 4.0 * b2,
            2.0 * a0 - 6.0 * a2,
            2.0 * b1 + 4.0 * b2,
            a0 + a1 + a2,
        ]
    }
}

/// How many shifts of the half-angle substitution are tried: the one whose excluded angle
/// (`φ = π`, `t` infinite) has the largest value is kept, so that no root is near it.
const SHIFTS: usize = 8;

/// The sines and cosines of the [`SHIFTS`] shifts, `k π / 4`, exact where they are 0 or 1.
const SHIFT_SIN_COS: [(f64, f64); SHIFTS] = {
    const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
    [
        (0.0, 1.0),
        (H, H),
        (1.0, 0.0),
        (H, -H),
        (0.0, -1.0),
        (-H, -H),
        (-1.0, 0.0),
        (-H, H),
    ]
};

/// How many times the tangency's tolerance (`TANGENT_REL * scale`) the two equations may miss
/// a root of the quartic. Their values sum eight terms, each rounded (and each rounded again
/// by the steps that built the inputs), so a solution's values carry several times a single
/// locus's rounding: a pair of solutions that rounding made complex is one double root when
/// the equations miss it by at most this many tolerances. A simple root polishes to a few ulps
/// of the scale where the Jacobian is regular; one of a close pair at a fold, where it is
/// singular and Newton's method stalls, to a few tens (39 measured). A simple root missing by
/// more is no root: the quartic's coefficients cancelled (near a continuum of solutions), and
/// the problem is reported degenerate.
const QUARTIC_SLACK: f64 = 4.0;

/// At most this many Newton steps on the two equations polish each simple solution.
const POLISH_STEPS: usize = 3;

impl System {
    /// The residuals of both equations at `[θ1, θ2]`.
    #[inline]
    fn residual(&self, t: [f64; 2]) -> [f64; 2] {
        self.residual_at(sin_cos(t[0]), sin_cos(t[1]))
    }

    /// [`Self::residual`] from the angles' sines and cosines.
    #[inline]
    fn residual_at(&self, (s1, c1): (f64, f64), (s2, c2): (f64, f64)) -> [f64; 2] {
        let r = |i: usize| {
            self.m1[i][0] * c1 + self.m1[i][1] * s1 + self.m2[i][0] * c2 + self.m2[i][1] * s2
                - self.d[i]
        };
        [r(0), r(1)]
    }

    /// Swaps the roles of the two angles.
    #[inline]
    fn swapped(&self) -> Self {
        Self {
            m1: self.m2,
            m2: self.m1,
            ..*self
        }
    }

    /// Every real solution. The better invertible of the two matrices is eliminated: with
    /// `m1` invertible, `(cos θ1, sin θ1) = adj(m1) (d - m2 (cos θ2, sin θ2)) / det(m1)`, and
    /// that vector has unit length where `|adj(m1) r(θ2)|² - det(m1)² = 0`, a trigonometric
    /// polynomial of degree two in `θ2`: a quartic in the tangent of the half angle, with its
    /// excluded angle moved away from the roots. Each root gives one solution, polished by
    /// Newton's method on the two equations.
    fn solve(&self) -> Solved {
        let (q1, q2) = (conditioning(&self.m1), conditioning(&self.m2));
        if q1.max(q2) <= ANGLE {
            return Solved::Degenerate;
        }
        let (sys, swap) = if q1 >= q2 {
            (*self, false)
        } else {
            (self.swapped(), true)
        };
        let unswap = |t: [f64; 2]| if swap { [t[1], t[0]] } else { t };
        // Eliminate θ1 (of `sys`): w(θ2) = adj(m1) (d - m2 x2) = w0 + wc cos θ2 + ws sin θ2.
        let m = sys.m1;
        let adj = [[m[1][1], -m[0][1]], [-m[1][0], m[0][0]]];
        let det = det2(&m);
        let mul = |v: [f64; 2]| {
            [
                adj[0][0] * v[0] + adj[0][1] * v[1],
                adj[1][0] * v[0] + adj[1][1] * v[1],
            ]
        };
        let w0 = mul(sys.d);
        let wc = mul([-sys.m2[0][0], -sys.m2[1][0]]);
        let ws = mul([-sys.m2[0][1], -sys.m2[1][1]]);
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let (cc, ss) = (dot(wc, wc), dot(ws, ws));
        let f = Trig2 {
            a0: dot(w0, w0) + 0.5 * (cc + ss) - det * det,
            a1: 2.0 * dot(w0, wc),
            b1: 2.0 * dot(w0, ws),
            a2: 0.5 * (cc - ss),
            b2: dot(wc, ws),
        };
        if !finite(&[f.a0, f.a1, f.b1, f.a2, f.b2]) {
            return Solved::Degenerate;
        }
        let first_of = |t2: f64| {
            let (s, c) = sin_cos(t2);
            let w = [w0[0] + wc[0] * c + ws[0] * s, w0[1] + wc[1] * c + ws[1] * s];
            // `det` may be negative: `w / det` has the direction of `w * det`.
            (w[1] * det).atan2(w[0] * det)
        };
        // The shift whose excluded angle has the largest |f|.
        let mut chosen = 0;
        let mut best = -1.0;
        for (i, &(s, c)) in SHIFT_SIN_COS.iter().enumerate() {
            // At `shift + π`: the sine and cosine negated.
            let v = f.at_sin_cos((-s, -c)).abs();
            if v > best {
                best = v;
                chosen = i;
            }
        }
        let shift = std::f64::consts::TAU * (chosen as f64) / (SHIFTS as f64);
        let g = f.shifted(SHIFT_SIN_COS[chosen]);
        let coeffs = g.quartic();
        let (roots, critical) = poly::roots_and_critical(&coeffs);
        // A double root that rounding split into a complex pair: a critical point with no root
        // between its neighbours where the equations, at the angles it gives, miss by at most
        // `QUARTIC_SLACK * TANGENT_REL * scale`. The function's value there is first compared with what such a
        // miss makes of it (`|∂f/∂d| = 2 |w| |adj|`, with `|w| = |det|` at a root), allowing
        // for the rounding of the elimination, amplified by its conditioning.
        let q = q1.max(q2);
        let d_tol = QUARTIC_SLACK * TANGENT_REL * self.scale;
        let f_tol = 2.0 * det.abs() * frob2(&m).sqrt() * d_tol * (0.5 / q);
        let crit = critical.as_slice();
        let mut found: Roots<RealRoot, 4> = roots;
        for (i, c) in crit.iter().enumerate() {
            let lo = if i > 0 {
                crit[i - 1].x
            } else {
                f64::NEG_INFINITY
            };
            let hi = crit.get(i + 1).map_or(f64::INFINITY, |n| n.x);
            if roots.as_slice().iter().any(|r| r.x >= lo && r.x <= hi) {
                continue;
            }
            let phi = shift + 2.0 * c.x.atan();
            let missed = || {
                let t2 = wrap(phi);
                let r = sys.residual([first_of(t2), t2]);
                r[0].hypot(r[1])
            };
            if f.at(phi).abs() <= f_tol && missed() <= d_tol {
                found.push(RealRoot {
                    x: c.x,
                    multiple: true,
                });
            }
        }
        if found.is_empty() {
            // The nearest miss: the critical point of smallest |f|.
            let mut t2 = shift + std::f64::consts::PI;
            let mut least = best;
            for c in crit {
                let phi = shift + 2.0 * c.x.atan();
                let v = f.at(phi).abs();
                if v < least {
                    least = v;
                    t2 = phi;
                }
            }
            let t2 = wrap(t2);
            return Solved::Miss(unswap([first_of(t2), t2]));
        }
        let mut out: Roots<([f64; 2], bool), 4> = Roots::new();
        for &RealRoot { x, multiple } in found.as_slice() {
            let t2 = wrap(shift + 2.0 * x.atan());
            let mut t = [first_of(t2), t2];
            if !multiple {
                let (polished, r) = sys.polish(t);
                t = polished;
                // A root the equations miss by more than `QUARTIC_SLACK` tangency tolerances, even
                // polished, is the rounding of a quartic whose coefficients cancelled: near a
                // continuum of solutions, where the elimination cannot be trusted. Unless it is
                // one of a close pair at a fold (a critical point between it and a neighbour,
                // where the function is within rounding of zero), where Newton's method stalls
                // and the pair is kept as found if the equations miss it by at most
                // `QUARTIC_SLACK` times more.
                let (miss, stall) = (r[0].hypot(r[1]), QUARTIC_SLACK * d_tol);
                if miss.partial_cmp(&stall) != Some(std::cmp::Ordering::Less) {
                    return Solved::Degenerate;
                }
                let missed = miss.partial_cmp(&d_tol) != Some(std::cmp::Ordering::Less);
                if missed
                    && !close_pair(roots.as_slice(), x, crit, |c| {
                        f.at(shift + 2.0 * c.atan()).abs() <= f_tol
                    })
                {
                    return Solved::Degenerate;
                }
            }
            let t = unswap([wrap(t[0]), wrap(t[1])]);
            out.push((t, multiple));
            if multiple {
                out.push((t, true));
            }
        }
        sort_by_first(&mut out);
        Solved::Roots(out)
    }

    /// Newton's method on both equations from `t`, keeping a step only while it lowers the
    /// residual.
    fn polish(&self, mut t: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let norm2 = |r: [f64; 2]| r[0] * r[0] + r[1] * r[1];
        let (mut sc1, mut sc2) = (sin_cos(t[0]), sin_cos(t[1]));
        let mut r = self.residual_at(sc1, sc2);
        for _ in 0..POLISH_STEPS {
            let ((s1, c1), (s2, c2)) = (sc1, sc2);
            let j = |i: usize| {
                [
                    -self.m1[i][0] * s1 + self.m1[i][1] * c1,
                    -self.m2[i][0] * s2 + self.m2[i][1] * c2,
                ]
            };
            let (j0, j1) = (j(0), j(1));
            let det = j0[0].mul_add(j1[1], -(j0[1] * j1[0]));
            if det == 0.0 || det.is_nan() {
                break;
            }
            let d0 = (r[0] * j1[1] - r[1] * j0[1]) / det;
            let d1 = (j0[0] * r[1] - j1[0] * r[0]) / det;
            let next = [t[0] - d0, t[1] - d1];
            let (n1, n2) = (sin_cos(next[0]), sin_cos(next[1]));
            let rn = self.residual_at(n1, n2);
            if norm2(rn).partial_cmp(&norm2(r)) != Some(std::cmp::Ordering::Less) {
                break;
            }
            (t, r, sc1, sc2) = (next, rn, n1, n2);
        }
        (t, r)
    }
}

/// Whether the root `x` of `roots` (ascending) has a neighbour root with a critical point
/// strictly between them at which `small` holds: the two are a close pair.
fn close_pair(roots: &[RealRoot], x: f64, crit: &[RealRoot], small: impl Fn(f64) -> bool) -> bool {
    let Some(i) = roots.iter().position(|r| r.x == x) else {
        return false;
    };
    let between = |a: f64, b: f64| crit.iter().any(|c| c.x > a && c.x < b && small(c.x));
    let before = i > 0 && between(roots[i - 1].x, x);
    let after = roots.get(i + 1).is_some_and(|n| between(x, n.x));
    before || after
}

/// Sorts solutions by their first angle (then the second), ascending; a handful, by insertion.
fn sort_by_first<const N: usize, T>(roots: &mut Roots<(T, bool), N>)
where
    T: Copy + Default + AsRef<[f64]>,
{
    let mut items = [(T::default(), false); N];
    let n = roots.len();
    for (i, v) in roots.as_slice().iter().enumerate() {
        items[i] = *v;
    }
    for i in 1..n {
        let mut j = i;
        while j > 0 && less(items[j].0.as_ref(), items[j - 1].0.as_ref()) {
            items.swap(j, j - 1);
            j -= 1;
        }
    }
    *roots = Roots::from_slice(&items[..n]);
}

#[inline]
fn less(a: &[f64], b: &[f64]) -> bool {
    for (x, y) in a.iter().zip(b) {
        if x < y {
            return true;
        }
        if x > y {
            return false;
        }
    }
    false
}

/// The height, along `along`, of `point` turning about `axis`: one term of [`four_terms`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Term {
    /// The axis the point turns about (its pivot and unit direction).
    pub axis: Line3,
    /// The point, in the pose where the term's angle is zero.
    pub point: Point3<f64>,
    /// The direction the height is measured along (any length: the term scales with it).
    pub along: Vector3<f64>,
}

/// SP6: the angles `[θ1, θ2]` at which, for each equation `i` of two,
/// `h(terms[i][0], θ1) + h(terms[i][1], θ1) + h(terms[i][2], θ2) + h(terms[i][3], θ2) = d[i]`,
/// where `h(term, θ) = term.along · turn(term.axis, θ, term.point)`: two bodies each turning
/// two points, whose heights along given directions must add to two given values.
///
/// Each equation is linear in the cosine and sine of each angle; eliminating the angle whose
/// two equations' coefficients are the better conditioned leaves a quartic in the tangent of
/// half the other (see the module's conventions), solved with every real root.
///
/// - **Branch:** up to four solutions, ordered by `θ1` ascending in `(-π, π]` (then `θ2`).
/// - `Crossing`: every root simple, each polished by Newton's method on the two equations.
///   `Tangent`: a double root (where two solutions merge), in two consecutive slots; the other
///   solutions, if any, in the others. A pair of solutions counts as merged when the equations'
///   values miss them by at most `4 TANGENT_REL * scale` (they sum eight rounded terms), with
///   `scale` the largest term or value.
///   A simple root is polished to a few ulps of the scale: at most `4 TANGENT_REL * scale`,
///   or `16 TANGENT_REL * scale` for one of a close pair at a fold, where Newton's method
///   stalls. Whether a close pair is one double root is decided, within rounding, on the
///   quartic's coefficients: near a fold of ill-conditioned equations that rounding can amount
///   to a miss of about `1e-11` of the scale.
/// - `Disjoint { gap }`: no solution; `gap` is the size of the two equations' residual,
///   `hypot`, at the pair of angles the quartic comes nearest a root at (in the units of `d`:
///   lengths when the directions are unit).
/// - `Coincident`: neither angle can be eliminated (each angle's coefficients in the two
///   equations are proportional, within [`tol::ANGLE`]), or the quartic's coefficients cancel
///   so far that a root of it misses the equations by more than `4 TANGENT_REL * scale` even
///   after polishing (16 for one of a close pair): the solutions, if any, are a continuum (or
///   decouple), or nearly so; not solved here.
/// - `ZeroRadius`: a zero axis.
pub fn four_terms(terms: &[[Term; 4]; 2], d: [f64; 2]) -> Intersection<[f64; 2], 4> {
    for t in terms.iter().flatten() {
        if !(finite_axis(&t.axis) && finite_point(&t.point) && finite_vector(&t.along)) {
            return not_finite();
        }
    }
    if !finite(&d) {
        return not_finite();
    }
    if terms.iter().flatten().any(|t| is_zero_dir(&t.axis.dir)) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let h = |t: &Term| Harmonic::of(&t.axis, &t.point, &t.along);
    let mut sys = System {
        m1: [[0.0; 2]; 2],
        m2: [[0.0; 2]; 2],
        d: [0.0; 2],
        scale: tol::scale(&d),
    };
    for (i, row) in terms.iter().enumerate() {
        for term in row {
            let t = h(term);
            sys.scale = sys.scale.max(tol::scale(&[t.k, t.c, t.s]));
        }
        let a = h(&row[0]).add(h(&row[1]));
        let b = h(&row[2]).add(h(&row[3]));
        sys.m1[i] = [a.c, a.s];
        sys.m2[i] = [b.c, b.s];
        sys.d[i] = d[i] - a.k - b.k;
    }
    match sys.solve() {
        Solved::Degenerate => Intersection::none(Contact::Coincident),
        Solved::Miss(t) => {
            let r = sys.residual(t);
            Intersection::none(Contact::Disjoint {
                gap: r[0].hypot(r[1]),
            })
        }
        Solved::Roots(roots) => collect(&roots, |t| t),
    }
}

/// The roots of a solve, mapped, with their contact: `Tangent` when any is double.
fn collect<T: Copy + Default, const N: usize>(
    roots: &Roots<([f64; 2], bool), N>,
    mut map: impl FnMut([f64; 2]) -> T,
) -> Intersection<T, N> {
    let mut out = Roots::new();
    let mut tangent = false;
    for &(t, multiple) in roots.as_slice() {
        out.push(map(t));
        tangent |= multiple;
    }
    let contact = if tangent {
        Contact::Tangent
    } else {
        Contact::Crossing
    };
    Intersection {
        roots: out,
        contact,
    }
}

/// SP6 for a planar sub-chain between two bodies turning about known axes (an arm with three
/// parallel axes in the middle): the angles `[θ1, θ2]` of the first body's turn about `first`
/// and of the far joint about `joint`, at which the chain closes.
///
/// The chain's parallel axes are `h` in the first body, its joint's point `base` (both in the
/// pose at `θ1 = 0`), and `far` in the chain's last body (in its pose at `θ2 = 0`, on the far
/// body, which turns about `joint` relative to it: `far` turns with the last body by `θ2`).
/// The far body only turns about `last`, a known axis through a known point of it. A turn
/// about `last` keeps the angle of a direction with it and the height along `h` of the point
/// `last` turns about, so the chain closes where (1) the chain's axis in the last body makes
/// the angle with `last` that the first body's `h` does (`sense` relates the two: the last
/// body's is `sense` times the first's), and (2) `last`'s point is at its height along `h`
/// from `base`: `offset` (the chain's, from `base` to `joint`'s point) plus that of `last`'s
/// point from `joint`'s, measured in the far body. Each equation is a term in each angle:
/// [`four_terms`], every real root.
///
/// - **Branch:** up to four solutions, ordered by `θ1` ascending in `(-π, π]` (then `θ2`).
/// - Contacts as [`four_terms`]'s; `Disjoint { gap }` in lengths, the two equations' miss.
#[allow(clippy::too_many_arguments)]
pub fn planar_chain_ends(
    first: &Line3,
    h: &Vector3<f64>,
    base: &Point3<f64>,
    joint: &Line3,
    far: &Vector3<f64>,
    last: &Line3,
    offset: f64,
    sense: f64,
) -> Intersection<[f64; 2], 4> {
    let origin = Point3::origin();
    let about = |axis: &Line3| Line3::new(origin, axis.dir);
    let term = |axis: &Line3, point: &Vector3<f64>, along: Vector3<f64>| Term {
        axis: about(axis),
        point: Point3::from(*point),
        along,
    };
    let none = Term {
        axis: about(first),
        point: origin,
        along: Vector3::zeros(),
    };
    let k = last.dir;
    // The far body's vector from the joint's point to `last`'s: its height along the chain's
    // axis is measured in the far body, where the last body's `far` turns by `θ2`.
    let reach = last.point - joint.point;
    let terms = [
        [term(first, h, k), none, term(joint, far, -sense * k), none],
        [
            term(first, h, last.point - first.point),
            none,
            term(joint, far, -sense * reach),
            none,
        ],
    ];
    four_terms(&terms, [0.0, offset + h.dot(&(base - first.point))])
}

/// SP5, the three-circle problem: the angles `[θ1, θ2, θ3]` at which `a`, turning by `θ1`
/// about `first`, meets `b`, turned by `θ3` about `third` and then, with `third`, by `θ2` about
/// `second`: `turn(first, θ1, a) = turn(second, θ2, turn(third, θ3, b))`, `third` given in
/// its pose at `θ2 = 0`. In a robot arm: the wrist centre `b` carried by two joints in series,
/// the target `a` turned by a joint at the base.
///
/// A turn about `second` keeps a point's distance from its pivot and its height along it, so
/// the two points must first agree in both: two equations in `θ1` and `θ3`, solved as
/// [`four_terms`] solves its (a quartic, every real root); then `θ2` turns the one onto the
/// other ([`nearest_turn`]), and Newton's method on the chain's own miss (three rows in the
/// three angles) closes it to a few ulps of the scale, where near a fold the quartic's
/// equations leave it a thousand times that.
///
/// - **Branch:** up to four solutions, ordered by `θ1` ascending in `(-π, π]` (then `θ3`).
/// - `Crossing`, `Tangent`: as [`four_terms`] (a double root in two consecutive slots).
/// - `Disjoint { gap }`: no solution; `gap` is how far the turned `a` misses the orbit about
///   `second` of the turned `b` ([`Nearest::miss`]) at the pair `θ1`, `θ3` nearest a solution
///   by the quartic: a miss that some turns leave, an upper bound of the smallest.
/// - `Coincident`: neither `θ1` nor `θ3` can be eliminated, or not reliably (as
///   [`four_terms`]): in particular all three axes parallel (a planar problem, whose solutions
///   are a continuum or none), or all three through one point or within about `1e-8` to
///   `1e-10` of the scale of one (both points then stay on spheres about it: a continuum or
///   none; measured on random instances, a few percent are refused at `1e-8`, most at
///   `1e-10`, all at `1e-14`).
/// - `ZeroRadius`: a zero axis, or `a` on `first`, or `b` on `third`.
///
/// Where a solution's meeting point lies on `second` (within `LENGTH_REL * scale`), `θ2` is
/// not determined by it and is returned as `0`.
pub fn three_circles(
    first: &Line3,
    a: &Point3<f64>,
    second: &Line3,
    third: &Line3,
    b: &Point3<f64>,
) -> Intersection<[f64; 3], 4> {
    three_circles_polishing(first, a, second, third, b, None)
}

/// [`three_circles`] for a caller that reads one root, `only` (every root when `None`): only
/// that root is polished on the chain's own miss, which is most of the work. The others are
/// the quartic's, in the same slots (the order is the quartic's, before any polish), and
/// close their two equations as [`four_terms`] leaves them, not the chain to rounding. Root
/// `only` is the same, to the bit, as [`three_circles`]'s.
pub fn three_circles_polishing(
    first: &Line3,
    a: &Point3<f64>,
    second: &Line3,
    third: &Line3,
    b: &Point3<f64>,
    only: Option<usize>,
) -> Intersection<[f64; 3], 4> {
    if !(finite_axis(first)
        && finite_axis(second)
        && finite_axis(third)
        && finite_point(a)
        && finite_point(b))
    {
        return not_finite();
    }
    if is_zero_dir(&first.dir) || is_zero_dir(&second.dir) || is_zero_dir(&third.dir) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sc = tol::scale(&[
        abs_max(&first.point.coords),
        abs_max(&second.point.coords),
        abs_max(&third.point.coords),
        abs_max(&a.coords),
        abs_max(&b.coords),
    ]);
    if across(first, a).norm() <= LENGTH_REL * sc || across(third, b).norm() <= LENGTH_REL * sc {
        return Intersection::none(Contact::ZeroRadius);
    }
    // About the pivot `o` of `second`, with `k` its direction: for `u = turn(first, θ1, a) - o`
    // and `v = turn(third, θ3, b) - o`, `k · u = k · v` and `|u|² = |v|²`. The second, halved
    // and divided by the scale so that both rows are lengths:
    // `(o1 - o) · r1(θ1) - (o3 - o) · r3(θ3) = (|v3|² - |u1|²) / 2` with `u1`, `r1` the parts of
    // `u` that do not turn and that do (and so for `v`).
    let o = second.point;
    let k = second.dir;
    let (ra, rb) = (across(first, a), across(third, b));
    // The parts that do not turn: the feet on the axes, from `o`.
    let fa = (a - ra) - o;
    let fb = (b - rb) - o;
    // `|u|² = |fa|² + |ra|² + 2 fa · r1(θ1)`, the turning part `r1` keeping the length of `ra`.
    let inv = 1.0 / sc;
    let row_len = |f: &Vector3<f64>, r: &Vector3<f64>, axis: &Vector3<f64>| {
        [f.dot(r) * inv, f.dot(&axis.cross(r)) * inv]
    };
    let row_k = |r: &Vector3<f64>, axis: &Vector3<f64>| [k.dot(r), k.dot(&axis.cross(r))];
    let la = row_len(&fa, &ra, &first.dir);
    let lb = row_len(&fb, &rb, &third.dir);
    let ka = row_k(&ra, &first.dir);
    let kb = row_k(&rb, &third.dir);
    let half = 0.5 * inv;
    let (nra, nrb) = (ra.norm(), rb.norm());
    let const_len = ((fb - fa).dot(&(fb + fa)) + (nrb - nra) * (nrb + nra)) * half;
    let sys = System {
        m1: [la, ka],
        m2: [[-lb[0], -lb[1]], [-kb[0], -kb[1]]],
        d: [const_len, k.dot(&(fb - fa))],
        scale: sc,
    };
    let meet = |t: [f64; 2]| {
        let pa = turn_point(first, t[0], a);
        let pb = turn_point(third, t[1], b);
        (pa, pb)
    };
    match sys.solve() {
        Solved::Degenerate => Intersection::none(Contact::Coincident),
        Solved::Miss(t) => {
            let (pa, pb) = meet(t);
            let gap = match nearest_turn(second, &pb, &pa) {
                Some(n) => n.miss,
                None => (pa - pb).norm(),
            };
            Intersection::none(Contact::Disjoint { gap })
        }
        Solved::Roots(roots) => {
            let mut slot = 0;
            collect(&roots, |t| {
                let (pa, pb) = meet(t);
                let t2 = nearest_turn(second, &pb, &pa).map_or(0.0, |n| n.angle);
                let read = only.is_none_or(|k| k == slot);
                slot += 1;
                if !read {
                    return [t[0], t2, t[1]].map(wrap);
                }
                let met = (pa, turn_point(second, t2, &pb));
                polish_three(first, a, second, third, b, [t[0], t2, t[1]], met, sc)
            })
        }
    }
}

/// Newton's method on the three-circle problem's own equation from `t`: the miss
/// `turn(first, θ1, a) - turn(second, θ2, turn(third, θ3, b))`, three rows in three angles.
/// The quartic's equations are a difference of squared lengths and a height: near a fold
/// (two roots close together) their polish stalls with the points a few thousand ulps of the
/// scale apart, which this one closes to rounding. A step is kept only while it lowers the
/// miss, and none is tried once the miss is within a few ulps of `scale`. `(p1, p2)` are the
/// two sides at `t`.
#[allow(clippy::too_many_arguments)]
fn polish_three(
    first: &Line3,
    a: &Point3<f64>,
    second: &Line3,
    third: &Line3,
    b: &Point3<f64>,
    mut t: [f64; 3],
    (mut p1, mut p2): (Point3<f64>, Point3<f64>),
    scale: f64,
) -> [f64; 3] {
    let turned = |t: &[f64; 3]| {
        let p1 = turn_point(first, t[0], a);
        let p2 = turn_point(second, t[1], &turn_point(third, t[2], b));
        (p1, p2)
    };
    let mut miss = (p1 - p2).norm();
    let good = 4.0 * f64::EPSILON * scale;
    for _ in 0..POLISH_STEPS {
        if miss <= good || miss.is_nan() {
            break;
        }
        // The third axis where the second turn has taken it.
        let at = turn_point(second, t[1], &third.point);
        let tip = turn_point(second, t[1], &(third.point + third.dir));
        let j = nalgebra::Matrix3::from_columns(&[
            first.dir.cross(&(p1 - first.point)),
            -second.dir.cross(&(p2 - second.point)),
            -(tip - at).cross(&(p2 - at)),
        ]);
        let Some(inverse) = j.try_inverse() else {
            break;
        };
        let step = inverse * (p1 - p2);
        let next = [t[0] - step.x, t[1] - step.y, t[2] - step.z];
        let (n1, n2) = turned(&next);
        let next_miss = (n1 - n2).norm();
        if next_miss.partial_cmp(&miss) != Some(std::cmp::Ordering::Less) {
            break;
        }
        (t, p1, p2, miss) = (next, n1, n2, next_miss);
    }
    t.map(wrap)
}
