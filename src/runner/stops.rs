//! What stops the cases of a suite: each case that did not pass is put down to one *stop* — the
//! command, keyword, modelisation, behaviour, Python construct or missing file its run stopped on —
//! and the stops are counted, so that `aster suite` can say which piece of work would unlock how
//! many cases (a table in the terminal, `stops.csv` and `suite.json` beside the JUnit report).
//!
//! A stop is read from what the run reported: the kind of its error, the command it arose in and
//! the message (`CMD: KEY/WORD: KEYWORD='VALUE' is not supported yet`, `unknown command 'X'`,
//! `import numpy: ...`), or its first NOOK check.

use super::suite::CaseResult;
use super::Diagnostic;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Why a case did not pass.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Stop {
    /// `command`, `keyword`, `value`, `modelisation`, `behaviour`, `phenomenon`, `python`,
    /// `syntax`, `data file`, `time limit`, `NOOK`, `no check`, `internal error`, `error`.
    pub category: &'static str,
    /// What exactly: `CALC_MODES`, `LIRE_MAILLAGE FORMAT='GIBI'`, `DKT`, `import numpy`, ...
    pub name: String,
}

impl Stop {
    fn new(category: &'static str, name: impl Into<String>) -> Stop {
        Stop { category, name: name.into() }
    }
}

/// The text between the first pair of quotes (`'...'`) of `s`.
fn quoted(s: &str) -> Option<&str> {
    let a = s.find('\'')?;
    let b = s[a + 1..].find('\'')?;
    Some(&s[a + 1..a + 1 + b])
}

/// The last component of a keyword path (`AFFE/MODELISATION` → `MODELISATION`).
fn last(path: &str) -> &str {
    path.rsplit('/').next().unwrap_or(path)
}

/// The stop of a run that ended with `kind` (the name of its error kind), in command `command` (if
/// any), with message `msg` (without its location).
pub fn classify_error(kind: &str, command: Option<&str>, msg: &str) -> Stop {
    let cmd = command.unwrap_or("");
    let within = |what: String| if cmd.is_empty() { what } else { format!("{cmd} {what}") };
    if kind == "TimeLimit" || msg.contains("time limit of") {
        return Stop::new("time limit", if cmd.is_empty() { "run".to_string() } else { cmd.to_string() });
    }
    if kind == "Internal" {
        return Stop::new("internal error", if cmd.is_empty() { "run".to_string() } else { cmd.to_string() });
    }
    if let Some(rest) = msg.strip_prefix("unknown command ") {
        return Stop::new("command", quoted(rest).unwrap_or(rest));
    }
    if msg.contains("several command files (POURSUITE)") {
        return Stop::new("command", "POURSUITE");
    }
    if let Some(name) = msg.strip_suffix(" is not supported yet").filter(|n| !n.contains([' ', ':', '='])) {
        return Stop::new("command", name);
    }
    if let Some(rest) = msg.strip_prefix("import ") {
        let module = rest.split([':', ' ']).next().unwrap_or(rest);
        let top = module.split('.').next().unwrap_or(module);
        return Stop::new("python", format!("import {top}"));
    }
    if let Some(rest) = msg.strip_prefix("NameError: name ") {
        return Stop::new("python", format!("name {}", quoted(rest).unwrap_or(rest)));
    }
    if let Some(rest) = msg.strip_prefix("invalid syntax: unexpected ") {
        return Stop::new("syntax", quoted(rest).unwrap_or(rest).to_string());
    }
    if msg.contains("data file") && msg.contains("does not exist") {
        return Stop::new("data file", "absent from the folder");
    }
    // `KEY/WORD: KEYWORD='VALUE' is not supported yet`: a value of a keyword.
    if let Some((path, rest)) = msg.split_once(": ") {
        let path = path.trim();
        let is_path =
            !path.is_empty() && path.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || "_/".contains(c));
        if is_path && (rest.contains("not supported") || rest.contains("does not use this keyword")) {
            if let Some((kw, value)) = rest.split_once("='") {
                let kw = last(kw.trim());
                let value = value.split('\'').next().unwrap_or(value);
                return match kw {
                    "MODELISATION" => Stop::new("modelisation", value),
                    "RELATION" => Stop::new("behaviour", value),
                    "PHENOMENE" => Stop::new("phenomenon", value),
                    _ => Stop::new("value", within(format!("{kw}='{value}'"))),
                };
            }
            return Stop::new("keyword", within(path.to_string()));
        }
    }
    if let Some(rest) = msg.strip_prefix("unknown keyword ") {
        return Stop::new("keyword", within(quoted(rest).unwrap_or(rest).to_string()));
    }
    if let Some(pos) = msg.find("unknown keyword '") {
        return Stop::new("keyword", within(quoted(&msg[pos..]).unwrap_or("?").to_string()));
    }
    if kind == "Unsupported" {
        return Stop::new("unsupported", within(head(msg)));
    }
    if kind == "Python" {
        return Stop::new("python", head(msg));
    }
    if kind == "Syntax" {
        return Stop::new("syntax", head(msg));
    }
    let cat = if kind == "Catalog" { "catalogue" } else { "error" };
    Stop::new(cat, if cmd.is_empty() { head(msg) } else { cmd.to_string() })
}

