//! Kinematic coupling of a solid's face to one node carrying rotations (a
//! beam or discrete `DIS_TR` node): code_aster's `LIAISON_ELEM`
//! `OPTION='3D_POU'` (`rapo3d`, with the face integrals of the options
//! `CARA_SECT_POUT3`/`CARA_SECT_POUT4`).
//!
//! With S the face's area, G its centroid, I_G its inertia tensor about G
//! (I₁ = ∫(y²+z²), I₂ = −∫xy, … of the coordinates relative to G) and,
//! for each face node i, cᵢ = ∫ Nᵢ dS and dᵢ = ∫ Nᵢ (x − G) dS, the six
//! relations are
//!
//! - Σᵢ cᵢ uᵢ − S u_P = 0 (the mean translation is the node's: three rows),
//! - Σᵢ dᵢ × uᵢ − I_G θ_P = 0 (the moment of the translations about G is
//!   the node's rotation through the face's inertia: three rows),
//!
//! as code_aster writes them: the node P's own position does not enter
//! (code_aster only warns when P is far from G).

use crate::error::FemError;
use crate::shape;
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeMap;

/// One linear relation Σ coef · u(node, component) = 0; components are
/// 0..6 for DX DY DZ DRX DRY DRZ.
pub type CouplingRow = Vec<(NodeId, usize, f64)>;

