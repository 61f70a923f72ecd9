//! Checking a command call against its schema — the one place that validates
//! keywords.

use super::args::{Arg, ArgValue, Args, Val};
use super::schema::*;
use crate::concepts::{ConceptKind, ConceptRef};
use crate::diag::{Error, Result};
use crate::interp::{format, KwArg, Value};
use crate::syntax::ast::Span;
use std::cell::RefCell;
use std::rc::Rc;

/// The outcome of validating one call.
pub struct Validated {
    pub args: Args,
    /// The concept named by `reuse=`, if any.
    pub reuse: Option<ConceptRef>,
    /// The `CO('name')` values: the new concepts the command creates beside its result, with the
    /// types the keyword declares.
    pub new_concepts: Vec<(ConceptRef, &'static [ConceptKind])>,
}

/// Validate the keyword arguments of a call to `cmd`.
pub fn validate(cmd: &Command, kwargs: Vec<KwArg>, span: Span) -> Result<Validated> {
    validate_as(cmd, kwargs, span, false)
}

/// Validate a call that passed the checked schema against the hand-written schema of the command's
/// stage: what lies outside it is valid Code_Aster that we do not run yet, and stops by name as such.
pub fn validate_supported(cmd: &Command, kwargs: Vec<KwArg>, span: Span) -> Result<Validated> {
    validate_as(cmd, kwargs, span, true)
}

fn validate_as(cmd: &Command, mut kwargs: Vec<KwArg>, span: Span, supported: bool) -> Result<Validated> {
    if !supported {
        super::compat::rewrite(cmd.name, &mut kwargs);
    }
    let mut reuse = None;
    let mut given = Vec::new();
    for k in kwargs {
        if k.name == "reuse" {
            match (&k.value, cmd.reentrant) {
                (_, Reentrant::No) if supported => {
                    return Err(Error::unsupported(format!("reuse= is not supported yet by {}", cmd.name))
                        .at(k.span)
                        .in_command(cmd.name))
                }
                (_, Reentrant::No) => {
                    return Err(cat_err(cmd.name, format!("{} does not accept reuse=", cmd.name), k.span))
                }
                (Value::Concept(c), _) => reuse = Some(c.clone()),
                (v, _) => {
                    return Err(cat_err(
                        cmd.name,
                        format!("reuse= expects a concept, got {} {}", v.type_name(), format::repr(v)),
                        k.span,
                    ))
                }
            }
            continue;
        }
        given.push(k);
    }
    if cmd.reentrant == Reentrant::Mandatory && reuse.is_none() {
        return Err(cat_err(cmd.name, format!("{} requires reuse=", cmd.name), span));
    }
    let new_concepts = RefCell::new(Vec::new());
    let level = Level { cmd: cmd.name, path: cmd.name.to_string(), open: cmd.open, new: &new_concepts, supported };
    let args = level.check(&cmd.entries, &cmd.rules, given, span, &[])?;
    Ok(Validated { args, reuse, new_concepts: new_concepts.into_inner() })
}

/// The type of a command's result, given its validated arguments.
#[derive(Debug, Clone, PartialEq)]
pub enum Produced {
    Nothing,
    Kind(ConceptKind),
    /// One of these, not known without computing (`aster check` of a generated schema).
    OneOf(Vec<ConceptKind>),
}

/// What `cmd` produces when called with `args`.
pub fn produced(cmd: &Command, args: &Args) -> Result<Produced> {
    Ok(match &cmd.produces {
        Produces::Nothing => Produced::Nothing,
        Produces::Fixed(k) => Produced::Kind(*k),
        Produces::Dynamic(f) => Produced::Kind(f(args)?),
        // A Python integer, not a concept.
        Produces::Int => Produced::Nothing,
        Produces::Cases { one_of, cases } => {
            let values = |path: &str| -> Option<Vec<Probe>> {
                let (level, name) = match path.split_once('/') {
                    Some((fact, kw)) => (args.fact(fact)?, kw),
                    None => (args, path),
                };
                match &level.get(name)?.value {
                    ArgValue::Simple(v) => Some(v.iter().map(Probe::from_val).collect()),
                    ArgValue::Factor(_) => Some(vec![Probe::Present]),
                }
            };
            fn eval(c: &Cond, values: &dyn Fn(&str) -> Option<Vec<Probe>>) -> Option<bool> {
                holds_on(c, values, &|c| eval(c, values))
            }
            for (c, out) in cases {
                let Some(holds) = eval(c, &values) else { break };
                if holds {
                    return Ok(match out {
                        Outcome::Kind(k) => Produced::Kind(*k),
                        Outcome::Nothing => Produced::Nothing,
                        Outcome::TypeOf(path) => match values(path).and_then(|v| v.into_iter().next()) {
                            Some(Probe::Concept(c)) if c.alternatives().is_empty() => Produced::Kind(c.kind()),
                            Some(Probe::Concept(c)) => Produced::OneOf(c.alternatives()),
                            _ => Produced::OneOf(one_of.clone()),
                        },
                    });
                }
            }
            // What the cases do not tell: one of these types, each possibly a subtype (a
            // `resultat_sdaster` may be an evol_elas).
            match one_of.as_slice() {
                [] => Produced::Nothing,
                ks => Produced::OneOf(ks.to_vec()),
            }
        }
    })
}

fn cat_err(cmd: &str, msg: String, span: Span) -> Error {
    Error::catalog(msg).at(span).in_command(cmd)
}

struct Level<'a> {
    cmd: &'a str,
    /// "CMD" or "CMD/FACT" — used in messages.
    path: String,
    open: bool,
    /// The `CO('name')` values met so far.
    new: &'a RefCell<Vec<(ConceptRef, &'static [ConceptKind])>>,
    /// Validating against the stage's schema a call Code_Aster's accepts: a refusal means "not
    /// supported yet".
    supported: bool,
}

