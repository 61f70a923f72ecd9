//! Structured box meshes with named boundary groups (fixtures, benchmarks,
//! `aster mesh box`).
//!
//! * 2D, `QUAD4` / `QUAD8` cells on `[0, LX] x [0, LY]`, or `TRIA3` / `TRIA6`
//!   (each quadrangle split into two triangles along its diagonal from its
//!   lowest to its highest corner): boundary edges as
//!   `SEG2` / `SEG3` cells in the cell groups `BAS` (y = 0), `DROITE`
//!   (x = LX), `HAUT` (y = LY), `GAUCHE` (x = 0), the same names as node
//!   groups (every node on that edge), and the cell group `SURFACE` holding
//!   the surface cells.
//! * 3D, `HEXA8` / `HEXA20` cells on `[0, LX] x [0, LY] x [0, LZ]`, or
//!   `TETRA4` / `TETRA10` (each hexahedron split into the six tetrahedra
//!   around its diagonal from (0, 0, 0) to (1, 1, 1), Kuhn's split) or
//!   `PENTA6` / `PENTA15` (each hexahedron split into two prisms, its xy
//!   faces along their diagonal from the lowest to the highest corner):
//!   boundary faces as `QUAD4` / `QUAD8` cells (`TRIA3` / `TRIA6` where the
//!   volume cells have triangular faces there) in the cell groups `XMIN`,
//!   `XMAX`, `YMIN`, `YMAX`, `ZMIN`, `ZMAX`, the same names as node groups,
//!   and the cell group `VOLUME` holding the volume cells. Every split takes
//!   a face's diagonal from its lowest to its highest corner, so the cells
//!   are conforming across faces, and the skin triangles are those faces.
//!
//! Nodes are numbered along x first, then y, then z, over the grid of
//! vertices and mid-edge points (`N1, N2, ...`; a quadratic simplex or prism
//! box also has the middle nodes of the diagonals it cuts: the quadrangles'
//! and faces' centres, and the hexahedra's for tetrahedra). Every volume
//! cell has a positive Jacobian. Cells come type by type in
//! Code_Aster's reading order (boundary cells first, group after group in
//! the order above, then the volume or surface cells), so the numbering
//! (`M1, M2, ...`) is the one a MED round trip gives back. Boundary cells
//! are oriented with their normal pointing out of the box; all connectivities
//! are in Code_Aster's local node order.

use super::{CellType, Mesh};
use crate::diag::{Error, Result};

/// The grid points of a box: `q` = 1 (linear) or 2 (quadratic: mid-edge
/// points at odd indices), `m[k] = q * n[k]` intervals per axis.
struct Grid {
    q: usize,
    m: [usize; 3],
    /// Node index of each grid point (`usize::MAX` for points that carry no node).
    id: Vec<usize>,
}

impl Grid {
    fn flat(&self, p: [usize; 3]) -> usize {
        p[0] + (self.m[0] + 1) * (p[1] + (self.m[1] + 1) * p[2])
    }
    fn node(&self, p: [usize; 3]) -> usize {
        let n = self.id[self.flat(p)];
        debug_assert!(n != usize::MAX, "grid point {p:?} has no node");
        n
    }
}

/// The cell types a box can be made of.
pub const BOX_CELLS: &str = "QUAD4, QUAD8, TRIA3, TRIA6, HEXA8, HEXA20, TETRA4, TETRA10, PENTA6 or PENTA15";

