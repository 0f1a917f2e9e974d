//! `MODI_MAILLAGE(MODI_MAILLE=_F(OPTION='NOEUD_QUART'))` (code_aster's
//! `momaba` with `barso1` and the per-type `bartri`, `barqua`, `bartet`,
//! `barpen`, `barpyr`, `barhex`): Barsoum's quarter-point elements at a
//! crack front. In each quadratic cell around the front, the mid-edge node
//! of every edge that leaves a front corner moves to the quarter of that
//! edge next to the front (x = x_front + (x_other − x_front)/4), which puts
//! the 1/√r singularity of linear elastic fracture into the displacement
//! interpolation. Corners never move; the mid-edge nodes of the front's own
//! edges stay where they are.
//!
//! Two ways to give the front, as code_aster reads them:
//! - by cells (`GROUP_MA_FOND`, 3D meshes only): SEG3 front cells — a cell
//!   is modified when it has both corners of a front segment, and its
//!   edges leaving either of them (not the segment itself) move — or POI1
//!   cells (every cell with that corner);
//! - by nodes (`GROUP_NO_FOND`: one node in 2D, at least two in 3D): every
//!   quadratic cell with a front node as a corner gets the edges leaving
//!   that corner moved; front nodes that are no cell's corner (the front's
//!   mid-edge nodes) then get their original position back, and their
//!   number must be one less than the corners' (code_aster's
//!   ALGORITH16_73).
//!
//! Only quadratic volume and face cells are modified (TRIA6/7, QUAD8/9,
//! TETRA10, PENTA15/18, PYRAM13, HEXA20/27); the face-centre and
//! volume-centre nodes of TRIA7, QUAD9, PENTA18, HEXA27 do not move.

use crate::ops::degree::linear_of;
use crate::{CellId, CellType, Mesh, MeshError, NodeId};
use std::collections::{BTreeSet, HashMap};

