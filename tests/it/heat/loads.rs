//! The loads of AFFE_CHAR_THER(_F) against closed-form answers, and THER_LINEAIRE / THER_NON_LINE /
//! STAT_NON_LINE refusing what is not theirs by name.
//!
//! The slab 0 ≤ x ≤ L (a strip of QUAD8 cells, insulated top and bottom) conducts with λ, heated by a
//! source s, held at T = 0 at x = 0 and exchanging with the outside at x = L: −λ T'(L) = h (T(L) − T_ext).
//! The temperature is the quadratic T = −s x² / (2λ) + a x, a = (sL + h s L² / (2λ) + h T_ext) / (λ + hL),
//! which quadratic cells reproduce exactly.

use crate::common::*;

const L: f64 = 1.0;
const LAMBDA: f64 = 2.0;
const S: f64 = 3.0;
const H: f64 = 5.0;
const TEXT: f64 = 10.0;

fn exact(x: f64) -> f64 {
    let a = (S * L + H * S * L * L / (2.0 * LAMBDA) + H * TEXT) / (LAMBDA + H * L);
    -S * x * x / (2.0 * LAMBDA) + a * x
}

/// The slab's command file: `mat` the material, `solve` the solving command's call up to its first keyword
/// (`THER_LINEAIRE(`).
fn slab(mat: &str, solve: &str) -> String {
    format!(
        r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="PLAN"))
{mat}
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
HF = DEFI_CONSTANTE(VALE={H})
TF = DEFI_FONCTION(NOM_PARA="X", VALE=(0.0, {TEXT}, 2.0, {TEXT}))
SF = DEFI_CONSTANTE(VALE={S})
ZF = DEFI_CONSTANTE(VALE=0.0)
CH = AFFE_CHAR_THER_F(
    MODELE=MO,
    TEMP_IMPO=_F(GROUP_NO="GAUCHE", TEMP=ZF),
    ECHANGE=_F(GROUP_MA="DROITE", COEF_H=HF, TEMP_EXT=TF),
    SOURCE=_F(GROUP_MA="SURFACE", SOUR=SF),
)
LI = DEFI_LIST_REEL(VALE=0.0)
RES = {solve}MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), TYPE_CALCUL="STAT", INCREMENT=_F(LIST_INST=LI))
TT = POST_RELEVE_T(ACTION=_F(OPERATION="EXTRACTION", INTITULE="T", RESULTAT=RES, NOM_CHAM="TEMP",
                             INST=0.0, GROUP_NO="BAS", NOM_CMP="TEMP"))
{tests}FIN()
"#,
        tests = XS
            .iter()
            .map(|x| format!(
                "TEST_TABLE(TABLE=TT, NOM_PARA=\"TEMP\", FILTRE=_F(NOM_PARA=\"COOR_X\", VALE={x}, CRITERE=\"ABSOLU\", \
                 PRECISION=1e-9), VALE_CALC={v:e}, VALE_REFE={v:e}, PRECISION=1e-9, REFERENCE=\"ANALYTIQUE\")\n",
                v = exact(*x)
            ))
            .collect::<String>()
    )
}

/// The abscissae checked: a vertex, a mid-side node, the exchanging end.
const XS: [f64; 3] = [0.25, 0.625, 1.0];

