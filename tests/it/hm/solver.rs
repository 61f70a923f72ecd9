//! The HM tangent goes to the symmetric solver when it can: with an incompressible liquid (constant
//! density) the pressure rows scaled by 1/ρ₀ make it symmetric, and LDLᵀ solves it; a compressible liquid
//! whose density changes by tens of percent (ρ = ρ₀ exp(p/K_w) at the points) leaves it non-symmetric,
//! and LU does.

use super::{column, run};
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

const STEPS: &str = r#"
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="HAUT", PRE1=0.0), _F(GROUP_NO="BAS", DX=0.0, DY=0.0),
                                          _F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0)),
                      PRES_REP=_F(GROUP_MA="HAUT", PRES=1.0))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=(_F(JUSQU_A=1.0e-4, NOMBRE=1), _F(JUSQU_A=100.0, NOMBRE=20)))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
)
TP = POST_RELEVE_T(ACTION=_F(OPERATION="EXTRACTION", INTITULE="P", RESULTAT=RES, NOM_CHAM="DEPL", INST=100.0,
                             GROUP_NO="GAUCHE", NOM_CMP="PRE1"))
IMPR_TABLE(TABLE=TP, NOM_PARA=("COOR_Y", "PRE1"))
FIN()
"#;

/// The solver line of the HM log and the .resu text of a column scene.
fn solve(tag: &str, comm: &str) -> (String, String) {
    let dir = crate::scratch!(tag);
    let mesh = box_mesh(CellType::Quad8, &[1, 8], &[1.0, 10.0]).unwrap();
    let (o, mess) = run(&dir, tag, &mesh, comm);
    assert_eq!(o.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{mess}", o.error);
    let line = mess.lines().skip_while(|l| !l.contains("    solver    :")).nth(1).unwrap_or_default().to_string();
    let resu = std::fs::read_to_string(dir.join("out").join(format!("{tag}.resu"))).unwrap_or_default();
    (line, resu)
}

#[test]
fn the_symmetric_tangent_goes_to_ldlt() {
    // Terzaghi's column (b = 1, incompressible phases, c_v = 0.1 m²/s, H = 10).
    let (line, resu) = solve("incompressible", &(column(1.0e7, 1.0, 0.5, 0.0, 1.0e-8) + STEPS));
    assert!(line.trim_start().starts_with("LDLT"), "{line}");
    // The base pressure at T = 0.1 against the series (0.94931), to the error of 8 cells and 20 implicit
    // Euler steps.
    let base = resu
        .lines()
        .filter_map(|l| {
            let w: Vec<f64> = l.split_whitespace().filter_map(|v| v.parse().ok()).collect();
            (w.len() == 2 && w[0] == 0.0).then(|| w[1])
        })
        .next()
        .unwrap_or_else(|| panic!("{resu}"));
    assert!((base - 0.94931).abs() < 1e-2, "{base}");
}

#[test]
fn the_tangent_of_a_compressible_liquid_goes_to_lu() {
    // The liquid of hm::newton: K_w = 1e7 Pa under a large inflow, the density changes within a step.
    let comm = column(1.0e8, 0.5, 0.3, 1.0e-7, 1.0e-13)
        + r#"
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT="OUI", DX=0.0, DY=0.0),
                      FLUX_THM_REP=_F(GROUP_MA="HAUT", FLUN_HYDR1=200.0))
L = DEFI_LIST_REEL(VALE=(0.0, 1.0, 2.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-12, ITER_GLOB_MAXI=20),
)
FIN()
"#;
    let (line, _) = solve("compressible", &comm);
    assert!(line.trim_start().starts_with("LU"), "{line}");
}
