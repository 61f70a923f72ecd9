//! Post-processing of element fields that knows no command: the average of values at the nodes of
//! cells (ELNO) over the cells sharing each node (Code_Aster's `*_NOEU` from `*_ELNO`), and the
//! equivalent stresses of SIEQ_*.

use crate::mesh::Mesh;
use nalgebra::Matrix3;

/// Average ELNO values to nodes over the cells sharing each node.
pub fn to_nodes(mesh: &Mesh, cells: &[Option<Vec<f64>>], ncmp: usize) -> Vec<f64> {
    let mut sum = vec![0.0; mesh.coords.len() * ncmp];
    let mut count = vec![0usize; mesh.coords.len()];
    for (c, v) in cells.iter().enumerate() {
        let Some(v) = v else { continue };
        for (i, &n) in mesh.cells[c].iter().enumerate() {
            count[n] += 1;
            for k in 0..ncmp {
                sum[n * ncmp + k] += v[i * ncmp + k];
            }
        }
    }
    for n in 0..count.len() {
        for k in 0..ncmp {
            sum[n * ncmp + k] = if count[n] > 0 { sum[n * ncmp + k] / count[n] as f64 } else { f64::NAN };
        }
    }
    sum
}

/// The components of SIEQ_* we compute (Code_Aster's SIEQ also has the
/// principal directions VECT_*, not computed yet).
pub const SIEQ_COMPONENTS: [&str; 8] = ["VMIS", "TRESCA", "PRIN_1", "PRIN_2", "PRIN_3", "VMIS_SG", "TRSIG", "TRIAX"];

/// Principal stresses (ascending) of a symmetric tensor given as
/// [xx, yy, zz, xy, (xz, yz)]: nalgebra's symmetric eigenvalues.
pub fn principal(s: &[f64]) -> [f64; 3] {
    let (xz, yz) = if s.len() >= 6 { (s[4], s[5]) } else { (0.0, 0.0) };
    let m = Matrix3::new(s[0], s[3], xz, s[3], s[1], yz, xz, yz, s[2]);
    let mut e: [f64; 3] = m.symmetric_eigenvalues().into();
    e.sort_by(|x, y| x.total_cmp(y));
    e
}

/// SIEQ components of one stress tensor.
pub fn equivalent_stresses(s: &[f64]) -> Vec<f64> {
    let tr = s[0] + s[1] + s[2];
    let m = tr / 3.0;
    let shear: f64 = s.iter().skip(3).map(|v| v * v).sum();
    let j2 = 0.5 * ((s[0] - m).powi(2) + (s[1] - m).powi(2) + (s[2] - m).powi(2)) + shear;
    let vmis = (3.0 * j2).sqrt();
    let pr = principal(s);
    let triax = if vmis > 0.0 { m / vmis } else { 0.0 };
    vec![vmis, pr[2] - pr[0], pr[0], pr[1], pr[2], if tr < 0.0 { -vmis } else { vmis }, tr, triax]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equivalent_stresses_of_known_tensors() {
        // Uniaxial: VMIS = TRESCA = |s|, principal (0, 0, s).
        let e = equivalent_stresses(&[0.0, 0.0, 7.0, 0.0, 0.0, 0.0]);
        assert!((e[0] - 7.0).abs() < 1e-12 && (e[1] - 7.0).abs() < 1e-12);
        assert!(e[2].abs() < 1e-12 && e[3].abs() < 1e-12 && (e[4] - 7.0).abs() < 1e-12);
        // Pure shear xy = t: principal (-t, 0, t), VMIS = sqrt(3) t, TRESCA = 2t.
        let e = equivalent_stresses(&[0.0, 0.0, 0.0, 2.0]);
        assert!((e[0] - 2.0 * 3f64.sqrt()).abs() < 1e-12 && (e[1] - 4.0).abs() < 1e-12);
        assert!((e[2] + 2.0).abs() < 1e-12 && e[3].abs() < 1e-12 && (e[4] - 2.0).abs() < 1e-12);
        // Hydrostatic: VMIS 0, TRSIG = 3p.
        let e = equivalent_stresses(&[-5.0, -5.0, -5.0, 0.0, 0.0, 0.0]);
        assert!(e[0].abs() < 1e-12 && (e[6] + 15.0).abs() < 1e-12);
        // A general tensor: principal values are the eigenvalues (their sum and product).
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 1.1];
        let p = principal(&s);
        assert!((p[0] + p[1] + p[2] - 4.0).abs() < 1e-12);
        let det = s[0] * (s[1] * s[2] - s[5] * s[5]) - s[3] * (s[3] * s[2] - s[5] * s[4])
            + s[4] * (s[3] * s[5] - s[1] * s[4]);
        assert!((p[0] * p[1] * p[2] - det).abs() < 1e-10);
    }
}

/// The elastic energy density `½ σ : S σ` of an isotropic law for the stress components `sig` (`XX YY ZZ
/// XY [XZ YZ]`, absent ones zero).
pub fn elastic_energy(e: f64, nu: f64, sig: &[f64; 6]) -> f64 {
    let tr = sig[0] + sig[1] + sig[2];
    let sq = sig[..3].iter().map(|s| s * s).sum::<f64>() + 2.0 * sig[3..].iter().map(|s| s * s).sum::<f64>();
    ((1.0 + nu) * sq - nu * tr * tr) / (2.0 * e)
}

#[cfg(test)]
mod energy_tests {
    /// Uniaxial σ: σ² / 2E; pure shear τ: τ² / 2G.
    #[test]
    fn elastic_energy_of_uniaxial_stress_and_shear() {
        let (e, nu) = (200.0, 0.25);
        assert!((super::elastic_energy(e, nu, &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0]) - 100.0 / 400.0).abs() < 1e-14);
        let g = e / (2.0 * (1.0 + nu));
        assert!((super::elastic_energy(e, nu, &[0.0, 0.0, 0.0, 3.0, 0.0, 0.0]) - 9.0 / (2.0 * g)).abs() < 1e-14);
    }
}
