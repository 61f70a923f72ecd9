//! IMPR_RESU FORMAT='GMSH': node fields of results in Gmsh's legacy ASCII
//! post-processing format, written the way Code_Aster writes it (`irgmsh`,
//! `irgmpf`, `irgmpv`, `irgmcn`, `irgnal`, `irgmma`/`irgmtb`, `irgmor`):
//!
//! ```text
//! $PostFormat
//!  1.2 0 8                     (VERSION=1.0: " 1.0 0 8")
//! $EndPostFormat
//! $View                        one view per printed component (SCALAIRE)
//! RES_DEPL_DX     1            result (8 chars), field, component; orders
//!        0        0        0   per element type: scalar, vector, tensor
//! ...                          counts (POI1 SEG2 TRIA3 [QUAD4] TETRA4
//!      0      0      0      0   [HEXA8 PENTA6 PYRAM5]; 1.2 only: 4 zeros)
//!  0.00000000E+00              the time of each order (10 a line)
//!  x1 x2 x3 (4 a line)         per element: x, y, z of its nodes, then per
//!  y1 ...                      order one line of values per node
//! $EndView
//! ```
//!
//! Cells are written as the linear types Gmsh knows: quadratic cells are cut
//! into linear ones (and in version 1.0, quadrangles and 3D cells other than
//! tetrahedra too), with Code_Aster's cutting tables.

use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::{CellType, Mesh};
use crate::stages::select::select_cells;
use crate::stages::Ctx;
use std::fmt::Write as _;

/// The element types of a Gmsh view, in the order Code_Aster writes them
/// (`irgmor`): POI1, SEG2, TRIA3, QUAD4, TETRA4, HEXA8, PENTA6, PYRAM5.
const NTYPES: usize = 8;
const POI: usize = 0;
const SEG: usize = 1;
const TRI: usize = 2;
const QUA: usize = 3;
const TET: usize = 4;
const HEX: usize = 5;
const PRI: usize = 6;
const PYR: usize = 7;

/// How a cell type is written (`irgmtb`): the Gmsh type it becomes and the
/// 1-based local nodes of each piece. None when Code_Aster cannot cut it.
fn cutting(t: CellType, version: u8) -> Option<(usize, &'static [&'static [usize]])> {
    use CellType::*;
    let v1 = version == 1;
    Some(match t {
        Poi1 => (POI, &[&[1]]),
        Seg2 => (SEG, &[&[1, 2]]),
        Seg3 => (SEG, &[&[1, 3], &[3, 2]]),
        Tria3 => (TRI, &[&[1, 2, 3]]),
        Tria6 => (TRI, &[&[1, 4, 6], &[4, 2, 5], &[5, 3, 6], &[4, 5, 6]]),
        Quad4 if v1 => (TRI, &[&[1, 2, 3], &[1, 3, 4]]),
        Quad4 => (QUA, &[&[1, 2, 3, 4]]),
        Quad8 | Quad9 => (TRI, &[&[1, 5, 8], &[5, 2, 6], &[6, 3, 7], &[7, 4, 8], &[5, 7, 8], &[5, 6, 7]]),
        Tetra4 => (TET, &[&[1, 2, 3, 4]]),
        Tetra10 => (
            TET,
            &[
                &[1, 5, 7, 8],
                &[2, 9, 6, 5],
                &[3, 6, 7, 10],
                &[4, 8, 9, 10],
                &[6, 7, 9, 5],
                &[7, 8, 9, 5],
                &[7, 8, 9, 10],
                &[6, 7, 9, 10],
            ],
        ),
        Penta6 if v1 => (TET, &[&[1, 2, 3, 5], &[1, 3, 6, 5], &[1, 6, 4, 5]]),
        Penta6 => (PRI, &[&[1, 2, 3, 4, 5, 6]]),
        Pyram5 if v1 => (TET, &[&[1, 2, 4, 5], &[2, 3, 4, 5]]),
        Pyram5 => (PYR, &[&[1, 2, 3, 4, 5]]),
        Hexa8 if v1 => {
            (TET, &[&[1, 2, 3, 5], &[2, 3, 5, 7], &[6, 2, 5, 7], &[1, 4, 3, 7], &[1, 7, 4, 8], &[8, 5, 1, 7]])
        }
        Hexa8 => (HEX, &[&[1, 2, 3, 4, 5, 6, 7, 8]]),
        Seg4 | Tria7 | Penta15 | Penta18 | Pyram13 | Hexa20 | Hexa27 => return None,
    })
}

