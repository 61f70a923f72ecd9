//! The multiplier space of the X-FEM mortar interface with
//! `ALGO_LAGR='VERSION2'`: contact cells, cut edges, "vital" edges and the
//! packets of nodes they tie together (Code_Aster `xtyele`, `xlagsp`,
//! `xrell2`, `xrelco`).
//!
//! # Contact cells (`xtyele`)
//!
//! Cracks are taken in the model's order; for each, its Heaviside cells in
//! cell order. A cell of full dimension is a contact cell of the crack when
//! the normal level set takes strictly opposite signs over its vertices (or,
//! when its maximum over the vertices is 0, when the vertices on the level
//! set whose neighbourhood reaches φ > 0 make a whole face). With several
//! cracks in the model, a cell having a cut edge (or a vertex on the level
//! set) whose end is not enriched by the crack is not a contact cell of that
//! crack. A cell in contact for one crack is also put in the contact list of
//! every other crack it is a Heaviside cell of (appended when met); so the
//! lists are not always in cell order.
//!
//! # Cut edges (`xlagsp`)
//!
//! Over the contact cells of a crack, in list order, and over each cell's
//! vertex–vertex edges in `conare` order, every edge whose end values of φ
//! have strictly opposite signs carries an intersection point (points at a
//! vertex carry no edge). A branch only exists where `c·φ_master < 0`, so an
//! intersection point beyond the junction is not one of the branch's. Each
//! edge is listed once, with the end order and the point of its first
//! occurrence.
//!
//! # An interface along a row or plane of nodes
//!
//! When φ vanishes on a whole edge (2D) or face (3D) of cells it does not cut
//! (an interface along mesh nodes, or snapped onto them by `xajuls`), the
//! cells on its − side (maximum of φ over the vertices 0) are contact cells
//! (`xtyele` above), and `xcface` takes the vertices of that edge or face as
//! their intersection points (its `arete` case, `ia = 0`; a cell on the + side
//! gets none). `xlagsp` lists no edge for them, so each such vertex is a packet
//! of its own, with no relation ([`cut_edges`]' vertex points), and the facets
//! are the cells' faces on the level set, seen from the − side
//! (`discrete::facets`). The two sides are then coupled by the same mortar
//! terms as across a cut cell.
//!
//! # Vital edges (`xrell2`, algorithm 2)
//!
//! Each listed edge gets a criterion: the distance from its point to the
//! nearest point of another listed edge through its first end node, plus the
//! same through its second end node (nearest = first strictly smaller
//! distance, with a 1e-12 absolute + relative tie tolerance). Node score =
//! number of listed edges at the node, edge score = min of its two node
//! scores. While the highest edge score exceeds 1, the edge with the highest
//! score (ties: the larger criterion, beyond the same tolerance, else the
//! first in the list) is removed and its nodes' scores decremented. What
//! remains are the vital edges. A node's score never drops to 0, so every
//! node of a cut edge stays on a vital edge.
//!
//! # Relations (`xrelco`)
//!
//! Each vital edge (a, b) gives the equalities `X(a) = X(b)` for every
//! interface unknown X of the crack's block at the two nodes; for HM-XFEM
//! these are the fluid pressure, the two fluid-flux multipliers and the
//! mechanical multipliers ([`relation_components`]). The nodes tied through
//! vital edges form a *packet*: one set of interface unknowns per packet.

use crate::mesh::Mesh;
use crate::xfem::cutting::dist;
use crate::xfem::levelset::{edges, Status};
use std::collections::BTreeMap;

/// A cut parent edge: its two end nodes (mesh indices, in the order of the
/// cell that listed it first) and its intersection point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutEdge {
    pub a: usize,
    pub b: usize,
    pub point: [f64; 3],
}

/// The vital edges of a crack and the packets of nodes they tie.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Packets {
    /// The vital edges (end nodes), in the order of the cut-edge list.
    pub vital: Vec<(usize, usize)>,
    /// Packet index of every node of a cut edge.
    pub packet_of_node: BTreeMap<usize, usize>,
    /// The nodes of each packet (sorted); packets are numbered in the order
    /// their first vital edge appears.
    pub packets: Vec<Vec<usize>>,
}

