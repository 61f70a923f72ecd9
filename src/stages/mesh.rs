//! LIRE_MAILLAGE, DEFI_GROUP and IMPR_RESU (MED: meshes and node fields of results).
//!
//! DEFI_GROUP follows Code_Aster's `sscgma` / `sscgno`: destruction first,
//! then CREA_GROUP_MA, then CREA_GROUP_NO, occurrence by occurrence, so an
//! occurrence sees the groups made by the previous ones. Node groups built
//! from cells are sorted by node number; INTERSEC / UNION / DIFFE keep the
//! order of the first group (UNION appends the new members of the others);
//! NOEUD, MAILLE and GROUP_NO keep the order given. An existing group name
//! is an error; an empty result is a warning and creates no group. Code_Aster
//! modifies the mesh of MAILLAGE in place even without `reuse`; so do we.

use super::Ctx;
use crate::catalog::args::Args;
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::med;
use crate::mesh::{CellType, Mesh};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::rc::Rc;

/// The mesh behind a concept.
pub fn mesh_of(c: &ConceptRef) -> Result<Rc<Mesh>> {
    match &*c.data() {
        ConceptData::Mesh(m) => Ok(m.clone()),
        _ => Err(Error::runtime(format!("{} ({}) holds no mesh", c.label(), c.kind()))),
    }
}

/// A text summary of a mesh: nodes, cells per type, groups with their
/// sizes, bounding box (LIRE_MAILLAGE INFO=2, `aster mesh info`).
pub fn describe(mesh: &Mesh, name: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "mesh {name}: space dimension {}", mesh.dim);
    let _ = writeln!(s, "  nodes: {}", mesh.nnodes());
    let _ = writeln!(s, "  cells: {}", mesh.ncells());
    for (t, n) in mesh.cell_type_counts() {
        let _ = writeln!(s, "    {:<8} {n:>10}", t.name());
    }
    let _ = writeln!(s, "  groups of cells: {}", mesh.cell_groups.len());
    for (g, n) in mesh.cell_group_sizes() {
        let _ = writeln!(s, "    {g:<24} {n:>10}");
    }
    let _ = writeln!(s, "  groups of nodes: {}", mesh.node_groups.len());
    for (g, n) in mesh.node_group_sizes() {
        let _ = writeln!(s, "    {g:<24} {n:>10}");
    }
    if let Some((lo, hi)) = mesh.bounding_box() {
        let axes = ["x", "y", "z"];
        let parts: Vec<String> =
            (0..mesh.dim.clamp(1, 3)).map(|k| format!("{} in [{}, {}]", axes[k], lo[k], hi[k])).collect();
        let _ = writeln!(s, "  bounding box: {}", parts.join(", "));
    }
    s
}

// ------------------------------------------------------------------ LIRE_MAILLAGE

pub fn lire_maillage(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let format = a.text("FORMAT").unwrap_or("MED");
    if format != "MED" {
        return Err(a.err("FORMAT", format!("FORMAT='{format}' is not supported yet (only 'MED')")));
    }
    let unit = a.int("UNITE").unwrap_or(20);
    let path = ctx.io.unit_path(unit, false).map_err(|e| locate(e, a, "UNITE"))?;
    let nom_med = a.text("NOM_MED");
    let mesh = med::read_mesh(&path, nom_med)
        .map_err(|e| locate(e, a, if nom_med.is_some() { "NOM_MED" } else { "UNITE" }))?;
    if a.int("INFO").unwrap_or(1) >= 2 {
        let shown = match nom_med {
            Some(n) => n.to_string(),
            None => med::list_meshes(&path).ok().and_then(|v| v.into_iter().next()).unwrap_or_default(),
        };
        ctx.io.mess(&format!("LIRE_MAILLAGE: unit {unit} ({})\n{}", path.display(), describe(&mesh, &shown)));
    }
    Ok(Some(ConceptData::Mesh(Rc::new(mesh))))
}

/// Attach keyword `kw`'s location to an error that has none, keeping its message.
fn locate(e: Error, a: &Args, kw: &str) -> Error {
    if e.span.is_some() {
        return e;
    }
    let mut out = a.err(kw, e.msg.clone());
    out.kind = e.kind;
    out
}

// ------------------------------------------------------------------ DEFI_GROUP

/// The mesh being modified, with name lookups built on demand.
struct Work {
    mesh: Mesh,
    label: String,
    alarm: bool,
    node_index: Option<HashMap<String, usize>>,
    cell_index: Option<HashMap<String, usize>>,
    messages: String,
    created_ma: Vec<String>,
    created_no: Vec<String>,
}

impl Work {
    fn warn(&mut self, msg: String) {
        if self.alarm {
            let _ = writeln!(self.messages, " <A> DEFI_GROUP: {msg}");
        }
    }

    fn node(&mut self, occ: &Args, kw: &str, name: &str) -> Result<usize> {
        let mesh = &self.mesh;
        let idx = self
            .node_index
            .get_or_insert_with(|| mesh.node_names.iter().enumerate().map(|(i, n)| (n.clone(), i)).collect());
        idx.get(name).copied().ok_or_else(|| occ.err(kw, format!("node '{name}' is not in mesh {}", self.label)))
    }

    fn cell(&mut self, occ: &Args, kw: &str, name: &str) -> Result<usize> {
        let mesh = &self.mesh;
        let idx = self
            .cell_index
            .get_or_insert_with(|| mesh.cell_names.iter().enumerate().map(|(i, n)| (n.clone(), i)).collect());
        idx.get(name).copied().ok_or_else(|| occ.err(kw, format!("cell '{name}' is not in mesh {}", self.label)))
    }

    fn cell_group(&self, occ: &Args, kw: &str, name: &str) -> Result<&Vec<usize>> {
        self.mesh
            .cell_groups
            .get(name)
            .ok_or_else(|| occ.err(kw, format!("group of cells '{name}' is not in mesh {}", self.label)))
    }

