//! The subset of numpy that command files use: 1-D and 2-D arrays of floats (and of integers and
//! booleans, as numpy types the results of `arange(3)` or `a > 0`), element-wise arithmetic and
//! comparisons with broadcasting, indexing and slicing, and the functions the corpus calls (creation,
//! element-wise math, reductions, a few of linear algebra, `interp`, `where`, `allclose`, ...).
//!
//! What lies outside stops by name (`numpy.fft: ... is not supported`). Two differences from numpy are
//! deliberate and documented: a slice is a copy, not a view of the array it was taken from, and the
//! elements of an array are Python `int`, `float` and `bool` values.

use super::value::{scalar, Array, ArrayRef, Builtin, DType, Value};
use crate::diag::{Error, Result};
use crate::text::float_repr;

fn err(msg: impl Into<String>) -> Error {
    Error::python(msg.into())
}

fn unsupported(what: &str) -> Error {
    Error::unsupported(format!("{what}: this part of numpy is not supported by aster-rs"))
}

// ------------------------------------------------------------------ conversion

/// Python data (a number, a nested list or tuple of numbers, an array) as an array.
pub fn to_array(v: &Value) -> Result<Array> {
    match v {
        Value::Array(a) => Ok(a.borrow().clone()),
        Value::Bool(b) => Ok(Array::new(vec![], vec![*b as i64 as f64], DType::Bool)),
        Value::Int(i) => Ok(Array::new(vec![], vec![*i as f64], DType::Int)),
        Value::Float(f) => Ok(Array::new(vec![], vec![*f], DType::Float)),
        Value::Complex(..) => Err(unsupported("complex arrays")),
        Value::List(_) | Value::Tuple(_) => {
            let items = v.iter_items()?;
            if items.is_empty() {
                return Ok(Array::vector(Vec::new(), DType::Float));
            }
            let parts: Vec<Array> = items.iter().map(to_array).collect::<Result<_>>()?;
            let inner = parts[0].dims.clone();
            if parts.iter().any(|p| p.dims != inner) {
                return Err(err("ValueError: setting an array element with a sequence: the rows differ in length"));
            }
            if inner.len() > 1 {
                return Err(unsupported("arrays of more than 2 dimensions"));
            }
            let dtype = parts.iter().map(|p| p.dtype).max().unwrap();
            let mut dims = vec![parts.len()];
            dims.extend(&inner);
            Ok(Array::new(dims, parts.into_iter().flat_map(|p| p.data).collect(), dtype))
        }
        other => Err(err(format!("TypeError: cannot make an array of {}", other.type_name()))),
    }
}

/// An array of at least one dimension (a scalar becomes `[x]`).
fn to_array_1d(v: &Value) -> Result<Array> {
    let mut a = to_array(v)?;
    if a.dims.is_empty() {
        a.dims = vec![1];
    }
    Ok(a)
}

fn as_f64(v: &Value, what: &str) -> Result<f64> {
    v.as_f64().ok_or_else(|| err(format!("TypeError: {what} expects a number, got {}", v.type_name())))
}

fn as_usize(v: &Value, what: &str) -> Result<usize> {
    match v.as_int() {
        Some(i) if i >= 0 => Ok(i as usize),
        _ => match v {
            Value::Float(f) if *f >= 0.0 && f.fract() == 0.0 => Ok(*f as usize),
            _ => Err(err(format!("TypeError: {what} expects a non-negative integer, got {}", v.type_name()))),
        },
    }
}

/// A shape argument: `n` or `(n,)` or `(n, m)`.
fn shape_arg(v: &Value) -> Result<Vec<usize>> {
    match v {
        Value::Tuple(_) | Value::List(_) => {
            let d: Vec<usize> = v.iter_items()?.iter().map(|x| as_usize(x, "shape")).collect::<Result<_>>()?;
            if d.is_empty() || d.len() > 2 {
                return Err(unsupported("arrays of other than 1 or 2 dimensions"));
            }
            Ok(d)
        }
        v => Ok(vec![as_usize(v, "shape")?]),
    }
}

/// The value of a 0-d result, or the array.
fn result(a: Array) -> Value {
    if a.dims.is_empty() {
        a.scalar(a.data[0])
    } else {
        a.value()
    }
}

// ------------------------------------------------------------------ element-wise operations

/// The shape two operands broadcast to (numpy's rules, for up to 2 dimensions).
fn broadcast(a: &[usize], b: &[usize]) -> Result<Vec<usize>> {
    let n = a.len().max(b.len());
    let pad = |d: &[usize]| -> Vec<usize> {
        let mut v = vec![1; n - d.len()];
        v.extend(d);
        v
    };
    let (pa, pb) = (pad(a), pad(b));
    pa.iter()
        .zip(&pb)
        .map(|(&x, &y)| match (x, y) {
            (x, y) if x == y => Ok(x),
            (1, y) => Ok(y),
            (x, 1) => Ok(x),
            _ => Err(err(format!("ValueError: operands could not be broadcast together with shapes {a:?} {b:?}"))),
        })
        .collect()
}

/// The element of `a` at `index` of the broadcast shape `dims`.
fn at(a: &Array, dims: &[usize], index: &[usize]) -> f64 {
    let off = dims.len() - a.dims.len();
    let mut flat = 0;
    for (k, &d) in a.dims.iter().enumerate() {
        let i = if d == 1 { 0 } else { index[k + off] };
        flat = flat * d + i;
    }
    a.data[flat]
}

fn indices(dims: &[usize]) -> Vec<Vec<usize>> {
    match dims.len() {
        0 => vec![vec![]],
        1 => (0..dims[0]).map(|i| vec![i]).collect(),
        _ => (0..dims[0]).flat_map(|i| (0..dims[1]).map(move |j| vec![i, j])).collect(),
    }
}

fn zip_with(a: &Array, b: &Array, dtype: DType, f: impl Fn(f64, f64) -> f64) -> Result<Array> {
    let dims = broadcast(&a.dims, &b.dims)?;
    let data = indices(&dims).iter().map(|ix| f(at(a, &dims, ix), at(b, &dims, ix))).collect();
    Ok(Array::new(dims, data, dtype))
}

/// `a OP b` where one side at least is an array.
pub fn binop(op: crate::syntax::ast::BinOp, a: &Value, b: &Value) -> Result<Value> {
    use crate::syntax::ast::BinOp::*;
    let (x, y) = (to_array(a)?, to_array(b)?);
    let num = x.dtype.max(y.dtype).max(DType::Int);
    let r = match op {
        Add => zip_with(&x, &y, num, |p, q| p + q)?,
        Sub => zip_with(&x, &y, num, |p, q| p - q)?,
        Mul => zip_with(&x, &y, num, |p, q| p * q)?,
        Div => zip_with(&x, &y, DType::Float, |p, q| p / q)?,
        FloorDiv => zip_with(&x, &y, num, |p, q| (p / q).floor())?,
        Mod => zip_with(&x, &y, num, |p, q| {
            let r = p % q;
            if r != 0.0 && (r < 0.0) != (q < 0.0) {
                r + q
            } else {
                r
            }
        })?,
        BitAnd | BitOr | BitXor | LShift | RShift => {
            let dtype = x.dtype.max(y.dtype);
            if dtype == DType::Float || (dtype == DType::Bool && matches!(op, LShift | RShift)) {
                return Err(err(format!(
                    "TypeError: ufunc '{}' not supported for the input types",
                    match op {
                        BitAnd => "bitwise_and",
                        BitOr => "bitwise_or",
                        BitXor => "bitwise_xor",
                        LShift => "left_shift",
                        _ => "right_shift",
                    }
                )));
            }
            let f: fn(i64, i64) -> i64 = match op {
                BitAnd => |p, q| p & q,
                BitOr => |p, q| p | q,
                BitXor => |p, q| p ^ q,
                LShift => |p, q| p.checked_shl(q as u32).unwrap_or(0),
                _ => |p, q| p.checked_shr(q as u32).unwrap_or(if p < 0 { -1 } else { 0 }),
            };
            zip_with(&x, &y, dtype, |p, q| f(p as i64, q as i64) as f64)?
        }
        Pow => {
            if num == DType::Int && y.data.iter().any(|q| *q < 0.0) {
                return Err(err("ValueError: Integers to negative integer powers are not allowed."));
            }
            zip_with(&x, &y, num, f64::powf)?
        }
    };
    Ok(result(r))
}

