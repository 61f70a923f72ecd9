//! LIRE_MAILLAGE (every format, with VERI_MAIL's checks), DEFI_GROUP.
//!
//! DEFI_GROUP follows Code_Aster's `sscgma` / `sscgno`: destruction first,
//! then CREA_GROUP_MA, then CREA_GROUP_NO, occurrence by occurrence, so an
//! occurrence sees the groups made by the previous ones. Node groups built
//! from cells are sorted by node number; INTERSEC / UNION / DIFFE keep the
//! order of the first group (UNION appends the new members of the others);
//! NOEUD, MAILLE and GROUP_NO keep the order given. An existing group name
//! is an error; an empty result is a warning and creates no group. Code_Aster
//! modifies the mesh of MAILLAGE in place even without `reuse`; so do we.

pub mod crea_maillage;
pub mod orient;

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::med;
use crate::mesh::{CellType, Mesh};
use crate::stages::Ctx;
use nalgebra::Vector3;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::rc::Rc;

// ------------------------------------------------------------------ LIRE_MAILLAGE

/// LIRE_MAILLAGE: a MED file (the mesh NOM_MED, else the first), or a text format read as Code_Aster
/// converts it (ASTER, GMSH, GIBI, IDEAS: see `mesh::TextFormat`); then, where VERI_MAIL is given,
/// its checks: their alarms go to the message file, their errors stop the command. (Code_Aster runs
/// them on every mesh; without the keyword we do not yet, so as not to stop a mesh Code_Aster takes on
/// a check of ours that is stricter than its own.)
pub fn lire_maillage(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let format = a.text("FORMAT").unwrap_or("MED");
    let unit = a.int("UNITE").unwrap_or(20);
    let path = ctx.io.unit_path(unit, false).map_err(|e| a.locate(e, "UNITE"))?;
    let info = a.int("INFO").unwrap_or(1);
    // INFO_MED only sets the verbosity of Code_Aster's MED library, PARTITIONNEUR='PTSCOTCH' the
    // distribution of a mesh over MPI processes: a mesh read whole on one process (what
    // Code_Aster does without MPI, with an alarm) is the same mesh.
    let _ = a.int("INFO_MED");
    if a.text("PARTITIONNEUR") == Some("PTSCOTCH") {
        ctx.io.mess(" <A> LIRE_MAILLAGE: PARTITIONNEUR='PTSCOTCH' needs MPI: the mesh is read whole\n");
    }
    let (mesh, shown) = match crate::mesh::TextFormat::from_keyword(format) {
        Some(mut text) => {
            if a.text("CREA_GROUP_COUL") == Some("OUI") {
                text = crate::mesh::TextFormat::Ideas { colour_groups: true };
            }
            let bytes = std::fs::read(&path)
                .map_err(|e| a.err("UNITE", format!("unit {unit}: cannot read {}: {e}", path.display())))?;
            let src = String::from_utf8_lossy(&bytes);
            let file = path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
            (text.read(&src, &file).map_err(|e| a.err("UNITE", e))?, file)
        }
        None => {
            let nom_med = a.text("NOM_MED");
            let mesh = med::read_mesh(&path, nom_med)
                .map_err(|e| a.locate(e, if nom_med.is_some() { "NOM_MED" } else { "UNITE" }))?;
            let shown = match nom_med {
                Some(n) => n.to_string(),
                None => med::list_meshes(&path).ok().and_then(|v| v.into_iter().next()).unwrap_or_default(),
            };
            (mesh, shown)
        }
    };
    if info >= 2 {
        ctx.io.mess(&format!("LIRE_MAILLAGE: unit {unit} ({})\n{}", path.display(), mesh.describe(&shown)));
    }
    if let Some(v) = a.fact("VERI_MAIL") {
        if v.text("VERIF") != Some("NON") {
            let report = crate::mesh::check::check(&mesh, v.real("APLAT").unwrap_or(1.0e-3));
            let mut text = String::new();
            for m in &report.alarms {
                text.push_str(&format!(" <A> LIRE_MAILLAGE: VERI_MAIL: {m}\n"));
            }
            for m in &report.errors {
                text.push_str(&format!(" <E> LIRE_MAILLAGE: VERI_MAIL: {m}\n"));
            }
            if !text.is_empty() {
                ctx.io.mess(&text);
            }
            if let Some(first) = report.errors.first() {
                return Err(v.err(
                    "VERIF",
                    format!("the mesh is invalid ({first}{}); VERIF='NON' skips the check", more(report.errors.len())),
                ));
            }
        }
    }
    Ok(Some(ConceptData::Mesh(Rc::new(mesh))))
}

