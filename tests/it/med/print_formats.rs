//! IMPR_RESU FORMAT='GMSH' and IMPR_TABLE FORMAT='AGRAF' run through the
//! `aster` binary.
//!
//! The GMSH files are read back by a reader written here from Gmsh's legacy
//! post-processing format (versions 1.0 and 1.2: `$PostFormat`, `$View`
//! sections with per-type element counts, time values, then per element
//! the x, y, z of its nodes and its node values per time step); the mesh is
//! read from the MED file with the library, and the displacements are
//! checked against the analytic solution of the case. When Python's `gmsh`
//! module is installed the file is also opened with it.

use crate::common::*;
use aster::med;
use aster::mesh::{CellType, Mesh};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn text(o: &Output) -> String {
    format!("stdout:\n{}\nstderr:\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

/// A QUAD4 box 2 x 1 (2 x 1 cells) with its SEG2 edge groups.
fn box_med(dir: &Path) -> PathBuf {
    let med = dir.join("box.med");
    let o = aster()
        .args(["mesh", "box", "--cell", "QUAD4", "--n", "2,1", "--size", "2,1", "-o"])
        .arg(&med)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    med
}

/// Tension of the box by an imposed displacement ramp: DX = 0.002 t at
/// x = 2, DX = 0 at x = 0, DY = 0 at y = 0; order numbers 0, 1, 2 at
/// t = 0, 1, 2.
/// Plane strain, uniaxial stress: DX = 0.001 t x, DY = -nu/(1-nu) 0.001 t y.
const PREAMBLE: &str = r#"
DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
ACIER = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.3))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=ACIER))
BLOC = AFFE_CHAR_MECA(
    MODELE=MO,
    DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0), _F(GROUP_NO="DROITE", DX=0.002)),
)
RAMPE = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 2.0, 2.0))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=2.0, NOMBRE=2))
RESU = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOC, FONC_MULT=RAMPE),
    COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=L),
)
RESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, CONTRAINTE=("SIGM_ELNO",))
"#;

fn exact(t: f64, x: f64, y: f64) -> [f64; 3] {
    [0.001 * t * x, -0.3 / 0.7 * 0.001 * t * y, 0.0]
}

struct Run {
    ok: bool,
    out: String,
    mess: String,
    pos: String,
}

/// Run the preamble plus `body`; unit 82 is the GMSH file.
fn run(dir: &Path, name: &str, body: &str) -> Run {
    let med = if dir.join("box.med").exists() { dir.join("box.med") } else { box_med(dir) };
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, format!("{PREAMBLE}{body}\nFIN()\n")).unwrap();
    let pos = dir.join(format!("{name}.pos"));
    let out = dir.join(format!("{name}.out"));
    let o = aster()
        .arg("run")
        .arg(&comm)
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .arg("--unit")
        .arg(format!("20={}", med.display()))
        .arg("--unit")
        .arg(format!("82={}", pos.display()))
        .output()
        .unwrap();
    Run {
        ok: o.status.success(),
        out: text(&o),
        mess: std::fs::read_to_string(out.join(format!("{name}.mess"))).unwrap_or_default(),
        pos: std::fs::read_to_string(&pos).unwrap_or_default(),
    }
}

// ------------------------------------------------------------ GMSH reader

/// The Gmsh element types of a view, in file order, and their node counts.
const TYPES: [(&str, usize); 8] = [
    ("point", 1),
    ("line", 2),
    ("triangle", 3),
    ("quadrangle", 4),
    ("tetrahedron", 4),
    ("hexahedron", 8),
    ("prism", 6),
    ("pyramid", 5),
];

#[derive(Debug)]
struct Element {
    /// "triangle", ...
    ty: &'static str,
    coords: Vec<[f64; 3]>,
    /// values[step][node][component]
    values: Vec<Vec<Vec<f64>>>,
}

#[derive(Debug)]
struct View {
    name: String,
    times: Vec<f64>,
    /// scalar / vector / tensor count per type, file order.
    counts: Vec<[usize; 3]>,
    elements: Vec<Element>,
}

struct PostFile {
    version: String,
    views: Vec<View>,
}

fn num(s: &str) -> f64 {
    // Fortran may drop the E of 3-digit exponents: 1.0+100.
    s.parse().unwrap_or_else(|_| panic!("not a number: {s:?}"))
}

