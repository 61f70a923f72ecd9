//! IMPR_RESU: results and meshes to MED (`med`, `med_fields`), as text (`text`, FORMAT='RESULTAT') and to GMSH
//! (`gmsh`); LIRE_RESU and LIRE_CHAMP from MED (`lire`);
//! the selection of steps and fields the formats share.

pub mod gmsh;
pub mod lire;
pub mod med;
pub mod med_fields;
pub mod text;

use crate::catalog::args::Args;
use crate::concepts::result::Step;
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::Result;
use crate::stages::Ctx;

pub fn impr_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    match a.text("FORMAT").unwrap_or("MED") {
        "MED" => med::impr_resu_med(ctx, a),
        "RESULTAT" => text::impr_resu_text(ctx, a),
        "GMSH" => gmsh::impr_resu_gmsh(ctx, a),
        format => Err(a.err(
            "FORMAT",
            format!("IMPR_RESU FORMAT='{format}' is not supported yet (only 'MED', 'RESULTAT' and 'GMSH')"),
        )),
    }
}

/// The name a concept is printed under (its variable name).
pub fn concept_name(c: &ConceptRef, fallback: &str) -> String {
    let n = c.name();
    if n.is_empty() {
        fallback.to_string()
    } else {
        n
    }
}

pub use crate::stages::select::{list_of, selected_steps};

/// The fields an occurrence prints: NOM_CHAM (then `true`), none under
/// TOUT_CHAM='NON', else every field of the selected steps, sorted.
pub fn selected_fields(steps: &[&Step], occ: &Args) -> (bool, Vec<String>) {
    if occ.has("NOM_CHAM") {
        return (true, occ.texts("NOM_CHAM"));
    }
    if occ.text("TOUT_CHAM") == Some("NON") {
        return (false, Vec::new());
    }
    let all: std::collections::BTreeSet<&String> = steps.iter().flat_map(|s| s.fields.keys()).collect();
    (false, all.into_iter().cloned().collect())
}
