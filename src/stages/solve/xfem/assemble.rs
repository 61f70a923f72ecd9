//! The discrete operators of an X-FEM solve, assembled once: the bulk stiffness on the sub-cells, the
//! mortar couplings of each cohesive zone, and the cohesive law of each multiplier packet.

use super::setup::Setup;
use crate::diag::{Error, Result};
use crate::fem::dofs::DofMap;
use crate::stages::core::problem::elastic_of;
use crate::stages::core::settings::Settings;
use crate::xfem::discrete::{self, Coupling, XDofs};
use std::collections::BTreeSet;
use std::time::{Duration, Instant};

/// A linear element: unknowns and matrix (row-major).
pub struct Lin {
    pub dofs: Vec<usize>,
    pub k: Vec<f64>,
}

/// One packet's cohesive law: zone, lumped weight, first unknown (λ, then w).
pub struct Law {
    pub zone: usize,
    pub m: f64,
    pub base: usize,
}

/// The operators assembled once: linear elements, cohesive laws, the interface measure per packet of
/// each zone, and the time it took.
pub struct Elements {
    pub lins: Vec<Lin>,
    pub laws: Vec<Law>,
    pub lumped: Vec<Vec<f64>>,
    /// Per zone, the multiplier components (packet, q) removed because they test only prescribed jumps
    /// (`discrete::dead_components`): their λ, w and μ are held at zero.
    pub dead: Vec<BTreeSet<(usize, usize)>>,
    /// The combinations of multiplier components that test no free jump, of one crack or across the
    /// cracks of a junction (`discrete::null_multipliers`).
    pub null: Vec<NullRelation>,
    pub time: Duration,
}

/// A multiplier direction removed (`discrete::NullDirection`), on the full unknowns: the μ are kept
/// orthogonal to it (Σ v μ = 0), and the free jump of a near-sliver set it tested is held at zero
/// (Σ g u = 0).
pub struct NullRelation {
    pub mu: Vec<(usize, f64)>,
    pub lock: Option<Vec<(usize, f64)>>,
}

