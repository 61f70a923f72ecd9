//! Scaling of a matrix before its factorization: Ruiz's symmetric equilibration and `S A S`.

use super::*;

/// Ruiz's equilibration: `S` such that every row and column of `S A S` that has an entry has its largest
/// one in [1/2, 1] (10 sweeps at most), each factor a power of 2 so that the scaling adds no round-off.
/// Unlike one sweep of max-scaling it also brings rows without a diagonal (multipliers) to unit size, so
/// that their pivots are measured against 1.
pub(super) fn equilibration(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let n = a.ncols();
    let mut s = vec![1.0f64; n];
    let mut m = vec![0.0f64; n];
    for _ in 0..10 {
        m.iter_mut().for_each(|x| *x = 0.0);
        for j in 0..n {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                let x = (v[p] * s[i] * s[j]).abs();
                m[j] = m[j].max(x);
                m[i] = m[i].max(x);
            }
        }
        let mut done = true;
        for (si, &mi) in s.iter_mut().zip(&m) {
            if mi > 0.0 && !(0.5..=1.0).contains(&mi) {
                done = false;
                // The nearest power of 2 to 1/√m.
                *si *= (-0.5 * mi.log2()).round().exp2();
            }
        }
        if done {
            break;
        }
    }
    s
}

/// `S A S` on the pattern of `a`.
pub(super) fn scaled(a: SparseColMatRef<'_, usize, f64>, scale: &[f64]) -> SparseColMat<usize, f64> {
    let n = a.ncols();
    let (cp, ri, v) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut sv = Vec::with_capacity(v.len());
    for j in 0..n {
        for p in cp[j]..cp[j + 1] {
            sv.push(v[p] * scale[ri[p]] * scale[j]);
        }
    }
    let sym = SymbolicSparseColMat::new_checked(
        a.nrows(),
        n,
        cp.to_vec(),
        a.symbolic().col_nnz().map(|c| c.to_vec()),
        ri.to_vec(),
    );
    SparseColMat::new(sym, sv)
}
