//! Saturated hydro-mechanics as a [`Physics`]: the problem of a model (its cells' elements and Biot
//! materials, the numbering `DX DY [DZ]` on every node and `PRE1` on the vertices, with on an X-FEM model
//! the Heaviside parts `H<j>X … H<j>PRE1`), its loads (the kinematic conditions, with Code_Aster's
//! `xddlim` on enriched nodes; nodal, surface and pressure forces, the weight of the mixture, FLUX_THM_REP
//! on the pressures, each with its Heaviside parts on an X-FEM model), the element loop, and the fields
//! DEPL, SIEF_ELGA and VARI_ELGA.

use super::element::{element_with, flux_load, StepData, Variant};
use super::law::PointState;
use super::thermal::ThermalMat;
use super::{Biot, CellPoints, Kinematics};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs};
use crate::fem::dofs::{Constraints, DofNumbering};
use crate::fem::elastic::coords_of;
use crate::fem::elasticity;
use crate::fem::field::Field;
use crate::fem::physics::{keep, traction, Condition, Failure, Force, Load, Physics, Prediction, StepInfo};
use crate::mesh::Mesh;
use crate::xfem::model::XfemModel;
use std::collections::BTreeMap;
use std::rc::Rc;

/// A multiplier of time (THM_DIFFU PESA_MULT), evaluated by the caller's functions.
pub type Multiplier = Rc<dyn Fn(f64) -> Result<f64>>;

/// One bulk cell of an HM model.
pub struct HmCell {
    pub points: CellPoints,
    pub mat: Biot,
    /// THM_DIFFU PESA_MULT: the multiplier of the fluid's gravity, a function of INST.
    pub pesa_mult: Option<Multiplier>,
    /// The global numbers of the cell's local unknowns.
    pub dofs: Vec<usize>,
    /// THM: the thermal parameters (None in HM).
    pub thermal: Option<ThermalMat>,
}

/// The saturated HM problem of a model.
pub struct HmProblem {
    pub mesh: Rc<Mesh>,
    /// MODELISATION, as Code_Aster names it.
    pub modelling: String,
    pub kin: Kinematics,
    pub variant: Variant,
    /// The bulk cells, and the skin cells of the model (where FLUX_THM_REP and PRES_REP act).
    pub bulk: Vec<usize>,
    pub skin: Vec<usize>,
    /// Per mesh cell: its HM element, for bulk cells.
    pub cells: Vec<Option<HmCell>>,
    pub numbering: DofNumbering,
    /// The index of PRE1 among the numbering's components.
    pub pre1: usize,
    /// THM: the index of TEMP among the numbering's components (None in HM).
    pub temp: Option<usize>,
    /// MODI_MODELE_XFEM: the enrichment of an X-FEM model (Heaviside-enriched displacement and pressure,
    /// components `H<j>X … H<j>PRE1` after the standard ones).
    pub xfem: Option<Rc<XfemModel>>,
    /// SCHEMA_THM PARM_THETA.
    pub theta: f64,
    /// The factor of the pressure rows that makes the tangent symmetric when it can be (1/ρ₀ of the
    /// liquid: the coupling blocks are −b Q and −ρ b Qᵀ), 0 when the materials disagree on ρ₀.
    pub pressure_row_scale: f64,
}

/// The components of the Heaviside enrichment sets, per set: `H<j>X H<j>Y [H<j>Z] H<j>PRE1`.
pub const HEAVISIDE: [[&str; 4]; 4] = [
    ["H1X", "H1Y", "H1Z", "H1PRE1"],
    ["H2X", "H2Y", "H2Z", "H2PRE1"],
    ["H3X", "H3Y", "H3Z", "H3PRE1"],
    ["H4X", "H4Y", "H4Z", "H4PRE1"],
];

impl HmProblem {
    /// True when component `k` of the numbering is a pressure (PRE1 or a Heaviside part of it).
    pub fn is_pressure(&self, k: usize) -> bool {
        self.numbering.components[k].ends_with("PRE1")
    }
}

impl HmProblem {
    /// The bulk cells with their elements.
    pub fn elements(&self) -> impl Iterator<Item = (usize, &HmCell)> {
        self.bulk.iter().map(move |&c| (c, self.cells[c].as_ref().expect("bulk cells have an element")))
    }
}

