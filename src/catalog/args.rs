//! Validated arguments: what a stage receives instead of the AST.
//!
//! Every keyword value has been checked against the schema and converted to a
//! typed [`Val`]; defaults are filled in. Accessors return `None` / empty for
//! absent keywords, and [`Args::err`] builds an error located at a keyword.

use crate::concepts::{ConceptKind, ConceptRef};
use crate::diag::{Error, Result};
use crate::interp::Value;
use crate::syntax::ast::Span;

#[derive(Debug, Clone)]
pub enum Val {
    I(i64),
    R(f64),
    C(f64, f64),
    T(String),
    Concept(ConceptRef),
    /// A Python callable (user function, builtin).
    Callable(Value),
}

impl Val {
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Val::I(i) => Some(*i as f64),
            Val::R(r) => Some(*r),
            _ => None,
        }
    }
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Val::T(s) => Some(s),
            _ => None,
        }
    }
    /// Short text for messages.
    pub fn show(&self) -> String {
        match self {
            Val::I(i) => i.to_string(),
            Val::R(r) => crate::interp::format::float_repr(*r),
            Val::C(a, b) => format!("({a}, {b})"),
            Val::T(t) => format!("'{t}'"),
            Val::Concept(c) => c.label(),
            Val::Callable(v) => crate::interp::format::to_str(v),
        }
    }
}

#[derive(Debug, Clone)]
pub enum ArgValue {
    Simple(Vec<Val>),
    Factor(Vec<Args>),
}

#[derive(Debug, Clone)]
pub struct Arg {
    pub name: String,
    pub value: ArgValue,
    /// Where the keyword was written (the call for defaults).
    pub span: Span,
    /// True when the value is a schema default, not written by the user.
    pub defaulted: bool,
}

/// The validated keywords of one command call or one factor occurrence.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The command name, and the factor path for occurrences ("CMD/FACT").
    pub path: String,
    pub span: Span,
    pub items: Vec<Arg>,
}

impl Args {
    pub fn get(&self, name: &str) -> Option<&Arg> {
        self.items.iter().find(|a| a.name == name)
    }
    pub fn has(&self, name: &str) -> bool {
        self.get(name).is_some()
    }
    /// Present because the user wrote it (not a default).
    pub fn given(&self, name: &str) -> bool {
        self.get(name).map(|a| !a.defaulted).unwrap_or(false)
    }
    pub fn span_of(&self, name: &str) -> Span {
        self.get(name).map(|a| a.span).unwrap_or(self.span)
    }
    pub fn vals(&self, name: &str) -> &[Val] {
        match self.get(name).map(|a| &a.value) {
            Some(ArgValue::Simple(v)) => v,
            _ => &[],
        }
    }
    pub fn val(&self, name: &str) -> Option<&Val> {
        self.vals(name).first()
    }
    pub fn text(&self, name: &str) -> Option<&str> {
        self.val(name).and_then(Val::as_text)
    }
    pub fn texts(&self, name: &str) -> Vec<String> {
        self.vals(name).iter().filter_map(|v| v.as_text().map(str::to_string)).collect()
    }
    pub fn real(&self, name: &str) -> Option<f64> {
        self.val(name).and_then(Val::as_f64)
    }
    pub fn reals(&self, name: &str) -> Vec<f64> {
        self.vals(name).iter().filter_map(Val::as_f64).collect()
    }
    pub fn int(&self, name: &str) -> Option<i64> {
        match self.val(name) {
            Some(Val::I(i)) => Some(*i),
            _ => None,
        }
    }
    pub fn ints(&self, name: &str) -> Vec<i64> {
        self.vals(name)
            .iter()
            .filter_map(|v| match v {
                Val::I(i) => Some(*i),
                _ => None,
            })
            .collect()
    }
    pub fn concept(&self, name: &str) -> Option<ConceptRef> {
        match self.val(name) {
            Some(Val::Concept(c)) => Some(c.clone()),
            _ => None,
        }
    }
    pub fn concepts(&self, name: &str) -> Vec<ConceptRef> {
        self.vals(name)
            .iter()
            .filter_map(|v| match v {
                Val::Concept(c) => Some(c.clone()),
                _ => None,
            })
            .collect()
    }
    pub fn facts(&self, name: &str) -> &[Args] {
        match self.get(name).map(|a| &a.value) {
            Some(ArgValue::Factor(v)) => v,
            _ => &[],
        }
    }
    pub fn fact(&self, name: &str) -> Option<&Args> {
        self.facts(name).first()
    }

    /// Stop on keywords the stage does not implement, if the user gave them.
    pub fn refuse(&self, names: &[&str]) -> Result<()> {
        match names.iter().find(|n| self.given(n)) {
            Some(n) => Err(self.err(n, "not supported yet")),
            None => Ok(()),
        }
    }

    /// A runtime error located at keyword `name` of this command.
    pub fn err(&self, name: &str, msg: impl Into<String>) -> Error {
        let msg = msg.into();
        let kw = self.path.split_once('/').map(|(_, f)| format!("{f}/{name}")).unwrap_or_else(|| name.to_string());
        Error::runtime(format!("{kw}: {msg}")).at(self.span_of(name))
    }

    /// Attach keyword `kw`'s location to an error that has none, keeping its message and kind.
    pub fn locate(&self, e: Error, kw: &str) -> Error {
        if e.span.is_some() {
            return e;
        }
        let mut out = self.err(kw, e.msg.clone());
        out.kind = e.kind;
        out
    }

    /// The mandatory text of a keyword the schema guarantees.
    pub fn req_text(&self, name: &str) -> Result<&str> {
        self.text(name).ok_or_else(|| self.err(name, "a text value is required"))
    }
    pub fn req_real(&self, name: &str) -> Result<f64> {
        self.real(name).ok_or_else(|| self.err(name, "a real value is required"))
    }
    pub fn req_concept(&self, name: &str) -> Result<ConceptRef> {
        self.concept(name).ok_or_else(|| self.err(name, "a concept is required"))
    }

    /// The concept of keyword `name`, checked to be one of `kinds`.
    pub fn concept_of(&self, name: &str, kinds: &[ConceptKind]) -> Result<Option<ConceptRef>> {
        match self.concept(name) {
            Some(c) if kinds.contains(&c.kind()) => Ok(Some(c)),
            Some(c) => Err(self.err(name, format!("{} is a {}, expected {:?}", c.label(), c.kind(), kinds))),
            None => Ok(None),
        }
    }
}
