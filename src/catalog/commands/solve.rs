//! Solvers: MECA_STATIQUE, STAT_NON_LINE, the time-step list DEFI_LIST_INST, and heat (THER_LINEAIRE,
//! THER_NON_LINE, in `thermal`).

use super::common::*;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

/// Keywords of a single-precision / low-rank factorisation preconditioner.
fn precond_sp() -> Vec<Entry> {
    kws![
        simp("RENUM").txt().d("PARMETIS").one_of(&["SANS", "METIS", "PARMETIS"]),
        simp("REAC_PRECOND").i().d(30),
        simp("PCENT_PIVOT").i().d(20).val_min(1.0),
        simp("GESTION_MEMOIRE").txt().d("AUTO").one_of(&["IN_CORE", "AUTO"]),
        simp("LOW_RANK_SEUIL").r().d(0.0),
    ]
}

/// The common `SOLVEUR` factor keyword; `linear` for MECA_STATIQUE, else the
/// non-linear variant (STAT_NON_LINE).
fn solveur(linear: bool) -> Fact {
    let mut mumps = kws![
        simp("RENUM")
            .txt()
            .d("AUTO")
            .one_of(&["AMD", "AMF", "PORD", "METIS", "QAMD", "SCOTCH", "AUTO", "PARMETIS", "PTSCOTCH"]),
        simp("NPREC").i().d(8),
        simp("ELIM_LAGR").txt().d("LAGR2").one_of(&["OUI", "NON", "LAGR2"]),
        simp("STOP_SINGULIER").txt().d("OUI").one_of(OUI_NON),
        simp("TYPE_RESOL").txt().d("AUTO").one_of(&["NONSYM", "SYMGEN", "SYMDEF", "AUTO"]),
        simp("ACCELERATION").txt().d("AUTO").one_of(&["AUTO", "FR", "FR+", "FR++", "LR", "LR+", "LR++"]),
        simp("LOW_RANK_SEUIL").r().d(0.0),
        simp("PRETRAITEMENTS").txt().d("AUTO").one_of(&["SANS", "AUTO"]),
        simp("POSTTRAITEMENTS").txt().d("AUTO").one_of(&["SANS", "AUTO", "FORCE", "MINI"]),
        simp("PCENT_PIVOT").i().d(35).val_min(1.0),
        simp("REDUCTION_MPI").i().d(0).val_min(0.0),
        simp("NB_RHS").i().d(1).val_min(1.0).val_max(32.0),
        simp("RESI_RELA").r().d(if linear { 1.0e-6 } else { -1.0 }),
        simp("GESTION_MEMOIRE").txt().d("AUTO").one_of(&["IN_CORE", "OUT_OF_CORE", "AUTO", "EVAL"]),
        simp("MATR_DISTRIBUEE").txt().d("NON").one_of(OUI_NON),
    ];
    if !linear {
        mumps
            .extend(
                kws![simp("FILTRAGE_MATRICE").r().d(-1.0), simp("MIXER_PRECISION").txt().d("NON").one_of(OUI_NON),],
            );
    }
    fact(
        "SOLVEUR",
        kws![
            simp("METHODE").txt().d("MUMPS").one_of(&["MULT_FRONT", "LDLT", "MUMPS", "GCPC", "PETSC"]),
            bloc(
                eq("METHODE", "MULT_FRONT"),
                kws![
                    simp("RENUM").txt().d("MDA").one_of(&["MD", "MDA", "METIS"]),
                    simp("NPREC").i().d(8),
                    simp("ELIM_LAGR").txt().d("NON").one_of(OUI_NON),
                    simp("STOP_SINGULIER").txt().d("OUI").one_of(OUI_NON),
                ]
            ),
            bloc(
                eq("METHODE", "LDLT"),
                kws![
                    simp("RENUM").txt().d("RCMK").one_of(&["RCMK"]),
                    simp("NPREC").i().d(8),
                    simp("ELIM_LAGR").txt().d("NON").one_of(OUI_NON),
                    simp("STOP_SINGULIER").txt().d("OUI").one_of(OUI_NON),
                ]
            ),
            bloc(eq("METHODE", "MUMPS"), mumps),
            bloc(
                eq("METHODE", "GCPC"),
                kws![
                    simp("ELIM_LAGR").txt().d("NON").one_of(OUI_NON),
                    simp("PRE_COND").txt().d("LDLT_INC").one_of(&["LDLT_INC", "LDLT_SP", "LDLT_DP"]),
                    simp("RESI_RELA").r().d(1.0e-6),
                    simp("NMAX_ITER").i().d(0),
                    bloc(
                        eq("PRE_COND", "LDLT_INC"),
                        kws![simp("RENUM").txt().d("RCMK").one_of(&["RCMK"]), simp("NIVE_REMPLISSAGE").i().d(0),]
                    ),
                    bloc(is_in("PRE_COND", &["LDLT_SP", "LDLT_DP"]), precond_sp()),
                ]
            ),
            bloc(
                eq("METHODE", "PETSC"),
                kws![
                    simp("ELIM_LAGR").txt().d("NON").one_of(OUI_NON),
                    simp("MATR_DISTRIBUEE").txt().d("NON").one_of(OUI_NON),
                    simp("ALGORITHME").txt().d("FGMRES").one_of(&["CG", "CR", "GMRES", "GCR", "FGMRES", "GMRES_LMP"]),
                    simp("OPTION_PETSC").txt(),
                    simp("PRE_COND").txt().d("LDLT_SP").one_of(&[
                        "LDLT_INC",
                        "LDLT_SP",
                        "LDLT_DP",
                        "JACOBI",
                        "SOR",
                        "ML",
                        "BOOMER",
                        "GAMG",
                        "BLOC_LAGR",
                        "FIELDSPLIT",
                        "UTILISATEUR",
                        "HPDDM",
                        "SANS",
                    ]),
                    simp("RESI_RELA").r().d(1.0e-6),
                    simp("NMAX_ITER").i().d(0),
                    bloc(
                        eq("PRE_COND", "LDLT_INC"),
                        kws![
                            simp("RENUM").txt().d("RCMK").one_of(&["RCMK"]),
                            simp("NIVE_REMPLISSAGE").i().d(0),
                            simp("REMPLISSAGE").r().d(1.0),
                        ]
                    ),
                    bloc(is_in("PRE_COND", &["LDLT_SP", "LDLT_DP"]), precond_sp()),
                    bloc(
                        is_in("PRE_COND", &["ML", "BOOMER", "GAMG", "BLOC_LAGR", "UTILISATEUR"]),
                        kws![simp("RENUM").txt().d("SANS").one_of(&["SANS"])]
                    ),
                    bloc(
                        eq("PRE_COND", "HPDDM"),
                        kws![
                            simp("RENUM").txt().d("SANS").one_of(&["SANS"]),
                            simp("TYPE_RESOL").txt().d("AUTO").one_of(&["AUTO", "GENEO", "HARMO"]),
                            simp("NB_MODE").i().d(30).val_min(1.0),
                            simp("SEUIL").r().val_min(0.0),
                        ]
                    )
                    .rules(vec![exclus(&["NB_MODE", "SEUIL"])]),
                    bloc(
                        eq("PRE_COND", "FIELDSPLIT"),
                        kws![
                            simp("RENUM").txt().d("SANS").one_of(&["SANS"]),
                            simp("PARTITION_CMP").i().many(),
                            simp("NOM_CMP").txt().many(),
                        ]
                    ),
                    bloc(
                        is_in("PRE_COND", &["JACOBI", "SOR", "SANS"]),
                        kws![simp("RENUM").txt().d("SANS").one_of(&["SANS", "RCMK"])]
                    ),
                ]
            ),
        ],
    )
    .d()
}

