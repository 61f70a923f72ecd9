//! The X-FEM library and stages on the real meshes: level sets and enrichment, TOPOSE cutting (quadratic
//! and linear parents, quadratic boundary cells), mortar packets, the cohesive law, interfaces near or through nodes, curved interfaces (random circles and spheres), POST_ERREUR
//! on a cut cell, and the coupled flow through a fluid-filled cohesive interface.
mod cohesive;
mod curved;
mod distorted;
mod fluid_interface;
mod hard_cases;
mod levelsets;
mod mortar;
mod pore_pressure;
mod post_erreur;
mod property;
mod restart;
mod topose;
mod topose_boundary;
mod topose_linear;
mod vertex_rows;