impl<'a> Level<'a> {
    /// The level of the factor keyword `name` inside this one.
    fn child(&self, name: &str) -> Level<'a> {
        Level {
            cmd: self.cmd,
            path: format!("{}/{}", self.path, name),
            open: false,
            new: self.new,
            supported: self.supported,
        }
    }
}

/// Where a keyword is declared: active now, or only inside an inactive block.
enum Found<'e> {
    Active,
    Inactive(&'e Cond),
    No,
}

impl<'a> Level<'a> {
    fn err(&self, msg: impl Into<String>, span: Span) -> Error {
        let msg = msg.into();
        let msg = match self.path.split_once('/') {
            Some((_, fpath)) => format!("{msg} (in {fpath})"),
            None => msg,
        };
        if self.supported {
            return Error::unsupported(format!("not supported yet: {msg}")).at(span).in_command(self.cmd);
        }
        cat_err(self.cmd, msg, span)
    }

    fn check(
        &self,
        entries: &[Entry],
        rules: &[Rule],
        given: Vec<KwArg>,
        span: Span,
        parents: &[&Args],
    ) -> Result<Args> {
        // `X=None` (or `()`, `[]`, `[None]`) means the keyword is absent, as in Code_Aster.
        let given: Vec<KwArg> = given.into_iter().filter(|k| !undefined(&k.value)).collect();

        // 1. Which entries are active, given the values and the defaults. An entry whose block
        // condition cannot be told without computing (it asks the type of a result `aster check`
        // does not know) may be given but is not required, and its block's rules are not checked.
        let mut active: Vec<&Entry> = Vec::new();
        let mut maybe: Vec<*const Entry> = Vec::new();
        let mut active_rules: Vec<&Rule> = rules.iter().collect();
        self.collect_active(entries, &given, parents, (&mut active, &mut maybe), &mut active_rules, false);
        let is_maybe = |e: &Entry| maybe.contains(&(e as *const Entry));

        // 2. Every given keyword must be active.
        for k in &given {
            match find(entries, &active, &k.name) {
                Found::Active => {}
                Found::Inactive(cond) => {
                    return Err(self.err(
                        format!("keyword '{}' is not allowed here: it requires {}", k.name, describe(cond)),
                        k.span,
                    ))
                }
                Found::No if self.open => {}
                Found::No if self.supported => {
                    let at = self.path.split_once('/').map(|(_, f)| format!(" (in {f})")).unwrap_or_default();
                    return Err(Error::unsupported(format!("keyword '{}' is not supported yet{at}", k.name))
                        .at(k.span)
                        .in_command(self.cmd));
                }
                Found::No => {
                    let mut names = Vec::new();
                    all_names(entries, &mut names);
                    let hint = match suggest(&k.name, &names) {
                        Some(s) => format!(" (did you mean '{s}'?)"),
                        None => String::new(),
                    };
                    return Err(self.err(format!("unknown keyword '{}'{hint}", k.name), k.span));
                }
            }
        }

        // 3. Convert and check each active entry. A name may be declared both
        // as a simple and as a factor keyword (DEBUT's CODE): the value decides.
        let has_fact = |n: &str| active.iter().any(|e| matches!(e, Entry::Fact(f) if f.name == n));
        let has_simp = |n: &str| active.iter().any(|e| matches!(e, Entry::Simp(s) if s.name == n));
        let mut declared = Vec::new();
        all_names(entries, &mut declared);
        let declared = (!self.open).then(|| Rc::new(declared));
        let mut out = Args { path: self.path.clone(), span, items: Vec::new(), declared };
        for e in &active {
            match e {
                Entry::Simp(s) => {
                    let k = given.iter().find(|k| k.name == s.name);
                    if k.map(|k| is_factor_value(&k.value) && has_fact(s.name)).unwrap_or(false) {
                        continue;
                    }
                    if k.is_none() && has_fact(s.name) && matches!(s.statut, Statut::F) {
                        continue;
                    }
                    if k.is_none() && is_maybe(e) {
                        continue;
                    }
                    if let Some(k) = k {
                        let vals = self.simple_values(s, &k.value, k.span)?;
                        out.items.push(Arg {
                            name: s.name.into(),
                            value: ArgValue::Simple(vals),
                            span: k.span,
                            defaulted: false,
                            read: Default::default(),
                        });
                    } else {
                        match &s.statut {
                            Statut::O => {
                                return Err(self.err(format!("mandatory keyword '{}' is missing", s.name), span))
                            }
                            Statut::D(d) => out.items.push(Arg {
                                name: s.name.into(),
                                value: ArgValue::Simple(d.iter().map(lit_val).collect()),
                                span,
                                defaulted: true,
                                read: Default::default(),
                            }),
                            Statut::F => {}
                        }
                    }
                }
                Entry::Fact(f) => {
                    let mut chain: Vec<&Args> = vec![&out];
                    chain.extend_from_slice(parents);
                    // `out` is borrowed for conditions of the nested level; build then push.
                    let k = given.iter().find(|k| k.name == f.name);
                    if k.map(|k| !is_factor_value(&k.value) && has_simp(f.name)).unwrap_or(false) {
                        continue;
                    }
                    let occ = if let Some(k) = k {
                        Some((self.factor(f, &k.value, k.span, &chain)?, k.span, false))
                    } else if is_maybe(e) {
                        None
                    } else {
                        match f.statut {
                            FactStatut::O => {
                                return Err(self.err(format!("mandatory keyword '{}' is missing", f.name), span))
                            }
                            FactStatut::D => {
                                let lvl = self.child(f.name);
                                Some((vec![lvl.check(&f.entries, &f.rules, Vec::new(), span, &chain)?], span, true))
                            }
                            FactStatut::F => None,
                        }
                    };
                    if let Some((occ, sp, defaulted)) = occ {
                        out.items.push(Arg {
                            name: f.name.into(),
                            value: ArgValue::Factor(occ),
                            span: sp,
                            defaulted,
                            read: Default::default(),
                        });
                    }
                }
                Entry::Bloc(_) => unreachable!("blocks are flattened"),
            }
        }
        if self.open {
            for k in &given {
                if matches!(find(entries, &active, &k.name), Found::No) {
                    let v = match &k.value {
                        Value::Concept(c) => Val::Concept(c.clone()),
                        v => Val::Callable(v.clone()),
                    };
                    out.items.push(Arg {
                        name: k.name.clone(),
                        value: ArgValue::Simple(vec![v]),
                        span: k.span,
                        defaulted: false,
                        read: Default::default(),
                    });
                }
            }
        }

        // 4. Rules.
        for r in active_rules {
            self.check_rule(r, &mut out, span)?;
        }
        Ok(out)
    }