    fn node_group(&self, occ: &Args, kw: &str, name: &str) -> Result<&Vec<usize>> {
        self.mesh
            .node_groups
            .get(name)
            .ok_or_else(|| occ.err(kw, format!("group of nodes '{name}' is not in mesh {}", self.label)))
    }

    fn add_cell_group(&mut self, occ: &Args, name: &str, cells: Vec<usize>) -> Result<()> {
        if self.mesh.cell_groups.contains_key(name) {
            return Err(occ.err("NOM", format!("group of cells '{name}' already exists in mesh {}", self.label)));
        }
        if cells.is_empty() {
            self.warn(format!("group of cells '{name}' would be empty: not created"));
            return Ok(());
        }
        self.mesh.cell_groups.insert(name.to_string(), cells);
        self.created_ma.push(name.to_string());
        Ok(())
    }

    fn add_node_group(&mut self, occ: &Args, kw: &str, name: &str, nodes: Vec<usize>) -> Result<()> {
        if self.mesh.node_groups.contains_key(name) {
            return Err(occ.err(kw, format!("group of nodes '{name}' already exists in mesh {}", self.label)));
        }
        if nodes.is_empty() {
            self.warn(format!("group of nodes '{name}' would be empty: not created"));
            return Ok(());
        }
        self.mesh.node_groups.insert(name.to_string(), nodes);
        self.created_no.push(name.to_string());
        Ok(())
    }
}

/// Code_Aster's list operations (`utlisi`): the order of `a` is kept, UNION
/// appends the members of `b` not in `a`.
fn list_op(op: &str, a: &[usize], b: &[usize]) -> Vec<usize> {
    match op {
        "UNION" => {
            let in_a: HashSet<usize> = a.iter().copied().collect();
            let mut out = a.to_vec();
            out.extend(b.iter().copied().filter(|x| !in_a.contains(x)));
            out
        }
        "INTERSEC" => {
            let inb: HashSet<usize> = b.iter().copied().collect();
            a.iter().copied().filter(|x| inb.contains(x)).collect()
        }
        _ => {
            let inb: HashSet<usize> = b.iter().copied().collect();
            a.iter().copied().filter(|x| !inb.contains(x)).collect()
        }
    }
}

/// NUME_INIT / NUME_FIN / POSITION applied to the members of a group.
fn sub_range(occ: &Args, members: &[usize]) -> Result<Vec<usize>> {
    if members.is_empty() {
        return Err(occ.err("GROUP_NO", "the group is empty"));
    }
    if let Some(pos) = occ.text("POSITION") {
        let len = members.len();
        let i = match pos {
            "INIT" => 0,
            "FIN" => len - 1,
            _ => len.div_ceil(2) - 1,
        };
        return Ok(vec![members[i]]);
    }
    let first = occ.int("NUME_INIT").unwrap_or(1);
    let last = occ.int("NUME_FIN").unwrap_or(members.len() as i64);
    if last < first {
        return Err(occ.err("NUME_FIN", format!("NUME_FIN={last} is smaller than NUME_INIT={first}")));
    }
    if last as usize > members.len() {
        return Err(occ.err(
            if occ.has("NUME_FIN") { "NUME_FIN" } else { "NUME_INIT" },
            format!("{last} is beyond the {} members of the group", members.len()),
        ));
    }
    Ok(members[first as usize - 1..last as usize].to_vec())
}

/// Does a cell type pass a TYPE_MAILLE filter (a type name or 1D/2D/3D)?
fn type_matches(filter: &str, t: CellType) -> bool {
    match filter {
        "1D" => t.dim() == 1,
        "2D" => t.dim() == 2,
        "3D" => t.dim() == 3,
        name => t.name() == name,
    }
}

fn crea_group_ma(w: &mut Work, occ: &Args) -> Result<()> {
    let name = occ.req_text("NOM")?.to_string();
    if w.mesh.cell_groups.contains_key(&name) {
        return Err(occ.err("NOM", format!("group of cells '{name}' already exists in mesh {}", w.label)));
    }
    let mut cells: Vec<usize> = if occ.has("TOUT") {
        (0..w.mesh.ncells()).collect()
    } else if occ.has("MAILLE") {
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        for m in occ.texts("MAILLE") {
            let i = w.cell(occ, "MAILLE", &m)?;
            if seen.insert(i) {
                out.push(i);
            } else {
                w.warn(format!("cell '{m}' is given twice for group '{name}'"));
            }
        }
        out
    } else if let Some(g) = occ.text("GROUP_MA") {
        let members = w.cell_group(occ, "GROUP_MA", g)?.clone();
        sub_range(occ, &members)?
    } else if let Some(op) = ["INTERSEC", "UNION", "DIFFE"].into_iter().find(|k| occ.has(k)) {
        let names = occ.texts(op);
        let mut acc = w.cell_group(occ, op, &names[0])?.clone();
        for g in &names[1..] {
            acc = list_op(op, &acc, w.cell_group(occ, op, g)?);
        }
        acc
    } else if let Some(opt) = occ.text("OPTION") {
        return Err(occ.err("OPTION", format!("OPTION='{opt}' is not supported yet")));
    } else {
        return Err(occ.err("NOM", "nothing to build the group from"));
    };
    let filter = occ.text("TYPE_MAILLE").unwrap_or("TOUT");
    if filter != "TOUT" {
        if matches!(filter, "SEG4" | "TRIA7" | "PENTA18") {
            return Err(occ.err("TYPE_MAILLE", format!("cell type {filter} is not supported")));
        }
        let types = &w.mesh.cell_types;
        cells.retain(|&c| type_matches(filter, types[c]));
    }
    w.add_cell_group(occ, &name, cells)
}

