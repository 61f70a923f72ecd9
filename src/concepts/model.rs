//! Models, materials, material fields and mechanical loads: what AFFE_MODELE,
//! DEFI_MATERIAU, AFFE_MATERIAU and AFFE_CHAR_MECA(_F) produce.

use super::ConceptRef;
use crate::mesh::{CellType, Mesh};
use std::collections::BTreeMap;
use std::rc::Rc;

/// What a modelisation puts on a cell: the bulk element, or a boundary
/// (skin) element that carries loads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    Bulk,
    Skin,
}

/// The modelisations AFFE_MODELE accepts (Code_Aster's MODELISATION names).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Modelling {
    ThreeD,
    ThreeDHm,
    ThreeDHmd,
    ThreeDSi,
    ThreeDDil,
    DPlan,
    CPlan,
    Axis,
    DPlanHm,
    DPlanHmd,
    AxisHm,
    AxisHmd,
    DPlanSi,
    AxisSi,
    ThreeDHms,
    ThreeDHmSi,
    DPlanHms,
    DPlanHmSi,
    AxisHms,
    /// Saturated THM: the HM elements with the temperature `TEMP` on their vertices.
    DPlanThm,
    DPlanThmd,
    DPlanThms,
    AxisThm,
    AxisThmd,
    AxisThms,
    ThreeDThm,
    ThreeDThmd,
    ThreeDThms,
    /// PHENOMENE='THERMIQUE': PLAN, AXIS, 3D and their _DIAG variants.
    Thermal(crate::thermal::Modelisation),
}

impl Modelling {
    const ALL: [(Modelling, &'static str); 28] = [
        (Modelling::ThreeD, "3D"),
        (Modelling::ThreeDHm, "3D_HM"),
        (Modelling::ThreeDHmd, "3D_HMD"),
        (Modelling::ThreeDSi, "3D_SI"),
        (Modelling::ThreeDDil, "3D_DIL"),
        (Modelling::DPlan, "D_PLAN"),
        (Modelling::CPlan, "C_PLAN"),
        (Modelling::Axis, "AXIS"),
        (Modelling::DPlanHm, "D_PLAN_HM"),
        (Modelling::DPlanHmd, "D_PLAN_HMD"),
        (Modelling::AxisHm, "AXIS_HM"),
        (Modelling::AxisHmd, "AXIS_HMD"),
        (Modelling::DPlanSi, "D_PLAN_SI"),
        (Modelling::AxisSi, "AXIS_SI"),
        (Modelling::ThreeDHms, "3D_HMS"),
        (Modelling::ThreeDHmSi, "3D_HM_SI"),
        (Modelling::DPlanHms, "D_PLAN_HMS"),
        (Modelling::DPlanHmSi, "D_PLAN_HM_SI"),
        (Modelling::AxisHms, "AXIS_HMS"),
        (Modelling::DPlanThm, "D_PLAN_THM"),
        (Modelling::DPlanThmd, "D_PLAN_THMD"),
        (Modelling::DPlanThms, "D_PLAN_THMS"),
        (Modelling::AxisThm, "AXIS_THM"),
        (Modelling::AxisThmd, "AXIS_THMD"),
        (Modelling::AxisThms, "AXIS_THMS"),
        (Modelling::ThreeDThm, "3D_THM"),
        (Modelling::ThreeDThmd, "3D_THMD"),
        (Modelling::ThreeDThms, "3D_THMS"),
    ];

    /// From Code_Aster's name; None for a modelisation we do not know.
    pub fn from_name(s: &str) -> Option<Modelling> {
        Self::ALL.iter().find(|(_, n)| *n == s).map(|(m, _)| *m)
    }

    /// From a phenomenon and Code_Aster's name under it.
    pub fn of_phenomenon(phenomenon: &str, s: &str) -> Option<Modelling> {
        match phenomenon {
            "MECANIQUE" => Self::from_name(s),
            "THERMIQUE" => crate::thermal::Modelisation::from_name(s).map(Modelling::Thermal),
            _ => None,
        }
    }

    /// The thermal modelisation, if it is one.
    pub fn thermal(self) -> Option<crate::thermal::Modelisation> {
        if let Modelling::Thermal(m) = self {
            Some(m)
        } else {
            None
        }
    }

    /// Code_Aster's name.
    pub fn name(self) -> &'static str {
        if let Modelling::Thermal(m) = self {
            return m.name();
        }
        Self::ALL.iter().find(|(m, _)| *m == self).map(|(_, n)| *n).unwrap_or("?")
    }

