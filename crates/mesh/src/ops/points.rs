//! `CREA_MAILLAGE(CREA_POI1=…)`: point cells on nodes, and
//! `MODI_MAILLE(OPTION='QUAD_TRIA3')`: quadrangles (QUAD4, QUAD8, QUAD9)
//! cut into triangles.

use crate::ops::rebuild::Namer;
use crate::{Cell, CellId, CellType, Mesh, NodeId};

impl Mesh {
    /// One new POI1 cell per node (in the order given, each node once),
    /// appended after the existing cells; with `group`, the new cells also
    /// form that cell group (replacing one of the same name). Returns the
    /// new cells.
    pub fn add_point_cells(&mut self, nodes: &[NodeId], group: Option<&str>) -> Vec<CellId> {
        let mut namer = Namer::new(&self.cell_names, "M");
        let mut seen = vec![false; self.node_count()];
        let mut made = Vec::new();
        for &n in nodes {
            if std::mem::replace(&mut seen[n.0 as usize], true) {
                continue;
            }
            let id = CellId(self.cells.len() as u32);
            let name = namer.name(self.cells.len());
            self.cells.push(Cell {
                ty: CellType::POI1,
                nodes: vec![n],
            });
            self.cell_names.push(name);
            made.push(id);
        }
        if let Some(g) = group {
            self.set_group_ma(g, made.clone());
        }
        made
    }

    /// `QUAD_TRIA3`: each selected QUAD4 (1 2 3 4) becomes the TRIA3s
    /// (1 2 3) and (3 4 1), each QUAD8 or QUAD9 the six TRIA3s (1 5 8)
    /// (5 2 6) (6 3 7) (7 4 8) (5 7 8) (5 6 7) of its edge nodes (a QUAD9's
    /// centre is left in no cell, as code_aster's `irgmtb` table does: "as a
    /// QUAD8, DX DY DZ being unknown on node 9 in COQUE_3D"), in place; the
    /// other cells are kept. The pieces get fresh names and belong to the
    /// groups of their quadrangle. Returns how many quadrangles were cut.
    pub fn quad4_to_tria3(&mut self, selected: &[CellId]) -> Result<usize, crate::MeshError> {
        let mut cut = vec![false; self.cells.len()];
        for &c in selected {
            if matches!(
                self.cell(c).ty,
                CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9
            ) {
                cut[c.0 as usize] = true;
            }
        }
        let count = cut.iter().filter(|c| **c).count();
        // code_aster's `irgmtb` tables (1-based node numbers).
        const QUAD4: [[usize; 3]; 2] = [[1, 2, 3], [3, 4, 1]];
        const QUAD8: [[usize; 3]; 6] = [
            [1, 5, 8],
            [5, 2, 6],
            [6, 3, 7],
            [7, 4, 8],
            [5, 7, 8],
            [5, 6, 7],
        ];
        self.rewrite_cells(|id, cell| {
            if !cut[id.0 as usize] {
                return vec![cell.clone()];
            }
            let table: &[[usize; 3]] = if cell.ty == CellType::QUAD4 {
                &QUAD4
            } else {
                &QUAD8
            };
            table
                .iter()
                .map(|t| Cell {
                    ty: CellType::TRIA3,
                    nodes: t.iter().map(|&k| cell.nodes[k - 1]).collect(),
                })
                .collect()
        });
        Ok(count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::testmesh::two_quads;

    #[test]
    fn poi1_cells_on_a_node_group() {
        let mut m = two_quads();
        let nodes = m.group_no("LEFT_EDGE").unwrap().members.clone();
        let made = m.add_point_cells(&nodes, Some("PTS"));
        assert_eq!(made, vec![CellId(3), CellId(4)]);
        assert_eq!(m.cells[3].ty, CellType::POI1);
        assert_eq!(m.cells[4].nodes, vec![NodeId(3)]);
        assert_eq!(m.cell_names[3..], ["M4".to_string(), "M5".to_string()]);
        assert_eq!(m.group_ma("PTS").unwrap().members, made);
    }

    #[test]
    fn quad_tria3_cuts_in_place_and_groups_follow() {
        let mut m = two_quads();
        let n = m.quad4_to_tria3(&[CellId(1)]).unwrap();
        assert_eq!(n, 1);
        assert_eq!(m.cells.len(), 4);
        assert_eq!(m.cells[1].ty, CellType::TRIA3);
        assert_eq!(m.cells[1].nodes, vec![NodeId(1), NodeId(2), NodeId(5)]);
        assert_eq!(m.cells[2].nodes, vec![NodeId(5), NodeId(4), NodeId(1)]);
        assert_eq!(m.cells[3].ty, CellType::SEG2);
        assert_eq!(
            m.group_ma("RIGHT").unwrap().members,
            vec![CellId(1), CellId(2)]
        );
        assert_eq!(m.group_ma("EDGE").unwrap().members, vec![CellId(3)]);
        assert_eq!(m.cell_names[3], "M3");
    }

    /// A QUAD9 becomes code_aster's six TRIA3 of its edge nodes.
    #[test]
    fn quad9_is_cut_into_six_triangles_of_its_edge_nodes() {
        let mut m = Mesh {
            dim: 2,
            node_names: (1..=9).map(|i| format!("N{i}")).collect(),
            cell_names: vec!["Q".into()],
            coords: vec![[0.0; 3]; 9],
            cells: vec![Cell {
                ty: CellType::QUAD9,
                nodes: (0..9).map(NodeId).collect(),
            }],
            ..Mesh::default()
        };
        assert_eq!(m.quad4_to_tria3(&[CellId(0)]).unwrap(), 1);
        assert_eq!(m.cells.len(), 6);
        let nodes = crate::ops::testmesh::one_based(&m);
        assert_eq!(
            nodes,
            vec![
                vec![1, 5, 8],
                vec![5, 2, 6],
                vec![6, 3, 7],
                vec![7, 4, 8],
                vec![5, 7, 8],
                vec![5, 6, 7]
            ]
        );
        assert!(m.cells.iter().all(|c| c.ty == CellType::TRIA3));
    }
}
