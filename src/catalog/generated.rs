//! The schemas taken from Code_Aster's catalogue (`generated/commands.cata`), read on demand.
//!
//! `scripts/extract_catalogue.py` writes the facts of Code_Aster's catalogue — names, types, allowed
//! values, defaults, cardinalities, bounds, conditions, rules, produced types — in the text format
//! below; this module reads a command's schema the first time it is asked for, so that a run pays only
//! for the commands its file calls. [`write`] writes any schema (hand-written ones too) in the same
//! format: `aster catalog --schema NAME`, which the extractor uses to compare the hand-written schemas
//! with Code_Aster's facts.
//!
//! # Format
//!
//! One item per line; `#` starts a comment line. Tokens are separated by spaces; `(`, `)`, `{`, `}`
//! are tokens of their own; a text literal is quoted `'...'` (with `\'` and `\\`), a real has a `.` or
//! an exponent, a complex is `c:RE:IM`; lists of literals are separated by commas.
//!
//! ```text
//! command NAME oper|macro|proc|form [reuse]
//!   doc 'one line of ours'
//!   produces none | produces KIND | produces one_of KIND...
//!   case COND KIND|none|typeof:KW|typeof:FACT/KW      (result type: the first matching case wins)
//!   rule exactly_one|at_least_one|at_most_one|together|present_present|present_absent|not_empty KW...
//!        [default KW=LIT ...]
//!   s NAME o|f TYPE... [n=MIN..MAX|*] [d=LITS] [into=LITS] [lo=LIT [lo_open]] [hi=LIT [hi_open]]
//!        [norepeat] [ordered|ordered_desc] [len=MIN..MAX] [check(VALCHECK)]...
//!   f NAME o|f|d [n=MIN..MAX|*] {          (a factor keyword; `d`: one default occurrence)
//!     ...
//!   }
//!   b COND {                               (a block: its entries exist when COND holds)
//!     ...
//!   }
//! end
//! ```
//!
//! TYPE is `R`, `I`, `C`, `T` (text, mesh entity names included), `unit` (a logical unit: an
//! integer), `any`, `co:KIND,...` (a concept of one of these types or a subtype) or `new:KIND,...`
//! (`CO('name')`: a concept the command creates). COND is `(eq KW LIT...)` (one of the values is one of
//! the literals), `(set KW)`, `(not C)`, `(and C...)`, `(or C...)`, `(true)`, `(false)`,
//! `(type KW KIND...)`, `(prefix KW LIT)`, `(lt KW LIT)`, `(gt KW LIT)`, `(count KW eq|lt|le|gt|ge N)`,
//! `(abs_lt KW LIT)`, `(same_tail KW N)`. VALCHECK is `(has_all LIT...)`, `(together LIT...)`,
//! `(has_none LIT...)`, `(one_prefix LIT)`, `(and VALCHECK...)`, `(or VALCHECK...)`.

use super::schema::*;
use crate::concepts::ConceptKind;
use std::collections::HashMap;
use std::sync::OnceLock;

static TEXT: &str = include_str!("generated/commands.cata");

/// The generated schemas: an index of the text, and each schema once it was read.
pub struct Store {
    index: HashMap<&'static str, usize>,
    spans: Vec<(&'static str, &'static str)>,
    parsed: Vec<OnceLock<Command>>,
}

impl Store {
    fn new(text: &'static str) -> Store {
        let mut spans = Vec::new();
        let mut start = None;
        let mut offset = 0;
        for line in text.split_inclusive('\n') {
            if line.starts_with("command ") {
                let name = line.split_whitespace().nth(1).unwrap_or("");
                start = Some((name, offset));
            } else if line.trim_end() == "end" {
                if let Some((name, s)) = start.take() {
                    spans.push((name, &text[s..offset + line.len()]));
                }
            }
            offset += line.len();
        }
        let index = spans.iter().enumerate().map(|(i, (n, _))| (*n, i)).collect();
        let parsed = spans.iter().map(|_| OnceLock::new()).collect();
        Store { index, spans, parsed }
    }

