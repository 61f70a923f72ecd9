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
    pub error: Option<String>,
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
    }
}

impl CaseResult {
    fn error(name: String, seconds: f64, msg: String) -> CaseResult {
        CaseResult { name, diagnostic: Diagnostic::Error, ok: 0, nook: 0, skip: 0, seconds, error: Some(msg) }
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

/// Run all .export files of `dir` with `jobs` workers; results in name order.
pub fn run_suite(exe: &Path, dir: &Path, out: &Path, jobs: usize) -> std::io::Result<Vec<CaseResult>> {
    let mut exports: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().map(|x| x == "export").unwrap_or(false))
        .collect();
    exports.sort();
    std::fs::create_dir_all(out)?;
    let queue = Arc::new(Mutex::new(exports.clone()));
    let results = Arc::new(Mutex::new(Vec::new()));
    let mut handles = Vec::new();
    for _ in 0..jobs.max(1) {
        let (q, r, exe, out) = (queue.clone(), results.clone(), exe.to_path_buf(), out.to_path_buf());
        handles.push(std::thread::spawn(move || loop {
            let next = q.lock().unwrap().pop();
            let Some(e) = next else { break };
            let res = run_one(&exe, &e, &out);
            r.lock().unwrap().push(res);
        }));
    }
    for h in handles {
        let _ = h.join();
    }
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
