//! Thermal loads and boundary conditions: AFFE_CHAR_THER (real values) and AFFE_CHAR_THER_F (functions).

use super::{names, tout, val, vals, V};
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

/// The temperature components of thermal models (shells have TEMP_MIL, TEMP_INF, TEMP_SUP; X-FEM H1).
const DDL_THER: &[&str] = &["TEMP", "TEMP_MIL", "TEMP_INF", "TEMP_SUP", "H1"];

/// A factor keyword selecting cells with TOUT or GROUP_MA (exactly one).
fn on_cells(name: &'static str, mut e: Vec<Entry>, mut rules: Vec<Rule>) -> Fact {
    let mut all = kws![tout(), names("GROUP_MA")];
    all.append(&mut e);
    rules.insert(0, un_parmi(&["TOUT", "GROUP_MA"]));
    fact(name, all).many().rules(rules)
}

fn entries(v: V) -> Vec<Entry> {
    let mut e = kws![
        simp("MODELE").co(&[ConceptKind::Modele]).o(),
        simp("DOUBLE_LAGRANGE").txt().d("OUI").one_of(&["OUI", "NON"]),
        fact(
            "TEMP_IMPO",
            kws![
                tout(),
                names("GROUP_NO"),
                names("GROUP_MA"),
                names("SANS_GROUP_MA"),
                names("SANS_GROUP_NO"),
                val("TEMP", v),
                val("TEMP_MIL", v),
                val("TEMP_INF", v),
                val("TEMP_SUP", v),
            ]
        )
        .many()
        .rules(vec![
            au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO"]),
            au_moins_un(&["TEMP", "TEMP_MIL", "TEMP_SUP", "TEMP_INF"])
        ]),
        fact(
            "SECH_IMPO",
            kws![
                tout(),
                names("GROUP_NO"),
                names("GROUP_MA"),
                names("SANS_GROUP_MA"),
                names("SANS_GROUP_NO"),
                if v == V::Real { val("SECH", v).o() } else { val("SECH", v) },
            ]
        )
        .many()
        .rules(vec![au_moins_un(&["TOUT", "GROUP_MA", "GROUP_NO"])]),
        on_cells("RAYONNEMENT", kws![val("SIGMA", v).o(), val("EPSILON", v).o(), val("TEMP_EXT", v).o()], vec![]),
        on_cells(
            "ECHANGE",
            vals(&["COEF_H", "TEMP_EXT", "COEF_H_INF", "TEMP_EXT_INF", "COEF_H_SUP", "TEMP_EXT_SUP"], v),
            vec![
                au_moins_un(&["COEF_H", "COEF_H_INF", "COEF_H_SUP"]),
                ensemble(&["COEF_H", "TEMP_EXT"]),
                ensemble(&["COEF_H_INF", "TEMP_EXT_INF"]),
                ensemble(&["COEF_H_SUP", "TEMP_EXT_SUP"]),
            ]
        ),
        on_cells(
            "PRE_GRAD_TEMP",
            vals(&["FLUX_X", "FLUX_Y", "FLUX_Z"], v),
            vec![au_moins_un(&["FLUX_X", "FLUX_Y", "FLUX_Z"])]
        ),
        fact(
            "ECHANGE_PAROI",
            kws![
                names("GROUP_MA_1"),
                names("GROUP_MA_2"),
                simp("FISSURE").co(&[ConceptKind::FissXfem]).many(),
                bloc(absent("FISSURE"), kws![val("COEF_H", v).o(), simp("TRAN").r().min(2).max(3)]),
                bloc(present("FISSURE"), kws![val("COEF_H", v), simp("TEMP_CONTINUE").txt().one_of(&["OUI"])])
                    .rules(vec![un_parmi(&["COEF_H", "TEMP_CONTINUE"])]),
            ]
        )
        .many()
        .rules(vec![un_parmi(&["GROUP_MA_1", "FISSURE"]), un_parmi(&["GROUP_MA_2", "FISSURE"])]),
        fact(
            "LIAISON_DDL",
            kws![
                names("GROUP_NO"),
                simp("DDL").txt().many().one_of(DDL_THER),
                simp("COEF_MULT").r().o().many(),
                val("COEF_IMPO", v).o(),
            ]
        )
        .many(),
        fact(
            "LIAISON_GROUP",
            kws![
                names("GROUP_MA_1"),
                names("GROUP_NO_1"),
                names("GROUP_MA_2"),
                names("GROUP_NO_2"),
                names("SANS_GROUP_NO"),
                simp("DDL_1").txt().many().d("TEMP").one_of(DDL_THER),
                simp("COEF_MULT_1").r().o().many(),
                simp("DDL_2").txt().many().d("TEMP").one_of(DDL_THER),
                simp("COEF_MULT_2").r().o().many(),
                val("COEF_IMPO", v).o(),
                simp("TRAN").r().many(),
                simp("ANGL_NAUT").r().many(),
                simp("CENTRE").r().many(),
            ]
        )
        .many()
        .rules(vec![
            un_parmi(&["GROUP_MA_1", "GROUP_NO_1"]),
            un_parmi(&["GROUP_MA_2", "GROUP_NO_2"]),
            exclus(&["GROUP_MA_1", "GROUP_NO_2"]),
            exclus(&["GROUP_NO_1", "GROUP_MA_2"]),
        ]),
        fact(
            "LIAISON_UNIF",
            kws![names("GROUP_NO"), names("GROUP_MA"), simp("DDL").txt().many().d("TEMP").one_of(DDL_THER)]
        )
        .many()
        .rules(vec![un_parmi(&["GROUP_NO", "GROUP_MA"])]),
        fact("CONVECTION", kws![simp("VITESSE").co(&[ConceptKind::ChamNo]).o()]),
        simp("INFO").i().d(1).one_of_i(&[1, 2]),
    ];
    match v {
        V::Real => e.extend(kws![
            simp("EVOL_CHAR").co(&[ConceptKind::EvolTher]),
            on_cells(
                "FLUX_REP",
                kws![
                    val("FLUN", v),
                    val("FLUN_INF", v),
                    val("FLUN_SUP", v),
                    simp("CARA_TORSION").co(&[ConceptKind::Table]),
                ],
                vec![
                    present_present("CARA_TORSION", &["GROUP_MA"]),
                    au_moins_un(&["FLUN", "FLUN_INF", "FLUN_SUP", "CARA_TORSION"]),
                ]
            ),
            fact(
                "SOURCE",
                kws![
                    tout(),
                    names("GROUP_MA"),
                    val("SOUR", v),
                    simp("SOUR_CALCULEE").co(&[ConceptKind::ChamElem, ConceptKind::ChamNo]),
                ]
            )
            .many()
            .rules(vec![
                un_parmi(&["SOUR", "SOUR_CALCULEE"]),
                present_absent("TOUT", &["GROUP_MA"]),
                present_absent("SOUR_CALCULEE", &["TOUT", "GROUP_MA"]),
            ]),
            fact(
                "LIAISON_MAIL",
                kws![
                    names("GROUP_MA_MAIT"),
                    names("GROUP_MA_ESCL"),
                    names("GROUP_NO_ESCL"),
                    simp("TRAN").r().many(),
                    simp("ANGL_NAUT").r().many(),
                    simp("CENTRE").r().many(),
                    simp("ELIM_MULT").txt().d("OUI").one_of(&["OUI", "NON"]),
                    simp("DISTANCE_MAX").r(),
                    simp("DISTANCE_ALARME").r(),
                ]
            )
            .many()
            .rules(vec![au_moins_un(&["GROUP_MA_ESCL", "GROUP_NO_ESCL"])]),
            fact("LIAISON_CHAMNO", kws![simp("CHAM_NO").co(&[ConceptKind::ChamNo]).o(), simp("COEF_IMPO").r().o()]),
        ]),
        V::Func => e.extend(kws![
            on_cells(
                "FLUX_REP",
                vals(&["FLUN", "FLUN_INF", "FLUN_SUP", "FLUX_X", "FLUX_Y", "FLUX_Z"], v),
                vec![au_moins_un(&["FLUN", "FLUN_INF", "FLUN_SUP", "FLUX_X", "FLUX_Y", "FLUX_Z"])]
            ),
            on_cells("FLUX_NL", kws![simp("FLUN").co(&[ConceptKind::Fonction]).o()], vec![]),
            on_cells("SOURCE", kws![val("SOUR", v).o()], vec![]),
            on_cells("SOUR_NL", kws![val("SOUR", v).o()], vec![]),
        ]),
    }
    e
}

