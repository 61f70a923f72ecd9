//! Tabulated functions of the temperature as `THER_NL` reads them (Code_Aster's `rcfode`): linear
//! interpolation between the points whatever the function's declared interpolation, and its
//! prolongations outside them; and the enthalpy `β(T)` integrated from a tabulated `ρCp(T)` as
//! `create_enthalpy` builds it (trapezoids through the points, linear between them).

use std::fmt;

/// How a curve continues outside its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extension {
    Constant,
    Linear,
    /// Evaluating there is an error.
    Excluded,
}

/// A piecewise-linear function of one variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    x: Vec<f64>,
    y: Vec<f64>,
    left: Extension,
    right: Extension,
}

/// A value outside a curve whose extension on that side is excluded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutOfRange {
    pub value: f64,
    /// The first or last abscissa it passed.
    pub bound: f64,
}

impl fmt::Display for OutOfRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let side = if self.value < self.bound { "below the first" } else { "above the last" };
        write!(
            f,
            "temperature {:e} is {side} abscissa {:e} of a function that is not extended there",
            self.value, self.bound
        )
    }
}

impl Curve {
    /// A curve through the points (strictly increasing abscissas, at least one point; one point is a
    /// constant).
    pub fn new(x: Vec<f64>, y: Vec<f64>, left: Extension, right: Extension) -> Result<Curve, String> {
        if x.is_empty() || x.len() != y.len() {
            return Err(format!(
                "a curve needs as many values as abscissas, at least one ({} and {})",
                x.len(),
                y.len()
            ));
        }
        if let Some(w) = x.windows(2).position(|w| w[1] <= w[0] || w[0].is_nan()) {
            return Err(format!("abscissas must be strictly increasing: {} then {}", x[w], x[w + 1]));
        }
        Ok(Curve { x, y, left, right })
    }

    /// The constant `v`.
    pub fn constant(v: f64) -> Curve {
        Curve { x: vec![0.0], y: vec![v], left: Extension::Constant, right: Extension::Constant }
    }

    /// The value and the derivative at `t`. Inside, the segment whose right end is the first abscissa
    /// ≥ `t` (so the left segment at a point). Below the first point Code_Aster's `rcfode` reads the
    /// *right* extension first: constant when it is constant, else the left one applies (linear, or
    /// an error when excluded; a constant left with a non-constant right is constant).
    pub fn eval(&self, t: f64) -> Result<(f64, f64), OutOfRange> {
        let n = self.x.len();
        if n == 1 {
            return Ok((self.y[0], 0.0));
        }
        let seg = |k: usize| {
            let d = (self.y[k] - self.y[k - 1]) / (self.x[k] - self.x[k - 1]);
            (d * (t - self.x[k - 1]) + self.y[k - 1], d)
        };
        if t < self.x[0] {
            if self.right == Extension::Constant {
                return Ok((self.y[0], 0.0));
            }
            return match self.left {
                Extension::Linear => Ok(seg(1)),
                Extension::Excluded => Err(OutOfRange { value: t, bound: self.x[0] }),
                Extension::Constant => Ok((self.y[0], 0.0)),
            };
        }
        if t > self.x[n - 1] {
            return match self.right {
                Extension::Constant => Ok((self.y[n - 1], 0.0)),
                Extension::Linear => Ok(seg(n - 1)),
                Extension::Excluded => Err(OutOfRange { value: t, bound: self.x[n - 1] }),
            };
        }
        let k = self.x.partition_point(|&x| x < t).max(1);
        Ok(seg(k))
    }

