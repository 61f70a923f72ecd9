//! Bad input to the HM driver: each a located `<F>` naming what is wrong, and no result file delivered.

use super::column;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

/// Run `comm` (with a result unit 80 asked for) and check the located error and that nothing was
/// delivered.
fn expect(tag: &str, comm: &str, located: &str, message: &str) {
    expect_diag(tag, comm, located, message, "<F>_ERROR")
}

fn expect_diag(tag: &str, comm: &str, located: &str, message: &str, diagnostic: &str) {
    let dir = scratch!(tag);
    let mesh = box_mesh(CellType::Quad8, &[1, 2], &[1.0, 2.0]).unwrap();
    let comm = format!("{comm}\nIMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(MAILLAGE=MA))\nFIN()\n");
    let mesh_path = dir.join(format!("{tag}.med"));
    aster::med::write_mesh(&mesh_path, &mesh, "MAIL").unwrap();
    let comm_path = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm_path, &comm).unwrap();
    let out = dir.join("out");
    let rmed = dir.join("result.rmed");
    use aster::runner::export::Dir;
    let opts = aster::runner::RunOptions {
        out_dir: Some(out.clone()),
        units: vec![(20, mesh_path, Dir::In), (80, rmed.clone(), Dir::Out)],
        echo: false,
    };
    let o = aster::runner::run_comm(&comm_path, &opts);
    let err = o.error.clone().unwrap_or_default();
    assert_eq!(o.diagnostic.to_string(), diagnostic, "{tag}: {err}");
    assert!(err.contains(located), "{tag}: expected the location '{located}' in: {err}");
    assert!(err.contains(message), "{tag}: expected '{message}' in: {err}");
    assert!(!rmed.exists(), "{tag}: a result file was delivered by a run that stopped");
}

const SOLVE: &str = r#"
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(TOUT="OUI", DX=0.0, DY=0.0), _F(GROUP_NO="BAS", PRE1=0.0)))
L = DEFI_LIST_REEL(VALE=(0.0, 1.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
)"#;

#[test]
fn missing_thm_data() {
    let comm: String = column(1.0e8, 1.0, 0.3, 0.0, 1.0e-12)
        .lines()
        .filter(|l| !l.contains("THM_LIQU="))
        .map(|l| format!("{l}\n"))
        .collect::<String>()
        + SOLVE;
    // The catalogue knows COMP_THM needs THM_LIQU (Code_Aster's: a mandatory keyword of its block).
    expect_diag("missing_thm", &comm, "DEFI_MATERIAU", "mandatory keyword 'THM_LIQU' is missing", "<F>_SYNTAX_ERROR");
    // A purely elastic material on an HM model: the driver names what is missing.
    let comm = column(1.0e8, 1.0, 0.3, 0.0, 1.0e-12).replace(
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=SOL))",
        "ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3))\nCHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=ACIER))",
    ) + SOLVE;
    expect("elastic_only", &comm, "STAT_NON_LINE", "the material has no COMP_THM");
}

#[test]
fn negative_permeability_and_viscosity() {
    let comm = column(1.0e8, 1.0, 0.3, 0.0, -1.0e-12) + SOLVE;
    expect("perm", &comm, "STAT_NON_LINE", "THM_DIFFU/PERM_IN = -0.000000000001 must not be negative");
    let comm = column(1.0e8, 1.0, 0.3, 0.0, 1.0e-12).replace("VISC=UN", "VISC=DEFI_CONSTANTE(VALE=-1.0e-3)") + SOLVE;
    expect("visc", &comm, "STAT_NON_LINE", "THM_LIQU/VISC = -0.001 must be positive");
}

#[test]
fn a_pressure_condition_on_a_model_without_pressure() {
    let comm = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ACIER))
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="BAS", DX=0.0, DY=0.0, PRE1=1.0e5),))
L = DEFI_LIST_REEL(VALE=(0.0, 1.0))
RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR), INCREMENT=_F(LIST_INST=L))"#;
    expect("pre1_dplan", comm, "STAT_NON_LINE", "PRE1 is not a dof of a D_PLAN model");
}

#[test]
fn a_time_list_that_does_not_increase() {
    let comm = column(1.0e8, 1.0, 0.3, 0.0, 1.0e-12) + &SOLVE.replace("VALE=(0.0, 1.0)", "VALE=(0.0, 2.0, 1.0)");
    expect("time_list", &comm, "DEFI_LIST_REEL", "the values must be strictly increasing (2 then 1)");
    let comm = column(1.0e8, 1.0, 0.3, 0.0, 1.0e-12)
        + &SOLVE
            .replace("L = DEFI_LIST_REEL(VALE=(0.0, 1.0))", "L = DEFI_LIST_INST(DEFI_LIST=_F(VALE=(0.0, 1.0, 1.0)))");
    expect("time_list_inst", &comm, "DEFI_LIST_INST", "the instants must increase strictly (1 then 1)");
}
