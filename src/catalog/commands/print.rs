//! Printing results and meshes (IMPR_RESU).

use super::common::*;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
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
        simp("RESULTAT").co(RESULTS),
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

pub fn commands() -> Vec<Command> {
    vec![impr_resu()]
}