/// `a CMP b` element-wise: a boolean array.
pub fn compare(op: crate::syntax::ast::CmpOp, a: &Value, b: &Value) -> Result<Value> {
    use crate::syntax::ast::CmpOp::*;
    let (x, y) = (to_array(a)?, to_array(b)?);
    let f: fn(f64, f64) -> bool = match op {
        Eq => |p, q| p == q,
        Ne => |p, q| p != q,
        Lt => |p, q| p < q,
        Le => |p, q| p <= q,
        Gt => |p, q| p > q,
        Ge => |p, q| p >= q,
        _ => return Err(unsupported("this comparison of arrays")),
    };
    Ok(result(zip_with(&x, &y, DType::Bool, |p, q| f(p, q) as i64 as f64)?))
}

pub fn negate(a: &Array) -> Result<Value> {
    if a.dtype == DType::Bool {
        return Err(err("TypeError: The numpy boolean negative, the `-` operator, is not supported, use the `~` operator or the logical_not function instead."));
    }
    Ok(Array::new(a.dims.clone(), a.data.iter().map(|x| -x).collect(), a.dtype).value())
}

/// `~a` of a boolean array.
pub fn invert(a: &Array) -> Result<Value> {
    match a.dtype {
        DType::Bool => {
            Ok(Array::new(a.dims.clone(), a.data.iter().map(|x| (*x == 0.0) as i64 as f64).collect(), DType::Bool)
                .value())
        }
        DType::Int => {
            Ok(Array::new(a.dims.clone(), a.data.iter().map(|x| !(*x as i64) as f64).collect(), DType::Int).value())
        }
        DType::Float => Err(err("TypeError: ufunc 'invert' not supported for the input types")),
    }
}

fn map(a: &Array, dtype: DType, f: impl Fn(f64) -> f64) -> Array {
    Array::new(a.dims.clone(), a.data.iter().map(|x| f(*x)).collect(), dtype)
}

// ------------------------------------------------------------------ indexing

/// One index of a subscript: an integer, a slice, or a list of integers / a boolean mask.
enum Ix {
    One(usize),
    Range(Vec<usize>),
}

fn norm(i: i64, len: usize, axis: usize) -> Result<usize> {
    let j = if i < 0 { i + len as i64 } else { i };
    if j < 0 || j >= len as i64 {
        return Err(err(format!("IndexError: index {i} is out of bounds for axis {axis} with size {len}")));
    }
    Ok(j as usize)
}

fn one_index(v: &Value, len: usize, axis: usize) -> Result<Ix> {
    if let Some((a, b, c)) = super::value::as_slice(v) {
        return Ok(Ix::Range(super::value::slice_indices(len, &a, &b, &c)?));
    }
    if let Some(i) = v.as_int().filter(|_| !matches!(v, Value::Bool(_))) {
        return Ok(Ix::One(norm(i, len, axis)?));
    }
    match v {
        Value::List(_) | Value::Array(_) => {
            let a = to_array(v)?;
            if a.dtype == DType::Bool {
                if a.size() != len {
                    return Err(err(format!(
                        "IndexError: boolean index did not match indexed array along axis {axis}; size of axis is {len} but size of corresponding boolean axis is {}",
                        a.size()
                    )));
                }
                return Ok(Ix::Range(a.data.iter().enumerate().filter(|(_, x)| **x != 0.0).map(|(i, _)| i).collect()));
            }
            if a.dtype == DType::Float {
                return Err(err("IndexError: arrays used as indices must be of integer (or boolean) type"));
            }
            Ok(Ix::Range(a.data.iter().map(|x| norm(*x as i64, len, axis)).collect::<Result<_>>()?))
        }
        _ => Err(err(
            "IndexError: only integers, slices (`:`), ellipsis (`...`), numpy.newaxis (`None`) and integer or boolean arrays are valid indices",
        )),
    }
}

/// The indices selected along each axis (a 2-D boolean mask selects flat elements).
fn resolve(a: &Array, idx: &Value) -> Result<Vec<Ix>> {
    if let Value::Array(m) = idx {
        let m = m.borrow();
        if m.dtype == DType::Bool && m.ndim() == 2 && a.ndim() == 2 {
            if m.dims != a.dims {
                return Err(err("IndexError: boolean index did not match the indexed array"));
            }
            return Err(unsupported("a 2-D boolean mask"));
        }
    }
    let parts: Vec<Value> = match idx {
        Value::Tuple(t) if super::value::as_slice(idx).is_none() => t.as_ref().clone(),
        v => vec![v.clone()],
    };
    if parts.len() > a.ndim() {
        return Err(err(format!(
            "IndexError: too many indices for array: array is {}-dimensional, but {} were indexed",
            a.ndim(),
            parts.len()
        )));
    }
    let mut out = Vec::new();
    for (k, p) in parts.iter().enumerate() {
        out.push(one_index(p, a.dims[k], k)?);
    }
    for k in parts.len()..a.ndim() {
        out.push(Ix::Range((0..a.dims[k]).collect()));
    }
    if out.iter().filter(|i| matches!(i, Ix::Range(_))).count() == 2 {
        if let (Some(Value::List(_) | Value::Array(_)), Some(Value::List(_) | Value::Array(_))) =
            (parts.first(), parts.get(1))
        {
            return Err(unsupported("indexing with two integer arrays"));
        }
    }
    Ok(out)
}

/// `a[idx]`.
pub fn get_item(a: &Array, idx: &Value) -> Result<Value> {
    let ix = resolve(a, idx)?;
    let flat = |i: usize, j: usize| if a.ndim() == 2 { i * a.dims[1] + j } else { i };
    match ix.as_slice() {
        [Ix::One(i)] => Ok(a.scalar(a.data[*i])),
        [Ix::Range(r)] => Ok(Array::vector(r.iter().map(|i| a.data[*i]).collect(), a.dtype).value()),
        [Ix::One(i), Ix::One(j)] => Ok(a.scalar(a.data[flat(*i, *j)])),
        [Ix::One(i), Ix::Range(c)] => {
            Ok(Array::vector(c.iter().map(|j| a.data[flat(*i, *j)]).collect(), a.dtype).value())
        }
        [Ix::Range(r), Ix::One(j)] => {
            Ok(Array::vector(r.iter().map(|i| a.data[flat(*i, *j)]).collect(), a.dtype).value())
        }
        [Ix::Range(r), Ix::Range(c)] => {
            if a.ndim() == 1 {
                unreachable!("two indices on a 1-D array are refused by resolve")
            }
            let data = r.iter().flat_map(|i| c.iter().map(move |j| flat(*i, *j))).map(|k| a.data[k]).collect();
            Ok(Array::new(vec![r.len(), c.len()], data, a.dtype).value())
        }
        _ => unreachable!("at most two indices"),
    }
}

