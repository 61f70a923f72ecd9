//! Operators, comparisons and item access with Python semantics.

use super::format;
use super::value::{as_slice, py_eq, slice_indices, Value};
use crate::diag::{Error, Result};
use crate::syntax::ast::{BinOp, CmpOp, UnOp};
use std::cmp::Ordering;

fn op_name(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::FloorDiv => "//",
        BinOp::Mod => "%",
        BinOp::Pow => "**",
        BinOp::BitOr => "|",
        BinOp::BitXor => "^",
        BinOp::BitAnd => "&",
        BinOp::LShift => "<<",
        BinOp::RShift => ">>",
    }
}

/// `&`, `|`, `^` of booleans (a boolean) or integers, `<<`, `>>` of integers.
fn bitwise(op: BinOp, a: &Value, b: &Value) -> Result<Value> {
    if let (Value::Bool(x), Value::Bool(y)) = (a, b) {
        match op {
            BinOp::BitAnd => return Ok(Value::Bool(*x & *y)),
            BinOp::BitOr => return Ok(Value::Bool(*x | *y)),
            BinOp::BitXor => return Ok(Value::Bool(*x ^ *y)),
            _ => {}
        }
    }
    let (Some(x), Some(y)) = (int_like(a), int_like(b)) else { return Err(type_err(op, a, b)) };
    Ok(Value::Int(match op {
        BinOp::BitAnd => x & y,
        BinOp::BitOr => x | y,
        BinOp::BitXor => x ^ y,
        _ => {
            if y < 0 {
                return Err(Error::python("ValueError: negative shift count"));
            }
            if op == BinOp::RShift {
                if y >= 64 {
                    if x < 0 {
                        -1
                    } else {
                        0
                    }
                } else {
                    x >> y
                }
            } else if x == 0 {
                0
            } else if y >= 63 {
                return Err(overflow());
            } else {
                i64::try_from((x as i128) << y).map_err(|_| overflow())?
            }
        }
    }))
}

fn type_err(op: BinOp, a: &Value, b: &Value) -> Error {
    Error::python(format!(
        "TypeError: unsupported operand type(s) for {}: '{}' and '{}'",
        op_name(op),
        a.type_name(),
        b.type_name()
    ))
}

fn overflow() -> Error {
    Error::python("OverflowError: integer result out of the 64-bit range")
}

fn zero_div() -> Error {
    Error::python("ZeroDivisionError: division by zero")
}

pub fn binop(op: BinOp, a: &Value, b: &Value) -> Result<Value> {
    use Value::*;
    if matches!(a, Array(_)) || matches!(b, Array(_)) {
        return super::numpy::binop(op, a, b);
    }
    // Integers (bool counts as int).
    if let (Some(x), Some(y)) = (int_like(a), int_like(b)) {
        return Ok(match op {
            BinOp::Add => Int(x.checked_add(y).ok_or_else(overflow)?),
            BinOp::Sub => Int(x.checked_sub(y).ok_or_else(overflow)?),
            BinOp::Mul => Int(x.checked_mul(y).ok_or_else(overflow)?),
            BinOp::Div => {
                if y == 0 {
                    return Err(zero_div());
                }
                Float(x as f64 / y as f64)
            }
            BinOp::FloorDiv => {
                if y == 0 {
                    return Err(zero_div());
                }
                let q = x.checked_div(y).ok_or_else(overflow)?;
                Int(if (x % y != 0) && ((x < 0) != (y < 0)) { q - 1 } else { q })
            }
            BinOp::Mod => {
                if y == 0 {
                    return Err(Error::python("ZeroDivisionError: integer modulo by zero"));
                }
                let r = x.checked_rem(y).ok_or_else(overflow)?;
                Int(if r != 0 && ((r < 0) != (y < 0)) { r + y } else { r })
            }
            BinOp::Pow => {
                if y < 0 {
                    if x == 0 {
                        return Err(Error::python("ZeroDivisionError: 0.0 cannot be raised to a negative power"));
                    }
                    Float((x as f64).powf(y as f64))
                } else {
                    let e = u32::try_from(y).map_err(|_| overflow())?;
                    Int(x.checked_pow(e).ok_or_else(overflow)?)
                }
            }
            BinOp::BitOr | BinOp::BitXor | BinOp::BitAnd | BinOp::LShift | BinOp::RShift => bitwise(op, a, b)?,
        });
    }
    // Floats (no bit operators: `&`, `|`, `^` of booleans and integers only).
    if let (Some(x), Some(y)) = (num(a), num(b)) {
        if matches!(op, BinOp::BitOr | BinOp::BitXor | BinOp::BitAnd | BinOp::LShift | BinOp::RShift) {
            return Err(type_err(op, a, b));
        }
        let r = float_binop(op, x, y)?;
        if r.is_infinite() && x.is_finite() && y.is_finite() {
            return Err(Error::python("OverflowError: numerical result out of range"));
        }
        return Ok(Float(r));
    }
    complex_or_sequence(op, a, b)
}

