//! The load pipeline every physics shares: the loads of EXCIT (AFFE_CHAR_MECA(_F), AFFE_CHAR_THER(_F) items, their mesh
//! entities already resolved) at an instant, their multiplier FONC_MULT applied and their values made
//! functions of the position, handed to the physics as typed items ([`fem::physics::Load`]); the
//! conditions come back as constraints on the unknowns, the forces as a vector on them.

use super::eval::eval_at;
use super::heat::of_temperature;
use super::settings::Settings;
use crate::concepts::model::HeatItem;
use crate::concepts::model::{Load as LoadConcept, LoadItem, LoadValue};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::dofs::Constraints;
use crate::fem::physics::{Condition, Force, Load, Physics, StepInfo, Value};

/// The loads of a computation.
pub struct Loads<'a> {
    cfg: &'a Settings,
}

impl<'a> Loads<'a> {
    pub fn new(cfg: &'a Settings) -> Self {
        Loads { cfg }
    }

    /// The multiplier of each load of EXCIT at `t` (FONC_MULT, 1 without).
    fn multipliers(&self, t: f64) -> Result<Vec<f64>> {
        self.cfg
            .excit
            .iter()
            .map(|e| match &e.fonc_mult {
                Some(f) => eval_at(f, &[0.0; 3], t).map_err(|err| err.at(e.fonc_mult_span)),
                None => Ok(1.0),
            })
            .collect()
    }

    /// Hand the loads at `t` to `f`, as the typed items a physics reads.
    pub fn with<R>(&self, t: f64, f: impl FnOnce(&[Load]) -> Result<R>) -> Result<R> {
        let mults = self.multipliers(t)?;
        let guards: Vec<_> = self.cfg.excit.iter().map(|e| e.load.data()).collect();
        let mut loads = Vec::with_capacity(guards.len());
        for ((g, e), &mult) in guards.iter().zip(&self.cfg.excit).zip(&mults) {
            let ConceptData::Load(LoadConcept { items, functional, .. }) = &**g else {
                unreachable!("the settings checked that EXCIT holds loads")
            };
            loads
                .push(typed(e.load.label(), *functional, items, t, mult).map_err(|err| self.cfg.locate(err, "EXCIT"))?);
        }
        f(&loads)
    }

    /// The kinematic conditions of the loads at `t` on the physics' unknowns.
    pub fn conditions<P: Physics>(&self, phys: &P, t: f64) -> Result<Constraints> {
        self.with(t, |loads| {
            let mut cons = Constraints::new();
            phys.conditions(loads, &mut cons).map_err(|e| self.cfg.place(e))?;
            Ok(cons)
        })
    }

    /// The external forces of the loads over `step` from the start state `x0` on the physics' unknowns:
    /// their values at its end, and what the physics takes of those at its start.
    pub fn forces<P: Physics>(&self, phys: &P, step: &StepInfo, x0: &[f64]) -> Result<Vec<f64>> {
        let mut f = self.with(step.t1, |loads| {
            let mut f = vec![0.0; phys.unknowns()];
            phys.forces(loads, step, &mut f).map_err(|e| self.cfg.place(e))?;
            Ok(f)
        })?;
        if step.t0 != step.t1 {
            self.with(step.t0, |loads| phys.start_forces(loads, step, x0, &mut f).map_err(|e| self.cfg.place(e)))?;
        }
        Ok(f)
    }
}

/// A load value at `t` times `mult`, as a function of the position.
fn value<'v>(v: &'v LoadValue, t: f64, mult: f64) -> Value<'v> {
    match v {
        LoadValue::Real(r) => Value::real(mult * r),
        LoadValue::Func(f) => {
            Value::function(std::rc::Rc::as_ptr(f) as usize, move |x| eval_at(f, x, t).map(|y| mult * y))
        }
    }
}

/// The items of one load at `t`, its multiplier applied.
fn typed<'v>(name: String, functional: bool, items: &'v [LoadItem], t: f64, mult: f64) -> Result<Load<'v>> {
    let mut conditions = Vec::new();
    let mut forces = Vec::new();
    for item in items {
        match item {
            LoadItem::Dof { node, component, value: v } => {
                conditions.push(Condition::Dof { node: *node, component, value: value(v, t, mult) })
            }
            LoadItem::Relation { terms, value: v } => {
                conditions.push(Condition::Relation { terms, value: value(v, t, mult) })
            }
            LoadItem::NodalForce { node, component, value: v } => {
                forces.push(Force::Nodal { node: *node, component, value: value(v, t, mult) })
            }
            LoadItem::SurfaceForce { cells, components } => forces.push(Force::Surface {
                cells,
                components: components.iter().map(|(c, v)| (c.as_str(), value(v, t, mult))).collect(),
            }),
            LoadItem::Pressure { cells, value: v, shear } => forces.push(Force::Pressure {
                cells,
                value: value(v, t, mult),
                shear: shear.as_ref().map(|s| value(s, t, mult)),
            }),
            LoadItem::CrackPressure { crack, name, value: v } => {
                forces.push(Force::LipPressure { crack: *crack, name, value: value(v, t, mult) })
            }
            LoadItem::Gravity { g, direction, cells } => {
                forces.push(Force::Gravity { g: mult * g, direction: *direction, cells: cells.as_deref() })
            }
            LoadItem::FluxThm { cells, value: v, heat } => {
                forces.push(Force::Flux { cells, value: value(v, t, mult), heat: *heat })
            }
            LoadItem::Heat(h) => forces.push(heat(h, t, mult)?),
        }
    }
    Ok(Load { name, functional, conditions, forces })
}

/// A heat item of AFFE_CHAR_THER(_F) at `t`: the multiplier scales what does not depend on the
/// temperature (a flux, a source, the exterior temperature of an exchange).
fn heat<'v>(h: &'v HeatItem, t: f64, mult: f64) -> Result<Force<'v>> {
    Ok(match h {
        HeatItem::NormalFlux { cells, value: v } => Force::HeatFlux { cells, value: value(v, t, mult) },
        HeatItem::FluxVector { cells, components } => Force::HeatFluxVector {
            cells,
            components: [0, 1, 2].map(|k| components[k].as_ref().map(|v| value(v, t, mult))),
        },
        HeatItem::Source { cells, value: v } => Force::HeatSource { cells, value: value(v, t, mult) },
        HeatItem::Exchange { cells, coef_h, temp_ext } => {
            Force::Exchange { cells, coef_h: value(coef_h, t, 1.0), temp_ext: value(temp_ext, t, mult) }
        }
        HeatItem::Radiation { cells, sigma, epsilon, temp_ext } => Force::Radiation {
            cells,
            sigma: value(sigma, t, 1.0),
            epsilon: value(epsilon, t, 1.0),
            temp_ext: value(temp_ext, t, 1.0),
        },
        HeatItem::NonlinearFlux { cells, flux } => {
            Force::HeatFluxOfTemperature { cells, flux: of_temperature(flux, "FLUX_NL/FLUN", t)? }
        }
        HeatItem::NonlinearSource { cells, source } => {
            Force::HeatSourceOfTemperature { cells, source: of_temperature(source, "SOUR_NL/SOUR", t)? }
        }
        HeatItem::WallExchange { pairs, coef_h } => Force::WallExchange { pairs, coef_h: value(coef_h, t, 1.0) },
    })
}
