//! MED geometric types and the node orders that differ from Code_Aster's.
//!
//! This is the ONE place where MED and Code_Aster local node orders are
//! related. Everything else converts through [`MedType::to_aster`] and
//! [`MedType::to_med`].
//!
//! Sources of the facts (not of code): Code_Aster's `lrmtyp` (table
//! `numnoa`: "node j of the Code_Aster cell is node k of the MED cell", and
//! its inverse `nuanom`) and the MED-fichier geometry codes (`MED_HEXA20 =
//! 320`, ...). Code_Aster 2025's LIRE_MAILLAGE (`MeshReader`) numbers cells
//! type by type in its own type order (POI1, SEG2, SEG3, TRIA3, TRIA6, QUAD4,
//! QUAD8, QUAD9, TETRA4, TETRA10, PENTA6, PENTA15, PYRAM5, PYRAM13, HEXA8,
//! HEXA20, HEXA27: the order of [`CellType::ALL`]), not in MED geometry code
//! order (TETRA4, PYRAM5, PENTA6, HEXA8, TETRA10, ...) as the 2020 reader
//! (`lrmtyp`'s `renumd`) did: see [`MedType::rank`].

use crate::mesh::CellType;

/// One MED cell type.
#[derive(Debug, Clone, Copy)]
pub struct MedType {
    pub cell: CellType,
    /// Three-letter group name under `MAI/` (`HE8`, `T10`, ...).
    pub med_name: &'static str,
    /// MED geometry code (`GEO` attribute; hundreds = dimension, units = nodes).
    pub geo: i32,
    /// `aster_from_med[j]` = 0-based position, in the MED cell, of the
    /// Code_Aster local node `j`. `None` when both orders are the same.
    aster_from_med: Option<&'static [usize]>,
}

const TETRA4: [usize; 4] = [0, 2, 1, 3];
const PYRAM5: [usize; 5] = [0, 3, 2, 1, 4];
const PENTA6: [usize; 6] = [0, 2, 1, 3, 5, 4];
const HEXA8: [usize; 8] = [0, 3, 2, 1, 4, 7, 6, 5];
const TETRA10: [usize; 10] = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8];
const PYRAM13: [usize; 13] = [0, 3, 2, 1, 4, 8, 7, 6, 5, 9, 12, 11, 10];
const PENTA15: [usize; 15] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 12, 14, 13, 11, 10, 9];
const PENTA18: [usize; 18] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 12, 14, 13, 11, 10, 9, 17, 16, 15];
const HEXA20: [usize; 20] = [0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 16, 19, 18, 17, 15, 14, 13, 12];
const HEXA27: [usize; 27] =
    [0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 16, 19, 18, 17, 15, 14, 13, 12, 20, 24, 23, 22, 21, 25, 26];

const fn t(cell: CellType, med_name: &'static str, geo: i32, aster_from_med: Option<&'static [usize]>) -> MedType {
    MedType { cell, med_name, geo, aster_from_med }
}

/// All supported MED cell types, in increasing geometry code.
pub const MED_TYPES: [MedType; 20] = [
    t(CellType::Poi1, "PO1", 1, None),
    t(CellType::Seg2, "SE2", 102, None),
    t(CellType::Seg3, "SE3", 103, None),
    t(CellType::Seg4, "SE4", 104, None),
    t(CellType::Tria3, "TR3", 203, None),
    t(CellType::Quad4, "QU4", 204, None),
    t(CellType::Tria6, "TR6", 206, None),
    t(CellType::Tria7, "TR7", 207, None),
    t(CellType::Quad8, "QU8", 208, None),
    t(CellType::Quad9, "QU9", 209, None),
    t(CellType::Tetra4, "TE4", 304, Some(&TETRA4)),
    t(CellType::Pyram5, "PY5", 305, Some(&PYRAM5)),
    t(CellType::Penta6, "PE6", 306, Some(&PENTA6)),
    t(CellType::Hexa8, "HE8", 308, Some(&HEXA8)),
    t(CellType::Tetra10, "T10", 310, Some(&TETRA10)),
    t(CellType::Pyram13, "P13", 313, Some(&PYRAM13)),
    t(CellType::Penta15, "P15", 315, Some(&PENTA15)),
    t(CellType::Penta18, "P18", 318, Some(&PENTA18)),
    t(CellType::Hexa20, "H20", 320, Some(&HEXA20)),
    t(CellType::Hexa27, "H27", 327, Some(&HEXA27)),
];

impl MedType {
    pub fn by_med_name(name: &str) -> Option<&'static MedType> {
        MED_TYPES.iter().find(|m| m.med_name == name)
    }

    pub fn by_geo(geo: i32) -> Option<&'static MedType> {
        MED_TYPES.iter().find(|m| m.geo == geo)
    }

    pub fn of(cell: CellType) -> &'static MedType {
        MED_TYPES.iter().find(|m| m.cell == cell).expect("every CellType has a MED type")
    }

    /// Position of the type in Code_Aster 2025's reading order: cells are numbered type by type in
    /// this order, file order within a type.
    pub fn rank(cell: CellType) -> usize {
        CellType::ALL.iter().position(|&c| c == cell).expect("CellType::ALL lists every type")
    }

    pub fn nnodes(&self) -> usize {
        self.cell.nnodes()
    }

    /// The permutation `aster_from_med` (identity if the orders agree).
    pub fn aster_from_med(&self) -> Vec<usize> {
        match self.aster_from_med {
            Some(p) => p.to_vec(),
            None => (0..self.nnodes()).collect(),
        }
    }

    /// The inverse permutation: `med_from_aster[k]` = Code_Aster position of
    /// the MED local node `k`.
    pub fn med_from_aster(&self) -> Vec<usize> {
        inverse(&self.aster_from_med())
    }

    /// Reorder one cell's nodes from MED order to Code_Aster order.
    pub fn to_aster<T: Copy>(&self, med: &[T]) -> Vec<T> {
        match self.aster_from_med {
            Some(p) => p.iter().map(|&k| med[k]).collect(),
            None => med.to_vec(),
        }
    }

    /// Reorder one cell's nodes from Code_Aster order to MED order.
    pub fn to_med<T: Copy + Default>(&self, aster: &[T]) -> Vec<T> {
        match self.aster_from_med {
            Some(p) => {
                let mut med = vec![T::default(); aster.len()];
                for (j, &k) in p.iter().enumerate() {
                    med[k] = aster[j];
                }
                med
            }
            None => aster.to_vec(),
        }
    }
}

