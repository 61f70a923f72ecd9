//! LIRE_MAILLAGE, DEFI_GROUP and IMPR_RESU (MED) run through the `aster`
//! binary; `aster mesh info`, `aster mesh box` and `aster diff`; bad input.
//!
//! Expected group contents are computed here from the generated (or astest)
//! mesh read with the library, independently of the stages. The astest
//! meshes are read in place from `../shared/astest` through `--unit`
//! mappings (tests that need them print a message and pass when absent).

use crate::common::*;
use aster::med;
use aster::mesh::generate::box_mesh;
use aster::mesh::{CellType, Mesh};
use std::path::Path;
use std::process::Output;

/// Run a command file with unit mappings; returns the process output.
fn run_comm(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) -> Output {
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, src).unwrap();
    let mut cmd = aster();
    cmd.arg("run").arg(&comm).arg("--out").arg(dir.join(format!("{name}.out"))).arg("-q");
    for (u, p) in units {
        cmd.arg("--unit").arg(format!("{u}={}", p.display()));
    }
    cmd.output().unwrap()
}

fn run_ok(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) {
    let o = run_comm(dir, name, src, units);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{name} failed:\nstdout:\n{out}\nstderr:\n{err}");
}

/// Names of a list of node indices.
fn names(mesh: &Mesh, nodes: &[usize]) -> Vec<String> {
    nodes.iter().map(|&n| mesh.node_names[n].clone()).collect()
}

/// Node group of a mesh read back, as names.
fn group_names(mesh: &Mesh, g: &str) -> Vec<String> {
    let v = mesh.node_groups.get(g).unwrap_or_else(|| panic!("no node group {g}"));
    names(mesh, v)
}

