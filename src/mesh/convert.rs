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
        Seg2 | Seg3 | Seg4 => &[(0, 1)],
        Tria3 | Tria6 | Tria7 => &[(0, 1), (1, 2), (2, 0)],
        Quad4 | Quad8 | Quad9 => &[(0, 1), (1, 2), (2, 3), (3, 0)],
        Tetra4 | Tetra10 => &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)],
        Penta6 | Penta15 | Penta18 => &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (3, 5)],
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
        Tria6 | Tria7 => Tria3,
        Quad8 | Quad9 => Quad4,
        Tetra10 => Tetra4,
        Penta15 | Penta18 => Penta6,
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
        Seg4 => 1,
        Seg3 => 2,
        Tria7 | Quad9 => 3,
        Hexa27 => 4,
        Tria6 | Quad8 => 5,
        Tetra10 | Penta15 | Penta18 | Pyram13 | Hexa20 => 6,
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

/// The quadrangular faces of a quadratic volume as Code_Aster lists them (`numbering_face`, 0-based):
/// 4 vertices then 4 middle nodes, in the face's own order.
fn quad_faces(t: CellType) -> &'static [[usize; 8]] {
    use CellType::*;
    match t {
        Hexa20 | Hexa27 => &[
            [0, 3, 2, 1, 11, 10, 9, 8],
            [0, 1, 5, 4, 8, 13, 16, 12],
            [1, 2, 6, 5, 9, 14, 17, 13],
            [2, 3, 7, 6, 10, 15, 18, 14],
            [0, 4, 7, 3, 12, 19, 15, 11],
            [4, 5, 6, 7, 16, 17, 18, 19],
        ],
        Penta15 => &[[0, 1, 4, 3, 6, 10, 12, 9], [1, 2, 5, 4, 7, 11, 13, 10], [0, 3, 5, 2, 9, 14, 11, 8]],
        Pyram13 => &[[0, 3, 2, 1, 8, 7, 6, 5]],
        Quad8 | Quad9 => &[[0, 1, 2, 3, 4, 5, 6, 7]],
        _ => &[],
    }
}

/// The centre node of a face or a volume while the cells are walked.
#[derive(Clone, Copy)]
enum Centre {
    Old(usize),
    /// The k-th centre created.
    New(usize),
}

/// What the k-th created centre is the centre of: the nodes of a QUAD8 face in its order, or a HEXA20.
enum Made {
    Face([usize; 8]),
    Volume(usize),
}

