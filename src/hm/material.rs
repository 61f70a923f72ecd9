//! The parameters of a saturated poro-elastic material (`ELAS`, `THM_INIT`, `THM_DIFFU`, `THM_LIQU`).

/// A saturated Biot material as `KIT_HM` (`ELAS`, `LIQU_SATU`, `HYDR_UTIL`) reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Biot {
    /// `ELAS E`, `NU`: the drained skeleton.
    pub e: f64,
    pub nu: f64,
    /// `THM_DIFFU BIOT_COEF`.
    pub biot: f64,
    /// `THM_INIT PORO`: the initial porosity φ₀.
    pub phi0: f64,
    /// `THM_LIQU RHO`: the initial liquid density ρ₀ (kg/m³).
    pub rho_l: f64,
    /// `THM_LIQU UN_SUR_K`: the liquid's compressibility 1/K_w (Pa⁻¹).
    pub inv_kw: f64,
    /// `THM_LIQU VISC`: the liquid's dynamic viscosity μ (Pa·s).
    pub visc: f64,
    /// `THM_DIFFU PERM_IN`: the intrinsic permeability K_int (m²).
    pub perm: f64,
    /// `THM_DIFFU PESA_X/Y/Z`: the gravity of the fluid (Darcy and the weight of the added mass).
    pub gravity: [f64; 3],
    /// `THM_DIFFU RHO`: the density of the mixture, which `PESANTEUR` weighs.
    pub rho_h: f64,
}

impl Biot {
    /// The drained bulk modulus K₀ = E / (3 (1 − 2ν)).
    pub fn k0(&self) -> f64 {
        self.e / (3.0 * (1.0 - 2.0 * self.nu))
    }

    /// 1/K_s = (1 − b)/K₀: the compressibility of the solid grains.
    pub fn inv_ks(&self) -> f64 {
        (1.0 - self.biot) / self.k0()
    }

    /// The mobility K_int/μ (m²/(Pa·s)).
    pub fn mobility(&self) -> f64 {
        self.perm / self.visc
    }

    /// The Biot modulus: 1/M = φ₀/K_w + (b − φ₀)/K_s.
    pub fn inv_biot_modulus(&self) -> f64 {
        self.phi0 * self.inv_kw + (self.biot - self.phi0) * self.inv_ks()
    }

    /// The parameters checked: the first one out of its physical range, named as Code_Aster names it.
    pub fn check(&self) -> Result<(), String> {
        let finite = [
            ("ELAS/E", self.e),
            ("ELAS/NU", self.nu),
            ("THM_DIFFU/BIOT_COEF", self.biot),
            ("THM_INIT/PORO", self.phi0),
            ("THM_LIQU/RHO", self.rho_l),
            ("THM_LIQU/UN_SUR_K", self.inv_kw),
            ("THM_LIQU/VISC", self.visc),
            ("THM_DIFFU/PERM_IN", self.perm),
            ("THM_DIFFU/RHO", self.rho_h),
        ];
        if let Some((n, v)) = finite.iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!("{n} = {v} is not a finite number"));
        }
        if self.e <= 0.0 {
            return Err(format!("ELAS/E = {} must be positive", self.e));
        }
        if !(-1.0 < self.nu && self.nu < 0.5) {
            return Err(format!("ELAS/NU = {} must lie in ]-1, 0.5[", self.nu));
        }
        if !(0.0 < self.phi0 && self.phi0 < 1.0) {
            return Err(format!("THM_INIT/PORO = {} must lie in ]0, 1[", self.phi0));
        }
        // Code_Aster takes any coefficient; one below the porosity (grains more compressible than the
        // skeleton) is unphysical but some tests use it to switch the coupling off (b = 1e-12).
        if !(0.0 <= self.biot && self.biot <= 1.0) {
            return Err(format!("THM_DIFFU/BIOT_COEF = {} must lie in [0, 1]", self.biot));
        }
        if self.rho_l <= 0.0 {
            return Err(format!("THM_LIQU/RHO = {} must be positive", self.rho_l));
        }
        if self.inv_kw < 0.0 {
            return Err(format!("THM_LIQU/UN_SUR_K = {} must not be negative", self.inv_kw));
        }
        if self.visc <= 0.0 {
            return Err(format!("THM_LIQU/VISC = {} must be positive", self.visc));
        }
        if self.perm < 0.0 {
            return Err(format!("THM_DIFFU/PERM_IN = {} must not be negative", self.perm));
        }
        if self.rho_h < 0.0 {
            return Err(format!("THM_DIFFU/RHO = {} must not be negative", self.rho_h));
        }
        Ok(())
    }
}

#[cfg(test)]
pub(crate) fn sample() -> Biot {
    Biot {
        e: 1.0e7,
        nu: 0.25,
        biot: 0.8,
        phi0: 0.3,
        rho_l: 1000.0,
        inv_kw: 5.0e-10,
        visc: 1.0e-3,
        perm: 1.0e-12,
        gravity: [0.0, -9.81, 0.0],
        rho_h: 2000.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moduli() {
        let m = sample();
        assert!((m.k0() - 1.0e7 / 1.5).abs() < 1e-6);
        assert!((m.inv_ks() - 0.2 / m.k0()).abs() < 1e-20);
        let inv_m = 0.3 * 5.0e-10 + 0.5 * 0.2 / m.k0();
        assert!((m.inv_biot_modulus() - inv_m).abs() < 1e-22);
    }

    #[test]
    fn out_of_range_parameters_are_named() {
        let bad = |f: fn(&mut Biot)| {
            let mut m = sample();
            f(&mut m);
            m.check().unwrap_err()
        };
        assert!(bad(|m| m.perm = -1.0).starts_with("THM_DIFFU/PERM_IN"));
        assert!(bad(|m| m.visc = 0.0).starts_with("THM_LIQU/VISC"));
        assert!(bad(|m| m.phi0 = 1.2).starts_with("THM_INIT/PORO"));
        assert!(bad(|m| m.biot = 1.1).starts_with("THM_DIFFU/BIOT_COEF"));
        assert!(bad(|m| m.e = f64::NAN).starts_with("ELAS/E"));
        sample().check().unwrap();
    }
}
