//! Heat conduction as a [`Physics`]: one temperature `TEMP` per node of the model, the conduction and
//! capacity of each bulk cell (`THER`, `THER_FO`, `THER_NL`), the heat the loads bring, and Code_Aster's
//! θ-scheme over a step.
//!
//! With `C(T)` the capacity term (`M T`, or `∫ β(T) N` for `THER_NL`), `K(T)` the conduction term and
//! `Q(T, t)` the heat of the loads, a transient step from `(T⁻, t⁻)` to `t⁺` solves
//!
//! `G(T) = [C(T) − C(T⁻)] / Δt + θ [K(T) − Q(T, t⁺)] + (1 − θ) [K(T⁻) − Q(T⁻, t⁻)] = 0`
//!
//! and a steady one (`t⁻ = t⁺`, or a computation without θ) `G(T) = K(T) − Q(T, t⁺) = 0`, the laws taken
//! at `t⁺`. On the core's terms: the internal forces are `C(T)/Δt + θ K(T)`, the old terms
//! `(1 − θ) K(T⁻) − C(T⁻)/Δt` and `−θ` times the heat of the loads that depend on the temperature
//! ([`Physics::state_loads`]); the external forces are `θ` times the heat of the others
//! ([`Physics::forces`]) and `(1 − θ) Q(T⁻, t⁻)` ([`Physics::start_forces`]).

use super::boundary::{radiation, skin_load, wall_exchange};
use super::element::{self, capacity, conduction, conduction_nl, enthalpy_nl, matvec, source};
use super::{Conductivity, Curve, Modelisation, ThermalError};
use crate::diag::Error;
use crate::fem::assembly::{Assembler, ElementDofs};
use crate::fem::dofs::DofNumbering;
use crate::fem::field::Field;
use crate::fem::frame::Frame;
use crate::fem::physics::{Failure, Force, Load, Physics, Prediction, Residual, StepInfo, Value};
use crate::mesh::Mesh;
use std::borrow::Cow;
use std::cell::{Cell, RefCell};
use std::rc::Rc;

/// A parameter of a linear heat law: a real, or a function of the time (`THER_FO`).
#[derive(Clone)]
pub enum Param {
    Real(f64),
    OfTime(Rc<dyn Fn(f64) -> Result<f64, Error>>),
}

impl Param {
    pub fn at(&self, inst: f64) -> Result<f64, Error> {
        match self {
            Param::Real(v) => Ok(*v),
            Param::OfTime(f) => f(inst),
        }
    }
}

/// A conductivity law: one value (isotropic), or three along the axes of a local frame (orthotropic,
/// `THER_ORTH`, `THER_NL_ORTH`: `λ_L λ_T λ_N`).
#[derive(Clone)]
pub enum Lambda<P> {
    Iso(P),
    Ortho([P; 3], Frame),
}

impl Lambda<Param> {
    /// The conductivity at a time.
    pub fn at(&self, inst: f64) -> Result<Conductivity, Error> {
        Ok(match self {
            Lambda::Iso(l) => Conductivity::Iso(l.at(inst)?),
            Lambda::Ortho(l, frame) => {
                Conductivity::Ortho { lambda: [l[0].at(inst)?, l[1].at(inst)?, l[2].at(inst)?], frame: *frame }
            }
        })
    }

    /// The conductivity when it does not depend on the time.
    fn constant(&self) -> Option<Conductivity> {
        match self {
            Lambda::Iso(Param::Real(l)) => Some(Conductivity::Iso(*l)),
            Lambda::Ortho([Param::Real(a), Param::Real(b), Param::Real(c)], frame) => {
                Some(Conductivity::Ortho { lambda: [*a, *b, *c], frame: *frame })
            }
            _ => None,
        }
    }
}

impl Lambda<Curve> {
    /// The conductivity at a temperature and its derivative in the temperature.
    pub fn eval(&self, temp: f64) -> Result<(Conductivity, Conductivity), super::curve::OutOfRange> {
        Ok(match self {
            Lambda::Iso(l) => {
                let (v, d) = l.eval(temp)?;
                (Conductivity::Iso(v), Conductivity::Iso(d))
            }
            Lambda::Ortho(l, frame) => {
                let (a, b, c) = (l[0].eval(temp)?, l[1].eval(temp)?, l[2].eval(temp)?);
                (
                    Conductivity::Ortho { lambda: [a.0, b.0, c.0], frame: *frame },
                    Conductivity::Ortho { lambda: [a.1, b.1, c.1], frame: *frame },
                )
            }
        })
    }
}

/// The heat law of a bulk cell.
#[derive(Clone)]
pub enum Law {
    /// `THER`, `THER_FO`, `THER_ORTH`: conductivity and volumetric heat capacity (None: steady
    /// computations only).
    Linear { lambda: Lambda<Param>, rho_cp: Option<Param> },
    /// `THER_NL`, `THER_NL_ORTH`: conductivity and enthalpy as tabulated functions of the temperature.
    Nonlinear { lambda: Lambda<Curve>, beta: Curve },
}

