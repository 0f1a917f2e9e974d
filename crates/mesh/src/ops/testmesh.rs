//! Small meshes for the operations' unit tests.

use crate::{Cell, CellId, CellType, Group, Mesh, NodeId};

/// Two unit squares side by side (QUAD4 M1, M2), nodes N1–N6:
///
/// ```text
/// N4 --- N5 --- N6
/// |  M1  |  M2  |
/// N1 --- N2 --- N3
/// ```
/// plus a SEG2 M3 on the left edge; groups LEFT, RIGHT, ALL, EDGE and node
/// groups LEFT_EDGE, ALL_NODES.
pub(crate) fn two_quads() -> Mesh {
    let coords = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let n = |v: &[u32]| v.iter().map(|&i| NodeId(i - 1)).collect::<Vec<_>>();
    Mesh {
        dim: 2,
        node_names: (1..=6).map(|i| format!("N{i}")).collect(),
        coords,
        cells: vec![
            Cell {
                ty: CellType::QUAD4,
                nodes: n(&[1, 2, 5, 4]),
            },
            Cell {
                ty: CellType::QUAD4,
                nodes: n(&[2, 3, 6, 5]),
            },
            Cell {
                ty: CellType::SEG2,
                nodes: n(&[4, 1]),
            },
        ],
        cell_names: vec!["M1".into(), "M2".into(), "M3".into()],
        groups_ma: vec![
            Group {
                name: "LEFT".into(),
                members: vec![CellId(0)],
            },
            Group {
                name: "RIGHT".into(),
                members: vec![CellId(1)],
            },
            Group {
                name: "ALL".into(),
                members: vec![CellId(0), CellId(1)],
            },
            Group {
                name: "EDGE".into(),
                members: vec![CellId(2)],
            },
        ],
        groups_no: vec![
            Group {
                name: "LEFT_EDGE".into(),
                members: n(&[1, 4]),
            },
            Group {
                name: "ALL_NODES".into(),
                members: n(&[1, 2, 3, 4, 5, 6]),
            },
        ],
    }
}

/// The cells' node numbers, 1-based (code_aster's tables), for assertions.
pub(crate) fn one_based(m: &Mesh) -> Vec<Vec<u32>> {
    m.cells
        .iter()
        .map(|c| c.nodes.iter().map(|n| n.0 + 1).collect())
        .collect()
}
