//! One integration point over a time step: `ELAS` + `LIQU_SATU` + `HYDR_UTIL` as Code_Aster updates
//! them (`thmCpl001`, `viporo`, `virhol`, `appmas`, `sigmap`, `thmFlh001` in its sources), and the
//! exact derivatives of the update, which make the element tangent consistent.
//!
//! Strains are engineering (`εxx εyy εzz γxy γxz γyz`), stresses tension positive, the pressure `p` is
//! `PRE1` (compression positive), relative to `THM_INIT PRE1`: only its increments and gradient enter.

use super::material::Biot;

/// What Code_Aster stores at an integration point: the effective stress σ' and the pore stress σ_p
/// (`SIXX..SIYZ`, `SIPXX..SIPYZ` of `SIEF_ELGA`), the fluid mass content `M11` and the mass flux
/// `FH11X..Z`; the porosity φ and liquid density ρ (`VARI_ELGA`: ρ − ρ₀ and φ − φ₀); and the strain
/// and pressure of the point, the start of the next step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    pub sig: [f64; 6],
    pub sigp: [f64; 6],
    pub m: f64,
    pub w: [f64; 3],
    pub phi: f64,
    pub rho: f64,
    pub eps: [f64; 6],
    pub p: f64,
    /// THM: the temperature of the point (TEMP, from THM_INIT TEMP), the liquid's enthalpy `ENT11`, the
    /// non-convected heat `QPRIM` and the heat flux `FHTX..Z` (zero in HM).
    pub temp: f64,
    pub h: f64,
    pub qp: f64,
    pub qt: [f64; 3],
}

impl PointState {
    /// The initial state of a material: no stress, no mass change, no flux, φ₀ and ρ₀.
    pub fn initial(m: &Biot) -> PointState {
        PointState {
            sig: [0.0; 6],
            sigp: [0.0; 6],
            m: 0.0,
            w: [0.0; 3],
            phi: m.phi0,
            rho: m.rho_l,
            eps: [0.0; 6],
            p: 0.0,
            temp: 0.0,
            h: 0.0,
            qp: 0.0,
            qt: [0.0; 3],
        }
    }

    /// The volumetric strain εxx + εyy + εzz.
    pub fn eps_v(&self) -> f64 {
        self.eps[0] + self.eps[1] + self.eps[2]
    }
}

/// The derivatives of the update that the element needs (σ' = D ε is the caller's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives {
    /// ∂σ_p/∂p on the normal components (−b).
    pub dsigp_dp: f64,
    /// ∂M/∂ε_v and ∂M/∂p.
    pub dm_depsv: f64,
    pub dm_dp: f64,
    /// ∂w/∂(∇p) = −ρ K/μ · I.
    pub dw_dgradp: f64,
    /// ∂w/∂p.
    pub dw_dp: [f64; 3],
}

/// Why a point could not be integrated: an exponent beyond Code_Aster's bound (5), which asks the
/// time stepping for a smaller step.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegrationFailure(pub String);

/// Code_Aster refuses the exponential updates beyond this argument (`viporo`, `virhol`).
const EXP_MAX: f64 = 5.0;

/// The state at the end of the step from the start state `prev`, the strain `eps` (engineering), the
/// pressure `p` and its gradient `grad_p` at the end of the step; `d` is the Hooke matrix (engineering
/// shear) of the kinematics, `g` the fluid's gravity.
pub fn update(
    mat: &Biot,
    d: &[[f64; 6]; 6],
    prev: &PointState,
    eps: &[f64; 6],
    p: f64,
    grad_p: &[f64; 3],
    g: &[f64; 3],
) -> Result<(PointState, Derivatives), IntegrationFailure> {
    let b = mat.biot;
    let deps: [f64; 6] = std::array::from_fn(|k| eps[k] - prev.eps[k]);
    let dp = p - prev.p;
    let mut sig = prev.sig;
    for (i, s) in sig.iter_mut().enumerate() {
        *s += (0..6).map(|j| d[i][j] * deps[j]).sum::<f64>();
    }
    let mut sigp = prev.sigp;
    for s in sigp.iter_mut().take(3) {
        *s -= b * dp;
    }
    let eps_v = eps[0] + eps[1] + eps[2];
    let deps_v = eps_v - prev.eps_v();
    let inv_ks = mat.inv_ks();
    let arg_phi = -deps_v - dp * inv_ks;
    let arg_rho = dp * mat.inv_kw;
    if arg_phi.abs() > EXP_MAX || arg_rho.abs() > EXP_MAX || !arg_phi.is_finite() || !arg_rho.is_finite() {
        return Err(IntegrationFailure(format!(
            "the porosity or liquid density update overflows (exponent {:.3e}, {:.3e}, beyond ±{EXP_MAX})",
            arg_phi, arg_rho
        )));
    }
    let phi = b - (b - prev.phi) * arg_phi.exp();
    let rho = prev.rho * arg_rho.exp();
    let m = prev.m + phi * rho * (1.0 + eps_v) - prev.phi * prev.rho * (1.0 + prev.eps_v());
    let kappa = mat.mobility();
    let w: [f64; 3] = std::array::from_fn(|i| rho * kappa * (-grad_p[i] + rho * g[i]));
    let der = derivatives(mat, phi, rho, kappa, grad_p, g);
    Ok((PointState { sig, sigp, m, w, phi, rho, eps: *eps, p, ..*prev }, der))
}

