//! L2 norms over skin cells (edges of plane models, faces of 3D ones) on
//! code_aster's skin Gauss family ([`crate::shape::skin_scheme`]: SEG2 FPG2, SEG3
//! FPG4, TRIA3 FPG3, QUAD4 FPG4…), as code_aster's `NORME_L2` (`te0563`)
//! integrates an `ELGA` field with the weights of `COOR_ELGA` (the Gauss
//! weight times the cell's length or area jacobian). The nodal values are
//! interpolated at the points by the cell's shape functions (code_aster's
//! `CREA_CHAMP(OPERATION='DISC')`).

use crate::elga;
use aster_mesh::{CellId, Mesh};

/// One integration point of a skin cell: [`crate::elga::ElgaPoint`]
/// (physical coordinates, the Gauss weight times the jacobian
/// |∂x/∂ξ| (segments) or |∂x/∂ξ × ∂x/∂η| (faces), the shape functions).
pub type SkinPoint = crate::elga::ElgaPoint;

/// The integration points of a skin cell (a segment or a face), or `None`
/// for a cell that is not one (points, volumes) or has no skin family.
pub fn skin_points(mesh: &Mesh, cell: CellId) -> Option<Vec<SkinPoint>> {
    let c = mesh.cell(cell);
    if !(1..=2).contains(&c.ty.dim()) {
        return None;
    }
    let scheme = elga::family(c.ty, elga::CellRole::Skin, false)?;
    Some(elga::points(mesh, cell, &scheme, false))
}

/// ∫ (Σᵢ Nᵢ vᵢ − e(x))² and ∫ e(x)² over one skin cell: the squared L2
/// norms of the difference between nodal values `v` (in the cell's node
/// order) interpolated at the points and an exact function `e`, and of
/// `e`. `None` as [`skin_points`]; the exact function's error is passed on.
pub fn skin_l2_squared<E>(
    mesh: &Mesh,
    cell: CellId,
    v: &[f64],
    mut exact: impl FnMut([f64; 3]) -> Result<f64, E>,
) -> Option<Result<(f64, f64), E>> {
    let points = skin_points(mesh, cell)?;
    let (mut diff, mut reference) = (0.0, 0.0);
    for p in &points {
        let e = match exact(p.x) {
            Ok(e) => e,
            Err(err) => return Some(Err(err)),
        };
        let h: f64 = p.shape.iter().zip(v).map(|(n, v)| n * v).sum();
        diff += p.weight * (h - e) * (h - e);
        reference += p.weight * e * e;
    }
    Some(Ok((diff, reference)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(text: &str) -> Mesh {
        aster_mesh::parse_mail(text, std::path::Path::new("t.mail")).unwrap()
    }

    #[test]
    fn segment_and_face_norms_are_exact_for_polynomials() {
        let m = mesh(
            "COOR_3D\nN1 0 0 0\nN2 2 0 0\nN3 2 3 0\nN4 0 3 0\nFINSF\nSEG2\nS1 N1 N2\nFINSF\nQUAD4\nQ1 N1 N2 N3 N4\nFINSF\nFIN\n",
        );
        // Segment of length 2, v = (0, 2) interpolates x; e = 0:
        // ∫₀² x² dx = 8/3, exactly with FPG2.
        let (d, r) = skin_l2_squared(&m, CellId(0), &[0.0, 2.0], |_| Ok::<_, ()>(0.0))
            .unwrap()
            .unwrap();
        assert!((d - 8.0 / 3.0).abs() < 1e-12 && r == 0.0);
        // Face 2 × 3, v = 0, e = y: ∫ y² = 2 · 9 = 18.
        let (d, r) = skin_l2_squared(&m, CellId(1), &[0.0; 4], |x| Ok::<_, ()>(x[1]))
            .unwrap()
            .unwrap();
        assert!((d - 18.0).abs() < 1e-12 && (r - 18.0).abs() < 1e-12);
    }
}
