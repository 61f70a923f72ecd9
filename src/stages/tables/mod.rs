//! CREA_TABLE, LIRE_TABLE, CALC_TABLE, IMPR_TABLE, and the row filters they
//! share with TEST_TABLE.

pub mod io;

use crate::catalog::args::{Args, Val};
use crate::concepts::table::{Cell, ColType, Column, Table};
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::stages::select::{filter_rows, filtered};
use crate::stages::Ctx;
use crate::text::fortran::RealFormat;
use io as table_io;

fn cell_of(v: &Val) -> Cell {
    match v {
        Val::I(i) => Cell::Int(*i),
        Val::R(r) => Cell::Real(*r),
        Val::T(t) => Cell::Text(t.clone()),
        Val::Concept(c) => Cell::Text(c.label()),
        _ => Cell::Empty,
    }
}

fn type_of(c: &Cell) -> ColType {
    match c {
        Cell::Int(_) => ColType::I,
        Cell::Real(_) | Cell::Empty => ColType::R,
        Cell::Text(t) => ColType::text_for(t.chars().count()),
    }
}

// ------------------------------------------------------------------ CREA_TABLE

pub fn crea_table(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    // TYPE_TABLE decides the concept type (the catalogue's); a container holds its rows as any table.
    if let Some(t) = a.text("TYPE_TABLE").filter(|t| *t == "TABLE_FONCTION") {
        return Err(
            a.err("TYPE_TABLE", format!("TYPE_TABLE='{t}' is not supported yet ('TABLE', 'TABLE_CONTAINER' are)"))
        );
    }
    let mut t = Table::default();
    if let Some(f) = a.fact("FONCTION") {
        let c = f.req_concept("FONCTION")?;
        let para = f.texts("PARA");
        let data = c.data();
        match &*data {
            ConceptData::Function(func) => {
                let px = para.first().cloned().unwrap_or_else(|| func.nom_para.clone());
                let py = para.get(1).cloned().unwrap_or_else(|| func.nom_resu.clone());
                t.add_column(&px, ColType::R, func.x.iter().map(|v| Cell::Real(*v)).collect())?;
                t.add_column(&py, ColType::R, func.y.iter().map(|v| Cell::Real(*v)).collect())?;
            }
            ConceptData::Nappe(n) => {
                let (mut p, mut x, mut y) = (Vec::new(), Vec::new(), Vec::new());
                for (pv, f) in n.params.iter().zip(&n.functions) {
                    for (xv, yv) in f.x.iter().zip(&f.y) {
                        p.push(Cell::Real(*pv));
                        x.push(Cell::Real(*xv));
                        y.push(Cell::Real(*yv));
                    }
                }
                t.add_column(&n.nom_para, ColType::R, p)?;
                t.add_column(&n.nom_para_fonc, ColType::R, x)?;
                t.add_column(&n.nom_resu, ColType::R, y)?;
            }
            _ => return Err(f.err("FONCTION", format!("{} holds no tabulated function", c.label()))),
        }
        return Ok(Some(ConceptData::Table(t)));
    }
    for occ in a.facts("LISTE") {
        let (cells, ty): (Vec<Cell>, ColType) = if occ.has("LISTE_I") {
            (occ.ints("LISTE_I").into_iter().map(Cell::Int).collect(), ColType::I)
        } else if occ.has("LISTE_R") {
            (occ.reals("LISTE_R").into_iter().map(Cell::Real).collect(), ColType::R)
        } else if occ.has("LISTE_K") {
            let k: usize = occ.text("TYPE_K").and_then(|s| s[1..].parse().ok()).unwrap_or(8);
            let texts = occ.texts("LISTE_K");
            let longest = texts.iter().map(|s| s.chars().count()).max().unwrap_or(0);
            if longest > k {
                return Err(occ.err("LISTE_K", format!("a value of {longest} characters does not fit TYPE_K='K{k}'")));
            }
            (texts.into_iter().map(Cell::Text).collect(), ColType::K(k))
        } else {
            // Concepts: their names, and (without PARA) their types beside.
            let cos = occ.concepts("LISTE_CO");
            if occ.text("PARA").is_none() {
                let names = cos.iter().map(|c| Cell::Text(c.label())).collect();
                let types = cos.iter().map(|c| Cell::Text(c.kind().aster_name().to_uppercase())).collect();
                t.add_column("NOM_SD", ColType::K(24), names)?;
                t.add_column("TYPE_OBJET", ColType::K(16), types)?;
                continue;
            }
            (cos.iter().map(|c| Cell::Text(c.label())).collect(), ColType::K(24))
        };
        let para =
            occ.text("PARA").ok_or_else(|| occ.err("PARA", "PARA is required for LISTE_I, LISTE_R and LISTE_K"))?;
        let cells = match occ.ints("NUME_LIGN") {
            rows if rows.is_empty() => cells,
            rows => {
                if rows.len() != cells.len() {
                    return Err(occ.err("NUME_LIGN", "NUME_LIGN needs one row number per value"));
                }
                let n = rows.iter().copied().max().unwrap_or(0).max(0) as usize;
                let mut placed = vec![Cell::Empty; n];
                for (r, c) in rows.iter().zip(cells) {
                    if *r < 1 {
                        return Err(occ.err("NUME_LIGN", "row numbers start at 1"));
                    }
                    placed[*r as usize - 1] = c;
                }
                placed
            }
        };
        t.add_column(para, ty, cells).map_err(|e| occ.err("PARA", e.msg))?;
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    Ok(Some(ConceptData::Table(t)))
}

// ------------------------------------------------------------------ LIRE_TABLE

pub fn lire_table(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let unit = a.int("UNITE").unwrap_or(19);
    let text = ctx.io.read_unit(unit).map_err(|e| e.at(a.span_of("UNITE")))?;
    let nblock = a.int("NUME_TABLE").unwrap_or(1) as usize;
    let sep = a.text("SEPARATEUR").unwrap_or(" ");
    let mut t = match a.text("FORMAT").unwrap_or("TABLEAU") {
        "ASTER" => table_io::read_aster(&text, nblock),
        "TABLEAU" => table_io::read_free(&text, sep, true, nblock),
        _ => table_io::read_free(&text, sep, false, nblock),
    }
    .map_err(|e| Error::runtime(format!("reading unit {unit}: {}", e.msg)).at(a.span))?;
    let mut seen = std::collections::HashSet::new();
    for c in t.columns.iter_mut() {
        if !seen.insert(c.name.clone()) {
            if a.text("RENOMME_PARA") == Some("UNIQUE") {
                let mut k = 1;
                while seen.contains(&format!("{}_{k}", c.name)) {
                    k += 1;
                }
                c.name = format!("{}_{k}", c.name);
                seen.insert(c.name.clone());
            } else {
                return Err(
                    a.err("UNITE", format!("parameter '{}' appears twice (RENOMME_PARA='UNIQUE' renames)", c.name))
                );
            }
        }
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    Ok(Some(ConceptData::Table(t)))
}

// ------------------------------------------------------------------ CALC_TABLE

/// The FORMAT_R of an occurrence, checked.
fn real_format(occ: &Args) -> Result<Option<RealFormat>> {
    occ.text("FORMAT_R").map(|f| RealFormat::parse(f).map_err(|e| occ.err("FORMAT_R", e))).transpose()
}

fn format_key(c: &Cell, fmt_r: Option<&RealFormat>) -> String {
    match (c, fmt_r) {
        (Cell::Real(r), Some(f)) => f.format(*r),
        (Cell::Real(r), None) => format!("{r:e}"),
        (Cell::Int(i), _) => i.to_string(),
        (Cell::Text(t), _) => t.trim_end().to_string(),
        (Cell::Empty, _) => "\u{0}".into(),
    }
}

/// Merge `b` into `a`: rows whose key values are unique in both tables are
/// merged (b's values win), the other rows of `b` are appended.
fn comb(
    a: &Table,
    b: &Table,
    keys: &[String],
    restrict: bool,
    fmt_r: Option<&RealFormat>,
    occ: &Args,
) -> Result<Table> {
    let mut out = a.clone();
    for c in &b.columns {
        if out.column(&c.name).is_none() {
            out.columns.push(Column { name: c.name.clone(), ty: c.ty, cells: vec![Cell::Empty; a.nrows()] });
        }
    }
    let key_cols = |t: &Table| -> Result<Vec<usize>> {
        keys.iter()
            .map(|k| {
                t.column(k)
                    .ok_or_else(|| occ.err("NOM_PARA", format!("parameter '{k}' is missing from a table to combine")))
            })
            .collect()
    };
    let (ka, kb) = if keys.is_empty() { (Vec::new(), Vec::new()) } else { (key_cols(a)?, key_cols(b)?) };
    let key = |t: &Table, cols: &[usize], r: usize| -> Vec<String> {
        cols.iter().map(|&c| format_key(&t.columns[c].cells[r], fmt_r)).collect()
    };
    let mut count_a = std::collections::HashMap::new();
    let mut row_a = std::collections::HashMap::new();
    if !keys.is_empty() {
        for r in 0..a.nrows() {
            let k = key(a, &ka, r);
            *count_a.entry(k.clone()).or_insert(0) += 1;
            row_a.insert(k, r);
        }
    }
    let mut count_b = std::collections::HashMap::new();
    if !keys.is_empty() {
        for r in 0..b.nrows() {
            *count_b.entry(key(b, &kb, r)).or_insert(0) += 1;
        }
    }
    for r in 0..b.nrows() {
        let target = if keys.is_empty() {
            None
        } else {
            let k = key(b, &kb, r);
            if count_a.get(&k) == Some(&1) && count_b.get(&k) == Some(&1) {
                row_a.get(&k).copied()
            } else {
                None
            }
        };
        match target {
            Some(ra) => {
                for c in &b.columns {
                    let j = out.column(&c.name).unwrap();
                    if !c.cells[r].is_empty() {
                        out.columns[j].cells[ra] = c.cells[r].clone();
                    }
                }
            }
            None if restrict => {}
            None => {
                let n = out.nrows();
                for col in out.columns.iter_mut() {
                    col.cells.push(Cell::Empty);
                }
                for c in &b.columns {
                    let j = out.column(&c.name).unwrap();
                    out.columns[j].cells[n] = c.cells[r].clone();
                }
            }
        }
    }
    for c in out.columns.iter_mut() {
        fix_type(c);
    }
    Ok(out)
}

/// After mixing cells, make the column type fit its content.
fn fix_type(c: &mut Column) {
    let has_real = c.cells.iter().any(|x| matches!(x, Cell::Real(_)));
    let has_text = c.cells.iter().any(|x| matches!(x, Cell::Text(_)));
    if c.ty == ColType::I && has_real {
        c.ty = ColType::R;
        for x in c.cells.iter_mut() {
            if let Cell::Int(i) = x {
                *x = Cell::Real(*i as f64);
            }
        }
    }
    if has_text {
        let len = c.cells.iter().map(|x| if let Cell::Text(t) = x { t.chars().count() } else { 0 }).max().unwrap_or(0);
        if let ColType::K(n) = c.ty {
            if len > n {
                c.ty = ColType::text_for(len);
            }
        }
    }
}

fn set_cell(t: &mut Table, name: &str, row: usize, cell: Cell) {
    let j = match t.column(name) {
        Some(j) => j,
        None => {
            let n = t.nrows();
            t.columns.push(Column { name: name.into(), ty: type_of(&cell), cells: vec![Cell::Empty; n] });
            t.columns.len() - 1
        }
    };
    let col = &mut t.columns[j];
    let cell = match (col.ty, cell) {
        (ColType::R, Cell::Int(i)) => Cell::Real(i as f64),
        (_, c) => c,
    };
    col.cells[row] = cell;
    fix_type(col);
}

fn statistics(t: &Table) -> Table {
    let empty = t.columns.iter().map(|c| c.cells.iter().filter(|x| x.is_empty()).count()).sum::<usize>();
    let mut s = Table::default();
    let names = ["NB_LIGNES", "NB_COLONNES", "NB_VIDE"];
    let vals = [t.nrows(), t.columns.len(), empty];
    s.add_column("STAT_NOM", ColType::K(16), names.iter().map(|n| Cell::Text(n.to_string())).collect()).unwrap();
    s.add_column("STAT_VALE", ColType::I, vals.iter().map(|v| Cell::Int(*v as i64)).collect()).unwrap();
    s
}

fn calcul(t: &Table, occ: &Args, table: &str) -> Result<Table> {
    let paras = occ.texts("NOM_PARA");
    let types = occ.texts("TYPE_CALCUL");
    let mut out = Table::default();
    out.add_column("TYPE_CALCUL", ColType::K(16), types.iter().map(|s| Cell::Text(s.clone())).collect())?;
    for p in &paras {
        let j = t.column(p).ok_or_else(|| occ.err("NOM_PARA", format!("table {table} has no parameter '{p}'")))?;
        let vals: Vec<f64> = t.columns[j].cells.iter().filter_map(Cell::as_f64).collect();
        if vals.is_empty() {
            return Err(occ.err("NOM_PARA", format!("parameter '{p}' of table {table} holds no number")));
        }
        let cells = types
            .iter()
            .map(|ty| {
                let v = match ty.as_str() {
                    "MAXI" => vals.iter().cloned().fold(f64::MIN, f64::max),
                    "MINI" => vals.iter().cloned().fold(f64::MAX, f64::min),
                    "SOMM" => vals.iter().sum(),
                    "MOY" => vals.iter().sum::<f64>() / vals.len() as f64,
                    "MAXI_ABS" => vals.iter().map(|v| v.abs()).fold(0.0, f64::max),
                    "MINI_ABS" => vals.iter().map(|v| v.abs()).fold(f64::MAX, f64::min),
                    _ => vals.iter().map(|v| v.abs()).sum(),
                };
                Cell::Real(v)
            })
            .collect();
        out.add_column(p, ColType::R, cells)?;
    }
    Ok(out)
}

pub fn calc_table(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let tc = a.req_concept("TABLE")?;
    let name = tc.label();
    let mut t = tc.table()?;
    for occ in a.facts("ACTION") {
        let op = occ.req_text("OPERATION")?;
        t = match op {
            "FILTRE" => {
                let rows = filter_rows(&t, &(0..t.nrows()).collect::<Vec<_>>(), occ, &name)?;
                t.select_rows(&rows)
            }
            "EXTR" | "SUPPRIME" => {
                let paras = occ.texts("NOM_PARA");
                for p in &paras {
                    if t.column(p).is_none() {
                        return Err(occ.err("NOM_PARA", format!("table {name} has no parameter '{p}'")));
                    }
                }
                let columns = if op == "EXTR" {
                    paras.iter().map(|p| t.columns[t.column(p).unwrap()].clone()).collect()
                } else {
                    t.columns.iter().filter(|c| !paras.contains(&c.name)).cloned().collect()
                };
                Table { title: t.title.clone(), columns }
            }
            "RENOMME" => {
                let p = occ.texts("NOM_PARA");
                let j = t
                    .column(&p[0])
                    .ok_or_else(|| occ.err("NOM_PARA", format!("table {name} has no parameter '{}'", p[0])))?;
                if t.column(&p[1]).is_some() {
                    return Err(occ.err("NOM_PARA", format!("table {name} already has a parameter '{}'", p[1])));
                }
                t.columns[j].name = p[1].clone();
                t
            }
            "TRI" => sort_table(&t, &occ.texts("NOM_PARA"), occ.text("ORDRE") == Some("DECROISSANT"), occ, &name)?,
            "COMB" => {
                let other = occ.req_concept("TABLE")?.table()?;
                comb(
                    &t,
                    &other,
                    &occ.texts("NOM_PARA"),
                    occ.text("RESTREINT") == Some("OUI"),
                    real_format(occ)?.as_ref(),
                    occ,
                )?
            }
            "AJOUT_LIGNE" => {
                let paras = occ.texts("NOM_PARA");
                let vals = occ.vals("VALE");
                if paras.len() != vals.len() {
                    return Err(occ.err("VALE", format!("{} parameters but {} values", paras.len(), vals.len())));
                }
                let n = t.nrows();
                for c in t.columns.iter_mut() {
                    c.cells.push(Cell::Empty);
                }
                for (p, v) in paras.iter().zip(vals) {
                    set_cell(&mut t, p, n, cell_of(v));
                }
                t
            }
            "AJOUT_COLONNE" => {
                let paras = occ.texts("NOM_PARA");
                if occ.has("VALE_COLONNE") {
                    if paras.len() != 1 {
                        return Err(occ.err("NOM_PARA", "VALE_COLONNE adds one column: give one NOM_PARA"));
                    }
                    let cells: Vec<Cell> = occ.vals("VALE_COLONNE").iter().map(cell_of).collect();
                    if cells.len() > t.nrows() {
                        return Err(occ
                            .err("VALE_COLONNE", format!("{} values for a table of {} rows", cells.len(), t.nrows())));
                    }
                    let ty = cells.first().map(type_of).unwrap_or(ColType::R);
                    let mut col = Column { name: paras[0].clone(), ty, cells };
                    fix_type(&mut col);
                    t.add_column(&col.name.clone(), col.ty, col.cells).map_err(|e| occ.err("NOM_PARA", e.msg))?;
                } else {
                    let vals = occ.vals("VALE");
                    if paras.len() != vals.len() {
                        return Err(occ.err("VALE", format!("{} parameters but {} values", paras.len(), vals.len())));
                    }
                    for (p, v) in paras.iter().zip(vals) {
                        let c = cell_of(v);
                        t.add_column(p, type_of(&c), vec![c; t.nrows()]).map_err(|e| occ.err("NOM_PARA", e.msg))?;
                    }
                }
                t
            }
            "OPER" => {
                let f = occ.req_concept("FORMULE")?;
                let target = occ.req_text("NOM_PARA")?.to_string();
                let data = f.data();
                let ConceptData::Formula(form) = &*data else {
                    return Err(occ.err("FORMULE", format!("{} is not a formula", f.label())));
                };
                let cols_names = match occ.texts("NOM_COLONNE") {
                    v if v.is_empty() => form.nom_para.clone(),
                    v => v,
                };
                if cols_names.len() != form.nom_para.len() {
                    return Err(occ.err(
                        "NOM_COLONNE",
                        format!(
                            "the formula takes {} parameters, {} columns given",
                            form.nom_para.len(),
                            cols_names.len()
                        ),
                    ));
                }
                let cols: Vec<usize> = cols_names
                    .iter()
                    .map(|p| {
                        t.column(p)
                            .ok_or_else(|| occ.err("NOM_COLONNE", format!("table {name} has no parameter '{p}'")))
                    })
                    .collect::<Result<_>>()?;
                let mut cells = Vec::with_capacity(t.nrows());
                for r in 0..t.nrows() {
                    let args: Option<Vec<f64>> = cols.iter().map(|&c| t.columns[c].cells[r].as_f64()).collect();
                    cells.push(match args {
                        Some(v) => Cell::Real(form.eval(&v).map_err(|e| e.at(occ.span))?),
                        None => Cell::Empty,
                    });
                }
                drop(data);
                match t.column(&target) {
                    Some(j) => {
                        t.columns[j].cells = cells;
                        t.columns[j].ty = ColType::R;
                    }
                    None => t.add_column(&target, ColType::R, cells)?,
                }
                t
            }
            "CALCUL" => calcul(&t, occ, &name)?,
            "STATISTIQUES" => statistics(&t),
            "UNIQUE" => {
                // Reals are compared as FORMAT_R writes them, when it is given.
                let fmt_r = real_format(occ)?;
                let paras = occ.texts("NOM_PARA");
                let cols: Vec<usize> = paras
                    .iter()
                    .map(|p| {
                        t.column(p).ok_or_else(|| occ.err("NOM_PARA", format!("table {name} has no parameter '{p}'")))
                    })
                    .collect::<Result<_>>()?;
                let mut seen = std::collections::HashSet::new();
                let rows: Vec<usize> = (0..t.nrows())
                    .filter(|&r| {
                        seen.insert(
                            cols.iter()
                                .map(|&c| format_key(&t.columns[c].cells[r], fmt_r.as_ref()))
                                .collect::<Vec<_>>(),
                        )
                    })
                    .collect();
                t.select_rows(&rows)
            }
            other => return Err(occ.err("OPERATION", format!("operation '{other}' is not supported yet"))),
        };
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    Ok(Some(ConceptData::Table(t)))
}

/// Rows sorted by the given parameters (numbers before empty cells).
fn sort_table(t: &Table, paras: &[String], descending: bool, occ: &Args, name: &str) -> Result<Table> {
    let cols: Vec<usize> = paras
        .iter()
        .map(|p| t.column(p).ok_or_else(|| occ.err("NOM_PARA", format!("table {name} has no parameter '{p}'"))))
        .collect::<Result<_>>()?;
    let cmp = |x: &Cell, y: &Cell| match (x, y) {
        (Cell::Text(a), Cell::Text(b)) => a.cmp(b),
        _ => x
            .as_f64()
            .unwrap_or(f64::MAX)
            .partial_cmp(&y.as_f64().unwrap_or(f64::MAX))
            .unwrap_or(std::cmp::Ordering::Equal),
    };
    let mut rows: Vec<usize> = (0..t.nrows()).collect();
    rows.sort_by(|&r1, &r2| {
        cols.iter()
            .map(|&c| cmp(&t.columns[c].cells[r1], &t.columns[c].cells[r2]))
            .find(|o| *o != std::cmp::Ordering::Equal)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    if descending {
        rows.reverse();
    }
    Ok(t.select_rows(&rows))
}

// ------------------------------------------------------------------ IMPR_TABLE

pub fn impr_table(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if a.text("IMPR_FONCTION") == Some("OUI") {
        return Err(
            a.err("IMPR_FONCTION", "IMPR_FONCTION='OUI' (printing the functions a table holds) is not supported yet")
        );
    }
    let tc = a.req_concept("TABLE")?;
    let name = tc.label();
    let mut t = tc.table()?;
    let rows = filtered(&t, a.facts("FILTRE"), &name)?;
    t = t.select_rows(&rows);
    if let Some(tri) = a.fact("TRI") {
        t = sort_table(&t, &tri.texts("NOM_PARA"), tri.text("ORDRE") == Some("DECROISSANT"), tri, &name)?;
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    let params = a.texts("NOM_PARA");
    let format = a.text("FORMAT").unwrap_or("TABLEAU");
    if !matches!(format, "TABLEAU" | "ASTER" | "AGRAF") {
        return Err(a.err("FORMAT", format!("FORMAT='{format}' is not supported yet")));
    }
    let text = table_io::write(
        &t,
        &name,
        format,
        &real_format(a)?.unwrap_or_default(),
        if params.is_empty() { None } else { Some(&params) },
    );
    let unit = a.int("UNITE").unwrap_or(8);
    ctx.io.write_unit(unit, &text).map_err(|e| e.at(a.span_of("UNITE")))?;
    Ok(None)
}
