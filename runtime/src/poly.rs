//! Real roots of polynomials of degree at most four, to full double precision.
//!
//! Coefficients are given highest degree first: `quadratic(a, b, c)` solves `a x² + b x + c = 0`.
//! Every finder returns the *distinct* real roots in **ascending order**; a multiple root is
//! returned once ([`real_roots`] also says which roots are multiple).
//!
//! Method:
//! - **Quadratic**: the cancellation-free form `q = -(b + sign(b) √disc) / 2`, `x = q / a, c / q`,
//!   with no loop; a discriminant within rounding of zero gives one double root `-b / 2a`.
//! - **Cubic and quartic**: the real roots are *isolated* between the critical points (the roots
//!   of the derivative, found recursively by the same method, so to full precision): on each
//!   interval the polynomial is monotone, so it has a root there exactly when its values at the
//!   ends have opposite signs. A critical point where the value is zero within the rounding error
//!   of Horner's rule ([`crate::tol::POLY_ZERO_REL`]) is a multiple root; because it is a simple
//!   root of the derivative it is found to full precision too, where a direct solve would lose
//!   half the digits. Each bracketed root is then polished by Newton's method on the original
//!   polynomial, its value computed by compensated Horner evaluation (as if in twice the
//!   precision), so close simple roots keep full precision too.
//! - **Starting points** come from closed forms, so that Newton usually needs one or two steps:
//!   the depressed cubic `t³ + pt + q` by the trigonometric method (three real roots) or the
//!   cancellation-free Cardano form `u - p / 3u` (one), and the quartic by Ferrari's
//!   factorisation into two quadratics through the largest root of its resolvent cubic. A closed
//!   form only proposes: a start outside its bracket (which happens near multiple roots, where
//!   the closed forms lose half the digits or turn a close real pair complex) is replaced by the
//!   bracket's midpoint, and Newton's method falls back to bisection whenever a step would leave
//!   the bracket or fails to halve (as in Numerical Recipes' `rtsafe`). So the closed forms set
//!   the speed, and the bracketing sets the correctness.
//!
//! Degenerate input: a zero leading coefficient lowers the degree (`a = 0` makes the quadratic
//! linear); a tiny nonzero one is kept and gives a root of large magnitude, computed without
//! overflow for the quadratic. The zero polynomial (every x is a root) and polynomials with a
//! NaN or infinite coefficient return no roots. Coefficients are scaled by a power of two first,
//! which is exact. Roots whose magnitude overflows when raised to the degree (beyond ~1e76 for a
//! quartic) may be missed; roots that are not finite are never returned. Nothing here panics or
//! allocates.
//!
//! Measured accuracy (test `worst_root_error_is_documented`, 30,000 polynomials of degree 2 to
//! 4 built from known roots in [-10, 10]):
//! - roots that are multiples of 1/256, so that the coefficients are exact: worst error **0**
//!   (every simple root, and every double, triple and quadruple root, is found to the last bit);
//! - random real roots separated by at least 1e-2, whose coefficients are rounded: worst error
//!   2.4e-10 relative, which is **1.7 condition numbers** `ε Σ|c_i||r|^i / |p'(r)|`: the roots of
//!   the rounded polynomial themselves moved that much; the method adds nothing measurable.
//!
//! Against the plain bracketing method without closed forms (test
//! `agrees_with_the_bracketing_method`, 200,000 cubics and quartics with clustered, double and
//! nearly double roots at scales 1e-6 to 1e6): the same roots, with the same multiplicity flags,
//! except in 2 cases where a critical value lies at the boundary of [`tol::POLY_ZERO_REL`]
//! (within a factor two of it), where the last bits of either evaluation decide whether a close
//! pair is one double root.

use crate::roots::Roots;
use crate::tol;

/// A real root and whether it is a multiple root (a zero of the polynomial and its derivative,
/// within rounding).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RealRoot {
    /// The root.
    pub x: f64,
    /// Whether the polynomial's derivative vanishes there too (a double or higher root).
    pub multiple: bool,
}

/// The value of the polynomial with coefficients `coeffs` (highest degree first) at `x`, by
/// Horner's rule. The empty polynomial is zero.
#[inline]
pub fn eval(coeffs: &[f64], x: f64) -> f64 {
    let mut p = 0.0;
    for &c in coeffs {
        p = p * x + c;
    }
    p
}

/// The distinct real roots of `a x² + b x + c`, ascending.
///
/// Stable form without cancellation. `a = 0` gives the linear root `-c / b`; `a = b = 0` gives
/// none; a discriminant within rounding of zero (relative to `b²` and `4|ac|`) gives the one
/// double root `-b / 2a`; a negative one gives none. NaN or infinite coefficients give none.
#[inline]
pub fn quadratic(a: f64, b: f64, c: f64) -> Roots<f64, 2> {
    let mut out = Roots::new();
    if finite(&[a, b, c]) {
        for r in roots2(a, b, c).as_slice() {
            out.push(r.x);
        }
    }
    out
}

/// The distinct real roots of `a x³ + b x² + c x + d`, ascending, polished by Newton's method.
///
/// `a = 0` drops to [`quadratic`]. A double or triple root is returned once. NaN or infinite
/// coefficients, and the zero polynomial, give none.
#[inline]
pub fn cubic(a: f64, b: f64, c: f64, d: f64) -> Roots<f64, 3> {
    let mut out = Roots::new();
    if finite(&[a, b, c, d]) {
        for r in roots3(a, b, c, d).as_slice() {
            out.push(r.x);
        }
    }
    out
}

/// The distinct real roots of `a x⁴ + b x³ + c x² + d x + e`, ascending, polished by Newton's
/// method.
///
/// `a = 0` drops to [`cubic`]. Multiple roots are returned once. NaN or infinite coefficients,
/// and the zero polynomial, give none.
#[inline]
pub fn quartic(a: f64, b: f64, c: f64, d: f64, e: f64) -> Roots<f64, 4> {
    let mut out = Roots::new();
    if finite(&[a, b, c, d, e]) {
        for r in roots4(a, b, c, d, e).0.as_slice() {
            out.push(r.x);
        }
    }
    out
}

/// The distinct real roots of the polynomial with coefficients `coeffs` (highest degree first,
/// degree at most four after leading zeros are dropped), ascending, each flagged when it is a
/// multiple root. A polynomial of higher degree, the zero polynomial, or any non-finite
/// coefficient gives no roots.
pub fn real_roots(coeffs: &[f64]) -> Roots<RealRoot, 4> {
    roots_and_critical(coeffs).0
}

