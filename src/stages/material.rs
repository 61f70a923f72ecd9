//! DEFI_MATERIAU and AFFE_MATERIAU: materials and the material field.

use crate::catalog::args::{ArgValue, Args, Val};
use crate::concepts::model::{MatValue, Material, MaterialField};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::select::select_cells;
use crate::stages::Ctx;
use std::collections::BTreeMap;
use std::rc::Rc;

// ------------------------------------------------------------------ DEFI_MATERIAU

pub fn defi_materiau(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["MATER", "TABLE"])?;
    let mut m = Material::default();
    for item in &a.items {
        // Every behaviour is stored; the stages that compute with a material read what they need.
        item.read.set(true);
        match &item.value {
            ArgValue::Factor(occs) => {
                let occ = &occs[0];
                let mut params = BTreeMap::new();
                for p in &occ.items {
                    let v = match occ.val(&p.name) {
                        Some(Val::R(r)) => MatValue::Real(*r),
                        Some(Val::I(i)) => MatValue::Real(*i as f64),
                        Some(Val::T(t)) => MatValue::Text(t.clone()),
                        Some(Val::Concept(c)) => MatValue::Func(c.clone()),
                        _ => continue,
                    };
                    params.insert(p.name.clone(), v);
                }
                m.behaviours.insert(item.name.clone(), params);
            }
            ArgValue::Simple(v) => {
                if let Some(Val::T(t)) = v.first() {
                    m.options.insert(item.name.clone(), t.clone());
                }
            }
        }
    }
    Ok(Some(ConceptData::Material(Rc::new(m))))
}

// ------------------------------------------------------------------ AFFE_MATERIAU

pub fn affe_materiau(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["AFFE_VARC"])?;
    let (mesh, name) = match (a.concept("MAILLAGE"), a.concept("MODELE")) {
        (Some(mc), _) => (mc.mesh()?, mc.label()),
        (None, Some(mo)) => {
            let m = mo.model()?;
            (m.current_mesh(), m.mesh_concept.label())
        }
        (None, None) => return Err(a.err("MAILLAGE", "MAILLAGE or MODELE is required")),
    };
    let mut cells = vec![None; mesh.cells.len()];
    for occ in a.facts("AFFE") {
        let maters = occ.concepts("MATER");
        if maters.len() > 1 {
            return Err(occ.err("MATER", "several materials on the same cells are not supported yet"));
        }
        for c in select_cells(&mesh, occ, &name)? {
            cells[c] = Some(maters[0].clone());
        }
    }
    Ok(Some(ConceptData::MaterialField(MaterialField { mesh, cells })))
}
