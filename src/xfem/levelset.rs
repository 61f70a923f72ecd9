//! Nodal level sets and the Heaviside enrichment of nodes and cells, as
//! DEFI_FISS_XFEM computes them (Code_Aster `op0041`): level sets at every
//! node (`xinils`), their adjustment near zero (`xajuls`, normal level set),
//! the cells where the normal level set changes sign (`xmafis`), the node
//! status (`xstano`, with the junction veto of `xinlsj`'s junction level
//! sets) and the enriched cells (`xstam1`).
//!
//! Everything here works on plain slices indexed by mesh node; nothing knows
//! concepts or commands.

use crate::mesh::{CellType, Mesh};

/// Edges of a cell as (vertex a, vertex b, mid-edge node) in local node
/// numbering, in Code_Aster's order (`conare`). The mid-edge node is only
/// meaningful for quadratic cells.
pub fn edges(t: CellType) -> &'static [[usize; 3]] {
    use CellType::*;
    const SEG: &[[usize; 3]] = &[[0, 1, 2]];
    const TRIA: &[[usize; 3]] = &[[0, 1, 3], [1, 2, 4], [2, 0, 5]];
    const QUAD: &[[usize; 3]] = &[[0, 1, 4], [1, 2, 5], [2, 3, 6], [3, 0, 7]];
    const TETRA: &[[usize; 3]] = &[[0, 1, 4], [1, 2, 5], [2, 0, 6], [0, 3, 7], [1, 3, 8], [2, 3, 9]];
    const PENTA: &[[usize; 3]] =
        &[[0, 1, 6], [1, 2, 7], [2, 0, 8], [0, 3, 9], [1, 4, 10], [2, 5, 11], [3, 4, 12], [4, 5, 13], [5, 3, 14]];
    const PYRAM: &[[usize; 3]] =
        &[[0, 1, 5], [1, 2, 6], [2, 3, 7], [3, 0, 8], [0, 4, 9], [1, 4, 10], [2, 4, 11], [3, 4, 12]];
    const HEXA: &[[usize; 3]] = &[
        [0, 1, 8],
        [1, 2, 9],
        [2, 3, 10],
        [3, 0, 11],
        [0, 4, 12],
        [1, 5, 13],
        [2, 6, 14],
        [3, 7, 15],
        [4, 5, 16],
        [5, 6, 17],
        [6, 7, 18],
        [7, 4, 19],
    ];
    match t {
        // A SEG4's inner nodes are not middles of its edge: X-FEM never cuts one.
        Poi1 | Seg4 => &[],
        Seg2 | Seg3 => SEG,
        Tria3 | Tria6 | Tria7 => TRIA,
        Quad4 | Quad8 | Quad9 => QUAD,
        Tetra4 | Tetra10 => TETRA,
        Penta6 | Penta15 | Penta18 => PENTA,
        Pyram5 | Pyram13 => PYRAM,
        Hexa8 | Hexa20 | Hexa27 => HEXA,
    }
}

/// Is the cell linear (Code_Aster's `ismali`)?
pub fn is_linear(t: CellType) -> bool {
    t.nnodes() == t.nvertices()
}

/// The mesh node nearest to a point (distance over the first `dim`
/// coordinates; the first node wins a tie, as `xinlsj`'s strict test).
pub fn nearest_node(mesh: &Mesh, point: &[f64]) -> Option<usize> {
    let dim = mesh.dim.min(point.len());
    let mut best: Option<(usize, f64)> = None;
    for (n, x) in mesh.coords.iter().enumerate() {
        let d: f64 = (0..dim).map(|k| (x[k] - point[k]).powi(2)).sum::<f64>().sqrt();
        if best.is_none_or(|(_, b)| d < b) {
            best = Some((n, d));
        }
    }
    best.map(|(n, _)| n)
}

