//! The seam between the solving core and a physics.
//!
//! A physics (linear elasticity, saturated hydro-mechanics, an X-FEM model with its cohesive interfaces,
//! heat) says what its unknowns are, how its elements and loads assemble, what its laws' internal
//! variables are and which fields a state gives; the core (`stages::core::driver`) owns everything else:
//! the instants and the cutting of a failed step, the kinematic conditions turned into a reduced system,
//! the prediction and the Newton corrections with Code_Aster's convergence test, the solver and the
//! archiving. A physics knows no command, concept or file: its loads reach it as the typed items of this
//! module, their values already evaluated at the instant (a function of the position where the value is
//! a field), and its errors name the keyword they belong to ([`Error::at_keyword`]), which the core
//! locates.

use super::assembly::{Assembler, ElementDofs};
use super::dofs::Constraints;
use super::field::Field;
use crate::diag::Error;

/// A function of the position.
type OfPosition<'a> = Box<dyn Fn(&[f64; 3]) -> crate::diag::Result<f64> + 'a>;

/// A function of the position and the temperature, with its derivative in the temperature (FLUX_NL,
/// SOUR_NL): `(value, ∂value/∂T)`.
pub type OfTemperature<'a> = Box<dyn Fn(&[f64; 3], f64) -> crate::diag::Result<(f64, f64)> + 'a>;

/// A value of a load at the instant (its multiplier applied), as a function of the position.
pub struct Value<'a> {
    /// The value where it does not depend on the position (a real).
    pub constant: Option<f64>,
    /// The identity of the function it evaluates (the same for every item that names that function).
    pub function: Option<usize>,
    eval: OfPosition<'a>,
}

impl<'a> Value<'a> {
    /// A real value.
    pub fn real(v: f64) -> Value<'a> {
        Value { constant: Some(v), function: None, eval: Box::new(move |_| Ok(v)) }
    }

    /// A function of the position, `id` its identity.
    pub fn function(id: usize, f: impl Fn(&[f64; 3]) -> crate::diag::Result<f64> + 'a) -> Value<'a> {
        Value { constant: None, function: Some(id), eval: Box::new(f) }
    }

    /// The value at a point.
    pub fn at(&self, x: &[f64; 3]) -> crate::diag::Result<f64> {
        (self.eval)(x)
    }
}

/// One load of the computation at an instant: its name for messages, its kinematic conditions and its
/// external forces.
pub struct Load<'a> {
    pub name: String,
    /// Its values are functions (AFFE_CHAR_MECA_F).
    pub functional: bool,
    pub conditions: Vec<Condition<'a>>,
    pub forces: Vec<Force<'a>>,
}

/// A kinematic condition of a load at an instant.
pub enum Condition<'a> {
    /// A component of a node prescribed (DDL_IMPO, TEMP_IMPO): the value as a function of the position,
    /// so that a physics whose unknowns are enriched may evaluate it on each side of an interface.
    Dof { node: usize, component: &'a str, value: Value<'a> },
    /// Σ coef · u(node, component) = value (LIAISON_DDL), the value taken at the origin.
    Relation { terms: &'a [(usize, String, f64)], value: Value<'a> },
}

