//! The checked elastic problem of a model and material field: modelisation, bulk cells, materials, dof numbering.

use super::settings::Settings;
use crate::concepts::model::{Material, MaterialField, Role};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::dofs::DofNumbering;
use crate::fem::elastic::Elastic;
use crate::fem::elasticity::{IsoElastic, Modelisation};
use crate::mesh::Mesh;
use std::rc::Rc;
/// a formula of no parameter). None when the parameter is not given.
/// A material parameter as a real: a real, or a function that does not
/// depend on a variable unknown here (DEFI_CONSTANTE, NOM_PARA 'TOUTPARA';
pub fn mat_param(m: &Material, behaviour: &str, param: &str, cell: &str) -> Result<Option<f64>> {
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
        let x = mat_param(m, beh, p, cell)?.ok_or_else(|| {
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
    let rho = mat_param(m, beh, "RHO", cell)?.unwrap_or(0.0);
    Ok((law, rho))
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
    let m = model.model()?;
    let mesh = m.current_mesh();
    let mut modelisation = None;
    let mut bulk = Vec::new();
    for (c, e) in m.elements.iter().enumerate() {
        let Some(e) = e else { continue };
        let Some(md) = e.modelisation.mechanics().filter(|_| !e.modelisation.is_hm()) else {
            return Err(Error::runtime(format!(
                "MODELISATION='{}' is not supported yet by this command (3D, D_PLAN, C_PLAN, AXIS are)",
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
    let mut cache: Vec<(*const crate::concepts::Concept, (IsoElastic, f64))> = Vec::new();
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
        let key = Rc::as_ptr(mc);
        let entry = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, v)) => *v,
            None => {
                let v = elastic_of(mat, &mesh.cell_names[c])?;
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
    let skin: Vec<bool> = {
        let m = cfg.model.model()?;
        m.elements.iter().map(|e| e.as_ref().is_some_and(|e| e.role == Role::Skin)).collect()
    };
    Elastic::new(p.mesh, p.modelisation, p.bulk, skin, p.materials, p.numbering, cfg.statics(), cfg.sief)
        .map_err(|e| e.at(cfg.span))
}