    fn collect_active<'e>(
        &self,
        entries: &'e [Entry],
        given: &[KwArg],
        parents: &[&Args],
        (active, maybe): (&mut Vec<&'e Entry>, &mut Vec<*const Entry>),
        rules: &mut Vec<&'e Rule>,
        uncertain: bool,
    ) {
        // As Code_Aster: the keywords of a level (given or defaulted) first, then its blocks in order,
        // so that a block's condition sees a default declared after it.
        for e in entries.iter().filter(|e| !matches!(e, Entry::Bloc(_))) {
            active.push(e);
            if uncertain {
                maybe.push(e as *const Entry);
            }
        }
        for e in entries {
            if let Entry::Bloc(b) = e {
                let certain: Vec<&Entry> =
                    active.iter().filter(|x| !maybe.contains(&(**x as *const Entry))).copied().collect();
                match self.holds(&b.cond, given, &certain, parents) {
                    Some(false) => {}
                    Some(true) if !uncertain => {
                        rules.extend(b.rules.iter());
                        self.collect_active(&b.entries, given, parents, (active, maybe), rules, false);
                    }
                    _ => self.collect_active(&b.entries, given, parents, (active, maybe), rules, true),
                }
            }
        }
    }

    /// The values of keyword `name` as block conditions see them: given, else the default of an
    /// active entry, else from an enclosing level; None when absent.
    fn values_of(&self, name: &str, given: &[KwArg], active: &[&Entry], parents: &[&Args]) -> Option<Vec<Probe>> {
        if let Some(k) = given.iter().find(|k| k.name == name) {
            let items = match &k.value {
                Value::Tuple(_) | Value::List(_) | Value::Array(_) => k.value.iter_items().ok()?,
                v => vec![v.clone()],
            };
            return Some(items.iter().map(Probe::from_value).collect());
        }
        for e in active {
            if let Entry::Simp(s) = e {
                if s.name == name {
                    if let Statut::D(d) = &s.statut {
                        return Some(d.iter().map(|l| Probe::from_val(&lit_val(l))).collect());
                    }
                }
            }
            if let Entry::Fact(f) = e {
                if f.name == name && f.statut == FactStatut::D {
                    return Some(vec![Probe::Present]);
                }
            }
        }
        for p in parents {
            if let Some(a) = p.get(name) {
                return match &a.value {
                    ArgValue::Simple(v) => Some(v.iter().map(Probe::from_val).collect()),
                    ArgValue::Factor(_) => Some(vec![Probe::Present]),
                };
            }
        }
        None
    }

