//! AFFE_CHAR_THER and AFFE_CHAR_THER_F: thermal loads on a thermal model, mesh entities resolved and
//! checked. Prescribed temperatures and linear relations become the loads' shared conditions
//! (`LoadItem::Dof` with component TEMP, `LoadItem::Relation`); fluxes, exchanges and sources become
//! [`HeatItem`]s on the model's skin (boundary) or bulk cells.

use super::load_value;
use crate::catalog::args::Args;
use crate::concepts::model::HeatItem;
use crate::concepts::model::{Load, LoadItem, LoadValue, Model, Role};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::Mesh;
use crate::stages::select::{select_cells, select_nodes};
use crate::stages::Ctx;
use std::collections::BTreeSet;

pub fn affe_char_ther(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    affe_char_ther_any(a, false)
}

pub fn affe_char_ther_f(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    affe_char_ther_any(a, true)
}

/// A value keyword of an occurrence (a real, or a function for AFFE_CHAR_THER_F).
fn value(occ: &Args, kw: &str) -> Result<LoadValue> {
    occ.val(kw).and_then(load_value).ok_or_else(|| occ.err(kw, format!("{kw} is required")))
}

/// The cells of an occurrence that carry an element of `role` in the model; an error when none does.
fn cells_of(model: &Model, mesh: &Mesh, occ: &Args, name: &str, role: Role, kw: &str) -> Result<Vec<usize>> {
    let cells: Vec<usize> = select_cells(mesh, occ, name)?
        .into_iter()
        .filter(|&c| model.elements.get(c).and_then(|e| e.as_ref()).is_some_and(|e| e.role == role))
        .collect();
    if cells.is_empty() {
        let what = if role == Role::Skin { "boundary (skin)" } else { "volume" };
        let at = if occ.has("GROUP_MA") { "GROUP_MA" } else { "TOUT" };
        return Err(occ.err(at, format!("{kw}: no cell of the selection carries a {what} element of the model")));
    }
    Ok(cells)
}