/// HEXA20_27 as Code_Aster 2025 does it (`cm2027`): the QUAD8 cells among `cells` become QUAD9 and the
/// HEXA20 cells HEXA27, with a node at the centre of each quadrangular face and of each hexahedron.
/// The module walks the cells in its type groups (see the module documentation) and creates the centre
/// of a face the first time it meets it (a QUAD9 cell or a HEXA27 brings its own), then the centre of
/// the volume; centres used by a converted cell are numbered after the nodes of the mesh in that order.
/// A centre sits where the QUAD8 / HEXA20 shape functions put the middle of the reference cell.
pub fn hexa20_to_27(mesh: &Mesh, cells: &[usize]) -> Converted {
    let mut order: Vec<usize> = (0..mesh.ncells()).collect();
    order.sort_by_key(|&c| visit_group(mesh.cell_types[c]));
    // Faces by sorted vertices: (sorted middle nodes, centre), first created first.
    let mut faces: HashMap<[usize; 4], Vec<([usize; 4], Centre)>> = HashMap::new();
    let mut volumes: HashMap<Vec<usize>, Centre> = HashMap::new();
    let mut made: Vec<Made> = Vec::new();
    let sorted4 = |a: &[usize]| {
        let mut k = [a[0], a[1], a[2], a[3]];
        k.sort_unstable();
        k
    };
    for &c in &order {
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        for (i, f) in quad_faces(t).iter().enumerate() {
            let fnodes: [usize; 8] = f.map(|k| nodes[k]);
            let (verts, mids) = (sorted4(&fnodes[..4]), sorted4(&fnodes[4..]));
            let list = faces.entry(verts).or_default();
            if list.iter().any(|(m, _)| *m == mids) {
                continue;
            }
            let centre = match t {
                CellType::Quad9 => Centre::Old(nodes[8]),
                CellType::Hexa27 => Centre::Old(nodes[20 + i]),
                _ => {
                    made.push(Made::Face(fnodes));
                    Centre::New(made.len() - 1)
                }
            };
            list.push((mids, centre));
        }
        if matches!(t, CellType::Hexa20 | CellType::Hexa27) {
            let mut key = nodes[..8].to_vec();
            key.sort_unstable();
            volumes.entry(key).or_insert_with(|| {
                if t == CellType::Hexa27 {
                    Centre::Old(nodes[26])
                } else {
                    made.push(Made::Volume(c));
                    Centre::New(made.len() - 1)
                }
            });
        }
    }
    let face_centre = |fnodes: [usize; 8]| {
        let (verts, mids) = (sorted4(&fnodes[..4]), sorted4(&fnodes[4..]));
        faces[&verts].iter().find(|(m, _)| *m == mids).map(|(_, c)| *c).expect("every face was walked")
    };
    let volume_centre = |c: usize| {
        let mut key = mesh.cells[c][..8].to_vec();
        key.sort_unstable();
        volumes[&key]
    };
    // The converted cells and the centres they use.
    let mut converted: Vec<(usize, Vec<Centre>)> = Vec::new();
    for &c in cells {
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let centres: Vec<Centre> = match t {
            CellType::Quad8 | CellType::Hexa20 => {
                quad_faces(t).iter().map(|f| face_centre(f.map(|k| nodes[k]))).collect()
            }
            _ => continue,
        };
        let mut centres = centres;
        if t == CellType::Hexa20 {
            centres.push(volume_centre(c));
        }
        converted.push((c, centres));
    }
    let mut used = vec![false; made.len()];
    for (_, centres) in &converted {
        for c in centres {
            if let Centre::New(k) = c {
                used[*k] = true;
            }
        }
    }
    let nn = mesh.nnodes();
    let mut out = mesh.clone();
    let mut number = vec![usize::MAX; made.len()];
    for (k, m) in made.iter().enumerate() {
        if !used[k] {
            continue;
        }
        // Shape functions at the centre of the reference cell, summed node after node as `elrfvf`'s
        // values are: QUAD8 -1/4 on vertices, 1/2 on middle nodes; HEXA20 -1/4 and 1/4.
        let (list, w_vertex, w_middle, nv): (Vec<usize>, f64, f64, usize) = match m {
            Made::Face(f) => (f.to_vec(), -0.25, 0.5, 4),
            Made::Volume(c) => (mesh.cells[*c][..20].to_vec(), -0.25, 0.25, 8),
        };
        let mut p = [0.0; 3];
        for (i, &n) in list.iter().enumerate() {
            let w = if i < nv { w_vertex } else { w_middle };
            for (pk, xk) in p.iter_mut().zip(mesh.coords[n]) {
                *pk += xk * w;
            }
        }
        number[k] = out.coords.len();
        out.coords.push(p);
        out.node_names.push(format!("N{}", out.coords.len()));
    }
    let mut counts = BTreeMap::new();
    for (c, centres) in converted {
        let t = mesh.cell_types[c];
        let to = if t == CellType::Quad8 { CellType::Quad9 } else { CellType::Hexa27 };
        out.cells[c].extend(centres.iter().map(|x| match x {
            Centre::Old(n) => *n,
            Centre::New(k) => number[*k],
        }));
        out.cell_types[c] = to;
        *counts.entry((t, to)).or_insert(0) += 1;
    }
    Converted { mesh: out, first_new: nn, counts, removed: 0 }
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
    fn hexa20_27_numbers_face_centres_then_the_volume_centre() {
        use crate::mesh::generate::box_mesh;
        // Two HEXA20 along x with their QUAD8 skins (cell order: the skins, then the volumes).
        let m = box_mesh(CellType::Hexa20, &[2, 1, 1], &[2.0, 1.0, 1.0]).unwrap();
        let nn = m.nnodes();
        let all: Vec<usize> = (0..m.ncells()).collect();
        let c = hexa20_to_27(&m, &all);
        let q = &c.mesh;
        let skins = m.cell_types.iter().filter(|&&t| t == CellType::Quad8).count();
        assert_eq!(skins, 10);
        // One centre per distinct quadrangle (10 skins + 1 shared inner face) and per hexahedron.
        assert_eq!(q.nnodes(), nn + 11 + 2);
        // The skins come first (group of TRIA6/QUAD8), in cell order: their centres are N(nn+1)...
        let quads: Vec<usize> = (0..m.ncells()).filter(|&i| m.cell_types[i] == CellType::Quad8).collect();
        for (k, &i) in quads.iter().enumerate() {
            assert_eq!(q.cell_types[i], CellType::Quad9);
            assert_eq!(q.cells[i][8], nn + k);
        }
        // The first hexahedron: its faces are all known except the inner one, made before its centre.
        let hexas: Vec<usize> = (0..m.ncells()).filter(|&i| m.cell_types[i] == CellType::Hexa20).collect();
        let h0 = &q.cells[hexas[0]];
        assert_eq!(h0.len(), 27);
        assert_eq!(h0[26], nn + 11, "volume centre after the inner face");
        assert!(h0[20..26].contains(&(nn + 10)), "the inner face's centre");
        assert_eq!(q.cells[hexas[1]][26], nn + 12);
        // Centres at the middle of their face / cell.
        let mid = |ids: &[usize]| -> [f64; 3] {
            let mut p = [0.0; 3];
            for &n in ids {
                p.iter_mut().zip(q.coords[n]).for_each(|(pk, x)| *pk += x / ids.len() as f64);
            }
            p
        };
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
        for (i, f) in quad_faces(CellType::Hexa20).iter().enumerate() {
            let verts: Vec<usize> = f[..4].iter().map(|&k| h0[k]).collect();
            assert!(close(q.coords[h0[20 + i]], mid(&verts)), "face {i}");
        }
        assert!(close(q.coords[h0[26]], mid(&h0[..8])));
        // Only the second hexahedron: the inner face and its own faces and centre are kept, in order.
        let one = hexa20_to_27(&m, &hexas[1..]).mesh;
        assert_eq!(one.nnodes(), nn + 7);
        assert_eq!(one.cells[hexas[1]][26], nn + 6);
        // Already HEXA27: nothing more.
        let again = hexa20_to_27(q, &all);
        assert!(again.counts.is_empty());
        assert_eq!(again.mesh.nnodes(), q.nnodes());
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
