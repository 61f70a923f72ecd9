//! CALC_CHAMP: fields computed from a result (strains, stresses at nodes, equivalent stresses, SIRO_ELEM).

use crate::catalog::args::Args;
use crate::concepts::model::Role;
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::postpro::{elastic_energy, equivalent_stresses, to_nodes, SIEQ_COMPONENTS};
use crate::mesh::CellType;
use crate::stages::Ctx;
use nalgebra::{Matrix3, Vector3};
use std::collections::HashSet;

use crate::fem::elasticity::{self, Modelisation};
use crate::fem::geometry::{bounded_cells, cell_coords, node_to_cells};
use crate::fem::reference::{node_coords, shape_deriv};
use crate::stages::core::problem::{coords_of, problem, problem_at_ref, Problem};
/// Component names of SIRO_ELEM, in Code_Aster's order (`EPJSIGM`).
pub const SIRO_COMPONENTS: [&str; 16] = [
    "SIG_NX", "SIG_NY", "SIG_NZ", "SIG_N", "SIG_TX", "SIG_TY", "SIG_TZ", "SIG_T1X", "SIG_T1Y", "SIG_T1Z", "SIG_T1",
    "SIG_T2X", "SIG_T2Y", "SIG_T2Z", "SIG_T2", "SIG_TN",
];

/// The rosette of a plane skin cell (a segment of a 2D model): its node
/// coordinates and the mean stress tensor (SIXX, SIYY, SIZZ, SIXY) over its
/// nodes give the 16 components of [`SIRO_COMPONENTS`]; None for a
/// degenerate segment.
pub fn rosette_2d(t: CellType, coords: &[[f64; 3]], sig: [f64; 4]) -> Option<[f64; 16]> {
    // Mean tangent over the nodes (the shape derivatives at each node).
    let mut t1 = [0.0; 3];
    for xi in node_coords(t) {
        for (g, x) in shape_deriv(t, xi).iter().zip(coords) {
            for k in 0..2 {
                t1[k] += g[0] * x[k];
            }
        }
    }
    // A zero or non-finite tangent: a degenerate segment.
    let unit = |v: Vector3<f64>| v.try_normalize(0.0).filter(|u| u.iter().all(|x| x.is_finite()));
    let t1 = unit(Vector3::from(t1))?;
    let n = unit(t1.cross(&Vector3::z()))?;
    let t2 = n.cross(&t1);
    let s = Matrix3::new(sig[0], sig[3], 0.0, sig[3], sig[1], 0.0, 0.0, 0.0, sig[2]);
    let (sn, st1, st2) = (s * n, s * t1, s * t2);
    Some([
        sn[0],
        sn[1],
        sn[2],
        n.dot(&sn),
        st1[0],
        st1[1],
        st1[2],
        st1[0],
        st1[1],
        st1[2],
        t1.dot(&st1),
        st2[0],
        st2[1],
        st2[2],
        t2.dot(&st2),
        t1.dot(&sn),
    ])
}

/// SIRO_ELEM of one displacement field: on every skin cell of the model that
/// `only` keeps, the rosette of the stress of the bulk cell it bounds (the
/// first one, in cell order, when it lies between two).
pub fn siro_elem(p: &Problem, model: &ConceptRef, depl: &[f64], only: &dyn Fn(&usize) -> bool) -> Result<Field> {
    let mesh = &p.mesh;
    let md = p.modelisation;
    if md == Modelisation::ThreeD {
        return Err(Error::runtime("SIRO_ELEM on 3D models is not supported yet (plane models are)"));
    }
    let dim = md.dim();
    let m = model.model()?;
    let node_cells = node_to_cells(mesh);
    let bulk: HashSet<usize> = p.bulk.iter().copied().collect();
    let mut cells = vec![None; mesh.cells.len()];
    for (c, e) in m.elements.iter().enumerate() {
        if e.as_ref().map(|e| e.role) != Some(Role::Skin) || !only(&c) || mesh.cell_types[c].dim() != dim - 1 {
            continue;
        }
        let Some(&v) = bounded_cells(mesh, &node_cells, c, Some(&bulk)).first() else { continue };
        let ue: Vec<f64> = mesh.cells[v].iter().flat_map(|&nd| (0..dim).map(move |k| depl[nd * dim + k])).collect();
        let mat = &p.materials[v].as_ref().expect("bulk cells have a material").0;
        let (_, sig) = elasticity::node_fields(md, mat, mesh.cell_types[v], &cell_coords(mesh, v), &ue)
            .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[v])))?;
        let mut mean = [0.0; 4];
        for nd in &mesh.cells[c] {
            let i = mesh.cells[v].iter().position(|x| x == nd).expect("a bounded cell holds the skin's nodes");
            for (k, m) in mean.iter_mut().enumerate() {
                *m += sig[i][k] / mesh.cells[c].len() as f64;
            }
        }
        let r = rosette_2d(mesh.cell_types[c], &cell_coords(mesh, c), mean)
            .ok_or_else(|| Error::runtime(format!("SIRO_ELEM: cell {} is degenerate", mesh.cell_names[c])))?;
        cells[c] = Some(r.to_vec());
    }
    Ok(Field::Elem { components: SIRO_COMPONENTS.iter().map(|s| s.to_string()).collect(), cells })
}

