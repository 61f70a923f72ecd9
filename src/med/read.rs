//! Reading MED meshes.

use super::types::MedType;
use super::{decode_name, h5err, ioerr, open_read, LNAME, SNAME};
use crate::diag::Result;
use crate::mesh::Mesh;
use hdf5::types::{FixedAscii, TypeDescriptor};
use hdf5::{Dataset, Group, Location};
use hdf5_metno as hdf5;
use std::collections::BTreeMap;
use std::path::Path;

/// Names of the meshes stored in a MED file, sorted.
pub fn list_meshes(path: &Path) -> Result<Vec<String>> {
    let file = open_read(path)?;
    mesh_names(path, &file)
}

fn mesh_names(path: &Path, file: &hdf5::File) -> Result<Vec<String>> {
    if !file.link_exists("ENS_MAA") {
        return Ok(Vec::new());
    }
    let ens = file.group("ENS_MAA").map_err(|e| h5err(path, "group /ENS_MAA", e))?;
    let mut names = ens.member_names().map_err(|e| h5err(path, "listing /ENS_MAA", e))?;
    names.sort();
    Ok(names)
}

pub(crate) fn attr_int(path: &Path, loc: &Location, name: &str) -> Result<Option<i64>> {
    if !loc.attr_names().map_err(|e| h5err(path, &loc.name(), e))?.iter().any(|a| a == name) {
        return Ok(None);
    }
    let a = loc.attr(name).map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))?;
    a.read_scalar::<i64>().map(Some).map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))
}

pub(crate) fn attr_f64(path: &Path, loc: &Location, name: &str) -> Result<Option<f64>> {
    if !loc.attr_names().map_err(|e| h5err(path, &loc.name(), e))?.iter().any(|a| a == name) {
        return Ok(None);
    }
    let a = loc.attr(name).map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))?;
    a.read_scalar::<f64>().map(Some).map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))
}

pub(crate) fn attr_str(path: &Path, loc: &Location, name: &str) -> Result<Option<String>> {
    if !loc.attr_names().map_err(|e| h5err(path, &loc.name(), e))?.iter().any(|a| a == name) {
        return Ok(None);
    }
    let a = loc.attr(name).map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))?;
    let s = a.read_scalar::<FixedAscii<1024>>().map_err(|e| h5err(path, &format!("{} attr {name}", loc.name()), e))?;
    Ok(Some(String::from_utf8_lossy(s.as_bytes()).trim_end_matches(['\0', ' ']).to_string()))
}

fn open_ds(path: &Path, g: &Group, name: &str) -> Result<Option<Dataset>> {
    if !g.link_exists(name) {
        return Ok(None);
    }
    g.dataset(name).map(Some).map_err(|e| h5err(path, &format!("dataset {}/{name}", g.name()), e))
}

pub(crate) fn read_ints(path: &Path, ds: &Dataset) -> Result<Vec<i64>> {
    ds.read_raw::<i64>().map_err(|e| h5err(path, &format!("reading {}", ds.name()), e))
}

pub(crate) fn read_f64s(path: &Path, ds: &Dataset) -> Result<Vec<f64>> {
    ds.read_raw::<f64>().map_err(|e| h5err(path, &format!("reading {}", ds.name()), e))
}

/// Read a dataset of fixed-size names (array type `[i8; N]`, or a flat
/// byte array of `count * N` bytes as some writers produce, or — in MED 2.x
/// files — a flat array of one-character strings).
fn read_names<const N: usize>(path: &Path, ds: &Dataset) -> Result<Vec<String>> {
    let what = format!("reading names {}", ds.name());
    let dtype = ds.dtype().map_err(|e| h5err(path, &what, e))?;
    let dsize = dtype.size();
    let is_string =
        matches!(dtype.to_descriptor(), Ok(TypeDescriptor::FixedAscii(_) | TypeDescriptor::FixedUnicode(_)));
    if is_string && dsize == 1 {
        // One character per element, a NUL read as an empty string; a byte past the last whole name (the
        // C string's terminator some writers keep: sslp320c.21 has 16 × 1271 + 1) is not a name.
        let raw = ds.read_raw::<FixedAscii<1>>().map_err(|e| h5err(path, &what, e))?;
        let bytes: Vec<i8> = raw.iter().map(|c| c.as_bytes().first().map_or(0, |&b| b as i8)).collect();
        Ok(bytes.chunks_exact(N).map(decode_name).collect())
    } else if is_string && dsize == N {
        let raw = ds.read_raw::<FixedAscii<N>>().map_err(|e| h5err(path, &what, e))?;
        Ok(raw.iter().map(|n| n.as_str().trim_end().to_string()).collect())
    } else if dsize == N {
        let raw = ds.read_raw::<[i8; N]>().map_err(|e| h5err(path, &what, e))?;
        Ok(raw.iter().map(|n| decode_name(n)).collect())
    } else if dsize == 1 {
        let raw = ds.read_raw::<i8>().map_err(|e| h5err(path, &what, e))?;
        Ok(raw.chunks_exact(N).map(decode_name).collect())
    } else {
        Err(ioerr(path, format!("{what}: unexpected element size {dsize} (expected {N})")))
    }
}

