//! `aster diff`: compare the meshes and node fields of two MED files.
//!
//! Meshes are compared by name: space dimension, node coordinates (within
//! the tolerance), node and cell names, cell types and connectivity, group
//! names and members (exactly). Node fields are compared by name, component
//! and time step (`numdt`): for each, the largest absolute difference
//! `|a - b|` and the largest relative difference `|a - b| / max(|a|, |b|)`
//! (0 where both are 0), with the node where each occurs. A value is within
//! tolerance when `|a - b| <= atol + rtol * max(|a|, |b|)`.

use super::{list_fields, list_meshes, read_mesh, read_node_field};
use crate::diag::Result;
use crate::mesh::Mesh;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;

/// Tolerances of a comparison.
#[derive(Debug, Clone, Copy)]
pub struct Tolerance {
    pub rtol: f64,
    pub atol: f64,
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance { rtol: 1e-6, atol: 1e-12 }
    }
}

impl Tolerance {
    pub fn accepts(&self, a: f64, b: f64) -> bool {
        if a == b {
            return true;
        }
        (a - b).abs() <= self.atol + self.rtol * a.abs().max(b.abs())
    }
}

/// The largest differences over a set of value pairs.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Extremes {
    pub max_abs: f64,
    /// Index of the pair with the largest absolute difference.
    pub at_abs: usize,
    pub max_rel: f64,
    pub at_rel: usize,
    /// Pairs beyond tolerance.
    pub beyond: usize,
}

/// Largest absolute and relative differences between `a` and `b` read with
/// a stride: pair `i` is `(a[i * stride + off], b[i * stride + off])`.
pub fn extremes(a: &[f64], b: &[f64], stride: usize, off: usize, tol: Tolerance) -> Extremes {
    let mut e = Extremes::default();
    let n = a.len().min(b.len()) / stride.max(1);
    for i in 0..n {
        let (x, y) = (a[i * stride + off], b[i * stride + off]);
        let d = (x - y).abs();
        let d = if d.is_nan() && !(x.is_nan() && y.is_nan()) {
            f64::INFINITY
        } else if d.is_nan() {
            0.0
        } else {
            d
        };
        let scale = x.abs().max(y.abs());
        let r = if d == 0.0 {
            0.0
        } else if scale == 0.0 || !scale.is_finite() {
            f64::INFINITY
        } else {
            d / scale
        };
        if d > e.max_abs {
            e.max_abs = d;
            e.at_abs = i;
        }
        if r > e.max_rel {
            e.max_rel = r;
            e.at_rel = i;
        }
        if !(tol.accepts(x, y) || x.is_nan() && y.is_nan()) {
            e.beyond += 1;
        }
    }
    e
}

/// The outcome of a comparison: the printed report and the verdict.
#[derive(Debug, Clone)]
pub struct Report {
    pub text: String,
    /// Everything matched within tolerance.
    pub within: bool,
    /// Largest absolute difference over all field values compared.
    pub max_abs: f64,
}

fn verdict(ok: bool) -> &'static str {
    if ok {
        "OK"
    } else {
        "DIFFERENT"
    }
}

fn node_label(mesh: Option<&Mesh>, i: usize) -> String {
    match mesh.and_then(|m| m.node_names.get(i)) {
        Some(n) => n.clone(),
        None => format!("node #{}", i + 1),
    }
}

