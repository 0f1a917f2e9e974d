//! Node groups defined by geometry (`DEFI_GROUP/CREA_GROUP_NO/OPTION`):
//! `ENV_SPHERE`, `PLAN`, `SEGM_DROI_ORDO`, `NOEUD_ORDO`, and the node kind
//! filter `CRIT_NOEUD` (`SOMMET`, `MILIEU`).

use crate::error::MeshError;
use crate::vec3::{dot, norm, sub};
use crate::{CellId, CellType, Mesh, NodeId};
use std::collections::HashMap;

/// Which nodes of cells `CRIT_NOEUD` keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeKind {
    /// `TOUS`.
    All,
    /// `SOMMET`: the corner (vertex) nodes.
    Corners,
    /// `MILIEU`: the mid-edge nodes of quadratic cells.
    MidEdges,
}

/// Number of mid-edge nodes after the corners (the rest are face or volume
/// centres).
fn mid_edge_count(ty: CellType) -> usize {
    match ty {
        CellType::SEG3 => 1,
        CellType::SEG4 => 2,
        CellType::TRIA6 | CellType::TRIA7 => 3,
        CellType::QUAD8 | CellType::QUAD9 => 4,
        CellType::TETRA10 => 6,
        CellType::PENTA15 | CellType::PENTA18 => 9,
        CellType::HEXA20 | CellType::HEXA27 => 12,
        CellType::PYRAM13 => 8,
        _ => 0,
    }
}

impl Mesh {
    /// The nodes of some cells of one kind, each once, in order of first
    /// appearance.
    pub fn nodes_of_cells_kind(&self, cells: &[CellId], kind: NodeKind) -> Vec<NodeId> {
        let mut seen = vec![false; self.node_count()];
        let mut out = Vec::new();
        for &c in cells {
            let cell = self.cell(c);
            let corners = cell.ty.corner_count();
            let range = match kind {
                NodeKind::All => 0..cell.nodes.len(),
                NodeKind::Corners => 0..corners.min(cell.nodes.len()),
                NodeKind::MidEdges => {
                    corners..(corners + mid_edge_count(cell.ty)).min(cell.nodes.len())
                }
            };
            for &n in &cell.nodes[range] {
                if !std::mem::replace(&mut seen[n.0 as usize], true) {
                    out.push(n);
                }
            }
        }
        out
    }

    /// `ENV_SPHERE`: nodes whose distance to `centre` is `radius` within
    /// `precision`, in node order.
    pub fn nodes_on_sphere(&self, centre: [f64; 3], radius: f64, precision: f64) -> Vec<NodeId> {
        self.nodes_where(|x| (norm(sub(x, centre)) - radius).abs() <= precision)
    }

    /// `PLAN`: nodes within `precision` of the plane (a line in 2D) through
    /// `point` with normal `normal`, in node order.
    pub fn nodes_on_plane(
        &self,
        point: [f64; 3],
        normal: [f64; 3],
        precision: f64,
    ) -> Result<Vec<NodeId>, MeshError> {
        let l = norm(normal);
        if l == 0.0 || !l.is_finite() {
            return Err(MeshError::Operation(
                "PLAN: the normal vector is zero".into(),
            ));
        }
        let n = [normal[0] / l, normal[1] / l, normal[2] / l];
        Ok(self.nodes_where(|x| dot(sub(x, point), n).abs() <= precision))
    }