/// Every real of a data line is written in a 15-wide field followed by one
/// blank (Fortran `1P,n(E15.x,1X)`).
fn check_fixed_width(line: &str) {
    assert!(line.len().is_multiple_of(16) && !line.is_empty(), "not 16-wide fields: {line:?}");
    for chunk in line.as_bytes().chunks(16) {
        assert_eq!(chunk[15], b' ', "field not followed by a blank: {line:?}");
        let f = std::str::from_utf8(&chunk[..15]).unwrap().trim();
        num(f);
    }
}

fn parse_pos(text: &str) -> PostFile {
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "$PostFormat", "{text}");
    assert_eq!(lines[2], "$EndPostFormat");
    let head: Vec<&str> = lines[1].split_whitespace().collect();
    assert_eq!(&head[1..], &["0", "8"], "ASCII file, 8-byte reals: {}", lines[1]);
    let version = head[0].to_string();
    let v12 = version == "1.2";
    let ntypes = if v12 { 8 } else { 4 };
    let types: Vec<(&str, usize)> = if v12 { TYPES.to_vec() } else { vec![TYPES[0], TYPES[1], TYPES[2], TYPES[4]] };
    let mut views = Vec::new();
    let mut i = 3;
    while i < lines.len() {
        assert_eq!(lines[i], "$View", "line {}: {:?}", i + 1, lines[i]);
        let mut words = lines[i + 1].split_whitespace();
        let name = words.next().unwrap().to_string();
        let nsteps: usize = words.next().unwrap().parse().unwrap();
        i += 2;
        let mut counts = Vec::new();
        for _ in 0..ntypes {
            let c: Vec<usize> = lines[i].split_whitespace().map(|w| w.parse().unwrap()).collect();
            assert_eq!(c.len(), 3, "{:?}", lines[i]);
            counts.push([c[0], c[1], c[2]]);
            i += 1;
        }
        if v12 {
            assert_eq!(lines[i].split_whitespace().collect::<Vec<_>>(), ["0", "0", "0", "0"], "text counts");
            i += 1;
        }
        let end = i + lines[i..].iter().position(|l| *l == "$EndView").expect("$EndView");
        for l in &lines[i..end] {
            check_fixed_width(l);
        }
        let mut tokens = lines[i..end].iter().flat_map(|l| l.split_whitespace()).map(num);
        let times: Vec<f64> = tokens.by_ref().take(nsteps).collect();
        let mut elements = Vec::new();
        for (k, (ty, nn)) in types.iter().enumerate() {
            for (kind, &count) in counts[k].iter().enumerate() {
                let ncmp = [1, 3, 9][kind];
                for _ in 0..count {
                    let xyz: Vec<f64> = tokens.by_ref().take(3 * nn).collect();
                    let coords = (0..*nn).map(|n| [xyz[n], xyz[nn + n], xyz[2 * nn + n]]).collect();
                    let values =
                        (0..nsteps).map(|_| (0..*nn).map(|_| tokens.by_ref().take(ncmp).collect()).collect()).collect();
                    elements.push(Element { ty, coords, values });
                }
            }
        }
        assert!(tokens.next().is_none(), "view {name}: values left over");
        views.push(View { name, times, counts, elements });
        i = end + 1;
    }
    PostFile { version, views }
}

/// The cells of the mesh as sets of node coordinates, for comparison with
/// the elements of a view.
fn cell_coords(mesh: &Mesh, t: CellType) -> Vec<Vec<[f64; 3]>> {
    (0..mesh.ncells())
        .filter(|&c| mesh.cell_types[c] == t)
        .map(|c| mesh.cells[c].iter().map(|&n| mesh.coords[n]).collect())
        .collect()
}

fn same_points(a: &[[f64; 3]], b: &[[f64; 3]]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| (0..3).all(|d| (p[d] - q[d]).abs() < 1e-12))
}

/// Values are written with 8 significant digits.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-7 * b.abs() + 1e-15
}

/// Python's gmsh, when installed, reads the file: the views and their
/// number of time steps.
fn gmsh_python_check(pos: &Path, views: &[(&str, usize)]) {
    let script = format!(
        "import gmsh\ngmsh.initialize()\ngmsh.option.setNumber('General.Terminal', 0)\ngmsh.open(r'{}')\n\
         for t in gmsh.view.getTags():\n    i = gmsh.view.getIndex(t)\n    \
         print(gmsh.option.getString('View[%d].Name' % i), int(gmsh.option.getNumber('View[%d].NbTimeStep' % i)))\n\
         gmsh.finalize()\n",
        pos.display()
    );
    let o = match Command::new("python3").arg("-c").arg(&script).output() {
        Ok(o) if o.status.success() => o,
        _ => {
            println!("SKIP: Python gmsh is not available");
            return;
        }
    };
    let got: Vec<String> = String::from_utf8_lossy(&o.stdout).lines().map(str::to_string).collect();
    let want: Vec<String> = views.iter().map(|(n, s)| format!("{n} {s}")).collect();
    assert_eq!(got, want);
}

