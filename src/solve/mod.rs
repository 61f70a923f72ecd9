//! Direct sparse solvers over faer.
//!
//! * Symmetric positive definite matrices: supernodal LLᵀ on the Jacobi-scaled matrix `S A S`
//!   (`S = diag(A)^-1/2`, unit diagonal).
//! * Symmetric indefinite matrices (the saddle points of multipliers): supernodal LDLᵀ without pivoting on
//!   the equilibrated matrix (largest entry of every row and column 1), with the unknowns without a positive
//!   diagonal (multipliers) ordered after their neighbours, as in a quasi-definite matrix, and iterative refinement against
//!   the original matrix; when the refinement does not reach round-off the matrix is factorised again by LU.
//! * Non-symmetric matrices: sparse LU with partial pivoting.
//!
//! The fill-reducing ordering is AMD or nested dissection (METIS) by size ([`ordering`]); the symbolic
//! analysis (ordering + elimination tree + supernodes) can be kept in an [`Analysis`] and reused while the
//! pattern does not change (Newton iterations, time steps); the numeric factorisation and the solves run on
//! `threads` threads.
//!
//! Precision (Code_Aster's `NPREC`): a pivot of the scaled matrix below `10^-NPREC` of its diagonal (of 1
//! for a zero diagonal) means that more than `NPREC` digits were lost: the matrix is declared singular at
//! that unknown. Such pivots are regularised during the factorisation, so every singular unknown is found
//! in one pass. Every factorisation estimates the 1-norm condition number of the scaled matrix
//! (Hager–Higham, from the factors) and reports the digits it costs. `RESI_RELA` bounds the relative
//! residual `‖b − A x‖ / ‖b‖` after the solve.

mod cholesky;
mod lu;
mod norms;
pub mod ordering;
mod scaling;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::{Solve, SolveCore};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, LdltRef, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
pub use ordering::Ordering;
use std::fmt;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Factorisation method.
pub use cholesky::Analysis;
use cholesky::*;
use lu::*;
pub use norms::*;
use scaling::*;
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// LLᵀ when the matrix is symmetric with a positive diagonal, LDLᵀ when it is symmetric with zero or
    /// negative diagonal entries, LU otherwise.
    Auto,
    Cholesky,
    /// Symmetric indefinite LDLᵀ (refined; LU when the refinement fails).
    Ldlt,
    Lu,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "automatic",
            Method::Cholesky => "LLT",
            Method::Ldlt => "LDLT",
            Method::Lu => "LU",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Solver settings (mapped from `SOLVEUR`).
#[derive(Debug, Clone, Copy)]
pub struct SolverOptions {
    pub method: Method,
    pub ordering: Ordering,
    /// Digits of precision whose loss declares a pivot singular (`NPREC`).
    /// A negative value disables the check (as in Code_Aster).
    pub nprec: i32,
    /// Maximum relative residual `‖b - A x‖ / ‖b‖` accepted (`RESI_RELA`);
    /// negative: not checked.
    pub resi_rela: f64,
    /// Relative tolerance of the symmetry test (Auto).
    pub sym_tol: f64,
    /// Threads of the numeric factorisation and solves (0: every core).
    pub threads: usize,
    /// Largest number of iterative refinement steps after a solve.
    pub refine_max: usize,
    /// Estimate the condition number after each factorisation.
    pub condition: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            method: Method::Auto,
            ordering: Ordering::Auto,
            nprec: 8,
            resi_rela: 1e-6,
            sym_tol: 1e-12,
            threads: 0,
            refine_max: 10,
            condition: true,
        }
    }
}

impl SolverOptions {
    fn par(&self) -> Par {
        let n = if self.threads == 0 {
            std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)
        } else {
            self.threads
        };
        if n <= 1 {
            Par::Seq
        } else {
            Par::rayon(n)
        }
    }

    /// Number of threads a factorisation uses.
    pub fn thread_count(&self) -> usize {
        match self.par() {
            Par::Seq => 1,
            Par::Rayon(n) => n.get(),
        }
    }
}

/// Timings of a solve.
#[derive(Debug, Clone, Copy, Default)]
pub struct Timings {
    /// Ordering + symbolic factorisation (zero when reused).
    pub symbolic: Duration,
    /// Numeric factorisation.
    pub factorization: Duration,
    /// Condition estimate (solves with the factors).
    pub condition: Duration,
    /// Triangular solves, refinement and residual.
    pub solve: Duration,
}

