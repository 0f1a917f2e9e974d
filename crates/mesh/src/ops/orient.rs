//! `MODI_MAILLAGE(ORIE_PEAU=_F(GROUP_MA_PEAU=…))` and the legacy
//! `ORIE_PEAU_2D`/`ORIE_PEAU_3D`: orient skin cells so that their normal
//! points out of the body they bound.
//!
//! Conventions (code_aster's): the normal of a segment a→b in the plane is
//! (Δy, −Δx), i.e. an outward normal means the boundary is travelled
//! counter-clockwise around the body; the normal of a face follows the
//! right-hand rule on its node order. A skin cell's body ("support") is the
//! cell of one dimension more that holds all its corner nodes; the skin cell
//! is reversed when its normal points towards the support's centroid.

use crate::error::MeshError;
use crate::vec3::{dot, sub};
use crate::{Cell, CellId, CellType, Mesh, NodeId};
use std::collections::HashMap;

/// What `orient_skin` did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct OrientReport {
    /// Skin cells examined.
    pub cells: usize,
    /// Skin cells whose node order was reversed.
    pub reversed: usize,
    /// Skin cells bounding no cell of one dimension more, left as they are
    /// (code_aster's `orilma` counts them as "not treated": a rigid
    /// master line drawn alone, say).
    pub untreated: usize,
}

impl CellType {
    /// Number of corner (vertex) nodes, which come first in code_aster order.
    pub fn corner_count(self) -> usize {
        match self {
            CellType::POI1 => 1,
            CellType::SEG2 | CellType::SEG3 | CellType::SEG4 => 2,
            CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7 => 3,
            CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 => 4,
            CellType::TETRA4 | CellType::TETRA10 => 4,
            CellType::PYRAM5 | CellType::PYRAM13 => 5,
            CellType::PENTA6 | CellType::PENTA15 | CellType::PENTA18 => 6,
            CellType::HEXA8 | CellType::HEXA20 | CellType::HEXA27 => 8,
        }
    }

    /// The node permutation `ORIE_PEAU` applies to a skin cell it turns
    /// over (code_aster's `oriema`): the corners in reverse order
    /// (`1 2 3 4` → `4 3 2 1`), the edge middles following their edges,
    /// a face centre kept. Which node comes first matters beyond the
    /// orientation: a projection that falls outside a master triangle is
    /// brought back onto it in reference coordinates, so the edges'
    /// reference roles decide where it lands (ssnv104i's two symmetric
    /// contact points came out swapped with [`CellType::reversal`]).
    /// `None` for types that have no orientation to reverse here.
    pub fn skin_reversal(self) -> Option<&'static [usize]> {
        Some(match self {
            CellType::SEG2 => &[1, 0],
            CellType::SEG3 => &[1, 0, 2],
            CellType::SEG4 => &[1, 0, 3, 2],
            CellType::TRIA3 => &[2, 1, 0],
            CellType::TRIA6 => &[2, 1, 0, 4, 3, 5],
            CellType::TRIA7 => &[2, 1, 0, 4, 3, 5, 6],
            CellType::QUAD4 => &[3, 2, 1, 0],
            CellType::QUAD8 => &[3, 2, 1, 0, 6, 5, 4, 7],
            CellType::QUAD9 => &[3, 2, 1, 0, 6, 5, 4, 7, 8],
            _ => return None,
        })
    }

    /// The node permutation that reverses a segment or face, keeping the
    /// first node (code_aster's `iorim1`/`iorim2`, which `ORIE_NORM_COQUE`
    /// and `ORIE_LIGNE` use); `None` for types that have no orientation to
    /// reverse here.
    pub fn reversal(self) -> Option<&'static [usize]> {
        Some(match self {
            CellType::SEG2 => &[1, 0],
            CellType::SEG3 => &[1, 0, 2],
            CellType::SEG4 => &[1, 0, 3, 2],
            CellType::TRIA3 => &[0, 2, 1],
            CellType::TRIA6 => &[0, 2, 1, 5, 4, 3],
            CellType::TRIA7 => &[0, 2, 1, 5, 4, 3, 6],
            CellType::QUAD4 => &[0, 3, 2, 1],
            CellType::QUAD8 => &[0, 3, 2, 1, 7, 6, 5, 4],
            CellType::QUAD9 => &[0, 3, 2, 1, 7, 6, 5, 4, 8],
            _ => return None,
        })
    }
}

