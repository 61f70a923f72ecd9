//! Built-in functions, the `math` module, and methods of str / list / dict.

use super::format::{self, to_str};
use super::ops;
use super::value::{py_eq, Builtin, Dict, Value};
use super::Interp;
use crate::diag::{Error, Result};
use crate::syntax::ast::Span;
use std::cmp::Ordering;

const BUILTINS: &[&str] = &[
    "abs",
    "all",
    "any",
    "bool",
    "chr",
    "complex",
    "dict",
    "divmod",
    "enumerate",
    "filter",
    "float",
    "format",
    "int",
    "isinstance",
    "len",
    "list",
    "map",
    "max",
    "min",
    "ord",
    "pow",
    "print",
    "range",
    "repr",
    "reversed",
    "round",
    "sorted",
    "str",
    "sum",
    "tuple",
    "zip",
    "_F",
    "open",
];

const MATH_FUNCS: &[&str] = &[
    "acos",
    "acosh",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "ceil",
    "copysign",
    "cos",
    "cosh",
    "degrees",
    "exp",
    "expm1",
    "fabs",
    "factorial",
    "floor",
    "fmod",
    "gcd",
    "hypot",
    "isclose",
    "isfinite",
    "isinf",
    "isnan",
    "log",
    "log10",
    "log1p",
    "log2",
    "pow",
    "radians",
    "sin",
    "sinh",
    "sqrt",
    "tan",
    "tanh",
    "trunc",
];

const MATH_CONSTS: &[(&str, f64)] = &[
    ("pi", std::f64::consts::PI),
    ("e", std::f64::consts::E),
    ("tau", std::f64::consts::TAU),
    ("inf", f64::INFINITY),
    ("nan", f64::NAN),
];

const STR_METHODS: &[&str] = &[
    "capitalize",
    "center",
    "count",
    "endswith",
    "find",
    "format",
    "index",
    "isalpha",
    "isdigit",
    "join",
    "ljust",
    "lower",
    "lstrip",
    "replace",
    "rfind",
    "rjust",
    "rsplit",
    "rstrip",
    "split",
    "splitlines",
    "startswith",
    "strip",
    "title",
    "upper",
    "zfill",
];
const LIST_METHODS: &[&str] =
    &["append", "clear", "copy", "count", "extend", "index", "insert", "pop", "remove", "reverse", "sort"];
const TUPLE_METHODS: &[&str] = &["count", "index"];
const DICT_METHODS: &[&str] = &["clear", "copy", "get", "items", "keys", "pop", "setdefault", "update", "values"];

pub fn lookup_builtin(name: &str) -> Option<Value> {
    BUILTINS.iter().find(|b| **b == name).map(|b| Value::Builtin(Builtin(b)))
}

fn math_member(name: &str) -> Option<Value> {
    if let Some(f) = MATH_FUNCS.iter().find(|f| **f == name) {
        // Stored under a qualified static name: "math.sqrt".
        let q: &'static str = MATH_QUALIFIED[MATH_FUNCS.iter().position(|x| x == f).unwrap()];
        return Some(Value::Builtin(Builtin(q)));
    }
    MATH_CONSTS.iter().find(|(n, _)| *n == name).map(|(_, v)| Value::Float(*v))
}

const MATH_QUALIFIED: &[&str] = &[
    "math.acos",
    "math.acosh",
    "math.asin",
    "math.asinh",
    "math.atan",
    "math.atan2",
    "math.atanh",
    "math.ceil",
    "math.copysign",
    "math.cos",
    "math.cosh",
    "math.degrees",
    "math.exp",
    "math.expm1",
    "math.fabs",
    "math.factorial",
    "math.floor",
    "math.fmod",
    "math.gcd",
    "math.hypot",
    "math.isclose",
    "math.isfinite",
    "math.isinf",
    "math.isnan",
    "math.log",
    "math.log10",
    "math.log1p",
    "math.log2",
    "math.pow",
    "math.radians",
    "math.sin",
    "math.sinh",
    "math.sqrt",
    "math.tan",
    "math.tanh",
    "math.trunc",
];

/// Every public name of `math`, as `from math import *` binds them.
pub fn math_names() -> Vec<(String, Value)> {
    let mut v: Vec<(String, Value)> = MATH_FUNCS.iter().map(|f| (f.to_string(), math_member(f).unwrap())).collect();
    v.extend(MATH_CONSTS.iter().map(|(n, x)| (n.to_string(), Value::Float(*x))));
    v
}

fn unsupported_module(module: &str) -> Error {
    let root = module.split('.').next().unwrap_or(module);
    match root {
        "numpy" => Error::unsupported(format!("import {module}: this part of numpy is not supported by aster-rs")),
        "scipy" => Error::unsupported(format!(
            "import {module}: {root} is not supported by aster-rs; command files may use the math module only"
        )),
        "code_aster" => Error::unsupported(format!(
            "import {module}: the code_aster object API is not supported; use the commands only"
        )),
        _ => Error::unsupported(format!(
            "import {module}: module '{module}' is not supported; command files may use the math module only"
        )),
    }
}

/// The value `import MODULE [as ALIAS]` binds: the module itself with an alias, else its root.
pub fn import_module(module: &str, alias: bool) -> Result<Value> {
    match module {
        "math" => Ok(Value::Module("math")),
        m => super::modules::import(m, alias).ok_or_else(|| unsupported_module(m)),
    }
}

pub fn from_import(module: &str, names: Option<&[(String, Option<String>)]>) -> Result<Vec<(String, Value)>> {
    match (module, names) {
        ("math", None) => Ok(math_names()),
        ("math", Some(names)) => names
            .iter()
            .map(|(n, alias)| {
                math_member(n)
                    .map(|v| (alias.clone().unwrap_or_else(|| n.clone()), v))
                    .ok_or_else(|| Error::python(format!("ImportError: cannot import name '{n}' from 'math'")))
            })
            .collect(),
        // The commands are in scope already (through the host); CO comes with them.
        ("code_aster.Cata.Commands", None) => Ok(Vec::new()),
        (m, None) => super::modules::star_import(m).ok_or_else(|| unsupported_module(m)),
        (m, Some(names)) => {
            let mut out = Vec::new();
            for (n, alias) in names {
                let v = match super::modules::from_import(m, n) {
                    Some(v) => v?,
                    None => return Err(unsupported_module(m)),
                };
                out.push((alias.clone().unwrap_or_else(|| n.clone()), v));
            }
            Ok(out)
        }
    }
}

