//! What the solving commands share, read once: MODELE, CHAM_MATER, EXCIT, INCREMENT (or INST), CONVERGENCE,
//! NEWTON, SOLVEUR, ARCHIVAGE, ETAT_INIT, COMPORTEMENT, SCHEMA_THM, CONTACT and OPTION become typed
//! [`Settings`], and the physics that solves the command is chosen here ([`PhysicsKind`], from the model),
//! which decides what of these keywords it takes: a keyword the physics does not implement stops the run
//! by name here, so that nothing below this module looks at the command's keywords again. THER_LINEAIRE
//! and THER_NON_LINE read theirs in `thermal` into the same settings. A physics and the
//! core's driver read the settings and locate their errors at a keyword through [`Settings::err`].

mod thermal;

pub use thermal::{HeatInitial, HeatSettings};

use super::newton::{Archive, Convergence, LineSearch};
use super::solver::{solveur, Solveur};
use crate::catalog::args::Args;
use crate::concepts::model::Load;
use crate::concepts::{ConceptData, ConceptRef, Subdivision};
use crate::diag::Span;
use crate::diag::{Error, Result};
use std::collections::BTreeMap;
use std::rc::Rc;

/// The solving commands on the shared core.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    MecaStatique,
    StatNonLine,
    TherLineaire,
    TherNonLine,
}

impl Command {
    pub fn name(self) -> &'static str {
        match self {
            Command::MecaStatique => "MECA_STATIQUE",
            Command::StatNonLine => "STAT_NON_LINE",
            Command::TherLineaire => "THER_LINEAIRE",
            Command::TherNonLine => "THER_NON_LINE",
        }
    }

    /// A command of heat conduction.
    pub fn thermal(self) -> bool {
        matches!(self, Command::TherLineaire | Command::TherNonLine)
    }
}

/// The physics a solving command runs, chosen from its model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhysicsKind {
    /// Linear elasticity on 3D, D_PLAN, C_PLAN and AXIS models.
    Elastic,
    /// Saturated hydro-mechanics (KIT_HM) on the `*_HM*` modelisations.
    Hm,
    /// A model enriched by MODI_MODELE_XFEM (mechanics, or HM with its hydraulics), with or without
    /// cohesive interfaces.
    Xfem,
    /// Heat conduction on a thermal model (PHENOMENE='THERMIQUE').
    Thermal,
}

/// A load of EXCIT: the load, its multiplier function and where it was given.
#[derive(Debug, Clone)]
pub struct Excit {
    pub load: ConceptRef,
    pub fonc_mult: Option<ConceptRef>,
    pub span: Span,
    /// Where FONC_MULT was given (the occurrence when absent).
    pub fonc_mult_span: Span,
}

/// One occurrence of COMPORTEMENT.
#[derive(Debug, Clone)]
pub struct Behaviour {
    pub relation: String,
    pub kit: Vec<String>,
    pub deformation: Option<String>,
    /// The cells of GROUP_MA / MAILLE; None for the whole model.
    pub cells: Option<Vec<usize>>,
    /// RESI_INTE (or RESI_INTE_RELA; 1e-6 when absent) and ITER_INTE_MAXI (20 when absent): the controls of
    /// a law integrated iteratively.
    pub resi_inte: f64,
    pub iter_inte: usize,
    /// Where RELATION and RELATION_KIT were given.
    relation_span: Span,
    kit_span: Span,
}

impl Behaviour {
    /// An error located at a keyword of this occurrence (`RELATION`, `RELATION_KIT`), worded as
    /// `Args::err` words it.
    pub fn err(&self, kw: &str, msg: impl Into<String>) -> Error {
        let span = if kw == "RELATION_KIT" { self.kit_span } else { self.relation_span };
        Error::runtime(format!("COMPORTEMENT/{kw}: {}", msg.into())).at(span)
    }
}

