//! DEFI_FISS_XFEM: an interface given by a normal level-set function, with
//! its junctions on master interfaces, as Code_Aster's `op0041` computes it:
//! nodal level sets (`xinils`) adjusted near zero (`xajuls`), the junction
//! coefficients (`xinlsj`), the node status and enriched cells (`xenrch`).

mod lips;

use crate::catalog::args::Args;
use crate::concepts::model::Model;
use crate::concepts::result::Field;
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::stages::core::eval::eval_at;
use crate::stages::Ctx;
use crate::xfem::model::ContactKind;
use crate::xfem::model::XfemModel;
use crate::xfem::postmail::{visual_mesh, NodeOrigin, Prefixes, VisualMesh};
use crate::xfem::topose::{topose, topose_boundary, CrackInCell};
use crate::xfem::{build_interface, Crack};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::rc::Rc;

pub fn defi_fiss_xfem(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["MAILLAGE_GRILLE", "FISS_GRILLE", "TYPE_ENRI_FOND", "RAYON_ENRI", "NB_COUCHES"])?;
    let typdis = a.req_text("TYPE_DISCONTINUITE")?;
    if typdis != "INTERFACE" {
        return Err(a.err("TYPE_DISCONTINUITE", format!("TYPE_DISCONTINUITE='{typdis}' is not supported yet")));
    }
    if a.text("CHAM_DISCONTINUITE").is_some_and(|c| c != "DEPL") {
        return Err(a.err("CHAM_DISCONTINUITE", "CHAM_DISCONTINUITE='SIGM' is not supported yet"));
    }
    let mc = a.req_concept("MAILLAGE")?;
    let mesh = mc.mesh()?;
    let mesh_name = mc.label();

    // Level sets (xinils, method FONCTION; an interface has lst = −1).
    let Some(df) = a.fact("DEFI_FISS") else {
        return Err(a.err("DEFI_FISS", "DEFI_FISS is required"));
    };
    let mut others: Vec<&str> = df.items.iter().filter(|i| !i.defaulted).map(|i| i.name.as_str()).collect();
    others.retain(|n| *n != "FONC_LN");
    if let Some(n) = others.first() {
        return Err(df.err(n, "not supported yet (DEFI_FISS takes FONC_LN only for now)"));
    }
    let fonc = df.concept("FONC_LN").ok_or_else(|| df.err("FONC_LN", "FONC_LN is required"))?;
    let mut lsn = Vec::with_capacity(mesh.nnodes());
    for x in &mesh.coords {
        let mut p = [0.0; 3];
        p[..mesh.dim].copy_from_slice(&x[..mesh.dim]);
        lsn.push(eval_at(&fonc, &p, 0.0).map_err(|e| df.err("FONC_LN", e.msg))?);
    }
    // GROUP_MA_ENRI (xlenri): all cells by default.
    let enri_cells = match a.text("GROUP_MA_ENRI") {
        Some(g) => {
            let mut v =
                mesh.cell_groups.get(g).cloned().ok_or_else(|| {
                    a.err("GROUP_MA_ENRI", format!("group of cells '{g}' is not in mesh {mesh_name}"))
                })?;
            v.sort_unstable();
            v.dedup();
            Some(v)
        }
        None => None,
    };
    let (masters, point) = match a.fact("JONCTION") {
        Some(j) => (
            j.concepts("FISSURE")
                .iter()
                .map(|c| c.crack().map(|k| (c.label(), k)).map_err(|e| j.locate(e, "FISSURE")))
                .collect::<Result<Vec<_>>>()?,
            Some(j.reals("POINT")),
        ),
        None => (Vec::new(), None),
    };
    let crack = build_interface(mesh_name.clone(), mesh, lsn, enri_cells, &masters, point.as_deref()).map_err(|e| {
        match (e.keyword, a.fact("JONCTION")) {
            ("FISSURE" | "POINT", Some(j)) => j.err(e.keyword, e.msg),
            ("DEFI_FISS", _) => a.err("DEFI_FISS", e.msg),
            _ => Error::runtime(e.msg),
        }
    })?;
    if a.int("INFO").unwrap_or(1) >= 2 {
        ctx.io.mess(&report(&crack)?);
    }
    Ok(Some(ConceptData::Crack(Rc::new(crack))))
}

