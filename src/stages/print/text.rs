//! IMPR_RESU FORMAT='RESULTAT': fields of results printed as text tables to a
//! unit (the .resu file by default), one block per field and order number.

use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::select::{select_cells, select_nodes};
use crate::stages::Ctx;
use std::fmt::Write as _;

fn num(v: f64) -> String {
    if v.is_nan() {
        format!("{:>13}", "-")
    } else {
        format!("{:>13}", crate::text::sci(v, 5, true))
    }
}

/// Print the result fields of one RESU occurrence.
fn print_occurrence(occ: &Args, out: &mut String) -> Result<()> {
    if let (Some(mc), false) = (occ.concept("MAILLAGE"), occ.has("RESULTAT")) {
        let mesh = mc.mesh()?;
        print_mesh(&mesh, &mc.label(), out);
        return Ok(());
    }
    occ.refuse(&[
        "CHAM_GD",
        "MAILLAGE",
        "SOUS_TITRE",
        "VALE_MAX",
        "VALE_MIN",
        "BORNE_SUP",
        "BORNE_INF",
        "LIST_ORDRE",
        "LIST_INST",
        "FREQ",
        "NUME_MODE",
        "NOM_CAS",
        "NOEUD_CMP",
        "ANGLE",
        "FORMAT_R",
        "NOM_PARA",
        "TOUT_PARA",
    ])?;
    if occ.text("TOUT_CHAM") == Some("NON") {
        return Err(occ.err("TOUT_CHAM", "TOUT_CHAM='NON' is not supported yet"));
    }
    let rc = occ.req_concept("RESULTAT")?;
    let name = rc.label();
    let r = rc.result()?;
    let model = r.model.model()?;
    let mesh = model.current_mesh();
    let mesh_name = model.mesh_concept.label();
    let restrict_nodes = if occ.has_if_declared("GROUP_NO") || occ.has_if_declared("NOEUD") {
        Some(select_nodes(&mesh, occ, &mesh_name)?)
    } else {
        None
    };
    let restrict_cells = if occ.has_if_declared("GROUP_MA") || occ.has_if_declared("MAILLE") {
        Some(select_cells(&mesh, occ, &mesh_name)?)
    } else {
        None
    };
    let orders = occ.ints("NUME_ORDRE");
    let insts = occ.reals("INST");
    let cmps = occ.texts("NOM_CMP");
    for step in &r.steps {
        if !orders.is_empty() && !orders.contains(&step.nume_ordre) {
            continue;
        }
        if !insts.is_empty() && !insts.iter().any(|t| (t - step.inst).abs() <= 1e-6 * t.abs().max(1e-300)) {
            continue;
        }
        let names: Vec<String> = match occ.texts("NOM_CHAM") {
            v if v.is_empty() => step.fields.keys().cloned().collect(),
            v => v,
        };
        for cham in names {
            let field = step.fields.get(&cham).ok_or_else(|| {
                occ.err("NOM_CHAM", format!("result {name} has no field {cham} at order {}", step.nume_ordre))
            })?;
            let all = field.components();
            let ks: Vec<usize> = if cmps.is_empty() {
                (0..all.len()).collect()
            } else {
                cmps.iter()
                    .map(|c| {
                        field
                            .component(c)
                            .ok_or_else(|| occ.err("NOM_CMP", format!("field {cham} has no component {c}")))
                    })
                    .collect::<Result<_>>()?
            };
            let n = all.len();
            let _ = writeln!(
                out,
                "\n FIELD {cham} OF RESULT {name}  NUME_ORDRE {}  INST {}",
                step.nume_ordre,
                num(step.inst).trim()
            );
            let header: String = ks.iter().map(|&k| format!(" {:>13}", all[k])).collect();
            match field {
                Field::Node { values, .. } => {
                    // IMPR_COOR='OUI': the node coordinates before the values.
                    let coor = occ.text("IMPR_COOR") == Some("OUI");
                    let axes = &["COOR_X", "COOR_Y", "COOR_Z"][..mesh.dim.clamp(1, 3)];
                    let coor_head: String =
                        if coor { axes.iter().map(|a| format!(" {a:>13}")).collect() } else { String::new() };
                    let _ = writeln!(out, " {:<10}{coor_head}{header}", "NOEUD");
                    for node in 0..mesh.coords.len() {
                        if restrict_nodes.as_ref().is_some_and(|r| !r.contains(&node)) {
                            continue;
                        }
                        if ks.iter().all(|&k| values[node * n + k].is_nan()) {
                            continue;
                        }
                        let row: String = ks.iter().map(|&k| format!(" {}", num(values[node * n + k]))).collect();
                        let xyz: String = if coor {
                            (0..axes.len()).map(|d| format!(" {}", num(mesh.coords[node][d]))).collect()
                        } else {
                            String::new()
                        };
                        let _ = writeln!(out, " {:<10}{xyz}{row}", mesh.node_names[node]);
                    }
                }
                Field::Elno { cells, .. } | Field::Elga { cells, .. } | Field::Elem { cells, .. } => {
                    let per_node = matches!(field, Field::Elno { .. });
                    let label = match field {
                        Field::Elno { .. } => "NOEUD",
                        Field::Elga { .. } => "POINT",
                        _ => "",
                    };
                    let _ = writeln!(out, " {:<10} {label:<10}{header}", "MAILLE");
                    for (c, v) in cells.iter().enumerate() {
                        let Some(v) = v else { continue };
                        if restrict_cells.as_ref().is_some_and(|r| !r.contains(&c)) {
                            continue;
                        }
                        for (i, chunk) in v.chunks(n).enumerate() {
                            let at =
                                if per_node { mesh.node_names[mesh.cells[c][i]].clone() } else { format!("{}", i + 1) };
                            if per_node && restrict_nodes.as_ref().is_some_and(|r| !r.contains(&mesh.cells[c][i])) {
                                continue;
                            }
                            let row: String = ks.iter().map(|&k| format!(" {}", num(chunk[k]))).collect();
                            let _ = writeln!(out, " {:<10} {at:<10}{row}", mesh.cell_names[c]);
                        }
                    }
                }
            }
        }
    }
    Ok(())
}

