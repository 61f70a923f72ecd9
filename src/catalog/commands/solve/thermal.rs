//! Heat: THER_LINEAIRE (linear conduction, steady or transient) and THER_NON_LINE (nonlinear conduction,
//! exchanges and sources, by Newton).

use super::{archivage, solveur};
use crate::catalog::commands::common::*;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

fn excit() -> Fact {
    fact(
        "EXCIT",
        kws![
            simp("CHARGE").co(&[ConceptKind::CharTher, ConceptKind::CharCineTher]).o(),
            simp("FONC_MULT").co(FUNCS),
            simp("TYPE_CHARGE").txt().d("FIXE_CSTE").one_of(&["FIXE_CSTE"]),
        ],
    )
    .o()
    .many()
}

/// INCREMENT: required by THER_LINEAIRE; THER_NON_LINE may omit it for a steady computation.
fn increment(required: bool) -> Fact {
    let f = fact(
        "INCREMENT",
        kws![
            simp("LIST_INST").co(&[ConceptKind::ListR8, ConceptKind::ListInst]).o(),
            simp("NUME_INST_INIT").i(),
            simp("INST_INIT").r(),
            simp("NUME_INST_FIN").i(),
            simp("INST_FIN").r(),
            simp("PRECISION").r().d(1.0e-6),
        ],
    )
    .rules(vec![exclus(&["NUME_INST_INIT", "INST_INIT"]), exclus(&["NUME_INST_FIN", "INST_FIN"])]);
    if required {
        f.o()
    } else {
        f
    }
}

/// ETAT_INIT of a transient computation (absent: `STAT='OUI'`, as Code_Aster's compatibility layer
/// fills it in). `STATIONNAIRE='OUI'` is the former spelling of `STAT='OUI'`.
fn etat_init() -> Fact {
    let mut e = kws![
        simp("STAT").txt().one_of(&["OUI"]),
        simp("STATIONNAIRE").txt().one_of(&["OUI"]),
        simp("EVOL_THER").co(&[ConceptKind::EvolTher]),
        simp("CHAM_NO").co(&[ConceptKind::ChamNo]),
        simp("VALE").r(),
    ];
    let mut evol = kws![simp("NUME_ORDRE").i(), simp("INST").r()];
    evol.push(Entry::Bloc(bloc(present("INST"), crit_prec())));
    e.push(Entry::Bloc(bloc(present("EVOL_THER"), evol).rules(vec![exclus(&["NUME_ORDRE", "INST"])])));
    fact("ETAT_INIT", e).rules(vec![un_parmi(&["STAT", "STATIONNAIRE", "EVOL_THER", "CHAM_NO", "VALE"])])
}

/// The θ-scheme; PARM_THETA is its former spelling.
fn schema_temps() -> Vec<Entry> {
    kws![
        fact(
            "SCHEMA_TEMPS",
            kws![
                simp("SCHEMA").txt().d("THETA").one_of(&["THETA"]),
                bloc(eq("SCHEMA", "THETA"), kws![simp("THETA").r().d(0.57).val_min(0.0).val_max(1.0)]),
            ]
        ),
        simp("PARM_THETA").r().val_min(0.0).val_max(1.0),
    ]
}

fn common(increment_required: bool) -> Vec<Entry> {
    kws![
        simp("RESULTAT").co(&[ConceptKind::EvolTher]),
        simp("MODELE").co(&[ConceptKind::Modele]).o(),
        simp("CHAM_MATER").co(&[ConceptKind::ChamMater]).o(),
        simp("CARA_ELEM").co(&[ConceptKind::CaraElem]),
        excit(),
        simp("TYPE_CALCUL").txt().d("TRAN").one_of(&["STAT", "TRAN"]),
        bloc(eq("TYPE_CALCUL", "TRAN"), with(kws![etat_init()], schema_temps())),
        increment(increment_required),
        archivage(),
        simp("TITRE").txt(),
        simp("INFO").i().one_of_i(&[1, 2]),
    ]
}

pub(super) fn ther_lineaire() -> Command {
    let mut e = common(true);
    e.push(Entry::from(solveur(true)));
    Command::new("THER_LINEAIRE", "Linear heat conduction, steady or transient (θ-scheme).")
        .produces(ConceptKind::EvolTher)
        .reuse()
        .kw(e)
        .rules(vec![exclus(&["SCHEMA_TEMPS", "PARM_THETA"])])
}

pub(super) fn ther_non_line() -> Command {
    let mut e = common(false);
    e.extend(kws![
        fact(
            "COMPORTEMENT",
            kws![
                simp("RELATION").txt().d("THER_NL").one_of(&["THER_NL", "THER_HYDR"]),
                simp("TOUT").txt().one_of(&["OUI"]),
                simp("GROUP_MA").txt().many(),
            ]
        )
        .many()
        .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
        simp("METHODE").txt().d("NEWTON").one_of(&["NEWTON", "MODELE_REDUIT", "NEWTON_KRYLOV", "RASPEN"]),
        bloc(
            is_in("METHODE", &["NEWTON", "NEWTON_KRYLOV", "RASPEN"]),
            kws![
                fact(
                    "NEWTON",
                    kws![
                        simp("REAC_ITER").i().d(0).val_min(0.0),
                        simp("REAC_INCR").i().d(1).val_min(0.0),
                        simp("PREDICTION").txt().d("TANGENTE").one_of(&["TANGENTE"]),
                        simp("MATRICE").txt().d("TANGENTE").one_of(&["TANGENTE"]),
                        // Former place of RECH_LINEAIRE's keywords.
                        simp("RESI_LINE_RELA").r().val_min(0.0),
                        simp("ITER_LINE_MAXI").i().val_min(0.0).val_max(999.0),
                    ]
                )
                .d(),
                fact(
                    "RECH_LINEAIRE",
                    kws![
                        simp("METHODE").txt().d("CORDE").one_of(&["CORDE"]),
                        simp("RESI_LINE_RELA").r().d(1.0e-1).val_min(0.0),
                        simp("ITER_LINE_MAXI").i().d(3).val_min(0.0).val_max(999.0),
                        simp("RHO_MIN").r().d(1.0e-2).val_min(0.0),
                        simp("RHO_MAX").r().d(1.0e1).val_min(0.0),
                        simp("RHO_EXCL").r().d(0.9e-2).val_min(0.0),
                    ]
                ),
            ]
        ),
        fact(
            "CONVERGENCE",
            kws![
                simp("RESI_GLOB_MAXI").r(),
                bloc(absent("RESI_GLOB_MAXI"), kws![simp("RESI_GLOB_RELA").r().d(1.0e-6)]),
                bloc(present("RESI_GLOB_MAXI"), kws![simp("RESI_GLOB_RELA").r()]),
                simp("ITER_GLOB_MAXI").i().d(10),
            ]
        )
        .d(),
        fact(
            "AFFICHAGE",
            kws![
                simp("INFO_RESIDU").txt().d("NON").one_of(OUI_NON),
                simp("INFO_TEMPS").txt().d("NON").one_of(OUI_NON),
                simp("UNITE").i(),
                simp("PAS").i().val_min(1.0),
            ]
        )
        .d(),
        solveur(false),
    ]);
    Command::new("THER_NON_LINE", "Nonlinear heat conduction (λ(T), enthalpy, nonlinear exchanges), by Newton.")
        .produces(ConceptKind::EvolTher)
        .reuse()
        .kw(e)
        .rules(vec![exclus(&["SCHEMA_TEMPS", "PARM_THETA"])])
}
