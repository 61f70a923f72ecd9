//! The 2020 interface hydraulics of an HM X-FEM model with cohesive interfaces, when the scene leaves
//! hydraulic unknowns free (`hm-coupled-formulation.md` §6.2; Code_Aster 2020 `xasshv_frac`,
//! `xvecha`, `xvechb`, `xvechc`, `xhvco5`).
//!
//! The unknowns are those of the mechanical solve (`XDofs`) followed by the bulk pressures of the HM
//! elements (PRE1 on the vertices, H<j>PRE1 on their enrichment sets) and, per multiplier packet, the
//! fracture unknowns p_f (PRE_FLU), q⁺ (LAG_FLI), q⁻ (LAG_FLS). The bulk is the HM element of
//! `stages::core::hm` on the sub-cells (the same element the HM driver steps), in place of the elastic
//! stiffness. On every facet, with Φ_k the packets' multiplier functions and N̂ ψ± the pressure functions
//! on the side ± (+ where the level set is positive):
//! - bulk pressure rows: `+Δt ∫ N̂ ψ± q̄±` (q̄ = θ q(t⁺) + (1 − θ) q(t⁻));
//! - continuity rows q±: `∫ Φ_k (p± − p_f) = 0`;
//! - fracture rows p_f: `−∫ Φ_k ρ (a⁺ − a⁻) − Δt ∫ Φ_k (q̄⁺ + q̄⁻)` (+ the cubic law along the interface,
//!   see below);
//! - the normal w-row of the mortar law: `−∫ Φ_k p_f` (the total traction is λ − p_f n).
//!
//! Only what the scene calls for: p_f must be prescribed on every packet; the fracture rows then carry only
//! their reactions (in the reference force of RESI_GLOB_RELA), where the storage takes ρ = ρ₀ and the cubic
//! law `ρ a³/(12μ) ∇p_f` is left out. A free p_f (the fracture mass balance with the cubic law) stops the
//! run by name.

use super::setup::{Flow, Setup};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs};
use crate::hm::element::{element, StepData};
use crate::hm::law::PointState;
use crate::stages::core::hm::hm_problem;
use crate::stages::core::settings::Settings;
use crate::xfem::discrete::{self, Exchange};
use std::fmt::Write as _;

impl Flow {
    pub fn new(cfg: &Settings, s: &Setup) -> Result<Flow> {
        let model = &cfg.model;
        let (mesh, xm, xd, ndim) = (&*s.mesh, &*s.xm, &s.xd, s.ndim());
        let hp = hm_problem(model, &s.chmat).map_err(|e| e.at(cfg.span_of("MODELE")))?;
        let num = &hp.numbering;
        let per_set = ndim + 1;
        let mut pre1 = vec![None; mesh.nnodes()];
        let mut hpre1: Vec<Vec<Option<usize>>> = xd.sets.iter().map(|v| vec![None; v.len()]).collect();
        let mut to_full = vec![0; num.ndofs()];
        let mut next = xd.n;
        for (d, slot) in to_full.iter_mut().enumerate() {
            let (n, k) = num.node_comp(d);
            let missing = || {
                Error::runtime(format!(
                    "node {}: component {} of the HM elements has no unknown in the X-FEM numbering",
                    mesh.node_names[n], num.components[k]
                ))
                .at(cfg.span)
            };
            *slot = if k < ndim {
                xd.std[n].ok_or_else(missing)? + k
            } else if k == ndim {
                pre1[n] = Some(next);
                next += 1;
                next - 1
            } else {
                let (j, r) = ((k - per_set) / per_set, (k - per_set) % per_set);
                if r < ndim {
                    *xd.sets[n].get(j).ok_or_else(missing)? + r
                } else {
                    let h = hpre1[n].get_mut(j).ok_or_else(missing)?;
                    *h = Some(next);
                    next += 1;
                    next - 1
                }
            };
        }
        let dofs: Vec<Vec<usize>> = hp.elements().map(|(_, c)| c.dofs.iter().map(|&d| to_full[d]).collect()).collect();
        let (first_pressure, npressure) = (xd.n, next - xd.n);
        let mut fracture = Vec::new();
        for z in &s.zones {
            let mut v = Vec::new();
            for _ in &z.packets {
                v.push(next);
                next += 3;
            }
            fracture.push(v);
        }
        let mut exchanges = Vec::new();
        let mut rho_f = Vec::new();
        for z in &s.zones {
            let rule = discrete::facet_rule(ndim, z.order).map_err(|e| cfg.err("CONTACT", e))?;
            let facets = s.facets(z.crack);
            let ex = discrete::exchanges(mesh, xm, z.crack, facets, &rule, &z.packet_of, &z.edges)
                .map_err(|e| cfg.err("CONTACT", format!("{}: {e}", xm.crack_names[z.crack])))?;
            let mut v = Vec::new();
            for e in ex {
                let nodes = &mesh.cells[e.cell];
                let mut cd = Vec::with_capacity(e.cols.len());
                for &(ai, set) in &e.cols {
                    let n = nodes[ai];
                    let d = match set {
                        None => pre1[n],
                        Some(j) => hpre1[n].get(j).copied().flatten(),
                    };
                    cd.push(d.ok_or_else(|| {
                        cfg.err(
                            "CONTACT",
                            format!("node {} of an interface cell carries no pressure", mesh.node_names[n]),
                        )
                    })?);
                }
                v.push((e, cd));
            }
            exchanges.push(v);
            let c = *z.cells.first().ok_or_else(|| cfg.err("CONTACT", "a cohesive zone without contact cells"))?;
            rho_f.push(hp.cells[c].as_ref().map_or(Ok(0.0), |hc| Ok::<f64, Error>(hc.mat.rho_l))?);
        }
        let theta = cfg.theta;
        Ok(Flow { hp, n: next, dofs, pre1, hpre1, first_pressure, npressure, fracture, exchanges, rho_f, theta })
    }

