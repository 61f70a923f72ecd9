//! AFFE_CHAR_MECA and AFFE_CHAR_MECA_F: mechanical loads on a model, mesh entities resolved and checked
//! (AFFE_CHAR_THER(_F), the thermal ones, in `thermal`); AFFE_CHAR_CINE(_F): prescribed unknowns;
//! DEFI_CONTACT: the cohesive zones of an X-FEM model.

use crate::catalog::args::{Args, Val};
use crate::concepts::model::{Load, LoadItem, LoadValue};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::mesh::Mesh;
use crate::stages::select::{select_cells, select_nodes};
use crate::stages::Ctx;
use crate::xfem::model::ContactKind;
use std::collections::HashMap;
use std::rc::Rc;

use crate::fem::geometry;

pub mod thermal;

// ------------------------------------------------------------------ AFFE_CHAR_MECA(_F)

/// Load keywords we implement; any other factor keyword given is refused.
const LOAD_KEYWORDS: &[&str] = &[
    "DDL_IMPO",
    "FACE_IMPO",
    "FORCE_NODALE",
    "FORCE_CONTOUR",
    "FORCE_FACE",
    "PRES_REP",
    "PESANTEUR",
    "LIAISON_DDL",
    "FLUX_THM_REP",
];
const PLAIN_KEYWORDS: &[&str] = &["MODELE", "INFO", "VERI_AFFE", "VERI_NORM", "DOUBLE_LAGRANGE", "CHAM_MATER"];
/// Keywords of DDL_IMPO / FORCE_* that select entities rather than give values.
const SELECTORS: &[&str] = &["TOUT", "NOEUD", "GROUP_NO", "GROUP_MA", "MAILLE", "SANS_GROUP_MA", "SANS_GROUP_NO"];

fn load_value(v: &Val) -> Option<LoadValue> {
    match v {
        Val::R(r) => Some(LoadValue::Real(*r)),
        Val::I(i) => Some(LoadValue::Real(*i as f64)),
        Val::Concept(c) => Some(LoadValue::Func(c.clone())),
        _ => None,
    }
}

/// The (component, value) pairs written in an occurrence, in schema order.
fn components(occ: &Args, skip: &[&str]) -> Vec<(String, LoadValue)> {
    occ.items
        .iter()
        .filter(|i| !SELECTORS.contains(&i.name.as_str()) && !skip.contains(&i.name.as_str()) && !i.defaulted)
        .filter_map(|i| occ.val(&i.name).and_then(load_value).map(|v| (i.name.clone(), v)))
        .collect()
}

