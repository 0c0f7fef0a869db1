//! The iteration and the linear algebra both spaces share: the Jacobian's and JᵀJ's patterns,
//! dense LU and Cholesky, faer's sparse LU and Cholesky, the equilibration by a length scale,
//! Newton with Armijo backtracking and Levenberg-Marquardt with Nielsen's damping.
//!
//! A space (`planar`, `spatial`) owns its unknowns and equations and answers
//! the three questions of [`Equations`]: where the unknowns are, what the equations are worth,
//! and what their Jacobian is. Everything else is here, once.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, LltRef, SymbolicCholesky};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
use std::time::Instant;

/// Up to this many unknowns the linear algebra is dense; above it, sparse.
pub const DENSE_MAX: usize = 120;

/// Which iteration to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Newton-Raphson with backtracking: the fast one near a solution.
    Newton,
    /// Levenberg-Marquardt: the robust one far from a solution or on non-square systems.
    LevenbergMarquardt,
}

/// Which linear algebra to use, so that tests and benchmarks can force either path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Linear {
    /// Dense up to [`DENSE_MAX`] unknowns, sparse above.
    Auto,
    /// Always dense.
    Dense,
    /// Always sparse.
    Sparse,
}

impl Linear {
    /// Whether `n` unknowns take the sparse path.
    pub(super) fn sparse(self, n: usize) -> bool {
        match self {
            Linear::Auto => n > DENSE_MAX,
            Linear::Dense => false,
            Linear::Sparse => true,
        }
    }
}

/// How to solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Newton or Levenberg-Marquardt.
    pub method: Method,
    /// Stop when the largest absolute equation value (lengths and radians) is at most this.
    pub tolerance: f64,
    /// Stop after this many linear solves (Levenberg-Marquardt counts rejected trials too).
    pub max_iterations: usize,
    /// Record `(elapsed ns, max residual)` after every iteration, for time-to-accuracy plots.
    pub trace: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Newton,
            tolerance: 1e-12,
            max_iterations: 50,
            trace: false,
        }
    }
}

/// Why a solve stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The residual reached the tolerance.
    Converged,
    /// `max_iterations` ran out.
    MaxIterations,
    /// No step decreased the residual (line search or damping gave up).
    Stalled,
    /// The equations or the step became non-finite.
    NotFinite,
}

/// The result of one solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Linear solves done.
    pub iterations: usize,
    /// The largest absolute equation value at the returned point.
    pub max_residual: f64,
    /// Whether `max_residual <= tolerance`.
    pub converged: bool,
    /// Why it stopped.
    pub stop: Stop,
    /// `(ns since the solve began, max residual)`: the start, then after every iteration;
    /// empty unless [`Options::trace`].
    pub trace: Vec<(u64, f64)>,
}

/// What the iteration needs of a space's equations.
pub(super) trait Equations {
    /// The unknowns, which the iteration steps in place (`n` of them).
    fn unknowns_mut(&mut self) -> &mut [f64];
    /// Every equation's raw value (a length or an angle) at the current unknowns, into `f`.
    fn values(&mut self, f: &mut [f64]);
    /// The raw Jacobian at the current unknowns, added into `jv` (zero on entry) at the
    /// positions [`Solver::position`] gave.
    fn jacobian(&mut self, jv: &mut [f64]);
}

/// The sparse structures, built once.
struct Sparse {
    /// The Jacobian's pattern (square systems only).
    j: Option<SymbolicSparseColMat<usize>>,
    lu: Option<SymbolicLu<usize>>,
    numeric: NumericLu<usize, f64>,
    /// The upper triangle of JᵀJ.
    a: SymbolicSparseColMat<usize>,
    chol: SymbolicCholesky<usize>,
    l: Vec<f64>,
    buf: MemBuffer,
}

