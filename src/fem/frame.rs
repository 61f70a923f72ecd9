//! Local frames of anisotropic materials (the orientation AFFE_CARA_ELEM's MASSIF gives a cell): fixed
//! frames from nautical or Euler angles, and cylindrical frames whose axes follow the point.
//!
//! A frame is given by its axes' global components, as rows `[L, T, N]` (in 2D, `L` and `T` in the
//! plane). Nautical angles `(α, β, γ)` turn the global frame about `Z` by α, then about the new `Y` by
//! β, then about the new `X` by γ (the rotation `R_z(α) R_y(β) R_x(γ)`, whose columns are the axes):
//! `L = (cos β cos α, cos β sin α, −sin β)`. Euler angles `(ψ, θ, φ)`
//! (Z-X-Z) are taken as Code_Aster takes them: `L` and `T` the first two columns of the Euler matrix. A
//! cylindrical frame about an axis through `origin`: in 3D `L` along the axis, `N` the radial direction
//! of the point, `T = N × L`; in 2D `L` the radial direction in the plane and `T` its normal.

/// A frame's axes as rows (`L`, `T`, `N`).
pub type Axes = [[f64; 3]; 3];

/// The orientation of a cell's material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frame {
    /// The same axes at every point.
    Fixed(Axes),
    /// Cylindrical axes about the line through `origin` along `axis` (3D), or about the point `origin`
    /// (2D: `axis` None).
    Cylinder { origin: [f64; 3], axis: Option<[f64; 3]> },
}

/// Why a frame has no axes at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct OnAxis {
    pub point: [f64; 3],
}

impl std::fmt::Display for OnAxis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the point ({}, {}, {}) lies on the axis of a cylindrical frame, where its radial direction is undefined",
            self.point[0], self.point[1], self.point[2]
        )
    }
}

use nalgebra::Vector3;

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    Vector3::from(*a).cross(&Vector3::from(*b)).into()
}