/// Build a structured box. `n` holds the cells per axis (of the quadrangles
/// or hexahedra that simplices and prisms split), `size` the box lengths (two
/// values in 2D, three in 3D).
pub fn box_mesh(cell: CellType, n: &[usize], size: &[f64]) -> Result<Mesh> {
    use CellType::*;
    let (dim, q) = match cell {
        Quad4 | Tria3 => (2, 1),
        Quad8 | Tria6 => (2, 2),
        Hexa8 | Tetra4 | Penta6 => (3, 1),
        Hexa20 | Tetra10 | Penta15 => (3, 2),
        other => return Err(Error::runtime(format!("box meshes are made of {BOX_CELLS} cells, not {}", other.name()))),
    };
    if n.len() != dim || size.len() != dim {
        return Err(Error::runtime(format!(
            "a {} box needs {dim} cell counts and {dim} lengths (got {} and {})",
            cell.name(),
            n.len(),
            size.len()
        )));
    }
    if n.contains(&0) {
        return Err(Error::runtime("every cell count must be at least 1"));
    }
    if size.iter().any(|&l| !(l.is_finite() && l > 0.0)) {
        return Err(Error::runtime("every box length must be a positive finite number"));
    }
    let mut m = [0usize; 3];
    let mut len = [0.0f64; 3];
    for k in 0..dim {
        m[k] = q * n[k];
        len[k] = size[k];
    }
    let npoints = (m[0] + 1).checked_mul(m[1] + 1).and_then(|v| v.checked_mul(m[2] + 1));
    let npoints = npoints.filter(|&v| v <= 1 << 31).ok_or_else(|| Error::runtime("box too large"))?;

    // Nodes: grid points with at most one odd index (all of them when linear), and the middles of
    // the diagonals that simplices and prisms cut (two or three odd indices: every face centre and
    // hexahedron centre for tetrahedra, the centres of the xy faces for prisms).
    let keep = |i: usize, j: usize, k: usize| {
        let odd = (i % 2) + (j % 2) + (k % 2);
        q == 1
            || odd <= 1
            || matches!(cell, Tria6 | Tetra10)
            || (cell == Penta15 && i % 2 == 1 && j % 2 == 1 && k.is_multiple_of(2))
    };
    let mut grid = Grid { q, m, id: vec![usize::MAX; npoints] };
    let mut mesh = Mesh { dim, named_nodes: true, ..Mesh::default() };
    for k in 0..=m[2] {
        for j in 0..=m[1] {
            for i in 0..=m[0] {
                if !keep(i, j, k) {
                    continue;
                }
                let f = grid.flat([i, j, k]);
                grid.id[f] = mesh.coords.len();
                let coord = |idx: usize, axis: usize| {
                    if m[axis] == 0 {
                        0.0
                    } else {
                        len[axis] * idx as f64 / m[axis] as f64
                    }
                };
                mesh.coords.push([coord(i, 0), coord(j, 1), coord(k, 2)]);
            }
        }
    }
    mesh.node_names = (1..=mesh.coords.len()).map(|i| format!("N{i}")).collect();

    if dim == 2 {
        build_2d(&mut mesh, &grid, n, cell);
    } else {
        build_3d(&mut mesh, &grid, n, cell);
    }
    mesh.cell_names = (1..=mesh.cells.len()).map(|i| format!("M{i}")).collect();
    Ok(mesh)
}

/// How [`distort`] moves the nodes of a box: each vertex by up to `shift`·h along every axis (h the
/// cell size along it), each mid-edge node (and the middle of a diagonal that a simplex or prism box
/// cuts) to the middle of its moved ends plus up to `bend`·h along every axis, which curves the edges
/// of quadratic cells; the draws are uniform, from `seed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distortion {
    pub shift: f64,
    pub bend: f64,
    pub seed: u64,
}

