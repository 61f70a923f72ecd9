//! The MED blocks of a result's fields: node fields, and cell fields at the nodes of cells (ELNO), at
//! integration points (ELGA, with Code_Aster's localizations) and constant on cells (ELEM), on the whole
//! mesh or on a selection of it (MED profiles).

use crate::concepts::model::Model;
use crate::concepts::result::Field;
use crate::fem::quadrature::{aster_families, aster_rule};
use crate::fem::reference::node_coords;
use crate::med::cellfield::cells_by_type;
use crate::med::{Block, Localization, Support};
use crate::mesh::Mesh;
use crate::stages::core::hm::elga_family;

/// The part of the mesh an occurrence prints: every node and cell, or the nodes of GROUP_NO / NOEUD and
/// of the cells of GROUP_MA / MAILLE, and those cells (Code_Aster's `irtopo`).
pub struct Selection {
    pub nodes: Option<Vec<bool>>,
    pub cells: Option<Vec<bool>>,
}

impl Selection {
    pub fn all() -> Selection {
        Selection { nodes: None, cells: None }
    }

    fn node(&self, n: usize) -> bool {
        self.nodes.as_ref().is_none_or(|v| v[n])
    }

    fn cell(&self, c: usize) -> bool {
        self.cells.as_ref().is_none_or(|v| v[c])
    }
}

/// The localization of the points of an ELGA field with `npts` points on cell `c`: the points of the
/// cell's element in the model, else (a field without model, or another count) Code_Aster's first family
/// of that many points on the cell's type.
fn localization_of(model: Option<&Model>, mesh: &Mesh, c: usize, npts: usize) -> Result<Localization, String> {
    let t = mesh.cell_types[c];
    let from_model = model
        .and_then(|m| m.elements.get(c))
        .and_then(|e| e.as_ref())
        .and_then(|e| elga_family(e.modelisation, t).ok());
    let (family, rule) = match from_model.filter(|(_, r)| r.len() == npts) {
        Some(x) => x,
        None => aster_families(t)
            .iter()
            .filter_map(|f| aster_rule(t, f).map(|r| (f.to_string(), r)))
            .find(|(_, r)| r.len() == npts)
            .ok_or_else(|| {
                format!(
                    "cell {} ({}): no family of {npts} integration points is known there",
                    mesh.cell_names[c],
                    t.name()
                )
            })?,
    };
    Ok(Localization {
        name: Localization::aster_name(t, &family),
        cell: t,
        ref_nodes: node_coords(t).to_vec(),
        points: rule.points,
        weights: rule.weights,
    })
}

/// The blocks of one field at one step: the components `picked` (indices into the field's components)
/// on the selection. Localizations the blocks name are added to `locs`. A node that carries none of
/// the picked components and a cell without values are left out (a profile); a component a node lacks
/// is written as 0, as Code_Aster's `ircmpn` does.
pub fn blocks_of(
    field: &Field,
    mesh: &Mesh,
    model: Option<&Model>,
    picked: &[usize],
    sel: &Selection,
    locs: &mut Vec<Localization>,
) -> Result<Vec<Block>, String> {
    let nco = field.components().len();
    let mut blocks = Vec::new();
    match field {
        Field::Node { values, .. } => {
            if values.len() != mesh.nnodes() * nco {
                return Err(format!("{} values for {} nodes x {nco} components", values.len(), mesh.nnodes()));
            }
            let mut entities = Vec::new();
            let mut v = Vec::new();
            for n in 0..mesh.nnodes() {
                let row = &values[n * nco..(n + 1) * nco];
                if !sel.node(n) || !picked.iter().any(|&k| row[k].is_finite()) {
                    continue;
                }
                entities.push(n);
                v.extend(picked.iter().map(|&k| if row[k].is_finite() { row[k] } else { 0.0 }));
            }
            if !entities.is_empty() {
                blocks.push(Block {
                    support: Support::Node,
                    cell: None,
                    localization: None,
                    per_entity: 1,
                    entities,
                    values: v,
                });
            }
        }
        Field::Elno { cells, .. } | Field::Elga { cells, .. } | Field::Elem { cells, .. } => {
            for (t, members) in cells_by_type(mesh) {
                let mut entities = Vec::new();
                let mut v = Vec::new();
                let mut per_entity = None;
                let mut loc: Option<Localization> = None;
                for (pos, &c) in members.iter().enumerate() {
                    let Some(vals) = cells.get(c).and_then(|x| x.as_ref()) else { continue };
                    if !sel.cell(c) {
                        continue;
                    }
                    if nco == 0 || vals.len() % nco != 0 {
                        return Err(format!("cell {}: {} values for {nco} components", mesh.cell_names[c], vals.len()));
                    }
                    let npts = vals.len() / nco;
                    let expected = match field {
                        Field::Elno { .. } => Some(t.nnodes()),
                        Field::Elem { .. } => Some(1),
                        _ => None,
                    };
                    if let Some(e) = expected.filter(|&e| e != npts) {
                        return Err(format!(
                            "cell {} ({}): {npts} values per component, {e} expected",
                            mesh.cell_names[c],
                            t.name()
                        ));
                    }
                    if let Field::Elga { .. } = field {
                        let l = localization_of(model, mesh, c, npts)?;
                        match &loc {
                            None => loc = Some(l),
                            Some(first) if first.name != l.name || !first.same_points(&l) => {
                                return Err(format!(
                                    "the {} cells carry points of two families ({} and {}): one MED localization \
                                     per cell type is supported",
                                    t.name(),
                                    first.name,
                                    l.name
                                ))
                            }
                            Some(_) => {}
                        }
                    }
                    if per_entity.is_some_and(|p| p != npts) {
                        return Err(format!("the {} cells do not all carry {npts} values per component", t.name()));
                    }
                    per_entity = Some(npts);
                    entities.push(pos);
                    for p in 0..npts {
                        v.extend(picked.iter().map(|&k| vals[p * nco + k]));
                    }
                }
                let Some(per_entity) = per_entity else { continue };
                let localization = loc.map(|l| {
                    let name = l.name.clone();
                    if !locs.iter().any(|x| x.name == name) {
                        locs.push(l);
                    }
                    name
                });
                let support = if matches!(field, Field::Elno { .. }) { Support::CellNode } else { Support::Cell };
                blocks.push(Block { support, cell: Some(t), localization, per_entity, entities, values: v });
            }
        }
    }
    Ok(blocks)
}
