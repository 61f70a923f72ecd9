//! The thermal physics built from concepts: the thermal element of every cell of the model, the heat law
//! of every bulk cell from the material field (`THER`, `THER_FO`: λ and ρCp, reals or functions of the
//! time; `THER_NL`: λ(T) and the enthalpy β(T), tabulated), the walls ECHANGE_PAROI pairs, and the
//! functions of the temperature of FLUX_NL and SOUR_NL.

use super::eval::eval_named;
use super::settings::Settings;
use crate::concepts::function::Prol;
use crate::concepts::model::HeatItem;
use crate::concepts::model::{MatValue, Material, MaterialField, Role};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::frame::Frame;
use crate::fem::physics::OfTemperature;
use crate::thermal::physics::{Lambda, Law, Param, Thermal};
use crate::thermal::{Curve, Extension};
use std::rc::Rc;

/// A tabulated function of the temperature as `THER_NL` reads it: a DEFI_FONCTION of TEMP (its
/// interpolation read as linear, its prolongations kept) or a DEFI_CONSTANTE.
pub fn curve_of(c: &ConceptRef, what: &str) -> Result<Curve> {
    let ext = |p: Prol| match p {
        Prol::Constant => Extension::Constant,
        Prol::Lineaire => Extension::Linear,
        Prol::Exclu => Extension::Excluded,
    };
    match &*c.data() {
        ConceptData::Function(f) if f.nom_para == "TOUTPARA" => Ok(Curve::constant(f.y[0])),
        ConceptData::Function(f) if f.nom_para == "TEMP" => {
            Curve::new(f.x.clone(), f.y.clone(), ext(f.prol_gauche), ext(f.prol_droite))
                .map_err(|e| Error::runtime(format!("{what} ({}): {e}", c.label())))
        }
        ConceptData::Function(f) => Err(Error::runtime(format!(
            "{what} ({}) is a function of {}; a function of TEMP is needed",
            c.label(),
            f.nom_para
        ))),
        _ => Err(Error::unsupported(format!(
            "{what} ({}, {}): a tabulated function of TEMP (DEFI_FONCTION) is needed",
            c.label(),
            c.kind()
        ))),
    }
}

/// A function of the temperature (and of X, Y, Z, INST) at the instant `t`, with its derivative in the
/// temperature: a tabulated function of TEMP read as `THER_NL` reads it, else the function evaluated and
/// differenced centrally.
pub fn of_temperature<'a>(c: &'a ConceptRef, what: &str, t: f64) -> Result<OfTemperature<'a>> {
    let tabulated = matches!(&*c.data(), ConceptData::Function(f) if f.nom_para == "TEMP" || f.nom_para == "TOUTPARA");
    if tabulated {
        let curve = curve_of(c, what)?;
        return Ok(Box::new(move |_, temp| curve.eval(temp).map_err(|e| Error::runtime(e.to_string()))));
    }
    Ok(Box::new(move |x, temp| {
        let at = |tp: f64| {
            eval_named(c, &|p| match p {
                "X" => Ok(x[0]),
                "Y" => Ok(x[1]),
                "Z" => Ok(x[2]),
                "INST" => Ok(t),
                "TEMP" => Ok(tp),
                other => Err(Error::runtime(format!("{}: parameter {other} is not known here", c.label()))),
            })
        };
        let h = 1e-6 * temp.abs().max(1.0);
        Ok((at(temp)?, (at(temp + h)? - at(temp - h)?) / (2.0 * h)))
    }))
}

fn param(m: &Material, beh: &str, p: &str) -> Option<Param> {
    match m.behaviours.get(beh)?.get(p)? {
        MatValue::Real(v) => Some(Param::Real(*v)),
        MatValue::Func(c) => {
            let c = c.clone();
            Some(Param::OfTime(Rc::new(move |inst| {
                eval_named(&c, &|p| match p {
                    "INST" => Ok(inst),
                    other => Err(Error::unsupported(format!(
                        "{}: a thermal parameter depending on {other} is not supported yet (INST is)",
                        c.label()
                    ))),
                })
            })))
        }
        MatValue::Text(_) => None,
    }
}

