//! `aster suite DIR`: run every .export of a folder like Code_Aster's test
//! runner — each case in its own process, with its time limit — and report one
//! row per case and a JUnit XML file.

use super::export::Export;
use super::{Diagnostic, Outcome};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// One case's result as the suite sees it.
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub name: String,
    pub diagnostic: Diagnostic,
    pub ok: usize,
    pub nook: usize,
    pub skip: usize,
    pub seconds: f64,
    /// The located error message the run stopped on.
    pub error: Option<String>,
    /// Its kind (`Unsupported`, `Catalog`, ...), command and message without location.
    pub kind: Option<String>,
    pub command: Option<String>,
    pub message: Option<String>,
    /// The command of the first NOOK check.
    pub first_nook: Option<String>,
}

/// The machine-readable summary `aster run --summary FILE` writes.
pub fn summary_text(o: &Outcome) -> String {
    let mut s = format!(
        "diagnostic={}\nok={}\nnook={}\nskip={}\nseconds={:.6}\n",
        o.diagnostic,
        o.ok_count(),
        o.nook_count(),
        o.skip_count(),
        o.seconds
    );
    if let Some(e) = &o.error {
        s.push_str(&format!("error={}\n", e.replace('\n', " ")));
    }
    if let Some(k) = o.error_kind {
        s.push_str(&format!("kind={k:?}\n"));
    }
    if let Some(c) = &o.error_command {
        s.push_str(&format!("command={c}\n"));
    }
    if let Some(m) = &o.error_message {
        s.push_str(&format!("message={}\n", m.replace('\n', " ")));
    }
    for r in &o.records {
        let v = match r.ok {
            Some(true) => "OK",
            Some(false) => "NOOK",
            None => "SKIP",
        };
        s.push_str(&format!("check={v}\t{}\t{}\t{}\t{}\n", r.command, r.line, r.reference, r.legend));
    }
    s
}

fn parse_summary(name: &str, text: &str) -> CaseResult {
    let get = |k: &str| text.lines().find_map(|l| l.strip_prefix(&format!("{k}="))).map(str::to_string);
    CaseResult {
        name: name.to_string(),
        diagnostic: get("diagnostic").and_then(|d| d.parse().ok()).unwrap_or(Diagnostic::Error),
        ok: get("ok").and_then(|v| v.parse().ok()).unwrap_or(0),
        nook: get("nook").and_then(|v| v.parse().ok()).unwrap_or(0),
        skip: get("skip").and_then(|v| v.parse().ok()).unwrap_or(0),
        seconds: get("seconds").and_then(|v| v.parse().ok()).unwrap_or(0.0),
        error: get("error"),
        kind: get("kind"),
        command: get("command"),
        message: get("message"),
        first_nook: text
            .lines()
            .filter_map(|l| l.strip_prefix("check=NOOK\t"))
            .find_map(|l| l.split('\t').next().map(str::to_string)),
    }
}

impl CaseResult {
    fn error(name: String, seconds: f64, msg: String) -> CaseResult {
        CaseResult {
            name,
            diagnostic: Diagnostic::Error,
            ok: 0,
            nook: 0,
            skip: 0,
            seconds,
            error: Some(msg.clone()),
            kind: None,
            command: None,
            message: Some(msg),
            first_nook: None,
        }
    }
}

fn run_one(exe: &Path, export: &Path, out: &Path) -> CaseResult {
    let name = export.file_stem().and_then(|s| s.to_str()).unwrap_or("?").to_string();
    // The case stops itself at its time limit with a located error (`aster run` reads the export's);
    // past a grace period the suite kills it.
    let limit = match Export::read(export).and_then(|e| e.time_limit()) {
        Ok(l) => l.map_or(600.0, |l| l.as_secs_f64()),
        Err(e) => return CaseResult::error(name, 0.0, e.msg),
    };
    let kill_after = limit + (0.1 * limit).max(2.0);
    let dir = out.join(&name);
    let _ = std::fs::create_dir_all(&dir);
    let summary = dir.join("summary.txt");
    let _ = std::fs::remove_file(&summary);
    let t0 = Instant::now();
    let child = Command::new(exe)
        .arg("run")
        .arg(export)
        .arg("--out")
        .arg(&dir)
        .arg("--summary")
        .arg(&summary)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => return CaseResult::error(name, 0.0, e.to_string()),
    };
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) if t0.elapsed().as_secs_f64() > kill_after => {
                let _ = child.kill();
                let _ = child.wait();
                return CaseResult::error(
                    name,
                    t0.elapsed().as_secs_f64(),
                    format!("time limit of {limit} s exceeded"),
                );
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return CaseResult::error(name, 0.0, e.to_string()),
        }
    }
    match std::fs::read_to_string(&summary) {
        Ok(t) => parse_summary(&name, &t),
        Err(_) => {
            CaseResult::error(name, t0.elapsed().as_secs_f64(), "the case stopped without a summary (crash)".into())
        }
    }
}

