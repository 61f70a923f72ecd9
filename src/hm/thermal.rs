//! The thermal part of saturated THM (`KIT_THM` = `ELAS`, `LIQU_SATU`, `HYDR_UTIL` on the `*_THM`,
//! `*_THMD`, `*_THMS` modelisations) at one integration point, as Code_Aster computes it
//! (`thmCpl001`, `calor`, `enteau`, `capaca`, `dileau`, `dilata`, `virhol`, `viporo`, `thmFlh001`,
//! `calcft`, `thmMecaElas`, `thmComputeResidual` in its sources; the HM part is the one of
//! `../shared/docs/hm-coupled-formulation.md`).
//!
//! `TEMP` is measured from `THM_INIT TEMP` (T₀): the absolute temperature of a point is `TEMP + T₀`,
//! which must stay positive. Beyond the saturated HM update of [`super::law`]:
//!
//! - the effective stress loses `3Kα_s ΔT` on its normal components (`ELAS ALPHA`);
//! - the porosity's exponent gains `3α_s ΔT`, the liquid density's loses `3α_l ΔT` (`THM_LIQU ALPHA`);
//! - the Darcy flux is evaluated with the viscosity at the temperature (`VISC`, `D_VISC_TEMP`);
//! - the liquid's enthalpy `h` (`ENT11`) gains `c_l ΔT + (1 − 3α_l T)/ρ Δp`;
//! - the non-convected heat `Q'` (`QPRIM`) gains `3Kα_s T̄ Δε_v − 3α_m T̄ Δp + C ΔT` (T̄ the mid-step
//!   temperature, α_m = (b − φ)α_s + φα_l, C = (ρ_h − φρ) c_s + φρ c_l − 9Kα_s² T);
//! - the heat flux is Fourier's `q = −λ ∇T` (`FHTX..`), λ = `LAMB_T`(T) + `LAMB_CT`.

use super::law::{Derivatives, IntegrationFailure, PointState};
use super::material::Biot;
use std::rc::Rc;

/// A material coefficient of the temperature (absolute, K): a constant or a function.
#[derive(Clone)]
pub enum Coef {
    Const(f64),
    OfTemp(Rc<dyn Fn(f64) -> Result<f64, String>>),
}

impl Coef {
    pub fn at(&self, t: f64) -> Result<f64, String> {
        match self {
            Coef::Const(v) => Ok(*v),
            Coef::OfTemp(f) => f(t),
        }
    }
    /// The constant, when it is one.
    pub fn constant(&self) -> Option<f64> {
        match self {
            Coef::Const(v) => Some(*v),
            Coef::OfTemp(_) => None,
        }
    }
}

impl std::fmt::Debug for Coef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Coef::Const(v) => write!(f, "{v}"),
            Coef::OfTemp(_) => f.write_str("f(TEMP)"),
        }
    }
}

/// The thermal parameters of a saturated THM material.
#[derive(Debug, Clone)]
pub struct ThermalMat {
    /// `THM_INIT TEMP`: the reference temperature T₀ (K), the absolute temperature of TEMP = 0.
    pub t0: f64,
    /// `ELAS ALPHA`: the skeleton's linear thermal expansion α_s.
    pub alpha_s: Coef,
    /// `THM_LIQU ALPHA`: the liquid's linear thermal expansion α_l (its density follows exp(−3α_l ΔT)).
    pub alpha_l: Coef,
    /// `THM_LIQU CP`: the liquid's specific heat c_l (J kg⁻¹ K⁻¹).
    pub cp_l: Coef,
    /// `THM_DIFFU CP`: the solid's specific heat c_s.
    pub cp_s: Coef,
    /// `THM_LIQU VISC`, `D_VISC_TEMP`: the viscosity and its derivative, functions of the temperature.
    pub visc: Coef,
    pub dvisc: Coef,
    /// `THM_DIFFU LAMB_T`, `D_LB_T`, `LAMB_CT`: the conductivity λ(T) + λ_c and the derivative of λ.
    pub lamb_t: Coef,
    pub dlamb_t: Coef,
    pub lamb_ct: Coef,
}

/// The coefficients at one temperature.
#[derive(Debug, Clone, Copy)]
struct At {
    alpha_s: f64,
    alpha_l: f64,
    cp_l: f64,
    cp_s: f64,
    visc: f64,
    dvisc: f64,
    lambda: f64,
    dlambda: f64,
}

impl ThermalMat {
    fn at(&self, t: f64) -> Result<At, String> {
        Ok(At {
            alpha_s: self.alpha_s.at(t)?,
            alpha_l: self.alpha_l.at(t)?,
            cp_l: self.cp_l.at(t)?,
            cp_s: self.cp_s.at(t)?,
            visc: self.visc.at(t)?,
            dvisc: self.dvisc.at(t)?,
            lambda: self.lamb_t.at(t)? + self.lamb_ct.at(t)?,
            dlambda: self.dlamb_t.at(t)?,
        })
    }
}

