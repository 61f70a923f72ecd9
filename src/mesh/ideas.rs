//! I-DEAS universal files (`.unv`, Code_Aster's `.msup`; LIRE_MAILLAGE FORMAT='IDEAS'), read as
//! Code_Aster's converter (`presup`, `sleneu`, `sleelt`, `slegro`) turns them into its own mesh:
//!
//! - datasets between `-1` lines; nodes from 15, 781 and 2411 (all of them, file order, named
//!   `N<label>`, three coordinates as written: a node in a cylindrical or spherical system (18,
//!   2420) stops the reading, one in a Cartesian system keeps its coordinates);
//! - elements from 71, 780 and 2412: I-DEAS's descriptor gives the Code_Aster type, cells are
//!   numbered type by type in the converter's type order, file order within a type, named
//!   `M<label>`, their nodes in Code_Aster's order;
//! - trace lines (82), the wire frames of modal-identification files: SEG2 cells from node to node
//!   (a 0 lifts the pen), after the elements, labelled on from the largest element label;
//! - groups from 752, 2417, 2429, 2430, 2432, 2435, 2452, 2467 and 2477: the nodes (`7`) and the
//!   elements (`8`) of a group become a group of nodes and a group of cells named by the group's
//!   first 8 characters (cut at the first character that is not a letter, digit or `_`; a name that
//!   does not start with a letter is skipped, `PERMANENT...` becomes `GRNO<n>`/`GRMA<n>`, the cells
//!   of `COUL_...` make no group);
//! - with `colour_groups` (CREA_GROUP_COUL='OUI'), `COUL_<c>` groups of the nodes and of the cells
//!   of each colour.
//!
//! Errors name the file and line.

use super::{CellType, Mesh};
use std::collections::{BTreeMap, HashMap};

/// The converter's cell types by internal code (`inistb`): Code_Aster type and, for the codes whose
/// nodes I-DEAS lists in another order, where the `i`-th node read goes (0-based).
fn code_type(code: usize) -> Option<(CellType, Option<&'static [usize]>)> {
    use CellType::*;
    Some(match code {
        1 | 29 | 31 | 34 => (Seg2, None),
        2 => (Tria3, None),
        3 => (Tria6, Some(&[0, 3, 1, 4, 2, 5])),
        5 => (Quad4, None),
        6 => (Quad8, Some(&[0, 4, 1, 5, 2, 6, 3, 7])),
        14 => (Tetra4, None),
        15 => (Tetra10, Some(&[0, 4, 1, 5, 2, 6, 7, 8, 9, 3])),
        16 => (Penta6, None),
        17 => (Penta15, Some(&[0, 6, 1, 7, 2, 8, 9, 10, 11, 3, 12, 4, 13, 5, 14])),
        19 => (Hexa8, None),
        20 => (Hexa20, Some(&[0, 8, 1, 9, 2, 10, 3, 11, 12, 13, 14, 15, 4, 16, 5, 17, 6, 18, 7, 19])),
        30 | 32 | 33 => (Poi1, None),
        35 => (Seg3, Some(&[0, 2, 1])),
        _ => return None,
    })
}

/// The internal code of an I-DEAS element descriptor (`cov4v5`).
fn descriptor_code(d: i64) -> Option<usize> {
    Some(match d {
        171 | 11 | 21 | 23 => 1,
        91 | 61 | 41 | 51 | 74 | 81 => 2,
        22 | 24 | 172 => 35,
        92 | 62 | 42 | 52 | 72 | 82 => 3,
        93 | 63 | 43 | 53 | 73 => 4,
        94 | 64 | 44 | 54 | 71 | 84 => 5,
        95 | 65 | 55 | 45 | 75 | 85 => 6,
        96 | 66 | 46 | 56 | 76 => 7,
        101..=106 => (d - 93) as usize,
        111 => 14,
        118 => 15,
        112 => 16,
        113 => 17,
        114 => 18,
        115 => 19,
        116 => 20,
        117 => 21,
        136 | 137 => 29,
        138 | 139 => 30,
        141 => 31,
        142 => 32,
        161 => 33,
        121 => 34,
        _ => return None,
    })
}

