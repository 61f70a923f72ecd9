//! Linear elasticity on isoparametric elements, in Code_Aster's
//! conventions.
//!
//! * Materials ([`IsoElastic`]): isotropic (E, ν), or a general 3D Hooke
//!   matrix in the global frame (transversely isotropic `ELAS_ISTR`), the
//!   latter in `3D` and `D_PLAN` only.
//! * Modelisations ([`Modelisation`]): `3D`, `D_PLAN` (plane strain),
//!   `C_PLAN` (plane stress) and `AXIS` (axisymmetric, x = r, y = z, per
//!   radian: the integration weight is multiplied by r, no 2π).
//! * Element dofs are numbered node by node, in Code_Aster's local node
//!   order: `[DX1, DY1, (DZ1), DX2, ...]`.
//! * Integration uses Code_Aster's default `RIGI` family of each cell
//!   ([`family_rule`]); boundary loads use the `RIGI` family of the skin
//!   elements ([`boundary_rule`]).
//! * Stress / strain components in Code_Aster's order: 2D `XX YY ZZ XY`,
//!   3D `XX YY ZZ XY XZ YZ`; strains are tensorial (`EPXY = γxy / 2`).
//!   `D_PLAN`: `EPZZ = 0`, `SIZZ = λ (εxx + εyy)`; `C_PLAN`: `SIZZ = 0`,
//!   `EPZZ = -ν/(1-ν) (εxx + εyy)`; `AXIS`: `EPZZ` is the hoop strain
//!   `u_r / r` and `SIZZ` the hoop stress.
//! * Gauss → node extrapolation (`*_ELNO`) as Code_Aster's `inmat4`/`inmat6`:
//!   one point → copied to every node; otherwise a least-squares fit of the
//!   values with the shape functions of the vertex element (QUAD4 for QUAD8,
//!   HEXA8 for HEXA20, ...) gives vertex values, and other nodes interpolate
//!   them linearly (mid-edge node = mean of the edge's ends).
//! * Pressure (`PRES_REP`) is positive in compression: the traction is
//!   `-p n`. In 2D, along a segment travelled from its first to its second
//!   node with tangent `t = dx/ds`, `n = (t_y, -t_x)`, and the optional shear
//!   `CISA` acts along `(-n_y, n_x) = t` (Code_Aster `vff2dn` / `te0089`). In
//!   3D, `n = (∂x/∂ξ × ∂x/∂η) / |…|` (Code_Aster `nmpr3d`): the face must be
//!   oriented (`ORIE_PEAU_3D`) so that `n` points out of the solid.

use super::quadrature::{aster_rule, family_rule, Family, QuadratureRule};
use super::reference::{jacobian_inverse, node_coords, shape, shape_and_deriv, MAX_NODES};
use crate::mesh::CellType;
use nalgebra::{DMatrix, Matrix6, Vector2, Vector3};
use std::fmt;

/// The mechanical modelisations handled here.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Modelisation {
    /// `3D`: volume cells, 3 dofs per node.
    ThreeD,
    /// `D_PLAN`: plane strain.
    DPlan,
    /// `C_PLAN`: plane stress.
    CPlan,
    /// `AXIS`: axisymmetric (x = r ≥ 0, y = axis).
    Axis,
}

impl Modelisation {
    /// From Code_Aster's name (`"3D"`, `"D_PLAN"`, `"C_PLAN"`, `"AXIS"`).
    pub fn from_name(s: &str) -> Option<Modelisation> {
        match s {
            "3D" => Some(Modelisation::ThreeD),
            "D_PLAN" => Some(Modelisation::DPlan),
            "C_PLAN" => Some(Modelisation::CPlan),
            "AXIS" => Some(Modelisation::Axis),
            _ => None,
        }
    }

    /// Code_Aster's name.
    pub fn name(self) -> &'static str {
        match self {
            Modelisation::ThreeD => "3D",
            Modelisation::DPlan => "D_PLAN",
            Modelisation::CPlan => "C_PLAN",
            Modelisation::Axis => "AXIS",
        }
    }

    /// Space dimension = displacement components per node (2 or 3).
    pub fn dim(self) -> usize {
        if self == Modelisation::ThreeD {
            3
        } else {
            2
        }
    }

    /// Number of stress / strain components (4 in 2D, 6 in 3D).
    pub fn nsig(self) -> usize {
        if self == Modelisation::ThreeD {
            6
        } else {
            4
        }
    }

    /// Stress component names, in order.
    pub fn sigma_names(self) -> &'static [&'static str] {
        const N: [&str; 6] = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
        &N[..self.nsig()]
    }

    /// Strain component names, in order.
    pub fn epsilon_names(self) -> &'static [&'static str] {
        const N: [&str; 6] = ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"];
        &N[..self.nsig()]
    }

    /// True for the cell types carrying volume (stiffness) elements.
    pub fn accepts_volume_cell(self, t: CellType) -> bool {
        t.dim() == self.dim()
    }

    /// True for the cell types carrying boundary (load) elements.
    pub fn accepts_boundary_cell(self, t: CellType) -> bool {
        t.dim() + 1 == self.dim()
    }
}

/// Linear elastic material: isotropic (`DEFI_MATERIAU/ELAS`: E, ν), or
/// anisotropic with a general 3D Hooke matrix in the global frame
/// (`ELAS_ISTR`, see [`IsoElastic::transverse_isotropic`]).
///
/// The anisotropic form is handled in `3D` and `D_PLAN` (where the Hooke
/// matrix is the `XX YY ZZ XY` block of the 3D one, as Code_Aster's
/// `dmatdp`); the element routines refuse it in `C_PLAN` and `AXIS`
/// ([`ElementError::AnisotropicUnsupported`]). For an anisotropic material
/// `e` and `nu` are the Young modulus and Poisson ratio along X
/// (`1/S_xx`, `-S_yx/S_xx` of the compliance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsoElastic {
    pub e: f64,
    pub nu: f64,
    /// The 3D Hooke matrix of an anisotropic material (engineering shear,
    /// components `XX YY ZZ XY XZ YZ`); None when isotropic.
    general: Option<[[f64; 6]; 6]>,
}

