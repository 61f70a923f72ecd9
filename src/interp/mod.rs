//! The interpreter: Python semantics for the command-file subset.
//!
//! It evaluates the AST and hands every Code_Aster command call to a
//! [`Host`] as a list of keyword arguments; it knows nothing of the
//! catalogue or of what commands do.

mod builtins;
pub mod fast;
pub mod format;
mod modules;
mod numpy;
mod ops;
pub mod value;

use crate::concepts::ConceptRef;
use crate::diag::{Error, Result};
use crate::syntax::ast::*;
use std::cell::{Cell, RefCell};
use std::collections::{HashMap, HashSet};
use std::rc::Rc;
pub use value::{Builtin, Dict, Scope, Value};

/// What Code_Aster's runner puts in a command file's namespace before it runs (`from math import *`,
/// `CA`, `CO`), unless the file imports the commands itself (`modules::predefine`).
pub fn predefine(globals: &Scope, src: &str) {
    if modules::predefine(globals, src) {
        globals.borrow_mut().extend(builtins::math_names());
    }
}

/// A keyword argument of a command call, with its location.
#[derive(Debug, Clone)]
pub struct KwArg {
    pub name: String,
    pub value: Value,
    pub span: Span,
}

/// What the interpreter needs from its embedder.
pub trait Host {
    /// Run a command. `target` is the variable the result is assigned to.
    fn call_command(
        &mut self,
        name: &'static str,
        kwargs: Vec<KwArg>,
        call_span: Span,
        target: Option<&str>,
    ) -> Result<Value>;
    /// `print(...)` output.
    fn print(&mut self, text: &str);
    /// True once FIN has run: the rest of the file is not executed.
    fn finished(&self) -> bool;
    /// Is `name` a command of the catalogue?
    fn command(&self, name: &str) -> Option<&'static str>;
    /// The closest command name, for "did you mean" hints.
    fn suggest_command(&self, name: &str) -> Option<&'static str>;
}

fn looks_like_command(n: &str) -> bool {
    n.len() > 2 && n.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') && n.contains('_')
}

/// A FORMULE: an expression over named parameters, evaluated in the context
/// of the command file that defined it.
#[derive(Debug)]
pub struct Formula {
    pub nom_para: Vec<String>,
    pub text: String,
    expr: Expr,
    context: Vec<(String, Value)>,
    globals: Scope,
    /// The expression compiled when it is plain arithmetic ([`fast`]); else the interpreter evaluates it.
    fast: Option<fast::Fast>,
}

impl crate::concepts::function::Evaluate for Formula {
    fn eval(&self, values: &[f64]) -> Result<f64> {
        Formula::eval(self, values)
    }
}

impl Formula {
    /// The FORMULE concept's data: its parameters, its text and this expression as its evaluation.
    pub fn into_concept(self) -> crate::concepts::Formula {
        crate::concepts::Formula::new(self.nom_para.clone(), self.text.clone(), Rc::new(self))
    }

    /// Parse `text`; `span` locates the VALE keyword for errors.
    pub fn new(text: &str, nom_para: Vec<String>, context: Vec<(String, Value)>, globals: Scope) -> Result<Formula> {
        let expr = crate::syntax::parse_expr(text.trim(), 0)
            .map_err(|e| Error::python(format!("in formula '{}': {}", text.trim(), e.message)))?;
        let fast = fast::compile(&expr, &nom_para, &context);
        Ok(Formula { nom_para, text: text.to_string(), expr, context, globals, fast })
    }

    /// Evaluate with the parameters bound to `values` (in NOM_PARA order).
    pub fn eval(&self, values: &[f64]) -> Result<f64> {
        if values.len() != self.nom_para.len() {
            return Err(Error::runtime(format!(
                "formula '{}' takes {} parameter(s) ({}), {} given",
                self.text.trim(),
                self.nom_para.len(),
                self.nom_para.join(", "),
                values.len()
            )));
        }
        if let Some(f) = &self.fast {
            let v = f
                .eval(values)
                .map_err(|e| Error::runtime(format!("evaluating formula '{}': {}", self.text.trim(), e.msg)))?;
            return v.as_f64().ok_or_else(|| {
                Error::runtime(format!("formula '{}' returned a {}, not a number", self.text.trim(), v.type_name()))
            });
        }
        let locals: Scope = Rc::new(RefCell::new(HashMap::new()));
        {
            let mut l = locals.borrow_mut();
            for (k, v) in builtins::math_names() {
                l.insert(k, v);
            }
            for (k, v) in &self.context {
                l.insert(k.clone(), v.clone());
            }
            for (k, v) in self.nom_para.iter().zip(values) {
                l.insert(k.clone(), Value::Float(*v));
            }
        }
        let mut it = Interp::new(self.globals.clone(), None);
        it.frames.push(Frame { locals, enclosing: Vec::new(), global_names: HashSet::new() });
        let v = it
            .eval(&self.expr)
            .map_err(|e| Error::runtime(format!("evaluating formula '{}': {}", self.text.trim(), e.msg)))?;
        v.as_f64().ok_or_else(|| {
            Error::runtime(format!("formula '{}' returned a {}, not a number", self.text.trim(), v.type_name()))
        })
    }
}

