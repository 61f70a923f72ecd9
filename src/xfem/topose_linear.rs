//! TOPOSE sub-cell cutting for LINEAR X-FEM parents (TRIA3, QUAD4,
//! TETRA4, HEXA8, PENTA6), as Code_Aster's `te0514` does it on its linear
//! path: primary split into simplices (`xdivte`), then, crack after crack,
//! every current simplex is cut (`xdecou`: intersection points on its edges
//! in `conare` order, crossing points by a Newton solve of the parent's
//! level set along the edge, `xinter`) and replaced by its children
//! (`xdecov`, with `xpente` for the prisms), tetrahedra reoriented, the
//! Heaviside value of each child from the sum of the level set over its
//! vertices, the junction skip for a branch. Intersection points are merged
//! over the whole parent and stored in creation order (`PINTTO`).
//!
//! The result uses the types of [`crate::xfem::cutting`]: point ids 1..=nno
//! for the parent's nodes (Code_Aster local order) and 1000+k for the
//! intersection points (there are no mid-points or centre nodes); the
//! sub-cells are TRIA3 / TETRA4 in Code_Aster's local order, first child in
//! the slot of its parent simplex, the others appended.
//!
//! Every `ASSERT` of the Fortran on this path (too many points, unexpected
//! vertex configurations, a zero level-set sum on a principal element, a
//! crossing point outside the parent) is reported as an error naming the
//! case; nothing is guessed.

use crate::fem::reference::{map_to_real, node_coords, shape, shape_and_deriv};
use crate::mesh::CellType;
use crate::xfem::cutting::Wp::{self, Inter as I, Node as N};
use crate::xfem::cutting::{
    dist, loncar, master_chain, prism_split, vertex_and_ends, CrackInCell, CutPoint, Cutting, Inter, PointId, Pt,
    SubCell, V3,
};

/// Coincidence tolerance of the point lists (`cridist`), relative to the
/// parent's characteristic length.
const CRIDIST: f64 = 1e-9;

/// Edges of the SEG2 / TRIA3 / TETRA4 simplices (`conare`), 1-based local vertices.
const SEG2_EDGES: [[usize; 2]; 1] = [[1, 2]];
const TRIA3_EDGES: [[usize; 2]; 3] = [[1, 2], [2, 3], [3, 1]];
const TETRA4_EDGES: [[usize; 2]; 6] = [[1, 2], [1, 3], [1, 4], [2, 3], [2, 4], [3, 4]];

/// Primary splits (`xdivte`, linear parents).
const QUAD4_SPLIT: [[Wp; 3]; 2] = [[N(1), N(2), N(4)], [N(2), N(3), N(4)]];
const HEXA8_SPLIT: [[Wp; 4]; 6] = [
    [N(6), N(3), N(2), N(4)],
    [N(4), N(5), N(1), N(2)],
    [N(2), N(5), N(6), N(4)],
    [N(5), N(4), N(8), N(6)],
    [N(3), N(6), N(7), N(8)],
    [N(3), N(8), N(4), N(6)],
];
const PENTA6_SPLIT: [[Wp; 4]; 3] = [[N(5), N(4), N(6), N(1)], [N(1), N(2), N(3), N(6)], [N(6), N(2), N(5), N(1)]];

/// The simplex type of the sub-cells of a linear parent of dimension `dim`
/// (SEG2 for a boundary segment, TRIA3, TETRA4).
pub fn subcell_type(dim: usize) -> CellType {
    match dim {
        1 => CellType::Seg2,
        2 => CellType::Tria3,
        _ => CellType::Tetra4,
    }
}

/// Is a reference point inside the parent's reference domain (`xveri0`,
/// tolerance 1e-12)?
fn inside(t: CellType, xi: &[f64; 3]) -> bool {
    const TOLE: f64 = 1e-12;
    let (zero, one) = (-TOLE, 1.0 + TOLE);
    match t {
        CellType::Tria3 => xi[0] >= zero && xi[1] >= zero && 1.0 - xi[0] - xi[1] >= zero,
        CellType::Tetra4 => xi.iter().all(|&v| v >= zero) && 1.0 - xi[0] - xi[1] - xi[2] >= zero,
        CellType::Penta6 => xi[0].abs() <= one && xi[1] <= one && xi[2] <= one && 1.0 - xi[1] - xi[2] >= zero,
        _ => xi.iter().take(t.dim()).all(|v| v.abs() <= one),
    }
}

/// The parent cell and the intersection points found so far.
struct Ctx<'a> {
    t: CellType,
    /// Dimension of the parent cell (`ndime`).
    dim: usize,
    /// Dimension of the mesh (`ndim`): larger than `dim` for a boundary cell.
    ndim: usize,
    nno: usize,
    coords: &'a [[f64; 3]],
    /// lsn[crack][node].
    lsn: Vec<&'a [f64]>,
    /// Intersection points of the parent (`PINTTO`), ids 1001...
    pint: Vec<Pt>,
    lonref: f64,
}