fn affe_char(a: &Args, functional: bool) -> Result<Option<ConceptData>> {
    for item in &a.items {
        let n = item.name.as_str();
        if !item.defaulted && !LOAD_KEYWORDS.contains(&n) && !PLAIN_KEYWORDS.contains(&n) {
            return Err(a.err(n, "not supported yet"));
        }
    }
    // VERI_NORM='NON' turns off Code_Aster's check of the skins' normals, which we do not make; an
    // explicit 'OUI' asks for that check and stays refused by name (unread).
    if let Some(v) = a.items.iter().find(|i| i.name == "VERI_NORM" && !i.defaulted) {
        v.read.set(a.text("VERI_NORM") == Some("NON"));
    }
    let mo = a.req_concept("MODELE")?;
    let (mesh, name) = {
        let m = mo.model()?;
        (m.current_mesh(), m.mesh_concept.label())
    };
    let mut items = Vec::new();
    for occ in a.facts("DDL_IMPO") {
        if occ.given("BLOCAGE") {
            return Err(occ.err("BLOCAGE", "not supported yet"));
        }
        let mut comps = components(occ, &["LIAISON"]);
        // LIAISON='ENCASTRE' clamps the nodes: every displacement component of the model is zero.
        match occ.text("LIAISON") {
            None => {}
            Some("ENCASTRE") => {
                for c in &["DX", "DY", "DZ"][..mo_dim(&mo)?] {
                    if !comps.iter().any(|(k, _)| k == c) {
                        comps.push((c.to_string(), LoadValue::Real(0.0)));
                    }
                }
            }
            Some(l) => return Err(occ.err("LIAISON", format!("LIAISON='{l}' is not supported yet (ENCASTRE is)"))),
        }
        if comps.is_empty() {
            return Err(occ.err("DDL_IMPO", "no component is prescribed"));
        }
        for node in select_nodes(&mesh, occ, &name)? {
            for (c, v) in &comps {
                items.push(LoadItem::Dof { node, component: c.clone(), value: v.clone() });
            }
        }
    }
    for occ in a.facts("FACE_IMPO") {
        items.extend(face_impo(&mesh, occ, &name, mo_dim(&mo)?, functional)?);
    }
    for occ in a.facts("FORCE_NODALE") {
        let comps = components(occ, &[]);
        for node in select_nodes(&mesh, occ, &name)? {
            for (c, v) in &comps {
                items.push(LoadItem::NodalForce { node, component: c.clone(), value: v.clone() });
            }
        }
    }
    for kw in ["FORCE_CONTOUR", "FORCE_FACE"] {
        for occ in a.facts(kw) {
            let cells = select_cells(&mesh, occ, &name)?;
            let comps = components(occ, &[]);
            if comps.iter().any(|(c, _)| !matches!(c.as_str(), "FX" | "FY" | "FZ")) {
                let bad: Vec<&str> =
                    comps.iter().map(|(c, _)| c.as_str()).filter(|c| !matches!(*c, "FX" | "FY" | "FZ")).collect();
                return Err(occ.err(bad[0], "not supported yet"));
            }
            items.push(LoadItem::SurfaceForce { cells, components: comps });
        }
    }
    for occ in a.facts("PRES_REP") {
        if occ.given("FISSURE") {
            if occ.given("CISA_2D") {
                return Err(
                    occ.err("CISA_2D", "a shear on the lips of a crack (CISA_2D with FISSURE) is not supported yet")
                );
            }
            // The lips of X-FEM cracks of the model: PRES pushes them apart.
            let value = occ.val("PRES").and_then(load_value).ok_or_else(|| occ.err("PRES", "PRES is required"))?;
            let xm = mo.model()?.xfem.clone();
            for fc in occ.concepts("FISSURE") {
                let crack = fc.crack().map_err(|e| occ.locate(e, "FISSURE"))?;
                let index = xm.as_ref().and_then(|xm| xm.cracks.iter().position(|k| Rc::ptr_eq(k, &crack)));
                let Some(index) = index else {
                    return Err(occ.err(
                        "FISSURE",
                        format!("{} is not a crack of model {} (MODI_MODELE_XFEM)", fc.label(), mo.label()),
                    ));
                };
                items.push(LoadItem::CrackPressure { crack: index, name: fc.label(), value: value.clone() });
            }
            continue;
        }
        let cells = select_cells(&mesh, occ, &name)?;
        let shear = occ.val("CISA_2D").and_then(load_value);
        if shear.is_some() && mo_dim(&mo)? != 2 {
            return Err(occ.err("CISA_2D", "CISA_2D is for plane models"));
        }
        let value = match (occ.val("PRES").and_then(load_value), &shear) {
            (Some(v), _) => v,
            (None, Some(_)) => LoadValue::Real(0.0),
            (None, None) => return Err(occ.err("PRES", "PRES or CISA_2D is required")),
        };
        items.push(LoadItem::Pressure { cells, value, shear });
    }
    for occ in a.facts("FLUX_THM_REP") {
        // FLUN_HYDR2 is the flux of a second fluid: it has no equation in a saturated (T)HM model. FLUN, the
        // heat flux, acts on the temperature of a THM model (the model refuses it otherwise).
        for k in ["FLUN_HYDR2", "FLUN_FRAC"] {
            if occ.declares(k) && occ.given(k) {
                return Err(occ.err(k, "not supported yet (FLUN_HYDR1, the flux of the liquid, and FLUN are)"));
            }
        }
        let hydr = occ.val("FLUN_HYDR1").and_then(load_value);
        let heat = if occ.declares("FLUN") && occ.given("FLUN") { occ.val("FLUN").and_then(load_value) } else { None };
        if hydr.is_none() && heat.is_none() {
            return Err(occ.err("FLUN_HYDR1", "FLUN_HYDR1 or FLUN is required"));
        }
        let cells = if occ.has("TOUT") { (0..mesh.cells.len()).collect() } else { select_cells(&mesh, occ, &name)? };
        if let Some(value) = hydr {
            items.push(LoadItem::FluxThm { cells: cells.clone(), value, heat: false });
        }
        if let Some(value) = heat {
            items.push(LoadItem::FluxThm { cells, value, heat: true });
        }
    }
    if let Some(occ) = a.declares("PESANTEUR").then(|| a.fact("PESANTEUR")).flatten() {
        let d = occ.reals("DIRECTION");
        let cells = if occ.has("GROUP_MA") { Some(select_cells(&mesh, occ, &name)?) } else { None };
        items.push(LoadItem::Gravity { g: occ.req_real("GRAVITE")?, direction: [d[0], d[1], d[2]], cells });
    }
    for occ in a.facts("LIAISON_DDL") {
        let mut nodes = Vec::new();
        let index: HashMap<&str, usize> = mesh.node_names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        for n in occ.texts("NOEUD") {
            nodes.push(
                *index.get(n.as_str()).ok_or_else(|| occ.err("NOEUD", format!("node '{n}' is not in mesh {name}")))?,
            );
        }
        nodes.extend(single_nodes(&mesh, occ, &name)?);
        let ddl = occ.texts("DDL");
        let coef = occ.reals("COEF_MULT");
        if nodes.len() != ddl.len() || ddl.len() != coef.len() {
            return Err(occ.err(
                "COEF_MULT",
                format!("{} nodes, {} DDL and {} COEF_MULT: they must match", nodes.len(), ddl.len(), coef.len()),
            ));
        }
        let value =
            occ.val("COEF_IMPO").and_then(load_value).ok_or_else(|| occ.err("COEF_IMPO", "COEF_IMPO is required"))?;
        let terms = nodes.into_iter().zip(ddl).zip(coef).map(|((n, d), c)| (n, d, c)).collect();
        items.push(LoadItem::Relation { terms, value });
    }
    Ok(Some(ConceptData::Load(Load { model: mo, items: surcharge(items), functional })))
}

