//! Older spellings Code_Aster still accepts, rewritten into the current ones before a call is checked.
//!
//! Code_Aster's catalogue keeps, beside a command's schema, a function that turns deprecated keywords
//! into their replacements before checking (`compat_syntax`: `PARM_THETA=0.5` becomes
//! `SCHEMA_TEMPS=_F(SCHEMA='THETA', THETA=0.5)`, `LIAISON='ENCASTRE'` becomes
//! `BLOCAGE=('DEPLACEMENT', 'ROTATION')`, ...). These are the same renames, written for the checked
//! schema. The user's values are never changed in place: a rewritten factor occurrence is a new
//! dictionary. The hand-written schemas of the stages see the call as written.

use crate::interp::{Dict, KwArg, Value};

/// The commands whose COMPORTEMENT takes RESI_INTE for the older RESI_INTE_MAXI / RESI_INTE_RELA.
const WITH_COMPORTEMENT: &[&str] = &[
    "CALCUL",
    "CALC_ESSAI_GEOMECA",
    "CALC_FORC_NONL",
    "CALC_PRECONT",
    "CALC_STAB_PENTE",
    "CREA_RESU",
    "DYNA_LINE",
    "DYNA_NON_LINE",
    "DYNA_VIBRA",
    "LIRE_RESU",
    "MACR_ECREVISSE",
    "MECA_NON_LINE",
    "PRE_SEISME_NONL",
    "SECH_NON_LINE",
    "SIMU_POINT_MAT",
    "STAT_NON_LINE",
    "TEST_COMPOR",
    "THER_NON_LINE",
];

