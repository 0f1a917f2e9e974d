//! `CREA_MAILLAGE` degree changes: `LINE_QUAD` (linear → quadratic cells),
//! `QUAD_LINE` (quadratic → linear), `HEXA20_27` / `PENTA15_18` and
//! `MODI_MAILLE` `QUAD8_9` / `TRIA6_7` (adding face and volume centres).
//!
//! Node ordering is code_aster's: the mid-edge nodes follow the corners in
//! the edge order of the quadratic type (TRIA6: 12 23 31; QUAD8: 12 23 34
//! 41; TETRA10: 12 23 31 14 24 34; PENTA15: 12 23 31 14 25 36 45 56 64;
//! HEXA20: 12 23 34 41 15 26 37 48 56 67 78 85; PYRAM13: 12 23 34 41 15
//! 25 35 45), then face centres (QUAD9/TRIA7: one; HEXA27: faces 1234
//! 1265 2376 3487 4158 5678 then the volume centre; PENTA18: faces 1254
//! 2365 3146). An edge or face shared by several cells gets one node.
//! Mid-edge nodes are at the middle of the straight edge; centre nodes are
//! at the isoparametric centre of the quadratic cell (for straight edges,
//! the centroid), so a curved quadratic cell keeps its shape.

use crate::ops::rebuild::Namer;
use crate::{Cell, CellId, CellType, Mesh, NodeId};
use std::collections::HashMap;

/// Local corner pairs of each linear type's edges, in the order its
/// quadratic counterpart numbers the mid-edge nodes
/// ([`CellType::corner_edges`]).
pub(crate) fn edges(ty: CellType) -> Option<(CellType, &'static [[usize; 2]])> {
    let quadratic = match ty {
        CellType::SEG2 => CellType::SEG3,
        CellType::TRIA3 => CellType::TRIA6,
        CellType::QUAD4 => CellType::QUAD8,
        CellType::TETRA4 => CellType::TETRA10,
        CellType::PENTA6 => CellType::PENTA15,
        CellType::HEXA8 => CellType::HEXA20,
        CellType::PYRAM5 => CellType::PYRAM13,
        _ => return None,
    };
    Some((quadratic, ty.corner_edges()))
}

/// The linear type of a quadratic one (`QUAD_LINE`).
pub(crate) fn linear_of(ty: CellType) -> Option<CellType> {
    Some(match ty {
        CellType::SEG3 | CellType::SEG4 => CellType::SEG2,
        CellType::TRIA6 | CellType::TRIA7 => CellType::TRIA3,
        CellType::QUAD8 | CellType::QUAD9 => CellType::QUAD4,
        CellType::TETRA10 => CellType::TETRA4,
        CellType::PENTA15 | CellType::PENTA18 => CellType::PENTA6,
        CellType::HEXA20 | CellType::HEXA27 => CellType::HEXA8,
        CellType::PYRAM13 => CellType::PYRAM5,
        _ => return None,
    })
}

/// Which centre nodes an operation adds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CentreNodes {
    /// `HEXA20_27`: HEXA20 → HEXA27 (and QUAD8 → QUAD9 faces).
    Hexa20To27,
    /// `PENTA15_18`: PENTA15 → PENTA18 (and QUAD8 → QUAD9 faces).
    Penta15To18,
    /// `MODI_MAILLE/OPTION='QUAD8_9'`.
    Quad8To9,
    /// `MODI_MAILLE/OPTION='TRIA6_7'`.
    Tria6To7,
}

impl CentreNodes {
    fn converts(self, ty: CellType) -> bool {
        matches!(
            (self, ty),
            (CentreNodes::Hexa20To27, CellType::HEXA20 | CellType::QUAD8)
                | (
                    CentreNodes::Penta15To18,
                    CellType::PENTA15 | CellType::QUAD8
                )
                | (CentreNodes::Quad8To9, CellType::QUAD8)
                | (CentreNodes::Tria6To7, CellType::TRIA6)
        )
    }
}

/// How many cells a degree change converted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DegreeReport {
    pub cells: usize,
    pub nodes_added: usize,
    pub nodes_removed: usize,
}

fn midpoint(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        (a[0] + b[0]) / 2.0,
        (a[1] + b[1]) / 2.0,
        (a[2] + b[2]) / 2.0,
    ]
}

/// Σ wᵢ xᵢ over some nodes.
fn combine(mesh: &Mesh, terms: &[(NodeId, f64)]) -> [f64; 3] {
    let mut x = [0.0; 3];
    for (n, w) in terms {
        let p = mesh.coord(*n);
        for k in 0..3 {
            x[k] += w * p[k];
        }
    }
    x
}