/// One crack as the contact-cell selection sees it.
#[derive(Debug, Clone, Copy)]
pub struct CrackTopo<'a> {
    /// Normal level set per mesh node.
    pub lsn: &'a [f64],
    /// Node status ([`Status::None`]: not enriched by this crack).
    pub status: &'a [Status],
    /// The crack's Heaviside cells, in cell order.
    pub heaviside_cells: &'a [usize],
}

const TOL: f64 = 1e-12;

/// Are two criterion values equal within Code_Aster's tolerance?
fn near(a: f64, reference: f64) -> bool {
    (a - reference).abs() <= TOL + reference * TOL
}

/// Does the cell make a face of vertices on the level set (the `maxlsn = 0`
/// case of `xtyele`)? `on` = number of vertices with φ = 0 whose
/// neighbourhood reaches φ > 0 (`xtyele` counts the vertices, `panbno`).
fn face_on_level_set(mesh: &Mesh, cell: usize, lsn: &[f64], support: &[Vec<usize>]) -> bool {
    use crate::mesh::CellType::*;
    let t = mesh.cell_types[cell];
    let nodes = &mesh.cells[cell];
    let nv = t.nvertices();
    let on = nodes[..nv]
        .iter()
        .filter(|&&n| lsn[n] == 0.0 && support[n].iter().flat_map(|&c| mesh.cells[c].iter()).any(|&m| lsn[m] > 0.0))
        .count();
    let linear = t.nnodes() == nv;
    if mesh.dim == 2 {
        return on == 2 || (on == 3 && !linear);
    }
    match t {
        Tetra4 | Tetra10 => on == 3,
        Pyram5 | Pyram13 => (lsn[nodes[4]] == 0.0 && on == 3) || on == 4,
        Penta6 | Penta15 => {
            let base = nodes[..3].iter().filter(|&&n| lsn[n] == 0.0).count();
            ((base == 3 || base == 0) && on == 3) || on == 4
        }
        Hexa8 | Hexa20 | Hexa27 => on == 4,
        _ => false,
    }
}

/// Is the cell a contact cell of this crack by its own level set (`xtyele`'s `lcont`)?
fn own_contact(mesh: &Mesh, cell: usize, k: &CrackTopo, multi: bool, support: &[Vec<usize>]) -> bool {
    let t = mesh.cell_types[cell];
    if t.dim() != mesh.dim {
        return false;
    }
    let nodes = &mesh.cells[cell];
    let (mut lo, mut hi) = (f64::MAX, -f64::MAX);
    for e in edges(t) {
        let (a, b) = (nodes[e[0]], nodes[e[1]]);
        let (la, lb) = (k.lsn[a], k.lsn[b]);
        lo = lo.min(la).min(lb);
        hi = hi.max(la).max(lb);
        if multi && la * lb <= 0.0 {
            let (sa, sb) = (k.status[a], k.status[b]);
            let (na, nb) = (sa == Status::None, sb == Status::None);
            if (la * lb < 0.0 && (na || nb)) || (la == 0.0 && na) || (lb == 0.0 && nb) {
                return false;
            }
        }
    }
    if lo * hi < 0.0 {
        true
    } else if hi == 0.0 {
        face_on_level_set(mesh, cell, k.lsn, support)
    } else {
        false
    }
}

