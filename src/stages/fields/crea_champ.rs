//! Fields of their own and fields on skins: CREA_CHAMP (AFFE — of reals, or of functions on nodes or
//! cells —, EXTR from a result or a mesh's geometry, EVAL of a field of functions on nodes or cells)
//! and CALC_CHAMP's SIRO_ELEM (the stress vector on skin cells).
//!
//! SIRO_ELEM follows Code_Aster's plane rosette (`te0554`): the stress of the
//! bulk cell a skin cell bounds, at the skin's nodes (its SIGM_ELNO), is
//! averaged over those nodes; the frame of the skin is the mean tangent
//! `t1 = ∂x/∂ξ` (normalized), `t2 = ez` and the normal `n = t1 × ez`, i.e.
//! `(t_y, -t_x)`: the skin cell's own orientation (MODI_MAILLAGE ORIE_PEAU
//! makes it point out). The components are the stress vector `σ·n` and its
//! normal part, `σ·t1`, `σ·t2` and the shear `t1·σ·n`.

use crate::catalog::args::Args;
use crate::concepts::result::{Field, FieldData};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::stages::core::eval::eval_named;
use crate::stages::select::{select_cells, select_nodes};
use crate::stages::Ctx;

// ------------------------------------------------------------------ CREA_CHAMP
/// The location part of TYPE_CHAM and whether the values are functions.
fn type_cham(a: &Args) -> Result<(&str, bool)> {
    let t = a.req_text("TYPE_CHAM")?;
    let loc = t.split('_').next().unwrap_or("");
    Ok((loc, t.ends_with("_F")))
}

fn same_location(loc: &str, f: &Field) -> bool {
    matches!(
        (loc, f),
        ("ELEM", Field::Elem { .. })
            | ("ELNO", Field::Elno { .. })
            | ("ELGA", Field::Elga { .. })
            | ("NOEU", Field::Node { .. })
    )
}

pub fn crea_champ(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    match a.req_text("OPERATION")? {
        "AFFE" => affe(a),
        "EXTR" => extr(a),
        "EVAL" => eval(a),
        "ASSE" => asse(a),
        o => Err(a.err("OPERATION", format!("OPERATION='{o}' is not supported yet"))),
    }
    .map(|f| Some(ConceptData::Field(f)))
}

