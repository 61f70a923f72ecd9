//! Reference (parent) elements in Code_Aster's conventions.
//!
//! For every [`CellType`] this module gives the reference domain, the
//! reference coordinates of the nodes in Code_Aster's local node order, the
//! Lagrange / serendipity shape functions and their first derivatives, the
//! isoparametric map (reference point → real point), its Jacobian, and the
//! inverse map (real point → reference point, by Newton iterations).
//!
//! Conventions, checked against Code_Aster's sources (`bibfor/elements/elrfno.F90`
//! for node coordinates, `elrfvf.F90` for shape functions, `elraca.F90` for the
//! reference measures; see also Code_Aster documentation R3.01.01):
//!
//! | cell            | domain                                        | measure |
//! |-----------------|-----------------------------------------------|---------|
//! | POI1            | a point                                       | 1       |
//! | SEG2/3          | x ∈ [-1, 1]                                   | 2       |
//! | TRIA3/6         | x, y ≥ 0, x + y ≤ 1; vertices (0,0),(1,0),(0,1) | 1/2   |
//! | QUAD4/8/9       | [-1, 1]²                                      | 4       |
//! | TETRA4/10       | x, y, z ≥ 0, x + y + z ≤ 1; **vertices (0,1,0),(0,0,1),(0,0,0),(1,0,0)** | 1/6 |
//! | PENTA6/15       | x ∈ [-1, 1] (axis), (y, z) in the unit triangle; vertices 1-3 on x = -1 | 1 |
//! | PYRAM5/13       | 0 ≤ z ≤ 1, abs(x) + abs(y) ≤ 1 - z; base vertices (1,0),(0,1),(-1,0),(0,-1), apex (0,0,1) | 2/3 |
//! | HEXA8/20/27     | [-1, 1]³                                      | 8       |
//!
//! Note the unusual tetrahedron and prism vertex orders: they are Code_Aster's,
//! and the shape functions follow them (e.g. TETRA4: N1 = y, N2 = z,
//! N3 = 1 - x - y - z, N4 = x).
//!
//! Shape-function derivatives are computed exactly by forward-mode automatic
//! differentiation (a small dual-number type), so each family is written once.
//!
//! Reference points are always `[f64; 3]`; unused coordinates (beyond the
//! cell's dimension) are ignored and reported as 0.

use crate::mesh::CellType;
use nalgebra::{Matrix2, Matrix3, Vector3};
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

// ---------------------------------------------------------------------------
// Dual numbers: a value and its gradient with respect to the 3 reference
// coordinates.
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq)]
struct D {
    v: f64,
    g: [f64; 3],
}

impl D {
    fn c(v: f64) -> D {
        D { v, g: [0.0; 3] }
    }
    fn var(v: f64, k: usize) -> D {
        let mut g = [0.0; 3];
        g[k] = 1.0;
        D { v, g }
    }
}

impl Add for D {
    type Output = D;
    fn add(self, o: D) -> D {
        D { v: self.v + o.v, g: [self.g[0] + o.g[0], self.g[1] + o.g[1], self.g[2] + o.g[2]] }
    }
}
impl Sub for D {
    type Output = D;
    fn sub(self, o: D) -> D {
        D { v: self.v - o.v, g: [self.g[0] - o.g[0], self.g[1] - o.g[1], self.g[2] - o.g[2]] }
    }
}
impl Mul for D {
    type Output = D;
    fn mul(self, o: D) -> D {
        D {
            v: self.v * o.v,
            g: [
                self.g[0] * o.v + self.v * o.g[0],
                self.g[1] * o.v + self.v * o.g[1],
                self.g[2] * o.v + self.v * o.g[2],
            ],
        }
    }
}
impl Div for D {
    type Output = D;
    fn div(self, o: D) -> D {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        D { v: q, g: [(self.g[0] - q * o.g[0]) * inv, (self.g[1] - q * o.g[1]) * inv, (self.g[2] - q * o.g[2]) * inv] }
    }
}
impl Neg for D {
    type Output = D;
    fn neg(self) -> D {
        D { v: -self.v, g: [-self.g[0], -self.g[1], -self.g[2]] }
    }
}
impl Add<f64> for D {
    type Output = D;
    fn add(self, o: f64) -> D {
        D { v: self.v + o, g: self.g }
    }
}
impl Sub<f64> for D {
    type Output = D;
    fn sub(self, o: f64) -> D {
        D { v: self.v - o, g: self.g }
    }
}
impl Mul<f64> for D {
    type Output = D;
    fn mul(self, o: f64) -> D {
        D { v: self.v * o, g: [self.g[0] * o, self.g[1] * o, self.g[2] * o] }
    }
}
impl Add<D> for f64 {
    type Output = D;
    fn add(self, o: D) -> D {
        o + self
    }
}
impl Sub<D> for f64 {
    type Output = D;
    fn sub(self, o: D) -> D {
        D { v: self - o.v, g: [-o.g[0], -o.g[1], -o.g[2]] }
    }
}
impl Mul<D> for f64 {
    type Output = D;
    fn mul(self, o: D) -> D {
        o * self
    }
}

// ---------------------------------------------------------------------------
// Reference geometry
// ---------------------------------------------------------------------------

/// Reference coordinates of the nodes of `t`, in Code_Aster's local node
/// order (source: `elrfno.F90`). Unused coordinates are 0.
pub fn node_coords(t: CellType) -> &'static [[f64; 3]] {
    use CellType::*;
    match t {
        Poi1 => &POI1_NODES,
        Seg2 => &SEG3_NODES[..2],
        Seg3 => &SEG3_NODES,
        Seg4 => &SEG4_NODES,
        Tria3 => &TRIA7_NODES[..3],
        Tria6 => &TRIA7_NODES[..6],
        Tria7 => &TRIA7_NODES,
        Quad4 => &QUAD9_NODES[..4],
        Quad8 => &QUAD9_NODES[..8],
        Quad9 => &QUAD9_NODES,
        Tetra4 => &TETRA10_NODES[..4],
        Tetra10 => &TETRA10_NODES,
        Penta6 => &PENTA18_NODES[..6],
        Penta15 => &PENTA18_NODES[..15],
        Penta18 => &PENTA18_NODES,
        Pyram5 => &PYRAM13_NODES[..5],
        Pyram13 => &PYRAM13_NODES,
        Hexa8 => &HEXA27_NODES[..8],
        Hexa20 => &HEXA27_NODES[..20],
        Hexa27 => &HEXA27_NODES,
    }
}

