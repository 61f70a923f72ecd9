//! Every class of bad input gives a located message and a non-zero exit,
//! and leaves no half-written result behind.

use std::path::Path;
use std::process::Command;

struct Run {
    code: i32,
    stderr: String,
    mess: String,
}

fn run_in(dir: &Path, file: &str, args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(dir.join(file))
        .args(["--out", dir.to_str().unwrap(), "-q"])
        .args(args)
        .output()
        .unwrap();
    let stem = Path::new(file).file_stem().unwrap().to_str().unwrap();
    Run {
        code: out.status.code().unwrap_or(-1),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        mess: std::fs::read_to_string(dir.join(format!("{stem}.mess"))).unwrap_or_default(),
    }
}

/// Run `src` as bad.comm; assert the exit code, the located message and the diagnostic.
fn expect(name: &str, src: &str, located: &str, diagnostic: &str) {
    let dir = scratch!(name);
    std::fs::write(dir.join("bad.comm"), src).unwrap();
    let r = run_in(&dir, "bad.comm", &[]);
    assert_eq!(r.code, 2, "{name}: exit code; stderr: {}", r.stderr);
    assert!(r.stderr.contains(located), "{name}: expected '{located}' in stderr:\n{}", r.stderr);
    assert!(r.mess.contains(located), "{name}: the .mess file must carry the message");
    assert!(
        r.mess.contains(&format!("DIAGNOSTIC JOB : {diagnostic}")),
        "{name}: expected diagnostic {diagnostic}; mess tail:\n{}",
        &r.mess[r.mess.len().saturating_sub(300)..]
    );
}