fn affe(a: &Args) -> Result<FieldData> {
    let (loc, func) = type_cham(a)?;
    if !matches!(loc, "ELEM" | "ELGA" | "NOEU") || (loc == "ELGA" && func) {
        return Err(a.err("TYPE_CHAM", format!("TYPE_CHAM='{}' is not supported yet", a.text("TYPE_CHAM").unwrap())));
    }
    let (mesh_concept, on_model): (ConceptRef, Option<Vec<bool>>) = match a.concept("MODELE") {
        Some(mo) => {
            let m = mo.model()?;
            (m.mesh_concept.clone(), Some(m.elements.iter().map(Option::is_some).collect()))
        }
        None => (a.req_concept("MAILLAGE")?, None),
    };
    let mesh = mesh_concept.mesh()?;
    let mesh_name = mesh_concept.label();
    let prol_zero = a.text("PROL_ZERO") == Some("OUI");
    // Components in order of first appearance.
    let mut comps: Vec<String> = Vec::new();
    for occ in a.facts("AFFE") {
        for c in occ.texts("NOM_CMP") {
            if !comps.contains(&c) {
                comps.push(c);
            }
        }
    }
    let n = comps.len();
    let fill = if prol_zero { 0.0 } else { f64::NAN };
    let nplaces = if loc == "NOEU" { mesh.coords.len() } else { mesh.cells.len() };
    let mut values: Vec<Option<Vec<f64>>> = vec![None; nplaces];
    let mut funcs: Vec<Option<Vec<Option<ConceptRef>>>> = vec![None; nplaces];
    for occ in a.facts("AFFE") {
        for kw in ["VALE_I", "VALE_C"] {
            if occ.given(kw) {
                return Err(occ.err(kw, "not supported yet"));
            }
        }
        let names = occ.texts("NOM_CMP");
        let count = if func { occ.concepts("VALE_F").len() } else { occ.reals("VALE").len() };
        let vkw = if func { "VALE_F" } else { "VALE" };
        if count != names.len() {
            return Err(occ.err(vkw, format!("{} values for {} components (NOM_CMP)", count, names.len())));
        }
        if !func && occ.given("VALE_F") || func && occ.given("VALE") {
            return Err(occ.err(vkw, format!("{vkw} is required by TYPE_CHAM='{}'", a.text("TYPE_CHAM").unwrap())));
        }
        let places: Vec<usize> = if loc == "NOEU" {
            select_nodes(&mesh, occ, &mesh_name)?
        } else {
            let sel = select_cells(&mesh, occ, &mesh_name)?;
            sel.into_iter().filter(|&c| on_model.as_ref().is_none_or(|m| m[c])).collect()
        };
        for p in places {
            let idx: Vec<usize> = names.iter().map(|c| comps.iter().position(|x| x == c).unwrap()).collect();
            if func {
                let slot = funcs[p].get_or_insert_with(|| vec![None; n]);
                for (&k, f) in idx.iter().zip(occ.concepts("VALE_F")) {
                    slot[k] = Some(f);
                }
                values[p].get_or_insert_with(|| vec![f64::NAN; n]);
            } else {
                let slot = values[p].get_or_insert_with(|| vec![fill; n]);
                for (&k, v) in idx.iter().zip(occ.reals("VALE")) {
                    slot[k] = v;
                }
            }
        }
    }
    if prol_zero {
        // Every other place of the model (or mesh) gets zeros (the zero function).
        for (p, v) in values.iter_mut().enumerate() {
            if loc == "ELEM" && on_model.as_ref().is_some_and(|m| !m[p]) {
                continue;
            }
            if v.is_none() {
                *v = Some(vec![if func { f64::NAN } else { 0.0 }; n]);
                if func {
                    funcs[p] = Some(vec![None; n]);
                }
            }
        }
    }
    let field = if loc == "NOEU" {
        Field::Node {
            components: comps,
            values: values.into_iter().flat_map(|v| v.unwrap_or(vec![f64::NAN; n])).collect(),
        }
    } else if loc == "ELGA" {
        // The same values at every integration point of the cell's element.
        let mo = a
            .concept("MODELE")
            .ok_or_else(|| a.err("TYPE_CHAM", "a field on integration points (ELGA) needs MODELE"))?;
        let m = mo.model()?;
        let mut cells = Vec::with_capacity(values.len());
        for (c, v) in values.into_iter().enumerate() {
            let npts = match (&m.elements[c], v.is_some()) {
                // Skin elements carry no stresses: the field lives on the bulk ones.
                (Some(e), true) if e.role == crate::concepts::model::Role::Bulk => {
                    crate::stages::core::hm::elga_points(e.modelisation, mesh.cell_types[c])
                        .map_err(|msg| a.err("TYPE_CHAM", format!("cell {}: {msg}", mesh.cell_names[c])))?
                }
                _ => 0,
            };
            cells.push(v.filter(|_| npts > 0).map(|v| v.repeat(npts)));
        }
        Field::Elga { components: comps, cells }
    } else {
        Field::Elem { components: comps, cells: values }
    };
    Ok(FieldData { mesh_concept, field, functions: func.then_some(funcs) })
}

/// The values of component `k` at place `p` (a node, or a cell: one per integration point or cell node),
/// None where the field has none.
fn point_values(f: &Field, p: usize, k: usize) -> Option<Vec<f64>> {
    let n = f.components().len();
    match f {
        Field::Node { values, .. } => values.get(p * n + k).copied().filter(|v| !v.is_nan()).map(|v| vec![v]),
        Field::Elem { cells, .. } => {
            cells.get(p)?.as_ref().and_then(|c| c.get(k).copied()).filter(|v| !v.is_nan()).map(|v| vec![v])
        }
        Field::Elga { cells, .. } | Field::Elno { cells, .. } => {
            let pts: Vec<f64> = cells.get(p)?.as_ref()?.iter().skip(k).step_by(n).copied().collect();
            (!pts.iter().all(|v| v.is_nan())).then_some(pts)
        }
    }
}

