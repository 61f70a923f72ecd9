//! Saturated THM (KIT_THM) on scenes of our own: a temperature prescribed everywhere is eliminated, and
//! the scene then solves exactly its HM twin; a uniformly heated drained block expands freely.

use super::{run, solved};
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

/// The rows of table `name` of a .resu text: (node, values of `cmps`).
fn values(resu: &str, name: &str, cmps: &[&str]) -> Vec<(String, Vec<f64>)> {
    crate::common::resu_rows(resu, name)
        .into_iter()
        .filter_map(|r| {
            let v: Option<Vec<f64>> = cmps.iter().map(|c| r.get(*c)?.parse().ok()).collect();
            Some((r.get("NOEUD")?.clone(), v?))
        })
        .collect()
}

/// A consolidating column (load on the drained top, base fixed, sides on rollers) in `modelisation`
/// with the thermal data a THM material needs; `extra` adds loads (EXC names them all).
fn consolidation(modelisation: &str, kit: &str, extra: &str) -> String {
    format!(
        r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="{modelisation}"))
UN = DEFI_CONSTANTE(VALE=1.0e-3)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE=1.0e-12)
ALPL = DEFI_CONSTANTE(VALE=2.0e-4)
LAMB = DEFI_CONSTANTE(VALE=1.8)
SOL = DEFI_MATERIAU(
    ELAS=_F(E=1.0e8, NU=0.25, ALPHA=1.0e-5),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO=0.3, TEMP=293.0),
    THM_DIFFU=_F(RHO=2000.0, CP=800.0, BIOT_COEF=0.9, PESA_X=0.0, PESA_Y=-9.81, PESA_Z=0.0, PERM_IN=KINT,
                 LAMB_T=LAMB),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=5.0e-10, VISC=UN, D_VISC_TEMP=ZERO, ALPHA=ALPL, CP=4180.0),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=SOL))
CHAR = AFFE_CHAR_MECA(MODELE=MO,
    DDL_IMPO=(_F(GROUP_NO="BAS", DY=0.0), _F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0), _F(GROUP_NO="HAUT", PRE1=0.0)),
    PRES_REP=_F(GROUP_MA="HAUT", PRES=1.0e5))
{extra}
L = DEFI_LIST_REEL(VALE=(0.0, 10.0, 100.0, 1000.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=EXC,
    COMPORTEMENT=_F(RELATION="{kit}", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    SCHEMA_THM=_F(PARM_THETA=0.57),
    INCREMENT=_F(LIST_INST=L),
)
T = POST_RELEVE_T(ACTION=_F(OPERATION="EXTRACTION", INTITULE="U", RESULTAT=RES, NOM_CHAM="DEPL", INST=1000.0,
                            GROUP_NO="GAUCHE", NOM_CMP=("DY", "PRE1")))
IMPR_TABLE(TABLE=T)
FIN()
"#
    )
}

