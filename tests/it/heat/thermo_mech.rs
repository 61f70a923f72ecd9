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