/// Where the crack front is.
#[derive(Debug, Clone, Copy)]
pub enum CrackFront<'a> {
    /// `GROUP_MA_FOND`: SEG3 or POI1 cells.
    Cells(&'a [CellId]),
    /// `GROUP_NO_FOND`: nodes.
    Nodes(&'a [NodeId]),
}

/// The quadratic types `NOEUD_QUART` modifies (`momaba`'s list).
fn modified(ty: CellType) -> bool {
    use CellType::*;
    matches!(
        ty,
        TRIA6 | TRIA7 | QUAD8 | QUAD9 | TETRA10 | PENTA15 | PENTA18 | PYRAM13 | HEXA20 | HEXA27
    )
}

impl Mesh {
    /// Moves the mid-edge nodes next to a crack front to the quarter
    /// points; returns how many cells were modified. Errors are
    /// code_aster's: a 2D mesh with `GROUP_MA_FOND` (ALGORITH6_16), front
    /// cells other than SEG3/POI1 (ALGORITH6_17), a front node count not
    /// allowed (ALGORITH6_18, ALGORITH16_74), no cell modified
    /// (ALGORITH16_72), front mid-edge nodes not one less than its corners
    /// (ALGORITH16_73), two front corners of a cell that are not an edge
    /// (ALGORITH_36).
    pub fn move_to_quarter_points(&mut self, front: CrackFront) -> Result<usize, MeshError> {
        let err = |m: String| MeshError::Operation(format!("MODI_MAILLE/NOEUD_QUART: {m}"));
        let mut around: HashMap<NodeId, Vec<CellId>> = HashMap::new();
        for (i, c) in self.cells.iter().enumerate() {
            for &n in &c.nodes {
                around.entry(n).or_default().push(CellId(i as u32));
            }
        }
        let original = self.coords.clone();
        let mut touched = BTreeSet::new();
        match front {
            CrackFront::Cells(cells) => {
                if self.dim == 2 {
                    return Err(err(
                        "GROUP_MA_FOND is not allowed on a mesh of dimension 2: give the crack tip with GROUP_NO_FOND (code_aster's ALGORITH6_16)".into(),
                    ));
                }
                for &f in cells {
                    let c = self.cell(f);
                    let (n1, n2) = match c.ty {
                        CellType::SEG3 => (c.nodes[0], Some(c.nodes[1])),
                        CellType::POI1 => (c.nodes[0], None),
                        other => {
                            return Err(err(format!(
                                "the front cell {} is a {other:?}: SEG3 or POI1 cells are needed (code_aster's ALGORITH6_17)",
                                self.cell_name(f)
                            )))
                        }
                    };
                    let front_corners: Vec<NodeId> = n2.into_iter().chain([n1]).collect();
                    for &ci in around.get(&n1).map(Vec::as_slice).unwrap_or(&[]) {
                        let cell = self.cell(ci);
                        let Some(corners) = linear_of(cell.ty).map(CellType::node_count) else {
                            continue;
                        };
                        if !modified(cell.ty) {
                            continue;
                        }
                        let has = |n: NodeId| cell.nodes[..corners].contains(&n);
                        if front_corners.iter().all(|&n| has(n)) {
                            self.quarter_cell(ci, &front_corners)
                                .map_err(|m| err(m.to_string()))?;
                            touched.insert(ci);
                        }
                    }
                }
            }
            CrackFront::Nodes(nodes) => {
                if self.dim == 2 && nodes.len() > 1 {
                    return Err(err(format!(
                        "{} front nodes on a mesh of dimension 2: the crack tip is one node (code_aster's ALGORITH6_18)",
                        nodes.len()
                    )));
                }
                if self.dim == 3 && nodes.len() < 2 {
                    return Err(err(
                        "a crack front in 3D needs at least 2 nodes (code_aster's ALGORITH16_74)"
                            .into(),
                    ));
                }
                let (mut corners_n, mut middles) = (0usize, Vec::new());
                for &n in nodes {
                    let mut corner = false;
                    for &ci in around.get(&n).map(Vec::as_slice).unwrap_or(&[]) {
                        let cell = self.cell(ci);
                        if !modified(cell.ty) {
                            continue;
                        }
                        let Some(k) = linear_of(cell.ty).map(CellType::node_count) else {
                            continue;
                        };
                        if cell.nodes[..k].contains(&n) {
                            corner = true;
                            self.quarter_cell(ci, &[n])
                                .map_err(|m| err(m.to_string()))?;
                            touched.insert(ci);
                        }
                    }
                    if corner {
                        corners_n += 1;
                    } else {
                        middles.push(n);
                    }
                }
                for n in &middles {
                    self.coords[n.0 as usize] = original[n.0 as usize];
                }
                if !touched.is_empty() && nodes.len() > 1 && middles.len() + 1 != corners_n {
                    return Err(err(format!(
                        "the front has {corners_n} corner node(s) and {} mid-edge node(s): {} mid-edge node(s) missing from GROUP_NO_FOND (code_aster's ALGORITH16_73)",
                        middles.len(),
                        (corners_n as i64 - 1 - middles.len() as i64)
                    )));
                }
            }
        }
        if touched.is_empty() {
            return Err(err(
                "no quadratic cell has a corner on the crack front: nothing was modified (code_aster's ALGORITH16_72)".into(),
            ));
        }
        Ok(touched.len())
    }

    /// In one cell, the mid-edge nodes of the edges from a front corner to
    /// a corner off the front move to the quarter point next to the front.
    /// With two front corners they must be an edge of the cell.
    fn quarter_cell(&mut self, ci: CellId, front: &[NodeId]) -> Result<(), String> {
        let cell = self.cell(ci).clone();
        let Some(linear) = linear_of(cell.ty) else {
            return Ok(());
        };
        let corners = linear.node_count();
        let edges = cell.ty.corner_edges();
        let on_front = |k: usize| front.contains(&cell.nodes[k]);
        if front.len() == 2 && !edges.iter().any(|&[a, b]| on_front(a) && on_front(b)) {
            return Err(format!(
                "in cell {}, the front nodes are not the ends of one edge (code_aster's ALGORITH_36)",
                self.cell_name(ci)
            ));
        }
        for (e, &[a, b]) in edges.iter().enumerate() {
            let (from, to) = match (on_front(a), on_front(b)) {
                (true, false) => (a, b),
                (false, true) => (b, a),
                _ => continue,
            };
            let (Some(&nf), Some(&nt), Some(&nm)) = (
                cell.nodes.get(from),
                cell.nodes.get(to),
                cell.nodes.get(corners + e),
            ) else {
                continue;
            };
            let (xf, xt) = (self.coord(nf), self.coord(nt));
            let x = &mut self.coords[nm.0 as usize];
            for k in 0..3 {
                x[k] = xf[k] + 0.25 * (xt[k] - xf[k]);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cell, Group};

    /// Two QUAD8 side by side, [0,2]×[0,1], sharing the edge x = 1; the
    /// crack tip at the corner (1, 0).
    fn two_quad8() -> Mesh {
        let coords = vec![
            [0.0, 0.0, 0.0], // 0
            [1.0, 0.0, 0.0], // 1 tip
            [2.0, 0.0, 0.0], // 2
            [0.0, 1.0, 0.0], // 3
            [1.0, 1.0, 0.0], // 4
            [2.0, 1.0, 0.0], // 5
            [0.5, 0.0, 0.0], // 6 mid 0-1
            [1.0, 0.5, 0.0], // 7 mid 1-4
            [0.5, 1.0, 0.0], // 8 mid 4-3
            [0.0, 0.5, 0.0], // 9 mid 3-0
            [1.5, 0.0, 0.0], // 10 mid 1-2
            [2.0, 0.5, 0.0], // 11 mid 2-5
            [1.5, 1.0, 0.0], // 12 mid 5-4
        ];
        let n = |i: u32| NodeId(i);
        let cells = vec![
            Cell {
                ty: CellType::QUAD8,
                nodes: [0, 1, 4, 3, 6, 7, 8, 9].map(n).to_vec(),
            },
            Cell {
                ty: CellType::QUAD8,
                nodes: [1, 2, 5, 4, 10, 11, 12, 7].map(n).to_vec(),
            },
        ];
        Mesh {
            dim: 2,
            node_names: (1..=coords.len()).map(|i| format!("N{i}")).collect(),
            coords,
            cell_names: vec!["M1".into(), "M2".into()],
            cells,
            groups_ma: Vec::<Group<CellId>>::new(),
            groups_no: Vec::<Group<NodeId>>::new(),
        }
    }

    #[test]
    fn the_edges_leaving_the_tip_get_their_quarter_points() {
        let mut m = two_quad8();
        let before = m.coords.clone();
        assert_eq!(
            m.move_to_quarter_points(CrackFront::Nodes(&[NodeId(1)])),
            Ok(2)
        );
        assert_eq!(m.coords[6], [0.75, 0.0, 0.0]);
        assert_eq!(m.coords[7], [1.0, 0.25, 0.0]);
        assert_eq!(m.coords[10], [1.25, 0.0, 0.0]);
        for k in [0, 1, 2, 3, 4, 5, 8, 9, 11, 12] {
            assert_eq!(m.coords[k], before[k], "node {k}");
        }
    }

    #[test]
    fn a_front_on_a_plane_mesh_is_one_node_and_not_cells() {
        let mut m = two_quad8();
        let e = m
            .move_to_quarter_points(CrackFront::Nodes(&[NodeId(1), NodeId(4)]))
            .unwrap_err();
        assert!(e.to_string().contains("ALGORITH6_18"), "{e}");
        let e = m
            .move_to_quarter_points(CrackFront::Cells(&[]))
            .unwrap_err();
        assert!(e.to_string().contains("ALGORITH6_16"), "{e}");
    }

    #[test]
    fn a_tip_on_no_quadratic_corner_is_an_error() {
        let mut m = two_quad8();
        let e = m
            .move_to_quarter_points(CrackFront::Nodes(&[NodeId(6)]))
            .unwrap_err();
        assert!(e.to_string().contains("ALGORITH16_72"), "{e}");
    }

    /// The same two cells lifted into 3D as a HEXA20 pair would need a
    /// volume mesh; a SEG3 front on a 3D face mesh: QUAD8 cells in the
    /// plane z = 0 of a 3D mesh, the front the segment 1-4 (mid node 7).
    #[test]
    fn a_seg3_front_moves_the_edges_leaving_both_ends_but_not_its_own() {
        let mut m = two_quad8();
        m.dim = 3;
        m.cells.push(Cell {
            ty: CellType::SEG3,
            nodes: vec![NodeId(1), NodeId(4), NodeId(7)],
        });
        m.cell_names.push("F1".into());
        let before = m.coords.clone();
        assert_eq!(
            m.move_to_quarter_points(CrackFront::Cells(&[CellId(2)])),
            Ok(2)
        );
        assert_eq!(m.coords[6], [0.75, 0.0, 0.0]); // 1 → 0
        assert_eq!(m.coords[8], [0.75, 1.0, 0.0]); // 4 → 3
        assert_eq!(m.coords[10], [1.25, 0.0, 0.0]); // 1 → 2
        assert_eq!(m.coords[12], [1.25, 1.0, 0.0]); // 4 → 5
        assert_eq!(m.coords[7], before[7]); // the front's own mid node
        let e = m
            .move_to_quarter_points(CrackFront::Cells(&[CellId(0)]))
            .unwrap_err();
        assert!(e.to_string().contains("ALGORITH6_17"), "{e}");
    }

    /// GROUP_NO_FOND in 3D with the front's mid node listed: it is moved by
    /// the corners' passes and put back.
    #[test]
    fn front_mid_nodes_given_by_nodes_keep_their_place() {
        let mut m = two_quad8();
        m.dim = 3;
        let before = m.coords.clone();
        let front = [NodeId(1), NodeId(7), NodeId(4)];
        assert_eq!(m.move_to_quarter_points(CrackFront::Nodes(&front)), Ok(2));
        assert_eq!(m.coords[7], before[7]);
        assert_eq!(m.coords[6], [0.75, 0.0, 0.0]);
        assert_eq!(m.coords[12], [1.25, 1.0, 0.0]);
        let mut m = two_quad8();
        m.dim = 3;
        let e = m
            .move_to_quarter_points(CrackFront::Nodes(&[NodeId(1), NodeId(4)]))
            .unwrap_err();
        assert!(e.to_string().contains("ALGORITH16_73"), "{e}");
    }
}
