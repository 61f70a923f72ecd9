//! Localizations of integration points (`/GAUSS`): the reference element of a cell type, the points of
//! a field at integration points (ELGA) in it and their weights.
//!
//! ```text
//! /GAUSS/<name>       attrs GEO (geometry code), DIM (reference dimension), NBR (points), INM ("")
//! /GAUSS/<name>/COO   reference coordinates of the cell's nodes, MED node order, non-interlaced
//! /GAUSS/<name>/GAU   coordinates of the points, non-interlaced
//! /GAUSS/<name>/VAL   weights
//! ```
//!
//! Code_Aster names a localization after its reference element and its family of points (`irmpg1`): the
//! element's name padded to 8 characters, then the family's, blanks turned into `_`
//! (`QU8_____FPG4NOS`); a name already used for other points gets a counter in characters 25 to 32.

use super::read::{attr_int, attr_str, read_f64s};
use super::types::MedType;
use super::write::{new_group, put_i32, put_str, to_i32};
use super::{h5err, ioerr, NAME};
use crate::diag::Result;
use crate::mesh::CellType;
use hdf5_metno as hdf5;
use std::collections::BTreeMap;
use std::path::Path;

/// The integration points of a field on the cells of one type.
#[derive(Debug, Clone, PartialEq)]
pub struct Localization {
    pub name: String,
    pub cell: CellType,
    /// The reference coordinates of the cell's nodes, in Code_Aster's node order (`dim` of the 3 used).
    pub ref_nodes: Vec<[f64; 3]>,
    /// The points, in the order of the field's values.
    pub points: Vec<[f64; 3]>,
    pub weights: Vec<f64>,
}

impl Localization {
    /// The reference dimension (that of the cell).
    pub fn dim(&self) -> usize {
        self.cell.dim().max(1)
    }

    /// Code_Aster's name of the localization of family `family` on the reference element of `cell`
    /// (`HE8_____FPG8`, `QU8_____FPG4NOS`).
    pub fn aster_name(cell: CellType, family: &str) -> String {
        let elrefe = MedType::of(cell).med_name;
        let raw = format!("{elrefe:<8}{family:<8}");
        raw.trim_end().replace(' ', "_")
    }

    /// Same points and weights (to round-off) and same reference element.
    pub fn same_points(&self, other: &Localization) -> bool {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
        let d = self.dim();
        self.cell == other.cell
            && self.points.len() == other.points.len()
            && self.points.iter().zip(&other.points).all(|(p, q)| (0..d).all(|k| close(p[k], q[k])))
            && self.weights.iter().zip(&other.weights).all(|(a, b)| close(*a, *b))
    }
}

fn non_interlaced(points: &[[f64; 3]], dim: usize) -> Vec<f64> {
    (0..dim).flat_map(|k| points.iter().map(move |p| p[k])).collect()
}

fn interlace(flat: &[f64], n: usize, dim: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let mut p = [0.0; 3];
            for (k, x) in p.iter_mut().enumerate().take(dim) {
                *x = flat[k * n + i];
            }
            p
        })
        .collect()
}

/// The localizations stored in a file, by name.
pub(crate) fn read_all(path: &Path, file: &hdf5::File) -> Result<BTreeMap<String, Localization>> {
    let mut out = BTreeMap::new();
    if !file.link_exists("GAUSS") {
        return Ok(out);
    }
    let g = file.group("GAUSS").map_err(|e| h5err(path, "group /GAUSS", e))?;
    for name in g.member_names().map_err(|e| h5err(path, "listing /GAUSS", e))? {
        let lg = g.group(&name).map_err(|e| h5err(path, &format!("/GAUSS/{name}"), e))?;
        let geo = attr_int(path, &lg, "GEO")?.unwrap_or(0) as i32;
        let Some(mt) = MedType::by_geo(geo) else {
            // A localization on a cell type we do not know cannot carry a field we read: skipped.
            continue;
        };
        let dim = attr_int(path, &lg, "DIM")?.unwrap_or(mt.cell.dim() as i64).clamp(1, 3) as usize;
        let nbr = attr_int(path, &lg, "NBR")?.unwrap_or(0).max(0) as usize;
        let read = |ds: &str| -> Result<Vec<f64>> {
            let d = lg.dataset(ds).map_err(|e| h5err(path, &format!("/GAUSS/{name}/{ds}"), e))?;
            read_f64s(path, &d)
        };
        let (coo, gau, val) = (read("COO")?, read("GAU")?, read("VAL")?);
        let nno = mt.nnodes();
        if coo.len() != nno * dim || gau.len() != nbr * dim || val.len() != nbr {
            return Err(ioerr(
                path,
                format!(
                    "localization '{name}': {} node coordinates, {} point coordinates and {} weights for {nbr} \
                     points of a {} in {dim}D",
                    coo.len(),
                    gau.len(),
                    val.len(),
                    mt.cell.name()
                ),
            ));
        }
        let _ = attr_str(path, &lg, "INM")?;
        let ref_nodes = mt.to_aster(&interlace(&coo, nno, dim));
        out.insert(
            name.clone(),
            Localization { name, cell: mt.cell, ref_nodes, points: interlace(&gau, nbr, dim), weights: val },
        );
    }
    Ok(out)
}

/// Store `loc` in the file, or find it there: the name it has in the file (a name already used for other
/// points gets Code_Aster's counter).
pub(crate) fn ensure(path: &Path, file: &hdf5::File, loc: &Localization) -> Result<String> {
    let existing = read_all(path, file)?;
    let mut name = loc.name.clone();
    let mut counter = 0;
    loop {
        match existing.get(&name) {
            Some(there) if there.same_points(loc) => return Ok(name),
            Some(_) => {
                counter += 1;
                // irmpg1: the name in characters 1 to 24, the counter right-justified in 25 to 32.
                let base: String = format!("{:<24}", loc.name).chars().take(24).collect();
                name = format!("{base}{counter:>8}").replace(' ', "_");
            }
            None => break,
        }
    }
    if name.is_empty() || name.len() > NAME || !name.is_ascii() {
        return Err(ioerr(path, format!("bad localization name '{name}'")));
    }
    let g = match file.group("GAUSS") {
        Ok(g) => g,
        Err(_) => new_group(path, file, "GAUSS")?,
    };
    let lg = new_group(path, &g, &name)?;
    let mt = MedType::of(loc.cell);
    let dim = loc.dim();
    put_i32(path, &lg, "DIM", dim as i32)?;
    put_i32(path, &lg, "GEO", mt.geo)?;
    put_str(path, &lg, "INM", "")?;
    put_i32(path, &lg, "NBR", to_i32(path, loc.points.len())?)?;
    let med_nodes = mt.to_med(&loc.ref_nodes);
    for (ds, data) in [
        ("COO", non_interlaced(&med_nodes, dim)),
        ("GAU", non_interlaced(&loc.points, dim)),
        ("VAL", loc.weights.clone()),
    ] {
        lg.new_dataset_builder()
            .with_data(&data[..])
            .create(ds)
            .map_err(|e| h5err(path, &format!("localization {name} {ds}"), e))?;
    }
    Ok(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_as_code_aster_writes_them() {
        assert_eq!(Localization::aster_name(CellType::Hexa8, "FPG8"), "HE8_____FPG8");
        assert_eq!(Localization::aster_name(CellType::Quad8, "FPG4NOS"), "QU8_____FPG4NOS");
        assert_eq!(Localization::aster_name(CellType::Tetra10, "NOEU_S"), "T10_____NOEU_S");
    }
}
