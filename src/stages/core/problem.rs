//! The checked elastic problem of a model and material field: modelisation, bulk cells, materials, dof numbering.

use super::settings::Settings;
use crate::concepts::model::{MatValue, Material, MaterialField, Role, VarcSource};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::dofs::DofNumbering;
use crate::fem::elastic::{Elastic, NodalTemperature, ThermalStrain};
use crate::fem::elasticity::{IsoElastic, Modelisation};
use crate::fem::plastic::Plastic;
use crate::fem::plastic::{LawOfTemperature, Temperature};
use crate::fem::plasticity::{Beyond, Hardening, TractionCurve, VonMises};
use crate::mesh::Mesh;
use std::rc::Rc;
/// A material parameter as a real: a real, or a function that does not
/// depend on a variable unknown here (DEFI_CONSTANTE, NOM_PARA 'TOUTPARA';
/// a formula of no parameter). None when the parameter is not given.
pub fn mat_param(m: &Material, behaviour: &str, param: &str, cell: &str) -> Result<Option<f64>> {
    mat_param_at(m, behaviour, param, cell, None)
}

/// [`mat_param`] at a temperature, when one is known: a function (or formula) of TEMP is evaluated there.
pub fn mat_param_at(m: &Material, behaviour: &str, param: &str, cell: &str, temp: Option<f64>) -> Result<Option<f64>> {
    let Some(v) = m.behaviours.get(behaviour).and_then(|b| b.get(param)) else {
        return Ok(None);
    };
    let depends = |on: &str, what: &str| {
        Error::unsupported(format!(
            "cell {cell}: {behaviour}/{param} is {what} of {on}; material parameters depending on {on} \
             are not supported yet (only constants: reals or DEFI_CONSTANTE)"
        ))
    };
    use crate::concepts::model::MatValue;
    match v {
        MatValue::Real(r) => Ok(Some(*r)),
        MatValue::Text(t) => {
            Err(Error::runtime(format!("cell {cell}: {behaviour}/{param} is the text '{t}', not a number")))
        }
        MatValue::Func(c) => {
            let label = c.label();
            let what = format!("the function {label}");
            let value = match &*c.data() {
                ConceptData::Function(f) if f.nom_para == "TOUTPARA" => f.eval(0.0),
                ConceptData::Function(f) if f.nom_para == "TEMP" && temp.is_some() => f.eval(temp.unwrap_or(0.0)),
                ConceptData::Formula(f) if f.nom_para == ["TEMP"] && temp.is_some() => f.eval(&[temp.unwrap_or(0.0)]),
                ConceptData::Function(f) => return Err(depends(&f.nom_para, &what)),
                ConceptData::Nappe(n) => return Err(depends(&n.nom_para, &what)),
                ConceptData::Formula(f) if f.nom_para.is_empty() => f.eval(&[]),
                ConceptData::Formula(f) => return Err(depends(&f.nom_para.join(", "), &what)),
                _ => {
                    return Err(Error::runtime(format!(
                        "cell {cell}: {behaviour}/{param}: {label} ({}) is not a function",
                        c.kind()
                    )))
                }
            };
            value
                .map(Some)
                .map_err(|e| Error::runtime(format!("cell {cell}: {behaviour}/{param} ({label}): {}", e.msg)))
        }
    }
}

/// The elastic behaviours we compute with, and the parameters each requires.
const ELASTIC_BEHAVIOURS: &[(&str, &[&str])] = &[
    ("ELAS", &["E", "NU"]),
    ("ELAS_FO", &["E", "NU"]),
    ("ELAS_ISTR", &["E_L", "E_N", "NU_LT", "NU_LN", "G_LN"]),
    ("ELAS_ISTR_FO", &["E_L", "E_N", "NU_LT", "NU_LN", "G_LN"]),
];

/// The elastic law of a material and its density RHO (0 when not given).
pub fn elastic_of(m: &Material, cell: &str) -> Result<(IsoElastic, f64)> {
    elastic_of_at(m, cell, None)
}