    /// The states of the bulk points for the unknowns `x` (the initial state).
    pub fn initial_states(&self, x: &[f64]) -> Vec<Vec<PointState>> {
        self.hp
            .elements()
            .zip(&self.dofs)
            .map(|((_, c), d)| {
                let ue: Vec<f64> = d.iter().map(|&i| x[i]).collect();
                c.points.initial_states(&c.mat, &ue)
            })
            .collect()
    }

    /// The unknown lists of the flow's operators, for the matrix pattern.
    pub fn elements(&self, s: &Setup, e: &mut ElementDofs) {
        for d in &self.dofs {
            e.push(d);
        }
        for (zi, ex) in self.exchanges.iter().enumerate() {
            for (x, cd) in ex {
                e.push(&self.exchange_dofs(s, zi, x, cd));
            }
        }
    }

    /// An exchange's unknowns: its pressure columns, then per packet q⁺, q⁻, p_f and the normal w.
    fn exchange_dofs(&self, s: &Setup, zi: usize, x: &Exchange, cd: &[usize]) -> Vec<usize> {
        let crack = s.zones[zi].crack;
        let mut d = cd.to_vec();
        for &k in &x.packets {
            let f = self.fracture[zi][k];
            d.extend([f + 1, f + 2, f, s.xd.packets[crack][k] + s.ndim()]);
        }
        d
    }

