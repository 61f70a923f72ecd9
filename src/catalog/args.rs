//! Validated arguments: what a stage receives instead of the AST.
//!
//! Every keyword value has been checked against the schema and converted to a
//! typed [`Val`]; defaults are filled in. Accessors return `None` / empty for
//! absent keywords, and [`Args::err`] builds an error located at a keyword.

use crate::concepts::{ConceptKind, ConceptRef};
use crate::diag::{Error, Result};
use crate::interp::Value;
use crate::syntax::ast::Span;
use std::cell::{Cell, RefCell};
use std::collections::BTreeSet;
use std::rc::Rc;

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
            Val::R(r) => crate::text::float_repr(*r),
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
    /// Set when a stage looked the keyword up (read it, tested it or refused it).
    pub read: Cell<bool>,
}

/// The validated keywords of one command call or one factor occurrence.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The command name, and the factor path for occurrences ("CMD/FACT").
    pub path: String,
    pub span: Span,
    pub items: Vec<Arg>,
    /// The keywords the schema declares at this level (every block included); None for an open
    /// schema or an `Args` built by hand.
    pub declared: Option<Rc<Vec<&'static str>>>,
}

thread_local! {
    static UNDECLARED: RefCell<BTreeSet<String>> = const { RefCell::new(BTreeSet::new()) };
}

/// The lookups of keywords the schema does not declare since the last call (`CMD/FACT/NAME`): a stage
/// that asks for a misspelt or foreign keyword would silently read "absent", so the tests assert that
/// this stays empty over every command file they run.
pub fn take_undeclared_lookups() -> Vec<String> {
    UNDECLARED.with(|u| std::mem::take(&mut *u.borrow_mut()).into_iter().collect())
}

/// Keywords that never change what is computed, whatever their value: INFO sets the verbosity of
/// Code_Aster's own messages, and our message file has its own fixed report.
const NO_EFFECT: &[&str] = &["INFO"];

/// A keyword given by the user that the stage never looked at.
#[derive(Debug, Clone)]
pub struct Unread {
    /// `CMD/FACT/NAME`.
    pub path: String,
    pub name: String,
    pub span: Span,
}

impl Args {
    /// The keyword, if present; the lookup is checked against the schema and marks the keyword read.
    #[track_caller]
    pub fn get(&self, name: &str) -> Option<&Arg> {
        if let Some(d) = &self.declared {
            if !d.contains(&name) {
                let at = std::panic::Location::caller();
                UNDECLARED
                    .with(|u| u.borrow_mut().insert(format!("{}/{name} (at {}:{})", self.path, at.file(), at.line())));
            }
        }
        let a = self.items.iter().find(|a| a.name == name);
        if let Some(a) = a {
            a.read.set(true);
        }
        a
    }

    /// Does the schema declare this keyword at this level (always true for an open schema)? Code shared
    /// by several commands asks before it looks up a keyword only some of them declare.
    #[track_caller]
    pub fn declares(&self, name: &str) -> bool {
        self.declared.as_ref().is_none_or(|d| d.contains(&name))
    }

    /// [`Args::texts`] of a keyword the schema may not declare (empty when it does not).
    #[track_caller]
    pub fn texts_if_declared(&self, name: &str) -> Vec<String> {
        if self.declares(name) {
            self.texts(name)
        } else {
            Vec::new()
        }
    }

    /// [`Args::text`] of a keyword the schema may not declare.
    #[track_caller]
    pub fn text_if_declared(&self, name: &str) -> Option<&str> {
        if self.declares(name) {
            self.text(name)
        } else {
            None
        }
    }

    /// [`Args::has`] of a keyword the schema may not declare.
    #[track_caller]
    pub fn has_if_declared(&self, name: &str) -> bool {
        self.declares(name) && self.has(name)
    }

    /// The keywords the user wrote that no stage looked up, in factor occurrences too (a factor keyword
    /// never looked up is reported as a whole).
    #[track_caller]
    pub fn unread(&self) -> Vec<Unread> {
        let mut out = Vec::new();
        for a in &self.items {
            if a.defaulted || NO_EFFECT.contains(&a.name.as_str()) {
                continue;
            }
            if !a.read.get() {
                out.push(Unread { path: self.path.clone(), name: a.name.clone(), span: a.span });
            } else if let ArgValue::Factor(occs) = &a.value {
                for o in occs {
                    out.extend(o.unread());
                }
            }
        }
        out
    }

    /// Forget every read: the catalogue's own checks (rules, blocks, the produced type) look keywords up
    /// before the stage runs.
    pub fn reset_reads(&self) {
        for a in &self.items {
            a.read.set(false);
            if let ArgValue::Factor(occs) = &a.value {
                occs.iter().for_each(Args::reset_reads);
            }
        }
    }