    /// The store of `generated/commands.cata`.
    pub fn get_static() -> &'static Store {
        static STORE: OnceLock<Store> = OnceLock::new();
        STORE.get_or_init(|| Store::new(TEXT))
    }

    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.spans.iter().map(|(n, _)| *n)
    }

    pub fn get(&self, name: &str) -> Option<&Command> {
        let i = *self.index.get(name)?;
        Some(self.parsed[i].get_or_init(|| {
            parse_command(self.spans[i].1)
                .unwrap_or_else(|e| panic!("generated/commands.cata, command {name}: {e} (regenerate the catalogue)"))
        }))
    }
}

// ------------------------------------------------------------------ reading

type R<T> = std::result::Result<T, String>;

/// The tokens of one line.
fn tokens(line: &'static str) -> R<Vec<&'static str>> {
    let b = line.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
        } else if matches!(c, b'(' | b')' | b'{' | b'}') {
            out.push(&line[i..i + 1]);
            i += 1;
        } else {
            let s = i;
            while i < b.len() && !b[i].is_ascii_whitespace() && !matches!(b[i], b'(' | b')' | b'{' | b'}') {
                if b[i] == b'\'' {
                    i += 1;
                    while i < b.len() && b[i] != b'\'' {
                        if b[i] == b'\\' {
                            i += 1;
                        }
                        i += 1;
                    }
                    if i >= b.len() {
                        return Err(format!("unterminated text in {line:?}"));
                    }
                }
                i += 1;
            }
            out.push(&line[s..i]);
        }
    }
    Ok(out)
}

/// Split a comma-separated list of literals (commas inside quotes kept).
fn split_list(s: &'static str) -> Vec<&'static str> {
    let mut out = Vec::new();
    let (mut start, mut quoted, mut escaped) = (0, false, false);
    for (i, c) in s.char_indices() {
        if escaped {
            escaped = false;
        } else if quoted && c == '\\' {
            escaped = true;
        } else if c == '\'' {
            quoted = !quoted;
        } else if c == ',' && !quoted {
            out.push(&s[start..i]);
            start = i + 1;
        }
    }
    out.push(&s[start..]);
    out
}

fn text(s: &'static str) -> R<&'static str> {
    let inner = s.strip_prefix('\'').and_then(|x| x.strip_suffix('\'')).ok_or_else(|| format!("not a text: {s}"))?;
    if !inner.contains('\\') {
        return Ok(inner);
    }
    let mut out = String::new();
    let mut chars = inner.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some('n') => out.push('\n'),
                Some('t') => out.push('\t'),
                Some(x) => out.push(x),
                None => {}
            }
        } else {
            out.push(c);
        }
    }
    Ok(Box::leak(out.into_boxed_str()))
}

fn lit(s: &'static str) -> R<Lit> {
    if s.starts_with('\'') {
        return Ok(Lit::T(text(s)?));
    }
    if let Some(c) = s.strip_prefix("c:") {
        let (re, im) = c.split_once(':').ok_or_else(|| format!("bad complex {s}"))?;
        let p = |x: &str| x.parse::<f64>().map_err(|e| format!("{s}: {e}"));
        return Ok(Lit::C(p(re)?, p(im)?));
    }
    if s.contains(['.', 'e', 'E']) {
        return s.parse::<f64>().map(Lit::R).map_err(|e| format!("{s}: {e}"));
    }
    s.parse::<i64>().map(Lit::I).map_err(|e| format!("{s}: {e}"))
}

fn lits(s: &'static str) -> R<Vec<Lit>> {
    split_list(s).into_iter().map(lit).collect()
}

fn kind(s: &str) -> R<ConceptKind> {
    ConceptKind::from_aster_name(s).ok_or_else(|| format!("unknown concept type {s}"))
}

