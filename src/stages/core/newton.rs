//! Time stepping and Newton iterations shared by the solving stages: the instants of INCREMENT, the
//! options no driver implements yet, Code_Aster's CONVERGENCE criteria and the Newton loop on a
//! reduced system.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::diag::Span;

/// The computation instants: the list, cut to INST_INIT / INST_FIN (or their
/// NUME_INST_* forms). The first one is the initial state.
pub fn instants(a: &Args) -> Result<Vec<f64>> {
    instants_from(a, None)
}

/// The instants of a DEFI_LIST_REEL or DEFI_LIST_INST concept, strictly increasing; the message of what
/// is wrong otherwise.
pub fn list_values(lc: &crate::concepts::ConceptRef) -> std::result::Result<Vec<f64>, String> {
    let list = match &*lc.data() {
        ConceptData::ListReal(v) => v.clone(),
        ConceptData::ListInst(l) => l.instants.clone(),
        _ => {
            return Err(format!(
                "{} ({}) is not a list of instants: give a DEFI_LIST_REEL or a DEFI_LIST_INST",
                lc.label(),
                lc.kind()
            ))
        }
    };
    if let Some(w) = list.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)) {
        return Err(format!(
            "the instants of {} must increase strictly ({} then {})",
            lc.label(),
            list[w],
            list[w + 1]
        ));
    }
    Ok(list)
}

/// The same, with `init` the instant of ETAT_INIT's state (EVOL_NOLI): when INCREMENT gives neither
/// INST_INIT nor NUME_INST_INIT, the computation starts there, as Code_Aster's `nmdini`/`nmcrls` do: at
/// the instant of the list within PRECISION times the smallest step of the list, else at the last
/// instant before it, whose value becomes `init`.
pub fn instants_from(a: &Args, init: Option<f64>) -> Result<Vec<f64>> {
    let inc = a.fact("INCREMENT").ok_or_else(|| a.err("INCREMENT", "INCREMENT is required"))?;
    let lc = inc.req_concept("LIST_INST")?;
    let list = list_values(&lc).map_err(|m| inc.err("LIST_INST", m))?;
    let prec = inc.real("PRECISION").unwrap_or(1e-6);
    let find = |t: f64, kw: &str| -> Result<usize> {
        list.iter()
            .position(|&x| (x - t).abs() <= prec * t.abs().max(1e-300) || x == t)
            .ok_or_else(|| inc.err(kw, format!("{t} is not an instant of {}", lc.label())))
    };
    // The list's instant that ETAT_INIT's one replaces, if it is not in the list.
    let mut replaced: Option<(usize, f64)> = None;
    let first = match (inc.int("NUME_INST_INIT"), inc.real("INST_INIT"), init) {
        (Some(n), _, _) => n as usize,
        (None, Some(t), _) => find(t, "INST_INIT")?,
        (None, None, Some(t)) => {
            let dtmin = list.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
            let tol = if dtmin.is_finite() { prec * dtmin } else { 0.0 };
            match list.iter().position(|&x| (x - t).abs() <= tol) {
                Some(i) => i,
                None => {
                    // The last instant before `init` (the first one if none is), which `init` replaces.
                    let i = list.iter().rposition(|&x| x < t).unwrap_or(0);
                    if list.get(i + 1).is_some_and(|&next| t >= next) || (i + 1 == list.len()) {
                        return Err(inc.err(
                            "LIST_INST",
                            format!(
                                "the initial state of ETAT_INIT is at INST={t}, at or after the last instant \
                                 to compute of {}",
                                lc.label()
                            ),
                        ));
                    }
                    replaced = Some((i, t));
                    i
                }
            }
        }
        _ => 0,
    };
    let last = match (inc.int("NUME_INST_FIN"), inc.real("INST_FIN")) {
        (Some(n), _) => n as usize,
        (None, Some(t)) => find(t, "INST_FIN")?,
        _ => list.len() - 1,
    };
    let mut list = list;
    if let Some((i, t)) = replaced {
        list[i] = t;
    }
    if first >= last || last >= list.len() {
        return Err(inc.err("LIST_INST", format!("no step to compute between instants #{first} and #{last}")));
    }
    Ok(list[first..=last].to_vec())
}

