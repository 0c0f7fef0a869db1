//! The 2d locus intersection table: one function per pair of loci that locus analysis meets.
//!
//! Every function returns an [`Intersection`]: the roots in a fixed-capacity [`Roots`] (no
//! allocation) and a [`Contact`] classification. Slot `i` is branch `i`, and each function
//! documents what its index means:
//! - **sign-separated roots** keep the sign as the index: circle-circle branch 0 is to the left
//!   of the directed line from the first centre to the second; line-circle and line-conic order
//!   along the line's direction. A motion that passes no singularity keeps its branch.
//! - **ray functions** with two roots return `Option<P2>` slots that keep the supporting line's
//!   branch index: a root behind the ray's origin is `None` in its slot rather than shifting the
//!   next root into it, so branch 1 never silently becomes branch 0.
//! - **polynomial roots** (circle-conic, conic-conic) are ordered by ascending parameter along
//!   the conic that is parametrised (documented per function); use [`nearest`] to follow a
//!   branch through a sweep.
//!
//! Tangency: when the loci touch, or miss by at most [`tol::TANGENT_REL`] times the scale of
//! the inputs (rounding), the contact is [`Contact::Tangent`] and the touching point fills
//! **both** slots it merges; such a root lies within that tolerance of both loci. Loci that
//! overlap, however little, cross: line-circle and circle-circle then return their two exact
//! roots (which merge continuously at tangency), so a solvable near-tangent assembly is solved
//! to rounding rather than snapped. Transversal roots lie on
//! both to rounding (relative 1e-13 of the scale, or of the root's distance from the origin when
//! nearly parallel lines cross far away).
//!
//! Disjoint loci report the gap: the distance by which they miss at their closest approach
//! (exact for lines, rays, circles and line-conic; for circle-conic and conic-conic, the
//! distance from the second locus of the first locus's point where the intersection polynomial
//! comes closest to zero, which is exact for circle-parabola and a close estimate otherwise).
//!
//! Zero-size loci: a circle of radius within [`tol::LENGTH_REL`] of the scale is a point (a
//! zero distance, a circle of zero radius), and its intersection with another locus is unique
//! when the point lies on it: [`Contact::Tangent`], the point in the two slots it merges, as for
//! any touching loci; otherwise [`Contact::Disjoint`] with the point's distance from the locus.
//! Two zero-size circles meet where they are one point. Such a meeting is no degenerate
//! configuration: the answer is determined, and the plan solves it (`on(B, base)` with
//! `distance(A, B) = 0` and `A` on `base` puts `B` at `A`). What stays degenerate is a locus
//! that determines nothing: two coincident circles of the same non-zero radius
//! ([`Contact::Coincident`]), a conic that is the circle.
//!
//! Non-finite input cannot be built (constructors of [`crate::locus2d`] refuse it); inputs so
//! large that intermediate squares overflow (|coordinates| beyond about 1e150) give
//! `Disjoint { gap: f64::INFINITY }` rather than NaN roots, except in [`circle_circle`], which
//! rescales by a power of two and solves circles at any finite scale (an infinite gap then
//! means roots beyond `f64`). Nothing here panics or allocates.

use crate::locus2d::{cross, finite_p, perp, Circle, Conic, Focal, Line, Rational, Ray, P2, V2};
use crate::poly;
use crate::roots::{Contact, Intersection, Roots};
use crate::tol;

/// The index of the root nearest to `reference`, to follow a branch through a sweep.
pub fn nearest<const N: usize>(roots: &Roots<P2, N>, reference: P2) -> Option<usize> {
    roots.nearest_to(reference, |a, b| (a - b).norm())
}

fn overflow<T: Copy + Default, const N: usize>() -> Intersection<T, N> {
    Intersection::none(Contact::Disjoint { gap: f64::INFINITY })
}

#[inline]
fn line_scale(l: &Line) -> [f64; 2] {
    [l.point().x, l.point().y]
}

#[inline]
fn circle_scale(c: &Circle) -> [f64; 3] {
    [c.center().x, c.center().y, c.radius()]
}

/// Two lines.
///
/// One branch: the crossing point. Degenerate cases: directions parallel within
/// [`tol::ANGLE`] (sine of the angle): [`Contact::Coincident`] when the lines are within
/// [`tol::LENGTH_REL`] of the scale of each other, else [`Contact::Parallel`] with their
/// distance. Nearly parallel lines beyond that tolerance cross far away; the root is then exact
/// relative to its own distance from the origin.
#[inline]
pub fn line_line(a: &Line, b: &Line) -> Intersection<P2, 1> {
    let s = tol::scale(&[a.point().x, a.point().y, b.point().x, b.point().y]);
    let sin = cross(a.dir(), b.dir());
    if sin.abs() <= tol::ANGLE {
        let gap = a.signed_distance(b.point()).abs();
        return if gap <= tol::LENGTH_REL * s {
            Intersection::none(Contact::Coincident)
        } else {
            Intersection::none(Contact::Parallel { gap })
        };
    }
    let t = cross(b.point() - a.point(), b.dir()) / sin;
    let x = a.at(t);
    if !finite_p(x) {
        return overflow();
    }
    Intersection {
        roots: Roots::from_slice(&[x]),
        contact: Contact::Crossing,
    }
}

/// A line and a ray.
///
/// One branch: the crossing point, when it is on the ray (parameter `≥ -`[`tol::LENGTH_REL`]
/// of the scale). The ray pointing away from the line gives [`Contact::Disjoint`] with the
/// distance of its origin from the line. Parallel and coincident (the ray lies on the line) as
/// in [`line_line`].
pub fn line_ray(l: &Line, r: &Ray) -> Intersection<P2, 1> {
    let i = line_line(l, &r.line());
    let Some(x) = i.branch(0) else { return i };
    let s = tol::scale(&[l.point().x, l.point().y, r.origin().x, r.origin().y]);
    if r.param_of(x) >= -tol::LENGTH_REL * s {
        i
    } else {
        Intersection::none(Contact::Disjoint {
            gap: l.residual(r.origin()),
        })
    }
}

/// Two rays.
///
/// One branch: the crossing point when it is on both rays. Degenerate cases:
/// - supporting lines cross outside a ray: [`Contact::Disjoint`], gap the smallest distance
///   between the rays (from an origin to the other ray);
/// - parallel distinct lines: [`Contact::Parallel`] with their distance;
/// - collinear, same direction, or opposite directions facing each other: [`Contact::Coincident`]
///   (they share a ray or a segment);
/// - collinear, opposite directions, origins within tolerance: [`Contact::Tangent`], the one
///   root the midpoint of the origins;
/// - collinear, opposite directions, pointing apart: [`Contact::Disjoint`], gap between origins.
pub fn ray_ray(a: &Ray, b: &Ray) -> Intersection<P2, 1> {
    let s = tol::scale(&[a.origin().x, a.origin().y, b.origin().x, b.origin().y]);
    let eps = tol::LENGTH_REL * s;
    let i = line_line(&a.line(), &b.line());
    match i.contact {
        Contact::Crossing => {
            let Some(x) = i.branch(0) else { return i };
            if a.param_of(x) >= -eps && b.param_of(x) >= -eps {
                i
            } else {
                let gap = a.residual(b.origin()).min(b.residual(a.origin()));
                Intersection::none(Contact::Disjoint { gap })
            }
        }
        Contact::Coincident => {
            if a.dir().dot(&b.dir()) > 0.0 {
                return i;
            }
            let t = a.param_of(b.origin());
            if t > eps {
                i
            } else if t >= -eps {
                let m = nalgebra::center(&a.origin(), &b.origin());
                Intersection {
                    roots: Roots::from_slice(&[m]),
                    contact: Contact::Tangent,
                }
            } else {
                Intersection::none(Contact::Disjoint { gap: -t })
            }
        }
        _ => i,
    }
}

/// Parameters along `l` of its crossings with `c`, ascending, with the contact.
#[inline]
fn line_circle_t(l: &Line, c: &Circle) -> (Roots<f64, 2>, Contact) {
    let [px, py] = line_scale(l);
    let [cx, cy, r] = circle_scale(c);
    let s = tol::scale(&[px, py, cx, cy, r]);
    // A circle of zero radius is a point: the tests below find it on the line (tangent, one
    // root) or off it (disjoint, by its distance).
    let sd = l.signed_distance(c.center());
    let t0 = l.param_of(c.center());
    let gap = sd.abs() - r;
    if !gap.is_finite() || !t0.is_finite() {
        return (Roots::new(), Contact::Disjoint { gap: f64::INFINITY });
    }
    if (0.0..=tol::TANGENT_REL * s).contains(&gap) {
        // Missing by rounding: the point midway between the line's and the circle's closest
        // points (the foot of the centre moved by half the gap towards the circle's point).
        // Overlapping loci, however little, cross: their two roots are computed exactly below.
        return (Roots::from_slice(&[t0, t0]), Contact::Tangent);
    }
    if gap > 0.0 {
        return (Roots::new(), Contact::Disjoint { gap });
    }
    let (inside, outside) = (r - sd.abs(), r + sd.abs());
    let product = inside * outside;
    // Past about 1e154 the product overflows, where each factor's root does not.
    let h = if product.is_finite() {
        product.sqrt()
    } else {
        inside.sqrt() * outside.sqrt()
    };
    let (first, second) = (t0 - h, t0 + h);
    if !first.is_finite() || !second.is_finite() {
        // Roots beyond `f64`.
        return (Roots::new(), Contact::Disjoint { gap: f64::INFINITY });
    }
    let contact = if h > 0.0 {
        Contact::Crossing
    } else {
        Contact::Tangent
    };
    (Roots::from_slice(&[first, second]), contact)
}

/// The tangent point of a line and a circle: midway between the foot of the centre on the line
/// and the circle's nearest point.
fn line_circle_tangent_point(l: &Line, c: &Circle) -> P2 {
    let foot = l.at(l.param_of(c.center()));
    let sd = l.signed_distance(c.center());
    // The circle's point nearest the line: from the centre towards the line.
    let towards = if sd >= 0.0 { -l.normal() } else { l.normal() };
    let on_circle = c.center() + towards * c.radius();
    nalgebra::center(&foot, &on_circle)
}