/// Node positions kept by CRIT_NOEUD for a cell type (Code_Aster's `gmgnre`).
fn crit_range(crit: &str, t: CellType) -> std::ops::Range<usize> {
    let nv = t.nvertices();
    let nn = t.nnodes();
    let centre_start = match t {
        CellType::Quad9 => 8,
        CellType::Hexa27 => 20,
        _ => nn,
    };
    match crit {
        "SOMMET" => 0..nv,
        "MILIEU" => nv..centre_start,
        "CENTRE" => centre_start..nn,
        _ => 0..nn,
    }
}

/// Nodes of some cells, sorted by node number (Code_Aster marks then scans).
fn nodes_of_cells(mesh: &Mesh, cells: &[usize], crit: &str) -> Vec<usize> {
    let mut mark = vec![false; mesh.nnodes()];
    for &c in cells {
        let range = crit_range(crit, mesh.cell_types[c]);
        for &n in &mesh.cells[c][range] {
            mark[n] = true;
        }
    }
    mark.iter().enumerate().filter(|(_, &m)| m).map(|(i, _)| i).collect()
}

fn crea_group_no(w: &mut Work, occ: &Args) -> Result<()> {
    if occ.has("TOUT_GROUP_MA") {
        let groups: Vec<(String, Vec<usize>)> =
            w.mesh.cell_groups.iter().map(|(k, v)| (k.clone(), v.clone())).collect();
        for (g, cells) in groups {
            let nodes = nodes_of_cells(&w.mesh, &cells, "TOUS");
            w.add_node_group(occ, "TOUT_GROUP_MA", &g, nodes)?;
        }
        return Ok(());
    }
    if occ.has("GROUP_MA") && !occ.has("OPTION") {
        let gmas = occ.texts("GROUP_MA");
        let noms = occ.texts("NOM");
        if !noms.is_empty() && noms.len() != gmas.len() && noms.len() != 1 {
            return Err(occ.err(
                "NOM",
                format!("give one name, or as many names as groups of cells ({} names for {})", noms.len(), gmas.len()),
            ));
        }
        let crit = occ.text("CRIT_NOEUD").unwrap_or("TOUS").to_string();
        let mut lists = Vec::new();
        for g in &gmas {
            let cells = w.cell_group(occ, "GROUP_MA", g)?;
            lists.push(nodes_of_cells(&w.mesh, cells, &crit));
        }
        if noms.len() == 1 && gmas.len() > 1 {
            let mut acc = lists[0].clone();
            for l in &lists[1..] {
                acc = list_op("UNION", &acc, l);
            }
            return w.add_node_group(occ, "NOM", &noms[0], acc);
        }
        for (i, nodes) in lists.into_iter().enumerate() {
            let (name, kw) = if noms.is_empty() { (&gmas[i], "GROUP_MA") } else { (&noms[i], "NOM") };
            w.add_node_group(occ, kw, name, nodes)?;
        }
        return Ok(());
    }
    let name = occ.req_text("NOM")?.to_string();
    if w.mesh.node_groups.contains_key(&name) {
        return Err(occ.err("NOM", format!("group of nodes '{name}' already exists in mesh {}", w.label)));
    }
    let nodes = if let Some(op) = ["INTERSEC", "UNION", "DIFFE"].into_iter().find(|k| occ.has(k)) {
        let names = occ.texts(op);
        let mut acc = w.node_group(occ, op, &names[0])?.clone();
        for g in &names[1..] {
            acc = list_op(op, &acc, w.node_group(occ, op, g)?);
        }
        acc
    } else if let Some(opt) = occ.text("OPTION") {
        match opt {
            "PLAN" => plane_nodes(w, occ)?,
            "NOEUD_ORDO" => ordered_line_nodes(w, occ)?,
            _ => return Err(occ.err("OPTION", format!("OPTION='{opt}' is not supported yet"))),
        }
    } else if occ.has("NOEUD") {
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        for n in occ.texts("NOEUD") {
            let i = w.node(occ, "NOEUD", &n)?;
            if seen.insert(i) {
                out.push(i);
            } else {
                w.warn(format!("node '{n}' is given twice for group '{name}'"));
            }
        }
        out
    } else if let Some(g) = occ.texts("GROUP_NO").first() {
        if occ.vals("GROUP_NO").len() > 1 {
            return Err(occ.err("GROUP_NO", "several groups here are not supported yet (use UNION)"));
        }
        let members = w.node_group(occ, "GROUP_NO", g)?.clone();
        sub_range(occ, &members)?
    } else {
        return Err(occ.err("NOM", "nothing to build the group from"));
    };
    w.add_node_group(occ, "NOM", &name, nodes)
}

/// A point given by POINT, NOEUD_CENTRE or GROUP_NO_CENTRE (first node).
fn centre(w: &mut Work, occ: &Args, ndim: usize) -> Result<[f64; 3]> {
    if occ.has("POINT") {
        let p = occ.reals("POINT");
        if p.len() != ndim {
            return Err(occ.err("POINT", format!("{} coordinates given, the mesh is {ndim}D here", p.len())));
        }
        let mut x = [0.0; 3];
        x[..ndim].copy_from_slice(&p);
        return Ok(x);
    }
    let n = if let Some(name) = occ.text("NOEUD_CENTRE") {
        w.node(occ, "NOEUD_CENTRE", name)?
    } else if let Some(g) = occ.text("GROUP_NO_CENTRE") {
        *w.node_group(occ, "GROUP_NO_CENTRE", g)?.first().ok_or_else(|| occ.err("GROUP_NO_CENTRE", "empty group"))?
    } else {
        return Err(occ.err("POINT", "POINT, NOEUD_CENTRE or GROUP_NO_CENTRE is required"));
    };
    Ok(w.mesh.coords[n])
}

