//! Finite-element building blocks: reference elements (node coordinates,
//! shape functions, isoparametric maps) and quadrature rules, in
//! Code_Aster's conventions (local node order, reference domains, Gauss
//! point families and their numbering).

pub mod assembly;
pub mod dofs;
pub mod elastic;
pub mod elasticity;
pub mod field;
pub mod frame;
pub mod geometry;
pub mod locate;
pub mod physics;
pub mod plastic;
pub mod plasticity;
pub mod postpro;
pub mod quadrature;
pub mod reference;

pub use quadrature::{
    aster_families, aster_rule, default_family, family_rule, gauss_legendre, rule_for_degree, Family, QuadratureRule,
    RefDomain,
};
pub use reference::{
    inverse_map, is_inside, jacobian, jacobian_det, map_to_real, node_coords, outside_distance, ref_centroid,
    ref_measure, shape, shape_and_deriv, shape_deriv, InverseMapError, InverseMapOptions, InverseMapResult,
};
