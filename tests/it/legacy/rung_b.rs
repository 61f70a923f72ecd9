//! Rung (b) commands end to end on small generated meshes: MODI_MAILLAGE
//! ORIE_PEAU, AFFE_CHAR_MECA FACE_IMPO (DX/DY, DNOR) and MODI_REPERE.
//!
//! Each scene is a homogeneous stress state whose displacement and stress
//! are known in closed form; the expected numbers are computed here (plane
//! stress, uniaxial) and written into the command file's TEST_RESU lines, so
//! a run with every check OK means the stages agree with the analytic values.

use crate::common::{resu_rows, run_on_box};
use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::{CellType, Mesh};
use aster::runner::export::Dir;
use aster::runner::{self, Outcome, RunOptions};
use std::path::Path;

const E: f64 = 2.0e5;
const NU: f64 = 0.3;

/// Write `mesh` and `comm`, run the command file with the mesh on unit 20.
fn run(dir: &Path, name: &str, mesh: &Mesh, comm: &str) -> Outcome {
    let mesh_path = dir.join(format!("{name}.med"));
    med::write_mesh(&mesh_path, mesh, "MAIL").unwrap();
    let comm_path = dir.join(format!("{name}.comm"));
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    runner::run_comm(&comm_path, &opts)
}

/// Every check OK: each TEST_RESU occurrence records a NON_REGRESSION and an
/// ANALYTIQUE verdict, so `checks` occurrences give twice as many records.
fn assert_all_ok(o: &Outcome, checks: usize) {
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    assert_eq!(o.ok_count(), 2 * checks, "{mess}");
    assert_eq!(o.nook_count(), 0, "{mess}");
}

/// The node at `x` (within 1e-12).
fn node_at(mesh: &Mesh, x: [f64; 2]) -> usize {
    (0..mesh.coords.len())
        .find(|&n| (mesh.coords[n][0] - x[0]).abs() < 1e-12 && (mesh.coords[n][1] - x[1]).abs() < 1e-12)
        .unwrap_or_else(|| panic!("no node at {x:?}"))
}

/// One TEST_RESU occurrence on node group C.
fn check(field: &str, cmp: &str, v: f64) -> String {
    let crit = if v.abs() < 1e-12 { "CRITERE='ABSOLU', ORDRE_GRANDEUR=1.0, " } else { "" };
    format!(
        "        _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='{field}', GROUP_NO='C', NOM_CMP='{cmp}', {crit}\
         VALE_CALC={v:e}, VALE_REFE={v:e}, REFERENCE='ANALYTIQUE', PRECISION=1.0e-9),\n"
    )
}

fn test_resu(result: &str, checks: &[(&str, &str, f64)]) -> String {
    let body: String = checks.iter().map(|(f, c, v)| check(f, c, *v)).collect();
    format!("TEST_RESU(RESU=(\n{}))\n", body.replace("RESULTAT=R,", &format!("RESULTAT={result},")))
}

/// Reverse the node order of every cell of a group (SEG2/SEG3: ends swapped).
fn reverse_group(mesh: &mut Mesh, group: &str) {
    for &c in &mesh.cell_groups[group].clone() {
        let v = &mut mesh.cells[c];
        match mesh.cell_types[c] {
            CellType::Seg2 | CellType::Seg3 => v.swap(0, 1),
            CellType::Quad4 => v.reverse(),
            CellType::Quad8 => *v = vec![v[0], v[3], v[2], v[1], v[7], v[6], v[5], v[4]],
            t => panic!("no reversal for {}", t.name()),
        }
    }
}

