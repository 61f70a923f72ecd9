//! The symmetric factorizations, supernodal LLᵀ and LDLᵀ over faer, with the symbolic analysis kept
//! for reuse, the regularised pivots that name singular unknowns, and NPREC's check.

use super::*;

/// LDLᵀ pivots of at most this size (of the equilibrated matrix) are replaced by ±[`LDLT_DELTA`].
pub(super) const LDLT_NULL_PIVOT: f64 = 1e-13;
pub(super) const LDLT_DELTA: f64 = 1e-8;

/// Value given to regularised pivots (recognised afterwards); any legitimate pivot equal to it bit for
/// bit is harmless except for a spurious report.
pub(super) const SENTINEL_PIVOT: f64 = 0.618_033_988_749_894_8;

/// The symbolic analysis of a symmetric pattern, kept to be reused while the pattern does not change.
pub struct Analysis {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    zero: Vec<bool>,
    ordering: Ordering,
    symbolic: Arc<SymbolicCholesky<usize>>,
}

impl Analysis {
    fn matches(&self, a: SparseColMatRef<'_, usize, f64>, zero: &[bool], ordering: Ordering) -> bool {
        self.ordering == ordering
            && self.col_ptr == a.symbolic().col_ptr()
            && self.row_idx == a.symbolic().row_idx()
            && self.zero == zero
    }
}

