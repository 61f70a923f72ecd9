//! Fields: computed from results (CALC_CHAMP), of their own (CREA_CHAMP), in another frame (MODI_REPERE);
//! results made of fields (CREA_RESU).

use super::common::*;
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::diag::{Error, Result};
use crate::kws;

/// MODI_REPERE: the type of RESULTAT, else of CHAM_GD.
fn modi_repere_type(a: &Args) -> Result<ConceptKind> {
    concept_kind(a, "RESULTAT").or_else(|| concept_kind(a, "CHAM_GD")).ok_or_else(|| missing(a, "RESULTAT or CHAM_GD"))
}

/// CREA_CHAMP: the location part of TYPE_CHAM (`NOEU_DEPL_R`, `ELGA_SIEF_R`,
/// `CART_NEUT_R`, ...) decides the kind of field.
fn crea_champ_type(a: &Args) -> Result<ConceptKind> {
    let t = a.text("TYPE_CHAM").ok_or_else(|| missing(a, "TYPE_CHAM"))?;
    let loc = t.split('_').next().unwrap_or("");
    match loc {
        "NOEU" => Ok(ConceptKind::ChamNo),
        "CART" => Ok(ConceptKind::Carte),
        "ELEM" | "ELGA" | "ELNO" => Ok(ConceptKind::ChamElem),
        _ => Err(Error::catalog(format!("TYPE_CHAM '{t}' must start with NOEU_, ELEM_, ELGA_, ELNO_ or CART_"))
            .at(a.span_of("TYPE_CHAM"))),
    }
}

// ------------------------------------------------------------------ CALC_CHAMP

const CONTRAINTE: &[&str] = &[
    "EFGE_ELGA",
    "EFGE_ELNO",
    "EFGE_NOEU",
    "SIEF_ELGA",
    "SIEF_ELNO",
    "SIEF_NOEU",
    "SIGM_ELGA",
    "SIGM_ELNO",
    "SIGM_NOEU",
    "SIPM_ELNO",
    "SIPO_ELNO",
    "SIPO_NOEU",
    "SIRO_ELEM",
    "STRX_ELGA",
];

const DEFORMATION: &[&str] = &[
    "DEGE_ELGA",
    "DEGE_ELNO",
    "DEGE_NOEU",
    "EPFD_ELGA",
    "EPFD_ELNO",
    "EPFD_NOEU",
    "EPFP_ELGA",
    "EPFP_ELNO",
    "EPFP_NOEU",
    "EPME_ELGA",
    "EPME_ELNO",
    "EPME_NOEU",
    "EPMG_ELGA",
    "EPMG_ELNO",
    "EPMG_NOEU",
    "EPSG_ELGA",
    "EPSG_ELNO",
    "EPSG_NOEU",
    "EPSI_ELGA",
    "EPSI_ELNO",
    "EPSI_NOEU",
    "EPSP_ELGA",
    "EPSP_ELNO",
    "EPSP_NOEU",
    "EPVC_ELGA",
    "EPVC_ELNO",
    "EPVC_NOEU",
    "EPSL_ELGA",
    "EPSL_ELNO",
    "EPSL_NOEU",
];

const ENERGIE: &[&str] = &[
    "DISS_ELEM",
    "DISS_ELGA",
    "DISS_ELNO",
    "DISS_NOEU",
    "ECIN_ELEM",
    "ENEL_ELEM",
    "ENEL_ELGA",
    "ENEL_ELNO",
    "ENEL_NOEU",
    "ENTR_ELEM",
    "EPOT_ELEM",
    "ETOT_ELEM",
    "ETOT_ELGA",
    "ETOT_ELNO",
    "ETOT_NOEU",
];

const CRITERES: &[&str] = &[
    "DERA_ELGA",
    "DERA_ELNO",
    "DERA_NOEU",
    "ENDO_ELGA",
    "ENDO_ELNO",
    "ENDO_NOEU",
    "EPEQ_ELGA",
    "EPEQ_ELNO",
    "EPEQ_NOEU",
    "EPGQ_ELGA",
    "EPGQ_ELNO",
    "EPGQ_NOEU",
    "EPMQ_ELGA",
    "EPMQ_ELNO",
    "EPMQ_NOEU",
    "INDL_ELGA",
    "PDIL_ELGA",
    "SIEQ_ELGA",
    "SIEQ_ELNO",
    "SIEQ_NOEU",
];

