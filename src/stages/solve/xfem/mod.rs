//! STAT_NON_LINE on an X-FEM model (MODI_MODELE_XFEM), with or without the
//! cohesive mortar interfaces of DEFI_CONTACT FORMULATION='XFEM',
//! ALGO_CONT='CZM', RELATION='CZM_LIN_MIX' (`hm-xfem-formulation.md` §4–§6).
//!
//! Only the effects the scene calls for are simulated. Hydro-mechanical
//! models (D_PLAN_HM, 3D_HM) whose every hydraulic unknown is prescribed
//! have them eliminated: the pressures and their Heaviside parts (any values)
//! and the fracture unknowns (p_f, q⁺, q⁻ of every multiplier packet, to
//! zero); a prescribed pore pressure loads the skeleton through the Biot term
//! −b·p (`forces`), p_f = 0 leaves the interface equations alone, and the run
//! log says so. When some are free, a scene without cohesive zones goes to the
//! HM driver, and one with cohesive zones solves the flow here (`flow`: the HM
//! elements on the sub-cells and the 2020 interface hydraulics, with p_f
//! prescribed). Interfaces without a contact zone carry no unknowns (free
//! surfaces).
//!
//! ETAT_INIT=_F(EVOL_NOLI=...) starts from a stored step: every unknown from its DEPL, the cohesive
//! variables from its COHE_ELEM (`state`), the first instant at the step's (`nmdoin`, `nmdini`). With
//! `reuse=`, the new steps are appended to the result as Code_Aster's storage manager does (`nmcrar`,
//! `nmarpr`, `nmnoli`): from the order after the last stored one (or, when the first instant computed is
//! not after the last stored instant, from the order stored at that instant, the later ones dropped),
//! and the initial state is not stored again.

mod assemble;
mod conditions;
mod flow;
mod forces;
mod hydraulic;
mod physics;
mod report;
mod setup;
mod state;