/// Names of the converter's codes that Code_Aster has no cell for.
fn code_name(code: usize) -> &'static str {
    match code {
        4 => "TRIA9",
        7 => "QUAD12",
        8 => "PENTAC6",
        9 => "PENTAC12",
        10 => "PENTAC18",
        11 => "HEXACE8",
        12 => "HEXACE16",
        13 => "HEXACE24",
        18 => "PENTA24",
        21 => "HEXA32",
        _ => "?",
    }
}

/// Fixed-width integer fields (Fortran `I10`): blanks read as 0.
fn int_at(line: &str, start: usize, width: usize) -> Result<i64, ()> {
    let field = line.get(start..(start + width).min(line.len())).unwrap_or("").trim();
    if field.is_empty() {
        Ok(0)
    } else {
        field.parse::<i64>().map_err(|_| ())
    }
}

/// A Fortran real (`E25.16`, `D` exponents).
fn real(field: &str) -> Option<f64> {
    let f = field.trim();
    if f.is_empty() {
        return Some(0.0);
    }
    f.replace(['D', 'd'], "E").parse::<f64>().ok()
}

struct Reader<'a> {
    file: &'a str,
    lines: Vec<&'a str>,
}

impl Reader<'_> {
    fn err(&self, line: usize, msg: impl std::fmt::Display) -> String {
        format!("{}:{}: {msg}", self.file, line + 1)
    }
    fn line(&self, k: usize, what: &str) -> Result<&str, String> {
        self.lines
            .get(k)
            .copied()
            .ok_or_else(|| self.err(self.lines.len().saturating_sub(1), format!("end of file in {what}")))
    }
    fn ints(&self, k: usize, n: usize, what: &str) -> Result<Vec<i64>, String> {
        let l = self.line(k, what)?;
        (0..n)
            .map(|i| int_at(l, 10 * i, 10).map_err(|_| self.err(k, format!("{what}: bad integer field {}", i + 1))))
            .collect()
    }
}

/// One dataset: its number and the line range of its body.
struct Dataset {
    number: i64,
    start: usize,
    end: usize,
}

fn datasets(r: &Reader) -> Result<Vec<Dataset>, String> {
    let is_delim = |l: &str| l.trim() == "-1";
    let mut out = Vec::new();
    let mut k = 0;
    while k < r.lines.len() {
        if !is_delim(r.lines[k]) {
            k += 1;
            continue;
        }
        // `-1`, the dataset number, its body, `-1`.
        let Some(head) = r.lines.get(k + 1) else { break };
        if is_delim(head) {
            k += 1;
            continue;
        }
        let number = head.split_whitespace().next().and_then(|w| w.parse::<i64>().ok()).unwrap_or(0);
        let start = k + 2;
        let mut end = start;
        while end < r.lines.len() && !is_delim(r.lines[end]) {
            end += 1;
        }
        if end >= r.lines.len() {
            return Err(r.err(k + 1, format!("dataset {number} is not closed by -1")));
        }
        out.push(Dataset { number, start, end });
        k = end + 1;
    }
    Ok(out)
}

struct Cell {
    label: i64,
    code: usize,
    nodes: Vec<i64>,
    colour: i64,
    line: usize,
}

