//! MACR_LIGN_COUPE: the values of a result's field (or of a field, CHAM_GD) along lines, into a table, as
//! Code_Aster's macro computes them.
//!
//! Code_Aster builds a mesh of SEG2 cells through the points of every line, projects the field onto its
//! nodes (PROJ_CHAMP METHODE='COLLOCATION') and reads them back with POST_RELEVE_T. The same is done here
//! without the intermediate concepts:
//!
//! * the points: TYPE='SEGMENT' NB_POINTS evenly spaced from COOR_ORIG (or the node of GROUP_NO_ORIG) to
//!   COOR_EXTR; 'ARC' NB_POINTS turned about CENTRE (and DNOR in 3D) by ANGLE; 'GROUP_NO' the group's nodes
//!   in its order; 'GROUP_MA' the nodes of the line of segments in order (NOEUD_ORDO). Coordinates go
//!   through the mesh file's `%21.14E`, as Code_Aster's do;
//! * each point is located in the cells of the model of the highest dimension (VIS_A_VIS narrows them):
//!   the first cell that holds it, else the nearest within DISTANCE_MAX (the smallest one given; none by
//!   default) — `fem::locate`. A node field is interpolated with the cell's shape functions, a field on
//!   cell nodes (ELNO) with its values in that cell, a field per cell (ELEM) takes the cell's value;
//! * points of a segment or an arc that fall outside the matter are left out (alarm POST0_8), and the
//!   curvilinear abscissa ABSC_CURV runs over the points kept (POST_RELEVE_T's `rvabsc`);
//! * REPERE (DEPL, SIGM_NOEU, SIGM_ELNO, SIEF_ELNO, FLUX_ELNO, FLUX_NOEU only; other fields stay global,
//!   alarm POST0_17): LOCAL — for a segment the frame of the segment and VECT_Y through the nautical
//!   angles Code_Aster derives from them, for a group the frame of the line at each node —,
//!   UTILISATEUR (ANGL_NAUT), CYLINDRIQUE (3D: ORIGINE and AXE_Z, or an arc's CENTRE and DNOR), as
//!   MODI_REPERE expresses them;
//! * OPERATION='EXTRACTION': one row per step and point — INTITULE, NOM_CHAM, NUME_ORDRE, INST,
//!   ABSC_CURV, COOR_X, COOR_Y, COOR_Z, the components (NOM_CMP, else all), or with TRAC_NOR (2D) the
//!   normal trace TRAC_NOR (vectors) or TR_NOR_1..3 (tensors) on the normal of the line; an arc adds
//!   ANGLE. OPERATION='MOYENNE': six rows per step (QUANTITE MOMENT_0, MOMENT_1, MINIMUM, MAXIMUM,
//!   MOYE_INT, MOYE_EXT) of POST_RELEVE_T's `rvpstm` over the line.
//!
//! INVARIANT gives VMIS, TRESCA, TRACE and DETER of a tensor field at each point.
//!
//! What the stage does not compute (REPERE='POLAIRE', ELEM_PRINCIPAUX, RESULTANTE, TRAC_DIR,
//! fields at Gauss points, UNITE_MAILLAGE) stops the run by name.

use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::concepts::table::{Cell, ColType, Table};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::frame::Frame;
use crate::fem::locate::{Located, Locator};
use crate::fem::reference::shape;
use crate::mesh::Mesh;
use crate::stages::select::selected_steps;
use crate::stages::Ctx;
use nalgebra::{Matrix3, Vector3};

/// One line of points.
struct Line {
    /// SEGMENT or ARC (points outside the matter are dropped), or a group (kept).
    drops_outside: bool,
    points: Vec<[f64; 3]>,
    /// The angle of each point of an arc.
    angles: Option<Vec<f64>>,
    intitule: String,
}

/// A coordinate as the line mesh's file writes it (`%21.14E`) and reads it back.
fn written(x: f64) -> f64 {
    format!("{x:.14E}").parse().unwrap_or(x)
}

fn point(c: &[f64]) -> [f64; 3] {
    [written(c[0]), written(c.get(1).copied().unwrap_or(0.0)), written(c.get(2).copied().unwrap_or(0.0))]
}

/// The coordinates of the single node of group `kw` (COOR_ORIG / COOR_EXTR otherwise).
fn end_point(occ: &Args, mesh: &Mesh, mesh_name: &str, coor: &str, group: &str, dim: usize) -> Result<[f64; 3]> {
    if let Some(g) = occ.text(group) {
        let nodes = mesh
            .node_groups
            .get(g)
            .ok_or_else(|| occ.err(group, format!("mesh {mesh_name} has no group of nodes '{g}' (POST0_13)")))?;
        if nodes.len() != 1 {
            return Err(occ.err(
                group,
                format!("group of nodes '{g}' holds {} nodes where one is expected (POST0_27)", nodes.len()),
            ));
        }
        return Ok(mesh.coords[nodes[0]]);
    }
    // Fewer coordinates than the mesh's dimension stop (POST0_11); a third one on a 2D mesh is not used.
    let c = occ.reals(coor);
    if c.len() < dim {
        return Err(occ.err(coor, format!("{} coordinates given for a mesh of dimension {dim} (POST0_11)", c.len())));
    }
    Ok([c[0], c[1], if dim == 3 { c[2] } else { 0.0 }])
}

