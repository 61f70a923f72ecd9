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

/// The relative offset from a crossing at which a function is sampled on each side (`xddlimf`).
const EPS: f64 = 2e-6;

/// Where crack `g`'s level set changes sign along the mesh edge n–k of a cell (`mid`: the edge's
/// mid-node on a quadratic cell): the root of its interpolation along the edge, as a fraction of the
/// segment n–k, on which the function is sampled (`xddlimf` places its samples on the chord).
fn crossing(xm: &XfemModel, g: usize, n: usize, k: usize, mid: Option<usize>) -> f64 {
    super::mortar::edge_root(xm.lsn[g][n], xm.lsn[g][k], mid.map(|m| xm.lsn[g][m]))
}

/// Whether `f` jumps across the crossing at fraction `t` of the segment from `xn` to `xk`, told by its
/// own values: the differences across the crossing at two offsets, 2e-6 and 2.5e-7 of the segment's
/// parts, fall by the ratio of the offsets for a function continuous there (smooth or kinked) and stay
/// for a jump. A difference within 1e-10 of the function's values is none. The function is never
/// evaluated on the crossing itself, where a function defined on each side may be defined on neither.
fn jumps_at(f: &Func, xn: &[f64; 3], xk: &[f64; 3], t: f64) -> Result<bool, String> {
    let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
    let across = |e: f64| -> Result<(f64, f64), String> { Ok((f(&at(t * (1.0 - e)))?, f(&at(t + e * (1.0 - t)))?)) };
    let ((w0, w1), (n0, n1)) = (across(EPS)?, across(EPS / 8.0)?);
    let (wide, narrow) = (w1 - w0, n1 - n0);
    let scale = [f(xn)?, f(xk)?, w0, w1].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    Ok(narrow.abs() > 0.5 * wide.abs() && narrow.abs() > 1e-10 * scale)
}

/// The Heaviside parts of node `n` under a function-valued DDL_IMPO of the
/// node set `same` (`xddlimf`): along each mesh edge from `n` to another
/// node `k` of the set where an interface crosses, the set of `n` for the
/// region on `k`'s side is fixed so that the trace there equals the function
/// just beyond the crossing: N_n(a_n + 2h) + N_k a_k = f(x_c⁺) on a linear
/// edge, with a_n = f(x_n), a_k = f(x_k). A set not reached this way gets
/// h = 0 when the function is continuous across the crossings of `n`, and
/// otherwise Code_Aster's point relation ([`point_relation`]) when a node of
/// the set's region belongs to the condition around `n` (nothing if none).
/// Where the function is continuous across the crossing, which its own
/// values tell ([`jumps_at`]), h = 0 on every edge; a discontinuous one on a
/// quadratic edge stops the run.
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
            let quadratic = ct.nnodes() > ct.nvertices();
            let alpha = crossing(xm, g, n, k, quadratic.then(|| nodes[e[2]]));
            let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
            let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
            let beyond = at(alpha + EPS * (1.0 - alpha));
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
            let h = if !jumps_at(eval, &xn, &xk, alpha)? {
                // Continuous across the crossing: the trace matches it on both sides with no jump (the
                // value just beyond, which `xddlimf` matches on a linear edge, differs from the linear
                // trace by the function's change over the offset: 1e-6 of it for a linear function).
                0.0
            } else if quadratic {
                return Err(
                    "a function discontinuous across the interface on a quadratic edge is not supported yet".into()
                );
            } else {
                let (fn_, fk, fc) = (eval(&xn)?, eval(&xk)?, eval(&beyond)?);
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
        let quadratic = ct.nnodes() > ct.nvertices();
        for e in super::levelset::edges(ct) {
            let (n, k) = (nodes[e[0]], nodes[e[1]]);
            if !same.contains(&n) || !same.contains(&k) {
                continue;
            }
            for g in 0..xm.lsn.len() {
                if xm.lsn[g][n] * xm.lsn[g][k] >= 0.0 {
                    continue;
                }
                let alpha = crossing(xm, g, n, k, quadratic.then(|| nodes[e[2]]));
                if jumps_at(f, &mesh.coords[n], &mesh.coords[k], alpha)? {
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