/// A unit square in plane stress, compressed by a pressure P on DROITE,
/// held by rollers on BAS and GAUCHE: σxx = -P, ux(x) = -P x / E,
/// uy(y) = ν P y / E. The pressure edge is given reversed (normal pointing
/// in); ORIE_PEAU turns it back. MODI_REPERE then expresses the stress at
/// C = (1, 1) in the cylindrical frame of origin (-1, -1): e_r = (1, 1)/√2,
/// so σrr = σθθ = -P/2 and σrθ = e_r·σ·e_θ = +P/2 (e_θ = (-1, 1)/√2).
fn pressure_scene(orient: bool) -> (Mesh, String) {
    let p = 10.0;
    let mut mesh = box_mesh(CellType::Quad8, &[2, 3], &[1.0, 1.0]).unwrap();
    reverse_group(&mut mesh, "DROITE");
    let c = node_at(&mesh, [1.0, 1.0]);
    mesh.node_groups.insert("C".into(), vec![c]);
    let orie =
        if orient { "MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU='DROITE'))\n" } else { "" };
    let sign = if orient { -1.0 } else { 1.0 };
    let mut comm = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n{orie}\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={E:e}, NU={NU}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_MA='BAS', DY=0.0), _F(GROUP_MA='GAUCHE', DX=0.0)),\n\
                             PRES_REP=_F(GROUP_MA='DROITE', PRES={p}))\n\
         RESU = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, CONTRAINTE='SIGM_NOEU')\n"
    );
    comm += &test_resu(
        "RESU",
        &[
            ("DEPL", "DX", sign * p / E),
            ("DEPL", "DY", -sign * NU * p / E),
            ("SIGM_NOEU", "SIXX", sign * p),
            ("SIGM_NOEU", "SIYY", 0.0),
        ],
    );
    if orient {
        comm += "CYL = MODI_REPERE(RESULTAT=RESU, NUME_ORDRE=1, REPERE='CYLINDRIQUE',\n\
                 MODI_CHAM=_F(NOM_CHAM='SIGM_NOEU', TYPE_CHAM='TENS_2D'), AFFE=_F(ORIGINE=(-1.0, -1.0), TOUT='OUI'))\n";
        comm += &test_resu(
            "CYL",
            &[
                ("SIGM_NOEU", "SIXX", -p / 2.0),
                ("SIGM_NOEU", "SIYY", 0.0),
                ("SIGM_NOEU", "SIZZ", -p / 2.0),
                ("SIGM_NOEU", "SIXY", p / 2.0),
            ],
        );
    }
    comm += "FIN()\n";
    (mesh, comm)
}

#[test]
fn orie_peau_turns_a_reversed_pressure_edge_out() {
    let dir = scratch!("orie2d");
    let (mesh, comm) = pressure_scene(true);
    let o = run(&dir, "press", &mesh, &comm);
    assert_all_ok(&o, 8);
    // Without ORIE_PEAU the reversed edge pulls: the same numbers with the other sign.
    let (mesh, comm) = pressure_scene(false);
    let o = run(&dir, "press_rev", &mesh, &comm);
    assert_all_ok(&o, 4);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A unit cube compressed by P on ZMAX (faces given reversed), held by
/// rollers on XMIN, YMIN, ZMIN: uz(1) = -P/E, ux(1) = uy(1) = ν P / E.
#[test]
fn orie_peau_3d_on_reversed_faces() {
    let dir = scratch!("orie3d");
    let p = 7.0;
    let mut mesh = box_mesh(CellType::Hexa20, &[1, 2, 1], &[1.0, 1.0, 1.0]).unwrap();
    reverse_group(&mut mesh, "ZMAX");
    let c = (0..mesh.coords.len()).find(|&n| mesh.coords[n] == [1.0, 1.0, 1.0]).unwrap();
    mesh.node_groups.insert("C".into(), vec![c]);
    let mut comm = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU=('ZMAX', 'XMAX')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={E:e}, NU={NU}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_MA='XMIN', DX=0.0), _F(GROUP_MA='YMIN', DY=0.0),\n\
                             _F(GROUP_MA='ZMIN', DZ=0.0)), PRES_REP=_F(GROUP_MA='ZMAX', PRES={p}))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n"
    );
    comm += &test_resu("R", &[("DEPL", "DX", NU * p / E), ("DEPL", "DY", NU * p / E), ("DEPL", "DZ", -p / E)]);
    comm += "FIN()\n";
    let o = run(&dir, "cube", &mesh, &comm);
    assert_all_ok(&o, 3);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The unit square turned by θ = 30°: rollers (DNOR = 0) on BAS and
