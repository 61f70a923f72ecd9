//! The hydraulic rows of an HM X-FEM model in the reference force of RESI_GLOB_RELA.
//!
//! The driver eliminates every hydraulic unknown at zero, but Code_Aster keeps them, blocked by dualised
//! conditions, and its reference force (`nmrede`) is the largest reaction over **all** equations: the
//! hydraulic rows count with the mechanical ones. With p = p_f = q± = 0 and no gravity every flux
//! vanishes, and the reaction of a hydraulic row is its storage term (hm-coupled-formulation.md §1.2, §6.2):
//! - bulk pressure row of vertex i (PRE1), and of its Heaviside part j (H<j>PRE1):
//!   ∫ N̂_i (ψ_j) (M⁺ − M⁻) dΩ over the sub-cells, with M = ρ₀ φ (1 + ε_v) and, the pressure staying
//!   zero, φ = b − (b − φ₀) exp(−ε_v) (`viporo` compounded from the unstrained state), ρ = ρ₀;
//! - fracture row of a multiplier packet (PRE_FLU): ρ₀ (w_n⁺ − w_n⁻) times the packet's interface measure
//!   (its vertices' rows summed; the storage m_f = ρ_f w_n per unit area).
//!
//! M⁻, w_n⁻ are those of the start of the step. These rows matter only where the mechanical reactions
//! vanish (a fully broken interface): there they set the scale Code_Aster converges to.

use super::assemble::{Elements, Law};
use super::setup::Setup;
use crate::diag::{Error, Result};
use crate::stages::core::settings::Settings;
use crate::xfem::discrete::{bulk_points, real_gradients};

/// One integration point: weight, region, real gradients of the cell's shape functions, and the
/// linear vertex functions N̂.
struct Point {
    w: f64,
    region: i32,
    grad: Vec<[f64; 3]>,
    nhat: Vec<f64>,
}

struct Cell {
    nodes: Vec<usize>,
    points: Vec<Point>,
    /// b, φ₀, ρ₀ of the cell's material.
    biot: f64,
    phi0: f64,
    rho: f64,
}

/// The geometry and materials of the hydraulic rows, built once per solve.
pub struct HydraulicRows {
    cells: Vec<Cell>,
    /// Per law (packet) of `Elements`: ρ₀ of the interface's material.
    rho_f: Vec<f64>,
}

impl HydraulicRows {
    /// None for a model without hydraulics.
    pub fn new(cfg: &Settings, s: &Setup, el: &Elements) -> Result<Option<HydraulicRows>> {
        if !s.hm {
            return Ok(None);
        }
        let (mesh, xm) = (&*s.mesh, &*s.xm);
        let mut cells = Vec::with_capacity(s.model_cells.len());
        for &c in &s.model_cells {
            let name = &mesh.cell_names[c];
            let bad = |e: String| Error::runtime(format!("cell {name}: {e}")).at(cfg.span);
            let m = s.material(cfg, c)?;
            let (biot, _) = crate::stages::core::hm::biot_of(&m, name).map_err(|e| e.at(cfg.span))?;
            let t = mesh.cell_types[c];
            let nodes = mesh.cells[c].clone();
            let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let pts: Vec<([f64; 3], f64, i32)> = if xm.cells.contains_key(&c) {
                bulk_points(t, &coords, xm, c).map_err(bad)?.into_iter().map(|p| (p.xi, p.w, p.region)).collect()
            } else {
                let rule = crate::fem::elasticity::rigi_rule(t);
                let mut v = Vec::new();
                for (q, w) in rule.points.iter().zip(&rule.weights) {
                    let (_, _, det) = real_gradients(t, &coords, q).ok_or_else(|| bad("degenerate cell".into()))?;
                    v.push((*q, w * det, 0));
                }
                v
            };
            let vt = crate::fem::elasticity::vertex_type(t);
            let mut points = Vec::with_capacity(pts.len());
            for (xi, w, region) in pts {
                let (_, grad, _) = real_gradients(t, &coords, &xi).ok_or_else(|| bad("degenerate cell".into()))?;
                points.push(Point { w, region, grad, nhat: crate::fem::reference::shape(vt, &xi) });
            }
            cells.push(Cell { nodes, points, biot: biot.biot, phi0: biot.phi0, rho: biot.rho_l });
        }
        let mut rho_f = Vec::with_capacity(el.laws.len());
        for l in &el.laws {
            let z = &s.zones[l.zone];
            let c = *z.cells.first().ok_or_else(|| cfg.err("CONTACT", "a cohesive zone without contact cells"))?;
            let m = s.material(cfg, c)?;
            let (biot, _) = crate::stages::core::hm::biot_of(&m, &mesh.cell_names[c]).map_err(|e| e.at(cfg.span))?;
            rho_f.push(biot.rho_l);
        }
        Ok(Some(HydraulicRows { cells, rho_f }))
    }

    /// The largest reaction of a hydraulic row between the start-of-step unknowns `x0` and `x`.
    pub fn largest(&self, s: &Setup, laws: &[Law], x0: &[f64], x: &[f64]) -> f64 {
        let (xm, xd, ndim) = (&*s.xm, &s.xd, s.ndim());
        let nn = s.mesh.nnodes();
        // Rows: PRE1 per node, then H<j>PRE1 per node and set.
        let mut plain = vec![0.0; nn];
        let mut enriched: Vec<Vec<f64>> = xd.sets.iter().map(|v| vec![0.0; v.len()]).collect();
        for cell in &self.cells {
            let nv = cell.points.first().map_or(0, |p| p.nhat.len());
            for p in &cell.points {
                let eps_v = |u: &[f64]| -> f64 {
                    let mut e = 0.0;
                    for (ia, &n) in cell.nodes.iter().enumerate() {
                        let b = xd.std[n].expect("node of a model cell");
                        for i in 0..ndim {
                            let mut v = u[b + i];
                            for (j, &sb) in xd.sets[n].iter().enumerate() {
                                let psi = xm.psi(n, j, p.region);
                                if psi != 0.0 {
                                    v += psi * u[sb + i];
                                }
                            }
                            e += p.grad[ia][i] * v;
                        }
                    }
                    e
                };
                let mass = |e: f64| -> f64 {
                    let phi = cell.biot - (cell.biot - cell.phi0) * (-e).exp();
                    cell.rho * phi * (1.0 + e)
                };
                let dm = (mass(eps_v(x)) - mass(eps_v(x0))) * p.w;
                for (ia, &n) in cell.nodes.iter().enumerate().take(nv) {
                    let f = p.nhat[ia] * dm;
                    plain[n] += f;
                    for (j, r) in enriched[n].iter_mut().enumerate() {
                        *r += xm.psi(n, j, p.region) * f;
                    }
                }
            }
        }
        let bulk = plain.iter().chain(enriched.iter().flatten()).fold(0.0_f64, |m, v| m.max(v.abs()));
        let fracture = laws
            .iter()
            .zip(&self.rho_f)
            .map(|(l, rho)| (rho * (x[l.base + ndim] - x0[l.base + ndim]) * l.m).abs())
            .fold(0.0, f64::max);
        bulk.max(fracture)
    }
}
