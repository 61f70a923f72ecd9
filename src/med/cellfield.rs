//! Fields of every support over time steps (`/CHA`): at the nodes (`NOE`), constant on cells (`MAI.<TYP>`
//! without localization, Code_Aster's ELEM), at the nodes of each cell (`NOE.<TYP>`, ELNO) and at
//! integration points (`MAI.<TYP>` with a localization of `/GAUSS`, ELGA), on the whole mesh or on a
//! part of it through a profile (`/PROFILS`).
//!
//! ```text
//! /CHA/<field>                                   attrs MAI (mesh) NCO NOM (16 chars per component) TYP UNI UNT
//! /CHA/<field>/<numdt><numit>                    attrs NDT NOR PDT RDT ROR
//! /CHA/<field>/<step>/<entity>                   attrs GAU (localization or "") PFL (profile)
//! /CHA/<field>/<step>/<entity>/<profile>         attrs GAU NBR (entities of the type in the mesh) NGA (values per entity)
//! /CHA/<field>/<step>/<entity>/<profile>/CO      values: component, then entity, then point
//! /PROFILS/<profile>/PFL                         1-based numbers of the entities (attr NBR)
//! ```
//!
//! Cells are numbered within their type, in the order of the mesh's cells of that type (the order the
//! mesh writer keeps). A field's values at the nodes of a cell are in Code_Aster's node order here and
//! in MED's node order in the file.

use super::gauss::{self, Localization};
use super::read::{attr_f64, attr_int, attr_str, read_f64s, read_ints};
use super::types::MedType;
use super::write::{new_group, put_f64, put_i32, put_str, step_name, to_i32};
use super::{h5err, ioerr, open_read, write_atomically, NAME, NO_PROFILE, SNAME};
use crate::diag::Result;
use crate::mesh::{CellType, Mesh};
use hdf5_metno as hdf5;
use std::collections::BTreeMap;
use std::path::Path;

/// MED_FLOAT64 in the field `TYP` attribute.
const MED_FLOAT64: i32 = 6;

/// Where a block of values lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Support {
    /// One value per node (`NOE`).
    Node,
    /// On cells (`MAI.<TYP>`): one value per cell, or one per integration point with a localization.
    Cell,
    /// One value per node of each cell (`NOE.<TYP>`, ELNO).
    CellNode,
}

/// The values of a field on one kind of entity at one step.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    pub support: Support,
    /// The cells' type (None for node values).
    pub cell: Option<CellType>,
    /// The localization of integration points (ELGA), by name.
    pub localization: Option<String>,
    /// Values per entity and component: 1 (nodes, ELEM), the cell's nodes (ELNO), its points (ELGA).
    pub per_entity: usize,
    /// 0-based numbers of the entities: node numbers, or positions among the mesh's cells of the type.
    pub entities: Vec<usize>,
    /// `values[(e * per_entity + p) * ncmp + k]` for entity `e` of `entities`, point or node `p`
    /// (Code_Aster's node order for ELNO), component `k`.
    pub values: Vec<f64>,
}

/// One time step of a field.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldStep {
    pub numdt: i32,
    pub numit: i32,
    pub time: f64,
    pub blocks: Vec<Block>,
}

impl FieldStep {
    /// The order number Code_Aster reads (`lrfmed`): `numit`, else `numdt`.
    pub fn order(&self) -> i32 {
        if self.numit != -1 {
            self.numit
        } else {
            self.numdt
        }
    }
}

/// A real field of a MED file.
#[derive(Debug, Clone, PartialEq)]
pub struct MedField {
    pub name: String,
    pub mesh_name: String,
    pub components: Vec<String>,
    pub steps: Vec<FieldStep>,
}

/// The cells of each type of a mesh, in the order of the file (the mesh's index order within a type).
pub fn cells_by_type(mesh: &Mesh) -> BTreeMap<CellType, Vec<usize>> {
    let mut m: BTreeMap<CellType, Vec<usize>> = BTreeMap::new();
    for (c, t) in mesh.cell_types.iter().enumerate() {
        m.entry(*t).or_default().push(c);
    }
    m
}

