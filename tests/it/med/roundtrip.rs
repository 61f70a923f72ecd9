//! MED reader/writer tests.
//!
//! The astest meshes are read in place from `../shared/astest` (the tests
//! that need them print a message and pass when the folder is absent).
//! Cross-checks use MED-fichier's own tools: python3-med (through
//! `scripts/med_check.py`, run with `/usr/bin/python3`), `mdump` and
//! `medconforme` (Debian packages `python3-med`, `libmed-tools`); without
//! them those checks are skipped with a message.

use aster::med::{self, types::MedType};
use aster::mesh::{CellType, Mesh};
use hdf5_metno as hdf5;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn astest_dir() -> Option<PathBuf> {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/astest");
    if d.is_dir() {
        Some(d)
    } else {
        println!("SKIP: {} is absent", d.display());
        None
    }
}

fn med_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("mmed") | Some("med")))
        .collect();
    v.sort();
    v
}

fn have_python_med() -> bool {
    let ok = Command::new("/usr/bin/python3")
        .args(["-c", "import med.medfile"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ok {
        println!("SKIP python3-med cross-checks: /usr/bin/python3 cannot import med (apt-get install python3-med)");
    }
    ok
}

fn have_tool(name: &str) -> bool {
    let ok = Path::new("/usr/bin").join(name).exists();
    if !ok {
        println!("SKIP {name} checks: not installed (apt-get install libmed-tools)");
    }
    ok
}

fn med_check(args: &[&str]) -> Vec<String> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/med_check.py");
    let out = Command::new("/usr/bin/python3").arg(script).args(args).output().unwrap();
    assert!(out.status.success(), "med_check.py {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(str::to_string).collect()
}

/// What python3-med sees in a mesh file.
#[derive(Debug, PartialEq)]
struct PyMesh {
    dim: usize,
    coords: Vec<Vec<f64>>,
    types: BTreeMap<String, usize>,
    conn: BTreeMap<String, Vec<Vec<usize>>>,
    node_groups: BTreeMap<String, usize>,
    cell_groups: BTreeMap<String, usize>,
}

fn py_mesh(path: &Path) -> PyMesh {
    let mut m = PyMesh {
        dim: 0,
        coords: vec![],
        types: BTreeMap::new(),
        conn: BTreeMap::new(),
        node_groups: BTreeMap::new(),
        cell_groups: BTreeMap::new(),
    };
    for line in med_check(&["mesh", path.to_str().unwrap()]) {
        let w: Vec<&str> = line.split(' ').collect();
        match w[0] {
            "MESH" => m.dim = w[2].parse().unwrap(),
            "COOR" => m.coords.push(w[1..].iter().map(|x| x.parse().unwrap()).collect()),
            "TYPE" => {
                m.types.insert(w[1].to_string(), w[2].parse().unwrap());
            }
            "CONN" => {
                m.conn.entry(w[1].to_string()).or_default().push(w[2..].iter().map(|x| x.parse().unwrap()).collect())
            }
            "NGROUP" => {
                m.node_groups.insert(w[1].to_string(), w[2].parse().unwrap());
            }
            "CGROUP" => {
                m.cell_groups.insert(w[1].to_string(), w[2].parse().unwrap());
            }
            other => panic!("unexpected med_check line {other}"),
        }
    }
    m
}

/// The same view computed from our `Mesh` (MED node order, 1-based).
fn our_view(mesh: &Mesh) -> PyMesh {
    let mut conn: BTreeMap<String, Vec<Vec<usize>>> = BTreeMap::new();
    let mut types = BTreeMap::new();
    for (c, t) in mesh.cells.iter().zip(&mesh.cell_types) {
        let mt = MedType::of(*t);
        *types.entry(mt.med_name.to_string()).or_insert(0) += 1;
        conn.entry(mt.med_name.to_string()).or_default().push(mt.to_med(c).iter().map(|n| n + 1).collect());
    }
    PyMesh {
        dim: mesh.dim,
        coords: mesh.coords.iter().map(|c| c[..mesh.dim].to_vec()).collect(),
        types,
        conn,
        node_groups: mesh.node_group_sizes(),
        cell_groups: mesh.cell_group_sizes(),
    }
}

fn assert_same_bits(a: &PyMesh, b: &PyMesh, what: &str) {
    assert_eq!(a.coords.len(), b.coords.len(), "{what}: node count");
    for (i, (x, y)) in a.coords.iter().zip(&b.coords).enumerate() {
        let xb: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
        let yb: Vec<u64> = y.iter().map(|v| v.to_bits()).collect();
        assert_eq!(xb, yb, "{what}: coordinates of node {i}");
    }
    assert_eq!(a, b, "{what}");
}

fn assert_same_mesh(a: &Mesh, b: &Mesh, what: &str) {
    assert_eq!(a.dim, b.dim, "{what}: dim");
    assert_eq!(a.coords.len(), b.coords.len(), "{what}: nodes");
    for (i, (x, y)) in a.coords.iter().zip(&b.coords).enumerate() {
        for k in 0..3 {
            assert_eq!(x[k].to_bits(), y[k].to_bits(), "{what}: node {i} coordinate {k}");
        }
    }
    assert_eq!(a.node_names, b.node_names, "{what}: node names");
    assert_eq!(a.cell_types, b.cell_types, "{what}: cell types");
    assert_eq!(a.cells, b.cells, "{what}: connectivity");
    assert_eq!(a.cell_names, b.cell_names, "{what}: cell names");
    assert_eq!(a.node_groups, b.node_groups, "{what}: node groups");
    assert_eq!(a.cell_groups, b.cell_groups, "{what}: cell groups");
}

fn mdump_ok(path: &Path) {
    let out = Command::new("/usr/bin/mdump")
        .arg(path)
        .args(["NODALE", "FULL_INTERLACE", "1"])
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("FIN DU DUMP"),
        "mdump rejects {}: status {:?}\n{}\n{}",
        path.display(),
        out.status,
        text,
        String::from_utf8_lossy(&out.stderr)
    );
}

fn medconforme_ok(path: &Path) {
    let out = Command::new("/usr/bin/medconforme").arg(path).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !text.contains("non conforme"), "medconforme rejects {}: {text}", path.display());
}

