//! The cohesive law `CZM_LIN_MIX` of the X-FEM mortar interface
//! (Code_Aster `lcecli`), evaluated node by node on the interface.
//!
//! # Variables
//!
//! At an interface node the law sees, in the local basis of the crack
//! (normal component first, then the tangential ones):
//! - `λ`, the cohesive multiplier (the effective cohesive traction at the
//!   solution),
//! - `w`, the displacement jump carried by the interface (positive normal
//!   component = opening).
//!
//! It works on the *augmented* traction `ℓ = λ + r·w`, with the augmentation
//! parameter and the critical opening
//!
//! ```text
//! r  = PENA_LAGR · σc² / Gc            δc = 2 Gc / σc          so  r·δc/σc = 2·PENA_LAGR.
//! ```
//!
//! The equivalent augmented traction mixes the positive part of the normal
//! component with the whole tangential part:
//! `ℓ_eq = sqrt(<ℓ_n>₊² + |ℓ_t|²)`.
//!
//! # The cohesive function D(ℓ)
//!
//! With the secant factor (β = 1/(2·PENA_LAGR − 1))
//!
//! ```text
//! g(s) = σc/s + β (σc/s − 1),          i.e.   g(s)·s = σc − β (s − σc),
//! ```
//!
//! and the threshold `κ = max(σc, κ⁻)` (κ⁻ the largest `ℓ_eq` seen so far,
//! 0 initially), the returned traction is
//!
//! - always the unilateral contact part `D_n = min(0, ℓ_n)`;
//! - *broken* (`ℓ_eq ≥ r δc` or `κ ≥ r δc`): nothing more (frictionless
//!   unilateral contact, the crack transmits no tension nor shear);
//! - *elastic / unloading* (`ℓ_eq ≤ κ`): plus `g(κ)·(<ℓ_n>₊, ℓ_t)`;
//! - *loading* (`ℓ_eq > κ`): plus `g(ℓ_eq)·(<ℓ_n>₊, ℓ_t)`.
//!
//! The internal state becomes `κ⁺ = max(κ⁻, ℓ_eq)` with the flags
//! "dissipating" (loading regime) and state 0 sound / 1 damaged / 2 broken.
//!
//! # Why this is linear softening
//!
//! At a node the λ-equation of the mortar formulation is `D(λ + r w) = λ`.
//! In mode I loading, `λ = σc − β(ℓ − σc)` and `ℓ = λ + r δ` (δ = w_n) give
//! `ℓ = σc + δ (r − σc/δc)` and then `λ = σc (1 − δ/δc)`: the classical
//! linear softening law, reaching zero at δ = δc where `ℓ = r δc` (broken).
//! Below the threshold with κ = σc, `g = 1` so `D(ℓ) = ℓ` and the
//! λ-equation forces `r w = 0`: the interface is rigid until σc is reached
//! (extrinsic law). After damage, `ℓ_eq ≤ κ` gives a secant unloading to the
//! origin with stiffness `λ/δ = σc(1 − δ*/δc)/δ*` (δ* the opening at κ).
//! In compression `D_n = ℓ_n` whatever the state, hence `w_n = 0` exactly
//! and `λ_n` is the contact pressure. The map ℓ ↦ δ is increasing only when
//! `r > σc/δc`, i.e. PENA_LAGR > 1/2 (Code_Aster's catalogue asks ≥ 1.01);
//! at 1/2 the factor β is infinite, below it the law would snap back, so
//! [`CzmParams::new`] refuses PENA_LAGR ≤ 1/2.
//!
//! # Tangent dD/dℓ
//!
//! `+1` on (n,n) when `ℓ_n ≤ 0`; elastic regime: `g(κ)` on the diagonal (the
//! (n,n) entry only when `ℓ_n > 0`); loading regime: `g(ℓ_eq) δ_ij +
//! g'(ℓ_eq)/ℓ_eq · ℓ_i ℓ_j` over the components entering `ℓ_eq`, with
//! `g'(s)/s = −σc (1 + β)/s³`; broken: the contact part and a `−1e-8`
//! regularisation on the diagonal entries that carry no cohesive stiffness
//! (the normal one only in tension), which is not the derivative of D
//! (Code_Aster adds it to keep the matrix regular).
//!
//! In the prediction phase Code_Aster calls the law with `RIGI_MECA_TANG`:
//! only the tangent, with the regime taken from the previous state instead
//! of the current ℓ ([`prediction_tangent`]).

