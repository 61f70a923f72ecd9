//! Fortran real edit descriptors, as Code_Aster's `FORMAT_R` keywords write them (`E12.5`,
//! `1PE21.14`, `F10.3`, `G12.5`, `D12.5`), written the way Code_Aster's Python tables do: as the
//! printf directive `%W.DE` (`%W.Df`, `%W.DG`); the scale factor `nP` is accepted and dropped.

use super::number::{fixed, general, nonfinite, sci};
use super::spec::{pad, sign_str, Spec};

/// A checked real format.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RealFormat {
    conv: char,
    width: usize,
    prec: Option<usize>,
}

/// The widest field or longest precision a `FORMAT_R` may ask for.
const MAX_FIELD: usize = 1000;

/// `E12.5`, Code_Aster's default for tables.
impl Default for RealFormat {
    fn default() -> RealFormat {
        RealFormat { conv: 'E', width: 12, prec: Some(5) }
    }
}

impl RealFormat {
    /// Parse a descriptor; the error says what is wrong with it.
    pub fn parse(text: &str) -> Result<RealFormat, String> {
        let bad = |why: &str| format!("'{text}' is not a Fortran real format such as E12.5, 1PE21.14 or F10.3: {why}");
        let t = text.trim().to_ascii_uppercase();
        // An optional scale factor: digits then P.
        let t = match t.find('P') {
            Some(p) if t[..p].chars().all(|c| c.is_ascii_digit() || c == '-') => &t[p + 1..],
            Some(_) => return Err(bad("a scale factor is written nP")),
            None => &t[..],
        };
        let mut chars = t.chars();
        let conv = match chars.next() {
            Some('E' | 'D') => 'E',
            Some('F') => 'f',
            Some('G') => 'G',
            Some(c) => return Err(bad(&format!("'{c}' is not one of the real descriptors E, D, F, G"))),
            None => return Err(bad("the descriptor letter is missing")),
        };
        let rest = chars.as_str();
        let (w, d) = match rest.split_once('.') {
            Some((w, d)) => (w, Some(d)),
            None => (rest, None),
        };
        let number = |s: &str, what: &str| -> Result<usize, String> {
            match s.parse::<usize>() {
                Ok(n) if n <= MAX_FIELD && s.chars().all(|c| c.is_ascii_digit()) => Ok(n),
                Ok(_) => Err(bad(&format!("the {what} is above {MAX_FIELD}"))),
                Err(_) => Err(bad(&format!("the {what} '{s}' is not a number"))),
            }
        };
        let width = if w.is_empty() { 0 } else { number(w, "width")? };
        let prec = match d {
            Some(d) => Some(number(d, "precision")?),
            None => None,
        };
        Ok(RealFormat { conv, width, prec })
    }

    /// `x` written with this format.
    pub fn format(&self, x: f64) -> String {
        let (a, p) = (x.abs(), self.prec.unwrap_or(6));
        let body = match self.conv {
            _ if !a.is_finite() => nonfinite(a, self.conv != 'f'),
            'E' => sci(a, p, true),
            'f' => fixed(a, p),
            _ => general(a, p, true, false),
        };
        let spec = Spec { width: self.width, ..Spec::default() };
        pad(body, &sign_str(x.is_sign_negative() && !x.is_nan(), None), &spec, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_real_formats() {
        let f = |t: &str, x: f64| RealFormat::parse(t).unwrap().format(x);
        // Python: '%12.5E' % 0.5, '%21.14E' % -1.5, '%10.3f' % 2.25, '%12.5G' % 1e-7
        assert_eq!(f("E12.5", 0.5), " 5.00000E-01");
        assert_eq!(f("1PE21.14", -1.5), "-1.50000000000000E+00");
        assert_eq!(f("F10.3", 2.25), "     2.250");
        assert_eq!(f("g12.5", 1e-7), "       1E-07");
        assert_eq!(f("D12.5", 0.5), " 5.00000E-01");
        assert_eq!(RealFormat::default(), RealFormat::parse("E12.5").unwrap());
        for bad in ["", "X12.5", "E12.x", "E99999999999999999999.5", "E12.2000", "1XE12.5", "é"] {
            assert!(RealFormat::parse(bad).is_err(), "{bad}");
        }
    }
}