/// `fixed`: the unknowns the kinematic conditions prescribe, and `map` their elimination with the
/// relations (at the first instant solved).
pub fn elements(cfg: &Settings, s: &Setup, fixed: &BTreeSet<usize>, map: &DofMap) -> Result<Elements> {
    let t0 = Instant::now();
    let (mesh, xm, xd, md, ndim) = (&s.mesh, &s.xm, &s.xd, s.md, s.ndim());
    let mut lins: Vec<Lin> = Vec::new();
    // With coupled flow the bulk is the HM element of `flow`, not the elastic stiffness.
    for &c in s.model_cells.iter().filter(|_| s.flow.is_none()) {
        let m = s.material(cfg, c)?;
        let (law, _) = elastic_of(&m, &mesh.cell_names[c]).map_err(|e| e.at(cfg.span))?;
        law.check(md).map_err(|e| cfg.err("CHAM_MATER", format!("cell {}: {e}", mesh.cell_names[c])))?;
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let k = discrete::bulk_stiffness(mesh.cell_types[c], &coords, nodes, xm, c, &law.hooke(md), md.nsig(), ndim)
            .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])).at(cfg.span))?;
        lins.push(Lin { dofs: xd.cell_dofs(nodes), k });
    }
    let nbulk = lins.len();
    let mut laws: Vec<Law> = Vec::new();
    let mut lumped: Vec<Vec<f64>> = Vec::new();
    let mut dead_all: Vec<BTreeSet<(usize, usize)>> = Vec::new();
    let mut all_cps: Vec<discrete::Coupling> = Vec::new();
    // A node's jump in direction d is prescribed when every Heaviside unknown of the node in d is.
    let fixed_jump = |n: usize, d: usize| xd.sets[n].iter().all(|&b| fixed.contains(&(b + d)));
    for (zi, z) in s.zones.iter().enumerate() {
        let rule = discrete::facet_rule(ndim, z.order).map_err(|e| cfg.err("CONTACT", e))?;
        let facets = s.facets(z.crack);
        // Heaviside sets with no facet to couple the sides they separate:
        // the interface would open freely where the scene glues it. An interface along a row or plane of
        // nodes has its facets on the cells of its − side; none is left when those are not in the model.
        if facets.is_empty() || z.packets.is_empty() {
            return Err(cfg.err(
                "CONTACT",
                format!(
                    "{}: the interface has no facet: no cell of the model is cut by it or lies on its − side \
                     with a whole edge or face on it",
                    xm.crack_names[z.crack]
                ),
            ));
        }
        let crack_err = |e: String| cfg.err("CONTACT", format!("{}: {e}", xm.crack_names[z.crack]));
        let dead = discrete::dead_components(
            mesh,
            xm,
            z.crack,
            facets,
            &rule,
            &z.packets,
            &z.packet_of,
            &z.edges,
            ndim,
            &fixed_jump,
        )
        .map_err(crack_err)?;
        let cps = discrete::couplings(mesh, xm, z.crack, facets, &rule, &z.packet_of, &z.edges, &dead, ndim)
            .map_err(crack_err)?;
        let mut m = vec![0.0; z.packets.len()];
        for cp in &cps {
            lins.push(coupling(&s.mesh, &s.xd, z.crack, cp, ndim));
            for (k, &p) in cp.packets.iter().enumerate() {
                m[p] += cp.m[k];
            }
        }
        for (k, &mk) in m.iter().enumerate() {
            if mk <= 0.0 {
                return Err(cfg.err(
                    "CONTACT",
                    format!(
                        "{}: multiplier packet {:?} has no interface measure",
                        xm.crack_names[z.crack],
                        super::setup::names(mesh, &z.packets[k])
                    ),
                ));
            }
            laws.push(Law { zone: zi, m: mk, base: xd.packets[z.crack][k] });
        }
        all_cps.extend(cps);
        lumped.push(m);
        dead_all.push(dead);
    }
    let none = BTreeSet::new();
    let dead_of: Vec<&BTreeSet<(usize, usize)>> = (0..xm.cracks.len())
        .map(|g| s.zones.iter().position(|z| z.crack == g).map_or(&none, |zi| &dead_all[zi]))
        .collect();
    // The bulk's stiffness weighs the near-null directions (with coupled flow it is the HM element's,
    // not assembled here: the directions are weighed as of mean stiffness).
    let bulk: Vec<(&[usize], &[f64])> = lins[..nbulk].iter().map(|l| (&l.dofs[..], &l.k[..])).collect();
    let bulk = (s.flow.is_none()).then_some(&bulk[..]);
    let null = discrete::null_multipliers(&all_cps, xd, mesh, ndim, &dead_of, map, bulk)
        .into_iter()
        .map(|v| NullRelation {
            mu: v.mu.into_iter().map(|(g, k, q, c)| (xd.packets[g][k] + 2 * ndim + q, c)).collect(),
            lock: v.lock.map(|l| l.into_iter().map(|(i, c)| (map.free_to_full[i], c)).collect()),
        })
        .collect();

    Ok(Elements { lins, laws, lumped, dead: dead_all, null, time: t0.elapsed() })
}

/// The mortar coupling of one cell with the packets it touches: the unknowns (the cell's, then w and μ
/// of each packet) and the symmetric matrix of the constraints μ·(C u − M w).
fn coupling(mesh: &crate::mesh::Mesh, xd: &XDofs, crack: usize, cp: &Coupling, ndim: usize) -> Lin {
    let z_crack = crack;
    let nodes = &mesh.cells[cp.cell];
    let mut dofs = xd.cell_dofs(nodes);
    let nu = dofs.len();
    let np = cp.packets.len();
    for &k in &cp.packets {
        let b = xd.packets[z_crack][k];
        dofs.extend(b + ndim..b + 2 * ndim); // w
    }
    for &k in &cp.packets {
        let b = xd.packets[z_crack][k];
        dofs.extend(b + 2 * ndim..b + 3 * ndim); // μ
    }
    let nd = dofs.len();
    let mut ke = vec![0.0; nd * nd];
    let wof = |k: usize, q: usize| nu + k * ndim + q;
    let muof = |k: usize, q: usize| nu + np * ndim + k * ndim + q;
    for r in 0..nu {
        for k in 0..np {
            for q in 0..ndim {
                let v = cp.c[r * np * ndim + k * ndim + q];
                ke[r * nd + muof(k, q)] += v;
                ke[muof(k, q) * nd + r] += v;
            }
        }
    }
    for k in 0..np {
        for l in 0..np {
            for q in 0..ndim {
                let v = -cp.mm[q * np * np + k * np + l];
                ke[muof(k, q) * nd + wof(l, q)] += v;
                ke[wof(k, q) * nd + muof(l, q)] += v;
            }
        }
    }
    Lin { dofs, k: ke }
}