    /// The space dimension of its bulk elements.
    pub fn dim(self) -> usize {
        use Modelling::*;
        match self {
            ThreeD | ThreeDHm | ThreeDHmd | ThreeDSi | ThreeDDil | ThreeDHms | ThreeDHmSi | ThreeDThm | ThreeDThmd
            | ThreeDThms => 3,
            Thermal(m) => m.dim(),
            _ => 2,
        }
    }

    /// Saturated thermo-hydro-mechanics (the _THM, _THMD and _THMS variants).
    pub fn is_thm(self) -> bool {
        use Modelling::*;
        matches!(
            self,
            DPlanThm | DPlanThmd | DPlanThms | AxisThm | AxisThmd | AxisThms | ThreeDThm | ThreeDThmd | ThreeDThms
        )
    }

    /// Saturated hydro-mechanics (the _HM, _HMD, _HMS and _HM_SI variants), with or without the
    /// temperature ([`Modelling::is_thm`]).
    pub fn is_hm(self) -> bool {
        use Modelling::*;
        self.is_thm()
            || matches!(
                self,
                ThreeDHm
                    | ThreeDHmd
                    | ThreeDHms
                    | ThreeDHmSi
                    | DPlanHm
                    | DPlanHmd
                    | DPlanHms
                    | DPlanHmSi
                    | AxisHm
                    | AxisHmd
                    | AxisHms
            )
    }

    /// The cells an element of this modelisation is built on: HM elements exist on quadratic cells
    /// only (volume cells and their skins), the others on every cell of the right dimension.
    pub fn accepts(self, t: crate::mesh::CellType) -> bool {
        use crate::mesh::CellType::*;
        if let Modelling::Thermal(m) = self {
            return m.accepts_volume(t) || m.accepts_skin(t);
        }
        !self.is_hm() || matches!(t, Seg3 | Tria6 | Quad8 | Tetra10 | Pyram13 | Penta15 | Hexa20)
    }

    /// The mechanical kernel of `fem` it computes with: the pure ones, and the skeleton of the HM
    /// ones; None where we have no kernel (the _SI and _DIL variants).
    pub fn mechanics(self) -> Option<crate::fem::elasticity::Modelisation> {
        use crate::fem::elasticity::Modelisation as M;
        use Modelling::*;
        match self {
            ThreeD | ThreeDHm | ThreeDHmd | ThreeDHms | ThreeDHmSi | ThreeDThm | ThreeDThmd | ThreeDThms => {
                Some(M::ThreeD)
            }
            DPlan | DPlanHm | DPlanHmd | DPlanHms | DPlanHmSi | DPlanThm | DPlanThmd | DPlanThms => Some(M::DPlan),
            CPlan => Some(M::CPlan),
            Axis | AxisHm | AxisHmd | AxisHms | AxisThm | AxisThmd | AxisThms => Some(M::Axis),
            _ => None,
        }
    }
}

impl std::fmt::Display for Modelling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The element a model assigns to one cell.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Element {
    pub phenomenon: String,
    pub modelisation: Modelling,
    pub role: Role,
}

#[derive(Debug)]
pub struct Model {
    pub mesh: Rc<Mesh>,
    /// The mesh concept (for names in messages and results).
    pub mesh_concept: ConceptRef,
    /// Per cell: its element, or None where the model puts nothing.
    pub elements: Vec<Option<Element>>,
    /// MODI_MODELE_XFEM: the enrichment, cuttings and cracks.
    pub xfem: Option<Rc<crate::xfem::model::XfemModel>>,
}

/// The role of a cell type under a modelisation of dimension `dim`, or None
/// when the modelisation puts no element on it (as Code_Aster does with, e.g.,
/// POI1 cells under D_PLAN).
pub fn role_of(dim: usize, t: CellType) -> Option<Role> {
    match (dim, t.dim()) {
        (3, 3) | (2, 2) => Some(Role::Bulk),
        (3, 2) | (2, 1) => Some(Role::Skin),
        _ => None,
    }
}

impl Model {
    /// The mesh as it is now: DEFI_GROUP and MODI_MAILLAGE change a mesh in
    /// place after the model was made, and the model must see it.
    pub fn current_mesh(&self) -> Rc<Mesh> {
        match &*self.mesh_concept.data() {
            super::ConceptData::Mesh(m) => m.clone(),
            _ => self.mesh.clone(),
        }
    }

