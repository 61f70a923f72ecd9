//! Our own scenes (comm/*.export) run end to end with every check OK.

use crate::common::*;
use aster::runner::{self, RunOptions};

#[test]
fn every_scene_runs_ok() {
    let dir = root().join("comm");
    let mut exports: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().map(|x| x == "export").unwrap_or(false))
        .collect();
    exports.sort();
    assert!(exports.len() >= 2, "comm/ should hold our scenes");
    let out = scratch!("scenes");
    let opts = RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false };
    let mut failures = Vec::new();
    for e in &exports {
        let o = runner::run_export(e, &opts);
        println!("{:<24} {:<16} {} OK {} NOOK {:.3} s", o.name, o.diagnostic, o.ok_count(), o.nook_count(), o.seconds);
        if o.diagnostic != "OK" || o.ok_count() == 0 {
            failures.push(format!("{}: {} {}", o.name, o.diagnostic, o.error.unwrap_or_default()));
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_default_scene_is_a_comm_file() {
    let (file, src) = runner::DEFAULT_SCENE;
    let on_disk = std::fs::read_to_string(root().join("comm").join(file)).unwrap();
    assert_eq!(src, on_disk);
    let o = runner::run_default(&RunOptions { out_dir: Some(scratch!("default")), units: Vec::new(), echo: false });
    assert_eq!(o.diagnostic, "OK", "{:?}", o.error);
}

/// `aster run` with no case (the README's first command) writes the demo's outputs in ./aster-out and
/// nothing else in the current folder.
#[test]
fn the_demo_writes_in_aster_out() {
    let cwd = scratch!("demo-cwd");
    let o = aster().args(["run", "--quiet"]).current_dir(&cwd).output().unwrap();
    assert!(o.status.success(), "{:?}", text(&o));
    let mut top: Vec<String> =
        std::fs::read_dir(&cwd).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    top.sort();
    assert_eq!(top, ["aster-out"]);
    for f in ["junction_2d.mess", "junction_2d.resu", "junction_2d.rmed"] {
        assert!(cwd.join("aster-out").join(f).is_file(), "{f}");
    }
    let mess = std::fs::read_to_string(cwd.join("aster-out/junction_2d.mess")).unwrap();
    assert!(mess.contains("DIAGNOSTIC JOB : OK"), "{mess}");
    let _ = std::fs::remove_dir_all(&cwd);
}