/// `a[idx] = v` (v broadcast to the selection).
pub fn set_item(a: &mut Array, idx: &Value, v: &Value) -> Result<()> {
    let ix = resolve(a, idx)?;
    let two = a.ndim() == 2;
    let width = if two { a.dims[1] } else { 1 };
    let pos = |i: usize, j: usize| if two { i * width + j } else { i };
    let (targets, sel_dims): (Vec<usize>, Vec<usize>) = match ix.as_slice() {
        [Ix::One(i)] if two => ((0..width).map(|j| pos(*i, j)).collect(), vec![width]),
        [Ix::One(i)] => (vec![*i], vec![]),
        [Ix::Range(r)] if !two => (r.clone(), vec![r.len()]),
        [Ix::One(i), Ix::One(j)] => (vec![pos(*i, *j)], vec![]),
        [Ix::One(i), Ix::Range(c)] => (c.iter().map(|j| pos(*i, *j)).collect(), vec![c.len()]),
        [Ix::Range(r), Ix::One(j)] => (r.iter().map(|i| pos(*i, *j)).collect(), vec![r.len()]),
        [Ix::Range(r), Ix::Range(c)] => (
            r.iter().flat_map(|i| c.iter().map(move |j| (*i, *j))).map(|(i, j)| pos(i, j)).collect(),
            vec![r.len(), c.len()],
        ),
        [Ix::Range(r)] => (
            r.iter().flat_map(|i| (0..width).map(move |j| (*i, j))).map(|(i, j)| pos(i, j)).collect(),
            vec![r.len(), width],
        ),
        _ => unreachable!("at most two indices"),
    };
    let src = to_array(v)?;
    let dims = broadcast(&sel_dims, &src.dims)?;
    if dims != sel_dims {
        return Err(err(format!(
            "ValueError: could not broadcast input array from shape {:?} into shape {sel_dims:?}",
            src.dims
        )));
    }
    let values: Vec<f64> = indices(&sel_dims).iter().map(|ix| at(&src, &sel_dims, ix)).collect();
    for (t, x) in targets.iter().zip(values) {
        a.data[*t] = match a.dtype {
            DType::Int => x.trunc(),
            DType::Bool => (x != 0.0) as i64 as f64,
            DType::Float => x,
        };
    }
    Ok(())
}

// ------------------------------------------------------------------ text

/// numpy's text of a float in an array: the shortest text that reads back, cut to 8 decimals.
fn float_text(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let s = float_repr(x);
    let s = if s.contains('e') {
        s
    } else {
        match s.split_once('.') {
            Some((_, f)) if f.len() > 8 => {
                let t = format!("{x:.8}");
                t.trim_end_matches('0').to_string()
            }
            _ => s,
        }
    };
    if let Some(t) = s.strip_suffix(".0") {
        return format!("{t}.");
    }
    s
}

fn exp_text(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return float_text(x);
    }
    let s = format!("{x:.digits$e}");
    let (m, e) = s.split_once('e').unwrap();
    let m = if m.contains('.') { m.trim_end_matches('0').to_string() } else { m.to_string() };
    let m = if m.ends_with('.') || m.contains('.') { m } else { format!("{m}.") };
    let e: i32 = e.parse().unwrap();
    format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// The texts of the elements, padded to a common width as numpy pads them.
fn element_texts(a: &Array) -> Vec<String> {
    match a.dtype {
        DType::Bool => {
            a.data.iter().map(|x| if *x != 0.0 { " True".to_string() } else { "False".to_string() }).collect()
        }
        DType::Int => {
            let t: Vec<String> = a.data.iter().map(|x| (*x as i64).to_string()).collect();
            let w = t.iter().map(String::len).max().unwrap_or(0);
            t.into_iter().map(|s| format!("{s:>w$}")).collect()
        }
        DType::Float => {
            let finite: Vec<f64> = a.data.iter().copied().filter(|x| x.is_finite()).map(f64::abs).collect();
            let max = finite.iter().copied().fold(0.0, f64::max);
            let min_nz = finite.iter().copied().filter(|x| *x != 0.0).fold(f64::INFINITY, f64::min);
            let exp = max >= 1e8 || (min_nz < 1e-4 && min_nz.is_finite()) || (min_nz.is_finite() && max / min_nz > 1e3);
            let texts: Vec<String> = if exp {
                let digits = a
                    .data
                    .iter()
                    .filter(|x| x.is_finite())
                    .map(|x| {
                        let s = format!("{:e}", x);
                        let m = s.split_once('e').unwrap().0;
                        m.split_once('.').map(|(_, f)| f.len()).unwrap_or(0).min(8)
                    })
                    .max()
                    .unwrap_or(0);
                a.data.iter().map(|x| exp_text(*x, digits)).collect()
            } else {
                a.data.iter().map(|x| float_text(*x)).collect()
            };
            // Align on the decimal point: pad the integer part on the left, the fraction on the right.
            let split = |s: &str| -> (String, String) {
                match s.find(['.', 'e']) {
                    Some(i) if !s.starts_with('n') && !s.contains("inf") => (s[..i].to_string(), s[i..].to_string()),
                    _ => (s.to_string(), String::new()),
                }
            };
            let parts: Vec<(String, String)> = texts.iter().map(|s| split(s)).collect();
            let wl = parts.iter().map(|(l, _)| l.len()).max().unwrap_or(0);
            let wr = parts.iter().map(|(_, r)| r.len()).max().unwrap_or(0);
            parts.into_iter().map(|(l, r)| format!("{l:>wl$}{r:<wr$}")).collect()
        }
    }
}

/// `str(a)` or `repr(a)` as numpy writes them (line width 75).
pub fn text(a: &Array, repr: bool) -> String {
    let t = element_texts(a);
    let (open, sep, indent) = if repr { ("array(", ", ", 6) } else { ("", " ", 0) };
    let row = |items: &[String], lead: usize| -> String {
        // numpy wraps a row at 75 characters, the continuation aligned after the bracket.
        let mut lines = vec![String::new()];
        let pad = " ".repeat(lead);
        for (k, s) in items.iter().enumerate() {
            let piece = if k + 1 < items.len() { format!("{s}{}", sep.trim_end()) } else { s.clone() };
            let cur = lines.last_mut().unwrap();
            let extra = if cur.is_empty() { 0 } else { 1 };
            if !cur.is_empty() && lead + cur.len() + extra + piece.len() + 1 > 75 {
                lines.push(piece);
            } else {
                if !cur.is_empty() {
                    cur.push(' ');
                }
                cur.push_str(&piece);
            }
        }
        lines.join(&format!("\n{pad}"))
    };
    let body = if a.ndim() == 1 {
        format!("[{}]", row(&t, indent + 1))
    } else {
        let c = a.cols();
        let rows: Vec<String> =
            (0..a.rows()).map(|i| format!("[{}]", row(&t[i * c..(i + 1) * c], indent + 2))).collect();
        let joiner = if repr { format!(",\n{}", " ".repeat(indent + 1)) } else { "\n ".to_string() };
        format!("[{}]", rows.join(&joiner))
    };
    if !repr {
        return body;
    }
    let empty_dtype = if a.size() == 0 { ", dtype=float64" } else { "" };
    format!("{open}{body}{empty_dtype})")
}

// ------------------------------------------------------------------ the module

macro_rules! names {
    ($($n:literal),* $(,)?) => { (&[$($n),*], &[$(concat!("numpy.", $n)),*]) };
}
/// The names of numpy we provide (`np.NAME`) and their qualified names, in the same order.
const NAMES: (&[&str], &[&str]) = names![
    "array",
    "asarray",
    "zeros",
    "ones",
    "full",
    "empty",
    "zeros_like",
    "ones_like",
    "linspace",
    "arange",
    "logspace",
    "eye",
    "identity",
    "diag",
    "copy",
    "abs",
    "absolute",
    "fabs",
    "sign",
    "sqrt",
    "square",
    "exp",
    "log",
    "log10",
    "sin",
    "cos",
    "tan",
    "arcsin",
    "arccos",
    "arctan",
    "arctan2",
    "sinh",
    "cosh",
    "tanh",
    "floor",
    "ceil",
    "around",
    "round",
    "real",
    "imag",
    "isnan",
    "isinf",
    "isfinite",
    "minimum",
    "maximum",
    "power",
    "degrees",
    "radians",
    "deg2rad",
    "rad2deg",
    "sum",
    "max",
    "amax",
    "min",
    "amin",
    "mean",
    "std",
    "median",
    "prod",
    "argmax",
    "argmin",
    "any",
    "all",
    "cumsum",
    "diff",
    "dot",
    "outer",
    "cross",
    "transpose",
    "reshape",
    "ravel",
    "concatenate",
    "vstack",
    "hstack",
    "append",
    "shape",
    "size",
    "ndim",
    "interp",
    "allclose",
    "isclose",
    "where",
    "trapz",
    "sort",
    "nonzero",
    "count_nonzero",
];
const FUNCS: &[&str] = NAMES.0;
const QUALIFIED: &[&str] = NAMES.1;

