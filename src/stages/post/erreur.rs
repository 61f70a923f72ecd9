//! POST_ERREUR: error norms of one field against reference FORMULEs over groups of cells, as Code_Aster's
//! `post_erreur_ops` computes them.
//!
//! - DEPL_RELA: per group, REFERENCE = ‖u_ref‖_L2 and DIFFERENCE = ‖u_h − u_ref‖_L2, the integrals taken
//!   at the integration points Code_Aster uses: the RIGI family of each cell (skin cells with their own
//!   line or surface measure), and on an X-FEM model the sub-cell points of the cut cells, where u_h is
//!   recomposed from the standard and Heaviside unknowns of the sub-cell's region (skin cells dropped).
//! - ENER_RELA: per group, the elastic energies ½∫σᵀSσ (S the compliance of the cell's material) of σ_ref
//!   and of σ_h − σ_ref, σ_h the CHAM_GD field at its own points (SIEF_ELGA).
//! - LAGR_RELA: per group, the L2 norms of p_ref and p_h − p_ref on the group's skin cells, p_h the LAGS_C
//!   component of CHAM_GD interpolated from the group's nodes.
//!
//! A reference component not given is zero; the computed components all enter the difference. The
//! table has GROUP_MA (K8), DIFFERENCE, REFERENCE, one row per group then TOTAL, and ERREUR RELATIVE
//! (on the TOTAL row only) when the total reference is above 1e-16. The run log gets one line per call
//! with the totals.

use crate::catalog::args::Args;
use crate::concepts::model::{MaterialField, Model, Modelling, Role};
use crate::concepts::result::{Field, FieldData};
use crate::concepts::table::{Cell, ColType, Table};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::elasticity::{self, Modelisation};
use crate::fem::reference::{map_to_real, shape};
use crate::mesh::Mesh;
use crate::stages::core::eval::eval_named;
use crate::stages::core::problem::elastic_of;
use crate::stages::Ctx;
use crate::xfem::discrete::bulk_points;
use crate::xfem::model::XfemModel;
use std::collections::BTreeSet;
use std::rc::Rc;

/// One integration point of a cell: real coordinates, weight (measure, × r in AXIS), parent reference
/// coordinates, X-FEM region (0 outside cut cells).
#[derive(Debug, Clone, Copy)]
struct Point {
    x: [f64; 3],
    w: f64,
    xi: [f64; 3],
    region: i32,
}

/// The model as POST_ERREUR sees it.
struct Setting<'a> {
    mesh: Rc<Mesh>,
    model: &'a Model,
    xfem: Option<Rc<XfemModel>>,
    /// 2 or 3: the parameters X, Y (, Z) of the reference formulas and the compared components.
    dim: usize,
    md: Modelisation,
}

pub fn post_erreur(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let option = a.req_text("OPTION")?.to_string();
    let model_c = a.req_concept("MODELE")?;
    let model = model_c.model()?;
    let mesh = model.current_mesh();
    let md = modelisation(a, &model)?;
    let set = Setting { mesh: mesh.clone(), model: &model, xfem: model.xfem.clone(), dim: md.dim(), md };
    let groups = a.texts("GROUP_MA");
    let mesh_name = model.mesh_concept.label();
    let mut cells_of = Vec::with_capacity(groups.len());
    let mut seen = BTreeSet::new();
    for g in &groups {
        let cells = mesh
            .cell_groups
            .get(g)
            .ok_or_else(|| a.err("GROUP_MA", format!("the mesh {mesh_name} has no group of cells '{g}'")))?;
        // Code_Aster assembles the difference field group after group with CUMUL: a cell in two groups
        // gets both contributions, which no norm of the field means. Refuse rather than reproduce it.
        if let Some(c) = cells.iter().find(|c| seen.contains(*c)) {
            return Err(a.err(
                "GROUP_MA",
                format!(
                    "cell {} is in several of the groups {}: overlapping groups are not supported yet",
                    mesh.cell_names[*c],
                    groups.join(", ")
                ),
            ));
        }
        seen.extend(cells.iter().copied());
        cells_of.push(cells.clone());
    }
    let (rows, title, energy) = match option.as_str() {
        "DEPL_RELA" => (depl_rela(a, &set, &groups, &cells_of)?, "ERREUR EN NORME L2 DU DEPLACEMENT", false),
        "ENER_RELA" => (ener_rela(a, &set, &groups, &cells_of)?, "ERREUR EN NORME ENERGIE", true),
        _ => (lagr_rela(a, &set, &groups, &cells_of)?, "ERREUR EN NORME L2 DE LA PRESSION", false),
    };
    let (table, summary) = table(&groups, &rows, energy, title)?;
    ctx.io.mess(&format!("  POST_ERREUR OPTION={option} GROUP_MA={}: {summary}\n", groups.join(",")));
    Ok(Some(ConceptData::Table(table)))
}

