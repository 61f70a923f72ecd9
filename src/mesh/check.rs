//! LIRE_MAILLAGE's VERI_MAIL: the checks Code_Aster makes on every mesh it reads (`chckma`).
//!
//! Alarms: orphan nodes (in no cell), nodes of more than 200 cells, cells on the same nodes as an
//! earlier cell, POI1 cells on a node of other cells, cells whose shortest distance between two of
//! their nodes is less than APLAT times the longest. Errors (the mesh is refused): a cell whose
//! first node comes twice in it, and, in meshes with quadratic cells, two edges with the same
//! vertices but different middle nodes, or two faces with the same vertices but different other
//! nodes.

use super::convert::edges;
use super::{CellType, Mesh};
use std::collections::HashMap;

/// What the checks found, as lines for the message file.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Report {
    pub alarms: Vec<String>,
    pub errors: Vec<String>,
}

/// Run the checks with the flatness threshold `aplat`.
pub fn check(mesh: &Mesh, aplat: f64) -> Report {
    let mut r = Report::default();
    if mesh.nnodes() == 0 {
        return r;
    }
    // Cells of each node, every occurrence (a cell repeating a node is listed twice).
    let mut of_node: Vec<Vec<usize>> = vec![Vec::new(); mesh.nnodes()];
    for (c, nodes) in mesh.cells.iter().enumerate() {
        for &n in nodes {
            of_node[n].push(c);
        }
    }
    let orphans: Vec<&str> =
        (0..mesh.nnodes()).filter(|&n| of_node[n].is_empty()).map(|n| mesh.node_names[n].as_str()).collect();
    if !orphans.is_empty() {
        r.alarms.push(format!("{} node(s) belong to no cell (orphan nodes): {}", orphans.len(), list(&orphans)));
    }
    let crowded: Vec<&str> =
        (0..mesh.nnodes()).filter(|&n| of_node[n].len() > 200).map(|n| mesh.node_names[n].as_str()).collect();
    if !crowded.is_empty() {
        r.alarms.push(format!(
            "{} node(s) connect more than 200 cells (their cells are not checked for doubles): {}",
            crowded.len(),
            list(&crowded)
        ));
    }
    // Doubles, repeated first nodes, POI1 inside other cells.
    let mut doubles = Vec::new();
    let mut poi1_inside = Vec::new();
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let Some(&first) = nodes.first() else { continue };
        let around = &of_node[first];
        if around.len() > 200 {
            continue;
        }
        if around.iter().filter(|&&d| d == c).count() != 1 {
            r.errors.push(format!(
                "cell {} ({}) is degenerate: a node comes twice in its connectivity",
                mesh.cell_names[c],
                mesh.cell_types[c].name()
            ));
        }
        if nodes.len() > 1 {
            for &d in around.iter().filter(|&&d| d < c) {
                if mesh.cells[d].len() == nodes.len() && mesh.cells[d].iter().all(|n| nodes.contains(n)) {
                    doubles.push(format!(
                        "{} and {} ({})",
                        mesh.cell_names[c],
                        mesh.cell_names[d],
                        mesh.cell_types[c].name()
                    ));
                }
            }
        } else if around.iter().any(|&d| d != c) {
            poi1_inside.push(mesh.cell_names[c].as_str());
        }
    }
    if !doubles.is_empty() {
        r.alarms.push(format!(
            "{} pair(s) of cells have the same nodes (double cells): {}",
            doubles.len(),
            list(&doubles)
        ));
    }
    if !poi1_inside.is_empty() {
        r.alarms.push(format!(
            "{} POI1 cell(s) lie on a node of another cell: {}",
            poi1_inside.len(),
            list(&poi1_inside)
        ));
    }
    // Flat cells.
    let mut flat = Vec::new();
    for (c, nodes) in mesh.cells.iter().enumerate() {
        if nodes.len() < 2 {
            continue;
        }
        let (mut dm, mut dp) = (f64::MAX, 0.0f64);
        for (i, &a) in nodes.iter().enumerate() {
            for &b in &nodes[i + 1..] {
                let (xa, xb) = (mesh.coords[a], mesh.coords[b]);
                let d = (0..3).map(|k| (xa[k] - xb[k]).powi(2)).sum::<f64>();
                dm = dm.min(d);
                dp = dp.max(d);
            }
        }
        if dp > 0.0 {
            let ratio = (dm / dp).sqrt();
            if ratio < aplat {
                flat.push(format!("{} ({}, ratio {ratio:.3e})", mesh.cell_names[c], mesh.cell_types[c].name()));
            }
        }
    }
    if !flat.is_empty() {
        r.alarms.push(format!(
            "{} cell(s) have nodes closer than APLAT={aplat:e} times their largest size (degenerate cells): {}",
            flat.len(),
            list(&flat)
        ));
    }
    if mesh.cell_types.iter().any(|t| t.nnodes() > t.nvertices() && *t != CellType::Poi1) {
        quadratic_consistency(mesh, &mut r);
    }
    r
}