/// The six relations coupling the face `cells` (2D cells of a 3D mesh) to
/// `node` (LIAISON_ELEM 3D_POU), in code_aster's order: DX, DY, DZ, then
/// the moments about x, y, z.
pub fn solid_to_beam(
    mesh: &Mesh,
    cells: &[CellId],
    node: NodeId,
) -> Result<Vec<CouplingRow>, FemError> {
    let mut area = 0.0;
    let mut first = [0.0; 3];
    let mut second = [[0.0; 3]; 3];
    // Per face node: ∫Nᵢ and ∫Nᵢ x.
    let mut per_node: BTreeMap<NodeId, (f64, [f64; 3])> = BTreeMap::new();
    for &cell in cells {
        let c = mesh.cell(cell);
        if c.ty.dim() != 2 || !shape::supported(c.ty) {
            return Err(FemError::Model(format!(
                "LIAISON_ELEM 3D_POU: cell {} ({}) is not a face (TRIA3, QUAD4, …) of the solid",
                mesh.cell_name(cell),
                c.ty.name()
            )));
        }
        for gp in shape::load_scheme(c.ty) {
            let s = shape::shape(c.ty, gp.xi);
            let [x, t1, t2] = shape::point_and_tangents(mesh, c, &s);
            let normal = [
                t1[1] * t2[2] - t1[2] * t2[1],
                t1[2] * t2[0] - t1[0] * t2[2],
                t1[0] * t2[1] - t1[1] * t2[0],
            ];
            let jac = (normal[0].powi(2) + normal[1].powi(2) + normal[2].powi(2)).sqrt();
            if !(jac > 0.0 && jac.is_finite()) {
                return Err(FemError::Model(format!(
                    "LIAISON_ELEM 3D_POU: degenerate face cell {}",
                    mesh.cell_name(cell)
                )));
            }
            let w = gp.weight * jac;
            area += w;
            for k in 0..3 {
                first[k] += w * x[k];
                for l in 0..3 {
                    second[k][l] += w * x[k] * x[l];
                }
            }
            for (i, &n) in c.nodes.iter().enumerate() {
                let slot = per_node.entry(n).or_insert((0.0, [0.0; 3]));
                slot.0 += w * s.n[i];
                for k in 0..3 {
                    slot.1[k] += w * s.n[i] * x[k];
                }
            }
        }
    }
    if area.is_nan() || area <= 0.0 {
        return Err(FemError::Model(
            "LIAISON_ELEM 3D_POU: the face has no area (code_aster's MODELISA6_46)".into(),
        ));
    }
    let g = [first[0] / area, first[1] / area, first[2] / area];
    // Second moments about G.
    let m = |k: usize, l: usize| second[k][l] - area * g[k] * g[l];
    let ig = [
        m(1, 1) + m(2, 2),
        -m(0, 1),
        -m(0, 2),
        m(2, 2) + m(0, 0),
        -m(1, 2),
        m(0, 0) + m(1, 1),
    ];
    let inertia = [
        [ig[0], ig[1], ig[2]],
        [ig[1], ig[3], ig[4]],
        [ig[2], ig[4], ig[5]],
    ];
    let mut rows: Vec<CouplingRow> = vec![Vec::new(); 6];
    for (&n, &(c, nx)) in &per_node {
        let d = [nx[0] - c * g[0], nx[1] - c * g[1], nx[2] - c * g[2]];
        for k in 0..3 {
            rows[k].push((n, k, c));
        }
        // (d × u)ₓ = d_y u_z − d_z u_y, and so on.
        rows[3].push((n, 2, d[1]));
        rows[3].push((n, 1, -d[2]));
        rows[4].push((n, 0, d[2]));
        rows[4].push((n, 2, -d[0]));
        rows[5].push((n, 1, d[0]));
        rows[5].push((n, 0, -d[1]));
    }
    for k in 0..3 {
        rows[k].push((node, k, -area));
        for (l, row) in inertia[k].iter().enumerate() {
            rows[3 + k].push((node, 3 + l, -row));
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::{Cell, CellType};

    /// A 2 × 1 rectangle in the plane z = 0 (two QUAD4) and a node at its
    /// centre: a rigid motion (translation t, small rotation ω) of the face
    /// and the node satisfies the six relations exactly; the coefficients of
    /// the node are −S and −I_G (I_xx = ∫y² = 2/12, I_yy = ∫x² = 8/12,
    /// I_zz their sum).
    #[test]
    fn a_rigid_motion_satisfies_the_coupling() {
        let coords = vec![
            [-1., -0.5, 0.],
            [0., -0.5, 0.],
            [1., -0.5, 0.],
            [-1., 0.5, 0.],
            [0., 0.5, 0.],
            [1., 0.5, 0.],
            [0., 0., 0.],
        ];
        let quad = |a: u32, b: u32, c: u32, d: u32| Cell {
            ty: CellType::QUAD4,
            nodes: vec![NodeId(a), NodeId(b), NodeId(c), NodeId(d)],
        };
        let mesh = Mesh {
            dim: 3,
            node_names: (0..coords.len()).map(|i| format!("N{i}")).collect(),
            coords: coords.clone(),
            cells: vec![quad(0, 1, 4, 3), quad(1, 2, 5, 4)],
            cell_names: vec!["F1".into(), "F2".into()],
            ..Mesh::default()
        };
        let rows = solid_to_beam(&mesh, &[CellId(0), CellId(1)], NodeId(6)).unwrap();
        assert_eq!(rows.len(), 6);
        let coef = |r: usize, c: usize| {
            rows[r]
                .iter()
                .filter(|(n, k, _)| *n == NodeId(6) && *k == c)
                .map(|t| t.2)
                .sum::<f64>()
        };
        assert!((coef(0, 0) + 2.0).abs() < 1e-14);
        assert!((coef(3, 3) + 2.0 / 12.0).abs() < 1e-14);
        assert!((coef(4, 4) + 8.0 / 12.0).abs() < 1e-14);
        assert!((coef(5, 5) + 10.0 / 12.0).abs() < 1e-14);
        assert!(coef(3, 4).abs() < 1e-14);
        let (t, w) = ([0.3, -0.2, 0.7], [0.01, -0.02, 0.03]);
        let u = |n: NodeId, k: usize| {
            let x = coords[n.0 as usize];
            if n == NodeId(6) {
                return if k < 3 { t[k] } else { w[k - 3] };
            }
            let wx = [
                w[1] * x[2] - w[2] * x[1],
                w[2] * x[0] - w[0] * x[2],
                w[0] * x[1] - w[1] * x[0],
            ];
            t[k] + wx[k]
        };
        for (r, row) in rows.iter().enumerate() {
            let sum: f64 = row.iter().map(|&(n, k, c)| c * u(n, k)).sum();
            assert!(sum.abs() < 1e-14, "row {r}: {sum}");
        }
    }

    #[test]
    fn a_volume_cell_is_not_a_face() {
        let mesh = Mesh {
            dim: 3,
            coords: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            node_names: (0..4).map(|i| format!("N{i}")).collect(),
            cells: vec![Cell {
                ty: CellType::TETRA4,
                nodes: (0..4).map(NodeId).collect(),
            }],
            cell_names: vec!["V1".into()],
            ..Mesh::default()
        };
        let e = solid_to_beam(&mesh, &[CellId(0)], NodeId(0)).unwrap_err();
        assert!(e.to_string().contains("V1"), "{e}");
    }
}