/// Sorted key of some nodes (shared edges and faces).
fn key(nodes: &[NodeId]) -> Vec<NodeId> {
    let mut k = nodes.to_vec();
    k.sort();
    k
}

/// Isoparametric centre of a quadratic face given its corners and mid-edge
/// nodes: QUAD8 −¼Σcorners + ½Σmids; TRIA6 −⅑Σcorners + 4⁄9Σmids.
fn face_centre(mesh: &Mesh, corners: &[NodeId], mids: &[NodeId]) -> [f64; 3] {
    let (wc, wm) = if corners.len() == 4 {
        (-0.25, 0.5)
    } else {
        (-1.0 / 9.0, 4.0 / 9.0)
    };
    let terms: Vec<(NodeId, f64)> = corners
        .iter()
        .map(|&n| (n, wc))
        .chain(mids.iter().map(|&n| (n, wm)))
        .collect();
    combine(mesh, &terms)
}

/// Local (corners, mids) of each quadrilateral face of HEXA20 / PENTA15, in
/// the order HEXA27 / PENTA18 number their face centres.
fn quad_faces(ty: CellType) -> &'static [([usize; 4], [usize; 4])] {
    match ty {
        CellType::HEXA20 => &[
            ([0, 1, 2, 3], [8, 9, 10, 11]),
            ([0, 1, 5, 4], [8, 13, 16, 12]),
            ([1, 2, 6, 5], [9, 14, 17, 13]),
            ([2, 3, 7, 6], [10, 15, 18, 14]),
            ([3, 0, 4, 7], [11, 12, 19, 15]),
            ([4, 5, 6, 7], [16, 17, 18, 19]),
        ],
        CellType::PENTA15 => &[
            ([0, 1, 4, 3], [6, 10, 12, 9]),
            ([1, 2, 5, 4], [7, 11, 13, 10]),
            ([2, 0, 3, 5], [8, 9, 14, 11]),
        ],
        CellType::QUAD8 => &[([0, 1, 2, 3], [4, 5, 6, 7])],
        _ => &[],
    }
}

impl Mesh {
    /// The shortest and longest edges of the cells, each edge measured
    /// straight between its two corner nodes (code_aster's
    /// `getMinMaxEdgeSizes`, and `AR_MIN`/`AR_MAX` of `cargeo`: the
    /// shortest edge *of non-zero length*, so the coincident corners of a
    /// degenerate cell are skipped); `None` when the cells have no edge of
    /// positive length (points only).
    pub fn edge_length_range(&self, cells: &[CellId]) -> Option<(f64, f64)> {
        let mut range: Option<(f64, f64)> = None;
        for &c in cells {
            let cell = self.cell(c);
            let linear = linear_of(cell.ty).unwrap_or(cell.ty);
            let Some((_, pairs)) = edges(linear) else {
                continue;
            };
            for [a, b] in pairs {
                let (p, q) = (self.coord(cell.nodes[*a]), self.coord(cell.nodes[*b]));
                let l =
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                if l == 0.0 {
                    continue;
                }
                range = Some(match range {
                    None => (l, l),
                    Some((lo, hi)) => (lo.min(l), hi.max(l)),
                });
            }
        }
        range
    }

    /// `LINE_QUAD`: the selected linear cells become quadratic (SEG2→SEG3,
    /// TRIA3→TRIA6, QUAD4→QUAD8, TETRA4→TETRA10, PENTA6→PENTA15,
    /// HEXA8→HEXA20, PYRAM5→PYRAM13); other types are kept as they are.
    pub fn line_to_quad(&mut self, selected: &[CellId]) -> DegreeReport {
        let mut namer = Namer::new(&self.node_names, "N");
        let mut mids: HashMap<[NodeId; 2], NodeId> = HashMap::new();
        let mut report = DegreeReport::default();
        let before = self.node_count();
        for &c in selected {
            let cell = self.cell(c).clone();
            let Some((quad, list)) = edges(cell.ty) else {
                continue;
            };
            let mut nodes = cell.nodes.clone();
            for [a, b] in list {
                let (na, nb) = (cell.nodes[*a], cell.nodes[*b]);
                let k = if na < nb { [na, nb] } else { [nb, na] };
                let m = match mids.get(&k) {
                    Some(&m) => m,
                    None => {
                        let x = midpoint(self.coord(na), self.coord(nb));
                        let m = self.push_node(&mut namer, x);
                        mids.insert(k, m);
                        m
                    }
                };
                nodes.push(m);
            }
            self.cells[c.0 as usize] = Cell { ty: quad, nodes };
            report.cells += 1;
        }
        report.nodes_added = self.node_count() - before;
        report
    }

