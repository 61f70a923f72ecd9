//! THER_LINEAIRE and THER_NON_LINE: heat conduction on a thermal model, steady or transient (θ-scheme),
//! on the core's driver: the thermal physics (`thermal::physics`) built from the model and the material
//! field, the initial state ETAT_INIT gives (a steady computation at the first instant by default), then
//! the instants of INCREMENT, one solve per step for THER_LINEAIRE and Newton corrections until
//! CONVERGENCE holds for THER_NON_LINE; the temperatures stored as ARCHIVAGE says (`TEMP`).

use crate::catalog::args::Args;
use crate::concepts::result::ResultData;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::physics::Physics;
use crate::stages::core::driver::{Driver, StepLog};
use crate::stages::core::heat::{couples, thermal_problem};
use crate::stages::core::settings::{Command, HeatInitial, Settings};
use crate::stages::core::solver::solver_log;
use crate::stages::Ctx;
use std::time::Instant;

pub fn ther_lineaire(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    run(ctx, a, Command::TherLineaire)
}

pub fn ther_non_line(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    run(ctx, a, Command::TherNonLine)
}

fn run(ctx: &mut Ctx, a: &Args, command: Command) -> Result<Option<ConceptData>> {
    let t_all = Instant::now();
    let cfg = Settings::read(a, command)?;
    let heat = cfg.heat.clone().expect("the thermal commands' settings");
    let chmat = cfg.chmat()?;
    let mesh = cfg.model.model()?.current_mesh();
    let p =
        thermal_problem(&cfg.model, &chmat, cfg.cara_elem.as_ref(), heat.theta, !heat.nonlinear, &couples(&cfg, &mesh))
            .map_err(|e| cfg.place(e))?;
    if !heat.nonlinear && p.nonlinear() {
        return Err(cfg.err("CHAM_MATER", "a THER_NL material depends on the temperature: THER_NON_LINE computes it"));
    }
    let t_setup = t_all.elapsed().as_secs_f64();
    let n = p.unknowns();
    let transient = heat.theta.is_some();
    let mut x = match (&heat.initial, transient) {
        (HeatInitial::Uniform(v), true) => vec![*v; n],
        (HeatInitial::Field(c), true) => {
            let f = c.field().map_err(|e| cfg.locate(e, "ETAT_INIT/CHAM_NO"))?;
            let field = f.reals(&c.label()).map_err(|e| cfg.locate(e, "ETAT_INIT/CHAM_NO"))?;
            p.temps_of(field, &c.label()).map_err(|e| cfg.locate(e, "ETAT_INIT/CHAM_NO"))?
        }
        (HeatInitial::Step(rc, k), true) => {
            let r = rc.result().map_err(|e| cfg.locate(e, "ETAT_INIT/EVOL_THER"))?;
            let step = &r.steps[*k];
            let f = step.fields.get("TEMP").ok_or_else(|| {
                cfg.err("ETAT_INIT/EVOL_THER", format!("{} has no TEMP at INST={}", rc.label(), step.inst))
            })?;
            p.temps_of(f, &rc.label()).map_err(|e| cfg.locate(e, "ETAT_INIT/EVOL_THER"))?
        }
        _ => vec![0.0; n],
    };
    let mut state = p.state(&x);
    let driver = Driver::new(&cfg, &p, cfg.solveur.opts);
    let mut log = StepLog::default();
    if transient && matches!(heat.initial, HeatInitial::Steady) {
        let t0 = cfg.times[0];
        driver.advance(t0, t0, &mut x, &mut state, 0, &mut log)?;
    }
    let mut steps = driver.run(&mut x, &mut state, transient && heat.store_initial, &mut log)?;
    // A steady THER_NON_LINE numbers its instants from 0 (THER_LINEAIRE from 1, as `run` does).
    if !transient && heat.nonlinear {
        for s in steps.iter_mut() {
            s.nume_ordre -= 1;
        }
    }
    // RESULTAT continued: its steps before the first new order kept, the new ones numbered from there.
    if let Some((rc, first)) = &heat.reuse {
        let r = rc.result()?;
        let mut kept: Vec<_> = r.steps.iter().filter(|s| s.nume_ordre < *first).cloned().collect();
        for (k, s) in steps.iter_mut().enumerate() {
            s.nume_ordre = first + k as i64;
        }
        kept.append(&mut steps);
        steps = kept;
    }
    let t = &log.solver;
    let eliminated = log.eliminated.iter().filter(|e| **e).count();
    let total = t_all.elapsed().as_secs_f64();
    let (t_fact, t_solve) = ((t.symbolic + t.factorization + t.condition).as_secs_f64(), t.solve.as_secs_f64());
    let mut notes = String::new();
    if heat.nonlinear {
        notes.push_str(&match cfg.reac_iter {
            0 => "  NEWTON REAC_ITER=0: the tangent of each step's start serves all its corrections\n".to_string(),
            1 => "  NEWTON REAC_ITER=1: the tangent is assembled again at every correction\n".to_string(),
            r => format!("  NEWTON REAC_ITER={r}: the tangent is assembled again at every {r}th correction\n"),
        });
    }
    if let Some(ls) = &cfg.line_search {
        notes.push_str(&format!(
            "  RECH_LINEAIRE (CORDE): RESI_LINE_RELA {}, ITER_LINE_MAXI {}, ρ in [{}, {}]\n",
            ls.resi, ls.iter_max, ls.rho_min, ls.rho_max
        ));
    }
    ctx.io.mess(&format!(
        "  {} ({}): {n} unknowns, {eliminated} of them prescribed, {} step(s) computed ({} Newton iterations), {} \
         stored; {} factorization(s)\n{}{notes}  time: setup {t_setup:.3} s, assembly {:.3} s, factorization \
         {t_fact:.3} s, solve {t_solve:.3} s, total {total:.3} s\n",
        if heat.nonlinear { "nonlinear heat conduction" } else { "linear heat conduction" },
        p.describe(),
        log.steps,
        log.iterations,
        steps.len(),
        log.factorizations,
        log.table,
        log.assembly,
    ));
    if let Some((info, residual, refinements)) = &log.last_solve {
        ctx.io.mess(&solver_log(&cfg.solveur, info, *residual, *refinements));
    }
    Ok(Some(ConceptData::Result(ResultData {
        model: cfg.model.clone(),
        material: Some(chmat),
        cara_elem: cfg.cara_elem.clone(),
        loads: cfg.loads(),
        steps,
        comportement: Vec::new(),
    })))
}