/// A line and a circle.
///
/// Branch 0 is the first crossing along the line's direction, branch 1 the second.
/// Degenerate cases: a circle of zero radius is its centre (see the module's zero-size loci);
/// [`Contact::Tangent`] when the distance of the centre from
/// the line is the radius within [`tol::TANGENT_REL`] of the scale, the touching point (midway
/// between the line's and the circle's closest points) in both slots; [`Contact::Disjoint`] with
/// gap `|sd| - r` when the line misses.
///
/// Always inlined, for the reason [`circle_circle_chord`] is: a solve that is itself inlined
/// called it out of line otherwise (the slider-crank 1.2x slower).
#[inline(always)]
pub fn line_circle(l: &Line, c: &Circle) -> Intersection<P2, 2> {
    let (ts, contact) = line_circle_t(l, c);
    let mut roots = Roots::new();
    if contact == Contact::Tangent {
        let x = line_circle_tangent_point(l, c);
        roots.push(x);
        roots.push(x);
    } else {
        for &t in ts.as_slice() {
            roots.push(l.at(t));
        }
    }
    Intersection { roots, contact }
}

/// The directions of the lines through `pivot` that pass `point` at signed distance `offset`
/// (positive with `point` to the left of the directed line): each unit `u` with
/// `cross(u, point - pivot) = offset`. These are the lines through `pivot` tangent to the circle
/// about `point` of radius `|offset|`, on the side its sign says; with `offset` zero, the two
/// senses of the line through both points. A line turning about a pivot until it passes a
/// point, or touches a circle, is turned onto one of them.
///
/// Branch 0 has `point` ahead of `pivot` along `u` (`u . (point - pivot) >= 0`), branch 1
/// behind it. Degenerate cases, with `rho = |point - pivot|`:
/// - `|offset| - rho` within [`tol::TANGENT_REL`] of the scale (the pivot on that circle):
///   [`Contact::Tangent`], the one direction, perpendicular to `point - pivot`, in both slots;
///   it is built as such, so the tangency holds to rounding rather than to its square root;
/// - `|offset| > rho` beyond it (the pivot inside the circle): [`Contact::Disjoint`] with gap
///   `|offset| - rho`;
/// - `pivot` and `point` the same within [`tol::LENGTH_REL`] of the scale, and `offset` zero
///   within it: every line through `pivot` passes `point`, [`Contact::Coincident`].
#[inline]
pub fn passing_directions(pivot: P2, point: P2, offset: f64) -> Intersection<V2, 2> {
    let v = point - pivot;
    let s = tol::scale(&[pivot.x, pivot.y, point.x, point.y, offset]);
    let rho = v.norm();
    if !rho.is_finite() || !offset.is_finite() {
        return Intersection::none(Contact::Disjoint { gap: f64::INFINITY });
    }
    if rho <= tol::LENGTH_REL * s && offset.abs() <= tol::LENGTH_REL * s {
        return Intersection::none(Contact::Coincident);
    }
    let gap = offset.abs() - rho;
    if gap > tol::TANGENT_REL * s {
        return Intersection::none(Contact::Disjoint { gap });
    }
    let along = v / rho;
    // To the right of `along`: `cross(right, along) = 1`.
    let right = -perp(along);
    if gap >= 0.0 {
        let u = right * offset.signum();
        return Intersection {
            roots: Roots::from_slice(&[u, u]),
            contact: Contact::Tangent,
        };
    }
    let sin = offset / rho;
    let cos = ((1.0 - sin) * (1.0 + sin)).sqrt();
    let side = right * sin;
    Intersection {
        roots: Roots::from_slice(&[along * cos + side, along * -cos + side]),
        contact: Contact::Crossing,
    }
}

/// Maps the line's roots to the ray's `Option` slots; all behind the origin gives `Disjoint`
/// with `gap`.
fn onto_ray(
    r: &Ray,
    line: Intersection<P2, 2>,
    scale: f64,
    gap_from_origin: impl FnOnce() -> f64,
) -> Intersection<Option<P2>, 2> {
    let mut roots = Roots::new();
    let mut any = false;
    for &x in line.roots.as_slice() {
        let ahead = r.param_of(x) >= -tol::LENGTH_REL * scale;
        any |= ahead;
        roots.push(ahead.then_some(x));
    }
    if line.roots.is_empty() {
        return Intersection::none(line.contact);
    }
    if !any {
        return Intersection::none(Contact::Disjoint {
            gap: gap_from_origin(),
        });
    }
    Intersection {
        roots,
        contact: line.contact,
    }
}

/// A ray and a circle.
///
/// Branches are those of [`line_circle`] on the supporting line (0 = first along the
/// direction), so the index never depends on filtering: a root behind the origin (parameter
/// below `-`[`tol::LENGTH_REL`] of the scale) is `None` in its slot. When both are behind, the
/// result is [`Contact::Disjoint`] with the distance of the origin from the circle. Other
/// degenerate cases as in [`line_circle`].
pub fn ray_circle(r: &Ray, c: &Circle) -> Intersection<Option<P2>, 2> {
    let [cx, cy, rad] = circle_scale(c);
    let s = tol::scale(&[r.origin().x, r.origin().y, cx, cy, rad]);
    onto_ray(r, line_circle(&r.line(), c), s, || c.residual(r.origin()))
}

/// Two circles.
///
/// Branch 0 is the root to the **left** of the directed line from the first centre to the
/// second, branch 1 the root to its right. Degenerate cases, with `d` the distance of the
/// centres and the scale the largest coordinate or radius:
/// - a radius within [`tol::LENGTH_REL`] of the scale: that circle is its centre, on the other
///   circle (touching, below) or off it (disjoint); two such circles touch where they are one
///   point, within [`tol::TANGENT_REL`] of the scale, and are disjoint by their distance
///   otherwise;
/// - `d` and `r1 - r2` both within [`tol::LENGTH_REL`] of the scale, the radii not zero:
///   [`Contact::Coincident`];
/// - `d - (r1 + r2)` or `|r1 - r2| - d` within [`tol::TANGENT_REL`] of the scale (externally
///   or internally touching): [`Contact::Tangent`], the touching point on the line of centres
///   in both slots;
/// - apart (`d > r1 + r2`) or nested (`d < |r1 - r2|`, including concentric circles):
///   [`Contact::Disjoint`] with gap `d - (r1 + r2)` or `|r1 - r2| - d`.
///
/// The roots are those of [`circle_circle_chord`], which a plan that needs one root calls.
#[inline]
pub fn circle_circle(a: &Circle, b: &Circle) -> Intersection<P2, 2> {
    match circle_circle_chord(a, b) {
        Ok(chord) => Intersection {
            roots: Roots::from_slice(&[chord.left(), chord.right()]),
            contact: if chord.half == V2::zeros() {
                Contact::Tangent
            } else {
                Contact::Crossing
            },
        },
        Err(contact) => Intersection::none(contact),
    }
}

/// Where two circles meet, as the midpoint of their common chord and half of it: the roots
/// are `mid + half` (branch 0, left of the line from the first centre to the second) and
/// `mid - half` (branch 1). Touching circles have a zero `half`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chord {
    /// The chord's midpoint, on the line of centres.
    pub mid: P2,
    /// From the midpoint to the left root.
    pub half: V2,
    /// From the first circle's centre to the midpoint: computed from the centres' offset, where
    /// `mid - c1` would cancel the digits a centre far from the origin takes.
    pub mid_from_a: V2,
    /// From the second circle's centre to the midpoint, likewise.
    pub mid_from_b: V2,
}

impl Chord {
    /// The root to the left of the line of centres (branch 0).
    #[inline]
    pub fn left(&self) -> P2 {
        self.mid + self.half
    }

    /// The root to the right of the line of centres (branch 1).
    #[inline]
    pub fn right(&self) -> P2 {
        self.mid - self.half
    }

    /// The root of `branch` (0 left, 1 right), computing only that one; `None` past 1.
    #[inline]
    pub fn root(&self, branch: usize) -> Option<P2> {
        match branch {
            0 => Some(self.left()),
            1 => Some(self.right()),
            _ => None,
        }
    }

    /// The root of `branch` from the first circle's centre: a radius of that circle, to
    /// rounding relative to the radius however far the centre is from the origin (the
    /// difference `root - c1` loses the digits the centre's coordinates take). A rotation
    /// about the centre onto the root reads it, and finds it on its circle to the last bits.
    #[inline]
    pub fn root_from_a(&self, branch: usize) -> Option<V2> {
        self.root_from(self.mid_from_a, branch)
    }

    /// The root of `branch` from the second circle's centre, as [`Chord::root_from_a`].
    #[inline]
    pub fn root_from_b(&self, branch: usize) -> Option<V2> {
        self.root_from(self.mid_from_b, branch)
    }

    /// The root of `branch` from a centre, given the midpoint from that centre.
    #[inline]
    fn root_from(&self, mid: V2, branch: usize) -> Option<V2> {
        match branch {
            0 => Some(mid + self.half),
            1 => Some(mid - self.half),
            _ => None,
        }
    }
}

