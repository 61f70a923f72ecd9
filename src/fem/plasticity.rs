//! Small-strain von Mises plasticity with isotropic hardening, as Code_Aster's `VMIS_ISOT_LINE` and
//! `VMIS_ISOT_TRAC` compute it (`nmisot`, `rcfonc`, `rctrac`): the radial return of one integration point
//! over a step, its internal variables — V1 the cumulated plastic strain `p`, V2 the plastic indicator
//! (1 when the step yielded, 0 otherwise) — and the tangent of the two options the Newton loop asks for:
//! the prediction's (`RIGI_MECA_TANG`: the start state's tangent, elastoplastic where the last step
//! yielded) and the corrections' (`FULL_MECA`: the tangent consistent with the return).
//!
//! The hardening is `R(p)`: linear, `R = SY + H p` with `H = E E_T / (E − E_T)` from ECRO_LINE's
//! `D_SIGM_EPSI = E_T`, or piecewise linear in `p` from a traction curve `σ(ε)` (TRACTION), whose first
//! point gives the yield stress and the Young modulus `E = σ₁ / ε₁` the law uses, the other points turned
//! into `p = ε − σ / E`; beyond its last point the curve's PROL_DROITE says what `R` does.
//!
//! Plane stress (C_PLAN) finds the out-of-plane strain with the return: the plastic increment solves the
//! scalar equation where `σ_zz` stays zero, and the tangent is the 3D one condensed on `σ_zz = 0`.
//!
//! Tensors here are Code_Aster's: `XX YY ZZ XY XZ YZ`, tensorial shear strains (`EPXY = γ / 2`); the
//! tangent acts on engineering shear strains (`γ`), as the element's `B` matrices give them. Internally
//! the return works on Mandel components (shear × √2), where the Euclidean norm is the tensor's.

use std::f64::consts::SQRT_2;

/// What a traction curve's hardening does beyond its last point (its function's PROL_DROITE).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// EXCLU: an error.
    Error,
    /// CONSTANT: R stays at its last value.
    Constant,
    /// LINEAIRE: the last segment's slope goes on.
    Linear,
}

/// One traction curve `σ(ε)` of a nappe, at its temperature, with its PROL_DROITE.
#[derive(Debug, Clone, PartialEq)]
pub struct TractionCurve {
    pub temp: f64,
    pub eps: Vec<f64>,
    pub sig: Vec<f64>,
    pub beyond: Beyond,
}

/// The isotropic hardening `R(p)`.
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// `R = sy + h p` (VMIS_ISOT_LINE).
    Linear { sy: f64, h: f64 },
    /// `R` piecewise linear through `(p[k], r[k])`, `p[0] = 0`, `r[0]` the yield stress (VMIS_ISOT_TRAC).
    Curve { p: Vec<f64>, r: Vec<f64>, beyond: Beyond },
}

impl Hardening {
    /// ECRO_LINE: the yield stress `sy` and the slope `d_sigm_epsi` of the uniaxial curve past it, with the
    /// Young modulus `e`; an error when the slope is not below `e`.
    pub fn linear(e: f64, d_sigm_epsi: f64, sy: f64) -> Result<Hardening, String> {
        if e - d_sigm_epsi < f64::MIN_POSITIVE {
            return Err(format!(
                "ECRO_LINE: D_SIGM_EPSI = {d_sigm_epsi} must be smaller than the Young modulus E = {e}"
            ));
        }
        Ok(Hardening::Linear { sy, h: d_sigm_epsi * e / (e - d_sigm_epsi) })
    }

    /// TRACTION: the points `(ε, σ)` of the curve; the hardening and the Young modulus of its first point.
    pub fn traction(eps: &[f64], sig: &[f64], beyond: Beyond) -> Result<(Hardening, f64), String> {
        if eps.len() != sig.len() || eps.len() < 2 {
            return Err("TRACTION: the curve SIGM needs at least two points".into());
        }
        if !(eps[0] > 0.0 && sig[0] > 0.0) {
            return Err(format!(
                "TRACTION: the first point of SIGM (ε = {}, σ = {}) must be the elastic limit, both positive",
                eps[0], sig[0]
            ));
        }
        let e = sig[0] / eps[0];
        let mut p: Vec<f64> = eps.iter().zip(sig).map(|(x, s)| x - s / e).collect();
        p[0] = 0.0;
        if let Some(k) = p.windows(2).position(|w| w[1] <= w[0]) {
            return Err(format!(
                "TRACTION: the curve SIGM must rise slower than its first slope E = {e}: the plastic strain \
                 ε − σ/E does not increase between its points {} and {}",
                k + 1,
                k + 2
            ));
        }
        Ok((Hardening::Curve { p, r: sig.to_vec(), beyond }, e))
    }

