//! Results and fields to and from files: IMPR_RESU, LIRE_RESU, LIRE_CHAMP.

use super::common::*;
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::diag::{Error, Result};
use crate::kws;

// ------------------------------------------------------------------ IMPR_RESU

/// Selection of fields and instants of a result to print.
fn impr_extraction() -> Bloc {
    bloc(
        present("RESULTAT"),
        kws![
            simp("TOUT_CHAM").txt().one_of(OUI_NON),
            simp("NOM_CHAM").txt().many(),
            simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
            simp("NUME_ORDRE").i().many(),
            simp("NUME_MODE").i().many(),
            simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
            simp("NOEUD_CMP").txt().many(),
            simp("NOM_CAS").txt().many(),
            simp("ANGLE").r().many(),
            simp("FREQ").r().many(),
            simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
            simp("INST").r().many(),
            simp("LIST_INST").co(&[ConceptKind::ListR8]),
            bloc(
                or(vec![
                    present("ANGLE"),
                    present("FREQ"),
                    present("LIST_FREQ"),
                    present("INST"),
                    present("LIST_INST"),
                ]),
                crit_prec()
            ),
        ],
    )
    .rules(vec![
        exclus(&["TOUT_CHAM", "NOM_CHAM"]),
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
            "ANGLE",
        ]),
    ])
}

/// What every RESU occurrence of IMPR_RESU starts with.
fn impr_sources() -> Vec<Entry> {
    kws![
        simp("MAILLAGE").co(&[ConceptKind::Maillage]),
        simp("CHAM_GD").co(CHAM_GD),
        simp("RESULTAT").co(STORED_RESULTS),
        impr_extraction(),
    ]
}

fn impr_topologie() -> Bloc {
    bloc(
        or(vec![present("CHAM_GD"), present("RESULTAT")]),
        kws![
            simp("TOUT").txt().one_of(&["OUI"]),
            simp("GROUP_NO").txt().many(),
            simp("MAILLE").txt().many(),
            simp("GROUP_MA").txt().many(),
        ],
    )
}

