//! Code_Aster's own text mesh format (`.mail`, LIRE_MAILLAGE FORMAT='ASTER'), as `lrmast` reads it:
//! free-format items separated by blanks, `%` to the end of a line a comment, sections each closed by
//! `FINSF` and the file by `FIN`:
//!
//! - `TITRE`: free text;
//! - `COOR_2D` / `COOR_3D`: `name x y [z]` per node (Fortran `D` exponents accepted);
//! - a cell type (`SEG2`, `QUAD8`, `HEXA20`, ...): `name node...` per cell, nodes in Code_Aster's order;
//! - `GROUP_NO` / `GROUP_MA`: a group name (or `NOM = name`) then its members.
//!
//! Options on a section's header line (`NOBJ = 13`, `NOM = G`) are read as such.
//!
//! Nodes and cells are numbered in the order the file gives them; groups keep their members' order.
//! Other sections (`GROUP_FA`, `SYS_COOR`, `MACRO_*`, ...) and 1D coordinates are refused by name.

use super::{CellType, Mesh};
use std::collections::HashMap;

/// An item of the file and the line it is on.
struct Item<'a> {
    text: &'a str,
    line: usize,
}

fn items(src: &str) -> Vec<Item<'_>> {
    let mut out = Vec::new();
    for (k, raw) in src.lines().enumerate() {
        let line = raw.split('%').next().unwrap_or("");
        // `NOM=G1` and `NOM = G1` are the same items.
        for piece in line.split(|c: char| c.is_whitespace() || c == ',') {
            let mut rest = piece;
            while let Some(i) = rest.find('=') {
                if i > 0 {
                    out.push(Item { text: &rest[..i], line: k + 1 });
                }
                out.push(Item { text: "=", line: k + 1 });
                rest = &rest[i + 1..];
            }
            if !rest.is_empty() {
                out.push(Item { text: rest, line: k + 1 });
            }
        }
    }
    out
}

/// A GROUP_NO / GROUP_MA section, resolved once every entity is known.
struct Group {
    of_nodes: bool,
    name: String,
    /// Member names and their lines.
    members: Vec<(String, usize)>,
    line: usize,
}