/// Adjust the normal level set near zero (`xajuls`, normal part; the
/// tangential level set of an interface is the constant −1 and is never
/// adjusted). Vertex values whose relative position on an edge is within
/// 1e-6 of an end are set to 0, and so are mid-edge values small relative to
/// the edge's jump; on quadratic cells the re-entrant configurations (double
/// sign change on an edge, zero mid-node with small ends, ...) are flattened
/// when the values are below 5 % of the cell's largest vertex |φ|, repeated
/// until nothing changes. Boundary cells (lower dimension) are skipped.
/// Returns the number of adjustments.
pub fn adjust_normal(mesh: &Mesh, lsn: &mut [f64]) -> usize {
    const FIT_TO_VERTEX: f64 = 1e-6;
    const PENAL: f64 = 0.05;
    let eps = f64::EPSILON;
    let mut count = 0;
    loop {
        let mut again = false;
        for (c, nodes) in mesh.cells.iter().enumerate() {
            let t = mesh.cell_types[c];
            if t.dim() < mesh.dim {
                continue;
            }
            let linear = is_linear(t);
            let mut lsnmax: f64 = 0.0;
            for e in edges(t) {
                let (a, b) = (nodes[e[0]], nodes[e[1]]);
                let (la, lb) = (lsn[a], lsn[b]);
                lsnmax = lsnmax.max(la.abs()).max(lb.abs());
                if (la - lb).abs() > eps {
                    let d1 = la / (la - lb);
                    if d1.abs() <= FIT_TO_VERTEX {
                        lsn[a] = 0.0;
                        count += 1;
                    }
                    if (d1 - 1.0).abs() <= FIT_TO_VERTEX {
                        lsn[b] = 0.0;
                        count += 1;
                    }
                    if !linear {
                        let m = nodes[e[2]];
                        if (lsn[m] / (la - lb)).abs() <= FIT_TO_VERTEX {
                            lsn[m] = 0.0;
                            count += 1;
                        }
                    }
                }
            }
            if linear {
                continue;
            }
            for e in edges(t) {
                let (a, b, m) = (nodes[e[0]], nodes[e[1]], nodes[e[2]]);
                let (la, lb, lm) = (lsn[a], lsn[b], lsn[m]);
                if la == 0.0 && lb == 0.0 && lm != 0.0 {
                    if (lm / lsnmax).abs() <= PENAL {
                        lsn[m] = 0.0;
                        count += 1;
                        again = true;
                    }
                } else if la * lm < 0.0 && lb * lm < 0.0 {
                    let (d1, d2, d3) = (la / lsnmax, lb / lsnmax, lm / lsnmax);
                    if d1.abs() <= PENAL && d2.abs() <= PENAL && d3.abs() <= PENAL {
                        lsn[m] = 0.0;
                        if d1 > d2 {
                            lsn[b] = 0.0;
                        } else {
                            lsn[a] = 0.0;
                        }
                        count += 2;
                        again = true;
                    }
                } else if (la == 0.0 && lb * lm < 0.0) || (la * lm < 0.0 && lb == 0.0) {
                    if (lm / lsnmax).abs() <= PENAL {
                        lsn[m] = 0.0;
                        count += 1;
                        again = true;
                    }
                } else if la * lb > 0.0 && lm == 0.0 {
                    let (d1, d2) = (la / lsnmax, lb / lsnmax);
                    if d1.abs() <= PENAL && d2.abs() <= PENAL {
                        if d1 > d2 {
                            lsn[b] = 0.0;
                        } else {
                            lsn[a] = 0.0;
                        }
                        count += 1;
                        again = true;
                    }
                }
            }
        }
        if !again {
            return count;
        }
    }
}

/// Cells of `cells` where the normal level set changes sign over the
/// vertices: some vertex's value times the first vertex's is ≤ 0 (`xmafis`).
pub fn cut_cells(mesh: &Mesh, cells: &[usize], lsn: &[f64]) -> Vec<usize> {
    cells
        .iter()
        .copied()
        .filter(|&c| {
            let nodes = &mesh.cells[c];
            let nv = mesh.cell_types[c].nvertices();
            let first = lsn[nodes[0]];
            nodes[1..nv].iter().any(|&n| first * lsn[n] <= 0.0)
        })
        .collect()
}

/// The junction level sets of one master crack (`xinlsj`): `side` = c·φ_master
/// (the branch exists where it is < 0) and `lst` (−1 for a declared master,
/// the master's tangential level set for one reached through it).
#[derive(Debug, Clone)]
pub struct JunctionLevelSets {
    pub side: Vec<f64>,
    pub lst: Vec<f64>,
}

