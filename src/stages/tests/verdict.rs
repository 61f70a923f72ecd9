//! The verdict of one TEST_* check, printed as Code_Aster prints it.
//!
//! Every check compares the computed value with `VALE_CALC` (NON_REGRESSION,
//! tolerance `TOLE_MACHINE`, default 1e-6 relative) and, when `REFERENCE` is
//! given, with `VALE_REFE` (tolerance `PRECISION`, default 1e-3). A
//! non-regression value below machine precision is skipped unless
//! `ORDRE_GRANDEUR` gives the scale for an absolute comparison. Lines are
//! `OK`/`NOOK`/`SKIP` followed by the reference type, the legend, the
//! reference and computed values, the error and the tolerance (both in % for
//! relative checks).

use crate::catalog::args::{Args, Val};
use crate::diag::Result;
use crate::stages::{CheckRecord, Ctx};
use crate::text::float_repr;

/// A computed value under test.
#[derive(Debug, Clone)]
pub enum Scalar {
    I(i64),
    R(f64),
    K(String),
}

impl Scalar {
    fn show(&self) -> String {
        match self {
            Scalar::I(i) => i.to_string(),
            Scalar::R(r) => fortran(&float_repr(*r)),
            Scalar::K(k) => k.clone(),
        }
    }
    fn num(&self) -> Option<f64> {
        match self {
            Scalar::I(i) => Some(*i as f64),
            Scalar::R(r) => Some(*r),
            Scalar::K(_) => None,
        }
    }
}

fn fortran(s: &str) -> String {
    s.replace('e', "E")
}

const R8PREM: f64 = f64::EPSILON;

/// One line of the verdict table.
struct Line {
    diag: &'static str,
    reference: String,
    legend: String,
    refe: String,
    calc: String,
    err: String,
    tole: String,
}

fn write_line(width: usize, cols: &[&str]) -> String {
    let w = [4usize, 16, 16, width, width, 16, 16];
    let mut s = String::from(" ");
    for (i, c) in cols.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        s.push_str(&format!("{:<w$}", c, w = w[i]));
    }
    s.trim_end().to_string()
}

/// Compare `val` with the reference values `refs` (the closest one counts).
fn compare(
    reference: &str,
    legend: &str,
    refs: &[Scalar],
    val: &Scalar,
    relative: bool,
    tole: f64,
    ordre: Option<f64>,
) -> Line {
    // Texts compare for equality.
    if let Scalar::K(v) = val {
        let ok = refs.iter().any(|r| matches!(r, Scalar::K(k) if k.trim_end() == v.trim_end()));
        let refe = refs.first().map(|r| r.show()).unwrap_or_default();
        return Line {
            diag: if ok { " OK " } else { "NOOK" },
            reference: reference.into(),
            legend: legend.into(),
            refe,
            calc: v.clone(),
            err: "-".into(),
            tole: "-".into(),
        };
    }
    let v = val.num().unwrap();
    // The closest reference decides.
    let r = refs
        .iter()
        .filter_map(|r| r.num().map(|x| (x, r)))
        .min_by(|a, b| (a.0 - v).abs().partial_cmp(&(b.0 - v).abs()).unwrap_or(std::cmp::Ordering::Equal));
    let Some((rv, rs)) = r else {
        return Line {
            diag: "NOOK",
            reference: reference.into(),
            legend: legend.into(),
            refe: "-".into(),
            calc: val.show(),
            err: "-".into(),
            tole: "-".into(),
        };
    };
    let mut relative = relative;
    let mut compare = 1.0;
    if reference == "NON_REGRESSION" && rv.abs() <= R8PREM {
        match ordre {
            Some(o) => {
                compare = o;
                relative = false;
            }
            None => {
                return Line {
                    diag: "SKIP",
                    reference: reference.into(),
                    legend: "-".into(),
                    refe: "-".into(),
                    calc: "-".into(),
                    err: "-".into(),
                    tole: "-".into(),
                }
            }
        }
    }
    let mut error = (rv - v).abs();
    let (ok, tol) = if relative {
        let ok = error <= (tole * rv).abs();
        if rv != 0.0 {
            error = error / rv.abs() * 100.0;
        } else if ok {
            error = 0.0;
        } else {
            error = 999.999999;
        }
        (ok, tole * 100.0)
    } else {
        let t = (tole * compare).abs();
        (error <= t, t)
    };
    let mut serr = float_repr(error);
    if serr.len() > 15 {
        serr = crate::text::sci(error, 6, false);
    }
    let mut stol = float_repr(tol);
    if relative {
        serr.push('%');
        stol.push('%');
    }
    // Integer references print as integers.
    let refe = match (rs, val) {
        (Scalar::I(i), _) => i.to_string(),
        _ => fortran(&float_repr(rv)),
    };
    Line {
        diag: if ok { " OK " } else { "NOOK" },
        reference: reference.into(),
        legend: legend.into(),
        refe,
        calc: val.show(),
        err: fortran(&serr),
        tole: fortran(&stol),
    }
}

