//! CREA_RESU: results made of fields (EVOL_ELAS, EVOL_NOLI, EVOL_THER, EVOL_VARC, EVOL_SECH).
//!
//! As Code_Aster does it (`op0124`: `crtype`, `crasse`, `crprol`):
//! - AFFE stores a field under NOM_CHAM at each instant of INST, or of LIST_INST from NUME_INIT to
//!   NUME_FIN. An instant the result already holds (before the occurrence; PRECISION, 0 by default, and
//!   CRITERE) gets the field at its order — with an alarm where the field was already there —, any other
//!   a new order after the largest (the first one of a new result is 1). A field of functions on nodes
//!   (`NOEU_TEMP_F`, ...) is evaluated at each instant, its functions of X, Y, Z and INST at the nodes.
//!   The result's model is the first MODELE given, else the one the result extended (reuse=) has, else
//!   none (a model without elements on the fields' mesh); the same for CHAM_MATER; EXCIT's loads are
//!   kept with it.
//! - ASSE puts results (EVOL_THER) one after the other, their instants shifted by TRANSLATION, in a new
//!   result numbered from 1; an instant equal to the previous one puts its fields in that order, an
//!   earlier one is an error. The model and material are the first result's.
//! - PROL_RTZ makes a 3D temperature of a 1D radial one: at each instant of the table (POST_RELEVE_T's
//!   INST, COOR_X, TEMP; or of INST / LIST_INST), the temperature at a node of MAILLAGE_FINAL is the
//!   table's interpolated at the node's radius, measured as Code_Aster measures it (the distance of the
//!   node from the line through 0 along AXE_Z, less that of ORIGINE); beyond the table's radii
//!   PROL_GAUCHE / PROL_DROITE say what to do (EXCLU: an error, CONSTANT: the end value, LINEAIRE: the
//!   line of the two end points).

use crate::catalog::args::Args;
use crate::concepts::result::{Field, FieldData, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::mesh::Mesh;
use crate::stages::core::eval::eval_at;
use crate::stages::core::stored::{bare_model, excit_loads, Location};
use crate::stages::Ctx;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::rc::Rc;

pub fn crea_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let op = a.req_text("OPERATION")?;
    let t = a.req_text("TYPE_RESU")?;
    if matches!(op, "ASSE" | "PROL_RTZ") && t != "EVOL_THER" {
        return Err(a.err("TYPE_RESU", format!("OPERATION='{op}' makes an EVOL_THER, not an {t}")));
    }
    let data = match op {
        "AFFE" => affe(ctx, a)?,
        "ASSE" => asse(ctx, a)?,
        "PROL_RTZ" => prol_rtz(ctx, a)?,
        o => {
            return Err(a.err(
                "OPERATION",
                format!("CREA_RESU OPERATION='{o}' is not supported yet (AFFE, ASSE and PROL_RTZ are)"),
            ))
        }
    };
    Ok(Some(ConceptData::Result(data)))
}

/// Is `t` the instant `s` within PRECISION and CRITERE?
fn same_instant(s: f64, t: f64, prec: f64, relative: bool) -> bool {
    let tol = if relative { prec * t.abs() } else { prec };
    (s - t).abs() <= tol
}

/// The instants of an AFFE occurrence: INST, or LIST_INST from NUME_INIT to NUME_FIN (1-based, both
/// included; NUME_FIN past the list's end stops at it).
fn instants(occ: &Args) -> Result<Vec<f64>> {
    if occ.has("INST") {
        return Ok(occ.reals("INST"));
    }
    let list = occ.req_concept("LIST_INST")?;
    let vals = list.reals().map_err(|e| occ.locate(e, "LIST_INST"))?;
    let first = occ.int("NUME_INIT").unwrap_or(1);
    let last = occ.int("NUME_FIN").map_or(vals.len() as i64, |n| n.min(vals.len() as i64));
    if occ.has("NUME_INIT") && occ.has("NUME_FIN") && last < first {
        return Err(occ.err("NUME_FIN", format!("NUME_FIN={last} comes before NUME_INIT={first}")));
    }
    Ok(vals.iter().enumerate().filter(|(k, _)| (first..=last).contains(&(*k as i64 + 1))).map(|(_, v)| *v).collect())
}

