//! The points of code_aster's element fields at Gauss points (`ELGA`) on
//! any cell: the `RIGI` family of the cell's element, each point's physical
//! coordinates and integration weight as `COOR_ELGA` gives them (`te0488`
//! in 3D, `te0479` in the plane), and the shape functions that interpolate
//! nodal values there (`CREA_CHAMP(OPERATION='DISC')`, `cnsces` with
//! `manopg`).
//!
//! Families (code_aster 17's element catalog, `TOU_INI_ELGA`):
//! - a cell of the model's dimension (a plane model's faces, a 3D model's
//!   volumes): the stiffness family ([`shape::stiffness_scheme`]: TRIA3
//!   FPG1, TRIA6 FPG3 (FPG6 axisymmetric), QUAD4 FPG4, QUAD8/9 FPG9,
//!   HEXA8 FPG8, …);
//! - a skin cell (edges of a plane model, faces of a 3D one): the skin
//!   family ([`shape::skin_scheme`]: SEG2 FPG2, SEG3 FPG4, TRIA3 FPG3,
//!   QUAD4 FPG4, TRIA6 FPG6, QUAD8/9 FPG9);
//! - an edge of a 3D model (`MECA_ARETE2`/`MECA_ARETE3`): SEG2 FPG2, SEG3
//!   FPG3.
//!
//! The weight is the Gauss weight times the cell's measure at the point:
//! |det J| for volumes, |∂x/∂ξ × ∂x/∂η| for faces (in a plane model that
//! is |det J|), |∂x/∂ξ| for segments; axisymmetric models multiply it by
//! the radius x (`te0479`).

use crate::shape::{self, GaussPoint};
use aster_mesh::vec3::{cross, norm};
use aster_mesh::{CellId, CellType, Mesh};

/// Where a cell stands in its model, which sets its element's family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellRole {
    /// A cell of the model's dimension (a continuum element).
    Continuum,
    /// One dimension below the model's (a skin element).
    Skin,
    /// A segment of a 3D model (an edge element).
    Edge,
}

impl CellRole {
    /// The role of a cell of dimension `cell_dim` in a model of dimension
    /// `model_dim` (2 or 3); `None` for a cell that carries no `ELGA` field
    /// (points).
    pub fn of(cell_dim: usize, model_dim: usize) -> Option<CellRole> {
        match model_dim.checked_sub(cell_dim)? {
            0 => Some(CellRole::Continuum),
            1 => Some(CellRole::Skin),
            2 if cell_dim == 1 => Some(CellRole::Edge),
            _ => None,
        }
    }
}

/// code_aster's `RIGI` family of the element a cell carries, in its point
/// order; `None` when the cell has no such element here.
pub fn family(ty: CellType, role: CellRole, axisymmetric: bool) -> Option<Vec<GaussPoint>> {
    if !shape::supported(ty) {
        return None;
    }
    let scheme = match role {
        CellRole::Continuum => {
            let hyp = axisymmetric.then_some(crate::Hypothesis::Axisymmetric);
            shape::stiffness_scheme(ty, hyp)
        }
        CellRole::Skin => shape::skin_scheme(ty),
        CellRole::Edge => match ty {
            CellType::SEG2 => shape::skin_scheme(ty),
            CellType::SEG3 => shape::rigi_scheme(ty),
            _ => Vec::new(),
        },
    };
    (!scheme.is_empty()).then_some(scheme)
}

/// One point of a cell's family.
#[derive(Clone, Debug, PartialEq)]
pub struct ElgaPoint {
    /// Physical coordinates (the mesh's).
    pub x: [f64; 3],
    /// The Gauss weight times the cell's measure there (and the radius on
    /// an axisymmetric model): `COOR_ELGA`'s `W`.
    pub weight: f64,
    /// The cell's shape functions at the point, in its node order.
    pub shape: Vec<f64>,
}

/// The points of `scheme` on a cell (see the module's weights).
pub fn points(
    mesh: &Mesh,
    cell: CellId,
    scheme: &[GaussPoint],
    axisymmetric: bool,
) -> Vec<ElgaPoint> {
    let c = mesh.cell(cell);
    let dim = c.ty.dim() as usize;
    scheme
        .iter()
        .map(|gp| {
            let s = shape::shape(c.ty, gp.xi);
            let mut x = [0.0; 3];
            let mut t = [[0.0; 3]; 3];
            for (i, &n) in c.nodes.iter().enumerate() {
                let p = mesh.coord(n);
                for k in 0..3 {
                    x[k] += s.n[i] * p[k];
                    for d in 0..3 {
                        t[d][k] += s.dn[i][d] * p[k];
                    }
                }
            }
            let measure = match dim {
                1 => norm(t[0]),
                2 => norm(cross(t[0], t[1])),
                _ => {
                    let c01 = cross(t[0], t[1]);
                    (c01[0] * t[2][0] + c01[1] * t[2][1] + c01[2] * t[2][2]).abs()
                }
            };
            let mut weight = gp.weight * measure;
            if axisymmetric {
                weight *= x[0];
            }
            ElgaPoint {
                x,
                weight,
                shape: s.n,
            }
        })
        .collect()
}

