//! Fill-reducing orderings of a symmetric sparsity pattern: approximate minimum degree (faer's AMD) for small
//! and 2D-like systems, nested dissection (METIS `METIS_NodeND`) for large and 3D ones, and the deferral of
//! zero-diagonal rows (Lagrange multipliers) after a neighbour with a pivot, so that an LDLᵀ without pivoting
//! never meets a structurally zero pivot.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

/// Which fill-reducing ordering to compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordering {
    /// Nested dissection from `ND_THRESHOLD` unknowns on, AMD below.
    Auto,
    /// Approximate minimum degree.
    Amd,
    /// Nested dissection (METIS).
    NestedDissection,
    /// The given order (no renumbering).
    Natural,
}

/// Size from which `Auto` chooses nested dissection: below it AMD is as good and cheaper to compute.
pub const ND_THRESHOLD: usize = 50_000;

impl Ordering {
    /// The ordering actually used for a system of `n` unknowns.
    pub fn resolve(self, n: usize) -> Ordering {
        match self {
            Ordering::Auto if n >= ND_THRESHOLD => Ordering::NestedDissection,
            Ordering::Auto => Ordering::Amd,
            o => o,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Ordering::Auto => "automatic",
            Ordering::Amd => "AMD",
            Ordering::NestedDissection => "nested dissection (METIS)",
            Ordering::Natural => "natural order",
        }
    }
}

/// The adjacency of a square pattern without its diagonal, made symmetric (either triangle may be given).
pub fn adjacency(a: SymbolicSparseColMatRef<'_, usize>) -> (Vec<usize>, Vec<usize>) {
    let n = a.ncols();
    let (cp, ri) = (a.col_ptr(), a.row_idx());
    let mut deg = vec![0usize; n + 1];
    for j in 0..n {
        for &i in &ri[cp[j]..cp[j + 1]] {
            if i != j {
                deg[i + 1] += 1;
                deg[j + 1] += 1;
            }
        }
    }
    for i in 0..n {
        deg[i + 1] += deg[i];
    }
    let mut pos = deg.clone();
    let mut adj = vec![0usize; deg[n]];
    for j in 0..n {
        for &i in &ri[cp[j]..cp[j + 1]] {
            if i != j {
                adj[pos[i]] = j;
                pos[i] += 1;
                adj[pos[j]] = i;
                pos[j] += 1;
            }
        }
    }
    // Sort and remove duplicates (a full symmetric pattern lists every edge twice).
    let mut ptr = vec![0usize; n + 1];
    let mut out = Vec::with_capacity(adj.len() / 2 + n);
    for v in 0..n {
        let s = &mut adj[deg[v]..deg[v + 1]];
        s.sort_unstable();
        let mut last = usize::MAX;
        for &w in s.iter() {
            if w != last {
                out.push(w);
                last = w;
            }
        }
        ptr[v + 1] = out.len();
    }
    (ptr, out)
}

/// A fill-reducing permutation `perm` (new position → old index) of the symmetric pattern `a`.
pub fn order(a: SymbolicSparseColMatRef<'_, usize>, ordering: Ordering) -> Result<Vec<usize>, String> {
    let (ptr, adj) = adjacency(a);
    order_graph(&ptr, &adj, ordering)
}

/// [`order`] on the adjacency (from [`adjacency`]) of the pattern.
pub fn order_graph(ptr: &[usize], adj: &[usize], ordering: Ordering) -> Result<Vec<usize>, String> {
    let n = ptr.len() - 1;
    match ordering.resolve(n) {
        Ordering::Natural => Ok((0..n).collect()),
        Ordering::Amd | Ordering::Auto => amd_order(ptr.to_vec(), adj.to_vec()),
        Ordering::NestedDissection => nested_dissection(ptr, adj),
    }
}