fn affe_char_ther_any(a: &Args, functional: bool) -> Result<Option<ConceptData>> {
    a.refuse(&["EVOL_CHAR", "SECH_IMPO", "PRE_GRAD_TEMP", "LIAISON_MAIL", "LIAISON_CHAMNO", "CONVECTION"])?;
    // Dualised (Lagrange) or eliminated, prescribed temperatures give the same solution: we eliminate.
    let _ = a.text("DOUBLE_LAGRANGE");
    let mo = a.req_concept("MODELE")?;
    let model = mo.model()?;
    if !model.is_thermal() {
        return Err(a.err("MODELE", format!("{} is not a thermal model (PHENOMENE='THERMIQUE')", mo.label())));
    }
    let mesh = model.current_mesh();
    let name = model.mesh_concept.label();
    let mut items = Vec::new();
    for occ in a.facts("TEMP_IMPO") {
        occ.refuse(&["TEMP_MIL", "TEMP_INF", "TEMP_SUP"])?;
        let v = value(occ, "TEMP")?;
        for node in select_nodes(&mesh, occ, &name)? {
            items.push(LoadItem::Dof { node, component: "TEMP".into(), value: v.clone() });
        }
    }
    for occ in a.facts("FLUX_REP") {
        occ.refuse(&["FLUN_INF", "FLUN_SUP", "CARA_TORSION"])?;
        let cells = cells_of(&model, &mesh, occ, &name, Role::Skin, "FLUX_REP")?;
        if occ.given("FLUN") {
            items.push(LoadItem::Heat(HeatItem::NormalFlux { cells: cells.clone(), value: value(occ, "FLUN")? }));
        }
        let comps =
            ["FLUX_X", "FLUX_Y", "FLUX_Z"].map(|k| occ.declares(k).then(|| occ.val(k).and_then(load_value)).flatten());
        if comps.iter().any(Option::is_some) {
            items.push(LoadItem::Heat(HeatItem::FluxVector { cells, components: comps }));
        }
    }
    for occ in a.facts("ECHANGE") {
        occ.refuse(&["COEF_H_INF", "TEMP_EXT_INF", "COEF_H_SUP", "TEMP_EXT_SUP"])?;
        let cells = cells_of(&model, &mesh, occ, &name, Role::Skin, "ECHANGE")?;
        items.push(LoadItem::Heat(HeatItem::Exchange {
            cells,
            coef_h: value(occ, "COEF_H")?,
            temp_ext: value(occ, "TEMP_EXT")?,
        }));
    }
    for occ in a.facts("SOURCE") {
        occ.refuse(&["SOUR_CALCULEE"])?;
        let cells = cells_of(&model, &mesh, occ, &name, Role::Bulk, "SOURCE")?;
        items.push(LoadItem::Heat(HeatItem::Source { cells, value: value(occ, "SOUR")? }));
    }
    for occ in a.facts("RAYONNEMENT") {
        let cells = cells_of(&model, &mesh, occ, &name, Role::Skin, "RAYONNEMENT")?;
        items.push(LoadItem::Heat(HeatItem::Radiation {
            cells,
            sigma: value(occ, "SIGMA")?,
            epsilon: value(occ, "EPSILON")?,
            temp_ext: value(occ, "TEMP_EXT")?,
        }));
    }
    let only_f = |k: &str| if a.declares(k) { a.facts(k) } else { &[] };
    for occ in only_f("FLUX_NL") {
        let cells = cells_of(&model, &mesh, occ, &name, Role::Skin, "FLUX_NL")?;
        items.push(LoadItem::Heat(HeatItem::NonlinearFlux { cells, flux: occ.req_concept("FLUN")? }));
    }
    for occ in only_f("SOUR_NL") {
        let cells = cells_of(&model, &mesh, occ, &name, Role::Bulk, "SOUR_NL")?;
        items.push(LoadItem::Heat(HeatItem::NonlinearSource { cells, source: occ.req_concept("SOUR")? }));
    }
    for occ in a.facts("ECHANGE_PAROI") {
        occ.refuse(&["FISSURE", "TEMP_CONTINUE"])?;
        items.push(LoadItem::Heat(wall_exchange(&model, &mesh, occ, &name)?));
    }
    for occ in a.facts("LIAISON_DDL") {
        items.push(liaison_ddl(&mesh, occ, &name)?);
    }
    for occ in a.facts("LIAISON_UNIF") {
        only_temp(occ, "DDL")?;
        let nodes = group_nodes(&mesh, occ, &name, "GROUP_MA", "GROUP_NO")?;
        for &n in nodes.iter().skip(1) {
            let terms = vec![(nodes[0], "TEMP".to_string(), 1.0), (n, "TEMP".to_string(), -1.0)];
            items.push(LoadItem::Relation { terms, value: LoadValue::Real(0.0) });
        }
    }
    for occ in a.facts("LIAISON_GROUP") {
        items.extend(liaison_group(&mesh, occ, &name)?);
    }
    drop(model);
    Ok(Some(ConceptData::Load(Load { model: mo, items: super::surcharge(items), functional })))
}

/// Only the temperature TEMP (TEMP_MIL, TEMP_INF, TEMP_SUP belong to shells, H1 to X-FEM).
fn only_temp(occ: &Args, kw: &str) -> Result<()> {
    match occ.texts(kw).into_iter().find(|d| d != "TEMP") {
        Some(d) => Err(occ.err(kw, format!("DDL '{d}' is not supported yet (TEMP is)"))),
        None => Ok(()),
    }
}

/// The nodes of GROUP_MA-like and GROUP_NO-like keywords of an occurrence, sorted, each once.
fn group_nodes(mesh: &Mesh, occ: &Args, name: &str, kw_ma: &str, kw_no: &str) -> Result<Vec<usize>> {
    let mut nodes = BTreeSet::new();
    for g in occ.texts(kw_ma) {
        let cells = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err(kw_ma, format!("group of cells '{g}' is not in mesh {name}")))?;
        nodes.extend(cells.iter().flat_map(|&c| mesh.cells[c].iter().copied()));
    }
    for g in occ.texts(kw_no) {
        let ns = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err(kw_no, format!("group of nodes '{g}' is not in mesh {name}")))?;
        nodes.extend(ns.iter().copied());
    }
    Ok(nodes.into_iter().collect())
}

