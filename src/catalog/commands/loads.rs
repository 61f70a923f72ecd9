//! Mechanical loads and boundary conditions (AFFE_CHAR_MECA, AFFE_CHAR_MECA_F), thermal ones
//! (AFFE_CHAR_THER(_F), in `thermal`) and contact definitions (DEFI_CONTACT).

use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

mod thermal;

pub fn commands() -> Vec<Command> {
    vec![
        affe_char_meca(),
        affe_char_meca_f(),
        affe_char_cine(V::Real),
        affe_char_cine(V::Func),
        defi_contact(),
        thermal::affe_char_ther(),
        thermal::affe_char_ther_f(),
    ]
}

/// A function of one or more parameters.
const FUNC: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule];

/// Whether load values are reals (AFFE_CHAR_MECA) or functions (AFFE_CHAR_MECA_F).
#[derive(Clone, Copy, PartialEq)]
enum V {
    Real,
    Func,
}

/// A load value: a real or a function, depending on the command.
fn val(name: &'static str, v: V) -> Simp {
    match v {
        V::Real => simp(name).r(),
        V::Func => simp(name).co(FUNC),
    }
}

/// Optional load values.
fn vals(names: &[&'static str], v: V) -> Vec<Entry> {
    names.iter().map(|n| Entry::from(val(n, v))).collect()
}

fn tout() -> Simp {
    simp("TOUT").txt().one_of(&["OUI"])
}

fn names(name: &'static str) -> Simp {
    simp(name).txt().many()
}

/// The degrees of freedom of mechanical models (LIAISON_DDL, LIAISON_UNIF...).
const DDL_MECA: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "PRES", "PHI", "GONF", "TEMP", "PRE1", "PRE2", "GRX", "DRGX", "DRGY",
    "DRGZ", "PSI", "UI2", "UI3", "VI2", "VI3", "WI2", "WI3", "UO2", "UO3", "VO2", "VO3", "WO2", "WO3", "UI4", "UI5",
    "VI4", "VI5", "WI4", "WI5", "UO4", "UO5", "VO4", "VO5", "WO4", "WO5", "UI6", "UO6", "VI6", "VO6", "WI6", "WO6",
    "WO", "WI1", "WO1", "H1X", "H1Y", "H1Z", "H1PRE1", "K1", "K2", "K3", "V11", "V12", "V13", "V21", "V22", "V23",
    "V31", "V32", "V33", "PRES11", "PRES12", "PRES13", "PRES21", "PRES22", "PRES23", "PRES31", "PRES32", "PRES33",
    "LH1", "GLIS", "HHO_U1", "HHO_U2", "HHO_U3", "HHO_U4", "HHO_U5", "HHO_U6", "HHO_V1", "HHO_V2", "HHO_V3", "HHO_V4",
    "HHO_V5", "HHO_V6", "HHO_W1", "HHO_W2", "HHO_W3", "HHO_W4", "HHO_W5", "HHO_W6",
];

/// DDL_MECA and DNOR.
fn ddl_meca_dnor() -> Vec<&'static str> {
    let mut v = DDL_MECA.to_vec();
    v.push("DNOR");
    v
}

/// Components DDL_IMPO accepts in AFFE_CHAR_MECA.
const DDL_IMPO_R: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "GRX", "DRGX", "DRGY", "DRGZ", "PRES", "PSI", "PHI", "TEMP", "PRE1", "PRE2",
    "UI2", "UI3", "UI4", "UI5", "UI6", "UO2", "UO3", "UO4", "UO5", "UO6", "VI2", "VI3", "VI4", "VI5", "VI6", "VO2",
    "VO3", "VO4", "VO5", "VO6", "WI2", "WI3", "WI4", "WI5", "WI6", "WO2", "WO3", "WO4", "WO5", "WO6", "WO", "WI1",
    "WO1", "GONF", "H1X", "H1Y", "H1Z", "H1PRE1", "H2X", "H2Y", "H2Z", "H2PRE1", "H3X", "H3Y", "H3Z", "H3PRE1", "H4X",
    "H4Y", "H4Z", "K1", "K2", "K3", "PRE_FLU", "LAG_FLI", "LAG_FLS", "PR2_FLU", "LA2_FLI", "LA2_FLS", "PR3_FLU",
    "LA3_FLI", "LA3_FLS", "LAGS_C", "LAGS_F1", "LAGS_F2", "LAG2_C", "LAG2_F1", "LAG2_F2", "LAG3_C", "LAG3_F1",
    "LAG3_F2", "LAG4_C", "LAG4_F1", "LAG4_F2", "V11", "V12", "V13", "V21", "V22", "V23", "V31", "V32", "V33", "PRES11",
    "PRES12", "PRES13", "PRES21", "PRES22", "PRES23", "PRES31", "PRES32", "PRES33", "LH1", "GLIS",
];

/// Components DDL_IMPO accepts in AFFE_CHAR_MECA_F.
const DDL_IMPO_F: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "DRGX", "DRGY", "DRGZ", "GRX", "PRES", "PHI", "TEMP", "PRE1", "PRE2",
    "GONF", "H1X", "H1Y", "H1Z", "H1PRE1", "K1", "K2", "K3", "LAGS_C", "GLIS",
];

