//! LIRE_RESU and LIRE_CHAMP (FORMAT='MED'): fields of a MED file — written by Code_Aster or by IMPR_RESU —
//! back into a result or a field concept.
//!
//! As Code_Aster reads them (`lrfmed`, `lrchme`): a field is found by its MED name (NOM_CHAM_MED, or
//! NOM_RESU cut to 8 characters and padded with '_' then NOM_CHAM); a step's order number is its
//! `numit`, else its `numdt`; INST picks the step at that time (CRITERE, PRECISION) and numbers the
//! steps read from 1; cells are matched type by type in the order of the mesh (the order the MED mesh
//! writer and reader keep), so the file's mesh must have as many nodes and cells of each type as the
//! mesh given. Values at the nodes of cells come back in Code_Aster's node order; values at
//! integration points in the order of the localization's points, which must be as many as the points
//! of the cell's element when a model is given.

use super::list_of;
use crate::catalog::args::Args;
use crate::concepts::model::Model;
use crate::concepts::result::{Field, FieldData, ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::med::{self, cellfield::cells_by_type, Block, MedField, Support};
use crate::mesh::Mesh;
use crate::stages::core::hm::elga_points;
use crate::stages::core::stored::{bare_model, excit_loads, Location as Kind};
use crate::stages::Ctx;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Does block `b` of a MED field hold values of this kind of field?
fn fits(kind: Kind, b: &Block) -> bool {
    match kind {
        Kind::Node => b.support == Support::Node,
        Kind::Elno => b.support == Support::CellNode,
        Kind::Elga => b.support == Support::Cell && b.localization.is_some(),
        Kind::Elem => b.support == Support::Cell && b.localization.is_none() && b.per_entity == 1,
    }
}

/// Where the values of the file go on our mesh.
struct Target<'a> {
    mesh: &'a Mesh,
    model: Option<&'a Model>,
    by_type: BTreeMap<crate::mesh::CellType, Vec<usize>>,
}

impl<'a> Target<'a> {
    fn new(mesh: &'a Mesh, model: Option<&'a Model>) -> Self {
        Target { mesh, model, by_type: cells_by_type(mesh) }
    }

    /// Check that the file's mesh has the entities of ours: as many nodes, and cells of each type.
    fn check_file_mesh(&self, path: &std::path::Path, med_mesh: &str) -> std::result::Result<(), String> {
        let (nn, cells) = med::cellfield::mesh_entity_counts(path, med_mesh).map_err(|e| e.msg)?;
        if nn != self.mesh.nnodes() {
            return Err(format!(
                "the field's mesh '{med_mesh}' in the file has {nn} nodes, the mesh given has {}",
                self.mesh.nnodes()
            ));
        }
        for (t, members) in &self.by_type {
            let there = cells.get(t).copied().unwrap_or(0);
            if there != members.len() {
                return Err(format!(
                    "the field's mesh '{med_mesh}' in the file has {there} {} cells, the mesh given has {}",
                    t.name(),
                    members.len()
                ));
            }
        }
        Ok(())
    }

    /// The field of our mesh made of the blocks of one step (components `ncmp`): node values NaN where
    /// the file has none (0 with PROL_ZERO), cells without value None.
    fn field(
        &self,
        kind: Kind,
        components: Vec<String>,
        blocks: &[&Block],
        prol_zero: bool,
    ) -> std::result::Result<Field, String> {
        let nco = components.len();
        let mesh = self.mesh;
        match kind {
            Kind::Node => {
                let mut values = vec![if prol_zero { 0.0 } else { f64::NAN }; mesh.nnodes() * nco];
                for b in blocks {
                    for (i, &n) in b.entities.iter().enumerate() {
                        if n >= mesh.nnodes() {
                            return Err(format!("node {} of the file is not in the mesh", n + 1));
                        }
                        values[n * nco..(n + 1) * nco].copy_from_slice(&b.values[i * nco..(i + 1) * nco]);
                    }
                }
                Ok(Field::Node { components, values })
            }
            _ => {
                let mut cells: Vec<Option<Vec<f64>>> = vec![None; mesh.ncells()];
                for b in blocks {
                    let t = b.cell.expect("cell blocks have a type");
                    let members = self.by_type.get(&t).map(Vec::as_slice).unwrap_or(&[]);
                    let per = b.per_entity * nco;
                    for (i, &pos) in b.entities.iter().enumerate() {
                        let c = *members
                            .get(pos)
                            .ok_or_else(|| format!("{} cell {} of the file is not in the mesh", t.name(), pos + 1))?;
                        if kind == Kind::Elga {
                            let elem = self.model.and_then(|m| m.elements.get(c)).and_then(|e| e.as_ref());
                            if let Some(e) = elem {
                                let want = elga_points(e.modelisation, t)?;
                                if want != b.per_entity {
                                    return Err(format!(
                                        "cell {} carries {} points in the file, its element ({}) has {want}",
                                        mesh.cell_names[c], b.per_entity, e.modelisation
                                    ));
                                }
                            }
                        }
                        cells[c] = Some(b.values[i * per..(i + 1) * per].to_vec());
                    }
                }
                Ok(match kind {
                    Kind::Elno => Field::Elno { components, cells },
                    Kind::Elga => Field::Elga { components, cells },
                    _ => Field::Elem { components, cells },
                })
            }
        }
    }
}