/// Behaviour laws whose name starts with META_ (metallurgical phases), which
/// take the metallurgy kit in RELATION_KIT.
const META_RELATIONS: &[&str] = &[
    "META_P_CL",
    "META_P_CL_PT",
    "META_P_CL_PT_RE",
    "META_P_CL_RE",
    "META_P_IL",
    "META_P_IL_PT",
    "META_P_IL_PT_RE",
    "META_P_IL_RE",
    "META_P_INL",
    "META_P_INL_PT",
    "META_P_INL_PT_RE",
    "META_P_INL_RE",
    "META_V_CL",
    "META_V_CL_PT",
    "META_V_CL_PT_RE",
    "META_V_CL_RE",
    "META_V_IL",
    "META_V_IL_PT",
    "META_V_IL_PT_RE",
    "META_V_IL_RE",
    "META_V_INL",
    "META_V_INL_PT",
    "META_V_INL_PT_RE",
    "META_V_INL_RE",
];

const KIT_THM: &[&str] = &[
    "KIT_HHM",
    "KIT_HH",
    "KIT_H",
    "KIT_HM",
    "KIT_THHM",
    "KIT_THH",
    "KIT_THM",
    "KIT_THV",
    "KIT_THH2M",
    "KIT_HH2M",
    "KIT_HH2",
    "KIT_THH2",
];

