//! STAT_NON_LINE for COMPORTEMENT RELATION='ELAS': a Newton loop per time
//! step on the reduced system of `statics`, with Code_Aster's convergence
//! keywords. The same driver will carry the contact and HM laws; until they
//! exist, any other behaviour stops with a located message.

use super::statics::{assemble, problem, solve_reduced, solver_options, step_fields, System};
use super::Ctx;
use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::solve;

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The computation instants: the list, cut to INST_INIT / INST_FIN (or their
/// NUME_INST_* forms). The first one is the initial state.
pub(super) fn instants(a: &Args) -> Result<Vec<f64>> {
    let inc = a.fact("INCREMENT").ok_or_else(|| a.err("INCREMENT", "INCREMENT is required"))?;
    let lc = inc.req_concept("LIST_INST")?;
    let list = match &*lc.data() {
        ConceptData::ListReal(v) => v.clone(),
        _ => {
            return Err(inc.err(
                "LIST_INST",
                format!("{} ({}) is not supported yet: give a DEFI_LIST_REEL", lc.label(), lc.kind()),
            ))
        }
    };
    let prec = inc.real("PRECISION").unwrap_or(1e-6);
    let find = |t: f64, kw: &str| -> Result<usize> {
        list.iter()
            .position(|&x| (x - t).abs() <= prec * t.abs().max(1e-300) || x == t)
            .ok_or_else(|| inc.err(kw, format!("{t} is not an instant of {}", lc.label())))
    };
    let first = match (inc.int("NUME_INST_INIT"), inc.real("INST_INIT")) {
        (Some(n), _) => n as usize,
        (None, Some(t)) => find(t, "INST_INIT")?,
        _ => 0,
    };
    let last = match (inc.int("NUME_INST_FIN"), inc.real("INST_FIN")) {
        (Some(n), _) => n as usize,
        (None, Some(t)) => find(t, "INST_FIN")?,
        _ => list.len() - 1,
    };
    if first >= last || last >= list.len() {
        return Err(inc.err("LIST_INST", format!("no step to compute between instants #{first} and #{last}")));
    }
    Ok(list[first..=last].to_vec())
}

/// STAT_NON_LINE keywords no driver implements yet, and METHODE other than NEWTON.
pub(super) fn refuse_unsupported_options(a: &Args) -> Result<()> {
    a.refuse(&[
        "SOUS_STRUC",
        "ETAT_INIT",
        "RECH_LINEAIRE",
        "PILOTAGE",
        "OBSERVATION",
        "SUIVI_DDL",
        "CRIT_QUALITE",
        "ENERGIE",
        "CRIT_STAB",
        "RESULTAT",
    ])?;
    if a.text("METHODE").is_some_and(|m| m != "NEWTON") {
        return Err(a.err("METHODE", "only METHODE='NEWTON' is supported yet"));
    }
    Ok(())
}

pub fn stat_non_line(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if let Some(mo) = a.concept("MODELE") {
        if super::model::model_of(&mo)?.xfem.is_some() {
            return super::xfem_solve::stat_non_line_xfem(ctx, a, &mo);
        }
    }
    a.refuse(&["CONTACT", "SCHEMA_THM"])?;
    refuse_unsupported_options(a)?;
    for occ in a.facts("COMPORTEMENT") {
        let rel = occ.text("RELATION").unwrap_or("ELAS");
        if rel != "ELAS" {
            return Err(occ.err("RELATION", format!("RELATION='{rel}' is not supported yet")));
        }
        if occ.text("DEFORMATION").is_some_and(|d| d != "PETIT") {
            return Err(occ.err("DEFORMATION", "only DEFORMATION='PETIT' is supported yet"));
        }
    }
    let conv = a.fact("CONVERGENCE");
    if let Some(c) = conv {
        if c.given("RESI_REFE_RELA") {
            return Err(c.err("RESI_REFE_RELA", "not supported yet"));
        }
    }
    let resi_rela = conv.and_then(|c| c.real("RESI_GLOB_RELA"));
    let resi_maxi = conv.and_then(|c| c.real("RESI_GLOB_MAXI"));
    let resi_rela = if resi_rela.is_none() && resi_maxi.is_none() { Some(1e-6) } else { resi_rela };
    let iter_max = conv.and_then(|c| c.int("ITER_GLOB_MAXI")).unwrap_or(10).max(1) as usize;
    if let Some(arch) = a.fact("ARCHIVAGE") {
        for kw in ["INST", "LIST_INST", "PAS_ARCH"] {
            if arch.given(kw) {
                return Err(arch.err(kw, "selective archiving is not supported yet (every instant is stored)"));
            }
        }
    }

    let model = a.req_concept("MODELE")?;
    let chmat = a.req_concept("CHAM_MATER")?;
    let p = problem(&model, &chmat).map_err(|e| e.at(a.span))?;
    let times = instants(a)?;
    let opts = solver_options(a);
    let nfull = p.numbering.ndofs();
    let mut u = vec![0.0; nfull];
    let mut steps = vec![Step { nume_ordre: 0, inst: times[0], fields: step_fields(&p, &u, true)? }];
    let mut log = format!("  {:>4}  {:>14}  {:>5}  {:>14}\n", "step", "INST", "iters", "residual");
    for (n, &t) in times.iter().enumerate().skip(1) {
        let System { map, k, rhs, .. } = assemble(a, &p, &model, t)?;
        // Start from the previous state; the imposed values of this step come with the map.
        let mut x: Vec<f64> = map.free_to_full.iter().map(|&d| u[d]).collect();
        let scale = inf_norm(&rhs);
        let fact = match solve::factorize(k.as_ref(), &opts) {
            Ok((f, ..)) => f,
            Err(_) => {
                // Let the solver report which unknowns are singular.
                solve_reduced(a, &p, &map, &k, &rhs, &opts)?;
                return Err(Error::runtime("factorization failed").at(a.span));
            }
        };
        let mut iters = 0;
        let residual = loop {
            let kx = solve::matvec(k.as_ref(), &x);
            let r: Vec<f64> = rhs.iter().zip(&kx).map(|(b, y)| b - y).collect();
            let abs = inf_norm(&r);
            let rel = if scale > 0.0 { abs / scale } else { abs };
            let converged = iters > 0
                && resi_rela.map(|tol| rel <= tol).unwrap_or(true)
                && resi_maxi.map(|tol| abs <= tol).unwrap_or(true);
            if converged {
                break rel;
            }
            if iters == iter_max {
                return Err(a.err(
                    "CONVERGENCE",
                    format!(
                        "Newton did not converge at INST={t} in {iter_max} iterations (relative residual {rel:.3e}, absolute {abs:.3e})"
                    ),
                ));
            }
            let dx = fact.solve(&r);
            for (xi, di) in x.iter_mut().zip(&dx) {
                *xi += di;
            }
            iters += 1;
        };
        u = map.expand(&x);
        let (ts, rs) = (crate::interp::format::sci(t, 6, false), crate::interp::format::sci(residual, 3, false));
        log.push_str(&format!("  {n:>4}  {ts:>14}  {iters:>5}  {rs:>14}\n"));
        steps.push(Step { nume_ordre: n as i64, inst: t, fields: step_fields(&p, &u, true)? });
    }
    ctx.io.mess(&format!(
        "  STAT_NON_LINE ({}, RELATION='ELAS'): {} unknowns, Newton per step:\n{log}",
        p.modelisation.name(),
        nfull
    ));
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData { model, material: Some(chmat), loads, steps })))
}