/// Where two circles meet, as a [`Chord`], or the [`Contact`] that says why they do not: the
/// cases and tolerances of [`circle_circle`], which is built on it.
///
/// Two circles that cross, the common case, take one test before the roots: the scale, the
/// radii, tangency and degeneracy are sorted out in a cold call only when the circles do not
/// plainly cross. Circles whose scale lies outside [`CHORD_SCALES`] are solved scaled by a
/// power of two, which is exact, so no step overflows or underflows at any finite scale.
///
/// Always inlined, as its cold cases are out of line: LLVM left it out of line in solves that
/// call it many times (a chain of four-bars) or that are themselves inlined, and there its
/// result went through memory. Inlined, a chain of 128 four-bars solves about 25% faster.
#[inline(always)]
pub fn circle_circle_chord(a: &Circle, b: &Circle) -> Result<Chord, Contact> {
    let (c1, c2) = (a.center(), b.center());
    let (r1, r2) = (a.radius(), b.radius());
    let s = chord_scale(c1, r1, c2, r2);
    let dv = c2 - c1;
    let d2 = dv.norm_squared();
    let (overlap, apart) = heron_factors(d2, r1, r2);
    if !plainly_cross(s, r1, r2, d2, overlap, apart) {
        return not_plainly_crossing([c1.x, c1.y, r1, c2.x, c2.y, r2]);
    }
    Ok(crossing(c1, dv, d2, r1, r2, overlap * apart))
}

/// Whether two circles at scale `s`, of radii `r1` and `r2`, with centres `sqrt(d2)` apart and
/// [`heron_factors`] `overlap` and `apart`, plainly cross: the scale in [`CHORD_SCALES`], the
/// radii and the distance above [`tol::LENGTH_REL`] of it, and both factors positive.
///
/// Within `CHORD_SCALES` every value of [`crossing`] is then finite and Heron's product
/// normal, so the roots need no test of their own. Where these tests on `d²` find no
/// crossing, tests on `d` would find none either (`sqrt(x * x)` is `|x|` in floating point,
/// and `sqrt` is monotone); they may find an overlap that `d` would round away, and such
/// circles cross.
#[inline(always)]
fn plainly_cross(s: f64, r1: f64, r2: f64, d2: f64, overlap: f64, apart: f64) -> bool {
    let least = tol::LENGTH_REL * s;
    CHORD_SCALES.contains(&s)
        && r1 > least
        && r2 > least
        && overlap > 0.0
        && apart > 0.0
        && d2 > least * least
}

/// The scale of two circles: their largest coordinate or radius. The radii first, then the
/// second centre: in a plan they are the values most often constant, and a maximum taken in
/// order folds its constant prefix at compile time.
#[inline(always)]
fn chord_scale(c1: P2, r1: f64, c2: P2, r2: f64) -> f64 {
    tol::scale(&[r1, r2, c2.x, c2.y, c1.x, c1.y])
}

/// Heron's product for circles of radii `r1`, `r2` whose centres are `sqrt(d2)` apart,
/// `16 area² = ((r1 + r2)² - d²)(d² - (r1 - r2)²)`, as its two factors: the first is positive
/// when the circles overlap, the second when neither holds the other. Both come from `d²`, so
/// no square root stands between the centres and the half chord's.
#[inline(always)]
fn heron_factors(d2: f64, r1: f64, r2: f64) -> (f64, f64) {
    let (sum, diff) = (r1 + r2, r1 - r2);
    (sum * sum - d2, d2 - diff * diff)
}

/// The chord of two circles that plainly cross (radii above [`tol::LENGTH_REL`] of the scale,
/// both of [`heron_factors`] positive, at a scale in [`CHORD_SCALES`]), from the first centre,
/// the vector `dv` to the second, `d2 = |dv|²`, the radii and Heron's product `area16`.
///
/// Everything is a multiple of `dv` and its perpendicular: the distance along the line of
/// centres is `(d² + r1² - r2²) / 2d`, the half chord `sqrt(area16) / 2d`, each divided once
/// more by `d` to scale `dv`. So one division, by `d²`, and one square root, of `area16`,
/// which the processor runs side by side; the distance `d` itself is never needed.
///
/// Accuracy: near tangency a factor of Heron's product is a difference of nearly equal
/// squares, off by a few ulps of `d²`; as `(r1 + r2 - d)(r1 + r2 + d)`, with `d` rounded from
/// `d²`, it is off by as much. That is the problem's own conditioning: the roots stay on both
/// circles to rounding.
#[inline(always)]
fn crossing(c1: P2, dv: V2, d2: f64, r1: f64, r2: f64, area16: f64) -> Chord {
    let inv_d2 = 1.0 / d2;
    let along = 0.5 * (d2 + (r1 - r2) * (r1 + r2)) * inv_d2;
    let back = 0.5 * (d2 + (r2 - r1) * (r2 + r1)) * inv_d2;
    let h = area16.sqrt() * (0.5 * inv_d2);
    let mid_from_a = dv * along;
    Chord {
        mid: c1 + mid_from_a,
        half: perp(dv) * h,
        mid_from_a,
        mid_from_b: dv * -back,
    }
}

/// The scales (largest coordinate or radius) at which [`circle_circle_chord`] computes
/// directly, `2^-150` to `2^150` (about 7e-46 to 1.4e45). With `s` the scale, every centre and
/// radius is at most `s`, so `d²` is at most `8s²`, both of [`heron_factors`] at most `8s²`,
/// their product at most `64s⁴` and `1/d²` at most `2^92 / s²` (`d` exceeds
/// [`tol::LENGTH_REL`]` * s = 2^-46 s`): all finite. For crossing circles the distance along
/// the line of centres is below `r1` and the half chord at most `r1`, so each root lies within
/// `3s` of the origin. Each factor is positive as computed, a difference of two floats of which
/// the larger is at least `2^-92 s²` (the radii and `d` exceed `2^-46 s`), so at least
/// `2^-146 s²`; the product is at least `2^-292 s⁴`, above `2^-900`: a normal number, whose
/// square root keeps full precision.
pub const CHORD_SCALES: std::ops::RangeInclusive<f64> = {
    // 2^-150 and 2^150, built from their exponents.
    let lo = f64::from_bits((1023 - 150) << 52);
    let hi = f64::from_bits((1023 + 150) << 52);
    lo..=hi
};

/// The cases of [`circle_circle_chord`] where two circles, given as their centres and radii,
/// do not plainly cross: a scale outside [`CHORD_SCALES`], a zero radius, coincident,
/// touching (within [`tol::TANGENT_REL`]) or apart.
///
/// Plain numbers rather than the circles: six floats travel in registers, where a circle by
/// reference had the caller store both circles on its hot path for this cold call.
#[cold]
fn not_plainly_crossing([x1, y1, r1, x2, y2, r2]: [f64; 6]) -> Result<Chord, Contact> {
    let (c1, c2) = (P2::new(x1, y1), P2::new(x2, y2));
    let s = chord_scale(c1, r1, c2, r2);
    if !CHORD_SCALES.contains(&s) {
        return rescaled([x1, y1, r1, x2, y2, r2], s);
    }
    let dv = c2 - c1;
    let d2 = dv.norm_squared();
    if r1 <= tol::LENGTH_REL * s && r2 <= tol::LENGTH_REL * s {
        // Two points: one where they coincide (midway, within rounding), else apart.
        let d = d2.sqrt();
        if d > tol::TANGENT_REL * s {
            return Err(Contact::Disjoint { gap: d });
        }
        let mid_from_a = dv * 0.5;
        return Ok(Chord {
            mid: c1 + mid_from_a,
            half: V2::zeros(),
            mid_from_a,
            mid_from_b: dv * -0.5,
        });
    }
    let (overlap, apart) = heron_factors(d2, r1, r2);
    if plainly_cross(s, r1, r2, d2, overlap, apart) {
        // Not reached: the caller computed the same values and found them crossing.
        return Ok(crossing(c1, dv, d2, r1, r2, overlap * apart));
    }
    let d = d2.sqrt();
    // Coincident circles determine no point (a zero radius is at most one, handled above).
    if d <= tol::LENGTH_REL * s && (r1 - r2).abs() <= tol::LENGTH_REL * s {
        return Err(Contact::Coincident);
    }
    let (outer, inner) = (d - (r1 + r2), (r1 - r2).abs() - d);
    let tangent = tol::TANGENT_REL * s;
    let u = if d > 0.0 { dv / d } else { V2::x() };
    // Missing by rounding (at most `tangent`): the touching point. Overlapping loci, however
    // little, cross, and their two roots are computed exactly. (`outer` and `inner` are not
    // negative here: where the tests on `d²` above find no crossing, neither would `d`.)
    let external = (0.0..=tangent).contains(&outer);
    let internal = (0.0..=tangent).contains(&inner) && d > tol::LENGTH_REL * s;
    if external || internal {
        // External: along u from the first centre; internal: towards the side of the larger.
        let along = if external {
            // Midway between the two circles' points on the line of centres.
            0.5 * (r1 + (d - r2))
        } else if r1 >= r2 {
            0.5 * (r1 + (d + r2))
        } else {
            -0.5 * (r1 + (r2 - d))
        };
        return Ok(Chord {
            mid: c1 + u * along,
            half: V2::zeros(),
            mid_from_a: u * along,
            mid_from_b: u * (along - d),
        });
    }
    Err(Contact::Disjoint {
        gap: if outer > 0.0 { outer } else { inner },
    })
}