// ------------------------------------------------------------ GMSH tests

#[test]
fn gmsh_default_scalar_views_of_a_result() {
    let dir = scratch!("scalar");
    let r = run(&dir, "scal", r#"IMPR_RESU(FORMAT="GMSH", UNITE=82, RESU=_F(RESULTAT=RESU))"#);
    assert!(r.ok, "{}", r.out);
    // Cell fields are not written, with an alarm.
    assert!(r.mess.contains("SIGM_ELNO (ELNO) not written"), "{}", r.mess);

    let lines: Vec<&str> = r.pos.lines().collect();
    assert_eq!(&lines[..3], &["$PostFormat", " 1.2 0 8", "$EndPostFormat"]);
    assert_eq!(lines[4], "RESU_DEPL_DX     3", "name, two blanks, I4");
    assert_eq!(lines[5], "       0        0        0 ", "3(I8,1X)");
    assert_eq!(lines[13], "     0      0      0      0 ", "4(I6,1X)");
    assert_eq!(lines[14], " 0.00000000E+00  1.00000000E+00  2.00000000E+00 ", "1P,10(E15.8,1X)");

    let f = parse_pos(&r.pos);
    assert_eq!(f.version, "1.2");
    let names: Vec<&str> = f.views.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["RESU_DEPL_DX", "RESU_DEPL_DY"]);

    let mesh = med::read_mesh(&dir.join("box.med"), None).unwrap();
    let segs = cell_coords(&mesh, CellType::Seg2);
    let quads = cell_coords(&mesh, CellType::Quad4);
    for (k, v) in f.views.iter().enumerate() {
        assert_eq!(v.times, [0.0, 1.0, 2.0]);
        // Scalar counts: 6 lines, 2 quadrangles, nothing else.
        let want = [[0, 0, 0], [segs.len(), 0, 0], [0, 0, 0], [quads.len(), 0, 0], [0; 3], [0; 3], [0; 3], [0; 3]];
        assert_eq!(v.counts, want, "{}", v.name);
        // Elements: the mesh cells, in mesh order per type, with their nodes.
        let lines: Vec<&Element> = v.elements.iter().filter(|e| e.ty == "line").collect();
        let quads_v: Vec<&Element> = v.elements.iter().filter(|e| e.ty == "quadrangle").collect();
        for (e, c) in lines.iter().zip(&segs).chain(quads_v.iter().zip(&quads)) {
            assert!(same_points(&e.coords, c), "{:?} vs {c:?}", e.coords);
        }
        for e in &v.elements {
            for (s, t) in v.times.iter().enumerate() {
                for (n, p) in e.coords.iter().enumerate() {
                    let want = exact(*t, p[0], p[1])[k];
                    assert!(close(e.values[s][n][0], want), "{} t={t} at {p:?}: {:?}", v.name, e.values[s][n]);
                }
            }
        }
    }
    gmsh_python_check(&dir.join("scal.pos"), &[("RESU_DEPL_DX", 3), ("RESU_DEPL_DY", 3)]);
}

#[test]
fn gmsh_version_1_0_writes_a_vector_on_triangles() {
    let dir = scratch!("v10");
    let r = run(
        &dir,
        "v10",
        r#"IMPR_RESU(FORMAT="GMSH", VERSION=1.0, UNITE=82,
          RESU=(_F(RESULTAT=RESU, NOM_CHAM="DEPL", INST=2.0),
                _F(RESULTAT=RESU, NOM_CHAM="DEPL", NUME_ORDRE=(0, 1), NOM_CMP="DY")))"#,
    );
    assert!(r.ok, "{}", r.out);
    // One header for the whole file (first occurrence only).
    assert_eq!(r.pos.matches("$PostFormat").count(), 1);
    assert!(r.pos.starts_with("$PostFormat\n 1.0 0 8\n$EndPostFormat\n"), "{}", r.pos);
    let f = parse_pos(&r.pos);
    let names: Vec<&str> = f.views.iter().map(|v| v.name.as_str()).collect();
    // Version 1.0: DX/DY/DZ as one vector view; with NOM_CMP, scalar views.
    assert_eq!(names, ["RESU_DEPL_VECTEUR", "RESU_DEPL_DY"]);

    let vect = &f.views[0];
    assert_eq!(vect.times, [2.0]);
    // Quadrangles are cut into two triangles each.
    assert_eq!(vect.counts, vec![[0, 0, 0], [0, 6, 0], [0, 4, 0], [0, 0, 0]]);
    let mesh = med::read_mesh(&dir.join("box.med"), None).unwrap();
    let quads = cell_coords(&mesh, CellType::Quad4);
    let tris: Vec<&Element> = vect.elements.iter().filter(|e| e.ty == "triangle").collect();
    for (q, pair) in quads.iter().zip(tris.chunks(2)) {
        assert!(same_points(&pair[0].coords, &[q[0], q[1], q[2]]));
        assert!(same_points(&pair[1].coords, &[q[0], q[2], q[3]]));
    }
    for e in &vect.elements {
        for (n, p) in e.coords.iter().enumerate() {
            let want = exact(2.0, p[0], p[1]);
            for (got, w) in e.values[0][n].iter().zip(want) {
                assert!(close(*got, w), "at {p:?}: {:?}", e.values[0][n]);
            }
        }
    }
    let dy = &f.views[1];
    assert_eq!(dy.times, [0.0, 1.0]);
    assert_eq!(dy.counts, vec![[0, 0, 0], [6, 0, 0], [4, 0, 0], [0, 0, 0]]);
    gmsh_python_check(&dir.join("v10.pos"), &[("RESU_DEPL_VECTEUR", 1), ("RESU_DEPL_DY", 2)]);
}

