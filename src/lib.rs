//! aster-rs: an interpreter for Code_Aster command files.
//!
//! See `docs/ARCHITECTURE.md` for the bird's-eye view.

pub mod catalog;
pub mod concepts;
pub mod diag;
pub mod fem;
pub mod hm;
pub mod interp;
pub mod med;
pub mod mesh;
pub mod runner;
pub mod solve;
pub mod stages;
pub mod study;
pub mod syntax;
pub mod text;
pub mod thermal;
pub mod xfem;
