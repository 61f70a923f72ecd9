//! Function values at a point and time: loads, FONC_MULT, level sets, conditions.

use crate::concepts::model::LoadValue;
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};

/// Evaluate a load value at a point and time.
pub fn load_value(v: &LoadValue, x: &[f64; 3], inst: f64) -> Result<f64> {
    match v {
        LoadValue::Real(r) => Ok(*r),
        LoadValue::Func(c) => eval_at(c, x, inst),
    }
}

/// A function, nappe or formula of (X, Y, Z, INST) at a point and time.
pub fn eval_at(c: &ConceptRef, x: &[f64; 3], inst: f64) -> Result<f64> {
    let arg = |p: &str| -> Result<f64> {
        match p {
            "X" => Ok(x[0]),
            "Y" => Ok(x[1]),
            "Z" => Ok(x[2]),
            "INST" => Ok(inst),
            other => {
                Err(Error::runtime(format!("{}: parameter {other} is not known here (X, Y, Z or INST)", c.label())))
            }
        }
    };
    eval_named(c, &arg)
}

/// A function, nappe or formula evaluated with its parameters looked up by name.
pub fn eval_named(f: &ConceptRef, arg: &dyn Fn(&str) -> Result<f64>) -> Result<f64> {
    match &*f.data() {
        ConceptData::Function(g) if g.nom_para == "TOUTPARA" => g.eval(0.0),
        ConceptData::Function(g) => g.eval(arg(&g.nom_para)?),
        ConceptData::Nappe(g) => g.eval(arg(&g.nom_para)?, arg(&g.nom_para_fonc)?),
        ConceptData::Formula(g) => {
            let vals: Vec<f64> = g.nom_para.iter().map(|p| arg(p)).collect::<Result<_>>()?;
            g.eval(&vals)
        }
        _ => Err(Error::runtime(format!("{} ({}) is not a function", f.label(), f.kind()))),
    }
}
