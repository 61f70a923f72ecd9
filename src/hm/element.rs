//! The saturated HM element: displacement on every node of the quadratic cell, pressure on its
//! vertices with the linear cell's functions (`PRE1` on vertices only), integrated as the variant says.
//!
//! Local unknowns node by node: node `a` carries `DX DY [DZ]`, then `PRE1` when it is a vertex (the
//! first `nvertices` nodes in Code_Aster's order). The internal forces are Code_Aster's (`assthm`):
//!
//! - displacement rows: `∫ Bᵀ (σ' + σ_p) − ∫ N g M`,
//! - pressure rows: `∫ −N̂ (M⁺ − M⁻) + Δt ∇N̂ · (θ w⁺ + (1 − θ) w⁻)`,
//!
//! so that `F_int = F_ext` with the boundary flux `F_ext = −Δt ∫ N̂ q` ([`flux_load`]).

use super::law::{update, Derivatives, IntegrationFailure, PointState};
use super::material::Biot;
use super::thermal::{self, ThermalMat};
use crate::fem::elasticity::{vertex_type, IsoElastic, Modelisation};
use crate::fem::quadrature::{aster_rule, QuadratureRule};
use crate::fem::reference::shape_and_deriv;
use crate::mesh::CellType;

/// The kinematics of an HM modelisation: plane strain, axisymmetric, 3D.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinematics {
    DPlan,
    Axis,
    ThreeD,
}

impl Kinematics {
    pub fn dim(self) -> usize {
        if self == Kinematics::ThreeD {
            3
        } else {
            2
        }
    }
    /// The mechanical modelisation of `fem` with the same strain components.
    pub fn mechanics(self) -> Modelisation {
        match self {
            Kinematics::DPlan => Modelisation::DPlan,
            Kinematics::Axis => Modelisation::Axis,
            Kinematics::ThreeD => Modelisation::ThreeD,
        }
    }
}

/// How the element integrates (Code_Aster's `INTTHM` attribute of the modelisation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// `*_HM`: every term at the points of the RIGI family (FPG9, FPG6, FPG27, FPG15, FPG21).
    Full,
    /// `*_HM_SI`: every term at the points of a reduced family (FPG4, FPG3, FPG8, FPG4, FPG6).
    Reduced,
    /// `*_HMD`: every term at the vertices only (`NOEU_S`): a diagonal storage matrix.
    Lumped,
    /// `*_HMS`: mechanics and the Darcy flux at the reduced family's points, the storage at the
    /// vertices (`FPG4NOS`, ...).
    Selective,
}

/// Which terms a point integrates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Role {
    /// σ' + σ_p and the weight of the added fluid mass (displacement rows).
    pub mech: bool,
    /// The Darcy flux (pressure rows, ∇N̂).
    pub flux: bool,
    /// The change of fluid mass (pressure rows, N̂).
    pub storage: bool,
}

const ALL: Role = Role { mech: true, flux: true, storage: true };

/// The geometry of one integration point of a cell.
#[derive(Debug, Clone)]
pub struct Point {
    /// Reference coordinates.
    pub xi: [f64; 3],
    /// Weight × |det J| (× r in AXIS).
    pub w: f64,
    pub x: [f64; 3],
    /// Displacement functions (all nodes) and their real gradients.
    pub n: Vec<f64>,
    pub dn: Vec<[f64; 3]>,
    /// Pressure functions (vertices) and their real gradients.
    pub nh: Vec<f64>,
    pub dnh: Vec<[f64; 3]>,
    /// AXIS: the point lies on the axis (the hoop strain is then ∂u_r/∂r).
    pub on_axis: bool,
    pub role: Role,
}

/// The integration points of one cell, with the layout of its local unknowns.
#[derive(Debug, Clone)]
pub struct CellPoints {
    pub kin: Kinematics,
    pub variant: Variant,
    pub cell: CellType,
    /// The Code_Aster families whose points these are (`"FPG9"`, `"NOEU_S"`, `"FPG4+NOEU_S"`).
    pub family: String,
    pub points: Vec<Point>,
    /// The first local unknown of each displacement function (a node's, or an enriched copy of it).
    pub first: Vec<usize>,
    /// The local unknown of each pressure function (a vertex's, or an enriched copy of it).
    pub pfirst: Vec<usize>,
    /// THM: the local unknown of the temperature of each vertex (empty in HM).
    pub tfirst: Vec<usize>,
    pub ndof: usize,
}

/// The families of a variant on a cell: (family of the Gauss points, with vertex points?).
fn families(variant: Variant, t: CellType) -> Result<(Option<&'static str>, bool), String> {
    use CellType::*;
    let full = match t {
        Quad8 => "FPG9",
        Tria6 => "FPG6",
        Hexa20 => "FPG27",
        Tetra10 => "FPG15",
        Penta15 => "FPG21",
        Pyram13 => "FPG10",
        _ => return Err(format!("HM elements are built on quadratic cells, not on {}", t.name())),
    };
    let reduced = match t {
        Quad8 => "FPG4",
        Tria6 => "FPG3",
        Hexa20 => "FPG8",
        Tetra10 => "FPG4",
        Penta15 => "FPG6",
        _ => "FPG10",
    };
    Ok(match variant {
        Variant::Full => (Some(full), false),
        Variant::Reduced => (Some(reduced), false),
        Variant::Lumped => (None, true),
        Variant::Selective => (Some(reduced), true),
    })
}