/// NOM_CMP / NOM_CMP_MED: the components kept and their names (all the file's, renamed by the pairs).
fn component_map(occ: &Args, file: &[String], field: &str) -> Result<(Vec<usize>, Vec<String>)> {
    let ours = occ.texts_if_declared("NOM_CMP");
    let theirs = occ.texts_if_declared("NOM_CMP_MED");
    if ours.is_empty() {
        return Ok(((0..file.len()).collect(), file.to_vec()));
    }
    if ours.len() != theirs.len() {
        return Err(occ.err("NOM_CMP_MED", format!("{} NOM_CMP for {} NOM_CMP_MED", ours.len(), theirs.len())));
    }
    let mut idx = Vec::new();
    for m in &theirs {
        idx.push(file.iter().position(|c| c == m).ok_or_else(|| {
            occ.err("NOM_CMP_MED", format!("field '{field}' of the file has no component {m} ({})", file.join(" ")))
        })?);
    }
    Ok((idx, ours))
}

/// The blocks of a step with the components `idx` only.
fn pick(b: &Block, nco: usize, idx: &[usize]) -> Block {
    let n = b.entities.len() * b.per_entity;
    let values = (0..n).flat_map(|i| idx.iter().map(move |&k| b.values[i * nco + k])).collect();
    Block { values, ..b.clone() }
}

/// The steps of a file's field LIRE_RESU selects: (order number, time, step index).
fn steps_asked(ctx: &mut Ctx, a: &Args, f: &MedField, last: i64, rname: &str) -> Result<Vec<(i64, f64, usize)>> {
    let mut out = Vec::new();
    if a.has("TOUT_ORDRE") {
        return Ok(f.steps.iter().enumerate().map(|(i, s)| (s.order() as i64, s.time, i)).collect());
    }
    let orders = if a.has("NUME_ORDRE") {
        Some(a.ints("NUME_ORDRE"))
    } else {
        list_of(a, "LIST_ORDRE")?.map(|v| v.iter().map(|&x| x as i64).collect())
    };
    if let Some(orders) = orders {
        for n in orders {
            match f.steps.iter().position(|s| s.order() as i64 == n) {
                Some(i) => out.push((n, f.steps[i].time, i)),
                // lrfmed: MED_87, the order is passed over.
                None => ctx.io.mess(&format!(
                    " <A> <MED_87> LIRE_RESU: field '{}' of the file has no order {n}: result {rname} does not get it\n",
                    f.name
                )),
            }
        }
        return Ok(out);
    }
    let times = if a.has("INST") { a.reals("INST") } else { list_of(a, "LIST_INST")?.unwrap_or_default() };
    let crit = a.text("CRITERE").unwrap_or("RELATIF");
    let prec = a.real("PRECISION").unwrap_or(1.0e-6);
    let mut next = last;
    for t in times {
        let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
        match f.steps.iter().position(|s| (s.time - t).abs() <= tol) {
            Some(i) => {
                next += 1;
                out.push((next, t, i));
            }
            None => ctx.io.mess(&format!(
                " <A> LIRE_RESU: field '{}' of the file has no step at time {t} (CRITERE='{crit}', PRECISION={prec})\n",
                f.name
            )),
        }
    }
    Ok(out)
}