fn describe(path: &Path, mesh: &Mesh) {
    let counts: Vec<String> = mesh.cell_type_counts().iter().map(|(t, n)| format!("{}:{n}", t.name())).collect();
    println!(
        "{}: {} nodes, {} cells [{}]",
        path.file_name().unwrap().to_string_lossy(),
        mesh.nnodes(),
        mesh.ncells(),
        counts.join(", ")
    );
    println!("  node groups {:?}", mesh.node_group_sizes());
    println!("  cell groups {:?}", mesh.cell_group_sizes());
}

#[test]
fn astest_meshes_load_and_agree_with_python_med() {
    let Some(dir) = astest_dir() else { return };
    let files = med_files(&dir);
    assert!(!files.is_empty());
    let py = have_python_med();
    for f in &files {
        let mesh = med::read_mesh(f, None).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        describe(f, &mesh);
        assert!(mesh.nnodes() > 0 && mesh.ncells() > 0);
        // Cells come type by type in MED geometry-code order.
        let ranks: Vec<usize> = mesh.cell_types.iter().map(|t| MedType::rank(*t)).collect();
        assert!(ranks.windows(2).all(|w| w[0] <= w[1]), "{}: cell order", f.display());
        if py {
            assert_same_bits(&py_mesh(f), &our_view(&mesh), &f.display().to_string());
        }
    }
}

#[test]
fn astest_meshes_roundtrip() {
    let Some(dir) = astest_dir() else { return };
    let tmp = scratch!("roundtrip");
    let py = have_python_med();
    let mdump = have_tool("mdump");
    let conf = have_tool("medconforme");
    for f in med_files(&dir) {
        let a = med::read_mesh(&f, None).unwrap();
        let out = tmp.join(format!("{}.med", f.file_stem().unwrap().to_string_lossy()));
        med::write_mesh(&out, &a, "MAIL").unwrap();
        let b = med::read_mesh(&out, Some("MAIL")).unwrap();
        assert_same_mesh(&a, &b, &f.display().to_string());
        if mdump {
            mdump_ok(&out);
        }
        if conf {
            medconforme_ok(&out);
        }
        if py {
            assert_same_bits(&py_mesh(&f), &py_mesh(&out), &out.display().to_string());
        }
    }
    // No temporary files left behind.
    for e in std::fs::read_dir(&tmp).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp"), "leftover {name}");
    }
    let _ = std::fs::remove_dir_all(&tmp);
}

/// A mesh with one cell of every type, cells deliberately out of MED order.
fn all_types_mesh() -> Mesh {
    let mut m = Mesh { dim: 3, ..Mesh::default() };
    for i in 0..30 {
        let x = i as f64;
        m.coords.push([x * 0.1, (x * 0.37).sin(), 1.0 / (x + 3.0)]);
        m.node_names.push(format!("P{i}"));
    }
    let mut types = CellType::ALL.to_vec();
    types.reverse();
    for (k, t) in types.iter().enumerate() {
        m.cells.push((0..t.nnodes()).map(|j| (j * 7 + k) % 30).collect());
        m.cell_types.push(*t);
        m.cell_names.push(format!("C{}", t.name()));
    }
    m.node_groups.insert("ALL".into(), (0..30).collect());
    m.node_groups.insert("EVEN".into(), (0..30).step_by(2).collect());
    m.node_groups.insert("A_VERY_LONG_GROUP_NAME_OF_MORE_THAN_24".into(), vec![3, 4]);
    m.cell_groups.insert("VOLUMES".into(), (0..m.cells.len()).filter(|&c| m.cell_types[c].dim() == 3).collect());
    m.cell_groups.insert("FIRST".into(), vec![0]);
    m
}

