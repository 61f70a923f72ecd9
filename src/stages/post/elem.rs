//! POST_ELEM: energies of a mechanical result or displacement field summed over the model or groups of
//! cells, as a table — ENER_POT (`peepot`, te0286: `½ ∫ (ε − ε_th) : D (ε − ε_th)` from the
//! displacements), ENER_ELAS (`peingl`, ENEL_ELEM: `½ ∫ σ : S σ` of the stresses) and ENER_TOTALE
//! (`peingl`, te0490: the elastic energy plus, for the von Mises laws, the plastic work `∫ R dp`). The
//! other quantities of POST_ELEM stop by name.

use crate::catalog::args::Args;
use crate::concepts::result::{Field, Step};
use crate::concepts::table::{Cell, ColType, Table};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::elasticity::{self, IsoElastic};
use crate::fem::postpro::elastic_energy;
use crate::stages::core::problem::{self, cell_temperatures, coords_of, Problem};
use crate::stages::Ctx;

/// What POST_ELEM sums.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Quantity {
    Potential,
    Elastic,
    Total,
}

impl Quantity {
    fn keyword(self) -> &'static str {
        match self {
            Quantity::Potential => "ENER_POT",
            Quantity::Elastic => "ENER_ELAS",
            Quantity::Total => "ENER_TOTALE",
        }
    }
}

