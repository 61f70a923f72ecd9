//! The time stepping every solving command shares, over any [`Physics`]: per step, the kinematic
//! conditions and external forces of EXCIT (`loads`), the reduced system, the prediction and the Newton
//! corrections until Code_Aster's CONVERGENCE holds, the solve, and the cutting of a step that fails when
//! DEFI_LIST_INST asks for it.
//!
//! The relative criterion is Code_Aster's (`nmresi`): the largest residual of the free equations over
//! the physics' reference force ([`Physics::reference`]: the external forces of the free equations and
//! the reactions of the eliminated ones). Eliminated equations carry their reaction.

use super::loads::Loads;
use super::newton::{inf_norm, LineSearch};
use super::settings::Settings;
use crate::concepts::result::Step;
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::{Constraints, DofMap};
use crate::fem::physics::{Failure, Physics, Prediction, Residual, StepInfo};
use crate::solve::{self, Analysis, SolverOptions};
use std::cell::{Cell, RefCell};

/// What the steps did, for the run log.
#[derive(Debug, Default)]
pub struct StepLog {
    pub steps: usize,
    pub cuts: usize,
    pub iterations: usize,
    /// The unknowns solved (free) at the last step, and whether each unknown was eliminated.
    pub solved: usize,
    pub eliminated: Vec<bool>,
    /// Per step: INST, Δt, iterations, the absolute residual, every iteration's relative residual.
    pub table: String,
    /// Seconds in the element computations and the assembly.
    pub assembly: f64,
    /// Seconds in the solver, summed over every factorization.
    pub solver: solve::Timings,
    pub factorizations: usize,
    /// The condition estimate of the first factorization (the only one estimated).
    pub condition: Option<f64>,
    /// The last factorization's summary, relative residual and refinement steps.
    pub last_solve: Option<(solve::FactorInfo, f64, usize)>,
    /// Steps at which the reactions vanished and the relative criterion used the largest earlier one.
    pub vanished: Vec<usize>,
}

/// The time stepping of one computation.
pub struct Driver<'a, P: Physics> {
    pub cfg: &'a Settings,
    pub phys: &'a P,
    pub loads: Loads<'a>,
    pub opts: SolverOptions,
    /// The symbolic analysis of the last factorization, reused while the pattern holds.
    analysis: RefCell<Option<Analysis>>,
    /// A linear physics' last reduced matrix and its factorization, reused while the matrix does not
    /// change (the steps of a transient computation at a constant Δt).
    kept: RefCell<Option<(faer::sparse::SparseColMat<usize, f64>, solve::Factorization)>>,
    /// The largest reference force of the converged steps (the relative criterion's fallback when the
    /// reactions vanish, for a physics that asks for it).
    ref_hist: Cell<f64>,
    /// For a physics that swaps to the absolute criterion ([`Physics::swaps_to_absolute`]): the smallest
    /// reference force of the converged states (NaN before the first), and the absolute residual of the
    /// last converged state.
    load_min: Cell<f64>,
    last_abs: Cell<f64>,
}

/// What every assembly of a step shares.
struct Frame {
    step: StepInfo,
    pattern: SparsityPattern,
    fext: Vec<f64>,
}

/// The reduced tangent and residual at a state, the internal forces and the laws' trial state.
struct Assembled<S> {
    /// None when only the residual was asked for.
    k: Option<faer::sparse::SparseColMat<usize, f64>>,
    rhs: Vec<f64>,
    fint: Vec<f64>,
    state: S,
}

/// The matrix a solve takes.
enum Matrix {
    /// Factorized for this solve (a linear physics keeps it while it does not change).
    Once(faer::sparse::SparseColMat<usize, f64>),
    /// Factorized and held for the Newton corrections that reuse it (NEWTON REAC_ITER ≠ 1).
    Hold(faer::sparse::SparseColMat<usize, f64>),
    /// The matrix held last.
    Held,
}

impl<'a, P: Physics> Driver<'a, P> {
    pub fn new(cfg: &'a Settings, phys: &'a P, opts: SolverOptions) -> Self {
        Driver {
            cfg,
            phys,
            loads: Loads::new(cfg),
            opts,
            analysis: RefCell::new(None),
            kept: RefCell::new(None),
            ref_hist: Cell::new(0.0),
            load_min: Cell::new(f64::NAN),
            last_abs: Cell::new(0.0),
        }
    }

