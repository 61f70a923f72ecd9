//! Helpers shared by the integration tests: the repository and the legacy suite's files read in place,
//! scratch folders, the `aster` binary, and FISS1/FISS2 of WTNV149 built from level-set closures.
#![allow(dead_code)]

use aster::mesh::Mesh;
use aster::xfem::{build_interface, Crack};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::rc::Rc;

/// The repository's root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The folder `../shared/astest`, or None (with a SKIP message) when absent.
pub fn astest_dir() -> Option<PathBuf> {
    let p = root().join("../shared/astest");
    if p.is_dir() {
        Some(p)
    } else {
        println!("SKIP: {} is absent", p.display());
        None
    }
}

/// A file of `../shared/astest`, or None (with a SKIP message) when absent.
pub fn astest(file: &str) -> Option<PathBuf> {
    let p = root().join("../shared/astest").join(file);
    if p.exists() {
        Some(p)
    } else {
        println!("SKIP: {} is absent", p.display());
        None
    }
}

/// A mesh of `../shared/astest`, read in place.
pub fn mesh(file: &str) -> Option<Rc<Mesh>> {
    let p = astest(file)?;
    Some(Rc::new(aster::med::read_mesh(&p, None).unwrap()))
}

/// A fresh, empty scratch folder for one test: `scratch!("tag")` names it after the calling module and
/// the tag, so tests of different modules never share one (they all run in this one process).
#[macro_export]
macro_rules! scratch {
    ($tag:expr) => {
        $crate::common::scratch_dir(module_path!(), &$tag)
    };
}

