//! The format-spec mini-language of `format()`, `str.format` and f-strings
//! (`[[fill]align][sign][#][0][width][,|_][.precision][type]`).

use super::number::{float_repr, general, nonfinite, sci};
use super::{FormatError, Number, Operand};

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

impl Spec {
    pub fn parse(spec: &str) -> Result<Spec, FormatError> {
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
}

fn bad_spec(spec: &str) -> FormatError {
    FormatError::value(format!("invalid format specifier '{spec}'"))
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

/// Pad `sign` + `body` to the spec's width, with its fill and alignment (numbers right, text left).
pub(crate) fn pad(body: String, sign: &str, s: &Spec, numeric: bool) -> String {
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

/// `format(v, spec)`.
pub fn format<O: Operand + ?Sized>(v: &O, spec: &str) -> Result<String, FormatError> {
    let s = Spec::parse(spec)?;
    match v.number() {
        Some(n @ (Number::Int(_) | Number::Bool(_)))
            if !matches!(s.ty, Some('e' | 'E' | 'f' | 'F' | 'g' | 'G' | '%')) =>
        {
            if s.ty.is_none() && matches!(n, Number::Bool(_)) && spec.is_empty() {
                return Ok(v.to_str());
            }
            let i = n.as_int().unwrap_or(0);
            let digits = match s.ty {
                None | Some('d') | Some('n') => i.unsigned_abs().to_string(),
                Some('x') => format!("{:x}", i.unsigned_abs()),
                Some('X') => format!("{:X}", i.unsigned_abs()),
                Some('o') => format!("{:o}", i.unsigned_abs()),
                Some('b') => format!("{:b}", i.unsigned_abs()),
                Some('c') => char::from_u32(i as u32).map(|c| c.to_string()).unwrap_or_default(),
                Some(t) => {
                    return Err(FormatError::value(format!("Unknown format code '{t}' for object of type 'int'")))
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
        Some(n) => {
            let f = n.as_f64();
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
                    return Err(FormatError::value(format!("Unknown format code '{t}' for object of type 'float'")))
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
        None => {
            if let Some(t) = s.ty {
                if t != 's' {
                    return Err(FormatError::value(format!(
                        "Unknown format code '{t}' for object of type '{}'",
                        v.type_name()
                    )));
                }
            }
            let mut text = v.to_str();
            if let Some(p) = s.prec {
                text = text.chars().take(p).collect();
            }
            Ok(pad(text, "", &s, false))
        }
    }
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
