//! Real command files end to end: the legacy suite of ../shared/astest (catalogue check of every file, the
//! conformance run against tests/passing.txt), the 2025 corpus exports that pass (tests/corpus_passing.txt)
//! and the cases that call POST_ERREUR, rung (b) variants, WTNV149, our own scenes of comm/ and `aster
//! suite`'s summary.
mod astest;
mod corpus_passing;
mod hm_corpus;
mod post_erreur_corpus;
mod rung_b;
mod scenes;
mod suite_summary;
mod wtnv149;