impl Law {
    /// The conductivity at a time and a temperature.
    pub fn conductivity(&self, inst: f64, temp: f64) -> Result<Conductivity, Error> {
        match self {
            Law::Linear { lambda, .. } => lambda.at(inst),
            Law::Nonlinear { lambda, .. } => {
                Ok(lambda.eval(temp).map_err(|e| Error::runtime(format!("THER_NL/LAMBDA: {e}")))?.0)
            }
        }
    }
}

/// The laws' trial state of a thermal computation: the temperatures it was computed at, and the parts
/// of the equations Code_Aster's relative residual is scaled by.
#[derive(Clone, Debug, Default)]
pub struct HeatState {
    /// Its identity (the old terms of a step are computed once per start state).
    id: u64,
    temps: Vec<f64>,
    /// The capacity term `C(T)` (transient steps), on every unknown.
    capacity: Vec<f64>,
    /// The heat of the loads that depend on the temperature, `Q_T(T, t⁺)`.
    heat: Vec<f64>,
}

/// The conduction matrix of a cell and its capacity matrix (row-major).
type CellMatrices = (Vec<f64>, Option<Vec<f64>>);

/// A cell's term and its derivative: computed, or lent from the matrices computed once.
type CellTerm<'a> = (Vec<f64>, Cow<'a, [f64]>);

/// A step from a start state: its identity, t⁻ and t⁺.
type StepKey = (u64, f64, f64);

/// A boundary heat flux density of the point and the temperature, with its derivative.
type SkinDensity<'a> = dyn Fn(&crate::fem::elasticity::BoundaryPoint, f64) -> Result<(f64, f64), Error> + 'a;

/// The heat conduction problem of a thermal model.
pub struct Thermal {
    pub mesh: Rc<Mesh>,
    /// Per mesh cell: its thermal element and whether it is a bulk (volume) one, None off the model.
    pub elements: Vec<Option<(Modelisation, bool)>>,
    pub bulk: Vec<usize>,
    /// Per mesh cell: the heat law of a bulk cell.
    pub laws: Vec<Option<Rc<Law>>>,
    /// `TEMP` on every node of the model's cells.
    pub numbering: DofNumbering,
    /// θ of a transient computation; None: every step is steady.
    theta: Option<f64>,
    /// THER_LINEAIRE: one solve per step.
    linear: bool,
    dofs: ElementDofs,
    /// Per mesh cell: the conduction and (transient computations) capacity matrices of a bulk cell whose
    /// law is linear with constant parameters, computed once.
    constant: Vec<Option<CellMatrices>>,
    /// The old terms of the last step computed: (start state, t⁻, t⁺) and the vector.
    old: RefCell<Option<(StepKey, Vec<f64>)>>,
    ids: Cell<u64>,
}

fn cell_err(mesh: &Mesh, c: usize) -> impl Fn(ThermalError) -> Error + '_ {
    move |e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c]))
}

fn excit(msg: String) -> Error {
    Error::runtime(msg).at_keyword("EXCIT")
}

/// One element term of the loads: the unknowns, the heat they bring and its derivative in the
/// temperatures where it depends on them (row-major).
struct Term {
    dofs: Vec<usize>,
    heat: Vec<f64>,
    tangent: Option<Vec<f64>>,
}

/// Does the heat of a load depend on the temperature?
fn depends_on_temperature(f: &Force) -> bool {
    matches!(
        f,
        Force::Exchange { .. }
            | Force::Radiation { .. }
            | Force::HeatFluxOfTemperature { .. }
            | Force::HeatSourceOfTemperature { .. }
            | Force::WallExchange { .. }
    )
}

