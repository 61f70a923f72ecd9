//! The discrete X-FEM operators: unknown numbering, bulk stiffness of cut
//! cells integrated on their sub-cells, interface facets with their local
//! bases and side regions, and the mortar coupling matrices of the cohesive
//! interface (`hm-xfem-formulation.md` §3–§4).
//!
//! Unknowns: per node the standard displacement (`DX DY (DZ)`) and, per
//! enrichment set, a Heaviside displacement (`H1X ...`); per crack and per
//! multiplier packet, λ (cohesive traction), w (interface jump) and μ (total
//! traction), each with `ndim` local components (normal first).
//! Displacement field in a region R: `u = Σ_i N_i (a_i + Σ_j ψ_ij(R) h_ij)`.

use super::model::XfemModel;
use crate::fem::dofs::DofMap;
use crate::fem::quadrature::{aster_rule, gauss_legendre, rule_for_degree, QuadratureRule, RefDomain};
pub use crate::fem::reference::real_gradients;
use crate::fem::reference::{jacobian, jacobian_inverse, shape, shape_and_deriv};
use crate::mesh::{CellType, Mesh};
use nalgebra::Vector3;
use std::collections::{BTreeMap, BTreeSet};

/// Unknown numbering of an X-FEM mechanical problem.
#[derive(Debug, Clone)]
pub struct XDofs {
    pub ndim: usize,
    /// First standard unknown of each node (None: not in the model).
    pub std: Vec<Option<usize>>,
    /// First unknown of each enrichment set of each node.
    pub sets: Vec<Vec<usize>>,
    /// Per crack, per packet: first unknown (λ at +0, w at +ndim, μ at +2·ndim).
    pub packets: Vec<Vec<usize>>,
    pub n: usize,
    /// Counts: standard, Heaviside, interface.
    pub n_std: usize,
    pub n_heaviside: usize,
    pub n_interface: usize,
}

impl XDofs {
    pub fn new(mesh: &Mesh, model_cells: &[usize], xm: &XfemModel, ndim: usize, packets: &[usize]) -> XDofs {
        let nn = mesh.nnodes();
        let mut used = vec![false; nn];
        for &c in model_cells {
            for &n in &mesh.cells[c] {
                used[n] = true;
            }
        }
        let mut std = vec![None; nn];
        let mut sets = vec![Vec::new(); nn];
        let mut n = 0;
        let (mut n_std, mut n_h) = (0, 0);
        for node in 0..nn {
            if !used[node] {
                continue;
            }
            std[node] = Some(n);
            n += ndim;
            n_std += ndim;
            for _ in &xm.node_sets[node] {
                sets[node].push(n);
                n += ndim;
                n_h += ndim;
            }
        }
        let mut pk = Vec::new();
        let start = n;
        for &np in packets {
            let mut v = Vec::with_capacity(np);
            for _ in 0..np {
                v.push(n);
                n += 3 * ndim;
            }
            pk.push(v);
        }
        XDofs { ndim, std, sets, packets: pk, n, n_std, n_heaviside: n_h, n_interface: n - start }
    }

    /// The unknowns of a cell's nodes, node after node: standard then sets.
    pub fn cell_dofs(&self, nodes: &[usize]) -> Vec<usize> {
        let mut v = Vec::new();
        for &n in nodes {
            let s = self.std[n].expect("node of a model cell");
            v.extend(s..s + self.ndim);
            for &b in &self.sets[n] {
                v.extend(b..b + self.ndim);
            }
        }
        v
    }
}

/// What each unknown of a cell is, in [`XDofs::cell_dofs`] order: (local
/// node, enrichment set or None for the standard part, component).
fn cell_columns(nodes: &[usize], xm: &XfemModel, ndim: usize) -> Vec<(usize, Option<usize>, usize)> {
    let mut cols = Vec::new();
    for (a, &n) in nodes.iter().enumerate() {
        cols.extend((0..ndim).map(|i| (a, None, i)));
        for j in 0..xm.node_sets[n].len() {
            cols.extend((0..ndim).map(|i| (a, Some(j), i)));
        }
    }
    cols
}

/// Strain–displacement rows (engineering shear, Code_Aster's order) of a
/// unit displacement along `i` with shape gradient `g`.
fn b_col(ndim: usize, g: &[f64; 3], i: usize) -> [f64; 6] {
    let mut b = [0.0; 6];
    b[i] = g[i];
    if ndim == 2 {
        // xx yy zz xy
        match i {
            0 => b[3] = g[1],
            _ => b[3] = g[0],
        }
    } else {
        // xx yy zz xy xz yz
        match i {
            0 => {
                b[3] = g[1];
                b[4] = g[2];
            }
            1 => {
                b[3] = g[0];
                b[5] = g[2];
            }
            _ => {
                b[4] = g[0];
                b[5] = g[1];
            }
        }
    }
    b
}

/// Bulk integration rule of sub-cells (`XINT`): 12 points (degree 6) on a
/// triangle, 15 points (degree 5) on a tetrahedron.
pub fn subcell_rule(dim: usize) -> QuadratureRule {
    if dim == 2 {
        rule_for_degree(RefDomain::Triangle, 6)
    } else {
        rule_for_degree(RefDomain::Tetrahedron, 5)
    }
}

/// A bulk integration point of a cell: parent reference coordinates, weight
/// (real measure) and region code.
#[derive(Debug, Clone, Copy)]
pub struct BulkPoint {
    pub xi: [f64; 3],
    pub w: f64,
    pub region: i32,
}

/// The bulk integration points of an X-FEM cell: the sub-cell rule mapped
/// through each sub-cell (defined in the parent's reference space) and the
/// parent map.
pub fn bulk_points(t: CellType, coords: &[[f64; 3]], xm: &XfemModel, cell: usize) -> Result<Vec<BulkPoint>, String> {
    subcell_points(t, coords, xm, cell, false)
}

/// The total degree of the shape functions of a cell type in its reference coordinates.
fn shape_degree(t: CellType) -> usize {
    match t {
        CellType::Seg2 | CellType::Tria3 | CellType::Tetra4 => 1,
        CellType::Seg3 | CellType::Quad4 | CellType::Tria6 | CellType::Tetra10 | CellType::Penta6 => 2,
        CellType::Quad8 | CellType::Hexa8 | CellType::Penta15 => 3,
        _ => 4,
    }
}

/// Whether the map of a cell from its reference cell is affine: its Jacobian the same at every node
/// (a simplex with straight edges and mid-nodes at their middles, a parallelogram or parallelepiped).
/// Distorted quadrangles and hexahedra, and quadratic cells with curved edges, are not.
pub fn affine(t: CellType, coords: &[[f64; 3]]) -> bool {
    let nodes = crate::fem::reference::node_coords(t);
    let j0 = jacobian(t, coords, &nodes[0]);
    let scale = j0.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    nodes.iter().skip(1).all(|xi| {
        let j = jacobian(t, coords, xi);
        j.iter().flatten().zip(j0.iter().flatten()).all(|(a, b)| (a - b).abs() <= 1e-12 * scale)
    })
}

/// The degree a rule needs on a sub-cell whose map from its reference simplex is of degree `s` (1
/// straight, 2 curved) in a parent of type `t` to integrate the parent's gradients exactly (the
/// internal forces of a uniform stress): ∇N·det J = adj(J)ᵀ ∇_ξN, of degree p − 1 + (dim − 1)(p − 1)
/// in the parent's reference coordinates for shape functions of degree p (p − 1 when the parent's map
/// is affine, adj(J) constant), composed with the sub-cell map (×s), times its Jacobian determinant
/// (degree dim (s − 1)). 9 on a curved sub-cell of an affine HEXA20 (Code_Aster's FPG15 is of degree
/// 5), 6 on a straight one of a distorted HEXA8, 21 on a curved one of a curved HEXA20.
fn subcell_degree(t: CellType, affine: bool, s: usize) -> usize {
    let (p, dim) = (shape_degree(t), t.dim());
    let adj = if affine { 0 } else { (dim - 1) * (p - 1) };
    s * (p - 1 + adj) + dim * (s - 1)
}

/// The degree a rule needs on a facet whose map from its reference simplex is of degree `s` in a
/// parent of type `t` to integrate the parent's shape functions times the facet's normal measure
/// exactly (the forces of a uniform traction): N of degree p composed with the facet map, times the
/// product of dim − 1 tangents J·dξ/ds (degree s (p − 1) + s − 1 each, s − 1 when J is constant).
fn facet_degree(t: CellType, affine: bool, s: usize) -> usize {
    let (p, dim) = (shape_degree(t), t.dim());
    let pj = if affine { 0 } else { p - 1 };
    s * p + (dim - 1) * (s * pj + s - 1)
}

