//! Concepts: the typed results of commands.
//!
//! In Code_Aster every command result is a *concept* of a named type
//! (`fonction_sdaster`, `table_sdaster`, `maillage_sdaster`, ...). The
//! catalogue declares which types each keyword accepts and which type a
//! command produces, so that a wrong type is reported at the call. The data
//! behind a concept lives in the submodules; this module owns the kinds and
//! the shared container.

pub mod function;
pub mod model;
pub mod result;
pub mod table;

use crate::diag::{Error, Result};
use std::cell::{Ref, RefCell, RefMut};
use std::fmt;
use std::rc::Rc;

pub use function::{Formula, Function, Interp as Interpolation, Nappe, Prol};
pub use table::{Cell, Table};

/// The concept types, named as in Code_Aster's catalogue.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ConceptKind {
    Maillage,
    Modele,
    Mater,
    ChamMater,
    CharMeca,
    CharCineMeca,
    CharCineTher,
    CharTher,
    CharContact,
    Fonction,
    FonctionC,
    Nappe,
    Formule,
    Table,
    TableContainer,
    ListR8,
    ListIs,
    ListInst,
    EvolElas,
    EvolNoli,
    EvolTher,
    FissXfem,
    ChamNo,
    ChamElem,
    Carte,
}

impl ConceptKind {
    /// The Code_Aster type name, as users see it in messages.
    pub fn aster_name(self) -> &'static str {
        use ConceptKind::*;
        match self {
            Maillage => "maillage_sdaster",
            Modele => "modele_sdaster",
            Mater => "mater_sdaster",
            ChamMater => "cham_mater",
            CharMeca => "char_meca",
            CharCineMeca => "char_cine_meca",
            CharCineTher => "char_cine_ther",
            CharTher => "char_ther",
            CharContact => "char_contact",
            Fonction => "fonction_sdaster",
            FonctionC => "fonction_c",
            Nappe => "nappe_sdaster",
            Formule => "formule",
            Table => "table_sdaster",
            TableContainer => "table_container",
            ListR8 => "listr8_sdaster",
            ListIs => "listis_sdaster",
            ListInst => "list_inst",
            EvolElas => "evol_elas",
            EvolNoli => "evol_noli",
            EvolTher => "evol_ther",
            FissXfem => "fiss_xfem",
            ChamNo => "cham_no_sdaster",
            ChamElem => "cham_elem",
            Carte => "carte_sdaster",
        }
    }
}

impl fmt::Display for ConceptKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.aster_name())
    }
}

/// The data a concept holds. `Pending` is what `aster check` produces: the
/// type is known, the content was never computed.
/// DEFI_LIST_INST: a list of instants with Code_Aster's handling of a step that fails (ECHEC).
#[derive(Debug, Clone, PartialEq)]
pub struct TimeList {
    pub instants: Vec<f64>,
    /// EVENEMENT='ERREUR' with ACTION='DECOUPE': how a failed step is cut; None for ACTION='ARRET'.
    pub subdivision: Option<Subdivision>,
}

/// SUBD_METHODE='MANUEL': a failed step is cut into `pas` equal steps, at most `niveau` times
/// recursively, never below `pas_mini` (0: no bound).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Subdivision {
    pub pas: usize,
    pub niveau: usize,
    pub pas_mini: f64,
}

#[derive(Debug)]
pub enum ConceptData {
    Pending,
    Function(Function),
    Nappe(Nappe),
    Formula(function::Formula),
    Table(Table),
    ListReal(Vec<f64>),
    ListInt(Vec<i64>),
    /// DEFI_LIST_INST: the instants and what to do when a step fails.
    ListInst(TimeList),
    Mesh(std::rc::Rc<crate::mesh::Mesh>),
    Model(model::Model),
    Material(std::rc::Rc<model::Material>),
    MaterialField(model::MaterialField),
    Load(model::Load),
    Result(result::ResultData),
    Crack(Rc<crate::xfem::Crack>),
    Contact(model::Contact),
    Field(result::FieldData),
}

