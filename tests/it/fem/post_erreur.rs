//! POST_ERREUR against norms computed by hand: on one cell (the displacement L2 norm, the energy norm with
//! Code_Aster's σzz of plane strain, the contact-pressure norm on a skin) and on a patch of cells solved
//! by MECA_STATIQUE (exact solution: the difference vanishes; the reference is the integral of the
//! analytic field over the volume and over a face). Every number is checked by TEST_TABLE in the command
//! file, at 1e-12 relative (or absolute for the vanishing differences).

use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};

/// Run `body` (between DEBUT and FIN) on a box mesh; every check must be OK and there must be `checks` of
/// them (a TEST_TABLE with VALE_CALC and VALE_REFE prints a NON_REGRESSION and an ANALYTIQUE line; a
/// NON_REGRESSION line of a zero value is skipped, as in Code_Aster).
fn run(tag: &str, cell: CellType, n: &[usize], size: &[f64], body: &str, checks: usize) {
    let dir = scratch!(tag);
    let mesh = box_mesh(cell, n, size).unwrap();
    let mesh_path = dir.join("box.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let comm = format!("DEBUT()\nMA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n{body}FIN()\n");
    let comm_path = dir.join("erreur.comm");
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    assert_eq!(o.ok_count(), checks, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// TEST_TABLE of one cell of a POST_ERREUR table.
fn check(table: &str, para: &str, group: &str, value: f64) -> String {
    let crit = if value == 0.0 { "CRITERE='ABSOLU', PRECISION=1.0e-12" } else { "PRECISION=1.0e-12" };
    format!(
        "TEST_TABLE(TABLE={table}, NOM_PARA='{para}', FILTRE=_F(NOM_PARA='GROUP_MA', VALE_K='{group}'),\n\
         VALE_CALC={value:e}, VALE_REFE={value:e}, REFERENCE='ANALYTIQUE', {crit})\n"
    )
}

#[test]
fn one_cell_displacement_and_energy_norms() {
    // The unit square, one QUAD4, in plane strain (E = 1000, ν = 0.25), every node displaced by
    // u_h = (0.1 x, 0.2 y), which the cell represents exactly.
    //
    // DEPL_RELA against u_ref = (0.1 x + 0.05 x y, 0.2 y): the difference is (−0.05 x y, 0), so
    // DIFFERENCE² = 0.0025 ∫x²y² = 0.0025/9, and REFERENCE² = ∫(0.1x + 0.05xy)² + (0.2y)²
    // = 0.01/3 + 0.01/6 + 0.0025/9 + 0.04/3 = 0.335/18 (FPG4 integrates these exactly).
    let diff = 0.05 / 3.0;
    let refe = (0.335f64 / 18.0).sqrt();
    // ENER_RELA against σ_ref = (SIXX, SIYY) = (200, 280) and no SIZZ. The plane-strain stress of u_h is
    // λ = μ = 400: σxx = 1200·0.1 + 400·0.2 = 200, σyy = 400·0.1 + 1200·0.2 = 280, σzz = λ(0.3) = 120.
    // Only σzz differs, and Code_Aster counts it: DIFFERENCE = ½ 120²/E = 7.2; REFERENCE =
    // ½ (200² + 280² − 2ν·200·280)/E = 45.2; ERREUR RELATIVE = √(7.2/45.2).
    let body = format!(
        "MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.25))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         UX = FORMULE(VALE='0.1*X', NOM_PARA=['X', 'Y'])\n\
         UY = FORMULE(VALE='0.2*Y', NOM_PARA=['X', 'Y'])\n\
         CH = AFFE_CHAR_MECA_F(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', DX=UX, DY=UY))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         U = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='NOEU_DEPL_R', RESULTAT=R, NOM_CHAM='DEPL', NUME_ORDRE=1)\n\
         S = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='ELGA_SIEF_R', RESULTAT=R, NOM_CHAM='SIEF_ELGA', NUME_ORDRE=1)\n\
         RX = FORMULE(VALE='0.1*X + 0.05*X*Y', NOM_PARA=['X', 'Y'])\n\
         TL2 = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=U, DX=RX, DY=UY)\n\
         IMPR_TABLE(TABLE=TL2)\n\
         SXX = FORMULE(VALE='200.0', NOM_PARA=['X', 'Y'])\n\
         SYY = FORMULE(VALE='280.0', NOM_PARA=['X', 'Y'])\n\
         TEN = POST_ERREUR(OPTION='ENER_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=S, CHAM_MATER=CM,\n\
                           DEFORMATION='PETIT', SIXX=SXX, SIYY=SYY)\n\
         IMPR_TABLE(TABLE=TEN)\n\
         {}{}{}{}{}{}{}",
        check("TL2", "DIFFERENCE", "SURFACE", diff),
        check("TL2", "REFERENCE", "TOTAL", refe),
        check("TL2", "ERREUR RELATIVE", "TOTAL", diff / refe),
        check("TEN", "DIFFERENCE", "SURFACE", 7.2),
        check("TEN", "REFERENCE", "TOTAL", 45.2),
        check("TEN", "ERREUR RELATIVE", "TOTAL", (7.2f64 / 45.2).sqrt()),
        check("TEN", "DIFFERENCE", "TOTAL", 7.2),
    );
    run("one_cell", CellType::Quad4, &[1, 1], &[1.0, 1.0], &body, 14);
}

#[test]
fn patch_of_cells_solved_by_meca_statique() {
    // A 2 × 1 × 1 block of 4 × 2 × 2 HEXA8 under uniaxial traction F on x = 2 with symmetry on the three
    // coordinate planes: the exact solution u = (a x, b y, b z), a = F/E, b = −νF/E, is in the space, so
    // the differences vanish (to round-off) and the references are integrals of the analytic field:
    //   VOLUME: ∫ a²x² + b²y² + b²z² dV = a²·8/3 + b²·2/3 + b²·2/3,
    //   XMAX (the face x = 2, a skin integrated with its area): 4a² + b²/3 + b²/3,
    //   TOTAL: the square root of the sum of their squares;
    //   energy: ½ F²/E · V with V = 2.
    let (e, nu, f) = (70000.0f64, 0.25, 50.0);
    let (a, b) = (f / e, -nu * f / e);
    let vol = (a * a * 8.0 / 3.0 + b * b * 4.0 / 3.0).sqrt();
    let face = (4.0 * a * a + b * b * 2.0 / 3.0).sqrt();
    let total = (vol * vol + face * face).sqrt();
    let energy = 0.5 * f * f / e * 2.0;
    let body = format!(
        "MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E={e:e}, NU={nu}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         SYME = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='XMIN', DX=0.0), _F(GROUP_NO='YMIN', DY=0.0),\n\
                                                    _F(GROUP_NO='ZMIN', DZ=0.0)))\n\
         TRAC = AFFE_CHAR_MECA(MODELE=MO, FORCE_FACE=_F(GROUP_MA='XMAX', FX={f:e}))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=SYME), _F(CHARGE=TRAC)))\n\
         U = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='NOEU_DEPL_R', RESULTAT=R, NOM_CHAM='DEPL', NUME_ORDRE=1)\n\
         S = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='ELGA_SIEF_R', RESULTAT=R, NOM_CHAM='SIEF_ELGA', NUME_ORDRE=1)\n\
         RX = FORMULE(VALE='{a:e}*X', NOM_PARA=['X', 'Y', 'Z'])\n\
         RY = FORMULE(VALE='{b:e}*Y', NOM_PARA=['X', 'Y', 'Z'])\n\
         RZ = FORMULE(VALE='{b:e}*Z', NOM_PARA=['X', 'Y', 'Z'])\n\
         TL2 = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA=('VOLUME', 'XMAX'), CHAM_GD=U,\n\
                           DX=(RX, RX), DY=(RY, RY), DZ=(RZ, RZ))\n\
         IMPR_TABLE(TABLE=TL2)\n\
         SXX = FORMULE(VALE='{f:e}', NOM_PARA=['X', 'Y', 'Z'])\n\
         TEN = POST_ERREUR(OPTION='ENER_RELA', MODELE=MO, GROUP_MA='VOLUME', CHAM_GD=S, CHAM_MATER=CM,\n\
                           DEFORMATION='PETIT', SIXX=SXX)\n\
         {}{}{}{}{}{}{}",
        check("TL2", "REFERENCE", "VOLUME", vol),
        check("TL2", "REFERENCE", "XMAX", face),
        check("TL2", "REFERENCE", "TOTAL", total),
        check("TL2", "DIFFERENCE", "TOTAL", 0.0),
        check("TL2", "ERREUR RELATIVE", "TOTAL", 0.0),
        check("TEN", "REFERENCE", "TOTAL", energy),
        check("TEN", "ERREUR RELATIVE", "TOTAL", 0.0),
    );
    run("patch", CellType::Hexa8, &[4, 2, 2], &[2.0, 1.0, 1.0], &body, 11);
}

#[test]
fn contact_pressure_norm_on_a_skin() {
    // LAGR_RELA: a nodal field carrying LAGS_C = −3 everywhere, against the reference −2 on the edge
    // x = 2 (DROITE, length 1): REFERENCE = 2·√1, DIFFERENCE = 1·√1, ERREUR RELATIVE = 0.5. On the
    // surface cells the pressure has no carrier (2D bulk elements have no DZ): both norms are zero and
    // the table has no ERREUR RELATIVE column.
    let body = "MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         P = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MA,\n\
                        AFFE=_F(TOUT='OUI', NOM_CMP=('DX', 'DY', 'LAGS_C'), VALE=(0.0, 0.0, -3.0)))\n\
         PREF = FORMULE(VALE='-2.0', NOM_PARA=['X', 'Y'])\n\
         T = POST_ERREUR(OPTION='LAGR_RELA', MODELE=MO, GROUP_MA='DROITE', CHAM_GD=P, LAGS_C=PREF)\n\
         IMPR_TABLE(TABLE=T)\n\
         T2 = POST_ERREUR(OPTION='LAGR_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=P, LAGS_C=PREF)\n"
        .to_string()
        + &check("T", "REFERENCE", "TOTAL", 2.0)
        + &check("T", "DIFFERENCE", "TOTAL", 1.0)
        + &check("T", "ERREUR RELATIVE", "TOTAL", 0.5)
        + &check("T2", "REFERENCE", "TOTAL", 0.0);
    run("lagr", CellType::Quad4, &[2, 1], &[2.0, 1.0], &body, 7);
}

#[test]
fn located_errors() {
    // One reference function per group (Code_Aster's PREPOST_12), ENER_RELA over one group only.
    let dir = scratch!("errors");
    let mesh = box_mesh(CellType::Quad4, &[1, 1], &[1.0, 1.0]).unwrap();
    let mesh_path = dir.join("box.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         P = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MA,\n\
                        AFFE=_F(TOUT='OUI', NOM_CMP=('DX', 'DY'), VALE=(0.0, 0.0)))\n\
         F = FORMULE(VALE='X', NOM_PARA=['X', 'Y'])\n\
         G = FORMULE(VALE='Z', NOM_PARA=['X', 'Y', 'Z'])\n";
    let cases = [
        (
            "T = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA=('SURFACE', 'BAS'), CHAM_GD=P, DX=F)\n",
            "erreur.comm:8:",
            "DX gives 1 function(s) for 2 group(s)",
        ),
        (
            "T = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=P, DX=G)\n",
            "erreur.comm:8:",
            "parameter Z is not one of the coordinates",
        ),
    ];
    for (call, at, msg) in cases {
        let comm_path = dir.join("erreur.comm");
        std::fs::write(&comm_path, format!("{head}{call}FIN()\n")).unwrap();
        let opts =
            RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path.clone(), Dir::In)], echo: false };
        let o = runner::run_comm(&comm_path, &opts);
        let e = o.error.clone().unwrap_or_default();
        assert!(e.contains(at) && e.contains(msg), "{e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