fn check(tag: &str, mat: &str, solve: &str) {
    let dir = scratch!(tag);
    std::fs::create_dir_all(&dir).unwrap();
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &slab(mat, solve));
    assert!(status.success(), "{mess}");
    // Each abscissa against the closed form within 1e-9 (and against itself).
    let analytic = mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count();
    assert_eq!(analytic, XS.len(), "{mess}");
    assert!(!mess.lines().any(|l| l.trim_start().starts_with("NOOK")), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn source_and_exchange_give_the_quadratic_profile_in_ther_lineaire() {
    check("linear", "MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0, RHO_CP=1.0))", "THER_LINEAIRE(");
}

#[test]
fn the_same_by_newton_in_ther_non_line_with_a_ther_nl_material() {
    let mat = "LF = DEFI_FONCTION(NOM_PARA=\"TEMP\", VALE=(0.0, 2.0, 100.0, 2.0))\n\
               BF = DEFI_FONCTION(NOM_PARA=\"TEMP\", VALE=(0.0, 0.0, 100.0, 100.0))\n\
               MAT = DEFI_MATERIAU(THER_NL=_F(LAMBDA=LF, BETA=BF))";
    check("newton", mat, "THER_NON_LINE(");
}

/// What is not a command's stops the run by name, at its keyword.
#[test]
fn commands_refuse_what_is_not_theirs_by_name() {
    let dir = scratch!("refusals");
    std::fs::create_dir_all(&dir).unwrap();
    // A load depending on the temperature in THER_LINEAIRE.
    let comm = slab("MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0))", "THER_LINEAIRE(")
        .replace("    SOURCE=_F(GROUP_MA=\"SURFACE\", SOUR=SF),", "    FLUX_NL=_F(GROUP_MA=\"DROITE\", FLUN=SF),");
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &comm);
    assert!(!status.success());
    assert!(mess.contains("FLUX_NL depends on the temperature: THER_NON_LINE computes it"), "{mess}");
    // STAT_NON_LINE on a thermal model.
    let comm = slab("MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0))", "THER_LINEAIRE(").replace(
        "RES = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), TYPE_CALCUL=\"STAT\", \
         INCREMENT=_F(LIST_INST=LI))",
        "RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, INCREMENT=_F(LIST_INST=LI))",
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &comm);
    assert!(!status.success());
    assert!(mess.contains("is a thermal model: THER_LINEAIRE or THER_NON_LINE solves it"), "{mess}");
    // A transient computation without RHO_CP.
    let comm = slab("MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0))", "THER_LINEAIRE(")
        .replace("LI = DEFI_LIST_REEL(VALE=0.0)", "LI = DEFI_LIST_REEL(VALE=(0.0, 1.0))")
        .replace("TYPE_CALCUL=\"STAT\", ", "");
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &comm);
    assert!(!status.success());
    assert!(mess.contains("a transient computation needs RHO_CP"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// AFFE_CHAR_CINE(_F) prescribes the unknowns as TEMP_IMPO / DDL_IMPO do: the slab with its left end held by
/// THER_IMPO, and a bar in tension clamped by MECA_IMPO (ν = 0: u = F L / E exactly).
#[test]
fn kinematic_loads_prescribe_the_unknowns() {
    let dir = scratch!("cine");
    std::fs::create_dir_all(&dir).unwrap();
    let comm = slab("MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0))", "THER_LINEAIRE(")
        .replace("    TEMP_IMPO=_F(GROUP_NO=\"GAUCHE\", TEMP=ZF),\n", "")
        .replace(
            "LI = DEFI_LIST_REEL(VALE=0.0)",
            "CI = AFFE_CHAR_CINE_F(MODELE=MO, THER_IMPO=_F(GROUP_NO=\"GAUCHE\", TEMP=ZF))\nLI = DEFI_LIST_REEL(VALE=0.0)",
        )
        .replace("EXCIT=_F(CHARGE=CH)", "EXCIT=(_F(CHARGE=CH), _F(CHARGE=CI))");
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,1", "1,0.1"), &comm);
    assert!(status.success(), "{mess}");
    let analytic = mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count();
    assert_eq!(analytic, XS.len(), "{mess}");
    let bar = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
MAT = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.0))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CI = AFFE_CHAR_CINE(MODELE=MO, MECA_IMPO=_F(GROUP_NO="GAUCHE", DX=0.0, DY=0.0))
CH = AFFE_CHAR_MECA(MODELE=MO, FORCE_CONTOUR=_F(GROUP_MA="DROITE", FX=1.0))
RES = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=CI), _F(CHARGE=CH)))
TEST_RESU(RESU=_F(RESULTAT=RES, NUME_ORDRE=1, NOM_CHAM="DEPL", NOM_CMP="DX", TYPE_TEST="MAX",
                  VALE_CALC=0.002, VALE_REFE=0.002, PRECISION=1e-10, REFERENCE="ANALYTIQUE"))
FIN()
"#;
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "4,2", "2,1"), bar);
    assert!(status.success(), "{mess}");
    assert!(mess.contains("OK  ANALYTIQUE"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// CALC_CHAMP SOUR_ELGA (Joule heating of a potential computed as a temperature): a uniform gradient
/// g = ΔT/2 across a 2 × 1 box gives |λg|²/λ = λg² at every point; the steps asked by INST.
#[test]
fn sour_elga_of_a_uniform_gradient() {
    let dir = scratch!("sour_elga");
    std::fs::create_dir_all(&dir).unwrap();
    let (lambda, dt) = (2.0_f64, 10.0_f64);
    let sour = lambda * (dt / 2.0).powi(2);
    let comm = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="PLAN"))
MAT = DEFI_MATERIAU(THER=_F(LAMBDA=@L@))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CH = AFFE_CHAR_THER(MODELE=MO, TEMP_IMPO=(_F(GROUP_NO="GAUCHE", TEMP=0.0), _F(GROUP_NO="DROITE", TEMP=@DT@)))
RES = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), TYPE_CALCUL="STAT",
                    INCREMENT=_F(LIST_INST=DEFI_LIST_REEL(VALE=(0.0, 1.0))))
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, INST=1.0, THERMIQUE=("SOUR_ELGA",))
TEST_RESU(RESU=(_F(RESULTAT=RES, INST=1.0, NOM_CHAM="SOUR_ELGA", NOM_CMP="SOUR", TYPE_TEST="MAX",
                   VALE_CALC=@S@, VALE_REFE=@S@, PRECISION=1e-9, REFERENCE="ANALYTIQUE"),
                _F(RESULTAT=RES, INST=1.0, NOM_CHAM="SOUR_ELGA", NOM_CMP="SOUR", TYPE_TEST="MIN",
                   VALE_CALC=@S@, VALE_REFE=@S@, PRECISION=1e-9, REFERENCE="ANALYTIQUE")))
FIN()
"#
    .replace("@L@", &format!("{lambda:?}"))
    .replace("@DT@", &format!("{dt:?}"))
    .replace("@S@", &format!("{sour:?}"));
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "4,2", "2,1"), &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count(), 2, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}
