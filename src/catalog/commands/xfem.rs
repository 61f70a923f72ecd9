//! X-FEM: crack and interface definitions (DEFI_FISS_XFEM) and the enriched model (MODI_MODELE_XFEM).

use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

pub fn commands() -> Vec<Command> {
    vec![defi_fiss_xfem(), modi_modele_xfem(), post_mail_xfem(), post_cham_xfem()]
}

/// A level-set function.
const LEVEL_SET: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Formule];

fn point3(name: &'static str) -> Simp {
    simp(name).r().o().min(3).max(3)
}

fn half_axes() -> Vec<Entry> {
    kws![simp("DEMI_GRAND_AXE").r().o().val_min(0.0), simp("DEMI_PETIT_AXE").r().o().val_min(0.0)]
}

fn frame() -> Vec<Entry> {
    kws![point3("CENTRE"), point3("VECT_X"), point3("VECT_Y")]
}

fn cote_fiss() -> Simp {
    simp("COTE_FISS").txt().d("IN").one_of(&["IN", "OUT"])
}

/// FORM_FISS and the parameters of each analytical shape.
fn shapes() -> Vec<Entry> {
    let mut ellipse = half_axes();
    ellipse.extend(frame());
    ellipse.push(Entry::from(cote_fiss()));
    let mut rectangle = half_axes();
    rectangle.push(Entry::from(simp("RAYON_CONGE").r().d(0.0).val_min(0.0)));
    rectangle.extend(frame());
    rectangle.push(Entry::from(cote_fiss()));
    let mut entaille = kws![simp("DEMI_LONGUEUR").r().o().val_min(0.0), simp("RAYON_CONGE").r().o().val_min(0.0)];
    entaille.extend(frame());
    let mut cylindre = half_axes();
    cylindre.extend(frame());
    kws![
        simp("FORM_FISS").txt().one_of(&[
            "ELLIPSE",
            "RECTANGLE",
            "CYLINDRE",
            "DEMI_PLAN",
            "SEGMENT",
            "DEMI_DROITE",
            "DROITE",
            "ENTAILLE",
        ]),
        bloc(eq("FORM_FISS", "ELLIPSE"), ellipse),
        bloc(eq("FORM_FISS", "RECTANGLE"), rectangle),
        bloc(eq("FORM_FISS", "ENTAILLE"), entaille),
        bloc(eq("FORM_FISS", "CYLINDRE"), cylindre),
        bloc(eq("FORM_FISS", "DEMI_PLAN"), kws![point3("PFON"), point3("NORMALE"), point3("DTAN")]),
        bloc(eq("FORM_FISS", "SEGMENT"), kws![point3("PFON_ORIG"), point3("PFON_EXTR")]),
        bloc(eq("FORM_FISS", "DEMI_DROITE"), kws![point3("PFON"), point3("DTAN")]),
        bloc(eq("FORM_FISS", "DROITE"), kws![point3("POINT"), point3("DTAN")]),
    ]
}

