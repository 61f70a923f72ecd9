//! The skin elements of heat conduction: a boundary heat flux density and its tangent, and the
//! exchange between two walls.
//!
//! Families (Code_Aster's `ther_*_skin.py`): FPG4 on SEG2 and SEG3, COT3 on TRIA3, FPG6 on TRIA6, FPG4
//! on QUAD4, FPG9 on QUAD8/9. Every boundary condition of `AFFE_CHAR_THER(_F)` but the prescribed
//! temperatures is a density `q(x, n, T)` of heat entering the body, integrated as `∫ q N`, with the
//! derivative `∫ ∂q/∂T N Nᵀ`:
//! - `FLUX_REP` `FLUN`: `q`; `FLUX_X FLUX_Y FLUX_Z`: `q = φ · n`;
//! - `ECHANGE`: `q = h (T_ext − T)`;
//! - `RAYONNEMENT`: `q = σ ε ((T_ext + 273.15)⁴ − (T + 273.15)⁴)`;
//! - `FLUX_NL`: `q = f(T)`.
//!
//! The normal `n` is the skin cell's (`(t_y, −t_x)` for a segment, `∂x/∂ξ × ∂x/∂η` for a face): outward
//! for a skin oriented as Code_Aster's `ORIE_PEAU` leaves it.
//!
//! `ECHANGE_PAROI` joins two faces whose nodes are paired: `h (T₂ − T₁)` enters face 1 and the opposite
//! face 2, a matrix `[[A, −A], [−A, A]]` with `A = ∫ h N Nᵀ` on face 1 in 3D, on the mean of the two
//! segments' weights in 2D (Code_Aster's `te0301`, `te0211`; FPG2 on SEG2, FPG4 on SEG3).

use super::element::{family, radius, Kinematics, Modelisation, PointLaw, ThermalError};
use crate::fem::elasticity::{boundary_points_on, BoundaryPoint, Modelisation as Mech};
use crate::fem::quadrature::QuadratureRule;
use crate::mesh::CellType;

/// `°C` to `K`, as the radiation law adds it.
pub const ZERO_CELSIUS: f64 = 273.15;

/// The family of a skin element.
pub fn skin_rule(t: CellType) -> QuadratureRule {
    use CellType::*;
    let name = match t {
        Seg2 | Seg3 | Quad4 => "FPG4",
        Tria3 => "COT3",
        Tria6 => "FPG6",
        Quad8 | Quad9 => "FPG9",
        _ => "FPG1",
    };
    family(name, t)
}

fn points_on(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    rule: &QuadratureRule,
) -> Result<Vec<BoundaryPoint>, ThermalError> {
    if !m.accepts_skin(t) {
        return Err(ThermalError::WrongCell { cell_type: t, modelisation: m.name() });
    }
    let mech = if m.dim() == 3 { Mech::ThreeD } else { Mech::DPlan };
    let mut pts = boundary_points_on(mech, t, coords, rule)?;
    if m.kinematics == Kinematics::Axis {
        let size = coords.iter().map(|c| c[0].abs().max(c[1].abs())).fold(0.0, f64::max);
        for (g, p) in pts.iter_mut().enumerate() {
            p.w *= radius(p.x[0], size, g)?;
        }
    }
    Ok(pts)
}

/// The geometry of a skin cell at its family's points: weight (× r in `AXIS`), point, unit normal,
/// shape functions.
pub fn skin_points(m: Modelisation, t: CellType, coords: &[[f64; 3]]) -> Result<Vec<BoundaryPoint>, ThermalError> {
    points_on(m, t, coords, &skin_rule(t))
}

/// A boundary heat flux density `q(point, T)` entering the body (with `∂q/∂T`), integrated on a skin
/// cell: the load `∫ q N` and its derivative `∫ ∂q/∂T N Nᵀ`. `temps` None where `q` does not depend on
/// the temperature (it is then given 0).
pub fn skin_load(
    m: Modelisation,
    t: CellType,
    coords: &[[f64; 3]],
    temps: Option<&[f64]>,
    q: &PointLaw<'_, BoundaryPoint>,
) -> Result<(Vec<f64>, Vec<f64>), ThermalError> {
    let pts = skin_points(m, t, coords)?;
    super::element::density(&pts, t.nnodes(), temps, |p| (p.w, &p.n), q)
}

/// The radiation density `σ ε ((T_ext + 273.15)⁴ − (T + 273.15)⁴)` and its derivative in `T`.
pub fn radiation(sigma: f64, epsilon: f64, t_ext: f64, t: f64) -> (f64, f64) {
    let (a, b) = (t_ext + ZERO_CELSIUS, t + ZERO_CELSIUS);
    (sigma * epsilon * (a.powi(4) - b.powi(4)), -4.0 * sigma * epsilon * b.powi(3))
}

