//! IMPR_RESU FORMAT='MED': a mesh and the fields of results and of CHAM_GD.

use super::med_fields::{blocks_of, Selection};
use super::{concept_name, selected_fields, selected_steps};
use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::med::{self, FieldStep, Localization, MedField};
use crate::mesh::Mesh;
use crate::stages::Ctx;
use std::fmt::Write as _;
use std::rc::Rc;
// ------------------------------------------------------------------ IMPR_RESU
//
// IMPR_RESU FORMAT='MED' writes one mesh and fields on it: node fields, and cell fields at the nodes of
// cells (ELNO), at integration points (ELGA, with Code_Aster's localizations) and constant on cells
// (ELEM), on the whole mesh or on the part GROUP_MA / GROUP_NO select (MED profiles). Field names follow
// Code_Aster (`mdnoch` and the Python IMPR_RESU): the result name (NOM_RESU_MED, else the concept
// name), cut to 8 characters and padded to 8 with '_', then the field name (`RESU____DEPL`);
// NOM_CHAM_MED names them explicitly; a CHAM_GD is written under its concept name. A step is written as
// numdt = numit = NUME_ORDRE at time INST (`irchme`). Like Code_Aster, a unit already written in the run
// is extended (its mesh is kept, fields are added), and a field missing at some selected steps or a
// NOM_CMP component missing from a field gives an alarm.

/// What one IMPR_RESU call writes: a mesh and fields on it.
#[derive(Default)]
struct MedOut {
    mesh: Option<(String, Rc<Mesh>)>,
    fields: Vec<MedField>,
    localizations: Vec<Localization>,
    info: String,
    alarms: String,
}

impl MedOut {
    fn alarm(&mut self, msg: String) {
        let _ = writeln!(self.alarms, " <A> IMPR_RESU: {msg}");
    }

    /// The mesh of an occurrence: the first one fixes the file's mesh.
    fn use_mesh(&mut self, occ: &Args, kw: &str, name: String, mesh: Rc<Mesh>) -> Result<()> {
        match &self.mesh {
            None => {
                self.mesh = Some((name, mesh));
                Ok(())
            }
            Some((n, m)) if *n == name && (Rc::ptr_eq(m, &mesh) || m.nnodes() == mesh.nnodes()) => Ok(()),
            Some((n, _)) => Err(occ.err(
                kw,
                format!("this file already gets mesh {n}: several meshes in one MED file are not supported yet"),
            )),
        }
    }

    fn add(&mut self, field: MedField) {
        match self.fields.iter_mut().find(|f| f.name == field.name) {
            Some(f) => f.steps.extend(field.steps),
            None => self.fields.push(field),
        }
    }
}

/// Code_Aster's MED field name for field `symbol` of a result named `prefix`.
fn med_field_name(prefix: &str, symbol: &str) -> String {
    let short: String = prefix.chars().take(8).collect();
    format!("{short:_<8}{symbol}")
}

/// Keywords of a RESU occurrence that IMPR_RESU (MED) does not handle yet.
fn refuse_med_keywords(occ: &Args) -> Result<()> {
    if occ.has("PARTIE") {
        return Err(occ.err("PARTIE", "PARTIE applies to complex fields, which are not supported yet"));
    }
    if occ.has("NOM_PARA") {
        return Err(occ.err("NOM_PARA", "writing result parameters to MED (NOM_PARA) is not supported yet"));
    }
    if occ.has("SOUS_TITRE") {
        return Err(occ.err("SOUS_TITRE", "SOUS_TITRE is not supported yet with FORMAT='MED'"));
    }
    if occ.has("RESULTAT") || occ.has("CHAM_GD") {
        return Ok(());
    }
    for kw in ["NOM_CMP", "TOUT_CMP"] {
        if occ.has(kw) {
            return Err(occ.err(kw, format!("{kw} applies to fields; this occurrence prints a mesh only")));
        }
    }
    Ok(())
}

/// The part of the mesh an occurrence restricts the fields to (GROUP_MA, MAILLE, GROUP_NO; TOUT='OUI'
/// or nothing: all of it).
fn selection(occ: &Args, mesh: &Mesh, mesh_name: &str) -> Result<Selection> {
    let by_cells = occ.has("GROUP_MA") || occ.has("MAILLE");
    let by_nodes = occ.has("GROUP_NO");
    if !by_cells && !by_nodes {
        let _ = occ.text("TOUT");
        return Ok(Selection::all());
    }
    let mut nodes = vec![false; mesh.nnodes()];
    let mut cells = vec![false; mesh.ncells()];
    for n in crate::stages::select::select_nodes(mesh, occ, mesh_name)? {
        nodes[n] = true;
    }
    if by_cells {
        for c in crate::stages::select::select_cells(mesh, occ, mesh_name)? {
            cells[c] = true;
        }
    }
    Ok(Selection { nodes: Some(nodes), cells: Some(cells) })
}