pub(super) fn factorize_symmetric(
    a: SparseColMatRef<'_, usize, f64>,
    diag: &[f64],
    method: Method,
    opts: &SolverOptions,
    analysis: &mut Option<Analysis>,
) -> Result<Factorization, SolveError> {
    let n = a.nrows();
    let mut timings = Timings::default();
    let t0 = Instant::now();
    let (cp, ri) = (a.symbolic().col_ptr(), a.symbolic().row_idx());
    // Scaling: Jacobi for LLᵀ (unit diagonal), max-equilibration for LDLᵀ (unit largest entries).
    let scale: Vec<f64> =
        if method == Method::Cholesky { diag.iter().map(|d| 1.0 / d.sqrt()).collect() } else { equilibration(a) };
    let sdiag: Vec<f64> = (0..n).map(|j| diag[j] * scale[j] * scale[j]).collect();
    // Rows without a positive diagonal (multipliers): ordered after their positive neighbours.
    let zero: Vec<bool> =
        if method == Method::Ldlt { sdiag.iter().map(|&d| d <= 1e-14).collect() } else { vec![false; n] };
    let ordering = opts.ordering.resolve(n);
    let reused = analysis.as_ref().is_some_and(|an| an.matches(a, &zero, ordering));
    if !reused {
        let (ptr, adj) = ordering::adjacency(a.symbolic());
        let perm = ordering::order_graph(&ptr, &adj, ordering).map_err(SolveError::Internal)?;
        let perm = ordering::defer_multipliers(&ptr, &adj, &zero, perm);
        drop((ptr, adj));
        let mut inv = vec![0usize; n];
        for (k, &p) in perm.iter().enumerate() {
            inv[p] = k;
        }
        let perm_ref = faer::perm::PermRef::new_checked(&perm, &inv, n);
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(perm_ref),
            Default::default(),
        )
        .map_err(|e| SolveError::Internal(format!("{e:?}")))?;
        *analysis = Some(Analysis {
            col_ptr: cp.to_vec(),
            row_idx: ri.to_vec(),
            zero: zero.clone(),
            ordering,
            symbolic: Arc::new(symbolic),
        });
    }
    let symbolic = analysis.as_ref().expect("analysis set above").symbolic.clone();
    let scaled = scaled(a, &scale);
    timings.symbolic = t0.elapsed();

    let t1 = Instant::now();
    let par = opts.par();
    let mut values = vec![0.0f64; symbolic.len_val()];
    // LLᵀ: a pivot below 10^-NPREC is singular, marked by the sentinel. LDLᵀ: a pivot below round-off
    // (an unknown whose only couplings are eliminated later) is replaced by ±δ, a perturbation that
    // the refinement corrects; a singular matrix shows in the condition estimate.
    let (eps, delta) = match (method, opts.nprec >= 0) {
        (Method::Cholesky, true) => (10f64.powi(-opts.nprec), SENTINEL_PIVOT),
        (Method::Cholesky, false) => (f64::MIN_POSITIVE, f64::EPSILON),
        _ => (LDLT_NULL_PIVOT, LDLT_DELTA),
    };
    let failed = if method == Method::Cholesky {
        let reg = LltRegularization { dynamic_regularization_delta: delta, dynamic_regularization_epsilon: eps };
        let mut buf = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        symbolic
            .factorize_numeric_llt(
                &mut values,
                scaled.as_ref(),
                Side::Lower,
                reg,
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .err()
            .map(|faer::linalg::solvers::LltError::NonPositivePivot { index }| index)
    } else {
        let reg = LdltRegularization {
            dynamic_regularization_signs: None,
            dynamic_regularization_delta: delta,
            dynamic_regularization_epsilon: eps,
        };
        let mut buf = MemBuffer::new(symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()));
        symbolic
            .factorize_numeric_ldlt(
                &mut values,
                scaled.as_ref(),
                Side::Lower,
                reg,
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .err()
            .map(|faer::linalg::solvers::LdltError::ZeroPivot { index }| index)
    };
    timings.factorization = t1.elapsed();
    let perm_fwd: Vec<usize> = match symbolic.perm() {
        Some(p) => p.arrays().0.to_vec(),
        None => (0..n).collect(),
    };
    if let Some(index) = failed {
        let k = index.saturating_sub(1).min(n.saturating_sub(1));
        return Err(SolveError::Singular { kind: SingularKind::Pivot, dofs: vec![perm_fwd[k]], pivots: vec![0.0] });
    }
    // Relative pivots: d_k / a_kk (LLᵀ: l_kk² with a unit diagonal), |d_k| for a zero diagonal.
    let fdiag = factor_diagonal(&symbolic, &values);
    let mut worst: Vec<(f64, usize)> = Vec::new();
    let mut min_pivot = f64::INFINITY;
    let mut regularized = 0;
    for (k, &l) in fdiag.iter().enumerate() {
        let dof = perm_fwd[k];
        let regularised = if method == Method::Cholesky { l == SENTINEL_PIVOT.sqrt() } else { l.abs() == delta };
        if regularised && method == Method::Ldlt {
            // A null pivot of the elimination order, not of the matrix: the refinement corrects the
            // perturbation, and a singular matrix shows there (then LU takes over).
            regularized += 1;
            continue;
        }
        // LLᵀ: l_kk² is the pivot relative to the unit diagonal of the scaled matrix; LDLᵀ: |d_k| relative
        // to the largest entry of its row, 1 in the equilibrated matrix.
        let rel = if regularised {
            0.0
        } else if method == Method::Cholesky {
            l * l
        } else {
            l.abs()
        };
        min_pivot = min_pivot.min(rel);
        if opts.nprec >= 0 && (rel < eps || rel.is_nan()) {
            worst.push((rel, dof));
        }
    }
    if !worst.is_empty() {
        worst.sort_by(|x, y| x.0.total_cmp(&y.0));
        return Err(SolveError::Singular {
            kind: SingularKind::Pivot,
            dofs: worst.iter().map(|w| w.1).collect(),
            pivots: worst.iter().map(|w| w.0).collect(),
        });
    }
    let info = FactorInfo {
        method: Some(method),
        ordering: Some(ordering),
        threads: opts.thread_count(),
        n,
        factor_nnz: symbolic.len_val(),
        reused,
        regularized,
        min_pivot: (method == Method::Cholesky).then_some(min_pivot),
        timings,
        ..Default::default()
    };
    let kind =
        if method == Method::Cholesky { Kind::Llt { symbolic, values } } else { Kind::Ldlt { symbolic, values } };
    Ok(Factorization { kind, scale, par, info })
}

/// Diagonal of the factor (L of LLᵀ, D of LDLᵀ), in the permuted order.
pub(super) fn factor_diagonal(symbolic: &SymbolicCholesky<usize>, values: &[f64]) -> Vec<f64> {
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