    /// `CREA_GROUP_MA/OPTION='CYLINDRE'` (code_aster's `cgmacy`, 3D
    /// meshes): the cells, in cell order, with at least one node
    /// (`at_least_one`) or all their nodes within `radius` of the axis
    /// through `point` along `axis`. A node at `point` itself selects its
    /// cell.
    pub fn cells_in_cylinder(
        &self,
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
        at_least_one: bool,
    ) -> Result<Vec<CellId>, MeshError> {
        let l = norm(axis);
        if l == 0.0 || !l.is_finite() {
            return Err(MeshError::Operation(
                "CYLINDRE: the axis vector is zero".into(),
            ));
        }
        if radius.is_nan() || radius <= 0.0 {
            return Err(MeshError::Operation(
                "CYLINDRE: RAYON must be positive".into(),
            ));
        }
        let a = [axis[0] / l, axis[1] / l, axis[2] / l];
        // Squared distance to the axis, as cgmacy computes it:
        // |x − x0|² sin²(angle between x − x0 and the axis).
        let inside = |x: [f64; 3]| -> Option<bool> {
            let d = sub(x, point);
            let r2 = dot(d, d);
            if r2 == 0.0 {
                return None;
            }
            let r = r2.sqrt();
            let mut c = (dot(d, a) / r).abs();
            if c > 1.0 {
                c -= 100.0 * f64::EPSILON;
            }
            let s = c.acos().sin();
            Some(r2 * s * s <= radius * radius)
        };
        let mut out = Vec::new();
        for (i, cell) in self.cells.iter().enumerate() {
            let mut inside_count = 0;
            let mut at_point = false;
            for &n in &cell.nodes {
                match inside(self.coord(n)) {
                    None => at_point = true,
                    Some(true) => inside_count += 1,
                    Some(false) => {}
                }
                if at_point {
                    break;
                }
            }
            let keep = at_point
                || if at_least_one {
                    inside_count > 0
                } else {
                    inside_count == cell.nodes.len()
                };
            if keep {
                out.push(CellId(i as u32));
            }
        }
        Ok(out)
    }

    fn nodes_where(&self, keep: impl Fn([f64; 3]) -> bool) -> Vec<NodeId> {
        (0..self.node_count() as u32)
            .map(NodeId)
            .filter(|n| keep(self.coord(*n)))
            .collect()
    }

    /// `SEGM_DROI_ORDO`: the `candidates` within `tolerance` of the segment
    /// from `a` to `b` (a distance; the caller scales it for
    /// `CRITERE='RELATIF'`), ordered by their abscissa from `a`.
    pub fn nodes_on_segment(
        &self,
        candidates: &[NodeId],
        a: NodeId,
        b: NodeId,
        tolerance: f64,
    ) -> Result<Vec<NodeId>, MeshError> {
        let (pa, pb) = (self.coord(a), self.coord(b));
        let ab = sub(pb, pa);
        let len = norm(ab);
        if len == 0.0 {
            return Err(MeshError::Operation(
                "SEGM_DROI_ORDO: the origin and the end are the same point".into(),
            ));
        }
        let t = [ab[0] / len, ab[1] / len, ab[2] / len];
        let mut on: Vec<(f64, NodeId)> = Vec::new();
        for &n in candidates {
            let ap = sub(self.coord(n), pa);
            let s = dot(ap, t);
            let off = [ap[0] - s * t[0], ap[1] - s * t[1], ap[2] - s * t[2]];
            if norm(off) <= tolerance && s >= -tolerance && s <= len + tolerance {
                on.push((s, n));
            }
        }
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        Ok(on.into_iter().map(|(_, n)| n).collect())
    }