/// [`elastic_of`] at a temperature, when one is known (parameters functions of TEMP evaluated there).
pub fn elastic_of_at(m: &Material, cell: &str, temp: Option<f64>) -> Result<(IsoElastic, f64)> {
    let Some((beh, params)) = ELASTIC_BEHAVIOURS.iter().find(|(b, _)| m.behaviours.contains_key(*b)) else {
        let others: Vec<&str> = m.behaviours.keys().map(String::as_str).collect();
        return Err(Error::unsupported(format!(
            "cell {cell}: the material has no ELAS (E, NU), ELAS_FO or ELAS_ISTR(_FO); it defines {}, \
             which this command does not support yet",
            if others.is_empty() { "nothing".to_string() } else { others.join(", ") }
        )));
    };
    let mut v = Vec::with_capacity(params.len());
    for p in params.iter() {
        let x = mat_param_at(m, beh, p, cell, temp)?.ok_or_else(|| {
            Error::unsupported(format!(
                "cell {cell}: {beh} without {p} is not supported yet ({} are needed)",
                params.join(", ")
            ))
        })?;
        v.push(x);
    }
    let law = match v[..] {
        [e, nu] => IsoElastic::new(e, nu),
        [e_l, e_n, nu_lt, nu_ln, g_ln] => IsoElastic::transverse_isotropic(e_l, e_n, nu_lt, nu_ln, g_ln)
            .map_err(|e| Error::runtime(format!("cell {cell}: {beh}: {e}")))?,
        _ => unreachable!("ELASTIC_BEHAVIOURS lists 2 or 5 parameters"),
    };
    let rho = mat_param_at(m, beh, "RHO", cell, temp)?.unwrap_or(0.0);
    Ok((law, rho))
}

/// The plastic behaviours the mechanics computes (COMPORTEMENT RELATION), besides ELAS.
pub const PLASTIC_RELATIONS: &[&str] = &["VMIS_ISOT_LINE", "VMIS_ISOT_TRAC"];

/// The law of COMPORTEMENT's `relation` (ELAS or one of [`PLASTIC_RELATIONS`]) on a cell of material `m`:
/// E and NU from ELAS; ECRO_LINE (or ECRO_LINE_FO, constant) for VMIS_ISOT_LINE; TRACTION's curve SIGM for
/// VMIS_ISOT_TRAC, whose first point gives the yield stress and the Young modulus the law uses, as
/// Code_Aster's `rctrac` does.
pub fn von_mises_of(m: &Material, relation: &str, cell: &str) -> Result<VonMises> {
    von_mises_at(m, relation, cell, None)
}

