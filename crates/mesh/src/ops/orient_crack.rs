//! `MODI_MAILLAGE(ORIE_FISSURE=_F(GROUP_MA=…))`: orient the cells of a
//! joint (a layer of QUAD4/QUAD8 "crack" cells between two bodies) so that
//! their face 1-2 and face 3-4 (node 4 facing node 1) lie on the two bodies
//! and the cell is numbered counter-clockwise, as code_aster's `conori`
//! does (`op0154` → `conori`, `conini`, `contac`, `conqua`, `concom`,
//! `conper`, `conech`, `conors`, `conjac`), in 2D.
//!
//! For each crack cell (groups in order, cells in group order), every
//! "reference" cell — a cell of no crack group sharing at least two nodes
//! with the crack cells (`conini`), in cell order — that shares exactly two
//! corners with it (`concom`; QUAD4 crack against QUAD4/TRIA3, QUAD8
//! against QUAD8/QUAD9/TRIA6, `contac`) is a support:
//!
//! - shared corners (1, 2) or (3, 4): the face is in place; (1, 4) or
//!   (2, 3): the corners are rotated by one (1←2, 2←3, 3←4, 4←1, and the
//!   mid-edge nodes likewise) so that it is (`conqua`, `conper`);
//! - if the support's centroid lies on the left of its face, travelled
//!   from its first corner to its second (`conors`), the cell is mirrored
//!   (1↔4, 2↔3, 5↔7, `conech`).
//!
//! A crack cell needs one or two supports, on opposite faces; the second
//! one must need no change (code_aster's `ALGORITH2_30`).

use crate::error::MeshError;
use crate::{CellId, CellType, Mesh};

/// What [`Mesh::orient_crack`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CrackReport {
    /// How many reference cells were tested (`conini`'s count).
    pub references: usize,
    /// How many crack cells were renumbered.
    pub changed: usize,
}