/// ASSE: a field assembled from pieces of others, as Code_Aster's `chpass` does: each occurrence takes
/// the components NOM_CMP (all by default) of CHAM_GD, renamed NOM_CMP_RESU, times COEF_R, on the nodes
/// (NOEU) or cells (EL*) of TOUT / GROUP_MA / GROUP_NO; where the result already has a value, CUMUL='OUI'
/// adds to it and 'NON' replaces it. PROL_ZERO='OUI' gives the components missing on the model's cells
/// the value 0 (EL* fields).
fn asse(a: &Args) -> Result<FieldData> {
    let (loc, func) = type_cham(a)?;
    let t = a.text("TYPE_CHAM").unwrap_or_default().to_string();
    if func || t.ends_with("_C") || !matches!(loc, "NOEU" | "ELEM" | "ELGA" | "ELNO") {
        return Err(a.err("TYPE_CHAM", format!("OPERATION='ASSE' of TYPE_CHAM='{t}' is not supported yet")));
    }
    // OPTION names the element option whose layout a cell field has in Code_Aster; here the layout
    // (points per cell) is the assembled fields' own, so it changes nothing.
    let _ = a.text("OPTION");
    let prol_zero = a.text("PROL_ZERO") == Some("OUI");
    let model = a.concept("MODELE");
    let mesh_concept = match &model {
        Some(mo) => mo.model()?.mesh_concept.clone(),
        None => a.req_concept("MAILLAGE")?,
    };
    let mesh = mesh_concept.mesh()?;
    let mesh_name = mesh_concept.label();
    let nplaces = if loc == "NOEU" { mesh.coords.len() } else { mesh.cells.len() };
    let mut comps: Vec<String> = Vec::new();
    // Per component of the result, per place, the values at its points.
    let mut vals: Vec<Vec<Option<Vec<f64>>>> = Vec::new();
    for occ in a.facts("ASSE") {
        occ.refuse(&["COEF_C"])?;
        let fc = occ.req_concept("CHAM_GD")?;
        let fd = fc.field().map_err(|e| occ.locate(e, "CHAM_GD"))?;
        let field = fd.reals(&fc.label()).map_err(|e| occ.locate(e, "CHAM_GD"))?;
        if !std::rc::Rc::ptr_eq(&fd.mesh_concept, &mesh_concept) {
            return Err(occ.err(
                "CHAM_GD",
                format!("{} lies on mesh {}, the field made on {mesh_name}", fc.label(), fd.mesh_concept.label()),
            ));
        }
        if !same_location(loc, field) {
            return Err(occ.err(
                "CHAM_GD",
                format!("{} is not a {loc} field: assembling it into TYPE_CHAM='{t}' is not supported yet", fc.label()),
            ));
        }
        let names = occ.texts("NOM_CMP");
        let taken: Vec<String> = if names.is_empty() { field.components().to_vec() } else { names };
        let renamed = occ.texts("NOM_CMP_RESU");
        if !renamed.is_empty() && renamed.len() != taken.len() {
            return Err(
                occ.err("NOM_CMP_RESU", format!("{} names for {} components (NOM_CMP)", renamed.len(), taken.len()))
            );
        }
        let mut index = Vec::with_capacity(taken.len());
        for c in &taken {
            index.push(field.component(c).ok_or_else(|| {
                occ.err(
                    "NOM_CMP",
                    format!("{} has no component {c} (it has {})", fc.label(), field.components().join(", ")),
                )
            })?);
        }
        let coef = occ.real("COEF_R").unwrap_or(1.0);
        let cumul = occ.text("CUMUL") == Some("OUI");
        let places =
            if loc == "NOEU" { select_nodes(&mesh, occ, &mesh_name)? } else { select_cells(&mesh, occ, &mesh_name)? };
        for (j, &k) in index.iter().enumerate() {
            let name = if renamed.is_empty() { &taken[j] } else { &renamed[j] };
            let r = match comps.iter().position(|c| c == name) {
                Some(r) => r,
                None => {
                    comps.push(name.clone());
                    vals.push(vec![None; nplaces]);
                    comps.len() - 1
                }
            };
            for &p in &places {
                let Some(v) = point_values(field, p, k) else { continue };
                let slot = &mut vals[r][p];
                match slot {
                    Some(old) if cumul => {
                        if old.len() != v.len() {
                            return Err(occ.err(
                                "CHAM_GD",
                                format!(
                                    "{}: cell {} has {} points here, {} in the field assembled so far",
                                    fc.label(),
                                    mesh.cell_names[p],
                                    v.len(),
                                    old.len()
                                ),
                            ));
                        }
                        old.iter_mut().zip(&v).for_each(|(o, x)| *o += coef * x);
                    }
                    _ => *slot = Some(v.iter().map(|x| coef * x).collect()),
                }
            }
        }
    }
    let n = comps.len();
    // The points of each place: the same for every component there.
    let mut npts: Vec<Option<usize>> = vec![None; nplaces];
    for cv in &vals {
        for (p, v) in cv.iter().enumerate() {
            let Some(v) = v else { continue };
            match npts[p] {
                Some(m) if m != v.len() => {
                    return Err(a.err(
                        "ASSE",
                        format!(
                            "cell {}: the fields assembled have {m} and {} points there",
                            mesh.cell_names[p],
                            v.len()
                        ),
                    ))
                }
                _ => npts[p] = Some(v.len()),
            }
        }
    }
    if prol_zero && loc != "NOEU" {
        let mo = model.as_ref().ok_or_else(|| a.err("PROL_ZERO", "PROL_ZERO='OUI' of a cell field needs MODELE"))?;
        let m = mo.model()?;
        for (c, e) in m.elements.iter().enumerate() {
            let Some(e) = e.as_ref().filter(|e| e.role == crate::concepts::model::Role::Bulk) else { continue };
            if npts[c].is_none() {
                npts[c] = Some(match loc {
                    "ELGA" => crate::stages::core::hm::elga_points(e.modelisation, mesh.cell_types[c])
                        .map_err(|msg| a.err("PROL_ZERO", format!("cell {}: {msg}", mesh.cell_names[c])))?,
                    "ELNO" => mesh.cells[c].len(),
                    _ => 1,
                });
            }
        }
    }
    let fill = if prol_zero { 0.0 } else { f64::NAN };
    let at = |p: usize, g: usize, k: usize| vals[k][p].as_ref().map_or(fill, |v| v[g]);
    let field = if loc == "NOEU" {
        let vals = &vals;
        let values =
            (0..nplaces).flat_map(|p| (0..n).map(move |k| vals[k][p].as_ref().map_or(f64::NAN, |v| v[0]))).collect();
        Field::Node { components: comps, values }
    } else {
        let cells: Vec<Option<Vec<f64>>> = (0..nplaces)
            .map(|p| {
                npts[p].map(|m| (0..m).flat_map(|g| (0..n).map(move |k| (g, k))).map(|(g, k)| at(p, g, k)).collect())
            })
            .collect();
        match loc {
            "ELGA" => Field::Elga { components: comps, cells },
            "ELNO" => Field::Elno { components: comps, cells },
            _ => Field::Elem { components: comps, cells },
        }
    };
    Ok(FieldData { mesh_concept, field, functions: None })
}

