//! Python-compatible text forms of numbers, and the two formatting mini-languages Python offers for
//! them: `%`-directives (`'%5.2f' % x`) and format specs (`format(x, '>8.3e')`, `str.format`,
//! f-strings). Neutral: it knows no value type of the interpreter, only numbers and text, so the
//! interpreter, the catalogue and the stages all format numbers the same way through it.
//!
//! Values of a language reach the formatters through the [`Operand`] trait (what Python's `%` and
//! `format()` need to know of a value: a number, a string, or something with a `str` and a `repr`).

pub mod fortran;
mod number;
pub mod printf;
pub mod spec;

pub use number::{fixed, float_repr, general, nonfinite, sci};

use std::fmt;

/// The widest field and the longest precision a format may ask for. Python would try to allocate
/// what `'%.2000000000f'` asks for; we stop with a `MemoryError` naming the limit instead.
pub const MAX_WIDTH: usize = 10_000_000;

/// A width or precision within [`MAX_WIDTH`], else the `MemoryError` naming it (`what`: "format width").
pub fn check_size(what: &str, n: usize) -> Result<(), FormatError> {
    if n > MAX_WIDTH {
        return Err(FormatError::new("MemoryError", format!("{what} {n} exceeds the limit of {MAX_WIDTH} characters")));
    }
    Ok(())
}

/// A formatting failure, as the Python exception it is: `ValueError: incomplete format`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FormatError {
    /// The Python exception's name (`ValueError`, `TypeError`, ...).
    pub exception: &'static str,
    pub message: String,
}

impl FormatError {
    pub fn new(exception: &'static str, message: impl Into<String>) -> FormatError {
        FormatError { exception, message: message.into() }
    }
    pub fn value(message: impl Into<String>) -> FormatError {
        FormatError::new("ValueError", message)
    }
    pub fn type_error(message: impl Into<String>) -> FormatError {
        FormatError::new("TypeError", message)
    }
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.exception, self.message)
    }
}

impl std::error::Error for FormatError {}

/// Python's `ascii()` of a `repr`: non-ASCII characters as `\xhh`, `\uhhhh` or `\Uhhhhhhhh`.
pub fn ascii(repr: &str) -> String {
    let mut out = String::new();
    for ch in repr.chars() {
        match ch as u32 {
            0..=0x7f => out.push(ch),
            n @ 0x80..=0xff => out.push_str(&format!("\\x{n:02x}")),
            n @ 0x100..=0xffff => out.push_str(&format!("\\u{n:04x}")),
            n => out.push_str(&format!("\\U{n:08x}")),
        }
    }
    out
}

/// A number as Python's formatters see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Number {
    Bool(bool),
    Int(i64),
    Float(f64),
}

impl Number {
    pub fn as_f64(self) -> f64 {
        match self {
            Number::Bool(b) => b as i64 as f64,
            Number::Int(i) => i as f64,
            Number::Float(f) => f,
        }
    }
    /// The integer of an int or bool.
    pub fn as_int(self) -> Option<i64> {
        match self {
            Number::Bool(b) => Some(b as i64),
            Number::Int(i) => Some(i),
            Number::Float(_) => None,
        }
    }
}

/// What the formatters need to know of a value.
pub trait Operand {
    /// The value as a number, if it is an int, a bool or a float.
    fn number(&self) -> Option<Number>;
    /// The value as text, if it is a string.
    fn text(&self) -> Option<&str>;
    /// Python's type name, for messages (`NoneType`, `list`).
    fn type_name(&self) -> String;
    /// `str(v)`.
    fn to_str(&self) -> String;
    /// `repr(v)`.
    fn repr(&self) -> String;
}

/// A float is an operand: the stages format numbers with `%` directives.
impl Operand for f64 {
    fn number(&self) -> Option<Number> {
        Some(Number::Float(*self))
    }
    fn text(&self) -> Option<&str> {
        None
    }
    fn type_name(&self) -> String {
        "float".into()
    }
    fn to_str(&self) -> String {
        float_repr(*self)
    }
    fn repr(&self) -> String {
        float_repr(*self)
    }
}