/// Why a matrix is singular.
#[derive(Debug, Clone, PartialEq)]
pub enum SingularKind {
    /// Zero (or negative) diagonal: these dofs carry no stiffness.
    NoStiffness,
    /// Pivots that lost more than `NPREC` digits (or were not positive).
    Pivot,
    /// Structural rank deficiency found by the LU.
    Structural,
    /// The computed solution is not finite or its residual is too large.
    Residual(f64),
}

/// Solver errors.
#[derive(Debug, Clone, PartialEq)]
pub enum SolveError {
    /// The matrix is singular; `dofs` are the (reduced) equations where it
    /// shows, worst first, `pivots` the corresponding relative pivots (NaN if n/a).
    Singular { kind: SingularKind, dofs: Vec<usize>, pivots: Vec<f64> },
    /// Cholesky requested on a non-symmetric matrix.
    NotSymmetric,
    /// Size mismatch or allocation failure.
    Internal(String),
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::Singular { kind, dofs, pivots } => {
                let what = match kind {
                    SingularKind::NoStiffness => "dofs without stiffness".to_string(),
                    SingularKind::Pivot => {
                        let worst = pivots.first().copied().unwrap_or(f64::NAN);
                        if worst.is_finite() && worst > 0.0 {
                            format!(
                                "pivots losing more than NPREC digits, the worst {:.1} digits (relative pivot {worst:.1e})",
                                -worst.log10()
                            )
                        } else {
                            "pivots losing more than NPREC digits, the worst a null pivot".to_string()
                        }
                    }
                    SingularKind::Structural => "structurally singular".to_string(),
                    SingularKind::Residual(r) => format!("relative residual {r:.3e} above RESI_RELA"),
                };
                write!(f, "singular matrix ({what}) at equations {dofs:?}")
            }
            SolveError::NotSymmetric => write!(f, "the matrix is not symmetric: Cholesky is not applicable"),
            SolveError::Internal(s) => write!(f, "solver failure: {s}"),
        }
    }
}

impl std::error::Error for SolveError {}

/// What a factorisation did: for the run log.
#[derive(Debug, Clone, Default)]
pub struct FactorInfo {
    /// Method used (Cholesky, Ldlt or Lu).
    pub method: Option<Method>,
    /// Ordering used (none for LU, which orders its columns itself).
    pub ordering: Option<Ordering>,
    pub threads: usize,
    pub n: usize,
    /// Non-zeros of the factor(s) (0 when unknown).
    pub factor_nnz: usize,
    /// The symbolic analysis was reused from an earlier factorisation.
    pub reused: bool,
    /// Estimated 1-norm condition number of the scaled matrix.
    pub condition: Option<f64>,
    /// The unknown where the worst column of the inverse peaks (from the condition estimate).
    pub sensitive: Option<usize>,
    /// Smallest relative pivot of a symmetric factorisation.
    pub min_pivot: Option<f64>,
    /// The LDLᵀ fell back on LU (its refinement did not converge).
    pub fallback: bool,
    /// Pivots of the LDLᵀ below round-off, replaced by ±δ (the refinement then corrects the solution).
    pub regularized: usize,
    pub timings: Timings,
}

impl FactorInfo {
    /// One line for the run log: method, ordering, threads, fill, condition and the digits it costs.
    pub fn summary(&self) -> String {
        let mut s = format!(
            "{}{}",
            self.method.map(|m| m.name()).unwrap_or("?"),
            if self.fallback { " (LDLT refinement failed: LU)" } else { "" }
        );
        if let Some(o) = self.ordering {
            s += &format!(", {} ordering{}", o.name(), if self.reused { " (analysis reused)" } else { "" });
        }
        s += &format!(", {} thread(s)", self.threads);
        if self.factor_nnz > 0 {
            s += &format!(", factor {:.1} M non-zeros", self.factor_nnz as f64 / 1e6);
        }
        if self.regularized > 0 {
            s += &format!(", {} null pivot(s) regularised", self.regularized);
        }
        if let Some(c) = self.condition {
            s += &format!(", condition estimate {c:.1e} ({:.1} digits lost)", c.max(1.0).log10());
        }
        let t = &self.timings;
        s += &format!(
            "; analysis {:.3} s, factorization {:.3} s, condition {:.3} s, solves {:.3} s",
            t.symbolic.as_secs_f64(),
            t.factorization.as_secs_f64(),
            t.condition.as_secs_f64(),
            t.solve.as_secs_f64()
        );
        s
    }
}

