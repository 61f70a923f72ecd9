//! THER_LINEAIRE's and THER_NON_LINE's keywords, read once into the shared [`Settings`]: the instants as
//! Code_Aster's thermal time stepper takes them (steady at every instant, or transient from an initial
//! state), ETAT_INIT, the θ-scheme (SCHEMA_TEMPS, PARM_THETA), ARCHIVAGE (THER_NON_LINE always stores its
//! last instant), RESULTAT continued, and THER_NON_LINE's COMPORTEMENT, NEWTON, RECH_LINEAIRE and
//! CONVERGENCE.

use super::super::newton::{Archive, Convergence, LineSearch};
use super::super::solver::solveur;
use super::{Command, Excit, PhysicsKind, Settings};
use crate::catalog::args::Args;
use crate::concepts::model::HeatItem;
use crate::concepts::model::{Load, LoadItem};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Result, Span};
use std::collections::BTreeMap;
use std::rc::Rc;

/// How a transient computation's first state is had.
#[derive(Debug, Clone)]
pub enum HeatInitial {
    /// A steady computation at the initial instant (ETAT_INIT STAT='OUI', the default).
    Steady,
    /// A uniform temperature (VALE).
    Uniform(f64),
    /// A field of TEMP on nodes (CHAM_NO).
    Field(ConceptRef),
    /// A step of a thermal result (EVOL_THER, NUME_ORDRE or INST, else its last), by its index.
    Step(ConceptRef, usize),
}

/// What a thermal computation adds to the shared settings.
#[derive(Debug, Clone)]
pub struct HeatSettings {
    /// THER_NON_LINE.
    pub nonlinear: bool,
    /// θ of a transient computation; None: steady at every instant.
    pub theta: Option<f64>,
    /// The state at the first instant of a transient computation.
    pub initial: HeatInitial,
    /// RESULTAT (reused): the result continued and the steps of it kept (those numbered before
    /// `first`, the order of the first new step).
    pub reuse: Option<(ConceptRef, i64)>,
    /// Whether the initial state is stored (not when it is RESULTAT's own last step).
    pub store_initial: bool,
}

fn nonlinear_item(items: &[LoadItem]) -> Option<&'static str> {
    items.iter().find_map(|i| match i {
        LoadItem::Heat(
            h @ (HeatItem::Radiation { .. } | HeatItem::NonlinearFlux { .. } | HeatItem::NonlinearSource { .. }),
        ) => Some(h.keyword()),
        _ => None,
    })
}

/// The instants as Code_Aster's thermal stepper takes them: the initial one (INST_INIT, the
/// NUME_INST_INIT-th, else the first; none for a steady computation, which computes every instant), then
/// those after it up to INST_FIN / NUME_INST_FIN (INST_FIN appended when it is not one).
fn instants(a: &Args, steady: bool) -> Result<(Option<f64>, Vec<f64>)> {
    let Some(inc) = a.fact("INCREMENT") else {
        return Ok((None, vec![0.0]));
    };
    let lc = inc.req_concept("LIST_INST")?;
    let list = lc.reals().map_err(|e| inc.err("LIST_INST", e.msg))?;
    if list.is_empty() {
        return Err(inc.err("LIST_INST", format!("{} holds no instant", lc.label())));
    }
    if let Some(w) = list.windows(2).position(|w| w[1] <= w[0]) {
        return Err(
            inc.err("LIST_INST", format!("the instants must increase strictly ({} then {})", list[w], list[w + 1]))
        );
    }
    let prec = inc.real("PRECISION").unwrap_or(1e-6);
    let index = |n: i64, kw: &str| -> Result<f64> {
        usize::try_from(n)
            .ok()
            .and_then(|i| list.get(i).copied())
            .ok_or_else(|| inc.err(kw, format!("{} holds {} instants (numbered from 0)", lc.label(), list.len())))
    };
    let mut initial = if steady { None } else { Some(list[0]) };
    if let Some(t) = inc.real("INST_INIT") {
        initial = Some(t);
    }
    if let Some(n) = inc.int("NUME_INST_INIT").filter(|&n| n != 0) {
        initial = Some(index(n, "NUME_INST_INIT")?);
    }
    let mut fin = inc.real("INST_FIN");
    if let Some(n) = inc.int("NUME_INST_FIN").filter(|&n| n != 0) {
        fin = Some(index(n, "NUME_INST_FIN")?);
    }
    let cmp = |a: f64, b: f64| {
        if (a - b).abs() <= prec * b.abs().max(1e-300) {
            std::cmp::Ordering::Equal
        } else {
            a.total_cmp(&b)
        }
    };
    let mut steps: Vec<f64> = list.iter().copied().filter(|&t| initial.is_none_or(|i| cmp(t, i).is_gt())).collect();
    if let Some(f) = fin {
        steps.retain(|&t| cmp(t, f).is_le());
        if steps.last().is_none_or(|&l| cmp(f, l).is_gt()) {
            steps.push(f);
        }
    }
    Ok((initial, steps))
}