/// STAT_NON_LINE's `COMPORTEMENT`: the behaviour law per group of cells.
///
/// Both syntaxes are accepted: `RESI_INTE` (2025) and the older
/// `RESI_INTE_RELA` / `RESI_INTE_MAXI` (2020). The defaults of the integration
/// criteria depend on the law (1e-6 / 20 iterations in general, 1e-8 / 100
/// for MFRONT, -1 iterations for the RGI concrete laws) and are left to the
/// stage.
pub(super) fn comportement() -> Fact {
    fact(
        "COMPORTEMENT",
        kws![
            simp("TOUT").txt().one_of(&["OUI"]),
            simp("GROUP_MA").txt().many(),
            simp("MAILLE").txt().many(),
            simp("RELATION").txt().d("ELAS"),
            simp("REGU_VISC").txt().d("NON").one_of(OUI_NON),
            bloc(eq("RELATION", "MULTIFIBRE"), kws![simp("RIGI_GEOM").txt().d("DEFAUT").one_of(&["DEFAUT", "OUI"])]),
            bloc(
                eq("RELATION", "UMAT"),
                kws![simp("NB_VARI").i().o(), simp("LIBRAIRIE").txt().o(), simp("NOM_ROUTINE").txt().o()]
            ),
            bloc(
                eq("RELATION", "MFRONT"),
                kws![
                    simp("UNITE_LIBRAIRIE").i(),
                    simp("LIBRAIRIE").txt(),
                    simp("NOM_ROUTINE").txt(),
                    simp("VERI_BORNE").txt().d("ARRET").one_of(&["ARRET", "SANS", "MESSAGE"]),
                    simp("ALGO_CPLAN").txt().d("DEBORST").one_of(&["DEBORST", "ANALYTIQUE"]),
                    simp("SYME_MATR_TANG").txt().d("OUI").one_of(OUI_NON),
                ]
            )
            .rules(vec![exclus(&["UNITE_LIBRAIRIE", "LIBRAIRIE"])]),
            bloc(
                eq("RELATION", "KIT_DDI"),
                kws![simp("RELATION_KIT")
                    .txt()
                    .min(2)
                    .max(2)
                    .one_of(&[
                        "VMIS_CINE_LINE",
                        "VMIS_ISOT_TRAC",
                        "VMIS_ISOT_LINE",
                        "VMIS_ISOT_PUIS",
                        "GLRC_DM",
                        "BETON_GRANGER",
                        "BETON_GRANGER_V",
                        "BETON_UMLV",
                        "ROUSS_PR",
                        "BETON_DOUBLE_DP",
                        "ENDO_ISOT_BETON",
                        "MAZARS",
                    ])
                    .o()]
            ),
            bloc(
                eq("RELATION", "KIT_CG"),
                kws![simp("RELATION_KIT")
                    .txt()
                    .min(2)
                    .max(2)
                    .one_of(&[
                        "CABLE_GAINE_FROT",
                        "VMIS_ISOT_LINE",
                        "VMIS_ISOT_TRAC",
                        "VMIS_CINE_LINE",
                        "PINTO_MENEGOTTO",
                        "ELAS",
                        "SANS",
                    ])
                    .o()]
            ),
            bloc(is_in("RELATION", KIT_THM), kws![simp("RELATION_KIT").txt().max(9).o()]),
            bloc(is_in("RELATION", META_RELATIONS), kws![simp("RELATION_KIT").txt().one_of(&["ACIER", "ZIRC"]).o()]),
            bloc(
                is_in(
                    "RELATION",
                    &["VMIS_ISOT_LINE", "VMIS_ISOT_TRAC", "VISCOCHAB", "VISC_ISOT_LINE", "VISC_ISOT_TRAC"]
                ),
                kws![simp("POST_ITER").txt().one_of(&["CRIT_RUPT"])]
            ),
            bloc(
                is_in(
                    "RELATION",
                    &[
                        "VMIS_ISOT_LINE",
                        "VMIS_CINE_LINE",
                        "VMIS_ECMI_LINE",
                        "VMIS_ISOT_TRAC",
                        "VMIS_CIN1_CHAB",
                        "VMIS_CIN2_CHAB"
                    ]
                ),
                kws![simp("POST_INCR").txt().one_of(&["REST_ECRO", "SANS"])]
            ),
            simp("DEFORMATION").txt().d("PETIT").one_of(&[
                "PETIT",
                "PETIT_REAC",
                "GROT_GDEP",
                "SIMO_MIEHE",
                "GDEF_LOG",
                "GREEN_LAGRANGE",
            ]),
            simp("RESI_CPLAN_MAXI").r(),
            bloc(absent("RESI_CPLAN_MAXI"), kws![simp("RESI_CPLAN_RELA").r().d(1.0e-6)]),
            simp("ITER_CPLAN_MAXI").i().d(10),
            simp("RESI_INTE").r(),
            simp("RESI_INTE_RELA").r(),
            simp("RESI_INTE_MAXI").r(),
            simp("ITER_INTE_MAXI").i(),
            bloc(is_in("DEFORMATION", &["PETIT", "PETIT_REAC", "GROT_GDEP"]), kws![simp("ITER_INTE_PAS").i().d(0)]),
            simp("ALGO_INTE").txt().one_of(&[
                "ANALYTIQUE",
                "SECANTE",
                "DEKKER",
                "NEWTON_1D",
                "BRENT",
                "NEWTON",
                "NEWTON_RELI",
                "NEWTON_PERT",
                "RUNGE_KUTTA",
                "SPECIFIQUE",
                "SEMI_EXPLICITE",
                "BASCULE_EXPLICITE",
                "SANS_OBJET",
            ]),
            simp("TYPE_MATR_TANG").txt().one_of(&["PERTURBATION", "VERIFICATION"]),
            bloc(present("TYPE_MATR_TANG"), kws![simp("VALE_PERT_RELA").r().d(1.0e-5)]),
            bloc(absent("TYPE_MATR_TANG"), kws![simp("RESI_RADI_RELA").r()]),
            simp("PARM_THETA").r().d(1.0).val_min(0.0).val_max(1.0),
        ],
    )
    .d()
    .many()
    .rules(vec![
        present_absent("TOUT", &["GROUP_MA", "MAILLE"]),
        exclus(&["RESI_INTE", "RESI_INTE_RELA", "RESI_INTE_MAXI"]),
    ])
}

