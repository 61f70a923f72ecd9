//! Small-strain plasticity as a [`Physics`]: the elastic problem's unknowns, loads and kinematics
//! ([`Elastic`]), with a law per bulk cell ([`VonMises`]: elastic, or von Mises with isotropic hardening)
//! integrated at the cell's `RIGI` points. The state is the laws' state at every point; the fields are
//! DEPL, SIEF_ELGA and VARI_ELGA (`V1` the cumulated plastic strain, `V2` the plastic indicator).

use super::assembly::{Assembler, ElementDofs};
use super::dofs::Constraints;
use super::elastic::{coords_of, Elastic, NodalTemperature};
use super::elasticity::{self, GaussGeom, Modelisation};
use super::field::Field;
use super::physics::{Failure, Load, Physics, Prediction, StepInfo};
use super::plasticity::{Kind, PointState, Request, ThermalStep, VonMises};
use crate::diag::Error;

/// The components of VARI_ELGA of the von Mises laws.
pub const VARI_NAMES: [&str; 2] = ["V1", "V2"];

/// The plastic problem of a model.
pub struct Plastic {
    pub elastic: Elastic,
    /// Per bulk cell (in the order of `elastic.bulk`): its law and its points' geometry.
    laws: Vec<VonMises>,
    points: Vec<Vec<GaussGeom>>,
    dofs: ElementDofs,
    kind: Kind,
    /// The relations, for the run log.
    relations: String,
    /// The elastic matrix instead of the tangent for the prediction and for the corrections.
    pub elastic_prediction: bool,
    pub elastic_correction: bool,
    /// The temperature the laws follow, where AFFE_VARC gives one.
    temperature: Option<Temperature>,
}

/// The laws' state: per bulk cell, per point.
pub type State = Vec<Vec<PointState>>;

/// A law whose parameters depend on the temperature: the law and the thermal expansion coefficient at a
/// temperature.
pub type LawOfTemperature = std::rc::Rc<dyn Fn(f64) -> Result<(VonMises, f64), String>>;

/// The temperature of AFFE_VARC (NOM_VARC='TEMP') where it acts on the laws: its sources (one per
/// occurrence) and, per mesh cell, T_ref, the index of its source and the cell's law of the temperature.
pub struct Temperature {
    pub sources: Vec<NodalTemperature>,
    pub cells: Vec<Option<(f64, usize, LawOfTemperature)>>,
    /// Whether a point in the natural state (no strain, no stress) starts its step at T_ref (MECA_STATIQUE:
    /// each instant measured from the natural state) rather than at the temperature of the step's start
    /// (STAT_NON_LINE: the initial state is free of stress at the first instant's temperature).
    pub natural_start: bool,
}