#[test]
fn syntax_error() {
    expect("syntax", "DEBUT()\nX = 1 +* 2\nFIN()\n", "bad.comm:2:", "<F>_SYNTAX_ERROR");
    expect(
        "unclosed",
        "DEBUT()\nF = DEFI_FONCTION(NOM_PARA='X', VALE=(0., 1.,\nFIN()\n",
        "bad.comm:2:38: invalid syntax: '(' is never closed",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn unknown_command() {
    expect(
        "command",
        "DEBUT()\nF = DEFI_FONCTIONN(NOM_PARA='X', VALE=(0., 1., 1., 2.))\n",
        "bad.comm:2:5: unknown command 'DEFI_FONCTIONN' (did you mean 'DEFI_FONCTION'?)",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn unknown_keyword() {
    expect(
        "keyword",
        "DEBUT()\nF = DEFI_FONCTION(NOM_PARA='X',\n    VALEE=(0., 1., 1., 2.))\n",
        "bad.comm:3:5: DEFI_FONCTION: unknown keyword 'VALEE' (did you mean 'VALE'?)",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn wrong_type() {
    expect(
        "type",
        "DEBUT()\nF = DEFI_CONSTANTE(VALE=1.)\nTEST_TABLE(TABLE=F, NOM_PARA='X', VALE_CALC=1.)\n",
        "bad.comm:3:12: TEST_TABLE: keyword 'TABLE' expects table_sdaster or table_container, got fonction_sdaster F",
        "<F>_SYNTAX_ERROR",
    );
    expect(
        "type-real",
        "DEBUT()\nF = DEFI_CONSTANTE(VALE='one')\n",
        "bad.comm:2:20: DEFI_CONSTANTE: keyword 'VALE' expects a real, got str 'one'",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn value_not_allowed() {
    expect(
        "into",
        "DEBUT()\nF = DEFI_FONCTION(NOM_PARA='X', VALE=(0., 1., 1., 2.), PROL_DROITE='LINEAR')\n",
        "bad.comm:2:56: DEFI_FONCTION: value 'LINEAR' is not allowed for keyword 'PROL_DROITE' (did you mean 'LINEAIRE'?)",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn missing_mandatory_keyword() {
    expect(
        "mandatory",
        "DEBUT()\nF = DEFI_FONCTION(VALE=(0., 1., 1., 2.))\n",
        "bad.comm:2:5: DEFI_FONCTION: mandatory keyword 'NOM_PARA' is missing",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn rule_broken() {
    expect(
        "rule",
        "DEBUT()\nL = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2, PAS=0.5))\n",
        "DEFI_LIST_REEL: exactly one of 'NOMBRE', 'PAS' is required (got NOMBRE and PAS) (in INTERVALLE)",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn undefined_name() {
    expect(
        "name",
        "DEBUT()\nF = DEFI_CONSTANTE(VALE=young)\n",
        "bad.comm:2:25: NameError: name 'young' is not defined",
        "<F>_ERROR",
    );
}

#[test]
fn numpy_import() {
    expect(
        "numpy",
        "import numpy.fft as F\nDEBUT()\n",
        "bad.comm:1:1: import numpy.fft: this part of numpy is not supported by aster-rs",
        "<F>_ERROR",
    );
}

#[test]
fn unsupported_command() {
    // Every command of Code_Aster's catalogue is checked: a call that breaks its schema stops before
    // anything runs, and a valid call to a command without a stage stops the run by name, when it is
    // reached.
    expect(
        "unsupported-invalid",
        "DEBUT()\nR = DYNA_VIBRA(TYPE_CALCUL='TRAN')\n",
        "bad.comm:2:5: DYNA_VIBRA: mandatory keyword 'BASE_CALCUL' is missing",
        "<F>_SYNTAX_ERROR",
    );
    expect(
        "unsupported",
        "DEBUT()\nL = DEFI_LIST_FREQ(VALE=(1.0, 2.0))\nFIN()\n",
        "bad.comm:2:5: DEFI_LIST_FREQ is not supported yet",
        "<F>_ERROR",
    );
}

#[test]
fn missing_unit_file() {
    expect(
        "unit",
        "DEBUT()\nT = LIRE_TABLE(UNITE=31)\n",
        "bad.comm:2:16: LIRE_TABLE: unit 31 is not assigned to a file",
        "<F>_ERROR",
    );
    // An .export naming a data file that does not exist stops before running.
    let dir = scratch!("unit-export");
    std::fs::write(dir.join("case.comm"), "DEBUT()\nT = LIRE_TABLE(UNITE=31)\nFIN()\n").unwrap();
    std::fs::write(dir.join("case.export"), "P time_limit 60\nF comm case.comm D 1\nF libr missing.31 D 31\n").unwrap();
    let r = run_in(&dir, "case.export", &[]);
    assert_eq!(r.code, 2);
    assert!(r.stderr.contains("unit 31: data file") && r.stderr.contains("missing.31 does not exist"), "{}", r.stderr);
    // ... and names the line of the .export that names it.
    assert!(r.stderr.contains("case.export:3: F libr missing.31 D 31)"), "{}", r.stderr);
    // A command file the .export names that does not exist, likewise.
    std::fs::write(dir.join("case.export"), "P time_limit 60\nF comm nocase.comm D 1\n").unwrap();
    let r = run_in(&dir, "case.export", &[]);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr.contains("command file") && r.stderr.contains("case.export:2: F comm nocase.comm D 1"),
        "{}",
        r.stderr
    );
}

#[test]
fn file_cut_in_the_middle_of_a_call() {
    // The file ends inside the brackets of a call, on the line of its last bracket: the bracket left open
    // is named (the end of the file used to be).
    expect(
        "cut",
        "DEBUT()\nMO = AFFE_MODELE(MAILLAGE=MA,\n    AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE',",
        "bad.comm:3:12: invalid syntax: '(' is never closed (the file ends at line 3, column",
        "<F>_SYNTAX_ERROR",
    );
}

#[test]
fn failed_run_leaves_no_result_file() {
    let dir = scratch!("atomic");
    let src = "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='A', LISTE_I=(1, 2)))\nIMPR_TABLE(TABLE=T, UNITE=38)\nX = undefined_name\n";
    std::fs::write(dir.join("case.comm"), src).unwrap();
    let target = dir.join("table.txt");
    let r = run_in(&dir, "case.comm", &["--unit", &format!("38={}", target.display())]);
    assert_eq!(r.code, 2);
    assert!(!target.exists(), "a failed run must not deliver results");
    // The same file without the error delivers the table.
    std::fs::write(dir.join("case.comm"), &src[..src.find("X = ").unwrap()]).unwrap();
    let r = run_in(&dir, "case.comm", &["--unit", &format!("38={}", target.display())]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&target).unwrap();
    assert!(text.lines().any(|l| l.split_whitespace().collect::<Vec<_>>() == ["2"]), "{text}");
}
