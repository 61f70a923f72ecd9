//! IMPR_RESU FORMAT='MED': a mesh and the node fields of results.

use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::mesh::Mesh;
use crate::stages::Ctx;
use std::fmt::Write as _;
use std::rc::Rc;

use super::{concept_name, selected_fields, selected_steps};
use crate::med;
// ------------------------------------------------------------------ IMPR_RESU
//
// IMPR_RESU FORMAT='MED' writes one mesh and node fields on it. Field names
// follow Code_Aster (`mdnoch` and the Python IMPR_RESU): the result name
// (NOM_RESU_MED, else the concept name), cut to 8 characters and padded to 8
// with '_', then the field name (`RESU____DEPL`); NOM_CHAM_MED names them
// explicitly. A step is written as numdt = NUME_ORDRE at time INST. Like
// Code_Aster, a unit already written in the run is extended (its mesh is
// kept, fields are added), and a field missing at some selected steps or a
// NOM_CMP component missing from a field gives an alarm.

/// What one IMPR_RESU call writes: a mesh and node fields on it.
#[derive(Default)]
struct MedOut {
    mesh: Option<(String, Rc<Mesh>)>,
    fields: Vec<FieldOut>,
    alarms: String,
}

/// One node field to write: its MED name, components and
/// `(numdt, time, values interlaced per node)`.
struct FieldOut {
    med_name: String,
    components: Vec<String>,
    steps: Vec<(i32, f64, Vec<f64>)>,
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
}

/// Code_Aster's MED field name for field `symbol` of a result named `prefix`.
fn med_field_name(prefix: &str, symbol: &str) -> String {
    let short: String = prefix.chars().take(8).collect();
    format!("{short:_<8}{symbol}")
}

fn field_kind(f: &Field) -> &'static str {
    match f {
        Field::Node { .. } => "node (NOEU)",
        Field::Elno { .. } => "ELNO",
        Field::Elga { .. } => "ELGA",
        Field::Elem { .. } => "ELEM",
    }
}

/// Keywords of a RESU occurrence that IMPR_RESU (MED) does not handle yet.
fn refuse_med_keywords(occ: &Args) -> Result<()> {
    if occ.has("CHAM_GD") {
        return Err(occ.err("CHAM_GD", "printing a CHAM_GD to MED is not supported yet (MAILLAGE and RESULTAT are)"));
    }
    for kw in ["GROUP_MA", "GROUP_NO", "MAILLE"] {
        if occ.has(kw) {
            return Err(occ
                .err(kw, format!("{kw}: restricting fields to part of the mesh (MED profiles) is not supported yet")));
        }
    }
    if occ.has("PARTIE") {
        return Err(occ.err("PARTIE", "PARTIE applies to complex fields, which are not supported yet"));
    }
    if occ.has("NOM_PARA") {
        return Err(occ.err("NOM_PARA", "writing result parameters to MED (NOM_PARA) is not supported yet"));
    }
    if occ.has("SOUS_TITRE") {
        return Err(occ.err("SOUS_TITRE", "SOUS_TITRE is not supported yet with FORMAT='MED'"));
    }
    if occ.has("RESULTAT") {
        return Ok(());
    }
    for kw in ["NOM_CMP", "TOUT_CMP"] {
        if occ.has(kw) {
            return Err(occ.err(kw, format!("{kw} applies to fields; this occurrence prints a mesh only")));
        }
    }
    Ok(())
}

