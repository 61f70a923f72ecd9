//! Gmsh meshes (`.msh`, LIRE_MAILLAGE FORMAT='GMSH'), read as Code_Aster's converter (`pregms`,
//! `gmlelt`, `gmeelt`) turns them into its own mesh, for the ASCII formats 1 (`$NOD`/`$ELM`),
//! 2.x (`$MeshFormat 2.2 0 8`) and 4.x (`$MeshFormat 4.1 0 8`, which Code_Aster does not read;
//! here with the same conventions):
//!
//! - nodes keep the file's order, named `N<number>`, with three coordinates; nodes no cell uses are
//!   dropped (so is the centre of a 9-node quadrangle, read as a QUAD8, and of a 14-node pyramid);
//! - cells are numbered type by type in Gmsh's type order (1: SEG2, 2: TRIA3, ..., 19: PYRAM13),
//!   file order within a type, named `M<number>`, their nodes in Code_Aster's order;
//! - format 1: one group of cells `GM<physical>` per physical number, in order of appearance;
//! - formats 2 and 4: one group per `$PhysicalNames` entry, named by its first 8 characters, of
//!   the cells of that dimension one of whose tags (format 2: physical, elementary, ...; format 4:
//!   the physical tags of its entity) is the group's number; without `$PhysicalNames`, no group;
//! - a group of one POI1 cell is also a group of nodes (its node), of the same name.
//!
//! Errors name the file and line.

use super::{CellType, Mesh};
use std::collections::{BTreeMap, HashMap, HashSet};

/// One Gmsh element type: the Code_Aster type and, for Code_Aster's node `j`, the (0-based) position
/// of the Gmsh node it takes (`inigms`'s `nuconn`); `dim` is the element's dimension.
struct GmshType {
    cell: CellType,
    /// Nodes of the Gmsh element.
    nnodes: usize,
    dim: usize,
    from_gmsh: &'static [usize],
}

const ID: [usize; 27] =
    [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26];
const TETRA10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];
const HEXA27: [usize; 27] =
    [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 10, 12, 14, 15, 16, 18, 19, 17, 20, 21, 23, 24, 22, 25, 26];
const PENTA18: [usize; 18] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 8, 10, 11, 12, 14, 13, 15, 17, 16];
const PYRAM13: [usize; 13] = [0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12];

/// Gmsh's element types 1 to 19 (index + 1).
const TYPES: [GmshType; 19] = [
    GmshType { cell: CellType::Seg2, nnodes: 2, dim: 1, from_gmsh: &ID },
    GmshType { cell: CellType::Tria3, nnodes: 3, dim: 2, from_gmsh: &ID },
    GmshType { cell: CellType::Quad4, nnodes: 4, dim: 2, from_gmsh: &ID },
    GmshType { cell: CellType::Tetra4, nnodes: 4, dim: 3, from_gmsh: &ID },
    GmshType { cell: CellType::Hexa8, nnodes: 8, dim: 3, from_gmsh: &ID },
    GmshType { cell: CellType::Penta6, nnodes: 6, dim: 3, from_gmsh: &ID },
    GmshType { cell: CellType::Pyram5, nnodes: 5, dim: 3, from_gmsh: &ID },
    GmshType { cell: CellType::Seg3, nnodes: 3, dim: 1, from_gmsh: &ID },
    GmshType { cell: CellType::Tria6, nnodes: 6, dim: 2, from_gmsh: &ID },
    // The 9-node quadrangle is read as a QUAD8: its centre is dropped.
    GmshType { cell: CellType::Quad8, nnodes: 9, dim: 2, from_gmsh: &ID },
    GmshType { cell: CellType::Tetra10, nnodes: 10, dim: 3, from_gmsh: &TETRA10 },
    GmshType { cell: CellType::Hexa27, nnodes: 27, dim: 3, from_gmsh: &HEXA27 },
    GmshType { cell: CellType::Penta18, nnodes: 18, dim: 3, from_gmsh: &PENTA18 },
    // The 14-node pyramid is read as a PYRAM13: its centre is dropped.
    GmshType { cell: CellType::Pyram13, nnodes: 14, dim: 3, from_gmsh: &PYRAM13 },
    GmshType { cell: CellType::Poi1, nnodes: 1, dim: 0, from_gmsh: &ID },
    GmshType { cell: CellType::Quad8, nnodes: 8, dim: 2, from_gmsh: &ID },
    GmshType { cell: CellType::Hexa20, nnodes: 20, dim: 3, from_gmsh: &HEXA27 },
    GmshType { cell: CellType::Penta15, nnodes: 15, dim: 3, from_gmsh: &PENTA18 },
    GmshType { cell: CellType::Pyram13, nnodes: 13, dim: 3, from_gmsh: &PYRAM13 },
];