/// Material parameters of `RUPT_FRAG` used by `CZM_LIN_MIX`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CzmParams {
    /// SIGM_C: critical stress σc.
    pub sigma_c: f64,
    /// GC: fracture energy.
    pub gc: f64,
    /// PENA_LAGR: dimensionless augmentation coefficient.
    pub pena_lagr: f64,
}

impl CzmParams {
    /// Checked parameters: σc > 0, Gc > 0, PENA_LAGR > 1/2 (see the module docs).
    pub fn new(sigma_c: f64, gc: f64, pena_lagr: f64) -> Result<Self, String> {
        if !(sigma_c > 0.0 && sigma_c.is_finite()) {
            return Err(format!("SIGM_C must be positive (got {sigma_c})"));
        }
        if !(gc > 0.0 && gc.is_finite()) {
            return Err(format!("GC must be positive (got {gc})"));
        }
        if !(pena_lagr > 0.5 && pena_lagr.is_finite()) {
            return Err(format!(
                "PENA_LAGR must exceed 1/2 for CZM_LIN_MIX (got {pena_lagr}): the softening branch \
                 is not monotone in the augmented traction otherwise"
            ));
        }
        Ok(CzmParams { sigma_c, gc, pena_lagr })
    }

    /// Augmentation parameter r = PENA_LAGR σc² / Gc.
    pub fn r(&self) -> f64 {
        self.pena_lagr * self.sigma_c * self.sigma_c / self.gc
    }

    /// Critical opening δc = 2 Gc / σc.
    pub fn delta_c(&self) -> f64 {
        2.0 * self.gc / self.sigma_c
    }

    /// β = 1 / (r δc/σc − 1) = 1 / (2 PENA_LAGR − 1).
    pub fn beta(&self) -> f64 {
        1.0 / (self.r() * self.delta_c() / self.sigma_c - 1.0)
    }

    /// The secant factor g(s) = σc/s + β (σc/s − 1).
    pub fn g(&self, s: f64) -> f64 {
        let sc = self.sigma_c;
        sc / s + self.beta() * (sc / s - 1.0)
    }

    /// g'(s)/s = −σc (1 + β) / s³ (the coefficient of ℓ_i ℓ_j in the loading tangent).
    pub fn dg_over_s(&self, s: f64) -> f64 {
        -self.sigma_c * (1.0 + self.beta()) / (s * s * s)
    }

    /// Augmented traction at which the interface is broken: r δc.
    pub fn broken_threshold(&self) -> f64 {
        self.r() * self.delta_c()
    }

    /// Effective threshold κ = max(σc, κ⁻).
    pub fn threshold(&self, state: &CzmState) -> f64 {
        self.sigma_c.max(state.kappa)
    }

    /// Opening (norm of the jump) on the softening envelope reached when the
    /// equivalent augmented traction is κ: δ = (κ − σc)/(r − σc/δc), within [0, δc].
    pub fn opening_at_threshold(&self, kappa: f64) -> f64 {
        let d = (kappa - self.sigma_c) / (self.r() - self.sigma_c / self.delta_c());
        d.clamp(0.0, self.delta_c())
    }

    /// The linear softening envelope t(δ) = σc (1 − δ/δc) for δ ≥ 0, zero beyond δc.
    pub fn envelope_traction(&self, delta: f64) -> f64 {
        (self.sigma_c * (1.0 - delta / self.delta_c())).max(0.0)
    }

    /// Energy dissipated per unit area once the threshold is κ: the work
    /// σc δ* − σc δ*²/(2δc) along the envelope minus the recoverable part
    /// ½ t(δ*) δ* of the secant unloading, i.e. ½ σc δ* (δ* the opening at κ);
    /// Gc once broken.
    pub fn dissipated_energy(&self, kappa: f64) -> f64 {
        0.5 * self.sigma_c * self.opening_at_threshold(kappa)
    }
}

/// Internal variables of one interface node.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CzmState {
    /// Largest equivalent augmented traction seen (κ); 0 initially, so that σc is used.
    pub kappa: f64,
    /// 0 sound, 1 damaged, 2 broken.
    pub state: u8,
    /// The last evaluation was in the loading (dissipating) regime.
    pub dissipating: bool,
}