/// LIST_ORDRE takes a DEFI_LIST_ENTI, given by intervals or by values.
#[test]
fn gmsh_steps_from_a_list_of_integers() {
    let dir = scratch!("list_ordre");
    let r = run(
        &dir,
        "list_ordre",
        r#"EVEN = DEFI_LIST_ENTI(DEBUT=0, INTERVALLE=_F(JUSQU_A=2, PAS=2))
LAST = DEFI_LIST_ENTI(VALE=(1, 2))
IMPR_RESU(FORMAT="GMSH", VERSION=1.0, UNITE=82,
          RESU=(_F(RESULTAT=RESU, NOM_CHAM="DEPL", LIST_ORDRE=EVEN, NOM_CMP="DY"),
                _F(RESULTAT=RESU, NOM_CHAM="DEPL", LIST_ORDRE=LAST, NOM_CMP="DX")))"#,
    );
    assert!(r.ok, "{}", r.out);
    let f = parse_pos(&r.pos);
    let views: Vec<(&str, &[f64])> = f.views.iter().map(|v| (v.name.as_str(), v.times.as_slice())).collect();
    assert_eq!(views, [("RESU_DEPL_DY", &[0.0, 2.0][..]), ("RESU_DEPL_DX", &[1.0, 2.0][..])]);
    for e in &f.views[1].elements {
        for (n, p) in e.coords.iter().enumerate() {
            assert!(close(e.values[1][n][0], exact(2.0, p[0], p[1])[0]), "at {p:?}");
        }
    }
}

#[test]
fn gmsh_vect_2d_on_a_group_of_cells() {
    let dir = scratch!("vect2d");
    let r = run(
        &dir,
        "vect",
        r#"IMPR_RESU(FORMAT="GMSH", UNITE=82,
          RESU=_F(RESULTAT=RESU, NOM_CHAM="DEPL", NUME_ORDRE=1, GROUP_MA="SURFACE",
                  TYPE_CHAM="VECT_2D", NOM_CMP=("DX", "DY")))"#,
    );
    assert!(r.ok, "{}", r.out);
    let f = parse_pos(&r.pos);
    assert_eq!(f.views.len(), 1);
    let v = &f.views[0];
    assert_eq!(v.name, "RESU_DEPL_VECTEUR");
    assert_eq!(v.times, [1.0]);
    let mut want = vec![[0usize; 3]; 8];
    want[3] = [0, 2, 0];
    assert_eq!(v.counts, want);
    for e in &v.elements {
        for (n, p) in e.coords.iter().enumerate() {
            let w = exact(1.0, p[0], p[1]);
            assert!((0..3).all(|d| close(e.values[0][n][d], w[d])), "at {p:?}: {:?}", e.values[0][n]);
        }
    }
}

