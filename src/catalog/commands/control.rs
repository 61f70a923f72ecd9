use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

/// Every concept type: DETRUIRE takes any concept.
const ANY_CONCEPT: &[ConceptKind] = &[
    ConceptKind::Maillage,
    ConceptKind::Modele,
    ConceptKind::Mater,
    ConceptKind::ChamMater,
    ConceptKind::CharMeca,
    ConceptKind::CharContact,
    ConceptKind::Fonction,
    ConceptKind::FonctionC,
    ConceptKind::Nappe,
    ConceptKind::Formule,
    ConceptKind::Table,
    ConceptKind::TableContainer,
    ConceptKind::ListR8,
    ConceptKind::ListIs,
    ConceptKind::ListInst,
    ConceptKind::EvolElas,
    ConceptKind::EvolNoli,
    ConceptKind::FissXfem,
    ConceptKind::ChamNo,
    ConceptKind::ChamElem,
    ConceptKind::Carte,
];

/// The keywords of DEBUT and POURSUITE (Code_Aster's `Starter`: one catalogue for both).
fn starter() -> Vec<Entry> {
    let yes_no = |n: &'static str| simp(n).txt().one_of(&["OUI", "NON"]);
    kws![
        simp("CODE").txt().one_of(&["OUI", "NON"]),
        fact("CODE", kws![simp("NIV_PUB_WEB").txt().one_of(&["INTERNET", "INTRANET"]), yes_no("VISU_EFICAS")]),
        fact(
            "ERREUR",
            kws![
                simp("ERREUR_F").txt().one_of(&["ABORT", "EXCEPTION"]),
                simp("ALARME").txt().one_of(&["ALARME", "EXCEPTION"]),
            ]
        ),
        fact(
            "DEBUG",
            kws![
                yes_no("JXVERI"),
                yes_no("SDVERI"),
                yes_no("JEVEUX"),
                yes_no("HIST_ETAPE"),
                simp("ENVIMA").txt().one_of(&["TEST"]),
                simp("VERI_BASE").txt().one_of(&["GLOBALE", "VOLATILE"]),
                simp("VERI_BASE_NB").i(),
            ]
        ),
        // The sizes of Code_Aster's databases (no effect on what is computed).
        fact(
            "BASE",
            kws![
                simp("FICHIER").txt().one_of(&["GLOBALE", "VOLATILE"]),
                simp("TAILLE").i(),
                simp("LONG_ENRE").i(),
                simp("NMAX_ENRE").i(),
                simp("LONG_REPE").i(),
                simp("TITRE").txt(),
                simp("CAS").txt(),
            ]
        )
        .max(2),
        fact("CATALOGUE", kws![simp("FICHIER").txt().o(), simp("UNITE").i()]).max(10),
        fact("MESURE_TEMPS", kws![simp("NIVE_DETAIL").i().one_of_i(&[0, 1, 2, 3]), yes_no("MOYENNE")]),
        fact("MEMOIRE", kws![simp("TAILLE_BLOC").r(), simp("TAILLE_GROUP_ELEM").i()]),
        fact("RESERVE_CPU", kws![simp("VALE").i().val_min(0.0), simp("POURCENTAGE").r().val_min(0.0).val_max(1.0)])
            .rules(vec![exclus(&["VALE", "POURCENTAGE"])]),
        fact("RESERVE_MEMOIRE", kws![simp("VALE").i().val_min(0.0), simp("POURCENTAGE").r().val_min(0.0).val_max(1.0)])
            .rules(vec![exclus(&["VALE", "POURCENTAGE"])]),
        simp("IGNORE_ALARM").txt().many(),
        yes_no("PAR_LOT"),
        yes_no("FORMAT_HDF"),
        simp("LANG").txt(),
        yes_no("IMPR_MACRO"),
        simp("INFO").i().one_of_i(&[1, 2]),
        simp("MODE").txt().one_of(&["AUTO", "DEBUT", "POURSUITE"]),
    ]
}

