//! The saturated-HM cases of Code_Aster's 2025 corpus that run with every check OK, read unmodified in
//! place (`../shared/corpus/astest-2025`; skipped with a message where absent): KIT_HM with ELAS,
//! LIQU_SATU and HYDR_UTIL, beyond rung d of ../shared/astest. wtnv113a, wtnv114a and wtnv114h read their
//! mesh in Code_Aster's text format (LIRE_MAILLAGE FORMAT='ASTER'). Each with its number of OK lines.

use crate::common::*;
use aster::runner::{self, RunOptions};

const CASES: [(&str, usize); 5] =
    [("wtnv113a", 24), ("wtnv113c", 24), ("wtnv114a", 20), ("wtnv114h", 8), ("wtna113a", 4)];

#[test]
fn corpus_hm_cases_pass() {
    let dir = root().join("../shared/corpus/astest-2025");
    if !dir.is_dir() {
        println!("SKIP: {} is absent", dir.display());
        return;
    }
    let out = scratch!("corpus");
    let mut failures = Vec::new();
    for (case, ok) in CASES {
        let opts = RunOptions { out_dir: Some(out.join(case)), units: vec![], echo: false };
        let o = runner::run_export(&dir.join(format!("{case}.export")), &opts);
        println!("{case:<10} {:<16} {} OK", o.diagnostic, o.ok_count());
        if o.diagnostic != "OK" || o.ok_count() != ok {
            failures.push(format!(
                "{case}: {} with {} OK lines (want {ok}): {:?}",
                o.diagnostic,
                o.ok_count(),
                o.error
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let _ = std::fs::remove_dir_all(&out);
}
