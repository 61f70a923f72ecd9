//! `aster study`: one case over a grid of variants, error against cost.
//!
//! A variant sets every knob to one of its values: the top-level assignments `NAME = ...` of the command
//! file are overridden (`--set N=8,16,32`), and meshes are generated from templates that name knobs
//! (`--mesh '20=box --cell QUAD8 --n {N},{N} --size 10,10'`). Each variant runs as its own `aster run`
//! process (`-j` at once), in `OUT/runs/<run>/`; the study measures its wall time and peak memory and
//! reads its message file (time per command, unknowns, Newton iterations, POST_ERREUR's relative
//! errors, the ANALYTIQUE / SOURCE_EXTERNE check lines). It writes `OUT/study.csv`, `OUT/study.md` (the
//! table and the Pareto fronts) and, per error metric, `OUT/<metric>_vs_time.svg` and
//! `OUT/<metric>_vs_unknowns.svg`. Time is the run's wall time less POST_ERREUR's (what measuring the
//! error costs is not what the accuracy costs); the CSV has both.

pub mod grid;
pub mod measure;
pub mod report;

use crate::diag::{Error, Result};
use crate::runner::export::{Dir, Export};
use grid::{combinations, override_assignments, Knob, MeshSpec};
use measure::Metrics;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// What to study.
#[derive(Debug, Clone)]
pub struct StudyOptions {
    /// A command file, or an export whose command file and data units are used.
    pub case: PathBuf,
    pub knobs: Vec<Knob>,
    pub meshes: Vec<MeshSpec>,
    /// Other units: N=PATH.
    pub units: Vec<(i64, PathBuf)>,
    pub jobs: usize,
    pub out: PathBuf,
    /// Error metrics to plot (POST_ERREUR options, `check`); empty: every metric found.
    pub errors: Vec<String>,
    /// The knobs drawn as curves (one curve per setting of the other knobs); empty: the knobs with the
    /// most values.
    pub curves: Vec<String>,
    pub time_limit: Option<f64>,
    /// Runs of each variant; the fastest one is kept (timings on a shared machine are noisy).
    pub repeat: usize,
    pub progress: bool,
    pub title: String,
}

/// One run of a study.
#[derive(Debug, Clone)]
pub struct Run {
    pub label: String,
    /// The value of each knob, in knob order.
    pub values: Vec<String>,
    pub metrics: Metrics,
}

/// A finished study.
#[derive(Debug, Clone)]
pub struct Study {
    pub title: String,
    pub knobs: Vec<Knob>,
    /// The knobs drawn as curves in the plots.
    pub curves: Vec<String>,
    pub runs: Vec<Run>,
    /// The files written (CSV, markdown, plots).
    pub written: Vec<PathBuf>,
}

/// The command file and the data units of the case.
fn case_files(opts: &StudyOptions) -> Result<(PathBuf, Vec<(i64, PathBuf)>)> {
    let c = &opts.case;
    let mut units: Vec<(i64, PathBuf)> = Vec::new();
    let comm = if c.extension().is_some_and(|e| e == "export") {
        let ex = Export::read(c)?;
        let comm = ex
            .comm_files()
            .first()
            .map(|f| f.path.clone())
            .ok_or_else(|| Error::io(format!("{}: no comm file", c.display())))?;
        for f in &ex.files {
            if f.kind != "comm" && f.dir != Dir::Out && f.unit > 0 {
                units.push((f.unit, absolute(&f.path)));
            }
        }
        comm
    } else {
        c.clone()
    };
    for (u, p) in &opts.units {
        units.retain(|(v, _)| v != u);
        units.push((*u, absolute(p)));
    }
    Ok((absolute(&comm), units))
}

fn absolute(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}

