//! Post-processing: values of results and fields extracted to tables (POST_RELEVE_T) or along lines
//! (MACR_LIGN_COUPE), error norms of a field against reference formulas (POST_ERREUR).

use super::common::*;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

// ------------------------------------------------------------------ POST_RELEVE_T

fn post_releve_t() -> Command {
    let extraction = with(
        kws![
            simp("NOM_CHAM").txt().o(),
            simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
            simp("NUME_ORDRE").i().many(),
            simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
            simp("NUME_MODE").i().many(),
            simp("LIST_MODE").co(&[ConceptKind::ListIs]),
            simp("NOEUD_CMP").txt().many(),
            simp("NOM_CAS").txt().many(),
            simp("FREQ").r().many(),
            simp("LIST_FREQ").co(&[ConceptKind::ListR8]),
            simp("INST").r().many(),
            simp("LIST_INST").co(&[ConceptKind::ListR8]),
        ],
        crit_prec(),
    );
    let groups = kws![
        simp("TOUT").txt().one_of(&["OUI"]),
        simp("GROUP_MA").txt().many(),
        simp("MAILLE").txt().many(),
        simp("GROUP_NO").txt().many(),
        simp("NOEUD").txt().many(),
        simp("TOUT_CMP").txt().one_of(&["OUI"]),
        simp("NOM_CMP").txt().many(),
    ];
    let autre = with(
        groups.clone(),
        kws![
            simp("INVARIANT").txt().one_of(&["OUI"]),
            simp("ELEM_PRINCIPAUX").txt().one_of(&["OUI"]),
            simp("RESULTANTE").txt().many().one_of(&["DX", "DY", "DZ", "NXX", "NYY", "NXY", "PRE1", "PRE2", "TEMP"]),
            simp("MOMENT").txt().many().one_of(&["DRX", "DRY", "DRZ", "MXX", "MYY", "MXY"]),
            simp("POINT").r().many(),
            simp("REPERE").txt().d("GLOBAL").one_of(&["GLOBAL", "LOCAL", "POLAIRE", "UTILISATEUR", "CYLINDRIQUE"]),
            simp("ANGL_NAUT").r().min(3).max(3),
            simp("ORIGINE").r().min(3).max(3),
            simp("AXE_Z").r().min(3).max(3),
            simp("TRAC_NOR").txt().one_of(&["OUI"]),
            simp("TRAC_DIR").txt().one_of(&["OUI"]),
            simp("DIRECTION").r().many(),
            simp("VECT_Y").r().many(),
            simp("MOYE_NOEUD").txt().d("OUI").one_of(OUI_NON),
        ],
    );
    Command::new("POST_RELEVE_T", "Extract field components (or averages, extrema, invariants) into a table.")
        .produces(ConceptKind::Table)
        .kw(kws![
            fact(
                "ACTION",
                kws![
                    simp("OPERATION").txt().o().max(2).one_of(&["EXTRACTION", "MOYENNE", "MOYENNE_ARITH", "EXTREMA"]),
                    simp("INTITULE").txt().o(),
                    simp("CHAM_GD").co(&[ConceptKind::ChamNo, ConceptKind::ChamElem]),
                    simp("RESULTAT").co(STORED_RESULTS),
                    bloc(present("RESULTAT"), extraction).rules(vec![exclus(&[
                        "TOUT_ORDRE",
                        "NUME_ORDRE",
                        "LIST_ORDRE",
                        "NUME_MODE",
                        "LIST_MODE",
                        "INST",
                        "LIST_INST",
                        "FREQ",
                        "LIST_FREQ",
                        "NOEUD_CMP",
                        "NOM_CAS",
                    ])]),
                    bloc(eq("OPERATION", "EXTREMA"), groups.clone()).rules(vec![exclus(&["TOUT_CMP", "NOM_CMP"])]),
                    bloc(eq("OPERATION", "MOYENNE_ARITH"), groups).rules(vec![exclus(&["TOUT_CMP", "NOM_CMP"])]),
                    bloc(is_in("OPERATION", &["EXTRACTION", "MOYENNE"]), autre).rules(vec![
                        au_moins_un(&["GROUP_NO", "NOEUD"]),
                        un_parmi(&["TOUT_CMP", "NOM_CMP", "INVARIANT", "ELEM_PRINCIPAUX", "RESULTANTE"]),
                        present_present("TRAC_DIR", &["DIRECTION"]),
                        ensemble(&["MOMENT", "POINT"]),
                        present_present("MOMENT", &["RESULTANTE"]),
                        present_absent("TOUT_CMP", &["TRAC_DIR", "TRAC_NOR"]),
                        exclus(&["TRAC_DIR", "TRAC_NOR"]),
                        present_present("ORIGINE", &["AXE_Z"]),
                    ]),
                    simp("FORMAT_C").txt().d("MODULE").one_of(&["MODULE", "REEL", "IMAG"]),
                ]
            )
            .o()
            .many()
            .rules(vec![un_parmi(&["RESULTAT", "CHAM_GD"])]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            simp("TITRE").txt(),
        ])
}

// ------------------------------------------------------------------ POST_ELEM

/// POST_ELEM's energies (ENER_POT, ENER_ELAS, ENER_TOTALE): Code_Aster's keywords for them; its other
/// quantities (MASS_INER, INTEGRALE, MINMAX, ...) are not in this schema and stop by name.
fn post_elem() -> Command {
    let places = || fact_places();
    let mut kw = kws![
        fact("ENER_POT", places()).many().rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
        fact("ENER_ELAS", places()).many().rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
        fact("ENER_TOTALE", places()).many().rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
        simp("MODELE").co(&[ConceptKind::Modele]),
        simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
        simp("CARA_ELEM").co(&[ConceptKind::CaraElem]),
        simp("NUME_COUCHE").i().d(1),
        simp("NIVE_COUCHE").txt().d("MOY").one_of(&["INF", "SUP", "MOY"]),
        simp("MODE_FOURIER").i().d(0),
        simp("CHAM_GD").co(&[ConceptKind::ChamNo, ConceptKind::ChamElem]),
        simp("RESULTAT").co(&[ConceptKind::EvolElas, ConceptKind::EvolNoli]),
        simp("TOUT_ORDRE").txt().one_of(&["OUI"]),
        simp("NUME_ORDRE").i().many(),
        simp("LIST_ORDRE").co(&[ConceptKind::ListIs]),
        simp("INST").r().many(),
        simp("LIST_INST").co(&[ConceptKind::ListR8]),
        simp("TITRE").txt().many(),
    ];
    kw.extend(crit_prec());
    Command::new("POST_ELEM", "Compute global quantities (energies) of a mechanical result on a model.")
        .produces(ConceptKind::Table)
        .kw(kw)
        .rules(vec![
            un_parmi(&["ENER_POT", "ENER_ELAS", "ENER_TOTALE"]),
            exclus(&["CHAM_GD", "RESULTAT"]),
            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST"]),
        ])
}

/// TOUT or GROUP_MA, one of them.
fn fact_places() -> Vec<Entry> {
    kws![simp("TOUT").txt().one_of(&["OUI"]), simp("GROUP_MA").txt().many()]
}

// ------------------------------------------------------------------ POST_ERREUR

/// Code_Aster's `post_erreur.py`: one field (CHAM_GD) against reference FORMULEs of X, Y (, Z), one per
/// group of GROUP_MA for each component given.
fn post_erreur() -> Command {
    let formulas = |names: &[&'static str]| -> Vec<Entry> {
        names.iter().map(|n| Entry::from(simp(n).co(&[ConceptKind::Formule]).many())).collect()
    };
    let mut depl =
        kws![simp("CHAM_MATER").co(&[ConceptKind::ChamMater]), simp("CHAM_GD").co(&[ConceptKind::ChamNo]).o(),];
    depl.extend(formulas(&["DX", "DY", "DZ"]));
    let mut ener = kws![
        simp("CHAM_MATER").co(&[ConceptKind::ChamMater]).o(),
        simp("DEFORMATION").txt().o().one_of(&["PETIT"]),
        simp("CHAM_GD").co(&[ConceptKind::ChamElem]).o(),
    ];
    ener.extend(formulas(&["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]));
    let mut lagr = kws![simp("CHAM_GD").co(&[ConceptKind::ChamNo]).o()];
    lagr.extend(formulas(&["LAGS_C"]));
    Command::new(
        "POST_ERREUR",
        "Error norms of a field against reference formulas over groups of cells: L2 of the displacement, \
         energy norm of the stress, L2 of the contact pressure.",
    )
    .produces(ConceptKind::Table)
    .kw(kws![
        simp("OPTION").txt().o().one_of(&["DEPL_RELA", "ENER_RELA", "LAGR_RELA"]),
        simp("MODELE").co(&[ConceptKind::Modele]).o(),
        simp("GROUP_MA").txt().o().many(),
        bloc(eq("OPTION", "DEPL_RELA"), depl),
        bloc(eq("OPTION", "ENER_RELA"), ener),
        bloc(eq("OPTION", "LAGR_RELA"), lagr),
    ])
}

// ------------------------------------------------------------------ MACR_LIGN_COUPE

/// Code_Aster's `macr_lign_coupe.py`: values of a result or a field along lines (segments, arcs, groups of
/// nodes or of segment cells) into a table.
fn macr_lign_coupe() -> Command {
    use ConceptKind::*;
    let orders = with(
        kws![
            simp("NUME_ORDRE").i().many(),
            simp("NUME_MODE").i().many(),
            simp("LIST_ORDRE").co(&[ListIs]),
            simp("INST").r().many(),
            simp("LIST_INST").co(&[ListR8]),
        ],
        vec![bloc(or(vec![present("INST"), present("LIST_INST")]), crit_prec()).into()],
    );
    let ther = &[
        "TEMP",
        "HHO_TEMP",
        "FLUX_ELGA",
        "FLUX_ELNO",
        "FLUX_NOEU",
        "META_ELNO",
        "META_NOEU",
        "DURT_ELNO",
        "DURT_NOEU",
        "HYDR_ELNO",
        "HYDR_NOEU",
        "DETE_ELNO",
        "DETE_NOEU",
        "SOUR_ELGA",
        "COMPORTHER",
        "ERTH_ELEM",
        "ERTH_ELNO",
        "ERTH_NOEU",
    ];
    let line = kws![
        simp("INTITULE").txt(),
        simp("TYPE").txt().d("SEGMENT").one_of(&["GROUP_NO", "SEGMENT", "ARC", "GROUP_MA"]),
        simp("REPERE").txt().d("GLOBAL").one_of(&["GLOBAL", "LOCAL", "POLAIRE", "UTILISATEUR", "CYLINDRIQUE"]),
        simp("OPERATION").txt().d("EXTRACTION").one_of(&["EXTRACTION", "MOYENNE"]),
        simp("NOM_CMP").txt().many(),
        simp("INVARIANT").txt().one_of(&["OUI"]),
        simp("ELEM_PRINCIPAUX").txt().one_of(&["OUI"]),
        simp("TRAC_NOR").txt().one_of(&["OUI"]),
        simp("TRAC_DIR").txt().one_of(&["OUI"]),
        simp("DIRECTION").r().many(),
        bloc(
            or(vec![eq("TYPE", "GROUP_NO"), eq("TYPE", "GROUP_MA")]),
            kws![
                simp("RESULTANTE").txt().many().one_of(&["DX", "DY", "DZ", "NXX", "NYY", "NXY"]),
                simp("MOMENT").txt().many().one_of(&["DRX", "DRY", "DRZ", "MXX", "MYY", "MXY"]),
                simp("POINT").r().many(),
            ]
        )
        .rules(vec![present_present("MOMENT", &["RESULTANTE"])]),
        bloc(eq("REPERE", "LOCAL"), kws![simp("VECT_Y").r().min(2).max(3)]),
        bloc(eq("REPERE", "UTILISATEUR"), kws![simp("ANGL_NAUT").r().o().min(3).max(3)]),
        bloc(eq("TYPE", "GROUP_NO"), kws![simp("GROUP_NO").txt().o()]),
        bloc(
            eq("TYPE", "GROUP_MA"),
            kws![
                simp("GROUP_MA").txt().o(),
                simp("MAILLAGE").co(&[Maillage]).o(),
                simp("GROUP_NO_ORIG").txt(),
                simp("GROUP_NO_EXTR").txt(),
                simp("VECT_ORIE").r().max(3),
            ]
        ),
        bloc(
            eq("TYPE", "SEGMENT"),
            kws![
                simp("NB_POINTS").i().o().val_min(2.0),
                simp("COOR_ORIG").r().min(2).max(3),
                simp("COOR_EXTR").r().min(2).max(3),
                simp("GROUP_NO_ORIG").txt(),
                simp("GROUP_NO_EXTR").txt(),
            ]
        )
        .rules(vec![un_parmi(&["COOR_ORIG", "GROUP_NO_ORIG"]), un_parmi(&["COOR_EXTR", "GROUP_NO_EXTR"])]),
        bloc(
            eq("TYPE", "ARC"),
            kws![
                simp("NB_POINTS").i().o().val_min(2.0),
                simp("COOR_ORIG").r().o().min(2).max(3),
                simp("CENTRE").r().o().min(2).max(3),
                simp("ANGLE").r().o(),
                simp("DNOR").r().min(2).max(3),
            ]
        ),
        bloc(
            and(vec![eq("REPERE", "CYLINDRIQUE"), Cond::Not(Box::new(eq("TYPE", "ARC")))]),
            kws![simp("ORIGINE").r().min(2).max(3), simp("AXE_Z").r().min(3).max(3)]
        ),
        simp("DISTANCE_MAX").r().d(0.0),
        simp("DISTANCE_ALARME").r(),
    ];
    Command::new("MACR_LIGN_COUPE", "Extract results along lines into a table.")
        .produces(ConceptKind::Table)
        .rules(vec![un_parmi(&["RESULTAT", "CHAM_GD"])])
        .kw(kws![
            simp("RESULTAT").co(&[EvolElas, EvolNoli, EvolTher, EvolSech]),
            simp("CHAM_GD").co(CHAM_GD),
            bloc(present("RESULTAT"), orders).rules(vec![exclus(&[
                "NUME_ORDRE",
                "NUME_MODE",
                "LIST_ORDRE",
                "INST",
                "LIST_INST"
            ])]),
            bloc(Cond::Type("RESULTAT", &[EvolElas, EvolNoli]), kws![simp("NOM_CHAM").txt().d("SIGM_NOEU")]),
            bloc(Cond::Type("RESULTAT", &[EvolTher]), kws![simp("NOM_CHAM").txt().d("TEMP").one_of(ther)]),
            bloc(
                Cond::Type("RESULTAT", &[EvolSech]),
                kws![simp("NOM_CHAM").txt().d("SECH").one_of(&[
                    "SECH",
                    "FLUX_ELGA",
                    "FLUX_ELNO",
                    "FLUX_NOEU",
                    "COMPORTHER"
                ])]
            ),
            bloc(present("CHAM_GD"), kws![simp("NOM_CHAM").txt()]),
            simp("UNITE_MAILLAGE").i(),
            simp("MODELE").co(&[Modele]),
            fact("VIS_A_VIS", kws![simp("GROUP_MA_1").txt(), simp("MAILLE_1").txt().many()])
                .many()
                .rules(vec![exclus(&["GROUP_MA_1", "MAILLE_1"])]),
            fact("LIGN_COUPE", line).o().many().rules(vec![
                exclus(&["NOM_CMP", "INVARIANT", "ELEM_PRINCIPAUX", "RESULTANTE"]),
                present_present("TRAC_DIR", &["DIRECTION"]),
                exclus(&["TRAC_DIR", "TRAC_NOR"]),
                present_present("TRAC_DIR", &["NOM_CMP"]),
                present_present("TRAC_NOR", &["NOM_CMP"]),
                ensemble(&["MOMENT", "POINT"]),
            ]),
        ])
}

pub fn commands() -> Vec<Command> {
    vec![post_releve_t(), post_erreur(), post_elem(), macr_lign_coupe()]
}