/// Edges (two vertices) and faces (their vertices) met twice with different other nodes.
fn quadratic_consistency(mesh: &Mesh, r: &mut Report) {
    let mut edge_mid: HashMap<(usize, usize), usize> = HashMap::new();
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let t = mesh.cell_types[c];
        if t == CellType::Seg4 || t.nnodes() == t.nvertices() {
            continue;
        }
        let nv = t.nvertices();
        for (i, &(a, b)) in edges(t).iter().enumerate() {
            let Some(&mid) = nodes.get(nv + i) else { continue };
            let key = (nodes[a].min(nodes[b]), nodes[a].max(nodes[b]));
            match edge_mid.get(&key) {
                Some(&m) if m != mid => r.errors.push(format!(
                    "two edges have the same vertices ({}, {}) but different middle nodes ({} and {})",
                    mesh.node_names[key.0], mesh.node_names[key.1], mesh.node_names[m], mesh.node_names[mid]
                )),
                Some(_) => {}
                None => {
                    edge_mid.insert(key, mid);
                }
            }
        }
    }
    // Faces with a centre node: QUAD9 cells and the quadrangular faces of HEXA27 / PENTA18 are
    // compared through their centre only when the cells are surface cells (volume faces share
    // their centre by construction of the connectivity).
    let mut face_centre: HashMap<Vec<usize>, usize> = HashMap::new();
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let t = mesh.cell_types[c];
        let centre = match t {
            CellType::Quad9 => 8,
            CellType::Tria7 => 6,
            _ => continue,
        };
        let mut key: Vec<usize> = nodes[..t.nvertices()].to_vec();
        key.sort_unstable();
        let mid = nodes[centre];
        match face_centre.get(&key) {
            Some(&m) if m != mid => {
                let names: Vec<&str> = key.iter().map(|&n| mesh.node_names[n].as_str()).collect();
                r.errors.push(format!(
                    "two faces have the same vertices ({}) but different other nodes ({} and {})",
                    names.join(", "),
                    mesh.node_names[m],
                    mesh.node_names[mid]
                ));
            }
            Some(_) => {}
            None => {
                face_centre.insert(key, mid);
            }
        }
    }
}

/// The first items of a list, and how many more.
fn list<S: AsRef<str>>(items: &[S]) -> String {
    const SHOWN: usize = 10;
    let mut s = items.iter().take(SHOWN).map(|i| i.as_ref()).collect::<Vec<_>>().join(", ");
    if items.len() > SHOWN {
        s.push_str(&format!(", ... ({} more)", items.len() - SHOWN));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(coords: Vec<[f64; 3]>, cells: Vec<(CellType, Vec<usize>)>) -> Mesh {
        let n = coords.len();
        Mesh {
            dim: 2,
            node_names: (1..=n).map(|i| format!("N{i}")).collect(),
            coords,
            cell_names: (1..=cells.len()).map(|i| format!("M{i}")).collect(),
            cell_types: cells.iter().map(|c| c.0).collect(),
            cells: cells.into_iter().map(|c| c.1).collect(),
            ..Default::default()
        }
    }

    #[test]
    fn finds_orphans_doubles_flat_and_degenerate_cells() {
        let sq =
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 0.0], [1e-5, 0.0, 0.0]];
        let m = mesh(
            sq,
            vec![
                (CellType::Quad4, vec![0, 1, 2, 3]),
                (CellType::Quad4, vec![1, 2, 3, 0]),
                (CellType::Poi1, vec![2]),
                (CellType::Tria3, vec![0, 5, 3]),
            ],
        );
        let r = check(&m, 1e-3);
        assert!(r.errors.is_empty(), "{r:?}");
        assert_eq!(r.alarms.len(), 4, "{r:?}");
        assert_eq!(r.alarms[0], "1 node(s) belong to no cell (orphan nodes): N5");
        assert_eq!(r.alarms[1], "1 pair(s) of cells have the same nodes (double cells): M2 and M1 (QUAD4)");
        assert_eq!(r.alarms[2], "1 POI1 cell(s) lie on a node of another cell: M3");
        assert!(r.alarms[3].starts_with("1 cell(s) have nodes closer than APLAT=1e-3"), "{}", r.alarms[3]);
        assert!(r.alarms[3].contains("M4 (TRIA3, ratio 1.000e-5)"), "{}", r.alarms[3]);
        let bad = mesh(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![(CellType::Tria3, vec![0, 1, 0])]);
        assert_eq!(check(&bad, 1e-3).errors.len(), 1);
    }

    #[test]
    fn quadratic_edges_must_share_their_middle_node() {
        let x = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
            [0.5, 0.01, 0.0],
        ];
        let good = mesh(x.clone(), vec![(CellType::Tria6, vec![0, 1, 2, 3, 4, 5]), (CellType::Seg3, vec![0, 1, 3])]);
        assert!(check(&good, 1e-3).errors.is_empty());
        let bad = mesh(x, vec![(CellType::Tria6, vec![0, 1, 2, 3, 4, 5]), (CellType::Seg3, vec![1, 0, 6])]);
        let r = check(&bad, 1e-3);
        assert_eq!(r.errors, ["two edges have the same vertices (N1, N2) but different middle nodes (N4 and N7)"]);
    }
}