fn ddl_impo(v: V) -> Fact {
    let (comps, blocage): (&[&'static str], Simp) = match v {
        V::Real => (DDL_IMPO_R, simp("BLOCAGE").txt().max(3).one_of(&["DEPLACEMENT", "ROTATION", "TUYAU_FOURIER"])),
        V::Func => (DDL_IMPO_F, simp("BLOCAGE").txt().max(2).one_of(&["DEPLACEMENT", "ROTATION"])),
    };
    let mut e = kws![
        tout(),
        names("NOEUD"),
        names("GROUP_NO"),
        names("GROUP_MA"),
        names("SANS_GROUP_MA"),
        names("SANS_GROUP_NO"),
        blocage,
        // Former syntax, turned into BLOCAGE by Code_Aster.
        simp("LIAISON").txt().one_of(&["ENCASTRE"]),
    ];
    e.extend(vals(comps, v));
    let mut any: Vec<&'static str> = comps.to_vec();
    any.extend(["BLOCAGE", "LIAISON"]);
    fact("DDL_IMPO", e).many().rules(vec![au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO", "NOEUD"]), au_moins_un(&any)])
}

fn face_impo(v: V) -> Fact {
    let comps =
        ["DX", "DY", "DZ", "DRX", "DRY", "DRZ", "DNOR", "DRNOR", "DTAN", "GRX", "PRES", "PHI", "TEMP", "PRE1", "PRE2"];
    let mut e = kws![names("GROUP_MA"), names("SANS_GROUP_MA"), names("SANS_GROUP_NO")];
    e.extend(vals(&comps, v));
    let mut rules = vec![au_moins_un(&comps)];
    for c in ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"] {
        rules.push(exclus(&["DNOR", c]));
    }
    for c in ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"] {
        rules.push(exclus(&["DTAN", c]));
    }
    fact("FACE_IMPO", e).many().rules(rules)
}

fn liaison_ddl(v: V) -> Fact {
    let mut e = kws![names("GROUP_NO"), names("NOEUD"), simp("DDL").txt().o().many().one_of(DDL_MECA),];
    let mut rules = vec![un_parmi(&["GROUP_NO", "NOEUD"])];
    match v {
        V::Real => e.extend(kws![simp("COEF_MULT").r().o().many(), simp("COEF_IMPO").r().o()]),
        V::Func => {
            e.extend(kws![
                simp("COEF_MULT").r().many(),
                simp("COEF_MULT_FONC").co(FUNC).many(),
                simp("COEF_IMPO").co(FUNC).o(),
            ]);
            rules.push(un_parmi(&["COEF_MULT", "COEF_MULT_FONC"]));
        }
    }
    fact("LIAISON_DDL", e).many().rules(rules)
}

fn liaison_oblique(v: V) -> Fact {
    let comps = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];
    let mut e = kws![
        names("GROUP_NO"),
        names("GROUP_MA"),
        names("SANS_GROUP_MA"),
        names("SANS_GROUP_NO"),
        simp("ANGL_NAUT").r().o().max(3),
    ];
    e.extend(vals(&comps, v));
    fact("LIAISON_OBLIQUE", e).many().rules(vec![au_moins_un(&["GROUP_MA", "GROUP_NO"]), au_moins_un(&comps)])
}

fn liaison_group(v: V) -> Fact {
    let dofs = ddl_meca_dnor();
    fact(
        "LIAISON_GROUP",
        kws![
            names("GROUP_MA_1"),
            names("GROUP_MA_2"),
            names("GROUP_NO_1"),
            names("GROUP_NO_2"),
            names("SANS_GROUP_NO"),
            simp("DDL_1").txt().o().many().one_of(&dofs),
            simp("COEF_MULT_1").r().o().many(),
            simp("DDL_2").txt().o().many().one_of(&dofs),
            simp("COEF_MULT_2").r().o().many(),
            val("COEF_IMPO", v).o(),
            simp("TRAN").r().max(3),
            simp("ANGL_NAUT").r().max(3),
            simp("CENTRE").r().max(3),
        ],
    )
    .many()
    .rules(vec![
        un_parmi(&["GROUP_MA_1", "GROUP_NO_1"]),
        un_parmi(&["GROUP_MA_2", "GROUP_NO_2"]),
        exclus(&["GROUP_MA_1", "GROUP_NO_2"]),
        exclus(&["GROUP_NO_1", "GROUP_MA_2"]),
    ])
}

fn liaison_unif() -> Fact {
    fact(
        "LIAISON_UNIF",
        kws![
            names("GROUP_NO"),
            names("GROUP_MA"),
            names("SANS_GROUP_MA"),
            names("SANS_GROUP_NO"),
            simp("DDL").txt().o().many().one_of(DDL_MECA),
        ],
    )
    .many()
    .rules(vec![un_parmi(&["GROUP_NO", "GROUP_MA"])])
}

fn liaison_coque() -> Fact {
    fact(
        "LIAISON_COQUE",
        kws![
            names("GROUP_MA_1"),
            names("GROUP_NO_1"),
            names("SANS_GROUP_MA_1"),
            names("SANS_GROUP_NO_1"),
            names("GROUP_MA_2"),
            names("GROUP_NO_2"),
            names("SANS_GROUP_MA_2"),
            names("SANS_GROUP_NO_2"),
        ],
    )
    .many()
    .rules(vec![au_moins_un(&["GROUP_MA_1", "GROUP_MA_2", "GROUP_NO_1", "GROUP_NO_2"])])
}

fn force_nodale(v: V) -> Fact {
    let comps = ["FX", "FY", "FZ", "MX", "MY", "MZ"];
    let mut e = kws![names("GROUP_NO"), names("NOEUD")];
    e.extend(vals(&comps, v));
    e.push(Entry::from(val("ANGL_NAUT", v).max(3)));
    fact("FORCE_NODALE", e).many().rules(vec![un_parmi(&["GROUP_NO", "NOEUD"]), au_moins_un(&comps)])
}

/// FORCE_FACE, FORCE_CONTOUR: forces on a group of cells.
fn force_on_cells(name: &'static str, comps: &'static [&'static str], v: V) -> Fact {
    let mut e = kws![names("GROUP_MA")];
    e.extend(vals(comps, v));
    fact(name, e).many().rules(vec![au_moins_un(comps)])
}

fn force_interne(v: V) -> Fact {
    let mut e = kws![tout(), names("GROUP_MA")];
    e.extend(vals(&["FX", "FY", "FZ"], v));
    // Neither TOUT nor GROUP_MA means TOUT='OUI'.
    fact("FORCE_INTERNE", e).many().rules(vec![exclus(&["TOUT", "GROUP_MA"]), au_moins_un(&["FX", "FY", "FZ"])])
}

fn pres_rep(v: V) -> Fact {
    fact(
        "PRES_REP",
        kws![
            tout(),
            names("GROUP_MA"),
            simp("FISSURE").co(&[ConceptKind::FissXfem]).max(100),
            val("PRES", v),
            val("CISA_2D", v),
        ],
    )
    .many()
    .rules(vec![
        au_moins_un(&["TOUT", "GROUP_MA", "FISSURE"]),
        present_absent("TOUT", &["GROUP_MA", "FISSURE"]),
        au_moins_un(&["PRES", "CISA_2D"]),
    ])
}

fn effe_fond(v: V) -> Fact {
    fact("EFFE_FOND", kws![names("GROUP_MA_INT").o(), names("GROUP_MA"), val("PRES", v).o()]).many()
}

fn force_poutre(v: V) -> Fact {
    let force = ["FX", "FY", "FZ", "MX", "MY", "MZ", "N", "VY", "VZ", "MT", "MFY", "MFZ", "MGX", "MGY", "MGZ"];
    let global = ["FX", "FY", "FZ", "MX", "MY", "MZ"];
    let local = ["N", "VY", "VZ", "MT", "MFY", "MFZ"];
    let mut force_rules = vec![au_moins_un(&force)];
    for k in global {
        force_rules.push(present_absent(k, &local));
    }
    for k in local {
        force_rules.push(present_absent(k, &global));
    }
    let vent = ["FX", "FY", "FZ", "N", "VY", "VZ"];
    let mut vent_rules = vec![au_moins_un(&vent)];
    for k in ["FX", "FY", "FZ"] {
        vent_rules.push(present_absent(k, &["N", "VY", "VZ"]));
    }
    for k in ["N", "VY", "VZ"] {
        vent_rules.push(present_absent(k, &["FX", "FY", "FZ"]));
    }
    fact(
        "FORCE_POUTRE",
        kws![
            tout(),
            names("GROUP_MA"),
            simp("TYPE_CHARGE").txt().d("FORCE").one_of(&["VENT", "FORCE"]),
            bloc(eq("TYPE_CHARGE", "FORCE"), vals(&force, v)).rules(force_rules),
            // Wind loads are functions in both commands.
            bloc(eq("TYPE_CHARGE", "VENT"), vals(&vent, V::Func)).rules(vent_rules),
        ],
    )
    .many()
    .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])])
}

