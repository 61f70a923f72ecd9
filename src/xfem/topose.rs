//! Sub-element cutting of an X-FEM parent cell by its interfaces, as
//! Code_Aster's TOPOSE option (`te0514`) does it: primary split into
//! quadratic simplices (`xdivte`, centre nodes `ndcent`; a TRIA6 or TETRA10
//! parent is its own single simplex), then, crack after
//! crack, each current simplex is cut (`xdecqu`, mid-points `xalgo2` /
//! `xalg30` / `xalg40`, children `xdecqv`), with the junction skip and the
//! Heaviside sign of every child. The split, the order and the numbering are
//! Code_Aster's, because POST_MAIL_XFEM's node names depend on them.
//!
//! Points are [`PointId`]s, Code_Aster's final connectivity (`PCNSETO`):
//! the parent's nodes (1..=nno, Code_Aster local order), intersection points
//! (1000+k), mid-points (2000+k) and centre nodes still in use (3000+k; as in
//! `te0514`, k continues the mid-point count: the first centre node in use
//! of a parent with 13 mid-points is 3014). While a parent is cut, the
//! points of the current sub-simplex and the centre nodes have working
//! numbers of their own ([`Wp`]).
//!
//! Interfaces through vertices of the sub-simplices are cut as Code_Aster
//! cuts them, in 2D and in 3D (`xdblsn` brings the grazing 3D cuttings of the
//! first crack back to the usual ones, then `xalg31` / `xalg41` / `xalg42`
//! and `xdecqv`'s children for 3 or 4 points of which 1 or 2 are vertices).
//! The Newton solves (xinter, xmifis, xcenfi) are Code_Aster's; a strongly
//! curved interface in a sub-tetrahedron (xcenfi's criterion) and a failed
//! primary split (the 107 rotated HEXA20 patterns) are reported as errors.

use super::cutting::{dist, loncar, master_chain, prism_split, vertex_and_ends, Inter, Pt, Wp, V3};
pub use super::cutting::{CrackInCell, CutPoint, Cutting, PointId, SubCell};
use crate::mesh::CellType;

use Wp::{Centre as C, Inter as I, LocalMid as M, Node as N};

use crate::fem::reference::{map_to_real, node_coords, shape};

/// Coincidence tolerance of Code_Aster's point lists (`cridist`), relative
/// to a length.
const CRIDIST: f64 = 1e-9;

/// Edges of the sub-simplices (`conare`): end A, end B, mid-node (1-based
/// local numbers).
const SEG3_EDGES: [[usize; 3]; 1] = [[1, 2, 3]];
const TRIA6_EDGES: [[usize; 3]; 3] = [[1, 2, 4], [2, 3, 5], [3, 1, 6]];
const TETRA10_EDGES: [[usize; 3]; 6] = [[1, 2, 5], [1, 3, 7], [1, 4, 8], [2, 3, 6], [2, 4, 9], [3, 4, 10]];

/// Primary split of a QUAD8 (`xdivte`, first configuration): node 9 is the
/// centre.
const QUAD8_SPLIT: [[Wp; 6]; 2] = [[N(1), N(2), N(4), N(5), C(1), N(8)], [N(2), N(3), N(4), N(6), N(7), C(1)]];

/// The QUAD8 split along the other diagonal (1–3), tried when the first one's sub-cells fold (an
/// interface nearly along the diagonal 2–4 and bent onto it by `xajuls`). The diagonal is inside the
/// cell, so its neighbours' cuttings are not concerned. Not Code_Aster's (it has one QUAD8 split).
const QUAD8_SPLIT_13: [[Wp; 6]; 2] = [[N(1), N(2), N(3), N(5), N(6), C(1)], [N(1), N(3), N(4), C(1), N(7), N(8)]];

/// Primary split of a HEXA20 into six TETRA10 (`xdivte`, first
/// configuration); 21..26 are the face centres (z−, y−, x+, y+, x−, z+) and
/// 27 the body centre.
const HEXA20_SPLIT: [[Wp; 10]; 6] = [
    [N(6), N(3), N(2), N(4), C(3), N(10), N(14), C(7), N(11), C(1)],
    [N(4), N(5), N(1), N(2), C(5), N(13), N(12), C(1), C(2), N(9)],
    [N(2), N(5), N(6), N(4), C(2), N(17), N(14), C(1), C(5), C(7)],
    [N(5), N(4), N(8), N(6), C(5), N(16), N(20), N(17), C(7), C(6)],
    [N(3), N(6), N(7), N(8), C(3), N(18), N(15), C(4), C(6), N(19)],
    [N(3), N(8), N(4), N(6), C(4), N(16), N(11), C(3), C(6), C(7)],
];

/// Primary split of a PENTA15 into three TETRA10 (`xdivte`, first configuration: no rotation); C(1..3)
/// are the centres of the quadrangular faces (PENTA18 nodes 16–18, `ndcent`).
const PENTA15_SPLIT: [[Wp; 10]; 3] = [
    [N(5), N(4), N(6), N(1), N(13), N(15), N(14), C(1), N(10), C(3)],
    [N(1), N(2), N(3), N(6), N(7), N(8), N(9), C(3), C(2), N(12)],
    [N(6), N(2), N(5), N(1), C(2), N(11), N(14), C(3), N(7), C(1)],
];

/// The reference coordinates of PENTA15's face centres, in PENTA18's order (`ndcent`).
const PENTA15_CENTRES: [[f64; 3]; 3] = [[0.0, 0.5, 0.5], [0.0, 0.0, 0.5], [0.0, 0.5, 0.0]];

fn mid(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, (a[2] + b[2]) / 2.0]
}

/// Normalised copy (`xnormv`: a zero vector stays zero).
fn xnormv(a: V3) -> V3 {
    a.try_normalize(0.0).unwrap_or(a)
}

/// The parent cell and the state of its cutting.
struct Ctx<'a> {
    t: CellType,
    /// Dimension of the parent cell (`ndime`: 1, 2 or 3).
    dim: usize,
    /// Dimension of the mesh (`ndim`): larger than `dim` for a boundary cell.
    ndim: usize,
    nno: usize,
    coords: &'a [[f64; 3]],
    /// lsn[crack][node].
    lsn: Vec<&'a [f64]>,
    /// Centre nodes (`ndcent`): ids nno+1..nno+nnc.
    centre: Vec<Pt>,
    /// centre_lsn[centre][crack], parent interpolation.
    centre_lsn: Vec<Vec<f64>>,
    /// Intersection points of the parent (`PINTTO`), ids 1001...
    pint: Vec<Pt>,
    /// Mid-points of the parent (`PMILTO`), ids 2001...
    pmil: Vec<Pt>,
    /// Characteristic length of the parent (`loncar`).
    lonref: f64,
    /// Mid-points placed flat (the middles of their chords) rather than on a
    /// curved interface: in 2D the type-2 and type-3 points, in 3D the
    /// centre of an interface quadrangle (the points inside a sub-simplex);
    /// set while a sub-simplex whose curved cutting folds is cut again.
    flat: std::cell::Cell<bool>,
}

impl Ctx<'_> {
    /// Edges of the sub-simplices (`conare` of `elrese(ndime)`).
    fn edges(&self) -> &'static [[usize; 3]] {
        match self.dim {
            1 => &SEG3_EDGES,
            2 => &TRIA6_EDGES,
            _ => &TETRA10_EDGES,
        }
    }

    fn interp(&self, xi: &[f64; 3], crack: usize) -> f64 {
        shape(self.t, xi).iter().zip(self.lsn[crack]).map(|(n, v)| n * v).sum()
    }

    fn to_real(&self, xi: [f64; 3]) -> Pt {
        Pt { xi, x: map_to_real(self.t, self.coords, &xi) }
    }

    /// A point known to the parent (node, centre node, archived intersection
    /// or mid-point) or to the current sub-simplex.
    fn pt(&self, id: Wp, inter: &[Inter], mil: &[Pt]) -> Result<Pt, String> {
        let at = |k: usize| k.checked_sub(1);
        let p = match id {
            Wp::Node(j) => {
                at(j.into()).filter(|&k| k < self.nno).map(|k| Pt { xi: node_coords(self.t)[k], x: self.coords[k] })
            }
            Wp::Centre(j) => at(j.into()).and_then(|k| self.centre.get(k).copied()),
            Wp::Inter(j) => at(j.into()).and_then(|k| inter.get(k).map(|p| p.p)),
            Wp::LocalMid(j) => at(j.into()).and_then(|k| mil.get(k).copied()),
            Wp::PInt(j) => at(j.into()).and_then(|k| self.pint.get(k).copied()),
            Wp::PMil(j) => at(j.into()).and_then(|k| self.pmil.get(k).copied()),
        };
        p.ok_or_else(|| format!("TOPOSE: internal error, point {id:?} is unknown"))
    }

    /// Level set of a node of a sub-simplex as `xdecqu` reads it: nodal value
    /// at parent nodes, the centre value at centre nodes, the parent
    /// interpolation at generated points.
    fn node_lsn(&self, id: Wp, crack: usize, inter: &[Inter], mil: &[Pt]) -> Result<f64, String> {
        Ok(match id {
            Wp::Node(j) if usize::from(j) <= self.nno && j > 0 => self.lsn[crack][usize::from(j) - 1],
            Wp::Centre(j) if j > 0 => self.centre_lsn[usize::from(j) - 1][crack],
            _ => self.interp(&self.pt(id, inter, mil)?.xi, crack),
        })
    }
}

/// What `xdecqu` finds on one sub-simplex.
struct Decoupe {
    cut: bool,
    inter: Vec<Inter>,
    npts: usize,
    mil: Vec<Pt>,
}

/// Add an intersection point unless one is closer than `longar`·cridist
/// (`xajpin`); true when added.
fn add_inter(list: &mut Vec<Inter>, p: Inter, longar: f64) -> bool {
    if list.iter().any(|q| dist(&q.p.x, &p.p.x) < longar * CRIDIST) {
        return false;
    }
    list.push(p);
    true
}

/// Add a mid-point unless one is closer than `lonref`·cridist (`xajpmi`).
fn add_mid(list: &mut Vec<Pt>, p: Pt, lonref: f64) {
    if !list.iter().any(|q| dist(&q.x, &p.x) < lonref * CRIDIST) {
        list.push(p);
    }
}

