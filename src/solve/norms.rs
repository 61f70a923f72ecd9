//! Products, residuals and norms of sparse matrices and vectors: the symmetry test, `A x`, `b − A x`,
//! the normwise backward error and the norms the solvers report.

use super::*;

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

pub(super) fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
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

/// `r = b − A x`, each entry accumulated with its rounding error (Neumaier's compensated sum of
/// exact products from `mul_add`), so that the residual of a solution accurate to round-off is itself
/// accurate: iterative refinement then improves the solution, not only the residual.
pub fn residual(a: SparseColMatRef<'_, usize, f64>, x: &[f64], b: &[f64]) -> Vec<f64> {
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut hi = b.to_vec();
    let mut lo = vec![0.0; b.len()];
    for j in 0..a.ncols() {
        let xj = x[j];
        if xj != 0.0 {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                let prod = -v[p] * xj;
                let err = (-v[p]).mul_add(xj, -prod);
                let s = hi[i] + prod;
                let c = if hi[i].abs() >= prod.abs() { (hi[i] - s) + prod } else { (prod - s) + hi[i] };
                hi[i] = s;
                lo[i] += c + err;
            }
        }
    }
    hi.iter().zip(&lo).map(|(h, l)| h + l).collect()
}

/// The normwise backward error of x in the metric of the scaling `s` (that of the factorization, under
/// which every row and column has entries of order 1): `‖S r‖∞ / (‖S A S‖∞ ‖S⁻¹ x‖∞ + ‖S b‖∞)`, with
/// `anorm = ‖S A S‖∞`. Unlike `‖r‖/‖b‖` it gives the small equations (a multiplier's, an interface's) their
/// weight; unlike a componentwise error it does not count rows whose unknowns all vanish to round-off.
pub(super) fn backward_error(r: &[f64], x: &[f64], b: &[f64], s: &[f64], anorm: f64) -> f64 {
    let inf = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0f64, |m, v| m.max(v.abs()));
    let nr = inf(&mut r.iter().zip(s).map(|(r, s)| r * s));
    let nx = inf(&mut x.iter().zip(s).map(|(x, s)| x / s));
    let nb = inf(&mut b.iter().zip(s).map(|(b, s)| b * s));
    let d = anorm * nx + nb;
    if d > 0.0 {
        nr / d
    } else if nr == 0.0 {
        0.0
    } else {
        f64::INFINITY
    }
}

/// `‖S A S‖∞`.
pub(super) fn scaled_inf_norm(a: SparseColMatRef<'_, usize, f64>, s: &[f64]) -> f64 {
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut row = vec![0.0f64; a.nrows()];
    for j in 0..a.ncols() {
        for p in cp[j]..cp[j + 1] {
            row[ri[p]] += (v[p] * s[ri[p]] * s[j]).abs();
        }
    }
    row.into_iter().fold(0.0, f64::max)
}

pub(super) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub(super) fn relative(r: &[f64], b: &[f64]) -> f64 {
    let nb = norm(b);
    let nr = norm(r);
    if nb == 0.0 {
        if nr == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        nr / nb
    }
}

pub(super) fn norm1_of(cp: &[usize], v: &[f64], n: usize) -> f64 {
    (0..n).map(|j| v[cp[j]..cp[j + 1]].iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max)
}
