//! The kinematic conditions of an X-FEM solve at an instant: DDL_IMPO on standard, Heaviside and
//! hydraulic components; function-valued conditions on enriched nodes through `xfem::conditions`
//! (`xddlimf`); the elimination of fully prescribed hydraulics with its report; the rigid translations
//! pinned under NPREC < 0.

use super::setup::names;
use super::setup::Setup;
use super::state::PorePressure;
use crate::diag::Result;
use crate::fem::dofs::Constraints;
use crate::fem::physics::{Condition, Force, Load};
use crate::stages::core::settings::Settings;
use crate::xfem::conditions::{function_jumps, trace_sets};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

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

/// The multiplier (0: λ, 1: w, 2: μ) and local component (C, F1, F2) of an interface component of the
/// first block: LAGS_*, LAG2_*, LAG3_*.
fn interface_component(c: &str) -> Option<(usize, usize)> {
    let (head, d) = c.split_once('_')?;
    let u = ["LAGS", "LAG2", "LAG3"].iter().position(|h| *h == head)?;
    let q = ["C", "F1", "F2"].iter().position(|x| *x == d)?;
    Some((u, q))
}

fn direction(c: &str) -> Option<usize> {
    match c {
        "DX" => Some(0),
        "DY" => Some(1),
        "DZ" => Some(2),
        _ => None,
    }
}

/// What the loads prescribe at an instant.
pub struct Conditions {
    pub cons: Constraints,
    /// The report on the hydraulic unknowns (HM models), for the log.
    pub report: String,
    /// The rigid translations pinned when NPREC < 0, for the log.
    pub pins: Vec<String>,
    /// The prescribed pore pressure when it is not zero everywhere (HM models).
    pub pressure: Option<PorePressure>,
    /// A hydraulic unknown no load prescribes (HM models), named: the flow must then be solved.
    pub free_hydraulics: Option<String>,
    /// The first load this driver does not apply (the HM driver may, with coupled flow).
    pub unsupported: Option<crate::diag::Error>,
}

impl Conditions {
    /// Stop on a load this driver does not apply, or when a hydraulic unknown is free: this driver
    /// eliminates the hydraulics.
    pub fn require_prescribed_hydraulics(&self, cfg: &Settings) -> Result<()> {
        if let Some(e) = &self.unsupported {
            return Err(e.clone());
        }
        match &self.free_hydraulics {
            None => Ok(()),
            Some(what) => Err(cfg.err(
                "EXCIT",
                format!(
                    "{what} is not prescribed: the flow must be solved, which X-FEM elements with cohesive \
                     interfaces (CONTACT) or with MECA_STATIQUE do not support yet"
                ),
            )),
        }
    }
}

/// A load this driver does not apply (it may go to the HM driver, with coupled flow).
fn unsupported_load(cfg: &Settings, s: &Setup, name: &str) -> crate::diag::Error {
    cfg.err(
        "EXCIT",
        format!(
            "load {name}: only DDL_IMPO, PRES_REP with FISSURE and PESANTEUR are supported yet on an X-FEM model{}",
            if s.hm { " with cohesive interfaces or with every hydraulic unknown prescribed" } else { "" }
        ),
    )
}