    /// Every instant of the settings from the state `(x, state)` of the first one: the steps stored at the
    /// instants ARCHIVAGE keeps (every instant without it), the initial state first as order 0 when
    /// `initial`, numbered from there; CHAM_EXCLU's fields left out of all but the last.
    pub fn run(&self, x: &mut Vec<f64>, state: &mut P::State, initial: bool, log: &mut StepLog) -> Result<Vec<Step>> {
        let times = &self.cfg.times;
        let fields = |x: &[f64], state: &P::State, t: f64, n: usize| -> Result<Step> {
            let f = self.phys.fields(x, state).map_err(|e| self.cfg.place(e))?;
            Ok(Step { nume_ordre: n as i64, inst: t, fields: f.into_iter().collect() })
        };
        let mut steps = Vec::new();
        if initial {
            steps.push(fields(x, state, times[0], 0)?);
        }
        for (n, w) in times.windows(2).enumerate() {
            self.advance(w[0], w[1], x, state, 0, log)?;
            if self.cfg.archive.as_ref().is_none_or(|a| a.keeps(w[1])) {
                steps.push(fields(x, state, w[1], n + 1)?);
            }
        }
        Ok(match &self.cfg.archive {
            Some(a) => a.select(steps, initial),
            None => steps,
        })
    }

    /// Start the relative criterion's memory from a state (ETAT_INIT's reactions are the reference force
    /// of the earlier computation).
    pub fn remember_reference(&self, t: f64, x: &[f64], state: &P::State) -> Result<()> {
        let step = StepInfo::new(t, t);
        let cons = self.loads.conditions(self.phys, t)?;
        let fext = self.loads.forces(self.phys, &step, x)?;
        let map = DofMap::build(x.len(), &zero(&cons)).map_err(|e| self.cfg.err("EXCIT", e.to_string()))?;
        let mut fint = vec![0.0; x.len()];
        let trial = self.internal(&step, x, state, None, &mut fint).map_err(fatal)?;
        let free = free_of(&map, x.len());
        let r = Residual { fext: &fext, fint: &fint, free: &free, x0: x, x };
        self.ref_hist.set(self.phys.reference_at(&r, &trial));
        Ok(())
    }

    /// Advance from `t0` to `t1`; on a failure, cut the step as DEFI_LIST_INST's ECHEC says (`level`
    /// cuts so far).
    pub fn advance(
        &self,
        t0: f64,
        t1: f64,
        x: &mut Vec<f64>,
        state: &mut P::State,
        level: usize,
        log: &mut StepLog,
    ) -> Result<()> {
        match self.step(t0, t1, x, state, log) {
            Ok(()) => Ok(()),
            Err(Failure::Fatal(e)) => Err(e),
            Err(Failure::Step(e)) => {
                let Some(sd) = self.cfg.subdivision else {
                    return Err(e);
                };
                let dt = (t1 - t0) / sd.pas as f64;
                if level >= sd.niveau || (sd.pas_mini > 0.0 && dt < sd.pas_mini) {
                    return Err(Error::runtime(format!(
                        "{} — the step from {t0} to {t1} cannot be cut further (SUBD_NIVEAU = {}, SUBD_PAS_MINI = {})",
                        e.msg, sd.niveau, sd.pas_mini
                    ))
                    .at(e.span.unwrap_or(self.cfg.span)));
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
                    self.advance(a, b, x, state, level + 1, log)?;
                }
                Ok(())
            }
        }
    }