/// A [`box_mesh`] whose nodes are moved as `d` says: the cells become general quadrilaterals,
/// hexahedra and simplices, with curved edges where they are quadratic, while every node on a face of
/// the box moves only within that face (the box and its groups keep their shape, so that conditions
/// on whole faces still describe a box). Neither the topology, the names nor the groups change. The
/// caller checks the Jacobians (`fem::geometry::inverted_cells`): a shift of 0.2 and a bend of 0.05
/// keep them positive on every cell type.
pub fn distort(mesh: &mut Mesh, n: &[usize], size: &[f64], d: Distortion) -> Result<()> {
    let dim = mesh.dim;
    if n.len() != dim || size.len() != dim {
        return Err(Error::runtime("distort: a cell count and a length per axis are needed"));
    }
    if !(0.0..0.5).contains(&d.shift) || !(0.0..0.25).contains(&d.bend) {
        return Err(Error::runtime("distort: expected 0 <= shift < 0.5 and 0 <= bend < 0.25 (in cell sizes)"));
    }
    // The quadratic grid: index 2i on vertex i, 2i + 1 between; a linear box's nodes are on even indices.
    let h: Vec<f64> = (0..dim).map(|a| size[a] / n[a] as f64).collect();
    let index = |x: &[f64; 3]| -> [i64; 3] {
        let mut p = [0i64; 3];
        for a in 0..dim {
            p[a] = (x[a] / h[a] * 2.0).round() as i64;
        }
        p
    };
    let mut rng = SplitMix(d.seed);
    let mut moved: std::collections::HashMap<[i64; 3], [f64; 3]> = std::collections::HashMap::new();
    let top = |a: usize| 2 * n[a] as i64;
    let draw = |p: [i64; 3], amp: f64, rng: &mut SplitMix| -> [f64; 3] {
        let mut v = [0.0; 3];
        for a in 0..dim {
            // A node on a face of the box stays on it.
            if p[a] != 0 && p[a] != top(a) {
                v[a] = amp * h[a] * (2.0 * rng.unit() - 1.0);
            }
        }
        v
    };
    let mut vertex = |p: [i64; 3], rng: &mut SplitMix| -> [f64; 3] {
        *moved.entry(p).or_insert_with(|| {
            let v = draw(p, d.shift, rng);
            [0, 1, 2].map(|a| if a < dim { p[a] as f64 / 2.0 * h[a] + v[a] } else { 0.0 })
        })
    };
    // Vertices first, in node order, so that the draws do not depend on the mid-nodes'.
    let grid: Vec<[i64; 3]> = mesh.coords.iter().map(index).collect();
    for p in &grid {
        if p.iter().all(|c| c % 2 == 0) {
            vertex(*p, &mut rng);
        }
    }
    for (k, p) in grid.iter().enumerate() {
        if p.iter().all(|c| c % 2 == 0) {
            mesh.coords[k] = vertex(*p, &mut rng);
            continue;
        }
        // The middle of the segment from p − Σ e_a to p + Σ e_a over its odd axes: the edge or the
        // diagonal (always from its lowest to its highest corner in a box) it is the middle of.
        let lo = p.map(|c| c - c.rem_euclid(2));
        let hi = p.map(|c| c + c.rem_euclid(2));
        let (a, b) = (vertex(lo, &mut rng), vertex(hi, &mut rng));
        let v = draw(*p, d.bend, &mut rng);
        mesh.coords[k] = [0, 1, 2].map(|i| (a[i] + b[i]) / 2.0 + v[i]);
    }
    Ok(())
}

/// SplitMix64: a small seedable generator for the distortions (reproducible from the seed alone).
struct SplitMix(u64);