    /// Does the condition hold (None: it cannot be told without computing)?
    fn holds(&self, c: &Cond, given: &[KwArg], active: &[&Entry], parents: &[&Args]) -> Option<bool> {
        let vals = |k: &str| self.values_of(k, given, active, parents);
        let rec = |c: &Cond| self.holds(c, given, active, parents);
        holds_on(c, &vals, &rec)
    }

    fn factor(&self, f: &Fact, v: &Value, span: Span, parents: &[&Args]) -> Result<Vec<Args>> {
        let occurrences: Vec<Value> = match v {
            Value::Dict(_) => vec![v.clone()],
            Value::Tuple(_) | Value::List(_) => v.iter_items()?,
            other => {
                return Err(self.err(
                    format!(
                        "keyword '{}' expects _F(...) or a list of _F(...), got {} {}",
                        f.name,
                        other.type_name(),
                        format::repr(other)
                    ),
                    span,
                ))
            }
        };
        if occurrences.len() < f.min {
            return Err(self.err(format!("keyword '{}' needs at least {} occurrence(s)", f.name, f.min), span));
        }
        if let Some(max) = f.max {
            if occurrences.len() > max {
                return Err(self.err(
                    format!("keyword '{}' takes at most {max} occurrence(s), {} given", f.name, occurrences.len()),
                    span,
                ));
            }
        }
        let lvl = self.child(f.name);
        let mut out = Vec::new();
        for occ in occurrences {
            let Value::Dict(d) = &occ else {
                return Err(
                    self.err(format!("each occurrence of '{}' must be _F(...), got {}", f.name, occ.type_name()), span)
                );
            };
            let mut kws = Vec::new();
            for (k, val) in d.borrow().items.iter() {
                let Some(name) = k.as_str() else {
                    return Err(self.err(format!("keywords of '{}' must be strings", f.name), span));
                };
                kws.push(KwArg { name: name.to_string(), value: val.clone(), span });
            }
            out.push(lvl.check(&f.entries, &f.rules, kws, span, parents)?);
        }
        Ok(out)
    }

    fn simple_values(&self, s: &Simp, v: &Value, span: Span) -> Result<Vec<Val>> {
        if matches!(v, Value::Dict(_)) {
            return Err(
                self.err(format!("keyword '{}' is a simple keyword; _F(...) is not allowed here", s.name), span)
            );
        }
        let mut items = match v {
            // A numpy array is a sequence of its values (its rows for a 2-D one), as in Code_Aster.
            Value::Tuple(_) | Value::List(_) | Value::Array(_) => v.iter_items()?,
            _ => vec![v.clone()],
        };
        if s.types.contains(&Ty::C) {
            // Code_Aster's older complex notation: ('RI', re, im) or ('MP', modulus, phase in degrees),
            // alone or in a list.
            if old_complex(v).is_some() {
                items = vec![v.clone()];
            }
            items = items.into_iter().map(|i| old_complex(&i).unwrap_or(i)).collect();
        }
        let n = items.len();
        if let Some(max) = s.max {
            if n > max {
                return Err(self.err(format!("keyword '{}' takes at most {max} value(s), {n} given", s.name), span));
            }
        }
        if n < s.min.max(1) {
            return Err(
                self.err(format!("keyword '{}' needs at least {} value(s), {n} given", s.name, s.min.max(1)), span)
            );
        }
        let mut out = Vec::with_capacity(n);
        for item in &items {
            let val = s
                .types
                .iter()
                .find_map(|t| convert(t, item))
                .or_else(|| s.types.iter().find_map(|t| integral(t, item)))
                .ok_or_else(|| {
                    let want: Vec<String> = s.types.iter().map(type_desc).collect();
                    self.err(
                        format!(
                            "keyword '{}' expects {}, got {} {}",
                            s.name,
                            want.join(" or "),
                            item.type_name(),
                            short_repr(item)
                        ),
                        span,
                    )
                })?;
            if let Some(allowed) = &s.allowed {
                if !allowed.iter().any(|a| val_eq_lit(&val, a)) {
                    let list: Vec<String> = allowed.iter().map(|a| a.to_string()).collect();
                    let hint = match &val {
                        Val::T(t) => {
                            let names: Vec<&str> = allowed
                                .iter()
                                .filter_map(|a| if let Lit::T(t) = a { Some(*t) } else { None })
                                .collect();
                            suggest(t, &names).map(|x| format!(" (did you mean '{x}'?)")).unwrap_or_default()
                        }
                        _ => String::new(),
                    };
                    return Err(self.err(
                        format!(
                            "value {} is not allowed for keyword '{}'{hint}; allowed: {}",
                            val.show(),
                            s.name,
                            list.join(", ")
                        ),
                        span,
                    ));
                }
            }
            if let (Val::Concept(c), true) = (&val, c_is_new(&val)) {
                if let Some(kinds) =
                    s.types.iter().find_map(|t| if let Ty::NewConcept(k) = t { Some(*k) } else { None })
                {
                    self.new.borrow_mut().push((c.clone(), kinds));
                }
            }
            if let Some(x) = val.as_f64() {
                let below = s.val_min.is_some_and(|m| x < m || (s.min_open && x == m));
                let above = s.val_max.is_some_and(|m| x > m || (s.max_open && x == m));
                if below || above {
                    return Err(self.err(
                        format!(
                            "value {} of keyword '{}' is outside [{}, {}]",
                            val.show(),
                            s.name,
                            s.val_min.map(|m| m.to_string()).unwrap_or("-inf".into()),
                            s.val_max.map(|m| m.to_string()).unwrap_or("+inf".into())
                        ),
                        span,
                    ));
                }
            }
            out.push(val);
        }
        for c in &s.checks {
            if let Some(msg) = check_values(c, &out) {
                return Err(self.err(format!("keyword '{}': {msg}", s.name), span));
            }
        }
        Ok(out)
    }