/// Run the study: every variant, the report files.
pub fn run_study(exe: &Path, opts: &StudyOptions) -> Result<Study> {
    let (comm, units) = case_files(opts)?;
    let src = std::fs::read_to_string(&comm).map_err(|e| Error::io(format!("{}: {e}", comm.display())))?;
    // Every knob must act: on an assignment of the command file or in a mesh template.
    let all: Vec<(String, String)> = opts.knobs.iter().map(|k| (k.name.clone(), k.values[0].clone())).collect();
    let (_, counts) = override_assignments(&src, &all)?;
    if let Some(c) = opts.curves.iter().find(|c| !opts.knobs.iter().any(|k| k.name == **c)) {
        return Err(Error::runtime(format!("--curve {c}: no --set names it")));
    }
    for (k, n) in opts.knobs.iter().zip(&counts) {
        if *n == 0 && !opts.meshes.iter().any(|m| m.uses(&k.name)) {
            return Err(Error::runtime(format!(
                "--set {}: {} has no top-level assignment `{} = ...` and no --mesh names {{{}}}",
                k.name,
                comm.display(),
                k.name,
                k.name
            )));
        }
    }
    let combos = combinations(&opts.knobs);
    let runs_dir = opts.out.join("runs");
    std::fs::create_dir_all(&runs_dir).map_err(|e| Error::io(format!("{}: {e}", runs_dir.display())))?;
    let runs_dir = absolute(&runs_dir);
    let bar = progress_bar(combos.len(), opts.progress);
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Run>>> = Mutex::new(vec![None; combos.len()]);
    let first_error: Mutex<Option<Error>> = Mutex::new(None);
    let jobs = opts.jobs.max(1).min(combos.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::SeqCst);
                if i >= combos.len() || first_error.lock().unwrap().is_some() {
                    break;
                }
                let values: Vec<String> =
                    combos[i].iter().zip(&opts.knobs).map(|(&j, k)| k.values[j].clone()).collect();
                let label = format!("r{:03}", i + 1);
                bar.set_message(describe(&opts.knobs, &values));
                let mut best: Option<Metrics> = None;
                for _ in 0..opts.repeat.max(1) {
                    match one_run(exe, opts, &comm, &src, &units, &runs_dir.join(&label), &values) {
                        Ok(m) if best.as_ref().is_none_or(|b| m.wall < b.wall) => best = Some(m),
                        Ok(_) => {}
                        Err(e) => {
                            first_error.lock().unwrap().get_or_insert(e);
                            break;
                        }
                    }
                }
                if let Some(metrics) = best {
                    results.lock().unwrap()[i] = Some(Run { label, values, metrics });
                }
                bar.inc(1);
            });
        }
    });
    bar.finish_and_clear();
    if let Some(e) = first_error.into_inner().unwrap() {
        return Err(e);
    }
    let runs: Vec<Run> = results.into_inner().unwrap().into_iter().flatten().collect();
    let most = opts.knobs.iter().map(|k| k.values.len()).max().unwrap_or(0);
    let curves = if opts.curves.is_empty() {
        opts.knobs.iter().filter(|k| k.values.len() == most && most > 1).map(|k| k.name.clone()).collect()
    } else {
        opts.curves.clone()
    };
    let mut study = Study { title: opts.title.clone(), knobs: opts.knobs.clone(), curves, runs, written: Vec::new() };
    write_report(&mut study, opts)?;
    Ok(study)
}

/// `N=8 ORDRE=2`.
pub fn describe(knobs: &[Knob], values: &[String]) -> String {
    knobs.iter().zip(values).map(|(k, v)| format!("{}={v}", k.name)).collect::<Vec<_>>().join(" ")
}

fn progress_bar(n: usize, show: bool) -> Arc<indicatif::ProgressBar> {
    let bar = if show { indicatif::ProgressBar::new(n as u64) } else { indicatif::ProgressBar::hidden() };
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} runs, {elapsed} ({eta} left) {msg}")
    {
        bar.set_style(style);
    }
    Arc::new(bar)
}