fn gmsh_type(code: i64) -> Option<&'static GmshType> {
    usize::try_from(code).ok().filter(|c| (1..=19).contains(c)).map(|c| &TYPES[c - 1])
}

/// One element as read: its number, Gmsh type (1-19), tags and nodes (Gmsh numbers).
struct Elem {
    num: i64,
    gtype: i64,
    tags: Vec<i64>,
    nodes: Vec<i64>,
    line: usize,
}

/// A physical group: dimension (None in format 1: any), number, name.
struct Physical {
    dim: Option<usize>,
    tag: i64,
    name: String,
}

/// The lines of the file with their numbers, skipping blank lines.
struct Lines<'a> {
    lines: Vec<(usize, &'a str)>,
    pos: usize,
    file: &'a str,
}

impl<'a> Lines<'a> {
    fn new(src: &'a str, file: &'a str) -> Lines<'a> {
        let lines = src.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty()).collect();
        Lines { lines, pos: 0, file }
    }
    fn err(&self, line: usize, msg: impl std::fmt::Display) -> String {
        format!("{}:{line}: {msg}", self.file)
    }
    fn last_line(&self) -> usize {
        self.lines.last().map(|l| l.0).unwrap_or(1)
    }
    fn next(&mut self, what: &str) -> Result<(usize, &'a str), String> {
        let l = self
            .lines
            .get(self.pos)
            .copied()
            .ok_or_else(|| self.err(self.last_line(), format!("end of file in {what}")))?;
        self.pos += 1;
        Ok(l)
    }
    fn peek(&self) -> Option<(usize, &'a str)> {
        self.lines.get(self.pos).copied()
    }
    /// The next line's whitespace-separated fields parsed as numbers.
    fn numbers<T: std::str::FromStr>(&mut self, what: &str) -> Result<(usize, Vec<T>), String> {
        let (n, l) = self.next(what)?;
        let v = l
            .split_whitespace()
            .map(|w| w.parse::<T>().map_err(|_| self.err(n, format!("{what}: '{w}' is not a number"))))
            .collect::<Result<Vec<T>, String>>()?;
        Ok((n, v))
    }
    /// Skip to the line `end` (included).
    fn skip_to(&mut self, end: &str) -> Result<(), String> {
        loop {
            let (_, l) = self.next(end)?;
            if l == end {
                return Ok(());
            }
        }
    }
    fn expect(&mut self, end: &str) -> Result<(), String> {
        let (n, l) = self.next(end)?;
        if l == end {
            Ok(())
        } else {
            Err(self.err(n, format!("'{end}' expected, found '{l}'")))
        }
    }
}

fn count(lines: &Lines, n: usize, v: &[i64], at: usize, what: &str) -> Result<usize, String> {
    v.get(at).and_then(|&c| usize::try_from(c).ok()).ok_or_else(|| lines.err(n, format!("{what}: a count is expected")))
}

/// Nodes of the file in file order: number and coordinates.
type Nodes = Vec<(i64, [f64; 3], usize)>;

