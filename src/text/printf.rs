//! Python's `%`-formatting (`'%5.2f %s' % (x, name)`).

use super::number::{general, nonfinite, sci};
use super::spec::{pad, sign_str, Spec};
use super::{FormatError, Operand};

/// How `%(key)s` finds its operand: a lookup in the mapping on the right of `%`.
pub type Mapping<'a, O> = &'a dyn Fn(&str) -> Result<O, FormatError>;

/// `fmt % args`: `positional` are the operands in order; `mapping` looks up `%(key)s` operands.
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
        if i >= c.len() {
            return Err(FormatError::value("incomplete format"));
        }
        if c[i] == '%' {
            out.push('%');
            i += 1;
            continue;
        }
        let mut keyed: Option<O> = None;
        if c[i] == '(' {
            let st = i + 1;
            while i < c.len() && c[i] != ')' {
                i += 1;
            }
            let key: String = c[st..i].iter().collect();
            i += 1;
            let m = mapping.ok_or_else(|| FormatError::type_error("format requires a mapping"))?;
            keyed = Some(m(&key)?);
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
        if i < c.len() && c[i] == '*' {
            spec.width = take(&mut next)?.number().and_then(|n| n.as_int()).unwrap_or(0) as usize;
            i += 1;
        } else {
            let st = i;
            while i < c.len() && c[i].is_ascii_digit() {
                i += 1;
            }
            if i > st {
                spec.width = c[st..i].iter().collect::<String>().parse().unwrap();
            }
        }
        if i < c.len() && c[i] == '.' {
            i += 1;
            if i < c.len() && c[i] == '*' {
                spec.prec = Some(take(&mut next)?.number().and_then(|n| n.as_int()).unwrap_or(0) as usize);
                i += 1;
            } else {
                let st = i;
                while i < c.len() && c[i].is_ascii_digit() {
                    i += 1;
                }
                spec.prec = Some(c[st..i].iter().collect::<String>().parse().unwrap_or(0));
            }
        }
        while i < c.len() && matches!(c[i], 'l' | 'h' | 'L') {
            i += 1;
        }
        if i >= c.len() {
            return Err(FormatError::value("incomplete format"));
        }
        let conv = c[i];
        i += 1;
        let v: &O = match &keyed {
            Some(v) => v,
            None => take(&mut next)?,
        };
        if spec.align == Some('<') {
            spec.zero = false;
        }
        let text = match conv {
            's' | 'r' | 'a' => {
                let mut t = if conv == 's' { v.to_str() } else { v.repr() };
                if let Some(p) = spec.prec {
                    t = t.chars().take(p).collect();
                }
                spec.zero = false;
                pad(t, "", &spec, spec.align.is_none())
            }
            'd' | 'i' | 'u' => {
                let n = match v.number() {
                    Some(super::Number::Float(f)) => f.trunc() as i64,
                    n => n.and_then(|n| n.as_int()).ok_or_else(|| {
                        FormatError::type_error(format!("%d format: a number is required, not {}", v.type_name()))
                    })?,
                };
                let sign = sign_str(n < 0, spec.sign);
                pad(n.unsigned_abs().to_string(), &sign, &spec, true)
            }
            'x' | 'X' | 'o' => {
                let n = v
                    .number()
                    .and_then(|n| n.as_int())
                    .ok_or_else(|| FormatError::type_error("an integer is required"))?;
                let body = match conv {
                    'x' => format!("{:x}", n.unsigned_abs()),
                    'X' => format!("{:X}", n.unsigned_abs()),
                    _ => format!("{:o}", n.unsigned_abs()),
                };
                pad(body, &sign_str(n < 0, spec.sign), &spec, true)
            }
            'e' | 'E' | 'f' | 'F' | 'g' | 'G' => {
                let f = v
                    .number()
                    .map(|n| n.as_f64())
                    .ok_or_else(|| FormatError::type_error(format!("must be real number, not {}", v.type_name())))?;
                let a = f.abs();
                let p = spec.prec.unwrap_or(6);
                let body = match conv {
                    'e' | 'E' if a.is_finite() => sci(a, p, conv == 'E'),
                    'f' | 'F' if a.is_finite() => format!("{:.*}", p, a),
                    'g' | 'G' => general(a, p, conv == 'G', spec.alt),
                    _ => nonfinite(a, conv.is_uppercase()),
                };
                pad(body, &sign_str(f.is_sign_negative() && !f.is_nan(), spec.sign), &spec, true)
            }
            'c' => match v.text() {
                Some(s) => s.to_string(),
                None => v
                    .number()
                    .and_then(|n| n.as_int())
                    .and_then(|n| char::from_u32(n as u32))
                    .map(|c| c.to_string())
                    .unwrap_or_default(),
            },
            o => return Err(FormatError::value(format!("unsupported format character '{o}'"))),
        };
        out.push_str(&text);
    }
    if mapping.is_none() && next < positional.len() {
        return Err(FormatError::type_error("not all arguments converted during string formatting"));
    }
    Ok(out)
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
    }
}
