//! Cast3M (GIBI) meshes saved in text (`SAUVER FORMAT`, `.mgib`; LIRE_MAILLAGE FORMAT='GIBI'), read
//! as Code_Aster's converter (`gilir2`, `gilig0`-`gilig3`, `gilio2`, `gidoma`, `giecas`, `giecma`)
//! turns them into its own mesh:
//!
//! - records `ENREGISTREMENT DE TYPE n`: 4 gives the level (which sets the width of integer fields:
//!   16 per line of 5 characters at level 3, else 10 of 8) and the dimension; 2 a stack (`PILE`): 1
//!   the meshes (simple ones: one cell type, colours and connectivity; composite ones: a list of
//!   meshes), 32 the points (named points, then the coordinate of each point), 33 the coordinates;
//!   0, the older layout, named points and coordinates at once; 5 ends the file;
//! - the nodes are the coordinates some point uses, in increasing order, named `N<coordinate>`;
//! - the cells are those of the named meshes and of the parts of named composite meshes, in stack
//!   order, named `M<rank>` by their rank among all the cells of the stack; a cell identical to an
//!   earlier one (same nodes in the same order) is that cell;
//! - every named mesh is a group of cells of its name, every named point a group of one node; names
//!   starting with `#` are Cast3M's own and make no group.
//!
//! Errors name the file and line.

use super::{CellType, Mesh};
use std::collections::{BTreeMap, HashMap, HashSet};

/// Cast3M element type → Code_Aster type and, for Code_Aster node `j`, the (0-based) Cast3M node
/// (`giinco`).
fn element_type(itypel: i64) -> Option<(CellType, &'static [usize])> {
    use CellType::*;
    Some(match itypel {
        1 => (Poi1, &[0]),
        2 => (Seg2, &[0, 1]),
        3 => (Seg3, &[0, 2, 1]),
        4 => (Tria3, &[0, 1, 2]),
        6 => (Tria6, &[0, 2, 4, 1, 3, 5]),
        8 => (Quad4, &[0, 1, 2, 3]),
        10 => (Quad8, &[0, 2, 4, 6, 1, 3, 5, 7]),
        11 => (Quad9, &[0, 2, 4, 6, 1, 3, 5, 7, 8]),
        14 => (Hexa8, &[0, 1, 2, 3, 4, 5, 6, 7]),
        15 => (Hexa20, &[0, 2, 4, 6, 12, 14, 16, 18, 1, 3, 5, 7, 8, 9, 10, 11, 13, 15, 17, 19]),
        33 => (
            Hexa27,
            &[0, 2, 4, 6, 12, 14, 16, 18, 1, 3, 5, 7, 8, 9, 10, 11, 13, 15, 17, 19, 24, 20, 21, 22, 23, 25, 26],
        ),
        16 => (Penta6, &[0, 1, 2, 3, 4, 5]),
        17 => (Penta15, &[0, 2, 4, 9, 11, 13, 1, 3, 5, 6, 7, 8, 10, 12, 14]),
        23 => (Tetra4, &[0, 1, 2, 3]),
        24 => (Tetra10, &[0, 2, 4, 9, 1, 3, 5, 6, 7, 8]),
        25 => (Pyram5, &[0, 1, 2, 3, 4]),
        26 => (Pyram13, &[0, 2, 4, 6, 12, 1, 3, 5, 7, 8, 9, 10, 11]),
        _ => return None,
    })
}

/// A mesh object of stack 1.
struct Object {
    /// Parts (1-based object numbers) of a composite mesh; empty for a simple one.
    parts: Vec<usize>,
    itypel: i64,
    nbno: usize,
    /// Connectivity (point numbers), `nbno` per cell.
    conn: Vec<i64>,
    line: usize,
}

struct Reader<'a> {
    file: &'a str,
    lines: Vec<&'a str>,
    pos: usize,
    /// Integer fields: width and count per line.
    int_width: usize,
    ints_per_line: usize,
}