impl Frame {
    /// The global frame.
    pub const GLOBAL: Frame = Frame::Fixed([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// A fixed frame from nautical angles in degrees (missing angles are zero; in 2D only α counts).
    pub fn nautical(deg: &[f64]) -> Frame {
        let a = |i: usize| deg.get(i).copied().unwrap_or(0.0).to_radians();
        let (sa, ca) = a(0).sin_cos();
        let (sb, cb) = a(1).sin_cos();
        let (sg, cg) = a(2).sin_cos();
        Frame::Fixed([
            [cb * ca, cb * sa, -sb],
            [sg * sb * ca - cg * sa, cg * ca + sg * sb * sa, sg * cb],
            [sg * sa + cg * sb * ca, cg * sb * sa - ca * sg, cg * cb],
        ])
    }

    /// A fixed frame from Euler angles (ψ, θ, φ) in degrees.
    pub fn euler(deg: &[f64]) -> Frame {
        let a = |i: usize| deg.get(i).copied().unwrap_or(0.0).to_radians();
        let (sp, cp) = a(0).sin_cos();
        let (st, ct) = a(1).sin_cos();
        let (sf, cf) = a(2).sin_cos();
        let l = [cf * cp - sf * ct * sp, cf * sp + sf * ct * cp, sf * st];
        let t = [-sf * cp - cf * ct * sp, -sf * sp + cf * ct * cp, cf * st];
        Frame::Fixed([l, t, cross(&l, &t)])
    }

    /// A cylindrical frame: in 3D about the axis through `origin` of direction given by the nautical
    /// angles (α, β) in degrees; in 2D (`axis_deg` None) about the point `origin`.
    pub fn cylinder(origin: [f64; 3], axis_deg: Option<[f64; 2]>) -> Frame {
        // The axis is the L of the nautical frame of those angles.
        let axis = axis_deg.map(|[a, b]| match Frame::nautical(&[a, b]) {
            Frame::Fixed(ax) => ax[0],
            Frame::Cylinder { .. } => unreachable!("a nautical frame is fixed"),
        });
        Frame::Cylinder { origin, axis }
    }

    /// The axes at the point `x`.
    pub fn axes_at(&self, x: &[f64; 3]) -> Result<Axes, OnAxis> {
        match *self {
            Frame::Fixed(a) => Ok(a),
            Frame::Cylinder { origin, axis } => {
                let d = Vector3::from(*x) - Vector3::from(origin);
                match axis {
                    Some(e) => {
                        let l = Vector3::from(e).normalize();
                        // The radial direction: d less its part along the axis.
                        let r = d - l * d.dot(&l);
                        if r.norm() <= 1e-14 * d.norm().max(1e-300) {
                            return Err(OnAxis { point: *x });
                        }
                        let n = r.normalize();
                        Ok([l.into(), n.cross(&l).into(), n.into()])
                    }
                    None => {
                        let nr = d.x.hypot(d.y);
                        if nr == 0.0 {
                            return Err(OnAxis { point: *x });
                        }
                        let (c, s) = (d.x / nr, d.y / nr);
                        Ok([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
                    }
                }
            }
        }
    }
}

/// The tensor `Σ λᵢ aᵢ aᵢᵀ` of principal values `lambda` along the axes `axes` (rows), on the first `dim`
/// axes and components.
pub fn principal_tensor(lambda: &[f64; 3], axes: &Axes, dim: usize) -> [[f64; 3]; 3] {
    let mut k = [[0.0; 3]; 3];
    for (l, a) in lambda.iter().zip(axes).take(dim) {
        for i in 0..dim {
            for j in 0..dim {
                k[i][j] += l * a[i] * a[j];
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Axes, b: &Axes, tol: f64) -> bool {
        (0..3).all(|i| (0..3).all(|j| (a[i][j] - b[i][j]).abs() < tol))
    }

    fn orthonormal(a: &Axes) -> bool {
        (0..3).all(|i| {
            (0..3).all(|j| {
                let d: f64 = (0..3).map(|k| a[i][k] * a[j][k]).sum();
                (d - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14
            })
        }) && {
            let c = cross(&a[0], &a[1]);
            (0..3).all(|k| (c[k] - a[2][k]).abs() < 1e-14)
        }
    }

    #[test]
    fn nautical_angles_turn_the_global_frame() {
        let Frame::Fixed(a) = Frame::nautical(&[90.0]) else { unreachable!() };
        assert!(close(&a, &[[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], 1e-15));
        let Frame::Fixed(b) = Frame::nautical(&[0.0, 90.0, 0.0]) else { unreachable!() };
        // β turns about Y: L goes down to −Z.
        assert!(close(&b, &[[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]], 1e-15));
        let Frame::Fixed(c) = Frame::nautical(&[30.0, 20.0, 10.0]) else { unreachable!() };
        assert!(orthonormal(&c));
        assert_eq!(Frame::nautical(&[0.0, 0.0, 0.0]), Frame::GLOBAL);
    }

    #[test]
    fn euler_angles_give_the_nautical_frame_of_the_same_axes() {
        // ψ about Z alone is α: (ψ, 0, 0) = nautical (ψ, 0, 0).
        let (Frame::Fixed(e), Frame::Fixed(n)) = (Frame::euler(&[40.0, 0.0, 0.0]), Frame::nautical(&[40.0])) else {
            unreachable!()
        };
        assert!(close(&e, &n, 1e-15));
        let Frame::Fixed(g) = Frame::euler(&[15.0, 35.0, 55.0]) else { unreachable!() };
        assert!(orthonormal(&g));
        // θ about the new X: N leans from Z toward −Y' (ψ = φ = 0): N = (0, −sin θ, cos θ).
        let Frame::Fixed(t) = Frame::euler(&[0.0, 35.0, 0.0]) else { unreachable!() };
        let s = 35f64.to_radians();
        assert!(close(&t, &[[1.0, 0.0, 0.0], [0.0, s.cos(), s.sin()], [0.0, -s.sin(), s.cos()]], 1e-15));
    }

    #[test]
    fn cylindrical_frames_follow_the_point() {
        // 3D, the axis along Z (α = 0, β = −90°): L = Z, N radial, T orthoradial.
        let f = Frame::cylinder([1.0, 1.0, 0.0], Some([0.0, -90.0]));
        let a = f.axes_at(&[1.0, 3.0, 5.0]).unwrap();
        assert!(close(&a, &[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], 1e-15));
        assert!(orthonormal(&a));
        assert!(f.axes_at(&[1.0, 1.0, 2.0]).is_err());
        // 2D: L radial in the plane.
        let g = Frame::cylinder([0.0, 0.0, 0.0], None);
        let b = g.axes_at(&[0.0, 2.0, 0.0]).unwrap();
        assert!(close(&b, &[[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], 1e-15));
    }

    #[test]
    fn principal_tensor_of_rotated_axes() {
        let Frame::Fixed(a) = Frame::nautical(&[30.0]) else { unreachable!() };
        let k = principal_tensor(&[4.0, 1.0, 9.0], &a, 2);
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        assert!((k[0][0] - (4.0 * c * c + s * s)).abs() < 1e-14);
        assert!((k[0][1] - 3.0 * c * s).abs() < 1e-14);
        assert_eq!(k[2][2], 0.0);
    }
}
