//! Thermal cases of Code_Aster's 2025 corpus (../shared/corpus/astest-2025, read in place), run unmodified:
//! each ends OK with exactly its number of OK check lines. Steady and transient THER_LINEAIRE on PLAN,
//! AXIS and 3D cells (linear and quadratic), THER_NON_LINE with THER_NL materials, FLUX_NL, RAYONNEMENT,
//! SOUR_NL and ECHANGE, ETAT_INIT from a field or a result, RESULTAT continued, CALC_CHAMP's FLUX_*.
use crate::common::run_corpus_cases;

const CASES: [(&str, usize); 16] = [
    ("ttll01a", 16),
    ("ttll01g", 32),
    ("ttll100b", 32),
    ("ttlv01a", 100),
    ("ttlv100a", 32),
    ("tpla04a", 48),
    ("tpll01d", 14),
    ("tplp303d", 48),
    ("tplv305b", 136),
    ("tpnv01a", 148),
    ("tpnl300b", 18),
    ("tpna300c", 60),
    ("ttnl02c", 32),
    ("ttnl100a", 14),
    ("ttnl302b", 160),
    ("ttnl303a", 77),
];

/// THER_NON_LINE without NEWTON (REAC_ITER=0: the tangent of each step's start serves all its corrections)
/// on nonlinear conduction: Code_Aster's non-regression values, checked to 1e-6 absolute, are those of its
/// modified Newton stopped at RESI_GLOB_RELA; a full Newton ends ~1.2e-6 away (the NOOK these cases had).
const MODIFIED_NEWTON: [(&str, usize); 3] = [("ttnl303d", 192), ("tpna300d", 102), ("ttnl302e", 440)];

#[test]
fn corpus_thermal_modified_newton_matches_code_aster() {
    run_corpus_cases(&scratch!("corpus_reac"), &MODIFIED_NEWTON);
}

#[test]
fn corpus_thermal_cases_pass() {
    run_corpus_cases(&scratch!("corpus"), &CASES);
}

/// Orthotropic conduction in the local frames of AFFE_CARA_ELEM MASSIF: nautical angles on PLAN, AXIS and
/// 3D cells (tpla07a: AXIS, with ETHE_ELEM; ttlp303c: a frame at −15°), a cylindrical frame about a 3D
/// axis (tplv103b: ORIG_AXE + ANGL_AXE), THER_NL_ORTH with λ_L(T), λ_T(T), λ_N(T) (ttnl304b).
const ORTHOTROPIC: [(&str, usize); 8] = [
    ("tpla07a", 16),
    ("tpll100b", 14),
    ("tplp02a", 58),
    ("tplv103b", 6),
    ("ttlp300a", 8),
    ("ttlp303c", 32),
    ("ttlp304a", 36),
    ("ttnl304b", 24),
];

#[test]
fn corpus_orthotropic_cases_pass() {
    run_corpus_cases(&scratch!("corpus_ortho"), &ORTHOTROPIC);
}