    /// TRACTION given as a nappe of the temperature: the curve at `temp`, as Code_Aster's `rctrac` builds
    /// it. At (within 1e-6 relative) a curve's temperature, that curve; between two curves, the Young
    /// modulus interpolated linearly between theirs and the hardening on the union of their plastic
    /// abscissas, `R` interpolated between the two curves' values there (each curve continued past its last
    /// point as its PROL_DROITE says; one that ends with 'EXCLU' ends the merged curve); below the first
    /// or above the last temperature, the nappe's PROL_GAUCHE / PROL_DROITE: the end curve (CONSTANT),
    /// the two end curves extrapolated (LINEAIRE) or an error (EXCLU).
    pub fn traction_at(
        curves: &[TractionCurve],
        below: Beyond,
        above: Beyond,
        temp: f64,
    ) -> Result<(Hardening, f64), String> {
        let n = curves.len();
        if n == 0 {
            return Err("TRACTION: the nappe SIGM holds no curve".into());
        }
        enum At {
            Curve(usize),
            Between(usize),
        }
        let outside = |side: Beyond, end: usize, pair: usize, what: &str, prol: &str| -> Result<At, String> {
            match side {
                Beyond::Constant => Ok(At::Curve(end)),
                Beyond::Linear if n > 1 => Ok(At::Between(pair)),
                _ => Err(format!(
                    "TRACTION: the temperature {temp} lies {what} the temperatures of the nappe SIGM ({} to {}) \
                     and its {prol} is 'EXCLU'",
                    curves[0].temp,
                    curves[n - 1].temp
                )),
            }
        };
        let at = if temp < curves[0].temp {
            outside(below, 0, 0, "below", "PROL_GAUCHE")?
        } else if temp > curves[n - 1].temp {
            outside(above, n - 1, n.saturating_sub(2), "above", "PROL_DROITE")?
        } else {
            let near = |t: f64| (t - temp).abs() <= 1e-6 * t.abs();
            let mut at = At::Curve(0);
            for j in 0..n - 1 {
                let (t1, t2) = (curves[j].temp, curves[j + 1].temp);
                if near(t1) {
                    at = At::Curve(j);
                    break;
                }
                if near(t2) {
                    at = At::Curve(j + 1);
                    break;
                }
                if t1 < temp && temp < t2 {
                    at = At::Between(j);
                    break;
                }
            }
            at
        };
        let i = match at {
            At::Curve(k) => return Hardening::traction(&curves[k].eps, &curves[k].sig, curves[k].beyond),
            At::Between(i) => i,
        };
        let (c1, c2) = (&curves[i], &curves[i + 1]);
        let (h1, e1) = Hardening::traction(&c1.eps, &c1.sig, c1.beyond)?;
        let (h2, e2) = Hardening::traction(&c2.eps, &c2.sig, c2.beyond)?;
        let coef = (temp - c1.temp) / (c2.temp - c1.temp);
        let e = e1 + coef * (e2 - e1);
        let (Hardening::Curve { p: p1, r: r1, .. }, Hardening::Curve { p: p2, r: r2, .. }) = (&h1, &h2) else {
            unreachable!("a traction curve's hardening is a curve")
        };
        // R of a curve at `z` past its last point, as its PROL_DROITE continues it (None: it ends there).
        let past = |p: &[f64], r: &[f64], beyond: Beyond, z: f64| -> Option<f64> {
            let m = p.len();
            match beyond {
                Beyond::Error => None,
                Beyond::Constant => Some(r[m - 1]),
                Beyond::Linear => Some(r[m - 1] + (r[m - 1] - r[m - 2]) / (p[m - 1] - p[m - 2]) * (z - p[m - 1])),
            }
        };
        // R of a curve at `z` within it (the segment holding it).
        let within = |p: &[f64], r: &[f64], z: f64| -> f64 {
            let (s, _) = Hardening::segment(p, z);
            r[s] + (r[s + 1] - r[s]) / (p[s + 1] - p[s]) * (z - p[s])
        };
        let mut p = vec![0.0];
        let mut r = vec![r1[0] + coef * (r2[0] - r1[0])];
        let (mut k1, mut k2) = (1, 1);
        while k1 < p1.len() || k2 < p2.len() {
            let (z, v1, v2);
            if k1 >= p1.len() {
                z = p2[k2];
                let Some(x) = past(p1, r1, c1.beyond, z) else { break };
                (v1, v2) = (x, r2[k2]);
                k2 += 1;
            } else if k2 >= p2.len() {
                z = p1[k1];
                let Some(x) = past(p2, r2, c2.beyond, z) else { break };
                (v1, v2) = (r1[k1], x);
                k1 += 1;
            } else if (p2[k2] - p1[k1]).abs() <= 1e-6 * p1[k1] {
                z = p1[k1];
                (v1, v2) = (r1[k1], r2[k2]);
                k1 += 1;
                k2 += 1;
            } else if p2[k2] > p1[k1] {
                z = p1[k1];
                (v1, v2) = (r1[k1], within(p2, r2, z));
                k1 += 1;
            } else {
                z = p2[k2];
                (v1, v2) = (within(p1, r1, z), r2[k2]);
                k2 += 1;
            }
            p.push(z);
            r.push(v1 + coef * (v2 - v1));
        }
        if p.len() < 2 {
            return Err(format!("TRACTION: the curve SIGM at the temperature {temp} has a single point"));
        }
        let beyond = match (c1.beyond, c2.beyond) {
            (Beyond::Error, _) | (_, Beyond::Error) => Beyond::Error,
            (Beyond::Linear, _) | (_, Beyond::Linear) => Beyond::Linear,
            _ => Beyond::Constant,
        };
        Ok((Hardening::Curve { p, r, beyond }, e))
    }

    /// The area under `R` from 0 to `p`: the plastic work per unit volume of a uniaxial path (`rcfonc`'s
    /// AIRERP), past the last point of a curve along its continuation.
    pub fn area(&self, at: f64) -> Result<f64, String> {
        match self {
            Hardening::Linear { sy, h } => Ok(sy * at + 0.5 * h * at * at),
            Hardening::Curve { p, .. } => {
                let mut sum = 0.0;
                let mut x0 = 0.0;
                let mut r0 = self.at(0.0)?.0;
                for &x in p.iter().skip(1).filter(|&&x| x < at) {
                    let r = self.at(x)?.0;
                    sum += 0.5 * (r0 + r) * (x - x0);
                    (x0, r0) = (x, r);
                }
                Ok(sum + 0.5 * (r0 + self.at(at)?.0) * (at - x0))
            }
        }
    }

    /// The yield stress `R(0)`.
    pub fn yield_stress(&self) -> f64 {
        match self {
            Hardening::Linear { sy, .. } => *sy,
            Hardening::Curve { r, .. } => r[0],
        }
    }

    /// The segment of the curve holding `p` (`p < p[k+1]`, the last one beyond), and whether `p` lies
    /// beyond the curve.
    fn segment(p: &[f64], at: f64) -> (usize, bool) {
        match (1..p.len()).find(|&i| at < p[i]) {
            Some(i) => (i - 1, false),
            None => (p.len() - 2, true),
        }
    }