pub fn get_attr(obj: &Value, name: &str) -> Result<Value> {
    let methods: &[&str] = match obj {
        Value::Module("math") => {
            return math_member(name)
                .ok_or_else(|| Error::python(format!("AttributeError: module 'math' has no attribute '{name}'")))
        }
        Value::Module(m @ ("numpy" | "numpy.linalg")) => return super::numpy::get_attr(m, name),
        Value::Module(_) => return super::modules::get_attr(obj, name),
        Value::Array(_) => return super::numpy::array_attr(obj, name),
        Value::Instance(i) => {
            if let Some(v) = i.attrs.borrow().get(name) {
                return Ok(v.clone());
            }
            return match i.class.ns.borrow().get(name) {
                Some(Value::Func(f)) => Ok(Value::BoundMethod(i.clone(), f.clone())),
                Some(v) => Ok(v.clone()),
                None => {
                    Err(Error::python(format!("AttributeError: '{}' object has no attribute '{name}'", i.class.name)))
                }
            };
        }
        Value::Class(c) => {
            return c.ns.borrow().get(name).cloned().ok_or_else(|| {
                Error::python(format!("AttributeError: type object '{}' has no attribute '{name}'", c.name))
            })
        }
        Value::Complex(a, b) => {
            return match name {
                "real" => Ok(Value::Float(*a)),
                "imag" => Ok(Value::Float(*b)),
                _ => Err(Error::python(format!("AttributeError: 'complex' object has no attribute '{name}'"))),
            }
        }
        Value::Float(f) => {
            return match name {
                "real" => Ok(Value::Float(*f)),
                "imag" => Ok(Value::Float(0.0)),
                "is_integer" => Ok(Value::Method(Box::new(obj.clone()), "is_integer")),
                _ => Err(Error::python(format!("AttributeError: 'float' object has no attribute '{name}'"))),
            }
        }
        Value::Concept(c) => {
            return Err(Error::unsupported(format!(
                "{}.{name}: the code_aster object API (methods on {}) is not supported",
                c.label(),
                c.kind()
            )))
        }
        Value::Str(_) => STR_METHODS,
        Value::List(_) => LIST_METHODS,
        Value::Tuple(_) => TUPLE_METHODS,
        Value::Dict(_) => DICT_METHODS,
        _ => &[],
    };
    match methods.iter().find(|m| **m == name) {
        Some(m) => Ok(Value::Method(Box::new(obj.clone()), m)),
        None => Err(Error::python(format!("AttributeError: '{}' object has no attribute '{name}'", obj.type_name()))),
    }
}

// ------------------------------------------------------------------ helpers

fn arity(name: &str, args: &[Value], min: usize, max: usize) -> Result<()> {
    if args.len() < min || args.len() > max {
        let want = if min == max { format!("{min}") } else { format!("{min} to {max}") };
        return Err(Error::python(format!("TypeError: {name}() takes {want} argument(s) ({} given)", args.len())));
    }
    Ok(())
}

fn no_kw(name: &str, kw: &[(String, Value)]) -> Result<()> {
    match kw.first() {
        Some((k, _)) => Err(Error::python(format!("TypeError: {name}() got an unexpected keyword argument '{k}'"))),
        None => Ok(()),
    }
}

fn f64_arg(name: &str, v: &Value) -> Result<f64> {
    v.as_f64().ok_or_else(|| Error::python(format!("TypeError: {name}() needs a number, not {}", v.type_name())))
}

fn int_arg(name: &str, v: &Value) -> Result<i64> {
    v.as_int().ok_or_else(|| Error::python(format!("TypeError: {name}() needs an integer, not {}", v.type_name())))
}

/// The width of `str.ljust`, `rjust`, `center`, `zfill`: an int, at most `text::MAX_WIDTH`.
fn width_arg(name: &str, v: &Value) -> Result<usize> {
    let w = int_arg(name, v)?.max(0) as u64;
    let w = usize::try_from(w).unwrap_or(usize::MAX);
    crate::text::check_size(&format!("str.{name}() width"), w).map_err(|e| Error::python(e.to_string()))?;
    Ok(w)
}

fn math_domain() -> Error {
    Error::python("ValueError: math domain error")
}

fn sort_values(it: &mut Interp, items: &mut [Value], key: Option<&Value>, reverse: bool) -> Result<()> {
    let keys: Vec<Value> = match key {
        Some(k) if !matches!(k, Value::None) => {
            items.iter().map(|v| it.call(k, vec![v.clone()], Vec::new(), Span::default())).collect::<Result<_>>()?
        }
        _ => items.to_vec(),
    };
    let mut idx: Vec<usize> = (0..items.len()).collect();
    let mut err = None;
    idx.sort_by(|&a, &b| match ops::order(&keys[a], &keys[b]) {
        Ok(o) => {
            if reverse {
                o.reverse()
            } else {
                o
            }
        }
        Err(e) => {
            err = Some(e);
            Ordering::Equal
        }
    });
    if let Some(e) = err {
        return Err(e);
    }
    let sorted: Vec<Value> = idx.iter().map(|&i| items[i].clone()).collect();
    items.clone_from_slice(&sorted);
    Ok(())
}

fn kwarg<'a>(kw: &'a [(String, Value)], name: &str) -> Option<&'a Value> {
    kw.iter().find(|(k, _)| k == name).map(|(_, v)| v)
}

fn min_max(it: &mut Interp, name: &str, args: Vec<Value>, kw: &[(String, Value)], want: Ordering) -> Result<Value> {
    let items = if args.len() == 1 { args[0].iter_items()? } else { args };
    if items.is_empty() {
        return match kwarg(kw, "default") {
            Some(d) => Ok(d.clone()),
            None => Err(Error::python(format!("ValueError: {name}() arg is an empty sequence"))),
        };
    }
    let key = kwarg(kw, "key").cloned();
    let mut best = items[0].clone();
    let mut best_key = match &key {
        Some(k) => it.call(k, vec![best.clone()], Vec::new(), Span::default())?,
        None => best.clone(),
    };
    for v in items.into_iter().skip(1) {
        let k = match &key {
            Some(kf) => it.call(kf, vec![v.clone()], Vec::new(), Span::default())?,
            None => v.clone(),
        };
        if ops::order(&k, &best_key)? == want {
            best = v;
            best_key = k;
        }
    }
    Ok(best)
}

