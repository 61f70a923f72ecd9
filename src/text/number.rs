//! Python's text forms of floats: `repr`, `%e`, `%f`, `%g`.
//!
//! Rust's formatter refuses precisions above `u16::MAX` (and `{:.65535e}` overflows inside it), so
//! the digits are asked for only as far as they can be non-zero and the rest is zeros, as Python
//! writes them: an `f64` has at most 767 significant decimal digits and 1074 after the point.

/// `repr(float)`: the shortest round-trip digits, positional between 1e-4 and 1e16.
pub fn float_repr(f: f64) -> String {
    if !f.is_finite() {
        return nonfinite(f, false);
    }
    if f == 0.0 {
        return if f.is_sign_negative() { "-0.0".into() } else { "0.0".into() };
    }
    let (neg, digits, exp) = shortest(f);
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

/// The shortest round-trip digits of a finite non-zero float: sign, digits, decimal exponent.
fn shortest(f: f64) -> (bool, String, i32) {
    let s = format!("{:e}", f.abs()); // e.g. "1.5e-7"
    let (mant, exp) = split_exp(&s);
    (f.is_sign_negative(), mant.chars().filter(char::is_ascii_digit).collect(), exp)
}

/// `"1.5e-7"` → `("1.5", -7)`; Rust writes the exponent of every finite float.
fn split_exp(s: &str) -> (&str, i32) {
    match s.split_once('e') {
        Some((m, e)) => (m, e.parse().unwrap_or(0)),
        None => (s, 0),
    }
}

/// Significant digits beyond which an `f64` has only zeros.
const MAX_SIGNIFICANT: usize = 800;
/// Digits after the point beyond which an `f64` has only zeros.
const MAX_DECIMALS: usize = 1100;

/// `%.{prec}f` of a finite float.
pub fn fixed(f: f64, prec: usize) -> String {
    if !f.is_finite() {
        return nonfinite(f, false);
    }
    let mut s = format!("{:.*}", prec.min(MAX_DECIMALS), f);
    if prec > MAX_DECIMALS {
        s.extend(std::iter::repeat_n('0', prec - MAX_DECIMALS));
    }
    s
}

/// Scientific notation with Python's exponent form (`1.500000e-07`); `nan`/`inf` as Python writes them.
pub fn sci(f: f64, prec: usize, upper: bool) -> String {
    if !f.is_finite() {
        return nonfinite(f, upper);
    }
    let s = format!("{:.*e}", prec.min(MAX_SIGNIFICANT), f);
    let (m, e) = split_exp(&s);
    let mut m = m.to_string();
    if prec > MAX_SIGNIFICANT {
        m.extend(std::iter::repeat_n('0', prec - MAX_SIGNIFICANT));
    }
    let out = format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs());
    if upper {
        out.to_uppercase()
    } else {
        out
    }
}

/// `%g` / `{:g}`: `alt` keeps trailing zeros.
pub fn general(f: f64, prec: usize, upper: bool, alt: bool) -> String {
    let p = prec.max(1);
    general_with(f, p, upper, alt, p as i64)
}

/// A float under a format spec with a precision and no type (`'{:.3}'`): `%g` with at least one digit
/// after the point, in scientific notation from one exponent earlier than `%g`.
pub fn general_dot0(f: f64, prec: usize) -> String {
    let p = prec.max(1);
    let s = general_with(f, p, false, false, p as i64 - 1);
    if s.contains(['.', 'e', 'n', 'i']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// `%g` switching to scientific notation for exponents below -4 or from `sci_from` on.
fn general_with(f: f64, p: usize, upper: bool, alt: bool, sci_from: i64) -> String {
    if !f.is_finite() {
        return nonfinite(f, upper);
    }
    if f == 0.0 {
        let z = if alt { fixed(0.0, p - 1) } else { "0".into() };
        return if f.is_sign_negative() { format!("-{z}") } else { z };
    }
    // The exponent after rounding to p significant digits.
    let exp = split_exp(&sci(f, p - 1, false)).1 as i64;
    let out = if exp >= -4 && exp < sci_from {
        let decimals = (p as i64 - 1 - exp).max(0) as usize;
        let t = fixed(f, decimals);
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
            let (m, e) = t.split_once('e').unwrap_or((&t, ""));
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

/// `nan`, `inf`, `-inf` (upper case for `%E`, `%F`, `%G`).
pub fn nonfinite(f: f64, upper: bool) -> String {
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
            (f64::NAN, "nan"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            assert_eq!(float_repr(f), s);
        }
    }

    #[test]
    fn non_finite_and_huge_precisions_do_not_panic() {
        // Python: '%e' % float('nan'), '%E' % float('-inf')
        assert_eq!(sci(f64::NAN, 6, false), "nan");
        assert_eq!(sci(f64::NEG_INFINITY, 3, true), "-INF");
        // Rust's own formatter panics from precision 65535 on.
        let s = sci(1.5, 70_000, false);
        assert_eq!(s.len(), "1.".len() + 70_000 + "e+00".len());
        assert!(s.starts_with("1.5000") && s.ends_with("0e+00"));
        let s = fixed(5e-324, 2000);
        assert_eq!(s.len(), 2002);
        // Python: len('%.1100f' % 5e-324) == 1102, its last non-zero digit at place 1074.
        assert_eq!(fixed(5e-324, 1100).trim_end_matches('0').len(), 2 + 1074);
        assert_eq!(general(1.5, 70_000, false, false), "1.5");
    }
}