impl Ctx<'_> {
    fn edges(&self) -> &'static [[usize; 2]] {
        match self.dim {
            1 => &SEG2_EDGES,
            2 => &TRIA3_EDGES,
            _ => &TETRA4_EDGES,
        }
    }

    fn interp(&self, xi: &[f64; 3], crack: usize) -> f64 {
        shape(self.t, xi).iter().zip(self.lsn[crack]).map(|(n, v)| n * v).sum()
    }

    /// A parent node, an archived intersection point or a point of the
    /// current simplex.
    fn pt(&self, id: Wp, local: &[Inter]) -> Result<Pt, String> {
        let at = |k: usize| k.checked_sub(1);
        let p = match id {
            Wp::Node(j) => {
                at(j.into()).filter(|&k| k < self.nno).map(|k| Pt { xi: node_coords(self.t)[k], x: self.coords[k] })
            }
            Wp::Inter(j) => at(j.into()).and_then(|k| local.get(k).map(|p| p.p)),
            Wp::PInt(j) => at(j.into()).and_then(|k| self.pint.get(k).copied()),
            _ => None,
        };
        p.ok_or_else(|| format!("TOPOSE: internal error, point {id:?} is unknown"))
    }

    /// Level set of a vertex as `xdecov` sums it (and `xdecou` for the
    /// junction test): nodal value at parent nodes, parent interpolation
    /// elsewhere.
    fn vertex_lsn(&self, id: Wp, crack: usize, local: &[Inter]) -> Result<f64, String> {
        match id {
            Wp::Node(j) if j > 0 && usize::from(j) <= self.nno => Ok(self.lsn[crack][usize::from(j) - 1]),
            _ => Ok(self.interp(&self.pt(id, local)?.xi, crack)),
        }
    }

    /// Level set of a vertex as `xdecou` reads it on an edge: the
    /// interpolated value at an intersection point is set to 0 below
    /// lonref·1e-12 (round-off of a point on the level set). Code_Aster's
    /// `xdecou` sets it to 0 below lonref·1e-4: that moves a branch onto an
    /// earlier crack's intersection point in one cell and not in the one
    /// beside it, whose cuttings then disagree on the shared face (a junction
    /// 1e-4…1e-6·h from a node: 9.3e-6·U on QUAD4, 2.5e-6·U on HEXA8;
    /// docs/xfem-small-subcells.md).
    fn edge_lsn(&self, id: Wp, crack: usize) -> Result<f64, String> {
        let v = self.vertex_lsn(id, crack, &[])?;
        if !matches!(id, Wp::Node(_)) && v.abs() < self.lonref * 1e-12 {
            Ok(0.0)
        } else {
            Ok(v)
        }
    }

    /// Crossing point of crack `ifiss` on the edge (na, nb) (`xinter` with
    /// no mid-node): Newton solve of φ(ξa + s(ξb − ξa)) = 0 on the parent's
    /// interpolation, from the linear estimate s = φa/(φa − φb), iterates
    /// kept in [0, 1] (`xnewto` / `xdelt0`); the start value is kept when
    /// it does not converge in 100 iterations.
    fn xinter(&self, na: Wp, nb: Wp, la: f64, lb: f64, ifiss: usize) -> Result<Pt, String> {
        let pa = self.pt(na, &[])?.xi;
        let pb = self.pt(nb, &[])?.xi;
        if la - lb == 0.0 {
            return Err("TOPOSE: xinter: equal level sets at the ends of a cut edge".into());
        }
        let s0 = la / (la - lb);
        let dir = V3::from(pb) - V3::from(pa);
        let on_edge = |s: f64| -> [f64; 3] {
            let pm = [0, 1, 2].map(|j| (pa[j] + pb[j]) / 2.0);
            let (wa, wm, wb) = (2.0 * (1.0 - s) * (0.5 - s), 4.0 * s * (1.0 - s), 2.0 * s * (s - 0.5));
            [0, 1, 2].map(|j| wa * pa[j] + wm * pm[j] + wb * pb[j])
        };
        let nn = self.nno;
        let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
        let mut s = s0;
        let mut iter = 0;
        loop {
            let xi = on_edge(s);
            shape_and_deriv(self.t, &xi, &mut n, &mut dn);
            let f: f64 = n.iter().zip(self.lsn[ifiss]).map(|(a, b)| a * b).sum();
            let df: f64 = dn.iter().zip(self.lsn[ifiss]).map(|(d, v)| v * V3::from(*d).dot(&dir)).sum();
            if df.abs() <= 1.0 / f64::MAX || !df.is_finite() {
                return Err("TOPOSE: xinter: zero derivative of the level set along a cut edge".into());
            }
            let delta = f / df;
            s -= delta;
            iter += 1;
            if iter == 100 {
                s = s0;
                break;
            }
            if s > 1.0 {
                s = (s + delta + 1.0) / 2.0;
            } else if s < 0.0 {
                s = (s + delta) / 2.0;
            }
            let (refe, eps) = if s * s <= 1e-9 { (1.0, 1e-11) } else { (s * s, 1e-9) };
            if iter >= 3 && (delta * delta / refe).sqrt() <= eps {
                // xnewto applies the last increment once more on exit.
                s -= delta;
                break;
            }
        }
        let xi = on_edge(s);
        if !inside(self.t, &xi) {
            return Err(format!("TOPOSE: xinter: the crossing point {xi:?} is outside the parent (xveri0)"));
        }
        Ok(Pt { xi, x: map_to_real(self.t, self.coords, &xi) })
    }

    /// Intersection points of simplex `sub` with crack `ifiss` (`xdecou`):
    /// the points and how many are vertices of the simplex.
    fn decou(&self, sub: &[Wp], ifiss: usize, fisc: &[(usize, f64)]) -> Result<(Vec<Inter>, usize), String> {
        // Junction: the branch does not exist on this side of its masters.
        for &(m, c) in fisc {
            let mut som = 0.0;
            for &id in sub {
                som += self.vertex_lsn(id, m, &[])?;
            }
            if c * som > 0.0 {
                return Ok((Vec::new(), 0));
            }
        }
        // Capacity of the point list (`xdecou`): 4 on a tetrahedron, 3 on a
        // boundary triangle of a 3D mesh, 2 on a triangle of a 2D mesh and
        // on a segment.
        let ptmax = match (self.ndim, self.dim) {
            (_, 3) => 4,
            (3, 2) => 3,
            _ => 2,
        };
        let tol = self.lonref * CRIDIST;
        let mut inter: Vec<Inter> = Vec::new();
        let mut npts = 0;
        let add = |list: &mut Vec<Inter>, p: Inter| -> Result<bool, String> {
            if list.iter().any(|q| dist(&q.p.x, &p.p.x) < tol) {
                return Ok(false);
            }
            if list.len() == ptmax {
                return Err(format!(
                    "TOPOSE: more than {ptmax} intersection points of crack {} on a {} sub-cell (xajpin)",
                    ifiss + 1,
                    subcell_type(self.dim).name()
                ));
            }
            list.push(p);
            Ok(true)
        };
        for (ia, e) in self.edges().iter().enumerate() {
            let (na, nb) = (sub[e[0] - 1], sub[e[1] - 1]);
            let a = self.pt(na, &[])?;
            let b = self.pt(nb, &[])?;
            let la = self.edge_lsn(na, ifiss)?;
            let lb = self.edge_lsn(nb, ifiss)?;
            if la * lb > 0.0 {
                continue;
            }
            if la == 0.0 && add(&mut inter, Inter { p: a, edge: 0, node: Some(na) })? {
                npts += 1;
            }
            if lb == 0.0 && add(&mut inter, Inter { p: b, edge: 0, node: Some(nb) })? {
                npts += 1;
            }
            if la != 0.0 && lb != 0.0 {
                let c = self.xinter(na, nb, la, lb, ifiss)?;
                add(&mut inter, Inter { p: c, edge: ia + 1, node: None })?;
            }
        }
        // Selection sort by edge number (vertices first).
        let n = inter.len();
        for pd in 0..n.saturating_sub(1) {
            let mut pp = pd;
            for i in pd..n {
                if inter[i].edge < inter[pp].edge {
                    pp = i;
                }
            }
            inter.swap(pp, pd);
        }
        // Four points: point 4 is the one whose edge shares no vertex with point 1's.
        if n == 4 && npts == 0 {
            let ed = self.edges();
            let a1 = inter[0].edge;
            for ia in 1..3 {
                let a2 = inter[ia].edge;
                let shared = (0..2).any(|i| (0..2).any(|j| ed[a1 - 1][i] == ed[a2 - 1][j]));
                if !shared {
                    inter.swap(ia, 3);
                }
            }
        }
        Ok((inter, npts))
    }
}

