//! Changes of cell degree, with Code_Aster's numbering of the nodes they create or remove.
//!
//! [`line_to_quad`] and [`quad_to_line`] follow Code_Aster 2025's `crea_maillage_module` as
//! CREA_MAILLAGE's LINE_QUAD (`cmlqlq`) and QUAD_LINE (`cmqlql`) drive it; [`line_to_quad_2020`]
//! follows the 2020 operator (`cmlqna` / `cmlqnd` / `cmlqma`). The facts that fix the numbering:
//!
//! - 2025 visits every cell of the mesh (not only the converted ones) in ten groups of types — POI1,
//!   SEG4, SEG3, TRIA7/QUAD9, 27/21/19/15-node volumes, TRIA6/QUAD8, the other quadratic volumes,
//!   SEG2, TRIA3/QUAD4, linear volumes — each group by increasing cell number, and walks the edges
//!   of each cell in its local order ([`edges`]). An edge (unordered pair of vertices) met for the
//!   first time gets a node at its straight midpoint, unless the cell is quadratic and brings its
//!   own middle node; later cells reuse the first one. (Face and cell centres are made too, for
//!   the QUAD9/HEXA27 "maximal" cells the module builds, and dropped at the end: they never take
//!   a number.) Kept nodes are numbered in creation order: the original nodes keep 1..N, the
//!   middle nodes used by a converted cell follow; the others are dropped.
//! - 2020 walks only the converted cells, in increasing cell number, and numbers the middle node
//!   of each new edge in order of first appearance; the middle nodes of quadratic cells are not
//!   reused.
//! - Converted cells list their middle nodes in edge order (QUAD8 5..8, TETRA10 5..10, HEXA20
//!   9..20, ...). Cell numbers, names and groups do not change; node groups are copied unchanged
//!   (middle nodes join none).
//! - QUAD_LINE keeps the first vertices of each converted cell, then drops every node that no cell
//!   uses any more (a node no cell used in the input is kept), numbering the others compactly in
//!   their old order; node groups lose the dropped nodes and disappear when emptied.

use super::{CellType, Mesh};
use std::collections::{BTreeMap, HashMap};

/// The edges of a cell type as pairs of local vertex positions (0-based), in Code_Aster's order
/// (`numbering_edge`): the i-th edge's middle node is node `nvertices + i` of the quadratic cell.
pub fn edges(t: CellType) -> &'static [(usize, usize)] {
    use CellType::*;
    match t {
        Poi1 => &[],
        Seg2 | Seg3 => &[(0, 1)],
        Tria3 | Tria6 => &[(0, 1), (1, 2), (2, 0)],
        Quad4 | Quad8 | Quad9 => &[(0, 1), (1, 2), (2, 3), (3, 0)],
        Tetra4 | Tetra10 => &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)],
        Penta6 | Penta15 => &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (3, 5)],
        Pyram5 | Pyram13 => &[(0, 1), (1, 2), (2, 3), (0, 3), (0, 4), (1, 4), (2, 4), (3, 4)],
        Hexa8 | Hexa20 | Hexa27 => {
            &[(0, 1), (1, 2), (2, 3), (0, 3), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6), (6, 7), (4, 7)]
        }
    }
}

/// The quadratic type LINE_QUAD makes of a linear type.
pub fn quadratic_of(t: CellType) -> Option<CellType> {
    use CellType::*;
    Some(match t {
        Seg2 => Seg3,
        Tria3 => Tria6,
        Quad4 => Quad8,
        Tetra4 => Tetra10,
        Penta6 => Penta15,
        Pyram5 => Pyram13,
        Hexa8 => Hexa20,
        _ => return None,
    })
}

/// The linear type QUAD_LINE makes of a quadratic type.
pub fn linear_of(t: CellType) -> Option<CellType> {
    use CellType::*;
    Some(match t {
        Seg3 => Seg2,
        Tria6 => Tria3,
        Quad8 | Quad9 => Quad4,
        Tetra10 => Tetra4,
        Penta15 => Penta6,
        Pyram13 => Pyram5,
        Hexa20 | Hexa27 => Hexa8,
        _ => return None,
    })
}