/// The first words of a message (up to a colon or 60 characters), for grouping.
fn head(msg: &str) -> String {
    let first = msg.split(": ").next().unwrap_or(msg);
    first.chars().take(60).collect()
}

/// The stop of a case, `None` if it passed.
pub fn classify(r: &CaseResult) -> Option<Stop> {
    match r.diagnostic {
        Diagnostic::Ok => None,
        Diagnostic::NookTestResu => Some(Stop::new("NOOK", r.first_nook.clone().unwrap_or_else(|| "check".into()))),
        Diagnostic::NoTestResu if r.error.is_none() => Some(Stop::new("no check", "the run made no check")),
        _ => {
            let msg = r.message.as_deref().or(r.error.as_deref()).unwrap_or("");
            Some(classify_error(r.kind.as_deref().unwrap_or(""), r.command.as_deref(), msg))
        }
    }
}

/// Every stop with the cases it stops (in name order), most cases first.
pub fn tally(results: &[CaseResult]) -> Vec<(Stop, Vec<String>)> {
    let mut by: BTreeMap<Stop, Vec<String>> = BTreeMap::new();
    for r in results {
        if let Some(s) = classify(r) {
            by.entry(s).or_default().push(r.name.clone());
        }
    }
    let mut v: Vec<(Stop, Vec<String>)> = by.into_iter().collect();
    v.sort_by(|a, b| b.1.len().cmp(&a.1.len()).then_with(|| a.0.cmp(&b.0)));
    v
}

