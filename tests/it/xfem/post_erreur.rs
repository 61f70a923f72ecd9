//! POST_ERREUR on an X-FEM model, against norms computed by hand on one cut cell: the unit square (one
//! QUAD4, plane strain, E = 1000, ν = 0) cut by the interface x = 1/2 (a free surface), the left edge
//! fixed and the right edge displaced by (1, 0). The halves separate: u = 0 on the left, u = (1, 0) on
//! the right, which the Heaviside enrichment represents exactly. The norms are integrated on the
//! sub-cells, with the displacement recomposed in each sub-cell's region:
//!
//! - against u_ref = (x, 0): REFERENCE² = ∫x² = 1/3, DIFFERENCE² = ∫₀^½ x² + ∫_½¹ (1 − x)² = 1/12,
//!   ERREUR RELATIVE = 1/2;
//! - against the step u_ref = (H(x − ½), 0): REFERENCE² = 1/2, DIFFERENCE = 0 to round-off;
//! - energy against σ_ref = (SIXX = 1): σ_h = 0, so DIFFERENCE = REFERENCE = ½·1²/E = 5e-4 and
//!   ERREUR RELATIVE = 1.

use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};

#[test]
fn norms_on_one_cut_cell() {
    let dir = scratch!("cut_cell");
    let mesh = box_mesh(CellType::Quad4, &[1, 1], &[1.0, 1.0]).unwrap();
    let mesh_path = dir.join("box.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let check = |t: &str, para: &str, v: f64| {
        let crit = if v == 0.0 { "CRITERE='ABSOLU', PRECISION=1.0e-12" } else { "PRECISION=1.0e-12" };
        format!(
            "TEST_TABLE(TABLE={t}, NOM_PARA='{para}', FILTRE=_F(NOM_PARA='GROUP_MA', VALE_K='TOTAL'),\n\
             VALE_CALC={v:e}, VALE_REFE={v:e}, REFERENCE='ANALYTIQUE', {crit})\n"
        )
    };
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
         MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         LN = FORMULE(VALE='X-0.5', NOM_PARA=['X', 'Y'])\n\
         FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE='INTERFACE', DEFI_FISS=_F(FONC_LN=LN))\n\
         MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS)\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.0))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_MA='GAUCHE', DX=0.0, DY=0.0),\n\
                                                  _F(GROUP_MA='DROITE', DX=1.0, DY=0.0)))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         U = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='NOEU_DEPL_R', RESULTAT=R, NOM_CHAM='DEPL', NUME_ORDRE=1)\n\
         S = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='ELGA_SIEF_R', RESULTAT=R, NOM_CHAM='SIEF_ELGA', NUME_ORDRE=1)\n\
         def step(x):\n    return 1.0 if x > 0.5 else 0.0\n\
         RX = FORMULE(VALE='X', NOM_PARA=['X', 'Y'])\n\
         RH = FORMULE(VALE='step(X)', step=step, NOM_PARA=['X', 'Y'])\n\
         T1 = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=U, DX=RX)\n\
         T2 = POST_ERREUR(OPTION='DEPL_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=U, DX=RH)\n\
         SXX = FORMULE(VALE='1.0', NOM_PARA=['X', 'Y'])\n\
         T3 = POST_ERREUR(OPTION='ENER_RELA', MODELE=MO, GROUP_MA='SURFACE', CHAM_GD=S, CHAM_MATER=CM,\n\
                          DEFORMATION='PETIT', SIXX=SXX)\n\
         {}{}{}{}{}{}{}{}FIN()\n",
        check("T1", "REFERENCE", (1.0f64 / 3.0).sqrt()),
        check("T1", "DIFFERENCE", (1.0f64 / 12.0).sqrt()),
        check("T1", "ERREUR RELATIVE", 0.5),
        check("T2", "REFERENCE", 0.5f64.sqrt()),
        check("T2", "ERREUR RELATIVE", 0.0),
        check("T3", "REFERENCE", 5.0e-4),
        check("T3", "DIFFERENCE", 5.0e-4),
        check("T3", "ERREUR RELATIVE", 1.0),
    );
    let comm_path = dir.join("cut.comm");
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    // Two lines per check (NON_REGRESSION, ANALYTIQUE), the NON_REGRESSION line of the zero one skipped.
    assert_eq!(o.ok_count(), 15, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}