/// Read a universal file; `file` names it in errors (`file:line: message`).
pub fn read(src: &str, file: &str, colour_groups: bool) -> Result<Mesh, String> {
    let r = Reader { file, lines: src.lines().collect() };
    let sets = datasets(&r)?;
    let mut systems: HashMap<i64, i64> = HashMap::new();
    // Nodes: label, coordinates, colour, line.
    let mut nodes: Vec<(i64, [f64; 3], i64, usize)> = Vec::new();
    let mut cells: Vec<Cell> = Vec::new();
    // Groups in file order: name, of nodes, member labels, line.
    let mut groups: Vec<(String, bool, Vec<i64>, usize)> = Vec::new();
    let mut node_colours: Vec<Vec<(i64, i64)>> = Vec::new();
    let mut cell_colours: Vec<Vec<(i64, i64)>> = Vec::new();
    let mut read_something = false;
    // Trace lines (82): colour, node labels (0 lifts the pen), line.
    let mut traces: Vec<(i64, Vec<i64>, usize)> = Vec::new();
    for ds in &sets {
        match ds.number {
            18 | 2420 => read_systems(&r, ds, &mut systems)?,
            15 | 781 | 2411 => {
                let first = nodes.len();
                read_nodes(&r, ds, &systems, &mut nodes)?;
                node_colours.push(nodes[first..].iter().map(|n| (n.0, n.2)).collect());
                read_something = true;
            }
            71 | 780 | 2412 => {
                let first = cells.len();
                read_elements(&r, ds, &mut cells)?;
                cell_colours.push(cells[first..].iter().map(|c| (c.label, c.colour)).collect());
                read_something = true;
            }
            82 => {
                read_trace_lines(&r, ds, &mut traces)?;
                read_something = true;
            }
            2431 => return Err(r.err(ds.start - 1, format!("dataset {} (trace lines) is not supported", ds.number))),
            752 | 2417 | 2429 | 2430 | 2432 | 2435 | 2452 | 2467 | 2477 => {
                read_groups(&r, ds, &mut groups)?;
                read_something = true;
            }
            _ => {}
        }
    }
    if !read_something {
        return Err(format!("{file}: no node, element or group dataset: not an I-DEAS universal file"));
    }
    // A trace line drawn from node to node is a chain of SEG2 cells (files of modal identification
    // describe their wire-frame models so), labelled after the elements.
    let mut label = cells.iter().map(|c| c.label).max().unwrap_or(0);
    let first = cells.len();
    for (colour, path, line) in &traces {
        for pair in path.windows(2) {
            if pair[0] != 0 && pair[1] != 0 {
                label += 1;
                let nodes = pair.to_vec();
                cells.push(Cell { label, code: 1, nodes, colour: *colour, line: *line });
            }
        }
    }
    if cells.len() > first {
        cell_colours.push(cells[first..].iter().map(|c| (c.label, c.colour)).collect());
    }
    if colour_groups {
        for set in &node_colours {
            for (name, members) in colour_sets(set) {
                groups.push((name, true, members, 0));
            }
        }
        for set in &cell_colours {
            for (name, members) in colour_sets(set) {
                groups.push((name, false, members, 0));
            }
        }
    }
    build(&r, nodes, cells, groups)
}

/// `COUL_<c>` sets of labels, by increasing colour.
fn colour_sets(items: &[(i64, i64)]) -> Vec<(String, Vec<i64>)> {
    let mut by: BTreeMap<i64, Vec<i64>> = BTreeMap::new();
    for &(label, colour) in items {
        if (0..256).contains(&colour) {
            by.entry(colour).or_default().push(label);
        }
    }
    by.into_iter().map(|(c, v)| (format!("COUL_{c}"), v)).collect()
}

fn read_systems(r: &Reader, ds: &Dataset, systems: &mut HashMap<i64, i64>) -> Result<(), String> {
    let mut k = ds.start;
    if ds.number == 2420 {
        k += 2; // the part's number and name
    }
    while k < ds.end {
        let v = r.ints(k, 3, "coordinate system")?;
        systems.insert(v[0], v[1]);
        // 2420: a name line and 4 lines of 3 reals; 18: a name line and 2 lines of reals.
        k += if ds.number == 2420 { 6 } else { 4 };
    }
    Ok(())
}

fn read_nodes(
    r: &Reader,
    ds: &Dataset,
    systems: &HashMap<i64, i64>,
    out: &mut Vec<(i64, [f64; 3], i64, usize)>,
) -> Result<(), String> {
    let mut k = ds.start;
    while k < ds.end {
        let v = r.ints(k, 4, "node")?;
        let (label, system, colour) = (v[0], v[1], v[3]);
        if systems.get(&system).copied().unwrap_or(0) != 0 {
            return Err(r.err(k, format!("node {label} is given in a non-Cartesian coordinate system ({system})")));
        }
        let mut x = [0.0; 3];
        let (text, at, width) = if ds.number == 15 {
            (r.line(k, "node")?, 40, 13)
        } else {
            k += 1;
            (r.line(k, "node")?, 0, 25)
        };
        for (i, xi) in x.iter_mut().enumerate() {
            let s = at + width * i;
            let field = text.get(s..(s + width).min(text.len())).unwrap_or("");
            *xi =
                real(field).ok_or_else(|| r.err(k, format!("node {label}: '{}' is not a coordinate", field.trim())))?;
        }
        out.push((label, x, colour, k));
        k += 1;
    }
    Ok(())
}

