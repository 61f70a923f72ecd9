//! The variants of a study: knobs and their values, the command file with its top-level assignments
//! overridden, and generated meshes.

use crate::diag::{Error, Result};
use crate::mesh::generate::{box_mesh, ring_mesh};
use crate::mesh::{CellType, Mesh};
use crate::syntax::ast::{ExprKind, StmtKind};
use crate::syntax::parser::parse_module;

/// A knob: a name and the values it takes, in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct Knob {
    pub name: String,
    pub values: Vec<String>,
}

impl Knob {
    /// `NAME=v1,v2,...`.
    pub fn parse(s: &str) -> std::result::Result<Knob, String> {
        let (name, vals) = s.split_once('=').ok_or_else(|| format!("--set '{s}': expected NAME=v1,v2,..."))?;
        let name = name.trim();
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(format!("--set '{s}': '{name}' is not a variable name"));
        }
        let values: Vec<String> = vals.split(',').map(|v| v.trim().to_string()).filter(|v| !v.is_empty()).collect();
        if values.is_empty() {
            return Err(format!("--set '{s}': no value"));
        }
        Ok(Knob { name: name.to_string(), values })
    }
}

/// A generated mesh bound to a logical unit: `UNIT=box --cell C --n ... --size ...` or
/// `UNIT=ring --cell C --n ... --radii RI,RE [--height H]`, where `{NAME}` stands for a knob's value.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSpec {
    pub unit: i64,
    pub template: String,
}

impl MeshSpec {
    pub fn parse(s: &str) -> std::result::Result<MeshSpec, String> {
        let (u, t) = s.split_once('=').ok_or_else(|| format!("--mesh '{s}': expected UNIT=box|ring ..."))?;
        let unit = u.trim().parse().map_err(|_| format!("--mesh '{s}': '{u}' is not a unit number"))?;
        Ok(MeshSpec { unit, template: t.trim().to_string() })
    }

    /// The knobs the template names.
    pub fn uses(&self, knob: &str) -> bool {
        self.template.contains(&format!("{{{knob}}}"))
    }

    /// Build the mesh of one variant.
    pub fn build(&self, values: &[(String, String)]) -> Result<Mesh> {
        let text = substitute(&self.template, values);
        if text.contains('{') {
            return Err(Error::runtime(format!("--mesh '{text}': a {{NAME}} names no knob")));
        }
        let mut words = text.split_whitespace();
        let kind = words.next().unwrap_or("");
        let mut opts: Vec<(String, String)> = Vec::new();
        while let Some(w) = words.next() {
            let v = words.next().ok_or_else(|| Error::runtime(format!("--mesh '{text}': {w} has no value")))?;
            opts.push((w.trim_start_matches('-').to_string(), v.to_string()));
        }
        let get = |k: &str| opts.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
        let reals = |k: &str| -> Result<Vec<f64>> {
            get(k)
                .ok_or_else(|| Error::runtime(format!("--mesh '{text}': --{k} is required")))?
                .split(',')
                .map(|v| v.trim().parse::<f64>().map_err(|_| Error::runtime(format!("--mesh '{text}': --{k} {v}?"))))
                .collect()
        };
        for (k, _) in &opts {
            let known: &[&str] = if kind == "box" { &["cell", "n", "size"] } else { &["cell", "n", "radii", "height"] };
            if !known.contains(&k.as_str()) {
                return Err(Error::runtime(format!("--mesh '{text}': unknown option --{k}")));
            }
        }
        let cell = get("cell").ok_or_else(|| Error::runtime(format!("--mesh '{text}': --cell is required")))?;
        let cell = CellType::from_name(&cell.to_ascii_uppercase())
            .ok_or_else(|| Error::runtime(format!("--mesh '{text}': unknown cell type {cell}")))?;
        let n: Vec<usize> = reals("n")?.iter().map(|v| *v as usize).collect();
        match kind {
            "box" => box_mesh(cell, &n, &reals("size")?),
            "ring" => {
                let r = reals("radii")?;
                if r.len() != 2 {
                    return Err(Error::runtime(format!("--mesh '{text}': --radii RI,RE")));
                }
                let h = if get("height").is_some() { Some(reals("height")?[0]) } else { None };
                ring_mesh(cell, &n, [r[0], r[1]], h)
            }
            _ => Err(Error::runtime(format!("--mesh '{text}': expected 'box' or 'ring', got '{kind}'"))),
        }
    }
}

