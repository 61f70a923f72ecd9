//! CREA_RESU end to end: an EVOL_THER made of a function of (X, Y, INST) evaluated at the instants of a
//! list, extended by reuse= (an instant it holds replaced, with an alarm; a new one appended), read back
//! by TEST_RESU against the function's values; the same function evaluated by CREA_CHAMP EVAL; the result
//! feeding the thermal strain of mechanics; ASSE; the corpus cases (PROL_RTZ); bad input stopping by name.

use crate::common::*;

/// T(x, y, t) = 10 + 5x − 3y + 2t on the 2 × 1 rectangle of 4 × 2 QUAD4 (15 nodes: x in 0, 0.5, …, 2 and
/// y in 0, 0.5, 1): its maximum is at (2, 0), 20 + 2t, its minimum at (0, 1), 7 + 2t, and its sum over the
/// nodes 15·10 + 5·15 − 3·7.5 + 15·2t = 202.5 + 30t.
const HEAD: &str = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
TXYT = FORMULE(VALE="10.0 + 5.0*X - 3.0*Y + 2.0*INST", NOM_PARA=("X", "Y", "INST"))
CHF = CREA_CHAMP(TYPE_CHAM="NOEU_TEMP_F", OPERATION="AFFE", MAILLAGE=MA,
                 AFFE=_F(TOUT="OUI", NOM_CMP="TEMP", VALE_F=TXYT))
"#;

fn max(t: f64) -> f64 {
    20.0 + 2.0 * t
}
fn min(t: f64) -> f64 {
    7.0 + 2.0 * t
}
fn somm(t: f64) -> f64 {
    202.5 + 30.0 * t
}

/// A TEST_RESU occurrence of TEMP of TH at `at` (`INST=..` or `NUME_ORDRE=..`), TYPE_TEST `tt`, against `v`.
fn temp(at: &str, tt: &str, v: f64) -> String {
    format!(
        "_F(RESULTAT=TH, {at}, NOM_CHAM=\"TEMP\", NOM_CMP=\"TEMP\", TYPE_TEST=\"{tt}\", VALE_CALC={v:e}, \
         VALE_REFE={v:e}, PRECISION=1e-12, REFERENCE=\"ANALYTIQUE\"),\n"
    )
}

fn analytic_ok(mess: &str) -> usize {
    mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count()
}

fn run(tag: &str, comm: &str) -> (std::process::ExitStatus, String) {
    let dir = scratch!(tag);
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "4,2", "2,1"), comm);
    let _ = std::fs::remove_dir_all(&dir);
    (status, mess)
}

#[test]
fn a_field_of_functions_is_evaluated_at_each_instant_and_reuse_extends_the_result() {
    let mut tests = String::new();
    // LIST_INST from its 2nd to its 4th value: 0.5, 1, 2 at orders 1, 2, 3.
    for (order, t) in [(1, 0.5), (3, 2.0)] {
        tests += &temp(&format!("NUME_ORDRE={order}"), "MAX", max(t));
        tests += &temp(&format!("INST={t}"), "MIN", min(t));
        tests += &temp(&format!("INST={t}"), "SOMM", somm(t));
    }
    // reuse=: INST=1 (order 2) now holds the uniform 20; INST=3 is a new order 4.
    tests += &temp("NUME_ORDRE=2", "MAX", 20.0);
    tests += &temp("INST=1.0", "MIN", 20.0);
    tests += &temp("NUME_ORDRE=4", "SOMM", 15.0 * 20.0);
    let comm = format!(
        r#"{HEAD}
LI = DEFI_LIST_REEL(VALE=(0.0, 0.5, 1.0, 2.0, 4.0))
TH = CREA_RESU(OPERATION="AFFE", TYPE_RESU="EVOL_THER",
               AFFE=_F(NOM_CHAM="TEMP", CHAM_GD=CHF, LIST_INST=LI, NUME_INIT=2, NUME_FIN=4))
T20 = CREA_CHAMP(TYPE_CHAM="NOEU_TEMP_R", OPERATION="AFFE", MAILLAGE=MA, AFFE=_F(TOUT="OUI", NOM_CMP="TEMP", VALE=20.0))
TH = CREA_RESU(reuse=TH, RESULTAT=TH, OPERATION="AFFE", TYPE_RESU="EVOL_THER",
               AFFE=_F(NOM_CHAM="TEMP", CHAM_GD=T20, INST=(1.0, 3.0)))
TEST_RESU(RESU=({tests}))
# The same function evaluated by CREA_CHAMP: its parameters from the geometry and a field of INST.
GEOM = CREA_CHAMP(TYPE_CHAM="NOEU_GEOM_R", OPERATION="EXTR", MAILLAGE=MA, NOM_CHAM="GEOMETRIE")
TI = CREA_CHAMP(TYPE_CHAM="NOEU_INST_R", OPERATION="AFFE", MAILLAGE=MA, AFFE=_F(TOUT="OUI", NOM_CMP="INST", VALE=2.0))
NF = CREA_CHAMP(TYPE_CHAM="NOEU_NEUT_F", OPERATION="AFFE", MAILLAGE=MA, AFFE=_F(TOUT="OUI", NOM_CMP="X1", VALE_F=TXYT))
NR = CREA_CHAMP(TYPE_CHAM="NOEU_NEUT_R", OPERATION="EVAL", CHAM_F=NF, CHAM_PARA=(GEOM, TI))
TEST_RESU(CHAM_NO=(
    _F(CHAM_GD=NR, NOM_CMP="X1", TYPE_TEST="SOMM", VALE_CALC={s:e}, VALE_REFE={s:e}, PRECISION=1e-12,
       REFERENCE="ANALYTIQUE"),
    _F(CHAM_GD=NR, NOM_CMP="X1", TYPE_TEST="MAX", VALE_CALC={m:e}, VALE_REFE={m:e}, PRECISION=1e-12,
       REFERENCE="ANALYTIQUE"),
))
FIN()
"#,
        s = somm(2.0),
        m = max(2.0),
    );
    let (status, mess) = run("affe", &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 11, "{mess}");
    // The field replaced at INST=1 is reported as Code_Aster reports it.
    assert!(mess.contains("<A> <ALGORITH11_87> CREA_RESU: field TEMP at order 2 (INST=1)"), "{mess}");
}

