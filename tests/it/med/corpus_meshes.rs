//! Every mesh of Code_Aster's 2025 verification corpus (../shared/corpus/astest-2025) reads — MED
//! (3.x/4.x and 2.x layouts; also the MED files exports name under a unit number), `.mail`, Gmsh `.msh`, Cast3M `.mgib` and I-DEAS `.msup` — and its node
//! and cell counts agree with a reader independent of ours (scripts/mesh_counts.py: MED-fichier's
//! own API through python3-med, meshio and gmsh for Gmsh and I-DEAS files, small separate parsers for
//! `.mail` and `.mgib`). Skips with a message where the corpus or a reader is absent.

use aster::mesh::TextFormat;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `(file, mesh)` → `(nodes, cells)` or the reader's error, from the script's lines.
type Counts = HashMap<(String, String), Result<(usize, usize), String>>;

/// The counts of `files` by the independent reader `mode` run with `python`, or None (with a SKIP
/// message) when the reader is absent.
fn independent(python: &str, mode: &str, import: &str, files: &[PathBuf]) -> Option<Counts> {
    let probe = Command::new(python).args(["-c", import]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        println!("SKIP: {mode} counts: `{python} -c '{import}'` fails (reader absent)");
        return None;
    }
    if files.is_empty() {
        return Some(Counts::new());
    }
    let script = crate::common::root().join("scripts/mesh_counts.py");
    let out = Command::new(python).arg(&script).arg(mode).args(files).output().expect("run scripts/mesh_counts.py");
    assert!(out.status.success(), "mesh_counts.py {mode}: {}", String::from_utf8_lossy(&out.stderr));
    let mut counts = Counts::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let f: Vec<&str> = line.split('\t').collect();
        match f[..] {
            [file, "ERROR", msg] => {
                counts.insert((file.into(), String::new()), Err(msg.into()));
            }
            [file, mesh, n, c] => {
                counts.insert((file.into(), mesh.into()), Ok((n.parse().unwrap(), c.parse().unwrap())));
            }
            _ => panic!("mesh_counts.py {mode}: unexpected line '{line}'"),
        }
    }
    Some(counts)
}

fn name(p: &Path) -> String {
    p.file_name().unwrap().to_string_lossy().into_owned()
}

#[test]
fn every_corpus_mesh_reads_with_the_counts_of_an_independent_reader() {
    let dir = crate::common::root().join("../shared/corpus/astest-2025");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        println!("SKIP: {} is absent", dir.display());
        return;
    };
    let mut all: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
    all.sort();
    let with = |exts: &[&str]| -> Vec<PathBuf> {
        all.iter().filter(|p| p.extension().is_some_and(|x| exts.iter().any(|e| x == *e))).cloned().collect()
    };
    let (mut med, text, mut gmsh) = (with(&["mmed", "med"]), with(&["mail", "mgib"]), with(&["msh", "msup"]));
    // MED files an `.export` names as meshes under a unit number (`F mmed sslp320c.21 D 21`).
    med.extend(numbered_med_meshes(&dir, &all));
    // Some `.msup` files of the corpus are not meshes (interspectra for LIRE_INTE_SPEC, results for
    // LIRE_RESU): a universal file of a mesh has a dataset of nodes (15, 781 or 2411).
    gmsh.retain(|p| p.extension().is_some_and(|x| x == "msh") || is_universal_mesh(p));
    let mut unverified = Vec::new();
    let mut failures = Vec::new();
    let mut checked = 0;

    // MED: every mesh of every file.
    if let Some(counts) = independent("/usr/bin/python3", "med", "import med", &med) {
        for f in &med {
            let file = name(f);
            let names = match aster::med::list_meshes(f) {
                Ok(n) => n,
                Err(e) => {
                    failures.push(format!("{file}: {e}"));
                    continue;
                }
            };
            for mesh in names {
                let ours = aster::med::read_mesh(f, Some(&mesh)).map(|m| (m.nnodes(), m.ncells()));
                compare(&counts, &file, &mesh, ours.map_err(|e| e.to_string()), &mut failures);
                checked += 1;
            }
        }
    }
    // Text formats.
    let formats: [(&str, &str, &str, &[PathBuf]); 2] =
        [("python3", "text", "import re", &text), ("python3", "gmsh", "import meshio, gmsh", &gmsh)];
    for (python, mode, import, files) in formats {
        let Some(counts) = independent(python, mode, import, files) else { continue };
        for f in files {
            let file = name(f);
            let ext = f.extension().unwrap().to_string_lossy().into_owned();
            let format = TextFormat::from_extension(&ext).expect("a text mesh extension");
            let src = String::from_utf8_lossy(&std::fs::read(f).unwrap()).into_owned();
            let ours = format.read(&src, &file).map(|m| {
                for (c, t) in m.cells.iter().zip(&m.cell_types) {
                    assert_eq!(c.len(), t.nnodes(), "{file}");
                }
                // gmsh drops the nodes of an I-DEAS file that no cell uses (we keep them, as Code_Aster
                // does): compare the used ones.
                let nodes = if ext == "msup" {
                    m.cells.iter().flatten().collect::<std::collections::HashSet<_>>().len()
                } else {
                    m.nnodes()
                };
                (nodes, m.ncells())
            });
            // gmsh reads only the newer I-DEAS datasets (2411, 2412): an older file it cannot count is
            // read, not verified.
            let theirs = counts.get(&(file.clone(), String::new()));
            if ext == "msup" && ours.is_ok() && matches!(theirs, Some(Err(_)) | Some(Ok((0, 0)))) {
                unverified.push(file);
                continue;
            }
            compare(&counts, &file, "", ours, &mut failures);
            checked += 1;
        }
    }
    if !unverified.is_empty() {
        println!("read, but no independent reader counts them (older I-DEAS datasets): {}", unverified.join(" "));
    }
    println!(
        "corpus meshes: {checked} meshes checked ({} MED files, {} .mail/.mgib, {} .msh/.msup), {} disagree",
        med.len(),
        text.len(),
        gmsh.len(),
        failures.len()
    );
    assert!(failures.is_empty(), "{} meshes fail:\n{}", failures.len(), failures.join("\n"));
}