/// Whether a quadratic simplex (its nodes' reference coordinates in Code_Aster's order) is curved: a
/// mid-node off the middle of its edge.
fn is_curved(st: CellType, xis: &[[f64; 3]]) -> bool {
    let edges = crate::xfem::levelset::edges(st);
    xis.len() > st.nvertices()
        && edges.iter().any(|e| {
            let (a, b, m) = (xis[e[0]], xis[e[1]], xis[e[2]]);
            let len = (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt();
            (0..3).map(|k| (m[k] - (a[k] + b[k]) / 2.0).powi(2)).sum::<f64>().sqrt() > 1e-12 * len
        })
}

/// The integration points of the sub-cells of cut cell `cell`: Code_Aster's sub-cell rule
/// ([`subcell_rule`]), or with `exact`, on a curved sub-cell, a rule of the degree that integrates the
/// internal forces of a uniform stress exactly ([`subcell_degree`]: 9 for an affine HEXA20 parent, where
/// Code_Aster's FPG15 is of degree 5; straight sub-cells too when the parent's map is not affine), so that the linear fields stay exact on curved interfaces.
fn subcell_points(
    t: CellType,
    coords: &[[f64; 3]],
    xm: &XfemModel,
    cell: usize,
    exact: bool,
) -> Result<Vec<BulkPoint>, String> {
    let xc = &xm.cells[&cell];
    let dim = t.dim();
    let st = match xc.cutting.subcells.first().map(|sc| sc.nodes.len()) {
        Some(n) => subcell_type(dim, n),
        None => return Ok(Vec::new()),
    };
    let base = subcell_rule(dim);
    // With `exact`, the rules for straight (s = 1) and curved (s = 2) sub-cells when they are above
    // Code_Aster's.
    let flat = exact && affine(t, coords);
    let upgraded: [Option<QuadratureRule>; 2] = [1, 2].map(|s| {
        let deg = subcell_degree(t, flat, s);
        (exact && deg > base.degree && (s == 2 || !flat)).then(|| rule_for_degree(RefDomain::of(st), deg))
    });
    let nsub = st.nnodes();
    let mut out = Vec::new();
    let mut n = vec![0.0; nsub];
    let mut d = vec![[0.0; 3]; nsub];
    for (s, sc) in xc.cutting.subcells.iter().enumerate() {
        let xis: Vec<[f64; 3]> = sc.nodes.iter().map(|&p| xc.cutting.points[p].xi).collect();
        let rule = upgraded[usize::from(is_curved(st, &xis))].as_ref().unwrap_or(&base);
        for (q, wq) in rule.points.iter().zip(&rule.weights) {
            shape_and_deriv(st, q, &mut n, &mut d);
            let mut xi = [0.0; 3];
            let mut js = [[0.0; 3]; 3];
            for k in 0..nsub {
                for a in 0..dim {
                    xi[a] += n[k] * xis[k][a];
                    for b in 0..dim {
                        js[a][b] += xis[k][a] * d[k][b];
                    }
                }
            }
            let (dets, regular) = jacobian_inverse(&js, dim);
            regular.ok_or_else(|| format!("degenerate sub-cell {} of the cut cell", s + 1))?;
            let (detp, regular) = jacobian_inverse(&jacobian(t, coords, &xi), dim);
            regular.ok_or("degenerate parent cell")?;
            out.push(BulkPoint { xi, w: wq * dets.abs() * detp.abs(), region: xc.regions[s] });
        }
    }
    Ok(out)
}

/// The integration points of a model cell: those of its sub-cells when it is cut, else its RIGI rule.
fn cell_points(t: CellType, coords: &[[f64; 3]], xm: &XfemModel, cell: usize) -> Result<Vec<BulkPoint>, String> {
    if xm.cells.contains_key(&cell) {
        return subcell_points(t, coords, xm, cell, true);
    }
    let rule = crate::fem::elasticity::rigi_rule(t);
    let mut v = Vec::new();
    for (q, w) in rule.points.iter().zip(&rule.weights) {
        let (_, _, det) = real_gradients(t, coords, q).ok_or("degenerate cell")?;
        v.push(BulkPoint { xi: *q, w: w * det, region: 0 });
    }
    Ok(v)
}

/// The nodal forces of a uniform body force `f` (force per unit volume, e.g. ρ g) on a cell, in
/// [`XDofs::cell_dofs`] order: ∫ N_a f_i on the standard unknowns and ∫ N_a ψ f_i on the Heaviside ones,
/// over the sub-cells of a cut cell.
pub fn body_force(
    t: CellType,
    coords: &[[f64; 3]],
    nodes: &[usize],
    xm: &XfemModel,
    cell: usize,
    ndim: usize,
    f: &[f64; 3],
) -> Result<Vec<f64>, String> {
    let cols = cell_columns(nodes, xm, ndim);
    let mut fe = vec![0.0; cols.len()];
    for p in cell_points(t, coords, xm, cell)? {
        let ff = shape(t, &p.xi);
        for (r, &(a, set, i)) in cols.iter().enumerate() {
            let psi = match set {
                None => 1.0,
                Some(j) => xm.psi(nodes[a], j, p.region),
            };
            fe[r] += p.w * ff[a] * psi * f[i];
        }
    }
    Ok(fe)
}

/// The nodal forces of a known pore pressure acting on the skeleton through the Biot coefficient `b`
/// (saturated HM with every hydraulic unknown prescribed): the stress σ_p = −b p 1 of the mixture moved
/// to the right-hand side, ∫ Bᵀ (b p 1), in [`XDofs::cell_dofs`] order. The pressure is interpolated as
/// the X-FEM HM elements do (`xcabhm`): with the functions N̂ of the cell's vertices,
/// p = Σ_v N̂_v (p_v + Σ_j ψ_vj h_vj), enriched with the displacement's Heaviside functions ψ;
/// `pre1[v]` and `hpre1[v][j]` are the values at the cell's `v`-th vertex.
#[allow(clippy::too_many_arguments)]
pub fn pore_pressure_force(
    t: CellType,
    coords: &[[f64; 3]],
    nodes: &[usize],
    xm: &XfemModel,
    cell: usize,
    ndim: usize,
    b: f64,
    pre1: &[f64],
    hpre1: &[Vec<f64>],
) -> Result<Vec<f64>, String> {
    let cols = cell_columns(nodes, xm, ndim);
    let mut fe = vec![0.0; cols.len()];
    let tv = crate::fem::elasticity::vertex_type(t);
    let nv = tv.nnodes();
    for p in cell_points(t, coords, xm, cell)? {
        let (_, g, _) = real_gradients(t, coords, &p.xi).ok_or("degenerate cell")?;
        let nh = shape(tv, &p.xi);
        let mut pv = 0.0;
        for v in 0..nv {
            let mut pv_v = pre1[v];
            for (j, h) in hpre1[v].iter().enumerate() {
                pv_v += xm.psi(nodes[v], j, p.region) * h;
            }
            pv += nh[v] * pv_v;
        }
        if pv == 0.0 {
            continue;
        }
        for (r, &(a, set, i)) in cols.iter().enumerate() {
            let psi = match set {
                None => 1.0,
                Some(j) => xm.psi(nodes[a], j, p.region),
            };
            // The normal strains of a unit displacement along i: ε_ii = ∂N_a/∂x_i.
            fe[r] += p.w * psi * g[a][i] * b * pv;
        }
    }
    Ok(fe)
}

/// Stiffness matrix of a cell on its unknowns ([`XDofs::cell_dofs`] order),
/// row-major; `hooke` on engineering strains of `nsig` components.
#[allow(clippy::too_many_arguments)]
pub fn bulk_stiffness(
    t: CellType,
    coords: &[[f64; 3]],
    nodes: &[usize],
    xm: &XfemModel,
    cell: usize,
    hooke: &[[f64; 6]; 6],
    nsig: usize,
    ndim: usize,
) -> Result<Vec<f64>, String> {
    let points = cell_points(t, coords, xm, cell)?;
    // Columns: (node index in cell, factor selector) per unknown.
    let cols = cell_columns(nodes, xm, ndim);
    let nd = cols.len();
    let mut k = vec![0.0; nd * nd];
    let mut b = vec![[0.0; 6]; nd];
    for p in &points {
        let (_, g, _) = real_gradients(t, coords, &p.xi).ok_or("degenerate cell")?;
        for (c, &(a, set, i)) in cols.iter().enumerate() {
            let f = match set {
                None => 1.0,
                Some(j) => xm.psi(nodes[a], j, p.region),
            };
            b[c] = if f == 0.0 { [0.0; 6] } else { b_col(ndim, &g[a], i).map(|v| v * f) };
        }
        let db: Vec<[f64; 6]> = b
            .iter()
            .map(|bc| {
                let mut r = [0.0; 6];
                for (s, rs) in r.iter_mut().enumerate().take(nsig) {
                    *rs = (0..nsig).map(|q| hooke[s][q] * bc[q]).sum();
                }
                r
            })
            .collect();
        for r in 0..nd {
            if b[r].iter().all(|v| *v == 0.0) {
                continue;
            }
            for c in 0..nd {
                let v: f64 = (0..nsig).map(|s| b[r][s] * db[c][s]).sum();
                k[r * nd + c] += p.w * v;
            }
        }
    }
    Ok(k)
}

/// A facet of an interface inside a cell: a face of a sub-cell on the
/// interface, seen from the slave (−) side.
#[derive(Debug, Clone)]
pub struct Facet {
    pub cell: usize,
    /// Parent reference coordinates of the facet's nodes (SEG3 / TRIA6 order).
    pub xi: Vec<[f64; 3]>,
    /// Global sign tuples of the slave and master sides.
    pub slave: Vec<i32>,
    pub master: Vec<i32>,
    /// Parent reference coordinates of the slave sub-cell's vertex off the facet: the facet's normal
    /// points away from it, from the − to the + side.
    pub inner: [f64; 3],
    /// The slave sub-cell (its nodes' parent reference coordinates) and the facet's nodes among them,
    /// when the facet is one of its faces: the side is then read from the sub-cell's own map.
    pub face_of: Option<(Vec<[f64; 3]>, Vec<usize>)>,
}

/// The simplex type of a sub-cell from its node count.
pub fn subcell_type(dim: usize, nnodes: usize) -> CellType {
    match (dim, nnodes) {
        (2, 3) => CellType::Tria3,
        (2, _) => CellType::Tria6,
        (_, 4) => CellType::Tetra4,
        _ => CellType::Tetra10,
    }
}

const TRIA3_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];
const TETRA4_FACES: [[usize; 3]; 4] = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
const TRIA6_EDGES: [[usize; 3]; 3] = [[0, 1, 3], [1, 2, 4], [2, 0, 5]];
const TETRA10_FACES: [[usize; 6]; 4] = [[0, 1, 2, 4, 5, 6], [0, 1, 3, 4, 8, 7], [0, 2, 3, 6, 9, 7], [1, 2, 3, 5, 9, 8]];