impl<'a> Reader<'a> {
    fn err(&self, line: usize, msg: impl std::fmt::Display) -> String {
        format!("{}:{}: {msg}", self.file, line + 1)
    }
    fn next(&mut self, what: &str) -> Result<(usize, &'a str), String> {
        let k = self.pos;
        let l = self
            .lines
            .get(k)
            .copied()
            .ok_or_else(|| self.err(k.saturating_sub(1), format!("end of file in {what}")))?;
        self.pos += 1;
        Ok((k, l))
    }
    /// A fixed-width field of a line (blanks read as 0 for numbers).
    fn field(line: &str, start: usize, width: usize) -> &str {
        line.get(start.min(line.len())..(start + width).min(line.len())).unwrap_or("").trim()
    }
    fn int(&self, line: (usize, &str), start: usize, width: usize, what: &str) -> Result<i64, String> {
        let f = Self::field(line.1, start, width);
        if f.is_empty() {
            return Ok(0);
        }
        f.parse::<i64>().map_err(|_| self.err(line.0, format!("{what}: '{f}' is not an integer")))
    }
    /// `n` integers, `per_line` per line, field `k` of a line at `first + k * stride`, `width` wide.
    fn ints_fmt(
        &mut self,
        n: usize,
        (first, stride, width): (usize, usize, usize),
        per_line: usize,
        what: &str,
    ) -> Result<Vec<i64>, String> {
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let l = self.next(what)?;
            for k in 0..per_line.min(n - out.len()) {
                out.push(self.int(l, first + k * stride, width, what)?);
            }
        }
        Ok(out)
    }
    /// `n` integers in the file's integer layout (`10(i8)` or, at level 3, `16(i5)`).
    fn ints(&mut self, n: usize, what: &str) -> Result<Vec<i64>, String> {
        let (w, p) = (self.int_width, self.ints_per_line);
        self.ints_fmt(n, (0, w, w), p, what)
    }
    /// `n` names, 8 per line (`8(1x,a8)`).
    fn names(&mut self, n: usize, what: &str) -> Result<Vec<String>, String> {
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let (_, l) = self.next(what)?;
            for k in 0..8.min(n - out.len()) {
                out.push(Self::field(l, 1 + 9 * k, 8).to_string());
            }
        }
        Ok(out)
    }
    /// `n` reals, 3 per line (`3(1x,d21.14)`).
    fn reals(&mut self, n: usize, what: &str) -> Result<Vec<f64>, String> {
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let (k, l) = self.next(what)?;
            for j in 0..3.min(n - out.len()) {
                let f = Self::field(l, 1 + 22 * j, 21);
                let v = if f.is_empty() { Some(0.0) } else { f.replace(['D', 'd'], "E").parse::<f64>().ok() };
                out.push(v.ok_or_else(|| self.err(k, format!("{what}: '{f}' is not a real")))?);
            }
        }
        Ok(out)
    }
}