/// [`von_mises_of`] at a temperature, when one is known: the parameters functions of TEMP evaluated there,
/// a TRACTION nappe of TEMP interpolated there as Code_Aster's `rctrac` does.
pub fn von_mises_at(m: &Material, relation: &str, cell: &str, temp: Option<f64>) -> Result<VonMises> {
    let (elastic, _) = elastic_of_at(m, cell, temp)?;
    if !elastic.is_isotropic() {
        return Err(Error::unsupported(format!(
            "cell {cell}: RELATION='{relation}' on an anisotropic elastic material is not supported yet"
        )));
    }
    let (e, nu) = (elastic.e, elastic.nu);
    let need = |beh: &str, p: &str| -> Result<f64> {
        mat_param_at(m, beh, p, cell, temp)?
            .ok_or_else(|| Error::runtime(format!("cell {cell}: RELATION='{relation}' needs {beh}/{p}")))
    };
    let lib = |msg: String| Error::runtime(format!("cell {cell}: {msg}"));
    match relation {
        "ELAS" => Ok(VonMises::new(e, nu, None)),
        "VMIS_ISOT_LINE" => {
            let beh = if m.behaviours.contains_key("ECRO_LINE") { "ECRO_LINE" } else { "ECRO_LINE_FO" };
            if !m.behaviours.contains_key(beh) {
                return Err(Error::runtime(format!(
                    "cell {cell}: RELATION='VMIS_ISOT_LINE' needs ECRO_LINE (D_SIGM_EPSI, SY) in the material"
                )));
            }
            let h = Hardening::linear(e, need(beh, "D_SIGM_EPSI")?, need(beh, "SY")?).map_err(lib)?;
            Ok(VonMises::new(e, nu, Some(h)))
        }
        "VMIS_ISOT_TRAC" => {
            let Some(MatValue::Func(c)) = m.behaviours.get("TRACTION").and_then(|b| b.get("SIGM")) else {
                return Err(Error::runtime(format!(
                    "cell {cell}: RELATION='VMIS_ISOT_TRAC' needs TRACTION (SIGM) in the material"
                )));
            };
            use crate::concepts::function::Prol;
            let beyond = |p: Prol| match p {
                Prol::Exclu => Beyond::Error,
                Prol::Constant => Beyond::Constant,
                Prol::Lineaire => Beyond::Linear,
            };
            let data = c.data();
            let (h, e_curve) = match (&*data, temp) {
                (ConceptData::Function(f), _) => Hardening::traction(&f.x, &f.y, beyond(f.prol_droite)),
                (ConceptData::Nappe(n), Some(t)) if n.nom_para == "TEMP" => {
                    let curves: Vec<TractionCurve> = n
                        .params
                        .iter()
                        .zip(&n.functions)
                        .map(|(&temp, f)| TractionCurve {
                            temp,
                            eps: f.x.clone(),
                            sig: f.y.clone(),
                            beyond: beyond(f.prol_droite),
                        })
                        .collect();
                    Hardening::traction_at(&curves, beyond(n.prol_gauche), beyond(n.prol_droite), t)
                }
                (ConceptData::Nappe(n), None) if n.nom_para == "TEMP" => {
                    return Err(Error::unsupported(format!(
                        "cell {cell}: TRACTION/SIGM {} is a nappe of TEMP: it needs the temperature of AFFE_VARC \
                         (NOM_VARC='TEMP') on the cell",
                        c.label()
                    )))
                }
                _ => {
                    return Err(Error::unsupported(format!(
                        "cell {cell}: TRACTION/SIGM {} ({}) is neither a function of EPSI nor a nappe of TEMP: \
                         traction curves depending on another variable are not supported yet",
                        c.label(),
                        c.kind()
                    )))
                }
            }
            .map_err(lib)?;
            Ok(VonMises::new(e_curve, nu, Some(h)))
        }
        other => Err(Error::unsupported(format!("RELATION='{other}' is not supported yet"))),
    }
}

/// What a linear elastic computation is built from, checked.
pub struct Problem {
    pub mesh: Rc<Mesh>,
    pub modelisation: Modelisation,
    pub bulk: Vec<usize>,
    pub materials: Vec<Option<(IsoElastic, f64)>>,
    pub numbering: DofNumbering,
}

pub fn problem(model: &ConceptRef, chmat: &ConceptRef) -> Result<Problem> {
    problem_with(model, chmat, false)
}

/// [`problem`] with the parameters that depend on TEMP taken at AFFE_VARC's VALE_REF (for a result whose
/// laws followed the temperature and which holds its stresses).
pub fn problem_at_ref(model: &ConceptRef, chmat: &ConceptRef) -> Result<Problem> {
    problem_with(model, chmat, true)
}