/// The facets of crack `g` (model index) in every X-FEM cell that sees it,
/// in cell order. `tol` is a length: a point is on the interface when
/// |φ| ≤ tol.
pub fn facets(mesh: &Mesh, xm: &XfemModel, g: usize, tol: f64) -> Vec<Facet> {
    let mut out = Vec::new();
    for (&c, xc) in &xm.cells {
        let Some(p) = xc.cracks.iter().position(|&k| k == g) else { continue };
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let linear = xc.cutting.subcells.first().is_some_and(|sc| sc.nodes.len() == mesh.dim + 1);
        let faces: Vec<Vec<usize>> = match (mesh.dim, linear) {
            (2, true) => TRIA3_EDGES.iter().map(|e| e.to_vec()).collect(),
            (2, false) => TRIA6_EDGES.iter().map(|e| e.to_vec()).collect(),
            (_, true) => TETRA4_FACES.iter().map(|f| f.to_vec()).collect(),
            (_, false) => TETRA10_FACES.iter().map(|f| f.to_vec()).collect(),
        };
        // Vertex sets of the faces of the master-side sub-cells (he = +1).
        let key = |sc: &super::topose::SubCell, f: &[usize]| -> Vec<usize> {
            let mut k: Vec<usize> = f[..mesh.dim].iter().map(|&l| sc.nodes[l]).collect();
            k.sort_unstable();
            k
        };
        let master_faces: std::collections::BTreeSet<Vec<usize>> = xc
            .cutting
            .subcells
            .iter()
            .filter(|sc| sc.he[p] == 1)
            .flat_map(|sc| faces.iter().map(move |f| key(sc, f)))
            .collect();
        // Faces of two slave-side sub-cells are inside the slave side, whatever their vertices' level set
        // (a point `xdecqu` put at a mid-node it set to 0, vertices snapped by `xajuls`).
        let mut slave_count: BTreeMap<Vec<usize>, usize> = BTreeMap::new();
        for sc in xc.cutting.subcells.iter().filter(|sc| sc.he[p] == -1) {
            for f in &faces {
                *slave_count.entry(key(sc, f)).or_default() += 1;
            }
        }
        let on_level_set = |pts: &[usize]| pts[..mesh.dim].iter().all(|&q| xc.cutting.points[q].lsn[p].abs() <= tol);
        // The vertex of a sub-cell off one of its faces.
        let opposite = |sc: &super::topose::SubCell, f: &[usize]| -> [f64; 3] {
            let l = (0..=mesh.dim).find(|l| !f[..mesh.dim].contains(l)).unwrap_or(0);
            xc.cutting.points[sc.nodes[l]].xi
        };
        // The master-side sub-cells' faces on the level set (sub-cell, face points), gathered when a
        // slave face is not shared.
        let mut master_on: Option<Vec<(usize, Vec<usize>)>> = None;
        for (s, sc) in xc.cutting.subcells.iter().enumerate() {
            if sc.he[p] != -1 {
                continue;
            }
            for f in &faces {
                let pts: Vec<usize> = f.iter().map(|&l| sc.nodes[l]).collect();
                // A face is on the interface when a master-side sub-cell of
                // the cell shares it (the interface inside the parent), or
                // when its vertices are on the level set (an interface along
                // the parent's boundary). Only vertices are tested: on a
                // curved interface (level set snapped by xajuls, mid-nodes
                // moved by xmilfa) the points of a face, and a junction point
                // found on a curved sub-edge, are only near the zero set.
                let shared = master_faces.contains(&key(sc, f));
                if !shared && (!on_level_set(&pts) || slave_count.get(&key(sc, f)).is_some_and(|&n| n > 1)) {
                    continue;
                }
                if !shared {
                    // A face the master side splits (a branch cuts the master side's sub-cells, not the
                    // slave side's: the junction point lies inside this face): the master side differs
                    // along it, so the facets are the master side's pieces, each with its own side.
                    let candidates = master_on.get_or_insert_with(|| {
                        let plus = xc.cutting.subcells.iter().enumerate().filter(|(_, m)| m.he[p] == 1);
                        plus.flat_map(|(t, m)| faces.iter().map(move |g| (t, g.iter().map(|&l| m.nodes[l]).collect())))
                            .filter(|(_, g): &(usize, Vec<usize>)| on_level_set(g))
                            .collect()
                    });
                    let pieces = pieces_of(&xc.cutting, candidates, mesh.dim, &pts, tol);
                    if !pieces.is_empty() {
                        for (plus, g) in pieces {
                            let xi: Vec<[f64; 3]> = g.iter().map(|&q| xc.cutting.points[q].xi).collect();
                            out.push(Facet {
                                cell: c,
                                xi,
                                slave: xc.signs[s].clone(),
                                master: xc.signs[plus].clone(),
                                inner: opposite(sc, f),
                                face_of: None,
                            });
                        }
                        continue;
                    }
                }
                let xi: Vec<[f64; 3]> = pts.iter().map(|&q| xc.cutting.points[q].xi).collect();
                let slave = xc.signs[s].clone();
                // Master side: the crack's sign flipped; branches of this
                // crack exist on that side only where c·(+1) < 0.
                let mut master = slave.clone();
                master[g] = 1;
                let centre = centroid(&xi, mesh.dim);
                let ff = shape(t, &centre);
                for (b, mb) in xm.masters.iter().enumerate() {
                    if let Some((m, coef)) = mb {
                        if *m == g {
                            master[b] = if coef * 1.0 < 0.0 {
                                let v: f64 = nodes.iter().zip(&ff).map(|(&n, f)| f * xm.lsn[b][n]).sum();
                                if v < 0.0 {
                                    -1
                                } else {
                                    1
                                }
                            } else {
                                0
                            };
                        }
                    }
                }
                let sub = sc.nodes.iter().map(|&q| xc.cutting.points[q].xi).collect();
                out.push(Facet { cell: c, xi, slave, master, inner: opposite(sc, f), face_of: Some((sub, f.clone())) });
            }
        }
    }
    out
}

