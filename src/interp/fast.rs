//! A FORMULE's expression compiled once for evaluation without an interpreter, when it is plain
//! arithmetic: numbers, its parameters, numeric values of its context, the math module's constants and
//! functions, `+ - * / // % **` and unary signs. The operations are the interpreter's own (`ops::binop`,
//! `ops::unary`, `builtins::math_call`) applied in the same order, so the results are the same bit for
//! bit; anything else (other names, which the file's globals resolve at call time, comparisons,
//! conditionals, calls of other functions) leaves the formula to the interpreter.
//!
//! DEFI_FISS_XFEM evaluates its level-set formulas at every node and the loads theirs at every
//! integration point: the interpreter's setup per call (a scope with the math module, the context and
//! the parameters) cost more than the arithmetic.

use super::builtins;
use super::ops;
use super::value::Value;
use crate::diag::Result;
use crate::syntax::ast::{Arg, Expr, ExprKind, UnOp};

/// A compiled expression.
#[derive(Debug, Clone)]
pub enum Fast {
    Const(Value),
    Param(usize),
    Bin(crate::syntax::ast::BinOp, Box<Fast>, Box<Fast>),
    Unary(UnOp, Box<Fast>),
    /// A math function (unqualified name) and its positional arguments.
    Math(String, Vec<Fast>),
}

/// Compile `e` for parameters `params` and the context `context` (later entries shadow earlier ones,
/// parameters shadow the context, the context shadows the math module, as the interpreter's scope does).
pub fn compile(e: &Expr, params: &[String], context: &[(String, Value)]) -> Option<Fast> {
    let local = |n: &str| -> Option<Fast> {
        if let Some(i) = params.iter().rposition(|p| p == n) {
            return Some(Fast::Param(i));
        }
        if let Some((_, v)) = context.iter().rev().find(|(k, _)| k == n) {
            return match v {
                Value::Int(_) | Value::Float(_) | Value::Bool(_) => Some(Fast::Const(v.clone())),
                _ => None,
            };
        }
        builtins::math_constant(n).map(|v| Fast::Const(Value::Float(v)))
    };
    let shadowed = |n: &str| params.iter().any(|p| p == n) || context.iter().any(|(k, _)| k == n);
    Some(match &e.kind {
        ExprKind::Int(i) => Fast::Const(Value::Int(*i)),
        ExprKind::Float(f) => Fast::Const(Value::Float(*f)),
        ExprKind::Name(n) => local(n)?,
        ExprKind::BinOp(a, op, b) => {
            Fast::Bin(*op, Box::new(compile(a, params, context)?), Box::new(compile(b, params, context)?))
        }
        ExprKind::Unary(op, a) if matches!(op, UnOp::Neg | UnOp::Pos) => {
            Fast::Unary(*op, Box::new(compile(a, params, context)?))
        }
        ExprKind::Call(f, args) => {
            let ExprKind::Name(name) = &f.kind else { return None };
            if shadowed(name) || !builtins::is_math_function(name) {
                return None;
            }
            let mut compiled = Vec::with_capacity(args.len());
            for a in args {
                let Arg::Positional(x) = a else { return None };
                compiled.push(compile(x, params, context)?);
            }
            Fast::Math(name.clone(), compiled)
        }
        _ => return None,
    })
}

impl Fast {
    /// The value for the parameters `values`.
    pub fn eval(&self, values: &[f64]) -> Result<Value> {
        Ok(match self {
            Fast::Const(v) => v.clone(),
            Fast::Param(i) => Value::Float(values[*i]),
            Fast::Bin(op, a, b) => {
                let a = a.eval(values)?;
                let b = b.eval(values)?;
                ops::binop(*op, &a, &b)?
            }
            Fast::Unary(op, a) => ops::unary(*op, &a.eval(values)?)?,
            Fast::Math(name, args) => {
                let args: Vec<Value> = args.iter().map(|a| a.eval(values)).collect::<Result<_>>()?;
                builtins::math_call(name, &args)?
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fast(text: &str, params: &[&str], context: &[(&str, f64)]) -> Option<Fast> {
        let e = crate::syntax::parse_expr(text, 0).unwrap();
        let p: Vec<String> = params.iter().map(|s| s.to_string()).collect();
        let c: Vec<(String, Value)> = context.iter().map(|(k, v)| (k.to_string(), Value::Float(*v))).collect();
        compile(&e, &p, &c)
    }

    #[test]
    fn arithmetic_compiles_and_other_names_do_not() {
        let f = fast("Y-0.5*X-(2.0+D)", &["X", "Y"], &[("D", 0.25)]).unwrap();
        assert_eq!(f.eval(&[2.0, 4.0]).unwrap().as_f64(), Some(4.0 - 0.5 * 2.0 - (2.0 + 0.25)));
        let f = fast("sqrt(X**2+Y**2)-R*cos(pi/3)", &["X", "Y"], &[("R", 2.0)]).unwrap();
        let want = (3.0f64.powf(2.0) + 4.0f64.powf(2.0)).sqrt() - 2.0 * (std::f64::consts::PI / 3.0).cos();
        assert_eq!(f.eval(&[3.0, 4.0]).unwrap().as_f64(), Some(want));
        // A global, a comparison, a user function: left to the interpreter.
        assert!(fast("X+U", &["X"], &[]).is_none());
        assert!(fast("X if X > 0 else 0", &["X"], &[]).is_none());
        assert!(fast("f(X)", &["X"], &[]).is_none());
        // A parameter named like a math function shadows it.
        assert!(fast("e(X)", &["X", "e"], &[]).is_none());
        let f = fast("e*2", &["e"], &[]).unwrap();
        assert_eq!(f.eval(&[1.5]).unwrap().as_f64(), Some(3.0));
    }

    #[test]
    fn errors_are_the_interpreters() {
        let f = fast("1/X", &["X"], &[]).unwrap();
        assert!(f.eval(&[0.0]).unwrap_err().msg.contains("ZeroDivisionError"));
        let f = fast("sqrt(X)", &["X"], &[]).unwrap();
        assert!(f.eval(&[-1.0]).unwrap_err().msg.contains("math domain error"));
    }
}
