//! Errors and their locations.
//!
//! Every error carries a [`ErrorKind`] (which decides the Code_Aster
//! diagnostic), a message, and where known the span in the command file and
//! the command it arose in. The runner turns spans into `file:line:col`.

use crate::syntax::ast::Span;
use std::fmt;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The text is not valid command-file syntax.
    Syntax,
    /// A command call broke its catalogue schema (keyword, type, value, rule).
    Catalog,
    /// A Python-level error: undefined name, bad operand types, ...
    Python,
    /// A command or feature we know but do not support yet.
    Unsupported,
    /// Reading or writing files and units.
    Io,
    /// A command ran and failed (bad data, numerical failure, ...).
    Runtime,
    /// A bug of aster-rs, not of the command file: a panic the runner caught.
    Internal,
}

#[derive(Debug, Clone)]
pub struct Error {
    pub kind: ErrorKind,
    pub msg: String,
    pub span: Option<Span>,
    pub command: Option<String>,
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn new(kind: ErrorKind, msg: impl Into<String>) -> Self {
        Error { kind, msg: msg.into(), span: None, command: None }
    }
    pub fn python(msg: impl Into<String>) -> Self {
        Self::new(ErrorKind::Python, msg)
    }
    pub fn catalog(msg: impl Into<String>) -> Self {
        Self::new(ErrorKind::Catalog, msg)
    }
    pub fn runtime(msg: impl Into<String>) -> Self {
        Self::new(ErrorKind::Runtime, msg)
    }
    pub fn io(msg: impl Into<String>) -> Self {
        Self::new(ErrorKind::Io, msg)
    }
    pub fn unsupported(msg: impl Into<String>) -> Self {
        Self::new(ErrorKind::Unsupported, msg)
    }
    /// A caught panic: `internal error: MESSAGE`.
    pub fn internal(panic: &str) -> Self {
        Self::new(ErrorKind::Internal, format!("internal error: {panic}"))
    }
    /// Attach a span unless a more precise one is already there.
    pub fn at(mut self, span: Span) -> Self {
        if self.span.is_none() {
            self.span = Some(span);
        }
        self
    }
    /// Attach the command name unless one is already there.
    pub fn in_command(mut self, name: &str) -> Self {
        if self.command.is_none() {
            self.command = Some(name.to_string());
        }
        self
    }

    /// `file:line:col: CMD: message` given the file name and its text.
    pub fn located(&self, file: &str, src: &str) -> String {
        let mut s = String::new();
        match self.span {
            Some(sp) => {
                let (l, c) = crate::syntax::lexer::line_col(src, sp.start);
                s.push_str(&format!("{file}:{l}:{c}: "));
            }
            None => s.push_str(&format!("{file}: ")),
        }
        if let Some(c) = &self.command {
            s.push_str(c);
            s.push_str(": ");
        }
        s.push_str(&self.msg);
        s
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(c) = &self.command {
            write!(f, "{c}: ")?;
        }
        write!(f, "{}", self.msg)
    }
}

impl std::error::Error for Error {}
