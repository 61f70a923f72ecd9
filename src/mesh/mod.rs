//! Meshes: nodes, cells and groups, in Code_Aster's numbering and node order.
//!
//! Cells are stored with their nodes in Code_Aster's local order; converting
//! from and to other orders (MED) is the job of the format layer alone.

pub mod aster_text;
pub mod check;
pub mod convert;
pub mod derive;
pub mod generate;
pub mod gibi;
pub mod gmsh;
pub mod ideas;
pub mod line;

use std::collections::BTreeMap;

/// Cell types, named as in Code_Aster.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellType {
    Poi1,
    Seg2,
    Seg3,
    Seg4,
    Tria3,
    Tria6,
    Tria7,
    Quad4,
    Quad8,
    Quad9,
    Tetra4,
    Tetra10,
    Penta6,
    Penta15,
    Penta18,
    Pyram5,
    Pyram13,
    Hexa8,
    Hexa20,
    Hexa27,
}

impl CellType {
    /// Every type, in Code_Aster's order of cell types (`&CATA.TM`), which is the order its MED
    /// reader numbers cells in.
    pub const ALL: [CellType; 20] = [
        CellType::Poi1,
        CellType::Seg2,
        CellType::Seg3,
        CellType::Seg4,
        CellType::Tria3,
        CellType::Tria6,
        CellType::Tria7,
        CellType::Quad4,
        CellType::Quad8,
        CellType::Quad9,
        CellType::Tetra4,
        CellType::Tetra10,
        CellType::Penta6,
        CellType::Penta15,
        CellType::Penta18,
        CellType::Pyram5,
        CellType::Pyram13,
        CellType::Hexa8,
        CellType::Hexa20,
        CellType::Hexa27,
    ];

    pub fn name(self) -> &'static str {
        use CellType::*;
        match self {
            Poi1 => "POI1",
            Seg2 => "SEG2",
            Seg3 => "SEG3",
            Seg4 => "SEG4",
            Tria3 => "TRIA3",
            Tria6 => "TRIA6",
            Tria7 => "TRIA7",
            Quad4 => "QUAD4",
            Quad8 => "QUAD8",
            Quad9 => "QUAD9",
            Tetra4 => "TETRA4",
            Tetra10 => "TETRA10",
            Penta6 => "PENTA6",
            Penta15 => "PENTA15",
            Penta18 => "PENTA18",
            Pyram5 => "PYRAM5",
            Pyram13 => "PYRAM13",
            Hexa8 => "HEXA8",
            Hexa20 => "HEXA20",
            Hexa27 => "HEXA27",
        }
    }

    pub fn from_name(s: &str) -> Option<CellType> {
        CellType::ALL.iter().copied().find(|t| t.name() == s)
    }

    pub fn nnodes(self) -> usize {
        use CellType::*;
        match self {
            Poi1 => 1,
            Seg2 => 2,
            Seg3 => 3,
            Seg4 => 4,
            Tria3 => 3,
            Tria6 => 6,
            Tria7 => 7,
            Quad4 => 4,
            Quad8 => 8,
            Quad9 => 9,
            Tetra4 => 4,
            Tetra10 => 10,
            Penta6 => 6,
            Penta15 => 15,
            Penta18 => 18,
            Pyram5 => 5,
            Pyram13 => 13,
            Hexa8 => 8,
            Hexa20 => 20,
            Hexa27 => 27,
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        use CellType::*;
        match self {
            Poi1 => 0,
            Seg2 | Seg3 | Seg4 => 1,
            Tria3 | Tria6 | Tria7 | Quad4 | Quad8 | Quad9 => 2,
            _ => 3,
        }
    }

    /// Number of vertices (corner nodes, listed first in every order used here).
    pub fn nvertices(self) -> usize {
        use CellType::*;
        match self {
            Poi1 => 1,
            Seg2 | Seg3 | Seg4 => 2,
            Tria3 | Tria6 | Tria7 => 3,
            Quad4 | Quad8 | Quad9 => 4,
            Tetra4 | Tetra10 => 4,
            Penta6 | Penta15 | Penta18 => 6,
            Pyram5 | Pyram13 => 5,
            Hexa8 | Hexa20 | Hexa27 => 8,
        }
    }
}

/// The text mesh formats LIRE_MAILLAGE reads besides MED.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextFormat {
    /// Code_Aster's own (`.mail`).
    Aster,
    /// Gmsh (`.msh`, formats 1, 2 and 4 in ASCII).
    Gmsh,
    /// Cast3M's saved files (`.mgib`).
    Gibi,
    /// I-DEAS universal files (`.unv`, `.msup`); `colour_groups`: CREA_GROUP_COUL='OUI'.
    Ideas { colour_groups: bool },
}

impl TextFormat {
    /// The format of LIRE_MAILLAGE's FORMAT keyword (`ASTER`, `GMSH`, `GIBI`, `IDEAS`).
    pub fn from_keyword(name: &str) -> Option<TextFormat> {
        Some(match name {
            "ASTER" => TextFormat::Aster,
            "GMSH" => TextFormat::Gmsh,
            "GIBI" => TextFormat::Gibi,
            "IDEAS" => TextFormat::Ideas { colour_groups: false },
            _ => return None,
        })
    }

    /// The format a file's extension names: `.mail`, `.msh`, `.mgib`, `.unv` / `.msup`.
    pub fn from_extension(ext: &str) -> Option<TextFormat> {
        Some(match ext.to_ascii_lowercase().as_str() {
            "mail" => TextFormat::Aster,
            "msh" => TextFormat::Gmsh,
            "mgib" | "gibi" => TextFormat::Gibi,
            "unv" | "msup" | "ideas" => TextFormat::Ideas { colour_groups: false },
            _ => return None,
        })
    }

