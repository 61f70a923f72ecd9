//! A bounded mutation fuzzer of the whole pipeline: the real command files of ../shared/astest and
//! comm/, with one or two keyword values replaced by a value of another kind or size (0, negative,
//! nan, inf, huge, empty list or tuple, a string, another concept of the file) or a keyword
//! occurrence deleted, run through `aster check` and `aster run` in-process with their own meshes and
//! units, outputs in a temporary folder and a short time limit.
//!
//! Every mutant must end in a verdict (OK, NOOK_TEST_RESU, NO_TEST_RESU) or a located `<F>`
//! (`file:line:col: ...`): a caught panic (an `internal error`), an unlocated error or a run that
//! does not return fails the test, printing the mutant and the seed. Time budget: FUZZ_SECONDS
//! (default 8 s); the seed is fixed, so a run is reproducible (FUZZ_SEED overrides it). Cases whose
//! unmutated run takes more than 2 s are left out. Before each run the mutant is written to
//! target/tmp/fuzz-pipeline-last-mutant.comm, so that one that aborts the process (a stack overflow,
//! an allocation failure) can be replayed; FUZZ_VERBOSE=1 prints every mutant and its outcome.

use aster::diag::ErrorKind;
use aster::runner::export::{Dir, Export};
use aster::runner::{self, Case, Outcome, RunOptions};
use aster::syntax::ast::{Arg, Expr, ExprKind, FPart, Module, Param, Span, Stmt, StmtKind};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::common::Rng;

/// What a keyword's value becomes.
const VALUES: &[&str] = &[
    "0",
    "0.0",
    "-1",
    "-2.5e3",
    "float('nan')",
    "float('inf')",
    "-float('inf')",
    "1e308",
    "-1e308",
    "1e-308",
    "10**30",
    "2**62",
    "()",
    "[]",
    "(_F(),)",
    "'FOO'",
    "''",
    "None",
    "(1.0, 2.0, 3.0)",
];

/// Numbers in place of a number: zero, negative, not finite, huge, tiny.
const NUMBERS: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "-1",
    "-1.0e3",
    "float('nan')",
    "float('inf')",
    "-float('inf')",
    "1e308",
    "1e-308",
    "10**30",
    "2**62",
    "7",
];

/// Strings in place of a string (besides the other strings of the file).
const STRINGS: &[&str] = &["''", "'FOO'", "' '", "'OUI'", "'NON'", "'TOUT'"];

/// A keyword occurrence of a command call (possibly inside a `_F`).
struct Site {
    /// `COMMAND/FACTOR/KEYWORD`.
    path: String,
    /// `KEYWORD=VALUE`.
    whole: Span,
    value: Span,
    /// The number and string literals of the value (elements of a list included).
    literals: Vec<(Span, bool)>,
    /// The value is a tuple or list display: its element spans.
    items: Vec<Span>,
    /// A keyword occurrence (which can be deleted), not a variable (`E = 2.1e11`).
    keyword: bool,
}

/// The number (`false`) and string (`true`) literals of `e`, outside nested calls.
fn literals(e: &Expr, out: &mut Vec<(Span, bool)>) {
    match &e.kind {
        ExprKind::Int(_) | ExprKind::Float(_) => out.push((e.span, false)),
        ExprKind::Unary(_, a) if matches!(a.kind, ExprKind::Int(_) | ExprKind::Float(_)) => out.push((e.span, false)),
        ExprKind::Str(_) => out.push((e.span, true)),
        ExprKind::Tuple(xs) | ExprKind::List(xs) => xs.iter().for_each(|x| literals(x, out)),
        _ => {}
    }
}

/// A case of the corpus: its command file, its units and how long its unmutated run takes.
struct Case0 {
    name: String,
    comm_name: String,
    src: String,
    units: Vec<(i64, PathBuf, Dir)>,
    sites: Vec<Site>,
    concepts: Vec<String>,
    /// The string and number literals of the file, as written.
    strings: Vec<String>,
    numbers: Vec<String>,
    baseline: Duration,
    /// The unmutated case runs to its end (it does not stop on something unsupported).
    runs: bool,
}