const LINALG: &[&str] = &["norm", "solve", "inv", "det"];
const LINALG_QUALIFIED: &[&str] = &["numpy.linalg.norm", "numpy.linalg.solve", "numpy.linalg.inv", "numpy.linalg.det"];

/// `numpy.NAME` / `numpy.linalg.NAME`.
pub fn get_attr(module: &str, name: &str) -> Result<Value> {
    if module == "numpy.linalg" {
        return match LINALG.iter().position(|n| *n == name) {
            Some(i) => Ok(Value::Builtin(Builtin(LINALG_QUALIFIED[i]))),
            None => Err(unsupported(&format!("numpy.linalg.{name}"))),
        };
    }
    if let Some(i) = FUNCS.iter().position(|n| *n == name) {
        return Ok(Value::Builtin(Builtin(QUALIFIED[i])));
    }
    Ok(match name {
        "pi" => Value::Float(std::f64::consts::PI),
        "e" => Value::Float(std::f64::consts::E),
        "inf" | "Inf" | "infty" => Value::Float(f64::INFINITY),
        "nan" | "NaN" => Value::Float(f64::NAN),
        "linalg" => Value::Module("numpy.linalg"),
        // The scalar types: Python's own.
        "float" | "float64" | "float_" | "double" => Value::Builtin(Builtin("float")),
        "int" | "int64" | "int_" | "int32" => Value::Builtin(Builtin("int")),
        "bool" | "bool_" => Value::Builtin(Builtin("bool")),
        "ndarray" => Value::Builtin(Builtin("numpy.ndarray")),
        _ => return Err(unsupported(&format!("numpy.{name}"))),
    })
}

/// `from numpy import *`.
pub fn star() -> Vec<(String, Value)> {
    let mut v: Vec<(String, Value)> =
        FUNCS.iter().zip(QUALIFIED).map(|(n, q)| (n.to_string(), Value::Builtin(Builtin(q)))).collect();
    for n in ["pi", "e", "inf", "nan", "linalg"] {
        v.push((n.to_string(), get_attr("numpy", n).unwrap()));
    }
    v
}

fn kwarg<'a>(kw: &'a [(String, Value)], name: &str) -> Option<&'a Value> {
    kw.iter().find(|(k, _)| k == name).map(|(_, v)| v).filter(|v| !matches!(v, Value::None))
}

fn check_kw(f: &str, kw: &[(String, Value)], allowed: &[&str]) -> Result<()> {
    match kw.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
        Some((k, _)) => Err(unsupported(&format!("numpy.{f}(..., {k}=...)"))),
        None => Ok(()),
    }
}

fn arg<'a>(f: &str, args: &'a [Value], i: usize) -> Result<&'a Value> {
    args.get(i).ok_or_else(|| err(format!("TypeError: {f}() missing required argument {}", i + 1)))
}

/// The `axis` argument: None, 0 or 1 (negative counted from the end).
fn axis_arg(f: &str, args: &[Value], pos: usize, kw: &[(String, Value)], ndim: usize) -> Result<Option<usize>> {
    let v = kwarg(kw, "axis").or_else(|| args.get(pos).filter(|v| !matches!(v, Value::None)));
    match v {
        None => Ok(None),
        Some(v) => {
            let i = v.as_int().ok_or_else(|| err(format!("TypeError: {f}(): axis must be an integer")))?;
            let j = if i < 0 { i + ndim as i64 } else { i };
            if j < 0 || j as usize >= ndim {
                return Err(err(format!(
                    "numpy.exceptions.AxisError: axis {i} is out of bounds for array of dimension {ndim}"
                )));
            }
            Ok(Some(j as usize))
        }
    }
}

/// A reduction over all elements (axis None) or along an axis.
fn reduce(a: &Array, axis: Option<usize>, dtype: DType, f: &dyn Fn(&[f64]) -> Result<f64>) -> Result<Value> {
    match (axis, a.ndim()) {
        (None, _) | (Some(0), 1) => Ok(scalar(f(&a.data)?, dtype)),
        (Some(ax), 2) => {
            let (r, c) = (a.rows(), a.cols());
            let lanes: Vec<Vec<f64>> = if ax == 0 {
                (0..c).map(|j| (0..r).map(|i| a.data[i * c + j]).collect()).collect()
            } else {
                (0..r).map(|i| a.data[i * c..(i + 1) * c].to_vec()).collect()
            };
            Ok(Array::vector(lanes.iter().map(|l| f(l)).collect::<Result<_>>()?, dtype).value())
        }
        _ => unreachable!("axis checked"),
    }
}

fn nonempty<'a>(f: &str, x: &'a [f64]) -> Result<&'a [f64]> {
    if x.is_empty() {
        return Err(err(format!("ValueError: zero-size array to reduction operation {f} which has no identity")));
    }
    Ok(x)
}

fn float_fn(name: &str) -> Option<fn(f64) -> f64> {
    Some(match name {
        "sqrt" => f64::sqrt,
        "square" => |x| x * x,
        "exp" => f64::exp,
        "log" => f64::ln,
        "log10" => f64::log10,
        "sin" => f64::sin,
        "cos" => f64::cos,
        "tan" => f64::tan,
        "arcsin" => f64::asin,
        "arccos" => f64::acos,
        "arctan" => f64::atan,
        "sinh" => f64::sinh,
        "cosh" => f64::cosh,
        "tanh" => f64::tanh,
        "degrees" | "rad2deg" => f64::to_degrees,
        "radians" | "deg2rad" => f64::to_radians,
        "fabs" => f64::abs,
        _ => return None,
    })
}

/// numpy's rounding: half to even at the given number of decimals.
fn round_to(x: f64, decimals: i64) -> f64 {
    let p = 10f64.powi(decimals as i32);
    let y = x * p;
    let r = y.round();
    let r = if (y - y.trunc()).abs() == 0.5 { 2.0 * (y / 2.0).round() } else { r };
    r / p
}