/// [`problem`]; with `at_ref`, the cells under AFFE_VARC's temperature take their material parameters
/// that depend on TEMP at its VALE_REF (a law that follows the temperature replaces them later).
fn problem_with(model: &ConceptRef, chmat: &ConceptRef, at_ref: bool) -> Result<Problem> {
    let m = model.model()?;
    let mesh = m.current_mesh();
    let mut modelisation = None;
    let mut bulk = Vec::new();
    for (c, e) in m.elements.iter().enumerate() {
        let Some(e) = e else { continue };
        let Some(md) = e.modelisation.mechanics().filter(|_| !e.modelisation.is_hm()) else {
            return Err(Error::unsupported(format!(
                "AFFE_MODELE/MODELISATION: MODELISATION='{}' is not supported yet by this command (3D, D_PLAN, C_PLAN, AXIS are)",
                e.modelisation
            )));
        };
        if modelisation.is_some_and(|x| x != md) {
            return Err(Error::runtime("models mixing several modelisations are not supported yet"));
        }
        modelisation = Some(md);
        if e.role == Role::Bulk {
            bulk.push(c);
        }
    }
    let modelisation = modelisation.ok_or_else(|| Error::runtime(format!("model {} has no element", model.label())))?;
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { cells, .. }) = &*data else {
        return Err(Error::runtime(format!("{} holds no material field", chmat.label())));
    };
    let mut materials = vec![None; mesh.cells.len()];
    let refs = if at_ref { temperature_refs(chmat, mesh.cells.len()) } else { vec![None; mesh.cells.len()] };
    // One evaluation per material concept and reference temperature.
    type Key = (*const crate::concepts::Concept, Option<u64>);
    let mut cache: Vec<(Key, (IsoElastic, f64))> = Vec::new();
    for &c in &bulk {
        let Some(mc) = &cells[c] else {
            return Err(Error::runtime(format!(
                "cell {} of the model has no material (AFFE_MATERIAU)",
                mesh.cell_names[c]
            )));
        };
        let md = mc.data();
        let ConceptData::Material(mat) = &*md else { unreachable!("AFFE_MATERIAU holds materials") };
        // One evaluation per material concept.
        let key = (Rc::as_ptr(mc), refs[c].map(f64::to_bits));
        let entry = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, v)) => *v,
            None => {
                let v = elastic_of_at(mat, &mesh.cell_names[c], refs[c])?;
                if let Err(e) = v.0.check(modelisation) {
                    return Err(Error::unsupported(format!("cell {}: {e}", mesh.cell_names[c])));
                }
                cache.push((key, v));
                v
            }
        };
        materials[c] = Some(entry);
    }
    let numbering = DofNumbering::for_cells(&mesh, modelisation.dim(), &bulk);
    Ok(Problem { mesh, modelisation, bulk, materials, numbering })
}

pub use crate::fem::elastic::coords_of;

/// The elastic physics of a solving command's model and material field: element stiffnesses computed
/// once, one solve per step for MECA_STATIQUE, SIEF_ELGA unless OPTION='SANS'.
pub fn elastic(cfg: &Settings, chmat: &ConceptRef) -> Result<Elastic> {
    let p = problem(&cfg.model, chmat).map_err(|e| e.at(cfg.span))?;
    let thermal = thermal_strain(chmat, &p).map_err(|e| cfg.locate(e, "CHAM_MATER"))?;
    let e = elastic_of_problem(cfg, p)?;
    Ok(match thermal {
        Some(t) => e.with_thermal(t),
        None => e,
    })
}

/// The elastic physics of a checked problem, without thermal strain.
fn elastic_of_problem(cfg: &Settings, p: Problem) -> Result<Elastic> {
    let skin: Vec<bool> = {
        let m = cfg.model.model()?;
        m.elements.iter().map(|e| e.as_ref().is_some_and(|e| e.role == Role::Skin)).collect()
    };
    Elastic::new(p.mesh, p.modelisation, p.bulk, skin, p.materials, p.numbering, cfg.statics(), cfg.sief)
        .map_err(|e| e.at(cfg.span))
}