fn round_half_even(x: f64, nd: i64) -> f64 {
    if nd == 0 {
        return x.round_ties_even();
    }
    if nd > 0 {
        // Correctly rounded decimal text, then back: matches Python's round.
        format!("{:.*}", nd.min(300) as usize, x).parse().unwrap_or(x)
    } else {
        let p = 10f64.powi((-nd) as i32);
        (x / p).round_ties_even() * p
    }
}

fn parse_int_text(s: &str, base: u32) -> Result<i64> {
    if base != 0 && !(2..=36).contains(&base) {
        return Err(Error::python("ValueError: int() base must be >= 2 and <= 36, or 0"));
    }
    let t: String = s.trim().chars().filter(|c| *c != '_').collect();
    if base == 0 {
        let l = t.to_ascii_lowercase();
        let (neg, body) = match l.strip_prefix('-') {
            Some(b) => (true, b.to_string()),
            None => (false, l.trim_start_matches('+').to_string()),
        };
        let (b, digits) = if let Some(d) = body.strip_prefix("0x") {
            (16, d.to_string())
        } else if let Some(d) = body.strip_prefix("0o") {
            (8, d.to_string())
        } else if let Some(d) = body.strip_prefix("0b") {
            (2, d.to_string())
        } else {
            (10, body)
        };
        let v = parse_int_text(&digits, b)?;
        return Ok(if neg { -v } else { v });
    }
    i64::from_str_radix(&t, base).map_err(|_| {
        Error::python(format!("ValueError: invalid literal for int() with base {base}: {}", format::str_repr(s)))
    })
}

pub fn parse_float_text(s: &str) -> Option<f64> {
    let t = s.trim().to_ascii_lowercase().replace('_', "");
    match t.as_str() {
        "inf" | "+inf" | "infinity" => Some(f64::INFINITY),
        "-inf" | "-infinity" => Some(f64::NEG_INFINITY),
        "nan" | "+nan" | "-nan" => Some(f64::NAN),
        _ => t.parse::<f64>().ok(),
    }
}

// ------------------------------------------------------------------ builtins

pub fn call_builtin(it: &mut Interp, name: &'static str, args: Vec<Value>, kw: Vec<(String, Value)>) -> Result<Value> {
    if let Some(m) = name.strip_prefix("math.") {
        no_kw(name, &kw)?;
        return math_call(m, &args);
    }
    if let Some(m) = name.strip_prefix("os.path.") {
        no_kw(name, &kw)?;
        return super::modules::call_os_path(m, &args);
    }
    if name == "CO" {
        no_kw(name, &kw)?;
        return super::modules::co(&args);
    }
    if name == "CA.disable_fpe" {
        no_kw(name, &kw)?;
        arity(name, &args, 0, 0)?;
        return Ok(Value::Builtin(Builtin("CA.disable_fpe.context")));
    }
    if name == "open" {
        return Err(Error::unsupported(
            "open: reading or writing files outside the run's units is not supported by aster-rs",
        ));
    }
    if name.starts_with("numpy.") {
        return super::numpy::call(name, &args, &kw);
    }
    match name {
        "_F" => {
            if !args.is_empty() {
                return Err(Error::catalog("_F() takes keyword arguments only"));
            }
            let mut d = Dict::default();
            for (k, v) in kw {
                d.set(Value::str(&k), v);
            }
            Ok(Value::dict(d))
        }
        "dict" => {
            let mut d = match args.first() {
                Some(Value::Dict(src)) => src.borrow().clone(),
                Some(v) => {
                    let mut d = Dict::default();
                    for pair in v.iter_items()? {
                        let kv = pair.iter_items()?;
                        if kv.len() != 2 {
                            return Err(Error::python(
                                "ValueError: dictionary update sequence element has wrong length",
                            ));
                        }
                        ops::check_hashable(&kv[0])?;
                        d.set(kv[0].clone(), kv[1].clone());
                    }
                    d
                }
                None => Dict::default(),
            };
            for (k, v) in kw {
                d.set(Value::str(&k), v);
            }
            Ok(Value::dict(d))
        }
        "sorted" => {
            arity(name, &args, 1, 1)?;
            let mut items = args[0].iter_items()?;
            let reverse = kwarg(&kw, "reverse").map(|v| v.truthy()).transpose()?.unwrap_or(false);
            sort_values(it, &mut items, kwarg(&kw, "key"), reverse)?;
            Ok(Value::list(items))
        }
        "max" => min_max(it, name, args, &kw, Ordering::Greater),
        "min" => min_max(it, name, args, &kw, Ordering::Less),
        "map" => {
            if args.len() < 2 {
                return Err(Error::python("TypeError: map() must have at least two arguments."));
            }
            let f = args[0].clone();
            let seqs: Vec<Vec<Value>> = args[1..].iter().map(|s| s.iter_items()).collect::<Result<_>>()?;
            let n = seqs.iter().map(|s| s.len()).min().unwrap_or(0);
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                out.push(it.call(&f, seqs.iter().map(|s| s[i].clone()).collect(), Vec::new(), Span::default())?);
            }
            Ok(Value::list(out))
        }
        "filter" => {
            arity(name, &args, 2, 2)?;
            let mut out = Vec::new();
            for v in args[1].iter_items()? {
                let keep = match &args[0] {
                    Value::None => v.truthy()?,
                    f => it.call(f, vec![v.clone()], Vec::new(), Span::default())?.truthy()?,
                };
                if keep {
                    out.push(v);
                }
            }
            Ok(Value::list(out))
        }
        _ => {
            if name != "sum" && name != "int" && name != "round" {
                no_kw(name, &kw)?;
            }
            simple_builtin(name, args, &kw)
        }
    }
}

