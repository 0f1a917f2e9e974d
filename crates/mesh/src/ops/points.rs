//! `CREA_MAILLAGE(CREA_POI1=…)`: point cells on nodes, and
//! `MODI_MAILLE(OPTION='QUAD_TRIA3')`: quadrangles cut into triangles.

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
    /// (1 2 3) and (3 4 1), in place (code_aster's cutting table); the
    /// other cells are kept. The pieces get fresh names and belong to the
    /// groups of their quadrangle. Returns how many quadrangles were cut;
    /// a selected QUAD8/QUAD9 is an error (code_aster cuts it into six
    /// triangles, which is not done here).
    pub fn quad4_to_tria3(&mut self, selected: &[CellId]) -> Result<usize, crate::MeshError> {
        let mut cut = vec![false; self.cells.len()];
        for &c in selected {
            match self.cell(c).ty {
                CellType::QUAD4 => cut[c.0 as usize] = true,
                CellType::QUAD8 | CellType::QUAD9 => {
                    return Err(crate::MeshError::Operation(format!(
                        "MODI_MAILLE/QUAD_TRIA3: cell {} is a {}; only QUAD4 cells are cut into triangles here",
                        self.cell_names[c.0 as usize],
                        self.cell(c).ty.name()
                    )))
                }
                _ => {}
            }
        }
        let count = cut.iter().filter(|c| **c).count();
        self.rewrite_cells(|id, cell| {
            if cut[id.0 as usize] {
                let n = &cell.nodes;
                vec![
                    Cell {
                        ty: CellType::TRIA3,
                        nodes: vec![n[0], n[1], n[2]],
                    },
                    Cell {
                        ty: CellType::TRIA3,
                        nodes: vec![n[2], n[3], n[0]],
                    },
                ]
            } else {
                vec![cell.clone()]
            }
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
}
