//! The abstract syntax tree of the command-file language.
//!
//! Every node that can fail at run time carries a [`Span`] (byte offsets into
//! the original text) so that errors name the line and column.

use std::rc::Rc;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Span {
    pub start: usize,
    pub end: usize,
}

#[derive(Debug, Clone)]
pub struct Stmt {
    pub kind: StmtKind,
    pub span: Span,
}

#[derive(Debug, Clone)]
pub enum StmtKind {
    Expr(Expr),
    Assign {
        targets: Vec<Expr>,
        value: Expr,
    },
    AugAssign {
        target: Expr,
        op: BinOp,
        value: Expr,
    },
    If {
        branches: Vec<(Expr, Vec<Stmt>)>,
        orelse: Vec<Stmt>,
    },
    For {
        target: Expr,
        iter: Expr,
        body: Vec<Stmt>,
        orelse: Vec<Stmt>,
    },
    While {
        cond: Expr,
        body: Vec<Stmt>,
        orelse: Vec<Stmt>,
    },
    Def(Rc<FuncDef>),
    Return(Option<Expr>),
    Pass,
    Break,
    Continue,
    Del(Vec<Expr>),
    Global(Vec<String>),
    Assert(Expr, Option<Expr>),
    Raise(Option<Expr>),
    /// `try:` with its `except` handlers, `else:` and `finally:` blocks.
    Try {
        body: Vec<Stmt>,
        handlers: Vec<Handler>,
        orelse: Vec<Stmt>,
        finalbody: Vec<Stmt>,
    },
    /// `with EXPR [as TARGET], ...:`
    With {
        items: Vec<(Expr, Option<Expr>)>,
        body: Vec<Stmt>,
    },
    /// `class NAME[(BASES)]:` — a plain class.
    Class(Rc<ClassDef>),
    /// `@DECORATOR` lines before a `def` or `class` (applied bottom-up to what it defines).
    Decorated {
        decorators: Vec<Expr>,
        def: Box<Stmt>,
    },
    /// `import a.b as c` — (module path, alias)
    Import(Vec<(String, Option<String>)>),
    /// `from m import *` (names = None) or `from m import a as b, ...`
    FromImport {
        module: String,
        names: Option<Vec<(String, Option<String>)>>,
    },
}

#[derive(Debug)]
pub struct FuncDef {
    pub name: String,
    pub params: Vec<Param>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Debug)]
pub struct ClassDef {
    pub name: String,
    pub bases: Vec<Expr>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Debug, Clone)]
pub enum Param {
    Plain(String, Option<Expr>),
    Star(String),
    DoubleStar(String),
}

#[derive(Debug, Clone)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    FloorDiv,
    Mod,
    Pow,
    BitOr,
    BitXor,
    BitAnd,
    LShift,
    RShift,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CmpOp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    In,
    NotIn,
    Is,
    IsNot,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Pos,
    Invert,
    Not,
}

#[derive(Debug, Clone)]
pub enum Arg {
    Positional(Expr),
    Keyword(String, Expr, Span),
    Star(Expr),
    DoubleStar(Expr),
}

#[derive(Debug, Clone)]
pub struct Comprehension {
    pub target: Expr,
    pub iter: Expr,
    pub conds: Vec<Expr>,
}

/// One piece of an f-string: literal text, or a replacement field.
#[derive(Debug, Clone)]
pub enum FPart {
    Lit(String),
    Field { expr: Box<Expr>, conv: Option<char>, spec: Vec<FPart> },
}

#[derive(Debug, Clone)]
pub enum ExprKind {
    None,
    Bool(bool),
    Int(i64),
    Float(f64),
    Imag(f64),
    Str(String),
    FString(Vec<FPart>),
    Name(String),
    Tuple(Vec<Expr>),
    List(Vec<Expr>),
    Dict(Vec<(Expr, Expr)>),
    ListComp(Box<Expr>, Vec<Comprehension>),
    GenExp(Box<Expr>, Vec<Comprehension>),
    DictComp(Box<Expr>, Box<Expr>, Vec<Comprehension>),
    BinOp(Box<Expr>, BinOp, Box<Expr>),
    Unary(UnOp, Box<Expr>),
    Compare(Box<Expr>, Vec<(CmpOp, Expr)>),
    And(Box<Expr>, Box<Expr>),
    Or(Box<Expr>, Box<Expr>),
    IfExp { cond: Box<Expr>, then: Box<Expr>, orelse: Box<Expr> },
    Lambda(Rc<FuncDef>),
    Call(Box<Expr>, Vec<Arg>),
    Subscript(Box<Expr>, Box<Expr>),
    Slice(Option<Box<Expr>>, Option<Box<Expr>>, Option<Box<Expr>>),
    Attr(Box<Expr>, String),
}

impl Expr {
    pub fn new(kind: ExprKind, span: Span) -> Self {
        Expr { kind, span }
    }
}

/// An `except [TYPES [as NAME]]:` clause.
#[derive(Debug, Clone)]
pub struct Handler {
    /// The exception classes (a name or a tuple of names); `None` for a bare `except:`.
    pub types: Option<Expr>,
    pub name: Option<String>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

/// A parsed command file.
#[derive(Debug)]
pub struct Module {
    pub body: Vec<Stmt>,
}