/// The values at instant `t` of a field of functions on nodes: each function of X, Y, Z and INST at its
/// node (the zero function of PROL_ZERO gives 0; a node without the component keeps none).
fn evaluate(fd: &FieldData, mesh: &Mesh, t: f64) -> Result<Field> {
    let (Field::Node { components, .. }, Some(funcs)) = (&fd.field, &fd.functions) else {
        return Err(Error::runtime("only a field of functions on nodes (NOEU_*_F) is evaluated at instants"));
    };
    let n = components.len();
    if funcs.len() != mesh.coords.len() {
        return Err(Error::runtime(format!("the field has {} nodes, its mesh {} now", funcs.len(), mesh.coords.len())));
    }
    let mut values = vec![f64::NAN; funcs.len() * n];
    for (i, fs) in funcs.iter().enumerate() {
        let Some(fs) = fs else { continue };
        for (k, g) in fs.iter().enumerate().take(n) {
            values[i * n + k] = match g {
                None => 0.0,
                Some(g) => eval_at(g, &mesh.coords[i], t)
                    .map_err(|e| Error::runtime(format!("at node {}, INST={t}: {}", mesh.node_names[i], e.msg)))?,
            };
        }
    }
    Ok(Field::Node { components: components.clone(), values })
}

/// The result reuse= extends: RESULTAT, when given, must name it.
fn extended(ctx: &Ctx, a: &Args) -> Result<Option<ConceptRef>> {
    match (&ctx.reuse, a.concept("RESULTAT")) {
        (Some(r), Some(res)) if !Rc::ptr_eq(r, &res) => {
            Err(a.err("RESULTAT", format!("RESULTAT={} must be the result of reuse= ({})", res.label(), r.label())))
        }
        (None, Some(res)) => Err(a.err(
            "RESULTAT",
            format!("RESULTAT={} names a result to extend: it needs reuse={} as well", res.label(), res.label()),
        )),
        (r, _) => Ok(r.clone()),
    }
}

