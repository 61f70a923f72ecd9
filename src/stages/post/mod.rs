//! POST_RELEVE_T (EXTRACTION): values of results (RESULTAT) and of nodal fields (CHAM_GD) as a table, or
//! their normal trace on the line of the nodes (TRAC_NOR, 2D); POST_ERREUR (`erreur`): error
//! norms of a field against reference formulas; MACR_LIGN_COUPE (`lign_coupe`): values along lines.

mod elem;
mod erreur;
pub use elem::post_elem;
mod lign_coupe;
pub use erreur::post_erreur;
pub use lign_coupe::macr_lign_coupe;

use crate::catalog::args::Args;
use crate::concepts::result::{Field, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::Ctx;

use crate::concepts::table::{Cell, ColType, Table};
// ------------------------------------------------------------------ POST_RELEVE_T

/// The node label and coordinates columns of a row (Code_Aster shows node numbers for meshes whose
/// file gave no node names), with the curvilinear abscissa of the node along the list of nodes when it
/// is known.
fn node_columns(mesh: &crate::mesh::Mesh, node: usize, absc: Option<f64>) -> Vec<(String, Cell)> {
    let label = if mesh.named_nodes { mesh.node_names[node].clone() } else { (node + 1).to_string() };
    let mut row = vec![("NOEUD".to_string(), Cell::Text(label))];
    if let Some(s) = absc {
        row.push(("ABSC_CURV".to_string(), Cell::Real(s)));
    }
    for (d, name) in ["COOR_X", "COOR_Y", "COOR_Z"].iter().enumerate().take(mesh.dim.max(2)) {
        row.push((name.to_string(), Cell::Real(mesh.coords[node][d])));
    }
    row
}

/// The curvilinear abscissa of each node along the nodes in their order (`rvabsc`; a node met twice keeps
/// its first).
fn abscissas(mesh: &crate::mesh::Mesh, nodes: &[usize]) -> std::collections::HashMap<usize, f64> {
    let mut absc = std::collections::HashMap::new();
    let mut s_acc = 0.0;
    for (j, &node) in nodes.iter().enumerate() {
        if j > 0 {
            let (a, b) = (mesh.coords[nodes[j - 1]], mesh.coords[node]);
            s_acc += ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
        }
        absc.entry(node).or_insert(s_acc);
    }
    absc
}

/// The nodes of an occurrence: named alone (NOEUD, GROUP_NO) in the order given; with cells, the mesh's.
fn occurrence_nodes(mesh: &crate::mesh::Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    if occ.has("GROUP_MA") || occ.has("MAILLE") || occ.has("TOUT") {
        crate::stages::select::select_nodes(mesh, occ, mesh_name)
    } else {
        crate::stages::select::nodes_in_order(mesh, occ, mesh_name)
    }
}

/// EXTRACTION from a nodal field given by CHAM_GD (CREA_CHAMP's fields): one row per selected node,
/// with the columns INTITULE, CHAM_GD, NOEUD, its coordinates and the components asked for.
fn field_rows(occ: &Args, intitule: &str, fc: &crate::concepts::ConceptRef) -> Result<Vec<Vec<(String, Cell)>>> {
    let data = fc.field()?;
    let Field::Node { values, components } = &data.field else {
        return Err(occ.err("CHAM_GD", format!("{} is not a field at nodes: not supported yet", fc.label())));
    };
    if data.functions.is_some() {
        return Err(occ.err("CHAM_GD", format!("{} is a field of functions: not supported yet", fc.label())));
    }
    let mesh = data.mesh_concept.mesh()?;
    let nodes = occurrence_nodes(&mesh, occ, &data.mesh_concept.label())?;
    let absc = abscissas(&mesh, &nodes);
    let cells_given = occ.has("GROUP_MA") || occ.has("MAILLE") || occ.has("TOUT");
    let comps: Vec<String> =
        if occ.text("TOUT_CMP") == Some("OUI") { components.clone() } else { occ.texts("NOM_CMP") };
    let ks: Vec<usize> = comps
        .iter()
        .map(|c| {
            components
                .iter()
                .position(|x| x == c)
                .ok_or_else(|| occ.err("NOM_CMP", format!("field {} has no component {c}", fc.label())))
        })
        .collect::<Result<_>>()?;
    let n = components.len();
    let mut rows = Vec::new();
    for node in nodes {
        let mut row = vec![
            ("INTITULE".to_string(), Cell::Text(intitule.to_string())),
            ("CHAM_GD".to_string(), Cell::Text(fc.label())),
        ];
        row.extend(node_columns(&mesh, node, absc.get(&node).copied().filter(|_| !cells_given)));
        for (c, &k) in comps.iter().zip(&ks) {
            let v = values[node * n + k];
            row.push((c.clone(), if v.is_nan() { Cell::Empty } else { Cell::Real(v) }));
        }
        rows.push(row);
    }
    Ok(rows)
}

pub fn post_releve_t(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mut t = Table::default();
    let mut rows: Vec<Vec<(String, Cell)>> = Vec::new();
    for occ in a.facts("ACTION") {
        let ops = occ.texts("OPERATION");
        if ops.iter().any(|o| o != "EXTRACTION") {
            return Err(occ.err("OPERATION", format!("OPERATION='{}' is not supported yet", ops.join("', '"))));
        }
        occ.refuse(&[
            "INVARIANT",
            "ELEM_PRINCIPAUX",
            "RESULTANTE",
            "MOMENT",
            "POINT",
            "REPERE",
            "LIST_ORDRE",
            "LIST_INST",
            "FREQ",
            "NUME_MODE",
            "LIST_FREQ",
            "LIST_MODE",
            "NOEUD_CMP",
            "NOM_CAS",
            "TRAC_DIR",
            "DIRECTION",
        ])?;
        let intitule = occ.req_text("INTITULE")?.to_string();
        if let Some(fc) = occ.concept("CHAM_GD") {
            occ.refuse(&["TRAC_NOR"])?;
            rows.extend(field_rows(occ, &intitule, &fc)?);
            continue;
        }
        if occ.text("CRITERE") == Some("ABSOLU") {
            return Err(occ.err("CRITERE", "CRITERE='ABSOLU' for the time search is not supported yet"));
        }
        let rc = occ.req_concept("RESULTAT")?;
        let name = rc.label();
        let r = rc.result()?;
        let mesh = r.model.model()?.current_mesh();
        let mesh_name = r.model.model()?.mesh_concept.label();
        let cham = occ.req_text("NOM_CHAM")?.to_string();
        let steps: Vec<&Step> = if occ.has("NUME_ORDRE") {
            occ.ints("NUME_ORDRE")
                .iter()
                .map(|n| {
                    r.by_order(*n)
                        .ok_or_else(|| occ.err("NUME_ORDRE", format!("result {name} has no order number {n}")))
                })
                .collect::<Result<_>>()?
        } else if occ.has("INST") {
            let prec = occ.real("PRECISION").unwrap_or(1e-6);
            occ.reals("INST")
                .iter()
                .map(|t| {
                    r.by_inst(*t, prec).ok_or_else(|| occ.err("INST", format!("result {name} has no step at time {t}")))
                })
                .collect::<Result<_>>()?
        } else {
            r.steps.iter().collect()
        };
        let nodes = occurrence_nodes(&mesh, occ, &mesh_name)?;
        // TRAC_NOR (2D): the normal trace on the line the nodes form, in their order (`rvrlln`).
        let normals = if occ.text("TRAC_NOR") == Some("OUI") {
            if mesh.dim != 2 {
                return Err(occ.err("TRAC_NOR", "TRAC_NOR on nodes of a 3D mesh is not supported yet"));
            }
            let pts: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            Some(lign_coupe::line_normals(&pts))
        } else {
            None
        };
        let absc = abscissas(&mesh, &nodes);
        let cells_sel = if occ.has("GROUP_MA") || occ.has("MAILLE") || occ.has("TOUT") {
            Some(crate::stages::select::select_cells(&mesh, occ, &mesh_name)?)
        } else {
            None
        };
        for step in steps {
            let field = step.fields.get(&cham).ok_or_else(|| {
                occ.err("NOM_CHAM", format!("result {name} has no field {cham} at order {}", step.nume_ordre))
            })?;
            let comps: Vec<String> =
                if occ.text("TOUT_CMP") == Some("OUI") { field.components().to_vec() } else { occ.texts("NOM_CMP") };
            let ks: Vec<usize> = comps
                .iter()
                .map(|c| {
                    field.component(c).ok_or_else(|| occ.err("NOM_CMP", format!("field {cham} has no component {c}")))
                })
                .collect::<Result<_>>()?;
            let n = field.components().len();
            let head = |node: usize, cell: Option<usize>| {
                let mut row = vec![
                    ("INTITULE".to_string(), Cell::Text(intitule.clone())),
                    ("RESU".to_string(), Cell::Text(name.clone())),
                    ("NOM_CHAM".to_string(), Cell::Text(cham.clone())),
                    ("NUME_ORDRE".to_string(), Cell::Int(step.nume_ordre)),
                    ("INST".to_string(), Cell::Real(step.inst)),
                ];
                if let Some(c) = cell {
                    row.push(("MAILLE".to_string(), Cell::Text(mesh.cell_names[c].clone())));
                }
                row.extend(node_columns(&mesh, node, absc.get(&node).copied().filter(|_| cell.is_none())));
                row
            };
            match field {
                Field::Node { values, .. } => {
                    for (j, &node) in nodes.iter().enumerate() {
                        let mut row = head(node, None);
                        if let Some(normals) = &normals {
                            let v = &values[node * n..(node + 1) * n];
                            row.extend(lign_coupe::normal_trace(&cham, field.components(), Some(v), &ks, normals[j]));
                        } else {
                            for (c, &k) in comps.iter().zip(&ks) {
                                let v = values[node * n + k];
                                row.push((c.clone(), if v.is_nan() { Cell::Empty } else { Cell::Real(v) }));
                            }
                        }
                        rows.push(row);
                    }
                }
                Field::Elno { cells, .. } => {
                    let cell_list: Vec<usize> = match &cells_sel {
                        Some(c) => c.clone(),
                        None => {
                            (0..mesh.cells.len()).filter(|&c| mesh.cells[c].iter().any(|x| nodes.contains(x))).collect()
                        }
                    };
                    // (node, cell, values at the node) over the cells of the selection.
                    let mut at_nodes: Vec<(usize, usize, &[f64])> = Vec::new();
                    for c in cell_list {
                        let Some(vals) = &cells[c] else { continue };
                        for (i, &node) in mesh.cells[c].iter().enumerate() {
                            if nodes.contains(&node) {
                                at_nodes.push((node, c, &vals[i * n..(i + 1) * n]));
                            }
                        }
                    }
                    if occ.text("MOYE_NOEUD") == Some("NON") {
                        if normals.is_some() {
                            return Err(occ.err("TRAC_NOR", "TRAC_NOR with MOYE_NOEUD='NON' is not supported yet"));
                        }
                        // One row per cell and node.
                        for (node, c, v) in at_nodes {
                            let mut row = head(node, Some(c));
                            for (cn, &k) in comps.iter().zip(&ks) {
                                row.push((cn.clone(), Cell::Real(v[k])));
                            }
                            rows.push(row);
                        }
                    } else {
                        // MOYE_NOEUD='OUI' (the default): the values of the cells around a node averaged,
                        // one row per node, in the order of the node selection.
                        for (j, &node) in nodes.iter().enumerate() {
                            let around: Vec<&[f64]> =
                                at_nodes.iter().filter(|(m, _, _)| *m == node).map(|(_, _, v)| *v).collect();
                            if around.is_empty() {
                                continue;
                            }
                            let mut row = head(node, None);
                            let mean: Vec<f64> = (0..n)
                                .map(|k| around.iter().map(|v| v[k]).sum::<f64>() / around.len() as f64)
                                .collect();
                            if let Some(normals) = &normals {
                                row.extend(lign_coupe::normal_trace(
                                    &cham,
                                    field.components(),
                                    Some(&mean),
                                    &ks,
                                    normals[j],
                                ));
                            } else {
                                for (cn, &k) in comps.iter().zip(&ks) {
                                    row.push((cn.clone(), Cell::Real(mean[k])));
                                }
                            }
                            rows.push(row);
                        }
                    }
                }
                _ => {
                    return Err(occ.err(
                        "NOM_CHAM",
                        format!("extraction of {cham} (a field at Gauss points or per cell) is not supported yet"),
                    ))
                }
            }
        }
    }
    // Columns in order of first appearance.
    let mut names: Vec<String> = Vec::new();
    for r in &rows {
        for (n, _) in r {
            if !names.contains(n) {
                names.push(n.clone());
            }
        }
    }
    for n in &names {
        let cells: Vec<Cell> = rows
            .iter()
            .map(|r| r.iter().find(|(k, _)| k == n).map(|(_, c)| c.clone()).unwrap_or(Cell::Empty))
            .collect();
        let ty = match cells.iter().find(|c| !c.is_empty()) {
            Some(Cell::Int(_)) => ColType::I,
            Some(Cell::Text(_)) => ColType::K(16),
            _ => ColType::R,
        };
        t.add_column(n, ty, cells)?;
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    Ok(Some(ConceptData::Table(t)))
}