/// Fortran `1PEw.d` (`exp_digits` None) or `1PEw.dEe` editing of one real.
pub fn fortran_e(v: f64, w: usize, d: usize, exp_digits: Option<usize>) -> String {
    let s = format!("{:.*e}", d, v);
    let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let sign = if exp < 0 { '-' } else { '+' };
    let mag = exp.unsigned_abs() as usize;
    let digits = mag.to_string();
    let tail = match exp_digits {
        Some(e) if digits.len() <= e => format!("E{sign}{digits:0>e$}"),
        Some(_) => return "*".repeat(w),
        None if mag <= 99 => format!("E{sign}{digits:0>2}"),
        None if mag <= 999 => format!("{sign}{digits:0>3}"),
        None => return "*".repeat(w),
    };
    let out = format!("{mant}{tail}");
    if out.len() > w {
        "*".repeat(w)
    } else {
        format!("{out:>w$}")
    }
}

/// Values written `n` a line, each followed by one blank (Fortran `n(fmt,1x)`).
fn lines_of(out: &mut String, vals: &[f64], per_line: usize, fmt: impl Fn(f64) -> String) {
    for chunk in vals.chunks(per_line) {
        for v in chunk {
            out.push_str(&fmt(*v));
            out.push(' ');
        }
        out.push('\n');
    }
}

fn coord(v: f64) -> String {
    fortran_e(v, 15, 7, Some(3))
}

/// The cells of the mesh as Gmsh elements, per Gmsh type (`irgmma`).
struct Elements {
    /// Per Gmsh type, the mesh nodes of each element.
    by_type: [Vec<Vec<usize>>; NTYPES],
}

impl Elements {
    fn new(mesh: &Mesh, cells: &[usize], version: u8, occ: &Args) -> Result<Elements> {
        let mut by_type: [Vec<Vec<usize>>; NTYPES] = Default::default();
        for &c in cells {
            let t = mesh.cell_types[c];
            let (target, pieces) = cutting(t, version).ok_or_else(|| {
                occ.err(
                    "RESULTAT",
                    format!(
                        "cell {} is a {}: writing {} cells to GMSH is not supported yet",
                        mesh.cell_names[c],
                        t.name(),
                        t.name()
                    ),
                )
            })?;
            for p in pieces {
                by_type[target].push(p.iter().map(|&i| mesh.cells[c][i - 1]).collect());
            }
        }
        Ok(Elements { by_type })
    }
}

/// What one view holds: a scalar (one component) or a vector (three).
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Scalar,
    Vector,
}

/// The header of a view (`irgmpv`).
fn view_header(out: &mut String, name: &str, times: &[f64], els: &Elements, kind: Kind, version: u8) {
    out.push_str("$View\n");
    let _ = writeln!(out, "{name}  {:>4}", times.len());
    let order: &[usize] = if version == 2 { &[POI, SEG, TRI, QUA, TET, HEX, PRI, PYR] } else { &[POI, SEG, TRI, TET] };
    for &t in order {
        let n = els.by_type[t].len();
        let (s, v) = if kind == Kind::Scalar { (n, 0) } else { (0, n) };
        let _ = writeln!(out, "{s:>8} {v:>8} {:>8} ", 0);
    }
    if version == 2 {
        let _ = writeln!(out, "{:>6} {:>6} {:>6} {:>6} ", 0, 0, 0, 0);
    }
    lines_of(out, times, 10, |t| fortran_e(t, 15, 8, None));
}

