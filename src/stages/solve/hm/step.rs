//! One time step of an HM STAT_NON_LINE: Code_Aster's prediction, then Newton corrections until the
//! relative residual over all equations meets CONVERGENCE; a step that fails is cut as DEFI_LIST_INST
//! says.
//!
//! The prediction is the linearisation at the start of the step with the new step length: the tangent
//! and internal forces of the start state (whose pressure rows then hold only `Δt ∫ ∇N̂ · w⁻`), the
//! prescribed increments moved to the right-hand side. Its result is tested like every later
//! iteration (Code_Aster's iteration 0), with `RESI_GLOB_RELA = max |F_int + reactions − F_ext| /
//! max |reactions − F_ext|` over all equations (`nmresi`): eliminated equations carry their reaction.

use super::setup::{gravity, loads_at};
use crate::catalog::args::Args;
use crate::concepts::Subdivision;
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::{Constraints, DofMap};
use crate::hm::element::{element, StepData};
use crate::hm::law::PointState;
use crate::solve::{self, Analysis, SolverOptions};
use crate::stages::core::hm::HmProblem;
use crate::stages::core::newton::{inf_norm, Convergence};
use std::cell::RefCell;

/// What the steps did, for the report.
#[derive(Debug, Default)]
pub struct StepLog {
    pub steps: usize,
    pub cuts: usize,
    pub iterations: usize,
    pub solved: usize,
    pub eliminated_u: usize,
    pub eliminated_p: usize,
    pub table: String,
    /// Seconds in the element computations and the assembly (every assembly of every step).
    pub assembly: f64,
    /// Seconds in the solver, summed over every factorization: analysis, numeric factorization,
    /// condition estimate, solves and refinement.
    pub solver: solve::Timings,
    pub factorizations: usize,
    /// The condition estimate of the first factorization (the only one estimated).
    pub condition: Option<f64>,
    /// The last factorization's summary and residual, for the solver line of the log.
    pub last_solve: Option<(solve::FactorInfo, f64, usize)>,
}

/// Why a step failed: Code_Aster's event ERREUR (which DEFI_LIST_INST may answer by cutting the step).
enum Failure {
    /// A located error that ends the run whatever the time list says.
    Fatal(Error),
    /// No convergence, an integration failure, a singular tangent.
    Step(Error),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Fatal(e)
    }
}

pub struct Driver<'a> {
    pub a: &'a Args,
    pub p: &'a HmProblem,
    pub conv: Convergence,
    pub opts: SolverOptions,
    pub theta: f64,
    pub subd: Option<Subdivision>,
    /// The symbolic analysis of the last factorization, reused while the pattern holds.
    pub analysis: RefCell<Option<Analysis>>,
    /// The factor of the pressure rows that makes the tangent symmetric when it can be (1/ρ₀ of the
    /// liquid: the coupling blocks are −b Q and −ρ b Qᵀ), 0 when the materials disagree on ρ₀.
    pub pressure_row_scale: f64,
}

/// What every assembly of a step shares: the matrix structure, the external forces, the instants.
struct StepFrame {
    pattern: SparsityPattern,
    elems: ElementDofs,
    fext: Vec<f64>,
    t1: f64,
    dt: f64,
}

/// The assembled reduced tangent and residual at a state, and the state of every point.
struct Assembled {
    k: faer::sparse::SparseColMat<usize, f64>,
    /// Tᵀ (F_ext − F_int) − Tᵀ K d (d: the prescribed increments of the map).
    rhs: Vec<f64>,
    fint: Vec<f64>,
    states: Vec<Vec<PointState>>,
    seconds: f64,
}