fn walk_stmts(stmts: &[Stmt], sites: &mut Vec<Site>, concepts: &mut Vec<String>) {
    for s in stmts {
        match &s.kind {
            StmtKind::Expr(e) | StmtKind::Return(Some(e)) | StmtKind::Raise(Some(e)) => walk(e, None, sites),
            StmtKind::Assign { targets, value } => {
                if let (ExprKind::Call(f, _), [Expr { kind: ExprKind::Name(n), .. }]) =
                    (&value.kind, targets.as_slice())
                {
                    if matches!(&f.kind, ExprKind::Name(c) if is_command(c)) {
                        concepts.push(n.clone());
                    }
                }
                // A variable set to numbers or strings (`E = 2.1e11`, `LX, LY = 2.0, 1.0`) feeds keywords.
                let mut lits = Vec::new();
                literals(value, &mut lits);
                if !lits.is_empty() {
                    let items = match &value.kind {
                        ExprKind::Tuple(xs) | ExprKind::List(xs) => xs.iter().map(|x| x.span).collect(),
                        _ => Vec::new(),
                    };
                    let path = assigned_names(targets);
                    sites.push(Site {
                        path,
                        whole: value.span,
                        value: value.span,
                        literals: lits,
                        items,
                        keyword: false,
                    });
                }
                targets.iter().for_each(|t| walk(t, None, sites));
                walk(value, None, sites);
            }
            StmtKind::AugAssign { target, value, .. } => {
                walk(target, None, sites);
                walk(value, None, sites);
            }
            StmtKind::If { branches, orelse } => {
                for (c, b) in branches {
                    walk(c, None, sites);
                    walk_stmts(b, sites, concepts);
                }
                walk_stmts(orelse, sites, concepts);
            }
            StmtKind::For { target, iter, body, orelse } => {
                walk(target, None, sites);
                walk(iter, None, sites);
                walk_stmts(body, sites, concepts);
                walk_stmts(orelse, sites, concepts);
            }
            StmtKind::While { cond, body, orelse } => {
                walk(cond, None, sites);
                walk_stmts(body, sites, concepts);
                walk_stmts(orelse, sites, concepts);
            }
            StmtKind::Def(d) => {
                for p in &d.params {
                    if let Param::Plain(_, Some(e)) = p {
                        walk(e, None, sites);
                    }
                }
                walk_stmts(&d.body, sites, concepts);
            }
            StmtKind::Del(es) => es.iter().for_each(|e| walk(e, None, sites)),
            StmtKind::Assert(a, b) => {
                walk(a, None, sites);
                if let Some(b) = b {
                    walk(b, None, sites);
                }
            }
            _ => {}
        }
    }
}

/// The names a statement assigns (`LX, LY`).
fn assigned_names(targets: &[Expr]) -> String {
    fn names(e: &Expr, out: &mut Vec<String>) {
        match &e.kind {
            ExprKind::Name(n) => out.push(n.clone()),
            ExprKind::Tuple(xs) | ExprKind::List(xs) => xs.iter().for_each(|x| names(x, out)),
            _ => out.push("...".into()),
        }
    }
    let mut out = Vec::new();
    targets.iter().for_each(|t| names(t, &mut out));
    out.join(", ")
}

fn is_command(n: &str) -> bool {
    n.len() > 2 && n.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') && n != "_F"
}

