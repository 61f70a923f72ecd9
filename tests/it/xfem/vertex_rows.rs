//! Interfaces a hair's breadth from a row of mesh nodes (issue 10): the
//! scenes `comm/vertex_row_*.comm` run end to end. Each checks the analytic
//! (uncracked, linear) field at every node of the mesh and of the visual
//! mesh to 1e-8 of the displacement scale U; here every check line must be
//! OK, their number must be the scene's, and the worst node error is
//! printed.

use crate::common::*;
use aster::runner::{self, RunOptions};

/// Run `comm/<name>.export`; check the diagnostic and the number of OK
/// lines; return the worst |error| / U of the ANALYTIQUE lines (`scale` is
/// what the scene's ERR_* columns are relative to: U for absolute errors,
/// 1 for errors already divided by U).
fn run_scene(name: &str, ok_lines: usize, scale: f64) -> f64 {
    let out = scratch!(name);
    let opts = RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false };
    let o = runner::run_export(&root().join("comm").join(format!("{name}.export")), &opts);
    let resu = std::fs::read_to_string(out.join(format!("{name}.resu"))).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&out);
    assert_eq!(o.diagnostic, "OK", "{name}: {:?}", o.error);
    assert_eq!(o.nook_count(), 0, "{name}");
    assert_eq!(o.ok_count(), ok_lines, "{name}: OK lines");
    let errors = analytic_errors(&resu);
    assert_eq!(errors.len(), ok_lines / 2, "{name}: every ANALYTIQUE line has its NON_REGRESSION twin");
    let worst = errors.iter().fold(0.0f64, |m, e| m.max(e.abs() / scale));
    println!("{name}: {} OK lines, worst node error {worst:.2e} U", o.ok_count());
    assert!(worst <= 1e-8, "{name}: {worst:e}");
    worst
}

/// QUAD8 cells of size 2, FISS1 at 1e-4·h from a row of vertices and
/// mid-side nodes, FISS2 branching on it: 2 results × 2 components × max
/// and min, each with an ANALYTIQUE and a NON_REGRESSION line.
#[test]
fn quad8_at_1e_4_from_a_vertex_row() {
    run_scene("vertex_row_2d", 16, 1.0e-4);
}

/// HEXA20 cells of size 2, FISS1 at 1e-3·h and 1e-4·h from a row of vertices
/// and mid-side nodes: 2 distances × 2 results × 3 components × max and min
/// × 2 lines.
#[test]
fn hexa20_at_1e_3_and_1e_4_from_a_vertex_row() {
    run_scene("vertex_row_3d", 48, 1.0);
}

/// HEXA20 cells of size 2, FISS1 at 1e-8·h and 1e-10·h from a row of
/// vertices and mid-side nodes, and exactly through it: TOPOSE's degenerate
/// 3D cuttings (sub-tetrahedra cut through their vertices): 3 distances × 2
/// results × 3 components × max and min × 2 lines.
#[test]
fn hexa20_through_and_next_to_a_vertex_row() {
    run_scene("vertex_row_3d_degenerate", 72, 1.0);
}

/// QUAD8 cells of size 2, FISS1 along the row of nodes Y = 4 (vertices and
/// mid-side nodes), at 1e-9·h from it and exactly on it, FISS2 branching on
/// it: no cell is cut, the cells below the row carry the facets (one packet
/// per vertex of the row). 2 distances × 2 results × 2 components × max and
/// min × 2 lines.
#[test]
fn quad8_along_a_row_of_nodes() {
    run_scene("vertex_row_2d_through", 32, 1.0e-4);
}

/// HEXA20 cells of size 2, FISS1 along the plane of nodes Z = 4, at 1e-9·h
/// from it and exactly on it, FISS2 branching on it: 2 distances × 2 results
/// × 3 components × max and min × 2 lines.
#[test]
fn hexa20_along_a_plane_of_nodes() {
    run_scene("vertex_row_3d_through", 48, 1.0);
}