fn refs_from(vals: &[Val], int: bool) -> Vec<Scalar> {
    vals.iter()
        .filter_map(|v| match v {
            Val::I(i) if int => Some(Scalar::I(*i)),
            Val::I(i) => Some(Scalar::R(*i as f64)),
            Val::R(r) => Some(Scalar::R(*r)),
            Val::T(t) => Some(Scalar::K(t.clone())),
            _ => None,
        })
        .collect()
}

/// Run the checks of one TEST_* occurrence `occ` on the computed `val`.
/// `title` describes what is tested (printed above the table).
pub fn check(ctx: &mut Ctx, occ: &Args, val: Scalar, legend: &str, title: &str) -> Result<()> {
    let legend = occ.text("LEGENDE").map(str::to_string).unwrap_or_else(|| legend.to_string());
    let val = match (occ.text("VALE_ABS"), val) {
        (Some("OUI"), Scalar::R(r)) => Scalar::R(r.abs()),
        (Some("OUI"), Scalar::I(i)) => Scalar::I(i.abs()),
        (_, v) => v,
    };
    let (calc_kw, refe_kw, int) = if occ.has_if_declared("VALE_CALC_I") {
        ("VALE_CALC_I", "VALE_REFE_I", true)
    } else if occ.has_if_declared("VALE_CALC_K") {
        ("VALE_CALC_K", "VALE_REFE_K", false)
    } else if occ.has("VALE_CALC_C") || occ.has("VALE_REFE_C") {
        return Err(occ.err("VALE_CALC_C", "checks of complex values are not supported yet"));
    } else {
        ("VALE_CALC", "VALE_REFE", false)
    };
    // A text value under test needs a text reference and conversely.
    let val = match (&val, calc_kw) {
        (Scalar::K(_), "VALE_CALC_K") | (Scalar::I(_), "VALE_CALC_I") | (Scalar::R(_), "VALE_CALC") => val,
        (Scalar::I(i), "VALE_CALC") => Scalar::R(*i as f64),
        (Scalar::R(r), "VALE_CALC_I") if r.fract() == 0.0 => Scalar::I(*r as i64),
        (v, kw) => return Err(occ.err(kw, format!("the tested value {} is not of the type {kw} expects", v.show()))),
    };
    let calc = refs_from(occ.vals(calc_kw), int);
    let crit = occ.texts("CRITERE");
    let crit_nr = crit.first().map(String::as_str).unwrap_or("RELATIF");
    let crit_ref = crit.get(1).or(crit.first()).map(String::as_str).unwrap_or("RELATIF");
    let tole_m = occ.reals("TOLE_MACHINE");
    let tole_nr = tole_m.first().copied().unwrap_or(1e-6);
    let ordre = occ.real("ORDRE_GRANDEUR");

    let mut lines = Vec::new();
    lines.push(compare("NON_REGRESSION", &legend, &calc, &val, crit_nr == "RELATIF", tole_nr, ordre));
    match occ.text("REFERENCE") {
        Some(reference) if reference != "NON_REGRESSION" => {
            let refe = refs_from(occ.vals(refe_kw), int);
            if refe.is_empty() {
                return Err(occ.err("REFERENCE", format!("REFERENCE='{reference}' needs {refe_kw}")));
            }
            let prec = occ.real("PRECISION").unwrap_or(1e-3);
            lines.push(compare(reference, &legend, &refe, &val, crit_ref == "RELATIF", prec, None));
        }
        _ => {
            if occ.has(refe_kw) {
                return Err(occ.err(
                    refe_kw,
                    "a reference value needs REFERENCE (ANALYTIQUE, SOURCE_EXTERNE, AUTRE_ASTER, NON_DEFINI)",
                ));
            }
        }
    }

    emit(ctx, title, lines);
    Ok(())
}