fn read_elements(r: &Reader, ds: &Dataset, out: &mut Vec<Cell>) -> Result<(), String> {
    let mut k = ds.start;
    while k < ds.end {
        let head = k;
        let (label, code, colour, nbnode) = match ds.number {
            71 => {
                let v = r.ints(k, 7, "element")?;
                (v[0], usize::try_from(v[1]).unwrap_or(0), v[5], v[6])
            }
            780 | 2412 => {
                let v = r.ints(k, if ds.number == 780 { 8 } else { 6 }, "element")?;
                let (label, desc) = (v[0], v[1]);
                let (colour, nbnode) = if ds.number == 780 { (v[6], v[7]) } else { (v[4], v[5]) };
                if matches!(desc, 11 | 21 | 22 | 23 | 24) {
                    k += 1; // the beam's orientation
                }
                let code = descriptor_code(desc).ok_or_else(|| {
                    r.err(head, format!("element {label}: I-DEAS descriptor {desc} is not supported"))
                })?;
                (label, code, colour, nbnode)
            }
            _ => unreachable!("element datasets only"),
        };
        let nbnode = usize::try_from(nbnode).map_err(|_| r.err(head, format!("element {label}: bad node count")))?;
        let mut nodes = Vec::with_capacity(nbnode);
        while nodes.len() < nbnode {
            k += 1;
            let l = r.line(k, "element nodes")?;
            for i in 0..8.min(nbnode - nodes.len()) {
                nodes.push(int_at(l, 10 * i, 10).map_err(|_| r.err(k, format!("element {label}: bad node number")))?);
            }
        }
        out.push(Cell { label, code, nodes, colour, line: head });
        k += 1;
    }
    Ok(())
}

/// Dataset 82: a header (number, node count, colour), an identification line, the nodes 8 to a line.
fn read_trace_lines(r: &Reader, ds: &Dataset, out: &mut Vec<(i64, Vec<i64>, usize)>) -> Result<(), String> {
    let mut k = ds.start;
    while k < ds.end {
        let head = k;
        let v = r.ints(k, 3, "trace line")?;
        let count = usize::try_from(v[1]).map_err(|_| r.err(head, format!("trace line {}: bad node count", v[0])))?;
        k += 1; // the identification line
        let mut nodes = Vec::with_capacity(count);
        while nodes.len() < count {
            k += 1;
            let l = r.line(k, "trace line nodes")?;
            for i in 0..8.min(count - nodes.len()) {
                nodes.push(int_at(l, 10 * i, 10).map_err(|_| r.err(k, format!("trace line {}: bad node", v[0])))?);
            }
        }
        out.push((v[2], nodes, head));
        k += 1;
    }
    Ok(())
}

/// An identifier at the start of `s`: its length (letters, digits, `_`, starting with a letter).
fn identifier_len(s: &str) -> usize {
    let b = s.as_bytes();
    if b.first().is_none_or(|c| !c.is_ascii_alphabetic()) {
        return 0;
    }
    b.iter().take_while(|c| c.is_ascii_alphanumeric() || **c == b'_').count()
}

