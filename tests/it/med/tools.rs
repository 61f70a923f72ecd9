//! MED files through other programs: IMPR_RESU results read back by
//! MED-fichier (`mdump`, python3-med) and meshio; a gmsh MED mesh read by
//! us and by `aster mesh info`.
//!
//! The reference tools come from Debian (`libmed-tools`, `python3-med`, run
//! with `/usr/bin/python3`) and PyPI (`meshio` with `h5py`, `gmsh`, for the
//! `python3` first on PATH). A sub-test whose tool is absent prints
//! `SKIPPED` with the reason and passes. Expected values are computed here:
//! the analytic displacement of the scene, and counts reported by gmsh itself.

use crate::common::*;
use aster::med::{self, types::MedType};
use aster::mesh::{CellType, Mesh};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

/// Does `python` import every module of `modules`? Otherwise the reason.
fn python_has(python: &str, modules: &str) -> Result<(), String> {
    match Command::new(python).args(["-c", &format!("import {modules}")]).output() {
        Ok(o) if o.status.success() => Ok(()),
        Ok(o) => Err(format!("{python} cannot import {modules}: {}", text(&o).1.lines().last().unwrap_or(""))),
        Err(e) => Err(format!("{python} cannot be run: {e}")),
    }
}

fn skipped(what: &str, why: &str) {
    println!("SKIPPED {what}: {why}");
}

/// Run a Python script with `python`; its standard output.
fn python(python: &str, script: &str, args: &[&str]) -> String {
    let o = Command::new(python).arg("-c").arg(script).args(args).output().unwrap();
    let (out, err) = text(&o);
    assert!(o.status.success(), "{python} script failed:\n{script}\nstdout:\n{out}\nstderr:\n{err}");
    out
}

fn floats(words: &[&str]) -> Vec<f64> {
    words.iter().map(|w| w.parse::<f64>().unwrap_or_else(|_| panic!("not a number: {w}"))).collect()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The 2D scene with extra commands before its FIN(), run with the scene's
/// mesh on unit 20 and the given output units.
fn run_scene(dir: &Path, name: &str, extra: &str, units: &[(i64, &Path)]) -> Output {
    let scene = std::fs::read_to_string(root().join("comm/block_tension_2d.comm")).unwrap();
    let at = scene.rfind("FIN()").expect("the scene ends with FIN()");
    let src = format!("{}{extra}\n{}", &scene[..at], &scene[at..]);
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, src).unwrap();
    let mut cmd = aster();
    cmd.arg("run").arg(&comm).arg("--out").arg(dir.join(format!("{name}.out"))).arg("-q");
    cmd.arg("--unit").arg(format!("20={}", root().join("med/block_quad8.med").display()));
    for (u, p) in units {
        cmd.arg("--unit").arg(format!("{u}={}", p.display()));
    }
    cmd.output().unwrap()
}

fn run_scene_ok(dir: &Path, name: &str, extra: &str, units: &[(i64, &Path)]) {
    let o = run_scene(dir, name, extra, units);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{name} failed:\nstdout:\n{out}\nstderr:\n{err}");
}

/// Material and load of comm/block_tension_2d.comm.
const E: f64 = 210000.0;
const NU: f64 = 0.3;
const P: f64 = 100.0;