/// Call a Python callable outside any running interpreter (stages use this
/// for Python functions handed to commands).
pub fn call_value(f: &Value, args: Vec<Value>) -> Result<Value> {
    let globals = match f {
        Value::Func(func) => func.globals.clone(),
        _ => Rc::new(RefCell::new(HashMap::new())),
    };
    let mut it = Interp::new(globals, None);
    it.call(f, args, Vec::new(), Span::default())
}

struct Frame {
    locals: Scope,
    enclosing: Vec<Scope>,
    global_names: HashSet<String>,
}

enum Flow {
    Normal,
    Return(Value),
    Break,
    Continue,
    Stop,
}

pub struct Interp<'h> {
    pub globals: Scope,
    host: Option<&'h mut dyn Host>,
    frames: Vec<Frame>,
    depth: usize,
    /// Where the statement being executed is, for whoever runs the interpreter (see [`Interp::track`]).
    position: Option<Rc<Cell<Span>>>,
    /// Statements and loop iterations executed, to check the run's deadline every `TICKS_PER_CHECK`.
    ticks: u32,
}

/// The interpreter reads the clock (for the run's deadline) once per this many statements and
/// loop iterations: a few microseconds apart.
const TICKS_PER_CHECK: u32 = 256;

const MAX_DEPTH: usize = 200;

impl<'h> Interp<'h> {
    pub fn new(globals: Scope, host: Option<&'h mut dyn Host>) -> Self {
        Interp { globals, host, frames: Vec::new(), depth: 0, position: None, ticks: 0 }
    }

    /// Keep `at` set to the span of the statement being executed, so that the runner can locate
    /// what it was doing if the interpreter stops by a panic.
    pub fn track(&mut self, at: Rc<Cell<Span>>) {
        self.position = Some(at);
    }

    /// Execute a whole module at top level.
    pub fn run(&mut self, module: &Module) -> Result<()> {
        match self.exec_block(&module.body)? {
            Flow::Normal | Flow::Stop => Ok(()),
            Flow::Return(_) => Err(Error::python("SyntaxError: 'return' outside function")),
            Flow::Break | Flow::Continue => Err(Error::python("SyntaxError: 'break' or 'continue' outside loop")),
        }
    }

    /// Count a statement or a loop iteration; past the run's deadline, stop (`diag::check_deadline`).
    fn tick(&mut self) -> Result<()> {
        self.ticks = self.ticks.wrapping_add(1);
        if self.ticks.is_multiple_of(TICKS_PER_CHECK) {
            crate::diag::check_deadline()?;
        }
        Ok(())
    }

    fn finished(&self) -> bool {
        self.host.as_ref().map(|h| h.finished()).unwrap_or(false)
    }

    fn exec_block(&mut self, body: &[Stmt]) -> Result<Flow> {
        for s in body {
            if let Some(p) = &self.position {
                p.set(s.span);
            }
            self.tick().map_err(|e| e.at(s.span))?;
            let flow = self.exec(s).map_err(|e| e.at(s.span))?;
            if !matches!(flow, Flow::Normal) {
                return Ok(flow);
            }
            if self.finished() {
                return Ok(Flow::Stop);
            }
        }
        Ok(Flow::Normal)
    }