fn read_v1(lines: &mut Lines) -> Result<(Nodes, Vec<Elem>, Vec<Physical>), String> {
    lines.expect("$NOD")?;
    let (n, v) = lines.numbers::<i64>("$NOD")?;
    let nn = count(lines, n, &v, 0, "$NOD")?;
    let nodes = read_node_lines(lines, nn)?;
    let (n, l) = lines.next("$ENDNOD")?;
    if l != "$ENDNOD" {
        return Err(lines.err(n, format!("'$ENDNOD' expected, found '{l}'")));
    }
    lines.expect("$ELM")?;
    let (n, v) = lines.numbers::<i64>("$ELM")?;
    let ne = count(lines, n, &v, 0, "$ELM")?;
    let mut elems = Vec::with_capacity(ne);
    let mut physicals: Vec<Physical> = Vec::new();
    let mut seen = HashSet::new();
    for _ in 0..ne {
        let (n, v) = lines.numbers::<i64>("$ELM")?;
        if v.len() < 5 {
            return Err(lines.err(n, "an element is: number, type, physical, elementary, node count, nodes"));
        }
        let nno = count(lines, n, &v, 4, "$ELM")?;
        if v.len() != 5 + nno {
            return Err(lines.err(n, format!("element {}: {nno} nodes announced, {} given", v[0], v.len() - 5)));
        }
        if seen.insert(v[2]) {
            physicals.push(Physical { dim: None, tag: v[2], name: format!("GM{}", v[2]) });
        }
        elems.push(Elem { num: v[0], gtype: v[1], tags: vec![v[2]], nodes: v[5..].to_vec(), line: n });
    }
    lines.expect("$ENDELM")?;
    Ok((nodes, elems, physicals))
}

fn read_node_lines(lines: &mut Lines, nn: usize) -> Result<Nodes, String> {
    let mut nodes = Vec::with_capacity(nn);
    for _ in 0..nn {
        let (n, l) = lines.next("the nodes")?;
        let w: Vec<&str> = l.split_whitespace().collect();
        if w.len() < 4 {
            return Err(lines.err(n, "a node is: number, x, y, z"));
        }
        let num = w[0].parse::<i64>().map_err(|_| lines.err(n, format!("'{}' is not a node number", w[0])))?;
        let mut x = [0.0; 3];
        for k in 0..3 {
            x[k] = w[1 + k].parse::<f64>().map_err(|_| lines.err(n, format!("'{}' is not a coordinate", w[1 + k])))?;
        }
        nodes.push((num, x, n));
    }
    Ok(nodes)
}

/// `"name"` (or a bare word) of a `$PhysicalNames` line, as Code_Aster keeps it: 8 characters.
fn physical_name(rest: &str) -> String {
    let rest = rest.trim();
    let inner = match rest.strip_prefix('"') {
        Some(r) => r.split('"').next().unwrap_or(r),
        None => rest.split_whitespace().next().unwrap_or(""),
    };
    let mut name: String = inner.chars().take(8).collect();
    if let Some(q) = name.find('"') {
        name.truncate(q);
    }
    name.trim_end().to_string()
}

fn read_physical_names(lines: &mut Lines) -> Result<Vec<Physical>, String> {
    let (n, v) = lines.numbers::<i64>("$PhysicalNames")?;
    let np = count(lines, n, &v, 0, "$PhysicalNames")?;
    let mut out = Vec::with_capacity(np);
    for _ in 0..np {
        let (n, l) = lines.next("$PhysicalNames")?;
        let mut w = l.splitn(3, char::is_whitespace);
        let dim = w.next().and_then(|d| d.parse::<usize>().ok());
        let tag = w.next().and_then(|t| t.trim().parse::<i64>().ok());
        let (Some(dim), Some(tag)) = (dim, tag) else {
            return Err(lines.err(n, "a physical name is: dimension, number, \"name\""));
        };
        out.push(Physical { dim: Some(dim), tag, name: physical_name(w.next().unwrap_or("")) });
    }
    lines.expect("$EndPhysicalNames")?;
    Ok(out)
}