impl SplitMix {
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A quarter of a thick ring (2D) or of a thick-walled cylinder (3D): the box of `n` cells on
/// `[0, RE − RI] × [0, π/2] (× [0, H])` mapped by `(s, θ, z) ↦ ((RI + s) cos θ, (RI + s) sin θ, z)`,
/// so that every node, mid-edge nodes included, lies on its circle (quadratic cells follow the arcs).
/// `n` = (radial, circumferential[, axial]) cells. The map keeps the orientation, and the groups are
/// the box's renamed: `INT` (r = RI), `EXT` (r = RE), `BAS` (y = 0), `GAUCHE` (x = 0), `SURFACE` in
/// 2D; `ZMIN`, `ZMAX` and `VOLUME` as in the box in 3D.
pub fn ring_mesh(cell: CellType, n: &[usize], radii: [f64; 2], height: Option<f64>) -> Result<Mesh> {
    let [ri, re] = radii;
    if !(ri.is_finite() && re.is_finite() && ri > 0.0 && re > ri) {
        return Err(Error::runtime("ring radii: expected 0 < RI < RE"));
    }
    let mut size = vec![re - ri, std::f64::consts::FRAC_PI_2];
    if cell.dim() == 3 {
        size.push(height.ok_or_else(|| Error::runtime("a 3D ring needs a height"))?);
    } else if height.is_some() {
        return Err(Error::runtime("a height applies to 3D rings (HEXA8, HEXA20) only"));
    }
    let mut m = box_mesh(cell, n, &size)?;
    for c in m.coords.iter_mut() {
        let (r, t) = (ri + c[0], c[1]);
        // Exact zeros on the cut planes (cos π/2 is 6e-17 in floating point).
        let (cs, sn) = if t == std::f64::consts::FRAC_PI_2 { (0.0, 1.0) } else { (t.cos(), t.sin()) };
        c[0] = r * cs;
        c[1] = r * sn;
    }
    let names: &[(&str, &str)] = if m.dim == 2 {
        &[("GAUCHE", "INT"), ("DROITE", "EXT"), ("HAUT", "GAUCHE")]
    } else {
        &[("XMIN", "INT"), ("XMAX", "EXT"), ("YMIN", "BAS"), ("YMAX", "GAUCHE")]
    };
    // Renamed together (GAUCHE is both an old and a new name in 2D).
    for groups in [&mut m.cell_groups, &mut m.node_groups] {
        let taken: Vec<(String, Vec<usize>)> =
            names.iter().filter_map(|(old, _)| groups.remove(*old).map(|v| (old.to_string(), v))).collect();
        for (old, v) in taken {
            let new = names.iter().find(|(o, _)| *o == old).unwrap().1;
            groups.insert(new.to_string(), v);
        }
    }
    Ok(m)
}

/// Add a cell to the mesh and to a cell group; its nodes to a node group.
fn push_cell(mesh: &mut Mesh, t: CellType, nodes: Vec<usize>, group: &str, with_nodes: bool) {
    let idx = mesh.cells.len();
    if with_nodes {
        mesh.node_groups.entry(group.to_string()).or_default().extend(nodes.iter().copied());
    }
    mesh.cells.push(nodes);
    mesh.cell_types.push(t);
    mesh.cell_groups.entry(group.to_string()).or_default().push(idx);
}

fn build_2d(mesh: &mut Mesh, g: &Grid, n: &[usize], cell: CellType) {
    let q = g.q;
    let (mx, my) = (g.m[0], g.m[1]);
    let seg = if q == 2 { CellType::Seg3 } else { CellType::Seg2 };
    // Boundary edges, counterclockwise around the square: (start, end) in
    // grid coordinates for cell `c` of the edge.
    type EdgeFn = Box<dyn Fn(usize) -> ([usize; 2], [usize; 2])>;
    let edges: [(&str, usize, EdgeFn); 4] = [
        ("BAS", n[0], Box::new(move |c| ([q * c, 0], [q * c + q, 0]))),
        ("DROITE", n[1], Box::new(move |c| ([mx, q * c], [mx, q * c + q]))),
        ("HAUT", n[0], Box::new(move |c| ([mx - q * c, my], [mx - q * c - q, my]))),
        ("GAUCHE", n[1], Box::new(move |c| ([0, my - q * c], [0, my - q * c - q]))),
    ];
    for (name, count, f) in edges.iter() {
        for c in 0..*count {
            let (a, b) = f(c);
            let mut nodes = vec![g.node([a[0], a[1], 0]), g.node([b[0], b[1], 0])];
            if q == 2 {
                nodes.push(g.node([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, 0]));
            }
            push_cell(mesh, seg, nodes, name, true);
        }
    }
    for b in 0..n[1] {
        for a in 0..n[0] {
            let (i0, j0) = (q * a, q * b);
            let corners = [[i0, j0], [i0 + q, j0], [i0 + q, j0 + q], [i0, j0 + q]];
            if matches!(cell, CellType::Tria3 | CellType::Tria6) {
                for tri in [[0, 1, 2], [0, 2, 3]] {
                    let v: Vec<[usize; 3]> = tri.iter().map(|&c| [corners[c][0], corners[c][1], 0]).collect();
                    push_split_cell(mesh, g, cell, v, "SURFACE");
                }
                continue;
            }
            let mut nodes: Vec<usize> = corners.iter().map(|p| g.node([p[0], p[1], 0])).collect();
            if q == 2 {
                for e in 0..4 {
                    let (p, r) = (corners[e], corners[(e + 1) % 4]);
                    nodes.push(g.node([(p[0] + r[0]) / 2, (p[1] + r[1]) / 2, 0]));
                }
            }
            push_cell(mesh, cell, nodes, "SURFACE", false);
        }
    }
    finish_node_groups(mesh);
}

/// Code_Aster's HEXA8 vertices (unit offsets) and HEXA20 edges.
const HEXA_VERTICES: [[usize; 3]; 8] =
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
const HEXA_EDGES: [(usize, usize); 12] =
    [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6), (6, 7), (7, 4)];

fn mid(a: [usize; 3], b: [usize; 3]) -> [usize; 3] {
    [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2]
}