// ------------------------------------------------------------------ CALC_CHAMP

/// The points of a cell's `*_ELGA` values of `n` components.
fn points_of(v: &[f64], n: usize) -> Vec<[f64; 6]> {
    v.chunks(n)
        .map(|c| {
            let mut p = [0.0; 6];
            p[..n.min(6)].copy_from_slice(&c[..n.min(6)]);
            p
        })
        .collect()
}

/// The first `n` components of each point, flattened.
fn flat(v: &[[f64; 6]], n: usize) -> Vec<f64> {
    v.iter().flat_map(|p| p[..n].to_vec()).collect()
}

/// The steps CALC_CHAMP is asked for.
enum Asked {
    All,
    Orders(Vec<i64>),
    /// What the result lacks (`order 3`, `instant 2.5`).
    Missing(String),
}

/// NUME_ORDRE / LIST_ORDRE / INST / LIST_INST (CRITERE, PRECISION) against the steps of the result.
fn asked_orders(a: &Args, steps: &[Step]) -> Result<Asked> {
    let list = |kw: &str| -> Result<Option<Vec<f64>>> {
        a.concept(kw).map(|c| c.reals().map_err(|e| a.err(kw, e.msg))).transpose()
    };
    let orders: Option<Vec<i64>> = if a.has("NUME_ORDRE") {
        Some(a.ints("NUME_ORDRE"))
    } else {
        list("LIST_ORDRE")?.map(|v| v.iter().map(|&x| x as i64).collect())
    };
    if let Some(orders) = orders {
        let missing: Vec<String> =
            orders.iter().filter(|n| !steps.iter().any(|s| s.nume_ordre == **n)).map(|n| n.to_string()).collect();
        return Ok(if missing.is_empty() {
            Asked::Orders(orders)
        } else {
            Asked::Missing(format!("order {}", missing.join(", ")))
        });
    }
    let times = if a.has("INST") { Some(a.reals("INST")) } else { list("LIST_INST")? };
    let Some(times) = times else { return Ok(Asked::All) };
    let crit = a.text("CRITERE").unwrap_or("RELATIF");
    let prec = a.real("PRECISION").unwrap_or(1.0e-6);
    let mut found = Vec::new();
    let mut missing = Vec::new();
    for t in times {
        let tol = if crit == "ABSOLU" { prec } else { prec * t.abs() };
        match steps.iter().find(|s| (s.inst - t).abs() <= tol) {
            Some(s) => found.push(s.nume_ordre),
            None => missing.push(crate::text::float_repr(t)),
        }
    }
    Ok(if missing.is_empty() {
        Asked::Orders(found)
    } else {
        Asked::Missing(format!("instant {} (CRITERE='{crit}', PRECISION={prec})", missing.join(", ")))
    })
}

/// op0052: a step the result does not have stops the command, with an alarm; the result is unchanged.
fn nothing_computed(ctx: &mut Ctx, rc: &ConceptRef, what: &str, steps: Vec<Step>) -> Result<ConceptData> {
    ctx.io.mess(&format!(" <A> <ALGORITH3_41> CALC_CHAMP: result {} has no {what}: nothing is computed\n", rc.label()));
    let r = rc.result()?;
    Ok(ConceptData::Result(ResultData {
        model: r.model.clone(),
        material: r.material.clone(),
        cara_elem: r.cara_elem.clone(),
        loads: r.loads.clone(),
        steps,
        comportement: Vec::new(),
    }))
}

