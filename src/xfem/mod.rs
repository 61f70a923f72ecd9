//! X-FEM: cracks and interfaces described by level sets (DEFI_FISS_XFEM).
//!
//! A [`Crack`] holds what Code_Aster's `fiss_xfem` data structure holds for
//! an interface: the nodal normal level set, the junctions on master cracks
//! (`JONFISS`/`JONCOEF`), the node status (`STNO`) and the enriched cells
//! (`MAILFISS.HEAV`). The computations live in [`levelset`]; the region
//! codes of nodes over a list of cracks (`xlsjon`, `xcalc_code`) are here.

pub mod conditions;
pub mod cutting;
pub mod czm;
pub mod discrete;
pub mod levelset;
pub mod model;
pub mod mortar;
pub mod postmail;
pub mod topose;
pub mod topose_linear;

use crate::mesh::Mesh;
use std::rc::Rc;

pub use levelset::{region_code, Status};

/// A junction: the crack this one branches on and the side where the branch exists.
#[derive(Debug, Clone)]
pub struct Junction {
    pub crack: Rc<Crack>,
    /// The master's name (DEFI_FISS_XFEM result), for messages.
    pub name: String,
    /// c = −sign(φ_master) at the node nearest POINT: the branch exists where c·φ_master < 0.
    pub coef: f64,
    /// Declared under JONCTION (true) or reached through a declared master's own junctions.
    pub declared: bool,
}

/// A crack or interface defined by DEFI_FISS_XFEM.
pub struct Crack {
    /// The name of the mesh concept the crack was defined on, for messages.
    pub mesh_name: String,
    pub mesh: Rc<Mesh>,
    /// TYPE_DISCONTINUITE: only 'INTERFACE' for now.
    pub discontinuity: String,
    /// Normal level set φ per node, after Code_Aster's adjustment near zero.
    pub lsn: Vec<f64>,
    /// Tangential level set per node (−1 everywhere for an interface).
    pub lst: Vec<f64>,
    /// Number of level-set values the adjustment set to zero.
    pub adjusted: usize,
    /// Cells of GROUP_MA_ENRI (all cells by default).
    pub enri_cells: Vec<usize>,
    /// The junctions (JONFISS order: declared masters first).
    pub junctions: Vec<Junction>,
    /// The mesh node nearest to JONCTION's POINT.
    pub junction_node: Option<usize>,
    /// Cells where φ changes sign over the vertices.
    pub cut_cells: Vec<usize>,
    /// Node status (crack-tip values never occur for an interface).
    pub status: Vec<Status>,
    /// Cells with at least one Heaviside-enriched node.
    pub heaviside_cells: Vec<usize>,
}

impl std::fmt::Debug for Crack {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Crack")
            .field("mesh", &self.mesh_name)
            .field("discontinuity", &self.discontinuity)
            .field("junctions", &self.junctions.iter().map(|j| (j.name.as_str(), j.coef)).collect::<Vec<_>>())
            .field("enriched_nodes", &self.enriched_nodes().len())
            .field("heaviside_cells", &self.heaviside_cells.len())
            .finish()
    }
}

impl Crack {
    /// Is the node Heaviside-enriched by this crack?
    pub fn enriched(&self, node: usize) -> bool {
        self.status[node].heaviside()
    }

    /// The Heaviside-enriched nodes, in node order.
    pub fn enriched_nodes(&self) -> Vec<usize> {
        (0..self.status.len()).filter(|&n| self.enriched(n)).collect()
    }

    /// The first declared master crack and its coefficient, if this crack branches.
    pub fn master(&self) -> Option<(&Rc<Crack>, f64)> {
        self.junctions.iter().find(|j| j.declared).map(|j| (&j.crack, j.coef))
    }
}

/// Signs of a node over a list of cracks, with the junction zeroing
/// (`xlsjon`): a junction counts when its master is in the list.
pub fn node_signs(cracks: &[Rc<Crack>], node: usize) -> Vec<i32> {
    let lsn: Vec<&[f64]> = cracks.iter().map(|k| k.lsn.as_slice()).collect();
    let master: Vec<Option<(usize, f64)>> = cracks
        .iter()
        .map(|k| {
            k.junctions.iter().find_map(|j| cracks.iter().position(|c| Rc::ptr_eq(c, &j.crack)).map(|m| (m, j.coef)))
        })
        .collect();
    levelset::node_signs(&lsn, &master, node)
}

/// A node's own sub-domain code over a list of cracks (`xlsjon` then `xcalc_code`).
pub fn node_code(cracks: &[Rc<Crack>], node: usize) -> i32 {
    region_code(&node_signs(cracks, node))
}

/// What went wrong building a crack, and the keyword to blame.
#[derive(Debug, Clone)]
pub struct BuildError {
    /// "FISSURE" or "POINT" (of JONCTION), "DEFI_FISS", or "" (no keyword).
    pub keyword: &'static str,
    pub msg: String,
}