/// The first computation-step group of a mesh (`-0000000000000000001-...`
/// for meshes without steps); MED 2.x files have no step level, their `NOE` and `MAI` sit in the
/// mesh's group itself.
fn first_step(path: &Path, mesh: &Group, mesh_name: &str) -> Result<Group> {
    if mesh.link_exists("NOE") || mesh.link_exists("MAI") {
        return Ok(mesh.clone());
    }
    let mut names = mesh.member_names().map_err(|e| h5err(path, &format!("listing mesh '{mesh_name}'"), e))?;
    names.sort();
    for n in names {
        if let Ok(g) = mesh.group(&n) {
            if g.link_exists("NOE") || g.link_exists("MAI") {
                return Ok(g);
            }
        }
    }
    Err(ioerr(path, format!("mesh '{mesh_name}' has no computation step with nodes")))
}

/// Family number -> group names, from `/FAS/<mesh>` (both `NOEUD` and
/// `ELEME`, plus families stored directly under the mesh, e.g.
/// `FAMILLE_ZERO`), or from `/ENS_MAA/<mesh>/FAS` in MED 2.x files.
fn read_families(path: &Path, file: &hdf5::File, mesh: &str) -> Result<BTreeMap<i64, Vec<String>>> {
    let mut fams: BTreeMap<i64, Vec<String>> = BTreeMap::new();
    let root = if file.link_exists("FAS") && file.group("FAS").is_ok_and(|g| g.link_exists(mesh)) {
        format!("FAS/{mesh}")
    } else if file.group(&format!("ENS_MAA/{mesh}")).is_ok_and(|g| g.link_exists("FAS")) {
        format!("ENS_MAA/{mesh}/FAS")
    } else {
        return Ok(fams);
    };
    let fas = file.group(&root).map_err(|e| h5err(path, &root, e))?;
    let mut holders = vec![fas.clone()];
    for sub in ["NOEUD", "ELEME"] {
        if fas.link_exists(sub) {
            holders.push(fas.group(sub).map_err(|e| h5err(path, &format!("{root}/{sub}"), e))?);
        }
    }
    for holder in holders {
        let mut names = holder.member_names().map_err(|e| h5err(path, &holder.name(), e))?;
        names.sort();
        for fname in names {
            if holder.name() == fas.name() && (fname == "NOEUD" || fname == "ELEME") {
                continue;
            }
            let Ok(fg) = holder.group(&fname) else { continue };
            let Some(num) = attr_int(path, &fg, "NUM")? else { continue };
            let mut groups = Vec::new();
            if fg.link_exists("GRO") {
                let gro = fg.group("GRO").map_err(|e| h5err(path, &fg.name(), e))?;
                if let Some(ds) = open_ds(path, &gro, "NOM")? {
                    groups = read_names::<LNAME>(path, &ds)?;
                }
            }
            groups.retain(|g| !g.is_empty());
            fams.entry(num).or_default().extend(groups);
        }
    }
    Ok(fams)
}

