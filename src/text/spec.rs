//! The format-spec mini-language of `format()`, `str.format` and f-strings
//! (`[[fill]align][sign][#][0][width][,|_][.precision][type]`), as CPython 3.11 reads it.

use super::number::{fixed, float_repr, general, general_dot0, nonfinite, sci};
use super::{check_size, FormatError, Number, Operand};

/// A parsed format spec; `%`-directives fill the same fields.
#[derive(Default, Debug, Clone)]
pub struct Spec {
    pub fill: Option<char>,
    pub align: Option<char>,
    pub sign: Option<char>,
    pub alt: bool,
    pub zero: bool,
    pub width: usize,
    pub grouping: Option<char>,
    pub prec: Option<usize>,
    pub ty: Option<char>,
}

/// Decimal digits at `c[*i..]` as a count, or `None` past `limit`.
fn digits(c: &[char], i: &mut usize, limit: usize) -> Option<usize> {
    let mut n: usize = 0;
    while let Some(d) = c.get(*i).and_then(|ch| ch.to_digit(10)) {
        n = n.checked_mul(10).and_then(|n| n.checked_add(d as usize)).filter(|n| *n <= limit)?;
        *i += 1;
    }
    Some(n)
}

impl Spec {
    /// Parse `spec` for a value of type `type_name` (named by the error of a malformed spec).
    pub fn parse(spec: &str, type_name: &str) -> Result<Spec, FormatError> {
        let too_many = || FormatError::value("Too many decimal digits in format string");
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
        s.width = digits(&c, &mut i, isize::MAX as usize).ok_or_else(too_many)?;
        if i < c.len() && (c[i] == ',' || c[i] == '_') {
            s.grouping = Some(c[i]);
            i += 1;
            if i < c.len() && (c[i] == ',' || c[i] == '_') {
                return Err(FormatError::value("Cannot specify both ',' and '_'."));
            }
        }
        if i < c.len() && c[i] == '.' {
            i += 1;
            let st = i;
            let p = digits(&c, &mut i, isize::MAX as usize).ok_or_else(too_many)?;
            if i == st {
                return Err(FormatError::value("Format specifier missing precision"));
            }
            s.prec = Some(p);
        }
        if c.len() - i > 1 {
            return Err(FormatError::value(format!(
                "Invalid format specifier '{spec}' for object of type '{type_name}'"
            )));
        }
        s.ty = c.get(i).copied();
        check_size("format width", s.width)?;
        if let Some(p) = s.prec {
            check_size("format precision", p)?;
        }
        Ok(s)
    }
}

/// Group the digits of `int_part` by `size` with `sep`.
fn group(int_part: &str, sep: char, size: usize) -> String {
    let digits: Vec<char> = int_part.chars().collect();
    let mut out = String::new();
    for (i, ch) in digits.iter().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(size) {
            out.push(sep);
        }
        out.push(*ch);
    }
    out
}

/// Pad `sign` + `body` to the spec's width, with its fill and alignment (numbers right, text left; the
/// `0` flag fills with zeros between the sign and a number).
pub(crate) fn pad(body: String, sign: &str, s: &Spec, numeric: bool) -> String {
    let len = body.chars().count() + sign.chars().count();
    if len >= s.width {
        return format!("{sign}{body}");
    }
    let n = s.width - len;
    let fill = s.fill.unwrap_or(if s.zero { '0' } else { ' ' });
    let align = s.align.unwrap_or(match (numeric, s.zero) {
        (true, true) => '=',
        (true, false) => '>',
        (false, _) => '<',
    });
    let f = |k: usize| std::iter::repeat_n(fill, k).collect::<String>();
    match align {
        '<' => format!("{sign}{body}{}", f(n)),
        '>' => format!("{}{sign}{body}", f(n)),
        '^' => format!("{}{sign}{body}{}", f(n / 2), f(n - n / 2)),
        _ => format!("{sign}{}{body}", f(n)),
    }
}

