//! The enriched model of MODI_MODELE_XFEM: which cells are X-FEM cells, the
//! cracks each one sees, its cutting into sub-cells, the sub-domain (region)
//! of every sub-cell, and the Heaviside enrichment sets of every node.
//!
//! Regions are sign tuples over the model's whole crack list, with the
//! junction zeroing (a branch's sign is 0 where it does not exist), coded as
//! `xcalc_code` does. A node's enrichment sets are the regions present in
//! its support other than its own region; set `j` of node `i` multiplies
//! `N_i` by `ψ = 2·χ(region)`, so that the nodal value of the field is the
//! standard unknown. This spans the same space as Code_Aster's per-element
//! Heaviside lists (`hm-xfem-formulation.md` §2.3); only the order of the
//! sets inside a node is ours: sets are sorted by the first crack (in model
//! order) whose sign differs from the node's own region, then by code, so
//! that H1 is the first crack's set and H2 the second's at a junction node.

use super::levelset::{node_signs, region_code};
use super::topose::Cutting;
use crate::fem::reference::shape;
use crate::mesh::{CellType, Mesh};
use std::collections::BTreeMap;

/// One X-FEM cell.
#[derive(Debug, Clone)]
pub struct XfemCell {
    /// The cracks the cell sees (indices in the model's crack list, model order).
    pub cracks: Vec<usize>,
    pub cutting: Cutting,
    /// Global sign tuple of each sub-cell (over the model's crack list).
    pub signs: Vec<Vec<i32>>,
    /// Region code of each sub-cell.
    pub regions: Vec<i32>,
}

/// What MODI_MODELE_XFEM adds to a model.
#[derive(Debug, Clone)]
pub struct XfemModel {
    /// The cracks (DEFI_FISS_XFEM concepts), model order.
    pub cracks: Vec<crate::concepts::ConceptRef>,
    /// Names of the cracks, model order.
    pub crack_names: Vec<String>,
    /// Nodal normal level set of each crack.
    pub lsn: Vec<Vec<f64>>,
    /// Junction of each crack: (index of its master in the list, coef).
    pub masters: Vec<Option<(usize, f64)>>,
    /// Heaviside-enriched nodes of each crack (node status).
    pub enriched: Vec<Vec<bool>>,
    /// CONTACT: 'SANS' or 'MORTAR'.
    pub contact: String,
    /// The X-FEM cells.
    pub cells: BTreeMap<usize, XfemCell>,
    /// Own region code of every node (`xlsjon` + `xcalc_code`).
    pub node_region: Vec<i32>,
    /// Enrichment sets of every node: the region codes, in set order.
    pub node_sets: Vec<Vec<i32>>,
}

fn sign(v: f64) -> i32 {
    if v < 0.0 {
        -1
    } else {
        1
    }
}

/// The global sign tuple at a point of a cell: the sub-cell's Heaviside
/// values for the cracks the cell sees, the sign of the interpolated level
/// set for the others, then the junction zeroing of the others (a branch
/// whose master is seen by the cell uses the master's Heaviside value).
pub fn point_signs(
    lsn: &[Vec<f64>],
    masters: &[Option<(usize, f64)>],
    cell_nodes: &[usize],
    ff: &[f64],
    cell_cracks: &[usize],
    he: &[i32],
) -> Vec<i32> {
    let m = lsn.len();
    let val = |g: usize| -> f64 { cell_nodes.iter().zip(ff).map(|(&n, f)| f * lsn[g][n]).sum() };
    let mut s = vec![0; m];
    let mut from_cell = vec![false; m];
    for (p, &g) in cell_cracks.iter().enumerate() {
        s[g] = he[p];
        from_cell[g] = true;
    }
    let values: Vec<f64> = (0..m).map(&val).collect();
    for g in 0..m {
        if from_cell[g] {
            continue;
        }
        // Own sign, then the junction chain (xlsjon's rule on values).
        let one: Vec<[f64; 1]> = (0..m)
            .map(|k| {
                if from_cell[k] {
                    // The cell's Heaviside value stands for the level set.
                    [if s[k] == 0 { f64::NAN } else { s[k] as f64 }]
                } else {
                    [values[k]]
                }
            })
            .collect();
        let refs: Vec<&[f64]> = one.iter().map(|v| v.as_slice()).collect();
        s[g] = if m == 1 { sign(values[g]) } else { node_signs(&refs, masters, 0)[g] };
    }
    s
}

