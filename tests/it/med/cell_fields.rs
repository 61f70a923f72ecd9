//! Cell fields in MED: IMPR_RESU writes the fields of a statics, of a saturated HM and of an X-FEM HM
//! result (nodes, nodes of cells, integration points with Code_Aster's localizations), LIRE_RESU reads
//! them back and IMPR_RESU writes them again: `aster diff` finds the two files identical to the bit.
//! MED-fichier (`mdump`, python3-med) lists the fields and their localizations and reads the same
//! values; `aster diff` of two runs that differ names the field, the component and the place.

use crate::common::*;
use aster::med::{self, Support};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A mesh of `aster mesh box`.
fn box_mesh(dir: &Path, cell: &str, n: &str, size: &str) -> PathBuf {
    let p = dir.join(format!("{}.med", cell.to_lowercase()));
    let o = aster().args(["mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o"]).arg(&p).output().unwrap();
    assert!(o.status.success(), "{:?}", text(&o));
    p
}

/// Run a command file with units; its message file's text.
fn run(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) -> String {
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, src).unwrap();
    let out = dir.join(format!("{name}.out"));
    let mut cmd = aster();
    cmd.arg("run").arg(&comm).arg("--out").arg(&out).arg("-q");
    for (u, p) in units {
        cmd.arg("--unit").arg(format!("{u}={}", p.display()));
    }
    let o = cmd.output().unwrap();
    let mess = std::fs::read_to_string(out.join(format!("{name}.mess"))).unwrap_or_default();
    assert!(o.status.success(), "{name} failed:\n{}\n{mess}", text(&o).1);
    mess
}

/// `aster diff A B` with tolerances: exit code and output.
fn diff(a: &Path, b: &Path, tol: &[&str]) -> (i32, String) {
    let o = aster().arg("diff").arg(a).arg(b).args(tol).output().unwrap();
    let (out, err) = text(&o);
    (o.status.code().unwrap_or(-1), format!("{out}{err}"))
}

/// The round trip: `a` (IMPR_RESU of the result) and `b` (IMPR_RESU of LIRE_RESU of `a`) are the same
/// file to the bit, and they hold the fields asked.
fn assert_round_trip(a: &Path, b: &Path, fields: &[&str]) {
    let (code, out) = diff(a, b, &["--rtol", "0", "--atol", "0"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("files match"), "{out}");
    for f in fields {
        assert!(out.lines().any(|l| l.starts_with(f)), "{f} not compared:\n{out}");
    }
    assert!(!out.contains("only in"), "{out}");
}

/// The statics: a QUAD8 plate under a traction FX on its right side, its fields written to unit 80
/// (with the extra keywords `part` of the RESU occurrence), read back and written again to unit 81.
fn statics(fx: f64, part: &str, test: &str) -> String {
    statics_read(fx, part, "", test)
}

/// [`statics`] with extra keywords of LIRE_RESU.
fn statics_read(fx: f64, part: &str, read: &str, test: &str) -> String {
    format!(
        r#"DEBUT()
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM="PART", MAILLE=("M14", "M17")))
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
ACIER = DEFI_MATERIAU(ELAS=_F(E=210000.0, NU=0.3))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ACIER))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0)))
TRAC = AFFE_CHAR_MECA(MODELE=MO, FORCE_CONTOUR=_F(GROUP_MA="DROITE", FX={fx:?}, FY=10.0))
RESU = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=TRAC)))
RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, CONTRAINTE=("SIGM_ELNO",), DEFORMATION=("EPSI_ELGA",),
                  CRITERES=("SIEQ_ELNO",))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(RESULTAT=RESU{part}))
R2 = LIRE_RESU(TYPE_RESU="EVOL_ELAS", FORMAT="MED", UNITE=80, MODELE=MO, TOUT_ORDRE="OUI"{read},
               FORMAT_MED=(_F(NOM_CHAM="DEPL", NOM_RESU="RESU"), _F(NOM_CHAM="SIEF_ELGA", NOM_RESU="RESU"),
                           _F(NOM_CHAM="SIGM_ELNO", NOM_RESU="RESU"), _F(NOM_CHAM="EPSI_ELGA", NOM_RESU="RESU"),
                           _F(NOM_CHAM="SIEQ_ELNO", NOM_RESU="RESU")))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(RESULTAT=R2, NOM_RESU_MED="RESU"))
{test}
FIN()
"#
    )
}

