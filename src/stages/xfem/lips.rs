//! POST_CHAM_XFEM: the interface unknowns (cohesive multipliers λ, w, μ and, on HM models, the fracture
//! unknowns) carried from the vertices of a cut cell to the new nodes on the crack, as Code_Aster's
//! `xpoajd` does for mortar interfaces: only at the nodes on the crack (the intersection points, the
//! parent's nodes with lsn exactly 0, the mid-points with |lsn| < 1e-6) that lie on the slave side
//! (Heaviside −1 of the nearest crack), interpolated with the parent's linear vertex functions of which
//! the inactive vertices' shares go equally to the active ones (`xmofhm`); the other nodes have none.
//! Parents that see several cracks, or whose vertices hold the unknowns of several interfaces, are left
//! without them (the interface blocks of a junction are not carried yet).

use crate::xfem::model::XfemModel;
use crate::xfem::topose::PointId;

/// The first-block interface components of a DEPL field, in `xpodim`'s order, and their positions in it;
/// None when the field has no interface unknowns.
pub fn interface_components(components: &[String], ndim: usize, hm: bool) -> Option<Vec<(String, usize)>> {
    let idx = |c: &str| components.iter().position(|x| x == c);
    idx("LAGS_C")?;
    let mut names: Vec<String> = Vec::new();
    if hm {
        names.extend(["PRE_FLU", "LAG_FLI", "LAG_FLS"].map(String::from));
    }
    for head in ["LAGS", "LAG2", "LAG3"] {
        for d in ["C", "F1", "F2"].iter().take(ndim) {
            names.push(format!("{head}_{d}"));
        }
    }
    names.into_iter().map(|n| idx(&n).map(|k| (n, k))).collect()
}

/// The values of the interface components `comps` at a new node of X-FEM parent `parent` (point `id` at
/// reference coordinates `xi`, on the side `he` of the parent's cracks), or None where Code_Aster puts none.
#[allow(clippy::too_many_arguments)]
pub fn at_lip_node(
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    parent: usize,
    id: PointId,
    xi: &[f64; 3],
    he: &[i32],
    values: &[f64],
    nc: usize,
    comps: &[(String, usize)],
    second_block: Option<usize>,
) -> Option<Vec<f64>> {
    let xc = xm.cells.get(&parent)?;
    if xc.cracks.len() != 1 || he.len() != 1 || he[0] != -1 {
        return None;
    }
    let g = xc.cracks[0];
    let t = mesh.cell_types[parent];
    let nodes = &mesh.cells[parent];
    let ff = crate::fem::reference::shape(t, xi);
    let lsn: f64 = nodes.iter().zip(&ff).map(|(&n, f)| f * xm.lsn[g][n]).sum();
    let on_crack = match id {
        PointId::Node(j) => xm.lsn[g][nodes[usize::from(j) - 1]] == 0.0,
        PointId::Intersection(_) => true,
        PointId::Mid(_) | PointId::Centre(_) => lsn.abs() < 1e-6,
    };
    if !on_crack {
        return None;
    }
    let vt = crate::fem::elasticity::vertex_type(t);
    let nv = vt.nnodes();
    let lin = crate::fem::reference::shape(vt, xi);
    let lags_c = comps.iter().find(|(n, _)| n == "LAGS_C").map(|(_, k)| *k)?;
    let active: Vec<bool> = nodes[..nv].iter().map(|&n| values[n * nc + lags_c].is_finite()).collect();
    let nact = active.iter().filter(|&&a| a).count();
    if nact == 0 {
        return None;
    }
    // A vertex with the unknowns of another interface too: which block is this crack's is not known here.
    if second_block.is_some_and(|k| nodes[..nv].iter().any(|&n| values[n * nc + k].is_finite())) {
        return None;
    }
    let mut ffc = lin.clone();
    for i in 0..nv {
        if !active[i] {
            for j in 0..nv {
                if j != i && active[j] {
                    ffc[j] += lin[i] / nact as f64;
                }
            }
            ffc[i] = 0.0;
        }
    }
    Some(
        comps
            .iter()
            .map(|(_, k)| (0..nv).filter(|&j| active[j]).map(|j| ffc[j] * values[nodes[j] * nc + k]).sum())
            .collect(),
    )
}
