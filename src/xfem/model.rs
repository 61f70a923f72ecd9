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

use crate::mesh::{CellType, Mesh};
use std::collections::BTreeMap;
use std::rc::Rc;

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

/// MODI_MODELE_XFEM's CONTACT: the interfaces are free surfaces ('SANS'),
/// or carry the mortar multipliers of a contact/cohesive law ('MORTAR').
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactKind {
    Sans,
    Mortar,
}

impl ContactKind {
    /// From Code_Aster's keyword value ('SANS', 'MORTAR').
    pub fn from_name(s: &str) -> Option<ContactKind> {
        match s {
            "SANS" => Some(ContactKind::Sans),
            "MORTAR" => Some(ContactKind::Mortar),
            _ => None,
        }
    }
    /// Code_Aster's name.
    pub fn name(self) -> &'static str {
        match self {
            ContactKind::Sans => "SANS",
            ContactKind::Mortar => "MORTAR",
        }
    }
}

/// What MODI_MODELE_XFEM adds to a model.
#[derive(Debug, Clone)]
pub struct XfemModel {
    /// The cracks (DEFI_FISS_XFEM concepts), model order.
    pub cracks: Vec<Rc<super::Crack>>,
    /// Names of the cracks, model order.
    pub crack_names: Vec<String>,
    /// Nodal normal level set of each crack.
    pub lsn: Vec<Vec<f64>>,
    /// Junction of each crack: (index of its master in the list, coef).
    pub masters: Vec<Option<(usize, f64)>>,
    /// Heaviside-enriched nodes of each crack (node status).
    pub enriched: Vec<Vec<bool>>,
    /// CONTACT of MODI_MODELE_XFEM.
    pub contact: ContactKind,
    /// The X-FEM cells.
    pub cells: BTreeMap<usize, XfemCell>,
    /// The X-FEM BOUNDARY cells (skin elements of the model with a
    /// Heaviside-enriched node): the cracks each one sees (model order) and
    /// its TOPOSE cutting. Kept apart from `cells`, which the solver
    /// integrates over: they only matter to POST_MAIL_XFEM's node names.
    pub boundary: BTreeMap<usize, (Vec<usize>, Cutting)>,
    /// Own region code of every node (`xlsjon` + `xcalc_code`).
    pub node_region: Vec<i32>,
    /// Enrichment sets of every node: the region codes, in set order.
    pub node_sets: Vec<Vec<i32>>,
    /// Enrichment sets removed by the stiffness criterion of `xstan2`
    /// ([`XfemModel::drop_stiffless_sets`]): (node, region code, criterion).
    pub dropped_sets: Vec<(usize, i32, f64)>,
}

/// The smallest stiffness share a Heaviside set may have (a floor on
/// Code_Aster's `xcodec` thresholds).
pub const MIN_SHARE: f64 = 1e-8;

/// Thresholds of `xstan2` (`xcodec`, PRETRAITEMENTS): per dimension, for
/// vertex nodes and for mid-side nodes; the criterion is compared with their
/// power `ndim`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetCriterion {
    pub vertex: f64,
    pub middle: f64,
    /// At least one crack of the model has a crack tip (`exi_fiss`): the
    /// quadratic correction of `xcrvol` applies.
    pub with_tips: bool,
}

impl SetCriterion {
    /// `xcodec`'s values for PRETRAITEMENTS='AUTO' | 'FORCE' | 'SANS' on a
    /// quadratic (`quadratic`) or linear model.
    pub fn new(pretraitements: &str, quadratic: bool, with_tips: bool) -> Option<SetCriterion> {
        let (vertex, middle) = match pretraitements {
            "AUTO" if quadratic && with_tips => (1e-6, 1e-4),
            "AUTO" if quadratic => (1e-6, 1e-5),
            "AUTO" | "FORCE" => (1e-8, 1e-5),
            "SANS" => (1e-4, 1e-4),
            _ => return None,
        };
        Some(SetCriterion { vertex, middle, with_tips })
    }
}

