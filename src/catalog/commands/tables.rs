use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::diag::Result;
use crate::kws;

pub const CRIT_COMP: &[&str] =
    &["EQ", "NE", "GT", "LT", "GE", "LE", "VIDE", "NON_VIDE", "MAXI", "MAXI_ABS", "MINI", "MINI_ABS", "REGEXP"];
const TABLES: &[ConceptKind] = &[ConceptKind::Table, ConceptKind::TableContainer];

/// The keywords of one row filter (CALC_TABLE FILTRE, TEST_TABLE FILTRE, ...).
pub fn filter_keywords() -> Vec<Entry> {
    kws![
        simp("NOM_PARA").txt().o(),
        simp("CRIT_COMP").txt().one_of(CRIT_COMP).d("EQ"),
        simp("VALE").r().many(),
        simp("VALE_I").i().many(),
        simp("VALE_C").c().many(),
        simp("VALE_K").txt().many(),
        simp("CRITERE").txt().one_of(&["RELATIF", "ABSOLU"]).d("RELATIF"),
        simp("PRECISION").r().d(1.0e-3),
    ]
}

fn crea_table_type(a: &Args) -> Result<ConceptKind> {
    Ok(match a.text("TYPE_TABLE") {
        Some("TABLE_CONTAINER") => ConceptKind::TableContainer,
        _ => ConceptKind::Table,
    })
}