    /// `R(p)` and its slope `R'(p)` (the slope of the segment holding `p`).
    pub fn at(&self, at: f64) -> Result<(f64, f64), String> {
        match self {
            Hardening::Linear { sy, h } => Ok((sy + h * at, *h)),
            Hardening::Curve { p, r, beyond } => {
                let (i, past) = Hardening::segment(p, at);
                let slope =
                    if past { self.beyond_slope(*beyond, p, r)? } else { (r[i + 1] - r[i]) / (p[i + 1] - p[i]) };
                let (p0, r0) = if past { (p[i + 1], r[i + 1]) } else { (p[i], r[i]) };
                Ok((r0 + slope * (at - p0), slope))
            }
        }
    }

    fn beyond_slope(&self, beyond: Beyond, p: &[f64], r: &[f64]) -> Result<f64, String> {
        let n = p.len();
        match beyond {
            Beyond::Error => Err(format!(
                "the cumulated plastic strain goes beyond the last point of the traction curve (p = {}), whose \
                 PROL_DROITE is 'EXCLU'",
                p[n - 1]
            )),
            Beyond::Constant => Ok(0.0),
            Beyond::Linear => Ok((r[n - 1] - r[n - 2]) / (p[n - 1] - p[n - 2])),
        }
    }

    /// The radial return from `p` for an elastic trial equivalent stress `seq` beyond `R(p)`, with
    /// `three_mu = 3μ`: the increment `Δp` solving `seq − 3μ Δp = R(p + Δp)`, with `R` and `R'` there.
    pub fn radial_return(&self, at: f64, seq: f64, three_mu: f64) -> Result<(f64, f64, f64), String> {
        match self {
            Hardening::Linear { sy, h } => {
                let dp = (seq - sy - h * at) / (h + three_mu);
                Ok((dp, sy + h * (at + dp), *h))
            }
            Hardening::Curve { p, r, beyond } => {
                // The segment where the return lands: the first point past `at` whose R + 3μ (p_k − p) exceeds seq.
                let (start, _) = Hardening::segment(p, at);
                let landed = (start + 1..p.len()).find(|&k| r[k] + three_mu * (p[k] - at) - seq > 0.0);
                let (p0, r0, slope) = match landed {
                    Some(k) => (p[k - 1], r[k - 1], (r[k] - r[k - 1]) / (p[k] - p[k - 1])),
                    None => {
                        let n = p.len();
                        (p[n - 1], r[n - 1], self.beyond_slope(*beyond, p, r)?)
                    }
                };
                let dp = (seq - r0 - slope * (at - p0)) / (three_mu + slope);
                Ok((dp, r0 + slope * (at + dp - p0), slope))
            }
        }
    }
}

/// The plane of the computation, which decides the components and the treatment of `zz`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// 3D: six components.
    Solid,
    /// D_PLAN and AXIS: `XX YY ZZ XY`, the strain `ZZ` given by the element.
    Plane,
    /// C_PLAN: `XX YY ZZ XY`, the strain `ZZ` found by the law so that `σ_zz = 0`.
    PlaneStress,
}

impl Kind {
    /// The number of components.
    pub fn ncomp(self) -> usize {
        if self == Kind::Solid {
            6
        } else {
            4
        }
    }
}

/// The state of one integration point: the total strain (tensorial shear), the stress, `p` and the
/// plastic indicator.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointState {
    pub eps: [f64; 6],
    pub sig: [f64; 6],
    pub p: f64,
    pub plastic: bool,
}

/// What the Newton loop asks of a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Request {
    /// RIGI_MECA_TANG: the start state's tangent; the state does not change.
    Prediction,
    /// FULL_MECA: the return and its consistent tangent.
    Full,
}

/// A material point's law: isotropic elasticity and, unless `hardening` is None, von Mises plasticity.
#[derive(Debug, Clone, PartialEq)]
pub struct VonMises {
    pub e: f64,
    pub nu: f64,
    pub hardening: Option<Hardening>,
    /// The controls of an iterative return (C_PLAN): COMPORTEMENT's RESI_INTE (relative to the yield
    /// stress) and ITER_INTE_MAXI.
    pub resi_inte: f64,
    pub iter_inte: usize,
}

impl VonMises {
    /// The law with Code_Aster's default controls (RESI_INTE 1e-6, ITER_INTE_MAXI 20).
    pub fn new(e: f64, nu: f64, hardening: Option<Hardening>) -> VonMises {
        VonMises { e, nu, hardening, resi_inte: 1e-6, iter_inte: 20 }
    }
}

/// What a step's change of temperature does to a point: the law at the step's start (its moduli rescale
/// the start stress) and the increment of the thermal strain `α⁺ (T⁺ − T_ref) − α⁻ (T⁻ − T_ref)`.
#[derive(Debug, Clone)]
pub struct ThermalStep {
    pub minus: VonMises,
    pub deps_th: f64,
}

/// Tensorial (`EPXY`) to Mandel (`√2 EPXY`) components, and back.
fn to_mandel(v: &[f64; 6]) -> [f64; 6] {
    [v[0], v[1], v[2], v[3] * SQRT_2, v[4] * SQRT_2, v[5] * SQRT_2]
}

fn from_mandel(v: &[f64; 6]) -> [f64; 6] {
    [v[0], v[1], v[2], v[3] / SQRT_2, v[4] / SQRT_2, v[5] / SQRT_2]
}

/// The deviator of Mandel components and their mean.
fn deviator(v: &[f64; 6]) -> ([f64; 6], f64) {
    let m = (v[0] + v[1] + v[2]) / 3.0;
    let mut d = *v;
    for x in d.iter_mut().take(3) {
        *x -= m;
    }
    (d, m)
}