const DDL_CRIT_STAB: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "GRX", "PRES", "PHI", "TEMP", "PRE1", "PRE2", "UI2", "UI3", "VI2", "VI3",
    "WI2", "WI3", "UO2", "UO3", "VO2", "VO3", "WO2", "WO3", "UI4", "UI5", "VI4", "VI5", "WI4", "WI5", "UO4", "UO5",
    "VO4", "VO5", "WO4", "WO5", "UI6", "UO6", "VI6", "VO6", "WI6", "WO6", "WO", "WI1", "WO1", "GONF", "LIAISON", "DCX",
    "DCY", "DCZ", "H1X", "H1Y", "H1Z", "K1", "K2", "K3", "LAGS_C", "V11", "V12", "V13", "V21", "V22", "V23", "V31",
    "V32", "V33", "PRES11", "PRES12", "PRES13", "PRES21", "PRES22", "PRES23", "PRES31", "PRES32", "PRES33", "VARI",
    "LAG_GV", "DAMG",
];

fn crit_stab() -> Fact {
    let mut e = kws![
        simp("OPTION").txt().d("PLUS_PETITE").one_of(&["PLUS_PETITE", "BANDE", "CALIBRATION"]),
        bloc(eq("OPTION", "BANDE"), kws![simp("CHAR_CRIT").r().min(2).max(2)]),
        bloc(eq("OPTION", "PLUS_PETITE"), kws![simp("NMAX_CHAR_CRIT").i().d(3).val_min(1.0)]),
        bloc(eq("OPTION", "CALIBRATION"), kws![simp("CHAR_CRIT").r().min(2).max(2)]),
        simp("COEF_DIM_ESPACE").i().d(5).val_min(2.0),
        simp("RIGI_GEOM").txt().d("OUI").one_of(OUI_NON),
        simp("MODI_RIGI").txt().d("NON").one_of(OUI_NON),
        simp("TYPE").txt().d("FLAMBEMENT").one_of(&["FLAMBEMENT", "STABILITE"]),
        simp("PREC_INSTAB").r().d(1.0e-6),
        simp("SIGNE").txt().d("POSITIF_NEGATIF").one_of(&["NEGATIF", "POSITIF", "POSITIF_NEGATIF"]),
        bloc(eq("RIGI_GEOM", "NON"), kws![simp("DDL_EXCLUS").txt().max(40).one_of(DDL_CRIT_STAB)]),
        bloc(
            and(vec![eq("TYPE", "STABILITE"), eq("RIGI_GEOM", "NON")]),
            kws![simp("DDL_STAB").txt().max(40).one_of(DDL_CRIT_STAB).o()]
        ),
        simp("LIST_INST").co(&[ConceptKind::ListR8]),
        simp("INST").r().many(),
        simp("PAS_CALC").i(),
    ];
    e.extend(crit_prec());
    fact("CRIT_STAB", e).rules(vec![exclus(&["PAS_CALC", "LIST_INST", "INST"])])
}

/// Selection of nodes / cells for OBSERVATION and SUIVI_DDL.
fn obs_location() -> Vec<Entry> {
    kws![
        bloc(
            is_in(
                "NOM_CHAM",
                &[
                    "DEPL",
                    "VITE",
                    "ACCE",
                    "TEMP",
                    "FORC_NODA",
                    "CONT_NOEU",
                    "DEPL_ABSOLU",
                    "VITE_ABSOLU",
                    "ACCE_ABSOLU",
                ]
            ),
            kws![
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("NOEUD").txt().many(),
                simp("GROUP_NO").txt().many(),
                simp("MAILLE").txt().many(),
                simp("GROUP_MA").txt().many(),
            ]
        )
        .rules(vec![un_parmi(&["NOEUD", "GROUP_NO", "GROUP_MA", "MAILLE", "TOUT"])]),
        bloc(
            is_in("NOM_CHAM", &["SIEF_ELGA", "EPSI_ELGA", "VARI_ELGA"]),
            kws![
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("MAILLE").txt().many(),
                simp("GROUP_MA").txt().many(),
                simp("EVAL_ELGA").txt().d("VALE").one_of(&["MIN", "MAX", "VALE"]),
                bloc(eq("EVAL_ELGA", "VALE"), kws![simp("POINT").i().many().o(), simp("SOUS_POINT").i().many()]),
            ]
        )
        .rules(vec![un_parmi(&["GROUP_MA", "MAILLE", "TOUT"])]),
        bloc(
            eq("NOM_CHAM", "CONT_ELEM"),
            kws![simp("TOUT").txt().one_of(&["OUI"]), simp("MAILLE").txt().many(), simp("GROUP_MA").txt().many(),]
        )
        .rules(vec![un_parmi(&["GROUP_MA", "MAILLE", "TOUT"])]),
    ]
}