/// The exchange matrix of two paired walls (`ECHANGE_PAROI`), `2n × 2n` over the nodes of face 1 then
/// those of face 2 (node `i` of face 2 paired with node `i` of face 1); `h` is evaluated at face 1's
/// points.
pub fn wall_exchange(
    m: Modelisation,
    t: CellType,
    face1: &[[f64; 3]],
    face2: &[[f64; 3]],
    h: &dyn Fn(&[f64; 3]) -> Result<f64, ThermalError>,
) -> Result<Vec<f64>, ThermalError> {
    let rule = match t {
        CellType::Seg2 => family("FPG2", t),
        _ => skin_rule(t),
    };
    let p1 = points_on(m, t, face1, &rule)?;
    let w2: Vec<f64> =
        if m.dim() == 2 { points_on(m, t, face2, &rule)?.iter().map(|p| p.w).collect() } else { Vec::new() };
    let n = t.nnodes();
    let mut a = vec![0.0; n * n];
    for (g, p) in p1.iter().enumerate() {
        let w = if m.dim() == 2 { 0.5 * (p.w + w2[g]) } else { p.w };
        let hv = h(&p.x)?;
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] += w * hv * p.n[i] * p.n[j];
            }
        }
    }
    let nn = 2 * n;
    let mut out = vec![0.0; nn * nn];
    for i in 0..n {
        for j in 0..n {
            let v = a[i * n + j];
            out[i * nn + j] = v;
            out[(i + n) * nn + j + n] = v;
            out[i * nn + j + n] = -v;
            out[(i + n) * nn + j] = -v;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::reference::node_coords;
    use CellType::*;

    fn skin(t: CellType) -> Vec<[f64; 3]> {
        node_coords(t)
            .iter()
            .map(|p| {
                if t.dim() == 1 {
                    [1.0 + 0.5 * p[0], 2.0 + 1.5 * p[0], 0.0]
                } else {
                    [1.0 + p[0], 2.0 + 0.5 * p[1], 0.3 * p[0]]
                }
            })
            .collect()
    }

    fn measure(m: Modelisation, t: CellType) -> f64 {
        skin_load(m, t, &skin(t), None, &|_, _| Ok((1.0, 0.0))).unwrap().0.iter().sum()
    }

    #[test]
    fn a_uniform_flux_loads_the_area() {
        let plan = Modelisation::from_name("PLAN").unwrap();
        let axis = Modelisation::from_name("AXIS").unwrap();
        let solid = Modelisation::from_name("3D").unwrap();
        let l = (0.5f64.powi(2) + 1.5f64.powi(2)).sqrt() * 2.0;
        for t in [Seg2, Seg3] {
            assert!((measure(plan, t) - l).abs() < 1e-12);
            // ∫ r ds along the segment from r = 0.5 to 1.5: mean radius 1.
            assert!((measure(axis, t) - l).abs() < 1e-12);
        }
        for t in [Tria3, Tria6] {
            let a = 0.5 * (1.0f64 + 0.09).sqrt() * 0.5;
            assert!((measure(solid, t) - a).abs() < 1e-12, "{t:?}");
        }
        for t in [Quad4, Quad8, Quad9] {
            let a = 4.0 * (1.0f64 + 0.09).sqrt() * 0.5;
            assert!((measure(solid, t) - a).abs() < 1e-12, "{t:?}");
        }
    }

    #[test]
    fn exchange_is_linear_and_its_tangent_is_minus_h_times_the_boundary_mass() {
        let m = Modelisation::from_name("3D").unwrap();
        let x = skin(Quad8);
        let temps: Vec<f64> = x.iter().map(|p| 10.0 + p[0] - 2.0 * p[1]).collect();
        let (h, text) = (25.0, 100.0);
        let (f, df) = skin_load(m, Quad8, &x, Some(&temps), &|_, t| Ok((h * (text - t), -h))).unwrap();
        let (f0, _) = skin_load(m, Quad8, &x, None, &|_, _| Ok((h * text, 0.0))).unwrap();
        let hm = super::super::element::matvec(&df, &temps);
        for a in 0..8 {
            assert!((f[a] - (f0[a] + hm[a])).abs() < 1e-9 * f0[a].abs());
        }
        // Σ ∂F/∂T = −h × area.
        let area = measure(m, Quad8);
        assert!((df.iter().sum::<f64>() + h * area).abs() < 1e-9 * h * area);
    }

    #[test]
    fn radiation_derivative() {
        let (f, d) = radiation(5.67e-8, 0.8, 500.0, 300.0);
        let h = 1e-3;
        let fd =
            (radiation(5.67e-8, 0.8, 500.0, 300.0 + h).0 - radiation(5.67e-8, 0.8, 500.0, 300.0 - h).0) / (2.0 * h);
        assert!(f > 0.0 && (fd - d).abs() < 1e-8 * d.abs());
    }

    #[test]
    fn the_normal_of_an_oriented_skin_points_out() {
        // The bottom edge of the square (0,1)², run from (0,0) to (1,0): the normal is −y.
        let m = Modelisation::from_name("PLAN").unwrap();
        let pts = skin_points(m, Seg2, &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]).unwrap();
        assert!(pts.iter().all(|p| (p.normal[1] + 1.0).abs() < 1e-14));
        assert_eq!(pts.len(), 4);
    }

    #[test]
    fn walls_exchange_what_one_gains_and_the_other_loses() {
        for (name, t) in [("PLAN", Seg2), ("AXIS", Seg3), ("3D", Tria3), ("3D", Quad4)] {
            let m = Modelisation::from_name(name).unwrap();
            let f1 = skin(t);
            let f2: Vec<[f64; 3]> = f1.iter().map(|p| [p[0] + 1e-3, p[1], p[2]]).collect();
            let k = wall_exchange(m, t, &f1, &f2, &|_| Ok(7.0)).unwrap();
            let n = 2 * t.nnodes();
            // Equal temperatures exchange nothing; a jump of 1 exchanges h × area.
            let eq = super::super::element::matvec(&k, &vec![3.0; n]);
            assert!(eq.iter().all(|v| v.abs() < 1e-10));
            let jump: Vec<f64> = (0..n).map(|i| if i < n / 2 { 0.0 } else { 1.0 }).collect();
            let f = super::super::element::matvec(&k, &jump);
            let into1: f64 = -f[..n / 2].iter().sum::<f64>();
            let area = measure(m, t);
            assert!((into1 - 7.0 * area).abs() < 2e-2 * 7.0 * area, "{name} {t:?}: {into1} vs {}", 7.0 * area);
            assert!((f.iter().sum::<f64>()).abs() < 1e-10);
        }
    }
}