fn amd_order(ptr: Vec<usize>, adj: Vec<usize>) -> Result<Vec<usize>, String> {
    let n = ptr.len() - 1;
    // AMD reads the upper triangle of a pattern whose rows may be in any order.
    let sym = faer::sparse::SymbolicSparseColMat::new_checked(n, n, ptr, None, adj);
    let mut perm = vec![0usize; n];
    let mut perm_inv = vec![0usize; n];
    let mut buf = MemBuffer::new(amd::order_maybe_unsorted_scratch::<usize>(n, sym.compute_nnz()));
    amd::order_maybe_unsorted(&mut perm, &mut perm_inv, sym.as_ref(), Default::default(), MemStack::new(&mut buf))
        .map_err(|e| format!("AMD ordering: {e:?}"))?;
    Ok(perm)
}

/// METIS nested dissection on the graph whose consecutive unknowns with identical adjacency (the components
/// of a node) are merged into one weighted vertex.
fn nested_dissection(ptr: &[usize], adj: &[usize]) -> Result<Vec<usize>, String> {
    let n = ptr.len() - 1;
    if n <= 1 {
        return Ok((0..n).collect());
    }
    // Supervariables: v joins v-1's group when their closed neighbourhoods coincide, that is when each is
    // the other's neighbour and their other neighbours are the same (sorted lists, no allocation).
    let closed_eq = |u: usize, v: usize| -> bool {
        let (su, sv) = (&adj[ptr[u]..ptr[u + 1]], &adj[ptr[v]..ptr[v + 1]]);
        su.len() == sv.len()
            && su.binary_search(&v).is_ok()
            && su.iter().filter(|&&w| w != v).eq(sv.iter().filter(|&&w| w != u))
    };
    let mut group = vec![0usize; n];
    let mut starts = vec![0usize];
    for v in 1..n {
        if closed_eq(v - 1, v) {
            group[v] = group[v - 1];
        } else {
            group[v] = starts.len();
            starts.push(v);
        }
    }
    let ng = starts.len();
    starts.push(n);
    let to_i32 = |x: usize| i32::try_from(x).map_err(|_| "graph too large for METIS (32-bit indices)".to_string());
    let mut xadj: Vec<i32> = Vec::with_capacity(ng + 1);
    let mut adjncy: Vec<i32> = Vec::new();
    let mut vwgt: Vec<i32> = Vec::with_capacity(ng);
    xadj.push(0);
    let mut mark = vec![usize::MAX; ng];
    for g in 0..ng {
        let v = starts[g];
        mark[g] = g;
        for &w in &adj[ptr[v]..ptr[v + 1]] {
            let h = group[w];
            if mark[h] != g {
                mark[h] = g;
                adjncy.push(to_i32(h)?);
            }
        }
        xadj.push(to_i32(adjncy.len())?);
        vwgt.push(to_i32(starts[g + 1] - starts[g])?);
    }
    let mut nv = to_i32(ng)?;
    let mut perm = vec![0i32; ng];
    let mut iperm = vec![0i32; ng];
    let mut options = [-1i32; metis_sys::METIS_NOPTIONS as usize];
    // SAFETY: METIS reads nv + 1 offsets, xadj[nv] neighbours and nv weights, and writes nv entries into
    // perm and iperm; every array has that length, and the default options array has METIS_NOPTIONS entries.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_NodeND(
            &mut nv,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            vwgt.as_mut_ptr(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(format!("METIS_NodeND failed (status {status})"));
    }
    // METIS: row i of the permuted matrix is row perm[i] of the original (perm is new → old).
    let mut out = Vec::with_capacity(n);
    for &g in &perm {
        let g = g as usize;
        out.extend(starts[g]..starts[g + 1]);
    }
    Ok(out)
}

