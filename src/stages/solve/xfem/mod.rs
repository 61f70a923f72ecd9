//! STAT_NON_LINE on an X-FEM model (MODI_MODELE_XFEM), with or without the
//! cohesive mortar interfaces of DEFI_CONTACT FORMULATION='XFEM',
//! ALGO_CONT='CZM', RELATION='CZM_LIN_MIX' (`hm-xfem-formulation.md` §4–§6).
//!
//! Only the effects the scene calls for are simulated. Hydro-mechanical
//! models (D_PLAN_HM, 3D_HM) are accepted when every hydraulic unknown is
//! prescribed to zero: the pressures, their Heaviside parts and the fracture
//! unknowns (p_f, q⁺, q⁻ of every multiplier packet) are then eliminated,
//! with the coupling terms they carry (b·p in the bulk, p_f in the interface
//! equations), and the run log says so; a scene that needs coupled flow
//! stops with a message. Interfaces without a contact zone carry no
//! unknowns (free surfaces).

use crate::catalog::args::Args;
use crate::concepts::model::{Contact, LoadItem, LoadValue, MaterialField, Role};
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::{Constraints, DofMap};
use crate::fem::elasticity::Modelisation;
use crate::solve::{self, Method};
use crate::stages::core::assembly::loads;
use crate::stages::core::eval::load_value;
use crate::stages::core::problem::{elastic_of, mat_param};
use crate::stages::core::solver::solver_options;
use crate::stages::Ctx;
use crate::xfem::czm::{self, CzmParams, CzmState};
use crate::xfem::discrete::{self, XDofs};
use crate::xfem::model::{ContactKind, XfemModel};
use crate::xfem::mortar;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::rc::Rc;
use std::time::{Duration, Instant};

/// A cohesive zone: its crack, law, facet rule and multiplier packets.
struct Zone {
    crack: usize,
    params: CzmParams,
    order: i64,
    packets: Vec<Vec<usize>>,
    packet_of: BTreeMap<usize, usize>,
    edges: BTreeSet<(usize, usize)>,
}

/// A linear element: unknowns and matrix (row-major).
struct Lin {
    dofs: Vec<usize>,
    k: Vec<f64>,
}

