//! Saturated hydro-mechanics: Biot poro-elasticity as Code_Aster computes it with
//! `KIT_HM` = (`ELAS`, `LIQU_SATU`, `HYDR_UTIL`) on the `*_HM`, `*_HMD`, `*_HMS` and `*_HM_SI`
//! modelisations (see `../shared/docs/hm-coupled-formulation.md` for the sources).
//!
//! - [`material`]: the parameters (`ELAS`, `THM_INIT`, `THM_DIFFU`, `THM_LIQU`), checked.
//! - [`law`]: the update of one integration point over a time step (effective and pore stresses,
//!   porosity, liquid density, fluid mass content, Darcy flux) and its exact derivatives.
//! - [`element`]: the integration points of each variant (all terms at the Gauss points; at the
//!   vertices only; mechanics and flux at the Gauss points and storage at the vertices) and the
//!   element's internal forces and tangent, displacement quadratic on all nodes and pressure linear on
//!   the vertices.
//!
//! - [`thermal`]: the thermal part of saturated THM (`KIT_THM`) at a point: thermal expansion of the
//!   skeleton and the liquid, the liquid's enthalpy, the non-convected heat, Fourier's flux.
//! - [`physics`]: the problem of a model (its cells' elements, materials and numbering) as a
//!   [`crate::fem::physics::Physics`]: its loads, its element loop and its fields.
//!
//! The library knows cells, shape functions and numbers: nothing of commands, concepts or files.

pub mod element;
pub mod law;
pub mod material;
pub mod physics;
pub mod thermal;

pub use element::{CellPoints, Kinematics, Variant};
pub use law::PointState;
pub use material::Biot;
