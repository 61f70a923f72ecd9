//! The state of an X-FEM solve as the fields of a result, and back (ETAT_INIT=_F(EVOL_NOLI=...)).
//!
//! - DEPL holds every unknown at the mesh nodes, as Code_Aster's X-FEM elements name them: DX DY (DZ),
//!   PRE1 for HM models, the Heaviside parts H<j>X..., then on the vertices of each multiplier packet its
//!   interface unknowns, all in the interface's local basis (n, τ1, τ2): λ as LAGS_C LAGS_F1 (LAGS_F2), w
//!   as LAG2_*, μ as LAG3_* (the first block; a node on the packets of a second or third interface uses
//!   the blocks D1*/D2*/D3* and V1*/V2*/V3*, `meca_d_plan_hm_xmc.py` EN5/EN6), preceded on HM models by
//!   the fracture unknowns PRE_FLU LAG_FLI LAG_FLS (PR2_*, LA2_*; PR3_*, LA3_*), zero when the driver
//!   eliminates them, solved with coupled flow (`flow`; PRE1 and H<j>PRE1 too). Every node of a packet carries the packet's values (Code_Aster ties them by equality).
//! - COHE_ELEM holds the cohesive internal variables, which Code_Aster keeps in this field for the
//!   cohesive X-FEM laws and reads back at ETAT_INIT (`nmetac`, `nmetcr`: ELNO for the mortar interfaces
//!   `XFEM_CONT=2`, the `N5NEUTR` variables of `te0556`): per contact cell and vertex, X1 = κ (the largest
//!   equivalent traction), X2 = ±(state + 1) signed by "dissipating" (`CzmState::to_vari`), X3..X5 = 0 (the
//!   prediction flag and the fracture's hydraulic variables, unused here); X6..X10 for a second
//!   interface's packets at the same node, and so on. CHAM_EXCLU='VARI_ELGA' does not touch it.

use super::assemble::Elements;
use super::setup::Setup;
use crate::concepts::result::Field;
use crate::concepts::ConceptRef;
use crate::diag::Result;
use crate::stages::core::settings::Settings;
use crate::xfem::czm::CzmState;
use std::collections::BTreeMap;

/// Cohesive variables per vertex and interface block in COHE_ELEM.
pub const NCOHE: usize = 5;

/// The DEPL components of interface block `b` (0, 1, 2) of a node: the fracture unknowns on HM models,
/// then λ, w and μ.
pub fn interface_components(ndim: usize, hm: bool, b: usize) -> Option<Vec<String>> {
    let hydr: [[&str; 3]; 3] =
        [["PRE_FLU", "LAG_FLI", "LAG_FLS"], ["PR2_FLU", "LA2_FLI", "LA2_FLS"], ["PR3_FLU", "LA3_FLI", "LA3_FLS"]];
    let mut v: Vec<String> = Vec::new();
    if hm {
        v.extend(hydr.get(b)?.iter().map(|s| s.to_string()));
    }
    for u in 0..3 {
        for d in 0..ndim {
            v.push(match b {
                0 => {
                    let head = ["LAGS", "LAG2", "LAG3"][u];
                    format!("{head}_{}", ["C", "F1", "F2"][d])
                }
                1 => format!("D{}{}", u + 1, ["X", "Y", "Z"][d]),
                2 => format!("V{}{}", u + 1, d + 1),
                _ => return None,
            });
        }
    }
    Some(v)
}

/// Per mesh node, the multiplier packets it belongs to, (zone, packet) in zone order: the index in this
/// list is the node's interface block for that zone.
pub fn node_blocks(s: &Setup) -> Vec<Vec<(usize, usize)>> {
    let mut blocks = vec![Vec::new(); s.mesh.nnodes()];
    for (zi, z) in s.zones.iter().enumerate() {
        for (k, nodes) in z.packets.iter().enumerate() {
            for &n in nodes {
                blocks[n].push((zi, k));
            }
        }
    }
    blocks
}