fn extr(a: &Args) -> Result<FieldData> {
    let (loc, _) = type_cham(a)?;
    a.refuse(&["TABLE"])?;
    if let Some(mc) = a.concept("MAILLAGE") {
        return geometry(a, mc);
    }
    let rc = a
        .concept("RESULTAT")
        .ok_or_else(|| a.err("RESULTAT", "only extraction from a result or a mesh is supported yet"))?;
    if a.given("TYPE_MAXI") {
        return Err(a.err("TYPE_MAXI", "not supported yet"));
    }
    let name = rc.label();
    let r = rc.result()?;
    let step = if let Some(n) = a.int("NUME_ORDRE") {
        r.by_order(n).ok_or_else(|| a.err("NUME_ORDRE", format!("result {name} has no order number {n}")))?
    } else if let Some(t) = a.real("INST") {
        let prec = a.real("PRECISION").unwrap_or(1e-6);
        r.by_inst(t, prec).ok_or_else(|| a.err("INST", format!("result {name} has no step at time {t}")))?
    } else {
        let kw = ["FREQ", "NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE"]
            .into_iter()
            .find(|k| a.declares(k) && a.given(k))
            .unwrap_or("NUME_ORDRE");
        return Err(a.err(kw, "not supported yet"));
    };
    let cham = a.req_text("NOM_CHAM")?;
    let field = step
        .fields
        .get(cham)
        .ok_or_else(|| a.err("NOM_CHAM", format!("result {name} has no field {cham} at order {}", step.nume_ordre)))?;
    if !same_location(loc, field) {
        return Err(a.err(
            "TYPE_CHAM",
            format!("field {cham} of {name} is not a field of type {}", a.text("TYPE_CHAM").unwrap()),
        ));
    }
    let mesh_concept = r.model.model()?.mesh_concept.clone();
    Ok(FieldData { mesh_concept, field: field.clone(), functions: None })
}