/// The points of an arc: COOR_ORIG turned about CENTRE (about DNOR in 3D) by angles evenly spread over
/// ANGLE (a full turn does not repeat its first point).
fn arc_points(occ: &Args, dim: usize) -> Result<(Vec<[f64; 3]>, Vec<f64>)> {
    let n = occ.int("NB_POINTS").unwrap_or(2).max(2) as usize;
    let (o, c) = (occ.reals("COOR_ORIG"), occ.reals("CENTRE"));
    for (kw, v) in [("COOR_ORIG", &o), ("CENTRE", &c)] {
        if v.len() < dim {
            return Err(occ.err(kw, format!("{} coordinates given for a mesh of dimension {dim} (POST0_11)", v.len())));
        }
    }
    let angle = occ.real("ANGLE").unwrap_or(0.0);
    let d = occ.reals("DNOR");
    if dim == 3 && d.len() != 3 {
        return Err(occ.err("DNOR", "an arc in 3D needs DNOR, the normal of its plane (POST0_12)"));
    }
    let r: Vec<f64> = (0..dim).map(|k| o[k] - c[k]).collect();
    if r.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-8 {
        return Err(occ.err("COOR_ORIG", "the origin of the arc is its centre (POST0_6)"));
    }
    let nbpt = if (angle - 360.0).abs() < 1e-8 { n + 1 } else { n };
    let mut pts = Vec::with_capacity(n);
    let mut angles = Vec::with_capacity(n);
    for j in 0..n {
        let aj = j as f64 * angle / (nbpt - 1) as f64;
        let (s, co) = aj.to_radians().sin_cos();
        let p = if dim == 2 {
            [c[0] + r[0] * co - r[1] * s, c[1] + r[1] * co + r[0] * s, 0.0]
        } else {
            let dn = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let (a, b, cz) = (r[0], r[1], r[2]);
            [
                c[0] + a * co + s * (cz * d[1] - b * d[2]) / dn,
                c[1] + b * co + s * (a * d[2] - cz * d[0]) / dn,
                c[2] + cz * co + s * (b * d[0] - a * d[1]) / dn,
            ]
        };
        pts.push(point(&p));
        angles.push(aj);
    }
    Ok((pts, angles))
}

/// The lines of the LIGN_COUPE occurrences.
fn lines(a: &Args, mesh: &Mesh, mesh_name: &str) -> Result<Vec<Line>> {
    let dim = mesh.dim;
    let mut out = Vec::new();
    let mut counted = 0;
    let occs = a.facts("LIGN_COUPE");
    let arcs = occs.iter().filter(|o| o.text("TYPE") == Some("ARC")).count();
    if arcs > 0 && arcs < occs.len() {
        return Err(a.err("LIGN_COUPE", "arcs cannot be mixed with segments or groups in one call (POST0_16)"));
    }
    for occ in occs {
        let ty = occ.text("TYPE").unwrap_or("SEGMENT");
        let default_title = |counted: usize| format!("l.coupe{counted}");
        let line = match ty {
            "SEGMENT" => {
                counted += 1;
                let o = end_point(occ, mesh, mesh_name, "COOR_ORIG", "GROUP_NO_ORIG", dim)?;
                let e = end_point(occ, mesh, mesh_name, "COOR_EXTR", "GROUP_NO_EXTR", dim)?;
                let n = occ.int("NB_POINTS").unwrap_or(2).max(2) as usize;
                let points = (0..n)
                    .map(|j| {
                        let f = |k: usize| o[k] + j as f64 * (e[k] - o[k]) / (n - 1) as f64;
                        point(&[f(0), f(1), if dim == 3 { f(2) } else { 0.0 }])
                    })
                    .collect();
                Line { drops_outside: true, points, angles: None, intitule: default_title(counted) }
            }
            "ARC" => {
                counted += 1;
                let (points, angles) = arc_points(occ, dim)?;
                Line { drops_outside: true, points, angles: Some(angles), intitule: default_title(counted) }
            }
            "GROUP_NO" => {
                let g = occ.req_text("GROUP_NO")?;
                let nodes = mesh.node_groups.get(g).ok_or_else(|| {
                    occ.err("GROUP_NO", format!("mesh {mesh_name} has no group of nodes '{g}' (POST0_13)"))
                })?;
                let points = nodes.iter().map(|&n| point(&mesh.coords[n])).collect();
                Line { drops_outside: false, points, angles: None, intitule: g.to_string() }
            }
            _ => {
                let g = occ.req_text("GROUP_MA")?;
                // The line's nodes are ordered on MAILLAGE, their coordinates read on the result's mesh.
                let lm = occ.req_concept("MAILLAGE")?.mesh()?;
                let cells = lm.cell_groups.get(g).ok_or_else(|| {
                    occ.err("GROUP_MA", format!("mesh {mesh_name} has no group of cells '{g}' (POST0_14)"))
                })?;
                let first = |kw: &str| -> Result<Option<usize>> {
                    match occ.text(kw) {
                        None => Ok(None),
                        Some(n) => lm
                            .node_groups
                            .get(n)
                            .and_then(|v| v.first().copied())
                            .map(Some)
                            .ok_or_else(|| occ.err(kw, format!("no group of nodes '{n}' (or it is empty)"))),
                    }
                };
                let how = crate::mesh::line::LineEnds {
                    orig: first("GROUP_NO_ORIG")?,
                    extr: first("GROUP_NO_EXTR")?,
                    no_origin: true,
                    vect_orie: occ.reals("VECT_ORIE"),
                };
                let nodes =
                    crate::mesh::line::ordered_nodes(&lm, cells, &how).map_err(|e| occ.err(e.keyword, e.message))?;
                let mut points = Vec::with_capacity(nodes.len());
                for n in nodes {
                    let c = mesh.coords.get(n).ok_or_else(|| {
                        occ.err("MAILLAGE", format!("node {} of MAILLAGE is not a node of mesh {mesh_name}", n + 1))
                    })?;
                    points.push(point(c));
                }
                Line { drops_outside: false, points, angles: None, intitule: g.to_string() }
            }
        };
        let intitule = occ.text("INTITULE").map(str::to_string).unwrap_or(line.intitule);
        out.push(Line { intitule, ..line });
    }
    Ok(out)
}