/// Sorted, deduplicated nodes of some cells, optionally vertices only.
fn nodes_of(mesh: &Mesh, cells: &[usize], vertices_only: bool) -> Vec<usize> {
    let mut v: Vec<usize> = cells
        .iter()
        .flat_map(|&c| {
            let k = if vertices_only { mesh.cell_types[c].nvertices() } else { mesh.cells[c].len() };
            mesh.cells[c][..k].to_vec()
        })
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// The members of a group as DEFI_GROUP INFO=2 lists them in the message
/// file, in order ("nodes of group G:" / "cells of group G:" then lines of
/// names). MED files keep groups as families, so member order is only
/// observable there.
fn listed(dir: &Path, name: &str, header: &str) -> Vec<String> {
    let mess = std::fs::read_to_string(dir.join(format!("{name}.out")).join(format!("{name}.mess"))).unwrap();
    let mut lines = mess.lines().skip_while(|l| l.trim() != header);
    assert!(lines.next().is_some(), "no '{header}' in {name}.mess");
    lines
        .take_while(|l| l.starts_with("  ") && !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .flat_map(|l| l.split_whitespace())
        .map(str::to_string)
        .collect()
}

#[test]
fn mesh_box_and_info() {
    let dir = scratch!("box");
    let out = dir.join("q4.med");
    let o = aster()
        .args(["mesh", "box", "--cell", "QUAD4", "--n", "4,3", "--size", "2,1.5", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{:?}", text(&o));
    let m = med::read_mesh(&out, Some("MAIL")).unwrap();
    let (nx, ny) = (4usize, 3usize);
    assert_eq!(m.nnodes(), (nx + 1) * (ny + 1));
    assert_eq!(m.cell_type_counts()[&CellType::Quad4], nx * ny);
    assert_eq!(m.cell_type_counts()[&CellType::Seg2], 2 * (nx + ny));
    for (g, axis, val, count) in
        [("BAS", 1, 0.0, nx + 1), ("HAUT", 1, 1.5, nx + 1), ("GAUCHE", 0, 0.0, ny + 1), ("DROITE", 0, 2.0, ny + 1)]
    {
        let want: Vec<usize> = (0..m.nnodes()).filter(|&i| m.coords[i][axis] == val).collect();
        assert_eq!(want.len(), count);
        assert_eq!(m.node_groups[g], want, "{g}");
    }

    let o = aster().args(["mesh", "info"]).arg(&out).output().unwrap();
    let (stdout, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let lines: Vec<Vec<&str>> = stdout.lines().map(|l| l.split_whitespace().collect()).collect();
    assert!(lines.contains(&vec!["nodes:", "20"]), "{stdout}");
    assert!(lines.contains(&vec!["QUAD4", "12"]), "{stdout}");
    assert!(lines.contains(&vec!["SEG2", "14"]), "{stdout}");
    assert!(lines.contains(&vec!["BAS", "5"]), "{stdout}"); // node group
    assert!(lines.contains(&vec!["BAS", "4"]), "{stdout}"); // cell group
    assert!(stdout.contains("bounding box: x in [0, 2], y in [0, 1.5]"), "{stdout}");

    // A mesh name that is not in the file.
    let o = aster().args(["mesh", "info", "--mesh", "NOPE"]).arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains("no mesh named 'NOPE'"), "{:?}", text(&o));
}

#[test]
fn defi_group_on_a_generated_box() {
    let dir = scratch!("defi");
    let src_mesh = dir.join("h20.med");
    let mesh = box_mesh(CellType::Hexa20, &[2, 3, 2], &[1.0, 1.5, 2.0]).unwrap();
    med::write_mesh(&src_mesh, &mesh, "BOX").unwrap();
    let result = dir.join("out.rmed");
    let comm = r#"
DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED', NOM_MED='BOX', INFO=2)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, INFO=2,
    DETR_GROUP_NO=_F(NOM=('XMIN',)),
    CREA_GROUP_MA=(
        _F(NOM='XFACES', UNION=('XMIN', 'XMAX')),
        _F(NOM='SKIN', TOUT='OUI', TYPE_MAILLE='2D'),
        _F(NOM='HEX', TOUT='OUI', TYPE_MAILLE='HEXA20'),
        _F(NOM='TWO', MAILLE=('M3', 'M1')),
        _F(NOM='NOTX', DIFFE=('SKIN', 'XFACES')),
        _F(NOM='SECOND', GROUP_MA='HEX', NUME_INIT=2, NUME_FIN=2),
    ),
    CREA_GROUP_NO=(
        _F(GROUP_MA='XMIN'),
        _F(NOM='XMAXS', GROUP_MA='XMAX', CRIT_NOEUD='SOMMET'),
        _F(NOM='EDGE', INTERSEC=('YMIN', 'ZMIN')),
        _F(NOM='YZ', UNION=('ZMIN', 'YMIN')),
        _F(NOM='Y_NOT_Z', DIFFE=('YMIN', 'ZMIN')),
        _F(NOM='PICK', NOEUD=('N7', 'N2')),
        _F(NOM='MIDX', OPTION='PLAN', POINT=(0.5, 0., 0.), VECT_NORMALE=(2., 0., 0.), PRECISION=1.e-9),
    ),
)
IMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(MAILLAGE=MA))
FIN()
"#;
    run_ok(&dir, "defi", comm, &[(20, &src_mesh), (80, &result)]);
    let got = med::read_mesh(&result, Some("MA")).unwrap();
    let m = &mesh;
    // Unchanged geometry.
    assert_eq!(got.coords, m.coords);
    assert_eq!(got.cells, m.cells);
    // Cell groups.
    let mut xfaces = m.cell_groups["XMIN"].clone();
    xfaces.extend(&m.cell_groups["XMAX"]);
    assert_eq!(got.cell_groups["XFACES"], xfaces);
    let skin: Vec<usize> = (0..m.ncells()).filter(|&c| m.cell_types[c].dim() == 2).collect();
    let hex: Vec<usize> = (0..m.ncells()).filter(|&c| m.cell_types[c] == CellType::Hexa20).collect();
    assert_eq!(got.cell_groups["SKIN"], skin);
    assert_eq!(got.cell_groups["HEX"], hex);
    assert_eq!(got.cell_groups["TWO"], vec![0, 2]);
    assert_eq!(listed(&dir, "defi", "cells of group TWO:"), vec!["M3", "M1"]);
    let notx: Vec<usize> = skin.iter().copied().filter(|c| !xfaces.contains(c)).collect();
    assert_eq!(got.cell_groups["NOTX"], notx);
    assert_eq!(got.cell_groups["SECOND"], vec![hex[1]]);
    // Node groups.
    assert_eq!(got.node_groups["XMIN"], nodes_of(m, &m.cell_groups["XMIN"], false));
    assert_eq!(got.node_groups["XMAXS"], nodes_of(m, &m.cell_groups["XMAX"], true));
    assert_eq!(got.node_groups["XMAXS"].len(), 4 * 3);
    let (ymin, zmin) = (&m.node_groups["YMIN"], &m.node_groups["ZMIN"]);
    let edge: Vec<usize> = ymin.iter().copied().filter(|n| zmin.contains(n)).collect();
    assert_eq!(edge.len(), 2 * 2 + 1);
    assert!(edge.iter().all(|&n| m.coords[n][1] == 0.0 && m.coords[n][2] == 0.0));
    assert_eq!(got.node_groups["EDGE"], edge);
    let mut yz = zmin.clone();
    yz.extend(ymin.iter().copied().filter(|n| !zmin.contains(n)));
    let mut yz_sorted = yz.clone();
    yz_sorted.sort_unstable();
    assert_eq!(got.node_groups["YZ"], yz_sorted);
    assert_eq!(listed(&dir, "defi", "nodes of group YZ:"), names(m, &yz));
    let y_not_z: Vec<usize> = ymin.iter().copied().filter(|n| !zmin.contains(n)).collect();
    assert_eq!(got.node_groups["Y_NOT_Z"], y_not_z);
    assert_eq!(group_names(&got, "PICK"), vec!["N2", "N7"]);
    assert_eq!(listed(&dir, "defi", "nodes of group PICK:"), vec!["N7", "N2"]);
    let midx: Vec<usize> = (0..m.nnodes()).filter(|&n| (m.coords[n][0] - 0.5).abs() <= 1e-9).collect();
    assert!(!midx.is_empty());
    assert_eq!(got.node_groups["MIDX"], midx);
    // INFO=2 summary of LIRE_MAILLAGE in the message file.
    let mess = std::fs::read_to_string(dir.join("defi.out").join("defi.mess")).unwrap();
    assert!(mess.contains(&format!("nodes: {}", m.nnodes())), "message file lacks the INFO=2 summary");
}

/// DEFI_GROUP's geometric options on generated boxes, each group computed here from the coordinates:
/// ENV_SPHERE, ENV_CYLINDRE and SEGM_DROI_ORDO (nodes), SPHERE with each CRIT_NOEUD, CYLINDRE, BANDE,
/// FACE_NORMALE and APPUI (cells), in 3D, and SPHERE, BANDE and FACE_NORMALE in 2D.
#[test]
fn defi_group_geometric_options() {
    let dir = scratch!("geom");
    let src_mesh = dir.join("h8.med");
    let m = box_mesh(CellType::Hexa8, &[4, 4, 2], &[2.0, 2.0, 1.0]).unwrap();
    med::write_mesh(&src_mesh, &m, "BOX").unwrap();
    let corner = (0..m.nnodes()).find(|&n| m.coords[n] == [0.0, 0.0, 0.0]).unwrap();
    let far = (0..m.nnodes()).find(|&n| m.coords[n] == [2.0, 2.0, 0.0]).unwrap();
    let result = dir.join("out.rmed");
    let comm = format!(
        r#"
DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED', NOM_MED='BOX')
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, INFO=2,
    CREA_GROUP_MA=(
        _F(NOM='SPH_UN', OPTION='SPHERE', POINT=(0., 0., 0.), RAYON=0.8),
        _F(NOM='SPH_TOUS', OPTION='SPHERE', POINT=(0., 0., 0.), RAYON=0.8, CRIT_NOEUD='TOUS'),
        _F(NOM='SPH_MAJ', OPTION='SPHERE', POINT=(0., 0., 0.), RAYON=0.8, CRIT_NOEUD='MAJORITE'),
        _F(NOM='CYL', OPTION='CYLINDRE', POINT=(1., 1., 0.), VECT_NORMALE=(0., 0., 2.), RAYON=0.75,
           CRIT_NOEUD='TOUS'),
        _F(NOM='BAND', OPTION='BANDE', POINT=(1., 0., 0.), ANGL_NAUT=(0., 0.), DIST=0.3, CRIT_NOEUD='TOUS'),
        _F(NOM='TOP', OPTION='FACE_NORMALE', VECT_NORMALE=(0., 0., 1.)),
        _F(NOM='TOPBOT', OPTION='FACE_NORMALE', VECT_NORMALE=(0., 0., 1.), VERI_SIGNE='NON'),
        _F(NOM='TOUCH', OPTION='APPUI', NOEUD='{c}', TYPE_APPUI='AU_MOINS_UN'),
        _F(NOM='ONZMIN', OPTION='APPUI', GROUP_NO='ZMIN', TYPE_APPUI='TOUT'),
    ),
    CREA_GROUP_NO=(
        _F(NOM='SHELL', OPTION='ENV_SPHERE', POINT=(0., 0., 0.), RAYON=1.0, PRECISION=1.e-6),
        _F(NOM='TUBE', OPTION='ENV_CYLINDRE', POINT=(0., 0., 0.), ANGL_NAUT=(0., -90.), RAYON=1.0,
           PRECISION=1.e-6),
        _F(NOM='A', NOEUD='{c}'),
        _F(NOM='B', NOEUD='{f}'),
        _F(NOM='DIAG', OPTION='SEGM_DROI_ORDO', GROUP_NO='ZMIN', GROUP_NO_ORIG='B', GROUP_NO_EXTR='A',
           PRECISION=1.e-6, CRITERE='ABSOLU'),
    ),
)
IMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(MAILLAGE=MA))
FIN()
"#,
        c = m.node_names[corner],
        f = m.node_names[far],
    );
    // SEGM_DROI_ORDO stops on nodes off the segment: ZMIN holds the whole bottom face.
    let o = run_comm(&dir, "geom_bad", &comm, &[(20, &src_mesh), (80, &result)]);
    let (out, err) = text(&o);
    assert!(!o.status.success() && err.contains("from the segment, beyond PRECISION"), "{out}\n{err}");
    // The diagonal of the bottom face for the ordered segment.
    let diag: Vec<usize> =
        (0..m.nnodes()).filter(|&n| m.coords[n][2] == 0.0 && m.coords[n][0] == m.coords[n][1]).collect();
    assert_eq!(diag.len(), 5);
    let names_diag: Vec<String> = names(&m, &diag);
    let comm = comm.replace(
        "_F(NOM='DIAG', OPTION='SEGM_DROI_ORDO', GROUP_NO='ZMIN',",
        &format!(
            "_F(NOM='DG', NOEUD=({})),\n        _F(NOM='DIAG', OPTION='SEGM_DROI_ORDO', GROUP_NO='DG',",
            names_diag.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
        ),
    );
    run_ok(&dir, "geom", &comm, &[(20, &src_mesh), (80, &result)]);
    let got = med::read_mesh(&result, None).unwrap();
    let x = |n: usize| m.coords[n];
    let d2 = |n: usize, c: [f64; 3]| (0..3).map(|k| (x(n)[k] - c[k]).powi(2)).sum::<f64>();
    let cells_where =
        |pred: &dyn Fn(&[usize]) -> bool| -> Vec<usize> { (0..m.ncells()).filter(|&c| pred(&m.cells[c])).collect() };
    let inside = |n: usize| d2(n, [0.0; 3]) <= 0.64;
    let un = cells_where(&|ns| ns.iter().any(|&n| inside(n)));
    let tous = cells_where(&|ns| ns.iter().all(|&n| inside(n)));
    let maj = cells_where(&|ns| 2 * ns.iter().filter(|&&n| inside(n)).count() >= ns.len());
    // The corner hexahedron has 7 of its 8 nodes within 0.8 (h = 0.5): a majority, not all.
    assert!(tous.len() < maj.len() && maj.len() < un.len(), "{} {} {}", tous.len(), maj.len(), un.len());
    assert_eq!(got.cell_groups["SPH_UN"], un);
    assert_eq!(got.cell_groups["SPH_TOUS"], tous);
    assert_eq!(got.cell_groups["SPH_MAJ"], maj);
    let cyl = cells_where(&|ns| ns.iter().all(|&n| (x(n)[0] - 1.0).powi(2) + (x(n)[1] - 1.0).powi(2) <= 0.5625));
    assert_eq!(cyl.len(), 4 * 2 + 4 * 2, "8 hexahedra and the 4 quadrangles below and above them");
    assert_eq!(got.cell_groups["CYL"], cyl);
    let band = cells_where(&|ns| ns.iter().all(|&n| (x(n)[0] - 1.0).abs() <= 0.3));
    assert!(band.is_empty(), "no cell lies within 0.3 of x = 1 with h = 0.5");
    assert!(!got.cell_groups.contains_key("BAND"), "an empty group is not created");
    let quads = |z: f64| cells_where(&|ns| ns.len() == 4 && ns.iter().all(|&n| x(n)[2] == z));
    let top = quads(1.0);
    assert_eq!(top.len(), 16);
    assert_eq!(got.cell_groups["TOP"], top);
    let topbot: Vec<usize> = (0..m.ncells()).filter(|c| top.contains(c) || quads(0.0).contains(c)).collect();
    assert_eq!(got.cell_groups["TOPBOT"], topbot);
    assert_eq!(got.cell_groups["TOUCH"], cells_where(&|ns| ns.contains(&corner)));
    let zmin = &m.node_groups["ZMIN"];
    assert_eq!(got.cell_groups["ONZMIN"], cells_where(&|ns| ns.iter().all(|n| zmin.contains(n))));
    let shell: Vec<usize> = (0..m.nnodes()).filter(|&n| (d2(n, [0.0; 3]).sqrt() - 1.0).abs() <= 1e-6).collect();
    assert_eq!(shell.len(), 3, "(1,0,0), (0,1,0) and (0,0,1)");
    assert_eq!(got.node_groups["SHELL"], shell);
    // ANGL_NAUT=(0, -90) is the z axis.
    let tube: Vec<usize> =
        (0..m.nnodes()).filter(|&n| ((x(n)[0].powi(2) + x(n)[1].powi(2)).sqrt() - 1.0).abs() <= 1e-6).collect();
    assert_eq!(tube.len(), 2 * 3);
    assert_eq!(got.node_groups["TUBE"], tube);
    let mut from_far = diag.clone();
    from_far.sort_by(|&a, &b| x(b)[0].total_cmp(&x(a)[0]));
    assert_eq!(listed(&dir, "geom", "nodes of group DIAG:"), names(&m, &from_far));

    // 2D: z is left out; the normal of a segment is (dy, −dx).
    let src2 = dir.join("q4.med");
    let m2 = box_mesh(CellType::Quad4, &[4, 2], &[2.0, 1.0]).unwrap();
    med::write_mesh(&src2, &m2, "PLAQ").unwrap();
    let comm2 = r#"
DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED')
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA,
    CREA_GROUP_MA=(
        _F(NOM='DISC', OPTION='SPHERE', POINT=(2., 1.), RAYON=0.6, CRIT_NOEUD='TOUS'),
        _F(NOM='STRIP', OPTION='BANDE', POINT=(0., 0.5), VECT_NORMALE=(0., 1.), DIST=0.5, CRIT_NOEUD='TOUS',
           TYPE_MAILLE='2D'),
        _F(NOM='NORM', OPTION='FACE_NORMALE', ANGL_NAUT=(90.,), VERI_SIGNE='NON'),
    ),
    CREA_GROUP_NO=_F(NOM='ARC', OPTION='ENV_SPHERE', POINT=(0., 0.), RAYON=1., PRECISION=1.e-9),
)
IMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(MAILLAGE=MA))
FIN()
"#;
    let result2 = dir.join("out2.rmed");
    run_ok(&dir, "geom2", comm2, &[(20, &src2), (80, &result2)]);
    let got2 = med::read_mesh(&result2, None).unwrap();
    let y = |n: usize| m2.coords[n];
    let disc: Vec<usize> = (0..m2.ncells())
        .filter(|&c| m2.cells[c].iter().all(|&n| (y(n)[0] - 2.0).powi(2) + (y(n)[1] - 1.0).powi(2) <= 0.36))
        .collect();
    assert_eq!(disc.len(), 2, "the two edge segments at the corner (2, 1); the corner quadrangle reaches 0.71");
    assert_eq!(got2.cell_groups["DISC"], disc);
    let quads: Vec<usize> = (0..m2.ncells()).filter(|&c| m2.cell_types[c] == CellType::Quad4).collect();
    assert_eq!(got2.cell_groups["STRIP"], quads);
    let horizontal: Vec<usize> = (0..m2.ncells())
        .filter(|&c| m2.cell_types[c] == CellType::Seg2 && y(m2.cells[c][0])[1] == y(m2.cells[c][1])[1])
        .collect();
    assert_eq!(horizontal.len(), 8);
    assert_eq!(got2.cell_groups["NORM"], horizontal);
    let arc: Vec<usize> =
        (0..m2.nnodes()).filter(|&n| ((y(n)[0].powi(2) + y(n)[1].powi(2)).sqrt() - 1.0).abs() <= 1e-9).collect();
    assert_eq!(arc.len(), 2);
    assert_eq!(got2.node_groups["ARC"], arc);
}