/// Read a `.mgib` text; `file` names it in errors (`file:line: message`).
pub fn read(src: &str, file: &str) -> Result<Mesh, String> {
    let mut r = Reader { file, lines: src.lines().collect(), pos: 0, int_width: 8, ints_per_line: 10 };
    let mut level = 0i64;
    let mut dim = 0usize;
    let mut objects: Vec<Object> = Vec::new();
    let mut object_names: Vec<(String, usize)> = Vec::new();
    let mut point_names: Vec<(String, i64)> = Vec::new();
    let mut indirect: Option<Vec<i64>> = None;
    let mut coords: Option<Vec<f64>> = None;
    let mut old_layout = false;
    let mut ended = false;
    while r.pos < r.lines.len() {
        let (k, l) = r.next("a record")?;
        if Reader::field(l, 1, 14) != "ENREGISTREMENT" || Reader::field(l, 19, 4) != "TYPE" {
            continue;
        }
        match Reader::field(l, 26, 1) {
            "4" => {
                let line = r.next("the level")?;
                level = r.int(line, 7, 4, "NIVEAU")?;
                dim = usize::try_from(r.int(line, 39, 4, "DIMENSION")?).unwrap_or(0);
                if level == 3 {
                    (r.int_width, r.ints_per_line) = (5, 16);
                }
                r.next("the density")?;
            }
            "7" => {
                r.next("a record of type 7")?;
                r.next("a record of type 7")?;
            }
            "5" => {
                ended = true;
                break;
            }
            "2" => {
                let line = r.next("a stack header")?;
                let w = if level <= 6 { 5 } else { 8 };
                let stack = r.int(line, 12, 4, "PILE NUMERO")?;
                let named = usize::try_from(r.int(line, 34, w, "NBRE OBJETS NOMMES")?).unwrap_or(0);
                let count = usize::try_from(r.int(line, 34 + w + 11, w, "NBRE OBJETS")?).unwrap_or(0);
                match stack {
                    0 => {
                        old_layout = true;
                        let names = r.names(named, "named points")?;
                        let nums = r.ints(named, "named points")?;
                        point_names = names.into_iter().zip(nums).collect();
                        coords = Some(r.reals(count * (dim + 1), "coordinates")?);
                        indirect.get_or_insert_with(|| (1..=count as i64).collect());
                    }
                    32 if !old_layout => {
                        let names = r.names(named, "named points")?;
                        let nums = r.ints(named, "named points")?;
                        let n = r.ints(1, "the number of points")?[0];
                        if n as usize != count {
                            return Err(r.err(r.pos - 1, format!("{n} points announced, {count} expected")));
                        }
                        let ind = r.ints(count, "the points' coordinates")?;
                        point_names = names
                            .into_iter()
                            .zip(nums)
                            .map(|(name, p)| {
                                let c = usize::try_from(p - 1).ok().and_then(|i| ind.get(i)).copied();
                                c.map(|c| (name.clone(), c))
                                    .ok_or_else(|| r.err(k, format!("point {name}: bad number {p}")))
                            })
                            .collect::<Result<_, String>>()?;
                        indirect = Some(ind);
                    }
                    33 => {
                        let n = r.ints_fmt(1, (1, 8, 7), 1, "the number of coordinates")?[0];
                        coords = Some(r.reals(usize::try_from(n).unwrap_or(0), "coordinates")?);
                    }
                    1 => {
                        let names = r.names(named, "named meshes")?;
                        let nums = if level == 3 {
                            r.ints_fmt(named, (1, 5, 4), 16, "named meshes")?
                        } else {
                            r.ints_fmt(named, (1, 8, 7), 10, "named meshes")?
                        };
                        for (name, n) in names.into_iter().zip(nums) {
                            let n = usize::try_from(n).ok().filter(|n| (1..=count).contains(n));
                            let n = n.ok_or_else(|| r.err(k, format!("mesh {name}: bad object number")))?;
                            object_names.push((name, n));
                        }
                        for _ in 0..count {
                            objects.push(read_object(&mut r)?);
                        }
                    }
                    _ => {}
                }
            }
            _ => {}
        }
    }
    if !ended && objects.is_empty() {
        return Err(format!("{file}: no 'ENREGISTREMENT DE TYPE' record: not a Cast3M (GIBI) file"));
    }
    let coords = coords.ok_or_else(|| format!("{file}: no coordinates (stack 33)"))?;
    let indirect = indirect.ok_or_else(|| format!("{file}: no points (stack 32)"))?;
    build(&r, dim, &coords, &indirect, &objects, &object_names, &point_names)
}

fn read_object(r: &mut Reader) -> Result<Object, String> {
    let head = r.ints(5, "a mesh header")?;
    let line = r.pos - 1;
    let (itypel, nbsoob, nbref, nbno, nbele) = (head[0], head[1], head[2], head[3], head[4]);
    let count = |v: i64| usize::try_from(v).map_err(|_| r.err(line, "a negative count"));
    let (nbsoob, nbref, nbno, nbele) = (count(nbsoob)?, count(nbref)?, count(nbno)?, count(nbele)?);
    if itypel == 0 && nbsoob == 0 {
        return Err(r.err(line, "a mesh with neither cells nor parts"));
    }
    if itypel != 0 && element_type(itypel).is_none() {
        return Err(r.err(line, format!("Cast3M element type {itypel} is not supported")));
    }
    let mut parts = Vec::new();
    let mut conn = Vec::new();
    if nbsoob > 0 {
        parts = r.ints(nbsoob, "the parts of a mesh")?.into_iter().map(|p| p.max(0) as usize).collect();
        r.ints(nbref, "references")?;
    } else {
        r.ints(nbref, "references")?;
        if nbele > 0 {
            r.ints(nbele, "colours")?;
            conn = r.ints(nbele * nbno, "connectivity")?;
        }
    }
    Ok(Object { parts, itypel, nbno, conn, line })
}