/// The values of every component of `field` at a located point (NaN where it has none).
fn values_at(field: &Field, mesh: &Mesh, at: &Located) -> Vec<f64> {
    let n = field.components().len();
    let cell = &mesh.cells[at.cell];
    let weights = || shape(mesh.cell_types[at.cell], &at.xi);
    match field {
        Field::Node { values, .. } => {
            let w = weights();
            (0..n)
                .map(|k| {
                    // A component some node of the cell lacks is not projected (`cnsprj`).
                    cell.iter().zip(&w).map(|(&node, wi)| wi * values[node * n + k]).sum::<f64>()
                })
                .collect()
        }
        Field::Elno { cells, .. } => match &cells[at.cell] {
            Some(v) => {
                let w = weights();
                (0..n).map(|k| w.iter().enumerate().map(|(i, wi)| wi * v[i * n + k]).sum::<f64>()).collect()
            }
            None => vec![f64::NAN; n],
        },
        Field::Elem { cells, .. } => cells[at.cell].clone().unwrap_or_else(|| vec![f64::NAN; n]),
        Field::Elga { .. } => vec![f64::NAN; n],
    }
}

/// How a field's components turn with a frame.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Turns {
    Vector(&'static [&'static str]),
    Tensor(&'static [&'static str]),
}

