//! Functions, nappes, lists and formulas: DEFI_*, CALC_FONCTION,
//! CALC_FONC_INTERP, IMPR_FONCTION, LIRE_FONCTION, RECU_FONCTION.

use crate::catalog::args::{Args, Val};
use crate::concepts::function::{Function, Interp, Nappe, Prol};
use crate::concepts::table::Table;
use crate::concepts::Formula as FormulaConcept;
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::interp::{Formula, Value};
use crate::stages::select::filtered;
use crate::stages::Ctx;
use crate::text::float_repr;

// ------------------------------------------------------------------ helpers

fn interp_of(a: &Args, kw: &str, default: (Interp, Interp)) -> (Interp, Interp) {
    let v = a.texts(kw);
    match v.as_slice() {
        [] => default,
        [one] => {
            let i = Interp::parse(one).unwrap_or(Interp::Lin);
            (i, i)
        }
        [x, y, ..] => (Interp::parse(x).unwrap_or(Interp::Lin), Interp::parse(y).unwrap_or(Interp::Lin)),
    }
}

fn prol_of(a: &Args, kw: &str, default: Prol) -> Prol {
    a.text(kw).and_then(Prol::parse).unwrap_or(default)
}

/// Keyword-given attributes override those inherited from `base`.
fn function_from(a: &Args, base: Option<&Function>, x: Vec<f64>, y: Vec<f64>) -> Result<Function> {
    let (np, nr, it, pg, pd) = match base {
        Some(b) => (b.nom_para.clone(), b.nom_resu.clone(), b.interp, b.prol_gauche, b.prol_droite),
        None => ("TOUTPARA".into(), "TOUTRESU".into(), (Interp::Lin, Interp::Lin), Prol::Exclu, Prol::Exclu),
    };
    Function::new(
        a.text_if_declared("NOM_PARA").unwrap_or(&np),
        a.text_if_declared("NOM_RESU").unwrap_or(&nr),
        x,
        y,
        interp_of(a, "INTERPOL", it),
        prol_of(a, "PROL_GAUCHE", pg),
        prol_of(a, "PROL_DROITE", pd),
    )
    .map_err(|e| e.at(a.span))
}

fn pairs(a: &Args, kw: &str) -> Result<(Vec<f64>, Vec<f64>)> {
    let v = a.reals(kw);
    if !v.len().is_multiple_of(2) {
        return Err(a.err(kw, format!("{} values given: VALE needs (x, y) pairs", v.len())));
    }
    Ok((v.iter().step_by(2).copied().collect(), v.iter().skip(1).step_by(2).copied().collect()))
}

pub fn list_of(c: &ConceptRef) -> Result<Vec<f64>> {
    match &*c.data() {
        ConceptData::ListReal(v) => Ok(v.clone()),
        ConceptData::ListInt(v) => Ok(v.iter().map(|i| *i as f64).collect()),
        _ => Err(Error::runtime(format!("{} is not a list of reals", c.label()))),
    }
}

fn sort_pairs(x: Vec<f64>, y: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let mut p: Vec<(f64, f64)> = x.into_iter().zip(y).collect();
    p.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    p.into_iter().unzip()
}

/// Sorted union of abscissas (exact duplicates merged).
fn union(sets: &[&[f64]]) -> Vec<f64> {
    let mut all: Vec<f64> = sets.iter().flat_map(|s| s.iter().copied()).collect();
    all.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    all.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300));
    all
}

/// Anything that can be evaluated at one abscissa.
enum F1<'a> {
    Tab(&'a Function),
    Formula(&'a FormulaConcept),
}

impl F1<'_> {
    fn eval(&self, x: f64) -> Result<f64> {
        match self {
            F1::Tab(f) => f.eval(x),
            F1::Formula(f) => f.eval(&[x]),
        }
    }
}

// ------------------------------------------------------------------ DEFI_*

pub fn defi_constante(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    Ok(Some(ConceptData::Function(Function::constant(a.text("NOM_RESU").unwrap_or("TOUTRESU"), a.req_real("VALE")?))))
}