/// Compare two meshes; returns false if they differ.
fn diff_mesh(out: &mut String, name: &str, a: &Mesh, b: &Mesh, tol: Tolerance) -> bool {
    let _ = writeln!(out, "mesh {name}: {} nodes, {} cells", a.nnodes(), a.ncells());
    let mut ok = true;
    if a.dim != b.dim {
        let _ = writeln!(out, "  space dimension: {} vs {}  DIFFERENT", a.dim, b.dim);
        ok = false;
    }
    if a.nnodes() != b.nnodes() {
        let _ = writeln!(out, "  nodes: {} vs {}  DIFFERENT", a.nnodes(), b.nnodes());
        ok = false;
    } else {
        let fa: Vec<f64> = a.coords.iter().flat_map(|c| c.iter().copied()).collect();
        let fb: Vec<f64> = b.coords.iter().flat_map(|c| c.iter().copied()).collect();
        let mut worst = Extremes::default();
        let mut beyond = 0;
        for k in 0..3 {
            let e = extremes(&fa, &fb, 3, k, tol);
            beyond += e.beyond;
            if e.max_abs > worst.max_abs {
                worst.max_abs = e.max_abs;
                worst.at_abs = e.at_abs;
            }
        }
        let _ = writeln!(
            out,
            "  coordinates: max |a-b| = {:.6e} at {}  {}",
            worst.max_abs,
            node_label(Some(a), worst.at_abs),
            verdict(beyond == 0)
        );
        ok &= beyond == 0;
        let renamed = a.node_names.iter().zip(&b.node_names).filter(|(x, y)| x != y).count();
        if renamed > 0 {
            let _ = writeln!(out, "  node names: {renamed} differ  DIFFERENT");
            ok = false;
        }
    }
    if a.ncells() != b.ncells() || a.cell_type_counts() != b.cell_type_counts() {
        let show = |m: &Mesh| -> String {
            m.cell_type_counts().iter().map(|(t, n)| format!("{} {n}", t.name())).collect::<Vec<_>>().join(", ")
        };
        let _ = writeln!(out, "  cells: [{}] vs [{}]  DIFFERENT", show(a), show(b));
        ok = false;
    } else {
        let bad: Vec<usize> =
            (0..a.ncells()).filter(|&i| a.cell_types[i] != b.cell_types[i] || a.cells[i] != b.cells[i]).collect();
        match bad.first() {
            None => {
                let _ = writeln!(out, "  connectivity: identical  OK");
            }
            Some(&i) => {
                let _ = writeln!(
                    out,
                    "  connectivity: {} cells differ (first: {})  DIFFERENT",
                    bad.len(),
                    a.cell_names.get(i).cloned().unwrap_or_default()
                );
                ok = false;
            }
        }
        let renamed = a.cell_names.iter().zip(&b.cell_names).filter(|(x, y)| x != y).count();
        if renamed > 0 {
            let _ = writeln!(out, "  cell names: {renamed} differ  DIFFERENT");
            ok = false;
        }
    }
    for (kind, ga, gb) in [("cells", &a.cell_groups, &b.cell_groups), ("nodes", &a.node_groups, &b.node_groups)] {
        let names: BTreeSet<&String> = ga.keys().chain(gb.keys()).collect();
        let mut problems = Vec::new();
        for g in names {
            match (ga.get(g), gb.get(g)) {
                (Some(x), Some(y)) if x == y => {}
                (Some(x), Some(y)) => {
                    problems.push(format!("'{g}' has {} vs {} members or other members", x.len(), y.len()))
                }
                (Some(_), None) => problems.push(format!("'{g}' only in A")),
                (None, _) => problems.push(format!("'{g}' only in B")),
            }
        }
        if problems.is_empty() {
            let _ = writeln!(out, "  groups of {kind}: {} identical  OK", ga.len());
        } else {
            let _ = writeln!(out, "  groups of {kind}: {}  DIFFERENT", problems.join("; "));
            ok = false;
        }
    }
    ok
}

