//! The volume elements of heat conduction: modelisations, integration families, conduction and
//! capacity, the nonlinear terms of `THER_NON_LINE`, sources and the heat flux.
//!
//! Integration families (Code_Aster's `ther_3d.py`, `ther_plan.py`, `ther_axis.py` and their `_diag`
//! variants): `RIGI` is FPG3 on TRIA3, FPG6 on TRIA6, FPG4 on QUAD4, FPG9 on QUAD8/9, FPG4 on TETRA4,
//! FPG15 on TETRA10, FPG6 on PENTA6, FPG21 on PENTA15, FPG5 on PYRAM5, FPG10 on PYRAM13, FPG8 on
//! HEXA8 and FPG27 on HEXA20/27; `MASS` is the same family, or the vertices (`NOEU_S`) on the lumped
//! `_DIAG` elements, which exist on linear cells only (TRIA3, QUAD4; TETRA4, PENTA6, HEXA8).
//!
//! The terms, for a cell with shape functions `N` and nodal temperatures `T`:
//! - conduction `K = ∫ ∇Nᵀ Λ ∇N` (`RIGI`), `Λ` isotropic `λ I` or orthotropic `Σ λᵢ aᵢ aᵢᵀ`;
//! - capacity `M = ∫ ρCp N Nᵀ` (`MASS`);
//! - nonlinear conduction: residual `∫ ∇N · Λ(T) ∇T`, tangent `∫ ∇N Λ(T) ∇Nᵀ + ∇N (Λ'(T) ∇T) Nᵀ`;
//! - enthalpy: residual `∫ β(T) N`, tangent `∫ β'(T) N Nᵀ` (`MASS`);
//! - a source `s(x, T)`: load `∫ s N` and its derivative `∫ ∂s/∂T N Nᵀ` (`RIGI`);
//! - the flux `q = −Λ(T) ∇T` at the `RIGI` points, extrapolated to the nodes as every `*_ELNO` field.

use crate::fem::elasticity::{gauss_geometry, gauss_to_node_matrix, ElementError, GaussGeom};
use crate::fem::frame::{principal_tensor, Frame};
use crate::fem::quadrature::{aster_rule, QuadratureRule};
use crate::mesh::CellType;
use std::fmt;

use super::curve::OutOfRange;

/// The geometry of a thermal modelisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kinematics {
    /// `PLAN`: a plane section, per unit thickness.
    Plan,
    /// `AXIS`: axisymmetric, x = r ≥ 0, per radian.
    Axis,
    ThreeD,
}

/// A thermal modelisation: its geometry, and whether the capacity is lumped at the vertices (`_DIAG`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Modelisation {
    pub kinematics: Kinematics,
    pub lumped: bool,
}

const NAMES: [(&str, Kinematics, bool); 6] = [
    ("PLAN", Kinematics::Plan, false),
    ("PLAN_DIAG", Kinematics::Plan, true),
    ("AXIS", Kinematics::Axis, false),
    ("AXIS_DIAG", Kinematics::Axis, true),
    ("3D", Kinematics::ThreeD, false),
    ("3D_DIAG", Kinematics::ThreeD, true),
];

impl Modelisation {
    /// From Code_Aster's name under `PHENOMENE='THERMIQUE'`.
    pub fn from_name(s: &str) -> Option<Modelisation> {
        NAMES.iter().find(|(n, ..)| *n == s).map(|&(_, kinematics, lumped)| Modelisation { kinematics, lumped })
    }

