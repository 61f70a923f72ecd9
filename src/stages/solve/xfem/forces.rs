//! The external forces of an X-FEM solve at an instant: PRES_REP with FISSURE, a pressure on both lips
//! of a crack (`xfem::discrete::lip_pressure`), on the facets of the sub-cells; PESANTEUR, ρ g over the
//! sub-cells (`xfem::discrete::body_force`), ρ being ELAS RHO, or THM_DIFFU RHO (the mixture's) on a
//! hydro-mechanical model.

use super::setup::Setup;
use super::state::PorePressure;
use crate::diag::Result;
use crate::fem::physics::{Force, Load};
use crate::stages::core::problem::mat_param;
use crate::stages::core::settings::Settings;
use crate::xfem::discrete;

/// The external forces of the loads added to `f` (all unknowns); `pressure`, the pore pressure the loads
/// prescribe on an HM model, acts through the Biot term ([`biot`]).
pub fn external(
    cfg: &Settings,
    s: &Setup,
    loads: &[Load],
    pressure: Option<&PorePressure>,
    f: &mut [f64],
) -> Result<()> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    if let Some(p) = pressure {
        biot(cfg, s, p, f)?;
    }
    for load in loads {
        for item in &load.forces {
            if let Force::Gravity { g, direction, cells } = item {
                gravity(cfg, s, *g, direction, *cells, f)?;
                continue;
            }
            let Force::LipPressure { crack, name, value } = item else { continue };
            // A rule exact for a pressure affine in space on straight facets: the parent's shape
            // functions restricted to a plane inclined to the axes are of degree 3 (HEXA8's xyz) or 4
            // (HEXA20's x²yz, PENTA15), one more with the pressure: FPG7 (degree 5) in 3D; on a line,
            // degree 2 (QUAD4's xy) or 3 (QUAD8's x²y), plus one: 2 or 4 Gauss points. With FPG3 the
            // lips of HEXA8 cells were loaded unlike the sub-cells that carry them (1.5e-3·U off).
            let quadratic = || {
                s.model_cells.iter().any(|&c| {
                    let t = mesh.cell_types[c];
                    t.nnodes() > t.nvertices()
                })
            };
            let order = if ndim == 3 {
                5
            } else if quadratic() {
                4
            } else {
                2
            };
            let rule = discrete::facet_rule(ndim, order).map_err(|e| cfg.err("EXCIT", e))?;
            let p = |x: &[f64; 3]| -> std::result::Result<f64, String> { value.at(x).map_err(|e| e.msg) };
            // Code_Aster loads the cells of the crack's enriched-cell lists (`xtmafi`: MAILFISS.HEAV, …, the
            // cells with a node it enriches), and in each of them the lips of every interface the cell sees
            // (`te0037` loops over the cell's cracks): a branch of a junction is loaded where it crosses
            // those cells.
            let loaded: std::collections::BTreeSet<usize> = xm.cracks[*crack].heaviside_cells.iter().copied().collect();
            for g in 0..xm.cracks.len() {
                let facets: Vec<discrete::Facet> =
                    s.facets(g).iter().filter(|fc| loaded.contains(&fc.cell)).cloned().collect();
                let cells = discrete::lip_pressure(mesh, xm, g, &facets, &rule, ndim, &p).map_err(|e| {
                    cfg.err(
                        "EXCIT",
                        format!(
                            "load {}: PRES_REP on the lips of {} ({name}'s cells): {e}",
                            load.name, xm.crack_names[g]
                        ),
                    )
                })?;
                for (c, fe) in cells {
                    for (d, v) in xd.cell_dofs(&mesh.cells[c]).into_iter().zip(fe) {
                        f[d] += v;
                    }
                }
            }
        }
    }
    Ok(())
}

/// PESANTEUR: ρ g along `direction` on the model's cells (those of `cells` when given).
fn gravity(
    cfg: &Settings,
    s: &Setup,
    g: f64,
    direction: &[f64; 3],
    cells: Option<&[usize]>,
    f: &mut [f64],
) -> Result<()> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    let (behaviour, what) = if s.hm { ("THM_DIFFU", "THM_DIFFU/RHO") } else { ("ELAS", "ELAS/RHO") };
    for &c in &s.model_cells {
        if cells.is_some_and(|sel| !sel.contains(&c)) {
            continue;
        }
        let name = &mesh.cell_names[c];
        let m = s.material(cfg, c)?;
        let rho = mat_param(&m, behaviour, "RHO", name).map_err(|e| e.at(cfg.span))?.ok_or_else(|| {
            cfg.err("CHAM_MATER", format!("PESANTEUR needs the density {what} of the material of cell {name}"))
        })?;
        let acc = direction.map(|d| rho * g * d);
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let fe = discrete::body_force(mesh.cell_types[c], &coords, nodes, xm, c, ndim, &acc)
            .map_err(|e| cfg.err("EXCIT", format!("PESANTEUR on cell {name}: {e}")))?;
        for (d, v) in xd.cell_dofs(nodes).into_iter().zip(fe) {
            f[d] += v;
        }
    }
    Ok(())
}

/// A prescribed pore pressure on the skeleton: the stress −b·p of the mixture moved to the right-hand
/// side on every model cell (`discrete::pore_pressure_force`), b being THM_DIFFU BIOT_COEF. The stress
/// of the pressure is incremental in Code_Aster; the initial state here has p = 0.
fn biot(cfg: &Settings, s: &Setup, p: &PorePressure, f: &mut [f64]) -> Result<()> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    for &c in &s.model_cells {
        let name = &mesh.cell_names[c];
        let nodes = &mesh.cells[c];
        let t = mesh.cell_types[c];
        let nv = t.nvertices();
        if nodes[..nv].iter().all(|&n| p.pre1[n] == 0.0 && p.hpre1[n].iter().all(|v| *v == 0.0)) {
            continue;
        }
        let m = s.material(cfg, c)?;
        let b = mat_param(&m, "THM_DIFFU", "BIOT_COEF", name).map_err(|e| e.at(cfg.span))?.ok_or_else(|| {
            cfg.err("CHAM_MATER", format!("cell {name}: a prescribed pore pressure needs THM_DIFFU/BIOT_COEF"))
        })?;
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let pre1: Vec<f64> = nodes[..nv].iter().map(|&n| p.pre1[n]).collect();
        let hpre1: Vec<Vec<f64>> = nodes[..nv].iter().map(|&n| p.hpre1[n].clone()).collect();
        let fe = discrete::pore_pressure_force(t, &coords, nodes, xm, c, ndim, b, &pre1, &hpre1)
            .map_err(|e| cfg.err("EXCIT", format!("pore pressure on cell {name}: {e}")))?;
        for (d, v) in xd.cell_dofs(nodes).into_iter().zip(fe) {
            f[d] += v;
        }
    }
    Ok(())
}