/// The plastic physics of STAT_NON_LINE's model and material field: the elastic problem (its unknowns and
/// loads) with the law of COMPORTEMENT's relation on every bulk cell (the occurrences apply in their
/// order, a later one over an earlier one on the cells they share; ELAS where none applies).
pub fn plastic(cfg: &Settings, chmat: &ConceptRef) -> Result<Plastic> {
    let varc = super::settings::has_varc(chmat);
    let e = if varc {
        // The laws take the temperature in (thermal strain, parameters of TEMP): no thermal forces.
        let p = problem_with(&cfg.model, chmat, true).map_err(|e| e.at(cfg.span))?;
        elastic_of_problem(cfg, p)?
    } else {
        elastic(cfg, chmat)?
    }
    .storing_stresses(false);
    let refs = temperature_refs(chmat, e.mesh.cells.len());
    // The occurrence of COMPORTEMENT that decides each cell's law.
    let mut which: Vec<Option<usize>> = vec![None; e.mesh.cells.len()];
    for (k, b) in cfg.behaviours.iter().enumerate() {
        match &b.cells {
            Some(cells) => cells.iter().for_each(|&c| which[c] = Some(k)),
            None => which.iter_mut().for_each(|w| *w = Some(k)),
        }
    }
    let mut laws: Vec<Option<VonMises>> = vec![None; e.mesh.cells.len()];
    {
        let data = chmat.data();
        let ConceptData::MaterialField(MaterialField { cells, .. }) = &*data else {
            return Err(cfg.err("CHAM_MATER", format!("{} holds no material field", chmat.label())));
        };
        type Key = (*const crate::concepts::Concept, Option<usize>, Option<u64>);
        let mut cache: Vec<(Key, VonMises)> = Vec::new();
        for &c in &e.bulk {
            let mc = cells[c].as_ref().expect("the elastic problem checked every bulk cell's material");
            let key = (Rc::as_ptr(mc), which[c], refs[c].map(f64::to_bits));
            let law = match cache.iter().find(|(k, _)| *k == key) {
                Some((_, l)) => l.clone(),
                None => {
                    let md = mc.data();
                    let ConceptData::Material(mat) = &*md else { unreachable!("AFFE_MATERIAU holds materials") };
                    let b = which[c].map(|k| &cfg.behaviours[k]);
                    let relation = b.map_or("ELAS", |b| b.relation.as_str());
                    let l = von_mises_at(mat, relation, &e.mesh.cell_names[c], refs[c]).map_err(|err| match b {
                        Some(b) => b.err("RELATION", err.msg),
                        None => err.at(cfg.span),
                    })?;
                    let l = match b {
                        Some(b) => VonMises { resi_inte: b.resi_inte, iter_inte: b.iter_inte, ..l },
                        None => l,
                    };
                    cache.push((key, l.clone()));
                    l
                }
            };
            laws[c] = Some(law);
        }
    }
    let mut relations: Vec<String> = Vec::new();
    for b in &cfg.behaviours {
        let r = format!("'{}'", b.relation);
        if !relations.contains(&r) {
            relations.push(r);
        }
    }
    let temperature = if varc { Some(plastic_temperature(cfg, chmat, &e, &which)?) } else { None };
    let mut p = Plastic::new(e, &laws, relations.join(", ")).map_err(|err| err.at(cfg.span))?;
    p.elastic_prediction = cfg.matrices.prediction_elastic;
    p.elastic_correction = cfg.matrices.correction_elastic;
    Ok(match temperature {
        Some(t) => p.with_temperature(t),
        None => p,
    })
}

/// Whether AFFE_VARC's temperature acts on the elastic law itself on some cell (ELAS_FO's E, NU or ALPHA a
/// function or formula of TEMP): the law must then follow the temperature point by point ([`plastic`]'s
/// laws do, ELAS among them), not once per cell.
pub fn elasticity_follows_temperature(chmat: &ConceptRef) -> bool {
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { varc, cells, .. }) = &*data else { return false };
    let of_temp = |v: &MatValue| match v {
        MatValue::Func(c) => match &*c.data() {
            ConceptData::Function(f) => f.nom_para == "TEMP",
            ConceptData::Formula(f) => f.nom_para.iter().any(|p| p == "TEMP"),
            _ => false,
        },
        _ => false,
    };
    varc.iter().flat_map(|v| v.cells.iter()).filter_map(|&c| cells.get(c).and_then(|m| m.as_ref())).any(|mc| {
        let md = mc.data();
        let ConceptData::Material(m) = &*md else { return false };
        ["ELAS", "ELAS_FO"]
            .iter()
            .filter_map(|b| m.behaviours.get(*b))
            .any(|b| ["E", "NU", "ALPHA"].iter().filter_map(|p| b.get(*p)).any(of_temp))
    })
}

/// Per mesh cell, the VALE_REF of the AFFE_VARC temperature that covers it (the last occurrence).
fn temperature_refs(chmat: &ConceptRef, ncells: usize) -> Vec<Option<f64>> {
    let mut out = vec![None; ncells];
    if let ConceptData::MaterialField(MaterialField { varc, .. }) = &*chmat.data() {
        for v in varc {
            for &c in v.cells.iter().filter(|&&c| c < ncells) {
                out[c] = v.vale_ref;
            }
        }
    }
    out
}

