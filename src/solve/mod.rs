//! Direct sparse solvers over faer.
//!
//! * Symmetric matrices: supernodal/simplicial LLᵀ (faer, AMD ordering) on
//!   the Jacobi-scaled matrix `S A S` (`S = diag(A)^-1/2`, unit diagonal).
//!   A pivot of the scaled matrix below `10^-NPREC` means that more than
//!   `NPREC` significant digits were lost: the matrix is declared singular at
//!   that dof, as Code_Aster does (`NPREC`, default 8). Such pivots are
//!   regularised during the factorisation, so every singular dof is found in
//!   one pass (e.g. the 3 / 6 rigid-body modes of a free structure).
//! * Non-symmetric matrices: sparse LU with partial pivoting; singularity is
//!   detected structurally (faer) or by a non-finite solution / a residual
//!   above `resi_rela`.
//!
//! Symbolic analysis, numeric factorisation and solve are timed separately.

pub mod scaling;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};
use std::fmt;
use std::time::{Duration, Instant};

/// Factorisation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// LLᵀ when the matrix is symmetric, LU otherwise.
    Auto,
    Cholesky,
    Lu,
}

/// Solver settings (mapped from `SOLVEUR`).
#[derive(Debug, Clone, Copy)]
pub struct SolverOptions {
    pub method: Method,
    /// Digits of precision whose loss declares a pivot singular (`NPREC`).
    /// A negative value disables the check (as in Code_Aster).
    pub nprec: i32,
    /// Maximum relative residual `‖b - A x‖ / ‖b‖` accepted (`RESI_RELA`);
    /// negative: not checked.
    pub resi_rela: f64,
    /// Relative tolerance of the symmetry test (Auto).
    pub sym_tol: f64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions { method: Method::Auto, nprec: 8, resi_rela: 1e-6, sym_tol: 1e-12 }
    }
}

/// Timings of a solve.
#[derive(Debug, Clone, Copy, Default)]
pub struct Timings {
    /// Ordering + symbolic factorisation.
    pub symbolic: Duration,
    /// Numeric factorisation.
    pub factorization: Duration,
    /// Triangular solves (+ residual).
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
    /// shows, `pivots` the corresponding pivot values (scaled; NaN if n/a).
    Singular { kind: SingularKind, dofs: Vec<usize>, pivots: Vec<f64> },
    /// Cholesky requested on a non-symmetric matrix.
    NotSymmetric,
    /// Size mismatch or allocation failure.
    Internal(String),
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::Singular { kind, dofs, .. } => {
                let what = match kind {
                    SingularKind::NoStiffness => "dofs without stiffness".to_string(),
                    SingularKind::Pivot => "pivots losing too many digits".to_string(),
                    SingularKind::Structural => "structurally singular".to_string(),
                    SingularKind::Residual(r) => format!("solution residual {r:e}"),
                };
                write!(f, "singular matrix ({what}) at equations {dofs:?}")
            }
            SolveError::NotSymmetric => write!(f, "the matrix is not symmetric: Cholesky is not applicable"),
            SolveError::Internal(s) => write!(f, "solver failure: {s}"),
        }
    }
}

impl std::error::Error for SolveError {}

/// Result of [`solve`].
#[derive(Debug, Clone)]
pub struct Solution {
    pub x: Vec<f64>,
    /// Method actually used (Cholesky or Lu).
    pub method: Method,
    pub timings: Timings,
    /// `‖b - A x‖ / ‖b‖` (0 for b = 0).
    pub residual: f64,
    /// Non-zeros of the factor(s).
    pub factor_nnz: usize,
}

/// True when `a` is numerically symmetric within `tol · max|a|`.
pub fn is_symmetric(a: SparseColMatRef<'_, usize, f64>, tol: f64) -> bool {
    if a.nrows() != a.ncols() {
        return false;
    }
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let amax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let get = |i: usize, j: usize| -> f64 {
        let s = &ri[cp[j]..cp[j + 1]];
        match s.binary_search(&i) {
            Ok(p) => v[cp[j] + p],
            Err(_) => s.iter().position(|&r| r == i).map(|p| v[cp[j] + p]).unwrap_or(0.0),
        }
    };
    for j in 0..a.ncols() {
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            if i != j && (v[p] - get(j, i)).abs() > tol * amax {
                return false;
            }
        }
    }
    true
}

fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut d = vec![0.0; a.ncols()];
    for j in 0..a.ncols() {
        for p in cp[j]..cp[j + 1] {
            if ri[p] == j {
                d[j] += v[p];
            }
        }
    }
    d
}

