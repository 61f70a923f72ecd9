//! Tabulated functions of one variable (`fonction_sdaster`) and of two
//! (`nappe_sdaster`), with Code_Aster's interpolation and extension rules.

use crate::diag::{Error, Result};

/// Interpolation along one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interp {
    Lin,
    Log,
    /// No interpolation: only tabulated abscissas may be evaluated.
    Non,
}

impl Interp {
    pub fn parse(s: &str) -> Option<Interp> {
        match s {
            "LIN" => Some(Interp::Lin),
            "LOG" => Some(Interp::Log),
            "NON" => Some(Interp::Non),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Interp::Lin => "LIN",
            Interp::Log => "LOG",
            Interp::Non => "NON",
        }
    }
}

/// Extension outside the tabulated range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prol {
    Constant,
    Lineaire,
    Exclu,
}

impl Prol {
    pub fn parse(s: &str) -> Option<Prol> {
        match s {
            "CONSTANT" => Some(Prol::Constant),
            "LINEAIRE" => Some(Prol::Lineaire),
            "EXCLU" => Some(Prol::Exclu),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Prol::Constant => "CONSTANT",
            Prol::Lineaire => "LINEAIRE",
            Prol::Exclu => "EXCLU",
        }
    }
}

/// A function y(x) given by points.
#[derive(Debug, Clone)]
pub struct Function {
    pub nom_para: String,
    pub nom_resu: String,
    /// Interpolation of (x, y): LIN LIN, LOG LOG, ...
    pub interp: (Interp, Interp),
    pub prol_gauche: Prol,
    pub prol_droite: Prol,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
}

fn fwd(i: Interp, v: f64) -> f64 {
    if i == Interp::Log {
        v.ln()
    } else {
        v
    }
}

fn back(i: Interp, v: f64) -> f64 {
    if i == Interp::Log {
        v.exp()
    } else {
        v
    }
}

impl Function {
    /// Build and check a function: abscissas must be strictly increasing.
    pub fn new(
        nom_para: &str,
        nom_resu: &str,
        x: Vec<f64>,
        y: Vec<f64>,
        interp: (Interp, Interp),
        prol_gauche: Prol,
        prol_droite: Prol,
    ) -> Result<Function> {
        if x.len() != y.len() {
            return Err(Error::runtime(format!(
                "a function needs as many ordinates as abscissas ({} vs {})",
                y.len(),
                x.len()
            )));
        }
        if x.is_empty() {
            return Err(Error::runtime("a function needs at least one point"));
        }
        if let Some(w) = x.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::runtime(format!(
                "the abscissas of a function must be strictly increasing: {} then {} (points {} and {})",
                x[w],
                x[w + 1],
                w + 1,
                w + 2
            )));
        }
        Ok(Function {
            nom_para: nom_para.to_string(),
            nom_resu: nom_resu.to_string(),
            interp,
            prol_gauche,
            prol_droite,
            x,
            y,
        })
    }

    /// A constant function (DEFI_CONSTANTE).
    pub fn constant(nom_resu: &str, v: f64) -> Function {
        Function {
            nom_para: "TOUTPARA".into(),
            nom_resu: nom_resu.into(),
            interp: (Interp::Lin, Interp::Lin),
            prol_gauche: Prol::Constant,
            prol_droite: Prol::Constant,
            x: vec![1.0],
            y: vec![v],
        }
    }

    fn segment(&self, i: usize, x: f64) -> f64 {
        let (ix, iy) = self.interp;
        let (x0, x1) = (fwd(ix, self.x[i]), fwd(ix, self.x[i + 1]));
        let (y0, y1) = (fwd(iy, self.y[i]), fwd(iy, self.y[i + 1]));
        let t = (fwd(ix, x) - x0) / (x1 - x0);
        back(iy, y0 + t * (y1 - y0))
    }

    /// Evaluate at `x` (interpolating and extending as declared).
    pub fn eval(&self, x: f64) -> Result<f64> {
        let n = self.x.len();
        let tol = 1e-12 * self.x[0].abs().max(self.x[n - 1].abs()).max(1.0);
        if let Some(i) = self.x.iter().position(|&xi| (xi - x).abs() <= tol) {
            return Ok(self.y[i]);
        }
        if x < self.x[0] {
            return match self.prol_gauche {
                Prol::Exclu => Err(self.out_of_range(x, "left")),
                Prol::Constant => Ok(self.y[0]),
                Prol::Lineaire if n >= 2 => Ok(self.segment(0, x)),
                Prol::Lineaire => Ok(self.y[0]),
            };
        }
        if x > self.x[n - 1] {
            return match self.prol_droite {
                Prol::Exclu => Err(self.out_of_range(x, "right")),
                Prol::Constant => Ok(self.y[n - 1]),
                Prol::Lineaire if n >= 2 => Ok(self.segment(n - 2, x)),
                Prol::Lineaire => Ok(self.y[n - 1]),
            };
        }
        if self.interp.0 == Interp::Non {
            return Err(Error::runtime(format!(
                "function with INTERPOL='NON' evaluated at {x}, which is not one of its abscissas"
            )));
        }
        let i = self.x.partition_point(|&xi| xi <= x) - 1;
        Ok(self.segment(i.min(n - 2), x))
    }

    fn out_of_range(&self, x: f64, side: &str) -> Error {
        Error::runtime(format!(
            "{} = {x} is outside the range [{}, {}] of the function, which is not extended to the {side} (PROL_{}='EXCLU')",
            self.nom_para,
            self.x[0],
            self.x[self.x.len() - 1],
            if side == "left" { "GAUCHE" } else { "DROITE" }
        ))
    }
}

