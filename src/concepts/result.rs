//! Results (`evol_elas`, `evol_noli`) and the fields they hold.

use super::ConceptRef;
use crate::diag::{Error, Result};
use std::collections::BTreeMap;

pub use crate::fem::field::Field;

/// A field of its own (`cham_no`, `cham_elem`: CREA_CHAMP): its values on the
/// cells or nodes of a mesh (the mesh concept, whose current content gives
/// names and groups) and, for a field of functions (`*_NEUT_F`, `NOEU_TEMP_F`, ...), the function of
/// each place — cell, or node for a field on nodes — and component (None: the zero function of
/// PROL_ZERO), `field` then holding NaN: its values are computed where it is used (CREA_CHAMP EVAL,
/// CREA_RESU).
#[derive(Debug, Clone)]
pub struct FieldData {
    pub mesh_concept: ConceptRef,
    pub field: Field,
    pub functions: Option<Vec<Option<Vec<Option<ConceptRef>>>>>,
}

impl FieldData {
    /// The values of a field of reals; a field of functions, which has none, is an error naming it
    /// (`label`).
    pub fn reals(&self, label: &str) -> Result<&Field> {
        match self.functions {
            None => Ok(&self.field),
            Some(_) => Err(Error::runtime(format!(
                "{label} is a field of functions: its values are known only where it is evaluated \
                 (CREA_CHAMP OPERATION='EVAL', CREA_RESU); a field of reals is expected here"
            ))),
        }
    }
}

/// One stored step of a result.
#[derive(Debug, Clone)]
pub struct Step {
    pub nume_ordre: i64,
    pub inst: f64,
    pub fields: BTreeMap<String, Field>,
}

#[derive(Debug)]
pub struct ResultData {
    pub model: ConceptRef,
    pub material: Option<ConceptRef>,
    /// The element characteristics it was computed with (AFFE_CARA_ELEM).
    pub cara_elem: Option<ConceptRef>,
    pub loads: Vec<ConceptRef>,
    pub steps: Vec<Step>,
    /// COMPORTEMENT of the command that computed it (STAT_NON_LINE): each relation and the cells it
    /// covers (None: the whole model), in order, a later one over an earlier one; empty when unknown.
    pub comportement: Vec<(String, Option<Vec<usize>>)>,
}

impl ResultData {
    /// The same result (model, material, characteristics, loads) with other steps: what a command that
    /// adds fields to a result's steps (CALC_CHAMP) produces.
    pub fn with_steps(&self, steps: Vec<Step>) -> ResultData {
        ResultData {
            model: self.model.clone(),
            material: self.material.clone(),
            cara_elem: self.cara_elem.clone(),
            loads: self.loads.clone(),
            steps,
            comportement: self.comportement.clone(),
        }
    }

    /// The step with this order number.
    pub fn by_order(&self, n: i64) -> Option<&Step> {
        self.steps.iter().find(|s| s.nume_ordre == n)
    }
    /// The step at this time, within a relative tolerance.
    pub fn by_inst(&self, t: f64, rel: f64) -> Option<&Step> {
        self.steps.iter().find(|s| (s.inst - t).abs() <= rel * t.abs().max(1e-300) || s.inst == t)
    }
}