/// Prepare and run one variant in `dir`.
fn one_run(
    exe: &Path,
    opts: &StudyOptions,
    comm: &Path,
    src: &str,
    units: &[(i64, PathBuf)],
    dir: &Path,
    values: &[String],
) -> Result<Metrics> {
    let io = |e: std::io::Error| Error::io(format!("{}: {e}", dir.display()));
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).map_err(io)?;
    let named: Vec<(String, String)> = opts.knobs.iter().map(|k| k.name.clone()).zip(values.iter().cloned()).collect();
    let (text, _) = override_assignments(src, &named)?;
    let name = comm.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_else(|| "case.comm".into());
    let comm_path = dir.join(&name);
    std::fs::write(&comm_path, text).map_err(io)?;
    // Files that exist are read in place; the others are results, written in the run's folder.
    let mut unit_args: Vec<(i64, PathBuf)> = units
        .iter()
        .map(|(u, p)| match p.exists() {
            true => (*u, p.clone()),
            false => (*u, dir.join(p.file_name().map(PathBuf::from).unwrap_or_else(|| format!("unit{u}").into()))),
        })
        .collect();
    for m in &opts.meshes {
        let mesh = m.build(&named)?;
        let p = dir.join(format!("unit{}.med", m.unit));
        crate::med::write_mesh(&p, &mesh, "MAIL")?;
        unit_args.retain(|(u, _)| *u != m.unit);
        unit_args.push((m.unit, p));
    }
    let mut cmd = Command::new(exe);
    cmd.arg("run").arg(&comm_path).arg("--out").arg(dir).arg("--quiet");
    for (u, p) in &unit_args {
        cmd.arg("--unit").arg(format!("{u}={}", p.display()));
    }
    cmd.current_dir(dir).stdin(Stdio::null());
    cmd.stdout(std::fs::File::create(dir.join("stdout.txt")).map_err(io)?);
    cmd.stderr(std::fs::File::create(dir.join("stderr.txt")).map_err(io)?);
    let (code, wall, peak) = measure::run_child(cmd, opts.time_limit.map(Duration::from_secs_f64)).map_err(io)?;
    let mut m = Metrics { wall, peak_mib: peak, ..Metrics::default() };
    let stem = comm_path.file_stem().map(|s| s.to_string_lossy().to_string()).unwrap_or_default();
    let mess = dir.join(format!("{stem}.mess"));
    measure::read_mess(&mess, &mut m);
    let text = std::fs::read_to_string(&mess).unwrap_or_default();
    m.diagnostic = match code {
        None => "TIMEOUT".into(),
        Some(_) => text
            .lines()
            .rev()
            .find_map(|l| l.trim().strip_prefix("DIAGNOSTIC JOB : "))
            .map(|d| d.trim().to_string())
            .unwrap_or_else(|| "<F>_ERROR".into()),
    };
    let stderr = std::fs::read_to_string(dir.join("stderr.txt")).unwrap_or_default();
    m.error = stderr.lines().find(|l| l.starts_with("<F>")).map(str::to_string);
    Ok(m)
}

/// study.csv, study.md and the plots.
fn write_report(s: &mut Study, opts: &StudyOptions) -> Result<()> {
    let io = |p: &Path, e: std::io::Error| Error::io(format!("{}: {e}", p.display()));
    let csv = opts.out.join("study.csv");
    std::fs::write(&csv, report::csv(s)).map_err(|e| io(&csv, e))?;
    s.written.push(csv);
    let md = opts.out.join("study.md");
    let text = format!("{}\n{}", report::markdown(s), report::pareto_summary(s));
    std::fs::write(&md, text).map_err(|e| io(&md, e))?;
    s.written.push(md);
    let keys = if opts.errors.is_empty() { report::error_keys(&s.runs) } else { opts.errors.clone() };
    for key in keys {
        for axis in [report::Axis::Wall, report::Axis::Unknowns] {
            let p = opts.out.join(report::plot_name(&key, axis));
            match report::plot(s, &key, axis, &p) {
                Ok(()) => s.written.push(p),
                // A metric no run measured (or a cost no run reported) has nothing to plot.
                Err(e) if !opts.errors.contains(&key) || axis == report::Axis::Unknowns => {
                    eprintln!("aster study: {e}")
                }
                Err(e) => return Err(Error::runtime(e)),
            }
        }
    }
    Ok(())
}
