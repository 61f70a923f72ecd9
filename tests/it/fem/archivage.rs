//! STAT_NON_LINE's ARCHIVAGE on every driver: the instants of INST / PAS_ARCH and always the last one,
//! numbered from 0; the fields of CHAM_EXCLU left out of every stored instant but the last. Our scenes
//! comm/block_ramp_snl.comm (elastic, mesh unknowns) and comm/pressurised_interface_2d.comm (X-FEM)
//! run with an ARCHIVAGE added; what was not stored is refused by name when a check asks for it.

use crate::common::*;

/// Run `comm/<scene>.comm` with `edit` applied (from, to), its mesh as unit 20: (exit code, stderr, mess).
fn run_edited(tag: &str, scene: &str, mesh: &str, edits: &[(&str, &str)]) -> (i32, String, String) {
    run_scene_edited(&crate::scratch!(tag), scene, &[(20, mesh)], edits)
}

fn ok_lines(mess: &str) -> usize {
    mess.lines().filter(|l| l.trim_start().starts_with("OK ")).count()
}

const SNL_END: &str = "CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-8, ITER_GLOB_MAXI=5),\n)";

#[test]
fn elastic_ramp_stores_the_instants_asked_for_and_the_last() {
    // INST 0.25 .. 2.0 in six steps; 1.0 and 1.5 asked for, 2.0 stored as the last: the checks at 1.0,
    // 1.5 and 2.0 pass, SIEF_ELGA at 1.0 is not checked here (excluded).
    let keep = "CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-8, ITER_GLOB_MAXI=5),\n    \
                ARCHIVAGE=_F(INST=(1.0, 1.5), CHAM_EXCLU='SIEF_ELGA'),\n)";
    let no_025 = ("((0.25, 0.25), (1.0, 1.0), (1.5, 0.75), (2.0, 0.5))", "((1.0, 1.0), (1.5, 0.75), (2.0, 0.5))");
    let sief_at_2 = ("INST=1.0, NOM_CHAM=\"SIEF_ELGA\"", "INST=2.0, NOM_CHAM=\"SIEF_ELGA\"");
    let half = ("VALE_CALC=P, VALE_REFE=P,", "VALE_CALC=0.5 * P, VALE_REFE=0.5 * P,");
    let (code, err, mess) =
        run_edited("snl", "block_ramp_snl", "block_quad8.med", &[(SNL_END, keep), no_025, sief_at_2, half]);
    assert_eq!(code, 0, "{err}\n{mess}");
    assert_eq!(ok_lines(&mess), 8, "{mess}"); // four checks, each ANALYTIQUE and NON_REGRESSION
                                              // An instant left out, and an excluded field before the last instant, are refused by name.
    let (code, err, _) = run_edited("snl-025", "block_ramp_snl", "block_quad8.med", &[(SNL_END, keep)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("TEST_RESU") && err.contains("0.25"), "{err}");
    let (code, err, _) = run_edited("snl-sief", "block_ramp_snl", "block_quad8.med", &[(SNL_END, keep), no_025]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("TEST_RESU") && err.contains("SIEF_ELGA"), "{err}");
}

#[test]
fn xfem_driver_archives_too() {
    let end = "CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10))";
    // INST=1.0 asked for, 2.0 the last: every check of the scene passes, as without ARCHIVAGE.
    let (code, err, mess) = run_edited(
        "xfem",
        "pressurised_interface_2d",
        "junction_quad8.med",
        &[(end, "CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10), ARCHIVAGE=_F(INST=1.0, CHAM_EXCLU='SIEF_ELGA'))")],
    );
    assert_eq!(code, 0, "{err}\n{mess}");
    assert_eq!(ok_lines(&mess), 144, "{mess}");
    // Every second instant: INST=1.0 is not stored, and the check there says so.
    let (code, err, _) = run_edited(
        "xfem-pas",
        "pressurised_interface_2d",
        "junction_quad8.med",
        &[(end, "CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10), ARCHIVAGE=_F(PAS_ARCH=2))")],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("RESNL has no step at time 1"), "{err}");
}

/// The elastic STAT_NON_LINE reports its solver as the X-FEM and HM drivers do: the method, the condition
/// estimate of the first factorization and the digits it costs (issue 10, point 3).
#[test]
fn elastic_newton_logs_the_condition_estimate() {
    let (code, err, mess) = run_edited("snl-cond", "block_ramp_snl", "block_quad8.med", &[]);
    assert_eq!(code, 0, "{err}");
    let line = mess.lines().find(|l| l.contains("condition estimate")).unwrap_or_else(|| panic!("{mess}"));
    // "condition estimate 8.2e2 (2.9 digits lost)"
    let est = line.split("condition estimate ").nth(1).and_then(|s| s.split(" digits lost").next()).unwrap();
    let (c, lost) = est.split_once(" (").unwrap();
    let (c, lost): (f64, f64) = (c.parse().unwrap(), lost.parse().unwrap());
    assert!((1.0..1e8).contains(&c), "{line}");
    assert!((lost - c.log10()).abs() < 0.06, "{line}");
    assert!(mess.contains("solver    : SOLVEUR METHODE='MUMPS'"), "{mess}");
}