pub(crate) fn sign_str(neg: bool, sign: Option<char>) -> String {
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

/// The digits of a number under grouping, zero-filled to the width when the `0` flag (and no other
/// fill) asks for it, as CPython fills: `format(1234567, '012,')` is `'0,001,234,567'`.
fn grouped(int_part: &str, rest: &str, sign: &str, s: &Spec, size: usize) -> String {
    let Some(sep) = s.grouping else {
        return format!("{int_part}{rest}");
    };
    let zero_fill = s.zero && s.fill.is_none() && matches!(s.align, None | Some('='));
    let mut n = int_part.len();
    if zero_fill {
        let fixed_len = sign.chars().count() + rest.chars().count();
        while fixed_len + n + (n.max(1) - 1) / size < s.width {
            n += 1;
        }
    }
    let padded: String = std::iter::repeat_n('0', n - int_part.len()).chain(int_part.chars()).collect();
    format!("{}{rest}", group(&padded, sep, size))
}

/// `format(v, spec)`.
pub fn format<O: Operand + ?Sized>(v: &O, spec: &str) -> Result<String, FormatError> {
    let s = Spec::parse(spec, &v.type_name())?;
    match v.number() {
        Some(Number::Bool(_)) if spec.is_empty() => Ok(v.to_str()),
        Some(n @ (Number::Int(_) | Number::Bool(_)))
            if !matches!(s.ty, Some('e' | 'E' | 'f' | 'F' | 'g' | 'G' | '%')) =>
        {
            format_int(n.as_int().unwrap_or(0), &s)
        }
        Some(n) => format_float(n.as_f64(), &s),
        None => match v.text() {
            Some(t) => format_text(t, &s),
            None if spec.is_empty() => Ok(v.to_str()),
            None => Err(FormatError::type_error(format!(
                "unsupported format string passed to {}.__format__",
                v.type_name()
            ))),
        },
    }
}

fn format_int(i: i64, s: &Spec) -> Result<String, FormatError> {
    let ty = s.ty.unwrap_or('d');
    if s.prec.is_some() {
        return Err(FormatError::value("Precision not allowed in integer format specifier"));
    }
    if let (Some(g), 'c' | 'n' | 'x' | 'X' | 'o' | 'b') = (s.grouping, ty) {
        if g == ',' || matches!(ty, 'c' | 'n') {
            return Err(FormatError::value(format!("Cannot specify '{g}' with '{ty}'.")));
        }
    }
    if ty == 'c' {
        if s.sign.is_some() {
            return Err(FormatError::value("Sign not allowed with integer format specifier 'c'"));
        }
        if s.alt {
            return Err(FormatError::value("Alternate form (#) not allowed with integer format specifier 'c'"));
        }
        return Ok(pad(char_of(i)?, "", s, true));
    }
    let a = i.unsigned_abs();
    let (digits, prefix, size) = match ty {
        'd' | 'n' => (a.to_string(), "", 3),
        'x' => (format!("{a:x}"), "0x", 4),
        'X' => (format!("{a:X}"), "0X", 4),
        'o' => (format!("{a:o}"), "0o", 4),
        'b' => (format!("{a:b}"), "0b", 4),
        t => return Err(FormatError::value(format!("Unknown format code '{t}' for object of type 'int'"))),
    };
    let sign = sign_str(i < 0, s.sign) + if s.alt { prefix } else { "" };
    Ok(pad(grouped(&digits, "", &sign, s, size), &sign, s, true))
}

/// The character of code point `i` (`%c`, `{:c}`).
pub(crate) fn char_of(i: i64) -> Result<String, FormatError> {
    if !(0..0x110000).contains(&i) {
        return Err(FormatError::new("OverflowError", "%c arg not in range(0x110000)"));
    }
    char::from_u32(i as u32).map(String::from).ok_or_else(|| {
        FormatError::value(format!(
            "%c arg {i:#x} is a surrogate code point, which this interpreter's strings cannot hold"
        ))
    })
}

fn format_float(f: f64, s: &Spec) -> Result<String, FormatError> {
    if let (Some(g), Some('n')) = (s.grouping, s.ty) {
        return Err(FormatError::value(format!("Cannot specify '{g}' with 'n'.")));
    }
    let a = f.abs();
    let upper = matches!(s.ty, Some('E' | 'F' | 'G'));
    let body = match s.ty {
        Some('f' | 'F' | 'e' | 'E' | 'g' | 'G' | 'n' | '%') | None if !a.is_finite() => nonfinite(a, upper),
        Some('f' | 'F') => with_point(fixed(a, s.prec.unwrap_or(6)), s.alt),
        Some('e' | 'E') => with_point(sci(a, s.prec.unwrap_or(6), upper), s.alt),
        Some('g' | 'G' | 'n') => general(a, s.prec.unwrap_or(6), upper, s.alt),
        Some('%') => with_point(fixed(a * 100.0, s.prec.unwrap_or(6)), s.alt),
        None => match s.prec {
            Some(p) => with_point(general_dot0(a, p), s.alt),
            None => float_repr(a),
        },
        Some(t) => return Err(FormatError::value(format!("Unknown format code '{t}' for object of type 'float'"))),
    };
    let body = if s.ty == Some('%') { body + "%" } else { body };
    let sign = sign_str(f.is_sign_negative() && !f.is_nan(), s.sign);
    let split = body.find(|c: char| !c.is_ascii_digit()).unwrap_or(body.len());
    let body = if a.is_finite() { grouped(&body[..split], &body[split..], &sign, s, 3) } else { body };
    Ok(pad(body, &sign, s, true))
}

/// The `#` flag keeps the decimal point of a number written without decimals (`'%#.0f' % 15` → `15.`).
pub(crate) fn with_point(body: String, alt: bool) -> String {
    if !alt || body.contains('.') || !body.starts_with(|c: char| c.is_ascii_digit()) {
        return body;
    }
    match body.find(['e', 'E']) {
        Some(p) => format!("{}.{}", &body[..p], &body[p..]),
        None => body + ".",
    }
}

fn format_text(t: &str, s: &Spec) -> Result<String, FormatError> {
    match s.ty {
        None | Some('s') => {}
        Some(ty) => return Err(FormatError::value(format!("Unknown format code '{ty}' for object of type 'str'"))),
    }
    if s.sign.is_some() {
        return Err(FormatError::value("Sign not allowed in string format specifier"));
    }
    if s.alt {
        return Err(FormatError::value("Alternate form (#) not allowed in string format specifier"));
    }
    if let Some(g) = s.grouping {
        return Err(FormatError::value(format!("Cannot specify '{g}' with 's'.")));
    }
    if s.align == Some('=') {
        return Err(FormatError::value("'=' alignment not allowed in string format specifier"));
    }
    let text: String = match s.prec {
        Some(p) => t.chars().take(p).collect(),
        None => t.to_string(),
    };
    Ok(pad(text, "", s, false))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_specs() {
        assert_eq!(format(&1.23456, ".3f").unwrap(), "1.235");
        assert_eq!(format(&1234.5, ".3e").unwrap(), "1.234e+03");
        assert_eq!(format(&0.5, "").unwrap(), "0.5");
        assert_eq!(format(&2.0, ".3").unwrap(), "2.0");
    }
}
