//! ETAT_INIT=_F(EVOL_NOLI=...) with `reuse=` on a cohesive X-FEM interface (one QUAD8 cell cut by
//! Y = 0.3, pulled open past the threshold, unloaded, reloaded to full separation, then pushed shut): the
//! computation cut in two calls at a damaged, unloading state gives the numbers of one call — the
//! interface report of every step (λ_n, w_n, the damage counts, the dissipated energy), and the stored
//! result: its orders, instants, displacements and cohesive multipliers (POST_RELEVE_T of every order).

use crate::common::run_on_box;

const SCENE: &str = r#"DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
LN = FORMULE(VALE="Y-0.3", NOM_PARA=["X", "Y"])
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS, DECOUPE_FACETTE="SOUS_ELEMENTS", CONTACT="MORTAR")
CTX = DEFI_CONTACT(MODELE=MO, FORMULATION="XFEM", ZONE=_F(FISS_MAIT=FISS, INTEGRATION="GAUSS", ORDRE_INT=2,
                   ALGO_CONT="CZM", ALGO_LAGR="VERSION2", RELATION="CZM_LIN_MIX"))
MAT = DEFI_MATERIAU(ELAS=_F(E=5.8e9, NU=0.0), RUPT_FRAG=_F(GC=9.0e3, SIGM_C=5.0e5, PENA_LAGR=100.0))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=MAT))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_MA="BAS", DX=0.0, DY=0.0), _F(GROUP_MA="HAUT", DX=0.0)))
TIRE = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA="HAUT", DY=1.0))
CHEMIN = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 0.5, 5.0e-5, 1.0, 0.004, 2.0, 0.012, 3.0, 0.005, 4.0, 0.04,
                                               5.0, -1.0e-4))
LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=5.0, NOMBRE=10))
STEPS
T = POST_RELEVE_T(ACTION=_F(INTITULE="U", GROUP_NO="HAUT", RESULTAT=RESU, NOM_CHAM="DEPL",
                            NOM_CMP=("DY", "H1Y", "LAGS_C", "LAG2_C", "LAG3_C"), OPERATION="EXTRACTION"))
IMPR_TABLE(TABLE=T)
FIN()
"#;

fn snl(extra: &str, fin: f64) -> String {
    format!(
        "RESU = STAT_NON_LINE({extra}MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TIRE, \
         FONC_MULT=CHEMIN)), CONTACT=CTX, COMPORTEMENT=_F(RELATION=\"ELAS\"), INCREMENT=_F(LIST_INST=LINST, \
         INST_FIN={fin}), CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10, ITER_GLOB_MAXI=30), \
         ARCHIVAGE=_F(CHAM_EXCLU=\"SIEF_ELGA\"))\n"
    )
}

/// Run the scene with `steps` for its STAT_NON_LINE calls: (interface lines, the table of the result).
fn run(tag: &str, steps: &str) -> (Vec<String>, String) {
    let dir = scratch!(tag);
    let (status, mess, resu) = run_on_box(&dir, ("QUAD8", "1,1", "1,1"), &SCENE.replace("STEPS\n", steps));
    assert!(mess.contains("DIAGNOSTIC JOB : NO_TEST_RESU") && !mess.contains("<F>"), "{status}\n{mess}");
    let _ = std::fs::remove_dir_all(&dir);
    let lines = mess.lines().filter(|l| l.trim_start().starts_with("FISS: lambda_n")).map(|l| l.trim().to_string());
    (lines.collect(), resu)
}

/// The numbers of a text, in order.
fn numbers(s: &str) -> Vec<f64> {
    s.split(|c: char| c.is_whitespace() || c == ',' || c == '[' || c == ']' || c == '/')
        .filter_map(|w| w.parse::<f64>().ok())
        .collect()
}

fn close(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: {} numbers against {}", a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= 1e-9 * x.abs().max(y.abs()) + 1e-300, "{what}: {x} against {y}");
    }
}

#[test]
fn a_restart_in_two_calls_gives_the_numbers_of_one_call() {
    let (one, table_one) = run("one", &snl("", 5.0));
    let two_calls = format!("{}{}", snl("", 2.5), snl("reuse=RESU, ETAT_INIT=_F(EVOL_NOLI=RESU), ", 5.0));
    let (two, table_two) = run("two", &two_calls);
    assert_eq!(one.len(), 10, "{one:#?}");
    assert_eq!(two.len(), 10, "{two:#?}");
    for (a, b) in one.iter().zip(&two) {
        close(&numbers(a), &numbers(b), &format!("{a} / {b}"));
    }
    // The path goes through every regime: sound, damaged, unloading, broken, shut again.
    let last = numbers(one.last().unwrap());
    assert!(last[0] < -1.0e5 && last[2].abs() < 1e-15 && last[3].abs() < 1e-15, "{last:?}");
    assert!(one[0].contains("sound/damaged/broken 2/0/0"), "{}", one[0]);
    assert!(one.iter().any(|l| l.contains("sound/damaged/broken 0/2/0")), "{one:#?}");
    assert!(one.iter().any(|l| l.contains("sound/damaged/broken 0/0/2")), "{one:#?}");
    // The stored result: orders 0..10 at the instants 0, 0.5, ..., 5 in both, with the same fields.
    let rows_one: Vec<&str> = table_one.lines().filter(|l| l.trim_start().starts_with("U ")).collect();
    let rows_two: Vec<&str> = table_two.lines().filter(|l| l.trim_start().starts_with("U ")).collect();
    assert_eq!(rows_one.len(), 11 * 3, "{table_one}");
    assert_eq!(rows_two.len(), rows_one.len(), "{table_two}");
    for (k, (a, b)) in rows_one.iter().zip(&rows_two).enumerate() {
        let (na, nb) = (numbers(a), numbers(b));
        assert_eq!(na[0], (k / 3) as f64, "order of row {k}: {a}");
        assert_eq!(na[1], 0.5 * (k / 3) as f64, "instant of row {k}: {a}");
        close(&na, &nb, &format!("{a} / {b}"));
    }
}

#[test]
fn etat_init_refuses_what_it_cannot_continue() {
    // An order the result does not hold: a located error, no panic.
    let steps = format!(
        "{}RESU = STAT_NON_LINE(reuse=RESU, ETAT_INIT=_F(EVOL_NOLI=RESU, NUME_ORDRE=7), MODELE=MO, \
         CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TIRE, FONC_MULT=CHEMIN)), CONTACT=CTX, \
         COMPORTEMENT=_F(RELATION=\"ELAS\"), INCREMENT=_F(LIST_INST=LINST, INST_FIN=5.0))\n",
        snl("", 1.0)
    );
    let dir = scratch!("bad");
    let (_, mess, _) = run_on_box(&dir, ("QUAD8", "1,1", "1,1"), &SCENE.replace("STEPS\n", &steps));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(mess.contains("ETAT_INIT/NUME_ORDRE: RESU has no order 7"), "{mess}");
    assert!(!mess.contains("panicked"), "{mess}");
}