#[test]
fn impr_resu_result_read_by_med_tools_and_meshio() {
    let dir = scratch!("result");
    let rmed = dir.join("out.rmed");
    run_scene_ok(
        &dir,
        "scene",
        "IMPR_RESU(FORMAT='MED', UNITE=80, RESU=_F(RESULTAT=RESU, NOM_CHAM=('DEPL','SIGM_NOEU')))",
        &[(80, &rmed)],
    );

    // Our reader: the mesh of the model, named after the mesh concept, with
    // the coordinates of the input mesh, and the analytic displacement.
    let input = med::read_mesh(&root().join("med/block_quad8.med"), None).unwrap();
    let mesh = med::read_mesh(&rmed, Some("MA")).unwrap();
    assert_eq!(bits(&mesh.coords.concat()), bits(&input.coords.concat()));
    assert_eq!(mesh.cells, input.cells);
    assert_eq!(med::list_fields(&rmed).unwrap(), vec!["RESU____DEPL", "RESU____SIGM_NOEU"]);
    let depl = med::read_node_field(&rmed, "RESU____DEPL").unwrap();
    assert_eq!(depl.mesh_name, "MA");
    assert_eq!(depl.components, vec!["DX", "DY"]);
    assert_eq!(depl.steps.len(), 1);
    let (numdt, time, values) = &depl.steps[0];
    assert_eq!((*numdt, *time), (1, 0.0));
    assert_eq!(values.len(), 2 * mesh.nnodes());
    for (i, c) in mesh.coords.iter().enumerate() {
        let ux = (1.0 - NU * NU) * P * c[0] / E;
        let uy = -NU * (1.0 + NU) * P * c[1] / E;
        assert!((values[2 * i] - ux).abs() <= 1e-12, "DX at node {i}: {} vs {ux}", values[2 * i]);
        assert!((values[2 * i + 1] - uy).abs() <= 1e-12, "DY at node {i}: {} vs {uy}", values[2 * i + 1]);
    }
    let sig = med::read_node_field(&rmed, "RESU____SIGM_NOEU").unwrap();
    assert_eq!(sig.components, vec!["SIXX", "SIYY", "SIZZ", "SIXY"]);
    for (i, s) in sig.steps[0].2.chunks(4).enumerate() {
        for (k, want) in [P, 0.0, NU * P, 0.0].into_iter().enumerate() {
            assert!((s[k] - want).abs() <= 1e-9 * P, "SIGM_NOEU component {k} at node {i}: {} vs {want}", s[k]);
        }
    }

    // mdump (MED-fichier) dumps the whole file, fields included.
    match Command::new("mdump")
        .arg(&rmed)
        .args(["NODALE", "FULL_INTERLACE", "1"])
        .stdin(std::process::Stdio::null())
        .output()
    {
        Err(e) => skipped("mdump", &format!("cannot run mdump ({e}); apt-get install libmed-tools")),
        Ok(o) => {
            let (out, err) = text(&o);
            assert!(o.status.success() && out.contains("FIN DU DUMP"), "mdump rejects the file:\n{out}\n{err}");
            for f in ["RESU____DEPL", "RESU____SIGM_NOEU"] {
                assert!(out.contains(&format!("CHAMP |{f}|")), "mdump does not show {f}:\n{out}");
            }
            println!("mdump: OK");
        }
    }

    // python3-med reads the same DEPL values, bit for bit.
    match python_has("/usr/bin/python3", "med.medfield") {
        Err(why) => skipped("python3-med", &format!("{why}; apt-get install python3-med")),
        Ok(()) => {
            let script = root().join("scripts/med_check.py");
            let o = Command::new("/usr/bin/python3")
                .arg(&script)
                .args(["field", rmed.to_str().unwrap(), "RESU____DEPL"])
                .output()
                .unwrap();
            let (out, err) = text(&o);
            assert!(o.status.success(), "med_check.py field failed:\n{err}");
            let lines: Vec<Vec<&str>> = out.lines().map(|l| l.split(' ').collect()).collect();
            assert_eq!(lines[0], vec!["COMP", "DX", "DY"]);
            assert_eq!(lines.len(), 2, "one step expected:\n{out}");
            assert_eq!(lines[1][..3], ["STEP", "1", "0.0"]);
            assert_eq!(bits(&floats(&lines[1][3..])), bits(values), "python3-med DEPL values");
            println!("python3-med: OK");
        }
    }

    // meshio opens the file and sees the same points, cells and point data.
    match python_has("python3", "meshio, h5py") {
        Err(why) => skipped("meshio", &format!("{why}; pip install meshio h5py")),
        Ok(()) => {
            let script = r#"
import sys, meshio
m = meshio.read(sys.argv[1], file_format="med")
for p in m.points:
    print("POINT", *[repr(float(x)) for x in p])
for block in m.cells:
    for c in block.data:
        print("CELL", block.type, *[int(n) for n in c])
for name, data in m.point_data.items():
    for row in data.reshape(len(m.points), -1):
        print("DATA", name, *[repr(float(x)) for x in row])
"#;
            let out = python("python3", script, &[rmed.to_str().unwrap()]);
            let mut points = Vec::new();
            let mut cells: BTreeMap<String, Vec<Vec<usize>>> = BTreeMap::new();
            let mut data: BTreeMap<String, Vec<f64>> = BTreeMap::new();
            for l in out.lines() {
                let w: Vec<&str> = l.split(' ').collect();
                match w[0] {
                    "POINT" => points.push(floats(&w[1..])),
                    "CELL" => cells
                        .entry(w[1].to_string())
                        .or_default()
                        .push(w[2..].iter().map(|n| n.parse().unwrap()).collect()),
                    "DATA" => data.entry(w[1].to_string()).or_default().extend(floats(&w[2..])),
                    _ => panic!("unexpected meshio line {l}"),
                }
            }
            let ours: Vec<Vec<f64>> = mesh.coords.iter().map(|c| c[..mesh.dim].to_vec()).collect();
            assert_eq!(bits(&points.concat()), bits(&ours.concat()), "meshio points");
            // Our cells per type, in MED node order, 0-based (meshio's view).
            let meshio_name = |t: CellType| match t {
                CellType::Seg2 => "line",
                CellType::Seg3 => "line3",
                CellType::Tria3 => "triangle",
                CellType::Tria6 => "triangle6",
                CellType::Quad4 => "quad",
                CellType::Quad8 => "quad8",
                other => panic!("no meshio name for {other:?} in this test"),
            };
            let mut want: BTreeMap<String, Vec<Vec<usize>>> = BTreeMap::new();
            for (c, t) in mesh.cells.iter().zip(&mesh.cell_types) {
                want.entry(meshio_name(*t).to_string()).or_default().push(MedType::of(*t).to_med(c));
            }
            assert_eq!(cells, want, "meshio cells");
            assert_eq!(bits(&data["RESU____DEPL"]), bits(values), "meshio DEPL point data");
            assert_eq!(bits(&data["RESU____SIGM_NOEU"]), bits(&sig.steps[0].2), "meshio SIGM_NOEU point data");
            println!("meshio: OK");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn impr_resu_several_occurrences_components_and_appending() {
    let dir = scratch!("occ");
    let (a, b) = (dir.join("a.rmed"), dir.join("b.rmed"));
    let extra = "
IMPR_RESU(FORMAT='MED', UNITE=80, RESU=(_F(MAILLAGE=MA), _F(RESULTAT=RESU, NOM_CHAM=('DEPL', 'SIGM_NOEU'))))
IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(RESULTAT=RESU, NOM_CMP='DX', INST=0.0))
IMPR_RESU(FORMAT='MED', UNITE=81, RESU=_F(RESULTAT=RESU, NOM_CHAM='SIGM_NOEU', NOM_CHAM_MED='STRESS', NUME_ORDRE=1))
";
    run_scene_ok(&dir, "occ", extra, &[(80, &a), (81, &b)]);
    assert_eq!(med::list_meshes(&a).unwrap(), vec!["MA"]);
    assert_eq!(med::list_fields(&a).unwrap(), vec!["RESU____DEPL", "RESU____SIGM_NOEU"]);
    // Unit 81: DX only (SIEF_ELGA, SIGM_ELNO and SIGM_NOEU have no DX: alarms),
    // then STRESS added to the same file by the next call.
    assert_eq!(med::list_meshes(&b).unwrap(), vec!["MA"]);
    assert_eq!(med::list_fields(&b).unwrap(), vec!["RESU____DEPL", "STRESS"]);
    let full = med::read_node_field(&a, "RESU____DEPL").unwrap();
    let dx = med::read_node_field(&b, "RESU____DEPL").unwrap();
    assert_eq!(dx.components, vec!["DX"]);
    let want: Vec<f64> = full.steps[0].2.iter().step_by(2).copied().collect();
    assert_eq!(bits(&dx.steps[0].2), bits(&want));
    let stress = med::read_node_field(&b, "STRESS").unwrap();
    let sig = med::read_node_field(&a, "RESU____SIGM_NOEU").unwrap();
    assert_eq!(stress.components, sig.components);
    assert_eq!(bits(&stress.steps[0].2), bits(&sig.steps[0].2));
    let mess = std::fs::read_to_string(dir.join("occ.out/occ.mess")).unwrap();
    assert!(mess.contains("SIGM_NOEU of result RESU has none of the components DX"), "{mess}");
    assert!(mess.contains("SIGM_ELNO of result RESU has none of the components DX"), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn impr_resu_errors_are_located() {
    let dir = scratch!("errors");
    let out = dir.join("e.rmed");
    let cases = [
        ("RESU=_F(RESULTAT=RESU, NUME_ORDRE=2)", "NUME_ORDRE", "no order number 2"),
        ("RESU=_F(RESULTAT=RESU, INST=5.0)", "INST", "no step at time 5"),
        ("RESU=_F(RESULTAT=RESU, NOM_CMP='DZ')", "NOM_CMP", "component DZ is in none"),
        ("RESU=_F(RESULTAT=RESU, NOM_CHAM=('DEPL', 'SIGM_NOEU'), NOM_CHAM_MED='U')", "NOM_CHAM_MED", "as many"),
    ];
    for (i, (resu, kw, msg)) in cases.iter().enumerate() {
        let name = format!("e{i}");
        let line = format!("IMPR_RESU(FORMAT='MED', UNITE=80, {resu})");
        let o = run_scene(&dir, &name, &line, &[(80, &out)]);
        let (stdout, err) = text(&o);
        assert!(!o.status.success(), "{resu}: should fail\n{stdout}");
        let all = stdout + &err;
        // Located at the keyword: file:line:col of the IMPR_RESU line, keyword
        // named. Keywords inside _F(...) carry the span of their factor
        // keyword (RESU) today; the keyword's own column is accepted too.
        let src = std::fs::read_to_string(dir.join(format!("{name}.comm"))).unwrap();
        let lineno = src.lines().position(|l| l.starts_with("IMPR_RESU(")).unwrap() + 1;
        let at = |k: &str| format!("{name}.comm:{lineno}:{}:", line.find(&format!("{k}=")).unwrap() + 1);
        assert!(all.contains(&at(kw)) || all.contains(&at("RESU")), "{resu}: not located at {kw}:\n{all}");
        assert!(all.contains(&format!("RESU/{kw}")) && all.contains(msg), "{resu}: message\n{all}");
        assert!(!out.exists(), "{resu}: a failed run delivers no file");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn gmsh_mesh_read_by_us_and_aster_mesh_info() {
    if let Err(why) = python_has("python3", "gmsh") {
        skipped("gmsh", &format!("{why}; pip install gmsh"));
        return;
    }
    let dir = scratch!("gmsh");
    let geo = dir.join("square.geo");
    let medf = dir.join("square.med");
    std::fs::write(
        &geo,
        r#"lc = 0.2;
Point(1) = {0, 0, 0, lc};
Point(2) = {2, 0, 0, lc};
Point(3) = {2, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("BOTTOM") = {1};
Physical Curve("TOP") = {3};
Physical Surface("PLATE") = {1};
"#,
    )
    .unwrap();
    // gmsh meshes, writes MED and reports what it wrote: the elements of the
    // physical groups (what gmsh saves by default), their nodes, and sizes.
    let script = r#"
import sys, gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(sys.argv[1])
gmsh.model.mesh.generate(2)
gmsh.write(sys.argv[2])
counts, nodes, seen = {}, set(), set()
for dim, tag in gmsh.model.getPhysicalGroups():
    size = 0
    for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
        types, etags, enodes = gmsh.model.mesh.getElements(dim, ent)
        for t, tags, conn in zip(types, etags, enodes):
            name = gmsh.model.mesh.getElementProperties(t)[0]
            size += len(tags)
            nodes.update(int(n) for n in conn)
            for e in tags:
                if int(e) not in seen:
                    seen.add(int(e))
                    counts[name] = counts.get(name, 0) + 1
    print("GROUP", gmsh.model.getPhysicalName(dim, tag), size)
for name, n in sorted(counts.items()):
    print("TYPE", name.replace(" ", "_"), n)
tags, coords, _ = gmsh.model.mesh.getNodes()
used = {int(t): coords[3 * i:3 * i + 3] for i, t in enumerate(tags) if int(t) in nodes}
print("NODES", len(used))
for t in sorted(used):
    print("COOR", *[repr(float(x)) for x in used[t]])
gmsh.finalize()
"#;
    let out = python("python3", script, &[geo.to_str().unwrap(), medf.to_str().unwrap()]);
    let (mut groups, mut types, mut nnodes, mut coords) = (BTreeMap::new(), BTreeMap::new(), 0usize, Vec::new());
    for l in out.lines() {
        let w: Vec<&str> = l.split(' ').collect();
        match w[0] {
            "GROUP" => {
                groups.insert(w[1].to_string(), w[2].parse::<usize>().unwrap());
            }
            "TYPE" => {
                let t = match w[1] {
                    "Line_2" => CellType::Seg2,
                    "Triangle_3" => CellType::Tria3,
                    other => panic!("unexpected gmsh element type {other}"),
                };
                types.insert(t, w[2].parse::<usize>().unwrap());
            }
            "NODES" => nnodes = w[1].parse().unwrap(),
            "COOR" => coords.push(floats(&w[1..])),
            _ => {} // gmsh's own messages
        }
    }
    assert!(nnodes > 0 && types.contains_key(&CellType::Tria3), "gmsh report:\n{out}");

    // Our reader.
    let m: Mesh = med::read_mesh(&medf, None).unwrap();
    assert_eq!(m.nnodes(), nnodes, "nodes");
    assert_eq!(m.cell_type_counts(), types, "cells per type");
    assert_eq!(m.cell_group_sizes(), groups, "cell groups");
    let key = |v: &Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
    let mut ours: Vec<Vec<f64>> = m.coords.iter().map(|c| c.to_vec()).collect();
    ours.sort_by_key(key);
    coords.sort_by_key(key);
    assert_eq!(ours, coords, "node coordinates (as sets)");

    // `aster mesh info`.
    let o = aster().args(["mesh", "info"]).arg(&medf).output().unwrap();
    let (stdout, err) = text(&o);
    assert!(o.status.success(), "aster mesh info: {err}");
    let lines: Vec<Vec<&str>> = stdout.lines().map(|l| l.split_whitespace().collect()).collect();
    let has = |a: &str, n: usize| lines.contains(&vec![a, n.to_string().as_str()]);
    assert!(has("nodes:", nnodes), "{stdout}");
    assert!(has("cells:", types.values().sum()), "{stdout}");
    for (t, n) in &types {
        assert!(has(t.name(), *n), "{} {n}:\n{stdout}", t.name());
    }
    for (g, n) in &groups {
        assert!(has(g, *n), "{g} {n}:\n{stdout}");
    }
    println!("gmsh: {nnodes} nodes, {types:?}, groups {groups:?}: OK");
    let _ = std::fs::remove_dir_all(&dir);
}
