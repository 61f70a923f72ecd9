//! Python values of the command-file subset.

use crate::concepts::ConceptRef;
use crate::diag::{Error, Result};
use crate::syntax::ast::FuncDef;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

pub type Scope = Rc<RefCell<HashMap<String, Value>>>;

/// A user function (`def` or `lambda`) with the globals it was defined in
/// and, for nested definitions, the enclosing locals it closes over
/// (innermost first).
#[derive(Debug)]
pub struct Function {
    pub def: Rc<FuncDef>,
    pub defaults: Vec<Option<Value>>,
    pub globals: Scope,
    pub closure: Vec<Scope>,
}

/// A plain class (`class NAME:`): its name and the namespace its body made (methods, attributes).
#[derive(Debug)]
pub struct Class {
    pub name: String,
    pub ns: Scope,
}

/// An object of a plain class, with its own attributes.
#[derive(Debug)]
pub struct Instance {
    pub class: Rc<Class>,
    pub attrs: RefCell<HashMap<String, Value>>,
}

/// Built-in callables, addressed by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Builtin(pub &'static str);

#[derive(Debug, Clone)]
pub enum Value {
    None,
    Bool(bool),
    Int(i64),
    Float(f64),
    Complex(f64, f64),
    Str(Rc<str>),
    Tuple(Rc<Vec<Value>>),
    List(Rc<RefCell<Vec<Value>>>),
    Dict(Rc<RefCell<Dict>>),
    Func(Rc<Function>),
    Builtin(Builtin),
    /// A method bound to its receiver: `"a,b".split`, `lst.append`, ...
    Method(Box<Value>, &'static str),
    Module(&'static str),
    Class(Rc<Class>),
    Instance(Rc<Instance>),
    /// A method of an object, bound to it: `obj.method`.
    BoundMethod(Rc<Instance>, Rc<Function>),
    /// A numpy array (the subset of `interp::numpy`).
    Array(super::numpy::ArrayRef),
    /// A Code_Aster command, called by the interpreter through the host.
    Command(&'static str),
    Concept(ConceptRef),
}

/// An insertion-ordered dictionary (command files use small ones).
#[derive(Debug, Clone, Default)]
pub struct Dict {
    pub items: Vec<(Value, Value)>,
}

impl Dict {
    pub fn get(&self, k: &Value) -> Option<&Value> {
        self.items.iter().find(|(kk, _)| py_eq(kk, k)).map(|(_, v)| v)
    }
    pub fn set(&mut self, k: Value, v: Value) {
        match self.items.iter_mut().find(|(kk, _)| py_eq(kk, &k)) {
            Some(slot) => slot.1 = v,
            None => self.items.push((k, v)),
        }
    }
    pub fn remove(&mut self, k: &Value) -> Option<Value> {
        let pos = self.items.iter().position(|(kk, _)| py_eq(kk, k))?;
        Some(self.items.remove(pos).1)
    }
}

impl Value {
    pub fn str(s: &str) -> Value {
        Value::Str(Rc::from(s))
    }
    pub fn list(v: Vec<Value>) -> Value {
        Value::List(Rc::new(RefCell::new(v)))
    }
    pub fn tuple(v: Vec<Value>) -> Value {
        Value::Tuple(Rc::new(v))
    }
    pub fn dict(d: Dict) -> Value {
        Value::Dict(Rc::new(RefCell::new(d)))
    }

    /// The Python type name, for messages.
    pub fn type_name(&self) -> String {
        match self {
            Value::None => "NoneType".into(),
            Value::Bool(_) => "bool".into(),
            Value::Int(_) => "int".into(),
            Value::Float(_) => "float".into(),
            Value::Complex(..) => "complex".into(),
            Value::Str(_) => "str".into(),
            Value::Tuple(_) => "tuple".into(),
            Value::List(_) => "list".into(),
            Value::Dict(_) => "dict".into(),
            Value::Func(_) => "function".into(),
            Value::Builtin(_) | Value::Method(..) => "builtin_function_or_method".into(),
            Value::Module(_) => "module".into(),
            Value::Array(_) => "numpy.ndarray".into(),
            Value::Class(_) => "type".into(),
            Value::Instance(i) => i.class.name.clone(),
            Value::BoundMethod(..) => "method".into(),
            Value::Command(_) => "command".into(),
            Value::Concept(c) => c.kind().aster_name().into(),
        }
    }

    pub fn truthy(&self) -> Result<bool> {
        Ok(match self {
            Value::None => false,
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Float(f) => *f != 0.0,
            Value::Complex(a, b) => *a != 0.0 || *b != 0.0,
            Value::Str(s) => !s.is_empty(),
            Value::Tuple(t) => !t.is_empty(),
            Value::List(l) => !l.borrow().is_empty(),
            Value::Dict(d) => !d.borrow().items.is_empty(),
            Value::Array(a) => super::numpy::truthy(&a.borrow())?,
            _ => true,
        })
    }

    /// Numeric value as f64 (bool and int promote), else None.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Bool(b) => Some(*b as i64 as f64),
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            _ => None,
        }
    }
    pub fn as_int(&self) -> Option<i64> {
        match self {
            Value::Bool(b) => Some(*b as i64),
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// The items of a sequence-like value, or a type error.
    pub fn iter_items(&self) -> Result<Vec<Value>> {
        match self {
            Value::Tuple(t) => Ok(t.as_ref().clone()),
            Value::List(l) => Ok(l.borrow().clone()),
            Value::Str(s) => Ok(s.chars().map(|c| Value::str(&c.to_string())).collect()),
            Value::Dict(d) => Ok(d.borrow().items.iter().map(|(k, _)| k.clone()).collect()),
            Value::Array(a) => Ok(a.borrow().items()),
            v => Err(Error::python(format!("'{}' object is not iterable", v.type_name()))),
        }
    }
}

/// Python `==`.
pub fn py_eq(a: &Value, b: &Value) -> bool {
    use Value::*;
    match (a, b) {
        (None, None) => true,
        (Str(x), Str(y)) => x == y,
        (Tuple(x), Tuple(y)) => x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| py_eq(p, q)),
        (List(x), List(y)) => {
            let (x, y) = (x.borrow(), y.borrow());
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| py_eq(p, q))
        }
        (Dict(x), Dict(y)) => {
            let (x, y) = (x.borrow(), y.borrow());
            x.items.len() == y.items.len()
                && x.items.iter().all(|(k, v)| y.get(k).map(|w| py_eq(v, w)).unwrap_or(false))
        }
        (Complex(a1, b1), Complex(a2, b2)) => a1 == a2 && b1 == b2,
        (Concept(x), Concept(y)) => std::rc::Rc::ptr_eq(x, y),
        (Func(x), Func(y)) => std::rc::Rc::ptr_eq(x, y),
        (Builtin(x), Builtin(y)) => x == y,
        (Command(x), Command(y)) => x == y,
        (Module(x), Module(y)) => x == y,
        (Array(x), Array(y)) => std::rc::Rc::ptr_eq(x, y),
        (Class(x), Class(y)) => std::rc::Rc::ptr_eq(x, y),
        (Instance(x), Instance(y)) => std::rc::Rc::ptr_eq(x, y),
        _ => match (a.as_int(), b.as_int()) {
            (Some(x), Some(y)) => x == y,
            _ => match (a.as_f64(), b.as_f64()) {
                (Some(x), Some(y)) => x == y,
                _ => false,
            },
        },
    }
}