fn build_3d(mesh: &mut Mesh, g: &Grid, n: &[usize], cell: CellType) {
    let q = g.q;
    let face_type = if q == 2 { CellType::Quad8 } else { CellType::Quad4 };
    let tria_type = if q == 2 { CellType::Tria6 } else { CellType::Tria3 };
    // Faces split into two triangles: all of them for tetrahedra, the z faces for prisms.
    let split = |axis: usize| match cell {
        CellType::Tetra4 | CellType::Tetra10 => true,
        CellType::Penta6 | CellType::Penta15 => axis == 2,
        _ => false,
    };
    // Triangles before quadrangles (Code_Aster's reading order), group after group within a type.
    let mut skin: Vec<(CellType, Vec<usize>, &str)> = Vec::new();
    // (name, fixed axis, at max?, u axis, v axis) with u x v = outward normal.
    let faces: [(&str, usize, bool, usize, usize); 6] = [
        ("XMIN", 0, false, 2, 1),
        ("XMAX", 0, true, 1, 2),
        ("YMIN", 1, false, 0, 2),
        ("YMAX", 1, true, 2, 0),
        ("ZMIN", 2, false, 1, 0),
        ("ZMAX", 2, true, 0, 1),
    ];
    for (name, axis, at_max, u, v) in faces {
        let fixed = if at_max { g.m[axis] } else { 0 };
        for b in 0..n[v] {
            for a in 0..n[u] {
                let at = |du: usize, dv: usize| {
                    let mut p = [0usize; 3];
                    p[axis] = fixed;
                    p[u] = q * a + du;
                    p[v] = q * b + dv;
                    p
                };
                let corners = [at(0, 0), at(q, 0), at(q, q), at(0, q)];
                if split(axis) {
                    // Along the diagonal at(0, 0)–at(q, q), from the lowest to the highest corner;
                    // u × v stays the outward normal of both triangles.
                    for tri in [[0, 1, 2], [0, 2, 3]] {
                        let v: Vec<[usize; 3]> = tri.iter().map(|&c| corners[c]).collect();
                        skin.push((tria_type, with_middles(g, tria_type, &v), name));
                    }
                    continue;
                }
                let mut nodes: Vec<usize> = corners.iter().map(|&p| g.node(p)).collect();
                if q == 2 {
                    for e in 0..4 {
                        nodes.push(g.node(mid(corners[e], corners[(e + 1) % 4])));
                    }
                }
                skin.push((face_type, nodes, name));
            }
        }
    }
    skin.sort_by_key(|(t, _, _)| *t != tria_type);
    for (t, nodes, name) in skin {
        push_cell(mesh, t, nodes, name, true);
    }
    for c in 0..n[2] {
        for b in 0..n[1] {
            for a in 0..n[0] {
                let base = [q * a, q * b, q * c];
                let corners: Vec<[usize; 3]> = HEXA_VERTICES
                    .iter()
                    .map(|o| [base[0] + q * o[0], base[1] + q * o[1], base[2] + q * o[2]])
                    .collect();
                match cell {
                    CellType::Tetra4 | CellType::Tetra10 => {
                        // Kuhn: (0,0,0) → +e_a → +e_b → (1,1,1) for each order (a, b, c) of the axes.
                        for (a, b) in [(0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)] {
                            let mut p1 = base;
                            p1[a] += q;
                            let mut p2 = p1;
                            p2[b] += q;
                            push_split_cell(mesh, g, cell, vec![corners[0], p1, p2, corners[6]], "VOLUME");
                        }
                        continue;
                    }
                    CellType::Penta6 | CellType::Penta15 => {
                        // The xy quadrangle's triangles (0, 1, 2) and (0, 2, 3), extruded along z.
                        for tri in [[0, 1, 2], [0, 2, 3]] {
                            let mut v: Vec<[usize; 3]> = tri.iter().map(|&c| corners[c]).collect();
                            v.extend(tri.iter().map(|&c| corners[c + 4]));
                            push_split_cell(mesh, g, cell, v, "VOLUME");
                        }
                        continue;
                    }
                    _ => {}
                }
                let mut nodes: Vec<usize> = corners.iter().map(|&p| g.node(p)).collect();
                if q == 2 {
                    for (s, e) in HEXA_EDGES {
                        nodes.push(g.node(mid(corners[s], corners[e])));
                    }
                }
                push_cell(mesh, cell, nodes, "VOLUME", false);
            }
        }
    }
    finish_node_groups(mesh);
}

/// The nodes of a simplex or prism on grid points `v` (its vertices), the
/// middle nodes added in Code_Aster's edge order for a quadratic type.
fn with_middles(g: &Grid, t: CellType, v: &[[usize; 3]]) -> Vec<usize> {
    let mut nodes: Vec<usize> = v.iter().map(|&p| g.node(p)).collect();
    if t.nnodes() > t.nvertices() {
        for &(a, b) in super::convert::edges(t) {
            nodes.push(g.node(mid(v[a], v[b])));
        }
    }
    nodes
}

