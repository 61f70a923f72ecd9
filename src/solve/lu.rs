//! LU with partial pivoting (faer's sparse LU) of the equilibrated matrix: the non-symmetric systems,
//! and the fallback of an LDLᵀ whose refinement does not reach round-off.

use super::*;

pub(super) fn factorize_lu(
    a: SparseColMatRef<'_, usize, f64>,
    opts: &SolverOptions,
) -> Result<Factorization, SolveError> {
    let _ = opts;
    let n = a.nrows();
    let mut timings = Timings::default();
    let t0 = Instant::now();
    // Symmetric equilibration (Ruiz): one sweep of max-scaling left rows of the X-FEM interface
    // laws, whose entries mix E with 1/E, unbalanced against the bulk (condition estimates 1e17–1e19
    // where the equilibrated matrix has 1e8–1e10, and LU pivots lost on a TETRA4 junction that did not
    // converge).
    let scale = equilibration(a);
    let sa = scaled(a, &scale);
    let symbolic = SymbolicLu::try_new(sa.symbolic()).map_err(|e| SolveError::Internal(format!("{e:?}")))?;
    timings.symbolic = t0.elapsed();
    let t1 = Instant::now();
    let lu = Lu::try_new_with_symbolic(symbolic, sa.as_ref()).map_err(|e| match e {
        faer::sparse::linalg::LuError::SymbolicSingular { index } => SolveError::Singular {
            kind: SingularKind::Structural,
            dofs: vec![index.min(n.saturating_sub(1))],
            pivots: vec![f64::NAN],
        },
        other => SolveError::Internal(format!("{other:?}")),
    })?;
    timings.factorization = t1.elapsed();
    let info = FactorInfo { method: Some(Method::Lu), threads: 1, n, timings, ..Default::default() };
    Ok(Factorization { kind: Kind::Lu(Box::new(lu)), scale, par: Par::Seq, info })
}