/// The kinematic conditions of the loads at an instant, the report on the
/// hydraulic unknowns (HM models: all must be prescribed; the pore pressure
/// they give acts on the skeleton), and the rigid translations pinned when
/// NPREC < 0.
pub fn constraints(cfg: &Settings, s: &Setup, loads: &[Load]) -> Result<Conditions> {
    let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
    let mut cons = Constraints::new();
    let mut hydraulic: BTreeMap<(usize, String), f64> = BTreeMap::new();
    let mut blocked_dir = vec![false; ndim];
    let mut jump_cache: BTreeMap<(usize, String), bool> = BTreeMap::new();
    let mut flux_loads: Vec<String> = Vec::new();
    let mut unsupported = None;
    let blocks = super::state::node_blocks(s);
    for load in loads {
        let name = &load.name;
        for item in &load.forces {
            match item {
                // Lip pressures and gravity are forces (`super::forces`).
                Force::LipPressure { .. } | Force::Gravity { .. } => {}
                // A fluid flux acts on the hydraulic equations only; they are eliminated when every
                // hydraulic unknown is prescribed (checked below), and then it changes no unknown.
                Force::Flux { value, heat: false, .. } if s.hm => {
                    if s.flow.is_some() && value.constant != Some(0.0) {
                        return Err(cfg.err(
                            "EXCIT",
                            format!(
                                "load {name}: a non-zero FLUX_THM_REP with cohesive interfaces and coupled flow is not \
                                 supported yet"
                            ),
                        ));
                    }
                    if !flux_loads.contains(name) {
                        flux_loads.push(name.clone());
                    }
                }
                // Kept for later: with coupled flow the HM driver takes the scene, loads and all.
                _ => {
                    if unsupported.is_none() {
                        unsupported = Some(unsupported_load(cfg, s, name));
                    }
                }
            }
        }
        for item in &load.conditions {
            let Condition::Dof { node, component, value } = item else {
                if unsupported.is_none() {
                    unsupported = Some(unsupported_load(cfg, s, name));
                }
                continue;
            };
            let n = *node;
            let Some(std) = xd.std[n] else {
                return Err(cfg.err("EXCIT", format!("load {name}: node {} is not in the model", mesh.node_names[n])));
            };
            let c = *component;
            if let Some((u, q)) = interface_component(c).filter(|&(_, q)| q < ndim) {
                let v = value.at(&mesh.coords[n])?;
                match blocks[n].as_slice() {
                    [(zi, k)] => cons.impose(xd.packets[s.zones[*zi].crack][*k] + u * ndim + q, v),
                    // A node on no packet: its interface unknowns are inactive (held at zero by X-FEM's own
                    // relations in Code_Aster), and the condition has nothing to act on there.
                    [] => {}
                    _ => {
                        return Err(cfg.err(
                            "EXCIT",
                            format!(
                                "load {name}: {c} at node {}, which is on the packets of several interfaces: not \
                                 supported yet",
                                mesh.node_names[n]
                            ),
                        ))
                    }
                }
                continue;
            }
            if is_hydraulic(c) {
                if !s.hm {
                    return Err(cfg.err("EXCIT", format!("load {name}: component {c} does not exist in this model")));
                }
                let v = value.at(&mesh.coords[n])?;
                hydraulic.insert((n, c.to_string()), v);
                continue;
            }
            if let Some(d) = direction(c).filter(|&d| d < ndim) {
                let v = value.at(&mesh.coords[n])?;
                cons.impose(std + d, v);
                blocked_dir[d] = true;
                // A function-valued condition prescribes the trace on every
                // side of the node (xddlimf): each Heaviside part makes the
                // trace match the function just across the interface.
                if let (true, Some(f)) = (load.functional && !xd.sets[n].is_empty(), value.function) {
                    let same: BTreeSet<usize> = load
                        .conditions
                        .iter()
                        .filter_map(|it| match it {
                            Condition::Dof { node, component, value: g }
                                if *component == c && g.function == Some(f) =>
                            {
                                Some(*node)
                            }
                            _ => None,
                        })
                        .collect();
                    let at = |x: &[f64; 3]| value.at(x).map_err(|e| e.msg);
                    let key = (f, c.to_string());
                    let jumps = match jump_cache.get(&key) {
                        Some(&j) => j,
                        None => {
                            let j = function_jumps(mesh, xm, &same, &at)
                                .map_err(|e| cfg.err("EXCIT", format!("load {name}: {c}: {e}")))?;
                            jump_cache.insert(key, j);
                            j
                        }
                    };
                    let (values, points) = trace_sets(mesh, xm, n, &same, &at, jumps).map_err(|e| {
                        cfg.err("EXCIT", format!("load {name}: {c} at node {}: {e}", mesh.node_names[n]))
                    })?;
                    for (j, h) in values {
                        cons.impose(xd.sets[n][j] + d, h);
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
                                terms.push((xd.sets[i][jj] + d, xm.psi(i, jj, p.region) * p.ff[k]));
                            }
                        }
                        cons.relation(terms, p.value);
                    }
                }
            } else if let Some((j, d)) = heaviside_component(c).filter(|&(_, d)| d < ndim) {
                // Acts on the nodes that carry the set.
                if let Some(&b) = xd.sets[n].get(j) {
                    cons.impose(b + d, value.at(&mesh.coords[n])?);
                }
            } else {
                return Err(
                    cfg.err("EXCIT", format!("load {name}: DDL_IMPO on {c} is not supported yet on an X-FEM model"))
                );
            }
        }
    }
    let (mut report, pressure, free_hydraulics) = if let Some(flow) = &s.flow {
        impose_flow(cfg, s, flow, &blocks, &hydraulic, &mut cons)?;
        let fixed: BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
        (flow.report(cfg, s, &|d| fixed.contains(&d))?, None, None)
    } else if s.hm {
        match hydraulic_report(cfg, s, &hydraulic)? {
            Ok((r, p)) => (r, p, None),
            Err(what) => (String::new(), None, Some(what)),
        }
    } else {
        (String::new(), None, None)
    };
    if !flux_loads.is_empty() {
        let why = if s.flow.is_some() {
            "a zero flux FLUN_HYDR1 (the only one supported with cohesive interfaces and coupled flow)"
        } else {
            "on the eliminated hydraulic equations only"
        };
        let _ = writeln!(report, "    FLUX_THM_REP of {}: {why}, so it changes no unknown", flux_loads.join(", "));
    }
    let pins = pin_translations(s, &mut cons, &blocked_dir);
    Ok(Conditions { cons, report, pins, pressure, free_hydraulics, unsupported })
}