/// Those of the master-side faces on the interface `candidates` (sub-cell, face points) that lie inside
/// the slave face of points `face`, when they cover it exactly (by measure); none otherwise (the face
/// is not split, or the master side is in another cell: an interface along the parent's boundary).
/// `tol` is a length. Faces of linear sub-cells are compared in the parent's reference coordinates,
/// where they are TOPOSE's straight simplices: in real coordinates those of a parent whose map is not
/// affine are curved, and a piece of a face was not found in it (a junction 1e-1 … 1e-3·h from a vertex
/// of a distorted QUAD4: an error proportional to that distance, 1.2e-2·U at 0.1·h). Faces of quadratic
/// sub-cells follow the interface, straight in real coordinates where it is a plane, and are compared
/// there.
fn pieces_of(
    cut: &super::topose::Cutting,
    candidates: &[(usize, Vec<usize>)],
    dim: usize,
    face: &[usize],
    tol: f64,
) -> Vec<(usize, Vec<usize>)> {
    let linear = face.len() == dim;
    if dim == 2 && !linear {
        return pieces_of_seg3(cut, candidates, face, tol);
    }
    let x = |q: usize| Vector3::from(if linear { cut.points[q].xi } else { cut.points[q].x });
    let outer: Vec<Vector3<f64>> = face[..dim].iter().map(|&q| x(q)).collect();
    // `tol` in reference lengths on linear faces, in proportion to the face's first side.
    let real = (Vector3::from(cut.points[face[1]].x) - Vector3::from(cut.points[face[0]].x)).norm();
    let tol = if !linear {
        tol
    } else if real > 0.0 {
        tol * (outer[1] - outer[0]).norm() / real
    } else {
        0.0
    };
    let measure = |v: &[Vector3<f64>]| {
        if dim == 2 {
            (v[1] - v[0]).norm()
        } else {
            (v[1] - v[0]).cross(&(v[2] - v[0])).norm() / 2.0
        }
    };
    // Is point y in the face `outer` (within tol of its line or plane, barycentric coordinates ≥ 0)?
    let inside = |y: Vector3<f64>| -> bool {
        let scale = (outer[1] - outer[0]).norm().max(f64::MIN_POSITIVE);
        let eps = 1e-9 * scale + tol;
        if dim == 2 {
            let e = outer[1] - outer[0];
            let t = (y - outer[0]).dot(&e) / e.norm_squared();
            let off = (y - outer[0] - t * e).norm();
            off <= eps && t * scale >= -eps && (1.0 - t) * scale >= -eps
        } else {
            let (e1, e2) = (outer[1] - outer[0], outer[2] - outer[0]);
            let n = e1.cross(&e2);
            if n.norm() == 0.0 {
                return false;
            }
            let r = y - outer[0];
            if (r.dot(&n) / n.norm()).abs() > eps {
                return false;
            }
            // Barycentric coordinates from the areas.
            let b1 = r.cross(&e2).dot(&n) / n.norm_squared();
            let b2 = e1.cross(&r).dot(&n) / n.norm_squared();
            let lim = -eps / scale;
            b1 >= lim && b2 >= lim && 1.0 - b1 - b2 >= lim
        }
    };
    let mut pieces = Vec::new();
    let mut covered = 0.0;
    for (t, pts) in candidates {
        let vs: Vec<Vector3<f64>> = pts[..dim].iter().map(|&q| x(q)).collect();
        let centre = vs.iter().sum::<Vector3<f64>>() / dim as f64;
        if vs.iter().chain(std::iter::once(&centre)).all(|&v| inside(v)) {
            covered += measure(&vs);
            pieces.push((*t, pts.clone()));
        }
    }
    let whole = measure(&outer);
    if pieces.is_empty() || (covered - whole).abs() > 1e-9 * whole.max(f64::MIN_POSITIVE) {
        return Vec::new();
    }
    pieces
}

/// [`pieces_of`] for a slave face of a quadratic sub-cell in 2D (SEG3: ends, middle): the candidates'
/// points are placed on the face's own quadratic map ξ(s) in the parent's reference coordinates, on
/// which TOPOSE found them (a junction point on a sub-edge, the middles of its halves); a piece lies in
/// the face when its ends and middle are on it, and the pieces cover it when their parameter intervals
/// add up to [0, 1]. The chord in real coordinates misses a junction point on a bent side by the bend
/// (a junction 0.1·h from a vertex of a distorted QUAD8: 6.0e-2·U).
fn pieces_of_seg3(
    cut: &super::topose::Cutting,
    candidates: &[(usize, Vec<usize>)],
    face: &[usize],
    tol: f64,
) -> Vec<(usize, Vec<usize>)> {
    let p = |q: usize| Vector3::from(cut.points[q].xi);
    let (a, b, m) = (p(face[0]), p(face[1]), p(face[2]));
    let curve = |s: f64| a * (2.0 * (1.0 - s) * (0.5 - s)) + m * (4.0 * s * (1.0 - s)) + b * (2.0 * s * (s - 0.5));
    let deriv = |s: f64| a * (4.0 * s - 3.0) + m * (4.0 - 8.0 * s) + b * (4.0 * s - 1.0);
    let chord = (b - a).norm();
    let real = (Vector3::from(cut.points[face[1]].x) - Vector3::from(cut.points[face[0]].x)).norm();
    if chord == 0.0 || real == 0.0 {
        return Vec::new();
    }
    let eps = (1e-9 + tol / real) * chord;
    // The parameter of y on the face, when y is on it.
    let param = |y: Vector3<f64>| -> Option<f64> {
        let e = b - a;
        let mut s = (y - a).dot(&e) / e.norm_squared();
        for _ in 0..50 {
            let (r, d) = (curve(s) - y, deriv(s));
            let step = r.dot(&d) / d.norm_squared().max(f64::MIN_POSITIVE);
            s -= step;
            if step.abs() <= 1e-15 {
                break;
            }
        }
        let lim = eps / chord;
        ((curve(s) - y).norm() <= eps && s >= -lim && s <= 1.0 + lim).then_some(s)
    };
    let mut pieces = Vec::new();
    let mut covered = 0.0;
    for (t, pts) in candidates {
        let (Some(s0), Some(s1), Some(sm)) = (param(p(pts[0])), param(p(pts[1])), param(p(pts[2]))) else {
            continue;
        };
        if (sm - s0) * (s1 - sm) > 0.0 {
            covered += (s1 - s0).abs();
            pieces.push((*t, pts.clone()));
        }
    }
    if pieces.is_empty() || (covered - 1.0).abs() > 1e-9 {
        return Vec::new();
    }
    pieces
}

fn centroid(xi: &[[f64; 3]], dim: usize) -> [f64; 3] {
    let nv = dim; // vertices of a SEG3 (2) or TRIA6 (3)
    let mut c = [0.0; 3];
    for p in &xi[..nv] {
        for k in 0..3 {
            c[k] += p[k] / nv as f64;
        }
    }
    c
}

/// Facet rule of CONTACT ZONE INTEGRATION='GAUSS' with ORDRE_INT (`xminte`):
/// segments FPG2 (orders 1–2), FPG3 (3), FPG4 (≥ 4); triangles FPG3 (1–2),
/// FPG4 (3), FPG6 (4), FPG7 (5).
pub fn facet_rule(dim: usize, order: i64) -> Result<QuadratureRule, String> {
    if dim == 2 {
        let n = match order {
            1 | 2 => 2,
            3 => 3,
            _ => 4,
        };
        Ok(gauss_legendre(n))
    } else {
        let name = match order {
            1 | 2 => "FPG3",
            3 => "FPG4",
            4 => "FPG6",
            5 => "FPG7",
            _ => return Err(format!("ORDRE_INT={order} on triangular facets is not supported yet")),
        };
        aster_rule(CellType::Tria3, name).ok_or_else(|| format!("rule {name} is missing"))
    }
}

/// A facet integration point.
#[derive(Debug, Clone)]
pub struct FacetPoint {
    pub xi: [f64; 3],
    pub w: f64,
    /// Local basis rows: n, τ1 (, τ2).
    pub basis: [[f64; 3]; 3],
}