/// Call `numpy.NAME` (or `numpy.linalg.NAME`).
pub fn call(qualified: &str, args: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    if let Some(name) = qualified.strip_prefix("numpy.linalg.") {
        return linalg(name, args, kw);
    }
    let f = qualified.strip_prefix("numpy.").unwrap_or(qualified);
    let a0 = || arg(f, args, 0);
    let arr0 = || to_array(arg(f, args, 0)?);
    if let Some(g) = float_fn(f) {
        check_kw(f, kw, &[])?;
        let a = arr0()?;
        return Ok(result(map(&a, DType::Float, g)));
    }
    match f {
        "array" | "asarray" => {
            check_kw(f, kw, &["dtype", "copy"])?;
            let mut a = to_array(a0()?)?;
            if let Some(t) = kwarg(kw, "dtype") {
                a = astype(&a, t)?;
            }
            if a.dims.is_empty() {
                return Err(unsupported("0-dimensional arrays"));
            }
            Ok(a.value())
        }
        "zeros" | "ones" | "empty" | "full" => {
            check_kw(f, kw, &["dtype"])?;
            let dims = shape_arg(a0()?)?;
            let (x, mut dtype) = match f {
                "ones" => (1.0, DType::Float),
                "full" => {
                    let v = arg(f, args, 1)?;
                    (as_f64(v, "full")?, if matches!(v, Value::Float(_)) { DType::Float } else { DType::Int })
                }
                _ => (0.0, DType::Float),
            };
            if let Some(t) = kwarg(kw, "dtype") {
                dtype = dtype_of(t)?;
            }
            let n = dims.iter().product();
            Ok(Array::new(dims, vec![x; n], dtype).value())
        }
        "zeros_like" | "ones_like" => {
            let a = arr0()?;
            let x = if f == "zeros_like" { 0.0 } else { 1.0 };
            Ok(Array::new(a.dims.clone(), vec![x; a.size()], a.dtype.max(DType::Int)).value())
        }
        "linspace" => {
            check_kw(f, kw, &["num", "endpoint"])?;
            let start = as_f64(a0()?, "linspace")?;
            let stop = as_f64(arg(f, args, 1)?, "linspace")?;
            let num = match args.get(2).or_else(|| kwarg(kw, "num")) {
                Some(v) => as_usize(v, "linspace num")?,
                None => 50,
            };
            let endpoint = kwarg(kw, "endpoint").map(|v| v.truthy()).transpose()?.unwrap_or(true);
            let div = if endpoint { num.saturating_sub(1) } else { num };
            let step = if div > 0 { (stop - start) / div as f64 } else { 0.0 };
            let mut data: Vec<f64> = (0..num).map(|i| start + i as f64 * step).collect();
            if endpoint && num > 1 {
                data[num - 1] = stop;
            }
            Ok(Array::vector(data, DType::Float).value())
        }
        "logspace" => {
            let lin = call("numpy.linspace", args, kw)?;
            let Value::Array(a) = lin else { unreachable!() };
            let a = a.borrow();
            Ok(map(&a, DType::Float, |x| 10f64.powf(x)).value())
        }
        "arange" => {
            check_kw(f, kw, &["dtype"])?;
            let (start, stop, step) = match args {
                [b] => (Value::Int(0), b.clone(), Value::Int(1)),
                [a, b] => (a.clone(), b.clone(), Value::Int(1)),
                [a, b, c] => (a.clone(), b.clone(), c.clone()),
                _ => return Err(err("TypeError: arange() takes 1 to 3 positional arguments")),
            };
            let int = [&start, &stop, &step].iter().all(|v| v.as_int().is_some());
            let (a, b, s) = (as_f64(&start, "arange")?, as_f64(&stop, "arange")?, as_f64(&step, "arange")?);
            if s == 0.0 {
                return Err(err("ZeroDivisionError: division by zero"));
            }
            let n = ((b - a) / s).ceil().max(0.0) as usize;
            let mut dtype = if int { DType::Int } else { DType::Float };
            if let Some(t) = kwarg(kw, "dtype") {
                dtype = dtype_of(t)?;
            }
            Ok(Array::vector((0..n).map(|i| a + i as f64 * s).collect(), dtype).value())
        }
        "eye" | "identity" => {
            check_kw(f, kw, &["dtype"])?;
            let n = as_usize(a0()?, f)?;
            let m = match args.get(1) {
                Some(v) if f == "eye" => as_usize(v, f)?,
                _ => n,
            };
            let data = (0..n).flat_map(|i| (0..m).map(move |j| (i == j) as i64 as f64)).collect();
            Ok(Array::new(vec![n, m], data, DType::Float).value())
        }
        "diag" => {
            let a = arr0()?;
            match a.ndim() {
                1 => {
                    let n = a.size();
                    let mut data = vec![0.0; n * n];
                    for i in 0..n {
                        data[i * n + i] = a.data[i];
                    }
                    Ok(Array::new(vec![n, n], data, a.dtype).value())
                }
                2 => {
                    let n = a.rows().min(a.cols());
                    Ok(Array::vector((0..n).map(|i| a.data[i * a.cols() + i]).collect(), a.dtype).value())
                }
                _ => Err(unsupported("numpy.diag of a scalar")),
            }
        }
        "copy" => Ok(result(arr0()?)),
        "abs" | "absolute" => {
            let a = arr0()?;
            Ok(result(map(&a, a.dtype.max(DType::Int), f64::abs)))
        }
        "sign" => {
            let a = arr0()?;
            Ok(result(map(&a, a.dtype.max(DType::Int), |x| {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    x
                }
            })))
        }
        "floor" | "ceil" => {
            let a = arr0()?;
            Ok(result(map(&a, DType::Float, if f == "floor" { f64::floor } else { f64::ceil })))
        }
        "around" | "round" => {
            check_kw(f, kw, &["decimals"])?;
            let a = arr0()?;
            let d = match args.get(1).or_else(|| kwarg(kw, "decimals")) {
                Some(v) => v.as_int().ok_or_else(|| err("TypeError: decimals must be an integer"))?,
                None => 0,
            };
            Ok(result(map(&a, a.dtype.max(DType::Int), |x| round_to(x, d))))
        }
        "real" | "imag" => match a0()? {
            Value::Complex(r, i) => Ok(Value::Float(if f == "real" { *r } else { *i })),
            v => {
                let a = to_array(v)?;
                Ok(result(if f == "real" { a } else { map(&a, a.dtype, |_| 0.0) }))
            }
        },
        "isnan" | "isinf" | "isfinite" => {
            let a = arr0()?;
            let g: fn(f64) -> bool = match f {
                "isnan" => f64::is_nan,
                "isinf" => f64::is_infinite,
                _ => f64::is_finite,
            };
            Ok(result(map(&a, DType::Bool, |x| g(x) as i64 as f64)))
        }
        "minimum" | "maximum" | "power" | "arctan2" => {
            let (x, y) = (arr0()?, to_array(arg(f, args, 1)?)?);
            let num = x.dtype.max(y.dtype).max(DType::Int);
            Ok(result(match f {
                "minimum" => zip_with(&x, &y, num, |p, q| if p.is_nan() || q.is_nan() { f64::NAN } else { p.min(q) })?,
                "maximum" => zip_with(&x, &y, num, |p, q| if p.is_nan() || q.is_nan() { f64::NAN } else { p.max(q) })?,
                "power" => zip_with(&x, &y, num, f64::powf)?,
                _ => zip_with(&x, &y, DType::Float, f64::atan2)?,
            }))
        }
        "sum" | "max" | "amax" | "min" | "amin" | "mean" | "std" | "median" | "prod" | "any" | "all" => {
            check_kw(f, kw, &["axis"])?;
            let a = to_array_1d(a0()?)?;
            let axis = axis_arg(f, args, 1, kw, a.ndim())?;
            reduction(f, &a, axis)
        }
        "argmax" | "argmin" => {
            let a = to_array_1d(a0()?)?;
            if axis_arg(f, args, 1, kw, a.ndim())?.is_some() {
                return Err(unsupported(&format!("numpy.{f}(..., axis=...)")));
            }
            arg_extreme(f, &a)
        }
        "cumsum" => {
            let a = to_array_1d(a0()?)?;
            let mut acc = 0.0;
            Ok(Array::vector(
                a.data
                    .iter()
                    .map(|x| {
                        acc += x;
                        acc
                    })
                    .collect(),
                a.dtype.max(DType::Int),
            )
            .value())
        }
        "diff" => {
            let a = to_array_1d(a0()?)?;
            if a.ndim() != 1 {
                return Err(unsupported("numpy.diff of a 2-D array"));
            }
            Ok(Array::vector(a.data.windows(2).map(|w| w[1] - w[0]).collect(), a.dtype.max(DType::Int)).value())
        }
        "dot" => dot(&arr0()?, &to_array(arg(f, args, 1)?)?),
        "outer" => {
            let (x, y) = (arr0()?, to_array(arg(f, args, 1)?)?);
            let data = x.data.iter().flat_map(|p| y.data.iter().map(move |q| p * q)).collect();
            Ok(Array::new(vec![x.size(), y.size()], data, x.dtype.max(y.dtype).max(DType::Int)).value())
        }
        "cross" => {
            let (x, y) = (arr0()?, to_array(arg(f, args, 1)?)?);
            if x.dims != [3] || y.dims != [3] {
                return Err(unsupported("numpy.cross of other than two 3-vectors"));
            }
            let (a, b) = (&x.data, &y.data);
            let c = vec![a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
            Ok(Array::vector(c, x.dtype.max(y.dtype).max(DType::Int)).value())
        }
        "transpose" => Ok(transpose(&arr0()?).value()),
        "reshape" => reshape(&arr0()?, &args[1..], kw),
        "ravel" => {
            let a = arr0()?;
            Ok(Array::vector(a.data, a.dtype).value())
        }
        "shape" => Ok(Value::tuple(to_array(a0()?)?.dims.iter().map(|d| Value::Int(*d as i64)).collect())),
        "size" => Ok(Value::Int(to_array(a0()?)?.size() as i64)),
        "ndim" => Ok(Value::Int(to_array(a0()?)?.ndim() as i64)),
        "concatenate" | "vstack" | "hstack" | "append" => stack(f, args, kw),
        "interp" => interp(args, kw),
        "allclose" | "isclose" => {
            check_kw(f, kw, &["rtol", "atol", "equal_nan"])?;
            let (x, y) = (arr0()?, to_array(arg(f, args, 1)?)?);
            let rtol = match args.get(2).or_else(|| kwarg(kw, "rtol")) {
                Some(v) => as_f64(v, "rtol")?,
                None => 1e-5,
            };
            let atol = match args.get(3).or_else(|| kwarg(kw, "atol")) {
                Some(v) => as_f64(v, "atol")?,
                None => 1e-8,
            };
            let eq_nan = kwarg(kw, "equal_nan").map(|v| v.truthy()).transpose()?.unwrap_or(false);
            let close = zip_with(&x, &y, DType::Bool, |p, q| {
                let c = if p.is_nan() || q.is_nan() {
                    eq_nan && p.is_nan() && q.is_nan()
                } else if p.is_infinite() || q.is_infinite() {
                    p == q
                } else {
                    (p - q).abs() <= atol + rtol * q.abs()
                };
                c as i64 as f64
            })?;
            if f == "allclose" {
                Ok(Value::Bool(close.data.iter().all(|c| *c != 0.0)))
            } else {
                Ok(result(close))
            }
        }
        "where" => match args {
            [c] => nonzero(&to_array(c)?),
            [c, x, y] => {
                let (c, x, y) = (to_array(c)?, to_array(x)?, to_array(y)?);
                let dims = broadcast(&broadcast(&c.dims, &x.dims)?, &y.dims)?;
                let dtype = x.dtype.max(y.dtype);
                let data = indices(&dims)
                    .iter()
                    .map(|ix| if at(&c, &dims, ix) != 0.0 { at(&x, &dims, ix) } else { at(&y, &dims, ix) })
                    .collect();
                Ok(result(Array::new(dims, data, dtype)))
            }
            _ => Err(err("TypeError: where() takes 1 or 3 arguments")),
        },
        "nonzero" => nonzero(&arr0()?),
        "count_nonzero" => Ok(Value::Int(arr0()?.data.iter().filter(|x| **x != 0.0).count() as i64)),
        "trapz" => {
            check_kw(f, kw, &["x", "dx"])?;
            let y = to_array_1d(a0()?)?;
            let x = match args.get(1).or_else(|| kwarg(kw, "x")) {
                Some(v) => Some(to_array_1d(v)?),
                None => None,
            };
            let dx = match kwarg(kw, "dx") {
                Some(v) => as_f64(v, "dx")?,
                None => 1.0,
            };
            if x.as_ref().is_some_and(|x| x.size() != y.size()) {
                return Err(err("ValueError: x and y must have the same length"));
            }
            let mut s = 0.0;
            for i in 1..y.size() {
                let h = x.as_ref().map(|x| x.data[i] - x.data[i - 1]).unwrap_or(dx);
                s += h * (y.data[i] + y.data[i - 1]) / 2.0;
            }
            Ok(Value::Float(s))
        }
        "sort" => {
            let mut a = to_array_1d(a0()?)?;
            if a.ndim() != 1 {
                return Err(unsupported("numpy.sort of a 2-D array"));
            }
            a.data.sort_by(|p, q| p.partial_cmp(q).unwrap_or(std::cmp::Ordering::Greater));
            Ok(a.value())
        }
        _ => Err(unsupported(&format!("numpy.{f}"))),
    }
}