/// Code_Aster's rule of overloading within one load: a component of a node prescribed by several
/// occurrences (DDL_IMPO, FACE_IMPO, TEMP_IMPO, ...) takes the value of the last one, as its field of
/// prescribed values does (a later `nocart` overwrites an earlier one).
pub fn surcharge(items: Vec<LoadItem>) -> Vec<LoadItem> {
    let mut seen = std::collections::HashSet::new();
    let mut kept: Vec<LoadItem> = items
        .into_iter()
        .rev()
        .filter(|i| match i {
            LoadItem::Dof { node, component, .. } => seen.insert((*node, component.clone())),
            _ => true,
        })
        .collect();
    kept.reverse();
    kept
}

/// The node of each group of GROUP_NO, in order (LIAISON_DDL: one node per group).
fn single_nodes(mesh: &Mesh, occ: &Args, name: &str) -> Result<Vec<usize>> {
    let mut nodes = Vec::new();
    for g in occ.texts("GROUP_NO") {
        let m = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err("GROUP_NO", format!("group of nodes '{g}' is not in mesh {name}")))?;
        if m.len() != 1 {
            return Err(occ.err(
                "GROUP_NO",
                format!("group '{g}' holds {} nodes; LIAISON_DDL needs one node per group", m.len()),
            ));
        }
        nodes.push(m[0]);
    }
    Ok(nodes)
}

fn mo_dim(mo: &ConceptRef) -> Result<usize> {
    Ok(mo.model()?.dim())
}