/// GAUCHE, a normal displacement DNOR = D on DROITE. In the turned frame
/// (x', y') the state is uniaxial: u' = (D x', -ν D y'), σ' = E D e'x ⊗ e'x.
/// At C (x', y') = (1, 1): u = D e'x - ν D e'y, σxx = E D cos²θ,
/// σyy = E D sin²θ, σxy = E D sinθ cosθ. MODI_REPERE UTILISATEUR with
/// ANGL_NAUT = 30 gives back σ'xx = E D, σ'yy = σ'xy = 0 and u' = (D, -ν D).
#[test]
fn face_impo_dnor_on_inclined_faces_and_modi_repere() {
    let dir = scratch!("dnor");
    let d = 1.0e-3;
    let th = 30f64.to_radians();
    let (s, c) = th.sin_cos();
    let mut mesh = box_mesh(CellType::Quad8, &[3, 2], &[1.0, 1.0]).unwrap();
    let corner = node_at(&mesh, [1.0, 1.0]);
    for x in mesh.coords.iter_mut() {
        *x = [c * x[0] - s * x[1], s * x[0] + c * x[1], 0.0];
    }
    mesh.node_groups.insert("C".into(), vec![corner]);
    let mut comm = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={E:e}, NU={NU}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, FACE_IMPO=(_F(GROUP_MA='BAS', DNOR=0.0), _F(GROUP_MA='GAUCHE', DNOR=0.0),\n\
                             _F(GROUP_MA='DROITE', DNOR={d:e})))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_NOEU')\n"
    );
    let sig = E * d;
    comm += &test_resu(
        "R",
        &[
            ("DEPL", "DX", d * c + NU * d * s),
            ("DEPL", "DY", d * s - NU * d * c),
            ("SIGM_NOEU", "SIXX", sig * c * c),
            ("SIGM_NOEU", "SIYY", sig * s * s),
            ("SIGM_NOEU", "SIXY", sig * s * c),
        ],
    );
    comm += "RL = MODI_REPERE(RESULTAT=R, REPERE='UTILISATEUR', AFFE=_F(ANGL_NAUT=30.0, TOUT='OUI'),\n\
             MODI_CHAM=(_F(NOM_CHAM='SIGM_NOEU', TYPE_CHAM='TENS_2D'), _F(NOM_CHAM='DEPL', TYPE_CHAM='VECT_2D')))\n";
    comm += &test_resu(
        "RL",
        &[
            ("SIGM_NOEU", "SIXX", sig),
            ("SIGM_NOEU", "SIYY", 0.0),
            ("SIGM_NOEU", "SIXY", 0.0),
            ("DEPL", "DX", d),
            ("DEPL", "DY", -NU * d),
        ],
    );
    comm += "FIN()\n";
    let o = run(&dir, "dnor", &mesh, &comm);
    assert_all_ok(&o, 10);
    let _ = std::fs::remove_dir_all(&dir);
}