fn more(n: usize) -> String {
    if n > 1 {
        format!(", and {} more error(s) in the message file", n - 1)
    } else {
        String::new()
    }
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
        let k = idx.get(name).copied().or_else(|| crate::mesh::numbered(name, 'N', mesh.nnodes()));
        k.ok_or_else(|| occ.err(kw, format!("node '{name}' is not in mesh {}", self.label)))
    }

    fn cell(&mut self, occ: &Args, kw: &str, name: &str) -> Result<usize> {
        let mesh = &self.mesh;
        let idx = self
            .cell_index
            .get_or_insert_with(|| mesh.cell_names.iter().enumerate().map(|(i, n)| (n.clone(), i)).collect());
        let c = idx.get(name).copied().or_else(|| crate::mesh::numbered(name, 'M', mesh.ncells()));
        c.ok_or_else(|| occ.err(kw, format!("cell '{name}' is not in mesh {}", self.label)))
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
        match opt {
            "SPHERE" | "CYLINDRE" | "BANDE" => cells_in_shape(w, occ, opt)?,
            "FACE_NORMALE" => cells_facing(w, occ)?,
            "APPUI" => cells_on_nodes(w, occ)?,
            _ => return Err(occ.err("OPTION", format!("OPTION='{opt}' is not supported yet"))),
        }
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
            "ENV_SPHERE" | "ENV_CYLINDRE" => nodes_on_surface(w, occ, opt)?,
            "SEGM_DROI_ORDO" => ordered_segment_nodes(w, occ)?,
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

/// The dimension DEFI_GROUP's geometric options work in (Code_Aster's `Z_CST`): 2 when every node has
/// the same z, where z is then left out (taken as 0), else 3.
fn z_cst_dim(mesh: &Mesh) -> usize {
    let z0 = mesh.coords.first().map(|c| c[2]).unwrap_or(0.0);
    if mesh.coords.iter().all(|c| c[2] == z0) {
        2
    } else {
        3
    }
}

/// A node's coordinates as the geometric options see them in dimension `ndim` (z is 0 in 2D).
fn seen(c: &[f64; 3], ndim: usize) -> Vector3<f64> {
    Vector3::new(c[0], c[1], if ndim == 2 { 0.0 } else { c[2] })
}

/// A point given by POINT, NOEUD_CENTRE or GROUP_NO_CENTRE (first node), in dimension `ndim`.
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
    let x = seen(&w.mesh.coords[n], ndim);
    Ok([x[0], x[1], x[2]])
}

/// The unit direction of VECT_NORMALE (`ndim` components) or ANGL_NAUT (`ndim − 1` angles in degrees:
/// in 2D (cos α, sin α), in 3D (cos α cos β, sin α cos β, −sin β)). With `exact`, ANGL_NAUT must give
/// exactly `ndim − 1` angles; without (OPTION='PLAN'), the first ones are used and a missing β is 0.
fn unit_direction(occ: &Args, ndim: usize, exact: bool) -> Result<Vector3<f64>> {
    let v = if occ.has("VECT_NORMALE") {
        let v = occ.reals("VECT_NORMALE");
        if v.len() != ndim {
            return Err(occ.err("VECT_NORMALE", format!("{} components given, the mesh is {ndim}D here", v.len())));
        }
        Vector3::from_fn(|k, _| v.get(k).copied().unwrap_or(0.0))
    } else if occ.has("ANGL_NAUT") {
        let ang: Vec<f64> = occ.reals("ANGL_NAUT").iter().map(|d| d.to_radians()).collect();
        if ang.is_empty() || (exact && ang.len() != ndim - 1) {
            return Err(occ.err("ANGL_NAUT", format!("{} angle(s) given, {} needed in {ndim}D", ang.len(), ndim - 1)));
        }
        if ndim == 2 {
            Vector3::new(ang[0].cos(), ang[0].sin(), 0.0)
        } else {
            let beta = ang.get(1).copied().unwrap_or(0.0);
            Vector3::new(ang[0].cos() * beta.cos(), ang[0].sin() * beta.cos(), -beta.sin())
        }
    } else {
        return Err(occ.err("VECT_NORMALE", "VECT_NORMALE or ANGL_NAUT is required"));
    };
    let norm = v.norm();
    if norm == 0.0 {
        return Err(occ.err(if occ.has("VECT_NORMALE") { "VECT_NORMALE" } else { "ANGL_NAUT" }, "the vector is zero"));
    }
    Ok(v / norm)
}