/// The elements of a view and the values at their nodes (`irgnal`): `cmps`
/// are the component indices in the field, None for a component the field
/// does not have (written as 0).
fn view_body(out: &mut String, mesh: &Mesh, els: &Elements, fields: &[(&[f64], usize)], cmps: &[Option<usize>]) {
    for elements in &els.by_type {
        for nodes in elements {
            for d in 0..3 {
                let xs: Vec<f64> = nodes.iter().map(|&n| mesh.coords[n][d]).collect();
                lines_of(out, &xs, 4, coord);
            }
            for &(values, ncmp) in fields {
                for &n in nodes {
                    let row: Vec<f64> = cmps
                        .iter()
                        .map(|k| {
                            let v = k.map_or(0.0, |k| values[n * ncmp + k]);
                            if v.is_nan() || v.abs() <= 1.0e-99 {
                                0.0
                            } else {
                                v
                            }
                        })
                        .collect();
                    lines_of(out, &row, 4, coord);
                }
            }
        }
    }
    out.push_str("$EndView\n");
}

/// One RESU occurrence: the views of the node fields of a result.
fn print_occurrence(occ: &Args, first: bool, version: u8, out: &mut String, alarms: &mut String) -> Result<()> {
    occ.refuse(&["MAILLAGE", "CHAM_GD", "NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE", "FREQ", "LIST_FREQ"])?;
    // TYPE_CHAM is read in version 1.2 only (irmfac).
    let type_cham = if version == 2 { occ.text("TYPE_CHAM").unwrap_or("SCALAIRE") } else { "SCALAIRE" };
    if type_cham.starts_with("TENS") {
        return Err(occ.err("TYPE_CHAM", format!("TYPE_CHAM='{type_cham}' is not supported yet")));
    }
    let rc = occ.req_concept("RESULTAT")?;
    let full_name = rc.label();
    // The view names use the 8 characters of a Code_Aster concept name.
    let rname: String = full_name.chars().take(8).collect();
    let r = rc.result()?;
    let model = r.model.model()?;
    let mesh = model.current_mesh();
    let mesh_name = model.mesh_concept.label();
    let steps = super::selected_steps(&r, occ, &full_name)?;
    if steps.is_empty() {
        return Err(occ.err("RESULTAT", format!("result {full_name} holds no step")));
    }
    let (explicit, names) = super::selected_fields(&steps, occ);
    // Fields absent at the first order are skipped (irgmsh); nothing at all
    // is written when no field exists (PREPOST2_59).
    let names: Vec<String> = names.into_iter().filter(|n| steps[0].fields.contains_key(n)).collect();
    if names.is_empty() {
        let _ = writeln!(alarms, " <A> IMPR_RESU: result {full_name}: no field to print at the selected orders");
        return Ok(());
    }
    if first {
        out.push_str("$PostFormat\n");
        let _ = writeln!(out, "{:>4.1} 0 8", if version == 1 { 1.0 } else { 1.2 });
        out.push_str("$EndPostFormat\n");
    }
    let cells: Vec<usize> = if occ.has("GROUP_MA") || occ.has("MAILLE") {
        select_cells(&mesh, occ, &mesh_name)?
    } else {
        (0..mesh.ncells()).collect()
    };
    let els = Elements::new(&mesh, &cells, version, occ)?;
    let times: Vec<f64> = steps.iter().map(|s| s.inst).collect();
    let nom_cmp = occ.texts("NOM_CMP");
    for cham in &names {
        // The field at each order, node fields only.
        let mut per_step: Vec<(&[f64], usize)> = Vec::new();
        let mut comps: &[String] = &[];
        let mut cell_kind = None;
        for st in &steps {
            match st.fields.get(cham) {
                Some(Field::Node { components, values }) => {
                    if per_step.is_empty() {
                        comps = components;
                    } else if components.as_slice() != comps {
                        return Err(occ.err(
                            "RESULTAT",
                            format!("field {cham} of result {full_name} changes components between orders"),
                        ));
                    }
                    per_step.push((values.as_slice(), components.len()));
                }
                Some(Field::Elno { .. }) => cell_kind = Some("ELNO"),
                Some(Field::Elga { .. }) => cell_kind = Some("ELGA"),
                Some(Field::Elem { .. }) => cell_kind = Some("ELEM"),
                None => {
                    return Err(occ.err(
                        if explicit { "NOM_CHAM" } else { "RESULTAT" },
                        format!("result {full_name} has no field {cham} at order {}", st.nume_ordre),
                    ))
                }
            }
        }
        if let Some(kind) = cell_kind {
            if explicit {
                return Err(occ.err(
                    "NOM_CHAM",
                    format!("{cham} is an {kind} field: writing cell fields to GMSH is not supported yet"),
                ));
            }
            let _ = writeln!(
                alarms,
                " <A> IMPR_RESU: result {full_name}: {cham} ({kind}) not written (cell fields are not supported yet \
                 in GMSH output)"
            );
            continue;
        }
        let index = |c: &str| comps.iter().position(|x| x == c);
        // What to write (irgmcn): version 1.0 writes DX/DY/DZ as a vector
        // and every component as a scalar view; version 1.2 follows
        // TYPE_CHAM.
        let (vect, scal) = if version == 1 {
            if nom_cmp.is_empty() {
                let v = comps.iter().any(|c| matches!(c.as_str(), "DX" | "DY" | "DZ"));
                let s = comps.iter().any(|c| !matches!(c.as_str(), "DX" | "DY" | "DZ"));
                (v, s)
            } else {
                (false, true)
            }
        } else {
            (type_cham.starts_with("VECT"), type_cham == "SCALAIRE")
        };
        let scal_cmps: Vec<String> = if nom_cmp.is_empty() { comps.to_vec() } else { nom_cmp.clone() };
        if vect {
            let vc: Vec<Option<usize>> = if version == 1 {
                ["DX", "DY", "DZ"].iter().map(|c| index(c)).collect()
            } else {
                (0..3).map(|i| nom_cmp.get(i).and_then(|c| index(c))).collect()
            };
            view_header(out, &format!("{rname}_{cham}_VECTEUR"), &times, &els, Kind::Vector, version);
            view_body(out, &mesh, &els, &per_step, &vc);
        }
        if scal {
            for c in &scal_cmps {
                view_header(out, &format!("{rname}_{cham}_{c}"), &times, &els, Kind::Scalar, version);
                view_body(out, &mesh, &els, &per_step, &[index(c)]);
            }
        }
    }
    Ok(())
}

/// IMPR_RESU with FORMAT='GMSH'.
pub fn impr_resu_gmsh(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["MODELE"])?;
    let version: u8 = match a.real("VERSION") {
        Some(v) if (v - 1.0).abs() < 1.0e-6 => 1,
        _ => 2,
    };
    let mut out = String::new();
    let mut alarms = String::new();
    for (i, occ) in a.facts("RESU").iter().enumerate() {
        print_occurrence(occ, i == 0, version, &mut out, &mut alarms)?;
    }
    let unit = a.int("UNITE").unwrap_or(37);
    ctx.io.write_unit(unit, &out).map_err(|e| e.at(a.span_of("UNITE")))?;
    if !alarms.is_empty() {
        ctx.io.mess(&alarms);
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::fortran_e;

    #[test]
    fn fortran_reals() {
        assert_eq!(fortran_e(0.0, 15, 7, Some(3)), " 0.0000000E+000");
        assert_eq!(fortran_e(-1.5e-6, 15, 7, Some(3)), "-1.5000000E-006");
        assert_eq!(fortran_e(2.0, 15, 8, None), " 2.00000000E+00");
        assert_eq!(fortran_e(1.0e100, 15, 8, None), " 1.00000000+100");
    }
}
