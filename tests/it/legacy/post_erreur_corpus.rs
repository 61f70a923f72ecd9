//! The Code_Aster 2025 test cases that call POST_ERREUR and fall within our physics, run unmodified from
//! the corpus (`../shared/corpus/astest-2025`, read in place; skipped with a message where absent):
//! X-FEM interfaces with junctions solved by MECA_STATIQUE, then the energy norm (zero reference: no
//! relative error) and the displacement L2 norm against the piecewise rigid field. Every check must be
//! OK, with the number of OK lines each case prints today.

use crate::common::*;

const CASES: [(&str, usize); 5] =
    [("ssnv511a", 34), ("ssnv511b", 33), ("ssnv511c", 52), ("ssnv511d", 48), ("ssnv512e", 33)];

#[test]
fn corpus_cases_with_post_erreur_pass() {
    run_corpus_cases(&scratch!("corpus"), &CASES);
}