fn impr_resu() -> Command {
    let base_rules = || vec![au_moins_un(&["CHAM_GD", "RESULTAT", "MAILLAGE"]), exclus(&["CHAM_GD", "RESULTAT"])];
    let resu_med = with(
        impr_sources(),
        kws![
            simp("INFO_MAILLAGE").txt().d("NON").one_of(OUI_NON),
            simp("PARTIE").txt().one_of(&["REEL", "IMAG", "MODULE", "PHASE"]),
            simp("IMPR_NOM_VARI").txt().d("OUI").one_of(OUI_NON),
            bloc(present("RESULTAT"), kws![simp("NOM_PARA").txt().many()]),
            simp("TOUT_CMP").txt().one_of(&["OUI"]),
            simp("NOM_CMP").txt().many(),
            bloc(
                or(vec![present("CHAM_GD"), present("RESULTAT")]),
                kws![simp("NOM_CHAM_MED").txt().many(), simp("NOM_RESU_MED").txt()]
            )
            .rules(vec![exclus(&["NOM_CHAM_MED", "NOM_RESU_MED"])]),
            simp("TOUT").txt().one_of(&["OUI"]),
            simp("GROUP_NO").txt().many(),
            simp("MAILLE").txt().many(),
            simp("GROUP_MA").txt().many(),
            simp("SOUS_TITRE").txt(),
        ],
    );
    let resu_resultat = with(
        impr_sources(),
        kws![
            simp("PARTIE").txt().one_of(&["REEL", "IMAG", "MODULE", "PHASE"]),
            simp("TOUT_PARA").txt().one_of(OUI_NON),
            simp("NOM_PARA").txt().many(),
            simp("FORM_TABL").txt().d("NON").one_of(&["OUI", "NON", "EXCEL"]),
            simp("TOUT_CMP").txt().one_of(&["OUI"]),
            simp("NOM_CMP").txt().many(),
            impr_topologie(),
            simp("VALE_MAX").txt().one_of(&["OUI"]),
            simp("VALE_MIN").txt().one_of(&["OUI"]),
            simp("BORNE_SUP").r(),
            simp("BORNE_INF").r(),
            simp("IMPR_COOR").txt().d("NON").one_of(OUI_NON),
            simp("FORMAT_R").txt().d("1PE21.14"),
            simp("SOUS_TITRE").txt(),
        ],
    );
    let resu_gmsh = with(
        impr_sources(),
        kws![
            simp("PARTIE").txt().one_of(&["REEL", "IMAG"]),
            simp("MAILLE").txt().many(),
            simp("GROUP_MA").txt().many(),
            simp("TYPE_CHAM").txt().d("SCALAIRE").one_of(&["VECT_2D", "VECT_3D", "SCALAIRE", "TENS_2D", "TENS_3D"]),
            bloc(eq("TYPE_CHAM", "SCALAIRE"), kws![simp("NOM_CMP").txt().many()]),
            bloc(eq("TYPE_CHAM", "VECT_2D"), kws![simp("NOM_CMP").txt().min(2).max(2).o()]),
            bloc(eq("TYPE_CHAM", "VECT_3D"), kws![simp("NOM_CMP").txt().min(3).max(3).o()]),
            bloc(eq("TYPE_CHAM", "TENS_2D"), kws![simp("NOM_CMP").txt().min(4).max(4).o()]),
            bloc(eq("TYPE_CHAM", "TENS_3D"), kws![simp("NOM_CMP").txt().min(6).max(6).o()]),
            simp("SOUS_TITRE").txt(),
        ],
    );
    let resu_ideas = with(
        impr_sources(),
        kws![
            simp("TOUT_CMP").txt().one_of(&["OUI"]),
            simp("NOM_CMP").txt().many(),
            impr_topologie(),
            simp("SOUS_TITRE").txt(),
        ],
    );
    let resu_aster = with(impr_sources(), kws![simp("FORMAT_R").txt().d("1PE21.14"), simp("SOUS_TITRE").txt()]);

    let mut gmsh_version = simp("VERSION").r().d(1.2);
    gmsh_version.allowed = Some(vec![Lit::R(1.0), Lit::R(1.2)]);

    Command::new("IMPR_RESU", "Print a mesh, fields or results (MED, RESULTAT, ASTER, GMSH, IDEAS formats).").kw(kws![
        simp("FORMAT").txt().d("MED").one_of(&["RESULTAT", "IDEAS", "ASTER", "MED", "GMSH"]),
        simp("PROC0").txt().one_of(OUI_NON),
        bloc(is_in("FORMAT", &["RESULTAT", "IDEAS", "ASTER", "GMSH"]), kws![simp("MODELE").co(&[ConceptKind::Modele])]),
        bloc(eq("FORMAT", "RESULTAT"), kws![simp("UNITE").i().d(8)]),
        bloc(eq("FORMAT", "IDEAS"), kws![simp("UNITE").i().d(30), simp("VERSION").i().d(5).one_of_i(&[4, 5])]),
        bloc(eq("FORMAT", "ASTER"), kws![simp("UNITE").i().d(26)]),
        bloc(
            eq("FORMAT", "MED"),
            kws![
                simp("UNITE").i().d(80),
                simp("VERSION_MED").txt().d("3.3.1").one_of(&["3.3.1", "4.0.0", "4.1.0"]),
                simp("FICHIER_UNIQUE").txt().d("NON").one_of(OUI_NON),
            ]
        ),
        bloc(eq("FORMAT", "GMSH"), kws![simp("UNITE").i().d(37), gmsh_version]),
        bloc(
            eq("FORMAT", "MED"),
            kws![fact("RESU", resu_med).o().many().rules({
                let mut r = base_rules();
                r.push(exclus(&["TOUT_CMP", "NOM_CMP"]));
                r
            })]
        ),
        bloc(
            eq("FORMAT", "RESULTAT"),
            kws![fact("RESU", resu_resultat).many().rules({
                let mut r = base_rules();
                r.push(exclus(&["TOUT_PARA", "NOM_PARA"]));
                r.push(exclus(&["TOUT_CMP", "NOM_CMP"]));
                r
            })]
        ),
        bloc(eq("FORMAT", "GMSH"), kws![fact("RESU", resu_gmsh).many().rules(base_rules())]),
        bloc(
            eq("FORMAT", "IDEAS"),
            kws![fact("RESU", resu_ideas).many().rules({
                let mut r = base_rules();
                r.push(exclus(&["TOUT_CMP", "NOM_CMP"]));
                r
            })]
        ),
        bloc(eq("FORMAT", "ASTER"), kws![fact("RESU", resu_aster).many().rules(base_rules())]),
        simp("INFO").i().d(1).one_of_i(&[1, 2]),
    ])
}