/// Integration points of a facet with the local basis (`n = ∇φ/|∇φ|`,
/// τ1 = e_x projected on the tangent plane (e_y if n ∥ e_x), τ2 = n × τ1).
pub fn facet_points(
    t: CellType,
    coords: &[[f64; 3]],
    nodes: &[usize],
    lsn: &[f64],
    facet: &Facet,
    rule: &QuadratureRule,
) -> Result<Vec<FacetPoint>, String> {
    let dim = t.dim();
    let ft = match (dim, facet.xi.len()) {
        (2, 2) => CellType::Seg2,
        (2, _) => CellType::Seg3,
        (_, 3) => CellType::Tria3,
        _ => CellType::Tria6,
    };
    let nf = ft.nnodes();
    // On a curved facet, or any facet of a parent whose map is not affine, a rule that integrates the
    // parent's shape functions times the facet's normal measure exactly (the forces of a uniform
    // traction, [`facet_degree`]: 10 on a curved facet of an affine HEXA20, 7 on a flat one of a
    // distorted HEXA8), above the ORDRE_INT rules of Code_Aster (at most degree 7 on segments and 5 on
    // triangles), which are exact on flat facets of affine parents only.
    let (curved, flat) = (is_curved(ft, &facet.xi), affine(t, coords));
    let need = facet_degree(t, flat, 1 + usize::from(curved));
    let upgraded;
    let rule = if (curved || !flat) && rule.degree < need {
        upgraded = rule_for_degree(RefDomain::of(ft), need);
        &upgraded
    } else {
        rule
    };
    let mut n = vec![0.0; nf];
    let mut d = vec![[0.0; 3]; nf];
    let mut out = Vec::with_capacity(rule.len());
    // The facet's own normal, pointing away from the slave sub-cell (from the − to the + side), one
    // orientation for the whole facet: the interface term then closes the divergence theorem of the
    // sub-cells exactly, also where the discrete interface is curved. ∇φ, Code_Aster's normal and the
    // same on a flat facet, may turn past the facet's tangent plane at some of its points where the
    // level set is curved (a sphere seen by a HEXA20 near a corner: 1e-3 of the cell off), which flipped
    // the normal there.
    //
    // The side is judged in the parent's reference coordinates, where the sub-cells are the simplices
    // TOPOSE made: the real normal is cof(J) times the reference one (det J > 0), so both point away
    // from the slave sub-cell together. In real coordinates a facet of a parent whose map is not affine
    // is curved, and the slave sub-cell's vertex off it (10⁻ᵏ·h away when the interface passes that
    // close to a node) can lie on its outer side: a distorted QUAD4 cut 1e-2·h from a vertex had its
    // facet turned over (0.1·U). A curved sub-cell can hide its vertex behind its face in reference
    // coordinates too, so where the facet is a face of the slave sub-cell the outward direction at each
    // point is the sub-cell map's image of the direction from its reference vertex off the face to the
    // point (a diffeomorphism maps outward vectors to outward vectors).
    let inner = facet.inner;
    let sub = facet.face_of.as_ref().map(|(xis, face)| {
        let st = subcell_type(dim, xis.len());
        let rn = crate::fem::reference::node_coords(st);
        let opp = (0..=dim).find(|l| !face[..dim].contains(l)).unwrap_or(0);
        (st, xis, face, rn, rn[opp])
    });
    let mut sn = vec![0.0; sub.as_ref().map_or(0, |s| s.1.len())];
    let mut sd = vec![[0.0; 3]; sn.len()];
    let mut side = 0.0;
    let mut sgn_of = |tang: &[[f64; 3]; 2], xi: &[f64; 3], fshape: &[f64], w: f64| {
        let n = if dim == 2 {
            Vector3::new(tang[0][1], -tang[0][0], 0.0)
        } else {
            Vector3::from(tang[0]).cross(&Vector3::from(tang[1]))
        };
        let out: [f64; 3] = match &sub {
            Some((st, xis, face, rn, opp)) => {
                // The point in the sub-cell's reference coordinates, and J_s (its point − opp).
                let mut zs = [0.0; 3];
                for (k, &l) in face.iter().enumerate() {
                    for a in 0..3 {
                        zs[a] += fshape[k] * rn[l][a];
                    }
                }
                shape_and_deriv(*st, &zs, &mut sn, &mut sd);
                let v: [f64; 3] = [0, 1, 2].map(|a| zs[a] - opp[a]);
                let mut o = [0.0; 3];
                for (k, xk) in xis.iter().enumerate() {
                    let dv: f64 = (0..dim).map(|b| sd[k][b] * v[b]).sum();
                    for a in 0..dim {
                        o[a] += xk[a] * dv;
                    }
                }
                o
            }
            None => [0, 1, 2].map(|k| xi[k] - inner[k]),
        };
        side += w * (0..dim).map(|k| n[k] * out[k]).sum::<f64>();
    };
    for (q, wq) in rule.points.iter().zip(&rule.weights) {
        shape_and_deriv(ft, q, &mut n, &mut d);
        let mut xi = [0.0; 3];
        let mut tang = [[0.0; 3]; 2]; // dξ/ds_k
        for k in 0..nf {
            for a in 0..dim {
                xi[a] += n[k] * facet.xi[k][a];
                for (s, ts) in tang.iter_mut().enumerate().take(dim - 1) {
                    ts[a] += facet.xi[k][a] * d[k][s];
                }
            }
        }
        let jp = jacobian(t, coords, &xi);
        let real = |v: &[f64; 3]| -> [f64; 3] {
            let mut r = [0.0; 3];
            for (i, ri) in r.iter_mut().enumerate().take(dim) {
                *ri = (0..dim).map(|k| jp[i][k] * v[k]).sum();
            }
            r
        };
        // Geometric normal of the facet (not yet oriented) and its measure.
        let geo = if dim == 2 {
            let t0 = real(&tang[0]);
            Vector3::new(t0[1], -t0[0], 0.0)
        } else {
            Vector3::from(real(&tang[0])).cross(&Vector3::from(real(&tang[1])))
        };
        let measure = geo.norm();
        let (_, g, _) = real_gradients(t, coords, &xi).ok_or("degenerate cell")?;
        let mut gn = Vector3::zeros();
        for (a, &nd) in nodes.iter().enumerate() {
            gn += lsn[nd] * Vector3::from(g[a]);
        }
        if gn.norm_squared() == 0.0 || measure == 0.0 {
            return Err("degenerate facet (zero measure or level-set gradient)".into());
        }
        sgn_of(&tang, &xi, &n, *wq);
        let nrm = geo / measure;
        // τ1: e_x projected on the tangent plane, (I - n nᵀ) e_x, or e_y's
        // projection when n ∥ e_x.
        let mut t1 = Vector3::new(1.0 - nrm[0] * nrm[0], -nrm[0] * nrm[1], -nrm[0] * nrm[2]);
        if t1.norm() < 1e-8 {
            t1 = Vector3::new(-nrm[1] * nrm[0], 1.0 - nrm[1] * nrm[1], -nrm[1] * nrm[2]);
        }
        let t1 = t1 / t1.norm();
        let t2 = if dim == 3 { nrm.cross(&t1) } else { Vector3::zeros() };
        out.push(FacetPoint { xi, w: wq * measure, basis: [nrm.into(), t1.into(), t2.into()] });
    }
    if side < 0.0 {
        for p in out.iter_mut() {
            let [n, t1, t2] = p.basis;
            let t2 = if dim == 3 { t2 } else { [0.0; 3] };
            // n → −n, and the tangents kept right-handed: τ1 stays the projection of e_x, τ2 = n × τ1.
            p.basis = [n.map(|c| -c), t1, t2.map(|c| -c)];
        }
    }
    Ok(out)
}

/// The facets grouped by the cell they lie in, in cell order.
fn by_cell(facets: &[Facet]) -> BTreeMap<usize, Vec<&Facet>> {
    let mut m: BTreeMap<usize, Vec<&Facet>> = BTreeMap::new();
    for f in facets {
        m.entry(f.cell).or_default().push(f);
    }
    m
}

/// The nodal forces of a pressure `p` on both lips of crack `g` (PRES_REP with FISSURE): on every facet,
/// ∫ p n·[[δu]] with n from the − to the + side, so that a positive pressure pushes the lips apart. Per
/// cell that sees the crack, the forces in [`XDofs::cell_dofs`] order; only Heaviside unknowns carry
/// them (the standard part of δu has no jump). `p` takes the real coordinates of a facet point.
pub fn lip_pressure(
    mesh: &Mesh,
    xm: &XfemModel,
    g: usize,
    facets: &[Facet],
    rule: &QuadratureRule,
    ndim: usize,
    p: &dyn Fn(&[f64; 3]) -> Result<f64, String>,
) -> Result<Vec<(usize, Vec<f64>)>, String> {
    let mut out = Vec::new();
    for (c, fs) in by_cell(facets) {
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let cols = cell_columns(nodes, xm, ndim);
        let mut fe = vec![0.0; cols.len()];
        for f in fs {
            let code = super::levelset::region_code;
            let (rm, rp) = (code(&f.slave), code(&f.master));
            for q in facet_points(t, &coords, nodes, &xm.lsn[g], f, rule)? {
                let ff = shape(t, &q.xi);
                let mut x = [0.0; 3];
                for (a, xa) in coords.iter().enumerate() {
                    for k in 0..3 {
                        x[k] += ff[a] * xa[k];
                    }
                }
                let pq = p(&x)?;
                if !pq.is_finite() {
                    return Err(format!("the pressure is not finite at ({}, {}, {})", x[0], x[1], x[2]));
                }
                for (r, &(a, set, i)) in cols.iter().enumerate() {
                    let Some(j) = set else { continue };
                    let jc = xm.psi(nodes[a], j, rp) - xm.psi(nodes[a], j, rm);
                    fe[r] += q.w * pq * ff[a] * jc * q.basis[0][i];
                }
            }
        }
        out.push((c, fe));
    }
    Ok(out)
}

/// The mortar coupling of one crack in one cell: `c` couples the cell's
/// unknowns to the packets' μ (∫ (P[[N]])ᵀ Φ_k^q), `mm` the packets' w and μ
/// (∫ Φ_k^q Φ_l^q, per component q), `m` the lumped weights (∫ Φ_k). Φ_k^q
/// is Φ_k but where some packets' component q is removed ([`dead_components`]).
#[derive(Debug, Clone)]
pub struct Coupling {
    pub cell: usize,
    pub crack: usize,
    /// Packets touched, in local order.
    pub packets: Vec<usize>,
    /// Row-major (n_cell_dofs × (npk·ndim)).
    pub c: Vec<f64>,
    /// ndim × npk × npk (component q at q·npk², row-major).
    pub mm: Vec<f64>,
    pub m: Vec<f64>,
}