/// Vertex lists of the primary simplices of an uncut parent (`xdivte`, first
/// configuration), 0-based.
fn primary_simplices(t: CellType) -> Vec<Vec<usize>> {
    match t {
        CellType::Quad8 | CellType::Quad4 | CellType::Quad9 => vec![vec![0, 1, 3], vec![1, 2, 3]],
        CellType::Tria3 | CellType::Tria6 => vec![vec![0, 1, 2]],
        CellType::Tetra4 | CellType::Tetra10 => vec![vec![0, 1, 2, 3]],
        CellType::Hexa8 | CellType::Hexa20 | CellType::Hexa27 => vec![
            vec![5, 2, 1, 3],
            vec![3, 4, 0, 1],
            vec![1, 4, 5, 3],
            vec![4, 3, 7, 5],
            vec![2, 5, 6, 7],
            vec![2, 7, 3, 5],
        ],
        _ => Vec::new(),
    }
}

fn sign(v: f64) -> i32 {
    if v < 0.0 {
        -1
    } else {
        1
    }
}

/// Weights that give the mean of a cell's vertex values, to pass as `ff` to [`point_signs`] for the side
/// of a cell no crack cuts: its vertices decide it (a sub-simplex is cut where their signs differ), while
/// a curved level set may take the other sign at its centre (an interface bulging through a face, or
/// crossing an edge twice), which would put the cell on a side its neighbours' sub-cells are not on.
pub fn vertex_weights(t: crate::mesh::CellType) -> Vec<f64> {
    let nv = t.nvertices();
    (0..t.nnodes()).map(|k| if k < nv { 1.0 / nv as f64 } else { 0.0 }).collect()
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
    // A branch does not exist where its master does not, nor on the master's
    // side it does not reach — also when the cell cut it as a full interface
    // because its master is not among the cell's cracks (Code_Aster's
    // per-cell view; over the whole model the region is the same).
    if m > 1 {
        for _ in 0..m {
            for g in 0..m {
                if let Some((mm, c)) = masters[g] {
                    let sm = f64::from(s[mm]);
                    if s[mm] == 0 || (c > 0.0 && c * sm >= 0.0) || (c < 0.0 && c * sm > 0.0) {
                        s[g] = 0;
                    }
                }
            }
        }
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
        cracks: Vec<Rc<super::Crack>>,
        crack_names: Vec<String>,
        lsn: Vec<Vec<f64>>,
        masters: Vec<Option<(usize, f64)>>,
        enriched: Vec<Vec<bool>>,
        contact: ContactKind,
        cuttings: BTreeMap<usize, (Vec<usize>, Cutting)>,
        pretraitements: &str,
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
                // The cracks that do not cut the cell: the side of its vertices.
                let ff = vertex_weights(t);
                for sc in &cutting.subcells {
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
                let s = point_signs(&lsn, &masters, nodes, &vertex_weights(t), &[], &[]);
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
            // The sets in the order the regions are first met, cell after cell and sub-cell after sub-cell
            // (`te0120` lists a cell's regions so, `xcelno` appends them per node over the cells): the
            // order Code_Aster numbers H1*, H2*, … in.
            let mut others: Vec<(usize, i32)> = around[n]
                .iter()
                .filter(|(_, r)| *r != own_code)
                .map(|(s, r)| (s.iter().zip(&own).position(|(a, b)| a != b).unwrap_or(usize::MAX), *r))
                .collect();
            if others.len() == around[n].len() {
                // The node's own region is not in its support (it lies on an
                // interface): one region stands for the standard unknown, the
                // first to differ from the node's signs on the first crack.
                let first = others.iter().enumerate().min_by_key(|(_, o)| **o).map(|(k, _)| k).unwrap_or(0);
                others.remove(first);
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
        let mut xm = XfemModel {
            cracks,
            crack_names,
            lsn,
            masters,
            enriched,
            contact,
            cells,
            boundary: BTreeMap::new(),
            node_region,
            node_sets,
            dropped_sets: Vec::new(),
        };
        // MODI_MODELE_XFEM's PRETRAITEMENTS (default 'AUTO').
        let quadratic = model_cells.iter().any(|&c| mesh.cell_types[c].nnodes() > mesh.cell_types[c].nvertices());
        let with_tips = xm.cracks.iter().any(|k| k.discontinuity == "FISSURE");
        if let Some(crit) = SetCriterion::new(pretraitements, quadratic, with_tips) {
            xm.drop_stiffless_sets(mesh, model_cells, &crit);
        }
        Ok(xm)
    }

    /// The stiffness share of node `n`'s enrichment by region `r` over its
    /// support (`xcrvol`): Σ over the sub-cells of region `r` of
    /// |sub-cell|·(max |∂N_n/∂x|)² — the derivative taken at the sub-cell's
    /// barycentre, and on a quadratic parent also half-way between it and
    /// each vertex — divided by the same sum over every sub-cell of the
    /// support (uncut cells count their primary simplices). With crack tips
    /// on a quadratic parent each term is multiplied once more by the
    /// sub-cell's weighted measure, as `xcrvol` does (its `3/ndim` is an
    /// integer division).
    pub fn set_criterion(&self, mesh: &Mesh, support: &[usize], n: usize, r: i32, with_tips: bool) -> f64 {
        let dim = mesh.dim;
        let (mut vhea, mut vtot) = (0.0, 0.0);
        for &c in support {
            let t = mesh.cell_types[c];
            let nodes = &mesh.cells[c];
            let Some(loc) = nodes.iter().position(|&m| m == n) else { continue };
            let coords: Vec<[f64; 3]> = nodes.iter().map(|&m| mesh.coords[m]).collect();
            let quadratic = t.nnodes() > t.nvertices();
            // (vertices in reference coordinates, region) of each simplex.
            let simplices: Vec<(Vec<[f64; 3]>, i32)> = match self.cells.get(&c) {
                Some(xc) => xc
                    .cutting
                    .subcells
                    .iter()
                    .zip(&xc.regions)
                    .map(|(sc, &reg)| (sc.nodes[..=dim].iter().map(|&p| xc.cutting.points[p].xi).collect(), reg))
                    .collect(),
                None => {
                    let xi = crate::fem::reference::node_coords(t);
                    let reg = self.node_region[nodes[0]];
                    primary_simplices(t).iter().map(|v| (v.iter().map(|&k| xi[k]).collect(), reg)).collect()
                }
            };
            for (vx, reg) in simplices {
                let real: Vec<[f64; 3]> =
                    vx.iter().map(|xi| crate::fem::reference::map_to_real(t, &coords, xi)).collect();
                let d = |k: usize, j: usize| real[0][j] - real[k + 1][j];
                let mut vse = if dim == 2 {
                    (d(0, 0) * d(1, 1) - d(1, 0) * d(0, 1)).abs() / 2.0
                } else {
                    (d(0, 0) * (d(1, 1) * d(2, 2) - d(2, 1) * d(1, 2))
                        - d(1, 0) * (d(0, 1) * d(2, 2) - d(2, 1) * d(0, 2))
                        + d(2, 0) * (d(0, 1) * d(1, 2) - d(1, 1) * d(0, 2)))
                    .abs()
                        / 6.0
                };
                let mut bary = [0.0; 3];
                for p in &vx {
                    for (b, v) in bary.iter_mut().zip(p) {
                        *b += v / vx.len() as f64;
                    }
                }
                let mut pts = vec![bary];
                if quadratic {
                    pts.extend(vx.iter().map(|p| [0, 1, 2].map(|j| (bary[j] + p[j]) / 2.0)));
                }
                let mut deriv: f64 = 0.0;
                for xi in &pts {
                    if let Some((_, g, _)) = crate::fem::reference::real_gradients(t, &coords, xi) {
                        deriv = g[loc][..dim].iter().fold(deriv, |m, v| m.max(v.abs()));
                    }
                }
                vse *= deriv * deriv;
                if quadratic && with_tips {
                    vse *= vse;
                }
                if reg == r {
                    vhea += vse;
                }
                vtot += vse;
            }
        }
        if vtot > 0.0 {
            vhea / vtot
        } else {
            0.0
        }
    }

    /// Remove the enrichment sets whose stiffness share over the node's
    /// support ([`XfemModel::set_criterion`]) is below the threshold of
    /// `xstan2` (`crit.vertex^ndim` at a vertex, `crit.middle^ndim` at a
    /// mid-side node): Code_Aster sets the node status to 0 for such a set,
    /// "to avoid zero pivots and ill-conditioning". A set whose region is a
    /// sliver of the support adds a near-null direction to the system (its
    /// stiffness, and its share of the interface, vanish with the sliver)
    /// while it can only carry a displacement of the sliver's size.
    pub fn drop_stiffless_sets(&mut self, mesh: &Mesh, model_cells: &[usize], crit: &SetCriterion) {
        let nn = mesh.nnodes();
        let mut support: Vec<Vec<usize>> = vec![Vec::new(); nn];
        let mut middle = vec![false; nn];
        for &c in model_cells {
            let t = mesh.cell_types[c];
            for (k, &n) in mesh.cells[c].iter().enumerate() {
                support[n].push(c);
                if k >= t.nvertices() {
                    middle[n] = true;
                }
            }
        }
        let dim = mesh.dim as i32;
        for n in 0..nn {
            if self.node_sets[n].is_empty() {
                continue;
            }
            let threshold = if middle[n] { crit.middle.powi(dim) } else { crit.vertex.powi(dim) };
            // Our floor (docs/xfem-small-subcells.md): below a share of 1e-8
            // the set's unknown is fixed only to ε/share of the solution's
            // scale, and any inexact load on it (a facet rule on a curved
            // facet) makes it of the order of the solution.
            let threshold = threshold.max(MIN_SHARE);
            let sets = self.node_sets[n].clone();
            let mut kept = Vec::with_capacity(sets.len());
            for r in sets {
                let v = self.set_criterion(mesh, &support[n], n, r, crit.with_tips);
                if v < threshold {
                    self.dropped_sets.push((n, r, v));
                } else {
                    kept.push(r);
                }
            }
            self.node_sets[n] = kept;
        }
    }

    /// ψ of node `n`'s set `j` in region `r` (`xcalc_heav`): 2 in the set's region, 0 elsewhere, except
    /// for a node with a single set on the + side of the crack that separates it from the set's region,
    /// where it is −2 (`xcelno`'s flag for mono-Heaviside nodes: the jump u⁺ − u⁻ is then 2h on both
    /// sides). The sign matters only where a Heaviside unknown is given a value (DDL_IMPO H1PRE1, …).
    pub fn psi(&self, n: usize, j: usize, r: i32) -> f64 {
        if self.node_sets[n][j] != r {
            0.0
        } else if self.node_sets[n].len() == 1 && self.own_plus_side(n, r) {
            -2.0
        } else {
            2.0
        }
    }

    /// Is node `n` on the + side of the first crack on which its own region and region `r` differ?
    fn own_plus_side(&self, n: usize, r: i32) -> bool {
        // Region codes hold one base-4 digit h + 2 per crack, the first crack most significant.
        let nc = self.lsn.len() as u32;
        let digit = |code: i32, g: u32| (code / 4i32.pow(nc - 1 - g)) % 4;
        let own = self.node_region[n];
        (0..nc).find(|&g| digit(own, g) != digit(r, g)).is_some_and(|g| digit(own, g) == 3)
    }

    /// Number of enrichment sets over all nodes.
    pub fn n_sets(&self) -> usize {
        self.node_sets.iter().map(|s| s.len()).sum()
    }
}

/// Is the zero level set straight (flat in 3D) inside a cell? It is when the nodal values are an
/// affine function of the nodal coordinates: the isoparametric interpolation of the level set is then
/// that affine function on the whole cell, whatever the cell's shape. Always true for a simplex.
/// `dim` is the space dimension; the tolerance is relative to the values' spread.
pub fn straight_in_cell(coords: &[[f64; 3]], lsn: &[f64], dim: usize) -> bool {
    use nalgebra::{DMatrix, DVector};
    let n = coords.len().min(lsn.len());
    if n <= dim + 1 {
        return true;
    }
    // Least squares of lsn ≈ a·x + b over the nodes.
    let a = DMatrix::from_fn(n, dim + 1, |i, j| if j < dim { coords[i][j] } else { 1.0 });
    let b = DVector::from_iterator(n, lsn[..n].iter().copied());
    let Ok(fit) = a.clone().svd(true, true).solve(&b, 1e-14) else { return false };
    let scale = lsn[..n].iter().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    (a * fit - b).amax() <= 1e-9 * scale
}

#[cfg(test)]
mod straight_tests {
    use super::straight_in_cell;

    #[test]
    fn an_affine_level_set_is_straight_in_a_distorted_quad() {
        let q = [[0.0, 0.0, 0.0], [2.0, 0.1, 0.0], [2.5, 1.7, 0.0], [-0.2, 1.0, 0.0]];
        let affine: Vec<f64> = q.iter().map(|x| 0.3 * x[0] - 0.8 * x[1] + 0.1).collect();
        assert!(straight_in_cell(&q, &affine, 2));
        // A bilinear one (x·y) is not.
        let curved: Vec<f64> = q.iter().map(|x| x[0] * x[1] - 0.5).collect();
        assert!(!straight_in_cell(&q, &curved, 2));
        // Three nodes always are.
        assert!(straight_in_cell(&q[..3], &curved[..3], 2));
    }
}