/// A strictly positive real keyword.
fn positive(occ: &Args, kw: &str) -> Result<f64> {
    let v = occ.req_real(kw)?;
    if v <= 0.0 {
        return Err(occ.err(kw, format!("{kw} must be positive")));
    }
    Ok(v)
}

/// The squared distance of `x` from the axis through `x0` along the unit vector `axe` (Code_Aster's
/// `cgmacy` / `cgnoec`: |x − x0|² sin² of the angle with the axis).
fn axis_distance2(x: Vector3<f64>, x0: Vector3<f64>, axe: &Vector3<f64>) -> f64 {
    let d = x - x0;
    let r2 = d.norm_squared();
    if r2 == 0.0 {
        return 0.0;
    }
    let cos = (d.dot(axe) / r2.sqrt()).abs().min(1.0);
    r2 * cos.acos().sin().powi(2)
}

/// OPTION='PLAN' (`cgnopl`): nodes at distance <= PRECISION from the line
/// (2D: all z equal) or plane (3D) through the point with the given normal.
fn plane_nodes(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let ndim = z_cst_dim(&w.mesh);
    let x0 = Vector3::from(centre(w, occ, ndim)?);
    let nrm = unit_direction(occ, ndim, false)?;
    let prec = positive(occ, "PRECISION")?;
    Ok((0..w.mesh.nnodes()).filter(|&n| (seen(&w.mesh.coords[n], ndim) - x0).dot(&nrm).abs() <= prec).collect())
}

/// CREA_GROUP_NO OPTION='ENV_SPHERE' (`cgnoes`) and 'ENV_CYLINDRE' (`cgnoec`, 3D only): the nodes within
/// PRECISION of the sphere of RAYON about the centre, or of the cylinder of RAYON about the axis through
/// it, in node order.
fn nodes_on_surface(w: &mut Work, occ: &Args, opt: &str) -> Result<Vec<usize>> {
    let ndim = z_cst_dim(&w.mesh);
    let cylinder = opt == "ENV_CYLINDRE";
    if cylinder && ndim != 3 {
        return Err(occ.err("OPTION", "OPTION='ENV_CYLINDRE' needs a 3D mesh (its nodes all have the same z)"));
    }
    let x0 = Vector3::from(centre(w, occ, ndim)?);
    let axe = if cylinder { Some(unit_direction(occ, 3, true)?) } else { None };
    let rayon = positive(occ, "RAYON")?;
    let prec = positive(occ, "PRECISION")?;
    Ok((0..w.mesh.nnodes())
        .filter(|&n| {
            let x = seen(&w.mesh.coords[n], ndim);
            let dist = match &axe {
                Some(axe) => axis_distance2(x, x0, axe).sqrt(),
                None => (x - x0).norm(),
            };
            (dist - rayon).abs() <= prec
        })
        .collect())
}

/// The cells whose nodes pass `inside` as CRIT_NOEUD asks: AU_MOINS_UN one of them, TOUS all, MAJORITE
/// at least half (rounded up), in cell order.
fn cells_by_nodes(mesh: &Mesh, crit: &str, inside: impl Fn(usize) -> bool) -> Vec<usize> {
    (0..mesh.ncells())
        .filter(|&c| {
            let nodes = &mesh.cells[c];
            match crit {
                "AU_MOINS_UN" => nodes.iter().any(|&n| inside(n)),
                "TOUS" => nodes.iter().all(|&n| inside(n)),
                _ => nodes.iter().filter(|&&n| inside(n)).count() >= nodes.len().div_ceil(2),
            }
        })
        .collect()
}