const VARI_INTERNE: &[&str] = &["VAEX_ELGA", "VAEX_ELNO", "VAEX_NOEU", "VARC_ELGA", "VARI_ELNO", "VARI_NOEU"];

const NOM_VARI_VAEX: &[&str] = &[
    "DPORO",
    "DRHOLQ",
    "DPVP",
    "SATLIQ",
    "EVP",
    "IND_ETA",
    "D",
    "IND_END",
    "TEMP_MAX",
    "GAMP",
    "PCR",
    "SEUIL_HYD",
    "IND_HYD",
    "PCOHE",
    "COMP_ROC",
    "SEUIL_ISO",
    "ANG_DEV",
    "X11",
    "X22",
    "X33",
    "X12",
    "X13",
    "X23",
    "DIST_DEV",
    "DEV_SUR_CRIT",
    "DIST_ISO",
    "NB_ITER",
    "ARRET",
    "NB_REDE",
    "SIGNE",
    "RDEV_1",
    "RDEV_2",
    "RDEV_3",
    "RISO",
    "EPSIVPLA",
    "IND_1",
    "IND_2",
    "IND_3",
    "IND_4",
];

const CALC_OPTIONS: &[&str] = &[
    "THERMIQUE",
    "CONTRAINTE",
    "DEFORMATION",
    "ENERGIE",
    "CRITERES",
    "VARI_INTERNE",
    "PROPRIETES",
    "HYDRAULIQUE",
    "FORCE",
    "CHAM_UTIL",
];

fn calc_champ() -> Command {
    Command::new("CALC_CHAMP", "Compute element or nodal fields (stresses, strains, criteria, ...) of a result.")
        .produces_dyn(type_of_resultat)
        .reuse()
        .kw(with(
            kws![
                simp("MODELE").co(&[ConceptKind::Modele]),
                simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
                simp("CARA_ELEM").co(&[ConceptKind::CaraElem]),
                simp("RESULTAT").co(RESULTS).o(),
                simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
                simp("NUME_ORDRE").i().many(),
                simp("NUME_MODE").i().many(),
                simp("NOEUD_CMP").txt().many(),
                simp("NOM_CAS").txt(),
                simp("INST").r().many(),
                simp("FREQ").r().many(),
                simp("LIST_INST").co(&[ConceptKind::ListR8]),
                simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
                simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("GROUP_MA").txt().many(),
                simp("MAILLE").txt().many(),
                simp("CONTRAINTE").txt().many().one_of(CONTRAINTE),
                simp("DEFORMATION").txt().many().one_of(DEFORMATION),
                simp("ENERGIE").txt().many().one_of(ENERGIE),
                simp("CRITERES").txt().many().one_of(CRITERES),
                simp("VARI_INTERNE").txt().many().one_of(VARI_INTERNE),
                bloc(
                    is_in("VARI_INTERNE", &["VAEX_ELNO", "VAEX_ELGA", "VAEX_NOEU"]),
                    kws![simp("NOM_VARI").txt().many().one_of(NOM_VARI_VAEX).o()]
                ),
                simp("PROPRIETES").txt().many().one_of(&["MATE_ELGA", "MATE_ELEM"]),
                simp("HYDRAULIQUE").txt().many().one_of(&["FLHN_ELGA"]),
                simp("THERMIQUE").txt().many().one_of(&[
                    "TEMP_ELGA",
                    "FLUX_ELGA",
                    "FLUX_ELNO",
                    "FLUX_NOEU",
                    "GRAT_ELGA",
                    "GRAT_ELNO",
                    "GRAT_NOEU",
                    "HYDR_ELGA",
                    "HYDR_ELNO",
                    "HYDR_NOEU",
                    "SOUR_ELGA",
                    "ETHE_ELEM",
                    "HHO_TEMP",
                ]),
                simp("FORCE").txt().many().one_of(&["FORC_NODA", "REAC_NODA"]),
                fact(
                    "EXCIT",
                    kws![
                        simp("CHARGE").co(&[ConceptKind::CharMeca]).o(),
                        simp("FONC_MULT").co(FUNCS),
                        simp("COEF_MULT").r(),
                        simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&["FIXE_CSTE", "FIXE_PILO", "SUIV", "DIDI"]),
                    ]
                )
                .many()
                .rules(vec![exclus(&["FONC_MULT", "COEF_MULT"])]),
                fact(
                    "CHAM_UTIL",
                    kws![
                        simp("NOM_CHAM").txt().o(),
                        simp("FORMULE").co(&[ConceptKind::Formule]).many(),
                        simp("CRITERE").txt().one_of(&["TRACE", "VMIS", "INVA_2"]),
                        simp("NORME").txt().one_of(&["L2", "FROBENIUS"]),
                        simp("NUME_CHAM_RESU").i().o().val_min(1.0).val_max(20.0),
                    ]
                )
                .many()
                .rules(vec![un_parmi(&["FORMULE", "CRITERE", "NORME"])]),
                simp("INFO").i().d(1).one_of_i(&[1, 2]),
                simp("TITRE").txt(),
            ],
            crit_prec(),
        ))
        .rules(vec![
            exclus(&[
                "TOUT_ORDRE",
                "NUME_ORDRE",
                "INST",
                "FREQ",
                "NUME_MODE",
                "NOEUD_CMP",
                "LIST_INST",
                "LIST_FREQ",
                "LIST_ORDRE",
                "NOM_CAS",
            ]),
            present_absent("TOUT", &["GROUP_MA", "MAILLE"]),
            au_moins_un(CALC_OPTIONS),
        ])
}

