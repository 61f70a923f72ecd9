//! Python's text forms of values: `repr`, `str`, and the values' side of
//! `%`-formatting and of the format-spec mini-language used by `str.format`,
//! f-strings and `format()` (the formatting itself is the neutral `text` module).

use super::value::{Dict, Value};
use crate::diag::{Error, Result};
use crate::text::{self, float_repr, FormatError, Number, Operand};

pub fn str_repr(s: &str) -> String {
    let quote = if s.contains('\'') && !s.contains('"') { '"' } else { '\'' };
    let mut out = String::new();
    out.push(quote);
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            // Python writes the other control characters (and the Latin-1 ones, and the soft hyphen) as \xhh.
            c if (c as u32) < 0x20 || (0x7f..=0xa0).contains(&(c as u32)) || c == '\u{ad}' => {
                out.push_str(&format!("\\x{:02x}", c as u32))
            }
            c if c == quote => {
                out.push('\\');
                out.push(c)
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

pub fn repr(v: &Value) -> String {
    match v {
        Value::Str(s) => str_repr(s),
        Value::Array(a) => super::numpy::text(&a.borrow(), true),
        _ => to_str(v),
    }
}

fn complex_repr(a: f64, b: f64) -> String {
    let im = |x: f64| {
        let r = float_repr(x);
        r.strip_suffix(".0").map(str::to_string).unwrap_or(r)
    };
    if a == 0.0 && !a.is_sign_negative() {
        format!("{}j", im(b))
    } else {
        let sign = if b < 0.0 || (b == 0.0 && b.is_sign_negative()) { "-" } else { "+" };
        format!("({}{}{}j)", im(a), sign, im(b.abs()))
    }
}

/// `str(v)`.
pub fn to_str(v: &Value) -> String {
    match v {
        Value::None => "None".into(),
        Value::Bool(b) => if *b { "True" } else { "False" }.into(),
        Value::Int(i) => i.to_string(),
        Value::Float(f) => float_repr(*f),
        Value::Complex(a, b) => complex_repr(*a, *b),
        Value::Str(s) => s.to_string(),
        Value::Tuple(t) => {
            let items: Vec<String> = t.iter().map(repr).collect();
            if items.len() == 1 {
                format!("({},)", items[0])
            } else {
                format!("({})", items.join(", "))
            }
        }
        Value::List(l) => format!("[{}]", l.borrow().iter().map(repr).collect::<Vec<_>>().join(", ")),
        Value::Dict(d) => dict_repr(&d.borrow()),
        Value::Func(f) => format!("<function {}>", f.def.name),
        Value::Builtin(b) => format!("<built-in function {}>", b.0),
        Value::Method(_, m) => format!("<built-in method {m}>"),
        Value::Module(m) => format!("<module '{m}'>"),
        Value::Array(a) => super::numpy::text(&a.borrow(), false),
        Value::Class(c) => format!("<class '__main__.{}'>", c.name),
        Value::Instance(i) => format!("<__main__.{} object>", i.class.name),
        Value::BoundMethod(i, f) => {
            format!("<bound method {}.{} of <__main__.{} object>>", i.class.name, f.def.name, i.class.name)
        }
        Value::Command(c) => format!("<command {c}>"),
        Value::Concept(c) => c.label(),
    }
}

fn dict_repr(d: &Dict) -> String {
    let items: Vec<String> = d.items.iter().map(|(k, v)| format!("{}: {}", repr(k), repr(v))).collect();
    format!("{{{}}}", items.join(", "))
}

// ----------------------------------------------------------------- formatting

/// A text-module error as the Python exception it is.
fn py(e: FormatError) -> Error {
    Error::python(e.to_string())
}

impl Operand for Value {
    fn number(&self) -> Option<Number> {
        match self {
            Value::Bool(b) => Some(Number::Bool(*b)),
            Value::Int(i) => Some(Number::Int(*i)),
            Value::Float(f) => Some(Number::Float(*f)),
            _ => None,
        }
    }
    fn text(&self) -> Option<&str> {
        self.as_str()
    }
    fn type_name(&self) -> String {
        Value::type_name(self)
    }
    fn to_str(&self) -> String {
        to_str(self)
    }
    fn repr(&self) -> String {
        repr(self)
    }
}

/// Apply a format spec to a value (`format(v, spec)`).
pub fn format_value(v: &Value, spec: &str) -> Result<String> {
    text::spec::format(v, spec).map_err(py)
}

/// `fmt % args`.
pub fn percent(fmt: &str, args: &Value) -> Result<String> {
    match args {
        Value::Tuple(t) => text::printf::format(fmt, t.as_ref(), None).map_err(py),
        Value::Dict(d) => {
            let lookup = |key: &str| -> std::result::Result<Value, FormatError> {
                d.borrow().get(&Value::str(key)).cloned().ok_or_else(|| FormatError::new("KeyError", str_repr(key)))
            };
            text::printf::format(fmt, std::slice::from_ref(args), Some(&lookup)).map_err(py)
        }
        v => text::printf::format(fmt, std::slice::from_ref(v), None).map_err(py),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_formats() {
        let t = Value::tuple(vec![Value::Int(5), Value::Float(1.23456), Value::str("ab")]);
        assert_eq!(percent("%3d|%.2f|%-4s|", &t).unwrap(), "  5|1.23|ab  |");
        assert_eq!(percent("%e", &Value::Float(12345.678)).unwrap(), "1.234568e+04");
        assert_eq!(percent("%g", &Value::Float(0.00001234)).unwrap(), "1.234e-05");
        assert_eq!(percent("%g", &Value::Float(100000.0)).unwrap(), "100000");
        assert_eq!(percent("%g", &Value::Float(1e6)).unwrap(), "1e+06");
        assert_eq!(percent("%05.1f", &Value::Float(-2.25)).unwrap(), "-02.2");
        assert_eq!(percent("100%%", &Value::tuple(vec![])).unwrap(), "100%");
    }

    #[test]
    fn format_specs() {
        assert_eq!(format_value(&Value::Float(1.23456), ".3f").unwrap(), "1.235");
        assert_eq!(format_value(&Value::Int(42), ">6").unwrap(), "    42");
        assert_eq!(format_value(&Value::Int(42), "06d").unwrap(), "000042");
        assert_eq!(format_value(&Value::str("ab"), "^6").unwrap(), "  ab  ");
        assert_eq!(format_value(&Value::Float(1234.5), ".3e").unwrap(), "1.234e+03");
        assert_eq!(format_value(&Value::Float(0.5), "").unwrap(), "0.5");
        assert_eq!(format_value(&Value::Int(1234567), ",").unwrap(), "1,234,567");
        assert_eq!(format_value(&Value::Float(2.0), ".3").unwrap(), "2.0");
    }
}