/// A strip held in x at both ends and in y along its bottom (C_PLAN) under a uniform temperature 100 t of a
/// CREA_RESU EVOL_THER: σxx = −E α T at t = 1 and, interpolated between the result's instants, at 0.25;
/// with AFFE_VARC FONC_INST = t / 2 the result is read at half the instant: at t = 1, T = 50.
#[test]
fn a_created_evol_ther_drives_the_thermal_strain_of_mechanics() {
    let sig = |t: f64| -2.0e11 * 1.0e-5 * 100.0 * t;
    let check = |res: &str, t: f64, v: f64| {
        format!(
            "TEST_RESU(RESU=_F(RESULTAT={res}, INST={t}, NOM_CHAM=\"SIEF_ELGA\", NOM_CMP=\"SIXX\", TYPE_TEST=\"MIN\", \
             VALE_CALC={v:e}, VALE_REFE={v:e}, PRECISION=1e-9, REFERENCE=\"ANALYTIQUE\"))\n"
        )
    };
    let comm = format!(
        r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MOME = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="C_PLAN"))
STEEL = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1.0e-5))
HEAT = FORMULE(VALE="100.0*INST", NOM_PARA="INST")
CHF = CREA_CHAMP(TYPE_CHAM="NOEU_TEMP_F", OPERATION="AFFE", MAILLAGE=MA, AFFE=_F(TOUT="OUI", NOM_CMP="TEMP", VALE_F=HEAT))
TH = CREA_RESU(OPERATION="AFFE", TYPE_RESU="EVOL_THER", AFFE=_F(NOM_CHAM="TEMP", CHAM_GD=CHF, INST=(0.0, 1.0)))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=STEEL),
                   AFFE_VARC=_F(NOM_VARC="TEMP", EVOL=TH, VALE_REF=0.0))
HELD = AFFE_CHAR_MECA(MODELE=MOME, DDL_IMPO=(_F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0), _F(GROUP_NO="BAS", DY=0.0)))
R1 = MECA_STATIQUE(MODELE=MOME, CHAM_MATER=CM, EXCIT=_F(CHARGE=HELD), INST=1.0)
R2 = MECA_STATIQUE(MODELE=MOME, CHAM_MATER=CM, EXCIT=_F(CHARGE=HELD), INST=0.25)
HALF = FORMULE(VALE="INST/2.0", NOM_PARA="INST")
CM2 = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=STEEL),
                    AFFE_VARC=_F(NOM_VARC="TEMP", EVOL=TH, VALE_REF=0.0, FONC_INST=HALF))
R3 = MECA_STATIQUE(MODELE=MOME, CHAM_MATER=CM2, EXCIT=_F(CHARGE=HELD), INST=1.0)
{}{}{}FIN()
"#,
        check("R1", 1.0, sig(1.0)),
        check("R2", 0.25, sig(0.25)),
        check("R3", 1.0, sig(0.5))
    );
    let (status, mess) = run("varc", &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 3, "{mess}");
}