// ------------------------------------------------------------------ LIRE_RESU, LIRE_CHAMP

/// LIRE_RESU: TYPE_RESU decides the type of the result.
fn lire_resu_type(a: &Args) -> Result<ConceptKind> {
    match a.text("TYPE_RESU") {
        Some("EVOL_ELAS") => Ok(ConceptKind::EvolElas),
        Some("EVOL_NOLI") => Ok(ConceptKind::EvolNoli),
        Some("EVOL_THER") => Ok(ConceptKind::EvolTher),
        Some(other) => Err(Error::unsupported(format!(
            "LIRE_RESU TYPE_RESU='{other}' is not supported yet (EVOL_ELAS, EVOL_NOLI and EVOL_THER are)"
        ))
        .at(a.span_of("TYPE_RESU"))),
        None => Err(missing(a, "TYPE_RESU")),
    }
}

fn lire_resu() -> Command {
    let excit = |loads: &'static [ConceptKind], extra: Vec<Entry>| {
        fact("EXCIT", with(kws![simp("CHARGE").co(loads).o(), simp("FONC_MULT").co(FUNCS),], extra)).many()
    };
    const MECA: &[ConceptKind] = &[ConceptKind::CharMeca, ConceptKind::CharCineMeca];
    Command::new("LIRE_RESU", "Read the fields of a result from a file (MED) into a result concept.")
        .produces_dyn(lire_resu_type)
        .reuse()
        .kw(with(
            kws![
                simp("TYPE_RESU").txt().o().one_of(&[
                    "EVOL_THER",
                    "EVOL_ELAS",
                    "EVOL_NOLI",
                    "MODE_MECA",
                    "MODE_MECA_C",
                    "DYNA_TRANS",
                    "DYNA_HARMO",
                    "EVOL_CHAR",
                    "EVOL_VARC",
                    "MODE_EMPI",
                    "EVOL_SECH",
                ]),
                simp("FORMAT").txt().o().one_of(&["IDEAS", "IDEAS_DS58", "MED"]),
                simp("INFO").i().one_of_i(&[1, 2]),
                simp("TITRE").txt(),
                simp("RESULTAT").co(RESULTS),
                simp("MAILLAGE").co(&[ConceptKind::Maillage]),
                simp("MODELE").co(&[ConceptKind::Modele]),
                simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
                simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
                simp("NUME_ORDRE").i().many(),
                simp("INST").r().many(),
                simp("LIST_INST").co(&[ConceptKind::ListR8]),
                simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
                simp("FREQ").r().many(),
                simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
                bloc(
                    or(vec![present("INST"), present("LIST_INST"), present("FREQ"), present("LIST_FREQ")]),
                    crit_prec()
                ),
                bloc(
                    eq("TYPE_RESU", "EVOL_ELAS"),
                    kws![excit(MECA, kws![simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&["FIXE_CSTE"])])]
                ),
                bloc(
                    eq("TYPE_RESU", "EVOL_THER"),
                    kws![excit(&[ConceptKind::CharTher, ConceptKind::CharCineTher], kws![])]
                ),
                bloc(
                    eq("TYPE_RESU", "EVOL_NOLI"),
                    kws![
                        super::solve::comportement(),
                        simp("VERI_VARI").txt().d("OUI").one_of(OUI_NON),
                        excit(
                            MECA,
                            kws![simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&[
                                "FIXE_CSTE",
                                "FIXE_PILO",
                                "SUIV",
                                "DIDI"
                            ])]
                        ),
                    ]
                ),
                bloc(
                    eq("FORMAT", "MED"),
                    kws![
                        simp("UNITE").i().d(81),
                        fact(
                            "FORMAT_MED",
                            kws![
                                simp("NOM_CHAM").txt().o(),
                                simp("NOM_CHAM_MED").txt(),
                                simp("NOM_RESU").txt(),
                                simp("NOM_CMP").txt().many(),
                                simp("NOM_CMP_MED").txt().many(),
                            ]
                        )
                        .o()
                        .many()
                        .rules(vec![ensemble(&["NOM_CMP", "NOM_CMP_MED"]), un_parmi(&["NOM_CHAM_MED", "NOM_RESU"])]),
                        simp("PROL_ZERO").txt().d("OUI").one_of(OUI_NON),
                    ]
                ),
                bloc(is_in("FORMAT", &["IDEAS", "IDEAS_DS58"]), kws![simp("UNITE").i().d(19)]),
                // The IDEAS formats' keywords, so that a file using them stops on FORMAT by name.
                bloc(
                    eq("FORMAT", "IDEAS_DS58"),
                    kws![
                        simp("NOM_CHAM").txt().many(),
                        fact(
                            "REDEFI_ORIENT",
                            kws![
                                simp("CODE_DIR").i().one_of_i(&[1, 2, 3]),
                                simp("DIRECTION").r().min(3).max(3),
                                simp("NOEUD").txt().many(),
                            ]
                        )
                        .many()
                    ]
                ),
                bloc(
                    eq("FORMAT", "IDEAS"),
                    kws![
                        simp("NB_VARI").i(),
                        simp("NOM_CHAM").txt().o().many(),
                        fact(
                            "FORMAT_IDEAS",
                            kws![
                                simp("NOM_CHAM").txt().o(),
                                simp("NUME_DATASET").i().one_of_i(&[55, 57, 2414]),
                                simp("RECORD_3").i().max(10),
                                simp("RECORD_6").i().max(10),
                                simp("RECORD_9").i().max(10),
                                simp("POSI_ORDRE").i().min(2).max(2).o(),
                                simp("POSI_NUME_MODE").i().min(2).max(2),
                                simp("POSI_MASS_GENE").i().min(2).max(2),
                                simp("POSI_AMOR_GENE").i().min(2).max(2),
                                simp("POSI_INST").i().min(2).max(2),
                                simp("POSI_FREQ").i().min(2).max(2),
                                simp("NOM_CMP").txt().o().many(),
                            ]
                        )
                        .many()
                        .rules(vec![un_parmi(&["POSI_INST", "POSI_FREQ"])]),
                    ]
                ),
            ],
            vec![],
        ))
        .rules(vec![
            un_parmi(&["MAILLAGE", "MODELE"]),
            un_parmi(&["TOUT_ORDRE", "NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST", "FREQ", "LIST_FREQ"]),
        ])
}