/// `{NAME}` replaced by the knob's value.
pub fn substitute(template: &str, values: &[(String, String)]) -> String {
    let mut s = template.to_string();
    for (k, v) in values {
        s = s.replace(&format!("{{{k}}}"), v);
    }
    s
}

/// Every combination of the knobs' values, the first knob varying slowest.
pub fn combinations(knobs: &[Knob]) -> Vec<Vec<usize>> {
    let mut out = vec![vec![]];
    for k in knobs {
        out = out.into_iter().flat_map(|c| (0..k.values.len()).map(move |i| [c.clone(), vec![i]].concat())).collect();
    }
    out
}

/// The Python text of a knob value: numbers and Python literals as written, any other word quoted.
pub fn literal(v: &str) -> String {
    let quoted = v.starts_with('"') || v.starts_with('\'');
    let bracket = v.starts_with('(') || v.starts_with('[');
    if quoted || bracket || v.parse::<f64>().is_ok() || v == "True" || v == "False" || v == "None" {
        v.to_string()
    } else {
        format!("{v:?}")
    }
}

/// The command file with the right-hand side of every top-level assignment `NAME = ...` of a knob
/// replaced by its value. Returns the new text and, per knob, the number of assignments replaced.
pub fn override_assignments(src: &str, values: &[(String, String)]) -> Result<(String, Vec<usize>)> {
    let module = parse_module(src).map_err(|e| Error::runtime(format!("the command file does not parse: {e:?}")))?;
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let mut counts = vec![0; values.len()];
    for st in &module.body {
        let StmtKind::Assign { targets, value } = &st.kind else { continue };
        if targets.len() != 1 {
            continue;
        }
        let ExprKind::Name(n) = &targets[0].kind else { continue };
        if let Some(k) = values.iter().position(|(name, _)| name == n) {
            edits.push((value.span.start, value.span.end, literal(&values[k].1)));
            counts[k] += 1;
        }
    }
    edits.sort_by_key(|e| std::cmp::Reverse(e.0));
    let mut out = src.to_string();
    for (a, b, text) in edits {
        out.replace_range(a..b, &text);
    }
    Ok((out, counts))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_top_level_assignments_only() {
        let src = "N = 8\nORDRE = 2  # facet rule\nif True:\n    N = 3\nX = f(N=N)\nCELL = 'QUAD4'\n";
        let v = [("N".to_string(), "16".to_string()), ("CELL".to_string(), "QUAD8".to_string())];
        let (out, counts) = override_assignments(src, &v).unwrap();
        assert_eq!(out, "N = 16\nORDRE = 2  # facet rule\nif True:\n    N = 3\nX = f(N=N)\nCELL = \"QUAD8\"\n");
        assert_eq!(counts, [1, 1]);
    }

    #[test]
    fn combinations_vary_the_first_knob_slowest() {
        let k = [Knob::parse("A=1,2").unwrap(), Knob::parse("B=x,y,z").unwrap()];
        let c = combinations(&k);
        assert_eq!(c.len(), 6);
        assert_eq!(c[0], [0, 0]);
        assert_eq!(c[1], [0, 1]);
        assert_eq!(c[3], [1, 0]);
    }

    #[test]
    fn mesh_templates_take_knob_values() {
        let s = MeshSpec::parse("20=box --cell QUAD4 --n {N},{N} --size 1,2").unwrap();
        assert!(s.uses("N"));
        let m = s.build(&[("N".into(), "3".into())]).unwrap();
        assert_eq!(m.cells.len(), 9 + 12);
        let r = MeshSpec::parse("20=ring --cell QUAD8 --n 2,3 --radii 1,2").unwrap();
        let m = r.build(&[]).unwrap();
        assert!(m.cell_groups.contains_key("INT") && m.node_groups.contains_key("GAUCHE"));
        // Every node of the inner arc is on the circle r = 1, mid-edge nodes included.
        for &n in &m.node_groups["INT"] {
            let c = m.coords[n];
            assert!((c[0].hypot(c[1]) - 1.0).abs() < 1e-14);
        }
        assert!(MeshSpec::parse("20=box --cell QUAD4 --n {M},1 --size 1,1").unwrap().build(&[]).is_err());
    }
}
