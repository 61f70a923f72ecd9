//! SOLVEUR options, the solve of a reduced system with singular unknowns named, and the fields of a step.

use super::problem::{coords_of, Problem};
use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::diag::{Error, Result};
use crate::fem::dofs::DofMap;
use crate::fem::elasticity::{self};
use crate::solve::{self, SolverOptions};
use std::collections::BTreeMap;
///
/// Every METHODE of Code_Aster is solved by our sparse direct factorization: the direct ones (MUMPS,
/// MULT_FRONT, LDLT) are what it is, and an iterative one (GCPC, PETSC) converges towards what it gives
/// exactly. NPREC and RESI_RELA keep their meaning. The knobs of how a solver works (RENUM,
/// PCENT_PIVOT, GESTION_MEMOIRE, ACCELERATION, preconditioners, ...) change its cost or make it
/// approximate, never the exact solution we compute, so they are taken as read. STOP_SINGULIER='NON'
/// (going on with a singular matrix) is refused.
pub fn solver_options(a: &Args) -> Result<SolverOptions> {
    let mut opts = SolverOptions::default();
    if let Some(s) = a.fact("SOLVEUR") {
        if s.text_if_declared("STOP_SINGULIER") == Some("NON") {
            return Err(s.err("STOP_SINGULIER", "STOP_SINGULIER='NON' is not supported yet"));
        }
        if let Some(n) = s.int("NPREC") {
            opts.nprec = n as i32;
        }
        if let Some(r) = s.real("RESI_RELA") {
            opts.resi_rela = r;
        }
        s.read_all();
    }
    Ok(opts)
}

/// Solve, turning a singular matrix into a message naming the unknowns.
pub fn solve_reduced(
    a: &Args,
    p: &Problem,
    map: &DofMap,
    k: &faer::sparse::SparseColMat<usize, f64>,
    rhs: &[f64],
    opts: &SolverOptions,
) -> Result<solve::Solution> {
    // A nan or an infinity in the data (E, NU, a load, a coordinate) reaches the system as such: name
    // it, rather than let the factorisation call the system singular.
    let name = |dofs: &[usize]| -> String {
        let names: Vec<String> =
            dofs.iter().take(6).map(|&d| p.numbering.label(map.free_to_full[d], Some(&p.mesh))).collect();
        names.join(", ")
    };
    let (col_ptr, values) = (k.col_ptr(), k.val());
    let bad_k: Vec<usize> =
        (0..k.ncols()).filter(|&j| values[col_ptr[j]..col_ptr[j + 1]].iter().any(|v| !v.is_finite())).collect();
    if !bad_k.is_empty() {
        return Err(a.err(
            "CHAM_MATER",
            format!(
                "the stiffness is not finite (nan or infinite) at unknowns {}: check the material (E, NU) and the mesh",
                name(&bad_k)
            ),
        ));
    }
    let bad_f: Vec<usize> = (0..rhs.len()).filter(|&d| !rhs[d].is_finite()).collect();
    if !bad_f.is_empty() {
        return Err(a.err(
            "EXCIT",
            format!(
                "the loads are not finite (nan or infinite) at unknowns {}: check the values of the loads",
                name(&bad_f)
            ),
        ));
    }
    solve::solve(k.as_ref(), rhs, opts).map_err(|e| match e {
        solve::SolveError::Singular { dofs, .. } => {
            let names: Vec<String> =
                dofs.iter().take(6).map(|&d| p.numbering.label(map.free_to_full[d], Some(&p.mesh))).collect();
            a.err(
                "EXCIT",
                format!("the system is singular (rigid-body motion not prevented?): unknowns {}", names.join(", ")),
            )
        }
        other => Error::runtime(other.to_string()).at(a.span),
    })
}

/// DEPL (and SIEF_ELGA) of a full displacement vector.
pub fn step_fields(p: &Problem, u: &[f64], with_sief: bool) -> Result<BTreeMap<String, Field>> {
    let mesh = &p.mesh;
    let md = p.modelisation;
    let dim = md.dim();
    let mut depl = vec![f64::NAN; mesh.coords.len() * dim];
    for (d, v) in u.iter().enumerate() {
        let (node, k) = p.numbering.node_comp(d);
        depl[node * dim + k] = *v;
    }
    let comps: Vec<String> = ["DX", "DY", "DZ"][..dim].iter().map(|s| s.to_string()).collect();
    let mut fields = BTreeMap::new();
    fields.insert("DEPL".to_string(), Field::Node { components: comps, values: depl });
    if with_sief {
        let mut cells = vec![None; mesh.cells.len()];
        for &c in &p.bulk {
            let ue: Vec<f64> = p.numbering.cell_dofs(&mesh.cells[c]).unwrap().iter().map(|&d| u[d]).collect();
            let g = elasticity::gauss_fields(
                md,
                &p.materials[c].as_ref().unwrap().0,
                mesh.cell_types[c],
                &coords_of(mesh, c),
                &ue,
            )
            .map_err(|e| Error::runtime(e.to_string()))?;
            cells[c] = Some(g.sig.iter().flat_map(|s| s[..md.nsig()].to_vec()).collect());
        }
        let names = md.sigma_names().iter().map(|s| s.to_string()).collect();
        fields.insert("SIEF_ELGA".to_string(), Field::Elga { components: names, cells });
    }
    Ok(fields)
}