fn read_v2_nodes(lines: &mut Lines) -> Result<Nodes, String> {
    let (n, v) = lines.numbers::<i64>("$Nodes")?;
    let nn = count(lines, n, &v, 0, "$Nodes")?;
    let nodes = read_node_lines(lines, nn)?;
    lines.expect("$EndNodes")?;
    Ok(nodes)
}

fn read_v2_elements(lines: &mut Lines) -> Result<Vec<Elem>, String> {
    let (n, v) = lines.numbers::<i64>("$Elements")?;
    let ne = count(lines, n, &v, 0, "$Elements")?;
    let mut elems = Vec::with_capacity(ne);
    for _ in 0..ne {
        let (n, v) = lines.numbers::<i64>("$Elements")?;
        if v.len() < 3 {
            return Err(lines.err(n, "an element is: number, type, tag count, tags, nodes"));
        }
        let t = gmsh_type(v[1])
            .ok_or_else(|| lines.err(n, format!("element {}: Gmsh type {} is not supported", v[0], v[1])))?;
        let nt = count(lines, n, &v, 2, "$Elements")?;
        if v.len() != 3 + nt + t.nnodes {
            return Err(lines.err(n, format!("element {}: {} values, expected {}", v[0], v.len(), 3 + nt + t.nnodes)));
        }
        elems.push(Elem { num: v[0], gtype: v[1], tags: v[3..3 + nt].to_vec(), nodes: v[3 + nt..].to_vec(), line: n });
    }
    lines.expect("$EndElements")?;
    Ok(elems)
}

/// Format 4: the physical tags of each entity (dimension, tag).
fn read_v4_entities(lines: &mut Lines, v41: bool) -> Result<HashMap<(usize, i64), Vec<i64>>, String> {
    let (n, v) = lines.numbers::<i64>("$Entities")?;
    if v.len() < 4 {
        return Err(lines.err(n, "$Entities: the counts of points, curves, surfaces and volumes are expected"));
    }
    let mut out = HashMap::new();
    for dim in 0..4 {
        let k = count(lines, n, &v, dim, "$Entities")?;
        for _ in 0..k {
            let (n, w) = lines.numbers::<f64>("$Entities")?;
            // A point is `tag x y z` (4.1) or `tag box(6)` (4.0); the others `tag box(6)`; then the
            // physical tags' count and the tags.
            let at = if dim == 0 && v41 { 4 } else { 7 };
            let np =
                w.get(at).copied().filter(|x| *x >= 0.0).ok_or_else(|| lines.err(n, "$Entities: bad entity"))? as usize;
            let phys = w.get(at + 1..at + 1 + np).ok_or_else(|| lines.err(n, "$Entities: bad physical tags"))?;
            out.insert((dim, w[0] as i64), phys.iter().map(|x| *x as i64).collect());
        }
    }
    lines.expect("$EndEntities")?;
    Ok(out)
}

fn read_v4_nodes(lines: &mut Lines, v41: bool) -> Result<Nodes, String> {
    let (n, v) = lines.numbers::<i64>("$Nodes")?;
    let blocks = count(lines, n, &v, 0, "$Nodes")?;
    let mut nodes = Vec::with_capacity(count(lines, n, &v, 1, "$Nodes")?);
    for _ in 0..blocks {
        let (n, b) = lines.numbers::<i64>("$Nodes")?;
        let k = count(lines, n, &b, 3, "$Nodes")?;
        let parametric = b.get(2).copied().unwrap_or(0) != 0;
        if v41 {
            let mut tags = Vec::with_capacity(k);
            for _ in 0..k {
                let (n, t) = lines.numbers::<i64>("$Nodes")?;
                tags.push((*t.first().ok_or_else(|| lines.err(n, "a node number is expected"))?, n));
            }
            for (tag, _) in tags {
                let (n, x) = lines.numbers::<f64>("$Nodes")?;
                if x.len() < 3 || (!parametric && x.len() != 3) {
                    return Err(lines.err(n, "three coordinates are expected"));
                }
                nodes.push((tag, [x[0], x[1], x[2]], n));
            }
        } else {
            nodes.extend(read_node_lines(lines, k)?);
        }
    }
    lines.expect("$EndNodes")?;
    Ok(nodes)
}

