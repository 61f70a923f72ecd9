//! Heat scenes with analytic answers (docs/accuracy-vs-time.md §5): each passes its checks at its default
//! knobs, and `aster study` measures the orders theory gives — the half-space heated by a ramp converges at
//! order 1 in Δt with implicit Euler and 2 with Crank–Nicolson; the cylinder wall's nodal temperatures at
//! order 4 in h (quadratic cells superconverge at their vertices).

use crate::common::*;
use aster::runner::{self, RunOptions};
use std::collections::BTreeMap;

/// Run a scene of comm/ at its default knobs: (OK lines, ANALYTIQUE OK lines, NOOK lines).
fn plain(scene: &str) -> (usize, usize, usize) {
    let out = scratch!(scene);
    let o = runner::run_export(
        &root().join(format!("comm/{scene}.export")),
        &RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false },
    );
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    let analytic = mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count();
    let _ = std::fs::remove_dir_all(&out);
    (o.ok_count(), analytic, o.nook_count())
}

/// ERR_L2 of every variant of a study of `scene` on strips of N QUAD8 cells, keyed by the values of
/// `keys` joined by spaces.
fn study(scene: &str, tag: &str, knobs: &[&str], keys: &[&str]) -> BTreeMap<String, f64> {
    let out = scratch!(tag);
    let errs =
        study_err_l2(&out, &format!("{scene}.export"), "20=box --cell QUAD8 --n {N},1 --size 1,0.05", knobs, keys);
    let _ = std::fs::remove_dir_all(&out);
    errs
}

#[test]
fn the_scenes_pass_every_check_at_their_default_knobs() {
    // Three temperatures and ERR_L2, each against the exact solution and our own value.
    assert_eq!(plain("heat_half_space"), (8, 4, 0));
    // The mid-wall temperature and ERR_L2.
    assert_eq!(plain("heat_wall_axis"), (4, 2, 0));
}

#[test]
fn the_half_space_converges_at_order_one_with_implicit_euler_and_two_with_crank_nicolson() {
    let e = study("heat_half_space", "time", &["N=128", "NSTEP=32,64", "THETA=0.5,1.0"], &["NSTEP", "THETA"]);
    let euler = (e["32 1.0"] / e["64 1.0"]).log2();
    assert!((euler - 1.0).abs() < 0.2, "order {euler} in Δt with θ = 1: {e:?}");
    let cn = (e["32 0.5"] / e["64 0.5"]).log2();
    assert!((cn - 2.0).abs() < 0.2, "order {cn} in Δt with θ = 0.5: {e:?}");
}

#[test]
fn the_cylinder_wall_converges_at_order_four_at_the_vertices() {
    let e = study("heat_wall_axis", "space", &["N=4,8,16"], &["N"]);
    for (a, b) in [("4", "8"), ("8", "16")] {
        let order = (e[a] / e[b]).log2();
        assert!((order - 4.0).abs() < 0.2, "order {order} in h from N = {a} to {b}: {e:?}");
    }
    assert!(e["16"] < 1e-7, "{e:?}");
}