/// The linear algebra and the iteration for one system of `m` equations in `n` unknowns,
/// built once from the Jacobian's pattern and reused for every solve.
pub(super) struct Solver {
    n: usize,
    m: usize,
    sparse_path: bool,
    /// The equilibrated values `W F` at the current point and at a trial one.
    f: Vec<f64>,
    f_trial: Vec<f64>,
    x_trial: Vec<f64>,
    /// The Jacobian's pattern by column, for [`Solver::position`] on the sparse path.
    j_col_ptr: Vec<usize>,
    j_row_idx: Vec<usize>,
    // Unique entries per equation: (column, position in J).
    uent_ptr: Vec<usize>,
    uent_col: Vec<usize>,
    uent_pos: Vec<usize>,
    // JᵀJ accumulation: J[pa] * J[pb] into A[pt].
    pair_a: Vec<usize>,
    pair_b: Vec<usize>,
    pair_t: Vec<usize>,
    diag: Vec<usize>,
    jv: Vec<f64>,
    av: Vec<f64>,
    lu: Vec<f64>,
    perm: Vec<usize>,
    g: Vec<f64>,
    dsave: Vec<f64>,
    step: Vec<f64>,
    sp: Option<Sparse>,
    // Equilibration (see [`Solver::equilibrate`]): per Jacobian position its row and
    // column; per equation and per unknown whether it is a length (else an angle or a pure
    // number); the row weights and column scales of the current solve.
    jrow: Vec<usize>,
    jcol: Vec<usize>,
    row_len: Vec<bool>,
    col_len: Vec<bool>,
    w: Vec<f64>,
    cs: Vec<f64>,
}