/// The modelisation of the model's mechanical elements (one, as our solvers require).
fn modelisation(a: &Args, model: &Model) -> Result<Modelisation> {
    let mut found: Option<Modelling> = None;
    for e in model.elements.iter().flatten() {
        if e.phenomenon != "MECANIQUE" {
            return Err(a.err("MODELE", format!("the model is not mechanical (PHENOMENE='{}')", e.phenomenon)));
        }
        if found.is_some_and(|f| f != e.modelisation) {
            return Err(a.err("MODELE", "models mixing several modelisations are not supported yet"));
        }
        found = Some(e.modelisation);
    }
    let m = found.ok_or_else(|| a.err("MODELE", "the model has no element"))?;
    if m.is_hm() && model.xfem.is_some() {
        // Code_Aster refuses X-FEM HM models (XFEM_89).
        return Err(a.err("MODELE", format!("POST_ERREUR does not accept an X-FEM {m} model (Code_Aster's XFEM_89)")));
    }
    m.mechanics()
        .filter(|_| !m.is_hm())
        .ok_or_else(|| a.err("MODELE", format!("MODELISATION='{m}' is not supported yet by POST_ERREUR")))
}

/// The reference formulas of one component, one per group, or None when the component is not given.
fn formulas(a: &Args, comp: &str, ngroups: usize) -> Result<Option<Vec<ConceptRef>>> {
    if !a.has(comp) {
        return Ok(None);
    }
    let f = a.concepts(comp);
    if f.len() != ngroups {
        // Code_Aster's PREPOST_12.
        return Err(a.err(
            comp,
            format!("{comp} gives {} function(s) for {ngroups} group(s) of GROUP_MA: one per group is needed", f.len()),
        ));
    }
    Ok(Some(f))
}

/// A reference formula at a point: parameters X, Y (and Z in 3D) by name.
fn eval(f: &ConceptRef, x: &[f64; 3], dim: usize) -> Result<f64> {
    let arg = |p: &str| -> Result<f64> {
        match (p, dim) {
            ("X", _) => Ok(x[0]),
            ("Y", _) => Ok(x[1]),
            ("Z", 3) => Ok(x[2]),
            _ => Err(Error::runtime(format!(
                "{}: parameter {p} is not one of the coordinates of the integration points ({})",
                f.label(),
                if dim == 3 { "X, Y, Z" } else { "X, Y" }
            ))),
        }
    };
    eval_named(f, &arg)
}

/// Is the cell part of what the norms integrate over: in the model, and for an X-FEM model of the
/// model's dimension (Code_Aster filters the skin cells out there).
fn counted(set: &Setting, c: usize) -> Option<Role> {
    let e = set.model.elements.get(c)?.as_ref()?;
    if set.xfem.is_some() && e.role != Role::Bulk {
        return None;
    }
    Some(e.role)
}

