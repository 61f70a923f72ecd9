use super::common::*;
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::diag::Result;
use crate::kws;

const INTERPOL: &[&str] = &["NON", "LIN", "LOG"];
const PROL: &[&str] = &["CONSTANT", "LINEAIRE", "EXCLU"];
const FUNC: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule];

fn interp_keywords(suffix: bool) -> Vec<Entry> {
    if suffix {
        kws![
            simp("INTERPOL_FONC").txt().max(2).one_of(INTERPOL),
            simp("PROL_DROITE_FONC").txt().one_of(PROL),
            simp("PROL_GAUCHE_FONC").txt().one_of(PROL),
        ]
    } else {
        kws![
            simp("INTERPOL").txt().max(2).one_of(INTERPOL),
            simp("PROL_DROITE").txt().one_of(PROL),
            simp("PROL_GAUCHE").txt().one_of(PROL),
        ]
    }
}

/// CALC_FONCTION returns a nappe when its inputs are nappes.
fn calc_fonction_type(a: &Args) -> Result<ConceptKind> {
    if a.has("COMB_C") {
        return Ok(ConceptKind::FonctionC);
    }
    for op in [
        "COMB",
        "ENVELOPPE",
        "FRACTILE",
        "MOYENNE",
        "ABS",
        "DERIVE",
        "INTEGRE",
        "INVERSE",
        "PUISSANCE",
        "EXTRACTION",
        "COMPOSE",
        "ASSE",
    ] {
        for occ in a.facts(op) {
            if occ.concepts("FONCTION").iter().any(|c| c.kind() == ConceptKind::Nappe) {
                return Ok(ConceptKind::Nappe);
            }
        }
    }
    Ok(ConceptKind::Fonction)
}

fn defi_fonction_type(a: &Args) -> Result<ConceptKind> {
    Ok(if a.has("VALE_C") { ConceptKind::FonctionC } else { ConceptKind::Fonction })
}

fn interp_type(a: &Args) -> Result<ConceptKind> {
    Ok(match a.concept("FONCTION").map(|c| c.kind()) {
        Some(ConceptKind::Nappe) => ConceptKind::Nappe,
        _ => ConceptKind::Fonction,
    })
}

fn lire_fonction_type(a: &Args) -> Result<ConceptKind> {
    Ok(match a.text("TYPE") {
        Some("NAPPE") => ConceptKind::Nappe,
        Some("FONCTION_C") => ConceptKind::FonctionC,
        _ => ConceptKind::Fonction,
    })
}