/// DEPL of an X-FEM state on the mesh nodes (see the module's documentation).
pub fn depl_fields(
    cfg: &Settings,
    s: &Setup,
    x: &[f64],
    pressure: Option<&PorePressure>,
) -> Result<BTreeMap<String, Field>> {
    let (mesh, xm, xd, hm) = (&*s.mesh, &*s.xm, &s.xd, s.hm);
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
    // The Heaviside parts of the pressure (vertices of the enriched cells).
    let hp = comps.len();
    if hm {
        comps.extend((0..maxsets).map(|j| format!("H{}PRE1", j + 1)));
    }
    let blocks = node_blocks(s);
    let nblocks = blocks.iter().map(Vec::len).max().unwrap_or(0);
    let first_interface = comps.len();
    let mut block_width = 0;
    for b in 0..nblocks {
        let names = interface_components(ndim, hm, b).ok_or_else(|| {
            cfg.err("CONTACT", format!("a node on the packets of {} interfaces: at most 3 are supported", b + 1))
        })?;
        block_width = names.len();
        comps.extend(names);
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
            if let Some(f) = &s.flow {
                if let Some(d) = f.pre1[n] {
                    row[k] = x[d];
                }
                for (j, h) in f.hpre1[n].iter().enumerate() {
                    if let Some(d) = h {
                        row[hp + j] = x[*d];
                    }
                }
            } else if vertex[n] {
                row[k] = pressure.map_or(0.0, |p| p.pre1[n]);
                for j in 0..xd.sets[n].len() {
                    row[hp + j] = pressure.map_or(0.0, |p| p.hpre1[n][j]);
                }
            }
            k += 1;
        }
        for (j, &s) in xd.sets[n].iter().enumerate() {
            row[k + j * ndim..k + (j + 1) * ndim].copy_from_slice(&x[s..s + ndim]);
        }
        for (bi, &(zi, p)) in blocks[n].iter().enumerate() {
            let base = xd.packets[s.zones[zi].crack][p];
            let at = first_interface + bi * block_width;
            let hyd = if hm { 3 } else { 0 };
            match &s.flow {
                Some(f) => {
                    let d = f.fracture[zi][p];
                    row[at..at + 3].copy_from_slice(&x[d..d + 3]);
                }
                None => row[at..at + hyd].fill(0.0),
            }
            row[at + hyd..at + hyd + 3 * ndim].copy_from_slice(&x[base..base + 3 * ndim]);
        }
    }
    let mut f = BTreeMap::new();
    f.insert("DEPL".to_string(), Field::Node { components: comps, values });
    Ok(f)
}

/// COHE_ELEM of the cohesive states `states` (one per law of `el`), or None without cohesive zones.
pub fn cohe_field(s: &Setup, el: &Elements, states: &[CzmState]) -> Option<Field> {
    if s.zones.is_empty() {
        return None;
    }
    let mesh = &*s.mesh;
    let law_of: BTreeMap<usize, usize> = el.laws.iter().enumerate().map(|(li, l)| (l.base, li)).collect();
    // The zones of each contact cell, in zone order.
    let mut cell_zones: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (zi, z) in s.zones.iter().enumerate() {
        for &c in &z.cells {
            cell_zones.entry(c).or_default().push(zi);
        }
    }
    let nb = cell_zones.values().map(Vec::len).max().unwrap_or(1);
    let nc = NCOHE * nb;
    let components: Vec<String> = (1..=nc).map(|k| format!("X{k}")).collect();
    let mut cells = vec![None; mesh.ncells()];
    for (&c, zones) in &cell_zones {
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let mut v = vec![f64::NAN; nodes.len() * nc];
        for (i, &n) in nodes.iter().enumerate().take(t.nvertices()) {
            for (b, &zi) in zones.iter().enumerate() {
                let z = &s.zones[zi];
                let at = i * nc + b * NCOHE;
                v[at..at + NCOHE].fill(0.0);
                let Some(&p) = z.packet_of.get(&n) else { continue };
                let Some(&li) = law_of.get(&s.xd.packets[z.crack][p]) else { continue };
                let [k, st] = states[li].to_vari();
                v[at] = k;
                v[at + 1] = st;
            }
        }
        cells[c] = Some(v);
    }
    Some(Field::Elno { components, cells })
}

/// Where ETAT_INIT=_F(EVOL_NOLI=...) takes the initial state: the result and its stored step.
pub struct Source {
    pub result: ConceptRef,
    pub order: i64,
    pub inst: f64,
}

/// The step ETAT_INIT starts from (EVOL_NOLI, found by the settings).
pub fn source(cfg: &Settings) -> Option<Source> {
    let init = cfg.initial.as_ref()?;
    let (order, inst) = init.step?;
    Some(Source { result: init.evol_noli.clone()?, order, inst })
}