use crate::concepts::result::{ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::core::driver::{Driver, StepLog};
use crate::stages::core::loads::Loads;
use crate::stages::core::settings::Settings;
use crate::stages::Ctx;
use std::time::Instant;

/// STAT_NON_LINE on an X-FEM model: the instants of INCREMENT, the initial
/// state stored as order 0.
pub fn stat_non_line_xfem(ctx: &mut Ctx, cfg: &Settings) -> Result<Option<ConceptData>> {
    solve_xfem(ctx, cfg, state::source(cfg))
}

/// MECA_STATIQUE on an X-FEM model (no contact zone: the interfaces are free
/// surfaces): one linear solve at INST (0 by default), stored as order 1.
pub fn meca_statique_xfem(ctx: &mut Ctx, cfg: &Settings) -> Result<Option<ConceptData>> {
    solve_xfem(ctx, cfg, None)
}

/// Setup, operators, instants, report: the whole solve of an X-FEM model.
fn solve_xfem(ctx: &mut Ctx, cfg: &Settings, init: Option<state::Source>) -> Result<Option<ConceptData>> {
    let (model, times) = (&cfg.model, &cfg.times);
    let statics = cfg.statics();
    let t_start = Instant::now();
    let mut s = setup::setup(cfg, model)?;
    // The unknowns the kinematic conditions prescribe, at the first instant solved: multiplier components
    // that test only prescribed jumps are removed (`discrete::dead_components`).
    let t_first = times.get(1).or(times.last()).copied().unwrap_or(0.0);
    let loads = Loads::new(cfg);
    let mut first = loads.with(t_first, |l| conditions::constraints(cfg, &s, l))?;
    if first.free_hydraulics.is_some() && s.zones.is_empty() && !statics && init.is_none() {
        // Coupled flow without cohesive interfaces: the HM physics, on the enriched elements
        // (`stages::core::hm`), solves the flow with the mechanics.
        return crate::stages::solve::hm::stat_non_line_hm(ctx, cfg);
    }
    if first.free_hydraulics.is_some() && !s.zones.is_empty() && first.unsupported.is_none() {
        // Coupled flow with cohesive interfaces: the HM elements and the interface hydraulics join this
        // physics' unknowns (`flow`), which keeps the mortar law and its multipliers in one place.
        if statics {
            return Err(cfg.err("EXCIT", "coupled flow needs STAT_NON_LINE (MECA_STATIQUE solves no flow)"));
        }
        if init.is_some() {
            return Err(cfg.err(
                "ETAT_INIT",
                "ETAT_INIT with coupled flow in cohesive interfaces is not supported yet (the HM point states are \
                 not read back)",
            ));
        }
        s.flow = Some(setup::Flow::new(cfg, &s)?);
        first = loads.with(t_first, |l| conditions::constraints(cfg, &s, l))?;
    }
    first.require_prescribed_hydraulics(cfg)?;
    let cons = first.cons;
    let fixed: std::collections::BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
    let map = crate::fem::dofs::DofMap::build(s.nunk(), &cons).map_err(|e| cfg.err("EXCIT", e.to_string()))?;
    let el = assemble::elements(cfg, &s, &fixed, &map)?;
    // The steps a reentrant call keeps, and the order of its first new step.
    let reused: Option<(Vec<Step>, i64)> = if statics {
        None
    } else {
        ctx.reuse.as_ref().and_then(|r| match &*r.data() {
            ConceptData::Result(rd) => Some(appended(&rd.steps, times[1])),
            _ => None,
        })
    };
    let phys = physics::Xfem::new(cfg, &s, &el)?;
    let (x, czm) = match &init {
        Some(src) => {
            let (x, czm) = state::restore(cfg, src, &s, &el)?;
            (x, Some(czm))
        }
        None => (vec![0.0; s.nunk()], None),
    };
    let mut state = phys.initial_state(x.clone(), czm);
    let mut x = x;
    let driver = Driver::new(cfg, &phys, s.opts);
    if init.is_some() {
        // From ETAT_INIT: the reactions of the initial state are the earlier reference force.
        driver.remember_reference(t_first, &x, &state)?;
    }
    let mut log = StepLog::default();
    let mut steps = driver.run(&mut x, &mut state, !statics && reused.is_none(), &mut log)?;
    if let Some((mut kept, first)) = reused {
        for st in &mut steps {
            st.nume_ordre += first - 1;
        }
        kept.append(&mut steps);
        steps = kept;
    }
    let first = phys.first.take().unwrap_or_default();
    ctx.io.mess(&report::run_log(cfg, &s, &el, &log, &first, init.as_ref(), t_start));
    Ok(Some(ConceptData::Result(ResultData {
        model: model.clone(),
        material: Some(s.chmat.clone()),
        cara_elem: cfg.cara_elem.clone(),
        loads: cfg.loads(),
        steps,
        comportement: Vec::new(),
    })))
}

/// A reentrant STAT_NON_LINE whose first computed instant is `t1`: the steps of the result it keeps and
/// the order of its first new step (`nmarpr`, `nmttch`, `rsrusd`): after the last stored order, or, when
/// `t1` is not after the last stored instant, the order stored at `t1` (the one after the last instant
/// before it), the steps from there on being dropped.
fn appended(old: &[Step], t1: f64) -> (Vec<Step>, i64) {
    let Some(last) = old.iter().max_by_key(|s| s.nume_ordre) else { return (Vec::new(), 0) };
    let first = if t1 <= last.inst {
        let tol = 1e-12 * t1.abs().max(1e-300);
        match old.iter().find(|s| (s.inst - t1).abs() <= tol) {
            Some(s) => s.nume_ordre,
            None => old
                .iter()
                .filter(|s| s.inst < t1)
                .max_by(|p, q| p.inst.total_cmp(&q.inst))
                .map(|s| s.nume_ordre + 1)
                .unwrap_or(old.iter().map(|s| s.nume_ordre).min().unwrap_or(0)),
        }
    } else {
        last.nume_ordre + 1
    };
    (old.iter().filter(|s| s.nume_ordre < first).cloned().collect(), first)
}
