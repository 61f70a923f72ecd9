//! The command definitions, one file per family.

use super::schema::Command;

mod common;
mod control;
mod fields;
mod functions;
mod loads;
mod material;
mod mesh;
mod model;
mod post;
mod print;
mod solve;
mod tables;
mod tests;
mod xfem;

pub fn all() -> Vec<Command> {
    let mut v = Vec::new();
    v.extend(control::commands());
    v.extend(functions::commands());
    v.extend(tables::commands());
    v.extend(tests::commands());
    v.extend(mesh::commands());
    v.extend(model::commands());
    v.extend(material::commands());
    v.extend(loads::commands());
    v.extend(xfem::commands());
    v.extend(solve::commands());
    v.extend(fields::commands());
    v.extend(post::commands());
    v.extend(print::commands());
    v
}