/// One packet's cohesive law: zone, packet, lumped weight, first unknown.
struct Law {
    zone: usize,
    m: f64,
    base: usize,
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

const HYDRAULIC: &[&str] = &["PRE1", "PRE_FLU", "LAG_FLI", "LAG_FLS", "PR2_FLU", "LA2_FLI", "LA2_FLS"];

fn is_hydraulic(c: &str) -> bool {
    HYDRAULIC.contains(&c) || (c.starts_with('H') && c.ends_with("PRE1"))
}

/// The enrichment-set index and direction of a component `H<j><X|Y|Z>`.
fn heaviside_component(c: &str) -> Option<(usize, usize)> {
    let r = c.strip_prefix('H')?;
    let (j, d) = r.split_at(r.len().checked_sub(1)?);
    let j: usize = j.parse().ok()?;
    let d = match d {
        "X" => 0,
        "Y" => 1,
        "Z" => 2,
        _ => return None,
    };
    (j >= 1).then_some((j - 1, d))
}

fn direction(c: &str) -> Option<usize> {
    match c {
        "DX" => Some(0),
        "DY" => Some(1),
        "DZ" => Some(2),
        _ => None,
    }
}

/// STAT_NON_LINE on an X-FEM model: the instants of INCREMENT, the initial
/// state stored as order 0.
pub fn stat_non_line_xfem(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    let times = crate::stages::core::newton::instants(a)?;
    solve_xfem(ctx, a, model, times, "STAT_NON_LINE")
}

/// MECA_STATIQUE on an X-FEM model (no contact zone: the interfaces are free
/// surfaces): one linear solve at INST (0 by default), stored as order 1.
pub fn meca_statique_xfem(ctx: &mut Ctx, a: &Args, model: &ConceptRef) -> Result<Option<ConceptData>> {
    a.refuse(&["CARA_ELEM", "LIST_INST", "SENSIBILITE", "RESULTAT", "INST_FIN"])?;
    if let Some(o) = a.text("OPTION") {
        if o != "SIEF_ELGA" && o != "SANS" {
            return Err(a.err("OPTION", format!("OPTION='{o}' is not supported yet")));
        }
    }
    let inst = a.reals("INST").first().copied().unwrap_or(0.0);
    solve_xfem(ctx, a, model, vec![inst, inst], "MECA_STATIQUE")
}

fn solve_xfem(
    ctx: &mut Ctx,
    a: &Args,
    model: &ConceptRef,
    times: Vec<f64>,
    command: &str,
) -> Result<Option<ConceptData>> {
    let statics = command == "MECA_STATIQUE";
    if !statics {
        crate::stages::core::newton::refuse_unsupported_options(a)?;
    }
    let t_start = Instant::now();
    let (mesh, xm, elements) = {
        let m = model.model()?;
        (m.current_mesh(), m.xfem.clone().expect("an X-FEM model"), m.elements.clone())
    };
    let model_cells: Vec<usize> =
        (0..mesh.ncells()).filter(|&c| elements[c].as_ref().is_some_and(|e| e.role == Role::Bulk)).collect();
    let mut modelisations: Vec<String> =
        model_cells.iter().filter_map(|&c| elements[c].as_ref().map(|e| e.modelisation.clone())).collect();
    modelisations.sort();
    modelisations.dedup();
    if modelisations.len() != 1 {
        return Err(a.err(
            "MODELE",
            format!("several modelisations in one X-FEM model are not supported yet: {modelisations:?}"),
        ));
    }
    let modelisation = modelisations[0].clone();
    let (md, hm) = match modelisation.as_str() {
        "D_PLAN" => (Modelisation::DPlan, false),
        "C_PLAN" => (Modelisation::CPlan, false),
        "D_PLAN_HM" => (Modelisation::DPlan, true),
        "3D" => (Modelisation::ThreeD, false),
        "3D_HM" => (Modelisation::ThreeD, true),
        m => return Err(a.err("MODELE", format!("STAT_NON_LINE on an X-FEM {m} model is not supported yet"))),
    };
    let ndim = md.dim();
    // Behaviour: the elastic part of the kit, the hydraulic laws only act on eliminated unknowns.
    for occ in a.facts("COMPORTEMENT") {
        let rel = occ.text("RELATION").unwrap_or("ELAS");
        match (rel, hm) {
            ("ELAS", false) => {}
            ("KIT_HM", true) => {
                let kit = occ.texts("RELATION_KIT");
                if kit.first().map(String::as_str) != Some("ELAS") {
                    return Err(occ.err(
                        "RELATION_KIT",
                        format!("only an ELAS skeleton is supported yet in KIT_HM (got {kit:?})"),
                    ));
                }
                for k in &kit[1..] {
                    if !matches!(k.as_str(), "LIQU_SATU" | "HYDR_UTIL") {
                        return Err(occ.err("RELATION_KIT", format!("'{k}' is not supported yet")));
                    }
                }
            }
            _ => {
                return Err(occ.err(
                    "RELATION",
                    format!("RELATION='{rel}' on an X-FEM {modelisation} model is not supported yet"),
                ))
            }
        }
        if occ.text("DEFORMATION").is_some_and(|d| d != "PETIT") {
            return Err(occ.err("DEFORMATION", "only DEFORMATION='PETIT' is supported yet"));
        }
    }
    if a.given("SCHEMA_THM") && !hm {
        return Err(a.err("SCHEMA_THM", format!("SCHEMA_THM needs a hydro-mechanical model ({modelisation} is not)")));
    }
    let conv = a.fact("CONVERGENCE");
    if let Some(c) = conv {
        if c.given("RESI_REFE_RELA") {
            return Err(c.err("RESI_REFE_RELA", "not supported yet"));
        }
    }
    let resi_rela = conv.and_then(|c| c.real("RESI_GLOB_RELA"));
    let resi_maxi = conv.and_then(|c| c.real("RESI_GLOB_MAXI"));
    let resi_rela = if resi_rela.is_none() && resi_maxi.is_none() { Some(1e-6) } else { resi_rela };
    let iter_max = conv.and_then(|c| c.int("ITER_GLOB_MAXI")).unwrap_or(10).max(1) as usize;
    let mut opts = solver_options(a);
    opts.method = Method::Lu;

    // Materials.
    let chmat = a.req_concept("CHAM_MATER")?;
    let mats: Vec<Option<ConceptRef>> = match &*chmat.data() {
        ConceptData::MaterialField(MaterialField { cells, .. }) => cells.clone(),
        _ => return Err(a.err("CHAM_MATER", format!("{} is not a material field", chmat.label()))),
    };
    let material = |c: usize| -> Result<Rc<crate::concepts::model::Material>> {
        let mc = mats.get(c).cloned().flatten().ok_or_else(|| {
            a.err("CHAM_MATER", format!("cell {} has no material in {}", mesh.cell_names[c], chmat.label()))
        })?;
        let d = mc.data();
        match &*d {
            ConceptData::Material(m) => Ok(m.clone()),
            _ => Err(a.err("CHAM_MATER", format!("{} is not a material", mc.label()))),
        }
    };

    // Contact zones.
    let mut zones: Vec<Zone> = Vec::new();
    let mut iter_cont_maxi = 0;
    if let Some(cc) = a.concept("CONTACT") {
        let d = cc.data();
        let ConceptData::Contact(Contact { zones: cz, model: cmodel, iter_cont_maxi: icm }) = &*d else {
            return Err(a.err("CONTACT", format!("{} is not a contact definition", cc.label())));
        };
        if !Rc::ptr_eq(cmodel, model) {
            return Err(a.err("CONTACT", format!("{} is defined on another model ({})", cc.label(), cmodel.label())));
        }
        iter_cont_maxi = *icm;
        // Contact cells of every crack (xtyele), over the model's cracks.
        let topo: Vec<mortar::CrackTopo> = xm
            .cracks
            .iter()
            .map(|k| mortar::CrackTopo { lsn: &k.lsn, status: &k.status, heaviside_cells: &k.heaviside_cells })
            .collect();
        let contact = mortar::contact_cells(&mesh, &topo);
        if xm.contact != ContactKind::Mortar {
            return Err(a.err("CONTACT", "the cohesive zones need MODI_MODELE_XFEM CONTACT='MORTAR'"));
        }
        for z in cz {
            let g = xm.cracks.iter().position(|k| Rc::ptr_eq(k, &z.crack)).ok_or_else(|| {
                a.err("CONTACT", format!("FISS_MAIT={} is not a crack of {}", z.crack_name, model.label()))
            })?;
            if zones.iter().any(|o| o.crack == g) {
                return Err(a.err("CONTACT", format!("two zones on {}", z.crack_name)));
            }
            // RUPT_FRAG of the cells the crack crosses (one material).
            let mut params: Option<CzmParams> = None;
            for (&c, xc) in &xm.cells {
                if !xc.cracks.contains(&g) {
                    continue;
                }
                let m = material(c)?;
                let name = &mesh.cell_names[c];
                let get = |p: &str| -> Result<f64> {
                    mat_param(&m, "RUPT_FRAG", p, name)?.ok_or_else(|| {
                        a.err("CHAM_MATER", format!("cell {name}: RELATION='CZM_LIN_MIX' needs RUPT_FRAG {p}"))
                    })
                };
                let p = CzmParams::new(get("SIGM_C")?, get("GC")?, get("PENA_LAGR")?)
                    .map_err(|e| a.err("CHAM_MATER", format!("cell {name}: RUPT_FRAG: {e}")))?;
                match params {
                    None => params = Some(p),
                    Some(q) if q != p => {
                        return Err(a.err(
                            "CHAM_MATER",
                            format!(
                                "{}: several RUPT_FRAG materials along one interface are not supported yet",
                                z.crack_name
                            ),
                        ))
                    }
                    _ => {}
                }
            }
            let params = params.ok_or_else(|| a.err("CONTACT", format!("{} crosses no cell", z.crack_name)))?;
            let cells = &contact[g];
            let master = xm.masters[g].map(|(m, c)| (xm.lsn[m].as_slice(), c));
            let edges = mortar::cut_edges(&mesh, cells, &xm.lsn[g], master);
            let pk = mortar::vital_edges(&edges);
            zones.push(Zone {
                crack: g,
                params,
                order: z.order,
                packets: pk.packets.clone(),
                packet_of: pk.packet_of_node.clone(),
                edges: edges.iter().map(|e| (e.a.min(e.b), e.a.max(e.b))).collect(),
            });
        }
    }
    let mut npk = vec![0; xm.cracks.len()];
    for z in &zones {
        npk[z.crack] = z.packets.len();
    }
    let xd = XDofs::new(&mesh, &model_cells, &xm, ndim, &npk);

    // Elements.
    let t0 = Instant::now();
    let mut lins: Vec<Lin> = Vec::new();
    for &c in &model_cells {
        let m = material(c)?;
        let (law, _) = elastic_of(&m, &mesh.cell_names[c]).map_err(|e| e.at(a.span))?;
        law.check(md).map_err(|e| a.err("CHAM_MATER", format!("cell {}: {e}", mesh.cell_names[c])))?;
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let k = discrete::bulk_stiffness(mesh.cell_types[c], &coords, nodes, &xm, c, &law.hooke(md), md.nsig(), ndim)
            .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])).at(a.span))?;
        lins.push(Lin { dofs: xd.cell_dofs(nodes), k });
    }
    let mut laws: Vec<Law> = Vec::new();
    let mut lumped: Vec<Vec<f64>> = Vec::new();
    let lonref = {
        let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    };
    for (zi, z) in zones.iter().enumerate() {
        let rule = discrete::facet_rule(ndim, z.order).map_err(|e| a.err("CONTACT", e))?;
        let facets = discrete::facets(&mesh, &xm, z.crack, 1e-9 * lonref);
        let cps = discrete::couplings(&mesh, &xm, z.crack, &facets, &rule, &z.packet_of, &z.edges, ndim)
            .map_err(|e| a.err("CONTACT", format!("{}: {e}", xm.crack_names[z.crack])))?;
        let mut m = vec![0.0; z.packets.len()];
        for cp in &cps {
            let nodes = &mesh.cells[cp.cell];
            let mut dofs = xd.cell_dofs(nodes);
            let nu = dofs.len();
            let np = cp.packets.len();
            for &k in &cp.packets {
                let b = xd.packets[z.crack][k];
                dofs.extend(b + ndim..b + 2 * ndim); // w
            }
            for &k in &cp.packets {
                let b = xd.packets[z.crack][k];
                dofs.extend(b + 2 * ndim..b + 3 * ndim); // μ
            }
            let nd = dofs.len();
            let mut ke = vec![0.0; nd * nd];
            let wof = |k: usize, q: usize| nu + k * ndim + q;
            let muof = |k: usize, q: usize| nu + np * ndim + k * ndim + q;
            for r in 0..nu {
                for k in 0..np {
                    for q in 0..ndim {
                        let v = cp.c[r * np * ndim + k * ndim + q];
                        ke[r * nd + muof(k, q)] += v;
                        ke[muof(k, q) * nd + r] += v;
                    }
                }
            }
            for k in 0..np {
                for l in 0..np {
                    for q in 0..ndim {
                        let v = -cp.mm[k * np + l];
                        ke[muof(k, q) * nd + wof(l, q)] += v;
                        ke[wof(k, q) * nd + muof(l, q)] += v;
                    }
                }
                m[cp.packets[k]] += cp.m[k];
            }
            lins.push(Lin { dofs, k: ke });
        }
        for (k, &mk) in m.iter().enumerate() {
            if mk <= 0.0 {
                return Err(a.err(
                    "CONTACT",
                    format!(
                        "{}: multiplier packet {:?} has no interface measure",
                        xm.crack_names[z.crack],
                        names(&mesh, &z.packets[k])
                    ),
                ));
            }
            laws.push(Law { zone: zi, m: mk, base: xd.packets[z.crack][k] });
        }
        lumped.push(m);
    }
    let t_elements = t0.elapsed();

    // Instants.
    let mut states: Vec<CzmState> = vec![CzmState::default(); laws.len()];
    let mut x = vec![0.0; xd.n];
    let mut steps = if statics {
        Vec::new()
    } else {
        vec![Step { nume_ordre: 0, inst: times[0], fields: depl_fields(&mesh, &xm, &xd, &x, hm) }]
    };
    let mut log = String::new();
    let mut t_fact = Duration::ZERO;
    let mut t_asm = Duration::ZERO;
    let mut nfree = 0;
    let mut hm_report = String::new();
    let mut pinned = Vec::new();
    // Largest reference force of the converged steps: the scale of the
    // relative criterion once the forces vanish (a fully broken interface).
    let mut ref_hist: f64 = 0.0;
    let mut vanished_steps = Vec::new();
    for (n, &t) in times.iter().enumerate().skip(1) {
        let (cons, hydr, pins) = constraints(a, model, &mesh, &xm, &xd, &zones, t, ndim, hm, opts.nprec)?;
        if n == 1 {
            hm_report = hydr;
            pinned = pins;
        }
        let map = DofMap::build(xd.n, &cons).map_err(|e| a.err("EXCIT", e.to_string()))?;
        nfree = map.nfree;
        // Start from the previous state with this step's imposed values.
        let free: Vec<f64> = map.free_to_full.iter().map(|&d| x[d]).collect();
        x = map.expand(&free);
        let mut elems = ElementDofs::new();
        for l in &lins {
            elems.push(&l.dofs);
        }
        for l in &laws {
            let v: Vec<usize> = (l.base..l.base + 2 * ndim).collect();
            elems.push(&v);
        }
        let pattern = SparsityPattern::build(&map, &elems);
        let mut iters = 0;
        let (rel, abs) = loop {
            let ta = Instant::now();
            // Residual and tangent at x.
            let mut r = vec![0.0; xd.n];
            let mut asm = Assembler::new(&map, pattern.clone());
            for l in &lins {
                let nd = l.dofs.len();
                for (i, &di) in l.dofs.iter().enumerate() {
                    let row = &l.k[i * nd..(i + 1) * nd];
                    r[di] += row.iter().zip(&l.dofs).map(|(k, &dj)| k * x[dj]).sum::<f64>();
                }
                asm.add_matrix(&l.dofs, &l.k);
            }
            for (li, l) in laws.iter().enumerate() {
                let z = &zones[l.zone];
                let lam = &x[l.base..l.base + ndim];
                let w = &x[l.base + ndim..l.base + 2 * ndim];
                let ev = czm::evaluate(&z.params, ndim, lam, w, &states[li]);
                let rr = z.params.r();
                let nd = 2 * ndim;
                let mut ke = vec![0.0; nd * nd];
                for i in 0..ndim {
                    r[l.base + i] += l.m / rr * (ev.d[i] - lam[i]);
                    r[l.base + ndim + i] += l.m * ev.d[i];
                    for j in 0..ndim {
                        let dij = ev.dd[i][j];
                        let id = if i == j { 1.0 } else { 0.0 };
                        ke[i * nd + j] = l.m / rr * (dij - id);
                        ke[i * nd + ndim + j] = l.m * dij;
                        ke[(ndim + i) * nd + j] = l.m * dij;
                        ke[(ndim + i) * nd + ndim + j] = rr * l.m * dij;
                    }
                }
                let dofs: Vec<usize> = (l.base..l.base + nd).collect();
                asm.add_matrix(&dofs, &ke);
            }
            let (k, _) = asm.finish();
            // Symmetric equilibration: the system mixes stiffnesses (E·h)
            // with interface couplings of order 1; LU on the scaled matrix
            // keeps the accuracy of the solution.
            let (k, scale) = equilibrate(&k);
            t_asm += ta.elapsed();
            // Reduced residual and reference (reactions at prescribed unknowns).
            let mut rf = vec![0.0; map.nfree];
            let mut reactions: f64 = 0.0;
            for (d, rd) in r.iter().enumerate() {
                for &(i, c) in map.expr(d).0 {
                    rf[i] += c * rd;
                }
                if !map.is_free(d) {
                    reactions = reactions.max(rd.abs());
                }
            }
            let abs = inf_norm(&rf);
            let vanished = reactions <= 1e-6 * ref_hist;
            let scale_ref = if vanished { ref_hist } else { reactions };
            let rel = if scale_ref > 0.0 { abs / scale_ref } else { abs };
            if converged_check(iters, rel, abs, resi_rela, resi_maxi) {
                ref_hist = ref_hist.max(reactions);
                if vanished {
                    vanished_steps.push(n);
                }
            }
            // MECA_STATIQUE: one linear solve, no convergence test.
            let converged = if statics { iters == 1 } else { converged_check(iters, rel, abs, resi_rela, resi_maxi) };
            if converged {
                break (rel, abs);
            }
            if iters == iter_max {
                return Err(a.err(
                    "CONVERGENCE",
                    format!(
                        "Newton did not converge at INST={t} in {iter_max} iterations (relative residual {rel:.3e}, absolute {abs:.3e})"
                    ),
                ));
            }
            let tf = Instant::now();
            let fact = match solve::factorize(k.as_ref(), &opts) {
                Ok((f, ..)) => f,
                Err(e) => {
                    let dofs = match &e {
                        solve::SolveError::Singular { dofs, .. } => dofs.clone(),
                        _ => vec![],
                    };
                    let labels: Vec<String> =
                        dofs.iter().take(6).map(|&d| label(&mesh, &xm, &xd, &zones, map.free_to_full[d])).collect();
                    return Err(Error::runtime(format!("{e}; unknowns: {}", labels.join(", "))).at(a.span));
                }
            };
            let neg: Vec<f64> = rf.iter().zip(&scale).map(|(v, s)| -v * s).collect();
            let dx: Vec<f64> = fact.solve(&neg).iter().zip(&scale).map(|(v, s)| v * s).collect();
            t_fact += tf.elapsed();
            if dx.iter().any(|v| !v.is_finite()) {
                return Err(Error::runtime("the Newton correction is not finite (singular system)").at(a.span));
            }
            for (d, xd_) in x.iter_mut().enumerate() {
                let (terms, _) = map.expr(d);
                *xd_ += terms.iter().map(|&(i, c)| c * dx[i]).sum::<f64>();
            }
            iters += 1;
        };
        // Internal variables after convergence.
        for (li, l) in laws.iter().enumerate() {
            let z = &zones[l.zone];
            let ev = czm::evaluate(
                &z.params,
                ndim,
                &x[l.base..l.base + ndim],
                &x[l.base + ndim..l.base + 2 * ndim],
                &states[li],
            );
            states[li] = ev.new_state;
        }
        // The state of each cohesive interface: tractions, openings, damage, energy.
        let mut zone_log = String::new();
        for (zi, z) in zones.iter().enumerate() {
            let (mut lmin, mut lmax, mut wmax, mut wmin) = (f64::MAX, f64::MIN, f64::MIN, f64::MAX);
            let mut counts = [0usize; 3];
            let mut energy = 0.0;
            for (li, l) in laws.iter().enumerate().filter(|(_, l)| l.zone == zi) {
                lmin = lmin.min(x[l.base]);
                lmax = lmax.max(x[l.base]);
                wmin = wmin.min(x[l.base + ndim]);
                wmax = wmax.max(x[l.base + ndim]);
                counts[states[li].state.min(2) as usize] += 1;
                energy += l.m * z.params.dissipated_energy(states[li].kappa);
            }
            let _ = writeln!(
                zone_log,
                "        {}: lambda_n in [{lmin:.9e}, {lmax:.9e}], w_n in [{wmin:.9e}, {wmax:.9e}], sound/damaged/broken {}/{}/{}, dissipated {energy:.9e}",
                xm.crack_names[z.crack], counts[0], counts[1], counts[2]
            );
        }
        let _ = writeln!(
            log,
            "  {n:>4}  {:>14}  {iters:>5}  {:>14}  {:>14}",
            crate::interp::format::sci(t, 6, false),
            crate::interp::format::sci(rel, 3, false),
            crate::interp::format::sci(abs, 3, false)
        );
        log.push_str(&zone_log);
        steps.push(Step { nume_ordre: n as i64, inst: t, fields: depl_fields(&mesh, &xm, &xd, &x, hm) });
    }

    // The run log: what was simulated, eliminated, and how.
    let mut s = String::new();
    let _ = writeln!(s, "  {command} on X-FEM model {} ({modelisation}):", model.label());
    let _ = writeln!(
        s,
        "    simulated : {} elasticity, Heaviside enrichment by {} interface(s) ({})",
        match md {
            Modelisation::DPlan => "plane-strain",
            Modelisation::CPlan => "plane-stress",
            _ => "3D",
        },
        xm.cracks.len(),
        xm.crack_names.join(", ")
    );
    for (zi, z) in zones.iter().enumerate() {
        let _ = writeln!(
            s,
            "                cohesive interface {} (CZM_LIN_MIX, mortar, {} packets, facet rule ORDRE_INT={}, interface measure {:.12e})",
            xm.crack_names[z.crack],
            z.packets.len(),
            z.order,
            lumped[zi].iter().sum::<f64>()
        );
    }
    for (g, name) in xm.crack_names.iter().enumerate() {
        if !zones.iter().any(|z| z.crack == g) {
            let _ = writeln!(s, "                {name}: no contact zone: free surfaces, no interface unknowns");
        }
    }
    if hm {
        s.push_str(&hm_report);
    }
    for p in &pinned {
        let _ = writeln!(s, "    null mode : {p}");
    }
    if !vanished_steps.is_empty() {
        let _ = writeln!(
            s,
            "    criterion : at steps {vanished_steps:?} the reactions vanished (below 1e-6 of the largest earlier one); \
             RESI_GLOB_RELA was measured against the largest earlier reaction"
        );
    }
    if iter_cont_maxi > 0 {
        let _ = writeln!(
            s,
            "    contact loop: the cohesive variables are updated after each converged step (ITER_CONT_MAXI={iter_cont_maxi} not needed)"
        );
    }
    let _ = writeln!(
        s,
        "    unknowns  : {} ({} standard, {} Heaviside, {} interface λ/w/μ), {} solved after elimination of the kinematic conditions",
        xd.n, xd.n_std, xd.n_heaviside, xd.n_interface, nfree
    );
    let _ = writeln!(
        s,
        "  {:>4}  {:>14}  {:>5}  {:>14}  {:>14}",
        "step", "INST", "iters", "RESI_GLOB_RELA", "RESI_GLOB_MAXI"
    );
    s.push_str(&log);
    let _ = writeln!(
        s,
        "    time      : elements {:.3} s, assembly {:.3} s, factorization and solves {:.3} s, total {:.3} s",
        t_elements.as_secs_f64(),
        t_asm.as_secs_f64(),
        t_fact.as_secs_f64(),
        t_start.elapsed().as_secs_f64()
    );
    ctx.io.mess(&s);
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData { model: model.clone(), material: Some(chmat), loads, steps })))
}