impl Ctx<'_> {
    /// Intersection points and mid-points of sub-simplex `sub` with crack
    /// `ifiss` (`xdecqu`, then `xalgo2` / `xalg30` / `xalg40`).
    fn decqu(&self, sub: &[Wp], ifiss: usize, fisc: &[(usize, f64)]) -> Result<Decoupe, String> {
        let nnose = sub.len();
        let edges = self.edges();
        let none = Decoupe { cut: false, inter: Vec::new(), npts: 0, mil: Vec::new() };
        let mut tabls = vec![0.0; nnose];
        let mut som = vec![0.0; fisc.len()];
        for (j, &id) in sub.iter().enumerate() {
            let v = self.node_lsn(id, ifiss, &[], &[])?;
            for (s, &(m, _)) in som.iter_mut().zip(fisc) {
                *s += self.node_lsn(id, m, &[], &[])?;
            }
            tabls[j] = if v.abs() <= 1e-8 { 0.0 } else { v };
        }
        // Junction: the branch does not exist on this side of its master.
        if fisc.iter().zip(&som).any(|(&(_, c), s)| c * s > 0.0) {
            return Ok(none);
        }
        // A crack entering along an edge puts the mid-node on it.
        for e in edges {
            let (la, lb, lm) = (tabls[e[0] - 1], tabls[e[1] - 1], tabls[e[2] - 1]);
            let entering_a = la == 0.0 && (lb == 0.0 || lb * lm < 0.0);
            if entering_a || (lb == 0.0 && la * lm < 0.0) {
                tabls[e[2] - 1] = 0.0;
            }
        }
        let cut = edges.iter().any(|e| tabls[e[0] - 1] * tabls[e[1] - 1] < 0.0);
        if !cut && self.dim + 1 == self.ndim && tabls[..=self.dim].iter().filter(|&&v| v == 0.0).count() == self.ndim {
            // A boundary cell lying in the interface: Code_Aster gives it
            // the Heaviside value 99, which `xoripe` replaces by the side of
            // its support cell.
            return Err(format!(
                "TOPOSE: the boundary cell lies in the interface of crack {} (its side would be taken from its \
                 support cell by xoripe), which is not supported",
                ifiss + 1
            ));
        }
        if !cut {
            // Only vertex-type points can be found: nothing is archived.
            return Ok(none);
        }
        let mut inter: Vec<Inter> = Vec::new();
        let (mut npts, mut nptm) = (0, 0);
        for (ie, e) in edges.iter().enumerate() {
            let (na, nb, nm) = (sub[e[0] - 1], sub[e[1] - 1], sub[e[2] - 1]);
            let (la, lb, lm) = (tabls[e[0] - 1], tabls[e[1] - 1], tabls[e[2] - 1]);
            if la * lb > 0.0 {
                continue;
            }
            let a = self.pt(na, &[], &[])?;
            let b = self.pt(nb, &[], &[])?;
            let longar = dist(&a.x, &b.x);
            if la == 0.0 && add_inter(&mut inter, Inter { p: a, edge: 0, node: Some(na) }, longar) {
                npts += 1;
            }
            if lb == 0.0 && add_inter(&mut inter, Inter { p: b, edge: 0, node: Some(nb) }, longar) {
                npts += 1;
            }
            if lm == 0.0 {
                let m = self.pt(nm, &[], &[])?;
                if add_inter(&mut inter, Inter { p: m, edge: ie + 1, node: None }, longar) {
                    nptm += 1;
                }
            }
            if la != 0.0 && lb != 0.0 && lm != 0.0 {
                let c = self.xinter(na, nb, nm, la, lb, lm, ifiss)?;
                add_inter(&mut inter, Inter { p: c, edge: ie + 1, node: None }, longar);
            }
        }
        // Selection sort by edge number.
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
        // Degenerate (grazing) 3D cuttings of the first crack brought back to
        // the usual ones (`xdblsn`).
        if self.dim == 3 && ifiss == 0 {
            xdblsn(sub, &mut inter, &mut npts)?;
        }
        let n = inter.len();
        if n == 4 && npts == 0 {
            // Point 4 must be the one whose edge shares no vertex with point 1's.
            let a1 = inter[0].edge;
            for ia in 1..3 {
                let a2 = inter[ia].edge;
                let shared = (0..2).any(|i| (0..2).any(|j| edges[a1 - 1][i] == edges[a2 - 1][j]));
                if !shared {
                    inter.swap(ia, 3);
                }
            }
        }
        if self.dim == 3 && n == 4 && npts == 2 {
            // The point on the edge joining the two vertex points goes last.
            let (na, nb) = (inter[0].node, inter[1].node);
            let im = edges
                .iter()
                .position(|e| (0..2).any(|j| Some(sub[e[j] - 1]) == na && Some(sub[e[1 - j] - 1]) == nb))
                .map(|k| k + 1)
                .ok_or("TOPOSE: xdecqu: the two vertex points are not joined by an edge")?;
            for ipt in 0..n - 1 {
                if inter[ipt].edge == im {
                    inter.swap(ipt, n - 1);
                }
            }
        }
        if self.dim == 3 && n == 4 && npts == 1 {
            // Second: the point on an edge from the vertex point (at its
            // mid-node); third: the point whose edge shares that edge's
            // other end (noeua).
            let (mut noeua, mut noeub) = (0, 0);
            for (i, p) in inter.iter().enumerate().skip(1) {
                let e = edges[p.edge - 1];
                if tabls[e[0] - 1] == 0.0 {
                    (noeub, noeua) = (i, e[1]);
                } else if tabls[e[1] - 1] == 0.0 {
                    (noeub, noeua) = (i, e[0]);
                }
            }
            if noeub == 0 {
                return Err("TOPOSE: xdecqu: 4 points, one on a vertex, but no edge from it is cut".into());
            }
            inter.swap(1, noeub);
            let noeuc = (2..4)
                .rfind(|&i| edges[inter[i].edge - 1][..2].contains(&noeua))
                .ok_or("TOPOSE: xdecqu: 4 points, one on a vertex: no cut edge from the far end")?;
            inter.swap(2, noeuc);
        }
        // Configurations Code_Aster refuses (xerfis, first crack only).
        if ifiss == 0 {
            let bad = if self.dim == 1 {
                n != 1 && npts != 0
            } else if self.dim == 2 {
                n <= 1
                    || n > 3
                    || npts > n
                    || (n == 2 && npts == 2)
                    || (n == 3 && npts == 0)
                    || (n == 3 && npts == 1 && nptm != 1)
                    || (n == 3 && npts >= 2)
            } else {
                n == 3 && npts == 2
            };
            if bad {
                return Err(format!(
                    "TOPOSE: forbidden cutting configuration (XFEM_64): {n} intersection points, {npts} on \
                     vertices, {nptm} on mid-nodes"
                ));
            }
        }
        let vertices: Vec<[f64; 3]> =
            sub.iter().map(|&id| self.pt(id, &[], &[]).map(|p| p.x)).collect::<Result<_, _>>()?;
        let lonref_sub = loncar(Cutting::subcell_type(self.dim), &vertices);
        // xalgo2 in a 2D mesh; in a 3D mesh xalgo3, which cuts a boundary
        // triangle as xalgo2 does (xalg20) and has no case for a segment.
        let mil = if self.dim == 1 && self.ndim == 3 {
            return Err("TOPOSE: a quadratic boundary segment of a 3D mesh is cut (xalgo3 has no such case)".into());
        } else if self.dim <= 2 {
            self.algo2(sub, &inter, npts, lonref_sub, ifiss)?
        } else {
            match (n, npts) {
                (3, 0) => self.alg30(sub, &inter, lonref_sub, ifiss)?,
                (3, 1) => self.alg31(sub, &inter, lonref_sub, ifiss)?,
                (4, 0) => self.alg40(sub, &inter, lonref_sub, ifiss)?,
                (4, 1) if nptm >= 1 => self.alg41(sub, &inter, lonref_sub, ifiss)?,
                (4, 2) if nptm >= 1 && inter[2].edge != 0 => self.alg42(sub, &inter, lonref_sub, ifiss)?,
                _ => {
                    return Err(format!(
                        "TOPOSE: unexpected 3D cutting of crack {}: {n} intersection points, {npts} on vertices, \
                         {nptm} on mid-nodes",
                        ifiss + 1
                    ))
                }
            }
        };
        Ok(Decoupe { cut, inter, npts, mil })
    }

    /// Crossing point of crack `ifiss` on a quadratic sub-edge (`xinter`):
    /// the root of the quadratic interpolation of the sub-edge values starts
    /// a Newton solve of φ(ξ(s)) = 0 along the (possibly curved) sub-edge
    /// ξ(s), φ the parent interpolation of the nodal level set (`xnewto`,
    /// `xdelt0`). The sub-edge is curved, or the nodal values are not those of
    /// a linear field, when `xajuls` snapped a value to zero or `xmilfa` moved
    /// a mid-node of a flat sub-triangle.
    #[allow(clippy::too_many_arguments)]
    fn xinter(&self, na: Wp, nb: Wp, nm: Wp, la: f64, lb: f64, lm: f64, ifiss: usize) -> Result<Pt, String> {
        let pa = self.pt(na, &[], &[])?.xi;
        let pb = self.pt(nb, &[], &[])?.xi;
        let pm = self.pt(nm, &[], &[])?.xi;
        if (la - lb).abs() <= 0.0 {
            return Err("TOPOSE: equal level sets at the ends of a cut edge".into());
        }
        let (a, b, c) = ((la + lb - 2.0 * lm) / 2.0, (lb - la) / 2.0, lm);
        let s0 = if a.abs() < 1e-8 {
            la / (la - lb)
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                return Err("TOPOSE: xinter: no root of the level set on a cut sub-edge".into());
            }
            let mut x = (-b - disc.sqrt()) / (2.0 * a);
            if x.abs() > 1.0 {
                x = (-b + disc.sqrt()) / (2.0 * a);
            }
            if x.abs() > 1.0 {
                return Err("TOPOSE: xinter: the root of the level set is off the sub-edge".into());
            }
            (x + 1.0) / 2.0
        };
        let curve = |s: f64| -> ([f64; 3], [f64; 3]) {
            let (wa, wm, wb) = (2.0 * (1.0 - s) * (0.5 - s), 4.0 * s * (1.0 - s), 2.0 * s * (s - 0.5));
            let (da, dm, db) = (4.0 * s - 3.0, 4.0 - 8.0 * s, 4.0 * s - 1.0);
            (
                [0, 1, 2].map(|j| wa * pa[j] + wm * pm[j] + wb * pb[j]),
                [0, 1, 2].map(|j| da * pa[j] + dm * pm[j] + db * pb[j]),
            )
        };
        let s = self.newton(s0, (0.0, 1.0), curve, ifiss).unwrap_or(s0);
        let xi = curve(s).0;
        self.check_on_crack(&xi, ifiss, "xinter")?;
        Ok(self.to_real(xi))
    }

    /// Value and gradient (reference coordinates) of crack `ifiss`'s level
    /// set, parent interpolation.
    fn lsn_grad(&self, xi: &[f64; 3], ifiss: usize) -> (f64, [f64; 3]) {
        let nn = self.t.nnodes();
        let mut n = vec![0.0; nn];
        let mut dn = vec![[0.0; 3]; nn];
        crate::fem::reference::shape_and_deriv(self.t, xi, &mut n, &mut dn);
        let mut v = 0.0;
        let mut g = [0.0; 3];
        for k in 0..nn {
            v += n[k] * self.lsn[ifiss][k];
            for (gj, dj) in g.iter_mut().zip(&dn[k]) {
                *gj += dj * self.lsn[ifiss][k];
            }
        }
        (v, g)
    }

    /// Newton solve of φ(ξ(s)) = 0 on a parametrised line or curve
    /// (`xnewto` with `xdelt0`): at least 3 and at most 100 iterations,
    /// relative increment 1e-9 (absolute 1e-11 near s = 0); an iterate
    /// leaving `bounds` is pulled back half-way to the bound (the Dekker
    /// safeguard). None when it does not converge.
    fn newton(
        &self,
        s0: f64,
        bounds: (f64, f64),
        curve: impl Fn(f64) -> ([f64; 3], [f64; 3]),
        ifiss: usize,
    ) -> Option<f64> {
        const EPSMAX: f64 = 1e-9;
        let mut s = s0;
        for iter in 1..=100 {
            let (xi, dxi) = curve(s);
            let (v, g) = self.lsn_grad(&xi, ifiss);
            let dv = V3::from(g).dot(&V3::from(dxi));
            if dv == 0.0 || !dv.is_finite() {
                return None;
            }
            let delta = v / dv;
            s -= delta;
            if s > bounds.1 {
                s = (s + delta + bounds.1) / 2.0;
            } else if s < bounds.0 {
                s = (s + delta + bounds.0) / 2.0;
            }
            let (refe, eps) = if s * s <= EPSMAX { (1.0, EPSMAX / 100.0) } else { (s * s, EPSMAX) };
            if iter >= 3 && (delta * delta / refe).sqrt() <= eps {
                return Some(s);
            }
        }
        None
    }

    /// The Newton solves of Code_Aster (xnewto) converge on the interface;
    /// a point still off it means a case that is not reproduced.
    fn check_on_crack(&self, xi: &[f64; 3], ifiss: usize, what: &str) -> Result<(), String> {
        let v = self.interp(xi, ifiss);
        let scale = self.lsn[ifiss].iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
        if v.abs() > 1e-8 * scale {
            return Err(format!(
                "TOPOSE: {what}: the point is off the interface (level set {v:.3e}) after the Newton solve"
            ));
        }
        Ok(())
    }

    /// Type-1 mid-points of intersection point `r` (`xmilar`): between the
    /// point and end `ia`, then between the point and end `ib`.
    fn milar(&self, ia: Wp, ib: Wp, im: Wp, pr: &[f64; 3]) -> Result<(Pt, Pt), String> {
        let pta = self.pt(ia, &[], &[])?.xi;
        let ptb = self.pt(ib, &[], &[])?.xi;
        let ptm = self.pt(im, &[], &[])?.xi;
        // A mid-node of the parent (or a centre node): straight halves; an
        // archived mid-point: along the quadratic sub-edge.
        let (ka, kb) = if !matches!(im, Wp::PMil(_)) {
            (mid(pr, &pta), mid(pr, &ptb))
        } else {
            let ab = V3::from(ptb) - V3::from(pta);
            let aip = V3::from(*pr) - V3::from(pta);
            let s = aip.norm() / ab.norm() * xnormv(ab).dot(&xnormv(aip));
            let ka = [0, 1, 2]
                .map(|j| (1.0 - s) * (1.0 - s / 2.0) * pta[j] + s / 2.0 * (s - 1.0) * ptb[j] + s * (2.0 - s) * ptm[j]);
            let kb = [0, 1, 2]
                .map(|j| s / 2.0 * (s - 1.0) * pta[j] + s / 2.0 * (s + 1.0) * ptb[j] + (s + 1.0) * (1.0 - s) * ptm[j]);
            (ka, kb)
        };
        Ok((self.to_real(ka), self.to_real(kb)))
    }

    /// Type-2 mid-point between intersection points `ip1` and `ip2` (1-based
    /// in `inter`, `xmifis`): from their middle, a Newton solve along a line
    /// across the segment puts it on the interface, the iterates kept in the
    /// triangle that holds both points (`xintva`'s Dekker bounds); where the
    /// solve does not converge there, the middle itself, as Code_Aster's
    /// `xnewto` takes on its last split. In 2D the line is the perpendicular
    /// in the reference plane (Code_Aster's); in 3D it lies within the face of
    /// the sub-tetrahedron that holds both points (`detefa`), toward the
    /// vertex their edges share (along the edge of the edge point when the
    /// other is a vertex): a direction made of the face's points, so that the
    /// two cells — or sub-tetrahedra — sharing the face find the same point
    /// whatever their reference coordinates (Code_Aster's perpendicular is
    /// not invariant under the affine change of coordinates between two
    /// TETRA10 sharing a face, and its point on a curved interface differs
    /// between them). On a straight interface both give the middle. A point
    /// that would fold the face's sub-triangles is replaced by the middle
    /// ([`Ctx::face_folds`]), a rule of the face alone.
    fn mifis(&self, sub: &[Wp], inter: &[Inter], ip1: usize, ip2: usize, ifiss: usize) -> Result<Pt, String> {
        let (p1, p2) = (&inter[ip1 - 1], &inter[ip2 - 1]);
        let (q1, q2) = (V3::from(p1.p.xi), V3::from(p2.p.xi));
        if self.flat.get() && self.dim == 2 {
            return Ok(self.to_real(((q1 + q2) / 2.0).into()));
        }
        // In 3D, on a face bent by an earlier crack (`CurvedFace`), the search runs in the plane of the
        // face's vertices, from the points brought back to it, and is lifted onto the face.
        let (v, face, q1, q2, tri) = if self.dim == 2 {
            let d = q2 - q1;
            let tri = [0, 1, 2].map(|l| self.pt(sub[l], &[], &[]).map(|p| V3::from(p.xi)));
            let tri = [tri[0].clone()?, tri[1].clone()?, tri[2].clone()?];
            (xnormv(V3::new(-d[1], d[0], 0.0)), None, q1, q2, tri)
        } else {
            let ([na, nb, nc], ids) = self.detefa(sub, p1, p2)?;
            let face = CurvedFace::of(self, sub, ids)?;
            let (q1, q2) = match &face {
                Some(f) => (f.flatten(&q1)?, f.flatten(&q2)?),
                None => (q1, q2),
            };
            let (pa, pb, pc) = (V3::from(na.xi), V3::from(nb.xi), V3::from(nc.xi));
            let v = if p1.edge == 0 || p2.edge == 0 { xnormv(pc - pb) } else { xnormv(pa - (q1 + q2) / 2.0) };
            if v.norm() == 0.0 || !v.iter().all(|c| c.is_finite()) {
                return Err("TOPOSE: xmifis: the two points and the face are aligned".into());
            }
            (v, face, q1, q2, [pa, pb, pc])
        };
        let m = (q1 + q2) / 2.0;
        let curve = |k: f64| {
            let p = m + k * v;
            let (b, db) = face.as_ref().map_or((V3::zeros(), V3::zeros()), |f| f.bubble(&p, &v));
            ((p + b).into(), (v + db).into())
        };
        let bounds = dekker_triangle(&m, &v, &tri);
        let xi = match self.newton(0.0, bounds, curve, ifiss) {
            Some(k) if self.check_on_crack(&curve(k).0, ifiss, "xmifis").is_ok() => {
                let xi = curve(k).0;
                // Only a point off the chord's middle by more than BENT of the chord is a curved
                // interface's: below, the level set was bent by `xajuls` (nodal values set to 0, which
                // moves the interface by at most the distance they moved it), and a sub-triangle it
                // folds is a sliver of a vertex that the interface passes within that distance of —
                // taking the middle there would move the interface off the neighbouring cells' by as
                // much (a TETRA10 junction 1e-6·h from a node: 4.6e-7·U).
                let bent = (V3::from(xi) - m).norm() > BENT * (q2 - q1).norm();
                if self.dim == 3
                    && face.is_none()
                    && bent
                    && face_folds(&tri, &q1, &q2, &V3::from(xi), p1.edge == 0 || p2.edge == 0)
                {
                    curve(0.0).0
                } else {
                    xi
                }
            }
            _ => curve(0.0).0,
        };
        Ok(self.to_real(xi))
    }

    /// The face of the sub-tetrahedron holding two intersection points
    /// (`detefa`): (a, b, c) with the search plane spanned by a − b and
    /// c − b. A vertex point gives its edge partner's edge and itself; two
    /// edge points give the far ends of their edges and the shared vertex.
    fn detefa(&self, sub: &[Wp], p1: &Inter, p2: &Inter) -> Result<([Pt; 3], [usize; 3]), String> {
        let ed = &TETRA10_EDGES;
        let ids: [usize; 3] = match (p1.edge, p2.edge) {
            (0, 0) => return Err("TOPOSE: detefa: both points are vertices".into()),
            (0, a) | (a, 0) => {
                let v = if p1.edge == 0 { p1.node } else { p2.node };
                let v = v.ok_or("TOPOSE: detefa: a vertex point without its vertex")?;
                let l =
                    sub[..4].iter().position(|&w| w == v).ok_or("TOPOSE: detefa: the vertex point is not a vertex")?;
                [ed[a - 1][0], ed[a - 1][1], l + 1]
            }
            (a1, a2) => {
                let mut found = None;
                for i in 0..2 {
                    for j in 0..2 {
                        if ed[a1 - 1][i] == ed[a2 - 1][j] {
                            found = Some([ed[a1 - 1][1 - i], ed[a2 - 1][1 - j], ed[a1 - 1][i]]);
                        }
                    }
                }
                found.ok_or("TOPOSE: detefa: the two cut edges share no vertex")?
            }
        };
        let pt = |l: usize| self.pt(sub[l - 1], &[], &[]);
        // n(1) = b, n(2) = c, n(3) = a in xmifis.
        Ok(([pt(ids[2])?, pt(ids[0])?, pt(ids[1])?], ids))
    }

    /// Type-3 mid-point (`xmilfa`): between point `ip1` and the far end b of
    /// point `ip2`'s edge; `pm2` is the 1-based index of their type-2
    /// mid-point in `mil`.
    ///
    /// Code_Aster moves the point to the middle of (`pm2`, mid-node of the
    /// edge a–b) when the sub-edge ip1–b is within 1e-3 rad of the interface
    /// ("courbe"), for a curved interface that the straight middle could
    /// cross. It does so for a straight interface too, where the angle is
    /// small because ip2 is near b: the sub-cell (ip1, ip2, b) is then a
    /// needle whose edge ip1–b bulges by a fraction of the cell, and its
    /// quadratic map folds — the sub-cells overlap and no longer tile the
    /// parent (a volume error of 8 % in a QUAD8 at 5e-5·h from a vertex).
    /// The point is moved only where it must be: when the straight middle is
    /// not strictly on b's side of the interface (crack `ifiss`).
    #[allow(clippy::too_many_arguments)]
    fn milfa(
        &self,
        sub: &[Wp],
        inter: &[Inter],
        ip1: usize,
        ip2: usize,
        pm2: usize,
        mil: &[Pt],
        ifiss: usize,
    ) -> Result<Pt, String> {
        let edges = self.edges();
        let a1 = inter[ip1 - 1].edge;
        let a2 = inter[ip2 - 1].edge;
        // The vertex the two edges share, and their other ends a and b.
        let (shared, a, b) = vertex_and_ends(edges, a1, a2);
        let mut d = 0;
        for e in edges {
            for j in 0..2 {
                if e[j] == a && e[1 - j] == b {
                    d = e[2];
                }
            }
        }
        if a * b * d == 0 {
            return Err("TOPOSE: xmilfa: the two intersection edges share no vertex".into());
        }
        let pta = self.pt(sub[a - 1], &[], &[])?.xi;
        let ptb = self.pt(sub[b - 1], &[], &[])?.xi;
        let ptd = self.pt(sub[d - 1], &[], &[])?.xi;
        let q1 = inter[ip1 - 1].p.xi;
        let q2 = inter[ip2 - 1].p.xi;
        let pm = mil.get(pm2 - 1).ok_or("TOPOSE: xmilfa: missing mid-point")?.xi;
        if self.flat.get() && self.dim == 2 {
            return Ok(self.to_real(mid(&q1, &ptb)));
        }
        // On a curved face (an earlier crack's, bent by xajuls) the middles are taken on the face.
        let face = if self.dim == 3 { CurvedFace::of(self, sub, [a, b, shared])? } else { None };
        let middle = |p: &[f64; 3], q: &[f64; 3]| -> Result<[f64; 3], String> {
            match &face {
                Some(f) => Ok(f.lift(&((f.flatten(&V3::from(*p))? + f.flatten(&V3::from(*q))?) / 2.0)).into()),
                None => Ok(mid(p, q)),
            }
        };
        let mut ksi = middle(&q1, &ptb)?;
        let t1 = xnormv(V3::from(ksi) - V3::from(q1));
        let t2 = xnormv(V3::from([0, 1, 2].map(|i| -1.5 * q1[i] - 0.5 * q2[i] + 2.0 * pm[i])));
        let t3 = xnormv(V3::from(pta) - V3::from(q1));
        let cosu = t1.dot(&t2);
        // NaN (|cosu| > 1 by round-off) compares false, as in Fortran.
        let mut sinu = (1.0 - cosu * cosu).sqrt();
        if t3.dot(&t2) > t3.dot(&t1) {
            sinu = -sinu;
        }
        if sinu < 1e-3 {
            let side_b = self.node_lsn(sub[b - 1], ifiss, &[], &[])?;
            if self.interp(&ksi, ifiss) * side_b <= 0.0 {
                ksi = middle(&pm, &ptd)?;
            }
        }
        for v in ksi.iter_mut().take(self.dim) {
            if v.abs() > 1.0 + 1e-12 {
                return Err("TOPOSE: xmilfa: mid-point outside the parent".into());
            }
            *v = v.clamp(-1.0, 1.0);
        }
        Ok(self.to_real(ksi))
    }

    /// 2D mid-points (`xalgo2`).
    fn algo2(&self, sub: &[Wp], inter: &[Inter], npts: usize, lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = self.edges();
        let n = inter.len();
        let shared = |a1: usize, a2: usize| -> usize {
            let mut s = 0;
            for i in 0..2 {
                for j in 0..2 {
                    if ed[a1 - 1][i] == ed[a2 - 1][j] {
                        s = ed[a1 - 1][i];
                    }
                }
            }
            s
        };
        let noeua = match (n, npts) {
            (2, 0) => shared(inter[0].edge, inter[1].edge),
            (3, 1) => shared(inter[1].edge, inter[2].edge),
            (2, 1) => ed[inter[1].edge - 1][0],
            // A boundary segment: its single edge's first end.
            _ if self.dim == 1 => inter.first().and_then(|p| p.edge.checked_sub(1)).map_or(0, |k| ed[k][0]),
            _ => 0,
        };
        if noeua == 0 {
            return Err(format!("TOPOSE: xalgo2: unexpected configuration ({n} points, {npts} on vertices)"));
        }
        // xstudo: (ip1, ip2, pm2).
        let pairs: Vec<(usize, usize, usize)> = match (n, npts) {
            (2, 0) => vec![(1, 2, 5)],
            (2, 1) => vec![(1, 2, 0)],
            (3, _) => vec![(2, 3, 5)],
            _ => vec![],
        };
        let mut mil = Vec::new();
        self.type1(sub, inter, ed, &mut mil, lonref, |e| (0..2).find(|&i| e[i] == noeua).map(|i| (e[1 - i], e[i])))?;
        for &(i1, i2, _) in &pairs {
            if inter[i1 - 1].edge != 0 || inter[i2 - 1].edge != 0 {
                let p = self.mifis(sub, inter, i1, i2, ifiss)?;
                add_mid(&mut mil, p, lonref);
            }
        }
        for &(i1, i2, pm2) in &pairs {
            if inter[i1 - 1].edge != 0 && inter[i2 - 1].edge != 0 {
                let p = self.milfa(sub, inter, i1, i2, pm2, &mil, ifiss)?;
                add_mid(&mut mil, p, lonref);
            }
        }
        Ok(mil)
    }

    /// Type-1 mid-points of every non-vertex intersection point: `ends`
    /// gives, for the point's edge, (end of the first mid-point, end of the
    /// second) as 1-based local nodes.
    fn type1(
        &self,
        sub: &[Wp],
        inter: &[Inter],
        ed: &[[usize; 3]],
        mil: &mut Vec<Pt>,
        lonref: f64,
        ends: impl Fn(&[usize; 3]) -> Option<(usize, usize)>,
    ) -> Result<(), String> {
        for p in inter {
            if p.edge == 0 {
                continue;
            }
            let e = &ed[p.edge - 1];
            let (ia, ib) = ends(e).ok_or("TOPOSE: mid-points: the reference vertex is not on the edge")?;
            let (ma, mb) = self.milar(sub[ia - 1], sub[ib - 1], sub[e[2] - 1], &p.p.xi)?;
            add_mid(mil, ma, lonref);
            add_mid(mil, mb, lonref);
        }
        Ok(())
    }

    /// 3D mid-points, three intersection points (`xalg30`).
    fn alg30(&self, sub: &[Wp], inter: &[Inter], lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = &TETRA10_EDGES;
        let (a2, a3) = (inter[1].edge, inter[2].edge);
        let mut noeua = 0;
        for i in 0..2 {
            for j in 0..2 {
                if ed[a2 - 1][i] == ed[a3 - 1][j] {
                    noeua = ed[a2 - 1][i];
                }
            }
        }
        if noeua == 0 {
            return Err("TOPOSE: xalg30: the cut edges share no vertex".into());
        }
        let mut mil = Vec::new();
        self.type1(sub, inter, ed, &mut mil, lonref, |e| (0..2).find(|&i| e[i] == noeua).map(|i| (e[1 - i], e[i])))?;
        let pairs = [(1, 2, 7), (2, 3, 8), (1, 3, 9)];
        for &(i1, i2, _) in &pairs {
            let p = self.mifis(sub, inter, i1, i2, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        for &(i1, i2, pm2) in &pairs {
            let p = self.milfa(sub, inter, i1, i2, pm2, &mil, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        if mil.len() != 12 {
            return Err(format!("TOPOSE: xalg30: {} mid-points instead of 12", mil.len()));
        }
        Ok(mil)
    }

    /// 3D mid-points, four intersection points (`xalg40`).
    fn alg40(&self, sub: &[Wp], inter: &[Inter], lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = &TETRA10_EDGES;
        let (a1, a2) = (inter[0].edge, inter[1].edge);
        let (mut nb, mut nc) = (0, 0);
        for i in 0..2 {
            for j in 0..2 {
                if ed[a1 - 1][i] == ed[a2 - 1][j] {
                    nb = ed[a1 - 1][1 - i];
                    nc = ed[a2 - 1][1 - j];
                }
            }
        }
        if nb * nc == 0 {
            return Err("TOPOSE: xalg40: the first two cut edges share no vertex".into());
        }
        let mut mil = Vec::new();
        self.type1(sub, inter, ed, &mut mil, lonref, |e| {
            (0..2).find(|&i| e[1 - i] == nb || e[1 - i] == nc).map(|i| (e[1 - i], e[i]))
        })?;
        let pairs = [(2, 1, 9), (4, 2, 10), (4, 3, 11), (3, 1, 12)];
        for &(i1, i2, _) in &pairs {
            let p = self.mifis(sub, inter, i1, i2, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        let c = self.cenfi(sub, inter, &mil, [1, 2, 3, 4], [9, 12, 11, 10], ifiss)?;
        add_mid(&mut mil, c, lonref);
        for &(i1, i2, pm2) in &pairs {
            let p = self.milfa(sub, inter, i1, i2, pm2, &mil, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        if mil.len() != 17 {
            return Err(format!("TOPOSE: xalg40: {} mid-points instead of 17", mil.len()));
        }
        Ok(mil)
    }

    /// Centre of the interface quadrangle (pi1, pi2, pi4, pi3) of a
    /// sub-tetrahedron (`xcenfi`): `quad` is (pi1, pi2, pi3, pi4) and `mids`
    /// the 1-based mid-points of its sides (m12, m13, m34, m24) in `mil`. The
    /// search starts from the middle of the diagonal pi1–pi4, or, where a side
    /// is bent by more than 1e-2 rad from its chord (a curved interface), from
    /// the middle of the mid-points of that side and of the opposite one; it
    /// runs along the level set's gradient there, the iterates kept in the
    /// sub-tetrahedron (`xintva`), and takes the start where it does not
    /// converge (`xnewto`'s last split). In [`Ctx::flat`] mode: the middle
    /// of pi1–pi4.
    fn cenfi(
        &self,
        sub: &[Wp],
        inter: &[Inter],
        mil: &[Pt],
        quad: [usize; 4],
        mids: [usize; 4],
        ifiss: usize,
    ) -> Result<Pt, String> {
        let [p1, p2, p3, p4] = quad;
        let [m12, m13, m34, m24] = mids;
        let vin = |k: usize| V3::from(inter[k - 1].p.xi);
        let vmil = |k: usize| mil.get(k - 1).map(|p| V3::from(p.xi)).ok_or("TOPOSE: xcenfi: missing mid-point");
        if self.flat.get() {
            return Ok(self.to_real(((vin(p1) + vin(p4)) / 2.0).into()));
        }
        let (mut maxi, mut worst) = (0.0f64, 0);
        for (side, (a, b, m)) in [(p1, p2, m12), (p2, p4, m24), (p3, p4, m34), (p1, p3, m13)].into_iter().enumerate() {
            let cosi = xnormv(vin(b) - vin(a)).dot(&xnormv(vmil(m)? - vin(a)));
            if cosi < 1.0 && cosi.acos() > maxi {
                (maxi, worst) = (cosi.acos(), side);
            }
        }
        let start = if maxi <= 1e-2 {
            (vin(p1) + vin(p4)) / 2.0
        } else if worst == 0 || worst == 2 {
            (vmil(m12)? + vmil(m34)?) / 2.0
        } else {
            (vmil(m13)? + vmil(m24)?) / 2.0
        };
        let g = xnormv(V3::from(self.lsn_grad(&start.into(), ifiss).1));
        let line = |k: f64| ((start + k * g).into(), g.into());
        let verts: Vec<V3> =
            sub[..4].iter().map(|&w| self.pt(w, &[], &[]).map(|p| V3::from(p.xi))).collect::<Result<_, _>>()?;
        let bounds = dekker_tetra(&start, &g, &verts);
        let c = match self.newton(0.0, bounds, line, ifiss) {
            Some(k) if self.check_on_crack(&line(k).0, ifiss, "xcenfi").is_ok() => line(k).0,
            _ => start.into(),
        };
        Ok(self.to_real(c))
    }

    /// 3D mid-points, three intersection points of which the first is a
    /// vertex of the sub-tetrahedron (`xalg31`): the type-1 points of points
    /// 2 and 3 (from the vertex their edges share), the type-2 points of
    /// (1, 2), (2, 3), (3, 1), the type-3 point of (2, 3).
    fn alg31(&self, sub: &[Wp], inter: &[Inter], lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = &TETRA10_EDGES;
        let noeua =
            shared_vertex(ed, inter[1].edge, inter[2].edge).ok_or("TOPOSE: xalg31: the cut edges share no vertex")?;
        let mut mil = Vec::new();
        self.type1(sub, inter, ed, &mut mil, lonref, |e| (0..2).find(|&i| e[i] == noeua).map(|i| (e[1 - i], e[i])))?;
        for (i1, i2) in [(1, 2), (2, 3), (3, 1)] {
            let p = self.mifis(sub, inter, i1, i2, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        let p = self.milfa(sub, inter, 2, 3, 6, &mil, ifiss)?;
        add_mid(&mut mil, p, lonref);
        if mil.len() != 8 {
            return Err(format!("TOPOSE: xalg31: {} mid-points instead of 8", mil.len()));
        }
        Ok(mil)
    }

    /// 3D mid-points, four intersection points of which the first is a
    /// vertex and the second on the mid-node of an edge from it (`xalg41`,
    /// after `xdecqu`'s ordering): type-1 points, type-2 points of (2, 3),
    /// (3, 4), (4, 1), the centre of the quadrangle (4, 3, 1, 2), type-3
    /// points of (2, 3) and (3, 4), and the middle of point 2 and the far end
    /// noeuc of point 4's edge.
    fn alg41(&self, sub: &[Wp], inter: &[Inter], lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = &TETRA10_EDGES;
        let noeua = shared_vertex(ed, inter[1].edge, inter[2].edge);
        let noeub = shared_vertex(ed, inter[2].edge, inter[3].edge);
        let (Some(noeua), Some(noeub)) = (noeua, noeub) else {
            return Err("TOPOSE: xalg41: consecutive cut edges share no vertex".into());
        };
        let e4 = ed[inter[3].edge - 1];
        let noeuc = if e4[0] == noeub { e4[1] } else { e4[0] };
        let mut mil = Vec::new();
        self.type1(sub, inter, ed, &mut mil, lonref, |e| {
            (0..2).find(|&i| e[i] == noeua).or_else(|| (0..2).find(|&i| e[i] == noeub)).map(|i| (e[1 - i], e[i]))
        })?;
        for (i1, i2) in [(2, 3), (3, 4), (4, 1)] {
            let p = self.mifis(sub, inter, i1, i2, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        let c = self.cenfi(sub, inter, &mil, [4, 3, 1, 2], [8, 9, 1, 7], ifiss)?;
        add_mid(&mut mil, c, lonref);
        for (i1, i2, pm2) in [(2, 3, 7), (3, 4, 8)] {
            let p = self.milfa(sub, inter, i1, i2, pm2, &mil, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        let far = self.pt(sub[noeuc - 1], &[], &[])?.xi;
        add_mid(&mut mil, self.to_real(mid(&inter[1].p.xi, &far)), lonref);
        if mil.len() != 13 {
            return Err(format!("TOPOSE: xalg41: {} mid-points instead of 13", mil.len()));
        }
        Ok(mil)
    }

    /// 3D mid-points, four intersection points, the first two vertices of the
    /// sub-tetrahedron and the last on the mid-node of the edge joining them
    /// (`xalg42`): the type-1 points of point 3 and the type-2 points of
    /// (1, 3) and (2, 3).
    fn alg42(&self, sub: &[Wp], inter: &[Inter], lonref: f64, ifiss: usize) -> Result<Vec<Pt>, String> {
        let ed = &TETRA10_EDGES;
        let mut mil = Vec::new();
        self.type1(sub, &inter[..3], ed, &mut mil, lonref, |e| Some((e[0], e[1])))?;
        for (i1, i2) in [(1, 3), (2, 3)] {
            let p = self.mifis(sub, inter, i1, i2, ifiss)?;
            add_mid(&mut mil, p, lonref);
        }
        if mil.len() != 4 {
            return Err(format!("TOPOSE: xalg42: {} mid-points instead of 4", mil.len()));
        }
        Ok(mil)
    }
}

/// A face of a sub-tetrahedron whose mid-nodes are off its edges' middles in the parent's reference
/// space: the face of a child of an earlier crack on that crack's interface, where `xajuls` bent the
/// level set (a quadratic face, TRIA6-like). Its points are ξ = p + b(p), p on the plane of its vertices
/// and b the quadratic bubble of its mid-node offsets, Σ 4 λᵢ λⱼ dᵢⱼ over its edges (λ the barycentric
/// coordinates of p). Mid-points that a later crack puts on such a face (`xmifis`, `xmilfa`) are taken on
/// it rather than on the plane of its vertices, so that the sub-cells on its two sides share it: on the
/// plane they left gaps and overlaps of the size of the bend (a HEXA20 junction 1e-6·h from a node row:
/// 9.6e-9 of the cell, refused as a tiling).
struct CurvedFace {
    v: [V3; 3],
    /// Offsets of the mid-nodes of the edges (0, 1), (1, 2), (2, 0).
    d: [V3; 3],
}

impl CurvedFace {
    /// Vertex pairs of the three edges, in the order of `d`.
    const EDGES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

    /// The face of `sub` (a TETRA10 sub-cell) through its local vertices `f` (1-based), or None when it is
    /// flat (every mid-node within 1e-13 of its edge's middle).
    fn of(ctx: &Ctx, sub: &[Wp], f: [usize; 3]) -> Result<Option<CurvedFace>, String> {
        if sub.len() != 10 {
            return Ok(None);
        }
        let at = |l: usize| ctx.pt(sub[l - 1], &[], &[]).map(|p| V3::from(p.xi));
        let v = [at(f[0])?, at(f[1])?, at(f[2])?];
        let mut d = [V3::zeros(); 3];
        for (k, &(i, j)) in Self::EDGES.iter().enumerate() {
            let e = TETRA10_EDGES
                .iter()
                .find(|e| (e[0] == f[i] && e[1] == f[j]) || (e[0] == f[j] && e[1] == f[i]))
                .ok_or("TOPOSE: internal error, a face's vertices are not joined by an edge")?;
            d[k] = at(e[2])? - (v[i] + v[j]) / 2.0;
        }
        Ok(d.iter().any(|x| x.norm() > 1e-13).then_some(CurvedFace { v, d }))
    }

    /// Barycentric coordinates of the projection of `p` on the plane of the vertices.
    fn lambda(&self, p: &V3) -> [f64; 3] {
        let (e1, e2, r) = (self.v[1] - self.v[0], self.v[2] - self.v[0], p - self.v[0]);
        let (a, b, c) = (e1.dot(&e1), e1.dot(&e2), e2.dot(&e2));
        let (r1, r2) = (r.dot(&e1), r.dot(&e2));
        let det = a * c - b * b;
        let (l1, l2) = ((r1 * c - r2 * b) / det, (a * r2 - b * r1) / det);
        [1.0 - l1 - l2, l1, l2]
    }

    /// The bubble at `p` and its derivative along `dir`.
    fn bubble(&self, p: &V3, dir: &V3) -> (V3, V3) {
        let l = self.lambda(p);
        let l0 = self.lambda(&self.v[0]);
        let dl: [f64; 3] = {
            let q = self.lambda(&(self.v[0] + dir));
            [q[0] - l0[0], q[1] - l0[1], q[2] - l0[2]]
        };
        let (mut b, mut db) = (V3::zeros(), V3::zeros());
        for (k, &(i, j)) in Self::EDGES.iter().enumerate() {
            b += 4.0 * l[i] * l[j] * self.d[k];
            db += 4.0 * (dl[i] * l[j] + l[i] * dl[j]) * self.d[k];
        }
        (b, db)
    }

    /// The point of the face over `p` (on the plane).
    fn lift(&self, p: &V3) -> V3 {
        p + self.bubble(p, &V3::zeros()).0
    }

    /// The point of the plane under `q` (on the face): p = q − b(p) by fixed-point iteration, which
    /// contracts by the size of the bend.
    fn flatten(&self, q: &V3) -> Result<V3, String> {
        let mut p = *q;
        for _ in 0..100 {
            let next = q - self.bubble(&p, &V3::zeros()).0;
            let step = (next - p).norm();
            p = next;
            if step <= 1e-15 * (1.0 + q.norm()) {
                return Ok(p);
            }
        }
        Err("TOPOSE: a point of a curved sub-cell face could not be brought back to its plane".into())
    }
}

/// The interval of a line search m + k·v (v a unit vector) that stays in the triangle `tri` (`xintva`
/// for `xmifis`): the parameters where the line meets the triangle's sides, the last one found on either
/// side of the start; unbounded when the line meets no side on one of them.
fn dekker_triangle(m: &V3, v: &V3, tri: &[V3; 3]) -> (f64, f64) {
    const TOLE: f64 = 5e-7;
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..3 {
        let (a, b) = (tri[i], tri[(i + 1) % 3]);
        let len = (b - a).norm();
        let e = xnormv(b - a);
        let (b1, c1, c2) = (v.dot(&e), v.dot(&(a - m)), (a - m).dot(&e));
        let det = b1 * b1 - 1.0;
        if det.abs() <= 1e-12 || len == 0.0 {
            continue;
        }
        let (kappa, alpha) = ((-c1 + c2 * b1) / det, (c2 - b1 * c1) / det / len);
        if (-TOLE..=1.0 + TOLE).contains(&alpha) {
            if kappa <= 0.0 {
                lo = kappa;
            }
            if kappa >= 0.0 {
                hi = kappa;
            }
        }
    }
    if lo < hi {
        (lo.max(-f64::MAX), hi.min(f64::MAX))
    } else {
        (-f64::MAX, f64::MAX)
    }
}

/// The interval of a line search m + k·g (g a unit vector) that stays in the tetrahedron `t` (`xintva`
/// for `xcenfi`): within ±10, narrowed by the planes of its faces that the line is not parallel to.
fn dekker_tetra(m: &V3, g: &V3, t: &[V3]) -> (f64, f64) {
    const TOLE: f64 = 5e-7;
    let (a, b, c, d) = (t[0], t[1], t[2], t[3]);
    let (ab, bc, ca, ad, bd) = (xnormv(b - a), xnormv(c - b), xnormv(a - c), xnormv(d - a), xnormv(d - b));
    let (mut lo, mut hi) = (-10.0, 10.0);
    for (n, p) in [(ab.cross(&bc), a), (ab.cross(&ad), a), (ca.cross(&ad), a), (bd.cross(&bc), b)] {
        let n = xnormv(n);
        let ng = n.dot(g);
        if ng.abs() >= TOLE {
            let alpha = (p - m).dot(&n) / ng;
            if alpha > lo && alpha < 0.0 {
                lo = alpha;
            } else if alpha < hi && alpha > 0.0 {
                hi = alpha;
            }
        }
    }
    (lo, hi)
}

/// The offset of a type-2 point from the middle of its chord, relative to the chord, below which the
/// interface counts as straight for [`face_folds`] (the folds of a curved one are seen from 1.5e-2 on
/// the random spheres of `tests/it/xfem/curved.rs`; `xajuls` snaps vertex values within 1e-6 of an
/// edge's end, which bends a straight interface by as little).
const BENT: f64 = 1e-3;

/// Whether a type-2 point `m` between `q1` and `q2` on the face `tri` = (a, b, c) of a sub-tetrahedron
/// folds the face's sub-triangles it is a mid-node of: the corner (a, q1, q2) and the two triangles the
/// quadrangle beyond can give, (q1, q2, b) and (q1, q2, c), their other mid-nodes straight; for a vertex
/// point (`vertex`: a is q1 or q2, the other on b–c), (a, q, b) and (a, q, c). Computed in the face's
/// own affine coordinates, so that both sub-tetrahedra — or cells — sharing the face decide alike.
fn face_folds(tri: &[V3; 3], q1: &V3, q2: &V3, m: &V3, vertex: bool) -> bool {
    let [a, b, c] = *tri;
    let (e1, e2) = (b - a, c - a);
    let (g11, g12, g22) = (e1.dot(&e1), e1.dot(&e2), e2.dot(&e2));
    let det = g11 * g22 - g12 * g12;
    if det <= 0.0 {
        return false;
    }
    let coords = |p: &V3| -> [f64; 3] {
        let r = p - a;
        let (r1, r2) = (r.dot(&e1), r.dot(&e2));
        [(r1 * g22 - r2 * g12) / det, (g11 * r2 - g12 * r1) / det, 0.0]
    };
    let tria6 = |p: V3, q: V3, r: V3, mpq: V3| -> bool {
        let nodes = [p, q, r, mpq, (q + r) / 2.0, (r + p) / 2.0].map(|x| coords(&x));
        folds(CellType::Tria6, &nodes)
    };
    let others: Vec<V3> = if vertex { vec![b, c] } else { vec![a, b, c] };
    others.into_iter().any(|r| tria6(*q1, *q2, r, *m))
}

/// Whether the quadratic map of a sub-cell whose nodes are at the reference points `xi` (a SEG3, TRIA6
/// or TETRA10, or a linear simplex) folds: its Jacobian changes sign over its nodes and the points of a
/// rule of degree 4.
pub(super) fn folds(st: CellType, xi: &[[f64; 3]]) -> bool {
    use crate::fem::quadrature::{rule_for_degree, RefDomain};
    let dim = st.dim();
    let rule = rule_for_degree(RefDomain::of(st), 4);
    let (mut pos, mut neg) = (false, false);
    for q in rule.points.iter().chain(node_coords(st)) {
        let d = crate::fem::reference::jacobian_det(st, xi, q, dim);
        pos |= d > 0.0;
        neg |= d < 0.0 || d.is_nan();
    }
    pos && neg
}

/// The vertex two edges share (1-based local numbers), if any.
fn shared_vertex(ed: &[[usize; 3]], a1: usize, a2: usize) -> Option<usize> {
    let (e1, e2) = (ed.get(a1.checked_sub(1)?)?, ed.get(a2.checked_sub(1)?)?);
    let mut r = None;
    for &x in &e1[..2] {
        for &y in &e2[..2] {
            if x == y {
                r = Some(x);
            }
        }
    }
    r
}

/// Bring a degenerate (grazing) cutting of a sub-tetrahedron by the first
/// crack back to a usual one (`xdblsn`), `inter` sorted by edge (vertex
/// points first):
/// - 5 points, 2 on vertices p1, p2: the vertex point whose vertex ends
///   another cut edge and the point on the edge p1–p2 are dropped (3, 1);
/// - 6 points, 2 on vertices, or 5, 1 on a vertex: the vertex points are
///   dropped, then a point whose edge shares no vertex with the three
///   others' common one, if they have one (Code_Aster's search order);
/// - 4 points, 1 on a vertex: the vertex point is dropped when the three
///   cut edges meet at a vertex.
fn xdblsn(sub: &[Wp], inter: &mut Vec<Inter>, npts: &mut usize) -> Result<(), String> {
    let ed = &TETRA10_EDGES;
    let bad = || "TOPOSE: xdblsn: unexpected degenerate cutting".to_string();
    if inter.len() > 6 || *npts > 2 {
        return Err(format!("TOPOSE: xdblsn: {} intersection points, {} on vertices", inter.len(), *npts));
    }
    let edge = |p: &Inter| -> Result<[usize; 2], String> {
        let e = ed.get(p.edge.checked_sub(1).ok_or_else(bad)?).ok_or_else(bad)?;
        Ok([e[0], e[1]])
    };
    let local = |p: &Inter| -> Result<usize, String> {
        let id = p.node.ok_or_else(bad)?;
        sub[..4].iter().position(|&s| s == id).map(|k| k + 1).ok_or_else(bad)
    };
    // The point to drop among four edge points: Code_Aster's loop order.
    let three = |inter: &[Inter]| -> Result<Option<usize>, String> {
        let [a1, a2, a3, a4] = [edge(&inter[0])?, edge(&inter[1])?, edge(&inter[2])?, edge(&inter[3])?];
        for &x1 in &a1 {
            for &x2 in &a2 {
                for &x3 in &a3 {
                    for &x4 in &a4 {
                        if x1 == x2 && x1 == x3 {
                            return Ok(Some(4));
                        } else if x1 == x2 && x1 == x4 {
                            return Ok(Some(3));
                        } else if x1 == x3 && x1 == x4 {
                            return Ok(Some(2));
                        } else if x2 == x3 && x2 == x4 {
                            return Ok(Some(1));
                        }
                    }
                }
            }
        }
        Ok(None)
    };
    match (inter.len(), *npts) {
        (5, 2) => {
            let (p1, p2) = (local(&inter[0])?, local(&inter[1])?);
            let joins = |e: [usize; 2]| (e[0] == p1 && e[1] == p2) || (e[0] == p2 && e[1] == p1);
            let mut elim2 = 0;
            for p in &inter[2..5] {
                let e = edge(p)?;
                if joins(e) {
                } else if e[0] == p1 {
                    elim2 = 1;
                } else if e[0] == p2 {
                    elim2 = 2;
                } else if e[1] == p1 {
                    elim2 = 1;
                } else if e[1] == p2 {
                    elim2 = 2;
                }
            }
            if elim2 == 0 {
                return Err(bad());
            }
            inter.remove(elim2 - 1);
            *npts -= 1;
            let mut elim = None;
            for (i, p) in inter.iter().enumerate().skip(1) {
                if joins(edge(p)?) {
                    elim = Some(i);
                }
            }
            inter.remove(elim.ok_or_else(bad)?);
        }
        (6, 2) | (5, 1) => {
            let nv = *npts;
            inter.drain(..nv);
            *npts = 0;
            if let Some(k) = three(inter)? {
                inter.remove(k - 1);
            }
        }
        (4, 1) => {
            let [a1, a2, a3] = [edge(&inter[1])?, edge(&inter[2])?, edge(&inter[3])?];
            if (0..2).any(|i| (0..2).any(|j| (0..2).any(|k| a1[i] == a2[j] && a1[i] == a3[k]))) {
                inter.remove(0);
                *npts = 0;
            }
        }
        _ => {}
    }
    if inter.len() > 4 || *npts > 2 {
        return Err(format!("TOPOSE: xdblsn: {} intersection points, {} on vertices remain", inter.len(), *npts));
    }
    Ok(())
}

/// Split a quadratic prism (18 nodes: 6 vertices, 9 edge mid-nodes, 3
/// face mid-nodes) into three TETRA10 (`xpente`, default pattern).
fn xpente(n: &[Wp; 18]) -> [[Wp; 10]; 3] {
    let g = |k: usize| n[k - 1];
    [
        [g(1), g(5), g(2), g(6), g(16), g(11), g(7), g(18), g(14), g(17)],
        [g(4), g(5), g(1), g(6), g(13), g(16), g(10), g(15), g(14), g(18)],
        [g(1), g(2), g(3), g(6), g(7), g(8), g(9), g(18), g(17), g(12)],
    ]
}

impl Ctx<'_> {
    /// Cut a sub-simplex by crack `ifiss` (`xdecqu`, `xdecqv`, the children oriented): with the mid-points
    /// on the curved interface as Code_Aster places them, and where a child's map folds — a curved
    /// interface, or one curved in the reference coordinates of a non-affine parent, bending an edge past
    /// a vertex or another edge — again with the points inside the sub-simplex flat ([`Ctx::flat`]),
    /// which the flat points keep from folding in a straight sub-simplex. The numbering and the
    /// connectivity are the same either way; a cutting that still folds is left to the tiling check.
    fn cut_simplex(&self, sub: &[Wp], ifiss: usize, fisc: &[(usize, f64)]) -> Result<(Decoupe, Vec<Vec<Wp>>), String> {
        let attempt = |flat: bool| -> Result<(Decoupe, Vec<Vec<Wp>>), String> {
            self.flat.set(flat);
            let d = self.decqu(sub, ifiss, fisc);
            self.flat.set(false);
            let d = d?;
            let mut children = self.decqv(sub, &d)?;
            self.orient(&mut children, &d)?;
            Ok((d, children))
        };
        let curved = attempt(false)?;
        if !curved.0.cut || self.dim == 1 || !self.children_fold(&curved.1, &curved.0)? {
            return Ok(curved);
        }
        match attempt(true) {
            Ok(flat) if !self.children_fold(&flat.1, &flat.0)? => Ok(flat),
            _ => Ok(curved),
        }
    }

    /// Whether the map of one of `children` folds ([`folds`]).
    fn children_fold(&self, children: &[Vec<Wp>], d: &Decoupe) -> Result<bool, String> {
        let st = Cutting::subcell_type(self.dim);
        for ch in children {
            let xi: Vec<[f64; 3]> =
                ch.iter().map(|&w| self.pt(w, &d.inter, &d.mil).map(|p| p.xi)).collect::<Result<_, _>>()?;
            if xi.len() == st.nnodes() && folds(st, &xi) {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// Children of a sub-simplex (`xdecqv`): connectivities with the points
    /// of the sub-simplex ([`Wp::Inter`], [`Wp::LocalMid`]).
    fn decqv(&self, sub: &[Wp], d: &Decoupe) -> Result<Vec<Vec<Wp>>, String> {
        if !d.cut {
            return Ok(vec![sub.to_vec()]);
        }
        let n = d.inter.len();
        let s = |k: usize| sub[k - 1];
        let mut out: Vec<Vec<Wp>> = Vec::new();
        if self.dim == 1 {
            // A boundary segment cut at an inner point P: (P, A, mid(P, A))
            // and (P, B, mid(P, B)), the type-1 mid-points being (P, B) then
            // (P, A).
            match (n, d.npts) {
                (1, 0) => {
                    let e = SEG3_EDGES[d.inter[0].edge.checked_sub(1).ok_or("TOPOSE: xdecqv: bad edge")?];
                    out.push(vec![I(1), s(e[0]), M(2)]);
                    out.push(vec![I(1), s(e[1]), M(1)]);
                }
                _ => out.push(sub.to_vec()),
            }
        } else if self.dim == 2 {
            let ed = &TRIA6_EDGES;
            // a: vertex shared by the edges of points i and j; b, c: their other ends; e: mid-node of the third edge.
            let abce = |a1: usize, a2: usize| -> Option<[usize; 4]> {
                let mut r = None;
                for i in 0..2 {
                    for j in 0..2 {
                        if ed[a1 - 1][i] == ed[a2 - 1][j] {
                            r = Some([ed[a1 - 1][i], ed[a1 - 1][1 - i], ed[a2 - 1][1 - j], ed[6 - a1 - a2 - 1][2]]);
                        }
                    }
                }
                r
            };
            match (n, d.npts) {
                (2, 0) => {
                    let [a, b, c, e] = abce(d.inter[0].edge, d.inter[1].edge).ok_or("TOPOSE: xdecqv: bad edges")?;
                    out.push(vec![I(1), I(2), s(a), M(5), M(4), M(2)]);
                    out.push(vec![I(1), I(2), s(c), M(5), M(3), M(6)]);
                    out.push(vec![I(1), s(b), s(c), M(1), s(e), M(6)]);
                }
                (2, 1) => {
                    let ip1 = d.inter[0].node.ok_or("TOPOSE: xdecqv: the first point is not a vertex")?;
                    let a2 = d.inter[1].edge;
                    let (b, c) = (ed[a2 - 1][0], ed[a2 - 1][1]);
                    let (mut e, mut f) = (0, 0);
                    for r in ed {
                        for j in 0..2 {
                            if s(r[j]) == ip1 && r[1 - j] == b {
                                e = r[2];
                            }
                            if s(r[j]) == ip1 && r[1 - j] == c {
                                f = r[2];
                            }
                        }
                    }
                    if e * f == 0 {
                        return Err("TOPOSE: xdecqv: vertex point not found on the sub-element".into());
                    }
                    out.push(vec![ip1, I(2), s(b), M(3), M(2), s(e)]);
                    out.push(vec![ip1, I(2), s(c), M(3), M(1), s(f)]);
                }
                (3, 1) => {
                    let [a, b, c, e] = abce(d.inter[1].edge, d.inter[2].edge).ok_or("TOPOSE: xdecqv: bad edges")?;
                    out.push(vec![I(2), I(3), s(a), M(5), M(4), M(2)]);
                    out.push(vec![I(2), I(3), s(c), M(5), M(3), M(6)]);
                    out.push(vec![I(2), s(b), s(c), M(1), s(e), M(6)]);
                }
                _ => out.push(sub.to_vec()),
            }
        } else {
            let ed = &TETRA10_EDGES;
            let midn = |p: usize, q: usize| -> usize {
                ed.iter().find(|r| (r[0] == p && r[1] == q) || (r[0] == q && r[1] == p)).map(|r| r[2]).unwrap_or(0)
            };
            let abc = |a1: usize, a2: usize| vertex_and_ends(ed, a1, a2);
            // The mid-node of the edge from a vertex point (a working id) to a local vertex.
            let mid_to = |ip: Wp, v: usize| -> usize {
                ed.iter().find(|r| (0..2).any(|j| s(r[j]) == ip && r[1 - j] == v)).map(|r| r[2]).unwrap_or(0)
            };
            let (a, b, c) = abc(d.inter[0].edge, d.inter[1].edge);
            match (n, d.npts) {
                (0..=2, _) | (3, 2..=3) => out.push(sub.to_vec()),
                (3, 1) => {
                    let ip1 = d.inter[0].node.ok_or("TOPOSE: xdecqv: the first point is not a vertex")?;
                    let (a, b, c) = abc(d.inter[1].edge, d.inter[2].edge);
                    let (e, f, g, h) = (midn(b, c), mid_to(ip1, b), mid_to(ip1, c), mid_to(ip1, a));
                    if d.inter[0].edge != 0 || a * b * c * e * f * g * h == 0 {
                        return Err("TOPOSE: xdecqv: inconsistent 3-point cutting through a vertex".into());
                    }
                    out.push(vec![ip1, I(2), I(3), s(a), M(5), M(6), M(7), s(h), M(2), M(4)]);
                    out.push(vec![ip1, I(2), I(3), s(c), M(5), M(6), M(7), s(g), M(8), M(3)]);
                    out.push(vec![ip1, I(2), s(b), s(c), M(5), M(1), s(f), s(g), M(8), s(e)]);
                }
                (4, 1) => {
                    let ip1 = d.inter[0].node.ok_or("TOPOSE: xdecqv: the first point is not a vertex")?;
                    let (a2, a3, a4) = (d.inter[1].edge, d.inter[2].edge, d.inter[3].edge);
                    let a = shared_vertex(ed, a2, a3).unwrap_or(0);
                    let b = shared_vertex(ed, a3, a4).unwrap_or(0);
                    let c = match a4.checked_sub(1).and_then(|k| ed.get(k)) {
                        Some(r) if r[0] == b => r[1],
                        Some(r) => r[0],
                        None => 0,
                    };
                    let (mut dm, mut e, mut f) = (0, 0, 0);
                    for r in ed {
                        if (r[0] == a && r[1] == c) || (r[0] == c && r[1] == a) {
                            dm = r[2];
                        } else if (r[0] == b && r[1] != a && r[1] != c) || (r[1] == b && r[0] != a && r[0] != c) {
                            e = r[2];
                        } else if (r[0] == c && r[1] != a && r[1] != b) || (r[1] == c && r[0] != a && r[0] != b) {
                            f = r[2];
                        }
                    }
                    if d.inter[0].edge != 0 || a * b * c * dm * e * f == 0 {
                        return Err("TOPOSE: xdecqv: inconsistent 4-point cutting through a vertex".into());
                    }
                    out.push(vec![s(b), I(2), I(4), I(3), M(11), M(10), M(6), M(3), M(7), M(8)]);
                    out.push(vec![s(b), ip1, I(4), I(2), s(e), M(9), M(6), M(11), M(1), M(10)]);
                    let pr = [
                        s(c),
                        I(4),
                        ip1,
                        s(a),
                        I(3),
                        I(2),
                        M(5),
                        M(9),
                        s(f),
                        s(dm),
                        M(8),
                        M(1),
                        M(4),
                        M(7),
                        M(2),
                        M(12),
                        M(10),
                        M(13),
                    ];
                    out.extend(xpente(&pr).iter().map(|t| t.to_vec()));
                }
                (4, 2) => {
                    let (Some(pc), Some(pd)) = (d.inter[0].node, d.inter[1].node) else {
                        return Err("TOPOSE: xdecqv: the first two points are not vertices".into());
                    };
                    let a3 = d.inter[2].edge;
                    if a3 == 0 {
                        return Err("TOPOSE: xdecqv: the third point is a vertex".into());
                    }
                    let (a, b) = (ed[a3 - 1][0], ed[a3 - 1][1]);
                    let e = ed.iter().find(|r| (0..2).any(|j| s(r[j]) == pc && s(r[1 - j]) == pd)).map_or(0, |r| r[2]);
                    let (f, g, h, l) = (mid_to(pc, a), mid_to(pd, a), mid_to(pc, b), mid_to(pd, b));
                    if e * f * g * h * l == 0 {
                        return Err("TOPOSE: xdecqv: inconsistent cutting through two vertices".into());
                    }
                    out.push(vec![pc, pd, I(3), s(a), s(e), M(4), M(3), s(f), s(g), M(1)]);
                    out.push(vec![pc, pd, I(3), s(b), s(e), M(4), M(3), s(h), s(l), M(2)]);
                }
                (3, 0) => {
                    let a3 = d.inter[2].edge;
                    let dd = (0..2).find(|&i| ed[a3 - 1][i] == a).map(|i| ed[a3 - 1][1 - i]).unwrap_or(0);
                    let (e, f, g) = (midn(b, c), midn(c, dd), midn(b, dd));
                    if a * b * c * dd * e * f * g == 0 {
                        return Err("TOPOSE: xdecqv: inconsistent 3-point cutting".into());
                    }
                    out.push(vec![I(1), I(2), I(3), s(a), M(7), M(8), M(9), M(2), M(4), M(6)]);
                    let pr = [
                        I(1),
                        I(2),
                        I(3),
                        s(b),
                        s(c),
                        s(dd),
                        M(7),
                        M(8),
                        M(9),
                        M(1),
                        M(3),
                        M(5),
                        s(e),
                        s(f),
                        s(g),
                        M(10),
                        M(11),
                        M(12),
                    ];
                    out.extend(xpente(&pr).iter().map(|t| t.to_vec()));
                }
                (4, 0) => {
                    let (a3, a4) = (d.inter[2].edge, d.inter[3].edge);
                    let mut dd = 0;
                    for i in 0..2 {
                        for j in 0..2 {
                            if ed[a3 - 1][i] == ed[a4 - 1][j] {
                                dd = ed[a3 - 1][i];
                            }
                        }
                    }
                    let (e, f) = (midn(b, c), midn(a, dd));
                    if a * b * c * dd * e * f == 0 {
                        return Err("TOPOSE: xdecqv: inconsistent 4-point cutting".into());
                    }
                    let p1 = [
                        I(4),
                        I(2),
                        s(c),
                        I(3),
                        I(1),
                        s(b),
                        M(10),
                        M(3),
                        M(7),
                        M(11),
                        M(9),
                        s(e),
                        M(12),
                        M(1),
                        M(5),
                        M(13),
                        M(14),
                        M(16),
                    ];
                    let p2 = [
                        s(a),
                        I(1),
                        I(2),
                        s(dd),
                        I(3),
                        I(4),
                        M(2),
                        M(9),
                        M(4),
                        s(f),
                        M(12),
                        M(10),
                        M(6),
                        M(11),
                        M(8),
                        M(17),
                        M(13),
                        M(15),
                    ];
                    out.extend(xpente(&p1).iter().map(|t| t.to_vec()));
                    out.extend(xpente(&p2).iter().map(|t| t.to_vec()));
                }
                _ => {
                    return Err(format!("TOPOSE: 3D cutting with {n} points, {} on vertices, is not supported", d.npts))
                }
            }
        }
        Ok(out)
    }

    /// Orientation of the TETRA10 children (`xdecqv`): a negative volume
    /// swaps vertices 3↔4 and mid-nodes 6↔9, 7↔8.
    fn orient(&self, children: &mut [Vec<Wp>], d: &Decoupe) -> Result<(), String> {
        if self.dim != 3 {
            return Ok(());
        }
        for ch in children.iter_mut() {
            let mut v = [V3::zeros(); 4];
            for (k, vk) in v.iter_mut().enumerate() {
                if matches!(ch[k], Wp::Centre(_)) {
                    return Err("TOPOSE: a centre node is a vertex of a sub-tetrahedron".into());
                }
                *vk = V3::from(self.pt(ch[k], &d.inter, &d.mil)?.x);
            }
            let ps = (v[1] - v[0]).cross(&(v[2] - v[0])).dot(&(v[3] - v[0]));
            if ps < 0.0 {
                ch.swap(2, 3);
                ch.swap(8, 5);
                ch.swap(6, 7);
            }
        }
        Ok(())
    }

    /// Heaviside values of the children (`xdecqv`): earlier cracks copied
    /// from the parent sub-simplex, the current one from the sign of the sum
    /// of its level set over the nodes (generated points at vertices only).
    fn heaviside(
        &self,
        children: &[Vec<Wp>],
        d: &Decoupe,
        parent_he: &[i32],
        ifiss: usize,
        fisc: &[(usize, f64)],
    ) -> Result<Vec<Vec<i32>>, String> {
        let nnose = children.first().map(|c| c.len()).unwrap_or(0) as f64;
        let mut out = Vec::new();
        for ch in children {
            let mut he: Vec<i32> = parent_he[..ifiss].to_vec();
            he.push(0);
            let mut som = vec![0.0; fisc.len()];
            let (mut cur, mut abslsn, mut vertices) = (0.0, 0.0, 0.0);
            let mut bary = [0.0; 3];
            for (pos, &id) in ch.iter().enumerate() {
                let p = self.pt(id, &d.inter, &d.mil)?;
                for (b, x) in bary.iter_mut().zip(&p.x) {
                    *b += x / nnose;
                }
                let generated = !matches!(id, Wp::Node(_) | Wp::Centre(_));
                if generated && pos > self.dim {
                    continue;
                }
                let l = self.node_lsn(id, ifiss, &d.inter, &d.mil)?;
                // Generated vertices are on the interface as the cutting sees it (`xdecqu` puts a point at a
                // mid-node whose level set it sets to 0, where it is not), and values within 1e-8 are 0.
                if pos <= self.dim && !generated && l.abs() > 1e-8 {
                    vertices += l;
                }
                for (sm, &(m, _)) in som.iter_mut().zip(fisc) {
                    *sm += self.node_lsn(id, m, &d.inter, &d.mil)?;
                }
                cur += l;
                abslsn += l.abs();
            }
            if ifiss == 1 && fisc.len() == 1 && fisc[0].1 * som[0] > 0.0 {
                he[0] = if fisc[0].1 < 0.0 { -1 } else { 1 };
            }
            if fisc.iter().zip(&som).any(|(&(_, c), s)| c * s > 0.0) {
                out.push(he);
                continue;
            }
            // The side of the child's vertices off the interface: they decide which side a sub-simplex
            // is on (it is cut where they differ), while a curved level set may take the other sign at
            // a mid-node, which Code_Aster's sum over the nodes counts (an edge the interface crosses
            // twice, a face it bulges through): there its sign would put the child on the side its
            // vertices — and the neighbouring cells — are not on.
            if vertices != 0.0 {
                he[ifiss] = if vertices < 0.0 { -1 } else { 1 };
                out.push(he);
                continue;
            }
            if abslsn * self.lonref < 1e-8 {
                let xi = crate::fem::reference::inverse_map(
                    self.t,
                    self.coords,
                    &bary,
                    &crate::fem::reference::InverseMapOptions::default(),
                )
                .map_err(|e| format!("TOPOSE: barycentre of a sub-element: {e}"))?
                .xi;
                cur = self.interp(&xi, ifiss);
            }
            he[ifiss] = if cur < 0.0 { -1 } else { 1 };
            out.push(he);
        }
        Ok(out)
    }
}

/// Cut a BOUNDARY cell of the model (a skin element of dimension lower
/// than the mesh's, `mesh_dim`) by its interfaces, as TOPOSE does for the
/// X-FEM boundary elements (`te0514` with `ndime < ndim`). The linear ones
/// (SEG2, and TRIA3 / QUAD4 faces of a 3D mesh) are cut by
/// [`super::topose_linear::topose_linear_boundary`]. The quadratic ones are
/// cut as the bulk cells, in the boundary cell's own reference space:
/// `xdivte` (SEG3 and TRIA6 are their own sub-cell, a QUAD8 face the two
/// TRIA6 of a QUAD8 with its centre node), `xdecqu` on the sub-cell's edges
/// (one for a SEG3), the mid-points of `xalgo2` (`xalg20` for a face of a 3D
/// mesh: the same points), and `xdecqv`: a SEG3 cut at an inner point P
/// gives (P, 1, mid(P, 1)) and (P, 2, mid(P, 2)), a triangle the children of
/// the 2D case. A SEG3 is supported in a 2D mesh only (a cut one in a 3D
/// mesh stops Code_Aster: `xalgo3` has no case for it); a boundary cell
/// lying in an interface (Heaviside value 99, set by `xoripe`) is refused.
/// The sub-cells are SEG3 / TRIA6 in Code_Aster's local order; their
/// orientation is [`super::topose_linear::orient_boundary`]'s.
pub fn topose_boundary(
    t: CellType,
    mesh_dim: usize,
    coords: &[[f64; 3]],
    cracks: &[CrackInCell],
) -> Result<Cutting, String> {
    match (t, mesh_dim) {
        (CellType::Seg3, 2 | 3) | (CellType::Tria6 | CellType::Quad8, 3) => cut_quadratic(t, mesh_dim, coords, cracks),
        _ => super::topose_linear::topose_linear_boundary(t, mesh_dim, coords, cracks),
    }
}

/// Cut a parent cell by its interfaces, as TOPOSE (`te0514`) does. `coords`
/// and `cracks[k].lsn` follow Code_Aster's local node order; the cracks are
/// in the cell's order (model order).
pub fn topose(t: CellType, coords: &[[f64; 3]], cracks: &[CrackInCell]) -> Result<Cutting, String> {
    match t {
        // A TRIA6 or TETRA10 parent is its own single sub-cell (`xdivte`), cut as the sub-cells of
        // a QUAD8 or HEXA20 are.
        // When the sub-triangles fold, the split along the other diagonal (inside the cell).
        CellType::Quad8 => tiled(t, cut_quadratic_split(t, 2, coords, cracks, false)?).or_else(|e| {
            cut_quadratic_split(t, 2, coords, cracks, true).and_then(|c| tiled(t, c)).map_err(|_| e)
        }),
        CellType::Hexa20 | CellType::Tria6 | CellType::Tetra10 | CellType::Penta15 => {
            cut_quadratic(t, t.dim(), coords, cracks)
        }
        CellType::Tria3 | CellType::Quad4 | CellType::Tetra4 | CellType::Penta6 | CellType::Hexa8 => {
            super::topose_linear::topose_linear(t, coords, cracks)
        }
        _ => Err(format!(
            "TOPOSE: parent cell type {} is not supported (QUAD8, HEXA20, TRIA6, TETRA10, PENTA15 and the linear TRIA3, QUAD4, TETRA4, PENTA6, HEXA8)",
            t.name()
        )),
    }
}

/// TOPOSE of a quadratic cell of dimension `t.dim()` in a mesh of dimension
/// `ndim` (a QUAD8, HEXA20, TRIA6 or TETRA10 parent, or a SEG3 / TRIA6 / QUAD8 boundary cell).
fn cut_quadratic(t: CellType, ndim: usize, coords: &[[f64; 3]], cracks: &[CrackInCell]) -> Result<Cutting, String> {
    tiled(t, cut_quadratic_split(t, ndim, coords, cracks, false)?)
}

/// [`cut_quadratic`] before the tiling check, a QUAD8 split along its diagonal 1–3 when
/// `other_diagonal`.
fn cut_quadratic_split(
    t: CellType,
    ndim: usize,
    coords: &[[f64; 3]],
    cracks: &[CrackInCell],
    other_diagonal: bool,
) -> Result<Cutting, String> {
    let (dim, nno) = (t.dim(), t.nnodes());
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
    let lsn: Vec<&[f64]> = cracks.iter().map(|c| c.lsn.as_slice()).collect();
    let mut ctx = Ctx {
        t,
        dim,
        ndim,
        nno,
        coords,
        lsn,
        centre: Vec::new(),
        centre_lsn: Vec::new(),
        pint: Vec::new(),
        pmil: Vec::new(),
        lonref: loncar(t, coords),
        flat: std::cell::Cell::new(false),
    };
    // Centre nodes (`ndcent`): QUAD8, HEXA20 and PENTA15 only.
    let centres: &[[f64; 3]] = match t {
        CellType::Quad8 => &node_coords(CellType::Quad9)[nno..],
        CellType::Hexa20 => &node_coords(CellType::Hexa27)[nno..],
        CellType::Penta15 => &PENTA15_CENTRES,
        _ => &[],
    };
    for xi in centres {
        let p = ctx.to_real(*xi);
        let l = (0..cracks.len()).map(|k| ctx.interp(xi, k)).collect();
        ctx.centre.push(p);
        ctx.centre_lsn.push(l);
    }
    let mut subs: Vec<Vec<Wp>> = match t {
        CellType::Quad8 if other_diagonal => QUAD8_SPLIT_13.iter().map(|s| s.to_vec()).collect(),
        CellType::Quad8 => QUAD8_SPLIT.iter().map(|s| s.to_vec()).collect(),
        CellType::Hexa20 => HEXA20_SPLIT.iter().map(|s| s.to_vec()).collect(),
        CellType::Penta15 => prism_split(&PENTA15_SPLIT, coords),
        // SEG3, TRIA6, TETRA10: the cell itself (`xdivte`).
        _ => vec![(1..=nno).map(|j| N(j as u8)).collect()],
    };
    let mut heav: Vec<Vec<i32>> = vec![vec![0; cracks.len()]; subs.len()];
    // (intersection point, earlier crack it lies on).
    let mut on_crack: Vec<(usize, usize)> = Vec::new();
    for ifiss in 0..cracks.len() {
        let fisc = master_chain(cracks, ifiss)?;
        let nit = subs.len();
        for it in 0..nit {
            let (d, mut children) = ctx.cut_simplex(&subs[it], ifiss, &fisc)?;
            let hes = ctx.heaviside(&children, &d, &heav[it], ifiss, &fisc)?;
            // Archive the intersection points (vertex points keep their id).
            for (ipt, p) in d.inter.iter().enumerate() {
                let mut found = None;
                for (i, q) in ctx.pint.iter().enumerate() {
                    if dist(&q.x, &p.p.x) < ctx.lonref * CRIDIST {
                        found = Some(i);
                    }
                }
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
                // A point of a sub-edge lying on an earlier crack (both ends
                // on its level set) is on that crack too: a junction point
                // (`xdecqu`'s najonc/nbjonc). On a curved interface the
                // parent interpolation there is only near zero.
                let e = ctx.edges()[p.edge - 1];
                let (na, nb) = (subs[it][e[0] - 1], subs[it][e[1] - 1]);
                for f in 0..ifiss {
                    let on = |id: Wp| ctx.node_lsn(id, f, &[], &[]).map(|v| v.abs() <= 1e-12 * ctx.lonref);
                    if on(na)? && on(nb)? && !on_crack.contains(&(ni, f)) {
                        on_crack.push((ni, f));
                    }
                }
                for ch in children.iter_mut() {
                    for v in ch.iter_mut().take(dim + 1) {
                        if *v == Wp::Inter(ipt as u8 + 1) {
                            *v = Wp::PInt(ni as u16 + 1);
                        }
                    }
                }
            }
            for (ipt, p) in d.mil.iter().enumerate() {
                let mut found = None;
                for (i, q) in ctx.pmil.iter().enumerate() {
                    if dist(&q.x, &p.x) < ctx.lonref * CRIDIST {
                        found = Some(i);
                    }
                }
                let ni = match found {
                    Some(i) => i,
                    None => {
                        ctx.pmil.push(*p);
                        ctx.pmil.len() - 1
                    }
                };
                for ch in children.iter_mut() {
                    for v in ch.iter_mut() {
                        if *v == Wp::LocalMid(ipt as u8 + 1) {
                            *v = Wp::PMil(ni as u16 + 1);
                        }
                    }
                }
            }
            for (k, (ch, he)) in children.into_iter().zip(hes).enumerate() {
                if ch.iter().any(|v| matches!(v, Wp::Inter(_) | Wp::LocalMid(_))) {
                    return Err("TOPOSE: internal error, a local point id was left in a sub-element".into());
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
    // Points: parent nodes, intersections, mid-points, then the centre nodes
    // still in use, which become 3000+k, k following the mid-points.
    let ncr = cracks.len();
    let mut points: Vec<CutPoint> = Vec::new();
    let rnodes = node_coords(t);
    for j in 0..nno {
        points.push(CutPoint {
            id: PointId::Node(j as u8 + 1),
            xi: rnodes[j],
            x: coords[j],
            lsn: (0..ncr).map(|k| cracks[k].lsn[j]).collect(),
        });
    }
    let centres: Vec<(u8, Pt)> = (0..ctx.centre.len())
        .map(|j| (j as u8 + 1, ctx.centre[j]))
        .filter(|(j, _)| subs.iter().any(|s| s.contains(&Wp::Centre(*j))))
        .collect();
    let nmil = ctx.pmil.len() as u16;
    let generated = ctx
        .pint
        .iter()
        .enumerate()
        .map(|(k, p)| (PointId::Intersection(k as u16 + 1), *p))
        .chain(ctx.pmil.iter().enumerate().map(|(k, p)| (PointId::Mid(k as u16 + 1), *p)))
        .chain(centres.iter().enumerate().map(|(k, (_, p))| (PointId::Centre(nmil + k as u16 + 1), *p)));
    for (id, p) in generated {
        let on = |f: usize| match id {
            PointId::Intersection(k) => on_crack.contains(&(usize::from(k) - 1, f)),
            _ => false,
        };
        let lsn = (0..ncr).map(|k| if on(k) { 0.0 } else { ctx.interp(&p.xi, k) }).collect();
        points.push(CutPoint { id, xi: p.xi, x: p.x, lsn });
    }
    // Index of a working point among the points.
    let index = |v: Wp| -> Result<usize, String> {
        let found = match v {
            Wp::Node(j) if (1..=nno).contains(&usize::from(j)) => Some(usize::from(j) - 1),
            Wp::PInt(k) if (1..=ctx.pint.len()).contains(&usize::from(k)) => Some(nno + usize::from(k) - 1),
            Wp::PMil(k) if (1..=ctx.pmil.len()).contains(&usize::from(k)) => {
                Some(nno + ctx.pint.len() + usize::from(k) - 1)
            }
            Wp::Centre(j) => {
                centres.iter().position(|(c, _)| *c == j).map(|k| nno + ctx.pint.len() + ctx.pmil.len() + k)
            }
            _ => None,
        };
        found.ok_or_else(|| format!("TOPOSE: internal error, point {v:?} missing"))
    };
    let subcells = subs
        .iter()
        .zip(heav)
        .map(|(s, he)| Ok(SubCell { nodes: s.iter().map(|&v| index(v)).collect::<Result<Vec<_>, String>>()?, he }))
        .collect::<Result<Vec<_>, String>>()?;
    Ok(Cutting { points, subcells })
}

/// `cut` if its sub-cells tile the parent ([`tiling_defect`] within [`TILING_TOL`]), else the error.
fn tiled(t: CellType, cut: Cutting) -> Result<Cutting, String> {
    let defect = tiling_defect(t, &cut);
    if defect.is_nan() || defect > TILING_TOL {
        return Err(format!(
            "TOPOSE: the sub-cells of the {} do not tile it (their reference measures differ from the parent's by \
             {defect:.3e} of it, or a sub-cell map folds)",
            t.name()
        ));
    }
    Ok(cut)
}

/// The largest relative defect of a tiling that [`topose`] accepts.
const TILING_TOL: f64 = 1e-9;

/// How far the sub-cells of a cutting are from tiling their parent: the sum
/// of the measures of the sub-cells in the parent's reference space (each
/// the integral of |det J| of its map, exact for TRIA6 / TETRA10 maps with
/// a rule of degree 4), relative to the parent's reference measure, minus 1
/// in absolute value. Overlapping sub-cells, as a folded curved sub-cell
/// makes, add their overlap; a sub-cell whose Jacobian changes sign makes
/// the defect infinite. Sub-cells that tile the parent give round-off.
pub fn tiling_defect(t: CellType, cut: &Cutting) -> f64 {
    use crate::fem::quadrature::{rule_for_degree, RefDomain};
    let Some(first) = cut.subcells.first() else { return f64::INFINITY };
    let dim = t.dim();
    let st = match (dim, first.nodes.len()) {
        (1, 2) => CellType::Seg2,
        (1, _) => CellType::Seg3,
        (2, 3) => CellType::Tria3,
        (2, _) => CellType::Tria6,
        (_, 4) => CellType::Tetra4,
        _ => CellType::Tetra10,
    };
    let rule = rule_for_degree(RefDomain::of(st), 4);
    let nsub = st.nnodes();
    let mut total = 0.0;
    for sc in &cut.subcells {
        if sc.nodes.len() != nsub {
            return f64::INFINITY;
        }
        let xi: Vec<[f64; 3]> = sc.nodes.iter().map(|&p| cut.points[p].xi).collect();
        if folds(st, &xi) {
            return f64::INFINITY;
        }
        for (q, w) in rule.points.iter().zip(&rule.weights) {
            total += w * crate::fem::reference::jacobian_det(st, &xi, q, dim).abs();
        }
    }
    let reference = RefDomain::of(t).measure();
    ((total - reference) / reference).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The QUAD8 [0,2]×[0,1] in Code_Aster order.
    fn quad8() -> Vec<[f64; 3]> {
        let v = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]];
        let mut c: Vec<[f64; 3]> = v.iter().map(|p| [p[0], p[1], 0.0]).collect();
        for i in 0..4 {
            let (a, b) = (v[i], v[(i + 1) % 4]);
            c.push([(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, 0.0]);
        }
        c
    }

    fn area(cut: &Cutting, s: &SubCell) -> f64 {
        let p = |k: usize| V3::from(cut.points[s.nodes[k]].x);
        // TRIA6 children are not reoriented in 2D (te0514 only checks tetrahedra).
        ((p(1) - p(0)).cross(&(p(2) - p(0)))[2] / 2.0).abs()
    }

    fn check_straight(cut: &Cutting) {
        for s in &cut.subcells {
            for (m, a, b) in [(3, 0, 1), (4, 1, 2), (5, 2, 0)] {
                let (pm, pa, pb) = (cut.points[s.nodes[m]].x, cut.points[s.nodes[a]].x, cut.points[s.nodes[b]].x);
                for k in 0..3 {
                    assert!((pm[k] - (pa[k] + pb[k]) / 2.0).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn uncut_quad8_is_split_along_diagonal_2_4() {
        let c = quad8();
        let lsn: Vec<f64> = c.iter().map(|p| p[1] + 3.0).collect();
        let cut = topose(CellType::Quad8, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        assert_eq!(cut.subcells.len(), 2);
        let ids: Vec<Vec<u32>> =
            cut.subcells.iter().map(|s| s.nodes.iter().map(|&i| cut.points[i].id.number()).collect()).collect();
        assert_eq!(ids, vec![vec![1, 2, 4, 5, 3001, 8], vec![2, 3, 4, 6, 7, 3001]]);
        assert!(cut.subcells.iter().all(|s| s.he == vec![1]));
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s)).sum();
        assert!((total - 2.0).abs() < 1e-14);
    }

    #[test]
    fn quad8_cut_by_one_line() {
        let c = quad8();
        // y = 0.3 + 0.15 x: crosses edges 4-1 (x=0) and 2-3 (x=2) and the diagonal 2-4.
        let lsn: Vec<f64> = c.iter().map(|p| p[1] - 0.3 - 0.15 * p[0]).collect();
        let cut = topose(CellType::Quad8, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        check_straight(&cut);
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s)).sum();
        assert!((total - 2.0).abs() < 1e-12, "{total}");
        assert!(cut.subcells.iter().all(|s| area(&cut, s) > 1e-3));
        // Both primary triangles are cut in 3: 6 sub-elements.
        assert_eq!(cut.subcells.len(), 6);
        // Three distinct intersection points: on edge 4-1, on the diagonal, on edge 2-3.
        let inter: Vec<&CutPoint> = cut.points.iter().filter(|p| matches!(p.id, PointId::Intersection(_))).collect();
        assert_eq!(inter.len(), 3);
        for p in &inter {
            assert!(p.lsn[0].abs() < 1e-14);
        }
        assert_eq!(inter[0].id, PointId::Intersection(1));
        // First triangle (1,2,4): the points are on its edges 2-4 (edge 2) and 4-1 (edge 3).
        assert!((inter[0].x[0] - 0.7 / 0.65).abs() < 1e-12 && (inter[0].x[1] - (1.0 - 0.35 / 0.65)).abs() < 1e-12);
        assert!((inter[1].x[0]).abs() < 1e-12 && (inter[1].x[1] - 0.3).abs() < 1e-12);
        assert!((inter[2].x[0] - 2.0).abs() < 1e-12 && (inter[2].x[1] - 0.6).abs() < 1e-12);
        // Sides: every sub-element's points agree with its sign.
        for s in &cut.subcells {
            for &i in &s.nodes {
                assert!(cut.points[i].lsn[0] * s.he[0] as f64 >= -1e-12);
            }
        }
        // First child replaces slot 1 (the child holding vertex 4, above the line).
        assert_eq!(cut.subcells[0].he, vec![1]);
        let ids: Vec<u32> = cut.subcells[0].nodes.iter().map(|&i| cut.points[i].id.number()).collect();
        assert_eq!(&ids[..3], &[1001, 1002, 4]);
        // The cut diagonal no longer uses the centre node.
        assert!(cut.points.iter().all(|p| !matches!(p.id, PointId::Centre(_))));
        assert_eq!(
            cut.points.iter().filter(|p| matches!(p.id, PointId::Mid(_))).count(),
            6 + 4,
            "the two halves of the diagonal are shared"
        );
    }

    #[test]
    fn quad8_cut_through_a_vertex() {
        let c = quad8();
        // Through node 1 (0,0) and the point (2, 0.5) of edge 2-3.
        let lsn: Vec<f64> = c.iter().map(|p| p[1] - 0.25 * p[0]).collect();
        let cut = topose(CellType::Quad8, &c, &[CrackInCell { lsn, master: None }]).unwrap();
        check_straight(&cut);
        let total: f64 = cut.subcells.iter().map(|s| area(&cut, s)).sum();
        assert!((total - 2.0).abs() < 1e-12);
        for s in &cut.subcells {
            assert!(area(&cut, s) > 1e-3);
            for &i in &s.nodes {
                assert!(cut.points[i].lsn[0] * s.he[0] as f64 >= -1e-12);
            }
        }
        // Vertex 1 is used as it is, no intersection point is made there.
        assert!(cut.points.iter().filter(|p| matches!(p.id, PointId::Intersection(_))).all(|p| p.x[0] > 0.5));
    }

    /// A QUAD8 or HEXA20 box cell in Code_Aster's node order.
    fn box_cell(t: CellType, lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
        crate::fem::reference::node_coords(t)
            .iter()
            .map(|xi| [0, 1, 2].map(|k| if k < t.dim() { lo[k] + (xi[k] + 1.0) / 2.0 * (hi[k] - lo[k]) } else { 0.0 }))
            .collect()
    }

    /// FISS1 at δ from a vertex and a mid-node of the cell, FISS2 branching
    /// on it inside the cell (the junction cell of comm/junction_2d.comm and
    /// junction_3d.comm on cells of size 2, FISS1 at δ from a row of nodes):
    /// the sub-cells tile the parent for every δ. With Code_Aster's xmilfa
    /// the needle (ip1, ip2, vertex) of FISS1 got an edge bulging by a third
    /// of the cell; FISS2 then cut that curved sub-cell into folded ones.
    #[test]
    fn a_junction_near_a_vertex_keeps_the_tiling() {
        for k in 1..=5 {
            for sg in [1.0, -1.0] {
                let d = sg * 2.0 * 10f64.powi(-k);
                for (t, hi, up) in [(CellType::Quad8, [6.0, 6.0, 0.0], 1), (CellType::Hexa20, [6.0, 2.0, 6.0], 2)] {
                    let c = box_cell(t, [4.0, 4.0 * (2 - up) as f64, 4.0], hi);
                    let l1: Vec<f64> = c.iter().map(|p| p[up] - 0.5 * p[0] - 2.0 - d).collect();
                    let l2: Vec<f64> = c.iter().map(|p| p[up] + 0.5 * p[0] - 7.3).collect();
                    let cracks =
                        [CrackInCell { lsn: l1, master: None }, CrackInCell { lsn: l2, master: Some((0, 1.0)) }];
                    let cut = topose(t, &c, &cracks).unwrap_or_else(|e| panic!("{}, δ = {d}: {e}", t.name()));
                    assert!(tiling_defect(t, &cut) < 1e-13, "{}, δ = {d}", t.name());
                }
            }
        }
    }

    /// The same junction cell with FISS1 1e-6·h and 1e-7·h from its row of nodes, whose values `xajuls`
    /// sets to zero: FISS1's interface is then bent between the row's nodes, and so are the faces of its
    /// children on it. FISS2 cuts those children; the mid-points it puts on a bent face are taken on the
    /// face (`CurvedFace`), not on the plane of its vertices, and the sub-cells still tile the parent —
    /// on the plane they left gaps and overlaps of 9.6e-9 of the cell and TOPOSE refused it.
    #[test]
    fn a_junction_on_an_interface_bent_by_xajuls_keeps_the_tiling() {
        for d in [2e-6, -2e-6, 2e-7, -2e-7] {
            let t = CellType::Hexa20;
            let c = box_cell(t, [4.0, 0.0, 4.0], [6.0, 2.0, 6.0]);
            let snap = |v: f64| if v.abs() < 1e-5 { 0.0 } else { v };
            let l1: Vec<f64> = c.iter().map(|p| snap(p[2] - 0.5 * p[0] - 2.0 - d)).collect();
            assert!(l1.iter().filter(|v| **v == 0.0).count() >= 3, "{l1:?}");
            let l2: Vec<f64> = c.iter().map(|p| p[2] + 0.5 * p[0] - 7.3).collect();
            let cracks = [CrackInCell { lsn: l1, master: None }, CrackInCell { lsn: l2, master: Some((0, 1.0)) }];
            let cut = topose(t, &c, &cracks).unwrap_or_else(|e| panic!("δ = {d}: {e}"));
            assert!(tiling_defect(t, &cut) < 1e-13, "δ = {d}: {}", tiling_defect(t, &cut));
        }
    }

    /// Planes through one, two and three vertices of a HEXA20, along its
    /// edges and face diagonals, and a hair's breadth from them: the
    /// degenerate cuttings of the sub-tetrahedra (`xdblsn`, `xalg31`,
    /// `xalg41`, `xalg42`) give sub-cells that tile the parent, on both sides.
    #[test]
    fn planes_through_vertices_of_a_hexa20_tile_it() {
        let c = box_cell(CellType::Hexa20, [0.0; 3], [2.0, 2.0, 2.0]);
        let planes: [([f64; 3], f64); 8] = [
            ([1.0, 1.0, 1.0], 2.0),
            ([1.0, 1.0, 0.0], 2.0),
            ([1.0, 0.0, 0.0], 1.0),
            ([1.0, -1.0, 0.0], 0.0),
            ([1.0, 1.0, -1.0], 1.0),
            ([0.5, 1.0, 0.0], 2.0),
            ([1.0, 0.3, 0.7], 2.0),
            ([1.0, 2.0, 3.0], 3.0),
        ];
        for (n, d0) in planes {
            for shift in [0.0, 1e-12, -1e-9, 1e-8, -1e-6] {
                let lsn: Vec<f64> = c.iter().map(|p| n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d0 - shift).collect();
                let cut = topose(CellType::Hexa20, &c, &[CrackInCell { lsn, master: None }])
                    .unwrap_or_else(|e| panic!("{n:?}·x = {d0} + {shift}: {e}"));
                assert!(tiling_defect(CellType::Hexa20, &cut) < 1e-12, "{n:?}·x = {d0} + {shift}");
            }
        }
    }

    /// TRIA6 and TETRA10 parents are their own single sub-cell (`xdivte`):
    /// cut through vertices, along edges, near nodes and anywhere, the
    /// sub-cells tile the parent, both sides get sub-cells when the interface
    /// crosses it.
    #[test]
    fn tria6_and_tetra10_parents_are_cut_as_one_sub_cell() {
        // Skewed straight-sided cells: x = x0 + A ξ.
        let a = [[2.0, 0.3, -0.2], [0.1, 1.5, 0.4], [0.2, -0.1, 1.8]];
        let x0 = [0.5, -0.25, 0.75];
        for t in [CellType::Tria6, CellType::Tetra10] {
            let dim = t.dim();
            let c: Vec<[f64; 3]> = crate::fem::reference::node_coords(t)
                .iter()
                .map(|xi| {
                    [0, 1, 2]
                        .map(|i| if i < dim { x0[i] + (0..dim).map(|j| a[i][j] * xi[j]).sum::<f64>() } else { 0.0 })
                })
                .collect();
            let vert = |i: usize| c[i];
            // Planes through the centroid, through one and two vertices (an edge in 2D), and near them.
            let g: [f64; 3] = [0, 1, 2].map(|i| (0..=dim).map(|v| vert(v)[i]).sum::<f64>() / (dim + 1) as f64);
            let normals: [[f64; 3]; 4] = [[1.0, 0.0, 0.0], [0.3, 1.0, -0.4], [1.0, -1.0, 0.5], [0.0, 0.2, 1.0]];
            for n in normals {
                let n = if dim == 2 { [n[0], n[1], 0.0] } else { n };
                let dot = |p: [f64; 3]| n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
                for through in [g, vert(0), vert(1)] {
                    for shift in [0.0, 1e-12, -1e-9, 1e-6, -1e-3, 0.1] {
                        let d0 = dot(through) + shift;
                        let lsn: Vec<f64> = c.iter().map(|&p| dot(p) - d0).collect();
                        let cut = topose(t, &c, &[CrackInCell { lsn: lsn.clone(), master: None }])
                            .unwrap_or_else(|e| panic!("{} {n:?} {shift}: {e}", t.name()));
                        assert!(tiling_defect(t, &cut) < 1e-12, "{} {n:?} {shift}", t.name());
                        let lo = lsn[..=dim].iter().cloned().fold(f64::INFINITY, f64::min);
                        let hi = lsn[..=dim].iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                        if lo < -1e-6 && hi > 1e-6 {
                            let sides: Vec<i32> = cut.subcells.iter().map(|s| s.he[0]).collect();
                            assert!(sides.contains(&-1) && sides.contains(&1), "{} {n:?} {shift}", t.name());
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn other_types_are_refused() {
        let e = topose(CellType::Pyram13, &[[0.0; 3]; 13], &[]).unwrap_err();
        assert!(e.contains("PYRAM13"), "{e}");
    }

    /// Whatever a prism's local numbering, its primary split cuts each quadrangular face along the
    /// diagonal through the face's lexicographically lowest vertex (so two cells sharing the face cut
    /// it alike), and the three tetrahedra fill the prism.
    #[test]
    fn prism_splits_agree_on_shared_faces() {
        let base =
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        let faces = [[0, 1, 4, 3], [1, 2, 5, 4], [0, 2, 5, 3]];
        let lex = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| a[k].total_cmp(&b[k])).find(|o| o.is_ne()).unwrap();
        // The 12 numberings of the same prism: rotations and mirror of the triangle, either end first.
        for tri in [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]] {
            for flip in [false, true] {
                let (lo, hi) = if flip { (3, 0) } else { (0, 3) };
                let order: Vec<usize> = tri.iter().map(|&v| v + lo).chain(tri.iter().map(|&v| v + hi)).collect();
                let c: Vec<[f64; 3]> = order.iter().map(|&v| base[v]).collect();
                let tets = prism_split(&PENTA15_SPLIT, &c);
                let v = |w: Wp| match w {
                    Wp::Node(j) => usize::from(j) - 1,
                    _ => unreachable!(),
                };
                let mut volume = 0.0;
                for t in &tets {
                    let p: Vec<V3> = t[..4].iter().map(|&w| V3::from(c[v(w)])).collect();
                    volume += ((p[1] - p[0]).cross(&(p[2] - p[0])).dot(&(p[3] - p[0])) / 6.0).abs();
                }
                assert!((volume - 0.5).abs() < 1e-14, "{order:?}: volume {volume}");
                for f in faces {
                    // The face's vertices in this numbering, its lowest one, and the diagonal used.
                    let fv: Vec<usize> = f.iter().map(|&b| order.iter().position(|&o| o == b).unwrap()).collect();
                    let low = *fv.iter().min_by(|&&a, &&b| lex(&c[a], &c[b])).unwrap();
                    // The face's diagonals are its opposite corners (positions 0–2 and 1–3).
                    let mut used = std::collections::BTreeSet::new();
                    for t in &tets {
                        let ns: Vec<usize> = t[..4].iter().map(|&w| v(w)).collect();
                        for (a, b) in [(fv[0], fv[2]), (fv[1], fv[3])] {
                            if ns.contains(&a) && ns.contains(&b) {
                                used.extend([a, b]);
                            }
                        }
                    }
                    assert_eq!(used.len(), 2, "{order:?}: face {f:?} is cut along {used:?}");
                    assert!(used.contains(&low), "{order:?}: face {f:?} cut along {used:?}, lowest vertex {low}");
                }
            }
        }
    }

    /// A PENTA15 parent is split into three TETRA10 with its face centres (`xdivte`) and cut: the
    /// sub-cells tile it, and a plane across it leaves sub-cells on both sides.
    #[test]
    fn penta15_parents_are_split_and_cut() {
        let a = [[2.0, 0.3, -0.2], [0.1, 1.5, 0.4], [0.2, -0.1, 1.8]];
        let c: Vec<[f64; 3]> = crate::fem::reference::node_coords(CellType::Penta15)
            .iter()
            .map(|xi| [0, 1, 2].map(|i| 0.5 + (0..3).map(|j| a[i][j] * xi[j]).sum::<f64>()))
            .collect();
        let g: [f64; 3] = [0, 1, 2].map(|i| c[..6].iter().map(|p| p[i]).sum::<f64>() / 6.0);
        for n in [[1.0, 0.0, 0.0], [0.3, 1.0, -0.4], [0.0, 0.2, 1.0]] {
            let dot = |p: [f64; 3]| n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
            for shift in [0.0, 1e-9, -1e-3, 0.1] {
                let d0 = dot(g) + shift;
                let lsn: Vec<f64> = c.iter().map(|&p| dot(p) - d0).collect();
                let cut = topose(CellType::Penta15, &c, &[CrackInCell { lsn, master: None }])
                    .unwrap_or_else(|e| panic!("{n:?} {shift}: {e}"));
                assert!(tiling_defect(CellType::Penta15, &cut) < 1e-12, "{n:?} {shift}");
                let sides: Vec<i32> = cut.subcells.iter().map(|s| s.he[0]).collect();
                assert!(sides.contains(&-1) && sides.contains(&1), "{n:?} {shift}");
            }
        }
    }
}