fn read_groups(r: &Reader, ds: &Dataset, out: &mut Vec<(String, bool, Vec<i64>, usize)>) -> Result<(), String> {
    let (count_at, per_line) = match ds.number {
        752 => (50, 4),
        2417 => (60, 4),
        2429 | 2430 | 2432 => (70, 4),
        _ => (70, 2),
    };
    let mut k = ds.start;
    while k < ds.end {
        let head = k;
        let l = r.line(k, "group")?;
        let number = int_at(l, 0, 10).map_err(|_| r.err(k, "bad group number"))?;
        let count = int_at(l, count_at, 10).map_err(|_| r.err(k, "bad entity count"))?;
        let count = usize::try_from(count).map_err(|_| r.err(k, "bad entity count"))?;
        k += 1;
        let raw: String = r.line(k, "group name")?.chars().take(20).collect();
        let full = raw.trim_end();
        let name8: String = full.chars().take(8).collect();
        let ident = identifier_len(&name8);
        // The members: (entity type, label) pairs, `per_line` per line.
        let mut members: Vec<(i64, i64)> = Vec::with_capacity(count);
        while members.len() < count {
            k += 1;
            let l = r.line(k, "group members")?;
            for j in 0..per_line.min(count - members.len()) {
                let at = if per_line == 4 { 20 * j } else { 40 * j };
                let t = int_at(l, at, 10).map_err(|_| r.err(k, "bad entity type"))?;
                let n = int_at(l, at + 10, 10).map_err(|_| r.err(k, "bad entity label"))?;
                members.push((t, n));
            }
        }
        k += 1;
        if ident == 0 || count == 0 {
            continue;
        }
        let name = name8[..ident].to_string();
        let permanent = full.starts_with("PERMANENT");
        let nodes: Vec<i64> = members.iter().filter(|m| m.0 == 7).map(|m| m.1).collect();
        let cells: Vec<i64> = members.iter().filter(|m| m.0 == 8).map(|m| m.1).collect();
        if !nodes.is_empty() {
            let n = if permanent { format!("GRNO{number}") } else { name.clone() };
            out.push((n, true, nodes, head));
        }
        if !cells.is_empty() && !name.starts_with("COUL_") {
            let n = if permanent { format!("GRMA{number}") } else { name };
            out.push((n, false, cells, head));
        }
    }
    Ok(())
}

