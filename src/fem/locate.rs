//! Points located in a mesh, as Code_Aster's collocation (PROJ_CHAMP METHODE='COLLOCATION', which
//! MACR_LIGN_COUPE projects through) locates them: the first cell, in the order of the mesh, whose
//! reference domain holds the point (within round-off); else, within a maximum distance, the nearest cell,
//! the point being taken there at its own reference coordinates when it lies just outside (the field is
//! then extrapolated a little, as `pjefmi` keeps the Newton solution) or at the nearest point of the cell.

use super::reference::{inverse_map, map_to_real, outside_distance, InverseMapError, InverseMapOptions};
use crate::mesh::{CellType, Mesh};
use nalgebra::Vector3;

/// Where a point lies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Located {
    pub cell: usize,
    /// The reference coordinates the cell's shape functions are taken at.
    pub xi: [f64; 3],
    /// The distance from the point to the cell (0 inside).
    pub distance: f64,
}

/// The cells a point is searched in, with their bounding boxes.
pub struct Locator<'m> {
    mesh: &'m Mesh,
    cells: Vec<usize>,
    boxes: Vec<([f64; 3], [f64; 3])>,
}

/// Reference coordinates beyond the domain by more than this are not extrapolated to: the nearest point
/// of the cell is taken (`pjeflo`'s 1e-2).
const EXTRAPOLATE: f64 = 1.0e-2;
/// A point inside up to this (in reference units) is inside (the barycentric tolerance of `pj2da1`).
const INSIDE: f64 = 1.0e-10;

/// The reference point of the domain of `t` nearest to `xi` (exact for segments, quadrangles and
/// hexahedra; simplices and the other shapes clamped coordinate by coordinate).
fn clamp_to_domain(t: CellType, xi: &[f64; 3]) -> [f64; 3] {
    use CellType::*;
    let c = |v: f64| v.clamp(-1.0, 1.0);
    let simplex = |p: &mut [f64]| {
        for v in p.iter_mut() {
            *v = v.max(0.0);
        }
        let s: f64 = p.iter().sum();
        if s > 1.0 {
            // Down onto the face x + y (+ z) = 1 along its normal, then clamped again.
            let d = (s - 1.0) / p.len() as f64;
            for v in p.iter_mut() {
                *v = (*v - d).max(0.0);
            }
            let s: f64 = p.iter().sum();
            if s > 1.0 {
                for v in p.iter_mut() {
                    *v /= s;
                }
            }
        }
    };
    let mut p = *xi;
    match t {
        Poi1 => p = [0.0; 3],
        Seg2 | Seg3 | Seg4 => p[0] = c(p[0]),
        Quad4 | Quad8 | Quad9 => {
            p[0] = c(p[0]);
            p[1] = c(p[1]);
        }
        Hexa8 | Hexa20 | Hexa27 => p = [c(p[0]), c(p[1]), c(p[2])],
        Tria3 | Tria6 | Tria7 => simplex(&mut p[..2]),
        Tetra4 | Tetra10 => simplex(&mut p[..3]),
        Penta6 | Penta15 | Penta18 => {
            p[0] = c(p[0]);
            simplex(&mut p[1..3]);
        }
        Pyram5 | Pyram13 => {
            p[2] = p[2].clamp(0.0, 1.0);
            let r = 1.0 - p[2];
            let s = p[0].abs() + p[1].abs();
            if s > r && s > 0.0 {
                p[0] *= r / s;
                p[1] *= r / s;
            }
        }
    }
    p
}