/// `y = A x`.
pub fn matvec(a: SparseColMatRef<'_, usize, f64>, x: &[f64]) -> Vec<f64> {
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut y = vec![0.0; a.nrows()];
    for j in 0..a.ncols() {
        let xj = x[j];
        if xj != 0.0 {
            for p in cp[j]..cp[j + 1] {
                y[ri[p]] += v[p] * xj;
            }
        }
    }
    y
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn relative_residual(a: SparseColMatRef<'_, usize, f64>, x: &[f64], b: &[f64]) -> f64 {
    let ax = matvec(a, x);
    let r: Vec<f64> = ax.iter().zip(b).map(|(p, q)| q - p).collect();
    let nb = norm(b);
    if nb == 0.0 {
        if norm(&r) == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        norm(&r) / nb
    }
}

/// Value given to regularised pivots (recognised afterwards by their exact
/// square root); any legitimate pivot equal to it bit for bit is harmless
/// except for a spurious report.
const SENTINEL_PIVOT: f64 = 0.618_033_988_749_894_8;

/// A factorised matrix, reusable for several right-hand sides.
pub enum Factorization {
    Cholesky { symbolic: Box<SymbolicCholesky<usize>>, values: Vec<f64>, scale: Vec<f64> },
    Lu(Box<Lu<usize, f64>>),
}

impl Factorization {
    /// Solve `A x = b` with the factors.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        match self {
            Factorization::Cholesky { symbolic, values, scale } => {
                let mut y: Vec<f64> = b.iter().zip(scale).map(|(v, s)| v * s).collect();
                let n = y.len();
                let par = Par::Seq;
                let llt = LltRef::new(symbolic, values);
                let req = symbolic.solve_in_place_scratch::<f64>(1, par);
                let mut buf = MemBuffer::new(req);
                llt.solve_in_place_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(&mut y, n, 1),
                    par,
                    MemStack::new(&mut buf),
                );
                y.iter().zip(scale).map(|(v, s)| v * s).collect()
            }
            Factorization::Lu(lu) => {
                let mut y = b.to_vec();
                let n = y.len();
                lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut y, n, 1));
                y
            }
        }
    }
}