/// EXTR from MAILLAGE: NOM_CHAM='GEOMETRIE' is the mesh's coordinates, a NOEU_GEOM_R field of components
/// X, Y, Z (Code_Aster's `.COORDO` has the three whatever the mesh's dimension).
fn geometry(a: &Args, mc: ConceptRef) -> Result<FieldData> {
    let cham = a.req_text("NOM_CHAM")?;
    if cham != "GEOMETRIE" {
        return Err(a.err("NOM_CHAM", format!("NOM_CHAM='{cham}' of a mesh is not supported yet (GEOMETRIE is)")));
    }
    let t = a.req_text("TYPE_CHAM")?;
    if t != "NOEU_GEOM_R" {
        return Err(a.err("TYPE_CHAM", format!("the geometry of a mesh is a NOEU_GEOM_R field, not {t}")));
    }
    let values = mc.mesh()?.coords.iter().flatten().copied().collect();
    let components = ["X", "Y", "Z"].map(String::from).to_vec();
    Ok(FieldData { mesh_concept: mc, field: Field::Node { components, values }, functions: None })
}

/// Evaluate the functions of a field by cell (None: the zero function) with
/// their parameters taken by name among the components of `paras` (fields by
/// cell) on the same cell.
pub fn eval_cells(
    funcs: &[Option<Vec<Option<ConceptRef>>>],
    paras: &[&Field],
    cell_names: &[String],
) -> Result<Vec<Option<Vec<f64>>>> {
    let mut out = vec![None; funcs.len()];
    for (c, fs) in funcs.iter().enumerate() {
        let Some(fs) = fs else { continue };
        let arg = |name: &str| -> Result<f64> {
            for p in paras {
                let Field::Elem { cells, .. } = p else { continue };
                if let (Some(k), Some(Some(v))) = (p.component(name), cells.get(c)) {
                    if !v[k].is_nan() {
                        return Ok(v[k]);
                    }
                }
            }
            Err(Error::runtime(format!(
                "CHAM_PARA: parameter {name} has no value on cell {} in the parameter fields",
                cell_names[c]
            )))
        };
        let vals: Vec<f64> =
            fs.iter().map(|g| g.as_ref().map_or(Ok(0.0), |g| eval_named(g, &arg))).collect::<Result<_>>()?;
        out[c] = Some(vals);
    }
    Ok(out)
}

