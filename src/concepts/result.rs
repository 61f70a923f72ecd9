//! Results (`evol_elas`, `evol_noli`) and the fields they hold.

use super::ConceptRef;
use std::collections::BTreeMap;

/// Where a field's values live.
#[derive(Debug, Clone, PartialEq)]
pub enum Field {
    /// One value per node and component (`*_NOEU`, `DEPL`): `values[node * ncmp + k]`;
    /// NaN where a node does not carry the component.
    Node { components: Vec<String>, values: Vec<f64> },
    /// Per cell, one value per cell node and component (`*_ELNO`): `cells[c][i * ncmp + k]`.
    Elno { components: Vec<String>, cells: Vec<Option<Vec<f64>>> },
    /// Per cell, one value per Gauss point and component (`*_ELGA`): `cells[c][g * ncmp + k]`.
    Elga { components: Vec<String>, cells: Vec<Option<Vec<f64>>> },
    /// Per cell, one value per component (`*_ELEM`).
    Elem { components: Vec<String>, cells: Vec<Option<Vec<f64>>> },
}

impl Field {
    pub fn components(&self) -> &[String] {
        match self {
            Field::Node { components, .. }
            | Field::Elno { components, .. }
            | Field::Elga { components, .. }
            | Field::Elem { components, .. } => components,
        }
    }
    pub fn component(&self, name: &str) -> Option<usize> {
        self.components().iter().position(|c| c == name)
    }
    /// Every finite value of a component over the whole field (TYPE_TEST).
    pub fn all_values(&self, k: usize) -> Vec<f64> {
        let n = self.components().len();
        let pick = |v: &[f64]| v.iter().skip(k).step_by(n).copied().filter(|x| x.is_finite()).collect::<Vec<_>>();
        match self {
            Field::Node { values, .. } => pick(values),
            Field::Elno { cells, .. } | Field::Elga { cells, .. } | Field::Elem { cells, .. } => {
                cells.iter().flatten().flat_map(|v| pick(v)).collect()
            }
        }
    }
}

/// A field of its own (`cham_no`, `cham_elem`: CREA_CHAMP): its values on the
/// cells or nodes of a mesh (the mesh concept, whose current content gives
/// names and groups) and, for a field of functions (`*_NEUT_F`), the function of each
/// cell and component (None: the zero function of PROL_ZERO), `field` then
/// holding NaN.
#[derive(Debug, Clone)]
pub struct FieldData {
    pub mesh_concept: ConceptRef,
    pub field: Field,
    pub functions: Option<Vec<Option<Vec<Option<ConceptRef>>>>>,
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
    pub loads: Vec<ConceptRef>,
    pub steps: Vec<Step>,
}

impl ResultData {
    /// The step with this order number.
    pub fn by_order(&self, n: i64) -> Option<&Step> {
        self.steps.iter().find(|s| s.nume_ordre == n)
    }
    /// The step at this time, within a relative tolerance.
    pub fn by_inst(&self, t: f64, rel: f64) -> Option<&Step> {
        self.steps.iter().find(|s| (s.inst - t).abs() <= rel * t.abs().max(1e-300) || s.inst == t)
    }
}