    /// `QUAD_LINE`: the selected quadratic cells become linear; nodes no
    /// cell uses any more are removed (from node groups too).
    pub fn quad_to_line(&mut self, selected: &[CellId]) -> DegreeReport {
        self.linearise(selected, vec![false; self.node_count()])
    }

    /// The selected quadratic cells made linear; the nodes no cell uses any
    /// more are removed, but those `keep` says.
    pub(crate) fn linearise(&mut self, selected: &[CellId], keep: Vec<bool>) -> DegreeReport {
        let mut report = DegreeReport::default();
        for &c in selected {
            let cell = &mut self.cells[c.0 as usize];
            if let Some(lin) = linear_of(cell.ty) {
                cell.nodes.truncate(lin.node_count());
                cell.ty = lin;
                report.cells += 1;
            }
        }
        let used: Vec<bool> = self
            .used_nodes()
            .into_iter()
            .zip(keep)
            .map(|(u, k)| u || k)
            .collect();
        report.nodes_removed = used.iter().filter(|u| !**u).count();
        self.retain_nodes(&used);
        report
    }

    /// Adds face (and volume) centre nodes to the selected cells of the
    /// types `op` converts.
    ///
    /// `QUAD8_9`/`TRIA6_7` (`MODI_MAILLE`, code_aster's `cmmoma`): one new
    /// node per selected cell, in the order of the selection. `HEXA20_27` and
    /// `PENTA15_18` (`cm2027`/`cm1518`, `crea_maillage_module`): a face
    /// shared by cells gets one centre, and the new nodes are numbered in
    /// the order code_aster creates them — every cell of the mesh visited
    /// by type (QUAD8 and TRIA6 cells, then HEXA20, PENTA15… volumes),
    /// each volume's faces in the order HEXA27/PENTA18 number them and then
    /// its centre — keeping those the selected cells use (tplv304a's
    /// `NOEUD='N137'`).
    pub fn add_centre_nodes(&mut self, selected: &[CellId], op: CentreNodes) -> DegreeReport {
        let mut namer = Namer::new(&self.node_names, "N");
        let mut report = DegreeReport::default();
        let before = self.node_count();
        let converted: Vec<CellId> = selected
            .iter()
            .copied()
            .filter(|c| op.converts(self.cell(*c).ty))
            .collect();
        let faces_of = |cell: &Cell| -> Vec<(Vec<NodeId>, Vec<NodeId>)> {
            match cell.ty {
                CellType::TRIA6 => vec![(cell.nodes[..3].to_vec(), cell.nodes[3..6].to_vec())],
                ty => quad_faces(ty)
                    .iter()
                    .map(|(c4, m4)| {
                        (
                            c4.iter().map(|&i| cell.nodes[i]).collect(),
                            m4.iter().map(|&i| cell.nodes[i]).collect(),
                        )
                    })
                    .collect(),
            }
        };
        // The centres the converted cells need.
        let mut needed: HashMap<Vec<NodeId>, Option<NodeId>> = HashMap::new();
        let mut volume_centre: HashMap<CellId, NodeId> = HashMap::new();
        for &c in &converted {
            for (corners, _) in faces_of(self.cell(c)) {
                needed.insert(key(&corners), None);
            }
        }
        let merged = matches!(op, CentreNodes::Hexa20To27 | CentreNodes::Penta15To18);
        if merged {
            let selected_set: std::collections::HashSet<CellId> =
                converted.iter().copied().collect();
            // code_aster's reading order of the cell types (init_mesh).
            let rank = |ty: CellType| match ty {
                CellType::TRIA6 | CellType::QUAD8 => 0,
                CellType::PENTA18
                | CellType::HEXA20
                | CellType::PENTA15
                | CellType::PYRAM13
                | CellType::TETRA10 => 1,
                _ => 2,
            };
            let mut order: Vec<CellId> = (0..self.cells.len() as u32)
                .map(CellId)
                .filter(|c| rank(self.cell(*c).ty) < 2)
                .collect();
            order.sort_by_key(|c| rank(self.cell(*c).ty));
            for c in order {
                let cell = self.cell(c).clone();
                for (corners, mids) in faces_of(&cell) {
                    if let Some(slot @ None) = needed.get_mut(&key(&corners)) {
                        let x = face_centre(self, &corners, &mids);
                        *slot = Some(self.push_node(&mut namer, x));
                    }
                }
                if cell.ty == CellType::HEXA20 && selected_set.contains(&c) {
                    // Serendipity HEXA20 at ξ=η=ζ=0: corners −¼, mid-edges ¼.
                    let terms: Vec<(NodeId, f64)> = (0..20)
                        .map(|i| (cell.nodes[i], if i < 8 { -0.25 } else { 0.25 }))
                        .collect();
                    let x = combine(self, &terms);
                    volume_centre.insert(c, self.push_node(&mut namer, x));
                }
            }
        }
        for &c in &converted {
            let cell = self.cell(c).clone();
            let mut nodes = cell.nodes.clone();
            for (corners, mids) in faces_of(&cell) {
                let n = match needed.get(&key(&corners)).copied().flatten() {
                    Some(n) if merged => n,
                    _ => {
                        let x = face_centre(self, &corners, &mids);
                        self.push_node(&mut namer, x)
                    }
                };
                nodes.push(n);
            }
            let ty = match cell.ty {
                CellType::HEXA20 => {
                    if let Some(&n) = volume_centre.get(&c) {
                        nodes.push(n);
                    }
                    CellType::HEXA27
                }
                CellType::PENTA15 => CellType::PENTA18,
                CellType::QUAD8 => CellType::QUAD9,
                _ => CellType::TRIA7,
            };
            self.cells[c.0 as usize] = Cell { ty, nodes };
            report.cells += 1;
        }
        report.nodes_added = self.node_count() - before;
        report
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::testmesh::two_quads;

    fn all(m: &Mesh) -> Vec<CellId> {
        (0..m.cells.len() as u32).map(CellId).collect()
    }

    #[test]
    fn line_quad_shares_mid_edge_nodes() {
        let mut m = two_quads();
        let sel = all(&m);
        let r = m.line_to_quad(&sel);
        // 7 distinct edges among the two quads (one shared) and the SEG2
        // (which is the left edge of M1).
        assert_eq!(r.nodes_added, 7);
        assert_eq!(r.cells, 3);
        assert_eq!(m.cells[0].ty, CellType::QUAD8);
        assert_eq!(m.cells[2].ty, CellType::SEG3);
        // M1's 4th edge (N4–N1) is the SEG2's edge: one node.
        assert_eq!(m.cells[0].nodes[7], m.cells[2].nodes[2]);
        // M2's 4th edge (N5–N2) is M1's 2nd edge (N2–N5).
        assert_eq!(m.cells[1].nodes[7], m.cells[0].nodes[5]);
        assert_eq!(m.coord(m.cells[0].nodes[4]), [0.5, 0.0, 0.0]);
        assert_eq!(m.node_names[6], "N7");
    }

    #[test]
    fn quad_line_is_the_inverse() {
        let mut m = two_quads();
        let orig = m.clone();
        let sel = all(&m);
        m.line_to_quad(&sel);
        let r = m.quad_to_line(&sel);
        assert_eq!(r.nodes_removed, 7);
        assert_eq!(m, orig);
    }

    #[test]
    fn quad8_to_9_centre_is_isoparametric() {
        let mut m = two_quads();
        let sel = all(&m);
        m.line_to_quad(&sel);
        // Bow the bottom mid-node of M1 down by 0.2: the centre is
        // −¼·Σ corner y + ½·Σ mid y = −¼·2 + ½·(−0.2 + 0.5 + 1 + 0.5) = 0.4.
        let bottom = m.cells[0].nodes[4];
        m.coords[bottom.0 as usize][1] = -0.2;
        let r = m.add_centre_nodes(&[CellId(0)], CentreNodes::Quad8To9);
        assert_eq!(r.nodes_added, 1);
        assert_eq!(m.cells[0].ty, CellType::QUAD9);
        let c = m.coord(m.cells[0].nodes[8]);
        assert!(
            (c[0] - 0.5).abs() < 1e-15 && (c[1] - 0.4).abs() < 1e-15,
            "{c:?}"
        );
    }

    #[test]
    fn hexa20_27_on_a_unit_cube() {
        let mut m = Mesh {
            dim: 3,
            ..Mesh::default()
        };
        for (i, p) in [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
        ]
        .into_iter()
        .enumerate()
        {
            m.coords.push(p);
            m.node_names.push(format!("N{}", i + 1));
        }
        m.cells.push(Cell {
            ty: CellType::HEXA8,
            nodes: (0..8).map(NodeId).collect(),
        });
        m.cell_names.push("M1".into());
        m.line_to_quad(&[CellId(0)]);
        assert_eq!(m.node_count(), 20);
        // HEXA20 node 13 is the middle of edge 1–5.
        assert_eq!(m.coord(m.cells[0].nodes[12]), [0., 0., 0.5]);
        let r = m.add_centre_nodes(&[CellId(0)], CentreNodes::Hexa20To27);
        assert_eq!(r.nodes_added, 7);
        let c = &m.cells[0];
        assert_eq!(c.ty, CellType::HEXA27);
        assert_eq!(m.coord(c.nodes[20]), [0.5, 0.5, 0.0]);
        assert_eq!(m.coord(c.nodes[21]), [0.5, 0.0, 0.5]);
        assert_eq!(m.coord(c.nodes[25]), [0.5, 0.5, 1.0]);
        assert_eq!(m.coord(c.nodes[26]), [0.5, 0.5, 0.5]);
    }

    #[test]
    fn hexa20_27_numbers_its_new_nodes_in_code_asters_order() {
        // Two HEXA20 stacked along z and a QUAD8 skin cell on the top face:
        // code_aster (crea_maillage_module) visits the QUAD8 cells first,
        // then each volume's faces in HEXA27 order and its centre.
        let mut m = Mesh {
            dim: 3,
            ..Mesh::default()
        };
        for z in [0., 1., 2.] {
            for (x, y) in [(0., 0.), (1., 0.), (1., 1.), (0., 1.)] {
                m.coords.push([x, y, z]);
                m.node_names.push(format!("N{}", m.coords.len()));
            }
        }
        for base in [0u32, 4] {
            m.cells.push(Cell {
                ty: CellType::HEXA8,
                nodes: (base..base + 8).map(NodeId).collect(),
            });
            m.cell_names.push(format!("M{}", m.cells.len()));
        }
        m.line_to_quad(&[CellId(0), CellId(1)]);
        let top = m.cells[1].nodes.clone();
        m.cells.push(Cell {
            ty: CellType::QUAD8,
            nodes: [4, 5, 6, 7, 16, 17, 18, 19]
                .iter()
                .map(|&i| top[i])
                .collect(),
        });
        m.cell_names.push("M3".into());
        let before = m.node_count();
        let r = m.add_centre_nodes(&all(&m), CentreNodes::Hexa20To27);
        assert_eq!((r.cells, r.nodes_added), (3, 13));
        let at = |k: usize| m.coord(NodeId((before + k) as u32));
        // The QUAD8 skin cell's centre first, then the lower hexahedron's
        // six faces and centre, then the upper one's four new sides and
        // centre (its bottom and top faces already have theirs).
        assert_eq!(at(0), [0.5, 0.5, 2.0]);
        assert_eq!(at(1), [0.5, 0.5, 0.0]);
        assert_eq!(at(6), [0.5, 0.5, 1.0]);
        assert_eq!(at(7), [0.5, 0.5, 0.5]);
        assert_eq!(at(12), [0.5, 0.5, 1.5]);
        assert_eq!(m.node_names[before], format!("N{}", before + 1));
        // Shared faces share their centre.
        assert_eq!(m.cells[2].nodes[8], m.cells[1].nodes[25]);
        assert_eq!(m.cells[0].nodes[25], m.cells[1].nodes[20]);
    }

    #[test]
    fn edge_lengths_skip_coincident_corners() {
        let mut m = two_quads();
        assert_eq!(m.edge_length_range(&all(&m)), Some((1.0, 1.0)));
        // Stretch N3 and N6 to x = 4: M2's horizontal edges become 3 long.
        m.coords[2][0] = 4.0;
        m.coords[5][0] = 4.0;
        assert_eq!(m.edge_length_range(&all(&m)), Some((1.0, 3.0)));
        // M1 alone keeps unit edges.
        assert_eq!(m.edge_length_range(&[CellId(0)]), Some((1.0, 1.0)));
        // Collapse M2's right edge (N3 onto N6): a zero-length edge is not
        // the shortest one (cargeo's AR_MIN is the shortest non-zero edge).
        m.coords[2] = m.coords[5];
        let (lo, _) = m.edge_length_range(&all(&m)).unwrap();
        assert_eq!(lo, 1.0);
    }
}