/// Evaluate the `n` functions per node of a field on nodes (None: the zero function) with their parameters taken
/// by name among the components the fields `paras` have at the same node, as Code_Aster does
/// (`cnseva`): a parameter given by two of them is an error, one given by none too.
pub fn eval_nodes(
    funcs: &[Option<Vec<Option<ConceptRef>>>],
    n: usize,
    paras: &[(&str, &Field)],
    node_names: &[String],
) -> Result<Vec<f64>> {
    let mut out = vec![f64::NAN; funcs.len() * n];
    let mut given: Vec<(&str, f64, &str)> = Vec::new();
    let node = |i: usize| node_names.get(i).cloned().unwrap_or_else(|| format!("#{}", i + 1));
    for (i, fs) in funcs.iter().enumerate() {
        let Some(fs) = fs else { continue };
        given.clear();
        for &(label, p) in paras {
            let Field::Node { components, values } = p else { continue };
            let m = components.len();
            for (k, c) in components.iter().enumerate() {
                let v = values.get(i * m + k).copied().unwrap_or(f64::NAN);
                if v.is_nan() {
                    continue;
                }
                if let Some((_, _, first)) = given.iter().find(|g| g.0 == c) {
                    return Err(Error::runtime(format!(
                        "CHAM_PARA: parameter {c} is given at node {} by two fields ({first} and {label})",
                        node(i)
                    )));
                }
                given.push((c, v, label));
            }
        }
        let arg = |name: &str| -> Result<f64> {
            given.iter().find(|g| g.0 == name).map(|g| g.1).ok_or_else(|| {
                Error::runtime(format!(
                    "CHAM_PARA: parameter {name} has no value at node {} in the parameter fields",
                    node(i)
                ))
            })
        };
        for (k, g) in fs.iter().enumerate().take(n) {
            out[i * n + k] = g.as_ref().map_or(Ok(0.0), |g| eval_named(g, &arg))?;
        }
    }
    Ok(out)
}

