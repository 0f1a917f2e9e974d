//! The shortest and longest cell edges (code_aster's `cargeo`: the
//! `AR_MIN`/`AR_MAX` of a mesh's `CARA_GEOM` table, and
//! `Mesh.getMinMaxEdgeSizes()`): the straight distances between the corners
//! each edge of a cell joins (mid-edge nodes are not used); zero-length
//! edges are ignored.

use crate::ops::degree::{edges, linear_of};
use crate::{CellId, Mesh};

impl Mesh {
    /// `(shortest, longest)` edge of the given cells (`None` when they have
    /// no edge of positive length: points only, or coincident corners).
    pub fn edge_size_range(&self, cells: impl IntoIterator<Item = CellId>) -> Option<(f64, f64)> {
        let mut lo = f64::INFINITY;
        let mut hi = 0.0f64;
        for c in cells {
            let cell = self.cell(c);
            let ty = linear_of(cell.ty).unwrap_or(cell.ty);
            let Some((_, pairs)) = edges(ty) else {
                continue;
            };
            for [a, b] in pairs {
                let (Some(&na), Some(&nb)) = (cell.nodes.get(*a), cell.nodes.get(*b)) else {
                    continue;
                };
                let (p, q) = (self.coord(na), self.coord(nb));
                let d2: f64 = (0..3).map(|k| (q[k] - p[k]).powi(2)).sum();
                if d2 > 0.0 {
                    lo = lo.min(d2);
                    hi = hi.max(d2);
                }
            }
        }
        (hi > 0.0).then(|| (lo.sqrt(), hi.sqrt()))
    }

    /// [`Mesh::edge_size_range`] over every cell.
    pub fn edge_sizes(&self) -> Option<(f64, f64)> {
        self.edge_size_range((0..self.cells.len() as u32).map(CellId))
    }
}

#[cfg(test)]
mod tests {
    use crate::ops::testmesh::two_quads;
    use crate::CellId;

    #[test]
    fn unit_squares_have_unit_edges_and_a_stretched_one_a_longer_edge() {
        let mut m = two_quads();
        assert_eq!(m.edge_sizes(), Some((1.0, 1.0)));
        // Stretch N3 and N6 to x = 4: M2's horizontal edges become 3 long.
        m.coords[2][0] = 4.0;
        m.coords[5][0] = 4.0;
        assert_eq!(m.edge_sizes(), Some((1.0, 3.0)));
        // M1 alone keeps unit edges.
        assert_eq!(m.edge_size_range([CellId(0)]), Some((1.0, 1.0)));
    }
}