fn observation() -> Fact {
    let mut e = kws![
        simp("NOM_CHAM").txt().o().one_of(&[
            "CONT_NOEU",
            "FORC_NODA",
            "CONT_ELEM",
            "DEPL",
            "VITE",
            "ACCE",
            "SIEF_ELGA",
            "VARI_ELGA",
            "EPSI_ELGA",
            "DEPL_ABSOLU",
            "VITE_ABSOLU",
            "ACCE_ABSOLU",
        ]),
        simp("TITRE").txt(),
        simp("OBSE_ETAT_INIT").txt().d("OUI").one_of(OUI_NON),
        simp("EVAL_CHAM").txt().d("VALE").one_of(&["MIN", "MAX", "MOY", "MAXI_ABS", "MINI_ABS", "VALE"]),
        simp("NOM_CMP").txt().max(20),
        simp("NOM_VARI").txt().max(20),
        simp("EVAL_CMP").txt().d("VALE").one_of(&["VALE", "FORMULE"]),
        bloc(eq("EVAL_CMP", "FORMULE"), kws![simp("FORMULE").co(&[ConceptKind::Formule]).o()]),
        simp("INST").r().many(),
        simp("LIST_INST").co(&[ConceptKind::ListR8]),
        simp("PAS_OBSE").i(),
    ];
    e.extend(crit_prec());
    e.extend(obs_location());
    fact("OBSERVATION", e).max(99).rules(vec![un_parmi(&["NOM_CMP", "NOM_VARI"])])
}

fn suivi_ddl() -> Fact {
    let mut e = kws![
        simp("NOM_CHAM").txt().o().one_of(&[
            "DEPL",
            "VITE",
            "ACCE",
            "FORC_NODA",
            "SIEF_ELGA",
            "VARI_ELGA",
            "EPSI_ELGA",
        ]),
        simp("EVAL_CHAM").txt().d("VALE").one_of(&["MIN", "MAX", "MOY", "MAXI_ABS", "MINI_ABS", "VALE"]),
        simp("NOM_CMP").txt().max(20),
        simp("NOM_VARI").txt().max(20),
        simp("EVAL_CMP").txt().d("VALE").one_of(&["VALE", "FORMULE"]),
        bloc(eq("EVAL_CMP", "FORMULE"), kws![simp("FORMULE").co(&[ConceptKind::Formule]).o()]),
        simp("TITRE").txt().max(3),
    ];
    e.extend(obs_location());
    fact("SUIVI_DDL", e).max(4).rules(vec![un_parmi(&["NOM_CMP", "NOM_VARI"])])
}

fn convergence() -> Fact {
    fact(
        "CONVERGENCE",
        kws![
            simp("RESI_REFE_RELA").r(),
            simp("RESI_GLOB_MAXI").r(),
            // RESI_GLOB_RELA = 1e-6 when no other criterion is given.
            bloc(
                and(vec![absent("RESI_GLOB_MAXI"), absent("RESI_REFE_RELA")]),
                kws![simp("RESI_GLOB_RELA").r().d(1.0e-6)]
            ),
            bloc(present("RESI_GLOB_MAXI"), kws![simp("RESI_GLOB_RELA").r()]),
            simp("RESI_COMP_RELA").r(),
            bloc(
                present("RESI_REFE_RELA"),
                kws![
                    simp("SIGM_REFE").r(),
                    simp("EPSI_REFE").r(),
                    simp("FLUX_THER_REFE").r(),
                    simp("FLUX_HYD1_REFE").r(),
                    simp("FLUX_HYD2_REFE").r(),
                    simp("EFFORT_REFE").r(),
                    simp("MOMENT_REFE").r(),
                    simp("VARI_REFE").r(),
                    simp("DEPL_REFE").r(),
                    simp("LAGR_REFE").r(),
                    simp("PI_REFE").r(),
                ]
            )
            .rules(vec![au_moins_un(&[
                "SIGM_REFE",
                "EPSI_REFE",
                "FLUX_THER_REFE",
                "FLUX_HYD1_REFE",
                "FLUX_HYD2_REFE",
                "EFFORT_REFE",
                "MOMENT_REFE",
                "VARI_REFE",
                "DEPL_REFE",
                "LAGR_REFE",
                "PI_REFE",
            ])]),
            simp("ITER_GLOB_MAXI").i().d(10),
            simp("ITER_GLOB_ELAS").i().d(25),
            simp("ARRET").txt().d("OUI").one_of(OUI_NON),
            simp("VERIF").txt().d("TOUT").one_of(&["TOUT", "AU_MOINS_UN"]),
        ],
    )
    .d()
    .rules(vec![present_absent("RESI_REFE_RELA", &["RESI_GLOB_MAXI", "RESI_COMP_RELA"])])
}

fn archivage() -> Fact {
    let mut e = kws![
        // PAS_ARCH = 1 when neither LIST_INST nor INST is given.
        bloc(and(vec![absent("LIST_INST"), absent("INST")]), kws![simp("PAS_ARCH").i().d(1)]),
        simp("LIST_INST").co(&[ConceptKind::ListR8]),
        simp("INST").r().many(),
        simp("CHAM_EXCLU").txt().many(),
    ];
    e.push(Entry::Bloc(bloc(or(vec![present("INST"), present("LIST_INST")]), crit_prec())));
    fact("ARCHIVAGE", e).d().rules(vec![exclus(&["LIST_INST", "INST"])])
}