impl HmProblem {
    /// The fluid's gravity of a cell at `t`: THM_DIFFU PESA_X/Y/Z × PESA_MULT(t).
    pub fn gravity(&self, cell: &HmCell, t: f64) -> Result<[f64; 3]> {
        let m = match &cell.pesa_mult {
            Some(f) => f(t)?,
            None => 1.0,
        };
        Ok(cell.mat.gravity.map(|g| g * m))
    }

    /// The unknowns of the displacements of a cell's nodes.
    fn udofs(&self, c: usize) -> Option<Vec<usize>> {
        let dim = self.kin.dim();
        self.mesh.cells[c].iter().flat_map(|&n| (0..dim).map(move |i| self.numbering.dof(n, i))).collect()
    }

    /// The displacement unknowns of a skin cell of the model carrying a load.
    fn skin_cell(&self, load: &str, c: usize) -> Result<Vec<usize>> {
        match self.udofs(c) {
            Some(d) if self.skin.contains(&c) => Ok(d),
            _ => {
                Err(excit(format!("load {load}: cell {} is not a boundary cell of the model", self.mesh.cell_names[c])))
            }
        }
    }
}

fn excit(msg: String) -> Error {
    Error::runtime(msg).at_keyword("EXCIT")
}

impl Physics for HmProblem {
    type State = Vec<Vec<PointState>>;

    fn describe(&self) -> String {
        let kit = if self.temp.is_some() { "KIT_THM" } else { "KIT_HM" };
        format!("{}, {kit} ELAS/LIQU_SATU/HYDR_UTIL, θ = {}", self.modelling, self.theta)
    }

    fn unknowns(&self) -> usize {
        self.numbering.ndofs()
    }

    fn label(&self, dof: usize) -> String {
        self.numbering.label(dof, Some(&self.mesh))
    }

    fn element_dofs(&self) -> ElementDofs {
        let mut e = ElementDofs::new();
        for (_, cell) in self.elements() {
            e.push(&cell.dofs);
        }
        e
    }

