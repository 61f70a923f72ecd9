//! Degrees of freedom: numbering and elimination of kinematic conditions.
//!
//! [`DofNumbering`] numbers the displacement dofs once, node by node
//! (`DX DY [DZ]` for every node carried by the model's cells, in node
//! order). [`DofMap`] eliminates imposed values (`DDL_IMPO`) and linear
//! relations `Σ aᵢ uᵢ = b` (`LIAISON_DDL`, ...): every dof is written as an
//! affine function of the remaining free dofs, `u = T û + g`, so the
//! reduced system is `Tᵀ K T û = Tᵀ (f - K g)`. The count of eliminated
//! equations is [`DofMap::n_eliminated`].

use crate::mesh::Mesh;
use std::collections::HashMap;
use std::fmt;

/// Component names of the displacement dofs.
pub const COMPONENTS: [&str; 3] = ["DX", "DY", "DZ"];

/// Index of a component name (`"DX"` → 0 ...).
pub fn component_index(name: &str) -> Option<usize> {
    COMPONENTS.iter().position(|c| *c == name)
}

/// Numbering of the dofs of a model: for every node carried by the model's cells, in node order, the
/// components it carries among `components` (`DX DY [DZ]` on every node of a mechanical model; `DX DY
/// [DZ] PRE1` on the vertices and `DX DY [DZ]` on the middle nodes of an HM model), in that order.
#[derive(Debug, Clone)]
pub struct DofNumbering {
    /// Components per node at most (2 or 3 for mechanics, 3 or 4 with `PRE1`).
    pub ncomp: usize,
    /// Their names, in numbering order.
    pub components: Vec<&'static str>,
    /// First dof of each mesh node, `usize::MAX` for nodes outside the model.
    node_first: Vec<usize>,
    /// The components each node carries (bit k: component k), 0 outside the model.
    node_mask: Vec<u32>,
    /// Node of each dof.
    pub dof_node: Vec<usize>,
    /// Component of each dof.
    dof_comp: Vec<u8>,
}

impl DofNumbering {
    /// Number the nodes carried by `cells` (lists of node indices) among
    /// `nnodes` mesh nodes, `ncomp` displacement components each, in node order.
    pub fn new<'a>(nnodes: usize, ncomp: usize, cells: impl IntoIterator<Item = &'a [usize]>) -> DofNumbering {
        let mut mask = vec![0u32; nnodes];
        let all = (1u32 << ncomp) - 1;
        for c in cells {
            for &n in c {
                mask[n] = all;
            }
        }
        DofNumbering::with_components(COMPONENTS[..ncomp].to_vec(), mask)
    }

    /// Number every node whose `mask` is not empty, with the components of its mask (bit k:
    /// `components[k]`), in node order.
    pub fn with_components(components: Vec<&'static str>, mask: Vec<u32>) -> DofNumbering {
        assert!(components.len() <= 32, "at most 32 components per node");
        let mut node_first = vec![usize::MAX; mask.len()];
        let mut dof_node = Vec::new();
        let mut dof_comp = Vec::new();
        for (n, &m) in mask.iter().enumerate() {
            if m != 0 {
                node_first[n] = dof_node.len();
                for k in 0..components.len() {
                    if m & (1 << k) != 0 {
                        dof_node.push(n);
                        dof_comp.push(k as u8);
                    }
                }
            }
        }
        DofNumbering { ncomp: components.len(), components, node_first, node_mask: mask, dof_node, dof_comp }
    }

    /// Numbering for the cells `cell_ids` of `mesh`.
    pub fn for_cells(mesh: &Mesh, ncomp: usize, cell_ids: &[usize]) -> DofNumbering {
        DofNumbering::new(mesh.nnodes(), ncomp, cell_ids.iter().map(|&c| mesh.cells[c].as_slice()))
    }

    /// Total number of dofs.
    pub fn ndofs(&self) -> usize {
        self.dof_node.len()
    }

    /// Dof of `(node, comp)`, `None` when the node is not in the model or does not carry the component.
    pub fn dof(&self, node: usize, comp: usize) -> Option<usize> {
        let f = *self.node_first.get(node)?;
        let m = self.node_mask[node];
        if f == usize::MAX || comp >= self.ncomp || m & (1 << comp) == 0 {
            return None;
        }
        Some(f + (m & ((1u32 << comp) - 1)).count_ones() as usize)
    }

    /// The index of a component name among the numbering's components.
    pub fn component(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| *c == name)
    }

    /// True when the node carries dofs.
    pub fn has_node(&self, node: usize) -> bool {
        self.node_first.get(node).is_some_and(|&f| f != usize::MAX)
    }

    /// `(node, component)` of a dof.
    pub fn node_comp(&self, dof: usize) -> (usize, usize) {
        (self.dof_node[dof], self.dof_comp[dof] as usize)
    }

    /// Dofs of a cell, node by node, each node's components in order (`None` if a node is not
    /// numbered).
    pub fn cell_dofs(&self, nodes: &[usize]) -> Option<Vec<usize>> {
        let mut v = Vec::with_capacity(nodes.len() * self.ncomp);
        for &n in nodes {
            let f = *self.node_first.get(n)?;
            if f == usize::MAX {
                return None;
            }
            v.extend(f..f + self.node_mask[n].count_ones() as usize);
        }
        Some(v)
    }

    /// `"N12 DX"`-style label of a dof (node names from `mesh` when given).
    pub fn label(&self, dof: usize, mesh: Option<&Mesh>) -> String {
        let (n, c) = self.node_comp(dof);
        let name = mesh.and_then(|m| m.node_names.get(n).cloned()).unwrap_or_else(|| format!("N{}", n + 1));
        format!("{name} {}", self.components[c])
    }
}