    fn exec(&mut self, s: &Stmt) -> Result<Flow> {
        match &s.kind {
            StmtKind::Expr(e) => {
                self.eval(e)?;
            }
            StmtKind::Assign { targets, value } => {
                let target_name = match targets.as_slice() {
                    [Expr { kind: ExprKind::Name(n), .. }] => Some(n.as_str()),
                    _ => None,
                };
                let v = match (&value.kind, target_name) {
                    (ExprKind::Call(f, args), Some(name)) => self.eval_call(f, args, value.span, Some(name))?,
                    _ => self.eval(value)?,
                };
                if let (Value::Concept(c), Some(n)) = (&v, target_name) {
                    c.set_name(n);
                }
                for t in targets {
                    self.assign(t, v.clone())?;
                }
            }
            StmtKind::AugAssign { target, op, value } => {
                let cur = self.eval(target)?;
                let rhs = self.eval(value)?;
                let new = match (&cur, op) {
                    // In-place list extension keeps identity, as in Python.
                    (Value::List(l), BinOp::Add) => {
                        let items = rhs.iter_items()?;
                        l.borrow_mut().extend(items);
                        cur.clone()
                    }
                    _ => ops::binop(*op, &cur, &rhs).map_err(|e| e.at(s.span))?,
                };
                self.assign(target, new)?;
            }
            StmtKind::If { branches, orelse } => {
                for (cond, body) in branches {
                    if self.eval(cond)?.truthy()? {
                        return self.exec_block(body);
                    }
                }
                return self.exec_block(orelse);
            }
            StmtKind::For { target, iter, body, orelse } => {
                let items = self.eval(iter)?.iter_items().map_err(|e| e.at(iter.span))?;
                for item in items {
                    self.tick()?;
                    self.assign(target, item)?;
                    match self.exec_block(body)? {
                        Flow::Break => return Ok(Flow::Normal),
                        Flow::Continue | Flow::Normal => {}
                        f => return Ok(f),
                    }
                }
                return self.exec_block(orelse);
            }
            StmtKind::While { cond, body, orelse } => {
                let mut guard: u64 = 0;
                while self.eval(cond)?.truthy()? {
                    self.tick()?;
                    guard += 1;
                    if guard > 100_000_000 {
                        return Err(Error::python("while loop did not terminate after 1e8 iterations"));
                    }
                    match self.exec_block(body)? {
                        Flow::Break => return Ok(Flow::Normal),
                        Flow::Continue | Flow::Normal => {}
                        f => return Ok(f),
                    }
                }
                return self.exec_block(orelse);
            }
            StmtKind::Def(def) => {
                let f = self.make_function(def)?;
                self.store(&def.name, f);
            }
            StmtKind::Return(e) => {
                if self.frames.is_empty() {
                    return Err(Error::python("SyntaxError: 'return' outside function"));
                }
                let v = match e {
                    Some(e) => self.eval(e)?,
                    None => Value::None,
                };
                return Ok(Flow::Return(v));
            }
            StmtKind::Pass => {}
            StmtKind::Break => return Ok(Flow::Break),
            StmtKind::Continue => return Ok(Flow::Continue),
            StmtKind::Del(targets) => {
                for t in targets {
                    self.delete(t)?;
                }
            }
            StmtKind::Global(names) => {
                if let Some(f) = self.frames.last_mut() {
                    f.global_names.extend(names.iter().cloned());
                }
            }
            StmtKind::Assert(c, m) => {
                if !self.eval(c)?.truthy()? {
                    let msg = match m {
                        Some(m) => format::to_str(&self.eval(m)?),
                        None => String::new(),
                    };
                    return Err(Error::python(format!("AssertionError: {msg}")));
                }
            }
            StmtKind::Try { body, handlers, orelse, finalbody } => {
                let outcome = match self.exec_block(body) {
                    Ok(Flow::Normal) => self.exec_block(orelse),
                    Ok(flow) => Ok(flow),
                    Err(e) => match exception_class(&e) {
                        None => Err(e),
                        Some(class) => {
                            let mut caught = None;
                            for h in handlers {
                                if handler_matches(h, class)? {
                                    caught = Some(h);
                                    break;
                                }
                            }
                            match caught {
                                None => Err(e),
                                Some(h) => {
                                    if let Some(n) = &h.name {
                                        // `str(e)`: the message without its class, as CPython shows it.
                                        let text = e.msg.strip_prefix(class).and_then(|r| r.strip_prefix(": "));
                                        self.store(n, Value::Str(Rc::from(text.unwrap_or(&e.msg))));
                                    }
                                    self.exec_block(&h.body)
                                }
                            }
                        }
                    },
                };
                // `finally` runs whatever happened; its own exit (an error, a return, a break) wins.
                match self.exec_block(finalbody)? {
                    Flow::Normal => return outcome,
                    flow => return Ok(flow),
                }
            }
            StmtKind::Raise(e) => {
                let msg = match e {
                    Some(e) => format::to_str(&self.eval(e)?),
                    None => "exception".into(),
                };
                return Err(Error::python(format!("raised: {msg}")));
            }
            StmtKind::With { items, body } => {
                for (ctx, target) in items {
                    let v = self.eval(ctx)?;
                    let entered = context_enter(&v).map_err(|e| e.at(ctx.span))?;
                    if let Some(t) = target {
                        self.assign(t, entered)?;
                    }
                }
                return self.exec_block(body);
            }
            StmtKind::Class(def) => {
                let c = self.make_class(def)?;
                self.store(&def.name, c);
            }
            StmtKind::Decorated { decorators, def } => {
                let name = match &def.kind {
                    StmtKind::Def(f) => f.name.clone(),
                    StmtKind::Class(c) => c.name.clone(),
                    _ => unreachable!("decorators decorate a def or a class"),
                };
                let decos: Vec<Value> = decorators.iter().map(|d| self.eval(d)).collect::<Result<_>>()?;
                self.exec(def)?;
                let mut v = self.lookup(&name, def.span)?;
                for d in decos.iter().rev() {
                    v = self.call(d, vec![v], Vec::new(), s.span)?;
                }
                self.store(&name, v);
            }
            StmtKind::Import(names) => {
                for (module, alias) in names {
                    let m = builtins::import_module(module, alias.is_some())?;
                    let bind = alias.clone().unwrap_or_else(|| module.split('.').next().unwrap().to_string());
                    self.store(&bind, m);
                }
            }
            StmtKind::FromImport { module, names } => {
                let bindings = builtins::from_import(module, names.as_deref())?;
                for (k, v) in bindings {
                    self.store(&k, v);
                }
            }
        }
        Ok(Flow::Normal)
    }

    /// Run a class body in its own namespace: the class's methods and attributes.
    fn make_class(&mut self, def: &Rc<ClassDef>) -> Result<Value> {
        for b in &def.bases {
            let ok = matches!(&b.kind, ExprKind::Name(n) if n == "object");
            if !ok {
                return Err(Error::unsupported(format!(
                    "class {}: inheritance from other classes is not supported (plain classes only)",
                    def.name
                ))
                .at(b.span));
            }
        }
        let ns: Scope = Rc::new(RefCell::new(HashMap::new()));
        let enclosing = match self.frames.last() {
            Some(f) => {
                let mut c = vec![f.locals.clone()];
                c.extend(f.enclosing.iter().cloned());
                c
            }
            None => Vec::new(),
        };
        self.frames.push(Frame { locals: ns.clone(), enclosing, global_names: HashSet::new() });
        let r = self.exec_block(&def.body);
        self.frames.pop();
        match r? {
            Flow::Normal => {}
            _ => return Err(Error::python("SyntaxError: 'return', 'break' or 'continue' in a class body").at(def.span)),
        }
        Ok(Value::Class(Rc::new(value::Class { name: def.name.clone(), ns })))
    }