/// The integration points of a cell of the model: the sub-cell points of an X-FEM cell, else the RIGI
/// rule of the bulk element or of the skin element.
fn points(a: &Args, set: &Setting, c: usize, role: Role) -> Result<Vec<Point>> {
    let mesh = &set.mesh;
    let t = mesh.cell_types[c];
    let coords: Vec<[f64; 3]> = mesh.cells[c].iter().map(|&n| mesh.coords[n]).collect();
    let name = &mesh.cell_names[c];
    let bad = |e: String| a.err("MODELE", format!("cell {name}: {e}"));
    let axis = set.md == Modelisation::Axis;
    if let Some(xm) = set.xfem.as_ref().filter(|xm| xm.cells.contains_key(&c)) {
        let pts = bulk_points(t, &coords, xm, c).map_err(bad)?;
        return Ok(pts
            .into_iter()
            .map(|p| {
                let x = map_to_real(t, &coords, &p.xi);
                Point { x, w: if axis { p.w * x[0] } else { p.w }, xi: p.xi, region: p.region }
            })
            .collect());
    }
    let rule = match role {
        Role::Bulk => elasticity::rigi_rule_of(set.md, t),
        Role::Skin => elasticity::boundary_rule(t),
    };
    match role {
        Role::Bulk => {
            let gg = elasticity::gauss_geometry(set.md, t, &coords, &rule).map_err(|e| bad(e.to_string()))?;
            Ok(gg.iter().zip(&rule.points).map(|(g, xi)| Point { x: g.x, w: g.w, xi: *xi, region: 0 }).collect())
        }
        Role::Skin => {
            let bp = elasticity::boundary_points(set.md, t, &coords).map_err(|e| bad(e.to_string()))?;
            Ok(bp.iter().zip(&rule.points).map(|(g, xi)| Point { x: g.x, w: g.w, xi: *xi, region: 0 }).collect())
        }
    }
}

/// The nodal field of CHAM_GD, checked to lie on the model's mesh.
fn node_field(a: &Args, set: &Setting) -> Result<(Vec<String>, Vec<f64>)> {
    let fc = a.req_concept("CHAM_GD")?;
    let fd = fc.field()?;
    check_mesh(a, set, &fd, &fc)?;
    match &fd.field {
        Field::Node { components, values } if fd.functions.is_none() => Ok((components.clone(), values.clone())),
        _ => Err(a.err("CHAM_GD", format!("{} is not a field of real values at nodes", fc.label()))),
    }
}

fn check_mesh(a: &Args, set: &Setting, fd: &FieldData, fc: &ConceptRef) -> Result<()> {
    if !Rc::ptr_eq(&fd.mesh_concept, &set.model.mesh_concept) {
        return Err(a.err(
            "CHAM_GD",
            format!(
                "{} lies on mesh {}, the model on {}",
                fc.label(),
                fd.mesh_concept.label(),
                set.model.mesh_concept.label()
            ),
        ));
    }
    Ok(())
}

/// The value of component `k` at node `n`, which must carry it.
fn nodal(a: &Args, mesh: &Mesh, comps: &[String], values: &[f64], n: usize, k: usize) -> Result<f64> {
    let v = values[n * comps.len() + k];
    if v.is_nan() {
        return Err(a.err("CHAM_GD", format!("the field has no {} at node {}", comps[k], mesh.node_names[n])));
    }
    Ok(v)
}

/// Per group: (DIFFERENCE, REFERENCE) as the table holds them.
type Rows = Vec<(f64, f64)>;