/// First four nodes of the three tetrahedra of a prism (`xpente`, default
/// pattern, linear part).
fn xpente(n: &[Wp; 6]) -> [[Wp; 4]; 3] {
    [[n[0], n[4], n[1], n[5]], [n[3], n[4], n[0], n[5]], [n[0], n[1], n[2], n[5]]]
}

impl Ctx<'_> {
    /// Children of simplex `sub` (`xdecov`): connectivities with the local
    /// the intersection points of the simplex ([`Wp::Inter`]).
    fn decov(&self, sub: &[Wp], inter: &[Inter], npts: usize) -> Result<Vec<Vec<Wp>>, String> {
        let n = inter.len();
        let ed = self.edges();
        let s = |k: usize| sub[k - 1];
        let bad = |what: &str| {
            format!(
                "TOPOSE: {} sub-cell with {n} intersection point(s), {npts} on its vertices: {what} (xdecov)",
                subcell_type(self.dim).name()
            )
        };
        let mut out: Vec<Vec<Wp>> = Vec::new();
        if self.dim == 1 {
            // A boundary segment (`xdecov`, ndime = 1).
            match n {
                0 => out.push(sub.to_vec()),
                1 => {
                    if npts == 1 {
                        out.push(sub.to_vec());
                    } else {
                        let a1 = inter[0].edge;
                        if a1 == 0 {
                            return Err(bad("unexpected point order"));
                        }
                        out.push(vec![I(1), s(ed[a1 - 1][0])]);
                        out.push(vec![I(1), s(ed[a1 - 1][1])]);
                    }
                }
                2 => {
                    // The interface contains the segment.
                    if npts != n {
                        return Err(bad("two points, not both vertices"));
                    }
                    out.push(sub.to_vec());
                }
                _ => return Err(bad("too many points")),
            }
        } else if self.dim == 2 {
            match n {
                0 | 1 => {
                    if npts != n {
                        return Err(bad("a single point that is not a vertex"));
                    }
                    out.push(sub.to_vec());
                }
                2 => {
                    let (a1, a2) = (inter[0].edge, inter[1].edge);
                    match npts {
                        2 => out.push(sub.to_vec()),
                        1 => {
                            if a1 != 0 || a2 == 0 {
                                return Err(bad("unexpected point order"));
                            }
                            let v = inter[0].node.ok_or_else(|| bad("unexpected point order"))?;
                            out.push(vec![v, I(2), s(ed[a2 - 1][0])]);
                            out.push(vec![v, I(2), s(ed[a2 - 1][1])]);
                        }
                        _ => {
                            if a1 == 0 {
                                return Err(bad("unexpected point order"));
                            }
                            let (a, b, c) = vertex_and_ends(ed, a1, a2);
                            if a * b * c == 0 {
                                return Err(bad("the two cut edges share no vertex"));
                            }
                            out.push(vec![I(1), I(2), s(a)]);
                            out.push(vec![I(1), I(2), s(c)]);
                            out.push(vec![I(1), s(b), s(c)]);
                        }
                    }
                }
                3 => {
                    // The interface contains a boundary triangle of a 3D mesh.
                    if npts != n {
                        return Err(bad("three points, not all vertices"));
                    }
                    out.push(sub.to_vec());
                }
                _ => return Err(bad("too many points")),
            }
        } else {
            match n {
                0..=2 => {
                    if npts != n {
                        return Err(bad("fewer than 3 points, not all vertices"));
                    }
                    out.push(sub.to_vec());
                }
                3 => {
                    let (a1, a2, a3) = (inter[0].edge, inter[1].edge, inter[2].edge);
                    match npts {
                        3 => out.push(sub.to_vec()),
                        2 => {
                            if a1 != 0 || a2 != 0 || a3 == 0 {
                                return Err(bad("unexpected point order"));
                            }
                            let (Some(v1), Some(v2)) = (inter[0].node, inter[1].node) else {
                                return Err(bad("unexpected point order"));
                            };
                            out.push(vec![v1, v2, I(3), s(ed[a3 - 1][0])]);
                            out.push(vec![v1, v2, I(3), s(ed[a3 - 1][1])]);
                        }
                        1 => {
                            if a1 != 0 || a2 == 0 || a3 == 0 {
                                return Err(bad("unexpected point order"));
                            }
                            let (a, b, c) = vertex_and_ends(ed, a2, a3);
                            if a * b * c == 0 {
                                return Err(bad("the two cut edges share no vertex"));
                            }
                            let v = inter[0].node.ok_or_else(|| bad("unexpected point order"))?;
                            out.push(vec![v, I(2), I(3), s(a)]);
                            out.push(vec![v, I(2), I(3), s(c)]);
                            out.push(vec![v, I(2), s(b), s(c)]);
                        }
                        _ => {
                            let (a, b, c) = vertex_and_ends(ed, a1, a2);
                            // The end of edge a3 other than a (the last one when neither is a).
                            let d = ed[a3 - 1].iter().rev().find(|&&v| v != a).copied().unwrap_or(0);
                            if a * b * c * d == 0 {
                                return Err(bad("inconsistent cut edges"));
                            }
                            out.push(vec![I(1), I(2), I(3), s(a)]);
                            let pr = [I(3), I(1), I(2), s(d), s(b), s(c)];
                            out.extend(xpente(&pr).iter().map(|t| t.to_vec()));
                        }
                    }
                }
                4 => {
                    let a: Vec<usize> = inter.iter().map(|p| p.edge).collect();
                    if a.contains(&0) {
                        return Err(bad("four points, some of them vertices"));
                    }
                    let (va, vb, vc) = vertex_and_ends(ed, a[0], a[1]);
                    let (vd, _, _) = vertex_and_ends(ed, a[2], a[3]);
                    if va * vb * vc * vd == 0 {
                        return Err(bad("inconsistent cut edges"));
                    }
                    let p1 = [I(4), I(2), s(vc), I(3), I(1), s(vb)];
                    let p2 = [s(va), I(1), I(2), s(vd), I(3), I(4)];
                    out.extend(xpente(&p1).iter().map(|t| t.to_vec()));
                    out.extend(xpente(&p2).iter().map(|t| t.to_vec()));
                }
                _ => return Err(bad("too many points")),
            }
        }
        Ok(out)
    }

    /// Orientation of the tetrahedra (`xdecov`): a negative volume swaps
    /// vertices 3 and 4.
    fn orient(&self, children: &mut [Vec<Wp>], local: &[Inter]) -> Result<(), String> {
        if self.dim != 3 {
            return Ok(());
        }
        for ch in children.iter_mut() {
            let mut v = [V3::zeros(); 4];
            for (k, vk) in v.iter_mut().enumerate() {
                *vk = V3::from(self.pt(ch[k], local)?.x);
            }
            let ps = (v[1] - v[0]).cross(&(v[2] - v[0])).dot(&(v[3] - v[0]));
            if ps < 0.0 {
                ch.swap(2, 3);
            }
        }
        Ok(())
    }

    /// Heaviside values of the children (`xdecov`): earlier cracks copied
    /// from the parent simplex; the current one 0 on the inactive side of
    /// a junction, else the sign of the sum of its level set over the
    /// vertices.
    fn heaviside(
        &self,
        children: &[Vec<Wp>],
        local: &[Inter],
        parent_he: &[i32],
        ifiss: usize,
        fisc: &[(usize, f64)],
    ) -> Result<Vec<Vec<i32>>, String> {
        let mut out = Vec::with_capacity(children.len());
        for ch in children {
            let mut he: Vec<i32> = parent_he[..ifiss].to_vec();
            he.push(0);
            let mut inactive = false;
            for &(m, c) in fisc {
                let mut som = 0.0;
                for &id in ch {
                    som += self.vertex_lsn(id, m, local)?;
                }
                inactive |= c * som > 0.0;
            }
            if !inactive {
                let mut som = 0.0;
                for &id in ch {
                    som += self.vertex_lsn(id, ifiss, local)?;
                }
                if som == 0.0 {
                    return Err(format!(
                        "TOPOSE: the level set of crack {} sums to 0 over a sub-cell: its side is undefined \
                         (xdecov)",
                        ifiss + 1
                    ));
                }
                he[ifiss] = if som < 0.0 { -1 } else { 1 };
            }
            out.push(he);
        }
        Ok(out)
    }
}