/// SIXX at point 9 of cell M13 (the first QUAD8) of the statics under FX = 100, as computed.
const SIXX_M1_9: f64 = 100.92097350642963;

/// TEST_RESU of [`SIXX_M1_9`] on the result read back (R2).
fn sixx_check() -> String {
    format!(
        "TEST_RESU(RESU=_F(RESULTAT=R2, NUME_ORDRE=1, NOM_CHAM=\"SIEF_ELGA\", MAILLE=\"M13\", POINT=9, \
         NOM_CMP=\"SIXX\", VALE_CALC={SIXX_M1_9:?}))"
    )
}

/// A transient heat result (EVOL_THER: TEMP and FLUX_ELNO over four steps) written by IMPR_RESU, read
/// back by LIRE_RESU TYPE_RESU='EVOL_THER' and written again: the same file to the bit.
#[test]
fn heat_fields_go_through_med_and_back() {
    let dir = scratch!("heat");
    let mesh = box_mesh(&dir, "QUAD8", "4,2", "2,1");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    let src = r#"DEBUT()
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="PLAN"))
MAT = DEFI_MATERIAU(THER=_F(LAMBDA=2.0, RHO_CP=3.0))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CH = AFFE_CHAR_THER(MODELE=MO, TEMP_IMPO=(_F(GROUP_NO="GAUCHE", TEMP=100.0), _F(GROUP_NO="DROITE", TEMP=20.0)))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=4))
TH = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CH), INCREMENT=_F(LIST_INST=L),
                   ETAT_INIT=_F(VALE=20.0))
TH = CALC_CHAMP(reuse=TH, RESULTAT=TH, THERMIQUE=("FLUX_ELNO",))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(RESULTAT=TH))
T2 = LIRE_RESU(TYPE_RESU="EVOL_THER", FORMAT="MED", UNITE=80, MODELE=MO, TOUT_ORDRE="OUI", EXCIT=_F(CHARGE=CH),
               FORMAT_MED=(_F(NOM_CHAM="TEMP", NOM_RESU="TH"), _F(NOM_CHAM="FLUX_ELNO", NOM_RESU="TH")))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(RESULTAT=T2, NOM_RESU_MED="TH"))
FIN()
"#;
    run(&dir, "heat", src, &[(20, &mesh), (80, &a), (81, &b)]);
    assert_round_trip(&a, &b, &["TH______TEMP", "TH______FLUX_ELNO"]);
    let temp = med::read_field(&b, "TH______TEMP").unwrap();
    assert_eq!(temp.steps.len(), 5, "the initial state and four steps");
}

/// A unit that DEFI_FICHIER opened and nothing wrote yet (an empty file) takes a new MED file, as in
/// Code_Aster (zzzz162a/b stopped on "not an HDF5 file").
#[test]
fn impr_resu_writes_a_new_med_file_on_a_unit_defi_fichier_opened() {
    let dir = scratch!("empty_unit");
    let mesh = box_mesh(&dir, "QUAD8", "4,2", "2,1");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    let test = format!(
        r#"DEFI_FICHIER(FICHIER="MED_70", UNITE=70, TYPE="LIBRE")
IMPR_RESU(FORMAT="MED", UNITE=70, RESU=_F(RESULTAT=RESU))
R3 = LIRE_RESU(TYPE_RESU="EVOL_ELAS", FORMAT="MED", UNITE=70, MODELE=MO, TOUT_ORDRE="OUI",
               FORMAT_MED=_F(NOM_CHAM="SIEF_ELGA", NOM_RESU="RESU"))
TEST_RESU(RESU=_F(RESULTAT=R3, NUME_ORDRE=1, NOM_CHAM="SIEF_ELGA", MAILLE="M13", POINT=9, NOM_CMP="SIXX",
                  VALE_CALC={SIXX_M1_9:?}))"#
    );
    let mess = run(&dir, "empty_unit", &statics(100.0, "", &test), &[(20, &mesh), (80, &a), (81, &b)]);
    assert!(mess.contains(" 1 OK, 0 NOOK"), "{mess}");
}