fn depl_rela(a: &Args, set: &Setting, groups: &[String], cells_of: &[Vec<usize>]) -> Result<Rows> {
    let xyz = ["DX", "DY", "DZ"];
    let refs: Vec<Option<Vec<ConceptRef>>> = xyz.iter().map(|c| formulas(a, c, groups.len())).collect::<Result<_>>()?;
    // CHAM_MATER is read by Code_Aster only for X-FEM cracks with tip enrichment; interfaces need none.
    let _ = a.concept("CHAM_MATER");
    let (comps, values) = node_field(a, set)?;
    let mesh = &set.mesh;
    let dim = set.dim;
    let idx = |name: &str| comps.iter().position(|c| c == name);
    let kd: Vec<usize> = xyz[..dim]
        .iter()
        .map(|c| idx(c).ok_or_else(|| a.err("CHAM_GD", format!("the field has no component {c}"))))
        .collect::<Result<_>>()?;
    // Heaviside components of node sets: H<j><X|Y|Z>.
    let kh = |j: usize, d: usize| idx(&format!("H{}{}", j + 1, ["X", "Y", "Z"][d]));
    let mut rows = Vec::new();
    for (gi, cells) in cells_of.iter().enumerate() {
        let (mut diff, mut refe) = (0.0, 0.0);
        for &c in cells {
            let Some(role) = counted(set, c) else { continue };
            let t = mesh.cell_types[c];
            let nodes = &mesh.cells[c];
            // Components in the layout of the element's DEPL at points: DX, DY in 2D bulk cells, DX, DY,
            // DZ in 3D and skin cells; only the first `dim` enter the difference.
            let nref = if role == Role::Bulk { dim } else { 3 };
            for p in points(a, set, c, role)? {
                let n = shape(t, &p.xi);
                let mut uh = [0.0; 3];
                for (ia, &node) in nodes.iter().enumerate() {
                    for d in 0..dim {
                        let mut v = nodal(a, mesh, &comps, &values, node, kd[d])?;
                        if let Some(xm) = &set.xfem {
                            for j in 0..xm.node_sets[node].len() {
                                let psi = xm.psi(node, j, p.region);
                                if psi != 0.0 {
                                    let k = kh(j, d).ok_or_else(|| {
                                        a.err("CHAM_GD", format!("the field has no Heaviside component H{}", j + 1))
                                    })?;
                                    v += psi * nodal(a, mesh, &comps, &values, node, k)?;
                                }
                            }
                        }
                        uh[d] += n[ia] * v;
                    }
                }
                let mut ur = [0.0; 3];
                for (d, r) in refs.iter().enumerate().take(nref) {
                    if let Some(f) = r {
                        ur[d] = eval(&f[gi], &p.x, dim).map_err(|e| a.locate(e, xyz[d]))?;
                    }
                }
                refe += p.w * ur[..nref].iter().map(|v| v * v).sum::<f64>();
                diff += p.w * (0..dim).map(|d| (uh[d] - ur[d]).powi(2)).sum::<f64>();
            }
        }
        rows.push((diff.sqrt(), refe.sqrt()));
    }
    Ok(rows)
}

const SIG: [&str; 6] = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];

