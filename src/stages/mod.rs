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
use crate::diag::Result;
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
}

/// The stage's context for one command.
pub struct Ctx<'a> {
    pub io: &'a mut dyn StageIo,
    /// The globals of the command file (FORMULE evaluates in them).
    pub globals: Scope,
    /// The command's name and its line, for records.
    pub command: &'static str,
    pub line: usize,
}

pub type StageFn = fn(&mut Ctx, &Args) -> Result<Option<ConceptData>>;

/// The stage of a command, if it has one.
pub fn stage(name: &str) -> Option<StageFn> {
    Some(match name {
        "DEBUT" | "FIN" => control::nothing,
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
        "IMPR_RESU" => print::impr_resu,
        "AFFE_MODELE" => model::affe_modele,
        "DEFI_MATERIAU" => material::defi_materiau,
        "AFFE_MATERIAU" => material::affe_materiau,
        "AFFE_CHAR_MECA" => loads::affe_char_meca,
        "AFFE_CHAR_MECA_F" => loads::affe_char_meca_f,
        "TEST_RESU" => tests::test_resu::test_resu,
        "MECA_STATIQUE" => solve::meca_statique,
        "CALC_CHAMP" => fields::calc_champ,
        "CREA_CHAMP" => fields::crea_champ,
        "STAT_NON_LINE" => solve::stat_non_line,
        "POST_RELEVE_T" => post::post_releve_t,
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