/// [`real_roots`] of the polynomial and of its derivative (its critical points, which the
/// solver finds first anyway), in one call.
pub(crate) fn roots_and_critical(coeffs: &[f64]) -> (Roots<RealRoot, 4>, Roots<RealRoot, 4>) {
    let none = (Roots::new(), Roots::new());
    if !finite(coeffs) {
        return none;
    }
    let first = coeffs
        .iter()
        .position(|&x| x != 0.0)
        .unwrap_or(coeffs.len());
    match *coeffs.get(first..).unwrap_or(&[]) {
        [a, b] => (roots1(a, b), Roots::new()),
        [a, b, c] => (roots2(a, b, c), roots1(2.0 * a, b)),
        [a, b, c, d] => {
            let s = inverse_pow2(max_abs(&[a, b, c, d]));
            let p = [a * s, b * s, c * s, d * s];
            let crit = quad(3.0 * p[0], 2.0 * p[1], p[2]);
            (cubic_roots(&p, &crit), crit)
        }
        [a, b, c, d, e] => roots4(a, b, c, d, e),
        _ => none,
    }
}

#[inline]
fn finite(c: &[f64]) -> bool {
    c.iter().all(|x| x.is_finite())
}

#[inline]
fn max_abs(c: &[f64]) -> f64 {
    c.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// `2^-e` where `2^e <= m < 2^(e+1)` for a finite `m > 0`, the exponent clamped to ±1000: a
/// power of two that brings `m` near 1, from the bits of `m` (no logarithm). Scaling the
/// coefficients by it is exact and keeps Horner's rule away from overflow.
#[inline]
fn inverse_pow2(m: f64) -> f64 {
    let biased = ((m.to_bits() >> 52) & 0x7ff) as i64;
    // Subnormal m has biased exponent 0, i.e. e <= -1023: clamped to 1000 anyway.
    let e = (biased - 1023).clamp(-1000, 1000);
    f64::from_bits(((1023 - e) as u64) << 52)
}

/// `a x + b` (finite coefficients): none when `a = 0`.
#[inline]
fn roots1(a: f64, b: f64) -> Roots<RealRoot, 4> {
    if a == 0.0 {
        Roots::new()
    } else {
        linear(a, b)
    }
}

/// `a x² + b x + c` (finite coefficients, leading zeros allowed).
#[inline]
fn roots2(a: f64, b: f64, c: f64) -> Roots<RealRoot, 4> {
    if a == 0.0 {
        return roots1(b, c);
    }
    let s = inverse_pow2(max_abs(&[a, b, c]));
    quad(a * s, b * s, c * s)
}

/// `a x³ + b x² + c x + d` (finite coefficients, leading zeros allowed).
fn roots3(a: f64, b: f64, c: f64, d: f64) -> Roots<RealRoot, 4> {
    if a == 0.0 {
        return roots2(b, c, d);
    }
    let s = inverse_pow2(max_abs(&[a, b, c, d]));
    let p = [a * s, b * s, c * s, d * s];
    cubic_roots(&p, &quad(3.0 * p[0], 2.0 * p[1], p[2]))
}

/// `a x⁴ + b x³ + c x² + d x + e` (finite coefficients, leading zeros allowed), and its critical
/// points.
fn roots4(a: f64, b: f64, c: f64, d: f64, e: f64) -> (Roots<RealRoot, 4>, Roots<RealRoot, 4>) {
    if a == 0.0 {
        if b == 0.0 {
            return (roots2(c, d, e), roots1(2.0 * c, d));
        }
        let s = inverse_pow2(max_abs(&[b, c, d, e]));
        let p = [b * s, c * s, d * s, e * s];
        let crit = quad(3.0 * p[0], 2.0 * p[1], p[2]);
        return (cubic_roots(&p, &crit), crit);
    }
    let s = inverse_pow2(max_abs(&[a, b, c, d, e]));
    let p = [a * s, b * s, c * s, d * s, e * s];
    let crit = quartic_critical(&p);
    (quartic_roots(&p, &crit), crit)
}

fn linear(a: f64, b: f64) -> Roots<RealRoot, 4> {
    let mut out = Roots::new();
    let x = -b / a;
    if x.is_finite() {
        out.push(RealRoot { x, multiple: false });
    }
    out
}

/// The roots of `a x² + b x + c`, `a != 0`, coefficients at most a few units in magnitude.
#[inline]
fn quad(a: f64, b: f64, c: f64) -> Roots<RealRoot, 4> {
    let mut out = Roots::new();
    if a == 0.0 {
        return linear(b, c);
    }
    let disc = b * b - 4.0 * a * c;
    let noise = 4.0 * tol::POLY_ZERO_REL * (b * b + 4.0 * (a * c).abs());
    if disc.abs() <= noise {
        let x = -b / (2.0 * a);
        if x.is_finite() {
            out.push(RealRoot { x, multiple: true });
        }
    } else if disc > 0.0 {
        let q = -0.5 * (b + disc.sqrt().copysign(b));
        let (x1, x2) = (q / a, c / q);
        let (lo, hi) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
        if lo.is_finite() {
            out.push(RealRoot {
                x: lo,
                multiple: false,
            });
        }
        if hi.is_finite() {
            out.push(RealRoot {
                x: hi,
                multiple: false,
            });
        }
    }
    out
}

/// The critical points of the quartic `c` (the roots of its derivative, a cubic), to the
/// precision of plain double arithmetic: [`quartic_roots`] re-polishes, as if in twice the
/// precision, the one that turns out to be a multiple root.
///
/// Fast path: the closed form of the derivative and one Newton step per root, when the
/// derivative's discriminant is clearly away from zero (its roots are then well separated and
/// the closed form accurate to many digits). Otherwise the derivative's roots are isolated
/// between its own critical points, as for any cubic.
#[inline]
fn quartic_critical(c: &[f64; 5]) -> Roots<RealRoot, 4> {
    let d = [4.0 * c[0], 3.0 * c[1], 2.0 * c[2], c[3]];
    let (starts, k, clear) = cubic_starts_checked(d[0], d[1], d[2], d[3]);
    let starts = starts.get(..k).unwrap_or(&[]);
    if clear {
        let mut xs = [0.0; 3];
        let mut ok = true;
        for (x, &s) in xs.iter_mut().zip(starts) {
            let (v, dv, _, _) = eval_plain(&d, s);
            *x = s - v / dv;
            ok &= x.is_finite();
        }
        let xs = xs.get(..k).unwrap_or(&[]);
        if ok && xs.windows(2).all(|w| w[0] < w[1]) {
            let mut out = Roots::new();
            for &x in xs {
                out.push(RealRoot { x, multiple: false });
            }
            return out;
        }
    }
    let crit = quad(3.0 * d[0], 2.0 * d[1], d[2]);
    isolate::<4, false>(&d, crit.as_slice(), starts, 2.0e102)
}

/// The roots of the cubic `c` (`c[0] != 0`) given its critical points.
fn cubic_roots(c: &[f64; 4], crit: &Roots<RealRoot, 4>) -> Roots<RealRoot, 4> {
    let (starts, k) = cubic_starts(c[0], c[1], c[2], c[3]);
    isolate::<4, true>(c, crit.as_slice(), starts.get(..k).unwrap_or(&[]), 2.0e102)
}

/// The roots of the quartic `c` (`c[0] != 0`) given its critical points.
fn quartic_roots(c: &[f64; 5], crit: &Roots<RealRoot, 4>) -> Roots<RealRoot, 4> {
    let (starts, k) = quartic_starts(c);
    isolate::<5, true>(c, crit.as_slice(), starts.get(..k).unwrap_or(&[]), 6.0e76)
}

/// Approximate real roots of `a x³ + b x² + c x + d` by the closed form (unordered, possibly
/// inaccurate or non-finite: they only start Newton's method).
#[inline]
fn cubic_starts(a: f64, b: f64, c: f64, d: f64) -> ([f64; 3], usize) {
    let (x, k, _) = cubic_starts_checked(a, b, c, d);
    (x, k)
}

/// [`cubic_starts`], ascending when there are three, and whether the discriminant is clearly
/// away from zero (relative [`tol::CUBIC_CLEAR_REL`]), so that the roots are well separated and accurate.
#[inline]
fn cubic_starts_checked(a: f64, b: f64, c: f64, d: f64) -> ([f64; 3], usize, bool) {
    let (b, c, d) = (b / a, c / a, d / a);
    let shift = b * (1.0 / 3.0);
    // x = t - shift: t³ + p t + q.
    let p = c - b * shift;
    let q = d + shift * (2.0 * shift * shift - c);
    let (p3, q2) = (p * (1.0 / 3.0), 0.5 * q);
    let (qq, ppp) = (q2 * q2, p3 * p3 * p3);
    let delta = qq + ppp;
    // Rounding in p and q (from the shift) and in the discriminant itself.
    let noise = tol::CUBIC_CLEAR_REL * (qq + ppp.abs() + (shift * shift).powi(3));
    let clear = delta.abs() > noise && delta.is_finite();
    if delta < 0.0 {
        // Three real roots: t = 2 √(-p/3) cos(φ - 2πk/3), cos 3φ = -q/2 / (-p/3)^(3/2).
        let r = (-p3).sqrt();
        let cos3 = (-q2 / (r * r * r)).clamp(-1.0, 1.0);
        let (s, co) = (cos3.acos() * (1.0 / 3.0)).sin_cos();
        let h = 0.866_025_403_784_438_6 * s; // sin(2π/3) sin φ
        let m = 2.0 * r;
        // φ in [0, π/3]: cos(φ + 2π/3) <= cos(φ - 2π/3) <= cos φ.
        let t = [m * (-0.5 * co - h), m * (-0.5 * co + h), m * co];
        ([t[0] - shift, t[1] - shift, t[2] - shift], 3, clear)
    } else {
        // One real root (or a multiple one): Cardano without cancellation, u³ = -q/2 ∓ √Δ.
        let u = (-q2 - delta.sqrt().copysign(q2)).cbrt();
        let t = if u != 0.0 { u - p3 / u } else { 0.0 };
        ([t - shift, 0.0, 0.0], 1, clear)
    }
}

/// Approximate real roots of the quartic `c` by Ferrari's method (unordered, possibly
/// inaccurate or non-finite: they only start Newton's method).
#[inline]
fn quartic_starts(c: &[f64; 5]) -> ([f64; 4], usize) {
    let inv = 1.0 / c[0];
    let (a, b, cc, d) = (c[1] * inv, c[2] * inv, c[3] * inv, c[4] * inv);
    let shift = 0.25 * a;
    let s2 = shift * shift;
    // x = y - shift: y⁴ + p y² + q y + r.
    let p = b - 6.0 * s2;
    let q = cc - 2.0 * b * shift + 8.0 * s2 * shift;
    let r = d - cc * shift + b * s2 - 3.0 * s2 * s2;
    let mut out = [0.0; 4];
    let mut k = 0;
    let mut push_quad = |bq: f64, cq: f64| {
        // y² + bq y + cq.
        let disc = bq * bq - 4.0 * cq;
        if disc >= 0.0 {
            let h = -0.5 * (bq + disc.sqrt().copysign(bq));
            for y in [h, if h != 0.0 { cq / h } else { 0.0 }] {
                if let Some(slot) = out.get_mut(k) {
                    *slot = y - shift;
                    k += 1;
                }
            }
        }
    };
    // Resolvent: the largest root m of m³ + p m² + (p²/4 - r) m - q²/8, m ≥ 0, gives
    // y⁴ + p y² + q y + r = (y² - s y + p/2 + m + q/2s)(y² + s y + p/2 + m - q/2s), s = √(2m).
    let (ms, mk) = cubic_starts(1.0, p, 0.25 * p * p - r, -0.125 * q * q);
    let mut m = f64::NEG_INFINITY;
    for &x in ms.get(..mk).unwrap_or(&[]) {
        m = m.max(x);
    }
    if m > 0.0 && q != 0.0 {
        let s = (2.0 * m).sqrt();
        let (base, t) = (0.5 * p + m, q / (2.0 * s));
        push_quad(-s, base + t);
        push_quad(s, base - t);
    } else {
        // Biquadratic: z = y², z² + p z + r.
        let disc = p * p - 4.0 * r;
        if disc >= 0.0 {
            let h = -0.5 * (p + disc.sqrt().copysign(p));
            for z in [h, if h != 0.0 { r / h } else { 0.0 }] {
                if z >= 0.0 {
                    push_quad(0.0, -z);
                }
            }
        }
    }
    (out, k)
}

/// Value, and the running magnitude `sum |c_i| |x|^i`, by Horner's rule.
#[inline(always)]
fn eval_mag<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64) {
    let (mut p, mut mag) = (0.0f64, 0.0f64);
    let ax = x.abs();
    for &a in c {
        p = p * x + a;
        mag = mag * ax + a.abs();
    }
    (p, mag)
}

