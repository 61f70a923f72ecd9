//! What one run of a study measured: from the child process (wall time, peak memory, exit) and from its
//! message file (time per command, unknowns, Newton iterations, POST_ERREUR's norms, check lines).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// The metrics of one run.
#[derive(Debug, Clone, Default)]
pub struct Metrics {
    /// OK, NOOK_TEST_RESU, <F>_ERROR, ..., TIMEOUT.
    pub diagnostic: String,
    pub wall: f64,
    /// Peak resident memory of the run's process (MiB).
    pub peak_mib: f64,
    /// Seconds per command name, summed over its calls (the `.mess` "End of command" lines).
    pub stages: BTreeMap<String, f64>,
    /// The largest number of unknowns a solve reported.
    pub unknowns: Option<u64>,
    /// Newton iterations summed over the steps of every nonlinear solve.
    pub newton: Option<u64>,
    /// POST_ERREUR's ERREUR RELATIVE per call, keyed by OPTION (OPTION#2, ... for later calls).
    pub errors: BTreeMap<String, f64>,
    /// The largest relative error of the ANALYTIQUE / SOURCE_EXTERNE check lines (absolute where the
    /// reference is zero), and how many such lines there were.
    pub check_max: Option<f64>,
    /// The same per legend of the check lines (`check:W`, `check:SIXX`, ...).
    pub check_by_legend: BTreeMap<String, f64>,
    pub checks: usize,
    pub nook: usize,
    /// The located error of a run that stopped.
    pub error: Option<String>,
}