fn etat_init() -> Fact {
    let mut e = kws![
        simp("DEPL").co(&[ConceptKind::ChamNo]),
        simp("SIGM").co(&[ConceptKind::ChamElem, ConceptKind::Carte]),
        simp("VARI").co(&[ConceptKind::ChamElem]),
        simp("STRX").co(&[ConceptKind::ChamElem]),
        simp("COHE").co(&[ConceptKind::ChamElem]),
        simp("EVOL_NOLI").co(&[ConceptKind::EvolNoli]),
        simp("NUME_ORDRE").i(),
        simp("INST").r(),
        simp("NUME_DIDI").i(),
        simp("INST_ETAT_INIT").r(),
    ];
    e.extend(crit_prec());
    fact("ETAT_INIT", e)
        .rules(vec![au_moins_un(&["EVOL_NOLI", "DEPL", "SIGM", "VARI", "COHE"]), exclus(&["NUME_ORDRE", "INST"])])
}

fn stat_non_line() -> Command {
    Command::new(
        "STAT_NON_LINE",
        "Quasi-static non-linear (possibly thermo-hydro-mechanical) evolution of a structure.",
    )
    .produces(ConceptKind::EvolNoli)
    .reuse()
    .kw(kws![
        simp("RESULTAT").co(&[ConceptKind::EvolNoli]),
        simp("MODELE").co(&[ConceptKind::Modele]).o(),
        simp("CHAM_MATER").co(&[ConceptKind::ChamMater]).o(),
        fact(
            "EXCIT",
            kws![
                simp("CHARGE").co(&[ConceptKind::CharMeca, ConceptKind::CharCineMeca]).o(),
                simp("FONC_MULT").co(FUNCS),
                simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&[
                    "FIXE_CSTE",
                    "FIXE_PILO",
                    "SUIV",
                    "SUIV_PILO",
                    "DIDI"
                ]),
            ]
        )
        .many(),
        simp("CONTACT").co(&[ConceptKind::CharContact]),
        fact(
            "SOUS_STRUC",
            kws![
                simp("CAS_CHARGE").txt().o(),
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("SUPER_MAILLE").txt().many(),
                simp("FONC_MULT").co(FUNCS),
            ]
        )
        .many()
        .rules(vec![un_parmi(&["TOUT", "SUPER_MAILLE"])]),
        fact(
            "SCHEMA_THM",
            kws![simp("PARM_THETA").r().d(1.0).val_min(0.0).val_max(1.0), simp("PARM_ALPHA").r().d(1.0)]
        ),
        comportement(),
        etat_init(),
        fact(
            "INCREMENT",
            kws![
                simp("LIST_INST").co(&[ConceptKind::ListR8, ConceptKind::ListInst]).o(),
                simp("NUME_INST_INIT").i(),
                simp("INST_INIT").r(),
                simp("NUME_INST_FIN").i(),
                simp("INST_FIN").r(),
                simp("PRECISION").r().d(1.0e-6),
            ]
        )
        .o()
        .rules(vec![exclus(&["NUME_INST_INIT", "INST_INIT"]), exclus(&["NUME_INST_FIN", "INST_FIN"])]),
        simp("METHODE").txt().d("NEWTON").one_of(&["NEWTON", "IMPLEX", "NEWTON_KRYLOV", "MODELE_REDUIT"]),
        bloc(
            is_in("METHODE", &["NEWTON", "NEWTON_KRYLOV"]),
            kws![fact(
                "NEWTON",
                kws![
                    simp("REAC_INCR").i().d(1).val_min(0.0),
                    simp("PREDICTION").txt().one_of(&["DEPL_CALCULE", "TANGENTE", "ELASTIQUE", "EXTRAPOLE"]),
                    simp("MATRICE").txt().d("TANGENTE").one_of(&["TANGENTE", "ELASTIQUE"]),
                    simp("PAS_MINI_ELAS").r().val_min(0.0),
                    simp("REAC_ITER").i().d(1).val_min(0.0),
                    simp("REAC_ITER_ELAS").i().d(0).val_min(0.0),
                    simp("EVOL_NOLI").co(&[ConceptKind::EvolNoli]),
                    simp("MATR_RIGI_SYME").txt().d("NON").one_of(OUI_NON),
                ]
            )
            .d()]
        ),
        fact(
            "RECH_LINEAIRE",
            kws![
                simp("METHODE").txt().d("CORDE").one_of(&["CORDE", "MIXTE", "PILOTAGE"]),
                simp("RESI_LINE_RELA").r().d(1.0e-1).val_min(0.0),
                simp("ITER_LINE_MAXI").i().d(3).val_min(0.0).val_max(999.0),
                simp("RHO_MIN").r().d(1.0e-2).val_min(0.0),
                simp("RHO_MAX").r().d(1.0e1).val_min(0.0),
                simp("RHO_EXCL").r().d(0.9e-2).val_min(0.0),
            ]
        ),
        fact(
            "PILOTAGE",
            kws![
                simp("TYPE").txt().o().one_of(&[
                    "DDL_IMPO",
                    "LONG_ARC",
                    "PRED_ELAS",
                    "DEFORMATION",
                    "ANA_LIM",
                    "SAUT_IMPO",
                    "SAUT_LONG_ARC"
                ]),
                simp("COEF_MULT").r().d(1.0),
                simp("EVOL_PARA").txt().d("SANS").one_of(&["SANS", "CROISSANT", "DECROISSANT"]),
                simp("ETA_PILO_MAX").r(),
                simp("ETA_PILO_MIN").r(),
                simp("ETA_PILO_R_MAX").r(),
                simp("ETA_PILO_R_MIN").r(),
                simp("PROJ_BORNES").txt().d("OUI").one_of(OUI_NON),
                simp("SELECTION").txt().d("NORM_INCR_DEPL").one_of(&[
                    "RESIDU",
                    "MIXTE",
                    "ANGL_INCR_DEPL",
                    "NORM_INCR_DEPL"
                ]),
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("GROUP_MA").txt().many(),
                simp("FISSURE").co(&[ConceptKind::FissXfem]).many(),
                simp("NOEUD").txt().many(),
                simp("GROUP_NO").txt().many(),
                simp("NOM_CMP").txt().many(),
                simp("DIRE_PILO").txt().many(),
            ]
        )
        .rules(vec![exclus(&["NOEUD", "GROUP_NO"]), present_absent("TOUT", &["GROUP_MA"])]),
        convergence(),
        solveur(false),
        observation(),
        suivi_ddl(),
        archivage(),
        fact("CRIT_QUALITE", kws![simp("ERRE_TEMPS_THM").txt().d("NON").one_of(OUI_NON)]),
        fact("ENERGIE", kws![simp("CALCUL").txt().d("OUI").one_of(&["OUI"])]),
        fact(
            "AFFICHAGE",
            kws![
                simp("INFO_RESIDU").txt().d("NON").one_of(OUI_NON),
                simp("INFO_TEMPS").txt().d("NON").one_of(OUI_NON),
                simp("UNITE").i(),
                simp("PAS").i().val_min(1.0),
            ]
        )
        .d(),
        crit_stab(),
        simp("INFO").i().one_of_i(&[1, 2]),
        bloc(
            eq("INFO", 2),
            kws![simp("INFO_DBG").txt().many().one_of(&[
                "CONTACT",
                "MECANONLINE",
                "MECA_NON_LINE",
                "PILOTAGE",
                "FACTOR",
                "FACTORISATION",
                "SOLVEUR",
                "APPARIEMENT",
            ])]
        ),
        simp("TITRE").txt(),
    ])
}