pub fn defi_fonction(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if a.has("VALE_C") {
        return Err(a.err("VALE_C", "complex functions are not supported yet"));
    }
    let (x, y) = if a.has("VALE") {
        pairs(a, "VALE")?
    } else if a.has("ABSCISSE") {
        let (x, y) = (a.reals("ABSCISSE"), a.reals("ORDONNEE"));
        if x.len() != y.len() {
            return Err(a.err("ORDONNEE", format!("{} abscissas but {} ordinates", x.len(), y.len())));
        }
        (x, y)
    } else {
        let x = list_of(&a.req_concept("VALE_PARA")?)?;
        let y = list_of(&a.req_concept("VALE_FONC")?)?;
        if x.len() != y.len() {
            return Err(a.err("VALE_FONC", format!("{} abscissas but {} ordinates", x.len(), y.len())));
        }
        (x, y)
    };
    let (x, y) = if a.text("VERIF") == Some("NON") { sort_pairs(x, y) } else { (x, y) };
    Ok(Some(ConceptData::Function(function_from(a, None, x, y)?)))
}

pub fn defi_nappe(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let params = a.reals("PARA");
    let nom_para_fonc = a.text("NOM_PARA_FONC").unwrap_or("TOUTPARA").to_string();
    let mut functions = Vec::new();
    if a.has("FONCTION") {
        for c in a.concepts("FONCTION") {
            match &*c.data() {
                ConceptData::Function(f) => functions.push(f.clone()),
                _ => return Err(a.err("FONCTION", format!("{} is not a tabulated function", c.label()))),
            }
        }
    } else {
        for occ in a.facts("DEFI_FONCTION") {
            let (x, y) = pairs(occ, "VALE")?;
            let f = Function::new(
                &nom_para_fonc,
                a.text("NOM_RESU").unwrap_or("TOUTRESU"),
                x,
                y,
                interp_of(occ, "INTERPOL", interp_of(a, "INTERPOL_FONC", (Interp::Lin, Interp::Lin))),
                prol_of(occ, "PROL_GAUCHE", prol_of(a, "PROL_GAUCHE_FONC", Prol::Exclu)),
                prol_of(occ, "PROL_DROITE", prol_of(a, "PROL_DROITE_FONC", Prol::Exclu)),
            )
            .map_err(|e| e.at(occ.span))?;
            functions.push(f);
        }
    }
    let nom_para_fonc = functions.first().map(|f| f.nom_para.clone()).unwrap_or(nom_para_fonc);
    Ok(Some(ConceptData::Nappe(nappe_of(a, &nom_para_fonc, params, functions)?)))
}

/// The nappe of functions at the parameter values `params`: NOM_PARA, NOM_RESU, INTERPOL and PROL_* of
/// the command (DEFI_NAPPE, LIRE_FONCTION TYPE='NAPPE').
fn nappe_of(a: &Args, nom_para_fonc: &str, params: Vec<f64>, functions: Vec<Function>) -> Result<Nappe> {
    Nappe::new(
        a.req_text("NOM_PARA")?,
        nom_para_fonc,
        a.text("NOM_RESU").unwrap_or("TOUTRESU"),
        params,
        functions,
        interp_of(a, "INTERPOL", (Interp::Lin, Interp::Lin)),
        prol_of(a, "PROL_GAUCHE", Prol::Exclu),
        prol_of(a, "PROL_DROITE", Prol::Exclu),
    )
    .map_err(|e| e.at(a.span))
}

/// The most values DEFI_LIST_REEL and DEFI_LIST_ENTI make (80 MB of reals): more is a mistake in
/// NOMBRE or PAS, which would otherwise exhaust the memory or the time of the run.
const MAX_LIST: usize = 10_000_000;

