//! Assembly of element matrices and vectors straight into faer's sparse
//! column format, on the reduced (eliminated) dofs of a [`DofMap`].
//!
//! Two passes: [`SparsityPattern::build`] computes the sorted row indices of
//! every column from the element dof lists (O(nnz) memory, no triplets), then
//! [`Assembler`] adds the element matrices in place (duplicates summed) and
//! the load vectors; for an element matrix `Kₑ` on full dofs `u = T û + g`
//! it adds `Tₑᵀ Kₑ Tₑ` to the matrix and `-Tₑᵀ Kₑ gₑ` to the right-hand side.

use super::dofs::DofMap;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// Element dof lists (full dof numbers) in CSR form.
#[derive(Debug, Clone, Default)]
pub struct ElementDofs {
    pub ptr: Vec<usize>,
    pub dofs: Vec<usize>,
}

impl ElementDofs {
    pub fn new() -> ElementDofs {
        ElementDofs { ptr: vec![0], dofs: vec![] }
    }

    pub fn push(&mut self, dofs: &[usize]) {
        if self.ptr.is_empty() {
            self.ptr.push(0);
        }
        self.dofs.extend_from_slice(dofs);
        self.ptr.push(self.dofs.len());
    }

    pub fn len(&self) -> usize {
        self.ptr.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn get(&self, e: usize) -> &[usize] {
        &self.dofs[self.ptr[e]..self.ptr[e + 1]]
    }
}

/// Sparsity pattern of the reduced matrix (CSC, sorted rows per column).
#[derive(Debug, Clone)]
pub struct SparsityPattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
}

impl SparsityPattern {
    /// Pattern of `Σₑ Tₑᵀ Kₑ Tₑ` for full element matrices on `elems`.
    pub fn build(map: &DofMap, elems: &ElementDofs) -> SparsityPattern {
        let n = map.nfree;
        // Reduced dofs of each element.
        let mut rptr = vec![0usize];
        let mut rdofs: Vec<usize> = Vec::with_capacity(elems.dofs.len());
        for e in 0..elems.len() {
            let start = rdofs.len();
            for &d in elems.get(e) {
                rdofs.extend(map.expr(d).0.iter().map(|t| t.0));
            }
            let s = &mut rdofs[start..];
            s.sort_unstable();
            let mut k = 0;
            for i in 0..s.len() {
                if i == 0 || s[i] != s[k - 1] {
                    s[k] = s[i];
                    k += 1;
                }
            }
            rdofs.truncate(start + k);
            rptr.push(rdofs.len());
        }
        // Reduced dof → elements.
        let mut cnt = vec![0usize; n + 1];
        for &d in &rdofs {
            cnt[d + 1] += 1;
        }
        for i in 0..n {
            cnt[i + 1] += cnt[i];
        }
        let mut d2e = vec![0usize; rdofs.len()];
        let mut pos = cnt.clone();
        for e in 0..rptr.len() - 1 {
            for &d in &rdofs[rptr[e]..rptr[e + 1]] {
                d2e[pos[d]] = e;
                pos[d] += 1;
            }
        }
        // Columns: union of the element dof sets, with a marker array.
        let mut mark = vec![usize::MAX; n];
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for j in 0..n {
            let start = row_idx.len();
            for &e in &d2e[cnt[j]..cnt[j + 1]] {
                for &i in &rdofs[rptr[e]..rptr[e + 1]] {
                    if mark[i] != j {
                        mark[i] = j;
                        row_idx.push(i);
                    }
                }
            }
            row_idx[start..].sort_unstable();
            col_ptr.push(row_idx.len());
        }
        SparsityPattern { n, col_ptr, row_idx }
    }

    /// Position of entry `(i, j)` in the value array.
    #[inline]
    pub fn position(&self, i: usize, j: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
        s.binary_search(&i).ok().map(|p| self.col_ptr[j] + p)
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
}

/// Accumulates element contributions into the reduced matrix and
/// right-hand side.
pub struct Assembler<'a> {
    map: &'a DofMap,
    pattern: SparsityPattern,
    values: Vec<f64>,
    rhs: Vec<f64>,
}

