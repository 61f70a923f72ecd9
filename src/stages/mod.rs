//! Stages: what each command does once its keywords are validated.
//!
//! A stage receives validated [`Args`] and a [`Ctx`] through which it reads
//! and writes logical units, writes to the message file and records check
//! verdicts. Stages never see the AST nor the file system layout.

// The shared floor: entity selection and the solving core. Command families may use them, never each other.
pub mod core;
pub mod select;

// The command families: one file or folder per family, named as its schema file in `catalog/commands/`.
pub mod control;
pub mod fields;
pub mod functions;
pub mod loads;
pub mod material;
pub mod mesh;
pub mod model;
pub mod post;
pub mod print;
pub mod solve;
pub mod tables;
pub mod tests;
pub mod xfem;

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::{Error, Result};
use crate::interp::Scope;

/// One printed check line, for the run summary and the conformance table.
#[derive(Debug, Clone)]
pub struct CheckRecord {
    pub command: String,
    /// 1-based line of the command in the command file.
    pub line: usize,
    /// NON_REGRESSION, ANALYTIQUE, ...
    pub reference: String,
    pub legend: String,
    /// None for a skipped check.
    pub ok: Option<bool>,
}

/// What a stage may do beyond computing its result.
pub trait StageIo {
    /// Append to the message file (and the console).
    fn mess(&mut self, text: &str);
    /// Append to the result file (unit 8); also shown in the message file.
    fn resu(&mut self, text: &str);
    /// Read the whole content of a logical unit.
    fn read_unit(&mut self, unit: i64) -> Result<String>;
    /// Write to a logical unit: the first write of a run replaces, later ones append.
    fn write_unit(&mut self, unit: i64, text: &str) -> Result<()>;
    /// The file behind a unit, for binary formats (MED): an existing file to
    /// read, or (`write`) the file to create in the run's work folder, which the
    /// runner delivers at the end of a successful run.
    fn unit_path(&mut self, unit: i64, write: bool) -> Result<std::path::PathBuf>;
    /// Record a check verdict.
    fn record(&mut self, rec: CheckRecord);
    /// Is this a validation test case (NON_REGRESSION checks are then not enforced)?
    fn is_validation(&self) -> bool {
        false
    }
    /// DEFI_FICHIER: associate `unit` (or, without one, a free unit, which is returned) with a
    /// file of the run's folder (`file`, relative), or reserve it (`reserve`).
    fn associate(&mut self, unit: Option<i64>, file: Option<&str>, access: Access, reserve: bool) -> Result<i64> {
        let _ = (unit, file, access, reserve);
        Err(crate::diag::Error::unsupported("associating units with files is not supported here"))
    }
    /// DEFI_FICHIER ACTION='LIBERER': free a unit (or the unit of a file); returns the unit.
    fn release(&mut self, unit: Option<i64>, file: Option<&str>) -> Result<i64> {
        let _ = (unit, file);
        Err(crate::diag::Error::unsupported("freeing units is not supported here"))
    }
    /// The state of a unit (or of the unit of a file) and its file.
    fn unit_state(&mut self, unit: Option<i64>, file: Option<&str>) -> (UnitState, Option<String>) {
        let _ = (unit, file);
        (UnitState::Closed, None)
    }
    /// The largest free unit from 99 down to 70 (Code_Aster's `ulnume`), None if all are taken.
    fn free_unit(&mut self) -> Option<i64> {
        None
    }
    /// DETRUIRE: unbind every name bound to `concept`; returns the names.
    fn forget(&mut self, concept: &crate::concepts::ConceptRef) -> Vec<String> {
        let _ = concept;
        Vec::new()
    }
}

/// How DEFI_FICHIER opens a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Created, or emptied if it exists.
    New,
    /// Written after what it holds.
    Append,
    /// It must exist.
    Old,
}

