//! DEFI_FISS_XFEM on the real WTNV149 cases (formulation step 4 of
//! `hm-xfem-formulation.md`, issue 5 acceptance 3): the LIRE_MAILLAGE,
//! FORMULE and DEFI_FISS_XFEM calls are extracted at test time from
//! `../shared/astest/wtnv149a.comm` and `wtnv149b.comm` and run on the meshes
//! read in place (`wtnv145a.mmed`, `wtnv145b.mmed`); the enriched-node counts
//! are read from the message file (INFO=2). The junction side and the node
//! sub-domain codes are checked through the library on the same meshes.
//! Every test prints a message and passes when `../shared` is absent.

use aster::mesh::Mesh;
use aster::xfem::node_code;
use std::path::Path;
use std::process::Command;
use std::rc::Rc;

use crate::common::*;

/// The statement `NAME = ...(...)` of a command file, up to its closing
/// parenthesis (quotes respected), with a trailing `;` dropped.
fn statement(src: &str, name: &str) -> String {
    let start = src
        .lines()
        .scan(0usize, |off, l| {
            let here = *off;
            *off += l.len() + 1;
            Some((here, l))
        })
        .find(|(_, l)| {
            l.strip_prefix(name).map(|r| r.trim_start().starts_with('=')).unwrap_or(false)
                && !l.trim_start().starts_with('#')
        })
        .map(|(o, _)| o)
        .unwrap_or_else(|| panic!("no statement {name} in the command file"));
    let bytes = src.as_bytes();
    let (mut depth, mut quote, mut opened) = (0i32, None::<u8>, false);
    for (i, &b) in bytes.iter().enumerate().skip(start) {
        match (quote, b) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, b'\'' | b'"') => quote = Some(b),
            (None, b'(') => {
                depth += 1;
                opened = true;
            }
            (None, b')') => {
                depth -= 1;
                if opened && depth == 0 {
                    return src[start..=i].to_string();
                }
            }
            _ => {}
        }
    }
    panic!("statement {name} is not closed");
}

/// The DEFI_FISS_XFEM part of a WTNV149 command file, with INFO=2.
fn level_set_part(comm: &Path) -> String {
    let src = std::fs::read_to_string(comm).unwrap();
    let mut out = String::from("DEBUT()\n");
    for name in ["MAILLAG2", "LN1", "FISS1", "LN2", "FISS2"] {
        let mut s = statement(&src, name);
        if name.starts_with("FISS") {
            assert!(s.contains("DEFI_FISS_XFEM"), "{name} is not a DEFI_FISS_XFEM: {s}");
            s = s.replace("INFO=1", "INFO=2");
        }
        out.push_str(&s);
        out.push('\n');
    }
    out.push_str("FIN()\n");
    out
}