impl Mesh {
    fn centroid(&self, nodes: &[NodeId]) -> [f64; 3] {
        let mut c = [0.0; 3];
        for n in nodes {
            let p = self.coord(*n);
            for d in 0..3 {
                c[d] += p[d];
            }
        }
        let k = nodes.len().max(1) as f64;
        [c[0] / k, c[1] / k, c[2] / k]
    }

    /// The normal of a skin cell (not normalised): (Δy, −Δx) for a segment,
    /// Newell's vector for a face.
    pub fn skin_normal(&self, cell: &Cell) -> [f64; 3] {
        let corners = &cell.nodes[..cell.ty.corner_count().min(cell.nodes.len())];
        if cell.ty.dim() == 1 {
            let d = sub(self.coord(corners[1]), self.coord(corners[0]));
            return [d[1], -d[0], 0.0];
        }
        let mut n = [0.0; 3];
        for i in 0..corners.len() {
            let p = self.coord(corners[i]);
            let q = self.coord(corners[(i + 1) % corners.len()]);
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        n
    }

    /// Orient the skin cells of the named groups outwards (`ORIE_PEAU`).
    /// Errors: unknown group (with did-you-mean), a cell that is not a
    /// segment or face, a skin cell with two support cells (an inner
    /// boundary has no "outside"), a segment skin in a 3D mesh. A skin cell
    /// with no support cell is left as it is (counted in the report).
    pub fn orient_skin(&mut self, groups: &[&str]) -> Result<OrientReport, MeshError> {
        let skin = self.cells_of_groups(groups)?;
        // Support candidates: cells of one dimension more, indexed by node.
        let mut by_node: HashMap<NodeId, Vec<CellId>> = HashMap::new();
        let skin_dims: Vec<u8> = skin.iter().map(|c| self.cell(*c).ty.dim()).collect();
        let wanted: Vec<u8> = skin_dims.iter().map(|d| d + 1).collect();
        for (i, cell) in self.cells.iter().enumerate() {
            if wanted.contains(&cell.ty.dim()) {
                for &n in &cell.nodes[..cell.ty.corner_count()] {
                    by_node.entry(n).or_default().push(CellId(i as u32));
                }
            }
        }
        let mut report = OrientReport::default();
        for id in skin {
            let cell = self.cell(id).clone();
            let name = &self.cell_names[id.0 as usize];
            let Some(reversal) = cell.ty.skin_reversal() else {
                return Err(MeshError::Operation(format!(
                    "ORIE_PEAU: cell `{name}` is a {}; skin cells must be segments (2D) or faces (3D)",
                    cell.ty.name()
                )));
            };
            if cell.ty.dim() == 1 && self.dim == 3 && self.coords.iter().any(|c| c[2] != 0.0) {
                return Err(MeshError::Operation(format!(
                    "ORIE_PEAU: segment `{name}` in a 3D mesh: only segments of plane (x, y) meshes can be oriented"
                )));
            }
            let corners = &cell.nodes[..cell.ty.corner_count()];
            let supports: Vec<CellId> = by_node
                .get(&corners[0])
                .map(|cands| {
                    cands
                        .iter()
                        .copied()
                        .filter(|s| {
                            let sc = self.cell(*s);
                            sc.ty.dim() == cell.ty.dim() + 1
                                && corners.iter().all(|n| sc.nodes.contains(n))
                        })
                        .collect()
                })
                .unwrap_or_default();
            let support = match supports.as_slice() {
                [s] => *s,
                [] => {
                    report.untreated += 1;
                    continue;
                }
                [a, b, ..] => {
                    return Err(MeshError::Operation(format!(
                        "ORIE_PEAU: skin cell `{name}` lies between cells `{}` and `{}`: an inner boundary has no outward side",
                        self.cell_names[a.0 as usize], self.cell_names[b.0 as usize]
                    )))
                }
            };
            let inside = self.centroid(&self.cell(support).nodes.clone());
            let here = self.centroid(corners);
            let normal = self.skin_normal(&cell);
            report.cells += 1;
            if dot(normal, sub(here, inside)) < 0.0 {
                let nodes = reversal.iter().map(|&k| cell.nodes[k]).collect();
                self.cells[id.0 as usize].nodes = nodes;
                report.reversed += 1;
            }
        }
        Ok(report)
    }
}
