//! The cohesive interface end to end on one QUAD8 cell cut by a horizontal
//! interface Y = 0.3 (issue 5, acceptance point 3): pulled open by a
//! prescribed DY on the top edge, the traction follows σc(1 − δ/δc) once the
//! threshold is passed, vanishes at δc, and the energy dissipated is GC
//! times the interface length; pushed shut, the opening is exactly zero and
//! the traction is the bulk stress. The numbers come from STAT_NON_LINE's
//! per-step interface report in the message file. The pull is repeated on a
//! column of two cells whose common edge is the interface (along a row of
//! nodes: no cell cut).

use crate::common::run_on_box;
use std::path::Path;
use std::process::Command;

const SIGMA_C: f64 = 5.0e5;
const GC: f64 = 9.0e3;
const E: f64 = 5.8e9;

fn scene(ln: &str, delta: f64, instants: &str) -> String {
    format!(
        r#"DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
LN = FORMULE(VALE="{ln}", NOM_PARA=["X", "Y"])
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS, DECOUPE_FACETTE="SOUS_ELEMENTS", CONTACT="MORTAR")
CTX = DEFI_CONTACT(MODELE=MO, FORMULATION="XFEM", ZONE=_F(FISS_MAIT=FISS, INTEGRATION="GAUSS", ORDRE_INT=2,
                   ALGO_CONT="CZM", ALGO_LAGR="VERSION2", RELATION="CZM_LIN_MIX"))
MAT = DEFI_MATERIAU(ELAS=_F(E={E}, NU=0.0), RUPT_FRAG=_F(GC={GC}, SIGM_C={SIGMA_C}, PENA_LAGR=100.0))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=MAT))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_MA="BAS", DX=0.0, DY=0.0), _F(GROUP_MA="HAUT", DX=0.0)))
TIRE = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA="HAUT", DY={delta}))
RAMPE = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 1.0, 1.0))
LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=({instants}))
RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TIRE, FONC_MULT=RAMPE)),
                     CONTACT=CTX, COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LINST),
                     CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10, ITER_GLOB_MAXI=30))
FIN()
"#
    )
}

/// Run the scene on one 1×1 QUAD8 cell cut by Y = 0.3; returns, per step, (λ_n min, λ_n max, w_n min,
/// w_n max, dissipated).
fn run(tag: &str, delta: f64, instants: &str) -> Vec<[f64; 5]> {
    run_on(tag, ("1,1", "1,1"), "Y-0.3", delta, instants)
}

/// Run the scene on a QUAD8 box (`--n`, `--size`) with the level set `ln`.
fn run_on(tag: &str, (n, size): (&str, &str), ln: &str, delta: f64, instants: &str) -> Vec<[f64; 5]> {
    let dir = scratch!(tag);
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", n, size), &scene(ln, delta, instants));
    // The scene has no TEST_* command (this test checks the numbers): NO_TEST_RESU.
    assert!(mess.contains("DIAGNOSTIC JOB : NO_TEST_RESU") && !mess.contains("<F>"), "{status}\n{mess}");
    let _ = std::fs::remove_dir_all(&dir);
    parse(&mess)
}

fn parse(mess: &str) -> Vec<[f64; 5]> {
    let num =
        |s: &str| -> f64 { s.trim().trim_end_matches(',').parse().unwrap_or_else(|_| panic!("not a number: {s}")) };
    mess.lines()
        .filter_map(|l| l.trim().strip_prefix("FISS: lambda_n in ["))
        .map(|r| {
            let (lam, r) = r.split_once("], w_n in [").unwrap();
            let (w, r) = r.split_once("], ").unwrap();
            let e = r.rsplit("dissipated ").next().unwrap();
            let (l0, l1) = lam.split_once(", ").unwrap();
            let (w0, w1) = w.split_once(", ").unwrap();
            [num(l0), num(l1), num(w0), num(w1), num(e)]
        })
        .collect()
}

#[test]
fn opening_follows_the_linear_softening_law_and_dissipates_gc() {
    let delta_c = 2.0 * GC / SIGMA_C;
    // Fine steps up to just past the threshold, then to 1.25 δc.
    let steps = run("open", 1.25 * delta_c, "_F(JUSQU_A=0.002, NOMBRE=4), _F(JUSQU_A=1.0, NOMBRE=45)");
    check_opening(&steps);
}

