//! The command-file language: the Python subset against CPython's behaviour, located errors on bad input,
//! and the bounded parser fuzzer.
mod bad_input;
mod fuzz_parser;
mod fuzz_pipeline;
mod python_subset;
mod robustness;