/// FACE_IMPO DX/DY (AFFE_CHAR_MECA_F with a function of Y): a linear
/// horizontal displacement ux = a y imposed on GAUCHE and DROITE of a
/// square in plane stress with uy = 0 on BAS; the solution is the simple
/// shear ux = a y: σxy = E a / (2 (1 + ν)), uy = 0.
#[test]
fn face_impo_components_with_a_function() {
    let dir = scratch!("faceimpo");
    let a = 2.0e-3;
    let mut mesh = box_mesh(CellType::Quad4, &[2, 2], &[1.0, 1.0]).unwrap();
    let c = node_at(&mesh, [1.0, 1.0]);
    mesh.node_groups.insert("C".into(), vec![c]);
    let mut comm = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={E:e}, NU={NU}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         FX = DEFI_FONCTION(NOM_PARA='Y', VALE=(0.0, 0.0, 1.0, {a:e}), PROL_DROITE='LINEAIRE', PROL_GAUCHE='LINEAIRE')\n\
         ZERO = DEFI_CONSTANTE(VALE=0.0)\n\
         CH = AFFE_CHAR_MECA_F(MODELE=MO, FACE_IMPO=(_F(GROUP_MA=('GAUCHE', 'DROITE', 'HAUT', 'BAS'), DX=FX, DY=ZERO),))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_NOEU')\n"
    );
    comm += &test_resu(
        "R",
        &[
            ("DEPL", "DX", a),
            ("DEPL", "DY", 0.0),
            ("SIGM_NOEU", "SIXY", E * a / (2.0 * (1.0 + NU))),
            ("SIGM_NOEU", "SIXX", 0.0),
        ],
    );
    comm += "FIN()\n";
    let o = run(&dir, "shear", &mesh, &comm);
    assert_all_ok(&o, 4);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Located errors: a skin edge between two cells with no side named, a