/// CREA_GROUP_MA OPTION='SPHERE' (`cgmasp`: nodes within RAYON of the centre), 'CYLINDRE' (`cgmacy`,
/// 3D: within RAYON of the axis) and 'BANDE' (`cgmaba`: within DIST of the plane (3D) or line (2D)
/// through the centre normal to the direction), cells chosen by CRIT_NOEUD.
fn cells_in_shape(w: &mut Work, occ: &Args, opt: &str) -> Result<Vec<usize>> {
    let ndim = z_cst_dim(&w.mesh);
    if opt == "CYLINDRE" && ndim != 3 {
        return Err(occ.err("OPTION", "OPTION='CYLINDRE' needs a 3D mesh (its nodes all have the same z)"));
    }
    let x0 = Vector3::from(centre(w, occ, ndim)?);
    let crit = occ.text("CRIT_NOEUD").unwrap_or("AU_MOINS_UN").to_string();
    let mesh = &w.mesh;
    let cells = match opt {
        "SPHERE" => {
            let r = positive(occ, "RAYON")?;
            cells_by_nodes(mesh, &crit, |n| (seen(&mesh.coords[n], ndim) - x0).norm_squared() <= r * r)
        }
        "CYLINDRE" => {
            let r = positive(occ, "RAYON")?;
            let axe = unit_direction(occ, 3, true)?;
            // A node on the centre itself takes its cell whatever CRIT_NOEUD says (as `cgmacy` does).
            let on_centre: HashSet<usize> =
                (0..mesh.nnodes()).filter(|&n| Vector3::from(mesh.coords[n]) == x0).collect();
            let mut cells =
                cells_by_nodes(mesh, &crit, |n| axis_distance2(Vector3::from(mesh.coords[n]), x0, &axe) <= r * r);
            if !on_centre.is_empty() {
                let chosen: HashSet<usize> = cells.iter().copied().collect();
                cells.extend(
                    (0..mesh.ncells())
                        .filter(|c| !chosen.contains(c) && mesh.cells[*c].iter().any(|n| on_centre.contains(n))),
                );
                cells.sort_unstable();
            }
            cells
        }
        _ => {
            let dist = positive(occ, "DIST")?;
            let nrm = unit_direction(occ, ndim, true)?;
            cells_by_nodes(mesh, &crit, |n| (Vector3::from(mesh.coords[n]) - x0).dot(&nrm).abs() <= dist)
        }
    };
    Ok(cells)
}

/// CREA_GROUP_MA OPTION='FACE_NORMALE' (`cgmafn`): the SEG cells of a 2D mesh, or the TRIA and QUAD
/// cells of a 3D one, whose normal (of the first two nodes, or of the plane of the first three) is
/// within ANGL_PREC degrees of the direction; with VERI_SIGNE='OUI' (the default) it must also point
/// the same way.
fn cells_facing(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let dir = unit_direction(occ, z_cst_dim(&w.mesh), true)?;
    let prec = occ.real("ANGL_PREC").unwrap_or(0.5).to_radians();
    let signed = occ.text("VERI_SIGNE").unwrap_or("OUI") == "OUI";
    let mesh = &w.mesh;
    let mut out = Vec::new();
    for c in 0..mesh.ncells() {
        let name = mesh.cell_types[c].name();
        let p = |k: usize| Vector3::from(mesh.coords[mesh.cells[c][k]]);
        let normal = if mesh.dim == 2 && name.starts_with("SEG") {
            let d = p(1) - p(0);
            Vector3::new(d[1], -d[0], 0.0)
        } else if mesh.dim == 3 && (name.starts_with("TRIA") || name.starts_with("QUAD")) {
            (p(1) - p(0)).cross(&(p(2) - p(0)))
        } else {
            continue;
        };
        let norm = normal.norm();
        if norm == 0.0 {
            return Err(occ.err("OPTION", format!("cell {} is degenerate: it has no normal", mesh.cell_names[c])));
        }
        let normal = normal / norm;
        let dot = normal.dot(&dir);
        if signed && dot <= 0.0 {
            continue;
        }
        if dot.abs().min(1.0).acos() < prec.abs() {
            out.push(c);
        }
    }
    Ok(out)
}

/// CREA_GROUP_MA OPTION='APPUI' (`cgmaap`): the cells that touch the nodes of NOEUD / GROUP_NO as
/// TYPE_APPUI asks: AU_MOINS_UN one node, TOUT all their nodes, SOMMET all their vertices, MAJORITE at
/// least half their nodes (rounded up); in cell order.
fn cells_on_nodes(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let mut given = vec![false; w.mesh.nnodes()];
    for name in occ.texts("NOEUD") {
        given[w.node(occ, "NOEUD", &name)?] = true;
    }
    for g in occ.texts("GROUP_NO") {
        for &n in w.node_group(occ, "GROUP_NO", &g)? {
            given[n] = true;
        }
    }
    let kind = occ.req_text("TYPE_APPUI")?;
    let mesh = &w.mesh;
    Ok((0..mesh.ncells())
        .filter(|&c| {
            let nodes = &mesh.cells[c];
            if !nodes.iter().any(|&n| given[n]) {
                return false;
            }
            let count = |k: usize| nodes[..k].iter().filter(|&&n| given[n]).count();
            match kind {
                "AU_MOINS_UN" => true,
                "TOUT" => count(nodes.len()) == nodes.len(),
                "SOMMET" => {
                    let nv = mesh.cell_types[c].nvertices();
                    count(nv) == nv
                }
                _ => count(nodes.len()) >= nodes.len().div_ceil(2),
            }
        })
        .collect())
}