/// NEWTON's choice of matrices (STAT_NON_LINE on mechanics): the elastic one instead of the tangent for
/// the prediction (PREDICTION='ELASTIQUE') and for the corrections (MATRICE='ELASTIQUE').
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Matrices {
    pub prediction_elastic: bool,
    pub correction_elastic: bool,
}

/// STAT_NON_LINE's NEWTON on mechanics, as Code_Aster's `nmdomt` reads it: MATRICE (TANGENTE by default,
/// or ELASTIQUE), PREDICTION (MATRICE's when absent; TANGENTE or ELASTIQUE — EXTRAPOLE and DEPL_CALCULE
/// stop by name), REAC_ITER (1), REAC_INCR (1; another value only with an elastic prediction, whose matrix
/// does not change), MATR_RIGI_SYME (our matrices are symmetric); PAS_MINI_ELAS and REAC_ITER_ELAS stop
/// by name. The line of the run log, the matrices and REAC_ITER.
fn mechanics_newton(a: &Args) -> Result<(Option<String>, Matrices, usize)> {
    let Some(nw) = a.fact("NEWTON") else { return Ok((None, Matrices::default(), 1)) };
    let matrice = nw.text("MATRICE").unwrap_or("TANGENTE").to_string();
    let prediction = nw.text("PREDICTION").unwrap_or(&matrice).to_string();
    if !["TANGENTE", "ELASTIQUE"].contains(&prediction.as_str()) {
        return Err(
            nw.err("PREDICTION", format!("PREDICTION='{prediction}' is not supported yet (TANGENTE, ELASTIQUE are)"))
        );
    }
    let m = Matrices { prediction_elastic: prediction == "ELASTIQUE", correction_elastic: matrice == "ELASTIQUE" };
    let reac_iter = nw.int("REAC_ITER").unwrap_or(1).max(0) as usize;
    let reac_incr = nw.int("REAC_INCR").unwrap_or(1);
    if reac_incr != 1 && !m.prediction_elastic {
        return Err(nw.err("REAC_INCR", "REAC_INCR other than 1 with a tangent prediction is not supported yet"));
    }
    if nw.given("PAS_MINI_ELAS") {
        return Err(nw.err("PAS_MINI_ELAS", "not supported yet"));
    }
    if nw.int("REAC_ITER_ELAS").is_some_and(|r| r != 0) {
        return Err(nw.err("REAC_ITER_ELAS", "not supported yet"));
    }
    let _ = nw.text("MATR_RIGI_SYME");
    let asked: Vec<String> = nw.items.iter().filter(|i| !i.defaulted).map(|i| i.name.clone()).collect();
    let note = (!asked.is_empty()).then(|| {
        format!(
            "    NEWTON    : PREDICTION='{prediction}', MATRICE='{matrice}', REAC_ITER={reac_iter}, REAC_INCR={reac_incr}"
        )
    });
    Ok((note, m, reac_iter))
}

/// ETAT_INIT: a stored step of a result (EVOL_NOLI, by NUME_ORDRE or INST) or fields (DEPL, SIGM, VARI).
#[derive(Debug, Clone, Default)]
pub struct InitialState {
    pub evol_noli: Option<ConceptRef>,
    pub nume_ordre: Option<i64>,
    pub inst: Option<f64>,
    pub precision: f64,
    pub absolute: bool,
    pub depl: Option<ConceptRef>,
    pub sigm: Option<ConceptRef>,
    pub vari: Option<ConceptRef>,
    /// The order and instant of EVOL_NOLI's step.
    pub step: Option<(i64, f64)>,
}

/// What a physics takes of the shared keywords; anything else the user gives stops the run by name.
struct Takes {
    /// Top-level keywords of STAT_NON_LINE it implements beyond the ones every physics takes.
    keywords: &'static [&'static str],
    /// The keywords of ETAT_INIT it reads.
    etat_init: &'static [&'static str],
}

