//! What an X-FEM solve is built from, checked once before the first instant: the modelisation, the
//! behaviour, the materials, the cohesive zones of DEFI_CONTACT with their multiplier packets, and the
//! numbering of the unknowns.

use crate::concepts::model::{Contact, Material, MaterialField, Modelling, Role};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::fem::elasticity::Modelisation;
use crate::mesh::Mesh;
use crate::solve::{Method, SolverOptions};
use crate::stages::core::hm::HmProblem;
use crate::stages::core::problem::mat_param;
use crate::stages::core::settings::Settings;
use crate::xfem::czm::CzmParams;
use crate::xfem::discrete::Exchange;
use crate::xfem::discrete::{Facet, XDofs};
use crate::xfem::model::{ContactKind, XfemModel};
use crate::xfem::mortar;
use std::collections::{BTreeMap, BTreeSet};
use std::rc::Rc;

/// The checked data of one X-FEM solve.
pub struct Setup {
    pub mesh: Rc<Mesh>,
    pub xm: Rc<XfemModel>,
    /// The bulk cells of the model.
    pub model_cells: Vec<usize>,
    /// MODELISATION as Code_Aster names it, its mechanical part, and whether it is hydro-mechanical.
    pub modelisation: Modelling,
    pub md: Modelisation,
    pub hm: bool,
    pub opts: SolverOptions,
    pub chmat: ConceptRef,
    mats: Vec<Option<ConceptRef>>,
    pub zones: Vec<Zone>,
    pub iter_cont_maxi: i64,
    pub xd: XDofs,
    /// The interface hydraulics, when the scene leaves hydraulic unknowns free (`flow`).
    pub flow: Option<Flow>,
    /// Per crack, its facets (`discrete::facets`), built on first use.
    facets: Vec<std::cell::OnceCell<Vec<Facet>>>,
}

impl Setup {
    pub fn ndim(&self) -> usize {
        self.md.dim()
    }

    /// The number of unknowns: the mechanical ones, and the flow's with free hydraulics.
    pub fn nunk(&self) -> usize {
        self.flow.as_ref().map_or(self.xd.n, |f| f.n)
    }

    /// The facets of crack `g` (model order): the faces of its sub-cells on the interface, a point being on
    /// it within 1e-9 of the mesh's largest extent.
    pub fn facets(&self, g: usize) -> &[Facet] {
        self.facets[g].get_or_init(|| {
            let (lo, hi) = self.mesh.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
            let lonref = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
            crate::xfem::discrete::facets(&self.mesh, &self.xm, g, 1e-9 * lonref)
        })
    }

    /// The material of a cell.
    pub fn material(&self, cfg: &Settings, c: usize) -> Result<Rc<Material>> {
        material_of(cfg, &self.mats, &self.chmat, &self.mesh, c)
    }
}

fn material_of(
    cfg: &Settings,
    mats: &[Option<ConceptRef>],
    chmat: &ConceptRef,
    mesh: &Mesh,
    c: usize,
) -> Result<Rc<Material>> {
    let mc = mats.get(c).cloned().flatten().ok_or_else(|| {
        cfg.err("CHAM_MATER", format!("cell {} has no material in {}", mesh.cell_names[c], chmat.label()))
    })?;
    let d = mc.data();
    match &*d {
        ConceptData::Material(m) => Ok(m.clone()),
        _ => Err(cfg.err("CHAM_MATER", format!("{} is not a material", mc.label()))),
    }
}