fn simple_builtin(name: &str, args: Vec<Value>, kw: &[(String, Value)]) -> Result<Value> {
    match name {
        "abs" => {
            arity(name, &args, 1, 1)?;
            match &args[0] {
                Value::Complex(a, b) => Ok(Value::Float(a.hypot(*b))),
                Value::Float(f) => Ok(Value::Float(f.abs())),
                Value::Array(_) => super::numpy::call("numpy.abs", &args, &[]),
                v => Ok(Value::Int(int_arg(name, v)?.checked_abs().ok_or_else(|| Error::python("OverflowError"))?)),
            }
        }
        "len" => {
            arity(name, &args, 1, 1)?;
            let n = match &args[0] {
                Value::Str(s) => s.chars().count(),
                Value::List(l) => l.borrow().len(),
                Value::Tuple(t) => t.len(),
                Value::Dict(d) => d.borrow().items.len(),
                Value::Array(a) => a.borrow().dims[0],
                v => return Err(Error::python(format!("TypeError: object of type '{}' has no len()", v.type_name()))),
            };
            Ok(Value::Int(n as i64))
        }
        "sum" => {
            arity(name, &args, 1, 2)?;
            let mut acc = args.get(1).cloned().or_else(|| kwarg(kw, "start").cloned()).unwrap_or(Value::Int(0));
            for v in args[0].iter_items()? {
                acc = ops::binop(crate::syntax::ast::BinOp::Add, &acc, &v)?;
            }
            Ok(acc)
        }
        "round" => {
            arity(name, &args, 1, 2)?;
            let nd = args.get(1).or_else(|| kwarg(kw, "ndigits")).cloned().unwrap_or(Value::None);
            match (&args[0], &nd) {
                (v, Value::None) if v.as_int().is_some() => Ok(Value::Int(v.as_int().unwrap())),
                (v, Value::None) => {
                    let f = f64_arg(name, v)?;
                    if !f.is_finite() {
                        return Err(Error::python("ValueError: cannot convert float NaN or infinity to integer"));
                    }
                    let r = f.round_ties_even();
                    if r.abs() >= 9.2e18 {
                        return Err(Error::python("OverflowError: the result does not fit a 64-bit integer"));
                    }
                    Ok(Value::Int(r as i64))
                }
                (v, n) if v.as_int().is_some() => {
                    let n = int_arg(name, n)?;
                    if n >= 0 {
                        Ok(Value::Int(v.as_int().unwrap()))
                    } else {
                        Ok(Value::Int(round_half_even(v.as_int().unwrap() as f64, n) as i64))
                    }
                }
                (v, n) => Ok(Value::Float(round_half_even(f64_arg(name, v)?, int_arg(name, n)?))),
            }
        }
        "int" => {
            arity(name, &args, 0, 2)?;
            let base = args.get(1).or_else(|| kwarg(kw, "base")).map(|b| int_arg(name, b)).transpose()?;
            match (args.first(), base) {
                (None, _) => Ok(Value::Int(0)),
                (Some(Value::Str(s)), b) => Ok(Value::Int(parse_int_text(s, b.unwrap_or(10) as u32)?)),
                (Some(Value::Float(f)), None) => {
                    if !f.is_finite() {
                        return Err(Error::python("ValueError: cannot convert float NaN or infinity to integer"));
                    }
                    if f.trunc().abs() >= 9.2e18 {
                        return Err(Error::python("OverflowError: the result does not fit a 64-bit integer"));
                    }
                    Ok(Value::Int(f.trunc() as i64))
                }
                (Some(v), None) if v.as_int().is_some() => Ok(Value::Int(v.as_int().unwrap())),
                (Some(v), _) => Err(Error::python(format!(
                    "TypeError: int() argument must be a string or a number, not '{}'",
                    v.type_name()
                ))),
            }
        }
        "float" => {
            arity(name, &args, 0, 1)?;
            match args.first() {
                None => Ok(Value::Float(0.0)),
                Some(Value::Str(s)) => parse_float_text(s).map(Value::Float).ok_or_else(|| {
                    Error::python(format!("ValueError: could not convert string to float: {}", format::str_repr(s)))
                }),
                Some(Value::Array(a)) => {
                    let a = a.borrow();
                    match a.data.as_slice() {
                        [x] => Ok(Value::Float(*x)),
                        _ => Err(Error::python("TypeError: only length-1 arrays can be converted to Python scalars")),
                    }
                }
                Some(v) => Ok(Value::Float(f64_arg(name, v)?)),
            }
        }
        "complex" => {
            arity(name, &args, 0, 2)?;
            let re = args.first().map(|v| f64_arg(name, v)).transpose()?.unwrap_or(0.0);
            let im = args.get(1).map(|v| f64_arg(name, v)).transpose()?.unwrap_or(0.0);
            Ok(Value::Complex(re, im))
        }
        "str" => {
            arity(name, &args, 0, 1)?;
            Ok(Value::str(&args.first().map(to_str).unwrap_or_default()))
        }
        "repr" => {
            arity(name, &args, 1, 1)?;
            Ok(Value::str(&format::repr(&args[0])))
        }
        "bool" => {
            arity(name, &args, 0, 1)?;
            Ok(Value::Bool(match args.first() {
                Some(v) => v.truthy()?,
                None => false,
            }))
        }
        "format" => {
            arity(name, &args, 1, 2)?;
            let spec = args.get(1).map(to_str).unwrap_or_default();
            Ok(Value::str(&format::format_value(&args[0], &spec)?))
        }
        "chr" => {
            arity(name, &args, 1, 1)?;
            let i = int_arg(name, &args[0])?;
            if i32::try_from(i).is_err() {
                return Err(Error::python("OverflowError: Python int too large to convert to C int"));
            }
            let c = u32::try_from(i)
                .ok()
                .filter(|i| *i < 0x110000)
                .ok_or_else(|| Error::python("ValueError: chr() arg not in range(0x110000)"))?;
            let c = char::from_u32(c).ok_or_else(|| {
                Error::python(format!(
                    "ValueError: chr({i:#x}) is a surrogate code point, which this interpreter's strings cannot hold"
                ))
            })?;
            Ok(Value::str(&c.to_string()))
        }
        "ord" => {
            arity(name, &args, 1, 1)?;
            let s = args[0].as_str().ok_or_else(|| Error::python("TypeError: ord() expected string"))?;
            let mut ch = s.chars();
            match (ch.next(), ch.next()) {
                (Some(c), None) => Ok(Value::Int(c as i64)),
                _ => Err(Error::python("TypeError: ord() expected a character")),
            }
        }
        "range" => {
            arity(name, &args, 1, 3)?;
            let ints: Vec<i64> = args.iter().map(|a| int_arg(name, a)).collect::<Result<_>>()?;
            let (start, stop, step) = match ints.as_slice() {
                [e] => (0, *e, 1),
                [s, e] => (*s, *e, 1),
                [s, e, st] => (*s, *e, *st),
                _ => unreachable!(),
            };
            if step == 0 {
                return Err(Error::python("ValueError: range() arg 3 must not be zero"));
            }
            let n = if step > 0 {
                (stop - start + step - 1).max(0) / step
            } else {
                (start - stop - step - 1).max(0) / -step
            };
            if n > 50_000_000 {
                return Err(Error::python(format!("MemoryError: range of {n} items is too large")));
            }
            Ok(Value::list((0..n).map(|i| Value::Int(start + i * step)).collect()))
        }
        "list" => {
            arity(name, &args, 0, 1)?;
            Ok(Value::list(args.first().map(|v| v.iter_items()).transpose()?.unwrap_or_default()))
        }
        "tuple" => {
            arity(name, &args, 0, 1)?;
            Ok(Value::tuple(args.first().map(|v| v.iter_items()).transpose()?.unwrap_or_default()))
        }
        "zip" => {
            let seqs: Vec<Vec<Value>> = args.iter().map(|s| s.iter_items()).collect::<Result<_>>()?;
            let n = seqs.iter().map(|s| s.len()).min().unwrap_or(0);
            Ok(Value::list((0..n).map(|i| Value::tuple(seqs.iter().map(|s| s[i].clone()).collect())).collect()))
        }
        "enumerate" => {
            arity(name, &args, 1, 2)?;
            let start = args.get(1).map(|v| int_arg(name, v)).transpose()?.unwrap_or(0);
            Ok(Value::list(
                args[0]
                    .iter_items()?
                    .into_iter()
                    .enumerate()
                    .map(|(i, v)| Value::tuple(vec![Value::Int(start + i as i64), v]))
                    .collect(),
            ))
        }
        "reversed" => {
            arity(name, &args, 1, 1)?;
            let mut v = args[0].iter_items()?;
            v.reverse();
            Ok(Value::list(v))
        }
        "any" | "all" => {
            arity(name, &args, 1, 1)?;
            let items = args[0].iter_items()?;
            let mut acc = name == "all";
            for v in items {
                let t = v.truthy()?;
                if name == "any" && t {
                    acc = true;
                    break;
                }
                if name == "all" && !t {
                    acc = false;
                    break;
                }
            }
            Ok(Value::Bool(acc))
        }
        "divmod" => {
            arity(name, &args, 2, 2)?;
            let q = ops::binop(crate::syntax::ast::BinOp::FloorDiv, &args[0], &args[1])?;
            let r = ops::binop(crate::syntax::ast::BinOp::Mod, &args[0], &args[1])?;
            Ok(Value::tuple(vec![q, r]))
        }
        "pow" => {
            arity(name, &args, 2, 2)?;
            ops::binop(crate::syntax::ast::BinOp::Pow, &args[0], &args[1])
        }
        "isinstance" => {
            arity(name, &args, 2, 2)?;
            let types = match &args[1] {
                Value::Tuple(t) => t.as_ref().clone(),
                v => vec![v.clone()],
            };
            let tn = args[0].type_name();
            let ok = types.iter().any(|t| match t {
                Value::Builtin(Builtin(b)) => *b == tn || (*b == "int" && tn == "bool"),
                _ => false,
            });
            Ok(Value::Bool(ok))
        }
        other => Err(Error::python(format!("built-in '{other}' is not supported"))),
    }
}

