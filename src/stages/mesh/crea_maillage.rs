//! CREA_MAILLAGE: a new mesh made from MAILLAGE.
//!
//! LINE_QUAD and QUAD_LINE change the degree of cells with Code_Aster 2025's numbering
//! ([`crate::mesh::convert`]). Code_Aster 2025 builds the new mesh without names, whatever the input
//! carried: its nodes and cells are `N` / `M` + number, and a file designates them so (a name the
//! input's file gave no longer designates its node). A LINE_QUAD occurrence that gives PREF_NOEUD or PREF_NUME (keywords of the 2020
//! syntax, gone in 2025) gets the 2020 operator instead: its numbering and the names PREF_NOEUD +
//! (PREF_NUME − 1 + k). HEXA20_27 adds face and cell centres with the same module. CREA_MAILLE, CREA_POI1, MODI_MAILLE OPTION='QUAD8_9' and RESTREINT follow
//! `op0167` and `rdtmai` ([`crate::mesh::derive`]); their 2020 naming keywords (PREF_MAILLE,
//! PREF_NOEUD, PREF_NUME) are refused by name. The other operations stop by name until they are
//! implemented.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::convert::{self, Converted};
use crate::mesh::derive::{self, Groups};
use crate::mesh::{CellType, Mesh};
use crate::stages::select::{select_cells, select_nodes};
use crate::stages::Ctx;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::rc::Rc;

/// Operations and keywords of CREA_MAILLAGE not implemented yet.
const NOT_YET: &[&str] =
    &["COQU_VOLU", "CREA_FISS", "PENTA15_18", "MODI_HHO", "COQUE_SOLIDE", "REPERE", "DECOUPE_LAC", "ECLA_PG", "TITRE"];

pub fn crea_maillage(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(NOT_YET)?;
    let c = a.concept("MAILLAGE").ok_or_else(|| a.err("MAILLAGE", "MAILLAGE is required here"))?;
    let mesh = c.mesh().map_err(|e| a.locate(e, "MAILLAGE"))?;
    let label = c.label();
    let mut mess = String::new();
    // Only LINE_QUAD in the 2020 syntax names what it makes; every other operation makes a mesh
    // without names, as Code_Aster 2025 does (`op0167` and `rdtmai` build no `.NOMNOE` / `.NOMMAI`).
    let syntax_2020 = a.fact("LINE_QUAD").is_some_and(|o| o.given("PREF_NOEUD") || o.given("PREF_NUME"));
    let mut out = if let Some(occ) = a.fact("LINE_QUAD") {
        line_quad(&mesh, occ, &label, &mut mess)?
    } else if let Some(occ) = a.fact("QUAD_LINE") {
        quad_line(&mesh, occ, &label, &mut mess)?
    } else if let Some(occ) = a.fact("HEXA20_27") {
        hexa20_27(&mesh, occ, &label, &mut mess)?
    } else if a.has("CREA_MAILLE") {
        crea_maille(&mesh, a.facts("CREA_MAILLE"), &label, &mut mess)?
    } else if a.has("CREA_POI1") {
        crea_poi1(&mesh, a.facts("CREA_POI1"), &label, &mut mess)?
    } else if a.has("MODI_MAILLE") {
        modi_maille(&mesh, a.facts("MODI_MAILLE"), &label, &mut mess)?
    } else if let Some(occ) = a.fact("RESTREINT") {
        restreint(&mesh, occ, &label, &mut mess)?
    } else {
        // The catalogue asks for exactly one operation and the others are refused above.
        return Err(a.err("MAILLAGE", "no operation given"));
    };
    if !syntax_2020 {
        number_names(&mut out);
    }
    if a.int("INFO") == Some(2) {
        mess.push_str(&out.describe("(CREA_MAILLAGE)"));
    }
    ctx.io.mess(&mess);
    Ok(Some(ConceptData::Mesh(Rc::new(out))))
}