/// ETAT_INIT of a transient computation.
fn initial_state(a: &Args, sites: &mut BTreeMap<String, Span>) -> Result<HeatInitial> {
    let Some(ei) = a.fact("ETAT_INIT") else { return Ok(HeatInitial::Steady) };
    sites.insert("ETAT_INIT".into(), a.span_of("ETAT_INIT"));
    if ei.has("STAT") || ei.has("STATIONNAIRE") {
        return Ok(HeatInitial::Steady);
    }
    if let Some(v) = ei.real("VALE") {
        return Ok(HeatInitial::Uniform(v));
    }
    if let Some(c) = ei.concept("CHAM_NO") {
        sites.insert("ETAT_INIT/CHAM_NO".into(), ei.span_of("CHAM_NO"));
        return Ok(HeatInitial::Field(c));
    }
    let c = ei.req_concept("EVOL_THER")?;
    sites.insert("ETAT_INIT/EVOL_THER".into(), ei.span_of("EVOL_THER"));
    let r = c.result().map_err(|e| ei.err("EVOL_THER", e.msg))?;
    let k = if let Some(n) = ei.int("NUME_ORDRE") {
        r.steps
            .iter()
            .position(|s| s.nume_ordre == n)
            .ok_or_else(|| ei.err("NUME_ORDRE", format!("{} has no NUME_ORDRE {n}", c.label())))?
    } else if let Some(t) = ei.real("INST") {
        let prec = ei.real("PRECISION").unwrap_or(1e-6);
        let abs = ei.text("CRITERE") == Some("ABSOLU");
        r.steps
            .iter()
            .position(|s| (s.inst - t).abs() <= if abs { prec } else { prec * t.abs() })
            .ok_or_else(|| ei.err("INST", format!("{} has no instant {t}", c.label())))?
    } else {
        r.steps.len().checked_sub(1).ok_or_else(|| ei.err("EVOL_THER", format!("{} holds no step", c.label())))?
    };
    Ok(HeatInitial::Step(c.clone(), k))
}

