//! The control commands. DEBUT, POURSUITE and FIN: their options only tune Code_Aster's own runtime
//! (test mode CODE, DEBUG output, the error mode ERREUR, IGNORE_ALARM, memory and PAR_LOT); none
//! changes what is computed, so they are taken as read. The run state they mark (a study started,
//! continued from the previous command file, ended) is handled by the runner. DETRUIRE unbinds the
//! names of concepts; DEFI_FICHIER associates, reserves and frees logical units; INFO_EXEC_ASTER
//! reports the time left, a free unit and the state of a unit as a table.

use crate::catalog::args::Args;
use crate::concepts::table::{Cell, ColType, Table};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::{Access, Ctx, UnitState};
use std::rc::Rc;

pub fn nothing(_ctx: &mut Ctx, args: &Args) -> Result<Option<ConceptData>> {
    args.read_all();
    Ok(None)
}

/// DETRUIRE: every name bound to the concepts given (NOM, or the older CONCEPT/NOM) is unbound, so
/// that a later use of the name is a NameError, as in Code_Aster. OBJET (a JEVEUX object by name)
/// has no counterpart here and stops the run by name.
pub fn detruire(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let mut concepts = a.concepts("NOM");
    for occ in a.facts("CONCEPT") {
        concepts.extend(occ.concepts("NOM"));
    }
    // OBJET: Code_Aster destroys the memory objects whose names hold CHAINE (at POSITION, from 1); a
    // concept's objects carry its name first, so here the concepts whose names hold it go.
    for occ in a.facts("OBJET") {
        let pos = occ.int("POSITION").and_then(|p| usize::try_from(p - 1).ok());
        for s in occ.texts("CHAINE") {
            let hit = |name: &str| match pos {
                Some(p) => name.get(p..).is_some_and(|t| t.starts_with(s.as_str())),
                None => name.contains(s.as_str()),
            };
            let globals = ctx.globals.borrow();
            for v in globals.values() {
                if let crate::interp::value::Value::Concept(c) = v {
                    if hit(&c.name()) && !concepts.iter().any(|k| Rc::ptr_eq(k, c)) {
                        concepts.push(c.clone());
                    }
                }
            }
        }
    }
    let info = a.int("INFO").unwrap_or(1);
    for c in concepts {
        let names = ctx.io.forget(&c);
        if info >= 2 {
            ctx.io.mess(&format!("DETRUIRE: {} ({}) unbound: {}\n", c.label(), c.kind(), names.join(", ")));
        }
    }
    Ok(None)
}

/// DEFI_FICHIER (`op0026` + `ulopen`/`ulaffe`): ASSOCIER ties a unit to a file of the run's
/// folder, opened NEW (emptied), APPEND or OLD (must exist); without UNITE it takes a free unit and
/// returns it. RESERVER reserves a unit for a file; LIBERER frees it.
pub fn defi_fichier(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let action = a.text("ACTION").unwrap_or("ASSOCIER");
    let unit = a.int("UNITE");
    let file = a.text("FICHIER");
    // TYPE (ASCII, BINARY, LIBRE) only decides how Fortran opens the file; every unit here is a
    // file the stages read or write whole, as text or through its path.
    let _ = a.text("TYPE");
    let _ = a.int("INFO");
    let kw = if unit.is_some() { "UNITE" } else { "FICHIER" };
    let u = match action {
        "LIBERER" => ctx.io.release(unit, file).map_err(|e| a.locate(e, kw))?,
        _ => {
            let access = match a.text("ACCES").unwrap_or("NEW") {
                "APPEND" => Access::Append,
                "OLD" => Access::Old,
                _ => Access::New,
            };
            ctx.io.associate(unit, file, access, action == "RESERVER").map_err(|e| a.locate(e, kw))?
        }
    };
    if unit.is_none() && action != "LIBERER" {
        ctx.int_result = Some(u);
    }
    Ok(None)
}

/// INFO_EXEC_ASTER (`op0035`): one row per item of LISTE_INFO, each with only its own column —
/// TEMPS_RESTANT (R, seconds left before the run's time limit; infinite without one), UNITE_LIBRE
/// (I, `ulnume`'s free unit) and ETAT_UNITE (K8 `OUVERT`, `RESERVE` or `FERME`, with the file's name
/// in NOMFIC1 for an open or reserved unit).
pub fn info_exec_aster(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let items = a.texts("LISTE_INFO");
    let n = items.len();
    let mut t = Table { title: a.text("TITRE").unwrap_or("").to_string(), columns: Vec::new() };
    let mut nomfic: Vec<Cell> = vec![Cell::Empty; n];
    for (k, item) in items.iter().enumerate() {
        let mut cells = vec![Cell::Empty; n];
        let ty = match item.as_str() {
            "TEMPS_RESTANT" => {
                let left = crate::diag::time_left().map_or(f64::INFINITY, |d| d.as_secs_f64());
                cells[k] = Cell::Real(left);
                ColType::R
            }
            "UNITE_LIBRE" => {
                let u = ctx.io.free_unit().ok_or_else(|| a.err("LISTE_INFO", "no free unit from 99 down to 70"))?;
                cells[k] = Cell::Int(u);
                ColType::I
            }
            _ => {
                let (state, file) = ctx.io.unit_state(a.int("UNITE"), a.text("FICHIER"));
                let shown = match state {
                    UnitState::Open => "OUVERT",
                    UnitState::Reserved => "RESERVE",
                    UnitState::Closed => "FERME",
                };
                cells[k] = Cell::Text(shown.to_string());
                if let Some(f) = file {
                    nomfic[k] = Cell::Text(f.chars().take(80).collect());
                }
                ColType::K(8)
            }
        };
        t.add_column(item, ty, cells).map_err(|e| a.locate(e, "LISTE_INFO"))?;
    }
    if nomfic.iter().any(|c| !c.is_empty()) {
        t.add_column("NOMFIC1", ColType::K(80), nomfic).map_err(|e| a.locate(e, "LISTE_INFO"))?;
    }
    let _ = a.int("INFO");
    Ok(Some(ConceptData::Table(t)))
}