const REAL_LOADS: &[&str] = &[
    "EVOL_CHAR",
    "TEMP_IMPO",
    "SECH_IMPO",
    "SOURCE",
    "FLUX_REP",
    "ECHANGE",
    "ECHANGE_PAROI",
    "PRE_GRAD_TEMP",
    "LIAISON_DDL",
    "LIAISON_GROUP",
    "LIAISON_UNIF",
    "LIAISON_CHAMNO",
    "RAYONNEMENT",
    "LIAISON_MAIL",
    "CONVECTION",
];

const FUNC_LOADS: &[&str] = &[
    "TEMP_IMPO",
    "SECH_IMPO",
    "SOURCE",
    "SOUR_NL",
    "FLUX_REP",
    "FLUX_NL",
    "ECHANGE",
    "ECHANGE_PAROI",
    "LIAISON_DDL",
    "LIAISON_GROUP",
    "LIAISON_UNIF",
    "PRE_GRAD_TEMP",
    "RAYONNEMENT",
    "CONVECTION",
];

pub(super) fn affe_char_ther() -> Command {
    Command::new("AFFE_CHAR_THER", "Thermal loads and boundary conditions of constant value on a thermal model.")
        .produces(ConceptKind::CharTher)
        .kw(entries(V::Real))
        .rules(vec![au_moins_un(REAL_LOADS), exclus(&["TEMP_IMPO", "SECH_IMPO"])])
}

pub(super) fn affe_char_ther_f() -> Command {
    Command::new(
        "AFFE_CHAR_THER_F",
        "Thermal loads and boundary conditions given by functions (of space, time, temperature) on a thermal model.",
    )
    .produces(ConceptKind::CharTher)
    .kw(entries(V::Func))
    .rules(vec![au_moins_un(FUNC_LOADS), exclus(&["TEMP_IMPO", "SECH_IMPO"])])
}
