//! The control commands and continued studies: an .export with several command files runs them in
//! order in one interpreter (POURSUITE), every name carrying over and FIN ending each file; DETRUIRE
//! unbinds names; DEFI_FICHIER ties units to files of the run's folder (and hands out free ones);
//! INFO_EXEC_ASTER reports them.

use crate::common::*;
use std::path::Path;

/// Run `files` (name, text) of one .export in `dir`: exit status, message file.
fn run_export(dir: &Path, files: &[(&str, &str)]) -> (std::process::ExitStatus, String, String) {
    let mut export = String::from("P time_limit 60\n");
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
        export.push_str(&format!("F comm {name} D 1\n"));
    }
    std::fs::write(dir.join("case.export"), export).unwrap();
    let o = aster().arg("run").arg(dir.join("case.export")).arg("--out").arg(dir).arg("-q").output().unwrap();
    let (_, err) = text(&o);
    (o.status, std::fs::read_to_string(dir.join("case.mess")).unwrap_or_default(), err)
}

#[test]
fn poursuite_runs_the_command_files_in_order_with_every_name() {
    let dir = scratch!("poursuite");
    let first = "DEBUT(CODE='OUI')\nx = 2.0\nF = DEFI_CONSTANTE(VALE=3.0)\ndef twice(v):\n    return 2 * v\nFIN()\n\
                 UNKNOWN_AFTER_FIN(A=1)\n";
    let second = "POURSUITE(CODE='OUI', ERREUR=_F(ALARME='EXCEPTION'))\n\
                  T = CREA_TABLE(LISTE=_F(PARA='X', LISTE_R=(twice(x) * F(0.0),)))\n\
                  TEST_TABLE(TABLE=T, NOM_PARA='X', VALE_CALC=12.0)\nFIN()\n";
    let third = "POURSUITE()\nTEST_TABLE(TABLE=T, NOM_PARA='X', VALE_CALC=12.0)\nFIN()\n";
    let (status, mess, err) = run_export(&dir, &[("case.comm", first), ("case.com1", second), ("case.com2", third)]);
    assert!(status.success(), "{err}\n{mess}");
    assert!(mess.contains("Continued in case.com1 (POURSUITE)"), "{mess}");
    assert_eq!(mess.matches(" OK ").count(), 2, "{mess}");
    assert!(mess.contains("DIAGNOSTIC JOB : OK"), "{mess}");
    // An error in a continuation is located in its own file.
    let bad = "POURSUITE()\ny = undefined_name + 1\n";
    let (status, _, err) = run_export(&dir, &[("case.comm", first), ("case.com1", bad)]);
    assert_eq!(status.code(), Some(2), "{err}");
    assert!(err.contains("case.com1:2:5: NameError: name 'undefined_name' is not defined"), "{err}");
}

#[test]
fn detruire_unbinds_the_names_of_a_concept() {
    let dir = scratch!("detruire");
    let src = "DEBUT()\nF = DEFI_CONSTANTE(VALE=3.0)\nG = F\nH = DEFI_CONSTANTE(VALE=1.0)\n\
               DETRUIRE(NOM=F, INFO=2)\nDETRUIRE(CONCEPT=_F(NOM=(H,)))\nz = G(0.0)\nFIN()\n";
    let (status, mess, err) = run_export(&dir, &[("case.comm", src)]);
    assert_eq!(status.code(), Some(2), "{mess}");
    assert!(mess.contains("DETRUIRE: F (fonction_sdaster) unbound: F, G"), "{mess}");
    assert!(err.contains("case.comm:7:5: NameError: name 'G' is not defined"), "{err}");
}

#[test]
fn defi_fichier_ties_units_to_files_of_the_run() {
    let dir = scratch!("defi_fichier");
    let src = "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='A', LISTE_R=(1.5, 2.5)))\n\
               u = DEFI_FICHIER(FICHIER='./REPE_OUT/t.txt', ACTION='ASSOCIER', TYPE='ASCII', ACCES='NEW')\n\
               IMPR_TABLE(TABLE=T, UNITE=u)\n\
               I1 = INFO_EXEC_ASTER(LISTE_INFO='ETAT_UNITE', UNITE=u)\n\
               TEST_TABLE(TABLE=I1, NOM_PARA='ETAT_UNITE', VALE_CALC_K='OUVERT')\n\
               DEFI_FICHIER(UNITE=u, ACTION='LIBERER')\n\
               DEFI_FICHIER(UNITE=33, FICHIER='REPE_OUT/t.txt', ACCES='OLD')\n\
               T2 = LIRE_TABLE(UNITE=33, FORMAT='TABLEAU')\n\
               TEST_TABLE(TABLE=T2, NOM_PARA='A', TYPE_TEST='SOMM', VALE_CALC=4.0)\n\
               I2 = INFO_EXEC_ASTER(LISTE_INFO='UNITE_LIBRE')\n\
               TEST_TABLE(TABLE=I2, NOM_PARA='UNITE_LIBRE', VALE_CALC_I=99)\n\
               I3 = INFO_EXEC_ASTER(LISTE_INFO='TEMPS_RESTANT')\n\
               TEST_TABLE(TABLE=I3, NOM_PARA='TEMPS_RESTANT', VALE_CALC=30.0, CRITERE='ABSOLU', TOLE_MACHINE=30.5)\n\
               FIN()\n";
    let (status, mess, err) = run_export(&dir, &[("case.comm", src)]);
    assert!(status.success(), "{err}\n{mess}");
    // 99, the largest free unit, went to u and is free again after LIBERER; the time left is within
    // the .export's 60 s.
    assert_eq!(mess.matches(" OK ").count(), 4, "{mess}");
    // Files outside the run's folder are refused by name.
    let out = "DEBUT()\nDEFI_FICHIER(UNITE=30, FICHIER='/tmp/elsewhere.txt')\nFIN()\n";
    let (status, _, err) = run_export(&dir, &[("case.comm", out)]);
    assert_eq!(status.code(), Some(2));
    assert!(err.contains("only files of the run's folder"), "{err}");
    let old = "DEBUT()\nDEFI_FICHIER(UNITE=30, FICHIER='absent.txt', ACCES='OLD')\nFIN()\n";
    let (status, _, err) = run_export(&dir, &[("case.comm", old)]);
    assert_eq!(status.code(), Some(2));
    assert!(err.contains("file 'absent.txt' does not exist (ACCES='OLD')"), "{err}");
}
