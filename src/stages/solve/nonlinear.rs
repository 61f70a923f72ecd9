//! STAT_NON_LINE for COMPORTEMENT RELATION='ELAS': a Newton loop per time
//! step on the reduced system of `statics`, with Code_Aster's convergence
//! keywords. The same driver will carry the contact and HM laws; until they
//! exist, any other behaviour stops with a located message.

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::solve;
use crate::stages::core::assembly::{assemble, System};
use crate::stages::core::newton::{
    inf_norm, instants, newton, newton_note, refuse_unsupported_options, Converged, Convergence, NewtonStep,
};
use crate::stages::core::problem::problem;
use crate::stages::core::solver::{peak_memory, solve_reduced, solveur, step_fields};
use crate::stages::Ctx;

pub fn stat_non_line(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if let Some(mo) = a.concept("MODELE") {
        if mo.model()?.xfem.is_some() {
            return super::xfem::stat_non_line_xfem(ctx, a, &mo);
        }
        let hm = mo.model()?.elements.iter().flatten().any(|e| e.modelisation.is_hm());
        if hm {
            return super::hm::stat_non_line_hm(ctx, a, &mo);
        }
    }
    a.refuse(&["CONTACT", "SCHEMA_THM"])?;
    refuse_unsupported_options(a)?;
    for occ in a.facts("COMPORTEMENT") {
        crate::stages::core::newton::closed_form_behaviour(occ)?;
        let rel = occ.text("RELATION").unwrap_or("ELAS");
        if rel != "ELAS" {
            return Err(occ.err("RELATION", format!("RELATION='{rel}' is not supported yet")));
        }
        if occ.text("DEFORMATION").is_some_and(|d| d != "PETIT") {
            return Err(occ.err("DEFORMATION", "only DEFORMATION='PETIT' is supported yet"));
        }
    }
    let conv = Convergence::from_args(a)?;

    let model = a.req_concept("MODELE")?;
    let chmat = a.req_concept("CHAM_MATER")?;
    let p = problem(&model, &chmat).map_err(|e| e.at(a.span))?;
    let times = instants(a)?;
    let archive = crate::stages::core::newton::Archive::from_args(a, &times)?;
    let sv = solveur(a)?;
    let opts = sv.opts;
    // The first factorization's report (method, ordering, condition estimate and the digits it costs).
    let mut first: Option<solve::FactorInfo> = None;
    let nfull = p.numbering.ndofs();
    let mut u = vec![0.0; nfull];
    let mut steps = vec![Step { nume_ordre: 0, inst: times[0], fields: step_fields(&p, &u, true)? }];
    let mut log = format!("  {:>4}  {:>14}  {:>5}  {:>14}\n", "step", "INST", "iters", "residual");
    for (n, &t) in times.iter().enumerate().skip(1) {
        let System { map, k, rhs, .. } = assemble(a, &p, &model, t)?;
        // Start from the previous state; the imposed values of this step come with the map.
        let x: Vec<f64> = map.free_to_full.iter().map(|&d| u[d]).collect();
        let fact = match solve::factorize(k.as_ref(), &opts) {
            Ok(f) => f,
            Err(_) => {
                // Let the solver report which unknowns are singular.
                solve_reduced(a, &p, &map, &k, &rhs, &opts)?;
                return Err(Error::runtime("factorization failed").at(a.span));
            }
        };
        if first.is_none() {
            first = Some(fact.info.clone());
        }
        let mut step = LinearStep { scale: inf_norm(&rhs), k: &k, rhs: &rhs, x, r: Vec::new(), fact };
        let Converged { iters, rel: residual, .. } = newton(a, &conv, false, t, &mut step)?;
        let x = step.x;
        u = map.expand(&x);
        let (ts, rs) = (crate::text::sci(t, 6, false), crate::text::sci(residual, 3, false));
        log.push_str(&format!("  {n:>4}  {ts:>14}  {iters:>5}  {rs:>14}\n"));
        if archive.keeps(t) {
            steps.push(Step { nume_ordre: n as i64, inst: t, fields: step_fields(&p, &u, true)? });
        }
    }
    let note = newton_note(a).map(|n| n + "\n").unwrap_or_default();
    let solver = first.map_or(String::new(), |info| {
        format!(
            "    solver    : SOLVEUR {}\n                {}; peak memory {}\n",
            sv.mapping,
            info.summary(),
            peak_memory()
        )
    });
    ctx.io.mess(&format!(
        "  STAT_NON_LINE ({}, RELATION='ELAS'): {} unknowns, Newton per step:\n{note}{log}{solver}",
        p.modelisation.name(),
        nfull
    ));
    let steps = archive.select(steps, true);
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData { model, material: Some(chmat), loads, steps })))
}

/// A Newton step on a linear reduced system, factorized once per instant: the residual b − K x and the
/// correction K⁻¹ r.
struct LinearStep<'s> {
    k: &'s faer::sparse::SparseColMat<usize, f64>,
    rhs: &'s [f64],
    scale: f64,
    x: Vec<f64>,
    r: Vec<f64>,
    fact: solve::Factorization,
}

impl NewtonStep for LinearStep<'_> {
    fn residual(&mut self) -> Result<(f64, f64)> {
        let kx = solve::matvec(self.k.as_ref(), &self.x);
        self.r = self.rhs.iter().zip(&kx).map(|(b, y)| b - y).collect();
        let abs = inf_norm(&self.r);
        Ok((if self.scale > 0.0 { abs / self.scale } else { abs }, abs))
    }
    fn correct(&mut self) -> Result<()> {
        let dx = self.fact.solve(&self.r);
        for (xi, di) in self.x.iter_mut().zip(&dx) {
            *xi += di;
        }
        Ok(())
    }
}