fn names(mesh: &crate::mesh::Mesh, nodes: &[usize]) -> Vec<String> {
    nodes.iter().map(|&n| mesh.node_names[n].clone()).collect()
}

/// A readable name of an unknown.
fn label(mesh: &crate::mesh::Mesh, xm: &XfemModel, xd: &XDofs, zones: &[Zone], d: usize) -> String {
    const XYZ: [&str; 3] = ["X", "Y", "Z"];
    for (n, s) in xd.std.iter().enumerate() {
        if let Some(b) = s {
            if (*b..*b + xd.ndim).contains(&d) {
                return format!("{} D{}", mesh.node_names[n], XYZ[d - b]);
            }
        }
        for (j, &b) in xd.sets[n].iter().enumerate() {
            if (b..b + xd.ndim).contains(&d) {
                return format!("{} H{}{}", mesh.node_names[n], j + 1, XYZ[d - b]);
            }
        }
    }
    for z in zones {
        for (k, &b) in xd.packets[z.crack].iter().enumerate() {
            if (b..b + 3 * xd.ndim).contains(&d) {
                let what = ["λ", "w", "μ"][(d - b) / xd.ndim];
                return format!(
                    "{} packet {:?} {what}{}",
                    xm.crack_names[z.crack],
                    names(mesh, &z.packets[k]),
                    (d - b) % xd.ndim
                );
            }
        }
    }
    format!("unknown #{d}")
}

