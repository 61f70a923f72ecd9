//! `.export` files: Code_Aster's test-runner description of a case.
//!
//! `P key value` lines set parameters; `F type path D|R|DR unit` lines map a
//! file (relative to the export's folder) to a logical unit, as data (D),
//! result (R) or both.

use crate::diag::{Error, Result};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// A time limit in seconds (`60`, `0.5`): positive and finite, else a message saying why not.
pub fn parse_seconds(text: &str) -> std::result::Result<Duration, String> {
    match text.trim().parse::<f64>() {
        Ok(s) if s > 0.0 => {
            Duration::try_from_secs_f64(s).map_err(|_| format!("'{text}' is too large a number of seconds"))
        }
        _ => Err(format!("'{text}' is not a positive number of seconds")),
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    In,
    Out,
    InOut,
}

#[derive(Debug, Clone)]
pub struct FileLine {
    pub kind: String,
    pub path: PathBuf,
    pub dir: Dir,
    pub unit: i64,
    /// Where the line is: `file.export:N: F type path D unit`, for messages about the file it names.
    pub origin: String,
}

#[derive(Debug, Clone, Default)]
pub struct Export {
    pub params: Vec<(String, String)>,
    pub files: Vec<FileLine>,
}

impl Export {
    pub fn param(&self, key: &str) -> Option<&str> {
        self.params.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }

    /// `P time_limit SECONDS`, if given; an error if it is not a positive number of seconds.
    pub fn time_limit(&self) -> Result<Option<Duration>> {
        self.param("time_limit")
            .map(|t| parse_seconds(t).map_err(|e| Error::io(format!("P time_limit {e}"))))
            .transpose()
    }

    /// A validation case ignores NON_REGRESSION checks (`P testlist ... validation`).
    pub fn is_validation(&self) -> bool {
        self.param("testlist").map(|v| v.split_whitespace().any(|w| w == "validation")).unwrap_or(false)
    }

    /// The command files, in unit order.
    pub fn comm_files(&self) -> Vec<&FileLine> {
        let mut v: Vec<&FileLine> = self.files.iter().filter(|f| f.kind == "comm").collect();
        v.sort_by_key(|f| f.unit);
        v
    }

    pub fn read(path: &Path) -> Result<Export> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(format!("{}: {e}", path.display())))?;
        Self::parse(&text, path.parent().unwrap_or(Path::new(".")), &path.display().to_string())
    }

    pub fn parse(text: &str, base: &Path, name: &str) -> Result<Export> {
        let mut ex = Export::default();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let mut w = line.split_whitespace();
            match w.next() {
                Some("P") => {
                    let key = w.next().unwrap_or("").to_string();
                    let val: Vec<&str> = w.collect();
                    ex.params.push((key, val.join(" ")));
                }
                Some("F") | Some("R") => {
                    let fields: Vec<&str> = w.collect();
                    if fields.len() != 4 {
                        return Err(Error::io(format!(
                            "{name}:{}: a file line needs 'F type path D|R|DR unit', got '{line}'",
                            i + 1
                        )));
                    }
                    let dir = match fields[2] {
                        "D" => Dir::In,
                        "R" => Dir::Out,
                        "DR" | "RD" => Dir::InOut,
                        d => return Err(Error::io(format!("{name}:{}: unknown direction '{d}' (D, R or DR)", i + 1))),
                    };
                    let unit = fields[3]
                        .parse()
                        .map_err(|_| Error::io(format!("{name}:{}: unit '{}' is not a number", i + 1, fields[3])))?;
                    let p = Path::new(fields[1]);
                    let path = if p.is_absolute() { p.to_path_buf() } else { base.join(p) };
                    let origin =
                        format!("{name}:{}: {}", i + 1, fields.iter().fold("F".to_string(), |s, f| s + " " + f));
                    ex.files.push(FileLine { kind: fields[0].to_string(), path, dir, unit, origin });
                }
                Some("A") | Some("N") => {}
                Some(other) => {
                    return Err(Error::io(format!("{name}:{}: unknown line type '{other}'", i + 1)));
                }
                None => {}
            }
        }
        Ok(ex)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_params_and_files() {
        let ex = Export::parse(
            "P time_limit 60\nP testlist submit verification sequential\n\nF comm a.comm D 1\n# F comm b D 2\nF libr t.31 D 31\nF rmed out.rmed R 80\n",
            Path::new("/x"),
            "t.export",
        )
        .unwrap();
        assert_eq!(ex.param("time_limit"), Some("60"));
        assert_eq!(ex.time_limit().unwrap(), Some(Duration::from_secs(60)));
        for bad in ["0", "-1", "nan", "inf", "1e300", "soon"] {
            let e = Export::parse(&format!("P time_limit {bad}\n"), Path::new("."), "e").unwrap();
            assert!(e.time_limit().is_err(), "{bad}");
        }
        assert!(!ex.is_validation());
        assert_eq!(ex.comm_files().len(), 1);
        assert_eq!(ex.files[1].path, Path::new("/x/t.31"));
        assert_eq!(ex.files[2].dir, Dir::Out);
        assert!(Export::parse("F comm a.comm Q 1\n", Path::new("."), "e").is_err());
    }
}
