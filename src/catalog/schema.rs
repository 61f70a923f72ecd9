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
    /// Any value, unchecked (Code_Aster's `not_checked`).
    Any,
    /// `CO('name')`: a new concept, of one of these types, that the command creates under that name
    /// (an existing concept of any type is accepted too, as in Code_Aster).
    NewConcept(&'static [ConceptKind]),
}

/// A check on all the values of a simple keyword (Code_Aster's validators).
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// All values differ.
    NoRepeat,
    /// Values in increasing (`false`) or decreasing (`true`) order, equal neighbours allowed.
    Ordered(bool),
    /// Every text has between `min` and `max` characters.
    Len(usize, usize),
    /// A condition on the set of (text) values.
    Values(ValCheck),
}

/// A condition on the set of values of a keyword (AFFE_CARA_ELEM's CARA lists, ...).
#[derive(Debug, Clone, PartialEq)]
pub enum ValCheck {
    /// Every one of these values is given.
    HasAll(Vec<Lit>),
    /// All or none of these values are given.
    Together(Vec<Lit>),
    /// None of these values is given.
    HasNone(Vec<Lit>),
    /// At most one (distinct) value starts with this prefix.
    OnePrefix(&'static str),
    And(Vec<ValCheck>),
    Or(Vec<ValCheck>),
}

impl std::fmt::Display for ValCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let l = |v: &[Lit]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ");
        let j = |v: &[ValCheck], sep: &str| v.iter().map(|x| format!("({x})")).collect::<Vec<_>>().join(sep);
        match self {
            ValCheck::HasAll(v) => write!(f, "all of {} given", l(v)),
            ValCheck::Together(v) => write!(f, "all or none of {}", l(v)),
            ValCheck::HasNone(v) => write!(f, "none of {}", l(v)),
            ValCheck::OnePrefix(p) => write!(f, "at most one value starting with '{p}'"),
            ValCheck::And(v) => write!(f, "{}", j(v, " and ")),
            ValCheck::Or(v) => write!(f, "{}", j(v, " or ")),
        }
    }
}

/// A literal used for defaults, allowed values and conditions.
#[derive(Debug, Clone, PartialEq)]
pub enum Lit {
    I(i64),
    R(f64),
    C(f64, f64),
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
            Lit::C(a, b) => write!(f, "({}+{}j)", crate::text::float_repr(*a), crate::text::float_repr(*b)),
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
    /// The bounds exclude their value.
    pub min_open: bool,
    pub max_open: bool,
    pub checks: Vec<Check>,
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
/// (then of enclosing levels). A condition on an absent keyword is false, but for `Absent`.
#[derive(Debug, Clone)]
pub enum Cond {
    /// One of the keyword's values equals the literal.
    Eq(&'static str, Lit),
    /// One of the keyword's values is one of the literals.
    In(&'static str, Vec<Lit>),
    /// The keyword is present (given or defaulted).
    Present(&'static str),
    Absent(&'static str),
    And(Vec<Cond>),
    Or(Vec<Cond>),
    Not(Box<Cond>),
    True,
    False,
    /// The keyword's (first) concept is of one of these types (or a subtype).
    Type(&'static str, &'static [ConceptKind]),
    /// The keyword's (first) text value starts with the prefix.
    Prefix(&'static str, &'static str),
    /// The keyword's (single) value compared with a number: `value < x`, `value > x`.
    Less(&'static str, f64),
    Greater(&'static str, f64),
    /// The number of values of the keyword compared with `n`.
    Count(&'static str, CountOp, usize),
    /// `abs(first value) < x`.
    AbsLess(&'static str, f64),
    /// The first two text values are equal from character `n` on.
    SameTail(&'static str, usize),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CountOp {
    Eq,
    Lt,
    Le,
    Gt,
    Ge,
}

impl CountOp {
    pub fn holds(self, a: usize, b: usize) -> bool {
        match self {
            CountOp::Eq => a == b,
            CountOp::Lt => a < b,
            CountOp::Le => a <= b,
            CountOp::Gt => a > b,
            CountOp::Ge => a >= b,
        }
    }
    pub fn symbol(self) -> &'static str {
        match self {
            CountOp::Eq => "==",
            CountOp::Lt => "<",
            CountOp::Le => "<=",
            CountOp::Gt => ">",
            CountOp::Ge => ">=",
        }
    }
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
    /// At least one keyword at this level (defaults included).
    NotEmpty,
    /// When none of the rule's keywords is given, these defaults are inserted before the rule is
    /// checked (Code_Aster's `UN_PARMI(..., TOUT='OUI')`).
    WithDefaults(Box<Rule>, Vec<(&'static str, Lit)>),
}

impl Rule {
    /// The keywords the rule names.
    pub fn keywords(&self) -> Vec<&'static str> {
        match self {
            Rule::UnParmi(k) | Rule::AuMoinsUn(k) | Rule::Exclus(k) | Rule::Ensemble(k) => k.clone(),
            Rule::PresentPresent(a, k) | Rule::PresentAbsent(a, k) => {
                let mut v = vec![*a];
                v.extend(k);
                v
            }
            Rule::NotEmpty => Vec::new(),
            Rule::WithDefaults(r, _) => r.keywords(),
        }
    }
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
            Rule::NotEmpty => write!(f, "at least one keyword"),
            Rule::WithDefaults(r, d) => {
                let d: Vec<String> = d.iter().map(|(k, v)| format!("{k}={v}")).collect();
                write!(f, "{r} (when none is given: {})", d.join(", "))
            }
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
            Cond::Not(c) => write!(f, "not ({c})"),
            Cond::True => write!(f, "always"),
            Cond::False => write!(f, "never"),
            Cond::Type(k, kinds) => {
                write!(f, "{k} is a {}", kinds.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(" or "))
            }
            Cond::Prefix(k, p) => write!(f, "{k} starts with '{p}'"),
            Cond::Less(k, x) => write!(f, "{k} < {}", crate::text::float_repr(*x)),
            Cond::Greater(k, x) => write!(f, "{k} > {}", crate::text::float_repr(*x)),
            Cond::Count(k, op, n) => write!(f, "number of values of {k} {} {n}", op.symbol()),
            Cond::AbsLess(k, x) => write!(f, "|{k}| < {}", crate::text::float_repr(*x)),
            Cond::SameTail(k, n) => write!(f, "the first two values of {k} agree from character {n} on"),
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
    /// The type depends on the arguments, as a list of cases (first match wins); when no case
    /// matches, one of `one_of`, not known without computing.
    Cases {
        one_of: Vec<ConceptKind>,
        cases: Vec<(Cond, Outcome)>,
    },
}

/// What a case of [`Produces::Cases`] gives.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Kind(ConceptKind),
    /// The type of the concept of a keyword (`FACT/KW`: in the first occurrence of FACT).
    TypeOf(&'static str),
    Nothing,
}

impl std::fmt::Debug for Produces {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Produces::Nothing => write!(f, "Nothing"),
            Produces::Fixed(k) => write!(f, "Fixed({k})"),
            Produces::Dynamic(_) => write!(f, "Dynamic"),
            Produces::Int => write!(f, "Int"),
            Produces::Cases { one_of, cases } => write!(f, "Cases({one_of:?}, {} cases)", cases.len()),
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
        min_open: false,
        max_open: false,
        checks: Vec::new(),
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
