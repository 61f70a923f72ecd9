//! IMPR_RESU: results and meshes to MED (`med`, `med_fields`), as text (`text`, FORMAT='RESULTAT') and to GMSH
//! (`gmsh`); LIRE_RESU and LIRE_CHAMP from MED (`lire`);
//! the selection of steps and fields the formats share.

pub mod gmsh;
pub mod lire;
pub mod med;
pub mod med_fields;
pub mod text;

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::Ctx;

pub fn impr_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    match a.text("FORMAT").unwrap_or("MED") {
        "MED" => med::impr_resu_med(ctx, a),
        "RESULTAT" => text::impr_resu_text(ctx, a),
        "GMSH" => gmsh::impr_resu_gmsh(ctx, a),
        format => Err(a.err(
            "FORMAT",
            format!("IMPR_RESU FORMAT='{format}' is not supported yet (only 'MED', 'RESULTAT' and 'GMSH')"),
        )),
    }
}

/// The name a concept is printed under (its variable name).
pub fn concept_name(c: &ConceptRef, fallback: &str) -> String {
    let n = c.name();
    if n.is_empty() {
        fallback.to_string()
    } else {
        n
    }
}

/// The values of a LIST_ORDRE / LIST_INST concept.
pub fn list_of(occ: &Args, kw: &str) -> Result<Option<Vec<f64>>> {
    occ.concept(kw).map(|c| c.reals().map_err(|e| occ.err(kw, e.msg))).transpose()
}

/// The steps an occurrence selects (TOUT_ORDRE, NUME_ORDRE, LIST_ORDRE,
/// INST, LIST_INST; all steps by default), in the result's order.
pub fn selected_steps<'r>(r: &'r ResultData, occ: &Args, name: &str) -> Result<Vec<&'r Step>> {
    for kw in ["NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE", "FREQ", "LIST_FREQ"] {
        if occ.has_if_declared(kw) {
            return Err(occ.err(kw, format!("{kw} is not supported yet (only NUME_ORDRE and INST select steps)")));
        }
    }
    if r.steps.is_empty() {
        return Err(occ.err("RESULTAT", format!("result {name} holds no step")));
    }
    let mut wanted: Vec<i64> = Vec::new();
    let orders = if occ.has("NUME_ORDRE") {
        Some(("NUME_ORDRE", occ.ints("NUME_ORDRE")))
    } else {
        list_of(occ, "LIST_ORDRE")?.map(|v| ("LIST_ORDRE", v.iter().map(|&x| x as i64).collect()))
    };
    let insts = if occ.has("INST") {
        Some(("INST", occ.reals("INST")))
    } else {
        list_of(occ, "LIST_INST")?.map(|v| ("LIST_INST", v))
    };
    if let Some((kw, orders)) = orders {
        for n in orders {
            if r.by_order(n).is_none() {
                return Err(occ.err(kw, format!("result {name} has no order number {n}")));
            }
            wanted.push(n);
        }
    } else if let Some((kw, insts)) = insts {
        let crit = occ.text("CRITERE").unwrap_or("RELATIF");
        let prec = occ.real("PRECISION").unwrap_or(1.0e-6);
        for t in insts {
            let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
            let found: Vec<&Step> = r.steps.iter().filter(|s| (s.inst - t).abs() <= tol).collect();
            match found.as_slice() {
                [one] => wanted.push(one.nume_ordre),
                [] => {
                    return Err(occ.err(
                        kw,
                        format!("result {name} has no step at time {t} (CRITERE='{crit}', PRECISION={prec})"),
                    ))
                }
                many => {
                    let n: Vec<String> = many.iter().map(|s| s.nume_ordre.to_string()).collect();
                    return Err(occ.err(
                        kw,
                        format!("time {t} matches several steps of result {name} (order numbers {})", n.join(", ")),
                    ));
                }
            }
        }
    } else {
        return Ok(r.steps.iter().collect());
    }
    Ok(r.steps.iter().filter(|s| wanted.contains(&s.nume_ordre)).collect())
}

/// The fields an occurrence prints: NOM_CHAM (then `true`), none under
/// TOUT_CHAM='NON', else every field of the selected steps, sorted.
pub fn selected_fields(steps: &[&Step], occ: &Args) -> (bool, Vec<String>) {
    if occ.has("NOM_CHAM") {
        return (true, occ.texts("NOM_CHAM"));
    }
    if occ.text("TOUT_CHAM") == Some("NON") {
        return (false, Vec::new());
    }
    let all: std::collections::BTreeSet<&String> = steps.iter().flat_map(|s| s.fields.keys()).collect();
    (false, all.into_iter().cloned().collect())
}
