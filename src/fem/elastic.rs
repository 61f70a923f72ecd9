//! Linear elasticity as a [`Physics`]: the displacements `DX DY [DZ]` of every node of the model's bulk
//! cells, the element stiffness of each bulk cell (computed once), the loads of AFFE_CHAR_MECA on its
//! skin and nodes, and the fields DEPL and SIEF_ELGA.

use super::assembly::{Assembler, ElementDofs};
use super::dofs::{component_index, DofNumbering};
use super::elasticity::{self, IsoElastic, Modelisation};
use super::field::Field;
use super::physics::{keep, traction, Failure, Force, Load, Physics, Prediction, StepInfo};
use crate::diag::Error;
use crate::mesh::Mesh;
use std::rc::Rc;

/// The elastic problem of a model.
pub struct Elastic {
    pub mesh: Rc<Mesh>,
    pub modelisation: Modelisation,
    /// The bulk cells, and whether each mesh cell is a skin element of the model (surface loads act there).
    pub bulk: Vec<usize>,
    pub skin: Vec<bool>,
    /// Per mesh cell: the elastic law and the density RHO (0 when not given), for bulk cells.
    pub materials: Vec<Option<(IsoElastic, f64)>>,
    pub numbering: DofNumbering,
    /// The stiffness of each bulk cell (row-major) and its unknowns.
    stiffness: Vec<Vec<f64>>,
    dofs: ElementDofs,
    /// MECA_STATIQUE: one solve per step.
    linear: bool,
    /// SIEF_ELGA is computed with DEPL.
    sief: bool,
    /// The thermal strain of AFFE_VARC's temperature, where the model has one.
    thermal: Option<ThermalStrain>,
}

/// The temperature at the nodes at an instant (NaN where it is not known), or why it cannot be had.
pub type NodalTemperature = Box<dyn Fn(f64) -> Result<Vec<f64>, Error>>;

/// A thermal strain `α (T − T_ref)` of the bulk cells (AFFE_VARC NOM_VARC='TEMP' with ELAS's ALPHA).
pub struct ThermalStrain {
    /// The sources of the temperature (one per AFFE_VARC occurrence).
    pub sources: Vec<NodalTemperature>,
    /// Per mesh cell: α, T_ref and the index of its source.
    pub cells: Vec<Option<(f64, f64, usize)>>,
}

impl ThermalStrain {
    /// `α (T − T_ref)` at the nodes of every cell of `bulk` with a thermal strain at `t` (None elsewhere).
    pub fn theta(&self, mesh: &Mesh, bulk: &[usize], t: f64) -> Result<Vec<Option<Vec<f64>>>, Error> {
        let mut out = vec![None; mesh.cells.len()];
        let mut temps: Vec<Option<Vec<f64>>> = vec![None; self.sources.len()];
        for &c in bulk {
            let Some((alpha, tref, k)) = self.cells[c] else { continue };
            if temps[k].is_none() {
                temps[k] = Some((self.sources[k])(t)?);
            }
            let tk = temps[k].as_ref().expect("just computed");
            let mut v = Vec::with_capacity(mesh.cells[c].len());
            for &n in &mesh.cells[c] {
                let tn = tk.get(n).copied().unwrap_or(f64::NAN);
                if !tn.is_finite() {
                    return Err(Error::runtime(format!(
                        "AFFE_VARC: no temperature at node {} of cell {} at INST={t}",
                        mesh.node_names[n], mesh.cell_names[c]
                    ))
                    .at_keyword("CHAM_MATER"));
                }
                v.push(alpha * (tn - tref));
            }
            out[c] = Some(v);
        }
        Ok(out)
    }
}

