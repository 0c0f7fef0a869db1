//! The linear systems of a plan's linear stage: clusters whose directions are all known can
//! still translate and stretch (a closed profile of horizontal and vertical segments with
//! fillets, a belt of parallel runs), and every constraint left between them is linear in
//! those slides and free lengths. The analysis writes such a system once, as rows of terms
//! whose coefficients are dot and cross products of known directions, and *tears* it: it
//! orders the unknowns so that each row gives one unknown from the ones before, except for a
//! few (the tears), which the remaining rows (the closures) then fix. A solve is then one pass
//! over the rows carrying each unknown as an affine function of the tears, and a small dense
//! system for the tears: linear in the size of the system, allocation-free, with the same
//! arithmetic in the interpreter and in generated code.

use crate::tol;

/// The most tears a system may have: its closure is solved as a dense system of this size.
pub const MAX_TEARS: usize = 8;

/// The shape of a torn linear system, fixed when the model is analysed.
///
/// Row `r` reads `sum(coef[t] * x[term_unknown[t]]) = rhs[r]` over its terms
/// `t in row_start[r]..row_start[r + 1]`; an unknown may appear in several terms of a row
/// (their coefficients add up).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Torn<'a> {
    /// The number of unknowns.
    pub unknowns: usize,
    /// Where each row's terms start (one entry more than there are rows).
    pub row_start: &'a [u32],
    /// The unknown of each term.
    pub term_unknown: &'a [u16],
    /// The unknowns taken as the system's parameters, in order (at most [`MAX_TEARS`]).
    pub tears: &'a [u16],
    /// The row that gives each other unknown, with that unknown, in the order they are
    /// solved: every other unknown of the row is torn or solved before it.
    pub pivots: &'a [(u16, u16)],
    /// The rows the tears must satisfy, one per tear.
    pub closures: &'a [u16],
}

/// A system with no unique solution: the row whose pivot (or the closure row whose
/// elimination) vanished. Its constraint does not fix the unknown it was to fix, in this
/// configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singular {
    /// The row.
    pub row: usize,
}

impl Torn<'_> {
    /// Solves the system with coefficients `coef` (one per term) and right-hand sides `rhs`
    /// (one per row). `W` is the size of the working space, `N * (tears + 1)`.
    ///
    /// # Errors
    ///
    /// [`Singular`] when a pivot vanishes (relative to its row) or the closures do not fix
    /// the tears.
    #[inline]
    pub fn solve<const N: usize, const W: usize>(
        &self,
        coef: &[f64],
        rhs: &[f64],
    ) -> Result<[f64; N], Singular> {
        let mut forms = [0.0; W];
        let mut x = [0.0; N];
        self.solve_into(coef, rhs, &mut forms, &mut x)?;
        Ok(x)
    }

    /// [`Torn::solve`] into slices: `forms` holds `unknowns * (tears + 1)` numbers of working
    /// space, `x` the `unknowns` answers.
    ///
    /// # Errors
    ///
    /// As [`Torn::solve`]; also [`Singular`] (row 0) when a slice is too short or there are
    /// more than [`MAX_TEARS`] tears, which the analysis never writes.
    pub fn solve_into(
        &self,
        coef: &[f64],
        rhs: &[f64],
        forms: &mut [f64],
        x: &mut [f64],
    ) -> Result<(), Singular> {
        let k = self.tears.len();
        let w = k + 1;
        let n = self.unknowns;
        let rows = self.row_start.len().saturating_sub(1);
        let malformed = Singular { row: 0 };
        if k > MAX_TEARS
            || self.closures.len() != k
            || forms.len() < n * w
            || x.len() < n
            || rhs.len() < rows
            || coef.len() < self.term_unknown.len()
        {
            return Err(malformed);
        }
        forms[..n * w].fill(0.0);
        for (i, &t) in self.tears.iter().enumerate() {
            forms[t as usize * w + 1 + i] = 1.0;
        }
        // Each pivot row gives its unknown as an affine function of the tears.
        let mut acc = [0.0; MAX_TEARS + 1];
        for &(row, u) in self.pivots {
            let (row, u) = (row as usize, u as usize);
            let terms = self.terms(row).ok_or(malformed)?;
            acc[..w].fill(0.0);
            acc[0] = rhs[row];
            let mut pivot = 0.0;
            let mut size: f64 = 0.0;
            for t in terms {
                let j = self.term_unknown[t] as usize;
                let c = coef[t];
                size = size.max(c.abs());
                if j == u {
                    pivot += c;
                } else {
                    let form = forms.get(j * w..(j + 1) * w).ok_or(malformed)?;
                    for (a, f) in acc[..w].iter_mut().zip(form) {
                        *a -= c * f;
                    }
                }
            }
            // (A NaN pivot vanishes too.)
            if pivot.is_nan() || pivot.abs() <= tol::LINEAR_PIVOT_REL * size {
                return Err(Singular { row });
            }
            let form = forms.get_mut(u * w..(u + 1) * w).ok_or(malformed)?;
            for (f, a) in form.iter_mut().zip(&acc[..w]) {
                *f = a / pivot;
            }
        }
        // The closures: a dense system in the tears.
        let mut m = [[0.0; MAX_TEARS + 1]; MAX_TEARS];
        for (q, &row) in self.closures.iter().enumerate() {
            let row = row as usize;
            let terms = self.terms(row).ok_or(malformed)?;
            acc[..w].fill(0.0);
            for t in terms {
                let j = self.term_unknown[t] as usize;
                let form = forms.get(j * w..(j + 1) * w).ok_or(malformed)?;
                for (a, f) in acc[..w].iter_mut().zip(form) {
                    *a += coef[t] * f;
                }
            }
            m[q][..k].copy_from_slice(&acc[1..w]);
            m[q][k] = rhs[row] - acc[0];
        }
        let mut tears = [0.0; MAX_TEARS];
        eliminate(&mut m[..k], &mut tears[..k]).map_err(|q| Singular {
            row: self.closures[q] as usize,
        })?;
        for (j, xj) in x[..n].iter_mut().enumerate() {
            let form = &forms[j * w..(j + 1) * w];
            let mut v = form[0];
            for (f, t) in form[1..].iter().zip(&tears[..k]) {
                v += f * t;
            }
            *xj = v;
        }
        Ok(())
    }

    /// The terms of row `row`, or `None` if it has none in range.
    fn terms(&self, row: usize) -> Option<std::ops::Range<usize>> {
        let start = *self.row_start.get(row)? as usize;
        let end = *self.row_start.get(row + 1)? as usize;
        (start <= end && end <= self.term_unknown.len()).then_some(start..end)
    }
}