/// Value, first and second derivative (halved), the value by compensated Horner evaluation
/// (error-free transformations), as accurate as if computed in twice the precision, so that
/// Newton's method polishes roots to full precision even when they are close.
#[inline(always)]
fn eval_compensated<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64, f64) {
    let xs = Split::new(x);
    let (mut s, mut e, mut dp, mut ddp) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for &a in c {
        ddp = ddp * x + dp;
        dp = dp * x + s;
        let p = s * x;
        let pi = two_product_err(s, &xs, p);
        let t = p + a;
        let bb = t - p;
        let sigma = (p - (t - bb)) + (a - bb);
        e = e * x + (pi + sigma);
        s = t;
    }
    (s + e, dp, ddp)
}

/// Value, first and second derivative (halved), and the running magnitude
/// `sum |c_i| |x|^i`, by Horner's rule in plain double precision.
#[inline(always)]
fn eval_plain<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64, f64, f64) {
    let ax = x.abs();
    let (mut p, mut dp, mut ddp, mut mag) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for &a in c {
        ddp = ddp * x + dp;
        dp = dp * x + p;
        p = p * x + a;
        mag = mag * ax + a.abs();
    }
    (p, dp, ddp, mag)
}

/// A critical point `x` of `c` (a simple root of the derivative, found in plain precision)
/// polished by Newton's method on the derivative with compensated evaluation: two steps, each
/// kept only if it reduces the derivative's magnitude.
fn polish_critical<const N: usize>(c: &[f64; N], x: f64) -> f64 {
    // The derivative, padded with a leading zero to the same length (which changes no value).
    let mut d = [0.0; N];
    for (i, (dst, &a)) in d.iter_mut().skip(1).zip(c).enumerate() {
        *dst = a * (N - 1 - i) as f64;
    }
    let (mut best, mut best_v) = (x, eval_compensated(&d, x).0.abs());
    let mut y = x;
    for _ in 0..2 {
        let (v, dv, _) = eval_compensated(&d, y);
        let next = y - v / dv;
        if !next.is_finite() {
            break;
        }
        let nv = eval_compensated(&d, next).0.abs();
        if nv < best_v {
            best = next;
            best_v = nv;
        }
        y = next;
    }
    best
}