/// The state of a logical unit, as INFO_EXEC_ASTER ETAT_UNITE reports it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitState {
    Open,
    Reserved,
    Closed,
}

/// The stage's context for one command.
pub struct Ctx<'a> {
    pub io: &'a mut dyn StageIo,
    /// The globals of the command file (FORMULE evaluates in them).
    pub globals: Scope,
    /// The command's name and its line, for records.
    pub command: &'static str,
    pub line: usize,
    /// The concept of `reuse=`, which the command's result replaces (a reentrant STAT_NON_LINE appends
    /// to the steps it holds).
    pub reuse: Option<crate::concepts::ConceptRef>,
    /// The integer a command of `Produces::Int` returns (DEFI_FICHIER's free unit).
    pub int_result: Option<i64>,
}

pub type StageFn = fn(&mut Ctx, &Args) -> Result<Option<ConceptData>>;

/// After a stage: every keyword the user wrote was used (read, or refused by name), and the stage looked
/// up only keywords its schema declares. A keyword the stage passed over stops the run by name rather
/// than being ignored; a lookup of an undeclared keyword is a defect of the stage (it would read
/// "absent" forever) and stops the run as an internal error.
pub fn all_keywords_used(command: &str, args: &Args) -> Result<()> {
    let undeclared = crate::catalog::args::take_undeclared_lookups();
    if !undeclared.is_empty() {
        return Err(Error::runtime(format!(
            "internal error: the stage of {command} looked up keyword(s) its schema does not declare: {}",
            undeclared.join(", ")
        )));
    }
    match args.unread().into_iter().next() {
        Some(u) => Err(Error::unsupported(format!(
            "{}: {command} does not use this keyword (given in {}): not supported yet",
            u.name, u.path
        ))
        .at(u.span)),
        None => Ok(()),
    }
}

/// The stage of a command, if it has one.
pub fn stage(name: &str) -> Option<StageFn> {
    Some(match name {
        "DEBUT" | "POURSUITE" | "FIN" => control::nothing,
        "DETRUIRE" => control::detruire,
        "DEFI_FICHIER" => control::defi_fichier,
        "INFO_EXEC_ASTER" => control::info_exec_aster,
        "DEFI_CONSTANTE" => functions::defi_constante,
        "DEFI_FONCTION" => functions::defi_fonction,
        "DEFI_NAPPE" => functions::defi_nappe,
        "DEFI_LIST_REEL" => functions::defi_list_reel,
        "DEFI_LIST_ENTI" => functions::defi_list_enti,
        "FORMULE" => functions::formule,
        "CALC_FONCTION" => functions::calc_fonction,
        "CALC_FONC_INTERP" => functions::calc_fonc_interp,
        "IMPR_FONCTION" => functions::impr_fonction,
        "LIRE_FONCTION" => functions::lire_fonction,
        "RECU_FONCTION" => functions::recu_fonction,
        "CREA_TABLE" => tables::crea_table,
        "LIRE_TABLE" => tables::lire_table,
        "CALC_TABLE" => tables::calc_table,
        "IMPR_TABLE" => tables::impr_table,
        "TEST_TABLE" => tests::test_table,
        "TEST_FONCTION" => tests::test_fonction,
        "LIRE_MAILLAGE" => mesh::lire_maillage,
        "DEFI_GROUP" => mesh::defi_group,
        "CREA_MAILLAGE" => mesh::crea_maillage::crea_maillage,
        "IMPR_RESU" => print::impr_resu,
        "LIRE_RESU" => print::lire::lire_resu,
        "LIRE_CHAMP" => print::lire::lire_champ,
        "AFFE_MODELE" => model::affe_modele,
        "DEFI_MATERIAU" => material::defi_materiau,
        "AFFE_MATERIAU" => material::affe_materiau,
        "AFFE_CARA_ELEM" => material::affe_cara_elem,
        "AFFE_CHAR_MECA" => loads::affe_char_meca,
        "AFFE_CHAR_MECA_F" => loads::affe_char_meca_f,
        "AFFE_CHAR_CINE" => loads::affe_char_cine,
        "AFFE_CHAR_CINE_F" => loads::affe_char_cine_f,
        "AFFE_CHAR_THER" => loads::thermal::affe_char_ther,
        "AFFE_CHAR_THER_F" => loads::thermal::affe_char_ther_f,
        "TEST_RESU" => tests::test_resu::test_resu,
        "MECA_STATIQUE" => solve::meca_statique,
        "CALC_CHAMP" => fields::calc_champ,
        "CREA_CHAMP" => fields::crea_champ,
        "CREA_RESU" => fields::crea_resu,
        "STAT_NON_LINE" => solve::stat_non_line,
        "THER_LINEAIRE" => solve::ther_lineaire,
        "THER_NON_LINE" => solve::ther_non_line,
        "DEFI_LIST_INST" => solve::defi_list_inst,
        "POST_RELEVE_T" => post::post_releve_t,
        "POST_ERREUR" => post::post_erreur,
        "POST_ELEM" => post::post_elem,
        "MACR_LIGN_COUPE" => post::macr_lign_coupe,
        "MODI_MAILLAGE" => mesh::orient::modi_maillage,
        "MODI_REPERE" => fields::modi_repere,
        "DEFI_FISS_XFEM" => xfem::defi_fiss_xfem,
        "MODI_MODELE_XFEM" => xfem::modi_modele_xfem,
        "DEFI_CONTACT" => loads::defi_contact,
        "POST_MAIL_XFEM" => xfem::post_mail_xfem,
        "POST_CHAM_XFEM" => xfem::post_cham_xfem,
        _ => return None,
    })
}

