//! Kinematic conditions on enriched nodes given by a function (Code_Aster's `xddlimf`): the Heaviside
//! parts that make the trace of the field match the function on every side of an interface, and the
//! point relation for a set no cut edge reaches. The function is a closure of the position, so this
//! knows nothing of concepts or commands.

use super::model::{point_signs, XfemModel};
use super::region_code;
use crate::fem::reference::{inverse_map, shape};
use crate::mesh::Mesh;
use std::collections::BTreeSet;

/// A function of the position (the condition's function at the step's time).
pub type Func<'f> = dyn Fn(&[f64; 3]) -> Result<f64, String> + 'f;

/// The relative offset from a crossing at which a function is sampled on each side.
const EPS: f64 = 2e-6;

/// The Heaviside parts of node `n` under a function-valued DDL_IMPO of the
/// node set `same` (`xddlimf`): along each mesh edge from `n` to another
/// node `k` of the set where an interface crosses, the set of `n` for the
/// region on `k`'s side is fixed so that the trace there equals the function
/// just beyond the crossing: N_n(a_n + 2h) + N_k a_k = f(x_c⁺) on a linear
/// edge, with a_n = f(x_n), a_k = f(x_k). A set not reached this way gets
/// h = 0 when the function is continuous across the crossings of `n`, and
/// otherwise Code_Aster's point relation ([`point_relation`]) when a node of
/// the set's region belongs to the condition around `n` (nothing if none). A
/// quadratic edge is handled when the function is continuous across the
/// crossing (then h = 0); a discontinuous one stops the run.
pub fn trace_sets(
    mesh: &Mesh,
    xm: &XfemModel,
    n: usize,
    same: &BTreeSet<usize>,
    f: &Func,
    jump: bool,
) -> Result<TraceConditions, String> {
    let eval = f;
    let mut out: Vec<(usize, f64)> = (0..xm.node_sets[n].len()).map(|j| (j, 0.0)).collect();
    let mut done = vec![false; out.len()];
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let ct = mesh.cell_types[c];
        if ct.dim() != mesh.dim || !nodes.contains(&n) {
            continue;
        }
        for e in super::levelset::edges(ct) {
            let (ia, ib) = (nodes[e[0]], nodes[e[1]]);
            let k = if ia == n {
                ib
            } else if ib == n {
                ia
            } else {
                continue;
            };
            if !same.contains(&k) {
                continue;
            }
            // The first crack that changes sign along the edge.
            let Some(g) = (0..xm.lsn.len()).find(|&g| xm.lsn[g][n] * xm.lsn[g][k] < 0.0) else { continue };
            let alpha = xm.lsn[g][n] / (xm.lsn[g][n] - xm.lsn[g][k]);
            let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
            let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
            let beyond = at(alpha + EPS * (1.0 - alpha));
            let before = at(alpha * (1.0 - EPS));
            // Region just beyond the crossing, from the cell's nodal level sets.
            let xi = inverse_map(
                ct,
                &nodes.iter().map(|&m| mesh.coords[m]).collect::<Vec<_>>(),
                &beyond,
                &Default::default(),
            )
            .map_err(|e| format!("locating the crossing: {e}"))?
            .xi;
            let ff = shape(ct, &xi);
            let region = region_code(&point_signs(&xm.lsn, &xm.masters, nodes, &ff, &[], &[]));
            let Some(j) = xm.node_sets[n].iter().position(|&r| r == region) else { continue };
            let (fn_, fk, fc) = (eval(&xn)?, eval(&xk)?, eval(&beyond)?);
            let quadratic = ct.nnodes() > ct.nvertices();
            let fb = eval(&before)?;
            let discontinuous = (fc - fb).abs() > 1e-9 * fc.abs().max(fb.abs()).max(1e-300);
            let h = if quadratic {
                if discontinuous {
                    return Err(
                        "a function discontinuous across the interface on a quadratic edge is not supported yet".into(),
                    );
                }
                0.0
            } else {
                // The value the field takes with ψ = 2, turned to the node's ψ (−2 on some nodes).
                ((fc - alpha * fk) / (2.0 * (1.0 - alpha)) - fn_ / 2.0) * 2.0 / xm.psi(n, j, region)
            };
            if done[j] && (out[j].1 - h).abs() > 1e-9 * h.abs().max(out[j].1.abs()).max(1e-300) {
                return Err(format!("two edges ask different Heaviside values ({} and {h}) for one set", out[j].1));
            }
            out[j] = (j, h);
            done[j] = true;
        }
    }
    // A set no cut edge of the condition reaches keeps h = 0, which is exact
    // for a function continuous across the interfaces. For a discontinuous
    // one Code_Aster ties the whole field at a point of the set's region
    // (xddlimf's second case), which we do not do yet.
    // A set no cut edge reaches: Code_Aster ties the whole field at a point
    // of the set's region to the function (xddlimf's second case), or, when
    // no node of the condition lies in that region around the node, imposes
    // nothing on it.
    // For a function continuous across the interfaces the trace matches on
    // every side with h = 0, which that relation then also gives.
    let mut kept = Vec::new();
    let mut points = Vec::new();
    for (j, h) in out {
        if done[j] || !jump {
            kept.push((j, h));
        } else if let Some(p) = point_relation(mesh, xm, n, j, same, f)? {
            points.push(p);
        }
    }
    Ok((kept, points))
}