/// Result of [`solve`].
#[derive(Debug, Clone)]
pub struct Solution {
    pub x: Vec<f64>,
    /// Method actually used (Cholesky, Ldlt or Lu).
    pub method: Method,
    pub timings: Timings,
    /// `‖b - A x‖ / ‖b‖` (0 for b = 0).
    pub residual: f64,
    /// Non-zeros of the factor(s).
    pub factor_nnz: usize,
    /// Iterative refinement steps taken.
    pub refinements: usize,
    pub info: FactorInfo,
}

enum Kind {
    Llt { symbolic: Arc<SymbolicCholesky<usize>>, values: Vec<f64> },
    Ldlt { symbolic: Arc<SymbolicCholesky<usize>>, values: Vec<f64> },
    Lu(Box<Lu<usize, f64>>),
}

/// A factorised matrix `S A S = F` (S diagonal scaling), reusable for several right-hand sides.
pub struct Factorization {
    kind: Kind,
    scale: Vec<f64>,
    par: Par,
    pub info: FactorInfo,
}

impl Factorization {
    /// `y ← F⁻¹ y` (scaled system).
    fn solve_scaled(&self, y: &mut [f64], transpose: bool) {
        let n = y.len();
        let rhs = MatMut::from_column_major_slice_mut(y, n, 1);
        match &self.kind {
            Kind::Llt { symbolic, values } => {
                let mut buf = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, self.par));
                LltRef::new(symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    rhs,
                    self.par,
                    MemStack::new(&mut buf),
                );
            }
            Kind::Ldlt { symbolic, values } => {
                let mut buf = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, self.par));
                LdltRef::new(symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    rhs,
                    self.par,
                    MemStack::new(&mut buf),
                );
            }
            Kind::Lu(lu) => {
                if transpose {
                    lu.solve_transpose_in_place_with_conj(Conj::No, rhs);
                } else {
                    lu.solve_in_place(rhs);
                }
            }
        }
    }

    /// Solve `A x = b` with the factors (one solve, no refinement).
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut y: Vec<f64> = b.iter().zip(&self.scale).map(|(v, s)| v * s).collect();
        self.solve_scaled(&mut y, false);
        y.iter().zip(&self.scale).map(|(v, s)| v * s).collect()
    }

    /// Solve `A x = b` and refine against `a` (the matrix that was factorised) until the backward error
    /// (see [`backward_error`]) reaches round-off or stops halving; returns x, the relative residual `‖b − A x‖/‖b‖`
    /// and the refinement steps.
    pub fn solve_refined(
        &self,
        a: SparseColMatRef<'_, usize, f64>,
        b: &[f64],
        max_steps: usize,
    ) -> (Vec<f64>, f64, usize) {
        let (x, _, rel, steps) = self.refine(a, b, max_steps);
        (x, rel, steps)
    }

    /// [`Self::solve_refined`] with the final backward error: (x, backward error, relative residual, steps).
    fn refine(&self, a: SparseColMatRef<'_, usize, f64>, b: &[f64], max_steps: usize) -> (Vec<f64>, f64, f64, usize) {
        let anorm = scaled_inf_norm(a, &self.scale);
        let berr = |r: &[f64], x: &[f64]| backward_error(r, x, b, &self.scale, anorm);
        let mut x = self.solve(b);
        let mut r = residual(a, &x, b);
        let mut w = berr(&r, &x);
        let mut steps = 0;
        while steps < max_steps && w > 2.0 * f64::EPSILON && w.is_finite() {
            let dx = self.solve(&r);
            let xn: Vec<f64> = x.iter().zip(&dx).map(|(p, q)| p + q).collect();
            let rn = residual(a, &xn, b);
            let wn = berr(&rn, &xn);
            steps += 1;
            if wn.is_nan() || wn >= w {
                break;
            }
            let done = wn > 0.5 * w;
            x = xn;
            r = rn;
            w = wn;
            if done {
                break;
            }
        }
        let rel = relative(&r, b);
        (x, w, rel, steps)
    }

    /// Hager–Higham estimate of ‖F⁻¹‖₁ (at most 5 iterations, plus Higham's alternative vector), and the
    /// unknown where the column of F⁻¹ that gives it peaks (the worst conditioned unknown).
    fn inverse_norm1(&self) -> (f64, usize) {
        let n = self.scale.len();
        if n == 0 {
            return (0.0, 0);
        }
        let norm1 = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
        let sign = |v: &[f64]| v.iter().map(|&x| if x >= 0.0 { 1.0 } else { -1.0 }).collect::<Vec<f64>>();
        let argmax = |v: &[f64]| {
            let mut j = 0;
            for (i, x) in v.iter().enumerate() {
                if x.abs() > v[j].abs() {
                    j = i;
                }
            }
            j
        };
        let mut x = vec![1.0 / n as f64; n];
        self.solve_scaled(&mut x, false);
        let mut est = norm1(&x);
        let mut worst = argmax(&x);
        if n > 1 {
            let mut s = sign(&x);
            let mut z = s.clone();
            self.solve_scaled(&mut z, true);
            let mut j = argmax(&z);
            for _ in 1..5 {
                let mut e = vec![0.0; n];
                e[j] = 1.0;
                self.solve_scaled(&mut e, false);
                let old = est;
                est = norm1(&e);
                let sn = sign(&e);
                if est > old {
                    worst = argmax(&e);
                }
                if sn == s || est <= old {
                    est = est.max(old);
                    break;
                }
                s = sn;
                z.clone_from(&s);
                self.solve_scaled(&mut z, true);
                let jl = j;
                j = argmax(&z);
                if z[jl].abs() == z[j].abs() {
                    break;
                }
            }
            let mut alt: Vec<f64> = (0..n)
                .map(|i| {
                    let v = 1.0 + i as f64 / (n - 1) as f64;
                    if i % 2 == 0 {
                        v
                    } else {
                        -v
                    }
                })
                .collect();
            self.solve_scaled(&mut alt, false);
            let alt_est = 2.0 * norm1(&alt) / (3.0 * n as f64);
            if alt_est > est {
                est = alt_est;
                worst = argmax(&alt);
            }
        }
        (est, worst)
    }

    /// Estimate the condition number of the scaled matrix, and the unknown most sensitive to it.
    fn estimate_condition(
        &mut self,
        a: SparseColMatRef<'_, usize, f64>,
        opts: &SolverOptions,
    ) -> Result<(), SolveError> {
        if !opts.condition {
            return Ok(());
        }
        let t = Instant::now();
        let sa = scaled(a, &self.scale);
        let anorm = norm1_of(a.symbolic().col_ptr(), sa.val(), a.ncols());
        let (inv, worst) = self.inverse_norm1();
        let c = anorm * inv;
        self.info.condition = Some(c);
        self.info.timings.condition = t.elapsed();
        self.info.sensitive = Some(worst);
        Ok(())
    }
}

