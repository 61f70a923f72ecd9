//! The nodes of a line of segment cells in the order of the line (Code_Aster's `cgnoor` + `ornofd`, what
//! DEFI_GROUP's NOEUD_ORDO and MACR_LIGN_COUPE's TYPE='GROUP_MA' walk): from an end (or a given origin),
//! the middle node of a SEG3 between its vertices.

use super::{CellType, Mesh};
use nalgebra::Vector3;
use std::collections::HashMap;

/// How the walk starts and ends.
#[derive(Debug, Clone, Default)]
pub struct LineEnds {
    /// The origin (GROUP_NO_ORIG), or None: the first end met.
    pub orig: Option<usize>,
    /// The end the walk must reach (GROUP_NO_EXTR).
    pub extr: Option<usize>,
    /// ORIGINE='SANS': a closed line without origin starts at the first cell's first node.
    pub no_origin: bool,
    /// VECT_ORIE: the direction a closed line is walked along.
    pub vect_orie: Vec<f64>,
}

/// Why a line cannot be walked: the keyword at fault (GROUP_MA, GROUP_NO_ORIG, GROUP_NO_EXTR) and what is
/// wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct LineError {
    pub keyword: &'static str,
    pub message: String,
}

fn fail(keyword: &'static str, message: String) -> LineError {
    LineError { keyword, message }
}

/// The nodes of the line the segment cells `cells` (all SEG2 or all SEG3) form, in order.
pub fn ordered_nodes(mesh: &Mesh, cells: &[usize], how: &LineEnds) -> Result<Vec<usize>, LineError> {
    let Some(&first) = cells.first() else { return Err(fail("GROUP_MA", "no cells given".into())) };
    let t0 = mesh.cell_types[first];
    for &c in cells {
        let t = mesh.cell_types[c];
        if !matches!(t, CellType::Seg2 | CellType::Seg3) {
            return Err(fail("GROUP_MA", format!("cell {} is a {}, not a segment", mesh.cell_names[c], t.name())));
        }
        if t != t0 {
            return Err(fail("GROUP_MA", "the segments must all be of the same type (SEG2 or SEG3)".into()));
        }
    }
    let ends: Vec<(usize, usize)> = cells.iter().map(|&c| (mesh.cells[c][0], mesh.cells[c][1])).collect();
    let mut degree: HashMap<usize, usize> = HashMap::new();
    for &(a, b) in &ends {
        *degree.entry(a).or_default() += 1;
        *degree.entry(b).or_default() += 1;
    }
    if degree.values().filter(|&&d| d == 1).count() > 2 || degree.values().any(|&d| d > 2) {
        return Err(fail("GROUP_MA", "the cells do not form one line without branches".into()));
    }
    let closed = how.orig.is_some() && how.orig == how.extr;
    for (kw, n) in [("GROUP_NO_EXTR", how.extr), ("GROUP_NO_ORIG", how.orig)] {
        if let Some(n) = n {
            let name = &mesh.node_names[n];
            match degree.get(&n) {
                None => return Err(fail(kw, format!("node {name} is not on the line"))),
                Some(&d) if d != 1 && !closed => {
                    return Err(fail(kw, format!("node {name} is not an end of the line")))
                }
                _ => {}
            }
        }
    }
    let start = match how.orig {
        Some(n) => n,
        None => {
            // The first end met (origin ends of all cells, then the others) used once.
            let order: Vec<usize> = ends.iter().map(|e| e.0).chain(ends.iter().map(|e| e.1)).collect();
            match order.iter().find(|n| degree[n] == 1) {
                Some(&n) => n,
                None if how.no_origin => order[0],
                None => {
                    return Err(fail("GROUP_MA", "the line is closed: give GROUP_NO_ORIG or ORIGINE='SANS'".into()))
                }
            }
        }
    };
    // Walk the chain.
    let mut used = vec![false; cells.len()];
    let mut out = vec![start];
    let mut cur = start;
    for _ in 0..cells.len() {
        let next = (0..cells.len()).find(|&i| !used[i] && (ends[i].0 == cur || ends[i].1 == cur));
        let Some(i) = next else {
            return Err(fail(
                "GROUP_MA",
                format!("the cells do not form one line from node {}", mesh.node_names[start]),
            ));
        };
        used[i] = true;
        if t0 == CellType::Seg3 {
            out.push(mesh.cells[cells[i]][2]);
        }
        cur = if ends[i].0 == cur { ends[i].1 } else { ends[i].0 };
        out.push(cur);
    }
    if let Some(e) = how.extr {
        if cur != e {
            return Err(fail(
                "GROUP_NO_EXTR",
                format!(
                    "the line from {} ends at {}, not at {}",
                    mesh.node_names[start], mesh.node_names[cur], mesh.node_names[e]
                ),
            ));
        }
    }
    // VECT_ORIE orients a closed line.
    let v = &how.vect_orie;
    if v.iter().any(|x| *x != 0.0) && out.len() >= 3 && out[0] == out[out.len() - 1] {
        let dir = |a: usize, b: usize| -> f64 {
            let d = Vector3::from(mesh.coords[b]) - Vector3::from(mesh.coords[a]);
            let orie = Vector3::from_fn(|k, _| v.get(k).copied().unwrap_or(0.0));
            d.dot(&orie) / d.norm()
        };
        let nb = out.len();
        if dir(out[nb - 1], out[nb - 2]) > dir(out[0], out[1]) {
            out.reverse();
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three SEG2 cells given out of order: 1-2, 3-4, 2-3 over nodes on the X axis.
    fn chain() -> Mesh {
        let mut m = Mesh { dim: 2, ..Default::default() };
        for i in 0..4 {
            m.coords.push([i as f64, 0.0, 0.0]);
            m.node_names.push(format!("N{}", i + 1));
        }
        for (k, c) in [[0, 1], [2, 3], [1, 2]].iter().enumerate() {
            m.cells.push(c.to_vec());
            m.cell_types.push(CellType::Seg2);
            m.cell_names.push(format!("M{}", k + 1));
        }
        m
    }

    #[test]
    fn a_line_is_walked_from_its_first_end_or_from_the_origin() {
        let m = chain();
        assert_eq!(ordered_nodes(&m, &[0, 1, 2], &LineEnds::default()).unwrap(), vec![0, 1, 2, 3]);
        let from_end = LineEnds { orig: Some(3), ..Default::default() };
        assert_eq!(ordered_nodes(&m, &[0, 1, 2], &from_end).unwrap(), vec![3, 2, 1, 0]);
        let wrong = LineEnds { orig: Some(1), ..Default::default() };
        assert_eq!(ordered_nodes(&m, &[0, 1, 2], &wrong).unwrap_err().keyword, "GROUP_NO_ORIG");
        let bad_end = LineEnds { extr: Some(1), ..Default::default() };
        assert_eq!(ordered_nodes(&m, &[0, 1, 2], &bad_end).unwrap_err().keyword, "GROUP_NO_EXTR");
    }
}