/// Defers every unknown without a positive diagonal (`minus[i]`: a multiplier, zero or negative diagonal)
/// to just after the last of its neighbours with a positive diagonal in `perm`. In an LDLᵀ without
/// pivoting its pivot is then its diagonal minus `b P⁻¹ bᵀ` (b its couplings, P the positive block
/// around it), negative and nonzero when the multiplier acts on something: a saddle point is factorised
/// as a quasi-definite matrix would be. Multipliers are few, so the fill hardly changes.
pub fn defer_multipliers(ptr: &[usize], adj: &[usize], minus: &[bool], perm: Vec<usize>) -> Vec<usize> {
    let n = perm.len();
    if !minus.iter().any(|&z| z) {
        return perm;
    }
    let mut pos = vec![0usize; n];
    for (k, &v) in perm.iter().enumerate() {
        pos[v] = k;
    }
    // Key of each unknown: (position, 0), or (position of its last positive neighbour, 1) when deferred;
    // a multiplier with no positive neighbour (an unknown whose only couplings are multipliers) comes
    // after the last of its neighbours, (their latest key's position, 2).
    let mut key: Vec<(usize, u8)> = (0..n).map(|v| (pos[v], 0)).collect();
    for &v in &perm {
        if minus[v] {
            if let Some(f) = adj[ptr[v]..ptr[v + 1]].iter().filter(|&&w| !minus[w]).map(|&w| pos[w]).max() {
                if f > pos[v] {
                    key[v] = (f, 1);
                }
            }
        }
    }
    for &v in &perm {
        let nb = &adj[ptr[v]..ptr[v + 1]];
        if minus[v] && !nb.is_empty() && nb.iter().all(|&w| minus[w]) {
            let f = nb.iter().map(|&w| key[w].0).max().unwrap_or(0);
            if f >= key[v].0 {
                key[v] = (f, 2);
            }
        }
    }
    let mut order: Vec<(usize, u8, usize, usize)> = perm.iter().map(|&v| (key[v].0, key[v].1, pos[v], v)).collect();
    order.sort_unstable();
    order.into_iter().map(|t| t.3).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::SymbolicSparseColMat;

    fn grid(m: usize) -> SymbolicSparseColMat<usize> {
        // 5-point Laplacian pattern of an m×m grid, full symmetric storage.
        let n = m * m;
        let mut cp = vec![0];
        let mut ri = vec![];
        for j in 0..n {
            let (x, y) = (j % m, j / m);
            let mut c = vec![j];
            if x > 0 {
                c.push(j - 1);
            }
            if x + 1 < m {
                c.push(j + 1);
            }
            if y > 0 {
                c.push(j - m);
            }
            if y + 1 < m {
                c.push(j + m);
            }
            c.sort_unstable();
            ri.extend(c);
            cp.push(ri.len());
        }
        SymbolicSparseColMat::new_checked(n, n, cp, None, ri)
    }

    fn is_perm(p: &[usize]) -> bool {
        let mut s = p.to_vec();
        s.sort_unstable();
        s.iter().enumerate().all(|(i, &v)| i == v)
    }

    #[test]
    fn orderings_are_permutations() {
        let g = grid(30);
        for o in [Ordering::Amd, Ordering::NestedDissection, Ordering::Natural, Ordering::Auto] {
            let p = order(g.as_ref(), o).unwrap();
            assert_eq!(p.len(), 900);
            assert!(is_perm(&p), "{o:?}");
        }
    }

    #[test]
    fn multipliers_follow_their_neighbours() {
        let g = grid(6);
        let mut minus = vec![false; 36];
        minus[0] = true;
        minus[14] = true;
        let (ptr, adj) = adjacency(g.as_ref());
        let p = defer_multipliers(&ptr, &adj, &minus, (0..36).collect());
        assert!(is_perm(&p));
        let pos = |v: usize| p.iter().position(|&x| x == v).unwrap();
        // 0's neighbours are 1 and 6: it comes right after 6.
        assert_eq!(pos(0), pos(6) + 1);
        assert!([8, 13, 15, 20].iter().all(|&w| pos(14) > pos(w)));
    }
}