/// The vertex functions of the multipliers of one crack in one cell: the
/// linear vertex shape functions of active vertices, the inactive ones'
/// shares spread equally over the active ones (`xmofhm`), summed per packet.
fn multiplier_functions(lin: &[f64], active: &[Option<usize>], packets: &[usize]) -> Vec<f64> {
    let nact = active.iter().filter(|a| a.is_some()).count() as f64;
    let spare: f64 = lin.iter().zip(active).filter(|(_, a)| a.is_none()).map(|(v, _)| v).sum();
    let mut phi = vec![0.0; packets.len()];
    for (v, a) in lin.iter().zip(active) {
        if let Some(k) = a {
            let loc = packets.iter().position(|p| p == k).expect("packet of an active vertex");
            phi[loc] += v + spare / nact;
        }
    }
    phi
}

/// The multiplier functions of component q: those of the packets whose
/// component q is removed (`dead`) spread equally over the others of the cell
/// (as `xmofhm` spreads inactive vertices), or dropped when none is left.
fn component_functions(phi: &[f64], dead: &[bool]) -> Vec<f64> {
    let nlive = dead.iter().filter(|d| !**d).count();
    let spare: f64 = phi.iter().zip(dead).filter(|(_, d)| **d).map(|(v, _)| v).sum();
    phi.iter().zip(dead).map(|(v, &d)| if d || nlive == 0 { 0.0 } else { v + spare / nlive as f64 }).collect()
}

/// The active vertices of cell `c` ([`active_vertices`]) and the packets they carry, sorted, or None when
/// no vertex of the cell is active.
#[allow(clippy::type_complexity)]
fn cell_packets(
    mesh: &Mesh,
    c: usize,
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
) -> Result<Option<(Vec<Option<usize>>, Vec<usize>)>, String> {
    let active = active_vertices(mesh, c, packet_of, active_edges)?;
    if active.iter().all(|a| a.is_none()) {
        return Ok(None);
    }
    let mut pk: Vec<usize> = active.iter().flatten().copied().collect();
    pk.sort_unstable();
    pk.dedup();
    Ok(Some((active, pk)))
}

/// The active vertices of crack `g`'s multipliers in cell `c` (`xmulhm`): ends
/// of its cut edges and vertex points, with their packets; None when a node of
/// a cut edge has no packet.
fn active_vertices(
    mesh: &Mesh,
    c: usize,
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
) -> Result<Vec<Option<usize>>, String> {
    let t = mesh.cell_types[c];
    let nodes = &mesh.cells[c];
    let nv = crate::fem::elasticity::vertex_type(t).nnodes();
    let mut active: Vec<Option<usize>> = vec![None; nv];
    for (l, &n) in nodes[..nv].iter().enumerate() {
        if active_edges.contains(&(n, n)) {
            active[l] = packet_of.get(&n).copied();
        }
    }
    for e in super::levelset::edges(t) {
        let (a, b) = (nodes[e[0]], nodes[e[1]]);
        if active_edges.contains(&(a.min(b), a.max(b))) {
            for l in [e[0], e[1]] {
                let k = packet_of.get(&nodes[l]).ok_or_else(|| {
                    format!("node {} of a cut edge belongs to no multiplier packet", mesh.node_names[nodes[l]])
                })?;
                active[l] = Some(*k);
            }
        }
    }
    Ok(active)
}

/// The multiplier components (packet, q of the local basis n, τ1, τ2) that
/// test only jumps the kinematic conditions prescribe, on linear cells.
///
/// A component q of packet k is removed when every cell where k is active is
/// linear and, at every facet point of those cells, the basis vector q has no
/// part along a direction d in which some node of the packet has a free jump
/// (`fixed(node, d)`: every Heaviside unknown of the node in direction d is
/// prescribed). On linear cells each packet brings one jump function per
/// component: where the conditions fix it, the packet's multiplier is one
/// function too many, and the P1 multipliers against the free P1 jumps leave
/// a null space (the tangent is singular: the multiplier is arbitrary there and
/// wakes the cohesive law). Quadratic cells keep free mid-side jumps and are
/// left as they are.
#[allow(clippy::too_many_arguments)]
pub fn dead_components(
    mesh: &Mesh,
    xm: &XfemModel,
    g: usize,
    facets: &[Facet],
    rule: &QuadratureRule,
    packets: &[Vec<usize>],
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
    ndim: usize,
    fixed: &dyn Fn(usize, usize) -> bool,
) -> Result<BTreeSet<(usize, usize)>, String> {
    let mut by_cell: BTreeMap<usize, Vec<&Facet>> = BTreeMap::new();
    for f in facets {
        by_cell.entry(f.cell).or_default().push(f);
    }
    // Directions in which every node of the packet has its jump prescribed.
    let fixed_dirs: Vec<Vec<bool>> =
        packets.iter().map(|p| (0..ndim).map(|d| p.iter().all(|&n| fixed(n, d))).collect()).collect();
    // Candidates: (k, q) still possible.
    let mut alive = vec![vec![true; ndim]; packets.len()];
    let mut seen = vec![false; packets.len()];
    for (c, fs) in by_cell {
        let t = mesh.cell_types[c];
        let active = active_vertices(mesh, c, packet_of, active_edges)?;
        let linear = t.nnodes() == t.nvertices();
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let mut points = Vec::new();
        for f in &fs {
            points.extend(facet_points(t, &coords, nodes, &xm.lsn[g], f, rule)?);
        }
        for &k in active.iter().flatten() {
            seen[k] = true;
            for (q, al) in alive[k].iter_mut().enumerate() {
                let ok = linear
                    && points.iter().all(|p| (0..ndim).all(|d| fixed_dirs[k][d] || p.basis[q][d].abs() <= 1e-12));
                if !ok {
                    *al = false;
                }
            }
        }
    }
    let mut out = BTreeSet::new();
    for (k, a) in alive.iter().enumerate() {
        for (q, &dead) in a.iter().enumerate() {
            if dead && seen[k] {
                out.insert((k, q));
            }
        }
    }
    Ok(out)
}

/// Build the couplings of crack `g` from its facets. `packet_of` maps a mesh
/// node to its packet; `active_edges` are the crack's cut vertex edges, and (v, v) for its vertex points (the
/// active vertices of a cell are the ends of its edges in that set).
#[allow(clippy::too_many_arguments)]
pub fn couplings(
    mesh: &Mesh,
    xm: &XfemModel,
    g: usize,
    facets: &[Facet],
    rule: &QuadratureRule,
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
    dead: &BTreeSet<(usize, usize)>,
    ndim: usize,
) -> Result<Vec<Coupling>, String> {
    let mut out = Vec::new();
    for mc in mortar_cells(mesh, facets, packet_of, active_edges)? {
        let (c, nodes, npk) = (mc.cell, &mesh.cells[mc.cell], mc.packets.len());
        // Cell unknown layout (XDofs::cell_dofs order).
        let cols = cell_columns(nodes, xm, ndim);
        let nd = cols.len();
        let mut cm = vec![0.0; nd * npk * ndim];
        let mut mm = vec![0.0; ndim * npk * npk];
        let dead_q: Vec<Vec<bool>> =
            (0..ndim).map(|q| mc.packets.iter().map(|&k| dead.contains(&(k, q))).collect()).collect();
        let mut m = vec![0.0; npk];
        mc.for_each_point(mesh, xm, g, rule, |pt| {
            let ff = shape(mesh.cell_types[c], &pt.point.xi);
            let phq: Vec<Vec<f64>> = dead_q.iter().map(|d| component_functions(&pt.phi, d)).collect();
            for k in 0..npk {
                m[k] += pt.point.w * pt.phi[k];
                for (q, ph) in phq.iter().enumerate() {
                    for l in 0..npk {
                        mm[q * npk * npk + k * npk + l] += pt.point.w * ph[k] * ph[l];
                    }
                }
            }
            // Jump of each unknown, projected on the local basis.
            for (r, &(a, set, i)) in cols.iter().enumerate() {
                let Some(j) = set else { continue };
                let n = nodes[a];
                let jc = xm.psi(n, j, pt.master) - xm.psi(n, j, pt.slave);
                if jc == 0.0 {
                    continue;
                }
                let v = ff[a] * jc;
                for k in 0..npk {
                    for q in 0..ndim {
                        cm[r * npk * ndim + k * ndim + q] += pt.point.w * v * pt.point.basis[q][i] * phq[q][k];
                    }
                }
            }
        })?;
        out.push(Coupling { cell: c, crack: g, packets: mc.packets, c: cm, mm, m });
    }
    Ok(out)
}

/// A cell holding facets of a crack whose vertices carry its multipliers (`xmulhm`): the ends of cut
/// edges of the cell and the vertices where the interface passes (vertex points, listed as degenerate
/// edges (v, v)), and the packets they carry, sorted.
struct MortarCell<'f> {
    cell: usize,
    active: Vec<Option<usize>>,
    packets: Vec<usize>,
    facets: Vec<&'f Facet>,
}

