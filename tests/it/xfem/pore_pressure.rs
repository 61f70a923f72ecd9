//! Pore pressures on X-FEM hydro-mechanical models, in a column of 2 × 4 QUAD8 cells (D_PLAN_HM, ν = 0,
//! lateral displacement held) cut by a horizontal interface y = 1.3, its lips free, held at y = 0 and
//! y = 4, with p₋ = 2e5 below and p₊ = 5e5 above. Each part is then a free bar with σ_yy = E ε − b p = 0:
//! ε = b p / E, so DY = b p₋/E · 1.3 on the lower lip and −b p₊/E · 2.7 on the upper one, and
//! POST_CHAM_XFEM gives each lip its side's pressure.
//!
//! - Prescribed everywhere (the flow is not solved): PRE1 by side, and H1PRE1 = (p₊ − p₋)/2 on every
//!   enriched vertex. That single value holds on both sides only with Code_Aster's Heaviside functions
//!   (ψ = +2 above for a node below the interface, ψ = −2 below for a node above it: `xcelno`'s
//!   mono-Heaviside flag). The pressure loads the skeleton through the Biot term −b·p.
//! - Solved (coupled flow in the enriched elements, the HM driver): PRE1 given on the bottom and top
//!   edges only. The interface is impervious, so at steady state each part takes its edge's pressure; one
//!   implicit step of 1e10 s with Δt·K/μ·E/L² ≈ 6e10 reaches it to round-off.

use crate::hm::run;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;

const E: f64 = 1.0e7;
const BIOT: f64 = 0.8;
const P_LO: f64 = 2.0e5;
const P_HI: f64 = 5.0e5;
const Y_C: f64 = 1.3;

/// Rows (node, DY, PRE1) of the `LIPS` table of a run's .resu text.
fn lips(resu: &str) -> Vec<(String, f64, f64)> {
    crate::common::resu_rows(resu, "LIPS")
        .into_iter()
        .map(|r| (r["NOEUD"].clone(), r["DY"].parse().unwrap(), r["PRE1"].parse().unwrap()))
        .collect()
}

/// The column's command file with the hydraulic load `hydr` and the instants `inst`.
fn scene(hydr: &str, inst: &str) -> String {
    format!(
        r#"DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_HM"))
LN = FORMULE(VALE="Y-{Y_C}", NOM_PARA=["X", "Y"])
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS)
VISC = DEFI_CONSTANTE(VALE=1.0e-3)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE=1.0e-8)
SOL = DEFI_MATERIAU(
    ELAS=_F(E={E:e}, NU=0.0),
    COMP_THM="LIQU_SATU",
    THM_INIT=_F(PRE1=0.0, PORO=0.3),
    THM_DIFFU=_F(RHO=2000.0, BIOT_COEF={BIOT}, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=KINT),
    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=0.0, VISC=VISC, D_VISC_TEMP=ZERO),
)
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=SOL))
MECA = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(TOUT="OUI", DX=0.0, H1X=0.0), _F(GROUP_MA=("BAS", "HAUT"), DY=0.0)))
HYDR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=({hydr}))
L = DEFI_LIST_REEL(VALE=(0.0, {inst}))
RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=MECA), _F(CHARGE=HYDR)),
                    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
                    INCREMENT=_F(LIST_INST=L))
MAX = POST_MAIL_XFEM(MODELE=MO)
MOV = AFFE_MODELE(MAILLAGE=MAX, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN_HM"))
RESV = POST_CHAM_XFEM(MODELE_VISU=MOV, RESULTAT=RES)
T = POST_RELEVE_T(ACTION=_F(OPERATION="EXTRACTION", INTITULE="LIPS", RESULTAT=RESV, NOM_CHAM="DEPL", NUME_ORDRE=1,
                            GROUP_NO="NFISSU", TOUT_CMP="OUI"))
IMPR_TABLE(TABLE=T)
FIN()
"#
    )
}

/// Run the scene; the message file and the lips' (node, DY, PRE1), checked against the analytic field.
fn run_and_check(tag: &str, comm: &str) -> String {
    let dir = scratch!(tag);
    let mut mesh = box_mesh(CellType::Quad8, &[2, 4], &[2.0, 4.0]).unwrap();
    let side = |above: bool| (0..mesh.coords.len()).filter(|&n| (mesh.coords[n][1] > Y_C) == above).collect();
    let (lo, hi): (Vec<usize>, Vec<usize>) = (side(false), side(true));
    mesh.node_groups.insert("LO".into(), lo);
    mesh.node_groups.insert("HI".into(), hi);
    let (o, mess) = run(&dir, "column", &mesh, comm);
    assert_eq!(o.diagnostic.to_string(), "NO_TEST_RESU", "{:?}\n{mess}", o.error);
    let resu = std::fs::read_to_string(dir.join("out/column.resu")).unwrap();
    let rows = lips(&resu);
    // Both lips, 12 nodes each (the sub-cells' facets across 2 cells).
    let minus = rows.iter().filter(|r| r.0.starts_with("NM")).count();
    assert_eq!((minus, rows.len()), (12, 24), "{resu}");
    let (dy_lo, dy_hi) = (BIOT * P_LO / E * Y_C, -BIOT * P_HI / E * (4.0 - Y_C));
    for (node, dy, p) in &rows {
        let (dy_ref, p_ref) = if node.starts_with("NM") { (dy_lo, P_LO) } else { (dy_hi, P_HI) };
        assert!((dy - dy_ref).abs() <= 1e-9 * dy_ref.abs(), "{tag} {node}: DY {dy}, analytic {dy_ref}");
        assert!((p - p_ref).abs() <= 1e-9 * p_ref, "{tag} {node}: PRE1 {p}, analytic {p_ref}");
    }
    mess
}

#[test]
fn prescribed_enriched_pressure_loads_the_skeleton() {
    let hydr = format!(
        r#"_F(GROUP_NO="LO", PRE1={P_LO:e}), _F(GROUP_NO="HI", PRE1={P_HI:e}), _F(TOUT="OUI", H1PRE1={:e})"#,
        (P_HI - P_LO) / 2.0
    );
    let mess = run_and_check("prescribed", &scene(&hydr, "1.0"));
    assert!(mess.contains("through the Biot term"), "{mess}");
}

#[test]
fn coupled_flow_stops_at_an_impervious_interface() {
    let hydr = format!(r#"_F(GROUP_MA="BAS", PRE1={P_LO:e}), _F(GROUP_MA="HAUT", PRE1={P_HI:e})"#);
    let mess = run_and_check("coupled", &scene(&hydr, "1.0e10"));
    // The HM driver took the scene: the enriched pressures are solved.
    assert!(mess.contains("X-FEM     : 13 Heaviside sets over 13 nodes"), "{mess}");
    assert!(mess.contains("the flow is solved on the other 15"), "{mess}");
}