pub fn calc_champ(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    const DONE: &[&str] = &[
        "SIGM_ELNO",
        "SIGM_NOEU",
        "EPSI_ELNO",
        "EPSI_NOEU",
        "SIEF_ELGA",
        "SIGM_ELGA",
        "EPSI_ELGA",
        "SIRO_ELEM",
        "SIEQ_ELNO",
        "SIEQ_NOEU",
        "SIEQ_ELGA",
        "SIEF_ELNO",
        "SIEF_NOEU",
        "EPSP_ELGA",
        "ENEL_ELGA",
        "ENEL_ELNO",
        "ETOT_ELGA",
        "EPSP_ELNO",
        "VARI_ELNO",
        "VARI_NOEU",
        "FORC_NODA",
    ];
    let rc = a.req_concept("RESULTAT")?;
    let (model, chmat, mut steps) = {
        let r = rc.result()?;
        let chmat = r.material.clone().ok_or_else(|| a.err("RESULTAT", "the result has no material field"))?;
        (r.model.clone(), chmat, r.steps.clone())
    };
    if model.model()?.xfem.is_some() {
        // The fields of an X-FEM result live on the sub-cells, with the Heaviside unknowns: the classical
        // element computations below would ignore the enrichment.
        return Err(a.err(
            "RESULTAT",
            format!("CALC_CHAMP on a result of the X-FEM model {} is not supported yet", model.label()),
        ));
    }
    if model.model()?.is_thermal() {
        let orders = match asked_orders(a, &steps)? {
            Asked::All => Vec::new(),
            Asked::Orders(o) => o,
            Asked::Missing(what) => return Ok(Some(nothing_computed(ctx, &rc, &what, steps)?)),
        };
        return super::thermal::calc_champ_ther(a, &rc, &model, &chmat, steps, &orders);
    }
    a.refuse(&["THERMIQUE"])?;
    let hm = model.model()?.elements.iter().flatten().any(|e| e.modelisation.is_hm()) && model.model()?.xfem.is_none();
    let mut wanted = Vec::new();
    let kws: &[&str] = if hm {
        &["CONTRAINTE", "DEFORMATION", "CRITERES", "VARI_INTERNE", "FORCE"]
    } else {
        &["CONTRAINTE", "DEFORMATION", "CRITERES", "VARI_INTERNE", "FORCE", "ENERGIE"]
    };
    for kw in kws {
        for o in a.texts(kw) {
            let known = if hm { super::hm::OPTIONS.contains(&o.as_str()) } else { DONE.contains(&o.as_str()) };
            if !known {
                return Err(a.err(kw, format!("option {o} is not supported yet")));
            }
            wanted.push(o);
        }
    }
    a.refuse(&["ERREUR", "EQUI", "CHAM_UTIL", "HYDRAULIQUE", "PROPRIETES"])?;
    if hm {
        a.refuse(&["ENERGIE"])?;
    }
    let mesh = model.model()?.current_mesh();
    let restrict = if a.has("GROUP_MA") || a.has("MAILLE") {
        Some(crate::stages::select::select_cells(&mesh, a, &model.model()?.mesh_concept.label())?)
    } else {
        None
    };
    let only = |c: &usize| restrict.as_ref().map(|r| r.contains(c)).unwrap_or(true);
    // The result's own model and material are used; other step selections are not implemented.
    a.refuse(&[
        "MODELE",
        "CHAM_MATER",
        "FREQ",
        "LIST_FREQ",
        "NUME_MODE",
        "NOM_CAS",
        "NOEUD_CMP",
        "CARA_ELEM",
        "EXCIT",
    ])?;
    let _ = a.text("TOUT_ORDRE"); // every step: the default
    let orders = match asked_orders(a, &steps)? {
        Asked::All => Vec::new(),
        Asked::Orders(o) => o,
        Asked::Missing(what) => return Ok(Some(nothing_computed(ctx, &rc, &what, steps)?)),
    };
    if hm {
        let passed_over = super::hm::calc_champ_hm(a, &wanted, &mut steps, &model, &chmat, &only, &orders)?;
        if !passed_over.is_empty() {
            let list: Vec<String> = passed_over.iter().map(|n| n.to_string()).collect();
            ctx.io.mess(&format!(
                " <A> CALC_CHAMP: result {} holds no SIEF_ELGA and VARI_ELGA at order {}: nothing is computed there\n",
                rc.label(),
                list.join(", ")
            ));
        }
        let r = rc.result()?;
        let data = r.with_steps(steps);
        return Ok(Some(ConceptData::Result(data)));
    }
    // A plastic result under AFFE_VARC's temperature holds its stresses: its materials (which may depend on
    // TEMP) serve the strains only, taken at VALE_REF; the options that need the law at the temperature
    // stop by name.
    let plastic_varc = crate::stages::core::settings::has_varc(&chmat)
        && !steps.is_empty()
        && steps.iter().all(|s| s.fields.contains_key("VARI_ELGA") && s.fields.contains_key("SIEF_ELGA"));
    if plastic_varc {
        if let Some(o) = wanted.iter().find(|o| o.starts_with("EPSP_")) {
            return Err(a.err("DEFORMATION", format!("{o} of a plastic result under AFFE_VARC is not supported yet")));
        }
    }
    let p = if plastic_varc { problem_at_ref(&model, &chmat) } else { problem(&model, &chmat) }
        .map_err(|e| e.at(a.span))?;
    // AFFE_VARC's thermal strain: the stresses are D (ε − ε_th), at each step's instant.
    let thermal = match plastic_varc {
        true => None,
        false => crate::stages::core::problem::thermal_strain(&chmat, &p).map_err(|e| e.at(a.span))?,
    };
    // ENEL: the elastic energy density ½ σ : S σ of ELAS (te0575, enelpg with small strains).
    if wanted.iter().any(|o| o.starts_with("ENEL_")) && plastic_varc {
        constant_elasticity(&chmat, &p).map_err(|e| a.locate(e, "ENERGIE"))?;
    }
    let mesh = &p.mesh;
    let md = p.modelisation;
    let etot = wanted.iter().any(|o| o == "ETOT_ELGA");
    if etot && !orders.is_empty() {
        return Err(a.err("ENERGIE", "ETOT_ELGA on some orders only is not supported yet (it sums over every step)"));
    }
    // ETOT: the work of the stresses summed over the steps in their order (the strains and stresses and
    // the sum of the step before).
    type Points = Vec<Option<Vec<f64>>>;
    let mut before: Option<(Points, Points, Points)> = None;
    steps.sort_by_key(|s| s.nume_ordre);
    for step in steps.iter_mut() {
        if !orders.is_empty() && !orders.contains(&step.nume_ordre) {
            continue;
        }
        let thetas = match &thermal {
            Some(th) => th.theta(mesh, &p.bulk, step.inst).map_err(|e| e.at(a.span))?,
            None => vec![None; mesh.cells.len()],
        };
        let Some(Field::Node { values: depl, .. }) = step.fields.get("DEPL") else {
            return Err(a.err("RESULTAT", format!("no DEPL at order {}", step.nume_ordre)));
        };
        // A result of a plastic law holds its stresses and internal variables at the points: the fields
        // of stresses come from them (extrapolated to the nodes as Code_Aster's ELNO options do), the
        // others from DEPL.
        let stored = |name: &str| match step.fields.get(name) {
            Some(Field::Elga { cells, .. }) if step.fields.contains_key("VARI_ELGA") => Some(cells.clone()),
            _ => None,
        };
        let (plastic_sig, plastic_vari) = (stored("SIEF_ELGA"), stored("VARI_ELGA"));
        let vari_names: Vec<String> = step.fields.get("VARI_ELGA").map(|f| f.components().to_vec()).unwrap_or_default();
        if plastic_vari.is_none() {
            if let Some(o) = wanted.iter().find(|o| o.starts_with("VARI_") || o.starts_with("EPSP_")) {
                return Err(a.err(
                    if o.starts_with("VARI_") { "VARI_INTERNE" } else { "DEFORMATION" },
                    format!(
                        "{o}: result {} holds no internal variables (VARI_ELGA) at order {}",
                        rc.label(),
                        step.nume_ordre
                    ),
                ));
            }
        }
        let ns = md.nsig();
        let (mut sig_elno, mut eps_elno) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        let (mut sig_elga, mut eps_elga) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        let (mut epsp_elga, mut epsp_elno) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        let mut vari_elno = vec![None; mesh.cells.len()];
        let (mut enel_elga, mut enel_elno) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        // FORC_NODA on the nodes of the model (NaN elsewhere, as DEPL).
        let mut forc_noda: Vec<f64> = depl.iter().map(|v| if v.is_finite() { 0.0 } else { f64::NAN }).collect();
        for &c in p.bulk.iter().filter(|c| only(c)) {
            let ue: Vec<f64> =
                mesh.cells[c].iter().flat_map(|&n| (0..md.dim()).map(move |k| depl[n * md.dim() + k])).collect();
            let mat = &p.materials[c].as_ref().unwrap().0;
            let xs = coords_of(mesh, c);
            let zero = vec![0.0; mesh.cells[c].len()];
            let theta = thetas[c].as_deref().unwrap_or(&zero);
            let (eps, sig) = elasticity::node_fields_thermal(md, mat, mesh.cell_types[c], &xs, &ue, theta)
                .map_err(|e| Error::runtime(e.to_string()))?;
            sig_elno[c] = Some(sig.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            eps_elno[c] = Some(eps.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            let g = elasticity::gauss_fields_thermal(md, mat, mesh.cell_types[c], &xs, &ue, theta)
                .map_err(|e| Error::runtime(e.to_string()))?;
            sig_elga[c] = Some(g.sig.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            eps_elga[c] = Some(g.eps.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            if let Some(sv) = plastic_sig.as_ref().and_then(|p| p[c].as_ref()) {
                let t = mesh.cell_types[c];
                if sv.len() != g.sig.len() * ns {
                    return Err(a.err(
                        "RESULTAT",
                        format!("SIEF_ELGA of cell {} does not have its {} points", mesh.cell_names[c], g.sig.len()),
                    ));
                }
                let pts = points_of(sv, ns);
                sig_elno[c] = Some(flat(&elasticity::gauss_to_nodes(md, t, &pts, ns), ns));
                sig_elga[c] = Some(sv.clone());
                if let Some(v) = plastic_vari.as_ref().and_then(|p| p[c].as_ref()) {
                    let nv = vari_names.len();
                    vari_elno[c] = Some(flat(&elasticity::gauss_to_nodes(md, t, &points_of(v, nv), nv), nv));
                }
                if wanted.iter().any(|o| o.starts_with("EPSP_")) {
                    // ε_p = ε − S σ, S the compliance of ELAS (under C_PLAN, ε_zz the elastic estimate
                    // −ν/(1−ν) (ε_xx + ε_yy) of the displacement, as Code_Aster's te0334).
                    let (e, nu) = (mat.e, mat.nu);
                    let ep: Vec<[f64; 6]> = g
                        .eps
                        .iter()
                        .zip(&pts)
                        .map(|(eps, sg)| {
                            let tr = sg[0] + sg[1] + sg[2];
                            let mut out = [0.0; 6];
                            for k in 0..ns {
                                let elastic =
                                    if k < 3 { ((1.0 + nu) * sg[k] - nu * tr) / e } else { (1.0 + nu) / e * sg[k] };
                                out[k] = eps[k] - elastic;
                            }
                            out
                        })
                        .collect();
                    epsp_elga[c] = Some(flat(&ep, ns));
                    epsp_elno[c] = Some(flat(&elasticity::gauss_to_nodes(md, t, &ep, ns), ns));
                }
            }
            if wanted.iter().any(|o| o.starts_with("ENEL_")) {
                if !mat.is_isotropic() {
                    return Err(a.err("ENERGIE", "ENEL_* of an anisotropic material is not supported yet"));
                }
                let sv = sig_elga[c].as_ref().expect("computed above");
                let w: Vec<[f64; 6]> = points_of(sv, ns)
                    .iter()
                    .map(|sg| {
                        let mut out = [0.0; 6];
                        out[0] = elastic_energy(mat.e, mat.nu, sg);
                        out
                    })
                    .collect();
                enel_elga[c] = Some(w.iter().map(|x| x[0]).collect::<Vec<_>>());
                let t = mesh.cell_types[c];
                enel_elno[c] = Some(flat(&elasticity::gauss_to_nodes(md, t, &w, 1), 1));
            }
            if wanted.iter().any(|o| o == "FORC_NODA") {
                let sv = sig_elga[c].as_ref().expect("computed above");
                let f = elasticity::internal_forces(md, mesh.cell_types[c], &xs, &points_of(sv, ns))
                    .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])))?;
                for (i, &n) in mesh.cells[c].iter().enumerate() {
                    for k in 0..md.dim() {
                        forc_noda[n * md.dim() + k] += f[i * md.dim() + k];
                    }
                }
            }
        }
        if thermal.is_some() && wanted.iter().any(|o| o == "SIRO_ELEM") {
            return Err(a.err("CONTRAINTE", "SIRO_ELEM with AFFE_VARC's thermal strain is not supported yet"));
        }
        let siro = match wanted.iter().any(|o| o == "SIRO_ELEM") {
            true => Some(siro_elem(&p, &model, depl, &only).map_err(|e| e.at(a.span))?),
            false => None,
        };
        let etot_elga: Points = if etot {
            let half_work = |sig: &[f64], deps: &[f64]| -> f64 {
                0.5 * (0..ns).map(|k| if k < 3 { sig[k] * deps[k] } else { 2.0 * sig[k] * deps[k] }).sum::<f64>()
            };
            let mut out = vec![None; mesh.cells.len()];
            for &c in p.bulk.iter().filter(|c| only(c)) {
                let (Some(e1), Some(s1)) = (&eps_elga[c], &sig_elga[c]) else { continue };
                let v: Vec<f64> = match before.as_ref().map(|(e, s, w)| (&e[c], &s[c], &w[c])) {
                    Some((Some(e0), Some(s0), Some(w0))) => (0..e1.len() / ns)
                        .map(|g| {
                            let r = g * ns..(g + 1) * ns;
                            let de: Vec<f64> = e1[r.clone()].iter().zip(&e0[r.clone()]).map(|(x, y)| x - y).collect();
                            w0[g] + half_work(&s1[r.clone()], &de) + half_work(&s0[r], &de)
                        })
                        .collect(),
                    _ => (0..e1.len() / ns)
                        .map(|g| half_work(&s1[g * ns..(g + 1) * ns], &e1[g * ns..(g + 1) * ns]))
                        .collect(),
                };
                out[c] = Some(v);
            }
            before = Some((eps_elga.clone(), sig_elga.clone(), out.clone()));
            out
        } else {
            Vec::new()
        };
        let sn: Vec<String> = md.sigma_names().iter().map(|s| s.to_string()).collect();
        let en: Vec<String> = md.epsilon_names().iter().map(|s| s.to_string()).collect();
        for o in &wanted {
            let f = match o.as_str() {
                "SIGM_ELNO" | "SIEF_ELNO" => Field::Elno { components: sn.clone(), cells: sig_elno.clone() },
                "SIEF_NOEU" => Field::Node { components: sn.clone(), values: to_nodes(mesh, &sig_elno, ns) },
                "EPSP_ELGA" => Field::Elga { components: en.clone(), cells: epsp_elga.clone() },
                "EPSP_ELNO" => Field::Elno { components: en.clone(), cells: epsp_elno.clone() },
                "VARI_ELNO" => Field::Elno { components: vari_names.clone(), cells: vari_elno.clone() },
                "VARI_NOEU" => {
                    Field::Node { components: vari_names.clone(), values: to_nodes(mesh, &vari_elno, vari_names.len()) }
                }
                "FORC_NODA" => Field::Node {
                    components: ["DX", "DY", "DZ"][..md.dim()].iter().map(|s| s.to_string()).collect(),
                    values: forc_noda.clone(),
                },
                "SIEQ_ELGA" => Field::Elga {
                    components: SIEQ_COMPONENTS.iter().map(|s| s.to_string()).collect(),
                    cells: sig_elga
                        .iter()
                        .map(|c| c.as_ref().map(|v| v.chunks(ns).flat_map(equivalent_stresses).collect()))
                        .collect(),
                },
                "EPSI_ELNO" => Field::Elno { components: en.clone(), cells: eps_elno.clone() },
                "ENEL_ELGA" => Field::Elga { components: vec!["TOTALE".into()], cells: enel_elga.clone() },
                "ETOT_ELGA" => Field::Elga { components: vec!["TOTALE".into()], cells: etot_elga.clone() },
                "ENEL_ELNO" => Field::Elno { components: vec!["TOTALE".into()], cells: enel_elno.clone() },
                "SIGM_NOEU" => Field::Node { components: sn.clone(), values: to_nodes(mesh, &sig_elno, ns) },
                "EPSI_NOEU" => Field::Node { components: en.clone(), values: to_nodes(mesh, &eps_elno, ns) },
                // In linear elasticity the generalized and Cauchy stresses coincide.
                "SIEF_ELGA" | "SIGM_ELGA" => Field::Elga { components: sn.clone(), cells: sig_elga.clone() },
                "SIRO_ELEM" => siro.clone().expect("computed above"),
                "SIEQ_ELNO" | "SIEQ_NOEU" => {
                    let cells: Vec<Option<Vec<f64>>> = sig_elno
                        .iter()
                        .map(|c| c.as_ref().map(|v| v.chunks(ns).flat_map(equivalent_stresses).collect()))
                        .collect();
                    let names = SIEQ_COMPONENTS.iter().map(|s| s.to_string()).collect();
                    if o == "SIEQ_ELNO" {
                        Field::Elno { components: names, cells }
                    } else {
                        Field::Node { components: names, values: to_nodes(mesh, &cells, SIEQ_COMPONENTS.len()) }
                    }
                }
                _ => Field::Elga { components: en.clone(), cells: eps_elga.clone() },
            };
            step.fields.insert(o.clone(), f);
        }
    }
    let r = rc.result()?;
    let data = r.with_steps(steps);
    Ok(Some(ConceptData::Result(data)))
}

