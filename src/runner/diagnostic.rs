//! Code_Aster's diagnostic of a run (`DIAGNOSTIC JOB : OK`).

use crate::diag::ErrorKind;
use std::fmt;
use std::str::FromStr;

/// How a run ended, shown by its Code_Aster name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Diagnostic {
    /// Every check passed (at least one check).
    Ok,
    /// A check failed.
    NookTestResu,
    /// The run ended without a check.
    NoTestResu,
    /// The run stopped on an error.
    Error,
    /// The run stopped on a syntax or catalogue error.
    SyntaxError,
}

impl Diagnostic {
    /// Code_Aster's name: `OK`, `NOOK_TEST_RESU`, `NO_TEST_RESU`, `<F>_ERROR`, `<F>_SYNTAX_ERROR`.
    pub fn name(self) -> &'static str {
        match self {
            Diagnostic::Ok => "OK",
            Diagnostic::NookTestResu => "NOOK_TEST_RESU",
            Diagnostic::NoTestResu => "NO_TEST_RESU",
            Diagnostic::Error => "<F>_ERROR",
            Diagnostic::SyntaxError => "<F>_SYNTAX_ERROR",
        }
    }

    /// The diagnostic of a run stopped by an error of this kind.
    pub fn of_error(kind: ErrorKind) -> Diagnostic {
        match kind {
            ErrorKind::Syntax | ErrorKind::Catalog => Diagnostic::SyntaxError,
            ErrorKind::Python
            | ErrorKind::Unsupported
            | ErrorKind::Io
            | ErrorKind::Runtime
            | ErrorKind::Internal
            | ErrorKind::TimeLimit => Diagnostic::Error,
        }
    }

    /// The process exit code: 0 for OK and for a run without checks, 1 for a failed check, 2 for errors.
    pub fn exit_code(self) -> i32 {
        match self {
            Diagnostic::Ok | Diagnostic::NoTestResu => 0,
            Diagnostic::NookTestResu => 1,
            Diagnostic::Error | Diagnostic::SyntaxError => 2,
        }
    }

    /// An `<F>` diagnostic: the run stopped on an error.
    pub fn is_error(self) -> bool {
        matches!(self, Diagnostic::Error | Diagnostic::SyntaxError)
    }

    const ALL: [Diagnostic; 5] =
        [Diagnostic::Ok, Diagnostic::NookTestResu, Diagnostic::NoTestResu, Diagnostic::Error, Diagnostic::SyntaxError];
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl FromStr for Diagnostic {
    type Err = String;
    fn from_str(s: &str) -> Result<Diagnostic, String> {
        Diagnostic::ALL.into_iter().find(|d| d.name() == s).ok_or_else(|| format!("'{s}' is not a diagnostic"))
    }
}

/// Compares with Code_Aster's name (`outcome.diagnostic == "OK"`).
impl PartialEq<&str> for Diagnostic {
    fn eq(&self, other: &&str) -> bool {
        self.name() == *other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_pad() {
        for d in Diagnostic::ALL {
            assert_eq!(d.to_string().parse::<Diagnostic>(), Ok(d));
        }
        assert_eq!(format!("[{:<6}]", Diagnostic::Ok), "[OK    ]");
        assert!("FOO".parse::<Diagnostic>().is_err());
        assert_eq!(Diagnostic::of_error(ErrorKind::Catalog), "<F>_SYNTAX_ERROR");
    }
}