impl CzmState {
    /// The first two ELNO internal variables of the interface block as
    /// Code_Aster stores them (`xhmsa6`): κ, and ±(state + 1) with the sign
    /// of "dissipating" (+ loading, − otherwise).
    pub fn to_vari(&self) -> [f64; 2] {
        let s = f64::from(self.state) + 1.0;
        [self.kappa, if self.dissipating { s } else { -s }]
    }

    /// The inverse of [`CzmState::to_vari`]. A zero second value (the
    /// initial field) decodes as "sound, not dissipating" (Code_Aster reads
    /// state −1 there, which behaves as 0).
    pub fn from_vari(v: [f64; 2]) -> Self {
        let dissipating = v[1] > 0.0;
        let state = (v[1].abs() - 1.0).round().clamp(0.0, 2.0) as u8;
        CzmState { kappa: v[0], state, dissipating }
    }
}

/// The regime the law used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regime {
    /// ℓ_eq ≤ κ: rigid (undamaged) or secant unloading.
    Elastic,
    /// ℓ_eq > κ: damage grows.
    Loading,
    /// Fully broken: unilateral contact only.
    Broken,
}

/// Result of one evaluation of the law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CzmEval {
    /// D(ℓ), local components (unused ones 0).
    pub d: [f64; 3],
    /// dD/dℓ (with the broken-state regularisation).
    pub dd: [[f64; 3]; 3],
    /// Updated internal state.
    pub new_state: CzmState,
    pub regime: Regime,
    /// The augmented traction ℓ = λ + r w.
    pub laug: [f64; 3],
}

const REGUL: f64 = 1e-8;

fn augmented(p: &CzmParams, ndim: usize, lambda: &[f64], w: &[f64]) -> ([f64; 3], f64) {
    assert!(ndim == 2 || ndim == 3, "CZM_LIN_MIX: ndim must be 2 or 3");
    assert!(lambda.len() >= ndim && w.len() >= ndim, "CZM_LIN_MIX: λ and w need {ndim} components");
    let r = p.r();
    let mut l = [0.0; 3];
    for i in 0..ndim {
        l[i] = lambda[i] + r * w[i];
    }
    let tan2: f64 = l[1..ndim].iter().map(|v| v * v).sum();
    let na = (l[0].max(0.0).powi(2) + tan2).sqrt();
    (l, na)
}

/// The tangent of a regime at ℓ (κ the effective threshold).
fn tangent(p: &CzmParams, ndim: usize, l: &[f64; 3], na: f64, kappa: f64, regime: Regime) -> [[f64; 3]; 3] {
    let mut dd = [[0.0; 3]; 3];
    let tension = l[0] > 0.0;
    if !tension {
        dd[0][0] += 1.0;
    }
    match regime {
        Regime::Broken => {
            if tension {
                dd[0][0] -= REGUL;
            }
            for (i, row) in dd.iter_mut().enumerate().take(ndim).skip(1) {
                row[i] -= REGUL;
            }
        }
        Regime::Elastic => {
            let rk = p.g(kappa);
            if tension {
                dd[0][0] += rk;
            }
            for (i, row) in dd.iter_mut().enumerate().take(ndim).skip(1) {
                row[i] += rk;
            }
        }
        Regime::Loading => {
            let coef = p.g(na);
            let coef2 = p.dg_over_s(na);
            let first = if tension { 0 } else { 1 };
            for i in first..ndim {
                for j in first..ndim {
                    dd[i][j] += coef2 * l[i] * l[j];
                }
                dd[i][i] += coef;
            }
        }
    }
    dd
}

/// Evaluate the law (Code_Aster option FULL_MECA): traction D(ℓ), tangent,
/// and the updated internal state, for local λ and w (normal first).
pub fn evaluate(p: &CzmParams, ndim: usize, lambda: &[f64], w: &[f64], prev: &CzmState) -> CzmEval {
    let (l, na) = augmented(p, ndim, lambda, w);
    let kappa = p.threshold(prev);
    let lim = p.broken_threshold();
    let mut d = [0.0; 3];
    d[0] = l[0].min(0.0);
    let (regime, state, dissipating) = if na >= lim || kappa >= lim {
        (Regime::Broken, 2, false)
    } else if na <= kappa {
        (Regime::Elastic, if kappa > p.sigma_c { 1 } else { 0 }, false)
    } else {
        (Regime::Loading, 1, true)
    };
    let factor = match regime {
        Regime::Broken => 0.0,
        Regime::Elastic => p.g(kappa),
        Regime::Loading => p.g(na),
    };
    if regime != Regime::Broken {
        d[0] += factor * l[0].max(0.0);
        for i in 1..ndim {
            d[i] += factor * l[i];
        }
    }
    let new_state = CzmState { kappa: prev.kappa.max(na), state, dissipating };
    let dd = tangent(p, ndim, &l, na, kappa, regime);
    CzmEval { d, dd, new_state, regime, laug: l }
}