    /// Add the internal forces and tangent of the flow at `x` over a step from `x0` (length `dt`, end
    /// `t`), from the point states `prev`; the point states at `x`.
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &self,
        cfg: &Settings,
        s: &Setup,
        x: &[f64],
        x0: &[f64],
        prev: &[Vec<PointState>],
        dt: f64,
        t: f64,
        r: &mut [f64],
        mut asm: Option<&mut Assembler>,
    ) -> Result<Vec<Vec<PointState>>> {
        let mut states = Vec::with_capacity(prev.len());
        for (((c, cell), d), pv) in self.hp.elements().zip(&self.dofs).zip(prev) {
            let gravity = self.hp.gravity(cell, t).map_err(|e| e.at(cfg.span))?;
            let step = StepData { dt, theta: self.theta, gravity };
            let ue: Vec<f64> = d.iter().map(|&i| x[i]).collect();
            let out = element(&cell.points, &cell.mat, &ue, pv, &step).map_err(|e| {
                Error::runtime(format!("cell {}: {} (INST={t})", s.mesh.cell_names[c], e.0)).at(cfg.span)
            })?;
            for (i, &di) in d.iter().enumerate() {
                r[di] += out.fint[i];
            }
            if let Some(a) = asm.as_deref_mut() {
                a.add_matrix(d, &out.k);
            }
            states.push(out.states);
        }
        let th = self.theta;
        for (zi, ex) in self.exchanges.iter().enumerate() {
            let rho = self.rho_f[zi];
            for (e, cd) in ex {
                let dofs = self.exchange_dofs(s, zi, e, cd);
                let (nc, npk) = (cd.len(), e.packets.len());
                let nd = dofs.len();
                let mut ke = vec![0.0; nd * nd];
                // Local positions of packet k's q⁺, q⁻, p_f, w_n.
                let at = |k: usize, o: usize| nc + 4 * k + o;
                let bar = |d: usize| th * x[d] + (1.0 - th) * x0[d];
                for i in 0..nc {
                    for k in 0..npk {
                        let (qp, qm) = (dofs[at(k, 0)], dofs[at(k, 1)]);
                        let (ep, em) = (e.ep[i * npk + k], e.em[i * npk + k]);
                        // Bulk pressure rows: + Δt ∫ N̂ ψ± q̄±.
                        r[cd[i]] += dt * (ep * bar(qp) + em * bar(qm));
                        ke[i * nd + at(k, 0)] += dt * th * ep;
                        ke[i * nd + at(k, 1)] += dt * th * em;
                        // Continuity rows: ∫ Φ_k p±.
                        r[qp] += ep * x[cd[i]];
                        r[qm] += em * x[cd[i]];
                        ke[at(k, 0) * nd + i] += ep;
                        ke[at(k, 1) * nd + i] += em;
                    }
                }
                for k in 0..npk {
                    for l in 0..npk {
                        let mkl = e.mm[k * npk + l];
                        let (pf_l, qp_l, qm_l, w_l) = (dofs[at(l, 2)], dofs[at(l, 0)], dofs[at(l, 1)], dofs[at(l, 3)]);
                        // Continuity rows: − ∫ Φ_k p_f.
                        r[dofs[at(k, 0)]] -= mkl * x[pf_l];
                        r[dofs[at(k, 1)]] -= mkl * x[pf_l];
                        ke[at(k, 0) * nd + at(l, 2)] -= mkl;
                        ke[at(k, 1) * nd + at(l, 2)] -= mkl;
                        // Fracture rows: − ∫ Φ_k ρ (a⁺ − a⁻) − Δt ∫ Φ_k (q̄⁺ + q̄⁻).
                        r[dofs[at(k, 2)]] -= mkl * (rho * (x[w_l] - x0[w_l]) + dt * (bar(qp_l) + bar(qm_l)));
                        ke[at(k, 2) * nd + at(l, 3)] -= mkl * rho;
                        ke[at(k, 2) * nd + at(l, 0)] -= mkl * dt * th;
                        ke[at(k, 2) * nd + at(l, 1)] -= mkl * dt * th;
                        // The normal w-row of the mortar law: − ∫ Φ_k p_f.
                        r[dofs[at(k, 3)]] -= mkl * x[pf_l];
                        ke[at(k, 3) * nd + at(l, 2)] -= mkl;
                    }
                }
                if let Some(a) = asm.as_deref_mut() {
                    a.add_matrix(&dofs, &ke);
                }
            }
        }
        Ok(states)
    }

    /// Stop when a packet's p_f is free (the fracture mass balance is not computed); the run log's
    /// account of the hydraulic unknowns, solved and eliminated.
    pub fn report(&self, cfg: &Settings, s: &Setup, prescribed: &dyn Fn(usize) -> bool) -> Result<String> {
        let mesh = &*s.mesh;
        for (zi, z) in s.zones.iter().enumerate() {
            for (k, &f) in self.fracture[zi].iter().enumerate() {
                if !prescribed(f) {
                    return Err(cfg.err(
                        "EXCIT",
                        format!(
                            "PRE_FLU of {} on packet {:?} is not prescribed: the fracture mass balance (storage ρ_f·a and \
                             the cubic law ρ a³/(12μ) ∇p_f along the interface) is not supported yet",
                            s.xm.crack_names[z.crack],
                            super::setup::names(mesh, &z.packets[k])
                        ),
                    ));
                }
            }
        }
        let count = |v: &mut dyn Iterator<Item = usize>| {
            let all: Vec<usize> = v.collect();
            let fixed = all.iter().filter(|&&d| prescribed(d)).count();
            (all.len() - fixed, fixed)
        };
        let (p_free, p_fixed) = count(&mut (self.first_pressure..self.first_pressure + self.npressure));
        let (q_free, q_fixed) =
            count(&mut self.fracture.iter().flatten().flat_map(|&f| [f + 1, f + 2]).collect::<Vec<_>>().into_iter());
        let npk: usize = self.fracture.iter().map(Vec::len).sum();
        let mut r = String::new();
        let _ = writeln!(
            r,
            "    solved: coupled flow — some hydraulic unknowns are free ({p_free} bulk pressures PRE1/H*PRE1, {q_free} \
             exchange fluxes q+/q- (LAG_FLI/LAG_FLS)); the bulk is the HM element (KIT_HM, θ = {}) on the sub-cells, the \
             exchange +Δt∫N̂ψ±q̄± enters the pressure rows of each side, continuity ∫Φ(p± − p_f) = 0 holds on the \
             facets, and p_f acts on the lips through the mortar w-equation (−∫Φ p_f n)",
            self.theta
        );
        let _ = writeln!(
            r,
            "    eliminated: {p_fixed} bulk pressures and {q_fixed} exchange fluxes prescribed by the loads; p_f (PRE_FLU) \
             prescribed on all {npk} packets, so the fracture mass balance is not solved: its rows carry only their \
             reactions (storage with ρ₀, without the cubic law), in the reference of RESI_GLOB_RELA"
        );
        Ok(r)
    }
}