/// The enrichment of a node by one crack (`xstano`'s STNO), with
/// Code_Aster's code of each value ([`Status::code`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Status {
    /// 0: not enriched.
    #[default]
    None,
    /// 1: Heaviside enrichment (the normal level set changes sign over the
    /// node's support, which the crack crosses entirely).
    Heaviside,
    /// 2: crack-tip enrichment within the enrichment radius (`RAYON_ENRI`).
    Tip,
    /// −2: crack-tip enrichment of a node whose support the crack front
    /// crosses, without Heaviside enrichment.
    TipOnFront,
    /// 3: both Heaviside and crack-tip enrichment.
    HeavisideAndTip,
}

impl Status {
    /// Code_Aster's value in STNO.
    pub fn code(self) -> i8 {
        match self {
            Status::None => 0,
            Status::Heaviside => 1,
            Status::Tip => 2,
            Status::TipOnFront => -2,
            Status::HeavisideAndTip => 3,
        }
    }

    /// Is the node Heaviside-enriched (STNO 1 or 3)?
    pub fn heaviside(self) -> bool {
        matches!(self, Status::Heaviside | Status::HeavisideAndTip)
    }

    /// Is the node crack-tip enriched (|STNO| ≥ 2)?
    pub fn tip(self) -> bool {
        matches!(self, Status::Tip | Status::TipOnFront | Status::HeavisideAndTip)
    }
}

/// Running min/max of the level sets over the intersection points of one node's support.
struct PointRange {
    minlst: f64,
    maxlst: f64,
    /// Per junction: min of `side`, max of `side`, min of `lst`.
    junc: Vec<(f64, f64, f64)>,
}

impl PointRange {
    fn new(nj: usize) -> PointRange {
        PointRange { minlst: f64::MAX, maxlst: -f64::MAX, junc: vec![(f64::MAX, -f64::MAX, f64::MAX); nj] }
    }
    /// Take a point where the normal level set vanishes, with its lst and junction values.
    fn take(&mut self, lst: f64, junc: impl Iterator<Item = (f64, f64)>) {
        self.minlst = self.minlst.min(lst);
        self.maxlst = self.maxlst.max(lst);
        for (r, (s, l)) in self.junc.iter_mut().zip(junc) {
            r.0 = r.0.min(s);
            r.1 = r.1.max(s);
            r.2 = r.2.min(l);
        }
    }
}

/// The level-set values on an edge: at a, b and (quadratic) the mid-node m.
struct EdgeValues {
    lsn: [f64; 3],
    lst: [f64; 3],
    side: Vec<[f64; 3]>,
    jlst: Vec<[f64; 3]>,
}

/// Quadratic interpolation on an edge, x ∈ [−1, 1] (a at −1, b at +1, m at 0).
fn quad_interp(v: &[f64; 3], x: f64) -> f64 {
    let (a2, b2, c2) = (v[0] + v[1] - 2.0 * v[2], v[1] - v[0], 2.0 * v[2]);
    (a2 * x * x + b2 * x + c2) * 0.5
}