fn equivalent(dev: &[f64; 6], n: usize) -> f64 {
    (1.5 * dev[..n].iter().map(|x| x * x).sum::<f64>()).sqrt()
}

impl VonMises {
    /// One step of the point: from the state `old`, the total strain `eps` at the step's end (tensorial
    /// shear; under C_PLAN its `ZZ` is not read). The new state and the tangent (engineering shear, the
    /// first `kind.ncomp()` rows and columns; under C_PLAN the `ZZ` row and column are zero). Under
    /// [`Request::Prediction`] the state is `old` and the tangent is the start state's.
    pub fn integrate(
        &self,
        kind: Kind,
        old: &PointState,
        eps: &[f64; 6],
        request: Request,
    ) -> Result<(PointState, [[f64; 6]; 6]), String> {
        self.integrate_with(kind, old, eps, request, false)
    }

    /// [`VonMises::integrate`], the tangent replaced by the elastic matrix when `elastic_matrix` (NEWTON
    /// MATRICE or PREDICTION 'ELASTIQUE': Code_Aster's `*_ELAS` options).
    pub fn integrate_with(
        &self,
        kind: Kind,
        old: &PointState,
        eps: &[f64; 6],
        option: Request,
        elastic_matrix: bool,
    ) -> Result<(PointState, [[f64; 6]; 6]), String> {
        self.integrate_thermal(kind, old, eps, option, elastic_matrix, None)
    }

    /// [`VonMises::integrate_with`] over a step where the temperature changes (`self` is the law at the
    /// step's end, `thermal` says what it was at its start and the thermal strain's increment), as
    /// `nmisot` does: the start stress rescaled by the ratios of the shear and bulk moduli (end over
    /// start), the isotropic thermal increment taken off the strain's. Under [`Request::Prediction`] the
    /// returned stress is the start one's elastic response to the thermal increment alone (the forces
    /// the prediction balances); the tangent is the start state's.
    pub fn integrate_thermal(
        &self,
        kind: Kind,
        old: &PointState,
        eps: &[f64; 6],
        option: Request,
        elastic_matrix: bool,
        thermal: Option<&ThermalStep>,
    ) -> Result<(PointState, [[f64; 6]; 6]), String> {
        let n = kind.ncomp();
        let (e, nu) = (self.e, self.nu);
        let two_mu = e / (1.0 + nu);
        let three_k = e / (1.0 - 2.0 * nu);
        let three_mu = 1.5 * two_mu;
        let coef = thermal.map_or(0.0, |t| t.deps_th);
        let mut deps = [0.0; 6];
        for k in 0..n {
            deps[k] = eps[k] - old.eps[k];
        }
        if option == Request::Prediction && thermal.is_some() {
            // The prediction's forces: the thermal increment alone.
            deps = [0.0; 6];
        }
        if kind == Kind::PlaneStress {
            deps[2] = -nu / (1.0 - nu) * (deps[0] + deps[1]) + (1.0 + nu) / (1.0 - nu) * coef;
        }
        for d in deps.iter_mut().take(3) {
            *d -= coef;
        }
        let deps = to_mandel(&deps);
        let (mut depsdv, mut depsmo) = deviator(&deps);
        let (mut sigmdv, mut sigmmo) = deviator(&to_mandel(&old.sig));
        if let Some(t) = thermal {
            // The start stress seen by the end's moduli.
            let (two_mu_m, three_k_m) = (t.minus.e / (1.0 + t.minus.nu), t.minus.e / (1.0 - 2.0 * t.minus.nu));
            sigmdv.iter_mut().for_each(|x| *x *= two_mu / two_mu_m);
            sigmmo *= three_k / three_k_m;
        }
        let mut sigel = [0.0; 6];
        for k in 0..n {
            sigel[k] = sigmdv[k] + two_mu * depsdv[k];
        }
        // The hardening at the start state.
        let (r_old, slope_old) = match &self.hardening {
            Some(h) => h.at(old.p)?,
            None => (f64::INFINITY, 0.0),
        };
        let mut state = *old;
        let (mut sigdv, mut rp, mut slope, mut dp, plastic, sigeps);
        match option {
            Request::Prediction => {
                sigdv = sigmdv;
                rp = equivalent(&sigmdv, n);
                slope = slope_old;
                dp = 0.0;
                plastic = old.plastic && self.hardening.is_some();
                sigeps = 1.0;
                if thermal.is_some() {
                    let mut sig = [0.0; 6];
                    for k in 0..n {
                        sig[k] = sigmdv[k] + two_mu * depsdv[k] + if k < 3 { sigmmo + three_k * depsmo } else { 0.0 };
                    }
                    state.sig = from_mandel(&sig);
                }
            }
            Request::Full => {
                let mut seq = equivalent(&sigel, n);
                if r_old.is_finite() && (seq - r_old).abs() <= f64::EPSILON * r_old {
                    seq = r_old;
                }
                rp = r_old;
                slope = slope_old;
                dp = 0.0;
                plastic = seq - r_old > 0.0;
                if plastic {
                    let h = self.hardening.as_ref().expect("a finite yield stress has a hardening");
                    if kind == Kind::PlaneStress {
                        let (x, r, s) =
                            plane_stress_return(h, e, nu, old.p, seq, &sigel, self.resi_inte, self.iter_inte)?;
                        dp = x;
                        rp = r;
                        slope = s;
                        let dx = 3.0 * (1.0 - 2.0 * nu) * sigel[2] * dp / (e * dp + 2.0 * (1.0 - nu) * rp);
                        depsmo += dx / 3.0;
                        depsdv[0] -= dx / 3.0;
                        depsdv[1] -= dx / 3.0;
                        depsdv[2] += dx * 2.0 / 3.0;
                    } else {
                        let (x, r, s) = h.radial_return(old.p, seq, three_mu)?;
                        dp = x;
                        rp = r;
                        slope = s;
                    }
                }
                let mut sig = [0.0; 6];
                sigdv = [0.0; 6];
                // The radial factor (1 without a plastic increment: also for a law without yield, R = ∞).
                let radial = if dp == 0.0 { 1.0 } else { rp / (rp + three_mu * dp) };
                for k in 0..n {
                    sigdv[k] = (sigmdv[k] + two_mu * depsdv[k]) * radial;
                    sig[k] = sigdv[k] + if k < 3 { sigmmo + three_k * depsmo } else { 0.0 };
                }
                let mut total = [0.0; 6];
                total[..n].copy_from_slice(&eps[..n]);
                if kind == Kind::PlaneStress {
                    // εzz of the law: the elastic estimate with the plastic correction.
                    total[2] = old.eps[2] + depsmo + depsdv[2] + coef;
                }
                state = PointState { eps: total, sig: from_mandel(&sig), p: old.p + dp, plastic };
                sigeps = (0..n).map(|k| sigdv[k] * depsdv[k]).sum::<f64>();
            }
        }
        // The tangent, on Mandel components.
        let mut d = [[0.0; 6]; 6];
        let mut a = 1.0;
        if plastic && sigeps >= 0.0 && !elastic_matrix {
            if rp <= 1e-15 {
                return Err("the equivalent stress of a plastic point vanishes: no tangent".into());
            }
            a = 1.0 + three_mu * dp / rp;
            let coef = -three_mu * three_mu / (three_mu + slope) / (rp * rp) * (1.0 - dp * slope / rp) / a;
            for k in 0..n {
                for l in 0..n {
                    d[k][l] = coef * sigdv[k] * sigdv[l];
                }
            }
        }
        for row in d.iter_mut().take(3) {
            for x in row.iter_mut().take(3) {
                *x += three_k / 3.0 - two_mu / (3.0 * a);
            }
        }
        for (k, row) in d.iter_mut().enumerate().take(n) {
            row[k] += two_mu / a;
        }
        if kind == Kind::PlaneStress {
            let d33 = d[2][2];
            let col: Vec<f64> = (0..n).map(|k| d[k][2]).collect();
            let row: Vec<f64> = (0..n).map(|l| d[2][l]).collect();
            for k in (0..n).filter(|&k| k != 2) {
                for l in (0..n).filter(|&l| l != 2) {
                    d[k][l] -= col[k] * row[l] / d33;
                }
            }
            for row in d.iter_mut().take(n) {
                row[2] = 0.0;
            }
            d[2] = [0.0; 6];
        }
        // Mandel to engineering shear: σ_xy = σ₄/√2 and ε₄ = γ/√2.
        for (k, row) in d.iter_mut().enumerate().take(n) {
            for (l, x) in row.iter_mut().enumerate().take(n) {
                if k >= 3 {
                    *x /= SQRT_2;
                }
                if l >= 3 {
                    *x /= SQRT_2;
                }
            }
        }
        Ok((state, d))
    }
}