/// Does a cell of this type carry a middle node on each edge?
fn has_middle_nodes(t: CellType) -> bool {
    t.nnodes() > t.nvertices() && t != CellType::Poi1
}

/// The group in which Code_Aster 2025's module visits a cell type (`init_mesh`).
fn visit_group(t: CellType) -> usize {
    use CellType::*;
    match t {
        Poi1 => 0,
        Seg3 => 2,
        Quad9 => 3,
        Hexa27 => 4,
        Tria6 | Quad8 => 5,
        Tetra10 | Penta15 | Pyram13 | Hexa20 => 6,
        Seg2 => 7,
        Tria3 | Quad4 => 8,
        Tetra4 | Penta6 | Pyram5 | Hexa8 => 9,
    }
}

/// A changed mesh and what changed.
#[derive(Debug, Clone)]
pub struct Converted {
    pub mesh: Mesh,
    /// The nodes from this index on are new (LINE_QUAD); their names are `N` + number.
    pub first_new: usize,
    /// Cells converted, by (from, to) type.
    pub counts: BTreeMap<(CellType, CellType), usize>,
    /// Nodes removed (QUAD_LINE).
    pub removed: usize,
}

/// The middle node of an edge while the edges are walked.
#[derive(Clone, Copy)]
enum Middle {
    /// A node of the input (the middle node of a quadratic cell).
    Old(usize),
    /// The k-th node created.
    New(usize),
}

/// Unordered key of an edge.
fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Build the converted mesh from the middle node of every edge of the converted cells: `middle`
/// gives, for a converted cell and its edge, the created node's index in `created` or an old node.
fn assemble(
    mesh: &Mesh,
    cells: &[usize],
    created: &[(usize, usize)],
    middle_of: impl Fn(usize, usize) -> Middle,
) -> Converted {
    let nn = mesh.nnodes();
    let mut out = mesh.clone();
    let mut counts = BTreeMap::new();
    // The created nodes that a converted cell uses, numbered in creation order.
    let mut used = vec![false; created.len()];
    let mut converted = Vec::new();
    for &c in cells {
        let t = mesh.cell_types[c];
        let Some(q) = quadratic_of(t) else { continue };
        converted.push((c, q));
        for i in 0..edges(t).len() {
            if let Middle::New(k) = middle_of(c, i) {
                used[k] = true;
            }
        }
    }
    let mut number = vec![usize::MAX; created.len()];
    for (k, &(a, b)) in created.iter().enumerate() {
        if used[k] {
            number[k] = out.coords.len();
            let (pa, pb) = (mesh.coords[a], mesh.coords[b]);
            out.coords.push([0.5 * pa[0] + 0.5 * pb[0], 0.5 * pa[1] + 0.5 * pb[1], 0.5 * pa[2] + 0.5 * pb[2]]);
            out.node_names.push(format!("N{}", out.coords.len()));
        }
    }
    for (c, q) in converted {
        let t = mesh.cell_types[c];
        let mut nodes = mesh.cells[c][..t.nvertices()].to_vec();
        for i in 0..edges(t).len() {
            nodes.push(match middle_of(c, i) {
                Middle::Old(n) => n,
                Middle::New(k) => number[k],
            });
        }
        out.cells[c] = nodes;
        out.cell_types[c] = q;
        *counts.entry((t, q)).or_insert(0) += 1;
    }
    Converted { mesh: out, first_new: nn, counts, removed: 0 }
}