fn float_binop(op: BinOp, x: f64, y: f64) -> Result<f64> {
    {
        Ok(match op {
            BinOp::BitOr | BinOp::BitXor | BinOp::BitAnd | BinOp::LShift | BinOp::RShift => {
                return Err(Error::python(format!(
                    "TypeError: unsupported operand type(s) for {}: 'float'",
                    op_name(op)
                )))
            }
            BinOp::Add => x + y,
            BinOp::Sub => x - y,
            BinOp::Mul => x * y,
            BinOp::Div => {
                if y == 0.0 {
                    return Err(Error::python("ZeroDivisionError: float division by zero"));
                }
                x / y
            }
            BinOp::FloorDiv => {
                if y == 0.0 {
                    return Err(Error::python("ZeroDivisionError: float floor division by zero"));
                }
                // As CPython: from the remainder, so that 1 // 0.1 == 9.0.
                let m = x % y;
                let m = if m != 0.0 && ((m < 0.0) != (y < 0.0)) { m + y } else { m };
                ((x - m) / y).round()
            }
            BinOp::Mod => {
                if y == 0.0 {
                    return Err(Error::python("ZeroDivisionError: float modulo"));
                }
                let r = x % y;
                if r != 0.0 && ((r < 0.0) != (y < 0.0)) {
                    r + y
                } else {
                    r
                }
            }
            BinOp::Pow => {
                if x == 0.0 && y < 0.0 {
                    return Err(Error::python("ZeroDivisionError: 0.0 cannot be raised to a negative power"));
                }
                if x < 0.0 && y.fract() != 0.0 {
                    return Err(Error::python(
                        "ValueError: negative number raised to a fractional power (complex result)",
                    ));
                }
                x.powf(y)
            }
        })
    }
}

fn complex_or_sequence(op: BinOp, a: &Value, b: &Value) -> Result<Value> {
    use Value::*;
    // Complex numbers.
    if let (Some((ar, ai)), Some((br, bi))) = (cplx(a), cplx(b)) {
        return match op {
            BinOp::Add => Ok(Complex(ar + br, ai + bi)),
            BinOp::Sub => Ok(Complex(ar - br, ai - bi)),
            BinOp::Mul => Ok(Complex(ar * br - ai * bi, ar * bi + ai * br)),
            BinOp::Div => {
                let d = br * br + bi * bi;
                if d == 0.0 {
                    return Err(Error::python("ZeroDivisionError: complex division by zero"));
                }
                Ok(Complex((ar * br + ai * bi) / d, (ai * br - ar * bi) / d))
            }
            _ => Err(type_err(op, a, b)),
        };
    }
    match (op, a, b) {
        (BinOp::Add, Str(x), Str(y)) => Ok(Value::str(&format!("{x}{y}"))),
        (BinOp::Add, List(x), List(y)) => {
            let mut v = x.borrow().clone();
            v.extend(y.borrow().iter().cloned());
            Ok(Value::list(v))
        }
        (BinOp::Add, Tuple(x), Tuple(y)) => {
            let mut v = x.as_ref().clone();
            v.extend(y.iter().cloned());
            Ok(Value::tuple(v))
        }
        (BinOp::Mul, Str(_) | List(_) | Tuple(_), _) if int_like(b).is_some() => repeat(a, int_like(b).unwrap()),
        (BinOp::Mul, _, Str(_) | List(_) | Tuple(_)) if int_like(a).is_some() => repeat(b, int_like(a).unwrap()),
        (BinOp::Mod, Str(f), args) => Ok(Value::str(&format::percent(f, args)?)),
        _ => Err(type_err(op, a, b)),
    }
}