/// Read a mesh from a MED file. `mesh_name` `None` takes the only mesh of
/// the file (the first in name order if there are several).
pub fn read_mesh(path: &Path, mesh_name: Option<&str>) -> Result<Mesh> {
    let file = open_read(path)?;
    let names = mesh_names(path, &file)?;
    if names.is_empty() {
        return Err(ioerr(path, "contains no mesh (no /ENS_MAA group)"));
    }
    let name = match mesh_name {
        Some(n) => {
            if !names.iter().any(|m| m == n) {
                return Err(ioerr(path, format!("no mesh named '{n}'; meshes present: {}", names.join(", "))));
            }
            n.to_string()
        }
        None => names[0].clone(),
    };
    let mgroup = file.group(&format!("ENS_MAA/{name}")).map_err(|e| h5err(path, &format!("mesh '{name}'"), e))?;
    let typ = attr_int(path, &mgroup, "TYP")?.unwrap_or(0);
    if typ != 0 {
        return Err(ioerr(path, format!("mesh '{name}' is a structured grid, not supported")));
    }
    let step = first_step(path, &mgroup, &name)?;
    let noe = step.group("NOE").map_err(|e| h5err(path, &format!("mesh '{name}' nodes"), e))?;
    let coo =
        open_ds(path, &noe, "COO")?.ok_or_else(|| ioerr(path, format!("mesh '{name}' has no node coordinates")))?;
    // The space dimension: ESP (MED 3+); in MED 2.x files, which have only DIM (the mesh's own
    // dimension), the number of coordinates per node (COO's size over its NBR nodes).
    let esp = match attr_int(path, &mgroup, "ESP")? {
        Some(e) => e,
        None => {
            let dim = attr_int(path, &mgroup, "DIM")?
                .ok_or_else(|| ioerr(path, format!("mesh '{name}' has no ESP/DIM attribute")))?;
            match attr_int(path, &coo, "NBR")? {
                Some(n) if n > 0 && coo.size() % n as usize == 0 => (coo.size() / n as usize) as i64,
                _ => dim,
            }
        }
    };
    if !(1..=3).contains(&esp) {
        return Err(ioerr(path, format!("mesh '{name}': bad space dimension {esp}")));
    }
    let esp = esp as usize;

    // Nodes.
    let flat = read_f64s(path, &coo)?;
    if flat.len() % esp != 0 {
        return Err(ioerr(path, format!("mesh '{name}': coordinate array size not a multiple of {esp}")));
    }
    let nn = flat.len() / esp;
    let coords: Vec<[f64; 3]> = (0..nn)
        .map(|i| {
            let mut c = [0.0; 3];
            for (k, ck) in c.iter_mut().enumerate().take(esp) {
                *ck = flat[k * nn + i];
            }
            c
        })
        .collect();
    let named_nodes = open_ds(path, &noe, "NOM")?.is_some();
    let node_names = match open_ds(path, &noe, "NOM")? {
        Some(ds) => {
            let v = read_names::<SNAME>(path, &ds)?;
            if v.len() != nn {
                return Err(ioerr(path, format!("mesh '{name}': {} node names for {nn} nodes", v.len())));
            }
            v
        }
        None => (1..=nn).map(|i| format!("N{i}")).collect(),
    };
    let node_fam = match open_ds(path, &noe, "FAM")? {
        Some(ds) => read_ints(path, &ds)?,
        None => vec![0; nn],
    };
    if node_fam.len() != nn {
        return Err(ioerr(path, format!("mesh '{name}': node family array has a bad size")));
    }

    // Cells, type by type in Code_Aster's reading order (MedType::rank).
    let mut by_type: Vec<(&'static MedType, Group)> = Vec::new();
    if step.link_exists("MAI") {
        let mai = step.group("MAI").map_err(|e| h5err(path, &format!("mesh '{name}' cells"), e))?;
        let tnames = mai.member_names().map_err(|e| h5err(path, &mai.name(), e))?;
        for tn in tnames {
            let mt = MedType::by_med_name(&tn)
                .ok_or_else(|| ioerr(path, format!("mesh '{name}': unknown or unsupported cell type '{tn}'")))?;
            let g = mai.group(&tn).map_err(|e| h5err(path, &format!("cells {tn}"), e))?;
            by_type.push((mt, g));
        }
    }
    by_type.sort_by_key(|(mt, _)| MedType::rank(mt.cell));

    let mut mesh = Mesh { dim: esp, coords, node_names, named_nodes, ..Mesh::default() };
    let mut cell_fam: Vec<i64> = Vec::new();
    for (mt, g) in &by_type {
        let nod = open_ds(path, g, "NOD")?
            .ok_or_else(|| ioerr(path, format!("mesh '{name}': cells {} have no nodal connectivity", mt.med_name)))?;
        let conn = read_ints(path, &nod)?;
        let nno = mt.nnodes();
        if conn.len() % nno != 0 {
            return Err(ioerr(path, format!("mesh '{name}': {} connectivity has a bad size", mt.med_name)));
        }
        let nc = conn.len() / nno;
        let mut med = vec![0usize; nno];
        for i in 0..nc {
            for (k, m) in med.iter_mut().enumerate() {
                let v = conn[k * nc + i];
                if v < 1 || v as usize > nn {
                    return Err(ioerr(
                        path,
                        format!(
                            "mesh '{name}': {} cell {} refers to node {v} (mesh has {nn} nodes)",
                            mt.med_name,
                            i + 1
                        ),
                    ));
                }
                *m = v as usize - 1;
            }
            mesh.cells.push(mt.to_aster(&med));
            mesh.cell_types.push(mt.cell);
        }
        let fam = match open_ds(path, g, "FAM")? {
            Some(ds) => read_ints(path, &ds)?,
            None => vec![0; nc],
        };
        if fam.len() != nc {
            return Err(ioerr(path, format!("mesh '{name}': {} family array has a bad size", mt.med_name)));
        }
        cell_fam.extend(fam);
        // Default names follow the global cell number.
        let start = mesh.cell_names.len();
        match open_ds(path, g, "NOM")? {
            Some(ds) => {
                let v = read_names::<SNAME>(path, &ds)?;
                if v.len() != nc {
                    return Err(ioerr(path, format!("mesh '{name}': {} names have a bad size", mt.med_name)));
                }
                mesh.cell_names.extend(v);
            }
            None => mesh.cell_names.extend((start + 1..=start + nc).map(|i| format!("M{i}"))),
        }
    }

    // Groups from families.
    let fams = read_families(path, &file, &name)?;
    for (i, f) in node_fam.iter().enumerate() {
        if *f == 0 {
            continue;
        }
        if let Some(gs) = fams.get(f) {
            for g in gs {
                mesh.node_groups.entry(g.clone()).or_default().push(i);
            }
        }
    }
    for (i, f) in cell_fam.iter().enumerate() {
        if *f == 0 {
            continue;
        }
        if let Some(gs) = fams.get(f) {
            for g in gs {
                mesh.cell_groups.entry(g.clone()).or_default().push(i);
            }
        }
    }
    for v in mesh.node_groups.values_mut().chain(mesh.cell_groups.values_mut()) {
        v.dedup();
    }
    Ok(mesh)
}
