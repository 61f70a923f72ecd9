//! Mesh commands: reading a mesh, defining groups, deriving and modifying meshes.

use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

pub fn commands() -> Vec<Command> {
    vec![lire_maillage(), defi_group(), crea_maillage(), modi_maillage()]
}

/// `TOUT='OUI'`.
fn tout(name: &'static str) -> Simp {
    simp(name).txt().one_of(&["OUI"])
}

/// A list of group, cell or node names.
fn names(name: &'static str) -> Simp {
    simp(name).txt().many()
}

fn lire_maillage() -> Command {
    Command::new("LIRE_MAILLAGE", "Read a mesh from a file (MED, ASTER, GMSH, IDEAS or GIBI format).")
        .produces(ConceptKind::Maillage)
        .kw(kws![
            simp("FORMAT").txt().d("MED").one_of(&["ASTER", "GIBI", "GMSH", "IDEAS", "MED"]),
            simp("UNITE").i().d(20),
            fact("VERI_MAIL", kws![simp("VERIF").txt().d("OUI").one_of(&["OUI", "NON"]), simp("APLAT").r().d(1.0e-3),])
                .d(),
            bloc(
                eq("FORMAT", "MED"),
                kws![
                    simp("NOM_MED").txt(),
                    simp("INFO_MED").i().d(1).one_of_i(&[0, 1, 2, 3]),
                    simp("PARTITIONNEUR").txt().d("SANS").one_of(&["SANS", "PTSCOTCH"]),
                ]
            ),
            bloc(eq("FORMAT", "IDEAS"), kws![simp("CREA_GROUP_COUL").txt().d("NON").one_of(&["OUI", "NON"])]),
            simp("INFO").i().d(1).one_of_i(&[0, 1, 2]),
        ])
}

/// Options of CREA_GROUP_MA.
fn crea_group_ma() -> Fact {
    let crit_noeud = || simp("CRIT_NOEUD").txt().d("AU_MOINS_UN").one_of(&["TOUS", "AU_MOINS_UN", "MAJORITE"]);
    fact(
        "CREA_GROUP_MA",
        kws![
            simp("NOM").txt().o(),
            tout("TOUT"),
            simp("GROUP_MA").txt(),
            names("MAILLE"),
            names("INTERSEC"),
            names("UNION"),
            names("DIFFE"),
            simp("TYPE_MAILLE").txt().d("TOUT").one_of(&[
                "TOUT", "1D", "2D", "3D", "POI1", "SEG2", "SEG3", "SEG4", "TRIA3", "TRIA6", "TRIA7", "QUAD4", "QUAD8",
                "QUAD9", "TETRA4", "TETRA10", "PENTA6", "PENTA15", "PENTA18", "HEXA8", "HEXA20", "HEXA27", "PYRAM5",
                "PYRAM13",
            ]),
            simp("OPTION").txt().one_of(&["FACE_NORMALE", "SPHERE", "CYLINDRE", "BANDE", "APPUI", "FISS_XFEM"]),
            bloc(
                present("GROUP_MA"),
                kws![
                    simp("NUME_INIT").i().val_min(1.0),
                    simp("POSITION").txt().one_of(&["INIT", "FIN", "MILIEU"]),
                    bloc(present("NUME_INIT"), kws![simp("NUME_FIN").i().val_min(1.0)]),
                ]
            )
            .rules(vec![exclus(&["POSITION", "NUME_INIT"])]),
            bloc(
                eq("OPTION", "FACE_NORMALE"),
                kws![
                    simp("ANGL_NAUT").r().max(2),
                    simp("VECT_NORMALE").r().max(3),
                    simp("ANGL_PREC").r().d(0.5),
                    simp("VERI_SIGNE").txt().d("OUI").one_of(&["OUI", "NON"]),
                ]
            )
            .rules(vec![un_parmi(&["ANGL_NAUT", "VECT_NORMALE"])]),
            bloc(
                eq("OPTION", "SPHERE"),
                kws![
                    simp("POINT").r().max(3),
                    simp("NOEUD_CENTRE").txt(),
                    simp("GROUP_NO_CENTRE").txt(),
                    simp("RAYON").r().o(),
                    crit_noeud(),
                ]
            )
            .rules(vec![un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"])]),
            bloc(
                eq("OPTION", "CYLINDRE"),
                kws![
                    simp("POINT").r().max(3),
                    simp("NOEUD_CENTRE").txt(),
                    simp("GROUP_NO_CENTRE").txt(),
                    simp("RAYON").r().o(),
                    simp("ANGL_NAUT").r().max(2),
                    simp("VECT_NORMALE").r().max(3),
                    crit_noeud(),
                ]
            )
            .rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ]),
            bloc(
                eq("OPTION", "BANDE"),
                kws![
                    simp("POINT").r().max(3),
                    simp("NOEUD_CENTRE").txt(),
                    simp("GROUP_NO_CENTRE").txt(),
                    simp("DIST").r().o(),
                    simp("ANGL_NAUT").r().max(2),
                    simp("VECT_NORMALE").r().max(3),
                    crit_noeud(),
                ]
            )
            .rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ]),
            bloc(
                eq("OPTION", "APPUI"),
                kws![
                    names("NOEUD"),
                    names("GROUP_NO"),
                    simp("TYPE_APPUI").txt().o().one_of(&["AU_MOINS_UN", "TOUT", "SOMMET", "MAJORITE"]),
                ]
            )
            .rules(vec![un_parmi(&["NOEUD", "GROUP_NO"])]),
            bloc(
                eq("OPTION", "FISS_XFEM"),
                kws![
                    simp("TYPE_GROUP").txt().d("XFEM").one_of(&["HEAVISIDE", "CRACKTIP", "MIXTE", "FISSUREE", "XFEM"]),
                    simp("FISSURE").co(&[ConceptKind::FissXfem]).o().many(),
                ]
            ),
        ],
    )
    .many()
    .rules(vec![un_parmi(&["TOUT", "GROUP_MA", "MAILLE", "INTERSEC", "UNION", "DIFFE", "OPTION"])])
}

