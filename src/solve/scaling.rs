//! Symmetric diagonal scaling of a sparse matrix, for systems that mix very different magnitudes (a
//! stiffness of order E·h beside interface couplings of order 1): the factorization of the scaled matrix
//! keeps the accuracy of the solution.

use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// `S K S` with `S = diag(1/√max_j |K_ij|)` over rows and columns, and S (1 for an empty row).
/// The solution of K x = b is `x = S y` with `(S K S) y = S b`.
pub fn equilibrate(k: &SparseColMat<usize, f64>) -> (SparseColMat<usize, f64>, Vec<f64>) {
    let n = k.nrows();
    let colp = k.symbolic().col_ptr().to_vec();
    let rows = k.symbolic().row_idx().to_vec();
    let mut vals = k.val().to_vec();
    let mut s = vec![0.0f64; n];
    for j in 0..n {
        for p in colp[j]..colp[j + 1] {
            let v = vals[p].abs();
            s[j] = s[j].max(v);
            s[rows[p]] = s[rows[p]].max(v);
        }
    }
    for v in s.iter_mut() {
        *v = if *v > 0.0 { 1.0 / v.sqrt() } else { 1.0 };
    }
    for j in 0..n {
        for p in colp[j]..colp[j + 1] {
            vals[p] *= s[rows[p]] * s[j];
        }
    }
    let sym = SymbolicSparseColMat::new_checked(n, n, colp, None, rows);
    (SparseColMat::new(sym, vals), s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::Triplet;

    #[test]
    fn equilibrated_matrix_has_unit_largest_entries() {
        // [[1e8, 2e3], [2e3, 1]]: S = diag(1e-4, 1/sqrt(2e3)).
        let t = [Triplet::new(0, 0, 1e8), Triplet::new(1, 0, 2e3), Triplet::new(0, 1, 2e3), Triplet::new(1, 1, 1.0)];
        let k = SparseColMat::<usize, f64>::try_new_from_triplets(2, 2, &t).unwrap();
        let (ks, s) = equilibrate(&k);
        assert!((s[0] - 1e-4).abs() < 1e-18);
        assert!((s[1] - 1.0 / 2e3f64.sqrt()).abs() < 1e-15);
        let v = ks.val();
        assert!((v[0] - 1.0).abs() < 1e-12, "{v:?}");
        assert!(v.iter().all(|x| x.abs() <= 1.0 + 1e-12), "{v:?}");
    }
}