/// Σ_points weight · Σ_c coef_c · v_c²: code_aster's `NORME_L2` of one
/// cell (`te0563` with `PCALCI` < 0, the squared norm), `values[p][c]` the
/// value of component c at point p.
pub fn weighted_square_sum(points: &[ElgaPoint], values: &[Vec<f64>], coef: &[f64]) -> f64 {
    let mut out = 0.0;
    for (p, v) in points.iter().zip(values) {
        let mut at = 0.0;
        for (c, x) in coef.iter().zip(v) {
            at += c * x * x;
        }
        out += at * p.weight;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(text: &str) -> Mesh {
        aster_mesh::parse_mail(text, std::path::Path::new("t.mail")).unwrap()
    }

    #[test]
    fn weights_integrate_the_measure_and_shapes_interpolate() {
        // A hexahedron 2 × 3 × 4 (volume 24) and its bottom face (area 6).
        let m = mesh(
            "COOR_3D\nN1 0 0 0\nN2 2 0 0\nN3 2 3 0\nN4 0 3 0\nN5 0 0 4\nN6 2 0 4\nN7 2 3 4\nN8 0 3 4\nFINSF\n\
             HEXA8\nH1 N1 N2 N3 N4 N5 N6 N7 N8\nFINSF\nQUAD4\nQ1 N1 N2 N3 N4\nFINSF\nSEG2\nS1 N1 N5\nFINSF\nFIN\n",
        );
        let cases = [
            (CellId(0), CellRole::Continuum, 8, 24.0),
            (CellId(1), CellRole::Skin, 4, 6.0),
            (CellId(2), CellRole::Edge, 2, 4.0),
        ];
        for (cell, role, n, measure) in cases {
            let ty = m.cell(cell).ty;
            let f = family(ty, role, false).unwrap();
            assert_eq!(f.len(), n);
            let pts = points(&m, cell, &f, false);
            let w: f64 = pts.iter().map(|p| p.weight).sum();
            assert!((w - measure).abs() < 1e-12, "{w} vs {measure}");
            // ∫ z² over the hexahedron: 2 · 3 · 4³/3 = 128, exact with FPG8.
            if role == CellRole::Continuum {
                let v: Vec<Vec<f64>> = pts.iter().map(|p| vec![p.x[2]]).collect();
                let s = weighted_square_sum(&pts, &v, &[1.0]);
                assert!((s - 128.0).abs() < 1e-10, "{s}");
            }
            // The shapes reproduce the coordinates.
            for p in &pts {
                let c = m.cell(cell);
                let x: f64 = c
                    .nodes
                    .iter()
                    .zip(&p.shape)
                    .map(|(&n, s)| s * m.coord(n)[0])
                    .sum();
                assert!((x - p.x[0]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn axisymmetric_weights_carry_the_radius() {
        // QUAD4 [1, 3] × [0, 1]: ∫ r dr dz = (9 − 1)/2 = 4.
        let m = mesh(
            "COOR_2D\nN1 1 0\nN2 3 0\nN3 3 1\nN4 1 1\nFINSF\nQUAD4\nQ1 N1 N2 N3 N4\nFINSF\nFIN\n",
        );
        let f = family(CellType::QUAD4, CellRole::Continuum, true).unwrap();
        let w: f64 = points(&m, CellId(0), &f, true)
            .iter()
            .map(|p| p.weight)
            .sum();
        assert!((w - 4.0).abs() < 1e-12);
    }

    #[test]
    fn roles() {
        assert_eq!(CellRole::of(3, 3), Some(CellRole::Continuum));
        assert_eq!(CellRole::of(2, 3), Some(CellRole::Skin));
        assert_eq!(CellRole::of(1, 3), Some(CellRole::Edge));
        assert_eq!(CellRole::of(1, 2), Some(CellRole::Skin));
        assert_eq!(CellRole::of(0, 2), None);
        assert_eq!(CellRole::of(0, 3), None);
    }
}