/// The cells of an occurrence whose TOUT / GROUP_MA / MAILLE default to the whole mesh (Code_Aster
/// 2025's `UN_PARMI("TOUT", "GROUP_MA", TOUT="OUI")`); an empty selection is an error, as in `getelem`.
fn cells_or_all(mesh: &Mesh, occ: &Args, label: &str) -> Result<Vec<usize>> {
    if !["TOUT", "GROUP_MA", "MAILLE"].iter().any(|k| occ.has(k)) {
        return Ok((0..mesh.ncells()).collect());
    }
    let cells = select_cells(mesh, occ, label)?;
    if cells.is_empty() {
        let kw = ["GROUP_MA", "MAILLE"].into_iter().find(|k| occ.has(k)).unwrap_or("TOUT");
        return Err(occ.err(kw, "the selection holds no cell"));
    }
    Ok(cells)
}

/// [`cells_or_all`], with Code_Aster's alarm when they are not all the cells of the mesh.
fn cells_of(mesh: &Mesh, occ: &Args, label: &str, what: &str, mess: &mut String) -> Result<Vec<usize>> {
    let cells = cells_or_all(mesh, occ, label)?;
    if cells.len() != mesh.ncells() {
        let _ = writeln!(
            mess,
            " <A> CREA_MAILLAGE: {what} changes {} of the {} cells of mesh {label}: the result may not be conforming",
            cells.len(),
            mesh.ncells()
        );
    }
    Ok(cells)
}

/// "n FROM -> TO" for every conversion.
fn conversions(conv: &Converted) -> String {
    let parts: Vec<String> =
        conv.counts.iter().map(|((f, t), n)| format!("{n} {} -> {}", f.name(), t.name())).collect();
    if parts.is_empty() {
        "no cell converted".to_string()
    } else {
        parts.join(", ")
    }
}

fn line_quad(mesh: &Mesh, occ: &Args, label: &str, mess: &mut String) -> Result<Mesh> {
    let cells = cells_of(mesh, occ, label, "LINE_QUAD", mess)?;
    let syntax_2020 = occ.given("PREF_NOEUD") || occ.given("PREF_NUME");
    let conv = if syntax_2020 { convert::line_to_quad_2020(mesh, &cells) } else { convert::line_to_quad(mesh, &cells) };
    let mut out = conv.mesh.clone();
    let created = out.nnodes() - conv.first_new;
    if syntax_2020 {
        let prefix = occ.text("PREF_NOEUD").unwrap_or("NS");
        let start = occ.int("PREF_NUME").unwrap_or(1);
        let kw = if occ.given("PREF_NOEUD") { "PREF_NOEUD" } else { "PREF_NUME" };
        for k in 0..created {
            let name = format!("{prefix}{}", start + k as i64);
            if name.len() > 8 {
                return Err(occ.err(kw, format!("node name '{name}' would be longer than 8 characters")));
            }
            out.node_names[conv.first_new + k] = name;
        }
        if created == 0 {
            let _ = writeln!(mess, " <A> CREA_MAILLAGE: LINE_QUAD: there is no linear cell to convert");
        }
    }
    // In the 2020 syntax a new name must not be the name of a node of the input (the mesh keeps its
    // names there).
    let old: HashSet<&str> = mesh.node_names.iter().map(String::as_str).collect();
    if let Some(n) = out.node_names[conv.first_new..].iter().find(|n| syntax_2020 && old.contains(n.as_str())) {
        return Err(occ.err(
            "PREF_NOEUD",
            format!("new node {n}: a node of mesh {label} already has this name (its file named the nodes)"),
        ));
    }
    let _ = write!(mess, "CREA_MAILLAGE/LINE_QUAD on {label}: {}", conversions(&conv));
    if created > 0 {
        let _ = write!(
            mess,
            "; {created} nodes created, {} to {}",
            out.node_names[conv.first_new],
            out.node_names[out.nnodes() - 1]
        );
    }
    mess.push('\n');
    Ok(out)
}

