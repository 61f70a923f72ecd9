//! The data of a cutting that the quadratic (`topose`) and the linear (`topose_linear`) TOPOSE share:
//! a crack as a parent cell sees it, the points and sub-cells of a cutting and their numbering
//! ([`PointId`], the working numbers [`Wp`]), the prisms' conforming primary split, and the small
//! geometric helpers both use (`loncar`, the master chain of a branch).

use crate::mesh::CellType;
use nalgebra::Vector3;

/// One crack as a parent cell sees it.
#[derive(Debug, Clone)]
pub struct CrackInCell {
    /// Normal level set at the parent's nodes (Code_Aster local order).
    pub lsn: Vec<f64>,
    /// For a branch: (index of its master in this cell's crack list, coef);
    /// the branch exists where coef·φ_master < 0 (`FISSCO`).
    pub master: Option<(usize, f64)>,
}

/// What a point of a cutting is, numbered as Code_Aster numbers it in its
/// final connectivity (`PCNSETO`): POST_MAIL_XFEM's node names follow the
/// order of these points, and [`PointId::number`] gives Code_Aster's number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PointId {
    /// A node of the parent: its 1-based local number (1..=nno).
    Node(u8),
    /// The k-th intersection point of the parent, 1-based (1000 + k).
    Intersection(u16),
    /// The k-th mid-point of the parent, 1-based (2000 + k).
    Mid(u16),
    /// A centre node of the primary split still in use (`ndcent`), numbered
    /// after the mid-points: 3000 + k.
    Centre(u16),
}

impl PointId {
    /// Code_Aster's number of the point (1..=nno, 1000+k, 2000+k, 3000+k).
    pub fn number(self) -> u32 {
        match self {
            PointId::Node(j) => u32::from(j),
            PointId::Intersection(k) => 1000 + u32::from(k),
            PointId::Mid(k) => 2000 + u32::from(k),
            PointId::Centre(k) => 3000 + u32::from(k),
        }
    }

    /// The parent node, 0-based, if the point is one.
    pub fn node(self) -> Option<usize> {
        match self {
            PointId::Node(j) => Some(usize::from(j) - 1),
            _ => None,
        }
    }
}

impl std::fmt::Display for PointId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.number())
    }
}

/// A point while a parent is being cut, with Code_Aster's working numbers
/// (`te0514`, `xdecqu`, `xdecqv`): the parent's nodes, the centre nodes of
/// the primary split (nno+k), the intersection points and mid-points of the
/// current sub-simplex (100+k, 200+k), and those archived for the parent
/// (1000+k, 2000+k). Every index is 1-based, as in Code_Aster.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Wp {
    /// A node of the parent (1..=nno).
    Node(u8),
    /// A centre node of the primary split (`ndcent`, nno + k).
    Centre(u8),
    /// An intersection point of the current sub-simplex (100 + k).
    Inter(u8),
    /// A mid-point of the current sub-simplex (200 + k).
    LocalMid(u8),
    /// An intersection point archived for the parent (1000 + k).
    PInt(u16),
    /// A mid-point archived for the parent (2000 + k).
    PMil(u16),
}

/// A point of the cutting.
#[derive(Debug, Clone)]
pub struct CutPoint {
    /// What the point is (see the module docs).
    pub id: PointId,
    /// Reference coordinates in the parent cell.
    pub xi: [f64; 3],
    /// Real coordinates.
    pub x: [f64; 3],
    /// Normal level set of each crack of the cell at this point (nodal value
    /// at parent nodes, parent interpolation elsewhere).
    pub lsn: Vec<f64>,
}

/// A sub-cell: a quadratic simplex (TRIA6 / TETRA10, Code_Aster local order).
#[derive(Debug, Clone)]
pub struct SubCell {
    /// Indices into [`Cutting::points`].
    pub nodes: Vec<usize>,
    /// Heaviside value per crack of the cell: −1, +1, or 0 where a branch does not exist.
    pub he: Vec<i32>,
}