impl Solver {
    /// Builds the Jacobian's and JᵀJ's patterns from the columns each equation reads
    /// (`cols[e]`, sorted, without repeats) and, on the sparse path, the symbolic
    /// factorisations. `row_len` and `col_len` say which equations and unknowns are lengths.
    pub(super) fn new(
        n: usize,
        cols: &[Vec<usize>],
        row_len: Vec<bool>,
        col_len: Vec<bool>,
        sparse_path: bool,
    ) -> Result<Solver, String> {
        let m = cols.len();
        let mut s = Solver {
            n,
            m,
            sparse_path,
            f: vec![0.0; m],
            f_trial: vec![0.0; m],
            x_trial: vec![0.0; n],
            j_col_ptr: Vec::new(),
            j_row_idx: Vec::new(),
            uent_ptr: vec![0],
            uent_col: Vec::new(),
            uent_pos: Vec::new(),
            pair_a: Vec::new(),
            pair_b: Vec::new(),
            pair_t: Vec::new(),
            diag: Vec::new(),
            jv: Vec::new(),
            av: Vec::new(),
            lu: Vec::new(),
            perm: vec![0; n],
            g: vec![0.0; n],
            dsave: vec![0.0; n],
            step: vec![0.0; n.max(m)],
            sp: None,
            jrow: Vec::new(),
            jcol: Vec::new(),
            row_len,
            col_len,
            w: vec![1.0; m],
            cs: vec![1.0; n],
        };
        // Jacobian positions.
        let mut jsym = None;
        if sparse_path {
            let mut col_rows: Vec<Vec<usize>> = vec![Vec::new(); n];
            for (e, cs) in cols.iter().enumerate() {
                for &c in cs {
                    col_rows[c].push(e);
                }
            }
            let mut col_ptr = vec![0usize];
            let mut row_idx = Vec::new();
            for rs in &col_rows {
                row_idx.extend_from_slice(rs);
                col_ptr.push(row_idx.len());
            }
            s.jv = vec![0.0; row_idx.len()];
            s.jrow = row_idx.clone();
            s.jcol = (0..n)
                .flat_map(|c| std::iter::repeat_n(c, col_ptr[c + 1] - col_ptr[c]))
                .collect();
            s.j_col_ptr = col_ptr.clone();
            s.j_row_idx = row_idx.clone();
            jsym = Some(SymbolicSparseColMat::new_checked(
                m, n, col_ptr, None, row_idx,
            ));
        } else {
            s.jv = vec![0.0; m * n];
            s.jrow = (0..m * n).map(|p| p / n).collect();
            s.jcol = (0..m * n).map(|p| p % n).collect();
        }
        for (e, cs) in cols.iter().enumerate() {
            for &c in cs {
                s.uent_col.push(c);
                s.uent_pos.push(s.position(e, c));
            }
            s.uent_ptr.push(s.uent_pos.len());
        }
        // JᵀJ: the upper triangle, (i <= j).
        let mut upper: Vec<Vec<usize>> = vec![Vec::new(); n];
        for cs in cols {
            for (ia, &i) in cs.iter().enumerate() {
                for &j in &cs[ia..] {
                    upper[j].push(i);
                }
            }
        }
        for (j, u) in upper.iter_mut().enumerate() {
            u.push(j);
            u.sort_unstable();
            u.dedup();
        }
        let apos: Box<dyn Fn(usize, usize) -> usize>;
        let mut asym = None;
        if sparse_path {
            let mut col_ptr = vec![0usize];
            let mut row_idx = Vec::new();
            for rs in &upper {
                row_idx.extend_from_slice(rs);
                col_ptr.push(row_idx.len());
            }
            let cp = col_ptr.clone();
            let ri = row_idx.clone();
            apos = Box::new(move |i, j| {
                let rs = &ri[cp[j]..cp[j + 1]];
                cp[j] + rs.binary_search(&i).unwrap_or(0)
            });
            s.av = vec![0.0; row_idx.len()];
            asym = Some(SymbolicSparseColMat::new_checked(
                n, n, col_ptr, None, row_idx,
            ));
        } else {
            s.av = vec![0.0; n * n];
            s.lu = vec![0.0; n * n];
            apos = Box::new(move |i, j| i * n + j);
        }
        for e in 0..m {
            let (a0, t) = (s.uent_ptr[e], s.uent_ptr[e + 1]);
            for a in a0..t {
                for bb in a..t {
                    s.pair_a.push(s.uent_pos[a]);
                    s.pair_b.push(s.uent_pos[bb]);
                    s.pair_t.push(apos(s.uent_col[a], s.uent_col[bb]));
                }
            }
        }
        s.diag = (0..n).map(|i| apos(i, i)).collect();
        if let Some(asym) = asym {
            let chol = factorize_symbolic_cholesky(
                asym.as_ref(),
                Side::Upper,
                Default::default(),
                Default::default(),
            )
            .map_err(|e| format!("sparse Cholesky analysis failed: {e:?}"))?;
            let mut req = chol
                .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
                .or(chol.solve_in_place_scratch::<f64>(1, Par::Seq));
            let mut lu = None;
            if m == n {
                if let Some(js) = &jsym {
                    let sy = factorize_symbolic_lu(js.as_ref(), Default::default())
                        .map_err(|e| format!("sparse LU analysis failed: {e:?}"))?;
                    req = req
                        .or(sy.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()))
                        .or(sy.solve_in_place_scratch::<f64>(1, Par::Seq));
                    lu = Some(sy);
                }
            }
            s.sp = Some(Sparse {
                l: vec![0.0; chol.len_val()],
                j: jsym,
                lu,
                numeric: NumericLu::new(),
                a: asym,
                chol,
                buf: MemBuffer::new(req),
            });
        }
        Ok(s)
    }

    /// The position in the Jacobian's values of entry (`e`, `col`), which must be in the
    /// pattern.
    pub(super) fn position(&self, e: usize, col: usize) -> usize {
        if self.sparse_path {
            let (cp, ri) = (&self.j_col_ptr, &self.j_row_idx);
            let rs = &ri[cp[col]..cp[col + 1]];
            cp[col] + rs.binary_search(&e).unwrap_or(0)
        } else {
            e * self.n + col
        }
    }

    /// Whether the sparse linear algebra is in use.
    pub(super) fn is_sparse(&self) -> bool {
        self.sparse_path
    }

    /// Sets the row weights and column scales of this solve from the length scale `l` of the
    /// start configuration: a length equation is divided by `l`, a length unknown is measured
    /// in units of `l` (angle equations and unknowns are left alone). The iteration then works
    /// on the dimensionless system `W J C d = -W F`, `dx = C d`, whose merit `|W F|^2`, pivot
    /// threshold, regularisation and floors are all independent of the model's units: a model
    /// scaled by `s` takes the same steps. A length scale that is not positive and finite is 1.
    pub(super) fn equilibrate(&mut self, l: f64) {
        let l = if l > 0.0 && l.is_finite() { l } else { 1.0 };
        for (w, &len) in self.w.iter_mut().zip(&self.row_len) {
            *w = if len { 1.0 / l } else { 1.0 };
        }
        for (c, &len) in self.cs.iter_mut().zip(&self.col_len) {
            *c = if len { l } else { 1.0 };
        }
    }

    /// Runs the iteration from the unknowns `eqs` holds (the caller has loaded them, chosen
    /// its sides and called [`Solver::equilibrate`]); they end at the returned point. `t0` is
    /// when the solve began, for the trace.
    pub(super) fn iterate<E: Equations>(
        &mut self,
        eqs: &mut E,
        opts: &Options,
        t0: Instant,
    ) -> Outcome {
        let n = self.n;
        let mut out = Outcome {
            iterations: 0,
            max_residual: f64::NAN,
            converged: false,
            stop: Stop::MaxIterations,
            trace: Vec::new(),
        };
        let (mut r, mut ss) = self.residual(eqs);
        self.f.copy_from_slice(&self.f_trial);
        let trace = |out: &mut Outcome, r: f64| {
            if opts.trace {
                out.trace.push((t0.elapsed().as_nanos() as u64, r));
            }
        };
        trace(&mut out, r);
        let mut mu = 0.0;
        let mut nu = 2.0;
        let mut fresh = true; // whether J at z is up to date
        loop {
            if !r.is_finite() {
                out.stop = Stop::NotFinite;
                break;
            }
            if r <= opts.tolerance {
                out.stop = Stop::Converged;
                break;
            }
            if out.iterations >= opts.max_iterations {
                out.stop = Stop::MaxIterations;
                break;
            }
            out.iterations += 1;
            match opts.method {
                Method::Newton => {
                    self.jacobian(eqs);
                    if !self.newton_step() {
                        self.normal_equations();
                        if !self.damped_step(1e-10, false) {
                            out.stop = Stop::NotFinite;
                            break;
                        }
                    }
                    // Backtracking on |F|^2 along the step.
                    let mut alpha = 1.0;
                    let mut accepted = false;
                    for _ in 0..30 {
                        let z = eqs.unknowns_mut();
                        self.x_trial[..n].copy_from_slice(&z[..n]);
                        for ((v, c), s) in z[..n].iter_mut().zip(&self.cs).zip(&self.step) {
                            *v += alpha * c * s;
                        }
                        let (rt, st) = self.residual(eqs);
                        if st.is_finite() && st <= (1.0 - 1e-4 * alpha) * ss {
                            r = rt;
                            ss = st;
                            self.f.copy_from_slice(&self.f_trial);
                            accepted = true;
                            break;
                        }
                        eqs.unknowns_mut()[..n].copy_from_slice(&self.x_trial[..n]);
                        alpha *= 0.5;
                    }
                    if !accepted {
                        out.stop = Stop::Stalled;
                        trace(&mut out, r);
                        break;
                    }
                }
                Method::LevenbergMarquardt => {
                    if fresh {
                        self.jacobian(eqs);
                        self.normal_equations();
                        if mu == 0.0 {
                            mu = 1e-3;
                        }
                    }
                    if !self.damped_step(mu, true) {
                        mu *= nu;
                        nu *= 2.0;
                        fresh = false;
                    } else {
                        // Predicted reduction: d' (mu D d - g).
                        let mut pred = 0.0;
                        for i in 0..n {
                            let dd = self.av[self.diag[i]].max(1e-12);
                            pred += self.step[i] * (mu * dd * self.step[i] - self.g[i]);
                        }
                        let z = eqs.unknowns_mut();
                        self.x_trial[..n].copy_from_slice(&z[..n]);
                        for ((v, c), s) in z[..n].iter_mut().zip(&self.cs).zip(&self.step) {
                            *v += c * s;
                        }
                        let (rt, st) = self.residual(eqs);
                        let rho = (ss - st) / pred;
                        if st.is_finite() && rho > 0.0 {
                            r = rt;
                            ss = st;
                            self.f.copy_from_slice(&self.f_trial);
                            mu *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                            nu = 2.0;
                            fresh = true;
                        } else {
                            eqs.unknowns_mut()[..n].copy_from_slice(&self.x_trial[..n]);
                            mu *= nu;
                            nu *= 2.0;
                            fresh = false;
                        }
                    }
                    if !mu.is_finite() || mu > 1e300 {
                        out.stop = Stop::Stalled;
                        trace(&mut out, r);
                        break;
                    }
                }
            }
            trace(&mut out, r);
        }
        out.max_residual = r;
        out.converged = r <= opts.tolerance;
        out
    }

    /// Evaluates the equations into `f_trial`, weighted (`W F`); returns (max |F|, |W F|^2):
    /// the raw largest residual (what the tolerance is on) and the dimensionless merit.
    pub(super) fn residual<E: Equations>(&mut self, eqs: &mut E) -> (f64, f64) {
        eqs.values(&mut self.f_trial);
        let (mut mx, mut ss) = (0.0f64, 0.0);
        for e in 0..self.m {
            let v = self.f_trial[e];
            mx = mx.max(v.abs());
            if v.is_nan() {
                mx = f64::NAN;
            }
            let v = v * self.w[e];
            self.f_trial[e] = v;
            ss += v * v;
        }
        if mx.is_nan() {
            return (f64::NAN, f64::NAN);
        }
        (mx, ss)
    }

    /// The equilibrated Jacobian `W J C` into `jv`.
    pub(super) fn jacobian<E: Equations>(&mut self, eqs: &mut E) {
        self.jv.iter_mut().for_each(|v| *v = 0.0);
        eqs.jacobian(&mut self.jv);
        for ((v, &r), &c) in self.jv.iter_mut().zip(&self.jrow).zip(&self.jcol) {
            *v *= self.w[r] * self.cs[c];
        }
    }

    /// The equilibrated Jacobian's values, as [`Solver::jacobian`] left them.
    #[cfg(test)]
    pub(super) fn jacobian_values(&self) -> &[f64] {
        &self.jv
    }

    /// The equilibrated values [`Solver::residual`] left.
    #[cfg(test)]
    pub(super) fn trial_values(&self) -> &[f64] {
        &self.f_trial
    }

    /// The scale of column `c` of the current solve.
    #[cfg(test)]
    pub(super) fn column_scale(&self, c: usize) -> f64 {
        self.cs[c]
    }

    /// A = JᵀJ (upper triangle) and g = JᵀF.
    fn normal_equations(&mut self) {
        self.av.iter_mut().for_each(|v| *v = 0.0);
        for ((&a, &b), &t) in self.pair_a.iter().zip(&self.pair_b).zip(&self.pair_t) {
            self.av[t] += self.jv[a] * self.jv[b];
        }
        self.g.iter_mut().for_each(|v| *v = 0.0);
        for e in 0..self.m {
            for u in self.uent_ptr[e]..self.uent_ptr[e + 1] {
                self.g[self.uent_col[u]] += self.jv[self.uent_pos[u]] * self.f[e];
            }
        }
    }

    /// The Newton step `J d = -F` for a square system; false if not square or singular.
    fn newton_step(&mut self) -> bool {
        let n = self.n;
        if self.m != n {
            return false;
        }
        for i in 0..n {
            self.step[i] = -self.f[i];
        }
        let ok = if let Some(sp) = &mut self.sp {
            let (Some(js), Some(lu)) = (&sp.j, &sp.lu) else {
                return false;
            };
            let mat = SparseColMatRef::new(js.as_ref(), &self.jv);
            match lu.factorize_numeric_lu(
                &mut sp.numeric,
                mat,
                Par::Seq,
                MemStack::new(&mut sp.buf),
                Default::default(),
            ) {
                Ok(f) => {
                    f.solve_in_place_with_conj(
                        Conj::No,
                        MatMut::from_column_major_slice_mut(&mut self.step[..n], n, 1),
                        Par::Seq,
                        MemStack::new(&mut sp.buf),
                    );
                    true
                }
                Err(_) => false,
            }
        } else {
            self.lu.copy_from_slice(&self.jv);
            dense_lu(&mut self.lu, &mut self.perm, n) && {
                dense_lu_solve(&self.lu, &self.perm, n, &mut self.step[..n]);
                true
            }
        };
        ok && self.step[..n].iter().all(|v| v.is_finite())
    }

    /// The step `(JᵀJ + mu D) d = -JᵀF`, with `D = diag(JᵀJ)` (floored) if `scaled`, else
    /// `D = max diag` (a Levenberg step, used for Newton's fallback). Restores `av`.
    fn damped_step(&mut self, mu: f64, scaled: bool) -> bool {
        let n = self.n;
        let mx = self.diag.iter().map(|&p| self.av[p]).fold(0.0, f64::max);
        for i in 0..n {
            let d = self.av[self.diag[i]];
            self.dsave[i] = d;
            let add = if scaled {
                mu * d.max(1e-12)
            } else {
                mu * mx.max(1e-300)
            };
            self.av[self.diag[i]] = d + add;
            self.step[i] = -self.g[i];
        }
        let ok = if let Some(sp) = &mut self.sp {
            let mat = SparseColMatRef::new(sp.a.as_ref(), &self.av);
            match sp.chol.factorize_numeric_llt(
                &mut sp.l,
                mat,
                Side::Upper,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut sp.buf),
                Default::default(),
            ) {
                Ok(_) => {
                    LltRef::new(&sp.chol, &sp.l).solve_in_place_with_conj(
                        Conj::No,
                        MatMut::from_column_major_slice_mut(&mut self.step[..n], n, 1),
                        Par::Seq,
                        MemStack::new(&mut sp.buf),
                    );
                    true
                }
                Err(_) => false,
            }
        } else {
            self.lu.copy_from_slice(&self.av);
            dense_cholesky(&mut self.lu, n) && {
                dense_cholesky_solve(&self.lu, n, &mut self.step[..n]);
                true
            }
        };
        for i in 0..n {
            self.av[self.diag[i]] = self.dsave[i];
        }
        ok && self.step[..n].iter().all(|v| v.is_finite())
    }
}