#[test]
fn statics_fields_go_through_med_and_back() {
    let dir = scratch!("statics");
    let mesh = box_mesh(&dir, "QUAD8", "4,2", "2,1");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    let test = sixx_check();
    let mess = run(&dir, "statics", &statics(100.0, "", &test), &[(20, &mesh), (80, &a), (81, &b)]);
    assert!(mess.contains(" 1 OK, 0 NOOK"), "{mess}");
    assert_round_trip(
        &a,
        &b,
        &["RESU____DEPL", "RESU____SIEF_ELGA", "RESU____SIGM_ELNO", "RESU____EPSI_ELGA", "RESU____SIEQ_ELNO"],
    );

    // What the file holds: Code_Aster's localization of the QUAD8 RIGI points, the ELGA values on it,
    // the ELNO values on the nodes of the cells; order 1 written as (numdt, numit) = (1, 1).
    let locs = med::read_localizations(&a).unwrap();
    assert_eq!(locs.keys().collect::<Vec<_>>(), vec!["QU8_____FPG9"]);
    assert_eq!(locs["QU8_____FPG9"].points.len(), 9);
    let sief = med::read_field(&a, "RESU____SIEF_ELGA").unwrap();
    assert_eq!(sief.components, ["SIXX", "SIYY", "SIZZ", "SIXY"]);
    assert_eq!((sief.steps[0].numdt, sief.steps[0].numit), (1, 1));
    let blk = &sief.steps[0].blocks[0];
    assert_eq!((blk.support, blk.per_entity, blk.entities.len()), (Support::Cell, 9, 8));
    assert_eq!(blk.localization.as_deref(), Some("QU8_____FPG9"));
    assert!((blk.values[8 * 4] - SIXX_M1_9).abs() < 1e-9, "{}", blk.values[8 * 4]);
    let elno = med::read_field(&a, "RESU____SIGM_ELNO").unwrap();
    assert_eq!(elno.steps[0].blocks[0].support, Support::CellNode);

    // MED-fichier sees the same: the localization and, value for value, the fields.
    if have_python_med() {
        let lines = med_check(&["cells", a.to_str().unwrap()]);
        let loc = lines.iter().find(|l| l.starts_with("LOC QU8_____FPG9 208 2 9 ")).expect("the localization");
        let w: Vec<f64> = loc.split(' ').skip(5).map(|x| x.parse().unwrap()).collect();
        let l = &locs["QU8_____FPG9"];
        let want: Vec<f64> = l.points.iter().flat_map(|p| [p[0], p[1]]).chain(l.weights.iter().copied()).collect();
        assert_eq!(w, want);
        let vals = lines
            .iter()
            .find(|l| l.starts_with("VALUES RESU____SIEF_ELGA 1 1 CELL 208 QU8_____FPG9 - 8 9 "))
            .expect("SIEF_ELGA values");
        let got: Vec<f64> = vals.split(' ').skip(10).map(|x| x.parse().unwrap()).collect();
        assert_eq!(got, blk.values);
        assert!(lines.iter().any(|l| l.starts_with("VALUES RESU____SIGM_ELNO 1 1 NODE_ELEMENT 208 - - 8 8 ")));
    }
    if let Some(out) = mdump(&a) {
        assert!(out.contains("|QU8_____FPG9|") && out.contains("9 pts de GAUSS"), "{out}");
        for f in ["RESU____SIEF_ELGA", "RESU____SIGM_ELNO", "RESU____EPSI_ELGA", "RESU____DEPL"] {
            assert!(out.contains(&format!("CHAMP |{f}|")), "mdump does not show {f}");
        }
    }

    // A second run under another load differs: diff names the field, the component and the place.
    let (c, d) = (dir.join("c.rmed"), dir.join("d.rmed"));
    run(&dir, "statics2", &statics(100.001, "", ""), &[(20, &mesh), (80, &c), (81, &d)]);
    let (code, out) = diff(&a, &c, &[]);
    assert_eq!(code, 1, "{out}");
    let row = |f: &str, cmp: &str| {
        out.lines()
            .find(|l| l.starts_with(f) && l.contains(&format!(" {cmp} ")))
            .unwrap_or_else(|| panic!("no {f} {cmp} row:\n{out}"))
    };
    let r = row("RESU____SIEF_ELGA", "SIXX");
    assert!(r.contains("QUAD8 points") && r.contains(" point ") && r.contains("DIFFERENT"), "{r}");
    let r = row("RESU____SIGM_ELNO", "SIXX");
    assert!(r.contains("QUAD8 nodes") && r.contains(" node N") && r.contains("DIFFERENT"), "{r}");
    let r = row("RESU____DEPL", "DX");
    assert!(r.contains("nodes") && r.contains("DIFFERENT"), "{r}");
    assert!(out.contains("files differ"), "{out}");
    // Within a loose tolerance, the same.
    assert_eq!(diff(&a, &c, &["--rtol", "1e-3"]).0, 0);
}