/// `math.<name>(*args)` as CPython computes it (a finite input giving an infinite result overflows).
pub fn math_call(name: &str, args: &[Value]) -> Result<Value> {
    let v = call_math(name, args)?;
    if matches!(v, Value::Float(f) if f.is_infinite())
        && args.iter().all(|a| a.as_f64().map(f64::is_finite).unwrap_or(true))
    {
        return Err(Error::python("OverflowError: math range error"));
    }
    Ok(v)
}

/// Is `name` a function of the math module?
pub fn is_math_function(name: &str) -> bool {
    MATH_FUNCS.contains(&name)
}

/// The value of a constant of the math module (`pi`, `e`, ...).
pub fn math_constant(name: &str) -> Option<f64> {
    MATH_CONSTS.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

fn call_math(name: &str, args: &[Value]) -> Result<Value> {
    let f = |i: usize| -> Result<f64> { f64_arg(name, &args[i]) };
    let one = |g: fn(f64) -> f64| -> Result<Value> {
        arity(name, args, 1, 1)?;
        let r = g(f(0)?);
        if r.is_nan() && !f(0)?.is_nan() {
            return Err(math_domain());
        }
        Ok(Value::Float(r))
    };
    match name {
        "sqrt" => {
            arity(name, args, 1, 1)?;
            let x = f(0)?;
            if x < 0.0 {
                return Err(math_domain());
            }
            Ok(Value::Float(x.sqrt()))
        }
        "exp" => one(f64::exp),
        "expm1" => one(f64::exp_m1),
        "log" => {
            arity(name, args, 1, 2)?;
            let x = f(0)?;
            if x <= 0.0 {
                return Err(math_domain());
            }
            match args.get(1) {
                None => Ok(Value::Float(x.ln())),
                Some(_) => {
                    let b = f(1)?;
                    if b <= 0.0 || b == 1.0 {
                        return Err(math_domain());
                    }
                    Ok(Value::Float(x.ln() / b.ln()))
                }
            }
        }
        "log10" | "log2" | "log1p" => {
            arity(name, args, 1, 1)?;
            let x = f(0)?;
            if (name == "log1p" && x <= -1.0) || (name != "log1p" && x <= 0.0) {
                return Err(math_domain());
            }
            Ok(Value::Float(match name {
                "log10" => x.log10(),
                "log2" => x.log2(),
                _ => x.ln_1p(),
            }))
        }
        "sin" => one(f64::sin),
        "cos" => one(f64::cos),
        "tan" => one(f64::tan),
        "asin" => one(f64::asin),
        "acos" => one(f64::acos),
        "atan" => one(f64::atan),
        "sinh" => one(f64::sinh),
        "cosh" => one(f64::cosh),
        "tanh" => one(f64::tanh),
        "asinh" => one(f64::asinh),
        "acosh" => one(f64::acosh),
        "atanh" => one(f64::atanh),
        "fabs" => one(f64::abs),
        "degrees" => one(f64::to_degrees),
        "radians" => one(f64::to_radians),
        "atan2" | "hypot" | "copysign" | "fmod" | "pow" => {
            arity(name, args, 2, 2)?;
            let (x, y) = (f(0)?, f(1)?);
            let r = match name {
                "atan2" => x.atan2(y),
                "hypot" => x.hypot(y),
                "copysign" => x.copysign(y),
                "fmod" => {
                    if y == 0.0 {
                        return Err(math_domain());
                    }
                    x % y
                }
                _ => {
                    if x == 0.0 && y < 0.0 || x < 0.0 && y.fract() != 0.0 {
                        return Err(math_domain());
                    }
                    x.powf(y)
                }
            };
            Ok(Value::Float(r))
        }
        "floor" | "ceil" | "trunc" => {
            arity(name, args, 1, 1)?;
            if let Some(i) = args[0].as_int() {
                return Ok(Value::Int(i));
            }
            let x = f(0)?;
            if !x.is_finite() {
                return Err(Error::python("ValueError: cannot convert float NaN or infinity to integer"));
            }
            Ok(Value::Int(match name {
                "floor" => x.floor(),
                "ceil" => x.ceil(),
                _ => x.trunc(),
            } as i64))
        }
        "isnan" | "isinf" | "isfinite" => {
            arity(name, args, 1, 1)?;
            let x = f(0)?;
            Ok(Value::Bool(match name {
                "isnan" => x.is_nan(),
                "isinf" => x.is_infinite(),
                _ => x.is_finite(),
            }))
        }
        "isclose" => {
            arity(name, args, 2, 2)?;
            let (a, b) = (f(0)?, f(1)?);
            Ok(Value::Bool(a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs())))
        }
        "factorial" => {
            arity(name, args, 1, 1)?;
            let n = int_arg(name, &args[0])?;
            if n < 0 {
                return Err(Error::python("ValueError: factorial() not defined for negative values"));
            }
            let mut acc: i64 = 1;
            for k in 2..=n {
                acc = acc.checked_mul(k).ok_or_else(|| Error::python("OverflowError: factorial too large"))?;
            }
            Ok(Value::Int(acc))
        }
        "gcd" => {
            arity(name, args, 2, 2)?;
            let (mut a, mut b) = (int_arg(name, &args[0])?.abs(), int_arg(name, &args[1])?.abs());
            while b != 0 {
                (a, b) = (b, a % b);
            }
            Ok(Value::Int(a))
        }
        _ => Err(Error::python(format!("math.{name} is not supported"))),
    }
}

