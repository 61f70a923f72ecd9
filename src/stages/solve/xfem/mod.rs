//! STAT_NON_LINE on an X-FEM model (MODI_MODELE_XFEM), with or without the
//! cohesive mortar interfaces of DEFI_CONTACT FORMULATION='XFEM',
//! ALGO_CONT='CZM', RELATION='CZM_LIN_MIX' (`hm-xfem-formulation.md` §4–§6).
//!
//! Only the effects the scene calls for are simulated. Hydro-mechanical
//! models (D_PLAN_HM, 3D_HM) are accepted when every hydraulic unknown is
//! prescribed to zero: the pressures, their Heaviside parts and the fracture
//! unknowns (p_f, q⁺, q⁻ of every multiplier packet) are then eliminated,
//! with the coupling terms they carry (b·p in the bulk, p_f in the interface
//! equations), and the run log says so; a scene that needs coupled flow
//! stops with a message. Interfaces without a contact zone carry no
//! unknowns (free surfaces).

mod assemble;
mod conditions;
mod forces;
mod report;
mod setup;
mod step;

use crate::catalog::args::Args;
use crate::concepts::result::ResultData;
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::Ctx;
use std::time::Instant;

/// STAT_NON_LINE on an X-FEM model: the instants of INCREMENT, the initial
/// state stored as order 0.
pub fn stat_non_line_xfem(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    let times = crate::stages::core::newton::instants(a)?;
    solve_xfem(ctx, a, model, times, "STAT_NON_LINE")
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
    solve_xfem(ctx, a, model, vec![inst, inst], "MECA_STATIQUE")
}

/// Setup, operators, instants, report: the whole solve of an X-FEM model.
fn solve_xfem(
    ctx: &mut Ctx,
    a: &Args,
    model: &ConceptRef,
    times: Vec<f64>,
    command: &str,
) -> Result<Option<ConceptData>> {
    let statics = command == "MECA_STATIQUE";
    if !statics {
        crate::stages::core::newton::refuse_unsupported_options(a)?;
    }
    let t_start = Instant::now();
    let s = setup::setup(a, model)?;
    // The unknowns the kinematic conditions prescribe, at the first instant solved: multiplier components
    // that test only prescribed jumps are removed (`discrete::dead_components`).
    let t_first = times.get(1).or(times.last()).copied().unwrap_or(0.0);
    let (cons, _, _) = conditions::constraints(a, model, &s, t_first)?;
    let fixed: std::collections::BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
    let map = crate::fem::dofs::DofMap::build(s.xd.n, &cons).map_err(|e| a.err("EXCIT", e.to_string()))?;
    let el = assemble::elements(a, &s, &fixed, &map)?;
    // ARCHIVAGE (STAT_NON_LINE): the instants and fields stored.
    let archive = if statics { None } else { Some(crate::stages::core::newton::Archive::from_args(a, &times)?) };
    let mut run = step::run(a, model, &s, &el, &times, statics, archive.as_ref())?;
    if let Some(archive) = archive {
        run.steps = archive.select(std::mem::take(&mut run.steps), true);
    }
    ctx.io.mess(&report::run_log(command, model, &s, &el, &run, t_start));
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData {
        model: model.clone(),
        material: Some(s.chmat.clone()),
        loads,
        steps: run.steps,
    })))
}
