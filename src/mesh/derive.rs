//! Meshes derived from a mesh by adding cells or nodes, or by keeping a part of it, with Code_Aster
//! 2025's numbering (CREA_MAILLAGE's `op0167` and `rdtmai`).
//!
//! - [`copy_cells`] (CREA_MAILLE): the copies come after the cells of the mesh, occurrence after
//!   occurrence, each in increasing number of the copied cell; each occurrence's copies make a
//!   group of cells.
//! - [`point_cells`] (CREA_POI1): one POI1 cell per node selected by any occurrence, in increasing
//!   node number, after the cells of the mesh; an occurrence that names a group gets the POI1 cells
//!   of its own nodes.
//! - [`centre_nodes`] (MODI_MAILLE QUAD8_9): each QUAD8 becomes a QUAD9 whose centre node comes
//!   after the nodes of the mesh, in the order the cells are given.
//! - [`restrict`] (RESTREINT): the given cells, renumbered in increasing order, and their nodes
//!   numbered in order of first appearance (cell by cell, in local order), then the nodes of the
//!   extra node list.
//!
//! New cells and nodes are named `M` / `N` + number, as Code_Aster 2025 shows them. Groups are
//! copied unchanged unless said otherwise.

use super::{CellType, Mesh};

/// Append copies of cells: one `(group name, cells)` per occurrence (see the module documentation).
pub fn copy_cells(mesh: &Mesh, occurrences: &[(String, Vec<usize>)]) -> Mesh {
    let mut out = mesh.clone();
    for (group, cells) in occurrences {
        let mut members = Vec::with_capacity(cells.len());
        for &c in cells {
            members.push(out.cells.len());
            out.cells.push(mesh.cells[c].clone());
            out.cell_types.push(mesh.cell_types[c]);
            out.cell_names.push(format!("M{}", out.cells.len()));
        }
        out.cell_groups.insert(group.clone(), members);
    }
    out
}

/// Append POI1 cells on nodes: one `(optional group name, nodes)` per occurrence (see the module
/// documentation).
pub fn point_cells(mesh: &Mesh, occurrences: &[(Option<String>, Vec<usize>)]) -> Mesh {
    let mut out = mesh.clone();
    let mut cell_of = vec![usize::MAX; mesh.nnodes()];
    for (_, nodes) in occurrences {
        nodes.iter().for_each(|&n| cell_of[n] = 0);
    }
    for (n, c) in cell_of.iter_mut().enumerate() {
        if *c == 0 {
            *c = out.cells.len();
            out.cells.push(vec![n]);
            out.cell_types.push(CellType::Poi1);
            out.cell_names.push(format!("M{}", out.cells.len()));
        }
    }
    for (group, nodes) in occurrences {
        if let Some(g) = group {
            out.cell_groups.insert(g.clone(), nodes.iter().map(|&n| cell_of[n]).collect());
        }
    }
    out
}

/// Turn QUAD8 cells into QUAD9 cells with a centre node each (see the module documentation); a cell
/// listed twice gets two centres, the second one used, as in Code_Aster.
pub fn centre_nodes(mesh: &Mesh, quad8: &[usize]) -> Mesh {
    let mut out = mesh.clone();
    for &c in quad8 {
        debug_assert_eq!(mesh.cell_types[c], CellType::Quad8);
        let nodes = &mesh.cells[c];
        // QUAD8's shape functions at the centre: -1/4 on the vertices, 1/2 on the middle nodes,
        // summed in this order as `cmmoma` does.
        let mut p = [0.0; 3];
        for (k, pk) in p.iter_mut().enumerate() {
            let mut w = 0.0;
            for (i, &n) in nodes.iter().enumerate() {
                w += mesh.coords[n][k] * if i < 4 { -1.0 / 4.0 } else { 1.0 / 2.0 };
            }
            *pk = w;
        }
        out.coords.push(p);
        out.node_names.push(format!("N{}", out.coords.len()));
        let mut cell = nodes.clone();
        cell.truncate(8);
        cell.push(out.coords.len() - 1);
        out.cells[c] = cell;
        out.cell_types[c] = CellType::Quad9;
    }
    out
}

/// Which groups a restricted mesh keeps.
#[derive(Debug, Clone)]
pub enum Groups {
    /// Every group with a member in the restricted mesh, reduced to those members.
    All,
    /// These groups, reduced to their members in the restricted mesh (dropped when none is).
    These(Vec<String>),
}