fn build(
    r: &Reader,
    nodes: Vec<(i64, [f64; 3], i64, usize)>,
    cells: Vec<Cell>,
    groups: Vec<(String, bool, Vec<i64>, usize)>,
) -> Result<Mesh, String> {
    let mut mesh = Mesh { dim: 3, named_nodes: true, ..Default::default() };
    let mut node_index: HashMap<i64, usize> = HashMap::with_capacity(nodes.len());
    for (label, x, _, line) in nodes {
        if node_index.insert(label, mesh.coords.len()).is_some() {
            return Err(r.err(line, format!("node {label} is defined twice")));
        }
        mesh.coords.push(x);
        mesh.node_names.push(format!("N{label}"));
    }
    let mut cell_index: HashMap<i64, usize> = HashMap::with_capacity(cells.len());
    for code in 1..=35 {
        for c in cells.iter().filter(|c| c.code == code) {
            let (t, perm) = code_type(code).ok_or_else(|| {
                r.err(c.line, format!("element {}: {} cells have no Code_Aster counterpart", c.label, code_name(code)))
            })?;
            if c.nodes.len() != t.nnodes() {
                return Err(r.err(c.line, format!("element {}: {} nodes for a {}", c.label, c.nodes.len(), t.name())));
            }
            let mut conn = vec![0usize; t.nnodes()];
            for (i, label) in c.nodes.iter().enumerate() {
                let n = *node_index
                    .get(label)
                    .ok_or_else(|| r.err(c.line, format!("element {}: node {label} is not defined", c.label)))?;
                conn[perm.map_or(i, |p| p[i])] = n;
            }
            if cell_index.insert(c.label, mesh.cells.len()).is_some() {
                return Err(r.err(c.line, format!("element {} is defined twice", c.label)));
            }
            mesh.cells.push(conn);
            mesh.cell_types.push(t);
            mesh.cell_names.push(format!("M{}", c.label));
        }
    }
    for (name, of_nodes, members, line) in groups {
        let (index, what, map) = if of_nodes {
            (&node_index, "node", &mut mesh.node_groups)
        } else {
            (&cell_index, "element", &mut mesh.cell_groups)
        };
        if map.contains_key(&name) {
            return Err(r.err(line, format!("two groups of {what}s are named {name} (names are cut to 8 characters)")));
        }
        let list = members
            .iter()
            .map(|m| {
                index.get(m).copied().ok_or_else(|| r.err(line, format!("group {name}: {what} {m} is not defined")))
            })
            .collect::<Result<Vec<usize>, String>>()?;
        map.insert(name, list);
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn i10(v: &[i64]) -> String {
        v.iter().map(|x| format!("{x:>10}")).collect()
    }

    fn sample() -> String {
        let mut s = String::from("    -1\n   151\nheader\n    -1\n    -1\n  2411\n");
        let xs = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 0.5, 0.0]];
        for (i, x) in xs.iter().enumerate() {
            s.push_str(&format!("{}\n", i10(&[i as i64 + 1, 0, 0, 11])));
            s.push_str(&format!("{:>25}{:>25}{:>25}\n", format!("{:.16E}", x[0]), format!("{:.16E}", x[1]), "0.0D+00"));
        }
        s.push_str("    -1\n    -1\n  2412\n");
        // A 6-node triangle (descriptor 92): I-DEAS lists corner, middle, corner, ...
        s.push_str(&format!("{}\n{}\n", i10(&[7, 92, 1, 1, 5, 6]), i10(&[1, 4, 2, 5, 3, 6])));
        // A beam (descriptor 21): an orientation line before its nodes.
        s.push_str(&format!("{}\n{}\n{}\n", i10(&[3, 21, 1, 1, 5, 2]), i10(&[0, 0, 0]), i10(&[1, 2])));
        s.push_str("    -1\n    -1\n  2467\n");
        s.push_str(&format!("{}\nBASE_LINE_LONG\n", i10(&[1, 0, 0, 0, 0, 0, 0, 3])));
        s.push_str(&format!("{}{:20}{}\n{}\n", i10(&[8, 3]), "", i10(&[7, 1]), i10(&[7, 2])));
        s.push_str(&format!("{}\n1BAD\n{}\n", i10(&[2, 0, 0, 0, 0, 0, 0, 1]), i10(&[8, 7])));
        s.push_str("    -1\n");
        s
    }

    #[test]
    fn reads_nodes_elements_and_groups_as_the_converter() {
        let m = read(&sample(), "t.unv", false).unwrap();
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N6"]);
        assert_eq!(m.coords[4], [0.5, 0.5, 0.0]);
        // SEG2 (code 1) before TRIA6 (code 3).
        assert_eq!(m.cell_names, ["M3", "M7"]);
        assert_eq!(m.cell_types, [CellType::Seg2, CellType::Tria6]);
        assert_eq!(m.cells[1], [0, 1, 2, 3, 4, 5]);
        // Names cut to 8 characters; a name not starting with a letter makes no group.
        assert_eq!(m.cell_groups.keys().collect::<Vec<_>>(), ["BASE_LIN"]);
        assert_eq!(m.cell_groups["BASE_LIN"], [0]);
        assert_eq!(m.node_groups["BASE_LIN"], [0, 1]);
        let c = read(&sample(), "t.unv", true).unwrap();
        assert_eq!(c.node_groups["COUL_11"].len(), 6);
        assert_eq!(c.cell_groups["COUL_5"], [1, 0]);
    }

    #[test]
    fn trace_lines_are_chains_of_segments_and_systems_of_dataset_18_are_skipped() {
        // A Cartesian system (18: a header, a name, two lines of reals) before the nodes; a trace line
        // 1-2, pen lifted, 3-4-5 after the elements.
        let system = format!(
            "    -1\n    18\n{}\nCS\n{}\n{}\n    -1\n",
            i10(&[1, 0, 0, 1, 1]),
            "0.0 ".repeat(6),
            "0.0 ".repeat(3)
        );
        let trace = format!("    -1\n    82\n{}\nNONE\n{}\n    -1\n", i10(&[1, 6, 4]), i10(&[1, 2, 0, 3, 4, 5]));
        let m = read(&format!("{system}{}{trace}", sample()), "t.unv", true).unwrap();
        assert_eq!(m.cell_names, ["M3", "M8", "M9", "M10", "M7"]);
        assert_eq!(&m.cells[1..4], [[0, 1], [2, 3], [3, 4]]);
        assert_eq!(m.cell_groups["COUL_4"], [1, 2, 3]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read(&sample().replace(&i10(&[7, 92, 1, 1, 5, 6]), &i10(&[7, 93, 1, 1, 5, 6])), "t.unv", false)
            .unwrap_err();
        assert!(e.starts_with("t.unv:22: element 7: TRIA9 cells"), "{e}");
        let e = read(&sample().replace(&i10(&[1, 2])[..], &i10(&[1, 99])), "t.unv", false).unwrap_err();
        assert!(e.contains("element 3: node 99 is not defined"), "{e}");
        assert!(read("hello\n", "x.unv", false).is_err());
    }
}