/// The kinematic conditions of the loads at `t`, the report on the
/// hydraulic unknowns (HM models: all must be prescribed to zero), and the
/// rigid translations pinned when NPREC < 0.
#[allow(clippy::too_many_arguments)]
fn constraints(
    a: &Args,
    model: &ConceptRef,
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    xd: &XDofs,
    zones: &[Zone],
    t: f64,
    ndim: usize,
    hm: bool,
    nprec: i32,
) -> Result<(Constraints, String, Vec<String>)> {
    let mut cons = Constraints::new();
    let mut hydraulic: BTreeMap<(usize, String), f64> = BTreeMap::new();
    let mut blocked_dir = vec![false; ndim];
    let mut jump_cache: BTreeMap<(usize, String), bool> = BTreeMap::new();
    for (lc, mult) in loads(a, t)? {
        let data = lc.data();
        let ConceptData::Load(load) = &*data else {
            return Err(a.err("EXCIT", format!("{} is not a mechanical load", lc.label())));
        };
        if !Rc::ptr_eq(&load.model, model) {
            return Err(
                a.err("EXCIT", format!("load {} is defined on another model ({})", lc.label(), load.model.label()))
            );
        }
        for item in &load.items {
            let LoadItem::Dof { node, component, value } = item else {
                return Err(
                    a.err("EXCIT", format!("load {}: only DDL_IMPO is supported yet on an X-FEM model", lc.label()))
                );
            };
            let n = *node;
            let Some(std) = xd.std[n] else {
                return Err(
                    a.err("EXCIT", format!("load {}: node {} is not in the model", lc.label(), mesh.node_names[n]))
                );
            };
            let c = component.as_str();
            if is_hydraulic(c) {
                if !hm {
                    return Err(
                        a.err("EXCIT", format!("load {}: component {c} does not exist in this model", lc.label()))
                    );
                }
                let v = mult * load_value(value, &mesh.coords[n], t)?;
                hydraulic.insert((n, c.to_string()), v);
                continue;
            }
            if let Some(d) = direction(c).filter(|&d| d < ndim) {
                let v = mult * load_value(value, &mesh.coords[n], t)?;
                cons.impose(std + d, v);
                blocked_dir[d] = true;
                // A function-valued condition prescribes the trace on every
                // side of the node (xddlimf): each Heaviside part makes the
                // trace match the function just across the interface.
                if load.functional && !xd.sets[n].is_empty() {
                    let LoadValue::Func(f) = value else { unreachable!("functional load") };
                    let same: BTreeSet<usize> = load
                        .items
                        .iter()
                        .filter_map(|it| match it {
                            LoadItem::Dof { node, component, value: LoadValue::Func(g) }
                                if component == c && Rc::ptr_eq(g, f) =>
                            {
                                Some(*node)
                            }
                            _ => None,
                        })
                        .collect();
                    let key = (Rc::as_ptr(f) as usize, c.to_string());
                    let jumps = match jump_cache.get(&key) {
                        Some(&j) => j,
                        None => {
                            let j = function_jumps(mesh, xm, &same, f, t)
                                .map_err(|e| a.err("EXCIT", format!("load {}: {c}: {e}", lc.label())))?;
                            jump_cache.insert(key, j);
                            j
                        }
                    };
                    let (values, points) = trace_sets(mesh, xm, n, &same, f, t, jumps).map_err(|e| {
                        a.err("EXCIT", format!("load {}: {c} at node {}: {e}", lc.label(), mesh.node_names[n]))
                    })?;
                    for (j, h) in values {
                        cons.impose(xd.sets[n][j] + d, mult * h);
                    }
                    // xddlimf's point relation: the whole field at a point
                    // of the set's region equals the function there.
                    for p in points {
                        let nodes = &mesh.cells[p.cell];
                        let mut terms = Vec::new();
                        for (k, &i) in nodes.iter().enumerate() {
                            let std_i = xd.std[i].expect("node of a model cell");
                            terms.push((std_i + d, p.ff[k]));
                            if let Some(jj) = xm.node_sets[i].iter().position(|&r| r == p.region) {
                                terms.push((xd.sets[i][jj] + d, 2.0 * p.ff[k]));
                            }
                        }
                        cons.relation(terms, mult * p.value);
                    }
                }
            } else if let Some((j, d)) = heaviside_component(c).filter(|&(_, d)| d < ndim) {
                // Acts on the nodes that carry the set.
                if let Some(&b) = xd.sets[n].get(j) {
                    cons.impose(b + d, mult * load_value(value, &mesh.coords[n], t)?);
                }
            } else {
                return Err(a.err(
                    "EXCIT",
                    format!("load {}: DDL_IMPO on {c} is not supported yet on an X-FEM model", lc.label()),
                ));
            }
        }
    }
    // Hydraulics: every unknown must be prescribed to zero to be eliminated.
    let mut report = String::new();
    if hm {
        if let Some(((n, c), v)) = hydraulic.iter().find(|(_, v)| **v != 0.0) {
            return Err(a.err(
                "EXCIT",
                format!(
                    "{c} = {v} at node {}: a non-zero hydraulic condition needs coupled flow, which X-FEM {} \
                     elements do not support yet",
                    mesh.node_names[*n],
                    if ndim == 2 { "D_PLAN_HM" } else { "3D_HM" }
                ),
            ));
        }
        let fixed = |n: usize, c: &str| hydraulic.contains_key(&(n, c.to_string()));
        let free_msg = |what: String| {
            a.err(
                "EXCIT",
                format!(
                    "{what} is not prescribed: coupled hydraulics in X-FEM elements is not supported yet \
                     (the hydraulic unknowns are eliminated only when all are prescribed to zero)"
                ),
            )
        };
        let mut vertices: BTreeSet<usize> = BTreeSet::new();
        for (nodes, t) in mesh.cells.iter().zip(&mesh.cell_types) {
            if t.dim() == ndim {
                vertices.extend(nodes[..t.nvertices()].iter().copied().filter(|&n| xd.std[n].is_some()));
            }
        }
        let mut n_h = 0;
        for &n in &vertices {
            if !fixed(n, "PRE1") {
                return Err(free_msg(format!("PRE1 at node {}", mesh.node_names[n])));
            }
            for j in 0..xd.sets[n].len() {
                let c = format!("H{}PRE1", j + 1);
                if !fixed(n, &c) {
                    return Err(free_msg(format!("{c} at node {}", mesh.node_names[n])));
                }
                n_h += 1;
            }
        }
        // Fracture unknowns: one block per crack a node's packets belong to.
        let mut n_pk = 0;
        for z in zones {
            for p in &z.packets {
                let block =
                    |n: usize| zones.iter().filter(|o| o.crack < z.crack && o.packet_of.contains_key(&n)).count();
                for (role, cmps) in
                    [("p_f", ["PRE_FLU", "PR2_FLU"]), ("q+", ["LAG_FLI", "LA2_FLI"]), ("q-", ["LAG_FLS", "LA2_FLS"])]
                {
                    let ok = p.iter().any(|&n| {
                        let b = block(n);
                        b < 2 && (fixed(n, cmps[b]) || (role == "p_f" && b == 1 && fixed(n, cmps[0])))
                    });
                    if !ok {
                        return Err(free_msg(format!(
                            "the fracture unknown {role} ({}) of {} on packet {:?}",
                            cmps.join("/"),
                            xm.crack_names[z.crack],
                            names(mesh, p)
                        )));
                    }
                }
                n_pk += 1;
            }
        }
        let _ = writeln!(
            report,
            "    eliminated: hydraulics — PRE1 on {} vertices, H*PRE1 on {n_h} enrichment sets, fracture p_f/q+/q- on {n_pk} packets, \
             all prescribed to 0 by the loads; with p = p_f = 0 the Biot term b·p and the fracture pressure in the interface \
             vanish, so THM_INIT, THM_DIFFU, THM_LIQU, SCHEMA_THM and the time step play no part",
            vertices.len()
        );
    }
    // Rigid translations with no condition at all (NPREC < 0: pinned, as a
    // singular-tolerant direct solver would pick one solution).
    let mut pins = Vec::new();
    for (d, blocked) in blocked_dir.iter().enumerate() {
        if *blocked || nprec >= 0 {
            continue;
        }
        let n = xd.std.iter().position(|s| s.is_some()).expect("a node");
        cons.impose(xd.std[n].unwrap() + d, 0.0);
        pins.push(format!(
            "no condition on D{} anywhere: the rigid translation is fixed by D{} = 0 at node {} (SOLVEUR NPREC < 0)",
            ["X", "Y", "Z"][d],
            ["X", "Y", "Z"][d],
            mesh.node_names[n]
        ));
    }
    Ok((cons, report, pins))
}

