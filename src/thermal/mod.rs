//! Heat conduction as Code_Aster's thermal elements compute it (`PHENOMENE='THERMIQUE'`, modelisations
//! `PLAN`, `AXIS`, `3D` and their lumped `_DIAG` variants), on linear and quadratic cells.
//!
//! - [`element`]: the modelisations, their integration families (Code_Aster's `ther_*.py` element
//!   catalogues), the geometry of the integration points, the conduction matrix (`RIGI_THER`), the
//!   capacity matrix (`MASS_THER`, lumped at the vertices for `_DIAG`), the nonlinear conduction and
//!   enthalpy terms of `THER_NON_LINE` with their tangents (`RAPH_THER`, `RIGI_THER_TANG`,
//!   `MASS_THER_RESI`, `MASS_THER_TANG`), volume sources, the heat flux at the integration points
//!   (`FLUX_ELGA`) and its extrapolation to the nodes (`FLUX_ELNO`).
//! - [`boundary`]: the skin elements' loads — a heat flux density given as a function of the point, its
//!   normal and the temperature there (normal flux, flux vector, exchange, radiation, nonlinear flux) with
//!   its tangent — and the exchange between two walls (`ECHANGE_PAROI`).
//! - [`physics`]: heat conduction as the solving core's `Physics`: the temperatures, the θ-scheme, the
//!   loads' heat (constant, or depending on the temperature), the fields of a state.
//! - [`curve`]: tabulated functions of the temperature as `THER_NL` reads them (linear interpolation,
//!   Code_Aster's prolongations) and the enthalpy integrated from a tabulated `ρCp`.
//!
//! Conventions: a cell's unknowns are its nodes' temperatures in Code_Aster's local node order;
//! matrices are row-major `n × n`; `AXIS` integrates per radian (weights × r, x = r ≥ 0); the flux is
//! `q = −Λ ∇T` (`FLUX FLUY [FLUZ]`); a boundary flux density is positive when heat enters the body.
//! Material values that depend on time or temperature reach the library as numbers, closures or
//! [`curve::Curve`]s. The library knows cells, shape functions and numbers, and the solving core's seam
//! (`fem::physics`): nothing of commands, concepts or files.

pub mod boundary;
pub mod curve;
pub mod element;
pub mod physics;

#[cfg(test)]
mod analytic_tests;

pub use curve::{Curve, Extension};
pub use element::{Conductivity, Kinematics, Modelisation, ThermalError};
