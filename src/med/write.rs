//! Writing MED meshes (stamped MED 4.1.0).

use super::types::MedType;
use super::{encode_name, h5err, ioerr, write_atomically, LNAME, MED_VERSION, NAME, NO_PROFILE, SNAME};
use crate::diag::Result;
use crate::mesh::Mesh;
use hdf5::plist::group_create::LinkCreationOrder;
use hdf5::types::{FixedAscii, TypeDescriptor};
use hdf5::{Group, Location};
use hdf5_metno as hdf5;
use std::collections::BTreeMap;
use std::path::Path;

pub(crate) fn put_i32(path: &Path, loc: &Location, name: &str, v: i32) -> Result<()> {
    let what = format!("{} attr {name}", loc.name());
    let a = loc.new_attr::<i32>().create(name).map_err(|e| h5err(path, &what, e))?;
    a.write_scalar(&v).map_err(|e| h5err(path, &what, e))
}

pub(crate) fn put_f64(path: &Path, loc: &Location, name: &str, v: f64) -> Result<()> {
    let what = format!("{} attr {name}", loc.name());
    let a = loc.new_attr::<f64>().create(name).map_err(|e| h5err(path, &what, e))?;
    a.write_scalar(&v).map_err(|e| h5err(path, &what, e))
}

/// A fixed-length string attribute of `len + 1` bytes, as MED writes them.
pub(crate) fn put_str(path: &Path, loc: &Location, name: &str, v: &str) -> Result<()> {
    let what = format!("{} attr {name}", loc.name());
    if v.len() >= 1024 {
        return Err(ioerr(path, format!("{what}: string too long")));
    }
    let val = FixedAscii::<1024>::from_ascii(v.as_bytes())
        .map_err(|e| ioerr(path, format!("{what}: '{v}' is not ASCII: {e}")))?;
    let a = loc
        .new_attr_builder()
        .empty_as(TypeDescriptor::FixedAscii(v.len() + 1))
        .create(name)
        .map_err(|e| h5err(path, &what, e))?;
    a.write_scalar(&val).map_err(|e| h5err(path, &what, e))
}

pub(crate) fn new_group(path: &Path, parent: &Group, name: &str) -> Result<Group> {
    // MED-fichier walks some groups by creation-order index (families,
    // field steps): keep the creation order of links, as MED does.
    parent
        .create_group_builder()
        .with_gcpl(|p| p.link_creation_order(LinkCreationOrder::Indexed))
        .create(name)
        .map_err(|e| h5err(path, &format!("creating group {}/{name}", parent.name()), e))
}

/// A 1-D dataset with MED's `CGT`/`NBR` attributes (`nbr` = entity count).
fn put_ds<T: hdf5::H5Type>(path: &Path, g: &Group, name: &str, data: &[T], nbr: usize) -> Result<()> {
    let what = format!("dataset {}/{name}", g.name());
    let ds = g.new_dataset_builder().with_data(data).create(name).map_err(|e| h5err(path, &what, e))?;
    put_i32(path, &ds, "CGT", 1)?;
    put_i32(path, &ds, "NBR", to_i32(path, nbr)?)
}

pub(crate) fn to_i32(path: &Path, v: usize) -> Result<i32> {
    i32::try_from(v).map_err(|_| ioerr(path, format!("count {v} does not fit in a MED integer")))
}

pub(crate) fn step_name(numdt: i32, numit: i32) -> String {
    format!("{numdt:020}{numit:020}")
}

pub(crate) fn write_infos(path: &Path, file: &hdf5::File) -> Result<()> {
    let g = new_group(path, file, "INFOS_GENERALES")?;
    put_i32(path, &g, "MAJ", MED_VERSION.0)?;
    put_i32(path, &g, "MIN", MED_VERSION.1)?;
    put_i32(path, &g, "REL", MED_VERSION.2)
}

fn pad16(items: &[&str]) -> String {
    items.iter().map(|s| format!("{s:<16}")).collect()
}

/// Families from groups: entities with the same set of groups share a
/// family. Returns the family number of each entity and, per family
/// number, its groups (in group-name order). Numbers are `sign * 1, 2, ...`
/// in order of first appearance; entities in no group get family 0.
/// A family: its number and its groups.
type Family = (i32, Vec<String>);