    /// The enthalpy of a volumetric heat capacity `ρCp(T)`: `β(T) = ∫ ρCp dT` by trapezoids through
    /// `rho_cp`'s points (exact there for a piecewise-linear `ρCp`) and linear between them, from
    /// `β(T₁) = ρ̄ (T₁ + 273.15)` with `ρ̄` the mean of the first two values (Code_Aster's
    /// `create_enthalpy`; the constant never shows, only differences of `β` do). Extended linearly on
    /// the left, and on the right where `ρCp` is constant there (else as `ρCp` is). A constant `ρCp = c`
    /// gives the line of slope `c` through `(T₁, c (T₁ + 273.15))`.
    pub fn enthalpy(rho_cp: &Curve) -> Curve {
        const ZERO_CELSIUS: f64 = 273.15;
        let (x, y) = (&rho_cp.x, &rho_cp.y);
        if x.len() == 1 {
            let b0 = y[0] * (x[0] + ZERO_CELSIUS);
            return Curve {
                x: vec![x[0], x[0] + 1.0],
                y: vec![b0, b0 + y[0]],
                left: Extension::Linear,
                right: Extension::Linear,
            };
        }
        let mut b = Vec::with_capacity(x.len());
        b.push(0.5 * (y[0] + y[1]) * (x[0] + ZERO_CELSIUS));
        for k in 1..x.len() {
            b.push(b[k - 1] + 0.5 * (y[k] + y[k - 1]) * (x[k] - x[k - 1]));
        }
        let right = if rho_cp.right == Extension::Constant { Extension::Linear } else { rho_cp.right };
        Curve { x: x.clone(), y: b, left: Extension::Linear, right }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(left: Extension, right: Extension) -> Curve {
        Curve::new(vec![0.0, 10.0, 20.0], vec![1.0, 3.0, 4.0], left, right).unwrap()
    }

    #[test]
    fn inside_linear_with_the_left_segment_at_a_point() {
        let f = c(Extension::Excluded, Extension::Excluded);
        assert_eq!(f.eval(5.0).unwrap(), (2.0, 0.2));
        assert_eq!(f.eval(10.0).unwrap(), (3.0, 0.2));
        assert_eq!(f.eval(15.0).unwrap(), (3.5, 0.1));
        assert_eq!(f.eval(0.0).unwrap(), (1.0, 0.2));
        assert_eq!(f.eval(20.0).unwrap(), (4.0, 0.1));
    }

    #[test]
    fn extensions_as_rcfode_reads_them() {
        let f = c(Extension::Linear, Extension::Linear);
        assert_eq!(f.eval(-5.0).unwrap(), (0.0, 0.2));
        assert_eq!(f.eval(30.0).unwrap(), (5.0, 0.1));
        let f = c(Extension::Constant, Extension::Constant);
        assert_eq!(f.eval(-5.0).unwrap(), (1.0, 0.0));
        assert_eq!(f.eval(30.0).unwrap(), (4.0, 0.0));
        // Below the range a constant right extension wins over a linear left one.
        let f = c(Extension::Linear, Extension::Constant);
        assert_eq!(f.eval(-5.0).unwrap(), (1.0, 0.0));
        let f = c(Extension::Excluded, Extension::Linear);
        let e = f.eval(-1.0).unwrap_err();
        assert_eq!(e, OutOfRange { value: -1.0, bound: 0.0 });
        assert!(e.to_string().contains("below the first abscissa"));
        assert!(c(Extension::Linear, Extension::Excluded).eval(21.0).is_err());
    }

    #[test]
    fn enthalpy_integrates_rho_cp_exactly_at_the_points() {
        let rho_cp = c(Extension::Constant, Extension::Constant);
        let b = Curve::enthalpy(&rho_cp);
        let (b0, _) = b.eval(0.0).unwrap();
        // ∫₀¹⁰ (1 + 0.2 T) dT = 20, ∫₁₀²⁰ (3 + 0.1 (T − 10)) dT = 35.
        assert!((b.eval(10.0).unwrap().0 - b0 - 20.0).abs() < 1e-12);
        assert!((b.eval(20.0).unwrap().0 - b0 - 55.0).abs() < 1e-12);
        // Linear beyond, with the slope of the last (first) segment: ρCp is constant there.
        let (v, d) = b.eval(30.0).unwrap();
        assert!((d - 3.5).abs() < 1e-12 && (v - b0 - 90.0).abs() < 1e-12);
        assert!((b.eval(-10.0).unwrap().1 - 2.0).abs() < 1e-12);
        // A constant: a line of that slope.
        let b = Curve::enthalpy(&Curve::constant(4.0e6));
        let (v1, d1) = b.eval(-50.0).unwrap();
        let (v2, d2) = b.eval(500.0).unwrap();
        assert_eq!((d1, d2), (4.0e6, 4.0e6));
        assert!(((v2 - v1) / 550.0 - 4.0e6).abs() < 1e-6);
    }

    #[test]
    fn bad_points_are_refused() {
        assert!(Curve::new(vec![0.0, 0.0], vec![1.0, 2.0], Extension::Linear, Extension::Linear).is_err());
        assert!(Curve::new(vec![], vec![], Extension::Linear, Extension::Linear).is_err());
        assert!(Curve::new(vec![0.0], vec![1.0, 2.0], Extension::Linear, Extension::Linear).is_err());
    }
}