/// The INFO=2 summary: counts, junctions, and the nodes shared with each master.
fn report(k: &Crack) -> Result<String> {
    let mesh = &k.mesh;
    let nodes = k.enriched_nodes();
    let vol = |cells: &[usize]| cells.iter().filter(|&&c| mesh.cell_types[c].dim() == mesh.dim).count();
    let mut s = String::new();
    let _ = writeln!(s, "  DEFI_FISS_XFEM (INTERFACE) on {}:", k.mesh_name);
    let _ = writeln!(s, "    level-set values adjusted to 0       : {}", k.adjusted);
    let _ = writeln!(
        s,
        "    cells cut by the interface           : {} ({} of dimension {})",
        k.cut_cells.len(),
        vol(&k.cut_cells),
        mesh.dim
    );
    let _ = writeln!(s, "    Heaviside-enriched nodes             : {}", nodes.len());
    let _ = writeln!(
        s,
        "    Heaviside-enriched cells             : {} ({} of dimension {})",
        k.heaviside_cells.len(),
        vol(&k.heaviside_cells),
        mesh.dim
    );
    if let Some(n) = k.junction_node {
        let _ = writeln!(s, "    junction: node nearest POINT         : {}", mesh.node_names[n]);
    }
    for j in &k.junctions {
        let m = &j.crack;
        let shared = nodes.iter().filter(|&&n| m.enriched(n)).count();
        let both: Vec<usize> =
            k.heaviside_cells.iter().copied().filter(|c| m.heaviside_cells.binary_search(c).is_ok()).collect();
        let _ = writeln!(
            s,
            "    junction on {} (c = {:+}{}): the branch exists where c*LSN({}) < 0",
            j.name,
            j.coef,
            if j.declared { "" } else { ", through a master" },
            j.name,
        );
        let _ = writeln!(s, "      nodes enriched by both             : {shared}");
        let _ = writeln!(
            s,
            "      cells enriched by both             : {} ({} of dimension {})",
            both.len(),
            vol(&both),
            mesh.dim
        );
    }
    Ok(s)
}

// ------------------------------------------------------------------ MODI_MODELE_XFEM

