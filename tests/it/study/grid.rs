//! `aster study` on Lamé's thick cylinder (comm/lame_2d.comm) over h refinement and the cell degree: the
//! CSV has one row per variant with its measures, the error falls under refinement at the rates theory
//! gives, and the plots are written as SVG files.

use crate::common::*;

/// The columns of a CSV row by name.
fn field<'a>(head: &[&str], row: &'a [&'a str], name: &str) -> &'a str {
    let i = head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    row[i]
}

#[test]
fn a_small_grid_of_the_lame_scene() {
    let out = scratch!("lame");
    let o = aster()
        .args(["study", root().join("comm/lame_2d.comm").to_str().unwrap()])
        .args(["--mesh", "20=ring --cell {CELL} --n {N},{N} --radii 1,2"])
        .args(["--set", "CELL=QUAD4,QUAD8", "--set", "N=2,4,8", "-j", "2", "--quiet", "--title", "Lamé 2D"])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stdout}\n{stderr}");
    let csv = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    let head: Vec<&str> = lines[0].split(',').collect();
    let rows: Vec<Vec<&str>> = lines[1..].iter().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 6, "{csv}");
    for r in &rows {
        // Every run ran to its end and was measured.
        assert!(!field(&head, r, "diagnostic").starts_with("<F>"), "{csv}");
        for col in ["wall_s", "peak_mib", "unknowns", "err_DEPL_RELA", "err_ENER_RELA"] {
            let v: f64 = field(&head, r, col).parse().unwrap_or_else(|_| panic!("{col} of {r:?}"));
            assert!(v > 0.0, "{col} of {r:?}");
        }
        // The .mess gives command times to the millisecond: a small solve may take 0.000 s.
        let t: f64 = field(&head, r, "t_MECA_STATIQUE").parse().unwrap();
        assert!(t >= 0.0);
    }
    // Under refinement the errors fall, by 2^(p+1) (L2) and 2^p (energy) per halving of h for cells of
    // degree p, to within a factor 2^0.3 on these coarse meshes.
    for (cell, p) in [("QUAD4", 1.0), ("QUAD8", 2.0)] {
        let of = |n: &str, col: &str| -> f64 {
            let r = rows.iter().find(|r| field(&head, r, "CELL") == cell && field(&head, r, "N") == n).unwrap();
            field(&head, r, col).parse().unwrap()
        };
        for (col, order) in [("err_DEPL_RELA", p + 1.0), ("err_ENER_RELA", p)] {
            let measured = (of("4", col) / of("8", col)).log2();
            assert!((measured - order).abs() < 0.3, "{cell} {col}: order {measured}, theory {order}");
            assert!(of("2", col) > of("4", col), "{cell} {col}");
        }
        assert!(of("8", "unknowns") > of("4", "unknowns"));
    }
    let md = std::fs::read_to_string(out.join("study.md")).unwrap();
    assert!(md.contains("| CELL | N | unknowns |") && md.contains("Pareto front of DEPL_RELA"), "{md}");
    for f in ["DEPL_RELA_vs_time.svg", "DEPL_RELA_vs_unknowns.svg", "ENER_RELA_vs_time.svg", "check_vs_time.svg"] {
        let svg = std::fs::read_to_string(out.join(f)).unwrap_or_default();
        assert!(svg.starts_with("<svg") && svg.contains("Pareto front") && svg.contains("N varies"), "{f}");
    }
    let _ = std::fs::remove_dir_all(&out);
}
