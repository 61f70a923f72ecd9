//! Tables as text: Code_Aster's TABLEAU, ASTER and LIBRE formats.

use crate::concepts::table::{Cell, ColType, Column, Table};
use crate::diag::{Error, Result};
use crate::text::float_repr;
use crate::text::fortran::RealFormat;

/// Split on one or more occurrences of `sep`, ignoring leading/trailing ones.
fn msplit(line: &str, sep: &str) -> Vec<String> {
    let sep = if sep.is_empty() { " " } else { sep };
    let trimmed = trim_matches_str(line, sep);
    let mut out = Vec::new();
    for part in trimmed.split(sep) {
        if part.is_empty() && !out.is_empty() && sep != " " {
            // Repeated separators count once, as the reference reader does.
            continue;
        }
        if part.is_empty() && sep == " " {
            continue;
        }
        out.push(part.to_string());
    }
    if out.is_empty() {
        out.push(String::new());
    }
    out
}

fn trim_matches_str<'a>(mut s: &'a str, sep: &str) -> &'a str {
    if sep == " " {
        return s.trim_matches(|c: char| c == ' ' || c == '\t' || c == '\r');
    }
    s = s.trim_end_matches('\r');
    while let Some(r) = s.strip_prefix(sep) {
        s = r;
    }
    while let Some(r) = s.strip_suffix(sep) {
        s = r;
    }
    s
}

/// A text value as the table readers convert it: int, then real (also with a
/// decimal comma), else text.
fn convert(v: &str) -> Cell {
    if let Ok(i) = v.parse::<i64>() {
        return Cell::Int(i);
    }
    if let Ok(r) = v.parse::<f64>() {
        return Cell::Real(r);
    }
    if let Ok(r) = v.replace(',', ".").parse::<f64>() {
        return Cell::Real(r);
    }
    Cell::Text(v.to_string())
}

/// Build typed columns from rows of cells, inferring each column's type.
pub fn columns_from_rows(names: &[String], rows: &[Vec<Cell>]) -> Vec<Column> {
    names
        .iter()
        .enumerate()
        .map(|(j, name)| {
            let cells: Vec<Cell> = rows.iter().map(|r| r.get(j).cloned().unwrap_or(Cell::Empty)).collect();
            let all_int = cells.iter().all(|c| matches!(c, Cell::Int(_) | Cell::Empty));
            let all_num = cells.iter().all(|c| matches!(c, Cell::Int(_) | Cell::Real(_) | Cell::Empty));
            let ty = if all_int && cells.iter().any(|c| !c.is_empty()) {
                ColType::I
            } else if all_num {
                ColType::R
            } else {
                let len = cells
                    .iter()
                    .map(|c| match c {
                        Cell::Text(t) => t.chars().count(),
                        _ => 8,
                    })
                    .max()
                    .unwrap_or(8);
                ColType::text_for(len)
            };
            let cells = cells
                .into_iter()
                .map(|c| match (ty, c) {
                    (ColType::R, Cell::Int(i)) => Cell::Real(i as f64),
                    (ColType::K(_), Cell::Int(i)) => Cell::Text(i.to_string()),
                    (ColType::K(_), Cell::Real(r)) => Cell::Text(float_repr(r)),
                    (_, c) => c,
                })
                .collect();
            Column { name: name.clone(), ty, cells }
        })
        .collect()
}

/// Read a table in the TABLEAU (`#` comments, `-` empty cells) or LIBRE format.
pub fn read_free(text: &str, sep: &str, tableau: bool, nblock: usize) -> Result<Table> {
    let empty = if tableau { "-" } else { "" };
    let is_comment = |l: &str| tableau && l.starts_with('#');
    let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    // Split into blocks: fewer fields than the previous line starts a new one.
    let mut blocks: Vec<Vec<(usize, &str)>> = vec![Vec::new()];
    let mut nbcol = 0;
    let mut has_value = false;
    for line in &lines {
        let mut cur = msplit(line, sep).len();
        if is_comment(line) && !has_value {
            cur = 0;
        } else if nbcol > 1 && cur < nbcol {
            if blocks.len() >= nblock {
                break;
            }
            blocks.push(Vec::new());
            has_value = false;
        }
        nbcol = cur;
        blocks.last_mut().unwrap().push((cur, line));
        if !is_comment(line) {
            has_value = true;
        }
    }
    if nblock > blocks.len() {
        return Err(Error::runtime(format!("table number {nblock} requested, the unit holds {}", blocks.len())));
    }
    let block = &blocks[nblock - 1];
    let ncol = block.iter().map(|(n, _)| *n).max().unwrap_or(0);
    let mut title = Vec::new();
    let mut data = Vec::new();
    for (n, l) in block {
        if *n == ncol && !is_comment(l) {
            data.push(*l);
        } else {
            title.push(l.trim_start_matches('#').trim().to_string());
        }
    }
    if data.is_empty() {
        return Err(Error::runtime("no table found: no line of parameter names"));
    }
    let names: Vec<String> = msplit(data[0], sep).into_iter().map(|p| p.trim().replace(' ', "_")).collect();
    let rows: Vec<Vec<Cell>> = data[1..]
        .iter()
        .map(|l| {
            msplit(l, sep)
                .into_iter()
                .map(|v| {
                    let v = v.trim();
                    if v == empty {
                        Cell::Empty
                    } else {
                        convert(v)
                    }
                })
                .collect()
        })
        .collect();
    Ok(Table { title: title.join("\n"), columns: columns_from_rows(&names, &rows) })
}