/// The number of each entity of a mesh in a file: nodes, and cells per MED type name.
pub(crate) fn entity_counts(
    path: &Path,
    file: &hdf5::File,
    mesh_name: &str,
) -> Result<(usize, BTreeMap<String, usize>)> {
    let has = file.link_exists("ENS_MAA") && file.group("ENS_MAA").is_ok_and(|g| g.link_exists(mesh_name));
    if !has {
        return Err(ioerr(path, format!("no mesh named '{mesh_name}' to carry a field")));
    }
    let mpath = format!("ENS_MAA/{mesh_name}");
    let mg = file.group(&mpath).map_err(|e| h5err(path, &mpath, e))?;
    let esp = attr_int(path, &mg, "ESP")?.or(attr_int(path, &mg, "DIM")?).unwrap_or(3).max(1) as usize;
    let mut steps = mg.member_names().map_err(|e| h5err(path, &mpath, e))?;
    steps.sort();
    for s in steps {
        let Ok(g) = mg.group(&s) else { continue };
        if !g.link_exists("NOE") {
            continue;
        }
        let ds = g.dataset("NOE/COO").map_err(|e| h5err(path, &format!("{mpath}/{s}/NOE/COO"), e))?;
        let nn = ds.size() / esp;
        let mut cells = BTreeMap::new();
        if g.link_exists("MAI") {
            let mai = g.group("MAI").map_err(|e| h5err(path, &format!("{mpath}/{s}/MAI"), e))?;
            for t in mai.member_names().map_err(|e| h5err(path, &format!("{mpath}/{s}/MAI"), e))? {
                let Some(mt) = MedType::by_med_name(&t) else { continue };
                let tg = mai.group(&t).map_err(|e| h5err(path, &format!("{mpath}/{s}/MAI/{t}"), e))?;
                if tg.link_exists("NOD") {
                    let nod = tg.dataset("NOD").map_err(|e| h5err(path, &format!("{mpath}/{s}/MAI/{t}/NOD"), e))?;
                    cells.insert(t, nod.size() / mt.nnodes());
                }
            }
        }
        return Ok((nn, cells));
    }
    Err(ioerr(path, format!("mesh '{mesh_name}' has no nodes")))
}

/// The number of nodes and of cells of each type of a mesh of a file.
pub fn mesh_entity_counts(path: &Path, mesh_name: &str) -> Result<(usize, BTreeMap<CellType, usize>)> {
    let file = open_read(path)?;
    let (nn, cells) = entity_counts(path, &file, mesh_name)?;
    let cells = cells.into_iter().filter_map(|(t, n)| MedType::by_med_name(&t).map(|m| (m.cell, n))).collect();
    Ok((nn, cells))
}

/// The name of a block's group under a step (`NOE`, `MAI.QU8`, `NOE.QU8`).
fn entity_group(b: &Block) -> Option<String> {
    match (b.support, b.cell) {
        (Support::Node, _) => Some("NOE".into()),
        (Support::Cell, Some(t)) => Some(format!("MAI.{}", MedType::of(t).med_name)),
        (Support::CellNode, Some(t)) => Some(format!("NOE.{}", MedType::of(t).med_name)),
        _ => None,
    }
}

/// A profile with these 1-based numbers: an identical one of the file, or a new one.
fn ensure_profile(path: &Path, file: &hdf5::File, numbers: &[i32]) -> Result<String> {
    let g = match file.group("PROFILS") {
        Ok(g) => g,
        Err(_) => new_group(path, file, "PROFILS")?,
    };
    let mut names = g.member_names().map_err(|e| h5err(path, "listing /PROFILS", e))?;
    names.sort();
    for n in &names {
        let ds = g.dataset(&format!("{n}/PFL")).map_err(|e| h5err(path, &format!("/PROFILS/{n}/PFL"), e))?;
        let there = read_ints(path, &ds)?;
        if there.len() == numbers.len() && there.iter().zip(numbers).all(|(a, b)| *a == *b as i64) {
            return Ok(n.clone());
        }
    }
    let name = (1..).map(|i| format!("PROFIL__{i:08}")).find(|n| !names.contains(n)).expect("a free profile name");
    let pg = new_group(path, &g, &name)?;
    put_i32(path, &pg, "NBR", to_i32(path, numbers.len())?)?;
    pg.new_dataset_builder()
        .with_data(numbers)
        .create("PFL")
        .map_err(|e| h5err(path, &format!("profile {name}"), e))?;
    Ok(name)
}