const POI1_NODES: [[f64; 3]; 1] = [[0.0, 0.0, 0.0]];

const SEG3_NODES: [[f64; 3]; 3] = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];

const SEG4_NODES: [[f64; 3]; 4] = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-1.0 / 3.0, 0.0, 0.0], [1.0 / 3.0, 0.0, 0.0]];

const TRIA7_NODES: [[f64; 3]; 7] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [1.0 / 3.0, 1.0 / 3.0, 0.0],
];

const QUAD9_NODES: [[f64; 3]; 9] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 0.0, 0.0],
];

const TETRA10_NODES: [[f64; 3]; 10] = [
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 0.5, 0.5],
    [0.0, 0.0, 0.5],
    [0.0, 0.5, 0.0],
    [0.5, 0.5, 0.0],
    [0.5, 0.0, 0.5],
    [0.5, 0.0, 0.0],
];

const PENTA18_NODES: [[f64; 3]; 18] = [
    [-1.0, 1.0, 0.0],
    [-1.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 1.0],
    [1.0, 0.0, 0.0],
    [-1.0, 0.5, 0.5],
    [-1.0, 0.0, 0.5],
    [-1.0, 0.5, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
    [1.0, 0.5, 0.5],
    [1.0, 0.0, 0.5],
    [1.0, 0.5, 0.0],
    [0.0, 0.5, 0.5],
    [0.0, 0.0, 0.5],
    [0.0, 0.5, 0.0],
];

const PYRAM13_NODES: [[f64; 3]; 13] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.5, 0.0],
    [-0.5, 0.5, 0.0],
    [-0.5, -0.5, 0.0],
    [0.5, -0.5, 0.0],
    [0.5, 0.0, 0.5],
    [0.0, 0.5, 0.5],
    [-0.5, 0.0, 0.5],
    [0.0, -0.5, 0.5],
];

const HEXA27_NODES: [[f64; 3]; 27] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
    [0.0, -1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
];

/// Measure (length, area, volume) of the reference domain of `t`
/// (source: `elrfno.F90`, `cellVolu`). POI1 counts as 1.
pub fn ref_measure(t: CellType) -> f64 {
    use CellType::*;
    match t {
        Poi1 => 1.0,
        Seg2 | Seg3 | Seg4 => 2.0,
        Tria3 | Tria6 | Tria7 => 0.5,
        Quad4 | Quad8 | Quad9 => 4.0,
        Tetra4 | Tetra10 => 1.0 / 6.0,
        Penta6 | Penta15 | Penta18 => 1.0,
        Pyram5 | Pyram13 => 2.0 / 3.0,
        Hexa8 | Hexa20 | Hexa27 => 8.0,
    }
}

/// Centroid of the reference domain (a convenient interior point; it is the
/// starting point of the inverse map).
pub fn ref_centroid(t: CellType) -> [f64; 3] {
    use CellType::*;
    match t {
        Tria3 | Tria6 | Tria7 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        Tetra4 | Tetra10 => [0.25, 0.25, 0.25],
        Penta6 | Penta15 | Penta18 => [0.0, 1.0 / 3.0, 1.0 / 3.0],
        Pyram5 | Pyram13 => [0.0, 0.0, 0.25],
        _ => [0.0, 0.0, 0.0],
    }
}

/// How far the reference point `xi` lies outside the reference domain of
/// `t`, measured as the largest violation of the domain's defining
/// inequalities (0 when inside or on the boundary).
pub fn outside_distance(t: CellType, xi: &[f64; 3]) -> f64 {
    use CellType::*;
    let [x, y, z] = *xi;
    let viol = |a: f64| a.max(0.0);
    match t {
        Poi1 => 0.0,
        Seg2 | Seg3 | Seg4 => viol(x.abs() - 1.0),
        Tria3 | Tria6 | Tria7 => viol(-x).max(viol(-y)).max(viol(x + y - 1.0)),
        Quad4 | Quad8 | Quad9 => viol(x.abs() - 1.0).max(viol(y.abs() - 1.0)),
        Tetra4 | Tetra10 => viol(-x).max(viol(-y)).max(viol(-z)).max(viol(x + y + z - 1.0)),
        Penta6 | Penta15 | Penta18 => viol(x.abs() - 1.0).max(viol(-y)).max(viol(-z)).max(viol(y + z - 1.0)),
        Pyram5 | Pyram13 => viol(-z).max(viol(z - 1.0)).max(viol(x.abs() + y.abs() + z - 1.0)),
        Hexa8 | Hexa20 | Hexa27 => viol(x.abs() - 1.0).max(viol(y.abs() - 1.0)).max(viol(z.abs() - 1.0)),
    }
}

/// True when `xi` is inside the reference domain of `t`, up to `tol`.
pub fn is_inside(t: CellType, xi: &[f64; 3], tol: f64) -> bool {
    outside_distance(t, xi) <= tol
}

// ---------------------------------------------------------------------------
// Shape functions
// ---------------------------------------------------------------------------

/// 1D quadratic Lagrange basis on nodes -1, 0, +1, selected by the node
/// coordinate `a`.
fn lag3(a: f64, u: D) -> D {
    if a < -0.5 {
        u * (u - 1.0) * 0.5
    } else if a > 0.5 {
        u * (u + 1.0) * 0.5
    } else {
        (1.0 - u) * (1.0 + u)
    }
}