/// FACE_IMPO: DX / DY / DZ on the nodes of the cells (less those of
/// SANS_GROUP_MA and SANS_GROUP_NO), or DNOR: at each of those nodes
/// `u · n = value`, with `n` the mean of the unit normals of the cells at the
/// node (Code_Aster's `canort`), each cell's normal turned out of the cell
/// it bounds where there is one on a single side; or, in 2D, DTAN: `u · t = value` along the mean
/// tangent `t` of the segments at the node, each taken along its own node order (`n = (t_y, −t_x)`).
fn face_impo(mesh: &Mesh, occ: &Args, name: &str, dim: usize, functional: bool) -> Result<Vec<LoadItem>> {
    for k in ["DRX", "DRY", "DRZ", "DRNOR", "GRX", "PRES", "PHI", "TEMP", "PRE1", "PRE2"] {
        if occ.given(k) {
            return Err(occ.err(k, "not supported yet"));
        }
    }
    let mut cells = Vec::new();
    for g in occ.texts("GROUP_MA") {
        let members = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err("GROUP_MA", format!("group of cells '{g}' is not in mesh {name}")))?;
        cells.extend(members.iter().copied());
    }
    cells.sort_unstable();
    cells.dedup();
    let mut excluded: std::collections::HashSet<usize> = std::collections::HashSet::new();
    for g in occ.texts("SANS_GROUP_MA") {
        let members = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err("SANS_GROUP_MA", format!("group of cells '{g}' is not in mesh {name}")))?;
        excluded.extend(members.iter().flat_map(|&c| mesh.cells[c].iter().copied()));
    }
    for g in occ.texts("SANS_GROUP_NO") {
        let members = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err("SANS_GROUP_NO", format!("group of nodes '{g}' is not in mesh {name}")))?;
        excluded.extend(members.iter().copied());
    }
    let mut nodes: Vec<usize> = cells.iter().flat_map(|&c| mesh.cells[c].iter().copied()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes.retain(|n| !excluded.contains(n));
    let mut items = Vec::new();
    if occ.given("DTAN") && dim != 2 {
        return Err(occ.err("DTAN", "DTAN is for plane models (in 3D the tangent plane has two directions)"));
    }
    let along: Vec<&str> = ["DNOR", "DTAN"].into_iter().filter(|k| occ.given(k)).collect();
    if !along.is_empty() {
        let mut values = Vec::new();
        for k in &along {
            let value = occ.val(k).and_then(load_value).ok_or_else(|| occ.err(k, "a value is required"))?;
            if functional || matches!(value, LoadValue::Func(_)) {
                return Err(occ.err(k, format!("{k} given by a function is not supported yet")));
            }
            values.push((*k, value));
        }
        for &c in &cells {
            let t = mesh.cell_types[c];
            if !geometry::is_skin_type(t) || t.dim() + 1 != dim {
                return Err(occ.err(
                    "GROUP_MA",
                    format!(
                        "{}: cell {} is a {}; the normal is taken on {} of a {dim}D model",
                        along[0],
                        mesh.cell_names[c],
                        t.name(),
                        if dim == 2 { "segments (SEG2, SEG3)" } else { "faces (TRIA3/6, QUAD4/8/9)" }
                    ),
                ));
            }
        }
        // DNOR's normals are turned out of the cells they bound; DTAN's tangent runs along each segment's
        // own orientation (Code_Aster's canort): from the normals of the segments as they are, unturned.
        let signs: Vec<f64> = if occ.given("DNOR") {
            let node_cells = geometry::node_to_cells(mesh);
            cells.iter().map(|&c| geometry::outward_sign(mesh, &node_cells, c).unwrap_or(1.0)).collect()
        } else {
            Vec::new()
        };
        let node_normals =
            |signs: &[f64]| geometry::averaged_node_normals(mesh, &cells, signs).map_err(|e| occ.err("GROUP_MA", e));
        let normals = if occ.given("DNOR") { node_normals(&signs)? } else { Default::default() };
        let raw = if occ.given("DTAN") { node_normals(&vec![1.0; cells.len()])? } else { Default::default() };
        for node in nodes {
            for (k, value) in &values {
                let d = if *k == "DNOR" {
                    normals[&node]
                } else {
                    let n = raw[&node];
                    [-n[1], n[0], 0.0]
                };
                let terms =
                    ["DX", "DY", "DZ"][..dim].iter().enumerate().map(|(i, c)| (node, c.to_string(), d[i])).collect();
                items.push(LoadItem::Relation { terms, value: value.clone() });
            }
        }
        return Ok(items);
    }
    let comps = components(occ, &[]);
    if comps.is_empty() {
        return Err(occ.err("GROUP_MA", "no component is prescribed"));
    }
    for node in nodes {
        for (c, v) in &comps {
            items.push(LoadItem::Dof { node, component: c.clone(), value: v.clone() });
        }
    }
    Ok(items)
}

// ------------------------------------------------------------------ AFFE_CHAR_CINE(_F)

pub fn affe_char_cine(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    char_cine(a, false)
}

pub fn affe_char_cine_f(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    char_cine(a, true)
}

/// Kinematic loads: the values of MECA_IMPO / THER_IMPO prescribed on the nodes they select. Code_Aster
/// eliminates them from the system where AFFE_CHAR_MECA's DDL_IMPO adds multipliers; the solution is the
/// same, and we eliminate both.
fn char_cine(a: &Args, functional: bool) -> Result<Option<ConceptData>> {
    a.refuse(&["ACOU_IMPO", "EVOL_IMPO"])?;
    let _ = a.int("INFO");
    let mo = a.req_concept("MODELE")?;
    let (mesh, name, thermal) = {
        let m = mo.model()?;
        (m.current_mesh(), m.mesh_concept.label(), m.is_thermal())
    };
    let mut items = Vec::new();
    for (kw, wants_thermal) in [("MECA_IMPO", false), ("THER_IMPO", true)] {
        for occ in a.facts(kw) {
            if thermal != wants_thermal {
                let what = if thermal { "a thermal model" } else { "a mechanical model" };
                return Err(a.err(kw, format!("{} is {what}", mo.label())));
            }
            occ.refuse(&["TEMP_INF", "TEMP_SUP", "TEMP_MIL"])?;
            let comps = components(occ, &[]);
            for node in select_nodes(&mesh, occ, &name)? {
                for (c, v) in &comps {
                    items.push(LoadItem::Dof { node, component: c.clone(), value: v.clone() });
                }
            }
        }
    }
    Ok(Some(ConceptData::Load(Load { model: mo, items: surcharge(items), functional })))
}