/// The HDF5 files that an `.export` of `dir` names with the type `mmed` under another extension than
/// `.mmed`/`.med` (a unit number mostly).
fn numbered_med_meshes(dir: &Path, all: &[PathBuf]) -> Vec<PathBuf> {
    let mut out = std::collections::BTreeSet::new();
    for e in all.iter().filter(|p| p.extension().is_some_and(|x| x == "export")) {
        let text = std::fs::read_to_string(e).unwrap_or_default();
        for line in text.lines() {
            let w: Vec<&str> = line.split_whitespace().collect();
            if let ["F", "mmed", file, ..] = w[..] {
                let p = dir.join(file);
                let ext = p.extension().map(|x| x.to_string_lossy().into_owned()).unwrap_or_default();
                let mut head = [0u8; 4];
                let hdf5 = std::fs::File::open(&p)
                    .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut head))
                    .is_ok_and(|()| &head == b"\x89HDF");
                if ext != "mmed" && ext != "med" && hdf5 {
                    out.insert(p);
                }
            }
        }
    }
    out.into_iter().collect()
}

/// Does the I-DEAS universal file `p` hold a dataset of nodes (15, 781, 2411)?
fn is_universal_mesh(p: &Path) -> bool {
    let Ok(bytes) = std::fs::read(p) else { return false };
    let text = String::from_utf8_lossy(&bytes);
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    lines.windows(2).any(|w| w[0] == "-1" && matches!(w[1], "15" | "781" | "2411"))
}

fn compare(counts: &Counts, file: &str, mesh: &str, ours: Result<(usize, usize), String>, failures: &mut Vec<String>) {
    let theirs =
        counts.get(&(file.to_string(), mesh.to_string())).or_else(|| counts.get(&(file.to_string(), String::new())));
    match (ours, theirs) {
        (Err(e), _) => failures.push(format!("{file} {mesh}: we fail: {e}")),
        (Ok(_), None) => failures.push(format!("{file} {mesh}: the independent reader has no count")),
        (Ok(_), Some(Err(e))) => failures.push(format!("{file} {mesh}: the independent reader fails: {e}")),
        (Ok(a), Some(Ok(b))) if a != *b => failures.push(format!(
            "{file} {mesh}: we read {} nodes and {} cells, the independent reader {} and {}",
            a.0, a.1, b.0, b.1
        )),
        _ => {}
    }
}

/// `aster mesh info` and `aster mesh convert` take every format: a file of each kind of the corpus is
/// described, converted to MED and to `.mail`, and both read back with its node and cell counts.
#[test]
fn aster_mesh_info_and_convert_take_every_format() {
    let dir = crate::common::root().join("../shared/corpus/astest-2025");
    if !dir.is_dir() {
        println!("SKIP: {} is absent", dir.display());
        return;
    }
    let out = scratch!("mesh_convert");
    for file in ["ssnp147a.msh", "sdll110d.msh", "epicu03a.mgib", "zzzz161a.msup", "comp001a.mail", "cont001i.med"] {
        let input = dir.join(file);
        if !input.exists() {
            println!("SKIP: {file} is absent");
            continue;
        }
        let o = crate::common::aster().args(["mesh", "info"]).arg(&input).output().unwrap();
        let (stdout, stderr) = crate::common::text(&o);
        assert!(o.status.success(), "mesh info {file}: {stderr}");
        let nodes = stdout.lines().find_map(|l| l.trim().strip_prefix("nodes: ")).expect("a node count").to_string();
        for ext in ["med", "mail"] {
            let target = out.join(format!("{file}.{ext}"));
            let o = crate::common::aster().args(["mesh", "convert"]).arg(&input).arg(&target).output().unwrap();
            assert!(o.status.success(), "mesh convert {file} → .{ext}: {}", crate::common::text(&o).1);
            let o = crate::common::aster().args(["mesh", "info"]).arg(&target).output().unwrap();
            let (back, stderr) = crate::common::text(&o);
            assert!(o.status.success(), "mesh info of {file} converted to .{ext}: {stderr}");
            assert!(back.lines().any(|l| l.trim() == format!("nodes: {nodes}")), "{file} → .{ext}:\n{back}");
        }
    }
    let _ = std::fs::remove_dir_all(&out);
}