fn force_tuyau(v: V) -> Fact {
    fact("FORCE_TUYAU", kws![tout(), names("GROUP_MA"), val("PRES", v).o()])
        .many()
        .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])])
}

fn force_coque(v: V) -> Fact {
    let comps = ["FX", "FY", "FZ", "MX", "MY", "MZ", "F1", "F2", "F3", "MF1", "MF2", "PRES"];
    let global = ["FX", "FY", "FZ", "MX", "MY", "MZ"];
    let local = ["F1", "F2", "F3", "MF1", "MF2"];
    let mut rules = vec![un_parmi(&["TOUT", "GROUP_MA"]), au_moins_un(&comps)];
    for k in global {
        let mut others = vec!["PRES"];
        others.extend(local);
        rules.push(present_absent(k, &others));
    }
    for k in local {
        let mut others = vec!["PRES"];
        others.extend(global);
        rules.push(present_absent(k, &others));
    }
    let mut e = kws![tout(), names("GROUP_MA")];
    e.extend(vals(&comps, v));
    e.push(Entry::from(simp("PLAN").txt().d("MAIL").one_of(&["SUP", "INF", "MOY", "MAIL"])));
    fact("FORCE_COQUE", e).many().rules(rules)
}

fn vite_face(v: V) -> Fact {
    fact(
        "VITE_FACE",
        kws![
            names("GROUP_MA"),
            val("VNOR", v),
            val("DIRECTION", v).min(2).max(3),
            bloc(present("DIRECTION"), kws![val("VITE", v).o()]),
        ],
    )
    .many()
    .rules(vec![un_parmi(&["VNOR", "DIRECTION"])])
}

fn flux_thm_rep(v: V) -> Fact {
    let comps: &[&'static str] = match v {
        V::Real => &["FLUN", "FLUN_HYDR1", "FLUN_HYDR2"],
        V::Func => &["FLUN", "FLUN_FRAC", "FLUN_HYDR1", "FLUN_HYDR2"],
    };
    let mut e = kws![tout(), names("GROUP_MA")];
    e.extend(vals(comps, v));
    fact("FLUX_THM_REP", e).many().rules(vec![un_parmi(&["TOUT", "GROUP_MA"]), au_moins_un(comps)])
}

fn echange_thm(v: V) -> Fact {
    let (coef_11, pre1_ext) = match v {
        V::Real => (val("COEF_11", v), val("PRE1_EXT", v)),
        V::Func => (val("COEF_11", v).o(), val("PRE1_EXT", v).o()),
    };
    let tout_rule = match v {
        V::Real => un_parmi(&["TOUT", "GROUP_MA"]),
        // Neither TOUT nor GROUP_MA means TOUT='OUI'.
        V::Func => exclus(&["TOUT", "GROUP_MA"]),
    };
    fact(
        "ECHANGE_THM",
        kws![
            tout(),
            names("GROUP_MA"),
            coef_11,
            val("COEF_12", v),
            val("COEF_21", v),
            val("COEF_22", v),
            pre1_ext,
            val("PRE2_EXT", v),
        ],
    )
    .many()
    .rules(vec![tout_rule, au_moins_un(&["COEF_11", "COEF_12", "COEF_21", "COEF_22"])])
}

