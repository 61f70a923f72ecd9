//! The integration tests: one crate (one link of hdf5 and faer), one module per domain. tests/README.md maps
//! every command and every legacy case to the tests that exercise it.

#[macro_use]
mod common;

mod fem;
mod fields;
mod heat;
mod hm;
mod language;
mod legacy;
mod med;
mod study;
mod tidy;
mod xfem;