fn affe(ctx: &mut Ctx, a: &Args) -> Result<ResultData> {
    let base = extended(ctx, a)?;
    let (mut steps, base_model, base_material, base_cara, mut loads) = match &base {
        Some(r) => {
            let rd = r.result().map_err(|e| a.locate(e, "RESULTAT"))?;
            (rd.steps.clone(), Some(rd.model.clone()), rd.material.clone(), rd.cara_elem.clone(), rd.loads.clone())
        }
        None => (Vec::new(), None, None, None, Vec::new()),
    };
    for l in excit_loads(a)? {
        if !loads.iter().any(|x| Rc::ptr_eq(x, &l)) {
            loads.push(l);
        }
    }
    let (mut model, mut material): (Option<ConceptRef>, Option<ConceptRef>) = (None, None);
    let mut cara = base_cara;
    // The mesh of every field stored, with the occurrence that stored it first.
    let mut meshes: Vec<(ConceptRef, &Args)> = Vec::new();
    let mut mess = String::new();
    for occ in a.facts("AFFE") {
        if let Some(c) = occ.concept("CARA_ELEM") {
            c.cara_elem().map_err(|e| occ.locate(e, "CARA_ELEM"))?;
            cara.get_or_insert(c);
        }
        let nom = occ.req_text("NOM_CHAM")?.to_string();
        let fc = occ.req_concept("CHAM_GD")?;
        let fd = fc.field().map_err(|e| occ.locate(e, "CHAM_GD"))?;
        let loc = Location::of_symbol(&nom);
        if !loc.holds(&fd.field) {
            return Err(occ.err("CHAM_GD", format!("{nom} is an {} field, {} is not one", loc.name(), fc.label())));
        }
        if let Some(mo) = occ.concept("MODELE") {
            let m = mo.model().map_err(|e| occ.locate(e, "MODELE"))?;
            if !Rc::ptr_eq(&m.mesh_concept, &fd.mesh_concept) {
                return Err(occ.err(
                    "MODELE",
                    format!(
                        "{} lies on mesh {}, model {} on mesh {}",
                        fc.label(),
                        fd.mesh_concept.label(),
                        mo.label(),
                        m.mesh_concept.label()
                    ),
                ));
            }
            model.get_or_insert(mo.clone());
        }
        if let Some(cm) = occ.concept("CHAM_MATER") {
            material.get_or_insert(cm);
        }
        if !meshes.iter().any(|(m, _)| Rc::ptr_eq(m, &fd.mesh_concept)) {
            meshes.push((fd.mesh_concept.clone(), occ));
        }
        let mesh = fd.mesh_concept.mesh()?;
        let prec = occ.real("PRECISION").unwrap_or(0.0);
        let relative = occ.text("CRITERE") != Some("ABSOLU");
        // The orders are found among the steps the result held before this occurrence.
        let held = steps.len();
        let mut last = steps.iter().map(|s| s.nume_ordre).max().unwrap_or(0);
        let kw = if occ.has("INST") { "INST" } else { "LIST_INST" };
        for t in instants(occ)? {
            let found: Vec<usize> = (0..held).filter(|&i| same_instant(steps[i].inst, t, prec, relative)).collect();
            if found.len() > 1 {
                return Err(
                    occ.err(kw, format!("INST={t} matches {} steps of the result (PRECISION={prec})", found.len()))
                );
            }
            let field = if fd.functions.is_some() {
                evaluate(&fd, &mesh, t).map_err(|e| occ.err("CHAM_GD", format!("{}: {}", fc.label(), e.msg)))?
            } else {
                fd.field.clone()
            };
            match found.first() {
                Some(&i) => {
                    let s = &mut steps[i];
                    if s.fields.contains_key(&nom) {
                        let _ = writeln!(
                            mess,
                            " <A> <ALGORITH11_87> CREA_RESU: field {nom} at order {} (INST={}) is replaced by {} \
                             (INST={t})",
                            s.nume_ordre,
                            s.inst,
                            fc.label()
                        );
                    }
                    s.fields.insert(nom.clone(), field);
                }
                None => {
                    last += 1;
                    steps.push(Step { nume_ordre: last, inst: t, fields: BTreeMap::from([(nom.clone(), field)]) });
                }
            }
        }
    }
    ctx.io.mess(&mess);
    let model = match model.or(base_model) {
        Some(m) => m,
        None => {
            let (mesh, occ) = meshes.first().ok_or_else(|| a.err("AFFE", "no field given"))?;
            bare_model(mesh).map_err(|e| occ.locate(e, "CHAM_GD"))?
        }
    };
    let on = model.model()?.mesh_concept.clone();
    if let Some((m, occ)) = meshes.iter().find(|(m, _)| !Rc::ptr_eq(m, &on)) {
        return Err(
            occ.err("CHAM_GD", format!("the field lies on mesh {}, the result on mesh {}", m.label(), on.label()))
        );
    }
    steps.sort_by_key(|s| s.nume_ordre);
    Ok(ResultData {
        model,
        material: material.or(base_material),
        cara_elem: cara,
        loads,
        steps,
        comportement: Vec::new(),
    })
}

