//! Terzaghi's consolidation over h, Δt and θ (comm/terzaghi_study.comm, docs/accuracy-vs-time.md §4): the
//! scene passes every check at its default knobs, and `aster study` measures the orders theory gives —
//! 2 in h for the linear pressure, 1 in Δt for implicit Euler, 2 for Crank–Nicolson once its start is
//! damped (Rannacher), while the undamped start leaves the pressure near the drained top oscillating.

use crate::common::*;
use aster::runner::{self, RunOptions};
use std::collections::BTreeMap;

#[test]
fn the_scene_passes_every_check_at_its_default_knobs() {
    let out = scratch!("default");
    let o = runner::run_export(
        &root().join("comm/terzaghi_study.export"),
        &RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false },
    );
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    // 12 pressures, 3 settlements and the L2 error, each against the series and our own value.
    assert_eq!((o.ok_count(), o.nook_count()), (32, 0), "{mess}");
    let analytic = mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count();
    assert_eq!(analytic, 16, "{mess}");
    assert!(mess.contains("ANALYTIQUE       ERR_L2"), "{mess}");
}

/// ERR_L2 of every variant of a study of the scene, keyed by "N NSTEP THETA START".
fn study(tag: &str, knobs: &[&str]) -> BTreeMap<String, f64> {
    study_err_l2(
        &scratch!(tag),
        "terzaghi_study.export",
        "20=box --cell QUAD8 --n 1,{N} --size 1,10",
        knobs,
        &["N", "NSTEP", "THETA", "START"],
    )
}

#[test]
fn the_pressure_converges_at_order_two_in_h() {
    // Crank–Nicolson with a damped start and small steps: the error is the space error.
    let e = study("space", &["N=8,16", "NSTEP=160", "THETA=0.5", "START=2"]);
    let order = (e["8 160 0.5 2"] / e["16 160 0.5 2"]).log2();
    assert!((order - 2.0).abs() < 0.3, "order {order} in h: {e:?}");
}

#[test]
fn implicit_euler_converges_at_order_one_in_time() {
    let e = study("euler", &["N=16", "NSTEP=20,40", "THETA=1.0", "START=0"]);
    let order = (e["16 20 1.0 0"] / e["16 40 1.0 0"]).log2();
    assert!((order - 1.0).abs() < 0.3, "order {order} in Δt: {e:?}");
}

#[test]
fn crank_nicolson_converges_at_order_two_once_its_start_is_damped() {
    let e = study("cn", &["N=128", "NSTEP=40,80", "THETA=0.5", "START=0,2"]);
    let order = (e["128 40 0.5 2"] / e["128 80 0.5 2"]).log2();
    assert!((order - 2.0).abs() < 0.3, "order {order} in Δt: {e:?}");
    // Without the implicit start the modes the sudden load excites flip sign at every step instead of
    // decaying: the error is orders of magnitude larger at the same cost.
    for n in ["40", "80"] {
        let (plain, damped) = (e[&format!("128 {n} 0.5 0")], e[&format!("128 {n} 0.5 2")]);
        assert!(plain > 100.0 * damped, "NSTEP={n}: {plain} against {damped}");
    }
}
