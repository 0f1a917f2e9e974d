//! The in-memory mesh.

use serde::Serialize;

/// Index of a node in [`Mesh::coords`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct NodeId(pub u32);

/// Index of a cell in [`Mesh::cells`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct CellId(pub u32);

/// Cell types with code_aster's names; node ordering is code_aster's.
#[allow(clippy::upper_case_acronyms)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum CellType {
    POI1,
    SEG2,
    SEG3,
    SEG4,
    TRIA3,
    TRIA6,
    TRIA7,
    QUAD4,
    QUAD8,
    QUAD9,
    TETRA4,
    TETRA10,
    PENTA6,
    PENTA15,
    PENTA18,
    HEXA8,
    HEXA20,
    HEXA27,
    PYRAM5,
    PYRAM13,
}

impl CellType {
    /// The corner pairs of the cell's edges in code_aster's order (`conare`;
    /// the order the quadratic types number their mid-edge nodes: QUAD8
    /// 12 23 34 41, HEXA20 12 23 34 41 15 26 37 48 56 67 78 85…); empty for
    /// points.
    pub fn corner_edges(self) -> &'static [[usize; 2]] {
        use CellType::*;
        match self {
            SEG2 | SEG3 | SEG4 => &[[0, 1]],
            TRIA3 | TRIA6 | TRIA7 => &[[0, 1], [1, 2], [2, 0]],
            QUAD4 | QUAD8 | QUAD9 => &[[0, 1], [1, 2], [2, 3], [3, 0]],
            TETRA4 | TETRA10 => &[[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]],
            PENTA6 | PENTA15 | PENTA18 => &[
                [0, 1],
                [1, 2],
                [2, 0],
                [0, 3],
                [1, 4],
                [2, 5],
                [3, 4],
                [4, 5],
                [5, 3],
            ],
            HEXA8 | HEXA20 | HEXA27 => &[
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [0, 4],
                [1, 5],
                [2, 6],
                [3, 7],
                [4, 5],
                [5, 6],
                [6, 7],
                [7, 4],
            ],
            PYRAM5 | PYRAM13 => &[
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [0, 4],
                [1, 4],
                [2, 4],
                [3, 4],
            ],
            _ => &[],
        }
    }

    pub const ALL: [CellType; 20] = [
        CellType::POI1,
        CellType::SEG2,
        CellType::SEG3,
        CellType::SEG4,
        CellType::TRIA3,
        CellType::TRIA6,
        CellType::TRIA7,
        CellType::QUAD4,
        CellType::QUAD8,
        CellType::QUAD9,
        CellType::TETRA4,
        CellType::TETRA10,
        CellType::PENTA6,
        CellType::PENTA15,
        CellType::PENTA18,
        CellType::HEXA8,
        CellType::HEXA20,
        CellType::HEXA27,
        CellType::PYRAM5,
        CellType::PYRAM13,
    ];

    /// code_aster's name, e.g. `"QUAD4"`.
    pub fn name(self) -> &'static str {
        match self {
            CellType::POI1 => "POI1",
            CellType::SEG2 => "SEG2",
            CellType::SEG3 => "SEG3",
            CellType::SEG4 => "SEG4",
            CellType::TRIA3 => "TRIA3",
            CellType::TRIA6 => "TRIA6",
            CellType::TRIA7 => "TRIA7",
            CellType::QUAD4 => "QUAD4",
            CellType::QUAD8 => "QUAD8",
            CellType::QUAD9 => "QUAD9",
            CellType::TETRA4 => "TETRA4",
            CellType::TETRA10 => "TETRA10",
            CellType::PENTA6 => "PENTA6",
            CellType::PENTA15 => "PENTA15",
            CellType::PENTA18 => "PENTA18",
            CellType::HEXA8 => "HEXA8",
            CellType::HEXA20 => "HEXA20",
            CellType::HEXA27 => "HEXA27",
            CellType::PYRAM5 => "PYRAM5",
            CellType::PYRAM13 => "PYRAM13",
        }
    }

    pub fn from_name(name: &str) -> Option<CellType> {
        CellType::ALL.into_iter().find(|t| t.name() == name)
    }

    pub fn node_count(self) -> usize {
        match self {
            CellType::POI1 => 1,
            CellType::SEG2 => 2,
            CellType::SEG3 => 3,
            CellType::SEG4 => 4,
            CellType::TRIA3 => 3,
            CellType::TRIA6 => 6,
            CellType::TRIA7 => 7,
            CellType::QUAD4 => 4,
            CellType::QUAD8 => 8,
            CellType::QUAD9 => 9,
            CellType::TETRA4 => 4,
            CellType::TETRA10 => 10,
            CellType::PENTA6 => 6,
            CellType::PENTA15 => 15,
            CellType::PENTA18 => 18,
            CellType::HEXA8 => 8,
            CellType::HEXA20 => 20,
            CellType::HEXA27 => 27,
            CellType::PYRAM5 => 5,
            CellType::PYRAM13 => 13,
        }
    }

    /// Topological dimension: 0 for points, 1 for segments, 2 for faces, 3 for volumes.
    pub fn dim(self) -> u8 {
        match self {
            CellType::POI1 => 0,
            CellType::SEG2 | CellType::SEG3 | CellType::SEG4 => 1,
            CellType::TRIA3
            | CellType::TRIA6
            | CellType::TRIA7
            | CellType::QUAD4
            | CellType::QUAD8
            | CellType::QUAD9 => 2,
            _ => 3,
        }
    }
}