/// Collect the points of one edge where the normal level set vanishes, as `xstano` does.
fn edge_points(ev: &EdgeValues, linear: bool, coords: (&[f64; 3], &[f64; 3]), dim: usize, r: &mut PointRange) {
    let [la, lb, lm] = ev.lsn;
    let at = |k: usize| -> (f64, Vec<(f64, f64)>) {
        (ev.lst[k], ev.side.iter().zip(&ev.jlst).map(|(s, l)| (s[k], l[k])).collect())
    };
    let take = |k: usize, r: &mut PointRange| {
        let (l, j) = at(k);
        r.take(l, j.into_iter());
    };
    if !linear {
        if la == 0.0 && lb == 0.0 {
            take(1, r);
            take(0, r);
            take(2, r);
        } else if la == 0.0 {
            take(0, r);
            if lm == 0.0 {
                take(2, r);
            }
        } else if lb == 0.0 {
            take(1, r);
            if lm == 0.0 {
                take(2, r);
            }
        } else if la * lb < 0.0 {
            // The root of the edge's quadratic interpolation in [−1, 1].
            let (a1, b1, c1) = (la + lb - 2.0 * lm, lb - la, 2.0 * lm);
            let x = if a1.abs() < 1e-8 {
                2.0 * (la / (la - lb)) - 1.0
            } else {
                let sq = (b1 * b1 - 4.0 * a1 * c1).sqrt();
                let x1 = (-b1 - sq) / (2.0 * a1);
                if x1.abs() > 1.0 {
                    (-b1 + sq) / (2.0 * a1)
                } else {
                    x1
                }
            };
            let lst = quad_interp(&ev.lst, x);
            let junc: Vec<(f64, f64)> =
                ev.side.iter().zip(&ev.jlst).map(|(s, l)| (quad_interp(s, x), quad_interp(l, x))).collect();
            r.take(lst, junc.into_iter());
        }
    } else if la == 0.0 && lb == 0.0 {
        take(1, r);
        take(0, r);
    } else if la * lb <= 0.0 {
        // Linear interpolation at the point C = A − la/(lb − la)·AB, projected on AB.
        let (a, b) = coords;
        let (mut ab2, mut abac) = (0.0, 0.0);
        for k in 0..dim {
            let ab = b[k] - a[k];
            let ac = -la / (lb - la) * ab;
            ab2 += ab * ab;
            abac += ab * ac;
        }
        let s = abac / ab2;
        let lin = |v: &[f64; 3]| v[0] + (v[1] - v[0]) * s;
        let junc: Vec<(f64, f64)> = ev.side.iter().zip(&ev.jlst).map(|(sd, l)| (lin(sd), lin(l))).collect();
        r.take(lin(&ev.lst), junc.into_iter());
    }
}

/// Node status (`xstano`, radius 0 as for an interface). `nodes` are the
/// nodes considered (those of GROUP_MA_ENRI), `cut` the cut cells
/// ([`cut_cells`]). A node's support is every mesh cell holding it; only cut
/// cells count. Over them: the node is Heaviside-enriched when the vertex
/// values of φ have strictly opposite signs and the tangential level set is
/// ≤ 0 at every point where φ vanishes on an edge; crack-tip status comes
/// from the tangential level set changing sign there (never for an
/// interface, whose lst is −1). A junction vetoes both when every such
/// point lies where its branch does not exist (min of c·φ_master ≥ 0 with a
/// point inside the master, min lst < 0).
pub fn node_status(
    mesh: &Mesh,
    nodes: &[usize],
    cut: &[usize],
    lsn: &[f64],
    lst: &[f64],
    junctions: &[JunctionLevelSets],
) -> Vec<Status> {
    let eps = f64::EPSILON;
    let mut in_cut = vec![false; mesh.cells.len()];
    for &c in cut {
        in_cut[c] = true;
    }
    let mut support: Vec<Vec<usize>> = vec![Vec::new(); mesh.nnodes()];
    for (c, cn) in mesh.cells.iter().enumerate() {
        for &n in cn {
            support[n].push(c);
        }
    }
    let mut status = vec![Status::None; mesh.nnodes()];
    for &ino in nodes {
        if support[ino].is_empty() {
            continue;
        }
        let (mut minlsn, mut maxlsn) = (f64::MAX, -f64::MAX);
        let mut range = PointRange::new(junctions.len());
        let mut isup = false;
        for &c in &support[ino] {
            if !in_cut[c] {
                continue;
            }
            isup = true;
            let t = mesh.cell_types[c];
            let cn = &mesh.cells[c];
            let linear = is_linear(t);
            for e in edges(t) {
                let (a, b) = (cn[e[0]], cn[e[1]]);
                let m = if linear { a } else { cn[e[2]] };
                let v = |f: &[f64]| [f[a], f[b], f[m]];
                let ev = EdgeValues {
                    lsn: v(lsn),
                    lst: v(lst),
                    side: junctions.iter().map(|j| v(&j.side)).collect(),
                    jlst: junctions.iter().map(|j| v(&j.lst)).collect(),
                };
                edge_points(&ev, linear, (&mesh.coords[a], &mesh.coords[b]), mesh.dim, &mut range);
            }
            for &n in &cn[..t.nvertices()] {
                minlsn = minlsn.min(lsn[n]);
                maxlsn = maxlsn.max(lsn[n]);
            }
        }
        if !isup {
            continue;
        }
        // Heaviside (Code_Aster's enr1) and crack-tip (enr2) enrichment.
        let mut heaviside = minlsn * maxlsn < 0.0 && range.maxlst <= eps;
        let mut tip = minlsn * maxlsn <= eps && range.minlst * range.maxlst <= eps;
        for &(smin, smax, lmin) in &range.junc {
            // Wrong side of the junction: no point where the branch exists.
            if smin >= 0.0 && lmin < 0.0 {
                heaviside = false;
                tip = false;
            }
            // On the junction.
            if tip && smin * smax <= eps && lmin < 0.0 {
                tip = false;
                if minlsn * maxlsn < 0.0 {
                    heaviside = true;
                }
            }
        }
        status[ino] = match (heaviside, tip) {
            (false, false) => Status::None,
            (true, false) => Status::Heaviside,
            (false, true) => Status::TipOnFront,
            (true, true) => Status::HeavisideAndTip,
        };
    }
    status
}