/// LIAISON_DDL: Σ COEF_MULT·T(node) = COEF_IMPO, one node per GROUP_NO (DDL, TEMP for each, may be left out).
fn liaison_ddl(mesh: &Mesh, occ: &Args, name: &str) -> Result<LoadItem> {
    only_temp(occ, "DDL")?;
    let nodes = super::single_nodes(mesh, occ, name)?;
    // Without DDL, every term is on TEMP.
    let mut ddl = occ.texts("DDL");
    if ddl.is_empty() {
        ddl = vec!["TEMP".to_string(); nodes.len()];
    }
    let coef = occ.reals("COEF_MULT");
    if nodes.len() != ddl.len() || ddl.len() != coef.len() {
        return Err(occ.err(
            "COEF_MULT",
            format!("{} nodes, {} DDL and {} COEF_MULT: they must match", nodes.len(), ddl.len(), coef.len()),
        ));
    }
    let terms = nodes.into_iter().zip(ddl).zip(coef).map(|((n, d), c)| (n, d, c)).collect();
    Ok(LoadItem::Relation { terms, value: value(occ, "COEF_IMPO")? })
}

/// The node of `candidates` nearest to `x` (squared distance), Code_Aster's pairing (`pacoap`).
fn nearest(mesh: &Mesh, candidates: &[usize], x: [f64; 3]) -> Option<usize> {
    let d2 = |n: usize| (0..3).map(|k| (mesh.coords[n][k] - x[k]).powi(2)).sum::<f64>();
    candidates.iter().copied().min_by(|&a, &b| d2(a).total_cmp(&d2(b)))
}

/// LIAISON_GROUP: the nodes of side 1 (less SANS_GROUP_NO) each paired with the nearest node of side 2
/// after the translation TRAN (no node of side 2 twice); for each pair
/// `Σ COEF_MULT_1·T(n₁) + Σ COEF_MULT_2·T(n₂) = COEF_IMPO`.
fn liaison_group(mesh: &Mesh, occ: &Args, name: &str) -> Result<Vec<LoadItem>> {
    only_temp(occ, "DDL_1")?;
    only_temp(occ, "DDL_2")?;
    if occ.reals("ANGL_NAUT").iter().any(|v| *v != 0.0) || occ.given("CENTRE") {
        let k = if occ.given("CENTRE") { "CENTRE" } else { "ANGL_NAUT" };
        return Err(occ.err(k, "a rotation between the two sides is not supported yet (TRAN is)"));
    }
    let (c1, c2) = (occ.reals("COEF_MULT_1"), occ.reals("COEF_MULT_2"));
    let (d1, d2) = (occ.texts("DDL_1"), occ.texts("DDL_2"));
    if c1.len() != d1.len() || c2.len() != d2.len() {
        return Err(occ.err("COEF_MULT_1", "as many COEF_MULT_1 (COEF_MULT_2) as DDL_1 (DDL_2) are needed"));
    }
    let side1 = group_nodes(mesh, occ, name, "GROUP_MA_1", "GROUP_NO_1")?;
    let side2 = group_nodes(mesh, occ, name, "GROUP_MA_2", "GROUP_NO_2")?;
    if side1.len() != side2.len() {
        return Err(occ.err(
            "GROUP_MA_1",
            format!("the two sides hold {} and {} nodes: they must hold as many", side1.len(), side2.len()),
        ));
    }
    let t = occ.reals("TRAN");
    let tran = [0, 1, 2].map(|k| t.get(k).copied().unwrap_or(0.0));
    let mut excluded = BTreeSet::new();
    for g in occ.texts("SANS_GROUP_NO") {
        let ns = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err("SANS_GROUP_NO", format!("group of nodes '{g}' is not in mesh {name}")))?;
        excluded.extend(ns.iter().copied());
    }
    let mut taken = vec![false; side2.len()];
    let value = value(occ, "COEF_IMPO")?;
    let mut out = Vec::new();
    for &n1 in &side1 {
        let x = [0, 1, 2].map(|k| mesh.coords[n1][k] + tran[k]);
        let n2 = nearest(mesh, &side2, x).expect("the sides hold as many nodes, at least one");
        let j = side2.binary_search(&n2).expect("a node of side 2");
        if std::mem::replace(&mut taken[j], true) {
            return Err(occ.err(
                "GROUP_MA_2",
                format!("node {} of side 2 is the nearest of two nodes of side 1", mesh.node_names[n2]),
            ));
        }
        if excluded.contains(&n1) || excluded.contains(&n2) || n1 == n2 {
            continue;
        }
        let mut terms: Vec<(usize, String, f64)> = c1.iter().map(|c| (n1, "TEMP".to_string(), *c)).collect();
        terms.extend(c2.iter().map(|c| (n2, "TEMP".to_string(), *c)));
        out.push(LoadItem::Relation { terms, value: value.clone() });
    }
    Ok(out)
}