fn fail(keyword: &'static str, msg: impl Into<String>) -> BuildError {
    BuildError { keyword, msg: msg.into() }
}

/// Build an interface from its nodal normal level set, as DEFI_FISS_XFEM
/// does after evaluating FONC_LN: adjustment near zero (`xajuls`), junction
/// coefficients from the node nearest `point` (`xinlsj`), cut cells, node
/// status and enriched cells (`xenrch`). `enri_cells` is GROUP_MA_ENRI
/// (None: every cell); `masters` the cracks of JONCTION/FISSURE with their names.
pub fn build_interface(
    mesh_name: String,
    mesh: Rc<Mesh>,
    mut lsn: Vec<f64>,
    enri_cells: Option<Vec<usize>>,
    masters: &[(String, Rc<Crack>)],
    point: Option<&[f64]>,
) -> std::result::Result<Crack, BuildError> {
    let nn = mesh.nnodes();
    let lst = vec![-1.0; nn];
    let adjusted = levelset::adjust_normal(&mesh, &mut lsn);
    let enri_cells = enri_cells.unwrap_or_else(|| (0..mesh.cells.len()).collect());
    let mut enri_nodes: Vec<usize> = enri_cells.iter().flat_map(|&c| mesh.cells[c].iter().copied()).collect();
    enri_nodes.sort_unstable();
    enri_nodes.dedup();

    // Junctions (xinlsj).
    let mut junctions: Vec<Junction> = Vec::new();
    let mut junction_node = None;
    if !masters.is_empty() {
        let point = point.ok_or_else(|| fail("POINT", "POINT is required with FISSURE"))?;
        if point.len() < mesh.dim {
            return Err(fail("POINT", format!("POINT needs {} coordinates in a {}D mesh", mesh.dim, mesh.dim)));
        }
        let node = levelset::nearest_node(&mesh, point).ok_or_else(|| fail("POINT", "the mesh has no node"))?;
        junction_node = Some(node);
        for (i, (fname, k)) in masters.iter().enumerate() {
            // A declared crack that a later declared one branches on is reached through it.
            let inside_later =
                masters[i + 1..].iter().any(|(_, g)| g.junctions.iter().any(|j| Rc::ptr_eq(&j.crack, k)));
            if inside_later {
                continue;
            }
            if k.lsn.len() != nn {
                return Err(fail("FISSURE", format!("{fname} is defined on another mesh")));
            }
            let v = k.lsn[node];
            if v == 0.0 {
                return Err(fail(
                    "POINT",
                    format!(
                        "the node nearest POINT, {}, lies on {} (level set 0): the side of the junction is undefined",
                        mesh.node_names[node], fname
                    ),
                ));
            }
            junctions.push(Junction { crack: k.clone(), name: fname.clone(), coef: -v.signum(), declared: true });
        }
        // The cracks the masters branch on, transitively, with their own coefficients.
        let mut start = 0;
        while start < junctions.len() {
            let end = junctions.len();
            for i in start..end {
                let inner = junctions[i].crack.junctions.clone();
                for k in inner {
                    if !junctions.iter().any(|e| Rc::ptr_eq(&e.crack, &k.crack)) {
                        junctions.push(Junction { declared: false, ..k });
                    }
                }
            }
            start = end;
        }
        if junctions.len() > 10 {
            return Err(fail("FISSURE", "more than 10 cracks in the junction chain"));
        }
    }
    let mut jls = Vec::with_capacity(junctions.len());
    for j in &junctions {
        let k = &j.crack;
        jls.push(levelset::JunctionLevelSets {
            side: k.lsn.iter().map(|v| j.coef * v).collect(),
            lst: if j.declared { vec![-1.0; nn] } else { k.lst.clone() },
        });
    }

    // Enrichment (xenrch: xmafis, xstano, xstama).
    let cut_cells = levelset::cut_cells(&mesh, &enri_cells, &lsn);
    if cut_cells.is_empty() {
        return Err(fail(
            "DEFI_FISS",
            "the interface does not cross the mesh (or coincides with its boundary): no cell is cut",
        ));
    }
    let status = levelset::node_status(&mesh, &enri_nodes, &cut_cells, &lsn, &lst, &jls);
    if let Some(n) = (0..nn).find(|&n| status[n].tip()) {
        return Err(fail(
            "",
            format!(
                "node {} gets a crack-tip status, which an interface cannot have (no point of the interface \
                 in the cut cells around it)",
                mesh.node_names[n]
            ),
        ));
    }
    let heaviside_cells = levelset::heaviside_cells(&mesh, &status);
    Ok(Crack {
        mesh_name,
        mesh,
        discontinuity: "INTERFACE".into(),
        lsn,
        lst,
        adjusted,
        enri_cells,
        junctions,
        junction_node,
        cut_cells,
        status,
        heaviside_cells,
    })
}