/// Collect the keyword sites of the command calls in `e`; `within` is the path of the enclosing
/// command call or factor keyword.
fn walk(e: &Expr, within: Option<&str>, sites: &mut Vec<Site>) {
    let w = |x: &Expr, sites: &mut Vec<Site>| walk(x, within, sites);
    match &e.kind {
        ExprKind::Call(f, args) => {
            let callee = match &f.kind {
                ExprKind::Name(n) => Some(n.as_str()),
                _ => None,
            };
            let here: Option<String> = match (callee, within) {
                (Some(n), _) if is_command(n) => Some(n.to_string()),
                (Some("_F"), Some(p)) => Some(p.to_string()),
                _ => None,
            };
            walk(f, within, sites);
            for a in args {
                match a {
                    Arg::Keyword(name, v, ksp) => {
                        if let Some(h) = &here {
                            let mut lits = Vec::new();
                            literals(v, &mut lits);
                            let items = match &v.kind {
                                ExprKind::Tuple(xs) | ExprKind::List(xs) => xs.iter().map(|x| x.span).collect(),
                                _ => Vec::new(),
                            };
                            sites.push(Site {
                                path: format!("{h}/{name}"),
                                whole: *ksp,
                                value: v.span,
                                literals: lits,
                                items,
                                keyword: true,
                            });
                            walk(v, Some(&format!("{h}/{name}")), sites);
                        } else {
                            walk(v, within, sites);
                        }
                    }
                    Arg::Positional(v) | Arg::Star(v) | Arg::DoubleStar(v) => walk(v, within, sites),
                }
            }
        }
        ExprKind::Tuple(xs) | ExprKind::List(xs) => xs.iter().for_each(|x| w(x, sites)),
        ExprKind::Dict(kv) => kv.iter().for_each(|(k, v)| {
            w(k, sites);
            w(v, sites)
        }),
        ExprKind::ListComp(a, cs) | ExprKind::GenExp(a, cs) => {
            w(a, sites);
            for c in cs {
                w(&c.iter, sites);
                c.conds.iter().for_each(|x| w(x, sites));
            }
        }
        ExprKind::DictComp(a, b, cs) => {
            w(a, sites);
            w(b, sites);
            for c in cs {
                w(&c.iter, sites);
            }
        }
        ExprKind::BinOp(a, _, b) | ExprKind::And(a, b) | ExprKind::Or(a, b) | ExprKind::Subscript(a, b) => {
            w(a, sites);
            w(b, sites)
        }
        ExprKind::Unary(_, a) | ExprKind::Attr(a, _) => w(a, sites),
        ExprKind::Compare(a, rest) => {
            w(a, sites);
            rest.iter().for_each(|(_, x)| w(x, sites));
        }
        ExprKind::IfExp { cond, then, orelse } => {
            w(cond, sites);
            w(then, sites);
            w(orelse, sites)
        }
        ExprKind::FString(parts) => {
            for p in parts {
                if let FPart::Field { expr, .. } = p {
                    w(expr, sites);
                }
            }
        }
        _ => {}
    }
}

fn corpus_dirs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let shared = root.join("../shared/astest");
    let mut dirs = Vec::new();
    if shared.is_dir() {
        dirs.push(shared);
    } else {
        eprintln!("SKIPPED: {} is absent; fuzzing comm/ only", shared.display());
    }
    dirs.push(root.join("comm"));
    dirs
}

/// A scratch folder for one run.
fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-fuzz-pipeline-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// How one mutant ended.
struct Ran {
    check: Result<usize, (String, ErrorKind)>,
    run: Outcome,
}

/// Run `src` as `comm_name` through `aster check` and `aster run` on a thread of its own (8 MiB of
/// stack, as the command line's main thread has), within `limit`.
fn check_and_run(comm_name: &str, src: &str, case_units: &[(i64, PathBuf, Dir)], limit: Duration, tag: &str) -> Ran {
    let dir = scratch(tag);
    let comm = dir.join(comm_name);
    std::fs::write(&comm, src).unwrap();
    // Units the run writes go to this run's folder: nothing is ever written beside the corpus.
    let units: Vec<(i64, PathBuf, Dir)> = case_units
        .iter()
        .map(|(u, p, d)| {
            let local = dir.join(p.file_name().unwrap_or_default());
            match d {
                Dir::In => (*u, p.clone(), *d),
                Dir::Out => (*u, local, *d),
                Dir::InOut => {
                    let _ = std::fs::copy(p, &local);
                    (*u, local, *d)
                }
            }
        })
        .collect();
    let opts = RunOptions { out_dir: Some(dir.clone()), units, echo: false };
    let (tx, rx) = mpsc::channel();
    let worker = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let check = runner::check_file(&comm);
            let run = runner::run(Case::Comm(&comm), &opts, Some(limit));
            let _ = tx.send(Ran { check, run });
        })
        .unwrap();
    // The runner stops itself at `limit`; a run that has not returned well after it hangs.
    let r = rx.recv_timeout(limit * 2 + Duration::from_secs(10));
    let _ = std::fs::remove_dir_all(&dir);
    match r {
        Ok(ran) => {
            let _ = worker.join();
            ran
        }
        Err(_) => {
            // Written to the process's stderr itself: the test harness captures `eprintln!`, and what it
            // captured is lost when the process exits here.
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "fuzz-pipeline: {comm_name}: the run did not return within {:?}: a hang (see \
                 target/tmp/fuzz-pipeline-last-mutant.comm)",
                limit * 2
            );
            std::process::exit(101);
        }
    }
}