#[test]
fn noeud_ordo_on_a_quad8_box() {
    let dir = scratch!("ordo");
    let src_mesh = dir.join("q8.med");
    let mesh = box_mesh(CellType::Quad8, &[4, 2], &[4.0, 1.0]).unwrap();
    med::write_mesh(&src_mesh, &mesh, "MAIL").unwrap();
    // Corner nodes of the bottom edge.
    let left = (0..mesh.nnodes()).find(|&n| mesh.coords[n] == [0.0, 0.0, 0.0]).unwrap();
    let right = (0..mesh.nnodes()).find(|&n| mesh.coords[n] == [4.0, 0.0, 0.0]).unwrap();
    let (ln, rn) = (&mesh.node_names[left], &mesh.node_names[right]);
    let result = dir.join("out.rmed");
    let comm = format!(
        r#"
DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='MED')
DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, INFO=2, CREA_GROUP_NO=(
    _F(NOM='A', NOEUD='{ln}'),
    _F(NOM='B', NOEUD='{rn}'),
    _F(NOM='FWD', OPTION='NOEUD_ORDO', GROUP_MA='BAS', GROUP_NO_ORIG='A', GROUP_NO_EXTR='B'),
    _F(NOM='BWD', OPTION='NOEUD_ORDO', GROUP_MA='BAS', GROUP_NO_ORIG='B'),
))
IMPR_RESU(FORMAT='MED', RESU=_F(MAILLAGE=MAIL))
FIN()
"#
    );
    run_ok(&dir, "ordo", &comm, &[(20, &src_mesh), (80, &result)]);
    let got = med::read_mesh(&result, None).unwrap();
    let mut bottom: Vec<usize> = (0..mesh.nnodes()).filter(|&n| mesh.coords[n][1] == 0.0).collect();
    bottom.sort_by(|&a, &b| mesh.coords[a][0].partial_cmp(&mesh.coords[b][0]).unwrap());
    assert_eq!(bottom.len(), 2 * 4 + 1);
    let mut sorted = bottom.clone();
    sorted.sort_unstable();
    assert_eq!(got.node_groups["FWD"], sorted);
    assert_eq!(got.node_groups["BWD"], sorted);
    assert_eq!(listed(&dir, "ordo", "nodes of group FWD:"), names(&mesh, &bottom));
    bottom.reverse();
    assert_eq!(listed(&dir, "ordo", "nodes of group BWD:"), names(&mesh, &bottom));
}