/// LIRE_CHAMP reads one field of a file: a node field (NOEU_DEPL_R) and a field at the integration points
/// (ELGA_SIEF_R, which needs the model), at the step NUME_ORDRE names, with the values of the result
/// that was written; TEST_RESU checks them as CHAM_NO and CHAM_ELEM. A node field asked as a cell field,
/// and a step the file lacks, are refused by keyword.
#[test]
fn lire_champ_reads_node_and_point_fields() {
    let dir = scratch!("lire_champ");
    let mesh = box_mesh(&dir, "QUAD8", "4,2", "2,1");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    run(&dir, "write", &statics(100.0, "", ""), &[(20, &mesh), (80, &a), (81, &b)]);
    let depl = med::read_node_field(&a, "RESU____DEPL").unwrap();
    let m = med::read_mesh(&a, None).unwrap();
    let n3 = m.node_names.iter().position(|n| n == "N3").unwrap();
    let dx3 = depl.steps[0].2[n3 * depl.components.len()];
    assert!(dx3.abs() > 1e-6, "{dx3}");
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
        MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n";
    let read = format!(
        "{head}U = LIRE_CHAMP(MAILLAGE=MA, FORMAT='MED', UNITE=80, NOM_MED='RESU____DEPL', TYPE_CHAM='NOEU_DEPL_R',\n\
                        NOM_CMP_IDEM='OUI', NUME_ORDRE=1)\n\
         S = LIRE_CHAMP(MAILLAGE=MA, MODELE=MO, UNITE=80, NOM_MED='RESU____SIEF_ELGA', TYPE_CHAM='ELGA_SIEF_R',\n\
                        NOM_CMP_IDEM='OUI', NUME_ORDRE=1)\n\
         TEST_RESU(CHAM_NO=_F(CHAM_GD=U, NOEUD='N3', NOM_CMP='DX', VALE_CALC={dx3:?}),\n\
                   CHAM_ELEM=_F(CHAM_GD=S, MAILLE='M13', POINT=9, NOM_CMP='SIXX', VALE_CALC={SIXX_M1_9:?}))\n\
         FIN()\n"
    );
    let mess = run(&dir, "read", &read, &[(20, &mesh), (80, &a)]);
    assert!(mess.contains("checks: 2 OK, 0 NOOK"), "{mess}");
    // Refusals, by keyword.
    for (call, kw, msg) in [
        (
            "S = LIRE_CHAMP(MAILLAGE=MA, MODELE=MO, UNITE=80, NOM_MED='RESU____DEPL', TYPE_CHAM='ELGA_SIEF_R', \
             NOM_CMP_IDEM='OUI', NUME_ORDRE=1)",
            "TYPE_CHAM",
            "holds no",
        ),
        (
            "U = LIRE_CHAMP(MAILLAGE=MA, UNITE=80, NOM_MED='RESU____DEPL', TYPE_CHAM='NOEU_DEPL_R', \
             NOM_CMP_IDEM='OUI', NUME_ORDRE=7)",
            "NUME_ORDRE",
            "has no such step",
        ),
    ] {
        let comm = dir.join("bad.comm");
        std::fs::write(&comm, format!("{head}{call}\nFIN()\n")).unwrap();
        let o = aster()
            .arg("run")
            .arg(&comm)
            .args(["--out", dir.join("bad.out").to_str().unwrap(), "-q"])
            .args(["--unit", &format!("20={}", mesh.display()), "--unit", &format!("80={}", a.display())])
            .output()
            .unwrap();
        let (out, err) = text(&o);
        assert!(!o.status.success(), "{call}: should fail\n{out}");
        let all = out + &err;
        assert!(all.contains(&format!("LIRE_CHAMP: {kw}")) && all.contains(msg), "{call}:\n{all}");
    }
}