fn families(
    path: &Path,
    count: usize,
    groups: &BTreeMap<String, Vec<usize>>,
    sign: i32,
    kind: &str,
) -> Result<(Vec<i32>, Vec<Family>)> {
    let names: Vec<&String> = groups.keys().collect();
    let mut of_entity: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (gi, (gname, members)) in groups.iter().enumerate() {
        for &m in members {
            if m >= count {
                return Err(ioerr(path, format!("{kind} group '{gname}' refers to {kind} {m} (only {count})")));
            }
            let v = &mut of_entity[m];
            if v.last() != Some(&gi) {
                v.push(gi);
            }
        }
    }
    let mut num_of: BTreeMap<Vec<usize>, i32> = BTreeMap::new();
    let mut fams: Vec<Family> = Vec::new();
    let mut out = vec![0i32; count];
    for (e, set) in of_entity.iter_mut().enumerate() {
        if set.is_empty() {
            continue;
        }
        set.sort_unstable();
        set.dedup();
        let n = match num_of.get(set) {
            Some(&n) => n,
            None => {
                let n = sign * to_i32(path, fams.len() + 1)?;
                num_of.insert(set.clone(), n);
                fams.push((n, set.iter().map(|&g| names[g].clone()).collect()));
                n
            }
        };
        out[e] = n;
    }
    Ok((out, fams))
}

fn family_name(num: i32, groups: &[String]) -> String {
    let mut s = format!("FAM_{num}");
    for g in groups {
        s.push('_');
        s.push_str(g);
    }
    let mut cut = s.len().min(NAME);
    while !s.is_char_boundary(cut) {
        cut -= 1;
    }
    s.truncate(cut);
    s
}

fn write_families(path: &Path, parent: &Group, kind: &str, fams: &[Family]) -> Result<()> {
    if fams.is_empty() {
        return Ok(());
    }
    let holder = new_group(path, parent, kind)?;
    for (num, groups) in fams {
        let fg = new_group(path, &holder, &family_name(*num, groups))?;
        put_i32(path, &fg, "NUM", *num)?;
        let gro = new_group(path, &fg, "GRO")?;
        put_i32(path, &gro, "NBR", to_i32(path, groups.len())?)?;
        let names = groups.iter().map(|g| encode_name::<LNAME>(path, "group name", g)).collect::<Result<Vec<_>>>()?;
        let what = format!("dataset {}/NOM", gro.name());
        gro.new_dataset_builder()
            .with_data::<_, [i8; LNAME], _>(&names[..])
            .create("NOM")
            .map_err(|e| h5err(path, &what, e))?;
    }
    Ok(())
}

fn check_mesh(path: &Path, mesh: &Mesh, name: &str) -> Result<()> {
    if name.is_empty() || name.len() > NAME || !name.is_ascii() {
        return Err(ioerr(path, format!("bad mesh name '{name}' (1 to {NAME} ASCII characters)")));
    }
    if !(1..=3).contains(&mesh.dim) {
        return Err(ioerr(path, format!("mesh '{name}': bad space dimension {}", mesh.dim)));
    }
    let nn = mesh.coords.len();
    if mesh.node_names.len() != nn {
        return Err(ioerr(path, format!("mesh '{name}': {} node names for {nn} nodes", mesh.node_names.len())));
    }
    let nc = mesh.cells.len();
    if mesh.cell_types.len() != nc || mesh.cell_names.len() != nc {
        return Err(ioerr(path, format!("mesh '{name}': inconsistent cell arrays")));
    }
    for (i, (c, t)) in mesh.cells.iter().zip(&mesh.cell_types).enumerate() {
        if c.len() != t.nnodes() {
            return Err(ioerr(
                path,
                format!("mesh '{name}': cell {} ({}) has {} nodes", mesh.cell_names[i], t.name(), c.len()),
            ));
        }
        if let Some(&n) = c.iter().find(|&&n| n >= nn) {
            return Err(ioerr(path, format!("mesh '{name}': cell {} refers to node index {n}", mesh.cell_names[i])));
        }
    }
    Ok(())
}

/// Write `mesh` as the only content of a new MED 4.1.0 file at `path`,
/// under the mesh name `name`. The file is written to a temporary file and
/// renamed into place. Cells are written type by type in MED geometry-code
/// order (Code_Aster's numbering); within a type they keep their order.
pub fn write_mesh(path: &Path, mesh: &Mesh, name: &str) -> Result<()> {
    check_mesh(path, mesh, name)?;
    write_atomically(path, false, |tmp| {
        let file = super::file_options().create(tmp).map_err(|e| h5err(path, "creating the file", e))?;
        write_infos(path, &file)?;
        write_mesh_into(path, &file, mesh, name)?;
        file.close().map_err(|e| h5err(path, "closing the file", e))
    })
}