    fn check_rule(&self, r: &Rule, a: &mut Args, span: Span) -> Result<()> {
        if let Rule::WithDefaults(inner, defaults) = r {
            if !inner.keywords().iter().any(|k| a.has(k)) {
                for (k, v) in defaults {
                    a.items.push(Arg {
                        name: k.to_string(),
                        value: ArgValue::Simple(vec![lit_val(v)]),
                        span,
                        defaulted: true,
                        read: Default::default(),
                    });
                }
            }
            return self.check_rule(inner, a, span);
        }
        let a = &*a;
        let present =
            |names: &[&str]| -> Vec<String> { names.iter().filter(|n| a.has(n)).map(|n| n.to_string()).collect() };
        let quoted = |v: &[&str]| v.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ");
        match r {
            Rule::UnParmi(ks) => {
                let p = present(ks);
                if p.len() != 1 {
                    let got = if p.is_empty() { "none".to_string() } else { p.join(" and ") };
                    return Err(self.err(format!("exactly one of {} is required (got {got})", quoted(ks)), span));
                }
            }
            Rule::AuMoinsUn(ks) => {
                if present(ks).is_empty() {
                    return Err(self.err(format!("at least one of {} is required", quoted(ks)), span));
                }
            }
            Rule::Exclus(ks) => {
                let p = present(ks);
                if p.len() > 1 {
                    return Err(
                        self.err(format!("{} are mutually exclusive (got {})", quoted(ks), p.join(" and ")), span)
                    );
                }
            }
            Rule::Ensemble(ks) => {
                let p = present(ks);
                if !p.is_empty() && p.len() != ks.len() {
                    return Err(
                        self.err(format!("{} go together: all or none (got only {})", quoted(ks), p.join(", ")), span)
                    );
                }
            }
            Rule::PresentPresent(first, ks) => {
                if a.has(first) {
                    let missing: Vec<&str> = ks.iter().filter(|k| !a.has(k)).copied().collect();
                    if !missing.is_empty() {
                        return Err(self.err(format!("'{first}' requires {}", quoted(&missing)), span));
                    }
                }
            }
            Rule::PresentAbsent(first, ks) => {
                if a.has(first) {
                    let p = present(ks);
                    if !p.is_empty() {
                        return Err(self.err(format!("'{first}' excludes {}", p.join(", ")), span));
                    }
                }
            }
            Rule::NotEmpty => {
                if a.items.is_empty() {
                    return Err(self.err("at least one keyword is required", span));
                }
            }
            Rule::WithDefaults(..) => unreachable!("handled above"),
        }
        Ok(())
    }
}

fn find<'e>(entries: &'e [Entry], active: &[&'e Entry], name: &str) -> Found<'e> {
    let is = |e: &Entry| match e {
        Entry::Simp(s) => s.name == name,
        Entry::Fact(f) => f.name == name,
        Entry::Bloc(_) => false,
    };
    if active.iter().any(|e| is(e)) {
        return Found::Active;
    }
    fn in_blocs<'e>(entries: &'e [Entry], name: &str) -> Option<&'e Cond> {
        for e in entries {
            if let Entry::Bloc(b) = e {
                let direct = b.entries.iter().any(|x| match x {
                    Entry::Simp(s) => s.name == name,
                    Entry::Fact(f) => f.name == name,
                    Entry::Bloc(_) => false,
                });
                if direct {
                    return Some(&b.cond);
                }
                if let Some(c) = in_blocs(&b.entries, name) {
                    return Some(c);
                }
            }
        }
        None
    }
    match in_blocs(entries, name) {
        Some(c) => Found::Inactive(c),
        None => Found::No,
    }
}