/// Part of a mesh: GROUP_MA writes the fields on the cells of the group and the nodes of these cells
/// (MED profiles), which LIRE_RESU reads back.
#[test]
fn fields_on_part_of_the_mesh_use_profiles() {
    let dir = scratch!("profiles");
    let mesh = box_mesh(&dir, "QUAD8", "4,2", "2,1");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    let test = sixx_check();
    // PROL_ZERO='NON': the nodes the file has no value at get none (they would get 0 with 'OUI').
    let src = statics_read(100.0, ", GROUP_MA=\"PART\"", ", PROL_ZERO=\"NON\"", "");
    run(&dir, "part", &src, &[(20, &mesh), (80, &a), (81, &b)]);
    let m = med::read_mesh(&mesh, None).unwrap();
    let part: Vec<usize> = ["M14", "M17"].iter().map(|n| m.cell_names.iter().position(|x| x == n).unwrap()).collect();
    let by_type = med::cellfield::cells_by_type(&m);
    let quads = &by_type[&aster::mesh::CellType::Quad8];
    let sief = med::read_field(&a, "RESU____SIEF_ELGA").unwrap();
    let got: Vec<usize> = sief.steps[0].blocks[0].entities.iter().map(|&p| quads[p]).collect();
    assert_eq!(got, part, "M14 and M17");
    let mut want: Vec<usize> = part.iter().flat_map(|&c| m.cells[c].clone()).collect();
    want.sort();
    want.dedup();
    let depl = med::read_field(&a, "RESU____DEPL").unwrap();
    assert_eq!(depl.steps[0].blocks[0].entities, want, "the nodes of M14 and M17");
    assert_round_trip(&a, &b, &["RESU____DEPL", "RESU____SIEF_ELGA", "RESU____SIGM_ELNO"]);
    if let Some(out) = mdump(&a) {
        assert!(out.contains("PROFIL__00000001"), "mdump shows no profile");
    }
    // A cell the file has no value on has none in the result read.
    let src = statics(100.0, ", GROUP_MA=\"PART\"", &test);
    let comm = dir.join("outside.comm");
    std::fs::write(&comm, src).unwrap();
    let o = aster()
        .arg("run")
        .arg(&comm)
        .args(["--out", dir.join("outside").to_str().unwrap(), "-q"])
        .arg("--unit")
        .arg(format!("20={}", mesh.display()))
        .output()
        .unwrap();
    let err = text(&o).1;
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("TEST_RESU: RESU/MAILLE: the field has no value on cell M13"), "{err}");
}

const HM: &str = r#"DEBUT()
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="MODELISATION_HM"))
UN = DEFI_CONSTANTE(VALE=1.0)
ZERO = DEFI_CONSTANTE(VALE=0.0)
KINT = DEFI_CONSTANTE(VALE=1.0e-8)
SOL = DEFI_MATERIAU(ELAS=_F(E=1.0e7, NU=0.0), COMP_THM="LIQU_SATU", THM_INIT=_F(PRE1=0.0, PORO=0.5),
                    THM_DIFFU=_F(RHO=2000.0, BIOT_COEF=1.0, PESA_X=0.0, PESA_Y=0.0, PESA_Z=0.0, PERM_IN=KINT),
                    THM_LIQU=_F(RHO=1000.0, UN_SUR_K=0.0, VISC=UN, D_VISC_TEMP=ZERO))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=SOL))