/// Cut a linear parent cell by its interfaces, as TOPOSE (`te0514`,
/// `xdivte` / `xdecou` / `xdecov`) does. `coords` and `cracks[k].lsn`
/// follow Code_Aster's local node order; the cracks are in the cell's
/// order (model order), `master` pointing into that list.
pub fn topose_linear(t: CellType, coords: &[[f64; 3]], cracks: &[CrackInCell]) -> Result<Cutting, String> {
    if t == CellType::Seg2 {
        return Err("TOPOSE: a SEG2 parent is a boundary cell: use topose_linear_boundary".into());
    }
    cut_linear(t, t.dim(), coords, cracks)
}

/// Cut a linear BOUNDARY cell of the model (a skin element on a Heaviside
/// cell: `te0514` with `ndime < ndim`) by its interfaces: a SEG2 in a 2D
/// or 3D mesh, a TRIA3 or QUAD4 face in a 3D mesh (`mesh_dim`). The same
/// algorithm as for the bulk cells (`xdivte`: SEG2 → (1,2), QUAD4 → (1,2,4)
/// and (2,3,4); `xdecou` with at most 2 points on a segment and 3 on a
/// face of a 3D mesh; `xdecov`: a segment cut at an inner point gives
/// (P,A) and (P,B), a face cut by a segment the 2 or 3 triangles of the 2D
/// case; the Heaviside value of each child from the sum of the level set
/// over its vertices). The sub-cells are SEG2 / TRIA3 in Code_Aster's local
/// order.
pub fn topose_linear_boundary(
    t: CellType,
    mesh_dim: usize,
    coords: &[[f64; 3]],
    cracks: &[CrackInCell],
) -> Result<Cutting, String> {
    match (t, mesh_dim) {
        (CellType::Seg2, 2 | 3) | (CellType::Tria3 | CellType::Quad4, 3) => cut_linear(t, mesh_dim, coords, cracks),
        _ => Err(format!(
            "TOPOSE: boundary cell type {} in a {mesh_dim}D mesh is not supported (SEG2, and TRIA3 / QUAD4 faces of a 3D mesh)",
            t.name()
        )),
    }
}

