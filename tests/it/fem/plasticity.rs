//! Von Mises plasticity with isotropic hardening in STAT_NON_LINE (VMIS_ISOT_LINE, VMIS_ISOT_TRAC):
//! our scene comm/plastic_bar.comm against the closed form of uniaxial tension past yield and back (3D,
//! C_PLAN with a traction curve, AXIS with RECH_LINEAIRE), the cases of Code_Aster's 2025 corpus it makes
//! pass (read in place, skipped with a message where absent), and what it refuses by name.

use crate::common::*;

/// Every check of the scene: the stress, V1 and V2 at every point and the lateral displacement at every
/// step of the three bars, against the closed form within 1e-6, and VARI_NOEU / SIGM_NOEU of CALC_CHAMP.
#[test]
fn bars_past_yield_follow_the_closed_form() {
    let out = crate::scratch!("plastic_bar");
    let opts = aster::runner::RunOptions { out_dir: Some(out.clone()), units: vec![], echo: false };
    let o = aster::runner::run_export(&root().join("comm/plastic_bar.export"), &opts);
    assert_eq!(o.diagnostic, "OK", "{:?}", o.error);
    assert_eq!((o.ok_count(), o.nook_count()), (196, 0));
    let mess = std::fs::read_to_string(out.join("plastic_bar.mess")).unwrap();
    // The run log names the law and the line search; a uniaxial path with linear hardening needs one
    // correction where yield starts and one where unloading starts.
    assert!(mess.contains("STAT_NON_LINE (3D, RELATION='VMIS_ISOT_LINE'): 333 unknowns, 5 steps, 2 Newton"), "{mess}");
    assert!(mess.contains("STAT_NON_LINE (C_PLAN, RELATION='VMIS_ISOT_TRAC')"), "{mess}");
    assert!(mess.contains("RECH_LINEAIRE (CORDE): RESI_LINE_RELA 0.1, ITER_LINE_MAXI 3"), "{mess}");
    let _ = std::fs::remove_dir_all(&out);
}

/// Code_Aster's corpus cases on VMIS_ISOT_LINE that run with every check OK: ssnp303a/b/c (C_PLAN, three
/// materials, MATRICE ELASTIQUE with REAC_ITER=0, TANGENTE with REAC_ITER=0 and 1, RECH_LINEAIRE); their
/// NON_REGRESSION values hold to 1e-6 because the plane-stress return stops where Code_Aster's does.
#[test]
fn corpus_von_mises_cases_pass() {
    run_corpus_cases(&crate::scratch!("corpus"), &[("ssnp303a", 67), ("ssnp303b", 67), ("ssnp303c", 67)]);
}

/// Code_Aster's hsnv100b/g: a square heated through THER_LINEAIRE, VMIS_ISOT_TRAC with a TRACTION nappe of
/// TEMP under AFFE_VARC (C_PLAN, AXIS), CALC_CHAMP ENEL_ELGA / ETOT_ELGA and POST_ELEM ENER_POT /
/// ENER_TOTALE: every check OK, the NON_REGRESSION values within 1e-10 of Code_Aster's.
#[test]
fn corpus_thermoplastic_cases_pass() {
    run_corpus_cases(&crate::scratch!("corpus_thermo"), &[("hsnv100b", 24), ("hsnv100g", 24)]);
}

/// Run comm/plastic_bar.comm with `edits` applied: (exit code, stderr).
fn run_edited(tag: &str, edits: &[(&str, &str)]) -> (i32, String) {
    let units = [(20, "block_hexa20.med"), (21, "bar_quad8.med")];
    let (code, err, _) = run_scene_edited(&crate::scratch!(tag), "plastic_bar", &units, edits);
    (code, err)
}

/// What the plastic laws do not take stops the run by name: another line search, large strains, a
/// hardening slope not below E.
#[test]
fn what_plasticity_does_not_take_is_refused_by_name() {
    let line = ("RECH_LINEAIRE=_F(ITER_LINE_MAXI=3)", "RECH_LINEAIRE=_F(METHODE='MIXTE')");
    let (code, err) = run_edited("mixte", &[line]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("RECH_LINEAIRE/METHODE") && err.contains("'MIXTE'"), "{err}");
    let gdef = ("RELATION=\"VMIS_ISOT_LINE\", TOUT=\"OUI\"", "RELATION=\"VMIS_ISOT_LINE\", DEFORMATION=\"GDEF_LOG\"");
    let (code, err) = run_edited("gdef", &[gdef]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("DEFORMATION") && err.contains("PETIT"), "{err}");
    let slope = ("ECRO_LINE=_F(SY=SY, D_SIGM_EPSI=ET)", "ECRO_LINE=_F(SY=SY, D_SIGM_EPSI=E)");
    let (code, err) = run_edited("slope", &[slope]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("D_SIGM_EPSI") && err.contains("smaller than the Young modulus"), "{err}");
}

/// comm/thermoplastic_bar.comm: a bar held at both ends and heated past yield, its TRACTION a nappe of
/// TEMP and the temperature a THER_LINEAIRE result through AFFE_VARC — SIXX, V1 and ENEL_ELGA at every
/// point of every step, and POST_ELEM's ENER_ELAS and ENER_TOTALE (elastic energy plus plastic work),
/// against the closed form to 1e-9 (the nappe interpolated in temperature as Code_Aster's `rctrac` does,
/// the thermal strain taken off in the law as `nmisot` does).
#[test]
fn heated_bar_yields_along_a_hardening_curve_of_the_temperature() {
    let out = crate::scratch!("thermoplastic_bar");
    let opts = aster::runner::RunOptions { out_dir: Some(out.clone()), units: vec![], echo: false };
    let o = aster::runner::run_export(&root().join("comm/thermoplastic_bar.export"), &opts);
    assert_eq!(o.diagnostic, "OK", "{:?}", o.error);
    assert_eq!((o.ok_count(), o.nook_count()), (47, 0));
    let mess = std::fs::read_to_string(out.join("thermoplastic_bar.mess")).unwrap();
    assert!(mess.contains("STAT_NON_LINE (C_PLAN, RELATION='VMIS_ISOT_TRAC'): 326 unknowns, 4 steps"), "{mess}");
    let _ = std::fs::remove_dir_all(&out);
    // Without the temperature the nappe cannot be read: the run stops by name.
    let varc = ("    AFFE_VARC=_F(TOUT=\"OUI\", NOM_VARC=\"TEMP\", EVOL=TH, VALE_REF=TREF),\n", "");
    let (code, err, _) =
        run_scene_edited(&crate::scratch!("no_varc"), "thermoplastic_bar", &[(20, "strip_quad8.med")], &[varc]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("TRACTION/SIGM") && err.contains("nappe of TEMP"), "{err}");
}