    /// `NOEUD_ORDO`: the nodes of a chain of segment cells, in order from
    /// `origin` (default: the free end met first in the cells' order) to
    /// `end` (default: the other free end); the mid nodes of SEG3 cells
    /// come between their corners.
    pub fn nodes_along_line(
        &self,
        cells: &[CellId],
        origin: Option<NodeId>,
        end: Option<NodeId>,
    ) -> Result<Vec<NodeId>, MeshError> {
        let mut adjacency: HashMap<NodeId, Vec<usize>> = HashMap::new();
        let mut segs = Vec::new();
        for &c in cells {
            let cell = self.cell(c);
            if cell.ty.dim() != 1 {
                return Err(MeshError::Operation(format!(
                    "NOEUD_ORDO: cell {} is a {}; the group must hold segments",
                    self.cell_names[c.0 as usize],
                    cell.ty.name()
                )));
            }
            let k = segs.len();
            segs.push(c);
            adjacency.entry(cell.nodes[0]).or_default().push(k);
            adjacency.entry(cell.nodes[1]).or_default().push(k);
        }
        if let Some((n, _)) = adjacency.iter().find(|(_, s)| s.len() > 2) {
            return Err(MeshError::Operation(format!(
                "NOEUD_ORDO: the segments branch at node {} (a line is needed)",
                self.node_names[n.0 as usize]
            )));
        }
        let start = match origin {
            Some(o) => {
                if !adjacency.contains_key(&o) {
                    return Err(MeshError::Operation(format!(
                        "NOEUD_ORDO: the origin node {} is not on the segments",
                        self.node_names[o.0 as usize]
                    )));
                }
                o
            }
            None => segs
                .iter()
                .flat_map(|c| self.cell(*c).nodes[..2].to_vec())
                .find(|n| adjacency[n].len() == 1)
                .ok_or_else(|| {
                    MeshError::Operation(
                        "NOEUD_ORDO: the line is closed; give GROUP_NO_ORIG".into(),
                    )
                })?,
        };
        let mut used = vec![false; segs.len()];
        let mut out = vec![start];
        let mut at = start;
        while Some(at) != end {
            let Some(&k) = adjacency[&at].iter().find(|k| !used[**k]) else {
                break;
            };
            used[k] = true;
            let cell = self.cell(segs[k]);
            let forward = cell.nodes[0] == at;
            let next = if forward {
                cell.nodes[1]
            } else {
                cell.nodes[0]
            };
            let mut mids: Vec<NodeId> = cell.nodes[2..].to_vec();
            if !forward {
                mids.reverse();
            }
            out.extend(mids);
            if next == start {
                break;
            }
            out.push(next);
            at = next;
        }
        if let Some(e) = end {
            if out.last() != Some(&e) {
                return Err(MeshError::Operation(format!(
                    "NOEUD_ORDO: the end node {} is not reached from the origin along the segments",
                    self.node_names[e.0 as usize]
                )));
            }
        }
        Ok(out)
    }
}

