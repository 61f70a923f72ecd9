//! STAT_NON_LINE on saturated hydro-mechanical models: `KIT_HM` = (`ELAS`, `LIQU_SATU`, `HYDR_UTIL`) on
//! the `*_HM`, `*_HMD`, `*_HMS` and `*_HM_SI` modelisations, as Code_Aster computes it
//! (`../shared/docs/hm-coupled-formulation.md`), on the core's driver (`stages::core::driver`) with the
//! physics of `hm::physics`.
//!
//! - `setup`: COMPORTEMENT and the run report.
//! - `fields`: ETAT_INIT read back into a state.
//!
//! Only the effects the scene calls for are computed: a pressure prescribed everywhere it exists removes
//! the hydraulic equations (the unknowns are eliminated and the log says so), and the log names the
//! couplings that vanish (no permeability, Biot coefficient zero, no gravity).

mod fields;
mod setup;

use crate::concepts::result::ResultData;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::core::driver::{Driver, StepLog};
use crate::stages::core::hm::hm_problem;
use crate::stages::core::settings::Settings;
use crate::stages::Ctx;
use std::time::Instant;

pub fn stat_non_line_hm(ctx: &mut Ctx, cfg: &Settings) -> Result<Option<ConceptData>> {
    let t_start = Instant::now();
    let chmat = cfg.chmat()?;
    let thm = cfg.model.model()?.elements.iter().flatten().any(|e| e.modelisation.is_thm());
    setup::behaviour(cfg, thm)?;
    let mut p = hm_problem(&cfg.model, &chmat).map_err(|e| e.at(cfg.span_of("MODELE")))?;
    p.theta = cfg.theta;
    // The HM tangent is symmetric only once its pressure rows are scaled by 1/ρ₀ of the liquid, and not
    // exactly: ∂M/∂ε_v = ρ (b + (b − φ) ε_v) against ∂σ_p/∂p = −b, the density's derivative. The solver
    // takes LDLᵀ of its lower triangle when the difference is below 1e-8 of its largest entry, refines
    // against the matrix itself to round-off (LU takes over when it cannot), and LU beyond.
    let rho: Vec<f64> = p.elements().map(|(_, c)| c.mat.rho_l).collect();
    p.pressure_row_scale =
        if rho.iter().all(|&r| r == rho[0] && r > 0.0) { 1.0 / rho.first().copied().unwrap_or(1.0) } else { 0.0 };
    let opts = crate::solve::SolverOptions { method: crate::solve::Method::Auto, sym_tol: 1e-8, ..cfg.solveur.opts };
    let (mut u, mut states) = fields::initial_state(cfg, &p)?;
    let mut log = StepLog::default();
    let steps = Driver::new(cfg, &p, opts).run(&mut u, &mut states, true, &mut log)?;
    ctx.io.mess(&setup::report(&p, cfg, &log, steps.len(), t_start.elapsed().as_secs_f64()));
    Ok(Some(ConceptData::Result(ResultData {
        model: cfg.model.clone(),
        material: Some(chmat),
        cara_elem: cfg.cara_elem.clone(),
        loads: cfg.loads(),
        steps,
        comportement: Vec::new(),
    })))
}