pub fn commands() -> Vec<Command> {
    vec![
        Command::new("CREA_TABLE", "A table from lists of values (one per column) or from a function.")
            .produces_dyn(crea_table_type)
            .kw(kws![
                fact(
                    "LISTE",
                    kws![
                        simp("PARA").txt(),
                        simp("LISTE_I").i().many(),
                        simp("LISTE_R").r().many(),
                        simp("LISTE_K").txt().many(),
                        simp("LISTE_CO")
                            .co(&[
                                ConceptKind::Table,
                                ConceptKind::Fonction,
                                ConceptKind::Nappe,
                                ConceptKind::Formule,
                                ConceptKind::Maillage,
                                ConceptKind::Modele,
                                ConceptKind::ChamNo,
                                ConceptKind::ChamElem,
                                ConceptKind::EvolElas,
                                ConceptKind::EvolNoli,
                            ])
                            .many(),
                        simp("TYPE_K").txt().one_of(&["K8", "K16", "K24", "K32", "K80"]).d("K8"),
                        simp("NUME_LIGN").i().many(),
                    ]
                )
                .many()
                .rules(vec![un_parmi(&["LISTE_I", "LISTE_R", "LISTE_K", "LISTE_CO"])]),
                fact(
                    "FONCTION",
                    kws![
                        simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe]).o(),
                        simp("PARA").txt().min(2).max(2)
                    ]
                ),
                simp("TYPE_TABLE").txt().one_of(&["TABLE", "TABLE_FONCTION", "TABLE_CONTAINER"]).d("TABLE"),
                simp("TITRE").txt().many(),
            ])
            .rules(vec![un_parmi(&["LISTE", "FONCTION"])]),
        Command::new("LIRE_TABLE", "Read a table from a text unit (ASTER, TABLEAU or LIBRE format).")
            .produces(ConceptKind::Table)
            .kw(kws![
                simp("UNITE").i().d(19),
                simp("FORMAT").txt().one_of(&["ASTER", "LIBRE", "TABLEAU"]).d("TABLEAU"),
                simp("NUME_TABLE").i().d(1).val_min(1.0),
                simp("SEPARATEUR").txt().d(" "),
                simp("RENOMME_PARA").txt().one_of(&["NON", "UNIQUE"]).d("NON"),
                simp("TITRE").txt().many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ]),
        Command::new("CALC_TABLE", "Operations on a table: filter, extract, combine, add rows or columns, compute.")
            .produces(ConceptKind::Table)
            .reuse()
            .kw(kws![
                simp("TABLE").co(TABLES).o(),
                fact(
                    "ACTION",
                    kws![
                        simp("OPERATION").txt().o().one_of(&[
                            "FILTRE",
                            "EXTR",
                            "SUPPRIME",
                            "RENOMME",
                            "TRI",
                            "COMB",
                            "AJOUT_LIGNE",
                            "AJOUT_COLONNE",
                            "OPER",
                            "CALCUL",
                            "STATISTIQUES",
                            "UNIQUE",
                        ]),
                        bloc(eq("OPERATION", "FILTRE"), filter_keywords()),
                        bloc(is_in("OPERATION", &["EXTR", "SUPPRIME"]), kws![simp("NOM_PARA").txt().many().o()]),
                        bloc(
                            eq("OPERATION", "UNIQUE"),
                            kws![simp("NOM_PARA").txt().many().o(), simp("FORMAT_R").txt()]
                        ),
                        bloc(eq("OPERATION", "RENOMME"), kws![simp("NOM_PARA").txt().min(2).max(2).o()]),
                        bloc(
                            eq("OPERATION", "TRI"),
                            kws![
                                simp("NOM_PARA").txt().many().o(),
                                simp("ORDRE").txt().one_of(&["CROISSANT", "DECROISSANT"]).d("CROISSANT"),
                            ]
                        ),
                        bloc(
                            eq("OPERATION", "COMB"),
                            kws![
                                simp("TABLE").co(TABLES).o(),
                                simp("NOM_PARA").txt().many(),
                                simp("RESTREINT").txt().one_of(&["OUI", "NON"]).d("NON"),
                                simp("FORMAT_R").txt(),
                            ]
                        ),
                        bloc(
                            eq("OPERATION", "AJOUT_LIGNE"),
                            kws![simp("NOM_PARA").txt().many().o(), simp("VALE").i().r().txt().many().o()]
                        ),
                        bloc(
                            eq("OPERATION", "AJOUT_COLONNE"),
                            kws![
                                simp("NOM_PARA").txt().many().o(),
                                simp("VALE").i().r().txt().many(),
                                simp("VALE_COLONNE").i().r().txt().many()
                            ]
                        )
                        .rules(vec![un_parmi(&["VALE", "VALE_COLONNE"])]),
                        bloc(
                            eq("OPERATION", "OPER"),
                            kws![
                                simp("FORMULE").co(&[ConceptKind::Formule]).o(),
                                simp("NOM_PARA").txt().o(),
                                simp("NOM_COLONNE").txt().many(),
                            ]
                        ),
                        bloc(
                            eq("OPERATION", "CALCUL"),
                            kws![
                                simp("NOM_PARA").txt().many().o(),
                                simp("TYPE_CALCUL")
                                    .txt()
                                    .many()
                                    .o()
                                    .one_of(&["MAXI", "MINI", "SOMM", "MOY", "MAXI_ABS", "MINI_ABS", "SOMM_ABS"]),
                            ]
                        ),
                    ]
                )
                .o()
                .many(),
                simp("TITRE").txt().many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ]),
        Command::new("IMPR_TABLE", "Print a table to a unit.").kw(kws![
            simp("TABLE").co(TABLES).o(),
            simp("FORMAT").txt().one_of(&["TABLEAU", "ASTER", "AGRAF", "TABLEAU_CROISE"]).d("TABLEAU"),
            simp("UNITE").i().d(8),
            simp("NOM_PARA").txt().many(),
            fact("FILTRE", filter_keywords()).many(),
            fact(
                "TRI",
                kws![
                    simp("NOM_PARA").txt().many().o(),
                    simp("ORDRE").txt().one_of(&["CROISSANT", "DECROISSANT"]).d("CROISSANT")
                ]
            ),
            simp("FORMAT_R").txt().d("E12.5"),
            simp("IMPR_FONCTION").txt().one_of(&["OUI", "NON"]).d("NON"),
            simp("SEPARATEUR").txt(),
            simp("TITRE").txt().many(),
            simp("INFO").i().one_of_i(&[1, 2]).d(1),
        ]),
    ]
}
