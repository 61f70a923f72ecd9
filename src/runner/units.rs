//! The logical units DEFI_FICHIER associates with files of the run's folder, and DETRUIRE's
//! unbinding of names: the session's side of those control commands.
//!
//! A unit associated with `FICHIER='./REPE_OUT/x.med'` is the file of that path inside the run's
//! work folder (Code_Aster runs in its work folder too); `fort.N` names the file of unit N, the
//! .export's data file when it has one. Paths that leave the work folder (absolute, `..`) are
//! refused by name: a command file reaches no file beyond its run's units.

use super::export::Dir;
use super::session::{Assoc, Session};
use crate::concepts::ConceptRef;
use crate::diag::{Error, Result};
use crate::interp::Value;
use crate::stages::{Access, UnitState};
use std::path::{Component, Path, PathBuf};
use std::rc::Rc;

/// Units Code_Aster keeps for itself (message, result, error files): never handed out as free.
const SYSTEM_UNITS: [i64; 4] = [1, 6, 8, 9];

impl Session {
    /// The file of the work folder that `name` designates.
    fn work_path(&self, name: &str) -> Result<PathBuf> {
        let rel = Path::new(name);
        if rel.is_absolute() || rel.components().any(|c| matches!(c, Component::ParentDir)) {
            return Err(Error::unsupported(format!(
                "FICHIER='{name}': only files of the run's folder (relative paths without '..') can be associated"
            )));
        }
        if name.trim().is_empty() {
            return Err(Error::runtime("FICHIER is empty"));
        }
        let clean: PathBuf = rel.components().filter(|c| !matches!(c, Component::CurDir)).collect();
        // `fort.N` is unit N's file: the .export's data file if it has one.
        if let Some(n) = clean.to_str().and_then(|s| s.strip_prefix("fort.")).and_then(|n| n.parse::<i64>().ok()) {
            if let Some((p, d)) = self.units.get(&n) {
                if *d != Dir::Out && !self.written_units().contains(&n) {
                    return Ok(p.clone());
                }
            }
        }
        Ok(self.workdir.join(clean))
    }

    /// The unit a file is associated with.
    fn unit_of_file(&self, name: &str) -> Option<i64> {
        self.assoc.iter().find(|(_, a)| a.name == name).map(|(u, _)| *u)
    }

    pub(super) fn associate_unit(
        &mut self,
        unit: Option<i64>,
        file: Option<&str>,
        access: Access,
        reserve: bool,
    ) -> Result<i64> {
        let unit = match unit {
            Some(u) => u,
            None => match file.and_then(|f| self.unit_of_file(f)) {
                Some(u) => u,
                None => self.free_unit_number().ok_or_else(|| Error::runtime("no free unit from 99 down to 70"))?,
            },
        };
        if !(1..=99).contains(&unit) || SYSTEM_UNITS.contains(&unit) {
            return Err(Error::runtime(format!("unit {unit} cannot be associated (units 2 to 99, but 6, 8 and 9)")));
        }
        let name = match file {
            Some(f) => f.to_string(),
            None => format!("fort.{unit}"),
        };
        let path = self.work_path(&name)?;
        match access {
            Access::Old if !path.exists() => {
                return Err(Error::io(format!("unit {unit}: file '{name}' does not exist (ACCES='OLD')")))
            }
            Access::New if !reserve => {
                if let Some(parent) = path.parent() {
                    std::fs::create_dir_all(parent)
                        .map_err(|e| Error::io(format!("unit {unit}: cannot create {}: {e}", parent.display())))?;
                }
                std::fs::write(&path, b"")
                    .map_err(|e| Error::io(format!("unit {unit}: cannot create '{name}': {e}")))?;
            }
            _ => {
                if let Some(parent) = path.parent() {
                    let _ = std::fs::create_dir_all(parent);
                }
            }
        }
        self.assoc.insert(unit, Assoc { name, path, reserved: reserve });
        Ok(unit)
    }

    pub(super) fn release_unit(&mut self, unit: Option<i64>, file: Option<&str>) -> Result<i64> {
        let unit = match (unit, file) {
            (Some(u), _) => u,
            (None, Some(f)) => self
                .unit_of_file(f)
                .ok_or_else(|| Error::runtime(format!("file '{f}' is not associated with a unit")))?,
            (None, None) => return Err(Error::runtime("UNITE or FICHIER is required")),
        };
        // A unit of the .export, or one never opened, is simply closed: nothing to do.
        self.assoc.remove(&unit);
        Ok(unit)
    }

    /// The file behind an associated unit.
    pub(super) fn associated(&self, unit: i64) -> Option<&PathBuf> {
        self.assoc.get(&unit).filter(|a| !a.reserved).map(|a| &a.path)
    }

    pub(super) fn state_of(&self, unit: Option<i64>, file: Option<&str>) -> (UnitState, Option<String>) {
        let unit = match (unit, file) {
            (Some(u), _) => Some(u),
            (None, Some(f)) => self.unit_of_file(f),
            _ => None,
        };
        let Some(u) = unit else { return (UnitState::Closed, None) };
        if let Some(a) = self.assoc.get(&u) {
            let state = if a.reserved { UnitState::Reserved } else { UnitState::Open };
            return (state, Some(a.name.clone()));
        }
        if self.written_units().contains(&u) {
            return (UnitState::Open, Some(format!("fort.{u}")));
        }
        (UnitState::Closed, None)
    }

    /// `ulnume`: the largest unit from 99 down to 70 that no file uses.
    pub(super) fn free_unit_number(&self) -> Option<i64> {
        (70..=99).rev().find(|u| !self.assoc.contains_key(u) && !self.units.contains_key(u))
    }

    /// Unbind every global name bound to `concept`.
    pub(super) fn forget_concept(&mut self, concept: &ConceptRef) -> Vec<String> {
        let mut g = self.globals.borrow_mut();
        let mut names: Vec<String> = g
            .iter()
            .filter(|(_, v)| matches!(v, Value::Concept(c) if Rc::ptr_eq(c, concept)))
            .map(|(k, _)| k.clone())
            .collect();
        names.sort();
        for n in &names {
            g.remove(n);
        }
        names
    }
}