    fn assemble(
        &self,
        step: &StepInfo,
        u: &[f64],
        prev: &Self::State,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> std::result::Result<Self::State, Failure> {
        let mut states = Vec::with_capacity(prev.len());
        for (i, ((c, cell), prev_c)) in self.elements().zip(prev).enumerate() {
            let data = StepData { dt: step.dt(), theta: self.theta, gravity: self.gravity(cell, step.t1)? };
            let ue: Vec<f64> = cell.dofs.iter().map(|&d| u[d]).collect();
            let out =
                element_with(&cell.points, &cell.mat, cell.thermal.as_ref(), &ue, prev_c, &data).map_err(|e| {
                    Failure::Step(Error::runtime(format!(
                        "integration failure in cell {}: {}",
                        self.mesh.cell_names[c], e.0
                    )))
                })?;
            let _ = i;
            if let Some(asm) = tangent.as_deref_mut() {
                asm.add_matrix(&cell.dofs, &out.k);
            }
            for (&d, v) in cell.dofs.iter().zip(&out.fint) {
                fint[d] += v;
            }
            states.push(out.states);
        }
        Ok(states)
    }

    fn conditions(&self, loads: &[Load], cons: &mut Constraints) -> Result<()> {
        let (mesh, num) = (&*self.mesh, &self.numbering);
        for load in loads {
            let name = &load.name;
            for item in &load.conditions {
                match item {
                    Condition::Dof { node, component, value } => {
                        let Some(d) = self.dof(name, *node, component)? else { continue };
                        let v = value.at(&mesh.coords[*node])?;
                        match enriched_condition(self, &load.conditions, *node, component, d) {
                            Some(relations) => {
                                for terms in relations {
                                    cons.relation(terms, v);
                                }
                            }
                            None => cons.impose(d, v),
                        }
                    }
                    Condition::Relation { terms, value } => {
                        let mut tt = Vec::new();
                        for (node, comp, coef) in terms.iter() {
                            let k = num.component(comp).ok_or_else(|| {
                                excit(format!("load {name}: {comp} is not an unknown of a {} model", self.modelling))
                            })?;
                            let d = num.dof(*node, k).ok_or_else(|| {
                                excit(format!("load {name}: node {} carries no {comp}", mesh.node_names[*node]))
                            })?;
                            tt.push((d, *coef));
                        }
                        cons.relation(tt, value.at(&[0.0; 3])?);
                    }
                }
            }
        }
        Ok(())
    }

    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>> {
        let num = &self.numbering;
        let k = num.component(component).ok_or_else(|| {
            excit(format!("load {load}: {component} is not an unknown of a {} model", self.modelling))
        })?;
        match num.dof(node, k) {
            Some(d) => Ok(Some(d)),
            // A middle node carries no pressure, a node outside the interface's reach no Heaviside
            // unknown: Code_Aster passes over them (afddli).
            None if (self.is_pressure(k)
                || Some(k) == self.temp
                || self.xfem.is_some() && component.starts_with('H'))
                && num.has_node(node) =>
            {
                Ok(None)
            }
            None => {
                Err(excit(format!("load {load}: node {} carries no element of the model", self.mesh.node_names[node])))
            }
        }
    }

    fn position(&self, node: usize) -> [f64; 3] {
        self.mesh.coords[node]
    }

    fn node_name(&self, node: usize) -> String {
        self.mesh.node_names[node].clone()
    }

    fn forces(&self, loads: &[Load], step: &StepInfo, f: &mut [f64]) -> Result<()> {
        let (mesh, num) = (&*self.mesh, &self.numbering);
        let dim = self.kin.dim();
        let md = self.kin.mechanics();
        let dt = step.dt();
        for load in loads {
            let name = &load.name;
            for item in &load.forces {
                match item {
                    Force::LipPressure { name: crack, .. } => {
                        return Err(excit(format!(
                            "load {name}: PRES_REP on the lips of {crack} {}",
                            if self.xfem.is_some() {
                                "with coupled flow in the X-FEM elements is not supported yet"
                            } else {
                                "needs the X-FEM model"
                            }
                        )))
                    }
                    Force::Nodal { node, component, value } => {
                        let k = match *component {
                            "FX" => 0,
                            "FY" => 1,
                            "FZ" if dim == 3 => 2,
                            c => {
                                return Err(excit(format!(
                                    "load {name}: FORCE_NODALE {c} is not supported on a {} model",
                                    self.modelling
                                )))
                            }
                        };
                        let d = num.dof(*node, k).ok_or_else(|| {
                            excit(format!(
                                "load {name}: node {} carries no element of the model",
                                mesh.node_names[*node]
                            ))
                        })?;
                        f[d] += value.at(&mesh.coords[*node])?;
                    }
                    Force::Surface { cells, components } => {
                        if dim < 3 && components.iter().any(|(n, _)| *n == "FZ") {
                            return Err(excit(format!("load {name}: FZ in a {} model", self.modelling)));
                        }
                        for &c in cells.iter() {
                            let dofs = self.skin_cell(name, c)?;
                            let err = std::cell::RefCell::new(None);
                            let fx = |x: &[f64; 3], _n: &[f64; 3]| keep(&err, traction(components, x));
                            let fe = elasticity::boundary_force(md, mesh.cell_types[c], &coords_of(mesh, c), &fx)
                                .map_err(|e| Error::runtime(e.to_string()))?;
                            let pending = err.borrow_mut().take();
                            if let Some(e) = pending {
                                return Err(e);
                            }
                            let density = |x: &[f64; 3], nr: &[f64; 3], _: &[f64]| fx(x, nr);
                            skin_load(self, c, &fe, &dofs, Density::Traction(&density), f)?;
                            let pending = err.borrow_mut().take();
                            if let Some(e) = pending {
                                return Err(e);
                            }
                        }
                    }
                    Force::Pressure { cells, value, shear } => {
                        if shear.is_some() {
                            return Err(Error::unsupported(format!(
                                "load {name}: PRES_REP CISA_2D on a hydro-mechanical model is not supported yet"
                            )));
                        }
                        for &c in cells.iter() {
                            let dofs = self.skin_cell(name, c)?;
                            let xs = coords_of(mesh, c);
                            let pres: Vec<f64> = xs.iter().map(|x| value.at(x)).collect::<Result<_>>()?;
                            let fe = elasticity::pressure_force(md, mesh.cell_types[c], &xs, &pres, None)
                                .map_err(|e| Error::runtime(e.to_string()))?;
                            // On a cell an interface crosses, the pressure at each point of each side (a function
                            // may jump across the interface); elsewhere the nodal values, as `pressure_force`.
                            let err = std::cell::RefCell::new(None);
                            let density = |x: &[f64; 3], nr: &[f64; 3], _: &[f64]| {
                                let pv = keep(&err, value.at(x));
                                nr.map(|v| -v * pv)
                            };
                            skin_load(self, c, &fe, &dofs, Density::Traction(&density), f)?;
                            let pending = err.borrow_mut().take();
                            if let Some(e) = pending {
                                return Err(e);
                            }
                        }
                    }
                    Force::Flux { cells, value, heat } => {
                        // FLUN_HYDR1 on the pressures, FLUN (a heat flux) on the temperatures of a THM model.
                        let (comp, comp_name) = match (*heat, self.temp) {
                            (false, _) => (self.pre1, "PRE1"),
                            (true, Some(k)) => (k, "TEMP"),
                            (true, None) => {
                                return Err(excit(format!(
                                    "load {name}: FLUX_THM_REP FLUN is a heat flux; {} has no temperature (the *_THM \
                                     modelisations have)",
                                    self.modelling
                                )))
                            }
                        };
                        for &c in cells.iter() {
                            self.skin_cell(name, c)?;
                            let t_c = mesh.cell_types[c];
                            let err = std::cell::RefCell::new(None);
                            let q = |x: &[f64; 3]| keep(&err, value.at(x));
                            let fe = flux_load(self.kin, t_c, &coords_of(mesh, c), dt, &q)
                                .map_err(|e| excit(format!("load {name}: cell {}: {e}", mesh.cell_names[c])))?;
                            let pending = err.borrow_mut().take();
                            if let Some(e) = pending {
                                return Err(e);
                            }
                            let dofs = (0..fe.len())
                                .map(|k| {
                                    let n = mesh.cells[c][k];
                                    num.dof(n, comp).ok_or_else(|| {
                                        excit(format!(
                                            "load {name}: node {} carries no {comp_name}",
                                            mesh.node_names[n]
                                        ))
                                    })
                                })
                                .collect::<Result<Vec<usize>>>()?;
                            skin_load(self, c, &fe, &dofs, Density::Flux(&q, dt), f)?;
                            let pending = err.borrow_mut().take();
                            if let Some(e) = pending {
                                return Err(e);
                            }
                        }
                    }
                    Force::Gravity { g, direction, cells } => {
                        let on: Vec<usize> = match cells {
                            Some(c) => c.iter().copied().filter(|c| self.cells[*c].is_some()).collect(),
                            None => self.bulk.clone(),
                        };
                        for c in on {
                            let cell = self.cells[c].as_ref().expect("a bulk cell");
                            let rho = cell.mat.rho_h;
                            let acc = [0, 1, 2].map(|i| rho * g * direction[i]);
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
                    heat => {
                        return Err(excit(format!(
                            "load {name}: {} is a thermal load, not one of a hydro-mechanical model",
                            heat.keyword()
                        )))
                    }
                }
            }
        }
        Ok(())
    }

    fn fields(&self, u: &[f64], states: &Self::State) -> Result<Vec<(String, Field)>> {
        Ok(step_fields(self, u, states).into_iter().collect())
    }

    fn prediction(&self) -> Prediction {
        Prediction::Tangent
    }

    fn row_scale(&self, dof: usize) -> f64 {
        if self.pressure_row_scale > 0.0 && self.is_pressure(self.numbering.node_comp(dof).1) {
            self.pressure_row_scale
        } else {
            1.0
        }
    }
}

/// DDL_IMPO of a standard component (DX DY DZ PRE1) on a node of an X-FEM model with Heaviside sets,
/// as `xddlim` prescribes it: the whole field on the node's side, std + Σ ψ h = value. Off the interface
/// ψ vanishes on the node's own side, so the standard unknown alone is prescribed (None). On it (a single
/// interface with the level set zero at the node) the sides where the load's other nodes lie, among the
/// cells holding the node: one relation per side (both when they lie on both, or none of them does).
/// `d` is the node's standard unknown of the component.
fn enriched_condition(
    p: &HmProblem,
    items: &[Condition],
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
            Condition::Dof { node, component: c, .. } if *c == component => Some(*node),
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
fn skin_load(p: &HmProblem, c: usize, fe: &[f64], dofs: &[usize], density: Density, f: &mut [f64]) -> Result<()> {
    if !add_enriched(p, c, fe, density, f)? {
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
fn add_enriched(p: &HmProblem, c: usize, fe: &[f64], density: Density, f: &mut [f64]) -> Result<bool> {
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
        let ff = crate::xfem::model::vertex_weights(t);
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
        return Err(Error::runtime(format!(
            "boundary cell {}: an X-FEM interface crosses it but it has no cutting",
            mesh.cell_names[c]
        ))
        .at_keyword("EXCIT"));
    };
    let coords = coords_of(mesh, c);
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
        // The sub-cell's side: its Heaviside values for the cell's cracks, the side of the cell's vertices
        // for the others (as `XfemModel` decides it).
        let ffc = crate::xfem::model::vertex_weights(t);
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

/// The components of SIEF_ELGA on an HM element (Code_Aster's ECONTPG: σ', σ_p, M, w), on a THM one
/// followed by the enthalpy `ENT11`, the non-convected heat `QPRIM` and the heat flux `FHTX..`.
pub fn sief_components(dim: usize, thm: bool) -> Vec<String> {
    let mut v: Vec<String> =
        ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ", "SIPXX", "SIPYY", "SIPZZ", "SIPXY", "SIPXZ", "SIPYZ", "M11"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    v.extend(["FH11X", "FH11Y", "FH11Z"][..dim].iter().map(|s| s.to_string()));
    if thm {
        v.extend(["ENT11", "QPRIM"].iter().map(|s| s.to_string()));
        v.extend(["FHTX", "FHTY", "FHTZ"][..dim].iter().map(|s| s.to_string()));
    }
    v
}

/// The internal variables of KIT_HM (ELAS, LIQU_SATU, HYDR_UTIL): V1 the skeleton's (none for ELAS),
/// V2 = ρ − ρ₀ (RHOLIQ), V3 = φ − φ₀ (POROSITE).
pub const VARI_COMPONENTS: [&str; 3] = ["V1", "V2", "V3"];

/// DEPL, SIEF_ELGA and VARI_ELGA of a state.
pub fn step_fields(p: &HmProblem, u: &[f64], states: &[Vec<PointState>]) -> BTreeMap<String, Field> {
    let num = &p.numbering;
    let nc = num.ncomp;
    let mut values = vec![f64::NAN; p.mesh.nnodes() * nc];
    for (d, v) in u.iter().enumerate() {
        let (n, k) = num.node_comp(d);
        values[n * nc + k] = *v;
    }
    let components = num.components.iter().map(|s| s.to_string()).collect();
    let dim = p.kin.dim();
    let thm = p.temp.is_some();
    let sief_c = sief_components(dim, thm);
    let mut sief: Vec<Option<Vec<f64>>> = vec![None; p.mesh.cells.len()];
    let mut vari: Vec<Option<Vec<f64>>> = vec![None; p.mesh.cells.len()];
    for ((c, cell), st) in p.elements().zip(states) {
        let ngauss =
            if p.variant == Variant::Selective { st.len() - p.mesh.cell_types[c].nvertices() } else { st.len() };
        let mut s = Vec::with_capacity(st.len() * sief_c.len());
        let mut v = Vec::with_capacity(st.len() * 3);
        for (k, ps) in st.iter().enumerate() {
            // The vertex points of an S element hold the effective stress of Gauss point k (Code_Aster copies it).
            let sig = if k >= ngauss { st[k - ngauss].sig } else { ps.sig };
            s.extend_from_slice(&sig);
            s.extend_from_slice(&ps.sigp);
            s.push(ps.m);
            s.extend_from_slice(&ps.w[..dim]);
            if thm {
                s.extend([ps.h, ps.qp]);
                s.extend_from_slice(&ps.qt[..dim]);
            }
            v.extend([0.0, ps.rho - cell.mat.rho_l, ps.phi - cell.mat.phi0]);
        }
        sief[c] = Some(s);
        vari[c] = Some(v);
    }
    let mut f = BTreeMap::new();
    f.insert("DEPL".to_string(), Field::Node { components, values });
    f.insert("SIEF_ELGA".to_string(), Field::Elga { components: sief_c, cells: sief });
    f.insert(
        "VARI_ELGA".to_string(),
        Field::Elga { components: VARI_COMPONENTS.iter().map(|s| s.to_string()).collect(), cells: vari },
    );
    f
}
