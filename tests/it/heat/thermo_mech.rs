//! Heat into mechanics: AFFE_MATERIAU AFFE_VARC NOM_VARC='TEMP' from an EVOL_THER, its thermal strain
//! α (T − VALE_REF) in MECA_STATIQUE / STAT_NON_LINE, the temperature interpolated in time between the
//! result's instants, PROL_DROITE beyond them, and what is not supported stopping by name.

use crate::common::*;

/// A strip held in x at both ends and in y along its bottom (C_PLAN): σxx = −E α (T − T_ref) exactly.
fn bar(varc: &str, solve: &str) -> String {
    format!(
        r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MOTH = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="PLAN"))
MOME = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="C_PLAN"))
STEEL = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1.0e-5), THER=_F(LAMBDA=1.0, RHO_CP=1.0))
CMTH = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=STEEL))
RAMP = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 1.0, 100.0))
HOT = AFFE_CHAR_THER_F(MODELE=MOTH, TEMP_IMPO=_F(TOUT="OUI", TEMP=RAMP))
LI = DEFI_LIST_REEL(VALE=(0.0, 1.0))
TH = THER_LINEAIRE(MODELE=MOTH, CHAM_MATER=CMTH, EXCIT=_F(CHARGE=HOT), INCREMENT=_F(LIST_INST=LI),
                   ETAT_INIT=_F(VALE=0.0))
CMME = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=STEEL),
                     AFFE_VARC=_F(NOM_VARC="TEMP", EVOL=TH, VALE_REF=0.0{varc}))
HELD = AFFE_CHAR_MECA(MODELE=MOME, DDL_IMPO=(_F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0), _F(GROUP_NO="BAS", DY=0.0)))
{solve}
FIN()
"#
    )
}

/// TEST_RESU lines on SIXX of `res` at `inst`: min and max against `sig`.
fn sixx(res: &str, inst: f64, sig: f64) -> String {
    ["MIN", "MAX"]
        .iter()
        .map(|k| {
            format!(
                "TEST_RESU(RESU=_F(RESULTAT={res}, INST={inst}, NOM_CHAM=\"SIEF_ELGA\", NOM_CMP=\"SIXX\", TYPE_TEST=\"{k}\", \
                 VALE_CALC={sig:e}, VALE_REFE={sig:e}, PRECISION=1e-9, REFERENCE=\"ANALYTIQUE\"))\n"
            )
        })
        .collect()
}

fn analytic_ok(mess: &str) -> usize {
    mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count()
}

#[test]
fn the_restrained_bar_scene_holds_back_its_thermal_strain() {
    let out = scratch!("scene");
    let o = aster::runner::run_export(
        &root().join("comm/heat_restrained_bar.export"),
        &aster::runner::RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false },
    );
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    // The four stresses and POST_ELEM's ENER_POT (its total and POUR_CENT).
    assert_eq!((analytic_ok(&mess), o.nook_count()), (6, 0), "{mess}");
    let _ = std::fs::remove_dir_all(&out);
}

/// ELAS_FO whose Young modulus is a function of TEMP, in MECA_STATIQUE under AFFE_VARC: the restrained bar
/// scene with E(T) falling linearly from 2e11 at 0 to 1e11 at 200 — at T1 = 120 the axial stress is
/// −E(120) α ΔT = −1.68e8 at every point (the law taken at each point's temperature), and POST_ELEM's
/// ENER_POT, which needs constant parameters, stops by name.
#[test]
fn a_young_modulus_of_the_temperature_in_meca_statique() {
    let material = (
        "STEEL = DEFI_MATERIAU(ELAS=_F(E=E, NU=0.3, ALPHA=ALPHA), THER=_F(LAMBDA=54.6, RHO_CP=3.71e6))",
        "FE = DEFI_FONCTION(NOM_PARA=\"TEMP\", VALE=(0.0, 2.0e11, 200.0, 1.0e11))\n\
         FNU = DEFI_CONSTANTE(VALE=0.3)\n\
         FALPHA = DEFI_CONSTANTE(VALE=ALPHA)\n\
         STEEL = DEFI_MATERIAU(ELAS_FO=_F(E=FE, NU=FNU, ALPHA=FALPHA, TEMP_DEF_ALPHA=TREF), \
         THER=_F(LAMBDA=54.6, RHO_CP=3.71e6))",
    );
    let sig = ("SIG = -E * ALPHA * (T1 - TREF)", "SIG = -1.4e11 * ALPHA * (T1 - TREF)");
    let no_epot = [
        ("EPOT = POST_ELEM(RESULTAT=RES, ENER_POT=_F(TOUT=\"OUI\"))\n", ""),
        ("TEST_TABLE(TABLE=EPOT, NOM_PARA=\"TOTALE\", VALE_CALC=WPOT, VALE_REFE=WPOT, PRECISION=1.0e-9, REFERENCE=\"ANALYTIQUE\")\n", ""),
        ("TEST_TABLE(TABLE=EPOT, NOM_PARA=\"POUR_CENT\", VALE_CALC=100.0, VALE_REFE=100.0, PRECISION=1.0e-12, REFERENCE=\"ANALYTIQUE\")\n", ""),
    ];
    let units = [(20, "strip_quad8.med")];
    let mut edits = vec![material, sig];
    edits.extend(no_epot);
    let (code, err, out) = run_scene_edited(&scratch!("elas_fo"), "heat_restrained_bar", &units, &edits);
    assert_eq!(code, 0, "{err}{out}");
    assert_eq!(out.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count(), 4, "{out}");
    assert!(out.contains("checks: 6 OK, 0 NOOK"), "{out}");
    let (code, err, _) = run_scene_edited(&scratch!("elas_fo_epot"), "heat_restrained_bar", &units, &[material, sig]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("POST_ELEM") && err.contains("TEMP"), "{err}");
}

