//! MACR_LIGN_COUPE on a scene whose answer is known everywhere: a 2 × 1 plate of 4 × 2 QUAD4 cells in
//! plane stress, every node displaced by u = (ε x, 0). The displacement is linear, so its values
//! interpolated at any point of a line are exact (DX = ε x), and the stress is homogeneous,
//! σxx = E ε / (1 − ν²), σyy = ν σxx, σxy = 0.
//!
//! Checked in the table, through TEST_TABLE: DX along an oblique segment; a segment that starts outside
//! the plate (its first point is left out and ABSC_CURV starts at the first point kept); SIGM_ELNO in
//! the local frame of a segment at 45° (the tensor turned: σ'xx = σ'yy = (σxx + σyy) / 2, σ'xy =
//! (σyy − σxx) / 2) and its invariants; OPERATION='MOYENNE' (the mean and the linear part's variation of DX); a group of
//! nodes; a field (CHAM_GD) with MODELE; a refusal by name.

use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};

const E: f64 = 2.0e5;
const NU: f64 = 0.25;
const EPS: f64 = 1.0e-3;

fn sxx() -> f64 {
    E * EPS / (1.0 - NU * NU)
}

/// Run the scene with `body` after the solution (R, with SIGM_ELNO) and return (diagnostic, OK count,
/// message file).
fn run(tag: &str, body: &str) -> (String, usize, String) {
    let dir = scratch!(tag);
    let mut mesh = box_mesh(CellType::Quad4, &[4, 2], &[2.0, 1.0]).unwrap();
    let top: Vec<usize> = (0..mesh.nnodes()).filter(|&n| (mesh.coords[n][1] - 1.0).abs() < 1e-12).collect();
    assert_eq!(top.len(), 5);
    mesh.node_groups.insert("TOP".into(), top);
    let mesh_path = dir.join("plate.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={E:e}, NU={NU}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         UX = FORMULE(VALE='{EPS:e}*X', NOM_PARA='X')\n\
         ZERO = DEFI_CONSTANTE(VALE=0.0)\n\
         CH = AFFE_CHAR_MECA_F(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', DX=UX, DY=ZERO))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_ELNO')\n\
         {body}\
         FIN()\n"
    );
    let comm_path = dir.join("coupe.comm");
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    let diag = if o.diagnostic == "OK" { "OK".to_string() } else { format!("{} {:?}", o.diagnostic, o.error) };
    let n = o.ok_count();
    let _ = std::fs::remove_dir_all(&dir);
    (diag, n, mess)
}

/// A TEST_TABLE of `para` reduced by `ty` against `v`, ANALYTIQUE.
fn check(table: &str, para: &str, ty: &str, v: f64, filtre: &str) -> String {
    format!(
        "TEST_TABLE(TABLE={table}, NOM_PARA='{para}', TYPE_TEST='{ty}', VALE_CALC={v:e}, VALE_REFE={v:e},\n\
         REFERENCE='ANALYTIQUE', PRECISION=1.0e-9, CRITERE='ABSOLU'{filtre})\n"
    )
}

#[test]
fn node_values_along_segments_are_interpolated_exactly() {
    let len = (1.6f64 * 1.6 + 0.6 * 0.6).sqrt();
    let mut body = String::from(
        "T1 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='DEPL', LIGN_COUPE=_F(NB_POINTS=5, COOR_ORIG=(0.1, 0.3),\n\
         COOR_EXTR=(1.7, 0.9), INTITULE='OBLIQUE', NOM_CMP=('DX', 'DY')))\n\
         T2 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='DEPL', LIGN_COUPE=_F(NB_POINTS=5, COOR_ORIG=(-0.5, 0.5),\n\
         COOR_EXTR=(1.5, 0.5), NOM_CMP='DX'))\n",
    );
    // Σ ε x over x = 0.1, 0.5, 0.9, 1.3, 1.7; DY is 0; the abscissa ends at the segment's length.
    body += &check("T1", "DX", "SOMM", EPS * 4.5, "");
    body += &check("T1", "DY", "SOMM_ABS", 0.0, "");
    body += &check("T1", "ABSC_CURV", "MAX", len, "");
    body += &check("T1", "DX", "SOMM", EPS * 1.3, ", FILTRE=_F(NOM_PARA='COOR_X', VALE=1.3)");
    // The first point (x = -0.5) lies outside: 4 rows, x = 0 .. 1.5, ABSC_CURV from 0 to 1.5.
    body += &check("T2", "DX", "SOMM", EPS * 3.0, "");
    body += &check("T2", "ABSC_CURV", "MAX", 1.5, "");
    body += &check("T2", "COOR_X", "MIN", 0.0, "");
    let (diag, ok, mess) = run("segments", &body);
    assert_eq!(diag, "OK", "{mess}");
    assert_eq!(ok, 12, "{mess}");
    assert!(mess.contains("<POST0_8>"), "the point left out is reported: {mess}");
}