/// The integration points of a variant on a cell (the points of SIEF_ELGA, in their order) with
/// Code_Aster's name of their family (`FPG9`, `NOEU_S`, `FPG4NOS` for the Gauss points then the
/// vertices of an `*_HMS` element).
pub fn point_family(variant: Variant, t: CellType) -> Result<(String, QuadratureRule), String> {
    let (gauss, vertices) = families(variant, t)?;
    let mut rules = Vec::new();
    if let Some(f) = gauss {
        rules.push(aster_rule(t, f).ok_or_else(|| format!("no {f} rule on {}", t.name()))?);
    }
    if vertices {
        rules.push(aster_rule(t, "NOEU_S").ok_or_else(|| format!("no NOEU_S rule on {}", t.name()))?);
    }
    let name = match (gauss, vertices) {
        (Some(g), true) => format!("{g}NOS"),
        (Some(g), false) => g.to_string(),
        _ => "NOEU_S".to_string(),
    };
    let mut rule = rules[0].clone();
    for r in &rules[1..] {
        rule.points.extend_from_slice(&r.points);
        rule.weights.extend_from_slice(&r.weights);
    }
    rule.name = name.clone();
    Ok((name, rule))
}

/// The number of integration points of a variant on a cell (the points of SIEF_ELGA).
pub fn point_count(variant: Variant, t: CellType) -> Result<usize, String> {
    let (gauss, vertices) = families(variant, t)?;
    let g = match gauss {
        Some(f) => aster_rule(t, f).ok_or_else(|| format!("no {f} rule on {}", t.name()))?.len(),
        None => 0,
    };
    Ok(g + if vertices { t.nvertices() } else { 0 })
}

/// The shape functions of a cell and of its vertex cell at `xi`, their real gradients, the point's
/// position and the Jacobian determinant.
#[allow(clippy::type_complexity)]
fn geometry(
    dim: usize,
    t: CellType,
    coords: &[[f64; 3]],
    xi: &[f64; 3],
) -> Option<(Vec<f64>, Vec<[f64; 3]>, Vec<f64>, Vec<[f64; 3]>, [f64; 3], f64)> {
    let (nno, nv) = (t.nnodes(), t.nvertices());
    let mut n = vec![0.0; nno];
    let mut dref = vec![[0.0; 3]; nno];
    shape_and_deriv(t, xi, &mut n, &mut dref);
    let mut nh = vec![0.0; nv];
    let mut dhref = vec![[0.0; 3]; nv];
    shape_and_deriv(vertex_type(t), xi, &mut nh, &mut dhref);
    let mut j = nalgebra::Matrix3::<f64>::identity();
    let mut x = [0.0; 3];
    for a in 0..nno {
        for i in 0..3 {
            x[i] += n[a] * coords[a][i];
        }
    }
    for r in 0..dim {
        for c in 0..dim {
            j[(r, c)] = (0..nno).map(|a| coords[a][r] * dref[a][c]).sum();
        }
    }
    let det = j.determinant();
    let inv = j.try_inverse().filter(|_| det.is_finite() && det != 0.0)?;
    let grad = |d: &[f64; 3]| -> [f64; 3] {
        let mut g = [0.0; 3];
        for (i, gi) in g.iter_mut().enumerate().take(dim) {
            *gi = (0..dim).map(|c| d[c] * inv[(c, i)]).sum();
        }
        g
    };
    let dn = dref.iter().map(grad).collect();
    let dnh = dhref.iter().map(grad).collect();
    Some((n, dn, nh, dnh, x, det))
}

/// A function of an enriched element: node `node`'s function (the displacement's, or the vertex
/// function for a pressure) times a factor of the enrichment `set` (None: the standard function, factor
/// 1), its unknowns from local index `first` (`dim` of them for a displacement, one for a pressure).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    pub node: usize,
    pub set: Option<usize>,
    pub first: usize,
}

impl CellPoints {
    /// The points of a cell with node coordinates `coords` (Code_Aster's node order).
    pub fn new(kin: Kinematics, variant: Variant, t: CellType, coords: &[[f64; 3]]) -> Result<CellPoints, String> {
        let (gauss, vertices) = families(variant, t)?;
        if t.dim() != kin.dim() {
            return Err(format!("a {} cell is not a volume cell of a {}D model", t.name(), kin.dim()));
        }
        let mut rules = Vec::new();
        if let Some(f) = gauss {
            let r = aster_rule(t, f).ok_or_else(|| format!("no {f} rule on {}", t.name()))?;
            let role = if variant == Variant::Selective { Role { storage: false, ..ALL } } else { ALL };
            rules.push((r, role));
        }
        if vertices {
            let r = aster_rule(t, "NOEU_S").ok_or_else(|| format!("no NOEU_S rule on {}", t.name()))?;
            let role =
                if variant == Variant::Selective { Role { mech: false, flux: false, storage: true } } else { ALL };
            rules.push((r, role));
        }
        let family = match (gauss, vertices) {
            (Some(g), true) => format!("{g}+NOEU_S"),
            (Some(g), false) => g.to_string(),
            _ => "NOEU_S".to_string(),
        };
        let dim = kin.dim();
        let (nno, nv) = (t.nnodes(), t.nvertices());
        // AXIS: a point on the axis is weighed with 1e-3 of the cell's largest radius (Code_Aster's rule).
        let r_max = coords.iter().map(|c| c[0]).fold(0.0, f64::max);
        let mut points = Vec::new();
        for (rule, role) in &rules {
            for (k, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
                let (n, dn, nh, dnh, x, det) = geometry(dim, t, coords, xi).ok_or_else(|| {
                    format!("degenerate {} cell: singular Jacobian at point {} of {}", t.name(), k + 1, rule.name)
                })?;
                let mut wd = w * det.abs();
                let mut on_axis = false;
                if kin == Kinematics::Axis {
                    if x[0] < -1e-12 * r_max {
                        return Err(format!("AXIS: point {} of the cell has radius {:e} < 0", k + 1, x[0]));
                    }
                    if x[0] <= 1e-12 * r_max {
                        on_axis = true;
                        wd *= 1e-3 * r_max;
                    } else {
                        wd *= x[0];
                    }
                }
                points.push(Point { xi: *xi, w: wd, x, n, dn, nh, dnh, on_axis, role: *role });
            }
        }
        let mut first = Vec::with_capacity(nno);
        let mut pfirst = Vec::with_capacity(nv);
        let mut ndof = 0;
        for a in 0..nno {
            first.push(ndof);
            if a < nv {
                pfirst.push(ndof + dim);
            }
            ndof += dim + usize::from(a < nv);
        }
        Ok(CellPoints { kin, variant, cell: t, family, points, first, pfirst, tfirst: Vec::new(), ndof })
    }