impl<'a> Assembler<'a> {
    pub fn new(map: &'a DofMap, pattern: SparsityPattern) -> Assembler<'a> {
        assert_eq!(pattern.n, map.nfree);
        let nnz = pattern.nnz();
        Assembler { map, pattern, values: vec![0.0; nnz], rhs: vec![0.0; map.nfree] }
    }

    /// Add an element matrix `ke` (row-major, `dofs.len()²`) on full dofs.
    /// Entries outside the pattern panic (the pattern must come from the same
    /// element dof lists).
    pub fn add_matrix(&mut self, dofs: &[usize], ke: &[f64]) {
        let nd = dofs.len();
        debug_assert_eq!(ke.len(), nd * nd);
        let map = self.map;
        // Fast path: all dofs free (identity expressions).
        let exprs: Vec<(&[(usize, f64)], f64)> = dofs.iter().map(|&d| map.expr(d)).collect();
        for (b, (tb, gb)) in exprs.iter().enumerate() {
            // Imposed part: rhs -= Tᵀ K g.
            if *gb != 0.0 {
                for (a, (ta, _)) in exprs.iter().enumerate() {
                    let k = ke[a * nd + b] * gb;
                    for &(i, ci) in ta.iter() {
                        self.rhs[i] -= ci * k;
                    }
                }
            }
            for &(j, cj) in tb.iter() {
                let col = &self.pattern.row_idx[self.pattern.col_ptr[j]..self.pattern.col_ptr[j + 1]];
                let base = self.pattern.col_ptr[j];
                for (a, (ta, _)) in exprs.iter().enumerate() {
                    let k = ke[a * nd + b];
                    if k == 0.0 {
                        continue;
                    }
                    for &(i, ci) in ta.iter() {
                        let p = col.binary_search(&i).expect("entry outside the sparsity pattern");
                        self.values[base + p] += ci * cj * k;
                    }
                }
            }
        }
    }

    /// Add an element (or nodal) force vector on full dofs.
    pub fn add_vector(&mut self, dofs: &[usize], fe: &[f64]) {
        for (&d, &f) in dofs.iter().zip(fe) {
            for &(i, c) in self.map.expr(d).0 {
                self.rhs[i] += c * f;
            }
        }
    }

    /// Current right-hand side.
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// The assembled reduced matrix and right-hand side.
    pub fn finish(self) -> (SparseColMat<usize, f64>, Vec<f64>) {
        let n = self.pattern.n;
        // SAFETY-free construction: the pattern has sorted, in-bounds rows.
        let sym = SymbolicSparseColMat::new_checked(n, n, self.pattern.col_ptr, None, self.pattern.row_idx);
        (SparseColMat::new(sym, self.values), self.rhs)
    }
}

/// Full (non-reduced) assembled vector from element vectors.
pub fn assemble_full_vector(nfull: usize, elems: &ElementDofs, vectors: &[Vec<f64>]) -> Vec<f64> {
    let mut v = vec![0.0; nfull];
    for (e, fe) in vectors.iter().enumerate() {
        for (&d, &f) in elems.get(e).iter().zip(fe) {
            v[d] += f;
        }
    }
    v
}

/// `y = K x` for element matrices on full dofs (unreduced product, e.g. for
/// reactions `R = K u - F`).
pub fn element_matvec(nfull: usize, elems: &ElementDofs, matrices: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; nfull];
    for (e, ke) in matrices.iter().enumerate() {
        let dofs = elems.get(e);
        let nd = dofs.len();
        for (a, &da) in dofs.iter().enumerate() {
            y[da] += (0..nd).map(|b| ke[a * nd + b] * x[dofs[b]]).sum::<f64>();
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::dofs::Constraints;

    #[test]
    fn springs_in_series_with_elimination() {
        // 3 dofs, two unit springs 0-1 and 1-2; u0 = 0 imposed, u2 = 1.
        let mut c = Constraints::new();
        c.impose(0, 0.0);
        c.impose(2, 1.0);
        let map = DofMap::build(3, &c).unwrap();
        let mut el = ElementDofs::new();
        el.push(&[0, 1]);
        el.push(&[1, 2]);
        let pat = SparsityPattern::build(&map, &el);
        let mut asm = Assembler::new(&map, pat);
        let k = [1.0, -1.0, -1.0, 1.0];
        asm.add_matrix(el.get(0), &k);
        asm.add_matrix(el.get(1), &k);
        let (a, b) = asm.finish();
        assert_eq!(a.nrows(), 1);
        assert_eq!(a.val(), &[2.0]);
        assert_eq!(b, vec![1.0]);
    }
}