/// The prediction tangent (Code_Aster option RIGI_MECA_TANG): dD/dℓ at the
/// current ℓ with the regime of the previous state (broken if its state is
/// 2, loading if it was dissipating, elastic otherwise); no traction, no
/// state update.
pub fn prediction_tangent(p: &CzmParams, ndim: usize, lambda: &[f64], w: &[f64], prev: &CzmState) -> [[f64; 3]; 3] {
    let (l, na) = augmented(p, ndim, lambda, w);
    let kappa = p.threshold(prev);
    let regime = if prev.state == 2 {
        Regime::Broken
    } else if prev.dissipating {
        Regime::Loading
    } else {
        Regime::Elastic
    };
    tangent(p, ndim, &l, na, kappa, regime)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// wtnv149a's RUPT_FRAG.
    fn params(pena: f64) -> CzmParams {
        CzmParams::new(5e5, 9e3, pena).unwrap()
    }

    #[test]
    fn parameters() {
        let p = params(100.0);
        assert!((p.r() - 100.0 * 25e10 / 9e3).abs() < 1e-3);
        assert!((p.delta_c() - 0.036).abs() < 1e-15);
        assert!((p.r() * p.delta_c() / p.sigma_c - 200.0).abs() < 1e-9);
        assert!((params(2.0).r() - 5.0 / 9.0 * 1e8).abs() < 1e-3);
        // g(σc) = 1 and g(r δc) = 0 (the traction vanishes at breakage).
        assert!((p.g(p.sigma_c) - 1.0).abs() < 1e-15);
        assert!(p.g(p.broken_threshold()).abs() < 1e-12);
        assert!(CzmParams::new(5e5, 9e3, 0.5).is_err());
        assert!(CzmParams::new(5e5, 9e3, 0.3).is_err());
        assert!(CzmParams::new(0.0, 9e3, 100.0).is_err());
        assert!(CzmParams::new(5e5, -1.0, 100.0).is_err());
        assert!((p.dissipated_energy(p.broken_threshold()) - p.gc).abs() < 1e-9 * p.gc);
        assert_eq!(p.dissipated_energy(p.sigma_c), 0.0);
    }

    #[test]
    fn vari_roundtrip() {
        for s in [
            CzmState { kappa: 1.0, state: 0, dissipating: false },
            CzmState { kappa: 2.0, state: 1, dissipating: true },
            CzmState { kappa: 3.0, state: 1, dissipating: false },
            CzmState { kappa: 4.0, state: 2, dissipating: false },
        ] {
            assert_eq!(CzmState::from_vari(s.to_vari()), s);
        }
        assert_eq!(CzmState::from_vari([0.0, 0.0]), CzmState::default());
    }

    /// Central differences of D with respect to ℓ (perturbing λ with w = 0),
    /// compared with the analytic tangent; the regime must not change.
    fn fd_check(p: &CzmParams, ndim: usize, l: &[f64], prev: &CzmState, expect: Regime) {
        let w = [0.0; 3];
        let e0 = evaluate(p, ndim, l, &w, prev);
        assert_eq!(e0.regime, expect, "ℓ = {l:?}, prev = {prev:?}");
        let h = 1e-4 * p.sigma_c;
        for j in 0..ndim {
            let mut lp = l.to_vec();
            let mut lm = l.to_vec();
            lp[j] += h;
            lm[j] -= h;
            let ep = evaluate(p, ndim, &lp, &w, prev);
            let em = evaluate(p, ndim, &lm, &w, prev);
            assert_eq!(ep.regime, expect);
            assert_eq!(em.regime, expect);
            for i in 0..ndim {
                let fd = (ep.d[i] - em.d[i]) / (2.0 * h);
                let an = e0.dd[i][j];
                let err = (fd - an).abs() / an.abs().max(fd.abs()).max(1.0);
                assert!(err <= 1e-6, "dD{i}/dℓ{j}: fd {fd} vs {an} (ℓ = {l:?}, {expect:?}, ndim {ndim})");
            }
        }
        for i in ndim..3 {
            assert_eq!(e0.d[i], 0.0);
            assert!(e0.dd[i].iter().all(|v| *v == 0.0));
        }
    }

    #[test]
    fn tangent_matches_finite_differences() {
        for pena in [100.0, 2.0] {
            let p = params(pena);
            let sc = p.sigma_c;
            let lim = p.broken_threshold();
            let sound = CzmState::default();
            let kd = sc + 0.3 * (lim - sc);
            let damaged = CzmState { kappa: kd, state: 1, dissipating: true };
            let broken = CzmState { kappa: 1.01 * lim, state: 2, dissipating: false };
            for ndim in [2, 3] {
                let t3 = |a: f64, b: f64, c: f64| -> Vec<f64> { vec![a, b, c][..ndim].to_vec() };
                // Contact (ℓ_n < 0), sound, shear below the threshold.
                fd_check(&p, ndim, &t3(-2.0 * sc, 0.2 * sc, -0.1 * sc), &sound, Regime::Elastic);
                // Elastic below threshold in tension, sound and damaged (secant).
                fd_check(&p, ndim, &t3(0.5 * sc, 0.3 * sc, 0.2 * sc), &sound, Regime::Elastic);
                fd_check(&p, ndim, &t3(0.6 * kd, -0.4 * kd, 0.3 * kd), &damaged, Regime::Elastic);
                // Contact with damage: only shear carries cohesive stiffness.
                fd_check(&p, ndim, &t3(-0.5 * sc, 0.5 * kd, 0.1 * kd), &damaged, Regime::Elastic);
                // Loading, pure mode I, mixed mode, and shear under compression.
                fd_check(&p, ndim, &t3(1.5 * sc, 0.0, 0.0), &sound, Regime::Loading);
                fd_check(&p, ndim, &t3(0.9 * kd, 0.7 * kd, -0.4 * kd), &damaged, Regime::Loading);
                fd_check(&p, ndim, &t3(1.2 * sc, -0.8 * sc, 0.6 * sc), &sound, Regime::Loading);
                fd_check(&p, ndim, &t3(-3.0 * sc, 1.3 * kd, 0.5 * kd), &damaged, Regime::Loading);
                // Broken: by the current ℓ or by the history, tension and compression.
                fd_check(&p, ndim, &t3(1.5 * lim, 0.2 * lim, 0.1 * lim), &sound, Regime::Broken);
                fd_check(&p, ndim, &t3(0.3 * sc, 0.2 * sc, -0.1 * sc), &broken, Regime::Broken);
                fd_check(&p, ndim, &t3(-0.3 * sc, 0.2 * sc, 0.4 * sc), &broken, Regime::Broken);
            }
        }
    }

    #[test]
    fn regimes_and_states() {
        let p = params(100.0);
        let sc = p.sigma_c;
        let s0 = CzmState::default();
        // Below σc: D = ℓ (rigid), sound.
        let e = evaluate(&p, 2, &[0.4 * sc, 0.3 * sc], &[0.0, 0.0], &s0);
        assert_eq!(e.d[..2], [0.4 * sc, 0.3 * sc]);
        assert_eq!(e.new_state, CzmState { kappa: 0.5 * sc, state: 0, dissipating: false });
        // Loading.
        let e = evaluate(&p, 2, &[2.0 * sc, 0.0], &[0.0, 0.0], &s0);
        assert_eq!(e.new_state, CzmState { kappa: 2.0 * sc, state: 1, dissipating: true });
        // Unloading after damage.
        let e2 = evaluate(&p, 2, &[sc, 0.0], &[0.0, 0.0], &e.new_state);
        assert_eq!(e2.regime, Regime::Elastic);
        assert_eq!(e2.new_state, CzmState { kappa: 2.0 * sc, state: 1, dissipating: false });
        // Broken: only contact remains.
        let e3 =
            evaluate(&p, 2, &[-sc, 0.5 * sc], &[0.0, 0.0], &CzmState { kappa: 1e20, state: 2, dissipating: false });
        assert_eq!(e3.d[..2], [-sc, 0.0]);
        // The prediction tangent follows the previous flags.
        let t = prediction_tangent(&p, 2, &[0.5 * sc, 0.0], &[0.0, 0.0], &e.new_state);
        let l = [0.5 * sc, 0.0, 0.0];
        assert_eq!(t, tangent(&p, 2, &l, 0.5 * sc, 2.0 * sc, Regime::Loading));
    }

    /// Solve the λ-equation of one packet, D(λ + r w) − λ = 0, for λ with w
    /// prescribed (scalar normal mode), by Newton with a bisection safeguard.
    fn solve_lambda(p: &CzmParams, w: f64, guess: f64, prev: &CzmState) -> (f64, CzmEval) {
        let f = |lam: f64| {
            let e = evaluate(p, 2, &[lam, 0.0], &[w, 0.0], prev);
            (e.d[0] - lam, e.dd[0][0] - 1.0, e)
        };
        let tol = 1e-10 * p.sigma_c;
        let mut lam = guess;
        for _ in 0..50 {
            let (res, jac, e) = f(lam);
            if res.abs() <= tol {
                return (lam, e);
            }
            if jac.abs() > 1e-12 {
                lam -= res / jac;
            } else {
                break;
            }
        }
        // Bisection on a bracket: f(−r w − σc) > 0 is not guaranteed, so widen.
        let (mut a, mut b) = (-p.sigma_c, p.sigma_c);
        while f(a).0 < 0.0 {
            a *= 2.0;
        }
        while f(b).0 > 0.0 {
            b *= 2.0;
        }
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if f(m).0 > 0.0 {
                a = m
            } else {
                b = m
            }
        }
        let lam = 0.5 * (a + b);
        (lam, f(lam).2)
    }

    #[test]
    fn one_point_opening_follows_linear_softening() {
        for pena in [100.0, 2.0] {
            let p = params(pena);
            let (sc, dc) = (p.sigma_c, p.delta_c());
            let n = 20_000;
            let wmax = 1.25 * dc;
            let mut state = CzmState::default();
            let mut lam = sc; // at w = 0 the rigid interface carries any λ ≤ σc: start at the threshold
            let mut work = 0.0;
            let (mut w_prev, mut lam_prev) = (0.0, sc);
            for k in 1..=n {
                let w = wmax * k as f64 / n as f64;
                let (l, e) = solve_lambda(&p, w, lam, &state);
                lam = l;
                state = e.new_state;
                let expect = p.envelope_traction(w);
                assert!((lam - expect).abs() <= 1e-8 * sc, "w = {w}: λ = {lam}, envelope {expect}");
                if w < dc * (1.0 - 1e-9) {
                    assert_eq!(e.regime, Regime::Loading, "w = {w}");
                    assert!(state.dissipating && state.state == 1);
                    assert!((p.opening_at_threshold(state.kappa) - w).abs() <= 1e-9 * dc);
                } else if w > dc * (1.0 + 1e-9) {
                    assert_eq!(e.regime, Regime::Broken);
                    assert!(lam.abs() <= 1e-10 * sc);
                    assert_eq!(state.state, 2);
                }
                work += 0.5 * (lam + lam_prev) * (w - w_prev);
                w_prev = w;
                lam_prev = lam;
            }
            assert!((work - p.gc).abs() <= 1e-3 * p.gc, "dissipated {work} vs Gc {}", p.gc);
            assert!((p.dissipated_energy(state.kappa) - p.gc).abs() <= 1e-9 * p.gc);
        }
    }

    #[test]
    fn unloading_is_secant_and_reloading_rejoins_the_envelope() {
        let p = params(100.0);
        let (sc, dc) = (p.sigma_c, p.delta_c());
        let mut state = CzmState::default();
        let mut lam = sc;
        let dstar = 0.4 * dc;
        let path: Vec<f64> = (1..=40)
            .map(|k| dstar * k as f64 / 40.0)
            .chain((0..40).rev().map(|k| dstar * k as f64 / 40.0 + 1e-6 * dc))
            .chain((1..=60).map(|k| 1e-6 * dc + 0.7 * dc * k as f64 / 60.0))
            .collect();
        let secant = p.envelope_traction(dstar) / dstar;
        let mut wmax: f64 = 0.0;
        for w in path {
            let (l, e) = solve_lambda(&p, w, lam, &state);
            lam = l;
            state = e.new_state;
            if w < wmax * (1.0 - 1e-9) {
                assert_eq!(e.regime, Regime::Elastic);
                assert!((lam - secant * w).abs() <= 1e-7 * sc, "w = {w}: λ = {lam}, secant {}", secant * w);
            } else {
                assert!((lam - p.envelope_traction(w)).abs() <= 1e-7 * sc);
            }
            wmax = wmax.max(w);
        }
    }

    /// The packet equations at a node with the total traction μ prescribed
    /// (no fluid pressure, unit lumped weight m): R_w = m (D(λ + r w) − μ),
    /// R_λ = (m/r)(D(λ + r w) − λ), solved by Newton with the element blocks
    /// K_ww = r m D', K_wλ = K_λw = m D', K_λλ = m (D' − I)/r.
    fn solve_packet(p: &CzmParams, ndim: usize, mu: &[f64], prev: &CzmState) -> ([f64; 3], [f64; 3], CzmEval) {
        let (r, m) = (p.r(), 1.0);
        let (mut w, mut lam) = ([0.0; 3], [0.0; 3]);
        for _ in 0..50 {
            let e = evaluate(p, ndim, &lam, &w, prev);
            let n = 2 * ndim;
            let mut a = vec![vec![0.0; n + 1]; n];
            let mut norm: f64 = 0.0;
            for i in 0..ndim {
                let rw = m * (e.d[i] - mu[i]);
                let rl = m / r * (e.d[i] - lam[i]);
                norm = norm.max(rw.abs()).max(rl.abs() * r);
                a[i][n] = -rw;
                a[ndim + i][n] = -rl;
                for j in 0..ndim {
                    let dd = e.dd[i][j];
                    a[i][j] = r * m * dd;
                    a[i][ndim + j] = m * dd;
                    a[ndim + i][j] = m * dd;
                    a[ndim + i][ndim + j] = m * (dd - if i == j { 1.0 } else { 0.0 }) / r;
                }
            }
            if norm <= 1e-9 * p.sigma_c {
                return (w, lam, e);
            }
            let x = DMatrix::from_fn(n, n, |i, j| a[i][j])
                .lu()
                .solve(&DVector::from_fn(n, |i, _| a[i][n]))
                .expect("singular packet system");
            for i in 0..ndim {
                w[i] += x[i];
                lam[i] += x[ndim + i];
            }
        }
        panic!("packet Newton did not converge for μ = {mu:?}");
    }

    #[test]
    fn compression_closes_the_crack_exactly() {
        for pena in [100.0, 2.0] {
            let p = params(pena);
            let sc = p.sigma_c;
            let damaged =
                CzmState { kappa: p.sigma_c + 0.5 * (p.broken_threshold() - sc), state: 1, dissipating: false };
            let broken = CzmState { kappa: 2.0 * p.broken_threshold(), state: 2, dissipating: false };
            for ndim in [2, 3] {
                // Pure compression, any history (−8e4 Pa is the WTNV149 order of magnitude).
                for prev in [CzmState::default(), damaged, broken] {
                    let mu = [-8e4, 0.0, 0.0];
                    let (w, lam, _) = solve_packet(&p, ndim, &mu, &prev);
                    // The first Newton step already lands on w_n = 0 (contact: D_n = ℓ_n,
                    // so the λ-row reads w_n = 0) and stays there.
                    assert_eq!(w[0], 0.0, "w_n must vanish exactly ({prev:?})");
                    assert!((lam[0] - mu[0]).abs() <= 1e-9 * sc);
                }
                // With shear below σc on a sound interface: stick (w = 0), λ = μ.
                let mu = [-8e4, 3e4, -2e4];
                let (w, lam, e) = solve_packet(&p, ndim, &mu, &CzmState::default());
                assert_eq!(w[0], 0.0);
                for i in 0..ndim {
                    assert!(p.r() * w[i].abs() <= 1e-12 * sc, "w = {w:?}");
                    assert!((lam[i] - mu[i]).abs() <= 1e-9 * sc, "λ = {lam:?}");
                }
                assert_eq!(e.new_state.state, 0);
            }
        }
    }
}