fn write_mesh_into(path: &Path, file: &hdf5::File, mesh: &Mesh, name: &str) -> Result<()> {
    let dim = mesh.dim;
    let nn = mesh.coords.len();
    let ens = new_group(path, file, "ENS_MAA")?;
    let mg = new_group(path, &ens, name)?;
    put_str(path, &mg, "DES", "created by aster-rs")?;
    put_i32(path, &mg, "DIM", dim as i32)?;
    put_i32(path, &mg, "ESP", dim as i32)?;
    put_str(path, &mg, "NOM", &pad16(&["X", "Y", "Z"][..dim]))?;
    put_i32(path, &mg, "NXI", -1)?;
    put_i32(path, &mg, "NXT", -1)?;
    put_i32(path, &mg, "REP", 0)?;
    put_i32(path, &mg, "SRT", 0)?;
    put_i32(path, &mg, "TYP", 0)?;
    put_str(path, &mg, "UNI", &pad16(&["", "", ""][..dim]))?;
    put_str(path, &mg, "UNT", "")?;

    let step = new_group(path, &mg, &step_name(-1, -1))?;
    put_i32(path, &step, "CGT", 1)?;
    put_i32(path, &step, "NDT", -1)?;
    put_i32(path, &step, "NOR", -1)?;
    put_i32(path, &step, "NXI", -1)?;
    put_i32(path, &step, "NXT", -1)?;
    put_f64(path, &step, "PDT", -1.0)?;
    put_i32(path, &step, "PVI", -1)?;
    put_i32(path, &step, "PVT", -1)?;

    // Nodes.
    let (node_fam, node_fams) = families(path, nn, &mesh.node_groups, 1, "node")?;
    let noe = new_group(path, &step, "NOE")?;
    put_i32(path, &noe, "CGS", 1)?;
    put_i32(path, &noe, "CGT", 1)?;
    put_str(path, &noe, "PFL", NO_PROFILE)?;
    let mut coo = Vec::with_capacity(nn * dim);
    for k in 0..dim {
        coo.extend(mesh.coords.iter().map(|c| c[k]));
    }
    put_ds(path, &noe, "COO", &coo, nn)?;
    put_ds(path, &noe, "FAM", &node_fam, nn)?;
    let names =
        mesh.node_names.iter().map(|n| encode_name::<SNAME>(path, "node name", n)).collect::<Result<Vec<_>>>()?;
    put_ds(path, &noe, "NOM", &names, nn)?;
    let nums: Vec<i32> = (1..=to_i32(path, nn)?).collect();
    put_ds(path, &noe, "NUM", &nums, nn)?;

    // Cells, in Code_Aster's order: by type in its reading order, stable within a type.
    let (cell_fam, cell_fams) = families(path, mesh.cells.len(), &mesh.cell_groups, -1, "cell")?;
    let mut order: Vec<usize> = (0..mesh.cells.len()).collect();
    order.sort_by_key(|&i| MedType::rank(mesh.cell_types[i]));
    let mai = new_group(path, &step, "MAI")?;
    put_i32(path, &mai, "CGT", 1)?;
    let mut written = 0usize;
    let mut start = 0;
    while start < order.len() {
        let ct = mesh.cell_types[order[start]];
        let end = start + order[start..].iter().take_while(|&&i| mesh.cell_types[i] == ct).count();
        let ids = &order[start..end];
        let mt = MedType::of(ct);
        let nc = ids.len();
        let nno = mt.nnodes();
        let mut nod = vec![0i32; nc * nno];
        for (i, &c) in ids.iter().enumerate() {
            let med = mt.to_med(&mesh.cells[c]);
            for (k, &n) in med.iter().enumerate() {
                nod[k * nc + i] = to_i32(path, n + 1)?;
            }
        }
        let tg = new_group(path, &mai, mt.med_name)?;
        put_i32(path, &tg, "CGS", 1)?;
        put_i32(path, &tg, "CGT", 1)?;
        put_i32(path, &tg, "GEO", mt.geo)?;
        put_str(path, &tg, "PFL", NO_PROFILE)?;
        let fam: Vec<i32> = ids.iter().map(|&c| cell_fam[c]).collect();
        put_ds(path, &tg, "FAM", &fam, nc)?;
        put_ds(path, &tg, "NOD", &nod, nc)?;
        let names = ids
            .iter()
            .map(|&c| encode_name::<SNAME>(path, "cell name", &mesh.cell_names[c]))
            .collect::<Result<Vec<_>>>()?;
        put_ds(path, &tg, "NOM", &names, nc)?;
        let nums: Vec<i32> = (written + 1..=written + nc).map(|i| i as i32).collect();
        put_ds(path, &tg, "NUM", &nums, nc)?;
        written += nc;
        start = end;
    }

    // Families.
    let fas = match file.group("FAS") {
        Ok(g) => g,
        Err(_) => new_group(path, file, "FAS")?,
    };
    let fm = new_group(path, &fas, name)?;
    let zero = new_group(path, &fm, "FAMILLE_ZERO")?;
    put_i32(path, &zero, "NUM", 0)?;
    write_families(path, &fm, "NOEUD", &node_fams)?;
    write_families(path, &fm, "ELEME", &cell_fams)?;
    Ok(())
}