/// In-place LU with partial pivoting of a row-major `n x n` matrix; false if singular.
fn dense_lu(a: &mut [f64], perm: &mut [usize], n: usize) -> bool {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return false;
    }
    for k in 0..n {
        let mut p = k;
        let mut best = a[k * n + k].abs();
        for i in k + 1..n {
            let v = a[i * n + k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best <= 1e-14 * scale {
            return false;
        }
        perm[k] = p;
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
        }
        let piv = a[k * n + k];
        for i in k + 1..n {
            let l = a[i * n + k] / piv;
            a[i * n + k] = l;
            if l != 0.0 {
                for j in k + 1..n {
                    a[i * n + j] -= l * a[k * n + j];
                }
            }
        }
    }
    true
}

fn dense_lu_solve(a: &[f64], perm: &[usize], n: usize, b: &mut [f64]) {
    for (k, &p) in perm.iter().enumerate().take(n) {
        b.swap(k, p);
    }
    for i in 0..n {
        let mut s = b[i];
        for j in 0..i {
            s -= a[i * n + j] * b[j];
        }
        b[i] = s;
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for j in i + 1..n {
            s -= a[i * n + j] * b[j];
        }
        b[i] = s / a[i * n + i];
    }
}

/// In-place Cholesky `A = UᵀU` of the upper triangle of a row-major matrix; false if not
/// positive definite.
fn dense_cholesky(a: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        for i in 0..=j {
            let mut s = a[i * n + j];
            for k in 0..i {
                s -= a[k * n + i] * a[k * n + j];
            }
            if i == j {
                if s <= 0.0 || !s.is_finite() {
                    return false;
                }
                a[j * n + j] = s.sqrt();
            } else {
                a[i * n + j] = s / a[i * n + i];
            }
        }
    }
    true
}

fn dense_cholesky_solve(u: &[f64], n: usize, b: &mut [f64]) {
    // Uᵀ y = b
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= u[k * n + i] * b[k];
        }
        b[i] = s / u[i * n + i];
    }
    // U x = y
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= u[i * n + k] * b[k];
        }
        b[i] = s / u[i * n + i];
    }
}