/// A linear relation `Σ aᵢ u_{dofᵢ} = rhs` between dofs.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearRelation {
    pub terms: Vec<(usize, f64)>,
    pub rhs: f64,
}

/// Kinematic conditions to eliminate.
#[derive(Debug, Clone, Default)]
pub struct Constraints {
    /// Imposed values `(dof, value)`.
    pub imposed: Vec<(usize, f64)>,
    pub relations: Vec<LinearRelation>,
}

impl Constraints {
    pub fn new() -> Constraints {
        Constraints::default()
    }

    pub fn impose(&mut self, dof: usize, value: f64) {
        self.imposed.push((dof, value));
    }

    pub fn relation(&mut self, terms: Vec<(usize, f64)>, rhs: f64) {
        self.relations.push(LinearRelation { terms, rhs });
    }
}

/// Errors of the elimination.
#[derive(Debug, Clone, PartialEq)]
pub enum ConstraintError {
    /// Two conditions impose incompatible values (`index` = position in
    /// the processing order: imposed values first, then relations).
    Conflict { dof: usize, index: usize, residual: f64 },
    /// A dof index out of range.
    UnknownDof { dof: usize },
}

impl fmt::Display for ConstraintError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConstraintError::Conflict { dof, index, residual } => write!(
                f,
                "kinematic condition {} on dof {dof} contradicts the previous ones (residual {residual:e})",
                index + 1
            ),
            ConstraintError::UnknownDof { dof } => write!(f, "kinematic condition on unknown dof {dof}"),
        }
    }
}

impl std::error::Error for ConstraintError {}

/// Every dof as an affine function of the free dofs: `u = T û + g`.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Number of dofs of the full system.
    pub nfull: usize,
    /// Number of free (reduced) dofs.
    pub nfree: usize,
    /// CSR of T: terms of dof `d` are `terms[ptr[d]..ptr[d+1]]`.
    ptr: Vec<usize>,
    terms: Vec<(usize, f64)>,
    /// g.
    constant: Vec<f64>,
    /// Full dof of each free dof.
    pub free_to_full: Vec<usize>,
    /// Number of redundant conditions (already satisfied).
    pub n_redundant: usize,
}

#[derive(Clone)]
enum Expr {
    Free,
    Bound(Vec<(usize, f64)>, f64),
}

impl DofMap {
    /// Identity map (no conditions).
    pub fn identity(n: usize) -> DofMap {
        DofMap {
            nfull: n,
            nfree: n,
            ptr: (0..=n).collect(),
            terms: (0..n).map(|i| (i, 1.0)).collect(),
            constant: vec![0.0; n],
            free_to_full: (0..n).collect(),
            n_redundant: 0,
        }
    }