/// STAT_NON_LINE keywords no physics implements yet.
const NOT_YET: &[&str] =
    &["SOUS_STRUC", "PILOTAGE", "OBSERVATION", "SUIVI_DDL", "CRIT_QUALITE", "ENERGIE", "CRIT_STAB", "RESULTAT"];

impl PhysicsKind {
    fn takes(self) -> Takes {
        match self {
            PhysicsKind::Elastic => Takes { keywords: &["ARCHIVAGE", "RECH_LINEAIRE"], etat_init: &[] },
            PhysicsKind::Hm => Takes {
                keywords: &["ETAT_INIT", "ARCHIVAGE", "SCHEMA_THM"],
                etat_init: &["DEPL", "SIGM", "VARI", "CRITERE", "PRECISION"],
            },
            PhysicsKind::Xfem => Takes {
                keywords: &["ETAT_INIT", "ARCHIVAGE", "SCHEMA_THM", "CONTACT"],
                etat_init: &["EVOL_NOLI", "NUME_ORDRE", "INST", "CRITERE", "PRECISION"],
            },
            // The thermal commands' keywords are read by `thermal::read`.
            PhysicsKind::Thermal => Takes { keywords: &[], etat_init: &[] },
        }
    }
}

/// The typed keywords of one solving command.
pub struct Settings {
    pub command: Command,
    pub physics: PhysicsKind,
    /// The command's own location.
    pub span: Span,
    /// Where each keyword was given, by path (`EXCIT`, `ETAT_INIT/EVOL_NOLI`, ...).
    sites: BTreeMap<String, Span>,
    pub model: ConceptRef,
    pub chmat: Option<ConceptRef>,
    /// CARA_ELEM: the element characteristics (the local frames of anisotropic materials).
    pub cara_elem: Option<ConceptRef>,
    pub excit: Vec<Excit>,
    /// The instants, the initial one first (MECA_STATIQUE: INST twice).
    pub times: Vec<f64>,
    /// DEFI_LIST_INST's cutting of a failed step.
    pub subdivision: Option<Subdivision>,
    pub conv: Convergence,
    /// NEWTON's options when the file sets them, for the log.
    pub newton_note: Option<String>,
    pub solveur: Solveur,
    /// ARCHIVAGE (STAT_NON_LINE).
    pub archive: Option<Archive>,
    pub initial: Option<InitialState>,
    pub behaviours: Vec<Behaviour>,
    /// SCHEMA_THM's PARM_THETA (1 when absent).
    pub theta: f64,
    pub schema_thm: bool,
    pub contact: Option<ConceptRef>,
    /// MECA_STATIQUE OPTION: SIEF_ELGA is computed unless 'SANS'.
    pub sief: bool,
    /// RECH_LINEAIRE along each Newton correction but the first of a step.
    pub line_search: Option<LineSearch>,
    /// NEWTON PREDICTION and MATRICE on mechanics: which steps use the elastic matrix.
    pub matrices: Matrices,
    /// NEWTON REAC_ITER: the corrections whose number is a multiple of it assemble the tangent again (1:
    /// every one; 0: none, the prediction's matrix serves the whole step).
    pub reac_iter: usize,
    /// THER_LINEAIRE, THER_NON_LINE: the θ-scheme, the initial state, RESULTAT continued.
    pub heat: Option<HeatSettings>,
}