/// λ_L, λ_T, λ_N of an orthotropic law by `get` (`missing` the error of an absent one); in the plane λ_N is
/// not used and may be absent (`zero` then).
fn three<P>(
    dim: usize,
    zero: P,
    get: impl Fn(&str) -> Result<Option<P>>,
    missing: impl Fn(&str) -> Error,
) -> Result<[P; 3]> {
    let [l, t, n] = ["LAMBDA_L", "LAMBDA_T", "LAMBDA_N"].map(|p| get(p).map(|v| (p, v)));
    let value = |(p, v): (&str, Option<P>)| v.ok_or_else(|| missing(p));
    let n = match n? {
        (_, None) if dim == 2 => zero,
        n => value(n)?,
    };
    Ok([value(l?)?, value(t?)?, n])
}

/// The heat law of a material; `cell` names it in messages, `frame` is its local frame (AFFE_CARA_ELEM
/// MASSIF: None without CARA_ELEM), `dim` the dimension of its element.
pub fn heat_law(m: &Material, cell: &str, frame: Option<Frame>, dim: usize) -> Result<Law> {
    let has = |b: &str| m.behaviours.contains_key(b);
    if let Some(b) = ["THER", "THER_FO"].into_iter().find(|b| has(b)) {
        let lambda = param(m, b, "LAMBDA").ok_or_else(|| Error::runtime(format!("cell {cell}: {b} without LAMBDA")))?;
        return Ok(Law::Linear { lambda: Lambda::Iso(lambda), rho_cp: param(m, b, "RHO_CP") });
    }
    if let Some(b) = ["THER_ORTH", "THER_NL_ORTH"].into_iter().find(|b| has(b)) {
        let frame = frame.ok_or_else(|| {
            Error::runtime(format!(
                "cell {cell}: {b} needs the local axes of its material: give CARA_ELEM (AFFE_CARA_ELEM MASSIF)"
            ))
        })?;
        let missing = |p: &str| Error::runtime(format!("cell {cell}: {b} without {p}"));
        if b == "THER_ORTH" {
            let l = three(dim, Param::Real(0.0), |p| Ok(param(m, b, p)), missing)?;
            return Ok(Law::Linear { lambda: Lambda::Ortho(l, frame), rho_cp: param(m, b, "RHO_CP") });
        }
        let func = |p: &str| match m.behaviours[b].get(p) {
            Some(MatValue::Func(c)) => Some(c.clone()),
            _ => None,
        };
        let get = |p: &str| func(p).map(|c| curve_of(&c, &format!("{b}/{p}"))).transpose();
        let l = three(dim, Curve::constant(0.0), get, missing)?;
        let beta = match (func("BETA"), func("RHO_CP")) {
            (Some(c), _) => curve_of(&c, &format!("{b}/BETA"))?,
            (None, Some(r)) => Curve::enthalpy(&curve_of(&r, &format!("{b}/RHO_CP"))?),
            (None, None) => return Err(missing("BETA or RHO_CP")),
        };
        return Ok(Law::Nonlinear { lambda: Lambda::Ortho(l, frame), beta });
    }
    if has("THER_NL") {
        let func = |p: &str| match m.behaviours["THER_NL"].get(p) {
            Some(MatValue::Func(c)) => Some(c.clone()),
            _ => None,
        };
        let lambda = func("LAMBDA").ok_or_else(|| Error::runtime(format!("cell {cell}: THER_NL without LAMBDA")))?;
        let lambda = curve_of(&lambda, "THER_NL/LAMBDA")?;
        let beta = match (func("BETA"), func("RHO_CP")) {
            (Some(b), _) => curve_of(&b, "THER_NL/BETA")?,
            (None, Some(r)) => Curve::enthalpy(&curve_of(&r, "THER_NL/RHO_CP")?),
            (None, None) => return Err(Error::runtime(format!("cell {cell}: THER_NL without BETA or RHO_CP"))),
        };
        return Ok(Law::Nonlinear { lambda: Lambda::Iso(lambda), beta });
    }
    let others: Vec<&str> = m.behaviours.keys().map(String::as_str).collect();
    Err(Error::runtime(format!(
        "cell {cell}: the material has no thermal behaviour (THER, THER_FO, THER_NL); it defines {}",
        if others.is_empty() { "nothing".to_string() } else { others.join(", ") }
    )))
}