/// The fields MACR_LIGN_COUPE expresses in another frame, and their components.
fn turns(nom_cham: &str, dim: usize) -> Option<Turns> {
    let three = dim == 3;
    match nom_cham {
        "DEPL" => Some(Turns::Vector(if three { &["DX", "DY", "DZ"] } else { &["DX", "DY"] })),
        "FLUX_ELNO" | "FLUX_NOEU" => {
            Some(Turns::Vector(if three { &["FLUX", "FLUY", "FLUZ"] } else { &["FLUX", "FLUY"] }))
        }
        "SIGM_NOEU" | "SIGM_ELNO" | "SIEF_ELNO" => Some(Turns::Tensor(if three {
            &["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]
        } else {
            &["SIXX", "SIYY", "SIZZ", "SIXY"]
        })),
        _ => None,
    }
}

/// Express the values `v` (all the field's components, named `names`) in the frame whose rows are `p`.
fn turn(kind: Turns, p: &Matrix3<f64>, names: &[String], v: &mut [f64], dim: usize) {
    let idx = |c: &str| names.iter().position(|n| n == c);
    let get = |v: &[f64], c: &str| idx(c).map(|i| v[i]).filter(|x| x.is_finite()).unwrap_or(0.0);
    match kind {
        Turns::Vector(cs) => {
            let x = Vector3::from_fn(|k, _| cs.get(k).map(|c| get(v, c)).unwrap_or(0.0));
            let y = p * x;
            for (k, c) in cs.iter().enumerate().take(dim) {
                if let Some(i) = idx(c) {
                    v[i] = y[k];
                }
            }
        }
        Turns::Tensor(cs) => {
            let s = |c: &str| get(v, c);
            let (xz, yz) = if dim == 3 { (s("SIXZ"), s("SIYZ")) } else { (0.0, 0.0) };
            let m = Matrix3::new(s("SIXX"), s("SIXY"), xz, s("SIXY"), s("SIYY"), yz, xz, yz, s("SIZZ"));
            let r = p * m * p.transpose();
            for c in cs.iter() {
                let val = match *c {
                    "SIXX" => r[(0, 0)],
                    "SIYY" => r[(1, 1)],
                    "SIZZ" => r[(2, 2)],
                    "SIXY" => r[(0, 1)],
                    "SIXZ" => r[(0, 2)],
                    _ => r[(1, 2)],
                };
                if let Some(i) = idx(c) {
                    v[i] = val;
                }
            }
        }
    }
}

fn axes(f: Frame) -> Matrix3<f64> {
    match f {
        Frame::Fixed(ax) => Matrix3::from_fn(|i, j| ax[i][j]),
        Frame::Cylinder { .. } => Matrix3::identity(),
    }
}

/// Code_Aster's nautical angles (degrees) of the frame of axes `x`, `y`, `z` (unit vectors).
fn nautical_of(x: [f64; 3], y: [f64; 3], z: [f64; 3], dim: usize) -> [f64; 3] {
    let (mut alpha, mut beta, mut gamma) = (x[1].atan2(x[0]), 0.0, 0.0);
    if dim == 3 {
        if x[0] * x[0] + x[1] * x[1] > 1e-8 {
            beta = -x[2].clamp(-1.0, 1.0).asin();
            gamma = y[2].atan2(z[2]);
        } else {
            alpha = (-y[0]).atan2(y[1]);
            beta = -x[2].clamp(-1.0, 1.0).asin();
        }
    }
    [alpha.to_degrees(), beta.to_degrees(), gamma.to_degrees()]
}

fn unit(v: Vector3<f64>) -> Vector3<f64> {
    v / v.norm()
}

/// The frame of a segment: X along it, Y from VECT_Y (made orthogonal, with an alarm, when it is not).
fn segment_frame(ctx: &mut Ctx, occ: &Args, line: &Line, dim: usize) -> Result<Matrix3<f64>> {
    let (o, e) = (line.points[0], line.points[line.points.len() - 1]);
    let mut x = Vector3::new(e[0] - o[0], e[1] - o[1], if dim == 3 { e[2] - o[2] } else { 0.0 });
    if x.norm() < 1e-8 {
        return Err(occ.err("COOR_EXTR", "the segment has no length: its local frame is undefined (POST0_1)"));
    }
    x = unit(x);
    let vy = occ.reals("VECT_Y");
    if vy.len() < 2 {
        return Err(occ.err("REPERE", "REPERE='LOCAL' on a segment needs VECT_Y (POST0_50)"));
    }
    let mut y = Vector3::new(vy[0], vy[1], if dim == 3 { vy.get(2).copied().unwrap_or(0.0) } else { 0.0 });
    if y.norm() < 1e-8 {
        return Err(occ.err("VECT_Y", "VECT_Y is zero (POST0_2)"));
    }
    y = unit(y);
    if (x - y).abs().max() < 1e-8 || (x + y).abs().max() < 1e-8 {
        return Err(occ.err("VECT_Y", "VECT_Y is along the segment (POST0_3)"));
    }
    let z;
    if x.dot(&y).abs() > 1e-8 {
        z = unit(x.cross(&y));
        y = unit(z.cross(&x));
        ctx.io.mess(&format!(
            " <A> <POST0_4> MACR_LIGN_COUPE: VECT_Y is not orthogonal to the segment; it is replaced by ({}, {}, {})\n",
            y[0], y[1], y[2]
        ));
    } else {
        z = x.cross(&y);
    }
    let ang = nautical_of(x.into(), y.into(), z.into(), dim);
    Ok(axes(Frame::nautical(if dim == 3 { &ang } else { &ang[..1] })))
}

/// The frame of a group's line at each of its points: X along the line (the sum of the two segments'
/// vectors at an inner point; Code_Aster takes their Z component as 0), Y normal to it — in 2D the
/// turned X, in 3D from VECT_Y.
fn group_frames(occ: &Args, line: &Line, dim: usize) -> Result<Vec<Matrix3<f64>>> {
    let p = &line.points;
    let seg = |i: usize| Vector3::new(p[i + 1][0] - p[i][0], p[i + 1][1] - p[i][1], 0.0);
    let vy = occ.reals("VECT_Y");
    if dim == 3 && vy.len() != 3 {
        return Err(occ.err("REPERE", "REPERE='LOCAL' on a group in 3D needs VECT_Y"));
    }
    (0..p.len())
        .map(|i| {
            let mut t = Vector3::zeros();
            if i > 0 {
                t += seg(i - 1);
            }
            if i + 1 < p.len() {
                t += seg(i);
            }
            if t.norm() == 0.0 {
                return Err(occ.err("TYPE", "two consecutive points of the line coincide: its frame is undefined"));
            }
            let x = unit(t);
            let (y, z) = if dim == 2 {
                (Vector3::new(-x[1], x[0], 0.0), Vector3::z())
            } else {
                let z = unit(x.cross(&unit(Vector3::new(vy[0], vy[1], vy[2]))));
                (unit(z.cross(&x)), z)
            };
            let ang = nautical_of(x.into(), y.into(), z.into(), dim);
            Ok(axes(Frame::nautical(if dim == 3 { &ang } else { &ang[..1] })))
        })
        .collect()
}

/// The cylindrical frame (rows e_r, e_z, e_θ) at `x` about the axis through `origin` along `axis`, as
/// MODI_REPERE's CYLINDRIQUE expresses components.
fn cylinder_at(x: &[f64; 3], origin: &[f64], axis: &[f64]) -> Option<Matrix3<f64>> {
    let a = unit(Vector3::new(axis[0], axis[1], axis[2]));
    let d = Vector3::from(*x) - Vector3::new(origin[0], origin[1], origin[2]);
    let r = d - a * d.dot(&a);
    if r.norm() < 1e-6 {
        return None;
    }
    let r = unit(r);
    let t = unit(a.cross(&r));
    Some(Matrix3::from_rows(&[r.transpose(), a.transpose(), t.transpose()]))
}

/// The frame of each point of an occurrence, None for the global frame.
fn frames(ctx: &mut Ctx, occ: &Args, line: &Line, dim: usize) -> Result<Option<Vec<Matrix3<f64>>>> {
    let n = line.points.len();
    let ty = occ.text("TYPE").unwrap_or("SEGMENT");
    match occ.text("REPERE").unwrap_or("GLOBAL") {
        "GLOBAL" => Ok(None),
        "POLAIRE" => Err(occ.err("REPERE", "REPERE='POLAIRE' is not supported yet")),
        r if ty == "ARC" && r != "CYLINDRIQUE" => {
            Err(occ.err("REPERE", format!("REPERE='{r}' is not allowed on an arc; only CYLINDRIQUE is (POST0_5)")))
        }
        "LOCAL" if ty == "SEGMENT" => Ok(Some(vec![segment_frame(ctx, occ, line, dim)?; n])),
        "LOCAL" => group_frames(occ, line, dim).map(Some),
        "UTILISATEUR" => {
            let ang = occ.reals("ANGL_NAUT");
            Ok(Some(vec![axes(Frame::nautical(if dim == 3 { &ang } else { &ang[..1] })); n]))
        }
        _ => {
            if dim != 3 {
                return Err(occ.err("REPERE", "REPERE='CYLINDRIQUE' on a 2D mesh is not supported yet"));
            }
            let (o, z, kws) = if ty == "ARC" {
                (occ.reals("CENTRE"), occ.reals("DNOR"), ("CENTRE", "DNOR"))
            } else {
                (occ.reals("ORIGINE"), occ.reals("AXE_Z"), ("ORIGINE", "AXE_Z"))
            };
            if o.len() != 3 || z.len() != 3 {
                return Err(occ.err("REPERE", format!("REPERE='CYLINDRIQUE' in 3D needs {} and {}", kws.0, kws.1)));
            }
            line.points
                .iter()
                .map(|x| {
                    cylinder_at(x, &o, &z).ok_or_else(|| {
                        occ.err(
                            "REPERE",
                            format!(
                                "the point ({}, {}, {}) lies on the axis of the cylindrical frame",
                                x[0], x[1], x[2]
                            ),
                        )
                    })
                })
                .collect::<Result<Vec<_>>>()
                .map(Some)
        }
    }
}

/// POST_RELEVE_T's `rvpstm` over a line: MOMENT_0 (the mean), MOMENT_1 (the linear part's variation),
/// MINIMUM, MAXIMUM, MOYE_INT and MOYE_EXT (the linear part at the ends) of values at abscissas `s`.
fn moments(s: &[f64], v: &[f64]) -> [f64; 6] {
    let (mut m1, mut m2, mut xl) = (0.0, 0.0, 0.0);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..s.len().saturating_sub(1) {
        let (t1, t2) = (v[i], v[i + 1]);
        let (s1, s2) = (s[i] - s[0], s[i + 1] - s[0]);
        let l = s2 - s1;
        xl += l;
        m1 += l * (t1 + t2);
        m2 += l / 3.0 * (t1 * s1 + 4.0 * (t1 + t2) / 2.0 * (s1 + s2) / 2.0 + t2 * s2);
        lo = lo.min(t1).min(t2);
        hi = hi.max(t1).max(t2);
    }
    let m1 = m1 / xl / 2.0;
    let m2 = 6.0 * (m2 / (xl * xl) - m1);
    [m1, m2, lo, hi, m1 - 0.5 * m2, m1 + 0.5 * m2]
}

/// The unit tangents' normals of a 2D line at its points (POST_RELEVE_T's `rvrlln`, LOCAL): at an inner
/// point the mean of the two segments' normals.
pub(super) fn line_normals(p: &[[f64; 3]]) -> Vec<[f64; 2]> {
    let n = p.len();
    let seg = |i: usize| {
        let (dx, dy) = (p[i + 1][0] - p[i][0], p[i + 1][1] - p[i][1]);
        let l = dx.hypot(dy);
        [-dy / l, dx / l]
    };
    (0..n)
        .map(|i| match (i, n) {
            (_, 1) => [0.0, 0.0],
            (0, _) => seg(0),
            (i, n) if i + 1 == n => seg(i - 1),
            (i, _) => {
                let (a, b) = (seg(i - 1), seg(i));
                [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
            }
        })
        .collect()
}

pub(super) type Row = Vec<(String, Cell)>;

fn real(v: f64) -> Cell {
    if v.is_finite() {
        Cell::Real(v)
    } else {
        Cell::Empty
    }
}

/// TRAC_NOR on a 2D line (POST_RELEVE_T's `rvpstd` on the normal `n` of the line at a point): the normal
/// trace of a tensor field (SIGM*, SIEF*, EPSI*: TR_NOR_1..3 from its own components), or the normal
/// component of a vector given by the first two components asked (`ks`) (TRAC_NOR). `v` holds every
/// component of the field at the point (None: no value there).
pub(super) fn normal_trace(nom_cham: &str, comps: &[String], v: Option<&[f64]>, ks: &[usize], n: [f64; 2]) -> Row {
    let tensor = tensor_prefix(nom_cham).is_some();
    let Some(v) = v else {
        return if tensor {
            ["TR_NOR_1", "TR_NOR_2", "TR_NOR_3"].iter().map(|c| (c.to_string(), Cell::Empty)).collect()
        } else {
            vec![("TRAC_NOR".into(), Cell::Empty)]
        };
    };
    let fin = |x: f64| if x.is_finite() { x } else { 0.0 };
    if tensor {
        let pre = tensor_prefix(nom_cham).unwrap_or("SI");
        let g = |c: &str| comps.iter().position(|x| *x == format!("{pre}{c}")).map(|i| fin(v[i])).unwrap_or(0.0);
        vec![
            ("TR_NOR_1".into(), real(g("XX") * n[0] + g("XY") * n[1])),
            ("TR_NOR_2".into(), real(g("XY") * n[0] + g("YY") * n[1])),
            ("TR_NOR_3".into(), real(g("XZ") * n[0] + g("YZ") * n[1])),
        ]
    } else {
        let c = |i: usize| ks.get(i).map(|&k| fin(v[k])).unwrap_or(0.0);
        vec![("TRAC_NOR".into(), real(c(0) * n[0] + c(1) * n[1]))]
    }
}

/// The prefix of a tensor field's components (SIGM*, SIEF*: SI; EPSI*: EP), None for other fields
/// (POST_RELEVE_T's `T3` quantities).
fn tensor_prefix(nom_cham: &str) -> Option<&'static str> {
    if nom_cham.starts_with("SIGM") || nom_cham.starts_with("SIEF") {
        Some("SI")
    } else if nom_cham.starts_with("EPSI") {
        Some("EP")
    } else {
        None
    }
}

/// INVARIANT (POST_RELEVE_T's `rvinvt`) of the tensor of a point: VMIS (√(3/2 s:s) of its deviator s),
/// TRESCA (the largest principal value less the smallest), TRACE and DETER. Missing components are 0.
fn invariants(nom_cham: &str, comps: &[String], v: &[f64]) -> [f64; 4] {
    let pre = tensor_prefix(nom_cham).unwrap_or("SI");
    let g = |c: &str| {
        comps.iter().position(|x| *x == format!("{pre}{c}")).map(|i| v[i]).filter(|x| x.is_finite()).unwrap_or(0.0)
    };
    let t = Matrix3::new(g("XX"), g("XY"), g("XZ"), g("XY"), g("YY"), g("YZ"), g("XZ"), g("YZ"), g("ZZ"));
    let trace = t.trace();
    let dev = t - Matrix3::identity() * (trace / 3.0);
    let vmis = (1.5 * dev.component_mul(&dev).sum()).sqrt();
    let eig = t.symmetric_eigenvalues();
    let tresca = eig.max() - eig.min();
    [vmis, tresca, trace, t.determinant()]
}

/// The field name a CHAM_GD gives by default, from its components (Code_Aster reads it from the physical
/// quantity: TEMP_R, DEPL_R, NEUT_R).
fn default_name(comps: &[String]) -> Option<&'static str> {
    let has = |c: &str| comps.iter().any(|x| x == c);
    if has("TEMP") {
        Some("TEMP")
    } else if has("DX") {
        Some("DEPL")
    } else if has("X1") {
        Some("NEUT")
    } else {
        None
    }
}

