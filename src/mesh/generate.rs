//! Structured box meshes with named boundary groups (fixtures, benchmarks,
//! `aster mesh box`).
//!
//! * 2D, `QUAD4` / `QUAD8` cells on `[0, LX] x [0, LY]`: boundary edges as
//!   `SEG2` / `SEG3` cells in the cell groups `BAS` (y = 0), `DROITE`
//!   (x = LX), `HAUT` (y = LY), `GAUCHE` (x = 0), the same names as node
//!   groups (every node on that edge), and the cell group `SURFACE` holding
//!   the quadrangles.
//! * 3D, `HEXA8` / `HEXA20` cells on `[0, LX] x [0, LY] x [0, LZ]`: boundary
//!   faces as `QUAD4` / `QUAD8` cells in the cell groups `XMIN`, `XMAX`,
//!   `YMIN`, `YMAX`, `ZMIN`, `ZMAX`, the same names as node groups, and the
//!   cell group `VOLUME` holding the hexahedra.
//!
//! Nodes are numbered along x first, then y, then z, over the grid of
//! vertices and mid-edge points (`N1, N2, ...`). Cells come type by type in
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

/// Build a structured box. `n` holds the cells per axis, `size` the box
/// lengths (two values for QUAD4/QUAD8, three for HEXA8/HEXA20).
pub fn box_mesh(cell: CellType, n: &[usize], size: &[f64]) -> Result<Mesh> {
    let (dim, q) = match cell {
        CellType::Quad4 => (2, 1),
        CellType::Quad8 => (2, 2),
        CellType::Hexa8 => (3, 1),
        CellType::Hexa20 => (3, 2),
        other => {
            return Err(Error::runtime(format!(
                "box meshes are made of QUAD4, QUAD8, HEXA8 or HEXA20 cells, not {}",
                other.name()
            )))
        }
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

    // Nodes: grid points with at most one odd index (all of them when linear).
    let mut grid = Grid { q, m, id: vec![usize::MAX; npoints] };
    let mut mesh = Mesh { dim, named_nodes: true, ..Mesh::default() };
    for k in 0..=m[2] {
        for j in 0..=m[1] {
            for i in 0..=m[0] {
                let odd = (i % 2) + (j % 2) + (k % 2);
                if q == 2 && odd > 1 {
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
                let mut nodes: Vec<usize> = corners.iter().map(|&p| g.node(p)).collect();
                if q == 2 {
                    for e in 0..4 {
                        nodes.push(g.node(mid(corners[e], corners[(e + 1) % 4])));
                    }
                }
                push_cell(mesh, face_type, nodes, name, true);
            }
        }
    }
    for c in 0..n[2] {
        for b in 0..n[1] {
            for a in 0..n[0] {
                let base = [q * a, q * b, q * c];
                let corners: Vec<[usize; 3]> = HEXA_VERTICES
                    .iter()
                    .map(|o| [base[0] + q * o[0], base[1] + q * o[1], base[2] + q * o[2]])
                    .collect();
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