/// [`circle_circle_chord`] of circles at scale `s` outside [`CHORD_SCALES`], given as their
/// centres and radii: the same circles scaled by a power of two (exact) to a scale in `[1, 2)`,
/// solved, and the chord scaled back. A chord too large for `f64` on the way back is
/// [`Contact::Disjoint`] with an infinite gap.
fn rescaled([x1, y1, r1, x2, y2, r2]: [f64; 6], s: f64) -> Result<Chord, Contact> {
    if [x1, y1, r1, x2, y2, r2].iter().all(|v| *v == 0.0) {
        // Two circles of no size at the origin: one point, where they meet (no scale to
        // bring them to, and no recursion).
        return Ok(Chord {
            mid: P2::origin(),
            half: V2::zeros(),
            mid_from_a: V2::zeros(),
            mid_from_b: V2::zeros(),
        });
    }
    // `s` is at least 1e-300, a normal number: its exponent field is its binary exponent.
    let exponent = ((s.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let shrink = |x: f64, y: f64, r: f64| {
        let [x, y, r] = [x, y, r].map(|v| times_pow2(v, -exponent));
        Circle::new(P2::new(x, y), r)
    };
    let (Some(a), Some(b)) = (shrink(x1, y1, r1), shrink(x2, y2, r2)) else {
        // Unreachable: scaling finite values down by a power of two keeps them finite.
        return Err(Contact::Disjoint { gap: f64::INFINITY });
    };
    let grow = |v: V2| V2::new(times_pow2(v.x, exponent), times_pow2(v.y, exponent));
    match circle_circle_chord(&a, &b) {
        Ok(chord) => {
            let chord = Chord {
                mid: P2::from(grow(chord.mid.coords)),
                half: grow(chord.half),
                mid_from_a: grow(chord.mid_from_a),
                mid_from_b: grow(chord.mid_from_b),
            };
            if finite_p(chord.left()) && finite_p(chord.right()) {
                Ok(chord)
            } else {
                Err(Contact::Disjoint { gap: f64::INFINITY })
            }
        }
        Err(Contact::Disjoint { gap }) => Err(Contact::Disjoint {
            gap: times_pow2(gap, exponent),
        }),
        Err(contact) => Err(contact),
    }
}

/// `x * 2^e`, exact when the result is normal, for `e` in `-2044..=2046`: two factors, each a
/// normal power of two.
fn times_pow2(x: f64, e: i32) -> f64 {
    let pow2 = |e: i32| f64::from_bits(((e + 1023) as u64) << 52);
    x * pow2(e / 2) * pow2(e - e / 2)
}

/// The implicit function of a curve, its gradient, and its residual; for 2d Newton polishing.
#[derive(Clone, Copy, Debug)]
enum Curve<'a> {
    Circle(&'a Circle),
    Conic(&'a Conic),
}

fn unit_or_zero(v: V2) -> V2 {
    let n = v.norm();
    if n > 0.0 {
        v / n
    } else {
        V2::zeros()
    }
}

impl Curve<'_> {
    fn value_grad(&self, x: P2) -> (f64, V2) {
        match self {
            Curve::Circle(c) => (c.implicit(x), unit_or_zero(x - c.center())),
            Curve::Conic(k) => {
                let g = match k {
                    Conic::Parabola(p) => unit_or_zero(x - p.focus()) - p.directrix().normal(),
                    Conic::Ellipse(e) => {
                        let (f1, f2) = e.foci();
                        unit_or_zero(x - f1) + unit_or_zero(x - f2)
                    }
                    Conic::Hyperbola(h) => {
                        let (f1, f2) = h.foci();
                        unit_or_zero(x - f1) - unit_or_zero(x - f2)
                    }
                };
                (k.implicit(x), g)
            }
        }
    }

    fn residual(&self, x: P2) -> f64 {
        match self {
            Curve::Circle(c) => c.residual(x),
            Curve::Conic(k) => k.residual(x),
        }
    }
}

/// The first-order distance `|f| / |∇f|` from an implicit value and gradient, as each curve's
/// `residual` computes it (`|f|` where the gradient vanishes).
#[inline]
fn first_order(f: f64, g: V2) -> f64 {
    let n = g.norm();
    if n > tol::TINY {
        f.abs() / n
    } else {
        f.abs()
    }
}

/// Two Newton steps on the pair of implicit equations, kept only if they reduce the larger
/// residual; skipped where the curves are nearly tangent (the step is ill-conditioned there).
/// Each point is evaluated once: its values and gradients give both its residuals and the next
/// step.
fn polish(x: P2, a: Curve<'_>, b: Curve<'_>) -> P2 {
    let (mut fa, mut ga) = a.value_grad(x);
    let (mut fb, mut gb) = b.value_grad(x);
    let mut best = x;
    let mut best_r = first_order(fa, ga).max(first_order(fb, gb));
    let mut y = x;
    for _ in 0..2 {
        if best_r == 0.0 {
            break;
        }
        let det = cross(ga, gb);
        if det.abs() <= tol::POLISH_MIN_SIN * ga.norm() * gb.norm() || !det.is_finite() {
            break;
        }
        // Solve [ga; gb] dx = -[fa; fb].
        let dx = V2::new(
            -(fa * gb.y - fb * ga.y) / det,
            -(ga.x * fb - gb.x * fa) / det,
        );
        y += dx;
        (fa, ga) = a.value_grad(y);
        (fb, gb) = b.value_grad(y);
        let r = first_order(fa, ga).max(first_order(fb, gb));
        if r.is_finite() && r < best_r {
            best = y;
            best_r = r;
        }
    }
    best
}

/// Parameters along `l` of its crossings with the conic, ascending (branch-filtered, polished),
/// with the contact, the tangent point if any.
fn line_conic_t(l: &Line, c: &Conic) -> (Roots<f64, 2>, Contact, Option<P2>) {
    let [px, py] = line_scale(l);
    let s = c.scale().max(tol::scale(&[px, py]));
    let f: Focal = c.focal();
    let d = l.dir();
    let q = l.point() - f.f;
    let alpha = f.w.dot(&q) + f.k;
    let beta = f.w.dot(&d);
    let wn = f.w.norm();
    let mut ts: Roots<f64, 2> = Roots::new();
    if f.mu <= tol::TANGENT_REL * wn {
        // The hyperbola's `diff = 0` (or within tolerance): its perpendicular-bisector line.
        if beta.abs() <= tol::ANGLE * wn {
            let gap = (alpha / wn).abs();
            let contact = if gap <= tol::LENGTH_REL * s {
                Contact::Coincident
            } else {
                Contact::Parallel { gap }
            };
            return (ts, contact, None);
        }
        ts.push(-alpha / beta);
        return (ts, Contact::Crossing, None);
    }
    let mu2 = f.mu * f.mu;
    let qa = mu2 - beta * beta;
    let qb = 2.0 * (mu2 * d.dot(&q) - alpha * beta);
    let qc = mu2 * q.norm_squared() - alpha * alpha;
    if !(qa.is_finite() && qb.is_finite() && qc.is_finite()) {
        return (ts, Contact::Disjoint { gap: f64::INFINITY }, None);
    }
    let curve = Curve::Conic(c);
    let eps_h = tol::LENGTH_REL * s * (wn + f.mu);
    // The extremum of the squared equation: a tangent point when it lies on the conic.
    if qa.abs() > tol::ANGLE * mu2 {
        let t0 = -qb / (2.0 * qa);
        let x0 = l.at(t0);
        // Far from the inputs (a parabola's arm), rounding grows with the point's magnitude.
        let sx = s.max(x0.coords.norm());
        let disc = qb * qb - 4.0 * qa * qc;
        let split = if disc > 0.0 {
            disc.sqrt() / (2.0 * qa.abs())
        } else {
            0.0
        };
        // The cheap test first: only a close pair of roots can be a tangency.
        if split <= tol::TANGENT_SPLIT_REL * sx
            && finite_p(x0)
            && f.h(x0) >= -eps_h
            && curve.residual(x0) <= tol::TANGENT_REL * sx
        {
            // Move the point onto the curve along the line's normal by half its residual, so
            // that it is within half the tangency tolerance of both.
            let (v, g) = curve.value_grad(x0);
            let gn = g.norm_squared();
            let x = if gn > 0.0 {
                x0 - g * (0.5 * v / gn)
            } else {
                x0
            };
            return (Roots::from_slice(&[t0, t0]), Contact::Tangent, Some(x));
        }
    }
    // The conic's implicit function along the line, unsquared, and its slope. The implicit
    // is evaluated without cancellation far along an arm, where the focal equation
    // `μ |q + t d| - (α + β t)` subtracts two nearly equal lengths: on a parabola's arm 4e7
    // times the inputs' scale, that left a residual of 2e-12 relative to the root.
    let focal_eq = |t: f64| -> (f64, f64) {
        let (value, grad) = curve.value_grad(l.at(t));
        (value, grad.dot(&d))
    };
    for &t in poly::quadratic(qa, qb, qc).as_slice() {
        let x = l.at(t);
        if finite_p(x) && f.h(x) >= -eps_h {
            // Polish along the line by Newton's method on the unsquared focal equation (whose
            // root the squaring may have moved), keeping a step only if it reduces |g|.
            let (mut best, (mut g, mut dg)) = (t, focal_eq(t));
            let mut best_g = g.abs();
            let mut u = t;
            for _ in 0..2 {
                let step = g / dg;
                if best_g == 0.0 || !step.is_finite() || step.abs() <= tol::ULP * u.abs() {
                    break;
                }
                u -= step;
                (g, dg) = focal_eq(u);
                if g.abs() < best_g {
                    best = u;
                    best_g = g.abs();
                }
            }
            ts.push(best);
        }
    }
    if ts.len() == 2 && ts.get(0) > ts.get(1) {
        ts = Roots::from_slice(&[ts.get(1).unwrap_or(0.0), ts.get(0).unwrap_or(0.0)]);
    }
    if ts.is_empty() {
        return (
            ts,
            Contact::Disjoint {
                gap: line_conic_gap(l, c),
            },
            None,
        );
    }
    (ts, Contact::Crossing, None)
}

/// The distance by which a line misses a conic: the distance from the line of the conic's point
/// whose tangent is parallel to the line, or, for a hyperbola met only by the other branch or
/// parallel to an asymptote, of the asymptotes' centre.
fn line_conic_gap(l: &Line, c: &Conic) -> f64 {
    let n = l.normal();
    let gap = match c {
        Conic::Parabola(p) => {
            let dn = n.dot(&p.directrix().normal());
            if dn.abs() > tol::ANGLE {
                let t = -p.focal_distance() * n.dot(&p.directrix().dir()) / dn;
                l.residual(p.at(t))
            } else {
                l.residual(p.vertex())
            }
        }
        Conic::Ellipse(e) => {
            let (m, a, b, u) = e.axes();
            let reach = (a * n.dot(&u)).hypot(b * n.dot(&perp(u)));
            (l.residual(m) - reach).max(0.0)
        }
        Conic::Hyperbola(h) => {
            let (m, a, b, u) = h.axes();
            let (nu, nv) = (a * n.dot(&u), b * n.dot(&perp(u)));
            if nv.abs() < nu.abs() {
                l.residual(h.at((-nv / nu).atanh()))
            } else {
                l.residual(m)
            }
        }
    };
    if gap.is_finite() {
        gap
    } else {
        f64::INFINITY
    }
}

/// A line and a conic (parabola, ellipse or hyperbola branch).
///
/// Branch 0 is the first crossing along the line's direction, branch 1 the second; crossings
/// with the other branch of a hyperbola are not roots (so a line through both branches has one
/// root). Degenerate cases: [`Contact::Tangent`] when the line touches within
/// [`tol::TANGENT_REL`] of the scale (the touching point, within half that of both, in both
/// slots); [`Contact::Disjoint`] with the distance at closest approach (for a hyperbola missed
/// along an asymptote, the distance to that asymptote); a line parallel to a parabola's axis or
/// a hyperbola's asymptote has one root (the other went to infinity). For the hyperbola with
/// `diff = 0` (a line): [`Contact::Parallel`] or [`Contact::Coincident`] as in [`line_line`].
pub fn line_conic(l: &Line, c: &Conic) -> Intersection<P2, 2> {
    let (ts, contact, tangent) = line_conic_t(l, c);
    let mut roots = Roots::new();
    match tangent {
        Some(x) => {
            roots.push(x);
            roots.push(x);
        }
        None => {
            for &t in ts.as_slice() {
                roots.push(l.at(t));
            }
        }
    }
    Intersection { roots, contact }
}

/// A ray and a conic.
///
/// Branches are those of [`line_conic`] on the supporting line, with a root behind the origin
/// `None` in its slot (as in [`ray_circle`]); both behind gives [`Contact::Disjoint`] with the
/// first-order distance of the origin from the conic. Other cases as in [`line_conic`].
pub fn ray_conic(r: &Ray, c: &Conic) -> Intersection<Option<P2>, 2> {
    let s = c.scale().max(tol::scale(&[r.origin().x, r.origin().y]));
    onto_ray(r, line_conic(&r.line(), c), s, || c.residual(r.origin()))
}

/// The implicit quadric `Xᵀ A X + 2 b·X + c` of a curve, in coordinates relative to `origin`.
#[derive(Clone, Copy, Debug)]
struct Quadric {
    a: [[f64; 2]; 2],
    b: V2,
    c: f64,
}

fn circle_quadric(c: &Circle, origin: P2) -> Quadric {
    let cc = c.center() - origin;
    Quadric {
        a: [[1.0, 0.0], [0.0, 1.0]],
        b: -cc,
        c: (cc.norm() - c.radius()) * (cc.norm() + c.radius()),
    }
}

fn conic_quadric(k: &Conic, origin: P2) -> Quadric {
    let f = k.focal();
    let fp = f.f - origin;
    let kp = f.k - f.w.dot(&fp);
    let wn = f.w.norm();
    if f.mu <= tol::TANGENT_REL * wn {
        // The line w·X + k' = 0.
        return Quadric {
            a: [[0.0; 2]; 2],
            b: f.w * 0.5,
            c: kp,
        };
    }
    let mu2 = f.mu * f.mu;
    Quadric {
        a: [
            [mu2 - f.w.x * f.w.x, -f.w.x * f.w.y],
            [-f.w.x * f.w.y, mu2 - f.w.y * f.w.y],
        ],
        b: -fp * mu2 - f.w * kp,
        c: mu2 * fp.norm_squared() - kp * kp,
    }
}

impl Quadric {
    fn form(&self, p: V2, q: V2) -> f64 {
        p.x * (self.a[0][0] * q.x + self.a[0][1] * q.y)
            + p.y * (self.a[1][0] * q.x + self.a[1][1] * q.y)
    }

    fn form_abs(&self, p: V2, q: V2) -> f64 {
        p.x.abs() * (self.a[0][0].abs() * q.x.abs() + self.a[0][1].abs() * q.y.abs())
            + p.y.abs() * (self.a[1][0].abs() * q.x.abs() + self.a[1][1].abs() * q.y.abs())
    }

    /// The quartic `Q(P(s)/w(s)) w(s)²` (lowest degree first) and the magnitudes of its terms.
    fn substitute(&self, r: &Rational) -> ([f64; 5], [f64; 5]) {
        let (mut c, mut m) = ([0.0; 5], [0.0; 5]);
        for i in 0..3 {
            for j in 0..3 {
                let (pi, pj) = (r.p[i], r.p[j]);
                let (wi, wj) = (r.w[i], r.w[j]);
                let term = self.form(pi, pj) + 2.0 * wi * self.b.dot(&pj) + self.c * wi * wj;
                let mag = self.form_abs(pi, pj)
                    + 2.0 * (wi * (self.b.x * pj.x).abs() + wi.abs() * (self.b.y * pj.y).abs())
                    + (self.c * wi * wj).abs();
                if let (Some(ci), Some(mi)) = (c.get_mut(i + j), m.get_mut(i + j)) {
                    *ci += term;
                    *mi += mag;
                }
            }
        }
        (c, m)
    }
}

/// Intersects the conic `a`, parametrised, with the curve `b` given by its quadric; roots in
/// ascending parameter of `a`, tangent points doubled.
fn param_implicit(a: &Conic, b: Curve<'_>, scale: f64) -> Intersection<P2, 4> {
    let origin = a.rational(0.0).origin;
    let quadric = match b {
        Curve::Circle(c) => circle_quadric(c, origin),
        Curve::Conic(k) => conic_quadric(k, origin),
    };
    // For an ellipse, start the tangent-half-angle parameter so that the one point it cannot
    // reach (θ0 + π) is the farthest from `b` among eight candidates, by the first-order
    // distance `|Q| / |∇Q|` of `b`'s quadric (compared squared).
    let theta0 = match a {
        Conic::Ellipse(e) => {
            let (m, ax, bx, u) = e.axes();
            let (u, v) = (u * ax, perp(u) * bx);
            let off = m - origin;
            let h = std::f64::consts::FRAC_1_SQRT_2;
            let cs = [(1.0, 0.0), (h, h), (0.0, 1.0), (-h, h)];
            let mut best = (0.0, -1.0);
            for k in 0..8 {
                let (c, sn) = cs[k % 4];
                let sign = if k < 4 { 1.0 } else { -1.0 };
                // The point at θ + π, relative to the quadric's origin.
                let p = off - (u * c + v * sn) * sign;
                let q = quadric.form(p, p) + 2.0 * quadric.b.dot(&p) + quadric.c;
                let g = V2::new(
                    quadric.a[0][0] * p.x + quadric.a[0][1] * p.y,
                    quadric.a[1][0] * p.x + quadric.a[1][1] * p.y,
                ) + quadric.b;
                let gn = g.norm_squared();
                let r = if gn > 0.0 { q * q / gn } else { q * q };
                if r > best.1 {
                    best = (k as f64 * std::f64::consts::FRAC_PI_4, r);
                }
            }
            best.0
        }
        _ => 0.0,
    };
    let rat = a.rational(theta0);
    let (low, mag) = quadric.substitute(&rat);
    let coeffs = [low[4], low[3], low[2], low[1], low[0]];
    if coeffs.iter().any(|c| !c.is_finite()) {
        return overflow();
    }
    let top = mag.iter().fold(0.0f64, |m, &x| m.max(x));
    if low
        .iter()
        .zip(&mag)
        .all(|(c, m)| c.abs() <= tol::TANGENT_REL * m.max(top * tol::COINCIDENT_FLOOR_REL))
    {
        return Intersection::none(Contact::Coincident);
    }
    let (roots, crit) = poly::roots_and_critical(&coeffs);
    // The branch side of a hyperbola `b` (every point of the other conics is on it).
    let side = match b {
        Curve::Conic(k) => {
            let f = k.focal();
            Some((f, -tol::LENGTH_REL * scale * (f.w.norm() + f.mu)))
        }
        Curve::Circle(_) => None,
    };
    let valid = |s: f64| -> Option<(f64, P2)> {
        let t = a.param_from_s(s, theta0)?;
        let x = rat.at(s)?;
        if let Some((f, min)) = side {
            if f.h(x) < min {
                return None;
            }
        }
        Some((t, x))
    };
    // Tangent points: critical points of the polynomial where `a` touches `b`.
    let mut tangents: Roots<(f64, f64, P2), 3> = Roots::new(); // (s, t, point)
    for r in crit.as_slice() {
        if let Some((t, x)) = valid(r.x) {
            if b.residual(x) <= tol::TANGENT_REL * scale.max(x.coords.norm()) {
                tangents.push((r.x, t, x));
            }
        }
    }
    let mut out: Roots<(f64, P2, bool), 4> = Roots::new();
    for r in roots.as_slice() {
        let Some((t, x)) = valid(r.x) else { continue };
        // A root that a tangent point absorbs: its close partner in the merged pair.
        let absorbed = tangents.as_slice().iter().any(|&(_, _, y)| {
            (x - y).norm() <= tol::TANGENT_ABSORB_REL * scale.max(y.coords.norm())
        });
        if absorbed {
            continue;
        }
        let x = polish(x, Curve::Conic(a), b);
        out.push((t, x, false));
    }
    for &(_, t, x) in tangents.as_slice() {
        // Within half the tolerance of both: move halfway towards `b` along its gradient.
        let (v, g) = b.value_grad(x);
        let gn = g.norm_squared();
        let y = if gn > 0.0 { x - g * (0.5 * v / gn) } else { x };
        out.push((t, y, true));
        out.push((t, y, true));
    }
    // Ascending parameter of `a` (insertion sort on at most four).
    let mut items = [(0.0, P2::origin(), false); 4];
    let n = out.len();
    for (dst, src) in items.iter_mut().zip(out.as_slice()) {
        *dst = *src;
    }
    for i in 1..n {
        let mut j = i;
        while j > 0 && items.get(j - 1).map(|p| p.0) > items.get(j).map(|p| p.0) {
            items.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut result = Roots::new();
    let mut tangent = false;
    for it in items.iter().take(n) {
        result.push(it.1);
        tangent |= it.2;
    }
    if result.is_empty() {
        // The closest approach: the critical point whose point is nearest to `b`.
        let mut gap = f64::INFINITY;
        for r in crit.as_slice() {
            if a.param_from_s(r.x, theta0).is_some() {
                if let Some(x) = rat.at(r.x) {
                    gap = gap.min(b.residual(x));
                }
            }
        }
        if !gap.is_finite() {
            gap = b.residual(a.at(0.0));
        }
        let gap = if gap.is_finite() { gap } else { f64::INFINITY };
        return Intersection::none(Contact::Disjoint { gap });
    }
    Intersection {
        roots: result,
        contact: if tangent {
            Contact::Tangent
        } else {
            Contact::Crossing
        },
    }
}

/// A circle and a conic: up to four roots.
///
/// Order: ascending parameter along the **conic** (parabola: coordinate along the directrix
/// from the vertex; ellipse: eccentric angle in `(-π, π]`, which wraps at `π`; hyperbola: `t`
/// of `cosh t, sinh t`), found as roots of a quartic in that parameter and polished by Newton's
/// method on both curves. Use [`nearest`] to follow a branch through a sweep. Degenerate cases:
/// a circle of zero radius is its centre: on the conic within [`tol::TANGENT_REL`] of the scale
/// it is the one root ([`Contact::Tangent`], in slots 0 and 1), off it [`Contact::Disjoint`]
/// with the conic's residual there;
/// [`Contact::Coincident`] when the conic is this circle (an ellipse with equal foci);
/// [`Contact::Tangent`] when they touch within [`tol::TANGENT_REL`] of the scale, the touching
/// point in two consecutive slots (other crossings, if any, keep their own slots);
/// [`Contact::Disjoint`] with the gap at closest approach (exact for a parabola).
pub fn circle_conic(c: &Circle, k: &Conic) -> Intersection<P2, 4> {
    let [cx, cy, r] = circle_scale(c);
    let s = k.scale().max(tol::scale(&[cx, cy, r]));
    if r <= tol::LENGTH_REL * s {
        let (at, gap) = (c.center(), k.residual(c.center()));
        if gap <= tol::TANGENT_REL * s {
            return Intersection {
                roots: Roots::from_slice(&[at, at]),
                contact: Contact::Tangent,
            };
        }
        return Intersection::none(Contact::Disjoint { gap });
    }
    param_implicit(k, Curve::Circle(c), s)
}

/// Two conics: up to four roots.
///
/// Order: ascending parameter along the **first** conic `a` (see [`circle_conic`] for each
/// parameter), found as the roots of a quartic and polished on both curves; use [`nearest`] to
/// follow a branch. Crossings with the other branch of a hyperbola `b` are not roots.
/// Degenerate cases: [`Contact::Coincident`] when the conics are the same curve;
/// [`Contact::Tangent`] (touching point in two consecutive slots) and [`Contact::Disjoint`]
/// (gap estimate) as in [`circle_conic`].
pub fn conic_conic(a: &Conic, b: &Conic) -> Intersection<P2, 4> {
    let s = a.scale().max(b.scale());
    param_implicit(a, Curve::Conic(b), s)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::locus2d::{centres_line_circle, Ellipse, Hyperbola, Parabola, Sense};

    fn p(x: f64, y: f64) -> P2 {
        P2::new(x, y)
    }
    fn line(x: f64, y: f64, dx: f64, dy: f64) -> Line {
        Line::new(p(x, y), V2::new(dx, dy)).unwrap()
    }
    fn circle(x: f64, y: f64, r: f64) -> Circle {
        Circle::new(p(x, y), r).unwrap()
    }
    fn close(a: P2, b: P2, tol: f64) -> bool {
        (a - b).norm() <= tol
    }

    #[test]
    fn two_points_at_the_origin_meet_there() {
        // Every input zero: no scale to rescale to (this once recursed without end).
        let o = circle(0.0, 0.0, 0.0);
        let chord = circle_circle_chord(&o, &o).unwrap();
        assert_eq!((chord.left(), chord.right()), (P2::origin(), P2::origin()));
        assert_eq!(circle_circle(&o, &o).contact, Contact::Tangent);
        // Elsewhere, or tiny, the same point still meets itself.
        let q = circle(1e-310, 0.0, 0.0);
        assert!(circle_circle_chord(&q, &q).is_ok());
    }
    /// Whether `a` is within 4e-16 of `b` relative to `scale`, at any scale: the difference
    /// is scaled before it is squared, which neither overflows nor underflows.
    fn close_at(a: P2, b: P2, scale: f64) -> bool {
        ((a - b) / scale).norm() <= 4e-16
    }

    #[test]
    fn line_line_cases() {
        let i = line_line(&line(0.0, 0.0, 1.0, 0.0), &line(2.0, -1.0, 0.0, 1.0));
        assert_eq!(i.contact, Contact::Crossing);
        assert_eq!(i.branch(0), Some(p(2.0, 0.0)));
        let i = line_line(&line(0.0, 0.0, 1.0, 0.0), &line(5.0, 3.0, -1.0, 0.0));
        assert_eq!(i.contact, Contact::Parallel { gap: 3.0 });
        assert!(i.roots.is_empty());
        let i = line_line(&line(0.0, 0.0, 1.0, 0.0), &line(5.0, 0.0, 2.0, 0.0));
        assert_eq!(i.contact, Contact::Coincident);
        // Nearly parallel beyond tolerance: a far crossing, on both lines relative to its size.
        let b = line(0.0, 1.0, 1.0, 1e-9);
        let i = line_line(&line(0.0, 0.0, 1.0, 0.0), &b);
        let x = i.branch(0).unwrap();
        assert!(x.y.abs() < 1e-6 && b.residual(x) < 1e-13 * x.coords.norm());
    }

    #[test]
    fn line_ray_and_ray_ray_cases() {
        let l = line(0.0, 0.0, 1.0, 0.0);
        let r = Ray::new(p(1.0, 2.0), V2::new(0.0, -1.0)).unwrap();
        assert_eq!(line_ray(&l, &r).branch(0), Some(p(1.0, 0.0)));
        let away = Ray::new(p(1.0, 2.0), V2::new(0.0, 1.0)).unwrap();
        assert_eq!(line_ray(&l, &away).contact, Contact::Disjoint { gap: 2.0 });
        let par = Ray::new(p(1.0, 2.0), V2::new(1.0, 0.0)).unwrap();
        assert_eq!(line_ray(&l, &par).contact, Contact::Parallel { gap: 2.0 });
        let on = Ray::new(p(1.0, 0.0), V2::new(-1.0, 0.0)).unwrap();
        assert_eq!(line_ray(&l, &on).contact, Contact::Coincident);
        // Ray-ray.
        let r1 = Ray::new(p(0.0, 0.0), V2::new(1.0, 1.0)).unwrap();
        let r2 = Ray::new(p(2.0, 0.0), V2::new(-1.0, 1.0)).unwrap();
        let i = ray_ray(&r1, &r2);
        assert_eq!(i.contact, Contact::Crossing);
        assert!(close(i.branch(0).unwrap(), p(1.0, 1.0), 1e-15));
        let r3 = Ray::new(p(2.0, 0.0), V2::new(1.0, -1.0)).unwrap();
        let i = ray_ray(&r1, &r3);
        assert!(
            matches!(i.contact, Contact::Disjoint { gap } if (gap - 2f64.sqrt()).abs() < 1e-15)
        );
        let r4 = Ray::new(p(5.0, 0.0), V2::new(-1.0, 0.0)).unwrap();
        let r5 = Ray::new(p(0.0, 0.0), V2::new(1.0, 0.0)).unwrap();
        assert_eq!(ray_ray(&r5, &r4).contact, Contact::Coincident);
        let r6 = Ray::new(p(0.0, 0.0), V2::new(-1.0, 0.0)).unwrap();
        let i = ray_ray(&r5, &r6);
        assert_eq!(i.contact, Contact::Tangent);
        assert_eq!(i.branch(0), Some(p(0.0, 0.0)));
        let r7 = Ray::new(p(-3.0, 0.0), V2::new(-1.0, 0.0)).unwrap();
        assert_eq!(ray_ray(&r5, &r7).contact, Contact::Disjoint { gap: 3.0 });
        let r8 = Ray::new(p(-3.0, 0.0), V2::new(1.0, 0.0)).unwrap();
        assert_eq!(ray_ray(&r5, &r8).contact, Contact::Coincident);
        let r9 = Ray::new(p(0.0, 1.0), V2::new(1.0, 0.0)).unwrap();
        assert_eq!(ray_ray(&r5, &r9).contact, Contact::Parallel { gap: 1.0 });
    }

    #[test]
    fn line_circle_cases() {
        let c = circle(0.0, 0.0, 1.0);
        let i = line_circle(&line(-5.0, 0.0, 1.0, 0.0), &c);
        assert_eq!(i.contact, Contact::Crossing);
        assert_eq!(i.roots.as_slice(), &[p(-1.0, 0.0), p(1.0, 0.0)]);
        // Reversing the line swaps the branches.
        let i = line_circle(&line(-5.0, 0.0, -1.0, 0.0), &c);
        assert_eq!(i.roots.as_slice(), &[p(1.0, 0.0), p(-1.0, 0.0)]);
        let i = line_circle(&line(0.0, 1.0, 1.0, 0.0), &c);
        assert_eq!(i.contact, Contact::Tangent);
        assert_eq!(i.roots.as_slice(), &[p(0.0, 1.0), p(0.0, 1.0)]);
        // Missing by rounding: still tangent; missing by more: disjoint, with the gap.
        let i = line_circle(&line(0.0, 1.0 + 2e-15, 1.0, 0.0), &c);
        assert_eq!(i.contact, Contact::Tangent);
        let i = line_circle(&line(0.0, 1.0 + 1e-12, 1.0, 0.0), &c);
        assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 1e-12).abs() < 1e-15));
        let i = line_circle(&line(0.0, 3.0, 1.0, 0.0), &c);
        assert_eq!(i.contact, Contact::Disjoint { gap: 2.0 });
        // A circle of zero radius is a point: one root on the line, else the gap.
        let i = line_circle(&line(0.0, 0.0, 1.0, 0.0), &circle(2.0, 0.0, 0.0));
        assert_eq!(i.contact, Contact::Tangent);
        assert_eq!(i.roots.as_slice(), &[p(2.0, 0.0), p(2.0, 0.0)]);
        let i = line_circle(&line(0.0, 0.0, 1.0, 0.0), &circle(2.0, 0.5, 0.0));
        assert_eq!(i.contact, Contact::Disjoint { gap: 0.5 });
        // Rays keep the line's branch slots.
        let r = Ray::new(p(0.0, 0.0), V2::x()).unwrap();
        let i = ray_circle(&r, &c);
        assert_eq!(i.roots.as_slice(), &[None, Some(p(1.0, 0.0))]);
        let r = Ray::new(p(3.0, 0.0), V2::x()).unwrap();
        assert_eq!(ray_circle(&r, &c).contact, Contact::Disjoint { gap: 2.0 });
        let r = Ray::new(p(-3.0, 0.0), V2::x()).unwrap();
        assert_eq!(ray_circle(&r, &c).roots.len(), 2);
    }

    #[test]
    fn circle_circle_cases() {
        let a = circle(0.0, 0.0, 5.0);
        let b = circle(8.0, 0.0, 5.0);
        let i = circle_circle(&a, &b);
        assert_eq!(i.contact, Contact::Crossing);
        // Branch 0 left of the line from a's centre to b's: +y.
        assert!(close(i.branch(0).unwrap(), p(4.0, 3.0), 1e-15));
        assert!(close(i.branch(1).unwrap(), p(4.0, -3.0), 1e-15));
        let i = circle_circle(&b, &a);
        assert!(close(i.branch(0).unwrap(), p(4.0, -3.0), 1e-15));
        let i = circle_circle(&a, &circle(10.0, 0.0, 5.0));
        assert_eq!(i.contact, Contact::Tangent);
        assert_eq!(i.roots.as_slice(), &[p(5.0, 0.0), p(5.0, 0.0)]);
        let i = circle_circle(&a, &circle(2.0, 0.0, 3.0));
        assert_eq!(i.contact, Contact::Tangent);
        assert!(close(i.branch(0).unwrap(), p(5.0, 0.0), 1e-15));
        let i = circle_circle(&circle(2.0, 0.0, 3.0), &a);
        assert!(close(i.branch(1).unwrap(), p(5.0, 0.0), 1e-15));
        assert_eq!(
            circle_circle(&a, &circle(12.0, 0.0, 5.0)).contact,
            Contact::Disjoint { gap: 2.0 }
        );
        assert_eq!(
            circle_circle(&a, &circle(1.0, 0.0, 1.0)).contact,
            Contact::Disjoint { gap: 3.0 }
        );
        assert_eq!(
            circle_circle(&a, &circle(0.0, 0.0, 1.0)).contact,
            Contact::Disjoint { gap: 4.0 }
        );
        assert_eq!(circle_circle(&a, &a).contact, Contact::Coincident);
        // Zero radii: a point on the other circle, off it, and two points.
        let on = circle_circle(&a, &circle(0.0, 5.0, 0.0));
        assert_eq!(on.contact, Contact::Tangent);
        assert!(on
            .roots
            .as_slice()
            .iter()
            .all(|&x| close(x, p(0.0, 5.0), 1e-15)));
        assert_eq!(
            circle_circle(&a, &circle(1.0, 0.0, 0.0)).contact,
            Contact::Disjoint { gap: 4.0 }
        );
        let z = circle(1.0, 1.0, 0.0);
        assert_eq!(
            circle_circle(&z, &z).roots.as_slice(),
            &[p(1.0, 1.0), p(1.0, 1.0)]
        );
        assert_eq!(
            circle_circle(&z, &circle(1.0, 4.0, 0.0)).contact,
            Contact::Disjoint { gap: 3.0 }
        );
    }

    fn check_on(x: P2, a: f64, b: f64, tol: f64) {
        assert!(a <= tol && b <= tol, "{x} residuals {a:e} {b:e}");
    }

    /// The same crossing, tangent and disjoint circles at every scale a double holds: the
    /// direct computation inside `CHORD_SCALES` and the rescaled one outside give the same
    /// roots, scaled, to rounding. Heron's product overflows past about 1e76 and underflows
    /// below 1e-77, where an unscaled computation would miss or snap the roots.
    /// Where the chord's tests on `d²` find circles apart or nested, tests on `d` would too:
    /// `sqrt` is correctly rounded and monotone, and `sqrt(x * x) == |x|` in floating point.
    /// So the cold path never sees circles that `d` says overlap. (The converse can fail by
    /// one rounding: `d²` sees an overlap that `d` rounds away; those cross.) Checked on
    /// circles that touch to rounding, where it matters.
    #[test]
    fn no_crossing_by_d2_is_no_crossing_by_d() {
        let (mut near, mut finer) = (0, 0);
        for k in 0..50_000 {
            let (r1, r2) = (
                1.0 + f64::from(k % 97) * 0.013,
                0.7 + f64::from(k % 13) * 0.05,
            );
            let angle = f64::from(k) * 0.000_37;
            for radius in [r1 + r2, r1 - r2] {
                let c2 = P2::new(radius * angle.cos(), radius * angle.sin());
                let d2 = c2.coords.norm_squared();
                let d = d2.sqrt();
                let r = radius.abs();
                near += usize::from(d == r);
                if radius * radius - d2 <= 0.0 {
                    assert!(d >= r, "apart by d², not by d: {radius} {c2:?}");
                } else {
                    finer += usize::from(d >= r);
                }
                if d2 - radius * radius <= 0.0 {
                    assert!(d <= r, "nested by d², not by d: {radius} {c2:?}");
                }
            }
        }
        // Touching to the last bit in many cases, so that the test is not vacuous.
        assert!(near > 10_000 && finer > 0, "{near} {finer}");
    }

    #[test]
    fn circle_circle_at_every_scale() {
        // Powers of two from 1e-300 to 1e300, across both edges of `CHORD_SCALES`, so that
        // the inputs are exact at every scale.
        for e in [
            -996, -664, -266, -154, -152, -150, -133, -20, 0, 20, 133, 146, 148, 150, 266, 664, 996,
        ] {
            let k = 2f64.powi(e);
            let i = circle_circle(&circle(0.0, 0.0, 5.0 * k), &circle(8.0 * k, 0.0, 5.0 * k));
            assert_eq!(i.contact, Contact::Crossing, "scale {k:e}");
            assert!(
                close_at(i.branch(0).unwrap(), p(4.0 * k, 3.0 * k), k),
                "scale {k:e}"
            );
            assert!(
                close_at(i.branch(1).unwrap(), p(4.0 * k, -3.0 * k), k),
                "scale {k:e}"
            );
            let i = circle_circle(&circle(0.0, 0.0, 5.0 * k), &circle(10.0 * k, 0.0, 5.0 * k));
            assert_eq!(i.contact, Contact::Tangent, "scale {k:e}");
            assert!(
                close_at(i.branch(0).unwrap(), p(5.0 * k, 0.0), k),
                "scale {k:e}"
            );
            let i = circle_circle(&circle(0.0, 0.0, 5.0 * k), &circle(12.0 * k, 0.0, 5.0 * k));
            let Contact::Disjoint { gap } = i.contact else {
                panic!("scale {k:e}: {:?}", i.contact);
            };
            assert!((gap / k - 2.0).abs() <= 4e-16, "scale {k:e}: gap {gap:e}");
        }
        // A root beyond the largest double (near x = 1.198 MAX): no roots, an infinite gap,
        // never a NaN.
        let m = f64::MAX;
        let i = circle_circle(
            &circle(0.6 * m, 0.0, 0.6 * m),
            &circle(0.6 * m, 0.1 * m, 0.6 * m),
        );
        assert_eq!(i.contact, Contact::Disjoint { gap: f64::INFINITY });
        // Circles as large as a double holds, whose roots are doubles, are solved.
        let i = circle_circle(&circle(0.0, 0.0, m), &circle(m, 0.0, m));
        assert_eq!(i.contact, Contact::Crossing);
        let top = p(0.5 * m, m * 0.75f64.sqrt());
        assert!(close_at(i.branch(0).unwrap(), top, m));
    }
    #[test]
    fn line_conic_cases() {
        // Parabola y = x²/4 (focus (0,1), directrix y = -1).
        let par: Conic = Parabola::new(p(0.0, 1.0), line(0.0, -1.0, 1.0, 0.0))
            .unwrap()
            .into();
        let i = line_conic(&line(-10.0, 1.0, 1.0, 0.0), &par);
        assert_eq!(i.contact, Contact::Crossing);
        assert!(close(i.branch(0).unwrap(), p(-2.0, 1.0), 1e-14));
        assert!(close(i.branch(1).unwrap(), p(2.0, 1.0), 1e-14));
        let i = line_conic(&line(-10.0, 0.0, 1.0, 0.0), &par);
        assert_eq!(i.contact, Contact::Tangent);
        assert!(close(i.branch(0).unwrap(), p(0.0, 0.0), 1e-14));
        assert_eq!(i.branch(0), i.branch(1));
        let i = line_conic(&line(-10.0, -2.0, 1.0, 0.0), &par);
        assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 2.0).abs() < 1e-14));
        // Parallel to the axis: one root.
        let i = line_conic(&line(2.0, -5.0, 0.0, 1.0), &par);
        assert_eq!(i.roots.len(), 1);
        assert!(close(i.branch(0).unwrap(), p(2.0, 1.0), 1e-14));
        // Ellipse x²/25 + y²/9 = 1 (foci ±4).
        let ell: Conic = Ellipse::new(p(-4.0, 0.0), p(4.0, 0.0), 10.0)
            .unwrap()
            .into();
        let i = line_conic(&line(0.0, -10.0, 0.0, 1.0), &ell);
        assert!(close(i.branch(0).unwrap(), p(0.0, -3.0), 1e-14));
        assert!(close(i.branch(1).unwrap(), p(0.0, 3.0), 1e-14));
        let i = line_conic(&line(0.0, 4.0, 1.0, 0.0), &ell);
        assert!(matches!(i.contact, Contact::Disjoint { gap } if (gap - 1.0).abs() < 1e-14));
        assert_eq!(
            line_conic(&line(5.0, 0.0, 0.0, 1.0), &ell).contact,
            Contact::Tangent
        );
        // Hyperbola branch x²/4 - y²/5 = 1, x > 0 (foci ±3, diff 4): the x axis meets it once.
        let hyp: Conic = Hyperbola::new(p(-3.0, 0.0), p(3.0, 0.0), 4.0)
            .unwrap()
            .into();
        let i = line_conic(&line(-10.0, 0.0, 1.0, 0.0), &hyp);
        assert_eq!(i.roots.as_slice().len(), 1);
        assert!(close(i.branch(0).unwrap(), p(2.0, 0.0), 1e-14));
        // Only the other branch: disjoint.
        let i = line_conic(&line(-3.0, -10.0, 0.0, 1.0), &hyp);
        assert!(matches!(i.contact, Contact::Disjoint { .. }), "{i:?}");
        // diff = 0: the perpendicular bisector x = 0.
        let bis: Conic = Hyperbola::new(p(-3.0, 0.0), p(3.0, 0.0), 0.0)
            .unwrap()
            .into();
        let i = line_conic(&line(-10.0, 1.0, 1.0, 0.0), &bis);
        assert!(close(i.branch(0).unwrap(), p(0.0, 1.0), 1e-14));
        assert_eq!(
            line_conic(&line(0.0, 5.0, 0.0, 1.0), &bis).contact,
            Contact::Coincident
        );
        assert_eq!(
            line_conic(&line(1.0, 5.0, 0.0, 1.0), &bis).contact,
            Contact::Parallel { gap: 1.0 }
        );
        // Ray-conic keeps slots.
        let r = Ray::new(p(0.0, 1.0), V2::x()).unwrap();
        let i = ray_conic(&r, &par);
        assert_eq!(i.roots.len(), 2);
        assert_eq!(i.branch(0), Some(None));
        assert!(close(i.branch(1).unwrap().unwrap(), p(2.0, 1.0), 1e-14));
    }

    /// Kramer's circle problem (paper 000, section 4.2): circle G tangent to the line y = -4 and
    /// externally tangent to the circle C of radius 2 about the origin; the end of a segment of
    /// length 3 from P = (6, 3) is G's centre.
    #[test]
    fn kramer_circle_problem_parabola_circle() {
        let l = line(0.0, -4.0, 1.0, 0.0);
        let (c, rc) = (p(0.0, 0.0), 2.0);
        let par = centres_line_circle(&l, 0.0, c, Sense::Plus, rc).unwrap();
        let end = circle(6.0, 3.0, 3.0);
        let i = circle_conic(&end, &par.into());
        assert!(matches!(i.contact, Contact::Crossing), "{i:?}");
        assert_eq!(i.roots.len(), 2, "{i:?}");
        let mut last = f64::NEG_INFINITY;
        for &x in i.roots.as_slice() {
            let radius = l.signed_distance(x); // G's radius: tangent to L from above
            assert!(radius > 0.0);
            assert!((l.signed_distance(x) - radius).abs() < 1e-13); // tangent to L
            assert!(((x - c).norm() - (radius + rc)).abs() < 1e-13, "{x}"); // tangent to C
            assert!(((x - p(6.0, 3.0)).norm() - 3.0).abs() < 1e-13); // segment length 3
            let t = par.param_of(x);
            assert!(t > last);
            last = t;
        }
    }

    #[test]
    fn circle_conic_cases() {
        let par: Conic = Parabola::new(p(0.0, 1.0), line(0.0, -1.0, 1.0, 0.0))
            .unwrap()
            .into();
        // Four crossings: a circle about (0, 3) of radius 2.9; 2.5 misses by √8 - 2.5.
        let i = circle_conic(&circle(0.0, 3.0, 2.9), &par);
        assert_eq!(i.roots.len(), 4, "{i:?}");
        let xs: Vec<f64> = i.roots.as_slice().iter().map(|x| x.x).collect();
        assert!(xs.windows(2).all(|w| w[0] < w[1]));
        let gap = 8f64.sqrt() - 2.5;
        assert!(matches!(circle_conic(&circle(0.0, 3.0, 2.5), &par).contact,
            Contact::Disjoint { gap: g } if (g - gap).abs() < 1e-14));
        // Tangent at the vertex from below: circle about (0, -1) radius 1.
        let i = circle_conic(&circle(0.0, -1.0, 1.0), &par);
        assert_eq!(i.contact, Contact::Tangent, "{i:?}");
        assert_eq!(i.roots.len(), 2);
        assert!(close(i.branch(0).unwrap(), p(0.0, 0.0), 1e-9));
        assert!(
            matches!(circle_conic(&circle(0.0, -3.0, 1.0), &par).contact, Contact::Disjoint { gap } if (gap - 2.0).abs() < 1e-12)
        );
        // A circle of zero radius: a point on the parabola is its one root; off it, the gap.
        let at = p(2.0, 1.0);
        let on = circle_conic(&Circle::new(at, 0.0).unwrap(), &par);
        assert_eq!(
            (on.contact, on.roots.as_slice()),
            (Contact::Tangent, &[at, at][..])
        );
        assert!(matches!(
            circle_conic(&circle(0.0, -3.0, 0.0), &par).contact,
            Contact::Disjoint { .. }
        ));
        // An ellipse with equal foci is a circle: coincident.
        let e: Conic = Ellipse::new(p(1.0, 1.0), p(1.0, 1.0), 4.0).unwrap().into();
        assert_eq!(
            circle_conic(&circle(1.0, 1.0, 2.0), &e).contact,
            Contact::Coincident
        );
        // Ellipse and circle: x²/25 + y²/9 = 1 against the circle r = 4 about the centre.
        let ell: Conic = Ellipse::new(p(-4.0, 0.0), p(4.0, 0.0), 10.0)
            .unwrap()
            .into();
        let c = circle(0.0, 0.0, 4.0);
        let i = circle_conic(&c, &ell);
        assert_eq!(i.roots.len(), 4);
        for &x in i.roots.as_slice() {
            check_on(x, c.residual(x), ell.residual(x), 1e-14);
        }
        // Internally tangent at (±5, 0) and (0, ±3): circles r = 5 and r = 3.
        assert_eq!(
            circle_conic(&circle(0.0, 0.0, 5.0), &ell).contact,
            Contact::Tangent
        );
        assert_eq!(circle_conic(&circle(0.0, 0.0, 5.0), &ell).roots.len(), 4);
        // Hyperbola and circle.
        let hyp: Conic = Hyperbola::new(p(-3.0, 0.0), p(3.0, 0.0), 4.0)
            .unwrap()
            .into();
        let c = circle(0.0, 0.0, 3.0);
        let i = circle_conic(&c, &hyp);
        assert_eq!(i.roots.len(), 2, "{i:?}");
        for &x in i.roots.as_slice() {
            assert!(x.x > 0.0);
            check_on(x, c.residual(x), hyp.residual(x), 1e-14);
        }
    }

    #[test]
    fn conic_conic_cases() {
        let par: Conic = Parabola::new(p(0.0, 1.0), line(0.0, -1.0, 1.0, 0.0))
            .unwrap()
            .into();
        let ell: Conic = Ellipse::new(p(-4.0, 0.0), p(4.0, 0.0), 10.0)
            .unwrap()
            .into();
        let hyp: Conic = Hyperbola::new(p(-3.0, 0.0), p(3.0, 0.0), 4.0)
            .unwrap()
            .into();
        let hyp_left: Conic = Hyperbola::new(p(-3.0, 0.0), p(3.0, 0.0), -4.0)
            .unwrap()
            .into();
        for (a, b, n) in [
            (&par, &ell, 2),
            (&ell, &par, 2),
            (&hyp, &ell, 2),
            (&ell, &hyp, 2),
            (&par, &hyp, 2),
            (&hyp, &par, 2),
            (&hyp, &hyp_left, 0),
        ] {
            let i = conic_conic(a, b);
            assert_eq!(i.roots.len(), n, "{a:?} {b:?} {i:?}");
            let mut last = f64::NEG_INFINITY;
            for &x in i.roots.as_slice() {
                check_on(x, a.residual(x), b.residual(x), 1e-13);
                let t = a.param_of(x);
                assert!(t >= last);
                last = t;
            }
        }
        assert_eq!(conic_conic(&ell, &ell).contact, Contact::Coincident);
        assert_eq!(conic_conic(&par, &par).contact, Contact::Coincident);
        // Two ellipses touching at (5, 0): the second is x²/25 + y²/16 = 1.
        let tall: Conic = Ellipse::new(p(-3.0, 0.0), p(3.0, 0.0), 10.0)
            .unwrap()
            .into();
        let i = conic_conic(&ell, &tall);
        assert_eq!(i.contact, Contact::Tangent, "{i:?}");
        assert_eq!(i.roots.len(), 4);
        // A small ellipse far away: disjoint with a positive gap.
        let far: Conic = Ellipse::new(p(20.0, 0.0), p(22.0, 0.0), 4.0)
            .unwrap()
            .into();
        assert!(matches!(conic_conic(&ell, &far).contact, Contact::Disjoint { gap } if gap > 10.0));
        assert_eq!(
            nearest(&conic_conic(&par, &ell).roots, p(100.0, 0.0)),
            Some(1)
        );
    }
}
