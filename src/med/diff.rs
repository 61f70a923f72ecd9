//! `aster diff`: compare the meshes and the fields of two MED files.
//!
//! Meshes are compared by name: space dimension, node coordinates (within
//! the tolerance), node and cell names, cell types and connectivity, group
//! names and members (exactly). Fields of every support (nodes, cells, nodes
//! of cells, integration points) are compared by name, component, step
//! (its order number: `numit`, else `numdt`) and kind of entity (nodes, or a
//! cell type): for each, the largest absolute difference `|a - b|` and the
//! largest relative difference `|a - b| / max(|a|, |b|)` (0 where both are
//! 0), with the node, cell, point or node of a cell where each occurs, in a
//! table. A value is within tolerance when `|a - b| <= atol + rtol * max(|a|, |b|)`;
//! values at integration points are compared only where both files place
//! them at the same points.

use super::cellfield::{read_field, read_localizations, Block, Support};
use super::{list_fields, list_meshes, read_mesh};
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

/// Where the values of a block live, for messages: `N12`, `M4 point 3`, `M4 node N7`, `M4`.
struct Places<'m> {
    mesh: Option<&'m Mesh>,
    by_type: std::collections::BTreeMap<crate::mesh::CellType, Vec<usize>>,
}

impl<'m> Places<'m> {
    fn new(mesh: Option<&'m Mesh>) -> Self {
        Places { mesh, by_type: mesh.map(super::cellfield::cells_by_type).unwrap_or_default() }
    }

    fn cell(&self, t: crate::mesh::CellType, pos: usize) -> Option<usize> {
        self.by_type.get(&t).and_then(|v| v.get(pos)).copied()
    }

    /// The place of value pair `i` of a block (entity `i / per_entity`, point `i % per_entity`).
    fn of(&self, b: &Block, i: usize) -> String {
        let (e, p) = (i / b.per_entity.max(1), i % b.per_entity.max(1));
        let Some(&ent) = b.entities.get(e) else { return "-".into() };
        match (b.support, b.cell) {
            (Support::Node, _) => node_label(self.mesh, ent),
            (_, Some(t)) => {
                let c = self.cell(t, ent);
                let cname = match (self.mesh, c) {
                    (Some(m), Some(c)) => m.cell_names[c].clone(),
                    _ => format!("{} #{}", t.name(), ent + 1),
                };
                match b.support {
                    Support::CellNode => match (self.mesh, c) {
                        (Some(m), Some(c)) => format!("{cname} node {}", node_label(Some(m), m.cells[c][p])),
                        _ => format!("{cname} node #{}", p + 1),
                    },
                    _ if b.localization.is_some() => format!("{cname} point {}", p + 1),
                    _ => cname,
                }
            }
            _ => "-".into(),
        }
    }
}

/// What a block is on: `nodes`, or the cell type and the kind of values.
fn block_kind(b: &Block) -> String {
    match (b.support, b.cell) {
        (Support::Node, _) => "nodes".into(),
        (Support::CellNode, Some(t)) => format!("{} nodes", t.name()),
        (Support::Cell, Some(t)) if b.localization.is_some() => format!("{} points", t.name()),
        (_, Some(t)) => format!("{} cells", t.name()),
        _ => "?".into(),
    }
}

/// The rows of the field table: field, component, step, entities, max |a-b| and where, max rel and
/// where, verdict.
struct Table {
    rows: Vec<[String; 9]>,
}

impl Table {
    fn note(&mut self, field: &str, what: String) {
        let mut r: [String; 9] = Default::default();
        r[0] = field.to_string();
        r[3] = what;
        r[8] = "DIFFERENT".into();
        self.rows.push(r);
    }

    fn render(&self, out: &mut String) {
        if self.rows.is_empty() {
            return;
        }
        let head = ["field", "cmp", "step", "on", "max |a-b|", "at", "max rel", "at", "verdict"];
        let mut w = head.map(str::len);
        for r in &self.rows {
            for (k, c) in r.iter().enumerate() {
                w[k] = w[k].max(c.len());
            }
        }
        let line = |cells: &[String], out: &mut String| {
            let mut s = String::new();
            for (k, c) in cells.iter().enumerate() {
                let _ = write!(s, "{c:<width$}  ", width = w[k]);
            }
            let _ = writeln!(out, "{}", s.trim_end());
        };
        line(&head.map(String::from), out);
        for r in &self.rows {
            line(r, out);
        }
    }
}