/// THER_NON_LINE's Newton options: COMPORTEMENT (THER_NL), METHODE, NEWTON, RECH_LINEAIRE (Code_Aster
/// turns it on whenever NEWTON is given: its RESI_LINE_RELA and ITER_LINE_MAXI are the former place of
/// RECH_LINEAIRE's), CONVERGENCE and AFFICHAGE (display only).
fn newton(a: &Args) -> Result<(Convergence, Option<LineSearch>, usize)> {
    for occ in a.facts("COMPORTEMENT") {
        let rel = occ.text("RELATION").unwrap_or("THER_NL");
        if rel != "THER_NL" {
            return Err(occ.err("RELATION", format!("RELATION='{rel}' is not supported yet (THER_NL is)")));
        }
        let _ = (occ.text("TOUT"), occ.texts("GROUP_MA"));
    }
    if let Some(m) = a.text("METHODE").filter(|m| *m != "NEWTON") {
        return Err(a.err("METHODE", format!("METHODE='{m}' is not supported yet (NEWTON is)")));
    }
    if let Some(f) = a.fact("AFFICHAGE") {
        f.read_all();
    }
    let conv = Convergence::from_args(a)?;
    let nw = a.fact("NEWTON");
    // THER_NON_LINE's REAC_ITER is 0 when not given: the tangent of the step's start serves every
    // correction.
    let mut reac_iter = 0;
    if let Some(f) = nw {
        let _ = (f.text("PREDICTION"), f.text("MATRICE"));
        if f.int("REAC_INCR").is_some_and(|r| r != 1) {
            return Err(f.err("REAC_INCR", "only REAC_INCR=1 (the tangent at every step's start) is supported yet"));
        }
        reac_iter = f.int("REAC_ITER").map_or(0, |r| r.max(0) as usize);
    }
    let rl = a.fact("RECH_LINEAIRE");
    let line_search = if a.given("NEWTON") || rl.is_some() {
        let from = |k: &str, d: f64| {
            let num = |f: &Args| f.real(k).or_else(|| f.int(k).map(|i| i as f64));
            nw.and_then(num).or_else(|| rl.and_then(num)).unwrap_or(d)
        };
        if let Some(r) = rl {
            let _ = r.text("METHODE");
        }
        let ls = LineSearch {
            resi: from("RESI_LINE_RELA", 0.1),
            iter_max: from("ITER_LINE_MAXI", 3.0) as usize,
            rho_min: rl.and_then(|f| f.real("RHO_MIN")).unwrap_or(1e-2),
            rho_max: rl.and_then(|f| f.real("RHO_MAX")).unwrap_or(10.0),
            rho_excl: rl.and_then(|f| f.real("RHO_EXCL")).unwrap_or(0.9e-2),
        };
        (ls.iter_max > 0).then_some(ls)
    } else {
        None
    };
    Ok((conv, line_search, reac_iter))
}