#[test]
fn gmsh_refuses_what_it_does_not_write() {
    let dir = scratch!("refuse");
    let cases = [
        ("maillage", r#"IMPR_RESU(FORMAT="GMSH", UNITE=82, RESU=_F(MAILLAGE=MA))"#, "MAILLAGE"),
        (
            "tens",
            r#"IMPR_RESU(FORMAT="GMSH", UNITE=82,
                RESU=_F(RESULTAT=RESU, TYPE_CHAM="TENS_2D", NOM_CMP=("DX", "DY", "DX", "DY")))"#,
            "TYPE_CHAM",
        ),
        (
            "elno",
            r#"IMPR_RESU(FORMAT="GMSH", UNITE=82, RESU=_F(RESULTAT=RESU, NOM_CHAM="SIGM_ELNO"))"#,
            "cell fields to GMSH is not supported yet",
        ),
        ("modele", r#"IMPR_RESU(FORMAT="GMSH", MODELE=MO, UNITE=82, RESU=_F(RESULTAT=RESU))"#, "MODELE"),
    ];
    for (name, body, needle) in cases {
        let r = run(&dir, name, body);
        assert!(!r.ok, "{name} should fail");
        assert!(r.out.contains(needle), "{name}: {}", r.out);
    }
}

// ------------------------------------------------------------ AGRAF

#[test]
fn agraf_is_tableau_with_marked_empty_cells() {
    let dir = scratch!("agraf");
    let comm = dir.join("t.comm");
    std::fs::write(
        &comm,
        r#"DEBUT(CODE="OUI")
T = CREA_TABLE(LISTE=(_F(PARA="NOEUD", LISTE_K=("N1", "N2")), _F(PARA="A", LISTE_I=(1, 2)),
                      _F(PARA="DX", LISTE_R=(-1.25e-3,))))
IMPR_TABLE(TABLE=T, FORMAT="AGRAF", UNITE=30, FORMAT_R="1PE12.5", IMPR_FONCTION="NON")
IMPR_TABLE(TABLE=T, FORMAT="TABLEAU", UNITE=31, FORMAT_R="1PE12.5")
FIN()
"#,
    )
    .unwrap();
    let (agraf, tableau) = (dir.join("agraf.txt"), dir.join("tableau.txt"));
    let o = aster()
        .arg("run")
        .arg(&comm)
        .arg("--out")
        .arg(dir.join("out"))
        .arg("-q")
        .arg("--unit")
        .arg(format!("30={}", agraf.display()))
        .arg("--unit")
        .arg(format!("31={}", tableau.display()))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let agraf = std::fs::read_to_string(agraf).unwrap();
    let tableau = std::fs::read_to_string(tableau).unwrap();
    // The empty DX of the second row is `\-`; everything else as TABLEAU.
    assert!(agraf.lines().any(|l| l.split_whitespace().collect::<Vec<_>>() == ["N2", "2", "\\-"]), "{agraf}");
    assert!(agraf.contains("-1.25000E-03"), "1PE12.5: {agraf}");
    assert_eq!(agraf.replace("\\-", "-"), tableau);
}

// ------------------------------------------------------------ legacy cases

#[test]
fn ssnv173f_runs_its_gmsh_and_agraf_prints() {
    let Some(export) = astest("ssnv173f.export") else { return };
    let dir = scratch!("ssnv173f");
    let pos = dir.join("res.pos");
    let o = aster()
        .arg("run")
        .arg(&export)
        .arg("--out")
        .arg(&dir)
        .arg("-q")
        .arg("--unit")
        .arg(format!("82={}", pos.display()))
        .output()
        .unwrap();
    let mess = std::fs::read_to_string(dir.join("ssnv173f.mess")).unwrap_or_default();
    assert!(mess.contains("FORMAT=\"AGRAF\""), "{}\n{mess}", text(&o));
    assert_no_print_error(&mess);
    let f = parse_pos(&std::fs::read_to_string(&pos).unwrap());
    let names: Vec<&str> = f.views.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["RES_XFEM_DEPL_DX", "RES_XFEM_DEPL_DY"]);
    assert!(f.views.iter().all(|v| v.times == [0.0] && !v.elements.is_empty()));
}

#[test]
fn ssnv173b_runs_its_agraf_prints() {
    let Some(export) = astest("ssnv173b.export") else { return };
    let dir = scratch!("ssnv173b");
    let o = aster().arg("run").arg(&export).arg("--out").arg(&dir).arg("-q").output().unwrap();
    let mess = std::fs::read_to_string(dir.join("ssnv173b.mess")).unwrap_or_default();
    assert!(mess.matches("FORMAT=\"AGRAF\"").count() >= 2, "{}\n{mess}", text(&o));
    assert_no_print_error(&mess);
}

/// The case may stop later, but not on IMPR_RESU or IMPR_TABLE.
fn assert_no_print_error(mess: &str) {
    for l in mess.lines().filter(|l| l.contains("<F>")) {
        assert!(!l.contains("IMPR_RESU") && !l.contains("IMPR_TABLE"), "{l}");
    }
}