fn list_from_intervals(a: &Args, start: f64, int: bool) -> Result<Vec<f64>> {
    if !start.is_finite() {
        return Err(a.err("DEBUT", format!("DEBUT={} is not a finite number", float_repr(start))));
    }
    let mut out = vec![start];
    let mut cur = start;
    for occ in a.facts("INTERVALLE") {
        let end = occ.req_real("JUSQU_A")?;
        if !end.is_finite() {
            return Err(occ.err("JUSQU_A", format!("JUSQU_A={} is not a finite number", float_repr(end))));
        }
        if end <= cur {
            return Err(occ.err("JUSQU_A", format!("the interval must end after its start ({end} <= {cur})")));
        }
        let room = MAX_LIST - out.len();
        let n = match (occ.int("NOMBRE"), occ.real("PAS")) {
            (Some(n), _) if n as u64 > room as u64 => {
                return Err(occ.err("NOMBRE", format!("NOMBRE={n} makes a list of more than {MAX_LIST} values")))
            }
            (Some(n), _) => n,
            (None, Some(p)) if p > 0.0 && p.is_finite() => {
                let n = ((end - cur) / p).round();
                if n > room as f64 {
                    return Err(occ.err(
                        "PAS",
                        format!("PAS={} makes a list of more than {MAX_LIST} values in [{cur}, {end}]", float_repr(p)),
                    ));
                }
                if ((cur + n * p) - end).abs() > 1e-6 * p.abs().max(1e-300) {
                    return Err(occ.err("PAS", format!("the step {p} does not divide the interval [{cur}, {end}]")));
                }
                n as i64
            }
            _ => return Err(occ.err("PAS", "the step must be a positive finite number")),
        };
        let step = (end - cur) / n as f64;
        for k in 1..n {
            let v = cur + k as f64 * step;
            out.push(if int { v.round() } else { v });
        }
        out.push(end);
        cur = end;
    }
    Ok(out)
}

pub fn defi_list_reel(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let v = if a.has("VALE") {
        let v = a.reals("VALE");
        if let Some(w) = v.windows(2).position(|w| w[1] <= w[0]) {
            return Err(a.err("VALE", format!("the values must be strictly increasing ({} then {})", v[w], v[w + 1])));
        }
        v
    } else {
        list_from_intervals(a, a.req_real("DEBUT")?, false)?
    };
    Ok(Some(ConceptData::ListReal(v)))
}

pub fn defi_list_enti(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let v = if a.has("VALE") {
        a.ints("VALE")
    } else {
        let start = a.int("DEBUT").ok_or_else(|| a.err("DEBUT", "an integer is required"))? as f64;
        list_from_intervals(a, start, true)?.into_iter().map(|x| x as i64).collect()
    };
    Ok(Some(ConceptData::ListInt(v)))
}

pub fn formule(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if a.has("VALE_C") {
        return Err(a.err("VALE_C", "complex formulas are not supported yet"));
    }
    let text = a.req_text("VALE")?;
    let mut context = Vec::new();
    for item in &a.items {
        if matches!(item.name.as_str(), "VALE" | "VALE_C" | "NOM_PARA") {
            continue;
        }
        for v in a.vals(&item.name) {
            let value = match v {
                Val::Callable(v) => v.clone(),
                Val::Concept(c) => Value::Concept(c.clone()),
                _ => continue,
            };
            context.push((item.name.clone(), value));
        }
    }
    let f =
        Formula::new(text, a.texts("NOM_PARA"), context, ctx.globals.clone()).map_err(|e| e.at(a.span_of("VALE")))?;
    Ok(Some(ConceptData::Formula(f.into_concept())))
}

// ------------------------------------------------------------------ CALC_FONCTION

/// A nappe or function input, seen as a nappe (a function is a one-parameter nappe).
enum Input {
    F(Function),
    N(Nappe),
}

fn inputs(occ: &Args) -> Result<Vec<Input>> {
    occ.concepts("FONCTION")
        .iter()
        .map(|c| match &*c.data() {
            ConceptData::Function(f) => Ok(Input::F(f.clone())),
            ConceptData::Nappe(n) => Ok(Input::N(n.clone())),
            _ => Err(occ.err("FONCTION", format!("{} is not a tabulated function or nappe", c.label()))),
        })
        .collect()
}

/// The function of a nappe at parameter `p`: tabulated when p is one of its
/// values, else interpolated (or extended) between its neighbours.
fn nappe_at(n: &Nappe, p: f64) -> Result<Function> {
    if let Some(i) = n.params.iter().position(|&q| (q - p).abs() <= 1e-12 * q.abs().max(1.0)) {
        return Ok(n.functions[i].clone());
    }
    let xs: Vec<&[f64]> = n.functions.iter().map(|f| f.x.as_slice()).collect();
    let x = union(&xs);
    let y: Vec<f64> = x.iter().map(|&xv| n.eval(p, xv)).collect::<Result<_>>()?;
    let f0 = &n.functions[0];
    Function::new(&f0.nom_para, &f0.nom_resu, x, y, f0.interp, f0.prol_gauche, f0.prol_droite)
}