/// The folder behind [`scratch!`]: `aster-rs-it-<pid>-<module>-<tag>` in the temporary folder.
pub fn scratch_dir(module: &str, tag: &str) -> PathBuf {
    let module = module.trim_start_matches("it::").replace("::", "-");
    let d = std::env::temp_dir().join(format!("aster-rs-it-{}-{module}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The `aster` binary of this build.
pub fn aster() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aster"))
}

/// A process's standard output and error as text.
pub fn text(o: &Output) -> (String, String) {
    (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// FISS1 then FISS2 with its junction on FISS1 at `point` (DEFI_FISS_XFEM of the .comm).
pub fn two_cracks(
    mesh: &Rc<Mesh>,
    f1: impl Fn(&[f64; 3]) -> f64,
    f2: impl Fn(&[f64; 3]) -> f64,
    point: &[f64],
) -> (Rc<Crack>, Rc<Crack>) {
    let l1 = mesh.coords.iter().map(&f1).collect();
    let c1 = Rc::new(build_interface("MA".into(), mesh.clone(), l1, None, &[], None).unwrap());
    let l2 = mesh.coords.iter().map(&f2).collect();
    let masters = [("FISS1".to_string(), c1.clone())];
    let c2 = Rc::new(build_interface("MA".into(), mesh.clone(), l2, None, &masters, Some(point)).unwrap());
    (c1, c2)
}

/// A small seeded generator (xorshift64*) for the fuzzers and property tests: a run is replayed from its
/// printed seed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in 0..n (0 when n is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
}

/// Run cases of Code_Aster's 2025 corpus (`../shared/corpus/astest-2025`, read in place) unmodified: each
/// must end OK with exactly its number of OK check lines. Skips with a message where the corpus is absent.
pub fn run_corpus_cases(out: &Path, cases: &[(&str, usize)]) {
    let dir = root().join("../shared/corpus/astest-2025");
    if !dir.is_dir() {
        println!("SKIP: {} is absent", dir.display());
        return;
    }
    let mut failures = Vec::new();
    for &(case, ok) in cases {
        let opts = aster::runner::RunOptions { out_dir: Some(out.join(case)), units: vec![], echo: false };
        let o = aster::runner::run_export(&dir.join(format!("{case}.export")), &opts);
        println!("{case:<10} {:<16} {} OK", o.diagnostic, o.ok_count());
        if o.diagnostic != "OK" || o.ok_count() != ok {
            failures.push(format!(
                "{case}: {} with {} OK lines (want {ok}): {:?}",
                o.diagnostic,
                o.ok_count(),
                o.error
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let _ = std::fs::remove_dir_all(out);
}

/// The rows of the table `intitule` in a run's .resu text (IMPR_TABLE of POST_RELEVE_T): per row, the
/// value of each column by its name (the header line starts with INTITULE, each row with the title).
pub fn resu_rows(resu: &str, intitule: &str) -> Vec<std::collections::BTreeMap<String, String>> {
    let mut out = Vec::new();
    let mut cols: Vec<&str> = Vec::new();
    for l in resu.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        if w.first() == Some(&"INTITULE") {
            cols = w;
        } else if w.first() == Some(&intitule) && w.len() == cols.len() {
            out.push(cols.iter().zip(&w).map(|(c, v)| (c.to_string(), v.to_string())).collect());
        }
    }
    out
}

/// Run `comm` (as `one.comm`) in `dir` on a box mesh of `aster mesh box --cell CELL --n N --size SIZE` on
/// unit 20: the run's exit status, message file and result file (empty where not written).
pub fn run_on_box(
    dir: &Path,
    (cell, n, size): (&str, &str, &str),
    comm: &str,
) -> (std::process::ExitStatus, String, String) {
    let mesh = dir.join("one.med");
    let o = aster().args(["mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o"]).arg(&mesh).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let path = dir.join("one.comm");
    std::fs::write(&path, comm).unwrap();
    let o = aster()
        .arg("run")
        .arg(&path)
        .arg("--out")
        .arg(dir)
        .arg("-q")
        .arg("--unit")
        .arg(format!("20={}", mesh.display()))
        .output()
        .unwrap();
    let read = |ext: &str| std::fs::read_to_string(dir.join(format!("one.{ext}"))).unwrap_or_default();
    (o.status, read("mess"), read("resu"))
}

/// The errors of the OK ANALYTIQUE lines on `ERR_*` columns of a .resu text (TEST_TABLE of an error
/// formula against 0), in order.
pub fn analytic_errors(resu: &str) -> Vec<f64> {
    resu.lines()
        .filter_map(|l| {
            let t: Vec<&str> = l.split_whitespace().collect();
            (t.len() >= 5 && t[0] == "OK" && t[1] == "ANALYTIQUE" && t[2].starts_with("ERR_"))
                .then(|| t[4].parse().ok())?
        })
        .collect()
}

/// `aster study` of `export` (under comm/) on the generated mesh `mesh` with the knobs `--set` gives,
/// into `out`: the `check:ERR_L2` of every variant keyed by the values of `keys` joined by spaces.
pub fn study_err_l2(
    out: &Path,
    export: &str,
    mesh: &str,
    knobs: &[&str],
    keys: &[&str],
) -> std::collections::BTreeMap<String, f64> {
    let mut cmd = aster();
    cmd.args(["study", root().join(format!("comm/{export}")).to_str().unwrap()]).args([
        "--mesh",
        mesh,
        "--quiet",
        "--error",
        "check:ERR_L2",
    ]);
    for k in knobs {
        cmd.args(["--set", k]);
    }
    let o = cmd.arg("--out").arg(out).output().unwrap();
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stdout}\n{stderr}");
    let csv = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("{name}: {csv}"));
    let mut errs = std::collections::BTreeMap::new();
    for l in lines {
        let r: Vec<&str> = l.split(',').collect();
        let key = keys.iter().map(|k| r[col(k)]).collect::<Vec<_>>().join(" ");
        let e: f64 = r[col("err_check:ERR_L2")].parse().unwrap_or_else(|_| panic!("{l}"));
        errs.insert(key, e);
    }
    errs
}

/// Run our scene `comm/<scene>.comm` with `edits` (from, to) applied, as `case.comm` in `dir`, its units
/// mapped to files of `med/` (`units`: number, file): (exit code, stderr, .mess text).
pub fn run_scene_edited(
    dir: &Path,
    scene: &str,
    units: &[(u32, &str)],
    edits: &[(&str, &str)],
) -> (i32, String, String) {
    let mut src = std::fs::read_to_string(root().join("comm").join(format!("{scene}.comm"))).unwrap();
    for (from, to) in edits {
        assert!(src.contains(from), "{scene}.comm no longer holds {from:?}");
        src = src.replace(from, to);
    }
    std::fs::write(dir.join("case.comm"), src).unwrap();
    let mut cmd = aster();
    cmd.arg("run").arg(dir.join("case.comm")).args(["--out", dir.to_str().unwrap(), "-q"]);
    for (n, file) in units {
        cmd.arg("--unit").arg(format!("{n}={}", root().join("med").join(file).display()));
    }
    let out = cmd.output().unwrap();
    let mess = std::fs::read_to_string(dir.join("case.mess")).unwrap_or_default();
    (out.status.code().unwrap_or(-1), text(&out).1, mess)
}