/// Whether the elastic parameters of every bulk cell are constants (not functions of TEMP): the options
/// that need the law at the temperature of a plastic result under AFFE_VARC stop otherwise.
pub(crate) fn constant_elasticity(chmat: &ConceptRef, p: &Problem) -> Result<()> {
    let data = chmat.data();
    let ConceptData::MaterialField(mf) = &*data else { return Ok(()) };
    for &c in &p.bulk {
        if let Some(mc) = &mf.cells[c] {
            if let ConceptData::Material(m) = &*mc.data() {
                crate::stages::core::problem::elastic_of(m, &p.mesh.cell_names[c])?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod sieq_tests {
    use super::*;

    #[test]
    fn rosette_of_a_uniform_stress_on_a_vertical_segment() {
        // σ = [[100, 50], [50, 200]], SIZZ = 7; segment from (1,0) to (1,1): t1 = ey, n = ex.
        let r = rosette_2d(CellType::Seg2, &[[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], [100.0, 200.0, 7.0, 50.0]).unwrap();
        let want = [100.0, 50.0, 0.0, 100.0, 50.0, 200.0, 0.0, 50.0, 200.0, 0.0, 200.0, 0.0, 0.0, 7.0, 7.0, 50.0];
        for (k, (g, w)) in r.iter().zip(want).enumerate() {
            assert!((g - w).abs() < 1e-12, "{}: {g} != {w}", SIRO_COMPONENTS[k]);
        }
        // Reversed segment: n = -ey... here t1 = -ey, n = -ex; σ·n and σ·t1 change sign, the
        // normal and tangential stresses and the shear t1·σ·n do not.
        let r = rosette_2d(CellType::Seg2, &[[1.0, 1.0, 0.0], [1.0, 0.0, 0.0]], [100.0, 200.0, 7.0, 50.0]).unwrap();
        assert_eq!((r[0], r[1], r[3], r[4], r[10], r[15]), (-100.0, -50.0, 100.0, -50.0, 200.0, 50.0));
    }

    #[test]
    fn rosette_of_a_top_edge_run_backwards() {
        // The top edge of a square run counterclockwise: from (1,1) to (0,1): t1 = -ex, n = ey.
        let r = rosette_2d(CellType::Seg2, &[[1.0, 1.0, 0.0], [0.0, 1.0, 0.0]], [100.0, 200.0, 0.0, 50.0]).unwrap();
        assert_eq!(&r[..4], &[50.0, 200.0, 0.0, 200.0]);
        assert_eq!((r[4], r[5], r[10], r[15]), (-100.0, -50.0, 100.0, -50.0));
        assert!(rosette_2d(CellType::Seg2, &[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0]], [0.0; 4]).is_none());
    }
}