/// Cases per category (`command`: 2,000, ...), most first.
fn per_category(t: &[(Stop, Vec<String>)]) -> Vec<(&'static str, usize, usize)> {
    let mut by: BTreeMap<&'static str, (usize, usize)> = BTreeMap::new();
    for (s, cases) in t {
        let e = by.entry(s.category).or_default();
        e.0 += cases.len();
        e.1 += 1;
    }
    let mut v: Vec<(&'static str, usize, usize)> = by.into_iter().map(|(k, (n, d))| (k, n, d)).collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
    v
}

fn examples(cases: &[String], n: usize) -> String {
    let mut s = cases.iter().take(n).cloned().collect::<Vec<_>>().join(" ");
    if cases.len() > n {
        s.push_str(" ...");
    }
    s
}

/// The terminal summary: totals, cases per category, and the `top` stops that stop the most cases.
pub fn table(results: &[CaseResult], top: usize) -> String {
    let t = tally(results);
    let mut s = String::new();
    let n = results.len();
    let count = |d: Diagnostic| results.iter().filter(|r| r.diagnostic == d).count();
    let _ = writeln!(
        s,
        "\n{n} cases: {} OK, {} NOOK, {} without checks, {} stopped by an error",
        count(Diagnostic::Ok),
        count(Diagnostic::NookTestResu),
        count(Diagnostic::NoTestResu),
        count(Diagnostic::Error) + count(Diagnostic::SyntaxError)
    );
    if t.is_empty() {
        return s;
    }
    let _ = writeln!(s, "\nwhat stops the cases, by kind:");
    let _ = writeln!(s, "  {:<16} {:>6} {:>8}", "KIND", "CASES", "DISTINCT");
    for (cat, cases, distinct) in per_category(&t) {
        let _ = writeln!(s, "  {cat:<16} {cases:>6} {distinct:>8}");
    }
    let _ = writeln!(s, "\nthe {} stops that stop the most cases (stops.csv has them all):", top.min(t.len()));
    let _ = writeln!(s, "  {:>5}  {:<14} {:<44} EXAMPLES", "CASES", "KIND", "STOP");
    for (stop, cases) in t.iter().take(top) {
        let _ = writeln!(s, "  {:>5}  {:<14} {:<44} {}", cases.len(), stop.category, stop.name, examples(cases, 3));
    }
    s
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `stops.csv`: one row per stop, most cases first.
pub fn csv(results: &[CaseResult]) -> String {
    let mut s = String::from("kind,stop,cases,examples\n");
    for (stop, cases) in tally(results) {
        let _ = writeln!(
            s,
            "{},{},{},{}",
            csv_field(stop.category),
            csv_field(&stop.name),
            cases.len(),
            csv_field(&examples(&cases, 10))
        );
    }
    s
}

fn json_str(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 2);
    o.push('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            '\n' => o.push_str("\\n"),
            '\r' => o.push_str("\\r"),
            '\t' => o.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

/// `suite.json`: the totals, the stops with all their cases, and every case with its stop.
pub fn json(results: &[CaseResult]) -> String {
    let count = |d: Diagnostic| results.iter().filter(|r| r.diagnostic == d).count();
    let mut s = String::from("{\n");
    let _ = writeln!(
        s,
        "  \"cases\": {}, \"ok\": {}, \"nook\": {}, \"no_check\": {}, \"error\": {},",
        results.len(),
        count(Diagnostic::Ok),
        count(Diagnostic::NookTestResu),
        count(Diagnostic::NoTestResu),
        count(Diagnostic::Error) + count(Diagnostic::SyntaxError)
    );
    s.push_str("  \"stops\": [\n");
    let t = tally(results);
    for (i, (stop, cases)) in t.iter().enumerate() {
        let list: Vec<String> = cases.iter().map(|c| json_str(c)).collect();
        let _ = write!(
            s,
            "    {{\"kind\": {}, \"stop\": {}, \"count\": {}, \"cases\": [{}]}}",
            json_str(stop.category),
            json_str(&stop.name),
            cases.len(),
            list.join(", ")
        );
        s.push_str(if i + 1 < t.len() { ",\n" } else { "\n" });
    }
    s.push_str("  ],\n  \"results\": [\n");
    for (i, r) in results.iter().enumerate() {
        let stop = classify(r);
        let _ = write!(
            s,
            "    {{\"name\": {}, \"diagnostic\": {}, \"ok\": {}, \"nook\": {}, \"seconds\": {:.3}",
            json_str(&r.name),
            json_str(r.diagnostic.name()),
            r.ok,
            r.nook,
            r.seconds
        );
        if let Some(st) = stop {
            let _ = write!(s, ", \"kind\": {}, \"stop\": {}", json_str(st.category), json_str(&st.name));
        }
        if let Some(e) = &r.error {
            let _ = write!(s, ", \"error\": {}", json_str(e));
        }
        s.push('}');
        s.push_str(if i + 1 < results.len() { ",\n" } else { "\n" });
    }
    s.push_str("  ]\n}\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stop(kind: &str, cmd: Option<&str>, msg: &str) -> (String, String) {
        let s = classify_error(kind, cmd, msg);
        (s.category.to_string(), s.name)
    }

    #[test]
    fn messages_are_put_down_to_what_stops_them() {
        let cases: [(&str, Option<&str>, &str, &str, &str); 14] = [
            ("Catalog", None, "unknown command 'CALC_MODES'", "command", "CALC_MODES"),
            ("Unsupported", None, "NUME_DDL is not supported yet", "command", "NUME_DDL"),
            (
                "Unsupported",
                None,
                "a.export: several command files (POURSUITE) are not supported yet",
                "command",
                "POURSUITE",
            ),
            ("Unsupported", None, "import numpy: numpy is not supported by aster-rs", "python", "import numpy"),
            ("Unsupported", None, "import code_aster.CA: the code_aster object API", "python", "import code_aster"),
            ("Python", None, "NameError: name 'COPIER' is not defined", "python", "name COPIER"),
            ("Syntax", None, "invalid syntax: unexpected 'with'", "syntax", "with"),
            (
                "Runtime",
                Some("AFFE_MODELE"),
                "AFFE/MODELISATION: MODELISATION='DKT' is not supported yet",
                "modelisation",
                "DKT",
            ),
            (
                "Runtime",
                Some("STAT_NON_LINE"),
                "COMPORTEMENT/RELATION: RELATION='VMIS_ISOT_LINE' is not supported yet",
                "behaviour",
                "VMIS_ISOT_LINE",
            ),
            (
                "Runtime",
                Some("LIRE_MAILLAGE"),
                "FORMAT: FORMAT='GIBI' is not supported yet (only 'MED' and 'ASTER')",
                "value",
                "LIRE_MAILLAGE FORMAT='GIBI'",
            ),
            ("Runtime", Some("CALC_CHAMP"), "ENERGIE: not supported yet", "keyword", "CALC_CHAMP ENERGIE"),
            (
                "Catalog",
                Some("DEFI_MATERIAU"),
                "unknown keyword 'ELAS_MEMBRANE'",
                "keyword",
                "DEFI_MATERIAU ELAS_MEMBRANE",
            ),
            ("Io", None, "unit 20: data file /x/zzzz506k.mmed does not exist", "data file", "absent from the folder"),
            ("TimeLimit", Some("STAT_NON_LINE"), "time limit of 60 s exceeded", "time limit", "STAT_NON_LINE"),
        ];
        for (kind, cmd, msg, cat, name) in cases {
            assert_eq!(stop(kind, cmd, msg), (cat.to_string(), name.to_string()), "{msg}");
        }
    }

    fn case(name: &str, d: Diagnostic, kind: &str, cmd: Option<&str>, msg: &str) -> CaseResult {
        CaseResult {
            name: name.into(),
            diagnostic: d,
            ok: 0,
            nook: 0,
            skip: 0,
            seconds: 0.5,
            error: (!msg.is_empty()).then(|| format!("x.comm:1:1: {msg}")),
            kind: (!kind.is_empty()).then(|| kind.into()),
            command: cmd.map(str::to_string),
            message: (!msg.is_empty()).then(|| msg.into()),
            first_nook: None,
        }
    }

    #[test]
    fn stops_are_counted_most_first_with_their_cases() {
        let results = vec![
            case("a", Diagnostic::Ok, "", None, ""),
            case("b", Diagnostic::SyntaxError, "Catalog", None, "unknown command 'NUME_DDL'"),
            case("c", Diagnostic::Error, "Unsupported", None, "import numpy: no"),
            case("d", Diagnostic::SyntaxError, "Catalog", None, "unknown command 'NUME_DDL'"),
            case("e", Diagnostic::NookTestResu, "", None, ""),
        ];
        let t = tally(&results);
        assert_eq!(t[0].0, Stop::new("command", "NUME_DDL"));
        assert_eq!(t[0].1, vec!["b".to_string(), "d".to_string()]);
        assert_eq!(t.len(), 3);
        let text = table(&results, 10);
        assert!(text.contains("5 cases: 1 OK, 1 NOOK, 0 without checks, 3 stopped by an error"), "{text}");
        let csv = csv(&results);
        assert_eq!(csv.lines().nth(1), Some("command,NUME_DDL,2,b d"));
        let js = json(&results);
        assert!(js.contains("\"stop\": \"NUME_DDL\", \"count\": 2, \"cases\": [\"b\", \"d\"]"), "{js}");
        assert!(
            js.contains("{\"name\": \"a\", \"diagnostic\": \"OK\", \"ok\": 0, \"nook\": 0, \"seconds\": 0.500}"),
            "{js}"
        );
        assert_eq!(json_str("a\"b\\\n"), "\"a\\\"b\\\\\\n\"");
        assert_eq!(csv_field("x, \"y\""), "\"x, \"\"y\"\"\"");
    }
}