/// The contact cells of every crack (`MAILFISS.CONT`), in Code_Aster's
/// order, for the cracks of a model taken in the model's order.
pub fn contact_cells(mesh: &Mesh, cracks: &[CrackTopo]) -> Vec<Vec<usize>> {
    let multi = cracks.len() > 1;
    let mut support: Vec<Vec<usize>> = vec![Vec::new(); mesh.nnodes()];
    for (c, cn) in mesh.cells.iter().enumerate() {
        for &n in cn {
            support[n].push(c);
        }
    }
    // Per cell: not seen yet, and the element code (> 0: contact for some crack).
    let mut unseen = vec![true; mesh.cells.len()];
    let mut code = vec![0i32; mesh.cells.len()];
    let mut lists: Vec<Vec<usize>> = vec![Vec::new(); cracks.len()];
    for (f, k) in cracks.iter().enumerate() {
        for &cell in k.heaviside_cells {
            let lcont = own_contact(mesh, cell, k, multi, &support);
            if lcont {
                lists[f].push(cell);
                if code[cell] <= 0 && !unseen[cell] {
                    // First time in contact, seen before without: the earlier
                    // cracks it is a Heaviside cell of get it too.
                    for (g, earlier) in cracks[..f].iter().enumerate() {
                        if earlier.heaviside_cells.contains(&cell) {
                            lists[g].push(cell);
                        }
                    }
                }
            } else if code[cell] > 0 {
                lists[f].push(cell);
            }
            if unseen[cell] {
                code[cell] = if lcont { 2 } else { -1 };
                unseen[cell] = false;
            } else {
                let any = code[cell] > 0 || lcont;
                code[cell] = if any { 6 } else { -2 };
            }
        }
    }
    lists
}

/// Position of the zero of φ along an edge, t ∈ (0, 1) from a to b, for end
/// values of strictly opposite signs; `mid` = value at the mid-edge node of a
/// quadratic cell (parabolic interpolation) or None (linear).
pub(crate) fn edge_root(fa: f64, fb: f64, mid: Option<f64>) -> f64 {
    let lin = fa / (fa - fb);
    let Some(fm) = mid else { return lin };
    // φ(t) = fa (1−t)(1−2t) + 4 fm t(1−t) + fb t(2t−1) = A t² + B t + fa.
    let a = 2.0 * fa + 2.0 * fb - 4.0 * fm;
    let b = -3.0 * fa - fb + 4.0 * fm;
    if a.abs() <= 1e-12 * (fa.abs() + fb.abs()) {
        return -fa / b;
    }
    let disc = (b * b - 4.0 * a * fa).max(0.0).sqrt();
    let roots = [(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)];
    roots.into_iter().find(|t| (0.0..=1.0).contains(t)).unwrap_or(lin)
}

/// Quadratic (or linear) interpolation along an edge at t.
fn edge_interp(va: f64, vb: f64, mid: Option<f64>, t: f64) -> f64 {
    match mid {
        None => va + t * (vb - va),
        Some(vm) => va * (1.0 - t) * (1.0 - 2.0 * t) + 4.0 * vm * t * (1.0 - t) + vb * t * (2.0 * t - 1.0),
    }
}

/// The cut edges of a crack (`xlagsp`'s list): over `cells` (its contact
/// cells, in order) and their vertex–vertex edges in `conare` order, the
/// edges where `lsn` takes strictly opposite signs, once each. For a branch,
/// `master` = (φ of the crack it branches on, c): points where c·φ_master ≥ 0
/// are beyond the junction and are dropped.
pub fn cut_edges(mesh: &Mesh, cells: &[usize], lsn: &[f64], master: Option<(&[f64], f64)>) -> Vec<CutEdge> {
    let mut out: Vec<CutEdge> = Vec::new();
    for &cell in cells {
        let t = mesh.cell_types[cell];
        let nodes = &mesh.cells[cell];
        let quadratic = t.nnodes() > t.nvertices();
        for e in edges(t) {
            let (a, b) = (nodes[e[0]], nodes[e[1]]);
            let (fa, fb) = (lsn[a], lsn[b]);
            if fa * fb >= 0.0 {
                continue;
            }
            if out.iter().any(|x| (x.a == a && x.b == b) || (x.a == b && x.b == a)) {
                continue;
            }
            let m = if quadratic { Some(nodes[e[2]]) } else { None };
            let s = edge_root(fa, fb, m.map(|m| lsn[m]));
            if let Some((phi, c)) = master {
                if c * edge_interp(phi[a], phi[b], m.map(|m| phi[m]), s) >= 0.0 {
                    continue;
                }
            }
            let mut point = [0.0; 3];
            for (k, p) in point.iter_mut().enumerate() {
                let (xa, xb) = (mesh.coords[a][k], mesh.coords[b][k]);
                *p = edge_interp(xa, xb, m.map(|m| mesh.coords[m][k]), s);
            }
            out.push(CutEdge { a, b, point });
        }
    }
    // Vertex points: a vertex of a contact cell where φ = 0 is an
    // intersection point with no edge (`ia = 0` in TOPOFAC.AI). `xlagsp`
    // lists no edge for it, but `xmulhm` activates the vertex, so it carries
    // interface unknowns of its own: it is listed as the degenerate edge
    // (v, v), after the cut edges, once. A branch's vertex point beyond the
    // junction (c·φ_master ≥ 0) is not one of the branch's.
    let mut vertex_points: Vec<CutEdge> = Vec::new();
    for &cell in cells {
        let t = mesh.cell_types[cell];
        let nodes = &mesh.cells[cell];
        let nv = t.nvertices();
        let (lo, hi) = nodes[..nv].iter().fold((f64::MAX, -f64::MAX), |(l, h), &n| (l.min(lsn[n]), h.max(lsn[n])));
        // A contact cell is cut (φ of both signs) or lies on the − side with a whole face on the level
        // set (`xtyele`'s maxlsn = 0 case): `xcface` then takes that face's vertices as its points
        // (`arete`, ia = 0); a cell with no vertex below zero carries no facet.
        if !(lo < 0.0 && hi >= 0.0) {
            continue;
        }
        for &v in &nodes[..nv] {
            if lsn[v] != 0.0 || vertex_points.iter().any(|e| e.a == v) {
                continue;
            }
            if let Some((phi, c)) = master {
                if c * phi[v] >= 0.0 {
                    continue;
                }
            }
            vertex_points.push(CutEdge { a: v, b: v, point: mesh.coords[v] });
        }
    }
    out.extend(vertex_points);
    out
}

