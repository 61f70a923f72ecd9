//! POST_RELEVE_T on an ELNO field at a node shared by four cells: MOYE_NOEUD='OUI' (Code_Aster's
//! default) averages the cells' values at the node into one row; MOYE_NOEUD='NON' gives one row per cell.
//!
//! The scene: a 2 × 2 QUAD4 square in plane stress, every node displaced by u = (ε x, 0), each cell of
//! its own Young's modulus E_c. The stress is uniform in each cell, σxx = E_c ε / (1 − ν²), so at the
//! centre node the four cells give four different values, whose mean and sum are known in closed form.
//! And a nodal field of CREA_CHAMP (the mesh's GEOMETRIE) read through CHAM_GD.

use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};

const NU: f64 = 0.25;
const EPS: f64 = 1.0e-3;
const YOUNG: [f64; 4] = [1.0e5, 2.0e5, 3.0e5, 6.0e5];

fn sxx(e: f64) -> f64 {
    e * EPS / (1.0 - NU * NU)
}

fn run(moye: &str, type_test: &str, expected: f64) {
    let dir = scratch!(moye);
    let mut mesh = box_mesh(CellType::Quad4, &[2, 2], &[2.0, 2.0]).unwrap();
    let centre = (0..mesh.nnodes())
        .find(|&n| (mesh.coords[n][0] - 1.0).abs() < 1e-12 && (mesh.coords[n][1] - 1.0).abs() < 1e-12)
        .unwrap();
    let around: Vec<usize> = (0..mesh.ncells()).filter(|&c| mesh.cells[c].contains(&centre)).collect();
    assert_eq!(around.len(), 4, "the centre node is shared by four cells");
    mesh.node_groups.insert("C".into(), vec![centre]);
    for (i, &c) in around.iter().enumerate() {
        mesh.cell_groups.insert(format!("G{i}"), vec![c]);
    }
    let mesh_path = dir.join("square.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let mats: String =
        YOUNG.iter().enumerate().map(|(i, e)| format!("M{i} = DEFI_MATERIAU(ELAS=_F(E={e:e}, NU={NU}))\n")).collect();
    let affe: String = (0..4).map(|i| format!("_F(GROUP_MA='G{i}', MATER=M{i}), ")).collect();
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='C_PLAN'))\n\
         {mats}\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=({affe}))\n\
         UX = FORMULE(VALE='{EPS:e}*X', NOM_PARA='X')\n\
         ZERO = DEFI_CONSTANTE(VALE=0.0)\n\
         CH = AFFE_CHAR_MECA_F(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', DX=UX, DY=ZERO))\n\
         R = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, CONTRAINTE='SIGM_ELNO')\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='S', RESULTAT=R, NOM_CHAM='SIGM_ELNO', GROUP_NO='C',\n\
                                     NOM_CMP='SIXX', OPERATION='EXTRACTION', MOYE_NOEUD='{moye}'))\n\
         TEST_TABLE(TABLE=T, NOM_PARA='SIXX', TYPE_TEST='{type_test}', VALE_CALC={expected:e},\n\
                    VALE_REFE={expected:e}, REFERENCE='ANALYTIQUE', PRECISION=1.0e-9)\n\
         FIN()\n"
    );
    let comm_path = dir.join("releve.comm");
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    assert_eq!(o.ok_count(), 2, "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn moye_noeud_oui_averages_the_four_cells_at_the_node() {
    // One row: the mean of the four cells. Its sum is the mean itself.
    let mean = YOUNG.iter().map(|&e| sxx(e)).sum::<f64>() / 4.0;
    run("OUI", "SOMM", mean);
}

#[test]
fn moye_noeud_non_gives_one_row_per_cell() {
    // Four rows: their sum is four times the mean, their largest the stiffest cell's.
    run("NON", "SOMM", YOUNG.iter().map(|&e| sxx(e)).sum::<f64>());
    run("NON", "MAX", sxx(6.0e5));
}

/// CREA_CHAMP EXTR of a mesh's GEOMETRIE and POST_RELEVE_T on it (CHAM_GD): the components X, Y, Z of
/// a 3D box's nodes, summed over a face and tested at a corner, against the coordinates.
#[test]
fn geometry_of_a_mesh_extracted_and_read_from_cham_gd() {
    let dir = scratch!("geometry");
    let mesh = box_mesh(CellType::Hexa8, &[2, 3, 1], &[2.0, 3.0, 0.5]).unwrap();
    let mesh_path = dir.join("box.med");
    med::write_mesh(&mesh_path, &mesh, "MA").unwrap();
    let xmax = &mesh.node_groups["XMAX"];
    let sum_y: f64 = xmax.iter().map(|&n| mesh.coords[n][1]).sum();
    let sum_z: f64 = xmax.iter().map(|&n| mesh.coords[n][2]).sum();
    assert_eq!(xmax.len(), 4 * 2);
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(UNITE=20, FORMAT='MED')\n\
         CHXN = CREA_CHAMP(OPERATION='EXTR', TYPE_CHAM='NOEU_GEOM_R', NOM_CHAM='GEOMETRIE', MAILLAGE=MA)\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='POS', CHAM_GD=CHXN, GROUP_NO='XMAX', TOUT_CMP='OUI',\n\
                                     OPERATION='EXTRACTION'))\n\
         TEST_TABLE(TABLE=T, NOM_PARA='X', TYPE_TEST='MIN', VALE_CALC=2.0, VALE_REFE=2.0, REFERENCE='ANALYTIQUE')\n\
         TEST_TABLE(TABLE=T, NOM_PARA='Y', TYPE_TEST='SOMM', VALE_CALC={sum_y:e}, VALE_REFE={sum_y:e},\n\
                    REFERENCE='ANALYTIQUE')\n\
         TEST_TABLE(TABLE=T, NOM_PARA='COOR_Z', TYPE_TEST='SOMM', VALE_CALC={sum_z:e}, VALE_REFE={sum_z:e},\n\
                    REFERENCE='ANALYTIQUE')\n\
         FIN()\n"
    );
    let comm_path = dir.join("geometry.comm");
    std::fs::write(&comm_path, comm).unwrap();
    let opts = RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, mesh_path, Dir::In)], echo: false };
    let o = runner::run_comm(&comm_path, &opts);
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    assert_eq!(o.diagnostic, "OK", "{:?}\n{mess}", o.error);
    assert_eq!(o.ok_count(), 6, "{mess}");
}
