//! `MODI_MAILLAGE(ORIE_NORM_COQUE=…)` and `ORIE_LIGNE`: orient a connected
//! set of faces (or segments) consistently, the one at a given node along a
//! given vector.
//!
//! Faces: the cell holding the node is reversed if its normal (right-hand
//! rule) points against `VECT_NORM`; its neighbours across shared edges are
//! then made consistent (a shared edge is travelled in opposite directions
//! by two consistently oriented faces). Segments: the cell at the node is
//! reversed if its tangent (node 1 → node 2) points against the vector, and
//! the chain follows (one segment ends where the next begins). In 2D,
//! `ORIE_NORM_COQUE` on segments uses their normal (Δy, −Δx).

use crate::error::MeshError;
use crate::vec3::dot;
use crate::{CellId, Mesh, NodeId};
use std::collections::{HashMap, VecDeque};

/// What the vector of [`Mesh::orient_along`] gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Along {
    /// `ORIE_NORM_COQUE`: the normal.
    Normal,
    /// `ORIE_LIGNE`: the tangent of segments.
    Tangent,
}

impl Mesh {
    /// Directed boundary edges (faces) or the single directed segment.
    fn directed_edges(&self, c: CellId) -> Vec<(NodeId, NodeId)> {
        let cell = self.cell(c);
        let k = cell.ty.corner_count().min(cell.nodes.len());
        let corners = &cell.nodes[..k];
        if cell.ty.dim() == 1 {
            return vec![(corners[0], corners[1])];
        }
        (0..k).map(|i| (corners[i], corners[(i + 1) % k])).collect()
    }

