// Shared by the benchmark and the gen_grid example.

use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

/// A 1000 × 1000 grid of nodes: 998,001 QUAD4, 3,996 boundary SEG2, cell
/// and node groups for the four sides.
pub fn grid(n: usize) -> Mesh {
    let mut m = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    for j in 0..n {
        for i in 0..n {
            m.coords.push([i as f64 * 1e-3, j as f64 * 1e-3, 0.0]);
        }
    }
    m.node_names = (1..=n * n).map(|i| format!("N{i}")).collect();
    let id = |i: usize, j: usize| NodeId((j * n + i) as u32);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            m.cells.push(Cell {
                ty: CellType::QUAD4,
                nodes: vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            });
        }
    }
    let side = |name: &str, edges: Vec<(NodeId, NodeId)>, m: &mut Mesh| {
        let start = m.cells.len();
        let mut nodes = Vec::new();
        for (a, b) in edges {
            m.cells.push(Cell {
                ty: CellType::SEG2,
                nodes: vec![a, b],
            });
            nodes.push(a);
        }
        let cells = (start..m.cells.len()).map(|c| CellId(c as u32)).collect();
        m.groups_ma.push(Group {
            name: name.into(),
            members: cells,
        });
        m.groups_no.push(Group {
            name: name.into(),
            members: nodes,
        });
    };
    side(
        "BAS",
        (0..n - 1).map(|i| (id(i, 0), id(i + 1, 0))).collect(),
        &mut m,
    );
    side(
        "DROITE",
        (0..n - 1)
            .map(|j| (id(n - 1, j), id(n - 1, j + 1)))
            .collect(),
        &mut m,
    );
    side(
        "HAUT",
        (0..n - 1)
            .map(|i| (id(i + 1, n - 1), id(i, n - 1)))
            .collect(),
        &mut m,
    );
    side(
        "GAUCHE",
        (0..n - 1).map(|j| (id(0, j + 1), id(0, j))).collect(),
        &mut m,
    );
    m.cell_names = (1..=m.cells.len()).map(|i| format!("M{i}")).collect();
    m
}