/// An external force of a load at an instant (the load's multiplier applied).
pub enum Force<'a> {
    /// A force on a component of a node (FORCE_NODALE), the value taken at the node.
    Nodal { node: usize, component: &'a str, value: Value<'a> },
    /// A force per unit measure on skin cells (FORCE_CONTOUR, FORCE_FACE): its components by name.
    Surface { cells: &'a [usize], components: Vec<(&'a str, Value<'a>)> },
    /// A pressure on skin cells (PRES_REP), and in the plane a shear along the tangent `(−n_y, n_x)`
    /// (CISA_2D).
    Pressure { cells: &'a [usize], value: Value<'a>, shear: Option<Value<'a>> },
    /// A pressure on both lips of an X-FEM crack of the model (PRES_REP with FISSURE): its index, its name.
    LipPressure { crack: usize, name: &'a str, value: Value<'a> },
    /// Gravity of magnitude `g` along `direction` on the cells (all of the model's when None).
    Gravity { g: f64, direction: [f64; 3], cells: Option<&'a [usize]> },
    /// A fluid mass flux entering through skin cells (FLUX_THM_REP FLUN_HYDR1), or with `heat` the heat
    /// flux entering a THM model (FLUX_THM_REP FLUN), both per unit time.
    Flux { cells: &'a [usize], value: Value<'a>, heat: bool },
    /// A heat flux density entering through skin cells (FLUX_REP FLUN).
    HeatFlux { cells: &'a [usize], value: Value<'a> },
    /// A heat flux vector φ on skin cells, whose density there is φ · n (FLUX_REP FLUX_X FLUX_Y FLUX_Z).
    HeatFluxVector { cells: &'a [usize], components: [Option<Value<'a>>; 3] },
    /// A heat source per unit volume on bulk cells (SOURCE SOUR).
    HeatSource { cells: &'a [usize], value: Value<'a> },
    /// An exchange `h (T_ext − T)` through skin cells (ECHANGE): the multiplier scales `T_ext` only.
    Exchange { cells: &'a [usize], coef_h: Value<'a>, temp_ext: Value<'a> },
    /// Radiation `σ ε ((T_ext + 273.15)⁴ − (T + 273.15)⁴)` through skin cells (RAYONNEMENT).
    Radiation { cells: &'a [usize], sigma: Value<'a>, epsilon: Value<'a>, temp_ext: Value<'a> },
    /// A heat flux density entering through skin cells, a function of the temperature (FLUX_NL).
    HeatFluxOfTemperature { cells: &'a [usize], flux: OfTemperature<'a> },
    /// A heat source, a function of the temperature (SOUR_NL).
    HeatSourceOfTemperature { cells: &'a [usize], source: OfTemperature<'a> },
    /// An exchange `h (T₂ − T₁)` between paired walls (ECHANGE_PAROI): each pair a skin cell and the nodes
    /// facing its nodes, in its node order.
    WallExchange { pairs: &'a [(usize, Vec<usize>)], coef_h: Value<'a> },
}

impl Force<'_> {
    /// The keyword of AFFE_CHAR_MECA this force comes from, for messages.
    pub fn keyword(&self) -> &'static str {
        match self {
            Force::Nodal { .. } => "FORCE_NODALE",
            Force::Surface { .. } => "FORCE_CONTOUR/FORCE_FACE",
            Force::Pressure { .. } => "PRES_REP",
            Force::LipPressure { .. } => "PRES_REP (FISSURE)",
            Force::Gravity { .. } => "PESANTEUR",
            Force::Flux { .. } => "FLUX_THM_REP",
            Force::HeatFlux { .. } | Force::HeatFluxVector { .. } => "FLUX_REP",
            Force::HeatSource { .. } => "SOURCE",
            Force::Exchange { .. } => "ECHANGE",
            Force::Radiation { .. } => "RAYONNEMENT",
            Force::HeatFluxOfTemperature { .. } => "FLUX_NL",
            Force::HeatSourceOfTemperature { .. } => "SOUR_NL",
            Force::WallExchange { .. } => "ECHANGE_PAROI",
        }
    }
}

/// One time step as a physics sees it.
#[derive(Debug, Clone, Copy)]
pub struct StepInfo {
    pub t0: f64,
    pub t1: f64,
    /// The assembly of the prediction ([`Prediction::Tangent`]: Code_Aster's `RIGI_MECA_TANG`), at the
    /// state of the step's start: a law whose tangent there depends on its history uses it.
    pub predict: bool,
}

impl StepInfo {
    /// The step from `t0` to `t1` (not the prediction).
    pub fn new(t0: f64, t1: f64) -> StepInfo {
        StepInfo { t0, t1, predict: false }
    }

    pub fn dt(&self) -> f64 {
        self.t1 - self.t0
    }
}

