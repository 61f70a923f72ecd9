//! The declarative keyword schema of a command, and the small builder DSL the
//! command definitions in `catalog/commands/` are written in.
//!
//! The vocabulary follows Code_Aster's catalogue: simple keywords (`SIMP`)
//! with a type, a status (mandatory, optional, defaulted), a cardinality and
//! allowed values; factor keywords (`FACT`) that group keywords and may be
//! repeated; conditional blocks (`BLOC`) whose keywords exist only when a
//! condition on sibling values holds; and rules between keywords.

use super::args::Args;
use crate::concepts::ConceptKind;
use crate::diag::Result;

/// The type of one value of a simple keyword.
#[derive(Debug, Clone, PartialEq)]
pub enum Ty {
    /// Integer (`I`).
    I,
    /// Real (`R`); integers are accepted and promoted.
    R,
    /// Complex (`C`).
    C,
    /// Text (`TXM`).
    Txm,
    /// A concept of one of these kinds.
    Co(&'static [ConceptKind]),
    /// A Python callable (functions handed to FORMULE, ...).
    Callable,
}

/// A literal used for defaults, allowed values and conditions.
#[derive(Debug, Clone, PartialEq)]
pub enum Lit {
    I(i64),
    R(f64),
    T(&'static str),
}

impl From<&'static str> for Lit {
    fn from(s: &'static str) -> Self {
        Lit::T(s)
    }
}
impl From<i64> for Lit {
    fn from(i: i64) -> Self {
        Lit::I(i)
    }
}
impl From<i32> for Lit {
    fn from(i: i32) -> Self {
        Lit::I(i as i64)
    }
}
impl From<f64> for Lit {
    fn from(r: f64) -> Self {
        Lit::R(r)
    }
}

impl std::fmt::Display for Lit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Lit::I(i) => write!(f, "{i}"),
            Lit::R(r) => write!(f, "{}", crate::text::float_repr(*r)),
            Lit::T(t) => write!(f, "'{t}'"),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Statut {
    /// Optional.
    F,
    /// Mandatory.
    O,
    /// Optional with a default applied when absent.
    D(Vec<Lit>),
}

#[derive(Debug, Clone)]
pub struct Simp {
    pub name: &'static str,
    pub statut: Statut,
    pub types: Vec<Ty>,
    pub min: usize,
    /// `None`: any number of values.
    pub max: Option<usize>,
    pub allowed: Option<Vec<Lit>>,
    pub val_min: Option<f64>,
    pub val_max: Option<f64>,
}

/// Status of a factor keyword: 'd' means one default occurrence is created.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FactStatut {
    F,
    O,
    D,
}

#[derive(Debug, Clone)]
pub struct Fact {
    pub name: &'static str,
    pub statut: FactStatut,
    pub min: usize,
    pub max: Option<usize>,
    pub entries: Vec<Entry>,
    pub rules: Vec<Rule>,
}

#[derive(Debug, Clone)]
pub struct Bloc {
    pub cond: Cond,
    pub entries: Vec<Entry>,
    pub rules: Vec<Rule>,
}

#[derive(Debug, Clone)]
pub enum Entry {
    Simp(Simp),
    Fact(Fact),
    Bloc(Bloc),
}

impl From<Simp> for Entry {
    fn from(s: Simp) -> Self {
        Entry::Simp(s)
    }
}
impl From<Fact> for Entry {
    fn from(f: Fact) -> Self {
        Entry::Fact(f)
    }
}
impl From<Bloc> for Entry {
    fn from(b: Bloc) -> Self {
        Entry::Bloc(b)
    }
}