/// Orientation of the sub-cells of a boundary cell of dimension
/// `mesh_dim − 1` (`xoripe`, after TOPOSE): `outward` is the boundary
/// cell's centroid minus the centroid of its support cell (the cell of the
/// mesh's dimension holding it); a sub-cell whose normal — (y_b − y_a,
/// −(x_b − x_a)) of its first two vertices in 2D, (b − a) × (c − a) in 3D —
/// points against it has its vertices 1 and 2 (2D) or 2 and 3 (3D)
/// swapped; a TRIA6 sub-cell of a face of a 3D mesh has its mid-nodes 4
/// and 6 swapped too, a SEG3 of a 2D mesh keeps its mid-node 3 (`xoripe`'s
/// `quadratique` is for 3D only). Boundary cells of lower dimension (a SEG2
/// in 3D) are left as they are, as `xoripe` does: the caller passes only
/// cells of dimension `mesh_dim − 1`. Returns the number of sub-cells
/// reoriented.
pub fn orient_boundary(cut: &mut Cutting, mesh_dim: usize, outward: &[f64; 3]) -> usize {
    let mut n = 0;
    // Linear and quadratic sub-cells of dimension mesh_dim − 1.
    let quadratic = if mesh_dim == 2 { 3 } else { 6 };
    for sc in cut.subcells.iter_mut() {
        let len = sc.nodes.len();
        if len != mesh_dim && len != quadratic {
            continue;
        }
        let p = |k: usize| V3::from(cut.points[sc.nodes[k]].x);
        let ab = p(1) - p(0);
        let normal = if mesh_dim == 2 { V3::new(ab[1], -ab[0], 0.0) } else { ab.cross(&(p(2) - p(0))) };
        let d: f64 = (0..mesh_dim).map(|j| normal[j] * outward[j]).sum();
        if d < 0.0 {
            sc.nodes.swap(mesh_dim - 2, mesh_dim - 1);
            if mesh_dim == 3 && len == quadratic {
                sc.nodes.swap(3, 5);
            }
            n += 1;
        }
    }
    n
}

