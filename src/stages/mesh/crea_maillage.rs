//! CREA_MAILLAGE: a new mesh made from MAILLAGE.
//!
//! LINE_QUAD and QUAD_LINE change the degree of cells with Code_Aster 2025's numbering
//! ([`crate::mesh::convert`]): new nodes are `N` + number, as Code_Aster 2025 shows nodes of meshes
//! without names. A LINE_QUAD occurrence that gives PREF_NOEUD or PREF_NUME (keywords of the 2020
//! syntax, gone in 2025) gets the 2020 operator instead: its numbering and the names PREF_NOEUD +
//! (PREF_NUME − 1 + k). The other operations stop by name until they are implemented.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::convert::{self, Converted};
use crate::mesh::Mesh;
use crate::stages::select::select_cells;
use crate::stages::Ctx;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::rc::Rc;

/// Operations and keywords of CREA_MAILLAGE not implemented yet.
const NOT_YET: &[&str] = &[
    "CREA_POI1",
    "CREA_MAILLE",
    "RESTREINT",
    "MODI_MAILLE",
    "HEXA20_27",
    "COQU_VOLU",
    "CREA_FISS",
    "PENTA15_18",
    "MODI_HHO",
    "COQUE_SOLIDE",
    "REPERE",
    "DECOUPE_LAC",
    "ECLA_PG",
    "TITRE",
];

pub fn crea_maillage(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(NOT_YET)?;
    let c = a.concept("MAILLAGE").ok_or_else(|| a.err("MAILLAGE", "MAILLAGE is required here"))?;
    let mesh = c.mesh().map_err(|e| a.locate(e, "MAILLAGE"))?;
    let label = c.label();
    let mut mess = String::new();
    let out = if let Some(occ) = a.fact("LINE_QUAD") {
        line_quad(&mesh, occ, &label, &mut mess)?
    } else if let Some(occ) = a.fact("QUAD_LINE") {
        quad_line(&mesh, occ, &label, &mut mess)?
    } else {
        // The catalogue asks for exactly one operation and the others are refused above.
        return Err(a.err("MAILLAGE", "no operation given"));
    };
    if a.int("INFO") == Some(2) {
        mess.push_str(&out.describe("(CREA_MAILLAGE)"));
    }
    ctx.io.mess(&mess);
    Ok(Some(ConceptData::Mesh(Rc::new(out))))
}

/// The cells of a TOUT / GROUP_MA / MAILLE occurrence (none is an error, as in `getelem`), with
/// Code_Aster's alarm when they are not all the cells of the mesh.
fn cells_of(mesh: &Mesh, occ: &Args, label: &str, what: &str, mess: &mut String) -> Result<Vec<usize>> {
    let cells = select_cells(mesh, occ, label)?;
    if cells.is_empty() {
        let kw = ["GROUP_MA", "MAILLE", "TOUT"].into_iter().find(|k| occ.has_if_declared(k)).unwrap_or("TOUT");
        return Err(occ.err(kw, "the selection holds no cell"));
    }
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
    // A new name must not be the name of a node of the input (meshes that carried their own names).
    let old: HashSet<&str> = mesh.node_names.iter().map(String::as_str).collect();
    if let Some(n) = out.node_names[conv.first_new..].iter().find(|n| old.contains(n.as_str())) {
        let kw = if syntax_2020 { "PREF_NOEUD" } else { "TOUT" };
        return Err(occ.err(kw, format!("new node {n}: a node of mesh {label} already has this name")));
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
