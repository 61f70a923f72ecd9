//! Real command files end to end: the legacy suite of ../shared/astest (catalogue check of every file, the
//! conformance run against tests/passing.txt), the 2025 corpus cases that call POST_ERREUR, rung (b)
//! variants, WTNV149 and our own scenes of comm/.
mod astest;
mod post_erreur_corpus;
mod rung_b;
mod scenes;
mod wtnv149;