#[test]
fn astest_defi_group_options() {
    let dir = scratch!("astest");
    // wtna113d: CREA_GROUP_MA copies, TOUT, NOEUD_ORDO from N3 to N4.
    if let Some(mm) = astest("wtna113a.mmed") {
        let mesh = med::read_mesh(&mm, None).unwrap();
        let result = dir.join("wtna.rmed");
        let comm = r#"
DEBUT()
MAILLAGE = LIRE_MAILLAGE(FORMAT="MED")
MAILLAGE = DEFI_GROUP(reuse=MAILLAGE, MAILLAGE=MAILLAGE, INFO=2,
    CREA_GROUP_MA=(_F(NOM="down", GROUP_MA="GM8"), _F(NOM="up", GROUP_MA="GM7"), _F(NOM="ROCHE", TOUT="OUI")),
    CREA_GROUP_NO=(
        _F(GROUP_MA="down"),
        _F(NOM="up", GROUP_MA="up", OPTION="NOEUD_ORDO", GROUP_NO_ORIG="N3", GROUP_NO_EXTR="N4"),
        _F(GROUP_MA="ROCHE"),
    ),
)
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(MAILLAGE=MAILLAGE))
FIN()
"#;
        run_ok(&dir, "wtna", comm, &[(20, &mm), (80, &result)]);
        let got = med::read_mesh(&result, None).unwrap();
        assert_eq!(got.cell_groups["up"], mesh.cell_groups["GM7"]);
        assert_eq!(got.cell_groups["ROCHE"], (0..mesh.ncells()).collect::<Vec<_>>());
        assert_eq!(got.node_groups["down"], nodes_of(&mesh, &mesh.cell_groups["GM8"], false));
        assert_eq!(got.node_groups["ROCHE"], (0..mesh.nnodes()).collect::<Vec<_>>());
        // The ordered line: the nodes of GM7, from N3's node to N4's, each
        // farther from the origin than the previous one (a straight edge).
        assert_eq!(got.node_groups["up"], nodes_of(&mesh, &mesh.cell_groups["GM7"], false));
        let index: std::collections::HashMap<&str, usize> =
            mesh.node_names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        let listed_up = listed(&dir, "wtna", "nodes of group up:");
        let up: Vec<usize> = listed_up.iter().map(|n| index[n.as_str()]).collect();
        let mut set = up.clone();
        set.sort_unstable();
        assert_eq!(set, got.node_groups["up"]);
        assert_eq!(up[0], mesh.node_groups["N3"][0]);
        assert_eq!(*up.last().unwrap(), mesh.node_groups["N4"][0]);
        let o = mesh.coords[up[0]];
        let dist = |n: usize| (0..3).map(|k| (mesh.coords[n][k] - o[k]).powi(2)).sum::<f64>().sqrt();
        assert!(up.windows(2).all(|w| dist(w[1]) > dist(w[0])), "not ordered along the line");
    }
    // ssnv508a: OPTION='PLAN' in 2D, and CREA_GROUP_NO with NOM over a GROUP_MA.
    if let Some(mm) = astest("ssnv508a.mmed") {
        let mesh = med::read_mesh(&mm, None).unwrap();
        let result = dir.join("ssnv.rmed");
        let comm = r#"
DEBUT()
MAILLAG1 = LIRE_MAILLAGE(FORMAT="MED", INFO=1)
MAILLAG1 = DEFI_GROUP(reuse=MAILLAG1, MAILLAGE=MAILLAG1, CREA_GROUP_NO=_F(GROUP_MA="MTOT", NOM="SURF"))
MAILLAG1 = DEFI_GROUP(reuse=MAILLAG1, MAILLAGE=MAILLAG1,
    CREA_GROUP_NO=(_F(NOM="L1", OPTION="PLAN", POINT=(0, 0), VECT_NORMALE=(1, 0), PRECISION=0.00001),))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(MAILLAGE=MAILLAG1))
