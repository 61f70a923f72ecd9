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
    Array(ArrayRef),
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
            Value::Array(a) => truthy(&a.borrow())?,
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

// ------------------------------------------------------------------ numpy arrays (interp::numpy)

/// The element type of an array.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum DType {
    Bool,
    Int,
    Float,
}

/// A 1-D or 2-D array (`dims` has one or two entries), row-major; integers and booleans are held as
/// exact f64 values.
#[derive(Debug, Clone, PartialEq)]
pub struct Array {
    pub dims: Vec<usize>,
    pub data: Vec<f64>,
    pub dtype: DType,
}

pub type ArrayRef = Rc<RefCell<Array>>;

impl Array {
    pub fn new(dims: Vec<usize>, data: Vec<f64>, dtype: DType) -> Array {
        debug_assert_eq!(dims.iter().product::<usize>(), data.len());
        Array { dims, data, dtype }
    }
    pub fn vector(data: Vec<f64>, dtype: DType) -> Array {
        Array { dims: vec![data.len()], data, dtype }
    }
    pub fn value(self) -> Value {
        Value::Array(Rc::new(RefCell::new(self)))
    }
    pub fn ndim(&self) -> usize {
        self.dims.len()
    }
    pub fn size(&self) -> usize {
        self.data.len()
    }
    pub fn rows(&self) -> usize {
        self.dims[0]
    }
    pub fn cols(&self) -> usize {
        if self.dims.len() == 2 {
            self.dims[1]
        } else {
            1
        }
    }
    /// An element as a Python value of the array's type.
    pub fn scalar(&self, x: f64) -> Value {
        scalar(x, self.dtype)
    }
    /// The items a Python iteration yields: elements of a 1-D array, rows of a 2-D one.
    pub fn items(&self) -> Vec<Value> {
        match self.ndim() {
            1 => self.data.iter().map(|x| self.scalar(*x)).collect(),
            _ => (0..self.rows())
                .map(|i| Array::vector(self.data[i * self.cols()..(i + 1) * self.cols()].to_vec(), self.dtype).value())
                .collect(),
        }
    }
}

pub fn scalar(x: f64, dtype: DType) -> Value {
    match dtype {
        DType::Bool => Value::Bool(x != 0.0),
        DType::Int => Value::Int(x as i64),
        DType::Float => Value::Float(x),
    }
}

/// The truth value of an array: its one element; ambiguous for more.
pub fn truthy(a: &Array) -> Result<bool> {
    match a.size() {
        1 => Ok(a.data[0] != 0.0),
        0 => Ok(false),
        _ => Err(Error::python(
            "ValueError: The truth value of an array with more than one element is ambiguous. Use a.any() or a.all()",
        )),
    }
}

/// Resolve a Python slice to the list of indices it selects.
pub(super) fn slice_indices(len: usize, start: &Value, stop: &Value, step: &Value) -> Result<Vec<usize>> {
    let step = match step {
        Value::None => 1,
        v => v.as_int().ok_or_else(|| Error::python("TypeError: slice indices must be integers"))?,
    };
    if step == 0 {
        return Err(Error::python("ValueError: slice step cannot be zero"));
    }
    let len = len as i64;
    let clamp = |v: &Value, default: i64| -> Result<i64> {
        match v {
            Value::None => Ok(default),
            v => {
                let i = v.as_int().ok_or_else(|| Error::python("TypeError: slice indices must be integers"))?;
                let i = if i < 0 { i + len } else { i };
                Ok(if step > 0 { i.clamp(0, len) } else { i.clamp(-1, len - 1) })
            }
        }
    };
    let (s, e) =
        if step > 0 { (clamp(start, 0)?, clamp(stop, len)?) } else { (clamp(start, len - 1)?, clamp(stop, -1)?) };
    let mut out = Vec::new();
    let mut i = s;
    while (step > 0 && i < e) || (step < 0 && i > e) {
        out.push(i as usize);
        i += step;
    }
    Ok(out)
}

pub(super) fn as_slice(idx: &Value) -> Option<(Value, Value, Value)> {
    if let Value::Tuple(t) = idx {
        if t.len() == 4 && matches!(t[0], Value::Builtin(Builtin("slice"))) {
            return Some((t[1].clone(), t[2].clone(), t[3].clone()));
        }
    }
    None
}
