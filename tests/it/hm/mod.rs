//! Coupled hydro-mechanics end to end on command files of our own: Newton's quadratic convergence on a
//! strongly nonlinear liquid, the elimination of prescribed pressures, located errors on bad input,
//! Terzaghi's consolidation over h, Δt and θ (the orders of convergence), and the choice of LDLᵀ or LU.
mod bad_input;
mod elimination;
mod newton;
mod solver;
mod terzaghi_study;
mod thermal;

use aster::med;
use aster::mesh::Mesh;
use aster::runner::export::Dir;
use aster::runner::{self, Outcome, RunOptions};
use std::path::Path;

/// The "N solved" count of an HM run's log.
pub fn solved(mess: &str) -> usize {
    let l = mess.lines().find(|l| l.contains("unknowns  :")).expect("the HM log");
    let s = l.split(',').next_back().unwrap().trim();
    s.split_whitespace().next().unwrap().parse().unwrap()
}

/// Write `mesh` and `comm` in `dir`, run the command file with the mesh on unit 20; the outcome and
/// the message file.
pub fn run(dir: &Path, name: &str, mesh: &Mesh, comm: &str) -> (Outcome, String) {
    let mesh_path = dir.join(format!("{name}.med"));
    med::write_mesh(&mesh_path, mesh, "MAIL").unwrap();
    let comm_path = dir.join(format!("{name}.comm"));
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    (o, mess)
}

/// The material and model of a saturated column, with `{E}`, `{BIOT}`, `{PORO}`, `{UNSURK}`, `{K}` to fill.
pub const COLUMN: &str = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_HM"))
UN = DEFI_CONSTANTE(VALE=1.0)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE={K})
SOL = DEFI_MATERIAU(
    ELAS=_F(E={E}, NU=0.0),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO={PORO}),
    THM_DIFFU=_F(RHO=2000.0, BIOT_COEF={BIOT}, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=KINT),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K={UNSURK}, VISC=UN, D_VISC_TEMP=ZERO),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=SOL))
"#;

/// COLUMN with its parameters.
pub fn column(e: f64, biot: f64, poro: f64, unsurk: f64, k: f64) -> String {
    COLUMN
        .replace("{E}", &format!("{e:e}"))
        .replace("{BIOT}", &format!("{biot}"))
        .replace("{PORO}", &format!("{poro}"))
        .replace("{UNSURK}", &format!("{unsurk:e}"))
        .replace("{K}", &format!("{k:e}"))
}
