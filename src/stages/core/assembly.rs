//! Loads and kinematic conditions of EXCIT at an instant, and the reduced (constraints eliminated) assembled system.

use super::eval::{eval_at, load_value};
use super::problem::{coords_of, Problem};
use crate::catalog::args::Args;
use crate::concepts::model::{Load, LoadItem, Role};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::{component_index, Constraints, DofMap};
use crate::fem::elasticity::{self};
use std::rc::Rc;
use std::time::Instant;
/// The loads of EXCIT with their multiplier at `inst`.
pub fn loads(a: &Args, inst: f64) -> Result<Vec<(ConceptRef, f64)>> {
    let mut out = Vec::new();
    for occ in a.facts("EXCIT") {
        if occ.given("TYPE_CHARGE") && occ.text("TYPE_CHARGE") != Some("FIXE_CSTE") {
            return Err(occ.err("TYPE_CHARGE", "not supported yet"));
        }
        let c = occ.req_concept("CHARGE")?;
        let mult = match occ.concept("FONC_MULT") {
            Some(f) => eval_at(&f, &[0.0; 3], inst).map_err(|e| e.at(occ.span_of("FONC_MULT")))?,
            None => 1.0,
        };
        out.push((c, mult));
    }
    Ok(out)
}

/// The reduced linear system of a step: constraints eliminated, loads at `inst`.
pub struct System {
    pub map: DofMap,
    pub k: faer::sparse::SparseColMat<usize, f64>,
    pub rhs: Vec<f64>,
    pub t_numbering: std::time::Duration,
    pub t_assembly: std::time::Duration,
}

