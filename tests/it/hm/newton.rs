//! The tangent of the HM driver is consistent: on a strongly compressible liquid (ρ = ρ₀ exp(p/K_w)
//! changes by tens of percent within a step) Newton's residual falls quadratically.

use super::{column, run};
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

/// The relative residuals of every step, from the run log's `RESI_GLOB_RELA a → b → c` lines.
fn histories(mess: &str) -> Vec<Vec<f64>> {
    mess.lines()
        .filter(|l| l.trim_start().starts_with("INST ") && l.contains("RESI_GLOB_RELA"))
        .map(|l| {
            let tail = l.split("RESI_GLOB_RELA").nth(1).unwrap();
            tail.split('→').map(|x| x.trim().parse::<f64>().unwrap()).collect()
        })
        .collect()
}

#[test]
fn newton_converges_quadratically_on_a_compressible_liquid() {
    let dir = scratch!("quadratic");
    let mesh = box_mesh(CellType::Quad8, &[1, 4], &[1.0, 4.0]).unwrap();
    // The skeleton held, a liquid with K_w = 1e7 Pa and a large inflow: the pressure rises by several
    // MPa per step, the density by e^0.3 and more.
    let comm = column(1.0e8, 0.5, 0.3, 1.0e-7, 1.0e-13)
        + r#"
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT="OUI", DX=0.0, DY=0.0),
                      FLUX_THM_REP=_F(GROUP_MA="HAUT", FLUN_HYDR1=200.0))
L = DEFI_LIST_REEL(VALE=(0.0, 1.0, 2.0, 3.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
    INCREMENT=_F(LIST_INST=L),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-14, ITER_GLOB_MAXI=20),
)
FIN()
"#;
    let (o, mess) = run(&dir, "quadratic", &mesh, &comm);
    assert_eq!(o.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{mess}", o.error);
    let h = histories(&mess);
    assert_eq!(h.len(), 3, "{mess}");
    let mut quadratic_steps = 0;
    for (k, r) in h.iter().enumerate() {
        assert!(r.len() >= 3, "step {k}: the prediction alone converged, the test is not nonlinear: {r:?}");
        assert!(*r.last().unwrap() <= 1e-14, "step {k}: {r:?}");
        // The order of three successive residuals well above round-off:
        // p = ln(r₂/r₁) / ln(r₁/r₀), 2 for Newton with a consistent tangent.
        for w in r.windows(3).filter(|w| w[2] > 1e-18) {
            let order = (w[2] / w[1]).ln() / (w[1] / w[0]).ln();
            assert!(order > 1.7, "step {k}: residuals {r:?} fall at order {order:.2}, not quadratically");
            quadratic_steps += 1;
        }
    }
    assert!(quadratic_steps >= 2, "too few iterations to measure an order: {h:?}");
}