/// Read a table in the ASTER format (`#DEBUT_TABLE` ... `#FIN_TABLE`).
pub fn read_aster(text: &str, nblock: usize) -> Result<Table> {
    let mut blocks = Vec::new();
    let mut cur: Option<Vec<&str>> = None;
    for l in text.lines() {
        let t = l.trim_end();
        if t == "#DEBUT_TABLE" {
            cur = Some(Vec::new());
        } else if t == "#FIN_TABLE" {
            if let Some(b) = cur.take() {
                blocks.push(b);
            }
        } else if let Some(b) = cur.as_mut() {
            b.push(l);
        }
    }
    if nblock > blocks.len() {
        return Err(Error::runtime(format!(
            "table number {nblock} requested, the unit holds {} table(s) in ASTER format",
            blocks.len()
        )));
    }
    let block = &blocks[nblock - 1];
    let mut title = Vec::new();
    let mut lines = Vec::new();
    for l in block {
        if let Some(t) = l.strip_prefix("#TITRE") {
            title.push(t.trim().to_string());
        } else if !l.trim().is_empty() {
            lines.push(*l);
        }
    }
    if lines.len() < 2 {
        return Err(Error::runtime("a table in ASTER format needs a line of names and a line of types"));
    }
    let names = msplit(lines[0], " ");
    let types: Vec<ColType> = msplit(lines[1], " ")
        .iter()
        .map(|t| ColType::parse(t).ok_or_else(|| Error::runtime(format!("unknown column type '{t}' in ASTER table"))))
        .collect::<Result<_>>()?;
    if types.len() != names.len() {
        return Err(Error::runtime(format!("{} parameter names but {} types", names.len(), types.len())));
    }
    let mut columns: Vec<Column> =
        names.iter().zip(&types).map(|(n, t)| Column { name: n.clone(), ty: *t, cells: Vec::new() }).collect();
    for (i, l) in lines[2..].iter().enumerate() {
        let fields = split_typed(l, &types)
            .ok_or_else(|| Error::runtime(format!("line {} of the table does not match its types: '{l}'", i + 1)))?;
        for (c, f) in columns.iter_mut().zip(fields) {
            let f = f.trim();
            c.cells.push(if f == "-" || f.is_empty() {
                Cell::Empty
            } else {
                match c.ty {
                    ColType::I => Cell::Int(f.parse().map_err(|_| Error::runtime(format!("'{f}' is not an integer")))?),
                    ColType::R => Cell::Real(
                        f.replace(['d', 'D'], "E")
                            .replace(',', ".")
                            .parse()
                            .map_err(|_| Error::runtime(format!("'{f}' is not a real")))?,
                    ),
                    ColType::K(_) => Cell::Text(f.to_string()),
                }
            });
        }
    }
    Ok(Table { title: title.join("\n"), columns })
}

/// Split a data line of an ASTER table: numbers are blank-separated, texts take
/// exactly their declared width.
fn split_typed(line: &str, types: &[ColType]) -> Option<Vec<String>> {
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    let mut out = Vec::new();
    for t in types {
        while i < chars.len() && chars[i] == ' ' {
            i += 1;
        }
        match t {
            ColType::K(n) => {
                let end = (i + n).min(chars.len());
                out.push(chars[i..end].iter().collect());
                i = end;
            }
            _ => {
                let st = i;
                while i < chars.len() && chars[i] != ' ' {
                    i += 1;
                }
                if st == i {
                    return None;
                }
                out.push(chars[st..i].iter().collect());
            }
        }
    }
    Some(out)
}