fn check_names(path: &Path, f: &MedField) -> Result<()> {
    if f.name.is_empty() || f.name.len() > NAME || !f.name.is_ascii() {
        return Err(ioerr(path, format!("bad field name '{}' (1 to {NAME} ASCII characters)", f.name)));
    }
    if f.components.is_empty() {
        return Err(ioerr(path, format!("field '{}' has no components", f.name)));
    }
    for c in &f.components {
        if c.len() > SNAME || !c.is_ascii() {
            return Err(ioerr(path, format!("field '{}': bad component name '{c}'", f.name)));
        }
    }
    Ok(())
}

/// Write fields into a MED file that already holds their mesh, with the localizations their blocks
/// name. A field that exists gets the new steps (same mesh and components; a step may gain entity
/// types, not repeat one). The file is updated through a temporary copy renamed into place.
pub fn write_fields(path: &Path, fields: &[MedField], localizations: &[Localization]) -> Result<()> {
    for f in fields {
        check_names(path, f)?;
    }
    drop(open_read(path)?);
    write_atomically(path, true, |tmp| {
        let file = super::file_options().open_rw(tmp).map_err(|e| h5err(path, "opening for update", e))?;
        // Localizations first: the names they have in the file.
        let mut loc_names: BTreeMap<String, String> = BTreeMap::new();
        for loc in localizations {
            let used = fields
                .iter()
                .flat_map(|f| &f.steps)
                .flat_map(|s| &s.blocks)
                .any(|b| b.localization.as_deref() == Some(loc.name.as_str()));
            if used && !loc_names.contains_key(&loc.name) {
                let stored = gauss::ensure(path, &file, loc)?;
                loc_names.insert(loc.name.clone(), stored);
            }
        }
        for f in fields {
            write_one(path, &file, f, localizations, &loc_names)?;
        }
        file.close().map_err(|e| h5err(path, "closing the file", e))
    })
}