/// A float and its Veltkamp split into two halves of 26 bits (for exact products without FMA).
// With a fused multiply-add only `x` is read; without, only the halves.
#[allow(dead_code)]
struct Split {
    x: f64,
    hi: f64,
    lo: f64,
}

impl Split {
    #[inline(always)]
    fn new(x: f64) -> Self {
        let t = 134_217_729.0 * x; // 2^27 + 1
        let hi = t - (t - x);
        Split { x, hi, lo: x - hi }
    }
}

/// The rounding error `a b - p` of the product `p = fl(a b)`, exactly: by a fused multiply-add
/// where the target has one, else by Dekker's product of the split halves.
#[inline(always)]
fn two_product_err(a: f64, b: &Split, p: f64) -> f64 {
    #[cfg(target_feature = "fma")]
    {
        a.mul_add(b.x, -p)
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let sa = Split::new(a);
        ((sa.hi * b.hi - p) + sa.hi * b.lo + sa.lo * b.hi) + sa.lo * b.lo
    }
}

/// The roots of the polynomial `c` of degree `N - 1` (3 or 4, `c[0] != 0`) between its critical
/// points `crit` (ascending), starting Newton's method from `starts` where one lies in the
/// bracket. `limit` is where Horner's rule could overflow (`(f64::MAX / 8)^(1/n)`, with the
/// coefficients at most 8). `PRECISE` polishes with compensated evaluation (to the last
/// unit); without it, in plain double precision (to the rounding level of Horner's rule, for
/// critical points: their value, not their position, decides the isolation).
#[inline(always)]
fn isolate<const N: usize, const PRECISE: bool>(
    c: &[f64; N],
    crit: &[RealRoot],
    starts: &[f64],
    limit: f64,
) -> Roots<RealRoot, 4> {
    let n = (N - 1) as f64;
    // Cauchy's bound on the magnitude of every (complex) root: 1 + max |c_i / c_0|.
    let lead = c[0];
    let mut top = 0.0f64;
    for &a in c.iter().skip(1) {
        top = top.max(a.abs());
    }
    let far = (1.0 + top / lead.abs()).min(limit);
    let lo = crit.first().map_or(-far, |r| r.x.min(-far)).max(-limit);
    let hi = crit.last().map_or(far, |r| r.x.max(far)).min(limit);
    // Breakpoints: lo, the critical points, hi; with their values and magnitudes (independent
    // evaluations, which the processor overlaps).
    let mut xs = [0.0; 5];
    let mut k = 0;
    let mut push = |x: f64| {
        if let Some(slot) = xs.get_mut(k) {
            *slot = x;
            k += 1;
        }
    };
    push(lo);
    for r in crit {
        push(r.x.clamp(-limit, limit));
    }
    push(hi);
    let mut vs = [(0.0, 0.0); 5];
    for (v, &x) in vs.iter_mut().zip(&xs).take(k) {
        *v = eval_mag(c, x);
    }
    // Each interval with a sign change brackets one simple root; a critical point valued zero
    // is a multiple root. Slots in ascending order: (bracket or multiple root).
    let mut slots = [Slot::default(); 4];
    let mut ns = 0;
    let mut prev: Option<(f64, f64, bool)> = None;
    for (i, (&x, &(v, mag))) in xs.iter().zip(&vs).take(k).enumerate() {
        let interior = i != 0 && i + 1 != k;
        let zero = interior && v.abs() <= tol::POLY_ZERO_REL * n * mag;
        if let Some((px, pv, pzero)) = prev {
            let opposite = (pv < 0.0 && v > 0.0) || (pv > 0.0 && v < 0.0);
            if !pzero && !zero && opposite {
                let start = starts
                    .iter()
                    .copied()
                    .find(|&s| s > px && s < x)
                    .unwrap_or_else(|| bisect(px, x));
                if let Some(slot) = slots.get_mut(ns) {
                    *slot = Slot::bracket(px, x, pv, start);
                    ns += 1;
                }
            }
        }
        if zero {
            // A critical point that is a simple root of the derivative, found in plain
            // precision: polish it as if in twice the precision, since it is now a root.
            let simple = crit.get(i.wrapping_sub(1)).is_some_and(|r| !r.multiple);
            let x = if PRECISE && simple {
                polish_critical(c, x)
            } else {
                x
            };
            if let Some(slot) = slots.get_mut(ns) {
                *slot = Slot::multiple(x);
                ns += 1;
            }
        }
        prev = Some((x, v, zero));
    }
    let slots = slots.get_mut(..ns).unwrap_or(&mut []);
    // Polish every bracketed root in lockstep: the iterations of different roots are
    // independent, so the processor overlaps them.
    for _ in 0..200 {
        let mut busy = false;
        for slot in slots.iter_mut() {
            if !slot.done {
                slot.step::<N, PRECISE>(c);
                busy |= !slot.done;
            }
        }
        if !busy {
            break;
        }
    }
    let mut out = Roots::new();
    for slot in slots.iter() {
        let x = if slot.done {
            slot.x
        } else {
            best_of(c, slot.x, slot.lo, slot.hi)
        };
        if x.is_finite() {
            out.push(RealRoot {
                x,
                multiple: slot.multiple,
            });
        }
    }
    out
}