    /// Read a mesh of this format from its text; `file` names it in errors (`file:line: message`).
    pub fn read(self, src: &str, file: &str) -> Result<Mesh, String> {
        match self {
            TextFormat::Aster => aster_text::read(src, file),
            TextFormat::Gmsh => gmsh::read(src, file),
            TextFormat::Gibi => gibi::read(src, file),
            TextFormat::Ideas { colour_groups } => ideas::read(src, file, colour_groups),
        }
    }
}

/// The entity that a name of Code_Aster 2025's numbering designates: since version 17 it no longer keeps
/// the names a mesh file gives its entities and calls node k `N<k>` and cell k `M<k>` (1-based), while
/// 2020-era files name them as their mesh file does. `name` read that way (`prefix` 'N' or 'M'), among
/// `count` entities; the stages try it only where no entity bears the name itself. A bare number
/// designates the entity of that number too, as Code_Aster's `char8_to_int` reads it on a mesh
/// without names (`MAILLE='12'`, `NOEUD='1'`).
pub fn numbered(name: &str, prefix: char, count: usize) -> Option<usize> {
    let digits = name.strip_prefix(prefix).unwrap_or(name);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.starts_with('0') {
        return None;
    }
    let k: usize = digits.parse().ok()?;
    (1..=count).contains(&k).then(|| k - 1)
}

/// A mesh. Nodes and cells are numbered from 0 in storage; their names
/// (N1, M1, ...) are what users see.
#[derive(Debug, Clone, Default)]
pub struct Mesh {
    /// Space dimension (2 or 3).
    pub dim: usize,
    pub coords: Vec<[f64; 3]>,
    pub node_names: Vec<String>,
    pub cell_types: Vec<CellType>,
    /// Connectivity in Code_Aster's local node order (0-based node indices).
    pub cells: Vec<Vec<usize>>,
    pub cell_names: Vec<String>,
    pub node_groups: BTreeMap<String, Vec<usize>>,
    pub cell_groups: BTreeMap<String, Vec<usize>>,
    /// False when the file gave no node names: they were made up as N1, N2, ...
    /// (Code_Aster then shows node numbers in tables).
    pub named_nodes: bool,
}

impl Mesh {
    pub fn nnodes(&self) -> usize {
        self.coords.len()
    }

    pub fn ncells(&self) -> usize {
        self.cells.len()
    }

    /// Number of cells of each type present.
    pub fn cell_type_counts(&self) -> BTreeMap<CellType, usize> {
        let mut m = BTreeMap::new();
        for t in &self.cell_types {
            *m.entry(*t).or_insert(0) += 1;
        }
        m
    }

    /// `(min, max)` corners of the node coordinates, `None` without nodes.
    pub fn bounding_box(&self) -> Option<([f64; 3], [f64; 3])> {
        let first = *self.coords.first()?;
        let (mut lo, mut hi) = (first, first);
        for c in &self.coords {
            for k in 0..3 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        Some((lo, hi))
    }

    /// Sizes of the node groups.
    pub fn node_group_sizes(&self) -> BTreeMap<String, usize> {
        self.node_groups.iter().map(|(k, v)| (k.clone(), v.len())).collect()
    }

    /// Sizes of the cell groups.
    pub fn cell_group_sizes(&self) -> BTreeMap<String, usize> {
        self.cell_groups.iter().map(|(k, v)| (k.clone(), v.len())).collect()
    }

    /// A text summary of a mesh: nodes, cells per type, groups with their
    /// sizes, bounding box (LIRE_MAILLAGE INFO=2, `aster mesh info`).
    pub fn describe(&self, name: &str) -> String {
        use std::fmt::Write as _;
        let mesh = self;
        let mut s = String::new();
        let _ = writeln!(s, "mesh {name}: space dimension {}", mesh.dim);
        let _ = writeln!(s, "  nodes: {}", mesh.nnodes());
        let _ = writeln!(s, "  cells: {}", mesh.ncells());
        for (t, n) in mesh.cell_type_counts() {
            let _ = writeln!(s, "    {:<8} {n:>10}", t.name());
        }
        let _ = writeln!(s, "  groups of cells: {}", mesh.cell_groups.len());
        for (g, n) in mesh.cell_group_sizes() {
            let _ = writeln!(s, "    {g:<24} {n:>10}");
        }
        let _ = writeln!(s, "  groups of nodes: {}", mesh.node_groups.len());
        for (g, n) in mesh.node_group_sizes() {
            let _ = writeln!(s, "    {g:<24} {n:>10}");
        }
        if let Some((lo, hi)) = mesh.bounding_box() {
            let axes = ["x", "y", "z"];
            let parts: Vec<String> =
                (0..mesh.dim.clamp(1, 3)).map(|k| format!("{} in [{}, {}]", axes[k], lo[k], hi[k])).collect();
            let _ = writeln!(s, "  bounding box: {}", parts.join(", "));
        }
        s
    }
}

#[cfg(test)]
mod numbered_tests {
    use super::numbered;

    #[test]
    fn numbered_names_are_those_of_code_aster_2025() {
        assert_eq!(numbered("M5", 'M', 5), Some(4));
        assert_eq!(numbered("N1", 'N', 3), Some(0));
        assert_eq!(numbered("12", 'M', 12), Some(11));
        assert_eq!(numbered("1", 'N', 3), Some(0));
        for bad in ["M6", "M0", "M05", "M", "MA5", "N5", "6", "0", "05", ""] {
            assert_eq!(numbered(bad, 'M', 5), None, "{bad}");
        }
    }
}
