//! Materials: DEFI_MATERIAU (material parameters) and AFFE_MATERIAU (assignment to the mesh).

use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

pub fn commands() -> Vec<Command> {
    vec![defi_materiau(), affe_materiau(), affe_cara_elem()]
}

/// A function of one or more parameters.
const FUNC: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule];
/// A function of one parameter (thermal expansion coefficients).
const FUNC1: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Formule];

/// A real parameter.
fn r(name: &'static str) -> Simp {
    simp(name).r()
}

/// A parameter given as a function.
fn f(name: &'static str) -> Simp {
    simp(name).co(FUNC)
}

/// Optional real parameters.
fn reals(names: &[&'static str]) -> Vec<Entry> {
    names.iter().map(|n| Entry::from(r(n))).collect()
}

/// Optional function parameters.
fn funcs(names: &[&'static str]) -> Vec<Entry> {
    names.iter().map(|n| Entry::from(f(n))).collect()
}

/// Every keyword of the list is required (as a rule, for conditional requirements).
fn required(names: &[&'static str]) -> Vec<Rule> {
    names.iter().map(|n| au_moins_un(&[*n])).collect()
}

/// The THM coupling laws.
const COMP_THM: &[&str] =
    &["LIQU_SATU", "LIQU_GAZ", "GAZ", "LIQU_GAZ_ATM", "LIQU_VAPE_GAZ", "LIQU_VAPE", "LIQU_AD_GAZ_VAPE", "LIQU_AD_GAZ"];

fn elasticity() -> Vec<Entry> {
    kws![
        fact(
            "ELAS",
            kws![
                r("E").val_min(0.0),
                r("NU").val_min(-1.0).val_max(0.5),
                r("K").val_min(0.0),
                r("MU").val_min(0.0),
                r("CELE_P").val_min(0.0),
                r("CELE_S").val_min(0.0),
                r("RHO"),
                r("ALPHA"),
                r("AMOR_ALPHA"),
                r("AMOR_BETA"),
                r("AMOR_HYST"),
                r("K_DESSIC").d(0.0),
                r("B_ENDOGE").d(0.0),
                r("LONG_CARA").val_min(0.0),
                r("COEF_AMOR").d(1.0),
            ]
        )
        .rules(vec![
            un_parmi(&["E", "K", "CELE_P"]),
            ensemble(&["E", "NU"]),
            ensemble(&["K", "MU"]),
            ensemble(&["CELE_P", "CELE_S"]),
            present_present("CELE_P", &["RHO"]),
        ]),
        fact(
            "ELAS_FO",
            kws![
                f("E").o(),
                f("NU").o(),
                f("RHO"),
                r("TEMP_DEF_ALPHA"),
                r("PRECISION").d(1.0),
                simp("ALPHA").co(FUNC1),
                f("AMOR_ALPHA"),
                f("AMOR_BETA"),
                f("AMOR_HYST"),
                r("K_DESSIC").d(0.0),
                r("B_ENDOGE").d(0.0),
                r("LONG_CARA").val_min(0.0),
                r("COEF_AMOR").d(1.0),
            ]
        )
        .rules(vec![present_present("ALPHA", &["TEMP_DEF_ALPHA"])]),
        fact(
            "ELAS_ISTR",
            kws![
                r("E_L").o(),
                r("E_N").o(),
                r("NU_LT").o(),
                r("NU_LN").o(),
                r("G_LN").o(),
                r("RHO"),
                r("ALPHA_L").d(0.0),
                r("ALPHA_N").d(0.0),
            ]
        ),
        fact(
            "ELAS_ISTR_FO",
            kws![
                f("E_L").o(),
                f("E_N").o(),
                f("NU_LT").o(),
                f("NU_LN").o(),
                f("G_LN").o(),
                f("RHO"),
                r("TEMP_DEF_ALPHA"),
                r("PRECISION").d(1.0),
                simp("ALPHA_L").co(FUNC1),
                simp("ALPHA_N").co(FUNC1),
            ]
        )
        .rules(vec![present_present("ALPHA_L", &["TEMP_DEF_ALPHA"]), present_present("ALPHA_N", &["TEMP_DEF_ALPHA"]),]),
        fact(
            "ELAS_ORTH",
            kws![
                r("E_L").o(),
                r("E_T").o(),
                r("E_N"),
                r("NU_LT").o(),
                r("NU_LN"),
                r("NU_TN"),
                r("G_LT").o(),
                r("G_LN"),
                r("G_TN"),
                r("RHO"),
                r("ALPHA_L").d(0.0),
                r("ALPHA_T").d(0.0),
                r("ALPHA_N").d(0.0),
                r("XT").d(1.0),
                r("XC").d(1.0),
                r("YT").d(1.0),
                r("YC").d(1.0),
                r("S_LT").d(1.0),
                r("AMOR_ALPHA"),
                r("AMOR_BETA"),
                r("AMOR_HYST"),
            ]
        ),
        fact(
            "ELAS_ORTH_FO",
            kws![
                f("E_L").o(),
                f("E_T").o(),
                f("E_N").o(),
                f("NU_LT").o(),
                f("NU_LN").o(),
                f("NU_TN").o(),
                f("G_LT").o(),
                f("G_LN").o(),
                f("G_TN").o(),
                f("RHO"),
                r("TEMP_DEF_ALPHA"),
                r("PRECISION").d(1.0),
                simp("ALPHA_L").co(FUNC1),
                simp("ALPHA_T").co(FUNC1),
                simp("ALPHA_N").co(FUNC1),
                f("AMOR_ALPHA"),
                f("AMOR_BETA"),
                f("AMOR_HYST"),
                r("K_DESSIC").d(0.0),
                r("B_ENDOGE").d(0.0),
            ]
        )
        .rules(vec![
            present_present("ALPHA_L", &["TEMP_DEF_ALPHA"]),
            present_present("ALPHA_N", &["TEMP_DEF_ALPHA"]),
            present_present("ALPHA_T", &["TEMP_DEF_ALPHA"]),
        ]),
        fact(
            "ELAS_HYPER",
            kws![
                r("C10").o(),
                r("C01").d(0.0),
                r("C20").d(0.0),
                r("K"),
                r("NU").val_min(-1.0).val_max(0.5),
                r("RHO").d(0.0),
            ]
        )
        .rules(vec![un_parmi(&["K", "NU"])]),
    ]
}

fn plasticity() -> Vec<Entry> {
    kws![
        fact("TRACTION", kws![f("SIGM").o()]),
        fact("ECRO_LINE", kws![r("D_SIGM_EPSI").o(), r("SY").o(), r("SIGM_LIM"), r("EPSI_LIM")]),
        fact("ECRO_LINE_FO", kws![f("D_SIGM_EPSI").o(), f("SY").o(), f("SIGM_LIM"), f("EPSI_LIM")]),
        fact("ECRO_PUIS", kws![r("SY").o(), r("A_PUIS").o().val_min(0.0), r("N_PUIS").o().val_min(1.0e-6)]),
        fact("ECRO_PUIS_FO", kws![f("SY").o(), f("A_PUIS").o(), f("N_PUIS").o()]),
        fact("PRAGER", kws![r("C").o()]),
        fact("PRAGER_FO", kws![f("C").o()]),
        fact("NORTON", kws![r("K").o(), r("N").o().val_min(1.0)]),
        fact("NORTON_FO", kws![f("K").o(), f("N").o()]),
        fact("LEMAITRE", kws![r("N").o(), r("UN_SUR_K").o(), r("UN_SUR_M").d(0.0)]),
        fact("LEMAITRE_FO", kws![f("N").o(), f("UN_SUR_K").o(), f("UN_SUR_M").o()]),
        fact(
            "CIN1_CHAB",
            kws![
                r("R_0").o(),
                r("R_I"),
                r("B").d(0.0),
                r("C_I").o(),
                r("K").d(1.0),
                r("W").d(0.0),
                r("G_0").o(),
                r("A_I").d(1.0),
            ]
        ),
        fact(
            "CIN2_CHAB",
            kws![
                r("R_0").o(),
                r("R_I"),
                r("B").d(0.0),
                r("C1_I").o(),
                r("C2_I").o(),
                r("K").d(1.0),
                r("W").d(0.0),
                r("G1_0").o(),
                r("G2_0").o(),
                r("A_I").d(1.0),
            ]
        ),
        fact(
            "DRUCK_PRAGER",
            kws![
                r("ALPHA").o(),
                r("SY").o(),
                simp("ECROUISSAGE").txt().o().one_of(&["LINEAIRE", "PARABOLIQUE", "EXPONENTIEL"]),
                bloc(eq("ECROUISSAGE", "LINEAIRE"), kws![r("H").o(), r("P_ULTM").o()]),
                bloc(eq("ECROUISSAGE", "PARABOLIQUE"), kws![r("SY_ULTM").o(), r("P_ULTM").o()]),
                bloc(eq("ECROUISSAGE", "EXPONENTIEL"), kws![r("P_C").o(), r("SY_ULTM").o(), r("DILAT_ULTM").d(0.0)]),
                r("DILAT").d(0.0),
            ]
        ),
        fact(
            "NON_LOCAL",
            kws![
                r("LONG_CARA"),
                r("C_GRAD_VARI"),
                r("PENA_LAGR"),
                r("PENA_LAGR_INCO").d(0.0),
                r("C_GONF"),
                r("COEF_RIGI_MINI"),
            ]
        )
        .rules(vec![au_moins_un(&["LONG_CARA", "C_GONF", "C_GRAD_VARI", "PENA_LAGR"])]),
    ]
}

fn cinematique(default: &'static str) -> Simp {
    simp("CINEMATIQUE").txt().d(default).one_of(&["UNILATER", "GLIS_1D", "GLIS_2D"])
}

/// Cohesive and fracture laws.
fn fracture() -> Vec<Entry> {
    kws![
        fact(
            "RUPT_FRAG",
            kws![
                r("GC").o(),
                r("SIGM_C"),
                r("PENA_ADHERENCE").val_min(1.0e-12).val_max(1.0),
                r("PENA_CONTACT").d(1.0),
                r("PENA_LAGR").d(1.0e2).val_min(1.01),
                r("RIGI_GLIS").d(1.0e1),
                cinematique("UNILATER"),
            ]
        ),
        fact(
            "RUPT_FRAG_FO",
            kws![
                f("GC").o(),
                f("SIGM_C"),
                f("PENA_ADHERENCE"),
                r("PENA_CONTACT").d(1.0),
                r("PENA_LAGR").d(1.0e2).val_min(1.01),
                r("RIGI_GLIS").d(1.0e1),
                cinematique("UNILATER"),
            ]
        ),
        fact(
            "CZM_LAB_MIX",
            kws![
                r("SIGM_C").o().val_min(1.0e-100),
                r("GLIS_C").o().val_min(1.0e-100),
                r("ALPHA").d(0.5).val_min(1.0e-3),
                r("BETA").d(1.0).val_min(0.0),
                r("PENA_LAGR").d(100.0).val_min(1.01),
                cinematique("GLIS_1D"),
            ]
        ),
        fact(
            "RUPT_DUCT",
            kws![
                r("GC").o(),
                r("SIGM_C").o(),
                r("COEF_EXTR").o().val_min(0.0).val_max(9.99e-1),
                r("COEF_PLAS").o().val_min(0.0).val_max(9.99e-1),
                r("PENA_LAGR").d(1.0e2).val_min(1.01),
                r("RIGI_GLIS").d(1.0e1),
            ]
        ),
        fact("THM_RUPT", kws![r("OUV_FICT").o(), r("UN_SUR_N").d(0.0)]),
    ]
}

fn thermal() -> Vec<Entry> {
    kws![
        fact("THER", kws![r("LAMBDA").o(), r("RHO_CP")]),
        fact("THER_FO", kws![f("LAMBDA").o(), f("RHO_CP")]),
        fact("THER_NL", kws![f("LAMBDA").o(), f("BETA"), f("RHO_CP")]).rules(vec![un_parmi(&["BETA", "RHO_CP"])]),
        fact("THER_ORTH", kws![r("LAMBDA_L").o(), r("LAMBDA_T").o(), r("LAMBDA_N"), r("RHO_CP")]),
        fact("THER_NL_ORTH", kws![f("LAMBDA_L").o(), f("LAMBDA_T").o(), f("LAMBDA_N"), f("BETA"), f("RHO_CP")])
            .rules(vec![un_parmi(&["BETA", "RHO_CP"])]),
    ]
}

/// THM_DIFFU: the porous medium (one schema for every coupling law; the
/// parameters each law requires are enforced by rules).
fn thm_diffu() -> Fact {
    let mut e = kws![r("RHO").o(), r("PESA_X").o(), r("PESA_Y").o(), r("PESA_Z").o()];
    e.extend(reals(&[
        "R_GAZ",
        "BIOT_COEF",
        "BIOT_L",
        "BIOT_N",
        "BIOT_T",
        "VG_N",
        "VG_SR",
        "VG_PR",
        "VG_SMAX",
        "VG_SATUR",
        "VG_PENTR",
        "A0",
        "SHUTTLE",
        "CP",
        "LAMB_CT",
        "LAMB_C_L",
        "LAMB_C_N",
        "LAMB_C_T",
        "EMMAG",
    ]));
    e.extend(funcs(&[
        "SATU_PRES",
        "D_SATU_PRES",
        "PERM_LIQU",
        "D_PERM_LIQU_SATU",
        "PERM_GAZ",
        "D_PERM_SATU_GAZ",
        "D_PERM_PRES_GAZ",
        "FICKV_T",
        "FICKV_PV",
        "FICKV_PG",
        "FICKV_S",
        "D_FV_T",
        "D_FV_PG",
        "FICKA_T",
        "FICKA_PA",
        "FICKA_PL",
        "FICKA_S",
        "D_FA_T",
        "PESA_MULT",
        "PERM_IN",
        "PERMIN_L",
        "PERMIN_N",
        "PERMIN_T",
        "PERM_END",
        "LAMB_PHI",
        "D_LB_PHI",
        "LAMB_T",
        "LAMB_TL",
        "LAMB_TN",
        "LAMB_TT",
        "D_LB_T",
        "D_LB_TL",
        "D_LB_TN",
        "D_LB_TT",
        "LAMB_S",
        "D_LB_S",
    ]));
    e.extend(kws![simp("EPAI").co(FUNC1), simp("S_BJH").co(FUNC1), simp("W_BJH").co(FUNC1)]);
    // Unsaturated laws: a saturation model (tabulated or Van Genuchten) and the gas constant.
    let unsaturated = ["LIQU_GAZ", "LIQU_VAPE_GAZ", "LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"];
    let mut unsat_rules = vec![
        ensemble(&[
            "SATU_PRES",
            "D_SATU_PRES",
            "PERM_LIQU",
            "D_PERM_LIQU_SATU",
            "PERM_GAZ",
            "D_PERM_SATU_GAZ",
            "D_PERM_PRES_GAZ",
        ]),
        ensemble(&["VG_N", "VG_SR", "VG_PR", "VG_SMAX", "VG_SATUR"]),
        un_parmi(&["VG_N", "SATU_PRES"]),
    ];
    unsat_rules.extend(required(&["R_GAZ"]));
    e.extend(kws![
        bloc(is_in("COMP_THM", &unsaturated), kws![]).rules(unsat_rules),
        bloc(eq("COMP_THM", "GAZ"), kws![]).rules(required(&["R_GAZ"])),
        bloc(eq("COMP_THM", "LIQU_GAZ_ATM"), kws![]).rules(required(&[
            "SATU_PRES",
            "D_SATU_PRES",
            "PERM_LIQU",
            "D_PERM_LIQU_SATU"
        ])),
        bloc(is_in("COMP_THM", &["LIQU_VAPE_GAZ", "LIQU_AD_GAZ_VAPE"]), kws![]).rules(required(&["FICKV_T"])),
        bloc(is_in("COMP_THM", &["LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"]), kws![]).rules(required(&["FICKA_T"])),
    ]);
    fact("THM_DIFFU", e).rules(vec![
        exclus(&["BIOT_COEF", "BIOT_N"]),
        present_present("BIOT_N", &["BIOT_L"]),
        present_present("BIOT_T", &["BIOT_L", "BIOT_N"]),
        exclus(&["PERM_IN", "PERM_END", "PERMIN_L"]),
        present_absent("PERMIN_N", &["PERMIN_T"]),
        present_present("PERMIN_N", &["PERMIN_L"]),
        present_present("PERMIN_T", &["PERMIN_L"]),
        exclus(&["LAMB_T", "LAMB_TL"]),
        present_absent("LAMB_TN", &["LAMB_TT"]),
        present_present("LAMB_TN", &["LAMB_TL"]),
        present_present("LAMB_TT", &["LAMB_TL"]),
        exclus(&["D_LB_T", "D_LB_TL"]),
        present_absent("D_LB_TN", &["D_LB_TT"]),
        present_present("D_LB_TN", &["D_LB_TL"]),
        exclus(&["LAMB_CT", "LAMB_C_L"]),
        present_absent("LAMB_C_N", &["LAMB_C_T"]),
        present_present("LAMB_C_N", &["LAMB_C_L"]),
        present_present("LAMB_C_T", &["LAMB_C_L"]),
        exclus(&["PERMIN_L", "BIOT_COEF"]),
        exclus(&["PERMIN_L", "LAMB_T"]),
        present_present("BIOT_L", &["PERMIN_L"]),
        present_present("BIOT_T", &["PERMIN_T"]),
        present_present("LAMB_TN", &["PERMIN_N"]),
        present_present("LAMB_TL", &["PERMIN_L"]),
        present_present("LAMB_TT", &["PERMIN_T"]),
        ensemble(&["A0", "SHUTTLE", "EPAI", "S_BJH", "W_BJH"]),
    ])
}

/// The THM coupling law and its data.
fn thm() -> Vec<Entry> {
    let with_gas = ["LIQU_GAZ", "LIQU_VAPE_GAZ", "LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"];
    let not_gas =
        ["LIQU_SATU", "LIQU_GAZ", "LIQU_GAZ_ATM", "LIQU_VAPE_GAZ", "LIQU_VAPE", "LIQU_AD_GAZ_VAPE", "LIQU_AD_GAZ"];
    kws![
        simp("COMP_THM").txt().one_of(COMP_THM),
        bloc(
            present("COMP_THM"),
            kws![
                fact(
                    "THM_INIT",
                    kws![
                        r("PRE1").d(0.0),
                        bloc(is_in("COMP_THM", &with_gas), kws![r("PRE2").d(0.0)]),
                        bloc(is_in("COMP_THM", &["LIQU_SATU", "GAZ", "LIQU_GAZ_ATM", "LIQU_VAPE"]), kws![r("PRE2")]),
                        r("PORO").o(),
                        r("PRES_VAPE"),
                        r("TEMP").d(0.0),
                        r("DEGR_SATU"),
                        bloc(is_in("COMP_THM", &["LIQU_VAPE_GAZ", "LIQU_AD_GAZ_VAPE"]), kws![])
                            .rules(required(&["PRES_VAPE"])),
                    ]
                ),
                thm_diffu(),
                fact(
                    "THM_LIQU",
                    kws![
                        r("RHO"),
                        r("UN_SUR_K"),
                        f("VISC"),
                        f("D_VISC_TEMP"),
                        f("ALPHA"),
                        r("CP"),
                        bloc(eq("COMP_THM", "GAZ"), kws![r("COEF_HENRY")]),
                        bloc(is_in("COMP_THM", &not_gas), kws![]).rules(required(&[
                            "RHO",
                            "UN_SUR_K",
                            "VISC",
                            "D_VISC_TEMP"
                        ])),
                    ]
                ),
                fact(
                    "THM_GAZ",
                    kws![
                        r("MASS_MOL"),
                        f("VISC"),
                        f("D_VISC_TEMP"),
                        r("CP"),
                        bloc(is_in("COMP_THM", &["LIQU_GAZ", "GAZ", "LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"]), kws![])
                            .rules(required(&["MASS_MOL", "VISC", "D_VISC_TEMP"])),
                    ]
                ),
                fact(
                    "THM_VAPE_GAZ",
                    kws![
                        r("MASS_MOL"),
                        r("CP"),
                        f("VISC"),
                        f("D_VISC_TEMP"),
                        bloc(is_in("COMP_THM", &["LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"]), kws![]).rules(required(&[
                            "MASS_MOL",
                            "CP",
                            "VISC",
                            "D_VISC_TEMP"
                        ])),
                    ]
                ),
            ]
        ),
        bloc(
            is_in("COMP_THM", &["LIQU_AD_GAZ", "LIQU_AD_GAZ_VAPE"]),
            kws![fact("THM_AIR_DISS", kws![r("CP").o(), f("COEF_HENRY").o()])]
        ),
        // The data each coupling law requires.
        bloc(eq("COMP_THM", "LIQU_SATU"), kws![])
            .rules(vec![present_present("COMP_THM", &["THM_INIT", "THM_DIFFU", "THM_LIQU"])]),
        bloc(is_in("COMP_THM", &["LIQU_GAZ", "LIQU_GAZ_ATM"]), kws![])
            .rules(vec![present_present("COMP_THM", &["THM_INIT", "THM_DIFFU", "THM_LIQU", "THM_GAZ"])]),
        bloc(eq("COMP_THM", "GAZ"), kws![])
            .rules(vec![present_present("COMP_THM", &["THM_INIT", "THM_DIFFU", "THM_GAZ"])]),
        bloc(eq("COMP_THM", "LIQU_VAPE"), kws![])
            .rules(vec![present_present("COMP_THM", &["THM_INIT", "THM_DIFFU", "THM_LIQU", "THM_VAPE_GAZ"])]),
        bloc(eq("COMP_THM", "LIQU_VAPE_GAZ"), kws![]).rules(vec![present_present(
            "COMP_THM",
            &["THM_INIT", "THM_DIFFU", "THM_LIQU", "THM_GAZ", "THM_VAPE_GAZ"]
        )]),
        bloc(eq("COMP_THM", "LIQU_AD_GAZ"), kws![]).rules(vec![present_present(
            "COMP_THM",
            &["THM_INIT", "THM_DIFFU", "THM_LIQU", "THM_GAZ", "THM_AIR_DISS"]
        )]),
        bloc(eq("COMP_THM", "LIQU_AD_GAZ_VAPE"), kws![]).rules(vec![present_present(
            "COMP_THM",
            &["THM_INIT", "THM_DIFFU", "THM_LIQU", "THM_GAZ", "THM_VAPE_GAZ", "THM_AIR_DISS"]
        )]),
    ]
}

/// The material behaviours declared here, any of which makes a material.
const BEHAVIOURS: &[&str] = &[
    "TABLE",
    "ELAS",
    "ELAS_FO",
    "ELAS_ISTR",
    "ELAS_ISTR_FO",
    "ELAS_ORTH",
    "ELAS_ORTH_FO",
    "ELAS_HYPER",
    "TRACTION",
    "ECRO_LINE",
    "ECRO_LINE_FO",
    "ECRO_PUIS",
    "ECRO_PUIS_FO",
    "PRAGER",
    "PRAGER_FO",
    "NORTON",
    "NORTON_FO",
    "LEMAITRE",
    "LEMAITRE_FO",
    "CIN1_CHAB",
    "CIN2_CHAB",
    "DRUCK_PRAGER",
    "NON_LOCAL",
    "RUPT_FRAG",
    "RUPT_FRAG_FO",
    "CZM_LAB_MIX",
    "RUPT_DUCT",
    "THM_RUPT",
    "THER",
    "THER_FO",
    "THER_NL",
    "THER_ORTH",
    "THER_NL_ORTH",
    "COMP_THM",
];

fn defi_materiau() -> Command {
    let mut entries = kws![
        simp("MATER").co(&[ConceptKind::Mater]),
        fact(
            "TABLE",
            kws![
                simp("TABLE").co(&[ConceptKind::Table]).o(),
                simp("NOM_PARA").txt().o().one_of(&["TEMP", "IRRA"]),
                simp("COMPOR").txt().o().many(),
                simp("INTERPOL").txt().d("LIN").one_of(&["LIN", "LOG"]),
                simp("PROL_DROITE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
                simp("PROL_GAUCHE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
            ]
        ),
    ];
    entries.extend(elasticity());
    entries.extend(plasticity());
    entries.extend(fracture());
    entries.extend(thermal());
    entries.extend(thm());
    entries.push(Entry::from(simp("INFO").i().d(1).one_of_i(&[1, 2])));
    Command::new("DEFI_MATERIAU", "Define the parameters of a material's behaviours.")
        .produces(ConceptKind::Mater)
        .reuse()
        .kw(entries)
        .rules(vec![
            exclus(&["ELAS", "ELAS_FO", "ELAS_ISTR", "ELAS_ISTR_FO", "ELAS_ORTH", "ELAS_ORTH_FO", "ELAS_HYPER"]),
            exclus(&["THER", "THER_FO", "THER_ORTH", "THER_NL", "THER_NL_ORTH"]),
            exclus(&["ECRO_LINE", "ECRO_LINE_FO", "ECRO_PUIS"]),
            exclus(&["NORTON", "NORTON_FO"]),
            exclus(&["LEMAITRE", "LEMAITRE_FO"]),
            present_present("DRUCK_PRAGER", &["ELAS"]),
            au_moins_un(BEHAVIOURS),
        ])
}

/// AFFE_CARA_ELEM as far as its stage goes: MASSIF, the local frames of anisotropic materials. The
/// structural elements' keywords (POUTRE, COQUE, DISCRET, ...) are valid Code_Aster that stops by name.
fn affe_cara_elem() -> Command {
    Command::new("AFFE_CARA_ELEM", "Assign element characteristics: the local frames of anisotropic materials.")
        .produces(ConceptKind::CaraElem)
        .kw(kws![
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            simp("VERIF").txt().many().one_of(&["MAILLE"]),
            fact(
                "MASSIF",
                kws![
                    simp("GROUP_MA").txt().many(),
                    simp("TOUT").txt().one_of(&["OUI"]),
                    simp("CHAM_ORIE").co(&[ConceptKind::ChamNo, ConceptKind::Carte]),
                    simp("ANGL_REP").r().min(1).max(3),
                    simp("ANGL_EULER").r().min(1).max(3),
                    simp("ANGL_AXE").r().min(2).max(2),
                    simp("ORIG_AXE").r().min(2).max(3),
                ]
            )
            .o()
            .many()
            .rules(vec![
                un_parmi(&["GROUP_MA", "TOUT"]),
                un_parmi(&["ANGL_REP", "ORIG_AXE", "ANGL_EULER", "CHAM_ORIE"]),
                present_present("ANGL_AXE", &["ORIG_AXE"]),
                ensemble(&["TOUT", "CHAM_ORIE"]),
            ]),
        ])
}

fn affe_materiau() -> Command {
    Command::new("AFFE_MATERIAU", "Assign materials and external state variables to the cells of a mesh.")
        .produces(ConceptKind::ChamMater)
        .kw(kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]),
            simp("MODELE").co(&[ConceptKind::Modele]),
            fact(
                "AFFE",
                kws![
                    simp("TOUT").txt().one_of(&["OUI"]),
                    simp("GROUP_MA").txt().many(),
                    simp("MATER").co(&[ConceptKind::Mater]).o().max(30),
                ]
            )
            .o()
            .many()
            .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
            fact(
                "AFFE_VARC",
                kws![
                    simp("TOUT").txt().one_of(&["OUI"]),
                    simp("GROUP_MA").txt().many(),
                    simp("MAILLE").txt().many(),
                    simp("NOM_VARC").txt().o().one_of(&[
                        "TEMP", "GEOM", "CORR", "IRRA", "HYDR", "SECH", "EPSA", "M_ACIER", "M_ZIRC", "NEUT1", "NEUT2",
                        "NEUT3", "PTOT", "DIVU",
                    ]),
                    simp("CHAM_GD").co(&[ConceptKind::ChamNo, ConceptKind::ChamElem, ConceptKind::Carte]),
                    simp("EVOL").co(&[ConceptKind::Evol]),
                    bloc(
                        present("EVOL"),
                        kws![
                            simp("NOM_CHAM").txt().one_of(&[
                                "TEMP",
                                "CORR",
                                "IRRA",
                                "NEUT",
                                "GEOM",
                                "HYDR_ELNO",
                                "HYDR_NOEU",
                                "META_ELNO",
                                "META_NOEU",
                                "EPSA_ELNO",
                                "EPSA_NOEU",
                                "PTOT",
                                "DIVU",
                            ]),
                            simp("PROL_DROITE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
                            simp("PROL_GAUCHE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
                            simp("FONC_INST").co(FUNC1),
                        ]
                    ),
                    bloc(is_in("NOM_VARC", &["TEMP", "SECH"]), kws![r("VALE_REF").o()]),
                ]
            )
            .many()
            .rules(vec![
                present_absent("TOUT", &["GROUP_MA", "MAILLE"]),
                present_absent("GROUP_MA", &["TOUT"]),
                present_absent("MAILLE", &["TOUT"]),
                exclus(&["EVOL", "CHAM_GD"]),
            ]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
        .rules(vec![au_moins_un(&["MAILLAGE", "MODELE"])])
}