/// A command result: its type, the name it was given, and its data.
#[derive(Debug)]
pub struct Concept {
    kind: ConceptKind,
    name: RefCell<String>,
    data: RefCell<ConceptData>,
}

pub type ConceptRef = Rc<Concept>;

impl Concept {
    pub fn new(kind: ConceptKind, data: ConceptData) -> ConceptRef {
        Rc::new(Concept { kind, name: RefCell::new(String::new()), data: RefCell::new(data) })
    }
    pub fn kind(&self) -> ConceptKind {
        self.kind
    }
    pub fn name(&self) -> String {
        self.name.borrow().clone()
    }
    pub fn set_name(&self, name: &str) {
        if self.name.borrow().is_empty() {
            *self.name.borrow_mut() = name.to_string();
        }
    }
    pub fn data(&self) -> Ref<'_, ConceptData> {
        self.data.borrow()
    }
    pub fn data_mut(&self) -> RefMut<'_, ConceptData> {
        self.data.borrow_mut()
    }
    /// `reuse=`: the concept keeps its identity and takes new content.
    pub fn replace(&self, data: ConceptData) {
        *self.data.borrow_mut() = data;
    }
    pub fn is_pending(&self) -> bool {
        matches!(*self.data.borrow(), ConceptData::Pending)
    }
    /// A display name: the variable name, or the type when unnamed.
    pub fn label(&self) -> String {
        let n = self.name();
        if n.is_empty() {
            format!("<{}>", self.kind)
        } else {
            n
        }
    }

    fn holds_no(&self, what: &str) -> Error {
        Error::runtime(format!("{} ({}) holds no {what}", self.label(), self.kind()))
    }

    /// The mesh behind a `maillage_sdaster`.
    pub fn mesh(&self) -> Result<Rc<crate::mesh::Mesh>> {
        match &*self.data() {
            ConceptData::Mesh(m) => Ok(m.clone()),
            _ => Err(self.holds_no("mesh")),
        }
    }

    /// The model behind a `modele_sdaster`.
    pub fn model(&self) -> Result<Ref<'_, model::Model>> {
        Ref::filter_map(self.data(), |d| if let ConceptData::Model(m) = d { Some(m) } else { None })
            .map_err(|_| self.holds_no("model"))
    }

    /// The result behind an `evol_*`.
    pub fn result(&self) -> Result<Ref<'_, result::ResultData>> {
        Ref::filter_map(self.data(), |d| if let ConceptData::Result(r) = d { Some(r) } else { None })
            .map_err(|_| self.holds_no("result"))
    }

    /// A copy of the table behind a `table_sdaster`.
    pub fn table(&self) -> Result<Table> {
        match &*self.data() {
            ConceptData::Table(t) => Ok(t.clone()),
            _ => Err(self.holds_no("table")),
        }
    }

    /// The field behind a `cham_no` / `cham_elem` / `carte`.
    pub fn field(&self) -> Result<Ref<'_, result::FieldData>> {
        Ref::filter_map(self.data(), |d| if let ConceptData::Field(f) = d { Some(f) } else { None })
            .map_err(|_| self.holds_no("field"))
    }

    /// The values of a list of reals or integers (DEFI_LIST_REEL, DEFI_LIST_ENTI).
    pub fn reals(&self) -> Result<Vec<f64>> {
        match &*self.data() {
            ConceptData::ListReal(v) => Ok(v.clone()),
            ConceptData::ListInt(v) => Ok(v.iter().map(|i| *i as f64).collect()),
            ConceptData::ListInst(l) => Ok(l.instants.clone()),
            _ => Err(Error::runtime(format!("{} is not a list of reals", self.label()))),
        }
    }

    /// The X-FEM crack behind a `fiss_xfem`.
    pub fn crack(&self) -> Result<Rc<crate::xfem::Crack>> {
        match &*self.data() {
            ConceptData::Crack(k) => Ok(k.clone()),
            _ => Err(self.holds_no("X-FEM crack")),
        }
    }
}