    fn make_function(&mut self, def: &Rc<FuncDef>) -> Result<Value> {
        let mut defaults = Vec::new();
        for p in &def.params {
            defaults.push(match p {
                Param::Plain(_, Some(d)) => Some(self.eval(d)?),
                _ => None,
            });
        }
        let closure = match self.frames.last() {
            Some(f) => {
                let mut c = vec![f.locals.clone()];
                c.extend(f.enclosing.iter().cloned());
                c
            }
            None => Vec::new(),
        };
        Ok(Value::Func(Rc::new(value::Function { def: def.clone(), defaults, globals: self.globals.clone(), closure })))
    }

    // ------------------------------------------------------------ names

    fn store(&mut self, name: &str, v: Value) {
        match self.frames.last() {
            Some(f) if !f.global_names.contains(name) => {
                f.locals.borrow_mut().insert(name.to_string(), v);
            }
            _ => {
                self.globals.borrow_mut().insert(name.to_string(), v);
            }
        }
    }

    fn lookup(&self, name: &str, span: Span) -> Result<Value> {
        if let Some(f) = self.frames.last() {
            if let Some(v) = f.locals.borrow().get(name) {
                return Ok(v.clone());
            }
            for s in &f.enclosing {
                if let Some(v) = s.borrow().get(name) {
                    return Ok(v.clone());
                }
            }
        }
        if let Some(v) = self.globals.borrow().get(name) {
            return Ok(v.clone());
        }
        if let Some(h) = &self.host {
            if let Some(c) = h.command(name) {
                return Ok(Value::Command(c));
            }
        }
        if let Some(b) = builtins::lookup_builtin(name) {
            return Ok(b);
        }
        Err(Error::python(format!("NameError: name '{name}' is not defined")).at(span))
    }

    fn assign(&mut self, target: &Expr, v: Value) -> Result<()> {
        match &target.kind {
            ExprKind::Name(n) => {
                self.store(n, v);
                Ok(())
            }
            ExprKind::Tuple(items) | ExprKind::List(items) => {
                let vals = v.iter_items().map_err(|e| e.at(target.span))?;
                if vals.len() != items.len() {
                    return Err(Error::python(format!(
                        "ValueError: cannot unpack {} values into {} targets",
                        vals.len(),
                        items.len()
                    ))
                    .at(target.span));
                }
                for (t, v) in items.iter().zip(vals) {
                    self.assign(t, v)?;
                }
                Ok(())
            }
            ExprKind::Subscript(obj, idx) => {
                let o = self.eval(obj)?;
                let i = self.eval(idx)?;
                ops::set_item(&o, i, v).map_err(|e| e.at(target.span))
            }
            ExprKind::Attr(obj, name) => {
                let o = self.eval(obj)?;
                match &o {
                    Value::Instance(i) => {
                        i.attrs.borrow_mut().insert(name.clone(), v);
                        Ok(())
                    }
                    Value::Class(c) => {
                        c.ns.borrow_mut().insert(name.clone(), v);
                        Ok(())
                    }
                    o => Err(Error::python(format!(
                        "AttributeError: cannot set attribute '{name}' of a '{}' object",
                        o.type_name()
                    ))
                    .at(target.span)),
                }
            }
            _ => Err(Error::python("SyntaxError: cannot assign to expression").at(target.span)),
        }
    }

    fn delete(&mut self, target: &Expr) -> Result<()> {
        match &target.kind {
            ExprKind::Name(n) => {
                let removed = match self.frames.last() {
                    Some(f) => f.locals.borrow_mut().remove(n),
                    None => self.globals.borrow_mut().remove(n),
                };
                removed
                    .map(|_| ())
                    .ok_or_else(|| Error::python(format!("NameError: name '{n}' is not defined")).at(target.span))
            }
            ExprKind::Subscript(obj, idx) => {
                let o = self.eval(obj)?;
                let i = self.eval(idx)?;
                ops::del_item(&o, &i).map_err(|e| e.at(target.span))
            }
            _ => Err(Error::python("SyntaxError: cannot delete expression").at(target.span)),
        }
    }

    // ------------------------------------------------------------ expressions

    pub fn eval(&mut self, e: &Expr) -> Result<Value> {
        self.eval_inner(e).map_err(|err| err.at(e.span))
    }

