//! Node fields over time steps (`/CHA`), e.g. DEPL.

use super::cellfield::{read_field, write_fields, Block, FieldStep, MedField, Support};
use super::{h5err, open_read};
use crate::diag::Result;
use std::path::Path;

/// A node field read back from a MED file.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeField {
    pub mesh_name: String,
    pub components: Vec<String>,
    /// `(numdt, time, values)`, values interlaced per node
    /// (node 0 all components, node 1, ...), in step order.
    pub steps: Vec<(i32, f64, Vec<f64>)>,
}

/// Append a real node field with one value per node and component at each
/// step to a MED file that already holds mesh `mesh_name`. `steps` holds
/// `(numdt, time, values interlaced per node)`. If the field exists, the
/// steps are added to it (components must match; a step may not repeat).
/// The file is updated through a temporary copy renamed into place.
pub fn write_node_field(
    path: &Path,
    mesh_name: &str,
    field_name: &str,
    components: &[&str],
    steps: &[(i32, f64, Vec<f64>)],
) -> Result<()> {
    let nco = components.len().max(1);
    let field = MedField {
        name: field_name.to_string(),
        mesh_name: mesh_name.to_string(),
        components: components.iter().map(|c| c.to_string()).collect(),
        steps: steps
            .iter()
            .map(|(numdt, time, values)| FieldStep {
                numdt: *numdt,
                numit: -1,
                time: *time,
                blocks: vec![Block {
                    support: Support::Node,
                    cell: None,
                    localization: None,
                    per_entity: 1,
                    entities: (0..values.len() / nco).collect(),
                    values: values.clone(),
                }],
            })
            .collect(),
    };
    let file = open_read(path)?;
    let (nn, _) = super::cellfield::entity_counts(path, &file, mesh_name)?;
    drop(file);
    for (numdt, _, values) in steps {
        if values.len() != nn * components.len() {
            return Err(super::ioerr(
                path,
                format!(
                    "field '{field_name}' step {numdt}: {} values for {nn} nodes x {} components",
                    values.len(),
                    components.len()
                ),
            ));
        }
    }
    write_fields(path, &[field], &[])
}

/// Read a real node field (node values without profile; steps without node
/// values are passed over).
pub fn read_node_field(path: &Path, field_name: &str) -> Result<NodeField> {
    let f = read_field(path, field_name)?;
    let nco = f.components.len().max(1);
    let mut steps = Vec::new();
    for st in f.steps {
        let Some(b) = st.blocks.into_iter().find(|b| b.support == Support::Node) else { continue };
        let nn = b.entities.iter().max().map_or(0, |m| m + 1).max(b.entities.len());
        let mut values = vec![f64::NAN; nn * nco];
        for (i, &n) in b.entities.iter().enumerate() {
            values[n * nco..(n + 1) * nco].copy_from_slice(&b.values[i * nco..(i + 1) * nco]);
        }
        steps.push((st.numdt, st.time, values));
    }
    Ok(NodeField { mesh_name: f.mesh_name, components: f.components, steps })
}

/// Names of the fields stored in a MED file (`/CHA`), sorted.
pub fn list_fields(path: &Path) -> Result<Vec<String>> {
    let file = open_read(path)?;
    if !file.link_exists("CHA") {
        return Ok(Vec::new());
    }
    let cha = file.group("CHA").map_err(|e| h5err(path, "group /CHA", e))?;
    let mut names = cha.member_names().map_err(|e| h5err(path, "listing /CHA", e))?;
    names.sort();
    Ok(names)
}