/// ASSE: two results one after the other, the second's instants shifted by TRANSLATION; an instant equal
/// to the previous one shares its order; the model is the first result's.
#[test]
fn asse_puts_results_one_after_the_other() {
    let comm = format!(
        r#"{HEAD}
A = CREA_RESU(OPERATION="AFFE", TYPE_RESU="EVOL_THER", AFFE=_F(NOM_CHAM="TEMP", CHAM_GD=CHF, INST=(0.0, 1.0)))
B = CREA_RESU(OPERATION="AFFE", TYPE_RESU="EVOL_THER", AFFE=_F(NOM_CHAM="TEMP", CHAM_GD=CHF, INST=(0.0, 2.0)))
TH = CREA_RESU(OPERATION="ASSE", TYPE_RESU="EVOL_THER",
               ASSE=(_F(RESULTAT=A), _F(RESULTAT=B, TRANSLATION=1.0)))
TEST_RESU(RESU=({}{}{}))
FIN()
"#,
        // A at 0 and 1 are orders 1 and 2; B's 0 (now 1, B's own T(0)) shares order 2; B's 2 is order 3 at 3.
        temp("NUME_ORDRE=1", "SOMM", somm(0.0)),
        temp("NUME_ORDRE=2", "SOMM", somm(0.0)),
        temp("INST=3.0", "MAX", max(2.0)),
    );
    let (status, mess) = run("asse", &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 3, "{mess}");
    // Instants that go back stop the run, naming the instants.
    let bad = comm.replace("TRANSLATION=1.0", "TRANSLATION=-1.0");
    let (status, mess) = run("asse_back", &bad);
    assert!(!status.success());
    assert!(mess.contains("instant -1 of B (order 1) comes before the previous instant 1"), "{mess}");
}

#[test]
fn what_does_not_fit_stops_by_name() {
    let cases = [
        // RESULTAT names the result to extend: without reuse= it is refused.
        (
            "TH = CREA_RESU(OPERATION=\"AFFE\", TYPE_RESU=\"EVOL_THER\", AFFE=_F(NOM_CHAM=\"TEMP\", CHAM_GD=CHF, INST=0.0))\n\
             TH2 = CREA_RESU(RESULTAT=TH, OPERATION=\"AFFE\", TYPE_RESU=\"EVOL_THER\", AFFE=_F(NOM_CHAM=\"TEMP\", CHAM_GD=CHF, INST=1.0))",
            "RESULTAT=TH names a result to extend: it needs reuse=TH as well",
        ),
        // A field on nodes is not an ELGA field.
        (
            "TH = CREA_RESU(OPERATION=\"AFFE\", TYPE_RESU=\"EVOL_ELAS\", AFFE=_F(NOM_CHAM=\"SIEF_ELGA\", CHAM_GD=CHF, INST=0.0))",
            "SIEF_ELGA is an ELGA field, CHF is not one",
        ),
        // The other types of result are not made yet.
        (
            "TH = CREA_RESU(OPERATION=\"AFFE\", TYPE_RESU=\"MULT_ELAS\", AFFE=_F(NOM_CHAM=\"DEPL\", CHAM_GD=CHF, NOM_CAS=\"A\"))",
            "not supported yet: value 'MULT_ELAS' is not allowed for keyword 'TYPE_RESU'",
        ),
        // A function of a parameter other than X, Y, Z, INST cannot be evaluated at nodes.
        (
            "G = FORMULE(VALE=\"2.0*EPSI\", NOM_PARA=\"EPSI\")\n\
             CHG = CREA_CHAMP(TYPE_CHAM=\"NOEU_TEMP_F\", OPERATION=\"AFFE\", MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE_F=G))\n\
             TH = CREA_RESU(OPERATION=\"AFFE\", TYPE_RESU=\"EVOL_THER\", AFFE=_F(NOM_CHAM=\"TEMP\", CHAM_GD=CHG, INST=0.0))",
            "parameter EPSI is not known here (X, Y, Z or INST)",
        ),
        // A field of functions has no values where a field of reals is used.
        (
            "MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"C_PLAN\"))\n\
             ST = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, ALPHA=1.0e-5))\n\
             CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=ST), AFFE_VARC=_F(NOM_VARC=\"TEMP\", CHAM_GD=CHF, VALE_REF=0.0))\n\
             BC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO=\"BAS\", DX=0.0, DY=0.0))\n\
             R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=BC))",
            "CHF is a field of functions",
        ),
    ];
    for (k, (body, want)) in cases.iter().enumerate() {
        let comm = format!("{HEAD}{body}\nFIN()\n");
        let (status, mess) = run(&format!("bad{k}"), &comm);
        assert!(!status.success(), "case {k} ran:\n{mess}");
        assert!(mess.contains(want), "case {k}: want '{want}' in\n{mess}");
    }
}

/// Corpus cases that run end to end with every check OK: PROL_RTZ (zzzz129a: a 1D radial temperature of
/// CREA_RESU AFFE, extracted by POST_RELEVE_T, onto a tilted 3D cylinder); an EVOL_VARC of a NOEU_NEUT_F
/// function of (INST, X, Y, Z) at the instants of a list (zzzz332a); initial temperatures made by
/// CREA_CHAMP EVAL of a NOEU_NEUT_F function of the geometry and ASSE into NOEU_TEMP_R (ttnl101a/b/c).
const CASES: [(&str, usize); 5] =
    [("zzzz129a", 20), ("zzzz332a", 30), ("ttnl101a", 8), ("ttnl101b", 2), ("ttnl101c", 6)];

#[test]
fn corpus_crea_resu_cases_pass() {
    run_corpus_cases(&scratch!("corpus"), &CASES);
}