pub fn setup(cfg: &Settings, model: &ConceptRef) -> Result<Setup> {
    let (mesh, xm, elements) = {
        let m = model.model()?;
        let Some(xm) = m.xfem.clone() else {
            return Err(cfg.err("MODELE", format!("{} is not an X-FEM model", model.label())));
        };
        (m.current_mesh(), xm, m.elements.clone())
    };
    let model_cells: Vec<usize> =
        (0..mesh.ncells()).filter(|&c| elements[c].as_ref().is_some_and(|e| e.role == Role::Bulk)).collect();
    let mut modelisations: Vec<Modelling> =
        model_cells.iter().filter_map(|&c| elements[c].as_ref().map(|e| e.modelisation)).collect();
    modelisations.sort();
    modelisations.dedup();
    if modelisations.len() != 1 {
        return Err(cfg.err(
            "MODELE",
            format!("several modelisations in one X-FEM model are not supported yet: {modelisations:?}"),
        ));
    }
    let modelisation = modelisations[0];
    let (md, hm) = match modelisation {
        Modelling::DPlan | Modelling::CPlan | Modelling::ThreeD | Modelling::DPlanHm | Modelling::ThreeDHm => {
            (modelisation.mechanics().expect("a mechanical kernel"), modelisation.is_hm())
        }
        m => return Err(cfg.err("MODELE", format!("an X-FEM {m} model is not supported yet"))),
    };
    check_behaviour(cfg, modelisation, hm)?;
    // The tangent is a symmetric saddle point (multipliers λ, w, μ beside the displacements): LDLᵀ.
    let mut opts = cfg.solveur.opts;
    opts.method = Method::Ldlt;

    let chmat = cfg.chmat()?;
    let mats: Vec<Option<ConceptRef>> = match &*chmat.data() {
        ConceptData::MaterialField(MaterialField { cells, .. }) => cells.clone(),
        _ => return Err(cfg.err("CHAM_MATER", format!("{} is not a material field", chmat.label()))),
    };
    let material = |c: usize| material_of(cfg, &mats, &chmat, &mesh, c);
    let (zones, iter_cont_maxi) = zones(cfg, model, &mesh, &xm, &material)?;
    let mut npk = vec![0; xm.cracks.len()];
    for z in &zones {
        npk[z.crack] = z.packets.len();
    }
    let xd = XDofs::new(&mesh, &model_cells, &xm, md.dim(), &npk);
    let ncracks = xm.cracks.len();
    Ok(Setup {
        mesh,
        xm,
        model_cells,
        modelisation,
        md,
        hm,
        opts,
        chmat,
        mats,
        zones,
        iter_cont_maxi,
        xd,
        flow: None,
        facets: (0..ncracks).map(|_| std::cell::OnceCell::new()).collect(),
    })
}

/// COMPORTEMENT: the elastic part of the kit; the hydraulic laws act on the flow when the scene leaves
/// hydraulic unknowns free (`flow`), else only on eliminated unknowns.
fn check_behaviour(cfg: &Settings, modelisation: Modelling, hm: bool) -> Result<()> {
    for b in &cfg.behaviours {
        match (b.relation.as_str(), hm) {
            ("ELAS", false) => {}
            ("KIT_HM", true) => {
                let kit = &b.kit;
                if kit.first().map(String::as_str) != Some("ELAS") {
                    return Err(b.err(
                        "RELATION_KIT",
                        format!("only an ELAS skeleton is supported yet in KIT_HM (got {kit:?})"),
                    ));
                }
                for k in &kit[1..] {
                    if !matches!(k.as_str(), "LIQU_SATU" | "HYDR_UTIL") {
                        return Err(b.err("RELATION_KIT", format!("'{k}' is not supported yet")));
                    }
                }
            }
            (rel, _) => {
                return Err(b.err(
                    "RELATION",
                    format!("RELATION='{rel}' on an X-FEM {modelisation} model is not supported yet"),
                ))
            }
        }
    }
    if cfg.schema_thm && !hm {
        return Err(cfg.err("SCHEMA_THM", format!("SCHEMA_THM needs a hydro-mechanical model ({modelisation} is not)")));
    }
    // With every hydraulic unknown eliminated (`conditions`, which stops otherwise) the time scheme of
    // the flow plays no part: the run log says so.
    Ok(())
}

