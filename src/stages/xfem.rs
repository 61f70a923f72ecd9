//! DEFI_FISS_XFEM: an interface given by a normal level-set function, with
//! its junctions on master interfaces, as Code_Aster's `op0041` computes it:
//! nodal level sets (`xinils`) adjusted near zero (`xajuls`), the junction
//! coefficients (`xinlsj`), the node status and enriched cells (`xenrch`).

use super::statics::eval_at;
use super::Ctx;
use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::xfem::{build_interface, crack_of, Crack};
use std::fmt::Write as _;

pub fn defi_fiss_xfem(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["MAILLAGE_GRILLE", "FISS_GRILLE", "TYPE_ENRI_FOND", "RAYON_ENRI", "NB_COUCHES"])?;
    let typdis = a.req_text("TYPE_DISCONTINUITE")?;
    if typdis != "INTERFACE" {
        return Err(a.err("TYPE_DISCONTINUITE", format!("TYPE_DISCONTINUITE='{typdis}' is not supported yet")));
    }
    if a.text("CHAM_DISCONTINUITE").is_some_and(|c| c != "DEPL") {
        return Err(a.err("CHAM_DISCONTINUITE", "CHAM_DISCONTINUITE='SIGM' is not supported yet"));
    }
    let mc = a.req_concept("MAILLAGE")?;
    let mesh = super::mesh::mesh_of(&mc)?;
    let mesh_name = mc.label();

    // Level sets (xinils, method FONCTION; an interface has lst = −1).
    let Some(df) = a.fact("DEFI_FISS") else {
        return Err(a.err("DEFI_FISS", "DEFI_FISS is required"));
    };
    let mut others: Vec<&str> = df.items.iter().filter(|i| !i.defaulted).map(|i| i.name.as_str()).collect();
    others.retain(|n| *n != "FONC_LN");
    if let Some(n) = others.first() {
        return Err(df.err(n, "not supported yet (DEFI_FISS takes FONC_LN only for now)"));
    }
    let fonc = df.concept("FONC_LN").ok_or_else(|| df.err("FONC_LN", "FONC_LN is required"))?;
    let mut lsn = Vec::with_capacity(mesh.nnodes());
    for x in &mesh.coords {
        let mut p = [0.0; 3];
        p[..mesh.dim].copy_from_slice(&x[..mesh.dim]);
        lsn.push(eval_at(&fonc, &p, 0.0).map_err(|e| df.err("FONC_LN", e.msg))?);
    }
    // GROUP_MA_ENRI (xlenri): all cells by default.
    let enri_cells = match a.text("GROUP_MA_ENRI") {
        Some(g) => {
            let mut v =
                mesh.cell_groups.get(g).cloned().ok_or_else(|| {
                    a.err("GROUP_MA_ENRI", format!("group of cells '{g}' is not in mesh {mesh_name}"))
                })?;
            v.sort_unstable();
            v.dedup();
            Some(v)
        }
        None => None,
    };
    let (masters, point) = match a.fact("JONCTION") {
        Some(j) => (j.concepts("FISSURE"), Some(j.reals("POINT"))),
        None => (Vec::new(), None),
    };
    let crack = build_interface(mc.clone(), mesh, lsn, enri_cells, &masters, point.as_deref()).map_err(|e| {
        match (e.keyword, a.fact("JONCTION")) {
            ("FISSURE" | "POINT", Some(j)) => j.err(e.keyword, e.msg),
            ("DEFI_FISS", _) => a.err("DEFI_FISS", e.msg),
            _ => Error::runtime(e.msg),
        }
    })?;
    if a.int("INFO").unwrap_or(1) >= 2 {
        ctx.io.mess(&report(&crack)?);
    }
    Ok(Some(ConceptData::Crack(crack)))
}

/// The INFO=2 summary: counts, junctions, and the nodes shared with each master.
fn report(k: &Crack) -> Result<String> {
    let mesh = &k.mesh;
    let nodes = k.enriched_nodes();
    let vol = |cells: &[usize]| cells.iter().filter(|&&c| mesh.cell_types[c].dim() == mesh.dim).count();
    let mut s = String::new();
    let _ = writeln!(s, "  DEFI_FISS_XFEM (INTERFACE) on {}:", k.mesh_concept.label());
    let _ = writeln!(s, "    level-set values adjusted to 0       : {}", k.adjusted);
    let _ = writeln!(
        s,
        "    cells cut by the interface           : {} ({} of dimension {})",
        k.cut_cells.len(),
        vol(&k.cut_cells),
        mesh.dim
    );
    let _ = writeln!(s, "    Heaviside-enriched nodes             : {}", nodes.len());
    let _ = writeln!(
        s,
        "    Heaviside-enriched cells             : {} ({} of dimension {})",
        k.heaviside_cells.len(),
        vol(&k.heaviside_cells),
        mesh.dim
    );
    if let Some(n) = k.junction_node {
        let _ = writeln!(s, "    junction: node nearest POINT         : {}", mesh.node_names[n]);
    }
    for j in &k.junctions {
        let m = crack_of(&j.crack)?;
        let shared = nodes.iter().filter(|&&n| m.enriched(n)).count();
        let both: Vec<usize> =
            k.heaviside_cells.iter().copied().filter(|c| m.heaviside_cells.binary_search(c).is_ok()).collect();
        let _ = writeln!(
            s,
            "    junction on {} (c = {:+}{}): the branch exists where c*LSN({}) < 0",
            j.crack.label(),
            j.coef,
            if j.declared { "" } else { ", through a master" },
            j.crack.label(),
        );
        let _ = writeln!(s, "      nodes enriched by both             : {shared}");
        let _ = writeln!(
            s,
            "      cells enriched by both             : {} ({} of dimension {})",
            both.len(),
            vol(&both),
            mesh.dim
        );
    }
    Ok(s)
}
