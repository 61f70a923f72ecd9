//! Running cases: a command file with its units, as `aster run`, `aster
//! check` and `aster suite` do, with Code_Aster's diagnostics.

pub mod diagnostic;
pub mod export;
pub mod guard;
pub mod session;
pub mod stops;
pub mod suite;
mod units;

use crate::diag::{with_deadline, Deadline, Error, ErrorKind};
use crate::interp::Interp;
use crate::stages::CheckRecord;
use crate::syntax::ast::Span;
pub use diagnostic::Diagnostic;
use export::{Dir, Export};
use session::{decode, write_atomic, Mode, Session, Timing, WorkDir};
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::{Duration, Instant};

/// Options of `aster run`.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Where the .mess and .resu files go (default: the current folder).
    pub out_dir: Option<PathBuf>,
    /// Extra or overriding units: (unit, path, direction).
    pub units: Vec<(i64, PathBuf, Dir)>,
    /// Echo the message file to stdout while running.
    pub echo: bool,
}

/// The result of a run.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub name: String,
    pub diagnostic: Diagnostic,
    pub records: Vec<CheckRecord>,
    /// The located error message, if the run stopped on one.
    pub error: Option<String>,
    /// The kind of that error (`Internal` for a caught panic).
    pub error_kind: Option<ErrorKind>,
    /// The command it arose in and its message without the location.
    pub error_command: Option<String>,
    pub error_message: Option<String>,
    pub mess: Option<PathBuf>,
    pub seconds: f64,
    pub timings: Vec<Timing>,
}

impl Outcome {
    pub fn ok_count(&self) -> usize {
        self.records.iter().filter(|r| r.ok == Some(true)).count()
    }
    pub fn nook_count(&self) -> usize {
        self.records.iter().filter(|r| r.ok == Some(false)).count()
    }
    pub fn skip_count(&self) -> usize {
        self.records.iter().filter(|r| r.ok.is_none()).count()
    }
    /// The process exit code: 0 for OK (and for a run without checks).
    pub fn exit_code(&self) -> i32 {
        self.diagnostic.exit_code()
    }
    fn failed(name: &str, kind: ErrorKind, error: String) -> Outcome {
        Outcome {
            name: name.into(),
            diagnostic: Diagnostic::of_error(kind),
            records: Vec::new(),
            error_message: Some(error.clone()),
            error: Some(error),
            error_kind: Some(kind),
            error_command: None,
            mess: None,
            seconds: 0.0,
            timings: Vec::new(),
        }
    }
}

fn stem(p: &Path) -> String {
    p.file_stem().and_then(|s| s.to_str()).unwrap_or("case").to_string()
}