fn read_v4_elements(
    lines: &mut Lines,
    v41: bool,
    entities: &HashMap<(usize, i64), Vec<i64>>,
) -> Result<Vec<Elem>, String> {
    let (n, v) = lines.numbers::<i64>("$Elements")?;
    let blocks = count(lines, n, &v, 0, "$Elements")?;
    let mut elems = Vec::with_capacity(count(lines, n, &v, 1, "$Elements")?);
    for _ in 0..blocks {
        let (n, b) = lines.numbers::<i64>("$Elements")?;
        if b.len() < 4 {
            return Err(lines.err(n, "an element block is: dimension, entity, type, count"));
        }
        let (dim, tag) = if v41 { (b[0], b[1]) } else { (b[1], b[0]) };
        let gtype = b[2];
        let t = gmsh_type(gtype).ok_or_else(|| lines.err(n, format!("Gmsh element type {gtype} is not supported")))?;
        let k = count(lines, n, &b, 3, "$Elements")?;
        let tags = entities.get(&(dim.max(0) as usize, tag)).cloned().unwrap_or_default();
        for _ in 0..k {
            let (n, e) = lines.numbers::<i64>("$Elements")?;
            if e.len() != 1 + t.nnodes {
                return Err(lines.err(n, format!("{} nodes expected for Gmsh type {gtype}", t.nnodes)));
            }
            elems.push(Elem { num: e[0], gtype, tags: tags.clone(), nodes: e[1..].to_vec(), line: n });
        }
    }
    lines.expect("$EndElements")?;
    Ok(elems)
}

/// Read a `.msh` text; `file` names it in errors (`file:line: message`).
pub fn read(src: &str, file: &str) -> Result<Mesh, String> {
    let mut lines = Lines::new(src, file);
    let (nodes, elems, physicals) = match lines.peek() {
        Some((_, "$NOD")) => read_v1(&mut lines)?,
        Some((_, "$MeshFormat")) => {
            lines.next("$MeshFormat")?;
            let (n, l) = lines.next("$MeshFormat")?;
            let w: Vec<&str> = l.split_whitespace().collect();
            let version: f64 =
                w.first().and_then(|v| v.parse().ok()).ok_or_else(|| lines.err(n, "a version is expected"))?;
            if w.get(1).copied() != Some("0") {
                return Err(lines.err(n, "binary .msh files are not supported (write them as ASCII)"));
            }
            if !(2.0..5.0).contains(&version) {
                return Err(lines.err(n, format!("Gmsh format {version} is not supported (1, 2 and 4 are)")));
            }
            lines.expect("$EndMeshFormat")?;
            let v4 = version >= 4.0;
            let v41 = version >= 4.1;
            let (mut nodes, mut elems, mut physicals, mut entities) = (None, None, Vec::new(), HashMap::new());
            while let Some((n, l)) = lines.peek() {
                lines.next("a section")?;
                match l {
                    "$PhysicalNames" => physicals = read_physical_names(&mut lines)?,
                    "$Entities" if v4 => entities = read_v4_entities(&mut lines, v41)?,
                    "$Nodes" if v4 => nodes = Some(read_v4_nodes(&mut lines, v41)?),
                    "$Nodes" => nodes = Some(read_v2_nodes(&mut lines)?),
                    "$Elements" if v4 => elems = Some(read_v4_elements(&mut lines, v41, &entities)?),
                    "$Elements" => elems = Some(read_v2_elements(&mut lines)?),
                    s if s.starts_with('$') && !s.starts_with("$End") => {
                        let end = format!("$End{}", &s[1..]);
                        lines.skip_to(&end)?;
                    }
                    _ => return Err(lines.err(n, format!("a section ($Nodes, $Elements, ...) expected, found '{l}'"))),
                }
            }
            let nodes = nodes.ok_or_else(|| lines.err(lines.last_line(), "no $Nodes section"))?;
            let elems = elems.ok_or_else(|| lines.err(lines.last_line(), "no $Elements section"))?;
            (nodes, elems, physicals)
        }
        Some((n, l)) => {
            return Err(lines.err(n, format!("not a Gmsh mesh: '$MeshFormat' or '$NOD' expected, found '{l}'")))
        }
        None => return Err(lines.err(1, "empty file")),
    };
    build(&lines, nodes, elems, &physicals)
}