#[cfg(test)]
mod keyword_tests {
    use super::*;
    use crate::catalog::{catalogue, validate};
    use crate::interp::{KwArg, Value};
    use crate::syntax::ast::Span;

    fn call(cmd: &str, kw: Vec<(&str, Value)>) -> Args {
        let kwargs =
            kw.into_iter().map(|(n, v)| KwArg { name: n.to_string(), value: v, span: Span::default() }).collect();
        let a = validate::validate(catalogue().hand_written(cmd).unwrap(), kwargs, Span::default()).unwrap().args;
        a.reset_reads();
        take();
        a
    }

    fn take() {
        crate::catalog::args::take_undeclared_lookups();
    }

    #[test]
    fn a_keyword_the_stage_passes_over_stops_the_run_by_name() {
        let a =
            call("DEFI_LIST_REEL", vec![("VALE", Value::list(vec![Value::Float(1.0)])), ("TITRE", Value::str("t"))]);
        // A stage that reads VALE only.
        let _ = a.reals("VALE");
        let e = all_keywords_used("DEFI_LIST_REEL", &a).unwrap_err();
        assert!(e.msg.starts_with("TITRE: DEFI_LIST_REEL does not use this keyword"), "{}", e.msg);
        // Read (or refused), it passes; INFO never counts.
        let _ = a.text("TITRE");
        all_keywords_used("DEFI_LIST_REEL", &a).unwrap();
    }

    #[test]
    fn a_lookup_of_an_undeclared_keyword_is_an_internal_error() {
        let a = call("DEFI_LIST_REEL", vec![("VALE", Value::list(vec![Value::Float(1.0)]))]);
        let _ = a.reals("VALE");
        let _ = a.text("VALEUR"); // misspelt: never declared
        let e = all_keywords_used("DEFI_LIST_REEL", &a).unwrap_err();
        assert!(e.msg.contains("does not declare: DEFI_LIST_REEL/VALEUR"), "{}", e.msg);
        // Shared code asks first.
        assert!(!a.declares("VALEUR"));
        assert_eq!(a.text_if_declared("VALEUR"), None);
        all_keywords_used("DEFI_LIST_REEL", &a).unwrap();
    }
}