fn write_one(
    path: &Path,
    file: &hdf5::File,
    f: &MedField,
    localizations: &[Localization],
    loc_names: &BTreeMap<String, String>,
) -> Result<()> {
    let (nn, cell_counts) = entity_counts(path, file, &f.mesh_name)?;
    let nco = f.components.len();
    let comp_names: String = f.components.iter().map(|c| format!("{c:<16}")).collect();
    let cha = match file.group("CHA") {
        Ok(g) => g,
        Err(_) => new_group(path, file, "CHA")?,
    };
    let name = &f.name;
    let fg = if cha.link_exists(name) {
        let fg = cha.group(name).map_err(|e| h5err(path, &format!("field '{name}'"), e))?;
        let old_mesh = attr_str(path, &fg, "MAI")?.unwrap_or_default();
        let old_comp = attr_str(path, &fg, "NOM")?.unwrap_or_default();
        if old_mesh != f.mesh_name || old_comp != comp_names.trim_end() {
            return Err(ioerr(
                path,
                format!("field '{name}' already exists on mesh '{old_mesh}' with other components"),
            ));
        }
        fg
    } else {
        let fg = new_group(path, &cha, name)?;
        put_str(path, &fg, "MAI", &f.mesh_name)?;
        put_i32(path, &fg, "NCO", to_i32(path, nco)?)?;
        put_str(path, &fg, "NOM", &comp_names)?;
        put_i32(path, &fg, "TYP", MED_FLOAT64)?;
        put_str(path, &fg, "UNI", &" ".repeat(SNAME * nco))?;
        put_str(path, &fg, "UNT", "")?;
        fg
    };
    for st in &f.steps {
        let sname = step_name(st.numdt, st.numit);
        let sg = if fg.link_exists(&sname) {
            fg.group(&sname).map_err(|e| h5err(path, &format!("field '{name}' step {sname}"), e))?
        } else {
            let sg = new_group(path, &fg, &sname)?;
            put_i32(path, &sg, "NDT", st.numdt)?;
            put_i32(path, &sg, "NOR", st.numit)?;
            put_f64(path, &sg, "PDT", st.time)?;
            put_i32(path, &sg, "RDT", -1)?;
            put_i32(path, &sg, "ROR", -1)?;
            sg
        };
        for b in &st.blocks {
            let what = format!("field '{name}' step {}", st.order());
            let eg_name =
                entity_group(b).ok_or_else(|| ioerr(path, format!("{what}: a cell block without cell type")))?;
            if sg.link_exists(&eg_name) {
                return Err(ioerr(path, format!("field '{name}' already has step {} on {eg_name}", st.order())));
            }
            let count = match b.cell {
                None => nn,
                Some(t) => *cell_counts
                    .get(MedType::of(t).med_name)
                    .ok_or_else(|| ioerr(path, format!("{what}: mesh '{}' has no {} cell", f.mesh_name, t.name())))?,
            };
            let ne = b.entities.len();
            if b.values.len() != ne * b.per_entity * nco {
                return Err(ioerr(
                    path,
                    format!(
                        "{what} on {eg_name}: {} values for {ne} entities x {} points x {nco} components",
                        b.values.len(),
                        b.per_entity
                    ),
                ));
            }
            if let Some(&e) = b.entities.iter().find(|&&e| e >= count) {
                return Err(ioerr(path, format!("{what} on {eg_name}: entity {} of {count}", e + 1)));
            }
            match (b.support, b.cell) {
                (Support::CellNode, Some(t)) if b.per_entity != t.nnodes() => {
                    return Err(ioerr(path, format!("{what}: {} values per {} cell", b.per_entity, t.name())));
                }
                _ => {}
            }
            let loc = match &b.localization {
                Some(l) => {
                    let stored = loc_names
                        .get(l)
                        .ok_or_else(|| ioerr(path, format!("{what}: localization '{l}' is not given")))?;
                    let given = localizations.iter().find(|x| &x.name == l).expect("resolved above");
                    if Some(given.cell) != b.cell || given.points.len() != b.per_entity {
                        return Err(ioerr(path, format!("{what}: localization '{l}' does not fit {eg_name}")));
                    }
                    stored.clone()
                }
                None => String::new(),
            };
            let whole = ne == count && b.entities.iter().enumerate().all(|(i, &e)| i == e);
            let pfl = if whole {
                NO_PROFILE.to_string()
            } else {
                let numbers = b.entities.iter().map(|&e| to_i32(path, e + 1)).collect::<Result<Vec<i32>>>()?;
                ensure_profile(path, file, &numbers)?
            };
            let eg = new_group(path, &sg, &eg_name)?;
            put_str(path, &eg, "GAU", &loc)?;
            put_str(path, &eg, "PFL", &pfl)?;
            let pg = new_group(path, &eg, &pfl)?;
            put_str(path, &pg, "GAU", &loc)?;
            put_i32(path, &pg, "NBR", to_i32(path, count)?)?;
            put_i32(path, &pg, "NGA", to_i32(path, b.per_entity)?)?;
            // ELNO values go to MED's node order.
            let to_file: Vec<usize> = match (b.support, b.cell) {
                (Support::CellNode, Some(t)) => MedType::of(t).med_from_aster(),
                _ => (0..b.per_entity).collect(),
            };
            let np = b.per_entity;
            let mut co = Vec::with_capacity(b.values.len());
            for k in 0..nco {
                for e in 0..ne {
                    for &p in &to_file {
                        co.push(b.values[(e * np + p) * nco + k]);
                    }
                }
            }
            pg.new_dataset_builder().with_data(&co[..]).create("CO").map_err(|e| h5err(path, &what, e))?;
        }
    }
    Ok(())
}