    /// The points of an enriched cell (X-FEM): `points` (reference coordinates, weight × |det J| already
    /// in real measure, a tag such as the sub-domain the point lies in) integrate every term (`XINT`);
    /// the displacement functions are `ucols` (a node's function times `factor(node, set, tag)`), the
    /// pressure functions `pcols` (a vertex's function times the same factor), on `ndof` local unknowns.
    /// The factors are constant per tag (Heaviside functions): their gradients vanish.
    #[allow(clippy::too_many_arguments)]
    pub fn enriched(
        kin: Kinematics,
        t: CellType,
        coords: &[[f64; 3]],
        points: &[([f64; 3], f64, i32)],
        ucols: &[Column],
        pcols: &[Column],
        ndof: usize,
        factor: &dyn Fn(usize, Option<usize>, i32) -> f64,
    ) -> Result<CellPoints, String> {
        if kin == Kinematics::Axis {
            return Err("enriched AXIS elements are not supported yet".into());
        }
        if t.dim() != kin.dim() {
            return Err(format!("a {} cell is not a volume cell of a {}D model", t.name(), kin.dim()));
        }
        let dim = kin.dim();
        let mut out = Vec::with_capacity(points.len());
        for (k, &(xi, w, tag)) in points.iter().enumerate() {
            let (n, dn, nh, dnh, x, _) = geometry(dim, t, coords, &xi).ok_or_else(|| {
                format!("degenerate {} cell: singular Jacobian at sub-cell point {}", t.name(), k + 1)
            })?;
            let f = |c: &Column| match c.set {
                None => 1.0,
                Some(_) => factor(c.node, c.set, tag),
            };
            let scale = |v: [f64; 3], s: f64| v.map(|x| x * s);
            let un = ucols.iter().map(|c| f(c) * n[c.node]).collect();
            let udn = ucols.iter().map(|c| scale(dn[c.node], f(c))).collect();
            let pn = pcols.iter().map(|c| f(c) * nh[c.node]).collect();
            let pdn = pcols.iter().map(|c| scale(dnh[c.node], f(c))).collect();
            out.push(Point { xi, w, x, n: un, dn: udn, nh: pn, dnh: pdn, on_axis: false, role: ALL });
        }
        Ok(CellPoints {
            kin,
            variant: Variant::Full,
            cell: t,
            family: "XINT".to_string(),
            points: out,
            first: ucols.iter().map(|c| c.first).collect(),
            pfirst: pcols.iter().map(|c| c.first).collect(),
            tfirst: Vec::new(),
            ndof,
        })
    }

    /// The THM layout: node by node `DX DY [DZ]`, then `PRE1 TEMP` on a vertex (the temperature is
    /// interpolated as the pressure, with the vertex functions).
    pub fn with_temperature(mut self) -> CellPoints {
        let dim = self.kin.dim();
        let nv = self.pfirst.len();
        let (mut first, mut pfirst, mut tfirst, mut ndof) = (Vec::new(), Vec::new(), Vec::new(), 0);
        for a in 0..self.first.len() {
            first.push(ndof);
            ndof += dim;
            if a < nv {
                pfirst.push(ndof);
                tfirst.push(ndof + 1);
                ndof += 2;
            }
        }
        self.first = first;
        self.pfirst = pfirst;
        self.tfirst = tfirst;
        self.ndof = ndof;
        self
    }

    /// The local index of the temperature of vertex `a` (THM).
    pub fn t(&self, a: usize) -> usize {
        self.tfirst[a]
    }

    /// The temperature and its gradient at a point (THM; zero in HM).
    fn temperature_at(&self, pt: &Point, ue: &[f64]) -> (f64, [f64; 3]) {
        let mut t = 0.0;
        let mut gt = [0.0; 3];
        for (v, &d) in self.tfirst.iter().enumerate() {
            t += pt.nh[v] * ue[d];
            for (g, dn) in gt.iter_mut().zip(&pt.dnh[v]) {
                *g += dn * ue[d];
            }
        }
        (t, gt)
    }

    /// The local index of displacement component `i` of node `a`.
    pub fn u(&self, a: usize, i: usize) -> usize {
        self.first[a] + i
    }
    /// The local index of the pressure of vertex `a` (of pressure function `a`).
    pub fn p(&self, a: usize) -> usize {
        self.pfirst[a]
    }

    /// The strain-displacement rows of node `a` at point `pt`: `b[c][i]`, strain component `c`
    /// (engineering), displacement component `i`.
    fn b(&self, pt: &Point, a: usize) -> [[f64; 3]; 6] {
        let d = pt.dn[a];
        let mut b = [[0.0; 3]; 6];
        b[0][0] = d[0];
        b[1][1] = d[1];
        b[3][0] = d[1];
        b[3][1] = d[0];
        match self.kin {
            Kinematics::ThreeD => {
                b[2][2] = d[2];
                b[4][0] = d[2];
                b[4][2] = d[0];
                b[5][1] = d[2];
                b[5][2] = d[1];
            }
            Kinematics::Axis => b[2][0] = if pt.on_axis { d[0] } else { pt.n[a] / pt.x[0] },
            Kinematics::DPlan => {}
        }
        b
    }