/// The criterion of each cut edge (`xlagsp`): distance from its point to the
/// nearest point of another edge through its first node, plus the same
/// through its second node (a missing neighbour counts 0).
pub fn criteria(edges: &[CutEdge]) -> Vec<f64> {
    edges
        .iter()
        .map(|e| {
            let (mut d1, mut d2) = (f64::MAX, f64::MAX);
            let (mut n1, mut n2) = (false, false);
            for o in edges {
                let via_a = (e.a == o.a && e.b != o.b) || (e.a == o.b && e.b != o.a);
                let via_b = (e.a != o.a && e.b == o.b) || (e.a != o.b && e.b == o.a);
                if via_a {
                    let l = dist(&e.point, &o.point);
                    if l < d1 && !near(l, d1) {
                        d1 = l;
                        n1 = true;
                    }
                }
                if via_b {
                    let l = dist(&e.point, &o.point);
                    if l < d2 && !near(l, d2) {
                        d2 = l;
                        n2 = true;
                    }
                }
            }
            (if n1 { d1 } else { 0.0 }) + (if n2 { d2 } else { 0.0 })
        })
        .collect()
}

/// The islands of a level set: the vertices of a group of at most `dim − 1` vertices of one strict sign
/// (connected by the edges of the mesh's cells) whose every other neighbour has the opposite strict
/// sign — a closed interface around one node (2D) or one or two (3D). Algorithm 2 ties the cut edges
/// around such a group into one packet per vertex of it ([`vital_edges`]), a multiplier too poor to
/// hold the group's side of the interface, which moves rigidly with the group's unknowns and its
/// neighbours' Heaviside ones: 2 to 6 rigid motions that no multiplier tests (a singular tangent).
pub fn islands(mesh: &Mesh, lsn: &[f64]) -> std::collections::BTreeSet<usize> {
    let mut next: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (c, nodes) in mesh.cells.iter().enumerate() {
        if mesh.cell_types[c].dim() != mesh.dim {
            continue;
        }
        for e in edges(mesh.cell_types[c]) {
            let (a, b) = (nodes[e[0]], nodes[e[1]]);
            next.entry(a).or_default().push(b);
            next.entry(b).or_default().push(a);
        }
    }
    let limit = mesh.dim.saturating_sub(1).max(1);
    let mut out = std::collections::BTreeSet::new();
    for (&v, _) in next.iter() {
        if lsn[v] == 0.0 || out.contains(&v) {
            continue;
        }
        // The component of v's strict sign, given up past the limit.
        let mut group = vec![v];
        let mut k = 0;
        let mut closed = true;
        while k < group.len() && closed {
            for &w in &next[&group[k]] {
                if group.contains(&w) {
                    continue;
                }
                if lsn[w] * lsn[v] > 0.0 {
                    group.push(w);
                    if group.len() > limit {
                        closed = false;
                        break;
                    }
                } else if lsn[w] == 0.0 {
                    closed = false;
                    break;
                }
            }
            k += 1;
        }
        if closed {
            out.extend(group);
        }
    }
    out
}

