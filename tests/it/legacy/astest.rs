//! The legacy suite in ../shared/astest: every command file passes `aster
//! check`, and the conformance run prints a table per test and fails when a
//! test on the list of passing tests (tests/passing.txt) regresses.
//! Both skip with a message where ../shared is absent.

use crate::common::*;
use aster::runner::{self, RunOptions};
use std::path::{Path, PathBuf};

fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().map(|x| x == ext).unwrap_or(false))
        .collect();
    v.sort();
    v
}

#[test]
fn every_command_file_passes_the_catalogue() {
    let Some(dir) = astest_dir() else { return };
    let comms = files(&dir, "comm");
    assert_eq!(comms.len(), 34, "the suite holds 34 command files");
    let mut failures = Vec::new();
    for f in &comms {
        match runner::check_file(f) {
            Ok(n) => {
                assert!(n > 0, "{}: no command call checked", f.display());
                println!("{:<16} OK  {n} command calls", f.file_name().unwrap().to_string_lossy());
            }
            Err((msg, _)) => failures.push(msg),
        }
    }
    assert!(failures.is_empty(), "aster check failed:\n{}", failures.join("\n"));
}

/// tests/passing.txt: (case, number of OK check lines).
fn passing_list() -> Vec<(String, usize)> {
    let text = std::fs::read_to_string(root().join("tests/passing.txt")).unwrap();
    text.lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let mut w = l.split_whitespace();
            let name = w.next().unwrap().to_string();
            let ok = w.next().and_then(|n| n.parse().ok());
            let ok =
                ok.unwrap_or_else(|| panic!("tests/passing.txt: '{l}' should be a case and its number of OK lines"));
            (name, ok)
        })
        .collect()
}

/// The regressions of a run of the suite against the passing list: a case on the list whose diagnostic
/// is not OK, or which prints fewer OK lines than recorded. Each outcome is (case, diagnostic, OK lines,
/// error).
fn regressions(passing: &[(String, usize)], outcomes: &[(String, String, usize, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (name, want) in passing {
        match outcomes.iter().find(|o| &o.0 == name) {
            None => out.push(format!("{name}: tests/passing.txt names it, but the suite has no such case")),
            Some((_, diag, ok, err)) if diag != "OK" => out.push(format!("{name}: {diag} ({ok} OK) {err}")),
            Some((_, _, ok, _)) if ok < want => {
                out.push(format!("{name}: {ok} OK lines, tests/passing.txt records {want}"))
            }
            Some(_) => {}
        }
    }
    out
}

#[test]
fn a_dropped_check_is_a_regression() {
    let passing = vec![("a".to_string(), 12), ("b".to_string(), 3)];
    let run = |a_ok: usize, b_diag: &str| {
        vec![
            ("a".to_string(), "OK".to_string(), a_ok, String::new()),
            ("b".to_string(), b_diag.to_string(), 3, String::new()),
        ]
    };
    assert!(regressions(&passing, &run(12, "OK")).is_empty());
    assert!(regressions(&passing, &run(13, "OK")).is_empty(), "more OK lines than recorded is progress");
    assert_eq!(regressions(&passing, &run(11, "OK")), vec!["a: 11 OK lines, tests/passing.txt records 12"]);
    assert_eq!(regressions(&passing, &run(12, "NOOK_TEST_RESU")).len(), 1);
    assert_eq!(regressions(&passing, &run(12, "OK")[..1]).len(), 1, "a case missing from the suite");
}

#[test]
fn conformance() {
    let Some(dir) = astest_dir() else { return };
    let passing = passing_list();
    let out = scratch!("conformance");
    let opts = RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false };
    let mut outcomes = Vec::new();
    for export in files(&dir, "export") {
        let o = runner::run_export(&export, &opts);
        println!(
            "\n== {}  DIAGNOSTIC {}  ({} OK, {} NOOK, {} skipped, {:.2} s)",
            o.name,
            o.diagnostic,
            o.ok_count(),
            o.nook_count(),
            o.skip_count(),
            o.seconds
        );
        for r in &o.records {
            let v = match r.ok {
                Some(true) => "OK",
                Some(false) => "NOOK",
                None => "SKIP",
            };
            println!("   {v:<5} {:<14} line {:<5} {:<16} {}", r.command, r.line, r.reference, r.legend);
        }
        if let Some(e) = &o.error {
            println!("   error {e}");
        }
        outcomes.push((o.name.clone(), o.diagnostic.to_string(), o.ok_count(), o.error.clone().unwrap_or_default()));
    }
    let _ = std::fs::remove_dir_all(&out);
    println!();
    for (name, diag, ok, _) in &outcomes {
        let listed = passing.iter().find(|p| &p.0 == name).map(|p| p.1);
        let note = match listed {
            Some(want) if *ok > want => format!("  (tests/passing.txt records {want}: raise it)"),
            None if diag == "OK" => "  (not on tests/passing.txt: add it)".to_string(),
            _ => String::new(),
        };
        println!("{name:<10} {diag:<16} {ok:>4} OK{note}");
    }
    let regressions = regressions(&passing, &outcomes);
    assert!(regressions.is_empty(), "tests on the passing list regressed:\n{}", regressions.join("\n"));
}