/// A mesh in Code_Aster's text (ASTER) mesh format: coordinates, cells per
/// type, groups of nodes and cells, each block closed by FINSF.
fn print_mesh(mesh: &crate::mesh::Mesh, name: &str, out: &mut String) {
    let _ = writeln!(out, "TITRE\n MAILLAGE {name}\nFINSF\n%");
    let _ = writeln!(out, "COOR_{}D", mesh.dim);
    for (n, x) in mesh.coords.iter().enumerate() {
        let _ = write!(out, " {:<8}", mesh.node_names[n]);
        for v in &x[..mesh.dim] {
            let _ = write!(out, " {}", num(*v));
        }
        out.push('\n');
    }
    out.push_str("FINSF\n%\n");
    for t in crate::mesh::CellType::ALL {
        let cells: Vec<usize> = (0..mesh.ncells()).filter(|&c| mesh.cell_types[c] == t).collect();
        if cells.is_empty() {
            continue;
        }
        let _ = writeln!(out, "{}", t.name());
        for c in cells {
            let _ = write!(out, " {:<8}", mesh.cell_names[c]);
            for &n in &mesh.cells[c] {
                let _ = write!(out, " {}", mesh.node_names[n]);
            }
            out.push('\n');
        }
        out.push_str("FINSF\n%\n");
    }
    for (g, nodes) in &mesh.node_groups {
        let _ = writeln!(out, "GROUP_NO\n {g}");
        for &n in nodes {
            let _ = writeln!(out, " {}", mesh.node_names[n]);
        }
        out.push_str("FINSF\n%\n");
    }
    for (g, cells) in &mesh.cell_groups {
        let _ = writeln!(out, "GROUP_MA\n {g}");
        for &c in cells {
            let _ = writeln!(out, " {}", mesh.cell_names[c]);
        }
        out.push_str("FINSF\n%\n");
    }
    out.push_str("FIN\n");
}

/// IMPR_RESU with FORMAT='RESULTAT'.
pub fn impr_resu_text(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mut out = String::new();
    for occ in a.facts("RESU") {
        print_occurrence(occ, &mut out)?;
    }
    // The text result file by default (UNITE's catalogue default is MED's).
    let unit = if a.given("UNITE") { a.int("UNITE").unwrap_or(8) } else { 8 };
    ctx.io.write_unit(unit, &out).map_err(|e| e.at(a.span_of("UNITE")))?;
    Ok(None)
}