// ------------------------------------------------------------------ methods

pub fn call_method(
    it: &mut Interp,
    recv: &Value,
    name: &str,
    args: Vec<Value>,
    kw: Vec<(String, Value)>,
) -> Result<Value> {
    match recv {
        Value::Array(a) => super::numpy::call_method(a, name, &args, &kw),
        Value::Str(s) => {
            if name == "format" {
                return Ok(Value::str(&str_format(s, &args, &kw)?));
            }
            no_kw(name, &kw)?;
            str_method(s, name, &args)
        }
        Value::List(l) => {
            if name == "sort" {
                let mut items = l.borrow().clone();
                let reverse = kwarg(&kw, "reverse").map(|v| v.truthy()).transpose()?.unwrap_or(false);
                sort_values(it, &mut items, kwarg(&kw, "key"), reverse)?;
                *l.borrow_mut() = items;
                return Ok(Value::None);
            }
            no_kw(name, &kw)?;
            let mut v = l.borrow_mut();
            match name {
                "append" => {
                    arity(name, &args, 1, 1)?;
                    v.push(args[0].clone());
                    Ok(Value::None)
                }
                "extend" => {
                    arity(name, &args, 1, 1)?;
                    let items = args[0].iter_items()?;
                    v.extend(items);
                    Ok(Value::None)
                }
                "insert" => {
                    arity(name, &args, 2, 2)?;
                    let n = v.len() as i64;
                    let i = int_arg(name, &args[0])?;
                    let i = if i < 0 { (i + n).max(0) } else { i.min(n) } as usize;
                    v.insert(i, args[1].clone());
                    Ok(Value::None)
                }
                "pop" => {
                    arity(name, &args, 0, 1)?;
                    if v.is_empty() {
                        return Err(Error::python("IndexError: pop from empty list"));
                    }
                    let n = v.len() as i64;
                    let i = args.first().map(|a| int_arg(name, a)).transpose()?.unwrap_or(-1);
                    let j = if i < 0 { i + n } else { i };
                    if j < 0 || j >= n {
                        return Err(Error::python("IndexError: pop index out of range"));
                    }
                    Ok(v.remove(j as usize))
                }
                "remove" => {
                    arity(name, &args, 1, 1)?;
                    let p = v
                        .iter()
                        .position(|x| py_eq(x, &args[0]))
                        .ok_or_else(|| Error::python("ValueError: list.remove(x): x not in list"))?;
                    v.remove(p);
                    Ok(Value::None)
                }
                "reverse" => {
                    v.reverse();
                    Ok(Value::None)
                }
                "clear" => {
                    v.clear();
                    Ok(Value::None)
                }
                "copy" => Ok(Value::list(v.clone())),
                "index" | "count" => seq_method(&v, name, &args),
                _ => unreachable!(),
            }
        }
        Value::Tuple(t) => {
            no_kw(name, &kw)?;
            seq_method(t, name, &args)
        }
        Value::Dict(d) => {
            if name == "update" {
                let mut dd = d.borrow_mut();
                if let Some(src) = args.first() {
                    match src {
                        Value::Dict(s) => {
                            let items = s.borrow().items.clone();
                            for (k, v) in items {
                                dd.set(k, v);
                            }
                        }
                        other => {
                            for pair in other.iter_items()? {
                                let kv = pair.iter_items()?;
                                if kv.len() == 2 {
                                    dd.set(kv[0].clone(), kv[1].clone());
                                }
                            }
                        }
                    }
                }
                for (k, v) in kw {
                    dd.set(Value::str(&k), v);
                }
                return Ok(Value::None);
            }
            no_kw(name, &kw)?;
            let mut dd = d.borrow_mut();
            match name {
                "keys" => Ok(Value::list(dd.items.iter().map(|(k, _)| k.clone()).collect())),
                "values" => Ok(Value::list(dd.items.iter().map(|(_, v)| v.clone()).collect())),
                "items" => {
                    Ok(Value::list(dd.items.iter().map(|(k, v)| Value::tuple(vec![k.clone(), v.clone()])).collect()))
                }
                "get" => {
                    arity(name, &args, 1, 2)?;
                    Ok(dd.get(&args[0]).cloned().unwrap_or_else(|| args.get(1).cloned().unwrap_or(Value::None)))
                }
                "pop" => {
                    arity(name, &args, 1, 2)?;
                    match dd.remove(&args[0]) {
                        Some(v) => Ok(v),
                        None => args
                            .get(1)
                            .cloned()
                            .ok_or_else(|| Error::python(format!("KeyError: {}", format::repr(&args[0])))),
                    }
                }
                "setdefault" => {
                    arity(name, &args, 1, 2)?;
                    if let Some(v) = dd.get(&args[0]) {
                        return Ok(v.clone());
                    }
                    let v = args.get(1).cloned().unwrap_or(Value::None);
                    ops::check_hashable(&args[0])?;
                    dd.set(args[0].clone(), v.clone());
                    Ok(v)
                }
                "copy" => Ok(Value::dict(dd.clone())),
                "clear" => {
                    dd.items.clear();
                    Ok(Value::None)
                }
                _ => unreachable!(),
            }
        }
        Value::Float(f) if name == "is_integer" => Ok(Value::Bool(f.fract() == 0.0)),
        v => Err(Error::python(format!("'{}' has no method '{name}'", v.type_name()))),
    }
}