fn kinds(list: &str) -> R<&'static [ConceptKind]> {
    let v: Vec<ConceptKind> = list.split(',').map(kind).collect::<R<_>>()?;
    Ok(Box::leak(v.into_boxed_slice()))
}

fn number(s: &str) -> R<f64> {
    s.parse::<f64>().map_err(|e| format!("{s}: {e}"))
}

fn range(s: &str) -> R<(usize, Option<usize>)> {
    let (a, b) = s.split_once("..").ok_or_else(|| format!("bad range {s}"))?;
    let a = a.parse().map_err(|_| format!("bad range {s}"))?;
    let b = if b == "*" { None } else { Some(b.parse().map_err(|_| format!("bad range {s}"))?) };
    Ok((a, b))
}

/// A cursor over the tokens of an s-expression.
struct Sexp<'t> {
    toks: &'t [&'static str],
    pos: usize,
}

impl Sexp<'_> {
    fn next(&mut self) -> R<&'static str> {
        let t = self.toks.get(self.pos).copied().ok_or("unexpected end of condition")?;
        self.pos += 1;
        Ok(t)
    }
    fn peek(&self) -> Option<&'static str> {
        self.toks.get(self.pos).copied()
    }
    fn expect(&mut self, t: &str) -> R<()> {
        let got = self.next()?;
        if got != t {
            return Err(format!("expected {t}, got {got}"));
        }
        Ok(())
    }
    /// The remaining atoms up to the closing parenthesis (consumed).
    fn atoms(&mut self) -> R<Vec<&'static str>> {
        let mut v = Vec::new();
        while self.peek() != Some(")") {
            v.push(self.next()?);
        }
        self.expect(")")?;
        Ok(v)
    }

    fn cond(&mut self) -> R<Cond> {
        self.expect("(")?;
        let op = self.next()?;
        let c = match op {
            "and" | "or" => {
                let mut cs = Vec::new();
                while self.peek() == Some("(") {
                    cs.push(self.cond()?);
                }
                self.expect(")")?;
                return Ok(if op == "and" { Cond::And(cs) } else { Cond::Or(cs) });
            }
            "not" => {
                let c = self.cond()?;
                self.expect(")")?;
                return Ok(Cond::Not(Box::new(c)));
            }
            _ => {
                let a = self.atoms()?;
                let arg = |i: usize| a.get(i).copied().ok_or_else(|| format!("({op} ...): missing argument"));
                match op {
                    "true" => Cond::True,
                    "false" => Cond::False,
                    "set" => Cond::Present(arg(0)?),
                    "eq" => {
                        let v: Vec<Lit> = a[1..].iter().map(|x| lit(x)).collect::<R<_>>()?;
                        match v.len() {
                            1 => Cond::Eq(arg(0)?, v.into_iter().next().unwrap()),
                            _ => Cond::In(arg(0)?, v),
                        }
                    }
                    "type" => {
                        let v: Vec<ConceptKind> = a[1..].iter().map(|x| kind(x)).collect::<R<_>>()?;
                        Cond::Type(arg(0)?, Box::leak(v.into_boxed_slice()))
                    }
                    "prefix" => Cond::Prefix(arg(0)?, text(arg(1)?)?),
                    "lt" => Cond::Less(arg(0)?, number(arg(1)?)?),
                    "gt" => Cond::Greater(arg(0)?, number(arg(1)?)?),
                    "abs_lt" => Cond::AbsLess(arg(0)?, number(arg(1)?)?),
                    "same_tail" => Cond::SameTail(arg(0)?, arg(1)?.parse().map_err(|_| "bad same_tail")?),
                    "count" => {
                        let op = match arg(1)? {
                            "eq" => CountOp::Eq,
                            "lt" => CountOp::Lt,
                            "le" => CountOp::Le,
                            "gt" => CountOp::Gt,
                            "ge" => CountOp::Ge,
                            o => return Err(format!("bad count operator {o}")),
                        };
                        Cond::Count(arg(0)?, op, arg(2)?.parse().map_err(|_| "bad count")?)
                    }
                    _ => return Err(format!("unknown condition {op}")),
                }
            }
        };
        Ok(c)
    }

    fn valcheck(&mut self) -> R<ValCheck> {
        self.expect("(")?;
        let op = self.next()?;
        if op == "and" || op == "or" {
            let mut cs = Vec::new();
            while self.peek() == Some("(") {
                cs.push(self.valcheck()?);
            }
            self.expect(")")?;
            return Ok(if op == "and" { ValCheck::And(cs) } else { ValCheck::Or(cs) });
        }
        let a = self.atoms()?;
        let l = || a.iter().map(|x| lit(x)).collect::<R<Vec<Lit>>>();
        Ok(match op {
            "has_all" => ValCheck::HasAll(l()?),
            "together" => ValCheck::Together(l()?),
            "has_none" => ValCheck::HasNone(l()?),
            "one_prefix" => ValCheck::OnePrefix(text(a.first().ok_or("one_prefix: no prefix")?)?),
            _ => return Err(format!("unknown value check {op}")),
        })
    }
}