/// The hydraulic values of the loads on the flow's unknowns: PRE1 and H<j>PRE1 on the vertices (passed
/// over on middle nodes and nodes without the set, as Code_Aster's `afddli`), the fracture unknowns on
/// the packet of the node's first interface block (PRE_FLU, LAG_FLI, LAG_FLS).
fn impose_flow(
    cfg: &Settings,
    s: &Setup,
    flow: &super::setup::Flow,
    blocks: &[Vec<(usize, usize)>],
    hydraulic: &BTreeMap<(usize, String), f64>,
    cons: &mut Constraints,
) -> Result<()> {
    let mesh = &*s.mesh;
    for ((n, c), &v) in hydraulic {
        let n = *n;
        let d = match c.as_str() {
            "PRE1" => flow.pre1[n],
            "PRE_FLU" | "LAG_FLI" | "LAG_FLS" => {
                let off = ["PRE_FLU", "LAG_FLI", "LAG_FLS"].iter().position(|x| x == c).expect("listed");
                match blocks[n].as_slice() {
                    [(zi, k)] => Some(flow.fracture[*zi][*k] + off),
                    [] => None, // on no packet: nothing to act on (as LAGS_* above)
                    _ => {
                        return Err(cfg.err(
                            "EXCIT",
                            format!(
                                "{c} at node {}, on the packets of several interfaces: not supported yet",
                                mesh.node_names[n]
                            ),
                        ))
                    }
                }
            }
            h if h.starts_with('H') && h.ends_with("PRE1") => {
                let j: usize = h[1..h.len() - 4]
                    .parse()
                    .map_err(|_| cfg.err("EXCIT", format!("{h}: not a Heaviside pressure component")))?;
                flow.hpre1[n].get(j.wrapping_sub(1)).copied().flatten()
            }
            other => {
                return Err(cfg.err(
                    "EXCIT",
                    format!("DDL_IMPO on {other} (a second interface's fracture unknowns) is not supported yet"),
                ))
            }
        };
        if let Some(d) = d {
            cons.impose(d, v);
        }
    }
    Ok(())
}