/// Inverse of a permutation of `0..n`.
pub fn inverse(p: &[usize]) -> Vec<usize> {
    let mut inv = vec![usize::MAX; p.len()];
    for (j, &k) in p.iter().enumerate() {
        inv[k] = j;
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_permutation(p: &[usize]) -> bool {
        let mut seen = vec![false; p.len()];
        for &k in p {
            if k >= p.len() || seen[k] {
                return false;
            }
            seen[k] = true;
        }
        true
    }

    #[test]
    fn tables_are_permutations_of_the_right_size() {
        for m in MED_TYPES.iter() {
            let p = m.aster_from_med();
            assert_eq!(p.len(), m.cell.nnodes(), "{}", m.med_name);
            assert!(is_permutation(&p), "{}", m.med_name);
            // Vertices stay among the first nodes in both orders.
            for (j, &k) in p.iter().enumerate() {
                assert_eq!(
                    j < m.cell.nvertices(),
                    k < m.cell.nvertices(),
                    "{}: vertex/non-vertex mix at {j}",
                    m.med_name
                );
            }
        }
    }

    #[test]
    fn permutation_and_inverse_compose_to_identity() {
        for m in MED_TYPES.iter() {
            let p = m.aster_from_med();
            let q = m.med_from_aster();
            for i in 0..p.len() {
                assert_eq!(p[q[i]], i, "{}", m.med_name);
                assert_eq!(q[p[i]], i, "{}", m.med_name);
            }
            let aster: Vec<usize> = (100..100 + p.len()).collect();
            assert_eq!(m.to_aster(&m.to_med(&aster)), aster, "{}", m.med_name);
            assert_eq!(m.to_med(&m.to_aster(&aster)), aster, "{}", m.med_name);
        }
    }

    #[test]
    fn inverse_matches_code_aster_nuanom_tables() {
        // Code_Aster's `nuanom` (MED node k is Code_Aster node j), 1-based,
        // listed independently of `numnoa`.
        let cases: [(CellType, &[usize]); 5] = [
            (CellType::Tetra10, &[1, 3, 2, 4, 7, 6, 5, 8, 10, 9]),
            (CellType::Pyram13, &[1, 4, 3, 2, 5, 9, 8, 7, 6, 10, 13, 12, 11]),
            (CellType::Penta15, &[1, 3, 2, 4, 6, 5, 9, 8, 7, 15, 14, 13, 10, 12, 11]),
            (CellType::Hexa20, &[1, 4, 3, 2, 5, 8, 7, 6, 12, 11, 10, 9, 20, 19, 18, 17, 13, 16, 15, 14]),
            (CellType::Penta18, &[1, 3, 2, 4, 6, 5, 9, 8, 7, 15, 14, 13, 10, 12, 11, 18, 17, 16]),
        ];
        for (cell, nuanom) in cases {
            let inv = MedType::of(cell).med_from_aster();
            let expected: Vec<usize> = nuanom.iter().map(|j| j - 1).collect();
            assert_eq!(inv, expected, "{cell:?}");
        }
    }

    #[test]
    fn cells_are_read_in_code_aster_type_order_not_geometry_code_order() {
        // MeshReader's asterTypeList: 3D linear types TETRA4, PENTA6, PYRAM5, HEXA8, quadratic after linear
        // per family; MED codes would put PYRAM5 (305) before PENTA6 (306) and HEXA8 (308) before TETRA10.
        use CellType::*;
        let order = [Poi1, Seg2, Seg3, Seg4, Tria3, Tria6, Tria7, Quad4, Quad8, Quad9, Tetra4, Tetra10, Penta6];
        let order: Vec<CellType> =
            order.into_iter().chain([Penta15, Penta18, Pyram5, Pyram13, Hexa8, Hexa20, Hexa27]).collect();
        for (i, c) in order.iter().enumerate() {
            assert_eq!(MedType::rank(*c), i, "{c:?}");
        }
    }

    #[test]
    fn geometry_codes_are_increasing_and_consistent() {
        for w in MED_TYPES.windows(2) {
            assert!(w[0].geo < w[1].geo);
        }
        for m in MED_TYPES.iter() {
            assert_eq!(m.geo as usize % 100, m.cell.nnodes(), "{}", m.med_name);
            assert_eq!(m.geo as usize / 100, m.cell.dim(), "{}", m.med_name);
            assert_eq!(MedType::by_geo(m.geo).unwrap().cell, m.cell);
            assert_eq!(MedType::by_med_name(m.med_name).unwrap().cell, m.cell);
        }
        assert_eq!(CellType::ALL.len(), MED_TYPES.len());
        for c in CellType::ALL {
            assert_eq!(MedType::of(c).cell, c);
        }
    }
}