    /// Eliminate `cons` from `n` dofs. Imposed values are processed first,
    /// then relations in order; each relation eliminates its dof of largest
    /// coefficient (after substitution of the earlier conditions).
    pub fn build(n: usize, cons: &Constraints) -> Result<DofMap, ConstraintError> {
        let mut expr: Vec<Expr> = vec![Expr::Free; n];
        // users[j]: dofs whose expression may mention free dof j.
        let mut users: HashMap<usize, Vec<usize>> = HashMap::new();
        let mut n_redundant = 0;
        let rels = cons
            .imposed
            .iter()
            .map(|&(d, v)| (vec![(d, 1.0)], v))
            .chain(cons.relations.iter().map(|r| (r.terms.clone(), r.rhs)));
        for (index, (terms, rhs)) in rels.enumerate() {
            // Substitute the current expressions.
            let mut acc: Vec<(usize, f64)> = Vec::with_capacity(terms.len());
            let mut b = rhs;
            let mut scale = rhs.abs();
            for &(d, a) in &terms {
                if d >= n {
                    return Err(ConstraintError::UnknownDof { dof: d });
                }
                match &expr[d] {
                    Expr::Free => acc.push((d, a)),
                    Expr::Bound(t, g) => {
                        b -= a * g;
                        scale = scale.max((a * g).abs());
                        acc.extend(t.iter().map(|&(j, c)| (j, a * c)));
                    }
                }
            }
            acc.sort_by_key(|p| p.0);
            let mut merged: Vec<(usize, f64)> = Vec::with_capacity(acc.len());
            for (j, c) in acc {
                match merged.last_mut() {
                    Some(l) if l.0 == j => l.1 += c,
                    _ => merged.push((j, c)),
                }
            }
            let amax = terms.iter().fold(0.0f64, |m, t| m.max(t.1.abs()));
            merged.retain(|t| t.1.abs() > 1e-13 * amax);
            let Some(&(slave, cs)) = merged.iter().max_by(|x, y| x.1.abs().total_cmp(&y.1.abs())) else {
                if b.abs() > 1e-10 * scale.max(f64::MIN_POSITIVE) && b != 0.0 {
                    let dof = terms.first().map(|t| t.0).unwrap_or(0);
                    return Err(ConstraintError::Conflict { dof, index, residual: b });
                }
                n_redundant += 1;
                continue;
            };
            let new_terms: Vec<(usize, f64)> =
                merged.iter().filter(|t| t.0 != slave).map(|&(j, c)| (j, -c / cs)).collect();
            let g = b / cs;
            for &(j, _) in &new_terms {
                users.entry(j).or_default().push(slave);
            }
            // Update the expressions that mention the new slave.
            if let Some(us) = users.remove(&slave) {
                for u in us {
                    let Expr::Bound(t, gu) = &expr[u] else { continue };
                    let Some(pos) = t.iter().position(|p| p.0 == slave) else { continue };
                    let mut t = t.clone();
                    let mut gu = *gu;
                    let c = t.swap_remove(pos).1;
                    gu += c * g;
                    for &(j, cj) in &new_terms {
                        match t.iter_mut().find(|p| p.0 == j) {
                            Some(p) => p.1 += c * cj,
                            None => {
                                t.push((j, c * cj));
                                users.entry(j).or_default().push(u);
                            }
                        }
                    }
                    expr[u] = Expr::Bound(t, gu);
                }
            }
            expr[slave] = Expr::Bound(new_terms, g);
        }
        // Compact numbering of the free dofs.
        let mut free_index = vec![usize::MAX; n];
        let mut free_to_full = Vec::new();
        for (d, e) in expr.iter().enumerate() {
            if matches!(e, Expr::Free) {
                free_index[d] = free_to_full.len();
                free_to_full.push(d);
            }
        }
        let mut ptr = Vec::with_capacity(n + 1);
        let mut all_terms = Vec::with_capacity(n);
        let mut constant = vec![0.0; n];
        ptr.push(0);
        for (d, e) in expr.iter().enumerate() {
            match e {
                Expr::Free => all_terms.push((free_index[d], 1.0)),
                Expr::Bound(t, g) => {
                    constant[d] = *g;
                    let mut t: Vec<_> = t.iter().filter(|p| p.1 != 0.0).map(|&(j, c)| (free_index[j], c)).collect();
                    t.sort_by_key(|p| p.0);
                    all_terms.extend(t);
                }
            }
            ptr.push(all_terms.len());
        }
        Ok(DofMap { nfull: n, nfree: free_to_full.len(), ptr, terms: all_terms, constant, free_to_full, n_redundant })
    }

