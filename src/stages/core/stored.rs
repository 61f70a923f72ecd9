//! Results made of stored fields rather than computed (LIRE_RESU, CREA_RESU): the model without elements
//! such a result has when only a mesh is known, the loads of its EXCIT, and the kind of field a result's
//! field name stands for.

use crate::catalog::args::Args;
use crate::concepts::model::Model;
use crate::concepts::result::Field;
use crate::concepts::{Concept, ConceptData, ConceptKind, ConceptRef};
use crate::diag::Result;

/// A model without elements on a mesh: the model of a result made with a mesh only (LIRE_RESU MAILLAGE,
/// CREA_RESU of fields without MODELE).
pub fn bare_model(mesh_concept: &ConceptRef) -> Result<ConceptRef> {
    let mesh = mesh_concept.mesh()?;
    let model = Model {
        mesh: mesh.clone(),
        mesh_concept: mesh_concept.clone(),
        elements: vec![None; mesh.ncells()],
        xfem: None,
    };
    Ok(Concept::new(ConceptKind::Modele, ConceptData::Model(model)))
}

/// The loads of EXCIT a stored result keeps (without multiplier: FONC_MULT and any TYPE_CHARGE but
/// FIXE_CSTE would be lost, so they stop by name). Nothing when the command's schema has no EXCIT.
pub fn excit_loads(a: &Args) -> Result<Vec<ConceptRef>> {
    if !a.declares("EXCIT") {
        return Ok(Vec::new());
    }
    let mut loads = Vec::new();
    for occ in a.facts("EXCIT") {
        occ.refuse(&["FONC_MULT"])?;
        // EVOL_THER's occurrences have no TYPE_CHARGE.
        let kind = occ.declares("TYPE_CHARGE").then(|| occ.text("TYPE_CHARGE")).flatten();
        if let Some(t) = kind.filter(|t| *t != "FIXE_CSTE") {
            return Err(occ.err("TYPE_CHARGE", format!("TYPE_CHARGE='{t}' is not supported yet (FIXE_CSTE is)")));
        }
        loads.push(occ.req_concept("CHARGE")?);
    }
    Ok(loads)
}

/// Where the values of a result's field live, by its name (NOM_CHAM): `_ELGA`, `_ELNO`, `_ELEM` fields
/// on cells, every other one (DEPL, TEMP, SIEF_NOEU, ...) on nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    Node,
    Elno,
    Elga,
    Elem,
}

impl Location {
    pub fn of_symbol(sym: &str) -> Location {
        if sym.ends_with("_ELGA") {
            Location::Elga
        } else if sym.ends_with("_ELNO") {
            Location::Elno
        } else if sym.ends_with("_ELEM") {
            Location::Elem
        } else {
            Location::Node
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Location::Node => "node (NOEU)",
            Location::Elno => "ELNO",
            Location::Elga => "ELGA",
            Location::Elem => "ELEM",
        }
    }

    /// Does `f` live here?
    pub fn holds(self, f: &Field) -> bool {
        matches!(
            (self, f),
            (Location::Node, Field::Node { .. })
                | (Location::Elno, Field::Elno { .. })
                | (Location::Elga, Field::Elga { .. })
                | (Location::Elem, Field::Elem { .. })
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_field_name_tells_where_its_values_live() {
        assert_eq!(Location::of_symbol("TEMP"), Location::Node);
        assert_eq!(Location::of_symbol("SIEF_ELGA"), Location::Elga);
        assert_eq!(Location::of_symbol("SIGM_ELNO"), Location::Elno);
        assert_eq!(Location::of_symbol("ERME_ELEM"), Location::Elem);
        assert_eq!(Location::of_symbol("SIEF_NOEU"), Location::Node);
        let node = Field::Node { components: vec!["TEMP".into()], values: vec![1.0] };
        let elga = Field::Elga { components: vec!["SIXX".into()], cells: vec![None] };
        assert!(Location::Node.holds(&node) && !Location::Node.holds(&elga));
        assert!(Location::Elga.holds(&elga) && !Location::Elem.holds(&elga));
    }
}
