//! TEST_RESU: compare values extracted from results, fields and meshes with
//! computed (non-regression) and reference values.

use crate::catalog::commands::common::*;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

/// What varies between the factor keywords in the test-value keywords.
struct RefOpts {
    /// VALE_CALC / VALE_REFE take several values (summed by TYPE_TEST).
    many: bool,
    /// VALE_CALC_C / VALE_REFE_C exist.
    complex: bool,
    /// VALE_ABS exists.
    vale_abs: bool,
    /// TYPE_TEST exists.
    type_test: bool,
    /// RESU: CRITERE and TOLE_MACHINE may be given twice (first for the
    /// computed value, second for the reference) and have no default.
    multi_prec: bool,
}

fn card(s: Simp, many: bool) -> Simp {
    if many {
        s.many()
    } else {
        s
    }
}

/// The keywords shared by TEST_RESU's factor keywords (and, in Code_Aster,
/// TEST_TABLE and TEST_FONCTION) that give the expected values.
///
/// PRECISION, the tolerance on the reference value, exists only with
/// REFERENCE; it has no default here: the stage applies 1e-3.
fn test_reference(o: &RefOpts) -> (Vec<Entry>, Vec<Rule>) {
    let mut calc = vec!["VALE_CALC", "VALE_CALC_I"];
    let mut refe = vec!["VALE_REFE", "VALE_REFE_I"];
    let mut e = kws![card(simp("VALE_CALC").r(), o.many), card(simp("VALE_CALC_I").i(), o.many),];
    let mut r = kws![card(simp("VALE_REFE").r(), o.many), card(simp("VALE_REFE_I").i(), o.many)];
    if o.complex {
        e.extend(kws![card(simp("VALE_CALC_C").c(), o.many)]);
        r.extend(kws![card(simp("VALE_REFE_C").c(), o.many)]);
        calc.push("VALE_CALC_C");
        refe.push("VALE_REFE_C");
    }
    r.extend(kws![simp("PRECISION").r()]);
    e.extend(kws![
        // Code_Aster only offers ORDRE_GRANDEUR when |VALE_CALC| < 1e-16.
        simp("ORDRE_GRANDEUR").r(),
        simp("LEGENDE").txt(),
    ]);
    if o.vale_abs {
        e.extend(kws![simp("VALE_ABS").txt().d("NON").one_of(&["OUI", "NON"])]);
    }
    if o.type_test {
        e.extend(kws![simp("TYPE_TEST").txt().one_of(&["SOMM_ABS", "SOMM", "MAX", "MIN"])]);
    }
    if o.multi_prec {
        e.extend(kws![simp("TOLE_MACHINE").r().max(2), simp("CRITERE").txt().max(2).one_of(&["RELATIF", "ABSOLU"]),]);
    } else {
        e.extend(kws![
            simp("TOLE_MACHINE").r().d(1.0e-6),
            simp("CRITERE").txt().d("RELATIF").one_of(&["RELATIF", "ABSOLU"]),
        ]);
    }
    e.extend(kws![
        simp("REFERENCE").txt().one_of(&["ANALYTIQUE", "SOURCE_EXTERNE", "AUTRE_ASTER", "NON_DEFINI"]),
        bloc(present("REFERENCE"), r).rules(vec![un_parmi(&refe)]),
    ]);
    (e, vec![un_parmi(&calc)])
}

/// A factor keyword: its own keywords, the test-value keywords, its rules.
fn test_fact(name: &'static str, own: Vec<Entry>, o: RefOpts, mut rules: Vec<Rule>) -> Fact {
    let (mut e, r) = test_reference(&o);
    let mut all = own;
    all.append(&mut e);
    rules.extend(r);
    fact(name, all).many().rules(rules)
}