fn cell_text(c: &Cell, fmt_r: &RealFormat, format: &str) -> String {
    match c {
        // AGRAF is TABLEAU with a backslash before the empty-cell marker
        // (Code_Aster's `ReprTable`).
        Cell::Empty if format == "AGRAF" => "\\-".into(),
        Cell::Empty => "-".into(),
        Cell::Int(i) => i.to_string(),
        Cell::Real(r) => fmt_r.format(*r),
        Cell::Text(t) => t.clone(),
    }
}

/// The table as text: `TABLEAU` (aligned columns), `ASTER` (re-readable) or
/// `AGRAF` (TABLEAU, empty cells written `\-`).
pub fn write(t: &Table, name: &str, format: &str, fmt_r: &RealFormat, params: Option<&[String]>) -> String {
    let cols: Vec<&Column> = match params {
        Some(p) => p.iter().filter_map(|n| t.columns.iter().find(|c| &c.name == n)).collect(),
        None => t.columns.iter().collect(),
    };
    let cells: Vec<Vec<String>> =
        cols.iter().map(|c| c.cells.iter().map(|x| cell_text(x, fmt_r, format)).collect()).collect();
    let widths: Vec<usize> = cols
        .iter()
        .zip(&cells)
        .map(|(c, cs)| {
            let w = cs.iter().map(|s| s.chars().count()).max().unwrap_or(0).max(c.name.chars().count());
            match c.ty {
                ColType::K(n) if format == "ASTER" => w.max(n),
                _ => w,
            }
        })
        .collect();
    let mut s = String::new();
    let pad = |v: &str, w: usize| format!("{v:<w$}");
    if format == "ASTER" {
        s.push_str("#DEBUT_TABLE\n");
        for l in t.title.lines() {
            s.push_str(&format!("#TITRE {l}\n"));
        }
        if t.title.is_empty() {
            s.push_str(&format!("#TITRE {name}\n"));
        }
    } else {
        s.push_str("#\n#--------------------------------------------------------------------------------\n");
        for l in t.title.lines() {
            s.push_str(&format!("#{l}\n"));
        }
        if t.title.is_empty() {
            s.push_str(&format!("#TABLE {name}\n"));
        }
    }
    let line = |vals: Vec<String>| -> String {
        let parts: Vec<String> = vals.iter().zip(&widths).map(|(v, w)| pad(v, *w)).collect();
        format!(" {}\n", parts.join(" ").trim_end())
    };
    s.push_str(&line(cols.iter().map(|c| c.name.clone()).collect()));
    if format == "ASTER" {
        s.push_str(&line(cols.iter().map(|c| c.ty.name()).collect()));
    }
    for r in 0..t.nrows() {
        s.push_str(&line(cells.iter().map(|c| c[r].clone()).collect()));
    }
    if format == "ASTER" {
        s.push_str("#FIN_TABLE\n");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_format_with_title_and_decimal_commas() {
        let text = "Title line;;\nmore;;\n;;\nCol A;Col B;Col C\nx;111;0,5\ny;222;10,25\n";
        let t = read_free(text, ";", false, 1).unwrap();
        assert_eq!(t.columns.iter().map(|c| c.name.as_str()).collect::<Vec<_>>(), ["Col_A", "Col_B", "Col_C"]);
        assert_eq!(t.columns[1].ty, ColType::I);
        assert_eq!(t.columns[2].cells[1], Cell::Real(10.25));
        assert!(t.title.contains("Title line"));
    }

    #[test]
    fn aster_format_round_trip() {
        let mut t = Table::default();
        t.add_column("N", ColType::I, vec![Cell::Int(1), Cell::Empty]).unwrap();
        t.add_column("NOM", ColType::K(8), vec![Cell::Text("a b".into()), Cell::Text("c".into())]).unwrap();
        t.add_column("V", ColType::R, vec![Cell::Real(1.5), Cell::Real(-2.0e-7)]).unwrap();
        let text = write(&t, "T", "ASTER", &RealFormat::default(), None);
        let back = read_aster(&text, 1).unwrap();
        assert_eq!(back.columns[0].cells, t.columns[0].cells);
        assert_eq!(back.columns[1].cells, t.columns[1].cells);
        assert_eq!(back.columns[2].cells, t.columns[2].cells);
    }

    #[test]
    fn tableau_with_empty_cells() {
        let t = read_free("#comment\n A B\n 1 -\n 2 x\n", " ", true, 1).unwrap();
        assert_eq!(t.columns[0].ty, ColType::I);
        assert_eq!(t.columns[1].cells[0], Cell::Empty);
    }
}
