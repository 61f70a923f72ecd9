//! The instants of an X-FEM solve: per instant the kinematic conditions, the reduced numbering, the
//! Newton loop of the core on an `XfemStep`, then the update of the cohesive internal variables.

use super::assemble::{Elements, Law, Lin, Zone};
use super::conditions::PorePressure;
use super::hydraulic::HydraulicRows;
use super::report::{label, sief_field, zone_state};
use super::setup::Setup;
use super::state::{cohe_field, depl_fields};
use crate::catalog::args::Args;
use crate::concepts::result::Step;
use crate::concepts::ConceptRef;
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::DofMap;
use crate::solve::{self, Analysis};
use crate::stages::core::newton::{inf_norm, newton, Archive, Converged, NewtonStep};
use crate::stages::core::solver::{solve_error, solver_log};
use crate::xfem::czm::{self, CzmState};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

/// Size of the reduced tangent from which it is factorised by LDLᵀ rather than LU.
pub const LDLT_FROM: usize = 20_000;

/// What the instants produced: the stored steps, the per-step log, and what the final report needs.
#[derive(Default)]
pub struct Run {
    pub steps: Vec<Step>,
    pub log: String,
    pub t_asm: Duration,
    pub t_fact: Duration,
    pub nfree: usize,
    pub hm_report: String,
    pub pinned: Vec<String>,
    /// Steps at which the reactions vanished and the relative criterion used the largest earlier one.
    pub vanished_steps: Vec<usize>,
    /// The solver's log line (of the last factorization).
    pub solver: String,
}

/// The state at the first instant: the unknowns and the cohesive variables (zero and sound, or those of
/// ETAT_INIT), and whether it is stored as a step.
pub struct Start {
    pub x: Vec<f64>,
    pub states: Vec<CzmState>,
    pub store: bool,
    /// The state is ETAT_INIT's: its reactions are the reference force the relative criterion falls back
    /// on if the reactions vanish (as the largest reaction of the earlier steps is in one computation).
    pub restart: bool,
}

