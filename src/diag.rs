//! Errors and their locations.
//!
//! Every error carries a [`ErrorKind`] (which decides the Code_Aster
//! diagnostic), a message, and where known the span in the command file and
//! the command it arose in. The runner turns spans into `file:line:col`.

pub use crate::syntax::ast::Span;
use std::cell::Cell;
use std::fmt;
use std::time::{Duration, Instant};

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
    /// The run's time limit passed (see [`Deadline`]).
    TimeLimit,
}

#[derive(Debug, Clone)]
pub struct Error {
    pub kind: ErrorKind,
    pub msg: String,
    pub span: Option<Span>,
    pub command: Option<String>,
    /// The keyword of the command the error belongs to, named by a library that knows no span (a physics
    /// names EXCIT or CHAM_MATER); the stage that knows the keywords' spans locates it (`"KW: msg"`).
    pub keyword: Option<&'static str>,
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn new(kind: ErrorKind, msg: impl Into<String>) -> Self {
        Error { kind, msg: msg.into(), span: None, command: None, keyword: None }
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
    /// Name the keyword the error belongs to, for the stage to locate (unless one is named already).
    pub fn at_keyword(mut self, kw: &'static str) -> Self {
        if self.keyword.is_none() && self.span.is_none() {
            self.keyword = Some(kw);
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

/// When a run must stop: `aster run --time-limit`, or the .export's `P time_limit`.
///
/// The runner sets it for its thread with [`with_deadline`]; the interpreter checks it every few
/// hundred statements and loop iterations, the runner between commands and the stages in their long
/// loops (Newton iterations), all through [`check_deadline`], which costs a clock read.
#[derive(Debug, Clone, Copy)]
pub struct Deadline {
    at: Instant,
    limit: Duration,
}

impl Deadline {
    /// `limit` from now.
    pub fn after(limit: Duration) -> Deadline {
        Deadline::since(Instant::now(), limit)
    }
    /// `limit` from `start`.
    pub fn since(start: Instant, limit: Duration) -> Deadline {
        Deadline { at: start.checked_add(limit).unwrap_or(start + Duration::from_secs(1 << 40)), limit }
    }
    pub fn limit(&self) -> Duration {
        self.limit
    }
}

thread_local! {
    static DEADLINE: Cell<Option<Deadline>> = const { Cell::new(None) };
}

/// Run `f` with `deadline` as this thread's deadline (the previous one is restored after, even if
/// `f` panics).
pub fn with_deadline<R>(deadline: Option<Deadline>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Deadline>);
    impl Drop for Restore {
        fn drop(&mut self) {
            DEADLINE.with(|d| d.set(self.0));
        }
    }
    let _restore = Restore(DEADLINE.with(|d| d.replace(deadline)));
    f()
}

/// A `TimeLimit` error if this thread's deadline has passed: `time limit of 2 s exceeded`.
pub fn check_deadline() -> Result<()> {
    match DEADLINE.with(Cell::get) {
        Some(d) if Instant::now() >= d.at => Err(Error::new(
            ErrorKind::TimeLimit,
            // Rust writes 2.0 as `2`.
            format!("time limit of {} s exceeded", d.limit.as_secs_f64()),
        )),
        _ => Ok(()),
    }
}

/// The time left before this thread's deadline (zero once passed), `None` without a deadline.
pub fn time_left() -> Option<Duration> {
    DEADLINE.with(Cell::get).map(|d| d.at.saturating_duration_since(Instant::now()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deadline_holds_for_its_scope_only() {
        assert!(check_deadline().is_ok());
        let e = with_deadline(Some(Deadline::after(Duration::ZERO)), check_deadline).unwrap_err();
        assert_eq!(e.kind, ErrorKind::TimeLimit);
        assert_eq!(e.msg, "time limit of 0 s exceeded");
        assert!(with_deadline(Some(Deadline::after(Duration::from_secs(60))), check_deadline).is_ok());
        assert!(check_deadline().is_ok());
        assert_eq!(time_left(), None);
        let left = with_deadline(Some(Deadline::after(Duration::from_secs(60))), time_left).unwrap();
        assert!(left > Duration::from_secs(59) && left <= Duration::from_secs(60));
    }
}