/// MODI_MODELE_XFEM: the X-FEM cells of the model (cells with a
/// Heaviside-enriched node), the cracks each sees, their cutting into
/// sub-cells (TOPOSE), the regions and the enrichment sets of the nodes.
pub fn modi_modele_xfem(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["MODELE_THER"])?;
    let contact_name = a.text("CONTACT").unwrap_or("SANS");
    let Some(contact) = ContactKind::from_name(contact_name) else {
        return Err(
            a.err("CONTACT", format!("CONTACT='{contact_name}' is not supported yet (only 'SANS' and 'MORTAR')"))
        );
    };
    // DECOUPE_FACETTE: the facets are always the faces of the sub-cells on
    // the interface. Code_Aster's default cuts the interface polygon of each
    // parent on its own; where the interface is straight in a linear cell
    // both tile the same segment or polygon with flat pieces, and the facet
    // integrals agree (docs/wtnv149.md); that is checked cell by cell below.
    // Quadratic cells keep the faithful SOUS_ELEMENTS only.
    let mo_in = a.req_concept("MODELE_IN")?;
    if mo_in.model()?.is_thermal() {
        return Err(a.err(
            "MODELE_IN",
            format!("{} is a thermal model: X-FEM on PHENOMENE='THERMIQUE' is not supported yet", mo_in.label()),
        ));
    }
    let quadratic_model = {
        let m = mo_in.model()?;
        let mesh = m.current_mesh();
        (0..mesh.ncells()).any(|c| {
            m.elements[c].as_ref().is_some_and(|e| e.role == crate::concepts::model::Role::Bulk)
                && mesh.cell_types[c].nnodes() > mesh.cell_types[c].nvertices()
        })
    };
    if a.text("DECOUPE_FACETTE").is_some_and(|d| d != "SOUS_ELEMENTS")
        && contact == ContactKind::Mortar
        && quadratic_model
    {
        return Err(a.err(
            "DECOUPE_FACETTE",
            "with CONTACT='MORTAR' on quadratic cells only DECOUPE_FACETTE='SOUS_ELEMENTS' is supported yet",
        ));
    }
    let mo = a.req_concept("MODELE_IN")?;
    let crack_concepts = a.concepts("FISSURE");
    let cracks: Vec<Rc<Crack>> =
        crack_concepts.iter().map(|c| c.crack().map_err(|e| a.locate(e, "FISSURE"))).collect::<Result<_>>()?;
    let (mesh, elements) = {
        let m = mo.model()?;
        if m.xfem.is_some() {
            return Err(a.err("MODELE_IN", format!("{} is already an X-FEM model", mo.label())));
        }
        (m.current_mesh(), m.elements.clone())
    };
    let model_cells: Vec<usize> = (0..mesh.ncells())
        .filter(|&c| elements[c].as_ref().is_some_and(|e| e.role == crate::concepts::model::Role::Bulk))
        .collect();
    if a.text("DECOUPE_FACETTE") == Some("DEFAUT") && contact == ContactKind::Mortar {
        for (f, k) in crack_concepts.iter().zip(&cracks) {
            for &c in k.cut_cells.iter().filter(|c| model_cells.binary_search(c).is_ok()) {
                let coords: Vec<[f64; 3]> = mesh.cells[c].iter().map(|&n| mesh.coords[n]).collect();
                let lsn: Vec<f64> = mesh.cells[c].iter().map(|&n| k.lsn[n]).collect();
                if !crate::xfem::model::straight_in_cell(&coords, &lsn, mesh.dim) {
                    return Err(a.err(
                        "DECOUPE_FACETTE",
                        format!(
                            "{} is not straight in cell {}: Code_Aster's DECOUPE_FACETTE='DEFAUT' facets differ there \
                             from the sub-cell faces; only 'SOUS_ELEMENTS' is supported yet",
                            f.label(),
                            mesh.cell_names[c]
                        ),
                    ));
                }
            }
        }
    }
    let mut lsn = Vec::new();
    let mut masters = Vec::new();
    let mut enriched = Vec::new();
    let mut hcells: Vec<Vec<usize>> = Vec::new();
    let mut names = Vec::new();
    for (i, (f, k)) in crack_concepts.iter().zip(&cracks).enumerate() {
        // The same mesh: the one the crack was defined on, or that mesh since changed in place.
        let same_mesh = Rc::ptr_eq(&k.mesh, &mesh) || k.mesh.coords == mesh.coords;
        if !same_mesh || k.lsn.len() != mesh.nnodes() {
            return Err(a.err("FISSURE", format!("{} is defined on another mesh than {}", f.label(), mo.label())));
        }
        if cracks[..i].iter().any(|g| Rc::ptr_eq(g, k)) {
            return Err(a.err("FISSURE", format!("{} is given twice", f.label())));
        }
        lsn.push(k.lsn.clone());
        enriched.push((0..mesh.nnodes()).map(|n| k.enriched(n)).collect::<Vec<bool>>());
        hcells.push(k.heaviside_cells.clone());
        names.push(f.label());
        masters.push(k.master().and_then(|(m, c)| cracks.iter().position(|g| Rc::ptr_eq(g, m)).map(|p| (p, c))));
        if let Some((m, _)) = k.master() {
            if !cracks.iter().any(|g| Rc::ptr_eq(g, m)) {
                let master = k.junctions.iter().find(|j| j.declared).map(|j| j.name.as_str()).unwrap_or("its master");
                return Err(
                    a.err("FISSURE", format!("{} branches on {master}, which must be in FISSURE too", f.label()))
                );
            }
        }
    }
    // The cracks a cell sees and what TOPOSE needs of them (level sets at
    // its nodes, the junctions among them), with the cell's coordinates.
    let cell_view = |c: usize, seen: &[usize]| -> (Vec<CrackInCell>, Vec<[f64; 3]>) {
        let nodes = &mesh.cells[c];
        let cic = seen
            .iter()
            .map(|&g| CrackInCell {
                lsn: nodes.iter().map(|&n| lsn[g][n]).collect(),
                master: masters[g].and_then(|(m, coef)| seen.iter().position(|&s| s == m).map(|p| (p, coef))),
            })
            .collect();
        (cic, nodes.iter().map(|&n| mesh.coords[n]).collect())
    };
    let mut cuttings = BTreeMap::new();
    for &c in &model_cells {
        let seen: Vec<usize> = (0..cracks.len()).filter(|&g| hcells[g].binary_search(&c).is_ok()).collect();
        if seen.is_empty() {
            continue;
        }
        let (cic, coords) = cell_view(c, &seen);
        let cut = topose(mesh.cell_types[c], &coords, &cic)
            .map_err(|e| a.err("FISSURE", format!("cutting cell {}: {e}", mesh.cell_names[c])))?;
        cuttings.insert(c, (seen, cut));
    }
    // The boundary cells of the model (skin elements) with a Heaviside node
    // are X-FEM elements too: TOPOSE cuts them (te0514 with ndime < ndim)
    // and POST_MAIL_XFEM makes sub-cells of them, which moves its node
    // counter. SEG2 / SEG3 and TRIA3 / QUAD4 / TRIA6 / QUAD8 faces are cut;
    // the others are left out, and POST_MAIL_XFEM refuses a model with such
    // a cell (see `visual_of`).
    let mut boundary = BTreeMap::new();
    for (c, el) in elements.iter().enumerate() {
        if !el.as_ref().is_some_and(|e| e.role == crate::concepts::model::Role::Skin)
            || mesh.cell_types[c].dim() >= mesh.dim
            || mesh.cell_types[c] == crate::mesh::CellType::Poi1
        {
            continue;
        }
        let seen: Vec<usize> = (0..cracks.len()).filter(|&g| hcells[g].binary_search(&c).is_ok()).collect();
        if seen.is_empty()
            || !matches!(
                mesh.cell_types[c],
                crate::mesh::CellType::Seg2
                    | crate::mesh::CellType::Tria3
                    | crate::mesh::CellType::Quad4
                    | crate::mesh::CellType::Seg3
                    | crate::mesh::CellType::Tria6
                    | crate::mesh::CellType::Quad8
            )
        {
            continue;
        }
        let (cic, coords) = cell_view(c, &seen);
        let nodes = &mesh.cells[c];
        let mut cut = topose_boundary(mesh.cell_types[c], mesh.dim, &coords, &cic)
            .map_err(|e| a.err("FISSURE", format!("cutting boundary cell {}: {e}", mesh.cell_names[c])))?;
        if mesh.cell_types[c].dim() + 1 == mesh.dim {
            // xoripe: the sub-cells turned outward of the support cell
            // (`utmasu`: here the lowest numbered cell of the mesh's
            // dimension holding all the boundary cell's nodes).
            let support = (0..mesh.ncells())
                .find(|&v| mesh.cell_types[v].dim() == mesh.dim && nodes.iter().all(|n| mesh.cells[v].contains(n)));
            let Some(v) = support else {
                return Err(a.err(
                    "FISSURE",
                    format!("boundary cell {} is on no cell of dimension {} (XFEM2_59)", mesh.cell_names[c], mesh.dim),
                ));
            };
            let centroid = |cs: &[usize]| {
                let mut g = [0.0; 3];
                for &n in cs {
                    for (gj, xj) in g.iter_mut().zip(&mesh.coords[n]) {
                        *gj += xj / cs.len() as f64;
                    }
                }
                g
            };
            let (gb, gp) = (centroid(nodes), centroid(&mesh.cells[v]));
            crate::xfem::topose_linear::orient_boundary(&mut cut, mesh.dim, &[0, 1, 2].map(|j| gb[j] - gp[j]));
        }
        boundary.insert(c, (seen, cut));
    }
    let pretraitements = a.text("PRETRAITEMENTS").unwrap_or("AUTO");
    let mut xm = XfemModel::new(
        &mesh,
        &model_cells,
        cracks.clone(),
        names,
        lsn,
        masters,
        enriched,
        contact,
        cuttings,
        pretraitements,
    )
    .map_err(|e| a.err("FISSURE", e))?;
    xm.boundary = boundary;
    let nsub: usize = xm.cells.values().map(|c| c.cutting.subcells.len()).sum();
    let ncut = xm.cells.values().filter(|c| {
        let mut r = c.regions.clone();
        r.sort_unstable();
        r.dedup();
        r.len() > 1
    });
    let mut s = String::new();
    let _ = writeln!(s, "  MODI_MODELE_XFEM ({} crack(s), CONTACT='{}'):", cracks.len(), xm.contact.name());
    let _ = writeln!(s, "    X-FEM cells                          : {} ({} cut)", xm.cells.len(), ncut.count());
    let _ = writeln!(s, "    sub-cells                            : {nsub}");
    if !xm.boundary.is_empty() {
        let nb: usize = xm.boundary.values().map(|(_, c)| c.subcells.len()).sum();
        let _ = writeln!(
            s,
            "    X-FEM boundary cells                 : {} ({nb} sub-cells, for POST_MAIL_XFEM)",
            xm.boundary.len()
        );
    }
    let enr = xm.node_sets.iter().filter(|v| !v.is_empty()).count();
    let _ = writeln!(s, "    nodes with Heaviside sets            : {enr} ({} sets)", xm.n_sets());
    if !xm.dropped_sets.is_empty() {
        let worst = xm.dropped_sets.iter().map(|d| d.2).fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "    sets removed (sliver regions)        : {} (stiffness share at most {worst:.2e}; PRETRAITEMENTS='{pretraitements}')",
            xm.dropped_sets.len()
        );
    }
    ctx.io.mess(&s);
    let mesh_concept = mo.model()?.mesh_concept.clone();
    Ok(Some(ConceptData::Model(Model { mesh, mesh_concept, elements, xfem: Some(Rc::new(xm)) })))
}