pub fn lire_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let format = a.req_text("FORMAT")?;
    if format != "MED" {
        return Err(a.err("FORMAT", format!("LIRE_RESU FORMAT='{format}' is not supported yet (only 'MED')")));
    }
    a.refuse(&["FREQ", "LIST_FREQ", "COMPORTEMENT"])?;
    let _ = a.text("TYPE_RESU"); // decided the concept's type (the catalogue)
    let _ = a.text("TITRE"); // titles are not printed
    let _ = a.text("VERI_VARI"); // the behaviour's variables are not checked: COMPORTEMENT is refused above
    let model_c = match a.concept("MODELE") {
        Some(m) => m,
        None => bare_model(&a.req_concept("MAILLAGE")?).map_err(|e| a.locate(e, "MAILLAGE"))?,
    };
    let model = model_c.model()?;
    let mesh = model.current_mesh();
    let target = Target::new(&mesh, Some(&model));
    let unit = a.int("UNITE").unwrap_or(81);
    let path = ctx.io.unit_path(unit, false).map_err(|e| a.locate(e, "UNITE"))?;
    let prol_zero = a.text("PROL_ZERO") != Some("NON");
    let rname = ctx.reuse.as_ref().map(|r| r.label()).unwrap_or_else(|| "the result".into());
    // The result extended (reuse=) or a new one.
    let (mut steps, material, mut loads) = match ctx.reuse.clone().or_else(|| a.concept("RESULTAT")) {
        Some(r) => {
            let rd = r.result().map_err(|e| a.locate(e, "RESULTAT"))?;
            (rd.steps.clone(), rd.material.clone(), rd.loads.clone())
        }
        None => (Vec::new(), None, Vec::new()),
    };
    let material = a.concept("CHAM_MATER").or(material);
    loads.extend(excit_loads(a)?);
    let last = steps.iter().map(|s| s.nume_ordre).max().unwrap_or(0);
    let mut report = String::new();
    for occ in a.facts("FORMAT_MED") {
        let sym = occ.req_text("NOM_CHAM")?.to_string();
        let med_name = match occ.text("NOM_CHAM_MED") {
            Some(n) => n.to_string(),
            None => {
                let prefix: String = occ.req_text("NOM_RESU")?.chars().take(8).collect();
                format!("{prefix:_<8}{sym}")
            }
        };
        let kw = if occ.has("NOM_CHAM_MED") { "NOM_CHAM_MED" } else { "NOM_RESU" };
        let f = med::read_field(&path, &med_name).map_err(|e| occ.err(kw, e.msg))?;
        target.check_file_mesh(&path, &f.mesh_name).map_err(|e| occ.err(kw, format!("field '{med_name}': {e}")))?;
        let (idx, components) = component_map(occ, &f.components, &med_name)?;
        let kind = Kind::of_symbol(&sym);
        let nco = f.components.len();
        let mut count = 0;
        for (order, time, i) in steps_asked(ctx, a, &f, last, &rname)? {
            let blocks: Vec<Block> =
                f.steps[i].blocks.iter().filter(|b| fits(kind, b)).map(|b| pick(b, nco, &idx)).collect();
            if blocks.is_empty() {
                let there: Vec<String> = f.steps[i].blocks.iter().map(|b| format!("{:?}", b.support)).collect();
                return Err(occ.err(
                    "NOM_CHAM",
                    format!(
                        "{sym} is an {} field, but field '{med_name}' of the file holds no such values at order \
                         {order} (it holds {})",
                        kind.name(),
                        if there.is_empty() { "nothing".to_string() } else { there.join(", ") }
                    ),
                ));
            }
            let refs: Vec<&Block> = blocks.iter().collect();
            let field = target
                .field(kind, components.clone(), &refs, prol_zero)
                .map_err(|e| occ.err(kw, format!("field '{med_name}' at order {order}: {e}")))?;
            match steps.iter_mut().find(|s| s.nume_ordre == order) {
                Some(s) => {
                    s.fields.insert(sym.clone(), field);
                }
                None => {
                    let mut fields = BTreeMap::new();
                    fields.insert(sym.clone(), field);
                    steps.push(Step { nume_ordre: order, inst: time, fields });
                }
            }
            count += 1;
        }
        let _ = writeln!(report, " LIRE_RESU: {sym} read from field '{med_name}' of unit {unit} at {count} order(s)");
    }
    steps.sort_by_key(|s| s.nume_ordre);
    ctx.io.mess(&report);
    if steps.is_empty() {
        return Err(a.err("FORMAT_MED", format!("no field was read from unit {unit} at the steps asked")));
    }
    drop(model);
    Ok(Some(ConceptData::Result(ResultData {
        model: model_c,
        material,
        cara_elem: None,
        loads,
        steps,
        comportement: Vec::new(),
    })))
}

