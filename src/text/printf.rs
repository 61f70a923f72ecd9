//! Python's `%`-formatting (`'%5.2f %s' % (x, name)`), as CPython 3.11 does it.

use super::number::{fixed, general, nonfinite, sci};
use super::spec::{char_of, pad, sign_str, with_point, Spec};
use super::{ascii, check_size, FormatError, Number, Operand};

/// How `%(key)s` finds its operand: a lookup in the mapping on the right of `%`.
pub type Mapping<'a, O> = &'a dyn Fn(&str) -> Result<O, FormatError>;

/// `fmt % args`: `positional` are the operands in order; `mapping` looks up `%(key)s` operands (when
/// the right of `%` is a mapping, it is also the one positional operand, as in Python).
pub fn format<O: Operand>(fmt: &str, positional: &[O], mapping: Option<Mapping<O>>) -> Result<String, FormatError> {
    let mut next = 0usize;
    let take = |next: &mut usize| -> Result<&O, FormatError> {
        let v =
            positional.get(*next).ok_or_else(|| FormatError::type_error("not enough arguments for format string"))?;
        *next += 1;
        Ok(v)
    };
    let c: Vec<char> = fmt.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < c.len() {
        if c[i] != '%' {
            out.push(c[i]);
            i += 1;
            continue;
        }
        i += 1;
        match c.get(i) {
            None => return Err(FormatError::value("incomplete format")),
            Some('%') => {
                out.push('%');
                i += 1;
                continue;
            }
            Some(_) => {}
        }
        let mut keyed: Option<O> = None;
        if c[i] == '(' {
            let mut depth = 1;
            i += 1;
            let st = i;
            while i < c.len() {
                match c[i] {
                    '(' => depth += 1,
                    ')' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                i += 1;
            }
            if i >= c.len() {
                return Err(FormatError::value("incomplete format key"));
            }
            let key: String = c[st..i].iter().collect();
            i += 1;
            let m = mapping.ok_or_else(|| FormatError::type_error("format requires a mapping"))?;
            keyed = Some(m(&key)?);
            // As in CPython, a keyed directive uses up the one positional operand (the mapping).
            next = positional.len();
        }
        let mut spec = Spec::default();
        while i < c.len() && matches!(c[i], '-' | '+' | ' ' | '#' | '0') {
            match c[i] {
                '-' => spec.align = Some('<'),
                '+' => spec.sign = Some('+'),
                ' ' => {
                    if spec.sign.is_none() {
                        spec.sign = Some(' ')
                    }
                }
                '#' => spec.alt = true,
                _ => spec.zero = true,
            }
            i += 1;
        }
        if c.get(i) == Some(&'*') {
            i += 1;
            let w = star(take(&mut next)?)?;
            if w < 0 {
                // A negative `*` width left-justifies.
                spec.align = Some('<');
            }
            spec.width = usize::try_from(w.unsigned_abs()).unwrap_or(usize::MAX);
        } else {
            spec.width = count(&c, &mut i, isize::MAX as usize).ok_or_else(|| FormatError::value("width too big"))?;
        }
        if c.get(i) == Some(&'.') {
            i += 1;
            if c.get(i) == Some(&'*') {
                i += 1;
                let p = star(take(&mut next)?)?;
                if i32::try_from(p).is_err() {
                    return Err(FormatError::new("OverflowError", "Python int too large to convert to C int"));
                }
                spec.prec = Some(p.max(0) as usize);
            } else {
                let p = count(&c, &mut i, i32::MAX as usize).ok_or_else(|| FormatError::value("precision too big"))?;
                spec.prec = Some(p);
            }
        }
        while i < c.len() && matches!(c[i], 'l' | 'h' | 'L') {
            i += 1;
        }
        let Some(&conv) = c.get(i) else {
            return Err(FormatError::value("incomplete format"));
        };
        let at = i;
        i += 1;
        let v: &O = match &keyed {
            Some(v) => v,
            None => take(&mut next)?,
        };
        if spec.align == Some('<') {
            spec.zero = false;
        }
        check_size("format width", spec.width)?;
        if let Some(p) = spec.prec {
            check_size("format precision", p)?;
        }
        out.push_str(&convert(conv, at, &spec, v)?);
    }
    if mapping.is_none() && next < positional.len() {
        return Err(FormatError::type_error("not all arguments converted during string formatting"));
    }
    Ok(out)
}

/// Decimal digits at `c[*i..]` as a count, or `None` past `limit`.
fn count(c: &[char], i: &mut usize, limit: usize) -> Option<usize> {
    let mut n: usize = 0;
    while let Some(d) = c.get(*i).and_then(|ch| ch.to_digit(10)) {
        n = n.checked_mul(10).and_then(|n| n.checked_add(d as usize)).filter(|n| *n <= limit)?;
        *i += 1;
    }
    Some(n)
}

/// The integer a `*` takes from the operands.
fn star<O: Operand>(v: &O) -> Result<i64, FormatError> {
    v.number().and_then(Number::as_int).ok_or_else(|| FormatError::type_error("* wants int"))
}

/// One conversion (`conv`, at char index `at` of the format) of one operand.
fn convert<O: Operand>(conv: char, at: usize, spec: &Spec, v: &O) -> Result<String, FormatError> {
    // `%s`, `%r`, `%a` and `%c` are right-justified text: the `0` flag does not apply.
    let text = |t: String| pad(t, "", &Spec { zero: false, ..spec.clone() }, true);
    let number = |neg: bool, prefix: &str, body: String| pad(body, &(sign_str(neg, spec.sign) + prefix), spec, true);
    // Integer digits with the precision as a minimum count (`'%.3d' % 5` is `'005'`).
    let min_digits = |d: String| match spec.prec {
        Some(p) if p > d.len() => "0".repeat(p - d.len()) + &d,
        _ => d,
    };
    match conv {
        's' | 'r' | 'a' => {
            let t = match conv {
                's' => v.to_str(),
                'r' => v.repr(),
                _ => ascii(&v.repr()),
            };
            Ok(text(match spec.prec {
                Some(p) => t.chars().take(p).collect(),
                None => t,
            }))
        }
        'd' | 'i' | 'u' => {
            let (neg, digits) = match v.number() {
                Some(Number::Float(f)) => integral(f)?,
                Some(n) => {
                    let i = n.as_int().unwrap_or(0);
                    (i < 0, i.unsigned_abs().to_string())
                }
                None => {
                    return Err(FormatError::type_error(format!(
                        "%{conv} format: a real number is required, not {}",
                        v.type_name()
                    )))
                }
            };
            Ok(number(neg, "", min_digits(digits)))
        }
        'x' | 'X' | 'o' => {
            let Some(i) = v.number().and_then(Number::as_int) else {
                return Err(FormatError::type_error(format!(
                    "%{conv} format: an integer is required, not {}",
                    v.type_name()
                )));
            };
            let a = i.unsigned_abs();
            let (digits, prefix) = match conv {
                'x' => (format!("{a:x}"), "0x"),
                'X' => (format!("{a:X}"), "0X"),
                _ => (format!("{a:o}"), "0o"),
            };
            Ok(number(i < 0, if spec.alt { prefix } else { "" }, min_digits(digits)))
        }
        'e' | 'E' | 'f' | 'F' | 'g' | 'G' => {
            let Some(f) = v.number().map(Number::as_f64) else {
                return Err(FormatError::type_error(format!("must be real number, not {}", v.type_name())));
            };
            let (a, p, upper) = (f.abs(), spec.prec.unwrap_or(6), conv.is_ascii_uppercase());
            let body = match conv {
                _ if !a.is_finite() => nonfinite(a, upper),
                'e' | 'E' => with_point(sci(a, p, upper), spec.alt),
                'f' | 'F' => with_point(fixed(a, p), spec.alt),
                _ => general(a, p, upper, spec.alt),
            };
            Ok(number(f.is_sign_negative() && !f.is_nan(), "", body))
        }
        'c' => {
            let ch = match (v.text(), v.number().and_then(Number::as_int)) {
                (Some(s), _) if s.chars().count() == 1 => s.to_string(),
                (None, Some(i)) => char_of(i)?,
                _ => return Err(FormatError::type_error("%c requires int or char")),
            };
            Ok(text(ch))
        }
        _ => {
            let shown = if (' '..='~').contains(&conv) { conv } else { '?' };
            Err(FormatError::value(format!(
                "unsupported format character '{shown}' ({:#x}) at index {at}",
                conv as u32
            )))
        }
    }
}

/// `int(f)` for `%d`: its sign and digits, or Python's error for nan and infinities.
fn integral(f: f64) -> Result<(bool, String), FormatError> {
    if f.is_nan() {
        return Err(FormatError::value("cannot convert float NaN to integer"));
    }
    if f.is_infinite() {
        return Err(FormatError::new("OverflowError", "cannot convert float infinity to integer"));
    }
    let t = f.trunc();
    Ok((t < 0.0, format!("{:.0}", t.abs())))
}

/// `fmt % x` for one float: how the stages write numbers with a `%` format.
pub fn format_real(fmt: &str, x: f64) -> Result<String, FormatError> {
    format(fmt, &[x], None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn real_formats() {
        assert_eq!(format_real("%e", 12345.678).unwrap(), "1.234568e+04");
        assert_eq!(format_real("%g", 0.00001234).unwrap(), "1.234e-05");
        assert_eq!(format_real("%g", 100000.0).unwrap(), "100000");
        assert_eq!(format_real("%g", 1e6).unwrap(), "1e+06");
        assert_eq!(format_real("%05.1f", -2.25).unwrap(), "-02.2");
        assert_eq!(format_real("%12.5E", 0.5).unwrap(), " 5.00000E-01");
        assert_eq!(format_real("%e", f64::NAN).unwrap(), "nan");
        assert_eq!(format_real("%08f", f64::INFINITY).unwrap(), "00000inf");
        assert_eq!(format_real("%d", 1e30).unwrap(), "1000000000000000019884624838656");
    }
}