/// Run `cmd` to its end (or kill it after `limit`), with its wall time and peak memory.
pub fn run_child(mut cmd: Command, limit: Option<Duration>) -> std::io::Result<(Option<i32>, f64, f64)> {
    let start = Instant::now();
    let child = cmd.spawn()?;
    let pid = child.id() as libc::pid_t;
    let mut status: libc::c_int = 0;
    // SAFETY: rusage is plain data; wait4 fills it for our own child, which std never reaps (we do not
    // call Child::wait), so the pid cannot have been reused while we wait on it.
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    let mut killed = false;
    loop {
        let flags = if killed { 0 } else { libc::WNOHANG };
        let r = unsafe { libc::wait4(pid, &mut status, flags, &mut ru) };
        if r == pid {
            break;
        }
        if r < 0 {
            return Err(std::io::Error::last_os_error());
        }
        if limit.is_some_and(|l| start.elapsed() > l) {
            // SAFETY: the child has not been reaped (wait4 returned 0), so the pid is still ours.
            unsafe { libc::kill(pid, libc::SIGKILL) };
            killed = true;
            continue;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let wall = start.elapsed().as_secs_f64();
    // ru_maxrss is in KiB on Linux.
    let peak = ru.ru_maxrss as f64 / 1024.0;
    let code = if !killed && libc::WIFEXITED(status) { Some(libc::WEXITSTATUS(status)) } else { None };
    Ok((code, wall, peak))
}

/// Read the metrics of a message file.
pub fn read_mess(path: &Path, m: &mut Metrics) {
    let Ok(text) = std::fs::read_to_string(path) else { return };
    parse_mess(&text, m);
}

pub fn parse_mess(text: &str, m: &mut Metrics) {
    let mut in_steps = false;
    for line in text.lines() {
        let t = line.trim();
        let w: Vec<&str> = t.split_whitespace().collect();
        if let Some(rest) = t.strip_prefix("# End of command #") {
            // "# End of command #0012 NAME  elapsed 0.123 s"
            let w: Vec<&str> = rest.split_whitespace().collect();
            if let (Some(name), Some(s)) = (w.get(1), w.iter().position(|x| *x == "elapsed")) {
                if let Some(v) = w.get(s + 1).and_then(|v| v.parse::<f64>().ok()) {
                    *m.stages.entry(name.to_string()).or_default() += v;
                }
            }
            in_steps = false;
            continue;
        }
        if w.first() == Some(&"step") && w.get(2) == Some(&"iters") {
            in_steps = true;
            continue;
        }
        if in_steps {
            if let (Some(Ok(_)), Some(Ok(it))) =
                (w.first().map(|v| v.parse::<u64>()), w.get(2).map(|v| v.parse::<u64>()))
            {
                *m.newton.get_or_insert(0) += it;
                continue;
            }
            if t.starts_with("time") {
                in_steps = false;
            }
        }
        // "linear statics (3D): 1234 unknowns, ..." and "unknowns  : 1234 (...)".
        // (The solver line "... AMD below 50000 unknowns, ..." is not a count.)
        let unknowns = t
            .split_once(" unknowns,")
            .filter(|(a, _)| !a.starts_with("solver"))
            .and_then(|(a, _)| a.rsplit(' ').next())
            .or_else(|| t.strip_prefix("unknowns").and_then(|r| r.trim_start().strip_prefix(':')))
            .and_then(|r| r.split_whitespace().next())
            .and_then(|v| v.parse::<u64>().ok());
        if let Some(n) = unknowns {
            m.unknowns = Some(m.unknowns.unwrap_or(0).max(n));
        }
        if let Some(rest) = t.strip_prefix("POST_ERREUR OPTION=") {
            let option = rest.split_whitespace().next().unwrap_or("?").to_string();
            if let Some(v) = rest.split("ERREUR RELATIVE = ").nth(1).and_then(|r| r.split_whitespace().next()) {
                if let Ok(v) = v.parse::<f64>() {
                    let mut key = option.clone();
                    let mut k = 2;
                    while m.errors.contains_key(&key) {
                        key = format!("{option}#{k}");
                        k += 1;
                    }
                    m.errors.insert(key, v);
                }
            }
        }
        // "OK  ANALYTIQUE  LEGEND  VALE_REFE  VALE_CALC  ERREUR  TOLE"
        if w.len() >= 6 && matches!(w[0], "OK" | "NOOK") && matches!(w[1], "ANALYTIQUE" | "SOURCE_EXTERNE") {
            let n = w.len();
            if let (Ok(refe), Ok(calc)) = (w[n - 4].parse::<f64>(), w[n - 3].parse::<f64>()) {
                let e = if refe != 0.0 { ((calc - refe) / refe).abs() } else { (calc - refe).abs() };
                m.check_max = Some(m.check_max.unwrap_or(0.0).max(e));
                let legend = format!("check:{}", w[2..n - 4].join(" "));
                let slot = m.check_by_legend.entry(legend).or_insert(0.0);
                *slot = slot.max(e);
                m.checks += 1;
                if w[0] == "NOOK" {
                    m.nook += 1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_message_file() {
        let mess = "  # End of command #0002 LIRE_MAILLAGE  elapsed 0.011 s\n\
            \x20 linear statics (3D): 1234 unknowns, 12 eliminated by kinematic conditions, 1222 solved\n\
            \x20   solver    : SOLVEUR METHODE='MUMPS': sparse direct, AMD below 50000 unknowns, METIS above\n\
            \x20 # End of command #0003 MECA_STATIQUE  elapsed 0.500 s\n\
            \x20   unknowns  : 368 (192 standard, 122 Heaviside, 54 interface), 315 solved\n\
            \x20 step            INST  iters  RESI_GLOB_RELA  RESI_GLOB_MAXI\n\
            \x20    1    5.000000E-01      3    1.000000E-12    1.000000E-08\n\
            \x20       FISS1: lambda_n in [0, 1], dissipated 0\n\
            \x20    2    1.000000E+00      4    1.000000E-12    1.000000E-08\n\
            \x20   time      : elements 0.1 s\n\
            \x20 # End of command #0004 STAT_NON_LINE  elapsed 0.250 s\n\
            \x20 POST_ERREUR OPTION=DEPL_RELA GROUP_MA=SURF: ERREUR RELATIVE = 1.5e-3 (DIFFERENCE 1, REFERENCE 2)\n\
            \x20 POST_ERREUR OPTION=DEPL_RELA GROUP_MA=SURF: ERREUR RELATIVE = 2.5e-3 (DIFFERENCE 1, REFERENCE 2)\n\
            \x20 OK  ANALYTIQUE       DX               -0.25                 -0.2500000000000008   3.1E-13%    1.0E-11%\n\
            \x20 NOOK  SOURCE_EXTERNE   XXXX           2.0                   2.002   0.1%    0.01%\n\
            \x20 OK  NON_REGRESSION   DX               5.0                   6.0   1%    1%\n\
            \x20 OK  ANALYTIQUE       DY               0.0                   1.0e-9   1.0E-9    1.0E-6\n";
        let mut m = Metrics::default();
        parse_mess(mess, &mut m);
        assert_eq!(m.stages["MECA_STATIQUE"], 0.5);
        assert_eq!(m.unknowns, Some(1234));
        assert_eq!(m.newton, Some(7));
        assert_eq!(m.errors["DEPL_RELA"], 1.5e-3);
        assert_eq!(m.errors["DEPL_RELA#2"], 2.5e-3);
        assert_eq!(m.checks, 3);
        assert_eq!(m.nook, 1);
        assert!((m.check_max.unwrap() - 1e-3).abs() < 1e-12);
        assert!((m.check_by_legend["check:XXXX"] - 1e-3).abs() < 1e-12);
        assert_eq!(m.check_by_legend["check:DY"], 1e-9);
    }
}
