//! Geometry of skin (boundary) cells: normals from the shape functions, the
//! cells a skin cell bounds, Code_Aster's orientation test and the node
//! permutation that flips a skin cell.
//!
//! Normal convention (the one of Code_Aster's skin elements, and of
//! [`crate::fem::elasticity::boundary_points`]): for a segment with tangent
//! `t = ∂x/∂ξ` the normal is `(t_y, -t_x)`; for a face it is
//! `∂x/∂ξ × ∂x/∂η`. A segment run counterclockwise around a plane domain,
//! or a face whose nodes turn counterclockwise seen from outside a volume,
//! has its normal pointing out.

use crate::fem::reference::{node_coords, shape_deriv};
use crate::mesh::{CellType, Mesh};
use nalgebra::Vector3;
use std::collections::{BTreeMap, HashSet};

/// Can the cell type be a skin cell whose normal we compute (SEG2/3 of a
/// plane domain, TRIA3/6 and QUAD4/8/9 of a volume)?
pub fn is_skin_type(t: CellType) -> bool {
    use CellType::*;
    matches!(t, Seg2 | Seg3 | Tria3 | Tria6 | Quad4 | Quad8 | Quad9)
}

type V3 = Vector3<f64>;

/// `a / |a|`, or None for a vector of zero or non-finite (NaN, overflowing)
/// length.
fn unit(a: V3) -> Option<V3> {
    a.try_normalize(0.0).filter(|_| a.norm().is_finite())
}

/// The (not normalized) normal of a skin cell at the reference point `xi`:
/// `(t_y, -t_x, 0)` for a segment, `∂x/∂ξ × ∂x/∂η` for a face.
fn raw_normal(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3]) -> V3 {
    let dn = shape_deriv(t, xi);
    let mut t1 = V3::zeros();
    let mut t2 = V3::zeros();
    for (g, x) in dn.iter().zip(coords) {
        for k in 0..3 {
            t1[k] += g[0] * x[k];
            t2[k] += g[1] * x[k];
        }
    }
    if t.dim() == 1 {
        V3::new(t1[1], -t1[0], 0.0)
    } else {
        t1.cross(&t2)
    }
}

/// Unit normal of a skin cell at the reference point `xi`; None where the
/// map is degenerate or the type is not a skin type.
pub fn normal_at(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3]) -> Option<[f64; 3]> {
    if !is_skin_type(t) || coords.len() != t.nnodes() {
        return None;
    }
    let n = raw_normal(t, coords, xi);
    // Relative to the cell size, so that a tiny but valid cell is not "degenerate".
    let x0 = V3::from(coords[0]);
    let h = coords.iter().map(|x| (V3::from(*x) - x0).norm()).fold(0.0, f64::max);
    let scale = if t.dim() == 1 { h } else { h * h };
    // (Written so that a NaN normal is refused too.)
    if n.norm().partial_cmp(&(1e-12 * scale)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    unit(n).map(Into::into)
}

/// Unit normals of a skin cell at each of its nodes (the shape-function
/// derivatives taken at the node's reference coordinates, as Code_Aster's
/// `canort` does).
pub fn node_normals(t: CellType, coords: &[[f64; 3]]) -> Vec<Option<[f64; 3]>> {
    if !is_skin_type(t) {
        return vec![None; t.nnodes()];
    }
    node_coords(t).iter().map(|xi| normal_at(t, coords, xi)).collect()
}

/// Centroid of the vertices of a cell (Code_Aster's "centre de gravité" of
/// `oriema`: mid-side and centre nodes are left out).
pub fn vertex_centroid(t: CellType, coords: &[[f64; 3]]) -> [f64; 3] {
    let nv = t.nvertices().min(coords.len()).max(1);
    let mut g = [0.0; 3];
    for x in &coords[..nv] {
        for k in 0..3 {
            g[k] += x[k] / nv as f64;
        }
    }
    g
}

/// The new connectivity order that flips a skin cell, as Code_Aster's
/// `oriema` builds it: the vertices reversed, the mid-side nodes following
/// their sides, a centre node kept (`new[i] = old[perm[i]]`).
pub fn flip_permutation(t: CellType) -> Option<&'static [usize]> {
    use CellType::*;
    Some(match t {
        Seg2 => &[1, 0],
        Seg3 => &[1, 0, 2],
        Tria3 => &[2, 1, 0],
        Tria6 => &[2, 1, 0, 4, 3, 5],
        Quad4 => &[3, 2, 1, 0],
        Quad8 => &[3, 2, 1, 0, 6, 5, 4, 7],
        Quad9 => &[3, 2, 1, 0, 6, 5, 4, 7, 8],
        _ => return None,
    })
}

