//! STAT_NON_LINE: one entry for every physics. The settings choose the physics from the model: linear
//! elasticity (COMPORTEMENT RELATION='ELAS') and von Mises plasticity (VMIS_ISOT_LINE, VMIS_ISOT_TRAC),
//! here on the core's driver, saturated HM (`hm`), an X-FEM
//! model (`xfem`).

use crate::catalog::args::Args;
use crate::concepts::result::ResultData;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::physics::Physics;
use crate::stages::core::driver::{Driver, StepLog};
use crate::stages::core::problem::{elastic, plastic, PLASTIC_RELATIONS};
use crate::stages::core::settings::{Command, PhysicsKind, Settings};
use crate::stages::core::solver::peak_memory;
use crate::stages::Ctx;

pub fn stat_non_line(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let cfg = Settings::read(a, Command::StatNonLine)?;
    match cfg.physics {
        PhysicsKind::Xfem => return super::xfem::stat_non_line_xfem(ctx, &cfg),
        PhysicsKind::Hm => return super::hm::stat_non_line_hm(ctx, &cfg),
        PhysicsKind::Elastic => {}
        PhysicsKind::Thermal => unreachable!("the settings refuse a thermal model in STAT_NON_LINE"),
    }
    for b in &cfg.behaviours {
        if b.relation != "ELAS" && !PLASTIC_RELATIONS.contains(&b.relation.as_str()) {
            return Err(b.err("RELATION", format!("RELATION='{}' is not supported yet", b.relation)));
        }
    }
    let chmat = cfg.chmat()?;
    // The plastic physics also carries ELAS laws that follow AFFE_VARC's temperature point by point.
    let plasticity = cfg.behaviours.iter().any(|b| b.relation != "ELAS")
        || crate::stages::core::problem::elasticity_follows_temperature(&chmat);
    let mut log = StepLog::default();
    let (steps, describe, unknowns) = if plasticity {
        let p = plastic(&cfg, &chmat)?;
        let mut u = vec![0.0; p.unknowns()];
        let mut state = p.initial_state();
        let steps = Driver::new(&cfg, &p, cfg.solveur.opts).run(&mut u, &mut state, true, &mut log)?;
        (steps, p.describe(), p.unknowns())
    } else {
        let p = elastic(&cfg, &chmat)?;
        let mut u = vec![0.0; p.unknowns()];
        let mut t0 = cfg.times[0];
        let steps = Driver::new(&cfg, &p, cfg.solveur.opts).run(&mut u, &mut t0, true, &mut log)?;
        (steps, p.describe(), p.unknowns())
    };
    let line = cfg.line_search.map_or(String::new(), |ls| {
        format!(
            "    RECH_LINEAIRE (CORDE): RESI_LINE_RELA {}, ITER_LINE_MAXI {}, ρ in [{}, {}]\n",
            ls.resi, ls.iter_max, ls.rho_min, ls.rho_max
        )
    });
    let note = cfg.newton_note.clone().map(|n| n + "\n").unwrap_or_default();
    let solver = log.last_solve.as_ref().map_or(String::new(), |(info, _, _)| {
        format!(
            "    solver    : SOLVEUR {}\n                {}; peak memory {}\n",
            cfg.solveur.mapping,
            info.summary(),
            peak_memory()
        )
    });
    ctx.io.mess(&format!(
        "  STAT_NON_LINE ({}): {} unknowns, {} steps, {} Newton iterations in all:\n{note}{line}{}{solver}",
        describe, unknowns, log.steps, log.iterations, log.table
    ));
    Ok(Some(ConceptData::Result(ResultData {
        model: cfg.model.clone(),
        material: Some(chmat),
        cara_elem: cfg.cara_elem.clone(),
        loads: cfg.loads(),
        steps,
        comportement: cfg.behaviours.iter().map(|b| (b.relation.clone(), b.cells.clone())).collect(),
    })))
}