FIN()
"#;
        run_ok(&dir, "ssnv", comm, &[(20, &mm), (80, &result)]);
        let got = med::read_mesh(&result, None).unwrap();
        let l1: Vec<usize> = (0..mesh.nnodes()).filter(|&n| mesh.coords[n][0].abs() <= 1e-5).collect();
        assert!(!l1.is_empty());
        assert_eq!(got.node_groups["L1"], l1);
        assert_eq!(got.node_groups["SURF"], nodes_of(&mesh, &mesh.cell_groups["MTOT"], false));
    }
    // wtnl100b: CRIT_NOEUD='SOMMET'.
    if let Some(mm) = astest("wtnl100b.mmed") {
        let mesh = med::read_mesh(&mm, None).unwrap();
        let result = dir.join("wtnl.rmed");
        let comm = r#"
DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT="MED")
MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, CREA_GROUP_NO=_F(NOM="HAUTS", CRIT_NOEUD="SOMMET", GROUP_MA="FACESUP"))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(MAILLAGE=MAIL))
FIN()
"#;
        run_ok(&dir, "wtnl", comm, &[(20, &mm), (80, &result)]);
        let got = med::read_mesh(&result, None).unwrap();
        let want = nodes_of(&mesh, &mesh.cell_groups["FACESUP"], true);
        assert_eq!(want.len(), 4);
        assert_eq!(got.node_groups["HAUTS"], want);
    }
    // zzzz325b: TYPE_MAILLE filter over TOUT.
    if let Some(mm) = astest("zzzz325b.med") {
        let mesh = med::read_mesh(&mm, None).unwrap();
        let result = dir.join("zzzz.rmed");
        let comm = r#"
DEBUT()
MA = LIRE_MAILLAGE(FORMAT="MED", INFO=2, UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM="LIGNE", TYPE_MAILLE=("SEG2"), TOUT="OUI"))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(MAILLAGE=MA))
FIN()
"#;
        run_ok(&dir, "zzzz", comm, &[(20, &mm), (80, &result)]);
        let got = med::read_mesh(&result, None).unwrap();
        let segs: Vec<usize> = (0..mesh.ncells()).filter(|&c| mesh.cell_types[c] == CellType::Seg2).collect();
        assert_eq!(segs.len(), 12);
        assert_eq!(got.cell_groups["LIGNE"], segs);
    }
}

