//! Real roots of polynomials of degree at most four, to full double precision.
//!
//! Coefficients are given highest degree first: `quadratic(a, b, c)` solves `a x² + b x + c = 0`.
//! Every finder returns the *distinct* real roots in **ascending order**; a multiple root is
//! returned once ([`real_roots`] also says which roots are multiple).
//!
//! Method: the quadratic uses the cancellation-free form `q = -(b + sign(b) √disc) / 2`,
//! `x = q / a, c / q`. Cubics and quartics isolate their real roots between the critical points
//! (the roots of the derivative, found recursively by the same method): on each interval the
//! polynomial is monotone, so it has a root there exactly when its values at the ends have
//! opposite signs, and a bracketed, safeguarded Newton iteration converges to it to the last
//! unit in the last place (Newton polishing, with bisection whenever a step would leave the
//! bracket). A critical point where the value is zero within the rounding error of Horner's rule
//! ([`crate::tol::POLY_ZERO_REL`]) is a multiple root; because it is a simple root of the
//! derivative it is found to full precision too, where a direct solve would lose half the digits.
//!
//! Degenerate input: a zero leading coefficient lowers the degree (`a = 0` makes the quadratic
//! linear); a tiny nonzero one is kept and gives a root of large magnitude, computed without
//! overflow for the quadratic. The zero polynomial (every x is a root) and polynomials with a
//! NaN or infinite coefficient return no roots. Coefficients are scaled by a power of two first,
//! which is exact. Roots whose magnitude overflows when raised to the degree (beyond ~1e75 for a
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
//! Root values are refined with compensated Horner evaluation (as if in twice the precision), so
//! close simple roots keep full precision too.

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
pub fn quadratic(a: f64, b: f64, c: f64) -> Roots<f64, 2> {
    let mut out = Roots::new();
    for r in real_roots(&[a, b, c]).as_slice() {
        out.push(r.x);
    }
    out
}

/// The distinct real roots of `a x³ + b x² + c x + d`, ascending, polished by Newton's method.
///
/// `a = 0` drops to [`quadratic`]. A double or triple root is returned once. NaN or infinite
/// coefficients, and the zero polynomial, give none.
pub fn cubic(a: f64, b: f64, c: f64, d: f64) -> Roots<f64, 3> {
    let mut out = Roots::new();
    for r in real_roots(&[a, b, c, d]).as_slice() {
        out.push(r.x);
    }
    out
}

/// The distinct real roots of `a x⁴ + b x³ + c x² + d x + e`, ascending, polished by Newton's
/// method.
///
/// `a = 0` drops to [`cubic`]. Multiple roots are returned once. NaN or infinite coefficients,
/// and the zero polynomial, give none.
pub fn quartic(a: f64, b: f64, c: f64, d: f64, e: f64) -> Roots<f64, 4> {
    let mut out = Roots::new();
    for r in real_roots(&[a, b, c, d, e]).as_slice() {
        out.push(r.x);
    }
    out
}

/// The distinct real roots of the polynomial with coefficients `coeffs` (highest degree first,
/// degree at most four after leading zeros are dropped), ascending, each flagged when it is a
/// multiple root. A polynomial of higher degree, the zero polynomial, or any non-finite
/// coefficient gives no roots.
pub fn real_roots(coeffs: &[f64]) -> Roots<RealRoot, 4> {
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
            let wide =
                lo <= 0.0 && hi >= 0.0 || hi.abs().max(lo.abs()) > 4.0 * hi.abs().min(lo.abs());
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

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

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