/// The thermal problem of a model and a material field: `theta` None for steady steps only, `linear` for
/// THER_LINEAIRE, `couples` the nodes ECHANGE_PAROI joins.
pub fn thermal_problem(
    model: &ConceptRef,
    chmat: &ConceptRef,
    cara: Option<&ConceptRef>,
    theta: Option<f64>,
    linear: bool,
    couples: &[Vec<usize>],
) -> Result<Thermal> {
    let m = model.model()?;
    let mesh = m.current_mesh();
    let mut elements = vec![None; mesh.cells.len()];
    for (c, e) in m.elements.iter().enumerate() {
        let Some(e) = e else { continue };
        let Some(md) = e.modelisation.thermal() else {
            return Err(Error::runtime(format!(
                "model {} is not a thermal model (PHENOMENE='THERMIQUE'): {} on cell {}",
                model.label(),
                e.modelisation,
                mesh.cell_names[c]
            )));
        };
        elements[c] = Some((md, e.role == Role::Bulk));
    }
    if !elements.iter().flatten().any(|(_, bulk)| *bulk) {
        return Err(Error::runtime(format!("model {} has no volume element", model.label())));
    }
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { cells, .. }) = &*data else {
        return Err(Error::runtime(format!("{} holds no material field", chmat.label())));
    };
    let mut laws = vec![None; mesh.cells.len()];
    let cara = match cara {
        Some(c) => Some(c.cara_elem().map_err(|e| e.at_keyword("CARA_ELEM"))?),
        None => None,
    };
    // One law per material and frame.
    type Key = (*const crate::concepts::Concept, Option<Frame>);
    let mut cache: Vec<(Key, Rc<Law>)> = Vec::new();
    for (c, e) in elements.iter().enumerate() {
        if !e.is_some_and(|(_, bulk)| bulk) {
            continue;
        }
        let Some(mc) = &cells[c] else {
            return Err(Error::runtime(format!(
                "cell {} of the model has no material (AFFE_MATERIAU)",
                mesh.cell_names[c]
            ))
            .at_keyword("CHAM_MATER"));
        };
        let frame = cara.as_ref().map(|ca| ca.frame(c));
        let key = (Rc::as_ptr(mc), frame);
        let law = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, l)) => l.clone(),
            None => {
                let md = mc.data();
                let ConceptData::Material(mat) = &*md else { unreachable!("AFFE_MATERIAU holds materials") };
                let dim = e.map(|(m, _)| m.dim()).unwrap_or(mesh.dim);
                let l =
                    Rc::new(heat_law(mat, &mesh.cell_names[c], frame, dim).map_err(|e| e.at_keyword("CHAM_MATER"))?);
                cache.push((key, l.clone()));
                l
            }
        };
        laws[c] = Some(law);
    }
    Thermal::new(mesh, elements, laws, theta, linear, couples)
}

/// The nodes the loads of the settings' EXCIT join beyond the model's cells: each pair of walls of
/// ECHANGE_PAROI.
pub fn couples(cfg: &Settings, mesh: &crate::mesh::Mesh) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    for e in &cfg.excit {
        if let ConceptData::Load(l) = &*e.load.data() {
            for item in &l.items {
                if let crate::concepts::model::LoadItem::Heat(HeatItem::WallExchange { pairs, .. }) = item {
                    out.extend(pairs.iter().map(|(c, facing)| [&mesh.cells[*c][..], facing].concat()));
                }
            }
        }
    }
    out
}