fn repeat(seq: &Value, n: i64) -> Result<Value> {
    let n = n.max(0) as usize;
    let len = match seq {
        Value::Str(s) => s.len(),
        Value::List(l) => l.borrow().len(),
        Value::Tuple(t) => t.len(),
        _ => 0,
    };
    // The result's size, not only the count: `[0] * 1000 * 10**7` would ask for 10^10 items.
    if len.checked_mul(n).is_none_or(|total| total > crate::text::MAX_WIDTH) {
        return Err(Error::python(format!(
            "MemoryError: repetition too large ({len} x {n} exceeds the limit of {} items)",
            crate::text::MAX_WIDTH
        )));
    }
    Ok(match seq {
        Value::Str(s) => Value::str(&s.repeat(n)),
        Value::List(l) => {
            let items = l.borrow();
            let mut v = Vec::with_capacity(items.len() * n);
            for _ in 0..n {
                v.extend(items.iter().cloned());
            }
            Value::list(v)
        }
        Value::Tuple(t) => {
            let mut v = Vec::with_capacity(t.len() * n);
            for _ in 0..n {
                v.extend(t.iter().cloned());
            }
            Value::tuple(v)
        }
        _ => unreachable!(),
    })
}

fn int_like(v: &Value) -> Option<i64> {
    v.as_int()
}

fn num(v: &Value) -> Option<f64> {
    v.as_f64()
}

fn cplx(v: &Value) -> Option<(f64, f64)> {
    match v {
        Value::Complex(a, b) => Some((*a, *b)),
        _ => v.as_f64().map(|x| (x, 0.0)),
    }
}

pub fn unary(op: UnOp, a: &Value) -> Result<Value> {
    match (op, a) {
        (UnOp::Not, v) => Ok(Value::Bool(!v.truthy()?)),
        (UnOp::Neg, Value::Array(x)) => super::numpy::negate(&x.borrow()),
        (UnOp::Pos, Value::Array(x)) => Ok(x.borrow().clone().value()),
        (UnOp::Invert, Value::Array(x)) => super::numpy::invert(&x.borrow()),
        (UnOp::Neg, Value::Float(f)) => Ok(Value::Float(-f)),
        (UnOp::Neg, Value::Complex(x, y)) => Ok(Value::Complex(-x, -y)),
        (UnOp::Neg, v) if v.as_int().is_some() => {
            Ok(Value::Int(v.as_int().unwrap().checked_neg().ok_or_else(overflow)?))
        }
        (UnOp::Pos, Value::Float(_) | Value::Complex(..)) => Ok(a.clone()),
        (UnOp::Pos, v) if v.as_int().is_some() => Ok(Value::Int(v.as_int().unwrap())),
        (UnOp::Invert, v) if v.as_int().is_some() => Ok(Value::Int(!v.as_int().unwrap())),
        _ => Err(Error::python(format!("TypeError: bad operand type for unary operator: '{}'", a.type_name()))),
    }
}