/// Factorise `a` (see the module documentation); returns the factors, the
/// method used, timings of the symbolic and numeric phases, and the factor
/// non-zeros.
pub fn factorize(
    a: SparseColMatRef<'_, usize, f64>,
    opts: &SolverOptions,
) -> Result<(Factorization, Method, Timings, usize), SolveError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(SolveError::Internal(format!("matrix is {}×{}", n, a.ncols())));
    }
    let method = match opts.method {
        Method::Auto => {
            if is_symmetric(a, opts.sym_tol) {
                Method::Cholesky
            } else {
                Method::Lu
            }
        }
        Method::Cholesky => {
            if !is_symmetric(a, opts.sym_tol) {
                return Err(SolveError::NotSymmetric);
            }
            Method::Cholesky
        }
        Method::Lu => Method::Lu,
    };
    let mut timings = Timings::default();
    // Dofs without stiffness (zero / negative diagonal) for both methods.
    let diag = diagonal(a);
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
    match method {
        Method::Cholesky => {
            let t0 = Instant::now();
            let scale: Vec<f64> = diag.iter().map(|d| 1.0 / d.sqrt()).collect();
            let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
            let mut sv = Vec::with_capacity(v.len());
            for j in 0..n {
                for p in cp[j]..cp[j + 1] {
                    sv.push(v[p] * scale[ri[p]] * scale[j]);
                }
            }
            let sym = SymbolicSparseColMat::new_checked(
                n,
                n,
                cp.to_vec(),
                a.symbolic().col_nnz().map(|c| c.to_vec()),
                ri.to_vec(),
            );
            let scaled = SparseColMat::new(sym, sv);
            let symbolic =
                factorize_symbolic_cholesky(scaled.symbolic(), Side::Lower, SymmetricOrdering::Amd, Default::default())
                    .map_err(|e| SolveError::Internal(format!("{e:?}")))?;
            timings.symbolic = t0.elapsed();
            let t1 = Instant::now();
            let par = Par::Seq;
            let mut values = vec![0.0f64; symbolic.len_val()];
            let eps = if opts.nprec >= 0 { 10f64.powi(-opts.nprec) } else { 0.0 };
            let reg = LltRegularization {
                dynamic_regularization_delta: if opts.nprec >= 0 { SENTINEL_PIVOT } else { 0.0 },
                dynamic_regularization_epsilon: eps,
            };
            let mut buf = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
            let res = symbolic.factorize_numeric_llt(
                &mut values,
                scaled.as_ref(),
                Side::Lower,
                reg,
                par,
                MemStack::new(&mut buf),
                Default::default(),
            );
            timings.factorization = t1.elapsed();
            let perm_fwd: Vec<usize> = match symbolic.perm() {
                Some(p) => p.arrays().0.to_vec(),
                None => (0..n).collect(),
            };
            if let Err(e) = res {
                let k = match e {
                    faer::linalg::solvers::LltError::NonPositivePivot { index } => {
                        index.saturating_sub(1).min(n.saturating_sub(1))
                    }
                };
                return Err(SolveError::Singular {
                    kind: SingularKind::Pivot,
                    dofs: vec![perm_fwd[k]],
                    pivots: vec![f64::NAN],
                });
            }
            let sq = SENTINEL_PIVOT.sqrt();
            let ldiag = factor_diagonal(&symbolic, &values);
            let mut dofs = vec![];
            let mut pivots = vec![];
            if opts.nprec >= 0 {
                for (k, &l) in ldiag.iter().enumerate() {
                    if l == sq || l * l < eps || l.is_nan() {
                        dofs.push(perm_fwd[k]);
                        pivots.push(if l == sq { 0.0 } else { l * l });
                    }
                }
            }
            if !dofs.is_empty() {
                return Err(SolveError::Singular { kind: SingularKind::Pivot, dofs, pivots });
            }
            let nnz = symbolic.len_val();
            Ok((Factorization::Cholesky { symbolic: Box::new(symbolic), values, scale }, method, timings, nnz))
        }
        _ => {
            let t0 = Instant::now();
            let symbolic = SymbolicLu::try_new(a.symbolic()).map_err(|e| SolveError::Internal(format!("{e:?}")))?;
            timings.symbolic = t0.elapsed();
            let t1 = Instant::now();
            let lu = Lu::try_new_with_symbolic(symbolic, a).map_err(|e| match e {
                faer::sparse::linalg::LuError::SymbolicSingular { index } => SolveError::Singular {
                    kind: SingularKind::Structural,
                    dofs: vec![index.min(n.saturating_sub(1))],
                    pivots: vec![f64::NAN],
                },
                other => SolveError::Internal(format!("{other:?}")),
            })?;
            timings.factorization = t1.elapsed();
            Ok((Factorization::Lu(Box::new(lu)), method, timings, 0))
        }
    }
}

/// Diagonal of the Cholesky factor, in the permuted order.
fn factor_diagonal(symbolic: &SymbolicCholesky<usize>, values: &[f64]) -> Vec<f64> {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            (0..s.nrows()).map(|k| values[cp[k]]).collect()
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let l = SupernodalLltRef::new(s, values);
            let mut d = vec![0.0; s.nrows()];
            for sn in 0..s.n_supernodes() {
                let node = l.supernode(sn);
                let start = node.start();
                let m = node.val();
                for j in 0..m.ncols() {
                    d[start + j] = m[(j, j)];
                }
            }
            d
        }
    }
}

/// Solve `A x = b` (factorisation + solve, timed; residual checked).
pub fn solve(a: SparseColMatRef<'_, usize, f64>, b: &[f64], opts: &SolverOptions) -> Result<Solution, SolveError> {
    if b.len() != a.nrows() {
        return Err(SolveError::Internal(format!("right-hand side has {} rows, matrix {}", b.len(), a.nrows())));
    }
    let (fact, method, mut timings, factor_nnz) = factorize(a, opts)?;
    let t = Instant::now();
    let x = fact.solve(b);
    let residual = relative_residual(a, &x, b);
    timings.solve = t.elapsed();
    if x.iter().any(|v| !v.is_finite()) || (opts.resi_rela >= 0.0 && (residual.is_nan() || residual > opts.resi_rela)) {
        // Report the equations with the largest residual.
        let ax = matvec(a, &x);
        let mut idx: Vec<usize> = (0..b.len()).collect();
        let r: Vec<f64> = ax.iter().zip(b).map(|(p, q)| (q - p).abs()).collect();
        idx.sort_by(|&i, &j| r[j].total_cmp(&r[i]));
        idx.truncate(6);
        return Err(SolveError::Singular { kind: SingularKind::Residual(residual), dofs: idx, pivots: vec![] });
    }
    Ok(Solution { x, method, timings, residual, factor_nnz })
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
}