/// TYPE_TEST: the MAX, MIN, SOMM or SOMM_ABS of values (callers check they are not empty).
pub fn type_test(tt: &str, vals: &[f64]) -> f64 {
    match tt {
        "MAX" => vals.iter().cloned().fold(f64::MIN, f64::max),
        "MIN" => vals.iter().cloned().fold(f64::MAX, f64::min),
        "SOMM" => vals.iter().sum(),
        _ => vals.iter().map(|x| x.abs()).sum(),
    }
}

/// A check of a text attribute against its expected value.
pub fn check_text(ctx: &mut Ctx, reference: &str, legend: &str, expected: &str, actual: &str, title: &str) {
    let l = compare(reference, legend, &[Scalar::K(expected.into())], &Scalar::K(actual.into()), true, 0.0, None);
    emit(ctx, title, vec![l]);
}

fn emit(ctx: &mut Ctx, title: &str, lines: Vec<Line>) {
    let width = lines.iter().map(|l| l.refe.len().max(l.calc.len())).max().unwrap_or(0).max(16) + 2;
    let mut text = String::new();
    text.push_str(&format!(" ---- {title}\n"));
    text.push_str(&write_line(width, &[" ", "REFERENCE", "LEGENDE", "VALE_REFE", "VALE_CALC", "ERREUR", "TOLE"]));
    text.push('\n');
    let validation = ctx.io.is_validation();
    for l in &lines {
        let ignored = validation && l.reference == "NON_REGRESSION";
        let diag = if ignored { "-" } else { l.diag };
        let tole = if ignored { "-" } else { l.tole.as_str() };
        text.push_str(&write_line(width, &[diag, &l.reference, &l.legend, &l.refe, &l.calc, &l.err, tole]));
        text.push('\n');
        ctx.io.record(CheckRecord {
            command: ctx.command.to_string(),
            line: ctx.line,
            reference: l.reference.clone(),
            legend: l.legend.clone(),
            ok: match (ignored, l.diag) {
                (true, _) | (_, "SKIP") => None,
                (_, d) => Some(d == " OK "),
            },
        });
    }
    text.push('\n');
    ctx.io.resu(&text);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_and_absolute() {
        let l = compare("ANALYTIQUE", "DX", &[Scalar::R(5.0)], &Scalar::R(5.004), true, 1e-3, None);
        assert_eq!(l.diag, " OK ");
        let l = compare("ANALYTIQUE", "DX", &[Scalar::R(5.0)], &Scalar::R(5.006), true, 1e-3, None);
        assert_eq!(l.diag, "NOOK");
        assert_eq!(l.tole, "0.1%");
        let l = compare("ANALYTIQUE", "DX", &[Scalar::R(0.0)], &Scalar::R(1e-11), false, 1e-10, None);
        assert_eq!(l.diag, " OK ");
        assert_eq!(l.refe, "0.0");
        assert_eq!(l.calc, "1E-11");
    }

    #[test]
    fn zero_non_regression_is_skipped_without_scale() {
        let l = compare("NON_REGRESSION", "DX", &[Scalar::R(0.0)], &Scalar::R(1e-20), true, 1e-6, None);
        assert_eq!(l.diag, "SKIP");
        let l = compare("NON_REGRESSION", "DX", &[Scalar::R(0.0)], &Scalar::R(1e-20), true, 1e-6, Some(1.0));
        assert_eq!(l.diag, " OK ");
    }

    #[test]
    fn closest_reference_counts() {
        let l = compare("NON_REGRESSION", "N", &[Scalar::R(1.0), Scalar::R(2.0)], &Scalar::R(2.0), true, 1e-6, None);
        assert_eq!(l.diag, " OK ");
        let l = compare("NON_REGRESSION", "N", &[Scalar::I(3)], &Scalar::I(3), true, 1e-6, None);
        assert_eq!((l.diag, l.refe.as_str(), l.calc.as_str()), (" OK ", "3", "3"));
    }
}