impl Mesh {
    /// `CREA_GROUP_MA/OPTION='FACE_NORMALE'`: the boundary cells among
    /// `candidates` (segments in a plane mesh, faces in 3D) whose normal
    /// makes an angle of at most `angle_deg` with `vector` (or with its
    /// opposite too when `same_sign` is false), in their order.
    pub fn cells_facing(
        &self,
        candidates: &[CellId],
        vector: [f64; 3],
        angle_deg: f64,
        same_sign: bool,
    ) -> Result<Vec<CellId>, MeshError> {
        let lv = norm(vector);
        if lv == 0.0 || !lv.is_finite() {
            return Err(MeshError::Operation(
                "FACE_NORMALE: the vector is zero".into(),
            ));
        }
        let plane = self.dim < 3 || self.coords.iter().all(|c| c[2] == 0.0);
        let wanted_dim = if plane { 1 } else { 2 };
        let cos_max = angle_deg.to_radians().cos();
        Ok(candidates
            .iter()
            .copied()
            .filter(|c| {
                let cell = self.cell(*c);
                if cell.ty.dim() != wanted_dim {
                    return false;
                }
                let n = self.skin_normal(cell);
                let ln = norm(n);
                if ln == 0.0 {
                    return false;
                }
                let cos = dot(n, vector) / (ln * lv);
                let cos = if same_sign { cos } else { cos.abs() };
                cos >= cos_max - 1e-12
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::testmesh::two_quads;

    #[test]
    fn sphere_and_plane() {
        let m = two_quads();
        // Nodes at distance 1 from N1 (0, 0): N2 (1, 0) and N4 (0, 1).
        assert_eq!(
            m.nodes_on_sphere([0.0; 3], 1.0, 1e-6),
            vec![NodeId(1), NodeId(3)]
        );
        // The line x = 1: N2 and N5.
        let on = m
            .nodes_on_plane([1.0, 0.5, 0.0], [2.0, 0.0, 0.0], 1e-6)
            .unwrap();
        assert_eq!(on, vec![NodeId(1), NodeId(4)]);
        assert!(m.nodes_on_plane([0.0; 3], [0.0; 3], 1e-6).is_err());
    }

    /// Axis along z through (2.1, 0.5): N3 and N6 are 0.51 from it, N2
    /// and N5 1.208, N1 and N4 2.16.
    #[test]
    fn cylinder_selects_cells_by_their_nodes() {
        let m = two_quads();
        let c = [2.1, 0.5, 0.0];
        let z = [0.0, 0.0, 3.0];
        assert_eq!(m.cells_in_cylinder(c, z, 0.5, true).unwrap(), vec![]);
        assert_eq!(
            m.cells_in_cylinder(c, z, 0.6, true).unwrap(),
            vec![CellId(1)]
        );
        assert_eq!(m.cells_in_cylinder(c, z, 0.6, false).unwrap(), vec![]);
        assert_eq!(
            m.cells_in_cylinder(c, z, 1.25, true).unwrap(),
            vec![CellId(0), CellId(1)]
        );
        assert_eq!(
            m.cells_in_cylinder(c, z, 1.25, false).unwrap(),
            vec![CellId(1)]
        );
        // A node on the axis point selects its cells whatever the rule.
        assert_eq!(
            m.cells_in_cylinder([0.0; 3], z, 1e-3, false).unwrap(),
            vec![CellId(0), CellId(2)]
        );
        assert!(m.cells_in_cylinder(c, [0.0; 3], 1.0, true).is_err());
        assert!(m.cells_in_cylinder(c, z, 0.0, true).is_err());
    }

    #[test]
    fn segment_orders_by_abscissa() {
        let m = two_quads();
        let all: Vec<NodeId> = (0..6).map(NodeId).rev().collect();
        let on = m
            .nodes_on_segment(&all, NodeId(2), NodeId(0), 1e-9)
            .unwrap();
        assert_eq!(on, vec![NodeId(2), NodeId(1), NodeId(0)]);
    }

    #[test]
    fn line_order_with_mid_nodes_and_corner_filter() {
        let mut m = two_quads();
        let sel: Vec<CellId> = (0..3).map(CellId).collect();
        m.line_to_quad(&sel);
        // The SEG3 M3 (N4 N1 mid): from N1 the order is N1, mid, N4.
        let mid = m.cells[2].nodes[2];
        let line = m
            .nodes_along_line(&[CellId(2)], Some(NodeId(0)), None)
            .unwrap();
        assert_eq!(line, vec![NodeId(0), mid, NodeId(3)]);
        let corners = m.nodes_of_cells_kind(&[CellId(0)], NodeKind::Corners);
        assert_eq!(corners, vec![NodeId(0), NodeId(1), NodeId(4), NodeId(3)]);
        let mids = m.nodes_of_cells_kind(&[CellId(0)], NodeKind::MidEdges);
        assert_eq!(mids.len(), 4);
        assert!(mids.contains(&mid));
    }

    #[test]
    fn branching_lines_are_refused() {
        let mut m = two_quads();
        // Three segments meeting at N2.
        for (a, b) in [(0u32, 1u32), (1, 2), (1, 4)] {
            m.cells.push(crate::Cell {
                ty: CellType::SEG2,
                nodes: vec![NodeId(a), NodeId(b)],
            });
            m.cell_names.push(format!("S{a}{b}"));
        }
        let err = m
            .nodes_along_line(&[CellId(3), CellId(4), CellId(5)], None, None)
            .unwrap_err()
            .to_string();
        assert!(err.contains("branch at node N2"), "{err}");
    }

    #[test]
    fn faces_facing_a_direction() {
        let m = two_quads();
        let all: Vec<CellId> = (0..3).map(CellId).collect();
        // M3 runs N4 -> N1 (downwards): its normal (dy, -dx) is (-1, 0).
        assert_eq!(
            m.cells_facing(&all, [-1.0, 0.0, 0.0], 0.5, true).unwrap(),
            vec![CellId(2)]
        );
        assert!(m
            .cells_facing(&all, [1.0, 0.0, 0.0], 0.5, true)
            .unwrap()
            .is_empty());
        assert_eq!(
            m.cells_facing(&all, [1.0, 0.0, 0.0], 0.5, false).unwrap(),
            vec![CellId(2)]
        );
        assert!(m.cells_facing(&all, [0.0; 3], 0.5, true).is_err());
    }
}