fn asse(ctx: &mut Ctx, a: &Args) -> Result<ResultData> {
    if let Some(r) = &ctx.reuse {
        return Err(a.err("ASSE", format!("OPERATION='ASSE' makes a new result: reuse={} is not accepted", r.label())));
    }
    let occs = a.facts("ASSE");
    let mut steps: Vec<Step> = Vec::new();
    let mut first: Option<(ConceptRef, Option<ConceptRef>)> = None;
    let mut mess = String::new();
    for occ in occs {
        let rc = occ.req_concept("RESULTAT")?;
        let shift = occ.real("TRANSLATION").unwrap_or(0.0);
        let r = rc.result().map_err(|e| occ.locate(e, "RESULTAT"))?;
        match &first {
            None => first = Some((r.model.clone(), r.material.clone())),
            Some((m, _)) => {
                let (a_mesh, b_mesh) = (&m.model()?.mesh_concept, &r.model.model()?.mesh_concept.clone());
                if !Rc::ptr_eq(a_mesh, b_mesh) {
                    return Err(occ.err(
                        "RESULTAT",
                        format!(
                            "{} lies on mesh {}, the first result on {}",
                            rc.label(),
                            b_mesh.label(),
                            a_mesh.label()
                        ),
                    ));
                }
            }
        }
        for s in &r.steps {
            let t = s.inst + shift;
            match steps.last_mut() {
                Some(prev) if t < prev.inst => {
                    return Err(occ.err(
                        "TRANSLATION",
                        format!(
                            "instant {t} of {} (order {}) comes before the previous instant {}: the result's \
                             instants must grow",
                            rc.label(),
                            s.nume_ordre,
                            prev.inst
                        ),
                    ))
                }
                Some(prev) if t == prev.inst => {
                    let _ = writeln!(
                        mess,
                        " CREA_RESU: instant {t} of {} is the previous one: its fields go to order {}",
                        rc.label(),
                        prev.nume_ordre
                    );
                    prev.fields.extend(s.fields.iter().map(|(k, v)| (k.clone(), v.clone())));
                }
                _ => {
                    let nume_ordre = steps.len() as i64 + 1;
                    steps.push(Step { nume_ordre, inst: t, fields: s.fields.clone() });
                }
            }
        }
    }
    ctx.io.mess(&mess);
    let (model, material) = first.ok_or_else(|| a.err("ASSE", "no result given"))?;
    Ok(ResultData { model, material, cara_elem: None, loads: Vec::new(), steps, comportement: Vec::new() })
}

// ------------------------------------------------------------------ PROL_RTZ

/// What lies beyond the table's radii.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Beyond {
    Exclu,
    Constant,
    Lineaire,
}

impl Beyond {
    fn of(s: Option<&str>) -> Beyond {
        match s {
            Some("CONSTANT") => Beyond::Constant,
            Some("LINEAIRE") => Beyond::Lineaire,
            _ => Beyond::Exclu,
        }
    }
}

/// The profile of one instant: radii in increasing order from 0 and their temperatures.
struct Profile {
    r: Vec<f64>,
    t: Vec<f64>,
}

impl Profile {
    /// The temperature at radius `x`, or Err(side) beyond an EXCLU side (true: left).
    fn at(&self, x: f64, left: Beyond, right: Beyond) -> std::result::Result<f64, bool> {
        let n = self.r.len();
        let line = |i: usize, j: usize| {
            let (r0, r1) = (self.r[i], self.r[j]);
            self.t[i] + (x - r0) / (r1 - r0) * (self.t[j] - self.t[i])
        };
        if x < 0.0 {
            return match left {
                Beyond::Exclu => Err(true),
                Beyond::Constant => Ok(self.t[0]),
                Beyond::Lineaire => Ok(line(0, 1)),
            };
        }
        match self.r.iter().position(|&r| x <= r) {
            Some(0) => Ok(self.t[0]),
            Some(j) => Ok(line(j - 1, j)),
            None => match right {
                Beyond::Exclu => Err(false),
                Beyond::Constant => Ok(self.t[n - 1]),
                Beyond::Lineaire => Ok(line(n - 2, n - 1)),
            },
        }
    }
}