/// How a step that fails is cut: DEFI_LIST_INST's ECHEC; a DEFI_LIST_REEL stops the run (ACTION='ARRET').
pub fn subdivision(a: &Args) -> Option<crate::concepts::Subdivision> {
    let lc = a.fact("INCREMENT")?.concept("LIST_INST")?;
    let d = lc.data();
    match &*d {
        ConceptData::ListInst(l) => l.subdivision,
        _ => None,
    }
}

/// NEWTON's options (PREDICTION, MATRICE, REAC_ITER, REAC_INCR, ...): our drivers assemble the
/// consistent tangent at every iteration, which converges to the same state as any of Code_Aster's
/// choices. A line for the run log when the file asks for something else than the default.
pub fn newton_note(a: &Args) -> Option<String> {
    let occ = a.declares("NEWTON").then(|| a.fact("NEWTON")).flatten()?;
    let asked: Vec<String> =
        occ.items.iter().filter(|i| !i.defaulted).map(|i| format!("{}={}", i.name, show(&i.value))).collect();
    occ.read_all();
    (!asked.is_empty()).then(|| {
        format!(
            "    NEWTON    : {} asked; the consistent tangent is assembled at every iteration (same converged state)",
            asked.join(", ")
        )
    })
}

fn show(v: &crate::catalog::args::ArgValue) -> String {
    match v {
        crate::catalog::args::ArgValue::Simple(vals) => vals.iter().map(|x| x.show()).collect::<Vec<_>>().join(", "),
        crate::catalog::args::ArgValue::Factor(_) => "_F(...)".into(),
    }
}

/// The largest absolute value of a vector (0 for an empty one).
pub fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// STAT_NON_LINE's CONVERGENCE as Code_Aster reads it: RESI_GLOB_RELA (1e-6 when neither it nor
/// RESI_GLOB_MAXI is given), RESI_GLOB_MAXI, ITER_GLOB_MAXI (10). The criteria we do not compute stop the
/// run by name: RESI_REFE_RELA, RESI_COMP_RELA, and ARRET='NON' (going on after a step that did not
/// converge).
#[derive(Debug, Clone, Copy)]
pub struct Convergence {
    pub resi_rela: Option<f64>,
    pub resi_maxi: Option<f64>,
    pub iter_max: usize,
    /// Where CONVERGENCE was given (the command when it was not): a step that does not converge is
    /// reported there.
    pub span: Span,
}

impl Default for Convergence {
    fn default() -> Self {
        Convergence { resi_rela: Some(1e-6), resi_maxi: None, iter_max: 10, span: Span::default() }
    }
}

impl Convergence {
    pub fn from_args(a: &Args) -> Result<Convergence> {
        let Some(c) = a.declares("CONVERGENCE").then(|| a.fact("CONVERGENCE")).flatten() else {
            return Ok(Convergence { span: a.span, ..Convergence::default() });
        };
        for kw in ["RESI_REFE_RELA", "RESI_COMP_RELA"] {
            if c.declares(kw) && c.given(kw) {
                return Err(c.err(kw, "not supported yet (RESI_GLOB_RELA and RESI_GLOB_MAXI are)"));
            }
        }
        if c.text_if_declared("ARRET") == Some("NON") {
            return Err(
                c.err("ARRET", "ARRET='NON' (going on after a step that did not converge) is not supported yet")
            );
        }
        let resi_rela = c.real("RESI_GLOB_RELA");
        let resi_maxi = c.real("RESI_GLOB_MAXI");
        Ok(Convergence {
            resi_rela: if resi_rela.is_none() && resi_maxi.is_none() { Some(1e-6) } else { resi_rela },
            resi_maxi,
            iter_max: c.int("ITER_GLOB_MAXI").unwrap_or(10).max(1) as usize,
            span: a.span_of("CONVERGENCE"),
        })
    }