// ------------------------------------------------------------------ CREA_CHAMP

const NOM_CHAM_CHARGE: &[&str] = &[
    ".CHME.EPSIN",
    ".CHME.F1D1D",
    ".CHME.F1D2D",
    ".CHME.F1D3D",
    ".CHME.F2D2D",
    ".CHME.F2D3D",
    ".CHME.F3D3D",
    ".CHME.FCO2D",
    ".CHME.FCO3D",
    ".CHME.FELEC",
    ".CHME.FL101",
    ".CHME.FL102",
    ".CHME.FLUX",
    ".CHME.FORNO",
    ".CHME.IMPE",
    ".CHME.ONDE",
    ".CHME.ONDPL",
    ".CHME.ONDPR",
    ".CHME.PESAN",
    ".CHME.PRESS",
    ".CHME.ROTAT",
    ".CHME.SIGIN",
    ".CHME.SIINT",
    ".CHME.VFACE",
];

const NOM_CHAM_FISSURE: &[&str] =
    &["LTNO", "LNNO", "GRLTNO", "GRLNNO", "STNO", "BASLOC", "GRI.LNNO", "GRI.LTNO", "GRI.GRLNNO", "GRI.GRLTNO"];

fn crea_champ_extr() -> Bloc {
    let resultat = with(
        kws![
            simp("NOM_CHAM").txt().o(),
            simp("TYPE_MAXI").txt().one_of(&["MAXI", "MINI", "MAXI_ABS", "MINI_ABS", "NORM_TRAN"]),
            bloc(
                is_in("TYPE_MAXI", &["MAXI_ABS", "MINI_ABS"]),
                kws![simp("TYPE_RESU").txt().d("VALE").one_of(&["VALE", "INST", "VALE_ABS"])]
            ),
            bloc(
                is_in("TYPE_MAXI", &["MAXI", "MINI", "NORM_TRAN"]),
                kws![simp("TYPE_RESU").txt().d("VALE").one_of(&["VALE", "INST"])]
            ),
            bloc(
                present("TYPE_MAXI"),
                kws![
                    simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
                    simp("LIST_INST").co(&[ConceptKind::ListR8]),
                    simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
                    simp("NUME_ORDRE").i().many(),
                    simp("INST").r().many(),
                    simp("FREQ").r().many(),
                    simp("NUME_MODE").i().many(),
                    simp("NOEUD_CMP").txt().many(),
                    simp("NOM_CAS").txt().many(),
                    simp("ANGLE").r().many(),
                ]
            )
            .rules(vec![exclus(&[
                "TOUT_ORDRE",
                "LIST_INST",
                "LIST_FREQ",
                "NUME_ORDRE",
                "INST",
                "FREQ",
                "NUME_MODE",
                "NOEUD_CMP",
                "NOM_CAS",
                "ANGLE",
            ])]),
            bloc(
                absent("TYPE_MAXI"),
                kws![
                    simp("NUME_ORDRE").i(),
                    simp("INST").r(),
                    simp("FREQ").r(),
                    simp("NUME_MODE").i(),
                    simp("NOEUD_CMP").txt().max(2),
                    simp("NOM_CAS").txt(),
                    simp("ANGLE").r(),
                    bloc(present("INST"), kws![simp("INTERPOL").txt().d("NON").one_of(&["NON", "LIN"])]),
                ]
            )
            .rules(vec![un_parmi(&[
                "NUME_ORDRE",
                "INST",
                "FREQ",
                "NUME_MODE",
                "NOEUD_CMP",
                "NOM_CAS",
                "ANGLE"
            ])]),
        ],
        crit_prec(),
    );
    bloc(
        eq("OPERATION", "EXTR"),
        kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]),
            simp("FISSURE").co(&[ConceptKind::FissXfem]),
            simp("RESULTAT").co(STORED_RESULTS),
            simp("TABLE").co(&[ConceptKind::Table]),
            simp("CHARGE").co(&[ConceptKind::CharMeca]),
            bloc(
                and(vec![present("MAILLAGE"), absent("TABLE")]),
                kws![simp("NOM_CHAM").txt().o().one_of(&["GEOMETRIE", "ABSC_CURV"])]
            ),
            bloc(present("CHARGE"), kws![simp("NOM_CHAM").txt().o().one_of(NOM_CHAM_CHARGE)]),
            bloc(present("FISSURE"), kws![simp("NOM_CHAM").txt().o().one_of(NOM_CHAM_FISSURE)]),
            bloc(present("TABLE"), kws![simp("MODELE").co(&[ConceptKind::Modele])]),
            bloc(present("RESULTAT"), resultat),
        ],
    )
    .rules(vec![
        au_moins_un(&["MAILLAGE", "FISSURE", "RESULTAT", "TABLE", "CHARGE"]),
        present_absent("MAILLAGE", &["FISSURE", "RESULTAT", "CHARGE"]),
        present_absent("FISSURE", &["MAILLAGE", "RESULTAT", "TABLE", "CHARGE"]),
        present_absent("RESULTAT", &["FISSURE", "MAILLAGE", "TABLE", "CHARGE"]),
        present_absent("TABLE", &["RESULTAT", "FISSURE", "CHARGE"]),
        present_absent("CHARGE", &["MAILLAGE", "TABLE", "RESULTAT", "FISSURE"]),
    ])
}