impl Plastic {
    /// The physics of `elastic`'s model with `laws[c]` on each mesh cell `c` of its bulk (`relations`
    /// names them for the log).
    pub fn new(elastic: Elastic, laws: &[Option<VonMises>], relations: String) -> Result<Plastic, Error> {
        let md = elastic.modelisation;
        let mesh = &elastic.mesh;
        let mut out_laws = Vec::with_capacity(elastic.bulk.len());
        let mut points = Vec::with_capacity(elastic.bulk.len());
        for &c in &elastic.bulk {
            let law = laws[c]
                .clone()
                .ok_or_else(|| Error::runtime(format!("cell {} of the model has no behaviour", mesh.cell_names[c])))?;
            let t = mesh.cell_types[c];
            let rule = elasticity::rigi_rule_of(md, t);
            let g = elasticity::gauss_geometry(md, t, &coords_of(mesh, c), &rule)
                .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])))?;
            out_laws.push(law);
            points.push(g);
        }
        let kind = match md {
            Modelisation::ThreeD => Kind::Solid,
            Modelisation::CPlan => Kind::PlaneStress,
            Modelisation::DPlan | Modelisation::Axis => Kind::Plane,
        };
        let dofs = elastic.element_dofs();
        Ok(Plastic {
            elastic,
            laws: out_laws,
            points,
            dofs,
            kind,
            relations,
            elastic_prediction: false,
            elastic_correction: false,
            temperature: None,
        })
    }

    /// The same physics, its laws following `temperature` on the cells it covers: each point's law and
    /// thermal strain at the temperature interpolated there from the nodes, at the step's start and end.
    pub fn with_temperature(mut self, temperature: Temperature) -> Plastic {
        self.temperature = Some(temperature);
        self
    }

    /// The temperature of every source at the nodes at `t` (computed on demand, once).
    fn nodal_temperatures(&self, t: f64) -> Result<Vec<Vec<f64>>, Error> {
        match &self.temperature {
            Some(th) => th.sources.iter().map(|s| s(t)).collect(),
            None => Ok(Vec::new()),
        }
    }

    /// The law at the end of the step at point `k` of bulk cell `i` and what the step's change of
    /// temperature does there (None where no temperature acts).
    fn thermal_law(
        &self,
        i: usize,
        k: usize,
        old: &PointState,
        temps: (&[Vec<f64>], &[Vec<f64>]),
    ) -> Result<Option<(VonMises, ThermalStep)>, String> {
        let Some(th) = &self.temperature else { return Ok(None) };
        let c = self.elastic.bulk[i];
        let Some((tref, src, law)) = &th.cells[c] else { return Ok(None) };
        let g = &self.points[i][k];
        let mesh = &self.elastic.mesh;
        let at = |nodal: &[f64]| -> Result<f64, String> {
            let mut t = 0.0;
            for (a, &n) in mesh.cells[c].iter().enumerate() {
                let v = nodal.get(n).copied().unwrap_or(f64::NAN);
                if !v.is_finite() {
                    return Err(format!("AFFE_VARC: no temperature at node {}", mesh.node_names[n]));
                }
                t += g.n[a] * v;
            }
            Ok(t)
        };
        let natural = old.eps == [0.0; 6] && old.sig == [0.0; 6] && old.p == 0.0;
        let tm = if th.natural_start && natural { *tref } else { at(&temps.0[*src])? };
        let tp = at(&temps.1[*src])?;
        let (plus, alpha_p) = law(tp)?;
        let (minus, alpha_m) = if tm == tp { (plus.clone(), alpha_p) } else { law(tm)? };
        let own = &self.laws[i];
        let plus = VonMises { resi_inte: own.resi_inte, iter_inte: own.iter_inte, ..plus };
        let deps_th = alpha_p * (tp - tref) - alpha_m * (tm - tref);
        Ok(Some((plus, ThermalStep { minus, deps_th })))
    }

    /// The natural state: no strain, no stress, no plastic strain.
    pub fn initial_state(&self) -> State {
        self.points.iter().map(|g| vec![PointState::default(); g.len()]).collect()
    }

    /// The laws' state from stored SIEF_ELGA and VARI_ELGA values per mesh cell (ETAT_INIT): the total
    /// strain of each point from the displacements `u`.
    pub fn state_from(
        &self,
        u: &[f64],
        sig: &[Option<Vec<f64>>],
        vari: Option<&[Option<Vec<f64>>]>,
    ) -> Result<State, Error> {
        let md = self.elastic.modelisation;
        let ns = md.nsig();
        let mut out = self.initial_state();
        for (i, &c) in self.elastic.bulk.iter().enumerate() {
            let name = &self.elastic.mesh.cell_names[c];
            let npg = self.points[i].len();
            let s = sig[c].as_ref().filter(|v| v.len() == npg * ns).ok_or_else(|| {
                Error::runtime(format!(
                    "ETAT_INIT: the stresses have no {npg} points of {ns} components on cell {name}"
                ))
            })?;
            let ue: Vec<f64> = self.dofs.get(i).iter().map(|&d| u[d]).collect();
            for (k, pt) in out[i].iter_mut().enumerate() {
                pt.eps = self.strain(i, k, &ue, None);
                pt.sig[..ns].copy_from_slice(&s[k * ns..(k + 1) * ns]);
                if let Some(v) = vari.and_then(|v| v[c].as_ref()) {
                    let nv = v.len() / npg;
                    if nv >= 2 {
                        pt.p = v[k * nv];
                        pt.plastic = v[k * nv + 1] >= 0.5;
                    }
                }
            }
        }
        Ok(out)
    }

    /// The strain (tensorial shear) at point `k` of bulk cell `i` for the element displacements `ue`; under
    /// C_PLAN `ZZ` is taken from `old` (the law finds it).
    fn strain(&self, i: usize, k: usize, ue: &[f64], old: Option<&PointState>) -> [f64; 6] {
        let md = self.elastic.modelisation;
        let (dim, ns) = (md.dim(), md.nsig());
        let g = &self.points[i][k];
        let mut e = [0.0; 6];
        for a in 0..ue.len() / dim {
            let b = elasticity::b_node(md, g, a);
            for (c, row) in b.iter().enumerate().take(ns) {
                for j in 0..dim {
                    e[c] += row[j] * ue[a * dim + j];
                }
            }
        }
        for v in e.iter_mut().skip(3) {
            *v *= 0.5;
        }
        if self.kind == Kind::PlaneStress {
            e[2] = old.map_or(0.0, |o| o.eps[2]);
        }
        e
    }
}

impl Physics for Plastic {
    type State = State;

    fn describe(&self) -> String {
        format!("{}, RELATION={}", self.elastic.modelisation.name(), self.relations)
    }

    fn unknowns(&self) -> usize {
        self.elastic.unknowns()
    }