    /// Strain, pressure and pressure gradient at a point from the local unknowns.
    fn kinematics_at(&self, pt: &Point, ue: &[f64]) -> ([f64; 6], f64, [f64; 3]) {
        let dim = self.kin.dim();
        let mut eps = [0.0; 6];
        for a in 0..self.first.len() {
            let b = self.b(pt, a);
            for (c, e) in eps.iter_mut().enumerate() {
                *e += (0..dim).map(|i| b[c][i] * ue[self.u(a, i)]).sum::<f64>();
            }
        }
        let mut p = 0.0;
        let mut gp = [0.0; 3];
        for (v, (nh, dnh)) in pt.nh.iter().zip(&pt.dnh).enumerate() {
            let pv = ue[self.p(v)];
            p += nh * pv;
            for i in 0..3 {
                gp[i] += dnh[i] * pv;
            }
        }
        (eps, p, gp)
    }

    /// The nodal forces of stored point states (Code_Aster's FORC_NODA of an HM or THM element, `fnothm`,
    /// `fonoda`), over the Gauss points (those that integrate the mechanics): on the displacements
    /// `∫ Bᵀ (σ' + σ_p) − N g M`; with the step's `dt` and the previous states (an order after the first)
    /// on the pressures `∫ −N̂ (M − M⁻) + Δt ∇N̂ · w` and on the temperatures
    /// `∫ Δt N̂ w · g + Δt ∇N̂ · (h w + q)` (the end-of-step values, no θ; no storage of heat).
    pub fn stored_forces(&self, states: &[PointState], prev: Option<(&[PointState], f64)>, g: &[f64; 3]) -> Vec<f64> {
        let dim = self.kin.dim();
        let mut f = vec![0.0; self.ndof];
        for (k, pt) in self.points.iter().enumerate().filter(|(_, pt)| pt.role.mech) {
            let s = &states[k];
            for a in 0..self.first.len() {
                let b = self.b(pt, a);
                for i in 0..dim {
                    let bs: f64 = (0..6).map(|c| b[c][i] * (s.sig[c] + s.sigp[c])).sum();
                    f[self.u(a, i)] += pt.w * (bs - pt.n[a] * g[i] * s.m);
                }
            }
            let Some((pv, dt)) = prev else { continue };
            let dm = s.m - pv[k].m;
            for (v, &r) in self.pfirst.iter().enumerate() {
                let div: f64 = (0..dim).map(|x| pt.dnh[v][x] * s.w[x]).sum();
                f[r] += pt.w * (-pt.nh[v] * dm + dt * div);
            }
            let wg: f64 = (0..dim).map(|x| s.w[x] * g[x]).sum();
            for (v, &r) in self.tfirst.iter().enumerate() {
                let div: f64 = (0..dim).map(|x| pt.dnh[v][x] * (s.h * s.w[x] + s.qt[x])).sum();
                f[r] += pt.w * dt * (pt.nh[v] * wg + div);
            }
        }
        f
    }

    /// The strain (engineering shear) at a point from the local unknowns.
    pub fn strain(&self, pt: &Point, ue: &[f64]) -> [f64; 6] {
        self.kinematics_at(pt, ue).0
    }

    /// The state of every point for the unknowns `ue`, from the initial state of the material (the
    /// strain and pressure of `ue` become the reference of the next step; no stress, no mass change).
    pub fn initial_states(&self, mat: &Biot, ue: &[f64]) -> Vec<PointState> {
        self.points
            .iter()
            .map(|pt| {
                let (eps, p, _) = self.kinematics_at(pt, ue);
                let temp = self.temperature_at(pt, ue).0;
                PointState { eps, p, temp, ..PointState::initial(mat) }
            })
            .collect()
    }
}

/// A time step as the element sees it.
#[derive(Debug, Clone, Copy)]
pub struct StepData {
    pub dt: f64,
    /// `SCHEMA_THM PARM_THETA`.
    pub theta: f64,
    /// The fluid's gravity at the end of the step (`PESA_*` × `PESA_MULT`).
    pub gravity: [f64; 3],
}

/// The element's internal forces, tangent (row-major, `ndof × ndof`) and the states of its points at
/// the end of the step.
#[derive(Debug, Clone)]
pub struct ElementOutput {
    pub fint: Vec<f64>,
    pub k: Vec<f64>,
    pub states: Vec<PointState>,
}

/// The element's internal forces and tangent for the local unknowns `ue` at the end of the step,
/// from the states `prev` of its points at the start.
pub fn element(
    cp: &CellPoints,
    mat: &Biot,
    ue: &[f64],
    prev: &[PointState],
    step: &StepData,
) -> Result<ElementOutput, IntegrationFailure> {
    element_with(cp, mat, None, ue, prev, step)
}