/// The component indices NOM_CMP picks in a field (all without NOM_CMP); marks the names found.
fn picked_components(components: &[String], nom_cmp: &[String], used: &mut [bool]) -> Vec<usize> {
    if nom_cmp.is_empty() {
        return (0..components.len()).collect();
    }
    let mut v = Vec::new();
    for (j, c) in nom_cmp.iter().enumerate() {
        if let Some(k) = components.iter().position(|x| x == c) {
            used[j] = true;
            v.push(k);
        }
    }
    v
}

/// The MED name of each printed field: NOM_CHAM_MED, else the result's prefix and the symbol.
fn med_names(occ: &Args, explicit: bool, symbols: &[String], rname: &str) -> Result<Vec<String>> {
    let names: Vec<String> = if occ.has("NOM_CHAM_MED") {
        let given = occ.texts("NOM_CHAM_MED");
        if occ.has("RESULTAT") && (!explicit || given.len() != symbols.len()) {
            return Err(occ.err(
                "NOM_CHAM_MED",
                format!("give as many NOM_CHAM_MED as NOM_CHAM ({} for {})", given.len(), symbols.len()),
            ));
        }
        given
    } else {
        let prefix = match occ.text("NOM_RESU_MED") {
            Some(p) => {
                if occ.has("NOM_CMP") {
                    return Err(occ.err("NOM_CMP", "NOM_CMP cannot be given with NOM_RESU_MED"));
                }
                if p.is_empty() || p.len() > 8 {
                    return Err(occ.err("NOM_RESU_MED", format!("'{p}' must have 1 to 8 characters")));
                }
                p.to_string()
            }
            None => rname.to_string(),
        };
        symbols.iter().map(|s| med_field_name(&prefix, s)).collect()
    };
    for m in &names {
        if m.is_empty() || m.len() > 64 || !m.is_ascii() {
            let kw = if occ.has("NOM_CHAM_MED") { "NOM_CHAM_MED" } else { "RESULTAT" };
            return Err(occ.err(kw, format!("'{m}' is not a MED field name (1 to 64 ASCII characters)")));
        }
    }
    Ok(names)
}