    pub fn name(self) -> &'static str {
        NAMES.iter().find(|(_, k, l)| *k == self.kinematics && *l == self.lumped).map(|(n, ..)| *n).unwrap_or("?")
    }

    /// The space dimension.
    pub fn dim(self) -> usize {
        if self.kinematics == Kinematics::ThreeD {
            3
        } else {
            2
        }
    }

    /// Does the modelisation put a volume element on cells of this type?
    pub fn accepts_volume(self, t: CellType) -> bool {
        use CellType::*;
        // Code_Aster's thermal catalogues have no TRIA7 or PENTA18 element.
        let shape_ok = !matches!(t, Tria7 | Penta18);
        shape_ok && t.dim() == self.dim() && (!self.lumped || matches!(t, Tria3 | Quad4 | Tetra4 | Penta6 | Hexa8))
    }

    /// Does the modelisation put a skin (boundary) element on cells of this type?
    pub fn accepts_skin(self, t: CellType) -> bool {
        use CellType::*;
        let shape_ok = matches!(t, Seg2 | Seg3 | Tria3 | Tria6 | Quad4 | Quad8 | Quad9);
        shape_ok && t.dim() + 1 == self.dim() && (!self.lumped || matches!(t, Seg2 | Tria3 | Quad4))
    }

    /// The family of the conduction terms and the flux (`RIGI`).
    pub fn rigi_rule(self, t: CellType) -> QuadratureRule {
        family(rigi_name(t), t)
    }

    /// The family of the capacity and enthalpy terms (`MASS`): the vertices when lumped.
    pub fn mass_rule(self, t: CellType) -> QuadratureRule {
        family(if self.lumped { "NOEU_S" } else { rigi_name(t) }, t)
    }

    /// The geometry of a volume cell at the points of `rule` (weights × r in `AXIS`).
    pub fn points(
        self,
        t: CellType,
        coords: &[[f64; 3]],
        rule: &QuadratureRule,
    ) -> Result<Vec<GaussGeom>, ThermalError> {
        if !self.accepts_volume(t) {
            return Err(ThermalError::WrongCell { cell_type: t, modelisation: self.name() });
        }
        let mech = if self.dim() == 3 {
            crate::fem::elasticity::Modelisation::ThreeD
        } else {
            crate::fem::elasticity::Modelisation::DPlan
        };
        let mut pts = gauss_geometry(mech, t, coords, rule)?;
        if self.kinematics == Kinematics::Axis {
            let size = coords.iter().map(|c| c[0].abs().max(c[1].abs())).fold(0.0, f64::max);
            for (g, p) in pts.iter_mut().enumerate() {
                p.w *= radius(p.x[0], size, g)?;
            }
        }
        Ok(pts)
    }
}

impl fmt::Display for Modelisation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The radius of an `AXIS` point: negative radii are refused, round-off below zero taken as zero (a
/// vertex on the axis carries no lumped capacity).
pub(super) fn radius(r: f64, size: f64, point: usize) -> Result<f64, ThermalError> {
    if r >= 0.0 {
        Ok(r)
    } else if r > -1e-12 * size {
        Ok(0.0)
    } else {
        Err(ThermalError::NegativeRadius { point, r })
    }
}

fn rigi_name(t: CellType) -> &'static str {
    use CellType::*;
    match t {
        Tria3 => "FPG3",
        Tria6 | Tria7 | Penta6 => "FPG6",
        Quad4 | Tetra4 => "FPG4",
        Quad8 | Quad9 => "FPG9",
        Tetra10 => "FPG15",
        Penta15 | Penta18 => "FPG21",
        Pyram5 => "FPG5",
        Pyram13 => "FPG10",
        Hexa8 => "FPG8",
        Hexa20 | Hexa27 => "FPG27",
        Poi1 | Seg2 | Seg3 | Seg4 => "FPG1",
    }
}

pub(super) fn family(name: &str, t: CellType) -> QuadratureRule {
    aster_rule(t, name).unwrap_or_else(|| panic!("family {name} missing on {}", t.name()))
}