/// LINE_QUAD as Code_Aster 2025 does it: the linear cells among `cells` become quadratic (SEG3,
/// TRIA6, QUAD8, TETRA10, PENTA15, PYRAM13, HEXA20); see the module documentation for the
/// numbering. Other cells, and cells not listed, are left as they are.
pub fn line_to_quad(mesh: &Mesh, cells: &[usize]) -> Converted {
    let mut order: Vec<usize> = (0..mesh.ncells()).collect();
    order.sort_by_key(|&c| visit_group(mesh.cell_types[c]));
    let mut middle: HashMap<(usize, usize), Middle> = HashMap::new();
    let mut created: Vec<(usize, usize)> = Vec::new();
    for &c in &order {
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let nv = t.nvertices();
        for (i, &(p, q)) in edges(t).iter().enumerate() {
            let (a, b) = (nodes[p], nodes[q]);
            // The first edge with these vertices wins; a quadratic cell brings its middle node.
            middle.entry(key(a, b)).or_insert_with(|| {
                if has_middle_nodes(t) {
                    Middle::Old(nodes[nv + i])
                } else {
                    created.push((a, b));
                    Middle::New(created.len() - 1)
                }
            });
        }
    }
    assemble(mesh, cells, &created, |c, i| {
        let (p, q) = edges(mesh.cell_types[c])[i];
        middle[&key(mesh.cells[c][p], mesh.cells[c][q])]
    })
}

/// LINE_QUAD as Code_Aster 2020 did it: only the linear cells among `cells` are walked, in
/// increasing cell number, and each new edge gets a new middle node (those of quadratic cells are
/// not reused).
pub fn line_to_quad_2020(mesh: &Mesh, cells: &[usize]) -> Converted {
    let mut sorted = cells.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut middle: HashMap<(usize, usize), usize> = HashMap::new();
    let mut created: Vec<(usize, usize)> = Vec::new();
    for &c in &sorted {
        let t = mesh.cell_types[c];
        if quadratic_of(t).is_none() {
            continue;
        }
        for &(p, q) in edges(t) {
            let (a, b) = (mesh.cells[c][p], mesh.cells[c][q]);
            middle.entry(key(a, b)).or_insert_with(|| {
                created.push((a, b));
                created.len() - 1
            });
        }
    }
    assemble(mesh, &sorted, &created, |c, i| {
        let (p, q) = edges(mesh.cell_types[c])[i];
        Middle::New(middle[&key(mesh.cells[c][p], mesh.cells[c][q])])
    })
}

