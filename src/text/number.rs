//! Python's text forms of floats: `repr`, `%e`, `%g`.

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
        ] {
            assert_eq!(float_repr(f), s);
        }
    }
}