fn norm(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if l == 0.0 {
        v
    } else {
        [v[0] / l, v[1] / l, v[2] / l]
    }
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The length of the part of `p` across the unit axis `z`.
fn across(p: &[f64; 3], z: &[f64; 3]) -> f64 {
    let s = dot(p, z);
    let q = [p[0] - s * z[0], p[1] - s * z[1], p[2] - s * z[2]];
    dot(&q, &q).sqrt()
}

fn prol_rtz(ctx: &mut Ctx, a: &Args) -> Result<ResultData> {
    if let Some(r) = &ctx.reuse {
        return Err(
            a.err("PROL_RTZ", format!("OPERATION='PROL_RTZ' makes a new result: reuse={} is not accepted", r.label()))
        );
    }
    let occ = a.fact("PROL_RTZ").ok_or_else(|| a.err("PROL_RTZ", "PROL_RTZ is required"))?;
    let mesh_c = occ.req_concept("MAILLAGE_FINAL")?;
    let mesh = mesh_c.mesh().map_err(|e| occ.locate(e, "MAILLAGE_FINAL"))?;
    if mesh.coords.iter().all(|c| c[2] == mesh.coords.first().map_or(0.0, |c0| c0[2])) {
        return Err(occ.err("MAILLAGE_FINAL", format!("mesh {} is not 3D (its Z is constant)", mesh_c.label())));
    }
    let tc = occ.req_concept("TABLE")?;
    let table = tc.table().map_err(|e| occ.locate(e, "TABLE"))?;
    let _ = occ.text("REPERE"); // CYLINDRIQUE, the only value
    let column = |name: &str| -> Result<Vec<Option<f64>>> {
        let k = table.require_column(name, &tc.label()).map_err(|e| occ.locate(e, "TABLE"))?;
        Ok(table.columns[k].cells.iter().map(|c| c.as_f64()).collect())
    };
    let (inst, coor, temp) = (column("INST")?, column("COOR_X")?, column("TEMP")?);
    // The instants: INST / LIST_INST, each found once in the table; else every instant of the table.
    let mut table_insts: Vec<f64> = Vec::new();
    for t in inst.iter().flatten() {
        if !table_insts.contains(t) {
            table_insts.push(*t);
        }
    }
    let asked = if occ.has("INST") {
        Some(occ.reals("INST"))
    } else if let Some(l) = occ.concept("LIST_INST") {
        Some(l.reals().map_err(|e| occ.locate(e, "LIST_INST"))?)
    } else {
        None
    };
    let (prec, relative) = match &asked {
        Some(_) => (occ.real("PRECISION").unwrap_or(1e-6), occ.text("CRITERE") != Some("ABSOLU")),
        None => (1e-6, true),
    };
    let kw = if occ.has("INST") { "INST" } else { "LIST_INST" };
    let times = match asked {
        Some(ts) => {
            for &t in &ts {
                let n = table_insts.iter().filter(|&&s| same_instant(s, t, prec, relative)).count();
                if n != 1 {
                    let what = if n == 0 { "no instant" } else { "several instants" };
                    return Err(occ.err(kw, format!("table {} has {what} INST={t}", tc.label())));
                }
            }
            ts
        }
        None => table_insts,
    };
    let z = norm(occ.reals("AXE_Z").try_into().map_err(|_| occ.err("AXE_Z", "three components"))?);
    let origin: [f64; 3] = occ.reals("ORIGINE").try_into().map_err(|_| occ.err("ORIGINE", "three components"))?;
    let r_ref = across(&origin, &z);
    let left = Beyond::of(occ.text("PROL_GAUCHE"));
    let right = Beyond::of(occ.text("PROL_DROITE"));
    let mut steps = Vec::new();
    for (k, &t) in times.iter().enumerate() {
        let mut pts: Vec<(f64, f64)> = Vec::new();
        for ((ti, r), v) in inst.iter().zip(&coor).zip(&temp) {
            if ti.is_some_and(|s| same_instant(s, t, prec, relative)) {
                match (r, v) {
                    (Some(r), Some(v)) => pts.push((*r, *v)),
                    _ => {
                        return Err(
                            occ.err("TABLE", format!("table {}: a row at INST={t} lacks COOR_X or TEMP", tc.label()))
                        )
                    }
                }
            }
        }
        if pts.is_empty() {
            return Err(occ.err("TABLE", format!("table {} has no row at INST={t}", tc.label())));
        }
        pts.sort_by(|p, q| p.0.total_cmp(&q.0));
        if pts[0].0 != 0.0 {
            return Err(
                occ.err("TABLE", format!("table {}: the radii (COOR_X) at INST={t} must start at 0", tc.label()))
            );
        }
        if pts.len() < 2 || pts.windows(2).any(|w| w[1].0 == w[0].0) {
            return Err(occ.err("TABLE", format!("table {}: two rows at INST={t} have the same radius", tc.label())));
        }
        let profile = Profile { r: pts.iter().map(|p| p.0).collect(), t: pts.iter().map(|p| p.1).collect() };
        let mut values = Vec::with_capacity(mesh.coords.len());
        for (i, p) in mesh.coords.iter().enumerate() {
            let x = across(p, &z) - r_ref;
            values.push(profile.at(x, left, right).map_err(|is_left| {
                let (kw, side) = if is_left { ("PROL_GAUCHE", "before") } else { ("PROL_DROITE", "past") };
                occ.err(
                    kw,
                    format!(
                        "node {} lies {side} the radii of table {} and {kw}='EXCLU'",
                        mesh.node_names[i],
                        tc.label()
                    ),
                )
            })?);
        }
        let field = Field::Node { components: vec!["TEMP".into()], values };
        steps.push(Step { nume_ordre: k as i64 + 1, inst: t, fields: BTreeMap::from([("TEMP".to_string(), field)]) });
    }
    let model = bare_model(&mesh_c).map_err(|e| occ.locate(e, "MAILLAGE_FINAL"))?;
    Ok(ResultData { model, material: None, cara_elem: None, loads: Vec::new(), steps, comportement: Vec::new() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_radial_profile_is_interpolated_and_extended_as_asked() {
        let p = Profile { r: vec![0.0, 1.0, 3.0], t: vec![10.0, 20.0, 0.0] };
        let (c, l, x) = (Beyond::Constant, Beyond::Lineaire, Beyond::Exclu);
        assert_eq!(p.at(0.0, x, x), Ok(10.0));
        assert_eq!(p.at(0.5, x, x), Ok(15.0));
        assert_eq!(p.at(2.0, x, x), Ok(10.0));
        assert_eq!(p.at(3.0, x, x), Ok(0.0));
        assert_eq!(p.at(4.0, x, c), Ok(0.0));
        assert_eq!(p.at(4.0, x, l), Ok(-10.0));
        assert_eq!(p.at(-1.0, c, x), Ok(10.0));
        assert_eq!(p.at(-1.0, l, x), Ok(0.0));
        assert_eq!(p.at(4.0, c, x), Err(false));
        assert_eq!(p.at(-0.5, x, c), Err(true));
    }

    #[test]
    fn the_radius_is_measured_across_the_axis_less_the_origin_s() {
        let z = norm([0.0, -25.0, 43.30127]);
        // A point on the axis's direction has no radius; one across it has its length.
        assert!(across(&[0.0, -2.5, 4.330127], &z) < 1e-6);
        let r = across(&[5.0, 0.0, 0.0], &z);
        assert!((r - 5.0).abs() < 1e-12);
        let q = [7.0, 0.866025, 0.5];
        assert!((across(&q, &z) - (49.0f64 + 1.0).sqrt()).abs() < 1e-5);
    }

    #[test]
    fn same_instant_follows_precision_and_criterion() {
        assert!(same_instant(1.0, 1.0, 0.0, true));
        assert!(!same_instant(1.0 + 1e-12, 1.0, 0.0, true));
        assert!(same_instant(1.0 + 1e-7, 1.0, 1e-6, true));
        assert!(same_instant(0.5, 1.0, 0.6, false));
        assert!(!same_instant(0.5, 1.0, 0.4, false));
    }
}