fn ener_rela(a: &Args, set: &Setting, groups: &[String], cells_of: &[Vec<usize>]) -> Result<Rows> {
    let _ = a.req_text("DEFORMATION")?; // 'PETIT', the only value the catalogue allows
    if groups.len() > 1 {
        // POST_ELEM ENER_ELAS adds a UNION_GROUP_MA row that the macro does not expect (DVP_9).
        return Err(a.err(
            "GROUP_MA",
            "OPTION='ENER_RELA' over several groups stops in Code_Aster (an assertion on the energy table); \
             give one group",
        ));
    }
    let refs: Vec<Option<Vec<ConceptRef>>> = SIG.iter().map(|c| formulas(a, c, groups.len())).collect::<Result<_>>()?;
    let chmat = a.req_concept("CHAM_MATER")?;
    let fc = a.req_concept("CHAM_GD")?;
    let fd = fc.field()?;
    check_mesh(a, set, &fd, &fc)?;
    let (comps, cellvals) = match &fd.field {
        Field::Elga { components, cells } if fd.functions.is_none() => (components, cells),
        _ => return Err(a.err("CHAM_GD", format!("{} is not a field of real values at Gauss points", fc.label()))),
    };
    let mesh = &set.mesh;
    let dim = set.dim;
    // The compared components: SIXX SIYY SIZZ SIXY in 2D, the six in 3D.
    let ncmp = 2 * dim;
    let ks: Vec<usize> = SIG[..ncmp]
        .iter()
        .map(|c| {
            comps
                .iter()
                .position(|x| x == c)
                .ok_or_else(|| a.err("CHAM_GD", format!("{} has no component {c}", fc.label())))
        })
        .collect::<Result<_>>()?;
    let mats = match &*chmat.data() {
        ConceptData::MaterialField(MaterialField { varc, .. }) if !varc.is_empty() => {
            return Err(a.err(
                "CHAM_MATER",
                format!("{}: the energy norm with AFFE_VARC's thermal strain is not supported yet", chmat.label()),
            ))
        }
        ConceptData::MaterialField(MaterialField { cells, .. }) => cells.clone(),
        _ => return Err(a.err("CHAM_MATER", format!("{} is not a material field", chmat.label()))),
    };
    let mut rows = Vec::new();
    for (gi, cells) in cells_of.iter().enumerate() {
        let (mut ediff, mut eref) = (0.0, 0.0);
        for &c in cells {
            // Skin cells have no elastic energy.
            if counted(set, c) != Some(Role::Bulk) {
                continue;
            }
            let name = &mesh.cell_names[c];
            let mc = mats[c]
                .clone()
                .ok_or_else(|| a.err("CHAM_MATER", format!("cell {name} has no material in {}", chmat.label())))?;
            let law = match &*mc.data() {
                ConceptData::Material(m) => elastic_of(m, name).map_err(|e| a.locate(e, "CHAM_MATER"))?.0,
                _ => return Err(a.err("CHAM_MATER", format!("{} is not a material", mc.label()))),
            };
            let s = compliance(&law.hooke(Modelisation::ThreeD))
                .ok_or_else(|| a.err("CHAM_MATER", format!("cell {name}: the Hooke matrix is singular")))?;
            let pts = points(a, set, c, Role::Bulk)?;
            let vals = cellvals
                .get(c)
                .and_then(|v| v.as_ref())
                .ok_or_else(|| a.err("CHAM_GD", format!("{} has no value on cell {name}", fc.label())))?;
            let nc = comps.len();
            if vals.len() != pts.len() * nc {
                return Err(a.err(
                    "CHAM_GD",
                    format!(
                        "{} has {} point(s) on cell {name}, where the model integrates on {}",
                        fc.label(),
                        vals.len() / nc,
                        pts.len()
                    ),
                ));
            }
            // Components the compliance couples: C_PLAN ignores σzz.
            let used: Vec<usize> = match set.md {
                Modelisation::CPlan => vec![0, 1, 3],
                Modelisation::ThreeD => (0..6).collect(),
                _ => vec![0, 1, 2, 3],
            };
            for (ip, p) in pts.iter().enumerate() {
                let mut sr = [0.0; 6];
                let mut sd = [0.0; 6];
                for (q, &k) in ks.iter().enumerate() {
                    if let Some(f) = &refs[q] {
                        sr[q] = eval(&f[gi], &p.x, dim).map_err(|e| a.locate(e, SIG[q]))?;
                    }
                    sd[q] = vals[ip * nc + k] - sr[q];
                }
                eref += p.w * energy_density(&s, &sr, &used);
                ediff += p.w * energy_density(&s, &sd, &used);
            }
        }
        rows.push((ediff, eref));
    }
    Ok(rows)
}

/// ½ σᵀ S σ over the components `used` (Voigt order xx yy zz xy xz yz, tensorial shear stresses; S the
/// compliance on engineering strains).
fn energy_density(s: &[[f64; 6]; 6], sig: &[f64; 6], used: &[usize]) -> f64 {
    let mut e = 0.0;
    for &i in used {
        for &j in used {
            e += sig[i] * s[i][j] * sig[j];
        }
    }
    0.5 * e
}