// ------------------------------------------------------------------ POST_MAIL_XFEM / POST_CHAM_XFEM

/// The visual mesh of an X-FEM model (POST_MAIL_XFEM's algorithm).
fn visual_of(model: &crate::concepts::ConceptRef, prefixes: &Prefixes) -> Result<(VisualMesh, Rc<XfemModel>)> {
    let m = model.model()?;
    let Some(xm) = m.xfem.clone() else {
        return Err(Error::runtime(format!("{} is not an X-FEM model (MODI_MODELE_XFEM)", model.label())));
    };
    let mesh = m.current_mesh();
    let model_cells: Vec<usize> = (0..mesh.ncells()).filter(|&c| m.elements[c].is_some()).collect();
    // X-FEM boundary cells MODI_MODELE_XFEM could not cut: their sub-cells
    // would move the node counter, so the names would not be Code_Aster's.
    if let Some(&c) = model_cells.iter().find(|&&c| {
        let t = mesh.cell_types[c];
        t != crate::mesh::CellType::Poi1
            && t.dim() < mesh.dim
            && !xm.boundary.contains_key(&c)
            && mesh.cells[c].iter().any(|&n| xm.enriched.iter().any(|e| e[n]))
    }) {
        return Err(Error::runtime(format!(
            "{}: the boundary cell {} ({}) of the model has a Heaviside-enriched node; Code_Aster cuts it \
             into sub-cells, which is only supported for SEG2, SEG3, TRIA3, QUAD4, TRIA6 and QUAD8 (the node names would differ)",
            model.label(),
            mesh.cell_names[c],
            mesh.cell_types[c].name()
        )));
    }
    // Bulk and boundary parents, in one ascending traversal (xpomax).
    let mut cuttings: BTreeMap<usize, crate::xfem::topose::Cutting> =
        xm.cells.iter().map(|(&c, xc)| (c, xc.cutting.clone())).collect();
    cuttings.extend(xm.boundary.iter().map(|(&c, (_, cut))| (c, cut.clone())));
    let vm = visual_mesh(&mesh, &model_cells, &cuttings, prefixes).map_err(Error::runtime)?;
    Ok((vm, xm))
}