/// Python ordering of two values (for <, sorted, min, max).
pub fn order(a: &Value, b: &Value) -> Result<Ordering> {
    use Value::*;
    match (a, b) {
        (Str(x), Str(y)) => Ok(x.cmp(y)),
        (Tuple(_) | List(_), Tuple(_) | List(_)) if std::mem::discriminant(a) == std::mem::discriminant(b) => {
            let x = a.iter_items()?;
            let y = b.iter_items()?;
            for (p, q) in x.iter().zip(y.iter()) {
                if !py_eq(p, q) {
                    return order(p, q);
                }
            }
            Ok(x.len().cmp(&y.len()))
        }
        _ => match (a.as_int(), b.as_int()) {
            (Some(x), Some(y)) => Ok(x.cmp(&y)),
            _ => match (a.as_f64(), b.as_f64()) {
                (Some(x), Some(y)) => Ok(x.partial_cmp(&y).unwrap_or(Ordering::Equal)),
                _ => Err(Error::python(format!(
                    "TypeError: '<' not supported between instances of '{}' and '{}'",
                    a.type_name(),
                    b.type_name()
                ))),
            },
        },
    }
}

pub fn compare(op: CmpOp, a: &Value, b: &Value) -> Result<bool> {
    Ok(match op {
        CmpOp::Eq => py_eq(a, b),
        CmpOp::Ne => !py_eq(a, b),
        CmpOp::Lt | CmpOp::Le | CmpOp::Gt | CmpOp::Ge => {
            // NaN compares false with everything.
            if let (Some(x), Some(y)) = (a.as_f64(), b.as_f64()) {
                if x.is_nan() || y.is_nan() {
                    return Ok(false);
                }
            }
            let o = order(a, b)?;
            match op {
                CmpOp::Lt => o == Ordering::Less,
                CmpOp::Le => o != Ordering::Greater,
                CmpOp::Gt => o == Ordering::Greater,
                _ => o != Ordering::Less,
            }
        }
        CmpOp::In => contains(b, a)?,
        CmpOp::NotIn => !contains(b, a)?,
        CmpOp::Is => is_same(a, b),
        CmpOp::IsNot => !is_same(a, b),
    })
}

fn is_same(a: &Value, b: &Value) -> bool {
    use Value::*;
    match (a, b) {
        (None, None) => true,
        (Bool(x), Bool(y)) => x == y,
        (List(x), List(y)) => std::rc::Rc::ptr_eq(x, y),
        (Dict(x), Dict(y)) => std::rc::Rc::ptr_eq(x, y),
        (Tuple(x), Tuple(y)) => std::rc::Rc::ptr_eq(x, y),
        (Concept(x), Concept(y)) => std::rc::Rc::ptr_eq(x, y),
        (Int(x), Int(y)) => x == y,
        (Str(x), Str(y)) => x == y,
        _ => false,
    }
}

fn contains(container: &Value, item: &Value) -> Result<bool> {
    match container {
        Value::Str(s) => match item {
            Value::Str(i) => Ok(s.contains(i.as_ref())),
            _ => Err(Error::python("TypeError: 'in <string>' requires string as left operand")),
        },
        Value::Dict(d) => Ok(d.borrow().get(item).is_some()),
        Value::Tuple(_) | Value::List(_) => Ok(container.iter_items()?.iter().any(|x| py_eq(x, item))),
        v => Err(Error::python(format!("TypeError: argument of type '{}' is not iterable", v.type_name()))),
    }
}

pub fn check_hashable(k: &Value) -> Result<()> {
    match k {
        Value::List(_) | Value::Dict(_) => {
            Err(Error::python(format!("TypeError: unhashable type: '{}'", k.type_name())))
        }
        _ => Ok(()),
    }
}

fn norm_index(i: i64, len: usize) -> Option<usize> {
    let len = len as i64;
    let j = if i < 0 { i + len } else { i };
    if j < 0 || j >= len {
        None
    } else {
        Some(j as usize)
    }
}