impl Mesh {
    /// `ORIE_FISSURE` on the cells of `groups` (see the module docs).
    pub fn orient_crack(&mut self, groups: &[&str]) -> Result<CrackReport, MeshError> {
        let err = |m: String| MeshError::Operation(format!("ORIE_FISSURE: {m}"));
        let mut crack: Vec<CellId> = Vec::new();
        let mut in_crack = vec![false; self.cells.len()];
        let mut on_crack = vec![false; self.coords.len()];
        for g in groups {
            let group = self.group_ma_checked(g)?;
            for &c in &group.members {
                let cell = self.cell(c);
                match cell.ty {
                    CellType::QUAD4 | CellType::QUAD8 => {}
                    CellType::PENTA6 | CellType::PENTA15 | CellType::HEXA8 | CellType::HEXA20 => {
                        return Err(err(format!(
                            "cell {} is a {}: the 3D crack cells (code_aster's conpen/conhex) are not supported yet, only QUAD4 and QUAD8",
                            self.cell_name(c),
                            cell.ty.name()
                        )))
                    }
                    ty => {
                        return Err(err(format!(
                            "cell {} of group {g} is a {}; a crack cell is a QUAD4 or a QUAD8 (code_aster's ALGORITH2_27)",
                            self.cell_name(c),
                            ty.name()
                        )))
                    }
                }
                in_crack[c.0 as usize] = true;
                for n in &cell.nodes {
                    on_crack[n.0 as usize] = true;
                }
                crack.push(c);
            }
        }
        // conini: the reference cells, in cell order.
        let references: Vec<CellId> = (0..self.cells.len())
            .filter(|&i| !in_crack[i])
            .filter(|&i| {
                self.cells[i]
                    .nodes
                    .iter()
                    .filter(|n| on_crack[n.0 as usize])
                    .count()
                    >= 2
            })
            .map(|i| CellId(i as u32))
            .collect();
        let mut report = CrackReport {
            references: references.len(),
            changed: 0,
        };
        for &c in &crack {
            let before = self.cell(c).nodes.clone();
            let mut nodes = before.clone();
            let crack_ty = self.cell(c).ty;
            let mut supports = 0usize;
            let mut face: Option<bool> = None;
            for &r in &references {
                let rcell = self.cell(r);
                let fits = matches!(
                    (crack_ty, rcell.ty),
                    (CellType::QUAD4, CellType::QUAD4 | CellType::TRIA3)
                        | (
                            CellType::QUAD8,
                            CellType::QUAD8 | CellType::QUAD9 | CellType::TRIA6
                        )
                );
                if !fits {
                    continue;
                }
                let quadratic = nodes.len() == 8;
                let corners_r = if quadratic {
                    &rcell.nodes[..rcell.nodes.len() / 2]
                } else {
                    &rcell.nodes[..]
                };
                // concom: the crack's corners (1-based) found in the support.
                let common: Vec<usize> = (0..4)
                    .filter(|&i| corners_r.contains(&nodes[i]))
                    .map(|i| i + 1)
                    .collect();
                if common.len() > 2 {
                    return Err(err(format!(
                        "cell {} shares {} corners with cell {} (code_aster's ALGORITH12_59)",
                        self.cell_name(c),
                        common.len(),
                        self.cell_name(r)
                    )));
                }
                if common.len() < 2 {
                    continue;
                }
                let pair = (common[0], common[1]);
                let (rotated, mut lower) = match pair {
                    (1, 2) | (3, 4) => (false, pair == (1, 2)),
                    (1, 4) | (2, 3) => (true, pair == (2, 3)),
                    _ => {
                        return Err(err(format!(
                            "cell {} touches cell {} by a diagonal (corners {} and {})",
                            self.cell_name(c),
                            self.cell_name(r),
                            pair.0,
                            pair.1
                        )))
                    }
                };
                if rotated {
                    nodes[..4].rotate_left(1);
                    if quadratic {
                        nodes[4..8].rotate_left(1);
                    }
                }
                // conors: is the support on the left of its face?
                let (i1, i2) = if lower { (0, 1) } else { (2, 3) };
                let x1 = self.coord(nodes[i1]);
                let x2 = self.coord(nodes[i2]);
                let normal = [-(x2[1] - x1[1]), x2[0] - x1[0]];
                let nr = rcell.nodes.len() as f64;
                let mut g = [0.0; 2];
                for n in &rcell.nodes {
                    let x = self.coord(*n);
                    g[0] += x[0] / nr;
                    g[1] += x[1] / nr;
                }
                let scal = normal[0] * (g[0] - x1[0]) + normal[1] * (g[1] - x1[1]);
                if scal == 0.0 {
                    return Err(err(format!(
                        "cell {}: the centroid of its support {} lies on the line of its face (code_aster's MODELISA4_36)",
                        self.cell_name(c),
                        self.cell_name(r)
                    )));
                }
                let mirrored = scal > 0.0;
                if mirrored {
                    nodes.swap(0, 3);
                    nodes.swap(1, 2);
                    if quadratic {
                        nodes.swap(4, 6);
                    }
                    lower = !lower;
                }
                supports += 1;
                let problem = supports == 3
                    || (supports == 2 && face == Some(lower))
                    || (supports == 2 && (rotated || mirrored));
                if problem {
                    return Err(err(format!(
                        "cell {} cannot be oriented: its supports are not one cell on each face (code_aster's ALGORITH2_30; support {} is cell {})",
                        self.cell_name(c),
                        supports,
                        self.cell_name(r)
                    )));
                }
                face = Some(lower);
            }
            if supports == 0 {
                return Err(err(format!(
                    "cell {} rests on no cell of the mesh by one of its faces (code_aster's ALGORITH2_30)",
                    self.cell_name(c)
                )));
            }
            // conjac: every corner must see its neighbours counter-clockwise.
            for (i0, i1, i2) in [(0, 3, 1), (1, 0, 2), (2, 1, 3), (3, 2, 0)] {
                let p0 = self.coord(nodes[i0]);
                let a = self.coord(nodes[i1]);
                let b = self.coord(nodes[i2]);
                let v1 = [a[0] - p0[0], a[1] - p0[1]];
                let v2 = [b[0] - p0[0], b[1] - p0[1]];
                if -(v1[0] * v2[1] - v2[0] * v1[1]) < 0.0 {
                    return Err(err(format!(
                        "cell {}: a negative Jacobian at its corner {} after orientation (code_aster's MODELISA4_35)",
                        self.cell_name(c),
                        i0 + 1
                    )));
                }
            }
            if nodes != before {
                report.changed += 1;
                self.cells[c.0 as usize].nodes = nodes;
            }
        }
        Ok(report)
    }
}