pub fn assemble(a: &Args, p: &Problem, model: &ConceptRef, inst: f64) -> Result<System> {
    let mesh = &p.mesh;
    let md = p.modelisation;
    let dim = md.dim();
    let t0 = Instant::now();
    // Kinematic conditions and forces.
    let mut cons = Constraints::new();
    let mut forces: Vec<(Vec<usize>, Vec<f64>)> = Vec::new();
    let model_ref = model.model()?;
    // The dofs of a boundary cell carrying a surface load; the cell must be a skin element of the model.
    let skin_dofs = |c: usize| -> Result<Vec<usize>> {
        let on_skin = model_ref.elements[c].as_ref().map(|e| e.role) == Some(Role::Skin);
        match p.numbering.cell_dofs(&mesh.cells[c]) {
            Some(d) if on_skin => Ok(d),
            _ => Err(a.err("EXCIT", format!("cell {} is not a boundary cell of the model", mesh.cell_names[c]))),
        }
    };
    for (lc, mult) in loads(a, inst)? {
        let data = lc.data();
        let ConceptData::Load(Load { items, model: lmodel, .. }) = &*data else {
            return Err(a.err("EXCIT", format!("{} is not a mechanical load", lc.label())));
        };
        if !Rc::ptr_eq(lmodel, model) {
            return Err(a.err("EXCIT", format!("load {} is defined on another model ({})", lc.label(), lmodel.label())));
        }
        for item in items {
            match item {
                LoadItem::Dof { node, component, value } => {
                    let comp = component_index(component).filter(|&k| k < dim).ok_or_else(|| {
                        a.err(
                            "EXCIT",
                            format!("load {}: component {component} is not a dof of a {} model", lc.label(), md.name()),
                        )
                    })?;
                    let dof = p.numbering.dof(*node, comp).ok_or_else(|| {
                        a.err(
                            "EXCIT",
                            format!(
                                "load {}: node {} carries no element of the model",
                                lc.label(),
                                mesh.node_names[*node]
                            ),
                        )
                    })?;
                    cons.impose(dof, mult * load_value(value, &mesh.coords[*node], inst)?);
                }
                LoadItem::Relation { terms, value } => {
                    let mut t = Vec::new();
                    for (node, comp, coef) in terms {
                        let k = component_index(comp)
                            .filter(|&k| k < dim)
                            .ok_or_else(|| a.err("EXCIT", format!("component {comp} is not a dof of the model")))?;
                        let dof = p.numbering.dof(*node, k).ok_or_else(|| {
                            a.err("EXCIT", format!("node {} carries no element of the model", mesh.node_names[*node]))
                        })?;
                        t.push((dof, *coef));
                    }
                    cons.relation(t, mult * load_value(value, &[0.0; 3], inst)?);
                }
                LoadItem::NodalForce { node, component, value } => {
                    let k = match component.as_str() {
                        "FX" => 0,
                        "FY" => 1,
                        "FZ" => 2,
                        c => {
                            return Err(
                                a.err("EXCIT", format!("load {}: FORCE_NODALE {c} is not supported yet", lc.label()))
                            )
                        }
                    };
                    if k >= dim {
                        return Err(
                            a.err("EXCIT", format!("load {}: {component} in a {} model", lc.label(), md.name()))
                        );
                    }
                    let dof = p.numbering.dof(*node, k).ok_or_else(|| {
                        a.err("EXCIT", format!("node {} carries no element of the model", mesh.node_names[*node]))
                    })?;
                    forces.push((vec![dof], vec![mult * load_value(value, &mesh.coords[*node], inst)?]));
                }
                LoadItem::SurfaceForce { cells, components } => {
                    if dim < 3 && components.iter().any(|(n, _)| n == "FZ") {
                        return Err(a.err("EXCIT", format!("load {}: FZ in a {} model", lc.label(), md.name())));
                    }
                    for &c in cells {
                        let dofs = skin_dofs(c)?;
                        let xs = coords_of(mesh, c);
                        let err = std::cell::RefCell::new(None);
                        let f = |x: &[f64; 3], _n: &[f64; 3]| -> [f64; 3] {
                            let mut v = [0.0; 3];
                            for (name, val) in components {
                                let k = match name.as_str() {
                                    "FX" => 0,
                                    "FY" => 1,
                                    _ => 2,
                                };
                                match load_value(val, x, inst) {
                                    Ok(r) => v[k] = mult * r,
                                    Err(e) => *err.borrow_mut() = Some(e),
                                }
                            }
                            v
                        };
                        let fe = elasticity::boundary_force(md, mesh.cell_types[c], &xs, &f)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        if let Some(e) = err.into_inner() {
                            return Err(e.at(a.span));
                        }
                        forces.push((dofs, fe));
                    }
                }
                LoadItem::Pressure { cells, value } => {
                    for &c in cells {
                        let dofs = skin_dofs(c)?;
                        let xs = coords_of(mesh, c);
                        let pres: Vec<f64> =
                            xs.iter().map(|x| load_value(value, x, inst).map(|v| v * mult)).collect::<Result<_>>()?;
                        let fe = elasticity::pressure_force(md, mesh.cell_types[c], &xs, &pres, None)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        forces.push((dofs, fe));
                    }
                }
                LoadItem::FluxThm { .. } => {
                    return Err(a.err(
                        "EXCIT",
                        format!(
                            "load {}: FLUX_THM_REP needs a hydro-mechanical model ({} has no pressure)",
                            lc.label(),
                            md.name()
                        ),
                    ))
                }
                LoadItem::Gravity { g, direction, cells } => {
                    let on: Vec<usize> = match cells {
                        Some(c) => c.iter().copied().filter(|c| p.materials[*c].is_some()).collect(),
                        None => p.bulk.clone(),
                    };
                    for c in on {
                        let rho = p.materials[c].as_ref().unwrap().1;
                        if rho == 0.0 {
                            return Err(a.err(
                                "EXCIT",
                                format!(
                                    "load {}: PESANTEUR on cell {}, whose material gives no RHO",
                                    lc.label(),
                                    mesh.cell_names[c]
                                ),
                            ));
                        }
                        let xs = coords_of(mesh, c);
                        let acc = [
                            rho * g * direction[0] * mult,
                            rho * g * direction[1] * mult,
                            rho * g * direction[2] * mult,
                        ];
                        let fe = elasticity::body_force(md, mesh.cell_types[c], &xs, &|_x| acc)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        let dofs = p.numbering.cell_dofs(&mesh.cells[c]).unwrap();
                        forces.push((dofs, fe));
                    }
                }
            }
        }
    }
    drop(model_ref);
    let map = DofMap::build(p.numbering.ndofs(), &cons)
        .map_err(|e| a.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
    let t_numbering = t0.elapsed();

    // Assembly.
    let t0 = Instant::now();
    let mut elems = ElementDofs::new();
    for &c in &p.bulk {
        elems.push(&p.numbering.cell_dofs(&mesh.cells[c]).unwrap());
    }
    let pattern = SparsityPattern::build(&map, &elems);
    let mut asm = Assembler::new(&map, pattern);
    for (i, &c) in p.bulk.iter().enumerate() {
        let mat = &p.materials[c].as_ref().unwrap().0;
        let ke = elasticity::stiffness(md, mat, mesh.cell_types[c], &coords_of(mesh, c))
            .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])).at(a.span))?;
        asm.add_matrix(elems.get(i), &ke);
    }
    for (dofs, fe) in &forces {
        asm.add_vector(dofs, fe);
    }
    let (k, rhs) = asm.finish();
    let t_assembly = t0.elapsed();
    Ok(System { map, k, rhs, t_numbering, t_assembly })
}