fn affe_char_meca() -> Command {
    let v = V::Real;
    let epsi =
        ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ", "EPX", "KY", "KZ", "EXX", "EYY", "EXY", "KXX", "KYY", "KXY"];
    let mut pre_epsi = kws![tout(), names("GROUP_MA")];
    pre_epsi.extend(vals(&epsi, v));
    pre_epsi.extend(kws![
        simp("EPSI").co(&[ConceptKind::ChamElem, ConceptKind::Carte]),
        simp("VECT_N").r().min(3).max(3),
        bloc(present("VECT_N"), kws![simp("KN1").r(), simp("KN2").r()]).rules(vec![au_moins_un(&["KN1", "KN2"])]),
    ]);
    let mut epsi_any = vec!["EPSI"];
    epsi_any.extend(epsi);
    epsi_any.push("VECT_N");
    let epsi_others: Vec<&'static str> = epsi_any[1..].to_vec();

    Command::new("AFFE_CHAR_MECA", "Define mechanical loads and boundary conditions with constant values.")
        .produces(ConceptKind::CharMeca)
        .kw(kws![
            simp("VERI_AFFE").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("VERI_NORM").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("CHAM_MATER").co(&[ConceptKind::ChamMater]),
            simp("DOUBLE_LAGRANGE").txt().d("OUI").one_of(&["OUI", "NON"]),
            fact(
                "PESANTEUR",
                kws![names("GROUP_MA"), simp("GRAVITE").r().o(), simp("DIRECTION").r().o().min(3).max(3)]
            ),
            fact(
                "ROTATION",
                kws![
                    names("GROUP_MA"),
                    names("SANS_GROUP_MA"),
                    simp("VITESSE").r().o(),
                    simp("AXE").r().o().min(2).max(3),
                    simp("CENTRE").r().min(2).max(3),
                ]
            ),
            ddl_impo(v),
            fact(
                "DDL_POUTRE",
                kws![
                    tout(),
                    names("GROUP_NO"),
                    names("GROUP_MA"),
                    names("SANS_GROUP_MA"),
                    names("SANS_GROUP_NO"),
                    simp("DX").r(),
                    simp("DY").r(),
                    simp("DZ").r(),
                    simp("DRX").r(),
                    simp("DRY").r(),
                    simp("DRZ").r(),
                    simp("VECT_Y").r().min(3).max(3),
                    simp("ANGL_VRIL").r(),
                    simp("GROUP_MA_REPE").txt(),
                ]
            )
            .many()
            .rules(vec![
                au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO"]),
                au_moins_un(&["DX", "DY", "DZ", "DRX", "DRY", "DRZ"]),
                un_parmi(&["VECT_Y", "ANGL_VRIL"]),
            ]),
            face_impo(v),
            fact("CHAMNO_IMPO", kws![simp("CHAM_NO").co(&[ConceptKind::ChamNo]).o(), simp("COEF_IMPO").r().o()]),
            fact(
                "ARETE_IMPO",
                kws![
                    names("GROUP_MA"),
                    names("SANS_GROUP_MA"),
                    names("SANS_GROUP_NO"),
                    simp("DX").r(),
                    simp("DY").r(),
                    simp("DZ").r(),
                    simp("DTAN").r(),
                    simp("PRE1").r(),
                    simp("PRE2").r(),
                    simp("PRES").r(),
                    simp("PHI").r(),
                    simp("TEMP").r(),
                ]
            )
            .many()
            .rules(vec![
                au_moins_un(&["DX", "DY", "DZ", "DTAN", "PRES", "PHI", "TEMP", "PRE1", "PRE2"]),
                exclus(&["DTAN", "DX"]),
                exclus(&["DTAN", "DY"]),
                exclus(&["DTAN", "DZ"]),
            ]),
            liaison_ddl(v),
            liaison_oblique(v),
            liaison_group(v),
            fact(
                "LIAISON_MAIL",
                kws![
                    names("GROUP_MA_MAIT"),
                    names("GROUP_MA_ESCL"),
                    names("GROUP_NO_ESCL"),
                    simp("DISTANCE_MAX").r(),
                    simp("DISTANCE_ALARME").r(),
                    simp("TYPE_RACCORD").txt().d("MASSIF").one_of(&["MASSIF", "COQUE", "COQUE_MASSIF", "MASSIF_COQUE"]),
                    bloc(
                        eq("TYPE_RACCORD", "COQUE"),
                        kws![
                            simp("TRANSF_GEOM_MAIT").co(FUNC).min(3).max(3),
                            simp("TRANSF_GEOM_ESCL").co(FUNC).min(3).max(3),
                            simp("DDL").txt().max(6).one_of(&["DX", "DY", "DZ", "DRX", "DRY", "DRZ"]),
                        ]
                    ),
                    bloc(
                        eq("TYPE_RACCORD", "MASSIF"),
                        kws![
                            simp("TRAN").r().max(3),
                            simp("ANGL_NAUT").r().max(3),
                            simp("CENTRE").r().max(3),
                            simp("DDL").txt().many().one_of(&ddl_meca_dnor()),
                        ]
                    ),
                    bloc(
                        eq("TYPE_RACCORD", "COQUE_MASSIF"),
                        kws![simp("EPAIS").r().o(), simp("CHAM_NORMALE").co(&[ConceptKind::ChamNo]).o()]
                    ),
                    simp("ELIM_MULT").txt().d("OUI").one_of(&["OUI", "NON"]),
                ]
            )
            .many()
            .rules(vec![au_moins_un(&["GROUP_MA_ESCL", "GROUP_NO_ESCL"])]),
            fact(
                "LIAISON_CYCL",
                kws![
                    names("GROUP_MA_MAIT1"),
                    names("GROUP_MA_MAIT2"),
                    names("GROUP_MA_ESCL"),
                    names("GROUP_NO_ESCL"),
                    simp("TRAN").r().max(3),
                    simp("ANGL_NAUT").r().max(3),
                    simp("CENTRE").r().max(3),
                    simp("COEF_MAIT1").r(),
                    simp("COEF_MAIT2").r(),
                    simp("COEF_ESCL").r(),
                    simp("DDL_MAIT").txt().one_of(&["DNOR"]),
                    simp("DDL_ESCL").txt().one_of(&["DNOR"]),
                ]
            )
            .many()
            .rules(vec![au_moins_un(&["GROUP_MA_ESCL", "GROUP_NO_ESCL"]), present_present("DDL_MAIT", &["DDL_ESCL"]),]),
            fact(
                "LIAISON_SOLIDE",
                kws![
                    names("GROUP_NO"),
                    names("GROUP_MA"),
                    names("SANS_GROUP_MA"),
                    names("SANS_GROUP_NO"),
                    simp("DIST_MIN").r(),
                ]
            )
            .many()
            .rules(vec![un_parmi(&["GROUP_NO", "GROUP_MA"])]),
            liaison_unif(),
            fact("LIAISON_CHAMNO", kws![simp("CHAM_NO").co(&[ConceptKind::ChamNo]).o(), simp("COEF_IMPO").r().o()]),
            fact(
                "LIAISON_RBE3",
                kws![
                    simp("GROUP_NO_MAIT").txt(),
                    simp("DDL_MAIT").txt().o().max(6).one_of(&["DX", "DY", "DZ", "DRX", "DRY", "DRZ"]),
                    names("GROUP_NO_ESCL"),
                    simp("DDL_ESCL").txt().o().many(),
                    simp("COEF_ESCL").r().many().d(1.0),
                ]
            )
            .many(),
            simp("VECT_ASSE").co(&[ConceptKind::ChamNo]),
            force_nodale(v),
            force_on_cells("FORCE_FACE", &["FX", "FY", "FZ"], v),
            force_on_cells("FORCE_ARETE", &["FX", "FY", "FZ", "MX", "MY", "MZ"], v),
            force_on_cells("FORCE_CONTOUR", &["FX", "FY", "FZ"], v),
            force_interne(v),
            fact("PRE_SIGM", kws![simp("SIGM").co(&[ConceptKind::ChamElem, ConceptKind::Carte]).o()]),
            pres_rep(v),
            effe_fond(v),
            fact("PRE_EPSI", pre_epsi).many().rules(vec![
                au_moins_un(&["TOUT", "GROUP_MA", "EPSI"]),
                present_absent("TOUT", &["GROUP_MA"]),
                present_absent("EPSI", &["TOUT", "GROUP_MA"]),
                au_moins_un(&epsi_any),
                present_absent("EPSI", &epsi_others),
                present_absent("VECT_N", &["KY", "KZ"]),
            ]),
            force_poutre(v),
            force_tuyau(v),
            force_coque(v),
            fact("FORCE_COQUE_FO", kws![tout(), names("GROUP_MA"), simp("PRES").co(FUNC)])
                .many()
                .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
            liaison_coque(),
            vite_face(v),
            fact("ONDE_FLUI", kws![names("GROUP_MA"), simp("PRES").r().o()]).many(),
            flux_thm_rep(v),
            echange_thm(v),
            fact(
                "ECHANGE_THM_HR",
                kws![
                    tout(),
                    names("GROUP_MA"),
                    simp("HR_EXT").r().o(),
                    simp("ALPHA").r().o(),
                    simp("PVAP_SAT").r().o(),
                ]
            )
            .many()
            .rules(vec![exclus(&["TOUT", "GROUP_MA"])]),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
        .rules(vec![
            au_moins_un(&[
                "PESANTEUR",
                "ROTATION",
                "DDL_IMPO",
                "DDL_POUTRE",
                "FACE_IMPO",
                "CHAMNO_IMPO",
                "ARETE_IMPO",
                "LIAISON_DDL",
                "LIAISON_OBLIQUE",
                "LIAISON_GROUP",
                "LIAISON_MAIL",
                "LIAISON_CYCL",
                "LIAISON_SOLIDE",
                "LIAISON_UNIF",
                "LIAISON_CHAMNO",
                "LIAISON_RBE3",
                "VECT_ASSE",
                "FORCE_NODALE",
                "FORCE_FACE",
                "FORCE_ARETE",
                "FORCE_CONTOUR",
                "FORCE_INTERNE",
                "PRE_SIGM",
                "PRES_REP",
                "EFFE_FOND",
                "PRE_EPSI",
                "FORCE_POUTRE",
                "FORCE_TUYAU",
                "FORCE_COQUE",
                "FORCE_COQUE_FO",
                "LIAISON_COQUE",
                "VITE_FACE",
                "ONDE_FLUI",
                "FLUX_THM_REP",
                "ECHANGE_THM",
                "ECHANGE_THM_HR",
            ]),
            present_present("EFFE_FOND", &["PRES_REP"]),
            exclus(&["FORCE_COQUE", "FORCE_COQUE_FO"]),
        ])
}

fn affe_char_meca_f() -> Command {
    let v = V::Func;
    let epsi =
        ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ", "EPX", "KY", "KZ", "EXX", "EYY", "EXY", "KXX", "KYY", "KXY"];
    let mut pre_epsi = kws![tout(), names("GROUP_MA")];
    pre_epsi.extend(vals(&epsi, v));
    Command::new("AFFE_CHAR_MECA_F", "Define mechanical loads and boundary conditions whose values are functions.")
        .produces(ConceptKind::CharMeca)
        .kw(kws![
            simp("VERI_NORM").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("DOUBLE_LAGRANGE").txt().d("OUI").one_of(&["OUI", "NON"]),
            ddl_impo(v),
            face_impo(v),
            liaison_ddl(v),
            liaison_oblique(v),
            liaison_group(v),
            liaison_unif(),
            force_nodale(v),
            force_on_cells("FORCE_FACE", &["FX", "FY", "FZ"], v),
            force_on_cells("FORCE_ARETE", &["FX", "FY", "FZ", "MX", "MY", "MZ"], v),
            force_on_cells("FORCE_CONTOUR", &["FX", "FY", "FZ"], v),
            force_interne(v),
            pres_rep(v),
            effe_fond(v),
            fact("PRE_EPSI", pre_epsi).many().rules(vec![exclus(&["TOUT", "GROUP_MA"]), au_moins_un(&epsi)]),
            force_poutre(v),
            force_tuyau(v),
            force_coque(v),
            liaison_coque(),
            vite_face(v),
            fact(
                "ONDE_PLANE",
                kws![
                    simp("DIRECTION").r().o().min(3).max(3),
                    simp("COOR_SOURCE").r().min(2).max(3),
                    bloc(present("COOR_SOURCE"), kws![simp("COOR_REFLECHI").r().min(2).max(3)]),
                    simp("TYPE_ONDE").txt().o().one_of(&["S", "P", "SV", "SH"]),
                    simp("FONC_SIGNAL").co(FUNC).o(),
                    simp("DEPL_IMPO").co(FUNC),
                    names("GROUP_MA"),
                ]
            ),
            flux_thm_rep(v),
            echange_thm(v),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
        ])
        .rules(vec![au_moins_un(&[
            "DDL_IMPO",
            "FACE_IMPO",
            "LIAISON_DDL",
            "FORCE_NODALE",
            "FORCE_FACE",
            "FORCE_ARETE",
            "FORCE_CONTOUR",
            "FORCE_INTERNE",
            "PRES_REP",
            "FORCE_POUTRE",
            "VITE_FACE",
            "ONDE_PLANE",
            "LIAISON_OBLIQUE",
            "PRE_EPSI",
            "LIAISON_GROUP",
            "LIAISON_UNIF",
            "FORCE_COQUE",
            "LIAISON_COQUE",
            "FORCE_TUYAU",
            "EFFE_FOND",
            "FLUX_THM_REP",
            "ECHANGE_THM",
        ])])
}

// ------------------------------------------------------------------ DEFI_CONTACT

fn oui_non(name: &'static str, default: &'static str) -> Simp {
    simp(name).txt().d(default).one_of(&["OUI", "NON"])
}

/// Geometric loop (REAC_GEOM) with its iteration parameters.
fn reac_geom(default: &'static str, resi_geom: f64) -> Vec<Entry> {
    kws![
        simp("REAC_GEOM").txt().d(default).one_of(&["AUTOMATIQUE", "CONTROLE", "SANS"]),
        bloc(
            eq("REAC_GEOM", "AUTOMATIQUE"),
            kws![simp("ITER_GEOM_MAXI").i().d(10), simp("RESI_GEOM").r().d(resi_geom)]
        ),
        bloc(eq("REAC_GEOM", "CONTROLE"), kws![simp("NB_ITER_GEOM").i().d(2)]),
    ]
}

/// Contact loop counted as a multiple of the number of contact nodes, or a maximum.
fn iter_cont_type() -> Vec<Entry> {
    kws![
        simp("ITER_CONT_TYPE").txt().d("MAXI").one_of(&["MULT", "MAXI"]),
        bloc(eq("ITER_CONT_TYPE", "MULT"), kws![simp("ITER_CONT_MULT").i().d(4)]),
        bloc(eq("ITER_CONT_TYPE", "MAXI"), kws![simp("ITER_CONT_MAXI").i().d(30)]),
    ]
}

/// Choice of the normals of a master/slave pairing.
fn normals() -> Vec<Entry> {
    kws![
        simp("NORMALE").txt().d("MAIT").one_of(&["MAIT", "MAIT_ESCL", "ESCL"]),
        simp("VECT_MAIT").txt().d("AUTO").one_of(&["AUTO", "FIXE", "VECT_Y"]),
        bloc(eq("VECT_MAIT", "FIXE"), kws![simp("MAIT_FIXE").r().o().min(3).max(3)]),
        bloc(eq("VECT_MAIT", "VECT_Y"), kws![simp("MAIT_VECT_Y").r().o().min(3).max(3)]),
        simp("VECT_ESCL").txt().d("AUTO").one_of(&["AUTO", "FIXE", "VECT_Y"]),
        bloc(eq("VECT_ESCL", "FIXE"), kws![simp("ESCL_FIXE").r().o().min(3).max(3)]),
        bloc(eq("VECT_ESCL", "VECT_Y"), kws![simp("ESCL_VECT_Y").r().o().min(3).max(3)]),
        simp("TYPE_PROJECTION").txt().d("ORTHOGONALE").one_of(&["ORTHOGONALE", "FIXE"]),
        bloc(eq("TYPE_PROJECTION", "FIXE"), kws![simp("DIRE_APPA").r().min(3).max(3)]),
    ]
}

/// Integration scheme of the contact terms, with the order of each scheme.
fn integration(default: &'static str, schemes: &'static [&'static str], gauss_order: i64) -> Vec<Entry> {
    kws![
        simp("INTEGRATION").txt().d(default).one_of(schemes),
        bloc(eq("INTEGRATION", "GAUSS"), kws![simp("ORDRE_INT").i().d(gauss_order).val_min(1.0).val_max(6.0)]),
        bloc(eq("INTEGRATION", "SIMPSON"), kws![simp("ORDRE_INT").i().d(1).val_min(1.0).val_max(4.0)]),
        bloc(eq("INTEGRATION", "NCOTES"), kws![simp("ORDRE_INT").i().d(3).val_min(3.0).val_max(8.0)]),
    ]
}

/// A ZONE of the discrete formulation.
fn zone_discrete(friction: bool) -> Fact {
    let mut e = kws![
        simp("APPARIEMENT").txt().d("MAIT_ESCL").one_of(&["NODAL", "MAIT_ESCL"]),
        simp("GROUP_MA_MAIT").txt(),
        simp("GROUP_MA_ESCL").txt(),
    ];
    e.extend(normals());
    e.extend(kws![
        simp("DIST_MAIT").co(FUNC),
        simp("DIST_ESCL").co(FUNC),
        simp("DIST_APPA").r().d(-1.0),
        simp("TOLE_PROJ_EXT").r().d(0.50),
        names("SANS_GROUP_NO"),
        names("SANS_GROUP_MA"),
        oui_non("RESOLUTION", "OUI"),
        bloc(eq("RESOLUTION", "NON"), kws![simp("TOLE_INTERP").r().d(0.0).val_min(0.0)]),
        simp("ALGO_CONT").txt().d("CONTRAINTE").one_of(&["CONTRAINTE", "PENALISATION", "GCP"]),
        bloc(
            eq("ALGO_CONT", "CONTRAINTE"),
            kws![oui_non("GLISSIERE", "NON"), bloc(eq("GLISSIERE", "OUI"), kws![simp("ALARME_JEU").r().d(0.0)]),]
        ),
        bloc(eq("ALGO_CONT", "PENALISATION"), kws![simp("E_N").r().o()]),
    ]);
    if friction {
        e.extend(kws![
            simp("COULOMB").r().o(),
            simp("COEF_MATR_FROT").r().d(0.0),
            simp("ALGO_FROT").txt().d("PENALISATION").one_of(&["PENALISATION"]),
            simp("E_T").r().o(),
        ]);
    }
    fact("ZONE", e).o().many()
}

/// Penalty/adaptation parameters of the continuous formulation with friction.
fn continue_friction_algos() -> Vec<Entry> {
    let adaptation = || simp("ADAPTATION").txt().d("CYCLAGE").one_of(&["ADAPT_COEF", "CYCLAGE", "TOUT", "NON"]);
    let adapt = || is_in("ADAPTATION", &["ADAPT_COEF", "TOUT"]);
    let no_adapt = || is_in("ADAPTATION", &["CYCLAGE", "NON"]);
    kws![
        simp("ALGO_FROT").txt().d("STANDARD").one_of(&["STANDARD", "PENALISATION"]),
        bloc(
            and(vec![eq("ALGO_CONT", "PENALISATION"), eq("ALGO_FROT", "STANDARD")]),
            kws![
                adaptation(),
                simp("COEF_FROT").r().d(100.0),
                bloc(no_adapt(), kws![simp("COEF_PENA_CONT").r().o()]),
                bloc(adapt(), kws![simp("PENE_MAXI").r(), simp("COEF_PENA_CONT").r().d(100.0)]),
            ]
        ),
        bloc(
            and(vec![eq("ALGO_CONT", "STANDARD"), eq("ALGO_FROT", "STANDARD")]),
            kws![adaptation(), simp("COEF_CONT").r().d(100.0), simp("COEF_FROT").r().d(100.0)]
        ),
        bloc(
            and(vec![eq("ALGO_CONT", "PENALISATION"), eq("ALGO_FROT", "PENALISATION")]),
            kws![
                adaptation(),
                bloc(no_adapt(), kws![simp("COEF_PENA_CONT").r().o(), simp("COEF_PENA_FROT").r().o()]),
                bloc(
                    adapt(),
                    kws![
                        simp("PENE_MAXI").r(),
                        simp("COEF_PENA_CONT").r().d(100.0),
                        simp("GLIS_MAXI").r(),
                        simp("COEF_PENA_FROT").r().d(100.0e5),
                    ]
                ),
            ]
        ),
        bloc(
            and(vec![eq("ALGO_CONT", "STANDARD"), eq("ALGO_FROT", "PENALISATION")]),
            kws![
                adaptation(),
                simp("COEF_CONT").r().d(100.0),
                bloc(no_adapt(), kws![simp("COEF_PENA_FROT").r().o()]),
                bloc(adapt(), kws![simp("GLIS_MAXI").r(), simp("COEF_PENA_FROT").r().d(100.0e5)]),
            ]
        ),
    ]
}

/// Contact parameters of the continuous formulation without friction.
fn continue_algos() -> Vec<Entry> {
    let adaptation = || simp("ADAPTATION").txt().d("CYCLAGE").one_of(&["ADAPT_COEF", "CYCLAGE", "TOUT", "NON"]);
    kws![
        bloc(eq("ALGO_CONT", "STANDARD"), kws![simp("COEF_CONT").r().d(100.0), adaptation()]),
        bloc(
            eq("ALGO_CONT", "PENALISATION"),
            kws![
                adaptation(),
                bloc(
                    is_in("ADAPTATION", &["ADAPT_COEF", "TOUT"]),
                    kws![simp("PENE_MAXI").r(), simp("COEF_PENA_CONT").r().d(100.0)]
                ),
                bloc(is_in("ADAPTATION", &["CYCLAGE", "NON"]), kws![simp("COEF_PENA_CONT").r().o()]),
            ]
        ),
    ]
}

/// A ZONE of the continuous formulation.
fn zone_continue(friction: bool) -> Fact {
    let mut e = kws![simp("ALGO_CONT").txt().d("STANDARD").one_of(&["STANDARD", "PENALISATION", "LAC"])];
    if friction {
        e.extend(continue_friction_algos());
    } else {
        e.extend(continue_algos());
    }
    let mut pair_std = kws![
        simp("APPARIEMENT").txt().d("MAIT_ESCL").one_of(&["MAIT_ESCL"]),
        simp("GROUP_MA_MAIT").txt(),
        simp("GROUP_MA_ESCL").txt(),
    ];
    pair_std.extend(normals());
    pair_std.extend(kws![
        simp("DIST_APPA").r().d(-1.0),
        simp("TOLE_PROJ_EXT").r().d(0.50),
        simp("DIST_MAIT").co(FUNC),
        simp("DIST_ESCL").co(FUNC),
        names("SANS_GROUP_NO"),
        names("SANS_GROUP_MA"),
    ]);
    pair_std.extend(integration("AUTO", &["AUTO", "GAUSS", "SIMPSON", "NCOTES"], 3));
    pair_std.extend(kws![
        oui_non("RESOLUTION", "OUI"),
        bloc(eq("RESOLUTION", "NON"), kws![simp("TOLE_INTERP").r().d(0.0)]),
        simp("CONTACT_INIT").txt().d("INTERPENETRE").one_of(&["OUI", "INTERPENETRE", "NON"]),
        oui_non("GLISSIERE", "NON"),
    ]);
    e.extend(kws![
        bloc(is_in("ALGO_CONT", &["STANDARD", "PENALISATION"]), pair_std),
        bloc(
            eq("ALGO_CONT", "LAC"),
            kws![
                simp("APPARIEMENT").txt().d("MORTAR").one_of(&["MORTAR"]),
                simp("TYPE_APPA").txt().d("RAPIDE").one_of(&["ROBUSTE", "RAPIDE"]),
                simp("RESI_APPA").r().d(1.0e-8),
                simp("TYPE_JACOBIEN").txt().d("INITIAL").one_of(&["INITIAL", "ACTUALISE"]),
                simp("INTEGRATION").txt().d("AUTO").one_of(&["AUTO"]),
                simp("GROUP_MA_MAIT").txt().o(),
                simp("GROUP_MA_ESCL").txt().o(),
                simp("CONTACT_INIT").txt().d("INTERPENETRE").one_of(&["OUI", "INTERPENETRE", "NON"]),
            ]
        ),
    ]);
    if friction {
        e.extend(kws![
            simp("COULOMB").r().o(),
            oui_non("GRAND_GLIS", "NON"),
            simp("SEUIL_INIT").r(),
            names("SANS_GROUP_NO_FR"),
            bloc(present("SANS_GROUP_NO_FR"), kws![simp("DIRE_EXCL_FROT").r().min(3).max(3)]),
        ]);
    }
    fact("ZONE", e).o().many()
}

/// A ZONE of the XFEM formulation.
fn zone_xfem(friction: bool) -> Fact {
    let mut e = kws![simp("FISS_MAIT").co(&[ConceptKind::FissXfem]).o(), simp("TOLE_PROJ_EXT").r().d(0.50)];
    e.extend(integration("GAUSS", &["NOEUD", "GAUSS", "SIMPSON", "NCOTES"], 6));
    let mut std = kws![simp("COEF_CONT").r().d(100.0)];
    if friction {
        std.push(Entry::from(simp("ADAPTATION").txt().d("CYCLAGE").one_of(&["ADAPT_COEF", "CYCLAGE", "TOUT", "NON"])));
    }
    e.extend(kws![
        simp("ALGO_LAGR").txt().d("AUTO").one_of(&["AUTO", "NON", "VERSION1", "VERSION2", "VERSION3"]),
        simp("ALGO_CONT").txt().d("STANDARD").one_of(&["STANDARD", "PENALISATION", "CZM"]),
        bloc(
            is_in("ALGO_CONT", &["STANDARD", "PENALISATION"]),
            kws![oui_non("CONTACT_INIT", "NON"), oui_non("GLISSIERE", "NON")]
        ),
        bloc(eq("ALGO_CONT", "STANDARD"), std),
        bloc(eq("ALGO_CONT", "PENALISATION"), kws![simp("COEF_PENA_CONT").r().o()]),
        bloc(
            eq("ALGO_CONT", "CZM"),
            kws![simp("RELATION").txt().o().one_of(&[
                "CZM_EXP_REG",
                "CZM_LIN_REG",
                "CZM_TAC_MIX",
                "CZM_OUV_MIX",
                "CZM_LIN_MIX",
            ])]
        ),
    ]);
    if friction {
        e.extend(kws![
            simp("COULOMB").r().o(),
            simp("SEUIL_INIT").r().d(0.0),
            simp("ALGO_FROT").txt().d("STANDARD").one_of(&["STANDARD", "PENALISATION"]),
            bloc(eq("ALGO_FROT", "STANDARD"), kws![simp("COEF_FROT").r().d(100.0)]),
            bloc(eq("ALGO_FROT", "PENALISATION"), kws![simp("COEF_PENA_FROT").r().o()]),
        ]);
    }
    fact("ZONE", e).o().many()
}

fn defi_contact() -> Command {
    let discrete = || eq("FORMULATION", "DISCRETE");
    let continuous = || eq("FORMULATION", "CONTINUE");
    let xfem = || eq("FORMULATION", "XFEM");
    let coulomb = || eq("FROTTEMENT", "COULOMB");
    let sans = || eq("FROTTEMENT", "SANS");

    let mut disc_geom = kws![simp("ALGO_RESO_GEOM").txt().d("POINT_FIXE").one_of(&["POINT_FIXE"])];
    disc_geom.extend(reac_geom("AUTOMATIQUE", 0.01));
    let cont_geom_pf = reac_geom("AUTOMATIQUE", 0.01);
    let mut xfem_geom = kws![simp("ALGO_RESO_GEOM").txt().d("POINT_FIXE").one_of(&["POINT_FIXE"])];
    xfem_geom.extend(reac_geom("SANS", 0.0001));

    Command::new("DEFI_CONTACT", "Define contact zones and unilateral conditions, with or without friction.")
        .produces(ConceptKind::CharContact)
        .kw(kws![
            simp("MODELE").co(&[ConceptKind::Modele]).o(),
            simp("INFO").i().one_of_i(&[1, 2]),
            simp("FORMULATION").txt().d("DISCRETE").one_of(&["DISCRETE", "CONTINUE", "XFEM", "LIAISON_UNIL"]),
            simp("FROTTEMENT").txt().d("SANS").one_of(&["COULOMB", "SANS"]),
            // General parameters (not depending on the zone).
            bloc(
                or(vec![continuous(), discrete()]),
                kws![oui_non("STOP_INTERP", "NON"), oui_non("LISSAGE", "NON"), oui_non("VERI_NORM", "OUI")]
            ),
            bloc(discrete(), disc_geom),
            bloc(
                continuous(),
                kws![
                    simp("ALGO_RESO_GEOM").txt().d("POINT_FIXE").one_of(&["POINT_FIXE", "NEWTON"]),
                    simp("CONT_STAT_ELAS").i().d(0).val_min(0.0),
                    bloc(eq("ALGO_RESO_GEOM", "NEWTON"), kws![simp("RESI_GEOM").r().d(0.000001)]),
                    bloc(eq("ALGO_RESO_GEOM", "POINT_FIXE"), cont_geom_pf),
                ]
            ),
            bloc(xfem(), xfem_geom),
            bloc(discrete(), kws![simp("ITER_CONT_MULT").i().d(4)]),
            bloc(
                continuous(),
                kws![
                    simp("ALGO_RESO_CONT").txt().d("NEWTON").one_of(&["POINT_FIXE", "NEWTON"]),
                    simp("RESI_CONT").r().d(-1.0),
                    bloc(eq("ALGO_RESO_CONT", "POINT_FIXE"), iter_cont_type()),
                ]
            ),
            bloc(xfem(), iter_cont_type()),
            bloc(
                and(vec![coulomb(), continuous()]),
                kws![
                    simp("ALGO_RESO_FROT").txt().d("NEWTON").one_of(&["POINT_FIXE", "NEWTON"]),
                    bloc(
                        eq("ALGO_RESO_FROT", "POINT_FIXE"),
                        kws![simp("ITER_FROT_MAXI").i().d(10), simp("RESI_FROT").r().d(0.0001)]
                    ),
                    bloc(eq("ALGO_RESO_FROT", "NEWTON"), kws![simp("RESI_FROT").r().d(0.0001)]),
                ]
            ),
            bloc(and(vec![coulomb(), xfem()]), kws![simp("ITER_FROT_MAXI").i().d(10), simp("RESI_FROT").r().d(0.0001)]),
            bloc(xfem(), kws![simp("ELIM_ARETE").txt().d("DUAL").one_of(&["DUAL", "ELIM"])]),
            bloc(
                discrete(),
                kws![
                    oui_non("STOP_SINGULIER", "OUI"),
                    simp("NB_RESOL").i().d(10),
                    simp("RESI_ABSO").r(),
                    simp("ITER_GCP_MAXI").i().d(0),
                    simp("RECH_LINEAIRE").txt().d("ADMISSIBLE").one_of(&["ADMISSIBLE", "NON_ADMISSIBLE"]),
                    simp("PRE_COND").txt().d("SANS").one_of(&["DIRICHLET", "SANS"]),
                    bloc(
                        eq("PRE_COND", "DIRICHLET"),
                        kws![simp("COEF_RESI").r().d(-1.0), simp("ITER_PRE_MAXI").i().d(0)]
                    ),
                ]
            ),
            // Zones.
            bloc(
                eq("FORMULATION", "LIAISON_UNIL"),
                kws![fact(
                    "ZONE",
                    kws![
                        names("GROUP_MA"),
                        names("GROUP_NO"),
                        simp("NOM_CMP").txt().o().many(),
                        simp("COEF_IMPO").co(FUNC).o(),
                        simp("COEF_MULT").co(FUNC).o().many(),
                        names("SANS_GROUP_NO"),
                        simp("ALGO_CONT").txt().d("CONTRAINTE").one_of(&["CONTRAINTE", "PENALISATION"]),
                        bloc(eq("ALGO_CONT", "PENALISATION"), kws![simp("COEF_PENA").r().o()]),
                    ]
                )
                .o()
                .many()
                .rules(vec![un_parmi(&["GROUP_MA", "GROUP_NO"])])]
            ),
            bloc(and(vec![discrete(), coulomb()]), kws![zone_discrete(true)]),
            bloc(and(vec![discrete(), sans()]), kws![zone_discrete(false)]),
            bloc(and(vec![continuous(), coulomb()]), kws![zone_continue(true)]),
            bloc(and(vec![continuous(), sans()]), kws![zone_continue(false)]),
            bloc(and(vec![xfem(), coulomb()]), kws![zone_xfem(true)]),
            bloc(and(vec![xfem(), sans()]), kws![zone_xfem(false)]),
        ])
}

/// The kind of kinematic load AFFE_CHAR_CINE(_F) makes: mechanical (MECA_IMPO, EVOL_IMPO of a mechanical
/// result) or thermal (THER_IMPO, EVOL_IMPO of an EVOL_THER).
fn char_cine_kind(a: &Args) -> crate::diag::Result<ConceptKind> {
    let thermal = a.has("THER_IMPO") || a.concept("EVOL_IMPO").is_some_and(|c| c.kind() == ConceptKind::EvolTher);
    Ok(if thermal { ConceptKind::CharCineTher } else { ConceptKind::CharCineMeca })
}

/// AFFE_CHAR_CINE and AFFE_CHAR_CINE_F: prescribed values of unknowns, eliminated from the system.
fn affe_char_cine(v: V) -> Command {
    let sel = || kws![tout(), names("GROUP_MA"), names("MAILLE"), names("GROUP_NO"), names("NOEUD")];
    let at_least = || au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]);
    let comps = if v == V::Real { DDL_IMPO_R } else { DDL_IMPO_F };
    let mut meca = sel();
    meca.extend(vals(comps, v));
    let mut ther = sel();
    ther.extend(vals(&["TEMP", "TEMP_INF", "TEMP_SUP", "TEMP_MIL"], v));
    let mut acou = sel();
    acou.extend(vals(&["PRES"], v));

    let mut entries = kws![
        simp("MODELE").co(&[ConceptKind::Modele]).o(),
        fact("MECA_IMPO", meca).many().rules(vec![at_least(), au_moins_un(comps)]),
        fact("THER_IMPO", ther)
            .many()
            .rules(vec![at_least(), au_moins_un(&["TEMP", "TEMP_INF", "TEMP_SUP", "TEMP_MIL"])]),
        fact("ACOU_IMPO", acou).many().rules(vec![at_least()]),
        simp("INFO").i().d(1).one_of_i(&[1, 2]),
    ];
    let mut rules = vec![un_parmi(&["MECA_IMPO", "THER_IMPO", "ACOU_IMPO", "EVOL_IMPO"])];
    if v == V::Real {
        entries.extend(kws![
            simp("EVOL_IMPO").co(&[ConceptKind::EvolElas, ConceptKind::EvolNoli, ConceptKind::EvolTher]),
            bloc(present("EVOL_IMPO"), kws![simp("NOM_CMP").txt().many()]),
        ]);
    } else {
        rules = vec![un_parmi(&["MECA_IMPO", "THER_IMPO", "ACOU_IMPO"])];
    }
    let command = match v {
        V::Real => {
            Command::new("AFFE_CHAR_CINE", "Prescribe unknowns by elimination (kinematic loads), constant values.")
        }
        V::Func => Command::new("AFFE_CHAR_CINE_F", "Prescribe unknowns by elimination (kinematic loads), functions."),
    };
    command.produces_dyn(char_cine_kind).kw(entries).rules(rules)
}