/// Evaluate all shape functions of `t` at the dual point `p` into `out`.
fn eval(t: CellType, p: [D; 3], out: &mut [D]) {
    use CellType::*;
    let [x, y, z] = p;
    match t {
        Poi1 => out[0] = D::c(1.0),
        Seg2 => {
            out[0] = (1.0 - x) * 0.5;
            out[1] = (1.0 + x) * 0.5;
        }
        Seg3 => {
            out[0] = x * (x - 1.0) * 0.5;
            out[1] = x * (x + 1.0) * 0.5;
            out[2] = (1.0 - x) * (1.0 + x);
        }
        Seg4 => {
            // Cubic Lagrange on -1, 1, -1/3, 1/3.
            let nodes = [-1.0, 1.0, -1.0 / 3.0, 1.0 / 3.0];
            for (i, &a) in nodes.iter().enumerate() {
                let mut v = D::c(1.0);
                for (j, &b) in nodes.iter().enumerate() {
                    if j != i {
                        v = v * (x - b) * (1.0 / (a - b));
                    }
                }
                out[i] = v;
            }
        }
        Tria3 | Tria6 => {
            let l = [1.0 - x - y, x, y];
            simplex(&l, &[(0, 1), (1, 2), (2, 0)], t == Tria6, out);
        }
        Tria7 => {
            // P2 plus the cubic bubble 27 λ1 λ2 λ3, which vanishes on every other node.
            let l = [1.0 - x - y, x, y];
            simplex(&l, &[(0, 1), (1, 2), (2, 0)], true, out);
            let b = l[0] * l[1] * l[2];
            for o in out.iter_mut().take(3) {
                *o = *o + b * 3.0;
            }
            for o in out.iter_mut().take(6).skip(3) {
                *o = *o - b * 12.0;
            }
            out[6] = b * 27.0;
        }
        Tetra4 | Tetra10 => {
            // Code_Aster's vertex order: (0,1,0), (0,0,1), (0,0,0), (1,0,0).
            let l = [y, z, 1.0 - x - y - z, x];
            simplex(&l, &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)], t == Tetra10, out);
        }
        Quad4 | Quad8 | Quad9 | Hexa8 | Hexa20 | Hexa27 => tensor_family(t, p, out),
        Penta6 => {
            let l = [y, z, 1.0 - y - z];
            let lo = (1.0 - x) * 0.5;
            let hi = (1.0 + x) * 0.5;
            for i in 0..3 {
                out[i] = l[i] * lo;
                out[i + 3] = l[i] * hi;
            }
        }
        Penta15 => {
            let l = [y, z, 1.0 - y - z];
            // Vertices: 0.5 λ (1 ± x)(2λ ± x - 2).
            for i in 0..3 {
                out[i] = l[i] * (1.0 - x) * (2.0 * l[i] - x - 2.0) * 0.5;
                out[i + 3] = l[i] * (1.0 + x) * (2.0 * l[i] + x - 2.0) * 0.5;
            }
            // Edges of the end triangles: 2 λi λj (1 ± x); axial edges λi (1 - x²).
            let edges = [(0, 1), (1, 2), (2, 0)];
            for (k, &(i, j)) in edges.iter().enumerate() {
                out[6 + k] = 2.0 * l[i] * l[j] * (1.0 - x);
                out[12 + k] = 2.0 * l[i] * l[j] * (1.0 + x);
                out[9 + k] = l[k] * (1.0 - x) * (1.0 + x);
            }
        }
        Penta18 => {
            // The quadratic triangle (in y, z) times the quadratic segment (in x).
            let l = [y, z, 1.0 - y - z];
            let mut tri = [D::c(0.0); 6];
            simplex(&l, &[(0, 1), (1, 2), (2, 0)], true, &mut tri);
            // Node k: its triangle node and its level on the axis.
            const TRI: [usize; 18] = [0, 1, 2, 0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5, 3, 4, 5];
            let nodes = node_coords(t);
            for (k, o) in out.iter_mut().enumerate().take(18) {
                *o = tri[TRI[k]] * lag3(nodes[k][0], x);
            }
        }
        Pyram5 | Pyram13 => pyramid(t == Pyram13, p, out),
    }
}