/// Rewrite the older spellings of a call to `cmd`.
pub fn rewrite(cmd: &str, kw: &mut Vec<KwArg>) {
    if WITH_COMPORTEMENT.contains(&cmd) {
        map_occurrences(kw, "COMPORTEMENT", |d| {
            for old in ["RESI_INTE_MAXI", "RESI_INTE_RELA"] {
                if let Some(v) = take(d, old) {
                    set(d, "RESI_INTE", v);
                }
            }
        });
    }
    match cmd {
        "AFFE_CHAR_MECA" | "AFFE_CHAR_MECA_C" | "AFFE_CHAR_MECA_F" => map_occurrences(kw, "DDL_IMPO", |d| {
            if let Some(v) = take(d, "LIAISON") {
                if v.as_str() == Some("ENCASTRE") {
                    set(d, "BLOCAGE", Value::tuple(vec![Value::str("DEPLACEMENT"), Value::str("ROTATION")]));
                }
            }
        }),
        "DEBUT" | "POURSUITE" => {
            remove(kw, "PAR_LOT");
            remove(kw, "FORMAT_HDF");
            map_occurrences(kw, "DEBUG", |d| {
                take(d, "HIST_ETAPE");
            });
            if let Some(k) = kw.iter_mut().find(|k| k.name == "CODE") {
                if matches!(k.value, Value::Dict(_)) {
                    k.value = Value::str("OUI");
                }
            }
        }
        "FIN" => {
            remove(kw, "FORMAT_HDF");
            remove(kw, "PROC0");
        }
        "DEFI_MATERIAU" if !has(kw, "BETON_DESORP") => {
            let mut moved = None;
            map_occurrences(kw, "ELAS_FO", |d| {
                if moved.is_none() {
                    moved = take(d, "FONC_DESORP");
                }
            });
            if let Some(v) = moved {
                let mut d = Dict::default();
                d.set(Value::str("FONC_DESORP"), v);
                push(kw, "BETON_DESORP", Value::dict(d));
            }
        }
        "DETRUIRE" => {
            if let Some(v) = remove(kw, "CONCEPT") {
                let mut names = Vec::new();
                for occ in occurrences(&v) {
                    if let Value::Dict(d) = occ {
                        if let Some(n) = d.borrow().get(&Value::str("NOM")) {
                            names.extend(items(n));
                        }
                    }
                }
                push(kw, "NOM", Value::list(names));
            }
            remove(kw, "OBJET");
        }
        "LIRE_FONCTION" => {
            if let Some(v) = remove(kw, "SEPAR") {
                if !has(kw, "SEPARATEUR") && matches!(v.as_str(), Some("None" | "," | ";" | "/")) {
                    push(kw, "SEPARATEUR", v);
                }
            }
        }
        "MECA_STATIQUE" => result_from_reuse(kw),
        "MODI_MAILLAGE" => {
            for (old, inner) in [("ORIE_PEAU_2D", "GROUP_MA_SURF"), ("ORIE_PEAU_3D", "GROUP_MA_VOLU")] {
                if let Some(v) = remove(kw, old) {
                    let renamed: Vec<Value> = occurrences(&v)
                        .into_iter()
                        .map(|o| {
                            let mut d = copy(&o);
                            if let Some(x) = take(&mut d, "GROUP_MA") {
                                set(&mut d, "GROUP_MA_PEAU", x);
                            }
                            if let Some(x) = take(&mut d, inner) {
                                set(&mut d, "GROUP_MA_INTERNE", x);
                            }
                            Value::dict(d)
                        })
                        .collect();
                    push(kw, "ORIE_PEAU", Value::list(renamed));
                }
            }
        }
        "PROJ_CHAMP" => {
            if let Some(v) = remove(kw, "PROL_ZERO") {
                if v.as_str() == Some("OUI") {
                    push(kw, "PROL_VALE", Value::Float(0.0));
                }
            }
        }
        "THER_LINEAIRE" | "THER_NON_LINE" => {
            result_from_reuse(kw);
            stationnaire(kw);
            if cmd == "THER_NON_LINE" && !has(kw, "TYPE_CALCUL") {
                stationary_without_increment(kw);
            }
            transient_default_state(kw);
            if cmd == "THER_NON_LINE" && has(kw, "NEWTON") {
                let mut line = Dict::default();
                if let Some(Value::Dict(d)) = value(kw, "RECH_LINEAIRE").and_then(|v| occurrences(v).into_iter().next())
                {
                    line = d.borrow().clone();
                }
                map_occurrences(kw, "NEWTON", |d| {
                    for key in ["RESI_LINE_RELA", "ITER_LINE_MAXI"] {
                        if let Some(v) = take(d, key) {
                            line.set(Value::str(key), v);
                        }
                    }
                });
                remove(kw, "RECH_LINEAIRE");
                push(kw, "RECH_LINEAIRE", Value::dict(line));
            }
            if let Some(theta) = remove(kw, "PARM_THETA") {
                let mut d = Dict::default();
                d.set(Value::str("SCHEMA"), Value::str("THETA"));
                d.set(Value::str("THETA"), theta);
                push(kw, "SCHEMA_TEMPS", Value::dict(d));
            }
        }
        "SECH_NON_LINE" => {
            result_from_reuse(kw);
            stationnaire(kw);
            if !has(kw, "TYPE_CALCUL") {
                stationary_without_increment(kw);
            }
            if value(kw, "TYPE_CALCUL").and_then(Value::as_str).is_none_or(|t| t == "TRAN") {
                if !has(kw, "ETAT_INIT") {
                    push(kw, "ETAT_INIT", stat_oui());
                }
                let theta = value(kw, "SCHEMA_TEMPS").and_then(|v| occurrences(v).into_iter().next()).and_then(|o| {
                    if let Value::Dict(d) = o {
                        d.borrow().get(&Value::str("THETA")).cloned()
                    } else {
                        None
                    }
                });
                if let Some(t) = theta {
                    push(kw, "PARM_THETA", t);
                    remove(kw, "SCHEMA_TEMPS");
                }
            }
        }
        _ => {}
    }
}

/// No TYPE_CALCUL, a stationary initial state (or none) and no INCREMENT: the older spelling of a
/// stationary computation, TYPE_CALCUL='STAT'.
fn stationary_without_increment(kw: &mut Vec<KwArg>) {
    let stat_init = match value(kw, "ETAT_INIT") {
        None => true,
        Some(v) => occurrences(v).first().map(|o| dict_has(o, "STAT")).unwrap_or(false),
    };
    if stat_init && !has(kw, "INCREMENT") {
        push(kw, "TYPE_CALCUL", Value::str("STAT"));
        remove(kw, "ETAT_INIT");
    }
}

/// `reuse=R` without RESULTAT: RESULTAT=R.
fn result_from_reuse(kw: &mut Vec<KwArg>) {
    if !has(kw, "RESULTAT") {
        if let Some(r) = value(kw, "reuse").cloned() {
            push(kw, "RESULTAT", r);
        }
    }
}

/// ETAT_INIT=_F(STATIONNAIRE=...) is ETAT_INIT=_F(STAT='OUI').
fn stationnaire(kw: &mut [KwArg]) {
    map_occurrences(kw, "ETAT_INIT", |d| {
        if take(d, "STATIONNAIRE").is_some() {
            set(d, "STAT", Value::str("OUI"));
        }
    });
}

/// A transient computation without initial state starts from the steady state.
fn transient_default_state(kw: &mut Vec<KwArg>) {
    let transient = value(kw, "TYPE_CALCUL").and_then(Value::as_str).is_none_or(|t| t == "TRAN");
    if transient && !has(kw, "ETAT_INIT") {
        push(kw, "ETAT_INIT", stat_oui());
    }
}