/// The derivatives of the saturated update at the end state (porosity φ, density ρ, mobility κ = K/μ).
pub(crate) fn derivatives(mat: &Biot, phi: f64, rho: f64, kappa: f64, grad_p: &[f64; 3], g: &[f64; 3]) -> Derivatives {
    let b = mat.biot;
    // ∂φ/∂p = (b − φ)/K_s, ∂ρ/∂p = ρ/K_w.
    let dphi_dp = (b - phi) * mat.inv_ks();
    let drho_dp = rho * mat.inv_kw;
    // The mass content's tangent as Code_Aster assembles it (`dmdepv`, `dmwdp1`): ρb and ρ(φ/K_w + c_s),
    // the derivatives of M without the (1 + ε_v) factor and the change of φ with ε_v — a tangent within
    // O(ε_v) of the exact one. The converged state is the same; the prediction, which Code_Aster's mixed
    // criterion often accepts as it is, carries that difference, and so do its non-regression values.
    Derivatives {
        dsigp_dp: -b,
        dm_depsv: rho * b,
        dm_dp: rho * (phi * mat.inv_kw + dphi_dp),
        dw_dgradp: -rho * kappa,
        dw_dp: std::array::from_fn(|i| kappa * drho_dp * (-grad_p[i] + 2.0 * rho * g[i])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::elasticity::{IsoElastic, Modelisation};

    fn setup() -> (Biot, [[f64; 6]; 6], PointState) {
        let m = crate::hm::material::sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let mut s = PointState::initial(&m);
        s.eps = [1e-4, -2e-4, 3e-4, 1e-4, 0.0, -5e-5];
        s.p = 1.0e5;
        s.rho = 1000.2;
        s.phi = 0.31;
        (m, d, s)
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (m, d, prev) = setup();
        let eps = [3e-4, -1e-4, 2e-4, 2e-4, 1e-4, 0.0];
        let (p, gp, g) = (3.0e6, [1.0e4, -2.0e4, 5.0e3], m.gravity);
        let (s, der) = update(&m, &d, &prev, &eps, p, &gp, &g).unwrap();
        // ε_v: the same increment on the three normal strains, a third each.
        let h = 1e-7;
        let mut e2 = eps;
        for e in e2.iter_mut().take(3) {
            *e += h / 3.0;
        }
        let (s2, _) = update(&m, &d, &prev, &e2, p, &gp, &g).unwrap();
        // The mass content's tangent is Code_Aster's (ρb, ρ(φ/K_w + c_s)): exact to O(ε_v).
        let eps_v = eps[0] + eps[1] + eps[2];
        assert_eq!(der.dm_depsv, s.rho * m.biot);
        assert_eq!(der.dm_dp, s.rho * (s.phi * m.inv_kw + (m.biot - s.phi) * m.inv_ks()));
        let fd = (s2.m - s.m) / h;
        assert!((fd - der.dm_depsv).abs() < 2.0 * eps_v.abs() * der.dm_depsv.abs(), "{fd} {}", der.dm_depsv);
        let hp = 10.0;
        let (s3, _) = update(&m, &d, &prev, &eps, p + hp, &gp, &g).unwrap();
        let fd = (s3.m - s.m) / hp;
        assert!((fd - der.dm_dp).abs() < 2.0 * eps_v.abs() * der.dm_dp.abs(), "{fd} {}", der.dm_dp);
        for i in 0..3 {
            let fd = (s3.w[i] - s.w[i]) / hp;
            assert!((fd - der.dw_dp[i]).abs() < 1e-5 * der.dw_dp[i].abs().max(1e-30), "{i}: {fd} {:?}", der.dw_dp);
            assert!((s3.sigp[i] - s.sigp[i]) / hp - der.dsigp_dp < 1e-9);
        }
        let mut gp2 = gp;
        gp2[1] += 1.0;
        let (s4, _) = update(&m, &d, &prev, &eps, p, &gp2, &g).unwrap();
        assert!(((s4.w[1] - s.w[1]) - der.dw_dgradp).abs() < 1e-9 * der.dw_dgradp.abs());
    }

    #[test]
    fn linearised_storage_is_biot() {
        // Small increments from the initial state: ΔM ≈ ρ₀ (b Δε_v + Δp / M).
        let m = crate::hm::material::sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let prev = PointState::initial(&m);
        let (de, dp) = (1e-7, 1.0);
        let (s, _) = update(&m, &d, &prev, &[de, 0.0, 0.0, 0.0, 0.0, 0.0], dp, &[0.0; 3], &[0.0; 3]).unwrap();
        let want = m.rho_l * (m.biot * de + dp * m.inv_biot_modulus());
        assert!((s.m - want).abs() < 1e-6 * want.abs(), "{} {want}", s.m);
        assert_eq!(s.sigp[0], -m.biot * dp);
        assert_eq!(s.sigp[3], 0.0);
    }

    #[test]
    fn darcy_flux_with_gravity() {
        let m = crate::hm::material::sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let prev = PointState::initial(&m);
        let gp = [0.0, -m.rho_l * 9.81, 0.0];
        // Hydrostatic: no flux.
        let (s, _) = update(&m, &d, &prev, &[0.0; 6], 0.0, &gp, &m.gravity).unwrap();
        assert!(s.w.iter().all(|w| w.abs() < 1e-12), "{:?}", s.w);
        let (s, _) = update(&m, &d, &prev, &[0.0; 6], 0.0, &[100.0, 0.0, 0.0], &[0.0; 3]).unwrap();
        assert!((s.w[0] + m.rho_l * m.mobility() * 100.0).abs() < 1e-20);
    }

    #[test]
    fn an_overflowing_exponent_is_an_integration_failure() {
        let m = crate::hm::material::sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let prev = PointState::initial(&m);
        let e = update(&m, &d, &prev, &[0.0; 6], 1.0e11, &[0.0; 3], &[0.0; 3]).unwrap_err();
        assert!(e.0.contains("overflows"), "{}", e.0);
    }
}