fn seq_method(v: &[Value], name: &str, args: &[Value]) -> Result<Value> {
    arity(name, args, 1, 1)?;
    match name {
        "count" => Ok(Value::Int(v.iter().filter(|x| py_eq(x, &args[0])).count() as i64)),
        _ => v
            .iter()
            .position(|x| py_eq(x, &args[0]))
            .map(|p| Value::Int(p as i64))
            .ok_or_else(|| Error::python(format!("ValueError: {} is not in list", format::repr(&args[0])))),
    }
}

fn str_method(s: &str, name: &str, args: &[Value]) -> Result<Value> {
    let sarg = |i: usize| -> Result<String> {
        args.get(i)
            .and_then(|v| v.as_str().map(str::to_string))
            .ok_or_else(|| Error::python(format!("TypeError: str.{name}() argument must be str")))
    };
    let strs = |v: Vec<&str>| Value::list(v.into_iter().map(Value::str).collect());
    Ok(match name {
        "upper" => Value::str(&s.to_uppercase()),
        "lower" => Value::str(&s.to_lowercase()),
        "title" => Value::str(
            &s.split(' ')
                .map(|w| {
                    let mut c = w.chars();
                    match c.next() {
                        Some(f) => f.to_uppercase().collect::<String>() + &c.as_str().to_lowercase(),
                        None => String::new(),
                    }
                })
                .collect::<Vec<_>>()
                .join(" "),
        ),
        "capitalize" => {
            let mut c = s.chars();
            Value::str(&match c.next() {
                Some(f) => f.to_uppercase().collect::<String>() + &c.as_str().to_lowercase(),
                None => String::new(),
            })
        }
        "strip" | "lstrip" | "rstrip" => {
            let set: Option<String> = args.first().and_then(|a| a.as_str().map(str::to_string));
            let pat = |c: char| match &set {
                Some(p) => p.contains(c),
                None => c.is_whitespace(),
            };
            Value::str(match name {
                "strip" => s.trim_matches(pat),
                "lstrip" => s.trim_start_matches(pat),
                _ => s.trim_end_matches(pat),
            })
        }
        "split" | "rsplit" => {
            let maxsplit = args.get(1).and_then(|v| v.as_int()).unwrap_or(-1);
            match args.first() {
                None | Some(Value::None) => {
                    let parts: Vec<&str> = s.split_whitespace().collect();
                    if maxsplit >= 0 && (maxsplit as usize) < parts.len() {
                        // Rare; keep Python's behaviour approximately by rejoining the tail.
                        let (head, tail) = parts.split_at(maxsplit as usize);
                        let mut v: Vec<String> = head.iter().map(|x| x.to_string()).collect();
                        v.push(tail.join(" "));
                        Value::list(v.iter().map(|x| Value::str(x)).collect())
                    } else {
                        strs(parts)
                    }
                }
                Some(_) => {
                    let sep = sarg(0)?;
                    if sep.is_empty() {
                        return Err(Error::python("ValueError: empty separator"));
                    }
                    if maxsplit >= 0 {
                        if name == "split" {
                            strs(s.splitn(maxsplit as usize + 1, sep.as_str()).collect())
                        } else {
                            let mut v: Vec<&str> = s.rsplitn(maxsplit as usize + 1, sep.as_str()).collect();
                            v.reverse();
                            strs(v)
                        }
                    } else {
                        strs(s.split(sep.as_str()).collect())
                    }
                }
            }
        }
        "splitlines" => strs(s.lines().collect()),
        "join" => {
            arity(name, args, 1, 1)?;
            let items = args[0].iter_items()?;
            let mut parts = Vec::new();
            for i in items {
                match i {
                    Value::Str(x) => parts.push(x.to_string()),
                    v => {
                        return Err(Error::python(format!(
                            "TypeError: sequence item: expected str instance, {} found",
                            v.type_name()
                        )))
                    }
                }
            }
            Value::str(&parts.join(s))
        }
        "replace" => {
            arity(name, args, 2, 3)?;
            let (a, b) = (sarg(0)?, sarg(1)?);
            match args.get(2).and_then(|v| v.as_int()) {
                Some(n) if n >= 0 => Value::str(&s.replacen(a.as_str(), &b, n as usize)),
                _ => Value::str(&s.replace(a.as_str(), &b)),
            }
        }
        "startswith" | "endswith" => {
            arity(name, args, 1, 1)?;
            let cands: Vec<String> = match &args[0] {
                Value::Tuple(t) => t.iter().filter_map(|v| v.as_str().map(str::to_string)).collect(),
                _ => vec![sarg(0)?],
            };
            Value::Bool(cands.iter().any(|c| {
                if name == "startswith" {
                    s.starts_with(c.as_str())
                } else {
                    s.ends_with(c.as_str())
                }
            }))
        }
        "find" | "rfind" | "index" => {
            arity(name, args, 1, 1)?;
            let sub = sarg(0)?;
            let pos = if name == "rfind" { s.rfind(sub.as_str()) } else { s.find(sub.as_str()) };
            match pos {
                Some(p) => Value::Int(s[..p].chars().count() as i64),
                None if name == "index" => return Err(Error::python("ValueError: substring not found")),
                None => Value::Int(-1),
            }
        }
        "count" => {
            arity(name, args, 1, 1)?;
            let sub = sarg(0)?;
            Value::Int(if sub.is_empty() {
                s.chars().count() as i64 + 1
            } else {
                s.matches(sub.as_str()).count() as i64
            })
        }
        "ljust" | "rjust" | "center" => {
            arity(name, args, 1, 2)?;
            let w = width_arg(name, &args[0])?;
            let fill = match args.get(1) {
                None => ' ',
                Some(Value::Str(f)) => {
                    let mut cs = f.chars();
                    match (cs.next(), cs.next()) {
                        (Some(c), None) => c,
                        _ => {
                            return Err(Error::python(
                                "TypeError: The fill character must be exactly one character long",
                            ))
                        }
                    }
                }
                Some(f) => {
                    return Err(Error::python(format!(
                        "TypeError: The fill character must be a unicode character, not {}",
                        f.type_name()
                    )))
                }
            };
            let n = s.chars().count();
            if n >= w {
                Value::str(s)
            } else {
                let p = w - n;
                let f = |k: usize| fill.to_string().repeat(k);
                Value::str(&match name {
                    "ljust" => format!("{s}{}", f(p)),
                    "rjust" => format!("{}{s}", f(p)),
                    _ => {
                        let left = p / 2 + (p & w & 1);
                        format!("{}{s}{}", f(left), f(p - left))
                    }
                })
            }
        }
        "zfill" => {
            arity(name, args, 1, 1)?;
            let w = width_arg(name, &args[0])?;
            let n = s.chars().count();
            if n >= w {
                Value::str(s)
            } else if let Some(rest) = s.strip_prefix(['-', '+']) {
                Value::str(&format!("{}{}{}", &s[..1], "0".repeat(w - n), rest))
            } else {
                Value::str(&format!("{}{s}", "0".repeat(w - n)))
            }
        }
        "isdigit" => Value::Bool(!s.is_empty() && s.chars().all(|c| c.is_ascii_digit())),
        "isalpha" => Value::Bool(!s.is_empty() && s.chars().all(char::is_alphabetic)),
        _ => unreachable!("str.{name}"),
    })
}