/// The temperature of AFFE_VARC as the plastic laws follow it: its sources, and per bulk cell it covers
/// the law of COMPORTEMENT's relation (occurrence `which[c]`) and the thermal expansion coefficient at
/// any temperature.
fn plastic_temperature(
    cfg: &Settings,
    chmat: &ConceptRef,
    e: &Elastic,
    which: &[Option<usize>],
) -> Result<Temperature> {
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { varc, cells: mats, .. }) = &*data else {
        return Err(cfg.err("CHAM_MATER", format!("{} holds no material field", chmat.label())));
    };
    let nnodes = e.mesh.nnodes();
    let mut sources = Vec::with_capacity(varc.len());
    let mut cells: Vec<Option<(f64, usize, LawOfTemperature)>> = vec![None; e.mesh.cells.len()];
    let bulk: std::collections::HashSet<usize> = e.bulk.iter().copied().collect();
    for (k, v) in varc.iter().enumerate() {
        let tref = v.vale_ref.ok_or_else(|| {
            cfg.err("CHAM_MATER", "AFFE_VARC: NOM_VARC='TEMP' needs VALE_REF (the temperature that strains nothing)")
        })?;
        for &c in v.cells.iter().filter(|c| bulk.contains(c)) {
            let Some(mc) = mats[c].clone() else { continue };
            let name = e.mesh.cell_names[c].clone();
            let relation = which[c].map_or("ELAS".to_string(), |b| cfg.behaviours[b].relation.clone());
            let alpha = {
                let md = mc.data();
                let ConceptData::Material(mat) = &*md else { continue };
                alpha_of(mat, &name, tref).map_err(|e| cfg.locate(e, "CHAM_MATER"))?
            };
            let law: LawOfTemperature = Rc::new(move |t: f64| {
                let md = mc.data();
                let ConceptData::Material(mat) = &*md else {
                    return Err("the material field holds no material".into());
                };
                let law = von_mises_at(mat, &relation, &name, Some(t)).map_err(|e| e.msg)?;
                Ok((law, alpha(t).map_err(|e| e.msg)?))
            });
            cells[c] = Some((tref, k, law));
        }
        sources.push(varc_source(v, nnodes)?);
    }
    Ok(Temperature { sources, cells, natural_start: cfg.statics() })
}

/// Per mesh cell of the problem's bulk under AFFE_VARC's temperature: the temperature of its nodes at `t`
/// (None elsewhere).
pub fn cell_temperatures(chmat: &ConceptRef, p: &Problem, t: f64) -> Result<Vec<Option<Vec<f64>>>> {
    let data = chmat.data();
    let mut out = vec![None; p.mesh.cells.len()];
    let ConceptData::MaterialField(MaterialField { varc, .. }) = &*data else { return Ok(out) };
    for v in varc {
        let nodal = varc_source(v, p.mesh.nnodes())?(t)?;
        let n = out.len();
        for &c in v.cells.iter().filter(|&&c| c < n && p.materials[c].is_some()) {
            let temps: Vec<f64> = p.mesh.cells[c].iter().map(|&n| nodal.get(n).copied().unwrap_or(f64::NAN)).collect();
            if let Some(k) = temps.iter().position(|x| !x.is_finite()) {
                return Err(Error::runtime(format!(
                    "AFFE_VARC: no temperature at node {} of cell {} at INST={t}",
                    p.mesh.node_names[p.mesh.cells[c][k]], p.mesh.cell_names[c]
                )));
            }
            out[c] = Some(temps);
        }
    }
    Ok(out)
}