pub fn affe_char_meca(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    affe_char(a, false)
}

pub fn affe_char_meca_f(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    affe_char(a, true)
}

// ------------------------------------------------------------------ DEFI_CONTACT

/// DEFI_CONTACT FORMULATION='XFEM' with cohesive zones (ALGO_CONT='CZM',
/// RELATION='CZM_LIN_MIX', ALGO_LAGR='VERSION2', INTEGRATION='GAUSS') on an
/// X-FEM model with CONTACT='MORTAR'. Every other formulation or option
/// stops by name.
pub fn defi_contact(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let form = a.text("FORMULATION").unwrap_or("DISCRETE");
    if form != "XFEM" {
        return Err(a.err("FORMULATION", format!("FORMULATION='{form}' is not supported yet (only 'XFEM')")));
    }
    if a.text("FROTTEMENT").is_some_and(|f| f != "SANS") {
        return Err(a.err("FROTTEMENT", "friction is not supported yet"));
    }
    for kw in ["REAC_GEOM", "ELIM_ARETE", "ITER_CONT_TYPE"] {
        let given = a.items.iter().any(|i| i.name == kw && !i.defaulted);
        if given {
            let ok = match kw {
                "REAC_GEOM" => a.text(kw) == Some("SANS"),
                "ELIM_ARETE" => a.text(kw) == Some("DUAL"),
                _ => a.text(kw) == Some("MAXI"),
            };
            if !ok {
                return Err(a.err(kw, "not supported yet with the cohesive X-FEM zones"));
            }
        }
    }
    let mo = a.req_concept("MODELE")?;
    let cracks = {
        let m = mo.model()?;
        let Some(xm) = &m.xfem else {
            return Err(a.err("MODELE", format!("{} is not an X-FEM model (MODI_MODELE_XFEM)", mo.label())));
        };
        if xm.contact != ContactKind::Mortar {
            return Err(a.err(
                "MODELE",
                format!(
                    "{}: CONTACT='{}' in MODI_MODELE_XFEM; the cohesive zones need CONTACT='MORTAR'",
                    mo.label(),
                    xm.contact.name()
                ),
            ));
        }
        xm.cracks.clone()
    };
    let mut zones = Vec::new();
    for occ in a.facts("ZONE") {
        let algo = occ.text("ALGO_CONT").unwrap_or("STANDARD");
        if algo != "CZM" {
            return Err(occ.err("ALGO_CONT", format!("ALGO_CONT='{algo}' is not supported yet (only 'CZM')")));
        }
        let rel = occ.req_text("RELATION")?;
        if rel != "CZM_LIN_MIX" {
            return Err(occ.err("RELATION", format!("RELATION='{rel}' is not supported yet (only 'CZM_LIN_MIX')")));
        }
        let lagr = occ.text("ALGO_LAGR").unwrap_or("AUTO");
        if !matches!(lagr, "VERSION2" | "AUTO") {
            return Err(occ.err("ALGO_LAGR", format!("ALGO_LAGR='{lagr}' is not supported yet (only 'VERSION2')")));
        }
        let integ = occ.text("INTEGRATION").unwrap_or("GAUSS");
        if integ != "GAUSS" {
            return Err(occ.err("INTEGRATION", format!("INTEGRATION='{integ}' is not supported yet (only 'GAUSS')")));
        }
        if occ.items.iter().any(|i| i.name == "TOLE_PROJ_EXT" && !i.defaulted) {
            return Err(occ.err("TOLE_PROJ_EXT", "not supported yet"));
        }
        let fc = occ.req_concept("FISS_MAIT")?;
        let crack = fc.crack().map_err(|e| occ.locate(e, "FISS_MAIT"))?;
        if !cracks.iter().any(|k| Rc::ptr_eq(k, &crack)) {
            return Err(occ.err("FISS_MAIT", format!("{} is not a crack of model {}", fc.label(), mo.label())));
        }
        zones.push(crate::concepts::model::ContactZone {
            crack,
            crack_name: fc.label(),
            order: occ.int("ORDRE_INT").unwrap_or(6),
            relation: rel.to_string(),
        });
    }
    let iter_cont_maxi = a.int("ITER_CONT_MAXI").unwrap_or(30);
    Ok(Some(ConceptData::Contact(crate::concepts::model::Contact { model: mo, zones, iter_cont_maxi })))
}