/// `str.format`.
pub fn str_format(fmt: &str, args: &[Value], kw: &[(String, Value)]) -> Result<String> {
    let mut numbering = Numbering { auto: 0, manual: None };
    str_format_nested(fmt, args, kw, &mut numbering, 2)
}

/// The field numbering of one `str.format` call, shared by the fields nested in specs (`'{:{}}'`).
struct Numbering {
    auto: usize,
    /// Automatic ({}) or manual ({0}) numbering, which may not be mixed.
    manual: Option<bool>,
}

/// `str.format` of `fmt` with `depth` levels of nesting left (CPython allows one field in a spec).
fn str_format_nested(
    fmt: &str,
    args: &[Value],
    kw: &[(String, Value)],
    numbering: &mut Numbering,
    depth: usize,
) -> Result<String> {
    if depth == 0 {
        return Err(Error::python("ValueError: Max string recursion exceeded"));
    }
    let c: Vec<char> = fmt.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch == '{' && c.get(i + 1) == Some(&'{') {
            out.push('{');
            i += 2;
            continue;
        }
        if ch == '}' {
            if c.get(i + 1) != Some(&'}') {
                return Err(Error::python("ValueError: Single '}' encountered in format string"));
            }
            out.push('}');
            i += 2;
            continue;
        }
        if ch != '{' {
            out.push(ch);
            i += 1;
            continue;
        }
        let mut j = i + 1;
        let mut open = 0usize;
        while j < c.len() && !(c[j] == '}' && open == 0) {
            if c[j] == '{' {
                open += 1;
            } else if c[j] == '}' {
                open -= 1;
            }
            j += 1;
        }
        if j >= c.len() {
            return Err(Error::python(if open > 0 {
                "ValueError: unmatched '{' in format spec"
            } else {
                "ValueError: Single '{' encountered in format string"
            }));
        }
        let field: String = c[i + 1..j].iter().collect();
        i = j + 1;
        let (name_conv, spec) = match field.find(':') {
            Some(p) => (field[..p].to_string(), field[p + 1..].to_string()),
            None => (field.clone(), String::new()),
        };
        let (fname, conv) = match name_conv.find('!') {
            Some(p) => {
                let mut cs = name_conv[p + 1..].chars();
                let conv = cs.next().ok_or_else(|| Error::python("ValueError: unmatched '{' in format spec"))?;
                if cs.next().is_some() {
                    return Err(Error::python("ValueError: expected ':' after conversion specifier"));
                }
                (name_conv[..p].to_string(), Some(conv))
            }
            None => (name_conv, None),
        };
        let (head, rest) = match fname.find(['.', '[']) {
            Some(p) => (&fname[..p], &fname[p..]),
            None => (fname.as_str(), ""),
        };
        let index = if !head.is_empty() && head.chars().all(|c| c.is_ascii_digit()) {
            Some(
                head.parse::<usize>()
                    .map_err(|_| Error::python("ValueError: Too many decimal digits in format string"))?,
            )
        } else {
            None
        };
        let manual = if head.is_empty() { Some(false) } else { index.map(|_| true) };
        match (manual, numbering.manual) {
            (Some(a), Some(m)) if a != m => {
                return Err(Error::python("ValueError: cannot switch between automatic and manual field numbering"))
            }
            (Some(a), _) => numbering.manual = Some(a),
            _ => {}
        }
        let mut v = if head.is_empty() {
            let n = numbering.auto;
            numbering.auto += 1;
            args.get(n).cloned().ok_or_else(|| {
                Error::python(format!("IndexError: Replacement index {n} out of range for positional args tuple"))
            })?
        } else if let Some(n) = index {
            args.get(n).cloned().ok_or_else(|| {
                Error::python(format!("IndexError: Replacement index {n} out of range for positional args tuple"))
            })?
        } else {
            kwarg(kw, head).cloned().ok_or_else(|| Error::python(format!("KeyError: {}", format::str_repr(head))))?
        };
        let mut r = rest;
        while let Some(stripped) = r.strip_prefix('[') {
            let end = stripped.find(']').ok_or_else(|| Error::python("ValueError: Missing ']' in format string"))?;
            let key = &stripped[..end];
            let k = match key.parse::<i64>() {
                Ok(n) => Value::Int(n),
                Err(_) => Value::str(key),
            };
            v = ops::get_item(&v, &k)?;
            r = &stripped[end + 1..];
        }
        if !r.is_empty() {
            return Err(Error::python(format!("attribute access '{r}' in format fields is not supported")));
        }
        // Nested replacement fields in the spec ("{:{w}}"), numbered after the field's own.
        let spec =
            if spec.contains(['{', '}']) { str_format_nested(&spec, args, kw, numbering, depth - 1)? } else { spec };
        let v = match conv {
            None => v,
            Some('r') => Value::str(&format::repr(&v)),
            Some('s') => Value::str(&to_str(&v)),
            Some('a') => Value::str(&crate::text::ascii(&format::repr(&v))),
            Some(c) => return Err(Error::python(format!("ValueError: Unknown conversion specifier {c}"))),
        };
        out.push_str(&format::format_value(&v, &spec)?);
    }
    Ok(out)
}
