//! Selections shared by the stages: mesh entities of an occurrence (TOUT, GROUP_MA, MAILLE, GROUP_NO,
//! NOEUD and their SANS_ forms) and the steps of a result an occurrence selects. A MAILLE or NOEUD name no entity bears is read as Code_Aster 2025 numbers
//! its entities (`M<k>`, `N<k>`: `mesh::numbered`).

use crate::catalog::args::Args;
use crate::concepts::result::{ResultData, Step};
use crate::concepts::table::{Cell, Table};
use crate::diag::Result;
use crate::mesh::Mesh;
use std::collections::HashMap;

pub fn select_cells(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    let mut cells: Vec<usize> = Vec::new();
    if occ.text_if_declared("TOUT") == Some("OUI") {
        cells.extend(0..mesh.cells.len());
    }
    for g in occ.texts_if_declared("GROUP_MA") {
        let members = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err("GROUP_MA", format!("group of cells '{g}' is not in mesh {mesh_name}")))?;
        cells.extend(members.iter().copied());
    }
    let names = occ.texts_if_declared("MAILLE");
    if !names.is_empty() {
        let index: HashMap<&str, usize> = mesh.cell_names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        for n in names {
            let c = index.get(n.as_str()).copied().or_else(|| crate::mesh::numbered(&n, 'M', mesh.cells.len()));
            cells.push(c.ok_or_else(|| occ.err("MAILLE", format!("cell '{n}' is not in mesh {mesh_name}")))?);
        }
    }
    for g in occ.texts_if_declared("SANS_GROUP_MA") {
        let members = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err("SANS_GROUP_MA", format!("group of cells '{g}' is not in mesh {mesh_name}")))?;
        cells.retain(|c| !members.contains(c));
    }
    cells.sort_unstable();
    cells.dedup();
    Ok(cells)
}

/// Nodes selected by TOUT / GROUP_MA / MAILLE / GROUP_NO / NOEUD (and SANS_GROUP_NO).
pub fn select_nodes(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    let mut nodes: Vec<usize> = Vec::new();
    if occ.has_if_declared("TOUT") || occ.has_if_declared("GROUP_MA") || occ.has_if_declared("MAILLE") {
        for c in select_cells(mesh, occ, mesh_name)? {
            nodes.extend(mesh.cells[c].iter().copied());
        }
    }
    nodes.extend(group_no_nodes(mesh, occ, mesh_name)?);
    nodes.extend(noeud_nodes(mesh, occ, mesh_name)?);
    for g in occ.texts_if_declared("SANS_GROUP_NO") {
        let members = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err("SANS_GROUP_NO", format!("group of nodes '{g}' is not in mesh {mesh_name}")))?;
        nodes.retain(|n| !members.contains(n));
    }
    nodes.sort_unstable();
    nodes.dedup();
    Ok(nodes)
}

/// The nodes of NOEUD then of the groups of GROUP_NO, in the order given, each once (less SANS_GROUP_NO):
/// the list of nodes POST_RELEVE_T follows (`rvgnoe`), whose order makes its curvilinear abscissa.
pub fn nodes_in_order(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    let mut listed = noeud_nodes(mesh, occ, mesh_name)?;
    listed.extend(group_no_nodes(mesh, occ, mesh_name)?);
    let kept = select_nodes(mesh, occ, mesh_name)?;
    let mut seen = std::collections::HashSet::new();
    Ok(listed.into_iter().filter(|n| kept.binary_search(n).is_ok() && seen.insert(*n)).collect())
}

/// The nodes of the groups of GROUP_NO, in the order given.
fn group_no_nodes(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    let mut nodes = Vec::new();
    for g in occ.texts_if_declared("GROUP_NO") {
        let members = mesh
            .node_groups
            .get(&g)
            .ok_or_else(|| occ.err("GROUP_NO", format!("group of nodes '{g}' is not in mesh {mesh_name}")))?;
        nodes.extend(members.iter().copied());
    }
    Ok(nodes)
}