    fn eval_inner(&mut self, e: &Expr) -> Result<Value> {
        Ok(match &e.kind {
            ExprKind::None => Value::None,
            ExprKind::Bool(b) => Value::Bool(*b),
            ExprKind::Int(i) => Value::Int(*i),
            ExprKind::Float(f) => Value::Float(*f),
            ExprKind::Imag(f) => Value::Complex(0.0, *f),
            ExprKind::Str(s) => Value::str(s),
            ExprKind::FString(parts) => Value::str(&self.fstring(parts)?),
            ExprKind::Name(n) => self.lookup(n, e.span)?,
            ExprKind::Tuple(items) => Value::tuple(self.eval_items(items)?),
            ExprKind::List(items) => Value::list(self.eval_items(items)?),
            ExprKind::Dict(items) => {
                let mut d = Dict::default();
                for (k, v) in items {
                    let k = self.eval(k)?;
                    ops::check_hashable(&k).map_err(|er| er.at(e.span))?;
                    let v = self.eval(v)?;
                    d.set(k, v);
                }
                Value::dict(d)
            }
            ExprKind::ListComp(elt, comps) => {
                let mut out = Vec::new();
                self.comprehension(comps, &mut |it, _| {
                    out.push(it.eval(elt)?);
                    Ok(())
                })?;
                Value::list(out)
            }
            ExprKind::GenExp(elt, comps) => {
                let mut out = Vec::new();
                self.comprehension(comps, &mut |it, _| {
                    out.push(it.eval(elt)?);
                    Ok(())
                })?;
                Value::tuple(out)
            }
            ExprKind::DictComp(k, v, comps) => {
                let mut d = Dict::default();
                self.comprehension(comps, &mut |it, _| {
                    let kk = it.eval(k)?;
                    ops::check_hashable(&kk)?;
                    let vv = it.eval(v)?;
                    d.set(kk, vv);
                    Ok(())
                })?;
                Value::dict(d)
            }
            ExprKind::BinOp(a, op, b) => {
                let a = self.eval(a)?;
                let b = self.eval(b)?;
                ops::binop(*op, &a, &b)?
            }
            ExprKind::Unary(op, a) => {
                let a = self.eval(a)?;
                ops::unary(*op, &a)?
            }
            ExprKind::Compare(first, rest) => {
                let mut left = self.eval(first)?;
                // An element-wise comparison of arrays gives an array (a single comparison only).
                if let [(op, r)] = rest.as_slice() {
                    if !matches!(op, CmpOp::In | CmpOp::NotIn | CmpOp::Is | CmpOp::IsNot) {
                        let right = self.eval(r)?;
                        if matches!(left, Value::Array(_)) || matches!(right, Value::Array(_)) {
                            return numpy::compare(*op, &left, &right);
                        }
                        return Ok(Value::Bool(ops::compare(*op, &left, &right)?));
                    }
                }
                for (op, r) in rest {
                    let right = self.eval(r)?;
                    if !ops::compare(*op, &left, &right)? {
                        return Ok(Value::Bool(false));
                    }
                    left = right;
                }
                Value::Bool(true)
            }
            ExprKind::And(a, b) => {
                let a = self.eval(a)?;
                if !a.truthy()? {
                    a
                } else {
                    self.eval(b)?
                }
            }
            ExprKind::Or(a, b) => {
                let a = self.eval(a)?;
                if a.truthy()? {
                    a
                } else {
                    self.eval(b)?
                }
            }
            ExprKind::IfExp { cond, then, orelse } => {
                if self.eval(cond)?.truthy()? {
                    self.eval(then)?
                } else {
                    self.eval(orelse)?
                }
            }
            ExprKind::Lambda(def) => self.make_function(def)?,
            ExprKind::Call(f, args) => self.eval_call(f, args, e.span, None)?,
            ExprKind::Subscript(obj, idx) => {
                let o = self.eval(obj)?;
                let i = self.eval(idx)?;
                ops::get_item(&o, &i)?
            }
            ExprKind::Slice(a, b, c) => {
                let mut part = |x: &Option<Box<Expr>>| -> Result<Value> {
                    match x {
                        Some(x) => self.eval(x),
                        None => Ok(Value::None),
                    }
                };
                let (a, b, c) = (part(a)?, part(b)?, part(c)?);
                // A slice is carried as a tagged tuple to get_item.
                Value::tuple(vec![Value::Builtin(Builtin("slice")), a, b, c])
            }
            ExprKind::Attr(obj, name) => {
                let o = self.eval(obj)?;
                builtins::get_attr(&o, name)?
            }
        })
    }

    fn eval_items(&mut self, items: &[Expr]) -> Result<Vec<Value>> {
        items.iter().map(|i| self.eval(i)).collect()
    }

    fn fstring(&mut self, parts: &[FPart]) -> Result<String> {
        let mut out = String::new();
        for p in parts {
            match p {
                FPart::Lit(s) => out.push_str(s),
                FPart::Field { expr, conv, spec } => {
                    let v = self.eval(expr)?;
                    let v = match conv {
                        Some('r') => Value::str(&format::repr(&v)),
                        Some('a') => Value::str(&crate::text::ascii(&format::repr(&v))),
                        Some('s') => Value::str(&format::to_str(&v)),
                        _ => v,
                    };
                    let spec = self.fstring(spec)?;
                    out.push_str(&format::format_value(&v, &spec)?);
                }
            }
        }
        Ok(out)
    }

    /// Run `body` for every binding of the comprehension clauses, in a scope
    /// of its own (as Python 3 does).
    fn comprehension(
        &mut self,
        comps: &[Comprehension],
        body: &mut dyn FnMut(&mut Self, ()) -> Result<()>,
    ) -> Result<()> {
        let (locals, enclosing) = match self.frames.last() {
            Some(f) => {
                let mut enc = vec![f.locals.clone()];
                enc.extend(f.enclosing.iter().cloned());
                (Rc::new(RefCell::new(HashMap::new())), enc)
            }
            None => (Rc::new(RefCell::new(HashMap::new())), Vec::new()),
        };
        // The first iterable is evaluated in the enclosing scope.
        let first = self.eval(&comps[0].iter)?.iter_items().map_err(|e| e.at(comps[0].iter.span))?;
        self.frames.push(Frame { locals, enclosing, global_names: HashSet::new() });
        let r = self.comp_level(comps, 0, Some(first), body);
        self.frames.pop();
        r
    }