impl Elastic {
    /// The element stiffnesses of the bulk cells, computed once (`linear`: MECA_STATIQUE; `sief`: store
    /// SIEF_ELGA).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        mesh: Rc<Mesh>,
        modelisation: Modelisation,
        bulk: Vec<usize>,
        skin: Vec<bool>,
        materials: Vec<Option<(IsoElastic, f64)>>,
        numbering: DofNumbering,
        linear: bool,
        sief: bool,
    ) -> Result<Elastic, Error> {
        let mut stiffness = Vec::with_capacity(bulk.len());
        let mut dofs = ElementDofs::new();
        for &c in &bulk {
            let mat = &materials[c].as_ref().expect("bulk cells have a material").0;
            let ke = elasticity::stiffness(modelisation, mat, mesh.cell_types[c], &coords_of(&mesh, c))
                .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])))?;
            stiffness.push(ke);
            dofs.push(&numbering.cell_dofs(&mesh.cells[c]).expect("bulk cells are numbered"));
        }
        Ok(Elastic {
            mesh,
            modelisation,
            bulk,
            skin,
            materials,
            numbering,
            stiffness,
            dofs,
            linear,
            sief,
            thermal: None,
        })
    }

    /// The same physics, storing SIEF_ELGA with DEPL or not.
    pub fn storing_stresses(mut self, sief: bool) -> Elastic {
        self.sief = sief;
        self
    }

    /// The same physics with a thermal strain.
    pub fn with_thermal(mut self, thermal: ThermalStrain) -> Elastic {
        self.thermal = Some(thermal);
        self
    }

    /// `α (T − T_ref)` at the nodes of every bulk cell with a thermal strain at `t` (None without one).
    fn theta(&self, t: f64) -> Result<Vec<Option<Vec<f64>>>, Error> {
        match &self.thermal {
            Some(th) => th.theta(&self.mesh, &self.bulk, t),
            None => Ok(vec![None; self.mesh.cells.len()]),
        }
    }

    /// The unknowns of a skin cell carrying a surface load.
    fn skin_dofs(&self, load: &str, c: usize) -> Result<Vec<usize>, Error> {
        match self.numbering.cell_dofs(&self.mesh.cells[c]) {
            Some(d) if self.skin[c] => Ok(d),
            _ => {
                Err(excit(format!("load {load}: cell {} is not a boundary cell of the model", self.mesh.cell_names[c])))
            }
        }
    }
}

/// The nodes' coordinates of a cell.
pub fn coords_of(mesh: &Mesh, cell: usize) -> Vec<[f64; 3]> {
    mesh.cells[cell].iter().map(|&n| mesh.coords[n]).collect()
}

fn excit(msg: String) -> Error {
    Error::runtime(msg).at_keyword("EXCIT")
}

impl Physics for Elastic {
    /// The instant of the state (the thermal strain is read there).
    type State = f64;

    fn describe(&self) -> String {
        format!("{}, RELATION='ELAS'", self.modelisation.name())
    }

    fn unknowns(&self) -> usize {
        self.numbering.ndofs()
    }

    fn label(&self, dof: usize) -> String {
        self.numbering.label(dof, Some(&self.mesh))
    }

    fn element_dofs(&self) -> ElementDofs {
        self.dofs.clone()
    }

    fn assemble(
        &self,
        step: &StepInfo,
        x: &[f64],
        _prev: &f64,
        mut tangent: Option<&mut Assembler>,
        fint: &mut [f64],
    ) -> Result<f64, Failure> {
        for (i, ke) in self.stiffness.iter().enumerate() {
            let dofs = self.dofs.get(i);
            let nd = dofs.len();
            for (r, &dr) in dofs.iter().enumerate() {
                fint[dr] += ke[r * nd..(r + 1) * nd].iter().zip(dofs).map(|(k, &dc)| k * x[dc]).sum::<f64>();
            }
            if let Some(asm) = tangent.as_deref_mut() {
                asm.add_matrix(dofs, ke);
            }
        }
        Ok(step.t1)
    }