    /// The error of a step that did not converge in ITER_GLOB_MAXI corrections, located at CONVERGENCE.
    pub fn not_converged(&self, t: f64, rel: f64, abs: f64) -> crate::diag::Error {
        crate::diag::Error::runtime(format!(
            "CONVERGENCE: Newton did not converge at INST={t} in {} iterations (relative residual {rel:.3e}, \
             absolute {abs:.3e})",
            self.iter_max
        ))
        .at(self.span)
    }

    /// After `iters` corrections, do the residual norms meet every given criterion?
    pub fn converged(&self, iters: usize, rel: f64, abs: f64) -> bool {
        iters > 0
            && self.resi_rela.map(|tol| rel <= tol).unwrap_or(true)
            && self.resi_maxi.map(|tol| abs <= tol).unwrap_or(true)
    }
}

/// One instant of a Newton solve, as a driver sees it: the residual at the current state and a
/// correction of that state.
pub trait NewtonStep {
    /// The residual at the current state: its relative and absolute norms.
    fn residual(&mut self) -> Result<(f64, f64)>;
    /// Solve the tangent system for a correction and apply it.
    fn correct(&mut self) -> Result<()>;
}

/// How a Newton solve of one instant ended.
#[derive(Debug, Clone, Copy)]
pub struct Converged {
    pub iters: usize,
    pub rel: f64,
    pub abs: f64,
}

/// The Newton loop of one instant at time `t`: corrections until `conv` holds, or exactly one when
/// `linear` (MECA_STATIQUE: one solve, no convergence test). A solve that does not converge in
/// ITER_GLOB_MAXI corrections stops with a message located at CONVERGENCE; one past the run's time
/// limit stops before its next correction.
pub fn newton(conv: &Convergence, linear: bool, t: f64, step: &mut impl NewtonStep) -> Result<Converged> {
    let mut iters = 0;
    loop {
        let (rel, abs) = step.residual()?;
        let done = if linear { iters == 1 } else { conv.converged(iters, rel, abs) };
        if done {
            return Ok(Converged { iters, rel, abs });
        }
        if iters == conv.iter_max {
            return Err(conv.not_converged(t, rel, abs));
        }
        crate::diag::check_deadline().map_err(|mut e| {
            e.msg = format!("{} during Newton iteration {} at INST={t}", e.msg, iters + 1);
            e
        })?;
        step.correct()?;
        iters += 1;
    }
}

/// What ARCHIVAGE keeps of a computation (as Code_Aster's storage manager): the initial state, the
/// instants of INST / LIST_INST (within PRECISION, by CRITERE) or every PAS_ARCH-th instant, always the
/// last one; the fields of CHAM_EXCLU are left out of every stored instant but the last.
pub struct Archive {
    /// The instants stored beyond the initial state.
    pub instants: Vec<f64>,
    pub excluded: Vec<String>,
}

impl Archive {
    /// ARCHIVAGE of a STAT_NON_LINE over `times` (the initial instant first); the last instant is always
    /// stored.
    pub fn from_args(a: &Args, times: &[f64]) -> Result<Archive> {
        Archive::from_args_keeping(a, times, true)
    }

    /// ARCHIVAGE over `times` (the initial instant first), the last instant stored when `keep_last` even
    /// if ARCHIVAGE does not select it.
    pub fn from_args_keeping(a: &Args, times: &[f64], keep_last: bool) -> Result<Archive> {
        let all = Archive { instants: times[1..].to_vec(), excluded: Vec::new() };
        let Some(arch) = a.fact("ARCHIVAGE") else { return Ok(all) };
        let excluded = arch.texts("CHAM_EXCLU");
        let wanted: Option<(Vec<f64>, &str)> = if arch.has("INST") {
            Some((arch.reals("INST"), "INST"))
        } else if let Some(l) = arch.concept("LIST_INST") {
            Some((l.reals().map_err(|e| arch.err("LIST_INST", e.msg))?, "LIST_INST"))
        } else {
            None
        };
        let mut out = Vec::new();
        match wanted {
            Some((list, kw)) => {
                let crit = arch.text("CRITERE").unwrap_or("RELATIF");
                let prec = arch.real("PRECISION").unwrap_or(1e-6);
                for &t in &times[1..] {
                    let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
                    if list.iter().any(|&x| (x - t).abs() <= tol) {
                        out.push(t);
                    }
                }
                // Instants asked for that the computation never reaches are left out, as Code_Aster does;
                // a list that selects none would store nothing.
                if out.is_empty() {
                    return Err(arch.err(kw, "no instant of the computation is selected"));
                }
            }
            None => {
                let pas = arch.int("PAS_ARCH").unwrap_or(1).max(1) as usize;
                out.extend(times[1..].iter().enumerate().filter(|(k, _)| (k + 1) % pas == 0).map(|(_, t)| *t));
            }
        }
        let last = *times.last().expect("an initial instant at least");
        if keep_last && times.len() > 1 && out.last() != Some(&last) {
            out.push(last);
        }
        Ok(Archive { instants: out, excluded })
    }