impl Driver<'_> {
    /// Advance from `t0` to `t1`; on a failure, cut the step as ECHEC says (`level` cuts so far).
    pub fn advance(
        &self,
        t0: f64,
        t1: f64,
        u: &mut Vec<f64>,
        states: &mut Vec<Vec<PointState>>,
        level: usize,
        log: &mut StepLog,
    ) -> Result<()> {
        match self.step(t0, t1, u, states, log) {
            Ok(()) => Ok(()),
            Err(Failure::Fatal(e)) => Err(e),
            Err(Failure::Step(e)) => {
                let Some(sd) = self.subd else {
                    return Err(e);
                };
                let dt = (t1 - t0) / sd.pas as f64;
                if level >= sd.niveau || (sd.pas_mini > 0.0 && dt < sd.pas_mini) {
                    return Err(Error::runtime(format!(
                        "{} — the step from {t0} to {t1} cannot be cut further (SUBD_NIVEAU = {}, SUBD_PAS_MINI = {})",
                        e.msg, sd.niveau, sd.pas_mini
                    ))
                    .at(e.span.unwrap_or(self.a.span)));
                }
                log.cuts += 1;
                log.table.push_str(&format!(
                    "  step {t0:e} → {t1:e} failed ({}); cut into {} (level {})\n",
                    e.msg.lines().next().unwrap_or(""),
                    sd.pas,
                    level + 1
                ));
                for k in 0..sd.pas {
                    let a = t0 + k as f64 * dt;
                    let b = if k + 1 == sd.pas { t1 } else { t0 + (k + 1) as f64 * dt };
                    self.advance(a, b, u, states, level + 1, log)?;
                }
                Ok(())
            }
        }
    }

    fn elements(&self) -> ElementDofs {
        let mut e = ElementDofs::new();
        for (_, cell) in self.p.elements() {
            e.push(&cell.dofs);
        }
        e
    }

    /// Tangent and residual of the state `u` over the step [t0, t1] from the states `prev`, reduced by
    /// `map`.
    fn assemble(
        &self,
        sc: &StepFrame,
        map: &DofMap,
        u: &[f64],
        prev: &[Vec<PointState>],
    ) -> std::result::Result<Assembled, Failure> {
        let StepFrame { pattern, elems, fext, t1, dt } = sc;
        let (t1, dt) = (*t1, *dt);
        let started = std::time::Instant::now();
        let mut asm = Assembler::new(map, pattern.clone());
        let mut fint = vec![0.0; u.len()];
        let mut states = Vec::with_capacity(prev.len());
        for (i, ((c, cell), prev_c)) in self.p.elements().zip(prev).enumerate() {
            let step = StepData { dt, theta: self.theta, gravity: gravity(cell, t1)? };
            let ue: Vec<f64> = cell.dofs.iter().map(|&d| u[d]).collect();
            let out = element(&cell.points, &cell.mat, &ue, prev_c, &step).map_err(|e| {
                Failure::Step(Error::runtime(format!(
                    "integration failure in cell {}: {}",
                    self.p.mesh.cell_names[c], e.0
                )))
            })?;
            asm.add_matrix(elems.get(i), &out.k);
            for (&d, v) in cell.dofs.iter().zip(&out.fint) {
                fint[d] += v;
            }
            states.push(out.states);
        }
        let r: Vec<f64> = fext.iter().zip(&fint).map(|(f, g)| f - g).collect();
        let all: Vec<usize> = (0..u.len()).collect();
        asm.add_vector(&all, &r);
        let (k, rhs) = asm.finish();
        Ok(Assembled { k, rhs, fint, states, seconds: started.elapsed().as_secs_f64() })
    }

    /// Code_Aster's relative and absolute residuals of a state: the free equations' residual over the
    /// largest of the loads on free equations and the reactions of the eliminated ones.
    fn residual(&self, map: &DofMap, free: &[bool], fext: &[f64], fint: &[f64]) -> (f64, f64) {
        let r: Vec<f64> = fext.iter().zip(fint).map(|(f, g)| f - g).collect();
        let abs = inf_norm(&map.reduce_vector(&r));
        let mut scale = 0.0f64;
        for d in 0..fext.len() {
            scale = scale.max(if free[d] { fext[d].abs() } else { fint[d].abs() });
        }
        (if scale > 0.0 { abs / scale } else { abs }, abs)
    }

    /// Solve the reduced system. The pressure rows are first divided by the liquid's density ρ₀: with the
    /// coupling terms at the same points (every variant but `*_HMS`) the tangent is then symmetric —
    /// indefinite, its pressure block negative — up to the derivatives of the density and the porosity
    /// (∂M/∂ε_v = ρ (b + (b − φ) ε_v)); within the driver's tolerance the solver takes LDLᵀ with its
    /// fill-reducing ordering on both cores, refined against the matrix itself, and LU otherwise. The
    /// scaling changes neither the solution nor the residual Newton tests.
    fn factor_solve(
        &self,
        map: &DofMap,
        k: &faer::sparse::SparseColMat<usize, f64>,
        rhs: &[f64],
        t1: f64,
        log: &mut StepLog,
    ) -> std::result::Result<Vec<f64>, Failure> {
        let p = self.p;
        let (k, rhs) = if self.pressure_row_scale > 0.0 {
            let row: Vec<f64> = map
                .free_to_full
                .iter()
                .map(|&d| if p.is_pressure(p.numbering.node_comp(d).1) { self.pressure_row_scale } else { 1.0 })
                .collect();
            let (cp, ri) = (k.symbolic().col_ptr(), k.symbolic().row_idx());
            let mut vals = k.val().to_vec();
            for j in 0..k.ncols() {
                for q in cp[j]..cp[j + 1] {
                    vals[q] *= row[ri[q]];
                }
            }
            let b: Vec<f64> = rhs.iter().zip(&row).map(|(v, s)| v * s).collect();
            (faer::sparse::SparseColMat::new(k.symbolic().to_owned().expect("a valid pattern"), vals), b)
        } else {
            (k.clone(), rhs.to_vec())
        };
        // The condition number is estimated on the first factorization only: it costs about ten solves,
        // as much as the factorization itself on large 2D systems, and the steps that follow change the
        // tangent little (NPREC still checks every factorization's pivots).
        let opts = SolverOptions { condition: self.opts.condition && log.factorizations == 0, ..self.opts };
        let sol = solve::solve_with(k.as_ref(), &rhs, &opts, &mut self.analysis.borrow_mut()).map_err(|e| {
            let msg = crate::stages::core::solver::solve_error(e, &self.opts, &|d| {
                p.numbering.label(map.free_to_full[d], Some(&p.mesh))
            });
            Failure::Step(self.a.err("SOLVEUR", format!("the tangent matrix at INST={t1}: {msg}")))
        })?;
        let (t, s) = (&mut log.solver, &sol.timings);
        t.symbolic += s.symbolic;
        t.factorization += s.factorization;
        t.condition += s.condition;
        t.solve += s.solve;
        if log.factorizations == 0 {
            log.condition = sol.info.condition;
        }
        log.factorizations += 1;
        let info = solve::FactorInfo { condition: log.condition, ..sol.info };
        log.last_solve = Some((info, sol.residual, sol.refinements));
        Ok(sol.x)
    }

    /// One step [t0, t1]: prediction, then Newton iterations.
    fn step(
        &self,
        t0: f64,
        t1: f64,
        u: &mut Vec<f64>,
        states: &mut Vec<Vec<PointState>>,
        log: &mut StepLog,
    ) -> std::result::Result<(), Failure> {
        let p = self.p;
        let n = p.numbering.ndofs();
        let dt = t1 - t0;
        let (cons, fext) = loads_at(self.a, p, &self.a.req_concept("MODELE")?, t1, dt)?;
        // The increments the conditions prescribe from the current state, then none.
        let incr = increments(&cons, u);
        let map_pred = DofMap::build(n, &incr)
            .map_err(|e| self.a.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
        let map = DofMap::build(n, &zero(&incr)).expect("the same conditions with no increment");
        let mut free = vec![false; n];
        for &d in &map.free_to_full {
            free[d] = true;
        }
        log.solved = map.nfree;
        log.eliminated_p = (0..n).filter(|&d| !free[d] && p.is_pressure(p.numbering.node_comp(d).1)).count();
        log.eliminated_u = (0..n).filter(|&d| !free[d] && !p.is_pressure(p.numbering.node_comp(d).1)).count();
        let elems = self.elements();
        let pattern = SparsityPattern::build(&map, &elems);
        let sc = StepFrame { pattern, elems, fext, t1, dt };
        // Prediction: tangent and internal forces of the start state.
        let pred = self.assemble(&sc, &map_pred, u, states)?;
        log.assembly += pred.seconds;
        let dx = self.factor_solve(&map_pred, &pred.k, &pred.rhs, t1, log)?;
        let mut unew: Vec<f64> = u.iter().zip(map_pred.expand(&dx)).map(|(a, b)| a + b).collect();
        let mut iters = 0;
        let mut history = Vec::new();
        loop {
            let now = self.assemble(&sc, &map, &unew, states)?;
            log.assembly += now.seconds;
            let (rel, abs) = self.residual(&map, &free, &sc.fext, &now.fint);
            history.push(rel);
            let done = self.conv.resi_rela.map(|tol| rel <= tol).unwrap_or(true)
                && self.conv.resi_maxi.map(|tol| abs <= tol).unwrap_or(true);
            if done {
                *u = unew;
                *states = now.states;
                log.steps += 1;
                log.iterations += iters;
                // Every iteration's relative residual, the prediction's first (Code_Aster's iteration 0).
                let hist: Vec<String> = history.iter().map(|r| crate::text::sci(*r, 3, false)).collect();
                log.table.push_str(&format!(
                    "  INST {:>14}  Δt {:>11}  iterations {:>2}  RESI_GLOB_MAXI {:>10}  RESI_GLOB_RELA {}\n",
                    crate::text::sci(t1, 6, false),
                    crate::text::sci(dt, 3, false),
                    iters,
                    crate::text::sci(abs, 3, false),
                    hist.join(" → "),
                ));
                return Ok(());
            }
            if iters >= self.conv.iter_max {
                return Err(Failure::Step(self.a.err(
                    "CONVERGENCE",
                    format!(
                        "Newton did not converge at INST={t1} in {} iterations (relative residual {rel:.3e}, absolute \
                         {abs:.3e})",
                        self.conv.iter_max
                    ),
                )));
            }
            let dx = self.factor_solve(&map, &now.k, &now.rhs, t1, log)?;
            for (ui, di) in unew.iter_mut().zip(map.expand(&dx)) {
                *ui += di;
            }
            iters += 1;
        }
    }
}

/// The conditions as increments from the state `u`: `Σ c u = b` becomes `Σ c δu = b − Σ c u`.
fn increments(cons: &Constraints, u: &[f64]) -> Constraints {
    let mut out = Constraints::new();
    for &(d, v) in &cons.imposed {
        out.impose(d, v - u[d]);
    }
    for r in &cons.relations {
        let now: f64 = r.terms.iter().map(|&(d, c)| c * u[d]).sum();
        out.relation(r.terms.clone(), r.rhs - now);
    }
    out
}

/// The same conditions with no increment.
fn zero(cons: &Constraints) -> Constraints {
    let mut out = Constraints::new();
    for &(d, _) in &cons.imposed {
        out.impose(d, 0.0);
    }
    for r in &cons.relations {
        out.relation(r.terms.clone(), 0.0);
    }
    out
}