/// Invert a symmetric positive definite 6×6 matrix by nalgebra's Cholesky
/// factorisation (of its lower triangle), or None when it is not positive
/// definite: a pivot (squared diagonal of the factor) at or below 1e-13 times
/// the largest diagonal entry, or not finite.
fn spd_inverse6(a: &[[f64; 6]; 6]) -> Option<[[f64; 6]; 6]> {
    let scale = (0..6).map(|i| a[i][i].abs()).fold(0.0f64, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let chol = Matrix6::from_fn(|r, c| a[r][c]).cholesky()?;
    if !chol.l_dirty().diagonal().iter().all(|l| l * l > 1e-13 * scale && l.is_finite()) {
        return None;
    }
    let inv = chol.inverse();
    Some(std::array::from_fn(|r| std::array::from_fn(|c| inv[(r, c)])))
}

impl IsoElastic {
    pub fn new(e: f64, nu: f64) -> IsoElastic {
        IsoElastic { e, nu, general: None }
    }

    /// An anisotropic material from its 3D Hooke matrix in the global frame
    /// (engineering shear, components `XX YY ZZ XY XZ YZ`). The matrix must
    /// be symmetric positive definite.
    pub fn from_hooke_3d(d: [[f64; 6]; 6]) -> Result<IsoElastic, String> {
        for i in 0..6 {
            for j in 0..i {
                let tol = 1e-12 * (d[i][i].abs() + d[j][j].abs());
                if (d[i][j] - d[j][i]).abs() > tol {
                    return Err(format!(
                        "the Hooke matrix is not symmetric (entries {}{} and {}{})",
                        i + 1,
                        j + 1,
                        j + 1,
                        i + 1
                    ));
                }
            }
        }
        let s = spd_inverse6(&d).ok_or_else(|| "the Hooke matrix is not positive definite".to_string())?;
        Ok(IsoElastic { e: 1.0 / s[0][0], nu: -s[1][0] / s[0][0], general: Some(d) })
    }

    /// Transversely isotropic material (`ELAS_ISTR`), in Code_Aster's
    /// convention (`dmat3d`): axes L, T, N; the plane L-T is the plane of
    /// isotropy, N its normal. With no orientation given (no `MASSIF` of
    /// AFFE_CARA_ELEM) L, T, N are the global X, Y, Z. The compliance is
    /// `ε_L = σ_L/E_L - ν_LT σ_T/E_L - ν_LN σ_N/E_L`,
    /// `ε_N = -ν_LN (σ_L + σ_T)/E_L + σ_N/E_N` (so `ν_NL = ν_LN E_N/E_L`),
    /// `γ_LT = 2 (1 + ν_LT)/E_L τ_LT`, `γ_LN = τ_LN/G_LN`, `γ_TN = τ_TN/G_LN`.
    pub fn transverse_isotropic(e_l: f64, e_n: f64, nu_lt: f64, nu_ln: f64, g_ln: f64) -> Result<IsoElastic, String> {
        if !(e_l > 0.0 && e_n > 0.0 && g_ln > 0.0) {
            return Err(format!("E_L = {e_l}, E_N = {e_n} and G_LN = {g_ln} must be positive"));
        }
        let nu_nl = nu_ln * e_n / e_l;
        let delta = 1.0 - nu_lt - 2.0 * nu_ln * nu_nl;
        if !(nu_lt > -1.0 && delta > 0.0) {
            return Err(format!(
                "NU_LT = {nu_lt}, NU_LN = {nu_ln} give no positive definite Hooke matrix \
                 (need NU_LT > -1 and 1 - NU_LT - 2 NU_LN² E_N/E_L > 0)"
            ));
        }
        let c1 = e_l / (1.0 + nu_lt);
        let mut d = [[0.0; 6]; 6];
        d[0][0] = c1 * (1.0 - nu_ln * nu_nl) / delta;
        d[1][1] = d[0][0];
        d[0][1] = c1 * ((1.0 - nu_ln * nu_nl) / delta - 1.0);
        d[1][0] = d[0][1];
        d[0][2] = e_n * nu_ln / delta;
        d[1][2] = d[0][2];
        d[2][0] = d[0][2];
        d[2][1] = d[0][2];
        d[2][2] = e_n * (1.0 - nu_lt) / delta;
        d[3][3] = 0.5 * c1;
        d[4][4] = g_ln;
        d[5][5] = g_ln;
        IsoElastic::from_hooke_3d(d)
    }

    /// True for an isotropic material (E, ν only).
    pub fn is_isotropic(&self) -> bool {
        self.general.is_none()
    }

    /// The error of the element routines when the material cannot be used
    /// with `m` (an anisotropic material in `C_PLAN` or `AXIS`).
    pub fn check(&self, m: Modelisation) -> Result<(), ElementError> {
        if self.general.is_some() && matches!(m, Modelisation::CPlan | Modelisation::Axis) {
            return Err(ElementError::AnisotropicUnsupported { modelisation: m });
        }
        Ok(())
    }

    /// Lamé coefficients (λ, μ).
    pub fn lame(&self) -> (f64, f64) {
        let mu = self.e / (2.0 * (1.0 + self.nu));
        let lambda = self.e * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu));
        (lambda, mu)
    }

    /// The (λ, μ) of the in-plane law actually used by `m`: plane stress
    /// replaces λ by λ* = 2λμ / (λ + 2μ) = Eν / (1 - ν²), computed from E and ν
    /// so that an incompressible material (ν = 0.5, λ = ∞) stays finite there.
    fn effective_lame(&self, m: Modelisation) -> (f64, f64) {
        if m == Modelisation::CPlan {
            let mu = self.e / (2.0 * (1.0 + self.nu));
            (self.e * self.nu / (1.0 - self.nu * self.nu), mu)
        } else {
            self.lame()
        }
    }

    /// Hooke matrix of `m` (`nsig × nsig` block of the returned array), acting
    /// on strains with engineering shear (γ = 2 ε): σ = D [εxx, εyy, εzz, γxy
    /// (, γxz, γyz)]. For `C_PLAN` the εzz row and column are zero (εzz is
    /// eliminated by σzz = 0). For an anisotropic material the 2D matrices
    /// are the `XX YY ZZ XY` block of the 3D one (condensed by σzz = 0 in
    /// `C_PLAN`).
    pub fn hooke(&self, m: Modelisation) -> [[f64; 6]; 6] {
        if let Some(g) = &self.general {
            return general_hooke(g, m);
        }
        let (l, mu) = self.lame();
        let mut d = [[0.0; 6]; 6];
        if m == Modelisation::CPlan {
            let c = self.e / (1.0 - self.nu * self.nu);
            d[0][0] = c;
            d[1][1] = c;
            d[0][1] = c * self.nu;
            d[1][0] = c * self.nu;
            d[3][3] = mu;
            return d;
        }
        for (i, row) in d.iter_mut().enumerate().take(m.nsig()) {
            if i < 3 {
                row[..3].fill(l);
                row[i] = l + 2.0 * mu;
            } else {
                row[i] = mu;
            }
        }
        d
    }
}

