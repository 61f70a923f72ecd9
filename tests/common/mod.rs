//! Helpers shared by the X-FEM integration tests: the legacy suite's files
//! read in place, and FISS1/FISS2 of WTNV149 built from level-set closures.
#![allow(dead_code)]

use aster::concepts::{Concept, ConceptData, ConceptKind, ConceptRef};
use aster::mesh::Mesh;
use aster::xfem::build_interface;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// A file of `../shared/astest`, or None (with a SKIP message) when absent.
pub fn astest(file: &str) -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/astest").join(file);
    if p.exists() {
        Some(p)
    } else {
        println!("SKIP: {} is absent", p.display());
        None
    }
}

/// A mesh of `../shared/astest`, read in place.
pub fn mesh(file: &str) -> Option<Rc<Mesh>> {
    let p = astest(file)?;
    Some(Rc::new(aster::med::read_mesh(&p, None).unwrap()))
}

/// FISS1 then FISS2 with its junction on FISS1 at `point` (DEFI_FISS_XFEM of the .comm).
pub fn two_cracks(
    mesh: &Rc<Mesh>,
    f1: impl Fn(&[f64; 3]) -> f64,
    f2: impl Fn(&[f64; 3]) -> f64,
    point: &[f64],
) -> (ConceptRef, ConceptRef) {
    let mc = Concept::new(ConceptKind::Maillage, ConceptData::Mesh(mesh.clone()));
    let l1 = mesh.coords.iter().map(&f1).collect();
    let k1 = build_interface(mc.clone(), mesh.clone(), l1, None, &[], None).unwrap();
    let c1 = Concept::new(ConceptKind::FissXfem, ConceptData::Crack(k1));
    c1.set_name("FISS1");
    let l2 = mesh.coords.iter().map(&f2).collect();
    let k2 = build_interface(mc, mesh.clone(), l2, None, std::slice::from_ref(&c1), Some(point)).unwrap();
    let c2 = Concept::new(ConceptKind::FissXfem, ConceptData::Crack(k2));
    c2.set_name("FISS2");
    (c1, c2)
}