    fn comp_level(
        &mut self,
        comps: &[Comprehension],
        level: usize,
        items: Option<Vec<Value>>,
        body: &mut dyn FnMut(&mut Self, ()) -> Result<()>,
    ) -> Result<()> {
        if level == comps.len() {
            return body(self, ());
        }
        let c = &comps[level];
        let items = match items {
            Some(i) => i,
            None => self.eval(&c.iter)?.iter_items().map_err(|e| e.at(c.iter.span))?,
        };
        'outer: for item in items {
            self.tick()?;
            self.assign(&c.target, item)?;
            for cond in &c.conds {
                if !self.eval(cond)?.truthy()? {
                    continue 'outer;
                }
            }
            self.comp_level(comps, level + 1, None, body)?;
        }
        Ok(())
    }

    fn eval_call(&mut self, f: &Expr, args: &[Arg], span: Span, target: Option<&str>) -> Result<Value> {
        let fv = match (&f.kind, self.eval(f)) {
            // Calling an undefined upper-case name: most likely a mistyped command.
            (ExprKind::Name(n), Err(e)) if looks_like_command(n) && self.host.is_some() => {
                let hint = self
                    .host
                    .as_ref()
                    .and_then(|h| h.suggest_command(n))
                    .map(|s| format!(" (did you mean '{s}'?)"))
                    .unwrap_or_default();
                let _ = e;
                return Err(Error::catalog(format!("unknown command '{n}'{hint}")).at(f.span));
            }
            (_, r) => r?,
        };
        let mut pos = Vec::new();
        let mut kw: Vec<KwArg> = Vec::new();
        for a in args {
            match a {
                Arg::Positional(e) => pos.push(self.eval(e)?),
                Arg::Star(e) => {
                    let v = self.eval(e)?;
                    pos.extend(v.iter_items().map_err(|er| er.at(e.span))?);
                }
                Arg::Keyword(name, e, ksp) => {
                    if kw.iter().any(|k| &k.name == name) {
                        return Err(Error::python(format!("SyntaxError: keyword argument repeated: {name}")).at(*ksp));
                    }
                    let value = self.eval(e)?;
                    kw.push(KwArg { name: name.clone(), value, span: *ksp });
                }
                Arg::DoubleStar(e) => {
                    let v = self.eval(e)?;
                    let Value::Dict(d) = &v else {
                        return Err(Error::python(format!(
                            "TypeError: argument after ** must be a mapping, not {}",
                            v.type_name()
                        ))
                        .at(e.span));
                    };
                    for (k, val) in d.borrow().items.iter() {
                        let Some(name) = k.as_str() else {
                            return Err(Error::python("TypeError: keywords must be strings").at(e.span));
                        };
                        if kw.iter().any(|x| x.name == name) {
                            return Err(Error::python(format!(
                                "TypeError: got multiple values for keyword argument '{name}'"
                            ))
                            .at(e.span));
                        }
                        kw.push(KwArg { name: name.to_string(), value: val.clone(), span: e.span });
                    }
                }
            }
        }
        if let Value::Command(name) = fv {
            if !pos.is_empty() {
                return Err(Error::catalog(format!(
                    "{name} takes keyword arguments only ({} positional given)",
                    pos.len()
                ))
                .at(span));
            }
            let Some(host) = self.host.as_mut() else {
                return Err(Error::python(format!("command {name} cannot be called from inside a formula")));
            };
            return host.call_command(name, kw, span, target);
        }
        if let Value::Builtin(Builtin(b @ ("CA.init" | "CA.close"))) = fv {
            return self.ca_init_close(b, pos, kw, span);
        }
        if let Value::Builtin(Builtin("print")) = fv {
            let opt = |name: &str| {
                kw.iter().find(|k| k.name == name && !matches!(k.value, Value::None)).map(|k| format::to_str(&k.value))
            };
            let (sep, end) = (opt("sep"), opt("end"));
            let text: Vec<String> = pos.iter().map(format::to_str).collect();
            let mut line = text.join(sep.as_deref().unwrap_or(" "));
            line.push_str(end.as_deref().unwrap_or("\n"));
            match self.host.as_mut() {
                Some(h) => h.print(&line),
                None => print!("{line}"),
            }
            return Ok(Value::None);
        }
        let kw = kw.into_iter().map(|k| (k.name, k.value)).collect();
        self.call(&fv, pos, kw, span)
    }

    /// `CA.init(OPTIONS..., debug=..., KEYWORDS...)` is DEBUT(KEYWORDS...) (POURSUITE with
    /// "--continue"), `CA.close()` is FIN(): the new-style preamble of a command file.
    fn ca_init_close(&mut self, name: &str, pos: Vec<Value>, mut kw: Vec<KwArg>, span: Span) -> Result<Value> {
        let mut cmd = if name == "CA.init" { "DEBUT" } else { "FIN" };
        for p in &pos {
            match p.as_str() {
                Some("--continue") if name == "CA.init" => cmd = "POURSUITE",
                Some(o) if o.starts_with('-') && name == "CA.init" => {}
                _ => {
                    return Err(Error::python(format!(
                    "TypeError: {name}() takes command-line options ('--test', ...) as positional arguments, got {}",
                    format::repr(p)
                ))
                    .at(span))
                }
            }
        }
        // `debug=` is an option of the runner, not a keyword of DEBUT.
        kw.retain(|k| k.name != "debug");
        let Some(host) = self.host.as_mut() else {
            return Err(Error::python(format!("{name}() cannot be called from inside a formula")));
        };
        let Some(cmd) = host.command(cmd) else {
            return Err(Error::unsupported(format!("{name}(\"--continue\"): POURSUITE is not supported yet")).at(span));
        };
        host.call_command(cmd, kw, span, None)
    }

    /// Call any Python callable.
    pub fn call(&mut self, f: &Value, pos: Vec<Value>, kw: Vec<(String, Value)>, span: Span) -> Result<Value> {
        match f {
            Value::Func(func) => self.call_function(func, pos, kw, span),
            Value::Builtin(b) => builtins::call_builtin(self, b.0, pos, kw),
            Value::Method(recv, name) => builtins::call_method(self, recv, name, pos, kw),
            Value::Concept(c) => call_concept(c, &pos),
            Value::Class(c) => {
                let obj = Rc::new(value::Instance { class: c.clone(), attrs: RefCell::new(HashMap::new()) });
                let init = c.ns.borrow().get("__init__").cloned();
                match init {
                    Some(Value::Func(f)) => {
                        let mut args = vec![Value::Instance(obj.clone())];
                        args.extend(pos);
                        let r = self.call_function(&f, args, kw, span)?;
                        if !matches!(r, Value::None) {
                            return Err(Error::python("TypeError: __init__() should return None"));
                        }
                    }
                    Some(_) => return Err(Error::python("TypeError: __init__ is not a function")),
                    None if !pos.is_empty() || !kw.is_empty() => {
                        return Err(Error::python(format!("TypeError: {}() takes no arguments", c.name)))
                    }
                    None => {}
                }
                Ok(Value::Instance(obj))
            }
            Value::BoundMethod(obj, f) => {
                let mut args = vec![Value::Instance(obj.clone())];
                args.extend(pos);
                self.call_function(f, args, kw, span)
            }
            Value::Instance(i) => {
                let call = i.class.ns.borrow().get("__call__").cloned();
                match call {
                    Some(Value::Func(f)) => {
                        let mut args = vec![f_self(i)];
                        args.extend(pos);
                        self.call_function(&f, args, kw, span)
                    }
                    _ => Err(Error::python(format!("TypeError: '{}' object is not callable", i.class.name))),
                }
            }
            Value::Command(name) => Err(Error::python(format!("command {name} cannot be called here"))),
            v => Err(Error::python(format!("TypeError: '{}' object is not callable", v.type_name()))),
        }
    }

    fn call_function(
        &mut self,
        func: &Rc<value::Function>,
        pos: Vec<Value>,
        kw: Vec<(String, Value)>,
        span: Span,
    ) -> Result<Value> {
        if self.depth >= MAX_DEPTH {
            return Err(Error::python("RecursionError: maximum recursion depth exceeded"));
        }
        let def = &func.def;
        let locals: Scope = Rc::new(RefCell::new(HashMap::new()));
        {
            let mut l = locals.borrow_mut();
            let mut pos_iter = pos.into_iter();
            let mut star: Option<String> = None;
            let mut dstar: Option<String> = None;
            let mut plain: Vec<(&str, &Option<Value>)> = Vec::new();
            for (p, d) in def.params.iter().zip(&func.defaults) {
                match p {
                    Param::Plain(n, _) => plain.push((n, d)),
                    Param::Star(n) => star = Some(n.clone()),
                    Param::DoubleStar(n) => dstar = Some(n.clone()),
                }
            }
            for (n, _) in &plain {
                if let Some(v) = pos_iter.next() {
                    l.insert(n.to_string(), v);
                }
            }
            let extra: Vec<Value> = pos_iter.collect();
            match &star {
                Some(s) => {
                    l.insert(s.clone(), Value::tuple(extra));
                }
                None if !extra.is_empty() => {
                    return Err(Error::python(format!(
                        "TypeError: {}() takes {} positional arguments but {} were given",
                        def.name,
                        plain.len(),
                        plain.len() + extra.len()
                    )));
                }
                None => {}
            }
            let mut kwextra = Dict::default();
            for (k, v) in kw {
                if plain.iter().any(|(n, _)| *n == k) {
                    if l.contains_key(&k) {
                        return Err(Error::python(format!(
                            "TypeError: {}() got multiple values for argument '{k}'",
                            def.name
                        )));
                    }
                    l.insert(k, v);
                } else if dstar.is_some() {
                    kwextra.set(Value::str(&k), v);
                } else {
                    return Err(Error::python(format!(
                        "TypeError: {}() got an unexpected keyword argument '{k}'",
                        def.name
                    )));
                }
            }
            if let Some(ds) = dstar {
                l.insert(ds, Value::dict(kwextra));
            }
            for (n, d) in &plain {
                if !l.contains_key(*n) {
                    match d {
                        Some(v) => {
                            l.insert(n.to_string(), v.clone());
                        }
                        None => {
                            return Err(Error::python(format!(
                                "TypeError: {}() missing required argument: '{n}'",
                                def.name
                            )))
                        }
                    }
                }
            }
        }
        let saved_globals = std::mem::replace(&mut self.globals, func.globals.clone());
        self.frames.push(Frame { locals, enclosing: func.closure.clone(), global_names: HashSet::new() });
        self.depth += 1;
        let r = self.exec_block(&def.body);
        self.depth -= 1;
        self.frames.pop();
        self.globals = saved_globals;
        match r.map_err(|e| e.at(span))? {
            Flow::Return(v) => Ok(v),
            Flow::Normal | Flow::Stop => Ok(Value::None),
            Flow::Break | Flow::Continue => Err(Error::python("SyntaxError: 'break' outside loop")),
        }
    }
}

