//! TEST_TABLE and TEST_FONCTION: locate the value, then hand it to the verdict.

pub mod test_resu;
pub mod verdict;

use crate::catalog::args::Args;
use crate::concepts::table::Cell;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::select::filtered;
use crate::stages::Ctx;
use verdict::{check, check_text, Scalar};

pub fn test_table(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let tc = a.req_concept("TABLE")?;
    let name = tc.label();
    let t = tc.table()?;
    let para = a.req_text("NOM_PARA")?;
    let col = t.column(para).ok_or_else(|| {
        let names: Vec<&str> = t.columns.iter().map(|c| c.name.as_str()).collect();
        a.err("NOM_PARA", format!("table {name} has no parameter '{para}' (parameters: {})", names.join(", ")))
    })?;
    let rows = filtered(&t, a.facts("FILTRE"), &name)?;
    let cells: Vec<&Cell> = rows.iter().map(|&r| &t.columns[col].cells[r]).filter(|c| !c.is_empty()).collect();
    let mut title = format!("TABLE {name} NOM_PARA {para}");
    for f in a.facts("FILTRE") {
        let v = f
            .vals("VALE")
            .first()
            .or(f.vals("VALE_I").first())
            .or(f.vals("VALE_K").first())
            .map(|v| v.show())
            .unwrap_or_default();
        title.push_str(&format!(" {} {} {v}", f.text("NOM_PARA").unwrap_or(""), f.text("CRIT_COMP").unwrap_or("EQ")));
    }
    let value = match a.text("TYPE_TEST") {
        Some(tt) => {
            title.push_str(&format!(" TYPE_TEST {tt}"));
            let nums: Vec<f64> = cells.iter().filter_map(|c| c.as_f64()).collect();
            if nums.is_empty() {
                return Err(
                    a.err("TYPE_TEST", format!("no numeric value of '{para}' in the selected rows of table {name}"))
                );
            }
            let v = verdict::type_test(tt, &nums);
            let all_int = cells.iter().all(|c| matches!(c, Cell::Int(_)));
            if all_int && a.has_if_declared("VALE_CALC_I") {
                Scalar::I(v as i64)
            } else {
                Scalar::R(v)
            }
        }
        None => {
            if cells.len() != 1 {
                return Err(a.err(
                    "FILTRE",
                    format!(
                        "{} value(s) of '{para}' in table {name} match the filters; TEST_TABLE needs exactly one (or TYPE_TEST)",
                        cells.len()
                    ),
                ));
            }
            match cells[0] {
                Cell::Int(i) => Scalar::I(*i),
                Cell::Real(r) => Scalar::R(*r),
                Cell::Text(s) => Scalar::K(s.clone()),
                Cell::Empty => unreachable!(),
            }
        }
    };
    check(ctx, a, value, para, &title)?;
    Ok(None)
}

pub fn test_fonction(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    for occ in a.facts("VALEUR") {
        let c = occ.req_concept("FONCTION")?;
        let x = occ.reals("VALE_PARA");
        let names = occ.texts("NOM_PARA");
        let v = {
            let data = c.data();
            let expected: Vec<String> = match &*data {
                ConceptData::Function(f) => vec![f.nom_para.clone()],
                ConceptData::Nappe(n) => vec![n.nom_para.clone(), n.nom_para_fonc.clone()],
                ConceptData::Formula(f) => f.nom_para.clone(),
                _ => Vec::new(),
            };
            if !names.is_empty() && names != expected && !matches!(&*data, ConceptData::Function(_)) {
                return Err(occ.err(
                    "NOM_PARA",
                    format!("{} has parameters ({}), not ({})", c.label(), expected.join(", "), names.join(", ")),
                ));
            }
            let r = match (&*data, x.as_slice()) {
                (ConceptData::Function(f), [p]) => f.eval(*p),
                (ConceptData::Nappe(n), [p, q]) => n.eval(*p, *q),
                (ConceptData::Formula(f), xs) => f.eval(xs),
                _ => {
                    return Err(occ.err(
                        "VALE_PARA",
                        format!("{} ({}) cannot be evaluated at {} value(s)", c.label(), c.kind(), x.len()),
                    ))
                }
            };
            r.map_err(|e| e.at(occ.span))?
        };
        let at: Vec<String> = x.iter().map(|v| crate::text::float_repr(*v)).collect();
        let title = format!("FONCTION {} VALE_PARA ({})", c.label(), at.join(", "));
        check(ctx, occ, Scalar::R(v), "XXXX", &title)?;
    }
    for occ in a.facts("ATTRIBUT") {
        let c = occ.req_concept("FONCTION")?;
        let attr = occ.req_text("ATTR")?;
        let actual = {
            let data = c.data();
            match (&*data, attr) {
                (ConceptData::Function(f), "NOM_PARA") => f.nom_para.clone(),
                (ConceptData::Function(f), "NOM_RESU") => f.nom_resu.clone(),
                (ConceptData::Function(f), "PROL_GAUCHE") => f.prol_gauche.name().into(),
                (ConceptData::Function(f), "PROL_DROITE") => f.prol_droite.name().into(),
                (ConceptData::Function(f), "INTERPOL") => format!("{} {}", f.interp.0.name(), f.interp.1.name()),
                (ConceptData::Nappe(n), "NOM_PARA") => n.nom_para.clone(),
                (ConceptData::Nappe(n), "NOM_RESU") => n.nom_resu.clone(),
                (ConceptData::Nappe(n), "NOM_PARA_FONC") => n.nom_para_fonc.clone(),
                (ConceptData::Nappe(n), "PROL_GAUCHE") => n.prol_gauche.name().into(),
                (ConceptData::Nappe(n), "PROL_DROITE") => n.prol_droite.name().into(),
                (ConceptData::Formula(f), "NOM_PARA") => f.nom_para.join(" "),
                _ => {
                    return Err(occ
                        .err("ATTR", format!("attribute {attr} of {} ({}) is not supported yet", c.label(), c.kind())))
                }
            }
        };
        let expected = occ.req_text("ATTR_REFE")?;
        let title = format!("FONCTION {} ATTR {attr}", c.label());
        check_text(ctx, occ.text("REFERENCE").unwrap_or("NON_REGRESSION"), attr, expected, &actual, &title);
    }
    Ok(None)
}