/// Linear (P1) or quadratic (P2) simplex functions from barycentric
/// coordinates `l`; quadratic mid-edge nodes follow `edges`.
fn simplex(l: &[D], edges: &[(usize, usize)], quadratic: bool, out: &mut [D]) {
    let nv = l.len();
    if !quadratic {
        out[..nv].copy_from_slice(l);
        return;
    }
    for i in 0..nv {
        out[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (k, &(i, j)) in edges.iter().enumerate() {
        out[nv + k] = 4.0 * l[i] * l[j];
    }
}

/// Quadrilaterals and hexahedra, from their node coordinates.
fn tensor_family(t: CellType, p: [D; 3], out: &mut [D]) {
    use CellType::*;
    let nodes = node_coords(t);
    let dim = t.dim();
    for (i, a) in nodes.iter().enumerate() {
        out[i] = match t {
            Quad9 | Hexa27 => {
                let mut v = D::c(1.0);
                for k in 0..dim {
                    v = v * lag3(a[k], p[k]);
                }
                v
            }
            Quad4 | Hexa8 => {
                let mut v = D::c(1.0 / (1u32 << dim) as f64);
                for k in 0..dim {
                    v = v * (1.0 + a[k] * p[k]);
                }
                v
            }
            // Serendipity (QUAD8, HEXA20).
            _ => {
                let zeros = (0..dim).filter(|&k| a[k] == 0.0).count();
                if zeros == 0 {
                    // Corner: Π(1 + a_k ξ_k) (Σ a_k ξ_k - (dim - 1)) / 2^dim.
                    let mut v = D::c(1.0 / (1u32 << dim) as f64);
                    let mut s = D::c(-((dim - 1) as f64));
                    for k in 0..dim {
                        v = v * (1.0 + a[k] * p[k]);
                        s = s + a[k] * p[k];
                    }
                    v * s
                } else {
                    // Mid-edge: (1 - ξ_m²) Π_{k≠m}(1 + a_k ξ_k) / 2^(dim-1).
                    let mut v = D::c(1.0 / (1u32 << (dim - 1)) as f64);
                    for k in 0..dim {
                        v = if a[k] == 0.0 { v * (1.0 - p[k]) * (1.0 + p[k]) } else { v * (1.0 + a[k] * p[k]) };
                    }
                    v
                }
            }
        };
    }
}

/// Pyramids: Code_Aster's rational shape functions (`elrfvf.F90`, PY5/P13).
/// At the apex (z = 1) they are defined by continuity (N5 = 1, others 0);
/// their derivatives there are not defined and are evaluated slightly below.
fn pyramid(quadratic: bool, p: [D; 3], out: &mut [D]) {
    let [x, y, mut z] = p;
    let n = if quadratic { 13 } else { 5 };
    if (1.0 - z.v).abs() < 1e-13 {
        z.v = 1.0 - 1e-13;
    }
    let f1 = x + y + z - 1.0;
    let f2 = y + z - x - 1.0;
    let f3 = z - x - y - 1.0;
    let f4 = x - y + z - 1.0;
    let one_m_z = 1.0 - z;
    if !quadratic {
        let d = one_m_z * 4.0;
        out[0] = f2 * f3 / d;
        out[1] = f3 * f4 / d;
        out[2] = f1 * f4 / d;
        out[3] = f1 * f2 / d;
        out[4] = z;
    } else {
        let d = one_m_z * 2.0;
        let m1 = x - 0.5;
        let m2 = y - 0.5;
        let m3 = -x - 0.5;
        let m4 = -y - 0.5;
        out[0] = f2 * f3 * m1 / d;
        out[1] = f3 * f4 * m2 / d;
        out[2] = f4 * f1 * m3 / d;
        out[3] = f1 * f2 * m4 / d;
        out[4] = 2.0 * z * (z - 0.5);
        out[5] = -(f2 * f3 * f4) / d;
        out[6] = -(f3 * f4 * f1) / d;
        out[7] = -(f4 * f1 * f2) / d;
        out[8] = -(f1 * f2 * f3) / d;
        out[9] = z * f2 * f3 / one_m_z;
        out[10] = z * f3 * f4 / one_m_z;
        out[11] = z * f4 * f1 / one_m_z;
        out[12] = z * f1 * f2 / one_m_z;
    }
    if (1.0 - p[2].v).abs() < 1e-13 {
        // Exact values at the apex.
        for (i, o) in out.iter_mut().enumerate().take(n) {
            o.v = if i == 4 { 1.0 } else { 0.0 };
        }
    }
}

/// Largest number of nodes of a cell type (HEXA27).
pub const MAX_NODES: usize = 27;

/// Shape functions as dual numbers, in a stack buffer (no allocation);
/// the first `t.nnodes()` entries are meaningful.
fn eval_dual(t: CellType, xi: &[f64; 3]) -> [D; MAX_NODES] {
    let p = [D::var(xi[0], 0), D::var(xi[1], 1), D::var(xi[2], 2)];
    let mut out = [D::c(0.0); MAX_NODES];
    eval(t, p, &mut out[..t.nnodes()]);
    out
}

/// Values of the shape functions of `t` at the reference point `xi`.
pub fn shape(t: CellType, xi: &[f64; 3]) -> Vec<f64> {
    eval_dual(t, xi)[..t.nnodes()].iter().map(|d| d.v).collect()
}

/// First derivatives of the shape functions: `dn[i][k] = ∂N_i/∂ξ_k`
/// (components beyond the cell's dimension are 0).
pub fn shape_deriv(t: CellType, xi: &[f64; 3]) -> Vec<[f64; 3]> {
    let dim = t.dim();
    eval_dual(t, xi)[..t.nnodes()]
        .iter()
        .map(|d| {
            let mut g = d.g;
            for c in g.iter_mut().skip(dim) {
                *c = 0.0;
            }
            g
        })
        .collect()
}

/// Values and first derivatives together, written into caller buffers of
/// length `t.nnodes()`.
pub fn shape_and_deriv(t: CellType, xi: &[f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let dim = t.dim();
    for (i, d) in eval_dual(t, xi)[..t.nnodes()].iter().enumerate() {
        n[i] = d.v;
        let mut g = d.g;
        for c in g.iter_mut().skip(dim) {
            *c = 0.0;
        }
        dn[i] = g;
    }
}

// ---------------------------------------------------------------------------
// Isoparametric map
// ---------------------------------------------------------------------------

/// Real coordinates of the reference point `xi`: x = Σ N_i(ξ) x_i.
/// `coords` are the cell's node coordinates in Code_Aster's local order.
pub fn map_to_real(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3]) -> [f64; 3] {
    assert_eq!(coords.len(), t.nnodes(), "{}: wrong number of node coordinates", t.name());
    let n = shape(t, xi);
    let mut x = [0.0; 3];
    for (ni, c) in n.iter().zip(coords) {
        for k in 0..3 {
            x[k] += ni * c[k];
        }
    }
    x
}

/// Jacobian of the isoparametric map: `j[i][k] = ∂x_i/∂ξ_k` for
/// k < `t.dim()` (other columns are 0). For cells of full dimension the
/// determinant of the leading `dim × dim` block is [`jacobian_det`].
pub fn jacobian(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3]) -> [[f64; 3]; 3] {
    assert_eq!(coords.len(), t.nnodes(), "{}: wrong number of node coordinates", t.name());
    let dn = shape_deriv(t, xi);
    let mut j = [[0.0; 3]; 3];
    for (g, c) in dn.iter().zip(coords) {
        for i in 0..3 {
            for k in 0..3 {
                j[i][k] += c[i] * g[k];
            }
        }
    }
    j
}

/// Measure density of the map at `xi`: |det J| for a cell whose dimension
/// equals `space_dim`, and the generalized (Gram) determinant sqrt(det JᵀJ)
/// otherwise (length / area element of a curve or surface). Signed for
/// full-dimensional cells (negative for inverted cells).
pub fn jacobian_det(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3], space_dim: usize) -> f64 {
    let j = jacobian(t, coords, xi);
    let dim = t.dim();
    if dim == 0 {
        return 1.0;
    }
    if dim == space_dim {
        return leading_det(&matrix3(&j), dim);
    }
    let g = leading_det(&gram(&matrix3(&j), dim), dim);
    match dim {
        1 => g.sqrt(),
        2 => g.max(0.0).sqrt(),
        _ => g.abs().sqrt(),
    }
}