/// The two blocks (of the same kind, `per_entity` values of `nco` components per entity) restricted to
/// the entities both have, in the order of `a`.
fn on_common_entities(a: &Block, b: &Block, nco: usize) -> (Block, Block) {
    let in_b: std::collections::HashMap<usize, usize> = b.entities.iter().enumerate().map(|(i, &e)| (e, i)).collect();
    let w = a.per_entity * nco;
    let (mut ra, mut rb) = (
        Block { entities: Vec::new(), values: Vec::new(), ..a.clone() },
        Block { entities: Vec::new(), values: Vec::new(), ..b.clone() },
    );
    for (i, &e) in a.entities.iter().enumerate() {
        if let Some(&j) = in_b.get(&e) {
            ra.entities.push(e);
            rb.entities.push(e);
            ra.values.extend_from_slice(&a.values[i * w..(i + 1) * w]);
            rb.values.extend_from_slice(&b.values[j * w..(j + 1) * w]);
        }
    }
    (ra, rb)
}

/// Compare two MED files: meshes, and every field of every support (nodes, cells, nodes of cells,
/// integration points), per component, step and kind of entity: the largest absolute and relative
/// differences and where they are.
pub fn diff_files(pa: &Path, pb: &Path, tol: Tolerance) -> Result<Report> {
    let mut out = String::new();
    let mut within = true;
    let mut max_abs = 0.0f64;
    let ma = list_meshes(pa)?;
    let mb = list_meshes(pb)?;
    let mut meshes_a = std::collections::BTreeMap::new();
    // One mesh in each file under two names (a file of Code_Aster's names its mesh after the concept, or
    // with a number): they are compared with each other.
    if let ([a1], [b1]) = (ma.as_slice(), mb.as_slice()) {
        if a1 != b1 {
            match (read_mesh(pa, Some(a1)), read_mesh(pb, Some(b1))) {
                (Ok(a), Ok(b)) => {
                    within &= diff_mesh(&mut out, &format!("{a1} (A) / {b1} (B)"), &a, &b, tol);
                    meshes_a.insert(a1.clone(), a);
                }
                (Err(e), _) | (_, Err(e)) => {
                    let _ = writeln!(out, "mesh {a1} (A) / {b1} (B): not compared ({})", e.msg);
                }
            }
        }
    }
    for name in ma.iter().chain(mb.iter()).collect::<BTreeSet<_>>() {
        if ma.len() == 1 && mb.len() == 1 && ma[0] != mb[0] {
            break;
        }
        match (ma.contains(name), mb.contains(name)) {
            (true, true) => match (read_mesh(pa, Some(name)), read_mesh(pb, Some(name))) {
                (Ok(a), Ok(b)) => {
                    within &= diff_mesh(&mut out, name, &a, &b, tol);
                    meshes_a.insert(name.clone(), a);
                }
                // A mesh we cannot read (a layout we do not know): its fields are still compared, their
                // places given by numbers.
                (Err(e), _) | (_, Err(e)) => {
                    let _ = writeln!(out, "mesh {name}: not compared ({})", e.msg);
                }
            },
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
    let locs_a = read_localizations(pa)?;
    let locs_b = read_localizations(pb)?;
    let mut table = Table { rows: Vec::new() };
    let (mut compared, mut beyond_rows) = (0usize, 0usize);
    for name in fa.iter().chain(fb.iter()).collect::<BTreeSet<_>>() {
        if !fa.contains(name) || !fb.contains(name) {
            table.note(name, format!("only in {}", if fa.contains(name) { "A" } else { "B" }));
            within = false;
            continue;
        }
        let (a, b) = match (read_field(pa, name), read_field(pb, name)) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                table.note(name, format!("not compared: {}", e.msg));
                within = false;
                continue;
            }
        };
        if a.components != b.components {
            table.note(name, format!("components [{}] vs [{}]", a.components.join(" "), b.components.join(" ")));
            within = false;
            continue;
        }
        let places = Places::new(meshes_a.get(&a.mesh_name));
        let nco = a.components.len().max(1);
        for sa in &a.steps {
            let step = sa.order();
            let Some(sb) = b.steps.iter().find(|s| s.order() == step) else {
                table.note(name, format!("step {step} only in A"));
                within = false;
                continue;
            };
            let step_label = format!("{step} (t={})", sa.time);
            if !tol.accepts(sa.time, sb.time) {
                table.note(name, format!("step {step}: time {} vs {}", sa.time, sb.time));
                within = false;
            }
            for ba in &sa.blocks {
                let kind = block_kind(ba);
                let Some(bb) = sb.blocks.iter().find(|x| x.support == ba.support && x.cell == ba.cell) else {
                    table.note(name, format!("step {step}: values on {kind} only in A"));
                    within = false;
                    continue;
                };
                if let (Some(la), Some(lb)) = (&ba.localization, &bb.localization) {
                    let same = match (locs_a.get(la), locs_b.get(lb)) {
                        (Some(x), Some(y)) => x.same_points(y),
                        _ => la == lb,
                    };
                    if !same {
                        table.note(name, format!("step {step}: {kind}: the points differ ({la} vs {lb})"));
                        within = false;
                        continue;
                    }
                }
                if ba.per_entity != bb.per_entity {
                    table.note(
                        name,
                        format!(
                            "step {step}: {kind}: {} x {} values vs {} x {}",
                            ba.entities.len(),
                            ba.per_entity,
                            bb.entities.len(),
                            bb.per_entity
                        ),
                    );
                    within = false;
                    continue;
                }
                // Values on other entities (another profile): the entities of one file only are a
                // difference, the common ones are compared.
                let common;
                let (ba, bb) = if ba.entities != bb.entities {
                    let (ca, cb) = on_common_entities(ba, bb, nco);
                    table.note(
                        name,
                        format!(
                            "step {step}: {kind}: {} entities only in A, {} only in B, {} in both",
                            ba.entities.len() - ca.entities.len(),
                            bb.entities.len() - ca.entities.len(),
                            ca.entities.len()
                        ),
                    );
                    within = false;
                    common = (ca, cb);
                    (&common.0, &common.1)
                } else {
                    (ba, bb)
                };
                for (k, comp) in a.components.iter().enumerate() {
                    let e = extremes(&ba.values, &bb.values, nco, k, tol);
                    max_abs = max_abs.max(e.max_abs);
                    compared += 1;
                    let ok = e.beyond == 0;
                    within &= ok;
                    if !ok {
                        beyond_rows += 1;
                    }
                    table.rows.push([
                        name.clone(),
                        comp.clone(),
                        step_label.clone(),
                        kind.clone(),
                        format!("{:.6e}", e.max_abs),
                        if e.max_abs > 0.0 { places.of(ba, e.at_abs) } else { "-".into() },
                        format!("{:.6e}", e.max_rel),
                        if e.max_rel > 0.0 { places.of(ba, e.at_rel) } else { "-".into() },
                        if ok { "OK".into() } else { format!("DIFFERENT ({} values)", e.beyond) },
                    ]);
                }
            }
            for bb in &sb.blocks {
                if !sa.blocks.iter().any(|x| x.support == bb.support && x.cell == bb.cell) {
                    table.note(name, format!("step {step}: values on {} only in B", block_kind(bb)));
                    within = false;
                }
            }
        }
        for sb in &b.steps {
            if !a.steps.iter().any(|s| s.order() == sb.order()) {
                table.note(name, format!("step {} only in B", sb.order()));
                within = false;
            }
        }
    }
    table.render(&mut out);
    let _ = writeln!(
        out,
        "{} ({compared} field components compared, {beyond_rows} beyond tolerance; rtol {:e}, atol {:e})",
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
    fn common_entities_keep_their_values() {
        let blk = |entities: Vec<usize>, values: Vec<f64>| Block {
            support: Support::Node,
            cell: None,
            localization: None,
            per_entity: 1,
            entities,
            values,
        };
        // Two components; A on nodes 0, 2, 5; B on nodes 5, 0, 7.
        let a = blk(vec![0, 2, 5], vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let b = blk(vec![5, 0, 7], vec![50.0, 60.0, 10.0, 20.0, 0.0, 0.0]);
        let (ca, cb) = on_common_entities(&a, &b, 2);
        assert_eq!(ca.entities, vec![0, 5]);
        assert_eq!(cb.entities, vec![0, 5]);
        assert_eq!(ca.values, vec![1.0, 2.0, 5.0, 6.0]);
        assert_eq!(cb.values, vec![10.0, 20.0, 50.0, 60.0]);
    }

    #[test]
    fn tolerance_is_symmetric() {
        let t = Tolerance { rtol: 0.1, atol: 0.0 };
        assert!(t.accepts(1.0, 1.1) && t.accepts(1.1, 1.0));
        assert!(!t.accepts(1.0, 1.2));
        assert!(Tolerance { rtol: 0.0, atol: 1e-9 }.accepts(0.0, 1e-10));
    }
}
