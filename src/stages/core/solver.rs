//! SOLVEUR as we run it, the messages of a solve that fails (singular unknowns named) and the solver's log.

use crate::catalog::args::Args;
use crate::diag::Result;
use crate::solve::{self, Ordering, SolverOptions};

/// SOLVEUR as we run it: the options, and the log line that says how Code_Aster's keywords were mapped.
#[derive(Debug, Clone)]
pub struct Solveur {
    pub opts: SolverOptions,
    /// METHODE and RENUM as given (or defaulted), and what runs for them.
    pub mapping: String,
}

/// Every METHODE of Code_Aster is solved by our sparse direct factorization: the direct ones (MUMPS,
/// MULT_FRONT, LDLT) by LLᵀ, LDLᵀ or LU as the matrix calls for (symmetric positive definite, symmetric
/// indefinite, non-symmetric), and an iterative one (GCPC, PETSC) by the same direct solve, which is what
/// it converges to. RENUM chooses our fill-reducing ordering: the nested dissections (METIS, SCOTCH, PORD,
/// PARMETIS, PTSCOTCH) run METIS's, the minimum degrees (AMD, AMF, QAMD, MD, MDA) and the profile
/// ordering RCMK run AMD (the solution does not depend on it), AUTO chooses by size. NPREC and RESI_RELA
/// keep their meaning (see `solve`). The other knobs of how a solver works (PCENT_PIVOT,
/// GESTION_MEMOIRE, ACCELERATION, preconditioners, ...) change its cost or make it approximate, never the
/// exact solution we compute, so they are taken as read. STOP_SINGULIER='NON' (going on with a singular
/// matrix) is refused.
pub fn solveur(a: &Args) -> Result<Solveur> {
    let mut opts = SolverOptions::default();
    let mut methode = "MUMPS".to_string();
    let mut renum = "AUTO".to_string();
    if let Some(s) = a.fact("SOLVEUR") {
        if s.text_if_declared("STOP_SINGULIER") == Some("NON") {
            return Err(s.err("STOP_SINGULIER", "STOP_SINGULIER='NON' is not supported yet"));
        }
        if let Some(m) = s.text_if_declared("METHODE") {
            methode = m.to_string();
        }
        if let Some(r) = s.text_if_declared("RENUM") {
            renum = r.to_string();
        }
        if let Some(n) = s.int("NPREC") {
            opts.nprec = n as i32;
        }
        if let Some(r) = s.real("RESI_RELA") {
            opts.resi_rela = r;
        }
        // LDLT and MULT_FRONT have no RESI_RELA: Code_Aster checks no residual after them (NPREC only).
        if matches!(methode.as_str(), "LDLT" | "MULT_FRONT") {
            opts.resi_rela = -1.0;
        }
        s.read_all();
    }
    opts.ordering = match renum.as_str() {
        "METIS" | "SCOTCH" | "PORD" | "PARMETIS" | "PTSCOTCH" => Ordering::NestedDissection,
        "AUTO" => Ordering::Auto,
        _ => Ordering::Amd,
    };
    let kind = match methode.as_str() {
        "GCPC" | "PETSC" => "the sparse direct solve it converges to",
        _ => "sparse direct",
    };
    let order = match opts.ordering {
        Ordering::Auto => {
            format!("AMD below {} unknowns, nested dissection (METIS) above", solve::ordering::ND_THRESHOLD)
        }
        o => o.name().to_string(),
    };
    let mapping = format!("METHODE='{methode}' RENUM='{renum}': {kind}, {order}");
    Ok(Solveur { opts, mapping })
}

/// The SOLVEUR options alone.
pub fn solver_options(a: &Args) -> Result<SolverOptions> {
    Ok(solveur(a)?.opts)
}

/// The run log's line on a solve: how SOLVEUR was mapped, what ran (method, ordering, threads, fill,
/// condition estimate and the digits it costs), NPREC and RESI_RELA, the residual reached, and the peak
/// memory of the process.
pub fn solver_log(sv: &Solveur, info: &solve::FactorInfo, residual: f64, refinements: usize) -> String {
    let resi = if sv.opts.resi_rela >= 0.0 { format!("{:.1e}", sv.opts.resi_rela) } else { "not checked".into() };
    let nprec = if sv.opts.nprec >= 0 { sv.opts.nprec.to_string() } else { "check off".into() };
    format!(
        "    solver    : SOLVEUR {}\n                {}\n                NPREC={nprec}, RESI_RELA={resi}: relative residual {residual:.1e} after {refinements} refinement step(s); peak memory {}\n",
        sv.mapping,
        info.summary(),
        peak_memory()
    )
}

/// The process's peak memory, for the log.
pub fn peak_memory() -> String {
    match solve::peak_memory() {
        Some(b) => format!("{:.2} GiB", b as f64 / (1u64 << 30) as f64),
        None => "unknown".into(),
    }
}

/// A solver error as the user reads it: a singular matrix names the unknowns where it shows (through
/// `label`, from a reduced equation number) and says how.
pub fn solve_error(e: solve::SolveError, opts: &SolverOptions, label: &dyn Fn(usize) -> String) -> String {
    match e {
        solve::SolveError::Singular { kind, dofs, pivots } => {
            let names: Vec<String> = dofs.iter().take(6).map(|&d| label(d)).collect();
            let more = if dofs.len() > 6 { format!(" and {} more", dofs.len() - 6) } else { String::new() };
            match kind {
                solve::SingularKind::Pivot => {
                    let worst = pivots.first().copied().unwrap_or(0.0);
                    let lost = if worst > 0.0 {
                        format!("{:.1} digits", -worst.log10())
                    } else {
                        "all digits (null pivot)".into()
                    };
                    format!(
                        "the system is singular: the factorization lost more than NPREC={} significant digits at \
                         unknown {} ({lost}){}{more} (rigid-body motion not prevented? a multiplier without its condition?)",
                        opts.nprec,
                        names.first().cloned().unwrap_or_default(),
                        if names.len() > 1 { format!(", also at {}", names[1..].join(", ")) } else { String::new() }
                    )
                }
                solve::SingularKind::NoStiffness => {
                    format!("the system is singular: unknowns without stiffness {}{more}", names.join(", "))
                }
                solve::SingularKind::Structural => {
                    format!("the system is structurally singular at unknown {}", names.join(", "))
                }
                solve::SingularKind::Residual(r) => format!(
                    "the relative residual of the solve, {r:.3e}, exceeds RESI_RELA={:.1e} (ill-conditioned or \
                     singular system); largest residuals at {}{more}",
                    opts.resi_rela,
                    names.join(", ")
                ),
            }
        }
        other => other.to_string(),
    }
}