/// LIRE_CHAMP: the location part of TYPE_CHAM decides the kind of field.
fn lire_champ_type(a: &Args) -> Result<ConceptKind> {
    let t = a.text("TYPE_CHAM").ok_or_else(|| missing(a, "TYPE_CHAM"))?;
    match t.split('_').next().unwrap_or("") {
        "NOEU" => Ok(ConceptKind::ChamNo),
        "CART" => Ok(ConceptKind::Carte),
        "ELEM" | "ELGA" | "ELNO" => Ok(ConceptKind::ChamElem),
        _ => Err(Error::catalog(format!("TYPE_CHAM '{t}' must start with NOEU_, ELEM_, ELGA_, ELNO_ or CART_"))
            .at(a.span_of("TYPE_CHAM"))),
    }
}

fn lire_champ() -> Command {
    Command::new("LIRE_CHAMP", "Read one field from a MED file into a field concept.").produces_dyn(lire_champ_type).kw(
        kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            simp("FORMAT").txt().d("MED").one_of(&["MED"]),
            simp("UNITE").i().d(81),
            bloc(
                eq("FORMAT", "MED"),
                kws![
                    simp("NOM_MED").txt().o(),
                    simp("NOM_CMP_IDEM").txt().one_of(&["OUI"]),
                    simp("NOM_CMP").txt().many(),
                    simp("NOM_CMP_MED").txt().many(),
                    simp("PROL_ZERO").txt().d("NON").one_of(OUI_NON),
                    simp("NUME_PT").i().many(),
                    simp("NUME_ORDRE").i().many(),
                    simp("INST").r(),
                    bloc(present("INST"), crit_prec()),
                    simp("NOM_MAIL_MED").txt(),
                ]
            )
            .rules(vec![
                un_parmi(&["NOM_CMP_IDEM", "NOM_CMP"]),
                present_present("NOM_CMP", &["NOM_CMP_MED"]),
                exclus(&["NUME_ORDRE", "INST"]),
                exclus(&["NUME_PT", "INST"]),
            ]),
            simp("TYPE_CHAM").txt().o(),
            // Code_Aster asks MODELE exactly when TYPE_CHAM starts with EL: the stage checks it.
            simp("MODELE").co(&[ConceptKind::Modele]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ],
    )
}

pub fn commands() -> Vec<Command> {
    vec![impr_resu(), lire_resu(), lire_champ()]
}
