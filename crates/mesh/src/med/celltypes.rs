//! MED geometric types and their mapping to code_aster cell types.
//!
//! MED orders the nodes of 3D cells differently from code_aster: MED's
//! volumes are numbered so that the first face is seen clockwise from
//! outside, code_aster's counter-clockwise. The tables below give, for each
//! code_aster node position `j`, the MED node `k` it is (1-based, as in
//! code_aster's MED reader: "node j in aster is node k in med"). Types not
//! listed (points, segments, faces) share the same ordering.

use crate::CellType;

/// (MED type name, MED geometry number, code_aster type), in increasing
/// MED geometry number: the order code_aster numbers cells in.
pub const MED_TYPES: [(&str, i32, CellType); 20] = [
    ("PO1", 1, CellType::POI1),
    ("SE2", 102, CellType::SEG2),
    ("SE3", 103, CellType::SEG3),
    ("SE4", 104, CellType::SEG4),
    ("TR3", 203, CellType::TRIA3),
    ("QU4", 204, CellType::QUAD4),
    ("TR6", 206, CellType::TRIA6),
    ("TR7", 207, CellType::TRIA7),
    ("QU8", 208, CellType::QUAD8),
    ("QU9", 209, CellType::QUAD9),
    ("TE4", 304, CellType::TETRA4),
    ("PY5", 305, CellType::PYRAM5),
    ("PE6", 306, CellType::PENTA6),
    ("HE8", 308, CellType::HEXA8),
    ("T10", 310, CellType::TETRA10),
    ("P13", 313, CellType::PYRAM13),
    ("P15", 315, CellType::PENTA15),
    ("P18", 318, CellType::PENTA18),
    ("H20", 320, CellType::HEXA20),
    ("H27", 327, CellType::HEXA27),
];

pub fn from_med_name(name: &str) -> Option<CellType> {
    MED_TYPES.iter().find(|t| t.0 == name).map(|t| t.2)
}

pub fn med_name(ty: CellType) -> &'static str {
    MED_TYPES.iter().find(|t| t.2 == ty).map_or("", |t| t.0)
}

pub fn med_geo(ty: CellType) -> i32 {
    MED_TYPES.iter().find(|t| t.2 == ty).map_or(0, |t| t.1)
}

/// For code_aster node position `j` (0-based), the 0-based MED position;
/// `None` when both orders agree.
pub fn aster_from_med(ty: CellType) -> Option<&'static [usize]> {
    const TETRA4: [usize; 4] = [0, 2, 1, 3];
    const TETRA10: [usize; 10] = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8];
    const PENTA6: [usize; 6] = [0, 2, 1, 3, 5, 4];
    const PENTA15: [usize; 15] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 12, 14, 13, 11, 10, 9];
    const PENTA18: [usize; 18] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 12, 14, 13, 11, 10, 9, 17, 16, 15];
    const PYRAM5: [usize; 5] = [0, 3, 2, 1, 4];
    const PYRAM13: [usize; 13] = [0, 3, 2, 1, 4, 8, 7, 6, 5, 9, 12, 11, 10];
    const HEXA8: [usize; 8] = [0, 3, 2, 1, 4, 7, 6, 5];
    const HEXA20: [usize; 20] = [
        0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 16, 19, 18, 17, 15, 14, 13, 12,
    ];
    const HEXA27: [usize; 27] = [
        0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 16, 19, 18, 17, 15, 14, 13, 12, 20, 24, 23, 22, 21,
        25, 26,
    ];
    match ty {
        CellType::TETRA4 => Some(&TETRA4),
        CellType::TETRA10 => Some(&TETRA10),
        CellType::PENTA6 => Some(&PENTA6),
        CellType::PENTA15 => Some(&PENTA15),
        CellType::PENTA18 => Some(&PENTA18),
        CellType::PYRAM5 => Some(&PYRAM5),
        CellType::PYRAM13 => Some(&PYRAM13),
        CellType::HEXA8 => Some(&HEXA8),
        CellType::HEXA20 => Some(&HEXA20),
        CellType::HEXA27 => Some(&HEXA27),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutations_are_bijections_of_the_right_size() {
        for ty in CellType::ALL {
            if let Some(p) = aster_from_med(ty) {
                assert_eq!(p.len(), ty.node_count(), "{ty:?}");
                let mut seen = vec![false; p.len()];
                for &k in p {
                    assert!(!seen[k], "{ty:?} repeats {k}");
                    seen[k] = true;
                }
            }
        }
    }

    #[test]
    fn every_aster_type_has_a_med_name() {
        for ty in CellType::ALL {
            assert_eq!(from_med_name(med_name(ty)), Some(ty));
        }
    }
}