/// The cutting of one parent cell (`TOPOSE`): points and sub-cells in
/// Code_Aster's storage order.
#[derive(Debug, Clone, Default)]
pub struct Cutting {
    pub points: Vec<CutPoint>,
    pub subcells: Vec<SubCell>,
}

impl Cutting {
    /// The simplex type of the sub-cells of a parent of dimension `dim`
    /// (SEG3 for a boundary segment, TRIA6, TETRA10).
    pub fn subcell_type(dim: usize) -> CellType {
        match dim {
            1 => CellType::Seg3,
            2 => CellType::Tria6,
            _ => CellType::Tetra10,
        }
    }
}

/// The relabelling of a prism's vertices under which `xdivte`'s primary split is conforming across
/// cells: new local vertex (0-based) → the cell's own. `xdivte` splits each quadrangular face along the
/// diagonal through its lowest-numbered vertex (faces 1-2-5-4 and 1-3-6-4 through 1, face 2-3-6-5
/// through 2); two prisms sharing a face split it alike when "lowest" is read in an order both see,
/// here the lexicographic order of the vertices' coordinates. With the local numbers the split of a
/// shared face depends on each cell's numbering: where the level set is not linear on the face
/// (adjusted near nodes by `xajuls`), the two cells then trace the interface differently on it, the
/// Heaviside functions are not continuous across it and the scheme loses the linear fields by
/// O(adjustment) (docs/xfem-small-subcells.md). Among the 12 symmetries of the prism, vertex 1 goes
/// to the lowest vertex and the mirror of the triangle is taken when the lowest vertex of the
/// opposite face would not be at 2 or 6.
pub(super) fn prism_relabel(coords: &[[f64; 3]]) -> [usize; 6] {
    if coords.len() < 6 {
        return [0, 1, 2, 3, 4, 5]; // the caller refuses the cell
    }
    let lex = |a: usize, b: usize| {
        (0..3).map(|k| coords[a][k].total_cmp(&coords[b][k])).find(|o| o.is_ne()).unwrap_or(std::cmp::Ordering::Equal)
    };
    let lowest = |vs: &mut dyn Iterator<Item = usize>| vs.min_by(|&a, &b| lex(a, b)).unwrap_or(0);
    let m = lowest(&mut (0..6));
    let (b, flip) = (m % 3, m >= 3);
    let map = |tri: [usize; 3]| -> [usize; 6] {
        let (lo, hi) = if flip { (3, 0) } else { (0, 3) };
        [tri[0] + lo, tri[1] + lo, tri[2] + lo, tri[0] + hi, tri[1] + hi, tri[2] + hi]
    };
    let rot = map([b, (b + 1) % 3, (b + 2) % 3]);
    // Face 2-3-6-5 (new numbers) is cut along 2-6: keep the rotation when its lowest vertex is 2 or 6.
    let low = lowest(&mut [rot[1], rot[2], rot[4], rot[5]].into_iter());
    if low == rot[1] || low == rot[5] {
        rot
    } else {
        map([b, (b + 2) % 3, (b + 1) % 3])
    }
}