/// A 3×3 array of rows (`a[row][column]`, as [`jacobian`] returns) as a
/// nalgebra matrix.
fn matrix3(a: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| a[r][c])
}

/// Determinant of the leading `dim × dim` block of `a` (dim = 1, 2 or 3).
fn leading_det(a: &Matrix3<f64>, dim: usize) -> f64 {
    match dim {
        1 => a[(0, 0)],
        2 => a.fixed_view::<2, 2>(0, 0).determinant(),
        _ => a.determinant(),
    }
}

/// The determinant and the inverse of the leading `dim × dim` block (dim = 1,
/// 2 or 3) of a Jacobian `j[i][k] = ∂x_i/∂ξ_k`, the inverse padded with zeros
/// (`inv[k][i] = ∂ξ_k/∂x_i`). The inverse is None when the block is singular
/// or not finite (its determinant is returned all the same, for the
/// caller's message).
pub fn jacobian_inverse(j: &[[f64; 3]; 3], dim: usize) -> (f64, Option<[[f64; 3]; 3]>) {
    let mut inv = [[0.0; 3]; 3];
    let det = match dim {
        1 => {
            let det = j[0][0];
            inv[0][0] = 1.0 / det;
            det
        }
        2 => {
            let m = Matrix2::new(j[0][0], j[0][1], j[1][0], j[1][1]);
            let det = m.determinant();
            let Some(mi) = m.try_inverse() else { return (det, None) };
            for (k, row) in inv.iter_mut().enumerate().take(2) {
                for (i, v) in row.iter_mut().enumerate().take(2) {
                    *v = mi[(k, i)];
                }
            }
            det
        }
        _ => {
            let m = matrix3(j);
            let det = m.determinant();
            let Some(mi) = m.try_inverse() else { return (det, None) };
            inv = mi.transpose().into();
            det
        }
    };
    let finite = det.is_finite() && inv.iter().flatten().all(|v| v.is_finite());
    (det, (det != 0.0 && finite).then_some(inv))
}

/// Shape gradients in real coordinates of a parent cell at ξ, and |det J|.
pub fn real_gradients(t: CellType, coords: &[[f64; 3]], xi: &[f64; 3]) -> Option<(Vec<f64>, Vec<[f64; 3]>, f64)> {
    let nno = t.nnodes();
    let dim = t.dim();
    let mut n = vec![0.0; nno];
    let mut dref = vec![[0.0; 3]; nno];
    shape_and_deriv(t, xi, &mut n, &mut dref);
    let j = jacobian(t, coords, xi);
    let (det, ij) = jacobian_inverse(&j, dim);
    let ij = ij?;
    let g = dref
        .iter()
        .map(|d| {
            let mut r = [0.0; 3];
            for (i, ri) in r.iter_mut().enumerate().take(dim) {
                *ri = (0..dim).map(|k| d[k] * ij[k][i]).sum();
            }
            r
        })
        .collect();
    Some((n, g, det.abs()))
}

/// JᵀJ restricted to the first `dim` reference directions (zero elsewhere).
fn gram(j: &Matrix3<f64>, dim: usize) -> Matrix3<f64> {
    Matrix3::from_fn(|a, b| if a < dim && b < dim { j.column(a).dot(&j.column(b)) } else { 0.0 })
}

/// Solve the `n × n` system `a s = b` (n ≤ 3, in the leading block) by
/// nalgebra's LU with partial pivoting, the unused block set to the
/// identity; `None` when a pivot is not above `1e-14 scale` (singular
/// relative to `scale`) or is not finite.
fn solve_small(a: &Matrix3<f64>, b: &Vector3<f64>, n: usize, scale: f64) -> Option<Vector3<f64>> {
    let mut a = *a;
    for k in n..3 {
        a[(k, k)] = 1.0;
    }
    let lu = a.lu();
    // The padded rows are zero in the first n columns, so they never pivot there.
    if !lu.u().diagonal().iter().take(n).all(|p| p.abs() > 1e-14 * scale && p.is_finite()) {
        return None;
    }
    lu.solve(b)
}

/// Settings of [`inverse_map`].
#[derive(Debug, Clone, Copy)]
pub struct InverseMapOptions {
    /// Convergence: stop when the Newton step (in reference coordinates) is
    /// below this.
    pub tol: f64,
    /// Maximum number of Newton iterations.
    pub max_iter: usize,
    /// A converged point farther outside the reference domain than this (see
    /// [`outside_distance`]) is reported as [`InverseMapError::Outside`].
    pub outside_tol: f64,
}

impl Default for InverseMapOptions {
    fn default() -> Self {
        InverseMapOptions { tol: 1e-12, max_iter: 50, outside_tol: 1e-6 }
    }
}

/// A successful inverse map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseMapResult {
    /// Reference coordinates found.
    pub xi: [f64; 3],
    /// Distance between the target point and the image of `xi` (0 up to
    /// round-off for full-dimensional cells; the projection distance for a
    /// curve or surface embedded in a higher-dimensional space).
    pub distance: f64,
    /// Newton iterations used.
    pub iterations: usize,
}

/// Why [`inverse_map`] failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InverseMapError {
    /// Newton did not converge within the allowed iterations (or diverged).
    NotConverged { xi: [f64; 3], iterations: usize, step: f64 },
    /// The Jacobian became singular (degenerate cell, or a point on a
    /// singular point of the map such as a pyramid apex).
    SingularJacobian { xi: [f64; 3] },
    /// Converged, but the point lies outside the cell by more than the
    /// tolerance; `excess` is [`outside_distance`] of `xi`.
    Outside { xi: [f64; 3], excess: f64, distance: f64 },
    /// The cell has no interior to search (POI1).
    Unsupported,
}

