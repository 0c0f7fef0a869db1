//! The 3d locus intersection table: one small function per pair of loci.
//!
//! Every function returns an [`Intersection`]: its roots in a fixed-capacity [`crate::Roots`]
//! (slot `i` is branch `i`) and a [`Contact`] that classifies the meeting. The doc comment of each
//! function states what its branch index means geometrically and how it classifies degenerate
//! inputs. The meanings are chosen so that a fixed branch moves continuously under any motion
//! that passes no singularity (a tangency, parallel or coincident loci).
//!
//! # Conventions shared by every function
//!
//! - **Scale.** Tolerances are those of [`crate::tol`], multiplied by the *scale* of the inputs:
//!   the largest absolute coordinate, radius or offset among them.
//! - **Zero size.** A radius at most `LENGTH_REL * scale` (or negative), or a zero direction or
//!   normal, gives [`Contact::ZeroRadius`] with no roots: the caller handles the point (or
//!   refuses) with the function of the lower-dimensional locus.
//! - **Tangency.** When the loci *miss* each other by at most `TANGENT_REL * scale` (a gap in
//!   `[0, TANGENT_REL * scale]`: rounding), the contact is [`Contact::Tangent`] and the double
//!   root, placed midway between the loci's closest points, fills *both* branch slots, so a
//!   fixed branch stays defined through the tangency. Such a root is within
//!   `TANGENT_REL * scale / 2` of each locus. Loci that *overlap*, however little, cross: the
//!   function returns their exact roots (two points, or a circle or lines), which merge
//!   continuously into the touching point as the overlap vanishes, so a solvable near-tangent
//!   assembly is solved to rounding rather than snapped to a midpoint. Each half chord is the
//!   square root of a product whose factors are the overlap itself and sums, all positive as
//!   computed when the overlap is, so a tiny overlap gives a tiny positive half chord, never
//!   zero from cancellation nor NaN. The one exception is two non-coplanar circles
//!   ([`circle_circle`]), whose meeting is itself decided with the tolerance both ways.
//! - **Parallel.** Directions whose angle has a sine at most [`tol::ANGLE`] are parallel.
//! - **Accuracy.** Outside tangency, every root lies on both loci within a few units in the last
//!   place of `max(scale, |root|)`: the tests check `1e-13` of that. The `|root|` term matters
//!   only for nearly parallel loci, whose meeting point can be far beyond the inputs; its
//!   coordinates alone then carry that rounding.
//! - **Non-finite input** (NaN or infinite coordinates, radii or offsets) gives no roots and
//!   `Contact::Disjoint { gap: NaN }`. Nothing here allocates or panics.

use nalgebra::{Point3, Vector3};

use crate::frame::perpendicular;
use crate::locus3d::{Circle3, Cylinder, Ellipse3, Line3, Plane, Sphere};
use crate::num::is_finite;
use crate::roots::{Contact, Intersection, Roots};
use crate::tol::{self, ANGLE, LENGTH_REL, TANGENT_REL};

/// What a plane cuts from a cylinder: an ellipse, or lines along the cylinder's axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CylinderSection {
    /// The section by a plane not parallel to the axis (a circle when perpendicular).
    Ellipse(Ellipse3),
    /// A line along the axis, when the plane is parallel to the axis.
    Line(Line3),
}

impl Default for CylinderSection {
    fn default() -> Self {
        CylinderSection::Line(Line3::default())
    }
}

// ---------------------------------------------------------------------------------------------
// Helpers.

/// `a * b - c * d` to about one unit in the last place (Kahan's algorithm with fused
/// multiply-adds): no cancellation error when the two products nearly agree.
#[inline]
fn diff_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let w = c * d;
    let e = (-c).mul_add(d, w);
    let f = a.mul_add(b, -w);
    f + e
}

/// `a x b` with every component accurate to about one unit in its last place, even for nearly
/// parallel vectors (where the plain formula loses all its digits).
#[inline]
fn cross_accurate(a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(
        diff_of_products(a.y, b.z, a.z, b.y),
        diff_of_products(a.z, b.x, a.x, b.z),
        diff_of_products(a.x, b.y, a.y, b.x),
    )
}

#[inline]
fn finite(values: &[f64]) -> bool {
    values.iter().all(|&v| is_finite(v))
}

#[inline]
fn abs_max(v: &Vector3<f64>) -> f64 {
    v.x.abs().max(v.y.abs()).max(v.z.abs())
}

/// `sqrt(r^2 - d^2)` computed as `sqrt((r - d)(r + d))`, zero when negative.
#[inline]
fn leg(r: f64, d: f64) -> f64 {
    ((r - d) * (r + d)).max(0.0).sqrt()
}

#[inline]
fn mid(a: &Point3<f64>, b: &Point3<f64>) -> Point3<f64> {
    a + (b - a) * 0.5
}

#[inline]
fn is_zero_dir(v: &Vector3<f64>) -> bool {
    let n = v.norm_squared();
    n.is_nan() || n < 0.25
}

#[inline]
fn not_finite<T: Copy + Default, const N: usize>() -> Intersection<T, N> {
    Intersection::none(Contact::Disjoint { gap: f64::NAN })
}

#[inline]
fn two<T: Copy + Default>(a: T, b: T, contact: Contact) -> Intersection<T, 2> {
    let mut roots = Roots::new();
    roots.push(a);
    roots.push(b);
    Intersection { roots, contact }
}

/// One root and its contact.
#[inline]
pub(crate) fn one<T: Copy + Default, const N: usize>(a: T, contact: Contact) -> Intersection<T, N> {
    let mut roots = Roots::new();
    roots.push(a);
    Intersection { roots, contact }
}

// ---------------------------------------------------------------------------------------------
// Sphere and plane pairs.

/// Sphere-sphere: the circle common to two spheres.
///
/// - **Branch:** a single root (branch 0), the circle whose centre lies on the line of centres
///   and whose normal points from `a`'s centre to `b`'s.
/// - `Crossing`: the circle, whenever the spheres overlap, however little; its radius shrinks
///   continuously to 0 as the overlap vanishes. `Tangent` (externally or internally, missing by
///   at most `TANGENT_REL * scale`): a circle of radius 0 at the touching point, midway between
///   the spheres' nearest points.
/// - `Disjoint { gap }`: the spheres are apart (`gap = d - ra - rb`), or one holds the other
///   (`gap = |ra - rb| - d`), or they are concentric with different radii (`gap = |ra - rb|`).
/// - `Coincident`: same centre and radius. `ZeroRadius`: a radius is zero.
pub fn sphere_sphere(a: &Sphere, b: &Sphere) -> Intersection<Circle3, 1> {
    let (ca, cb, ra, rb) = (a.center, b.center, a.radius, b.radius);
    if !finite(&[ca.x, ca.y, ca.z, cb.x, cb.y, cb.z, ra, rb]) {
        return not_finite();
    }
    let s = tol::scale(&[abs_max(&ca.coords), abs_max(&cb.coords), ra, rb]);
    let (tl, tt) = (LENGTH_REL * s, TANGENT_REL * s);
    if ra <= tl || rb <= tl {
        return Intersection::none(Contact::ZeroRadius);
    }
    let w = cb - ca;
    let d = w.norm();
    // The radical plane, where the circle lies, is `h` from `a`'s centre along `n`.
    let n = w / d;
    let (h, r, contact) = match centres_meeting(d, ra, rb, tl, tt) {
        Meeting::Apart(contact) => return Intersection::none(contact),
        Meeting::Touching(h) => (h, 0.0, Contact::Tangent),
        Meeting::Crossing { h, r } => (h, r, Contact::Crossing),
    };
    one(
        Circle3 {
            center: ca + n * h,
            normal: n,
            radius: r,
        },
        contact,
    )
}

/// How two spheres, or two circles in one plane, with centres `d` apart and radii `ra`, `rb`
/// meet: the classification [`sphere_sphere`] and the coplanar case of [`circle_circle`] share.
/// Lengths under `tl` are zero; a miss of at most `tt` is touching; any overlap is crossing.
enum Meeting {
    /// They do not meet: concentric (`Coincident` or `Disjoint`) or apart (`Disjoint`).
    Apart(Contact),
    /// They touch (miss by at most `tt`), at this distance from the first centre along the line
    /// of centres.
    Touching(f64),
    /// They overlap and cross in a circle (two points, in a plane) at distance `h` from the
    /// first centre along the line of centres, `r > 0` off that line (however small the
    /// overlap).
    Crossing { h: f64, r: f64 },
}

fn centres_meeting(d: f64, ra: f64, rb: f64, tl: f64, tt: f64) -> Meeting {
    if d <= tl {
        let g = (ra - rb).abs();
        return Meeting::Apart(if g <= tt {
            Contact::Coincident
        } else {
            Contact::Disjoint { gap: g }
        });
    }
    let outer = d - (ra + rb);
    let inner = (ra - rb).abs() - d;
    if outer > tt {
        return Meeting::Apart(Contact::Disjoint { gap: outer });
    }
    if inner > tt {
        return Meeting::Apart(Contact::Disjoint { gap: inner });
    }
    // Missing by at most `tt` (rounding): touching. Overlapping, however little: crossing.
    if outer >= 0.0 || inner >= 0.0 {
        // Midway between the two spheres' own touching points, which differ by at most `tt`.
        let (pa, pb) = if outer >= 0.0 {
            (ra, d - rb)
        } else if ra >= rb {
            (ra, d + rb)
        } else {
            (-ra, d - rb)
        };
        return Meeting::Touching(0.5 * (pa + pb));
    }
    let h = 0.5 * (d + (ra - rb) * (ra + rb) / d);
    // The radius `sqrt(ra^2 - h^2)` by Heron's four factors, `(ra + rb - d)(d - |ra - rb|)`
    // and `(d + |ra - rb|)(d + ra + rb)` over `2d`: the first two are `-outer` and `-inner`,
    // positive here as computed, so a tiny overlap gives a tiny positive radius (where
    // `ra - h`, from a rounded `h`, could be zero or negative).
    let near = (-outer) * (d + (ra + rb));
    let far = (-inner) * (d + (ra - rb).abs());
    Meeting::Crossing {
        h,
        r: near.sqrt() * far.sqrt() / (2.0 * d),
    }
}