/// Add a surface or volume simplex or prism with vertices on grid points `v`, reordered so that its
/// Jacobian is positive in Code_Aster's reference elements: a triangle counterclockwise; a
/// tetrahedron (reference nodes (0,1,0), (0,0,1), (0,0,0), (1,0,0)) or a prism (the triangle 1 2 3 at
/// ξ = −1 in the same (η, ζ) positions, 4 5 6 above it at ξ = +1) with
/// (x4 − x3)·((x1 − x3) × (x2 − x3)) > 0.
fn push_split_cell(mesh: &mut Mesh, g: &Grid, t: CellType, mut v: Vec<[usize; 3]>, group: &str) {
    let x = |i: usize| mesh.coords[g.node(v[i])];
    let d = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let sign = if mesh.dim == 2 {
        let (a, b) = (d(x(1), x(0)), d(x(2), x(0)));
        a[0] * b[1] - a[1] * b[0]
    } else {
        let (a, b, c) = (d(x(0), x(2)), d(x(1), x(2)), d(x(3), x(2)));
        c[0] * (a[1] * b[2] - a[2] * b[1]) + c[1] * (a[2] * b[0] - a[0] * b[2]) + c[2] * (a[0] * b[1] - a[1] * b[0])
    };
    if sign < 0.0 {
        v.swap(1, 2);
        if v.len() == 6 {
            v.swap(4, 5);
        }
    }
    let nodes = with_middles(g, t, &v);
    push_cell(mesh, t, nodes, group, false);
}