fn dtype_of(t: &Value) -> Result<DType> {
    Ok(match t {
        Value::Builtin(Builtin("float")) => DType::Float,
        Value::Builtin(Builtin("int")) => DType::Int,
        Value::Builtin(Builtin("bool")) => DType::Bool,
        Value::Str(s) if matches!(&**s, "float" | "float64" | "f8" | "d") => DType::Float,
        Value::Str(s) if matches!(&**s, "int" | "int64" | "i8") => DType::Int,
        Value::Str(s) if matches!(&**s, "bool") => DType::Bool,
        other => return Err(unsupported(&format!("dtype={}", other.type_name()))),
    })
}

fn astype(a: &Array, t: &Value) -> Result<Array> {
    let dtype = dtype_of(t)?;
    Ok(map(a, dtype, |x| match dtype {
        DType::Int => x.trunc(),
        DType::Bool => (x != 0.0) as i64 as f64,
        DType::Float => x,
    }))
}

fn reduction(f: &str, a: &Array, axis: Option<usize>) -> Result<Value> {
    let num = a.dtype.max(DType::Int);
    match f {
        "sum" => reduce(a, axis, num, &|x| Ok(x.iter().sum())),
        "prod" => reduce(a, axis, num, &|x| Ok(x.iter().product())),
        "max" | "amax" => reduce(a, axis, a.dtype, &|x| {
            Ok(nonempty("maximum", x)?.iter().copied().fold(f64::NEG_INFINITY, |m, v| {
                if v.is_nan() || m.is_nan() {
                    f64::NAN
                } else {
                    m.max(v)
                }
            }))
        }),
        "min" | "amin" => reduce(a, axis, a.dtype, &|x| {
            Ok(nonempty("minimum", x)?.iter().copied().fold(f64::INFINITY, |m, v| {
                if v.is_nan() || m.is_nan() {
                    f64::NAN
                } else {
                    m.min(v)
                }
            }))
        }),
        "mean" => reduce(a, axis, DType::Float, &|x| Ok(x.iter().sum::<f64>() / x.len() as f64)),
        "std" => reduce(a, axis, DType::Float, &|x| {
            let m = x.iter().sum::<f64>() / x.len() as f64;
            Ok((x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / x.len() as f64).sqrt())
        }),
        "median" => reduce(a, axis, DType::Float, &|x| {
            let mut v = x.to_vec();
            if v.is_empty() {
                return Ok(f64::NAN);
            }
            v.sort_by(|p, q| p.partial_cmp(q).unwrap_or(std::cmp::Ordering::Greater));
            let n = v.len();
            Ok(if n % 2 == 1 { v[n / 2] } else { (v[n / 2 - 1] + v[n / 2]) / 2.0 })
        }),
        "any" => reduce(a, axis, DType::Bool, &|x| Ok(x.iter().any(|v| *v != 0.0) as i64 as f64)),
        "all" => reduce(a, axis, DType::Bool, &|x| Ok(x.iter().all(|v| *v != 0.0) as i64 as f64)),
        _ => unreachable!("the reductions above"),
    }
}

fn arg_extreme(f: &str, a: &Array) -> Result<Value> {
    if a.size() == 0 {
        return Err(err(format!("ValueError: attempt to get {f} of an empty sequence")));
    }
    let mut best = 0;
    for (i, x) in a.data.iter().enumerate() {
        if x.is_nan() {
            return Ok(Value::Int(i as i64));
        }
        let b = a.data[best];
        if (f == "argmax" && *x > b) || (f == "argmin" && *x < b) {
            best = i;
        }
    }
    Ok(Value::Int(best as i64))
}

