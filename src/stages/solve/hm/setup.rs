//! COMPORTEMENT of an HM STAT_NON_LINE and the run report.

use crate::diag::Result;
use crate::hm::element::Variant;
use crate::stages::core::driver::StepLog;
use crate::stages::core::hm::HmProblem;
use crate::stages::core::settings::Settings;

/// COMPORTEMENT: KIT_HM (KIT_THM on a THM model) with RELATION_KIT=('ELAS', 'LIQU_SATU', 'HYDR_UTIL') on
/// the whole model, small strains.
pub fn behaviour(cfg: &Settings, thm: bool) -> Result<()> {
    let (kit_name, what) = if thm { ("KIT_THM", "a saturated THM model") } else { ("KIT_HM", "a saturated HM model") };
    if cfg.behaviours.is_empty() {
        return Err(cfg.err(
            "COMPORTEMENT",
            format!(
                "{what} needs COMPORTEMENT=_F(RELATION='{kit_name}', RELATION_KIT=('ELAS', 'LIQU_SATU', 'HYDR_UTIL'))"
            ),
        ));
    }
    for b in &cfg.behaviours {
        let rel = &b.relation;
        if rel != kit_name {
            return Err(b.err(
                "RELATION",
                format!("RELATION='{rel}' on {what}: {kit_name} is needed (the others are not supported yet)"),
            ));
        }
        let kit = &b.kit;
        let want = ["ELAS", "LIQU_SATU", "HYDR_UTIL"];
        if kit.len() != 3 || kit.iter().zip(want).any(|(k, w)| k != w) {
            return Err(b.err(
                "RELATION_KIT",
                format!("RELATION_KIT={kit:?} is not supported yet (('ELAS', 'LIQU_SATU', 'HYDR_UTIL') is)"),
            ));
        }
    }
    Ok(())
}

/// The TEMP unknowns the driver eliminated (prescribed).
fn elim_temp(p: &HmProblem, log: &StepLog) -> usize {
    let num = &p.numbering;
    (0..num.ndofs()).filter(|&d| log.eliminated.get(d) == Some(&true) && Some(num.node_comp(d).1) == p.temp).count()
}