/// The report on the hydraulic unknowns of an HM model, and the pore pressure they prescribe when it is
/// not zero: every one must be prescribed to be eliminated (PRE1 on the vertices, H*PRE1 on the
/// enrichment sets, p_f/q⁺/q⁻ on the packets, these to zero).
#[allow(clippy::type_complexity)]
fn hydraulic_report(
    cfg: &Settings,
    s: &Setup,
    hydraulic: &BTreeMap<(usize, String), f64>,
) -> Result<std::result::Result<(String, Option<PorePressure>), String>> {
    let (mesh, xm, xd, ndim, zones) = (&*s.mesh, &*s.xm, &s.xd, s.ndim(), &s.zones);
    let mut report = String::new();
    let bulk = |c: &str| c == "PRE1" || (c.starts_with('H') && c.ends_with("PRE1"));
    let fixed = |n: usize, c: &str| hydraulic.contains_key(&(n, c.to_string()));
    let mut vertices: BTreeSet<usize> = BTreeSet::new();
    for (nodes, t) in mesh.cells.iter().zip(&mesh.cell_types) {
        if t.dim() == ndim {
            vertices.extend(nodes[..t.nvertices()].iter().copied().filter(|&n| xd.std[n].is_some()));
        }
    }
    let mut n_h = 0;
    let mut pressure = PorePressure {
        pre1: vec![0.0; mesh.nnodes()],
        hpre1: xd.sets.iter().map(|sets| vec![0.0; sets.len()]).collect(),
    };
    let value = |n: usize, c: &str| hydraulic.get(&(n, c.to_string())).copied();
    for &n in &vertices {
        let Some(v) = value(n, "PRE1") else { return Ok(Err(format!("PRE1 at node {}", mesh.node_names[n]))) };
        pressure.pre1[n] = v;
        for j in 0..xd.sets[n].len() {
            let c = format!("H{}PRE1", j + 1);
            let Some(v) = value(n, &c) else { return Ok(Err(format!("{c} at node {}", mesh.node_names[n]))) };
            pressure.hpre1[n][j] = v;
            n_h += 1;
        }
    }
    let zero = pressure.pre1.iter().chain(pressure.hpre1.iter().flatten()).all(|v| *v == 0.0);
    // Fracture unknowns: one block per crack a node's packets belong to.
    let mut n_pk = 0;
    for z in zones {
        for p in &z.packets {
            let block = |n: usize| zones.iter().filter(|o| o.crack < z.crack && o.packet_of.contains_key(&n)).count();
            for (role, cmps) in
                [("p_f", ["PRE_FLU", "PR2_FLU"]), ("q+", ["LAG_FLI", "LA2_FLI"]), ("q-", ["LAG_FLS", "LA2_FLS"])]
            {
                let ok = p.iter().any(|&n| {
                    let b = block(n);
                    b < 2 && (fixed(n, cmps[b]) || (role == "p_f" && b == 1 && fixed(n, cmps[0])))
                });
                if !ok {
                    return Ok(Err(format!(
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
    if let Some(((n, c), v)) = hydraulic.iter().find(|((_, c), v)| **v != 0.0 && !bulk(c)) {
        return Err(cfg.err(
            "EXCIT",
            format!(
                "{c} = {v} at node {}: a non-zero fracture pressure or exchange flux acts on the lips through the flow in the \
                 interface, which X-FEM {} elements with every hydraulic unknown prescribed do not support yet",
                mesh.node_names[*n],
                if ndim == 2 { "D_PLAN_HM" } else { "3D_HM" }
            ),
        ));
    }
    if zero {
        let _ = writeln!(
            report,
            "    eliminated: hydraulics — PRE1 on {} vertices, H*PRE1 on {n_h} enrichment sets, fracture p_f/q+/q- on {n_pk} \
             packets, all prescribed to 0 by the loads; with p = p_f = 0 the Biot term b·p and the fracture pressure in the \
             interface vanish, so THM_INIT, THM_DIFFU, THM_LIQU, SCHEMA_THM and the time step play no part",
            vertices.len()
        );
        return Ok(Ok((report, None)));
    }
    let _ = writeln!(
        report,
        "    eliminated: hydraulics — PRE1 on {} vertices, H*PRE1 on {n_h} enrichment sets, fracture p_f/q+/q- on {n_pk} \
         packets, all prescribed by the loads; the prescribed pore pressure (Heaviside-enriched, with the vertex \
         functions) loads the skeleton through the Biot term −b·p (THM_DIFFU BIOT_COEF); the flow equations are not \
         solved, so THM_INIT, THM_LIQU, the permeability, SCHEMA_THM and the time step play no part",
        vertices.len()
    );
    Ok(Ok((report, Some(pressure))))
}

/// Rigid translations with no condition at all, pinned when NPREC < 0 (as a singular-tolerant direct
/// solver would pick one solution); what was pinned, for the log.
fn pin_translations(s: &Setup, cons: &mut Constraints, blocked_dir: &[bool]) -> Vec<String> {
    let (mesh, xd) = (&*s.mesh, &s.xd);
    let mut pins = Vec::new();
    for (d, blocked) in blocked_dir.iter().enumerate() {
        if *blocked || s.opts.nprec >= 0 {
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
    pins
}