pub fn commands() -> Vec<Command> {
    vec![
        Command::new("DEFI_CONSTANTE", "A constant function.")
            .produces(ConceptKind::Fonction)
            .kw(kws![
                simp("NOM_RESU").txt().d("TOUTRESU"),
                simp("VALE").r().o(),
                simp("TITRE").txt().many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ]),
        Command::new("DEFI_FONCTION", "A function of one variable from tabulated points.")
            .produces_dyn(defi_fonction_type)
            .kw(with(
                kws![
                    simp("NOM_PARA").txt().o(),
                    simp("NOM_RESU").txt().d("TOUTRESU"),
                    simp("VALE").r().many().min(2),
                    simp("VALE_C").r().many().min(3),
                    simp("ABSCISSE").r().many(),
                    simp("ORDONNEE").r().many(),
                    simp("VALE_PARA").co(&[ConceptKind::ListR8]),
                    simp("VALE_FONC").co(&[ConceptKind::ListR8]),
                    simp("VERIF").txt().one_of(&["CROISSANT", "NON"]).d("CROISSANT"),
                    simp("TITRE").txt().many(),
                    simp("INFO").i().one_of_i(&[1, 2]).d(1),
                ],
                interp_keywords(false),
            ))
            .rules(vec![
                un_parmi(&["VALE", "VALE_C", "VALE_PARA", "ABSCISSE"]),
                ensemble(&["VALE_PARA", "VALE_FONC"]),
                ensemble(&["ABSCISSE", "ORDONNEE"]),
            ]),
        Command::new("DEFI_NAPPE", "A function of two variables: one function per parameter value.")
            .produces(ConceptKind::Nappe)
            .kw(with(
                with(
                    kws![
                        simp("NOM_PARA").txt().o(),
                        simp("NOM_RESU").txt().d("TOUTRESU"),
                        simp("PARA").r().many().o(),
                        simp("FONCTION").co(&[ConceptKind::Fonction]).many(),
                        fact("DEFI_FONCTION", with(kws![simp("VALE").r().many().o()], interp_keywords(false))).many(),
                        simp("NOM_PARA_FONC").txt(),
                        simp("VERIF").txt().one_of(&["CROISSANT", "NON"]).d("CROISSANT"),
                        simp("TITRE").txt().many(),
                        simp("INFO").i().one_of_i(&[1, 2]).d(1),
                    ],
                    interp_keywords(false),
                ),
                interp_keywords(true),
            ))
            .rules(vec![un_parmi(&["FONCTION", "DEFI_FONCTION"]), present_present("DEFI_FONCTION", &["NOM_PARA_FONC"])]),
        Command::new("DEFI_LIST_REEL", "A list of reals, given or by intervals.")
            .produces(ConceptKind::ListR8)
            .kw(kws![
                simp("DEBUT").r(),
                fact(
                    "INTERVALLE",
                    kws![simp("JUSQU_A").r().o(), simp("NOMBRE").i().val_min(1.0), simp("PAS").r()]
                )
                .many()
                .rules(vec![un_parmi(&["NOMBRE", "PAS"])]),
                simp("VALE").r().many(),
                simp("TITRE").txt().many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ])
            .rules(vec![un_parmi(&["DEBUT", "VALE"]), exclus(&["VALE", "INTERVALLE"]), ensemble(&["DEBUT", "INTERVALLE"])]),
        Command::new("DEFI_LIST_ENTI", "A list of integers, given or by intervals.")
            .produces(ConceptKind::ListIs)
            .kw(kws![
                simp("DEBUT").i(),
                fact(
                    "INTERVALLE",
                    kws![simp("JUSQU_A").i().o(), simp("NOMBRE").i().val_min(1.0), simp("PAS").i()]
                )
                .many()
                .rules(vec![un_parmi(&["NOMBRE", "PAS"])]),
                simp("VALE").i().many(),
                simp("TITRE").txt().many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ])
            .rules(vec![un_parmi(&["DEBUT", "VALE"]), exclus(&["VALE", "INTERVALLE"]), ensemble(&["DEBUT", "INTERVALLE"])]),
        Command::new(
            "FORMULE",
            "A function given by a Python expression over NOM_PARA; other keywords become names the expression can use.",
        )
        .produces(ConceptKind::Formule)
        .open()
        .kw(kws![simp("VALE").txt(), simp("VALE_C").txt(), simp("NOM_PARA").txt().many().o()])
        .rules(vec![un_parmi(&["VALE", "VALE_C"])]),
        Command::new("CALC_FONCTION", "Operations on functions and nappes: combinations, envelopes, fractiles, means, ...")
            .produces_dyn(calc_fonction_type)
            .kw(with(
                with(
                    kws![
                        fact("COMB", kws![simp("FONCTION").co(FUNC).o(), simp("COEF").r().o()]).many(),
                        fact("ENVELOPPE", kws![
                            simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe]).many().o(),
                            simp("CRITERE").txt().one_of(&["SUP", "INF"]).d("SUP"),
                        ]),
                        fact("FRACTILE", kws![
                            simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe]).many().o(),
                            simp("FRACT").r().o().val_min(0.0).val_max(1.0),
                        ]),
                        fact("MOYENNE", kws![simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe]).many().o()]),
                        fact("ABS", kws![simp("FONCTION").co(FUNC).o()]),
                        fact("INVERSE", kws![simp("FONCTION").co(&[ConceptKind::Fonction]).o()]),
                        fact("PUISSANCE", kws![simp("FONCTION").co(FUNC).o(), simp("EXPOSANT").i().d(1)]),
                        fact("DERIVE", kws![simp("FONCTION").co(&[ConceptKind::Fonction]).o()]),
                        fact("INTEGRE", kws![
                            simp("FONCTION").co(&[ConceptKind::Fonction]).o(),
                            simp("METHODE").txt().one_of(&["TRAPEZE", "SIMPSON"]).d("TRAPEZE"),
                            simp("COEF").r().d(0.0),
                        ]),
                        simp("LIST_PARA").co(&[ConceptKind::ListR8]),
                        simp("NOM_PARA").txt(),
                        simp("NOM_RESU").txt(),
                        simp("NOM_PARA_FONC").txt(),
                        simp("TITRE").txt().many(),
                        simp("INFO").i().one_of_i(&[1, 2]).d(1),
                    ],
                    interp_keywords(false),
                ),
                interp_keywords(true),
            ))
            .rules(vec![un_parmi(&["COMB", "ENVELOPPE", "FRACTILE", "MOYENNE", "ABS", "INVERSE", "PUISSANCE", "DERIVE", "INTEGRE"])]),
        Command::new("CALC_FONC_INTERP", "Tabulate a function, nappe or formula on a list of parameter values.")
            .produces_dyn(interp_type)
            .kw(with(
                with(
                    kws![
                        simp("FONCTION").co(FUNC).o(),
                        simp("VALE_PARA").r().many(),
                        simp("LIST_PARA").co(&[ConceptKind::ListR8]),
                        simp("NOM_RESU").txt().d("TOUTRESU"),
                        simp("NOM_PARA").txt(),
                        simp("VALE_PARA_FONC").r().many(),
                        simp("LIST_PARA_FONC").co(&[ConceptKind::ListR8]),
                        simp("NOM_PARA_FONC").txt(),
                        simp("TITRE").txt().many(),
                        simp("INFO").i().one_of_i(&[1, 2]).d(1),
                    ],
                    interp_keywords(false),
                ),
                interp_keywords(true),
            ))
            .rules(vec![un_parmi(&["VALE_PARA", "LIST_PARA"]), exclus(&["VALE_PARA_FONC", "LIST_PARA_FONC"])]),
        Command::new("IMPR_FONCTION", "Print functions, as tables of values, to a unit.").kw(kws![
            simp("FORMAT").txt().one_of(&["TABLEAU", "RESULTAT"]).d("TABLEAU"),
            simp("UNITE").i().d(8),
            fact(
                "COURBE",
                kws![
                    simp("FONCTION").co(FUNC),
                    simp("FONC_X").co(FUNC),
                    simp("FONC_Y").co(FUNC),
                    simp("LIST_PARA").co(&[ConceptKind::ListR8]),
                    simp("ABSCISSE").r().many(),
                    simp("ORDONNEE").r().many(),
                    simp("LEGENDE").txt(),
                ]
            )
            .o()
            .many()
            .rules(vec![un_parmi(&["FONCTION", "FONC_X", "ABSCISSE"]), ensemble(&["FONC_X", "FONC_Y"]), ensemble(&["ABSCISSE", "ORDONNEE"])]),
            simp("TITRE").txt().many(),
            simp("SOUS_TITRE").txt().many(),
            simp("SEPARATEUR").txt().d(" "),
            simp("COMMENTAIRE").txt().d("#"),
            simp("INFO").i().one_of_i(&[1, 2]).d(1),
        ]),
        Command::new("LIRE_FONCTION", "Read a function from columns of numbers in a text unit.")
            .produces_dyn(lire_fonction_type)
            .kw(with(
                kws![
                    simp("TYPE").txt().one_of(&["FONCTION", "FONCTION_C", "NAPPE"]).d("FONCTION"),
                    simp("FORMAT").txt().one_of(&["LIBRE"]).d("LIBRE"),
                    simp("SEPARATEUR").txt(),
                    simp("UNITE").i().o(),
                    simp("NOM_PARA").txt().o(),
                    simp("NOM_RESU").txt().d("TOUTRESU"),
                    simp("INDIC_PARA").i().min(2).max(2).dv(vec![Lit::I(1), Lit::I(1)]),
                    bloc(
                        eq("TYPE", "FONCTION"),
                        kws![simp("INDIC_RESU").i().min(2).max(2).dv(vec![Lit::I(1), Lit::I(2)])]
                    ),
                    bloc(
                        eq("TYPE", "NAPPE"),
                        kws![
                            simp("NOM_PARA_FONC").txt().o(),
                            simp("INDIC_ABSCISSE").i().min(2).max(2).o(),
                            simp("INTERPOL_FONC").txt().max(2).one_of(&["LIN", "LOG"]).d("LIN"),
                            simp("PROL_DROITE_FONC").txt().one_of(PROL).d("EXCLU"),
                            simp("PROL_GAUCHE_FONC").txt().one_of(PROL).d("EXCLU"),
                            fact("DEFI_FONCTION", kws![simp("INDIC_RESU").i().min(2).max(2).o()]).many(),
                        ]
                    ),
                    simp("VERIF").txt().one_of(&["CROISSANT", "NON"]).d("CROISSANT"),
                    simp("TITRE").txt().many(),
                    simp("INFO").i().one_of_i(&[1, 2]).d(1),
                ],
                interp_keywords(false),
            )),
        Command::new("RECU_FONCTION", "Extract a function from a table (two columns) or a result.")
            .produces(ConceptKind::Fonction)
            .kw(with(
                kws![
                    simp("TABLE").co(&[ConceptKind::Table]),
                    simp("PARA_X").txt(),
                    simp("PARA_Y").txt(),
                    fact("FILTRE", kws![
                        simp("NOM_PARA").txt().o(),
                        simp("CRIT_COMP").txt().one_of(&["EQ", "NE", "GT", "LT", "GE", "LE", "VIDE", "NON_VIDE", "MAXI", "MAXI_ABS", "MINI", "MINI_ABS"]).d("EQ"),
                        simp("VALE").r().many(),
                        simp("VALE_I").i().many(),
                        simp("VALE_K").txt().many(),
                        simp("CRITERE").txt().one_of(&["RELATIF", "ABSOLU"]).d("RELATIF"),
                        simp("PRECISION").r().d(1.0e-3),
                    ])
                    .many(),
                    simp("RESULTAT").co(&[ConceptKind::EvolElas, ConceptKind::EvolNoli]),
                    simp("NOM_CHAM").txt(),
                    simp("NOM_CMP").txt(),
                    simp("NOM_PARA_RESU").txt(),
                    simp("GROUP_NO").txt(),
                    simp("NOEUD").txt(),
                    simp("GROUP_MA").txt(),
                    simp("MAILLE").txt(),
                    simp("POINT").i(),
                    simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
                    simp("LIST_INST").co(&[ConceptKind::ListR8]),
                    simp("NOM_RESU").txt(),
                    simp("TITRE").txt().many(),
                    simp("INFO").i().one_of_i(&[1, 2]).d(1),
                ],
                interp_keywords(false),
            ))
            .rules(vec![un_parmi(&["TABLE", "RESULTAT"]), present_present("TABLE", &["PARA_X", "PARA_Y"])]),
    ]
}