/// The same pull on a column of two QUAD8 cells whose common edge Y = 0.5 is the interface: no cell is
/// cut, the lower cell carries the facet and the edge's two vertices one packet each (as Code_Aster's
/// `xcface` / `xlagsp` do for an interface along a row of nodes). The law and the energy are the same.
#[test]
fn opening_along_a_row_of_nodes_follows_the_same_law() {
    let delta_c = 2.0 * GC / SIGMA_C;
    let steps = run_on(
        "open_row",
        ("1,2", "1,1"),
        "Y-0.5",
        1.25 * delta_c,
        "_F(JUSQU_A=0.002, NOMBRE=4), _F(JUSQU_A=1.0, NOMBRE=45)",
    );
    check_opening(&steps);
}

/// The checks of a pull to 1.25 δc in 49 steps: rigid below σc, the softening line, no traction after
/// separation, GC dissipated (length 1).
fn check_opening(steps: &[[f64; 5]]) {
    let delta_c = 2.0 * GC / SIGMA_C;
    assert_eq!(steps.len(), 49);
    let mut opened = 0;
    let mut work = 0.0;
    let (mut w_prev, mut l_prev) = (0.0, 0.0);
    for s in steps {
        let [l0, l1, w0, w1, _] = *s;
        // Uniform opening: both packets (left and right edges) agree.
        assert!((l1 - l0).abs() <= 1e-9 * SIGMA_C && (w1 - w0).abs() <= 1e-12, "{s:?}");
        let (l, w) = (l0, w0);
        // Round-off of the solve (the equilibrated LU leaves w ~ 1e-20 where the law is rigid).
        if w.abs() <= 1e-12 * delta_c {
            // Rigid below the threshold (extrinsic law).
            assert!(l <= SIGMA_C * (1.0 + 1e-12), "{s:?}");
        } else if w < delta_c * (1.0 - 1e-9) {
            opened += 1;
            let t = SIGMA_C * (1.0 - w / delta_c);
            assert!((l - t).abs() <= 1e-6 * SIGMA_C, "traction {l} against σc(1 − δ/δc) = {t} at δ = {w}");
        } else {
            assert!(l.abs() <= 1e-6 * SIGMA_C, "traction {l} after full separation (δ = {w})");
        }
        work += 0.5 * (l + l_prev) * (w - w_prev);
        (w_prev, l_prev) = (w, l);
    }
    assert!(opened >= 30, "{opened} steps on the softening branch");
    // Dissipated energy: GC × length 1, from the internal variables and from ∫λ dw.
    let last = steps.last().unwrap()[4];
    assert!((last - GC).abs() <= 1e-9 * GC, "dissipated {last}");
    assert!((work - GC).abs() <= 2e-3 * GC, "∫λ dw = {work}");
}

#[test]
fn compression_keeps_the_interface_shut() {
    let d = -1.0e-4;
    let steps = run("shut", d, "_F(JUSQU_A=1.0, NOMBRE=2)");
    assert_eq!(steps.len(), 2);
    for (k, s) in steps.iter().enumerate() {
        let [l0, l1, w0, w1, e] = *s;
        // w_n = 0 to round-off (1e-12 of δc), no energy; λ_n = σ_yy = E ε_yy (ν = 0).
        let delta_c = 2.0 * GC / SIGMA_C;
        assert!(w0.abs() <= 1e-12 * delta_c && w1.abs() <= 1e-12 * delta_c && e == 0.0, "{s:?}");
        let sigma = E * d * (k + 1) as f64 / 2.0;
        assert!((l0 - sigma).abs() <= 1e-9 * sigma.abs() && (l1 - sigma).abs() <= 1e-9 * sigma.abs(), "{s:?}");
    }
}

#[test]
fn the_test_scene_is_well_formed() {
    // The scene text itself passes the catalogue (guards the two tests above).
    let dir = scratch!("check");
    let comm = dir.join("one.comm");
    std::fs::write(&comm, scene("Y-0.3", 1e-3, "_F(JUSQU_A=1.0, NOMBRE=1)")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_aster")).arg("check").arg(&comm).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    let _ = std::fs::remove_dir_all(Path::new(&dir));
}