fn build(
    r: &Reader,
    dim: usize,
    coords: &[f64],
    indirect: &[i64],
    objects: &[Object],
    object_names: &[(String, usize)],
    point_names: &[(String, i64)],
) -> Result<Mesh, String> {
    if !(2..=3).contains(&dim) {
        return Err(format!("{}: dimension {dim}: only 2D and 3D meshes are supported", r.file));
    }
    let npoints = coords.len() / (dim + 1);
    // Nodes: the coordinates some point uses, in increasing order.
    let mut used: Vec<i64> = indirect.to_vec();
    used.sort_unstable();
    used.dedup();
    let mut mesh = Mesh { dim, named_nodes: true, ..Default::default() };
    let mut node_of: HashMap<i64, usize> = HashMap::with_capacity(used.len());
    for c in used {
        let i = usize::try_from(c - 1).ok().filter(|&i| i < npoints);
        let i = i.ok_or_else(|| format!("{}: point coordinate {c} beyond the {npoints} coordinates", r.file))?;
        let mut x = [0.0; 3];
        x[..dim].copy_from_slice(&coords[i * (dim + 1)..i * (dim + 1) + dim]);
        node_of.insert(c, mesh.coords.len());
        mesh.coords.push(x);
        mesh.node_names.push(format!("N{c}"));
    }
    // The meshes whose cells are kept: the named ones and the parts of named composites.
    let mut kept: HashSet<usize> = HashSet::new();
    for &(_, n) in object_names {
        kept.insert(n);
        for &p in &objects[n - 1].parts {
            kept.insert(p);
        }
    }
    // Every cell of the stack by rank; identical cells share the first kept one.
    let mut first_of: HashMap<&[i64], usize> = HashMap::new();
    let mut cell_of_rank: Vec<Option<usize>> = Vec::new();
    let mut rank_start = vec![0usize; objects.len() + 1];
    for (i, o) in objects.iter().enumerate() {
        let nbele = if o.parts.is_empty() && o.nbno > 0 { o.conn.len() / o.nbno } else { 0 };
        rank_start[i + 1] = rank_start[i] + nbele;
        if nbele == 0 {
            continue;
        }
        let (t, from) = element_type(o.itypel).expect("checked on reading");
        if o.nbno != from.len() {
            return Err(r.err(o.line, format!("{} cells of {} nodes, {} expected", t.name(), o.nbno, from.len())));
        }
        for (e, cell) in o.conn.chunks(o.nbno).enumerate() {
            let rank = rank_start[i] + e;
            if !kept.contains(&(i + 1)) {
                cell_of_rank.push(None);
                continue;
            }
            if let Some(&c) = first_of.get(cell) {
                cell_of_rank.push(Some(c));
                continue;
            }
            let mut nodes = Vec::with_capacity(from.len());
            for &g in from {
                let p = cell[g];
                let c = usize::try_from(p - 1).ok().and_then(|k| indirect.get(k)).copied();
                let c = c.ok_or_else(|| r.err(o.line, format!("cell {}: point {p} is not defined", rank + 1)))?;
                nodes.push(node_of[&c]);
            }
            first_of.insert(cell, mesh.cells.len());
            cell_of_rank.push(Some(mesh.cells.len()));
            mesh.cells.push(nodes);
            mesh.cell_types.push(t);
            mesh.cell_names.push(format!("M{}", rank + 1));
        }
    }
    for (name, c) in point_names {
        if name.starts_with('#') || name.is_empty() {
            continue;
        }
        let n = *node_of.get(c).ok_or_else(|| format!("{}: point {name}: coordinate {c} is not a node", r.file))?;
        mesh.node_groups.insert(name.clone(), vec![n]);
    }
    let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (name, n) in object_names {
        if name.starts_with('#') || name.is_empty() {
            continue;
        }
        let o = &objects[n - 1];
        let parts: Vec<usize> = if o.parts.is_empty() { vec![*n] } else { o.parts.clone() };
        let mut members = Vec::new();
        let mut seen = HashSet::new();
        for p in parts {
            let p = p
                .checked_sub(1)
                .filter(|&p| p < objects.len())
                .ok_or_else(|| r.err(o.line, format!("mesh {name}: bad part {p}")))?;
            for &c in cell_of_rank[rank_start[p]..rank_start[p + 1]].iter().flatten() {
                if seen.insert(c) {
                    members.push(c);
                }
            }
        }
        if !members.is_empty() {
            groups.insert(name.clone(), members);
        }
    }
    mesh.cell_groups = groups;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn i8s(v: &[i64]) -> String {
        v.iter().map(|x| format!("{x:>8}")).collect()
    }

    /// Two squares of QUA4 (one named S1, one repeating a cell of S1 in an unnamed mesh), a
    /// composite named TOUT of both, a named point.
    fn sample() -> String {
        let mut s = String::new();
        s.push_str(" ENREGISTREMENT DE TYPE   4\n NIVEAU  11 NIVEAU ERREUR   0 DIMENSION   2\n DENSITE 0.00000E+00\n");
        s.push_str(" ENREGISTREMENT DE TYPE   2\n PILE NUMERO   1NBRE OBJETS NOMMES       2NBRE OBJETS       3\n");
        s.push_str(" S1       TOUT    \n");
        s.push_str("       1       3\n");
        // Object 1: 2 QUA4.
        s.push_str(&format!("{}\n{}\n{}\n", i8s(&[8, 0, 0, 4, 2]), i8s(&[0, 0]), i8s(&[1, 2, 3, 4, 2, 5, 6, 3])));
        // Object 2: 1 QUA4, identical to the first of object 1.
        s.push_str(&format!("{}\n{}\n{}\n", i8s(&[8, 0, 0, 4, 1]), i8s(&[0]), i8s(&[1, 2, 3, 4])));
        // Object 3: composite of 2 and 1.
        s.push_str(&format!("{}\n{}\n", i8s(&[0, 2, 0, 0, 0]), i8s(&[2, 1])));
        s.push_str(" ENREGISTREMENT DE TYPE   2\n PILE NUMERO  32NBRE OBJETS NOMMES       1NBRE OBJETS       6\n");
        s.push_str(" PA      \n");
        s.push_str(&format!("{}\n{}\n{}\n", i8s(&[5]), i8s(&[6]), i8s(&[1, 2, 3, 4, 5, 7])));
        s.push_str(" ENREGISTREMENT DE TYPE   2\n PILE NUMERO  33NBRE OBJETS NOMMES       0NBRE OBJETS       1\n");
        s.push_str("      21\n");
        let pts = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.0], [9.0, 9.0], [2.0, 1.0]];
        let vals: Vec<f64> = pts.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
        for c in vals.chunks(3) {
            s.push_str(&c.iter().map(|v| format!(" {v:21.14E}")).collect::<String>());
            s.push('\n');
        }
        s.push_str(" ENREGISTREMENT DE TYPE   5\nLABEL AUTOMATIQUE :   1\n");
        s
    }

    #[test]
    fn reads_as_code_aster_converts() {
        let m = read(&sample(), "t.mgib").unwrap();
        assert_eq!(m.dim, 2);
        // Coordinate 6 is no point's: dropped.
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N7"]);
        assert_eq!(m.coords[5], [2.0, 1.0, 0.0]);
        // The cell of object 2 is the first cell of object 1: not repeated.
        assert_eq!(m.cell_names, ["M1", "M2"]);
        assert_eq!(m.cells[1], [1, 4, 5, 2]);
        assert_eq!(m.cell_groups["S1"], [0, 1]);
        assert_eq!(m.cell_groups["TOUT"], [0, 1]);
        assert_eq!(m.node_groups["PA"], [4]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read(&sample().replace(&i8s(&[8, 0, 0, 4, 1]), &i8s(&[99, 0, 0, 4, 1])), "t.mgib").unwrap_err();
        assert_eq!(e, "t.mgib:11: Cast3M element type 99 is not supported");
        assert!(read("hello\n", "x.mgib").unwrap_err().contains("not a Cast3M"));
    }
}
