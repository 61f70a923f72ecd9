//! One execution of a command file: the interpreter's host (command calls go
//! through the catalogue to the stages) and the stages' I/O (units, message
//! and result files, check records).

use super::export::Dir;
use crate::catalog::args::take_undeclared_lookups;
use crate::catalog::schema::Produces;
use crate::catalog::validate::Produced;
use crate::catalog::{catalogue, validate};
use crate::concepts::{Concept, ConceptData};
use crate::diag::{Error, Result};
use crate::interp::{Host, KwArg, Scope, Value};
use crate::stages::{self, Access, CheckRecord, Ctx, StageIo, UnitState};
use crate::syntax::ast::Span;
use std::collections::{BTreeMap, HashSet};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Validate only: commands return typed placeholders.
    Check,
    Run,
}

/// Time spent in one command.
#[derive(Debug, Clone)]
pub struct Timing {
    pub command: String,
    pub line: usize,
    pub seconds: f64,
}

pub struct Session {
    pub mode: Mode,
    pub file: String,
    pub src: String,
    pub globals: Scope,
    /// Units given by the .export or --unit: path and direction.
    pub units: BTreeMap<i64, (PathBuf, Dir)>,
    /// Where units written during the run live until they are delivered.
    pub workdir: PathBuf,
    written: HashSet<i64>,
    pub mess: String,
    pub resu: String,
    pub echo: bool,
    pub records: Vec<CheckRecord>,
    pub timings: Vec<Timing>,
    pub validation: bool,
    finished: bool,
    ncommands: usize,
    /// Units DEFI_FICHIER associated with files of the work folder.
    pub(super) assoc: BTreeMap<i64, Assoc>,
    /// The test hook `ASTER_INJECT_PANIC`: the command whose stage panics (see `guard`).
    inject_panic: Option<String>,
}

impl Session {
    pub fn new(mode: Mode, file: &str, src: &str, globals: Scope, workdir: PathBuf) -> Session {
        Session {
            mode,
            file: file.to_string(),
            src: src.to_string(),
            globals,
            units: BTreeMap::new(),
            workdir,
            written: HashSet::new(),
            mess: String::new(),
            resu: String::new(),
            echo: false,
            records: Vec::new(),
            timings: Vec::new(),
            validation: false,
            finished: false,
            ncommands: 0,
            assoc: BTreeMap::new(),
            inject_panic: super::guard::injected_panic(),
        }
    }

    fn line_of(&self, span: Span) -> usize {
        crate::syntax::lexer::line_col(&self.src, span.start).0
    }

    fn say(&mut self, text: &str) {
        self.mess.push_str(text);
        if self.echo {
            print!("{text}");
            let _ = std::io::stdout().flush();
        }
    }

    fn workfile(&self, unit: i64) -> PathBuf {
        self.workdir.join(format!("fort.{unit}"))
    }

    /// Units written during the run that the .export asks to keep.
    pub fn deliverables(&self) -> Vec<(PathBuf, PathBuf)> {
        self.units
            .iter()
            .filter(|(u, (_, d))| *d != Dir::In && self.written.contains(u))
            .map(|(u, (p, _))| (self.workfile(*u), p.clone()))
            .collect()
    }