impl Settings {
    /// Read a solving command's keywords: the model first (it chooses the physics), then every shared
    /// keyword, checked against what that physics takes.
    pub fn read(a: &Args, command: Command) -> Result<Settings> {
        let mut sites = BTreeMap::new();
        let model = a.req_concept("MODELE")?;
        let thermal_model = model.model()?.is_thermal();
        if command.thermal() {
            if !thermal_model {
                return Err(a.err(
                    "MODELE",
                    format!("{} is not a thermal model (AFFE_MODELE PHENOMENE='THERMIQUE')", model.label()),
                ));
            }
            return thermal::read(a, command, model);
        }
        if thermal_model {
            return Err(a.err(
                "MODELE",
                format!("{} is a thermal model: THER_LINEAIRE or THER_NON_LINE solves it", model.label()),
            ));
        }
        sites.insert("MODELE".to_string(), a.span_of("MODELE"));
        let physics = {
            let m = model.model()?;
            if m.xfem.is_some() {
                PhysicsKind::Xfem
            } else if m.elements.iter().flatten().any(|e| e.modelisation.is_hm()) {
                PhysicsKind::Hm
            } else {
                PhysicsKind::Elastic
            }
        };
        let takes = physics.takes();
        let statics = command == Command::MecaStatique;
        if statics {
            a.refuse(&["CARA_ELEM", "SENSIBILITE", "RESULTAT", "INST_FIN"])?;
        } else {
            a.refuse(NOT_YET)?;
            let refused: Vec<&str> = ["ETAT_INIT", "SCHEMA_THM", "CONTACT", "RECH_LINEAIRE"]
                .into_iter()
                .filter(|k| !takes.keywords.contains(k))
                .collect();
            a.refuse(&refused)?;
            if let Some(m) = a.text("METHODE").filter(|m| *m != "NEWTON") {
                return Err(Error::unsupported(format!("METHODE: METHODE='{m}' is not supported yet (NEWTON is)"))
                    .at(a.span_of("METHODE")));
            }
        }
        let chmat = a.concept("CHAM_MATER");
        if physics != PhysicsKind::Elastic && chmat.as_ref().is_some_and(has_varc) {
            let what = if physics == PhysicsKind::Hm { "a hydro-mechanical" } else { "an X-FEM" };
            return Err(a.err("CHAM_MATER", format!("AFFE_VARC on {what} model is not supported yet")));
        }
        for kw in ["CHAM_MATER", "EXCIT", "INCREMENT", "CONVERGENCE", "SOLVEUR", "ARCHIVAGE", "ETAT_INIT", "CONTACT"] {
            if a.declares(kw) && a.given(kw) {
                sites.insert(kw.to_string(), a.span_of(kw));
            }
        }
        let mut excit = Vec::new();
        for occ in a.facts("EXCIT") {
            if occ.given("TYPE_CHARGE") && occ.text("TYPE_CHARGE") != Some("FIXE_CSTE") {
                return Err(occ.err("TYPE_CHARGE", "not supported yet"));
            }
            let load = occ.req_concept("CHARGE")?;
            {
                let data = load.data();
                let ConceptData::Load(Load { model: lmodel, .. }) = &*data else {
                    return Err(a.err("EXCIT", format!("{} is not a mechanical load", load.label())));
                };
                if !Rc::ptr_eq(lmodel, &model) {
                    return Err(a.err(
                        "EXCIT",
                        format!("load {} is defined on another model ({})", load.label(), lmodel.label()),
                    ));
                }
            }
            let fonc_mult = occ.concept("FONC_MULT");
            excit.push(Excit { load, fonc_mult, span: occ.span, fonc_mult_span: occ.span_of("FONC_MULT") });
        }
        let initial = if a.declares("ETAT_INIT") { initial_state(a, &takes, &model, &mut sites)? } else { None };
        let behaviours = if a.declares("COMPORTEMENT") { behaviours(a, physics, &model)? } else { Vec::new() };
        let (theta, schema_thm) = match a.declares("SCHEMA_THM").then(|| a.fact("SCHEMA_THM")).flatten() {
            Some(s) => {
                // PARM_ALPHA weighs the thermal terms of other laws; saturated HM without temperature has none.
                let _ = s.real("PARM_ALPHA");
                (s.real("PARM_THETA").unwrap_or(1.0), a.given("SCHEMA_THM"))
            }
            None => (1.0, false),
        };
        let contact = a.declares("CONTACT").then(|| a.concept("CONTACT")).flatten();
        let sief = if statics {
            match a.text("OPTION") {
                None | Some("SIEF_ELGA") => true,
                Some("SANS") => false,
                Some(o) => return Err(a.err("OPTION", format!("OPTION='{o}' is not supported yet"))),
            }
        } else {
            true
        };
        let conv = if statics { Convergence::default() } else { Convergence::from_args(a)? };
        let (newton_note, matrices, reac_iter) = if statics {
            (None, Matrices::default(), 1)
        } else if physics == PhysicsKind::Elastic {
            mechanics_newton(a)?
        } else {
            (super::newton::newton_note(a), Matrices::default(), 1)
        };
        let solveur = solveur(a)?;
        let (times, subdivision) = if statics {
            match a.concept("LIST_INST") {
                // One linear solve at each instant of the list, numbered from 1.
                Some(lc) => {
                    let list = super::newton::list_values(&lc).map_err(|m| a.err("LIST_INST", m))?;
                    let first = *list.first().ok_or_else(|| a.err("LIST_INST", format!("{} is empty", lc.label())))?;
                    (std::iter::once(first).chain(list).collect(), None)
                }
                None => {
                    let inst = a.reals("INST").first().copied().unwrap_or(0.0);
                    (vec![inst, inst], None)
                }
            }
        } else {
            // ETAT_INIT's instant (EVOL_NOLI) starts the computation when INCREMENT does not say where.
            let init_inst = initial.as_ref().and_then(|i| i.step).map(|(_, t)| t);
            (super::newton::instants_from(a, init_inst)?, super::newton::subdivision(a))
        };
        let archive = if statics { None } else { Some(Archive::from_args(a, &times)?) };
        let line_search = if takes.keywords.contains(&"RECH_LINEAIRE") && !statics { line_search(a)? } else { None };
        Ok(Settings {
            command,
            physics,
            span: a.span,
            sites,
            model,
            chmat,
            cara_elem: None,
            excit,
            times,
            subdivision,
            conv,
            newton_note,
            solveur,
            archive,
            initial,
            behaviours,
            theta,
            schema_thm,
            contact,
            sief,
            line_search,
            matrices,
            reac_iter,
            heat: None,
        })
    }