/// The thermal expansion coefficient of ELAS / ELAS_FO at a temperature, as Code_Aster defines it for a
/// strain `α(T) (T − T_ref)`: ALPHA a real, or a function of TEMP given for a strain measured from
/// TEMP_DEF_ALPHA, which is turned into the coefficient measured from `tref` point by point (`alfint`:
/// within PRECISION of `tref`, the limit through the curve's slope). 0 without ALPHA.
type Alpha = Rc<dyn Fn(f64) -> Result<f64>>;
fn alpha_of(mat: &Material, cell: &str, tref: f64) -> Result<Alpha> {
    let beh = if mat.behaviours.contains_key("ELAS") { "ELAS" } else { "ELAS_FO" };
    let Some(v) = mat.behaviours.get(beh).and_then(|b| b.get("ALPHA")) else { return Ok(Rc::new(|_| Ok(0.0))) };
    let tdef = mat_param(mat, beh, "TEMP_DEF_ALPHA", cell)?;
    let func = match v {
        MatValue::Func(c) => match &*c.data() {
            ConceptData::Function(f) if f.nom_para == "TEMP" => Some(f.clone()),
            _ => None,
        },
        _ => None,
    };
    let Some(f) = func else {
        // A constant, or a formula of TEMP (no TEMP_DEF_ALPHA transform: Code_Aster asks for a function).
        if tdef.is_some() && matches!(v, MatValue::Func(c) if matches!(&*c.data(), ConceptData::Formula(_))) {
            return Err(Error::runtime(format!(
                "cell {cell}: {beh}/ALPHA with TEMP_DEF_ALPHA must be a function (DEFI_FONCTION), not a formula"
            )));
        }
        let (m, c) = (mat.clone(), cell.to_string());
        return Ok(Rc::new(move |t| Ok(mat_param_at(&m, beh, "ALPHA", &c, Some(t))?.unwrap_or(0.0))));
    };
    let Some(tdef) = tdef.filter(|_| f.x.len() > 1) else {
        return Ok(Rc::new(move |t| f.eval(t)));
    };
    let prec = mat_param(mat, beh, "PRECISION", cell)?.unwrap_or(1.0);
    let a_ref = f.eval(tref)?;
    let n = f.x.len();
    let mut g = f.clone();
    for i in 0..n {
        let ti = f.x[i];
        g.y[i] = if (ti - tref).abs() >= prec {
            (f.y[i] * (ti - tdef) - a_ref * (tref - tdef)) / (ti - tref)
        } else {
            let slope = |j: usize| (f.y[j] - a_ref) / (f.x[j] - tref);
            let d = match i {
                0 => slope(1),
                _ if i == n - 1 => slope(n - 2),
                _ => 0.5 * (slope(i + 1) + slope(i - 1)),
            };
            if !d.is_finite() {
                return Err(Error::runtime(format!(
                    "cell {cell}: {beh}/ALPHA: two temperatures of the function lie at VALE_REF = {tref}"
                )));
            }
            d * (tref - tdef) + a_ref
        };
    }
    Ok(Rc::new(move |t| g.eval(t)))
}

/// The thermal strain of the material field's AFFE_VARC (NOM_VARC='TEMP') on the problem's bulk cells:
/// α from ELAS's ALPHA (none: no thermal strain), T_ref from VALE_REF, the temperature from the EVOL_THER
/// (interpolated linearly in time between its instants, PROL_GAUCHE / PROL_DROITE beyond) or the field.
pub fn thermal_strain(chmat: &ConceptRef, p: &Problem) -> Result<Option<ThermalStrain>> {
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { varc, cells: mats, .. }) = &*data else { return Ok(None) };
    if varc.is_empty() {
        return Ok(None);
    }
    let nnodes = p.mesh.nnodes();
    let mut sources: Vec<NodalTemperature> = Vec::new();
    let mut cells = vec![None; p.mesh.cells.len()];
    let bulk: std::collections::HashSet<usize> = p.bulk.iter().copied().collect();
    for (k, v) in varc.iter().enumerate() {
        let tref = v.vale_ref.ok_or_else(|| {
            Error::runtime("AFFE_VARC: NOM_VARC='TEMP' needs VALE_REF (the temperature that strains nothing)")
        })?;
        for &c in v.cells.iter().filter(|c| bulk.contains(c)) {
            let Some(mc) = &mats[c] else { continue };
            let md = mc.data();
            let ConceptData::Material(mat) = &*md else { continue };
            let beh = if mat.behaviours.contains_key("ELAS") { "ELAS" } else { "ELAS_FO" };
            if let Some(alpha) = mat_param(mat, beh, "ALPHA", &p.mesh.cell_names[c])? {
                cells[c] = Some((alpha, tref, k));
            }
        }
        sources.push(varc_source(v, nnodes)?);
    }
    Ok(Some(ThermalStrain { sources, cells }))
}

