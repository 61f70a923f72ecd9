//! Answers a new user found wrong or silent, each against the behaviour of Code_Aster: TEST_RESU on a
//! CHAM_NO, plane stress of an incompressible material, the alarms Code_Aster gives (MODELE1_3,
//! MODELE1_4, ALGORITH3_41) with their count at the end of the run, IMPR_RESU naming the step a field
//! lacks, and catalogue facts (CALC_TABLE UNIQUE's FORMAT_R, LIRE_FONCTION TYPE='NAPPE' with
//! INTERPOL_FONC, an integral float for an integer), MECA_STATIQUE over LIST_INST.

use crate::common::*;

const PLATE: &str = r#"DEBUT()
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="MODELISATION"))
MAT = DEFI_MATERIAU(ELAS=_F(E=2.0e5, NU=POISSON))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0)))
TRAC = AFFE_CHAR_MECA(MODELE=MO, FORCE_CONTOUR=_F(GROUP_MA="DROITE", FX=10.0))
"#;

fn plate(modelisation: &str, nu: f64, rest: &str) -> String {
    format!(
        "{}{rest}\nFIN()\n",
        PLATE.replace("MODELISATION\"", &format!("{modelisation}\"")).replace("POISSON", &format!("{nu:?}"))
    )
}

/// TEST_RESU CHAM_NO at a node (the factor keyword declares neither cells nor points: looking them up
/// stopped the run as an internal error).
#[test]
fn test_resu_on_a_cham_no_at_a_node() {
    let dir = scratch!("cham_no");
    let comm = plate(
        "D_PLAN",
        0.3,
        "R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))\n\
         U = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='NOEU_DEPL_R', NOM_CHAM='DEPL', RESULTAT=R, NUME_ORDRE=1)\n\
         TEST_RESU(CHAM_NO=(_F(CHAM_GD=U, NOEUD='N1', NOM_CMP='DX', VALE_CALC=0.0, CRITERE='ABSOLU'),\n\
                            _F(CHAM_GD=U, NOEUD='N3', NOM_CMP='DX', VALE_CALC=9.1e-5),\n\
                            _F(CHAM_GD=U, NOM_CMP='DX', TYPE_TEST='MAX', VALE_CALC=9.1e-5)))",
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,1", "2,1"), &comm);
    assert!(status.success(), "{mess}");
    // The zero non-regression value without ORDRE_GRANDEUR is skipped, as Code_Aster does.
    assert!(mess.contains("checks: 2 OK, 0 NOOK, 1 skipped"), "{mess}");
}

/// Plane stress of an incompressible material (ν = 0.5): finite, and the analytic uniaxial answer
/// (σxx = 10, εxx = σ/E, εyy = −ν σ/E). The stiffness used to be infinite (λ = ∞ in 2λμ/(λ+2μ)).
#[test]
fn plane_stress_of_an_incompressible_material() {
    let dir = scratch!("c_plan");
    let (ux, uy) = (2.0 * 10.0 / 2.0e5, -0.5 * 10.0 / 2.0e5);
    let comm = plate(
        "C_PLAN",
        0.5,
        &format!(
            "R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))\n\
             R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_ELNO')\n\
             TEST_RESU(RESU=(_F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOEUD='N3', NOM_CMP='DX', VALE_CALC={ux:?},\n\
                                VALE_REFE={ux:?}, REFERENCE='ANALYTIQUE', PRECISION=1.0e-10),\n\
                             _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOEUD='N6', NOM_CMP='DY', VALE_CALC={uy:?},\n\
                                VALE_REFE={uy:?}, REFERENCE='ANALYTIQUE', PRECISION=1.0e-10),\n\
                             _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='SIGM_ELNO', MAILLE='M7', NOEUD='N1',\n\
                                NOM_CMP='SIXX', VALE_CALC=10.0, VALE_REFE=10.0, REFERENCE='ANALYTIQUE',\n\
                                PRECISION=1.0e-10)))"
        ),
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,1", "2,1"), &comm);
    assert!(status.success(), "{mess}");
    assert!(mess.contains("checks: 6 OK, 0 NOOK"), "{mess}");
}

/// MODELE1_3: a plane modelisation on a mesh out of the plane z = 0 gives Code_Aster's alarm, and the
/// cells asked for that get no element (the hexahedra, for D_PLAN) are counted (MODELE1_4); the end
/// of the run counts the alarms.
#[test]
fn plane_model_on_a_3d_mesh_is_told() {
    let dir = scratch!("modele1_3");
    let comm = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
                MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
                FIN()\n";
    let (status, mess, _) = run_on_box(&dir, ("HEXA8", "2,1,1", "2,1,1"), comm);
    assert!(status.success(), "{mess}");
    assert!(mess.contains("<A> <MODELE1_3> AFFE_MODELE: MODELISATION='D_PLAN'"), "{mess}");
    assert!(
        mess.contains("<MODELE1_4> AFFE_MODELE: of the 12 cells of mesh MA, 12 were asked for and 10 assigned"),
        "{mess}"
    );
    assert!(
        mess.contains("<A> AFFE_MODELE: 2 of the cells asked for carry no element of their modelisation (2 HEXA8)"),
        "{mess}"
    );
    assert!(mess.contains("<A> 2 alarm(s) in this run: 1 of aster-rs, MODELE1_3 x1"), "{mess}");
    // In the plane z = 0, no MODELE1_3 (nor alarm count).
    let dir2 = scratch!("modele1_3_plane");
    let (status, mess, _) = run_on_box(&dir2, ("QUAD4", "2,1", "2,1"), comm);
    assert!(status.success(), "{mess}");
    assert!(!mess.contains("MODELE1_3") && !mess.contains("alarm(s) in this run"), "{mess}");
    assert!(mess.contains("of the 8 cells of mesh MA, 8 were asked for and 8 assigned"), "{mess}");
}

/// ALGORITH3_41: CALC_CHAMP asked for an order or an instant the result does not have computes
/// nothing, with Code_Aster's alarm (it used to compute nothing and say nothing).
#[test]
fn calc_champ_at_a_missing_step_is_told() {
    let dir = scratch!("algorith3_41");
    let comm = plate(
        "D_PLAN",
        0.3,
        "R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_ELNO', NUME_ORDRE=3)\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_NOEU', INST=5.0)\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, DEFORMATION='EPSI_ELGA', INST=0.0)\n\
         TEST_RESU(RESU=_F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='EPSI_ELGA', MAILLE='M7', POINT=1, NOM_CMP='EPXX',\n\
                           VALE_CALC=4.55e-5))\n\
         IMPR_RESU(FORMAT='MED', RESU=_F(RESULTAT=R, NOM_CHAM='SIGM_ELNO'))",
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,1", "2,1"), &comm);
    assert!(!status.success(), "{mess}");
    assert!(mess.contains("<A> <ALGORITH3_41> CALC_CHAMP: result R has no order 3: nothing is computed"), "{mess}");
    assert!(mess.contains("<A> <ALGORITH3_41> CALC_CHAMP: result R has no instant 5.0"), "{mess}");
    assert!(mess.contains("1 OK, 0 NOOK"), "an instant the result has is computed: {mess}");
    assert!(mess.contains("IMPR_RESU: RESU/NOM_CHAM: result R has no field SIGM_ELNO at any order"), "{mess}");
    assert!(mess.contains("<A> 2 alarm(s) in this run: ALGORITH3_41 x2"), "{mess}");
}

/// IMPR_RESU of a field at a step that lacks it names the step (NUME_ORDRE) and the steps that have it.
#[test]
fn impr_resu_names_the_step_a_field_lacks() {
    let dir = scratch!("impr_nume_ordre");
    let comm = plate(
        "D_PLAN",
        0.3,
        "L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=2.0, NOMBRE=2))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)),\n\
                           COMPORTEMENT=_F(RELATION='ELAS'), INCREMENT=_F(LIST_INST=L))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_ELNO', NUME_ORDRE=1)\n\
         IMPR_RESU(FORMAT='MED', RESU=_F(RESULTAT=R, NOM_CHAM='SIGM_ELNO', NUME_ORDRE=2))",
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,1", "2,1"), &comm);
    assert!(!status.success(), "{mess}");
    assert!(
        mess.contains(
            "IMPR_RESU: RESU/NUME_ORDRE: result R has no field SIGM_ELNO at the selected order(s) 2 (it has it at order(s) 1)"
        ),
        "{mess}"
    );
}

/// Catalogue facts of Code_Aster: CALC_TABLE's UNIQUE takes FORMAT_R (values compared as written);
/// LIRE_FONCTION reads a nappe (TYPE='NAPPE', INTERPOL_FONC for its functions); an integer keyword takes
/// a float equal to an integer (NOMBRE=2.0).
#[test]
fn catalogue_facts_of_code_aster() {
    let dir = scratch!("catalogue");
    std::fs::write(dir.join("nappe.txt"), "1.0 10.0 20.0\n2.0 12.0 24.0\n4.0 16.0 30.0\n\n0.5\n1.5\n").unwrap();
    let comm = "DEBUT()\n\
        T = CREA_TABLE(LISTE=(_F(PARA='X', LISTE_R=(1.0, 1.0000001, 2.0)), _F(PARA='N', LISTE_I=(1, 2, 3))))\n\
        U = CALC_TABLE(TABLE=T, ACTION=_F(OPERATION='UNIQUE', NOM_PARA='X', FORMAT_R='1PE12.3'))\n\
        TEST_TABLE(TABLE=U, NOM_PARA='N', TYPE_TEST='SOMM', VALE_CALC_I=4)\n\
        N = LIRE_FONCTION(TYPE='NAPPE', UNITE=31, NOM_PARA='AMOR', NOM_PARA_FONC='FREQ', INDIC_PARA=(2, 1),\n\
                          INDIC_ABSCISSE=(1, 1), DEFI_FONCTION=(_F(INDIC_RESU=(1, 2)), _F(INDIC_RESU=(1, 3))),\n\
                          INTERPOL_FONC='LOG', PROL_DROITE_FONC='CONSTANT')\n\
        TEST_FONCTION(VALEUR=(_F(FONCTION=N, NOM_PARA=('AMOR', 'FREQ'), VALE_PARA=(1.5, 4.0), VALE_CALC=30.0),\n\
                              _F(FONCTION=N, NOM_PARA=('AMOR', 'FREQ'), VALE_PARA=(0.5, 8.0), VALE_CALC=16.0),\n\
                              _F(FONCTION=N, NOM_PARA=('AMOR', 'FREQ'), VALE_PARA=(0.5, 3.0),\n\
                                 VALE_CALC=12.0 * (3.0 / 2.0) ** (math.log(16.0 / 12.0) / math.log(2.0)))))\n\
        L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=4.0))\n\
        SQ = FORMULE(VALE='X*X', NOM_PARA='X')\n\
        G = CALC_FONC_INTERP(FONCTION=SQ, LIST_PARA=L, NOM_PARA='X')\n\
        TEST_FONCTION(VALEUR=_F(FONCTION=G, VALE_PARA=0.6, VALE_CALC=0.375))\n\
        FIN()\n";
    let comm = format!("import math\n{comm}");
    std::fs::write(dir.join("cat.comm"), comm).unwrap();
    let o = aster()
        .arg("run")
        .arg(dir.join("cat.comm"))
        .args(["--out", dir.to_str().unwrap(), "-q", "--unit"])
        .arg(format!("31={}", dir.join("nappe.txt").display()))
        .output()
        .unwrap();
    let mess = std::fs::read_to_string(dir.join("cat.mess")).unwrap_or_default();
    assert!(o.status.success(), "{}\n{mess}", text(&o).1);
    assert!(mess.contains("checks: 5 OK, 0 NOOK"), "{mess}");
    // L holds 0, 0.25, 0.5, 0.75, 1: G is linear between the squares of 0.5 and 0.75 (0.375 at 0.6).
}

/// MECA_STATIQUE over LIST_INST: one linear solve per instant, numbered from 1, the loads multiplied by
/// their FONC_MULT at each instant: with a ramp F(t) = t the displacement at t = 3 is three times the
/// one at t = 1 (DX at the loaded edge 9.1e-5 for the unit load, as above), and a constant load is
/// the same at every instant.
#[test]
fn meca_statique_over_a_list_of_instants() {
    let dir = scratch!("list_inst");
    let comm = plate(
        "D_PLAN",
        0.3,
        "L = DEFI_LIST_REEL(VALE=(1.0, 3.0))\n\
         RAMP = DEFI_FONCTION(NOM_PARA='INST', VALE=(0.0, 0.0, 10.0, 10.0))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, LIST_INST=L,\n\
                           EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC, FONC_MULT=RAMP)))\n\
         C = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, LIST_INST=L, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))\n\
         TEST_RESU(RESU=(_F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOM_CMP='DX', TYPE_TEST='MAX', VALE_CALC=9.1e-5),\n\
                         _F(RESULTAT=R, NUME_ORDRE=2, NOM_CHAM='DEPL', NOM_CMP='DX', TYPE_TEST='MAX', VALE_CALC=2.73e-4),\n\
                         _F(RESULTAT=R, INST=3.0, NOM_CHAM='DEPL', NOM_CMP='DX', TYPE_TEST='MAX', VALE_CALC=2.73e-4),\n\
                         _F(RESULTAT=C, NUME_ORDRE=2, NOM_CHAM='DEPL', NOM_CMP='DX', TYPE_TEST='MAX', VALE_CALC=9.1e-5)))",
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,1", "2,1"), &comm);
    assert!(status.success(), "{mess}");
    assert!(mess.contains("checks: 4 OK, 0 NOOK"), "{mess}");
}