    /// A runtime error located at keyword `kw` (a path as `ETAT_INIT/EVOL_NOLI`), worded as
    /// `Args::err` words it.
    pub fn err(&self, kw: &str, msg: impl Into<String>) -> Error {
        Error::runtime(format!("{kw}: {}", msg.into())).at(self.span_of(kw))
    }

    /// Where keyword `kw` was given (the command when it was not).
    pub fn span_of(&self, kw: &str) -> Span {
        self.sites.get(kw).copied().unwrap_or(self.span)
    }

    /// An error of a library located: at the keyword it names (`Error::at_keyword`, worded `"KW: msg"`), or
    /// at the command.
    pub fn place(&self, e: Error) -> Error {
        match (e.span, e.keyword) {
            (None, Some(kw)) => self.locate(Error { keyword: None, ..e }, kw),
            (None, None) => e.at(self.span),
            _ => e,
        }
    }

    /// The error `e` located at keyword `kw` when it has no location, its message and kind kept.
    pub fn locate(&self, e: Error, kw: &str) -> Error {
        if e.span.is_some() {
            return e;
        }
        let mut out = self.err(kw, e.msg.clone());
        out.kind = e.kind;
        out
    }

    /// The loads of EXCIT, the results keep them.
    pub fn loads(&self) -> Vec<ConceptRef> {
        self.excit.iter().map(|e| e.load.clone()).collect()
    }

    /// The material field, required by every physics.
    pub fn chmat(&self) -> Result<ConceptRef> {
        self.chmat.clone().ok_or_else(|| self.err("CHAM_MATER", "a material field is required"))
    }

    pub fn statics(&self) -> bool {
        self.command == Command::MecaStatique
    }
}