/// The unknowns and the cohesive states of the step of `src`: DEPL read back component by component,
/// COHE_ELEM (a result without it, as one computed without cohesive zones, starts the laws sound).
pub fn restore(cfg: &Settings, src: &Source, s: &Setup, el: &Elements) -> Result<(Vec<f64>, Vec<CzmState>)> {
    let r = src.result.result()?;
    let label = src.result.label();
    let step = r.by_order(src.order).expect("the order found by `source`");
    let bad = |msg: String| cfg.err("ETAT_INIT/EVOL_NOLI", format!("{label}, order {}: {msg}", src.order));
    let Some(Field::Node { components, values }) = step.fields.get("DEPL") else {
        return Err(bad("no DEPL field".into()));
    };
    let (mesh, xd, ndim) = (&*s.mesh, &s.xd, s.ndim());
    let nc = components.len();
    if values.len() != mesh.nnodes() * nc {
        return Err(bad(format!("DEPL is not a field on the {} nodes of the model's mesh", mesh.nnodes())));
    }
    let idx = |c: &str| components.iter().position(|x| x == c);
    let get = |n: usize, c: &str| -> Result<f64> {
        let v = idx(c).map(|k| values[n * nc + k]).unwrap_or(f64::NAN);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(bad(format!("DEPL has no component {c} at node {}", mesh.node_names[n])))
        }
    };
    let xyz = ["X", "Y", "Z"];
    let mut x = vec![0.0; xd.n];
    for n in 0..mesh.nnodes() {
        let Some(b) = xd.std[n] else { continue };
        for d in 0..ndim {
            x[b + d] = get(n, &format!("D{}", xyz[d]))?;
        }
        for (j, &sb) in xd.sets[n].iter().enumerate() {
            for d in 0..ndim {
                x[sb + d] = get(n, &format!("H{}{}", j + 1, xyz[d]))?;
            }
        }
    }
    // The hydraulic unknowns are eliminated at zero: a state where they are not cannot be continued.
    for c in components.iter().filter(|c| is_hydraulic(c)) {
        let k = idx(c).expect("a component of the field");
        if let Some(n) = (0..mesh.nnodes()).find(|&n| values[n * nc + k].is_finite() && values[n * nc + k] != 0.0) {
            return Err(bad(format!(
                "{c} = {} at node {}: the X-FEM driver eliminates the hydraulic unknowns at zero, a non-zero \
                 initial pressure is not supported yet",
                values[n * nc + k],
                mesh.node_names[n]
            )));
        }
    }
    // A result computed without cohesive zones has no interface unknowns: they start at zero.
    let blocks = if has_interface(components) { node_blocks(s) } else { Vec::new() };
    for (n, bl) in blocks.iter().enumerate() {
        for (bi, &(zi, p)) in bl.iter().enumerate() {
            let names = interface_components(ndim, s.hm, bi).expect("at most 3 blocks (checked when stored)");
            let names = &names[if s.hm { 3 } else { 0 }..];
            let base = xd.packets[s.zones[zi].crack][p];
            // Every node of a packet holds its values: the first one gives them.
            if s.zones[zi].packets[p].first() != Some(&n) {
                continue;
            }
            for (q, c) in names.iter().enumerate() {
                x[base + q] = get(n, c)?;
            }
        }
    }
    let mut states = vec![CzmState::default(); el.laws.len()];
    match step.fields.get("COHE_ELEM") {
        None if !s.zones.is_empty() && has_interface(components) => {
            return Err(bad(
                "no COHE_ELEM field (the cohesive variables; was it left out by ARCHIVAGE/CHAM_EXCLU?)".into()
            ))
        }
        None => {}
        Some(Field::Elno { components: cc, cells }) => {
            let ncc = cc.len();
            let law_of: BTreeMap<usize, usize> = el.laws.iter().enumerate().map(|(li, l)| (l.base, li)).collect();
            let mut seen = vec![false; el.laws.len()];
            let mut cell_zones: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
            for (zi, z) in s.zones.iter().enumerate() {
                for &c in &z.cells {
                    cell_zones.entry(c).or_default().push(zi);
                }
            }
            for (&c, zones) in &cell_zones {
                let Some(v) = cells.get(c).and_then(Option::as_ref) else {
                    return Err(bad(format!("COHE_ELEM has no values on cell {}", mesh.cell_names[c])));
                };
                for (i, &n) in mesh.cells[c].iter().enumerate().take(mesh.cell_types[c].nvertices()) {
                    for (b, &zi) in zones.iter().enumerate() {
                        let z = &s.zones[zi];
                        let Some(&p) = z.packet_of.get(&n) else { continue };
                        let Some(&li) = law_of.get(&xd.packets[z.crack][p]) else { continue };
                        let at = i * ncc + b * NCOHE;
                        if at + 2 > v.len() || seen[li] {
                            continue;
                        }
                        if !(v[at].is_finite() && v[at + 1].is_finite()) {
                            return Err(bad(format!(
                                "COHE_ELEM has no cohesive variables at node {} of cell {}",
                                mesh.node_names[n], mesh.cell_names[c]
                            )));
                        }
                        states[li] = CzmState::from_vari([v[at], v[at + 1]]);
                        seen[li] = true;
                    }
                }
            }
        }
        Some(_) => return Err(bad("COHE_ELEM is not a field at the cell nodes".into())),
    }
    Ok((x, states))
}

/// A hydraulic component of DEPL (pressures, fracture unknowns).
fn is_hydraulic(c: &str) -> bool {
    c.contains("PRE1")
        || ["PRE_FLU", "PR2_FLU", "PR3_FLU", "LAG_FLI", "LAG_FLS", "LA2_FLI", "LA2_FLS", "LA3_FLI", "LA3_FLS"]
            .contains(&c)
}

/// Does a DEPL carry interface unknowns?
fn has_interface(components: &[String]) -> bool {
    components.iter().any(|c| c == "LAGS_C")
}

/// A pore pressure prescribed on every hydraulic unknown of an HM model: `pre1[n]` at each vertex `n`
/// (0 elsewhere), `hpre1[n][j]` the Heaviside part of node `n`'s enrichment set `j` (`H<j+1>PRE1`).
#[derive(Debug, Clone, PartialEq)]
pub struct PorePressure {
    pub pre1: Vec<f64>,
    pub hpre1: Vec<Vec<f64>>,
}
