//! AFFE_MODELE: the element each cell of a mesh carries. Mesh entities are resolved and checked here.

use crate::catalog::args::Args;
use crate::concepts::model::{role_of, Element, Model, Modelling};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::select::select_cells;
use crate::stages::Ctx;
use std::collections::BTreeMap;

// ------------------------------------------------------------------ AFFE_MODELE

/// Code_Aster's `Z_QUASI_ZERO` of a mesh: every z is 0, or |z| stays below 1e-8 of the extent in x or y.
fn z_quasi_zero(mesh: &crate::mesh::Mesh) -> bool {
    let range = |k: usize| {
        let (lo, hi) =
            mesh.coords.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| (l.min(c[k]), h.max(c[k])));
        if lo.is_finite() {
            (lo, hi)
        } else {
            (0.0, 0.0)
        }
    };
    let ((x0, x1), (y0, y1), (z0, z1)) = (range(0), range(1), range(2));
    (z0 == 0.0 && z1 == 0.0) || z0.abs().max(z1.abs()) < (x1 - x0).max(y1 - y0) * 1e-8
}

pub fn affe_modele(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["AFFE_SOUS_STRUC", "GRANDEUR_CARA"])?;
    // DISTRIBUTION shares the cells among the MPI processes of a parallel run; a run of aster-rs is one
    // process holding every cell, so the method and its partition change nothing it computes.
    if let Some(d) = a.fact("DISTRIBUTION") {
        d.read_all();
    }
    let mc = a.req_concept("MAILLAGE")?;
    let mesh = mc.mesh()?;
    let name = mc.label();
    let mut elements: Vec<Option<crate::concepts::model::Element>> = vec![None; mesh.cells.len()];
    let mut asked = vec![false; mesh.cells.len()];
    let mut alarms = String::new();
    for occ in a.facts("AFFE") {
        let phen = occ.req_text("PHENOMENE")?;
        if !matches!(phen, "MECANIQUE" | "THERMIQUE") {
            return Err(occ.err("PHENOMENE", format!("PHENOMENE='{phen}' is not supported yet")));
        }
        if let Some(other) = elements.iter().flatten().map(|e| e.phenomenon.as_str()).find(|p| *p != phen) {
            return Err(occ.err("PHENOMENE", format!("a model holds one phenomenon: {other} and {phen} are given")));
        }
        let name_md = occ.req_text("MODELISATION")?;
        let Some(modelisation) = Modelling::of_phenomenon(phen, name_md) else {
            return Err(occ.err("MODELISATION", format!("MODELISATION='{name_md}' is not supported yet")));
        };
        let dim = modelisation.dim();
        if occ.given("FORMULATION") {
            return Err(occ.err("FORMULATION", "not supported yet"));
        }
        // op0018: a plane or axisymmetric modelisation wants the mesh in the plane z = 0.
        if (name_md.starts_with("AXIS") || name_md.contains("_PLAN") || name_md.starts_with("PLAN"))
            && !z_quasi_zero(&mesh)
            && !alarms.contains("MODELE1_3")
        {
            alarms.push_str(&format!(
                " <A> <MODELE1_3> AFFE_MODELE: MODELISATION='{name_md}' is plane or axisymmetric but mesh {name} is not \
                 in the plane z = 0: its cells are taken in the plane (x, y) and the cells that are not plane elements \
                 of it are not assigned\n"
            ));
        }
        let cells = select_cells(&mesh, occ, &name)?;
        let mut placed = 0;
        for c in cells {
            asked[c] = true;
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
    // op0018's MODELE1_4: how many cells were asked for and how many got an element.
    let n_asked = asked.iter().filter(|x| **x).count();
    let n_assigned = elements.iter().filter(|e| e.is_some()).count();
    alarms.push_str(&format!(
        "  <MODELE1_4> AFFE_MODELE: of the {} cells of mesh {name}, {n_asked} were asked for and {n_assigned} assigned\n",
        mesh.cells.len()
    ));
    if n_assigned < n_asked {
        let mut left: BTreeMap<&str, usize> = BTreeMap::new();
        for c in (0..mesh.cells.len()).filter(|&c| asked[c] && elements[c].is_none()) {
            *left.entry(mesh.cell_types[c].name()).or_default() += 1;
        }
        let list: Vec<String> = left.iter().map(|(t, n)| format!("{n} {t}")).collect();
        alarms.push_str(&format!(
            " <A> AFFE_MODELE: {} of the cells asked for carry no element of their modelisation ({}): they are not in \
             the model\n",
            n_asked - n_assigned,
            list.join(", ")
        ));
    }
    ctx.io.mess(&alarms);
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
