//! Node fields over time steps (`/CHA`), e.g. DEPL.

use super::read::{attr_f64, attr_int, attr_str, read_f64s};
use super::write::{new_group, put_f64, put_i32, put_str, step_name, to_i32};
use super::{h5err, ioerr, open_read, write_atomically, NAME, NO_PROFILE, SNAME};
use crate::diag::Result;
use hdf5_metno as hdf5;
use std::path::Path;

/// MED_FLOAT64 in the field `TYP` attribute.
const MED_FLOAT64: i32 = 6;

/// A node field read back from a MED file.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeField {
    pub mesh_name: String,
    pub components: Vec<String>,
    /// `(numdt, time, values)`, values interlaced per node
    /// (node 0 all components, node 1, ...), in step order.
    pub steps: Vec<(i32, f64, Vec<f64>)>,
}

/// Number of nodes of mesh `mesh_name` in an open file.
fn mesh_node_count(path: &Path, file: &hdf5::File, mesh_name: &str) -> Result<usize> {
    let mpath = format!("ENS_MAA/{mesh_name}");
    let has = file.link_exists("ENS_MAA") && file.group("ENS_MAA").is_ok_and(|g| g.link_exists(mesh_name));
    if !has {
        return Err(ioerr(path, format!("no mesh named '{mesh_name}' to carry a field")));
    }
    let mg = file.group(&mpath).map_err(|e| h5err(path, &mpath, e))?;
    let esp = attr_int(path, &mg, "ESP")?.or(attr_int(path, &mg, "DIM")?).unwrap_or(3).max(1) as usize;
    let mut steps = mg.member_names().map_err(|e| h5err(path, &mpath, e))?;
    steps.sort();
    for s in steps {
        let Ok(g) = mg.group(&s) else { continue };
        if g.link_exists("NOE") {
            let ds = g.dataset("NOE/COO").map_err(|e| h5err(path, &format!("{mpath}/{s}/NOE/COO"), e))?;
            return Ok(ds.size() / esp);
        }
    }
    Err(ioerr(path, format!("mesh '{mesh_name}' has no nodes")))
}

/// Append a real node field with one value per node and component at each
/// step to a MED file that already holds mesh `mesh_name`. `steps` holds
/// `(numdt, time, values interlaced per node)`. If the field exists, the
/// steps are added to it (components must match; a step may not repeat).
/// The file is updated through a temporary copy renamed into place.
pub fn write_node_field(
    path: &Path,
    mesh_name: &str,
    field_name: &str,
    components: &[&str],
    steps: &[(i32, f64, Vec<f64>)],
) -> Result<()> {
    if field_name.is_empty() || field_name.len() > NAME || !field_name.is_ascii() {
        return Err(ioerr(path, format!("bad field name '{field_name}' (1 to {NAME} ASCII characters)")));
    }
    if components.is_empty() {
        return Err(ioerr(path, format!("field '{field_name}' has no components")));
    }
    for c in components {
        if c.len() > SNAME || !c.is_ascii() {
            return Err(ioerr(path, format!("field '{field_name}': bad component name '{c}'")));
        }
    }
    // Check the file before copying it.
    drop(open_read(path)?);
    write_atomically(path, true, |tmp| {
        let file = super::file_options().open_rw(tmp).map_err(|e| h5err(path, "opening for update", e))?;
        let nn = mesh_node_count(path, &file, mesh_name)?;
        let nco = components.len();
        let comp_names: String = components.iter().map(|c| format!("{c:<16}")).collect();
        let cha = match file.group("CHA") {
            Ok(g) => g,
            Err(_) => new_group(path, &file, "CHA")?,
        };
        let fg = if cha.link_exists(field_name) {
            let fg = cha.group(field_name).map_err(|e| h5err(path, &format!("field '{field_name}'"), e))?;
            let old_mesh = attr_str(path, &fg, "MAI")?.unwrap_or_default();
            let old_comp = attr_str(path, &fg, "NOM")?.unwrap_or_default();
            if old_mesh != mesh_name || old_comp != comp_names.trim_end() {
                return Err(ioerr(
                    path,
                    format!("field '{field_name}' already exists on mesh '{old_mesh}' with other components"),
                ));
            }
            fg
        } else {
            let fg = new_group(path, &cha, field_name)?;
            put_str(path, &fg, "MAI", mesh_name)?;
            put_i32(path, &fg, "NCO", to_i32(path, nco)?)?;
            put_str(path, &fg, "NOM", &comp_names)?;
            put_i32(path, &fg, "TYP", MED_FLOAT64)?;
            put_str(path, &fg, "UNI", &" ".repeat(SNAME * nco))?;
            put_str(path, &fg, "UNT", "")?;
            fg
        };
        for (numdt, time, values) in steps {
            if values.len() != nn * nco {
                return Err(ioerr(
                    path,
                    format!(
                        "field '{field_name}' step {numdt}: {} values for {nn} nodes x {nco} components",
                        values.len()
                    ),
                ));
            }
            let sname = step_name(*numdt, -1);
            if fg.link_exists(&sname) {
                return Err(ioerr(path, format!("field '{field_name}' already has step {numdt}")));
            }
            let sg = new_group(path, &fg, &sname)?;
            put_i32(path, &sg, "NDT", *numdt)?;
            put_i32(path, &sg, "NOR", -1)?;
            put_f64(path, &sg, "PDT", *time)?;
            put_i32(path, &sg, "RDT", -1)?;
            put_i32(path, &sg, "ROR", -1)?;
            let noe = new_group(path, &sg, "NOE")?;
            put_str(path, &noe, "GAU", "")?;
            put_str(path, &noe, "PFL", NO_PROFILE)?;
            let pg = new_group(path, &noe, NO_PROFILE)?;
            put_str(path, &pg, "GAU", "")?;
            put_i32(path, &pg, "NBR", to_i32(path, nn)?)?;
            put_i32(path, &pg, "NGA", 1)?;
            // Non-interlaced in the file.
            let mut co = Vec::with_capacity(nn * nco);
            for k in 0..nco {
                co.extend((0..nn).map(|i| values[i * nco + k]));
            }
            let what = format!("field '{field_name}' step {numdt} values");
            pg.new_dataset_builder().with_data(&co[..]).create("CO").map_err(|e| h5err(path, &what, e))?;
        }
        file.close().map_err(|e| h5err(path, "closing the file", e))
    })
}