#[test]
fn diff_against_itself_and_a_perturbed_copy() {
    let dir = scratch!("diff");
    let mesh = box_mesh(CellType::Quad4, &[3, 2], &[3.0, 2.0]).unwrap();
    let nn = mesh.nnodes();
    let values =
        |t: f64| -> Vec<f64> { (0..nn).flat_map(|i| [t * mesh.coords[i][0], t * mesh.coords[i][1] + 1.0]).collect() };
    let a = dir.join("a.rmed");
    med::write_mesh(&a, &mesh, "MAIL").unwrap();
    med::write_node_field(&a, "MAIL", "DEPL", &["DX", "DY"], &[(1, 0.5, values(0.5)), (2, 1.0, values(1.0))]).unwrap();
    // The copy: DY of node index 5 at step 2 moved by 2.5e-3.
    let b = dir.join("b.rmed");
    med::write_mesh(&b, &mesh, "MAIL").unwrap();
    let mut v2 = values(1.0);
    let base = v2[5 * 2 + 1];
    v2[5 * 2 + 1] += 2.5e-3;
    let delta = v2[5 * 2 + 1] - base; // the exact difference in floating point
    med::write_node_field(&b, "MAIL", "DEPL", &["DX", "DY"], &[(1, 0.5, values(0.5)), (2, 1.0, v2.clone())]).unwrap();

    let o = aster().arg("diff").arg(&a).arg(&a).output().unwrap();
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{err}");
    // One table row per field, component and step: max |a-b|, where, max rel, where, verdict.
    let field_lines: Vec<&str> = out.lines().filter(|l| l.starts_with("DEPL ")).collect();
    assert_eq!(field_lines.len(), 4, "{out}");
    assert!(field_lines.iter().all(|l| l.contains(" 0.000000e0 ") && l.ends_with("OK")), "{out}");

    let o = aster().arg("diff").arg(&a).arg(&b).output().unwrap();
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}{err}");
    let row = |cmp: &str, step: &str| -> Vec<String> {
        let l = out
            .lines()
            .find(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                w.len() > 3 && w[0] == "DEPL" && w[1] == cmp && w[2] == step
            })
            .unwrap_or_else(|| panic!("no row DEPL {cmp} {step}:\n{out}"));
        l.split_whitespace().map(str::to_string).collect()
    };
    // field cmp step (t=..) on max|a-b| at max-rel at verdict
    let dy2 = row("DY", "2");
    assert_eq!(dy2[4], "nodes", "{dy2:?}");
    assert_eq!(dy2[5], format!("{delta:.6e}"), "{dy2:?}");
    assert_eq!(dy2[6], mesh.node_names[5], "{dy2:?}");
    let rel = delta / base.abs().max(v2[5 * 2 + 1].abs());
    assert_eq!(dy2[7], format!("{rel:.6e}"), "{dy2:?}");
    assert_eq!(dy2[8], mesh.node_names[5], "{dy2:?}");
    assert_eq!(dy2[9], "DIFFERENT", "{dy2:?}");
    let dx2 = row("DX", "2");
    assert_eq!((dx2[5].as_str(), dx2[9].as_str()), ("0.000000e0", "OK"), "{dx2:?}");

    // Within a loose tolerance.
    let o = aster().arg("diff").arg(&a).arg(&b).args(["--atol", "1e-2"]).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{:?}", text(&o));
    // Errors: a missing file exits with 2.
    let o = aster().arg("diff").arg(&a).arg(dir.join("missing.rmed")).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains("missing.rmed"), "{:?}", text(&o));
}

