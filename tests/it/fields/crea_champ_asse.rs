//! CREA_CHAMP OPERATION='ASSE' end to end: pieces of fields on nodes and at integration points taken by
//! component (NOM_CMP), renamed (NOM_CMP_RESU), scaled (COEF_R), added (CUMUL='OUI') or replacing, on the
//! nodes and cells chosen; checked by TEST_RESU TYPE_TEST='SOMM' against sums done by hand.

use crate::common::*;

fn analytic_ok(mess: &str) -> usize {
    mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count()
}

/// A TEST_RESU occurrence of the sum of component `cmp` of field `ch` against `v`.
fn somm(kw: &str, ch: &str, cmp: &str, v: f64) -> String {
    format!(
        "TEST_RESU({kw}=_F(CHAM_GD={ch}, NOM_CMP=\"{cmp}\", TYPE_TEST=\"SOMM\", VALE_CALC={v:e}, VALE_REFE={v:e}, \
         PRECISION=1e-12, REFERENCE=\"ANALYTIQUE\"))\n"
    )
}

/// On the 2 × 1 rectangle of 4 × 2 QUAD4 (15 nodes, x in 0, 0.5, …, 2 and y in 0, 0.5, 1; Σx = 15,
/// Σy = 7.5; GROUP_NO DROITE: the 3 nodes at x = 2, HAUT: the 5 at y = 1; 8 cells of 4 points each):
/// X1 = x, plus 10 x added on DROITE: 15 + 3·20 = 75; X2 = y, replaced by −y on HAUT: 7.5 − 2·5 = −2.5.
/// At the points, SIXX = 3·1 + 2 = 5 and SIYY = 3·2 = 6 at each of the 32 points.
#[test]
fn asse_takes_renames_scales_adds_and_replaces() {
    let comm = format!(
        r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
GEOM = CREA_CHAMP(TYPE_CHAM="NOEU_GEOM_R", OPERATION="EXTR", MAILLAGE=MA, NOM_CHAM="GEOMETRIE")
N = CREA_CHAMP(TYPE_CHAM="NOEU_NEUT_R", OPERATION="ASSE", MAILLAGE=MA, ASSE=(
    _F(TOUT="OUI", CHAM_GD=GEOM, NOM_CMP=("X", "Y"), NOM_CMP_RESU=("X1", "X2")),
    _F(GROUP_NO="DROITE", CHAM_GD=GEOM, NOM_CMP="X", NOM_CMP_RESU="X1", CUMUL="OUI", COEF_R=10.0),
    _F(GROUP_NO="HAUT", CHAM_GD=GEOM, NOM_CMP="Y", NOM_CMP_RESU="X2", COEF_R=-1.0),
))
{}{}S1 = CREA_CHAMP(TYPE_CHAM="ELGA_SIEF_R", OPERATION="AFFE", MODELE=MO,
                AFFE=_F(GROUP_MA="SURFACE", NOM_CMP=("SIXX", "SIYY"), VALE=(1.0, 2.0)))
S2 = CREA_CHAMP(TYPE_CHAM="ELGA_SIEF_R", OPERATION="ASSE", MODELE=MO, ASSE=(
    _F(TOUT="OUI", CHAM_GD=S1, COEF_R=3.0),
    _F(TOUT="OUI", CHAM_GD=S1, NOM_CMP="SIYY", NOM_CMP_RESU="SIXX", CUMUL="OUI"),
))
{}{}FIN()
"#,
        somm("CHAM_NO", "N", "X1", 75.0),
        somm("CHAM_NO", "N", "X2", -2.5),
        somm("CHAM_ELEM", "S2", "SIXX", 32.0 * 5.0),
        somm("CHAM_ELEM", "S2", "SIYY", 32.0 * 6.0),
    );
    let dir = scratch!("asse");
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "4,2", "2,1"), &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(analytic_ok(&mess), 4, "{mess}");
    // A component the field does not have is named.
    let bad = comm.replace("NOM_CMP=\"SIYY\", NOM_CMP_RESU", "NOM_CMP=\"SIZZ\", NOM_CMP_RESU");
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "4,2", "2,1"), &bad);
    assert!(!status.success());
    assert!(mess.contains("S1 has no component SIZZ (it has SIXX, SIYY)"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}