fn defi_fiss_xfem() -> Command {
    let mut cohesive =
        kws![simp("FONC_LT").co(LEVEL_SET), simp("FONC_LN").co(LEVEL_SET), simp("GROUP_MA_BORD").txt().o(),];
    cohesive.extend(shapes());
    let mut other = kws![
        simp("FONC_LT").co(LEVEL_SET),
        simp("FONC_LN").co(LEVEL_SET),
        simp("CHAM_NO_LSN").co(&[ConceptKind::ChamNo]),
        simp("CHAM_NO_LST").co(&[ConceptKind::ChamNo]),
        simp("GROUP_MA_FISS").txt(),
        simp("GROUP_MA_FOND").txt(),
    ];
    other.extend(shapes());
    Command::new("DEFI_FISS_XFEM", "Define a crack or an interface for X-FEM, by level sets.")
        .produces(ConceptKind::FissXfem)
        .kw(kws![
            simp("TYPE_DISCONTINUITE").txt().d("FISSURE").one_of(&["FISSURE", "INTERFACE", "COHESIF"]),
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            simp("MAILLAGE_GRILLE").co(&[ConceptKind::Maillage]),
            simp("FISS_GRILLE").co(&[ConceptKind::FissXfem]),
            bloc(eq("TYPE_DISCONTINUITE", "COHESIF"), kws![fact("DEFI_FISS", cohesive).o()]),
            bloc(is_in("TYPE_DISCONTINUITE", &["FISSURE", "INTERFACE"]), kws![fact("DEFI_FISS", other).o()]),
            simp("GROUP_MA_ENRI").txt(),
            bloc(
                eq("TYPE_DISCONTINUITE", "INTERFACE"),
                kws![simp("CHAM_DISCONTINUITE").txt().d("DEPL").one_of(&["DEPL", "SIGM"])]
            ),
            bloc(
                eq("TYPE_DISCONTINUITE", "FISSURE"),
                kws![
                    simp("CHAM_DISCONTINUITE").txt().d("DEPL").one_of(&["DEPL"]),
                    simp("TYPE_ENRI_FOND").txt().d("GEOMETRIQUE").one_of(&["TOPOLOGIQUE", "GEOMETRIQUE"]),
                    bloc(
                        eq("TYPE_ENRI_FOND", "GEOMETRIQUE"),
                        kws![
                            simp("RAYON_ENRI").r().val_min(0.0),
                            bloc(absent("RAYON_ENRI"), kws![simp("NB_COUCHES").i().d(2).val_min(1.0)]),
                        ]
                    ),
                ]
            ),
            bloc(
                and(vec![absent("MAILLAGE_GRILLE"), absent("FISS_GRILLE")]),
                kws![fact(
                    "JONCTION",
                    kws![simp("FISSURE").co(&[ConceptKind::FissXfem]).o().many(), simp("POINT").r().o().max(3)]
                )]
            ),
            simp("INFO").i().d(1).one_of_i(&[1, 2, 3]),
        ])
        .rules(vec![exclus(&["MAILLAGE_GRILLE", "FISS_GRILLE"])])
}

fn modi_modele_xfem() -> Command {
    Command::new("MODI_MODELE_XFEM", "Enrich a model with the X-FEM elements of one or more cracks or interfaces.")
        .produces(ConceptKind::Modele)
        .kw(kws![
            simp("MODELE_IN").co(&[ConceptKind::Modele]).o(),
            simp("FISSURE").co(&[ConceptKind::FissXfem]).max(99),
            simp("MODELE_THER").co(&[ConceptKind::Modele]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            simp("CONTACT").txt().d("SANS").one_of(&["SANS", "STANDARD", "MORTAR"]),
            simp("PRETRAITEMENTS").txt().d("AUTO").one_of(&["AUTO", "SANS", "FORCE"]),
            simp("DECOUPE_FACETTE").txt().d("DEFAUT").one_of(&["DEFAUT", "SOUS_ELEMENTS"]),
        ])
        .rules(vec![un_parmi(&["FISSURE", "MODELE_THER"])])
}

// ------------------------------------------------------------------ POST_MAIL_XFEM, POST_CHAM_XFEM

fn post_mail_xfem() -> Command {
    Command::new("POST_MAIL_XFEM", "Build a mesh conforming to the XFEM cracks, for visualisation.")
        .produces(ConceptKind::Maillage)
        .kw(kws![
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("PREF_NOEUD_X").txt().d("NX"),
            simp("PREF_NOEUD_M").txt().d("NM"),
            simp("PREF_NOEUD_P").txt().d("NP"),
            simp("PREF_MAILLE_X").txt().d("MX"),
            simp("PREF_GROUP_CO").txt().d("NFISSU"),
            simp("TITRE").txt(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
}

fn post_cham_xfem() -> Command {
    Command::new("POST_CHAM_XFEM", "Transfer the fields of an XFEM result to the visualisation mesh.")
        .produces_dyn(super::common::type_of_resultat)
        .kw(kws![
            simp("RESULTAT").co(super::common::RESULTS).o(),
            simp("MODELE_VISU").co(&[ConceptKind::Modele]).o(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
}