/// Solve every instant after the first (the initial state, stored as order 0 when `start.store`); the
/// fields are computed only at the instants `archive` keeps (all without one).
#[allow(clippy::too_many_arguments)]
pub fn run(
    a: &Args,
    model: &ConceptRef,
    s: &Setup,
    el: &Elements,
    times: &[f64],
    statics: bool,
    archive: Option<&Archive>,
    start: Start,
) -> Result<Run> {
    let (xd, ndim) = (&s.xd, s.ndim());
    let Start { mut x, mut states, store, restart } = start;
    let mut run = Run::default();
    // Eliminated hydraulics count in the reference through their storage rows; with coupled flow every
    // hydraulic row is assembled.
    let hydro = if s.flow.is_some() { None } else { HydraulicRows::new(a, s, el)? };
    let mut hm_states = s.flow.as_ref().map(|f| f.initial_states(&x)).unwrap_or_default();
    if store {
        run.steps.push(Step { nume_ordre: 0, inst: times[0], fields: step_fields(a, s, el, &x, &states, None)? });
    }
    // Largest reference force of the converged steps: the scale of the
    // relative criterion once the forces vanish (a fully broken interface).
    let mut ref_hist: f64 = 0.0;
    // The symbolic analysis, reused across Newton iterations and instants while the pattern holds.
    let mut analysis: Option<Analysis> = None;
    for (n, &t) in times.iter().enumerate().skip(1) {
        let conditions = super::conditions::constraints(a, model, s, t)?;
        conditions.require_prescribed_hydraulics(a)?;
        let super::conditions::Conditions { mut cons, report: hydr, pins, pressure, .. } = conditions;
        // Removed multiplier components: their λ, w and μ are zero.
        for (zi, dead) in el.dead.iter().enumerate() {
            let crack = s.zones[zi].crack;
            for &(k, q) in dead {
                let b = xd.packets[crack][k];
                for off in [0, ndim, 2 * ndim] {
                    cons.impose(b + off + q, 0.0);
                }
            }
        }
        // Multiplier directions that test no free jump: μ is kept orthogonal to them, unless the loads
        // prescribe λ on every component of the direction (DDL_IMPO on LAGS_*): the w-rows then fix μ.
        // The free jump of a near-sliver set such a direction tested is held at zero.
        let fixed: std::collections::BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
        for v in &el.null {
            if let Some(g) = &v.lock {
                cons.relation(g.clone(), 0.0);
            }
            if v.mu.iter().all(|&(d, _)| fixed.contains(&(d - 2 * ndim))) {
                continue;
            }
            cons.relation(v.mu.clone(), 0.0);
        }
        if n == 1 {
            run.hm_report = hydr;
            run.pinned = pins;
        }
        let map = DofMap::build(s.nunk(), &cons).map_err(|e| a.err("EXCIT", e.to_string()))?;
        let fext = super::forces::external(a, s, t, pressure.as_ref())?;
        run.nfree = map.nfree;
        let mut elems = ElementDofs::new();
        for l in &el.lins {
            elems.push(&l.dofs);
        }
        for l in &el.laws {
            let v: Vec<usize> = (l.base..l.base + 2 * ndim).collect();
            elems.push(&v);
        }
        if let Some(f) = &s.flow {
            f.elements(s, &mut elems);
        }
        let pattern = SparsityPattern::build(&map, &elems);
        if restart && n == 1 {
            // From ETAT_INIT: the reactions of the initial state are the earlier reference force.
            let mut probe = XfemStep {
                a,
                s,
                lins: &el.lins,
                laws: &el.laws,
                map: &map,
                pattern: pattern.clone(),
                states: &states,
                x: x.clone(),
                x0: &x,
                hydro: hydro.as_ref(),
                fext: fext.as_deref(),
                flow: None,
                ref_hist,
                rf: Vec::new(),
                k: None,
                analysis: &mut None,
                solved: None,
                reactions: 0.0,
                vanished: false,
                t_asm: Duration::ZERO,
                t_fact: Duration::ZERO,
            };
            probe.residual()?;
            ref_hist = probe.reactions;
        }
        // Start from the previous state with this step's imposed values.
        let x_start = x.clone();
        let free: Vec<f64> = map.free_to_full.iter().map(|&d| x[d]).collect();
        x = map.expand(&free);
        let mut step = XfemStep {
            a,
            s,
            lins: &el.lins,
            laws: &el.laws,
            map: &map,
            pattern,
            states: &states,
            x,
            x0: &x_start,
            hydro: hydro.as_ref(),
            fext: fext.as_deref(),
            flow: s.flow.as_ref().map(|_| FlowStep { prev: &hm_states, dt: t - times[n - 1], t, states: Vec::new() }),
            ref_hist,
            rf: Vec::new(),
            k: None,
            analysis: &mut analysis,
            solved: None,
            reactions: 0.0,
            vanished: false,
            t_asm: Duration::ZERO,
            t_fact: Duration::ZERO,
        };
        let Converged { iters, rel, abs } = newton(a, &s.conv, statics, t, &mut step)?;
        run.t_asm += step.t_asm;
        run.t_fact += step.t_fact;
        if let Some((info, res, refs)) = &step.solved {
            run.solver = solver_log(&s.solveur, info, *res, *refs);
        }
        if !statics || s.conv.converged(iters, rel, abs) {
            ref_hist = ref_hist.max(step.reactions);
            if step.vanished {
                run.vanished_steps.push(n);
            }
        }
        x = step.x;
        if let Some(f) = step.flow {
            hm_states = f.states;
        }
        // Internal variables after convergence.
        for (li, l) in el.laws.iter().enumerate() {
            let z = &s.zones[l.zone];
            let ev = czm::evaluate(
                &z.params,
                ndim,
                &x[l.base..l.base + ndim],
                &x[l.base + ndim..l.base + 2 * ndim],
                &states[li],
            );
            states[li] = ev.new_state;
        }
        let _ = writeln!(
            run.log,
            "  {n:>4}  {:>14}  {iters:>5}  {:>14}  {:>14}",
            crate::text::sci(t, 6, false),
            crate::text::sci(rel, 3, false),
            crate::text::sci(abs, 3, false)
        );
        run.log.push_str(&zone_state(s, el, &states, &x));
        if archive.is_none_or(|ar| ar.keeps(t)) {
            run.steps.push(Step {
                nume_ordre: n as i64,
                inst: t,
                fields: step_fields(a, s, el, &x, &states, pressure.as_ref())?,
            });
        }
    }
    Ok(run)
}

