//! The visual mesh of POST_MAIL_XFEM (`xpomac` / `xpomax` / `xpoajm` /
//! `xpoajn`): classic cells of the model copied with their nodes and
//! names, every X-FEM parent replaced by its TOPOSE sub-cells, with one new
//! node per (point, Heaviside tuple) of the parent — nothing is shared
//! between parents. New nodes are named by a global counter written in base
//! 36 (`codlet`) behind the NX / NM / NP prefixes, new cells by a counter in
//! base 10 behind MX; the nodes on a crack form the group PREF_GROUP_CO.

use crate::mesh::{CellType, Mesh};
use crate::xfem::topose::{Cutting, PointId};
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;

/// Name prefixes (PREF_NOEUD_X, PREF_NOEUD_M, PREF_NOEUD_P, PREF_MAILLE_X,
/// PREF_GROUP_CO).
#[derive(Debug, Clone)]
pub struct Prefixes {
    pub node_x: String,
    pub node_m: String,
    pub node_p: String,
    pub cell_x: String,
    pub group_co: String,
}

impl Default for Prefixes {
    fn default() -> Self {
        Prefixes {
            node_x: "NX".into(),
            node_m: "NM".into(),
            node_p: "NP".into(),
            cell_x: "MX".into(),
            group_co: "NFISSU".into(),
        }
    }
}

/// Where a node of the visual mesh comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum NodeOrigin {
    /// A node of a classic cell: its index in the original mesh.
    Classic(usize),
    /// A point of an X-FEM parent's cutting, on the side given by `he`
    /// (one value per crack of the parent, as in [`crate::xfem::topose::SubCell::he`]).
    Xfem {
        /// The parent cell (index in the original mesh).
        parent: usize,
        /// The point of the parent's cutting.
        id: PointId,
        /// Reference coordinates in the parent.
        xi: [f64; 3],
        he: Vec<i32>,
    },
    /// A point of the cutting of an X-FEM BOUNDARY parent (a skin cell of
    /// lower dimension than the mesh). Its field is the one of the bulk cell
    /// of the model that holds the boundary cell: `bulk` is the lowest
    /// numbered cell of the model, of the mesh's dimension, whose nodes
    /// include all of the boundary cell's (it has the boundary cell's
    /// Heaviside node, so it is an X-FEM cell too), and `bulk_xi` the
    /// point's reference coordinates in it (the boundary cell's shape
    /// functions applied to the reference coordinates of its nodes in the
    /// bulk cell: exact for the linear types, whose face map is the
    /// restriction of the cell's). On a face shared by two bulk cells the
    /// field of a region is the same from both.
    Boundary {
        /// The boundary parent (index in the original mesh).
        parent: usize,
        /// The point of the boundary parent's cutting.
        id: PointId,
        /// Reference coordinates in the boundary parent.
        xi: [f64; 3],
        /// Heaviside values of the boundary sub-cell (one per crack of the
        /// boundary parent).
        he: Vec<i32>,
        /// The bulk cell evaluated.
        bulk: usize,
        /// Reference coordinates in `bulk`.
        bulk_xi: [f64; 3],
    },
}

/// What POST_MAIL_XFEM made for one X-FEM parent.
#[derive(Debug, Clone, PartialEq)]
pub struct ParentRange {
    /// The parent cell (index in the original mesh).
    pub cell: usize,
    /// Values of the node counter used by the parent (1-based, as in the
    /// names).
    pub node_counters: Range<usize>,
    /// Values of the cell counter used by the parent (1-based, MX names).
    pub cell_counters: Range<usize>,
}

/// The visual mesh and the origin of each of its nodes.
#[derive(Debug, Clone)]
pub struct VisualMesh {
    pub mesh: Mesh,
    /// Per node of `mesh`.
    pub origins: Vec<NodeOrigin>,
    /// X-FEM parents in processing order.
    pub parents: Vec<ParentRange>,
}

/// A positive integer in base 36, digits 0-9A-Z, most significant first
/// (`codlet` with 'G').
pub fn base36(mut n: usize) -> String {
    const DIGITS: &[u8; 36] = b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    if n == 0 {
        return "0".into();
    }
    let mut out = Vec::new();
    while n > 0 {
        out.push(DIGITS[n % 36]);
        n /= 36;
    }
    out.reverse();
    String::from_utf8(out).unwrap_or_default()
}