/// Compare two MED files (meshes and node fields).
pub fn diff_files(pa: &Path, pb: &Path, tol: Tolerance) -> Result<Report> {
    let mut out = String::new();
    let mut within = true;
    let mut max_abs = 0.0f64;
    let ma = list_meshes(pa)?;
    let mb = list_meshes(pb)?;
    let mut meshes_a = std::collections::BTreeMap::new();
    for name in ma.iter().chain(mb.iter()).collect::<BTreeSet<_>>() {
        match (ma.contains(name), mb.contains(name)) {
            (true, true) => {
                let a = read_mesh(pa, Some(name))?;
                let b = read_mesh(pb, Some(name))?;
                within &= diff_mesh(&mut out, name, &a, &b, tol);
                meshes_a.insert(name.clone(), a);
            }
            (true, false) => {
                let _ = writeln!(out, "mesh {name}: only in A  DIFFERENT");
                within = false;
            }
            _ => {
                let _ = writeln!(out, "mesh {name}: only in B  DIFFERENT");
                within = false;
            }
        }
    }
    let fa = list_fields(pa)?;
    let fb = list_fields(pb)?;
    for name in fa.iter().chain(fb.iter()).collect::<BTreeSet<_>>() {
        if !fa.contains(name) || !fb.contains(name) {
            let _ = writeln!(out, "field {name}: only in {}  DIFFERENT", if fa.contains(name) { "A" } else { "B" });
            within = false;
            continue;
        }
        let a = read_node_field(pa, name)?;
        let b = read_node_field(pb, name)?;
        if a.steps.is_empty() && b.steps.is_empty() {
            let _ = writeln!(out, "field {name}: no node values (not compared)");
            continue;
        }
        if a.components != b.components {
            let _ = writeln!(
                out,
                "field {name}: components [{}] vs [{}]  DIFFERENT",
                a.components.join(" "),
                b.components.join(" ")
            );
            within = false;
            continue;
        }
        let mesh = meshes_a.get(&a.mesh_name);
        let nco = a.components.len().max(1);
        let steps_b: std::collections::BTreeMap<i32, &(i32, f64, Vec<f64>)> =
            b.steps.iter().map(|s| (s.0, s)).collect();
        for (numdt, time, va) in &a.steps {
            let Some((_, tb, vb)) = steps_b.get(numdt) else {
                let _ = writeln!(out, "field {name} step {numdt}: only in A  DIFFERENT");
                within = false;
                continue;
            };
            if va.len() != vb.len() {
                let _ = writeln!(
                    out,
                    "field {name} step {numdt}: {} vs {} values  DIFFERENT",
                    va.len() / nco,
                    vb.len() / nco
                );
                within = false;
                continue;
            }
            if !tol.accepts(*time, *tb) {
                let _ = writeln!(out, "field {name} step {numdt}: time {time} vs {tb}  DIFFERENT");
                within = false;
            }
            let named = mesh.filter(|m| m.nnodes() * nco == va.len());
            for (k, comp) in a.components.iter().enumerate() {
                let e = extremes(va, vb, nco, k, tol);
                max_abs = max_abs.max(e.max_abs);
                let ok = e.beyond == 0;
                within &= ok;
                let _ = writeln!(
                    out,
                    "field {name} {comp} step {numdt} (t={time}): max |a-b| = {:.6e} at {}, max rel = {:.6e} at {}{}  {}",
                    e.max_abs,
                    node_label(named, e.at_abs),
                    e.max_rel,
                    node_label(named, e.at_rel),
                    if ok { String::new() } else { format!(", {} values beyond tolerance", e.beyond) },
                    verdict(ok)
                );
            }
        }
        for numdt in b.steps.iter().map(|s| s.0) {
            if !a.steps.iter().any(|s| s.0 == numdt) {
                let _ = writeln!(out, "field {name} step {numdt}: only in B  DIFFERENT");
                within = false;
            }
        }
    }
    let _ = writeln!(
        out,
        "{} (rtol {:e}, atol {:e})",
        if within { "files match" } else { "files differ" },
        tol.rtol,
        tol.atol
    );
    Ok(Report { text: out, within, max_abs })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes_find_the_largest_differences() {
        let tol = Tolerance { rtol: 1e-3, atol: 0.0 };
        // Interlaced, two components.
        let a = [1.0, 10.0, 2.0, 20.0, 0.0, 30.0];
        let b = [1.0, 10.5, 2.001, 20.0, 0.0, 30.0];
        let e0 = extremes(&a, &b, 2, 0, tol);
        assert_eq!(e0.at_abs, 1);
        assert!((e0.max_abs - 0.001).abs() < 1e-15);
        assert_eq!(e0.beyond, 0);
        let e1 = extremes(&a, &b, 2, 1, tol);
        assert_eq!((e1.at_abs, e1.max_abs, e1.beyond), (0, 0.5, 1));
        assert!((e1.max_rel - 0.5 / 10.5).abs() < 1e-15);
    }

    #[test]
    fn tolerance_is_symmetric() {
        let t = Tolerance { rtol: 0.1, atol: 0.0 };
        assert!(t.accepts(1.0, 1.1) && t.accepts(1.1, 1.0));
        assert!(!t.accepts(1.0, 1.2));
        assert!(Tolerance { rtol: 0.0, atol: 1e-9 }.accepts(0.0, 1e-10));
    }
}