impl fmt::Display for InverseMapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InverseMapError::NotConverged { xi, iterations, step } => write!(
                f,
                "inverse isoparametric map did not converge after {iterations} iterations \
                 (last step {step:.3e}, last point {xi:?})"
            ),
            InverseMapError::SingularJacobian { xi } => {
                write!(f, "singular Jacobian in the inverse isoparametric map at reference point {xi:?}")
            }
            InverseMapError::Outside { xi, excess, .. } => {
                write!(f, "point is outside the cell (reference point {xi:?}, {excess:.3e} beyond the domain)")
            }
            InverseMapError::Unsupported => write!(f, "inverse map is not defined for point cells"),
        }
    }
}

impl std::error::Error for InverseMapError {}

/// Inverse isoparametric map: the reference point ξ with x(ξ) = `x`.
///
/// Newton iterations from the reference centroid, on J Δξ = x - x(ξ) for a
/// cell of the same dimension as the space spanned by its nodes, and the
/// Gauss–Newton normal equations (JᵀJ Δξ = Jᵀ(x - x(ξ))) for a curve or
/// surface in a higher-dimensional space, which then returns the closest
/// point's reference coordinates and the distance. Fails with a clear
/// [`InverseMapError`] when it does not converge or when the solution lies
/// outside the reference domain by more than `opts.outside_tol`.
pub fn inverse_map(
    t: CellType,
    coords: &[[f64; 3]],
    x: &[f64; 3],
    opts: &InverseMapOptions,
) -> Result<InverseMapResult, InverseMapError> {
    let dim = t.dim();
    if dim == 0 {
        return Err(InverseMapError::Unsupported);
    }
    // Length scale of the cell, for relative tolerances.
    let mut h2: f64 = 0.0;
    for c in coords {
        for d in coords {
            h2 = h2.max((Vector3::from(*c) - Vector3::from(*d)).norm_squared());
        }
    }
    let h = h2.sqrt().max(f64::MIN_POSITIVE);
    let mut xi = ref_centroid(t);
    let mut step = f64::INFINITY;
    for it in 1..=opts.max_iter {
        let r = Vector3::from(*x) - Vector3::from(map_to_real(t, coords, &xi));
        let j = matrix3(&jacobian(t, coords, &xi));
        let g = gram(&j, dim);
        let rhs = Vector3::from_fn(|a, _| if a < dim { j.column(a).dot(&r) } else { 0.0 });
        let d = solve_small(&g, &rhs, dim, h * h).ok_or(InverseMapError::SingularJacobian { xi })?;
        step = d.rows(0, dim).norm();
        // Damp overly long steps (the reference domains have size ~2).
        let damp = if step > 1.0 { 1.0 / step } else { 1.0 };
        for k in 0..dim {
            xi[k] += damp * d[k];
        }
        if !xi.iter().all(|v| v.is_finite()) || xi.iter().any(|v| v.abs() > 1e3) {
            return Err(InverseMapError::NotConverged { xi, iterations: it, step });
        }
        if step <= opts.tol {
            let distance = (Vector3::from(*x) - Vector3::from(map_to_real(t, coords, &xi))).norm();
            let excess = outside_distance(t, &xi);
            if excess > opts.outside_tol {
                return Err(InverseMapError::Outside { xi, excess, distance });
            }
            return Ok(InverseMapResult { xi, distance, iterations: it });
        }
    }
    Err(InverseMapError::NotConverged { xi, iterations: opts.max_iter, step })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers in [0, 1) (xorshift).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A random point strictly inside the reference domain of `t`, at
    /// least `margin` (in reference units, roughly) from its boundary.
    fn random_interior(t: CellType, rng: &mut Rng, margin: f64) -> [f64; 3] {
        use CellType::*;
        let s = |r: &mut Rng| (2.0 * r.next() - 1.0) * (1.0 - margin);
        loop {
            let p = match t {
                Poi1 => [0.0; 3],
                Seg2 | Seg3 | Seg4 => [s(rng), 0.0, 0.0],
                Quad4 | Quad8 | Quad9 => [s(rng), s(rng), 0.0],
                Hexa8 | Hexa20 | Hexa27 => [s(rng), s(rng), s(rng)],
                Tria3 | Tria6 | Tria7 => [rng.next(), rng.next(), 0.0],
                Tetra4 | Tetra10 => [rng.next(), rng.next(), rng.next()],
                Penta6 | Penta15 | Penta18 => [s(rng), rng.next(), rng.next()],
                Pyram5 | Pyram13 => [s(rng), s(rng), rng.next()],
            };
            let inner = match t {
                Tria3 | Tria6 | Tria7 => p[0] > margin && p[1] > margin && p[0] + p[1] < 1.0 - margin,
                Tetra4 | Tetra10 => p.iter().all(|&v| v > margin) && p[0] + p[1] + p[2] < 1.0 - margin,
                Penta6 | Penta15 | Penta18 => p[1] > margin && p[2] > margin && p[1] + p[2] < 1.0 - margin,
                Pyram5 | Pyram13 => p[2] > margin && p[0].abs() + p[1].abs() + p[2] < 1.0 - margin,
                _ => true,
            };
            if inner {
                return p;
            }
        }
    }

    #[test]
    fn node_tables_are_consistent() {
        for t in CellType::ALL {
            assert_eq!(node_coords(t).len(), t.nnodes(), "{}", t.name());
            for (i, c) in node_coords(t).iter().enumerate() {
                assert!(is_inside(t, c, 0.0), "{} node {} outside its domain", t.name(), i + 1);
                for v in c.iter().skip(t.dim()) {
                    assert_eq!(*v, 0.0);
                }
            }
            assert!(is_inside(t, &ref_centroid(t), 0.0));
        }
    }

    #[test]
    fn partition_of_unity_and_zero_derivative_sum() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        for t in CellType::ALL {
            for _ in 0..50 {
                let xi = random_interior(t, &mut rng, 0.0);
                let n = shape(t, &xi);
                let dn = shape_deriv(t, &xi);
                let s: f64 = n.iter().sum();
                assert!((s - 1.0).abs() < 1e-13, "{}: ΣN = {s}", t.name());
                for k in 0..3 {
                    let sd: f64 = dn.iter().map(|g| g[k]).sum();
                    assert!(sd.abs() < 1e-12, "{}: Σ∂N/∂ξ{k} = {sd}", t.name());
                }
            }
        }
    }

    #[test]
    fn kronecker_property_at_nodes() {
        for t in CellType::ALL {
            for (j, c) in node_coords(t).iter().enumerate() {
                let n = shape(t, c);
                for (i, v) in n.iter().enumerate() {
                    let e = if i == j { 1.0 } else { 0.0 };
                    assert!((v - e).abs() < 1e-12, "{}: N{}(node {}) = {v}", t.name(), i + 1, j + 1);
                }
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let mut rng = Rng(0xdead_beef_cafe_f00d);
        let h = 1e-6;
        for t in CellType::ALL {
            for _ in 0..20 {
                let xi = random_interior(t, &mut rng, 0.01);
                let dn = shape_deriv(t, &xi);
                for k in 0..t.dim() {
                    let mut p = xi;
                    let mut m = xi;
                    p[k] += h;
                    m[k] -= h;
                    let np = shape(t, &p);
                    let nm = shape(t, &m);
                    for i in 0..t.nnodes() {
                        let fd = (np[i] - nm[i]) / (2.0 * h);
                        assert!(
                            (fd - dn[i][k]).abs() < 1e-7 * (1.0 + fd.abs()),
                            "{}: ∂N{}/∂ξ{k} = {} vs FD {fd}",
                            t.name(),
                            i + 1,
                            dn[i][k]
                        );
                    }
                }
            }
        }
    }

    /// An affine map x = A ξ + b, with A of full rank.
    fn affine(xi: &[f64; 3]) -> [f64; 3] {
        let a = [[2.0, 0.3, -0.4], [0.5, 1.5, 0.2], [-0.1, 0.6, 1.8]];
        let b = [1.0, -2.0, 0.5];
        let mut x = b;
        for i in 0..3 {
            for k in 0..3 {
                x[i] += a[i][k] * xi[k];
            }
        }
        x
    }

    #[test]
    fn affine_maps_are_reproduced() {
        let mut rng = Rng(42);
        for t in CellType::ALL {
            let coords: Vec<[f64; 3]> = node_coords(t).iter().map(affine).collect();
            for _ in 0..20 {
                let xi = random_interior(t, &mut rng, 0.0);
                let x = map_to_real(t, &coords, &xi);
                let e = affine(&xi);
                for k in 0..3 {
                    assert!((x[k] - e[k]).abs() < 1e-12, "{}: {x:?} vs {e:?}", t.name());
                }
                if t.dim() == 3 {
                    let det = jacobian_det(t, &coords, &xi, 3);
                    let a = [[2.0, 0.3, -0.4], [0.5, 1.5, 0.2], [-0.1, 0.6, 1.8]];
                    assert!((det - matrix3(&a).determinant()).abs() < 1e-11, "{}: det {det}", t.name());
                }
            }
        }
    }

    /// Node coordinates of a distorted cell: an affine image of the reference
    /// nodes, plus a smooth nonlinear perturbation.
    fn distorted(t: CellType) -> Vec<[f64; 3]> {
        let dim = t.dim();
        node_coords(t)
            .iter()
            .map(|c| {
                let mut xi = *c;
                for v in xi.iter_mut().skip(dim) {
                    *v = 0.0;
                }
                let mut x = affine(&xi);
                x[0] += 0.08 * (xi[1] * xi[1] - xi[2]);
                x[1] += 0.06 * xi[0] * xi[2] - 0.05 * xi[0] * xi[0];
                x[2] += 0.07 * xi[0] * xi[1];
                if dim < 3 {
                    // keep 1D/2D cells in their own plane / line for the square Newton test
                    for v in x.iter_mut().skip(dim) {
                        *v = 0.0;
                    }
                }
                x
            })
            .collect()
    }

    #[test]
    fn inverse_map_inverts_map() {
        let mut rng = Rng(7);
        let opts = InverseMapOptions::default();
        for t in CellType::ALL {
            if t.dim() == 0 {
                assert_eq!(inverse_map(t, &[[0.0; 3]], &[0.0; 3], &opts), Err(InverseMapError::Unsupported));
                continue;
            }
            let coords = distorted(t);
            for _ in 0..30 {
                let xi = random_interior(t, &mut rng, 0.02);
                let x = map_to_real(t, &coords, &xi);
                let r = inverse_map(t, &coords, &x, &opts).unwrap_or_else(|e| panic!("{}: {e}", t.name()));
                for k in 0..t.dim() {
                    assert!((r.xi[k] - xi[k]).abs() < 1e-9, "{}: {:?} vs {xi:?}", t.name(), r.xi);
                }
                assert!(r.distance < 1e-9);
            }
        }
    }

    #[test]
    fn inverse_map_reports_outside_points() {
        let opts = InverseMapOptions::default();
        for t in [CellType::Quad4, CellType::Tria6, CellType::Hexa20, CellType::Tetra10, CellType::Penta6] {
            let coords: Vec<[f64; 3]> = node_coords(t).iter().map(|c| [2.0 * c[0], 3.0 * c[1], 4.0 * c[2]]).collect();
            // Far beyond the first reference axis.
            let x = [2.0 * 1.5, 0.3, if t.dim() == 3 { 0.2 } else { 0.0 }];
            match inverse_map(t, &coords, &x, &opts) {
                Err(InverseMapError::Outside { excess, .. }) => assert!(excess > 0.1, "{}", t.name()),
                other => panic!("{}: expected Outside, got {other:?}", t.name()),
            }
        }
    }

    #[test]
    fn inverse_map_projects_onto_embedded_surface() {
        // A QUAD4 in the plane z = 1 of 3D space: projection of a point above it.
        let t = CellType::Quad4;
        let coords = [[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [2.0, 2.0, 1.0], [0.0, 2.0, 1.0]];
        let r = inverse_map(t, &coords, &[1.5, 0.5, 3.0], &InverseMapOptions::default()).unwrap();
        assert!((r.xi[0] - 0.5).abs() < 1e-12 && (r.xi[1] + 0.5).abs() < 1e-12);
        assert!((r.distance - 2.0).abs() < 1e-12);
    }

    #[test]
    fn inverse_map_projects_onto_embedded_curve() {
        // A SEG3 arc-like curve in 3D: the image of a reference point, moved
        // off the curve along the curve's normal plane, projects back to it.
        let t = CellType::Seg3;
        let coords = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.5, 0.3]];
        let xi0 = [0.3, 0.0, 0.0];
        let x0 = map_to_real(t, &coords, &xi0);
        let j = jacobian(t, &coords, &xi0);
        let tangent = [j[0][0], j[1][0], j[2][0]];
        // A direction orthogonal to the tangent.
        let n = [tangent[1], -tangent[0], 0.0];
        let nn = (n[0] * n[0] + n[1] * n[1]).sqrt();
        let d = 1e-3;
        let x = [x0[0] + d * n[0] / nn, x0[1] + d * n[1] / nn, x0[2]];
        let r = inverse_map(t, &coords, &x, &InverseMapOptions::default()).unwrap();
        assert!((r.xi[0] - xi0[0]).abs() < 1e-5, "{:?}", r.xi);
        assert!((r.distance - d).abs() < 1e-6);
    }

    #[test]
    fn inverse_map_near_pyramid_apex() {
        let opts = InverseMapOptions::default();
        for t in [CellType::Pyram5, CellType::Pyram13] {
            let coords = distorted(t);
            for xi in [[0.01, -0.02, 0.95], [0.0, 0.0, 0.999], [0.3, 0.2, 0.4]] {
                let x = map_to_real(t, &coords, &xi);
                let r = inverse_map(t, &coords, &x, &opts).unwrap_or_else(|e| panic!("{}: {e}", t.name()));
                for k in 0..3 {
                    assert!((r.xi[k] - xi[k]).abs() < 1e-8, "{}: {:?} vs {xi:?}", t.name(), r.xi);
                }
            }
        }
    }

    #[test]
    fn degenerate_cell_is_singular() {
        let t = CellType::Tria3;
        let coords = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0]];
        assert!(matches!(
            inverse_map(t, &coords, &[0.5, 0.2, 0.0], &InverseMapOptions::default()),
            Err(InverseMapError::SingularJacobian { .. })
        ));
    }

    #[test]
    fn code_aster_conventions() {
        // TETRA4: N1 = y, N2 = z, N3 = 1 - x - y - z, N4 = x (elrfvf.F90).
        let n = shape(CellType::Tetra4, &[0.1, 0.2, 0.3]);
        let e = [0.2, 0.3, 0.4, 0.1];
        for i in 0..4 {
            assert!((n[i] - e[i]).abs() < 1e-15);
        }
        // PENTA6: N1 = y (1 - x) / 2.
        let n = shape(CellType::Penta6, &[0.5, 0.2, 0.3]);
        assert!((n[0] - 0.2 * 0.25).abs() < 1e-15);
        // PYRAM5 apex.
        let n = shape(CellType::Pyram5, &[0.0, 0.0, 1.0]);
        assert_eq!(n, vec![0.0, 0.0, 0.0, 0.0, 1.0]);
        for t in CellType::ALL {
            assert!(ref_measure(t) > 0.0);
        }
    }

    /// The Jacobi-scaled stiffness of a cell's shape functions restricted to a strip of width δ along an
    /// edge (δ of the reference width): its eigenvalues, ascending. The functions that vanish on the edge
    /// are (x − x₀)·∂ₓN(x₀, y) to first order; when there are more of them than that trace space has
    /// dimensions, some combinations are O(δ²) in energy relative to the others — why an X-FEM strip
    /// of quadratic cells costs 10²ᵏ in condition (docs/stability.md).
    fn strip_spectrum(t: CellType, delta: f64) -> Vec<f64> {
        let nn = t.nnodes();
        let (g, w) = crate::fem::quadrature::gauss_legendre_1d(8);
        let mut k = nalgebra::DMatrix::<f64>::zeros(nn, nn);
        let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
        for (gx, wx) in g.iter().zip(&w) {
            for (gy, wy) in g.iter().zip(&w) {
                let xi = [-1.0 + delta * (gx + 1.0), *gy, 0.0];
                shape_and_deriv(t, &xi, &mut n, &mut dn);
                for a in 0..nn {
                    for b in 0..nn {
                        k[(a, b)] += wx * wy * delta * (dn[a][0] * dn[b][0] + dn[a][1] * dn[b][1]);
                    }
                }
            }
        }
        let d: Vec<f64> = (0..nn).map(|a| 1.0 / k[(a, a)].sqrt()).collect();
        let scaled = nalgebra::DMatrix::from_fn(nn, nn, |a, b| k[(a, b)] * d[a] * d[b]);
        let mut ev: Vec<f64> = scaled.symmetric_eigen().eigenvalues.iter().copied().collect();
        ev.sort_by(|a, b| a.total_cmp(b));
        ev
    }

    #[test]
    fn quad8_functions_on_a_strip_are_nearly_dependent_quad4_ones_are_not() {
        for k in 1..=6 {
            let delta = 10f64.powi(-k);
            // The constant (Σ N = 1) is the null mode; QUAD8 has two more of size δ², QUAD4 none.
            let q8 = strip_spectrum(CellType::Quad8, delta);
            assert!(q8[0].abs() < 1e-14, "{q8:?}");
            for e in &q8[1..3] {
                assert!((0.03..0.3).contains(&(e / (delta * delta))), "QUAD8 δ = {delta}: {q8:?}");
            }
            assert!(q8[3] > 0.1, "QUAD8 δ = {delta}: {q8:?}");
            let q4 = strip_spectrum(CellType::Quad4, delta);
            assert!(q4[0].abs() < 1e-14 && q4[1] > 0.4, "QUAD4 δ = {delta}: {q4:?}");
        }
    }
}
