//! `aster suite` on a folder: the per-case table, the summary of what stops the cases (terminal,
//! stops.csv, suite.json) and the list of passing cases beside the JUnit report.

use crate::common::*;

#[test]
fn the_suite_summary_counts_what_stops_the_cases() {
    let dir = scratch!("suite");
    let cases = dir.join("cases");
    std::fs::create_dir_all(&cases).unwrap();
    let ok = "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='X', LISTE_R=(1.0,)))\n\
              TEST_TABLE(TABLE=T, NOM_PARA='X', VALE_CALC=1.0)\nFIN()\n";
    let unknown = "DEBUT()\nX = NOT_A_COMMAND(A=1)\nFIN()\n";
    for (name, text) in [("good", ok), ("bad1", unknown), ("bad2", unknown)] {
        std::fs::write(cases.join(format!("{name}.comm")), text).unwrap();
        std::fs::write(cases.join(format!("{name}.export")), format!("P time_limit 60\nF comm {name}.comm D 1\n"))
            .unwrap();
    }
    let out = dir.join("out");
    let o = aster().arg("suite").arg(&cases).arg("--out").arg(&out).arg("-q").output().unwrap();
    let (stdout, stderr) = text(&o);
    assert!(!o.status.success(), "two cases fail: {stdout}{stderr}");
    assert!(stdout.contains("3 cases: 1 OK"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("stops.csv")).unwrap();
    let row = csv.lines().find(|l| l.contains("NOT_A_COMMAND")).unwrap_or_else(|| panic!("{csv}"));
    assert!(row.contains(",2,") && row.contains("bad1 bad2"), "{row}");
    let json = std::fs::read_to_string(out.join("suite.json")).unwrap();
    assert!(json.contains("\"cases\": 3, \"ok\": 1"), "{json}");
    let passing = std::fs::read_to_string(out.join("passing.txt")).unwrap();
    assert!(passing.lines().any(|l| l.split_whitespace().collect::<Vec<_>>() == ["good", "1"]), "{passing}");
    assert!(out.join("junit.xml").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