fn eval(a: &Args) -> Result<FieldData> {
    let (loc, func) = type_cham(a)?;
    if func {
        return Err(a.err("TYPE_CHAM", "the result of EVAL is a field of reals (*_R)"));
    }
    let fc = a.req_concept("CHAM_F")?;
    let f = fc.field()?;
    let Some(funcs) = &f.functions else {
        return Err(a.err("CHAM_F", format!("{} is not a field of functions (*_F)", fc.label())));
    };
    let node = matches!(f.field, Field::Node { .. });
    if !matches!((loc, &f.field), ("ELEM", Field::Elem { .. }) | ("NOEU", Field::Node { .. })) {
        return Err(a.err(
            "TYPE_CHAM",
            format!(
                "TYPE_CHAM='{}' is not supported yet for CHAM_F {} (EVAL makes NOEU_*_R fields of NOEU_*_F ones and \
                 ELEM_*_R of ELEM_*_F)",
                a.text("TYPE_CHAM").unwrap(),
                fc.label()
            ),
        ));
    }
    let mesh = f.mesh_concept.mesh()?;
    let paras = a.concepts("CHAM_PARA");
    let para_data: Vec<std::cell::Ref<'_, FieldData>> = paras.iter().map(|c| c.field()).collect::<Result<_>>()?;
    for (p, d) in paras.iter().zip(&para_data) {
        let fits = if node { matches!(d.field, Field::Node { .. }) } else { matches!(d.field, Field::Elem { .. }) };
        if !fits || d.functions.is_some() {
            let want = if node { "on nodes (NOEU_*_R)" } else { "by cell (ELEM_*_R)" };
            return Err(a.err("CHAM_PARA", format!("{} is not a field of reals {want}", p.label())));
        }
        if node && !std::rc::Rc::ptr_eq(&d.mesh_concept, &f.mesh_concept) {
            return Err(a.err(
                "CHAM_PARA",
                format!("{} lies on mesh {}, CHAM_F on {}", p.label(), d.mesh_concept.label(), f.mesh_concept.label()),
            ));
        }
    }
    let components = f.field.components().to_vec();
    let field = if node {
        let labels: Vec<String> = paras.iter().map(|p| p.label()).collect();
        let para_fields: Vec<(&str, &Field)> =
            labels.iter().map(String::as_str).zip(para_data.iter().map(|d| &d.field)).collect();
        let values = eval_nodes(funcs, components.len(), &para_fields, &mesh.node_names).map_err(|e| e.at(a.span))?;
        Field::Node { components, values }
    } else {
        let para_fields: Vec<&Field> = para_data.iter().map(|d| &d.field).collect();
        let cells = eval_cells(funcs, &para_fields, &mesh.cell_names).map_err(|e| e.at(a.span))?;
        Field::Elem { components, cells }
    };
    Ok(FieldData { mesh_concept: f.mesh_concept.clone(), field, functions: None })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eval_of_a_formula_on_two_fields() {
        use crate::concepts::{Concept, ConceptKind};
        let globals: crate::interp::Scope = Default::default();
        let form =
            crate::interp::Formula::new("SIG_N * X1 + 1", vec!["SIG_N".into(), "X1".into()], vec![], globals).unwrap();
        let form = Concept::new(ConceptKind::Formule, ConceptData::Formula(form.into_concept()));
        // Cell 0: the formula; cell 1: the zero function; cell 2: nothing.
        let funcs = vec![Some(vec![Some(form.clone())]), Some(vec![None]), None];
        let siro = Field::Elem {
            components: vec!["SIG_NX".into(), "SIG_N".into()],
            cells: vec![Some(vec![1.0, 100.0]), None, None],
        };
        let neut = Field::Elem { components: vec!["X1".into()], cells: vec![Some(vec![3.0]), Some(vec![1.0]), None] };
        let names: Vec<String> = ["M1", "M2", "M3"].iter().map(|s| s.to_string()).collect();
        let out = eval_cells(&funcs, &[&siro, &neut], &names).unwrap();
        assert_eq!(out, vec![Some(vec![301.0]), Some(vec![0.0]), None]);
        // A parameter missing on a cell is an error naming it.
        let funcs = vec![None, Some(vec![Some(form)]), None];
        let e = eval_cells(&funcs, &[&siro, &neut], &names).unwrap_err();
        assert!(e.msg.contains("SIG_N") && e.msg.contains("M2"), "{}", e.msg);
    }

    #[test]
    fn eval_on_nodes_takes_each_parameter_from_the_one_field_that_has_it() {
        use crate::concepts::{Concept, ConceptKind};
        let globals: crate::interp::Scope = Default::default();
        let form =
            crate::interp::Formula::new("X*10 + INST", vec!["X".into(), "INST".into()], vec![], globals).unwrap();
        let form = Concept::new(ConceptKind::Formule, ConceptData::Formula(form.into_concept()));
        // Node 0: the formula; node 1: the zero function (PROL_ZERO); node 2: no value.
        let funcs = vec![Some(vec![Some(form.clone())]), Some(vec![None]), None];
        let geom = Field::Node {
            components: vec!["X".into(), "Y".into(), "Z".into()],
            values: vec![1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 3.0, 0.0, 0.0],
        };
        let inst = Field::Node { components: vec!["INST".into()], values: vec![0.5, 0.5, 0.5] };
        let names: Vec<String> = ["N1", "N2", "N3"].iter().map(|s| s.to_string()).collect();
        let out = eval_nodes(&funcs, 1, &[("GEOM", &geom), ("T", &inst)], &names).unwrap();
        assert_eq!(out[..2], [10.5, 0.0]);
        assert!(out[2].is_nan());
        // A parameter no field gives, or two give, is an error naming it and the node.
        let e = eval_nodes(&funcs, 1, &[("GEOM", &geom)], &names).unwrap_err();
        assert!(e.msg.contains("INST") && e.msg.contains("N1"), "{}", e.msg);
        let e = eval_nodes(&funcs, 1, &[("GEOM", &geom), ("T", &inst), ("U", &inst)], &names).unwrap_err();
        assert!(e.msg.contains("INST") && e.msg.contains("two fields"), "{}", e.msg);
    }
}