/// Read a real node field written by [`write_node_field`] (or any MED
/// writer: node values without profile, one value per node).
pub fn read_node_field(path: &Path, field_name: &str) -> Result<NodeField> {
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
    let mesh_name = attr_str(path, &fg, "MAI")?.unwrap_or_default();
    let nco = attr_int(path, &fg, "NCO")?.unwrap_or(1).max(1) as usize;
    let comp = attr_str(path, &fg, "NOM")?.unwrap_or_default();
    let components: Vec<String> = (0..nco)
        .map(|k| {
            let b = comp.as_bytes();
            let lo = (k * SNAME).min(b.len());
            let hi = ((k + 1) * SNAME).min(b.len());
            String::from_utf8_lossy(&b[lo..hi]).trim_end().to_string()
        })
        .collect();
    let mut snames = fg.member_names().map_err(|e| h5err(path, &fpath, e))?;
    snames.sort_by_key(|s| {
        (s.get(..20).and_then(|a| a.parse::<i64>().ok()), s.get(20..).and_then(|a| a.parse::<i64>().ok()))
    });
    let mut steps = Vec::new();
    for s in snames {
        let sg = fg.group(&s).map_err(|e| h5err(path, &format!("{fpath}/{s}"), e))?;
        let numdt = attr_int(path, &sg, "NDT")?.unwrap_or(-1) as i32;
        let time = attr_f64(path, &sg, "PDT")?.unwrap_or(0.0);
        if !sg.link_exists("NOE") {
            continue;
        }
        let noe = sg.group("NOE").map_err(|e| h5err(path, &format!("{fpath}/{s}/NOE"), e))?;
        let pfl = attr_str(path, &noe, "PFL")?.unwrap_or_else(|| NO_PROFILE.to_string());
        let co = noe.dataset(&format!("{pfl}/CO")).map_err(|e| h5err(path, &format!("{fpath}/{s}/NOE/{pfl}/CO"), e))?;
        let flat = read_f64s(path, &co)?;
        if flat.len() % nco != 0 {
            return Err(ioerr(path, format!("field '{field_name}' step {numdt}: bad value count")));
        }
        let nn = flat.len() / nco;
        let mut values = vec![0.0; flat.len()];
        for k in 0..nco {
            for i in 0..nn {
                values[i * nco + k] = flat[k * nn + i];
            }
        }
        steps.push((numdt, time, values));
    }
    Ok(NodeField { mesh_name, components, steps })
}

/// Names of the fields stored in a MED file (`/CHA`), sorted.
pub fn list_fields(path: &Path) -> Result<Vec<String>> {
    let file = open_read(path)?;
    if !file.link_exists("CHA") {
        return Ok(Vec::new());
    }
    let cha = file.group("CHA").map_err(|e| h5err(path, "group /CHA", e))?;
    let mut names = cha.member_names().map_err(|e| h5err(path, "listing /CHA", e))?;
    names.sort();
    Ok(names)
}