/// The fields stored at a step: DEPL, COHE_ELEM with cohesive zones, and SIEF_ELGA unless
/// MECA_STATIQUE's OPTION='SANS' asks for none (hydro-mechanical models, whose SIEF_ELGA would also hold
/// the hydraulic stresses, get none yet).
fn step_fields(
    a: &Args,
    s: &Setup,
    el: &Elements,
    x: &[f64],
    states: &[CzmState],
    pressure: Option<&PorePressure>,
) -> Result<std::collections::BTreeMap<String, crate::concepts::result::Field>> {
    let mut f = depl_fields(a, s, x, pressure)?;
    if let Some(c) = cohe_field(s, el, states) {
        f.insert("COHE_ELEM".to_string(), c);
    }
    if !s.hm && a.text_if_declared("OPTION") != Some("SANS") {
        f.insert("SIEF_ELGA".to_string(), sief_field(a, s, x)?);
    }
    Ok(f)
}

/// One instant's Newton step: the residual and tangent of the bulk, the mortar couplings and the
/// cohesive laws at the current state, on the reduced unknowns; the correction from an LDLᵀ of the
/// tangent (equilibrated, refined; see `solve`), whose symbolic analysis is kept while the pattern holds.
struct XfemStep<'s> {
    a: &'s Args,
    s: &'s Setup,
    lins: &'s [Lin],
    laws: &'s [Law],
    map: &'s DofMap,
    pattern: SparsityPattern,
    states: &'s [CzmState],
    x: Vec<f64>,
    /// The unknowns at the start of the instant, and the hydraulic rows of an HM model (their storage
    /// terms join the reference force).
    x0: &'s [f64],
    hydro: Option<&'s HydraulicRows>,
    /// The external forces of the instant (lip pressures), if any.
    fext: Option<&'s [f64]>,
    /// With coupled flow: the step and the HM point states.
    flow: Option<FlowStep<'s>>,
    ref_hist: f64,
    /// Of the last residual: the reduced residual and the tangent.
    rf: Vec<f64>,
    k: Option<faer::sparse::SparseColMat<usize, f64>>,
    analysis: &'s mut Option<Analysis>,
    /// Of the last solve: what the factorization did, the relative residual and the refinement steps.
    solved: Option<(solve::FactorInfo, f64, usize)>,
    /// Largest reaction at a prescribed unknown, and whether it vanished against the earlier steps.
    reactions: f64,
    vanished: bool,
    t_asm: Duration,
    t_fact: Duration,
}

/// The flow's part of one instant: the point states at its start, the step, and the states of the last
/// residual.
struct FlowStep<'s> {
    prev: &'s [Vec<crate::hm::law::PointState>],
    dt: f64,
    t: f64,
    states: Vec<Vec<crate::hm::law::PointState>>,
}

impl XfemStep<'_> {
    /// The cohesive law of one packet at the current state: its residual rows and 2·ndim square tangent.
    fn law(&self, l: &Law, zone: &Zone, state: &CzmState, r: &mut [f64]) -> Vec<f64> {
        let ndim = self.s.ndim();
        let x = &self.x;
        let lam = &x[l.base..l.base + ndim];
        let w = &x[l.base + ndim..l.base + 2 * ndim];
        let ev = czm::evaluate(&zone.params, ndim, lam, w, state);
        let rr = zone.params.r();
        let nd = 2 * ndim;
        let mut ke = vec![0.0; nd * nd];
        for i in 0..ndim {
            r[l.base + i] += l.m / rr * (ev.d[i] - lam[i]);
            r[l.base + ndim + i] += l.m * ev.d[i];
            for j in 0..ndim {
                let dij = ev.dd[i][j];
                let id = if i == j { 1.0 } else { 0.0 };
                ke[i * nd + j] = l.m / rr * (dij - id);
                ke[i * nd + ndim + j] = l.m * dij;
                ke[(ndim + i) * nd + j] = l.m * dij;
                ke[(ndim + i) * nd + ndim + j] = rr * l.m * dij;
            }
        }
        ke
    }
}