/// Factorise `a` (see the module documentation) with a fresh analysis.
pub fn factorize(a: SparseColMatRef<'_, usize, f64>, opts: &SolverOptions) -> Result<Factorization, SolveError> {
    factorize_with(a, opts, &mut None)
}

/// Factorise `a`, reusing the symbolic analysis in `analysis` when it was made for the same pattern (and
/// storing the new one otherwise).
pub fn factorize_with(
    a: SparseColMatRef<'_, usize, f64>,
    opts: &SolverOptions,
    analysis: &mut Option<Analysis>,
) -> Result<Factorization, SolveError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(SolveError::Internal(format!("matrix is {}×{}", n, a.ncols())));
    }
    let diag = diagonal(a);
    let symmetric = || is_symmetric(a, opts.sym_tol);
    let method = match opts.method {
        Method::Auto if symmetric() => {
            if diag.iter().all(|&d| d > 0.0) {
                Method::Cholesky
            } else {
                Method::Ldlt
            }
        }
        Method::Auto => Method::Lu,
        Method::Cholesky | Method::Ldlt if !symmetric() => return Err(SolveError::NotSymmetric),
        m => m,
    };
    let empty_col = |j: usize| {
        let cp = a.symbolic().col_ptr();
        a.val()[cp[j]..cp[j + 1]].iter().all(|v| *v == 0.0)
    };
    let bad: Vec<usize> = (0..n)
        .filter(|&j| diag[j].is_nan() || if method == Method::Cholesky { diag[j] <= 0.0 } else { empty_col(j) })
        .collect();
    if !bad.is_empty() {
        let pivots = bad.iter().map(|&j| diag[j]).collect();
        return Err(SolveError::Singular { kind: SingularKind::NoStiffness, dofs: bad, pivots });
    }
    let mut f = match method {
        Method::Lu => factorize_lu(a, opts)?,
        _ => factorize_symmetric(a, &diag, method, opts, analysis)?,
    };
    f.estimate_condition(a, opts)?;
    Ok(f)
}