/// A mesh made of `cells` (increasing, without repeats) and their nodes, plus `extra_nodes`
/// (increasing); the groups kept are chosen by `cell_groups` and `node_groups` (see the module
/// documentation). Names follow the new numbers unless the mesh carried its own.
pub fn restrict(
    mesh: &Mesh,
    cells: &[usize],
    extra_nodes: &[usize],
    cell_groups: &Groups,
    node_groups: &Groups,
) -> Mesh {
    let mut new_node = vec![usize::MAX; mesh.nnodes()];
    let mut old_nodes = Vec::new();
    let mut take = |n: usize| {
        if new_node[n] == usize::MAX {
            new_node[n] = old_nodes.len();
            old_nodes.push(n);
        }
    };
    for &c in cells {
        mesh.cells[c].iter().for_each(|&n| take(n));
    }
    extra_nodes.iter().for_each(|&n| take(n));
    let mut new_cell = vec![usize::MAX; mesh.ncells()];
    for (i, &c) in cells.iter().enumerate() {
        new_cell[c] = i;
    }
    let cell_default = mesh.cell_names.iter().enumerate().all(|(i, n)| *n == format!("M{}", i + 1));
    let out_cell_names =
        cells
            .iter()
            .enumerate()
            .map(|(i, &c)| if cell_default { format!("M{}", i + 1) } else { mesh.cell_names[c].clone() });
    let out_node_names = old_nodes.iter().enumerate().map(|(i, &n)| {
        if mesh.named_nodes {
            mesh.node_names[n].clone()
        } else {
            format!("N{}", i + 1)
        }
    });
    let reduce = |groups: &std::collections::BTreeMap<String, Vec<usize>>, new: &[usize], which: &Groups| {
        groups
            .iter()
            .filter(|(g, _)| match which {
                Groups::All => true,
                Groups::These(names) => names.contains(g),
            })
            .filter_map(|(g, members)| {
                let kept: Vec<usize> = members.iter().map(|&m| new[m]).filter(|&m| m != usize::MAX).collect();
                (!kept.is_empty()).then(|| (g.clone(), kept))
            })
            .collect()
    };
    Mesh {
        dim: mesh.dim,
        coords: old_nodes.iter().map(|&n| mesh.coords[n]).collect(),
        node_names: out_node_names.collect(),
        cell_types: cells.iter().map(|&c| mesh.cell_types[c]).collect(),
        cells: cells.iter().map(|&c| mesh.cells[c].iter().map(|&n| new_node[n]).collect()).collect(),
        cell_names: out_cell_names.collect(),
        node_groups: reduce(&mesh.node_groups, &new_node, node_groups),
        cell_groups: reduce(&mesh.cell_groups, &new_cell, cell_groups),
        named_nodes: mesh.named_nodes,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::box_mesh;

    /// 2 x 1 QUAD8 cells with their SEG3 boundaries (cells 1..6 SEG3, 7..8 QUAD8).
    fn quad8() -> Mesh {
        box_mesh(CellType::Quad8, &[2, 1], &[2.0, 1.0]).unwrap()
    }

    #[test]
    fn copies_follow_the_cells_and_make_one_group_per_occurrence() {
        let m = quad8();
        let nc = m.ncells();
        let out = copy_cells(&m, &[("A".into(), vec![6, 7]), ("B".into(), vec![0])]);
        assert_eq!(out.ncells(), nc + 3);
        assert_eq!(out.cell_groups["A"], vec![nc, nc + 1]);
        assert_eq!(out.cell_groups["B"], vec![nc + 2]);
        assert_eq!(out.cells[nc + 1], m.cells[7]);
        assert_eq!(out.cell_types[nc + 2], m.cell_types[0]);
        assert_eq!(out.cell_names[nc..], ["M9", "M10", "M11"]);
        assert_eq!(out.nnodes(), m.nnodes());
    }

    #[test]
    fn point_cells_are_numbered_by_node_and_grouped_by_occurrence() {
        let m = quad8();
        let nc = m.ncells();
        // Nodes 5 and 2 in one group, 2 and 9 in an unnamed occurrence: POI1 on 2, 5, 9.
        let out = point_cells(&m, &[(Some("P".into()), vec![2, 5]), (None, vec![2, 9])]);
        assert_eq!(out.ncells(), nc + 3);
        assert_eq!(out.cells[nc..], [vec![2], vec![5], vec![9]]);
        assert!(out.cell_types[nc..].iter().all(|&t| t == CellType::Poi1));
        assert_eq!(out.cell_groups["P"], vec![nc, nc + 1]);
        assert_eq!(out.cell_groups.len(), m.cell_groups.len() + 1);
    }

    #[test]
    fn quad8_to_quad9_adds_the_centre_at_the_shape_function_point() {
        let mut m = quad8();
        // Curve the top edge of the first cell: its centre moves by half of the bulge.
        let top = m.cells[6][6];
        m.coords[top][1] += 0.2;
        let out = centre_nodes(&m, &[7, 6]);
        let nn = m.nnodes();
        assert_eq!(out.nnodes(), nn + 2);
        assert_eq!(out.cells[7][8], nn);
        assert_eq!(out.cells[6][8], nn + 1);
        assert_eq!(out.cell_types[6], CellType::Quad9);
        assert_eq!(out.node_names[nn + 1], format!("N{}", nn + 2));
        let c = out.coords[nn + 1];
        assert!((c[0] - 0.5).abs() < 1e-15 && (c[1] - 0.6).abs() < 1e-15, "{c:?}");
    }

    #[test]
    fn restriction_numbers_nodes_by_first_appearance() {
        let m = quad8();
        // The second QUAD8 alone, plus node 0: its nodes in local order, then node 0.
        let out = restrict(&m, &[7], &[0], &Groups::All, &Groups::These(vec!["GAUCHE".into(), "DROITE".into()]));
        assert_eq!(out.ncells(), 1);
        assert_eq!(out.cells[0], (0..8).collect::<Vec<_>>());
        for (i, &n) in m.cells[7].iter().enumerate() {
            assert_eq!(out.coords[i], m.coords[n]);
        }
        assert_eq!(out.coords[8], m.coords[0]);
        assert_eq!(out.cell_names, ["M1"]);
        // SURFACE keeps one cell; DROITE's SEG3 is gone but the node group stays, reduced; GAUCHE keeps node 0.
        assert_eq!(out.cell_groups.keys().collect::<Vec<_>>(), ["SURFACE"]);
        assert_eq!(out.cell_groups["SURFACE"], vec![0]);
        assert_eq!(out.node_groups.keys().collect::<Vec<_>>(), ["DROITE", "GAUCHE"]);
        assert_eq!(out.node_groups["GAUCHE"], vec![8]);
        assert_eq!(out.node_groups["DROITE"].len(), 3);
    }
}