/// One cell: its type and its nodes in code_aster order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    pub ty: CellType,
    pub nodes: Vec<NodeId>,
}

/// A named group (of cells or of nodes), in file order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Group<T> {
    pub name: String,
    pub members: Vec<T>,
}

/// A mesh: nodes, cells and groups.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Mesh {
    /// Space dimension of the coordinates (2 or 3; 1 is possible).
    pub dim: u8,
    /// Node coordinates; unused components are 0.
    pub coords: Vec<[f64; 3]>,
    /// Node names (`N1`…), same length as `coords`.
    pub node_names: Vec<String>,
    pub cells: Vec<Cell>,
    /// Cell names (`M1`…), same length as `cells`.
    pub cell_names: Vec<String>,
    pub groups_ma: Vec<Group<CellId>>,
    pub groups_no: Vec<Group<NodeId>>,
}

/// The axis-aligned bounding box (lowest, highest corner) of points; of no
/// point, the empty box (+∞, −∞).
pub fn bounding_box(points: impl IntoIterator<Item = [f64; 3]>) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The length of a box's diagonal (0 for an empty box).
pub fn box_diagonal((lo, hi): ([f64; 3], [f64; 3])) -> f64 {
    (0..3)
        .map(|k| (hi[k] - lo[k]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

impl Mesh {
    pub fn node_count(&self) -> usize {
        self.coords.len()
    }

    pub fn group_ma(&self, name: &str) -> Option<&Group<CellId>> {
        self.groups_ma.iter().find(|g| g.name == name)
    }

    pub fn group_no(&self, name: &str) -> Option<&Group<NodeId>> {
        self.groups_no.iter().find(|g| g.name == name)
    }

    pub fn cell(&self, id: CellId) -> &Cell {
        &self.cells[id.0 as usize]
    }

    pub fn coord(&self, id: NodeId) -> [f64; 3] {
        self.coords[id.0 as usize]
    }

    /// A cell's name for messages (`#n`, 1-based, for a cell without one).
    pub fn cell_name(&self, id: CellId) -> String {
        self.cell_names
            .get(id.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("#{}", id.0 + 1))
    }

    /// A node's name for messages (`N<n>`, 1-based, as code_aster names
    /// nodes, for a node without one).
    pub fn node_name(&self, id: NodeId) -> String {
        self.node_names
            .get(id.0 as usize)
            .cloned()
            .unwrap_or_else(|| format!("N{}", id.0 + 1))
    }
}