/// The errors of the element computations.
#[derive(Debug, Clone, PartialEq)]
pub enum ThermalError {
    /// The modelisation has no element on this cell type.
    WrongCell { cell_type: CellType, modelisation: &'static str },
    /// A degenerate or inverted cell (from the geometry).
    Geometry(String),
    /// An `AXIS` point at a negative radius.
    NegativeRadius { point: usize, r: f64 },
    /// A material function evaluated where it is not extended.
    OutOfRange(OutOfRange),
    /// Anything a caller's closure reports.
    Material(String),
}

impl fmt::Display for ThermalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ThermalError::WrongCell { cell_type, modelisation } => {
                write!(f, "modelisation {modelisation} (THERMIQUE) has no element on a {} cell", cell_type.name())
            }
            ThermalError::Geometry(m) | ThermalError::Material(m) => f.write_str(m),
            ThermalError::NegativeRadius { point, r } => {
                write!(f, "AXIS: integration point {} has radius {r:e} < 0 (x must be the radius, ≥ 0)", point + 1)
            }
            ThermalError::OutOfRange(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for ThermalError {}

impl From<ElementError> for ThermalError {
    fn from(e: ElementError) -> Self {
        ThermalError::Geometry(e.to_string())
    }
}

impl From<OutOfRange> for ThermalError {
    fn from(e: OutOfRange) -> Self {
        ThermalError::OutOfRange(e)
    }
}

/// A conductivity: isotropic, or orthotropic along the axes of a local frame (`THER_ORTH`,
/// `THER_NL_ORTH`: `λ_L λ_T [λ_N]`; in 2D the first two, in the plane), which may turn with the point
/// (a cylindrical frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Conductivity {
    Iso(f64),
    Ortho { lambda: [f64; 3], frame: Frame },
}

impl Conductivity {
    /// The tensor `Λ` in global axes at the point `x`.
    pub fn tensor(&self, dim: usize, x: &[f64; 3]) -> Result<[[f64; 3]; 3], ThermalError> {
        match *self {
            Conductivity::Iso(l) => {
                let mut k = [[0.0; 3]; 3];
                (0..dim).for_each(|i| k[i][i] = l);
                Ok(k)
            }
            Conductivity::Ortho { lambda, frame } => {
                let axes = frame.axes_at(x).map_err(|e| ThermalError::Material(e.to_string()))?;
                Ok(principal_tensor(&lambda, &axes, dim))
            }
        }
    }
}

fn apply(k: &[[f64; 3]; 3], v: &[f64; 3], dim: usize) -> [f64; 3] {
    let mut out = [0.0; 3];
    for i in 0..dim {
        out[i] = (0..dim).map(|j| k[i][j] * v[j]).sum();
    }
    out
}

fn value_and_gradient(p: &GaussGeom, temps: &[f64], dim: usize) -> (f64, [f64; 3]) {
    let mut t = 0.0;
    let mut g = [0.0; 3];
    for (a, ta) in temps.iter().enumerate() {
        t += p.n[a] * ta;
        for (gi, dn) in g.iter_mut().zip(&p.dn[a]).take(dim) {
            *gi += dn * ta;
        }
    }
    (t, g)
}

/// The conduction matrix `K = ∫ ∇Nᵀ Λ ∇N` (`RIGI_THER`).
pub fn conduction(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    k: &Conductivity,
) -> Result<Vec<f64>, ThermalError> {
    let pts = m.points(t, coords, &m.rigi_rule(t))?;
    let (n, dim) = (t.nnodes(), m.dim());
    let mut out = vec![0.0; n * n];
    for p in &pts {
        let kt = k.tensor(dim, &p.x)?;
        for a in 0..n {
            let ka = apply(&kt, &p.dn[a], dim);
            for b in 0..n {
                out[a * n + b] += p.w * (0..dim).map(|i| ka[i] * p.dn[b][i]).sum::<f64>();
            }
        }
    }
    Ok(out)
}

/// The capacity matrix `M = ∫ ρCp N Nᵀ` (`MASS_THER`; diagonal when lumped).
pub fn capacity(m: Modelisation, t: CellType, coords: &[[f64; 3]], rho_cp: f64) -> Result<Vec<f64>, ThermalError> {
    let pts = m.points(t, coords, &m.mass_rule(t))?;
    let n = t.nnodes();
    let mut out = vec![0.0; n * n];
    for p in &pts {
        for a in 0..n {
            for b in 0..n {
                out[a * n + b] += p.w * rho_cp * p.n[a] * p.n[b];
            }
        }
    }
    Ok(out)
}

/// A value and its derivative with respect to the temperature, or the reason it cannot be had.
pub type Law<'a, V> = dyn Fn(f64) -> Result<(V, V), ThermalError> + 'a;

/// The nonlinear conduction of `THER_NL` at the temperatures `temps`: the residual `∫ ∇N · Λ(T) ∇T`
/// (`RAPH_THER`) and its tangent (`RIGI_THER_TANG`, not symmetric), `law(T)` giving `Λ` and `dΛ/dT`.
pub fn conduction_nl(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: &[f64],
    law: &Law<'_, Conductivity>,
) -> Result<(Vec<f64>, Vec<f64>), ThermalError> {
    let pts = m.points(t, coords, &m.rigi_rule(t))?;
    let (n, dim) = (t.nnodes(), m.dim());
    let mut resi = vec![0.0; n];
    let mut tang = vec![0.0; n * n];
    for p in &pts {
        let (tp, grad) = value_and_gradient(p, temps, dim);
        let (k, dk) = law(tp)?;
        let (kt, dkt) = (k.tensor(dim, &p.x)?, dk.tensor(dim, &p.x)?);
        let flux = apply(&kt, &grad, dim);
        let dflux = apply(&dkt, &grad, dim);
        for a in 0..n {
            let dot = |v: &[f64; 3]| (0..dim).map(|i| p.dn[a][i] * v[i]).sum::<f64>();
            resi[a] += p.w * dot(&flux);
            let da = dot(&dflux);
            let ka = apply(&kt, &p.dn[a], dim);
            for b in 0..n {
                tang[a * n + b] += p.w * ((0..dim).map(|i| ka[i] * p.dn[b][i]).sum::<f64>() + da * p.n[b]);
            }
        }
    }
    Ok((resi, tang))
}

/// The enthalpy term of `THER_NL`: residual `∫ β(T) N` (`MASS_THER_RESI`) and tangent `∫ β'(T) N Nᵀ`
/// (`MASS_THER_TANG`), on the `MASS` family.
pub fn enthalpy_nl(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: &[f64],
    beta: &Law<'_, f64>,
) -> Result<(Vec<f64>, Vec<f64>), ThermalError> {
    let pts = m.points(t, coords, &m.mass_rule(t))?;
    density(&pts, t.nnodes(), Some(temps), |p| (p.w, &p.n), &|_, tp| beta(tp))
}

/// A density of the point and the temperature there, with its derivative in the temperature.
pub type PointLaw<'a, P> = dyn Fn(&P, f64) -> Result<(f64, f64), ThermalError> + 'a;

/// A volume source (`SOURCE`, `SOUR_NL`): the load `∫ s N` and its derivative `∫ ∂s/∂T N Nᵀ`, on the
/// `RIGI` family; `temps` None for a source that does not depend on the temperature (taken at 0).
pub fn source(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: Option<&[f64]>,
    s: &PointLaw<'_, GaussGeom>,
) -> Result<(Vec<f64>, Vec<f64>), ThermalError> {
    let pts = m.points(t, coords, &m.rigi_rule(t))?;
    density(&pts, t.nnodes(), temps, |p| (p.w, &p.n), s)
}

/// A density `f(point, T)` integrated over points of weight `w` and shape values `N` (`geom(p)`): the
/// load `∫ f N` and its derivative `∫ ∂f/∂T N Nᵀ`; `temps` None where `f` does not depend on the
/// temperature (it is then given 0). Volume sources and boundary flux densities alike.
pub(crate) fn density<P>(
    pts: &[P],
    n: usize,
    temps: Option<&[f64]>,
    geom: impl Fn(&P) -> (f64, &[f64]),
    f: &PointLaw<'_, P>,
) -> Result<(Vec<f64>, Vec<f64>), ThermalError> {
    let mut load = vec![0.0; n];
    let mut tang = vec![0.0; n * n];
    for p in pts {
        let (w, shape) = geom(p);
        let tp = temps.map(|v| shape.iter().zip(v).map(|(a, b)| a * b).sum()).unwrap_or(0.0);
        let (fv, df) = f(p, tp)?;
        for a in 0..n {
            load[a] += w * fv * shape[a];
            if df != 0.0 {
                for b in 0..n {
                    tang[a * n + b] += w * df * shape[a] * shape[b];
                }
            }
        }
    }
    Ok((load, tang))
}

/// A point's coordinates and the flux there.
pub type PointFlux = ([f64; 3], [f64; 3]);

/// The heat flux `q = −Λ(T) ∇T` at the `RIGI` points (`FLUX_ELGA`: `FLUX FLUY [FLUZ]`), with the
/// points' coordinates; `law(T)` gives `Λ` there.
pub fn flux(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: &[f64],
    law: &dyn Fn(f64) -> Result<Conductivity, ThermalError>,
) -> Result<Vec<PointFlux>, ThermalError> {
    let pts = m.points(t, coords, &m.rigi_rule(t))?;
    let dim = m.dim();
    let mut out = Vec::with_capacity(pts.len());
    for p in &pts {
        let (tp, grad) = value_and_gradient(p, temps, dim);
        let q = apply(&law(tp)?.tensor(dim, &p.x)?, &grad, dim);
        out.push((p.x, [-q[0], -q[1], -q[2]]));
    }
    Ok(out)
}

/// The thermal energy of a cell, `−½ ∫ ∇T · Λ ∇T` on the `RIGI` points (`ETHE_ELEM`), as Code_Aster's
/// te0066 (3D: the frame at each point) and te0220 (in the plane: the plane area without the radius of
/// `AXIS`, the frame at the nodes' centre).
pub fn energy(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: &[f64],
    k: &Conductivity,
) -> Result<f64, ThermalError> {
    let plane = Modelisation { kinematics: if m.dim() == 2 { Kinematics::Plan } else { m.kinematics }, ..m };
    let pts = plane.points(t, coords, &m.rigi_rule(t))?;
    let dim = m.dim();
    let centre: [f64; 3] = std::array::from_fn(|i| coords.iter().map(|x| x[i]).sum::<f64>() / coords.len() as f64);
    let mut e = 0.0;
    for p in &pts {
        let (_, grad) = value_and_gradient(p, temps, dim);
        let kt = k.tensor(dim, if dim == 2 { &centre } else { &p.x })?;
        let q = apply(&kt, &grad, dim);
        e -= p.w * (0..dim).map(|i| grad[i] * q[i]).sum::<f64>();
    }
    Ok(e / 2.0)
}

/// Values at the `RIGI` points of a cell extrapolated to its nodes (`FLUX_ELNO` from `FLUX_ELGA`).
pub fn to_nodes(m: Modelisation, t: CellType, values: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mat = gauss_to_node_matrix(t, &m.rigi_rule(t));
    mat.iter()
        .map(|row| {
            let mut v = [0.0; 3];
            for (w, g) in row.iter().zip(values) {
                for c in 0..3 {
                    v[c] += w * g[c];
                }
            }
            v
        })
        .collect()
}

/// `y = A x` for a row-major square element matrix.
pub fn matvec(a: &[f64], x: &[f64]) -> Vec<f64> {
    let n = x.len();
    (0..n).map(|i| a[i * n..(i + 1) * n].iter().zip(x).map(|(m, v)| m * v).sum()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::reference::node_coords;
    use CellType::*;

    /// A cell of each type mapped off its reference shape (stretched, sheared, shifted so that AXIS
    /// radii stay positive).
    pub(crate) fn distorted(t: CellType) -> Vec<[f64; 3]> {
        node_coords(t)
            .iter()
            .map(|p| {
                let (x, y, z) = (p[0], p[1], p[2]);
                if t.dim() == 3 {
                    [2.0 + 1.3 * x + 0.2 * y + 0.05 * x * y, 1.0 + 0.1 * x + 0.9 * y + 0.1 * z, 0.5 + 0.8 * z + 0.1 * x]
                } else {
                    [2.0 + 1.3 * x + 0.2 * y + 0.05 * x * y, 1.0 + 0.1 * x + 0.9 * y, 0.0]
                }
            })
            .collect()
    }

    const PLANE: [CellType; 5] = [Tria3, Tria6, Quad4, Quad8, Quad9];
    const SOLID: [CellType; 10] = [Tetra4, Tetra10, Penta6, Penta15, Pyram5, Pyram13, Hexa8, Hexa20, Hexa27, Hexa8];

    fn cases() -> Vec<(Modelisation, CellType)> {
        let mut v = Vec::new();
        for name in ["PLAN", "AXIS", "PLAN_DIAG", "AXIS_DIAG"] {
            let m = Modelisation::from_name(name).unwrap();
            v.extend(PLANE.iter().filter(|t| m.accepts_volume(**t)).map(|t| (m, *t)));
        }
        for name in ["3D", "3D_DIAG"] {
            let m = Modelisation::from_name(name).unwrap();
            v.extend(SOLID.iter().filter(|t| m.accepts_volume(**t)).map(|t| (m, *t)));
        }
        v
    }

    #[test]
    fn names_and_cells() {
        for (name, ..) in NAMES {
            assert_eq!(Modelisation::from_name(name).unwrap().name(), name);
        }
        let diag = Modelisation::from_name("3D_DIAG").unwrap();
        assert!(diag.accepts_volume(Hexa8) && !diag.accepts_volume(Hexa20) && !diag.accepts_volume(Pyram5));
        assert!(diag.accepts_skin(Quad4) && !diag.accepts_skin(Quad8));
        let plan = Modelisation::from_name("PLAN").unwrap();
        assert!(plan.accepts_volume(Quad9) && plan.accepts_skin(Seg3) && !plan.accepts_volume(Hexa8));
        assert_eq!(plan.rigi_rule(Tria3).len(), 3);
        assert_eq!(Modelisation::from_name("PLAN_DIAG").unwrap().mass_rule(Quad4).name, "NOEU_S");
    }

    /// Patch test: a linear temperature has a constant flux; `K T` balances it on the nodes as the
    /// boundary integral `∫ (Λ∇T·n) N` does, so `Σ (K T)_a = 0` and `(K T)·x = V ∇Tᵀ Λ ∇T`-like
    /// identities hold. We check the two exact consequences on every cell: `K 1 = 0`, and
    /// `Tᵀ K T = ∫ ∇T·Λ∇T` (= measure × g·Λg for a linear T, with the measure from `M` and ρCp = 1).
    #[test]
    fn linear_temperatures_are_exact_on_every_cell() {
        let g = [0.7, -1.1, 0.4];
        let ortho = Conductivity::Ortho {
            lambda: [2.0, 0.5, 1.5],
            frame: Frame::Fixed([[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]]),
        };
        for (m, t) in cases() {
            let x = distorted(t);
            let dim = m.dim();
            let temps: Vec<f64> = x.iter().map(|p| 3.0 + (0..dim).map(|i| g[i] * p[i]).sum::<f64>()).collect();
            let n = t.nnodes();
            for k in [Conductivity::Iso(2.5), ortho] {
                let km = conduction(m, t, &x, &k).unwrap();
                let ones = matvec(&km, &vec![1.0; n]);
                assert!(ones.iter().all(|v| v.abs() < 1e-10), "{m} {t:?}: K 1 = {ones:?}");
                // The flux is exact at every point.
                let kt = k.tensor(dim, &[0.0; 3]).unwrap();
                let q = flux(m, t, &x, &temps, &|_| Ok(k)).unwrap();
                let exact = apply(&kt, &g, dim);
                for (_, qp) in &q {
                    for i in 0..dim {
                        assert!((qp[i] + exact[i]).abs() < 1e-10, "{m} {t:?}: flux {qp:?} vs {exact:?}");
                    }
                }
                // Energy: Tᵀ K T = ∫ g·Λg, the volume (×r) measured by the consistent rule of M.
                let mass = capacity(Modelisation { lumped: false, ..m }, t, &x, 1.0).unwrap();
                let volume: f64 = mass.iter().sum();
                let energy: f64 = temps.iter().zip(matvec(&km, &temps)).map(|(a, b)| a * b).sum();
                let gkg: f64 = (0..dim).map(|i| g[i] * exact[i]).sum();
                assert!((energy - volume * gkg).abs() < 1e-9 * energy.abs(), "{m} {t:?}: {energy} vs {}", volume * gkg);
                // The nodal flux is the same constant.
                let vals: Vec<[f64; 3]> = q.iter().map(|(_, v)| *v).collect();
                for v in to_nodes(m, t, &vals) {
                    for i in 0..dim {
                        assert!((v[i] + exact[i]).abs() < 1e-10);
                    }
                }
            }
        }
    }

    #[test]
    fn capacity_integrates_the_measure_and_lumps_on_the_vertices() {
        for (m, t) in cases() {
            let x = distorted(t);
            let mm = capacity(m, t, &x, 3.0).unwrap();
            let n = t.nnodes();
            let total: f64 = mm.iter().sum();
            let consistent: f64 = capacity(Modelisation { lumped: false, ..m }, t, &x, 3.0).unwrap().iter().sum();
            // The vertex rule integrates r |J| exactly only where it is linear (not on a lumped AXIS cell).
            let tol = if m.lumped && m.kinematics == Kinematics::Axis { 2e-2 } else { 1e-10 };
            assert!((total - consistent).abs() < tol * consistent, "{m} {t:?}");
            if m.lumped {
                for a in 0..n {
                    for b in 0..n {
                        assert!(a == b || mm[a * n + b] == 0.0);
                    }
                }
            }
        }
    }

    #[test]
    fn the_nonlinear_terms_reduce_to_the_linear_ones_and_their_tangents_are_exact() {
        let lam = |t: f64| Ok((Conductivity::Iso(1.0 + 0.01 * t), Conductivity::Iso(0.01)));
        let beta = |t: f64| Ok((2.0 * t + 0.1 * t * t, 2.0 + 0.2 * t));
        for (m, t) in cases() {
            let x = distorted(t);
            let n = t.nnodes();
            let temps: Vec<f64> = (0..n).map(|a| 20.0 + 5.0 * a as f64 + x[a][0]).collect();
            // Constant λ: the residual is K T, the tangent K.
            let k = conduction(m, t, &x, &Conductivity::Iso(2.0)).unwrap();
            let (r, tg) =
                conduction_nl(m, t, &x, &temps, &|_| Ok((Conductivity::Iso(2.0), Conductivity::Iso(0.0)))).unwrap();
            let kt = matvec(&k, &temps);
            for a in 0..n {
                assert!((r[a] - kt[a]).abs() < 1e-9 * (1.0 + kt[a].abs()));
            }
            for (u, v) in tg.iter().zip(&k) {
                assert!((u - v).abs() < 1e-12 * (1.0 + v.abs()));
            }
            // Tangents against central differences.
            for law in 0..2 {
                let f = |tv: &[f64]| {
                    if law == 0 {
                        conduction_nl(m, t, &x, tv, &lam).unwrap()
                    } else {
                        enthalpy_nl(m, t, &x, tv, &beta).unwrap()
                    }
                };
                let (_, tg) = f(&temps);
                for b in 0..n {
                    let h = 1e-4;
                    let mut tp = temps.clone();
                    tp[b] += h;
                    let mut tm = temps.clone();
                    tm[b] -= h;
                    let (rp, _) = f(&tp);
                    let (rm, _) = f(&tm);
                    for a in 0..n {
                        let fd = (rp[a] - rm[a]) / (2.0 * h);
                        assert!(
                            (fd - tg[a * n + b]).abs() < 1e-6 * (1.0 + fd.abs()),
                            "{m} {t:?} law {law}: {fd} vs {}",
                            tg[a * n + b]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_uniform_source_loads_the_measure() {
        for (m, t) in cases() {
            let x = distorted(t);
            let (f, _) = source(m, t, &x, None, &|_, _| Ok((4.0, 0.0))).unwrap();
            let vol: f64 = capacity(Modelisation { lumped: false, ..m }, t, &x, 1.0).unwrap().iter().sum();
            assert!((f.iter().sum::<f64>() - 4.0 * vol).abs() < 1e-10 * vol, "{m} {t:?}");
        }
    }

    #[test]
    fn axis_refuses_negative_radii_and_wrong_cells() {
        let m = Modelisation::from_name("AXIS").unwrap();
        let x: Vec<[f64; 3]> = node_coords(Quad4).iter().map(|p| [p[0] - 0.5, p[1], 0.0]).collect();
        assert!(matches!(conduction(m, Quad4, &x, &Conductivity::Iso(1.0)), Err(ThermalError::NegativeRadius { .. })));
        let e = conduction(m, Hexa8, &distorted(Hexa8), &Conductivity::Iso(1.0)).unwrap_err();
        assert_eq!(e.to_string(), "modelisation AXIS (THERMIQUE) has no element on a HEXA8 cell");
        // A lumped AXIS cell touching the axis: its vertices there carry nothing.
        let d = Modelisation::from_name("AXIS_DIAG").unwrap();
        let x: Vec<[f64; 3]> = node_coords(Quad4).iter().map(|p| [p[0] + 1.0, p[1], 0.0]).collect();
        let mm = capacity(d, Quad4, &x, 1.0).unwrap();
        assert_eq!(mm[0], 0.0);
        assert!(mm[5] > 0.0);
    }
}