/// OPTION='PLAN' (`cgnopl`): nodes at distance <= PRECISION from the line
/// (2D: all z equal) or plane (3D) through the point with the given normal.
fn plane_nodes(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let z0 = w.mesh.coords.first().map(|c| c[2]).unwrap_or(0.0);
    let ndim = if w.mesh.coords.iter().all(|c| c[2] == z0) { 2 } else { 3 };
    let x0 = centre(w, occ, ndim)?;
    let mut nrm = [0.0f64; 3];
    if occ.has("VECT_NORMALE") {
        let v = occ.reals("VECT_NORMALE");
        if v.len() != ndim {
            return Err(occ.err("VECT_NORMALE", format!("{} components given, the mesh is {ndim}D here", v.len())));
        }
        nrm[..ndim].copy_from_slice(&v);
    } else if occ.has("ANGL_NAUT") {
        let ang: Vec<f64> = occ.reals("ANGL_NAUT").iter().map(|d| d.to_radians()).collect();
        if ndim == 2 {
            nrm = [ang[0].cos(), ang[0].sin(), 0.0];
        } else {
            let beta = ang.get(1).copied().unwrap_or(0.0);
            nrm = [ang[0].cos() * beta.cos(), ang[0].sin() * beta.cos(), -beta.sin()];
        }
    } else {
        return Err(occ.err("VECT_NORMALE", "VECT_NORMALE or ANGL_NAUT is required"));
    }
    let norm = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
    if norm == 0.0 {
        return Err(occ.err("VECT_NORMALE", "the normal vector is zero"));
    }
    let prec = occ.req_real("PRECISION")?;
    if prec <= 0.0 {
        return Err(occ.err("PRECISION", "PRECISION must be positive"));
    }
    Ok(w.mesh
        .coords
        .iter()
        .enumerate()
        .filter(|(_, c)| {
            let d: f64 = (0..3).map(|k| (c[k] - x0[k]) * nrm[k] / norm).sum();
            d.abs() <= prec
        })
        .map(|(i, _)| i)
        .collect())
}

/// The first node of a group named by keyword `kw` (Code_Aster's `utnono`).
fn group_first_node(w: &mut Work, occ: &Args, kw: &str) -> Result<Option<usize>> {
    let Some(g) = occ.text(kw) else { return Ok(None) };
    let members = w.node_group(occ, kw, g)?;
    let first = *members.first().ok_or_else(|| occ.err(kw, format!("group of nodes '{g}' is empty")))?;
    if members.len() > 1 {
        let shown = w.mesh.node_names[first].clone();
        w.warn(format!("{kw}: group '{g}' has several nodes, the first one ({shown}) is used"));
    }
    Ok(Some(first))
}

/// OPTION='NOEUD_ORDO' (`cgnoor` + `ornofd`): the nodes of a line of SEG2 /
/// SEG3 cells, ordered from the origin; SEG3 middle nodes between their
/// vertices.
fn ordered_line_nodes(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let mut cells: Vec<usize> = Vec::new();
    let mut seen = HashSet::new();
    for g in occ.texts("GROUP_MA") {
        for &c in w.cell_group(occ, "GROUP_MA", &g)? {
            if seen.insert(c) {
                cells.push(c);
            }
        }
    }
    if cells.is_empty() {
        return Err(occ.err("GROUP_MA", "no cells given"));
    }
    let t0 = w.mesh.cell_types[cells[0]];
    for &c in &cells {
        let t = w.mesh.cell_types[c];
        if !matches!(t, CellType::Seg2 | CellType::Seg3) {
            return Err(occ.err("GROUP_MA", format!("cell {} is a {}, not a segment", w.mesh.cell_names[c], t.name())));
        }
        if t != t0 {
            return Err(occ.err("GROUP_MA", "the segments must all be of the same type (SEG2 or SEG3)"));
        }
    }
    let ends: Vec<(usize, usize)> = cells.iter().map(|&c| (w.mesh.cells[c][0], w.mesh.cells[c][1])).collect();
    let mut degree: HashMap<usize, usize> = HashMap::new();
    for &(a, b) in &ends {
        *degree.entry(a).or_default() += 1;
        *degree.entry(b).or_default() += 1;
    }
    if degree.values().filter(|&&d| d == 1).count() > 2 || degree.values().any(|&d| d > 2) {
        return Err(occ.err("GROUP_MA", "the cells do not form one line without branches"));
    }
    let orig = group_first_node(w, occ, "GROUP_NO_ORIG")?;
    let extr = group_first_node(w, occ, "GROUP_NO_EXTR")?;
    let closed = orig.is_some() && orig == extr;
    for (kw, n) in [("GROUP_NO_EXTR", extr), ("GROUP_NO_ORIG", orig)] {
        if let Some(n) = n {
            let name = &w.mesh.node_names[n];
            match degree.get(&n) {
                None => return Err(occ.err(kw, format!("node {name} is not on the line"))),
                Some(&d) if d != 1 && !closed => {
                    return Err(occ.err(kw, format!("node {name} is not an end of the line")))
                }
                _ => {}
            }
        }
    }
    let start = match orig {
        Some(n) => n,
        None => {
            // The first end met (origin ends of all cells, then the others) used once.
            let order: Vec<usize> = ends.iter().map(|e| e.0).chain(ends.iter().map(|e| e.1)).collect();
            match order.iter().find(|n| degree[n] == 1) {
                Some(&n) => n,
                None if occ.text("ORIGINE") == Some("SANS") => order[0],
                None => return Err(occ.err("GROUP_MA", "the line is closed: give GROUP_NO_ORIG or ORIGINE='SANS'")),
            }
        }
    };
    // Walk the chain.
    let mut used = vec![false; cells.len()];
    let mut out = vec![start];
    let mut cur = start;
    for _ in 0..cells.len() {
        let next = (0..cells.len()).find(|&i| !used[i] && (ends[i].0 == cur || ends[i].1 == cur));
        let Some(i) = next else {
            return Err(
                occ.err("GROUP_MA", format!("the cells do not form one line from node {}", w.mesh.node_names[start]))
            );
        };
        used[i] = true;
        if t0 == CellType::Seg3 {
            out.push(w.mesh.cells[cells[i]][2]);
        }
        cur = if ends[i].0 == cur { ends[i].1 } else { ends[i].0 };
        out.push(cur);
    }
    if let Some(e) = extr {
        if cur != e {
            return Err(occ.err(
                "GROUP_NO_EXTR",
                format!(
                    "the line from {} ends at {}, not at {}",
                    w.mesh.node_names[start], w.mesh.node_names[cur], w.mesh.node_names[e]
                ),
            ));
        }
    }
    // VECT_ORIE orients a closed line.
    let v = occ.reals("VECT_ORIE");
    if v.iter().any(|x| *x != 0.0) && out.len() >= 3 && out[0] == out[out.len() - 1] {
        let dir = |a: usize, b: usize| -> f64 {
            let (p, q) = (w.mesh.coords[a], w.mesh.coords[b]);
            let d: Vec<f64> = (0..3).map(|k| q[k] - p[k]).collect();
            let len = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            d.iter().zip(v.iter().chain(std::iter::repeat(&0.0))).map(|(x, y)| x * y).sum::<f64>() / len
        };
        let nb = out.len();
        if dir(out[nb - 1], out[nb - 2]) > dir(out[0], out[1]) {
            out.reverse();
        }
    }
    Ok(out)
}