/// Is this value a `CO('name')`, a concept the command is to create?
fn c_is_new(v: &Val) -> bool {
    matches!(v, Val::Concept(c) if c.kind() == ConceptKind::Co)
}

/// A validator's verdict on the values of a keyword: None when they pass, else what is wrong.
fn check_values(c: &Check, vals: &[Val]) -> Option<String> {
    let same = |a: &Val, b: &Val| match (a, b) {
        (Val::Concept(x), Val::Concept(y)) => Rc::ptr_eq(x, y),
        (Val::T(x), Val::T(y)) => x == y,
        _ => match (a.as_f64(), b.as_f64()) {
            (Some(x), Some(y)) => x == y,
            _ => false,
        },
    };
    match c {
        Check::NoRepeat => {
            for (i, a) in vals.iter().enumerate() {
                if vals[..i].iter().any(|b| same(a, b)) {
                    return Some(format!("all the values must differ, {} is repeated", a.show()));
                }
            }
            None
        }
        Check::Ordered(desc) => {
            for w in vals.windows(2) {
                let ok = match (w[0].as_f64(), w[1].as_f64(), &w[0], &w[1]) {
                    (Some(a), Some(b), _, _) => {
                        if *desc {
                            a >= b
                        } else {
                            a <= b
                        }
                    }
                    (_, _, Val::T(a), Val::T(b)) => {
                        if *desc {
                            a >= b
                        } else {
                            a <= b
                        }
                    }
                    _ => true,
                };
                if !ok {
                    let order = if *desc { "decreasing" } else { "increasing" };
                    return Some(format!("the values must be in {order} order: {} then {}", w[0].show(), w[1].show()));
                }
            }
            None
        }
        Check::Len(lo, hi) => vals.iter().find_map(|v| match v {
            Val::T(t) if t.chars().count() < *lo || t.chars().count() > *hi => {
                Some(format!("'{t}' has {} characters, {lo} to {hi} are allowed", t.chars().count()))
            }
            _ => None,
        }),
        Check::Values(vc) => (!values_ok(vc, vals)).then(|| format!("the values must satisfy: {vc}")),
    }
}

fn values_ok(c: &ValCheck, vals: &[Val]) -> bool {
    let has = |l: &Lit| vals.iter().any(|v| val_eq_lit(v, l));
    match c {
        ValCheck::HasAll(ls) => ls.iter().all(has),
        ValCheck::Together(ls) => {
            let n = ls.iter().filter(|l| has(l)).count();
            n == 0 || n == ls.len()
        }
        ValCheck::HasNone(ls) => !ls.iter().any(has),
        ValCheck::OnePrefix(p) => {
            let mut seen: Vec<&str> = vals.iter().filter_map(Val::as_text).filter(|t| t.starts_with(p)).collect();
            seen.sort_unstable();
            seen.dedup();
            seen.len() <= 1
        }
        ValCheck::And(cs) => cs.iter().all(|c| values_ok(c, vals)),
        ValCheck::Or(cs) => cs.iter().any(|c| values_ok(c, vals)),
    }
}

/// An `and` (`decisive` false) or an `or` (`decisive` true) of operands that may be uncertain (None).
fn decided_by(r: Vec<Option<bool>>, decisive: bool) -> Option<bool> {
    if r.contains(&Some(decisive)) {
        Some(decisive)
    } else if r.contains(&None) {
        None
    } else {
        Some(!decisive)
    }
}

/// `('RI', re, im)` or `('MP', modulus, degrees)` as a complex.
fn old_complex(v: &Value) -> Option<Value> {
    if !matches!(v, Value::Tuple(_) | Value::List(_)) {
        return None;
    }
    let items = v.iter_items().ok()?;
    let [tag, a, b] = items.as_slice() else { return None };
    let (a, b) = (a.as_f64()?, b.as_f64()?);
    match tag.as_str()? {
        "RI" => Some(Value::Complex(a, b)),
        "MP" => {
            let p = b * std::f64::consts::PI / 180.0;
            Some(Value::Complex(a * p.cos(), a * p.sin()))
        }
        _ => None,
    }
}

/// Code_Aster's undefined value: None, an empty list or tuple, or `[None]`.
fn undefined(v: &Value) -> bool {
    match v {
        Value::None => true,
        Value::Tuple(_) | Value::List(_) => {
            let items = v.iter_items().unwrap_or_default();
            items.is_empty() || (items.len() == 1 && matches!(items[0], Value::None))
        }
        _ => false,
    }
}

