//! The external forces of an X-FEM solve at an instant: PRES_REP with FISSURE, a pressure on both lips
//! of a crack (`xfem::discrete::lip_pressure`), on the facets of the sub-cells; PESANTEUR, ρ g over the
//! sub-cells (`xfem::discrete::body_force`), ρ being ELAS RHO, or THM_DIFFU RHO (the mixture's) on a
//! hydro-mechanical model.

use super::setup::Setup;
use crate::catalog::args::Args;
use crate::concepts::model::{LoadItem, LoadValue};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::core::assembly::loads;
use crate::stages::core::eval::eval_at;
use crate::stages::core::problem::mat_param;
use crate::xfem::discrete;

/// The external force vector at `t` (all unknowns), and whether any load gives one.
pub fn external(a: &Args, s: &Setup, t: f64) -> Result<Option<Vec<f64>>> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    let mut f: Option<Vec<f64>> = None;
    let lonref = {
        let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    };
    for (lc, mult) in loads(a, t)? {
        let data = lc.data();
        let ConceptData::Load(load) = &*data else { continue };
        for item in &load.items {
            if let LoadItem::Gravity { g, direction, cells } = item {
                let fv = f.get_or_insert_with(|| vec![0.0; xd.n]);
                gravity(a, s, mult * g, direction, cells.as_deref(), fv)?;
                continue;
            }
            let LoadItem::CrackPressure { crack, name, value } = item else { continue };
            // The rule of a quadratic facet under a pressure affine in space: exact on straight facets.
            let quadratic = s.model_cells.iter().any(|&c| {
                let t = mesh.cell_types[c];
                t.nnodes() > t.nvertices()
            });
            let order = if quadratic { 4 } else { 2 };
            let rule = discrete::facet_rule(ndim, order).map_err(|e| a.err("EXCIT", e))?;
            let facets = discrete::facets(mesh, xm, *crack, 1e-9 * lonref);
            let p = |x: &[f64; 3]| -> std::result::Result<f64, String> {
                Ok(mult
                    * match value {
                        LoadValue::Real(v) => *v,
                        LoadValue::Func(g) => eval_at(g, x, t).map_err(|e| e.msg)?,
                    })
            };
            let cells = discrete::lip_pressure(mesh, xm, *crack, &facets, &rule, ndim, &p)
                .map_err(|e| a.err("EXCIT", format!("load {}: PRES_REP on the lips of {name}: {e}", lc.label())))?;
            let fv = f.get_or_insert_with(|| vec![0.0; xd.n]);
            for (c, fe) in cells {
                for (d, v) in xd.cell_dofs(&mesh.cells[c]).into_iter().zip(fe) {
                    fv[d] += v;
                }
            }
        }
    }
    Ok(f)
}

/// PESANTEUR: ρ g along `direction` on the model's cells (those of `cells` when given).
fn gravity(a: &Args, s: &Setup, g: f64, direction: &[f64; 3], cells: Option<&[usize]>, f: &mut [f64]) -> Result<()> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    let (behaviour, what) = if s.hm { ("THM_DIFFU", "THM_DIFFU/RHO") } else { ("ELAS", "ELAS/RHO") };
    for &c in &s.model_cells {
        if cells.is_some_and(|sel| !sel.contains(&c)) {
            continue;
        }
        let name = &mesh.cell_names[c];
        let m = s.material(a, c)?;
        let rho = mat_param(&m, behaviour, "RHO", name).map_err(|e| e.at(a.span))?.ok_or_else(|| {
            a.err("CHAM_MATER", format!("PESANTEUR needs the density {what} of the material of cell {name}"))
        })?;
        let acc = direction.map(|d| rho * g * d);
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let fe = discrete::body_force(mesh.cell_types[c], &coords, nodes, xm, c, ndim, &acc)
            .map_err(|e| a.err("EXCIT", format!("PESANTEUR on cell {name}: {e}")))?;
        for (d, v) in xd.cell_dofs(nodes).into_iter().zip(fe) {
            f[d] += v;
        }
    }
    Ok(())
}