fn build(lines: &Lines, nodes: Nodes, elems: Vec<Elem>, physicals: &[Physical]) -> Result<Mesh, String> {
    let mut index: HashMap<i64, usize> = HashMap::with_capacity(nodes.len());
    for (i, (num, _, n)) in nodes.iter().enumerate() {
        if index.insert(*num, i).is_some() {
            return Err(lines.err(*n, format!("node {num} is defined twice")));
        }
    }
    // The nodes each element keeps, as file positions; the nodes used.
    let mut used = vec![false; nodes.len()];
    let mut kept: Vec<Vec<usize>> = Vec::with_capacity(elems.len());
    for e in &elems {
        let t = gmsh_type(e.gtype)
            .ok_or_else(|| lines.err(e.line, format!("element {}: Gmsh type {} is not supported", e.num, e.gtype)))?;
        if e.nodes.len() < t.cell.nnodes() {
            return Err(lines.err(e.line, format!("element {}: too few nodes for Gmsh type {}", e.num, e.gtype)));
        }
        let mut k = Vec::with_capacity(t.cell.nnodes());
        for &g in &t.from_gmsh[..t.cell.nnodes()] {
            let num = e.nodes[g];
            let i = *index
                .get(&num)
                .ok_or_else(|| lines.err(e.line, format!("element {}: node {num} is not defined", e.num)))?;
            used[i] = true;
            k.push(i);
        }
        kept.push(k);
    }
    let mut mesh = Mesh { dim: 3, named_nodes: true, ..Default::default() };
    let mut renum = vec![usize::MAX; nodes.len()];
    for (i, (num, x, _)) in nodes.iter().enumerate() {
        if used[i] {
            renum[i] = mesh.coords.len();
            mesh.coords.push(*x);
            mesh.node_names.push(format!("N{num}"));
        }
    }
    // Cells type by type in Gmsh's order, file order within a type.
    let mut cell_of = vec![usize::MAX; elems.len()];
    let mut names = HashSet::new();
    for code in 1..=19 {
        let t = &TYPES[code as usize - 1];
        for (k, e) in elems.iter().enumerate().filter(|(_, e)| e.gtype == code) {
            let name = format!("M{}", e.num);
            if !names.insert(name.clone()) {
                return Err(lines.err(e.line, format!("element {} is defined twice", e.num)));
            }
            cell_of[k] = mesh.cells.len();
            mesh.cells.push(kept[k].iter().map(|&i| renum[i]).collect());
            mesh.cell_types.push(t.cell);
            mesh.cell_names.push(name);
        }
    }
    let mut cell_groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for p in physicals {
        let members: Vec<usize> = elems
            .iter()
            .enumerate()
            .filter(|(_, e)| e.tags.contains(&p.tag))
            .filter(|(_, e)| p.dim.is_none_or(|d| gmsh_type(e.gtype).is_some_and(|t| t.dim == d)))
            .map(|(k, _)| cell_of[k])
            .collect();
        if members.is_empty() {
            continue;
        }
        if p.name.is_empty() {
            return Err(lines.err(1, format!("physical group {} has an empty name", p.tag)));
        }
        if cell_groups.contains_key(&p.name) {
            return Err(
                lines.err(1, format!("two physical groups are named {} (names are cut to 8 characters)", p.name))
            );
        }
        if let [c] = members[..] {
            if mesh.cell_types[c] == CellType::Poi1 {
                mesh.node_groups.insert(p.name.clone(), vec![mesh.cells[c][0]]);
            }
        }
        cell_groups.insert(p.name.clone(), members);
    }
    mesh.cell_groups = cell_groups;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    const V2: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n0 7 \"PointA\"\n1 5 \"Bottom_edge\"\n2 9 \"Plate\"\n$EndPhysicalNames\n\
        $Nodes\n6\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 2 0 0\n9 5 5 5\n$EndNodes\n\
        $Elements\n5\n1 15 2 7 1 1\n2 1 2 5 1 1 2\n3 1 2 5 1 2 5\n4 3 2 9 3 1 2 3 4\n5 2 2 9 3 2 5 3\n$EndElements\n";

    #[test]
    fn format_2_reads_as_code_aster_converts_it() {
        let m = read(V2, "t.msh").unwrap();
        // Node 9 is used by no cell: dropped.
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5"]);
        assert_eq!(m.dim, 3);
        // Type order: SEG2 (1), TRIA3 (2), QUAD4 (3), POI1 (15).
        assert_eq!(m.cell_names, ["M2", "M3", "M5", "M4", "M1"]);
        assert_eq!(m.cell_types, [CellType::Seg2, CellType::Seg2, CellType::Tria3, CellType::Quad4, CellType::Poi1]);
        assert_eq!(m.cells[2], [1, 4, 2]);
        // Names cut to 8 characters; dimensions checked; a one-POI1 group is also a node group.
        let g: Vec<&String> = m.cell_groups.keys().collect();
        assert_eq!(g, ["Bottom_e", "Plate", "PointA"]);
        assert_eq!(m.cell_groups["Plate"], [3, 2]);
        assert_eq!(m.cell_groups["Bottom_e"], [0, 1]);
        assert_eq!(m.node_groups["PointA"], [0]);
        assert_eq!(m.node_groups.len(), 1);
    }

    #[test]
    fn format_1_groups_by_physical_number() {
        let src = "$NOD\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$ENDNOD\n$ELM\n2\n1 2 4 1 3 1 2 3\n2 1 3 2 2 1 2\n$ENDELM\n";
        let m = read(src, "t.msh").unwrap();
        assert_eq!(m.cell_names, ["M2", "M1"]);
        assert_eq!(m.cell_groups["GM4"], [1]);
        assert_eq!(m.cell_groups["GM3"], [0]);
    }

    #[test]
    fn format_4_takes_the_physical_tags_of_entities() {
        let src = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 3 \"S\"\n$EndPhysicalNames\n\
            $Entities\n0 0 1 0\n1 0 0 0 1 1 0 1 3 0\n$EndEntities\n\
            $Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
            $Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 1 3 4\n$EndElements\n";
        let m = read(src, "t.msh").unwrap();
        assert_eq!(m.nnodes(), 4);
        assert_eq!(m.cell_names, ["M1", "M2"]);
        assert_eq!(m.cell_groups["S"], [0, 1]);
    }

    #[test]
    fn quadratic_cells_take_code_aster_node_order() {
        // A 10-node tetrahedron: Gmsh's 9th and 10th nodes swap.
        let mut src = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n");
        for i in 1..=10 {
            src.push_str(&format!("{i} {i} 0 0\n"));
        }
        src.push_str("$EndNodes\n$Elements\n1\n1 11 0 1 2 3 4 5 6 7 8 9 10\n$EndElements\n");
        let m = read(&src, "t.msh").unwrap();
        assert_eq!(m.cells[0], [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n", "b.msh").unwrap_err();
        assert_eq!(e, "b.msh:2: binary .msh files are not supported (write them as ASCII)");
        let e = read(&V2.replace("5 2 2 9 3 2 5 3", "5 2 2 9 3 2 5 77"), "t.msh").unwrap_err();
        assert_eq!(e, "t.msh:25: element 5: node 77 is not defined");
        let e = read(&V2.replace("4 3 2 9 3", "4 31 2 9 3"), "t.msh").unwrap_err();
        assert!(e.starts_with("t.msh:24: element 4: Gmsh type 31 is not supported"), "{e}");
        assert!(read("hello\n", "x.msh").unwrap_err().contains("not a Gmsh mesh"));
    }
}