/// Run the DEFI_FISS_XFEM part of a case; returns the message file.
fn run_case(case: &str, mesh: &Path) -> String {
    let comm = astest(&format!("{case}.comm")).unwrap();
    let dir = scratch!(case);
    let file = dir.join(format!("{case}_ls.comm"));
    std::fs::write(&file, level_set_part(&comm)).unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .arg("--unit")
        .arg(format!("20={}", mesh.display()))
        .output()
        .unwrap();
    let mess = std::fs::read_to_string(out.join(format!("{case}_ls.mess"))).unwrap_or_default();
    assert!(
        o.status.success(),
        "{case} failed:\n{}\n{}\n{mess}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
    mess
}

/// The integers after `label` in the message file, in order.
fn counts(mess: &str, label: &str) -> Vec<usize> {
    mess.lines()
        .filter_map(|l| l.trim().strip_prefix(label))
        .map(|r| r.trim_start().trim_start_matches(':').split_whitespace().next().unwrap().parse().unwrap())
        .collect()
}

fn check_counts(case: &str, mesh_file: &str, expect: [usize; 3]) {
    let (Some(_), Some(mesh)) = (astest(&format!("{case}.comm")), astest(mesh_file)) else { return };
    let mess = run_case(case, &mesh);
    assert_eq!(counts(&mess, "Heaviside-enriched nodes"), vec![expect[0], expect[1]], "{mess}");
    assert_eq!(counts(&mess, "nodes enriched by both"), vec![expect[2]], "{mess}");
    // 13 cells of the model see both interfaces (hm-xfem-formulation.md §2.3).
    let both: Vec<String> = mess
        .lines()
        .filter_map(|l| l.trim().strip_prefix("cells enriched by both"))
        .map(|r| r.split('(').nth(1).unwrap().split_whitespace().next().unwrap().to_string())
        .collect();
    assert_eq!(both, vec!["13".to_string()], "{mess}");
    assert!(mess.contains("junction on FISS1 (c = +1)"), "{mess}");
}

#[test]
fn wtnv149a_enriched_node_counts() {
    check_counts("wtnv149a", "wtnv145a.mmed", [38, 23, 13]);
}

#[test]
fn wtnv149b_enriched_node_counts() {
    check_counts("wtnv149b", "wtnv145b.mmed", [92, 56, 32]);
}

// ------------------------------------------------------------------ library level

fn node_at(mesh: &Mesh, x: &[f64]) -> usize {
    (0..mesh.nnodes())
        .find(|&n| x.iter().enumerate().all(|(k, v)| (mesh.coords[n][k] - v).abs() < 1e-9))
        .unwrap_or_else(|| panic!("no node at {x:?}"))
}

#[test]
fn wtnv149a_junction_side_and_codes() {
    let Some(m) = mesh("wtnv145a.mmed") else { return };
    let (c1, c2) = two_cracks(&m, |x| x[1] - 0.2 - 0.5 * x[0], |x| x[1] + 0.5 * x[0] + 0.2, &[2.0, -5.0]);
    {
        let k2 = c2.clone();
        let n = k2.junction_node.unwrap();
        assert_eq!(m.node_names[n], "N40");
        assert_eq!(m.coords[n][..2], [2.0, -5.0]);
        assert!((c1.clone().lsn[n] + 6.2).abs() < 1e-12);
        let (master, c) = k2.master().unwrap();
        assert!(Rc::ptr_eq(master, &c1));
        assert_eq!(c, 1.0);
        assert_eq!(c1.clone().enriched_nodes().len(), 38);
        assert_eq!(k2.enriched_nodes().len(), 23);
    }
    let both = [c1.clone(), c2.clone()];
    // Above FISS1 the branch does not exist: (+1, 0) → 14.
    assert_eq!(node_code(&both, node_at(&m, &[0.0, 5.0])), 14);
    assert_eq!(node_code(&both, node_at(&m, &[-5.0, 0.0])), 14);
    // Below FISS1: φ2 < 0 → 5, φ2 > 0 → 7.
    assert_eq!(node_code(&both, node_at(&m, &[0.0, -5.0])), 5);
    assert_eq!(node_code(&both, node_at(&m, &[4.0, -1.0])), 7);
    // One crack: − → 1, + → 3.
    assert_eq!(node_code(std::slice::from_ref(&c1), node_at(&m, &[0.0, -5.0])), 1);
    assert_eq!(node_code(std::slice::from_ref(&c1), node_at(&m, &[0.0, 5.0])), 3);
    assert_eq!(node_code(std::slice::from_ref(&c2), node_at(&m, &[0.0, 5.0])), 3);
}

#[test]
fn wtnv149b_junction_side_and_codes() {
    let Some(m) = mesh("wtnv145b.mmed") else { return };
    let (c1, c2) = two_cracks(&m, |x| x[2] - 0.5 * x[0] - 2.7, |x| x[2] - 7.3 + 0.5 * x[0], &[10.0, 0.0, 2.0]);
    {
        let k2 = c2.clone();
        let n = k2.junction_node.unwrap();
        assert_eq!(m.coords[n], [10.0, 0.0, 2.0]);
        assert!((c1.clone().lsn[n] + 5.7).abs() < 1e-12);
        assert_eq!(k2.master().unwrap().1, 1.0);
        assert_eq!(c1.clone().enriched_nodes().len(), 92);
        assert_eq!(k2.enriched_nodes().len(), 56);
    }
    let both = [c1.clone(), c2];
    assert_eq!(node_code(&both, node_at(&m, &[0.0, 0.0, 10.0])), 14);
    assert_eq!(node_code(&both, node_at(&m, &[0.0, 2.0, 0.0])), 5);
    assert_eq!(node_code(&both, node_at(&m, &[10.0, 0.0, 5.0])), 7);
    assert_eq!(node_code(std::slice::from_ref(&c1), node_at(&m, &[0.0, 0.0, 0.0])), 1);
    assert_eq!(node_code(std::slice::from_ref(&c1), node_at(&m, &[0.0, 0.0, 10.0])), 3);
}