impl Thermal {
    /// The problem of the model's cells (`elements`) with their laws; `couples` are element unknowns the
    /// loads join beyond the cells' (the paired walls of ECHANGE_PAROI), for the tangent's pattern.
    pub fn new(
        mesh: Rc<Mesh>,
        elements: Vec<Option<(Modelisation, bool)>>,
        laws: Vec<Option<Rc<Law>>>,
        theta: Option<f64>,
        linear: bool,
        couples: &[Vec<usize>],
    ) -> Result<Thermal, Error> {
        let bulk: Vec<usize> = (0..elements.len()).filter(|&c| elements[c].is_some_and(|(_, b)| b)).collect();
        if let Some(&c) = bulk.iter().find(|&&c| laws[c].is_none()) {
            return Err(Error::runtime(format!("cell {} of the model has no heat law", mesh.cell_names[c])));
        }
        let mut mask = vec![0u32; mesh.nnodes()];
        for (c, e) in elements.iter().enumerate() {
            if e.is_some() {
                mesh.cells[c].iter().for_each(|&n| mask[n] = 1);
            }
        }
        let numbering = DofNumbering::with_components(vec!["TEMP"], mask);
        let mut dofs = ElementDofs::new();
        for &c in &bulk {
            dofs.push(&numbering.cell_dofs(&mesh.cells[c]).expect("the model's nodes are numbered"));
        }
        for nodes in couples {
            let d: Option<Vec<usize>> = nodes.iter().map(|&n| numbering.dof(n, 0)).collect();
            let d = d.ok_or_else(|| excit("ECHANGE_PAROI: a wall's node carries no element of the model".into()))?;
            dofs.push(&d);
        }
        let mut constant = vec![None; mesh.cells.len()];
        for &c in &bulk {
            let Law::Linear { lambda, rho_cp } = &**laws[c].as_ref().expect("checked above") else {
                continue;
            };
            let Some(l) = lambda.constant() else { continue };
            let rho_cp = match rho_cp {
                Some(Param::Real(r)) => Some(*r),
                None => None,
                Some(Param::OfTime(_)) => continue,
            };
            let (md, _) = elements[c].expect("a bulk cell has its element");
            let x: Vec<[f64; 3]> = mesh.cells[c].iter().map(|&n| mesh.coords[n]).collect();
            let t = mesh.cell_types[c];
            let k = conduction(md, t, &x, &l).map_err(cell_err(&mesh, c))?;
            // The capacity of a steady computation is never asked for (and may be missing).
            let m = match (theta, rho_cp) {
                (Some(_), Some(r)) => Some(capacity(md, t, &x, r).map_err(cell_err(&mesh, c))?),
                _ => None,
            };
            constant[c] = Some((k, m));
        }
        Ok(Thermal {
            mesh,
            elements,
            bulk,
            laws,
            numbering,
            theta,
            linear,
            dofs,
            constant,
            old: RefCell::new(None),
            ids: Cell::new(0),
        })
    }

    /// Is any law nonlinear (`THER_NL`)?
    pub fn nonlinear(&self) -> bool {
        self.laws.iter().flatten().any(|l| matches!(**l, Law::Nonlinear { .. }))
    }

