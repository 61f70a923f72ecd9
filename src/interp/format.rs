//! Python's text forms of values: `repr`, `str`, `%`-formatting and the
//! format-spec mini-language used by `str.format`, f-strings and `format()`.

use super::value::{Dict, Value};
use crate::diag::{Error, Result};

/// `repr(float)`: the shortest round-trip digits, positional between 1e-4 and 1e16.
pub fn float_repr(f: f64) -> String {
    if f.is_nan() {
        return "nan".into();
    }
    if f.is_infinite() {
        return if f > 0.0 { "inf".into() } else { "-inf".into() };
    }
    if f == 0.0 {
        return if f.is_sign_negative() { "-0.0".into() } else { "0.0".into() };
    }
    let sci = format!("{f:e}"); // shortest round-trip, e.g. "-1.5e-7"
    let (mant, exp) = sci.split_once('e').unwrap();
    let exp: i32 = exp.parse().unwrap();
    let neg = mant.starts_with('-');
    let digits: String = mant.chars().filter(|c| c.is_ascii_digit()).collect();
    let sign = if neg { "-" } else { "" };
    if (-4..16).contains(&exp) {
        let n = digits.len() as i32;
        let s = if exp >= 0 {
            let int_len = exp + 1;
            if n <= int_len {
                format!("{}{}.0", digits, "0".repeat((int_len - n) as usize))
            } else {
                format!("{}.{}", &digits[..int_len as usize], &digits[int_len as usize..])
            }
        } else {
            format!("0.{}{}", "0".repeat((-exp - 1) as usize), digits)
        };
        format!("{sign}{s}")
    } else {
        let m = if digits.len() > 1 { format!("{}.{}", &digits[..1], &digits[1..]) } else { digits };
        format!("{sign}{m}e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs())
    }
}

pub fn str_repr(s: &str) -> String {
    let quote = if s.contains('\'') && !s.contains('"') { '"' } else { '\'' };
    let mut out = String::new();
    out.push(quote);
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c == quote => {
                out.push('\\');
                out.push(c)
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

pub fn repr(v: &Value) -> String {
    match v {
        Value::Str(s) => str_repr(s),
        _ => to_str(v),
    }
}

fn complex_repr(a: f64, b: f64) -> String {
    let im = |x: f64| {
        let r = float_repr(x);
        r.strip_suffix(".0").map(str::to_string).unwrap_or(r)
    };
    if a == 0.0 && !a.is_sign_negative() {
        format!("{}j", im(b))
    } else {
        let sign = if b < 0.0 || (b == 0.0 && b.is_sign_negative()) { "-" } else { "+" };
        format!("({}{}{}j)", im(a), sign, im(b.abs()))
    }
}

/// `str(v)`.
pub fn to_str(v: &Value) -> String {
    match v {
        Value::None => "None".into(),
        Value::Bool(b) => if *b { "True" } else { "False" }.into(),
        Value::Int(i) => i.to_string(),
        Value::Float(f) => float_repr(*f),
        Value::Complex(a, b) => complex_repr(*a, *b),
        Value::Str(s) => s.to_string(),
        Value::Tuple(t) => {
            let items: Vec<String> = t.iter().map(repr).collect();
            if items.len() == 1 {
                format!("({},)", items[0])
            } else {
                format!("({})", items.join(", "))
            }
        }
        Value::List(l) => format!("[{}]", l.borrow().iter().map(repr).collect::<Vec<_>>().join(", ")),
        Value::Dict(d) => dict_repr(&d.borrow()),
        Value::Func(f) => format!("<function {}>", f.def.name),
        Value::Builtin(b) => format!("<built-in function {}>", b.0),
        Value::Method(_, m) => format!("<built-in method {m}>"),
        Value::Module(m) => format!("<module '{m}'>"),
        Value::Command(c) => format!("<command {c}>"),
        Value::Concept(c) => c.label(),
    }
}

fn dict_repr(d: &Dict) -> String {
    let items: Vec<String> = d.items.iter().map(|(k, v)| format!("{}: {}", repr(k), repr(v))).collect();
    format!("{{{}}}", items.join(", "))
}

// ----------------------------------------------------------------- numbers

/// Scientific notation with Python's exponent form (`1.500000e-07`).
pub fn sci(f: f64, prec: usize, upper: bool) -> String {
    let s = format!("{:.*e}", prec, f);
    let (m, e) = s.split_once('e').unwrap();
    let e: i32 = e.parse().unwrap();
    let out = format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs());
    if upper {
        out.to_uppercase()
    } else {
        out
    }
}

/// `%g` / `{:g}`: `alt` keeps trailing zeros.
pub fn general(f: f64, prec: usize, upper: bool, alt: bool) -> String {
    if !f.is_finite() {
        return nonfinite(f, upper);
    }
    let p = if prec == 0 { 1 } else { prec };
    if f == 0.0 {
        let z = if alt { format!("{:.*}", p - 1, 0.0) } else { "0".into() };
        return if f.is_sign_negative() { format!("-{z}") } else { z };
    }
    // Exponent after rounding to p significant digits.
    let s = format!("{:.*e}", p - 1, f);
    let exp: i32 = s.split_once('e').unwrap().1.parse().unwrap();
    let out = if exp >= -4 && exp < p as i32 {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        let t = format!("{:.*}", decimals, f);
        if alt {
            t
        } else {
            strip_zeros(&t)
        }
    } else {
        let t = sci(f, p - 1, false);
        if alt {
            t
        } else {
            let (m, e) = t.split_once('e').unwrap();
            format!("{}e{}", strip_zeros(m), e)
        }
    };
    if upper {
        out.to_uppercase()
    } else {
        out
    }
}

fn strip_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

fn nonfinite(f: f64, upper: bool) -> String {
    let s = if f.is_nan() {
        "nan"
    } else if f > 0.0 {
        "inf"
    } else {
        "-inf"
    };
    if upper {
        s.to_uppercase()
    } else {
        s.to_string()
    }
}

// ----------------------------------------------------------------- format spec

#[derive(Default, Debug)]
struct Spec {
    fill: Option<char>,
    align: Option<char>,
    sign: Option<char>,
    alt: bool,
    zero: bool,
    width: usize,
    grouping: Option<char>,
    prec: Option<usize>,
    ty: Option<char>,
}

fn parse_spec(spec: &str) -> Result<Spec> {
    let c: Vec<char> = spec.chars().collect();
    let mut i = 0;
    let mut s = Spec::default();
    let is_align = |ch: char| matches!(ch, '<' | '>' | '^' | '=');
    if c.len() >= 2 && is_align(c[1]) {
        s.fill = Some(c[0]);
        s.align = Some(c[1]);
        i = 2;
    } else if !c.is_empty() && is_align(c[0]) {
        s.align = Some(c[0]);
        i = 1;
    }
    if i < c.len() && matches!(c[i], '+' | '-' | ' ') {
        s.sign = Some(c[i]);
        i += 1;
    }
    if i < c.len() && c[i] == '#' {
        s.alt = true;
        i += 1;
    }
    if i < c.len() && c[i] == '0' {
        s.zero = true;
        i += 1;
    }
    let st = i;
    while i < c.len() && c[i].is_ascii_digit() {
        i += 1;
    }
    if i > st {
        s.width = c[st..i].iter().collect::<String>().parse().unwrap();
    }
    if i < c.len() && (c[i] == ',' || c[i] == '_') {
        s.grouping = Some(c[i]);
        i += 1;
    }
    if i < c.len() && c[i] == '.' {
        i += 1;
        let st = i;
        while i < c.len() && c[i].is_ascii_digit() {
            i += 1;
        }
        s.prec = Some(c[st..i].iter().collect::<String>().parse().map_err(|_| bad_spec(spec))?);
    }
    if i < c.len() {
        s.ty = Some(c[i]);
        i += 1;
    }
    if i != c.len() {
        return Err(bad_spec(spec));
    }
    Ok(s)
}

fn bad_spec(spec: &str) -> Error {
    Error::python(format!("ValueError: invalid format specifier '{spec}'"))
}

fn group(int_part: &str, sep: char) -> String {
    let bytes: Vec<char> = int_part.chars().collect();
    let mut out = String::new();
    for (i, ch) in bytes.iter().enumerate() {
        if i > 0 && (bytes.len() - i).is_multiple_of(3) {
            out.push(sep);
        }
        out.push(*ch);
    }
    out
}

fn pad(body: String, sign: &str, s: &Spec, numeric: bool) -> String {
    let len = body.chars().count() + sign.chars().count();
    if len >= s.width {
        return format!("{sign}{body}");
    }
    let n = s.width - len;
    let (fill, align) = if s.zero && s.align.is_none() && numeric {
        ('0', '=')
    } else {
        (s.fill.unwrap_or(' '), s.align.unwrap_or(if numeric { '>' } else { '<' }))
    };
    let f = |k: usize| fill.to_string().repeat(k);
    match align {
        '<' => format!("{sign}{body}{}", f(n)),
        '>' => format!("{}{sign}{body}", f(n)),
        '^' => format!("{}{sign}{body}{}", f(n / 2), f(n - n / 2)),
        _ => format!("{sign}{}{body}", f(n)),
    }
}

/// Apply a format spec to a value (`format(v, spec)`).
pub fn format_value(v: &Value, spec: &str) -> Result<String> {
    let s = parse_spec(spec)?;
    match v {
        Value::Int(_) | Value::Bool(_) if !matches!(s.ty, Some('e' | 'E' | 'f' | 'F' | 'g' | 'G' | '%')) => {
            let i = v.as_int().unwrap();
            if s.ty.is_none() && matches!(v, Value::Bool(_)) && spec.is_empty() {
                return Ok(to_str(v));
            }
            let digits = match s.ty {
                None | Some('d') | Some('n') => i.unsigned_abs().to_string(),
                Some('x') => format!("{:x}", i.unsigned_abs()),
                Some('X') => format!("{:X}", i.unsigned_abs()),
                Some('o') => format!("{:o}", i.unsigned_abs()),
                Some('b') => format!("{:b}", i.unsigned_abs()),
                Some('c') => char::from_u32(i as u32).map(|c| c.to_string()).unwrap_or_default(),
                Some(t) => {
                    return Err(Error::python(format!(
                        "ValueError: Unknown format code '{t}' for object of type 'int'"
                    )))
                }
            };
            let digits = match s.grouping {
                Some(g) => group(&digits, g),
                None => digits,
            };
            let prefix = if s.alt {
                match s.ty {
                    Some('x') => "0x",
                    Some('X') => "0X",
                    Some('o') => "0o",
                    Some('b') => "0b",
                    _ => "",
                }
            } else {
                ""
            };
            let sign = sign_str(i < 0, s.sign);
            Ok(pad(format!("{prefix}{digits}"), &sign, &s, true))
        }
        Value::Int(_) | Value::Bool(_) | Value::Float(_) => {
            let f = v.as_f64().unwrap();
            let neg = f.is_sign_negative();
            let a = f.abs();
            let body = match s.ty {
                Some('f') | Some('F') => {
                    if a.is_finite() {
                        format!("{:.*}", s.prec.unwrap_or(6), a)
                    } else {
                        nonfinite(a, s.ty == Some('F'))
                    }
                }
                Some('e') | Some('E') => {
                    if a.is_finite() {
                        sci(a, s.prec.unwrap_or(6), s.ty == Some('E'))
                    } else {
                        nonfinite(a, s.ty == Some('E'))
                    }
                }
                Some('g') | Some('G') | Some('n') => general(a, s.prec.unwrap_or(6), s.ty == Some('G'), s.alt),
                Some('%') => format!("{:.*}%", s.prec.unwrap_or(6), a * 100.0),
                None => match s.prec {
                    Some(p) => {
                        let g = general(a, p, false, false);
                        if g.contains(['.', 'e', 'n', 'i']) {
                            g
                        } else {
                            format!("{g}.0")
                        }
                    }
                    None => float_repr(a),
                },
                Some(t) => {
                    return Err(Error::python(format!(
                        "ValueError: Unknown format code '{t}' for object of type 'float'"
                    )))
                }
            };
            let body = match s.grouping {
                Some(g) => {
                    let (ip, rest) = match body.find(|c: char| !c.is_ascii_digit()) {
                        Some(p) => (&body[..p], &body[p..]),
                        None => (&body[..], ""),
                    };
                    format!("{}{}", group(ip, g), rest)
                }
                None => body,
            };
            let sign = sign_str(neg && !(f.is_nan()), s.sign);
            Ok(pad(body, &sign, &s, true))
        }
        _ => {
            if let Some(t) = s.ty {
                if t != 's' {
                    return Err(Error::python(format!(
                        "ValueError: Unknown format code '{t}' for object of type '{}'",
                        v.type_name()
                    )));
                }
            }
            let mut text = to_str(v);
            if let Some(p) = s.prec {
                text = text.chars().take(p).collect();
            }
            Ok(pad(text, "", &s, false))
        }
    }
}

fn sign_str(neg: bool, sign: Option<char>) -> String {
    if neg {
        "-".into()
    } else {
        match sign {
            Some('+') => "+".into(),
            Some(' ') => " ".into(),
            _ => String::new(),
        }
    }
}

// ----------------------------------------------------------------- printf

/// `fmt % args`.
pub fn percent(fmt: &str, args: &Value) -> Result<String> {
    let positional: Vec<Value> = match args {
        Value::Tuple(t) => t.as_ref().clone(),
        Value::Dict(_) => Vec::new(),
        v => vec![v.clone()],
    };
    let mapping = match args {
        Value::Dict(d) => Some(d.clone()),
        _ => None,
    };
    let mut next = 0usize;
    let take = |next: &mut usize| -> Result<Value> {
        let v = positional
            .get(*next)
            .cloned()
            .ok_or_else(|| Error::python("TypeError: not enough arguments for format string"))?;
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
            return Err(Error::python("ValueError: incomplete format"));
        }
        if c[i] == '%' {
            out.push('%');
            i += 1;
            continue;
        }
        let mut value: Option<Value> = None;
        if c[i] == '(' {
            let st = i + 1;
            while i < c.len() && c[i] != ')' {
                i += 1;
            }
            let key: String = c[st..i].iter().collect();
            i += 1;
            let d = mapping.as_ref().ok_or_else(|| Error::python("TypeError: format requires a mapping"))?;
            value = Some(
                d.borrow()
                    .get(&Value::str(&key))
                    .cloned()
                    .ok_or_else(|| Error::python(format!("KeyError: '{key}'")))?,
            );
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
            spec.width = take(&mut next)?.as_int().unwrap_or(0) as usize;
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
                spec.prec = Some(take(&mut next)?.as_int().unwrap_or(0) as usize);
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
            return Err(Error::python("ValueError: incomplete format"));
        }
        let conv = c[i];
        i += 1;
        let v = match value {
            Some(v) => v,
            None => take(&mut next)?,
        };
        if spec.align == Some('<') {
            spec.zero = false;
        }
        let text = match conv {
            's' | 'r' | 'a' => {
                let mut t = if conv == 's' { to_str(&v) } else { repr(&v) };
                if let Some(p) = spec.prec {
                    t = t.chars().take(p).collect();
                }
                spec.zero = false;
                pad(t, "", &spec, spec.align.is_none())
            }
            'd' | 'i' | 'u' => {
                let n = match &v {
                    Value::Float(f) => f.trunc() as i64,
                    _ => v.as_int().ok_or_else(|| {
                        Error::python(format!("TypeError: %d format: a number is required, not {}", v.type_name()))
                    })?,
                };
                let sign = sign_str(n < 0, spec.sign);
                pad(n.unsigned_abs().to_string(), &sign, &spec, true)
            }
            'x' | 'X' | 'o' => {
                let n = v.as_int().ok_or_else(|| Error::python("TypeError: an integer is required"))?;
                let body = match conv {
                    'x' => format!("{:x}", n.unsigned_abs()),
                    'X' => format!("{:X}", n.unsigned_abs()),
                    _ => format!("{:o}", n.unsigned_abs()),
                };
                pad(body, &sign_str(n < 0, spec.sign), &spec, true)
            }
            'e' | 'E' | 'f' | 'F' | 'g' | 'G' => {
                let f = v
                    .as_f64()
                    .ok_or_else(|| Error::python(format!("TypeError: must be real number, not {}", v.type_name())))?;
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
            'c' => match &v {
                Value::Str(s) => s.to_string(),
                _ => v.as_int().and_then(|n| char::from_u32(n as u32)).map(|c| c.to_string()).unwrap_or_default(),
            },
            o => return Err(Error::python(format!("ValueError: unsupported format character '{o}'"))),
        };
        out.push_str(&text);
    }
    if mapping.is_none() && next < positional.len() {
        return Err(Error::python("TypeError: not all arguments converted during string formatting"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_repr_matches_python() {
        for (f, s) in [
            (1.0, "1.0"),
            (0.1, "0.1"),
            (1e16, "1e+16"),
            (1.5e-7, "1.5e-07"),
            (123456.789, "123456.789"),
            (0.0001, "0.0001"),
            (0.00001, "1e-05"),
            (-2.5, "-2.5"),
            (1e15, "1000000000000000.0"),
            (0.6, "0.6"),
            (1.23400e5, "123400.0"),
        ] {
            assert_eq!(float_repr(f), s);
        }
    }

    #[test]
    fn percent_formats() {
        let t = Value::tuple(vec![Value::Int(5), Value::Float(1.23456), Value::str("ab")]);
        assert_eq!(percent("%3d|%.2f|%-4s|", &t).unwrap(), "  5|1.23|ab  |");
        assert_eq!(percent("%e", &Value::Float(12345.678)).unwrap(), "1.234568e+04");
        assert_eq!(percent("%g", &Value::Float(0.00001234)).unwrap(), "1.234e-05");
        assert_eq!(percent("%g", &Value::Float(100000.0)).unwrap(), "100000");
        assert_eq!(percent("%g", &Value::Float(1e6)).unwrap(), "1e+06");
        assert_eq!(percent("%05.1f", &Value::Float(-2.25)).unwrap(), "-02.2");
        assert_eq!(percent("100%%", &Value::tuple(vec![])).unwrap(), "100%");
    }

    #[test]
    fn format_specs() {
        assert_eq!(format_value(&Value::Float(1.23456), ".3f").unwrap(), "1.235");
        assert_eq!(format_value(&Value::Int(42), ">6").unwrap(), "    42");
        assert_eq!(format_value(&Value::Int(42), "06d").unwrap(), "000042");
        assert_eq!(format_value(&Value::str("ab"), "^6").unwrap(), "  ab  ");
        assert_eq!(format_value(&Value::Float(1234.5), ".3e").unwrap(), "1.234e+03");
        assert_eq!(format_value(&Value::Float(0.5), "").unwrap(), "0.5");
        assert_eq!(format_value(&Value::Int(1234567), ",").unwrap(), "1,234,567");
        assert_eq!(format_value(&Value::Float(2.0), ".3").unwrap(), "2.0");
    }
}