/// The Hooke matrix of `m` from a general 3D one (see [`IsoElastic::hooke`]).
#[allow(clippy::needless_range_loop)]
fn general_hooke(g: &[[f64; 6]; 6], m: Modelisation) -> [[f64; 6]; 6] {
    if m == Modelisation::ThreeD {
        return *g;
    }
    let mut d = [[0.0; 6]; 6];
    for i in 0..4 {
        for j in 0..4 {
            d[i][j] = g[i][j];
        }
    }
    if m == Modelisation::CPlan {
        let d22 = d[2][2];
        let (r2, c2) = (d[2], [d[0][2], d[1][2], d[2][2], d[3][2]]);
        for i in [0, 1, 3] {
            for j in [0, 1, 3] {
                d[i][j] -= c2[i] * r2[j] / d22;
            }
        }
        for k in 0..4 {
            d[2][k] = 0.0;
            d[k][2] = 0.0;
        }
    }
    d
}

/// Errors of the element computations.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementError {
    /// The Jacobian determinant is not positive at a Gauss point (inverted
    /// or degenerate cell).
    BadJacobian { cell_type: CellType, gauss_point: usize, det: f64 },
    /// The cell type does not fit the modelisation (e.g. a TETRA4 in D_PLAN).
    WrongCellType { cell_type: CellType, modelisation: Modelisation },
    /// An AXIS Gauss point at r ≤ 0.
    NonPositiveRadius { gauss_point: usize, r: f64 },
    /// An anisotropic material under a modelisation that does not take one.
    AnisotropicUnsupported { modelisation: Modelisation },
}

impl fmt::Display for ElementError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ElementError::BadJacobian { cell_type, gauss_point, det } => write!(
                f,
                "{}: non-positive Jacobian determinant {det:e} at Gauss point {} (inverted or degenerate cell)",
                cell_type.name(),
                gauss_point + 1
            ),
            ElementError::WrongCellType { cell_type, modelisation } => {
                write!(f, "cell type {} is not supported by modelisation {}", cell_type.name(), modelisation.name())
            }
            ElementError::NonPositiveRadius { gauss_point, r } => {
                write!(f, "AXIS: Gauss point {} has radius {r:e} ≤ 0 (x must be the radius, ≥ 0)", gauss_point + 1)
            }
            ElementError::AnisotropicUnsupported { modelisation } => write!(
                f,
                "anisotropic elasticity (ELAS_ISTR) is not supported yet under modelisation {} (3D and D_PLAN are)",
                modelisation.name()
            ),
        }
    }
}

impl std::error::Error for ElementError {}

// ---------------------------------------------------------------------------
// Gauss-point geometry
// ---------------------------------------------------------------------------

/// Geometry of a volume element at one Gauss point.
#[derive(Clone)]
pub struct GaussGeom {
    /// Weight × |det J| (× r in AXIS).
    pub w: f64,
    /// Real coordinates of the point.
    pub x: [f64; 3],
    /// Shape function values.
    pub n: [f64; MAX_NODES],
    /// Shape function gradients in real coordinates.
    pub dn: [[f64; 3]; MAX_NODES],
}

/// Geometry at every point of `rule` for a volume cell of the modelisation.
pub fn gauss_geometry(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    rule: &QuadratureRule,
) -> Result<Vec<GaussGeom>, ElementError> {
    if !m.accepts_volume_cell(t) {
        return Err(ElementError::WrongCellType { cell_type: t, modelisation: m });
    }
    let dim = m.dim();
    let nno = t.nnodes();
    assert_eq!(coords.len(), nno, "{}: wrong number of node coordinates", t.name());
    let mut out = Vec::with_capacity(rule.len());
    let mut n = [0.0; MAX_NODES];
    let mut dref = [[0.0; 3]; MAX_NODES];
    for (g, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        shape_and_deriv(t, xi, &mut n[..nno], &mut dref[..nno]);
        let mut j = [[0.0; 3]; 3];
        let mut x = [0.0; 3];
        for a in 0..nno {
            for i in 0..3 {
                x[i] += n[a] * coords[a][i];
            }
            for i in 0..dim {
                for k in 0..dim {
                    j[i][k] += coords[a][i] * dref[a][k];
                }
            }
        }
        // Cells numbered clockwise have a negative Jacobian; like Code_Aster,
        // integrate with its absolute value and refuse only degenerate cells
        // (a singular or non-finite Jacobian).
        let (det, inv) = jacobian_inverse(&j, dim);
        let Some(inv) = inv else {
            return Err(ElementError::BadJacobian { cell_type: t, gauss_point: g, det });
        };
        let mut dn = [[0.0; 3]; MAX_NODES];
        for a in 0..nno {
            for i in 0..dim {
                dn[a][i] = (0..dim).map(|k| dref[a][k] * inv[k][i]).sum();
            }
        }
        let mut wd = w * det.abs();
        if m == Modelisation::Axis {
            if x[0] <= 0.0 {
                return Err(ElementError::NonPositiveRadius { gauss_point: g, r: x[0] });
            }
            wd *= x[0];
        }
        out.push(GaussGeom { w: wd, x, n, dn });
    }
    Ok(out)
}

/// Default stiffness rule of a volume cell (`RIGI`).
pub fn rigi_rule(t: CellType) -> QuadratureRule {
    family_rule(t, Family::Rigi)
}

/// The `RIGI` rule of the element of modelisation `m` on `t`: [`rigi_rule`], but FPG6 on the
/// axisymmetric TRIA6 (`MEAXTR6` of `meca_axis.py`, where the plane TRIA6 elements take FPG3).
pub fn rigi_rule_of(m: Modelisation, t: CellType) -> QuadratureRule {
    match (m, t) {
        (Modelisation::Axis, CellType::Tria6) => {
            crate::fem::quadrature::aster_rule(t, "FPG6").expect("FPG6 is a TRIA6 family")
        }
        _ => rigi_rule(t),
    }
}

/// `RIGI` rule of the skin (boundary) elements carrying surface loads:
/// SEG2 FPG2, SEG3 FPG4, TRIA3 FPG3, TRIA6 FPG6, QUAD4 FPG4, QUAD8/9 FPG9
/// (Code_Aster `meca_2d_skin.py`, `MECA_FACE*` of `meca_3d.py`).
pub fn boundary_rule(t: CellType) -> QuadratureRule {
    use CellType::*;
    let name = match t {
        Seg2 => "FPG2",
        Seg3 => "FPG4",
        Tria3 => "FPG3",
        Tria6 => "FPG6",
        Quad4 => "FPG4",
        Quad8 | Quad9 => "FPG9",
        _ => "FPG1",
    };
    aster_rule(t, name).unwrap_or_else(|| panic!("no {name} rule on {}", t.name()))
}