    fn run_command(&mut self, name: &'static str, kwargs: Vec<KwArg>, span: Span) -> Result<Value> {
        let cat = catalogue();
        let cmd = cat.get(name).expect("host only calls catalogue commands");
        let hand = cat.hand_written(name);
        // A run validates a second time against the stage's own schema (below): keep the keywords.
        let kept = hand.is_some().then(|| kwargs.clone());
        let (cmd, validated) = match validate::validate(cmd, kwargs, span) {
            Ok(v) => (cmd, v),
            // Our schema also takes spellings of older Code_Aster versions that 2025's dropped
            // (DEFI_CONTACT's XFEM zones, ITER_CONT_MAXI): a call it accepts is valid.
            Err(e) => match (hand, &kept) {
                (Some(h), Some(kw)) => match validate::validate(h, kw.clone(), span) {
                    Ok(v) => (h, v),
                    Err(_) => return Err(e),
                },
                _ => return Err(e),
            },
        };
        let kept = kept.filter(|_| self.mode == Mode::Run);
        let mut produced = validate::produced(cmd, &validated.args).map_err(|e| e.at(span).in_command(name))?;
        if let (Produced::OneOf(ks), Some(h)) = (&produced, hand) {
            // Code_Aster's cases could not tell; our own rule may (unless it only repeats one of the
            // possible types: the type of an argument that is itself uncertain).
            if let Ok(Produced::Kind(k)) = validate::produced(h, &validated.args) {
                if !ks.contains(&k) {
                    produced = Produced::Kind(k);
                }
            }
        }
        let validated = match (kept, hand) {
            (Some(kwargs), Some(h)) => {
                let v = validate::validate_supported(h, kwargs, span)?;
                produced = validate::produced(h, &v.args).map_err(|e| e.at(span).in_command(name))?;
                v
            }
            _ => validated,
        };
        let args = validated.args;
        // `CMD(reuse=X, ...)` modifies X in place and returns it: `Y = CMD(reuse=X, ...)` makes Y another
        // name of X, as in Code_Aster 2025, whose import drops `reuse` and whose reentrant commands
        // return the object they modify (wtnv122d: `MAILLAGE = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ...)`).
        let kind = match &produced {
            Produced::Kind(k) => Some(*k),
            // A generated schema whose only possible type is chosen by a rule (AFFE_CARA_ELEM).
            Produced::OneOf(ks) if ks.len() == 1 => Some(ks[0]),
            _ => None,
        };
        if let (Some(r), Some(k)) = (&validated.reuse, kind) {
            if !r.may_be(k) && !k.is_a(r.kind()) {
                return Err(Error::catalog(format!("reuse={} is a {}, {name} produces a {k}", r.label(), r.kind()))
                    .at(span)
                    .in_command(name));
            }
        }
        if name == "FIN" {
            self.finished = true;
        }
        if self.mode == Mode::Check {
            // A command that gives a Python integer (DEFI_FICHIER's free unit) gives 0 unrun.
            if matches!(cmd.produces, Produces::Int) || hand.is_some_and(|h| matches!(h.produces, Produces::Int)) {
                return Ok(Value::Int(0));
            }
            // The concepts named by CO('name') come into being under their names.
            for (co, kinds) in &validated.new_concepts {
                co.become_one_of(kinds);
                self.globals.borrow_mut().insert(co.name(), Value::Concept(co.clone()));
            }
            // Pure definitions (functions, constants, lists of reals) are computed, so that the file's
            // Python may use their values (`YOUN(TEMP)` in a later keyword); one that fails here is left
            // to the run, which reports it.
            if let (true, None, Produced::Kind(k)) = (PURE.contains(&name), &validated.reuse, &produced) {
                if let Some(v) = self.compute_pure(name, span, &args, *k) {
                    return Ok(v);
                }
            }
            return Ok(match (&validated.reuse, produced) {
                (_, Produced::Nothing) => Value::None,
                (Some(r), _) => Value::Concept(r.clone()),
                (None, Produced::Kind(k)) => Value::Concept(Concept::new(k, ConceptData::Pending)),
                (None, Produced::OneOf(ks)) => Value::Concept(Concept::pending_one_of(&ks)),
            });
        }
        let Some(stage) = stages::stage(name) else {
            return Err(Error::unsupported(format!("{name} is not supported yet")).at(span));
        };
        let line = self.line_of(span);
        let globals = self.globals.clone();
        let inject_panic = self.inject_panic.as_deref() == Some(name);
        let reuse = validated.reuse.clone();
        let mut ctx = Ctx { io: self, globals, command: name, line, reuse, int_result: None };
        args.reset_reads();
        take_undeclared_lookups();
        if inject_panic {
            panic!("panic injected in {name} by ASTER_INJECT_PANIC (a test hook)");
        }
        let data = stage(&mut ctx, &args).map_err(|e| e.at(span).in_command(name))?;
        let int_result = ctx.int_result;
        stages::all_keywords_used(name, &args).map_err(|e| e.at(span).in_command(name))?;
        if matches!(cmd.produces, Produces::Int) || hand.is_some_and(|h| matches!(h.produces, Produces::Int)) {
            return Ok(int_result.map(Value::Int).unwrap_or(Value::None));
        }
        match (kind, data) {
            (Some(k), Some(d)) => Ok(match &validated.reuse {
                Some(r) => {
                    r.replace(d);
                    Value::Concept(r.clone())
                }
                None => Value::Concept(Concept::new(k, d)),
            }),
            (None, _) => Ok(Value::None),
            (Some(k), None) => Err(Error::runtime(format!("internal error: {name} produced no {k}")).at(span)),
        }
    }
}