pub fn get_item(obj: &Value, idx: &Value) -> Result<Value> {
    if let Value::Array(a) = obj {
        return super::numpy::get_item(&a.borrow(), idx);
    }
    if let Some((a, b, c)) = as_slice(idx) {
        return match obj {
            Value::Str(s) => {
                let chars: Vec<char> = s.chars().collect();
                let ix = slice_indices(chars.len(), &a, &b, &c)?;
                Ok(Value::str(&ix.iter().map(|&i| chars[i]).collect::<String>()))
            }
            Value::List(_) | Value::Tuple(_) => {
                let items = obj.iter_items()?;
                let ix = slice_indices(items.len(), &a, &b, &c)?;
                let v: Vec<Value> = ix.iter().map(|&i| items[i].clone()).collect();
                Ok(if matches!(obj, Value::List(_)) { Value::list(v) } else { Value::tuple(v) })
            }
            v => Err(Error::python(format!("TypeError: '{}' object is not subscriptable", v.type_name()))),
        };
    }
    match obj {
        Value::List(_) | Value::Tuple(_) | Value::Str(_) => {
            let i = idx.as_int().ok_or_else(|| {
                Error::python(format!(
                    "TypeError: {} indices must be integers, not {}",
                    obj.type_name(),
                    idx.type_name()
                ))
            })?;
            let items: Vec<Value> = match obj {
                Value::List(l) => {
                    let l = l.borrow();
                    let j = norm_index(i, l.len())
                        .ok_or_else(|| Error::python(format!("IndexError: list index {i} out of range")))?;
                    return Ok(l[j].clone());
                }
                _ => obj.iter_items()?,
            };
            let j = norm_index(i, items.len())
                .ok_or_else(|| Error::python(format!("IndexError: {} index {i} out of range", obj.type_name())))?;
            Ok(items[j].clone())
        }
        Value::Dict(d) => {
            d.borrow().get(idx).cloned().ok_or_else(|| Error::python(format!("KeyError: {}", format::repr(idx))))
        }
        Value::Concept(c) => concept_item(c, idx),
        v => Err(Error::python(format!("TypeError: '{}' object is not subscriptable", v.type_name()))),
    }
}

/// `table['PARA', row]` (1-based row), as Code_Aster tables allow.
fn concept_item(c: &crate::concepts::ConceptRef, idx: &Value) -> Result<Value> {
    use crate::concepts::{Cell, ConceptData};
    let data = c.data();
    match &*data {
        ConceptData::Table(t) => {
            let (para, row) = match idx {
                Value::Tuple(p) if p.len() == 2 => (p[0].clone(), p[1].clone()),
                _ => return Err(Error::python("a table is indexed as TABLE['PARA', row]")),
            };
            let para = para.as_str().ok_or_else(|| Error::python("table parameter must be a string"))?;
            let row = row.as_int().ok_or_else(|| Error::python("table row must be an integer"))?;
            let col = t
                .column(para)
                .ok_or_else(|| Error::python(format!("KeyError: table {} has no parameter '{para}'", c.label())))?;
            if row < 1 || row as usize > t.nrows() {
                return Err(Error::python(format!(
                    "IndexError: table {} has {} rows, row {row} requested",
                    c.label(),
                    t.nrows()
                )));
            }
            Ok(match &t.columns[col].cells[row as usize - 1] {
                Cell::Int(i) => Value::Int(*i),
                Cell::Real(f) => Value::Float(*f),
                Cell::Text(s) => Value::str(s),
                Cell::Empty => Value::None,
            })
        }
        ConceptData::Pending => {
            Err(Error::python(format!("the content of {} is only known when the file is run, not checked", c.label())))
        }
        _ => Err(Error::python(format!("TypeError: '{}' object is not subscriptable", c.kind()))),
    }
}