// ---------------------------------------------------------------------------
// Stiffness
// ---------------------------------------------------------------------------

/// Element stiffness matrix `K = ∫ Bᵀ D B`, row-major, size
/// `(nnodes·dim)²`, dofs node by node.
pub fn stiffness(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
) -> Result<Vec<f64>, ElementError> {
    mat.check(m)?;
    if !mat.is_isotropic() {
        return stiffness_general(m, &mat.hooke(m), t, coords);
    }
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let dim = m.dim();
    let nno = t.nnodes();
    let nd = nno * dim;
    let mut k = vec![0.0; nd * nd];
    let (l, mu) = mat.effective_lame(m);
    let l2m = l + 2.0 * mu;
    for g in &gg {
        let w = g.w;
        let r = g.x[0];
        for a in 0..nno {
            let da = g.dn[a];
            for b in 0..=a {
                let db = g.dn[b];
                let dot: f64 = (0..dim).map(|i| da[i] * db[i]).sum();
                for i in 0..dim {
                    let row = (a * dim + i) * nd + b * dim;
                    for j in 0..dim {
                        let mut v = l * da[i] * db[j] + mu * da[j] * db[i];
                        if i == j {
                            v += mu * dot;
                        }
                        k[row + j] += w * v;
                    }
                }
                if m == Modelisation::Axis {
                    let (na, nb) = (g.n[a] / r, g.n[b] / r);
                    // hoop terms: (λ+2μ) εθθ εθθ + λ (εθθ tr2 + tr2 εθθ)
                    k[(a * dim) * nd + b * dim] += w * l2m * na * nb;
                    for j in 0..dim {
                        k[(a * dim) * nd + b * dim + j] += w * l * na * db[j];
                        k[(a * dim + j) * nd + b * dim] += w * l * nb * da[j];
                    }
                }
            }
        }
    }
    // Symmetrize: copy the lower node blocks to the upper ones.
    for a in 0..nno {
        for b in 0..a {
            for i in 0..dim {
                for j in 0..dim {
                    k[(b * dim + j) * nd + a * dim + i] = k[(a * dim + i) * nd + b * dim + j];
                }
            }
        }
    }
    Ok(k)
}

/// The B matrix rows of node `a` at a Gauss point (engineering shear):
/// `b[c][i]` = contribution of displacement component `i` of node `a` to
/// strain component `c`.
pub fn b_node(m: Modelisation, g: &GaussGeom, a: usize) -> [[f64; 3]; 6] {
    let d = g.dn[a];
    let mut b = [[0.0; 3]; 6];
    b[0][0] = d[0];
    b[1][1] = d[1];
    b[3][0] = d[1];
    b[3][1] = d[0];
    match m {
        Modelisation::ThreeD => {
            b[2][2] = d[2];
            b[4][0] = d[2];
            b[4][2] = d[0];
            b[5][1] = d[2];
            b[5][2] = d[1];
        }
        Modelisation::Axis => b[2][0] = g.n[a] / g.x[0],
        _ => {}
    }
    b
}

/// Add `w Bᵀ D B` of the point `g` of a cell of `nno` nodes to the element matrix `k` (row-major, dofs
/// node by node), for any matrix `d` acting on engineering strains: `D B` is formed once per node.
pub fn add_btdb(m: Modelisation, g: &GaussGeom, nno: usize, d: &[[f64; 6]; 6], k: &mut [f64]) {
    let (dim, ns) = (m.dim(), m.nsig());
    let nd = nno * dim;
    let bs: Vec<_> = (0..nno).map(|a| b_node(m, g, a)).collect();
    // db[b][p][j] = Σ_q D[p][q] B_b[q][j]
    let db: Vec<[[f64; 3]; 6]> = bs
        .iter()
        .map(|bb| {
            let mut out = [[0.0; 3]; 6];
            for (p, row) in out.iter_mut().enumerate().take(ns) {
                for (j, v) in row.iter_mut().enumerate().take(dim) {
                    *v = (0..ns).map(|q| d[p][q] * bb[q][j]).sum();
                }
            }
            out
        })
        .collect();
    for a in 0..nno {
        for b in 0..nno {
            for i in 0..dim {
                for j in 0..dim {
                    let s: f64 = (0..ns).map(|p| bs[a][p][i] * db[b][p][j]).sum();
                    k[(a * dim + i) * nd + b * dim + j] += g.w * s;
                }
            }
        }
    }
}

/// Add `w Bᵀ σ` of the point `g` of a cell of `nno` nodes to the element vector `f` (dofs node by node).
pub fn add_bt_sigma(m: Modelisation, g: &GaussGeom, nno: usize, sig: &[f64; 6], f: &mut [f64]) {
    let (dim, ns) = (m.dim(), m.nsig());
    for a in 0..nno {
        let b = b_node(m, g, a);
        for i in 0..dim {
            f[a * dim + i] += g.w * (0..ns).map(|p| b[p][i] * sig[p]).sum::<f64>();
        }
    }
}

/// `K = ∫ Bᵀ D B` for any Hooke matrix `d` of `m` (anisotropic materials).
fn stiffness_general(
    m: Modelisation,
    d: &[[f64; 6]; 6],
    t: CellType,
    coords: &[[f64; 3]],
) -> Result<Vec<f64>, ElementError> {
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let nno = t.nnodes();
    let nd = nno * m.dim();
    let mut k = vec![0.0; nd * nd];
    for g in &gg {
        add_btdb(m, g, nno, d, &mut k);
    }
    Ok(k)
}

/// Reference implementation of [`stiffness`] by explicit `Bᵀ D B` products
/// (slower; used to cross-check the fast formula).
pub fn stiffness_btdb(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
) -> Result<Vec<f64>, ElementError> {
    mat.check(m)?;
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let (dim, ns, nno) = (m.dim(), m.nsig(), t.nnodes());
    let nd = nno * dim;
    let d = mat.hooke(m);
    let mut k = vec![0.0; nd * nd];
    for g in &gg {
        let bs: Vec<_> = (0..nno).map(|a| b_node(m, g, a)).collect();
        for a in 0..nno {
            for b in 0..nno {
                for i in 0..dim {
                    for j in 0..dim {
                        let mut s = 0.0;
                        for p in 0..ns {
                            for q in 0..ns {
                                s += bs[a][p][i] * d[p][q] * bs[b][q][j];
                            }
                        }
                        k[(a * dim + i) * nd + b * dim + j] += g.w * s;
                    }
                }
            }
        }
    }
    Ok(k)
}

