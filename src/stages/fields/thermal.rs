//! CALC_CHAMP on thermal results (THERMIQUE): the flux `−Λ∇T` at the integration points (`FLUX_ELGA`),
//! extrapolated to the nodes of each cell (`FLUX_ELNO`) and averaged over the cells at each node
//! (`FLUX_NOEU`); the temperature at the integration points (`TEMP_ELGA`); the Joule heat of a potential
//! computed as a temperature (`SOUR_ELGA`); the thermal energy of each cell (`ETHE_ELEM`). The laws are taken at each
//! step's instant and at the points' temperatures.

use crate::catalog::args::Args;
use crate::concepts::result::{Field, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::core::heat::thermal_problem;

/// The options computed on thermal results.
pub const OPTIONS: &[&str] = &["FLUX_ELGA", "FLUX_ELNO", "FLUX_NOEU", "TEMP_ELGA", "SOUR_ELGA", "ETHE_ELEM"];

pub fn calc_champ_ther(
    a: &Args,
    rc: &ConceptRef,
    model: &ConceptRef,
    chmat: &ConceptRef,
    mut steps: Vec<Step>,
    orders: &[i64],
) -> Result<Option<ConceptData>> {
    a.refuse(&[
        "CONTRAINTE",
        "DEFORMATION",
        "ENERGIE",
        "CRITERES",
        "VARI_INTERNE",
        "HYDRAULIQUE",
        "FORCE",
        "PROPRIETES",
        "CHAM_UTIL",
        "MODELE",
        "CHAM_MATER",
        "EXCIT",
        "GROUP_MA",
        "MAILLE",
    ])?;
    let _ = a.text("TOUT");
    let mut wanted = Vec::new();
    for o in a.texts("THERMIQUE") {
        if !OPTIONS.contains(&o.as_str()) {
            return Err(a.err("THERMIQUE", format!("option {o} is not supported yet ({} are)", OPTIONS.join(", "))));
        }
        wanted.push(o);
    }
    // The element characteristics given, else those the result was computed with.
    let cara = match a.concept("CARA_ELEM") {
        Some(c) => Some(c),
        None => rc.result()?.cara_elem.clone(),
    };
    let heat = thermal_problem(model, chmat, cara.as_ref(), None, true, &[]).map_err(|e| e.at(a.span))?;
    // The steps NUME_ORDRE / LIST_ORDRE / INST / LIST_INST select (every one when empty).
    for step in steps.iter_mut() {
        if !orders.is_empty() && !orders.contains(&step.nume_ordre) {
            continue;
        }
        let temp = step
            .fields
            .get("TEMP")
            .ok_or_else(|| a.err("RESULTAT", format!("no TEMP at order {}", step.nume_ordre)))?;
        let temps = heat.temps_of(temp, &rc.label()).map_err(|e| e.at(a.span))?;
        let fluxes = if wanted.iter().any(|o| o.starts_with("FLUX")) {
            Some(heat.flux_fields(&temps, step.inst).map_err(|e| e.at(a.span))?)
        } else {
            None
        };
        for o in &wanted {
            let f = match (o.as_str(), &fluxes) {
                ("FLUX_ELGA", Some((elga, _))) => elga.clone(),
                ("FLUX_ELNO", Some((_, elno))) => elno.clone(),
                ("FLUX_NOEU", Some((_, elno))) => {
                    let Field::Elno { components, cells } = elno else { unreachable!("ELNO") };
                    Field::Node {
                        components: components.clone(),
                        values: crate::fem::postpro::to_nodes(&heat.mesh, cells, components.len()),
                    }
                }
                ("SOUR_ELGA", _) => heat.sour_elga(&temps, step.inst).map_err(|e| e.at(a.span))?,
                ("ETHE_ELEM", _) => heat.energy(&temps, step.inst).map_err(|e| e.at(a.span))?,
                _ => heat.temp_elga(&temps).map_err(|e| e.at(a.span))?,
            };
            step.fields.insert(o.clone(), f);
        }
    }
    let r = rc.result()?;
    let data = r.with_steps(steps);
    Ok(Some(ConceptData::Result(data)))
}
