//! The instants of an X-FEM solve: per instant the kinematic conditions, the reduced numbering, the
//! Newton loop of the core on an `XfemStep`, then the update of the cohesive internal variables.

use super::assemble::{Elements, Law, Lin, Zone};
use super::report::{depl_fields, label, zone_state};
use super::setup::Setup;
use crate::catalog::args::Args;
use crate::concepts::result::Step;
use crate::concepts::ConceptRef;
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::DofMap;
use crate::solve::{self, scaling::equilibrate};
use crate::stages::core::newton::{inf_norm, newton, Converged, NewtonStep};
use crate::xfem::czm::{self, CzmState};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

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
}

/// Solve every instant after the first (the initial state, stored as order 0 unless `statics`).
pub fn run(a: &Args, model: &ConceptRef, s: &Setup, el: &Elements, times: &[f64], statics: bool) -> Result<Run> {
    let (xd, ndim) = (&s.xd, s.ndim());
    let mut states: Vec<CzmState> = vec![CzmState::default(); el.laws.len()];
    let mut x = vec![0.0; xd.n];
    let mut run = Run::default();
    if !statics {
        run.steps.push(Step { nume_ordre: 0, inst: times[0], fields: depl_fields(s, &x) });
    }
    // Largest reference force of the converged steps: the scale of the
    // relative criterion once the forces vanish (a fully broken interface).
    let mut ref_hist: f64 = 0.0;
    for (n, &t) in times.iter().enumerate().skip(1) {
        let (cons, hydr, pins) = super::conditions::constraints(a, model, s, t)?;
        if n == 1 {
            run.hm_report = hydr;
            run.pinned = pins;
        }
        let map = DofMap::build(xd.n, &cons).map_err(|e| a.err("EXCIT", e.to_string()))?;
        run.nfree = map.nfree;
        // Start from the previous state with this step's imposed values.
        let free: Vec<f64> = map.free_to_full.iter().map(|&d| x[d]).collect();
        x = map.expand(&free);
        let mut elems = ElementDofs::new();
        for l in &el.lins {
            elems.push(&l.dofs);
        }
        for l in &el.laws {
            let v: Vec<usize> = (l.base..l.base + 2 * ndim).collect();
            elems.push(&v);
        }
        let pattern = SparsityPattern::build(&map, &elems);
        let mut step = XfemStep {
            a,
            s,
            lins: &el.lins,
            laws: &el.laws,
            map: &map,
            pattern,
            states: &states,
            x,
            ref_hist,
            rf: Vec::new(),
            k: None,
            scale: Vec::new(),
            reactions: 0.0,
            vanished: false,
            t_asm: Duration::ZERO,
            t_fact: Duration::ZERO,
        };
        let Converged { iters, rel, abs } = newton(a, &s.conv, statics, t, &mut step)?;
        run.t_asm += step.t_asm;
        run.t_fact += step.t_fact;
        if !statics || s.conv.converged(iters, rel, abs) {
            ref_hist = ref_hist.max(step.reactions);
            if step.vanished {
                run.vanished_steps.push(n);
            }
        }
        x = step.x;
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
        run.steps.push(Step { nume_ordre: n as i64, inst: t, fields: depl_fields(s, &x) });
    }
    Ok(run)
}

/// One instant's Newton step: the residual and tangent of the bulk, the mortar couplings and the
/// cohesive laws at the current state, on the reduced unknowns; the correction from an LU of the
/// symmetrically equilibrated tangent.
struct XfemStep<'s> {
    a: &'s Args,
    s: &'s Setup,
    lins: &'s [Lin],
    laws: &'s [Law],
    map: &'s DofMap,
    pattern: SparsityPattern,
    states: &'s [CzmState],
    x: Vec<f64>,
    ref_hist: f64,
    /// Of the last residual: the reduced residual, the scaled tangent and its scaling.
    rf: Vec<f64>,
    k: Option<faer::sparse::SparseColMat<usize, f64>>,
    scale: Vec<f64>,
    /// Largest reaction at a prescribed unknown, and whether it vanished against the earlier steps.
    reactions: f64,
    vanished: bool,
    t_asm: Duration,
    t_fact: Duration,
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
        let n = self.s.xd.n;
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
        let (k, _) = asm.finish();
        // Symmetric equilibration: the system mixes stiffnesses (E·h) with interface couplings of
        // order 1; LU on the scaled matrix keeps the accuracy of the solution.
        let (k, scale) = equilibrate(&k);
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
        self.vanished = reactions <= 1e-6 * self.ref_hist;
        self.reactions = reactions;
        let scale_ref = if self.vanished { self.ref_hist } else { reactions };
        let rel = if scale_ref > 0.0 { abs / scale_ref } else { abs };
        self.rf = rf;
        self.k = Some(k);
        self.scale = scale;
        Ok((rel, abs))
    }

    fn correct(&mut self) -> Result<()> {
        let a = self.a;
        let Some(k) = self.k.take() else { return Err(Error::runtime("no tangent to solve with").at(a.span)) };
        let tf = Instant::now();
        let fact = match solve::factorize(k.as_ref(), &self.s.opts) {
            Ok((f, ..)) => f,
            Err(e) => {
                let dofs = match &e {
                    solve::SolveError::Singular { dofs, .. } => dofs.clone(),
                    _ => vec![],
                };
                let labels: Vec<String> =
                    dofs.iter().take(6).map(|&d| label(self.s, self.map.free_to_full[d])).collect();
                return Err(Error::runtime(format!("{e}; unknowns: {}", labels.join(", "))).at(a.span));
            }
        };
        let neg: Vec<f64> = self.rf.iter().zip(&self.scale).map(|(v, s)| -v * s).collect();
        let dx: Vec<f64> = fact.solve(&neg).iter().zip(&self.scale).map(|(v, s)| v * s).collect();
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