/// Collect the node fields of one RESULTAT occurrence.
fn plan_result(out: &mut MedOut, occ: &Args) -> Result<()> {
    let rc = occ.req_concept("RESULTAT")?;
    let rname = concept_name(&rc, "RESULTAT");
    let r = rc.result().map_err(|e| occ.locate(e, "RESULTAT"))?;
    let model = r.model.model().map_err(|e| occ.locate(e, "RESULTAT"))?;
    let mesh = model.mesh_concept.mesh().unwrap_or_else(|_| model.current_mesh());
    if mesh.nnodes() != model.mesh.nnodes() {
        return Err(occ.err("RESULTAT", format!("the mesh of result {rname} changed since its model was made")));
    }
    out.use_mesh(occ, "RESULTAT", concept_name(&model.mesh_concept, "MAILLAGE"), mesh.clone())?;
    let steps = selected_steps(&r, occ, &rname)?;

    // Which fields, under which MED names.
    let (explicit, symbols) = selected_fields(&steps, occ);
    let med_names: Vec<String> = if occ.has("NOM_CHAM_MED") {
        let given = occ.texts("NOM_CHAM_MED");
        if !explicit || given.len() != symbols.len() {
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
            None => rname.clone(),
        };
        symbols.iter().map(|s| med_field_name(&prefix, s)).collect()
    };
    let kw_cham = if explicit { "NOM_CHAM" } else { "RESULTAT" };
    for m in &med_names {
        if m.is_empty() || m.len() > 64 || !m.is_ascii() {
            return Err(occ.err(
                if occ.has("NOM_CHAM_MED") { "NOM_CHAM_MED" } else { kw_cham },
                format!("'{m}' is not a MED field name (1 to 64 ASCII characters)"),
            ));
        }
    }

    let nom_cmp = occ.texts("NOM_CMP");
    let mut cmp_used = vec![false; nom_cmp.len()];
    let mut skipped = Vec::new();
    let nn = mesh.nnodes();
    'fields: for (sym, med_name) in symbols.iter().zip(&med_names) {
        let mut field_comps: Option<&Vec<String>> = None;
        let mut picked: Vec<(usize, String)> = Vec::new();
        let mut out_steps = Vec::new();
        let mut missing = Vec::new();
        for st in &steps {
            let (components, values) = match st.fields.get(sym) {
                None => {
                    missing.push(st.nume_ordre.to_string());
                    continue;
                }
                Some(Field::Node { components, values }) => (components, values),
                Some(other) if explicit => {
                    return Err(occ.err(
                        "NOM_CHAM",
                        format!(
                            "{sym} of result {rname} is an {} field: writing cell fields to MED is not supported yet \
                             (node fields are)",
                            field_kind(other)
                        ),
                    ))
                }
                Some(other) => {
                    skipped.push(format!("{sym} ({})", field_kind(other)));
                    continue 'fields;
                }
            };
            match field_comps {
                None => {
                    field_comps = Some(components);
                    picked = if nom_cmp.is_empty() {
                        components.iter().cloned().enumerate().collect()
                    } else {
                        let mut v = Vec::new();
                        for (j, c) in nom_cmp.iter().enumerate() {
                            if let Some(k) = components.iter().position(|x| x == c) {
                                cmp_used[j] = true;
                                v.push((k, c.clone()));
                            }
                        }
                        v
                    };
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
            let nco = components.len();
            if values.len() != nn * nco {
                return Err(occ.err(
                    kw_cham,
                    format!(
                        "field {sym} of result {rname} at order {}: {} values for {nn} nodes x {nco} components",
                        st.nume_ordre,
                        values.len()
                    ),
                ));
            }
            // As Code_Aster's `ircmpn`: a node carrying any of the components is written with all of them,
            // those it lacks as 0 (the simple field's initial value); a node with none would need a profile.
            let mut v = Vec::with_capacity(nn * picked.len());
            for i in 0..nn {
                if !picked.iter().any(|(k, _)| values[i * nco + k].is_finite()) {
                    return Err(occ.err(
                        kw_cham,
                        format!(
                            "field {sym} of result {rname} at order {}: node {} has none of the components written; \
                             node fields defined on part of the mesh (MED profiles) are not supported yet",
                            st.nume_ordre, mesh.node_names[i]
                        ),
                    ));
                }
                for (k, _) in &picked {
                    let x = values[i * nco + k];
                    v.push(if x.is_finite() { x } else { 0.0 });
                }
            }
            let numdt = i32::try_from(st.nume_ordre)
                .map_err(|_| occ.err(kw_cham, format!("order number {} does not fit in MED", st.nume_ordre)))?;
            out_steps.push((numdt, st.inst, v));
        }
        if out_steps.is_empty() {
            if explicit {
                return Err(occ.err(
                    "NOM_CHAM",
                    format!("result {rname} has no field {sym} at the selected steps (order {})", missing.join(", ")),
                ));
            }
            continue;
        }
        if !missing.is_empty() {
            out.alarm(format!("field {sym} of result {rname} is not computed at order {}", missing.join(", ")));
        }
        out.fields.push(FieldOut {
            med_name: med_name.clone(),
            components: picked.into_iter().map(|(_, c)| c).collect(),
            steps: out_steps,
        });
    }
    for (c, used) in nom_cmp.iter().zip(&cmp_used) {
        if !used {
            return Err(occ.err("NOM_CMP", format!("component {c} is in none of the fields written for {rname}")));
        }
    }
    if !skipped.is_empty() {
        out.alarm(format!(
            "result {rname}: {} not written (cell fields are not supported yet in MED output)",
            skipped.join(", ")
        ));
    }
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
        if let (Some("OUI"), Some((name, mesh))) = (occ.text("INFO_MAILLAGE"), &out.mesh) {
            info.push_str(&mesh.describe(name));
        }
    }
    let Some((mesh_name, mesh)) = out.mesh.take() else {
        return Err(a.err("RESU", "nothing to print: give MAILLAGE or RESULTAT"));
    };
    let unit = a.int("UNITE").unwrap_or(80);
    let path = ctx.io.unit_path(unit, true).map_err(|e| a.locate(e, "UNITE"))?;

    // A unit written earlier in the run is extended, as Code_Aster does.
    let existing = if path.exists() { med::list_meshes(&path).map_err(|e| a.locate(e, "UNITE"))? } else { Vec::new() };
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
        for f in &out.fields {
            let comps: Vec<&str> = f.components.iter().map(String::as_str).collect();
            med::write_node_field(&tmp, &mesh_name, &f.med_name, &comps, &f.steps)?;
        }
        std::fs::rename(&tmp, &path)
            .map_err(|e| Error::io(format!("unit {unit}: cannot move the MED file into place: {e}")))
    };
    if let Err(e) = build() {
        let _ = std::fs::remove_file(&tmp);
        return Err(a.locate(e, "UNITE"));
    }
    let mut mess = info;
    mess.push_str(&out.alarms);
    if !mess.is_empty() {
        ctx.io.mess(&mess);
    }
    Ok(None)
}