/// Sphere-plane: the circle a plane cuts from a sphere.
///
/// - **Branch:** a single root (branch 0), the circle centred at the foot of the perpendicular
///   from the sphere's centre, with the plane's normal.
/// - `Crossing`: the circle, whenever the plane cuts the sphere, however little; its radius
///   shrinks continuously to 0 as the cut vanishes. `Tangent`: the plane misses the sphere by at
///   most `TANGENT_REL * scale`; a circle of radius 0 at the touching point, midway between the
///   sphere's nearest point and its foot on the plane.
/// - `Disjoint { gap }`: the plane misses the sphere by `gap = |signed distance| - r`.
/// - `ZeroRadius`: the radius or the plane's normal is zero.
pub fn sphere_plane(s: &Sphere, p: &Plane) -> Intersection<Circle3, 1> {
    let (c, r, n) = (s.center, s.radius, p.normal);
    if !finite(&[c.x, c.y, c.z, r, n.x, n.y, n.z, p.offset]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&c.coords), r, p.offset]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if r <= tl || is_zero_dir(&n) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sd = p.signed_distance(&c);
    let g = sd.abs() - r;
    if g > tt {
        return Intersection::none(Contact::Disjoint { gap: g });
    }
    let foot = c - n * sd;
    // Missing by at most `tt` (rounding): touching. Cutting, however little: the circle, of
    // radius `sqrt(-g (r + |sd|))` (`r - |sd|` is exactly `-g`, positive here).
    if g >= 0.0 {
        let on_sphere = c - n * (r.copysign(sd));
        return one(
            Circle3 {
                center: mid(&foot, &on_sphere),
                normal: n,
                radius: 0.0,
            },
            Contact::Tangent,
        );
    }
    one(
        Circle3 {
            center: foot,
            normal: n,
            radius: leg(r, sd.abs()),
        },
        Contact::Crossing,
    )
}

/// Plane-plane: the line common to two planes.
///
/// - **Branch:** a single root (branch 0), the line directed along `a.normal x b.normal`,
///   through the point of the line nearest to the origin.
/// - `Crossing`: the line. `Parallel { gap }`: parallel and distinct, `gap` apart.
///   `Coincident`: the same plane (up to `TANGENT_REL * scale`, either orientation).
/// - `ZeroRadius`: a normal is zero.
/// - Accuracy: the line's point is within a few ulps of `max(scale, |point|)` of both planes; its
///   direction is perpendicular to both normals to a few ulps (the cross product is computed
///   without cancellation).
pub fn plane_plane(a: &Plane, b: &Plane) -> Intersection<Line3, 1> {
    let (na, nb) = (a.normal, b.normal);
    if !finite(&[na.x, na.y, na.z, nb.x, nb.y, nb.z, a.offset, b.offset]) {
        return not_finite();
    }
    if is_zero_dir(&na) || is_zero_dir(&nb) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sc = tol::scale(&[a.offset, b.offset]);
    let u = cross_accurate(&na, &nb);
    let su = u.norm();
    if su <= ANGLE {
        let gap = (a.offset - b.offset * na.dot(&nb).signum()).abs();
        return if gap <= TANGENT_REL * sc {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Parallel { gap })
        };
    }
    let uh = u / su;
    // From the point of `a` nearest the origin, move within `a` (along `g`, perpendicular to
    // the line, with `nb . g = su`) onto `b`: no cancellation between nearly equal terms.
    let p0 = Point3::from(na * a.offset);
    let g = uh.cross(&na);
    let sdb = b.signed_distance(&p0);
    one(
        Line3 {
            point: p0 - g * (sdb / su),
            dir: uh,
        },
        Contact::Crossing,
    )
}

/// Line-plane: the point where a line crosses a plane.
///
/// - **Branch:** a single root (branch 0).
/// - `Crossing`: the point. `Parallel { gap }`: the line is parallel to the plane, `gap` away.
///   `Coincident`: the line lies in the plane (within `TANGENT_REL * scale`).
/// - `ZeroRadius`: the line's direction or the plane's normal is zero.
pub fn line_plane(l: &Line3, p: &Plane) -> Intersection<Point3<f64>, 1> {
    let (q, d, n) = (l.point, l.dir, p.normal);
    if !finite(&[q.x, q.y, q.z, d.x, d.y, d.z, n.x, n.y, n.z, p.offset]) {
        return not_finite();
    }
    if is_zero_dir(&d) || is_zero_dir(&n) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sc = tol::scale(&[abs_max(&q.coords), p.offset]);
    let sd = p.signed_distance(&q);
    let denom = n.dot(&d);
    if denom.abs() <= ANGLE {
        return if sd.abs() <= TANGENT_REL * sc {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Parallel { gap: sd.abs() })
        };
    }
    one(q + d * (-sd / denom), Contact::Crossing)
}

/// Line-sphere: the points where a line pierces a sphere.
///
/// - **Branch:** order along the line's direction: branch 0 is the entry point (smaller
///   parameter), branch 1 the exit point. At tangency both slots hold the touching point.
/// - `Crossing`: two points, whenever the line passes inside the sphere, however little (the
///   exact roots, which merge continuously into the touching point as the overlap vanishes).
///   `Tangent`: the line misses the sphere by at most `TANGENT_REL * scale`; the double root,
///   midway between the line's and the sphere's nearest points, in both slots.
/// - `Disjoint { gap }`: the line passes `gap` outside the sphere.
/// - `ZeroRadius`: the radius or the line's direction is zero.
pub fn line_sphere(l: &Line3, s: &Sphere) -> Intersection<Point3<f64>, 2> {
    let (q, d, c, r) = (l.point, l.dir, s.center, s.radius);
    if !finite(&[q.x, q.y, q.z, d.x, d.y, d.z, c.x, c.y, c.z, r]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&q.coords), abs_max(&c.coords), r]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if r <= tl || is_zero_dir(&d) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let foot = l.closest(&c);
    let off = foot - c;
    let m = off.norm();
    let g = m - r;
    if g > tt {
        return Intersection::none(Contact::Disjoint { gap: g });
    }
    // Missing by at most `tt` (rounding): touching. Overlapping, however little: the two
    // roots, a half chord `sqrt(-g (r + m))` apart from the foot (`r - m` is exactly `-g`).
    if g >= 0.0 {
        // m is close to r > 0, so off / m is a unit vector.
        let t = mid(&foot, &(c + off * (r / m)));
        return two(t, t, Contact::Tangent);
    }
    let h = leg(r, m);
    two(foot - d * h, foot + d * h, Contact::Crossing)
}

/// Line-cylinder: the points where a line pierces a cylinder.
///
/// - **Branch:** order along the line's direction (branch 0 first), as for [`line_sphere`].
/// - `Crossing`: two points, whenever the line passes inside the cylinder, however little (the
///   exact roots, which merge continuously as the overlap vanishes). `Tangent`: the line misses
///   the cylinder by at most `TANGENT_REL * scale`; the double root, midway between the line's
///   and the cylinder's nearest points, in both slots.
/// - `Disjoint { gap }`: the line passes `gap` outside the cylinder.
/// - `Parallel { gap }`: the line is parallel to the axis, `gap` off the surface (inside or
///   outside). `Coincident`: the line lies on the surface.
/// - `ZeroRadius`: the radius, the axis direction or the line's direction is zero.
/// - Accuracy: a line nearly parallel to the axis meets the surface far away; the roots are then
///   accurate relative to their own magnitude.
pub fn line_cylinder(l: &Line3, cy: &Cylinder) -> Intersection<Point3<f64>, 2> {
    let (q, d, o, a, r) = (l.point, l.dir, cy.axis.point, cy.axis.dir, cy.radius);
    if !finite(&[
        q.x, q.y, q.z, d.x, d.y, d.z, o.x, o.y, o.z, a.x, a.y, a.z, r,
    ]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&q.coords), abs_max(&o.coords), r]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if r <= tl || is_zero_dir(&d) || is_zero_dir(&a) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let w = q - o;
    let wp = w - a * a.dot(&w);
    let dp = d - a * a.dot(&d);
    let sp = dp.norm();
    if sp <= ANGLE {
        let g = (wp.norm() - r).abs();
        return if g <= tt {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Parallel { gap: g })
        };
    }
    let t0 = -wp.dot(&dp) / (sp * sp);
    let radial = wp + dp * t0;
    let m = radial.norm();
    let g = m - r;
    if g > tt {
        return Intersection::none(Contact::Disjoint { gap: g });
    }
    let foot = q + d * t0;
    // Missing by at most `tt` (rounding): touching. Overlapping, however little: the two
    // roots (`r - m` in `leg` is exactly `-g`, positive).
    if g >= 0.0 {
        let t = foot + radial * ((r - m) / (2.0 * m));
        return two(t, t, Contact::Tangent);
    }
    let dt = leg(r, m) / sp;
    two(q + d * (t0 - dt), q + d * (t0 + dt), Contact::Crossing)
}

// ---------------------------------------------------------------------------------------------
// Circle pairs.

/// Circle-plane: the points where a plane cuts a circle.
///
/// - **Branch:** order along `u = circle.normal x plane.normal`, the direction of the line common
///   to the two planes: branch 0 has the smaller coordinate along `u`, i.e. it lies on the
///   negative side of `u` from the chord's midpoint. This is `-(normal x g)` with `g` the
///   in-plane direction from the centre towards the plane, a direction fixed by the two normals,
///   so the branch does not flip when the plane sweeps through the circle's centre.
/// - `Crossing`: two points, whenever the plane cuts the circle, however little (the exact
///   roots, which merge continuously into the touching point as the cut vanishes). `Tangent`:
///   the plane misses the circle by a `gap` (as below) of at most `TANGENT_REL * scale`; the
///   double root, midway between the circle's nearest point and its foot on the plane, in both
///   slots.
/// - `Disjoint { gap }`: the plane misses the circle by `gap` (distance from the plane to the
///   circle's nearest point).
/// - `Parallel { gap }`: the planes are parallel, `gap` apart. `Coincident`: the circle lies in
///   the plane.
/// - `ZeroRadius`: the radius or a normal is zero.
pub fn circle_plane(c: &Circle3, p: &Plane) -> Intersection<Point3<f64>, 2> {
    let (cc, nc, r, np) = (c.center, c.normal, c.radius, p.normal);
    if !finite(&[
        cc.x, cc.y, cc.z, nc.x, nc.y, nc.z, r, np.x, np.y, np.z, p.offset,
    ]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&cc.coords), r, p.offset]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if r <= tl || is_zero_dir(&nc) || is_zero_dir(&np) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let sd = p.signed_distance(&cc);
    let u = cross_accurate(&nc, &np);
    let su = u.norm();
    if su <= ANGLE {
        return if sd.abs() <= tt {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Parallel { gap: sd.abs() })
        };
    }
    let uh = u / su;
    // In the circle's plane, towards increasing signed distance from `p`.
    let gh = uh.cross(&nc);
    // Signed in-plane offset of the chord's midpoint from the centre along `gh`.
    let s = -sd / su;
    // How far the circle misses the line common to the planes, in its plane (negative when
    // it crosses it), and so the plane itself (`p` rises by `su` per unit along `gh`).
    let g = s.abs() - r;
    let gap = g * su;
    if gap > tt {
        return Intersection::none(Contact::Disjoint { gap });
    }
    // Missing by at most `tt` (rounding): touching, midway between the circle's point nearest
    // the plane (its signed distance `gap` with the sign of `sd`) and that point's foot.
    // Cutting, however little: the two roots (`r - |s|` in `leg` is exactly `-g`, positive).
    if g >= 0.0 {
        let t = cc + gh * r.copysign(s) - np * (0.5 * gap).copysign(sd);
        return two(t, t, Contact::Tangent);
    }
    let m = cc + gh * s;
    let h = leg(r, s.abs());
    two(m - uh * h, m + uh * h, Contact::Crossing)
}