pub fn lire_champ(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mesh_c = a.req_concept("MAILLAGE")?;
    let mesh = mesh_c.mesh().map_err(|e| a.locate(e, "MAILLAGE"))?;
    let _ = a.text("FORMAT");
    let _ = a.text("NOM_CMP_IDEM"); // the file's component names (the rule: this or NOM_CMP)
    let type_cham = a.req_text("TYPE_CHAM")?;
    let kind = match type_cham.split('_').next().unwrap_or("") {
        "NOEU" => Kind::Node,
        "ELNO" => Kind::Elno,
        "ELGA" => Kind::Elga,
        "ELEM" => Kind::Elem,
        _ => {
            return Err(a.err(
                "TYPE_CHAM",
                format!("TYPE_CHAM='{type_cham}' is not supported yet (NOEU_, ELNO_, ELGA_, ELEM_ fields are)"),
            ))
        }
    };
    let model_c = a.concept("MODELE");
    match (kind, &model_c) {
        (Kind::Node, Some(_)) => return Err(a.err("MODELE", "MODELE is for cell fields (TYPE_CHAM='EL...')")),
        (Kind::Node, None) => {}
        (_, None) => return Err(a.err("TYPE_CHAM", format!("a {type_cham} field needs MODELE"))),
        _ => {}
    }
    let model = model_c.as_ref().map(|m| m.model()).transpose()?;
    let unit = a.int("UNITE").unwrap_or(81);
    let path = ctx.io.unit_path(unit, false).map_err(|e| a.locate(e, "UNITE"))?;
    let name = a.req_text("NOM_MED")?;
    let f = med::read_field(&path, name).map_err(|e| a.err("NOM_MED", e.msg))?;
    if let Some(m) = a.text("NOM_MAIL_MED") {
        if m != f.mesh_name {
            return Err(a.err("NOM_MAIL_MED", format!("field '{name}' is on mesh '{}', not '{m}'", f.mesh_name)));
        }
    }
    let target = Target::new(&mesh, model.as_deref());
    target.check_file_mesh(&path, &f.mesh_name).map_err(|e| a.err("NOM_MED", format!("field '{name}': {e}")))?;
    let (idx, components) = component_map(a, &f.components, name)?;
    // The step: NUME_PT (numdt) and NUME_ORDRE (numit), INST, else the only one (or the one without
    // time step, numdt = numit = -1).
    let pts = a.ints("NUME_PT");
    let ords = a.ints("NUME_ORDRE");
    let step = if a.has("INST") {
        let t = a.reals("INST")[0];
        let crit = a.text("CRITERE").unwrap_or("RELATIF");
        let prec = a.real("PRECISION").unwrap_or(1.0e-6);
        let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
        f.steps.iter().find(|s| (s.time - t).abs() <= tol).ok_or_else(|| {
            a.err("INST", format!("field '{name}' has no step at time {t} (CRITERE='{crit}', PRECISION={prec})"))
        })?
    } else if !pts.is_empty() || !ords.is_empty() {
        f.steps
            .iter()
            .find(|s| {
                (pts.is_empty() || pts.contains(&(s.numdt as i64)))
                    && (ords.is_empty() || ords.contains(&(s.numit as i64)))
            })
            .ok_or_else(|| {
                let kw = if ords.is_empty() { "NUME_PT" } else { "NUME_ORDRE" };
                let have: Vec<String> = f.steps.iter().map(|s| format!("({}, {})", s.numdt, s.numit)).collect();
                a.err(kw, format!("field '{name}' has no such step; its steps (numdt, numit): {}", have.join(" ")))
            })?
    } else {
        match f.steps.iter().find(|s| s.numdt == -1 && s.numit == -1) {
            Some(s) => s,
            None if f.steps.len() == 1 => &f.steps[0],
            None => {
                return Err(a.err(
                    "NOM_MED",
                    format!("field '{name}' has {} steps: give NUME_ORDRE, NUME_PT or INST", f.steps.len()),
                ))
            }
        }
    };
    let nco = f.components.len();
    let blocks: Vec<Block> = step.blocks.iter().filter(|b| fits(kind, b)).map(|b| pick(b, nco, &idx)).collect();
    if blocks.is_empty() {
        return Err(a.err("TYPE_CHAM", format!("field '{name}' holds no {} values", kind.name())));
    }
    let refs: Vec<&Block> = blocks.iter().collect();
    let prol_zero = a.text("PROL_ZERO") == Some("OUI");
    let field = target
        .field(kind, components, &refs, prol_zero)
        .map_err(|e| a.err("NOM_MED", format!("field '{name}': {e}")))?;
    drop(model);
    Ok(Some(ConceptData::Field(FieldData { mesh_concept: mesh_c, field, functions: None })))
}