    /// Orients `cells` (one connected set of faces, or of segments) so the
    /// cell at `node` follows `vector`, and the others follow it; without a
    /// vector, the first cell keeps its orientation and the others follow.
    /// Returns how many cells were reversed.
    pub fn orient_along(
        &mut self,
        cells: &[CellId],
        node: NodeId,
        vector: Option<[f64; 3]>,
        along: Along,
    ) -> Result<usize, MeshError> {
        let what = match along {
            Along::Normal => "ORIE_NORM_COQUE",
            Along::Tangent => "ORIE_LIGNE",
        };
        for &c in cells {
            let ty = self.cell(c).ty;
            let ok = match along {
                Along::Normal => ty.reversal().is_some(),
                Along::Tangent => ty.dim() == 1,
            };
            if !ok {
                return Err(MeshError::Operation(format!(
                    "{what}: cell `{}` is a {}, which cannot be oriented here",
                    self.cell_names[c.0 as usize],
                    ty.name()
                )));
            }
        }
        let Some(&seed) = cells.iter().find(|c| self.cell(**c).nodes.contains(&node)) else {
            return Err(MeshError::Operation(format!(
                "{what}: node {} is not on the cells to orient",
                self.node_names[node.0 as usize]
            )));
        };
        // Cells by undirected edge (faces) or by node (segments).
        let mut by_key: HashMap<(NodeId, NodeId), Vec<CellId>> = HashMap::new();
        for &c in cells {
            if self.cell(c).ty.dim() == 1 {
                let (a, b) = self.directed_edges(c)[0];
                by_key.entry((a, a)).or_default().push(c);
                by_key.entry((b, b)).or_default().push(c);
            } else {
                for (a, b) in self.directed_edges(c) {
                    by_key.entry((a.min(b), a.max(b))).or_default().push(c);
                }
            }
        }
        let reference = {
            let cell = self.cell(seed).clone();
            match along {
                Along::Normal => self.skin_normal(&cell),
                Along::Tangent => {
                    let (a, b) = (self.coord(cell.nodes[0]), self.coord(cell.nodes[1]));
                    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
                }
            }
        };
        let mut flip: HashMap<CellId, bool> = HashMap::new();
        flip.insert(seed, vector.is_some_and(|v| dot(reference, v) < 0.0));
        let mut queue = VecDeque::from([seed]);
        while let Some(c) = queue.pop_front() {
            let f = flip[&c];
            for (a, b) in self.directed_edges(c) {
                let (a, b) = if f { (b, a) } else { (a, b) };
                let segment = self.cell(c).ty.dim() == 1;
                let keys: Vec<((NodeId, NodeId), bool)> = if segment {
                    // The next segment must start at b, the previous end at a.
                    vec![((b, b), true), ((a, a), false)]
                } else {
                    vec![((a.min(b), a.max(b)), true)]
                };
                for (key, _) in keys {
                    for &n in by_key.get(&key).map(Vec::as_slice).unwrap_or(&[]) {
                        if n == c {
                            continue;
                        }
                        let (na, nb) = self.directed_edges(n)[0];
                        let wants = if segment {
                            // Consistent: n starts where c ends, or ends where c starts.
                            let starts_at_b = na == b;
                            let ends_at_a = nb == a;
                            !(starts_at_b || ends_at_a)
                        } else {
                            // n must travel the shared edge as (b, a).
                            self.directed_edges(n).contains(&(a, b))
                        };
                        match flip.get(&n) {
                            None => {
                                flip.insert(n, wants);
                                queue.push_back(n);
                            }
                            Some(&have) if have != wants => {
                                return Err(MeshError::Operation(format!(
                                    "{what}: cells `{}` and `{}` cannot be oriented consistently (a non-orientable or branching surface)",
                                    self.cell_names[c.0 as usize],
                                    self.cell_names[n.0 as usize]
                                )));
                            }
                            Some(_) => {}
                        }
                    }
                }
            }
        }
        if let Some(&lost) = cells.iter().find(|c| !flip.contains_key(c)) {
            return Err(MeshError::Operation(format!(
                "{what}: cell `{}` is not connected to the cell at node {}; orient each connected part with its own node",
                self.cell_names[lost.0 as usize],
                self.node_names[node.0 as usize]
            )));
        }
        let mut reversed = 0;
        for (c, f) in flip {
            if f {
                let cell = &mut self.cells[c.0 as usize];
                let perm = cell.ty.reversal().unwrap_or(&[]);
                if perm.len() == cell.nodes.len() {
                    cell.nodes = perm.iter().map(|&k| cell.nodes[k]).collect();
                    reversed += 1;
                }
            }
        }
        Ok(reversed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ops::testmesh::two_quads;
    use crate::{Cell, CellType};

    #[test]
    fn faces_follow_the_vector_and_each_other() {
        let mut m = two_quads();
        // Make M2 clockwise (inconsistent with M1), then ask for -z normals.
        m.cells[1].nodes = vec![NodeId(1), NodeId(4), NodeId(5), NodeId(2)];
        let r = m
            .orient_along(
                &[CellId(0), CellId(1)],
                NodeId(0),
                Some([0.0, 0.0, -1.0]),
                Along::Normal,
            )
            .unwrap();
        assert_eq!(r, 1, "only M1 is reversed: M2 already has -z");
        for c in 0..2 {
            let n = m.skin_normal(&m.cells[c].clone());
            assert!(n[2] < 0.0, "cell {c}: {n:?}");
        }
    }

    #[test]
    fn a_chain_of_segments_follows_the_tangent() {
        let mut m = two_quads();
        // Bottom chain N1-N2 (as N2→N1) and N2-N3 (as N2→N3).
        for (a, b) in [(1u32, 0u32), (1, 2)] {
            m.cells.push(Cell {
                ty: CellType::SEG2,
                nodes: vec![NodeId(a), NodeId(b)],
            });
            m.cell_names.push(format!("S{a}{b}"));
        }
        let r = m
            .orient_along(
                &[CellId(3), CellId(4)],
                NodeId(2),
                Some([1.0, 0.0, 0.0]),
                Along::Tangent,
            )
            .unwrap();
        assert_eq!(r, 1);
        assert_eq!(m.cells[3].nodes, vec![NodeId(0), NodeId(1)]);
        assert_eq!(m.cells[4].nodes, vec![NodeId(1), NodeId(2)]);
    }

    #[test]
    fn disconnected_parts_are_named() {
        let mut m = two_quads();
        let err = m
            .orient_along(
                &[CellId(0), CellId(2)],
                NodeId(1),
                Some([0.0, 0.0, 1.0]),
                Along::Normal,
            )
            .unwrap_err()
            .to_string();
        assert!(err.contains("M3"), "{err}");
    }
}