#[test]
fn all_cell_types_roundtrip_in_code_aster_order() {
    let tmp = scratch!("alltypes");
    let m = all_types_mesh();
    let out = tmp.join("all.med");
    med::write_mesh(&out, &m, "ALLTYPES").unwrap();
    let b = med::read_mesh(&out, None).unwrap();
    // Read back in Code_Aster 2025's order (MeshReader): by its type order, not by MED geometry code
    // (which would put PYRAM5 before PENTA6 and HEXA8 before TETRA10).
    let names: Vec<String> = CellType::ALL.iter().map(|t| format!("C{}", t.name())).collect();
    assert_eq!(b.cell_names, names);
    let mut order: Vec<usize> = (0..m.ncells()).collect();
    order.sort_by_key(|&c| MedType::rank(m.cell_types[c]));
    let new_of_old: BTreeMap<usize, usize> = order.iter().enumerate().map(|(new, &old)| (old, new)).collect();
    let mut expected = m.clone();
    expected.cells = order.iter().map(|&c| m.cells[c].clone()).collect();
    expected.cell_types = order.iter().map(|&c| m.cell_types[c]).collect();
    expected.cell_names = order.iter().map(|&c| m.cell_names[c].clone()).collect();
    for v in expected.cell_groups.values_mut() {
        *v = v.iter().map(|c| new_of_old[c]).collect();
        v.sort();
    }
    assert_same_mesh(&expected, &b, "all types");
    // Writing again is stable.
    let out2 = tmp.join("all2.med");
    med::write_mesh(&out2, &b, "ALLTYPES").unwrap();
    assert_same_mesh(&b, &med::read_mesh(&out2, None).unwrap(), "all types, twice");
    if have_python_med() {
        // python3-med's connectivity is our connectivity through the MED permutation.
        assert_same_bits(&py_mesh(&out), &our_view(&b), "all types vs python3-med");
    }
    if have_tool("mdump") {
        mdump_ok(&out);
    }
    if have_tool("medconforme") {
        medconforme_ok(&out);
    }
    let _ = std::fs::remove_dir_all(&tmp);
}

fn small_mesh() -> Mesh {
    let mut m = Mesh { dim: 2, ..Mesh::default() };
    for (i, c) in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.0], [2.0, 1.0]].iter().enumerate() {
        m.coords.push([c[0], c[1], 0.0]);
        m.node_names.push(format!("N{}", i + 1));
    }
    m.cells = vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2], vec![0, 1]];
    m.cell_types = vec![CellType::Quad4, CellType::Quad4, CellType::Seg2];
    m.cell_names = vec!["M1".into(), "M2".into(), "M3".into()];
    m.cell_groups.insert("BAS".into(), vec![2]);
    m.node_groups.insert("GAUCHE".into(), vec![0, 3]);
    m
}

