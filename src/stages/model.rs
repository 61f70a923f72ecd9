//! AFFE_MODELE: the element each cell of a mesh carries. Mesh entities are resolved and checked here.

use crate::catalog::args::Args;
use crate::concepts::model::{role_of, Element, Model, Modelling};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::select::select_cells;
use crate::stages::Ctx;
use std::collections::BTreeMap;

// ------------------------------------------------------------------ AFFE_MODELE

pub fn affe_modele(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["AFFE_SOUS_STRUC", "GRANDEUR_CARA"])?;
    let mc = a.req_concept("MAILLAGE")?;
    let mesh = mc.mesh()?;
    let name = mc.label();
    let mut elements: Vec<Option<crate::concepts::model::Element>> = vec![None; mesh.cells.len()];
    for occ in a.facts("AFFE") {
        let phen = occ.req_text("PHENOMENE")?;
        if phen != "MECANIQUE" {
            return Err(occ.err("PHENOMENE", format!("PHENOMENE='{phen}' is not supported yet")));
        }
        let name_md = occ.req_text("MODELISATION")?;
        let Some(modelisation) = Modelling::from_name(name_md) else {
            return Err(occ.err("MODELISATION", format!("MODELISATION='{name_md}' is not supported yet")));
        };
        let dim = modelisation.dim();
        if occ.given("FORMULATION") {
            return Err(occ.err("FORMULATION", "not supported yet"));
        }
        let cells = select_cells(&mesh, occ, &name)?;
        let mut placed = 0;
        for c in cells {
            if let Some(role) = role_of(dim, mesh.cell_types[c]).filter(|_| modelisation.accepts(mesh.cell_types[c])) {
                elements[c] = Some(Element { phenomenon: phen.into(), modelisation, role });
                placed += 1;
            }
        }
        if placed == 0 {
            return Err(occ.err(
                "MODELISATION",
                format!("no cell of the selection can carry a {modelisation} element (check the cell types)"),
            ));
        }
    }
    let mut counts: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    for (c, e) in elements.iter().enumerate() {
        if let Some(e) = e {
            *counts.entry((e.modelisation.name(), mesh.cell_types[c].name())).or_default() += 1;
        }
    }
    let mut text = String::from("  model elements (modelisation, cell type, count):\n");
    for ((m, t), n) in counts {
        text.push_str(&format!("    {m:<12} {t:<8} {n:>8}\n"));
    }
    ctx.io.mess(&text);
    Ok(Some(ConceptData::Model(Model { mesh, mesh_concept: mc, elements, xfem: None })))
}