    /// Is the instant `t` of the computation stored?
    pub fn keeps(&self, t: f64) -> bool {
        self.instants.iter().any(|&k| (k - t).abs() <= 1e-12 * t.abs().max(1e-300))
    }

    /// The stored steps of a computation (the initial state first when `initial`; instants it does not
    /// keep are left out if a driver stored them): renumbered from 0 (or 1), CHAM_EXCLU's fields removed
    /// but at the last.
    pub fn select(
        &self,
        steps: Vec<crate::concepts::result::Step>,
        initial: bool,
    ) -> Vec<crate::concepts::result::Step> {
        let first = if initial { 0 } else { 1 };
        let mut kept: Vec<crate::concepts::result::Step> = steps
            .into_iter()
            .enumerate()
            .filter(|(k, s)| (initial && *k == 0) || self.keeps(s.inst))
            .map(|(_, s)| s)
            .collect();
        let n = kept.len();
        for (k, s) in kept.iter_mut().enumerate() {
            s.nume_ordre = (first + k) as i64;
            if k + 1 < n {
                for f in &self.excluded {
                    s.fields.remove(f);
                }
            }
        }
        kept
    }
}

/// A line search along a Newton correction Δ (RECH_LINEAIRE METHODE='CORDE', Code_Aster's secant
/// method): the step ρ where `f(ρ) = G(x + ρ Δ) · Δ` vanishes, within RESI_LINE_RELA of `f(0)`, in at
/// most ITER_LINE_MAXI secants, ρ kept within [RHO_MIN, RHO_MAX] and out of ]−RHO_EXCL, RHO_EXCL[.
#[derive(Debug, Clone, Copy)]
pub struct LineSearch {
    pub resi: f64,
    pub iter_max: usize,
    pub rho_min: f64,
    pub rho_max: f64,
    pub rho_excl: f64,
}

impl LineSearch {
    /// ρ within [RHO_MIN, RHO_MAX], and out of the exclusion zone, decided on the secant's own value as
    /// Code_Aster's `zbinte` does (a small negative secant gives −RHO_EXCL).
    fn limits(&self, rho: f64) -> f64 {
        let mut r = rho.clamp(self.rho_min, self.rho_max);
        if (-self.rho_excl..0.0).contains(&rho) {
            r = -self.rho_excl;
        }
        if (0.0..=self.rho_excl).contains(&rho) {
            r = self.rho_excl;
        }
        r
    }