/// The settings of THER_LINEAIRE / THER_NON_LINE on the thermal model `model`.
pub(super) fn read(a: &Args, command: Command, model: ConceptRef) -> Result<Settings> {
    let nonlinear = command == Command::TherNonLine;
    let _ = (a.text("TITRE"), a.int("INFO"));
    let mut sites = BTreeMap::new();
    sites.insert("MODELE".to_string(), a.span_of("MODELE"));
    for kw in ["CHAM_MATER", "EXCIT", "INCREMENT", "CONVERGENCE", "SOLVEUR", "ARCHIVAGE", "RESULTAT"] {
        if a.declares(kw) && a.given(kw) {
            sites.insert(kw.to_string(), a.span_of(kw));
        }
    }
    let chmat = a.req_concept("CHAM_MATER")?;
    let cara_elem = a.concept("CARA_ELEM");
    if let Some(c) = &cara_elem {
        let ca = c.cara_elem().map_err(|e| a.err("CARA_ELEM", e.msg))?;
        if !Rc::ptr_eq(&ca.model, &model) {
            return Err(a.err("CARA_ELEM", format!("{} is defined on another model ({})", c.label(), ca.model.label())));
        }
    }
    if super::has_varc(&chmat) {
        return Err(a.err("CHAM_MATER", "AFFE_VARC in a thermal computation is not supported yet"));
    }
    let mut excit = Vec::new();
    for occ in a.facts("EXCIT") {
        let _ = occ.text("TYPE_CHARGE"); // FIXE_CSTE, its only value
        let load = occ.req_concept("CHARGE")?;
        {
            let data = load.data();
            let ConceptData::Load(Load { model: lm, items, .. }) = &*data else {
                return Err(occ.err("CHARGE", format!("{} is not a thermal load", load.label())));
            };
            if !Rc::ptr_eq(lm, &model) {
                return Err(
                    occ.err("CHARGE", format!("load {} is defined on another model ({})", load.label(), lm.label()))
                );
            }
            if let Some(k) = nonlinear_item(items).filter(|_| !nonlinear) {
                return Err(occ.err(
                    "CHARGE",
                    format!("load {}: {k} depends on the temperature: THER_NON_LINE computes it", load.label()),
                ));
            }
        }
        let fonc_mult = occ.concept("FONC_MULT");
        excit.push(Excit { load, fonc_mult, span: occ.span, fonc_mult_span: occ.span_of("FONC_MULT") });
    }
    let (conv, line_search, reac_iter) =
        if nonlinear { newton(a)? } else { (Convergence { span: a.span, ..Convergence::default() }, None, 1) };
    // THER_NON_LINE without TYPE_CALCUL, INCREMENT and a transient ETAT_INIT is steady.
    let steady = a.text("TYPE_CALCUL") == Some("STAT")
        || (nonlinear
            && !a.given("TYPE_CALCUL")
            && !a.has("INCREMENT")
            && a.fact("ETAT_INIT").is_none_or(|e| e.has("STAT") || e.has("STATIONNAIRE")));
    let theta = if steady {
        None
    } else {
        Some(match (a.fact("SCHEMA_TEMPS"), a.real("PARM_THETA")) {
            (_, Some(t)) => t,
            (Some(s), None) => {
                let _ = s.text("SCHEMA");
                s.real("THETA").unwrap_or(0.57)
            }
            (None, None) => 0.57,
        })
    };
    let (mut initial_instant, mut instants) = instants(a, steady)?;
    // RESULTAT (reused): the computation goes on from the result's last instant, its steps numbered after
    // its last one; the initial state is stored again unless it is ETAT_INIT's EVOL_THER.
    let mut reuse = None;
    let mut store_initial = true;
    if let Some(rc) = a.concept("RESULTAT") {
        let r = rc.result().map_err(|e| a.err("RESULTAT", e.msg))?;
        let last = r.steps.last().ok_or_else(|| a.err("RESULTAT", format!("{} holds no step", rc.label())))?;
        let same = a.fact("ETAT_INIT").and_then(|e| e.concept("EVOL_THER")).is_some_and(|e| Rc::ptr_eq(&e, &rc));
        store_initial = !same;
        if !steady {
            initial_instant = Some(last.inst);
            instants.retain(|&t| t > last.inst + 1e-6 * last.inst.abs().max(1e-300));
        }
        reuse = Some((rc.clone(), last.nume_ordre + i64::from(same)));
    }
    let initial = if steady {
        if let Some(e) = a.fact("ETAT_INIT") {
            e.read_all();
        }
        HeatInitial::Steady
    } else {
        initial_state(a, &mut sites)?
    };
    // The driver's instants: the initial one first; a steady computation starts at its first instant,
    // which it computes like the others.
    let times: Vec<f64> = match initial_instant {
        Some(t0) => std::iter::once(t0).chain(instants.iter().copied()).collect(),
        None => std::iter::once(instants[0]).chain(instants.iter().copied()).collect(),
    };
    if times.len() < 2 && initial_instant.is_some() && !matches!(initial, HeatInitial::Steady) {
        return Err(a.err("INCREMENT", "no instant to compute after the initial one"));
    }
    let archive = Archive::from_args_keeping(a, &times, nonlinear)?;
    Ok(Settings {
        command,
        physics: PhysicsKind::Thermal,
        span: a.span,
        sites,
        model,
        chmat: Some(chmat),
        cara_elem,
        excit,
        times,
        subdivision: None,
        conv,
        newton_note: None,
        solveur: solveur(a)?,
        archive: Some(archive),
        initial: None,
        behaviours: Vec::new(),
        theta: 1.0,
        schema_thm: false,
        contact: None,
        sief: false,
        line_search,
        matrices: Default::default(),
        reac_iter,
        heat: Some(HeatSettings { nonlinear, theta, initial, reuse, store_initial }),
    })
}