    fn dof(&self, load: &str, node: usize, component: &str) -> Result<Option<usize>, Error> {
        let md = self.modelisation;
        let comp = component_index(component).filter(|&k| k < md.dim()).ok_or_else(|| {
            excit(format!("load {load}: component {component} is not a dof of a {} model", md.name()))
        })?;
        self.numbering.dof(node, comp).map(Some).ok_or_else(|| {
            excit(format!("load {load}: node {} carries no element of the model", self.mesh.node_names[node]))
        })
    }

    fn position(&self, node: usize) -> [f64; 3] {
        self.mesh.coords[node]
    }

    fn node_name(&self, node: usize) -> String {
        self.mesh.node_names[node].clone()
    }

    fn forces(&self, loads: &[Load], step: &StepInfo, f: &mut [f64]) -> Result<(), Error> {
        let (mesh, md) = (&*self.mesh, self.modelisation);
        let dim = md.dim();
        let mut add = |dofs: &[usize], fe: &[f64]| {
            for (d, v) in dofs.iter().zip(fe) {
                f[*d] += v;
            }
        };
        // The thermal strain acts as the forces ∫ Bᵀ D ε_th.
        for (c, theta) in self.theta(step.t1)?.into_iter().enumerate() {
            let Some(theta) = theta else { continue };
            let mat = &self.materials[c].as_ref().expect("a bulk cell").0;
            let fe = elasticity::thermal_force(md, mat, mesh.cell_types[c], &coords_of(mesh, c), &theta)
                .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])))?;
            add(&self.numbering.cell_dofs(&mesh.cells[c]).expect("a bulk cell"), &fe);
        }
        for load in loads {
            let name = &load.name;
            for item in &load.forces {
                match item {
                    Force::Nodal { node, component, value } => {
                        let k = match *component {
                            "FX" => 0,
                            "FY" => 1,
                            "FZ" => 2,
                            c => return Err(excit(format!("load {name}: FORCE_NODALE {c} is not supported yet"))),
                        };
                        if k >= dim {
                            return Err(excit(format!("load {name}: {component} in a {} model", md.name())));
                        }
                        let d = self.numbering.dof(*node, k).ok_or_else(|| {
                            excit(format!("node {} carries no element of the model", mesh.node_names[*node]))
                        })?;
                        add(&[d], &[value.at(&mesh.coords[*node])?]);
                    }
                    Force::Surface { cells, components } => {
                        if dim < 3 && components.iter().any(|(n, _)| *n == "FZ") {
                            return Err(excit(format!("load {name}: FZ in a {} model", md.name())));
                        }
                        for &c in cells.iter() {
                            let dofs = self.skin_dofs(name, c)?;
                            let err = std::cell::RefCell::new(None);
                            let fx = |x: &[f64; 3], _n: &[f64; 3]| keep(&err, traction(components, x));
                            let fe = elasticity::boundary_force(md, mesh.cell_types[c], &coords_of(mesh, c), &fx)
                                .map_err(|e| Error::runtime(e.to_string()))?;
                            if let Some(e) = err.into_inner() {
                                return Err(e);
                            }
                            add(&dofs, &fe);
                        }
                    }
                    Force::Pressure { cells, value, shear } => {
                        for &c in cells.iter() {
                            let dofs = self.skin_dofs(name, c)?;
                            let xs = coords_of(mesh, c);
                            let pres: Vec<f64> = xs.iter().map(|x| value.at(x)).collect::<Result<_, _>>()?;
                            let cisa: Option<Vec<f64>> = match shear {
                                Some(s) => Some(xs.iter().map(|x| s.at(x)).collect::<Result<_, _>>()?),
                                None => None,
                            };
                            let fe = elasticity::pressure_force(md, mesh.cell_types[c], &xs, &pres, cisa.as_deref())
                                .map_err(|e| Error::runtime(e.to_string()))?;
                            add(&dofs, &fe);
                        }
                    }
                    Force::LipPressure { name: crack, .. } => {
                        return Err(excit(format!(
                            "load {name}: PRES_REP on the lips of {crack} needs the X-FEM model"
                        )))
                    }
                    Force::Flux { .. } => {
                        return Err(excit(format!(
                            "load {name}: FLUX_THM_REP needs a hydro-mechanical model ({} has no pressure)",
                            md.name()
                        )))
                    }
                    heat @ (Force::HeatFlux { .. }
                    | Force::HeatFluxVector { .. }
                    | Force::HeatSource { .. }
                    | Force::Exchange { .. }
                    | Force::Radiation { .. }
                    | Force::HeatFluxOfTemperature { .. }
                    | Force::HeatSourceOfTemperature { .. }
                    | Force::WallExchange { .. }) => {
                        return Err(excit(format!(
                            "load {name}: {} is a thermal load; {} is a mechanical model",
                            heat.keyword(),
                            md.name()
                        )))
                    }
                    Force::Gravity { g, direction, cells } => {
                        let on: Vec<usize> = match cells {
                            Some(c) => c.iter().copied().filter(|c| self.materials[*c].is_some()).collect(),
                            None => self.bulk.clone(),
                        };
                        for c in on {
                            let rho = self.materials[c].as_ref().expect("a bulk cell").1;
                            if rho == 0.0 {
                                return Err(excit(format!(
                                    "load {name}: PESANTEUR on cell {}, whose material gives no RHO",
                                    mesh.cell_names[c]
                                )));
                            }
                            let acc = direction.map(|d| rho * g * d);
                            let fe = elasticity::body_force(md, mesh.cell_types[c], &coords_of(mesh, c), &|_x| acc)
                                .map_err(|e| Error::runtime(e.to_string()))?;
                            add(&self.numbering.cell_dofs(&mesh.cells[c]).expect("a bulk cell"), &fe);
                        }
                    }
                }
            }
        }
        Ok(())
    }

    fn fields(&self, u: &[f64], t: &f64) -> Result<Vec<(String, Field)>, Error> {
        let (mesh, md) = (&*self.mesh, self.modelisation);
        let dim = md.dim();
        let mut depl = vec![f64::NAN; mesh.coords.len() * dim];
        for (d, v) in u.iter().enumerate() {
            let (node, k) = self.numbering.node_comp(d);
            depl[node * dim + k] = *v;
        }
        let comps: Vec<String> = ["DX", "DY", "DZ"][..dim].iter().map(|s| s.to_string()).collect();
        let mut fields = vec![("DEPL".to_string(), Field::Node { components: comps, values: depl })];
        if self.sief {
            let mut cells = vec![None; mesh.cells.len()];
            let thetas = self.theta(*t)?;
            for &c in &self.bulk {
                let ue: Vec<f64> =
                    self.numbering.cell_dofs(&mesh.cells[c]).expect("a bulk cell").iter().map(|&d| u[d]).collect();
                let mat = &self.materials[c].as_ref().expect("a bulk cell").0;
                let (t_c, x_c) = (mesh.cell_types[c], coords_of(mesh, c));
                let g = match &thetas[c] {
                    Some(theta) => elasticity::gauss_fields_thermal(md, mat, t_c, &x_c, &ue, theta),
                    None => elasticity::gauss_fields(md, mat, t_c, &x_c, &ue),
                }
                .map_err(|e| Error::runtime(e.to_string()))?;
                cells[c] = Some(g.sig.iter().flat_map(|s| s[..md.nsig()].to_vec()).collect());
            }
            let names = md.sigma_names().iter().map(|s| s.to_string()).collect();
            fields.push(("SIEF_ELGA".to_string(), Field::Elga { components: names, cells }));
        }
        Ok(fields)
    }

    fn prediction(&self) -> Prediction {
        Prediction::Imposed
    }

    fn linear(&self) -> bool {
        self.linear
    }
}