/// Load the corpus: every .export with exactly one command file that parses, with its unmutated time.
fn corpus() -> Vec<Case0> {
    let mut out = Vec::new();
    for dir in corpus_dirs() {
        let mut exports: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "export"))
            .collect();
        exports.sort();
        for e in exports {
            let Ok(ex) = Export::read(&e) else { continue };
            let comms = ex.comm_files();
            let [comm] = comms.as_slice() else { continue };
            let Ok(bytes) = std::fs::read(&comm.path) else { continue };
            let src = String::from_utf8_lossy(&bytes).into_owned();
            let Ok(module): Result<Module, _> = aster::syntax::parse_module(&src) else { continue };
            let (mut sites, mut concepts) = (Vec::new(), Vec::new());
            walk_stmts(&module.body, &mut sites, &mut concepts);
            let name = e.file_stem().unwrap().to_string_lossy().into_owned();
            let comm_name = comm.path.file_name().unwrap().to_string_lossy().into_owned();
            let units: Vec<(i64, PathBuf, Dir)> = ex
                .files
                .iter()
                .filter(|f| f.kind != "comm" && f.kind != "mess")
                .map(|f| (f.unit, f.path.clone(), f.dir))
                .collect();
            let t0 = Instant::now();
            let base = check_and_run(&comm_name, &src, &units, Duration::from_secs(20), &format!("base-{name}"));
            let baseline = t0.elapsed();
            // A case slower than the fuzzing budget per run is left out below anyway; on a loaded machine
            // it may reach the base run's own limit, which is no fault of the pipeline.
            if base.run.error_kind == Some(ErrorKind::TimeLimit) {
                eprintln!("fuzz-pipeline: {name} left out (its run reached the time limit: {baseline:.2?})");
                continue;
            }
            if let Some(problem) = problem(&comm_name, &base) {
                panic!("the unmutated case {name} fails the fuzzer's contract: {problem}");
            }
            if baseline > Duration::from_secs(2) {
                eprintln!("fuzz-pipeline: {name} left out (its run takes {baseline:.2?})");
                continue;
            }
            let lit = |want: bool| -> Vec<String> {
                let mut v: Vec<String> = sites
                    .iter()
                    .flat_map(|s| {
                        s.literals.iter().filter(|l| l.1 == want).map(|l| src[l.0.start..l.0.end].to_string())
                    })
                    .collect();
                v.sort();
                v.dedup();
                if v.is_empty() {
                    v.push(if want { "'X'".into() } else { "1".into() });
                }
                v
            };
            let (strings, numbers) = (lit(true), lit(false));
            let runs = !base.run.diagnostic.is_error();
            out.push(Case0 { name, comm_name, src, units, sites, concepts, strings, numbers, baseline, runs });
        }
    }
    out
}

