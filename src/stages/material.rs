//! DEFI_MATERIAU and AFFE_MATERIAU: materials and the material field; AFFE_CARA_ELEM: the element
//! characteristics (the local frames of anisotropic materials).

use crate::catalog::args::{ArgValue, Args, Val};
use crate::concepts::model::{CaraElem, MatValue, Material, MaterialField, Varc, VarcSource};
use crate::concepts::{ConceptData, ConceptKind};
use crate::diag::Result;
use crate::fem::frame::Frame;
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
    let mut varc = Vec::new();
    for occ in a.facts("AFFE_VARC") {
        varc.push(affe_varc(&mesh, occ, &name)?);
    }
    Ok(Some(ConceptData::MaterialField(MaterialField { mesh, cells, varc })))
}

/// One occurrence of AFFE_VARC: the temperature (NOM_VARC='TEMP') from an EVOL_THER or EVOL_VARC (its TEMP field) or
/// a field on nodes; the other command variables stop by name.
fn affe_varc(mesh: &crate::mesh::Mesh, occ: &Args, name: &str) -> Result<Varc> {
    let nom = occ.req_text("NOM_VARC")?.to_string();
    if nom != "TEMP" {
        return Err(occ.err("NOM_VARC", format!("NOM_VARC='{nom}' is not supported yet (TEMP is)")));
    }
    // Without TOUT, GROUP_MA or MAILLE, the variable is on every cell.
    let cells = if ["TOUT", "GROUP_MA", "MAILLE"].iter().any(|k| occ.has(k)) {
        select_cells(mesh, occ, name)?
    } else {
        (0..mesh.cells.len()).collect()
    };
    let source = match (occ.concept("EVOL"), occ.concept("CHAM_GD")) {
        (Some(r), _) => {
            if !matches!(r.kind(), ConceptKind::EvolTher | ConceptKind::EvolVarc) {
                return Err(occ.err(
                    "EVOL",
                    format!("{} is an {}, not a temperature (EVOL_THER or EVOL_VARC)", r.label(), r.kind()),
                ));
            }
            let field = occ.text("NOM_CHAM").unwrap_or("TEMP").to_string();
            if field != "TEMP" {
                return Err(occ.err("NOM_CHAM", format!("NOM_CHAM='{field}' is not supported yet (TEMP is)")));
            }
            VarcSource::Evol { result: r, field, fonc_inst: occ.concept("FONC_INST") }
        }
        (None, Some(f)) => {
            if f.kind() != ConceptKind::ChamNo {
                return Err(occ.err("CHAM_GD", format!("{} is not a field on nodes (cham_no)", f.label())));
            }
            VarcSource::Field(f)
        }
        (None, None) => return Err(occ.err("NOM_VARC", "EVOL or CHAM_GD is required")),
    };
    let prol = |k: &str| occ.text_if_declared(k).unwrap_or("EXCLU").to_string();
    Ok(Varc {
        name: nom,
        cells,
        source,
        vale_ref: occ.real("VALE_REF"),
        prol: (prol("PROL_GAUCHE"), prol("PROL_DROITE")),
    })
}

// ------------------------------------------------------------------ AFFE_CARA_ELEM

/// AFFE_CARA_ELEM: the characteristics a model's cells need beyond their material. So far MASSIF, the
/// local frame of an anisotropic material (`THER_ORTH`, `THER_NL_ORTH`, ...): nautical angles
/// (ANGL_REP), Euler angles (ANGL_EULER) or a cylindrical frame (ORIG_AXE, with ANGL_AXE in 3D). The
/// structural elements' keywords (POUTRE, BARRE, COQUE, DISCRET, ...) stop the run by name.
///
/// As Code_Aster does: the cells MASSIF leaves out keep the global frame, later occurrences overwrite
/// earlier ones on the cells they share, and a cell of a plane modelisation takes the first nautical
/// angle only (its frame turns in the plane).
pub fn affe_cara_elem(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mo = a.req_concept("MODELE")?;
    let _ = (a.int("INFO"), a.texts("VERIF"));
    let (mesh, elements) = {
        let m = mo.model()?;
        (m.current_mesh(), m.elements.iter().map(|e| e.as_ref().map(|e| e.modelisation.dim())).collect::<Vec<_>>())
    };
    let name = mo.model()?.mesh_concept.label();
    let mut massif = vec![None; mesh.cells.len()];
    for occ in a.facts("MASSIF") {
        if occ.has("CHAM_ORIE") {
            return Err(occ.err("CHAM_ORIE", "a field of orientations (CHAM_ORIE) is not supported yet"));
        }
        let rep = occ.reals("ANGL_REP");
        let eul = occ.reals("ANGL_EULER");
        let axe = occ.reals("ANGL_AXE");
        let orig = occ.reals("ORIG_AXE");
        let cells = select_cells(&mesh, occ, &name)?;
        for c in cells {
            // The dimension of the cell's element (the mesh's for a cell the model leaves out).
            let dim = elements.get(c).copied().flatten().unwrap_or(mesh.dim);
            let frame = if !rep.is_empty() {
                Frame::nautical(if dim == 2 { &rep[..1] } else { &rep })
            } else if !eul.is_empty() {
                let f = Frame::euler(&eul);
                match (dim, f) {
                    // In the plane only the angle of L about Z counts.
                    (2, Frame::Fixed(ax)) => Frame::nautical(&[ax[0][1].atan2(ax[0][0]).to_degrees()]),
                    _ => f,
                }
            } else if !orig.is_empty() {
                let mut o = [0.0; 3];
                o.iter_mut().zip(&orig).for_each(|(d, v)| *d = *v);
                match (dim, axe.as_slice()) {
                    (3, [a, b]) => Frame::cylinder(o, Some([*a, *b])),
                    (3, _) => {
                        return Err(occ.err("ORIG_AXE", "in 3D a cylindrical frame needs its axis (ANGL_AXE)"));
                    }
                    (_, []) => Frame::cylinder(o, None),
                    _ => {
                        return Err(
                            occ.err("ANGL_AXE", "in 2D a cylindrical frame has no axis: ANGL_AXE is not allowed")
                        )
                    }
                }
            } else {
                return Err(occ.err("ANGL_REP", "ANGL_REP, ANGL_EULER or ORIG_AXE is required"));
            };
            massif[c] = Some(frame);
        }
    }
    Ok(Some(ConceptData::CaraElem(CaraElem { model: mo.clone(), massif })))
}