impl NewtonStep for XfemStep<'_> {
    fn residual(&mut self) -> Result<(f64, f64)> {
        let ta = Instant::now();
        let n = self.s.nunk();
        let mut r = vec![0.0; n];
        let mut asm = Assembler::new(self.map, self.pattern.clone());
        for l in self.lins {
            let nd = l.dofs.len();
            for (i, &di) in l.dofs.iter().enumerate() {
                let row = &l.k[i * nd..(i + 1) * nd];
                r[di] += row.iter().zip(&l.dofs).map(|(k, &dj)| k * self.x[dj]).sum::<f64>();
            }
            asm.add_matrix(&l.dofs, &l.k);
        }
        for (li, l) in self.laws.iter().enumerate() {
            let ke = self.law(l, &self.s.zones[l.zone], &self.states[li], &mut r);
            let dofs: Vec<usize> = (l.base..l.base + 2 * self.s.ndim()).collect();
            asm.add_matrix(&dofs, &ke);
        }
        if let (Some(flow), Some(fs)) = (&self.s.flow, &mut self.flow) {
            fs.states = flow.add(self.a, self.s, &self.x, self.x0, fs.prev, fs.dt, fs.t, &mut r, &mut asm)?;
        }
        let (k, _) = asm.finish();
        // r = F_int − F_ext; the external forces enter the reference with the reactions.
        let mut fmax: f64 = 0.0;
        if let Some(f) = self.fext {
            for (rd, fd) in r.iter_mut().zip(f) {
                *rd -= fd;
            }
            fmax = inf_norm(f);
        }
        self.t_asm += ta.elapsed();
        // Reduced residual and reference (reactions at prescribed unknowns).
        let mut rf = vec![0.0; self.map.nfree];
        let mut reactions: f64 = 0.0;
        for (d, rd) in r.iter().enumerate() {
            for &(i, c) in self.map.expr(d).0 {
                rf[i] += c * rd;
            }
            if !self.map.is_free(d) {
                reactions = reactions.max(rd.abs());
            }
        }
        let abs = inf_norm(&rf);
        let mut reactions = reactions.max(fmax);
        if let Some(h) = self.hydro {
            reactions = reactions.max(h.largest(self.s, self.laws, self.x0, &self.x));
        }
        self.vanished = reactions <= 1e-6 * self.ref_hist;
        self.reactions = reactions;
        let scale_ref = if self.vanished { self.ref_hist } else { reactions };
        let rel = if scale_ref > 0.0 { abs / scale_ref } else { abs };
        self.rf = rf;
        self.k = Some(k);
        Ok((rel, abs))
    }

    fn correct(&mut self) -> Result<()> {
        let a = self.a;
        let Some(k) = self.k.take() else { return Err(Error::runtime("no tangent to solve with").at(a.span)) };
        let tf = Instant::now();
        // Small tangents go to LU with partial pivoting: its cost is nothing there, and it solves the interface
        // rows by their own pivots, which keeps structural zeros exact (the opening of a closed interface is
        // 0, not round-off). Large ones go to the symmetric LDLᵀ, several times cheaper in time and memory.
        let mut opts = self.s.opts;
        if k.nrows() < LDLT_FROM {
            opts.method = solve::Method::Lu;
        }
        let opts = &opts;
        let name = |d: usize| label(self.s, self.map.free_to_full[d]);
        let err = |e| Error::runtime(solve_error(e, opts, &name)).at(a.span);
        let mut fact = solve::factorize_with(k.as_ref(), opts, self.analysis).map_err(err)?;
        let neg: Vec<f64> = self.rf.iter().map(|v| -v).collect();
        let ts = Instant::now();
        let (dx, res, refs) = solve::solve_refined_or_lu(&mut fact, k.as_ref(), &neg, opts).map_err(err)?;
        fact.info.timings.solve = ts.elapsed();
        solve::check_solution(k.as_ref(), &dx, &neg, res, opts).map_err(err)?;
        self.solved = Some((fact.info.clone(), res, refs));
        self.t_fact += tf.elapsed();
        if dx.iter().any(|v| !v.is_finite()) {
            return Err(Error::runtime("the Newton correction is not finite (singular system)").at(a.span));
        }
        for (d, xd_) in self.x.iter_mut().enumerate() {
            let (terms, _) = self.map.expr(d);
            *xd_ += terms.iter().map(|&(i, c)| c * dx[i]).sum::<f64>();
        }
        Ok(())
    }
}