/// The element of [`element`], THM when `th` gives the thermal parameters (the layout of
/// [`CellPoints::with_temperature`]): the energy rows are Code_Aster's (`thmComputeResidual`),
///
/// - temperature rows: `∫ N̂ [Δt w̄·g − ΔM h̄ − ΔQ'] + Δt ∇N̂ · (θ (h w + q)⁺ + (1 − θ) (h w + q)⁻)`,
///
/// x̄ = θx⁺ + (1 − θ)x⁻, the storage part (`ΔM h̄ + ΔQ'`) where the variant integrates the mass
/// storage, the rest where it integrates the flux.
#[allow(clippy::needless_range_loop)]
pub fn element_with(
    cp: &CellPoints,
    mat: &Biot,
    th: Option<&ThermalMat>,
    ue: &[f64],
    prev: &[PointState],
    step: &StepData,
) -> Result<ElementOutput, IntegrationFailure> {
    let dim = cp.kin.dim();
    // The displacement and pressure functions: the nodes and vertices, and their enriched copies.
    let (nno, nv, nd) = (cp.first.len(), cp.pfirst.len(), cp.ndof);
    let d = IsoElastic::new(mat.e, mat.nu).hooke(cp.kin.mechanics());
    let g = step.gravity;
    let mut fint = vec![0.0; nd];
    let mut k = vec![0.0; nd * nd];
    let mut states = Vec::with_capacity(cp.points.len());
    for (pt, prev) in cp.points.iter().zip(prev) {
        let (eps, p, gp) = cp.kinematics_at(pt, ue);
        let (s, der, tder) = match th {
            None => {
                let (s, der) = update(mat, &d, prev, &eps, p, &gp, &g)?;
                (s, der, None)
            }
            Some(th) => {
                let (t, gt) = cp.temperature_at(pt, ue);
                let axis = cp.kin == Kinematics::Axis;
                let (s, der, td) = thermal::update(mat, th, &d, prev, &eps, p, &gp, t, &gt, &g, axis)?;
                (s, der, Some(td))
            }
        };
        let Derivatives { dsigp_dp, dm_depsv, dm_dp, dw_dgradp, dw_dp } = der;
        let w = pt.w;
        let bs: Vec<[[f64; 3]; 6]> = (0..nno).map(|a| cp.b(pt, a)).collect();
        // ∂ε_v/∂u of every local displacement unknown.
        let trace = |a: usize, i: usize| bs[a][0][i] + bs[a][1][i] + bs[a][2][i];
        if pt.role.mech {
            let sig: [f64; 6] = std::array::from_fn(|c| s.sig[c] + s.sigp[c]);
            // D B of every node, and the weight of the added fluid mass's derivative.
            let db: Vec<[[f64; 3]; 6]> = bs
                .iter()
                .map(|b| std::array::from_fn(|c| std::array::from_fn(|j| (0..6).map(|e| d[c][e] * b[e][j]).sum())))
                .collect();
            let gm = g.iter().any(|x| *x != 0.0);
            for a in 0..nno {
                for i in 0..dim {
                    let r = cp.u(a, i);
                    fint[r] += w * ((0..6).map(|c| bs[a][c][i] * sig[c]).sum::<f64>() - pt.n[a] * g[i] * s.m);
                    // The strain components this unknown acts on (B is sparse).
                    let nz: Vec<(usize, f64)> =
                        (0..6).filter(|&c| bs[a][c][i] != 0.0).map(|c| (c, bs[a][c][i])).collect();
                    let row = &mut k[r * nd..(r + 1) * nd];
                    // K_uu: Bᵀ D B − N g ∂M/∂ε_v (m·B).
                    for b in 0..nno {
                        let col = cp.first[b];
                        for j in 0..dim {
                            let mut v: f64 = nz.iter().map(|&(c, bv)| bv * db[b][c][j]).sum();
                            if gm {
                                v -= pt.n[a] * g[i] * dm_depsv * trace(b, j);
                            }
                            row[col + j] += w * v;
                        }
                    }
                    // K_up: Bᵀ (∂σ_p/∂p m) N̂ − N g ∂M/∂p N̂.
                    let bm = trace(a, i);
                    for jv in 0..nv {
                        row[cp.p(jv)] += w * (bm * dsigp_dp - pt.n[a] * g[i] * dm_dp) * pt.nh[jv];
                    }
                }
            }
        }
        if pt.role.storage {
            let dm = s.m - prev.m;
            for iv in 0..nv {
                let r = cp.p(iv);
                fint[r] -= w * pt.nh[iv] * dm;
                for b in 0..nno {
                    for j in 0..dim {
                        k[r * nd + cp.u(b, j)] -= w * pt.nh[iv] * dm_depsv * trace(b, j);
                    }
                }
                for jv in 0..nv {
                    k[r * nd + cp.p(jv)] -= w * pt.nh[iv] * dm_dp * pt.nh[jv];
                }
            }
        }
        if pt.role.flux {
            let (th, dt) = (step.theta, step.dt);
            let wbar: [f64; 3] = std::array::from_fn(|i| th * s.w[i] + (1.0 - th) * prev.w[i]);
            for iv in 0..nv {
                let r = cp.p(iv);
                let gi = pt.dnh[iv];
                fint[r] += w * dt * (0..dim).map(|x| gi[x] * wbar[x]).sum::<f64>();
                for jv in 0..nv {
                    let gj = pt.dnh[jv];
                    let v: f64 = (0..dim).map(|x| gi[x] * (dw_dgradp * gj[x] + dw_dp[x] * pt.nh[jv])).sum();
                    k[r * nd + cp.p(jv)] += w * dt * th * v;
                }
            }
        }
        if let Some(td) = tder {
            let (th, dt) = (step.theta, step.dt);
            let nt = cp.tfirst.len();
            if pt.role.mech {
                // K_uT: Bᵀ ∂σ'/∂T N̂ − N g ∂M/∂T N̂.
                for a in 0..nno {
                    for i in 0..dim {
                        let r = cp.u(a, i);
                        let v = trace(a, i) * td.dsig_dt - pt.n[a] * g[i] * td.dm_dt;
                        for jv in 0..nt {
                            k[r * nd + cp.t(jv)] += w * v * pt.nh[jv];
                        }
                    }
                }
            }
            let dm = s.m - prev.m;
            let hbar = th * s.h + (1.0 - th) * prev.h;
            if pt.role.storage {
                for iv in 0..nv {
                    let r = cp.p(iv);
                    for jv in 0..nt {
                        k[r * nd + cp.t(jv)] -= w * pt.nh[iv] * td.dm_dt * pt.nh[jv];
                    }
                }
                for iv in 0..nt {
                    let r = cp.t(iv);
                    let wi = w * pt.nh[iv];
                    fint[r] -= wi * (dm * hbar + s.qp - prev.qp);
                    for b in 0..nno {
                        for j in 0..dim {
                            k[r * nd + cp.u(b, j)] -= wi * (hbar * dm_depsv + td.dq_deps) * trace(b, j);
                        }
                    }
                    for jv in 0..nt {
                        let kp = hbar * dm_dp + th * dm * td.dh_dp + td.dq_dp;
                        let kt = hbar * td.dm_dt + th * dm * td.dh_dt + td.dq_dt;
                        k[r * nd + cp.p(jv)] -= wi * kp * pt.nh[jv];
                        k[r * nd + cp.t(jv)] -= wi * kt * pt.nh[jv];
                    }
                }
            }
            if pt.role.flux {
                let wbar: [f64; 3] = std::array::from_fn(|i| th * s.w[i] + (1.0 - th) * prev.w[i]);
                // The heat carried by the liquid and conducted: h w + q at both ends of the step.
                let flow: [f64; 3] = std::array::from_fn(|i| {
                    th * (s.h * s.w[i] + s.qt[i]) + (1.0 - th) * (prev.h * prev.w[i] + prev.qt[i])
                });
                for iv in 0..nv {
                    let r = cp.p(iv);
                    let gi = pt.dnh[iv];
                    let v: f64 = (0..dim).map(|x| gi[x] * td.dw_dt[x]).sum();
                    for jv in 0..nt {
                        k[r * nd + cp.t(jv)] += w * dt * th * v * pt.nh[jv];
                    }
                }
                let wg: f64 = (0..dim).map(|x| wbar[x] * g[x]).sum();
                for iv in 0..nt {
                    let r = cp.t(iv);
                    let gi = pt.dnh[iv];
                    fint[r] += w * dt * (pt.nh[iv] * wg + (0..dim).map(|x| gi[x] * flow[x]).sum::<f64>());
                    for jv in 0..nt {
                        let gj = pt.dnh[jv];
                        let (mut kp, mut kt) = (0.0, 0.0);
                        for x in 0..dim {
                            let dwp = dw_dgradp * gj[x] + dw_dp[x] * pt.nh[jv];
                            let dwt = td.dw_dt[x] * pt.nh[jv];
                            // The weight of the flux along gravity, then the convected and conducted heat.
                            kp += pt.nh[iv] * g[x] * dwp;
                            kt += pt.nh[iv] * g[x] * dwt;
                            kp += gi[x] * (s.h * dwp + td.dh_dp * pt.nh[jv] * s.w[x]);
                            kt += gi[x]
                                * (s.h * dwt
                                    + td.dh_dt * pt.nh[jv] * s.w[x]
                                    + td.dqt_dgradt * gj[x]
                                    + td.dqt_dt[x] * pt.nh[jv]);
                        }
                        k[r * nd + cp.p(jv)] += w * dt * th * kp;
                        k[r * nd + cp.t(jv)] += w * dt * th * kt;
                    }
                }
            }
        }
        states.push(s);
    }
    Ok(ElementOutput { fint, k, states })
}