/// Circle-sphere: the points of a circle on a sphere.
///
/// - **Branch:** let `e` be the direction, in the circle's plane, from the circle's centre to the
///   projection of the sphere's centre. Branch 0 is the root on the positive side of
///   `normal x e` (counter-clockwise from `e` seen from the tip of the circle's normal),
///   branch 1 the other. `e` is defined away from the singular configuration where the sphere's
///   centre is on the circle's axis (then the circle lies on the sphere or misses it entirely).
/// - `Crossing`: two points, whenever the sphere's radius is strictly inside the range of
///   distances from its centre to the circle's points, however close to an end (the exact
///   roots, which merge continuously into the touching point as the overlap vanishes).
///   `Tangent`: the radius is outside that range by at most `TANGENT_REL * scale` (the sphere
///   misses the circle's point nearest to or farthest from its centre by that much); the double
///   root, midway between that point and the sphere, in both slots.
/// - `Disjoint { gap }`: `gap` is how far the sphere's radius is outside the range of distances
///   from its centre to the circle's points.
/// - `Coincident`: the circle lies on the sphere. `ZeroRadius`: a radius or the normal is zero.
pub fn circle_sphere(c: &Circle3, s: &Sphere) -> Intersection<Point3<f64>, 2> {
    let (cc, nc, rc, cs, rs) = (c.center, c.normal, c.radius, s.center, s.radius);
    if !finite(&[cc.x, cc.y, cc.z, nc.x, nc.y, nc.z, rc, cs.x, cs.y, cs.z, rs]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&cc.coords), abs_max(&cs.coords), rc, rs]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if rc <= tl || rs <= tl || is_zero_dir(&nc) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let w = cs - cc;
    let sd = nc.dot(&w);
    let ev = w - nc * sd;
    let rho = ev.norm();
    if rho <= tl {
        let g = rs - sd.hypot(rc);
        return if g.abs() <= tt {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Disjoint { gap: g.abs() })
        };
    }
    let e = ev / rho;
    let dmin = sd.hypot(rho - rc);
    let dmax = sd.hypot(rho + rc);
    // How far the sphere misses the circle's nearest and farthest points (negative inside).
    let (short, long) = (dmin - rs, rs - dmax);
    if short > tt {
        return Intersection::none(Contact::Disjoint { gap: short });
    }
    if long > tt {
        return Intersection::none(Contact::Disjoint { gap: long });
    }
    // Missing by at most `tt` (rounding): touching. Overlapping, however little: crossing.
    let near = short >= 0.0;
    if near || long >= 0.0 {
        let on_circle = if near { cc + e * rc } else { cc - e * rc };
        let to = on_circle - cs;
        let n = to.norm();
        let on_sphere = if n > 0.0 {
            cs + to * (rs / n)
        } else {
            on_circle
        };
        let t = mid(&on_circle, &on_sphere);
        return two(t, t, Contact::Tangent);
    }
    // The roots are at the angle `theta` from `e` where the distance to the sphere's centre,
    // `sqrt(dmin^2 + 2 rho rc (1 - cos theta))`, is `rs`. With `x = rc (1 - cos)` and
    // `y = rc (1 + cos)`, from `rs^2 - dmin^2 = -short (rs + dmin)` and
    // `dmax^2 - rs^2 = -long (dmax + rs)`, both positive here: the root is `a = rc - x` along
    // `e` and `h = sqrt(x (2 rc - x))` off it (or `y - rc` and `sqrt(y (2 rc - y))`, from the
    // farthest point, when the roots are nearer it), so a tiny overlap at either end gives a
    // tiny positive `h`, and `a^2 + h^2 = rc^2` to rounding.
    let x = -short * (rs + dmin) / (2.0 * rho);
    let y = -long * (dmax + rs) / (2.0 * rho);
    let (a, h) = if x <= y {
        (rc - x, (x * (2.0 * rc - x)).sqrt())
    } else {
        (y - rc, (y * (2.0 * rc - y)).sqrt())
    };
    let side = nc.cross(&e);
    let m = cc + e * a;
    two(m + side * h, m - side * h, Contact::Crossing)
}

/// Circle-circle: the points common to two circles, coplanar or not.
///
/// **Coplanar** (parallel normals and `b`'s centre within `TANGENT_REL * scale` of `a`'s plane;
/// the circles are treated as lying in `a`'s plane):
/// - **Branch:** with `e` the direction from `a`'s centre to `b`'s, branch 0 is the root on the
///   positive side of `a.normal x e` (left of the directed line of centres seen from the tip of
///   `a`'s normal), branch 1 the other.
/// - `Crossing`: two points, whenever the circles overlap, however little (the exact roots,
///   which merge continuously into the touching point as the overlap vanishes). `Tangent`
///   (externally or internally, missing by at most `TANGENT_REL * scale`): the double root,
///   midway between the circles' nearest points, in both slots.
/// - `Disjoint { gap }`: apart (`d - ra - rb`), nested (`|ra - rb| - d`) or concentric with
///   different radii (`|ra - rb|`). `Coincident`: the same circle.
///
/// **Parallel planes**, not coplanar: `Parallel { gap }` with the distance between the planes.
///
/// **Non-coplanar:** common points lie on the line `L` common to the two planes, directed along
/// `a.normal x b.normal`. The candidates are each circle's chord ends on `L` (or, when it touches
/// or misses `L`, its point nearest to `L`), each refined by a few alternating projections onto
/// the two circles; a candidate within `TANGENT_REL * scale` of both circles is a common point,
/// and candidates closer than `sqrt(2 TANGENT_REL) * scale` along `L` are the same point (the
/// chord length at which a tangency is declared).
/// - **Branch:** order along `L`'s direction: two common points fill branches 0 and 1 in that
///   order (`Crossing`). A single common point fills both slots: `Tangent` if a circle touches
///   `L` there (it is tangent to the other's plane), otherwise `Crossing` (the circles pass
///   through each other's plane at that point).
/// - `Disjoint { gap }`: `gap` is the smallest distance between a refined candidate of one
///   circle and the other circle: a distance between actual points of the two circles, so an
///   upper bound of their true distance (which needs a degree-8 solve) that vanishes exactly
///   when they meet, and usually their locally nearest distance.
/// - Tangency here is decided with `TANGENT_REL * scale` both ways, unlike the rest of the
///   table: a circle crossing the other's plane by a hair is no overlap of the two circles.
///   Two circles in space meet only by construction, and a circle built tangent to the other's
///   plane at a point of the other that rounding takes a hair across the plane has no exact
///   common point at all (its two crossings of `L` are about `sqrt(2 r hair)` either side of
///   the point), while the point itself is within the tolerance of both: so it is kept, as
///   `Tangent`.
///
/// `ZeroRadius`: a radius or a normal is zero.
///
/// Accuracy: a root is within `TANGENT_REL * scale` of both circles (plus rounding), a looser
/// bound than other functions because the meeting of two non-coplanar circles, and the
/// coplanarity of two circles, are themselves decided with that tolerance; exactly coplanar or
/// exactly meeting inputs give roots within a few ulps.
pub fn circle_circle(a: &Circle3, b: &Circle3) -> Intersection<Point3<f64>, 2> {
    let (ca, na, ra) = (a.center, a.normal, a.radius);
    let (cb, nb, rb) = (b.center, b.normal, b.radius);
    if !finite(&[
        ca.x, ca.y, ca.z, na.x, na.y, na.z, ra, cb.x, cb.y, cb.z, nb.x, nb.y, nb.z, rb,
    ]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&ca.coords), abs_max(&cb.coords), ra, rb]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if ra <= tl || rb <= tl || is_zero_dir(&na) || is_zero_dir(&nb) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let w = cb - ca;
    let off = na.dot(&w);
    let u = cross_accurate(&na, &nb);
    let su = u.norm();
    if su <= ANGLE {
        if off.abs() > tt {
            return Intersection::none(Contact::Parallel { gap: off.abs() });
        }
        return coplanar_circles(ca, na, ra, w - na * off, rb, tl, tt);
    }
    // Non-coplanar: common points lie on the line L common to the planes, directed along uh.
    let uh = u / su;
    let merge = sc * (2.0 * TANGENT_REL).sqrt();
    let (pts_a, ka, touch_a) =
        line_candidates(ca, uh.cross(&na), uh, ra, -nb.dot(&(ca - cb)) / su, tt);
    let (pts_b, kb, touch_b) = line_candidates(cb, nb.cross(&uh), uh, rb, -off / su, tt);
    // Refine every candidate by alternating projections; keep those on both circles.
    let mut acc = [(0.0, Point3::origin()); 4];
    let mut n = 0;
    let mut gap = f64::INFINITY;
    for x in pts_a.iter().take(ka).chain(pts_b.iter().take(kb)) {
        let (pa, pb) = refine_on_circles(a, b, x, tt);
        let d = (pa - pb).norm();
        if d <= tt {
            if let Some(slot) = acc.get_mut(n) {
                let m = mid(&pa, &pb);
                *slot = (uh.dot(&(m - ca)), m);
                n += 1;
            }
        } else {
            gap = gap.min(d);
        }
    }
    if n == 0 {
        return Intersection::none(Contact::Disjoint { gap });
    }
    let acc = acc.get_mut(..n).unwrap_or_default();
    acc.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
    // Cluster candidates of the same common point (ordered along L).
    let Some(&first) = acc.first() else {
        return Intersection::none(Contact::Disjoint { gap });
    };
    let mut last = first;
    for &c in acc.iter() {
        if c.0 - first.0 > merge {
            last = c;
        }
    }
    if last.0 - first.0 > merge {
        two(first.1, last.1, Contact::Crossing)
    } else {
        let contact = if touch_a || touch_b {
            Contact::Tangent
        } else {
            Contact::Crossing
        };
        two(first.1, first.1, contact)
    }
}

