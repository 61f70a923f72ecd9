//! An X-FEM model as a [`Physics`] of the core's driver: the unknowns of `XDofs` (and the flow's, with
//! free hydraulics), the operators assembled once (`assemble`: the bulk on the sub-cells, the mortar
//! couplings) with the cohesive law of each packet and, with coupled flow, the HM elements and the
//! interface hydraulics; the conditions of the loads (`conditions`, with the multiplier components and
//! directions that test no free jump held at zero), the lip pressures, gravity and the Biot term of a
//! prescribed pore pressure (`forces`); the stored fields (`state`).

use super::assemble::{Elements, Law};
use super::hydraulic::HydraulicRows;
use super::report::{label, sief_field, zone_state, FirstConditions};
use super::setup::{Setup, Zone};
use super::state::PorePressure;
use super::state::{cohe_field, depl_fields};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs};
use crate::fem::dofs::Constraints;
use crate::fem::field::Field;
use crate::fem::physics::{Failure, Load, Physics, Prediction, Residual, StepInfo};
use crate::hm::law::PointState;
use crate::stages::core::newton::inf_norm;
use crate::stages::core::settings::Settings;
use crate::xfem::czm::{self, CzmState};
use std::cell::RefCell;

/// Size of the reduced tangent from which it is factorised by LDLᵀ rather than LU.
pub const LDLT_FROM: usize = 20_000;

/// The laws' state of an X-FEM model: the cohesive variables of every packet, the HM point states of the
/// flow, and the unknowns at the state (the start of the next step, where the flow's increments start).
#[derive(Clone)]
pub struct XState {
    pub czm: Vec<CzmState>,
    pub hm: Vec<Vec<PointState>>,
    pub x: Vec<f64>,
}

/// The X-FEM physics of one solve.
pub struct Xfem<'s> {
    pub cfg: &'s Settings,
    pub s: &'s Setup,
    pub el: &'s Elements,
    hydro: Option<HydraulicRows>,
    statics: bool,
    /// The pore pressure the conditions of the current instant prescribe (HM models), which loads the
    /// skeleton through the Biot term.
    pressure: RefCell<Option<PorePressure>>,
    pub first: RefCell<Option<FirstConditions>>,
}

impl<'s> Xfem<'s> {
    pub fn new(cfg: &'s Settings, s: &'s Setup, el: &'s Elements) -> Result<Xfem<'s>> {
        // Eliminated hydraulics count in the reference through their storage rows; with coupled flow every
        // hydraulic row is assembled.
        let hydro = if s.flow.is_some() { None } else { HydraulicRows::new(cfg, s, el)? };
        Ok(Xfem { cfg, s, el, hydro, statics: cfg.statics(), pressure: RefCell::new(None), first: RefCell::new(None) })
    }

    /// The state of the laws for the unknowns `x` at rest (sound interfaces) or from ETAT_INIT's
    /// cohesive variables.
    pub fn initial_state(&self, x: Vec<f64>, czm: Option<Vec<CzmState>>) -> XState {
        let hm = self.s.flow.as_ref().map(|f| f.initial_states(&x)).unwrap_or_default();
        let czm = czm.unwrap_or_else(|| vec![CzmState::default(); self.el.laws.len()]);
        XState { czm, hm, x }
    }

    /// The cohesive law of one packet at `x`: its residual rows added to `r`, its 2·ndim square tangent.
    fn law(&self, x: &[f64], l: &Law, zone: &Zone, state: &CzmState, r: &mut [f64]) -> (Vec<f64>, CzmState) {
        let ndim = self.s.ndim();
        let lam = &x[l.base..l.base + ndim];
        let w = &x[l.base + ndim..l.base + 2 * ndim];
        let ev = czm::evaluate(&zone.params, ndim, lam, w, state);
        let rr = zone.params.r();
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
        (ke, ev.new_state)
    }
}

impl Physics for Xfem<'_> {
    type State = XState;

    fn describe(&self) -> String {
        format!("X-FEM {}", self.s.modelisation)
    }

    fn unknowns(&self) -> usize {
        self.s.nunk()
    }

    fn label(&self, dof: usize) -> String {
        label(self.s, dof)
    }

    fn element_dofs(&self) -> ElementDofs {
        let ndim = self.s.ndim();
        let mut elems = ElementDofs::new();
        for l in &self.el.lins {
            elems.push(&l.dofs);
        }
        for l in &self.el.laws {
            let v: Vec<usize> = (l.base..l.base + 2 * ndim).collect();
            elems.push(&v);
        }
        if let Some(f) = &self.s.flow {
            f.elements(self.s, &mut elems);
        }
        elems
    }