pub fn post_elem(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let q = [Quantity::Potential, Quantity::Elastic, Quantity::Total]
        .into_iter()
        .find(|q| a.has(q.keyword()))
        .ok_or_else(|| a.err("ENER_POT", "POST_ELEM needs one of ENER_POT, ENER_ELAS, ENER_TOTALE"))?;
    a.refuse(&["CARA_ELEM", "MODE_FOURIER", "NUME_COUCHE", "NIVE_COUCHE", "LIST_ORDRE", "LIST_INST"])?;
    let (model, chmat, steps, result) = match (a.concept("RESULTAT"), a.concept("CHAM_GD")) {
        (Some(rc), _) => {
            a.refuse(&["MODELE", "CHAM_MATER"])?;
            let r = rc.result()?;
            let chmat = r.material.clone().ok_or_else(|| a.err("RESULTAT", "the result has no material field"))?;
            let steps = crate::stages::select::selected_steps(&r, a, &rc.label())?.into_iter().cloned().collect();
            (r.model.clone(), chmat, steps, Some(rc.clone()))
        }
        (None, Some(fc)) => {
            if q != Quantity::Potential {
                return Err(a.err("CHAM_GD", format!("{} of a field (CHAM_GD) is not supported yet", q.keyword())));
            }
            let model = a.req_concept("MODELE")?;
            let chmat = a.req_concept("CHAM_MATER")?;
            let f = fc.field()?;
            let step = Step { nume_ordre: 0, inst: 0.0, fields: [("DEPL".to_string(), f.field.clone())].into() };
            (model, chmat, vec![step], None)
        }
        (None, None) => return Err(a.err("RESULTAT", "POST_ELEM needs RESULTAT or CHAM_GD")),
    };
    if model.model()?.xfem.is_some() || model.model()?.is_thermal() {
        return Err(a.err("RESULTAT", format!("POST_ELEM {} of this model is not supported yet", q.keyword())));
    }
    // The materials at VALE_REF where parameters depend on TEMP: the laws below are taken at each point's
    // temperature for ENER_ELAS / ENER_TOTALE; ENER_POT needs constant ones (the problem says which not).
    let p = match q {
        Quantity::Potential => problem::problem(&model, &chmat),
        _ => problem::problem_at_ref(&model, &chmat),
    }
    .map_err(|e| a.locate(e, "RESULTAT"))?;
    let thermal = match q {
        Quantity::Potential => problem::thermal_strain(&chmat, &p).map_err(|e| a.locate(e, "RESULTAT"))?,
        _ => None,
    };
    let relations = match (&result, q) {
        (Some(rc), Quantity::Total) => relations_of(a, rc, &p)?,
        _ => Vec::new(),
    };
    let mesh_name = model.model()?.mesh_concept.label();
    // The places: per occurrence, TOUT or each group of GROUP_MA.
    let mut places: Vec<(String, &'static str, Vec<bool>)> = Vec::new();
    for occ in a.facts(q.keyword()) {
        if occ.text("TOUT") == Some("OUI") {
            places.push((mesh_name.clone(), "TOUT", vec![true; p.mesh.cells.len()]));
        }
        for g in occ.texts("GROUP_MA") {
            let cells = p
                .mesh
                .cell_groups
                .get(&g)
                .ok_or_else(|| occ.err("GROUP_MA", format!("mesh {mesh_name} has no group of cells {g}")))?;
            if cells.is_empty() {
                return Err(occ.err("GROUP_MA", format!("the group of cells {g} is empty")));
            }
            let mut on = vec![false; p.mesh.cells.len()];
            cells.iter().for_each(|&c| on[c] = true);
            places.push((g, "GROUP_MA", on));
        }
    }
    let mut rows: Vec<Vec<(String, Cell)>> = Vec::new();
    for step in &steps {
        let per_cell = energies(a, q, &chmat, &p, step, thermal.as_ref(), &relations)?;
        let total: f64 = per_cell.iter().flatten().sum();
        for (lieu, entite, on) in &places {
            let sum: f64 = per_cell.iter().zip(on).filter(|(_, &o)| o).filter_map(|(e, _)| *e).sum();
            let mut row = Vec::new();
            if result.is_some() {
                row.push(("NUME_ORDRE".to_string(), Cell::Int(step.nume_ordre)));
                row.push(("INST".to_string(), Cell::Real(step.inst)));
            }
            row.push(("LIEU".to_string(), Cell::Text(lieu.clone())));
            row.push(("ENTITE".to_string(), Cell::Text(entite.to_string())));
            row.push(("TOTALE".to_string(), Cell::Real(sum)));
            match q {
                Quantity::Potential => {
                    let pc = if total != 0.0 { 100.0 * sum / total } else { 0.0 };
                    row.push(("POUR_CENT".to_string(), Cell::Real(pc)));
                }
                Quantity::Elastic => {
                    // The parts of plates and shells: nothing on continua.
                    for c in ["MEMBRANE", "FLEXION", "CISAILLE", "COUPL_MF"] {
                        row.push((c.to_string(), Cell::Real(0.0)));
                    }
                }
                Quantity::Total => {}
            }
            rows.push(row);
        }
    }
    let mut t = Table::default();
    if let Some(first) = rows.first() {
        for (k, (name, cell)) in first.iter().enumerate() {
            let ty = match cell {
                Cell::Int(_) => ColType::I,
                Cell::Text(_) => ColType::K(24),
                _ => ColType::R,
            };
            t.add_column(name, ty, rows.iter().map(|r| r[k].1.clone()).collect())?;
        }
    }
    if a.has("TITRE") {
        t.title = a.texts("TITRE").join("\n");
    }
    Ok(Some(ConceptData::Table(t)))
}

/// The relation of COMPORTEMENT on each cell of the result (the last occurrence covering it; ELAS for a
/// result of an elastic command).
fn relations_of(a: &Args, rc: &ConceptRef, p: &Problem) -> Result<Vec<String>> {
    let r = rc.result()?;
    let mut out = vec!["ELAS".to_string(); p.mesh.cells.len()];
    let noli = rc.kind() == crate::concepts::ConceptKind::EvolNoli;
    if noli && r.comportement.is_empty() {
        return Err(a.err(
            "RESULTAT",
            format!(
                "ENER_TOTALE: the behaviour (COMPORTEMENT) of {} is not known (it was not computed here)",
                rc.label()
            ),
        ));
    }
    let n = out.len();
    for (relation, cells) in &r.comportement {
        match cells {
            Some(cs) => cs.iter().filter(|&&c| c < n).for_each(|&c| out[c] = relation.clone()),
            None => out.iter_mut().for_each(|o| *o = relation.clone()),
        }
    }
    Ok(out)
}

/// The energy of each bulk cell of the problem at one step (None elsewhere).
fn energies(
    a: &Args,
    q: Quantity,
    chmat: &ConceptRef,
    p: &Problem,
    step: &Step,
    thermal: Option<&crate::fem::elastic::ThermalStrain>,
    relations: &[String],
) -> Result<Vec<Option<f64>>> {
    let md = p.modelisation;
    let (mesh, dim, ns) = (&p.mesh, md.dim(), md.nsig());
    let Some(Field::Node { values: depl, .. }) = step.fields.get("DEPL") else {
        return Err(a.err("RESULTAT", format!("no DEPL at order {}", step.nume_ordre)));
    };
    let thetas = match thermal {
        Some(th) => th.theta(mesh, &p.bulk, step.inst).map_err(|e| a.locate(e, "RESULTAT"))?,
        None => vec![None; mesh.cells.len()],
    };
    let stored = match (q, step.fields.get("SIEF_ELGA")) {
        (Quantity::Potential, _) => None,
        (_, Some(Field::Elga { cells, .. })) => Some(cells),
        _ => None,
    };
    let temps = match q {
        Quantity::Potential => vec![None; mesh.cells.len()],
        _ => cell_temperatures(chmat, p, step.inst).map_err(|e| a.locate(e, "RESULTAT"))?,
    };
    let mats = chmat.data();
    let ConceptData::MaterialField(mf) = &*mats else {
        return Err(a.err("RESULTAT", format!("{} holds no material field", chmat.label())));
    };
    let mut out = vec![None; mesh.cells.len()];
    for &c in &p.bulk {
        let name = &mesh.cell_names[c];
        let (t, xs) = (mesh.cell_types[c], coords_of(mesh, c));
        let iso: &IsoElastic = &p.materials[c].as_ref().expect("a bulk cell").0;
        let geom = elasticity::gauss_geometry(md, t, &xs, &elasticity::rigi_rule_of(md, t))
            .map_err(|e| Error::runtime(format!("cell {name}: {e}")))?;
        let ue: Vec<f64> = mesh.cells[c].iter().flat_map(|&n| (0..dim).map(move |k| depl[n * dim + k])).collect();
        let sig: Vec<[f64; 6]> = match stored.and_then(|s| s[c].as_ref()) {
            Some(v) => {
                if v.len() != geom.len() * ns {
                    return Err(
                        a.err("RESULTAT", format!("SIEF_ELGA of cell {name} does not have its {} points", geom.len()))
                    );
                }
                v.chunks(ns).map(|s| std::array::from_fn(|k| if k < ns { s[k] } else { 0.0 })).collect()
            }
            None => {
                let zero = vec![0.0; mesh.cells[c].len()];
                let theta = thetas[c].as_deref().unwrap_or(&zero);
                elasticity::gauss_fields_thermal(md, iso, t, &xs, &ue, theta)
                    .map_err(|e| Error::runtime(format!("cell {name}: {e}")))?
                    .sig
            }
        };
        let mat = mf.cells[c].as_ref().expect("a bulk cell has a material");
        let md_ = mat.data();
        let ConceptData::Material(m) = &*md_ else { continue };
        let mut sum = 0.0;
        for (k, (g, s)) in geom.iter().zip(&sig).enumerate() {
            let temp = temps[c].as_ref().map(|tn| tn.iter().zip(&g.n).map(|(x, n)| x * n).sum::<f64>());
            let law = match q {
                Quantity::Potential => *iso,
                _ => problem::elastic_of_at(m, name, temp).map_err(|e| a.locate(e, "RESULTAT"))?.0,
            };
            if !law.is_isotropic() {
                return Err(a.err(
                    "RESULTAT",
                    format!("{}: cell {name}: an anisotropic material is not supported yet", q.keyword()),
                ));
            }
            let mut w = elastic_energy(law.e, law.nu, s);
            if q == Quantity::Total {
                let relation = relations[c].as_str();
                if relation != "ELAS" {
                    let vm = problem::von_mises_at(m, relation, name, temp).map_err(|e| a.locate(e, "RESULTAT"))?;
                    let pcum = match step.fields.get("VARI_ELGA") {
                        Some(Field::Elga { cells, components }) => {
                            let nv = components.len();
                            cells[c].as_ref().and_then(|v| v.get(k * nv).copied()).unwrap_or(0.0)
                        }
                        _ => return Err(a.err("RESULTAT", format!("no VARI_ELGA at order {}", step.nume_ordre))),
                    };
                    let h = vm.hardening.as_ref().expect("a von Mises law has a hardening");
                    w += h.area(pcum).map_err(|e| Error::runtime(format!("cell {name}: {e}")))?;
                }
            }
            sum += w * g.w;
        }
        out[c] = Some(sum);
    }
    Ok(out)
}
