//! DEFI_LIST_INST with METHODE='MANUEL': the instants of a DEFI_LIST_REEL (or VALE) and Code_Aster's
//! answer to a step that fails (ECHEC: EVENEMENT='ERREUR', ACTION='DECOUPE' by default: the step is cut
//! in SUBD_PAS, at most SUBD_NIVEAU times, never below SUBD_PAS_MINI).

use crate::catalog::args::Args;
use crate::concepts::{ConceptData, Subdivision, TimeList};
use crate::diag::Result;
use crate::stages::Ctx;

pub fn defi_list_inst(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    time_list(a).map(|l| Some(ConceptData::ListInst(l)))
}

/// The time list of DEFI_LIST_INST's keywords.
pub fn time_list(a: &Args) -> Result<TimeList> {
    if a.text("METHODE") == Some("AUTO") {
        return Err(a.err("METHODE", "METHODE='AUTO' (adaptive time stepping) is not supported yet"));
    }
    a.refuse(&["MODELE"])?;
    let dl = a.fact("DEFI_LIST").ok_or_else(|| a.err("DEFI_LIST", "DEFI_LIST is required"))?;
    dl.refuse(&["RESULTAT", "SUBD_PAS"])?;
    let instants = match dl.concept("LIST_INST") {
        Some(l) => l.reals().map_err(|e| dl.err("LIST_INST", e.msg))?,
        None => dl.reals("VALE"),
    };
    let kw = if dl.has("LIST_INST") { "LIST_INST" } else { "VALE" };
    if instants.len() < 2 {
        return Err(dl.err(kw, format!("{} instant(s): a time list needs at least two", instants.len())));
    }
    if let Some(w) = instants.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)) {
        return Err(
            dl.err(kw, format!("the instants must increase strictly ({} then {})", instants[w], instants[w + 1]))
        );
    }
    let mut subdivision = None;
    let mut seen_error = false;
    for occ in a.facts("ECHEC") {
        let ev = occ.text("EVENEMENT").unwrap_or("ERREUR");
        if ev != "ERREUR" {
            return Err(occ.err("EVENEMENT", format!("EVENEMENT='{ev}' is not supported yet (ERREUR is)")));
        }
        if seen_error {
            return Err(occ.err("EVENEMENT", "EVENEMENT='ERREUR' is given twice"));
        }
        seen_error = true;
        if occ.text("ACTION") == Some("DECOUPE") {
            if occ.text("SUBD_METHODE") == Some("AUTO") {
                return Err(occ.err("SUBD_METHODE", "SUBD_METHODE='AUTO' is not supported yet (MANUEL is)"));
            }
            subdivision = Some(Subdivision {
                pas: occ.int("SUBD_PAS").unwrap_or(4).max(2) as usize,
                niveau: occ.int("SUBD_NIVEAU").unwrap_or(3).max(0) as usize,
                pas_mini: occ.real("SUBD_PAS_MINI").unwrap_or(0.0),
            });
        }
    }
    Ok(TimeList { instants, subdivision })
}

#[cfg(test)]
mod tests {
    use crate::catalog::{catalogue, validate};
    use crate::concepts::{Concept, ConceptData, ConceptKind};
    use crate::interp::{KwArg, Value};
    use crate::syntax::ast::Span;

    fn run(kw: Vec<(&str, Value)>) -> crate::diag::Result<ConceptData> {
        let kwargs =
            kw.into_iter().map(|(n, v)| KwArg { name: n.to_string(), value: v, span: Span::default() }).collect();
        let a = validate::validate(catalogue().hand_written("DEFI_LIST_INST").unwrap(), kwargs, Span::default())
            .unwrap()
            .args;
        super::time_list(&a).map(ConceptData::ListInst)
    }

    fn list(v: &[f64]) -> Value {
        let c = Concept::new(ConceptKind::ListR8, ConceptData::ListReal(v.to_vec()));
        Value::Concept(c)
    }

    fn f(items: Vec<(&str, Value)>) -> Value {
        let d = crate::interp::Dict { items: items.into_iter().map(|(k, v)| (Value::str(k), v)).collect() };
        Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d)))
    }

    #[test]
    fn default_failure_handling_cuts_in_four_three_times() {
        let d = run(vec![("DEFI_LIST", f(vec![("LIST_INST", list(&[0.0, 1.0, 3.0]))]))]).unwrap();
        let ConceptData::ListInst(l) = d else { panic!() };
        assert_eq!(l.instants, [0.0, 1.0, 3.0]);
        assert_eq!(l.subdivision, Some(crate::concepts::Subdivision { pas: 4, niveau: 3, pas_mini: 0.0 }));
    }

    #[test]
    fn arret_and_manual_subdivision() {
        let d = run(vec![
            ("DEFI_LIST", f(vec![("LIST_INST", list(&[0.0, 100.0]))])),
            (
                "ECHEC",
                f(vec![
                    ("ACTION", Value::str("DECOUPE")),
                    ("SUBD_METHODE", Value::str("MANUEL")),
                    ("SUBD_PAS", Value::Int(5)),
                    ("SUBD_PAS_MINI", Value::Float(0.1)),
                ]),
            ),
        ])
        .unwrap();
        let ConceptData::ListInst(l) = d else { panic!() };
        assert_eq!(l.subdivision, Some(crate::concepts::Subdivision { pas: 5, niveau: 3, pas_mini: 0.1 }));
        let d = run(vec![
            ("DEFI_LIST", f(vec![("LIST_INST", list(&[0.0, 100.0]))])),
            ("ECHEC", f(vec![("ACTION", Value::str("ARRET"))])),
        ])
        .unwrap();
        let ConceptData::ListInst(l) = d else { panic!() };
        assert_eq!(l.subdivision, None);
    }

    #[test]
    fn a_list_that_does_not_increase_is_refused() {
        let e = run(vec![(
            "DEFI_LIST",
            f(vec![("VALE", Value::list(vec![Value::Float(0.0), Value::Float(2.0), Value::Float(1.0)]))]),
        )])
        .unwrap_err();
        assert!(e.msg.contains("increase strictly (2 then 1)"), "{}", e.msg);
    }
}