    /// The best ρ found for `f`, and the number of evaluations beyond `f(0)`.
    pub fn run<E>(
        &self,
        f: &mut dyn FnMut(f64) -> std::result::Result<f64, E>,
    ) -> std::result::Result<(f64, usize), E> {
        let f0 = f(0.0)?;
        let fcvg = (self.resi * f0).abs();
        let (mut rhom, mut rho, mut fm) = (0.0, 1.0, f0);
        let (mut rhoopt, mut fopt) = (rho, f64::MAX);
        let mut evals = 0;
        for _ in 0..=self.iter_max {
            let fr = f(rho)?;
            evals += 1;
            if fr.abs() <= fopt {
                rhoopt = rho;
                fopt = fr.abs();
                if fr.abs() < fcvg {
                    return Ok((rhoopt, evals));
                }
            }
            let previous = rho;
            rho = if (fr - fm).abs() > f64::MIN_POSITIVE {
                self.limits((fr * rhom - fm * rho) / (fr - fm))
            } else if fr * (rho - rhom) * (fr - fm) <= 0.0 {
                self.rho_max
            } else {
                self.rho_min
            };
            rhom = previous;
            fm = fr;
        }
        Ok((rhoopt, evals))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x² = 2 by Newton from 1: converges quadratically, within the default criterion.
    struct Sqrt2 {
        x: f64,
    }
    impl NewtonStep for Sqrt2 {
        fn residual(&mut self) -> Result<(f64, f64)> {
            let r = (self.x * self.x - 2.0).abs();
            Ok((r / 2.0, r))
        }
        fn correct(&mut self) -> Result<()> {
            self.x -= (self.x * self.x - 2.0) / (2.0 * self.x);
            Ok(())
        }
    }

    #[test]
    fn newton_converges_quadratically_and_counts_corrections() {
        let mut s = Sqrt2 { x: 1.0 };
        let c = newton(&Convergence::default(), false, 1.0, &mut s).unwrap();
        assert!((s.x - 2f64.sqrt()).abs() < 1e-11);
        assert_eq!(c.iters, 4);
        assert!(c.rel <= 1e-6);
    }

    #[test]
    fn newton_stops_at_iter_glob_maxi() {
        let mut s = Sqrt2 { x: 1.0 };
        let conv = Convergence { iter_max: 2, ..Convergence::default() };
        let e = newton(&conv, false, 3.0, &mut s).unwrap_err();
        assert!(e.msg.contains("did not converge at INST=3 in 2 iterations"), "{}", e.msg);
    }

    #[test]
    fn newton_stops_at_the_runs_deadline() {
        let mut s = Sqrt2 { x: 1.0 };
        let deadline = crate::diag::Deadline::after(std::time::Duration::ZERO);
        let e = crate::diag::with_deadline(Some(deadline), || newton(&Convergence::default(), false, 2.0, &mut s))
            .unwrap_err();
        assert_eq!(e.kind, crate::diag::ErrorKind::TimeLimit);
        assert_eq!(e.msg, "time limit of 0 s exceeded during Newton iteration 1 at INST=2");
        assert_eq!(s.x, 1.0, "no correction past the deadline");
    }

    #[test]
    fn a_linear_solve_is_one_correction() {
        let mut s = Sqrt2 { x: 1.0 };
        let c = newton(&Convergence::default(), true, 0.0, &mut s).unwrap();
        assert_eq!(c.iters, 1);
        assert_eq!(s.x, 1.5);
    }

    #[test]
    fn inf_norm_of_mixed_signs() {
        assert_eq!(inf_norm(&[1.0, -3.5, 2.0]), 3.5);
        assert_eq!(inf_norm(&[]), 0.0);
    }

    fn search() -> LineSearch {
        LineSearch { resi: 0.1, iter_max: 3, rho_min: 1e-2, rho_max: 10.0, rho_excl: 0.9e-2 }
    }

    /// On a linear f the first secant lands on its root: f(ρ) = 2 (ρ − 0.4).
    #[test]
    fn line_search_finds_the_root_of_a_linear_function() {
        let (rho, evals) = search().run::<()>(&mut |r| Ok(2.0 * (r - 0.4))).expect("no error");
        assert!((rho - 0.4).abs() < 1e-12, "{rho}");
        assert_eq!(evals, 2);
    }

    /// A full step that already satisfies the criterion is kept; a root beyond RHO_MAX is clamped to it.
    #[test]
    fn line_search_keeps_a_good_step_and_clamps_to_rho_max() {
        let (rho, evals) = search().run::<()>(&mut |r| Ok(1.0 - 0.95 * r)).expect("no error");
        assert_eq!((rho, evals), (1.0, 1));
        let (rho, _) = search().run::<()>(&mut |r| Ok(1.0 - 0.01 * r)).expect("no error");
        assert_eq!(rho, 10.0);
    }
}
