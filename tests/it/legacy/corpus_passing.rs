//! The exports of Code_Aster's 2025 corpus that pass end to end, pinned: every case of
//! tests/corpus_passing.txt runs unmodified in place (../shared/corpus/astest-2025) within its .export's
//! time limit, on two threads, and must end OK with at least its recorded number of OK check lines.
//! Skips with a message where the corpus is absent. The whole folder runs with scripts/corpus_suite.sh.

use crate::common::*;
use aster::runner::{self, Case, RunOptions};
use std::sync::{Arc, Mutex};

/// tests/corpus_passing.txt: (case, number of OK check lines).
fn pinned() -> Vec<(String, usize)> {
    let text = std::fs::read_to_string(root().join("tests/corpus_passing.txt")).unwrap();
    let mut seen = std::collections::HashSet::new();
    text.lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let ok = w.get(1).and_then(|n| n.parse().ok());
            let ok = ok.unwrap_or_else(|| panic!("tests/corpus_passing.txt: '{l}' should be a case and its OK lines"));
            assert!(seen.insert(w[0].to_string()), "tests/corpus_passing.txt names {} twice", w[0]);
            (w[0].to_string(), ok)
        })
        .collect()
}

#[test]
fn the_pinned_corpus_exports_pass() {
    let cases = pinned();
    assert!(cases.len() >= 52, "tests/corpus_passing.txt only grows ({} cases)", cases.len());
    let dir = root().join("../shared/corpus/astest-2025");
    if !dir.is_dir() {
        println!("SKIP: {} is absent", dir.display());
        return;
    }
    let out = scratch!("corpus");
    let queue = Arc::new(Mutex::new(cases.clone()));
    let failures = Arc::new(Mutex::new(Vec::new()));
    let workers: Vec<_> = (0..2)
        .map(|_| {
            let (queue, failures, dir, out) = (queue.clone(), failures.clone(), dir.clone(), out.clone());
            std::thread::spawn(move || loop {
                let Some((case, want)) = queue.lock().unwrap().pop() else { break };
                let export = dir.join(format!("{case}.export"));
                let opts = RunOptions { out_dir: Some(out.join(&case)), units: vec![], echo: false };
                let o = runner::run(Case::Export(&export), &opts, None);
                println!("{case:<10} {:<16} {:>4} OK {:>7.2} s", o.diagnostic, o.ok_count(), o.seconds);
                if o.diagnostic != "OK" || o.ok_count() < want {
                    let e = o.error.clone().unwrap_or_default();
                    failures.lock().unwrap().push(format!(
                        "{case}: {} with {} OK lines (pinned {want}) {e}",
                        o.diagnostic,
                        o.ok_count()
                    ));
                }
            })
        })
        .collect();
    for w in workers {
        w.join().unwrap();
    }
    let failures = failures.lock().unwrap();
    assert!(
        failures.is_empty(),
        "{} of {} pinned corpus exports regress:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    let _ = std::fs::remove_dir_all(&out);
}