/// Combine functions point by point on the union of their abscissas.
fn pointwise(fs: &[Function], list: Option<&[f64]>, op: &dyn Fn(&[f64]) -> f64) -> Result<(Vec<f64>, Vec<f64>)> {
    let x = match list {
        Some(l) => l.to_vec(),
        None => union(&fs.iter().map(|f| f.x.as_slice()).collect::<Vec<_>>()),
    };
    let mut y = Vec::with_capacity(x.len());
    for &xv in &x {
        let vals: Vec<f64> = fs.iter().map(|f| f.eval(xv)).collect::<Result<_>>()?;
        y.push(op(&vals));
    }
    Ok((x, y))
}

fn fractile(vals: &[f64], q: f64) -> f64 {
    let mut v = vals.to_vec();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    let pos = q * (v.len() - 1) as f64;
    let i = pos.floor() as usize;
    if i + 1 >= v.len() {
        return v[v.len() - 1];
    }
    v[i] + (pos - i as f64) * (v[i + 1] - v[i])
}

/// Apply `op` to functions, or parameter by parameter to nappes.
fn combine(a: &Args, ins: Vec<Input>, op: &dyn Fn(&[f64]) -> f64) -> Result<ConceptData> {
    let list = match a.concept("LIST_PARA") {
        Some(c) => Some(c.reals()?),
        None => None,
    };
    if ins.iter().all(|i| matches!(i, Input::F(_))) {
        let fs: Vec<Function> = ins.into_iter().map(|i| if let Input::F(f) = i { f } else { unreachable!() }).collect();
        let (x, y) = pointwise(&fs, list.as_deref(), op).map_err(|e| e.at(a.span))?;
        return Ok(ConceptData::Function(function_from(a, Some(&fs[0]), x, y)?));
    }
    let nappes: Vec<Nappe> = ins
        .into_iter()
        .map(|i| match i {
            Input::N(n) => Ok(n),
            Input::F(_) => Err(a.err("FONCTION", "functions and nappes cannot be mixed")),
        })
        .collect::<Result<_>>()?;
    let params = union(&nappes.iter().map(|n| n.params.as_slice()).collect::<Vec<_>>());
    let first = &nappes[0];
    let f0 = &first.functions[0];
    let mut functions = Vec::new();
    for &p in &params {
        let fs: Vec<Function> =
            nappes.iter().map(|n| nappe_at(n, p)).collect::<Result<_>>().map_err(|e| e.at(a.span))?;
        let (x, y) = pointwise(&fs, list.as_deref(), op).map_err(|e| e.at(a.span))?;
        functions.push(
            Function::new(
                a.text("NOM_PARA_FONC").unwrap_or(&f0.nom_para),
                &f0.nom_resu,
                x,
                y,
                interp_of(a, "INTERPOL_FONC", f0.interp),
                prol_of(a, "PROL_GAUCHE_FONC", f0.prol_gauche),
                prol_of(a, "PROL_DROITE_FONC", f0.prol_droite),
            )
            .map_err(|e| e.at(a.span))?,
        );
    }
    let n = Nappe::new(
        a.text("NOM_PARA").unwrap_or(&first.nom_para),
        &functions[0].nom_para.clone(),
        a.text("NOM_RESU").unwrap_or(&first.nom_resu),
        params,
        functions,
        interp_of(a, "INTERPOL", first.interp),
        prol_of(a, "PROL_GAUCHE", first.prol_gauche),
        prol_of(a, "PROL_DROITE", first.prol_droite),
    )
    .map_err(|e| e.at(a.span))?;
    Ok(ConceptData::Nappe(n))
}