/// Why an outcome breaks the contract (a verdict or a located `<F>`), if it does.
fn problem(comm_name: &str, r: &Ran) -> Option<String> {
    let located = |msg: &str| {
        msg.strip_prefix(comm_name).and_then(|m| m.strip_prefix(':')).and_then(|m| m.split_once(':')).is_some_and(
            |(l, rest)| {
                l.parse::<usize>().is_ok() && rest.split(':').next().is_some_and(|c| c.parse::<usize>().is_ok())
            },
        )
    };
    if let Err((msg, kind)) = &r.check {
        if *kind == ErrorKind::Internal {
            return Some(format!("aster check: {msg}"));
        }
        if !located(msg) {
            return Some(format!("aster check: unlocated error: {msg}"));
        }
    }
    let o = &r.run;
    if o.error_kind == Some(ErrorKind::Internal) {
        return Some(format!("aster run: {}", o.error.as_deref().unwrap_or("")));
    }
    match (&o.error, o.diagnostic.is_error()) {
        (Some(e), true) if !located(e) => Some(format!("aster run: unlocated error: {e}")),
        (Some(_), true) | (None, false) => None,
        _ => Some(format!("aster run: diagnostic {} with error {:?}", o.diagnostic, o.error)),
    }
}

/// Replace or delete one or two keyword occurrences of `case`; returns the text and what was done.
fn mutate(rng: &mut Rng, case: &Case0) -> (String, Vec<String>) {
    let n = 1 + (rng.below(4) == 0) as usize;
    // The checking commands (TEST_RESU, TEST_TABLE, ...) hold most keywords of a test case but
    // little of its computation: draw again, twice out of three times, when one comes up.
    let mut pick = || {
        let i = rng.below(case.sites.len());
        if case.sites[i].path.starts_with("TEST_") && rng.below(3) != 0 {
            rng.below(case.sites.len())
        } else {
            i
        }
    };
    let mut picks: Vec<usize> = (0..n).map(|_| pick()).collect();
    picks.sort();
    picks.dedup();
    // Sites may nest (a factor keyword and a keyword inside it): keep the outer of overlapping ones.
    let mut chosen: Vec<&Site> = Vec::new();
    for &i in &picks {
        let s = &case.sites[i];
        if chosen.iter().all(|c| s.whole.start >= c.whole.end || s.whole.end <= c.whole.start) {
            chosen.push(s);
        }
    }
    chosen.sort_by_key(|s| std::cmp::Reverse(s.whole.start));
    let mut text = case.src.clone();
    let mut what = Vec::new();
    let line = |at: usize| case.src[..at].matches('\n').count() + 1;
    for s in chosen {
        let old = &case.src[s.value.start..s.value.end];
        let at = format!("line {}: {}", line(s.whole.start), s.path);
        let replace = |text: &mut String, span: Span, by: &str, what: &mut Vec<String>| {
            what.push(format!("{at} = {} -> {}", short(&case.src[span.start..span.end]), short(by)));
            text.replace_range(span.start..span.end, by);
        };
        match rng.below(20) {
            // A literal of the value (an element of a list included) by one of its own kind: the
            // mutants the catalogue lets through to the stages.
            0..=8 if !s.literals.is_empty() => {
                let (span, is_str) = s.literals[rng.below(s.literals.len())];
                let by = if is_str {
                    match rng.below(3) {
                        0 => STRINGS[rng.below(STRINGS.len())].to_string(),
                        _ => case.strings[rng.below(case.strings.len())].clone(),
                    }
                } else {
                    match rng.below(3) {
                        0 => case.numbers[rng.below(case.numbers.len())].clone(),
                        _ => NUMBERS[rng.below(NUMBERS.len())].to_string(),
                    }
                };
                replace(&mut text, span, &by, &mut what);
            }
            // A list of another length: empty, shortened, one element repeated.
            9..=10 if !s.items.is_empty() => {
                let by = match rng.below(3) {
                    0 => "()".to_string(),
                    1 => format!("({},)", case.src[s.items[0].start..s.items[0].end].trim()),
                    _ => {
                        let kept = &s.items[..s.items.len() - 1];
                        format!("({})", kept.iter().map(|i| &case.src[i.start..i.end]).collect::<Vec<_>>().join(", "))
                    }
                };
                replace(&mut text, s.value, &by, &mut what);
            }
            // A value of another kind.
            0..=13 => replace(&mut text, s.value, VALUES[rng.below(VALUES.len())], &mut what),
            // Another concept of the file.
            14..=16 if !case.concepts.is_empty() => {
                let c = case.concepts[rng.below(case.concepts.len())].clone();
                replace(&mut text, s.value, &c, &mut what);
            }
            _ if !s.keyword => replace(&mut text, s.value, NUMBERS[rng.below(NUMBERS.len())], &mut what),
            _ => {
                // Delete `KEYWORD=VALUE` and the comma after it (or before it, for the last one).
                let after = &case.src[s.whole.end..];
                let skip = after.len() - after.trim_start().len();
                let (a, b) = if after[skip..].starts_with(',') {
                    (s.whole.start, s.whole.end + skip + 1)
                } else {
                    let before = case.src[..s.whole.start].trim_end();
                    match before.strip_suffix(',') {
                        Some(b) => (b.len(), s.whole.end),
                        None => (s.whole.start, s.whole.end),
                    }
                };
                text.replace_range(a..b, "");
                what.push(format!("{at} = {} deleted", short(old)));
            }
        }
    }
    (text, what)
}

