//! Concepts: the typed results of commands.
//!
//! In Code_Aster every command result is a *concept* of a named type
//! (`fonction_sdaster`, `table_sdaster`, `maillage_sdaster`, ...). The
//! catalogue declares which types each keyword accepts and which type a
//! command produces, so that a wrong type is reported at the call. The data
//! behind a concept lives in the submodules; this module owns the kinds and
//! the shared container.

pub mod function;
mod kind;
pub mod model;
pub mod result;
pub mod table;

use crate::diag::{Error, Result};
use std::cell::{Ref, RefCell, RefMut};
use std::fmt;
use std::rc::Rc;

pub use function::{Formula, Function, Interp as Interpolation, Nappe, Prol};
pub use table::{Cell, Table};

pub use kind::ConceptKind;

impl ConceptKind {
    /// The Code_Aster type name, as users see it in messages.
    pub fn aster_name(self) -> &'static str {
        kind::KINDS[self as usize].1
    }

    /// The type this one specialises (`cham_no_sdaster` → `cham_gd_sdaster`); None at the root.
    pub fn parent(self) -> Option<ConceptKind> {
        kind::KINDS[self as usize].2
    }

    /// Is a concept of this type accepted where `other` is expected (the same type or a subtype)?
    pub fn is_a(self, other: ConceptKind) -> bool {
        let mut k = Some(self);
        while let Some(x) = k {
            if x == other {
                return true;
            }
            k = x.parent();
        }
        false
    }

    /// The kind named `name` in Code_Aster's catalogue.
    pub fn from_aster_name(name: &str) -> Option<ConceptKind> {
        kind::KINDS.iter().find(|(_, n, _)| *n == name).map(|(k, _, _)| *k)
    }

    /// The most specific type of which every one of `kinds` is a subtype.
    pub fn common_ancestor(kinds: &[ConceptKind]) -> ConceptKind {
        let Some(&first) = kinds.first() else { return ConceptKind::DataStructure };
        let mut k = Some(first);
        while let Some(x) = k {
            if kinds.iter().all(|o| o.is_a(x)) {
                return x;
            }
            k = x.parent();
        }
        ConceptKind::DataStructure
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
    CaraElem(model::CaraElem),
    Field(result::FieldData),
}

/// A command result: its type, the name it was given, and its data.
#[derive(Debug)]
pub struct Concept {
    /// Changes once: a `CO('name')` placeholder becomes the concept the command creates under it.
    kind: std::cell::Cell<ConceptKind>,
    /// `aster check` only: the types a result may have when the catalogue cannot tell which one
    /// without computing, each possibly a subtype of the one named (`kind` is then their common
    /// ancestor); empty when the type is known.
    alternatives: RefCell<Vec<ConceptKind>>,
    name: RefCell<String>,
    data: RefCell<ConceptData>,
}

pub type ConceptRef = Rc<Concept>;

impl Concept {
    pub fn new(kind: ConceptKind, data: ConceptData) -> ConceptRef {
        Rc::new(Concept {
            kind: kind.into(),
            alternatives: RefCell::new(Vec::new()),
            name: RefCell::new(String::new()),
            data: RefCell::new(data),
        })
    }
    /// A placeholder (`aster check`) for a result whose type is one of `kinds`, not known without
    /// computing.
    pub fn pending_one_of(kinds: &[ConceptKind]) -> ConceptRef {
        let kind = ConceptKind::common_ancestor(kinds);
        let alternatives = kinds.to_vec();
        Rc::new(Concept {
            kind: kind.into(),
            alternatives: RefCell::new(alternatives),
            name: RefCell::new(String::new()),
            data: RefCell::new(ConceptData::Pending),
        })
    }
    /// Can this concept be used where a `k` is expected: its type is `k` or a subtype, or (a
    /// placeholder of uncertain type) one of the types it may have is.
    pub fn may_be(&self, k: ConceptKind) -> bool {
        if self.kind().is_a(k) {
            return true;
        }
        // `aster check`'s placeholders know their type up to what the catalogue tells: one of the
        // alternatives, or a type that is only an upper bound (CALC_CHAMP's result is a
        // resultat_sdaster: an evol_elas, an evol_noli, ...).
        if !matches!(*self.data.borrow(), ConceptData::Pending) {
            return false;
        }
        self.alternatives.borrow().iter().any(|a| a.is_a(k) || k.is_a(*a))
    }
    /// The types a placeholder of uncertain type may have (empty when the type is known).
    pub fn alternatives(&self) -> Vec<ConceptKind> {
        self.alternatives.borrow().clone()
    }
    /// `aster check`: the `CO('name')` placeholder becomes a concept of one of `kinds`, the one its
    /// command creates (the same object, so that every reference to the placeholder sees it).
    pub fn become_one_of(&self, kinds: &[ConceptKind]) {
        self.kind.set(ConceptKind::common_ancestor(kinds));
        *self.alternatives.borrow_mut() = kinds.to_vec();
    }
    pub fn kind(&self) -> ConceptKind {
        self.kind.get()
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
            format!("<{}>", self.kind())
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

    /// The element characteristics behind a `cara_elem`.
    pub fn cara_elem(&self) -> Result<Ref<'_, model::CaraElem>> {
        Ref::filter_map(self.data(), |d| if let ConceptData::CaraElem(c) = d { Some(c) } else { None })
            .map_err(|_| self.holds_no("element characteristics"))
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