pub fn calc_fonction(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if a.has("COMB") {
        let occs = a.facts("COMB");
        let mut ins = Vec::new();
        let mut coefs = Vec::new();
        for o in occs {
            let c = o.req_concept("FONCTION")?;
            let data = c.data();
            ins.push(match &*data {
                ConceptData::Function(f) => Input::F(f.clone()),
                ConceptData::Nappe(n) => Input::N(n.clone()),
                _ => {
                    return Err(o.err(
                        "FONCTION",
                        format!(
                            "{} is not a tabulated function or nappe (formulas are not supported in COMB yet)",
                            c.label()
                        ),
                    ))
                }
            });
            coefs.push(o.req_real("COEF")?);
        }
        let op = move |v: &[f64]| v.iter().zip(&coefs).map(|(x, c)| x * c).sum();
        return Ok(Some(combine(a, ins, &op)?));
    }
    if let Some(o) = a.fact("ENVELOPPE") {
        let sup = o.text("CRITERE") != Some("INF");
        let op = move |v: &[f64]| {
            if sup {
                v.iter().cloned().fold(f64::MIN, f64::max)
            } else {
                v.iter().cloned().fold(f64::MAX, f64::min)
            }
        };
        return Ok(Some(combine(a, inputs(o)?, &op)?));
    }
    if let Some(o) = a.fact("FRACTILE") {
        let q = o.req_real("FRACT")?;
        let op = move |v: &[f64]| fractile(v, q);
        return Ok(Some(combine(a, inputs(o)?, &op)?));
    }
    if let Some(o) = a.fact("MOYENNE") {
        let op = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        return Ok(Some(combine(a, inputs(o)?, &op)?));
    }
    if let Some(o) = a.fact("ABS") {
        let c = o.req_concept("FONCTION")?;
        let ins = match &*c.data() {
            ConceptData::Function(f) => vec![Input::F(f.clone())],
            ConceptData::Nappe(n) => vec![Input::N(n.clone())],
            _ => return Err(o.err("FONCTION", format!("{} is not a tabulated function or nappe", c.label()))),
        };
        let op = |v: &[f64]| v[0].abs();
        return Ok(Some(combine(a, ins, &op)?));
    }
    for op in ["INVERSE", "PUISSANCE", "DERIVE", "INTEGRE"] {
        if a.has(op) {
            return Err(a.err(op, format!("CALC_FONCTION {op} is not supported yet")));
        }
    }
    Err(Error::runtime("CALC_FONCTION: no operation given").at(a.span))
}

pub fn calc_fonc_interp(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let c = a.req_concept("FONCTION")?;
    let x = match a.concept("LIST_PARA") {
        Some(l) => l.reals()?,
        None => a.reals("VALE_PARA"),
    };
    let data = c.data();
    let (f1, base) = match &*data {
        ConceptData::Function(f) => (F1::Tab(f), Some(f.clone())),
        ConceptData::Formula(f) if f.nom_para.len() == 1 => (F1::Formula(f), None),
        ConceptData::Nappe(_) | ConceptData::Formula(_) => {
            return Err(
                a.err("FONCTION", "CALC_FONC_INTERP of a nappe or of a formula of two parameters is not supported yet")
            )
        }
        _ => return Err(a.err("FONCTION", format!("{} is not a function", c.label()))),
    };
    let y: Vec<f64> = x.iter().map(|&v| f1.eval(v)).collect::<Result<_>>().map_err(|e| e.at(a.span))?;
    let base = base.or_else(|| {
        if let ConceptData::Formula(f) = &*data {
            Function::new(
                &f.nom_para[0],
                "TOUTRESU",
                vec![0.0],
                vec![0.0],
                (Interp::Lin, Interp::Lin),
                Prol::Exclu,
                Prol::Exclu,
            )
            .ok()
        } else {
            None
        }
    });
    Ok(Some(ConceptData::Function(function_from(a, base.as_ref(), x, y)?)))
}

// ------------------------------------------------------------------ IMPR / LIRE / RECU

fn tabulated(c: &ConceptRef) -> Result<Function> {
    match &*c.data() {
        ConceptData::Function(f) => Ok(f.clone()),
        _ => Err(Error::runtime(format!("{} is not a tabulated function", c.label()))),
    }
}

