//! CALC_CHAMP on thermal results (THERMIQUE): the flux `−Λ∇T` at the integration points (`FLUX_ELGA`),
//! extrapolated to the nodes of each cell (`FLUX_ELNO`) and averaged over the cells at each node
//! (`FLUX_NOEU`); the temperature at the integration points (`TEMP_ELGA`); the Joule heat of a potential
//! computed as a temperature (`SOUR_ELGA`). The laws are taken at each
//! step's instant and at the points' temperatures.

use crate::catalog::args::Args;
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::core::heat::thermal_problem;

/// The options computed on thermal results.
pub const OPTIONS: &[&str] = &["FLUX_ELGA", "FLUX_ELNO", "FLUX_NOEU", "TEMP_ELGA", "SOUR_ELGA"];

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
    let heat = thermal_problem(model, chmat, None, true, &[]).map_err(|e| e.at(a.span))?;
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
        let (elga, elno) = heat.flux_fields(&temps, step.inst).map_err(|e| e.at(a.span))?;
        for o in &wanted {
            let f = match o.as_str() {
                "FLUX_ELGA" => elga.clone(),
                "FLUX_ELNO" => elno.clone(),
                "FLUX_NOEU" => {
                    let Field::Elno { components, cells } = &elno else { unreachable!("ELNO") };
                    Field::Node {
                        components: components.clone(),
                        values: crate::fem::postpro::to_nodes(&heat.mesh, cells, components.len()),
                    }
                }
                "SOUR_ELGA" => heat.sour_elga(&temps, step.inst).map_err(|e| e.at(a.span))?,
                _ => heat.temp_elga(&temps).map_err(|e| e.at(a.span))?,
            };
            step.fields.insert(o.clone(), f);
        }
    }
    let r = rc.result()?;
    let data = ResultData { model: r.model.clone(), material: r.material.clone(), loads: r.loads.clone(), steps };
    Ok(Some(ConceptData::Result(data)))
}
