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

#[test]
fn conformance() {
    let Some(dir) = astest_dir() else { return };
    let passing_list = std::fs::read_to_string(root().join("tests/passing.txt")).unwrap();
    let passing: Vec<&str> =
        passing_list.lines().map(|l| l.split('#').next().unwrap().trim()).filter(|l| !l.is_empty()).collect();
    let out = scratch!("conformance");
    let opts = RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false };
    let mut regressions = Vec::new();
    let mut summary = Vec::new();
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
        summary.push(format!("{:<10} {}", o.name, o.diagnostic));
        if passing.contains(&o.name.as_str()) && o.diagnostic != "OK" {
            regressions.push(format!("{}: {} {}", o.name, o.diagnostic, o.error.clone().unwrap_or_default()));
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    println!("\n{}", summary.join("\n"));
    for p in &passing {
        assert!(
            summary.iter().any(|s| s.split_whitespace().next() == Some(p)),
            "tests/passing.txt names {p}, which is not in the suite"
        );
    }
    assert!(regressions.is_empty(), "tests on the passing list regressed:\n{}", regressions.join("\n"));
}