fn simple(t: &[&'static str]) -> R<Simp> {
    let mut s = simp(t.get(1).ok_or("s: no name")?);
    match t.get(2).copied() {
        Some("o") => s.statut = Statut::O,
        Some("f") => {}
        other => return Err(format!("{}: bad status {other:?}", s.name)),
    }
    let mut i = 3;
    while i < t.len() {
        let tok = t[i];
        i += 1;
        match tok {
            "R" => s.types.push(Ty::R),
            "I" | "unit" => s.types.push(Ty::I),
            "C" => s.types.push(Ty::C),
            "T" => s.types.push(Ty::Txm),
            "any" => s.types.push(Ty::Any),
            "norepeat" => s.checks.push(Check::NoRepeat),
            "ordered" => s.checks.push(Check::Ordered(false)),
            "ordered_desc" => s.checks.push(Check::Ordered(true)),
            "lo_open" => s.min_open = true,
            "hi_open" => s.max_open = true,
            "check" => {
                let mut x = Sexp { toks: &t[i..], pos: 0 };
                s.checks.push(Check::Values(x.valcheck()?));
                i += x.pos;
            }
            _ => {
                let (k, v) = tok.split_once(['=', ':']).ok_or_else(|| format!("{}: unknown item {tok}", s.name))?;
                match k {
                    "co" => s.types.push(Ty::Co(kinds(v)?)),
                    "new" => s.types.push(Ty::NewConcept(kinds(v)?)),
                    "n" => (s.min, s.max) = range(v)?,
                    "d" => s.statut = Statut::D(lits(v)?),
                    "into" => s.allowed = Some(lits(v)?),
                    "lo" => s.val_min = Some(number(v)?),
                    "hi" => s.val_max = Some(number(v)?),
                    "len" => {
                        let (a, b) = range(v)?;
                        s.checks.push(Check::Len(a, b.unwrap_or(usize::MAX)));
                    }
                    _ => return Err(format!("{}: unknown item {tok}", s.name)),
                }
            }
        }
    }
    if s.types.is_empty() {
        return Err(format!("{}: no type", s.name));
    }
    Ok(s)
}

fn rule(t: &[&'static str]) -> R<Rule> {
    let kind = t.get(1).copied().ok_or("rule: no kind")?;
    let mut names = Vec::new();
    let mut defaults = Vec::new();
    let mut i = 2;
    while i < t.len() {
        if t[i] == "default" {
            for d in &t[i + 1..] {
                let (k, v) = d.split_once('=').ok_or_else(|| format!("bad rule default {d}"))?;
                defaults.push((k, lit(v)?));
            }
            break;
        }
        names.push(t[i]);
        i += 1;
    }
    let r = match kind {
        "exactly_one" => Rule::UnParmi(names),
        "at_least_one" => Rule::AuMoinsUn(names),
        "at_most_one" => Rule::Exclus(names),
        "together" => Rule::Ensemble(names),
        "present_present" | "present_absent" => {
            let (first, rest) = names.split_first().ok_or("rule without keywords")?;
            if kind == "present_present" {
                Rule::PresentPresent(first, rest.to_vec())
            } else {
                Rule::PresentAbsent(first, rest.to_vec())
            }
        }
        "not_empty" => Rule::NotEmpty,
        _ => return Err(format!("unknown rule {kind}")),
    };
    Ok(if defaults.is_empty() { r } else { Rule::WithDefaults(Box::new(r), defaults) })
}

/// One level of entries (a command's, a factor keyword's or a block's) and its rules, up to the
/// closing `}` or `end`.
fn level(lines: &mut std::iter::Peekable<impl Iterator<Item = R<Vec<&'static str>>>>) -> R<(Vec<Entry>, Vec<Rule>)> {
    let mut entries = Vec::new();
    let mut rules = Vec::new();
    while let Some(t) = lines.peek() {
        let t = t.clone()?;
        match t[0] {
            "}" | "end" => break,
            _ => {
                lines.next();
            }
        }
        match t[0] {
            "s" => entries.push(Entry::Simp(simple(&t)?)),
            "rule" => rules.push(rule(&t)?),
            "f" => {
                let mut f = fact(t.get(1).ok_or("f: no name")?, Vec::new());
                f.statut = match t.get(2).copied() {
                    Some("o") => FactStatut::O,
                    Some("d") => FactStatut::D,
                    Some("f") => FactStatut::F,
                    other => return Err(format!("{}: bad status {other:?}", f.name)),
                };
                for tok in &t[3..] {
                    if let Some(v) = tok.strip_prefix("n=") {
                        (f.min, f.max) = range(v)?;
                    } else if *tok != "{" {
                        return Err(format!("{}: unknown item {tok}", f.name));
                    }
                }
                (f.entries, f.rules) = level(lines)?;
                close(lines)?;
                entries.push(Entry::Fact(f));
            }
            "b" => {
                let mut x = Sexp { toks: &t[1..], pos: 0 };
                let cond = x.cond()?;
                let (e, r) = level(lines)?;
                close(lines)?;
                entries.push(Entry::Bloc(bloc(cond, e).rules(r)));
            }
            other => return Err(format!("unexpected {other}")),
        }
    }
    Ok((entries, rules))
}

fn close(lines: &mut impl Iterator<Item = R<Vec<&'static str>>>) -> R<()> {
    match lines.next() {
        Some(Ok(t)) if t[0] == "}" => Ok(()),
        _ => Err("missing }".into()),
    }
}

/// Read the schema of one command (`command ...` to `end`).
pub fn parse_command(src: &'static str) -> R<Command> {
    let mut lines = src
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(tokens)
        .filter(|t| t.as_ref().map(|t| !t.is_empty()).unwrap_or(true))
        .peekable();
    let head = lines.next().ok_or("empty schema")??;
    if head.first() != Some(&"command") || head.len() < 3 {
        return Err(format!("bad command line {head:?}"));
    }
    let mut cmd = Command::new(head[1], "");
    if head[3..].contains(&"reuse") {
        cmd = cmd.reuse();
    }
    let mut one_of = Vec::new();
    let mut cases = Vec::new();
    let mut fixed = None;
    while let Some(Ok(t)) = lines.peek() {
        match t[0] {
            "doc" => cmd.doc = text(t.get(1).ok_or("doc: no text")?)?,
            "produces" => match t.get(1).copied() {
                Some("none") => {}
                Some("one_of") => one_of = t[2..].iter().map(|k| kind(k)).collect::<R<_>>()?,
                Some(k) => fixed = Some(kind(k)?),
                None => return Err("produces: nothing".into()),
            },
            "case" => {
                let mut x = Sexp { toks: &t[1..], pos: 0 };
                let c = x.cond()?;
                let out = t.get(1 + x.pos).copied().ok_or("case: no result")?;
                let out = match out {
                    "none" => Outcome::Nothing,
                    o if o.starts_with("typeof:") => Outcome::TypeOf(&o["typeof:".len()..]),
                    o => Outcome::Kind(kind(o)?),
                };
                cases.push((c, out));
            }
            _ => break,
        }
        lines.next();
    }
    cmd.produces = match (fixed, one_of.is_empty(), cases.is_empty()) {
        (Some(k), _, _) => Produces::Fixed(k),
        (None, true, true) => Produces::Nothing,
        (None, _, _) => Produces::Cases { one_of, cases },
    };
    (cmd.entries, cmd.rules) = level(&mut lines)?;
    match lines.next() {
        Some(Ok(t)) if t[0] == "end" => Ok(cmd),
        _ => Err("missing end".into()),
    }
}

// ------------------------------------------------------------------ writing

fn w_lit(l: &Lit) -> String {
    match l {
        Lit::I(i) => i.to_string(),
        Lit::R(r) => {
            let s = crate::text::float_repr(*r);
            if s.contains(['.', 'e', 'n', 'i']) {
                s
            } else {
                format!("{s}.0")
            }
        }
        Lit::C(a, b) => format!("c:{}:{}", crate::text::float_repr(*a), crate::text::float_repr(*b)),
        Lit::T(t) => {
            format!("'{}'", t.replace('\\', "\\\\").replace('\'', "\\'").replace('\n', "\\n").replace('\t', "\\t"))
        }
    }
}

fn w_lits(v: &[Lit]) -> String {
    v.iter().map(w_lit).collect::<Vec<_>>().join(",")
}

fn w_kinds(k: &[ConceptKind]) -> String {
    k.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(",")
}

fn w_cond(c: &Cond) -> String {
    let list = |cs: &[Cond]| cs.iter().map(w_cond).collect::<Vec<_>>().join(" ");
    let num = |x: f64| w_lit(&Lit::R(x));
    match c {
        Cond::Eq(k, v) => format!("(eq {k} {})", w_lit(v)),
        Cond::In(k, v) => format!("(eq {k} {})", v.iter().map(w_lit).collect::<Vec<_>>().join(" ")),
        Cond::Present(k) => format!("(set {k})"),
        Cond::Absent(k) => format!("(not (set {k}))"),
        Cond::And(cs) => format!("(and {})", list(cs)),
        Cond::Or(cs) => format!("(or {})", list(cs)),
        Cond::Not(c) => format!("(not {})", w_cond(c)),
        Cond::True => "(true)".into(),
        Cond::False => "(false)".into(),
        Cond::Type(k, kinds) => {
            format!("(type {k} {})", kinds.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(" "))
        }
        Cond::Prefix(k, p) => format!("(prefix {k} {})", w_lit(&Lit::T(p))),
        Cond::Less(k, x) => format!("(lt {k} {})", num(*x)),
        Cond::Greater(k, x) => format!("(gt {k} {})", num(*x)),
        Cond::AbsLess(k, x) => format!("(abs_lt {k} {})", num(*x)),
        Cond::SameTail(k, n) => format!("(same_tail {k} {n})"),
        Cond::Count(k, op, n) => {
            let o = match op {
                CountOp::Eq => "eq",
                CountOp::Lt => "lt",
                CountOp::Le => "le",
                CountOp::Gt => "gt",
                CountOp::Ge => "ge",
            };
            format!("(count {k} {o} {n})")
        }
    }
}

fn w_valcheck(c: &ValCheck) -> String {
    let list = |v: &[Lit]| v.iter().map(w_lit).collect::<Vec<_>>().join(" ");
    let sub = |v: &[ValCheck]| v.iter().map(w_valcheck).collect::<Vec<_>>().join(" ");
    match c {
        ValCheck::HasAll(v) => format!("(has_all {})", list(v)),
        ValCheck::Together(v) => format!("(together {})", list(v)),
        ValCheck::HasNone(v) => format!("(has_none {})", list(v)),
        ValCheck::OnePrefix(p) => format!("(one_prefix {})", w_lit(&Lit::T(p))),
        ValCheck::And(v) => format!("(and {})", sub(v)),
        ValCheck::Or(v) => format!("(or {})", sub(v)),
    }
}

fn w_rule(r: &Rule) -> String {
    match r {
        Rule::UnParmi(k) => format!("rule exactly_one {}", k.join(" ")),
        Rule::AuMoinsUn(k) => format!("rule at_least_one {}", k.join(" ")),
        Rule::Exclus(k) => format!("rule at_most_one {}", k.join(" ")),
        Rule::Ensemble(k) => format!("rule together {}", k.join(" ")),
        Rule::PresentPresent(a, k) => format!("rule present_present {a} {}", k.join(" ")),
        Rule::PresentAbsent(a, k) => format!("rule present_absent {a} {}", k.join(" ")),
        Rule::NotEmpty => "rule not_empty".into(),
        Rule::WithDefaults(r, d) => {
            let d: Vec<String> = d.iter().map(|(k, v)| format!("{k}={}", w_lit(v))).collect();
            format!("{} default {}", w_rule(r), d.join(" "))
        }
    }
}

fn w_card(min: usize, max: Option<usize>) -> String {
    match (min, max) {
        (1, Some(1)) => String::new(),
        (a, Some(b)) => format!(" n={a}..{b}"),
        (a, None) => format!(" n={a}..*"),
    }
}

fn w_entries(entries: &[Entry], rules: &[Rule], depth: usize, out: &mut String) {
    let pad = "  ".repeat(depth);
    for r in rules {
        out.push_str(&format!("{pad}{}\n", w_rule(r)));
    }
    for e in entries {
        match e {
            Entry::Simp(s) => {
                let mut line = format!("{pad}s {} {}", s.name, if s.statut == Statut::O { "o" } else { "f" });
                let cos: Vec<ConceptKind> = s
                    .types
                    .iter()
                    .filter_map(|t| if let Ty::Co(k) = t { Some(k.iter()) } else { None })
                    .flatten()
                    .copied()
                    .collect();
                if !cos.is_empty() {
                    line.push_str(&format!(" co:{}", w_kinds(&cos)));
                }
                for t in &s.types {
                    match t {
                        Ty::I => line.push_str(" I"),
                        Ty::R => line.push_str(" R"),
                        Ty::C => line.push_str(" C"),
                        Ty::Txm => line.push_str(" T"),
                        Ty::Any | Ty::Callable => line.push_str(" any"),
                        Ty::NewConcept(k) => line.push_str(&format!(" new:{}", w_kinds(k))),
                        Ty::Co(_) => {}
                    }
                }
                line.push_str(&w_card(s.min, s.max));
                if let Statut::D(d) = &s.statut {
                    line.push_str(&format!(" d={}", w_lits(d)));
                }
                if let Some(a) = &s.allowed {
                    line.push_str(&format!(" into={}", w_lits(a)));
                }
                if let Some(m) = s.val_min {
                    line.push_str(&format!(" lo={}", w_lit(&Lit::R(m))));
                    if s.min_open {
                        line.push_str(" lo_open");
                    }
                }
                if let Some(m) = s.val_max {
                    line.push_str(&format!(" hi={}", w_lit(&Lit::R(m))));
                    if s.max_open {
                        line.push_str(" hi_open");
                    }
                }
                for c in &s.checks {
                    match c {
                        Check::NoRepeat => line.push_str(" norepeat"),
                        Check::Ordered(false) => line.push_str(" ordered"),
                        Check::Ordered(true) => line.push_str(" ordered_desc"),
                        Check::Len(a, b) => line.push_str(&format!(" len={a}..{b}")),
                        Check::Values(v) => line.push_str(&format!(" check{}", w_valcheck(v))),
                    }
                }
                out.push_str(&line);
                out.push('\n');
            }
            Entry::Fact(f) => {
                let st = match f.statut {
                    FactStatut::O => "o",
                    FactStatut::D => "d",
                    FactStatut::F => "f",
                };
                out.push_str(&format!("{pad}f {} {st}{} {{\n", f.name, w_card(f.min, f.max)));
                w_entries(&f.entries, &f.rules, depth + 1, out);
                out.push_str(&format!("{pad}}}\n"));
            }
            Entry::Bloc(b) => {
                out.push_str(&format!("{pad}b {} {{\n", w_cond(&b.cond)));
                w_entries(&b.entries, &b.rules, depth + 1, out);
                out.push_str(&format!("{pad}}}\n"));
            }
        }
    }
}

/// A schema in the format above (a hand-written one's computed result type is shown as a comment).
pub fn write(cmd: &Command) -> String {
    let mut out =
        format!("command {} {}\n", cmd.name, if cmd.reentrant == Reentrant::No { "oper" } else { "oper reuse" });
    out.push_str(&format!("  doc {}\n", w_lit(&Lit::T(cmd.doc))));
    match &cmd.produces {
        Produces::Nothing => out.push_str("  produces none\n"),
        Produces::Fixed(k) => out.push_str(&format!("  produces {}\n", k.aster_name())),
        Produces::Dynamic(_) => out.push_str("  # produces: computed from the keywords by our own code\n"),
        Produces::Int => out.push_str("  # produces: a Python integer\n"),
        Produces::Cases { one_of, cases } => {
            if !one_of.is_empty() {
                out.push_str(&format!(
                    "  produces one_of {}\n",
                    one_of.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(" ")
                ));
            }
            for (c, o) in cases {
                let o = match o {
                    Outcome::Kind(k) => k.aster_name().to_string(),
                    Outcome::TypeOf(p) => format!("typeof:{p}"),
                    Outcome::Nothing => "none".into(),
                };
                out.push_str(&format!("  case {} {o}\n", w_cond(c)));
            }
        }
    }
    w_entries(&cmd.entries, &cmd.rules, 1, &mut out);
    out.push_str("end\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_generated_schema_reads() {
        let store = Store::get_static();
        let mut n = 0;
        for name in store.names() {
            let c = store.get(name).unwrap();
            assert_eq!(c.name, name);
            // The hand-written schemas carry the description of the commands that have one.
            let hand = crate::catalog::catalogue().hand_written(name).is_some();
            assert!(hand || !c.doc.is_empty(), "{name}: no description");
            n += 1;
        }
        assert!(n > 200, "{n} generated schemas");
    }

    #[test]
    fn written_schemas_read_back_the_same() {
        let store = Store::get_static();
        for name in store.names() {
            let c = store.get(name).unwrap();
            let text: &'static str = Box::leak(write(c).into_boxed_str());
            let again = parse_command(text).unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
            assert_eq!(write(&again), text, "{name}");
        }
    }

    #[test]
    fn literals_and_conditions() {
        assert_eq!(
            tokens("s A f T d='a b',1 into='x\\'y'").unwrap(),
            vec!["s", "A", "f", "T", "d='a b',1", "into='x\\'y'"]
        );
        assert_eq!(
            lits("'a,b',2,3.5,c:1.0:-2.0").unwrap(),
            vec![Lit::T("a,b"), Lit::I(2), Lit::R(3.5), Lit::C(1.0, -2.0)]
        );
        assert_eq!(text("'x\\'y'").unwrap(), "x'y");
        assert_eq!(text("'a\\nb\\\\'").unwrap(), "a\nb\\");
        assert_eq!(w_lit(&Lit::T("a\nb'\\")), "'a\\nb\\'\\\\'");
        let toks = tokens("(and (eq A 'X' 'Y') (not (set B)) (count C gt 2))").unwrap();
        let c = Sexp { toks: &toks, pos: 0 }.cond().unwrap();
        assert_eq!(w_cond(&c), "(and (eq A 'X' 'Y') (not (set B)) (count C gt 2))");
    }
}