/// CREA_GROUP_NO OPTION='SEGM_DROI_ORDO' (`cgnoso` + `oreino`): the nodes of NOEUD / GROUP_NO ordered
/// along the segment from GROUP_NO_ORIG to GROUP_NO_EXTR. Each must lie within PRECISION of the line
/// (CRITERE='ABSOLU' a distance, 'RELATIF' relative to the segment's length) and between the ends, and
/// no two may project on the same point: Code_Aster stops otherwise.
fn ordered_segment_nodes(w: &mut Work, occ: &Args) -> Result<Vec<usize>> {
    let mut nodes = Vec::new();
    let mut seen_nodes = HashSet::new();
    for g in occ.texts("GROUP_NO") {
        for &n in w.node_group(occ, "GROUP_NO", &g)? {
            if seen_nodes.insert(n) {
                nodes.push(n);
            }
        }
    }
    for name in occ.texts("NOEUD") {
        let n = w.node(occ, "NOEUD", &name)?;
        if seen_nodes.insert(n) {
            nodes.push(n);
        }
    }
    if nodes.is_empty() {
        return Err(occ.err("GROUP_NO", "no nodes given"));
    }
    let a = group_first_node(w, occ, "GROUP_NO_ORIG")?.ok_or_else(|| occ.err("GROUP_NO_ORIG", "required"))?;
    let b = group_first_node(w, occ, "GROUP_NO_EXTR")?.ok_or_else(|| occ.err("GROUP_NO_EXTR", "required"))?;
    let prec = occ.req_real("PRECISION")?;
    let relative = occ.req_text("CRITERE")? == "RELATIF";
    let mesh = &w.mesh;
    let (xa, xb) = (Vector3::from(mesh.coords[a]), Vector3::from(mesh.coords[b]));
    let ab = xb - xa;
    let ab2 = ab.norm_squared();
    if ab2 == 0.0 {
        return Err(occ.err("GROUP_NO_EXTR", "the origin and the end are the same point"));
    }
    let mut keyed = Vec::with_capacity(nodes.len());
    for &n in &nodes {
        let am = Vector3::from(mesh.coords[n]) - xa;
        let c = am.dot(&ab) / ab2;
        let off2 = (am - c * ab).norm_squared();
        let off = if relative { (off2 / ab2).sqrt() } else { off2.sqrt() };
        if off > prec {
            return Err(occ.err(
                "PRECISION",
                format!("node {} is {:e} from the segment, beyond PRECISION", mesh.node_names[n], off2.sqrt()),
            ));
        }
        if (c < 0.0 || am.norm_squared() > ab2) && (am.norm_squared() - ab2) / ab2 > f64::EPSILON {
            return Err(occ.err(
                "GROUP_NO",
                format!("node {} is outside the segment (abscissa {c:e} of its length)", mesh.node_names[n]),
            ));
        }
        keyed.push((c, n));
    }
    keyed.sort_by(|p, q| p.0.total_cmp(&q.0));
    if let Some(pair) = keyed.windows(2).find(|p| p[0].0 == p[1].0) {
        return Err(occ.err(
            "GROUP_NO",
            format!(
                "nodes {} and {} are at the same place on the segment",
                mesh.node_names[pair[0].1], mesh.node_names[pair[1].1]
            ),
        ));
    }
    Ok(keyed.into_iter().map(|(_, n)| n).collect())
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
/// SEG3 cells, ordered from the origin (`mesh::line`).
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
    let how = crate::mesh::line::LineEnds {
        orig: group_first_node(w, occ, "GROUP_NO_ORIG")?,
        extr: group_first_node(w, occ, "GROUP_NO_EXTR")?,
        no_origin: occ.text("ORIGINE") == Some("SANS"),
        vect_orie: occ.reals("VECT_ORIE"),
    };
    crate::mesh::line::ordered_nodes(&w.mesh, &cells, &how).map_err(|e| occ.err(e.keyword, e.message))
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
    let mesh = (*c.mesh().map_err(|e| a.locate(e, "MAILLAGE"))?).clone();
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