/// Does `f` jump across an interface somewhere on the condition's node set
/// (along a mesh edge between two of its nodes where a level set changes sign)?
pub fn function_jumps(mesh: &Mesh, xm: &XfemModel, same: &BTreeSet<usize>, f: &Func) -> Result<bool, String> {
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let ct = mesh.cell_types[c];
        if ct.dim() != mesh.dim {
            continue;
        }
        for e in super::levelset::edges(ct) {
            let (n, k) = (nodes[e[0]], nodes[e[1]]);
            if !same.contains(&n) || !same.contains(&k) {
                continue;
            }
            for g in 0..xm.lsn.len() {
                if xm.lsn[g][n] * xm.lsn[g][k] >= 0.0 {
                    continue;
                }
                let alpha = xm.lsn[g][n] / (xm.lsn[g][n] - xm.lsn[g][k]);
                let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
                let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
                let fa = f(&at(alpha * (1.0 - EPS)))?;
                let fb = f(&at(alpha + EPS * (1.0 - alpha)))?;
                if (fa - fb).abs() > 1e-9 * fa.abs().max(fb.abs()).max(1e-300) {
                    return Ok(true);
                }
            }
        }
    }
    Ok(false)
}

/// The conditions on a node's Heaviside sets: (set, value) pairs and point relations.
pub type TraceConditions = (Vec<(usize, f64)>, Vec<PointRelation>);

/// `xddlimf`'s relation for a set no cut edge reaches: the whole field of
/// the set's region at a point of a cell holding the node, equal to the
/// function there.
pub struct PointRelation {
    pub cell: usize,
    /// Shape functions of the cell at the point.
    pub ff: Vec<f64>,
    pub region: i32,
    pub value: f64,
}

/// The point of [`PointRelation`]: in a cell holding node `n` and a node `k`
/// of the condition whose own region is the set's, on the segment n–k at
/// Code_Aster's level-set-weighted position beyond the interface
/// ((|φ_n| + |φ_k|/2) x_k + |φ_k|/2 x_n)/(|φ_n| + |φ_k|), `k` the farthest
/// from the interface.
fn point_relation(
    mesh: &Mesh,
    xm: &XfemModel,
    n: usize,
    j: usize,
    same: &BTreeSet<usize>,
    f: &Func,
) -> Result<Option<PointRelation>, String> {
    let region = xm.node_sets[n][j];
    let mut best: Option<(f64, usize, usize, usize)> = None; // (|φ_k|, cell, k, crack)
    for (c, nodes) in mesh.cells.iter().enumerate() {
        if mesh.cell_types[c].dim() != mesh.dim || !nodes.contains(&n) {
            continue;
        }
        for &k in nodes {
            if k == n || !same.contains(&k) || xm.node_region[k] != region {
                continue;
            }
            let Some(g) = (0..xm.lsn.len()).find(|&g| xm.lsn[g][n] * xm.lsn[g][k] < 0.0) else { continue };
            let lk = xm.lsn[g][k].abs();
            if best.is_none_or(|b| lk > b.0) {
                best = Some((lk, c, k, g));
            }
        }
    }
    let Some((lk, c, k, g)) = best else { return Ok(None) };
    let ln = xm.lsn[g][n].abs();
    let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
    let xp: [f64; 3] = [0, 1, 2].map(|i| ((ln + lk / 2.0) * xk[i] + lk / 2.0 * xn[i]) / (ln + lk));
    let ct = mesh.cell_types[c];
    let coords: Vec<[f64; 3]> = mesh.cells[c].iter().map(|&m| mesh.coords[m]).collect();
    let xi =
        inverse_map(ct, &coords, &xp, &Default::default()).map_err(|e| format!("locating xddlimf's point: {e}"))?.xi;
    let ff = shape(ct, &xi);
    let value = f(&xp)?;
    Ok(Some(PointRelation { cell: c, ff, region, value }))
}