/// POST_MAIL_XFEM: the mesh of the sub-cells, lips doubled, with Code_Aster's node names.
pub fn post_mail_xfem(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mo = a.req_concept("MODELE")?;
    let d = Prefixes::default();
    let text = |k: &str, dflt: &str| a.text(k).unwrap_or(dflt).to_string();
    let prefixes = Prefixes {
        node_x: text("PREF_NOEUD_X", &d.node_x),
        node_m: text("PREF_NOEUD_M", &d.node_m),
        node_p: text("PREF_NOEUD_P", &d.node_p),
        cell_x: text("PREF_MAILLE_X", &d.cell_x),
        group_co: text("PREF_GROUP_CO", &d.group_co),
    };
    let (vm, _) = visual_of(&mo, &prefixes).map_err(|e| e.at(a.span))?;
    let group = vm.mesh.node_groups.get(&prefixes.group_co).map(|g| g.len()).unwrap_or(0);
    ctx.io.mess(&format!(
        "  POST_MAIL_XFEM on {}: {} nodes, {} cells ({} X-FEM parents cut into sub-cells), group {} of {} nodes on the interfaces\n",
        mo.label(),
        vm.mesh.nnodes(),
        vm.mesh.ncells(),
        vm.parents.len(),
        prefixes.group_co,
        group
    ));
    Ok(Some(ConceptData::Mesh(Rc::new(vm.mesh))))
}