fn is_factor_value(v: &Value) -> bool {
    match v {
        Value::Dict(_) => true,
        Value::Tuple(_) | Value::List(_) => {
            let items = v.iter_items().unwrap_or_default();
            !items.is_empty() && items.iter().all(|i| matches!(i, Value::Dict(_)))
        }
        _ => false,
    }
}

fn all_names(entries: &[Entry], out: &mut Vec<&'static str>) {
    for e in entries {
        match e {
            Entry::Simp(s) => out.push(s.name),
            Entry::Fact(f) => out.push(f.name),
            Entry::Bloc(b) => all_names(&b.entries, out),
        }
    }
}

fn describe(c: &Cond) -> String {
    c.to_string()
}

/// A keyword value as block conditions see it.
pub(crate) enum Probe {
    T(String),
    I(i64),
    R(f64),
    Concept(ConceptRef),
    /// Present, with no value a condition can compare (a factor, another Python object).
    Present,
}

impl Probe {
    pub(crate) fn from_val(v: &Val) -> Probe {
        match v {
            Val::T(t) => Probe::T(t.clone()),
            Val::I(i) => Probe::I(*i),
            Val::R(r) => Probe::R(*r),
            Val::Concept(c) => Probe::Concept(c.clone()),
            _ => Probe::Present,
        }
    }
    fn from_value(v: &Value) -> Probe {
        match v {
            Value::Str(s) => Probe::T(s.to_string()),
            Value::Int(i) => Probe::I(*i),
            Value::Float(f) => Probe::R(*f),
            Value::Bool(b) => Probe::I(*b as i64),
            Value::Concept(c) => Probe::Concept(c.clone()),
            _ => Probe::Present,
        }
    }
    fn matches(&self, l: &Lit) -> bool {
        match (self, l) {
            (Probe::T(x), Lit::T(y)) => x == y,
            (Probe::I(x), Lit::I(y)) => x == y,
            (Probe::R(x), Lit::R(y)) => x == y,
            (Probe::I(x), Lit::R(y)) | (Probe::R(y), Lit::I(x)) => *x as f64 == *y,
            _ => false,
        }
    }
    fn number(&self) -> Option<f64> {
        match self {
            Probe::I(i) => Some(*i as f64),
            Probe::R(r) => Some(*r),
            _ => None,
        }
    }
}

/// Evaluate a condition given how to find a keyword's values (`None`: absent) and how to evaluate a
/// sub-condition; None when it cannot be told without computing (the type of a result `aster check`
/// does not know). Shared by block conditions (on the call's keywords) and result-type cases (on the
/// validated arguments).
pub(crate) fn holds_on(
    c: &Cond,
    vals: &dyn Fn(&str) -> Option<Vec<Probe>>,
    rec: &dyn Fn(&Cond) -> Option<bool>,
) -> Option<bool> {
    Some(match c {
        Cond::Eq(k, v) => vals(k).is_some_and(|x| x.iter().any(|p| p.matches(v))),
        Cond::In(k, vs) => vals(k).is_some_and(|x| x.iter().any(|p| vs.iter().any(|v| p.matches(v)))),
        Cond::Present(k) => vals(k).is_some(),
        Cond::Absent(k) => vals(k).is_none(),
        // Three-valued: one decisive operand decides, else an uncertain one leaves it uncertain.
        Cond::And(cs) => return decided_by(cs.iter().map(rec).collect(), false),
        Cond::Or(cs) => return decided_by(cs.iter().map(rec).collect(), true),
        Cond::Not(c) => !rec(c)?,
        Cond::True => true,
        Cond::False => false,
        Cond::Type(k, kinds) => match vals(k).and_then(|x| x.into_iter().next()) {
            Some(Probe::Concept(c)) if kinds.iter().any(|t| c.kind().is_a(*t)) => true,
            Some(Probe::Concept(c)) if kinds.iter().any(|t| c.may_be(*t)) => return None,
            _ => false,
        },
        Cond::Prefix(k, p) => vals(k).is_some_and(|x| matches!(x.first(), Some(Probe::T(t)) if t.starts_with(p))),
        Cond::Less(k, v) => vals(k).is_some_and(|x| x.len() == 1 && x[0].number().is_some_and(|n| n < *v)),
        Cond::Greater(k, v) => vals(k).is_some_and(|x| x.len() == 1 && x[0].number().is_some_and(|n| n > *v)),
        Cond::Count(k, op, n) => vals(k).is_some_and(|x| op.holds(x.len(), *n)),
        Cond::AbsLess(k, v) => vals(k).is_some_and(|x| x.first().and_then(Probe::number).is_some_and(|n| n.abs() < *v)),
        Cond::SameTail(k, n) => vals(k).is_some_and(|x| match (x.first(), x.get(1)) {
            (Some(Probe::T(a)), Some(Probe::T(b))) => a.get(*n..).unwrap_or("") == b.get(*n..).unwrap_or(""),
            _ => false,
        }),
    })
}