    /// The dimension of the model's bulk elements.
    pub fn dim(&self) -> usize {
        self.elements
            .iter()
            .flatten()
            .filter(|e| e.role == Role::Bulk)
            .map(|e| e.modelisation.dim())
            .max()
            .unwrap_or(self.mesh.dim)
    }
    /// The modelisations used, each once.
    pub fn modelisations(&self) -> Vec<Modelling> {
        let mut v: Vec<Modelling> = self.elements.iter().flatten().map(|e| e.modelisation).collect();
        v.sort();
        v.dedup();
        v
    }
    /// A model of PHENOMENE='THERMIQUE'.
    pub fn is_thermal(&self) -> bool {
        self.elements.iter().flatten().any(|e| e.modelisation.thermal().is_some())
    }
}

/// A material parameter: a real, a function of a variable, or a text.
#[derive(Debug, Clone)]
pub enum MatValue {
    Real(f64),
    Func(ConceptRef),
    Text(String),
}

/// DEFI_MATERIAU: behaviours (ELAS, RUPT_FRAG, THM_*, ...) and their parameters.
#[derive(Debug, Clone, Default)]
pub struct Material {
    pub behaviours: BTreeMap<String, BTreeMap<String, MatValue>>,
    /// Simple keywords at the top level (COMP_THM, ...).
    pub options: BTreeMap<String, String>,
}

impl Material {
    /// A real parameter of a behaviour, if given as a real.
    pub fn real(&self, behaviour: &str, param: &str) -> Option<f64> {
        match self.behaviours.get(behaviour)?.get(param)? {
            MatValue::Real(v) => Some(*v),
            _ => None,
        }
    }
}

/// AFFE_MATERIAU: a material per cell.
#[derive(Debug)]
pub struct MaterialField {
    pub mesh: Rc<Mesh>,
    /// Per cell: the material concept assigned, if any.
    pub cells: Vec<Option<ConceptRef>>,
    /// AFFE_VARC: the command variables on cells (the temperature).
    pub varc: Vec<Varc>,
}

/// One occurrence of AFFE_VARC: a command variable on cells, from a result or a field.
#[derive(Debug, Clone)]
pub struct Varc {
    /// NOM_VARC.
    pub name: String,
    pub cells: Vec<usize>,
    pub source: VarcSource,
    /// VALE_REF: the value at which the variable strains nothing.
    pub vale_ref: Option<f64>,
    /// PROL_GAUCHE and PROL_DROITE of EVOL: 'EXCLU', 'CONSTANT' or 'LINEAIRE'.
    pub prol: (String, String),
}

/// Where a command variable comes from.
#[derive(Debug, Clone)]
pub enum VarcSource {
    /// EVOL: a result, its field NOM_CHAM interpolated in time — at the instant FONC_INST gives for the
    /// current one, when given.
    Evol { result: ConceptRef, field: String, fonc_inst: Option<ConceptRef> },
    /// CHAM_GD: a field on nodes, the same at every instant.
    Field(ConceptRef),
}

/// A load value: a real, or a function of space (and time) evaluated later.
#[derive(Debug, Clone)]
pub enum LoadValue {
    Real(f64),
    Func(ConceptRef),
}

/// One item of a mechanical load.
#[derive(Debug, Clone)]
pub enum LoadItem {
    /// DDL_IMPO: a component of a node prescribed.
    Dof { node: usize, component: String, value: LoadValue },
    /// FORCE_NODALE: a force on a node.
    NodalForce { node: usize, component: String, value: LoadValue },
    /// FORCE_CONTOUR / FORCE_FACE: a force per unit length/area on skin cells.
    SurfaceForce { cells: Vec<usize>, components: Vec<(String, LoadValue)> },
    /// PRES_REP: a pressure on skin cells, and in the plane a shear along them (CISA_2D).
    Pressure { cells: Vec<usize>, value: LoadValue, shear: Option<LoadValue> },
    /// PRES_REP with FISSURE: a pressure on both lips of an X-FEM crack of the model (its index there).
    CrackPressure { crack: usize, name: String, value: LoadValue },
    /// PESANTEUR: gravity of magnitude `g` along `direction`, on the cells.
    Gravity { g: f64, direction: [f64; 3], cells: Option<Vec<usize>> },
    /// FLUX_THM_REP FLUN_HYDR1: a fluid mass flux entering through skin cells (kg m⁻² s⁻¹).
    /// With `heat`: FLUX_THM_REP FLUN, the heat flux entering a THM model (W m⁻²).
    FluxThm { cells: Vec<usize>, value: LoadValue, heat: bool },
    /// LIAISON_DDL: Σ coef·u(node, component) = value.
    Relation { terms: Vec<(usize, String, f64)>, value: LoadValue },
    /// AFFE_CHAR_THER(_F): a heat flux, exchange or source.
    Heat(HeatItem),
}