/// ETAT_INIT's keywords: those the physics takes; any other given stops the run by name.
fn initial_state(
    a: &Args,
    takes: &Takes,
    model: &ConceptRef,
    sites: &mut BTreeMap<String, Span>,
) -> Result<Option<InitialState>> {
    let Some(e) = a.fact("ETAT_INIT") else { return Ok(None) };
    for i in e.items.iter().filter(|i| !i.defaulted) {
        sites.insert(format!("ETAT_INIT/{}", i.name), i.span);
    }
    let others: Vec<&str> = e
        .items
        .iter()
        .filter(|i| !i.defaulted && !takes.etat_init.contains(&i.name.as_str()))
        .map(|i| i.name.as_str())
        .collect();
    e.refuse(&others)?;
    let mut s = InitialState { precision: 1e-6, ..Default::default() };
    for k in takes.etat_init {
        match *k {
            "EVOL_NOLI" => s.evol_noli = e.concept("EVOL_NOLI"),
            "NUME_ORDRE" => s.nume_ordre = e.int("NUME_ORDRE"),
            "INST" => s.inst = e.real("INST"),
            "PRECISION" => s.precision = e.real("PRECISION").unwrap_or(1e-6),
            "CRITERE" => s.absolute = e.text("CRITERE") == Some("ABSOLU"),
            "DEPL" => s.depl = e.concept("DEPL"),
            "SIGM" => s.sigm = e.concept("SIGM"),
            "VARI" => s.vari = e.concept("VARI"),
            _ => unreachable!("ETAT_INIT keywords of a physics"),
        }
    }
    // CRITERE and PRECISION only qualify INST; with fields alone they have nothing to select.
    for k in ["CRITERE", "PRECISION"] {
        if e.declares(k) {
            e.has(k);
        }
    }
    if takes.etat_init.contains(&"EVOL_NOLI") {
        let Some(rc) = s.evol_noli.clone() else {
            return Err(e.err("EVOL_NOLI", "an X-FEM STAT_NON_LINE starts from a result: EVOL_NOLI is required"));
        };
        s.step = Some(initial_step(e, &rc, &s, model)?);
    }
    Ok(Some(s))
}

/// The order and instant of ETAT_INIT's step of `rc` (NUME_ORDRE, INST within PRECISION, else the last),
/// a result of the same model.
fn initial_step(e: &Args, rc: &ConceptRef, s: &InitialState, model: &ConceptRef) -> Result<(i64, f64)> {
    let r = rc.result().map_err(|err| e.locate(err, "EVOL_NOLI"))?;
    if !Rc::ptr_eq(&r.model, model) {
        return Err(e.err(
            "EVOL_NOLI",
            format!(
                "{} was computed on {}, not on {}: an initial state on another model is not supported yet",
                rc.label(),
                r.model.label(),
                model.label()
            ),
        ));
    }
    let step = if let Some(n) = s.nume_ordre {
        r.by_order(n).ok_or_else(|| e.err("NUME_ORDRE", format!("{} has no order {n}", rc.label())))?
    } else if let Some(t) = s.inst {
        let close = |x: f64| (x - t).abs() <= if s.absolute { s.precision } else { s.precision * t.abs() };
        let found: Vec<_> = r.steps.iter().filter(|st| close(st.inst) || st.inst == t).collect();
        match found.as_slice() {
            [st] => *st,
            [] => return Err(e.err("INST", format!("{} has no step at INST={t}", rc.label()))),
            _ => return Err(e.err("INST", format!("{} has several steps at INST={t}: give NUME_ORDRE", rc.label()))),
        }
    } else {
        r.steps
            .iter()
            .max_by_key(|st| st.nume_ordre)
            .ok_or_else(|| e.err("EVOL_NOLI", format!("{} is empty", rc.label())))?
    };
    Ok((step.nume_ordre, step.inst))
}