/// HEXA20_27: QUAD8 -> QUAD9 and HEXA20 -> HEXA27 (`cm2027`).
fn hexa20_27(mesh: &Mesh, occ: &Args, label: &str, mess: &mut String) -> Result<Mesh> {
    occ.refuse(&["PREF_NOEUD", "PREF_NUME"])?;
    let cells = cells_of(mesh, occ, label, "HEXA20_27", mess)?;
    if mesh.cell_types.iter().any(|t| matches!(t, CellType::Penta15 | CellType::Pyram13)) {
        let _ = writeln!(
            mess,
            " <A> CREA_MAILLAGE: HEXA20_27 adds centres to quadrangular faces, but PENTA15 or PYRAM13 cells \
             keep 8-node faces: the result may not be conforming"
        );
    }
    let conv = convert::hexa20_to_27(mesh, &cells);
    let created = conv.mesh.nnodes() - conv.first_new;
    let _ = writeln!(mess, "CREA_MAILLAGE/HEXA20_27 on {label}: {}; {created} nodes created", conversions(&conv));
    Ok(conv.mesh)
}

fn quad_line(mesh: &Mesh, occ: &Args, label: &str, mess: &mut String) -> Result<Mesh> {
    let cells = cells_of(mesh, occ, label, "QUAD_LINE", mess)?;
    let conv = convert::quad_to_line(mesh, &cells);
    let _ = writeln!(
        mess,
        "CREA_MAILLAGE/QUAD_LINE on {label}: {}; {} nodes removed, {} left",
        conversions(&conv),
        conv.removed,
        conv.mesh.nnodes()
    );
    Ok(conv.mesh)
}

/// A new group of cells must not exist yet (MESH1_20), in the mesh or from an earlier occurrence.
fn new_group(mesh: &Mesh, taken: &mut HashSet<String>, occ: &Args, kw: &str, name: &str, label: &str) -> Result<()> {
    if mesh.cell_groups.contains_key(name) || !taken.insert(name.to_string()) {
        return Err(occ.err(kw, format!("group of cells '{name}' already exists in mesh {label}")));
    }
    Ok(())
}

/// Code_Aster 2025's names of a mesh that carries none: node k is `N`k and cell k is `M`k, so that a
/// file that read a mesh whose nodes had their own names designates the nodes of the new mesh by their
/// numbers (a name given in the input file no longer designates its node there).
fn number_names(out: &mut Mesh) {
    out.node_names = (1..=out.nnodes()).map(|k| format!("N{k}")).collect();
    out.cell_names = (1..=out.ncells()).map(|k| format!("M{k}")).collect();
    out.named_nodes = false;
}

/// CREA_MAILLE: copies of cells, one group (NOM) per occurrence.
fn crea_maille(mesh: &Mesh, occs: &[Args], label: &str, mess: &mut String) -> Result<Mesh> {
    let mut taken = HashSet::new();
    let mut copies = Vec::new();
    for occ in occs {
        occ.refuse(&["PREF_MAILLE", "PREF_NUME"])?;
        let name = occ.req_text("NOM")?.to_string();
        new_group(mesh, &mut taken, occ, "NOM", &name, label)?;
        copies.push((name, cells_or_all(mesh, occ, label)?));
    }
    let out = derive::copy_cells(mesh, &copies);
    let made: Vec<String> = copies.iter().map(|(g, c)| format!("{g} ({} cells)", c.len())).collect();
    let _ = writeln!(mess, "CREA_MAILLAGE/CREA_MAILLE on {label}: copies in {}", made.join(", "));
    Ok(out)
}