/// Options of CREA_GROUP_NO.
fn crea_group_no() -> Fact {
    let center = || kws![simp("POINT").r().max(3), simp("NOEUD_CENTRE").txt(), simp("GROUP_NO_CENTRE").txt()];
    let mut env_sphere = kws![simp("NOM").txt().o()];
    env_sphere.extend(center());
    env_sphere.extend(kws![simp("RAYON").r().o(), simp("PRECISION").r().o()]);
    let mut env_cylindre = kws![simp("NOM").txt().o()];
    env_cylindre.extend(center());
    env_cylindre.extend(kws![
        simp("RAYON").r().o(),
        simp("ANGL_NAUT").r().max(3),
        simp("VECT_NORMALE").r().max(3),
        simp("PRECISION").r().o(),
    ]);
    let mut plan = kws![simp("NOM").txt().o()];
    plan.extend(center());
    plan.extend(kws![simp("ANGL_NAUT").r().max(3), simp("VECT_NORMALE").r().max(3), simp("PRECISION").r().o()]);
    fact(
        "CREA_GROUP_NO",
        kws![
            simp("OPTION").txt().one_of(&[
                "ENV_SPHERE",
                "ENV_CYLINDRE",
                "PLAN",
                "SEGM_DROI_ORDO",
                "NOEUD_ORDO",
                "TUNNEL",
                "INCLUSION",
                "FISS_XFEM",
                "INTERVALLE_VALE",
            ]),
            bloc(
                absent("OPTION"),
                kws![
                    tout("TOUT_GROUP_MA"),
                    names("GROUP_MA"),
                    names("GROUP_NO"),
                    names("NOEUD"),
                    names("INTERSEC"),
                    names("UNION"),
                    names("DIFFE"),
                    bloc(
                        present("GROUP_MA"),
                        kws![
                            names("NOM"),
                            simp("CRIT_NOEUD").txt().d("TOUS").one_of(&["TOUS", "SOMMET", "MILIEU", "CENTRE"]),
                        ]
                    ),
                    bloc(
                        present("GROUP_NO"),
                        kws![
                            simp("NUME_INIT").i().val_min(1.0),
                            simp("POSITION").txt().one_of(&["INIT", "FIN", "MILIEU"]),
                            bloc(present("NUME_INIT"), kws![simp("NUME_FIN").i().val_min(1.0)]),
                        ]
                    )
                    .rules(vec![exclus(&["POSITION", "NUME_INIT"])]),
                    bloc(and(vec![absent("GROUP_MA"), absent("TOUT_GROUP_MA")]), kws![simp("NOM").txt().o()]),
                ]
            )
            .rules(vec![un_parmi(&[
                "TOUT_GROUP_MA",
                "GROUP_MA",
                "GROUP_NO",
                "NOEUD",
                "INTERSEC",
                "UNION",
                "DIFFE"
            ])]),
            bloc(eq("OPTION", "ENV_SPHERE"), env_sphere).rules(vec![un_parmi(&[
                "POINT",
                "NOEUD_CENTRE",
                "GROUP_NO_CENTRE"
            ])]),
            bloc(eq("OPTION", "ENV_CYLINDRE"), env_cylindre).rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ]),
            bloc(eq("OPTION", "PLAN"), plan).rules(vec![
                un_parmi(&["POINT", "NOEUD_CENTRE", "GROUP_NO_CENTRE"]),
                un_parmi(&["ANGL_NAUT", "VECT_NORMALE"]),
            ]),
            bloc(
                eq("OPTION", "SEGM_DROI_ORDO"),
                kws![
                    simp("NOM").txt().o(),
                    names("GROUP_NO"),
                    simp("GROUP_NO_ORIG").txt().o(),
                    simp("GROUP_NO_EXTR").txt().o(),
                    simp("PRECISION").r().o(),
                    simp("CRITERE").txt().o().one_of(&["ABSOLU", "RELATIF"]),
                ]
            ),
            bloc(
                eq("OPTION", "NOEUD_ORDO"),
                kws![
                    simp("NOM").txt().o(),
                    names("GROUP_MA").o(),
                    simp("GROUP_NO_ORIG").txt(),
                    simp("GROUP_NO_EXTR").txt(),
                    simp("VECT_ORIE").r().max(3),
                    simp("ORIGINE").txt().one_of(&["SANS"]),
                ]
            ),
            bloc(
                eq("OPTION", "TUNNEL"),
                kws![
                    simp("NOM").txt().o(),
                    tout("TOUT"),
                    names("GROUP_MA"),
                    names("MAILLE"),
                    names("GROUP_MA_AXE"),
                    simp("GROUP_NO_ORIG").txt(),
                    simp("RAYON").r().o(),
                    simp("LONGUEUR").r(),
                ]
            )
            .rules(vec![au_moins_un(&["TOUT", "GROUP_MA", "MAILLE"])]),
            bloc(
                eq("OPTION", "INCLUSION"),
                kws![
                    simp("NOM").txt().o(),
                    simp("CAS_FIGURE").txt().o().one_of(&["2D", "3D", "2.5D"]),
                    simp("DISTANCE_MAX").r(),
                    names("GROUP_MA").o(),
                    names("GROUP_MA_INCL").o(),
                    simp("MAILLAGE_INCL").co(&[ConceptKind::Maillage]),
                ]
            ),
            bloc(
                eq("OPTION", "FISS_XFEM"),
                kws![
                    simp("NOM").txt().o(),
                    simp("TYPE_GROUP").txt().o().one_of(&[
                        "HEAVISIDE",
                        "CRACKTIP",
                        "MIXTE",
                        "XFEM",
                        "ZONE_MAJ",
                        "TORE"
                    ]),
                    simp("FISSURE").co(&[ConceptKind::FissXfem]).o().many(),
                    bloc(eq("TYPE_GROUP", "TORE"), kws![simp("RAYON_TORE").r().o().val_min(0.0)]),
                ]
            ),
            bloc(
                eq("OPTION", "INTERVALLE_VALE"),
                kws![
                    simp("NOM").txt().o(),
                    simp("CHAM_GD").co(&[ConceptKind::ChamNo]).o(),
                    simp("NOM_CMP").txt().o(),
                    simp("VALE").r().o().min(2).max(2),
                ]
            ),
        ],
    )
    .many()
}

