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
mod report;
mod setup;
mod state;
mod step;

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::Ctx;
use std::time::Instant;

/// STAT_NON_LINE on an X-FEM model: the instants of INCREMENT, the initial
/// state stored as order 0.
pub fn stat_non_line_xfem(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    crate::stages::core::newton::refuse_unsupported_options_except(a, &["ETAT_INIT"])?;
    let init = state::source(a, model)?;
    let times = crate::stages::core::newton::instants_from(a, init.as_ref().map(|i| i.inst))?;
    solve_xfem(ctx, a, model, times, "STAT_NON_LINE", init)
}

/// MECA_STATIQUE on an X-FEM model (no contact zone: the interfaces are free
/// surfaces): one linear solve at INST (0 by default), stored as order 1.
pub fn meca_statique_xfem(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    a.refuse(&["CARA_ELEM", "LIST_INST", "SENSIBILITE", "RESULTAT", "INST_FIN"])?;
    if let Some(o) = a.text("OPTION") {
        if o != "SIEF_ELGA" && o != "SANS" {
            return Err(a.err("OPTION", format!("OPTION='{o}' is not supported yet")));
        }
    }
    let inst = a.reals("INST").first().copied().unwrap_or(0.0);
    solve_xfem(ctx, a, model, vec![inst, inst], "MECA_STATIQUE", None)
}

/// Setup, operators, instants, report: the whole solve of an X-FEM model.
fn solve_xfem(
    ctx: &mut Ctx,
    a: &Args,
    model: &ConceptRef,
    times: Vec<f64>,
    command: &str,
    init: Option<state::Source>,
) -> Result<Option<ConceptData>> {
    let statics = command == "MECA_STATIQUE";
    let t_start = Instant::now();
    let mut s = setup::setup(a, model)?;
    // The unknowns the kinematic conditions prescribe, at the first instant solved: multiplier components
    // that test only prescribed jumps are removed (`discrete::dead_components`).
    let t_first = times.get(1).or(times.last()).copied().unwrap_or(0.0);
    let mut first = conditions::constraints(a, model, &s, t_first)?;
    if first.free_hydraulics.is_some() && s.zones.is_empty() && !statics && init.is_none() {
        // Coupled flow without cohesive interfaces: the HM driver, on the enriched elements
        // (`stages::core::hm`), solves the flow with the mechanics.
        return crate::stages::solve::hm::stat_non_line_hm(ctx, a, model);
    }
    if first.free_hydraulics.is_some() && !s.zones.is_empty() && first.unsupported.is_none() {
        // Coupled flow with cohesive interfaces: the HM elements and the interface hydraulics join this
        // driver's unknowns (`flow`), which keeps the mortar law and its multipliers in one place.
        if statics {
            return Err(a.err("EXCIT", "coupled flow needs STAT_NON_LINE (MECA_STATIQUE solves no flow)"));
        }
        if init.is_some() {
            return Err(a.err(
                "ETAT_INIT",
                "ETAT_INIT with coupled flow in cohesive interfaces is not supported yet (the HM point states are \
                 not read back)",
            ));
        }
        s.flow = Some(flow::Flow::new(a, model, &s)?);
        first = conditions::constraints(a, model, &s, t_first)?;
    }
    first.require_prescribed_hydraulics(a)?;
    let cons = first.cons;
    let fixed: std::collections::BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
    let map = crate::fem::dofs::DofMap::build(s.nunk(), &cons).map_err(|e| a.err("EXCIT", e.to_string()))?;
    let el = assemble::elements(a, &s, &fixed, &map)?;
    // ARCHIVAGE (STAT_NON_LINE): the instants and fields stored.
    let archive = if statics { None } else { Some(crate::stages::core::newton::Archive::from_args(a, &times)?) };
    // The steps a reentrant call keeps, and the order of its first new step.
    let reused: Option<(Vec<Step>, i64)> = if statics {
        None
    } else {
        ctx.reuse.as_ref().and_then(|r| match &*r.data() {
            ConceptData::Result(rd) => Some(appended(&rd.steps, times[1])),
            _ => None,
        })
    };
    let (x, states) = match &init {
        Some(src) => state::restore(a, src, &s, &el)?,
        None => (vec![0.0; s.nunk()], vec![crate::xfem::czm::CzmState::default(); el.laws.len()]),
    };
    let start = step::Start { x, states, store: !statics && reused.is_none(), restart: init.is_some() };
    let mut run = step::run(a, model, &s, &el, &times, statics, archive.as_ref(), start)?;
    if let Some(archive) = archive {
        run.steps = archive.select(std::mem::take(&mut run.steps), reused.is_none());
    }
    let mut steps = std::mem::take(&mut run.steps);
    if let Some((mut kept, first)) = reused {
        for st in &mut steps {
            st.nume_ordre += first - 1;
        }
        kept.append(&mut steps);
        steps = kept;
    }
    ctx.io.mess(&report::run_log(command, model, &s, &el, &run, init.as_ref(), t_start));
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData { model: model.clone(), material: Some(s.chmat.clone()), loads, steps })))
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
