//! Pieces several command schemas share.

use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::diag::{Error, Result};
use crate::kws;

/// A function of one or more variables: tabulated, nappe or formula.
pub const FUNCS: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule];
/// Results of mechanical and thermal computations.
pub const RESULTS: &[ConceptKind] = &[ConceptKind::EvolElas, ConceptKind::EvolNoli, ConceptKind::EvolTher];
/// Results whose fields are read as they are (tested, printed, extracted): those of computations and those
/// CREA_RESU makes of fields (command variables, drying).
pub const STORED_RESULTS: &[ConceptKind] = &[
    ConceptKind::EvolElas,
    ConceptKind::EvolNoli,
    ConceptKind::EvolTher,
    ConceptKind::EvolVarc,
    ConceptKind::EvolSech,
];
pub const OUI_NON: &[&str] = &["OUI", "NON"];

/// `CRITERE` (default RELATIF) and the `PRECISION` that goes with it, used to
/// find an instant in a list.
pub fn crit_prec() -> Vec<Entry> {
    kws![
        simp("CRITERE").txt().d("RELATIF").one_of(&["RELATIF", "ABSOLU"]),
        bloc(eq("CRITERE", "RELATIF"), kws![simp("PRECISION").r().d(1.0e-6)]),
        bloc(eq("CRITERE", "ABSOLU"), kws![simp("PRECISION").r().o()]),
    ]
}

/// Concatenate two keyword lists.
pub fn with(mut v: Vec<Entry>, more: Vec<Entry>) -> Vec<Entry> {
    v.extend(more);
    v
}

/// A field concept of any location.
pub const CHAM_GD: &[ConceptKind] = &[ConceptKind::ChamNo, ConceptKind::ChamElem, ConceptKind::Carte];

/// The type of the result named by keyword `kw`.
pub fn concept_kind(a: &Args, kw: &str) -> Option<ConceptKind> {
    a.concept(kw).map(|c| c.kind())
}

pub fn missing(a: &Args, what: &str) -> Error {
    Error::catalog(format!("cannot tell the type of the result: {what} is missing")).at(a.span)
}

/// CALC_CHAMP, POST_CHAM_XFEM: the result has the type of RESULTAT.
pub fn type_of_resultat(a: &Args) -> Result<ConceptKind> {
    concept_kind(a, "RESULTAT").ok_or_else(|| missing(a, "RESULTAT"))
}