fn transpose(a: &Array) -> Array {
    if a.ndim() < 2 {
        return a.clone();
    }
    let (r, c) = (a.rows(), a.cols());
    let data = (0..c).flat_map(|j| (0..r).map(move |i| (i, j))).map(|(i, j)| a.data[i * c + j]).collect();
    Array::new(vec![c, r], data, a.dtype)
}

fn reshape(a: &Array, shape: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    check_kw("reshape", kw, &[])?;
    let dims: Vec<i64> = match shape {
        [v @ (Value::Tuple(_) | Value::List(_))] => v
            .iter_items()?
            .iter()
            .map(|x| x.as_int().ok_or_else(|| err("TypeError: shape must be integers")))
            .collect::<Result<_>>()?,
        vs => vs
            .iter()
            .map(|x| x.as_int().ok_or_else(|| err("TypeError: shape must be integers")))
            .collect::<Result<_>>()?,
    };
    if dims.is_empty() || dims.len() > 2 {
        return Err(unsupported("arrays of other than 1 or 2 dimensions"));
    }
    let n = a.size() as i64;
    let known: i64 = dims.iter().filter(|d| **d >= 0).product();
    let dims: Vec<usize> =
        dims.iter().map(|d| if *d < 0 && known > 0 { (n / known) as usize } else { *d as usize }).collect();
    if dims.iter().product::<usize>() != a.size() {
        return Err(err(format!("ValueError: cannot reshape array of size {} into shape {dims:?}", a.size())));
    }
    Ok(Array::new(dims, a.data.clone(), a.dtype).value())
}

fn dot(x: &Array, y: &Array) -> Result<Value> {
    let num = x.dtype.max(y.dtype).max(DType::Int);
    match (x.ndim(), y.ndim()) {
        (0, _) | (_, 0) => binop(crate::syntax::ast::BinOp::Mul, &x.clone().value(), &y.clone().value()),
        (1, 1) => {
            if x.size() != y.size() {
                return Err(err(format!("ValueError: shapes ({},) and ({},) not aligned", x.size(), y.size())));
            }
            Ok(scalar(x.data.iter().zip(&y.data).map(|(p, q)| p * q).sum(), num))
        }
        (2, 1) => {
            let (r, c) = (x.rows(), x.cols());
            if c != y.size() {
                return Err(err(format!("ValueError: shapes ({r},{c}) and ({},) not aligned", y.size())));
            }
            Ok(Array::vector((0..r).map(|i| (0..c).map(|j| x.data[i * c + j] * y.data[j]).sum()).collect(), num)
                .value())
        }
        (1, 2) => {
            let (r, c) = (y.rows(), y.cols());
            if r != x.size() {
                return Err(err(format!("ValueError: shapes ({},) and ({r},{c}) not aligned", x.size())));
            }
            Ok(Array::vector((0..c).map(|j| (0..r).map(|i| x.data[i] * y.data[i * c + j]).sum()).collect(), num)
                .value())
        }
        _ => {
            let (r, k, c) = (x.rows(), x.cols(), y.cols());
            if k != y.rows() {
                return Err(err(format!("ValueError: shapes ({r},{k}) and ({},{c}) not aligned", y.rows())));
            }
            let mut data = vec![0.0; r * c];
            for i in 0..r {
                for j in 0..c {
                    data[i * c + j] = (0..k).map(|l| x.data[i * k + l] * y.data[l * c + j]).sum();
                }
            }
            Ok(Array::new(vec![r, c], data, num).value())
        }
    }
}

fn nonzero(a: &Array) -> Result<Value> {
    let hits: Vec<usize> = a.data.iter().enumerate().filter(|(_, x)| **x != 0.0).map(|(i, _)| i).collect();
    let axes: Vec<Value> = if a.ndim() <= 1 {
        vec![Array::vector(hits.iter().map(|i| *i as f64).collect(), DType::Int).value()]
    } else {
        let c = a.cols();
        vec![
            Array::vector(hits.iter().map(|i| (i / c) as f64).collect(), DType::Int).value(),
            Array::vector(hits.iter().map(|i| (i % c) as f64).collect(), DType::Int).value(),
        ]
    };
    Ok(Value::tuple(axes))
}

fn stack(f: &str, args: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    let parts: Vec<Array> = if f == "append" {
        check_kw(f, kw, &[])?;
        let (x, y) = (to_array_1d(arg(f, args, 0)?)?, to_array_1d(arg(f, args, 1)?)?);
        vec![Array::vector(x.data, x.dtype), Array::vector(y.data, y.dtype)]
    } else {
        check_kw(f, kw, &["axis"])?;
        arg(f, args, 0)?.iter_items()?.iter().map(to_array_1d).collect::<Result<_>>()?
    };
    if parts.is_empty() {
        return Err(err("ValueError: need at least one array to concatenate"));
    }
    let dtype = parts.iter().map(|p| p.dtype).max().unwrap();
    let along_rows = match f {
        "vstack" => true,
        "hstack" | "append" => false,
        _ => match axis_arg(f, &[], 9, kw, parts[0].ndim())? {
            None | Some(0) => true,
            Some(_) => false,
        },
    };
    let all_1d = parts.iter().all(|p| p.ndim() == 1);
    if all_1d && (f != "vstack") {
        return Ok(Array::vector(parts.into_iter().flat_map(|p| p.data).collect(), dtype).value());
    }
    let as2 = |p: Array| -> Array {
        if p.ndim() == 1 {
            let n = p.size();
            Array::new(vec![1, n], p.data, p.dtype)
        } else {
            p
        }
    };
    let parts: Vec<Array> = parts.into_iter().map(as2).collect();
    if along_rows {
        let c = parts[0].cols();
        if parts.iter().any(|p| p.cols() != c) {
            return Err(err(
                "ValueError: all the input array dimensions except for the concatenation axis must match exactly",
            ));
        }
        let r = parts.iter().map(|p| p.rows()).sum();
        Ok(Array::new(vec![r, c], parts.into_iter().flat_map(|p| p.data).collect(), dtype).value())
    } else {
        let r = parts[0].rows();
        if parts.iter().any(|p| p.rows() != r) {
            return Err(err(
                "ValueError: all the input array dimensions except for the concatenation axis must match exactly",
            ));
        }
        let c: usize = parts.iter().map(|p| p.cols()).sum();
        let mut data = Vec::with_capacity(r * c);
        for i in 0..r {
            for p in &parts {
                data.extend_from_slice(&p.data[i * p.cols()..(i + 1) * p.cols()]);
            }
        }
        Ok(Array::new(vec![r, c], data, dtype).value())
    }
}

/// `numpy.interp(x, xp, fp, left=None, right=None)`: piecewise linear, constant outside.
fn interp(args: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    check_kw("interp", kw, &["left", "right"])?;
    let x = to_array(arg("interp", args, 0)?)?;
    let xp = to_array_1d(arg("interp", args, 1)?)?;
    let fp = to_array_1d(arg("interp", args, 2)?)?;
    if xp.size() != fp.size() || xp.size() == 0 {
        return Err(err("ValueError: fp and xp are not of the same length."));
    }
    let left = match args.get(3).or_else(|| kwarg(kw, "left")) {
        Some(v) => as_f64(v, "left")?,
        None => fp.data[0],
    };
    let right = match args.get(4).or_else(|| kwarg(kw, "right")) {
        Some(v) => as_f64(v, "right")?,
        None => *fp.data.last().unwrap(),
    };
    let (xs, fs) = (&xp.data, &fp.data);
    let one = |t: f64| -> f64 {
        if t.is_nan() {
            return f64::NAN;
        }
        if t < xs[0] {
            return left;
        }
        if t > xs[xs.len() - 1] {
            return right;
        }
        if t == xs[xs.len() - 1] {
            return fs[fs.len() - 1];
        }
        let j = xs.partition_point(|v| *v <= t).max(1) - 1;
        let (x0, x1) = (xs[j], xs[j + 1]);
        if x1 == x0 {
            return fs[j];
        }
        let s = (fs[j + 1] - fs[j]) / (x1 - x0);
        s * (t - x0) + fs[j]
    };
    Ok(result(map(&x, DType::Float, one)))
}