/// The INFO table of created groups, as in Code_Aster's message file.
fn created_table(title: &str, what: &str, groups: &[String], sizes: &BTreeMap<String, usize>) -> String {
    let mut s = format!("\n{title} : {}\n", groups.len());
    let _ = writeln!(s, "    {:<24} {what}", "group");
    for g in groups {
        let _ = writeln!(s, "    {g:<24} {:>8}", sizes.get(g).copied().unwrap_or(0));
    }
    s
}

pub fn defi_group(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let Some(c) = a.concept("MAILLAGE") else {
        return Err(a.err("MAILLAGE", "DEFI_GROUP needs MAILLAGE (GRILLE is not supported)"));
    };
    let mesh = (*mesh_of(&c).map_err(|e| locate(e, a, "MAILLAGE"))?).clone();
    let mut w = Work {
        mesh,
        label: c.label(),
        alarm: a.text("ALARME") != Some("NON"),
        node_index: None,
        cell_index: None,
        messages: String::new(),
        created_ma: Vec::new(),
        created_no: Vec::new(),
    };
    for occ in a.facts("DETR_GROUP_MA") {
        for g in occ.texts("NOM") {
            if w.mesh.cell_groups.remove(&g).is_none() {
                w.warn(format!("DETR_GROUP_MA: group of cells '{g}' is not in mesh {}", w.label));
            }
        }
    }
    for occ in a.facts("DETR_GROUP_NO") {
        for g in occ.texts("NOM") {
            if w.mesh.node_groups.remove(&g).is_none() {
                w.warn(format!("DETR_GROUP_NO: group of nodes '{g}' is not in mesh {}", w.label));
            }
        }
    }
    for occ in a.facts("CREA_GROUP_MA") {
        crea_group_ma(&mut w, occ)?;
    }
    for occ in a.facts("CREA_GROUP_NO") {
        crea_group_no(&mut w, occ)?;
    }
    let mut out = std::mem::take(&mut w.messages);
    if !w.created_ma.is_empty() {
        out.push_str(&created_table(
            "number of groups of cells created",
            "cells",
            &w.created_ma,
            &w.mesh.cell_group_sizes(),
        ));
    }
    if !w.created_no.is_empty() {
        out.push_str(&created_table(
            "number of groups of nodes created",
            "nodes",
            &w.created_no,
            &w.mesh.node_group_sizes(),
        ));
    }
    if a.int("INFO") == Some(2) {
        for g in &w.created_ma {
            let names: Vec<&str> = w.mesh.cell_groups[g].iter().map(|&c| w.mesh.cell_names[c].as_str()).collect();
            let _ = writeln!(out, "\ncells of group {g}:");
            for chunk in names.chunks(8) {
                let _ = writeln!(out, "  {}", chunk.join(" "));
            }
        }
        for g in &w.created_no {
            let names: Vec<&str> = w.mesh.node_groups[g].iter().map(|&n| w.mesh.node_names[n].as_str()).collect();
            let _ = writeln!(out, "\nnodes of group {g}:");
            for chunk in names.chunks(8) {
                let _ = writeln!(out, "  {}", chunk.join(" "));
            }
        }
    }
    if !out.is_empty() {
        ctx.io.mess(&out);
    }
    let rc = Rc::new(w.mesh);
    // Code_Aster's DEFI_GROUP result is its MAILLAGE, reuse or not.
    c.replace(ConceptData::Mesh(rc.clone()));
    Ok(Some(ConceptData::Mesh(rc)))
}

// ------------------------------------------------------------------ IMPR_RESU
//
// IMPR_RESU FORMAT='MED' writes one mesh and node fields on it. Field names
// follow Code_Aster (`mdnoch` and the Python IMPR_RESU): the result name
// (NOM_RESU_MED, else the concept name), cut to 8 characters and padded to 8
// with '_', then the field name (`RESU____DEPL`); NOM_CHAM_MED names them
// explicitly. A step is written as numdt = NUME_ORDRE at time INST. Like
// Code_Aster, a unit already written in the run is extended (its mesh is
// kept, fields are added), and a field missing at some selected steps or a
// NOM_CMP component missing from a field gives an alarm.

/// What one IMPR_RESU call writes: a mesh and node fields on it.
#[derive(Default)]
struct MedOut {
    mesh: Option<(String, Rc<Mesh>)>,
    fields: Vec<FieldOut>,
    alarms: String,
}