/// A circle's candidate points on the line `L` common to its plane and another plane: its two
/// chord ends when it crosses `L`, or its point nearest `L` when it touches or misses it. `g` is
/// the in-plane unit direction towards the other plane, `s` the signed offset of the chord's
/// midpoint along it, `uh` the direction of `L`. Returns the points, their count and whether the
/// circle touches `L` (within `tt`).
#[inline]
fn line_candidates(
    c: Point3<f64>,
    g: Vector3<f64>,
    uh: Vector3<f64>,
    r: f64,
    s: f64,
    tt: f64,
) -> ([Point3<f64>; 2], usize, bool) {
    let miss = s.abs() - r;
    if miss >= -tt {
        let p = c + g * r.copysign(s);
        ([p, p], 1, miss <= tt)
    } else {
        let m = c + g * s;
        let h = leg(r, s.abs());
        ([m - uh * h, m + uh * h], 2, false)
    }
}

/// The point of circle `c` nearest to `x` (a fixed rim point when `x` is on the axis).
#[inline]
fn project_on_circle(c: &Circle3, x: &Point3<f64>) -> Point3<f64> {
    let w = x - c.center;
    let v = w - c.normal * c.normal.dot(&w);
    let rho = v.norm();
    if rho > 0.0 {
        c.center + v * (c.radius / rho)
    } else {
        let q = perpendicular(&c.normal);
        c.center + q * (c.radius / q.norm())
    }
}

/// Alternating projections from `x`: a point of `a` and its nearest point of `b`, after a few
/// rounds that pull them towards a common point (or a locally nearest pair). Stops as soon as
/// the two are within `tt`.
#[inline]
fn refine_on_circles(
    a: &Circle3,
    b: &Circle3,
    x: &Point3<f64>,
    tt: f64,
) -> (Point3<f64>, Point3<f64>) {
    let mut pa = project_on_circle(a, x);
    let mut pb = project_on_circle(b, &pa);
    for _ in 0..3 {
        if (pa - pb).norm() <= tt {
            break;
        }
        pa = project_on_circle(a, &pb);
        pb = project_on_circle(b, &pa);
    }
    (pa, pb)
}