#[test]
fn a_constant_temperature_thm_scene_solves_its_hm_twin() {
    let dir = scratch!("constant_temperature");
    let mesh = box_mesh(CellType::Quad8, &[2, 8], &[1.0, 4.0]).unwrap();
    let hm = consolidation("D_PLAN_HM", "KIT_HM", "EXC = (_F(CHARGE=CHAR),)");
    let thm = consolidation(
        "D_PLAN_THM",
        "KIT_THM",
        r#"TEMP = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT="OUI", TEMP=0.0))
EXC = (_F(CHARGE=CHAR), _F(CHARGE=TEMP))"#,
    );
    let (o1, m1) = run(&dir, "hm", &mesh, &hm);
    let (o2, m2) = run(&dir, "thm", &mesh, &thm);
    assert_eq!(o1.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{m1}", o1.error);
    assert_eq!(o2.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{m2}", o2.error);
    // 3 × 9 = 27 vertices carry a temperature, all prescribed and eliminated: the log says so.
    assert!(m2.contains("TEMP prescribed on all 27 vertices"), "{m2}");
    assert!(m2.contains("27 temperatures TEMP"), "{m2}");
    assert_eq!(solved(&m1), solved(&m2), "HM {}, THM {}", solved(&m1), solved(&m2));
    let r1 = std::fs::read_to_string(dir.join("out/hm.resu")).unwrap();
    let r2 = std::fs::read_to_string(dir.join("out/thm.resu")).unwrap();
    let (v1, v2) = (values(&r1, "U", &["DY"]), values(&r2, "U", &["DY"]));
    assert_eq!(v1.len(), 17, "{r1}");
    assert_eq!(v1.len(), v2.len());
    for ((n, a), (m, b)) in v1.iter().zip(&v2) {
        assert_eq!(n, m);
        assert!((a[0] - b[0]).abs() <= 1e-12 * a[0].abs().max(1e-12), "node {n}: DY {} HM, {} THM", a[0], b[0]);
    }
    let (p1, p2) = (values(&r1, "U", &["PRE1"]), values(&r2, "U", &["PRE1"]));
    // The vertices carry the pressures (9 of the 17 nodes of the side), still consolidating at t = 1000 s.
    assert_eq!(p1.len(), 9, "{r1}");
    assert!(p1.iter().any(|(_, p)| p[0] > 1.0e3), "{p1:?}");
    for ((n, a), (_, b)) in p1.iter().zip(&p2) {
        assert!((a[0] - b[0]).abs() <= 1e-9 * a[0].abs().max(1.0), "node {n}: PRE1 {} HM, {} THM", a[0], b[0]);
    }
}

#[test]
fn a_uniformly_heated_drained_block_expands_freely() {
    // D_PLAN_THM, ΔT = 20 K everywhere, drained (PRE1 = 0), held only at x = 0 (DX) and y = 0 (DY): no
    // stress in the plane, ε_xx = ε_yy = (1 + ν) α ΔT and σ_zz = −E α ΔT (plane strain).
    let dir = scratch!("heated_block");
    let mut mesh = box_mesh(CellType::Quad8, &[3, 2], &[3.0, 2.0]).unwrap();
    let corner = (0..mesh.nnodes()).find(|&n| mesh.coords[n][0] == 3.0 && mesh.coords[n][1] == 2.0).unwrap();
    mesh.node_groups.insert("CORNER".into(), vec![corner]);
    let quad = (0..mesh.ncells()).find(|&c| mesh.cell_types[c] == CellType::Quad8).unwrap();
    mesh.cell_groups.insert("ONE".into(), vec![quad]);
    let comm = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_THMD"))
UN = DEFI_CONSTANTE(VALE=1.0e-3)
ZERO = DEFI_CONSTANTE(VALE=0.0)
ALPL = DEFI_CONSTANTE(VALE=1.0e-4)
SOL = DEFI_MATERIAU(
    ELAS=_F(E=1.0e7, NU=0.25, ALPHA=1.0e-5),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO=0.3, TEMP=293.0),
    THM_DIFFU=_F(RHO=2000.0, CP=800.0, BIOT_COEF=1.0, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=UN, LAMB_T=UN),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=5.0e-10, VISC=UN, D_VISC_TEMP=ZERO, ALPHA=ALPL, CP=4180.0),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=SOL))
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0),
                                           _F(TOUT="OUI", PRE1=0.0, TEMP=20.0)))
L = DEFI_LIST_REEL(VALE=(0.0, 1.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
    COMPORTEMENT=_F(RELATION="KIT_THM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
)
TEST_RESU(RESU=(
    _F(RESULTAT=RES, NUME_ORDRE=1, NOM_CHAM="DEPL", GROUP_NO="CORNER", NOM_CMP="DX", VALE_CALC=7.5e-4,
       REFERENCE="ANALYTIQUE", VALE_REFE=7.5e-4, PRECISION=1.0e-9),
    _F(RESULTAT=RES, NUME_ORDRE=1, NOM_CHAM="DEPL", GROUP_NO="CORNER", NOM_CMP="DY", VALE_CALC=5.0e-4,
       REFERENCE="ANALYTIQUE", VALE_REFE=5.0e-4, PRECISION=1.0e-9),
    _F(RESULTAT=RES, NUME_ORDRE=1, NOM_CHAM="SIEF_ELGA", GROUP_MA="ONE", POINT=1, NOM_CMP="SIZZ", VALE_CALC=-2000.0,
       REFERENCE="ANALYTIQUE", VALE_REFE=-2000.0, PRECISION=1.0e-9),
    _F(RESULTAT=RES, NUME_ORDRE=1, NOM_CHAM="SIEF_ELGA", GROUP_MA="ONE", POINT=1, NOM_CMP="SIXX", VALE_CALC=0.0,
       REFERENCE="ANALYTIQUE", VALE_REFE=0.0, CRITERE="ABSOLU", PRECISION=1.0e-6),
))
FIN()
"#;
    let (o, mess) = run(&dir, "block", &mesh, comm);
    assert_eq!(o.diagnostic.to_string(), "OK", "{:?}\n{mess}", o.error);
    // Temperatures and pressures all prescribed: only displacements are solved.
    assert!(mess.contains("TEMP prescribed on all 12 vertices"), "{mess}");
    let resu = std::fs::read_to_string(dir.join("out/block.resu")).unwrap();
    assert_eq!(resu.lines().filter(|l| l.trim_start().starts_with("OK ")).count(), 7, "{resu}");
}