/// Solves the dense system whose augmented rows are `m` (`k` columns, then the right-hand
/// side) by Gaussian elimination with partial pivoting. `Err(q)`: the system is singular at
/// its column `q` (reported as the closure row `q`).
fn eliminate(m: &mut [[f64; MAX_TEARS + 1]], out: &mut [f64]) -> Result<(), usize> {
    let k = m.len();
    let size = m
        .iter()
        .flat_map(|row| row[..k].iter())
        .fold(0.0_f64, |s, v| s.max(v.abs()));
    for col in 0..k {
        let best = (col..k)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap_or(col);
        if m[best][col].is_nan() || m[best][col].abs() <= tol::LINEAR_PIVOT_REL * size {
            return Err(col);
        }
        m.swap(col, best);
        let (top, below) = m.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for row in below.iter_mut() {
            let f = row[col] / pivot_row[col];
            if f != 0.0 {
                for (x, p) in row[col..=k].iter_mut().zip(&pivot_row[col..=k]) {
                    *x -= f * p;
                }
            }
        }
    }
    for col in (0..k).rev() {
        let mut v = m[col][k];
        for c in col + 1..k {
            v -= m[col][c] * out[c];
        }
        out[col] = v / m[col][col];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Multiplies the system's sparse matrix by `x`.
    fn apply(s: &Torn<'_>, coef: &[f64], x: &[f64]) -> Vec<f64> {
        (0..s.row_start.len() - 1)
            .map(|r| {
                (s.row_start[r] as usize..s.row_start[r + 1] as usize)
                    .map(|t| coef[t] * x[s.term_unknown[t] as usize])
                    .sum()
            })
            .collect()
    }

    /// A closed loop of `n` unknowns: row `i` ties `x[i]` to `x[i+1]` (the last one to the
    /// first), plus a row fixing `x[0] + x[n/2]`; torn at `x[0]`.
    fn ring(n: usize) -> (Vec<u32>, Vec<u16>, Vec<(u16, u16)>) {
        let mut row_start = vec![0];
        let mut term_unknown = Vec::new();
        for i in 0..n - 1 {
            term_unknown.extend([i as u16, (i + 1) as u16]);
            row_start.push(term_unknown.len() as u32);
        }
        term_unknown.extend([0, (n / 2) as u16]);
        row_start.push(term_unknown.len() as u32);
        let pivots = (0..n - 1).map(|i| (i as u16, (i + 1) as u16)).collect();
        (row_start, term_unknown, pivots)
    }

    #[test]
    fn a_torn_ring_solves_exactly() {
        let n = 7;
        let (row_start, term_unknown, pivots) = ring(n);
        let s = Torn {
            unknowns: n,
            row_start: &row_start,
            term_unknown: &term_unknown,
            tears: &[0],
            pivots: &pivots,
            closures: &[(n - 1) as u16],
        };
        let coef: Vec<f64> = (0..term_unknown.len())
            .map(|t| {
                if t % 2 == 0 {
                    1.0
                } else {
                    -0.5 - t as f64 * 0.1
                }
            })
            .collect();
        let want: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).sin() * 4.0).collect();
        let rhs = apply(&s, &coef, &want);
        let x = s.solve::<7, 14>(&coef, &rhs).expect("a ring solves");
        for (a, b) in x.iter().zip(&want) {
            assert!((a - b).abs() < 1e-12, "{x:?} {want:?}");
        }
    }

    #[test]
    fn a_vanishing_pivot_names_its_row() {
        let s = Torn {
            unknowns: 2,
            row_start: &[0, 1, 3],
            term_unknown: &[0, 0, 1],
            tears: &[],
            pivots: &[(0, 0), (1, 1)],
            closures: &[],
        };
        // Row 1: x0 + 1e-20 x1 = 1: its pivot is nothing next to its row.
        let out = s.solve::<2, 2>(&[1.0, 1.0, 1e-20], &[2.0, 1.0]);
        assert_eq!(out, Err(Singular { row: 1 }));
    }

    #[test]
    fn closures_that_do_not_fix_the_tears_are_singular() {
        // x0 and x1 torn; both closures read x0 + x1.
        let s = Torn {
            unknowns: 2,
            row_start: &[0, 2, 4],
            term_unknown: &[0, 1, 0, 1],
            tears: &[0, 1],
            pivots: &[],
            closures: &[0, 1],
        };
        let out = s.solve::<2, 6>(&[1.0, 1.0, 2.0, 2.0], &[1.0, 2.0]);
        assert!(matches!(out, Err(Singular { .. })));
    }

    #[test]
    fn malformed_shapes_are_errors_not_panics() {
        let s = Torn {
            unknowns: 3,
            row_start: &[0, 5],
            term_unknown: &[0],
            tears: &[],
            pivots: &[(0, 0)],
            closures: &[],
        };
        assert!(s.solve::<3, 3>(&[1.0], &[1.0]).is_err());
    }

    proptest! {
        /// Random dense-ish systems torn at two unknowns, near-singular ones included: the
        /// answer satisfies every row to rounding, or the solve says which row is singular.
        #[test]
        fn random_torn_systems_solve_or_say_so(
            seed in proptest::collection::vec(-1.0f64..1.0, 64),
            tiny in prop_oneof![Just(1.0), Just(1e-6), Just(1e-13)],
        ) {
            // Unknowns 0, 1 torn; rows 0..4 give x2..x5 from the unknowns before; rows 4, 5
            // close on everything.
            let mut row_start = vec![0u32];
            let mut term_unknown = Vec::new();
            for u in 2..6u16 {
                term_unknown.extend(0..=u);
                row_start.push(term_unknown.len() as u32);
            }
            for _ in 0..2 {
                term_unknown.extend(0..6u16);
                row_start.push(term_unknown.len() as u32);
            }
            let s = Torn {
                unknowns: 6,
                row_start: &row_start,
                term_unknown: &term_unknown,
                tears: &[0, 1],
                pivots: &[(0, 2), (1, 3), (2, 4), (3, 5)],
                closures: &[4, 5],
            };
            let mut coef: Vec<f64> = (0..term_unknown.len()).map(|t| seed[t % 64] + 0.01 * t as f64).collect();
            // The last closure nearly repeats the first, by `tiny`.
            let (a, b) = (row_start[4] as usize, row_start[5] as usize);
            for t in 0..6 {
                coef[b + t] = coef[a + t] * (1.0 + tiny) + tiny * seed[(t + 7) % 64];
            }
            let want: Vec<f64> = (0..6).map(|i| seed[40 + i] * 10.0).collect();
            let rhs = apply(&s, &coef, &want);
            match s.solve::<6, 18>(&coef, &rhs) {
                Ok(x) => {
                    let back = apply(&s, &coef, &x);
                    let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for (r, (got, want)) in back.iter().zip(&rhs).enumerate() {
                        prop_assert!((got - want).abs() <= 1e-9 * scale * (1.0 + want.abs()),
                            "row {r}: {got} vs {want}");
                    }
                }
                Err(Singular { row }) => prop_assert!(row < 6),
            }
        }
    }
}