fn defi_group() -> Command {
    Command::new("DEFI_GROUP", "Create or destroy groups of cells and nodes in a mesh.")
        .produces(ConceptKind::Maillage)
        .reuse()
        .kw(kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            fact("DETR_GROUP_MA", kws![names("NOM").o()]).many(),
            fact("DETR_GROUP_NO", kws![names("NOM").o()]).many(),
            crea_group_ma(),
            crea_group_no(),
            simp("ALARME").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("INFO").i().one_of_i(&[1, 2]),
        ])
        .rules(vec![au_moins_un(&["CREA_GROUP_MA", "CREA_GROUP_NO", "DETR_GROUP_NO", "DETR_GROUP_MA"])])
}

/// Code_Aster 2025's `UN_PARMI("TOUT", "GROUP_MA", TOUT="OUI")`: TOUT excludes the other selections,
/// and none given means `TOUT='OUI'` (the stage's default). The 2020 syntax asked for at least one of
/// TOUT, MAILLE, GROUP_MA.
fn whole_mesh_by_default() -> Vec<Rule> {
    vec![exclus(&["TOUT", "GROUP_MA"]), exclus(&["TOUT", "MAILLE"])]
}

/// The cells a mesh transformation applies to, with the prefix of new nodes.
fn cells_with_new_nodes(name: &'static str) -> Fact {
    fact(
        name,
        kws![
            tout("TOUT"),
            names("MAILLE"),
            names("GROUP_MA"),
            simp("PREF_NOEUD").txt().d("NS"),
            simp("PREF_NUME").i().d(1),
        ],
    )
    .rules(whole_mesh_by_default())
}