    /// Number of eliminated equations (imposed + slave dofs).
    pub fn n_eliminated(&self) -> usize {
        self.nfull - self.nfree
    }

    /// Terms `(free dof, coefficient)` and constant of dof `d`.
    #[inline]
    pub fn expr(&self, d: usize) -> (&[(usize, f64)], f64) {
        (&self.terms[self.ptr[d]..self.ptr[d + 1]], self.constant[d])
    }

    /// True when `d` is a free dof.
    pub fn is_free(&self, d: usize) -> bool {
        let (t, g) = self.expr(d);
        t.len() == 1 && t[0].1 == 1.0 && g == 0.0 && self.free_to_full[t[0].0] == d
    }

    /// Full displacement `u = T û + g` from the reduced solution.
    pub fn expand(&self, reduced: &[f64]) -> Vec<f64> {
        assert_eq!(reduced.len(), self.nfree);
        (0..self.nfull)
            .map(|d| {
                let (t, g) = self.expr(d);
                g + t.iter().map(|&(j, c)| c * reduced[j]).sum::<f64>()
            })
            .collect()
    }

    /// Reduced vector `Tᵀ f` of a full vector.
    pub fn reduce_vector(&self, full: &[f64]) -> Vec<f64> {
        let mut r = vec![0.0; self.nfree];
        for (d, f) in full.iter().enumerate() {
            if *f != 0.0 {
                for &(j, c) in self.expr(d).0 {
                    r[j] += c * f;
                }
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbering_skips_unused_nodes() {
        let cells: Vec<Vec<usize>> = vec![vec![0, 2, 3]];
        let num = DofNumbering::new(5, 2, cells.iter().map(|c| c.as_slice()));
        assert_eq!(num.ndofs(), 6);
        assert_eq!(num.dof(2, 1), Some(3));
        assert_eq!(num.dof(1, 0), None);
        assert_eq!(num.node_comp(5), (3, 1));
        assert_eq!(num.label(5, None), "N4 DY");
    }

    #[test]
    fn numbering_with_pressure_on_vertices_only() {
        // Nodes 0 and 1 vertices (DX DY PRE1), node 2 a middle node (DX DY), node 3 outside.
        let num = DofNumbering::with_components(vec!["DX", "DY", "PRE1"], vec![0b111, 0b111, 0b011, 0]);
        assert_eq!(num.ndofs(), 8);
        assert_eq!(num.dof(1, 2), Some(5));
        assert_eq!(num.dof(2, 2), None);
        assert_eq!(num.dof(2, 1), Some(7));
        assert_eq!(num.dof(3, 0), None);
        assert_eq!(num.cell_dofs(&[2, 0]), Some(vec![6, 7, 0, 1, 2]));
        assert_eq!(num.node_comp(5), (1, 2));
        assert_eq!(num.label(2, None), "N1 PRE1");
        assert_eq!(num.component("PRE1"), Some(2));
    }

    #[test]
    fn imposed_and_chained_relations() {
        let mut c = Constraints::new();
        c.impose(0, 1.0);
        c.relation(vec![(1, 1.0), (0, -2.0)], 0.5); // u1 = 2 u0 + 0.5 = 2.5
        c.relation(vec![(2, 1.0), (3, -1.0)], 0.0); // u2 = u3 (one eliminated)
        c.relation(vec![(3, 1.0)], 4.0); // u3 = 4 (the other one)
        c.impose(0, 1.0); // redundant
        let m = DofMap::build(5, &c).unwrap();
        assert_eq!(m.nfree, 1);
        assert_eq!(m.n_eliminated(), 4);
        assert_eq!(m.n_redundant, 1);
        let u = m.expand(&[7.0]);
        assert_eq!(u, vec![1.0, 2.5, 4.0, 4.0, 7.0]);
        let mut bad = Constraints::new();
        bad.impose(1, 1.0);
        bad.impose(1, 2.0);
        assert!(matches!(DofMap::build(3, &bad), Err(ConstraintError::Conflict { dof: 1, .. })));
    }
}