/// Two circles in one plane (normal `n`): the coplanar case of [`circle_circle`]. `w` is the
/// in-plane vector from `a`'s centre to `b`'s: passing it rather than `b`'s centre keeps the
/// direction between nearby centres exactly in the plane.
fn coplanar_circles(
    ca: Point3<f64>,
    n: Vector3<f64>,
    ra: f64,
    w: Vector3<f64>,
    rb: f64,
    tl: f64,
    tt: f64,
) -> Intersection<Point3<f64>, 2> {
    let d = w.norm();
    let e = w / d;
    match centres_meeting(d, ra, rb, tl, tt) {
        Meeting::Apart(contact) => Intersection::none(contact),
        Meeting::Touching(h) => {
            let t = ca + e * h;
            two(t, t, Contact::Tangent)
        }
        Meeting::Crossing { h, r } => {
            let m = ca + e * h;
            let side = n.cross(&e);
            two(m + side * r, m - side * r, Contact::Crossing)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Plane and cylinder.

/// A line and a circle of space. In the circle's plane (the line parallel to it and in it,
/// to the tangency tolerance) they meet where the line meets the circle's sphere: branch `i`
/// is [`line_sphere`]'s. Across the plane the line meets it at one point, the root in both
/// slots when it is on the circle to the tangency tolerance over the sine of the line's angle
/// with the plane (a circle of space meets a line there or nowhere, and the sphere's other
/// root, off the circle, must never be taken); [`Contact::Disjoint`] with the gap otherwise,
/// [`Contact::Parallel`] for a line parallel to the plane and off it.
pub fn line_circle(l: &Line3, c: &Circle3) -> Intersection<Point3<f64>, 2> {
    let sphere = Sphere::new(c.center, c.radius);
    let across = l.dir.dot(&c.normal);
    let height = (l.point - c.center).dot(&c.normal);
    let scale = tol::scale(&[
        l.point.x, l.point.y, l.point.z, c.center.x, c.center.y, c.center.z, c.radius,
    ]);
    let tt = TANGENT_REL * scale;
    if across.abs() <= ANGLE {
        if height.abs() > tt {
            return Intersection::none(Contact::Parallel { gap: height.abs() });
        }
        return line_sphere(l, &sphere);
    }
    let at = l.point - l.dir * (height / across);
    let gap = ((at - c.center).norm() - c.radius).abs();
    // The crossing is as precise as the line is steep across the plane: rounding over the
    // sine of their angle.
    if gap > tt / across.abs().min(1.0) {
        return Intersection::none(Contact::Disjoint { gap });
    }
    Intersection {
        roots: Roots::from_slice(&[at, at]),
        contact: Contact::Tangent,
    }
}

/// The lines where a plane parallel to a cylinder's axis cuts it: [`plane_cylinder`]'s
/// sections of that case, as lines (branches, contacts and tolerances the same). What a line
/// whose direction lies in a plane meets when it must pass at a distance from a point: its own
/// point in the plane, on the cylinder about the point along its direction.
///
/// A plane not parallel to the axis (its normal's cosine with the axis above [`tol::ANGLE`])
/// cuts an ellipse, no line: [`Contact::Coincident`], a configuration this meeting does not
/// cover.
pub fn plane_cylinder_lines(p: &Plane, cy: &Cylinder) -> Intersection<Line3, 2> {
    let i = plane_cylinder(p, cy);
    let line = |k: usize| match i.roots.get(k) {
        Some(CylinderSection::Line(l)) => Some(l),
        _ => None,
    };
    match (i.contact, line(0), line(1)) {
        (Contact::Crossing | Contact::Tangent, Some(a), Some(b)) => two(a, b, i.contact),
        (Contact::Crossing | Contact::Tangent, _, _) => Intersection::none(Contact::Coincident),
        (contact, _, _) => Intersection::none(contact),
    }
}

/// Plane-cylinder: the section of a cylinder by a plane.
///
/// **Plane not parallel to the axis:** `Crossing` with a single root (branch 0; slot 1 stays
/// empty), the [`CylinderSection::Ellipse`] centred where the axis meets the plane, with the
/// plane's normal, semi-axis `b = r` along `minor = unit(normal x axis)` and semi-axis
/// `a = r / |cos(angle between normal and axis)|` along `major = minor x normal`. When the plane
/// is perpendicular to the axis the ellipse is a circle (`a = b = r`) and `minor` is the
/// deterministic [`perpendicular`] of the normal.
///
/// **Plane parallel to the axis** (sine of the angle between axis and plane at most
/// [`tol::ANGLE`]): lines along the axis direction ([`CylinderSection::Line`]).
/// - **Branch:** order along `normal x axis`: branch 0 has the smaller coordinate.
/// - `Crossing`: two lines, whenever the plane cuts the cylinder, however little (the exact
///   lines, which merge continuously as the cut vanishes). `Tangent`: the plane misses the
///   cylinder by at most `TANGENT_REL * scale`; the touching line, midway between the
///   cylinder's nearest line and its foot on the plane, in both slots.
/// - `Parallel { gap }`: the plane misses the cylinder by `gap`.
///
/// `ZeroRadius`: the radius, the axis direction or the normal is zero.
pub fn plane_cylinder(p: &Plane, cy: &Cylinder) -> Intersection<CylinderSection, 2> {
    let (n, o, a, r) = (p.normal, cy.axis.point, cy.axis.dir, cy.radius);
    if !finite(&[n.x, n.y, n.z, p.offset, o.x, o.y, o.z, a.x, a.y, a.z, r]) {
        return not_finite();
    }
    let sc = tol::scale(&[abs_max(&o.coords), p.offset, r]);
    let (tl, tt) = (LENGTH_REL * sc, TANGENT_REL * sc);
    if r <= tl || is_zero_dir(&n) || is_zero_dir(&a) {
        return Intersection::none(Contact::ZeroRadius);
    }
    let cos = n.dot(&a);
    let delta = p.signed_distance(&o);
    let nxa = cross_accurate(&n, &a);
    let snxa = nxa.norm();
    if cos.abs() <= ANGLE {
        let g = delta.abs() - r;
        if g > tt {
            return Intersection::none(Contact::Parallel { gap: g });
        }
        // Missing by at most `tt` (rounding): touching. Cutting, however little: the two
        // lines (`r - |delta|` in `leg` is exactly `-g`, positive).
        if g >= 0.0 {
            let point = o - n * (0.5 * (delta.abs() + r)).copysign(delta);
            let l = CylinderSection::Line(Line3 { point, dir: a });
            return two(l, l, Contact::Tangent);
        }
        let side = nxa / snxa;
        let foot = o - n * delta;
        let k = leg(r, delta.abs());
        return two(
            CylinderSection::Line(Line3 {
                point: foot - side * k,
                dir: a,
            }),
            CylinderSection::Line(Line3 {
                point: foot + side * k,
                dir: a,
            }),
            Contact::Crossing,
        );
    }
    let center = o - a * (delta / cos);
    let minor = if snxa > ANGLE {
        nxa / snxa
    } else {
        let q = perpendicular(&n);
        q / q.norm()
    };
    let major = minor.cross(&n);
    one(
        CylinderSection::Ellipse(Ellipse3 {
            center,
            normal: n,
            major,
            minor,
            a: r / cos.abs(),
            b: r,
        }),
        Contact::Crossing,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::locus3d::Locus3;

    const EPS: f64 = 1e-13;

    fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
        Point3::new(x, y, z)
    }

    fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
        Vector3::new(x, y, z)
    }

    /// Every root is on both loci within `tol`.
    fn on_both(roots: &[Point3<f64>], a: &dyn Locus3, b: &dyn Locus3, tol: f64) {
        for r in roots {
            assert!(
                a.distance(r) <= tol,
                "root {r:?} off first locus by {}",
                a.distance(r)
            );
            assert!(
                b.distance(r) <= tol,
                "root {r:?} off second locus by {}",
                b.distance(r)
            );
        }
    }

    fn circle_points(c: &Circle3) -> [Point3<f64>; 4] {
        let u = perpendicular(&c.normal).normalize();
        let w = c.normal.cross(&u);
        [
            c.center + u * c.radius,
            c.center + w * c.radius,
            c.center - u * c.radius,
            c.center - w * c.radius,
        ]
    }

    #[test]
    fn sphere_sphere_cases() {
        let a = Sphere::new(p(0.0, 0.0, 0.0), 2.0);
        let b = Sphere::new(p(2.0, 0.0, 0.0), 2.0);
        let x = sphere_sphere(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        let c = x.branch(0).unwrap_or_default();
        assert!((c.center - p(1.0, 0.0, 0.0)).norm() < EPS);
        assert!((c.radius - 3f64.sqrt()).abs() < EPS);
        assert_eq!(c.normal, Vector3::x());
        on_both(&circle_points(&c), &a, &b, EPS);
        // Tangent externally and internally.
        let t = sphere_sphere(&a, &Sphere::new(p(0.0, 5.0, 0.0), 3.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.branch(0).unwrap_or_default().center - p(0.0, 2.0, 0.0)).norm() < EPS);
        let t = sphere_sphere(&a, &Sphere::new(p(0.0, 0.0, 1.0), 1.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.branch(0).unwrap_or_default().center - p(0.0, 0.0, 2.0)).norm() < EPS);
        let t = sphere_sphere(&Sphere::new(p(0.0, 0.0, 1.0), 1.0), &a);
        assert!((t.branch(0).unwrap_or_default().center - p(0.0, 0.0, 2.0)).norm() < EPS);
        // Disjoint, nested, concentric, coincident, zero radius.
        let d = sphere_sphere(&a, &Sphere::new(p(5.0, 0.0, 0.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 2.0 });
        assert!(d.roots.is_empty());
        let d = sphere_sphere(&a, &Sphere::new(p(0.5, 0.0, 0.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 0.5 });
        let d = sphere_sphere(&a, &Sphere::new(p(0.0, 0.0, 0.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 1.0 });
        assert_eq!(sphere_sphere(&a, &a).contact, Contact::Coincident);
        let z = sphere_sphere(&a, &Sphere::new(p(1.0, 0.0, 0.0), 0.0));
        assert_eq!(z.contact, Contact::ZeroRadius);
        let n = sphere_sphere(&a, &Sphere::new(p(f64::NAN, 0.0, 0.0), 1.0));
        assert!(matches!(n.contact, Contact::Disjoint { gap } if gap.is_nan()));
    }

    #[test]
    fn sphere_plane_cases() {
        let s = Sphere::new(p(1.0, 1.0, 1.0), 2.0);
        let x = sphere_plane(&s, &Plane::new(v(0.0, 0.0, 1.0), 2.0));
        assert_eq!(x.contact, Contact::Crossing);
        let c = x.branch(0).unwrap_or_default();
        assert!((c.center - p(1.0, 1.0, 2.0)).norm() < EPS);
        assert!((c.radius - 3f64.sqrt()).abs() < EPS);
        on_both(
            &circle_points(&c),
            &s,
            &Plane::new(v(0.0, 0.0, 1.0), 2.0),
            EPS,
        );
        let t = sphere_plane(&s, &Plane::new(v(0.0, 0.0, -1.0), 1.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.branch(0).unwrap_or_default().center - p(1.0, 1.0, -1.0)).norm() < EPS);
        let d = sphere_plane(&s, &Plane::new(v(0.0, 0.0, 1.0), 4.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 1.0 });
        assert_eq!(
            sphere_plane(&s, &Plane::new(v(0.0, 0.0, 0.0), 4.0)).contact,
            Contact::ZeroRadius
        );
        assert_eq!(
            sphere_plane(
                &Sphere::new(p(0.0, 0.0, 0.0), 0.0),
                &Plane::new(Vector3::z(), 0.0)
            )
            .contact,
            Contact::ZeroRadius
        );
    }

    #[test]
    fn plane_plane_cases() {
        let a = Plane::new(v(0.0, 0.0, 1.0), 1.0);
        let b = Plane::new(v(1.0, 0.0, 0.0), 2.0);
        let x = plane_plane(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        let l = x.branch(0).unwrap_or_default();
        assert_eq!(l.dir, Vector3::y());
        assert!((l.point - p(2.0, 0.0, 1.0)).norm() < EPS);
        assert_eq!(
            plane_plane(&a, &Plane::new(v(0.0, 0.0, -2.0), 4.0)).contact,
            Contact::Parallel { gap: 3.0 }
        );
        assert_eq!(
            plane_plane(&a, &Plane::new(v(0.0, 0.0, -1.0), -1.0)).contact,
            Contact::Coincident
        );
        assert_eq!(
            plane_plane(&a, &Plane::new(Vector3::zeros(), 0.0)).contact,
            Contact::ZeroRadius
        );
        // Nearly parallel: the line is far, but on both planes relative to its magnitude.
        let b = Plane::new(v(1e-9, 0.0, 1.0), 1.5);
        let l = plane_plane(&a, &b).branch(0).unwrap_or_default();
        let m = l.point.coords.norm();
        assert!(m > 1e8);
        assert!(a.distance(&l.point) <= 1e-15 * m && b.distance(&l.point) <= 1e-15 * m);
        assert!(a.normal.dot(&l.dir).abs() < 1e-15 && b.normal.dot(&l.dir).abs() < 1e-15);
    }

    #[test]
    fn line_plane_cases() {
        let l = Line3::new(p(1.0, 2.0, 3.0), v(0.0, 0.0, -2.0));
        let pl = Plane::new(v(0.0, 0.0, 1.0), 1.0);
        let x = line_plane(&l, &pl);
        assert_eq!(x.contact, Contact::Crossing);
        assert_eq!(x.branch(0), Some(p(1.0, 2.0, 1.0)));
        let par = Line3::new(p(1.0, 2.0, 3.0), v(1.0, 0.0, 0.0));
        assert_eq!(
            line_plane(&par, &pl).contact,
            Contact::Parallel { gap: 2.0 }
        );
        let inside = Line3::new(p(1.0, 2.0, 1.0), v(1.0, 1.0, 0.0));
        assert_eq!(line_plane(&inside, &pl).contact, Contact::Coincident);
        let z = Line3::new(p(1.0, 2.0, 1.0), Vector3::zeros());
        assert_eq!(line_plane(&z, &pl).contact, Contact::ZeroRadius);
    }

    #[test]
    fn line_sphere_cases() {
        let s = Sphere::new(p(0.0, 0.0, 0.0), 5.0);
        let l = Line3::new(p(3.0, -10.0, 0.0), v(0.0, 1.0, 0.0));
        let x = line_sphere(&l, &s);
        assert_eq!(x.contact, Contact::Crossing);
        assert_eq!(x.roots.as_slice(), &[p(3.0, -4.0, 0.0), p(3.0, 4.0, 0.0)]);
        // Reversing the line swaps the branches (order along the direction).
        let r = Line3::new(p(3.0, -10.0, 0.0), v(0.0, -1.0, 0.0));
        assert_eq!(
            line_sphere(&r, &s).roots.as_slice(),
            &[p(3.0, 4.0, 0.0), p(3.0, -4.0, 0.0)]
        );
        let t = line_sphere(&Line3::new(p(5.0, 7.0, 0.0), v(0.0, 1.0, 0.0)), &s);
        assert_eq!(t.contact, Contact::Tangent);
        assert_eq!(t.roots.as_slice(), &[p(5.0, 0.0, 0.0), p(5.0, 0.0, 0.0)]);
        let d = line_sphere(&Line3::new(p(6.0, 7.0, 0.0), v(0.0, 1.0, 0.0)), &s);
        assert_eq!(d.contact, Contact::Disjoint { gap: 1.0 });
        assert_eq!(
            line_sphere(&l, &Sphere::new(p(0.0, 0.0, 0.0), -1.0)).contact,
            Contact::ZeroRadius
        );
    }

    #[test]
    fn line_cylinder_cases() {
        let cy = Cylinder::new(Line3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0)), 2.0);
        let l = Line3::new(p(-5.0, 0.0, -5.0), v(1.0, 0.0, 1.0));
        let x = line_cylinder(&l, &cy);
        assert_eq!(x.contact, Contact::Crossing);
        on_both(x.roots.as_slice(), &l, &cy, EPS);
        let r = x.roots.as_slice();
        assert!((r[0] - p(-2.0, 0.0, -2.0)).norm() < EPS && (r[1] - p(2.0, 0.0, 2.0)).norm() < EPS);
        let t = line_cylinder(&Line3::new(p(2.0, -3.0, 1.0), v(0.0, 1.0, 0.0)), &cy);
        assert_eq!(t.contact, Contact::Tangent);
        assert_eq!(t.roots.len(), 2);
        assert!((t.roots.as_slice()[0] - p(2.0, 0.0, 1.0)).norm() < EPS);
        let d = line_cylinder(&Line3::new(p(3.0, -3.0, 1.0), v(0.0, 1.0, 1.0)), &cy);
        assert_eq!(d.contact, Contact::Disjoint { gap: 1.0 });
        let par = line_cylinder(&Line3::new(p(3.0, 0.0, 0.0), v(0.0, 0.0, -1.0)), &cy);
        assert_eq!(par.contact, Contact::Parallel { gap: 1.0 });
        let inside = line_cylinder(&Line3::new(p(0.5, 0.0, 0.0), v(0.0, 0.0, 1.0)), &cy);
        assert_eq!(inside.contact, Contact::Parallel { gap: 1.5 });
        let on = line_cylinder(&Line3::new(p(0.0, 2.0, 0.0), v(0.0, 0.0, 1.0)), &cy);
        assert_eq!(on.contact, Contact::Coincident);
        let z = Cylinder::new(Line3::new(p(0.0, 0.0, 0.0), Vector3::zeros()), 2.0);
        assert_eq!(line_cylinder(&l, &z).contact, Contact::ZeroRadius);
    }

    #[test]
    fn circle_plane_cases() {
        let c = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 2.0);
        let pl = Plane::new(v(1.0, 0.0, 0.0), 1.0);
        let x = circle_plane(&c, &pl);
        assert_eq!(x.contact, Contact::Crossing);
        on_both(x.roots.as_slice(), &c, &pl, EPS);
        // u = z x x = y: branch 0 has the smaller y.
        let r = x.roots.as_slice();
        assert!(r[0].y < 0.0 && r[1].y > 0.0);
        // The branch does not flip as the plane sweeps through the centre.
        for off in [-1.0, -1e-9, 0.0, 1e-9, 1.0] {
            let x = circle_plane(&c, &Plane::new(v(1.0, 0.0, 0.0), off));
            let r = x.roots.as_slice();
            assert!(r[0].y < 0.0 && r[1].y > 0.0, "{off}");
        }
        let t = circle_plane(&c, &Plane::new(v(-1.0, 0.0, 0.0), 2.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert_eq!(t.roots.len(), 2);
        assert!((t.roots.as_slice()[1] - p(-2.0, 0.0, 0.0)).norm() < EPS);
        // Tilted plane missing the circle: gap is the distance to the circle's nearest point.
        let tilted = Plane::new(v(1.0, 0.0, 1.0), 3.0 / 2f64.sqrt());
        let d = circle_plane(&c, &tilted);
        match d.contact {
            Contact::Disjoint { gap } => {
                assert!((gap - tilted.distance(&p(2.0, 0.0, 0.0))).abs() < EPS)
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            circle_plane(&c, &Plane::new(v(0.0, 0.0, 1.0), 1.0)).contact,
            Contact::Parallel { gap: 1.0 }
        );
        assert_eq!(
            circle_plane(&c, &Plane::new(v(0.0, 0.0, -1.0), 0.0)).contact,
            Contact::Coincident
        );
        let z = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 0.0);
        assert_eq!(circle_plane(&z, &pl).contact, Contact::ZeroRadius);
    }

    #[test]
    fn circle_sphere_cases() {
        let c = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 2.0);
        let s = Sphere::new(p(2.0, 0.0, 1.0), 1.5);
        let x = circle_sphere(&c, &s);
        assert_eq!(x.contact, Contact::Crossing);
        on_both(x.roots.as_slice(), &c, &s, EPS);
        // e = +x, normal x e = +y: branch 0 has positive y.
        let r = x.roots.as_slice();
        assert!(r[0].y > 0.0 && r[1].y < 0.0);
        // Tangent at the nearest and at the farthest point.
        let t = circle_sphere(&c, &Sphere::new(p(5.0, 0.0, 4.0), 5.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.roots.as_slice()[0] - p(2.0, 0.0, 0.0)).norm() < EPS);
        let t = circle_sphere(&c, &Sphere::new(p(1.0, 0.0, 0.0), 3.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.roots.as_slice()[1] - p(-2.0, 0.0, 0.0)).norm() < EPS);
        let d = circle_sphere(&c, &Sphere::new(p(5.0, 0.0, 0.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 2.0 });
        let d = circle_sphere(&c, &Sphere::new(p(0.5, 0.0, 0.0), 5.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 2.5 });
        // Sphere centred on the circle's axis: the circle lies on it, or misses it.
        let on = circle_sphere(&c, &Sphere::new(p(0.0, 0.0, 1.5), 2.5));
        assert_eq!(on.contact, Contact::Coincident);
        let off = circle_sphere(&c, &Sphere::new(p(0.0, 0.0, 1.5), 3.5));
        assert_eq!(off.contact, Contact::Disjoint { gap: 1.0 });
        assert_eq!(
            circle_sphere(&c, &Sphere::new(p(0.0, 0.0, 1.5), 0.0)).contact,
            Contact::ZeroRadius
        );
    }

    #[test]
    fn circle_circle_coplanar_cases() {
        let a = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 2.0);
        let b = Circle3::new(p(2.0, 0.0, 0.0), v(0.0, 0.0, -1.0), 2.0);
        let x = circle_circle(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        on_both(x.roots.as_slice(), &a, &b, EPS);
        // Left of the directed line of centres (+x), seen from +z: positive y first.
        let r = x.roots.as_slice();
        assert!(r[0].y > 0.0 && r[1].y < 0.0);
        let t = circle_circle(&a, &Circle3::new(p(3.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 1.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.roots.as_slice()[0] - p(2.0, 0.0, 0.0)).norm() < EPS);
        let t = circle_circle(&a, &Circle3::new(p(-1.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 1.0));
        assert_eq!(t.contact, Contact::Tangent);
        assert!((t.roots.as_slice()[1] - p(-2.0, 0.0, 0.0)).norm() < EPS);
        let d = circle_circle(&a, &Circle3::new(p(5.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 2.0 });
        let d = circle_circle(&a, &Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 1.0));
        assert_eq!(d.contact, Contact::Disjoint { gap: 1.0 });
        assert_eq!(circle_circle(&a, &a).contact, Contact::Coincident);
        let par = circle_circle(&a, &Circle3::new(p(1.0, 0.0, 3.0), v(0.0, 0.0, 1.0), 2.0));
        assert_eq!(par.contact, Contact::Parallel { gap: 3.0 });
    }

    #[test]
    fn circle_circle_spatial_cases() {
        // Two unit circles through (1,0,0) and (-1,0,0): one in z=0, one in y=0.
        let a = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 1.0);
        let b = Circle3::new(p(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 1.0);
        let x = circle_circle(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        // L directed along z x y = -x: branch 0 has the larger x.
        assert_eq!(x.roots.as_slice(), &[p(1.0, 0.0, 0.0), p(-1.0, 0.0, 0.0)]);
        // Linked circles meeting in one point (a chain link through the other).
        let b = Circle3::new(p(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 2.0);
        let x = circle_circle(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        assert_eq!(x.roots.as_slice(), &[p(-1.0, 0.0, 0.0), p(-1.0, 0.0, 0.0)]);
        // Touching L: the circle in y=1 meets z=0 only at (0,1,0).
        let b = Circle3::new(p(0.0, 1.0, 1.0), v(1.0, 0.0, 0.0), 1.0);
        let x = circle_circle(&a, &b);
        assert_eq!(x.contact, Contact::Tangent);
        assert!((x.roots.as_slice()[0] - p(0.0, 1.0, 0.0)).norm() < EPS);
        // Missing: the gap is the distance between nearest points on L.
        let b = Circle3::new(p(3.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 1.0);
        assert_eq!(
            circle_circle(&a, &b).contact,
            Contact::Disjoint { gap: 1.0 }
        );
        // One circle does not reach L.
        let b = Circle3::new(p(0.0, 0.0, 3.0), v(0.0, 1.0, 0.0), 1.0);
        match circle_circle(&a, &b).contact {
            Contact::Disjoint { gap } => assert!(gap > 2.0 && gap <= 5f64.sqrt()),
            other => panic!("{other:?}"),
        }
        assert_eq!(
            circle_circle(&a, &Circle3::new(p(0.0, 0.0, 0.0), Vector3::zeros(), 1.0)).contact,
            Contact::ZeroRadius
        );
    }

    #[test]
    fn plane_cylinder_lines_are_the_parallel_sections() {
        let cy = Cylinder::new(Line3::new(p(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0)), 2.0);
        // Parallel to the axis, 1 from it: two lines, in the order of `plane_cylinder`.
        let pl = Plane::new(v(1.0, 0.0, 0.0), 2.0);
        let x = plane_cylinder_lines(&pl, &cy);
        assert_eq!(x.contact, Contact::Crossing);
        let (a, b) = (
            x.branch(0).unwrap_or_default(),
            x.branch(1).unwrap_or_default(),
        );
        assert!(a.point.y > 0.0 && b.point.y < 0.0);
        for l in [a, b] {
            for t in [0.0, 5.0] {
                assert!(cy.distance(&l.at(t)) < EPS && pl.distance(&l.at(t)) < EPS);
            }
        }
        // Touching, missing, and tilted (an ellipse: not this meeting's).
        let t = plane_cylinder_lines(&Plane::new(v(1.0, 0.0, 0.0), 3.0), &cy);
        assert_eq!(t.contact, Contact::Tangent);
        let m = plane_cylinder_lines(&Plane::new(v(1.0, 0.0, 0.0), 3.5), &cy);
        assert!(matches!(m.contact, Contact::Parallel { gap } if (gap - 0.5).abs() < EPS));
        let tilted = Plane::from_point_normal(&p(1.0, 0.0, 3.0), &v(1.0, 0.0, 1.0));
        let e = plane_cylinder_lines(&tilted, &cy);
        assert_eq!(e.contact, Contact::Coincident);
        assert!(e.roots.is_empty());
    }

    #[test]
    fn plane_cylinder_cases() {
        let cy = Cylinder::new(Line3::new(p(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0)), 2.0);
        // Tilted plane through z = 3 on the axis: an ellipse.
        let pl = Plane::from_point_normal(&p(1.0, 0.0, 3.0), &v(1.0, 0.0, 1.0));
        let x = plane_cylinder(&pl, &cy);
        assert_eq!(x.contact, Contact::Crossing);
        assert_eq!(x.roots.len(), 1);
        let CylinderSection::Ellipse(e) = x.branch(0).unwrap_or_default() else {
            panic!("expected an ellipse")
        };
        assert!((e.center - p(1.0, 0.0, 3.0)).norm() < EPS);
        assert!((e.a - 2.0 * 2f64.sqrt()).abs() < EPS && (e.b - 2.0).abs() < EPS);
        for i in 0..12 {
            let q = e.point_at(i as f64 * 0.5);
            assert!(pl.distance(&q) < EPS && cy.distance(&q) < EPS);
        }
        // Perpendicular plane: a circle.
        let x = plane_cylinder(&Plane::new(v(0.0, 0.0, 1.0), 1.0), &cy);
        let CylinderSection::Ellipse(e) = x.branch(0).unwrap_or_default() else {
            panic!("expected an ellipse")
        };
        assert!((e.a - 2.0).abs() < EPS && (e.b - 2.0).abs() < EPS);
        // Parallel to the axis: two lines, one, or none.
        let x = plane_cylinder(&Plane::new(v(1.0, 0.0, 0.0), 2.0), &cy);
        assert_eq!(x.contact, Contact::Crossing);
        let lines: Vec<Line3> = x
            .roots
            .as_slice()
            .iter()
            .filter_map(|s| match s {
                CylinderSection::Line(l) => Some(*l),
                CylinderSection::Ellipse(_) => None,
            })
            .collect();
        assert_eq!(lines.len(), 2);
        // normal x axis = x x z = -y: branch 0 has the larger y.
        assert!(lines[0].point.y > 0.0 && lines[1].point.y < 0.0);
        for l in &lines {
            assert!(cy.distance(&l.point) < EPS && cy.distance(&l.at(7.0)) < EPS);
            assert!((l.point.x - 2.0).abs() < EPS);
        }
        let t = plane_cylinder(&Plane::new(v(1.0, 0.0, 0.0), 3.0), &cy);
        assert_eq!(t.contact, Contact::Tangent);
        assert_eq!(t.roots.len(), 2);
        let m = plane_cylinder(&Plane::new(v(1.0, 0.0, 0.0), 4.0), &cy);
        assert_eq!(m.contact, Contact::Parallel { gap: 1.0 });
        assert_eq!(
            plane_cylinder(
                &Plane::new(v(1.0, 0.0, 0.0), 4.0),
                &Cylinder::new(cy.axis, 0.0)
            )
            .contact,
            Contact::ZeroRadius
        );
    }

    #[test]
    fn cross_accurate_keeps_digits_of_nearly_parallel_vectors() {
        let a = v(1.0, 0.0, 0.0);
        let b = v(1.0, 1e-12, 3e-13).normalize();
        let c = cross_accurate(&a, &b);
        assert!((c.z - b.y).abs() <= 1e-28 && (c.y + b.z).abs() <= 1e-28);
        assert_eq!(diff_of_products(3.0, 5.0, 2.0, 7.0), 1.0);
    }

    // -----------------------------------------------------------------------------------------
    // Near tangency: a miss of at most the tolerance touches, any overlap crosses.

    /// The scales of the near-tangency sweeps: near-degenerate small and large, and unit.
    const SCALES: [f64; 3] = [1e-3, 1.0, 1e3];

    /// Overlaps in units of `f64::EPSILON` times the kernel's scale of the inputs, shrinking
    /// from ten times the tangency tolerance (`TANGENT_REL` is 32 of them) to a few.
    const OVERLAPS: [f64; 8] = [320.0, 128.0, 64.0, 32.0, 16.0, 8.0, 6.0, 4.0];

    /// Misses within the tangency tolerance, in the same units (rounding of the oblique inputs
    /// moves them by a few).
    const TOUCHING: [f64; 4] = [6.0, 12.0, 20.0, 26.0];

    /// Misses beyond it, in the same units.
    const MISSING: [f64; 4] = [40.0, 64.0, 320.0, 1e6];

    /// A configuration built with a signed gap (negative: overlapping): the kernel's scale of
    /// its inputs, the contact, each root slot sampled as points (a point, or points of a
    /// circle or a line), the two loci, and the locus (a point, or a line) where they touch at
    /// gap zero.
    struct Near {
        scale: f64,
        contact: Contact,
        slots: Vec<Vec<Point3<f64>>>,
        /// Two distinct roots, or a circle of positive radius.
        distinct: bool,
        a: Box<dyn Locus3>,
        b: Box<dyn Locus3>,
        touch: Box<dyn Locus3>,
    }

    /// A point as a locus: the sphere of radius zero about it.
    fn at(q: Point3<f64>) -> Box<dyn Locus3> {
        Box::new(Sphere::new(q, 0.0))
    }

    /// The kernel's scale: the largest absolute coordinate, radius or offset.
    fn scale_of(points: &[Point3<f64>], lengths: &[f64]) -> f64 {
        let coords = points.iter().flat_map(|q| [q.x, q.y, q.z]);
        coords
            .chain(lengths.iter().copied())
            .fold(0.0, |m, x| m.max(x.abs()))
    }

    fn near_points<A: Locus3 + 'static, B: Locus3 + 'static>(
        scale: f64,
        x: Intersection<Point3<f64>, 2>,
        a: A,
        b: B,
        touch: Box<dyn Locus3>,
    ) -> Near {
        let r = x.roots.as_slice();
        Near {
            scale,
            contact: x.contact,
            slots: r.iter().map(|q| vec![*q]).collect(),
            distinct: r.len() == 2 && r[0] != r[1],
            a: Box::new(a),
            b: Box::new(b),
            touch,
        }
    }

    fn near_circle<A: Locus3 + 'static, B: Locus3 + 'static>(
        scale: f64,
        x: Intersection<Circle3, 1>,
        a: A,
        b: B,
        touch: Point3<f64>,
    ) -> Near {
        let c = x.branch(0);
        Near {
            scale,
            contact: x.contact,
            slots: c
                .map(|c| vec![circle_points(&c).to_vec()])
                .unwrap_or_default(),
            distinct: c.is_some_and(|c| c.radius > 0.0),
            a: Box::new(a),
            b: Box::new(b),
            touch: at(touch),
        }
    }

    /// An orthonormal frame of oblique directions, exact in the reals: `(2, 3, 6) / 7`,
    /// `(3, -6, 2) / 7`, `(6, 2, -3) / 7`.
    fn frame() -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        (
            v(2.0, 3.0, 6.0) / 7.0,
            v(3.0, -6.0, 2.0) / 7.0,
            v(6.0, 2.0, -3.0) / 7.0,
        )
    }

    /// A centre off the origin, at scale `s`.
    fn origin(s: f64) -> Point3<f64> {
        p(0.3, -0.7, 0.2) * s
    }

    /// For each scale `s` of [`SCALES`], with `S` the kernel's scale of the inputs built at
    /// `s` and `ulp = f64::EPSILON * S`: every overlap of [`OVERLAPS`] crosses, in two distinct
    /// roots (or a circle of positive radius) on both loci to `1e-13 S`, within
    /// `4 sqrt(overlap S)` of the touching point and no nearer than a twentieth of that (not
    /// snapped), converging on it as the overlap shrinks; every miss of [`TOUCHING`] touches,
    /// in one root in every slot within `TANGENT_REL * S / 2` (and rounding) of both loci and
    /// `TANGENT_REL * S` of the touching point; every miss of [`MISSING`] gives no root and its
    /// gap (`Parallel` rather than `Disjoint` when `parallel`).
    fn sweep(name: &str, parallel: bool, build: impl Fn(f64, f64) -> Near) {
        for s in SCALES {
            let big = build(s, 0.0).scale;
            let ulp = f64::EPSILON * big;
            let tt = TANGENT_REL * big;
            let mut farthest = Vec::new();
            for k in OVERLAPS {
                let delta = k * ulp;
                let n = build(s, -delta);
                let what = format!("{name}: scale {s}, overlap of {k} ulps");
                assert_eq!(n.contact, Contact::Crossing, "{what}");
                assert!(n.distinct && !n.slots.is_empty(), "{what}: {:?}", n.slots);
                let mut far: f64 = 0.0;
                for r in n.slots.iter().flatten() {
                    let (da, db) = (n.a.distance(r), n.b.distance(r));
                    assert!(
                        da <= EPS * big && db <= EPS * big,
                        "{what}: off by {da:e}, {db:e}"
                    );
                    far = far.max(n.touch.distance(r));
                }
                let chord = (delta * big).sqrt();
                assert!(
                    far <= 4.0 * chord && far >= 0.05 * chord,
                    "{what}: {far:e} from the touching point, sqrt(overlap scale) {chord:e}"
                );
                farthest.push(far);
            }
            // Converging: the roots of the smallest overlap are far nearer than the largest's.
            let (first, last) = (farthest[0], farthest[farthest.len() - 1]);
            assert!(last <= 0.25 * first, "{name}: scale {s}: {farthest:?}");
            for k in TOUCHING {
                let n = build(s, k * ulp);
                let what = format!("{name}: scale {s}, miss of {k} ulps");
                assert_eq!(n.contact, Contact::Tangent, "{what}");
                assert!(!n.distinct && !n.slots.is_empty(), "{what}");
                for slot in &n.slots {
                    assert_eq!(slot, &n.slots[0], "{what}");
                }
                for r in n.slots.iter().flatten() {
                    let (da, db) = (n.a.distance(r), n.b.distance(r));
                    let bound = 0.5 * tt + 4.0 * ulp;
                    assert!(da <= bound && db <= bound, "{what}: off by {da:e}, {db:e}");
                    assert!(n.touch.distance(r) <= tt, "{what}");
                }
            }
            for k in MISSING {
                let gap = k * ulp;
                let n = build(s, gap);
                let what = format!("{name}: scale {s}, miss of {k} ulps");
                let g = match (n.contact, parallel) {
                    (Contact::Disjoint { gap }, false) | (Contact::Parallel { gap }, true) => gap,
                    (other, _) => panic!("{what}: {other:?}"),
                };
                assert!((g - gap).abs() <= 8.0 * ulp, "{what}: gap {g:e}");
                assert!(n.slots.is_empty(), "{what}");
            }
        }
    }

    #[test]
    fn sphere_sphere_overlap_crosses_miss_touches() {
        let (u, _, _) = frame();
        let near = |a: Sphere, b: Sphere, touch| {
            let big = scale_of(&[a.center, b.center], &[a.radius, b.radius]);
            near_circle(big, sphere_sphere(&a, &b), a, b, touch)
        };
        // Apart (gap d - ra - rb), and nested either way (gap |ra - rb| - d).
        sweep("sphere_sphere apart", false, |s, g| {
            let (c, ra, rb) = (origin(s), 1.5 * s, 0.5 * s);
            let b = Sphere::new(c + u * (ra + rb + g), rb);
            near(Sphere::new(c, ra), b, c + u * ra)
        });
        sweep("sphere_sphere second inside", false, |s, g| {
            let (c, ra, rb) = (origin(s), 2.0 * s, s);
            let b = Sphere::new(c + u * (ra - rb - g), rb);
            near(Sphere::new(c, ra), b, c + u * ra)
        });
        sweep("sphere_sphere first inside", false, |s, g| {
            let (c, ra, rb) = (origin(s), 0.5 * s, 2.0 * s);
            let b = Sphere::new(c - u * (rb - ra - g), rb);
            near(Sphere::new(c, ra), b, c + u * ra)
        });
    }

    #[test]
    fn sphere_plane_overlap_crosses_miss_touches() {
        let (u, _, _) = frame();
        sweep("sphere_plane", false, |s, g| {
            let (c, r) = (origin(s), s);
            let (sp, pl) = (Sphere::new(c, r), Plane::new(u, u.dot(&c.coords) + r + g));
            let big = scale_of(&[c], &[r, pl.offset]);
            near_circle(big, sphere_plane(&sp, &pl), sp, pl, c + u * r)
        });
    }

    #[test]
    fn line_sphere_overlap_crosses_miss_touches() {
        let (u, w, _) = frame();
        sweep("line_sphere", false, |s, g| {
            let (c, r) = (origin(s), s);
            let sp = Sphere::new(c, r);
            let l = Line3::new(c + u * (r + g) + w * (0.4 * s), w);
            let big = scale_of(&[l.point, c], &[r]);
            near_points(big, line_sphere(&l, &sp), l, sp, at(c + u * r))
        });
    }

    #[test]
    fn line_cylinder_overlap_crosses_miss_touches() {
        let (u, w, z) = frame();
        sweep("line_cylinder", false, |s, g| {
            let (c, r) = (origin(s), s);
            let cy = Cylinder::new(Line3::new(c, z), r);
            // Perpendicular to the radial direction `u`, at 53 degrees to the axis.
            let l = Line3::new(c + u * (r + g) + z * (0.3 * s), z * 0.6 + w * 0.8);
            let big = scale_of(&[l.point, c], &[r]);
            let touch = at(c + u * r + z * (0.3 * s));
            near_points(big, line_cylinder(&l, &cy), l, cy, touch)
        });
    }

    #[test]
    fn circle_plane_overlap_crosses_miss_touches() {
        let (u, _, z) = frame();
        // The plane touches the circle at `c + u r`, tilted: `su = 0.6`, so the circle misses
        // the planes' common line by `gap / 0.6`, more than the tolerance for misses near it.
        sweep("circle_plane", false, |s, g| {
            let (c, r) = (origin(s), s);
            let ci = Circle3::new(c, z, r);
            let t = c + u * r;
            let n = u * 0.6 + z * 0.8;
            let pl = Plane::new(n, n.dot(&t.coords) + g);
            let big = scale_of(&[c], &[r, pl.offset]);
            near_points(big, circle_plane(&ci, &pl), ci, pl, at(t))
        });
    }

    #[test]
    fn circle_sphere_overlap_crosses_miss_touches() {
        let (u, _, z) = frame();
        // The sphere's centre 1.2 s out along `u` and 0.5 s above the circle's plane: at the
        // circle's nearest point `c + u r` the sphere touches from outside, at the farthest
        // `c - u r` from inside.
        let near = |ci: Circle3, sp: Sphere, touch| {
            let big = scale_of(&[ci.center, sp.center], &[ci.radius, sp.radius]);
            near_points(big, circle_sphere(&ci, &sp), ci, sp, at(touch))
        };
        let centre = |s: f64| origin(s) + u * (1.2 * s) + z * (0.5 * s);
        sweep("circle_sphere nearest", false, |s, g| {
            let (c, r) = (origin(s), s);
            let sp = Sphere::new(centre(s), (0.5 * s).hypot(0.2 * s) - g);
            near(Circle3::new(c, z, r), sp, c + u * r)
        });
        sweep("circle_sphere farthest", false, |s, g| {
            let (c, r) = (origin(s), s);
            let sp = Sphere::new(centre(s), (0.5 * s).hypot(2.2 * s) + g);
            near(Circle3::new(c, z, r), sp, c - u * r)
        });
    }

    #[test]
    fn circle_circle_coplanar_overlap_crosses_miss_touches() {
        let (u, _, z) = frame();
        let near = |a: Circle3, b: Circle3| {
            let big = scale_of(&[a.center, b.center], &[a.radius, b.radius]);
            let touch = at(a.center + u * a.radius);
            near_points(big, circle_circle(&a, &b), a, b, touch)
        };
        sweep("circle_circle apart", false, |s, g| {
            let (c, ra, rb) = (origin(s), 1.5 * s, 0.5 * s);
            near(
                Circle3::new(c, z, ra),
                Circle3::new(c + u * (ra + rb + g), -z, rb),
            )
        });
        sweep("circle_circle second inside", false, |s, g| {
            let (c, ra, rb) = (origin(s), 2.0 * s, s);
            near(
                Circle3::new(c, z, ra),
                Circle3::new(c + u * (ra - rb - g), z, rb),
            )
        });
        sweep("circle_circle first inside", false, |s, g| {
            let (c, ra, rb) = (origin(s), 0.5 * s, 2.0 * s);
            near(
                Circle3::new(c, z, ra),
                Circle3::new(c - u * (rb - ra - g), z, rb),
            )
        });
    }

    #[test]
    fn plane_cylinder_overlap_crosses_miss_touches() {
        let (u, _, z) = frame();
        sweep("plane_cylinder", true, |s, g| {
            let (c, r) = (origin(s), s);
            let cy = Cylinder::new(Line3::new(c, z), r);
            let pl = Plane::new(u, u.dot(&c.coords) + r + g);
            let x = plane_cylinder(&pl, &cy);
            let lines: Vec<Line3> = x
                .roots
                .as_slice()
                .iter()
                .filter_map(|sec| match sec {
                    CylinderSection::Line(l) => Some(*l),
                    CylinderSection::Ellipse(_) => None,
                })
                .collect();
            assert_eq!(lines.len(), x.roots.len());
            Near {
                scale: scale_of(&[c], &[pl.offset, r]),
                contact: x.contact,
                slots: lines
                    .iter()
                    .map(|l| vec![l.point, l.at(s), l.at(-3.0 * s)])
                    .collect(),
                distinct: lines.len() == 2 && lines[0].point != lines[1].point,
                a: Box::new(pl),
                b: Box::new(cy),
                touch: Box::new(Line3::new(c + u * r, z)),
            }
        });
    }

    /// Overlaps of a unit in the last place, built exactly (axis-aligned, exact coordinates):
    /// every function crosses, with a half chord (or a circle's radius) within `1e-12` of the
    /// exact one, where one from a rounded foot (`leg(r, h)` with `h` rounded) is zero or off
    /// by a factor.
    #[test]
    fn one_ulp_overlaps_cross_with_the_exact_half_chord() {
        let close = |got: f64, want: f64, what: &str| {
            assert!(
                (got - want).abs() <= 1e-12 * want,
                "{what}: {got:e} for {want:e}"
            );
        };
        let half = |x: &Intersection<Point3<f64>, 2>, what: &str| {
            assert_eq!(x.contact, Contact::Crossing, "{what}");
            let r = x.roots.as_slice();
            0.5 * (r[1] - r[0]).norm()
        };
        let o = p(0.0, 0.0, 0.0);
        // Radii 1.5 and 0.5, centres 2 - 2^-51 apart: the radius by Heron's factors.
        let e = 2f64.powi(-51);
        let d = 2.0 - e;
        let heron = (e * (d - 1.0) * (d + 1.0) * (d + 2.0)).sqrt() / (2.0 * d);
        let (a, b) = (Sphere::new(o, 1.5), Sphere::new(p(d, 0.0, 0.0), 0.5));
        let x = sphere_sphere(&a, &b);
        assert_eq!(x.contact, Contact::Crossing);
        let c = x.branch(0).unwrap_or_default();
        close(c.radius, heron, "sphere_sphere");
        on_both(&circle_points(&c), &a, &b, EPS);
        let z = Vector3::z();
        let (a, b) = (
            Circle3::new(o, z, 1.5),
            Circle3::new(p(d, 0.0, 0.0), z, 0.5),
        );
        let x = circle_circle(&a, &b);
        close(half(&x, "circle_circle"), heron, "circle_circle");
        on_both(x.roots.as_slice(), &a, &b, EPS);
        // A unit sphere, cylinder or circle met 1 - 2^-53 from its centre or axis.
        let e = 2f64.powi(-53);
        let m = 1.0 - e;
        let chord = (e * (1.0 + m)).sqrt();
        let sp = Sphere::new(o, 1.0);
        let pl = Plane::new(z, m);
        let x = sphere_plane(&sp, &pl);
        assert_eq!(x.contact, Contact::Crossing);
        let c = x.branch(0).unwrap_or_default();
        close(c.radius, chord, "sphere_plane");
        on_both(&circle_points(&c), &sp, &pl, EPS);
        let l = Line3::new(p(m, -2.0, 0.0), Vector3::y());
        let x = line_sphere(&l, &sp);
        close(half(&x, "line_sphere"), chord, "line_sphere");
        on_both(x.roots.as_slice(), &l, &sp, EPS);
        let cy = Cylinder::new(Line3::new(o, z), 1.0);
        let l = Line3::new(p(m, -2.0, 0.5), Vector3::y());
        let x = line_cylinder(&l, &cy);
        close(half(&x, "line_cylinder"), chord, "line_cylinder");
        on_both(x.roots.as_slice(), &l, &cy, EPS);
        let ci = Circle3::new(o, z, 1.0);
        let pl = Plane::new(Vector3::x(), m);
        let x = circle_plane(&ci, &pl);
        close(half(&x, "circle_plane"), chord, "circle_plane");
        on_both(x.roots.as_slice(), &ci, &pl, EPS);
        let x = plane_cylinder(&pl, &cy);
        assert_eq!(x.contact, Contact::Crossing);
        let points: Vec<Point3<f64>> = x
            .roots
            .as_slice()
            .iter()
            .map(|sec| match sec {
                CylinderSection::Line(l) => l.point,
                CylinderSection::Ellipse(_) => panic!("a line expected"),
            })
            .collect();
        close(
            0.5 * (points[1] - points[0]).norm(),
            chord,
            "plane_cylinder",
        );
        on_both(&points, &pl, &cy, EPS);
        // The unit circle about z and a sphere centred at (2, 0, 0.75), 1.25 from the circle's
        // nearest point, of radius 1.25 + 2^-52; or centred at (3, 0, 3), 5 from its farthest
        // point, of radius 5 - 2^-50. The root is `x = (rs^2 - dmin^2) / 2 rho` (or
        // `(dmax^2 - rs^2) / 2 rho`) from that point along the line of centres, and
        // `sqrt(x (2 - x))` off it.
        for (cs, rs, end, what) in [
            (
                p(2.0, 0.0, 0.75),
                1.25 + 2f64.powi(-52),
                1.25,
                "circle_sphere nearest",
            ),
            (
                p(3.0, 0.0, 3.0),
                5.0 - 2f64.powi(-50),
                5.0,
                "circle_sphere farthest",
            ),
        ] {
            let sp = Sphere::new(cs, rs);
            let x = circle_sphere(&ci, &sp);
            let along = (rs - end).abs() * (rs + end) / (2.0 * cs.x);
            close(half(&x, what), (along * (2.0 - along)).sqrt(), what);
            on_both(x.roots.as_slice(), &ci, &sp, EPS);
        }
    }
}