/// A function of two variables: one function of `nom_para_fonc` per value of
/// `nom_para`.
#[derive(Debug, Clone)]
pub struct Nappe {
    pub nom_para: String,
    pub nom_para_fonc: String,
    pub nom_resu: String,
    pub interp: (Interp, Interp),
    pub prol_gauche: Prol,
    pub prol_droite: Prol,
    pub params: Vec<f64>,
    pub functions: Vec<Function>,
}

impl Nappe {
    /// Build from possibly unsorted parameters (sorted here, functions follow).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        nom_para: &str,
        nom_para_fonc: &str,
        nom_resu: &str,
        params: Vec<f64>,
        functions: Vec<Function>,
        interp: (Interp, Interp),
        prol_gauche: Prol,
        prol_droite: Prol,
    ) -> Result<Nappe> {
        if params.len() != functions.len() {
            return Err(Error::runtime(format!(
                "a nappe needs one function per parameter value ({} values, {} functions)",
                params.len(),
                functions.len()
            )));
        }
        if params.is_empty() {
            return Err(Error::runtime("a nappe needs at least one parameter value"));
        }
        let mut pairs: Vec<(f64, Function)> = params.into_iter().zip(functions).collect();
        pairs.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        if let Some(w) = pairs.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(Error::runtime(format!("the parameter value {} appears twice in the nappe", w[0].0)));
        }
        let (params, functions) = pairs.into_iter().unzip();
        Ok(Nappe {
            nom_para: nom_para.into(),
            nom_para_fonc: nom_para_fonc.into(),
            nom_resu: nom_resu.into(),
            interp,
            prol_gauche,
            prol_droite,
            params,
            functions,
        })
    }

    /// Evaluate at (p, x): the functions on both sides of p at x, interpolated in p.
    pub fn eval(&self, p: f64, x: f64) -> Result<f64> {
        let n = self.params.len();
        let tol = 1e-12 * self.params[0].abs().max(self.params[n - 1].abs()).max(1.0);
        if let Some(i) = self.params.iter().position(|&q| (q - p).abs() <= tol) {
            return self.functions[i].eval(x);
        }
        let (i, prol) = if p < self.params[0] {
            (0, Some(self.prol_gauche))
        } else if p > self.params[n - 1] {
            (n.saturating_sub(2), Some(self.prol_droite))
        } else {
            ((self.params.partition_point(|&q| q <= p) - 1).min(n - 2), None)
        };
        match prol {
            Some(Prol::Exclu) => {
                return Err(Error::runtime(format!(
                    "{} = {p} is outside the range [{}, {}] of the nappe (PROL='EXCLU')",
                    self.nom_para,
                    self.params[0],
                    self.params[n - 1]
                )))
            }
            Some(Prol::Constant) => {
                let k = if p < self.params[0] { 0 } else { n - 1 };
                return self.functions[k].eval(x);
            }
            _ if n == 1 => return self.functions[0].eval(x),
            _ => {}
        }
        let (ip, iy) = self.interp;
        let (p0, p1) = (fwd(ip, self.params[i]), fwd(ip, self.params[i + 1]));
        let (y0, y1) = (fwd(iy, self.functions[i].eval(x)?), fwd(iy, self.functions[i + 1].eval(x)?));
        let t = (fwd(ip, p) - p0) / (p1 - p0);
        Ok(back(iy, y0 + t * (y1 - y0)))
    }
}