/// AFFE_CHAR_MECA(_F): the load items on a model.
#[derive(Debug)]
pub struct Load {
    pub model: ConceptRef,
    pub items: Vec<LoadItem>,
    /// AFFE_CHAR_MECA_F: values are functions.
    pub functional: bool,
}

/// A ZONE of DEFI_CONTACT FORMULATION='XFEM' with ALGO_CONT='CZM'.
#[derive(Debug, Clone)]
pub struct ContactZone {
    /// FISS_MAIT, and its name for messages.
    pub crack: Rc<crate::xfem::Crack>,
    pub crack_name: String,
    /// INTEGRATION='GAUSS' with ORDRE_INT.
    pub order: i64,
    /// RELATION (CZM_LIN_MIX).
    pub relation: String,
}

/// DEFI_CONTACT: the contact (cohesive) zones of an X-FEM model.
#[derive(Debug)]
pub struct Contact {
    pub model: ConceptRef,
    pub zones: Vec<ContactZone>,
    pub iter_cont_maxi: i64,
}

// ------------------------------------------------------------------ AFFE_CHAR_THER(_F)

/// A heat load on cells (a boundary flux density is positive when heat enters the body).
#[derive(Debug, Clone)]
pub enum HeatItem {
    /// FLUX_REP FLUN: a normal heat flux entering through skin cells.
    NormalFlux { cells: Vec<usize>, value: LoadValue },
    /// FLUX_REP FLUX_X FLUX_Y FLUX_Z: a flux vector φ, whose density on skin cells is φ · n.
    FluxVector { cells: Vec<usize>, components: [Option<LoadValue>; 3] },
    /// ECHANGE: h (T_ext − T) through skin cells.
    Exchange { cells: Vec<usize>, coef_h: LoadValue, temp_ext: LoadValue },
    /// SOURCE SOUR: a volume source on bulk cells.
    Source { cells: Vec<usize>, value: LoadValue },
    /// RAYONNEMENT: σ ε ((T_ext + 273.15)⁴ − (T + 273.15)⁴) through skin cells.
    Radiation { cells: Vec<usize>, sigma: LoadValue, epsilon: LoadValue, temp_ext: LoadValue },
    /// FLUX_NL FLUN: a flux entering through skin cells, a function of the temperature.
    NonlinearFlux { cells: Vec<usize>, flux: ConceptRef },
    /// SOUR_NL SOUR: a volume source, a function of the temperature (and of space and time).
    NonlinearSource { cells: Vec<usize>, source: ConceptRef },
    /// ECHANGE_PAROI: h (T₂ − T₁) between paired skin cells; each pair is a cell of GROUP_MA_1 and the
    /// nodes of GROUP_MA_2 facing its nodes, in its node order.
    WallExchange { pairs: Vec<(usize, Vec<usize>)>, coef_h: LoadValue },
}

impl HeatItem {
    /// The keyword of AFFE_CHAR_THER(_F) that makes it, for messages.
    pub fn keyword(&self) -> &'static str {
        match self {
            HeatItem::NormalFlux { .. } | HeatItem::FluxVector { .. } => "FLUX_REP",
            HeatItem::Exchange { .. } => "ECHANGE",
            HeatItem::Source { .. } => "SOURCE",
            HeatItem::Radiation { .. } => "RAYONNEMENT",
            HeatItem::NonlinearFlux { .. } => "FLUX_NL",
            HeatItem::NonlinearSource { .. } => "SOUR_NL",
            HeatItem::WallExchange { .. } => "ECHANGE_PAROI",
        }
    }
}

/// AFFE_CARA_ELEM: what it gives the cells of a model. So far the local frames of MASSIF (the axes of
/// anisotropic materials), per cell of the mesh (None: the global frame).
#[derive(Debug)]
pub struct CaraElem {
    pub model: ConceptRef,
    pub massif: Vec<Option<crate::fem::frame::Frame>>,
}

impl CaraElem {
    /// The frame of a cell's material.
    pub fn frame(&self, cell: usize) -> crate::fem::frame::Frame {
        self.massif.get(cell).copied().flatten().unwrap_or(crate::fem::frame::Frame::GLOBAL)
    }
}
