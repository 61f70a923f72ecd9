//! Coupled flow through a fluid-filled cohesive interface (issue 14, wtnv147a's set-up): the scenes
//! `comm/fluid_interface_2d.comm` and `_3d` hold the skeleton and the cohesive multipliers, prescribes the fracture
//! pressure p_f on the interface and PRE1 = 0 on the bottom and top edges, and solves the bulk pressures
//! and the exchange fluxes q± (LAG_FLI, LAG_FLS). Nothing is stored (incompressible liquid, Biot
//! coefficient 1), so each step is the steady state: a linear pressure on each side and the fluxes
//! ρ K/μ p_f / L±, which the Heaviside-enriched linear pressure and the packet multipliers hold exactly.
//! The scene checks them at every node of the visual mesh (1e-10); here every check line must be OK, the
//! worst error must be below 1e-8 relative, and the run log must say what was solved and what
//! eliminated. A free p_f (the fracture mass balance) stops the run by name.

use crate::common::*;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};

/// The worst |ERR_*| of the ANALYTIQUE lines of a .resu text, and their number.
fn worst_error(resu: &str) -> (f64, usize) {
    let errs = analytic_errors(resu);
    (errs.iter().fold(0.0f64, |m, e| m.max(e.abs())), errs.len())
}

/// Run a scene: every check OK, the worst error below 1e-8, the log's account of the flow.
fn steady_exchange(name: &str) {
    let out = scratch!(name);
    let opts = RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false };
    let o = runner::run_export(&root().join("comm").join(format!("{name}.export")), &opts);
    let resu = std::fs::read_to_string(out.join(format!("{name}.resu"))).unwrap_or_default();
    let mess = std::fs::read_to_string(out.join(format!("{name}.mess"))).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&out);
    assert_eq!(o.diagnostic, "OK", "{name}: {:?}", o.error);
    assert_eq!(o.nook_count(), 0);
    // 2 instants × (PRE1, LAG_FLI, LAG_FLS) × max and min × (ANALYTIQUE, NON_REGRESSION).
    assert_eq!(o.ok_count(), 24);
    let (worst, n) = worst_error(&resu);
    assert_eq!(n, 12, "every ANALYTIQUE line is read");
    println!("{name}: worst relative error {worst:.2e}");
    assert!(worst <= 1e-8, "{worst:e}");
    assert!(mess.contains("solved: coupled flow"), "the log says the flow is solved");
    assert!(mess.contains("p_f (PRE_FLU) prescribed on all"), "the log says why the fracture balance is eliminated");
}

#[test]
fn steady_exchange_2d_is_exact() {
    steady_exchange("fluid_interface_2d");
}

#[test]
fn steady_exchange_3d_is_exact() {
    steady_exchange("fluid_interface_3d");
}

#[test]
fn a_free_fracture_pressure_stops_by_name() {
    let base = std::fs::read_to_string(root().join("comm/fluid_interface_2d.comm")).unwrap();
    let comm_text = base.replace("LAGS_F1=0.0, PRE_FLU=PF", "LAGS_F1=0.0");
    assert_ne!(comm_text, base, "the scene prescribes PRE_FLU");
    let dir = scratch!("fluid_interface_free_pf");
    let comm = dir.join("free_pf.comm");
    std::fs::write(&comm, comm_text).unwrap();
    let mesh = root().join("med/junction_quad8.med");
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh, Dir::In)], echo: false };
    let o = runner::run_comm(&comm, &opts);
    let _ = std::fs::remove_dir_all(&dir);
    let err = o.error.unwrap_or_default();
    assert!(err.contains("PRE_FLU of FISS on packet") && err.contains("cubic law"), "{err}");
    assert!(err.contains("STAT_NON_LINE"), "located: {err}");
}
