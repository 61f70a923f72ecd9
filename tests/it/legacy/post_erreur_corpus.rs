//! The Code_Aster 2025 test cases that call POST_ERREUR and fall within our physics, run unmodified from
//! the corpus (`../shared/corpus/astest-2025`, read in place; skipped with a message where absent):
//! X-FEM interfaces with junctions solved by MECA_STATIQUE, then the energy norm (zero reference: no
//! relative error) and the displacement L2 norm against the piecewise rigid field. Every check must be
//! OK, with the number of OK lines each case prints today.

use crate::common::*;
use aster::runner::{self, RunOptions};

const CASES: [(&str, usize); 5] =
    [("ssnv511a", 34), ("ssnv511b", 33), ("ssnv511c", 52), ("ssnv511d", 48), ("ssnv512e", 33)];

#[test]
fn corpus_cases_with_post_erreur_pass() {
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