fn f_self(i: &Rc<value::Instance>) -> Value {
    Value::Instance(i.clone())
}

/// `with CTX [as NAME]:` — the value NAME is bound to. The only context managers are code_aster's
/// `CA.disable_fpe()` (it changes how floating-point errors are trapped, which our arithmetic does not
/// do: a no-op); files and the rest are refused by name.
fn context_enter(v: &Value) -> Result<Value> {
    match v {
        Value::Builtin(Builtin("CA.disable_fpe.context")) => Ok(Value::None),
        other => Err(Error::unsupported(format!(
            "with: a context manager of type '{}' is not supported by aster-rs",
            other.type_name()
        ))),
    }
}

/// Calling a concept: formulas and functions evaluate, as in Code_Aster
/// (`F(0.5)`).
fn call_concept(c: &ConceptRef, pos: &[Value]) -> Result<Value> {
    use crate::concepts::ConceptData;
    let args: Vec<f64> = pos
        .iter()
        .map(|v| {
            v.as_f64().ok_or_else(|| {
                Error::python(format!("TypeError: {} expects numbers, not {}", c.label(), v.type_name()))
            })
        })
        .collect::<Result<_>>()?;
    match &*c.data() {
        ConceptData::Formula(f) => Ok(Value::Float(f.eval(&args)?)),
        ConceptData::Function(f) if args.len() == 1 => Ok(Value::Float(f.eval(args[0])?)),
        ConceptData::Nappe(n) if args.len() == 2 => Ok(Value::Float(n.eval(args[0], args[1])?)),
        ConceptData::Pending => {
            Err(Error::python(format!("the value of {} is only known when the file is run, not checked", c.label())))
        }
        _ => Err(Error::python(format!(
            "TypeError: {} ({}) is not callable with {} argument(s)",
            c.label(),
            c.kind(),
            args.len()
        ))),
    }
}

