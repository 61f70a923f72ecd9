//! The keywords of an HM STAT_NON_LINE, the loads of EXCIT at an instant, and the run report.

use super::step::StepLog;
use crate::catalog::args::Args;
use crate::concepts::model::{Load, LoadItem, Role};
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::fem::dofs::Constraints;
use crate::fem::elasticity;
use crate::hm::element::{flux_load, Variant};
use crate::stages::core::assembly::loads;
use crate::stages::core::eval::{eval_at, load_value};
use crate::stages::core::hm::HmProblem;
use crate::stages::core::problem::coords_of;
use std::rc::Rc;

/// COMPORTEMENT: KIT_HM with RELATION_KIT=('ELAS', 'LIQU_SATU', 'HYDR_UTIL') on the whole model, small
/// strains; the integration controls have no effect (the laws update in closed form).
pub fn behaviour(a: &Args) -> Result<()> {
    let occs = a.facts("COMPORTEMENT");
    if occs.is_empty() {
        return Err(a.err(
            "COMPORTEMENT",
            "a saturated HM model needs COMPORTEMENT=_F(RELATION='KIT_HM', RELATION_KIT=('ELAS', 'LIQU_SATU', \
             'HYDR_UTIL'))",
        ));
    }
    for occ in occs {
        crate::stages::core::newton::closed_form_behaviour(occ)?;
        let rel = occ.text("RELATION").unwrap_or("ELAS");
        if rel != "KIT_HM" {
            return Err(occ.err(
                "RELATION",
                format!(
                    "RELATION='{rel}' on a saturated HM model: KIT_HM is needed (the others are not supported yet)"
                ),
            ));
        }
        let kit = occ.texts("RELATION_KIT");
        let want = ["ELAS", "LIQU_SATU", "HYDR_UTIL"];
        if kit.len() != 3 || kit.iter().zip(want).any(|(k, w)| k != w) {
            return Err(occ.err(
                "RELATION_KIT",
                format!("RELATION_KIT={kit:?} is not supported yet (('ELAS', 'LIQU_SATU', 'HYDR_UTIL') is)"),
            ));
        }
        if occ.text("DEFORMATION").is_some_and(|d| d != "PETIT") {
            return Err(occ.err("DEFORMATION", "only DEFORMATION='PETIT' is supported yet"));
        }
    }
    Ok(())
}

/// SCHEMA_THM PARM_THETA (1 by default); PARM_ALPHA plays no part in these laws.
pub fn theta(a: &Args) -> Result<f64> {
    let Some(s) = a.fact("SCHEMA_THM") else { return Ok(1.0) };
    let theta = s.real("PARM_THETA").unwrap_or(1.0);
    // PARM_ALPHA weighs the thermal terms of other laws; saturated HM without temperature ignores it.
    let _ = s.real("PARM_ALPHA");
    Ok(theta)
}

