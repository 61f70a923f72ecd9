//! Simulate only what the scene calls for: a pressure prescribed on part of the domain removes those
//! unknowns from the solve, and the answer is the same where both scenes apply.

use super::{column, run, solved};
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

/// The PRE1 values of the `P` table (node, value) of a run's .resu text.
fn pressures(resu: &str) -> Vec<(String, f64)> {
    crate::common::resu_rows(resu, "P")
        .into_iter()
        .filter_map(|r| Some((r.get("NOEUD")?.clone(), r.get("PRE1")?.parse().ok()?)))
        .collect()
}

#[test]
fn pressure_prescribed_on_half_the_column_is_eliminated_there() {
    let dir = scratch!("half");
    // A steady flow (skeleton held, incompressible phases) through a column of height 8: the pressure is
    // linear, p = 1e5 + 1e4 y. In the second scene the upper half is prescribed at those values: fewer
    // unknowns, the same pressures below.
    let mut mesh = box_mesh(CellType::Quad8, &[1, 16], &[1.0, 8.0]).unwrap();
    let upper: Vec<usize> = (0..mesh.coords.len()).filter(|&n| mesh.coords[n][1] >= 4.0 - 1e-12).collect();
    mesh.node_groups.insert("UPPER".into(), upper);
    let scene = |extra: &str| {
        column(1.0e9, 1.0, 0.3, 0.0, 1.0e-9)
            + &format!(
                r#"
PLIN = FORMULE(VALE="1.0e5 + 1.0e4 * Y", NOM_PARA=("X", "Y"))
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(TOUT="OUI", DX=0.0, DY=0.0), _F(GROUP_NO="BAS", PRE1=1.0e5)),
                      FLUX_THM_REP=_F(GROUP_MA="HAUT", FLUN_HYDR1=1.0e-2))
{extra}
L = DEFI_LIST_REEL(VALE=(0.0, 1.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=EXC,
    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
)
T = POST_RELEVE_T(ACTION=_F(OPERATION="EXTRACTION", INTITULE="P", RESULTAT=RES, NOM_CHAM="DEPL", NUME_ORDRE=1,
                            GROUP_NO="GAUCHE", NOM_CMP="PRE1"))
IMPR_TABLE(TABLE=T)
FIN()
"#
            )
    };
    let free = scene("EXC = (_F(CHARGE=CHAR),)");
    let half = scene(
        r#"HALF = AFFE_CHAR_MECA_F(MODELE=MO, DDL_IMPO=_F(GROUP_NO="UPPER", PRE1=PLIN))
EXC = (_F(CHARGE=CHAR), _F(CHARGE=HALF))"#,
    );
    let (o1, m1) = run(&dir, "free", &mesh, &free);
    let (o2, m2) = run(&dir, "half", &mesh, &half);
    assert_eq!(o1.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{m1}", o1.error);
    assert_eq!(o2.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{m2}", o2.error);
    // The log says what was eliminated.
    assert!(m2.contains("PRE1 prescribed on"), "{m2}");
    let (n1, n2) = (solved(&m1), solved(&m2));
    // 17 vertex rows of 2 vertices, the upper half's 9 rows (y ≥ 4) prescribed: 18 pressures fewer.
    assert_eq!(n1 - n2, 18, "free {n1}, half {n2}");
    let r1 = std::fs::read_to_string(dir.join("out/free.resu")).unwrap();
    let r2 = std::fs::read_to_string(dir.join("out/half.resu")).unwrap();
    let (p1, p2) = (pressures(&r1), pressures(&r2));
    assert_eq!(p1.len(), 17, "{r1}");
    assert_eq!(p1.len(), p2.len());
    for ((n, a), (m, b)) in p1.iter().zip(&p2) {
        assert_eq!(n, m);
        assert!((a - b).abs() <= 1e-9 * a.abs(), "node {n}: {a} free, {b} with the upper half prescribed");
    }
}
