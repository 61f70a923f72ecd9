//! MECA_STATIQUE (linear elastic statics): the elastic physics of the model (`fem::elastic`) on the core's
//! driver, one solve; the run log states the size of the system, what was eliminated and the time of
//! each phase.

use crate::catalog::args::Args;
use crate::concepts::result::ResultData;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::physics::Physics;
use crate::stages::core::driver::{Driver, StepLog};
use crate::stages::core::problem::{elastic, elasticity_follows_temperature, plastic};
use crate::stages::core::settings::{Command, PhysicsKind, Settings};
use crate::stages::core::solver::solver_log;
use crate::stages::Ctx;
use std::time::Instant;

pub fn meca_statique(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let cfg = Settings::read(a, Command::MecaStatique)?;
    if cfg.physics == PhysicsKind::Xfem {
        return super::xfem::meca_statique_xfem(ctx, &cfg);
    }
    let t_all = Instant::now();
    let chmat = cfg.chmat()?;
    let mut log = StepLog::default();
    // Parameters of ELAS_FO depending on AFFE_VARC's temperature: the elastic law at each point's
    // temperature (the plastic physics with ELAS everywhere, whose increments add up to σ = D(T) (ε − ε_th)).
    let (steps, modelisation, unknowns, t_setup) = if elasticity_follows_temperature(&chmat) {
        let p = plastic(&cfg, &chmat)?;
        let t_setup = t_all.elapsed();
        let mut u = vec![0.0; p.unknowns()];
        let mut state = p.initial_state();
        let mut steps = Driver::new(&cfg, &p, cfg.solveur.opts).run(&mut u, &mut state, false, &mut log)?;
        for s in &mut steps {
            s.fields.remove("VARI_ELGA");
            if !cfg.sief {
                s.fields.remove("SIEF_ELGA");
            }
        }
        (steps, p.elastic.modelisation, p.unknowns(), t_setup)
    } else {
        let p = elastic(&cfg, &chmat)?;
        let t_setup = t_all.elapsed();
        let mut u = vec![0.0; p.unknowns()];
        let mut t0 = cfg.times[0];
        let steps = Driver::new(&cfg, &p, cfg.solveur.opts).run(&mut u, &mut t0, false, &mut log)?;
        (steps, p.modelisation, p.unknowns(), t_setup)
    };
    let (info, residual, refinements) = log.last_solve.clone().expect("one solve");
    let t = &log.solver;
    let eliminated = log.eliminated.iter().filter(|e| **e).count();
    let total = t_all.elapsed().as_secs_f64();
    let (t_fact, t_solve) = ((t.symbolic + t.factorization + t.condition).as_secs_f64(), t.solve.as_secs_f64());
    ctx.io.mess(&format!(
        "  linear statics ({}): {} unknowns, {eliminated} eliminated by kinematic conditions, {} solved ({:?}); \
         residual {residual:.1e}\n  \
         time: element stiffnesses {:.3} s, assembly {:.3} s, factorization {t_fact:.3} s, solve {t_solve:.3} s, \
         fields and the rest {:.3} s, total {total:.3} s\n",
        modelisation.name(),
        unknowns,
        log.solved,
        info.method.unwrap_or(crate::solve::Method::Lu),
        t_setup.as_secs_f64(),
        log.assembly,
        total - t_setup.as_secs_f64() - log.assembly - t_fact - t_solve,
    ));
    ctx.io.mess(&solver_log(&cfg.solveur, &info, residual, refinements));
    Ok(Some(ConceptData::Result(ResultData {
        model: cfg.model.clone(),
        material: Some(chmat),
        cara_elem: cfg.cara_elem.clone(),
        loads: cfg.loads(),
        steps,
        comportement: Vec::new(),
    })))
}