/// Run a command file expected to fail; returns stderr.
fn run_fail(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) -> String {
    let o = run_comm(dir, name, src, units);
    let (out, err) = text(&o);
    assert!(!o.status.success(), "{name} should have failed:\n{out}\n{err}");
    err
}

#[test]
fn bad_input_is_a_located_error() {
    let dir = scratch!("bad");
    let good = dir.join("good.med");
    med::write_mesh(&good, &box_mesh(CellType::Quad4, &[2, 2], &[1.0, 1.0]).unwrap(), "MAIL").unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let truncated = dir.join("truncated.med");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let text_file = dir.join("notmed.med");
    std::fs::write(&text_file, "this is not an HDF5 file\n".repeat(100)).unwrap();
    let read = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\nFIN()\n";

    let err = run_fail(&dir, "trunc", read, &[(20, &truncated)]);
    assert!(err.contains("trunc.comm:2:") && err.contains("truncated"), "{err}");
    let err = run_fail(&dir, "nothdf", read, &[(20, &text_file)]);
    assert!(err.contains("nothdf.comm:2:") && err.contains("not an HDF5 file"), "{err}");
    let err = run_fail(
        &dir,
        "nomesh",
        "DEBUT()\n\nMA = LIRE_MAILLAGE(FORMAT='MED', NOM_MED='NOPE')\nFIN()\n",
        &[(20, &good)],
    );
    assert!(err.contains("nomesh.comm:3:") && err.contains("no mesh named 'NOPE'"), "{err}");
    let err = run_fail(&dir, "nounit", "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=21)\nFIN()\n", &[(20, &good)]);
    assert!(err.contains("nounit.comm:2:") && err.contains("unit 21"), "{err}");
    let err = run_fail(
        &dir,
        "nogroup",
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\nMA = DEFI_GROUP(reuse=MA, MAILLAGE=MA,\n    CREA_GROUP_NO=_F(GROUP_MA='NOPE'))\nFIN()\n",
        &[(20, &good)],
    );
    assert!(err.contains("nogroup.comm:4:") && err.contains("group of cells 'NOPE' is not in mesh MA"), "{err}");
    let err = run_fail(
        &dir,
        "nonode",
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\nDEFI_GROUP(reuse=MA, MAILLAGE=MA,\n    CREA_GROUP_NO=_F(NOM='X', NOEUD=('N1', 'N999')))\nFIN()\n",
        &[(20, &good)],
    );
    assert!(err.contains("nonode.comm:4:") && err.contains("node 'N999' is not in mesh MA"), "{err}");
    let err = run_fail(
        &dir,
        "dupgroup",
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\nDEFI_GROUP(reuse=MA, MAILLAGE=MA,\n    CREA_GROUP_NO=_F(GROUP_MA='BAS'))\nFIN()\n",
        &[(20, &good)],
    );
    assert!(err.contains("dupgroup.comm:4:") && err.contains("group of nodes 'BAS' already exists"), "{err}");
    let err = run_fail(
        &dir,
        "fmt",
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\nIMPR_RESU(FORMAT='IDEAS', RESU=_F(MAILLAGE=MA))\nFIN()\n",
        &[(20, &good)],
    );
    assert!(err.contains("fmt.comm:3:") && err.contains("FORMAT='IDEAS' is not supported yet"), "{err}");
    // `aster mesh info` on damaged files.
    for f in [&truncated, &text_file] {
        let o = aster().args(["mesh", "info"]).arg(f).output().unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(text(&o).1.contains(f.file_name().unwrap().to_str().unwrap()), "{:?}", text(&o));
    }
}

