//! The saturated-HM cases of Code_Aster's 2025 corpus that run with every check OK, read unmodified in
//! place (`../shared/corpus/astest-2025`; skipped with a message where absent): KIT_HM with ELAS,
//! LIQU_SATU and HYDR_UTIL, beyond rung d of ../shared/astest. wtnv113a, wtnv114a and wtnv114h read their
//! mesh in Code_Aster's text format (LIRE_MAILLAGE FORMAT='ASTER'). With X-FEM interfaces and coupled
//! flow in the enriched elements: wtnv114i (3D_HM, FLUX_THM_REP on faces the interface crosses), wtnv144b
//! (Terzaghi across an interface that cuts the loaded top, a pressure function jumping there) and wtnv144d
//! (its 3D_HM version); wtnv143d (3D_HM on PENTA15 parents). Each with its number of OK lines.

use crate::common::*;

const CASES: [(&str, usize); 9] = [
    ("wtnv113a", 24),
    ("wtnv113c", 24),
    ("wtnv114a", 20),
    ("wtnv114h", 8),
    ("wtna113a", 4),
    ("wtnv114i", 8),
    ("wtnv144b", 166),
    ("wtnv144d", 66),
    ("wtnv143d", 16),
];

#[test]
fn corpus_hm_cases_pass() {
    run_corpus_cases(&scratch!("corpus"), &CASES);
}

/// A compressible liquid (THM_LIQU UN_SUR_K = 0.5e-9) on D_PLAN_HMS and D_PLAN_HM_SI, PRE1 prescribed by
/// AFFE_CHAR_CINE: Code_Aster accepts each step's prediction (its relative criterion mixes the mechanical
/// reactions with the hydraulic rows), so its values carry its tangent of the mass content (ρb, ρ(φ/K_w +
/// c_s)); with the exact tangent they ended 2e-5 away (NOOK at t = 1 s and 10 s).
#[test]
fn compressible_liquid_predictions_carry_code_asters_tangent() {
    run_corpus_cases(&scratch!("corpus_compressible"), &[("wtnp129a", 26), ("wtnp129c", 52)]);
}

/// wtnl100b on 3D_HMS elements (the corpus has it on 3D_HMD): SIGM_ELNO is Code_Aster's fit through every
/// point of the FPG8NOS family, the vertex points holding the effective stress of a Gauss point, and
/// SIEQ_ELNO follows. At NO83 of MA16, first instant, Code_Aster's NON_REGRESSION VMIS is 0.4085 (we
/// printed 1.0 when the fit took the Gauss points only).
#[test]
fn hms_stresses_at_the_nodes_are_code_asters() {
    let dir = root().join("../shared/corpus/astest-2025");
    if !dir.is_dir() {
        println!("SKIP: {} is absent", dir.display());
        return;
    }
    let out = scratch!("wtnl100b_hms");
    let src = std::fs::read_to_string(dir.join("wtnl100b.comm")).unwrap().replace("\"3D_HMD\"", "\"3D_HMS\"");
    std::fs::write(out.join("hms.comm"), src).unwrap();
    let mesh = dir.join("wtnl100b.mmed");
    let opts = aster::runner::RunOptions {
        out_dir: Some(out.join("out")),
        units: vec![(20, mesh, aster::runner::export::Dir::In)],
        echo: false,
    };
    let o = aster::runner::run_comm(&out.join("hms.comm"), &opts);
    let mess = std::fs::read_to_string(o.mess.expect("a message file")).unwrap();
    let vmis = mess
        .split(" ---- ")
        .find(|b| b.starts_with("RESULTAT RESU1 NUME_ORDRE 1 NOM_CHAM SIEQ_ELNO NOM_CMP VMIS GROUP_NO NO83"))
        .and_then(|b| b.lines().find(|l| l.contains("NON_REGRESSION   VMIS")))
        .and_then(|l| l.split_whitespace().nth(4))
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no VMIS check at NO83:\n{mess}"));
    assert!((vmis - 0.4085).abs() < 1e-4, "VMIS at NO83: {vmis}");
}