// ---------------------------------------------------------------------------
// Strains and stresses
// ---------------------------------------------------------------------------

/// Strains and stresses at the Gauss points of a cell (`EPSI_ELGA`,
/// `SIEF_ELGA`), components in Code_Aster's order (first `nsig` entries).
#[derive(Debug, Clone, PartialEq)]
pub struct GaussFields {
    /// Real coordinates of the Gauss points.
    pub points: Vec<[f64; 3]>,
    /// Tensorial strains (`EPXY = γ/2`).
    pub eps: Vec<[f64; 6]>,
    pub sig: Vec<[f64; 6]>,
}

/// Strain (tensorial shear) of a given displacement at one Gauss point.
fn strain_at(m: Modelisation, mat: &IsoElastic, g: &GaussGeom, nno: usize, u: &[f64]) -> [f64; 6] {
    let dim = m.dim();
    let mut e = [0.0; 6];
    for a in 0..nno {
        let b = b_node(m, g, a);
        for (c, row) in b.iter().enumerate().take(m.nsig()) {
            for i in 0..dim {
                e[c] += row[i] * u[a * dim + i];
            }
        }
    }
    for v in e.iter_mut().skip(3) {
        *v *= 0.5;
    }
    if m == Modelisation::CPlan {
        e[2] = -mat.nu / (1.0 - mat.nu) * (e[0] + e[1]);
    }
    e
}

/// Stress from a tensorial strain (for C_PLAN the εzz entry is ignored and
/// σzz = 0).
pub fn stress_from_strain(m: Modelisation, mat: &IsoElastic, eps: &[f64; 6]) -> [f64; 6] {
    let d = mat.hooke(m);
    let ns = m.nsig();
    let mut eng = *eps;
    for v in eng.iter_mut().skip(3) {
        *v *= 2.0;
    }
    if m == Modelisation::CPlan {
        eng[2] = 0.0;
    }
    let mut s = [0.0; 6];
    for p in 0..ns {
        s[p] = (0..ns).map(|q| d[p][q] * eng[q]).sum();
    }
    s
}

/// Strains and stresses at the `RIGI` Gauss points for the element
/// displacement `u` (node by node).
pub fn gauss_fields(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
    u: &[f64],
) -> Result<GaussFields, ElementError> {
    gauss_fields_thermal(m, mat, t, coords, u, &vec![0.0; t.nnodes()])
}

/// θ at a point from its values at the nodes.
fn at_point(g: &GaussGeom, nodal: &[f64]) -> f64 {
    nodal.iter().enumerate().map(|(a, v)| g.n[a] * v).sum()
}

/// The nodal forces of an isotropic thermal strain `θ (1, 1, 1, 0, 0, 0)`, `θ = α (T − T_ref)` given at the
/// cell's nodes and interpolated at the `RIGI` points: `∫ Bᵀ D ε_th` (node by node). Under C_PLAN the
/// strain out of the plane is free (σzz = 0).
pub fn thermal_force(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
    theta: &[f64],
) -> Result<Vec<f64>, ElementError> {
    mat.check(m)?;
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let (dim, ns, nno) = (m.dim(), m.nsig(), t.nnodes());
    let mut v = vec![0.0; nno * dim];
    for g in &gg {
        let th = at_point(g, theta);
        let sig = stress_from_strain(m, mat, &[th, th, th, 0.0, 0.0, 0.0]);
        for a in 0..nno {
            let b = b_node(m, g, a);
            for i in 0..dim {
                v[a * dim + i] += g.w * (0..ns).map(|p| b[p][i] * sig[p]).sum::<f64>();
            }
        }
    }
    Ok(v)
}

/// [`gauss_fields`] with a thermal strain `θ (1, 1, 1, 0, 0, 0)` (`θ` at the nodes): the strains are the
/// total ones, the stresses `D (ε − ε_th)`.
pub fn gauss_fields_thermal(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
    u: &[f64],
    theta: &[f64],
) -> Result<GaussFields, ElementError> {
    mat.check(m)?;
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let nno = t.nnodes();
    assert_eq!(u.len(), nno * m.dim());
    let mut out = GaussFields { points: vec![], eps: vec![], sig: vec![] };
    for g in &gg {
        let th = at_point(g, theta);
        let mut e = strain_at(m, mat, g, nno, u);
        if m == Modelisation::CPlan {
            // σzz = 0: εzz = −ν/(1−ν) (εxx + εyy − 2θ) + θ.
            e[2] = -mat.nu / (1.0 - mat.nu) * (e[0] + e[1] - 2.0 * th) + th;
        }
        let mut mech = e;
        for v in mech.iter_mut().take(3) {
            *v -= th;
        }
        out.points.push(g.x);
        out.sig.push(stress_from_strain(m, mat, &mech));
        out.eps.push(e);
    }
    Ok(out)
}

/// The nodal forces `∫ Bᵀ σ` of the stresses `sig` at the `RIGI` points of a cell (FORC_NODA), node by
/// node.
pub fn internal_forces(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    sig: &[[f64; 6]],
) -> Result<Vec<f64>, ElementError> {
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let nno = t.nnodes();
    let mut v = vec![0.0; nno * m.dim()];
    for (g, s) in gg.iter().zip(sig) {
        add_bt_sigma(m, g, nno, s, &mut v);
    }
    Ok(v)
}

/// The vertex (linear) cell type of `t` (QUAD4 for QUAD8, ...).
pub fn vertex_type(t: CellType) -> CellType {
    use CellType::*;
    match t {
        Seg3 => Seg2,
        Tria6 => Tria3,
        Quad8 | Quad9 => Quad4,
        Tetra10 => Tetra4,
        Penta15 => Penta6,
        Pyram13 => Pyram5,
        Hexa20 | Hexa27 => Hexa8,
        other => other,
    }
}