/// Why a state could not be computed: a failure of the step, which DEFI_LIST_INST may answer by
/// cutting it (no convergence, an integration failure, a singular tangent), or an error that ends the run.
#[derive(Debug)]
pub enum Failure {
    Step(Error),
    Fatal(Error),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Fatal(e)
    }
}

/// How the core starts the Newton corrections of a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prediction {
    /// Code_Aster's PREDICTION='TANGENTE': the tangent and internal forces of the start state, with the
    /// increments the conditions prescribe; its result is tested like every later iteration (Code_Aster's
    /// iteration 0).
    Tangent,
    /// The prescribed values put in the start state, then corrections (at least one).
    Imposed,
}

/// What the reference force of the relative criterion is made of at a state.
pub struct Residual<'a> {
    /// The external forces of the step, on every unknown.
    pub fext: &'a [f64],
    /// The internal forces at the state, on every unknown.
    pub fint: &'a [f64],
    /// Whether each unknown is free (not eliminated by a condition).
    pub free: &'a [bool],
    /// The state at the start of the step and now.
    pub x0: &'a [f64],
    pub x: &'a [f64],
}

/// The traction of FORCE_FACE / FORCE_CONTOUR components (`FX`, `FY`, `FZ`) at a point.
pub fn traction(components: &[(&str, Value)], x: &[f64; 3]) -> Result<[f64; 3], Error> {
    let mut v = [0.0; 3];
    for (cn, val) in components {
        let k = ["FX", "FY", "FZ"].iter().position(|s| s == cn).unwrap_or(2);
        v[k] = val.at(x)?;
    }
    Ok(v)
}

/// The value of `r`, or the default with the first error kept in `err`: for callbacks of the element
/// routines, which cannot return an error (the caller returns the kept one after the call).
pub fn keep<T: Default>(err: &std::cell::RefCell<Option<Error>>, r: Result<T, Error>) -> T {
    r.unwrap_or_else(|e| {
        err.borrow_mut().get_or_insert(e);
        T::default()
    })
}

/// A physics as the solving core drives it.
pub trait Physics {
    /// The laws' internal variables at every point of the model, committed when a step converges.
    type State: Clone;

    /// What is simulated, for the run log (`D_PLAN, RELATION='ELAS'`, ...).
    fn describe(&self) -> String;

    /// The number of unknowns.
    fn unknowns(&self) -> usize;

    /// The name of an unknown for messages (`N12 DX`).
    fn label(&self, dof: usize) -> String;

    /// The unknowns of every element, which make the pattern of the tangent.
    fn element_dofs(&self) -> ElementDofs;