/// DEPL of an X-FEM solution on the mesh nodes: DX DY (DZ), PRE1 for HM
/// models (zero at vertices: eliminated), then H<j><X|Y|Z> per set.
fn depl_fields(mesh: &crate::mesh::Mesh, xm: &XfemModel, xd: &XDofs, x: &[f64], hm: bool) -> BTreeMap<String, Field> {
    let ndim = xd.ndim;
    let xyz = ["X", "Y", "Z"];
    let maxsets = xm.node_sets.iter().map(|s| s.len()).max().unwrap_or(0);
    let mut comps: Vec<String> = (0..ndim).map(|d| format!("D{}", xyz[d])).collect();
    if hm {
        comps.push("PRE1".into());
    }
    for j in 0..maxsets {
        for d in xyz.iter().take(ndim) {
            comps.push(format!("H{}{d}", j + 1));
        }
    }
    let nc = comps.len();
    let mut values = vec![f64::NAN; mesh.nnodes() * nc];
    let mut vertex = vec![false; mesh.nnodes()];
    for (nodes, t) in mesh.cells.iter().zip(&mesh.cell_types) {
        if t.dim() == ndim {
            for &n in &nodes[..t.nvertices()] {
                vertex[n] = true;
            }
        }
    }
    for n in 0..mesh.nnodes() {
        let Some(b) = xd.std[n] else { continue };
        let row = &mut values[n * nc..(n + 1) * nc];
        row[..ndim].copy_from_slice(&x[b..b + ndim]);
        let mut k = ndim;
        if hm {
            if vertex[n] {
                row[k] = 0.0;
            }
            k += 1;
        }
        for (j, &s) in xd.sets[n].iter().enumerate() {
            row[k + j * ndim..k + (j + 1) * ndim].copy_from_slice(&x[s..s + ndim]);
        }
    }
    let mut f = BTreeMap::new();
    f.insert("DEPL".to_string(), Field::Node { components: comps, values });
    f
}