fn lit_val(l: &Lit) -> Val {
    match l {
        Lit::I(i) => Val::I(*i),
        Lit::R(r) => Val::R(*r),
        Lit::C(a, b) => Val::C(*a, *b),
        Lit::T(t) => Val::T(t.to_string()),
    }
}

fn val_eq_lit(v: &Val, l: &Lit) -> bool {
    match (v, l) {
        (Val::T(a), Lit::T(b)) => a == b,
        (Val::I(a), Lit::I(b)) => a == b,
        (Val::R(a), Lit::R(b)) => a == b,
        (Val::I(a), Lit::R(b)) | (Val::R(b), Lit::I(a)) => *a as f64 == *b,
        (Val::C(a, b), Lit::C(c, d)) => a == c && b == d,
        _ => false,
    }
}

/// A float equal to its integer part given to an integer keyword: Code_Aster's syntax checker takes it as
/// that integer (tried only when no declared type takes the value as it is, so a keyword of integers or
/// reals keeps a real).
fn integral(t: &Ty, v: &Value) -> Option<Val> {
    match (t, v) {
        (Ty::I, Value::Float(f)) if f.fract() == 0.0 && f.abs() < 9.0e15 => Some(Val::I(*f as i64)),
        _ => None,
    }
}

fn convert(t: &Ty, v: &Value) -> Option<Val> {
    match (t, v) {
        (Ty::I, Value::Int(i)) => Some(Val::I(*i)),
        (Ty::I, Value::Bool(b)) => Some(Val::I(*b as i64)),
        // Code_Aster takes a float of integral value for an integer.
        (Ty::I, Value::Float(f)) if f.fract() == 0.0 && f.abs() < 9.0e15 => Some(Val::I(*f as i64)),
        (Ty::R, Value::Float(f)) => Some(Val::R(*f)),
        (Ty::R, Value::Int(i)) => Some(Val::R(*i as f64)),
        (Ty::C, Value::Complex(a, b)) => Some(Val::C(*a, *b)),
        (Ty::C, v) if v.as_f64().is_some() => Some(Val::C(v.as_f64().unwrap(), 0.0)),
        (Ty::Txm, Value::Str(s)) => Some(Val::T(s.to_string())),
        (Ty::Co(kinds), Value::Concept(c)) if kinds.iter().any(|k| c.may_be(*k)) => Some(Val::Concept(c.clone())),
        (Ty::Callable, Value::Func(_) | Value::Builtin(_) | Value::Method(..)) => Some(Val::Callable(v.clone())),
        (Ty::NewConcept(_), Value::Concept(c)) => Some(Val::Concept(c.clone())),
        (Ty::Any, Value::Concept(c)) => Some(Val::Concept(c.clone())),
        (Ty::Any, Value::Str(s)) => Some(Val::T(s.to_string())),
        (Ty::Any, Value::Int(i)) => Some(Val::I(*i)),
        (Ty::Any, Value::Float(f)) => Some(Val::R(*f)),
        (Ty::Any, v) => Some(Val::Callable(v.clone())),
        _ => None,
    }
}

fn type_desc(t: &Ty) -> String {
    match t {
        Ty::I => "an integer".into(),
        Ty::R => "a real".into(),
        Ty::C => "a complex".into(),
        Ty::Txm => "a text".into(),
        Ty::Co(k) => k.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(" or "),
        Ty::Callable => "a Python function".into(),
        Ty::Any => "any value".into(),
        Ty::NewConcept(k) => format!(
            "CO('name') (a new {}) or a concept",
            k.iter().map(|k| k.aster_name()).collect::<Vec<_>>().join(" or ")
        ),
    }
}

fn short_repr(v: &Value) -> String {
    let r = format::repr(v);
    if r.chars().count() > 40 {
        format!("{}...", r.chars().take(37).collect::<String>())
    } else {
        r
    }
}

/// Edit distance with adjacent transpositions.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// The closest name, if close enough to be a plausible typo.
pub fn suggest<'n>(word: &str, names: &[&'n str]) -> Option<&'n str> {
    let up = word.to_uppercase();
    names
        .iter()
        .map(|n| (distance(&up, &n.to_uppercase()), *n))
        .filter(|(d, n)| *d <= (n.len() / 3).clamp(1, 3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        assert_eq!(suggest("ZONNE", &["ZONE", "MODELE", "FORMULATION"]), Some("ZONE"));
        assert_eq!(suggest("MODLE", &["ZONE", "MODELE"]), Some("MODELE"));
        assert_eq!(suggest("XYZ", &["ZONE", "MODELE"]), None);
    }
}