    fn assemble(
        &self,
        step: &StepInfo,
        x: &[f64],
        prev: &XState,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> std::result::Result<XState, Failure> {
        for l in &self.el.lins {
            let nd = l.dofs.len();
            for (i, &di) in l.dofs.iter().enumerate() {
                let row = &l.k[i * nd..(i + 1) * nd];
                fint[di] += row.iter().zip(&l.dofs).map(|(k, &dj)| k * x[dj]).sum::<f64>();
            }
            if let Some(asm) = tangent.as_deref_mut() {
                asm.add_matrix(&l.dofs, &l.k);
            }
        }
        let mut czm_states = Vec::with_capacity(self.el.laws.len());
        for (li, l) in self.el.laws.iter().enumerate() {
            let (ke, st) = self.law(x, l, &self.s.zones[l.zone], &prev.czm[li], fint);
            czm_states.push(st);
            if let Some(asm) = tangent.as_deref_mut() {
                let dofs: Vec<usize> = (l.base..l.base + 2 * self.s.ndim()).collect();
                asm.add_matrix(&dofs, &ke);
            }
        }
        let hm = match &self.s.flow {
            Some(flow) => flow
                .add(self.cfg, self.s, x, &prev.x, &prev.hm, step.dt(), step.t1, fint, tangent)
                .map_err(Failure::Step)?,
            None => Vec::new(),
        };
        Ok(XState { czm: czm_states, hm, x: x.to_vec() })
    }

    fn conditions(&self, loads: &[Load], cons: &mut Constraints) -> Result<()> {
        let (cfg, s, el) = (self.cfg, self.s, self.el);
        let ndim = s.ndim();
        let c = super::conditions::constraints(cfg, s, loads)?;
        c.require_prescribed_hydraulics(cfg)?;
        *cons = c.cons;
        // Removed multiplier components: their λ, w and μ are zero.
        for (zi, dead) in el.dead.iter().enumerate() {
            let crack = s.zones[zi].crack;
            for &(k, q) in dead {
                let b = s.xd.packets[crack][k];
                for off in [0, ndim, 2 * ndim] {
                    cons.impose(b + off + q, 0.0);
                }
            }
        }
        // Multiplier directions that test no free jump: μ is kept orthogonal to them, unless the loads
        // prescribe λ on every component of the direction (DDL_IMPO on LAGS_*): the w-rows then fix μ.
        // The free jump of a near-sliver set such a direction tested is held at zero.
        let fixed: std::collections::BTreeSet<usize> = cons.imposed.iter().map(|&(d, _)| d).collect();
        for v in &el.null {
            if let Some(g) = &v.lock {
                cons.relation(g.clone(), 0.0);
            }
            if v.mu.iter().all(|&(d, _)| fixed.contains(&(d - 2 * ndim))) {
                continue;
            }
            cons.relation(v.mu.clone(), 0.0);
        }
        self.first.borrow_mut().get_or_insert(FirstConditions { hm_report: c.report, pinned: c.pins });
        *self.pressure.borrow_mut() = c.pressure;
        Ok(())
    }

    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>> {
        let d = ["DX", "DY", "DZ"].iter().position(|c| *c == component).filter(|&d| d < self.s.ndim());
        match (self.s.xd.std[node], d) {
            (Some(std), Some(d)) => Ok(Some(std + d)),
            _ => Err(Error::runtime(format!(
                "load {load}: {component} of node {} is not a standard unknown of the model",
                self.s.mesh.node_names[node]
            ))
            .at_keyword("EXCIT")),
        }
    }

    fn position(&self, node: usize) -> [f64; 3] {
        self.s.mesh.coords[node]
    }

    fn node_name(&self, node: usize) -> String {
        self.s.mesh.node_names[node].clone()
    }

    fn forces(&self, loads: &[Load], _step: &StepInfo, f: &mut [f64]) -> Result<()> {
        super::forces::external(self.cfg, self.s, loads, self.pressure.borrow().as_ref(), f)
    }

    fn fields(&self, x: &[f64], state: &XState) -> Result<Vec<(String, Field)>> {
        let (cfg, s) = (self.cfg, self.s);
        let mut f = depl_fields(cfg, s, x, self.pressure.borrow().as_ref())?;
        if let Some(c) = cohe_field(s, self.el, &state.czm) {
            f.insert("COHE_ELEM".to_string(), c);
        }
        // MECA_STATIQUE's OPTION='SANS' asks for none; hydro-mechanical models, whose SIEF_ELGA would also
        // hold the hydraulic stresses, get none yet.
        if !s.hm && cfg.sief {
            f.insert("SIEF_ELGA".to_string(), sief_field(cfg, s, x)?);
        }
        Ok(f.into_iter().collect())
    }

    fn prediction(&self) -> Prediction {
        Prediction::Imposed
    }

    fn linear(&self) -> bool {
        self.statics
    }

    /// The reactions at the prescribed unknowns, the external forces, and with eliminated hydraulics the
    /// storage terms of their rows.
    fn reference(&self, r: &Residual) -> f64 {
        let mut reactions: f64 = 0.0;
        for d in 0..r.fext.len() {
            if !r.free[d] {
                reactions = reactions.max((r.fint[d] - r.fext[d]).abs());
            }
        }
        let mut reactions = reactions.max(inf_norm(r.fext));
        if let Some(h) = &self.hydro {
            reactions = reactions.max(h.largest(self.s, &self.el.laws, r.x0, r.x));
        }
        reactions
    }

    fn reference_memory(&self) -> bool {
        true
    }

    /// Small tangents go to LU with partial pivoting: its cost is nothing there, and it solves the
    /// interface rows by their own pivots, which keeps structural zeros exact (the opening of a closed
    /// interface is 0, not round-off). Large ones go to the symmetric LDLᵀ, several times cheaper in
    /// time and memory.
    fn solver_method(&self, n: usize) -> Option<crate::solve::Method> {
        (n < LDLT_FROM).then_some(crate::solve::Method::Lu)
    }

    fn step_report(&self, x: &[f64], state: &XState) -> String {
        zone_state(self.s, self.el, &state.czm, x)
    }
}