/// Distance below which a mid-point or centre node counts as on a crack
/// (`xpoajn`, `crilsn`).
const CRILSN: f64 = 1e-4;

/// Prefix of a new node (`xpoajn`): on a crack or not, and on which side of
/// the nearest crack active on the sub-cell. Returns (prefix, on a crack).
fn node_prefix<'a>(id: PointId, lsn: &[f64], he: &[i32], p: &'a Prefixes) -> (&'a str, bool) {
    let on = match id {
        PointId::Node(_) => lsn.contains(&0.0),
        PointId::Intersection(_) => true,
        PointId::Mid(_) | PointId::Centre(_) => lsn.iter().any(|v| v.abs() < CRILSN),
    };
    if !on {
        return (&p.node_x, false);
    }
    let mut best: Option<usize> = None;
    let mut min = f64::MAX;
    for (k, (&v, &h)) in lsn.iter().zip(he).enumerate() {
        if v.abs() < min && h != 0 {
            min = v.abs();
            best = Some(k);
        }
    }
    match best {
        Some(k) if he[k] == -1 => (&p.node_m, true),
        _ => (&p.node_p, true),
    }
}

/// Build the visual mesh of POST_MAIL_XFEM. `model_cells`: the cells of the
/// model (any order; POI1 cells are ignored); `cuttings`: the TOPOSE
/// cutting of every X-FEM parent (every cell of the model with sub-cells),
/// the boundary ones (SEG2 / TRIA3 / QUAD4 skin cells, SEG2 / TRIA3
/// sub-cells) included: all are traversed in one ascending order, as
/// `xpomax` does, and a boundary parent's nodes get
/// [`NodeOrigin::Boundary`].
/// Classic cells are the other cells of the model.
///
/// Cell groups: as `xpodim`/`xpoco1`/`xpoajm`, every cell group of the
/// original mesh holding at least one processed cell is kept, with its
/// classic cells (ascending) then the sub-cells of its X-FEM parents in
/// creation order. Original node groups are not kept: the only node group
/// is PREF_GROUP_CO, in creation order (when not empty).
pub fn visual_mesh(
    mesh: &Mesh,
    model_cells: &[usize],
    cuttings: &BTreeMap<usize, Cutting>,
    prefixes: &Prefixes,
) -> Result<VisualMesh, String> {
    let mut cells: Vec<usize> =
        model_cells.iter().copied().filter(|&c| c < mesh.ncells() && mesh.cell_types[c] != CellType::Poi1).collect();
    if let Some(&c) = model_cells.iter().find(|&&c| c >= mesh.ncells()) {
        return Err(format!("POST_MAIL_XFEM: cell index {c} is not in the mesh"));
    }
    cells.sort_unstable();
    cells.dedup();
    if let Some(c) = cuttings.keys().find(|c| cells.binary_search(c).is_err()) {
        return Err(format!("POST_MAIL_XFEM: the X-FEM parent {} is not a cell of the model", mesh.cell_names[*c]));
    }
    let classic: Vec<usize> = cells.iter().copied().filter(|c| !cuttings.contains_key(c)).collect();

    let mut out = Mesh { dim: mesh.dim, named_nodes: true, ..Default::default() };
    let mut origins = Vec::new();
    // Classic nodes, ascending, with their names.
    let mut new_of_old: HashMap<usize, usize> = HashMap::new();
    let mut classic_nodes: Vec<usize> = classic.iter().flat_map(|&c| mesh.cells[c].iter().copied()).collect();
    classic_nodes.sort_unstable();
    classic_nodes.dedup();
    for &n in &classic_nodes {
        new_of_old.insert(n, out.coords.len());
        out.coords.push(mesh.coords[n]);
        out.node_names.push(mesh.node_names[n].clone());
        origins.push(NodeOrigin::Classic(n));
    }
    // Cell groups of the original mesh, by cell.
    let mut groups_of: HashMap<usize, Vec<&str>> = HashMap::new();
    for (g, members) in &mesh.cell_groups {
        for &c in members {
            groups_of.entry(c).or_default().push(g.as_str());
        }
    }
    let add_to_groups = |out: &mut Mesh, old: usize, new: usize| {
        if let Some(gs) = groups_of.get(&old) {
            for g in gs {
                out.cell_groups.entry((*g).to_string()).or_default().push(new);
            }
        }
    };
    for &c in &classic {
        let idx = out.cells.len();
        out.cells.push(mesh.cells[c].iter().map(|n| new_of_old[n]).collect());
        out.cell_types.push(mesh.cell_types[c]);
        out.cell_names.push(mesh.cell_names[c].clone());
        add_to_groups(&mut out, c, idx);
    }

    // Cells of the model of the mesh's dimension, by node (for the bulk
    // cell of a boundary parent).
    let mut bulk_of_node: HashMap<usize, Vec<usize>> = HashMap::new();
    for &c in &cells {
        if mesh.cell_types[c].dim() == mesh.dim {
            for &n in &mesh.cells[c] {
                bulk_of_node.entry(n).or_default().push(c);
            }
        }
    }

    let mut on_crack: Vec<usize> = Vec::new();
    let mut parents = Vec::new();
    let (mut inntot, mut inmtot) = (0usize, 0usize);
    for (&parent, cut) in cuttings {
        let dim = mesh.cell_types[parent].dim();
        // A boundary parent: the bulk cell holding it and the reference
        // coordinates of its nodes there.
        let bulk: Option<(usize, Vec<[f64; 3]>)> = if dim < mesh.dim {
            let pn = &mesh.cells[parent];
            let b = bulk_of_node
                .get(&pn[0])
                .and_then(|cs| cs.iter().copied().filter(|&c| pn.iter().all(|n| mesh.cells[c].contains(n))).min())
                .ok_or_else(|| {
                    format!(
                        "POST_MAIL_XFEM: the X-FEM boundary cell {} is on no cell of the model of dimension {}",
                        mesh.cell_names[parent], mesh.dim
                    )
                })?;
            let bt = mesh.cell_types[b];
            let bx = crate::fem::reference::node_coords(bt);
            let pos = pn
                .iter()
                .map(|n| mesh.cells[b].iter().position(|m| m == n).map(|k| bx[k]))
                .collect::<Option<Vec<_>>>()
                .ok_or("POST_MAIL_XFEM: internal error, boundary node not in its bulk cell")?;
            Some((b, pos))
        } else {
            None
        };
        let sub_type = if matches!(
            mesh.cell_types[parent],
            CellType::Seg2 | CellType::Tria3 | CellType::Quad4 | CellType::Tetra4 | CellType::Penta6 | CellType::Hexa8
        ) {
            crate::xfem::topose_linear::subcell_type(dim)
        } else {
            Cutting::subcell_type(dim)
        };
        let (n0, m0) = (inntot, inmtot);
        let mut local: HashMap<(usize, Vec<i32>), usize> = HashMap::new();
        for s in &cut.subcells {
            if s.nodes.len() != sub_type.nnodes() {
                return Err(format!(
                    "POST_MAIL_XFEM: a sub-cell of {} has {} nodes, {} expected",
                    mesh.cell_names[parent],
                    s.nodes.len(),
                    sub_type.nnodes()
                ));
            }
            let mut conn = Vec::with_capacity(s.nodes.len());
            for &pi in &s.nodes {
                let key = (pi, s.he.clone());
                if let Some(&n) = local.get(&key) {
                    conn.push(n);
                    continue;
                }
                let p = cut.points.get(pi).ok_or("POST_MAIL_XFEM: sub-cell point out of range")?;
                if p.lsn.len() != s.he.len() {
                    return Err("POST_MAIL_XFEM: level sets and Heaviside values disagree in number".into());
                }
                let (prefix, lpint) = node_prefix(p.id, &p.lsn, &s.he, prefixes);
                inntot += 1;
                let n = out.coords.len();
                let x = match p.id.node() {
                    Some(k) => {
                        let old = *mesh.cells[parent].get(k).ok_or("POST_MAIL_XFEM: parent node id out of range")?;
                        mesh.coords[old]
                    }
                    None => p.x,
                };
                out.coords.push(x);
                out.node_names.push(format!("{prefix}{}", base36(inntot)));
                origins.push(match &bulk {
                    None => NodeOrigin::Xfem { parent, id: p.id, xi: p.xi, he: s.he.clone() },
                    Some((b, pos)) => {
                        let ff = crate::fem::reference::shape(mesh.cell_types[parent], &p.xi);
                        let mut bulk_xi = [0.0; 3];
                        for (f, x) in ff.iter().zip(pos) {
                            for j in 0..3 {
                                bulk_xi[j] += f * x[j];
                            }
                        }
                        NodeOrigin::Boundary { parent, id: p.id, xi: p.xi, he: s.he.clone(), bulk: *b, bulk_xi }
                    }
                });
                if lpint {
                    on_crack.push(n);
                }
                local.insert(key, n);
                conn.push(n);
            }
            inmtot += 1;
            let idx = out.cells.len();
            out.cells.push(conn);
            out.cell_types.push(sub_type);
            out.cell_names.push(format!("{}{inmtot}", prefixes.cell_x));
            add_to_groups(&mut out, parent, idx);
        }
        parents.push(ParentRange {
            cell: parent,
            node_counters: n0 + 1..inntot + 1,
            cell_counters: m0 + 1..inmtot + 1,
        });
    }
    if !on_crack.is_empty() {
        out.node_groups.insert(prefixes.group_co.clone(), on_crack);
    }
    Ok(VisualMesh { mesh: out, origins, parents })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xfem::topose::{topose, CrackInCell};

    #[test]
    fn base36_as_codlet() {
        assert_eq!(base36(217), "61");
        assert_eq!(base36(1301), "105");
        assert_eq!(base36(35), "Z");
        assert_eq!(base36(36), "10");
        assert_eq!(base36(428), "BW");
    }

    /// Two QUAD8 side by side; the left one cut by x = 0.5.
    #[test]
    fn one_cut_parent_and_one_classic_cell() {
        let mut m = Mesh { dim: 2, named_nodes: true, ..Default::default() };
        // Nodes of [0,2]×[0,1] on a 5×3 grid (step 0.5).
        for j in 0..3 {
            for i in 0..5 {
                m.coords.push([0.5 * i as f64, 0.5 * j as f64, 0.0]);
                m.node_names.push(format!("N{}", m.coords.len()));
            }
        }
        let g = |i: usize, j: usize| j * 5 + i;
        for c in 0..2 {
            let i0 = 2 * c;
            m.cells.push(vec![
                g(i0, 0),
                g(i0 + 2, 0),
                g(i0 + 2, 2),
                g(i0, 2),
                g(i0 + 1, 0),
                g(i0 + 2, 1),
                g(i0 + 1, 2),
                g(i0, 1),
            ]);
            m.cell_types.push(CellType::Quad8);
            m.cell_names.push(format!("M{}", c + 1));
        }
        m.cell_groups.insert("ALL".into(), vec![0, 1]);
        let coords: Vec<[f64; 3]> = m.cells[0].iter().map(|&n| m.coords[n]).collect();
        let lsn: Vec<f64> = coords.iter().map(|p| p[0] - 0.3).collect();
        let cut = topose(CellType::Quad8, &coords, &[CrackInCell { lsn, master: None }]).unwrap();
        let nsub = cut.subcells.len();
        let cuttings: BTreeMap<usize, Cutting> = [(0, cut)].into_iter().collect();
        let v = visual_mesh(&m, &[0, 1], &cuttings, &Prefixes::default()).unwrap();
        // The classic cell keeps its 8 nodes and its name.
        assert_eq!(v.mesh.cell_names[0], "M2");
        assert_eq!(v.mesh.node_names[..8].len(), 8);
        assert!(v.origins[..8].iter().all(|o| matches!(o, NodeOrigin::Classic(_))));
        assert_eq!(v.mesh.ncells(), 1 + nsub);
        assert_eq!(v.mesh.cell_names[1], "MX1");
        assert_eq!(v.mesh.cell_groups["ALL"].len(), 1 + nsub);
        let nfissu = &v.mesh.node_groups["NFISSU"];
        // Every node on the crack is an NM or NP node at x = 0.3.
        for &n in nfissu {
            assert!((v.mesh.coords[n][0] - 0.3).abs() < 1e-12);
            assert!(v.mesh.node_names[n].starts_with("NM") || v.mesh.node_names[n].starts_with("NP"));
        }
        // Both lips: as many NM as NP.
        let nm = nfissu.iter().filter(|&&n| v.mesh.node_names[n].starts_with("NM")).count();
        assert_eq!(2 * nm, nfissu.len());
        assert_eq!(v.parents[0].node_counters.start, 1);
        assert_eq!(v.mesh.nnodes(), 8 + v.parents[0].node_counters.len());
    }
}