/// LIRE_MAILLAGE VERI_MAIL: an orphan node and double cells are alarms in the message file, a cell
/// repeating a node stops the command by name unless VERIF='NON'.
#[test]
fn veri_mail_warns_and_stops_as_code_aster() {
    let dir = scratch!("veri_mail");
    let mail = "COOR_2D\nN1 0. 0.\nN2 1. 0.\nN3 1. 1.\nN4 0. 1.\nN5 5. 5.\nFINSF\n\
                QUAD4\nM1 N1 N2 N3 N4\nM2 N2 N3 N4 N1\nFINSF\nSEG2\nM3 N1 N2\nFINSF\nFIN\n";
    let path = dir.join("m.mail");
    std::fs::write(&path, mail).unwrap();
    let comm = |veri: &str| format!("DEBUT()\nM = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20{veri})\nFIN()\n");
    let o = run_comm(&dir, "alarms", &comm(", VERI_MAIL=_F(VERIF='OUI')"), &[(20, &path)]);
    let (_, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let mess = std::fs::read_to_string(dir.join("alarms.out/alarms.mess")).unwrap();
    assert!(mess.contains("<A> LIRE_MAILLAGE: VERI_MAIL: 1 node(s) belong to no cell (orphan nodes): N5"), "{mess}");
    assert!(mess.contains("(double cells): M2 and M1 (QUAD4)"), "{mess}");
    // A degenerate cell is an error: the command stops, naming the cell; VERIF='NON' reads the mesh.
    std::fs::write(&path, mail.replace("M3 N1 N2", "M3 N1 N1")).unwrap();
    let o = run_comm(&dir, "error", &comm(", VERI_MAIL=_F(VERIF='OUI')"), &[(20, &path)]);
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("cell M3 (SEG2) is degenerate"), "{err}");
    run_ok(&dir, "skipped", &comm(", VERI_MAIL=_F(VERIF='NON')"), &[(20, &path)]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A command file of Code_Aster 2025 names cells and nodes by their number (`M2`, `N3`) whatever names
/// the mesh file gave them (erreu13a.mail's GAUCHE, NO3): such a name is read as a number where no
/// entity bears it, while a name the mesh has keeps designating its entity.
#[test]
fn numbered_names_designate_entities_as_in_code_aster_2025() {
    let dir = scratch!("numbered");
    let mail = "COOR_2D\nNO1 0. 0.\nNO2 1. 0.\nNO3 1. 1.\nM1 0. 1.\nFINSF\n\
                SEG2\nBAS NO1 NO2\nDROITE NO2 NO3\nM1 NO3 M1\nFINSF\nFIN\n";
    let path = dir.join("m.mail");
    std::fs::write(&path, mail).unwrap();
    let comm = "DEBUT()\nM = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
                M = DEFI_GROUP(reuse=M, MAILLAGE=M, CREA_GROUP_MA=(_F(NOM='G2', MAILLE='M2'), _F(NOM='G1', MAILLE='M1')),\n\
                CREA_GROUP_NO=_F(NOM='P', NOEUD=('N3', 'M1')))\n\
                IMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(MAILLAGE=M))\nFIN()\n";
    let med_out = dir.join("out.med");
    run_ok(&dir, "numbered", comm, &[(20, &path), (80, &med_out)]);
    let m = med::read_mesh(&med_out, None).unwrap();
    // M2 is the second cell (DROITE); M1 is the cell named M1 (the third), not the first.
    assert_eq!(m.cell_groups["G2"], [1]);
    assert_eq!(m.cell_groups["G1"], [2]);
    assert_eq!(names(&m, &m.node_groups["P"]), ["NO3", "M1"]);
    let _ = std::fs::remove_dir_all(&dir);
}