    /// Mark every keyword of this level read: for stages that pass the whole occurrence on (a table
    /// row, a formula's context) or that have validated it as a whole.
    #[track_caller]
    pub fn read_all(&self) {
        for a in &self.items {
            a.read.set(true);
            if let ArgValue::Factor(occs) = &a.value {
                occs.iter().for_each(Args::read_all);
            }
        }
    }
    #[track_caller]
    pub fn has(&self, name: &str) -> bool {
        self.get(name).is_some()
    }
    /// Present because the user wrote it (not a default).
    #[track_caller]
    pub fn given(&self, name: &str) -> bool {
        self.get(name).map(|a| !a.defaulted).unwrap_or(false)
    }
    #[track_caller]
    pub fn span_of(&self, name: &str) -> Span {
        self.get(name).map(|a| a.span).unwrap_or(self.span)
    }
    #[track_caller]
    pub fn vals(&self, name: &str) -> &[Val] {
        match self.get(name).map(|a| &a.value) {
            Some(ArgValue::Simple(v)) => v,
            _ => &[],
        }
    }
    #[track_caller]
    pub fn val(&self, name: &str) -> Option<&Val> {
        self.vals(name).first()
    }
    #[track_caller]
    pub fn text(&self, name: &str) -> Option<&str> {
        self.val(name).and_then(Val::as_text)
    }
    #[track_caller]
    pub fn texts(&self, name: &str) -> Vec<String> {
        self.vals(name).iter().filter_map(|v| v.as_text().map(str::to_string)).collect()
    }
    #[track_caller]
    pub fn real(&self, name: &str) -> Option<f64> {
        self.val(name).and_then(Val::as_f64)
    }
    #[track_caller]
    pub fn reals(&self, name: &str) -> Vec<f64> {
        self.vals(name).iter().filter_map(Val::as_f64).collect()
    }
    #[track_caller]
    pub fn int(&self, name: &str) -> Option<i64> {
        match self.val(name) {
            Some(Val::I(i)) => Some(*i),
            _ => None,
        }
    }
    #[track_caller]
    pub fn ints(&self, name: &str) -> Vec<i64> {
        self.vals(name)
            .iter()
            .filter_map(|v| match v {
                Val::I(i) => Some(*i),
                _ => None,
            })
            .collect()
    }
    #[track_caller]
    pub fn concept(&self, name: &str) -> Option<ConceptRef> {
        match self.val(name) {
            Some(Val::Concept(c)) => Some(c.clone()),
            _ => None,
        }
    }
    #[track_caller]
    pub fn concepts(&self, name: &str) -> Vec<ConceptRef> {
        self.vals(name)
            .iter()
            .filter_map(|v| match v {
                Val::Concept(c) => Some(c.clone()),
                _ => None,
            })
            .collect()
    }
    #[track_caller]
    pub fn facts(&self, name: &str) -> &[Args] {
        match self.get(name).map(|a| &a.value) {
            Some(ArgValue::Factor(v)) => v,
            _ => &[],
        }
    }
    #[track_caller]
    pub fn fact(&self, name: &str) -> Option<&Args> {
        self.facts(name).first()
    }

    /// Stop on keywords the stage does not implement, if the user gave them.
    /// Stop on the first of `names` the user gave: keywords the schema declares that the stage does not
    /// support (yet). Names the schema does not declare here cannot be given and are passed over.
    #[track_caller]
    pub fn refuse(&self, names: &[&str]) -> Result<()> {
        match names.iter().filter(|n| self.declares(n)).find(|n| self.given(n)) {
            Some(n) => Err(self.err(n, "not supported yet")),
            None => Ok(()),
        }
    }

    /// A runtime error located at keyword `name` of this command.
    #[track_caller]
    pub fn err(&self, name: &str, msg: impl Into<String>) -> Error {
        let msg = msg.into();
        let kw = self.path.split_once('/').map(|(_, f)| format!("{f}/{name}")).unwrap_or_else(|| name.to_string());
        Error::runtime(format!("{kw}: {msg}")).at(self.span_of(name))
    }

    /// Attach keyword `kw`'s location to an error that has none, keeping its message and kind.
    #[track_caller]
    pub fn locate(&self, e: Error, kw: &str) -> Error {
        if e.span.is_some() {
            return e;
        }
        let mut out = self.err(kw, e.msg.clone());
        out.kind = e.kind;
        out
    }

    /// The mandatory text of a keyword the schema guarantees.
    #[track_caller]
    pub fn req_text(&self, name: &str) -> Result<&str> {
        self.text(name).ok_or_else(|| self.err(name, "a text value is required"))
    }
    #[track_caller]
    pub fn req_real(&self, name: &str) -> Result<f64> {
        self.real(name).ok_or_else(|| self.err(name, "a real value is required"))
    }
    #[track_caller]
    pub fn req_concept(&self, name: &str) -> Result<ConceptRef> {
        self.concept(name).ok_or_else(|| self.err(name, "a concept is required"))
    }

    /// The concept of keyword `name`, checked to be one of `kinds`.
    #[track_caller]
    pub fn concept_of(&self, name: &str, kinds: &[ConceptKind]) -> Result<Option<ConceptRef>> {
        match self.concept(name) {
            Some(c) if kinds.contains(&c.kind()) => Ok(Some(c)),
            Some(c) => Err(self.err(name, format!("{} is a {}, expected {:?}", c.label(), c.kind(), kinds))),
            None => Ok(None),
        }
    }
}
