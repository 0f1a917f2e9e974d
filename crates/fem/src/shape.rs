//! Reference elements: shape functions, their derivatives and Gauss
//! schemes, with code_aster's node ordering and integration families.
//!
//! Reference cells (code_aster's): segments on [-1, 1]; triangles on
//! (0,0) (1,0) (0,1); quadrangles on [-1, 1]²; tetrahedra on the unit
//! simplex; hexahedra on [-1, 1]³.

use aster_mesh::CellType;

/// A quadrature point: reference coordinates and weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussPoint {
    pub xi: [f64; 3],
    pub weight: f64,
}

/// Shape function values and reference derivatives at one point.
pub struct ShapeAt {
    pub n: Vec<f64>,
    /// `dn[i][k]` = ∂Nᵢ/∂ξₖ.
    pub dn: Vec<[f64; 3]>,
}

/// Whether we have an isoparametric formulation for this cell type.
pub fn supported(ty: CellType) -> bool {
    matches!(
        ty,
        CellType::SEG2
            | CellType::SEG3
            | CellType::TRIA3
            | CellType::TRIA6
            | CellType::QUAD4
            | CellType::QUAD8
            | CellType::TETRA4
            | CellType::HEXA8
    )
}

/// Reference coordinates of the nodes of a cell type.
pub fn reference_nodes(ty: CellType) -> Vec<[f64; 3]> {
    match ty {
        CellType::SEG2 => vec![[-1., 0., 0.], [1., 0., 0.]],
        CellType::SEG3 => vec![[-1., 0., 0.], [1., 0., 0.], [0., 0., 0.]],
        CellType::TRIA3 => vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
        CellType::TRIA6 => vec![
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [0.5, 0., 0.],
            [0.5, 0.5, 0.],
            [0., 0.5, 0.],
        ],
        CellType::QUAD4 => vec![[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]],
        CellType::QUAD8 => vec![
            [-1., -1., 0.],
            [1., -1., 0.],
            [1., 1., 0.],
            [-1., 1., 0.],
            [0., -1., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
        ],
        CellType::TETRA4 => vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        CellType::HEXA8 => vec![
            [-1., -1., -1.],
            [1., -1., -1.],
            [1., 1., -1.],
            [-1., 1., -1.],
            [-1., -1., 1.],
            [1., -1., 1.],
            [1., 1., 1.],
            [-1., 1., 1.],
        ],
        _ => Vec::new(),
    }
}

/// Shape functions and reference derivatives at `xi`.
pub fn shape(ty: CellType, xi: [f64; 3]) -> ShapeAt {
    let [x, y, z] = xi;
    match ty {
        CellType::SEG2 => ShapeAt {
            n: vec![0.5 * (1. - x), 0.5 * (1. + x)],
            dn: vec![[-0.5, 0., 0.], [0.5, 0., 0.]],
        },
        CellType::SEG3 => ShapeAt {
            n: vec![-0.5 * x * (1. - x), 0.5 * x * (1. + x), 1. - x * x],
            dn: vec![[x - 0.5, 0., 0.], [x + 0.5, 0., 0.], [-2. * x, 0., 0.]],
        },
        CellType::TRIA3 => ShapeAt {
            n: vec![1. - x - y, x, y],
            dn: vec![[-1., -1., 0.], [1., 0., 0.], [0., 1., 0.]],
        },
        CellType::TRIA6 => {
            let l = 1. - x - y;
            ShapeAt {
                n: vec![
                    l * (2. * l - 1.),
                    x * (2. * x - 1.),
                    y * (2. * y - 1.),
                    4. * x * l,
                    4. * x * y,
                    4. * y * l,
                ],
                dn: vec![
                    [1. - 4. * l, 1. - 4. * l, 0.],
                    [4. * x - 1., 0., 0.],
                    [0., 4. * y - 1., 0.],
                    [4. * (l - x), -4. * x, 0.],
                    [4. * y, 4. * x, 0.],
                    [-4. * y, 4. * (l - y), 0.],
                ],
            }
        }
        CellType::QUAD4 => {
            let r = reference_nodes(ty);
            let mut n = Vec::with_capacity(4);
            let mut dn = Vec::with_capacity(4);
            for p in r {
                n.push(0.25 * (1. + p[0] * x) * (1. + p[1] * y));
                dn.push([
                    0.25 * p[0] * (1. + p[1] * y),
                    0.25 * p[1] * (1. + p[0] * x),
                    0.,
                ]);
            }
            ShapeAt { n, dn }
        }
        CellType::QUAD8 => {
            let r = reference_nodes(ty);
            let mut n = Vec::with_capacity(8);
            let mut dn = Vec::with_capacity(8);
            for (i, p) in r.into_iter().enumerate() {
                let (a, b) = (p[0], p[1]);
                if i < 4 {
                    let s = a * x + b * y - 1.;
                    n.push(0.25 * (1. + a * x) * (1. + b * y) * s);
                    dn.push([
                        0.25 * a * (1. + b * y) * (2. * a * x + b * y),
                        0.25 * b * (1. + a * x) * (a * x + 2. * b * y),
                        0.,
                    ]);
                } else if a == 0. {
                    n.push(0.5 * (1. - x * x) * (1. + b * y));
                    dn.push([-x * (1. + b * y), 0.5 * b * (1. - x * x), 0.]);
                } else {
                    n.push(0.5 * (1. + a * x) * (1. - y * y));
                    dn.push([0.5 * a * (1. - y * y), -y * (1. + a * x), 0.]);
                }
            }
            ShapeAt { n, dn }
        }
        CellType::TETRA4 => ShapeAt {
            n: vec![1. - x - y - z, x, y, z],
            dn: vec![[-1., -1., -1.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        },
        CellType::HEXA8 => {
            let r = reference_nodes(ty);
            let mut n = Vec::with_capacity(8);
            let mut dn = Vec::with_capacity(8);
            for p in r {
                let (a, b, c) = (1. + p[0] * x, 1. + p[1] * y, 1. + p[2] * z);
                n.push(0.125 * a * b * c);
                dn.push([
                    0.125 * p[0] * b * c,
                    0.125 * p[1] * a * c,
                    0.125 * p[2] * a * b,
                ]);
            }
            ShapeAt { n, dn }
        }
        _ => ShapeAt {
            n: Vec::new(),
            dn: Vec::new(),
        },
    }
}

const G2: f64 = 0.577_350_269_189_625_8; // 1/√3
const G3: f64 = 0.774_596_669_241_483_4; // √(3/5)

fn gauss_1d(order: usize) -> Vec<(f64, f64)> {
    match order {
        1 => vec![(0., 2.)],
        2 => vec![(-G2, 1.), (G2, 1.)],
        _ => vec![(-G3, 5. / 9.), (0., 8. / 9.), (G3, 5. / 9.)],
    }
}

/// The stiffness ("RIGI") Gauss family code_aster uses for each cell type:
/// SEG2 FPG2, SEG3 FPG3, TRIA3 FPG1, TRIA6 FPG3, QUAD4 FPG4 (2×2),
/// QUAD8 FPG9 (3×3), TETRA4 FPG1, HEXA8 FPG8 (2×2×2).
///
/// Point order follows code_aster's `elraga`: QUAD4 counter-clockwise from
/// (-a,-a); QUAD8 corners, then mid-edges, then centre; TRIA6 (1/6,1/6),
/// (2/3,1/6), (1/6,2/3).
pub fn rigi_scheme(ty: CellType) -> Vec<GaussPoint> {
    let gp = |x: f64, y: f64, z: f64, w: f64| GaussPoint {
        xi: [x, y, z],
        weight: w,
    };
    match ty {
        CellType::SEG2 => gauss_1d(2)
            .into_iter()
            .map(|(x, w)| gp(x, 0., 0., w))
            .collect(),
        CellType::SEG3 => gauss_1d(3)
            .into_iter()
            .map(|(x, w)| gp(x, 0., 0., w))
            .collect(),
        CellType::TRIA3 => vec![gp(1. / 3., 1. / 3., 0., 0.5)],
        CellType::TRIA6 => vec![
            gp(1. / 6., 1. / 6., 0., 1. / 6.),
            gp(2. / 3., 1. / 6., 0., 1. / 6.),
            gp(1. / 6., 2. / 3., 0., 1. / 6.),
        ],
        CellType::QUAD4 => vec![
            gp(-G2, -G2, 0., 1.),
            gp(G2, -G2, 0., 1.),
            gp(G2, G2, 0., 1.),
            gp(-G2, G2, 0., 1.),
        ],
        CellType::QUAD8 => {
            let (c, m) = (25. / 81., 40. / 81.);
            vec![
                gp(-G3, -G3, 0., c),
                gp(G3, -G3, 0., c),
                gp(G3, G3, 0., c),
                gp(-G3, G3, 0., c),
                gp(0., -G3, 0., m),
                gp(G3, 0., 0., m),
                gp(0., G3, 0., m),
                gp(-G3, 0., 0., m),
                gp(0., 0., 0., 64. / 81.),
            ]
        }
        CellType::TETRA4 => vec![gp(0.25, 0.25, 0.25, 1. / 6.)],
        CellType::HEXA8 => {
            let mut v = Vec::with_capacity(8);
            for &(z, _) in &gauss_1d(2) {
                for &(y, _) in &gauss_1d(2) {
                    for &(x, _) in &gauss_1d(2) {
                        v.push(gp(x, y, z, 1.));
                    }
                }
            }
            v
        }
        _ => Vec::new(),
    }
}

/// Integration scheme for boundary loads on a segment or face: exact for
/// the polynomial degree of the load times the shape functions.
pub fn load_scheme(ty: CellType) -> Vec<GaussPoint> {
    match ty {
        CellType::TRIA3 => vec![
            GaussPoint {
                xi: [1. / 6., 1. / 6., 0.],
                weight: 1. / 6.,
            },
            GaussPoint {
                xi: [2. / 3., 1. / 6., 0.],
                weight: 1. / 6.,
            },
            GaussPoint {
                xi: [1. / 6., 2. / 3., 0.],
                weight: 1. / 6.,
            },
        ],
        CellType::SEG2 => gauss_1d(3)
            .into_iter()
            .map(|(x, w)| GaussPoint {
                xi: [x, 0., 0.],
                weight: w,
            })
            .collect(),
        CellType::QUAD4 => {
            let mut v = Vec::new();
            for &(y, wy) in &gauss_1d(3) {
                for &(x, wx) in &gauss_1d(3) {
                    v.push(GaussPoint {
                        xi: [x, y, 0.],
                        weight: wx * wy,
                    });
                }
            }
            v
        }
        other => rigi_scheme(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_are_nodal_and_sum_to_one() {
        for ty in [
            CellType::SEG2,
            CellType::SEG3,
            CellType::TRIA3,
            CellType::TRIA6,
            CellType::QUAD4,
            CellType::QUAD8,
            CellType::TETRA4,
            CellType::HEXA8,
        ] {
            let nodes = reference_nodes(ty);
            assert_eq!(nodes.len(), ty.node_count());
            for (i, &p) in nodes.iter().enumerate() {
                let s = shape(ty, p);
                for (j, &v) in s.n.iter().enumerate() {
                    let want = if i == j { 1. } else { 0. };
                    assert!((v - want).abs() < 1e-14, "{ty:?} N{j} at node {i}: {v}");
                }
            }
            // Derivatives against finite differences at a generic point.
            let p = [0.21, 0.17, 0.13];
            let s = shape(ty, p);
            let sum: f64 = s.n.iter().sum();
            assert!((sum - 1.).abs() < 1e-14);
            let h = 1e-6;
            for k in 0..3 {
                let mut a = p;
                let mut b = p;
                a[k] += h;
                b[k] -= h;
                let (sa, sb) = (shape(ty, a), shape(ty, b));
                for i in 0..s.n.len() {
                    let fd = (sa.n[i] - sb.n[i]) / (2. * h);
                    assert!((fd - s.dn[i][k]).abs() < 1e-7, "{ty:?} dN{i}/dxi{k}");
                }
            }
        }
    }

    #[test]
    fn schemes_integrate_the_reference_measure() {
        for (ty, measure) in [
            (CellType::SEG2, 2.),
            (CellType::TRIA3, 0.5),
            (CellType::TRIA6, 0.5),
            (CellType::QUAD4, 4.),
            (CellType::QUAD8, 4.),
            (CellType::TETRA4, 1. / 6.),
            (CellType::HEXA8, 8.),
        ] {
            let w: f64 = rigi_scheme(ty).iter().map(|g| g.weight).sum();
            assert!((w - measure).abs() < 1e-14, "{ty:?}");
        }
    }
}