fn linalg(name: &str, args: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    let a = to_array(arg(name, args, 0)?)?;
    match name {
        "norm" => {
            check_kw("norm", kw, &["ord", "axis"])?;
            if kwarg(kw, "axis").is_some() {
                return Err(unsupported("numpy.linalg.norm(..., axis=...)"));
            }
            let ord = args.get(1).or_else(|| kwarg(kw, "ord"));
            let abs: Vec<f64> = a.data.iter().map(|x| x.abs()).collect();
            let v = match ord {
                None => abs.iter().map(|x| x * x).sum::<f64>().sqrt(),
                Some(Value::Str(s)) if &**s == "fro" && a.ndim() == 2 => abs.iter().map(|x| x * x).sum::<f64>().sqrt(),
                Some(o) if a.ndim() == 1 => match o.as_f64() {
                    Some(p) if p.is_infinite() && p > 0.0 => abs.iter().copied().fold(0.0, f64::max),
                    Some(p) if p.is_infinite() => abs.iter().copied().fold(f64::INFINITY, f64::min),
                    Some(1.0) => abs.iter().sum(),
                    Some(2.0) => abs.iter().map(|x| x * x).sum::<f64>().sqrt(),
                    Some(p) if p > 0.0 => abs.iter().map(|x| x.powf(p)).sum::<f64>().powf(1.0 / p),
                    _ => return Err(unsupported("this ord of numpy.linalg.norm")),
                },
                Some(_) => return Err(unsupported("this ord of numpy.linalg.norm for a matrix")),
            };
            Ok(Value::Float(v))
        }
        "det" | "inv" | "solve" => {
            if a.ndim() != 2 || a.rows() != a.cols() {
                return Err(err("numpy.linalg.LinAlgError: Last 2 dimensions of the array must be square"));
            }
            let n = a.rows();
            let m = nalgebra::DMatrix::from_row_slice(n, n, &a.data);
            match name {
                // As numpy: from the LU factors, the sign and the sum of the logarithms of the pivots.
                "det" => {
                    let lu = m.lu();
                    let u = lu.u();
                    let mut sign = lu.p().determinant::<f64>();
                    let mut log = 0.0;
                    for i in 0..n {
                        let d = u[(i, i)];
                        if d == 0.0 {
                            return Ok(Value::Float(0.0));
                        }
                        sign *= d.signum();
                        log += d.abs().ln();
                    }
                    Ok(Value::Float(sign * log.exp()))
                }
                // As numpy: the LU solve of the identity.
                "inv" => {
                    let inv = m
                        .lu()
                        .solve(&nalgebra::DMatrix::identity(n, n))
                        .ok_or_else(|| err("numpy.linalg.LinAlgError: Singular matrix"))?;
                    Ok(Array::new(vec![n, n], inv.transpose().as_slice().to_vec(), DType::Float).value())
                }
                _ => {
                    let b = to_array(arg(name, args, 1)?)?;
                    let lu = m.lu();
                    if b.ndim() == 1 {
                        let x = lu
                            .solve(&nalgebra::DVector::from_column_slice(&b.data))
                            .ok_or_else(|| err("numpy.linalg.LinAlgError: Singular matrix"))?;
                        Ok(Array::vector(x.as_slice().to_vec(), DType::Float).value())
                    } else {
                        let bm = nalgebra::DMatrix::from_row_slice(b.rows(), b.cols(), &b.data);
                        let x = lu.solve(&bm).ok_or_else(|| err("numpy.linalg.LinAlgError: Singular matrix"))?;
                        Ok(Array::new(vec![x.nrows(), x.ncols()], x.transpose().as_slice().to_vec(), DType::Float)
                            .value())
                    }
                }
            }
        }
        _ => Err(unsupported(&format!("numpy.linalg.{name}"))),
    }
}

// ------------------------------------------------------------------ attributes and methods

const METHODS: &[&str] = &[
    "tolist",
    "copy",
    "reshape",
    "flatten",
    "ravel",
    "transpose",
    "sum",
    "max",
    "min",
    "mean",
    "std",
    "prod",
    "argmax",
    "argmin",
    "dot",
    "round",
    "cumsum",
    "any",
    "all",
    "item",
    "astype",
    "fill",
];

/// `a.NAME`: an attribute, or a bound method.
pub fn array_attr(a: &Value, name: &str) -> Result<Value> {
    let Value::Array(r) = a else { unreachable!("an array") };
    let x = r.borrow();
    Ok(match name {
        "shape" => Value::tuple(x.dims.iter().map(|d| Value::Int(*d as i64)).collect()),
        "size" => Value::Int(x.size() as i64),
        "ndim" => Value::Int(x.ndim() as i64),
        "T" => transpose(&x).value(),
        "real" => x.clone().value(),
        "imag" => map(&x, x.dtype, |_| 0.0).value(),
        n => match METHODS.iter().find(|m| **m == n) {
            Some(m) => Value::Method(Box::new(a.clone()), m),
            None => return Err(unsupported(&format!("numpy.ndarray.{n}"))),
        },
    })
}

/// `a.NAME(args)`.
pub fn call_method(recv: &ArrayRef, name: &str, args: &[Value], kw: &[(String, Value)]) -> Result<Value> {
    let a = recv.borrow().clone();
    let with = |extra: &[Value]| -> Vec<Value> {
        let mut v = vec![a.clone().value()];
        v.extend_from_slice(extra);
        v
    };
    match name {
        "tolist" => Ok(match a.ndim() {
            1 => Value::list(a.items()),
            _ => Value::list(
                (0..a.rows())
                    .map(|i| {
                        Value::list(a.data[i * a.cols()..(i + 1) * a.cols()].iter().map(|x| a.scalar(*x)).collect())
                    })
                    .collect(),
            ),
        }),
        "copy" => Ok(a.value()),
        "flatten" | "ravel" => Ok(Array::vector(a.data, a.dtype).value()),
        "reshape" => reshape(&a, args, kw),
        "transpose" => Ok(transpose(&a).value()),
        "sum" | "max" | "min" | "mean" | "std" | "prod" | "any" | "all" => {
            check_kw(name, kw, &["axis"])?;
            let axis = axis_arg(name, args, 0, kw, a.ndim())?;
            reduction(name, &a, axis)
        }
        "argmax" | "argmin" => arg_extreme(name, &a),
        "dot" => dot(&a, &to_array(arg(name, args, 0)?)?),
        "round" => call("numpy.around", &with(args), kw),
        "cumsum" => call("numpy.cumsum", &with(args), kw),
        "astype" => Ok(astype(&a, arg(name, args, 0)?)?.value()),
        "item" => match args {
            [] if a.size() == 1 => Ok(a.scalar(a.data[0])),
            [] => Err(err("ValueError: can only convert an array of size 1 to a Python scalar")),
            [i] => {
                let i = i.as_int().ok_or_else(|| err("TypeError: item() expects an integer"))?;
                Ok(a.scalar(a.data[norm(i, a.size(), 0)?]))
            }
            _ => Err(unsupported("numpy.ndarray.item with several indices")),
        },
        "fill" => {
            let v = as_f64(arg(name, args, 0)?, "fill")?;
            recv.borrow_mut().data.iter_mut().for_each(|x| *x = v);
            Ok(Value::None)
        }
        _ => Err(unsupported(&format!("numpy.ndarray.{name}"))),
    }
}

#[cfg(test)]
mod tests;