fn crea_maillage() -> Command {
    Command::new(
        "CREA_MAILLAGE",
        "Create a new mesh from an existing one (degree change, cell duplication, restriction...).",
    )
    .produces(ConceptKind::Maillage)
    .kw(kws![
        simp("MAILLAGE").co(&[ConceptKind::Maillage]),
        fact(
            "CREA_POI1",
            kws![
                names("NOM_GROUP_MA"),
                tout("TOUT"),
                names("GROUP_MA"),
                names("MAILLE"),
                names("GROUP_NO"),
                names("NOEUD"),
            ]
        )
        .many()
        .rules(vec![au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"])]),
        fact(
            "CREA_MAILLE",
            kws![
                simp("NOM").txt().o(),
                tout("TOUT"),
                names("MAILLE"),
                names("GROUP_MA"),
                // 2020 syntax (mandatory then), gone in 2025.
                simp("PREF_MAILLE").txt(),
                simp("PREF_NUME").i(),
            ]
        )
        .many()
        .rules(whole_mesh_by_default()),
        fact(
            "RESTREINT",
            kws![
                names("GROUP_MA"),
                names("MAILLE"),
                simp("TOUT_GROUP_MA").txt().d("NON").one_of(&["OUI", "NON"]),
                names("GROUP_NO"),
                simp("TOUT_GROUP_NO").txt().d("NON").one_of(&["OUI", "NON"]),
            ]
        )
        .rules(vec![au_moins_un(&["GROUP_MA", "MAILLE"])]),
        fact(
            "COQU_VOLU",
            kws![
                simp("NOM").txt().o(),
                names("GROUP_MA").o(),
                simp("EPAIS").r().o(),
                simp("PREF_MAILLE").txt().d("MS"),
                simp("PREF_NOEUD").txt().d("NS"),
                simp("PREF_NUME").i().d(1),
                simp("PLAN").txt().o().one_of(&["SUP", "MOY", "INF"]),
                bloc(eq("PLAN", "MOY"), kws![simp("TRANSLATION").txt().o().one_of(&["SUP", "INF"])]),
            ]
        ),
        fact(
            "MODI_MAILLE",
            kws![
                tout("TOUT"),
                names("MAILLE"),
                names("GROUP_MA"),
                simp("OPTION").txt().o().one_of(&["TRIA6_7", "QUAD8_9", "SEG3_4", "QUAD_TRIA3"]),
                bloc(
                    is_in("OPTION", &["TRIA6_7", "QUAD8_9", "SEG3_4"]),
                    kws![simp("PREF_NOEUD").txt().d("NS"), simp("PREF_NUME").i().d(1)]
                ),
                bloc(eq("OPTION", "QUAD_TRIA3"), kws![simp("PREF_MAILLE").txt().d("MS"), simp("PREF_NUME").i().d(1)]),
            ]
        )
        .many()
        .rules(vec![au_moins_un(&["TOUT", "MAILLE", "GROUP_MA"])]),
        fact(
            "CREA_FISS",
            kws![
                simp("NOM").txt().o(),
                simp("GROUP_NO_1").txt().o(),
                simp("GROUP_NO_2").txt().o(),
                // 2020 syntax (mandatory then), gone in 2025.
                simp("PREF_MAILLE").txt(),
                simp("PREF_NUME").i().d(1),
            ]
        )
        .many(),
        cells_with_new_nodes("LINE_QUAD"),
        cells_with_new_nodes("HEXA20_27"),
        cells_with_new_nodes("PENTA15_18"),
        fact(
            "MODI_HHO",
            kws![tout("TOUT"), names("GROUP_MA"), simp("PREF_NOEUD").txt().d("NS"), simp("PREF_NUME").i().d(1)]
        )
        .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
        fact(
            "COQUE_SOLIDE",
            kws![
                names("GROUP_MA"),
                simp("PREF_NOEUD").txt().d("NS"),
                simp("PREF_NUME").i().d(1),
                names("GROUP_MA_SURF"),
            ]
        )
        .many(),
        fact("QUAD_LINE", kws![tout("TOUT"), names("MAILLE"), names("GROUP_MA")]).rules(whole_mesh_by_default()),
        fact(
            "REPERE",
            kws![
                simp("TABLE").co(&[ConceptKind::Table]).o(),
                simp("NOM_ORIG").txt().one_of(&["CDG", "TORSION"]),
                simp("NOM_ROTA").txt().one_of(&["INERTIE"]),
                bloc(eq("NOM_ORIG", "CDG"), kws![simp("GROUP_MA").txt()]),
            ]
        ),
        fact(
            "DECOUPE_LAC",
            kws![names("GROUP_MA_ESCL").o(), simp("DECOUPE_HEXA").txt().d("PYRA").one_of(&["PYRA", "HEXA"])]
        ),
        fact(
            "ECLA_PG",
            kws![
                simp("MODELE").co(&[ConceptKind::Modele]).o(),
                tout("TOUT"),
                names("MAILLE"),
                names("GROUP_MA"),
                simp("SHRINK").r().d(0.9),
                simp("TAILLE_MIN").r().d(0.0),
                names("NOM_CHAM").o(),
            ]
        ),
        simp("TITRE").txt(),
        simp("INFO").i().d(1).one_of_i(&[1, 2]),
    ])
    .rules(vec![un_parmi(&[
        "COQU_VOLU",
        "CREA_FISS",
        "CREA_MAILLE",
        "CREA_POI1",
        "ECLA_PG",
        "HEXA20_27",
        "LINE_QUAD",
        "MODI_MAILLE",
        "QUAD_LINE",
        "REPERE",
        "RESTREINT",
        "PENTA15_18",
        "DECOUPE_LAC",
        "MODI_HHO",
        "COQUE_SOLIDE",
    ])])
}

/// A factor keyword orienting the cells of GROUP_MA, with an optional vector
/// and the node fixing its sense.
fn orie_with_vector(name: &'static str, vect: &'static str) -> Fact {
    fact(
        name,
        kws![
            names("GROUP_MA").o(),
            simp(vect).r().max(3),
            bloc(present(vect), kws![simp("NOEUD").txt(), simp("GROUP_NO").txt()])
                .rules(vec![un_parmi(&["NOEUD", "GROUP_NO"])]),
        ],
    )
    .many()
}

fn modi_maillage() -> Command {
    let orient = [
        "ORIE_FISSURE",
        "DEFORME",
        "ORIE_PEAU",
        "ORIE_PEAU_2D",
        "ORIE_PEAU_3D",
        "ORIE_NORM_COQUE",
        "MODI_MAILLE",
        "ORIE_LIGNE",
    ];
    let others = |me: &'static str| -> Vec<&'static str> { orient.iter().copied().filter(|k| *k != me).collect() };
    let mut rules = vec![au_moins_un(&[
        "ORIE_FISSURE",
        "DEFORME",
        "ORIE_PEAU",
        "ORIE_PEAU_2D",
        "ORIE_PEAU_3D",
        "ORIE_NORM_COQUE",
        "MODI_MAILLE",
        "TRANSLATION",
        "ROTATION",
        "MODI_BASE",
        "ECHELLE",
        "SYMETRIE",
        "ORIE_LIGNE",
        "ABSC_CURV",
    ])];
    for k in ["ORIE_FISSURE", "DEFORME", "ORIE_PEAU", "ORIE_PEAU_2D", "ORIE_PEAU_3D", "ORIE_NORM_COQUE", "MODI_MAILLE"]
    {
        rules.push(present_absent(k, &others(k)));
    }
    rules.extend(vec![
        exclus(&["ROTATION", "MODI_BASE"]),
        exclus(&["SYMETRIE", "ROTATION"]),
        exclus(&["SYMETRIE", "TRANSLATION"]),
        exclus(&["SYMETRIE", "MODI_BASE"]),
        exclus(&["SYMETRIE", "ECHELLE"]),
    ]);
    Command::new("MODI_MAILLAGE", "Modify a mesh: orient skin cells, move, rotate or scale nodes.")
        .produces(ConceptKind::Maillage)
        .reuse()
        .kw(kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            fact("ORIE_FISSURE", kws![names("GROUP_MA").o()]),
            fact(
                "DEFORME",
                kws![
                    simp("OPTION").txt().o().one_of(&["TRAN"]),
                    simp("DEPL").co(&[ConceptKind::ChamNo]),
                    simp("ALEA").r(),
                ]
            )
            .rules(vec![un_parmi(&["DEPL", "ALEA"])]),
            fact("ORIE_PEAU", kws![names("GROUP_MA_PEAU").o(), names("GROUP_MA_INTERNE")]).many(),
            // Former syntax, turned into ORIE_PEAU by Code_Aster.
            fact("ORIE_PEAU_2D", kws![names("GROUP_MA").o(), names("GROUP_MA_SURF")]).many(),
            fact("ORIE_PEAU_3D", kws![names("GROUP_MA").o(), names("GROUP_MA_VOLU")]).many(),
            orie_with_vector("ORIE_NORM_COQUE", "VECT_NORM"),
            orie_with_vector("ORIE_LIGNE", "VECT_TANG"),
            fact(
                "MODI_MAILLE",
                kws![
                    simp("OPTION").txt().o().one_of(&["NOEUD_QUART"]),
                    simp("GROUP_MA_FOND").txt(),
                    simp("MAILLE_FOND").txt(),
                    simp("GROUP_NO_FOND").txt(),
                    simp("NOEUD_FOND").txt(),
                ]
            )
            .rules(vec![au_moins_un(&["GROUP_MA_FOND", "MAILLE_FOND", "GROUP_NO_FOND", "NOEUD_FOND"])]),
            fact("MODI_BASE", kws![simp("VECT_X").r().o().min(2).max(3), simp("VECT_Y").r().min(2).max(3)]),
            simp("ECHELLE").r(),
            simp("TRANSLATION").r().min(2).max(3),
            fact(
                "ROTATION",
                kws![
                    simp("POIN_1").r().o().min(2).max(3),
                    simp("ANGLE").r().d(0.0),
                    simp("POIN_2").r().min(2).max(3),
                    simp("DIR").r().min(2).max(3),
                ]
            )
            .many()
            .rules(vec![exclus(&["DIR", "POIN_2"])]),
            fact(
                "SYMETRIE",
                kws![
                    simp("POINT").r().o().min(2).max(3),
                    simp("AXE_1").r().o().min(2).max(3),
                    simp("AXE_2").r().min(3).max(3),
                ]
            ),
            fact(
                "ABSC_CURV",
                kws![
                    tout("TOUT"),
                    names("GROUP_MA"),
                    names("MAILLE"),
                    simp("GROUP_NO_ORIG").txt(),
                    simp("NOEUD_ORIG").txt(),
                ]
            )
            .rules(vec![
                au_moins_un(&["TOUT", "GROUP_MA", "MAILLE"]),
                un_parmi(&["GROUP_NO_ORIG", "NOEUD_ORIG"]),
                exclus(&["TOUT", "GROUP_MA"]),
                exclus(&["TOUT", "MAILLE"]),
            ]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
        .rules(rules)
}