/// The commands `aster check` computes: definitions that read no file and cost nothing.
const PURE: &[&str] = &["DEFI_CONSTANTE", "DEFI_FONCTION", "FORMULE", "DEFI_NAPPE", "DEFI_LIST_REEL", "DEFI_LIST_ENTI"];

impl Session {
    /// A pure definition computed in check mode: its concept, or None when its stage does not complete.
    fn compute_pure(
        &mut self,
        name: &'static str,
        span: Span,
        args: &crate::catalog::args::Args,
        k: crate::concepts::ConceptKind,
    ) -> Option<Value> {
        let stage = stages::stage(name)?;
        let line = self.line_of(span);
        let globals = self.globals.clone();
        let mut ctx = Ctx { io: self, globals, command: name, line, reuse: None, int_result: None };
        args.reset_reads();
        take_undeclared_lookups();
        let out = stage(&mut ctx, args);
        let undeclared = take_undeclared_lookups();
        match out {
            Ok(Some(d)) if undeclared.is_empty() => Some(Value::Concept(Concept::new(k, d))),
            _ => None,
        }
    }
}

impl Host for Session {
    fn call_command(
        &mut self,
        name: &'static str,
        kwargs: Vec<KwArg>,
        span: Span,
        target: Option<&str>,
    ) -> Result<Value> {
        self.ncommands += 1;
        let line = self.line_of(span);
        let n = self.ncommands;
        if self.mode == Mode::Run {
            let text: String = self.src.get(span.start..span.end).unwrap_or(name).to_string();
            let shown = match target {
                Some(t) => format!("{t} = {text}"),
                None => text,
            };
            let bar = "  # ".to_string() + &"-".repeat(86);
            self.say(&format!(
                "\n{bar}\n  # Command #{n:04}  {name}  ({}:{line})\n{bar}\n{}\n\n",
                self.file,
                shown.lines().map(|l| format!("  {l}")).collect::<Vec<_>>().join("\n")
            ));
        }
        // The run's time limit is checked between commands (and by the interpreter and long stages).
        crate::diag::check_deadline().map_err(|e| e.at(span).in_command(name))?;
        let t0 = Instant::now();
        // A panic of the catalogue or of the stage (a bug of ours) stops the run as a located error.
        let r = super::guard::catch(|| self.run_command(name, kwargs, span))
            .unwrap_or_else(|panic| Err(Error::internal(&panic).at(span).in_command(name)));
        let dt = t0.elapsed().as_secs_f64();
        if self.mode == Mode::Run {
            self.timings.push(Timing { command: name.to_string(), line, seconds: dt });
            if r.is_ok() {
                self.say(&format!("  # End of command #{n:04} {name}  elapsed {dt:.3} s\n"));
            }
        }
        r
    }

    fn print(&mut self, text: &str) {
        self.say(text);
    }

    fn finished(&self) -> bool {
        self.finished
    }

    fn command(&self, name: &str) -> Option<&'static str> {
        catalogue().get(name).map(|c| c.name)
    }

    fn suggest_command(&self, name: &str) -> Option<&'static str> {
        validate::suggest(name, &catalogue().names())
    }
}

impl StageIo for Session {
    fn mess(&mut self, text: &str) {
        self.say(text);
    }

    fn resu(&mut self, text: &str) {
        self.resu.push_str(text);
        self.say(text);
    }

    fn read_unit(&mut self, unit: i64) -> Result<String> {
        let path = if let Some(p) = self.associated(unit) {
            p.clone()
        } else if self.written.contains(&unit) {
            self.workfile(unit)
        } else {
            match self.units.get(&unit) {
                Some((p, _)) => p.clone(),
                None => {
                    return Err(Error::io(format!(
                        "unit {unit} is not assigned to a file: add 'F libr FILE D {unit}' to the .export or --unit {unit}=FILE"
                    )))
                }
            }
        };
        let bytes =
            std::fs::read(&path).map_err(|e| Error::io(format!("unit {unit}: cannot read {}: {e}", path.display())))?;
        Ok(decode(&bytes))
    }