/// The external forces of a fluid mass flux `q(x)` entering through a skin cell (`FLUX_THM_REP
/// FLUN_HYDR1`, kg m⁻² s⁻¹) over a step `dt`: `−Δt ∫ N̂ q` on the pressure of each vertex of the
/// face (the linear face functions, at the skin element's points: SEG3 FPG4, TRIA6 FPG6, QUAD8 FPG9).
pub fn flux_load(
    kin: Kinematics,
    t: CellType,
    coords: &[[f64; 3]],
    dt: f64,
    q: &dyn Fn(&[f64; 3]) -> f64,
) -> Result<Vec<f64>, String> {
    let rule = crate::fem::elasticity::boundary_rule(t);
    let pts = crate::fem::elasticity::boundary_points(kin.mechanics(), t, coords).map_err(|e| e.to_string())?;
    let tv = vertex_type(t);
    let nv = t.nvertices();
    let mut out = vec![0.0; nv];
    let mut nh = vec![0.0; nv];
    let mut dh = vec![[0.0; 3]; nv];
    for (xi, pt) in rule.points.iter().zip(&pts) {
        shape_and_deriv(tv, xi, &mut nh, &mut dh);
        let qv = q(&pt.x);
        for (o, n) in out.iter_mut().zip(&nh) {
            *o -= dt * pt.w * n * qv;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::reference::node_coords;
    use crate::hm::material::sample;

    fn distorted(t: CellType) -> Vec<[f64; 3]> {
        node_coords(t)
            .iter()
            .map(|p| {
                [
                    1.5 + p[0] + 0.1 * p[1] + 0.05 * p[0] * p[1],
                    0.4 + p[1] - 0.07 * p[0] + 0.02 * p[2],
                    p[2] + 0.03 * p[0] * p[1],
                ]
            })
            .collect()
    }

    fn unknowns(cp: &CellPoints, seed: f64) -> Vec<f64> {
        (0..cp.ndof).map(|k| 1e-4 * ((k as f64 + seed) * 1.7).sin()).collect()
    }

    /// The tangent is the derivative of the internal forces, for every kinematics and variant. The mass
    /// content's own tangent is Code_Aster's, exact to O(ε_v) (`hm::law`): the strains are kept at 1e-7
    /// so that the check at 1e-6 of each row's scale is on the element's assembly.
    #[test]
    fn tangent_is_the_derivative_of_the_internal_forces() {
        let mut mat = sample();
        mat.inv_kw = 1e-7; // a strongly nonlinear liquid
        let cases = [
            (Kinematics::DPlan, CellType::Quad8),
            (Kinematics::Axis, CellType::Tria6),
            (Kinematics::ThreeD, CellType::Hexa20),
            (Kinematics::ThreeD, CellType::Tetra10),
            (Kinematics::ThreeD, CellType::Penta15),
        ];
        for (kin, t) in cases {
            for variant in [Variant::Full, Variant::Reduced, Variant::Lumped, Variant::Selective] {
                let cp = CellPoints::new(kin, variant, t, &distorted(t)).unwrap();
                let small = |v: Vec<f64>| v.into_iter().map(|x| 1e-3 * x).collect::<Vec<f64>>();
                let mut u0 = small(unknowns(&cp, 0.3));
                for a in 0..t.nvertices() {
                    u0[cp.p(a)] = 1e5 * (a as f64 + 1.0);
                }
                let prev = cp.initial_states(&mat, &u0);
                let mut u = small(unknowns(&cp, 1.1));
                for a in 0..t.nvertices() {
                    u[cp.p(a)] = 2e5 * (a as f64 * 0.7).cos();
                }
                let step = StepData { dt: 10.0, theta: 0.57, gravity: [0.0, -9.81, 0.0] };
                let out = element(&cp, &mat, &u, &prev, &step).unwrap();
                let nd = cp.ndof;
                for j in 0..nd {
                    let h = if (0..t.nvertices()).any(|a| cp.p(a) == j) { 1.0 } else { 1e-9 };
                    let mut up = u.clone();
                    up[j] += h;
                    let mut um = u.clone();
                    um[j] -= h;
                    let fp = element(&cp, &mat, &up, &prev, &step).unwrap().fint;
                    let fm = element(&cp, &mat, &um, &prev, &step).unwrap().fint;
                    for i in 0..nd {
                        let fd = (fp[i] - fm[i]) / (2.0 * h);
                        let an = out.k[i * nd + j];
                        let scale = (0..nd).map(|c| out.k[i * nd + c].abs()).fold(0.0, f64::max);
                        assert!(
                            (fd - an).abs() <= 1e-6 * scale,
                            "{kin:?} {variant:?} {}: K[{i}][{j}] = {an:e}, finite difference {fd:e} (row scale {scale:e})",
                            t.name()
                        );
                    }
                }
            }
        }
    }

    /// THM: the tangent is the derivative of the internal forces, every variant, on the temperature
    /// columns and rows too. Code_Aster's tangent leaves out terms of the order of the step's increments
    /// (the mid-step temperature of `Q'` and its capacity's change with φ and ρ, times ΔT; the pressure's
    /// effect on the density in the enthalpy; the mass content's O(ε_v)): small increments keep them
    /// below 5e-4 of each row's scale, far below an assembly error.
    #[test]
    fn thm_tangent_is_the_derivative_of_the_internal_forces() {
        let mat = sample();
        let th = crate::hm::thermal::sample();
        let cases = [(Kinematics::DPlan, CellType::Quad8), (Kinematics::ThreeD, CellType::Hexa20)];
        for (kin, t) in cases {
            for variant in [Variant::Full, Variant::Reduced, Variant::Lumped, Variant::Selective] {
                let cp = CellPoints::new(kin, variant, t, &distorted(t)).unwrap().with_temperature();
                let small = |v: Vec<f64>| v.into_iter().map(|x| 1e-3 * x).collect::<Vec<f64>>();
                let mut u0 = small(unknowns(&cp, 0.3));
                for a in 0..t.nvertices() {
                    u0[cp.p(a)] = 1e3 * (a as f64 + 1.0);
                    u0[cp.t(a)] = 0.5 * a as f64;
                }
                let mut prev = cp.initial_states(&mat, &u0);
                for s in prev.iter_mut() {
                    s.h = 300.0;
                    s.w = [1e-6, -2e-6, 5e-7];
                }
                let mut u = small(unknowns(&cp, 1.1));
                for a in 0..t.nvertices() {
                    u[cp.p(a)] = 2e3 * (a as f64 * 0.7).cos();
                    // Code_Aster's heat tangent leaves out the change of the capacity with the strain
                    // and the pressure, times ΔT: a small temperature step keeps it negligible.
                    u[cp.t(a)] = u0[cp.t(a)] + 1e-5 * (a as f64 * 1.3).sin();
                }
                let step = StepData { dt: 10.0, theta: 0.57, gravity: [0.0, -9.81, 0.0] };
                let out = element_with(&cp, &mat, Some(&th), &u, &prev, &step).unwrap();
                let nd = cp.ndof;
                for j in 0..nd {
                    let vertex = (0..t.nvertices()).any(|a| cp.p(a) == j || cp.t(a) == j);
                    let h = if vertex { 1e-3 } else { 1e-9 };
                    let mut up = u.clone();
                    up[j] += h;
                    let mut um = u.clone();
                    um[j] -= h;
                    let fp = element_with(&cp, &mat, Some(&th), &up, &prev, &step).unwrap().fint;
                    let fm = element_with(&cp, &mat, Some(&th), &um, &prev, &step).unwrap().fint;
                    for i in 0..nd {
                        let fd = (fp[i] - fm[i]) / (2.0 * h);
                        let an = out.k[i * nd + j];
                        let scale = (0..nd).map(|c| out.k[i * nd + c].abs()).fold(0.0, f64::max);
                        assert!(
                            (fd - an).abs() <= 5e-4 * scale,
                            "{kin:?} {variant:?} {}: K[{i}][{j}] = {an:e}, finite difference {fd:e} (row scale {scale:e})",
                            t.name()
                        );
                    }
                }
            }
        }
    }

    /// Undrained uniform compression of a cell: with every pressure equal and a uniform strain the
    /// flux vanishes and the pressure rows hold only the change of mass, the same at every vertex
    /// up to the functions' integrals; the displacement rows balance a uniform total stress.
    #[test]
    fn uniform_states_give_uniform_stresses() {
        let mat = sample();
        let t = CellType::Quad8;
        let xs = distorted(t);
        for variant in [Variant::Full, Variant::Lumped, Variant::Selective, Variant::Reduced] {
            let cp = CellPoints::new(Kinematics::DPlan, variant, t, &xs).unwrap();
            let zero = vec![0.0; cp.ndof];
            let prev = cp.initial_states(&mat, &zero);
            let mut u = zero.clone();
            for (a, x) in xs.iter().enumerate() {
                u[cp.u(a, 0)] = -1e-4 * x[0];
                if a < 4 {
                    u[cp.p(a)] = 1.0e5;
                }
            }
            let step = StepData { dt: 1.0, theta: 1.0, gravity: [0.0; 3] };
            let out = element(&cp, &mat, &u, &prev, &step).unwrap();
            for s in &out.states {
                assert!((s.sig[0] - out.states[0].sig[0]).abs() < 1e-9 * s.sig[0].abs());
                assert_eq!(s.sigp[0], -mat.biot * 1.0e5);
                assert!(s.w.iter().all(|w| w.abs() < 1e-12), "{:?}", s.w);
            }
            // Σ of the displacement rows (a rigid translation) is zero: the element is in equilibrium.
            let sx: f64 = (0..8).map(|a| out.fint[cp.u(a, 0)]).sum();
            assert!(sx.abs() < 1e-9 * out.fint[cp.u(0, 0)].abs().max(1.0), "{variant:?}: {sx}");
            // Σ of the pressure rows = −∫ ΔM.
            let sp: f64 = (0..4).map(|a| out.fint[cp.p(a)]).sum();
            let area: f64 = cp.points.iter().filter(|p| p.role.storage).map(|p| p.w).sum();
            assert!((sp + area * out.states.last().unwrap().m).abs() < 1e-9 * sp.abs(), "{variant:?}");
        }
    }

    /// An enriched element whose copies carry the whole field (standard unknowns zero, each copy's factor
    /// 2 and its unknowns half the field) has the standard element's states, and forces twice its own on
    /// the copies' rows.
    #[test]
    fn enriched_copies_carry_the_field() {
        let mut mat = sample();
        mat.inv_kw = 1e-7;
        let t = CellType::Quad8;
        let xs = distorted(t);
        let cp = CellPoints::new(Kinematics::DPlan, Variant::Full, t, &xs).unwrap();
        let pts: Vec<([f64; 3], f64, i32)> = cp.points.iter().map(|p| (p.xi, p.w, 7)).collect();
        // Layout node by node: DX DY [PRE1], then the copy's DX DY [PRE1].
        let (mut ucols, mut pcols, mut next) = (Vec::new(), Vec::new(), 0);
        let mut map = Vec::new(); // (standard local index, enriched local index of the copy)
        for a in 0..8 {
            for set in [None, Some(0)] {
                for i in 0..2 {
                    if set.is_some() {
                        map.push((cp.u(a, i), next + i));
                    }
                }
                ucols.push(Column { node: a, set, first: next });
                next += 2;
                if a < 4 {
                    if set.is_some() {
                        map.push((cp.p(a), next));
                    }
                    pcols.push(Column { node: a, set, first: next });
                    next += 1;
                }
            }
        }
        let factor = |_: usize, _: Option<usize>, tag: i32| if tag == 7 { 2.0 } else { 0.0 };
        let ce = CellPoints::enriched(Kinematics::DPlan, t, &xs, &pts, &ucols, &pcols, next, &factor).unwrap();
        let mut u = unknowns(&cp, 0.4);
        for a in 0..4 {
            u[cp.p(a)] = 1e5 * (1.0 + a as f64);
        }
        let mut ue = vec![0.0; ce.ndof];
        for &(s, e) in &map {
            ue[e] = u[s] / 2.0;
        }
        let step = StepData { dt: 5.0, theta: 0.8, gravity: [0.0, -9.81, 0.0] };
        let prev = cp.initial_states(&mat, &vec![0.0; cp.ndof]);
        let out = element(&cp, &mat, &u, &prev, &step).unwrap();
        let oute = element(&ce, &mat, &ue, &prev, &step).unwrap();
        for (s1, s2) in out.states.iter().zip(&oute.states) {
            assert!(
                (s1.sig[1] - s2.sig[1]).abs() <= 1e-9 * s1.sig[1].abs() && (s1.m - s2.m).abs() <= 1e-12 * s1.m.abs()
            );
        }
        for &(s, e) in &map {
            let (f, fe) = (out.fint[s], oute.fint[e]);
            assert!((fe - 2.0 * f).abs() <= 1e-9 * f.abs().max(1e-3), "row {s}: {fe} against 2 × {f}");
        }
    }

    #[test]
    fn flux_load_integrates_the_flux() {
        // A SEG3 of length 2: the two vertices share ∫ q = 2 q; AXIS weighs it by r.
        let xs = [[1.0, 0.0, 0.0], [1.0, 2.0, 0.0], [1.0, 1.0, 0.0]];
        let f = flux_load(Kinematics::DPlan, CellType::Seg3, &xs, 3.0, &|_| 0.5).unwrap();
        assert!((f[0] + 1.5).abs() < 1e-12 && (f[1] + 1.5).abs() < 1e-12, "{f:?}");
        let xs = [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let f = flux_load(Kinematics::Axis, CellType::Seg3, &xs, 1.0, &|_| 1.0).unwrap();
        // ∫ r N̂ over r ∈ [1, 3]: (1·2 + 2·... ) = ∫ r (3 − r)/2 dr = 10/6 and ∫ r (r − 1)/2 dr = 14/6.
        assert!((f[0] + 10.0 / 6.0).abs() < 1e-12 && (f[1] + 14.0 / 6.0).abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn linear_cells_are_refused() {
        let e = CellPoints::new(Kinematics::DPlan, Variant::Full, CellType::Quad4, &distorted(CellType::Quad4))
            .unwrap_err();
        assert!(e.contains("quadratic"), "{e}");
    }
}