/// What was simulated and how: the unknowns, what was eliminated and why, the couplings that vanish,
/// then the steps.
pub fn report(p: &HmProblem, cfg: &Settings, log: &StepLog, stored: usize, seconds: f64) -> String {
    let (times, theta) = (&cfg.times, cfg.theta);
    let num = &p.numbering;
    let npre = (0..num.ndofs()).filter(|&d| p.is_pressure(num.node_comp(d).1)).count();
    let nu = num.ndofs() - npre;
    let variant = match p.variant {
        Variant::Full => "all terms at the Gauss points",
        Variant::Reduced => "all terms at the points of the reduced family",
        Variant::Lumped => "all terms at the vertices (lumped storage)",
        Variant::Selective => "mechanics and flow at the Gauss points, storage at the vertices",
    };
    let ntemp = (0..num.ndofs()).filter(|&d| Some(num.node_comp(d).1) == p.temp).count();
    let nu = nu - ntemp;
    let kit = if p.temp.is_some() { "KIT_THM" } else { "KIT_HM" };
    let mut s = format!(
        "  STAT_NON_LINE ({}, {kit} ELAS/LIQU_SATU/HYDR_UTIL, θ = {theta}): {} cells, {variant}\n",
        p.modelling,
        p.bulk.len()
    );
    let temps = if p.temp.is_some() { format!(", {ntemp} temperatures TEMP") } else { String::new() };
    s.push_str(&format!(
        "    unknowns  : {} ({nu} displacements, {npre} pressures PRE1{}{temps} on vertices), {} solved\n",
        num.ndofs(),
        if p.xfem.is_some() { " and H*PRE1" } else { "" },
        log.solved
    ));
    if let Some(xm) = &p.xfem {
        let cut = p.elements().filter(|(_, c)| c.points.family == "XINT").count();
        s.push_str(&format!(
            "    X-FEM     : {} Heaviside sets over {} nodes, displacement and pressure enriched (H*X H*Y [H*Z] \
             and H*PRE1 in the counts above); {cut} cells integrated on their sub-cells; the interfaces are \
             impervious and traction-free (no interface unknowns)\n",
            xm.n_sets(),
            xm.node_sets.iter().filter(|v| !v.is_empty()).count()
        ));
    }
    let eliminated = |pressure: bool| {
        (0..num.ndofs())
            .filter(|&d| log.eliminated.get(d) == Some(&true) && p.is_pressure(num.node_comp(d).1) == pressure)
            .count()
    };
    let (elim_p, elim_t) = (eliminated(true), elim_temp(p, log));
    let elim_u = eliminated(false) - elim_t;
    if elim_p == npre && npre > 0 {
        s.push_str(&format!(
            "    hydraulics: PRE1 prescribed on all {npre} vertices (DDL_IMPO): the flow is not computed, the \
             pressures act through the Biot coupling only\n"
        ));
    } else if elim_p > 0 {
        s.push_str(&format!(
            "    hydraulics: PRE1 prescribed on {elim_p} of {npre} vertices (eliminated); the flow is solved on the \
             other {}\n",
            npre - elim_p
        ));
    } else {
        s.push_str(&format!("    hydraulics: the flow is solved on all {npre} vertices\n"));
    }
    if p.temp.is_some() {
        if elim_t == ntemp && ntemp > 0 {
            s.push_str(&format!(
                "    thermal   : TEMP prescribed on all {ntemp} vertices (DDL_IMPO): the {ntemp} temperature unknowns \
                 are eliminated, the heat equation is not solved; the temperature acts through the thermal \
                 expansion of the skeleton and the liquid only\n"
            ));
        } else if elim_t > 0 {
            s.push_str(&format!(
                "    thermal   : TEMP prescribed on {elim_t} of {ntemp} vertices (eliminated); the heat equation is \
                 solved on the other {}\n",
                ntemp - elim_t
            ));
        } else {
            s.push_str(&format!("    thermal   : the heat equation is solved on all {ntemp} vertices\n"));
        }
    }
    s.push_str(&format!("    mechanics : {elim_u} of {nu} displacements prescribed (eliminated)\n"));
    // The couplings the material data switch off.
    let mats: Vec<_> = p.elements().map(|(_, c)| c.mat).collect();
    let mut vanish = Vec::new();
    if mats.iter().all(|m| m.perm == 0.0) {
        vanish.push("no permeability (PERM_IN = 0): no flow, undrained everywhere");
    }
    if mats.iter().all(|m| m.biot == 0.0) {
        vanish.push("BIOT_COEF = 0: the pressure does not load the skeleton");
    }
    if mats.iter().all(|m| m.gravity == [0.0; 3]) {
        vanish.push("PESA_X/Y/Z = 0: no weight of the fluid");
    }
    if mats.iter().all(|m| m.inv_kw == 0.0) {
        vanish.push("UN_SUR_K = 0: incompressible liquid");
    }
    if !vanish.is_empty() {
        s.push_str(&format!("    vanishing : {}\n", vanish.join("; ")));
    }
    if let Some(n) = &cfg.newton_note {
        s.push_str(n);
        s.push('\n');
    }
    s.push_str(&format!(
        "    steps     : {} instants from {} to {}, {} computed ({} cut), {} stored, {} Newton iterations in all, \
         {:.3} s\n",
        times.len() - 1,
        times[0],
        times[times.len() - 1],
        log.steps,
        log.cuts,
        stored,
        log.iterations,
        seconds
    ));
    if let Some((info, residual, refinements)) = &log.last_solve {
        s.push_str(&crate::stages::core::solver::solver_log(&cfg.solveur, info, *residual, *refinements));
    }
    let t = &log.solver;
    s.push_str(&format!(
        "    time      : elements and assembly {:.3} s; {} factorizations: analysis {:.3} s, factorization {:.3} s, \
         condition (first factorization) {:.3} s, solves {:.3} s\n",
        log.assembly,
        log.factorizations,
        t.symbolic.as_secs_f64(),
        t.factorization.as_secs_f64(),
        t.condition.as_secs_f64(),
        t.solve.as_secs_f64()
    ));
    s.push_str(&log.table);
    s
}