    /// Tangent (when `tangent`: else a correction solves with the matrix held) and residual of the state
    /// `x` over the step from the laws' state `prev`, reduced by `map`; `predict` for the prediction's.
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        &self,
        fr: &Frame,
        map: &DofMap,
        x: &[f64],
        prev: &P::State,
        tangent: bool,
        predict: bool,
        log: &mut StepLog,
    ) -> std::result::Result<Assembled<P::State>, Failure> {
        let started = std::time::Instant::now();
        let mut asm = tangent.then(|| Assembler::new(map, fr.pattern.clone()));
        let mut fint = vec![0.0; x.len()];
        let step = StepInfo { predict, ..fr.step };
        let state = self.internal(&step, x, prev, asm.as_mut(), &mut fint)?;
        let r: Vec<f64> = fr.fext.iter().zip(&fint).map(|(f, g)| f - g).collect();
        let (k, rhs) = match asm {
            Some(mut asm) => {
                let all: Vec<usize> = (0..x.len()).collect();
                asm.add_vector(&all, &r);
                let (k, rhs) = asm.finish();
                (Some(k), rhs)
            }
            None => (None, map.reduce_vector(&r)),
        };
        log.assembly += started.elapsed().as_secs_f64();
        Ok(Assembled { k, rhs, fint, state })
    }

    /// The internal forces at the state `x` (the loads that depend on it among them), the tangent added
    /// to `tangent` when asked; the laws' trial state.
    fn internal(
        &self,
        step: &StepInfo,
        x: &[f64],
        prev: &P::State,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> std::result::Result<P::State, Failure> {
        let mut state = self.phys.assemble(step, x, prev, tangent.as_deref_mut(), fint).map_err(|f| self.place(f))?;
        self.loads
            .with(step.t1, |loads| Ok(self.phys.state_loads(loads, step, x, &mut state, tangent, fint)))?
            .map_err(|f| self.place(f))?;
        Ok(state)
    }

    /// RECH_LINEAIRE along the correction `full` (`dx` reduced) from the state `x`: the step ρ where the
    /// residual is orthogonal to the correction, by secants.
    #[allow(clippy::too_many_arguments)]
    fn line_search(
        &self,
        ls: &LineSearch,
        fr: &Frame,
        map: &DofMap,
        x: &[f64],
        full: &[f64],
        dx: &[f64],
        prev: &P::State,
    ) -> std::result::Result<f64, Failure> {
        let mut f = |rho: f64| -> std::result::Result<f64, Failure> {
            let trial: Vec<f64> = x.iter().zip(full).map(|(a, b)| a + rho * b).collect();
            let mut fint = vec![0.0; x.len()];
            self.internal(&fr.step, &trial, prev, None, &mut fint)?;
            let g: Vec<f64> = fint.iter().zip(&fr.fext).map(|(a, b)| a - b).collect();
            Ok(map.reduce_vector(&g).iter().zip(dx).map(|(a, b)| a * b).sum())
        };
        Ok(ls.run(&mut f)?.0)
    }

    fn place(&self, f: Failure) -> Failure {
        match f {
            Failure::Step(e) => Failure::Step(self.cfg.place(e)),
            Failure::Fatal(e) => Failure::Fatal(self.cfg.place(e)),
        }
    }

    /// The relative and absolute residuals of a state (Code_Aster's RESI_GLOB_RELA and RESI_GLOB_MAXI),
    /// and whether the reactions vanished against the earlier steps.
    #[allow(clippy::too_many_arguments)]
    fn residual(
        &self,
        map: &DofMap,
        free: &[bool],
        fr: &Frame,
        x0: &[f64],
        x: &[f64],
        fint: &[f64],
        trial: &P::State,
    ) -> (f64, f64, f64, bool) {
        let r: Vec<f64> = fr.fext.iter().zip(fint).map(|(f, g)| f - g).collect();
        let abs = inf_norm(&map.reduce_vector(&r));
        let scale = self.phys.reference_at(&Residual { fext: &fr.fext, fint, free, x0, x }, trial);
        let hist = self.ref_hist.get();
        let vanished = self.phys.reference_memory() && scale <= 1e-6 * hist;
        let s = if vanished { hist } else { scale };
        (if s > 0.0 { abs / s } else { abs }, abs, scale, vanished)
    }

    /// Solve the reduced system, its rows scaled as the physics asks.
    fn factor_solve(
        &self,
        map: &DofMap,
        matrix: Matrix,
        mut rhs: Vec<f64>,
        t1: f64,
        log: &mut StepLog,
    ) -> std::result::Result<Vec<f64>, Failure> {
        let phys = self.phys;
        let row: Vec<f64> = map.free_to_full.iter().map(|&d| phys.row_scale(d)).collect();
        let scaled = row.iter().any(|&s| s != 1.0);
        if scaled {
            for (v, s) in rhs.iter_mut().zip(&row) {
                *v *= s;
            }
        }
        let names = |dofs: &[usize]| -> String {
            dofs.iter().take(6).map(|&d| phys.label(map.free_to_full[d])).collect::<Vec<_>>().join(", ")
        };
        let check_rhs = |rhs: &[f64]| {
            let bad_f: Vec<usize> = (0..rhs.len()).filter(|&d| !rhs[d].is_finite()).collect();
            if bad_f.is_empty() {
                return Ok(());
            }
            Err(Failure::Fatal(self.cfg.err(
                "EXCIT",
                format!(
                    "the loads are not finite (nan or infinite) at unknowns {}: check the values of the loads",
                    names(&bad_f)
                ),
            )))
        };
        let (mut k, hold) = match matrix {
            Matrix::Once(k) => (k, false),
            Matrix::Hold(k) => (k, true),
            Matrix::Held => {
                check_rhs(&rhs)?;
                let opts = SolverOptions { condition: false, ..self.opts };
                let sol = self.solve_kept(None, &rhs, &opts);
                return self.account(map, sol, t1, log);
            }
        };
        // Rows scaled in place: the system is consumed by its solve (no copy of the matrix is kept alive
        // beside its factors).
        if scaled {
            let ncols = k.ncols();
            let (symbolic, vals) = k.parts_mut();
            let (cp, ri) = (symbolic.col_ptr(), symbolic.row_idx());
            for j in 0..ncols {
                for q in cp[j]..cp[j + 1] {
                    vals[q] *= row[ri[q]];
                }
            }
        }
        // A nan or an infinity in the data (E, NU, a load, a coordinate) reaches the system as such: name
        // it, rather than let the factorization call the system singular.
        let (col_ptr, values) = (k.col_ptr(), k.val());
        let bad_k: Vec<usize> =
            (0..k.ncols()).filter(|&j| values[col_ptr[j]..col_ptr[j + 1]].iter().any(|v| !v.is_finite())).collect();
        if !bad_k.is_empty() {
            return Err(Failure::Fatal(self.cfg.err(
                "CHAM_MATER",
                format!(
                    "the stiffness is not finite (nan or infinite) at unknowns {}: check the material (E, NU) and the \
                     mesh",
                    names(&bad_k)
                ),
            )));
        }
        check_rhs(&rhs)?;
        // The condition number is estimated on the first factorization only: it costs about ten solves,
        // as much as the factorization itself on large 2D systems, and the steps that follow change the
        // tangent little (NPREC still checks every factorization's pivots).
        let mut opts = SolverOptions { condition: self.opts.condition && log.factorizations == 0, ..self.opts };
        if let Some(m) = phys.solver_method(k.nrows()) {
            opts.method = m;
        }
        // A linear physics over several steps keeps its matrix and factors for the next step, and so does a
        // Newton whose corrections reuse it (`hold`); a single solve (MECA_STATIQUE) keeps nothing beside
        // its factors.
        let sol = if hold {
            self.solve_kept(Some((k, true)), &rhs, &opts)
        } else if phys.linear() && self.cfg.times.len() > 2 {
            self.solve_kept(Some((k, false)), &rhs, &opts)
        } else {
            solve::solve_with(k.as_ref(), &rhs, &opts, &mut self.analysis.borrow_mut()).map(|s| (s, true))
        };
        self.account(map, sol, t1, log)
    }

    /// A solve's errors named, its times and factorizations counted in the log.
    fn account(
        &self,
        map: &DofMap,
        sol: std::result::Result<(solve::Solution, bool), solve::SolveError>,
        t1: f64,
        log: &mut StepLog,
    ) -> std::result::Result<Vec<f64>, Failure> {
        let phys = self.phys;
        let (sol, fresh) = sol.map_err(|e| {
            let singular = matches!(e, solve::SolveError::Singular { .. });
            let msg = super::solver::solve_error(e, &self.opts, &|d| phys.label(map.free_to_full[d]));
            if phys.linear() && singular {
                // A linear system that cannot be solved: the loads leave a motion free.
                Failure::Fatal(self.cfg.err("EXCIT", msg))
            } else {
                Failure::Step(self.cfg.err("SOLVEUR", format!("the tangent matrix at INST={t1}: {msg}")))
            }
        })?;
        let (t, s) = (&mut log.solver, &sol.timings);
        t.symbolic += s.symbolic;
        t.factorization += s.factorization;
        t.condition += s.condition;
        t.solve += s.solve;
        if log.factorizations == 0 {
            log.condition = sol.info.condition;
        }
        if fresh {
            log.factorizations += 1;
        }
        let info = solve::FactorInfo { condition: log.condition, ..sol.info };
        log.last_solve = Some((info, sol.residual, sol.refinements));
        if sol.x.iter().any(|v| !v.is_finite()) {
            return Err(Failure::Step(
                Error::runtime("the Newton correction is not finite (singular system)").at(self.cfg.span),
            ));
        }
        Ok(sol.x)
    }

    /// A solve with the kept matrix and factorization. `Some((k, false))` (a linear physics): the kept
    /// factorization serves when `k` has its pattern and values within 1e-10 (relative, the rounding of
    /// the instants' Δt), else `k` is factorized and kept (the old one freed first); `Some((k, true))`:
    /// `k` is factorized and kept; `None`: the kept ones serve (a Newton correction with the matrix of
    /// an earlier iteration). The refinement runs against the kept matrix, so the solution is its own.
    /// Whether it factorized.
    fn solve_kept(
        &self,
        new: Option<(faer::sparse::SparseColMat<usize, f64>, bool)>,
        rhs: &[f64],
        opts: &SolverOptions,
    ) -> std::result::Result<(solve::Solution, bool), solve::SolveError> {
        let mut kept = self.kept.borrow_mut();
        let same = match &new {
            None => true,
            Some((_, true)) => false,
            Some((k, false)) => kept.as_ref().is_some_and(|(m, _)| {
                let scale = m.val().iter().fold(0.0f64, |a, v| a.max(v.abs()));
                m.col_ptr() == k.col_ptr()
                    && m.row_idx() == k.row_idx()
                    && m.val().iter().zip(k.val()).all(|(a, b)| (a - b).abs() <= 1e-10 * scale)
            }),
        };
        if let (false, Some((k, _))) = (same, new) {
            *kept = None;
            let f = solve::factorize_with(k.as_ref(), opts, &mut self.analysis.borrow_mut())?;
            *kept = Some((k, f));
        }
        let Some((k, f)) = kept.as_mut() else {
            return Err(solve::SolveError::Internal("no matrix is held for this Newton correction".into()));
        };
        let started = std::time::Instant::now();
        let (x, residual, refinements) = solve::solve_refined_or_lu(f, k.as_ref(), rhs, opts)?;
        solve::check_solution(k.as_ref(), &x, rhs, residual, opts)?;
        let mut info = f.info.clone();
        info.timings.solve = started.elapsed();
        if same {
            // The factorization's own times were counted when it was made.
            info.timings.symbolic = Default::default();
            info.timings.factorization = Default::default();
            info.timings.condition = Default::default();
        }
        let sol = solve::Solution {
            x,
            method: info.method.unwrap_or(solve::Method::Lu),
            timings: info.timings,
            residual,
            factor_nnz: info.factor_nnz,
            refinements,
            info,
        };
        Ok((sol, !same))
    }

    /// One step [t0, t1]: the conditions and forces of the loads, the prediction, then Newton corrections.
    fn step(
        &self,
        t0: f64,
        t1: f64,
        x: &mut Vec<f64>,
        state: &mut P::State,
        log: &mut StepLog,
    ) -> std::result::Result<(), Failure> {
        // Every step, linear ones included, stops at the run's time limit.
        crate::diag::check_deadline()
            .map_err(|mut e| {
                e.msg = format!("{} at the step to INST={t1}", e.msg);
                e.at(self.cfg.span)
            })
            .map_err(Failure::Fatal)?;
        let n = self.phys.unknowns();
        let step = StepInfo::new(t0, t1);
        let cons = self.loads.conditions(self.phys, t1)?;
        let fext = self.loads.forces(self.phys, &step, x)?;
        // The increments the conditions prescribe from the current state, then none.
        let incr = increments(&cons, x);
        let map = DofMap::build(n, &zero(&incr))
            .map_err(|e| self.cfg.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
        let free = free_of(&map, n);
        log.solved = map.nfree;
        log.eliminated = free.iter().map(|f| !f).collect();
        let elems: ElementDofs = self.phys.element_dofs();
        let pattern = SparsityPattern::build(&map, &elems);
        let fr = Frame { step, pattern, fext };
        let x0 = x.clone();
        // NEWTON REAC_ITER (Code_Aster's semantics): the matrix is assembled again at the corrections
        // whose number is a multiple of it (1: every one, full Newton; 0: none, the prediction's matrix
        // serves every correction of the step); the others solve with the matrix held last.
        let reac = if self.phys.linear() { 1 } else { self.cfg.reac_iter };
        let modified = reac != 1;
        let mut unew = match self.phys.prediction() {
            Prediction::Tangent => {
                // The tangent and internal forces of the start state, the prescribed increments on the
                // right-hand side.
                let map_pred = DofMap::build(n, &incr)
                    .map_err(|e| self.cfg.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
                let pred = self.assemble(&fr, &map_pred, x, state, true, true, log)?;
                let k = pred.k.expect("assembled with its tangent");
                let k = if modified { Matrix::Hold(k) } else { Matrix::Once(k) };
                let dx = self.factor_solve(&map_pred, k, pred.rhs, t1, log)?;
                x.iter().zip(map_pred.expand(&dx)).map(|(a, b)| a + b).collect()
            }
            Prediction::Imposed => {
                let map_values = DofMap::build(n, &cons)
                    .map_err(|e| self.cfg.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
                let kept: Vec<f64> = map_values.free_to_full.iter().map(|&d| x[d]).collect();
                map_values.expand(&kept)
            }
        };
        // Whether a matrix is held for the next correction (the prediction's, under REAC_ITER ≠ 1).
        let mut held = modified && self.phys.prediction() == Prediction::Tangent;
        // Corrections made (the prediction's solve counts as the first for the test).
        let predicted = self.phys.prediction() == Prediction::Tangent;
        let mut iters = 0;
        let mut history = Vec::new();
        loop {
            // The correction this assembly serves (the prediction was the first).
            let next = iters + usize::from(predicted);
            let fresh = !held || (reac > 0 && next % reac == 0);
            let Assembled { k, rhs, fint, state: trial } = self.assemble(&fr, &map, &unew, state, fresh, false, log)?;
            let (rel, abs, reference, vanished) = self.residual(&map, &free, &fr, &x0, &unew, &fint, &trial);
            history.push(rel);
            let solved = predicted || iters > 0;
            // Code_Aster's swap: past the first step, vanishing loads turn RESI_GLOB_RELA into an absolute
            // test at the last converged residual.
            let swapped = self.phys.swaps_to_absolute() && {
                if self.load_min.get().is_nan() {
                    self.load_min.set(reference);
                }
                log.steps > 0 && self.cfg.conv.resi_rela.is_some() && reference <= 1e-6 * self.load_min.get()
            };
            let done = if self.phys.linear() {
                solved
            } else if swapped {
                solved && abs <= self.last_abs.get()
            } else {
                solved
                    && self.cfg.conv.resi_rela.map(|tol| rel <= tol).unwrap_or(true)
                    && self.cfg.conv.resi_maxi.map(|tol| abs <= tol).unwrap_or(true)
            };
            if done {
                if self.phys.swaps_to_absolute() {
                    if !swapped {
                        self.load_min.set(self.load_min.get().min(reference));
                    }
                    self.last_abs.set(abs);
                }
                *x = unew;
                *state = trial;
                log.steps += 1;
                log.iterations += iters;
                if !vanished {
                    self.ref_hist.set(self.ref_hist.get().max(reference));
                } else {
                    log.vanished.push(log.steps);
                }
                // Every iteration's relative residual (with a prediction, its own first).
                let hist: Vec<String> = history.iter().map(|r| crate::text::sci(*r, 3, false)).collect();
                log.table.push_str(&format!(
                    "  INST {:>14}  Δt {:>11}  iterations {:>2}  RESI_GLOB_MAXI {:>10}  RESI_GLOB_RELA {}\n",
                    crate::text::sci(t1, 6, false),
                    crate::text::sci(t1 - t0, 3, false),
                    iters,
                    crate::text::sci(abs, 3, false),
                    hist.join(" → "),
                ));
                log.table.push_str(&self.phys.step_report(x, state));
                return Ok(());
            }
            if iters >= self.cfg.conv.iter_max {
                return Err(Failure::Step(self.cfg.conv.not_converged(t1, rel, abs)));
            }
            crate::diag::check_deadline()
                .map_err(|mut e| {
                    e.msg = format!("{} during Newton iteration {} at INST={t1}", e.msg, iters + 1);
                    e
                })
                .map_err(Failure::Fatal)?;
            let k = match k {
                Some(k) if modified => {
                    held = true;
                    Matrix::Hold(k)
                }
                Some(k) => Matrix::Once(k),
                None => Matrix::Held,
            };
            let dx = self.factor_solve(&map, k, rhs, t1, log)?;
            let full = map.expand(&dx);
            let rho = match &self.cfg.line_search {
                Some(ls) => self.line_search(ls, &fr, &map, &unew, &full, &dx, state)?,
                None => 1.0,
            };
            for (ui, di) in unew.iter_mut().zip(full) {
                *ui += rho * di;
            }
            iters += 1;
        }
    }
}

fn fatal(f: Failure) -> Error {
    match f {
        Failure::Step(e) | Failure::Fatal(e) => e,
    }
}

/// Whether each unknown is free under `map`.
fn free_of(map: &DofMap, n: usize) -> Vec<bool> {
    let mut free = vec![false; n];
    for &d in &map.free_to_full {
        free[d] = true;
    }
    free
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