/// A root being polished in its bracket `[lo, hi]`, where the polynomial is monotone and has
/// the sign `neg_lo` at `lo` and the opposite one at `hi`: Newton's method from a start, keeping
/// the bracket, with bisection whenever a step would leave it or fails to halve the step before
/// last (as in Numerical Recipes' `rtsafe`). It is done when Newton's step is at the rounding
/// level (the root is polished to the last unit) or the bracket holds no other float.
#[derive(Clone, Copy, Debug, Default)]
struct Slot {
    x: f64,
    lo: f64,
    hi: f64,
    neg_lo: bool,
    dx: f64,
    dx_old: f64,
    done: bool,
    multiple: bool,
}

impl Slot {
    fn bracket(lo: f64, hi: f64, v_lo: f64, start: f64) -> Self {
        Slot {
            x: start,
            lo,
            hi,
            neg_lo: v_lo < 0.0,
            dx: f64::INFINITY,
            dx_old: f64::INFINITY,
            done: false,
            multiple: false,
        }
    }

    fn multiple(x: f64) -> Self {
        Slot {
            x,
            lo: x,
            hi: x,
            done: true,
            multiple: true,
            ..Slot::default()
        }
    }

    #[inline(always)]
    fn step<const N: usize, const PRECISE: bool>(&mut self, c: &[f64; N]) {
        let x = self.x;
        let (p, dp, half_ddp) = if PRECISE {
            eval_compensated(c, x)
        } else {
            let (p, dp, half_ddp, mag) = eval_plain(c, x);
            if p.abs() <= 2.0 * N as f64 * tol::ULP * mag {
                // At the rounding level of Horner's rule: as close as it can tell.
                self.done = true;
                return;
            }
            (p, dp, half_ddp)
        };
        #[cfg(test)]
        ITERS.with(|i| i.set(i.get() + 1));
        if p == 0.0 {
            self.done = true;
            return;
        }
        if (p < 0.0) == self.neg_lo {
            self.lo = x;
        } else {
            self.hi = x;
        }
        let newton = x - p / dp;
        let step = (newton - x).abs();
        let inside = newton > self.lo && newton < self.hi;
        // Newton's error after this step is about `step² p'' / 2p'`: when that is below a
        // quarter unit in the last place, `newton` is the root rounded (its value was computed
        // as if in twice the precision), and no further evaluation could move it.
        let quadratic_error = step * step * half_ddp.abs();
        if inside && quadratic_error <= tol::QUARTER_ULP * newton.abs() * dp.abs() {
            self.x = newton;
            self.done = true;
            return;
        }
        if step <= tol::POLY_STEP_REL * x.abs() {
            // Newton's step is at the rounding level: the root is polished.
            if inside {
                self.x = newton;
            }
            self.done = true;
            return;
        }
        let next = if inside && step <= 0.5 * self.dx_old {
            newton
        } else {
            bisect(self.lo, self.hi)
        };
        if next <= self.lo || next >= self.hi {
            // The bracket holds no other float: the best of its ends and the iterate.
            self.x = best_of(c, x, self.lo, self.hi);
            self.done = true;
            return;
        }
        self.dx_old = self.dx;
        self.dx = (next - x).abs();
        self.x = next;
    }
}

#[cfg(test)]
thread_local! {
/// Newton steps taken, for the tests.
pub(crate) static ITERS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) }; }

fn best_of<const N: usize>(c: &[f64; N], x: f64, lo: f64, hi: f64) -> f64 {
    let mut best = x;
    let mut bv = eval_compensated(c, x).0.abs();
    for e in [lo, hi] {
        let v = eval_compensated(c, e).0.abs();
        if v < bv {
            best = e;
            bv = v;
        }
    }
    best
}