/// The Python exception class of an error a `try` may catch: Python-level errors by the name their
/// message starts with ("ZeroDivisionError: ..."), an import of a module the subset does not have as
/// `ModuleNotFoundError`; command failures, unsupported features, time limits and internal errors are
/// not caught (they end the run, located).
fn exception_class(e: &Error) -> Option<&str> {
    match e.kind {
        crate::diag::ErrorKind::Python => {
            let head = e.msg.split(':').next().unwrap_or("");
            let is_class = !head.is_empty()
                && head.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                && (head.ends_with("Error") || head.ends_with("Exception") || head.ends_with("Warning"));
            Some(if is_class { head } else { "Exception" })
        }
        crate::diag::ErrorKind::Unsupported if e.msg.starts_with("import ") => Some("ModuleNotFoundError"),
        _ => None,
    }
}

/// Does `except TYPES:` catch an exception of class `class`? TYPES is a class name or a tuple of names
/// (bare `except:` catches every catchable one); the built-in hierarchy is followed where it groups the
/// classes command files name.
fn handler_matches(h: &crate::syntax::ast::Handler, class: &str) -> Result<bool> {
    let Some(types) = &h.types else { return Ok(true) };
    // `CA.AsterError` (code_aster's exceptions) is named by its attribute.
    fn class_name(e: &Expr) -> std::result::Result<&str, ()> {
        match &e.kind {
            ExprKind::Name(n) => Ok(n.as_str()),
            ExprKind::Attr(m, n) if matches!(&m.kind, ExprKind::Name(x) if x == "CA" || x == "code_aster") => {
                Ok(n.as_str())
            }
            _ => Err(()),
        }
    }
    let names: Vec<&str> = match &types.kind {
        ExprKind::Name(_) | ExprKind::Attr(..) => vec![class_name(types)
            .map_err(|_| Error::unsupported("except: only exception class names are supported").at(h.span))?],
        ExprKind::Tuple(items) => items
            .iter()
            .map(class_name)
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| Error::unsupported("except: only exception class names are supported").at(h.span))?,
        _ => return Err(Error::unsupported("except: only exception class names are supported").at(h.span)),
    };
    Ok(names.iter().any(|&n| {
        n == class
            || matches!(n, "Exception" | "BaseException")
            || (n == "ArithmeticError" && matches!(class, "ZeroDivisionError" | "OverflowError" | "FloatingPointError"))
            || (n == "LookupError" && matches!(class, "KeyError" | "IndexError"))
            || (n == "ImportError" && class == "ModuleNotFoundError")
            || (n == "OSError" && matches!(class, "FileNotFoundError" | "PermissionError"))
    }))
}