/// The node list of a crack cell, for tests.
#[cfg(test)]
fn names(mesh: &Mesh, c: CellId) -> Vec<String> {
    mesh.cell(c)
        .nodes
        .iter()
        .map(|n| mesh.node_names[n.0 as usize].clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cell, Group, NodeId};

    /// Two unit squares (bottom B: N1 N2 N5 N4, top T: N7 N8 N11 N10)
    /// with a thin joint J between them (N4 N5 above, N7 N8 below… the
    /// joint's nodes given in `joint`).
    fn sandwich(joint: [u32; 4]) -> Mesh {
        let coords = vec![
            [0.0, 0.0, 0.0], // N1
            [1.0, 0.0, 0.0], // N2
            [2.0, 0.0, 0.0], // N3 (unused)
            [0.0, 1.0, 0.0], // N4
            [1.0, 1.0, 0.0], // N5
            [2.0, 1.0, 0.0], // N6 (unused)
            [0.0, 1.1, 0.0], // N7
            [1.0, 1.1, 0.0], // N8
            [2.0, 1.1, 0.0], // N9 (unused)
            [0.0, 2.1, 0.0], // N10
            [1.0, 2.1, 0.0], // N11
        ];
        let n = |v: &[u32]| v.iter().map(|&i| NodeId(i - 1)).collect::<Vec<_>>();
        Mesh {
            dim: 2,
            node_names: (1..=11).map(|i| format!("N{i}")).collect(),
            coords,
            cells: vec![
                Cell {
                    ty: CellType::QUAD4,
                    nodes: n(&[1, 2, 5, 4]),
                },
                Cell {
                    ty: CellType::QUAD4,
                    nodes: n(&joint),
                },
                Cell {
                    ty: CellType::QUAD4,
                    nodes: n(&[7, 8, 11, 10]),
                },
                Cell {
                    ty: CellType::SEG2,
                    nodes: n(&[4, 5]),
                },
            ],
            cell_names: vec!["B".into(), "J".into(), "T".into(), "S".into()],
            groups_ma: vec![Group {
                name: "JOINT".into(),
                members: vec![CellId(1)],
            }],
            groups_no: vec![],
        }
    }

    #[test]
    fn every_numbering_of_the_joint_ends_counter_clockwise_with_its_faces_on_the_bodies() {
        // The eight numberings of the joint's corners (4 rotations × 2
        // directions): code_aster's conori leaves one of the two
        // counter-clockwise numberings whose 1-2 face is a body's face.
        let ccw = [4u32, 5, 8, 7];
        let mut numberings = Vec::new();
        for k in 0..4 {
            let mut v = ccw;
            v.rotate_left(k);
            numberings.push(v);
            let mut w = v;
            w.reverse();
            numberings.push(w);
        }
        for joint in numberings {
            let mut mesh = sandwich(joint);
            let report = mesh.orient_crack(&["JOINT"]).unwrap();
            assert_eq!(report.references, 3, "B, T and the SEG2 S");
            let got = names(&mesh, CellId(1));
            let ok = got == ["N4", "N5", "N8", "N7"] || got == ["N8", "N7", "N4", "N5"];
            assert!(ok, "{joint:?} gave {got:?}");
        }
    }

    #[test]
    fn the_counter_clockwise_numbering_from_the_lower_face_is_kept() {
        let mut mesh = sandwich([4, 5, 8, 7]);
        let report = mesh.orient_crack(&["JOINT"]).unwrap();
        assert_eq!(report.changed, 0);
        // Clockwise from the lower face: mirrored onto the upper face, as
        // code_aster does it.
        let mut mesh = sandwich([5, 4, 7, 8]);
        let report = mesh.orient_crack(&["JOINT"]).unwrap();
        assert_eq!(report.changed, 1);
        assert_eq!(names(&mesh, CellId(1)), ["N8", "N7", "N4", "N5"]);
    }

    #[test]
    fn a_crack_cell_that_is_not_a_quadrangle_is_refused() {
        let mut mesh = sandwich([4, 5, 8, 7]);
        mesh.groups_ma[0].members = vec![CellId(3)];
        let e = mesh.orient_crack(&["JOINT"]).unwrap_err().to_string();
        assert!(e.contains("SEG2"), "{e}");
    }

    #[test]
    fn a_joint_resting_on_nothing_is_refused() {
        let mut mesh = sandwich([4, 5, 8, 7]);
        mesh.cells[0].nodes = vec![NodeId(0), NodeId(1), NodeId(2), NodeId(0)];
        mesh.cells[2].nodes = vec![NodeId(9), NodeId(10), NodeId(8), NodeId(9)];
        mesh.cells[3].nodes = vec![NodeId(0), NodeId(1)];
        let e = mesh.orient_crack(&["JOINT"]).unwrap_err().to_string();
        assert!(e.contains("rests on no cell"), "{e}");
    }
}
