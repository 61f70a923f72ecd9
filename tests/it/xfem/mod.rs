//! The X-FEM library and stages on the real meshes: level sets and enrichment, TOPOSE cutting (quadratic
//! and linear parents), mortar packets, the cohesive law, and interfaces near or through nodes.
mod cohesive;
mod hard_cases;
mod levelsets;
mod mortar;
mod topose;
mod topose_linear;