/// One node field to write: its MED name, components and
/// `(numdt, time, values interlaced per node)`.
struct FieldOut {
    med_name: String,
    components: Vec<String>,
    steps: Vec<(i32, f64, Vec<f64>)>,
}

impl MedOut {
    fn alarm(&mut self, msg: String) {
        let _ = writeln!(self.alarms, " <A> IMPR_RESU: {msg}");
    }

    /// The mesh of an occurrence: the first one fixes the file's mesh.
    fn use_mesh(&mut self, occ: &Args, kw: &str, name: String, mesh: Rc<Mesh>) -> Result<()> {
        match &self.mesh {
            None => {
                self.mesh = Some((name, mesh));
                Ok(())
            }
            Some((n, m)) if *n == name && (Rc::ptr_eq(m, &mesh) || m.nnodes() == mesh.nnodes()) => Ok(()),
            Some((n, _)) => Err(occ.err(
                kw,
                format!("this file already gets mesh {n}: several meshes in one MED file are not supported yet"),
            )),
        }
    }
}

/// Code_Aster's MED field name for field `symbol` of a result named `prefix`.
fn med_field_name(prefix: &str, symbol: &str) -> String {
    let short: String = prefix.chars().take(8).collect();
    format!("{short:_<8}{symbol}")
}

/// The name a concept is printed under (its variable name).
fn concept_name(c: &ConceptRef, fallback: &str) -> String {
    let n = c.name();
    if n.is_empty() {
        fallback.to_string()
    } else {
        n
    }
}

/// The values of a LIST_ORDRE / LIST_INST concept.
fn list_of(occ: &Args, kw: &str) -> Result<Option<Vec<f64>>> {
    occ.concept(kw).map(|c| super::functions::list_of(&c).map_err(|e| occ.err(kw, e.msg))).transpose()
}

/// The steps an occurrence selects (TOUT_ORDRE, NUME_ORDRE, LIST_ORDRE,
/// INST, LIST_INST; all steps by default), in the result's order.
pub(super) fn selected_steps<'r>(r: &'r ResultData, occ: &Args, name: &str) -> Result<Vec<&'r Step>> {
    for kw in ["NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE", "FREQ", "LIST_FREQ"] {
        if occ.has(kw) {
            return Err(occ.err(kw, format!("{kw} is not supported yet (only NUME_ORDRE and INST select steps)")));
        }
    }
    if r.steps.is_empty() {
        return Err(occ.err("RESULTAT", format!("result {name} holds no step")));
    }
    let mut wanted: Vec<i64> = Vec::new();
    let orders = if occ.has("NUME_ORDRE") {
        Some(("NUME_ORDRE", occ.ints("NUME_ORDRE")))
    } else {
        list_of(occ, "LIST_ORDRE")?.map(|v| ("LIST_ORDRE", v.iter().map(|&x| x as i64).collect()))
    };
    let insts = if occ.has("INST") {
        Some(("INST", occ.reals("INST")))
    } else {
        list_of(occ, "LIST_INST")?.map(|v| ("LIST_INST", v))
    };
    if let Some((kw, orders)) = orders {
        for n in orders {
            if r.by_order(n).is_none() {
                return Err(occ.err(kw, format!("result {name} has no order number {n}")));
            }
            wanted.push(n);
        }
    } else if let Some((kw, insts)) = insts {
        let crit = occ.text("CRITERE").unwrap_or("RELATIF");
        let prec = occ.real("PRECISION").unwrap_or(1.0e-6);
        for t in insts {
            let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
            let found: Vec<&Step> = r.steps.iter().filter(|s| (s.inst - t).abs() <= tol).collect();
            match found.as_slice() {
                [one] => wanted.push(one.nume_ordre),
                [] => {
                    return Err(occ.err(
                        kw,
                        format!("result {name} has no step at time {t} (CRITERE='{crit}', PRECISION={prec})"),
                    ))
                }
                many => {
                    let n: Vec<String> = many.iter().map(|s| s.nume_ordre.to_string()).collect();
                    return Err(occ.err(
                        kw,
                        format!("time {t} matches several steps of result {name} (order numbers {})", n.join(", ")),
                    ));
                }
            }
        }
    } else {
        return Ok(r.steps.iter().collect());
    }
    Ok(r.steps.iter().filter(|s| wanted.contains(&s.nume_ordre)).collect())
}

/// The fields an occurrence prints: NOM_CHAM (then `true`), none under
/// TOUT_CHAM='NON', else every field of the selected steps, sorted.
pub(super) fn selected_fields(steps: &[&Step], occ: &Args) -> (bool, Vec<String>) {
    if occ.has("NOM_CHAM") {
        return (true, occ.texts("NOM_CHAM"));
    }
    if occ.text("TOUT_CHAM") == Some("NON") {
        return (false, Vec::new());
    }
    let all: std::collections::BTreeSet<&String> = steps.iter().flat_map(|s| s.fields.keys()).collect();
    (false, all.into_iter().cloned().collect())
}

fn field_kind(f: &Field) -> &'static str {
    match f {
        Field::Node { .. } => "node (NOEU)",
        Field::Elno { .. } => "ELNO",
        Field::Elga { .. } => "ELGA",
        Field::Elem { .. } => "ELEM",
    }
}