/// POST_CHAM_XFEM: DEPL of an X-FEM result on the visual mesh; each node
/// takes the value of its side (the Heaviside tuple of its sub-cell).
pub fn post_cham_xfem(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let rc = a.req_concept("RESULTAT")?;
    let visu = a.req_concept("MODELE_VISU")?;
    let r = rc.result()?;
    let (vm, xm) = visual_of(&r.model, &Prefixes::default()).map_err(|e| e.at(a.span))?;
    let vmesh = visu.model()?.current_mesh();
    if vmesh.nnodes() != vm.mesh.nnodes() {
        return Err(a.err(
            "MODELE_VISU",
            format!(
                "{} is not on the POST_MAIL_XFEM mesh of {} ({} nodes, expected {})",
                visu.label(),
                r.model.label(),
                vmesh.nnodes(),
                vm.mesh.nnodes()
            ),
        ));
    }
    let mesh = r.model.model()?.current_mesh();
    let ndim = mesh.dim;
    let sources = visual_cell_sources(&mesh, &vm);
    let mut steps = Vec::new();
    for st in &r.steps {
        let Some(Field::Node { components, values }) = st.fields.get("DEPL") else {
            return Err(a.err("RESULTAT", format!("{} has no DEPL at order {}", rc.label(), st.nume_ordre)));
        };
        let nc = components.len();
        let idx = |c: &str| components.iter().position(|x| x == c);
        let hm = idx("PRE1").is_some();
        let mut out_comps: Vec<String> = ["DX", "DY", "DZ"][..ndim].iter().map(|s| s.to_string()).collect();
        if hm {
            out_comps.push("PRE1".into());
        }
        // The interface unknowns on the lips (mortar interfaces), after the displacement and pressure.
        let iface = lips::interface_components(components, ndim, hm);
        let first_iface = out_comps.len();
        if let Some(ic) = &iface {
            out_comps.extend(ic.iter().map(|(n, _)| n.clone()));
        }
        let second_block = idx(["D1X", "PR2_FLU"][usize::from(hm)]);
        let no = out_comps.len();
        let mut out = vec![f64::NAN; vm.mesh.nnodes() * no];
        // A cell of each node (for the pressure at mid-side nodes).
        let mut cell_of = vec![usize::MAX; mesh.nnodes()];
        for (c, nodes) in mesh.cells.iter().enumerate() {
            if mesh.cell_types[c].dim() == mesh.dim {
                for &n in nodes {
                    cell_of[n] = c;
                }
            }
        }
        for (v, origin) in vm.origins.iter().enumerate() {
            let row = &mut out[v * no..(v + 1) * no];
            match origin {
                NodeOrigin::Classic(n) => {
                    for d in 0..ndim {
                        row[d] = values[n * nc + d];
                    }
                    if hm {
                        // The pressure is linear on the vertices: at a
                        // mid-side node, the value of the field there.
                        row[ndim] = pressure_at_node(&mesh, cell_of[*n], values, nc, idx("PRE1").unwrap(), *n);
                    }
                }
                NodeOrigin::Xfem { parent, xi, he, id } => {
                    let xc = &xm.cells[parent];
                    xfem_value(&mesh, &xm, *parent, xi, &xc.cracks, he, values, nc, hm, &idx, row);
                    if let Some(ic) = &iface {
                        let lip = lips::at_lip_node(&mesh, &xm, *parent, *id, xi, he, values, nc, ic, second_block);
                        if let Some(v) = lip {
                            row[first_iface..].copy_from_slice(&v);
                        }
                    }
                }
                NodeOrigin::Boundary { parent, he, bulk, bulk_xi, .. } => {
                    // The field of the bulk cell holding the boundary parent,
                    // in the region given by the boundary sub-cell's
                    // Heaviside values (over the boundary cell's cracks).
                    let cracks = &xm.boundary[parent].0;
                    xfem_value(&mesh, &xm, *bulk, bulk_xi, cracks, he, values, nc, hm, &idx, row);
                }
            }
        }
        let mut fields = BTreeMap::new();
        fields.insert("DEPL".to_string(), Field::Node { components: out_comps, values: out });
        // The point fields of an HM result, cell by cell (`xpoajc`, `xpoajm`).
        if hm {
            for name in ["SIEF_ELGA", "VARI_ELGA"] {
                if let Some(Field::Elga { components, cells }) = st.fields.get(name) {
                    let cells = elga_on_visual(&visu, &sources, &vm, cells, components.len())
                        .map_err(|e| a.err("RESULTAT", format!("{name} at order {}: {e}", st.nume_ordre)))?;
                    fields.insert(name.to_string(), Field::Elga { components: components.clone(), cells });
                }
            }
        }
        steps.push(crate::concepts::result::Step { nume_ordre: st.nume_ordre, inst: st.inst, fields });
    }
    // The material of each visual cell is its parent's: CALC_CHAMP on the result needs the elements.
    let material = match &r.material {
        Some(cm) => match &*cm.data() {
            ConceptData::MaterialField(mf) => {
                let cells = sources
                    .iter()
                    .map(|src| match src {
                        CellSource::Classic(c) | CellSource::Sub { parent: c, .. } => {
                            mf.cells.get(*c).cloned().flatten()
                        }
                        CellSource::Boundary => None,
                    })
                    .collect();
                Some(crate::concepts::Concept::new(
                    crate::concepts::ConceptKind::ChamMater,
                    ConceptData::MaterialField(crate::concepts::model::MaterialField {
                        mesh: vmesh.clone(),
                        cells,
                        varc: Vec::new(),
                    }),
                ))
            }
            _ => None,
        },
        None => None,
    };
    Ok(Some(ConceptData::Result(crate::concepts::result::ResultData {
        model: visu,
        material,
        cara_elem: None,
        loads: Vec::new(),
        steps,
        comportement: Vec::new(),
    })))
}