/// Select the vital edges among the cut edges (`xrell2`, algorithm 2) and
/// group the nodes into packets. The edges of an island's vertices
/// ([`islands`]) are not candidates: each of their nodes is a packet of its
/// own (the multipliers are then the vertex functions there, and the
/// directions among them that test no free jump are removed with the others,
/// `discrete::null_multipliers`). Not Code_Aster's, whose algorithm leaves
/// such an island free to move.
pub fn vital_edges(all: &[CutEdge], islands: &std::collections::BTreeSet<usize>) -> Packets {
    // Degenerate edges (vertex points, see [`cut_edges`]) carry no relation:
    // each makes a packet of its own, numbered after the edge packets.
    let edges: Vec<CutEdge> =
        all.iter().filter(|e| e.a != e.b && !islands.contains(&e.a) && !islands.contains(&e.b)).copied().collect();
    let edges = edges.as_slice();
    let crit = criteria(edges);
    let mut score: BTreeMap<usize, usize> = BTreeMap::new();
    for e in edges {
        *score.entry(e.a).or_default() += 1;
        *score.entry(e.b).or_default() += 1;
    }
    // Remaining edges: indices into `edges`, in list order.
    let mut left: Vec<usize> = (0..edges.len()).collect();
    loop {
        let mut best: Option<(usize, usize)> = None; // (position in `left`, score)
        for (pos, &i) in left.iter().enumerate() {
            let s = score[&edges[i].a].min(score[&edges[i].b]);
            match best {
                None => best = Some((pos, s)),
                Some((bp, bs)) => {
                    if s > bs {
                        best = Some((pos, s));
                    } else if s == bs {
                        let (c, cb) = (crit[i], crit[left[bp]]);
                        if c > cb && !near(c, cb) {
                            best = Some((pos, s));
                        }
                    }
                }
            }
        }
        match best {
            Some((pos, s)) if s > 1 => {
                let i = left.remove(pos);
                *score.get_mut(&edges[i].a).unwrap() -= 1;
                *score.get_mut(&edges[i].b).unwrap() -= 1;
            }
            _ => break,
        }
    }
    let vital: Vec<(usize, usize)> = left.iter().map(|&i| (edges[i].a, edges[i].b)).collect();
    // Packets: connected components through the vital edges, numbered by first appearance.
    let mut packet_of_node: BTreeMap<usize, usize> = BTreeMap::new();
    let mut next = 0usize;
    for &(a, b) in &vital {
        match (packet_of_node.get(&a).copied(), packet_of_node.get(&b).copied()) {
            (None, None) => {
                packet_of_node.insert(a, next);
                packet_of_node.insert(b, next);
                next += 1;
            }
            (None, Some(p)) => {
                packet_of_node.insert(a, p);
            }
            (Some(p), None) => {
                packet_of_node.insert(b, p);
            }
            (Some(p), Some(q)) if p != q => {
                let (lo, hi) = (p.min(q), p.max(q));
                for v in packet_of_node.values_mut() {
                    if *v == hi {
                        *v = lo;
                    }
                }
            }
            _ => {}
        }
    }
    // Renumber densely in order of first appearance.
    let mut order: Vec<usize> = Vec::new();
    for &(a, _) in &vital {
        let p = packet_of_node[&a];
        if !order.contains(&p) {
            order.push(p);
        }
    }
    let mut packets: Vec<Vec<usize>> = vec![Vec::new(); order.len()];
    for (n, p) in packet_of_node.iter_mut() {
        *p = order.iter().position(|q| q == p).unwrap();
        packets[*p].push(*n);
    }
    for e in all.iter().filter(|e| e.a == e.b || islands.contains(&e.a) || islands.contains(&e.b)) {
        for n in [e.a, e.b] {
            if let std::collections::btree_map::Entry::Vacant(v) = packet_of_node.entry(n) {
                v.insert(packets.len());
                packets.push(vec![n]);
            }
        }
    }
    Packets { vital, packet_of_node, packets }
}

