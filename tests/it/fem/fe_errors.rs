//! Bad input to the finite-element stages: each a located error, a non-zero
//! exit and a message that names the entity.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A QUAD4 block 2 x 1 (groups BAS, DROITE, HAUT, GAUCHE, SURFACE) written by our MED writer.
fn mesh(dir: &Path) -> PathBuf {
    let p = dir.join("block.med");
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["mesh", "box", "--cell", "QUAD4", "--n", "2,1", "--size", "2,1", "-o"])
        .arg(&p)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    p
}

const HEAD: &str = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e5, NU=0.3))\n";

fn run(name: &str, body: &str) -> (i32, String) {
    let dir = scratch!(name);
    let m = mesh(&dir);
    std::fs::write(dir.join("case.comm"), format!("{HEAD}{body}")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(dir.join("case.comm"))
        .args(["--out", dir.to_str().unwrap(), "-q", "--unit"])
        .arg(format!("20={}", m.display()))
        .output()
        .unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn missing_material_on_a_cell() {
    let (code, err) = run(
        "material",
        "MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM='M1ONLY', MAILLE='M1'))\n\
         CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(GROUP_MA='M1ONLY', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0., DY=0.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("case.comm:8:5: MECA_STATIQUE: cell") && err.contains("has no material (AFFE_MATERIAU)"),
        "{err}"
    );
}

#[test]
fn load_on_an_unknown_group() {
    let (code, err) = run("group", "CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='LEFT', DX=0.))\n");
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("case.comm:5:")
            && err.contains("AFFE_CHAR_MECA: DDL_IMPO/GROUP_NO: group of nodes 'LEFT' is not in mesh MA"),
        "{err}"
    );
}

#[test]
fn rigid_body_motion_is_reported_as_singular() {
    let (code, err) = run(
        "singular",
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("case.comm:7:48: MECA_STATIQUE: EXCIT: the system is singular"), "{err}");
    // The free motion is a vertical translation: the unknowns named are DY.
    assert!(err.contains(" DY"), "{err}");
}

/// NPREC (Code_Aster's meaning: a pivot losing more than NPREC digits is singular) stops the same free
/// system by naming the worst unknown, node and component; with the check off (NPREC < 0) an unbalanced
/// load on it has no solution, and RESI_RELA stops it after the solve.
#[test]
fn nprec_and_resi_rela_stop_an_ill_posed_case() {
    let (code, err) = run(
        "nprec",
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH), SOLVEUR=_F(NPREC=6))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("the factorization lost more than NPREC=6 significant digits at unknown N") && err.contains(" DY"),
        "{err}"
    );
    let (code, err) = run(
        "resi_rela",
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0.), FORCE_NODALE=_F(GROUP_NO='DROITE', FY=1.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH), SOLVEUR=_F(NPREC=-1, RESI_RELA=1.e-6))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("<F>") && err.contains("exceeds RESI_RELA=1.0e-6"), "{err}");
}

#[test]
fn component_foreign_to_the_model() {
    let (code, err) = run(
        "component",
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0., DY=0., DZ=0.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("component DZ is not a dof of a D_PLAN model"), "{err}");
}

#[test]
fn newton_that_does_not_converge() {
    let (code, err) = run(
        "newton",
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='GAUCHE', DX=0., DY=0.), _F(GROUP_NO='DROITE', DX=0.01)))\n\
         L = DEFI_LIST_REEL(VALE=(0., 1.))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH), COMPORTEMENT=_F(RELATION='ELAS'),\n\
             INCREMENT=_F(LIST_INST=L), CONVERGENCE=_F(RESI_GLOB_RELA=1.e-30, ITER_GLOB_MAXI=3))\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("case.comm:9:28: STAT_NON_LINE: CONVERGENCE: Newton did not converge at INST=1 in 3 iterations"),
        "{err}"
    );
}

/// `Y = CMD(reuse=X, ...)` (wtnv122d: `MAILLAGE = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ...)`) modifies X
/// in place and makes Y another name of it, as Code_Aster 2025 does: the group DEFI_GROUP adds under
/// the name MA2 is on MA, and a solve through either name passes its check.
#[test]
fn reuse_under_another_name_is_the_same_concept() {
    let (code, err) = run(
        "reuse-alias",
        "MA2 = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM='TOUTES', GROUP_MA='SURFACE'))\n\
         CHMAT = AFFE_MATERIAU(MAILLAGE=MA2, AFFE=_F(GROUP_MA='TOUTES', MATER=ACIER))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='GAUCHE', DX=0.), _F(GROUP_NO='BAS', DY=0.)),\n\
                             FORCE_NODALE=_F(GROUP_NO='DROITE', FX=1.))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH))\n\
         TEST_RESU(RESU=_F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOM_CMP='DX', TYPE_TEST='MIN',\n\
                           VALE_CALC=0.0, CRITERE='ABSOLU'))\n\
         FIN()\n",
    );
    assert_eq!(code, 0, "{err}");
}

/// VERI_NORM='NON' turns off a check of the skins' normals we do not make: the load is built; an
/// explicit VERI_NORM='OUI' asks for that check and stops by name.
#[test]
fn veri_norm_non_is_taken_and_oui_is_refused_by_name() {
    let body = |v: &str| {
        format!(
            "CH = AFFE_CHAR_MECA(MODELE=MO, VERI_NORM='{v}', DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0., DY=0.),\n\
             PRES_REP=_F(GROUP_MA='DROITE', PRES=1.))\n\
             CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
             R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH))\nFIN()\n"
        )
    };
    let (code, err) = run("verinon", &body("NON"));
    assert_eq!(code, 0, "{err}");
    let (code, err) = run("verioui", &body("OUI"));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("case.comm:5:") && err.contains("VERI_NORM") && err.contains("not supported yet"), "{err}");
}