CHAR = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="HAUT", PRE1=0.0), _F(GROUP_NO="BAS", DX=0.0, DY=0.0),
                      _F(GROUP_NO=("GAUCHE", "DROITE"), DX=0.0)), PRES_REP=_F(GROUP_MA="HAUT", PRES=1.0))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=(_F(JUSQU_A=1.0, NOMBRE=2), _F(JUSQU_A=10.0, NOMBRE=2)))
RES = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=CHAR),
                    COMPORTEMENT=_F(RELATION="KIT_HM", RELATION_KIT=("ELAS", "LIQU_SATU", "HYDR_UTIL")),
                    INCREMENT=_F(LIST_INST=L))
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, CONTRAINTE=("SIGM_ELNO",), VARI_INTERNE=("VARI_ELNO",))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(RESULTAT=RES))
R2 = LIRE_RESU(TYPE_RESU="EVOL_NOLI", FORMAT="MED", UNITE=80, MODELE=MO, CHAM_MATER=CHMAT, TOUT_ORDRE="OUI",
               FORMAT_MED=(_F(NOM_CHAM="DEPL", NOM_RESU="RES"), _F(NOM_CHAM="SIEF_ELGA", NOM_RESU="RES"),
                           _F(NOM_CHAM="VARI_ELGA", NOM_RESU="RES"), _F(NOM_CHAM="SIGM_ELNO", NOM_RESU="RES"),
                           _F(NOM_CHAM="VARI_ELNO", NOM_RESU="RES")))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(RESULTAT=R2, NOM_RESU_MED="RES"))
R2 = CALC_CHAMP(reuse=R2, RESULTAT=R2, CRITERES=("SIEQ_ELNO",))
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, CRITERES=("SIEQ_ELNO",))
IMPR_RESU(FORMAT="MED", UNITE=82, RESU=_F(RESULTAT=RES, NOM_CHAM="SIEQ_ELNO"))
IMPR_RESU(FORMAT="MED", UNITE=83, RESU=_F(RESULTAT=R2, NOM_RESU_MED="RES", NOM_CHAM="SIEQ_ELNO"))
FIN()
"#;

/// The HM variants' integration points go to MED under Code_Aster's family names: FPG9 (D_PLAN_HM),
/// NOEU_S (D_PLAN_HMD: the vertices), FPG4NOS (D_PLAN_HMS: four Gauss points and the vertices), and a
/// result read back computes the same fields (CALC_CHAMP on the read result).
#[test]
fn hm_fields_go_through_med_and_back() {
    let dir = scratch!("hm");
    let mesh = box_mesh(&dir, "QUAD8", "1,4", "1,2");
    for (md, loc, npts) in
        [("D_PLAN_HM", "QU8_____FPG9", 9), ("D_PLAN_HMD", "QU8_____NOEU_S", 4), ("D_PLAN_HMS", "QU8_____FPG4NOS", 8)]
    {
        let sub = dir.join(md);
        std::fs::create_dir_all(&sub).unwrap();
        let [a, b, c, d] = ["a", "b", "c", "d"].map(|n| sub.join(format!("{n}.rmed")));
        run(&sub, "hm", &HM.replace("MODELISATION_HM", md), &[(20, &mesh), (80, &a), (81, &b), (82, &c), (83, &d)]);
        assert_round_trip(
            &a,
            &b,
            &["RES_____DEPL", "RES_____SIEF_ELGA", "RES_____VARI_ELGA", "RES_____SIGM_ELNO", "RES_____VARI_ELNO"],
        );
        assert_round_trip(&c, &d, &["RES_____SIEQ_ELNO"]);
        let locs = med::read_localizations(&a).unwrap();
        assert_eq!(locs.keys().collect::<Vec<_>>(), vec![loc], "{md}");
        assert_eq!(locs[loc].points.len(), npts, "{md}");
        let sief = med::read_field(&a, "RES_____SIEF_ELGA").unwrap();
        assert_eq!(sief.components.len(), 15, "{md}: σ', σ_p, M, w");
        assert_eq!(sief.steps.len(), 5, "{md}: the initial state and four instants");
    }
}