/// ECHANGE_PAROI between meshed walls: each skin cell of GROUP_MA_1 paired with the nodes of GROUP_MA_2
/// that face its nodes, translated by TRAN (coincident walls without it).
fn wall_exchange(model: &Model, mesh: &Mesh, occ: &Args, name: &str) -> Result<HeatItem> {
    let by_group = |kw: &str| -> Result<Vec<usize>> {
        let mut cells = BTreeSet::new();
        for g in occ.texts(kw) {
            let m = mesh
                .cell_groups
                .get(&g)
                .ok_or_else(|| occ.err(kw, format!("group of cells '{g}' is not in mesh {name}")))?;
            cells.extend(m.iter().copied());
        }
        Ok(cells.into_iter().collect())
    };
    let (g1, g2) = (by_group("GROUP_MA_1")?, by_group("GROUP_MA_2")?);
    let side2: Vec<usize> =
        g2.iter().flat_map(|&c| mesh.cells[c].iter().copied()).collect::<BTreeSet<_>>().into_iter().collect();
    let t = occ.reals("TRAN");
    let tran = [0, 1, 2].map(|k| t.get(k).copied().unwrap_or(0.0));
    let mut pairs = Vec::new();
    for &c in &g1 {
        let skin = model.elements.get(c).and_then(|e| e.as_ref()).is_some_and(|e| e.role == Role::Skin);
        if !skin {
            return Err(occ.err(
                "GROUP_MA_1",
                format!("cell {} carries no boundary (skin) element of the model", mesh.cell_names[c]),
            ));
        }
        let nodes = &mesh.cells[c];
        let size = nodes
            .iter()
            .flat_map(|&a| nodes.iter().map(move |&b| (a, b)))
            .map(|(a, b)| (0..3).map(|k| (mesh.coords[a][k] - mesh.coords[b][k]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let mut facing = Vec::with_capacity(nodes.len());
        for &n in nodes {
            let x = [0, 1, 2].map(|k| mesh.coords[n][k] + tran[k]);
            let m = nearest(mesh, &side2, x)
                .filter(|&m| (0..3).map(|k| (mesh.coords[m][k] - x[k]).powi(2)).sum::<f64>().sqrt() <= 1e-3 * size);
            let Some(m) = m else {
                return Err(occ.err(
                    "GROUP_MA_2",
                    format!("no node of GROUP_MA_2 faces node {} of cell {}", mesh.node_names[n], mesh.cell_names[c]),
                ));
            };
            facing.push(m);
        }
        pairs.push((c, facing));
    }
    if pairs.is_empty() {
        return Err(occ.err("GROUP_MA_1", "no cell to exchange through"));
    }
    Ok(HeatItem::WallExchange { pairs, coef_h: value(occ, "COEF_H")? })
}