/// A prism's primary split written in the numbering of [`prism_relabel`], in the cell's own numbers:
/// vertices through the relabelling, mid-nodes (PENTA15 7–15) through their edges, the centres of
/// the quadrangular faces (`C`) through their faces.
pub(super) fn prism_split<const K: usize>(split: &[[Wp; K]], coords: &[[f64; 3]]) -> Vec<Vec<Wp>> {
    const EDGES: [[usize; 2]; 9] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 4], [2, 5], [3, 4], [4, 5], [5, 3]];
    const FACES: [[usize; 4]; 3] = [[0, 1, 4, 3], [1, 2, 5, 4], [0, 2, 5, 3]];
    let r = prism_relabel(coords);
    let same = |a: &[usize], b: &[usize]| a.len() == b.len() && a.iter().all(|x| b.contains(x));
    let node = |j: usize| -> usize {
        if j < 6 {
            return r[j];
        }
        let e = EDGES[j - 6];
        6 + EDGES.iter().position(|f| same(f, &[r[e[0]], r[e[1]]])).unwrap_or(j - 6)
    };
    let centre = |k: usize| -> usize {
        let f: Vec<usize> = FACES[k].iter().map(|&v| r[v]).collect();
        FACES.iter().position(|g| same(g, &f)).unwrap_or(k)
    };
    split
        .iter()
        .map(|t| {
            t.iter()
                .map(|&w| match w {
                    Wp::Node(j) => Wp::Node(node(usize::from(j) - 1) as u8 + 1),
                    Wp::Centre(k) => Wp::Centre(centre(usize::from(k) - 1) as u8 + 1),
                    other => other,
                })
                .collect()
        })
        .collect()
}

/// The vertex shared by the 1-based edges `a1` and `a2` of `ed` and their other ends: (a, b, c) with b on
/// `a1` and c on `a2` (the last match, as the Fortran loops); zeros when an edge is 0 (a vertex point).
pub(super) fn vertex_and_ends<const N: usize>(ed: &[[usize; N]], a1: usize, a2: usize) -> (usize, usize, usize) {
    let (mut a, mut b, mut c) = (0, 0, 0);
    if a1 == 0 || a2 == 0 {
        return (a, b, c);
    }
    for i in 0..2 {
        for j in 0..2 {
            if ed[a1 - 1][i] == ed[a2 - 1][j] {
                a = ed[a1 - 1][i];
                b = ed[a1 - 1][1 - i];
                c = ed[a2 - 1][1 - j];
            }
        }
    }
    (a, b, c)
}

/// A point: reference coordinates in the parent and real coordinates.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pt {
    pub(super) xi: [f64; 3],
    pub(super) x: [f64; 3],
}

/// An intersection point of the current sub-simplex (`pinter`/`ainter`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Inter {
    pub(super) p: Pt,
    /// 1-based local edge, 0 when the point is a vertex of the sub-simplex.
    pub(super) edge: usize,
    /// The vertex, when `edge == 0`.
    pub(super) node: Option<Wp>,
}

pub(super) type V3 = Vector3<f64>;

pub(super) fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (V3::from(*a) - V3::from(*b)).norm()
}

/// Characteristic length of a cell (`loncar`): the tolerances of the cutting are relative to it.
pub(super) fn loncar(t: CellType, x: &[[f64; 3]]) -> f64 {
    match t {
        CellType::Hexa8 | CellType::Hexa20 => dist(&x[0], &x[6]),
        CellType::Penta6 | CellType::Penta15 => (dist(&x[2], &x[0]) * dist(&x[2], &x[1]) * dist(&x[2], &x[5])).cbrt(),
        CellType::Seg2 | CellType::Seg3 => dist(&x[0], &x[1]),
        CellType::Tria3 | CellType::Quad4 | CellType::Tria6 | CellType::Quad8 => {
            (dist(&x[0], &x[1]) * dist(&x[0], &x[2])).sqrt()
        }
        _ => (dist(&x[0], &x[1]) * dist(&x[0], &x[2]) * dist(&x[0], &x[3])).cbrt(),
    }
}

/// The masters a crack branches on, transitively (`fisc`): (crack, coef).
pub(super) fn master_chain(cracks: &[CrackInCell], ifiss: usize) -> Result<Vec<(usize, f64)>, String> {
    let mut chain = Vec::new();
    let mut k = ifiss;
    while let Some((m, c)) = cracks[k].master {
        if m >= cracks.len() || chain.len() > cracks.len() {
            return Err(format!("TOPOSE: invalid junction table for crack {} of the cell", ifiss + 1));
        }
        chain.push((m, c));
        k = m;
    }
    Ok(chain)
}