/// The interface components `xrelco` ties along a vital edge for HM-XFEM,
/// for the crack's Heaviside block `block` (1-based) at the node: fluid
/// pressure, the two flux multipliers, then the mechanical multipliers (the
/// second and third blocks reuse the names D1X…, V11… of the catalogue).
pub fn relation_components(ndim: usize, block: usize) -> &'static [&'static str] {
    const D2: [&str; 27] = [
        "PRE_FLU", "LAG_FLI", "LAG_FLS", "LAGS_C", "LAGS_F1", "LAG2_C", "LAG2_F1", "LAG3_C", "LAG3_F1", "PR2_FLU",
        "LA2_FLI", "LA2_FLS", "D1X", "D1Y", "D2X", "D2Y", "D3X", "D3Y", "PR3_FLU", "LA3_FLI", "LA3_FLS", "V11", "V12",
        "V21", "V22", "V31", "V32",
    ];
    const D3: [&str; 36] = [
        "PRE_FLU", "LAG_FLI", "LAG_FLS", "LAGS_C", "LAGS_F1", "LAGS_F2", "LAG2_C", "LAG2_F1", "LAG2_F2", "LAG3_C",
        "LAG3_F1", "LAG3_F2", "PR2_FLU", "LA2_FLI", "LA2_FLS", "D1X", "D1Y", "D1Z", "D2X", "D2Y", "D2Z", "D3X", "D3Y",
        "D3Z", "PR3_FLU", "LA3_FLI", "LA3_FLS", "V11", "V12", "V13", "V21", "V22", "V23", "V31", "V32", "V33",
    ];
    assert!((1..=3).contains(&block), "block must be 1, 2 or 3");
    if ndim == 2 {
        &D2[9 * (block - 1)..9 * block]
    } else {
        &D3[12 * (block - 1)..12 * block]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn e(a: usize, b: usize, x: f64, y: f64) -> CutEdge {
        CutEdge { a, b, point: [x, y, 0.0] }
    }

    #[test]
    fn a_chain_of_vertical_edges_keeps_one_edge_per_node_pair() {
        // A straight crack crossing a strip of quads: vertical edges 0-1, 2-3, 4-5 are
        // cut and share no node: all vital, three packets.
        let edges = [e(0, 1, 0.0, 0.5), e(2, 3, 1.0, 0.5), e(4, 5, 2.0, 0.5)];
        let p = vital_edges(&edges, &Default::default());
        assert_eq!(p.vital, vec![(0, 1), (2, 3), (4, 5)]);
        assert_eq!(p.packets, vec![vec![0, 1], vec![2, 3], vec![4, 5]]);
    }

    #[test]
    fn fans_stay_whole_and_zigzags_lose_their_middle_edge() {
        // Node 0 on one side, 1, 2, 3 on the other: three edges at node 0 (score 3),
        // the end nodes score 1 each, so every edge scores 1: all vital, one packet.
        let edges = [e(0, 1, 0.0, 1.0), e(0, 2, 1.0, 1.0), e(0, 3, 2.0, 1.0)];
        let p = vital_edges(&edges, &Default::default());
        assert_eq!(p.vital.len(), 3);
        assert_eq!(p.packets, vec![vec![0, 1, 2, 3]]);
        // A zig-zag 0-1, 1-2, 2-3: scores 1, 2, 1 → the middle edge goes.
        let edges = [e(0, 1, 0.0, 0.0), e(1, 2, 1.0, 0.0), e(2, 3, 2.0, 0.0)];
        let p = vital_edges(&edges, &Default::default());
        assert_eq!(p.vital, vec![(0, 1), (2, 3)]);
        assert_eq!(p.packets, vec![vec![0, 1], vec![2, 3]]);
        assert_eq!(p.packet_of_node[&3], 1);
    }

    #[test]
    fn ties_go_to_the_larger_criterion_then_the_first() {
        // Square 0-1-2-3 all edges cut (scores 2): criteria equal → the first is removed,
        // then 2-3 / 3-0 … until every edge scores 1.
        let edges = [e(0, 1, 0.5, 0.0), e(1, 2, 1.0, 0.5), e(2, 3, 0.5, 1.0), e(3, 0, 0.0, 0.5)];
        let c = criteria(&edges);
        assert!(c.iter().all(|v| (v - c[0]).abs() < 1e-15));
        let p = vital_edges(&edges, &Default::default());
        assert_eq!(p.vital, vec![(1, 2), (3, 0)]);
        // A larger criterion wins the tie: with the points of 0-1 and 2-3 near nodes 1 and
        // 2, edge 3-0 has the largest criterion and goes first, then 1-2.
        let edges = [e(0, 1, 0.9, 0.0), e(1, 2, 1.0, 0.5), e(2, 3, 0.9, 1.0), e(3, 0, 0.0, 0.5)];
        let c = criteria(&edges);
        assert!(c[3] > c[0] && c[3] > c[1] && c[3] > c[2], "{c:?}");
        let p = vital_edges(&edges, &Default::default());
        assert_eq!(p.vital, vec![(0, 1), (2, 3)]);
        assert_eq!(p.packets, vec![vec![0, 1], vec![2, 3]]);
    }

    #[test]
    fn an_edge_on_the_level_set_gives_vertex_points_on_its_minus_side_only() {
        // 2×2 QUAD4 box, φ = X − 1: the middle column of nodes is on the level set, no edge is cut.
        let mesh = crate::mesh::generate::box_mesh(crate::mesh::CellType::Quad4, &[2, 2], &[2.0, 2.0]).unwrap();
        let lsn: Vec<f64> = mesh.coords.iter().map(|x| x[0] - 1.0).collect();
        let quads: Vec<usize> =
            (0..mesh.cells.len()).filter(|&c| mesh.cell_types[c] == crate::mesh::CellType::Quad4).collect();
        let (minus, plus): (Vec<usize>, Vec<usize>) =
            quads.iter().partition(|&&c| mesh.cells[c].iter().all(|&n| lsn[n] <= 0.0));
        assert_eq!((minus.len(), plus.len()), (2, 2));
        let on_row = |e: &CutEdge| e.a == e.b && lsn[e.a] == 0.0;
        let edges = cut_edges(&mesh, &minus, &lsn, None);
        assert_eq!(edges.len(), 3, "{edges:?}");
        assert!(edges.iter().all(on_row));
        // Each vertex of the row is a packet of its own, with no vital edge.
        let p = vital_edges(&edges, &Default::default());
        assert!(p.vital.is_empty());
        assert_eq!(p.packets.len(), 3);
        // The + side carries no facet, hence no point.
        assert!(cut_edges(&mesh, &plus, &lsn, None).is_empty());
    }

    #[test]
    fn quadratic_edge_root() {
        assert!((edge_root(-1.0, 3.0, None) - 0.25).abs() < 1e-15);
        // A linear field seen through the mid node gives the same root.
        assert!((edge_root(-1.0, 3.0, Some(1.0)) - 0.25).abs() < 1e-15);
        // φ(t) = t² − 0.25 has its root at t = 0.5.
        assert!((edge_root(-0.25, 0.75, Some(0.0)) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn relation_component_blocks() {
        assert_eq!(
            relation_components(2, 1),
            &["PRE_FLU", "LAG_FLI", "LAG_FLS", "LAGS_C", "LAGS_F1", "LAG2_C", "LAG2_F1", "LAG3_C", "LAG3_F1"]
        );
        assert_eq!(relation_components(2, 2)[..3], ["PR2_FLU", "LA2_FLI", "LA2_FLS"]);
        assert_eq!(relation_components(3, 2).len(), 12);
        assert_eq!(relation_components(3, 3)[0], "PR3_FLU");
    }
}
