//! The checks: TEST_TABLE, TEST_FONCTION, and TEST_RESU (`test_resu`).

pub mod test_resu;

use crate::catalog::commands::common::*;
use crate::catalog::commands::tables::filter_keywords;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

const REFERENCES: &[&str] = &["ANALYTIQUE", "SOURCE_EXTERNE", "AUTRE_ASTER", "NON_DEFINI", "NON_REGRESSION"];

/// The verification keywords shared by TEST_* commands.
pub fn check_keywords() -> Vec<Entry> {
    kws![
        simp("REFERENCE").txt().one_of(REFERENCES),
        simp("PRECISION").r(),
        simp("CRITERE").txt().one_of(&["RELATIF", "ABSOLU"]).max(2).d("RELATIF"),
        simp("TOLE_MACHINE").r().max(2),
        simp("ORDRE_GRANDEUR").r(),
        simp("VALE_ABS").txt().one_of(&["OUI", "NON"]).d("NON"),
        simp("LEGENDE").txt(),
    ]
}

pub fn commands() -> Vec<Command> {
    let mut v = vec![
        Command::new("TEST_TABLE", "Check a value of a table against VALE_CALC and a reference.")
            .kw(with(
                kws![
                    simp("TABLE").co(&[ConceptKind::Table, ConceptKind::TableContainer]).o(),
                    simp("NOM_PARA").txt().o(),
                    fact("FILTRE", filter_keywords()).many(),
                    simp("TYPE_TEST").txt().one_of(&["SOMM_ABS", "SOMM", "MAX", "MIN"]),
                    simp("VALE_CALC").r().many(),
                    simp("VALE_CALC_I").i().many(),
                    simp("VALE_CALC_C").c().many(),
                    simp("VALE_CALC_K").txt(),
                    simp("VALE_REFE").r().many(),
                    simp("VALE_REFE_I").i().many(),
                    simp("VALE_REFE_C").c().many(),
                    simp("VALE_REFE_K").txt(),
                    simp("INFO").i().one_of_i(&[1, 2]).d(1),
                ],
                check_keywords(),
            ))
            .rules(vec![un_parmi(&["VALE_CALC", "VALE_CALC_I", "VALE_CALC_C", "VALE_CALC_K"])]),
        Command::new("TEST_FONCTION", "Check values and attributes of functions against VALE_CALC and a reference.")
            .kw(kws![
                fact(
                    "VALEUR",
                    with(
                        kws![
                            simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule]).o(),
                            simp("NOM_PARA").txt().max(2),
                            simp("VALE_PARA").r().max(2).o(),
                            simp("VALE_CALC").r(),
                            simp("VALE_CALC_C").c(),
                            simp("VALE_REFE").r(),
                            simp("VALE_REFE_C").c(),
                        ],
                        check_keywords(),
                    )
                )
                .many()
                .rules(vec![un_parmi(&["VALE_CALC", "VALE_CALC_C"])]),
                fact(
                    "ATTRIBUT",
                    kws![
                        simp("FONCTION").co(&[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule]).o(),
                        simp("PARA").r(),
                        simp("ATTR").txt().o().one_of(&[
                            "NOM_PARA",
                            "NOM_RESU",
                            "PROL_DROITE",
                            "PROL_GAUCHE",
                            "INTERPOL",
                            "PROL_GAUCHE_FONC",
                            "PROL_DROITE_FONC",
                            "INTERPOL_FONC",
                            "NOM_PARA_FONC",
                        ]),
                        simp("ATTR_REFE").txt().o(),
                        simp("REFERENCE").txt().one_of(REFERENCES),
                    ]
                )
                .many(),
                simp("INFO").i().one_of_i(&[1, 2]).d(1),
            ])
            .rules(vec![au_moins_un(&["VALEUR", "ATTRIBUT"])]),
    ];
    v.extend(test_resu::commands());
    v
}