/// Code_Aster's Gauss → node extrapolation matrix of `rule` on `t`:
/// `m[node][gauss]` (see the module documentation).
pub fn gauss_to_node_matrix(t: CellType, rule: &QuadratureRule) -> Vec<Vec<f64>> {
    let nno = t.nnodes();
    let npg = rule.len();
    if npg == 1 {
        return vec![vec![1.0]; nno];
    }
    let tv = vertex_type(t);
    let nnos = tv.nnodes();
    // Least squares: (Σ_g N Nᵀ)⁻¹ [N(ξ_g)]_g, by nalgebra's LU with partial
    // pivoting. The vertex element is unisolvent on the RIGI points of every
    // cell type (the tests cover them all), so the system is regular.
    let p: Vec<Vec<f64>> = rule.points.iter().map(|xi| shape(tv, xi)).collect();
    let mm = DMatrix::from_fn(nnos, nnos, |i, j| p.iter().map(|pg| pg[i] * pg[j]).sum());
    let rhs = DMatrix::from_fn(nnos, npg, |i, g| p[g][i]);
    let x = mm.lu().solve(&rhs).expect("the vertex element is unisolvent on the Gauss points");
    let mut out: Vec<Vec<f64>> = x.row_iter().map(|r| r.iter().copied().collect()).collect();
    // Other nodes: linear (vertex-element) interpolation of vertex values.
    let nodes = node_coords(t);
    for node in nodes.iter().take(nno).skip(nnos) {
        let w = shape(tv, node);
        let row: Vec<f64> = (0..npg).map(|g| (0..nnos).map(|s| w[s] * x[(s, g)]).sum()).collect();
        out.push(row);
    }
    out
}

/// Extrapolate Gauss-point values (first `ncmp` components) of a cell to its
/// nodes, Code_Aster's way (`*_ELNO` from `*_ELGA` on the `RIGI` family).
pub fn gauss_to_nodes(m: Modelisation, t: CellType, values: &[[f64; 6]], ncmp: usize) -> Vec<[f64; 6]> {
    let rule = rigi_rule_of(m, t);
    assert_eq!(values.len(), rule.len());
    let m = gauss_to_node_matrix(t, &rule);
    m.iter()
        .map(|row| {
            let mut v = [0.0; 6];
            for (w, g) in row.iter().zip(values) {
                for c in 0..ncmp {
                    v[c] += w * g[c];
                }
            }
            v
        })
        .collect()
}

/// Values at the nodes of a cell: (strains, stresses).
pub type NodeFields = (Vec<[f64; 6]>, Vec<[f64; 6]>);

/// A surface traction density as a function of (point, unit normal).
pub type TractionFn<'a> = dyn Fn(&[f64; 3], &[f64; 3]) -> [f64; 3] + 'a;

/// `SIGM_ELNO` and `EPSI_ELNO` of a cell: (strains, stresses) at its nodes.
pub fn node_fields(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
    u: &[f64],
) -> Result<NodeFields, ElementError> {
    node_fields_thermal(m, mat, t, coords, u, &vec![0.0; t.nnodes()])
}

/// [`node_fields`] with a thermal strain `θ` at the nodes ([`gauss_fields_thermal`]).
pub fn node_fields_thermal(
    m: Modelisation,
    mat: &IsoElastic,
    t: CellType,
    coords: &[[f64; 3]],
    u: &[f64],
    theta: &[f64],
) -> Result<NodeFields, ElementError> {
    let g = gauss_fields_thermal(m, mat, t, coords, u, theta)?;
    Ok((gauss_to_nodes(m, t, &g.eps, m.nsig()), gauss_to_nodes(m, t, &g.sig, m.nsig())))
}

// ---------------------------------------------------------------------------
// Loads
// ---------------------------------------------------------------------------

/// Nodal forces of a body force density `f(x)` (force per unit volume) on a
/// volume cell: `F_a = ∫ N_a f` (× r in AXIS), on the `RIGI` rule. Gravity
/// (`PESANTEUR`) is `f = ρ g d` with `d` the unit direction.
pub fn body_force(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    f: &dyn Fn(&[f64; 3]) -> [f64; 3],
) -> Result<Vec<f64>, ElementError> {
    let rule = rigi_rule_of(m, t);
    let gg = gauss_geometry(m, t, coords, &rule)?;
    let (dim, nno) = (m.dim(), t.nnodes());
    let mut v = vec![0.0; nno * dim];
    for g in &gg {
        let fx = f(&g.x);
        for a in 0..nno {
            for i in 0..dim {
                v[a * dim + i] += g.w * g.n[a] * fx[i];
            }
        }
    }
    Ok(v)
}

/// Geometry of a boundary cell at one Gauss point.
#[derive(Debug, Clone)]
pub struct BoundaryPoint {
    /// Weight × length / area element (× r in AXIS).
    pub w: f64,
    pub x: [f64; 3],
    /// Unit normal in Code_Aster's convention (see the module documentation).
    pub normal: [f64; 3],
    pub n: Vec<f64>,
}

/// Gauss points of a boundary (skin) cell: SEG2/SEG3 in 2D (`dim = 2`),
/// TRIA3/6, QUAD4/8/9 in 3D.
pub fn boundary_points(m: Modelisation, t: CellType, coords: &[[f64; 3]]) -> Result<Vec<BoundaryPoint>, ElementError> {
    boundary_points_on(m, t, coords, &boundary_rule(t))
}

/// [`boundary_points`] at the points of `rule` (another physics' skin family).
pub fn boundary_points_on(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    rule: &QuadratureRule,
) -> Result<Vec<BoundaryPoint>, ElementError> {
    if !m.accepts_boundary_cell(t) {
        return Err(ElementError::WrongCellType { cell_type: t, modelisation: m });
    }
    let nno = t.nnodes();
    let mut n = [0.0; MAX_NODES];
    let mut dref = [[0.0; 3]; MAX_NODES];
    let mut out = Vec::with_capacity(rule.len());
    for (gp, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        shape_and_deriv(t, xi, &mut n[..nno], &mut dref[..nno]);
        let mut x = [0.0; 3];
        let mut t1 = [0.0; 3];
        let mut t2 = [0.0; 3];
        for a in 0..nno {
            for i in 0..3 {
                x[i] += n[a] * coords[a][i];
                t1[i] += dref[a][0] * coords[a][i];
                t2[i] += dref[a][1] * coords[a][i];
            }
        }
        let (jac, normal) = if t.dim() == 1 {
            let l = Vector2::new(t1[0], t1[1]).norm();
            (l, [t1[1] / l, -t1[0] / l, 0.0])
        } else {
            let c = Vector3::from(t1).cross(&Vector3::from(t2));
            let l = c.norm();
            (l, (c / l).into())
        };
        if jac.is_nan() || jac <= 0.0 {
            return Err(ElementError::BadJacobian { cell_type: t, gauss_point: gp, det: jac });
        }
        let mut wd = w * jac;
        if m == Modelisation::Axis {
            wd *= x[0];
        }
        out.push(BoundaryPoint { w: wd, x, normal, n: n[..nno].to_vec() });
    }
    Ok(out)
}