/// Where a cell of the visual mesh comes from: a classic cell of the model, the `k`-th of `n` sub-cells
/// of an X-FEM parent, or the cutting of a boundary parent (no point field).
#[derive(Debug, Clone, Copy)]
enum CellSource {
    Classic(usize),
    Sub { parent: usize, k: usize, n: usize },
    Boundary,
}

/// The source of every cell of the visual mesh: the classic cells first (same names), then the sub-cells
/// of each parent in order (`visual_mesh`).
fn visual_cell_sources(mesh: &crate::mesh::Mesh, vm: &VisualMesh) -> Vec<CellSource> {
    let nsub: usize = vm.parents.iter().map(|p| p.cell_counters.len()).sum();
    let n_classic = vm.mesh.ncells() - nsub;
    let by_name: std::collections::HashMap<&str, usize> =
        mesh.cell_names.iter().enumerate().map(|(c, n)| (n.as_str(), c)).collect();
    let mut out: Vec<CellSource> = (0..n_classic)
        .map(|v| by_name.get(vm.mesh.cell_names[v].as_str()).map_or(CellSource::Boundary, |&c| CellSource::Classic(c)))
        .collect();
    for p in &vm.parents {
        let n = p.cell_counters.len();
        let bulk = mesh.cell_types[p.cell].dim() == mesh.dim;
        out.extend((0..n).map(|k| if bulk { CellSource::Sub { parent: p.cell, k, n } } else { CellSource::Boundary }));
    }
    out
}