/// An X-FEM HM result on the visual mesh of POST_MAIL_XFEM (POST_CHAM_XFEM of wtnv144a, read in place in
/// ../shared/astest, with its CALC_CHAMP): the sub-cells' points and the lips' nodes go through MED and back.
#[test]
fn xfem_fields_on_the_visual_mesh_go_through_med_and_back() {
    let Some(comm) = astest("wtnv144a.comm") else { return };
    let dir = scratch!("xfem");
    let scene = std::fs::read_to_string(comm).unwrap();
    let at = scene.rfind("FIN()").unwrap();
    let extra = r#"
IMPR_RESU(FORMAT="MED", UNITE=82,
          RESU=_F(RESULTAT=RESU1, NOM_CHAM=("DEPL", "SIEF_ELGA", "VARI_ELGA", "SIGM_ELNO")))
R2 = LIRE_RESU(TYPE_RESU="EVOL_NOLI", FORMAT="MED", UNITE=82, MODELE=MOD_VISU, TOUT_ORDRE="OUI",
               FORMAT_MED=(_F(NOM_CHAM="DEPL", NOM_RESU="RESU1"), _F(NOM_CHAM="SIEF_ELGA", NOM_RESU="RESU1"),
                           _F(NOM_CHAM="VARI_ELGA", NOM_RESU="RESU1"), _F(NOM_CHAM="SIGM_ELNO", NOM_RESU="RESU1")))
IMPR_RESU(FORMAT="MED", UNITE=83, RESU=_F(RESULTAT=R2, NOM_RESU_MED="RESU1"))
"#;
    let src = format!("{}{extra}{}", &scene[..at], &scene[at..]);
    let mesh = astest("wtnv144a.mmed").unwrap();
    let [a, b] = ["a", "b"].map(|n| dir.join(format!("{n}.rmed")));
    run(&dir, "xfem", &src, &[(20, &mesh), (82, &a), (83, &b)]);
    assert_round_trip(&a, &b, &["RESU1___DEPL", "RESU1___SIEF_ELGA", "RESU1___VARI_ELGA", "RESU1___SIGM_ELNO"]);
    // The visual mesh has more nodes than the model's mesh (the lips' nodes are there twice), and the
    // fields at points live on its sub-cells.
    let visual = med::read_mesh(&a, None).unwrap();
    let model = med::read_mesh(&mesh, None).unwrap();
    assert!(visual.nnodes() > model.nnodes(), "{} vs {}", visual.nnodes(), model.nnodes());
    assert!(visual.ncells() > model.ncells(), "{} vs {}", visual.ncells(), model.ncells());
    let sief = med::read_field(&a, "RESU1___SIEF_ELGA").unwrap();
    let last = sief.steps.last().unwrap();
    assert!(!last.blocks.is_empty() && last.blocks.iter().all(|b| b.localization.is_some()));
}

fn have_python_med() -> bool {
    let ok =
        Command::new("/usr/bin/python3").args(["-c", "import med.medfile"]).output().is_ok_and(|o| o.status.success());
    if !ok {
        println!("SKIP python3-med cross-checks: /usr/bin/python3 cannot import med (apt-get install python3-med)");
    }
    ok
}