/// The temperature at the nodes at any instant of one AFFE_VARC occurrence.
fn varc_source(v: &crate::concepts::model::Varc, nnodes: usize) -> Result<NodalTemperature> {
    Ok(match &v.source {
        VarcSource::Field(f) => {
            let values = temp_of_field(f.field()?.reals(&f.label())?, nnodes, &f.label())?;
            Box::new(move |_t| Ok(values.clone()))
        }
        VarcSource::Evol { result, field, fonc_inst } => {
            let (result, field, prol, fonc) = (result.clone(), field.clone(), v.prol.clone(), fonc_inst.clone());
            Box::new(move |t| {
                // FONC_INST: the result is read at the instant the function gives for the current one.
                let at = match &fonc {
                    Some(f) => super::eval::eval_at(f, &[0.0; 3], t)
                        .map_err(|e| Error::runtime(format!("AFFE_VARC/FONC_INST: {}", e.msg)))?,
                    None => t,
                };
                temp_of_result(&result, &field, &prol, at, nnodes)
            })
        }
    })
}

/// The component TEMP of a field on nodes, per node (NaN where it has none).
fn temp_of_field(f: &crate::concepts::result::Field, nnodes: usize, what: &str) -> Result<Vec<f64>> {
    let crate::concepts::result::Field::Node { components, values } = f else {
        return Err(Error::runtime(format!("AFFE_VARC: {what} is not a field on nodes")));
    };
    let k = components
        .iter()
        .position(|c| c == "TEMP")
        .ok_or_else(|| Error::runtime(format!("AFFE_VARC: {what} has no component TEMP")))?;
    let n = components.len();
    Ok((0..nnodes).map(|i| values.get(i * n + k).copied().unwrap_or(f64::NAN)).collect())
}

/// The temperature of `result` at `t`: its field `field` at that instant, or interpolated linearly between
/// the two around it; before the first / after the last as PROL_GAUCHE / PROL_DROITE say (EXCLU: an error,
/// CONSTANT: the end value, LINEAIRE: the line of the two end instants).
fn temp_of_result(
    result: &ConceptRef,
    field: &str,
    prol: &(String, String),
    t: f64,
    nnodes: usize,
) -> Result<Vec<f64>> {
    let r = result.result()?;
    let mut steps: Vec<(f64, &crate::concepts::result::Field)> =
        r.steps.iter().filter_map(|s| s.fields.get(field).map(|f| (s.inst, f))).collect();
    steps.sort_by(|a, b| a.0.total_cmp(&b.0));
    let label = result.label();
    let at = |i: usize| temp_of_field(steps[i].1, nnodes, &label);
    let blend = |i: usize, j: usize| -> Result<Vec<f64>> {
        let (a, b) = (at(i)?, at(j)?);
        let w = (t - steps[i].0) / (steps[j].0 - steps[i].0);
        Ok(a.iter().zip(&b).map(|(x, y)| x + w * (y - x)).collect())
    };
    let n = steps.len();
    if n == 0 {
        return Err(Error::runtime(format!("AFFE_VARC: {label} holds no field {field}")));
    }
    let tol = 1e-10 * t.abs().max(1.0);
    if let Some(i) = steps.iter().position(|s| (s.0 - t).abs() <= tol) {
        return at(i);
    }
    let beyond = |side: &str, kw: &str, end: usize, other: usize| -> Result<Vec<f64>> {
        match side {
            "CONSTANT" => at(end),
            "LINEAIRE" if n > 1 => blend(other.min(end), other.max(end)),
            _ => Err(Error::runtime(format!(
                "AFFE_VARC: INST={t} lies outside the instants of {label} ({} to {}) and {kw}='{side}'",
                steps[0].0,
                steps[n - 1].0
            ))),
        }
    };
    if t < steps[0].0 {
        return beyond(&prol.0, "PROL_GAUCHE", 0, 1);
    }
    if t > steps[n - 1].0 {
        return beyond(&prol.1, "PROL_DROITE", n - 1, n.saturating_sub(2));
    }
    let i = steps.iter().rposition(|s| s.0 < t).expect("t lies within the instants");
    blend(i, i + 1)
}