pub fn impr_fonction(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let format = a.text("FORMAT").unwrap_or("TABLEAU");
    if format != "TABLEAU" {
        return Err(a.err("FORMAT", format!("FORMAT='{format}' is not supported yet")));
    }
    let fmt = |v: f64| crate::text::sci(v, 10, true);
    let mut text = String::new();
    for t in a.texts("TITRE") {
        text.push_str(&format!("#TITRE {t}\n"));
    }
    for occ in a.facts("COURBE") {
        let mut cols: Vec<(String, Vec<f64>)> = Vec::new();
        if let Some(c) = occ.concept("FONCTION") {
            let f = tabulated(&c).map_err(|e| e.at(occ.span))?;
            let x = match occ.concept("LIST_PARA") {
                Some(l) => l.reals()?,
                None => f.x.clone(),
            };
            let y = x.iter().map(|&v| f.eval(v)).collect::<Result<Vec<_>>>().map_err(|e| e.at(occ.span))?;
            cols.push((f.nom_para.clone(), x));
            cols.push((f.nom_resu.clone(), y));
        } else if let (Some(cx), Some(cy)) = (occ.concept("FONC_X"), occ.concept("FONC_Y")) {
            let (fx, fy) = (tabulated(&cx).map_err(|e| e.at(occ.span))?, tabulated(&cy).map_err(|e| e.at(occ.span))?);
            let list = occ.concept("LIST_PARA").map(|l| l.reals()).transpose()?;
            let t = list.clone().unwrap_or_else(|| union(&[&fx.x, &fy.x]));
            let xs = t.iter().map(|&v| fx.eval(v)).collect::<Result<Vec<_>>>().map_err(|e| e.at(occ.span))?;
            let ys = t.iter().map(|&v| fy.eval(v)).collect::<Result<Vec<_>>>().map_err(|e| e.at(occ.span))?;
            if list.is_some() {
                cols.push((fx.nom_para.clone(), t));
            }
            cols.push((fx.nom_resu.clone(), xs));
            cols.push((fy.nom_resu.clone(), ys));
        } else {
            let x = occ.reals("ABSCISSE");
            let y = occ.reals("ORDONNEE");
            if x.len() != y.len() {
                return Err(occ.err("ORDONNEE", format!("{} abscissas but {} ordinates", x.len(), y.len())));
            }
            cols.push(("ABSCISSE".into(), x));
            cols.push(("ORDONNEE".into(), y));
        }
        if let Some(l) = occ.text("LEGENDE") {
            text.push_str(&format!("#LEGENDE {l}\n"));
        }
        let names: Vec<String> = cols.iter().map(|(n, _)| format!("{n:<17}")).collect();
        text.push_str(&format!(" {}\n", names.join(" ").trim_end()));
        for r in 0..cols[0].1.len() {
            let row: Vec<String> = cols.iter().map(|(_, v)| format!("{:<17}", fmt(v[r]))).collect();
            text.push_str(&format!(" {}\n", row.join(" ").trim_end()));
        }
        text.push('\n');
    }
    let unit = a.int("UNITE").unwrap_or(8);
    ctx.io.write_unit(unit, &text).map_err(|e| e.at(a.span_of("UNITE")))?;
    Ok(None)
}

/// Blocks of consecutive lines made only of numbers.
fn numeric_blocks(text: &str, sep: Option<&str>) -> Vec<Vec<Vec<f64>>> {
    let mut blocks = Vec::new();
    let mut cur: Vec<Vec<f64>> = Vec::new();
    for line in text.lines() {
        let fields: Vec<&str> = match sep {
            Some(s) if !s.trim().is_empty() => line.split(s).map(str::trim).filter(|f| !f.is_empty()).collect(),
            _ => line.split_whitespace().collect(),
        };
        let nums: Option<Vec<f64>> = if fields.is_empty() {
            None
        } else {
            fields.iter().map(|f| f.replace(['d', 'D'], "E").parse::<f64>().ok()).collect()
        };
        match nums {
            Some(v) => cur.push(v),
            None => {
                if !cur.is_empty() {
                    blocks.push(std::mem::take(&mut cur));
                }
            }
        }
    }
    if !cur.is_empty() {
        blocks.push(cur);
    }
    blocks
}