fn med_check(args: &[&str]) -> Vec<String> {
    let script = root().join("scripts/med_check.py");
    let out = Command::new("/usr/bin/python3").arg(script).args(args).output().unwrap();
    assert!(out.status.success(), "med_check.py {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(str::to_string).collect()
}

/// mdump's dump of a file (None, with a SKIP line, where mdump is absent).
fn mdump(path: &Path) -> Option<String> {
    match Command::new("mdump")
        .arg(path)
        .args(["NODALE", "FULL_INTERLACE", "1"])
        .stdin(std::process::Stdio::null())
        .output()
    {
        Err(e) => {
            println!("SKIP mdump checks: cannot run mdump ({e}); apt-get install libmed-tools");
            None
        }
        Ok(o) => {
            let out = String::from_utf8_lossy(&o.stdout).into_owned();
            assert!(o.status.success() && out.contains("FIN DU DUMP"), "mdump rejects {}:\n{out}", path.display());
            Some(out)
        }
    }
}

/// The corpus files that read a result with LIRE_RESU and otherwise use what we support run with every
/// check OK (docs/corpus.md counts them).
#[test]
fn corpus_lire_resu_cases_pass() {
    run_corpus_cases(&scratch!("corpus"), &[("zzzz165a", 6)]);
}

/// Result files Code_Aster wrote (zzzz165a.med: DEPL, VARI_ELNO on QUAD8; zzzz155d.med: DEPL, SIEF_ELGA
/// on HE8_____FPG8, SIEF_ELNO on HEXA8) read by LIRE_RESU and written again by IMPR_RESU: `aster diff`
/// against Code_Aster's file finds every cell field identical, point by point (our localizations are
/// Code_Aster's), as docs/compare.md shows.
#[test]
fn code_aster_result_files_read_and_written_back() {
    let corpus = root().join("../shared/corpus/astest-2025");
    if !corpus.is_dir() {
        println!("SKIP: {} is absent", corpus.display());
        return;
    }
    let dir = scratch!("code_aster_files");
    for (file, md, typ, resu, fields) in [
        ("zzzz165a.med", "AXIS", "EVOL_NOLI", "00000027", &["DEPL", "VARI_ELNO"][..]),
        ("zzzz155d.med", "3D", "EVOL_ELAS", "00000008", &["DEPL", "SIEF_ELGA", "SIEF_ELNO"][..]),
    ] {
        let read: Vec<String> = fields.iter().map(|f| format!("_F(NOM_CHAM=\"{f}\", NOM_RESU=\"{resu}\")")).collect();
        let comm = format!(
            "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT=\"MED\", UNITE=20)\n\
             MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", PHENOMENE=\"MECANIQUE\", MODELISATION=\"{md}\"))\n\
             RESU = LIRE_RESU(MODELE=MO, FORMAT=\"MED\", TYPE_RESU=\"{typ}\", UNITE=20, TOUT_ORDRE=\"OUI\",\n\
                              FORMAT_MED=({}))\n\
             IMPR_RESU(FORMAT=\"MED\", UNITE=80, RESU=_F(RESULTAT=RESU, NOM_RESU_MED=\"{resu}\"))\nFIN()\n",
            read.join(", ")
        );
        let ca = corpus.join(file);
        let ours = dir.join(format!("{file}.rmed"));
        run(&dir, &file.replace('.', "_"), &comm, &[(20, &ca), (80, &ours)]);
        let (code, out) = diff(&ca, &ours, &["--rtol", "0", "--atol", "0"]);
        let rows: Vec<&str> = out.lines().filter(|l| l.starts_with(resu)).collect();
        // Every field is identical (zzzz155d's DEPL on the nodes both files give it, below).
        for f in fields {
            let name = format!("{resu}{f}");
            // The component rows (field, component, step (t=...), ...), not the notes.
            let mine: Vec<&&str> =
                rows.iter().filter(|l| l.split_whitespace().next() == Some(&name) && l.contains(" (t=")).collect();
            assert!(!mine.is_empty() && mine.iter().all(|l| l.ends_with(" OK")), "{name}:\n{out}");
        }
        if file == "zzzz165a.med" {
            assert_eq!(code, 0, "{out}");
        } else {
            // Code_Aster's DEPL lives on a profile of 18 of the 27 nodes; LIRE_RESU's PROL_ZERO fills the
            // others: the supports differ, and diff says so, comparing the 18 nodes both files have.
            assert_eq!(code, 1, "{out}");
            assert!(out.contains("step 1: nodes: 0 entities only in A, 9 only in B, 18 in both"), "{out}");
            let locs = med::read_localizations(&ours).unwrap();
            assert_eq!(locs.keys().collect::<Vec<_>>(), vec!["HE8_____FPG8"]);
        }
    }
}