/// Cells with at least one Heaviside-enriched node (status 1 or 3), point
/// cells excepted (`xstam1`'s MAENR1 and MAENR3).
pub fn heaviside_cells(mesh: &Mesh, status: &[Status]) -> Vec<usize> {
    (0..mesh.cells.len())
        .filter(|&c| mesh.cell_types[c] != CellType::Poi1 && mesh.cells[c].iter().any(|&n| status[n].heaviside()))
        .collect()
}

/// Sub-domain code of a sign tuple (`xcalc_code`): Σ_f (he_f + 2)·4^(m−f),
/// with he_f ∈ {−1, 0, +1} (0 where a branch does not exist).
pub fn region_code(he: &[i32]) -> i32 {
    he.iter().fold(0, |acc, &h| acc * 4 + (h + 2))
}

/// Signs of one node over a list of cracks (`xlsjon`): `lsn[f]` is crack f's
/// normal level set, `master[f]` the index in the list of the crack f
/// branches on and the coefficient c of that junction. A value 0 counts as
/// +1; the sign is 0 where some junction of the chain says the branch does
/// not exist (c > 0 and c·φ_master ≥ 0, or c < 0 and c·φ_master > 0). A
/// single crack ignores junctions, as Code_Aster does.
pub fn node_signs(lsn: &[&[f64]], master: &[Option<(usize, f64)>], node: usize) -> Vec<i32> {
    let sign = |v: f64| if v < 0.0 { -1 } else { 1 };
    if lsn.len() == 1 {
        return vec![sign(lsn[0][node])];
    }
    (0..lsn.len())
        .map(|f| {
            let mut cur = f;
            let mut seen = 0;
            while let Some((m, c)) = master[cur] {
                let l = lsn[m][node];
                if (c > 0.0 && c * l >= 0.0) || (c < 0.0 && c * l > 0.0) {
                    return 0;
                }
                cur = m;
                seen += 1;
                if seen > lsn.len() {
                    break;
                }
            }
            sign(lsn[f][node])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::box_mesh;

    fn nodal(mesh: &Mesh, f: impl Fn(&[f64; 3]) -> f64) -> Vec<f64> {
        mesh.coords.iter().map(f).collect()
    }

    #[test]
    fn codes() {
        assert_eq!(region_code(&[1, 0]), 14);
        assert_eq!(region_code(&[-1, -1]), 5);
        assert_eq!(region_code(&[-1, 1]), 7);
        assert_eq!(region_code(&[-1]), 1);
        assert_eq!(region_code(&[1]), 3);
        let l1 = [1.0, -1.0, -1.0, 0.0];
        let l2 = [-3.0, -2.0, 2.0, 0.0];
        let lsn: [&[f64]; 2] = [&l1, &l2];
        let master = [None, Some((0, 1.0))];
        assert_eq!(node_signs(&lsn, &master, 0), vec![1, 0]);
        assert_eq!(node_signs(&lsn, &master, 1), vec![-1, -1]);
        assert_eq!(node_signs(&lsn, &master, 2), vec![-1, 1]);
        // φ = 0 counts as +: on the master, the branch does not exist (c = +1).
        assert_eq!(node_signs(&lsn, &master, 3), vec![1, 0]);
        let master = [None, Some((0, -1.0))];
        assert_eq!(node_signs(&lsn, &master, 3), vec![1, 1]);
        assert_eq!(node_signs(&lsn, &master, 1), vec![-1, 0]);
    }

    #[test]
    fn straight_interface_enriches_the_crossed_row() {
        // 4×4 QUAD8 on [0,4]², φ = y − 1.4: cells of the second row are cut.
        let mesh = box_mesh(CellType::Quad8, &[4, 4], &[4.0, 4.0]).unwrap();
        let mut lsn = nodal(&mesh, |x| x[1] - 1.4);
        assert_eq!(adjust_normal(&mesh, &mut lsn), 0);
        // Through the mid-edge nodes (φ = y − 1.5) they are counted as set to 0, as xajuls
        // counts them: 8 cell edges of the cut row (3 shared twice, 2 on the boundary).
        let mut through = nodal(&mesh, |x| x[1] - 1.5);
        assert_eq!(adjust_normal(&mesh, &mut through), 8);
        let lst = vec![-1.0; mesh.nnodes()];
        let all: Vec<usize> = (0..mesh.cells.len()).collect();
        let cut = cut_cells(&mesh, &all, &lsn);
        let vol_cut = cut.iter().filter(|&&c| mesh.cell_types[c].dim() == 2).count();
        assert_eq!(vol_cut, 4);
        let nodes: Vec<usize> = (0..mesh.nnodes()).collect();
        let st = node_status(&mesh, &nodes, &cut, &lsn, &lst, &[]);
        // Every node of the cut row: y ∈ {1, 1.5, 2}.
        let expect = mesh.coords.iter().filter(|x| (1.0..=2.0).contains(&x[1])).count();
        assert_eq!(st.iter().filter(|&&s| s == Status::Heaviside).count(), expect);
        assert!(st.iter().all(|&s| s == Status::None || s == Status::Heaviside));
        let hc = heaviside_cells(&mesh, &st);
        // The cut row and the rows above and below share nodes with it.
        assert_eq!(hc.iter().filter(|&&c| mesh.cell_types[c].dim() == 2).count(), 12);
    }

    #[test]
    fn junction_veto_keeps_the_branch_on_its_side() {
        // Master φ1 = y − 2 (horizontal), branch φ2 = x − 2.5 below it (c = +1 at (2.5, 0)).
        let mesh = box_mesh(CellType::Quad8, &[4, 4], &[4.0, 4.0]).unwrap();
        let l1 = nodal(&mesh, |x| x[1] - 2.0);
        let l2 = nodal(&mesh, |x| x[0] - 2.5);
        let n = nearest_node(&mesh, &[2.4, 0.1]).unwrap();
        assert_eq!(mesh.coords[n][..2], [2.5, 0.0]);
        let c = -l1[n].signum();
        assert_eq!(c, 1.0);
        let side: Vec<f64> = l1.iter().map(|v| c * v).collect();
        let j = JunctionLevelSets { side, lst: vec![-1.0; mesh.nnodes()] };
        let all: Vec<usize> = (0..mesh.cells.len()).collect();
        let nodes: Vec<usize> = (0..mesh.nnodes()).collect();
        let lst = vec![-1.0; mesh.nnodes()];
        let cut = cut_cells(&mesh, &all, &l2);
        let st = node_status(&mesh, &nodes, &cut, &l2, &lst, &[j]);
        // Points of φ2 = 0 at y ≤ 2 exist in the cells of rows 0 and 1: nodes with y ≤ 2 of
        // the column x ∈ [2, 3]; row 2 cells (y ∈ [2,3]) have their points at y = 2 (c·φ1 = 0,
        // not < 0) and y = 3: vetoed unless the node also touches a lower cell.
        for (k, x) in mesh.coords.iter().enumerate() {
            let expect = (2.0..=3.0).contains(&x[0]) && x[1] <= 2.0;
            assert_eq!(st[k] == Status::Heaviside, expect, "node {k} at {x:?}");
        }
    }
}