/// The derivatives of the thermal update beyond the HM ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalDerivatives {
    /// ∂σ'/∂T on the normal components: −3Kα_s.
    pub dsig_dt: f64,
    /// ∂M/∂T = −3ρα_m.
    pub dm_dt: f64,
    /// ∂w/∂T (density and viscosity).
    pub dw_dt: [f64; 3],
    /// ∂h/∂p, ∂h/∂T.
    pub dh_dp: f64,
    pub dh_dt: f64,
    /// ∂Q'/∂ε on the normal components (3Kα_s T), ∂Q'/∂p (−3α_m T), ∂Q'/∂T (C).
    pub dq_deps: f64,
    pub dq_dp: f64,
    pub dq_dt: f64,
    /// ∂q/∂(∇T) = −λ · I, ∂q/∂T = −λ' ∇T.
    pub dqt_dgradt: f64,
    pub dqt_dt: [f64; 3],
}

/// Code_Aster refuses the exponential updates beyond this argument (`viporo`, `virhol`).
const EXP_MAX: f64 = 5.0;

/// The THM state at the end of the step: the HM quantities of [`super::law::update`] with the thermal
/// terms, the enthalpy, the non-convected heat and the heat flux; `t` and `grad_t` the temperature
/// (from T₀) and its gradient, `axis` the axisymmetric kinematics (Code_Aster's `calor` weighs the hoop
/// strain of its `Q'` increment by √2 there: reproduced).
#[allow(clippy::too_many_arguments)]
pub fn update(
    mat: &Biot,
    th: &ThermalMat,
    d: &[[f64; 6]; 6],
    prev: &PointState,
    eps: &[f64; 6],
    p: f64,
    grad_p: &[f64; 3],
    t: f64,
    grad_t: &[f64; 3],
    g: &[f64; 3],
    axis: bool,
) -> Result<(PointState, Derivatives, ThermalDerivatives), IntegrationFailure> {
    let tabs = t + th.t0;
    if tabs <= 0.0 || !tabs.is_finite() {
        return Err(IntegrationFailure(format!(
            "the absolute temperature {tabs:e} K (TEMP {t:e} + THM_INIT TEMP {}) is not positive",
            th.t0
        )));
    }
    let c = th.at(tabs).map_err(IntegrationFailure)?;
    let b = mat.biot;
    let k0 = mat.k0();
    let deps: [f64; 6] = std::array::from_fn(|k| eps[k] - prev.eps[k]);
    let dp = p - prev.p;
    let dtemp = t - prev.temp;
    // 3Kα_s: the thermal stress per kelvin on each normal component (Code_Aster's D·α with the 3D Hooke
    // matrix whatever the kinematics), and its product with α_s on the three.
    let mdal = 3.0 * k0 * c.alpha_s;
    let dalal = 3.0 * mdal * c.alpha_s;
    let mut sig = prev.sig;
    for (i, s) in sig.iter_mut().enumerate() {
        *s += (0..6).map(|j| d[i][j] * deps[j]).sum::<f64>();
        if i < 3 {
            *s -= mdal * dtemp;
        }
    }
    let mut sigp = prev.sigp;
    for s in sigp.iter_mut().take(3) {
        *s -= b * dp;
    }
    let eps_v = eps[0] + eps[1] + eps[2];
    let deps_v = eps_v - prev.eps_v();
    let inv_ks = mat.inv_ks();
    let arg_phi = -deps_v + 3.0 * c.alpha_s * dtemp - dp * inv_ks;
    let arg_rho = dp * mat.inv_kw - 3.0 * c.alpha_l * dtemp;
    if arg_phi > EXP_MAX || arg_rho > EXP_MAX || !arg_phi.is_finite() || !arg_rho.is_finite() {
        return Err(IntegrationFailure(format!(
            "the porosity or liquid density update overflows (exponent {arg_phi:.3e}, {arg_rho:.3e}, beyond {EXP_MAX})"
        )));
    }
    let phi = b - (b - prev.phi) * arg_phi.exp();
    let rho = prev.rho * arg_rho.exp();
    let m = prev.m + phi * rho * (1.0 + eps_v) - prev.phi * prev.rho * (1.0 + prev.eps_v());
    let kappa = mat.perm / c.visc;
    let w: [f64; 3] = std::array::from_fn(|i| rho * kappa * (-grad_p[i] + rho * g[i]));
    // The expansions of the pore volume: α_φ = (b − φ)α_s, α_m = α_φ + φα_l (dilata, dileau).
    let alp11 = (b - phi) * c.alpha_s + c.alpha_l * phi;
    // The heat capacity per unit volume (capaca): the solid's mass ρ_h − φρ must stay positive.
    let solid = mat.rho_h - rho * phi;
    let coeps = solid * c.cp_s + phi * rho * c.cp_l - tabs * dalal;
    if solid <= 0.0 || coeps <= 0.0 {
        return Err(IntegrationFailure(format!(
            "the heat capacity is not positive (solid mass ρ_h − φρ = {solid:e}, capacity {coeps:e})"
        )));
    }
    let h = prev.h + c.cp_l * dtemp + (1.0 - 3.0 * c.alpha_l * tabs) / rho * dp;
    let tmid = tabs - dtemp / 2.0;
    let hoop = if axis { std::f64::consts::SQRT_2 } else { 1.0 };
    let work = mdal * (deps[0] + deps[1] + hoop * deps[2]) * tmid;
    let qp = prev.qp + work - 3.0 * alp11 * tmid * dp + coeps * dtemp;
    let qt: [f64; 3] = std::array::from_fn(|i| -c.lambda * grad_t[i]);
    let der = super::law::derivatives(mat, phi, rho, kappa, grad_p, g);
    // ∂w/∂T: the density (−3α_l ρ) in both factors ρ, and the viscosity (−μ'/μ²).
    let drho_dt = -3.0 * c.alpha_l * rho;
    let dkappa_dt = -mat.perm * c.dvisc / (c.visc * c.visc);
    let tder = ThermalDerivatives {
        dsig_dt: -mdal,
        dm_dt: -3.0 * rho * alp11,
        dw_dt: std::array::from_fn(|i| {
            let drive = -grad_p[i] + rho * g[i];
            drho_dt * kappa * drive + rho * dkappa_dt * drive + rho * kappa * drho_dt * g[i]
        }),
        dh_dp: (1.0 - 3.0 * c.alpha_l * tabs) / rho,
        dh_dt: c.cp_l,
        dq_deps: mdal * tabs,
        dq_dp: -3.0 * alp11 * tabs,
        dq_dt: coeps,
        dqt_dgradt: -c.lambda,
        dqt_dt: std::array::from_fn(|i| -c.dlambda * grad_t[i]),
    };
    let state = PointState { sig, sigp, m, w, phi, rho, eps: *eps, p, temp: t, h, qp, qt };
    Ok((state, der, tder))
}

