//! STAT_NON_LINE on saturated hydro-mechanical models: `KIT_HM` = (`ELAS`, `LIQU_SATU`, `HYDR_UTIL`) on
//! the `*_HM`, `*_HMD`, `*_HMS` and `*_HM_SI` modelisations, as Code_Aster computes it
//! (`../shared/docs/hm-coupled-formulation.md`).
//!
//! - `setup`: the keywords (COMPORTEMENT, SCHEMA_THM, ARCHIVAGE, ETAT_INIT) and the loads of EXCIT at an
//!   instant: the kinematic conditions (DX DY DZ PRE1) and the external forces, FLUX_THM_REP on the
//!   pressures.
//! - `step`: one time step, a Newton loop whose first iteration is Code_Aster's prediction (the tangent
//!   at the start of the step, the prescribed increments, the internal forces of the start state), with
//!   the relative residual over all equations Code_Aster tests; the cutting of a step that fails when
//!   DEFI_LIST_INST asks for it.
//! - `fields`: DEPL, SIEF_ELGA and VARI_ELGA of a state, and ETAT_INIT read back into one.
//!
//! Only the effects the scene calls for are computed: a pressure prescribed everywhere it exists removes
//! the hydraulic equations (the unknowns are eliminated and the log says so), and the log names the
//! couplings that vanish (no permeability, Biot coefficient zero, no gravity).

mod fields;
mod setup;
mod step;

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::core::hm::hm_problem;
use crate::stages::core::newton::{instants, subdivision, Convergence};
use crate::stages::core::solver::solver_options;
use crate::stages::Ctx;
use std::time::Instant;

pub fn stat_non_line_hm(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    let t_start = Instant::now();
    a.refuse(&["CONTACT"])?;
    crate::stages::core::newton::refuse_unsupported_options_except(a, &["ETAT_INIT", "ARCHIVAGE"])?;
    setup::behaviour(a)?;
    let theta = setup::theta(a)?;
    let conv = Convergence::from_args(a)?;
    let chmat = a.req_concept("CHAM_MATER")?;
    let p = hm_problem(model, &chmat).map_err(|e| e.at(a.span_of("MODELE")))?;
    let times = instants(a)?;
    let subd = subdivision(a);
    let archive = setup::archive(a, &times)?;
    // The HM tangent is not symmetric (and its pressure block is negative): an LU factorization.
    let opts = crate::solve::SolverOptions { method: crate::solve::Method::Lu, ..solver_options(a)? };
    let (mut u, mut states) = fields::initial_state(a, &p)?;
    let mut steps = vec![Step { nume_ordre: 0, inst: times[0], fields: fields::step_fields(&p, &u, &states) }];
    let mut log = step::StepLog::default();
    let driver = step::Driver { a, p: &p, conv, opts, theta, subd };
    for w in times.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        driver.advance(t0, t1, &mut u, &mut states, 0, &mut log)?;
        if archive.iter().any(|&k| (k - t1).abs() <= 1e-12 * t1.abs().max(1e-300)) {
            let n = steps.len() as i64;
            steps.push(Step { nume_ordre: n, inst: t1, fields: fields::step_fields(&p, &u, &states) });
        }
    }
    let report = setup::report(&p, a, &times, theta, &log, steps.len(), t_start.elapsed().as_secs_f64())?;
    ctx.io.mess(&report);
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData { model: model.clone(), material: Some(chmat), loads, steps })))
}
