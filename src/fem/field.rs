//! Fields of values on a mesh: per node, per cell node, per integration point or per cell — what a
//! physics computes from a state and what results store.

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