/// What `aster run` runs.
#[derive(Debug, Clone, Copy)]
pub enum Case<'a> {
    /// The embedded demo scene ([`run_default`]).
    Demo,
    /// A case described by an .export file ([`run_export`]).
    Export(&'a Path),
    /// A command file with the units of [`RunOptions`] ([`run_comm`]).
    Comm(&'a Path),
}

/// Run a case within a time limit: `time_limit`, else the .export's `P time_limit`, else none. Past
/// it, the run stops with a located `<F> ... time limit of N s exceeded`.
pub fn run(case: Case<'_>, opts: &RunOptions, time_limit: Option<Duration>) -> Outcome {
    let start = Instant::now();
    let within =
        |limit: Option<Duration>, f: &dyn Fn() -> Outcome| with_deadline(limit.map(|l| Deadline::since(start, l)), f);
    match case {
        Case::Demo => within(time_limit, &|| run_default(opts)),
        Case::Comm(p) => within(time_limit, &|| run_comm(p, opts)),
        Case::Export(p) => {
            let limit = match time_limit {
                Some(l) => Some(l),
                None => match Export::read(p).and_then(|e| e.time_limit()) {
                    Ok(l) => l,
                    Err(e) => return Outcome::failed(&stem(p), e.kind, e.msg),
                },
            };
            within(limit, &|| run_export(p, opts))
        }
    }
}

/// Run the case described by an .export file (with no time limit: see [`run`]).
pub fn run_export(path: &Path, opts: &RunOptions) -> Outcome {
    let name = stem(path);
    let ex = match Export::read(path) {
        Ok(e) => e,
        Err(e) => return Outcome::failed(&name, e.kind, e.msg),
    };
    // A data file the .export names must exist: say which line names it.
    if let Some(f) = ex.files.iter().find(|f| f.dir != Dir::Out && !f.path.exists()) {
        let what = if f.kind == "comm" { "command file" } else { "data file" };
        return Outcome::failed(
            &name,
            ErrorKind::Io,
            format!("unit {}: {what} {} does not exist (named by {})", f.unit, f.path.display(), f.origin),
        );
    }
    // Several command files (`.comm`, `.com1`, `.com2`, ...) are a study continued with POURSUITE:
    // they run in the .export's order, one after the other, in one interpreter.
    let comms: Vec<PathBuf> = ex.comm_files().iter().map(|f| f.path.clone()).collect();
    if comms.is_empty() {
        return Outcome::failed(&name, ErrorKind::Io, format!("{}: no 'F comm FILE D 1' line", path.display()));
    }
    let mut units: Vec<(i64, PathBuf, Dir)> =
        ex.files.iter().filter(|f| f.kind != "comm").map(|f| (f.unit, f.path.clone(), f.dir)).collect();
    units.extend(opts.units.iter().cloned());
    let mess = ex.files.iter().find(|f| f.kind == "mess").map(|f| f.path.clone());
    run_files(&comms, &name, units, mess, ex.is_validation(), opts)
}

/// Run a command file with units given on the command line.
pub fn run_comm(path: &Path, opts: &RunOptions) -> Outcome {
    run_files(&[path.to_path_buf()], &stem(path), opts.units.clone(), None, false, opts)
}

/// The name and text of each command file.
fn read_sources(comms: &[PathBuf]) -> std::result::Result<Vec<(String, String)>, String> {
    comms
        .iter()
        .map(|comm| {
            let bytes = std::fs::read(comm).map_err(|e| format!("{}: {e}", comm.display()))?;
            let file = comm.file_name().and_then(|f| f.to_str()).unwrap_or("?").to_string();
            Ok((file, decode(&bytes)))
        })
        .collect()
}

fn run_files(
    comms: &[PathBuf],
    name: &str,
    units: Vec<(i64, PathBuf, Dir)>,
    mess_path: Option<PathBuf>,
    validation: bool,
    opts: &RunOptions,
) -> Outcome {
    match read_sources(comms) {
        Ok(sources) => run_text(&sources, name, units, mess_path, validation, opts),
        Err(e) => Outcome::failed(name, ErrorKind::Io, e),
    }
}

/// The scene `aster run` runs when given no case (comm/hardening_curve.comm).
pub const DEFAULT_SCENE: (&str, &str) = ("junction_2d.comm", include_str!("../../comm/junction_2d.comm"));

/// The mesh of the default scene (unit 20), made by `aster mesh box`.
pub const DEFAULT_MESH: (&str, &[u8]) = ("junction_quad8.med", include_bytes!("../../med/junction_quad8.med"));

/// Run the embedded default scene: the WTNV149-like 2D block with two
/// cohesive X-FEM interfaces meeting at a junction. Its mesh is written to a
/// temporary file given as unit 20, its MED result goes to unit 80.
pub fn run_default(opts: &RunOptions) -> Outcome {
    let (file, src) = DEFAULT_SCENE;
    let name = file.trim_end_matches(".comm");
    let dir = std::env::temp_dir().join(format!("aster-rs-default-{}", std::process::id()));
    let mesh = dir.join(DEFAULT_MESH.0);
    if let Err(e) = std::fs::create_dir_all(&dir).and_then(|_| std::fs::write(&mesh, DEFAULT_MESH.1)) {
        return Outcome::failed(name, ErrorKind::Io, format!("cannot write the default mesh {}: {e}", mesh.display()));
    }
    let mut units = opts.units.clone();
    if !units.iter().any(|(u, ..)| *u == 20) {
        units.push((20, mesh, Dir::In));
    }
    if !units.iter().any(|(u, ..)| *u == 80) {
        let out = opts.out_dir.clone().unwrap_or_else(|| PathBuf::from("."));
        units.push((80, out.join(format!("{name}.rmed")), Dir::Out));
    }
    let o = run_text(&[(file.to_string(), src.to_string())], name, units, None, false, opts);
    let _ = std::fs::remove_dir_all(&dir);
    o
}

/// Run command files one after the other in one interpreter: the first starts the study (DEBUT),
/// the others continue it (POURSUITE) with every name the earlier ones bound; FIN ends each file.
fn run_text(
    sources: &[(String, String)],
    name: &str,
    units: Vec<(i64, PathBuf, Dir)>,
    mess_path: Option<PathBuf>,
    validation: bool,
    opts: &RunOptions,
) -> Outcome {
    let t0 = Instant::now();
    let out_dir = opts.out_dir.clone().unwrap_or_else(|| PathBuf::from("."));
    let mess_path = mess_path.unwrap_or_else(|| out_dir.join(format!("{name}.mess")));
    let resu_path = mess_path.with_extension("resu");
    // Input units must exist before anything runs.
    for (u, p, d) in &units {
        if *d != Dir::Out && !p.exists() {
            return Outcome::failed(name, ErrorKind::Io, format!("unit {u}: data file {} does not exist", p.display()));
        }
    }
    let work = match WorkDir::new() {
        Ok(w) => w,
        Err(e) => return Outcome::failed(name, e.kind, e.msg),
    };
    let globals = Rc::new(RefCell::new(HashMap::new()));
    let (first_file, first_src) = sources.first().cloned().unwrap_or_default();
    // The runner's context (Code_Aster's predefined names), from what any of the command files imports.
    let all: Vec<&str> = sources.iter().map(|(_, s)| s.as_str()).collect();
    crate::interp::predefine(&globals, &all.join("\n"));
    let mut session = Session::new(Mode::Run, &first_file, &first_src, globals.clone(), work.0.clone());
    session.units = units.into_iter().map(|(u, p, d)| (u, (p, d))).collect();
    session.echo = opts.echo;
    session.validation = validation;

    let mut result = Ok(());
    let (mut file, mut src) = (first_file, first_src);
    for (k, (f, s)) in sources.iter().enumerate() {
        (file, src) = (f.clone(), s.clone());
        if k > 0 {
            session.continue_with(&file, &src);
        }
        let at = Rc::new(Cell::new(Span::default()));
        result = guard::catch(|| {
            crate::syntax::parse_module(&src)
                .map_err(|e| {
                    let mut err = Error::new(ErrorKind::Syntax, e.message);
                    err.span = Some(Span { start: e.offset, end: e.offset });
                    err
                })
                .and_then(|module| {
                    let mut it = Interp::new(globals.clone(), Some(&mut session));
                    it.track(at.clone());
                    it.run(&module)
                })
        })
        .unwrap_or_else(|panic| Err(Error::internal(&panic).at(at.get())));
        if result.is_err() {
            break;
        }
    }
    let (diagnostic, error) = match &result {
        Err(e) => {
            let located = e.located(&file, &src);
            session.mess.push_str(&format!("\n <F> {located}\n"));
            if opts.echo {
                println!("\n <F> {located}");
            }
            (Diagnostic::of_error(e.kind), Some(located))
        }
        Ok(()) => {
            let d = if session.records.iter().any(|r| r.ok == Some(false)) {
                Diagnostic::NookTestResu
            } else if session.records.iter().any(|r| r.ok == Some(true)) {
                Diagnostic::Ok
            } else {
                Diagnostic::NoTestResu
            };
            (d, None)
        }
    };
    // Results are delivered only from runs that did not stop on an error.
    if error.is_none() {
        for (from, to) in session.deliverables() {
            // A unit may name a folder that does not exist yet (the demo's ./aster-out): make it.
            if let Some(parent) = to.parent().filter(|p| !p.as_os_str().is_empty()) {
                let _ = std::fs::create_dir_all(parent);
            }
            if let Err(e) =
                std::fs::read(&from).map_err(|e| e.to_string()).and_then(|b| write_atomic(&to, &b).map_err(|e| e.msg))
            {
                session.mess.push_str(&format!(" <A> result {} not delivered: {e}\n", to.display()));
            }
        }
    }
    let alarms = alarm_count(&session.mess);
    let summary = format!(
        "{alarms}\n checks: {} OK, {} NOOK, {} skipped    elapsed {:.3} s\n DIAGNOSTIC JOB : {diagnostic}\n",
        session.records.iter().filter(|r| r.ok == Some(true)).count(),
        session.records.iter().filter(|r| r.ok == Some(false)).count(),
        session.records.iter().filter(|r| r.ok.is_none()).count(),
        t0.elapsed().as_secs_f64()
    );
    session.mess.push_str(&summary);
    if opts.echo {
        print!("{summary}");
    }
    let mut written = None;
    if std::fs::create_dir_all(&out_dir).is_ok() && write_atomic(&mess_path, session.mess.as_bytes()).is_ok() {
        written = Some(mess_path.clone());
        if !session.resu.is_empty() {
            let _ = write_atomic(&resu_path, session.resu.as_bytes());
        }
    }
    Outcome {
        name: name.to_string(),
        diagnostic,
        records: session.records.clone(),
        error,
        error_kind: result.as_ref().err().map(|e| e.kind),
        error_command: result.as_ref().err().and_then(|e| e.command.clone()),
        error_message: result.as_ref().err().map(|e| e.msg.clone()),
        mess: written,
        seconds: t0.elapsed().as_secs_f64(),
        timings: session.timings.clone(),
    }
}

/// The end-of-run count of the alarms (`<A>` lines) of a message file, by Code_Aster identifier where
/// the alarm names one (`<A> <MODELE1_3> ...`); empty without alarm.
pub fn alarm_count(mess: &str) -> String {
    let mut total = 0;
    let mut by_id: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
    for line in mess.lines() {
        let Some(rest) = line.trim_start().strip_prefix("<A>") else { continue };
        total += 1;
        let id = rest.trim_start().strip_prefix('<').and_then(|r| r.split_once('>')).map(|(id, _)| id);
        *by_id.entry(id.unwrap_or("")).or_default() += 1;
    }
    if total == 0 {
        return String::new();
    }
    let parts: Vec<String> = by_id
        .iter()
        .map(|(id, n)| if id.is_empty() { format!("{n} of aster-rs") } else { format!("{id} x{n}") })
        .collect();
    format!("\n <A> {total} alarm(s) in this run: {}\n", parts.join(", "))
}

/// `aster check`: parse and validate every command call, computing nothing but the pure definitions
/// (functions, constants, lists) whose values the file's Python may use.
/// Returns the number of commands checked, or the located error.
pub fn check_file(path: &Path) -> Result<usize, (String, ErrorKind)> {
    let bytes = std::fs::read(path).map_err(|e| (format!("{}: {e}", path.display()), ErrorKind::Io))?;
    let src = decode(&bytes);
    let file = path.file_name().and_then(|f| f.to_str()).unwrap_or("?").to_string();
    let module = guard::catch(|| crate::syntax::parse_module(&src))
        .map_err(|panic| (Error::internal(&panic).located(&file, &src), ErrorKind::Internal))?
        .map_err(|e| {
            let (l, c) = crate::syntax::lexer::line_col(&src, e.offset);
            (format!("{file}:{l}:{c}: {}", e.message), ErrorKind::Syntax)
        })?;
    let globals = Rc::new(RefCell::new(HashMap::new()));
    crate::interp::predefine(&globals, &src);
    let work = std::env::temp_dir();
    let mut session = Session::new(Mode::Check, &file, &src, globals.clone(), work);
    let at = Rc::new(Cell::new(Span::default()));
    let r = guard::catch(|| {
        let mut it = Interp::new(globals, Some(&mut session));
        it.track(at.clone());
        it.run(&module)
    })
    .unwrap_or_else(|panic| Err(Error::internal(&panic).at(at.get())));
    match r {
        Ok(()) => Ok(session.ncommands()),
        Err(e) => Err((e.located(&file, &src), e.kind)),
    }
}
