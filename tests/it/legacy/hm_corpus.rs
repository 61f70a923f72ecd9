//! The saturated-HM cases of Code_Aster's 2025 corpus that run with every check OK, read unmodified in
//! place (`../shared/corpus/astest-2025`; skipped with a message where absent): KIT_HM with ELAS,
//! LIQU_SATU and HYDR_UTIL, beyond rung d of ../shared/astest. wtnv113a, wtnv114a and wtnv114h read their
//! mesh in Code_Aster's text format (LIRE_MAILLAGE FORMAT='ASTER'). With X-FEM interfaces and coupled
//! flow in the enriched elements: wtnv114i (3D_HM, FLUX_THM_REP on faces the interface crosses), wtnv144b
//! (Terzaghi across an interface that cuts the loaded top, a pressure function jumping there) and wtnv144d
//! (its 3D_HM version); wtnv143d (3D_HM on PENTA15 parents). Each with its number of OK lines.

use crate::common::*;

const CASES: [(&str, usize); 9] = [
    ("wtnv113a", 24),
    ("wtnv113c", 24),
    ("wtnv114a", 20),
    ("wtnv114h", 8),
    ("wtna113a", 4),
    ("wtnv114i", 8),
    ("wtnv144b", 166),
    ("wtnv144d", 66),
    ("wtnv143d", 16),
];

#[test]
fn corpus_hm_cases_pass() {
    run_corpus_cases(&scratch!("corpus"), &CASES);
}