/// MODI_MAILLAGE keyword we do not implement, a FACE_IMPO component we do
/// not implement.
#[test]
fn located_errors() {
    let dir = scratch!("errors");
    let mut mesh = box_mesh(CellType::Quad4, &[2, 1], &[2.0, 1.0]).unwrap();
    let (a, b) = (node_at(&mesh, [1.0, 0.0]), node_at(&mesh, [1.0, 1.0]));
    mesh.cells.push(vec![a, b]);
    mesh.cell_types.push(CellType::Seg2);
    mesh.cell_names.push(format!("M{}", mesh.cells.len()));
    mesh.cell_groups.insert("MID".into(), vec![mesh.cells.len() - 1]);
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n";
    let cases = [
        ("MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU='MID'))\n", "GROUP_MA_INTERNE", ":3:"),
        (
            "MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ROTATION=_F(POIN_1=(0.0, 0.0), ANGLE=10.0))\n",
            "ROTATION: not supported yet",
            ":3:",
        ),
        (
            "MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
             CH = AFFE_CHAR_MECA(MODELE=MO, FACE_IMPO=_F(GROUP_MA='BAS', DRNOR=0.0))\n",
            "FACE_IMPO/DRNOR: not supported yet",
            ":4:",
        ),
    ];
    for (i, (body, msg, line)) in cases.iter().enumerate() {
        let o = run(&dir, &format!("err{i}"), &mesh, &format!("{head}{body}FIN()\n"));
        let err = o.error.clone().unwrap_or_default();
        assert_eq!(o.diagnostic, "<F>_ERROR", "{err}");
        assert!(err.contains(msg), "{err}");
        assert!(err.contains(line), "{err}");
    }
    // With the side named, the run goes through.
    let left: Vec<usize> = (0..mesh.cells.len())
        .filter(|&c| mesh.cell_types[c] == CellType::Quad4 && mesh.cells[c].iter().all(|&n| mesh.coords[n][0] <= 1.0))
        .collect();
    assert_eq!(left.len(), 1);
    mesh.cell_groups.insert("LEFT".into(), left);
    let o = run(
        &dir,
        "side",
        &mesh,
        &format!(
            "{head}MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU='MID', GROUP_MA_INTERNE='LEFT'))\nFIN()\n"
        ),
    );
    assert!(o.error.is_none(), "{:?}", o.error);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Three ways to clamp the bottom of a square pulled sideways and up at its top: DDL_IMPO DX = DY = 0,
/// DDL_IMPO LIAISON='ENCASTRE', and FACE_IMPO DNOR = DTAN = 0 (the normal and the tangent of the edge
/// blocked). The displacements of the top agree to round-off; DETRUIRE OBJET removes the concepts whose
/// names hold its string, and DTAN on a 3D model stops by name.
#[test]
fn clamping_by_components_encastre_and_dnor_dtan_agree() {
    let dir = scratch!("clamp");
    std::fs::create_dir_all(&dir).unwrap();
    let mut comm = String::from(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=2.0e5, NU=0.3))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         PULL = AFFE_CHAR_MECA(MODELE=MO, FORCE_CONTOUR=_F(GROUP_MA='HAUT', FX=30.0, FY=50.0))\n\
         CA = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='BAS', DX=0.0, DY=0.0))\n\
         CB = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='BAS', LIAISON='ENCASTRE'))\n\
         CC = AFFE_CHAR_MECA(MODELE=MO, FACE_IMPO=_F(GROUP_MA='BAS', DNOR=0.0, DTAN=0.0))\n\
         XXTMP = DEFI_CONSTANTE(VALE=1.0)\n\
         DETRUIRE(CONCEPT=_F(NOM=XXTMP), OBJET=_F(CHAINE='XXT'))\n",
    );
    for k in ["A", "B", "C"] {
        comm += &format!(
            "R{k} = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=PULL), _F(CHARGE=C{k})))\n\
             T{k} = POST_RELEVE_T(ACTION=_F(OPERATION='EXTRACTION', INTITULE='{k}', RESULTAT=R{k}, NOM_CHAM='DEPL',\n\
                                  GROUP_NO='HAUT', NOM_CMP=('DX', 'DY')))\n\
             IMPR_TABLE(TABLE=T{k}, FORMAT_R='E20.13')\n"
        );
    }
    comm += "FIN()\n";
    let (status, mess, resu) = run_on_box(&dir, ("QUAD8", "3,3", "1,1"), &comm);
    assert!(status.success(), "{mess}");
    let rows: Vec<_> = ["A", "B", "C"].iter().map(|k| resu_rows(&resu, k)).collect();
    assert!(rows[0].len() >= 7, "{resu}");
    let num = |r: &std::collections::BTreeMap<String, String>, c: &str| r[c].parse::<f64>().unwrap();
    let scale = rows[0].iter().map(|r| num(r, "DY").abs()).fold(0.0, f64::max);
    assert!(scale > 1e-5, "{resu}");
    for other in &rows[1..] {
        assert_eq!(other.len(), rows[0].len());
        for (a, b) in rows[0].iter().zip(other) {
            for c in ["DX", "DY"] {
                assert!((num(a, c) - num(b, c)).abs() <= 1e-10 * scale, "{c}: {a:?} vs {b:?}");
            }
        }
    }
    // XXTMP is gone: using it is a NameError.
    let (status, mess, _) = run_on_box(
        &dir,
        ("QUAD4", "1,1", "1,1"),
        "DEBUT()\nXXTMP = DEFI_CONSTANTE(VALE=1.0)\nK = DEFI_CONSTANTE(VALE=2.0)\n\
         DETRUIRE(CONCEPT=_F(NOM=K), OBJET=_F(CHAINE='XXT'))\nv = XXTMP(0.0)\nFIN()\n",
    );
    assert!(!status.success() && mess.contains("XXTMP"), "{mess}");
    let (status, mess, _) = run_on_box(
        &dir,
        ("HEXA8", "1,1,1", "1,1,1"),
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
         CC = AFFE_CHAR_MECA(MODELE=MO, FACE_IMPO=_F(GROUP_MA='ZMIN', DTAN=0.0))\nFIN()\n",
    );
    assert!(!status.success() && mess.contains("DTAN is for plane models"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// PRES_REP CISA_2D: the shear τ along the outward-turned edges of a square (its tangent `(−n_y, n_x)`, so
/// −τ on BAS and HAUT, +τ on GAUCHE and DROITE) holds it in simple shear: with the bottom corners held
/// (DX = DY = 0, and DY = 0), `u = (τ y / G, 0)` and σxy = τ everywhere.
#[test]
fn pres_rep_cisa_2d_shears_a_square() {
    let dir = scratch!("cisa");
    std::fs::create_dir_all(&dir).unwrap();
    let (e, nu, tau) = (2.0e5, 0.3, 40.0);
    let g = e / (2.0 * (1.0 + nu));
    let ux = tau / g;
    let comm = format!(
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=(_F(NOM='O', INTERSEC=('BAS', 'GAUCHE')),\n\
                         _F(NOM='P', INTERSEC=('BAS', 'DROITE')), _F(NOM='Q', INTERSEC=('HAUT', 'GAUCHE'))))\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU=('BAS', 'DROITE', 'HAUT', 'GAUCHE')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={e:e}, NU={nu}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='O', DX=0.0, DY=0.0), _F(GROUP_NO='P', DY=0.0)),\n\
                             PRES_REP=(_F(GROUP_MA=('BAS', 'HAUT'), CISA_2D={m:e}), _F(GROUP_MA=('GAUCHE', 'DROITE'), CISA_2D={tau:e})))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_NOEU')\n\
         TEST_RESU(RESU=(\n\
           _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOM_CMP='DX', GROUP_NO='Q', VALE_CALC={ux:e}, VALE_REFE={ux:e},\n\
              REFERENCE='ANALYTIQUE', PRECISION=1e-9),\n\
           _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOM_CMP='DY', TYPE_TEST='MAX', VALE_CALC=0.0, VALE_REFE=0.0,\n\
              REFERENCE='ANALYTIQUE', CRITERE='ABSOLU', PRECISION=1e-12),\n\
           _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='SIGM_NOEU', NOM_CMP='SIXY', TYPE_TEST='MIN', VALE_CALC={tau:e},\n\
              VALE_REFE={tau:e}, REFERENCE='ANALYTIQUE', PRECISION=1e-9),\n\
           _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='SIGM_NOEU', NOM_CMP='SIXY', TYPE_TEST='MAX', VALE_CALC={tau:e},\n\
              VALE_REFE={tau:e}, REFERENCE='ANALYTIQUE', PRECISION=1e-9)))\nFIN()\n",
        m = -tau
    );
    let (status, mess, _) = run_on_box(&dir, ("QUAD8", "2,2", "1,1"), &comm);
    assert!(status.success(), "{mess}");
    assert_eq!(mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count(), 4, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Code_Aster's overloading rule within one load: a node's component prescribed by several occurrences
/// takes the last value (DDL_IMPO on BAS, then DX again on its corner); and TYPE_TEST without NOM_CMP runs
/// over every component.
#[test]
fn the_last_occurrence_prescribing_a_component_wins() {
    let dir = scratch!("surcharge");
    std::fs::create_dir_all(&dir).unwrap();
    let comm = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(NOM='O', INTERSEC=('BAS', 'GAUCHE')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=2.0e5, NU=0.3))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='BAS', DX=0.0, DY=0.0), _F(GROUP_NO='O', DX=1.0e-3)))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         TEST_RESU(RESU=(_F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', NOM_CMP='DX', GROUP_NO='O', VALE_CALC=1.0e-3,\n\
                            VALE_REFE=1.0e-3, REFERENCE='ANALYTIQUE', PRECISION=1e-12),\n\
                         _F(RESULTAT=R, NUME_ORDRE=1, NOM_CHAM='DEPL', TYPE_TEST='MAX', VALE_CALC=1.0e-3,\n\
                            VALE_REFE=1.0e-3, REFERENCE='ANALYTIQUE', PRECISION=1e-12)))\nFIN()\n";
    let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,2", "1,1"), comm);
    assert!(status.success(), "{mess}");
    assert_eq!(mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count(), 2, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}