fn short(s: &str) -> String {
    let one: String = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if one.chars().count() > 40 {
        format!("{}...", one.chars().take(40).collect::<String>())
    } else {
        one
    }
}

#[test]
fn every_mutant_ends_in_a_verdict_or_a_located_error() {
    let budget =
        Duration::from_secs_f64(std::env::var("FUZZ_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(8.0));
    let seed = std::env::var("FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(0xA57E_F022_u64);
    let last = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-pipeline-last-mutant.comm");
    let start = Instant::now();
    let corpus = corpus();
    let loaded = start.elapsed();
    assert!(!corpus.is_empty(), "no case to fuzz");
    let verbose = std::env::var_os("FUZZ_VERBOSE").is_some();
    let mut rng = Rng(seed);
    let mut outcomes: BTreeMap<String, usize> = BTreeMap::new();
    let mut failures = Vec::new();
    let (mut cases, mut slowest) = (0usize, (Duration::ZERO, String::new()));
    let fuzz_start = Instant::now();
    while fuzz_start.elapsed() < budget {
        let case = &corpus[rng.below(corpus.len())];
        // A case that stops on something unsupported runs its mutants only that far: draw again,
        // twice out of three times.
        if case.sites.is_empty() || (!case.runs && rng.below(3) != 0) {
            continue;
        }
        let (text, what) = mutate(&mut rng, case);
        let label = format!("{} (seed {seed}, case {cases}): {}", case.name, what.join("; "));
        std::fs::write(&last, format!("# {label}\n{text}")).unwrap();
        let limit = (case.baseline * 4).max(Duration::from_secs(2));
        let t0 = Instant::now();
        let r = check_and_run(&case.comm_name, &text, &case.units, limit, &format!("m{cases}"));
        let dt = t0.elapsed();
        if dt > slowest.0 {
            slowest = (dt, label.clone());
        }
        let key = match r.run.error_kind {
            Some(ErrorKind::TimeLimit) => "<F> time limit".to_string(),
            _ => r.run.diagnostic.to_string(),
        };
        if verbose {
            println!("{label}\n    {key} {:.3?} {}", dt, r.run.error.as_deref().unwrap_or(""));
        }
        *outcomes.entry(key).or_default() += 1;
        if let Some(p) = problem(&case.comm_name, &r) {
            failures.push(format!("{label}\n    {p}"));
            eprintln!("FAILURE {label}\n    {p}");
        }
        cases += 1;
    }
    let _ = std::fs::remove_file(&last);
    let by: Vec<String> = outcomes.iter().map(|(k, n)| format!("{k}: {n}")).collect();
    println!(
        "fuzz-pipeline: {} command files (loaded and run unmutated in {loaded:.2?}), {cases} mutants in {:.2?}, seed {seed}",
        corpus.len(),
        fuzz_start.elapsed()
    );
    println!("fuzz-pipeline: outcomes: {}", by.join(", "));
    println!("fuzz-pipeline: slowest {:.3?}: {}", slowest.0, slowest.1);
    assert!(failures.is_empty(), "{} of {cases} mutants broke the contract:\n{}", failures.len(), failures.join("\n"));
    assert!(cases >= 10, "the fuzzer ran too few mutants ({cases})");
}