/// The .export files of `dir` in name order; with `only`, those whose case name it lists.
pub fn exports_of(dir: &Path, only: Option<&[String]>) -> std::io::Result<Vec<PathBuf>> {
    let mut exports: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().map(|x| x == "export").unwrap_or(false))
        .filter(|p| {
            only.is_none_or(|names| {
                p.file_stem().and_then(|s| s.to_str()).is_some_and(|s| names.iter().any(|n| n == s))
            })
        })
        .collect();
    exports.sort();
    Ok(exports)
}

/// The case names of a list file: the first word of each line, `#` comments and blank lines skipped
/// (the format of `tests/passing.txt`).
pub fn read_list(text: &str) -> Vec<String> {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .filter_map(|l| l.split_whitespace().next())
        .map(str::to_string)
        .collect()
}

/// Run `exports` with `jobs` workers, with a progress bar on the terminal when `progress`; results
/// in name order.
pub fn run_suite(
    exe: &Path,
    exports: &[PathBuf],
    out: &Path,
    jobs: usize,
    progress: bool,
) -> std::io::Result<Vec<CaseResult>> {
    std::fs::create_dir_all(out)?;
    // Longest names last: the workers pop from the end, in name order.
    let mut queue: Vec<PathBuf> = exports.to_vec();
    queue.reverse();
    let queue = Arc::new(Mutex::new(queue));
    let results = Arc::new(Mutex::new(Vec::new()));
    let bar = if progress {
        indicatif::ProgressBar::with_draw_target(
            Some(exports.len() as u64),
            indicatif::ProgressDrawTarget::stderr_with_hz(4),
        )
    } else {
        indicatif::ProgressBar::hidden()
    };
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} cases, {elapsed} ({eta} left) {msg}")
    {
        bar.set_style(style);
    }
    let passed = Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let mut handles = Vec::new();
    for _ in 0..jobs.max(1) {
        let (q, r, exe, out) = (queue.clone(), results.clone(), exe.to_path_buf(), out.to_path_buf());
        let (bar, passed) = (bar.clone(), passed.clone());
        handles.push(std::thread::spawn(move || loop {
            let next = q.lock().unwrap().pop();
            let Some(e) = next else { break };
            let res = run_one(&exe, &e, &out);
            if res.diagnostic == Diagnostic::Ok {
                passed.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            }
            bar.set_message(format!("{} OK, last {}", passed.load(std::sync::atomic::Ordering::Relaxed), res.name));
            bar.inc(1);
            r.lock().unwrap().push(res);
        }));
    }
    for h in handles {
        let _ = h.join();
    }
    bar.finish_and_clear();
    let mut v = Arc::try_unwrap(results).map(|m| m.into_inner().unwrap()).unwrap_or_default();
    v.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(v)
}

/// The console table.
pub fn table(results: &[CaseResult]) -> String {
    let mut s =
        format!("{:<12} {:<18} {:>5} {:>5} {:>5} {:>9}\n", "TEST", "DIAGNOSTIC", "OK", "NOOK", "SKIP", "TIME(s)");
    for r in results {
        s.push_str(&format!(
            "{:<12} {:<18} {:>5} {:>5} {:>5} {:>9.2}\n",
            r.name, r.diagnostic, r.ok, r.nook, r.skip, r.seconds
        ));
        if let Some(e) = &r.error {
            s.push_str(&format!("             {e}\n"));
        }
    }
    let ok = results.iter().filter(|r| r.diagnostic == Diagnostic::Ok).count();
    s.push_str(&format!("{} cases: {ok} OK, {} not OK\n", results.len(), results.len() - ok));
    s
}

/// The cases that passed (OK), each with its number of OK check lines, in the format of
/// tests/corpus_passing.txt.
pub fn passing_list(results: &[CaseResult]) -> String {
    let mut s = String::from("# cases that passed (DIAGNOSTIC JOB : OK) and their number of OK check lines\n");
    for r in results.iter().filter(|r| r.diagnostic == Diagnostic::Ok) {
        s.push_str(&format!("{:<10} {}\n", r.name, r.ok));
    }
    s
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A JUnit XML report: a failure for NOOK, an error for <F> diagnostics.
pub fn junit(results: &[CaseResult]) -> String {
    let failures = results.iter().filter(|r| r.diagnostic == Diagnostic::NookTestResu).count();
    let errors = results.iter().filter(|r| r.diagnostic.is_error()).count();
    let total: f64 = results.iter().map(|r| r.seconds).sum();
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"aster-suite\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" time=\"{total:.3}\">\n",
        results.len()
    );
    for r in results {
        s.push_str(&format!(
            "  <testcase classname=\"astest\" name=\"{}\" time=\"{:.3}\">",
            xml_escape(&r.name),
            r.seconds
        ));
        let msg = xml_escape(r.error.as_deref().unwrap_or(""));
        match r.diagnostic {
            Diagnostic::Ok | Diagnostic::NoTestResu => {}
            Diagnostic::NookTestResu => {
                s.push_str(&format!("<failure message=\"{}: {} NOOK\"/>", Diagnostic::NookTestResu, r.nook))
            }
            d @ (Diagnostic::Error | Diagnostic::SyntaxError) => {
                s.push_str(&format!("<error message=\"{}\">{msg}</error>", xml_escape(d.name())))
            }
        }
        s.push_str("</testcase>\n");
    }
    s.push_str("</testsuite>\n");
    s
}