/// `S K S` with `S = diag(1/√max_j |K_ij|)` (rows and columns), and S.
fn equilibrate(k: &faer::sparse::SparseColMat<usize, f64>) -> (faer::sparse::SparseColMat<usize, f64>, Vec<f64>) {
    let n = k.nrows();
    let colp = k.symbolic().col_ptr().to_vec();
    let rows = k.symbolic().row_idx().to_vec();
    let mut vals = k.val().to_vec();
    let mut s = vec![0.0f64; n];
    for j in 0..n {
        for p in colp[j]..colp[j + 1] {
            let v = vals[p].abs();
            s[j] = s[j].max(v);
            s[rows[p]] = s[rows[p]].max(v);
        }
    }
    for v in s.iter_mut() {
        *v = if *v > 0.0 { 1.0 / v.sqrt() } else { 1.0 };
    }
    for j in 0..n {
        for p in colp[j]..colp[j + 1] {
            vals[p] *= s[rows[p]] * s[j];
        }
    }
    let sym = faer::sparse::SymbolicSparseColMat::new_checked(n, n, colp, None, rows);
    (faer::sparse::SparseColMat::new(sym, vals), s)
}

fn converged_check(iters: usize, rel: f64, abs: f64, resi_rela: Option<f64>, resi_maxi: Option<f64>) -> bool {
    iters > 0 && resi_rela.map(|tol| rel <= tol).unwrap_or(true) && resi_maxi.map(|tol| abs <= tol).unwrap_or(true)
}