/// Code_Aster's hplp300a: a plate heated through THER_LINEAIRE, ELAS_FO's E and NU functions of TEMP in
/// MECA_STATIQUE under AFFE_VARC, the displacements read by POST_RELEVE_T along groups of nodes (with their
/// ABSC_CURV): every check OK.
#[test]
fn corpus_elasticity_of_the_temperature_passes() {
    run_corpus_cases(&scratch!("corpus_elas_fo"), &[("hplp300a", 33)]);
}

/// Timoshenko's thick cylinder under the logarithmic temperature of its wall (AXIS, no axial strain): the
/// hoop stress at the nodes (CALC_CHAMP SIGM_NOEU, with the thermal strain) within 0.05 % at the inner face
/// and 4.2e-4 in L2 across the wall at N = 32.
#[test]
fn the_thick_cylinder_scene_has_timoshenkos_hoop_stress() {
    let out = scratch!("cylinder");
    let o = aster::runner::run_export(
        &root().join("comm/heat_thick_cylinder.export"),
        &aster::runner::RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false },
    );
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    assert_eq!((analytic_ok(&mess), o.ok_count(), o.nook_count()), (2, 4, 0), "{mess}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_temperature_is_interpolated_between_the_instants_of_the_result() {
    let dir = scratch!("interpolated");
    std::fs::create_dir_all(&dir).unwrap();
    // T = 100 t: at 0.25 the temperature is 25 between the stored 0 and 100; STAT_NON_LINE steps at 0.5, 1.
    let solve = format!(
        "R1 = MECA_STATIQUE(MODELE=MOME, CHAM_MATER=CMME, EXCIT=_F(CHARGE=HELD), INST=0.25)\n{}\
         LM = DEFI_LIST_REEL(VALE=(0.0, 0.5, 1.0))\n\
         R2 = STAT_NON_LINE(MODELE=MOME, CHAM_MATER=CMME, EXCIT=_F(CHARGE=HELD), INCREMENT=_F(LIST_INST=LM))\n{}{}",
        sixx("R1", 0.25, -2.0e11 * 1.0e-5 * 25.0),
        sixx("R2", 0.5, -2.0e11 * 1.0e-5 * 50.0),
        sixx("R2", 1.0, -2.0e11 * 1.0e-5 * 100.0),
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &bar("", &solve));
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 6, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn beyond_the_last_instant_prol_droite_decides() {
    let dir = scratch!("prol");
    std::fs::create_dir_all(&dir).unwrap();
    let solve = "R1 = MECA_STATIQUE(MODELE=MOME, CHAM_MATER=CMME, EXCIT=_F(CHARGE=HELD), INST=2.0)\n";
    // EXCLU (the default): the run stops, naming the instant and PROL_DROITE.
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &bar("", solve));
    assert!(!status.success());
    assert!(mess.contains("INST=2 lies outside the instants of TH (0 to 1) and PROL_DROITE='EXCLU'"), "{mess}");
    // CONSTANT: the last temperature, 100.
    let solve = format!("{solve}{}", sixx("R1", 2.0, -2.0e11 * 1.0e-5 * 100.0));
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &bar(", PROL_DROITE=\"CONSTANT\"", &solve));
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 2, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn other_command_variables_stop_by_name() {
    let dir = scratch!("others");
    std::fs::create_dir_all(&dir).unwrap();
    let comm =
        bar("", "").replace("NOM_VARC=\"TEMP\", EVOL=TH, VALE_REF=0.0", "NOM_VARC=\"SECH\", EVOL=TH, VALE_REF=0.0");
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &comm);
    assert!(!status.success());
    assert!(mess.contains("NOM_VARC='SECH' is not supported yet (TEMP is)"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}