pub fn lire_fonction(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let ty = a.text("TYPE").unwrap_or("FONCTION");
    if ty == "FONCTION_C" {
        return Err(a.err("TYPE", format!("TYPE='{ty}' is not supported yet")));
    }
    let unit = a.int("UNITE").ok_or_else(|| a.err("UNITE", "a unit is required"))?;
    let text = ctx.io.read_unit(unit).map_err(|e| e.at(a.span_of("UNITE")))?;
    let blocks = numeric_blocks(&text, a.text("SEPARATEUR"));
    // The column (block, column) that keyword `kw` of occurrence `o` names.
    let pick = |o: &Args, kw: &str| -> Result<Vec<f64>> {
        let ind = o.ints(kw);
        let (b, c) = (ind[0], ind[1]);
        let block = blocks.get((b - 1).max(0) as usize).filter(|_| b >= 1).ok_or_else(|| {
            o.err(kw, format!("unit {unit} has {} block(s) of numbers, block {b} requested", blocks.len()))
        })?;
        block
            .iter()
            .enumerate()
            .map(|(i, row)| {
                row.get((c - 1).max(0) as usize).copied().filter(|_| c >= 1).ok_or_else(|| {
                    o.err(kw, format!("line {} of block {b} has {} column(s), column {c} requested", i + 1, row.len()))
                })
            })
            .collect()
    };
    let sorted = |x: Vec<f64>, y: Vec<f64>| if a.text("VERIF") == Some("NON") { sort_pairs(x, y) } else { (x, y) };
    if ty == "NAPPE" {
        // As Code_Aster's macro: the functions share the abscissas of INDIC_ABSCISSE, one ordinate column each
        // (DEFI_FONCTION), and the nappe's parameter values are the column INDIC_PARA.
        let xs = pick(a, "INDIC_ABSCISSE")?;
        let nom_para_fonc = a.req_text("NOM_PARA_FONC")?;
        let mut functions = Vec::new();
        for occ in a.facts("DEFI_FONCTION") {
            let y = pick(occ, "INDIC_RESU")?;
            if y.len() != xs.len() {
                return Err(occ.err("INDIC_RESU", "the abscissa and ordinate columns differ in length"));
            }
            let (x, y) = sorted(xs.clone(), y);
            let f = Function::new(
                nom_para_fonc,
                a.text("NOM_RESU").unwrap_or("TOUTRESU"),
                x,
                y,
                interp_of(a, "INTERPOL_FONC", (Interp::Lin, Interp::Lin)),
                prol_of(a, "PROL_GAUCHE_FONC", Prol::Exclu),
                prol_of(a, "PROL_DROITE_FONC", Prol::Exclu),
            )
            .map_err(|e| e.at(occ.span))?;
            functions.push(f);
        }
        let params = pick(a, "INDIC_PARA")?;
        return Ok(Some(ConceptData::Nappe(nappe_of(a, nom_para_fonc, params, functions)?)));
    }
    let x = pick(a, "INDIC_PARA")?;
    let y = pick(a, "INDIC_RESU")?;
    if x.len() != y.len() {
        return Err(a.err("INDIC_RESU", "the parameter and result columns differ in length"));
    }
    let (x, y) = sorted(x, y);
    Ok(Some(ConceptData::Function(function_from(a, None, x, y)?)))
}

pub fn recu_fonction(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    let Some(tc) = a.concept("TABLE") else {
        return recu_fonction_resultat(a);
    };
    let name = tc.label();
    let t: Table = tc.table()?;
    let rows = filtered(&t, a.facts("FILTRE"), &name)?;
    let (px, py) = (a.req_text("PARA_X")?, a.req_text("PARA_Y")?);
    let cx = t.column(px).ok_or_else(|| a.err("PARA_X", format!("table {name} has no parameter '{px}'")))?;
    let cy = t.column(py).ok_or_else(|| a.err("PARA_Y", format!("table {name} has no parameter '{py}'")))?;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for r in rows {
        if let (Some(u), Some(v)) = (t.columns[cx].cells[r].as_f64(), t.columns[cy].cells[r].as_f64()) {
            x.push(u);
            y.push(v);
        }
    }
    let base = Function::new(px, py, vec![0.0], vec![0.0], (Interp::Lin, Interp::Lin), Prol::Exclu, Prol::Exclu)?;
    Ok(Some(ConceptData::Function(function_from(a, Some(&base), x, y)?)))
}