/// The plane-stress return: `Δp` where the equivalent stress of the trial deviator corrected by the
/// out-of-plane strain `dx(Δp)` that keeps `σ_zz = 0` meets `R(p + Δp) + 3μ Δp`; with `R` and `R'` there.
/// Solved as Code_Aster does (`zerofr`, 'DEKKER'): secants from 0 and the 3D estimate, bracketed once the
/// root is enclosed (a bisection when a secant leaves the bracket), until the residual is below
/// `resi · SY`, in at most `iter_max` evaluations.
#[allow(clippy::too_many_arguments)]
fn plane_stress_return(
    h: &Hardening,
    e: f64,
    nu: f64,
    p: f64,
    seq: f64,
    sigel: &[f64; 6],
    resi: f64,
    iter_max: usize,
) -> Result<(f64, f64, f64), String> {
    let two_mu = e / (1.0 + nu);
    let g = |dp: f64| -> Result<f64, String> {
        let (r, _) = h.at(p + dp)?;
        let dx = 3.0 * (1.0 - 2.0 * nu) * sigel[2] * dp / (e * dp + 2.0 * (1.0 - nu) * r);
        let s = (sigel[0] - two_mu / 3.0 * dx).powi(2)
            + (sigel[1] - two_mu / 3.0 * dx).powi(2)
            + (sigel[2] + two_mu * 2.0 / 3.0 * dx).powi(2)
            + sigel[3].powi(2);
        Ok(1.5 * two_mu * dp - (1.5 * s).sqrt() + r)
    };
    let tol = resi.abs() * h.yield_stress();
    let fail =
        || format!("the plane-stress plastic return does not converge in ITER_INTE_MAXI = {iter_max} iterations");
    // The first guess: the return of the trial state as if ε_zz were free of it.
    let guess = h.radial_return(p, seq, 1.5 * two_mu)?.0;
    let (mut x, mut fx) = (0.0, g(0.0)?);
    if fx.abs() < tol {
        return Ok((0.0, h.at(p)?.0, h.at(p)?.1));
    }
    let (mut y, mut fy) = (guess, g(guess)?);
    let mut n = 1;
    let root = 'search: loop {
        if fy > 0.0 {
            // Enclosed in [x, y]: secants kept inside the bracket (a bisection where one leaves it).
            let (mut lo, mut hi) = (x, y);
            loop {
                if fx == fy {
                    return Err(fail());
                }
                let mut z = y - (y - x) * fy / (fy - fx);
                if (z - lo) * (z - hi) > 0.0 {
                    z = 0.5 * (lo + hi);
                }
                n += 1;
                let fz = g(z)?;
                if fz.abs() < tol {
                    break 'search z;
                }
                if n > iter_max {
                    return Err(fail());
                }
                if fz < 0.0 {
                    lo = z;
                } else {
                    hi = z;
                }
                (x, fx, y, fy) = (y, fy, z, fz);
            }
        } else {
            if fy < fx || fx == fy {
                return Err(fail());
            }
            let z = y - (y - x) * fy / (fy - fx);
            n += 1;
            (x, fx) = (y, fy);
            y = z;
            fy = g(z)?;
            if fy.abs() < tol {
                break z;
            }
            if n > iter_max {
                return Err(fail());
            }
        }
    };
    let (r, s) = h.at(p + root)?;
    Ok((root, r, s))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(h: f64) -> VonMises {
        let e = 200_000.0;
        VonMises::new(e, 0.3, Some(Hardening::linear(e, h, 200.0).unwrap()))
    }

    /// A uniaxial stress path in 3D, driven by the strains of uniaxial stress: σ = SY + E_T (ε − SY/E).
    #[test]
    fn uniaxial_stress_follows_the_bilinear_curve() {
        let (e, et, sy) = (200_000.0, 10_000.0, 200.0);
        let l = law(et);
        let mut st = PointState::default();
        // Uniaxial stress: find the lateral strain by Newton on σ_yy = σ_zz = 0 with the tangent.
        for step in 1..=20 {
            let exx = step as f64 * 2e-4;
            let mut eps = [exx, st.eps[1], st.eps[2], 0.0, 0.0, 0.0];
            let mut new = st;
            for _ in 0..30 {
                let (s, d) = l.integrate(Kind::Solid, &st, &eps, Request::Full).unwrap();
                new = s;
                let r = [s.sig[1], s.sig[2]];
                if r[0].abs().max(r[1].abs()) < 1e-9 {
                    break;
                }
                let (a, b, c, dd) = (d[1][1], d[1][2], d[2][1], d[2][2]);
                let det = a * dd - b * c;
                eps[1] -= (dd * r[0] - b * r[1]) / det;
                eps[2] -= (-c * r[0] + a * r[1]) / det;
            }
            st = new;
            let want = if exx <= sy / e { e * exx } else { sy + et * (exx - sy / e) };
            assert!((st.sig[0] - want).abs() < 1e-8 * want, "ε = {exx}: σ = {} ≠ {want}", st.sig[0]);
            let p_want = if exx <= sy / e { 0.0 } else { (want - sy) / (e * et / (e - et)) };
            assert!((st.p - p_want).abs() < 1e-12, "p = {} ≠ {p_want}", st.p);
            assert_eq!(st.plastic, exx > sy / e);
        }
    }

    /// Simple shear: τ = SY/√3 + μ_T-like hardening: in pure shear σ_eq = √3 τ, p = γ_p/√3, and
    /// τ = (R(p))/√3 with γ = τ/μ + γ_p.
    #[test]
    fn simple_shear_follows_the_closed_form() {
        let (e, nu, et, sy) = (200_000.0, 0.3, 10_000.0, 200.0);
        let l = law(et);
        let mu = e / (2.0 * (1.0 + nu));
        let h = e * et / (e - et);
        let mut st = PointState::default();
        for step in 1..=10 {
            let gamma = step as f64 * 5e-4;
            let (s, _) = l.integrate(Kind::Solid, &st, &[0.0, 0.0, 0.0, gamma / 2.0, 0.0, 0.0], Request::Full).unwrap();
            st = s;
            // τ = μ (γ − √3 p) and √3 τ = SY + H p when plastic.
            let tau_el = mu * gamma;
            let (tau, p) = if 3f64.sqrt() * tau_el <= sy {
                (tau_el, 0.0)
            } else {
                let p = (3f64.sqrt() * mu * gamma - sy) / (3.0 * mu + h);
                ((sy + h * p) / 3f64.sqrt(), p)
            };
            assert!((st.sig[3] - tau).abs() < 1e-9 * tau, "γ = {gamma}: τ = {} ≠ {tau}", st.sig[3]);
            assert!((st.p - p).abs() < 1e-14, "p = {} ≠ {p}", st.p);
            assert!(st.sig[0].abs() < 1e-9 && st.sig[2].abs() < 1e-9);
        }
    }

    /// The FULL_MECA tangent is the derivative of the stress in the total strain (engineering shear),
    /// in 3D, plane strain and plane stress (in-plane strains, σzz = 0 kept by the law), on linear
    /// hardening and on a traction curve.
    #[test]
    fn consistent_tangent_matches_finite_differences() {
        let (hc, e) = Hardening::traction(&[1e-3, 3e-3, 1e-2], &[200.0, 260.0, 300.0], Beyond::Linear).unwrap();
        let laws = [law(10_000.0), VonMises::new(e, 0.25, Some(hc))];
        for l in &laws {
            // The plane-stress return solved to round-off, so that differences see its derivative.
            let l = &VonMises { resi_inte: 1e-14, iter_inte: 200, ..l.clone() };
            for kind in [Kind::Solid, Kind::Plane, Kind::PlaneStress] {
                let n = kind.ncomp();
                let szz = if kind == Kind::PlaneStress { 0.0 } else { 10.0 };
                let old = PointState {
                    eps: [1e-3, -3e-4, -2e-4, 1e-4, 0.0, 0.0],
                    sig: [150.0, -20.0, szz, 40.0, 0.0, 0.0],
                    p: 2e-4,
                    plastic: true,
                };
                let eps =
                    [2.6e-3, -9e-4, -5e-4, 6e-4, if n == 6 { 3e-4 } else { 0.0 }, if n == 6 { -2e-4 } else { 0.0 }];
                let (s0, d) = l.integrate(kind, &old, &eps, Request::Full).unwrap();
                assert!(s0.plastic && s0.p > old.p);
                for j in (0..n).filter(|&j| kind != Kind::PlaneStress || j != 2) {
                    let h = 1e-9;
                    let (mut ep, mut em) = (eps, eps);
                    // Engineering shear: γ = 2 ε.
                    let dj = if j >= 3 { h / 2.0 } else { h };
                    ep[j] += dj;
                    em[j] -= dj;
                    let (sp, _) = l.integrate(kind, &old, &ep, Request::Full).unwrap();
                    let (sm, _) = l.integrate(kind, &old, &em, Request::Full).unwrap();
                    for i in 0..n {
                        let fd = (sp.sig[i] - sm.sig[i]) / (2.0 * h);
                        let scale = d[0][0].abs();
                        assert!(
                            (fd - d[i][j]).abs() < 1e-6 * scale,
                            "{kind:?} D[{i}][{j}] = {} vs finite differences {fd}",
                            d[i][j]
                        );
                    }
                }
            }
        }
    }

    /// Plane stress: a uniaxial path keeps σ_zz = 0 and follows the bilinear curve; the condensed
    /// prediction tangent of an elastic point is the plane-stress Hooke matrix.
    #[test]
    fn plane_stress_uniaxial_path() {
        let (e, et, sy, nu) = (200_000.0, 10_000.0, 200.0, 0.3);
        // Solved to round-off (Code_Aster's default RESI_INTE stops at 1e-6 SY).
        let l = VonMises { resi_inte: 1e-14, iter_inte: 200, ..law(et) };
        let (_, d) = l.integrate(Kind::PlaneStress, &PointState::default(), &[0.0; 6], Request::Prediction).unwrap();
        let c = e / (1.0 - nu * nu);
        assert!((d[0][0] - c).abs() < 1e-9 * c && (d[0][1] - c * nu).abs() < 1e-9 * c);
        assert!((d[3][3] - e / (2.0 * (1.0 + nu))).abs() < 1e-9 * c);
        let mut st = PointState::default();
        for step in 1..=10 {
            let exx = step as f64 * 4e-4;
            let mut eps = [exx, st.eps[1], 0.0, 0.0, 0.0, 0.0];
            let mut new = st;
            for _ in 0..50 {
                let (s, d) = l.integrate(Kind::PlaneStress, &st, &eps, Request::Full).unwrap();
                new = s;
                if s.sig[1].abs() < 1e-9 {
                    break;
                }
                eps[1] -= s.sig[1] / d[1][1];
            }
            st = new;
            let want = if exx <= sy / e { e * exx } else { sy + et * (exx - sy / e) };
            assert!((st.sig[0] - want).abs() < 1e-8 * want, "ε = {exx}: σ = {} ≠ {want}", st.sig[0]);
            assert!(st.sig[2].abs() < 1e-9 * want, "σzz = {}", st.sig[2]);
            // Plastic incompressibility and elastic Poisson effect: ε_zz = −ν σ/E − p/2.
            let ezz = -nu * st.sig[0] / e - st.p / 2.0;
            assert!((st.eps[2] - ezz).abs() < 1e-10, "εzz = {} ≠ {ezz}", st.eps[2]);
        }
    }

    /// A traction curve: the yield stress and E of its first point, R piecewise linear in p = ε − σ/E,
    /// extended as PROL_DROITE says.
    #[test]
    fn traction_curve_hardening() {
        let (h, e) = Hardening::traction(&[1e-3, 2e-3, 4e-3], &[200.0, 250.0, 280.0], Beyond::Constant).unwrap();
        assert_eq!(e, 200_000.0);
        assert_eq!(h.yield_stress(), 200.0);
        // p of the points: 0, 2e-3 − 250/2e5 = 7.5e-4, 4e-3 − 1.4e-3 = 2.6e-3.
        let (r, s) = h.at(7.5e-4 / 2.0).unwrap();
        assert!((r - 225.0).abs() < 1e-9 && (s - 50.0 / 7.5e-4).abs() < 1e-6);
        assert_eq!(h.at(1.0).unwrap(), (280.0, 0.0));
        // The return lands on the segment the closed form says: seq − 3μ Δp = R(p + Δp).
        let three_mu = 3.0 * e / 2.6;
        let (dp, r, _) = h.radial_return(0.0, 400.0, three_mu).unwrap();
        assert!((400.0 - three_mu * dp - r).abs() < 1e-9 && (r - h.at(dp).unwrap().0).abs() < 1e-9);
        let (ex, _) = Hardening::traction(&[1e-3, 2e-3], &[200.0, 250.0], Beyond::Error).unwrap();
        assert!(ex.at(1.0).unwrap_err().contains("EXCLU"));
        assert!(Hardening::linear(100.0, 100.0, 1.0).is_err());
    }

    /// A nappe of two curves (hsnv100's): at a curve's temperature that curve; between, E interpolated and
    /// R on the union of the plastic abscissas, each curve's R there interpolated in temperature.
    #[test]
    fn traction_nappe_interpolated_in_temperature() {
        let c = |temp: f64, eps: &[f64], sig: &[f64]| TractionCurve {
            temp,
            eps: eps.to_vec(),
            sig: sig.to_vec(),
            beyond: Beyond::Linear,
        };
        let curves = [c(0.0, &[2e-3, 4e-3], &[400.0, 500.0]), c(50.0, &[1e-3, 3e-3], &[200.0, 300.0])];
        let (h0, e0) = Hardening::traction_at(&curves, Beyond::Linear, Beyond::Linear, 0.0).unwrap();
        assert_eq!((h0.clone(), e0), Hardening::traction(&[2e-3, 4e-3], &[400.0, 500.0], Beyond::Linear).unwrap());
        // Both curves have E = 2e5; their plastic abscissas: 0, 1.5e-3 (first) and 0, 1.5e-3 (second).
        let (h, e) = Hardening::traction_at(&curves, Beyond::Linear, Beyond::Linear, 25.0).unwrap();
        assert_eq!(e, 200_000.0);
        let Hardening::Curve { p, r, beyond } = &h else { panic!("a curve") };
        assert_eq!((p.len(), *beyond), (2, Beyond::Linear));
        assert!((p[1] - 1.5e-3).abs() < 1e-15 && (r[0] - 300.0).abs() < 1e-12 && (r[1] - 400.0).abs() < 1e-12);
        // Past the last temperature, LINEAIRE extrapolates the two end curves: R(0) = 400 − 2·(400 − 200).
        let (hx, _) = Hardening::traction_at(&curves, Beyond::Linear, Beyond::Linear, 100.0).unwrap();
        assert!((hx.yield_stress() - 0.0).abs() < 1e-9);
        assert!(Hardening::traction_at(&curves, Beyond::Linear, Beyond::Error, 60.0).unwrap_err().contains("EXCLU"));
        // Abscissas that differ: the union, each curve's R interpolated on the other's points.
        let curves = [c(0.0, &[1e-3, 3e-3], &[200.0, 300.0]), c(10.0, &[1e-3, 2e-3, 5e-3], &[200.0, 250.0, 310.0])];
        let (h, _) = Hardening::traction_at(&curves, Beyond::Constant, Beyond::Constant, 5.0).unwrap();
        let Hardening::Curve { p, r, .. } = &h else { panic!("a curve") };
        // p: 0; 2e-3 − 250/2e5 = 7.5e-4; 3e-3 − 1.5e-3 = 1.5e-3; 5e-3 − 1.55e-3 = 3.45e-3.
        let want_p = [0.0, 7.5e-4, 1.5e-3, 3.45e-3];
        assert!(p.iter().zip(want_p).all(|(a, b)| (a - b).abs() < 1e-15), "{p:?}");
        // At 7.5e-4 the first curve gives 200 + 100·0.5 = 250: R = 250; at 1.5e-3 the second gives
        // 250 + 60·(0.75e-3/2.7e-3): R = (300 + that) / 2; at 3.45e-3 the first, LINEAIRE, continues its slope.
        assert!((r[1] - 250.0).abs() < 1e-9);
        assert!((r[2] - 0.5 * (300.0 + 250.0 + 60.0 * 0.75 / 2.7)).abs() < 1e-9);
        assert!((r[3] - 0.5 * (300.0 + 100.0 / 1.5e-3 * 1.95e-3 + 310.0)).abs() < 1e-9);
    }

    /// A point held at zero strain and heated by ΔT: σ = −3K α ΔT / 3 · I (3D); the start stress seen by
    /// the end's moduli (a stress from a softer start law doubled when E doubles), unchanged strain.
    #[test]
    fn thermal_step_strains_and_rescales() {
        let (e, nu, alpha, dt) = (200_000.0, 0.3, 1e-5, 50.0);
        let l = VonMises::new(e, nu, None);
        let step = ThermalStep { minus: l.clone(), deps_th: alpha * dt };
        let (st, _) = l
            .integrate_thermal(Kind::Solid, &PointState::default(), &[0.0; 6], Request::Full, false, Some(&step))
            .unwrap();
        let want = -e / (1.0 - 2.0 * nu) * alpha * dt;
        assert!(
            st.sig[..3].iter().all(|s| (s - want).abs() < 1e-9) && st.sig[3..].iter().all(|s| *s == 0.0),
            "{:?}",
            st.sig
        );
        // The prediction's stress is the same elastic response, the state's strain unchanged.
        let (pr, _) = l
            .integrate_thermal(Kind::Solid, &PointState::default(), &[1.0; 6], Request::Prediction, false, Some(&step))
            .unwrap();
        assert!((pr.sig[0] - want).abs() < 1e-9 && pr.eps == [0.0; 6]);
        // Plane stress, free in zz: the in-plane stresses −E α ΔT / (1 − ν), εzz = (1 + ν)/(1 − ν) α ΔT.
        let (ps, _) = l
            .integrate_thermal(Kind::PlaneStress, &PointState::default(), &[0.0; 6], Request::Full, false, Some(&step))
            .unwrap();
        assert!((ps.sig[0] + e * alpha * dt / (1.0 - nu)).abs() < 1e-9 && ps.sig[2].abs() < 1e-9);
        assert!((ps.eps[2] - (1.0 + nu) / (1.0 - nu) * alpha * dt).abs() < 1e-15);
        // Rescaling: a stress reached under E/2 is doubled under E at no strain change.
        let soft = VonMises::new(e / 2.0, nu, None);
        let old = PointState { sig: [10.0, -4.0, 3.0, 2.0, 0.0, 1.0], ..PointState::default() };
        let (st, _) = l
            .integrate_thermal(
                Kind::Solid,
                &old,
                &[0.0; 6],
                Request::Full,
                false,
                Some(&ThermalStep { minus: soft, deps_th: 0.0 }),
            )
            .unwrap();
        assert!(st.sig.iter().zip(old.sig).all(|(a, b)| (a - 2.0 * b).abs() < 1e-12), "{:?}", st.sig);
    }

    /// Unloading after yield is elastic: V2 back to 0, p kept; the prediction tangent of a point that
    /// yielded in its last step is the elastoplastic one.
    #[test]
    fn unloading_is_elastic_and_the_prediction_remembers_yield() {
        let l = law(10_000.0);
        let (s1, _) =
            l.integrate(Kind::Solid, &PointState::default(), &[0.0, 0.0, 0.0, 2e-3, 0.0, 0.0], Request::Full).unwrap();
        assert!(s1.plastic);
        let (_, dp) = l.integrate(Kind::Solid, &s1, &s1.eps, Request::Prediction).unwrap();
        let mu = 200_000.0 / 2.6;
        assert!(dp[3][3] < 0.9 * mu, "elastoplastic shear stiffness {} vs μ {mu}", dp[3][3]);
        let (s2, d2) = l.integrate(Kind::Solid, &s1, &[0.0, 0.0, 0.0, 1.5e-3, 0.0, 0.0], Request::Full).unwrap();
        assert!(!s2.plastic && s2.p == s1.p);
        assert!((s2.sig[3] - (s1.sig[3] - mu * 1e-3)).abs() < 1e-9);
        assert!((d2[3][3] - mu).abs() < 1e-9 * mu);
    }
}