/// Largest backward error an LDLᵀ solve may end with (64 ε): beyond it the pivot order did not
/// suit the matrix, and LU with partial pivoting takes over.
pub const LDLT_BACKWARD_ERROR: f64 = 64.0 * f64::EPSILON;

/// Solve `A x = b` with `f` and refine; an LDLᵀ whose refinement does not bring the backward error to
/// round-off ([`LDLT_BACKWARD_ERROR`]) is replaced by an LU of `a`, with which the solve is made again.
pub fn solve_refined_or_lu(
    f: &mut Factorization,
    a: SparseColMatRef<'_, usize, f64>,
    b: &[f64],
    opts: &SolverOptions,
) -> Result<(Vec<f64>, f64, usize), SolveError> {
    let (x, w, rel, steps) = f.refine(a, b, opts.refine_max);
    if f.info.method != Some(Method::Ldlt) || w <= LDLT_BACKWARD_ERROR {
        return Ok((x, rel, steps));
    }
    let mut lu = factorize_lu(a, opts)?;
    lu.info.fallback = true;
    lu.info.timings.symbolic += f.info.timings.symbolic;
    lu.info.timings.factorization += f.info.timings.factorization;
    lu.estimate_condition(a, opts)?;
    lu.info.timings.condition += f.info.timings.condition;
    *f = lu;
    Ok(f.solve_refined(a, b, opts.refine_max))
}

/// Solve `A x = b` (factorisation + solve + refinement, timed; residual checked against RESI_RELA).
pub fn solve(a: SparseColMatRef<'_, usize, f64>, b: &[f64], opts: &SolverOptions) -> Result<Solution, SolveError> {
    solve_with(a, b, opts, &mut None)
}

/// [`solve`] reusing (and keeping) a symbolic analysis.
pub fn solve_with(
    a: SparseColMatRef<'_, usize, f64>,
    b: &[f64],
    opts: &SolverOptions,
    analysis: &mut Option<Analysis>,
) -> Result<Solution, SolveError> {
    if b.len() != a.nrows() {
        return Err(SolveError::Internal(format!("right-hand side has {} rows, matrix {}", b.len(), a.nrows())));
    }
    let mut fact = factorize_with(a, opts, analysis)?;
    let t = Instant::now();
    let (x, residual, refinements) = solve_refined_or_lu(&mut fact, a, b, opts)?;
    let mut info = fact.info.clone();
    info.timings.solve = t.elapsed();
    check_solution(a, &x, b, residual, opts)?;
    Ok(Solution {
        x,
        method: info.method.unwrap_or(Method::Lu),
        timings: info.timings,
        residual,
        factor_nnz: info.factor_nnz,
        refinements,
        info,
    })
}

/// A non-finite solution, or a relative residual above RESI_RELA, is an error naming the equations with
/// the largest residuals.
pub fn check_solution(
    a: SparseColMatRef<'_, usize, f64>,
    x: &[f64],
    b: &[f64],
    rel: f64,
    opts: &SolverOptions,
) -> Result<(), SolveError> {
    if x.iter().any(|v| !v.is_finite()) || (opts.resi_rela >= 0.0 && (rel.is_nan() || rel > opts.resi_rela)) {
        let r: Vec<f64> = residual(a, x, b).iter().map(|v| v.abs()).collect();
        let mut idx: Vec<usize> = (0..b.len()).collect();
        idx.sort_by(|&i, &j| r[j].total_cmp(&r[i]));
        idx.truncate(6);
        return Err(SolveError::Singular { kind: SingularKind::Residual(rel), dofs: idx, pivots: vec![] });
    }
    Ok(())
}