/// Names of the fields of a file with their mesh and components.
pub fn field_infos(path: &Path) -> Result<Vec<(String, String, Vec<String>)>> {
    let names = super::list_fields(path)?;
    if names.is_empty() {
        return Ok(Vec::new());
    }
    let file = open_read(path)?;
    let cha = file.group("CHA").map_err(|e| h5err(path, "group /CHA", e))?;
    let mut out = Vec::new();
    for n in names {
        let fg = cha.group(&n).map_err(|e| h5err(path, &format!("/CHA/{n}"), e))?;
        let (mesh, comps) = header(path, &fg)?;
        out.push((n, mesh, comps));
    }
    Ok(out)
}

fn header(path: &Path, fg: &hdf5::Group) -> Result<(String, Vec<String>)> {
    let mesh = attr_str(path, fg, "MAI")?.unwrap_or_default();
    let nco = attr_int(path, fg, "NCO")?.unwrap_or(1).max(1) as usize;
    let comp = attr_str(path, fg, "NOM")?.unwrap_or_default();
    let b = comp.as_bytes();
    let comps = (0..nco)
        .map(|k| {
            let lo = (k * SNAME).min(b.len());
            let hi = ((k + 1) * SNAME).min(b.len());
            String::from_utf8_lossy(&b[lo..hi]).trim_end().to_string()
        })
        .collect();
    Ok((mesh, comps))
}

/// The localizations of a file, by name.
pub fn read_localizations(path: &Path) -> Result<BTreeMap<String, Localization>> {
    let file = open_read(path)?;
    gauss::read_all(path, &file)
}