    fn write_unit(&mut self, unit: i64, text: &str) -> Result<()> {
        match unit {
            6 => {
                self.say(text);
                return Ok(());
            }
            8 => {
                self.resu(text);
                return Ok(());
            }
            _ => {}
        }
        if let Some(p) = self.associated(unit) {
            // DEFI_FICHIER opened it (emptied for ACCES='NEW'): every write goes after the last.
            let mut f = std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(p)
                .map_err(|e| Error::io(format!("unit {unit}: cannot write {}: {e}", p.display())))?;
            return f.write_all(text.as_bytes()).map_err(|e| Error::io(format!("unit {unit}: {e}")));
        }
        let path = self.workfile(unit);
        let first = self.written.insert(unit);
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .write(true)
            .append(!first)
            .truncate(first)
            .open(&path)
            .map_err(|e| Error::io(format!("unit {unit}: cannot write {}: {e}", path.display())))?;
        f.write_all(text.as_bytes()).map_err(|e| Error::io(format!("unit {unit}: {e}")))?;
        Ok(())
    }

    fn unit_path(&mut self, unit: i64, write: bool) -> Result<PathBuf> {
        if let Some(p) = self.associated(unit) {
            if !write && !p.exists() {
                return Err(Error::io(format!("unit {unit}: file {} does not exist", p.display())));
            }
            return Ok(p.clone());
        }
        if write {
            self.written.insert(unit);
            return Ok(self.workfile(unit));
        }
        if self.written.contains(&unit) {
            return Ok(self.workfile(unit));
        }
        match self.units.get(&unit) {
            Some((p, _)) if p.exists() => Ok(p.clone()),
            Some((p, _)) => Err(Error::io(format!("unit {unit}: data file {} does not exist", p.display()))),
            None => Err(Error::io(format!(
                "unit {unit} is not assigned to a file: add 'F mmed FILE D {unit}' to the .export or --unit {unit}=FILE"
            ))),
        }
    }

    fn record(&mut self, rec: CheckRecord) {
        self.records.push(rec);
    }

    fn is_validation(&self) -> bool {
        self.validation
    }

    fn associate(&mut self, unit: Option<i64>, file: Option<&str>, access: Access, reserve: bool) -> Result<i64> {
        self.associate_unit(unit, file, access, reserve)
    }

    fn release(&mut self, unit: Option<i64>, file: Option<&str>) -> Result<i64> {
        self.release_unit(unit, file)
    }

    fn unit_state(&mut self, unit: Option<i64>, file: Option<&str>) -> (UnitState, Option<String>) {
        self.state_of(unit, file)
    }

    fn free_unit(&mut self) -> Option<i64> {
        self.free_unit_number()
    }

    fn forget(&mut self, concept: &crate::concepts::ConceptRef) -> Vec<String> {
        self.forget_concept(concept)
    }
}

/// Text of a file: UTF-8, else Latin-1 (old command files).
pub fn decode(bytes: &[u8]) -> String {
    match std::str::from_utf8(bytes) {
        Ok(s) => s.strip_prefix('\u{feff}').unwrap_or(s).to_string(),
        Err(_) => bytes.iter().map(|&b| b as char).collect(),
    }
}

/// A scratch folder for one run, removed when dropped.
pub struct WorkDir(pub PathBuf);

impl WorkDir {
    pub fn new() -> Result<WorkDir> {
        static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        let p = std::env::temp_dir().join(format!("aster-rs-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&p).map_err(|e| Error::io(format!("cannot create {}: {e}", p.display())))?;
        Ok(WorkDir(p))
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Write a file atomically: a temporary beside it, then a rename.
pub fn write_atomic(path: &Path, data: &[u8]) -> Result<()> {
    let tmp = path.with_extension(format!(
        "{}.tmp{}",
        path.extension().and_then(|e| e.to_str()).unwrap_or(""),
        std::process::id()
    ));
    std::fs::write(&tmp, data).map_err(|e| Error::io(format!("cannot write {}: {e}", tmp.display())))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(format!("cannot write {}: {e}", path.display()))
    })
}

impl Session {
    /// Go on with the next command file of a continued study (POURSUITE): its name and text locate
    /// what it does, and the FIN of the previous file no longer stops the interpreter.
    pub fn continue_with(&mut self, file: &str, src: &str) {
        self.file = file.to_string();
        self.src = src.to_string();
        self.finished = false;
        self.say(&format!("\n  # Continued in {file} (POURSUITE)\n"));
    }

    /// How many command calls were made.
    pub fn ncommands(&self) -> usize {
        self.ncommands
    }

    /// The units written during the run.
    pub(super) fn written_units(&self) -> &HashSet<i64> {
        &self.written
    }
}

/// A unit DEFI_FICHIER associated (`runner::units`) with (or reserved for) a file.
#[derive(Debug, Clone)]
pub struct Assoc {
    /// The file as the command file named it.
    pub name: String,
    pub path: PathBuf,
    pub reserved: bool,
}