pub fn macr_lign_coupe(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    for occ in a.facts("LIGN_COUPE") {
        occ.refuse(&["ELEM_PRINCIPAUX", "RESULTANTE", "MOMENT", "POINT", "TRAC_DIR", "DIRECTION"])?;
    }
    a.refuse(&["UNITE_MAILLAGE", "NUME_MODE"])?;
    // The steps (number, instant, field) and the model.
    let rc = a.concept("RESULTAT");
    let fc = a.concept("CHAM_GD");
    let model_c = match (&rc, a.concept("MODELE")) {
        (_, Some(m)) => m,
        (Some(r), None) => r.result()?.model.clone(),
        (None, None) => return Err(a.err("CHAM_GD", "MODELE is needed with CHAM_GD (POST0_10)")),
    };
    let model = model_c.model()?;
    let mesh = model.current_mesh();
    let mesh_name = model.mesh_concept.label();
    let dim = mesh.dim;
    let result;
    let field_data;
    let (nom_cham, steps): (String, Vec<(i64, f64, &Field)>) = match (&rc, &fc) {
        (Some(r), _) => {
            let name = r.label();
            result = r.result()?;
            let nom = a.req_text("NOM_CHAM")?.to_string();
            let chosen = selected_steps(&result, a, &name)?;
            let steps: Vec<_> =
                chosen.iter().filter_map(|s| s.fields.get(&nom).map(|f| (s.nume_ordre, s.inst, f))).collect();
            if steps.is_empty() {
                return Err(a.err("NOM_CHAM", format!("result {name} has no field {nom} at the steps chosen")));
            }
            (nom, steps)
        }
        (None, Some(f)) => {
            field_data = f.field()?;
            let field = field_data.reals(&f.label()).map_err(|e| a.locate(e, "CHAM_GD"))?;
            let nom = match a.text("NOM_CHAM") {
                Some(n) => n.to_string(),
                None => default_name(field.components())
                    .ok_or_else(|| {
                        a.err(
                            "CHAM_GD",
                            format!("give NOM_CHAM: the kind of field {} is not told by its components", f.label()),
                        )
                    })?
                    .to_string(),
            };
            (nom, vec![(1, 0.0, field)])
        }
        (None, None) => return Err(a.err("RESULTAT", "RESULTAT or CHAM_GD is needed")),
    };
    if nom_cham.get(5..9) == Some("ELGA") || matches!(steps[0].2, Field::Elga { .. }) {
        return Err(a.err(
            "NOM_CHAM",
            format!(
                "{nom_cham} is a field at Gauss points: its projection onto the lines is not supported yet (POST0_18)"
            ),
        ));
    }
    let comps: Vec<String> = steps[0].2.components().to_vec();
    // The cells searched: those of the model's highest dimension (all of the mesh's for a model without
    // elements), narrowed by VIS_A_VIS.
    let with_elements: Vec<usize> = (0..mesh.ncells()).filter(|&c| model.elements[c].is_some()).collect();
    let pool = if with_elements.is_empty() { (0..mesh.ncells()).collect() } else { with_elements };
    let top = pool.iter().map(|&c| mesh.cell_types[c].dim()).max().unwrap_or(0);
    let mut search: Vec<usize> = pool.into_iter().filter(|&c| mesh.cell_types[c].dim() == top).collect();
    if a.has("VIS_A_VIS") {
        let mut allowed = Vec::new();
        for v in a.facts("VIS_A_VIS") {
            if let Some(g) = v.text("GROUP_MA_1") {
                let cells = mesh
                    .cell_groups
                    .get(g)
                    .ok_or_else(|| v.err("GROUP_MA_1", format!("mesh {mesh_name} has no group of cells '{g}'")))?;
                allowed.extend(cells.iter().copied());
            }
            for m in v.texts("MAILLE_1") {
                let c = mesh
                    .cell_names
                    .iter()
                    .position(|x| *x == m)
                    .or_else(|| crate::mesh::numbered(&m, 'M', mesh.ncells()))
                    .ok_or_else(|| v.err("MAILLE_1", format!("mesh {mesh_name} has no cell '{m}'")))?;
                allowed.push(c);
            }
        }
        search.retain(|c| allowed.contains(c));
    }
    let locator = Locator::new(&mesh, search);
    let occs = a.facts("LIGN_COUPE");
    let dmaxs: Vec<f64> = occs.iter().filter_map(|o| o.real("DISTANCE_MAX")).filter(|&d| d != 0.0).collect();
    let dmax = dmaxs.iter().copied().fold(f64::INFINITY, f64::min);
    let dmax = if dmaxs.is_empty() { 0.0 } else { dmax };
    if dmaxs.iter().any(|&d| d != dmax) {
        ctx.io.mess(&format!(" <A> <POST0_53> MACR_LIGN_COUPE: the lines give several DISTANCE_MAX; the smallest, {dmax}, is used for all\n"));
    }
    let alarms: Vec<f64> = occs.iter().filter_map(|o| o.real("DISTANCE_ALARME")).filter(|&d| d != 0.0).collect();
    let dala = alarms.iter().copied().fold(f64::INFINITY, f64::min);
    let lines = lines(a, &mesh, &mesh_name)?;
    let mut rows: Vec<Row> = Vec::new();
    for (occ, line) in occs.iter().zip(&lines) {
        let located: Vec<Option<Located>> = line.points.iter().map(|p| locator.locate(p, dmax)).collect();
        for (p, l) in line.points.iter().zip(&located) {
            if let Some(l) = l {
                if l.distance > dala {
                    ctx.io.mess(&format!(
                        " <A> MACR_LIGN_COUPE: the point ({}, {}, {}) is {} from the mesh, beyond DISTANCE_ALARME\n",
                        p[0], p[1], p[2], l.distance
                    ));
                }
            }
        }
        // Values at every point for every step (all components).
        let mut vals: Vec<Vec<Option<Vec<f64>>>> = steps
            .iter()
            .map(|(_, _, f)| located.iter().map(|l| l.as_ref().map(|l| values_at(f, &mesh, l))).collect())
            .collect();
        let wanted: Vec<String> = if occ.has("NOM_CMP") { occ.texts("NOM_CMP") } else { comps.clone() };
        let ks: Vec<usize> = wanted
            .iter()
            .map(|c| {
                comps.iter().position(|x| x == c).ok_or_else(|| {
                    occ.err(
                        "NOM_CMP",
                        format!("field {nom_cham} has no component {c} (components: {})", comps.join(", ")),
                    )
                })
            })
            .collect::<Result<_>>()?;
        // The points in the matter: a value of the first component asked (of any, without NOM_CMP) at some
        // step.
        let probe: Vec<usize> = if occ.has("NOM_CMP") { vec![ks[0]] } else { (0..comps.len()).collect() };
        let inside: Vec<bool> = (0..line.points.len())
            .map(|i| {
                !line.drops_outside
                    || vals.iter().any(|s| s[i].as_ref().is_some_and(|v| probe.iter().any(|&k| v[k].is_finite())))
            })
            .collect();
        if inside.iter().any(|x| !x) {
            let show = |keep: bool| -> String {
                line.points
                    .iter()
                    .zip(&inside)
                    .filter(|(_, &i)| i == keep)
                    .map(|(p, _)| format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2]))
                    .collect::<Vec<_>>()
                    .join("\n            ")
            };
            ctx.io.mess(&format!(
                " <A> <POST0_8> MACR_LIGN_COUPE: points of the line '{}' lie outside the matter and are left out.\n   \
                 points kept:\n            {}\n   points left out:\n            {}\n",
                line.intitule,
                show(true),
                show(false)
            ));
        }
        if !inside.iter().any(|&x| x) {
            return Err(occ.err("LIGN_COUPE", format!("no point of the line '{}' lies in the matter", line.intitule)));
        }
        let kept: Vec<usize> = (0..line.points.len()).filter(|&i| inside[i]).collect();
        let pts: Vec<[f64; 3]> = kept.iter().map(|&i| line.points[i]).collect();
        // The frame.
        if occ.text("REPERE").unwrap_or("GLOBAL") != "GLOBAL" {
            match turns(&nom_cham, dim) {
                Some(kind) => {
                    if let Some(fr) = frames(ctx, occ, line, dim)? {
                        for s in vals.iter_mut() {
                            for (v, p) in s.iter_mut().zip(&fr) {
                                if let Some(v) = v {
                                    turn(kind, p, &comps, v, dim);
                                }
                            }
                        }
                    }
                }
                None => ctx.io.mess(&format!(
                    " <A> <POST0_17> MACR_LIGN_COUPE: field {nom_cham} cannot be expressed in REPERE='{}': it is \
                     given in the global frame\n",
                    occ.text("REPERE").unwrap_or("")
                )),
            }
        }
        let mut absc = vec![0.0; pts.len()];
        for i in 1..pts.len() {
            let d = Vector3::from(pts[i]) - Vector3::from(pts[i - 1]);
            absc[i] = absc[i - 1] + d.norm();
        }
        let trac_nor = occ.text("TRAC_NOR") == Some("OUI");
        let invariant = occ.text("INVARIANT") == Some("OUI");
        if invariant && (tensor_prefix(&nom_cham).is_none() || occ.text("OPERATION") == Some("MOYENNE")) {
            return Err(occ.err(
                "INVARIANT",
                format!("INVARIANT of {nom_cham} (only of a tensor field, with EXTRACTION) is not supported yet"),
            ));
        }
        if trac_nor && dim != 2 {
            return Err(occ.err("TRAC_NOR", "TRAC_NOR on a line of a 3D mesh is not supported yet"));
        }
        let normals = line_normals(&pts);
        let moyenne = occ.text("OPERATION") == Some("MOYENNE");
        for (s, (nume, inst, _)) in steps.iter().enumerate() {
            let head = || -> Row {
                vec![
                    ("INTITULE".into(), Cell::Text(line.intitule.clone())),
                    ("NOM_CHAM".into(), Cell::Text(nom_cham.clone())),
                    ("NUME_ORDRE".into(), Cell::Int(*nume)),
                    ("INST".into(), Cell::Real(*inst)),
                ]
            };
            let at = |j: usize| vals[s][kept[j]].as_ref();
            if moyenne {
                let cols: Vec<Vec<f64>> = ks
                    .iter()
                    .map(|&k| (0..pts.len()).map(|j| at(j).map(|v| v[k]).unwrap_or(f64::NAN)).collect())
                    .collect();
                let m: Vec<[f64; 6]> = cols.iter().map(|c| moments(&absc, c)).collect();
                for (q, name) in
                    ["MOMENT_0", "MOMENT_1", "MINIMUM", "MAXIMUM", "MOYE_INT", "MOYE_EXT"].iter().enumerate()
                {
                    let mut row = head();
                    for (c, mc) in wanted.iter().zip(&m) {
                        row.push((c.clone(), real(mc[q])));
                    }
                    row.push(("QUANTITE".into(), Cell::Text(name.to_string())));
                    rows.push(row);
                }
                continue;
            }
            for j in 0..pts.len() {
                let mut row = head();
                row.push(("ABSC_CURV".into(), Cell::Real(absc[j])));
                for (k, name) in ["COOR_X", "COOR_Y", "COOR_Z"].iter().enumerate() {
                    row.push((name.to_string(), Cell::Real(pts[j][k])));
                }
                let v = at(j);
                if trac_nor {
                    row.extend(normal_trace(&nom_cham, &comps, v.map(|v| v.as_slice()), &ks, normals[j]));
                } else if invariant {
                    let inv = v.map(|v| invariants(&nom_cham, &comps, v));
                    for (k, name) in ["VMIS", "TRESCA", "TRACE", "DETER"].iter().enumerate() {
                        row.push((name.to_string(), inv.map(|i| real(i[k])).unwrap_or(Cell::Empty)));
                    }
                } else {
                    for (c, &k) in wanted.iter().zip(&ks) {
                        row.push((c.clone(), v.map(|v| real(v[k])).unwrap_or(Cell::Empty)));
                    }
                }
                if let Some(ang) = &line.angles {
                    row.push(("ANGLE".into(), Cell::Real(ang[kept[j]])));
                }
                rows.push(row);
            }
        }
    }
    // Columns: the fixed head, the components in order of first appearance, then the traces, QUANTITE and
    // ANGLE, as the macro's table orders them.
    const HEAD: [&str; 8] = ["INTITULE", "NOM_CHAM", "NUME_ORDRE", "INST", "ABSC_CURV", "COOR_X", "COOR_Y", "COOR_Z"];
    const TAIL: [&str; 10] =
        ["VMIS", "TRESCA", "TRACE", "DETER", "TRAC_NOR", "TR_NOR_1", "TR_NOR_2", "TR_NOR_3", "QUANTITE", "ANGLE"];
    let mut names: Vec<String> = HEAD.iter().map(|s| s.to_string()).collect();
    for r in &rows {
        for (n, _) in r {
            if !names.contains(n) && !TAIL.contains(&n.as_str()) {
                names.push(n.clone());
            }
        }
    }
    names.extend(TAIL.iter().map(|s| s.to_string()));
    let mut t = Table::default();
    for n in &names {
        let cells: Vec<Cell> = rows
            .iter()
            .map(|r| r.iter().find(|(k, _)| k == n).map(|(_, c)| c.clone()).unwrap_or(Cell::Empty))
            .collect();
        if cells.iter().all(Cell::is_empty) {
            continue;
        }
        let ty = match n.as_str() {
            "NUME_ORDRE" => ColType::I,
            "INTITULE" | "NOM_CHAM" | "QUANTITE" => ColType::K(16),
            _ => ColType::R,
        };
        t.add_column(n, ty, cells)?;
    }
    Ok(Some(ConceptData::Table(t)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_moments_of_a_linear_profile_are_its_mean_and_its_ends() {
        let s = [0.0, 0.5, 1.5, 2.0];
        let v: Vec<f64> = s.iter().map(|x| 3.0 + 2.0 * x).collect();
        let m = moments(&s, &v);
        let want = [5.0, 4.0, 3.0, 7.0, 3.0, 7.0];
        for (a, b) in m.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{m:?}");
        }
    }

    #[test]
    fn coordinates_go_through_the_mesh_files_format() {
        assert_eq!(written(0.1), 0.1);
        assert_eq!(written(1.0 / 3.0), 3.33333333333333e-1);
        assert_ne!(written(1.0 / 3.0), 1.0 / 3.0);
    }

    #[test]
    fn normals_of_a_line_turn_its_tangent() {
        let n = line_normals(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]);
        assert_eq!(n[0], [0.0, 1.0]);
        assert_eq!(n[1], [-0.5, 0.5]);
        assert_eq!(n[2], [-1.0, 0.0]);
    }

    #[test]
    fn invariants_of_a_tensor() {
        // σ = diag(3, 1, 0) + 2 (e_x e_y + e_y e_x): principal values 2 ± √5, 0.
        let names: Vec<String> = ["SIXX", "SIYY", "SIZZ", "SIXY"].iter().map(|s| s.to_string()).collect();
        let [vmis, tresca, trace, det] = invariants("SIGM_ELNO", &names, &[3.0, 1.0, 0.0, 2.0]);
        let (a, b, c, xy): (f64, f64, f64, f64) = (3.0, 1.0, 0.0, 2.0);
        let want = (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2)) + 3.0 * xy * xy).sqrt();
        assert!((vmis - want).abs() < 1e-12);
        assert!((tresca - 2.0 * 5f64.sqrt()).abs() < 1e-12, "{tresca}");
        assert_eq!(trace, 4.0);
        assert!(det.abs() < 1e-12);
    }

    #[test]
    fn a_tensor_turns_with_its_frame() {
        // σ = diag(1, 2, 3) in a frame turned by 90° about Z: XX and YY swap, XY stays 0.
        let p = axes(Frame::nautical(&[90.0]));
        let names: Vec<String> = ["SIXX", "SIYY", "SIZZ", "SIXY"].iter().map(|s| s.to_string()).collect();
        let mut v = vec![1.0, 2.0, 3.0, 0.0];
        turn(Turns::Tensor(&["SIXX", "SIYY", "SIZZ", "SIXY"]), &p, &names, &mut v, 2);
        for (a, b) in v.iter().zip([2.0, 1.0, 3.0, 0.0]) {
            assert!((a - b).abs() < 1e-12, "{v:?}");
        }
    }
}