impl<'m> Locator<'m> {
    /// A locator over `cells` of `mesh` (searched in increasing order).
    pub fn new(mesh: &'m Mesh, mut cells: Vec<usize>) -> Locator<'m> {
        cells.sort_unstable();
        cells.dedup();
        let boxes = cells
            .iter()
            .map(|&c| {
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for &n in &mesh.cells[c] {
                    for k in 0..3 {
                        lo[k] = lo[k].min(mesh.coords[n][k]);
                        hi[k] = hi[k].max(mesh.coords[n][k]);
                    }
                }
                (lo, hi)
            })
            .collect();
        Locator { mesh, cells, boxes }
    }

    fn coords(&self, c: usize) -> Vec<[f64; 3]> {
        self.mesh.cells[c].iter().map(|&n| self.mesh.coords[n]).collect()
    }

    /// The candidates whose box, widened by `margin` (plus round-off of the box's size), holds `x`.
    fn candidates<'s>(&'s self, x: &'s [f64; 3], margin: f64) -> impl Iterator<Item = usize> + 's {
        self.cells.iter().zip(&self.boxes).filter_map(move |(&c, (lo, hi))| {
            let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
            let m = margin + 1e-8 * size;
            (0..3).all(|k| x[k] >= lo[k] - m && x[k] <= hi[k] + m).then_some(c)
        })
    }

    /// Where `x` lies: inside a cell, or (None when `dmax` is 0) within `dmax` of one — strictly.
    pub fn locate(&self, x: &[f64; 3], dmax: f64) -> Option<Located> {
        let exact = InverseMapOptions { outside_tol: INSIDE, ..Default::default() };
        for c in self.candidates(x, 0.0) {
            let t = self.mesh.cell_types[c];
            if let Ok(r) = inverse_map(t, &self.coords(c), x, &exact) {
                return Some(Located { cell: c, xi: r.xi, distance: 0.0 });
            }
        }
        if dmax <= 0.0 {
            return None;
        }
        let any = InverseMapOptions { outside_tol: f64::INFINITY, ..Default::default() };
        let mut best: Option<Located> = None;
        for c in self.candidates(x, dmax) {
            let t = self.mesh.cell_types[c];
            let coords = self.coords(c);
            let xi = match inverse_map(t, &coords, x, &any) {
                Ok(r) => r.xi,
                Err(InverseMapError::Outside { xi, .. }) => xi,
                Err(_) => continue,
            };
            let near = clamp_to_domain(t, &xi);
            let d = (Vector3::from(*x) - Vector3::from(map_to_real(t, &coords, &near))).norm();
            if d < dmax && best.is_none_or(|b| d < b.distance) {
                let at = if outside_distance(t, &xi) <= EXTRAPOLATE { xi } else { near };
                best = Some(Located { cell: c, xi: at, distance: d });
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::reference::shape;

    /// Two QUAD4 side by side, [0,1]x[0,1] and [1,2]x[0,1].
    fn two_quads() -> Mesh {
        let mut m = Mesh { dim: 2, ..Default::default() };
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (0.0, 1.0), (1.0, 1.0), (2.0, 1.0)] {
            m.coords.push([x, y, 0.0]);
            m.node_names.push(format!("N{}", m.coords.len()));
        }
        m.cells = vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]];
        m.cell_types = vec![CellType::Quad4; 2];
        m.cell_names = vec!["M1".into(), "M2".into()];
        m
    }

    #[test]
    fn a_point_is_found_in_the_first_cell_that_holds_it() {
        let m = two_quads();
        let l = Locator::new(&m, vec![1, 0]);
        let p = l.locate(&[1.5, 0.25, 0.0], 0.0).unwrap();
        assert_eq!(p.cell, 1);
        assert!((p.xi[0] - 0.0).abs() < 1e-12 && (p.xi[1] + 0.5).abs() < 1e-12);
        // On the shared edge: the first cell in the mesh's order.
        assert_eq!(l.locate(&[1.0, 0.5, 0.0], 0.0).unwrap().cell, 0);
        // Outside: nothing without a distance.
        assert!(l.locate(&[2.1, 0.5, 0.0], 0.0).is_none());
    }

    #[test]
    fn a_point_outside_is_taken_within_the_distance_only() {
        let m = two_quads();
        let l = Locator::new(&m, vec![0, 1]);
        // 0.001 beyond x = 2: within 0.01, at its own (extrapolated) reference coordinates.
        let p = l.locate(&[2.001, 0.5, 0.0], 0.01).unwrap();
        assert_eq!(p.cell, 1);
        assert!((p.distance - 0.001).abs() < 1e-12);
        assert!((p.xi[0] - 1.002).abs() < 1e-9, "{:?}", p.xi);
        // Farther out, the nearest point of the cell.
        let p = l.locate(&[2.5, 0.5, 0.0], 1.0).unwrap();
        assert!((p.xi[0] - 1.0).abs() < 1e-12 && (p.distance - 0.5).abs() < 1e-12);
        // The distance is strict.
        assert!(l.locate(&[2.5, 0.5, 0.0], 0.5).is_none());
        // A linear field is interpolated exactly.
        let p = l.locate(&[0.3, 0.7, 0.0], 0.0).unwrap();
        let n = shape(CellType::Quad4, &p.xi);
        let f: f64 = m.cells[p.cell].iter().zip(&n).map(|(&k, w)| w * (m.coords[k][0] + 2.0 * m.coords[k][1])).sum();
        assert!((f - 1.7).abs() < 1e-12);
    }
}