    /// The internal forces at the state `x` over `step`, from the laws' state `prev` at its start, added
    /// to `fint`; the tangent added to `tangent` when asked; the laws' trial state.
    fn assemble(
        &self,
        step: &StepInfo,
        x: &[f64],
        prev: &Self::State,
        tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> Result<Self::State, Failure>;

    /// The kinematic conditions of the loads at an instant on the unknowns. The default prescribes each
    /// named component of each node ([`Physics::dof`]) at the node's value.
    fn conditions(&self, loads: &[Load], cons: &mut Constraints) -> Result<(), Error> {
        for load in loads {
            for item in &load.conditions {
                match item {
                    Condition::Dof { node, component, value } => {
                        if let Some(d) = self.dof(&load.name, *node, component)? {
                            cons.impose(d, value.at(&self.position(*node))?);
                        }
                    }
                    Condition::Relation { terms, value } => {
                        let mut t = Vec::with_capacity(terms.len());
                        for (node, comp, coef) in terms.iter() {
                            let d = self.dof(&load.name, *node, comp)?.ok_or_else(|| {
                                Error::runtime(format!(
                                    "load {}: node {} carries no {comp}",
                                    load.name,
                                    self.node_name(*node)
                                ))
                                .at_keyword("EXCIT")
                            })?;
                            t.push((d, *coef));
                        }
                        cons.relation(t, value.at(&[0.0; 3])?);
                    }
                }
            }
        }
        Ok(())
    }

    /// The unknown of component `component` of `node`, for a condition of load `load`; None for a
    /// component the node does not carry and that the physics passes over (as Code_Aster's `afddli` does);
    /// an error naming the component or the node otherwise.
    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>, Error>;

    /// The position of a node and its name, for conditions and messages.
    fn position(&self, node: usize) -> [f64; 3];
    fn node_name(&self, node: usize) -> String;

    /// The external forces of the loads over the step, added to `f` (`loads` at its end).
    fn forces(&self, loads: &[Load], step: &StepInfo, f: &mut [f64]) -> Result<(), Error>;

    /// What the loads at the step's start bring to its external forces, from the start state `x0`
    /// (`loads` at `step.t0`; a θ-scheme's `(1 − θ)` part). None by default.
    fn start_forces(&self, _loads: &[Load], _step: &StepInfo, _x0: &[f64], _f: &mut [f64]) -> Result<(), Error> {
        Ok(())
    }

    /// The loads whose forces depend on the state (an exchange `h (T_ext − T)`, radiation): at the state
    /// `x` (`loads` at the step's end), subtracted from `fint` (they are internal forces of the
    /// equations), their tangent added to `tangent` when asked, recorded in the trial `state` as the
    /// physics needs. None by default.
    fn state_loads(
        &self,
        _loads: &[Load],
        _step: &StepInfo,
        _x: &[f64],
        _state: &mut Self::State,
        _tangent: Option<&mut Assembler>,
        _fint: &mut [f64],
    ) -> Result<(), Failure> {
        Ok(())
    }

    /// The fields of a state.
    fn fields(&self, x: &[f64], state: &Self::State) -> Result<Vec<(String, Field)>, Error>;

    /// How a step's corrections start.
    fn prediction(&self) -> Prediction {
        Prediction::Tangent
    }

    /// Linear: one correction per step, no convergence test (MECA_STATIQUE).
    fn linear(&self) -> bool {
        false
    }

    /// The reference force of the relative criterion (RESI_GLOB_RELA) at a state: the largest of the
    /// external forces on the free equations and the reactions of the eliminated ones, as Code_Aster's
    /// `nmresi`.
    fn reference(&self, r: &Residual) -> f64 {
        let mut scale = 0.0f64;
        for d in 0..r.fext.len() {
            scale = scale.max(if r.free[d] { r.fext[d].abs() } else { r.fint[d].abs() });
        }
        scale
    }

    /// The reference force at a state with its laws' trial state (by default [`Physics::reference`]).
    fn reference_at(&self, r: &Residual, _trial: &Self::State) -> f64 {
        self.reference(r)
    }

    /// The factorization to use for a reduced tangent of `n` unknowns, when the physics has a preference
    /// (None: the settings' SOLVEUR).
    fn solver_method(&self, _n: usize) -> Option<crate::solve::Method> {
        None
    }

    /// What the run log says of a converged state, after the step's line (the state of cohesive
    /// interfaces, ...).
    fn step_report(&self, _x: &[f64], _state: &Self::State) -> String {
        String::new()
    }

    /// Whether the relative criterion falls back on the largest reference force of the earlier steps
    /// when the reactions vanish (a fully broken interface leaves nothing to refer to).
    fn reference_memory(&self) -> bool {
        false
    }

    /// Whether the relative criterion gives way to the absolute one when the reference force falls to
    /// 1e-6 of the smallest one of the converged states (after the first step), with the absolute residual
    /// of the last converged state as its tolerance: Code_Aster's mechanics (`nmcore_swap`), for steps
    /// where the loads and the reactions vanish.
    fn swaps_to_absolute(&self) -> bool {
        false
    }

    /// A factor on the rows of unknown `dof` before the factorization, which may make the tangent
    /// symmetric (1 by default). It changes neither the solution nor the residual Newton tests.
    fn row_scale(&self, _dof: usize) -> f64 {
        1.0
    }
}