/// Nodal forces of a surface traction `f(x, normal)` (force per unit length
/// in 2D / area in 3D) on a boundary cell: `FORCE_CONTOUR`, `FORCE_FACE`.
pub fn boundary_force(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    f: &TractionFn<'_>,
) -> Result<Vec<f64>, ElementError> {
    let pts = boundary_points(m, t, coords)?;
    let (dim, nno) = (m.dim(), t.nnodes());
    let mut v = vec![0.0; nno * dim];
    for p in &pts {
        let fx = f(&p.x, &p.normal);
        for a in 0..nno {
            for i in 0..dim {
                v[a * dim + i] += p.w * p.n[a] * fx[i];
            }
        }
    }
    Ok(v)
}

/// Nodal forces of a pressure (`PRES_REP`) given by its values at the cell's
/// nodes (interpolated to the Gauss points), with an optional 2D shear
/// `CISA` (nodal values too): traction `-p n + c t`.
pub fn pressure_force(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    pres: &[f64],
    cisa: Option<&[f64]>,
) -> Result<Vec<f64>, ElementError> {
    let pts = boundary_points(m, t, coords)?;
    let (dim, nno) = (m.dim(), t.nnodes());
    assert_eq!(pres.len(), nno);
    let mut v = vec![0.0; nno * dim];
    for pt in &pts {
        let p: f64 = pt.n.iter().zip(pres).map(|(a, b)| a * b).sum();
        let c: f64 = cisa.map(|c| pt.n.iter().zip(c).map(|(a, b)| a * b).sum()).unwrap_or(0.0);
        let nr = pt.normal;
        let tr = [-nr[0] * p - nr[1] * c, -nr[1] * p + nr[0] * c, -nr[2] * p];
        for a in 0..nno {
            for i in 0..dim {
                v[a * dim + i] += pt.w * pt.n[a] * tr[i];
            }
        }
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ref_coords(t: CellType, scale: f64) -> Vec<[f64; 3]> {
        // A distorted copy of the reference element, moved to x ≥ 1 (AXIS).
        node_coords(t)
            .iter()
            .map(|p| {
                let (x, y, z) = (p[0], p[1], p[2]);
                [2.0 + scale * (x + 0.1 * y + 0.05 * x * y), 0.5 + scale * (y - 0.07 * x + 0.02 * z), z + 0.03 * x * y]
            })
            .collect()
    }

    #[test]
    fn hooke_matrices() {
        let mat = IsoElastic::new(200e9, 0.3);
        let (l, mu) = mat.lame();
        assert!((mu - 200e9 / 2.6).abs() < 1e-3);
        assert!((l - 200e9 * 0.3 / (1.3 * 0.4)).abs() < 1e-3);
        let d = mat.hooke(Modelisation::DPlan);
        assert_eq!(d[2][0], l);
        assert_eq!(d[3][3], mu);
        let c = mat.hooke(Modelisation::CPlan);
        assert!((c[0][0] - 200e9 / 0.91).abs() < 1e-2);
        assert_eq!(c[2][2], 0.0);
        let d3 = mat.hooke(Modelisation::ThreeD);
        assert_eq!(d3[5][5], mu);
        assert_eq!(d3[0][0], l + 2.0 * mu);
    }

    const ISTR: (f64, f64, f64, f64, f64) = (5.0e11, 2.0e11, 0.1, 0.3, 7.7e10);

    fn istr() -> IsoElastic {
        let (el, en, nlt, nln, g) = ISTR;
        IsoElastic::transverse_isotropic(el, en, nlt, nln, g).unwrap()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs())
    }

    #[test]
    fn transverse_isotropic_reduces_to_isotropic() {
        let (e, nu) = (210e9, 0.28);
        let iso = IsoElastic::new(e, nu);
        let ti = IsoElastic::transverse_isotropic(e, e, nu, nu, e / (2.0 * (1.0 + nu))).unwrap();
        assert!(!ti.is_isotropic());
        assert!(close(ti.e, e, 1e-13) && close(ti.nu, nu, 1e-12));
        for m in [Modelisation::ThreeD, Modelisation::DPlan, Modelisation::CPlan, Modelisation::Axis] {
            let (a, b) = (iso.hooke(m), ti.hooke(m));
            for i in 0..6 {
                for j in 0..6 {
                    assert!((a[i][j] - b[i][j]).abs() <= 1e-12 * a[0][0], "{m:?} {i}{j}: {} {}", a[i][j], b[i][j]);
                }
            }
        }
    }

    #[test]
    #[allow(clippy::needless_range_loop)]
    fn transverse_isotropic_compliance() {
        let (el, en, nlt, nln, g) = ISTR;
        let s = spd_inverse6(&istr().hooke(Modelisation::ThreeD)).unwrap();
        let mut want = [[0.0; 6]; 6];
        want[0][0] = 1.0 / el;
        want[1][1] = 1.0 / el;
        want[2][2] = 1.0 / en;
        want[0][1] = -nlt / el;
        want[1][0] = -nlt / el;
        for k in 0..2 {
            want[k][2] = -nln / el;
            want[2][k] = -nln / el;
        }
        want[3][3] = 2.0 * (1.0 + nlt) / el;
        want[4][4] = 1.0 / g;
        want[5][5] = 1.0 / g;
        for i in 0..6 {
            for j in 0..6 {
                assert!(
                    (s[i][j] - want[i][j]).abs() <= 1e-12 * s[i][i].abs(),
                    "S{i}{j}: {} vs {}",
                    s[i][j],
                    want[i][j]
                );
            }
        }
    }

    #[test]
    fn uniaxial_stress_along_n() {
        let (el, en, _, nln, _) = ISTR;
        let mat = istr();
        let sig = 3.0e7;
        // Strain of σ = σ e_N, checked through the Hooke matrix: D ε = σ.
        let s = spd_inverse6(&mat.hooke(Modelisation::ThreeD)).unwrap();
        let eps: Vec<f64> = (0..6).map(|i| s[i][2] * sig).collect();
        assert!(close(eps[2], sig / en, 1e-12));
        assert!(close(eps[0], -nln * sig / el, 1e-12) && close(eps[1], eps[0], 1e-12));
        let tens = [eps[0], eps[1], eps[2], 0.0, 0.0, 0.0];
        let back = stress_from_strain(Modelisation::ThreeD, &mat, &tens);
        assert!(close(back[2], sig, 1e-12) && back[0].abs() < 1e-6 * sig && back[1].abs() < 1e-6 * sig);
        // On a hexahedron: the uniform strain field of that stress.
        let c = ref_coords(CellType::Hexa8, 1.0);
        let u: Vec<f64> = c.iter().flat_map(|x| [eps[0] * x[0], eps[1] * x[1], eps[2] * x[2]]).collect();
        let g = gauss_fields(Modelisation::ThreeD, &mat, CellType::Hexa8, &c, &u).unwrap();
        for s in &g.sig {
            assert!(close(s[2], sig, 1e-10) && s[0].abs() < 1e-8 * sig && s[3].abs() < 1e-8 * sig);
        }
    }

    #[test]
    fn anisotropic_stiffness_matches_btdb_and_refuses_cplan_axis() {
        let mat = istr();
        for (m, t) in cases() {
            let c = ref_coords(t, 1.3);
            if matches!(m, Modelisation::CPlan | Modelisation::Axis) {
                let err = stiffness(m, &mat, t, &c).unwrap_err();
                assert_eq!(err, ElementError::AnisotropicUnsupported { modelisation: m });
                assert!(gauss_fields(m, &mat, t, &c, &vec![0.0; t.nnodes() * 2]).is_err());
                continue;
            }
            let k = stiffness(m, &mat, t, &c).unwrap();
            let k2 = stiffness_btdb(m, &mat, t, &c).unwrap();
            let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            for (a, b) in k.iter().zip(&k2) {
                assert!((a - b).abs() < 1e-11 * kmax, "{m:?} {t:?}");
            }
        }
        // An isotropic material written as a general matrix gives the fast formula's stiffness.
        let iso = IsoElastic::new(1000.0, 0.27);
        let gen = IsoElastic::from_hooke_3d(iso.hooke(Modelisation::ThreeD)).unwrap();
        for (m, t) in cases().into_iter().filter(|(m, _)| matches!(m, Modelisation::ThreeD | Modelisation::DPlan)) {
            let c = ref_coords(t, 1.3);
            let (k, k2) = (stiffness(m, &iso, t, &c).unwrap(), stiffness(m, &gen, t, &c).unwrap());
            let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            for (a, b) in k.iter().zip(&k2) {
                assert!((a - b).abs() < 1e-11 * kmax, "{m:?} {t:?}");
            }
        }
        assert!(IsoElastic::transverse_isotropic(1.0, 1.0, 0.6, 0.5, 1.0).is_err());
        assert!(IsoElastic::transverse_isotropic(1.0, -1.0, 0.1, 0.1, 1.0).is_err());
    }

    fn cases() -> Vec<(Modelisation, CellType)> {
        use CellType::*;
        let mut v = vec![];
        for t in [Tria3, Tria6, Quad4, Quad8, Quad9] {
            for m in [Modelisation::DPlan, Modelisation::CPlan, Modelisation::Axis] {
                v.push((m, t));
            }
        }
        for t in [Tetra4, Tetra10, Penta6, Penta15, Pyram5, Pyram13, Hexa8, Hexa20, Hexa27] {
            v.push((Modelisation::ThreeD, t));
        }
        v
    }

    #[test]
    fn stiffness_symmetric_matches_btdb_and_rigid_modes() {
        let mat = IsoElastic::new(1000.0, 0.27);
        for (m, t) in cases() {
            let c = ref_coords(t, 1.3);
            let k = stiffness(m, &mat, t, &c).unwrap();
            let k2 = stiffness_btdb(m, &mat, t, &c).unwrap();
            let nd = t.nnodes() * m.dim();
            let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            for i in 0..nd {
                for j in 0..nd {
                    assert!((k[i * nd + j] - k[j * nd + i]).abs() < 1e-12 * kmax, "{m:?} {t:?} sym");
                    assert!((k[i * nd + j] - k2[i * nd + j]).abs() < 1e-11 * kmax, "{m:?} {t:?} btdb");
                }
            }
            // Rigid-body modes: translations (not radial in AXIS), rotations.
            let dim = m.dim();
            let mut modes: Vec<Vec<f64>> = vec![];
            for i in 0..dim {
                if m == Modelisation::Axis && i == 0 {
                    continue;
                }
                modes.push((0..nd).map(|q| if q % dim == i { 1.0 } else { 0.0 }).collect());
            }
            if m != Modelisation::Axis {
                let rots: &[(usize, usize)] = if dim == 2 { &[(0, 1)] } else { &[(0, 1), (0, 2), (1, 2)] };
                for &(p, q) in rots {
                    let mut u = vec![0.0; nd];
                    for (a, x) in c.iter().enumerate() {
                        u[a * dim + p] = -x[q];
                        u[a * dim + q] = x[p];
                    }
                    modes.push(u);
                }
            }
            for u in modes {
                for i in 0..nd {
                    let r: f64 = (0..nd).map(|j| k[i * nd + j] * u[j]).sum();
                    assert!(r.abs() < 1e-10 * kmax, "{m:?} {t:?} rigid mode residual {r}");
                }
            }
        }
    }

    #[test]
    fn extrapolation_reproduces_linear_fields() {
        for (m, t) in cases() {
            let rule = rigi_rule(t);
            let mm = gauss_to_node_matrix(t, &rule);
            // Rows sum to one (constants are reproduced).
            for row in &mm {
                let s: f64 = row.iter().sum();
                assert!((s - 1.0).abs() < 1e-12, "{m:?} {t:?}");
            }
            assert_eq!(mm.len(), t.nnodes());
        }
    }

    #[test]
    fn pressure_on_unit_segment_and_face() {
        // Segment from (0,0) to (1,0): n = (0,-1); pressure 2 → force +2 along y.
        let c = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let f = pressure_force(Modelisation::DPlan, CellType::Seg2, &c, &[2.0, 2.0], None).unwrap();
        assert!((f[1] - 1.0).abs() < 1e-14 && (f[3] - 1.0).abs() < 1e-14 && f[0].abs() < 1e-14);
        // Counter-clockwise unit square face in z = 0: n = +z, force -p z.
        let q = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let f = pressure_force(Modelisation::ThreeD, CellType::Quad4, &q, &[3.0; 4], None).unwrap();
        let fz: f64 = (0..4).map(|a| f[3 * a + 2]).sum();
        assert!((fz + 3.0).abs() < 1e-13);
    }
}