pub fn commands() -> Vec<Command> {
    let cham_no = test_fact(
        "CHAM_NO",
        kws![
            simp("CHAM_GD").co(&[ConceptKind::ChamNo]).o(),
            simp("NOEUD").txt(),
            simp("GROUP_NO").txt(),
            simp("NOM_CMP").txt(),
        ],
        RefOpts { many: true, complex: true, vale_abs: true, type_test: true, multi_prec: false },
        vec![
            exclus(&["NOEUD", "GROUP_NO"]),
            present_present("NOEUD", &["NOM_CMP"]),
            present_present("GROUP_NO", &["NOM_CMP"]),
        ],
    );
    let carte = test_fact(
        "CARTE",
        kws![
            simp("CHAM_GD").co(&[ConceptKind::Carte]).o(),
            simp("GROUP_MA").txt(),
            simp("MAILLE").txt(),
            simp("NOM_CMP").txt().o(),
        ],
        RefOpts { many: false, complex: true, vale_abs: false, type_test: false, multi_prec: false },
        vec![exclus(&["MAILLE", "GROUP_MA"])],
    );
    let cham_elem = test_fact(
        "CHAM_ELEM",
        kws![
            simp("CHAM_GD").co(&[ConceptKind::ChamElem]).o(),
            simp("GROUP_MA").txt(),
            simp("MAILLE").txt(),
            simp("POINT").i(),
            simp("SOUS_POINT").i(),
            simp("NOEUD").txt(),
            simp("GROUP_NO").txt(),
            simp("NOM_CMP").txt(),
        ],
        RefOpts { many: true, complex: true, vale_abs: true, type_test: true, multi_prec: false },
        vec![
            exclus(&["MAILLE", "GROUP_MA"]),
            exclus(&["NOEUD", "GROUP_NO", "POINT"]),
            present_present("NOEUD", &["NOM_CMP"]),
            present_present("GROUP_NO", &["NOM_CMP"]),
            present_present("POINT", &["NOM_CMP"]),
        ],
    );
    let resu = test_fact(
        "RESU",
        kws![
            simp("RESULTAT").co(STORED_RESULTS).o(),
            simp("NUME_ORDRE").i(),
            simp("INST").r(),
            simp("FREQ").r(),
            simp("NUME_MODE").i(),
            simp("NOEUD_CMP").txt().min(2).max(2),
            simp("NOM_CAS").txt(),
            simp("ANGLE").r(),
            simp("PARA").txt(),
            simp("NOM_CHAM").txt(),
            simp("NOM_CMP").txt(),
            simp("NOM_VARI").txt(),
            simp("GROUP_MA").txt(),
            simp("MAILLE").txt(),
            simp("NOEUD").txt().many(),
            simp("GROUP_NO").txt().many(),
            simp("POINT").i(),
            simp("SOUS_POINT").i(),
        ],
        RefOpts { many: true, complex: true, vale_abs: true, type_test: true, multi_prec: true },
        vec![
            un_parmi(&["NUME_ORDRE", "INST", "FREQ", "NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE"]),
            un_parmi(&["NOM_CHAM", "PARA"]),
            present_absent("PARA", &["GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD", "POINT", "NOM_CMP", "NOM_VARI"]),
            exclus(&["NOEUD", "GROUP_NO", "POINT"]),
            exclus(&["MAILLE", "GROUP_MA"]),
            exclus(&["NOM_CMP", "NOM_VARI"]),
        ],
    );
    let objet = test_fact(
        "OBJET",
        kws![simp("NOM").txt().o()],
        RefOpts { many: false, complex: false, vale_abs: true, type_test: false, multi_prec: false },
        vec![],
    );
    let maillage = test_fact(
        "MAILLAGE",
        kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            simp("CARA").txt().o().one_of(&[
                "NB_MAILLE",
                "NB_NOEUD",
                "NB_GROUP_MA",
                "NB_GROUP_NO",
                "NB_MA_GROUP_MA",
                "NB_NO_GROUP_NO",
            ]),
            simp("NOM_GROUP_MA").txt(),
            simp("NOM_GROUP_NO").txt(),
        ],
        RefOpts { many: false, complex: true, vale_abs: true, type_test: true, multi_prec: false },
        vec![],
    );
    vec![Command::new(
        "TEST_RESU",
        "Check values extracted from results, fields or meshes against computed and reference values.",
    )
    .kw(kws![cham_no, carte, cham_elem, resu, objet, maillage, simp("TEST_NAN").txt().one_of(&["OUI", "NON"]),])
    .rules(vec![au_moins_un(&["CHAM_NO", "CHAM_ELEM", "CARTE", "RESU", "OBJET", "TEST_NAN", "MAILLAGE"])])]
}