/// Peak resident memory of this process (VmHWM), in bytes, where the system tells it.
pub fn peak_memory() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::Triplet;

    fn mat(n: usize, t: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
        let t: Vec<_> = t.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    #[test]
    fn spd_and_nonsymmetric() {
        let a = mat(3, &[(0, 0, 4.0), (1, 1, 3.0), (2, 2, 2.0), (0, 1, 1.0), (1, 0, 1.0)]);
        let s = solve(a.as_ref(), &[5.0, 4.0, 2.0], &SolverOptions::default()).unwrap();
        assert_eq!(s.method, Method::Cholesky);
        for (x, e) in s.x.iter().zip([1.0, 1.0, 1.0]) {
            assert!((x - e).abs() < 1e-14);
        }
        assert!(s.info.condition.unwrap() >= 1.0);
        let a = mat(2, &[(0, 0, 2.0), (0, 1, 1.0), (1, 1, 3.0)]);
        let s = solve(a.as_ref(), &[3.0, 3.0], &SolverOptions::default()).unwrap();
        assert_eq!(s.method, Method::Lu);
        assert!((s.x[0] - 1.0).abs() < 1e-14 && (s.x[1] - 1.0).abs() < 1e-14);
    }

    #[test]
    fn singular_spring_chain() {
        // Free chain of springs: one rigid mode.
        let n = 6;
        let mut t = vec![];
        for e in 0..n - 1 {
            t.extend([(e, e, 1.0), (e + 1, e + 1, 1.0), (e, e + 1, -1.0), (e + 1, e, -1.0)]);
        }
        let a = mat(n, &t);
        let err = solve(a.as_ref(), &vec![0.0; n], &SolverOptions::default()).unwrap_err();
        match err {
            SolveError::Singular { kind: SingularKind::Pivot, dofs, .. } => assert_eq!(dofs.len(), 1),
            e => panic!("{e:?}"),
        }
        let z = mat(2, &[(0, 0, 1.0)]);
        let err = solve(z.as_ref(), &[1.0, 0.0], &SolverOptions::default()).unwrap_err();
        assert!(matches!(err, SolveError::Singular { kind: SingularKind::NoStiffness, ref dofs, .. } if dofs == &[1]));
    }

    /// A saddle point [[K, Cᵀ], [C, 0]]: springs with a multiplier tying the two ends. LDLᵀ, with the
    /// multiplier ordered after its neighbours, solves it to round-off; the analysis is reused.
    #[test]
    fn saddle_point_by_ldlt() {
        let n = 5;
        let mut t = vec![];
        for e in 0..n - 1 {
            t.extend([(e, e, 2.0), (e + 1, e + 1, 2.0), (e, e + 1, -1.0), (e + 1, e, -1.0)]);
        }
        // Multiplier n: u0 - u4 = 0.
        t.extend([(n, 0, 1.0), (0, n, 1.0), (n, n - 1, -1.0), (n - 1, n, -1.0)]);
        let a = mat(n + 1, &t);
        let xe: Vec<f64> = vec![0.3, -1.0, 2.0, 0.5, 0.3, 7.0];
        let b = matvec(a.as_ref(), &xe);
        let mut an = None;
        let s = solve_with(a.as_ref(), &b, &SolverOptions::default(), &mut an).unwrap();
        assert_eq!(s.method, Method::Ldlt);
        assert!(!s.info.fallback);
        for (x, e) in s.x.iter().zip(&xe) {
            assert!((x - e).abs() < 1e-13, "{:?}", s.x);
        }
        let s = solve_with(a.as_ref(), &b, &SolverOptions::default(), &mut an).unwrap();
        assert!(s.info.reused);
    }

    /// Iterative refinement brings a badly scaled system back to round-off: an SPD block of order 1e6 beside
    /// a pair of multipliers of order 1e-6 whose only coupling is each other. The LDLᵀ meets a null pivot there,
    /// regularises it by δ, and its first solve is off by ~δ; the refinement against the matrix brings the
    /// error to round-off.
    #[test]
    fn refinement_brings_a_badly_scaled_saddle_point_back_to_round_off() {
        let a = mat(
            5,
            &[
                (0, 0, 4e6),
                (1, 1, 4e6),
                (2, 2, 4e6),
                (0, 1, -1e6),
                (1, 0, -1e6),
                (1, 2, -1e6),
                (2, 1, -1e6),
                (3, 4, 1e-6),
                (4, 3, 1e-6),
            ],
        );
        let xe = [1.0, -2.0, 0.5, 3.0e6, -7.0e6];
        let b = matvec(a.as_ref(), &xe);
        let f = factorize(a.as_ref(), &SolverOptions::default()).unwrap();
        assert_eq!(f.info.method, Some(Method::Ldlt));
        assert_eq!(f.info.regularized, 1);
        let err = |x: &[f64]| x.iter().zip(&xe).map(|(p, q)| (p - q).abs() / q.abs()).fold(0.0, f64::max);
        let x0 = f.solve(&b);
        assert!(err(&x0) > 1e-10, "the first solve is already exact: {:e}", err(&x0));
        let (x, rel, steps) = f.solve_refined(a.as_ref(), &b, 10);
        assert!(steps >= 1 && err(&x) < 1e-15 && rel < 1e-15, "error {:e}, residual {rel:e}", err(&x));
    }
}