/// Read a real field of every support, its steps in (numdt, numit) order.
pub fn read_field(path: &Path, field_name: &str) -> Result<MedField> {
    let file = open_read(path)?;
    let present = file.link_exists("CHA") && file.group("CHA").is_ok_and(|g| g.link_exists(field_name));
    if !present {
        let mut names = file.group("CHA").and_then(|g| g.member_names()).unwrap_or_default();
        names.sort();
        return Err(ioerr(
            path,
            format!(
                "no field named '{field_name}'; fields present: {}",
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        ));
    }
    let fpath = format!("CHA/{field_name}");
    let fg = file.group(&fpath).map_err(|e| h5err(path, &fpath, e))?;
    let (mesh_name, components) = header(path, &fg)?;
    let nco = components.len();
    if let Some(t) = attr_int(path, &fg, "TYP")? {
        if t != MED_FLOAT64 as i64 {
            return Err(ioerr(path, format!("field '{field_name}' is not a field of reals (type {t})")));
        }
    }
    let mut snames = fg.member_names().map_err(|e| h5err(path, &fpath, e))?;
    let parse =
        |s: &str| (s.get(..20).and_then(|a| a.parse::<i64>().ok()), s.get(20..).and_then(|a| a.parse::<i64>().ok()));
    if let Some(bad) = snames.iter().find(|s| s.len() != 40 || parse(s).0.is_none() || parse(s).1.is_none()) {
        return Err(ioerr(
            path,
            format!(
                "field '{field_name}': step '{}' is not a MED 3/4 computation step (MED 2.x fields are not read)",
                bad.trim()
            ),
        ));
    }
    snames.sort_by_key(|s| parse(s));
    let mut profiles: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    let mut steps = Vec::new();
    for s in snames {
        let sg = fg.group(&s).map_err(|e| h5err(path, &format!("{fpath}/{s}"), e))?;
        let numdt = attr_int(path, &sg, "NDT")?.unwrap_or(-1) as i32;
        let numit = attr_int(path, &sg, "NOR")?.unwrap_or(-1) as i32;
        let time = attr_f64(path, &sg, "PDT")?.unwrap_or(0.0);
        let mut blocks = Vec::new();
        let mut egs = sg.member_names().map_err(|e| h5err(path, &format!("{fpath}/{s}"), e))?;
        egs.sort();
        for eg_name in egs {
            let what = format!("field '{field_name}' step {numdt}/{numit} {eg_name}");
            let (support, cell) = match eg_name.split_once('.') {
                None if eg_name == "NOE" => (Support::Node, None),
                Some((kind @ ("MAI" | "NOE"), t)) => {
                    let mt = MedType::by_med_name(t)
                        .ok_or_else(|| ioerr(path, format!("{what}: cell type {t} is not supported")))?;
                    (if kind == "MAI" { Support::Cell } else { Support::CellNode }, Some(mt.cell))
                }
                _ => return Err(ioerr(path, format!("{what}: entity '{eg_name}' is not supported"))),
            };
            let eg = sg.group(&eg_name).map_err(|e| h5err(path, &what, e))?;
            let pfl = attr_str(path, &eg, "PFL")?.unwrap_or_else(|| NO_PROFILE.to_string());
            let gau = attr_str(path, &eg, "GAU")?.unwrap_or_default();
            let pg = eg.group(&pfl).map_err(|e| h5err(path, &format!("{what}/{pfl}"), e))?;
            let nga = attr_int(path, &pg, "NGA")?.unwrap_or(1).max(1) as usize;
            let co = pg.dataset("CO").map_err(|e| h5err(path, &format!("{what}/{pfl}/CO"), e))?;
            let flat = read_f64s(path, &co)?;
            if flat.len() % (nga * nco) != 0 {
                return Err(ioerr(path, format!("{what}: {} values for {nga} points x {nco} components", flat.len())));
            }
            let ne = flat.len() / (nga * nco);
            let entities = if pfl == NO_PROFILE || pfl.is_empty() {
                (0..ne).collect()
            } else {
                if !profiles.contains_key(&pfl) {
                    let ds = file
                        .dataset(&format!("PROFILS/{pfl}/PFL"))
                        .map_err(|e| h5err(path, &format!("profile {pfl}"), e))?;
                    let nums = read_ints(path, &ds)?;
                    if nums.iter().any(|&n| n < 1) {
                        return Err(ioerr(path, format!("profile {pfl}: entity numbers start at 1")));
                    }
                    profiles.insert(pfl.clone(), nums.iter().map(|&n| (n - 1) as usize).collect());
                }
                let e = profiles[&pfl].clone();
                if e.len() != ne {
                    return Err(ioerr(path, format!("{what}: {ne} entities of values, {} in profile {pfl}", e.len())));
                }
                e
            };
            if support == Support::CellNode && cell.is_some_and(|t| t.nnodes() != nga) {
                return Err(ioerr(path, format!("{what}: {nga} values per cell")));
            }
            let from_file: Vec<usize> = match (support, cell) {
                (Support::CellNode, Some(t)) => MedType::of(t).aster_from_med(),
                _ => (0..nga).collect(),
            };
            let mut values = vec![0.0; flat.len()];
            for k in 0..nco {
                for e in 0..ne {
                    for (p, &q) in from_file.iter().enumerate() {
                        values[(e * nga + p) * nco + k] = flat[(k * ne + e) * nga + q];
                    }
                }
            }
            let localization = (!gau.is_empty()).then_some(gau);
            blocks.push(Block { support, cell, localization, per_entity: nga, entities, values });
        }
        steps.push(FieldStep { numdt, numit, time, blocks });
    }
    Ok(MedField { name: field_name.to_string(), mesh_name, components, steps })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_as_code_aster_reads_them() {
        let s = |numdt, numit| FieldStep { numdt, numit, time: 0.0, blocks: vec![] };
        assert_eq!(s(3, 3).order(), 3);
        assert_eq!(s(3, -1).order(), 3);
        assert_eq!(s(-1, 5).order(), 5);
    }
}
