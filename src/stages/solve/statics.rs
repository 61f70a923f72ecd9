//! MECA_STATIQUE (linear elastic statics): model + material field + loads → assembled, reduced, solved
//! on the shared core; the run log states the size of the system, what was eliminated and the time of each
//! phase.

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::Ctx;

use crate::stages::core::assembly::{assemble, System};
use crate::stages::core::problem::problem;
use crate::stages::core::solver::{solve_reduced, solver_log, solveur, step_fields};
use std::time::Instant;
pub fn meca_statique(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if let Some(mo) = a.concept("MODELE") {
        if mo.model()?.xfem.is_some() {
            return super::xfem::meca_statique_xfem(ctx, a, &mo);
        }
    }
    // RESULTAT (adding a step to a result) and INST_FIN are not implemented.
    a.refuse(&["CARA_ELEM", "LIST_INST", "SENSIBILITE", "RESULTAT", "INST_FIN"])?;
    if let Some(o) = a.text("OPTION") {
        if o != "SIEF_ELGA" && o != "SANS" {
            return Err(a.err("OPTION", format!("OPTION='{o}' is not supported yet")));
        }
    }
    let t_all = Instant::now();
    let model = a.req_concept("MODELE")?;
    let chmat = a.concept("CHAM_MATER").ok_or_else(|| a.err("CHAM_MATER", "a material field is required"))?;
    let inst = a.reals("INST").first().copied().unwrap_or(0.0);
    let p = problem(&model, &chmat).map_err(|e| e.at(a.span))?;
    let md = p.modelisation;
    let System { map, k, rhs, t_numbering, t_assembly } = assemble(a, &p, &model, inst)?;

    // Solve.
    let sv = solveur(a)?;
    let sol = solve_reduced(a, &p, &map, &k, &rhs, &sv.opts)?;
    let u = map.expand(&sol.x);

    // Fields.
    let t0 = Instant::now();
    let fields = step_fields(&p, &u, a.text("OPTION") != Some("SANS"))?;
    let t_post = t0.elapsed();
    ctx.io.mess(&format!(
        "  linear statics ({}): {} unknowns, {} eliminated by kinematic conditions, {} solved ({:?}); residual {:.1e}\n  \
         time: numbering {:.3} s, assembly {:.3} s, factorization {:.3} s, solve {:.3} s, fields {:.3} s, total {:.3} s\n",
        md.name(),
        map.nfull,
        map.n_eliminated(),
        map.nfree,
        sol.method,
        sol.residual,
        t_numbering.as_secs_f64(),
        t_assembly.as_secs_f64(),
        (sol.timings.symbolic + sol.timings.factorization + sol.timings.condition).as_secs_f64(),
        sol.timings.solve.as_secs_f64(),
        t_post.as_secs_f64(),
        t_all.elapsed().as_secs_f64()
    ));
    ctx.io.mess(&solver_log(&sv, &sol.info, sol.residual, sol.refinements));
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData {
        model,
        material: Some(chmat),
        loads,
        steps: vec![Step { nume_ordre: 1, inst, fields }],
    })))
}