/// A facet integration point of a [`MortarCell`]: the point, the region codes of the slave and master
/// sides, the linear vertex functions and the multiplier functions of the packets there.
struct MortarPoint {
    point: FacetPoint,
    slave: i32,
    master: i32,
    lin: Vec<f64>,
    phi: Vec<f64>,
}

impl MortarCell<'_> {
    /// Call `f` at every integration point of the cell's facets.
    fn for_each_point(
        &self,
        mesh: &Mesh,
        xm: &XfemModel,
        g: usize,
        rule: &QuadratureRule,
        mut f: impl FnMut(&MortarPoint),
    ) -> Result<(), String> {
        let t = mesh.cell_types[self.cell];
        let nodes = &mesh.cells[self.cell];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let vt = crate::fem::elasticity::vertex_type(t);
        for fc in &self.facets {
            let (slave, master) = (super::levelset::region_code(&fc.slave), super::levelset::region_code(&fc.master));
            for point in facet_points(t, &coords, nodes, &xm.lsn[g], fc, rule)? {
                let lin = shape(vt, &point.xi);
                let phi = multiplier_functions(&lin, &self.active, &self.packets);
                f(&MortarPoint { point, slave, master, lin, phi });
            }
        }
        Ok(())
    }
}

/// The cells of `facets` that carry multipliers ([`MortarCell`]), in cell order; the others hold no
/// multiplier on their facets.
fn mortar_cells<'f>(
    mesh: &Mesh,
    facets: &'f [Facet],
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
) -> Result<Vec<MortarCell<'f>>, String> {
    let mut out = Vec::new();
    for (cell, fs) in by_cell(facets) {
        if let Some((active, packets)) = cell_packets(mesh, cell, packet_of, active_edges)? {
            out.push(MortarCell { cell, active, packets, facets: fs });
        }
    }
    Ok(out)
}

/// The hydraulic coupling of one crack in one cell (the 2020 interface flow, `hm-coupled-formulation.md`
/// §6.2): per pressure function of the cell (`cols`: vertex a, plain (None) or Heaviside set j) and packet
/// k, `ep` = ∫ N̂_a ψ_j⁺ Φ_k and `em` = ∫ N̂_a ψ_j⁻ Φ_k over the facets (N̂ the linear vertex functions,
/// ψ = 1 for the plain function, + the master side, where the level set is positive), and `mm` =
/// ∫ Φ_k Φ_l, with the multiplier functions Φ of the mortar couplings (no component removed).
#[derive(Debug, Clone)]
pub struct Exchange {
    pub cell: usize,
    pub packets: Vec<usize>,
    pub cols: Vec<(usize, Option<usize>)>,
    /// Row-major (cols × packets).
    pub ep: Vec<f64>,
    pub em: Vec<f64>,
    /// Row-major (packets × packets).
    pub mm: Vec<f64>,
}

/// The hydraulic couplings of crack `g` from its facets, cell by cell as [`couplings`] (same facets,
/// rule, packets and active vertices).
pub fn exchanges(
    mesh: &Mesh,
    xm: &XfemModel,
    g: usize,
    facets: &[Facet],
    rule: &QuadratureRule,
    packet_of: &BTreeMap<usize, usize>,
    active_edges: &BTreeSet<(usize, usize)>,
) -> Result<Vec<Exchange>, String> {
    let mut out = Vec::new();
    for mc in mortar_cells(mesh, facets, packet_of, active_edges)? {
        let (c, nodes, npk) = (mc.cell, &mesh.cells[mc.cell], mc.packets.len());
        let vt = crate::fem::elasticity::vertex_type(mesh.cell_types[c]);
        let mut cols = Vec::new();
        for (a, &n) in nodes[..vt.nnodes()].iter().enumerate() {
            cols.push((a, None));
            cols.extend((0..xm.node_sets[n].len()).map(|j| (a, Some(j))));
        }
        let nc = cols.len();
        let (mut ep, mut em, mut mm) = (vec![0.0; nc * npk], vec![0.0; nc * npk], vec![0.0; npk * npk]);
        mc.for_each_point(mesh, xm, g, rule, |pt| {
            let (w, lin, phi) = (pt.point.w, &pt.lin, &pt.phi);
            for k in 0..npk {
                for l in 0..npk {
                    mm[k * npk + l] += w * phi[k] * phi[l];
                }
            }
            for (r, &(a, set)) in cols.iter().enumerate() {
                let (sp, sm) = match set {
                    None => (1.0, 1.0),
                    Some(j) => (xm.psi(nodes[a], j, pt.master), xm.psi(nodes[a], j, pt.slave)),
                };
                for k in 0..npk {
                    ep[r * npk + k] += w * lin[a] * sp * phi[k];
                    em[r * npk + k] += w * lin[a] * sm * phi[k];
                }
            }
        })?;
        out.push(Exchange { cell: c, packets: mc.packets, cols, ep, em, mm });
    }
    Ok(out)
}

/// The pivot below which a multiplier direction is null ([`null_multipliers`]): σ²/k, σ the direction's
/// singular value in the scaled coupling block (columns of unit norm) and k the stiffness the bulk
/// opposes to the free jump it tests, relative to the mean diagonal stiffness of its rows — the
/// direction's pivot in the Schur complement of the bulk, relative to the others'. μ along a kept
/// direction is fixed to round-off/pivot, and can wake the cohesive law where that is not small;
/// removing it drops a force of relative size σ/k on the jump it tests. An interface 1e-7 … 1e-11 from
/// a row of nodes, or tilted by 1e-7 … 1e-5 rad from one, turns structural null directions into
/// directions with σ ∝ the distance and k ~ 1 (a TETRA4 junction 1e-7·h from a node: σ = 1.0e-8 and
/// 1.5e-8, k = 1.1 and 0.9; kept, the first Newton step woke the law and the run ended 1.3e-8·U off;
/// removed, 2e-9·U); a direction that tests the jump of a near-sliver set has k ≪ 1 (a TETRA4 plane
/// 1e-2·h from a node: σ = 8.5e-10, k = 3.9e-6, a pivot of 2e-13; μ removed alone, the nodes were
/// 1.1e-7·U off; kept, 8.6e-9·U) and goes with its jump ([`SLIVER_PIVOT`]: 2.5e-13·U). A bound on σ
/// alone (1e-8 before) cannot tell them apart.
pub const NULL_SCHUR: f64 = 1e-15;

/// A near-sliver jump ([`null_multipliers`]): a direction whose free jump the bulk opposes with less than
/// this share of the mean stiffness tests the jump of a set whose region is a sliver.
pub const SLIVER_STIFFNESS: f64 = 1e-3;

/// The pivot below which a near-sliver direction is removed with the jump it tests: μ along it is no
/// longer kept, and the free jump is held at zero. Removing μ alone drops a force of relative size σ/k,
/// which the sliver's small stiffness magnifies (σ = 1.2e-10 and k = 1.9e-8 on a PENTA6 plane: 4.7e-7·U
/// at the lips); keeping it costs 1/pivot in condition (σ = 2.0e-11 and k = 1.8e-7 on a TETRA4 plane
/// through a node: 1.5e17, 4.5e-8·U).
pub const SLIVER_PIVOT: f64 = 1e-10;

/// A multiplier direction that tests no free jump, or too small a one to be solved for
/// ([`null_multipliers`]).
#[derive(Debug, Clone)]
pub struct NullDirection {
    /// (crack, packet, component, coefficient), the largest coefficient 1: μ is kept orthogonal to it.
    pub mu: Vec<(usize, usize, usize, f64)>,
    /// For a near-sliver jump, the free jump it tests, on the reduced unknowns of `map` (largest
    /// coefficient 1): held at zero.
    pub lock: Option<Vec<(usize, f64)>>,
}

/// Singular values at or below which a direction is null whatever its stiffness (structural null
/// directions come out at 1e-16 or below).
pub const STRUCTURAL_SINGULAR_VALUE: f64 = 1e-12;

/// Singular values above which a direction is never null: σ²/k ≤ [`NULL_SCHUR`] needs σ below
/// 1e-7 for any stiffness the bulk can oppose (k is at most a few times the mean diagonal).
pub const NULL_SINGULAR_VALUE_MAX: f64 = 1e-6;