    /// The modelisations of the model, for the log.
    pub fn modelisations(&self) -> Vec<&'static str> {
        let mut v: Vec<&str> = self.elements.iter().flatten().map(|(m, _)| m.name()).collect();
        v.sort();
        v.dedup();
        v
    }

    /// A state at the temperatures `x` (the start of a computation).
    pub fn state(&self, x: &[f64]) -> HeatState {
        HeatState { id: self.next_id(), temps: x.to_vec(), ..Default::default() }
    }

    fn next_id(&self) -> u64 {
        self.ids.set(self.ids.get() + 1);
        self.ids.get()
    }

    /// Is the step steady, and its θ (1 when steady)?
    fn scheme(&self, step: &StepInfo) -> (bool, f64) {
        match self.theta {
            Some(th) if step.t1 != step.t0 => (false, th),
            _ => (true, 1.0),
        }
    }

    /// The temperatures of a cell's nodes.
    pub fn cell_temps(&self, c: usize, temps: &[f64]) -> Vec<f64> {
        self.mesh.cells[c].iter().map(|&n| self.numbering.dof(n, 0).map(|d| temps[d]).unwrap_or(0.0)).collect()
    }

    fn cell_dofs(&self, c: usize) -> Vec<usize> {
        self.numbering.cell_dofs(&self.mesh.cells[c]).expect("the model's cells are numbered")
    }

    fn coords(&self, c: usize) -> Vec<[f64; 3]> {
        self.mesh.cells[c].iter().map(|&n| self.mesh.coords[n]).collect()
    }

    /// The conduction `K(T)` and, when asked, the capacity `C(T)` of a bulk cell with their derivatives,
    /// the laws at `t`.
    #[allow(clippy::type_complexity)]
    fn cell_terms(
        &self,
        c: usize,
        temps: &[f64],
        t: f64,
        with_capacity: bool,
    ) -> Result<(CellTerm<'_>, Option<CellTerm<'_>>), Error> {
        let mesh = &*self.mesh;
        let te = self.cell_temps(c, temps);
        // The matrices computed once are lent, not copied.
        if let Some((k, m)) = &self.constant[c] {
            if !with_capacity || m.is_some() {
                let cap =
                    if with_capacity { m.as_ref().map(|m| (matvec(m, &te), Cow::Borrowed(&m[..]))) } else { None };
                return Ok(((matvec(k, &te), Cow::Borrowed(&k[..])), cap));
            }
        }
        let (md, _) = self.elements[c].expect("a bulk cell has its element");
        let ct = mesh.cell_types[c];
        let x = self.coords(c);
        let law = self.laws[c].as_ref().expect("a bulk cell has its law");
        match &**law {
            Law::Linear { lambda, rho_cp } => {
                let k = conduction(md, ct, &x, &lambda.at(t)?).map_err(cell_err(mesh, c))?;
                let cap = if with_capacity {
                    let rc = rho_cp.as_ref().ok_or_else(|| {
                        Error::runtime(format!(
                            "cell {}: a transient computation needs RHO_CP in THER / THER_FO",
                            mesh.cell_names[c]
                        ))
                        .at_keyword("CHAM_MATER")
                    })?;
                    let m = capacity(md, ct, &x, rc.at(t)?).map_err(cell_err(mesh, c))?;
                    Some((matvec(&m, &te), Cow::Owned(m)))
                } else {
                    None
                };
                Ok(((matvec(&k, &te), Cow::Owned(k)), cap))
            }
            Law::Nonlinear { lambda, beta } => {
                let k = conduction_nl(md, ct, &x, &te, &|tp| Ok(lambda.eval(tp)?)).map_err(cell_err(mesh, c))?;
                let cap = if with_capacity {
                    let (v, m) = enthalpy_nl(md, ct, &x, &te, &|tp| Ok(beta.eval(tp)?)).map_err(cell_err(mesh, c))?;
                    Some((v, Cow::Owned(m)))
                } else {
                    None
                };
                Ok(((k.0, Cow::Owned(k.1)), cap))
            }
        }
    }

    /// Add the old terms of a transient step, `(1 − θ) K(T⁻) − C(T⁻)/Δt` (the laws at `t⁺`), to `fint`:
    /// computed once per step and start state, then added from the cache.
    fn add_old_terms(&self, step: &StepInfo, theta: f64, prev: &HeatState, fint: &mut [f64]) -> Result<(), Error> {
        let key = (prev.id, step.t0, step.t1);
        let cached = matches!(&*self.old.borrow(), Some((k, _)) if *k == key);
        if !cached {
            let g = self.old_terms(step, theta, prev)?;
            *self.old.borrow_mut() = Some((key, g));
        }
        let old = self.old.borrow();
        let (_, g) = old.as_ref().expect("computed above");
        fint.iter_mut().zip(g).for_each(|(f, v)| *f += v);
        Ok(())
    }

    /// The old terms of a transient step on every unknown (see [`Thermal::add_old_terms`]).
    fn old_terms(&self, step: &StepInfo, theta: f64, prev: &HeatState) -> Result<Vec<f64>, Error> {
        let dt = step.dt();
        let mut g = vec![0.0; prev.temps.len()];
        for &c in &self.bulk {
            let ((k, _), cap) = self.cell_terms(c, &prev.temps, step.t1, true)?;
            let (cv, _) = cap.expect("asked for");
            for (i, d) in self.cell_dofs(c).into_iter().enumerate() {
                g[d] += (1.0 - theta) * k[i] - cv[i] / dt;
            }
        }
        Ok(g)
    }

    /// The skin cell `c` of a load's item, checked.
    fn skin(&self, load: &str, item: &Force, c: usize) -> Result<Modelisation, Error> {
        match self.elements[c] {
            Some((md, false)) => Ok(md),
            _ => Err(excit(format!(
                "load {load}: {}: cell {} is not a boundary cell of the model",
                item.keyword(),
                self.mesh.cell_names[c]
            ))),
        }
    }

    /// The element terms of one load item at the temperatures `temps`.
    fn terms(&self, load: &str, item: &Force, temps: &[f64]) -> Result<Vec<Term>, Error> {
        let mesh = &*self.mesh;
        let mut out = Vec::new();
        let material = |e: Error| ThermalError::Material(e.msg);
        // A boundary density q(point, T) on skin cells.
        let mut skin = |cells: &[usize], q: &SkinDensity, dep: bool| -> Result<(), Error> {
            for &c in cells {
                let md = self.skin(load, item, c)?;
                let te = self.cell_temps(c, temps);
                let (f, df) = skin_load(md, mesh.cell_types[c], &self.coords(c), dep.then_some(&te[..]), &|p, tp| {
                    q(p, tp).map_err(material)
                })
                .map_err(cell_err(mesh, c))?;
                out.push(Term { dofs: self.cell_dofs(c), heat: f, tangent: dep.then_some(df) });
            }
            Ok(())
        };
        let v = |val: &Value, x: &[f64; 3]| val.at(x);
        match item {
            Force::HeatFlux { cells, value } => skin(cells, &|p, _| Ok((v(value, &p.x)?, 0.0)), false)?,
            Force::HeatFluxVector { cells, components } => skin(
                cells,
                &|p, _| {
                    let mut q = 0.0;
                    for (k, c) in components.iter().enumerate() {
                        if let Some(c) = c {
                            q += v(c, &p.x)? * p.normal[k];
                        }
                    }
                    Ok((q, 0.0))
                },
                false,
            )?,
            Force::Exchange { cells, coef_h, temp_ext } => skin(
                cells,
                &|p, tp| {
                    let h = v(coef_h, &p.x)?;
                    Ok((h * (v(temp_ext, &p.x)? - tp), -h))
                },
                true,
            )?,
            Force::Radiation { cells, sigma, epsilon, temp_ext } => {
                skin(cells, &|p, tp| Ok(radiation(v(sigma, &p.x)?, v(epsilon, &p.x)?, v(temp_ext, &p.x)?, tp)), true)?
            }
            Force::HeatFluxOfTemperature { cells, flux } => skin(cells, &|p, tp| flux(&p.x, tp), true)?,
            Force::HeatSource { cells, value } => {
                for &c in cells.iter() {
                    let (md, _) = self.bulk_cell(load, item, c)?;
                    let (f, _) = source(md, mesh.cell_types[c], &self.coords(c), None, &|p, _| {
                        v(value, &p.x).map(|s| (s, 0.0)).map_err(material)
                    })
                    .map_err(cell_err(mesh, c))?;
                    out.push(Term { dofs: self.cell_dofs(c), heat: f, tangent: None });
                }
            }
            Force::HeatSourceOfTemperature { cells, source: s } => {
                for &c in cells.iter() {
                    let (md, _) = self.bulk_cell(load, item, c)?;
                    let te = self.cell_temps(c, temps);
                    let (q, dq) = source(md, mesh.cell_types[c], &self.coords(c), Some(&te), &|p, tp| {
                        s(&p.x, tp).map_err(material)
                    })
                    .map_err(cell_err(mesh, c))?;
                    out.push(Term { dofs: self.cell_dofs(c), heat: q, tangent: Some(dq) });
                }
            }
            Force::WallExchange { pairs, coef_h } => {
                for (c, facing) in pairs.iter() {
                    let md = self.skin(load, item, *c)?;
                    let mut dofs = self.cell_dofs(*c);
                    let other: Option<Vec<usize>> = facing.iter().map(|&n| self.numbering.dof(n, 0)).collect();
                    dofs.extend(other.ok_or_else(|| {
                        excit(format!(
                            "load {load}: ECHANGE_PAROI: the wall facing cell {} is not in the model",
                            mesh.cell_names[*c]
                        ))
                    })?);
                    let x2: Vec<[f64; 3]> = facing.iter().map(|&n| mesh.coords[n]).collect();
                    let hm = wall_exchange(md, mesh.cell_types[*c], &self.coords(*c), &x2, &|x| {
                        v(coef_h, x).map_err(material)
                    })
                    .map_err(cell_err(mesh, *c))?;
                    let te: Vec<f64> = dofs.iter().map(|&d| temps[d]).collect();
                    let q: Vec<f64> = matvec(&hm, &te).iter().map(|x| -x).collect();
                    out.push(Term { dofs, heat: q, tangent: Some(hm.iter().map(|x| -x).collect()) });
                }
            }
            other => {
                return Err(excit(format!(
                    "load {load}: {} is a mechanical load; the model is a thermal one",
                    other.keyword()
                )))
            }
        }
        Ok(out)
    }

    fn bulk_cell(&self, load: &str, item: &Force, c: usize) -> Result<(Modelisation, bool), Error> {
        match self.elements[c] {
            Some(e @ (_, true)) => Ok(e),
            _ => Err(excit(format!(
                "load {load}: {}: cell {} is not a volume cell of the model",
                item.keyword(),
                self.mesh.cell_names[c]
            ))),
        }
    }

    /// The field `TEMP` of the temperatures (NaN off the model).
    pub fn temp_field(&self, temps: &[f64]) -> Field {
        let mut values = vec![f64::NAN; self.mesh.nnodes()];
        for (d, v) in temps.iter().enumerate() {
            values[self.numbering.node_comp(d).0] = *v;
        }
        Field::Node { components: vec!["TEMP".into()], values }
    }

    /// The temperatures on the unknowns of a field `TEMP` on nodes; `what` names it in messages.
    pub fn temps_of(&self, f: &Field, what: &str) -> Result<Vec<f64>, Error> {
        let Field::Node { components, values } = f else {
            return Err(Error::runtime(format!("{what} is not a field on nodes")));
        };
        let k = components
            .iter()
            .position(|c| c == "TEMP")
            .ok_or_else(|| Error::runtime(format!("{what} has no component TEMP")))?;
        let n = components.len();
        (0..self.numbering.ndofs())
            .map(|d| {
                let node = self.numbering.node_comp(d).0;
                match values.get(node * n + k) {
                    Some(v) if v.is_finite() => Ok(*v),
                    _ => Err(Error::runtime(format!("{what} gives no TEMP at node {}", self.mesh.node_names[node]))),
                }
            })
            .collect()
    }

    /// The flux `−Λ∇T` at the integration points of every bulk cell (`FLUX_ELGA`) and at its nodes
    /// (`FLUX_ELNO`), the laws taken at `inst` and at each point's temperature.
    pub fn flux_fields(&self, temps: &[f64], inst: f64) -> Result<(Field, Field), Error> {
        let mesh = &*self.mesh;
        let dim = self.elements.iter().flatten().map(|(m, _)| m.dim()).max().unwrap_or(2);
        let names: Vec<String> = ["FLUX", "FLUY", "FLUZ"][..dim].iter().map(|s| s.to_string()).collect();
        let mut elga = vec![None; mesh.cells.len()];
        let mut elno = vec![None; mesh.cells.len()];
        for &c in &self.bulk {
            let (md, _) = self.elements[c].expect("a bulk cell has its element");
            let law = self.laws[c].as_ref().expect("a bulk cell has its law");
            let t = mesh.cell_types[c];
            let q = element::flux(md, t, &self.coords(c), &self.cell_temps(c, temps), &|tp| {
                law.conductivity(inst, tp).map_err(|e| ThermalError::Material(e.msg))
            })
            .map_err(cell_err(mesh, c))?;
            let pts: Vec<[f64; 3]> = q.iter().map(|(_, v)| *v).collect();
            elga[c] = Some(pts.iter().flat_map(|v| v[..dim].to_vec()).collect());
            elno[c] = Some(element::to_nodes(md, t, &pts).iter().flat_map(|v| v[..dim].to_vec()).collect());
        }
        Ok((Field::Elga { components: names.clone(), cells: elga }, Field::Elno { components: names, cells: elno }))
    }

    /// `SOUR_ELGA`, the heat that an electric potential computed as a temperature dissipates (Joule
    /// heating, Code_Aster's te0318): the flux `−λ∇T` averaged over the cell's `RIGI` points (a plain
    /// mean), and `|q̄|²/λ` at each point. Linear laws only (`THER`, `THER_FO`), as Code_Aster's.
    pub fn sour_elga(&self, temps: &[f64], inst: f64) -> Result<Field, Error> {
        let mesh = &*self.mesh;
        let mut cells = vec![None; mesh.cells.len()];
        for &c in &self.bulk {
            let (md, _) = self.elements[c].expect("a bulk cell has its element");
            let law = self.laws[c].as_ref().expect("a bulk cell has its law");
            let Law::Linear { lambda: Lambda::Iso(lambda), .. } = &**law else {
                return Err(Error::runtime(format!(
                    "cell {}: SOUR_ELGA takes a THER material (LAMBDA), not THER_NL or an orthotropic one",
                    mesh.cell_names[c]
                )));
            };
            let l = lambda.at(inst)?;
            let t = mesh.cell_types[c];
            let q = element::flux(md, t, &self.coords(c), &self.cell_temps(c, temps), &|_| Ok(Conductivity::Iso(l)))
                .map_err(cell_err(mesh, c))?;
            let n = q.len() as f64;
            let mean: [f64; 3] = std::array::from_fn(|k| q.iter().map(|(_, v)| v[k]).sum::<f64>() / n);
            let norm2: f64 = mean.iter().map(|v| v * v).sum();
            cells[c] = Some(vec![norm2 / l; q.len()]);
        }
        Ok(Field::Elga { components: vec!["SOUR".into()], cells })
    }

    /// The thermal energy of every bulk cell (`ETHE_ELEM`, component `TOTALE`), the law at `inst`. Linear
    /// laws only (`THER`, `THER_FO`, `THER_ORTH`), as Code_Aster's.
    pub fn energy(&self, temps: &[f64], inst: f64) -> Result<Field, Error> {
        let mesh = &*self.mesh;
        let mut cells = vec![None; mesh.cells.len()];
        for &c in &self.bulk {
            let (md, _) = self.elements[c].expect("a bulk cell has its element");
            let Law::Linear { lambda, .. } = &**self.laws[c].as_ref().expect("a bulk cell has its law") else {
                return Err(Error::runtime(format!(
                    "cell {}: ETHE_ELEM takes a THER or THER_ORTH material, not THER_NL",
                    mesh.cell_names[c]
                )));
            };
            let e =
                element::energy(md, mesh.cell_types[c], &self.coords(c), &self.cell_temps(c, temps), &lambda.at(inst)?)
                    .map_err(cell_err(mesh, c))?;
            cells[c] = Some(vec![e]);
        }
        Ok(Field::Elem { components: vec!["TOTALE".into()], cells })
    }

    /// The temperature at the integration points of every bulk cell (`TEMP_ELGA`).
    pub fn temp_elga(&self, temps: &[f64]) -> Result<Field, Error> {
        let mesh = &*self.mesh;
        let mut cells = vec![None; mesh.cells.len()];
        for &c in &self.bulk {
            let (md, _) = self.elements[c].expect("a bulk cell has its element");
            let t = mesh.cell_types[c];
            let pts = md.points(t, &self.coords(c), &md.rigi_rule(t)).map_err(cell_err(mesh, c))?;
            let te = self.cell_temps(c, temps);
            cells[c] = Some(pts.iter().map(|p| (0..te.len()).map(|i| p.n[i] * te[i]).sum()).collect());
        }
        Ok(Field::Elga { components: vec!["TEMP".into()], cells })
    }
}