fn meca_statique() -> Command {
    Command::new("MECA_STATIQUE", "Linear static mechanical analysis.")
        .produces(ConceptKind::EvolElas)
        .reuse()
        .kw(kws![
            simp("RESULTAT").co(&[ConceptKind::EvolElas]),
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("CHAM_MATER").co(&[ConceptKind::ChamMater]).o(),
            fact(
                "EXCIT",
                kws![
                    simp("CHARGE").co(&[ConceptKind::CharMeca, ConceptKind::CharCineMeca]).o(),
                    simp("FONC_MULT").co(FUNCS),
                    simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&["FIXE_CSTE"]),
                ]
            )
            .o()
            .many(),
            simp("INST").r(),
            simp("LIST_INST").co(&[ConceptKind::ListR8]),
            simp("INST_FIN").r(),
            simp("OPTION").txt().d("SIEF_ELGA").one_of(&["SIEF_ELGA", "SANS"]),
            solveur(true),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            simp("TITRE").txt(),
        ])
        .rules(vec![exclus(&["INST", "LIST_INST"])])
}

/// Keywords of the time-step subdivision (ACTION='DECOUPE').
fn decoupe() -> Bloc {
    bloc(
        eq("ACTION", "DECOUPE"),
        kws![
            simp("SUBD_METHODE").txt().d("MANUEL").one_of(&["MANUEL", "AUTO"]),
            bloc(
                eq("SUBD_METHODE", "MANUEL"),
                kws![
                    simp("SUBD_PAS").i().d(4).val_min(2.0),
                    simp("SUBD_NIVEAU").i().d(3).val_min(0.0),
                    simp("SUBD_PAS_MINI").r().d(0.0).val_min(0.0),
                ]
            ),
            bloc(eq("SUBD_METHODE", "AUTO"), kws![simp("SUBD_PAS_MINI").r().d(0.0).val_min(0.0)]),
        ],
    )
}

