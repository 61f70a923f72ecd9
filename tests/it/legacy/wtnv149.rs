//! WTNV149 end to end (issue 5): the original command files of
//! `../shared/astest` run unmodified (read in place), every check line OK;
//! the run log names the eliminated hydraulics; the same scene with
//! MODELISATION='D_PLAN' solves exactly as many unknowns; the interface
//! measures integrated on the facets equal the exact lengths and areas.
//! Every test prints a message and passes when `../shared` is absent.

use crate::common::*;
use aster::runner::{self, export::Dir, RunOptions};
use std::path::Path;

/// Run an export; returns (OK count, NOOK count, skipped, diagnostic, message file text).
fn run(export: &Path, tag: &str) -> (usize, usize, usize, String, String) {
    let out = scratch!(tag);
    let o = runner::run_export(export, &RunOptions { out_dir: Some(out.clone()), units: Vec::new(), echo: false });
    let mess = o.mess.as_ref().and_then(|p| std::fs::read_to_string(p).ok()).unwrap_or_default();
    let ok = o.records.iter().filter(|r| r.ok == Some(true)).count();
    let nook = o.records.iter().filter(|r| r.ok == Some(false)).count();
    let skipped = o.records.iter().filter(|r| r.ok.is_none()).count();
    let _ = std::fs::remove_dir_all(&out);
    (ok, nook, skipped, o.diagnostic.to_string(), mess)
}

/// The real numbers after `label` in the message file, in order.
fn numbers_after(mess: &str, label: &str) -> Vec<f64> {
    mess.match_indices(label)
        .map(|(i, _)| {
            let rest = &mess[i + label.len()..];
            let tok: String = rest
                .trim_start()
                .chars()
                .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+'))
                .collect();
            tok.parse().unwrap_or_else(|_| panic!("no number after {label}: {rest:.40}"))
        })
        .collect()
}

#[test]
fn wtnv149a_all_checks_ok_and_hydraulics_eliminated() {
    let Some(e) = astest("wtnv149a.export") else { return };
    let (ok, nook, skipped, diag, mess) = run(&e, "a");
    assert_eq!((ok, nook, skipped, diag.as_str()), (12, 0, 0, "OK"), "{mess}");
    assert!(mess.contains("eliminated: hydraulics"), "{mess}");
    assert!(mess.contains("fracture p_f/q+/q- on 9 packets"), "{mess}");
    // Facet lengths: FISS1 crosses the whole block, FISS2 stops at the junction (−0.4, 0).
    let m = numbers_after(&mess, "interface measure");
    let s = 1.25f64.sqrt();
    assert_eq!(m.len(), 2, "{mess}");
    assert!((m[0] - 10.0 * s).abs() < 1e-10 * m[0], "{m:?}");
    assert!((m[1] - 5.4 * s).abs() < 1e-10 * m[1], "{m:?}");
}

#[test]
fn wtnv149b_all_checks_ok() {
    let Some(e) = astest("wtnv149b.export") else { return };
    let (ok, nook, skipped, diag, mess) = run(&e, "b");
    // 12 ANALYTIQUE + 12 NON_REGRESSION lines: Code_Aster's own VALE_CALC
    // are reproduced (same 3-point facet rule, same sub-cells).
    assert_eq!((ok, nook, skipped, diag.as_str()), (24, 0, 0, "OK"), "{mess}");
    assert!(mess.contains("null mode : no condition on DY anywhere"), "{mess}");
    let m = numbers_after(&mess, "interface measure");
    let s = 1.25f64.sqrt();
    assert!((m[0] - 2.0 * 10.0 * s).abs() < 1e-10 * m[0], "{m:?}");
    assert!((m[1] - 2.0 * 5.4 * s).abs() < 1e-10 * m[1], "{m:?}");
}

/// wtnv149a with MODELISATION='D_PLAN': no hydraulic loads, ELAS behaviour.
fn d_plan_variant(src: &str) -> String {
    let mut out = String::new();
    let mut skip = false;
    for line in src.lines() {
        let t = line.trim_start();
        if t.starts_with("HYDR=") || t.starts_with("HYDR2=") {
            skip = true;
        }
        if skip {
            if t.ends_with(");") {
                skip = false;
            }
            continue;
        }
        if t.starts_with("_F(CHARGE = HYDR") || t.starts_with("SCHEMA_THM") {
            continue;
        }
        out.push_str(&line.replace("'D_PLAN_HM'", "'D_PLAN'"));
        out.push('\n');
    }
    let start = out.find("COMPORTEMENT   = _F(RELATION       = 'KIT_HM'").expect("the KIT_HM behaviour");
    let end = start + out[start..].find("NEWTON").expect("NEWTON after COMPORTEMENT");
    out.replace_range(start..end, "COMPORTEMENT = _F(RELATION='ELAS'),\n                    ");
    out
}

fn unknowns(mess: &str) -> (f64, f64) {
    let n = numbers_after(mess, "unknowns  :");
    let solved = numbers_after(mess, "interface λ/w/μ),");
    (n[0], solved[0])
}

#[test]
fn wtnv149a_solves_as_many_unknowns_as_the_d_plan_scene() {
    let (Some(comm), Some(mesh)) = (astest("wtnv149a.comm"), astest("wtnv145a.mmed")) else { return };
    let (_, _, _, diag, hm) = run(&astest("wtnv149a.export").unwrap(), "hm");
    assert_eq!(diag, "OK", "{hm}");
    let src = std::fs::read_to_string(&comm).unwrap();
    let out = scratch!("dplan");
    let file = out.join("wtnv149a_dplan.comm");
    std::fs::write(&file, d_plan_variant(&src)).unwrap();
    let o = runner::run_comm(
        &file,
        &RunOptions {
            out_dir: Some(out.clone()),
            units: vec![(20, mesh, Dir::In), (80, out.join("r.rmed"), Dir::Out)],
            echo: false,
        },
    );
    let mess = std::fs::read_to_string(o.mess.as_ref().unwrap()).unwrap();
    assert_eq!(o.diagnostic, "OK", "{mess}");
    assert!(!mess.contains("eliminated: hydraulics"), "{mess}");
    assert_eq!(unknowns(&hm), unknowns(&mess));
    let _ = std::fs::remove_dir_all(&out);
}