/// CREA_POI1: POI1 cells on the nodes of the occurrences.
fn crea_poi1(mesh: &Mesh, occs: &[Args], label: &str, mess: &mut String) -> Result<Mesh> {
    let mut taken = HashSet::new();
    let mut lists = Vec::new();
    for occ in occs {
        let nodes = select_nodes(mesh, occ, label)?;
        if nodes.is_empty() {
            let kw = ["GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE", "TOUT"].into_iter().find(|k| occ.has(k));
            return Err(occ.err(kw.unwrap_or("TOUT"), "the selection holds no node"));
        }
        let names = occ.texts("NOM_GROUP_MA");
        if names.len() > 1 {
            return Err(occ.err("NOM_GROUP_MA", "one group name per occurrence"));
        }
        let group = names.into_iter().next();
        if let Some(g) = &group {
            new_group(mesh, &mut taken, occ, "NOM_GROUP_MA", g, label)?;
        }
        lists.push((group, nodes));
    }
    let out = derive::point_cells(mesh, &lists);
    let _ = writeln!(mess, "CREA_MAILLAGE/CREA_POI1 on {label}: {} POI1 cells created", out.ncells() - mesh.ncells());
    Ok(out)
}

/// MODI_MAILLE: OPTION='QUAD8_9' adds a centre node to the QUAD8 cells of each occurrence.
fn modi_maille(mesh: &Mesh, occs: &[Args], label: &str, mess: &mut String) -> Result<Mesh> {
    let mut quad8 = Vec::new();
    for occ in occs {
        let option = occ.req_text("OPTION")?;
        match option {
            "QUAD8_9" => {}
            "TRIA6_7" | "SEG3_4" => {
                return Err(
                    occ.err("OPTION", format!("OPTION='{option}' is not supported yet (no TRIA7 or SEG4 cells)"))
                )
            }
            _ => return Err(occ.err("OPTION", format!("OPTION='{option}' is not supported yet"))),
        }
        occ.refuse(&["PREF_NOEUD", "PREF_NUME"])?;
        let cells = select_cells(mesh, occ, label)?;
        if cells.is_empty() {
            return Err(occ.err("GROUP_MA", "the selection holds no cell"));
        }
        let mine: Vec<usize> = cells.into_iter().filter(|&c| mesh.cell_types[c] == CellType::Quad8).collect();
        if mine.is_empty() {
            let _ =
                writeln!(mess, " <A> CREA_MAILLAGE: MODI_MAILLE OPTION='{option}': no QUAD8 cell among those given");
        }
        quad8.extend(mine);
    }
    if quad8.is_empty() {
        let _ = writeln!(mess, " <A> CREA_MAILLAGE: MODI_MAILLE: no cell modified");
    }
    let out = derive::centre_nodes(mesh, &quad8);
    let _ = writeln!(mess, "CREA_MAILLAGE/MODI_MAILLE on {label}: {} QUAD8 -> QUAD9", quad8.len());
    Ok(out)
}

/// RESTREINT: the mesh of some cells (and nodes), as `rdtmai` builds it.
fn restreint(mesh: &Mesh, occ: &Args, label: &str, mess: &mut String) -> Result<Mesh> {
    let cells = select_cells(mesh, occ, label)?;
    if cells.is_empty() {
        return Err(occ.err("GROUP_MA", "the selection holds no cell"));
    }
    // The nodes of GROUP_NO come after those of the cells (the selection holds both; the cells'
    // nodes are already numbered by then).
    let extra = if occ.has("GROUP_NO") { select_nodes(mesh, occ, label)? } else { Vec::new() };
    let cell_groups =
        if occ.text("TOUT_GROUP_MA") == Some("OUI") { Groups::All } else { Groups::These(occ.texts("GROUP_MA")) };
    let node_groups =
        if occ.text("TOUT_GROUP_NO") == Some("OUI") { Groups::All } else { Groups::These(occ.texts("GROUP_NO")) };
    let out = derive::restrict(mesh, &cells, &extra, &cell_groups, &node_groups);
    let _ = writeln!(
        mess,
        "CREA_MAILLAGE/RESTREINT on {label}: {} cells and {} nodes kept of {} and {}",
        out.ncells(),
        out.nnodes(),
        mesh.ncells(),
        mesh.nnodes()
    );
    Ok(out)
}