/// RECU_FONCTION from a result: one component of a field at a node (nodal fields) or at a Gauss point
/// of a cell (ELGA fields), as a function of INST over every stored step.
fn recu_fonction_resultat(a: &Args) -> Result<Option<ConceptData>> {
    use crate::concepts::result::Field;
    let rc = a.concept("RESULTAT").ok_or_else(|| a.err("TABLE", "TABLE or RESULTAT is required"))?;
    a.refuse(&["NOM_PARA_RESU", "LIST_INST"])?;
    let _ = a.text("TOUT_ORDRE"); // every step: the only selection supported
    let name = rc.label();
    let r = rc.result()?;
    let model = r.model.model()?;
    let mesh = model.current_mesh();
    let mesh_name = model.mesh_concept.label();
    let cham = a.req_text("NOM_CHAM")?;
    let cmp = a.req_text("NOM_CMP")?;
    let one = |kw: &str, names: &[String]| -> Result<String> {
        match names {
            [n] => Ok(n.clone()),
            _ => Err(a.err(kw, format!("{kw} must designate exactly one entity (it gives {})", names.len()))),
        }
    };
    let node = || -> Result<usize> {
        let n = if let Some(g) = a.text("GROUP_NO") {
            let nodes = mesh
                .node_groups
                .get(g)
                .ok_or_else(|| a.err("GROUP_NO", format!("the mesh {mesh_name} has no group of nodes '{g}'")))?;
            one("GROUP_NO", &nodes.iter().map(|&n| mesh.node_names[n].clone()).collect::<Vec<_>>())?
        } else {
            a.text("NOEUD").ok_or_else(|| a.err("NOEUD", "NOEUD or GROUP_NO is required"))?.to_string()
        };
        mesh.node_names
            .iter()
            .position(|x| *x == n)
            .ok_or_else(|| a.err("NOEUD", format!("the mesh {mesh_name} has no node {n}")))
    };
    let cell = || -> Result<usize> {
        let c = if let Some(g) = a.text("GROUP_MA") {
            let cells = mesh
                .cell_groups
                .get(g)
                .ok_or_else(|| a.err("GROUP_MA", format!("the mesh {mesh_name} has no group of cells '{g}'")))?;
            one("GROUP_MA", &cells.iter().map(|&c| mesh.cell_names[c].clone()).collect::<Vec<_>>())?
        } else {
            a.text("MAILLE").ok_or_else(|| a.err("MAILLE", "MAILLE or GROUP_MA is required"))?.to_string()
        };
        mesh.cell_names
            .iter()
            .position(|x| *x == c)
            .ok_or_else(|| a.err("MAILLE", format!("the mesh {mesh_name} has no cell {c}")))
    };
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for st in &r.steps {
        let f = st.fields.get(cham).ok_or_else(|| {
            a.err("NOM_CHAM", format!("result {name} has no field {cham} at order {}", st.nume_ordre))
        })?;
        let k = f.component(cmp).ok_or_else(|| a.err("NOM_CMP", format!("field {cham} has no component {cmp}")))?;
        let n = f.components().len();
        let v = match f {
            Field::Node { values, .. } => values[node()? * n + k],
            Field::Elga { cells, .. } => {
                let c = cell()?;
                let p =
                    a.int("POINT").ok_or_else(|| a.err("POINT", "POINT is required for a field at Gauss points"))?;
                let vals = cells[c].as_ref().ok_or_else(|| {
                    a.err("MAILLE", format!("field {cham} has no value on cell {}", mesh.cell_names[c]))
                })?;
                let npg = vals.len() / n;
                if p < 1 || p as usize > npg {
                    return Err(
                        a.err("POINT", format!("cell {} has {npg} points, point {p} requested", mesh.cell_names[c]))
                    );
                }
                vals[(p as usize - 1) * n + k]
            }
            _ => return Err(a.err("NOM_CHAM", format!("RECU_FONCTION of the {cham} field is not supported yet"))),
        };
        if v.is_nan() {
            return Err(a.err("NOM_CMP", format!("{cham} has no value of {cmp} there at order {}", st.nume_ordre)));
        }
        x.push(st.inst);
        y.push(v);
    }
    let base = Function::new("INST", cmp, vec![0.0], vec![0.0], (Interp::Lin, Interp::Lin), Prol::Exclu, Prol::Exclu)?;
    Ok(Some(ConceptData::Function(function_from(a, Some(&base), x, y)?)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractile_interpolates_sorted_values() {
        assert!((fractile(&[3.0, 4.0, 8.0], 0.7) - 5.6).abs() < 1e-12);
        assert_eq!(fractile(&[3.0, 4.0, 8.0], 1.0), 8.0);
        assert_eq!(fractile(&[3.0, 4.0, 8.0], 0.0), 3.0);
    }

    #[test]
    fn blocks_of_numbers() {
        let b = numeric_blocks("#T\n A B\n 1 2\n 3 4\n\n x\n 5 6 7\n", None);
        assert_eq!(b.len(), 2);
        assert_eq!(b[0], vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
    }
}