/// A point strictly inside `(lo, hi)` when there is one: 0 across a sign change, the midpoint of
/// the bit patterns (a geometric-like mean, so huge brackets shrink in at most 64 steps) when
/// the ends differ by more than a factor of four, else the arithmetic midpoint.
fn bisect(lo: f64, hi: f64) -> f64 {
    if lo < 0.0 && hi > 0.0 {
        return 0.0;
    }
    let (a, b) = (lo.abs().min(hi.abs()), lo.abs().max(hi.abs()));
    let mid = if b > 4.0 * a {
        f64::from_bits(a.to_bits() / 2 + b.to_bits() / 2)
    } else {
        0.5 * a + 0.5 * b
    };
    if lo < 0.0 || hi < 0.0 && lo <= 0.0 {
        -mid
    } else {
        mid
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    mod reference {
        //! The previous method (bisection-heavy isolation, no closed forms), kept as an oracle.
        use crate::poly::{bisect, RealRoot};
        use crate::roots::Roots;
        use crate::tol;

        pub(super) fn real_roots(coeffs: &[f64]) -> Roots<RealRoot, 4> {
            match Poly::new(coeffs) {
                Some(p) => p.roots(),
                None => Roots::new(),
            }
        }

        /// A polynomial of degree `n <= 4`, coefficients highest first in `c[..=n]`, `c[0] != 0`.
        #[derive(Clone, Copy, Debug)]
        struct Poly {
            c: [f64; 5],
            n: usize,
        }

        impl Poly {
            fn new(coeffs: &[f64]) -> Option<Self> {
                if coeffs.iter().any(|c| !c.is_finite()) {
                    return None;
                }
                let first = coeffs.iter().position(|&c| c != 0.0)?;
                let rest = coeffs.get(first..)?;
                if rest.len() > 5 {
                    return None;
                }
                // Scale by a power of two (exact) so that the largest coefficient is near 1.
                let m = rest.iter().fold(0.0f64, |m, c| m.max(c.abs()));
                let s = pow2(-(m.log2().floor()));
                let mut c = [0.0; 5];
                for (dst, &src) in c.iter_mut().zip(rest) {
                    *dst = src * s;
                }
                Some(Poly {
                    c,
                    n: rest.len() - 1,
                })
            }

            fn coeffs(&self) -> &[f64] {
                self.c.get(..=self.n).unwrap_or(&[])
            }

            /// Value, derivative and the running magnitude `sum |c_i| |x|^i`.
            #[inline]
            fn eval3(&self, x: f64) -> (f64, f64, f64) {
                let (mut p, mut dp, mut mag) = (0.0, 0.0, 0.0);
                let ax = x.abs();
                for &c in self.coeffs() {
                    dp = dp * x + p;
                    p = p * x + c;
                    mag = mag * ax + c.abs();
                }
                (p, dp, mag)
            }

            /// Value and derivative, the value by compensated Horner evaluation (error-free
            /// transformations with `mul_add`), as accurate as if computed in twice the precision, so
            /// that Newton's method polishes roots to full precision even when they are close.
            #[inline]
            fn eval_compensated(&self, x: f64) -> (f64, f64) {
                let (mut s, mut c, mut dp) = (0.0f64, 0.0f64, 0.0f64);
                for &a in self.coeffs() {
                    dp = dp * x + (s + c);
                    let p = s * x;
                    let pi = s.mul_add(x, -p);
                    let t = p + a;
                    let bb = t - p;
                    let sigma = (p - (t - bb)) + (a - bb);
                    c = c * x + (pi + sigma);
                    s = t;
                }
                (s + c, dp)
            }

            fn derivative(&self) -> Poly {
                let mut c = [0.0; 5];
                let n = self.n;
                for (i, (dst, &src)) in c.iter_mut().zip(self.coeffs()).take(n).enumerate() {
                    *dst = src * (n - i) as f64;
                }
                Poly {
                    c,
                    n: n.saturating_sub(1),
                }
            }

            fn roots(&self) -> Roots<RealRoot, 4> {
                let mut out = Roots::new();
                match self.n {
                    0 => {}
                    1 => {
                        let x = -self.c[1] / self.c[0];
                        if x.is_finite() {
                            out.push(RealRoot { x, multiple: false });
                        }
                    }
                    2 => {
                        let (a, b, c) = (self.c[0], self.c[1], self.c[2]);
                        let disc = b * b - 4.0 * a * c;
                        let noise = 4.0 * tol::POLY_ZERO_REL * (b * b + 4.0 * (a * c).abs());
                        if disc.abs() <= noise {
                            let x = -b / (2.0 * a);
                            if x.is_finite() {
                                out.push(RealRoot { x, multiple: true });
                            }
                        } else if disc > 0.0 {
                            let q = -0.5 * (b + 1.0f64.copysign(b) * disc.sqrt());
                            let (x1, x2) = (q / a, c / q);
                            let (lo, hi) = if x1 <= x2 { (x1, x2) } else { (x2, x1) };
                            for x in [lo, hi] {
                                if x.is_finite() {
                                    out.push(RealRoot { x, multiple: false });
                                }
                            }
                        }
                    }
                    _ => self.isolate(&mut out),
                }
                out
            }

            /// Roots of a cubic or quartic between its critical points.
            fn isolate(&self, out: &mut Roots<RealRoot, 4>) {
                let crit = self.derivative().roots();
                // Fujiwara's bound on the magnitude of every (complex) root.
                let lead = self.c[0];
                let mut bound: f64 = 0.0;
                for (k, &c) in self.coeffs().iter().enumerate().skip(1) {
                    let r = (c / lead).abs();
                    let r = if k == self.n { r / 2.0 } else { r };
                    bound = bound.max(r.powf(1.0 / k as f64));
                }
                // Beyond `limit` Horner's rule could overflow (coefficients are scaled to at most 1).
                let limit = (f64::MAX / 8.0).powf(1.0 / self.n as f64);
                let far = (4.0 * bound).max(1.0).min(limit);
                // Breakpoints: -far, critical points, +far, each with its value and whether it is zero.
                let mut xs = [0.0; 5];
                let mut k = 0;
                let lo = crit
                    .as_slice()
                    .first()
                    .map_or(-far, |r| r.x.min(-far))
                    .max(-limit);
                let hi = crit
                    .as_slice()
                    .last()
                    .map_or(far, |r| r.x.max(far))
                    .min(limit);
                let mut push = |x: f64| {
                    if let Some(slot) = xs.get_mut(k) {
                        *slot = x;
                        k += 1;
                    }
                };
                push(lo);
                for r in crit.as_slice() {
                    push(r.x.clamp(-limit, limit));
                }
                push(hi);
                let xs = xs.get(..k).unwrap_or(&[]);
                let mut prev: Option<(f64, f64, bool)> = None;
                for (i, &x) in xs.iter().enumerate() {
                    let (v, _, mag) = self.eval3(x);
                    let interior = i != 0 && i + 1 != xs.len();
                    let zero = interior && v.abs() <= tol::POLY_ZERO_REL * self.n as f64 * mag;
                    if let Some((px, pv, pzero)) = prev {
                        let opposite = (pv < 0.0 && v > 0.0) || (pv > 0.0 && v < 0.0);
                        if !pzero && !zero && opposite {
                            let r = self.refine(px, x, pv);
                            if r.is_finite() {
                                out.push(RealRoot {
                                    x: r,
                                    multiple: false,
                                });
                            }
                        }
                    }
                    if zero {
                        out.push(RealRoot { x, multiple: true });
                    }
                    prev = Some((x, v, zero));
                }
            }

            /// The root in `[lo, hi]`, where the polynomial is monotone and `p(lo)` has the sign of
            /// `v_lo` and `p(hi)` the opposite sign: bracketed Newton iteration with bisection fallback.
            fn refine(&self, mut lo: f64, mut hi: f64, v_lo: f64) -> f64 {
                let neg_lo = v_lo < 0.0;
                let mut x = bisect(lo, hi);
                // Newton is taken when it stays in the bracket and its step is at most half the step
                // before last (as in Numerical Recipes' rtsafe); else the bracket is bisected.
                let (mut dx, mut dx_old) = (f64::INFINITY, f64::INFINITY);
                for _ in 0..200 {
                    let (p, dp) = self.eval_compensated(x);
                    if p == 0.0 {
                        return x;
                    }
                    if (p < 0.0) == neg_lo {
                        lo = x;
                    } else {
                        hi = x;
                    }
                    let newton = x - p / dp;
                    let wide = lo <= 0.0 && hi >= 0.0
                        || hi.abs().max(lo.abs()) > 4.0 * hi.abs().min(lo.abs());
                    let step = (newton - x).abs();
                    let use_newton = !wide && newton > lo && newton < hi && step <= 0.5 * dx_old;
                    let next = if use_newton { newton } else { bisect(lo, hi) };
                    dx_old = dx;
                    dx = (next - x).abs();
                    if next == x || next <= lo || next >= hi {
                        // The bracket holds no other float: the best of its ends and the iterate.
                        return self.best_of(x, lo, hi);
                    }
                    if use_newton && dx <= 2.0 * f64::EPSILON * x.abs() {
                        // Newton's last step was at the rounding level: the root is polished.
                        return self.best_of(next, lo, hi);
                    }
                    x = next;
                }
                self.best_of(x, lo, hi)
            }

            fn best_of(&self, x: f64, lo: f64, hi: f64) -> f64 {
                let mut best = x;
                let mut bv = self.eval_compensated(x).0.abs();
                for c in [lo, hi] {
                    let v = self.eval_compensated(c).0.abs();
                    if v < bv {
                        best = c;
                        bv = v;
                    }
                }
                best
            }
        }

        /// `2^e` for an integral `e`, saturating to the normal range (exact, unlike `powi` of a
        /// rounded base).
        fn pow2(e: f64) -> f64 {
            let e = if e.is_finite() {
                e.clamp(-1000.0, 1000.0)
            } else {
                0.0
            };
            (2.0f64).powi(e as i32)
        }
    }

    fn from_roots(rs: &[f64]) -> [f64; 5] {
        // Highest first, padded at the front with zeros to degree four.
        let mut c = [0.0f64; 5];
        c[4] = 1.0;
        let mut deg = 0;
        for &r in rs {
            // Multiply by (x - r): coefficients stored lowest-first in a temp.
            let mut lowfirst = [0.0; 5];
            for i in 0..=deg {
                lowfirst[i] = c[4 - i];
            }
            let mut next = [0.0; 5];
            for i in 0..=deg {
                next[i + 1] += lowfirst[i];
                next[i] -= r * lowfirst[i];
            }
            deg += 1;
            for i in 0..=deg {
                c[4 - i] = next[i];
            }
        }
        c
    }

    /// Closed-form starts leave Newton's method one or two steps per root (the count includes
    /// the critical points' plain-precision steps).
    #[test]
    fn closed_form_starts_need_few_newton_steps() {
        for (c, n) in [
            ([0.0, 1.0, -6.0, 11.0, -6.0], 3),
            ([1.0, -10.0, 35.0, -50.0, 24.0], 4),
            (from_roots(&[-3.0, -1.0, 1.0, 2.5]), 4),
            ([0.0, 1.0, 0.0, 1.0, -2.0], 1),
            ([1.0, 0.3, -5.0, 1.0, 2.0], 4),
        ] {
            ITERS.with(|i| i.set(0));
            let r = real_roots(&c);
            let iters = ITERS.with(|i| i.get());
            assert_eq!(r.len(), n, "{c:?}");
            assert!(iters <= 2 * n, "{c:?}: {iters} steps for {n} roots");
        }
    }

    /// Polynomials from clustered, double and nearly double roots, tiny perturbations of
    /// exact multiple roots, and random coefficients, at scales 1e-6..1e6.
    fn hard_cases(rng: &mut Rng, count: usize) -> Vec<[f64; 5]> {
        let mut out = Vec::new();
        for case in 0..count {
            let deg = 3 + case % 2;
            let scale = 10f64.powi((case / 7 % 13) as i32 - 6);
            let mut rs = [0.0; 4];
            for r in rs.iter_mut() {
                *r = (20.0 * rng.next() - 10.0) * scale;
            }
            let sep = 10f64.powi(-((case / 3 % 12) as i32)) * scale;
            match case % 5 {
                0 => rs[1] = rs[0] + sep,
                1 => {
                    rs[1] = rs[0] + sep;
                    rs[2] = rs[0] - sep;
                }
                2 => {
                    rs[1] = rs[0];
                    rs[3] = rs[2];
                }
                _ => {}
            }
            let mut c = from_roots(&rs[..deg]);
            match case % 5 {
                2 | 3 => {
                    // Nudge the constant term by a relative 1e-16..1e-6.
                    let e = 10f64.powf(-6.0 - 10.0 * rng.next());
                    c[4] += (rng.next() - 0.5) * e * c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                }
                4 => {
                    for x in c.iter_mut().skip(4 - deg) {
                        *x = 2.0 * rng.next() - 1.0;
                    }
                }
                _ => {}
            }
            out.push(c);
        }
        out
    }

    /// The fast method finds the same roots as the plain bracketing method it replaced, except
    /// where a critical point's value is at the boundary of [`tol::POLY_ZERO_REL`]: there the
    /// last bits of the evaluation decide whether a close pair is one double root, for either
    /// method.
    #[test]
    fn agrees_with_the_bracketing_method() {
        let mut rng = Rng(0x2545f4914f6cdd1d);
        let n = if cfg!(debug_assertions) {
            30_000
        } else {
            200_000
        };
        let cases = hard_cases(&mut rng, n);
        let (mut borderline, mut worst) = (0usize, 0.0f64);
        for c in &cases {
            let (got, want) = (real_roots(c), reference::real_roots(c));
            let same = got.len() == want.len()
                && got
                    .as_slice()
                    .iter()
                    .zip(want.as_slice())
                    .all(|(g, w)| g.multiple == w.multiple);
            if same {
                for (g, w) in got.as_slice().iter().zip(want.as_slice()) {
                    worst = worst.max((g.x - w.x).abs() / g.x.abs().max(1e-300));
                }
                continue;
            }
            // Every root flagged multiple by either method has a value at the boundary.
            let s = inverse_pow2(max_abs(c));
            let p = c.map(|x| x * s);
            let n = 4 - c.iter().take_while(|&&x| x == 0.0).count();
            let mut multiples = got
                .as_slice()
                .iter()
                .chain(want.as_slice())
                .filter(|r| r.multiple);
            assert!(
                multiples.clone().count() > 0,
                "{c:?}\n  new {got:?}\n  old {want:?}"
            );
            assert!(
                multiples.all(|r| {
                    let (_, mag) = eval_mag(&p, r.x);
                    let v = eval_compensated(&p, r.x).0.abs();
                    v >= 0.5 * tol::POLY_ZERO_REL * n as f64 * mag
                }),
                "{c:?}\n  new {got:?}\n  old {want:?}"
            );
            borderline += 1;
        }
        eprintln!(
            "{borderline} borderline of {} cases; otherwise worst relative difference {worst:e}",
            cases.len()
        );
        assert!(borderline <= cases.len() / 10_000);
    }

    #[test]
    fn quadratic_cases() {
        assert_eq!(quadratic(1.0, -3.0, 2.0).as_slice(), &[1.0, 2.0]);
        assert_eq!(quadratic(0.0, 2.0, -4.0).as_slice(), &[2.0]);
        assert!(quadratic(0.0, 0.0, 1.0).is_empty());
        assert!(quadratic(0.0, 0.0, 0.0).is_empty());
        assert!(quadratic(1.0, 0.0, 1.0).is_empty());
        assert_eq!(quadratic(1.0, -2.0, 1.0).as_slice(), &[1.0]);
        assert!(quadratic(f64::NAN, 1.0, 1.0).is_empty());
        assert!(quadratic(1.0, f64::INFINITY, 1.0).is_empty());
        // No cancellation: roots 1e-8 and 1e8.
        let r = quadratic(1.0, -(1e8 + 1e-8), 1.0);
        assert_eq!(r.len(), 2);
        assert!((r.as_slice()[0] - 1e-8).abs() <= 1e-8 * 4.0 * f64::EPSILON);
        assert!((r.as_slice()[1] - 1e8).abs() <= 1e8 * 4.0 * f64::EPSILON);
        // Tiny leading coefficient: one ordinary root and one huge root.
        let r = quadratic(1e-300, 1.0, -1.0);
        assert_eq!(r.len(), 2);
        assert!((r.as_slice()[1] - 1.0).abs() < 1e-15);
        // Huge coefficients do not overflow.
        let r = quadratic(1e300, -3e300, 2e300);
        assert_eq!(r.as_slice(), &[1.0, 2.0]);
    }

    #[test]
    fn cubic_and_quartic_cases() {
        let c = from_roots(&[-2.0, 0.5, 3.0]);
        let r = cubic(c[1], c[2], c[3], c[4]);
        assert_eq!(r.as_slice(), &[-2.0, 0.5, 3.0]);
        // Triple root.
        assert_eq!(cubic(1.0, -3.0, 3.0, -1.0).as_slice(), &[1.0]);
        // One real root.
        let r = cubic(1.0, 0.0, 1.0, -2.0);
        assert_eq!(r.as_slice(), &[1.0]);
        // Degree drops.
        assert_eq!(cubic(0.0, 1.0, -3.0, 2.0).as_slice(), &[1.0, 2.0]);
        assert_eq!(quartic(0.0, 0.0, 0.0, 1.0, -5.0).as_slice(), &[5.0]);
        assert!(quartic(0.0, 0.0, 0.0, 0.0, 0.0).is_empty());
        assert!(quartic(1.0, f64::NAN, 0.0, 0.0, 0.0).is_empty());
        assert!(cubic(f64::NEG_INFINITY, 0.0, 0.0, 0.0).is_empty());
        let c = from_roots(&[-3.0, -1.0, 1.0, 2.5]);
        assert_eq!(
            quartic(c[0], c[1], c[2], c[3], c[4]).as_slice(),
            &[-3.0, -1.0, 1.0, 2.5]
        );
        // Two double roots, flagged multiple.
        let c = from_roots(&[-1.0, -1.0, 2.0, 2.0]);
        let rr = real_roots(&c);
        assert_eq!(rr.len(), 2);
        assert!(rr.as_slice().iter().all(|r| r.multiple));
        assert_eq!(rr.as_slice()[0].x, -1.0);
        assert_eq!(rr.as_slice()[1].x, 2.0);
        // No real root.
        assert!(quartic(1.0, 0.0, 0.0, 0.0, 1.0).is_empty());
        // x^4 = 0.
        assert_eq!(quartic(1.0, 0.0, 0.0, 0.0, 0.0).as_slice(), &[0.0]);
        // Tiny leading coefficient keeps its far root without panicking.
        let r = cubic(1e-200, 1.0, -3.0, 2.0);
        assert!(r.as_slice().contains(&1.0) && r.as_slice().contains(&2.0));
        assert!(quartic(1e-300, 1e300, 1.0, 1.0, 1.0).len() <= 4);
        assert_eq!(eval(&[1.0, -3.0, 2.0], 2.0), 0.0);
    }

    /// A small deterministic generator (xorshift) so the test needs no dependency.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The worst error of the computed roots against the known ones, relative to
    /// max(1, |root|), and the worst error in units of the root's condition number
    /// `ε Σ|c_i||r|^i / |p'(r)|` (the movement of a simple root under coefficient rounding).
    fn worst_error(rs: &[f64], c: &[f64; 5]) -> (f64, f64) {
        let got = real_roots(c);
        let mut want: Vec<f64> = rs.to_vec();
        want.sort_by(|a, b| a.partial_cmp(b).unwrap());
        want.dedup();
        assert_eq!(
            got.len(),
            want.len(),
            "roots {rs:?} coeffs {c:?} got {got:?}"
        );
        let (mut worst, mut worst_cond) = (0.0f64, 0.0f64);
        for (g, &w) in got.as_slice().iter().zip(&want) {
            let e = (g.x - w).abs();
            worst = worst.max(e / w.abs().max(1.0));
            let mag = c.iter().fold(0.0, |m, &ci| m * w.abs() + ci.abs());
            let dp = rs
                .iter()
                .filter(|&&r| r != w)
                .fold(1.0, |d, &r| d * (w - r));
            worst_cond = worst_cond.max(e / (f64::EPSILON * mag / dp.abs()));
        }
        (worst, worst_cond)
    }

    fn exact_root(rng: &mut Rng, range: f64, denom: f64) -> f64 {
        ((2.0 * range * denom * rng.next()) as i64 - (range * denom) as i64) as f64 / denom
    }

    #[test]
    fn worst_root_error_is_documented() {
        let mut rng = Rng(0x9e3779b97f4a7c15);
        let (mut worst_exact, mut worst_multiple) = (0.0f64, 0.0f64);
        let (mut worst_rounded, mut worst_cond) = (0.0f64, 0.0f64);
        for case in 0..30_000 {
            let deg = 2 + case % 3;
            let mut rs = [0.0; 4];
            match case % 3 {
                0 => {
                    // Simple roots k/256 in [-10, 10]: the coefficients are exact, so any error
                    // is the method's.
                    for r in rs.iter_mut().take(deg) {
                        *r = exact_root(&mut rng, 10.0, 256.0);
                    }
                    let c = from_roots(&rs[..deg]);
                    worst_exact = worst_exact.max(worst_error(&rs[..deg], &c).0);
                }
                1 => {
                    // A double, triple or quadruple root among exact roots.
                    let m = 2 + (case / 3) % (deg - 1);
                    let base = exact_root(&mut rng, 10.0, 256.0);
                    for (i, r) in rs.iter_mut().take(deg).enumerate() {
                        *r = if i < m {
                            base
                        } else {
                            exact_root(&mut rng, 10.0, 256.0)
                        };
                    }
                    let c = from_roots(&rs[..deg]);
                    worst_multiple = worst_multiple.max(worst_error(&rs[..deg], &c).0);
                }
                _ => {
                    // Random real roots separated by at least 1e-2; the coefficients are
                    // rounded, which moves the roots themselves by their condition number.
                    'draw: loop {
                        for r in rs.iter_mut().take(deg) {
                            *r = 20.0 * rng.next() - 10.0;
                        }
                        for i in 0..deg {
                            for j in 0..i {
                                if (rs[i] - rs[j]).abs() < 1e-2 {
                                    continue 'draw;
                                }
                            }
                        }
                        break;
                    }
                    let c = from_roots(&rs[..deg]);
                    let (e, ec) = worst_error(&rs[..deg], &c);
                    worst_rounded = worst_rounded.max(e);
                    worst_cond = worst_cond.max(ec);
                }
            }
        }
        eprintln!(
            "worst exact-simple {worst_exact:e} exact-multiple {worst_multiple:e} \
             rounded {worst_rounded:e} = {worst_cond:.2} condition numbers"
        );
        assert!(worst_exact <= 2.0 * f64::EPSILON, "{worst_exact:e}");
        assert!(worst_multiple <= 2.0 * f64::EPSILON, "{worst_multiple:e}");
        assert!(worst_cond <= 4.0, "{worst_cond}");
    }
}