/// QUAD_LINE as Code_Aster 2025 does it (`convert_max = false`): the quadratic cells among `cells`
/// keep their vertices; nodes no cell uses any more are removed (see the module documentation).
/// Node names follow the new numbers (`N` + number) unless the mesh carried its own names.
pub fn quad_to_line(mesh: &Mesh, cells: &[usize]) -> Converted {
    let nn = mesh.nnodes();
    let mut out = mesh.clone();
    let mut counts = BTreeMap::new();
    for &c in cells {
        let t = mesh.cell_types[c];
        if let Some(l) = linear_of(t) {
            out.cells[c].truncate(t.nvertices());
            out.cell_types[c] = l;
            *counts.entry((t, l)).or_insert(0) += 1;
        }
    }
    let mut used_in = vec![false; nn];
    for c in &mesh.cells {
        c.iter().for_each(|&n| used_in[n] = true);
    }
    // Orphans of the input stay; so do the nodes of the cells.
    let mut keep: Vec<bool> = used_in.iter().map(|u| !u).collect();
    for c in &out.cells {
        c.iter().for_each(|&n| keep[n] = true);
    }
    let mut new_of = vec![usize::MAX; nn];
    let mut coords = Vec::new();
    let mut names = Vec::new();
    for n in 0..nn {
        if keep[n] {
            new_of[n] = coords.len();
            coords.push(mesh.coords[n]);
            names.push(if mesh.named_nodes { mesh.node_names[n].clone() } else { format!("N{}", coords.len()) });
        }
    }
    let removed = nn - coords.len();
    out.coords = coords;
    out.node_names = names;
    for c in &mut out.cells {
        c.iter_mut().for_each(|n| *n = new_of[*n]);
    }
    out.node_groups = mesh
        .node_groups
        .iter()
        .filter_map(|(g, members)| {
            let kept: Vec<usize> = members.iter().filter(|&&n| keep[n]).map(|&n| new_of[n]).collect();
            (!kept.is_empty()).then(|| (g.clone(), kept))
        })
        .collect();
    Converted { mesh: out, first_new: nn - removed, counts, removed }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nodes 1(0,0) 2(1,0) 3(2,0) 4(2,1) 5(1,1) 6(0,1); cells 1 = SEG2(3,4), 2 = QUAD4(1,2,5,6),
    /// 3 = QUAD4(2,3,4,5).
    fn two_quads() -> Mesh {
        let coords = vec![[0., 0., 0.], [1., 0., 0.], [2., 0., 0.], [2., 1., 0.], [1., 1., 0.], [0., 1., 0.]];
        let mut m = Mesh {
            dim: 2,
            node_names: (1..=6).map(|i| format!("N{i}")).collect(),
            coords,
            cell_types: vec![CellType::Seg2, CellType::Quad4, CellType::Quad4],
            cells: vec![vec![2, 3], vec![0, 1, 4, 5], vec![1, 2, 3, 4]],
            cell_names: vec!["M1".into(), "M2".into(), "M3".into()],
            ..Mesh::default()
        };
        m.node_groups.insert("BAS".into(), vec![0, 1, 2]);
        m.cell_groups.insert("DROITE".into(), vec![0]);
        m
    }

    /// 1-based node numbers of a cell.
    fn numbers(m: &Mesh, c: usize) -> Vec<usize> {
        m.cells[c].iter().map(|n| n + 1).collect()
    }

    #[test]
    fn line_quad_numbers_middle_nodes_as_code_aster_2025() {
        let m = two_quads();
        let q = line_to_quad(&m, &[0, 1, 2]).mesh;
        // N7 from the SEG2 (visited first), N8..N11 from cell 2, N12 and N13 from cell 3.
        assert_eq!(q.nnodes(), 13);
        let expect = [[2., 0.5], [0.5, 0.], [1., 0.5], [0.5, 1.], [0., 0.5], [1.5, 0.], [1.5, 1.]];
        for (k, p) in expect.iter().enumerate() {
            assert_eq!([q.coords[6 + k][0], q.coords[6 + k][1]], *p, "N{}", 7 + k);
            assert_eq!(q.node_names[6 + k], format!("N{}", 7 + k));
        }
        assert_eq!(q.cell_types, vec![CellType::Seg3, CellType::Quad8, CellType::Quad8]);
        assert_eq!(numbers(&q, 1), vec![1, 2, 5, 6, 8, 9, 10, 11]);
        assert_eq!(numbers(&q, 2), vec![2, 3, 4, 5, 12, 7, 13, 9]);
        assert_eq!(numbers(&q, 0), vec![3, 4, 7]);
        // Groups unchanged: middle nodes join no node group.
        assert_eq!(q.node_groups["BAS"], vec![0, 1, 2]);
        assert_eq!(q.cell_groups["DROITE"], vec![0]);
        assert_eq!(q.cell_names, m.cell_names);
    }

    #[test]
    fn line_quad_of_a_subset_drops_the_middle_nodes_of_unconverted_cells() {
        let m = two_quads();
        // Only cell 3: the SEG2's edge (3-4) was met first (N7 in the full conversion), cell 2's
        // four edges next; kept are those of cell 3, in creation order: 3-4, 2-5, 2-3, 4-5.
        let q = line_to_quad(&m, &[2]).mesh;
        assert_eq!(q.nnodes(), 10);
        assert_eq!(q.cell_types, vec![CellType::Seg2, CellType::Quad4, CellType::Quad8]);
        // Edges of cell 3 in order: 2-3 (N9), 3-4 (N7), 4-5 (N10), 5-2 (N8).
        assert_eq!(numbers(&q, 2), vec![2, 3, 4, 5, 9, 7, 10, 8]);
        assert_eq!([q.coords[6][0], q.coords[6][1]], [2., 0.5]);
        assert_eq!([q.coords[7][0], q.coords[7][1]], [1., 0.5]);
    }

    #[test]
    fn line_quad_2020_walks_the_converted_cells_in_order() {
        let m = two_quads();
        let q = line_to_quad_2020(&m, &[0, 1, 2]).mesh;
        // Cell 1 (SEG2) first: N7; cell 2: N8..N11; cell 3: 2-3 N12, 3-4 (N7), 4-5 N13, 5-2 (N9).
        assert_eq!(numbers(&q, 0), vec![3, 4, 7]);
        assert_eq!(numbers(&q, 1), vec![1, 2, 5, 6, 8, 9, 10, 11]);
        assert_eq!(numbers(&q, 2), vec![2, 3, 4, 5, 12, 7, 13, 9]);
    }

    #[test]
    fn line_quad_reuses_the_middle_node_of_a_quadratic_neighbour() {
        // A SEG3 (3,4,7) then QUAD4 (2,3,4,5): edge 3-4 reuses node 7.
        let mut m = two_quads();
        m.coords.push([2.0, 0.5, 0.0]);
        m.node_names.push("N7".into());
        m.cells[0] = vec![2, 3, 6];
        m.cell_types[0] = CellType::Seg3;
        let c = line_to_quad(&m, &[1, 2]);
        assert_eq!(c.first_new, 7);
        let q = c.mesh;
        assert_eq!(numbers(&q, 2), vec![2, 3, 4, 5, 12, 7, 13, 9]);
        assert_eq!(c.counts[&(CellType::Quad4, CellType::Quad8)], 2);
        // Already quadratic: nothing changes.
        let again = line_to_quad(&q, &[0, 1, 2]);
        assert!(again.counts.is_empty());
        assert_eq!(again.mesh.cells, q.cells);
        assert_eq!(again.mesh.nnodes(), q.nnodes());
    }

    #[test]
    fn line_quad_of_a_hexa_lists_its_twelve_edges_in_order() {
        let coords = vec![
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
        ];
        let m = Mesh {
            dim: 3,
            node_names: (1..=8).map(|i| format!("N{i}")).collect(),
            coords,
            cell_types: vec![CellType::Hexa8],
            cells: vec![(0..8).collect()],
            cell_names: vec!["M1".into()],
            ..Mesh::default()
        };
        let q = line_to_quad(&m, &[0]).mesh;
        assert_eq!(q.cell_types[0], CellType::Hexa20);
        assert_eq!(numbers(&q, 0)[8..], (9..=20).collect::<Vec<_>>()[..]);
        for (i, &(a, b)) in edges(CellType::Hexa8).iter().enumerate() {
            for k in 0..3 {
                assert_eq!(q.coords[8 + i][k], 0.5 * m.coords[a][k] + 0.5 * m.coords[b][k]);
            }
        }
    }

    #[test]
    fn quad_line_removes_middle_nodes_and_renumbers() {
        let m = two_quads();
        let q = line_to_quad(&m, &[0, 1, 2]).mesh;
        let mut q2 = q.clone();
        // An orphan node stays; a group of middle nodes only disappears.
        q2.coords.push([9., 9., 0.]);
        q2.node_names.push("N14".into());
        q2.node_groups.insert("MIL".into(), vec![7, 8]);
        q2.node_groups.insert("MIX".into(), vec![12, 13, 0]);
        let l = quad_to_line(&q2, &[0, 1, 2]);
        assert_eq!(l.removed, 7);
        let lm = l.mesh;
        assert_eq!(lm.nnodes(), 7);
        assert_eq!(lm.cells, m.cells);
        assert_eq!(lm.cell_types, m.cell_types);
        assert_eq!(lm.node_names[6], "N7");
        assert_eq!(lm.coords[6], [9., 9., 0.]);
        assert!(!lm.node_groups.contains_key("MIL"));
        assert_eq!(lm.node_groups["MIX"], vec![6, 0]);
        assert_eq!(lm.node_groups["BAS"], vec![0, 1, 2]);
        // Only the SEG3: the quads keep the middle nodes they use.
        let part = quad_to_line(&q, &[0]);
        assert_eq!(part.removed, 0);
        assert_eq!(numbers(&part.mesh, 0), vec![3, 4]);
    }
}
