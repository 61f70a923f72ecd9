//! Helpers shared by the X-FEM integration tests: the legacy suite's files
//! read in place, and FISS1/FISS2 of WTNV149 built from level-set closures.
#![allow(dead_code)]

use aster::mesh::Mesh;
use aster::xfem::{build_interface, Crack};
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
) -> (Rc<Crack>, Rc<Crack>) {
    let l1 = mesh.coords.iter().map(&f1).collect();
    let c1 = Rc::new(build_interface("MA".into(), mesh.clone(), l1, None, &[], None).unwrap());
    let l2 = mesh.coords.iter().map(&f2).collect();
    let masters = [("FISS1".to_string(), c1.clone())];
    let c2 = Rc::new(build_interface("MA".into(), mesh.clone(), l2, None, &masters, Some(point)).unwrap());
    (c1, c2)
}