    fn label(&self, dof: usize) -> String {
        self.elastic.label(dof)
    }

    fn element_dofs(&self) -> ElementDofs {
        self.dofs.clone()
    }

    fn assemble(
        &self,
        step: &StepInfo,
        x: &[f64],
        prev: &State,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> Result<State, Failure> {
        let md = self.elastic.modelisation;
        let dim = md.dim();
        let request = if step.predict { Request::Prediction } else { Request::Full };
        let elastic_matrix = if step.predict { self.elastic_prediction } else { self.elastic_correction };
        let mut states = Vec::with_capacity(prev.len());
        let temps = match &self.temperature {
            Some(_) => Some((self.nodal_temperatures(step.t0)?, self.nodal_temperatures(step.t1)?)),
            None => None,
        };
        for (i, prev_c) in prev.iter().enumerate() {
            let dofs = self.dofs.get(i);
            let nd = dofs.len();
            let ue: Vec<f64> = dofs.iter().map(|&d| x[d]).collect();
            let mut fe = vec![0.0; nd];
            let mut ke = tangent.is_some().then(|| vec![0.0; nd * nd]);
            let mut new_c = Vec::with_capacity(prev_c.len());
            for (k, old) in prev_c.iter().enumerate() {
                let g = &self.points[i][k];
                let eps = self.strain(i, k, &ue, Some(old));
                let fail = |e: String| {
                    let c = self.elastic.bulk[i];
                    Failure::Step(Error::runtime(format!(
                        "integration failure at point {} of cell {}: {e}",
                        k + 1,
                        self.elastic.mesh.cell_names[c]
                    )))
                };
                let thermal = match &temps {
                    Some((t0, t1)) => self.thermal_law(i, k, old, (t0, t1)).map_err(fail)?,
                    None => None,
                };
                let (st, d) = match &thermal {
                    Some((law, step)) => {
                        law.integrate_thermal(self.kind, old, &eps, request, elastic_matrix, Some(step))
                    }
                    None => self.laws[i].integrate_with(self.kind, old, &eps, request, elastic_matrix),
                }
                .map_err(fail)?;
                elasticity::add_bt_sigma(md, g, nd / dim, &st.sig, &mut fe);
                if let Some(ke) = ke.as_mut() {
                    elasticity::add_btdb(md, g, nd / dim, &d, ke);
                }
                new_c.push(st);
            }
            for (&d, v) in dofs.iter().zip(&fe) {
                fint[d] += v;
            }
            if let (Some(asm), Some(ke)) = (tangent.as_deref_mut(), ke.as_ref()) {
                asm.add_matrix(dofs, ke);
            }
            states.push(new_c);
        }
        Ok(states)
    }

    fn conditions(&self, loads: &[Load], cons: &mut Constraints) -> Result<(), Error> {
        self.elastic.conditions(loads, cons)
    }

    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>, Error> {
        self.elastic.dof(load, node, component)
    }

    fn position(&self, node: usize) -> [f64; 3] {
        self.elastic.position(node)
    }

    fn node_name(&self, node: usize) -> String {
        self.elastic.node_name(node)
    }

    fn forces(&self, loads: &[Load], step: &StepInfo, f: &mut [f64]) -> Result<(), Error> {
        self.elastic.forces(loads, step, f)
    }

    fn fields(&self, x: &[f64], state: &State) -> Result<Vec<(String, Field)>, Error> {
        let mesh = &self.elastic.mesh;
        let ns = self.elastic.modelisation.nsig();
        // The elastic physics gives DEPL (it stores no stress: `sief` is off).
        let mut fields: Vec<(String, Field)> =
            self.elastic.fields(x, &0.0)?.into_iter().filter(|(n, _)| n == "DEPL").collect();
        let mut sig = vec![None; mesh.cells.len()];
        let mut vari = vec![None; mesh.cells.len()];
        for (&c, pts) in self.elastic.bulk.iter().zip(state) {
            sig[c] = Some(pts.iter().flat_map(|p| p.sig[..ns].to_vec()).collect::<Vec<_>>());
            vari[c] = Some(pts.iter().flat_map(|p| [p.p, if p.plastic { 1.0 } else { 0.0 }]).collect::<Vec<_>>());
        }
        let names = self.elastic.modelisation.sigma_names().iter().map(|s| s.to_string()).collect();
        fields.push(("SIEF_ELGA".to_string(), Field::Elga { components: names, cells: sig }));
        let vnames = VARI_NAMES.iter().map(|s| s.to_string()).collect();
        fields.push(("VARI_ELGA".to_string(), Field::Elga { components: vnames, cells: vari }));
        Ok(fields)
    }

    fn prediction(&self) -> Prediction {
        Prediction::Tangent
    }

    fn swaps_to_absolute(&self) -> bool {
        true
    }
}