/// Collect the fields of one RESULTAT occurrence.
fn plan_result(out: &mut MedOut, occ: &Args) -> Result<()> {
    let rc = occ.req_concept("RESULTAT")?;
    let rname = concept_name(&rc, "RESULTAT");
    let r = rc.result().map_err(|e| occ.locate(e, "RESULTAT"))?;
    let model = r.model.model().map_err(|e| occ.locate(e, "RESULTAT"))?;
    let mesh = model.mesh_concept.mesh().unwrap_or_else(|_| model.current_mesh());
    if mesh.nnodes() != model.mesh.nnodes() {
        return Err(occ.err("RESULTAT", format!("the mesh of result {rname} changed since its model was made")));
    }
    let mesh_name = concept_name(&model.mesh_concept, "MAILLAGE");
    out.use_mesh(occ, "RESULTAT", mesh_name.clone(), mesh.clone())?;
    let sel = selection(occ, &mesh, &mesh_name)?;
    let steps = selected_steps(&r, occ, &rname)?;
    let (explicit, symbols) = selected_fields(&steps, occ);
    let names = med_names(occ, explicit, &symbols, &rname)?;
    let kw_cham = if explicit { "NOM_CHAM" } else { "RESULTAT" };
    let nom_cmp = occ.texts("NOM_CMP");
    let mut cmp_used = vec![false; nom_cmp.len()];
    'fields: for (sym, med_name) in symbols.iter().zip(&names) {
        let mut comps: Option<&Vec<String>> = None;
        let mut picked: Vec<usize> = Vec::new();
        let mut out_steps = Vec::new();
        let mut missing = Vec::new();
        let mut outside = Vec::new();
        for st in &steps {
            let Some(field) = st.fields.get(sym) else {
                missing.push(st.nume_ordre.to_string());
                continue;
            };
            let components = match field {
                Field::Node { components, .. }
                | Field::Elno { components, .. }
                | Field::Elga { components, .. }
                | Field::Elem { components, .. } => components,
            };
            match comps {
                None => {
                    comps = Some(components);
                    picked = picked_components(components, &nom_cmp, &mut cmp_used);
                    if picked.is_empty() {
                        out.alarm(format!(
                            "field {sym} of result {rname} has none of the components {} (it has {}): not written",
                            nom_cmp.join(" "),
                            components.join(" ")
                        ));
                        continue 'fields;
                    }
                }
                Some(first) if first != components => {
                    return Err(occ.err(
                        kw_cham,
                        format!(
                            "field {sym} of result {rname} has components [{}] at order {} but [{}] before",
                            components.join(" "),
                            st.nume_ordre,
                            first.join(" ")
                        ),
                    ))
                }
                Some(_) => {}
            }
            let blocks = blocks_of(field, &mesh, Some(&model), &picked, &sel, &mut out.localizations).map_err(|e| {
                occ.err(kw_cham, format!("field {sym} of result {rname} at order {}: {e}", st.nume_ordre))
            })?;
            if blocks.is_empty() {
                outside.push(st.nume_ordre.to_string());
                continue;
            }
            let numdt = i32::try_from(st.nume_ordre)
                .map_err(|_| occ.err(kw_cham, format!("order number {} does not fit in MED", st.nume_ordre)))?;
            out_steps.push(FieldStep { numdt, numit: numdt, time: st.inst, blocks });
        }
        if !outside.is_empty() {
            out.alarm(format!(
                "field {sym} of result {rname} has no value on the selected part of the mesh at order {}: not written \
                 there",
                outside.join(", ")
            ));
        }
        if out_steps.is_empty() {
            if explicit && outside.is_empty() {
                let has: Vec<String> =
                    r.steps.iter().filter(|s| s.fields.contains_key(sym)).map(|s| s.nume_ordre.to_string()).collect();
                if has.is_empty() {
                    return Err(occ.err("NOM_CHAM", format!("result {rname} has no field {sym} at any order")));
                }
                let kw = ["NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST"]
                    .into_iter()
                    .find(|k| occ.has_if_declared(k))
                    .unwrap_or("NOM_CHAM");
                return Err(occ.err(
                    kw,
                    format!(
                        "result {rname} has no field {sym} at the selected order(s) {} (it has it at order(s) {})",
                        missing.join(", "),
                        has.join(", ")
                    ),
                ));
            }
            continue;
        }
        if !missing.is_empty() {
            out.alarm(format!("field {sym} of result {rname} is not written at order {}", missing.join(", ")));
        }
        out.add(MedField {
            name: med_name.clone(),
            mesh_name: mesh_name.clone(),
            components: picked.iter().map(|&k| comps.expect("set with picked")[k].clone()).collect(),
            steps: out_steps,
        });
    }
    for (c, used) in nom_cmp.iter().zip(&cmp_used) {
        if !used {
            return Err(occ.err("NOM_CMP", format!("component {c} is in none of the fields written for {rname}")));
        }
    }
    // IMPR_NOM_VARI='OUI' (the default): Code_Aster adds VARI_ELGA_NOMME, the internal variables under the
    // names of the behaviour's variables, which our results do not know: said, not written.
    if occ.text("IMPR_NOM_VARI") == Some("OUI") && symbols.iter().any(|s| s == "VARI_ELGA") {
        out.info.push_str(&format!(
            " IMPR_RESU: VARI_ELGA of {rname} is written with components V1, V2, ...; VARI_ELGA_NOMME (the \
             variables under their names) is not written\n"
        ));
    }
    Ok(())
}

/// Collect the field of one CHAM_GD occurrence (a cham_no or cham_elem), written without step
/// (numdt = numit = -1) under NOM_CHAM_MED or its concept name.
fn plan_field(out: &mut MedOut, occ: &Args) -> Result<()> {
    let fc = occ.req_concept("CHAM_GD")?;
    let fname = concept_name(&fc, "CHAM_GD");
    let f = fc.field().map_err(|e| occ.locate(e, "CHAM_GD"))?;
    if f.functions.is_some() {
        return Err(occ.err("CHAM_GD", format!("{fname} is a field of functions: only fields of reals are written")));
    }
    let mesh = f.mesh_concept.mesh().map_err(|e| occ.locate(e, "CHAM_GD"))?;
    let mesh_name = concept_name(&f.mesh_concept, "MAILLAGE");
    out.use_mesh(occ, "CHAM_GD", mesh_name.clone(), mesh.clone())?;
    let sel = selection(occ, &mesh, &mesh_name)?;
    let names = med_names(occ, true, std::slice::from_ref(&fname), &fname)?;
    let name = if occ.has("NOM_CHAM_MED") { names[0].clone() } else { fname.clone() };
    let nom_cmp = occ.texts("NOM_CMP");
    let mut used = vec![false; nom_cmp.len()];
    let picked = picked_components(f.field.components(), &nom_cmp, &mut used);
    if let Some((c, _)) = nom_cmp.iter().zip(&used).find(|(_, u)| !**u) {
        return Err(occ.err("NOM_CMP", format!("field {fname} has no component {c}")));
    }
    let blocks = blocks_of(&f.field, &mesh, None, &picked, &sel, &mut out.localizations)
        .map_err(|e| occ.err("CHAM_GD", format!("field {fname}: {e}")))?;
    if blocks.is_empty() {
        out.alarm(format!("field {fname} has no value on the selected part of the mesh: not written"));
        return Ok(());
    }
    out.add(MedField {
        name,
        mesh_name,
        components: picked.iter().map(|&k| f.field.components()[k].clone()).collect(),
        steps: vec![FieldStep { numdt: -1, numit: -1, time: 0.0, blocks }],
    });
    Ok(())
}