/// How a FORMULE is evaluated: by the interpreter that parsed it. Concepts know its parameters and its
/// text, never its expression.
pub trait Evaluate: std::fmt::Debug {
    /// The value with the parameters bound to `values` (in NOM_PARA order).
    fn eval(&self, values: &[f64]) -> Result<f64>;
}

/// FORMULE: its parameters (NOM_PARA), its text (VALE) and its evaluation.
#[derive(Debug, Clone)]
pub struct Formula {
    pub nom_para: Vec<String>,
    pub text: String,
    body: std::rc::Rc<dyn Evaluate>,
}

impl Formula {
    pub fn new(nom_para: Vec<String>, text: String, body: std::rc::Rc<dyn Evaluate>) -> Formula {
        Formula { nom_para, text, body }
    }

    /// Evaluate with the parameters bound to `values` (in NOM_PARA order).
    pub fn eval(&self, values: &[f64]) -> Result<f64> {
        self.body.eval(values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(x: Vec<f64>, y: Vec<f64>, pg: Prol, pd: Prol) -> Function {
        Function::new("X", "Y", x, y, (Interp::Lin, Interp::Lin), pg, pd).unwrap()
    }

    #[test]
    fn interpolation_and_extension() {
        let g = f(vec![0.0, 2.0, 4.0], vec![1.0, 2.0, 4.0], Prol::Lineaire, Prol::Constant);
        assert_eq!(g.eval(1.0).unwrap(), 1.5);
        assert_eq!(g.eval(3.0).unwrap(), 3.0);
        assert_eq!(g.eval(-2.0).unwrap(), 0.0);
        assert_eq!(g.eval(10.0).unwrap(), 4.0);
        let h = f(vec![0.0, 1.0], vec![0.0, 1.0], Prol::Exclu, Prol::Exclu);
        assert!(h.eval(1.5).unwrap_err().msg.contains("EXCLU"));
    }

    #[test]
    fn log_log_extension() {
        let g = Function::new(
            "X",
            "Y",
            vec![1.0, 2.0],
            vec![12.0, 16.0],
            (Interp::Log, Interp::Log),
            Prol::Constant,
            Prol::Lineaire,
        )
        .unwrap();
        let want = ((12f64).ln() + ((16f64).ln() - (12f64).ln()) / (2f64).ln() * (4f64).ln()).exp();
        assert!((g.eval(4.0).unwrap() - want).abs() < 1e-12 * want);
    }

    #[test]
    fn rejects_unsorted_abscissas() {
        assert!(Function::new(
            "X",
            "Y",
            vec![0.0, 0.0],
            vec![1.0, 2.0],
            (Interp::Lin, Interp::Lin),
            Prol::Exclu,
            Prol::Exclu
        )
        .is_err());
    }

    #[test]
    fn nappe_interpolates_between_functions() {
        let a = f(vec![1.0, 2.0], vec![3.0, 4.0], Prol::Exclu, Prol::Exclu);
        let b = f(vec![1.0, 2.0], vec![5.0, 8.0], Prol::Exclu, Prol::Exclu);
        let n = Nappe::new(
            "INST",
            "X",
            "Y",
            vec![20.0, 10.0],
            vec![b, a],
            (Interp::Lin, Interp::Lin),
            Prol::Exclu,
            Prol::Exclu,
        )
        .unwrap();
        assert_eq!(n.params, vec![10.0, 20.0]);
        assert_eq!(n.eval(15.0, 2.0).unwrap(), 6.0);
        assert!(n.eval(25.0, 1.0).is_err());
    }
}