/// Code_Aster's orientation test of a skin cell against a cell it bounds
/// (`oriema`): the normal from the first nodes (`(x2 - x1)` turned by -90°
/// for a segment, `(x2 - x1) × (x3 - x1)` for a face), dotted with the unit
/// vector from the bounded cell's vertex centroid to the skin cell's. Positive
/// when the normal points out of the bounded cell, negative when it points
/// in; None for a degenerate cell.
pub fn outward_measure(
    skin: CellType,
    skin_coords: &[[f64; 3]],
    support: CellType,
    support_coords: &[[f64; 3]],
) -> Option<f64> {
    if !is_skin_type(skin) || skin_coords.len() < 3 - usize::from(skin.dim() == 1) {
        return None;
    }
    let x = |i: usize| V3::from(skin_coords[i]);
    let n12 = x(1) - x(0);
    let n = if skin.dim() == 1 { V3::new(n12[1], -n12[0], 0.0) } else { n12.cross(&(x(2) - x(0))) };
    let n = unit(n)?;
    let d = unit(V3::from(vertex_centroid(skin, skin_coords)) - V3::from(vertex_centroid(support, support_coords)))?;
    Some(n.dot(&d))
}

/// For each node, the cells that hold it (ascending cell numbers).
pub fn node_to_cells(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); mesh.coords.len()];
    for (c, nodes) in mesh.cells.iter().enumerate() {
        for &n in nodes {
            if out[n].last() != Some(&c) {
                out[n].push(c);
            }
        }
    }
    out
}

/// The cells bounded by skin cell `skin`: cells of one dimension more that
/// hold every node of it, in ascending order, restricted to `allowed` when
/// given (Code_Aster's `utmasu`).
pub fn bounded_cells(
    mesh: &Mesh,
    node_cells: &[Vec<usize>],
    skin: usize,
    allowed: Option<&HashSet<usize>>,
) -> Vec<usize> {
    let nodes = &mesh.cells[skin];
    let Some(&first) = nodes.first() else { return Vec::new() };
    let want = mesh.cell_types[skin].dim() + 1;
    node_cells[first]
        .iter()
        .copied()
        .filter(|&c| c != skin && mesh.cell_types[c].dim() == want)
        .filter(|c| allowed.is_none_or(|a| a.contains(c)))
        .filter(|&c| nodes.iter().all(|n| mesh.cells[c].contains(n)))
        .collect()
}

/// The cells of the mesh's dimension whose map is not positive: a Jacobian determinant ≤ 0 at one of
/// their nodes or at a point of a rule of degree 4 (a generated or distorted mesh is checked with it).
pub fn inverted_cells(mesh: &Mesh) -> Vec<usize> {
    use crate::fem::quadrature::{rule_for_degree, RefDomain};
    use crate::fem::reference::{jacobian_det, node_coords};
    (0..mesh.ncells())
        .filter(|&c| {
            let t = mesh.cell_types[c];
            if t.dim() != mesh.dim {
                return false;
            }
            let x = cell_coords(mesh, c);
            let rule = rule_for_degree(RefDomain::of(t), 4);
            rule.points.iter().chain(node_coords(t)).any(|q| {
                let d = jacobian_det(t, &x, q, mesh.dim);
                d.is_nan() || d <= 0.0
            })
        })
        .collect()
}