/// The multiplier directions that test no free jump: combinations v of the packets' components
/// (crack, packet, q of the local basis) with Cᵀv = 0 on every free unknown, the `dead` components left
/// out. Such a v is a null direction of the whole tangent — μ along it changes no force on a free
/// unknown, and its λ = Mμ/m is arbitrary and can wake the cohesive law. They appear
/// - on linear cells where the interface meets faces on which the jump is prescribed (`H1Y=0` …): each
///   packet there brings one jump function per direction, and when the face is at an angle to the
///   interface the prescribed directions mix n, τ1 and τ2, which [`dead_components`] (one component at a
///   time) does not catch;
/// - at a junction, across the cracks: the multipliers of both cracks test the jumps of the same
///   Heaviside unknowns in the cells both cut, and there can be more of them than independent jumps
///   (a TETRA4 junction 1e-3·h from a node: each crack's block has full rank, the union does not).
///
/// `couplings` holds every crack's couplings (`dead[crack]` its removed components). `map` eliminates
/// the kinematic conditions: an unknown is replaced by the free unknowns it is a combination of (none
/// when prescribed), so that conditions and relations both count. Only packets near prescribed jumps or
/// in cells of several cracks can carry such a direction: the search runs on the packets active in a
/// cell with a non-free jump unknown or with couplings of two cracks, and on the packets that share a
/// cell with those. The null space of that block is exact for the whole matrix, since the other
/// packets' columns are zero in it; it is taken from an SVD with the columns scaled to unit norm, a
/// direction null when its pivot is below [`NULL_SCHUR`], or below [`SLIVER_PIVOT`] for the jump of a
/// near-sliver set, which is then returned to be held at zero (`bulk`: the bulk elements' unknowns and
/// matrices, for the stiffness behind each direction; without them it is taken as the mean). The caller
/// keeps μ orthogonal to each direction (relations Σ v μ = 0), which changes no force on a free unknown.
/// Holding a near-sliver jump g at zero (Σ g u = 0) is exact on a glued interface, whose jumps vanish,
/// and elsewhere fixes the relative motion of a region of that stiffness share, as removing its set
/// would.
pub fn null_multipliers(
    couplings: &[Coupling],
    xd: &XDofs,
    mesh: &Mesh,
    ndim: usize,
    dead: &[&BTreeSet<(usize, usize)>],
    map: &DofMap,
    bulk: Option<&[(&[usize], &[f64])]>,
) -> Vec<NullDirection> {
    let rows_of = |cp: &Coupling| -> Vec<usize> { xd.cell_dofs(&mesh.cells[cp.cell]) };
    let mut cracks_of: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
    for cp in couplings {
        cracks_of.entry(cp.cell).or_default().insert(cp.crack);
    }
    // Cells where a jump unknown is not free, or that several cracks' multipliers test.
    let mut near_cells: BTreeSet<usize> = BTreeSet::new();
    for cp in couplings {
        let np = cp.packets.len() * ndim;
        let touched = cracks_of[&cp.cell].len() > 1
            || rows_of(cp)
                .iter()
                .enumerate()
                .any(|(r, &d)| !map.is_free(d) && cp.c[r * np..(r + 1) * np].iter().any(|v| *v != 0.0));
        if touched {
            near_cells.insert(cp.cell);
        }
    }
    if near_cells.is_empty() {
        return Vec::new();
    }
    let near: BTreeSet<(usize, usize)> = couplings
        .iter()
        .filter(|cp| near_cells.contains(&cp.cell))
        .flat_map(|cp| cp.packets.iter().map(|&k| (cp.crack, k)))
        .collect();
    // The cells where a near packet is active, with every packet active there.
    let cells: BTreeSet<usize> = couplings
        .iter()
        .filter(|cp| cp.packets.iter().any(|&k| near.contains(&(cp.crack, k))))
        .map(|cp| cp.cell)
        .collect();
    let group: BTreeSet<(usize, usize)> = couplings
        .iter()
        .filter(|cp| cells.contains(&cp.cell))
        .flat_map(|cp| cp.packets.iter().map(|&k| (cp.crack, k)))
        .collect();
    let cols: Vec<(usize, usize, usize)> = group
        .iter()
        .flat_map(|&(g, k)| (0..ndim).map(move |q| (g, k, q)))
        .filter(|&(g, k, q)| !dead.get(g).is_some_and(|d| d.contains(&(k, q))))
        .collect();
    let col_of: BTreeMap<(usize, usize, usize), usize> = cols.iter().enumerate().map(|(i, &c)| (c, i)).collect();
    let mut row_of: BTreeMap<usize, usize> = BTreeMap::new();
    let mut entries: Vec<(usize, usize, f64)> = Vec::new();
    for cp in couplings.iter().filter(|cp| cells.contains(&cp.cell)) {
        let np = cp.packets.len() * ndim;
        for (r, d) in rows_of(cp).into_iter().enumerate() {
            let row = &cp.c[r * np..(r + 1) * np];
            if row.iter().all(|v| *v == 0.0) {
                continue;
            }
            for &(i, c) in map.expr(d).0 {
                let nr = row_of.len();
                let ri = *row_of.entry(i).or_insert(nr);
                for (kl, &k) in cp.packets.iter().enumerate() {
                    for q in 0..ndim {
                        if let Some(&ci) = col_of.get(&(cp.crack, k, q)) {
                            let v = row[kl * ndim + q];
                            if v != 0.0 {
                                entries.push((ri, ci, c * v));
                            }
                        }
                    }
                }
            }
        }
    }
    let nc = cols.len();
    // Zero rows pad the block to square when it has fewer rows than columns.
    let nr = row_of.len().max(nc);
    let mut a = nalgebra::DMatrix::<f64>::zeros(nr, nc);
    for (r, c, v) in entries {
        a[(r, c)] += v;
    }
    let scale: Vec<f64> = (0..nc)
        .map(|c| {
            let n = a.column(c).norm();
            if n > 0.0 {
                1.0 / n
            } else {
                1.0
            }
        })
        .collect();
    for (c, s) in scale.iter().enumerate() {
        a.column_mut(c).scale_mut(*s);
    }
    let svd = a.svd(true, true);
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else { return Vec::new() };
    // The stiffness the bulk opposes to the free jump a candidate direction tests (its left singular
    // vector ĝ, on the block's rows): ĝᵀKĝ / ĝᵀĝ over the mean diagonal stiffness of the rows, summed
    // over the bulk elements (ĝ read on an element's unknowns through the elimination of the conditions).
    let local = |dofs: &[usize], col: usize| -> Vec<f64> {
        dofs.iter()
            .map(|&d| map.expr(d).0.iter().map(|&(i, c)| row_of.get(&i).map_or(0.0, |&r| c * u[(r, col)])).sum())
            .collect()
    };
    // Computed on the first candidate: the bulk elements with an unknown on the block's rows (the only
    // ones a candidate's jump reaches) and the rows' mean diagonal stiffness.
    let reach = std::cell::OnceCell::new();
    let relative_stiffness = |col: usize| -> f64 {
        let Some(bulk) = bulk else { return 1.0 };
        let (near, kref): &(Vec<usize>, f64) = reach.get_or_init(|| {
            let mut diag = vec![0.0; row_of.len()];
            let mut near = Vec::new();
            for (e, &(dofs, k)) in bulk.iter().enumerate() {
                let nd = dofs.len();
                let mut touches = false;
                for (a, &d) in dofs.iter().enumerate() {
                    for &(i, c) in map.expr(d).0 {
                        if let Some(&r) = row_of.get(&i) {
                            diag[r] += c * c * k[a * nd + a];
                            touches = true;
                        }
                    }
                }
                if touches {
                    near.push(e);
                }
            }
            let stiff: Vec<f64> = diag.into_iter().filter(|x| *x > 0.0).collect();
            (near, stiff.iter().sum::<f64>() / stiff.len().max(1) as f64)
        });
        let kref = *kref;
        let norm: f64 = row_of.values().map(|&r| u[(r, col)] * u[(r, col)]).sum();
        let mut q = 0.0;
        for &(dofs, k) in near.iter().map(|&e| &bulk[e]) {
            let g = local(dofs, col);
            let nd = dofs.len();
            for a in (0..nd).filter(|&a| g[a] != 0.0) {
                q += g[a] * (0..nd).map(|b| k[a * nd + b] * g[b]).sum::<f64>();
            }
        }
        if kref > 0.0 && norm > 0.0 {
            q / norm / kref
        } else {
            1.0
        }
    };
    let mut out = Vec::new();
    for (i, &sv) in svd.singular_values.iter().enumerate() {
        if sv > NULL_SINGULAR_VALUE_MAX {
            continue;
        }
        let (k, pivot) = if sv > STRUCTURAL_SINGULAR_VALUE {
            let k = relative_stiffness(i);
            (k, sv * sv / k)
        } else {
            (1.0, 0.0)
        };
        let lock = k < SLIVER_STIFFNESS && pivot < SLIVER_PIVOT;
        if pivot > NULL_SCHUR && !lock {
            continue;
        }
        let v: Vec<f64> = (0..nc).map(|c| vt[(i, c)] * scale[c]).collect();
        let vmax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mu: Vec<(usize, usize, usize, f64)> = cols
            .iter()
            .zip(&v)
            .filter(|(_, x)| x.abs() > 1e-12 * vmax)
            .map(|(&(g, k, q), x)| (g, k, q, x / vmax))
            .collect();
        let lock = lock.then(|| {
            let gmax = row_of.values().fold(0.0f64, |m, &r| m.max(u[(r, i)].abs()));
            row_of.iter().map(|(&d, &r)| (d, u[(r, i)] / gmax)).filter(|(_, x)| x.abs() > 1e-12).collect()
        });
        out.push(NullDirection { mu, lock });
    }
    out
}
