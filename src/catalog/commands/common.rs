//! Pieces several command schemas share.

use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

/// A function of one or more variables: tabulated, nappe or formula.
pub const FUNCS: &[ConceptKind] = &[ConceptKind::Fonction, ConceptKind::Nappe, ConceptKind::Formule];
/// Results of mechanical computations.
pub const RESULTS: &[ConceptKind] = &[ConceptKind::EvolElas, ConceptKind::EvolNoli];
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