fn crea_champ() -> Command {
    Command::new("CREA_CHAMP", "Create a field (nodal, by element or constant per cell) by assignment, extraction, ...")
        .produces_dyn(crea_champ_type)
        .reuse()
        .kw(kws![
            bloc(is_in("OPERATION", &["ASSE", "COMB"]), kws![simp("CHAM_GD").co(CHAM_GD)]),
            simp("TYPE_CHAM").txt().o(),
            simp("CHAM_NO").co(&[ConceptKind::ChamNo]),
            simp("PROL_ZERO").txt().d("NON").one_of(OUI_NON),
            simp("OPTION").txt(),
            simp("OPERATION").txt().o().one_of(&[
                "AFFE",
                "ASSE",
                "ASSE_DEPL",
                "EVAL",
                "EXTR",
                "DISC",
                "NORMALE",
                "R2C",
                "C2R",
                "COMB",
            ]),
            bloc(
                eq("OPERATION", "NORMALE"),
                kws![simp("MODELE").co(&[ConceptKind::Modele]).o(), simp("GROUP_MA").txt().many().o()]
            ),
            bloc(
                eq("OPERATION", "AFFE"),
                kws![
                    simp("MAILLAGE").co(&[ConceptKind::Maillage]),
                    simp("MODELE").co(&[ConceptKind::Modele]),
                    fact(
                        "AFFE",
                        kws![
                            simp("TOUT").txt().one_of(&["OUI"]),
                            simp("GROUP_MA").txt().many(),
                            simp("GROUP_NO").txt().many(),
                            simp("MAILLE").txt().many(),
                            simp("NOEUD").txt().many(),
                            simp("NOM_CMP").txt().many().o(),
                            simp("VALE").r().many(),
                            simp("VALE_I").i().many(),
                            simp("VALE_C").c().many(),
                            simp("VALE_F").co(FUNCS).many(),
                        ]
                    )
                    .o()
                    .many()
                    .rules(vec![
                        au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO", "MAILLE", "NOEUD"]),
                        un_parmi(&["VALE", "VALE_I", "VALE_C", "VALE_F"]),
                    ]),
                ]
            )
            .rules(vec![un_parmi(&["MAILLAGE", "MODELE"])]),
            bloc(
                eq("OPERATION", "ASSE"),
                kws![
                    simp("MAILLAGE").co(&[ConceptKind::Maillage]),
                    simp("MODELE").co(&[ConceptKind::Modele]),
                    fact(
                        "ASSE",
                        kws![
                            simp("TOUT").txt().one_of(&["OUI"]),
                            simp("GROUP_MA").txt().many(),
                            simp("GROUP_NO").txt().many(),
                            simp("CHAM_GD").co(CHAM_GD).o(),
                            simp("NOM_CMP").txt().many(),
                            simp("NOM_CMP_RESU").txt().many(),
                            simp("CUMUL").txt().d("NON").one_of(OUI_NON),
                            simp("COEF_R").r().d(1.0),
                            simp("COEF_C").c(),
                        ]
                    )
                    .o()
                    .many()
                    .rules(vec![
                        au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO"]),
                        present_present("NOM_CMP_RESU", &["NOM_CMP"]),
                    ]),
                ]
            )
            .rules(vec![un_parmi(&["MAILLAGE", "MODELE"])]),
            bloc(
                eq("OPERATION", "COMB"),
                kws![fact("COMB", kws![simp("CHAM_GD").co(&[ConceptKind::ChamNo]).o(), simp("COEF_R").r().o()])
                    .o()
                    .many()]
            ),
            bloc(
                eq("OPERATION", "EVAL"),
                kws![simp("CHAM_F").co(CHAM_GD).o(), simp("CHAM_PARA").co(CHAM_GD).many().o()]
            ),
            bloc(
                eq("OPERATION", "ASSE_DEPL"),
                kws![
                    simp("CHAM_GD").co(CHAM_GD).o(),
                    simp("MODELE").co(&[ConceptKind::Modele]).o(),
                    simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
                ]
            ),
            bloc(eq("OPERATION", "R2C"), kws![simp("CHAM_GD").co(CHAM_GD).o()]),
            bloc(
                eq("OPERATION", "C2R"),
                kws![
                    simp("CHAM_GD").co(CHAM_GD).o(),
                    simp("PARTIE").txt().o().one_of(&["REEL", "IMAG", "MODULE", "PHASE"]),
                ]
            ),
            bloc(
                eq("OPERATION", "DISC"),
                kws![simp("MODELE").co(&[ConceptKind::Modele]), simp("CHAM_GD").co(CHAM_GD).o()]
            ),
            crea_champ_extr(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            simp("TITRE").txt(),
        ])
}

// ------------------------------------------------------------------ MODI_REPERE

/// Cells or nodes where a frame is assigned (exactly one selector).
fn repere_location() -> Vec<Entry> {
    kws![
        simp("TOUT").txt().one_of(&["OUI"]),
        simp("GROUP_MA").txt().many(),
        simp("GROUP_NO").txt().many(),
        simp("MAILLE").txt().many(),
        simp("NOEUD").txt().many(),
    ]
}

const REPERE_LOC: &[&str] = &["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"];

fn modi_repere() -> Command {
    let extraction = with(
        kws![
            simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
            simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
            simp("NUME_ORDRE").i().many(),
            simp("NUME_MODE").i().many(),
            simp("NOEUD_CMP").txt().many(),
            simp("NOM_CAS").txt(),
            simp("INST").r().many(),
            simp("FREQ").r().many(),
            simp("LIST_INST").co(&[ConceptKind::ListR8]),
            simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
            fact(
                "MODI_CHAM",
                kws![
                    simp("TYPE_CHAM").txt().o().one_of(&["VECT_2D", "VECT_3D", "TENS_2D", "TENS_3D", "COQUE_GENE"]),
                    simp("NOM_CHAM").txt().o(),
                    bloc(eq("TYPE_CHAM", "VECT_2D"), kws![simp("NOM_CMP").txt().min(2).max(2)]),
                    bloc(eq("TYPE_CHAM", "VECT_3D"), kws![simp("NOM_CMP").txt().min(3).max(6)]),
                    bloc(eq("TYPE_CHAM", "TENS_2D"), kws![simp("NOM_CMP").txt().min(4).max(4)]),
                    bloc(eq("TYPE_CHAM", "TENS_3D"), kws![simp("NOM_CMP").txt().min(6).max(6)]),
                    bloc(eq("TYPE_CHAM", "COQUE_GENE"), kws![simp("NOM_CMP").txt().min(8).max(8)]),
                ]
            )
            .o()
            .many(),
        ],
        crit_prec(),
    );
    Command::new("MODI_REPERE", "Express the fields of a result or a field in another frame.")
        .produces_dyn(modi_repere_type)
        .reuse()
        .kw(kws![
            simp("CHAM_GD").co(CHAM_GD),
            simp("RESULTAT").co(RESULTS),
            bloc(present("RESULTAT"), extraction).rules(vec![exclus(&[
                "TOUT_ORDRE",
                "NUME_ORDRE",
                "INST",
                "FREQ",
                "LIST_ORDRE",
                "NUME_MODE",
                "NOEUD_CMP",
                "LIST_INST",
                "LIST_FREQ",
                "NOM_CAS",
            ])]),
            simp("REPERE").txt().one_of(&[
                "UTILISATEUR",
                "CYLINDRIQUE",
                "COQUE",
                "GLOBAL_UTIL",
                "COQUE_INTR_UTIL",
                "COQUE_UTIL_INTR",
                "COQUE_UTIL_CYL",
            ]),
            bloc(
                is_in("REPERE", &["CYLINDRIQUE", "COQUE_UTIL_CYL"]),
                kws![fact(
                    "AFFE",
                    with(kws![simp("ORIGINE").r().min(2).max(3), simp("AXE_Z").r().min(3).max(3)], repere_location())
                )
                .o()
                .many()
                .rules(vec![un_parmi(REPERE_LOC)])]
            ),
            bloc(
                eq("REPERE", "UTILISATEUR"),
                kws![fact(
                    "AFFE",
                    with(
                        kws![
                            simp("ANGL_NAUT").r().max(3),
                            simp("VECT_X").r().min(3).max(3),
                            simp("VECT_Y").r().min(3).max(3),
                        ],
                        repere_location()
                    )
                )
                .o()
                .many()
                .rules(vec![
                    un_parmi(&["ANGL_NAUT", "VECT_X"]),
                    ensemble(&["VECT_X", "VECT_Y"]),
                    un_parmi(REPERE_LOC),
                ])]
            ),
            bloc(
                eq("REPERE", "COQUE"),
                kws![fact(
                    "AFFE",
                    with(
                        kws![simp("ANGL_REP").r().min(2).max(2), simp("VECTEUR").r().min(3).max(3)],
                        repere_location()
                    )
                )
                .o()
                .many()
                .rules(vec![un_parmi(&["ANGL_REP", "VECTEUR"]), un_parmi(REPERE_LOC)])]
            ),
            bloc(
                is_in("REPERE", &["GLOBAL_UTIL", "COQUE_INTR_UTIL", "COQUE_UTIL_INTR"]),
                kws![fact("AFFE", repere_location()).o().many().rules(vec![un_parmi(REPERE_LOC)])]
            ),
            simp("TITRE").txt(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
        .rules(vec![un_parmi(&["CHAM_GD", "RESULTAT"])])
}

// ------------------------------------------------------------------ CREA_RESU

/// The results CREA_RESU makes (the other TYPE_RESU stop by name).
const CREA_RESU_TYPES: &[(&str, ConceptKind)] = &[
    ("EVOL_ELAS", ConceptKind::EvolElas),
    ("EVOL_NOLI", ConceptKind::EvolNoli),
    ("EVOL_THER", ConceptKind::EvolTher),
    ("EVOL_VARC", ConceptKind::EvolVarc),
    ("EVOL_SECH", ConceptKind::EvolSech),
];

/// CREA_RESU: TYPE_RESU decides the type of the result.
fn crea_resu_type(a: &Args) -> Result<ConceptKind> {
    let t = a.text("TYPE_RESU").ok_or_else(|| missing(a, "TYPE_RESU"))?;
    CREA_RESU_TYPES.iter().find(|(n, _)| *n == t).map(|(_, k)| *k).ok_or_else(|| {
        Error::unsupported(format!(
            "CREA_RESU TYPE_RESU='{t}' is not supported yet (EVOL_ELAS, EVOL_NOLI, EVOL_THER, EVOL_VARC and \
             EVOL_SECH are)"
        ))
        .at(a.span_of("TYPE_RESU"))
    })
}

fn crea_resu() -> Command {
    const EVOLS: &[ConceptKind] = &[
        ConceptKind::EvolElas,
        ConceptKind::EvolNoli,
        ConceptKind::EvolTher,
        ConceptKind::EvolVarc,
        ConceptKind::EvolSech,
    ];
    const MECA: &[ConceptKind] = &[ConceptKind::CharMeca, ConceptKind::CharCineMeca];
    let excit = |loads: &'static [ConceptKind], charge: &'static [&'static str]| {
        let mut kw = kws![simp("CHARGE").co(loads).o(), simp("FONC_MULT").co(FUNCS)];
        if !charge.is_empty() {
            kw.push(simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(charge).into());
        }
        fact("EXCIT", kw).many()
    };
    let affe = |t: &'static str| and(vec![eq("OPERATION", "AFFE"), eq("TYPE_RESU", t)]);
    Command::new("CREA_RESU", "Create or extend a result from fields.").produces_dyn(crea_resu_type).reuse().kw(kws![
        simp("OPERATION").txt().o().one_of(&[
            "AFFE",
            "ASSE",
            "PERM_CHAM",
            "PROL_RTZ",
            "PREP_VARC",
            "KUCV",
            "CONV_CHAR",
            "CONV_RESU",
        ]),
        // The other types of Code_Aster's (MULT_ELAS, MODE_MECA, DYNA_TRANS, ...) stop here by name.
        simp("TYPE_RESU").txt().o().one_of(&["EVOL_ELAS", "EVOL_NOLI", "EVOL_THER", "EVOL_VARC", "EVOL_SECH"]),
        bloc(
            eq("OPERATION", "AFFE"),
            kws![
                simp("RESULTAT").co(EVOLS),
                fact(
                    "AFFE",
                    kws![
                        simp("CHAM_GD").co(CHAM_GD).o(),
                        simp("MODELE").co(&[ConceptKind::Modele]),
                        simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
                        simp("CARA_ELEM").co(&[ConceptKind::CaraElem]),
                        simp("INST").r().many(),
                        simp("LIST_INST").co(&[ConceptKind::ListR8]),
                        simp("NUME_INIT").i().val_min(1.0),
                        simp("NUME_FIN").i().val_min(1.0),
                        simp("PRECISION").r().d(0.0),
                        simp("CRITERE").txt().d("RELATIF").one_of(&["RELATIF", "ABSOLU"]),
                        simp("NOM_CHAM").txt().o(),
                    ]
                )
                .o()
                .many()
                .rules(vec![un_parmi(&["INST", "LIST_INST"])]),
            ]
        ),
        bloc(affe("EVOL_ELAS"), kws![excit(MECA, &["FIXE_CSTE"])]),
        bloc(affe("EVOL_THER"), kws![excit(&[ConceptKind::CharTher, ConceptKind::CharCineTher], &[])]),
        bloc(affe("EVOL_NOLI"), kws![excit(MECA, &["FIXE_CSTE", "FIXE_PILO", "SUIV", "DIDI"])]),
        bloc(
            eq("OPERATION", "ASSE"),
            kws![fact("ASSE", kws![simp("RESULTAT").co(&[ConceptKind::EvolTher]).o(), simp("TRANSLATION").r().d(0.0)])
                .o()
                .many()]
        ),
        bloc(
            eq("OPERATION", "PROL_RTZ"),
            kws![fact(
                "PROL_RTZ",
                kws![
                    simp("MAILLAGE_FINAL").co(&[ConceptKind::Maillage]).o(),
                    simp("TABLE").co(&[ConceptKind::Table]).o(),
                    simp("INST").r().many(),
                    simp("LIST_INST").co(&[ConceptKind::ListR8]),
                    bloc(or(vec![present("INST"), present("LIST_INST")]), crit_prec()),
                    simp("PROL_DROITE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
                    simp("PROL_GAUCHE").txt().d("EXCLU").one_of(&["CONSTANT", "LINEAIRE", "EXCLU"]),
                    simp("REPERE").txt().o().one_of(&["CYLINDRIQUE"]),
                    simp("ORIGINE").r().min(3).max(3).o(),
                    simp("AXE_Z").r().min(3).max(3).o(),
                ]
            )
            .o()
            .rules(vec![exclus(&["INST", "LIST_INST"])])]
        ),
    ])
}

pub fn commands() -> Vec<Command> {
    vec![calc_champ(), crea_champ(), crea_resu(), modi_repere()]
}