fn real(s: &str) -> Option<f64> {
    s.replace(['D', 'd'], "E").parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Read a `.mail` text; `file` names it in errors (`file:line: message`).
pub fn read(src: &str, file: &str) -> Result<Mesh, String> {
    let items = items(src);
    let err = |line: usize, msg: String| format!("{file}:{line}: {msg}");
    let mut mesh = Mesh { named_nodes: true, ..Default::default() };
    let mut node_index: HashMap<String, usize> = HashMap::new();
    let mut cell_index: HashMap<String, usize> = HashMap::new();
    // Groups are resolved at the end: they may name entities defined after them.
    let mut groups: Vec<Group> = Vec::new();
    let mut cell_nodes: Vec<Vec<(&str, usize)>> = Vec::new();
    let mut k = 0;
    let mut ended = false;
    while k < items.len() {
        let head = &items[k];
        k += 1;
        // The section's items, up to FINSF.
        let start = k;
        while k < items.len() && !items[k].text.eq_ignore_ascii_case("FINSF") {
            k += 1;
        }
        let mut body = &items[start..k.min(items.len())];
        let closed = k < items.len();
        // The header's options (`COOR_3D NOBJ=13`, `GROUP_NO NOM=BAS`, and on the lines after it the
        // `NUMIN=1 NUMAX=148`, `AUTEUR=… DATE=…` that interfaces write): NOM names a group; the others are
        // only hints.
        let mut nom: Option<&Item> = None;
        while let [key, eq, value, rest @ ..] = body {
            if eq.text != "=" {
                break;
            }
            if key.text.eq_ignore_ascii_case("NOM") {
                nom = Some(value);
            }
            body = rest;
        }
        let word = head.text.to_ascii_uppercase();
        if word == "FIN" {
            ended = true;
            break;
        }
        if !closed {
            return Err(err(head.line, format!("section {word} is not closed by FINSF")));
        }
        k += 1; // FINSF
        match word.as_str() {
            "TITRE" => {}
            "COOR_1D" => return Err(err(head.line, "1D meshes (COOR_1D) are not supported yet".into())),
            "COOR_2D" | "COOR_3D" => {
                let d = if word == "COOR_2D" { 2 } else { 3 };
                if mesh.dim != 0 && mesh.dim != d {
                    return Err(err(head.line, format!("{word} after coordinates of dimension {}", mesh.dim)));
                }
                mesh.dim = d;
                if !body.len().is_multiple_of(d + 1) {
                    return Err(err(head.line, format!("{word}: each node is a name and {d} coordinates")));
                }
                for node in body.chunks(d + 1) {
                    let name = node[0].text.to_string();
                    let mut x = [0.0; 3];
                    for (i, it) in node[1..].iter().enumerate() {
                        x[i] = real(it.text).ok_or_else(|| {
                            err(it.line, format!("{word}: node {name}: '{}' is not a coordinate", it.text))
                        })?;
                    }
                    if node_index.insert(name.clone(), mesh.coords.len()).is_some() {
                        return Err(err(node[0].line, format!("node {name} is defined twice")));
                    }
                    mesh.coords.push(x);
                    mesh.node_names.push(name);
                }
            }
            "GROUP_NO" | "GROUP_MA" => {
                let (name, members) = match (nom, body) {
                    (Some(g), rest) => (g, rest),
                    (None, [n, eq, g, rest @ ..]) if n.text.eq_ignore_ascii_case("NOM") && eq.text == "=" => (g, rest),
                    (None, [g, rest @ ..]) => (g, rest),
                    (None, []) => return Err(err(head.line, format!("{word} without a group name"))),
                };
                groups.push(Group {
                    of_nodes: word == "GROUP_NO",
                    name: name.text.to_string(),
                    members: members.iter().map(|m| (m.text.to_string(), m.line)).collect(),
                    line: name.line,
                });
            }
            _ => {
                let Some(t) = CellType::from_name(&word) else {
                    return Err(err(head.line, format!("section {word} is not supported")));
                };
                let n = t.nnodes();
                if !body.len().is_multiple_of(n + 1) {
                    return Err(err(head.line, format!("{word}: each cell is a name and {n} nodes")));
                }
                for cell in body.chunks(n + 1) {
                    let name = cell[0].text.to_string();
                    if cell_index.insert(name.clone(), mesh.cells.len()).is_some() {
                        return Err(err(cell[0].line, format!("cell {name} is defined twice")));
                    }
                    mesh.cell_names.push(name);
                    mesh.cell_types.push(t);
                    mesh.cells.push(Vec::new());
                    // Resolved once every node is known (a file may give the cells first).
                    cell_nodes.push(cell[1..].iter().map(|it| (it.text, it.line)).collect());
                }
            }
        }
    }
    if !ended {
        return Err(err(items.last().map(|i| i.line).unwrap_or(1), "the file does not end with FIN".into()));
    }
    if mesh.dim == 0 {
        return Err(err(1, "no coordinates (COOR_2D or COOR_3D)".into()));
    }
    for (c, names) in cell_nodes.into_iter().enumerate() {
        for (name, line) in names {
            let n = *node_index
                .get(name)
                .ok_or_else(|| err(line, format!("cell {}: node {name} is not defined", mesh.cell_names[c])))?;
            mesh.cells[c].push(n);
        }
    }
    for Group { of_nodes, name, members, line } in groups {
        let (index, what, map) = if of_nodes {
            (&node_index, "node", &mut mesh.node_groups)
        } else {
            (&cell_index, "cell", &mut mesh.cell_groups)
        };
        if map.contains_key(&name) {
            return Err(err(line, format!("group {name} is defined twice")));
        }
        let mut list = Vec::with_capacity(members.len());
        for (m, l) in members {
            list.push(*index.get(&m).ok_or_else(|| err(l, format!("group {name}: {what} {m} is not defined")))?);
        }
        map.insert(name, list);
    }
    Ok(mesh)
}

/// Write a mesh in this format: coordinates, cells (a section per run of one type, so that reading
/// it back numbers them as here), groups of nodes then of cells, coordinates written exactly.
pub fn write(mesh: &Mesh, title: &str) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let _ = writeln!(out, "TITRE\n {title}\nFINSF\n%");
    let dim = mesh.dim.clamp(2, 3);
    let _ = writeln!(out, "COOR_{dim}D");
    for (n, x) in mesh.coords.iter().enumerate() {
        let _ = write!(out, " {:<8}", mesh.node_names[n]);
        for v in &x[..dim] {
            let _ = write!(out, " {}", crate::text::float_repr(*v));
        }
        out.push('\n');
    }
    out.push_str("FINSF\n%\n");
    let mut c = 0;
    while c < mesh.ncells() {
        let t = mesh.cell_types[c];
        let _ = writeln!(out, "{}", t.name());
        while c < mesh.ncells() && mesh.cell_types[c] == t {
            let _ = write!(out, " {:<8}", mesh.cell_names[c]);
            for &n in &mesh.cells[c] {
                let _ = write!(out, " {}", mesh.node_names[n]);
            }
            out.push('\n');
            c += 1;
        }
        out.push_str("FINSF\n%\n");
    }
    for (kind, groups, names) in
        [("GROUP_NO", &mesh.node_groups, &mesh.node_names), ("GROUP_MA", &mesh.cell_groups, &mesh.cell_names)]
    {
        for (g, members) in groups {
            let _ = writeln!(out, "{kind}\n {g}");
            for chunk in members.chunks(8) {
                let line: Vec<&str> = chunk.iter().map(|&i| names[i].as_str()).collect();
                let _ = writeln!(out, " {}", line.join(" "));
            }
            out.push_str("FINSF\n%\n");
        }
    }
    out.push_str("FIN\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_is_written_reads_back_the_same() {
        let m = read(CUBE, "cube.mail").unwrap();
        let back = read(&write(&m, "cube"), "back.mail").unwrap();
        assert_eq!(back.coords, m.coords);
        assert_eq!(back.cells, m.cells);
        assert_eq!(back.cell_types, m.cell_types);
        assert_eq!(back.cell_names, m.cell_names);
        assert_eq!(back.node_names, m.node_names);
        assert_eq!(back.node_groups, m.node_groups);
        assert_eq!(back.cell_groups, m.cell_groups);
    }

    const CUBE: &str = "% a comment\nTITRE\nTEST\n ELEMENT CUBE\nFINSF\nCOOR_3D\nN1 0. 0. 0.\nN2 3.D0 0. 0.\n\
        N3 3. 3. 0.\nN4 0. 3. 0.\nN5 0. 0. 3.\nN6 3. 0. 3.\nN7 3. 3. 3.\nN8 0. 3. 3.\nFINSF\n\
        QUAD4\nMA2 N5 N6 N7 N8\nFINSF\nHEXA8\nMA1 N1 N2 N3 N4 N5 N6 N7 N8 % the cube\nFINSF\n\
        GROUP_NO NOM = BAS\nN1 N2 N3 N4\nFINSF\nGROUP_NO NOBJ=2\nDIAG N1 N7\nFINSF\nGROUP_MA\nHAUT MA2\nFINSF\nFIN\n";

    #[test]
    fn reads_the_sections_in_file_order() {
        let m = read(CUBE, "cube.mail").unwrap();
        assert_eq!(m.dim, 3);
        assert_eq!(m.node_names.len(), 8);
        assert_eq!(m.coords[1], [3.0, 0.0, 0.0]);
        assert_eq!(m.cell_names, ["MA2", "MA1"]);
        assert_eq!(m.cell_types, [CellType::Quad4, CellType::Hexa8]);
        assert_eq!(m.cells[1], [0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(m.node_groups["BAS"], [0, 1, 2, 3]);
        assert_eq!(m.node_groups["DIAG"], [0, 6]);
        assert_eq!(m.cell_groups["HAUT"], [0]);
    }

    /// Header options on the lines after the section's word, as the IDEAS interface writes them
    /// (sdls112a.20).
    #[test]
    fn header_options_on_the_following_lines() {
        let src = CUBE.replace(
            "COOR_3D\n",
            "COOR_3D    NOM=INDEFINI    NBOBJ=8\n           NUMIN=1   NUMAX=8\n   AUTEUR=INTERF_ST/TF   DATE=07/02/2005\n",
        );
        let m = read(&src, "cube.mail").unwrap();
        assert_eq!(m.node_names.len(), 8);
        assert_eq!(m.coords[1], [3.0, 0.0, 0.0]);
    }

    #[test]
    fn errors_name_the_line() {
        let bad = CUBE.replace("MA1 N1 N2", "MA1 N1 N9");
        assert_eq!(read(&bad, "c.mail").unwrap_err(), "c.mail:20: cell MA1: node N9 is not defined");
        let bad = CUBE.replace("N2 3.D0", "N2 3.X0");
        assert!(read(&bad, "c.mail").unwrap_err().starts_with("c.mail:8: COOR_3D: node N2: '3.X0'"));
        let bad = CUBE.replace("FIN\n", "");
        assert!(read(&bad, "c.mail").unwrap_err().ends_with("the file does not end with FIN"));
        let bad = CUBE.replace("GROUP_MA\n", "GROUP_FA\n");
        assert!(read(&bad, "c.mail").unwrap_err().contains("section GROUP_FA is not supported"));
        let bad = CUBE.replace("HAUT MA2", "HAUT MA3");
        assert!(read(&bad, "c.mail").unwrap_err().contains("group HAUT: cell MA3 is not defined"));
    }
}