/// The cohesive zones of CONTACT (DEFI_CONTACT): per zone its crack, RUPT_FRAG law, facet rule and
/// multiplier packets (VERSION2), and ITER_CONT_MAXI.
fn zones(
    cfg: &Settings,
    model: &ConceptRef,
    mesh: &Mesh,
    xm: &XfemModel,
    material: &dyn Fn(usize) -> Result<Rc<Material>>,
) -> Result<(Vec<Zone>, i64)> {
    let mut zones: Vec<Zone> = Vec::new();
    let mut iter_cont_maxi = 0;
    if let Some(cc) = &cfg.contact {
        let d = cc.data();
        let ConceptData::Contact(Contact { zones: cz, model: cmodel, iter_cont_maxi: icm }) = &*d else {
            return Err(cfg.err("CONTACT", format!("{} is not a contact definition", cc.label())));
        };
        if !Rc::ptr_eq(cmodel, model) {
            return Err(cfg.err("CONTACT", format!("{} is defined on another model ({})", cc.label(), cmodel.label())));
        }
        iter_cont_maxi = *icm;
        // Contact cells of every crack (xtyele), over the model's cracks.
        let topo: Vec<mortar::CrackTopo> = xm
            .cracks
            .iter()
            .map(|k| mortar::CrackTopo { lsn: &k.lsn, status: &k.status, heaviside_cells: &k.heaviside_cells })
            .collect();
        let contact = mortar::contact_cells(mesh, &topo);
        if xm.contact != ContactKind::Mortar {
            return Err(cfg.err("CONTACT", "the cohesive zones need MODI_MODELE_XFEM CONTACT='MORTAR'"));
        }
        for z in cz {
            let g = xm.cracks.iter().position(|k| Rc::ptr_eq(k, &z.crack)).ok_or_else(|| {
                cfg.err("CONTACT", format!("FISS_MAIT={} is not a crack of {}", z.crack_name, model.label()))
            })?;
            if zones.iter().any(|o| o.crack == g) {
                return Err(cfg.err("CONTACT", format!("two zones on {}", z.crack_name)));
            }
            // RUPT_FRAG of the cells the crack crosses (one material).
            let mut params: Option<CzmParams> = None;
            for (&c, xc) in &xm.cells {
                if !xc.cracks.contains(&g) {
                    continue;
                }
                let m = material(c)?;
                let name = &mesh.cell_names[c];
                let get = |p: &str| -> Result<f64> {
                    mat_param(&m, "RUPT_FRAG", p, name)?.ok_or_else(|| {
                        cfg.err("CHAM_MATER", format!("cell {name}: RELATION='CZM_LIN_MIX' needs RUPT_FRAG {p}"))
                    })
                };
                let p = CzmParams::new(get("SIGM_C")?, get("GC")?, get("PENA_LAGR")?)
                    .map_err(|e| cfg.err("CHAM_MATER", format!("cell {name}: RUPT_FRAG: {e}")))?;
                match params {
                    None => params = Some(p),
                    Some(q) if q != p => {
                        return Err(cfg.err(
                            "CHAM_MATER",
                            format!(
                                "{}: several RUPT_FRAG materials along one interface are not supported yet",
                                z.crack_name
                            ),
                        ))
                    }
                    _ => {}
                }
            }
            let params = params.ok_or_else(|| cfg.err("CONTACT", format!("{} crosses no cell", z.crack_name)))?;
            let cells = &contact[g];
            let master = xm.masters[g].map(|(m, c)| (xm.lsn[m].as_slice(), c));
            let edges = mortar::cut_edges(mesh, cells, &xm.lsn[g], master);
            let pk = mortar::vital_edges(&edges, &mortar::islands(mesh, &xm.lsn[g]));
            zones.push(Zone {
                crack: g,
                params,
                order: z.order,
                packets: pk.packets.clone(),
                packet_of: pk.packet_of_node.clone(),
                edges: edges.iter().map(|e| (e.a.min(e.b), e.a.max(e.b))).collect(),
                cells: cells.clone(),
            });
        }
    }
    // In the model's crack order whatever DEFI_CONTACT's order: the interface unknowns of a node in
    // several cracks' packets are numbered crack by crack (LAGS_*, LAG2_*, ...), and the conditions
    // between blocks count the cracks before a zone's own.
    zones.sort_by_key(|z| z.crack);
    Ok((zones, iter_cont_maxi))
}

/// A cohesive zone: its crack, law, facet rule and multiplier packets.
pub struct Zone {
    pub crack: usize,
    pub params: CzmParams,
    pub order: i64,
    pub packets: Vec<Vec<usize>>,
    pub packet_of: BTreeMap<usize, usize>,
    pub edges: BTreeSet<(usize, usize)>,
    /// The contact cells of the crack (`MAILFISS.CONT`), which carry its cohesive variables (COHE_ELEM).
    pub cells: Vec<usize>,
}

/// The names of nodes.
pub fn names(mesh: &Mesh, nodes: &[usize]) -> Vec<String> {
    nodes.iter().map(|&n| mesh.node_names[n].clone()).collect()
}

/// The flow unknowns and operators of one solve.
pub struct Flow {
    pub hp: HmProblem,
    /// All unknowns: the mechanical ones, the pressures, the fracture unknowns.
    pub n: usize,
    /// Per bulk cell of `hp` (in `hp.elements()` order), its element's unknowns in the full numbering.
    pub dofs: Vec<Vec<usize>>,
    /// Per node: PRE1, and per enrichment set H<j>PRE1 (vertices only).
    pub pre1: Vec<Option<usize>>,
    pub hpre1: Vec<Vec<Option<usize>>>,
    /// The first pressure unknown and the count of pressures.
    pub first_pressure: usize,
    pub npressure: usize,
    /// Per zone and packet: p_f (q⁺ at +1, q⁻ at +2).
    pub fracture: Vec<Vec<usize>>,
    /// Per zone: the hydraulic couplings of its cells with the full unknowns of their pressure columns.
    pub exchanges: Vec<Vec<(Exchange, Vec<usize>)>>,
    /// Per zone: ρ₀ of the liquid along the interface (storage in the fracture rows' reactions).
    pub rho_f: Vec<f64>,
    pub theta: f64,
}
