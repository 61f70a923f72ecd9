//! The command-file language: the Python subset against CPython's behaviour, located errors on bad input,
//! the bounded parser fuzzer, and the control commands of a run (POURSUITE, DETRUIRE, DEFI_FICHIER).
mod bad_input;
mod control;
mod fuzz_parser;
mod fuzz_pipeline;
mod python_subset;
mod robustness;