fn stat_oui() -> Value {
    let mut d = Dict::default();
    d.set(Value::str("STAT"), Value::str("OUI"));
    Value::dict(d)
}

// ------------------------------------------------------------------ on keyword lists and _F values

fn has(kw: &[KwArg], name: &str) -> bool {
    kw.iter().any(|k| k.name == name && !matches!(k.value, Value::None))
}

fn value<'a>(kw: &'a [KwArg], name: &str) -> Option<&'a Value> {
    kw.iter().find(|k| k.name == name && !matches!(k.value, Value::None)).map(|k| &k.value)
}

fn remove(kw: &mut Vec<KwArg>, name: &str) -> Option<Value> {
    let i = kw.iter().position(|k| k.name == name)?;
    Some(kw.remove(i).value).filter(|v| !matches!(v, Value::None))
}

/// Add a keyword, located at the call's first keyword (or nowhere for an empty call).
fn push(kw: &mut Vec<KwArg>, name: &str, v: Value) {
    let span = kw.first().map(|k| k.span).unwrap_or_default();
    kw.retain(|k| k.name != name);
    kw.push(KwArg { name: name.to_string(), value: v, span });
}

/// The occurrences of a factor keyword's value (one `_F` or a list of them).
fn occurrences(v: &Value) -> Vec<Value> {
    match v {
        Value::Tuple(_) | Value::List(_) => v.iter_items().unwrap_or_default(),
        other => vec![other.clone()],
    }
}

fn items(v: &Value) -> Vec<Value> {
    match v {
        Value::Tuple(_) | Value::List(_) => v.iter_items().unwrap_or_default(),
        other => vec![other.clone()],
    }
}

fn copy(v: &Value) -> Dict {
    match v {
        Value::Dict(d) => d.borrow().clone(),
        _ => Dict::default(),
    }
}

fn dict_has(v: &Value, key: &str) -> bool {
    matches!(v, Value::Dict(d) if d.borrow().get(&Value::str(key)).is_some_and(|x| !matches!(x, Value::None)))
}

fn take(d: &mut Dict, key: &str) -> Option<Value> {
    d.remove(&Value::str(key)).filter(|v| !matches!(v, Value::None))
}

fn set(d: &mut Dict, key: &str, v: Value) {
    d.set(Value::str(key), v);
}

/// Rewrite every occurrence of factor keyword `name` with `f`, on copies.
fn map_occurrences(kw: &mut [KwArg], name: &str, mut f: impl FnMut(&mut Dict)) {
    let Some(k) = kw.iter_mut().find(|k| k.name == name) else { return };
    if !matches!(k.value, Value::Dict(_) | Value::List(_) | Value::Tuple(_)) {
        return;
    }
    let occ: Vec<Value> = occurrences(&k.value)
        .into_iter()
        .map(|o| match o {
            Value::Dict(_) => {
                let mut d = copy(&o);
                f(&mut d);
                Value::dict(d)
            }
            other => other,
        })
        .collect();
    k.value = if matches!(k.value, Value::Dict(_)) { occ.into_iter().next().unwrap() } else { Value::list(occ) };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kw(name: &str, v: Value) -> KwArg {
        KwArg { name: name.into(), value: v, span: Default::default() }
    }

    #[test]
    fn parm_theta_becomes_schema_temps() {
        let mut k = vec![kw("PARM_THETA", Value::Float(0.57))];
        rewrite("THER_LINEAIRE", &mut k);
        let names: Vec<&str> = k.iter().map(|k| k.name.as_str()).collect();
        assert_eq!(names, ["ETAT_INIT", "SCHEMA_TEMPS"]);
        let Value::Dict(d) = &k[1].value else { panic!() };
        assert_eq!(
            d.borrow().get(&Value::str("SCHEMA")).and_then(|v| v.as_str().map(String::from)),
            Some("THETA".into())
        );
    }

    #[test]
    fn rewritten_occurrences_are_copies() {
        let mut occ = Dict::default();
        occ.set(Value::str("LIAISON"), Value::str("ENCASTRE"));
        let shared = Value::dict(occ);
        let mut k = vec![kw("DDL_IMPO", shared.clone())];
        rewrite("AFFE_CHAR_MECA", &mut k);
        let Value::Dict(new) = &k[0].value else { panic!() };
        assert!(new.borrow().get(&Value::str("BLOCAGE")).is_some());
        let Value::Dict(old) = &shared else { panic!() };
        assert!(old.borrow().get(&Value::str("LIAISON")).is_some(), "the user's _F is unchanged");
    }
}