/// Node groups as Code_Aster builds them from cells: sorted by node number.
fn finish_node_groups(mesh: &mut Mesh) {
    for v in mesh.node_groups.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn quad4_counts_and_groups() {
        let m = box_mesh(CellType::Quad4, &[3, 2], &[3.0, 2.0]).unwrap();
        assert_eq!(m.nnodes(), 4 * 3);
        assert_eq!(m.cell_type_counts()[&CellType::Quad4], 6);
        assert_eq!(m.cell_type_counts()[&CellType::Seg2], 10);
        assert_eq!(m.node_groups["BAS"].len(), 4);
        assert_eq!(m.node_groups["GAUCHE"].len(), 3);
        for &i in &m.node_groups["HAUT"] {
            assert_eq!(m.coords[i][1], 2.0);
        }
        // Boundary cells come first (lower MED type code).
        assert_eq!(m.cell_types[0], CellType::Seg2);
    }

    #[test]
    fn hexa20_counts_and_positive_orientation() {
        let (nx, ny, nz) = (2usize, 3usize, 4usize);
        let m = box_mesh(CellType::Hexa20, &[nx, ny, nz], &[1.0, 2.0, 3.0]).unwrap();
        let vertices = (nx + 1) * (ny + 1) * (nz + 1);
        let edges = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
        assert_eq!(m.nnodes(), vertices + edges);
        assert_eq!(m.cell_type_counts()[&CellType::Hexa20], nx * ny * nz);
        assert_eq!(m.cell_type_counts()[&CellType::Quad8], 2 * (nx * ny + ny * nz + nx * nz));
        // Mid-edge nodes sit halfway between their vertices.
        for (c, t) in m.cells.iter().zip(&m.cell_types) {
            if *t == CellType::Hexa20 {
                for (k, (s, e)) in HEXA_EDGES.iter().enumerate() {
                    for ax in 0..3 {
                        let want = 0.5 * (m.coords[c[*s]][ax] + m.coords[c[*e]][ax]);
                        assert!((m.coords[c[8 + k]][ax] - want).abs() < 1e-12);
                    }
                }
            }
        }
        // Faces point outwards: (p1 - p0) x (p3 - p0) along the outward axis.
        for (name, axis, sign) in [
            ("XMIN", 0, -1.0),
            ("XMAX", 0, 1.0),
            ("YMIN", 1, -1.0),
            ("YMAX", 1, 1.0),
            ("ZMIN", 2, -1.0),
            ("ZMAX", 2, 1.0),
        ] {
            for &ci in &m.cell_groups[name] {
                let c = &m.cells[ci];
                let d = |a: usize, b: usize| Vector3::from(m.coords[c[b]]) - Vector3::from(m.coords[c[a]]);
                let cross = d(0, 1).cross(&d(0, 3));
                assert!(cross[axis] * sign > 0.0, "{name}");
            }
        }
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;
    use crate::fem::geometry::{bounded_cells, cell_coords, node_to_cells, outward_sign};
    use crate::fem::reference::{jacobian_det, node_coords, ref_centroid, ref_measure};
    use std::collections::BTreeMap;

    /// Vertex sets of the faces (3D) or edges (2D) of a cell, sorted.
    fn facets(t: CellType, c: &[usize]) -> Vec<Vec<usize>> {
        let local: &[&[usize]] = match t {
            CellType::Tria3 | CellType::Tria6 => &[&[0, 1], &[1, 2], &[2, 0]],
            CellType::Tetra4 | CellType::Tetra10 => &[&[0, 1, 2], &[0, 1, 3], &[0, 2, 3], &[1, 2, 3]],
            _ => &[&[0, 1, 2], &[3, 4, 5], &[0, 1, 4, 3], &[1, 2, 5, 4], &[2, 0, 3, 5]],
        };
        local
            .iter()
            .map(|f| {
                let mut v: Vec<usize> = f.iter().map(|&i| c[i]).collect();
                v.sort_unstable();
                v
            })
            .collect()
    }

    /// (cell type, cells per axis, lengths, expected cells, expected nodes, skin cells by type).
    #[allow(clippy::type_complexity)]
    fn cases() -> Vec<(CellType, Vec<usize>, Vec<f64>, usize, usize, Vec<(CellType, usize)>)> {
        let (nx, ny, nz) = (2usize, 3usize, 2usize);
        let v2 = (nx + 1) * (ny + 1);
        let v3 = v2 * (nz + 1);
        let e3 = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
        let quads3 = 2 * (nx * ny + ny * nz + nx * nz);
        vec![
            (CellType::Tria3, vec![nx, ny], vec![2.0, 1.5], 2 * nx * ny, v2, vec![(CellType::Seg2, 2 * (nx + ny))]),
            (
                CellType::Tria6,
                vec![nx, ny],
                vec![2.0, 1.5],
                2 * nx * ny,
                (2 * nx + 1) * (2 * ny + 1),
                vec![(CellType::Seg3, 2 * (nx + ny))],
            ),
            (
                CellType::Tetra4,
                vec![nx, ny, nz],
                vec![1.0, 2.0, 0.5],
                6 * nx * ny * nz,
                v3,
                vec![(CellType::Tria3, 2 * quads3)],
            ),
            (
                CellType::Tetra10,
                vec![nx, ny, nz],
                vec![1.0, 2.0, 0.5],
                6 * nx * ny * nz,
                (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1),
                vec![(CellType::Tria6, 2 * quads3)],
            ),
            (
                CellType::Penta6,
                vec![nx, ny, nz],
                vec![1.0, 2.0, 0.5],
                2 * nx * ny * nz,
                v3,
                vec![(CellType::Tria3, 4 * nx * ny), (CellType::Quad4, quads3 - 2 * nx * ny)],
            ),
            (
                CellType::Penta15,
                vec![nx, ny, nz],
                vec![1.0, 2.0, 0.5],
                2 * nx * ny * nz,
                v3 + e3 + nx * ny * (nz + 1),
                vec![(CellType::Tria6, 4 * nx * ny), (CellType::Quad8, quads3 - 2 * nx * ny)],
            ),
        ]
    }

    #[test]
    fn simplex_and_prism_boxes_counts_volumes_and_orientation() {
        for (t, n, size, ncells, nnodes, skin) in cases() {
            let m = box_mesh(t, &n, &size).unwrap();
            let dim = n.len();
            let counts = m.cell_type_counts();
            assert_eq!(counts[&t], ncells, "{t:?}");
            assert_eq!(m.nnodes(), nnodes, "{t:?}");
            for (st, k) in &skin {
                assert_eq!(counts[st], *k, "{t:?} {st:?}");
            }
            assert_eq!(counts.len(), 1 + skin.len(), "{t:?}");
            // Every node is used; cells positive at each of their nodes; volumes add up to the box.
            let mut used = vec![false; m.nnodes()];
            let mut volume = 0.0;
            for (c, nodes) in m.cells.iter().enumerate() {
                nodes.iter().for_each(|&i| used[i] = true);
                if m.cell_types[c] != t {
                    continue;
                }
                let xs = cell_coords(&m, c);
                for xi in node_coords(t) {
                    assert!(jacobian_det(t, &xs, xi, dim) > 0.0, "{t:?} M{}", c + 1);
                }
                volume += jacobian_det(t, &xs, &ref_centroid(t), dim) * ref_measure(t);
                // Middle nodes halfway between their vertices.
                if t.nnodes() > t.nvertices() {
                    for (e, &(a, b)) in crate::mesh::convert::edges(t).iter().enumerate() {
                        let (pa, pb, pm) = (xs[a], xs[b], xs[t.nvertices() + e]);
                        assert!((0..3).all(|ax| (pm[ax] - 0.5 * (pa[ax] + pb[ax])).abs() < 1e-12), "{t:?}");
                    }
                }
            }
            assert!(used.iter().all(|&u| u), "{t:?}: unused node");
            let box_volume: f64 = size.iter().product();
            assert!((volume - box_volume).abs() < 1e-12 * box_volume, "{t:?}: {volume}");
            // Conforming: every facet is shared by two cells or is a skin cell.
            let mut shared: BTreeMap<Vec<usize>, usize> = BTreeMap::new();
            for (c, nodes) in m.cells.iter().enumerate() {
                if m.cell_types[c] == t {
                    for f in facets(t, nodes) {
                        *shared.entry(f).or_default() += 1;
                    }
                }
            }
            assert!(shared.values().all(|&k| k <= 2), "{t:?}");
            let mut boundary: Vec<Vec<usize>> = shared.into_iter().filter(|(_, k)| *k == 1).map(|(f, _)| f).collect();
            let mut skins: Vec<Vec<usize>> = (0..m.cells.len())
                .filter(|&c| m.cell_types[c] != t)
                .map(|c| {
                    let mut v = m.cells[c][..m.cell_types[c].nvertices()].to_vec();
                    v.sort_unstable();
                    v
                })
                .collect();
            boundary.sort();
            skins.sort();
            assert_eq!(boundary, skins, "{t:?}");
            // Skin cells point out, bound one cell each, and cover their face of the box.
            let nc = node_to_cells(&m);
            let groups: &[(&str, usize, f64)] = if dim == 2 {
                &[("BAS", 1, 0.0), ("DROITE", 0, 1.0), ("HAUT", 1, 1.0), ("GAUCHE", 0, 0.0)]
            } else {
                &[
                    ("XMIN", 0, 0.0),
                    ("XMAX", 0, 1.0),
                    ("YMIN", 1, 0.0),
                    ("YMAX", 1, 1.0),
                    ("ZMIN", 2, 0.0),
                    ("ZMAX", 2, 1.0),
                ]
            };
            let mut previous_rank = 0;
            for &(g, axis, side) in groups {
                let mut measure = 0.0;
                for &c in &m.cell_groups[g] {
                    let st = m.cell_types[c];
                    let xs = cell_coords(&m, c);
                    assert!(xs.iter().all(|x| x[axis] == side * size[axis]), "{t:?} {g}");
                    assert_eq!(bounded_cells(&m, &nc, c, None).len(), 1, "{t:?} {g}");
                    assert_eq!(outward_sign(&m, &nc, c), Some(1.0), "{t:?} {g}");
                    measure += jacobian_det(st, &xs, &ref_centroid(st), dim) * ref_measure(st);
                }
                let face: f64 = (0..dim).filter(|&a| a != axis).map(|a| size[a]).product();
                assert!((measure - face).abs() < 1e-12 * face, "{t:?} {g}: {measure}");
                for &i in &m.node_groups[g] {
                    assert_eq!(m.coords[i][axis], side * size[axis], "{t:?} {g}");
                }
            }
            // Skin triangles come before skin quadrangles (Code_Aster's reading order).
            for &st in &m.cell_types {
                let rank = match st {
                    CellType::Seg2 | CellType::Seg3 => 0,
                    _ if st == t => 3,
                    CellType::Tria3 | CellType::Tria6 => 1,
                    _ => 2,
                };
                assert!(rank >= previous_rank, "{t:?}");
                previous_rank = rank;
            }
        }
    }

    #[test]
    fn box_refuses_other_cell_types() {
        for t in [CellType::Pyram5, CellType::Hexa27, CellType::Seg2] {
            let e = box_mesh(t, &[1, 1, 1], &[1.0, 1.0, 1.0]).unwrap_err();
            assert!(e.to_string().contains("TETRA10"), "{e}");
        }
        assert!(box_mesh(CellType::Tetra4, &[1, 1], &[1.0, 1.0]).is_err());
    }
}