#[test]
fn stresses_in_the_local_frame_moyenne_groups_and_fields() {
    let (sx, sy) = (sxx(), NU * sxx());
    let mut body = String::from(
        "T3 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='SIGM_ELNO', LIGN_COUPE=_F(NB_POINTS=4, COOR_ORIG=(0.2, 0.1),\n\
         COOR_EXTR=(0.9, 0.8), REPERE='LOCAL', VECT_Y=(-1.0, 1.0), NOM_CMP=('SIXX', 'SIYY', 'SIXY')))\n\
         T4 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='DEPL', LIGN_COUPE=_F(NB_POINTS=3, COOR_ORIG=(0.0, 0.5),\n\
         COOR_EXTR=(2.0, 0.5), OPERATION='MOYENNE', NOM_CMP='DX'))\n\
         T5 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='DEPL', LIGN_COUPE=_F(TYPE='GROUP_NO', GROUP_NO='TOP',\n\
         NOM_CMP='DX'))\n\
         U = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', NUME_ORDRE=1)\n\
         T7 = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='SIGM_ELNO', LIGN_COUPE=_F(NB_POINTS=3, COOR_ORIG=(0.1, 0.2),\n\
         COOR_EXTR=(1.9, 0.8), INVARIANT='OUI'))\n\
         T6 = MACR_LIGN_COUPE(CHAM_GD=U, MODELE=MO, LIGN_COUPE=_F(NB_POINTS=2, COOR_ORIG=(0.25, 0.25),\n\
         COOR_EXTR=(1.75, 0.75), NOM_CMP='DX', INTITULE='CHAMP'))\n",
    );
    body += &check("T3", "SIXX", "MAX", 0.5 * (sx + sy), "");
    body += &check("T3", "SIYY", "MIN", 0.5 * (sx + sy), "");
    body += &check("T3", "SIXY", "MAX", 0.5 * (sy - sx), "");
    // DX = ε x over [0, 2]: mean ε, variation 2 ε, ends 0 and 2 ε.
    body += &check("T4", "DX", "SOMM", EPS, ", FILTRE=_F(NOM_PARA='QUANTITE', VALE_K='MOMENT_0')");
    body += &check("T4", "DX", "SOMM", 2.0 * EPS, ", FILTRE=_F(NOM_PARA='QUANTITE', VALE_K='MOMENT_1')");
    body += &check("T4", "DX", "SOMM", 2.0 * EPS, ", FILTRE=_F(NOM_PARA='QUANTITE', VALE_K='MOYE_EXT')");
    // The top nodes x = 0, 0.5, .., 2: Σ ε x = 5 ε; along the top ABSC_CURV ends at 2.
    body += &check("T5", "DX", "SOMM", 5.0 * EPS, "");
    body += &check("T5", "ABSC_CURV", "MAX", 2.0, "");
    body += &check("T6", "DX", "SOMM", EPS * 2.0, "");
    // The plane stress state (σxx, σyy, 0): its invariants at each of the 3 points.
    body += &check("T7", "VMIS", "MAX", (sx * sx - sx * sy + sy * sy).sqrt(), "");
    body += &check("T7", "TRESCA", "MIN", sx, "");
    body += &check("T7", "TRACE", "SOMM", 3.0 * (sx + sy), "");
    body += &check("T6", "INST", "MAX", 0.0, "");
    let (diag, ok, mess) = run("frames", &body);
    assert_eq!(diag, "OK", "{mess}");
    assert_eq!(ok, 25, "{mess}");
}

#[test]
fn what_is_not_computed_is_refused_by_name() {
    let (diag, _, mess) = run(
        "refused",
        "T = MACR_LIGN_COUPE(RESULTAT=R, NOM_CHAM='SIGM_ELNO', LIGN_COUPE=_F(NB_POINTS=3, COOR_ORIG=(0.0, 0.5),\n\
         COOR_EXTR=(2.0, 0.5), ELEM_PRINCIPAUX='OUI'))\n",
    );
    assert!(diag.contains("ELEM_PRINCIPAUX") && diag.contains("not supported"), "{diag}\n{mess}");
}