/// Keywords of a RESU occurrence that IMPR_RESU (MED) does not handle yet.
fn refuse_med_keywords(occ: &Args) -> Result<()> {
    if occ.has("CHAM_GD") {
        return Err(occ.err("CHAM_GD", "printing a CHAM_GD to MED is not supported yet (MAILLAGE and RESULTAT are)"));
    }
    for kw in ["GROUP_MA", "GROUP_NO", "MAILLE"] {
        if occ.has(kw) {
            return Err(occ
                .err(kw, format!("{kw}: restricting fields to part of the mesh (MED profiles) is not supported yet")));
        }
    }
    if occ.has("PARTIE") {
        return Err(occ.err("PARTIE", "PARTIE applies to complex fields, which are not supported yet"));
    }
    if occ.has("NOM_PARA") {
        return Err(occ.err("NOM_PARA", "writing result parameters to MED (NOM_PARA) is not supported yet"));
    }
    if occ.has("SOUS_TITRE") {
        return Err(occ.err("SOUS_TITRE", "SOUS_TITRE is not supported yet with FORMAT='MED'"));
    }
    if occ.has("RESULTAT") {
        return Ok(());
    }
    for kw in ["NOM_CMP", "TOUT_CMP"] {
        if occ.has(kw) {
            return Err(occ.err(kw, format!("{kw} applies to fields; this occurrence prints a mesh only")));
        }
    }
    Ok(())
}

/// Collect the node fields of one RESULTAT occurrence.
fn plan_result(out: &mut MedOut, occ: &Args) -> Result<()> {
    let rc = occ.req_concept("RESULTAT")?;
    let rname = concept_name(&rc, "RESULTAT");
    let r = super::results::result_of(&rc).map_err(|e| locate(e, occ, "RESULTAT"))?;
    let model = super::model::model_of(&r.model).map_err(|e| locate(e, occ, "RESULTAT"))?;
    let mesh = mesh_of(&model.mesh_concept).unwrap_or_else(|_| model.current_mesh());
    if mesh.nnodes() != model.mesh.nnodes() {
        return Err(occ.err("RESULTAT", format!("the mesh of result {rname} changed since its model was made")));
    }
    out.use_mesh(occ, "RESULTAT", concept_name(&model.mesh_concept, "MAILLAGE"), mesh.clone())?;
    let steps = selected_steps(&r, occ, &rname)?;

    // Which fields, under which MED names.
    let (explicit, symbols) = selected_fields(&steps, occ);
    let med_names: Vec<String> = if occ.has("NOM_CHAM_MED") {
        let given = occ.texts("NOM_CHAM_MED");
        if !explicit || given.len() != symbols.len() {
            return Err(occ.err(
                "NOM_CHAM_MED",
                format!("give as many NOM_CHAM_MED as NOM_CHAM ({} for {})", given.len(), symbols.len()),
            ));
        }
        given
    } else {
        let prefix = match occ.text("NOM_RESU_MED") {
            Some(p) => {
                if occ.has("NOM_CMP") {
                    return Err(occ.err("NOM_CMP", "NOM_CMP cannot be given with NOM_RESU_MED"));
                }
                if p.is_empty() || p.len() > 8 {
                    return Err(occ.err("NOM_RESU_MED", format!("'{p}' must have 1 to 8 characters")));
                }
                p.to_string()
            }
            None => rname.clone(),
        };
        symbols.iter().map(|s| med_field_name(&prefix, s)).collect()
    };
    let kw_cham = if explicit { "NOM_CHAM" } else { "RESULTAT" };
    for m in &med_names {
        if m.is_empty() || m.len() > 64 || !m.is_ascii() {
            return Err(occ.err(
                if occ.has("NOM_CHAM_MED") { "NOM_CHAM_MED" } else { kw_cham },
                format!("'{m}' is not a MED field name (1 to 64 ASCII characters)"),
            ));
        }
    }

    let nom_cmp = occ.texts("NOM_CMP");
    let mut cmp_used = vec![false; nom_cmp.len()];
    let mut skipped = Vec::new();
    let nn = mesh.nnodes();
    'fields: for (sym, med_name) in symbols.iter().zip(&med_names) {
        let mut field_comps: Option<&Vec<String>> = None;
        let mut picked: Vec<(usize, String)> = Vec::new();
        let mut out_steps = Vec::new();
        let mut missing = Vec::new();
        for st in &steps {
            let (components, values) = match st.fields.get(sym) {
                None => {
                    missing.push(st.nume_ordre.to_string());
                    continue;
                }
                Some(Field::Node { components, values }) => (components, values),
                Some(other) if explicit => {
                    return Err(occ.err(
                        "NOM_CHAM",
                        format!(
                            "{sym} of result {rname} is an {} field: writing cell fields to MED is not supported yet \
                             (node fields are)",
                            field_kind(other)
                        ),
                    ))
                }
                Some(other) => {
                    skipped.push(format!("{sym} ({})", field_kind(other)));
                    continue 'fields;
                }
            };
            match field_comps {
                None => {
                    field_comps = Some(components);
                    picked = if nom_cmp.is_empty() {
                        components.iter().cloned().enumerate().collect()
                    } else {
                        let mut v = Vec::new();
                        for (j, c) in nom_cmp.iter().enumerate() {
                            if let Some(k) = components.iter().position(|x| x == c) {
                                cmp_used[j] = true;
                                v.push((k, c.clone()));
                            }
                        }
                        v
                    };
                    if picked.is_empty() {
                        out.alarm(format!(
                            "field {sym} of result {rname} has none of the components {} (it has {}): not written",
                            nom_cmp.join(" "),
                            components.join(" ")
                        ));
                        continue 'fields;
                    }
                }
                Some(first) if first != components => {
                    return Err(occ.err(
                        kw_cham,
                        format!(
                            "field {sym} of result {rname} has components [{}] at order {} but [{}] before",
                            components.join(" "),
                            st.nume_ordre,
                            first.join(" ")
                        ),
                    ))
                }
                Some(_) => {}
            }
            let nco = components.len();
            if values.len() != nn * nco {
                return Err(occ.err(
                    kw_cham,
                    format!(
                        "field {sym} of result {rname} at order {}: {} values for {nn} nodes x {nco} components",
                        st.nume_ordre,
                        values.len()
                    ),
                ));
            }
            let mut v = Vec::with_capacity(nn * picked.len());
            for i in 0..nn {
                for (k, c) in &picked {
                    let x = values[i * nco + k];
                    if !x.is_finite() {
                        return Err(occ.err(
                            kw_cham,
                            format!(
                                "field {sym} of result {rname} at order {}: node {} has no value for {c}; node \
                                 fields defined on part of the mesh (MED profiles) are not supported yet",
                                st.nume_ordre, mesh.node_names[i]
                            ),
                        ));
                    }
                    v.push(x);
                }
            }
            let numdt = i32::try_from(st.nume_ordre)
                .map_err(|_| occ.err(kw_cham, format!("order number {} does not fit in MED", st.nume_ordre)))?;
            out_steps.push((numdt, st.inst, v));
        }
        if out_steps.is_empty() {
            if explicit {
                return Err(occ.err(
                    "NOM_CHAM",
                    format!("result {rname} has no field {sym} at the selected steps (order {})", missing.join(", ")),
                ));
            }
            continue;
        }
        if !missing.is_empty() {
            out.alarm(format!("field {sym} of result {rname} is not computed at order {}", missing.join(", ")));
        }
        out.fields.push(FieldOut {
            med_name: med_name.clone(),
            components: picked.into_iter().map(|(_, c)| c).collect(),
            steps: out_steps,
        });
    }
    for (c, used) in nom_cmp.iter().zip(&cmp_used) {
        if !used {
            return Err(occ.err("NOM_CMP", format!("component {c} is in none of the fields written for {rname}")));
        }
    }
    if !skipped.is_empty() {
        out.alarm(format!(
            "result {rname}: {} not written (cell fields are not supported yet in MED output)",
            skipped.join(", ")
        ));
    }
    Ok(())
}