pub fn set_item(obj: &Value, idx: Value, v: Value) -> Result<()> {
    match obj {
        Value::Array(a) => {
            // The value is read before the array is borrowed: `a[0] = a[1]` reads a.
            let v = match &v {
                Value::Array(x) if std::rc::Rc::ptr_eq(x, a) => x.borrow().clone().value(),
                _ => v,
            };
            super::numpy::set_item(&mut a.borrow_mut(), &idx, &v)
        }
        Value::List(l) => {
            let i = idx.as_int().ok_or_else(|| Error::python("TypeError: list indices must be integers"))?;
            let mut l = l.borrow_mut();
            let n = l.len();
            let j = norm_index(i, n)
                .ok_or_else(|| Error::python(format!("IndexError: list assignment index {i} out of range")))?;
            l[j] = v;
            Ok(())
        }
        Value::Dict(d) => {
            check_hashable(&idx)?;
            d.borrow_mut().set(idx, v);
            Ok(())
        }
        o => Err(Error::python(format!("TypeError: '{}' object does not support item assignment", o.type_name()))),
    }
}

pub fn del_item(obj: &Value, idx: &Value) -> Result<()> {
    match obj {
        Value::List(l) => {
            let i = idx.as_int().ok_or_else(|| Error::python("TypeError: list indices must be integers"))?;
            let mut l = l.borrow_mut();
            let n = l.len();
            let j = norm_index(i, n).ok_or_else(|| Error::python("IndexError: list index out of range"))?;
            l.remove(j);
            Ok(())
        }
        Value::Dict(d) => d
            .borrow_mut()
            .remove(idx)
            .map(|_| ())
            .ok_or_else(|| Error::python(format!("KeyError: {}", format::repr(idx)))),
        o => Err(Error::python(format!("TypeError: '{}' object doesn't support item deletion", o.type_name()))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::value::Builtin;

    #[test]
    fn python_integer_semantics() {
        let i = Value::Int;
        assert!(matches!(binop(BinOp::FloorDiv, &i(-7), &i(2)).unwrap(), Value::Int(-4)));
        assert!(matches!(binop(BinOp::Mod, &i(-7), &i(2)).unwrap(), Value::Int(1)));
        assert!(matches!(binop(BinOp::Mod, &i(7), &i(-2)).unwrap(), Value::Int(-1)));
        assert!(matches!(binop(BinOp::Div, &i(7), &i(2)).unwrap(), Value::Float(f) if f == 3.5));
        assert!(matches!(binop(BinOp::Pow, &i(2), &i(-1)).unwrap(), Value::Float(f) if f == 0.5));
        assert!(binop(BinOp::Div, &i(1), &i(0)).is_err());
        assert!(matches!(binop(BinOp::FloorDiv, &Value::Float(-7.0), &i(2)).unwrap(), Value::Float(f) if f == -4.0));
    }

    #[test]
    fn slices() {
        let l = Value::list((0..6).map(Value::Int).collect());
        let s = Value::tuple(vec![Value::Builtin(Builtin("slice")), Value::Int(1), Value::None, Value::Int(2)]);
        assert_eq!(format::to_str(&get_item(&l, &s).unwrap()), "[1, 3, 5]");
        let r = Value::tuple(vec![Value::Builtin(Builtin("slice")), Value::None, Value::None, Value::Int(-1)]);
        assert_eq!(format::to_str(&get_item(&l, &r).unwrap()), "[5, 4, 3, 2, 1, 0]");
    }
}

#[cfg(test)]
mod review_tests {
    use super::*;

    #[test]
    fn floor_division_and_overflow_as_cpython() {
        assert!(
            matches!(binop(BinOp::FloorDiv, &Value::Float(1.0), &Value::Float(0.1)).unwrap(), Value::Float(f) if f == 9.0)
        );
        assert!(
            matches!(binop(BinOp::FloorDiv, &Value::Float(-7.0), &Value::Float(2.0)).unwrap(), Value::Float(f) if f == -4.0)
        );
        assert!(binop(BinOp::Mod, &Value::Int(i64::MIN), &Value::Int(-1)).is_err());
        assert!(binop(BinOp::FloorDiv, &Value::Int(i64::MIN), &Value::Int(-1)).is_err());
        assert!(matches!(binop(BinOp::FloorDiv, &Value::Int(7), &Value::Int(-2)).unwrap(), Value::Int(-4)));
    }
}