/// The nodes NOEUD names, in the order given.
fn noeud_nodes(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Vec<usize>> {
    let names = occ.texts_if_declared("NOEUD");
    if names.is_empty() {
        return Ok(Vec::new());
    }
    let index: HashMap<&str, usize> = mesh.node_names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
    names
        .iter()
        .map(|n| {
            let k = index.get(n.as_str()).copied().or_else(|| crate::mesh::numbered(n, 'N', mesh.coords.len()));
            k.ok_or_else(|| occ.err("NOEUD", format!("node '{n}' is not in mesh {mesh_name}")))
        })
        .collect()
}

// ------------------------------------------------------------------ table rows (FILTRE)

fn matches_eq(cell: &Cell, occ: &Args) -> Result<bool> {
    let crit = occ.text("CRITERE").unwrap_or("RELATIF");
    let prec = occ.real("PRECISION").unwrap_or(1e-3);
    if occ.has("VALE_K") {
        let Cell::Text(t) = cell else { return Ok(false) };
        return Ok(occ.texts("VALE_K").iter().any(|k| k.trim_end() == t.trim_end()));
    }
    if occ.has("VALE_I") {
        return Ok(match cell {
            Cell::Int(i) => occ.ints("VALE_I").contains(i),
            Cell::Real(r) => occ.ints("VALE_I").iter().any(|i| *i as f64 == *r),
            _ => false,
        });
    }
    if occ.has("VALE") {
        let Some(x) = cell.as_f64() else { return Ok(false) };
        return Ok(occ.reals("VALE").iter().any(|&v| {
            if crit == "ABSOLU" {
                (x - v).abs() <= prec
            } else {
                let (a, b) = (v * (1.0 - prec), v * (1.0 + prec));
                a.min(b) <= x && x <= a.max(b)
            }
        }));
    }
    if occ.has("VALE_C") {
        return Err(occ.err("VALE_C", "filters on complex values are not supported yet"));
    }
    Err(occ.err("CRIT_COMP", "this comparison needs VALE, VALE_I or VALE_K"))
}

fn ordering(cell: &Cell, occ: &Args) -> Result<Option<std::cmp::Ordering>> {
    let refv = if let Some(v) = occ.real("VALE") {
        Cell::Real(v)
    } else if let Some(i) = occ.ints("VALE_I").first() {
        Cell::Int(*i)
    } else if let Some(k) = occ.text("VALE_K") {
        Cell::Text(k.to_string())
    } else {
        return Err(occ.err("CRIT_COMP", "this comparison needs VALE, VALE_I or VALE_K"));
    };
    Ok(match (cell, &refv) {
        (Cell::Text(a), Cell::Text(b)) => Some(a.as_str().cmp(b.as_str())),
        (a, b) => match (a.as_f64(), b.as_f64()) {
            (Some(x), Some(y)) => x.partial_cmp(&y),
            _ => None,
        },
    })
}

/// The rows of `t` kept by one filter occurrence (NOM_PARA, CRIT_COMP, VALE*).
pub fn filter_rows(t: &Table, rows: &[usize], occ: &Args, table: &str) -> Result<Vec<usize>> {
    let para = occ.req_text("NOM_PARA")?;
    let col = t.column(para).ok_or_else(|| {
        let names: Vec<&str> = t.columns.iter().map(|c| c.name.as_str()).collect();
        occ.err("NOM_PARA", format!("table {table} has no parameter '{para}' (parameters: {})", names.join(", ")))
    })?;
    let cells = &t.columns[col].cells;
    let crit = occ.text("CRIT_COMP").unwrap_or("EQ");
    use std::cmp::Ordering::*;
    let mut out = Vec::new();
    match crit {
        "MAXI" | "MINI" | "MAXI_ABS" | "MINI_ABS" => {
            let key = |r: usize| cells[r].as_f64().map(|x| if crit.ends_with("_ABS") { x.abs() } else { x });
            let best = rows.iter().filter_map(|&r| key(r)).fold(None, |acc: Option<f64>, x| {
                Some(match acc {
                    None => x,
                    Some(a) if crit.starts_with("MAXI") => a.max(x),
                    Some(a) => a.min(x),
                })
            });
            if let Some(b) = best {
                out.extend(rows.iter().copied().filter(|&r| key(r) == Some(b)));
            }
        }
        "REGEXP" => {
            let pat = occ.text("VALE_K").ok_or_else(|| occ.err("CRIT_COMP", "REGEXP needs VALE_K"))?;
            let re =
                regex::Regex::new(pat).map_err(|e| occ.err("VALE_K", format!("invalid regular expression: {e}")))?;
            out.extend(rows.iter().copied().filter(|&r| matches!(&cells[r], Cell::Text(t) if re.is_match(t))));
        }
        _ => {
            for &r in rows {
                let c = &cells[r];
                let keep = match crit {
                    "VIDE" => c.is_empty(),
                    "NON_VIDE" => !c.is_empty(),
                    _ if c.is_empty() => false,
                    "EQ" => matches_eq(c, occ)?,
                    "NE" => !matches_eq(c, occ)?,
                    "GT" => ordering(c, occ)? == Some(Greater),
                    "LT" => ordering(c, occ)? == Some(Less),
                    "GE" => matches!(ordering(c, occ)?, Some(Greater | Equal)),
                    "LE" => matches!(ordering(c, occ)?, Some(Less | Equal)),
                    other => return Err(occ.err("CRIT_COMP", format!("'{other}' is not supported"))),
                };
                if keep {
                    out.push(r);
                }
            }
        }
    }
    Ok(out)
}

/// Apply all occurrences of FILTRE in turn.
pub fn filtered(t: &Table, filters: &[Args], table: &str) -> Result<Vec<usize>> {
    let mut rows: Vec<usize> = (0..t.nrows()).collect();
    for f in filters {
        rows = filter_rows(t, &rows, f, table)?;
    }
    Ok(rows)
}

/// The values of a LIST_ORDRE / LIST_INST concept.
pub fn list_of(occ: &Args, kw: &str) -> Result<Option<Vec<f64>>> {
    occ.concept(kw).map(|c| c.reals().map_err(|e| occ.err(kw, e.msg))).transpose()
}

/// The steps an occurrence selects (TOUT_ORDRE, NUME_ORDRE, LIST_ORDRE,
/// INST, LIST_INST; all steps by default), in the result's order.
pub fn selected_steps<'r>(r: &'r ResultData, occ: &Args, name: &str) -> Result<Vec<&'r Step>> {
    for kw in ["NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE", "FREQ", "LIST_FREQ"] {
        if occ.has_if_declared(kw) {
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