pub fn commands() -> Vec<Command> {
    vec![
        Command::new("DEBUT", "Start a study: error handling, debug and publication options.").kw(starter()),
        Command::new(
            "POURSUITE",
            "Continue the study of the previous command file of the run, with every concept and name it made.",
        )
        .kw(starter()),
        Command::new("FIN", "End the study; commands after FIN are not run.").kw(kws![
            simp("FORMAT_HDF").txt().one_of(&["OUI", "NON"]),
            simp("RETASSAGE").txt().one_of(&["OUI", "NON"]),
            simp("INFO_RESU").txt().one_of(&["OUI", "NON"]),
            simp("INFO_BASE").txt().one_of(&["OUI", "NON"]),
            simp("PROC0").txt().one_of(&["OUI", "NON"]),
            simp("UNITE").i(),
        ]),
        Command::new("DETRUIRE", "Forget concepts: the names bound to them are unbound.")
            .kw(kws![
                simp("NOM").co(ANY_CONCEPT).many(),
                fact("CONCEPT", kws![simp("NOM").co(ANY_CONCEPT).o().many()]).many(),
                fact("OBJET", kws![simp("CHAINE").txt().o().many(), simp("POSITION").i()]).many(),
                simp("INFO").i().one_of_i(&[1, 2]),
            ])
            .rules(vec![au_moins_un(&["NOM", "CONCEPT", "OBJET"])]),
        Command::new(
            "DEFI_FICHIER",
            "Associate a logical unit with a file of the run's folder, reserve it, or free it; without UNITE, \
             returns a free unit.",
        )
        .produces_int()
        .kw(kws![
            simp("ACTION").txt().one_of(&["ASSOCIER", "LIBERER", "RESERVER"]).d("ASSOCIER"),
            bloc(
                eq("ACTION", "ASSOCIER"),
                kws![
                    simp("UNITE").i(),
                    simp("FICHIER").txt(),
                    simp("TYPE").txt().one_of(&["ASCII", "BINARY", "LIBRE"]).d("ASCII"),
                    bloc(eq("TYPE", "ASCII"), kws![simp("ACCES").txt().one_of(&["NEW", "APPEND", "OLD"]).d("NEW")]),
                    bloc(
                        or(vec![eq("TYPE", "BINARY"), eq("TYPE", "LIBRE")]),
                        kws![simp("ACCES").txt().one_of(&["NEW", "OLD"]).d("NEW")]
                    ),
                ]
            )
            .rules(vec![au_moins_un(&["FICHIER", "UNITE"])]),
            bloc(
                eq("ACTION", "RESERVER"),
                kws![
                    simp("UNITE").i(),
                    simp("FICHIER").txt(),
                    simp("TYPE").txt().one_of(&["ASCII"]).d("ASCII"),
                    simp("ACCES").txt().one_of(&["APPEND"]).d("APPEND"),
                ]
            )
            .rules(vec![au_moins_un(&["FICHIER", "UNITE"])]),
            bloc(eq("ACTION", "LIBERER"), kws![simp("UNITE").i(), simp("FICHIER").txt()])
                .rules(vec![un_parmi(&["FICHIER", "UNITE"])]),
            simp("INFO").i().one_of_i(&[1, 2]),
        ]),
        Command::new("INFO_EXEC_ASTER", "A table of facts about the run: time left, a free unit, a unit's state.")
            .produces(ConceptKind::Table)
            .kw(kws![
                simp("LISTE_INFO").txt().o().max(3).one_of(&["TEMPS_RESTANT", "UNITE_LIBRE", "ETAT_UNITE"]),
                bloc(is_in("LISTE_INFO", &["ETAT_UNITE"]), kws![simp("UNITE").i(), simp("FICHIER").txt()])
                    .rules(vec![un_parmi(&["UNITE", "FICHIER"])]),
                simp("TITRE").txt(),
                simp("INFO").i().one_of_i(&[1, 2]),
            ]),
    ]
}
