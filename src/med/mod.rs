//! MED files (MED-fichier 3.x / 4.x over HDF5): meshes, and fields of every support (nodes, cells,
//! nodes of cells, integration points with their localizations) with profiles.
//!
//! Layout handled here (MED 3/4, unstructured meshes, nodal connectivity):
//!
//! ```text
//! /INFOS_GENERALES                      attrs MAJ MIN REL
//! /ENS_MAA/<mesh>                       attrs DIM ESP NOM UNI DES TYP REP SRT ...
//! /ENS_MAA/<mesh>/<step>/NOE/{COO,NOM,NUM,FAM}
//! /ENS_MAA/<mesh>/<step>/MAI/<TYP>/{NOD,NOM,NUM,FAM}
//! /FAS/<mesh>/{NOEUD,ELEME}/<family>/GRO/NOM   family number in attr NUM
//! /CHA/<field>/<numdt><numit>/NOE/MED_NO_PROFILE_INTERNAL/CO
//! /CHA/<field>/<numdt><numit>/{MAI,NOE}.<TYP>/<profile>/CO     cell fields (cellfield.rs)
//! /GAUSS/<localization>/{COO,GAU,VAL}                          integration points (gauss.rs)
//! /PROFILS/<profile>/PFL                                       parts of the mesh
//! ```
//!
//! Coordinates, connectivities and field values are stored non-interlaced
//! (all first components, then all second components, ...). Node numbers in
//! connectivities are 1-based. Node and cell numbering follows Code_Aster:
//! nodes in file order, cells type by type in Code_Aster's type order
//! (see [`types::MedType::rank`]), file order within a type. Unnamed entities get
//! Code_Aster's default names `N1, N2, ...` / `M1, M2, ...`.

pub mod cellfield;
pub mod diff;
mod field;
pub mod gauss;
mod read;
pub mod types;
mod write;

pub use cellfield::{read_field, read_localizations, write_fields, Block, FieldStep, MedField, Support};
pub use field::{list_fields, read_node_field, write_node_field, NodeField};
pub use gauss::Localization;
pub use read::{list_meshes, read_mesh};
pub use write::write_mesh;

use crate::diag::Error;
use hdf5_metno as hdf5;
use std::path::Path;

/// Size of entity names (`NOE/NOM`, `MAI/*/NOM`).
pub(crate) const SNAME: usize = 16;
/// Size of group names (`GRO/NOM`).
pub(crate) const LNAME: usize = 80;
/// Size of MED object names (meshes, fields, families).
pub(crate) const NAME: usize = 64;
/// Version stamped in files we write (Debian's med-fichier 4.1 rejects 4.2).
pub(crate) const MED_VERSION: (i32, i32, i32) = (4, 1, 0);
pub(crate) const NO_PROFILE: &str = "MED_NO_PROFILE_INTERNAL";

/// `file: what: hdf5 message` as an I/O error.
pub(crate) fn h5err(path: &Path, what: &str, e: impl std::fmt::Display) -> Error {
    Error::io(format!("MED file {}: {what}: {e}", path.display()))
}

pub(crate) fn ioerr(path: &Path, msg: impl std::fmt::Display) -> Error {
    Error::io(format!("MED file {}: {msg}", path.display()))
}

/// Decode a fixed-size name: stop at the first NUL, drop trailing blanks.
pub(crate) fn decode_name(bytes: &[i8]) -> String {
    let raw: Vec<u8> = bytes.iter().map(|&b| b as u8).take_while(|&b| b != 0).collect();
    String::from_utf8_lossy(&raw).trim_end().to_string()
}

/// Encode a name into a fixed-size, blank-padded field.
pub(crate) fn encode_name<const N: usize>(path: &Path, what: &str, name: &str) -> crate::diag::Result<[i8; N]> {
    if name.len() > N {
        return Err(ioerr(path, format!("{what} '{name}' is longer than {N} bytes")));
    }
    let mut out = [b' ' as i8; N];
    for (o, b) in out.iter_mut().zip(name.bytes()) {
        *o = b as i8;
    }
    Ok(out)
}

/// Open an existing file for reading, with a clear message for files that
/// are not HDF5 at all and for damaged (e.g. truncated) ones.
pub(crate) fn open_read(path: &Path) -> crate::diag::Result<hdf5::File> {
    let meta = std::fs::metadata(path).map_err(|e| ioerr(path, format!("cannot open: {e}")))?;
    if !meta.is_file() {
        return Err(ioerr(path, "not a regular file"));
    }
    if !has_hdf5_signature(path) {
        return Err(ioerr(path, "not an HDF5 file (no HDF5 signature): not a MED file"));
    }
    file_options()
        .open(path)
        .map_err(|e| ioerr(path, format!("damaged or truncated HDF5 file, cannot be opened as MED: {e}")))
}

/// File options for every file we open: no HDF5 file locking (the locks
/// are held by open file descriptions, which child processes spawned while a
/// file is open inherit: a later open of the same file would then fail; our
/// writes go to private temporary files anyway), and a strong close degree
/// (closing the file closes everything in it).
pub(crate) fn file_options() -> hdf5::file::FileBuilder {
    let mut b = hdf5::File::with_options();
    b.with_fapl(|p| p.file_locking(false).fclose_degree(hdf5::file::FileCloseDegree::Strong));
    b.with_fcpl(|p| p.link_creation_order(hdf5::plist::group_create::LinkCreationOrder::Indexed));
    b
}

/// The HDF5 superblock signature sits at offset 0, 512, 1024, 2048, ...
fn has_hdf5_signature(path: &Path) -> bool {
    use std::io::{Read, Seek, SeekFrom};
    const SIG: [u8; 8] = [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'];
    let Ok(mut f) = std::fs::File::open(path) else {
        return false;
    };
    let len = f.metadata().map(|m| m.len()).unwrap_or(0);
    let mut off = 0u64;
    while off + 8 <= len {
        let mut buf = [0u8; 8];
        if f.seek(SeekFrom::Start(off)).is_err() || f.read_exact(&mut buf).is_err() {
            return false;
        }
        if buf == SIG {
            return true;
        }
        off = if off == 0 { 512 } else { off * 2 };
    }
    false
}

/// A temporary path beside `path` (same directory, so `rename` is atomic).
pub(crate) fn temp_path(path: &Path) -> std::path::PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let unique = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos()).unwrap_or(0);
    path.with_file_name(format!(".{name}.{}.{unique}.tmp", std::process::id()))
}

/// Run `body` on a temporary file, then rename it over `path`; the
/// temporary file is removed on error.
pub(crate) fn write_atomically(
    path: &Path,
    seed_from_existing: bool,
    body: impl FnOnce(&Path) -> crate::diag::Result<()>,
) -> crate::diag::Result<()> {
    let tmp = temp_path(path);
    if seed_from_existing {
        std::fs::copy(path, &tmp).map_err(|e| ioerr(path, format!("cannot copy to a temporary file: {e}")))?;
    }
    let res = body(&tmp);
    match res {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            ioerr(path, format!("cannot rename the temporary file into place: {e}"))
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}