impl XfemModel {
    /// Build the regions and enrichment sets from the cracks' data and the
    /// cells' cuttings. `model_cells` are the cells of the model (bulk).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        mesh: &Mesh,
        model_cells: &[usize],
        cracks: Vec<crate::concepts::ConceptRef>,
        crack_names: Vec<String>,
        lsn: Vec<Vec<f64>>,
        masters: Vec<Option<(usize, f64)>>,
        enriched: Vec<Vec<bool>>,
        contact: String,
        cuttings: BTreeMap<usize, (Vec<usize>, Cutting)>,
    ) -> Result<XfemModel, String> {
        let nn = mesh.nnodes();
        let lsn_refs: Vec<&[f64]> = lsn.iter().map(|v| v.as_slice()).collect();
        let node_region: Vec<i32> = (0..nn).map(|n| region_code(&node_signs(&lsn_refs, &masters, n))).collect();
        let mut cells = BTreeMap::new();
        // Regions present around every node.
        let mut around: Vec<Vec<(Vec<i32>, i32)>> = vec![Vec::new(); nn];
        for &c in model_cells {
            let t = mesh.cell_types[c];
            let nodes = &mesh.cells[c];
            if let Some((cracks, cutting)) = cuttings.get(&c) {
                let mut signs = Vec::with_capacity(cutting.subcells.len());
                let mut regions = Vec::with_capacity(cutting.subcells.len());
                for sc in &cutting.subcells {
                    let nv = if mesh.dim == 2 { 3 } else { 4 };
                    let mut xi = [0.0; 3];
                    for &p in &sc.nodes[..nv] {
                        for (x, v) in xi.iter_mut().zip(&cutting.points[p].xi) {
                            *x += v / nv as f64;
                        }
                    }
                    let ff = shape(t, &xi);
                    let s = point_signs(&lsn, &masters, nodes, &ff, cracks, &sc.he);
                    let code = region_code(&s);
                    for &n in nodes {
                        if !around[n].iter().any(|(_, r)| *r == code) {
                            around[n].push((s.clone(), code));
                        }
                    }
                    signs.push(s);
                    regions.push(code);
                }
                cells.insert(c, XfemCell { cracks: cracks.clone(), cutting: cutting.clone(), signs, regions });
            } else {
                let xi = crate::fem::reference::ref_centroid(t);
                let ff = shape(t, &xi);
                let s = point_signs(&lsn, &masters, nodes, &ff, &[], &[]);
                let code = region_code(&s);
                for &n in nodes {
                    if !around[n].iter().any(|(_, r)| *r == code) {
                        around[n].push((s.clone(), code));
                    }
                }
            }
        }
        let mut node_sets = vec![Vec::new(); nn];
        for n in 0..nn {
            if around[n].len() < 2 {
                continue;
            }
            let own = node_signs(&lsn_refs, &masters, n);
            let own_code = node_region[n];
            let mut others: Vec<(usize, i32)> = around[n]
                .iter()
                .filter(|(_, r)| *r != own_code)
                .map(|(s, r)| (s.iter().zip(&own).position(|(a, b)| a != b).unwrap_or(usize::MAX), *r))
                .collect();
            others.sort();
            if others.len() == around[n].len() {
                // The node's own region is not in its support (it lies on an
                // interface): one region stands for the standard unknown.
                others.remove(0);
            }
            if !others.is_empty() && !enriched.iter().any(|e| e[n]) {
                return Err(format!(
                    "node {} sees {} sub-domains but no interface enriches it",
                    mesh.node_names[n],
                    others.len() + 1
                ));
            }
            node_sets[n] = others.into_iter().map(|(_, r)| r).collect();
        }
        Ok(XfemModel { cracks, crack_names, lsn, masters, enriched, contact, cells, node_region, node_sets })
    }

    /// ψ of node `n`'s set `j` in region `r`.
    pub fn psi(&self, n: usize, j: usize, r: i32) -> f64 {
        if self.node_sets[n][j] == r {
            2.0
        } else {
            0.0
        }
    }

    /// The cell type of sub-cells in dimension `dim`.
    pub fn subcell_type(dim: usize) -> CellType {
        Cutting::subcell_type(dim)
    }

    /// Number of enrichment sets over all nodes.
    pub fn n_sets(&self) -> usize {
        self.node_sets.iter().map(|s| s.len()).sum()
    }
}