/// The inverse of a 6×6 Hooke matrix (Gauss–Jordan with partial pivoting), None when singular.
#[allow(clippy::needless_range_loop)]
fn compliance(d: &[[f64; 6]; 6]) -> Option<[[f64; 6]; 6]> {
    let mut m = *d;
    let mut inv = [[0.0; 6]; 6];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let scale = d.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    for col in 0..6 {
        let piv = (col..6).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        if m[piv][col].abs() <= 1e-14 * scale || m[piv][col].is_nan() {
            return None;
        }
        m.swap(col, piv);
        inv.swap(col, piv);
        let p = m[col][col];
        for k in 0..6 {
            m[col][k] /= p;
            inv[col][k] /= p;
        }
        for r in 0..6 {
            if r != col {
                let f = m[r][col];
                if f != 0.0 {
                    for k in 0..6 {
                        m[r][k] -= f * m[col][k];
                        inv[r][k] -= f * inv[col][k];
                    }
                }
            }
        }
    }
    Some(inv)
}

fn lagr_rela(a: &Args, set: &Setting, groups: &[String], cells_of: &[Vec<usize>]) -> Result<Rows> {
    if set.xfem.is_some() {
        // Code_Aster's XFEM_14.
        return Err(a.err("MODELE", "OPTION='LAGR_RELA' does not accept an X-FEM model"));
    }
    // Code_Aster reads LAGS_C unconditionally: without it the macro stops.
    let refs = formulas(a, "LAGS_C", groups.len())?
        .ok_or_else(|| a.err("LAGS_C", "OPTION='LAGR_RELA' needs the reference function LAGS_C"))?;
    let (comps, values) = node_field(a, set)?;
    let k = comps.iter().position(|c| c == "LAGS_C").ok_or_else(|| a.err("CHAM_GD", "the field has no LAGS_C"))?;
    let mesh = &set.mesh;
    let mut rows = Vec::new();
    for (gi, cells) in cells_of.iter().enumerate() {
        let (mut diff, mut refe) = (0.0, 0.0);
        for &c in cells {
            // The pressure rides on DZ, which only skin elements carry in 2D (and every element in 3D).
            let Some(role) = counted(set, c) else { continue };
            if set.dim == 2 && role == Role::Bulk {
                continue;
            }
            let t = mesh.cell_types[c];
            for p in points(a, set, c, role)? {
                let n = shape(t, &p.xi);
                let mut ph = 0.0;
                for (ia, &node) in mesh.cells[c].iter().enumerate() {
                    ph += n[ia] * nodal(a, mesh, &comps, &values, node, k)?;
                }
                let pr = eval(&refs[gi], &p.x, set.dim).map_err(|e| a.locate(e, "LAGS_C"))?;
                refe += p.w * pr * pr;
                diff += p.w * (ph - pr).powi(2);
            }
        }
        rows.push((diff.sqrt(), refe.sqrt()));
    }
    Ok(rows)
}