impl Physics for Thermal {
    type State = HeatState;

    fn describe(&self) -> String {
        let kind = match self.theta {
            None => "steady".to_string(),
            Some(th) => format!("transient, θ = {th}"),
        };
        let law = if self.nonlinear() { "THER_NL" } else { "THER" };
        format!("{}, {law}, {kind}", self.modelisations().join(", "))
    }

    fn unknowns(&self) -> usize {
        self.numbering.ndofs()
    }

    fn label(&self, dof: usize) -> String {
        self.numbering.label(dof, Some(&self.mesh))
    }

    fn element_dofs(&self) -> ElementDofs {
        self.dofs.clone()
    }

    fn assemble(
        &self,
        step: &StepInfo,
        x: &[f64],
        prev: &HeatState,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> Result<HeatState, Failure> {
        let (steady, theta) = self.scheme(step);
        let dt = step.dt();
        let mut cap = if steady { Vec::new() } else { vec![0.0; x.len()] };
        if !steady {
            self.add_old_terms(step, theta, prev, fint)?;
        }
        for &c in &self.bulk {
            let dofs = self.cell_dofs(c);
            let ((kv, km), capacity) = self.cell_terms(c, x, step.t1, !steady)?;
            let mut je: Vec<f64> = km.iter().map(|v| theta * v).collect();
            for (i, &d) in dofs.iter().enumerate() {
                fint[d] += theta * kv[i];
            }
            if let Some((cv, cm)) = capacity {
                je.iter_mut().zip(cm.iter()).for_each(|(a, b)| *a += b / dt);
                for (i, &d) in dofs.iter().enumerate() {
                    fint[d] += cv[i] / dt;
                    cap[d] += cv[i];
                }
            }
            if let Some(asm) = tangent.as_deref_mut() {
                asm.add_matrix(&dofs, &je);
            }
        }
        Ok(HeatState { id: self.next_id(), temps: x.to_vec(), capacity: cap, heat: vec![0.0; x.len()] })
    }

    fn state_loads(
        &self,
        loads: &[Load],
        step: &StepInfo,
        x: &[f64],
        state: &mut HeatState,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> Result<(), Failure> {
        let (_, theta) = self.scheme(step);
        for load in loads {
            for item in load.forces.iter().filter(|f| depends_on_temperature(f)) {
                for term in self.terms(&load.name, item, x)? {
                    for (i, &d) in term.dofs.iter().enumerate() {
                        fint[d] -= theta * term.heat[i];
                        state.heat[d] += term.heat[i];
                    }
                    if let (Some(m), Some(asm)) = (&term.tangent, tangent.as_deref_mut()) {
                        asm.add_matrix(&term.dofs, &m.iter().map(|v| -theta * v).collect::<Vec<_>>());
                    }
                }
            }
        }
        Ok(())
    }

    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>, Error> {
        if component != "TEMP" {
            return Err(excit(format!("load {load}: component {component} on a thermal model (its unknown is TEMP)")));
        }
        self.numbering.dof(node, 0).map(Some).ok_or_else(|| {
            excit(format!("load {load}: node {} carries no element of the model", self.mesh.node_names[node]))
        })
    }

    fn position(&self, node: usize) -> [f64; 3] {
        self.mesh.coords[node]
    }

    fn node_name(&self, node: usize) -> String {
        self.mesh.node_names[node].clone()
    }

    fn forces(&self, loads: &[Load], step: &StepInfo, f: &mut [f64]) -> Result<(), Error> {
        let (_, theta) = self.scheme(step);
        let none = vec![0.0; f.len()];
        for load in loads {
            for item in load.forces.iter().filter(|f| !depends_on_temperature(f)) {
                for term in self.terms(&load.name, item, &none)? {
                    for (i, &d) in term.dofs.iter().enumerate() {
                        f[d] += theta * term.heat[i];
                    }
                }
            }
        }
        Ok(())
    }

    fn start_forces(&self, loads: &[Load], step: &StepInfo, x0: &[f64], f: &mut [f64]) -> Result<(), Error> {
        let (steady, theta) = self.scheme(step);
        if steady {
            return Ok(());
        }
        for load in loads {
            for item in &load.forces {
                for term in self.terms(&load.name, item, x0)? {
                    for (i, &d) in term.dofs.iter().enumerate() {
                        f[d] += (1.0 - theta) * term.heat[i];
                    }
                }
            }
        }
        Ok(())
    }

    fn fields(&self, x: &[f64], _state: &HeatState) -> Result<Vec<(String, Field)>, Error> {
        Ok(vec![("TEMP".to_string(), self.temp_field(x))])
    }

    fn prediction(&self) -> Prediction {
        Prediction::Tangent
    }

    fn linear(&self) -> bool {
        self.linear
    }

    /// Code_Aster's scale of THER_NON_LINE's RESI_GLOB_RELA: the largest over the unknowns of
    /// `|R_dual + C(T) − F_ext|`, with `F_ext` the loads' heat θ-weighted over the step, `C(T)` the
    /// capacity term (transient steps) and `R_dual` the reaction of the conditions (`−G` on the unknowns
    /// they fix).
    fn reference_at(&self, r: &Residual, trial: &HeatState) -> f64 {
        let theta = self.theta.unwrap_or(1.0);
        let mut scale = 0.0f64;
        for d in 0..r.fext.len() {
            let ext = r.fext[d] + theta * trial.heat.get(d).copied().unwrap_or(0.0);
            let cap = trial.capacity.get(d).copied().unwrap_or(0.0);
            let dual = if r.free[d] { 0.0 } else { r.fext[d] - r.fint[d] };
            scale = scale.max((dual + cap - ext).abs());
        }
        scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::physics::Condition;
    use crate::mesh::CellType;

    /// A strip of `n` QUAD4 cells on [0, 1] × [0, h] and the SEG2 skin of its right end.
    fn strip(n: usize, h: f64) -> (Rc<Mesh>, Vec<usize>, Vec<usize>) {
        let mut coords = Vec::new();
        for j in 0..2 {
            for i in 0..=n {
                coords.push([i as f64 / n as f64, j as f64 * h, 0.0]);
            }
        }
        let mut cells = Vec::new();
        let mut types = Vec::new();
        for i in 0..n {
            cells.push(vec![i, i + 1, n + 2 + i, n + 1 + i]);
            types.push(CellType::Quad4);
        }
        // The right end, a skin segment.
        cells.push(vec![n, 2 * n + 1]);
        types.push(CellType::Seg2);
        let mesh = Mesh {
            dim: 2,
            node_names: (0..coords.len()).map(|i| format!("N{}", i + 1)).collect(),
            cell_names: (0..cells.len()).map(|i| format!("M{}", i + 1)).collect(),
            coords,
            cells,
            cell_types: types,
            named_nodes: true,
            ..Default::default()
        };
        let left = vec![0, n + 1];
        let right = vec![n, 2 * n + 1];
        (Rc::new(mesh), left, right)
    }

    fn plan() -> Modelisation {
        Modelisation::from_name("PLAN").expect("PLAN")
    }

    fn problem(n: usize, theta: Option<f64>) -> (Thermal, Vec<usize>, Vec<usize>) {
        let (mesh, left, right) = strip(n, 0.1);
        let ncells = mesh.cells.len();
        let mut elements = vec![Some((plan(), true)); ncells];
        elements[ncells - 1] = Some((plan(), false));
        let law = Rc::new(Law::Linear { lambda: Lambda::Iso(Param::Real(2.0)), rho_cp: Some(Param::Real(3.0)) });
        let mut laws = vec![Some(law); ncells];
        laws[ncells - 1] = None;
        (Thermal::new(mesh, elements, laws, theta, true, &[]).expect("a problem"), left, right)
    }

    /// Steady conduction with a flux entering at one end and the other end held at 0: T = q (1 − x)/λ.
    #[test]
    fn steady_flux_gives_the_linear_profile() {
        let (p, left, _) = problem(4, None);
        let skin = [p.mesh.cells.len() - 1];
        let step = StepInfo::new(0.0, 0.0);
        let loads = vec![Load {
            name: "CH".into(),
            functional: false,
            conditions: left
                .iter()
                .map(|&n| Condition::Dof { node: n, component: "TEMP", value: Value::real(0.0) })
                .collect(),
            forces: vec![Force::HeatFlux { cells: &skin, value: Value::real(5.0) }],
        }];
        let mut f = vec![0.0; p.unknowns()];
        p.forces(&loads, &step, &mut f).expect("forces");
        // The flux times the segment's length (0.1), shared by its two nodes.
        assert!((f.iter().sum::<f64>() - 0.5).abs() < 1e-12);
        let mut cons = crate::fem::dofs::Constraints::new();
        p.conditions(&loads, &mut cons).expect("conditions");
        let map = crate::fem::dofs::DofMap::build(p.unknowns(), &cons).expect("a map");
        let pattern = crate::fem::assembly::SparsityPattern::build(&map, &p.element_dofs());
        let mut asm = Assembler::new(&map, pattern);
        let mut fint = vec![0.0; p.unknowns()];
        let x0 = vec![0.0; p.unknowns()];
        p.assemble(&step, &x0, &p.state(&x0), Some(&mut asm), &mut fint).expect("assembly");
        let all: Vec<usize> = (0..p.unknowns()).collect();
        asm.add_vector(&all, &f);
        let (k, rhs) = asm.finish();
        let sol = crate::solve::solve_with(k.as_ref(), &rhs, &Default::default(), &mut None).expect("a solve");
        let t = map.expand(&sol.x);
        for n in 0..p.mesh.nnodes() {
            let x = p.mesh.coords[n][0];
            let d = p.numbering.dof(n, 0).expect("numbered");
            assert!((t[d] - 5.0 * x / 2.0).abs() < 1e-10, "T({x}) = {}", t[d]);
        }
    }

    /// The θ-scheme's terms: with T⁻ = T uniform and no load, G(T) vanishes whatever θ and Δt.
    #[test]
    fn a_uniform_state_is_at_rest() {
        let (p, _, _) = problem(3, Some(0.57));
        let x = vec![7.0; p.unknowns()];
        let step = StepInfo::new(0.0, 0.5);
        let mut fint = vec![0.0; p.unknowns()];
        let st = p.assemble(&step, &x, &p.state(&x), None, &mut fint).expect("assembly");
        assert!(fint.iter().all(|g| g.abs() < 1e-12), "{fint:?}");
        // The capacity term is M T: its sum is ρCp T times the area (1 × 0.1).
        assert!((st.capacity.iter().sum::<f64>() - 3.0 * 7.0 * 0.1).abs() < 1e-12);
    }
}
