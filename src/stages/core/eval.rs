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
    match &*c.data() {
        ConceptData::Function(f) if f.nom_para == "TOUTPARA" => f.eval(0.0),
        ConceptData::Function(f) => f.eval(arg(&f.nom_para)?),
        ConceptData::Nappe(n) => n.eval(arg(&n.nom_para)?, arg(&n.nom_para_fonc)?),
        ConceptData::Formula(f) => {
            let vals: Vec<f64> = f.nom_para.iter().map(|p| arg(p)).collect::<Result<_>>()?;
            f.eval(&vals)
        }
        _ => Err(Error::runtime(format!("{} ({}) is not a function", c.label(), c.kind()))),
    }
}