/// A point field of the model's cells on the visual cells: a classic cell keeps its values; a sub-cell
/// gets, on every point of its visual element, the mean of its own points in the parent (`xpoajc`).
fn elga_on_visual(
    visu: &crate::concepts::ConceptRef,
    sources: &[CellSource],
    vm: &VisualMesh,
    cells: &[Option<Vec<f64>>],
    nc: usize,
) -> std::result::Result<Vec<Option<Vec<f64>>>, String> {
    let vmodel = visu.model().map_err(|e| e.msg)?;
    let mut out = vec![None; vm.mesh.ncells()];
    for (v, src) in sources.iter().enumerate() {
        let Some(e) = vmodel.elements.get(v).and_then(|e| e.as_ref()) else { continue };
        if vm.mesh.cell_types[v].dim() < vm.mesh.dim {
            continue; // skin elements hold no point field
        }
        let npg2 = crate::stages::core::hm::elga_points(e.modelisation, vm.mesh.cell_types[v])?;
        match *src {
            CellSource::Classic(c) => {
                if let Some(vals) = cells.get(c).and_then(|x| x.as_ref()) {
                    if vals.len() != npg2 * nc {
                        return Err(format!(
                            "cell {} has {} values, {npg2} points of {nc} components expected",
                            vm.mesh.cell_names[v],
                            vals.len()
                        ));
                    }
                    out[v] = Some(vals.clone());
                }
            }
            CellSource::Sub { parent, k, n } => {
                let Some(vals) = cells.get(parent).and_then(|x| x.as_ref()) else { continue };
                let npts = vals.len() / nc;
                if !npts.is_multiple_of(n) {
                    return Err(format!("{npts} points for {n} sub-cells in the parent of {}", vm.mesh.cell_names[v]));
                }
                let npg1 = npts / n;
                let mean: Vec<f64> = (0..nc)
                    .map(|q| (0..npg1).map(|g| vals[(k * npg1 + g) * nc + q]).sum::<f64>() / npg1 as f64)
                    .collect();
                out[v] = Some((0..npg2).flat_map(|_| mean.iter().copied()).collect());
            }
            CellSource::Boundary => {}
        }
    }
    Ok(out)
}

/// The displacement (and the linear pressure) at reference point `xi` of
/// cell `c`, in the region of the sign tuple made of `he` for the cracks
/// `cracks` (model indices) and of the level sets for the others.
#[allow(clippy::too_many_arguments)]
fn xfem_value(
    mesh: &crate::mesh::Mesh,
    xm: &XfemModel,
    c: usize,
    xi: &[f64; 3],
    cracks: &[usize],
    he: &[i32],
    values: &[f64],
    nc: usize,
    hm: bool,
    idx: &dyn Fn(&str) -> Option<usize>,
    row: &mut [f64],
) {
    let ndim = mesh.dim;
    let t = mesh.cell_types[c];
    let nodes = &mesh.cells[c];
    let ff = crate::fem::reference::shape(t, xi);
    let s = crate::xfem::model::point_signs(&xm.lsn, &xm.masters, nodes, &ff, cracks, he);
    let region = crate::xfem::region_code(&s);
    for d in 0..ndim {
        let mut u = 0.0;
        for (a_, &n) in nodes.iter().enumerate() {
            let mut un = values[n * nc + d];
            for j in 0..xm.node_sets[n].len() {
                let psi = xm.psi(n, j, region);
                if psi != 0.0 {
                    let k = idx(&format!("H{}{}", j + 1, ["X", "Y", "Z"][d])).expect("Heaviside component of DEPL");
                    un += psi * values[n * nc + k];
                }
            }
            u += ff[a_] * un;
        }
        row[d] = u;
    }
    if hm {
        // Linear pressure on the vertices.
        let vt = crate::fem::elasticity::vertex_type(t);
        let lin = crate::fem::reference::shape(vt, xi);
        let k = idx("PRE1").unwrap();
        // With its Heaviside parts when the result has them (a prescribed enriched pressure).
        row[ndim] = nodes
            .iter()
            .zip(&lin)
            .map(|(&n, f)| {
                let mut p = values[n * nc + k];
                for j in 0..xm.node_sets[n].len() {
                    let psi = xm.psi(n, j, region);
                    if let Some(kh) = idx(&format!("H{}PRE1", j + 1)).filter(|_| psi != 0.0) {
                        p += psi * values[n * nc + kh];
                    }
                }
                f * p
            })
            .sum();
    }
}

/// The (linear) pressure at a mesh node: its own value at a vertex, the
/// interpolation of the vertices of a cell `c` holding it at a mid-side node.
fn pressure_at_node(mesh: &crate::mesh::Mesh, c: usize, values: &[f64], nc: usize, k: usize, n: usize) -> f64 {
    let v = values[n * nc + k];
    if v.is_finite() || c == usize::MAX {
        return v;
    }
    let t = mesh.cell_types[c];
    let nodes = &mesh.cells[c];
    let Some(l) = nodes.iter().position(|&m| m == n) else { return v };
    let xi = crate::fem::reference::node_coords(t)[l];
    let vt = crate::fem::elasticity::vertex_type(t);
    let lin = crate::fem::reference::shape(vt, &xi);
    nodes.iter().zip(&lin).map(|(&m, f)| f * values[m * nc + k]).sum()
}