#[cfg(test)]
pub(crate) fn sample() -> ThermalMat {
    ThermalMat {
        t0: 293.0,
        alpha_s: Coef::Const(1e-5),
        alpha_l: Coef::Const(1e-4),
        cp_l: Coef::Const(4180.0),
        cp_s: Coef::Const(800.0),
        // A viscosity falling with the temperature, D_VISC_TEMP its derivative.
        visc: Coef::OfTemp(Rc::new(|t| Ok(1e-3 - 2e-6 * (t - 293.0)))),
        dvisc: Coef::Const(-2e-6),
        lamb_t: Coef::OfTemp(Rc::new(|t| Ok(1.8 + 0.01 * (t - 293.0)))),
        dlamb_t: Coef::Const(0.01),
        lamb_ct: Coef::Const(0.2),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::elasticity::{IsoElastic, Modelisation};

    /// At a constant temperature the update is the saturated HM one.
    #[test]
    fn without_temperature_change_the_update_is_hm() {
        let m = crate::hm::material::sample();
        let th = sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let mut prev = PointState::initial(&m);
        // At the reference temperature, where the viscosity is the HM material's.
        prev.temp = 0.0;
        let eps = [3e-4, -1e-4, 2e-4, 2e-4, 1e-4, 0.0];
        let (gp, g) = ([1.0e4, -2.0e4, 5.0e3], m.gravity);
        let (s, der, _) = update(&m, &th, &d, &prev, &eps, 3.0e6, &gp, 0.0, &[0.0; 3], &g, false).unwrap();
        let (h, hder) = crate::hm::law::update(&m, &d, &prev, &eps, 3.0e6, &gp, &g).unwrap();
        assert_eq!((s.sig, s.sigp, s.phi, s.rho, s.m), (h.sig, h.sigp, h.phi, h.rho, h.m));
        assert_eq!(der, hder);
        for i in 0..3 {
            assert!((s.w[i] - h.w[i]).abs() <= 1e-15 * h.w[i].abs());
        }
    }

    /// The thermal derivatives against finite differences (the mass content's as Code_Aster's: exact
    /// to O(ε_v)).
    #[test]
    fn thermal_derivatives_match_finite_differences() {
        let m = crate::hm::material::sample();
        let th = sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let mut prev = PointState::initial(&m);
        prev.temp = 11.9; // ΔT = 0.1: Q' is a mid-step quantity
        let eps = [1e-7, -2e-7, 1e-7, 0.0, 0.0, 0.0];
        let (p, gp, gt, g) = (2.0e5, [1.0e4, -2.0e4, 5.0e3], [3.0, -1.0, 2.0], m.gravity);
        let t = 12.0;
        let run = |eps: &[f64; 6], p: f64, t: f64, gt: &[f64; 3]| {
            update(&m, &th, &d, &prev, eps, p, &gp, t, gt, &g, false).unwrap()
        };
        let (s, _, td) = run(&eps, p, t, &gt);
        let ht = 1e-4;
        let (s2, _, _) = run(&eps, p, t + ht, &gt);
        let (s1, _, _) = run(&eps, p, t - ht, &gt);
        let fd = |a: f64, b: f64| (a - b) / (2.0 * ht);
        assert!((fd(s2.sig[0], s1.sig[0]) - td.dsig_dt).abs() < 1e-6 * td.dsig_dt.abs());
        assert!((fd(s2.m, s1.m) - td.dm_dt).abs() < 1e-5 * td.dm_dt.abs(), "{} {}", fd(s2.m, s1.m), td.dm_dt);
        for i in 0..3 {
            assert!((fd(s2.w[i], s1.w[i]) - td.dw_dt[i]).abs() < 1e-6 * td.dw_dt[i].abs());
            assert!((fd(s2.qt[i], s1.qt[i]) - td.dqt_dt[i]).abs() < 1e-9, "{i}");
        }
        assert!((fd(s2.h, s1.h) - td.dh_dt).abs() < 1e-3 * td.dh_dt);
        // Q' is a mid-step quantity: its derivative in T is C to O(ΔT α).
        assert!((fd(s2.qp, s1.qp) - td.dq_dt).abs() < 1e-3 * td.dq_dt, "{} {}", fd(s2.qp, s1.qp), td.dq_dt);
        let hp = 10.0;
        let (sp, _, _) = run(&eps, p + hp, t, &gt);
        let (sm, _, _) = run(&eps, p - hp, t, &gt);
        let fdp = |a: f64, b: f64| (a - b) / (2.0 * hp);
        // Code_Aster's ∂h/∂p leaves out the density's change over the step: Δp/K_w = 1e-4 relative here.
        assert!((fdp(sp.h, sm.h) - td.dh_dp).abs() < 2e-4 * td.dh_dp.abs());
        // ∂Q'/∂p is Code_Aster's −3α_m T: it leaves out the capacity's change with the pressure over the
        // step, ΔT (c_l − c_s) ∂(φρ)/∂p.
        let left_out = 0.1 * (4180.0 - 800.0) * (s.rho * (m.biot - s.phi) * m.inv_ks() + s.phi * s.rho * m.inv_kw);
        let err = (fdp(sp.qp, sm.qp) - td.dq_dp).abs();
        assert!(err < 1.1 * left_out + 1e-3 * td.dq_dp.abs(), "{} {} {left_out}", fdp(sp.qp, sm.qp), td.dq_dp);
        let mut gt2 = gt;
        gt2[1] += 1.0;
        let (s3, _, _) = run(&eps, p, t, &gt2);
        assert!(((s3.qt[1] - s.qt[1]) - td.dqt_dgradt).abs() < 1e-12);
    }

    #[test]
    fn a_uniform_heating_expands_the_skeleton_and_the_liquid() {
        let m = crate::hm::material::sample();
        let th = sample();
        let d = IsoElastic::new(m.e, m.nu).hooke(Modelisation::ThreeD);
        let prev = PointState::initial(&m);
        let dt = 10.0;
        // A free expansion ε = α_s ΔT in every direction: no effective stress.
        let e = 1e-5 * dt;
        let (s, _, _) =
            update(&m, &th, &d, &prev, &[e, e, e, 0.0, 0.0, 0.0], 0.0, &[0.0; 3], dt, &[0.0; 3], &[0.0; 3], false)
                .unwrap();
        assert!(s.sig.iter().all(|x| x.abs() < 1e-6), "{:?}", s.sig);
        assert!((s.rho - m.rho_l * (-3e-4 * dt).exp()).abs() < 1e-9);
        assert!((s.h - 4180.0 * dt).abs() < 1e-9);
        let e = update(&m, &th, &d, &prev, &[0.0; 6], 0.0, &[0.0; 3], -400.0, &[0.0; 3], &[0.0; 3], false);
        assert!(e.unwrap_err().0.contains("not positive"));
    }
}