fn defi_list_inst() -> Command {
    let delta = kws![
        simp("GROUP_MA").txt().many(),
        simp("GROUP_NO").txt().many(),
        simp("VALE_REF").r().o(),
        simp("NOM_CHAM").txt().o().one_of(&["DEPL", "VARI_ELGA", "SIEF_ELGA"]),
        simp("NOM_CMP").txt().o(),
    ];
    let mut edelta = delta.clone();
    edelta.extend(kws![simp("ACTION").txt().d("DECOUPE").one_of(&["ARRET", "DECOUPE"]), decoupe()]);
    Command::new("DEFI_LIST_INST", "A list of instants with automatic time-step management.")
        .produces(ConceptKind::ListInst)
        .kw(kws![
            simp("MODELE").co(&[ConceptKind::Modele]),
            simp("METHODE").txt().d("MANUEL").one_of(&["MANUEL", "AUTO"]),
            bloc(
                eq("METHODE", "MANUEL"),
                kws![fact(
                    "DEFI_LIST",
                    kws![
                        simp("VALE").r().many(),
                        simp("LIST_INST").co(&[ConceptKind::ListR8]),
                        simp("RESULTAT").co(RESULTS),
                        simp("SUBD_PAS").i().val_min(1.0),
                    ]
                )
                .o()
                .rules(
                    vec![un_parmi(&["LIST_INST", "VALE", "RESULTAT"]), present_present("RESULTAT", &["SUBD_PAS"]),]
                )]
            ),
            bloc(
                eq("METHODE", "AUTO"),
                kws![fact(
                    "DEFI_LIST",
                    kws![
                        simp("VALE").r().many(),
                        simp("LIST_INST").co(&[ConceptKind::ListR8]),
                        simp("PAS_INIT").r().val_min(1.0e-12),
                        simp("PAS_MINI").r().val_min(1.0e-12),
                        simp("PAS_MAXI").r(),
                        simp("NB_PAS_MAXI").i().d(1000000).val_max(1000000.0),
                    ]
                )
                .o()
                .rules(vec![un_parmi(&["LIST_INST", "VALE"])])]
            ),
            fact(
                "ECHEC",
                kws![
                    simp("EVENEMENT").txt().d("ERREUR").one_of(&[
                        "ERREUR",
                        "DELTA_GRANDEUR",
                        "RESI_MAXI",
                        "INTERPENETRATION",
                        "DIVE_RESI",
                        "INSTABILITE",
                    ]),
                    bloc(
                        eq("EVENEMENT", "ERREUR"),
                        kws![simp("ACTION").txt().d("DECOUPE").one_of(&["ARRET", "DECOUPE"]), decoupe()]
                    ),
                    bloc(eq("EVENEMENT", "DELTA_GRANDEUR"), edelta).rules(vec![exclus(&["GROUP_MA", "GROUP_NO"])]),
                    bloc(
                        eq("EVENEMENT", "INTERPENETRATION"),
                        kws![simp("PENE_MAXI").r().o(), simp("ACTION").txt().d("ARRET").one_of(&["ARRET"])]
                    ),
                    bloc(
                        eq("EVENEMENT", "DIVE_RESI"),
                        kws![simp("ACTION").txt().d("DECOUPE").one_of(&["DECOUPE"]), decoupe()]
                    ),
                    bloc(
                        eq("EVENEMENT", "RESI_MAXI"),
                        kws![
                            simp("RESI_GLOB_MAXI").r().o(),
                            simp("ACTION").txt().d("DECOUPE").one_of(&["DECOUPE"]),
                            decoupe(),
                        ]
                    ),
                    bloc(
                        eq("EVENEMENT", "INSTABILITE"),
                        kws![simp("ACTION").txt().d("CONTINUE").one_of(&["ARRET", "CONTINUE"])]
                    ),
                ]
            )
            .d()
            .many(),
            bloc(
                eq("METHODE", "AUTO"),
                kws![fact(
                    "ADAPTATION",
                    kws![
                        simp("EVENEMENT").txt().d("SEUIL").one_of(&["SEUIL", "TOUT_INST", "AUCUN"]),
                        bloc(
                            eq("EVENEMENT", "SEUIL"),
                            kws![
                                simp("NB_INCR_SEUIL").i().d(2),
                                simp("NOM_PARA").txt().d("NB_ITER_NEWTON").one_of(&["NB_ITER_NEWTON"]),
                                simp("CRIT_COMP").txt().d("LE").one_of(&["LT", "GT", "LE", "GE"]),
                                bloc(eq("NOM_PARA", "NB_ITER_NEWTON"), kws![simp("VALE_I").i()]),
                            ]
                        ),
                        simp("MODE_CALCUL_TPLUS").txt().d("FIXE").one_of(&[
                            "FIXE",
                            "DELTA_GRANDEUR",
                            "ITER_NEWTON",
                            "IMPLEX"
                        ]),
                        bloc(eq("MODE_CALCUL_TPLUS", "FIXE"), kws![simp("PCENT_AUGM").r().d(100.0).val_min(-100.0)]),
                        bloc(eq("MODE_CALCUL_TPLUS", "DELTA_GRANDEUR"), delta)
                            .rules(vec![exclus(&["GROUP_MA", "GROUP_NO"])]),
                        bloc(eq("MODE_CALCUL_TPLUS", "ITER_NEWTON"), kws![simp("NB_ITER_NEWTON_REF").i().o()]),
                    ]
                )
                .d()
                .many()]
            ),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
}

mod thermal;

pub fn commands() -> Vec<Command> {
    vec![meca_statique(), stat_non_line(), defi_list_inst(), thermal::ther_lineaire(), thermal::ther_non_line()]
}