/// Code_Aster's table: the groups (names as K8) then TOTAL; ERREUR RELATIVE on the TOTAL row when the
/// total reference exceeds 1e-16. Also the one-line summary for the run log.
fn table(groups: &[String], rows: &Rows, energy: bool, title: &str) -> Result<(Table, String)> {
    let (dtot, rtot) = if energy {
        (rows.iter().map(|r| r.0).sum::<f64>(), rows.iter().map(|r| r.1).sum::<f64>())
    } else {
        (rows.iter().map(|r| r.0 * r.0).sum::<f64>().sqrt(), rows.iter().map(|r| r.1 * r.1).sum::<f64>().sqrt())
    };
    let (dnorm, rnorm) = if energy { (dtot.sqrt(), rtot.sqrt()) } else { (dtot, rtot) };
    let rel = (rnorm > 1e-16).then(|| dnorm / rnorm);
    let k8 = |s: &str| s.chars().take(8).collect::<String>();
    let mut names: Vec<Cell> = groups.iter().map(|g| Cell::Text(k8(g))).collect();
    names.push(Cell::Text("TOTAL".into()));
    let mut diffs: Vec<Cell> = rows.iter().map(|r| Cell::Real(r.0)).collect();
    diffs.push(Cell::Real(dtot));
    let mut refs: Vec<Cell> = rows.iter().map(|r| Cell::Real(r.1)).collect();
    refs.push(Cell::Real(rtot));
    let mut rels: Vec<Cell> = vec![Cell::Empty; groups.len()];
    if let Some(e) = rel {
        // CALC_TABLE COMB on GROUP_MA: a user group named TOTAL makes the key ambiguous, and the merged
        // row is appended instead.
        if groups.iter().any(|g| k8(g) == "TOTAL") {
            rels.push(Cell::Empty);
            names.push(Cell::Text("TOTAL".into()));
            diffs.push(Cell::Empty);
            refs.push(Cell::Empty);
        }
        rels.push(Cell::Real(e));
    }
    let mut t = Table { title: title.to_string(), ..Table::default() };
    t.add_column("GROUP_MA", ColType::K(8), names)?;
    t.add_column("DIFFERENCE", ColType::R, diffs)?;
    t.add_column("REFERENCE", ColType::R, refs)?;
    if rel.is_some() {
        t.add_column("ERREUR RELATIVE", ColType::R, rels)?;
    }
    let summary = match rel {
        Some(e) => format!("ERREUR RELATIVE = {e:.6e} (DIFFERENCE {dtot:.6e}, REFERENCE {rtot:.6e})"),
        None => format!("REFERENCE is zero, no relative error (DIFFERENCE {dtot:.6e}, REFERENCE {rtot:.6e})"),
    };
    Ok((t, summary))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compliance_of_an_isotropic_material() {
        let law = elasticity::IsoElastic::new(200.0, 0.25);
        let s = compliance(&law.hooke(Modelisation::ThreeD)).unwrap();
        assert!((s[0][0] - 1.0 / 200.0).abs() < 1e-15);
        assert!((s[0][1] + 0.25 / 200.0).abs() < 1e-15);
        // Engineering shear: 1/G = 2(1+ν)/E.
        assert!((s[3][3] - 2.5 / 200.0).abs() < 1e-15);
        // ½σᵀSσ of a uniaxial stress: σ²/2E.
        let w = energy_density(&s, &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0], &[0, 1, 2, 3, 4, 5]);
        assert!((w - 100.0 / 400.0).abs() < 1e-14);
    }

    #[test]
    fn the_table_has_code_asters_columns_and_total() {
        let (t, _) = table(&["SURFACE_A".into(), "B".into()], &vec![(3.0, 6.0), (4.0, 8.0)], false, "T").unwrap();
        let names: Vec<&str> = t.columns.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["GROUP_MA", "DIFFERENCE", "REFERENCE", "ERREUR RELATIVE"]);
        assert_eq!(t.columns[0].cells[0], Cell::Text("SURFACE_".into()));
        assert_eq!(t.columns[1].cells[2], Cell::Real(5.0));
        assert_eq!(t.columns[2].cells[2], Cell::Real(10.0));
        assert_eq!(t.columns[3].cells[2], Cell::Real(0.5));
        assert!(t.columns[3].cells[0].is_empty());
        // Energies add up; the relative error is the ratio of their square roots.
        let (t, _) = table(&["S".into()], &vec![(1.0, 4.0)], true, "T").unwrap();
        assert_eq!(t.columns[3].cells[1], Cell::Real(0.5));
        // A zero reference: no ERREUR RELATIVE column.
        let (t, _) = table(&["S".into()], &vec![(1.0, 0.0)], true, "T").unwrap();
        assert_eq!(t.columns.len(), 3);
    }
}