#[test]
fn depl_field_over_two_steps() {
    let tmp = scratch!("field");
    let m = small_mesh();
    let out = tmp.join("depl.med");
    med::write_mesh(&out, &m, "MA").unwrap();
    let nn = m.nnodes();
    let step = |s: f64| -> Vec<f64> { (0..nn * 2).map(|k| s * (k as f64 + 0.25) / 3.0).collect() };
    let steps = vec![(1, 0.5, step(1.0)), (2, 1.0, step(-2.0))];
    med::write_node_field(&out, "MA", "DEPL", &["DX", "DY"], &steps).unwrap();

    let f = med::read_node_field(&out, "DEPL").unwrap();
    assert_eq!(f.mesh_name, "MA");
    assert_eq!(f.components, vec!["DX", "DY"]);
    assert_eq!(f.steps, steps);
    // The mesh is still there and unchanged.
    assert_same_mesh(&med::read_mesh(&out, None).unwrap(), &med::read_mesh(&out, Some("MA")).unwrap(), "mesh");

    // Adding a step later, and refusing a repeated one.
    let more = vec![(3, 1.5, step(4.0))];
    med::write_node_field(&out, "MA", "DEPL", &["DX", "DY"], &more).unwrap();
    assert_eq!(med::read_node_field(&out, "DEPL").unwrap().steps.len(), 3);
    let err = med::write_node_field(&out, "MA", "DEPL", &["DX", "DY"], &more).unwrap_err();
    assert!(err.msg.contains("already has step 3"), "{}", err.msg);
    assert_eq!(med::read_node_field(&out, "DEPL").unwrap().steps.len(), 3, "failed update left the file as it was");
    let err = med::write_node_field(&out, "MA", "DEPL2", &["DX"], &[(1, 0.0, vec![0.0; 3])]).unwrap_err();
    assert!(err.msg.contains("values for 6 nodes"), "{}", err.msg);

    if have_python_med() {
        let lines = med_check(&["field", out.to_str().unwrap(), "DEPL"]);
        assert_eq!(lines[0], "COMP DX DY");
        let all: Vec<(i32, f64, Vec<f64>)> = steps.iter().chain(&more).cloned().collect();
        assert_eq!(lines.len(), 1 + all.len());
        for (line, (numdt, time, vals)) in lines[1..].iter().zip(&all) {
            let w: Vec<&str> = line.split(' ').collect();
            assert_eq!(w[0], "STEP");
            assert_eq!(w[1].parse::<i32>().unwrap(), *numdt);
            assert_eq!(w[2].parse::<f64>().unwrap().to_bits(), time.to_bits());
            let got: Vec<u64> = w[3..].iter().map(|x| x.parse::<f64>().unwrap().to_bits()).collect();
            let want: Vec<u64> = vals.iter().map(|v| v.to_bits()).collect();
            assert_eq!(got, want, "step {numdt}");
        }
    }
    if have_tool("mdump") {
        mdump_ok(&out);
    }
    if have_tool("medconforme") {
        medconforme_ok(&out);
    }
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn bad_input_gives_clear_errors() {
    let tmp = scratch!("bad");
    let good = tmp.join("good.med");
    med::write_mesh(&good, &small_mesh(), "MA").unwrap();

    // Not HDF5 at all.
    let text = tmp.join("text.med");
    std::fs::write(&text, "this is not a MED file\n").unwrap();
    let e = med::read_mesh(&text, None).unwrap_err();
    assert_eq!(e.kind, aster::diag::ErrorKind::Io);
    assert!(e.msg.contains("text.med") && e.msg.contains("not an HDF5 file"), "{}", e.msg);

    // Truncated.
    let bytes = std::fs::read(&good).unwrap();
    let trunc = tmp.join("trunc.med");
    std::fs::write(&trunc, &bytes[..bytes.len() / 2]).unwrap();
    let e = med::read_mesh(&trunc, None).unwrap_err();
    assert_eq!(e.kind, aster::diag::ErrorKind::Io);
    assert!(e.msg.contains("trunc.med"), "{}", e.msg);
    println!("truncated: {}", e.msg);

    // Missing file.
    let e = med::read_mesh(&tmp.join("absent.med"), None).unwrap_err();
    assert!(e.msg.contains("absent.med"), "{}", e.msg);

    // Missing mesh name: the message lists the meshes present.
    let e = med::read_mesh(&good, Some("OTHER")).unwrap_err();
    assert!(e.msg.contains("good.med") && e.msg.contains("'OTHER'") && e.msg.contains("MA"), "{}", e.msg);
    assert_eq!(med::list_meshes(&good).unwrap(), vec!["MA".to_string()]);

    // Unknown cell type.
    let odd = tmp.join("odd.med");
    std::fs::copy(&good, &odd).unwrap();
    {
        let f = hdf5::File::open_rw(&odd).unwrap();
        let mai = f.group("ENS_MAA/MA/-0000000000000000001-0000000000000000001/MAI").unwrap();
        mai.relink("QU4", "XX4").unwrap();
    }
    let e = med::read_mesh(&odd, None).unwrap_err();
    assert!(e.msg.contains("odd.med") && e.msg.contains("XX4"), "{}", e.msg);

    // A missing field.
    let e = med::read_node_field(&good, "DEPL").unwrap_err();
    assert!(e.msg.contains("no field named 'DEPL'"), "{}", e.msg);

    // Writing a name that does not fit leaves no file behind.
    let mut m = small_mesh();
    m.node_names[0] = "A_NODE_NAME_LONGER_THAN_16".into();
    let bad = tmp.join("bad.med");
    let e = med::write_mesh(&bad, &m, "MA").unwrap_err();
    assert!(e.msg.contains("longer than 16"), "{}", e.msg);
    let left: Vec<_> = std::fs::read_dir(&tmp)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".bad") || n == "bad.med")
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let _ = std::fs::remove_dir_all(&tmp);
}