/// STAT_NON_LINE's RECH_LINEAIRE on mechanics: METHODE='CORDE' (the default; the others stop by name),
/// along every Newton correction after the prediction, as Code_Aster's `nmdepl` does. None without it or
/// with ITER_LINE_MAXI=0.
fn line_search(a: &Args) -> Result<Option<LineSearch>> {
    let Some(rl) = a.fact("RECH_LINEAIRE") else { return Ok(None) };
    if let Some(m) = rl.text("METHODE").filter(|m| *m != "CORDE") {
        return Err(rl.err("METHODE", format!("METHODE='{m}' is not supported yet (CORDE is)")));
    }
    let ls = LineSearch {
        resi: rl.real("RESI_LINE_RELA").unwrap_or(0.1),
        iter_max: rl.int("ITER_LINE_MAXI").unwrap_or(3).max(0) as usize,
        rho_min: rl.real("RHO_MIN").unwrap_or(1e-2),
        rho_max: rl.real("RHO_MAX").unwrap_or(10.0),
        rho_excl: rl.real("RHO_EXCL").unwrap_or(0.9e-2),
    };
    Ok((ls.iter_max > 0).then_some(ls))
}

/// COMPORTEMENT, typed, with the cells of each occurrence (GROUP_MA, MAILLE: the plain mechanics alone
/// takes COMPORTEMENT on part of the model; the others refuse it); the controls of the local
/// integration are read here (the von Mises return under C_PLAN uses RESI_INTE and ITER_INTE_MAXI; the
/// other laws integrate in closed form).
fn behaviours(a: &Args, physics: PhysicsKind, model: &ConceptRef) -> Result<Vec<Behaviour>> {
    let mut out = Vec::new();
    for occ in a.facts("COMPORTEMENT") {
        let part = ["GROUP_MA", "MAILLE"].iter().any(|k| occ.declares(k) && occ.has(k));
        let cells = if part && physics == PhysicsKind::Elastic {
            let m = model.model()?;
            Some(crate::stages::select::select_cells(&m.current_mesh(), occ, &m.mesh_concept.label())?)
        } else {
            occ.refuse(&["GROUP_MA", "MAILLE"])?;
            None
        };
        // TOUT='OUI' is the whole model: what an occurrence without GROUP_MA or MAILLE covers.
        if occ.declares("TOUT") {
            occ.has("TOUT");
        }
        for k in ["ITER_INTE_PAS", "RESI_INTE_MAXI", "ALGO_INTE"] {
            if occ.declares(k) {
                occ.has(k);
            }
        }
        // The controls of an iterative return (the plane-stress one of the von Mises laws).
        let resi_inte = ["RESI_INTE", "RESI_INTE_RELA"]
            .iter()
            .filter(|k| occ.declares(k))
            .find_map(|k| occ.real(k))
            .unwrap_or(1e-6);
        let iter_inte = if occ.declares("ITER_INTE_MAXI") { occ.int("ITER_INTE_MAXI") } else { None }
            .map_or(20, |i| i.unsigned_abs() as usize);
        let deformation = occ.text("DEFORMATION").map(str::to_string);
        if let Some(d) = deformation.as_deref().filter(|d| *d != "PETIT") {
            return Err(Error::unsupported(format!(
                "COMPORTEMENT/DEFORMATION: DEFORMATION='{d}' is not supported yet (PETIT is)"
            ))
            .at(occ.span_of("DEFORMATION")));
        }
        out.push(Behaviour {
            relation: occ.text("RELATION").unwrap_or("ELAS").to_string(),
            kit: occ.texts("RELATION_KIT"),
            deformation,
            cells,
            resi_inte,
            iter_inte,
            relation_span: occ.span_of("RELATION"),
            kit_span: occ.span_of("RELATION_KIT"),
        });
    }
    Ok(out)
}

/// Does the material field carry command variables (AFFE_VARC)?
pub(crate) fn has_varc(chmat: &ConceptRef) -> bool {
    matches!(&*chmat.data(), ConceptData::MaterialField(m) if !m.varc.is_empty())
}