/// The Heaviside parts of node `n` under a function-valued DDL_IMPO of the
/// node set `same` (`xddlimf`): along each mesh edge from `n` to another
/// node `k` of the set where an interface crosses, the set of `n` for the
/// region on `k`'s side is fixed so that the trace there equals the function
/// just beyond the crossing: N_n(a_n + 2h) + N_k a_k = f(x_c⁺) on a linear
/// edge, with a_n = f(x_n), a_k = f(x_k). A set not reached this way gets
/// h = 0 when the function is continuous across the crossings of `n`, and
/// otherwise Code_Aster's point relation ([`point_relation`]) when a node of
/// the set's region belongs to the condition around `n` (nothing if none). A
/// quadratic edge is handled when the function is continuous across the
/// crossing (then h = 0); a discontinuous one stops the run.
fn trace_sets(
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    n: usize,
    same: &BTreeSet<usize>,
    f: &ConceptRef,
    t: f64,
    jump: bool,
) -> Result<TraceConditions> {
    const EPS: f64 = 2e-6;
    let eval = |x: &[f64; 3]| crate::stages::core::eval::eval_at(f, x, t);
    let mut out: Vec<(usize, f64)> = (0..xm.node_sets[n].len()).map(|j| (j, 0.0)).collect();
    let mut done = vec![false; out.len()];
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let ct = mesh.cell_types[c];
        if ct.dim() != mesh.dim || !nodes.contains(&n) {
            continue;
        }
        for e in crate::xfem::levelset::edges(ct) {
            let (ia, ib) = (nodes[e[0]], nodes[e[1]]);
            let k = if ia == n {
                ib
            } else if ib == n {
                ia
            } else {
                continue;
            };
            if !same.contains(&k) {
                continue;
            }
            // The first crack that changes sign along the edge.
            let Some(g) = (0..xm.lsn.len()).find(|&g| xm.lsn[g][n] * xm.lsn[g][k] < 0.0) else { continue };
            let alpha = xm.lsn[g][n] / (xm.lsn[g][n] - xm.lsn[g][k]);
            let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
            let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
            let beyond = at(alpha + EPS * (1.0 - alpha));
            let before = at(alpha * (1.0 - EPS));
            // Region just beyond the crossing, from the cell's nodal level sets.
            let xi = crate::fem::reference::inverse_map(
                ct,
                &nodes.iter().map(|&m| mesh.coords[m]).collect::<Vec<_>>(),
                &beyond,
                &Default::default(),
            )
            .map_err(|e| Error::runtime(format!("locating the crossing: {e}")))?
            .xi;
            let ff = crate::fem::reference::shape(ct, &xi);
            let region =
                crate::xfem::region_code(&crate::xfem::model::point_signs(&xm.lsn, &xm.masters, nodes, &ff, &[], &[]));
            let Some(j) = xm.node_sets[n].iter().position(|&r| r == region) else { continue };
            let (fn_, fk, fc) = (eval(&xn)?, eval(&xk)?, eval(&beyond)?);
            let quadratic = ct.nnodes() > ct.nvertices();
            let fb = eval(&before)?;
            let discontinuous = (fc - fb).abs() > 1e-9 * fc.abs().max(fb.abs()).max(1e-300);
            let h = if quadratic {
                if discontinuous {
                    return Err(Error::runtime(
                        "a function discontinuous across the interface on a quadratic edge is not supported yet",
                    ));
                }
                0.0
            } else {
                (fc - alpha * fk) / (2.0 * (1.0 - alpha)) - fn_ / 2.0
            };
            if done[j] && (out[j].1 - h).abs() > 1e-9 * h.abs().max(out[j].1.abs()).max(1e-300) {
                return Err(Error::runtime(format!(
                    "two edges ask different Heaviside values ({} and {h}) for one set",
                    out[j].1
                )));
            }
            out[j] = (j, h);
            done[j] = true;
        }
    }
    // A set no cut edge of the condition reaches keeps h = 0, which is exact
    // for a function continuous across the interfaces. For a discontinuous
    // one Code_Aster ties the whole field at a point of the set's region
    // (xddlimf's second case), which we do not do yet.
    // A set no cut edge reaches: Code_Aster ties the whole field at a point
    // of the set's region to the function (xddlimf's second case), or, when
    // no node of the condition lies in that region around the node, imposes
    // nothing on it.
    // For a function continuous across the interfaces the trace matches on
    // every side with h = 0, which that relation then also gives.
    let mut kept = Vec::new();
    let mut points = Vec::new();
    for (j, h) in out {
        if done[j] || !jump {
            kept.push((j, h));
        } else if let Some(p) = point_relation(mesh, xm, n, j, same, f, t)? {
            points.push(p);
        }
    }
    Ok((kept, points))
}