/// Node coordinates of cell `c`.
pub fn cell_coords(mesh: &Mesh, c: usize) -> Vec<[f64; 3]> {
    mesh.cells[c].iter().map(|&n| mesh.coords[n]).collect()
}

/// The sign that makes skin cell `skin`'s normal point out of the cells it
/// bounds: +1 or -1 when they are all on one side of it, None when it bounds
/// no cell or lies between cells on both sides.
pub fn outward_sign(mesh: &Mesh, node_cells: &[Vec<usize>], skin: usize) -> Option<f64> {
    let t = mesh.cell_types[skin];
    let xs = cell_coords(mesh, skin);
    let mut sign = None;
    for v in bounded_cells(mesh, node_cells, skin, None) {
        let m = outward_measure(t, &xs, mesh.cell_types[v], &cell_coords(mesh, v))?;
        let s = if m < 0.0 { -1.0 } else { 1.0 };
        match sign {
            None => sign = Some(s),
            Some(p) if p != s => return None,
            _ => {}
        }
    }
    sign
}

/// Unit normals at the nodes of skin cells: at each node, the mean of the
/// unit normals of the cells holding it (each cell's normal multiplied by
/// `signs[i]` for `cells[i]`), normalized. Err names the first degenerate
/// cell, or a node where the normals cancel.
pub fn averaged_node_normals(mesh: &Mesh, cells: &[usize], signs: &[f64]) -> Result<BTreeMap<usize, [f64; 3]>, String> {
    let mut sum: BTreeMap<usize, V3> = BTreeMap::new();
    for (&c, &s) in cells.iter().zip(signs) {
        let t = mesh.cell_types[c];
        if !is_skin_type(t) {
            return Err(format!("cell {} ({}) is not a boundary cell with a normal", mesh.cell_names[c], t.name()));
        }
        for (&node, n) in mesh.cells[c].iter().zip(node_normals(t, &cell_coords(mesh, c))) {
            let n = n.ok_or_else(|| format!("cell {} is degenerate: no normal", mesh.cell_names[c]))?;
            *sum.entry(node).or_insert_with(V3::zeros) += s * V3::from(n);
        }
    }
    let mut out = BTreeMap::new();
    for (node, v) in sum {
        let n = unit(v)
            .filter(|_| v.norm() > 1e-8)
            .ok_or_else(|| format!("the normals cancel at node {}", mesh.node_names[node]))?;
        out.insert(node, n.into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::box_mesh;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    /// Every node of a reference cell, flipped, keeps its position on the
    /// reversed cell: mid-side nodes stay between the same two vertices.
    #[test]
    fn flips_reverse_the_normal_and_keep_the_sides() {
        use CellType::*;
        for t in [Seg2, Seg3, Tria3, Tria6, Quad4, Quad8, Quad9] {
            let p = flip_permutation(t).unwrap();
            assert_eq!(p.len(), t.nnodes());
            // A permutation.
            let mut s = p.to_vec();
            s.sort_unstable();
            assert_eq!(s, (0..t.nnodes()).collect::<Vec<_>>(), "{}", t.name());
            // Put the reference cell in the plane z = 0 (x, y from the reference).
            let xs: Vec<[f64; 3]> = node_coords(t).iter().map(|x| [x[0], x[1], 0.0]).collect();
            let flipped: Vec<[f64; 3]> = p.iter().map(|&i| xs[i]).collect();
            // Each non-vertex node of the flipped cell sits where the reference
            // element puts it: at the midpoint of the two vertices (or the
            // centroid of all vertices) it is attached to by the node order.
            let r = node_coords(t);
            let nv = t.nvertices();
            for i in nv..t.nnodes() {
                let mid = |a: usize, b: usize| (0..3).all(|k| ((r[a][k] + r[b][k]) / 2.0 - r[i][k]).abs() < 1e-12);
                let pair = (0..nv).flat_map(|a| (a + 1..nv).map(move |b| (a, b))).find(|&(a, b)| mid(a, b));
                let expect = match pair {
                    Some((a, b)) => [0, 1, 2].map(|k| (flipped[a][k] + flipped[b][k]) / 2.0),
                    None => vertex_centroid(t, &flipped),
                };
                assert!(close(flipped[i], expect), "{} node {i}", t.name());
            }
            let n0 = normal_at(t, &xs, &[0.2, 0.1, 0.0]).unwrap();
            let xi_c = crate::fem::reference::ref_centroid(t);
            let n1 = normal_at(t, &flipped, &xi_c).unwrap();
            let n0c = normal_at(t, &xs, &xi_c).unwrap();
            assert!(close(n0, n0c), "{}: a plane cell has one normal", t.name());
            assert!(close(n1, [-n0[0], -n0[1], -n0[2]]), "{}: flip reverses the normal", t.name());
        }
    }

    #[test]
    fn code_aster_permutations() {
        // oriema: vertices reversed, mid-side nodes follow, a centre node stays.
        assert_eq!(flip_permutation(CellType::Seg3).unwrap(), &[1, 0, 2]);
        assert_eq!(flip_permutation(CellType::Tria6).unwrap(), &[2, 1, 0, 4, 3, 5]);
        assert_eq!(flip_permutation(CellType::Quad8).unwrap(), &[3, 2, 1, 0, 6, 5, 4, 7]);
        assert_eq!(flip_permutation(CellType::Quad9).unwrap(), &[3, 2, 1, 0, 6, 5, 4, 7, 8]);
        assert!(flip_permutation(CellType::Hexa8).is_none());
    }

    #[test]
    fn unit_square_skin_normals_point_out() {
        for t in [CellType::Quad4, CellType::Quad8] {
            let m = box_mesh(t, &[2, 3], &[1.0, 1.0]).unwrap();
            let nc = node_to_cells(&m);
            let expect = [("BAS", [0.0, -1.0, 0.0]), ("DROITE", [1.0, 0.0, 0.0]), ("HAUT", [0.0, 1.0, 0.0])];
            for (g, e) in expect.iter().chain([("GAUCHE", [-1.0, 0.0, 0.0])].iter()) {
                for &c in &m.cell_groups[*g] {
                    let xs = cell_coords(&m, c);
                    for n in node_normals(m.cell_types[c], &xs) {
                        assert!(close(n.unwrap(), *e), "{g}");
                    }
                    let v = bounded_cells(&m, &nc, c, None);
                    assert_eq!(v.len(), 1);
                    let meas = outward_measure(m.cell_types[c], &xs, m.cell_types[v[0]], &cell_coords(&m, v[0]));
                    assert!(meas.unwrap() > 0.0);
                    assert_eq!(outward_sign(&m, &nc, c), Some(1.0));
                }
            }
        }
    }

    #[test]
    fn unit_cube_skin_normals_point_out() {
        for t in [CellType::Hexa8, CellType::Hexa20] {
            let mut m = box_mesh(t, &[2, 1, 2], &[1.0, 1.0, 1.0]).unwrap();
            let faces = [
                ("XMIN", [-1.0, 0.0, 0.0]),
                ("XMAX", [1.0, 0.0, 0.0]),
                ("YMIN", [0.0, -1.0, 0.0]),
                ("YMAX", [0.0, 1.0, 0.0]),
                ("ZMIN", [0.0, 0.0, -1.0]),
                ("ZMAX", [0.0, 0.0, 1.0]),
            ];
            let nc = node_to_cells(&m);
            for (g, e) in faces {
                let cells = m.cell_groups[g].clone();
                for &c in &cells {
                    for n in node_normals(m.cell_types[c], &cell_coords(&m, c)) {
                        assert!(close(n.unwrap(), e), "{g}");
                    }
                    assert_eq!(outward_sign(&m, &nc, c), Some(1.0), "{g}");
                }
                let normals = averaged_node_normals(&m, &cells, &vec![1.0; cells.len()]).unwrap();
                assert!(normals.values().all(|n| close(*n, e)));
                // Flipped, the cells test as inward.
                for &c in &cells {
                    let p = flip_permutation(m.cell_types[c]).unwrap();
                    m.cells[c] = p.iter().map(|&i| m.cells[c][i]).collect();
                    assert_eq!(outward_sign(&m, &nc, c), Some(-1.0), "{g}");
                    for n in node_normals(m.cell_types[c], &cell_coords(&m, c)) {
                        assert!(close(n.unwrap(), [-e[0], -e[1], -e[2]]), "{g}");
                    }
                }
            }
        }
    }

    #[test]
    fn averaged_normal_at_a_corner() {
        // Two edges of the unit square meeting at (1, 0): normals (0,-1) and (1,0).
        let m = box_mesh(CellType::Quad4, &[1, 1], &[1.0, 1.0]).unwrap();
        let cells = [m.cell_groups["BAS"][0], m.cell_groups["DROITE"][0]];
        let normals = averaged_node_normals(&m, &cells, &[1.0, 1.0]).unwrap();
        let corner = (0..m.coords.len()).find(|&n| close(m.coords[n], [1.0, 0.0, 0.0])).unwrap();
        let s = 0.5f64.sqrt();
        assert!(close(normals[&corner], [s, -s, 0.0]));
        // Opposite signs cancel at the shared node.
        assert!(averaged_node_normals(&m, &[cells[0], cells[0]], &[1.0, -1.0]).is_err());
    }

    #[test]
    fn inclined_segment_normal() {
        // From (0,0) to (3,4): tangent (3,4)/5, normal (4,-3)/5.
        let xs = [[0.0, 0.0, 0.0], [3.0, 4.0, 0.0]];
        let n = normal_at(CellType::Seg2, &xs, &[0.0; 3]).unwrap();
        assert!(close(n, [0.8, -0.6, 0.0]));
        assert!(normal_at(CellType::Seg2, &[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0]], &[0.0; 3]).is_none());
    }

    /// A distorted box (`mesh::generate::distort`: vertices moved by up to 0.2·h, mid-edge nodes by up
    /// to 0.05·h off their edges' middles) of every family keeps positive Jacobians, its nodes on the
    /// box's faces on them, and moves its inner nodes; a folded cell is found.
    #[test]
    fn distorted_boxes_keep_positive_jacobians() {
        use crate::mesh::generate::{distort, Distortion};
        use CellType::*;
        for t in [Quad4, Quad8, Tria3, Tria6, Hexa8, Hexa20, Tetra4, Tetra10, Penta6, Penta15] {
            let dim = t.dim();
            let (n, size) = (vec![3; dim], vec![3.0; dim]);
            let straight = box_mesh(t, &n, &size).unwrap();
            let mut m = straight.clone();
            let bend = if t.nnodes() > t.nvertices() { 0.05 } else { 0.0 };
            distort(&mut m, &n, &size, Distortion { shift: 0.2, bend, seed: 7 }).unwrap();
            assert!(inverted_cells(&m).is_empty(), "{}", t.name());
            let mut moved = 0;
            for (a, b) in straight.coords.iter().zip(&m.coords) {
                for k in 0..dim {
                    let on_face = a[k] == 0.0 || a[k] == 3.0;
                    assert!(!on_face || a[k] == b[k], "{}: a node left the face {k} = {}", t.name(), a[k]);
                    moved += usize::from((a[k] - b[k]).abs() > 1e-3);
                }
            }
            assert!(moved > 0, "{}", t.name());
            assert_eq!(
                (&m.cells, &m.cell_groups, &m.node_groups),
                (&straight.cells, &straight.cell_groups, &straight.node_groups)
            );
        }
        let mut m = box_mesh(Quad4, &[1, 1], &[1.0, 1.0]).unwrap();
        m.coords.swap(0, 1);
        assert_eq!(inverted_cells(&m).len(), 1);
    }
}