fn cut_linear(t: CellType, ndim: usize, coords: &[[f64; 3]], cracks: &[CrackInCell]) -> Result<Cutting, String> {
    let (dim, nno, split): (usize, usize, Vec<Vec<Wp>>) = match t {
        CellType::Seg2 => (1, 2, vec![vec![N(1), N(2)]]),
        CellType::Tria3 => (2, 3, vec![vec![N(1), N(2), N(3)]]),
        CellType::Quad4 => (2, 4, QUAD4_SPLIT.iter().map(|s| s.to_vec()).collect()),
        CellType::Tetra4 => (3, 4, vec![vec![N(1), N(2), N(3), N(4)]]),
        CellType::Penta6 => (3, 6, prism_split(&PENTA6_SPLIT, coords)),
        CellType::Hexa8 => (3, 8, HEXA8_SPLIT.iter().map(|s| s.to_vec()).collect()),
        _ => {
            return Err(format!(
                "TOPOSE: parent cell type {} is not a supported linear cell (TRIA3, QUAD4, TETRA4, PENTA6, HEXA8)",
                t.name()
            ))
        }
    };
    if coords.len() != nno {
        return Err(format!("TOPOSE: {} needs {nno} node coordinates, got {}", t.name(), coords.len()));
    }
    if cracks.is_empty() {
        return Err("TOPOSE: the cell sees no crack".into());
    }
    if cracks.len() > 10 {
        return Err("TOPOSE: more than 10 cracks in a cell (XFEM2_6)".into());
    }
    for (k, c) in cracks.iter().enumerate() {
        if c.lsn.len() != nno {
            return Err(format!("TOPOSE: crack {} has {} level-set values for {nno} nodes", k + 1, c.lsn.len()));
        }
    }
    let mut ctx = Ctx {
        t,
        dim,
        ndim,
        nno,
        coords,
        lsn: cracks.iter().map(|c| c.lsn.as_slice()).collect(),
        pint: Vec::new(),
        lonref: loncar(t, coords),
    };
    let mut subs = split;
    let mut heav: Vec<Vec<i32>> = vec![vec![0; cracks.len()]; subs.len()];
    // (intersection point, earlier crack whose level set is 0 at both ends of its edge).
    let mut on_crack: Vec<(usize, usize)> = Vec::new();
    for ifiss in 0..cracks.len() {
        let fisc = master_chain(cracks, ifiss)?;
        let nit = subs.len();
        for it in 0..nit {
            let (inter, npts) = ctx.decou(&subs[it], ifiss, &fisc)?;
            let mut children = ctx.decov(&subs[it], &inter, npts)?;
            ctx.orient(&mut children, &inter)?;
            let hes = ctx.heaviside(&children, &inter, &heav[it], ifiss, &fisc)?;
            // Archive the points on edges; a point already known keeps the
            // last matching number.
            for (ipt, p) in inter.iter().enumerate() {
                let found = ctx.pint.iter().rposition(|q| dist(&q.x, &p.p.x) < ctx.lonref * CRIDIST);
                if p.edge == 0 {
                    continue;
                }
                let ni = match found {
                    Some(i) => i,
                    None => {
                        ctx.pint.push(p.p);
                        ctx.pint.len() - 1
                    }
                };
                let e = ctx.edges()[p.edge - 1];
                let (na, nb) = (subs[it][e[0] - 1], subs[it][e[1] - 1]);
                for f in 0..ifiss {
                    if ctx.edge_lsn(na, f)? == 0.0 && ctx.edge_lsn(nb, f)? == 0.0 && !on_crack.contains(&(ni, f)) {
                        on_crack.push((ni, f));
                    }
                }
                for ch in children.iter_mut() {
                    for v in ch.iter_mut() {
                        if *v == Wp::Inter(ipt as u8 + 1) {
                            *v = Wp::PInt(ni as u16 + 1);
                        }
                    }
                }
            }
            for (k, (ch, he)) in children.into_iter().zip(hes).enumerate() {
                if ch.iter().any(|v| matches!(v, Wp::Inter(_))) {
                    return Err("TOPOSE: internal error, a local point id was left in a sub-cell".into());
                }
                let mut h = heav[it].clone();
                h[..=ifiss].copy_from_slice(&he);
                if k == 0 {
                    subs[it] = ch;
                    heav[it] = h;
                } else {
                    subs.push(ch);
                    heav.push(h);
                }
            }
        }
    }
    let ncr = cracks.len();
    let rnodes = node_coords(t);
    let mut points: Vec<CutPoint> = (0..nno)
        .map(|j| CutPoint {
            id: PointId::Node(j as u8 + 1),
            xi: rnodes[j],
            x: coords[j],
            lsn: (0..ncr).map(|k| cracks[k].lsn[j]).collect(),
        })
        .collect();
    for (k, p) in ctx.pint.iter().enumerate() {
        let lsn = (0..ncr).map(|f| if on_crack.contains(&(k, f)) { 0.0 } else { ctx.interp(&p.xi, f) }).collect();
        points.push(CutPoint { id: PointId::Intersection(k as u16 + 1), xi: p.xi, x: p.x, lsn });
    }
    let index = |id: Wp| -> Result<usize, String> {
        match id {
            Wp::Node(j) if (1..=nno).contains(&usize::from(j)) => Ok(usize::from(j) - 1),
            Wp::PInt(k) if (1..=ctx.pint.len()).contains(&usize::from(k)) => Ok(nno + usize::from(k) - 1),
            _ => Err(format!("TOPOSE: internal error, point {id:?} missing")),
        }
    };
    let subcells = subs
        .iter()
        .zip(heav)
        .map(|(s, he)| Ok(SubCell { nodes: s.iter().map(|&v| index(v)).collect::<Result<Vec<_>, String>>()?, he }))
        .collect::<Result<Vec<_>, String>>()?;
    Ok(Cutting { points, subcells })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids(cut: &Cutting, s: &SubCell) -> Vec<u32> {
        s.nodes.iter().map(|&i| cut.points[i].id.number()).collect()
    }

    fn area(cut: &Cutting, s: &SubCell) -> f64 {
        let p = |k: usize| V3::from(cut.points[s.nodes[k]].x);
        (p(1) - p(0)).cross(&(p(2) - p(0)))[2] / 2.0
    }

    fn volume(cut: &Cutting, s: &SubCell) -> f64 {
        let p = |k: usize| V3::from(cut.points[s.nodes[k]].x);
        (p(1) - p(0)).cross(&(p(2) - p(0))).dot(&(p(3) - p(0))) / 6.0
    }

    fn check_sides(cut: &Cutting) {
        for s in &cut.subcells {
            for (f, &h) in s.he.iter().enumerate() {
                for &i in &s.nodes {
                    assert!(cut.points[i].lsn[f] * h as f64 >= -1e-12, "{:?}", ids(cut, s));
                }
            }
        }
    }

    /// QUAD4 [0,2]×[0,1] cut by y = 0.3 + 0.15 x.
    #[test]
    fn quad4_cut_by_one_line() {
        let c = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let lsn: Vec<f64> = c.iter().map(|p| p[1] - 0.3 - 0.15 * p[0]).collect();
        let cut = topose_linear(CellType::Quad4, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        // Triangle (1,2,4): points on its edges 2 (2-4, the diagonal) and 3
        // (4-1), shared vertex 4. Triangle (2,3,4): edges 1 (2-3) and 3 (4-2),
        // shared vertex 2. First children in slots 1 and 2, the others appended.
        let all: Vec<Vec<u32>> = cut.subcells.iter().map(|s| ids(&cut, s)).collect();
        assert_eq!(
            all,
            vec![
                vec![1001, 1002, 4],
                vec![1003, 1001, 2],
                vec![1001, 1002, 1],
                vec![1001, 2, 1],
                vec![1003, 1001, 4],
                vec![1003, 3, 4],
            ]
        );
        let he: Vec<i32> = cut.subcells.iter().map(|s| s.he[0]).collect();
        assert_eq!(he, vec![1, -1, -1, -1, 1, 1]);
        let x = |id: u32| cut.points.iter().find(|p| p.id.number() == id).unwrap().x;
        // 1001 on the diagonal 2-4, 1002 on 4-1 at y = 0.3, 1003 on 2-3 at y = 0.6.
        assert!((x(1001)[0] - 0.7 / 0.65).abs() < 1e-14 && (x(1001)[1] - (1.0 - 0.35 / 0.65)).abs() < 1e-14);
        assert!(x(1002)[0].abs() < 1e-15 && (x(1002)[1] - 0.3).abs() < 1e-15);
        assert!((x(1003)[0] - 2.0).abs() < 1e-15 && (x(1003)[1] - 0.6).abs() < 1e-15);
        assert_eq!(cut.points.len(), 7);
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s).abs()).sum();
        assert!((total - 2.0).abs() < 1e-14, "{total}");
        check_sides(&cut);
    }

    /// A line through vertex 1 of a QUAD4: vertex points are not archived.
    #[test]
    fn quad4_cut_through_a_vertex() {
        let c = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let lsn: Vec<f64> = c.iter().map(|p| p[1] - 0.25 * p[0]).collect();
        let cut = topose_linear(CellType::Quad4, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        let all: Vec<Vec<u32>> = cut.subcells.iter().map(|s| ids(&cut, s)).collect();
        // (1,2,4): vertex 1 and the diagonal point; (2,3,4): edge 2-3 and the diagonal.
        assert_eq!(all[0], vec![1, 1001, 2]);
        assert_eq!(all[1], vec![1002, 1001, 2]);
        assert_eq!(all[2], vec![1, 1001, 4]);
        assert_eq!(cut.points.iter().filter(|p| matches!(p.id, PointId::Intersection(_))).count(), 2);
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s).abs()).sum();
        assert!((total - 2.0).abs() < 1e-14);
        check_sides(&cut);
    }

    /// The unit cube cut by z = 0.4 + 0.1 x.
    #[test]
    fn hexa8_cut_by_one_plane() {
        let v = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        let c: Vec<[f64; 3]> = (0..8).map(|k| [v[k % 4][0], v[k % 4][1], (k / 4) as f64]).collect();
        let lsn: Vec<f64> = c.iter().map(|p| p[2] - 0.4 - 0.1 * p[0]).collect();
        let cut = topose_linear(CellType::Hexa8, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        let total: f64 = cut.subcells.iter().map(|s| volume(&cut, s)).sum();
        assert!((total - 1.0).abs() < 1e-14, "{total}");
        assert!(cut.subcells.iter().all(|s| volume(&cut, s) > 0.0));
        check_sides(&cut);
        // Every tetra of the split has vertices on both sides: 1 or 3 at z = 0
        // give 4 children, 2 give 6. (6,3,2,4): z = 1,0,0,0 → 4; (4,5,1,2) → 4;
        // (2,5,6,4) → 6; (5,4,8,6) → 4; (3,6,7,8) → 4; (3,8,4,6) → 6.
        assert_eq!(cut.subcells.len(), 4 + 4 + 6 + 4 + 4 + 6);
        // Intersection points: the 4 vertical edges, the diagonals of the 4
        // side faces and the body diagonal 4-6.
        let npint = cut.points.iter().filter(|p| matches!(p.id, PointId::Intersection(_))).count();
        assert_eq!(npint, 4 + 4 + 1);
        for p in cut.points.iter().filter(|p| matches!(p.id, PointId::Intersection(_))) {
            assert!(p.lsn[0].abs() < 1e-15);
        }
        // First tetra (6,3,2,4), cut on its edges 1-2 (6-3), 1-3 (6-2), 1-4
        // (6-4): the tip (101,102,103,6), reoriented (3↔4), stays in slot 1;
        // the prism (103,101,102 | 4,3,2) gives three tetrahedra, appended.
        let all: Vec<Vec<u32>> = cut.subcells.iter().map(|s| ids(&cut, s)).collect();
        assert_eq!(all[0], vec![1001, 1002, 6, 1003]);
        assert_eq!(&all[6..9], &[vec![1003, 3, 1001, 2], vec![4, 3, 1003, 2], vec![1003, 1001, 1002, 2]]);
        let he: Vec<i32> = cut.subcells.iter().map(|s| s.he[0]).collect();
        assert_eq!(&he[..1], &[1]);
        assert_eq!(&he[6..9], &[-1, -1, -1]);
        // 1003 on the body diagonal 4-6 (the split's inner edge).
        let p = |id: u32| cut.points.iter().find(|p| p.id.number() == id).unwrap().x;
        let d = p(1003);
        assert!(
            (d[0] - 4.0 / 9.0).abs() < 1e-15 && (d[1] - 5.0 / 9.0).abs() < 1e-15 && (d[2] - 4.0 / 9.0).abs() < 1e-15
        );
        let x = |id: u32| cut.points.iter().find(|p| p.id.number() == id).unwrap().x;
        // 1001 on 6-3 (the face diagonal x = 1 from (1,0,1) to (1,1,0)): z = 0.5 → y = 0.5.
        assert!((x(1001)[2] - 0.5).abs() < 1e-15 && (x(1001)[1] - 0.5).abs() < 1e-15);
        // 1002 on the vertical edge 6-2 at z = 0.5.
        assert!((x(1002)[0] - 1.0).abs() < 1e-15 && x(1002)[1].abs() < 1e-15 && (x(1002)[2] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn tetra4_through_two_vertices_gives_two_children() {
        let c = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // The plane x = y contains vertices 1 and 4 and cuts edge 2-3.
        let lsn: Vec<f64> = c.iter().map(|p| p[0] - p[1]).collect();
        let cut = topose_linear(CellType::Tetra4, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        assert_eq!(cut.subcells.len(), 2);
        let total: f64 = cut.subcells.iter().map(|s| volume(&cut, s)).sum();
        assert!((total - 1.0 / 6.0).abs() < 1e-15);
        assert!(cut.subcells.iter().all(|s| volume(&cut, s) > 0.0));
        let he: Vec<i32> = cut.subcells.iter().map(|s| s.he[0]).collect();
        assert_eq!(he, vec![1, -1]);
        check_sides(&cut);
    }

    #[test]
    fn junction_skip_leaves_the_branch_at_zero() {
        // FISS1: y = 0.5; FISS2: x = 1 exists where y < 0.5 (coef +1: c·φ1 < 0).
        let c = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let l1: Vec<f64> = c.iter().map(|p| p[1] - 0.5).collect();
        let l2: Vec<f64> = c.iter().map(|p| p[0] - 1.0).collect();
        let cracks = [CrackInCell { lsn: l1, master: None }, CrackInCell { lsn: l2, master: Some((0, 1.0)) }];
        let cut = topose_linear(CellType::Quad4, &c, &cracks).unwrap();
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s).abs()).sum();
        assert!((total - 2.0).abs() < 1e-14);
        check_sides(&cut);
        for s in &cut.subcells {
            let cy = s.nodes.iter().map(|&i| cut.points[i].x[1]).sum::<f64>() / 3.0;
            assert_eq!(s.he[1] == 0, cy > 0.5, "{:?} {:?}", ids(&cut, s), s.he);
        }
        let tuples: std::collections::BTreeSet<Vec<i32>> = cut.subcells.iter().map(|s| s.he.clone()).collect();
        assert_eq!(tuples.len(), 3);
    }

    #[test]
    fn penta6_cut_by_one_plane() {
        let tri = [[0.0, 1.0], [0.0, 0.0], [1.0, 0.0]];
        let c: Vec<[f64; 3]> = (0..6).map(|k| [tri[k % 3][0], tri[k % 3][1], (k / 3) as f64]).collect();
        let lsn: Vec<f64> = c.iter().map(|p| p[2] - 0.3 - 0.2 * p[1]).collect();
        let cut = topose_linear(CellType::Penta6, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        let total: f64 = cut.subcells.iter().map(|s| volume(&cut, s)).sum();
        assert!((total - 0.5).abs() < 1e-14, "{total}");
        assert!(cut.subcells.iter().all(|s| volume(&cut, s) > 0.0));
        check_sides(&cut);
    }

    #[test]
    fn other_types_are_refused() {
        let e = topose_linear(CellType::Quad8, &[[0.0; 3]; 8], &[]).unwrap_err();
        assert!(e.contains("QUAD8"), "{e}");
    }
}