/// IMPR_RESU FORMAT='MED'.
pub fn impr_resu_med(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mut out = MedOut::default();
    if let Some(v) = a.text("VERSION_MED").filter(|_| a.given("VERSION_MED")) {
        if v != "4.1.0" {
            out.alarm(format!("VERSION_MED='{v}': the file is written as MED 4.1.0"));
        }
    }
    let mut info = String::new();
    for occ in a.facts("RESU") {
        refuse_med_keywords(occ)?;
        if let Some(c) = occ.concept("MAILLAGE") {
            let mesh = c.mesh().map_err(|e| occ.locate(e, "MAILLAGE"))?;
            out.use_mesh(occ, "MAILLAGE", concept_name(&c, "MAILLAGE"), mesh)?;
        }
        if occ.has("RESULTAT") {
            plan_result(&mut out, occ)?;
        }
        if occ.has("CHAM_GD") {
            plan_field(&mut out, occ)?;
        }
        if let (Some("OUI"), Some((name, mesh))) = (occ.text("INFO_MAILLAGE"), &out.mesh) {
            info.push_str(&mesh.describe(name));
        }
    }
    let Some((mesh_name, mesh)) = out.mesh.take() else {
        return Err(a.err("RESU", "nothing to print: give MAILLAGE, RESULTAT or CHAM_GD"));
    };
    let unit = a.int("UNITE").unwrap_or(80);
    let path = ctx.io.unit_path(unit, true).map_err(|e| a.locate(e, "UNITE"))?;

    // A unit written earlier in the run is extended, as Code_Aster does; an empty file (DEFI_FICHIER's, or
    // a unit opened and never written) is a new one.
    let written = std::fs::metadata(&path).is_ok_and(|m| m.len() > 0);
    let existing = if written { med::list_meshes(&path).map_err(|e| a.locate(e, "UNITE"))? } else { Vec::new() };
    let reuse_mesh = existing.contains(&mesh_name);
    if !existing.is_empty() && !reuse_mesh {
        return Err(a.err(
            "UNITE",
            format!(
                "unit {unit} already holds mesh {}: adding mesh {mesh_name} (several meshes in one MED file) is \
                 not supported yet",
                existing.join(", ")
            ),
        ));
    }
    if reuse_mesh {
        let there = med::read_mesh(&path, Some(&mesh_name)).map_err(|e| a.locate(e, "UNITE"))?;
        if there.nnodes() != mesh.nnodes() || there.ncells() != mesh.ncells() {
            return Err(a.err(
                "UNITE",
                format!("unit {unit} already holds another mesh named {mesh_name} ({} nodes)", there.nnodes()),
            ));
        }
        let _ = writeln!(info, " IMPR_RESU: mesh {mesh_name} is already in unit {unit}: the fields are added to it");
    }

    // Build the whole file beside the unit, then rename it into place.
    let tmp = med::temp_path(&path);
    let build = || -> Result<()> {
        if reuse_mesh {
            std::fs::copy(&path, &tmp)
                .map_err(|e| Error::io(format!("unit {unit}: cannot copy {}: {e}", path.display())))?;
        } else {
            med::write_mesh(&tmp, &mesh, &mesh_name)?;
        }
        if !out.fields.is_empty() {
            med::write_fields(&tmp, &out.fields, &out.localizations)?;
        }
        std::fs::rename(&tmp, &path)
            .map_err(|e| Error::io(format!("unit {unit}: cannot move the MED file into place: {e}")))
    };
    if let Err(e) = build() {
        let _ = std::fs::remove_file(&tmp);
        return Err(a.locate(e, "UNITE"));
    }
    let mut mess = info;
    mess.push_str(&out.info);
    mess.push_str(&out.alarms);
    if !mess.is_empty() {
        ctx.io.mess(&mess);
    }
    Ok(None)
}