pub fn impr_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let format = a.text("FORMAT").unwrap_or("MED");
    if format == "RESULTAT" {
        return super::print::impr_resu_text(ctx, a);
    }
    if format == "GMSH" {
        return super::gmsh::impr_resu_gmsh(ctx, a);
    }
    if format != "MED" {
        return Err(a.err(
            "FORMAT",
            format!("IMPR_RESU FORMAT='{format}' is not supported yet (only 'MED', 'RESULTAT' and 'GMSH')"),
        ));
    }
    let mut out = MedOut::default();
    if let Some(v) = a.text("VERSION_MED").filter(|_| a.given("VERSION_MED")) {
        if v != "4.1.0" {
            out.alarm(format!("VERSION_MED='{v}': the file is written as MED 4.1.0"));
        }
    }
    let mut info = String::new();
    for occ in a.facts("RESU") {
        refuse_med_keywords(occ)?;
        if let Some(c) = occ.concept("MAILLAGE") {
            let mesh = mesh_of(&c).map_err(|e| locate(e, occ, "MAILLAGE"))?;
            out.use_mesh(occ, "MAILLAGE", concept_name(&c, "MAILLAGE"), mesh)?;
        }
        if occ.has("RESULTAT") {
            plan_result(&mut out, occ)?;
        }
        if let (Some("OUI"), Some((name, mesh))) = (occ.text("INFO_MAILLAGE"), &out.mesh) {
            info.push_str(&describe(mesh, name));
        }
    }
    let Some((mesh_name, mesh)) = out.mesh.take() else {
        return Err(a.err("RESU", "nothing to print: give MAILLAGE or RESULTAT"));
    };
    let unit = a.int("UNITE").unwrap_or(80);
    let path = ctx.io.unit_path(unit, true).map_err(|e| locate(e, a, "UNITE"))?;

    // A unit written earlier in the run is extended, as Code_Aster does.
    let existing = if path.exists() { med::list_meshes(&path).map_err(|e| locate(e, a, "UNITE"))? } else { Vec::new() };
    let reuse_mesh = existing.contains(&mesh_name);
    if !existing.is_empty() && !reuse_mesh {
        return Err(a.err(
            "UNITE",
            format!(
                "unit {unit} already holds mesh {}: adding mesh {mesh_name} (several meshes in one MED file) is \
                 not supported yet",
                existing.join(", ")
            ),
        ));
    }
    if reuse_mesh {
        let there = med::read_mesh(&path, Some(&mesh_name)).map_err(|e| locate(e, a, "UNITE"))?;
        if there.nnodes() != mesh.nnodes() || there.ncells() != mesh.ncells() {
            return Err(a.err(
                "UNITE",
                format!("unit {unit} already holds another mesh named {mesh_name} ({} nodes)", there.nnodes()),
            ));
        }
        let _ = writeln!(info, " IMPR_RESU: mesh {mesh_name} is already in unit {unit}: the fields are added to it");
    }

    // Build the whole file beside the unit, then rename it into place.
    let tmp = med::temp_path(&path);
    let build = || -> Result<()> {
        if reuse_mesh {
            std::fs::copy(&path, &tmp)
                .map_err(|e| Error::io(format!("unit {unit}: cannot copy {}: {e}", path.display())))?;
        } else {
            med::write_mesh(&tmp, &mesh, &mesh_name)?;
        }
        for f in &out.fields {
            let comps: Vec<&str> = f.components.iter().map(String::as_str).collect();
            med::write_node_field(&tmp, &mesh_name, &f.med_name, &comps, &f.steps)?;
        }
        std::fs::rename(&tmp, &path)
            .map_err(|e| Error::io(format!("unit {unit}: cannot move the MED file into place: {e}")))
    };
    if let Err(e) = build() {
        let _ = std::fs::remove_file(&tmp);
        return Err(locate(e, a, "UNITE"));
    }
    let mut mess = info;
    mess.push_str(&out.alarms);
    if !mess.is_empty() {
        ctx.io.mess(&mess);
    }
    Ok(None)
}