/// Does `f` jump across an interface somewhere on the condition's node set
/// (along a mesh edge between two of its nodes where a level set changes sign)?
fn function_jumps(
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    same: &BTreeSet<usize>,
    f: &ConceptRef,
    t: f64,
) -> Result<bool> {
    const EPS: f64 = 2e-6;
    for (c, nodes) in mesh.cells.iter().enumerate() {
        let ct = mesh.cell_types[c];
        if ct.dim() != mesh.dim {
            continue;
        }
        for e in crate::xfem::levelset::edges(ct) {
            let (n, k) = (nodes[e[0]], nodes[e[1]]);
            if !same.contains(&n) || !same.contains(&k) {
                continue;
            }
            for g in 0..xm.lsn.len() {
                if xm.lsn[g][n] * xm.lsn[g][k] >= 0.0 {
                    continue;
                }
                let alpha = xm.lsn[g][n] / (xm.lsn[g][n] - xm.lsn[g][k]);
                let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
                let at = |s: f64| -> [f64; 3] { [0, 1, 2].map(|i| xn[i] + s * (xk[i] - xn[i])) };
                let fa = crate::stages::core::eval::eval_at(f, &at(alpha * (1.0 - EPS)), t)?;
                let fb = crate::stages::core::eval::eval_at(f, &at(alpha + EPS * (1.0 - alpha)), t)?;
                if (fa - fb).abs() > 1e-9 * fa.abs().max(fb.abs()).max(1e-300) {
                    return Ok(true);
                }
            }
        }
    }
    Ok(false)
}

/// The conditions on a node's Heaviside sets: (set, value) pairs and point relations.
type TraceConditions = (Vec<(usize, f64)>, Vec<PointRelation>);

/// `xddlimf`'s relation for a set no cut edge reaches: the whole field of
/// the set's region at a point of a cell holding the node, equal to the
/// function there.
struct PointRelation {
    cell: usize,
    /// Shape functions of the cell at the point.
    ff: Vec<f64>,
    region: i32,
    value: f64,
}

/// The point of [`PointRelation`]: in a cell holding node `n` and a node `k`
/// of the condition whose own region is the set's, on the segment n–k at
/// Code_Aster's level-set-weighted position beyond the interface
/// ((|φ_n| + |φ_k|/2) x_k + |φ_k|/2 x_n)/(|φ_n| + |φ_k|), `k` the farthest
/// from the interface.
fn point_relation(
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    n: usize,
    j: usize,
    same: &BTreeSet<usize>,
    f: &ConceptRef,
    t: f64,
) -> Result<Option<PointRelation>> {
    let region = xm.node_sets[n][j];
    let mut best: Option<(f64, usize, usize, usize)> = None; // (|φ_k|, cell, k, crack)
    for (c, nodes) in mesh.cells.iter().enumerate() {
        if mesh.cell_types[c].dim() != mesh.dim || !nodes.contains(&n) {
            continue;
        }
        for &k in nodes {
            if k == n || !same.contains(&k) || xm.node_region[k] != region {
                continue;
            }
            let Some(g) = (0..xm.lsn.len()).find(|&g| xm.lsn[g][n] * xm.lsn[g][k] < 0.0) else { continue };
            let lk = xm.lsn[g][k].abs();
            if best.is_none_or(|b| lk > b.0) {
                best = Some((lk, c, k, g));
            }
        }
    }
    let Some((lk, c, k, g)) = best else { return Ok(None) };
    let ln = xm.lsn[g][n].abs();
    let (xn, xk) = (mesh.coords[n], mesh.coords[k]);
    let xp: [f64; 3] = [0, 1, 2].map(|i| ((ln + lk / 2.0) * xk[i] + lk / 2.0 * xn[i]) / (ln + lk));
    let ct = mesh.cell_types[c];
    let coords: Vec<[f64; 3]> = mesh.cells[c].iter().map(|&m| mesh.coords[m]).collect();
    let xi = crate::fem::reference::inverse_map(ct, &coords, &xp, &Default::default())
        .map_err(|e| Error::runtime(format!("locating xddlimf's point: {e}")))?
        .xi;
    let ff = crate::fem::reference::shape(ct, &xi);
    let value = crate::stages::core::eval::eval_at(f, &xp, t)?;
    Ok(Some(PointRelation { cell: c, ff, region, value }))
}