/// The condition of a block, on the values of keywords of the same level
/// (then of enclosing levels).
#[derive(Debug, Clone)]
pub enum Cond {
    /// The keyword's (first) value equals the literal.
    Eq(&'static str, Lit),
    /// The keyword's (first) value is one of the literals.
    In(&'static str, Vec<Lit>),
    /// The keyword is present (given or defaulted).
    Present(&'static str),
    Absent(&'static str),
    And(Vec<Cond>),
    Or(Vec<Cond>),
}

#[derive(Debug, Clone)]
pub enum Rule {
    /// Exactly one of these keywords.
    UnParmi(Vec<&'static str>),
    /// At least one.
    AuMoinsUn(Vec<&'static str>),
    /// At most one.
    Exclus(Vec<&'static str>),
    /// All or none.
    Ensemble(Vec<&'static str>),
    /// If the first is present, all the others must be.
    PresentPresent(&'static str, Vec<&'static str>),
    /// If the first is present, none of the others may be.
    PresentAbsent(&'static str, Vec<&'static str>),
}

impl std::fmt::Display for Rule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let j = |v: &[&str]| v.join(", ");
        match self {
            Rule::UnParmi(k) => write!(f, "exactly one of {}", j(k)),
            Rule::AuMoinsUn(k) => write!(f, "at least one of {}", j(k)),
            Rule::Exclus(k) => write!(f, "at most one of {}", j(k)),
            Rule::Ensemble(k) => write!(f, "all or none of {}", j(k)),
            Rule::PresentPresent(a, k) => write!(f, "{a} requires {}", j(k)),
            Rule::PresentAbsent(a, k) => write!(f, "{a} excludes {}", j(k)),
        }
    }
}

impl std::fmt::Display for Cond {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Cond::Eq(k, v) => write!(f, "{k} == {v}"),
            Cond::In(k, vs) => {
                write!(f, "{k} in ({})", vs.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", "))
            }
            Cond::Present(k) => write!(f, "{k} given"),
            Cond::Absent(k) => write!(f, "{k} absent"),
            Cond::And(cs) => write!(f, "{}", cs.iter().map(|c| format!("({c})")).collect::<Vec<_>>().join(" and ")),
            Cond::Or(cs) => write!(f, "{}", cs.iter().map(|c| format!("({c})")).collect::<Vec<_>>().join(" or ")),
        }
    }
}

/// The concept a command produces.
#[derive(Clone)]
pub enum Produces {
    Nothing,
    Fixed(ConceptKind),
    /// The type depends on the arguments (CALC_FONCTION, CREA_CHAMP, ...).
    Dynamic(fn(&Args) -> Result<ConceptKind>),
    /// A Python integer, not a concept (DEFI_FICHIER's free unit), which the stage sets in
    /// `Ctx::int_result`; nothing when it sets none.
    Int,
}

impl std::fmt::Debug for Produces {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Produces::Nothing => write!(f, "Nothing"),
            Produces::Fixed(k) => write!(f, "Fixed({k})"),
            Produces::Dynamic(_) => write!(f, "Dynamic"),
            Produces::Int => write!(f, "Int"),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reentrant {
    No,
    /// `reuse=` allowed.
    Optional,
    /// `reuse=` required.
    Mandatory,
}

#[derive(Debug, Clone)]
pub struct Command {
    pub name: &'static str,
    pub doc: &'static str,
    pub produces: Produces,
    pub reentrant: Reentrant,
    pub entries: Vec<Entry>,
    pub rules: Vec<Rule>,
    /// Keywords outside the schema are passed through (FORMULE's context).
    pub open: bool,
}

// ------------------------------------------------------------------ builders

pub fn simp(name: &'static str) -> Simp {
    Simp {
        name,
        statut: Statut::F,
        types: Vec::new(),
        min: 1,
        max: Some(1),
        allowed: None,
        val_min: None,
        val_max: None,
    }
}

impl Simp {
    /// Mandatory.
    pub fn o(mut self) -> Self {
        self.statut = Statut::O;
        self
    }
    /// Defaulted to one value.
    pub fn d(mut self, v: impl Into<Lit>) -> Self {
        self.statut = Statut::D(vec![v.into()]);
        self
    }
    /// Defaulted to several values.
    pub fn dv(mut self, v: Vec<Lit>) -> Self {
        self.statut = Statut::D(v);
        self
    }
    pub fn r(mut self) -> Self {
        self.types.push(Ty::R);
        self
    }
    pub fn i(mut self) -> Self {
        self.types.push(Ty::I);
        self
    }
    pub fn c(mut self) -> Self {
        self.types.push(Ty::C);
        self
    }
    pub fn txt(mut self) -> Self {
        self.types.push(Ty::Txm);
        self
    }
    pub fn co(mut self, kinds: &'static [ConceptKind]) -> Self {
        self.types.push(Ty::Co(kinds));
        self
    }
    pub fn callable(mut self) -> Self {
        self.types.push(Ty::Callable);
        self
    }
    /// At most `n` values.
    pub fn max(mut self, n: usize) -> Self {
        self.max = Some(n);
        self
    }
    /// Any number of values.
    pub fn many(mut self) -> Self {
        self.max = None;
        self
    }
    pub fn min(mut self, n: usize) -> Self {
        self.min = n;
        self
    }
    /// Allowed text values.
    pub fn one_of(mut self, vals: &[&'static str]) -> Self {
        self.allowed = Some(vals.iter().map(|v| Lit::T(v)).collect());
        self
    }
    /// Allowed integer values.
    pub fn one_of_i(mut self, vals: &[i64]) -> Self {
        self.allowed = Some(vals.iter().map(|v| Lit::I(*v)).collect());
        self
    }
    pub fn val_min(mut self, v: f64) -> Self {
        self.val_min = Some(v);
        self
    }
    pub fn val_max(mut self, v: f64) -> Self {
        self.val_max = Some(v);
        self
    }
}

pub fn fact(name: &'static str, entries: Vec<Entry>) -> Fact {
    Fact { name, statut: FactStatut::F, min: 1, max: Some(1), entries, rules: Vec::new() }
}

impl Fact {
    pub fn o(mut self) -> Self {
        self.statut = FactStatut::O;
        self
    }
    /// One default occurrence when absent.
    pub fn d(mut self) -> Self {
        self.statut = FactStatut::D;
        self
    }
    pub fn max(mut self, n: usize) -> Self {
        self.max = Some(n);
        self
    }
    pub fn many(mut self) -> Self {
        self.max = None;
        self
    }
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
}

pub fn bloc(cond: Cond, entries: Vec<Entry>) -> Bloc {
    Bloc { cond, entries, rules: Vec::new() }
}

impl Bloc {
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
}

pub fn eq(k: &'static str, v: impl Into<Lit>) -> Cond {
    Cond::Eq(k, v.into())
}
pub fn is_in(k: &'static str, vals: &[&'static str]) -> Cond {
    Cond::In(k, vals.iter().map(|v| Lit::T(v)).collect())
}
pub fn present(k: &'static str) -> Cond {
    Cond::Present(k)
}
pub fn absent(k: &'static str) -> Cond {
    Cond::Absent(k)
}
pub fn and(c: Vec<Cond>) -> Cond {
    Cond::And(c)
}
pub fn or(c: Vec<Cond>) -> Cond {
    Cond::Or(c)
}

pub fn un_parmi(k: &[&'static str]) -> Rule {
    Rule::UnParmi(k.to_vec())
}
pub fn au_moins_un(k: &[&'static str]) -> Rule {
    Rule::AuMoinsUn(k.to_vec())
}
pub fn exclus(k: &[&'static str]) -> Rule {
    Rule::Exclus(k.to_vec())
}
pub fn ensemble(k: &[&'static str]) -> Rule {
    Rule::Ensemble(k.to_vec())
}
pub fn present_present(a: &'static str, k: &[&'static str]) -> Rule {
    Rule::PresentPresent(a, k.to_vec())
}
pub fn present_absent(a: &'static str, k: &[&'static str]) -> Rule {
    Rule::PresentAbsent(a, k.to_vec())
}

/// `kws![a, b, c]`: a list of entries from simple, factor and block builders.
#[macro_export]
macro_rules! kws {
    ($($e:expr),* $(,)?) => {
        vec![$($crate::catalog::schema::Entry::from($e)),*]
    };
}

impl Command {
    pub fn new(name: &'static str, doc: &'static str) -> Command {
        Command {
            name,
            doc,
            produces: Produces::Nothing,
            reentrant: Reentrant::No,
            entries: Vec::new(),
            rules: Vec::new(),
            open: false,
        }
    }
    pub fn produces(mut self, k: ConceptKind) -> Self {
        self.produces = Produces::Fixed(k);
        self
    }
    pub fn produces_dyn(mut self, f: fn(&Args) -> Result<ConceptKind>) -> Self {
        self.produces = Produces::Dynamic(f);
        self
    }
    /// The command returns a Python integer (see [`Produces::Int`]).
    pub fn produces_int(mut self) -> Self {
        self.produces = Produces::Int;
        self
    }
    pub fn reuse(mut self) -> Self {
        self.reentrant = Reentrant::Optional;
        self
    }
    pub fn reuse_required(mut self) -> Self {
        self.reentrant = Reentrant::Mandatory;
        self
    }
    pub fn kw(mut self, entries: Vec<Entry>) -> Self {
        self.entries = entries;
        self
    }
    pub fn rules(mut self, rules: Vec<Rule>) -> Self {
        self.rules = rules;
        self
    }
    pub fn open(mut self) -> Self {
        self.open = true;
        self
    }
}