/// The loads of EXCIT over a step ending at `t` of length `dt`: the kinematic conditions (values at
/// `t`) and the external forces: nodal, surface and pressure forces on the displacements, the weight of
/// the mixture (PESANTEUR, with THM_DIFFU RHO), and FLUX_THM_REP on the pressures (`−Δt ∫ N̂ q`).
pub fn loads_at(
    a: &Args,
    p: &HmProblem,
    model: &crate::concepts::ConceptRef,
    t: f64,
    dt: f64,
) -> Result<(Constraints, Vec<f64>)> {
    let mesh = &p.mesh;
    let dim = p.kin.dim();
    let md = p.kin.mechanics();
    let num = &p.numbering;
    let mut cons = Constraints::new();
    let mut f = vec![0.0; num.ndofs()];
    let model_ref = model.model()?;
    let on_skin = |c: usize| model_ref.elements[c].as_ref().map(|e| e.role) == Some(Role::Skin);
    let udofs = |c: usize| -> Option<Vec<usize>> {
        mesh.cells[c].iter().flat_map(|&n| (0..dim).map(move |i| num.dof(n, i))).collect()
    };
    for (lc, mult) in loads(a, t)? {
        let data = lc.data();
        let ConceptData::Load(Load { items, model: lmodel, .. }) = &*data else {
            return Err(a.err("EXCIT", format!("{} is not a mechanical load", lc.label())));
        };
        if !Rc::ptr_eq(lmodel, model) {
            return Err(a.err("EXCIT", format!("load {} is defined on another model ({})", lc.label(), lmodel.label())));
        }
        let name = lc.label();
        let skin_cell = |c: usize| -> Result<Vec<usize>> {
            match udofs(c) {
                Some(d) if on_skin(c) => Ok(d),
                _ => Err(a.err(
                    "EXCIT",
                    format!("load {name}: cell {} is not a boundary cell of the model", mesh.cell_names[c]),
                )),
            }
        };
        let node_name = |n: usize| mesh.node_names[n].clone();
        for item in items {
            match item {
                LoadItem::Dof { node, component, value } => {
                    let k = num.component(component).ok_or_else(|| {
                        a.err("EXCIT", format!("load {name}: {component} is not an unknown of a {} model", p.modelling))
                    })?;
                    match num.dof(*node, k) {
                        Some(d) => {
                            let v = mult * load_value(value, &mesh.coords[*node], t)?;
                            match enriched_condition(p, items, *node, component, d) {
                                Some(relations) => {
                                    for terms in relations {
                                        cons.relation(terms, v);
                                    }
                                }
                                None => cons.impose(d, v),
                            }
                        }
                        // A middle node carries no pressure, a node outside the interface's reach no Heaviside
                        // unknown: Code_Aster passes over them (afddli).
                        None if (p.is_pressure(k) || p.xfem.is_some() && component.starts_with('H'))
                            && num.has_node(*node) => {}
                        None => {
                            return Err(a.err(
                                "EXCIT",
                                format!("load {name}: node {} carries no element of the model", node_name(*node)),
                            ))
                        }
                    }
                }
                LoadItem::CrackPressure { name: crack, .. } => {
                    return Err(a.err(
                        "EXCIT",
                        format!(
                            "load {name}: PRES_REP on the lips of {crack} {}",
                            if p.xfem.is_some() {
                                "with coupled flow in the X-FEM elements is not supported yet"
                            } else {
                                "needs the X-FEM model"
                            }
                        ),
                    ))
                }
                LoadItem::Relation { terms, value } => {
                    let mut tt = Vec::new();
                    for (node, comp, coef) in terms {
                        let k = num.component(comp).ok_or_else(|| {
                            a.err("EXCIT", format!("load {name}: {comp} is not an unknown of a {} model", p.modelling))
                        })?;
                        let d = num.dof(*node, k).ok_or_else(|| {
                            a.err("EXCIT", format!("load {name}: node {} carries no {comp}", node_name(*node)))
                        })?;
                        tt.push((d, *coef));
                    }
                    cons.relation(tt, mult * load_value(value, &[0.0; 3], t)?);
                }
                LoadItem::NodalForce { node, component, value } => {
                    let k = match component.as_str() {
                        "FX" => 0,
                        "FY" => 1,
                        "FZ" if dim == 3 => 2,
                        c => {
                            return Err(a.err(
                                "EXCIT",
                                format!("load {name}: FORCE_NODALE {c} is not supported on a {} model", p.modelling),
                            ))
                        }
                    };
                    let d = num.dof(*node, k).ok_or_else(|| {
                        a.err(
                            "EXCIT",
                            format!("load {name}: node {} carries no element of the model", node_name(*node)),
                        )
                    })?;
                    f[d] += mult * load_value(value, &mesh.coords[*node], t)?;
                }
                LoadItem::SurfaceForce { cells, components } => {
                    if dim < 3 && components.iter().any(|(n, _)| n == "FZ") {
                        return Err(a.err("EXCIT", format!("load {name}: FZ in a {} model", p.modelling)));
                    }
                    for &c in cells {
                        let dofs = skin_cell(c)?;
                        let err = std::cell::RefCell::new(None);
                        let fx = |x: &[f64; 3], _n: &[f64; 3]| -> [f64; 3] {
                            let mut v = [0.0; 3];
                            for (cn, val) in components {
                                let k = ["FX", "FY", "FZ"].iter().position(|s| s == cn).unwrap_or(2);
                                match load_value(val, x, t) {
                                    Ok(r) => v[k] = mult * r,
                                    Err(e) => *err.borrow_mut() = Some(e),
                                }
                            }
                            v
                        };
                        let fe = elasticity::boundary_force(md, mesh.cell_types[c], &coords_of(mesh, c), &fx)
                            .map_err(|e| Error::runtime(e.to_string()).at(a.span))?;
                        let pending = err.borrow_mut().take();
                        if let Some(e) = pending {
                            return Err(e.at(a.span));
                        }
                        let density = |x: &[f64; 3], nr: &[f64; 3], _: &[f64]| fx(x, nr);
                        skin_load(a, p, c, &fe, &dofs, Density::Traction(&density), &mut f)?;
                        let pending = err.borrow_mut().take();
                        if let Some(e) = pending {
                            return Err(e.at(a.span));
                        }
                    }
                }
                LoadItem::Pressure { cells, value } => {
                    for &c in cells {
                        let dofs = skin_cell(c)?;
                        let xs = coords_of(mesh, c);
                        let pres: Vec<f64> =
                            xs.iter().map(|x| load_value(value, x, t).map(|v| v * mult)).collect::<Result<_>>()?;
                        let fe = elasticity::pressure_force(md, mesh.cell_types[c], &xs, &pres, None)
                            .map_err(|e| Error::runtime(e.to_string()).at(a.span))?;
                        // On a cell an interface crosses, the pressure at each point of each side (a function
                        // may jump across the interface); elsewhere the nodal values, as `pressure_force`.
                        let err = std::cell::RefCell::new(None);
                        let density = |x: &[f64; 3], nr: &[f64; 3], _: &[f64]| {
                            let pv = match load_value(value, x, t) {
                                Ok(v) => v * mult,
                                Err(e) => {
                                    *err.borrow_mut() = Some(e);
                                    0.0
                                }
                            };
                            nr.map(|v| -v * pv)
                        };
                        skin_load(a, p, c, &fe, &dofs, Density::Traction(&density), &mut f)?;
                        let pending = err.borrow_mut().take();
                        if let Some(e) = pending {
                            return Err(e.at(a.span));
                        }
                    }
                }
                LoadItem::FluxThm { cells, value } => {
                    for &c in cells {
                        skin_cell(c)?;
                        let t_c = mesh.cell_types[c];
                        let err = std::cell::RefCell::new(None);
                        let q = |x: &[f64; 3]| match load_value(value, x, t) {
                            Ok(v) => mult * v,
                            Err(e) => {
                                *err.borrow_mut() = Some(e);
                                0.0
                            }
                        };
                        let fe = flux_load(p.kin, t_c, &coords_of(mesh, c), dt, &q)
                            .map_err(|e| a.err("EXCIT", format!("load {name}: cell {}: {e}", mesh.cell_names[c])))?;
                        let pending = err.borrow_mut().take();
                        if let Some(e) = pending {
                            return Err(e.at(a.span));
                        }
                        let dofs = (0..fe.len())
                            .map(|k| {
                                let n = mesh.cells[c][k];
                                num.dof(n, p.pre1).ok_or_else(|| {
                                    a.err("EXCIT", format!("load {name}: node {} carries no PRE1", node_name(n)))
                                })
                            })
                            .collect::<Result<Vec<usize>>>()?;
                        skin_load(a, p, c, &fe, &dofs, Density::Flux(&q, dt), &mut f)?;
                        let pending = err.borrow_mut().take();
                        if let Some(e) = pending {
                            return Err(e.at(a.span));
                        }
                    }
                }
                LoadItem::Gravity { g, direction, cells } => {
                    let on: Vec<usize> = match cells {
                        Some(c) => c.iter().copied().filter(|c| p.cells[*c].is_some()).collect(),
                        None => p.bulk.clone(),
                    };
                    for c in on {
                        let cell = p.cells[c].as_ref().unwrap();
                        let rho = cell.mat.rho_h;
                        let acc = [0, 1, 2].map(|i| rho * g * direction[i] * mult);
                        // The weight of the mixture, at the points where the element integrates mechanics.
                        for pt in cell.points.points.iter().filter(|pt| pt.role.mech) {
                            for (a_n, &n_a) in pt.n.iter().enumerate() {
                                for (i, acc_i) in acc.iter().enumerate().take(dim) {
                                    f[cell.dofs[cell.points.u(a_n, i)]] += pt.w * n_a * acc_i;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    Ok((cons, f))
}

/// DDL_IMPO of a standard component (DX DY DZ PRE1) on a node of an X-FEM model with Heaviside sets,
/// as `xddlim` prescribes it: the whole field on the node's side, std + Σ ψ h = value. Off the interface
/// ψ vanishes on the node's own side, so the standard unknown alone is prescribed (None). On it (a single
/// interface with the level set zero at the node) the sides where the load's other nodes lie, among the
/// cells holding the node: one relation per side (both when they lie on both, or none of them does).
/// `d` is the node's standard unknown of the component.
fn enriched_condition(
    p: &HmProblem,
    items: &[LoadItem],
    n: usize,
    component: &str,
    d: usize,
) -> Option<Vec<Vec<(usize, f64)>>> {
    let xm = p.xfem.as_ref()?;
    if xm.node_sets[n].is_empty() || xm.lsn.len() != 1 || xm.lsn[0][n] != 0.0 {
        return None;
    }
    let (mesh, num) = (&p.mesh, &p.numbering);
    let lsn = &xm.lsn[0];
    let same: std::collections::BTreeSet<usize> = items
        .iter()
        .filter_map(|it| match it {
            LoadItem::Dof { node, component: c, .. } if c == component => Some(*node),
            _ => None,
        })
        .collect();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (c, nodes) in mesh.cells.iter().enumerate() {
        if p.cells.get(c).is_none_or(|x| x.is_none()) || !nodes.contains(&n) {
            continue;
        }
        for &m in nodes.iter().filter(|m| same.contains(m)) {
            lo = lo.min(lsn[m]);
            hi = hi.max(lsn[m]);
        }
    }
    let sides: Vec<i32> = if lo == 0.0 && hi > 0.0 {
        vec![1]
    } else if lo < 0.0 && hi == 0.0 {
        vec![-1]
    } else if (lo < 0.0 && hi > 0.0) || same.len() <= 1 {
        vec![1, -1]
    } else {
        return Some(Vec::new()); // an isolated node: Code_Aster prescribes nothing there
    };
    let suffix = component.strip_prefix('D').unwrap_or(component);
    Some(
        sides
            .into_iter()
            .map(|side| {
                let region = crate::xfem::region_code(&[side]);
                let mut terms = vec![(d, 1.0)];
                for j in 0..xm.node_sets[n].len() {
                    let psi = xm.psi(n, j, region);
                    let hc = format!("H{}{suffix}", j + 1);
                    if let Some(hd) = num.component(&hc).and_then(|k| num.dof(n, k)).filter(|_| psi != 0.0) {
                        terms.push((hd, psi));
                    }
                }
                terms
            })
            .collect(),
    )
}

/// A traction at a point of a skin cell, from the point, the unit normal and the cell's functions there.
type Traction<'a> = dyn Fn(&[f64; 3], &[f64; 3], &[f64]) -> [f64; 3] + 'a;

/// What a load puts on a skin cell, per unit measure: a traction (from the point, the unit normal and the
/// cell's shape functions there), or a fluid mass flux over a step `dt` (on the pressures, `−Δt q N̂`).
enum Density<'a> {
    Traction(&'a Traction<'a>),
    Flux(&'a dyn Fn(&[f64; 3]) -> f64, f64),
}

/// A load on a skin cell: `fe`, its standard nodal values (`dim` per node for a traction, one per vertex
/// for a flux), on the standard unknowns `dofs`, with on an X-FEM model its Heaviside parts
/// ([`add_enriched`]).
fn skin_load(
    a: &Args,
    p: &HmProblem,
    c: usize,
    fe: &[f64],
    dofs: &[usize],
    density: Density,
    f: &mut [f64],
) -> Result<()> {
    if !add_enriched(a, p, c, fe, density, f)? {
        for (d, v) in dofs.iter().zip(fe) {
            f[*d] += v;
        }
    }
    Ok(())
}

/// The Heaviside parts of a load on a skin cell of an X-FEM model, on the sets' unknowns. On a cell the
/// interface does not cross, ψ is constant: `fe` (the standard nodal values, `dim` per node for a
/// traction, one per vertex for a flux) times ψ of each set on the cell's side; the caller adds `fe`
/// itself (false). On a cell it crosses, the whole load — standard and Heaviside parts — is integrated
/// over the sub-cells of the cell's cutting (`xm.boundary`), each on its side (true).
fn add_enriched(a: &Args, p: &HmProblem, c: usize, fe: &[f64], density: Density, f: &mut [f64]) -> Result<bool> {
    let Some(xm) = &p.xfem else { return Ok(false) };
    let (mesh, num) = (&p.mesh, &p.numbering);
    let nodes = &mesh.cells[c];
    if nodes.iter().all(|&n| xm.node_sets[n].is_empty()) {
        return Ok(false);
    }
    let dim = p.kin.dim();
    let xyz = ["X", "Y", "Z"];
    // The unknown of set j of node n for component i (a pressure for a flux).
    let set_dof = |n: usize, j: usize, i: Option<usize>| {
        let comp = match i {
            Some(i) => format!("H{}{}", j + 1, xyz[i]),
            None => format!("H{}PRE1", j + 1),
        };
        num.component(&comp).and_then(|k| num.dof(n, k))
    };
    // The standard unknown of node n for component i (PRE1 for a flux).
    let std_dof = |n: usize, i: Option<usize>| num.dof(n, i.unwrap_or(p.pre1));
    let t = mesh.cell_types[c];
    let cut = xm.lsn.iter().any(|l| nodes.iter().any(|&n| l[n] > 0.0) && nodes.iter().any(|&n| l[n] < 0.0));
    if !cut {
        let ff = crate::fem::reference::shape(t, &crate::fem::reference::ref_centroid(t));
        let region =
            crate::xfem::region_code(&crate::xfem::model::point_signs(&xm.lsn, &xm.masters, nodes, &ff, &[], &[]));
        for (a_n, &n) in nodes.iter().enumerate() {
            for j in 0..xm.node_sets[n].len() {
                let psi = xm.psi(n, j, region);
                if psi == 0.0 {
                    continue;
                }
                match density {
                    Density::Traction(_) => {
                        for i in 0..dim {
                            if let Some(d) = set_dof(n, j, Some(i)) {
                                f[d] += psi * fe[a_n * dim + i];
                            }
                        }
                    }
                    Density::Flux(..) => {
                        if let (Some(d), Some(v)) = (set_dof(n, j, None), fe.get(a_n)) {
                            f[d] += psi * v;
                        }
                    }
                }
            }
        }
        return Ok(false);
    }
    let Some((cracks, cutting)) = xm.boundary.get(&c) else {
        return Err(a.err(
            "EXCIT",
            format!("boundary cell {}: an X-FEM interface crosses it but it has no cutting", mesh.cell_names[c]),
        ));
    };
    let coords = crate::stages::core::problem::coords_of(mesh, c);
    let tdim = t.dim();
    let nno = t.nnodes();
    let tv = crate::fem::elasticity::vertex_type(t);
    let rule = if tdim == 1 {
        crate::fem::quadrature::gauss_legendre(4)
    } else {
        crate::fem::quadrature::rule_for_degree(crate::fem::quadrature::RefDomain::Triangle, 6)
    };
    for sc in &cutting.subcells {
        use crate::mesh::CellType;
        let st = match (tdim, sc.nodes.len()) {
            (1, 2) => CellType::Seg2,
            (1, _) => CellType::Seg3,
            (_, 3) => CellType::Tria3,
            _ => CellType::Tria6,
        };
        let xis: Vec<[f64; 3]> = sc.nodes.iter().map(|&q| cutting.points[q].xi).collect();
        // The sub-cell's side: the signs at its centroid, with its Heaviside values for the cell's cracks.
        let nv = tdim + 1;
        let mut xc = [0.0; 3];
        for xi in &xis[..nv] {
            for k in 0..3 {
                xc[k] += xi[k] / nv as f64;
            }
        }
        let ffc = crate::fem::reference::shape(t, &xc);
        let region = crate::xfem::region_code(&crate::xfem::model::point_signs(
            &xm.lsn,
            &xm.masters,
            nodes,
            &ffc,
            cracks,
            &sc.he,
        ));
        let mut ns = vec![0.0; st.nnodes()];
        let mut ds = vec![[0.0; 3]; st.nnodes()];
        let mut n = vec![0.0; nno];
        let mut dref = vec![[0.0; 3]; nno];
        for (q, wq) in rule.points.iter().zip(&rule.weights) {
            crate::fem::reference::shape_and_deriv(st, q, &mut ns, &mut ds);
            // The point in the parent's reference, and the sub-cell map's Jacobian there.
            let mut xi = [0.0; 3];
            let mut js = [[0.0; 3]; 3];
            for (k, xk) in xis.iter().enumerate() {
                for r in 0..tdim {
                    xi[r] += ns[k] * xk[r];
                    for s_ in 0..tdim {
                        js[r][s_] += xk[r] * ds[k][s_];
                    }
                }
            }
            let det_s = if tdim == 1 { js[0][0].abs() } else { (js[0][0] * js[1][1] - js[0][1] * js[1][0]).abs() };
            crate::fem::reference::shape_and_deriv(t, &xi, &mut n, &mut dref);
            let (mut x, mut t1, mut t2) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            for k in 0..nno {
                for i in 0..3 {
                    x[i] += n[k] * coords[k][i];
                    t1[i] += dref[k][0] * coords[k][i];
                    t2[i] += dref[k][1] * coords[k][i];
                }
            }
            let (jac, normal) = if tdim == 1 {
                let l = (t1[0] * t1[0] + t1[1] * t1[1]).sqrt();
                (l, [t1[1] / l, -t1[0] / l, 0.0])
            } else {
                let cr = [t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]];
                let l = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt();
                (l, cr.map(|v| v / l))
            };
            let w = wq * det_s * jac;
            match density {
                Density::Traction(g) => {
                    let tr = g(&x, &normal, &n);
                    for (a_n, &node) in nodes.iter().enumerate() {
                        for (i, tri) in tr.iter().enumerate().take(dim) {
                            if let Some(d) = std_dof(node, Some(i)) {
                                f[d] += w * n[a_n] * tri;
                            }
                        }
                        for j in 0..xm.node_sets[node].len() {
                            let psi = xm.psi(node, j, region);
                            for (i, tri) in tr.iter().enumerate().take(dim) {
                                if let Some(d) = set_dof(node, j, Some(i)).filter(|_| psi != 0.0) {
                                    f[d] += w * psi * n[a_n] * tri;
                                }
                            }
                        }
                    }
                }
                Density::Flux(qf, dt) => {
                    let nh = crate::fem::reference::shape(tv, &xi);
                    let qv = qf(&x);
                    for (a_n, &node) in nodes.iter().enumerate().take(tv.nnodes()) {
                        if let Some(d) = std_dof(node, None) {
                            f[d] -= dt * w * nh[a_n] * qv;
                        }
                        for j in 0..xm.node_sets[node].len() {
                            let psi = xm.psi(node, j, region);
                            if let Some(d) = set_dof(node, j, None).filter(|_| psi != 0.0) {
                                f[d] -= dt * w * psi * nh[a_n] * qv;
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(true)
}

/// The fluid's gravity of a cell at `t`: THM_DIFFU PESA_X/Y/Z × PESA_MULT(t).
pub fn gravity(cell: &crate::stages::core::hm::HmCell, t: f64) -> Result<[f64; 3]> {
    let m = match &cell.pesa_mult {
        Some(f) => eval_at(f, &[0.0; 3], t)?,
        None => 1.0,
    };
    Ok(cell.mat.gravity.map(|g| g * m))
}

/// What was simulated and how: the unknowns, what was eliminated and why, the couplings that vanish,
/// then the steps.
pub fn report(
    p: &HmProblem,
    a: &Args,
    times: &[f64],
    theta: f64,
    log: &StepLog,
    stored: usize,
    seconds: f64,
) -> Result<String> {
    let num = &p.numbering;
    let npre = (0..num.ndofs()).filter(|&d| p.is_pressure(num.node_comp(d).1)).count();
    let nu = num.ndofs() - npre;
    let variant = match p.variant {
        Variant::Full => "all terms at the Gauss points",
        Variant::Reduced => "all terms at the points of the reduced family",
        Variant::Lumped => "all terms at the vertices (lumped storage)",
        Variant::Selective => "mechanics and flow at the Gauss points, storage at the vertices",
    };
    let mut s = format!(
        "  STAT_NON_LINE ({}, KIT_HM ELAS/LIQU_SATU/HYDR_UTIL, θ = {theta}): {} cells, {variant}\n",
        p.modelling,
        p.bulk.len()
    );
    s.push_str(&format!(
        "    unknowns  : {} ({nu} displacements, {npre} pressures PRE1{} on vertices), {} solved\n",
        num.ndofs(),
        if p.xfem.is_some() { " and H*PRE1" } else { "" },
        log.solved
    ));
    if let Some(xm) = &p.xfem {
        let cut = p.elements().filter(|(_, c)| c.points.family == "XINT").count();
        s.push_str(&format!(
            "    X-FEM     : {} Heaviside sets over {} nodes, displacement and pressure enriched (H*X H*Y [H*Z] \
             and H*PRE1 in the counts above); {cut} cells integrated on their sub-cells; the interfaces are \
             impervious and traction-free (no interface unknowns)\n",
            xm.n_sets(),
            xm.node_sets.iter().filter(|v| !v.is_empty()).count()
        ));
    }
    let (elim_u, elim_p) = (log.eliminated_u, log.eliminated_p);
    if elim_p == npre && npre > 0 {
        s.push_str(&format!(
            "    hydraulics: PRE1 prescribed on all {npre} vertices (DDL_IMPO): the flow is not computed, the \
             pressures act through the Biot coupling only\n"
        ));
    } else if elim_p > 0 {
        s.push_str(&format!(
            "    hydraulics: PRE1 prescribed on {elim_p} of {npre} vertices (eliminated); the flow is solved on the \
             other {}\n",
            npre - elim_p
        ));
    } else {
        s.push_str(&format!("    hydraulics: the flow is solved on all {npre} vertices\n"));
    }
    s.push_str(&format!("    mechanics : {elim_u} of {nu} displacements prescribed (eliminated)\n"));
    // The couplings the material data switch off.
    let mats: Vec<_> = p.elements().map(|(_, c)| c.mat).collect();
    let mut vanish = Vec::new();
    if mats.iter().all(|m| m.perm == 0.0) {
        vanish.push("no permeability (PERM_IN = 0): no flow, undrained everywhere");
    }
    if mats.iter().all(|m| m.biot == 0.0) {
        vanish.push("BIOT_COEF = 0: the pressure does not load the skeleton");
    }
    if mats.iter().all(|m| m.gravity == [0.0; 3]) {
        vanish.push("PESA_X/Y/Z = 0: no weight of the fluid");
    }
    if mats.iter().all(|m| m.inv_kw == 0.0) {
        vanish.push("UN_SUR_K = 0: incompressible liquid");
    }
    if !vanish.is_empty() {
        s.push_str(&format!("    vanishing : {}\n", vanish.join("; ")));
    }
    if let Some(n) = crate::stages::core::newton::newton_note(a) {
        s.push_str(&n);
        s.push('\n');
    }
    s.push_str(&format!(
        "    steps     : {} instants from {} to {}, {} computed ({} cut), {} stored, {} Newton iterations in all, \
         {:.3} s\n",
        times.len() - 1,
        times[0],
        times[times.len() - 1],
        log.steps,
        log.cuts,
        stored,
        log.iterations,
        seconds
    ));
    if let Some((info, residual, refinements)) = &log.last_solve {
        let sv = crate::stages::core::solver::solveur(a)?;
        s.push_str(&crate::stages::core::solver::solver_log(&sv, info, *residual, *refinements));
    }
    let t = &log.solver;
    s.push_str(&format!(
        "    time      : elements and assembly {:.3} s; {} factorizations: analysis {:.3} s, factorization {:.3} s, \
         condition (first factorization) {:.3} s, solves {:.3} s\n",
        log.assembly,
        log.factorizations,
        t.symbolic.as_secs_f64(),
        t.factorization.as_secs_f64(),
        t.condition.as_secs_f64(),
        t.solve.as_secs_f64()
    ));
    s.push_str(&log.table);
    Ok(s)
}
