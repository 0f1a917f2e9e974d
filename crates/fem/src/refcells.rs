//! Reference cells added for the quadratic and 3D families: QUAD9, TRIA7,
//! TETRA4/TETRA10, HEXA20, HEXA27, PENTA6/15/18, PYRAM5/13.
//!
//! Node coordinates and shape functions are code_aster's (`elrfno`,
//! `elrfvf`), so that Gauss points given in code_aster's reference
//! coordinates land where code_aster puts them. Note code_aster's unusual
//! choices: the tetrahedron's node 1 is (0,1,0) and node 3 the origin; the
//! pentahedron is extruded along ξ (its triangles live in (η, ζ)); the
//! pyramid's base is the square |ξ|+|η| ≤ 1 with the apex at ζ = 1.

use crate::autodiff::Ad;
use aster_mesh::CellType;

const H: f64 = 0.5;
const T: f64 = 1. / 3.;

/// The reference HEXA8's corners, code_aster's order (also the first eight
/// nodes of HEXA20 and HEXA27).
pub const HEXA8: [[f64; 3]; 8] = [
    [-1., -1., -1.],
    [1., -1., -1.],
    [1., 1., -1.],
    [-1., 1., -1.],
    [-1., -1., 1.],
    [1., -1., 1.],
    [1., 1., 1.],
    [-1., 1., 1.],
];

/// Reference coordinates of the nodes, code_aster's order. Empty for the
/// types this module does not define.
pub fn nodes(ty: CellType) -> Vec<[f64; 3]> {
    match ty {
        CellType::QUAD9 => {
            let mut v = quad8_nodes();
            v.push([0., 0., 0.]);
            v
        }
        CellType::TRIA7 => vec![
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [H, 0., 0.],
            [H, H, 0.],
            [0., H, 0.],
            [T, T, 0.],
        ],
        CellType::TETRA4 => tetra_corners().to_vec(),
        CellType::TETRA10 => {
            let mut v = tetra_corners().to_vec();
            v.extend([
                [0., H, H],
                [0., 0., H],
                [0., H, 0.],
                [H, H, 0.],
                [H, 0., H],
                [H, 0., 0.],
            ]);
            v
        }
        CellType::HEXA20 => hexa20_nodes(),
        CellType::HEXA27 => {
            let mut v = hexa20_nodes();
            v.extend([
                [0., 0., -1.],
                [0., -1., 0.],
                [1., 0., 0.],
                [0., 1., 0.],
                [-1., 0., 0.],
                [0., 0., 1.],
                [0., 0., 0.],
            ]);
            v
        }
        CellType::PENTA6 => penta_corners().to_vec(),
        CellType::PENTA15 => penta15_nodes(),
        CellType::PENTA18 => {
            let mut v = penta15_nodes();
            v.extend([[0., H, H], [0., 0., H], [0., H, 0.]]);
            v
        }
        CellType::PYRAM5 => pyram_corners().to_vec(),
        CellType::PYRAM13 => {
            let mut v = pyram_corners().to_vec();
            v.extend([
                [H, H, 0.],
                [-H, H, 0.],
                [-H, -H, 0.],
                [H, -H, 0.],
                [H, 0., H],
                [0., H, H],
                [-H, 0., H],
                [0., -H, H],
            ]);
            v
        }
        _ => Vec::new(),
    }
}

fn quad8_nodes() -> Vec<[f64; 3]> {
    vec![
        [-1., -1., 0.],
        [1., -1., 0.],
        [1., 1., 0.],
        [-1., 1., 0.],
        [0., -1., 0.],
        [1., 0., 0.],
        [0., 1., 0.],
        [-1., 0., 0.],
    ]
}

fn tetra_corners() -> [[f64; 3]; 4] {
    [[0., 1., 0.], [0., 0., 1.], [0., 0., 0.], [1., 0., 0.]]
}

fn penta_corners() -> [[f64; 3]; 6] {
    [
        [-1., 1., 0.],
        [-1., 0., 1.],
        [-1., 0., 0.],
        [1., 1., 0.],
        [1., 0., 1.],
        [1., 0., 0.],
    ]
}

fn penta15_nodes() -> Vec<[f64; 3]> {
    let mut v = penta_corners().to_vec();
    v.extend([
        [-1., H, H],
        [-1., 0., H],
        [-1., H, 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [0., 0., 0.],
        [1., H, H],
        [1., 0., H],
        [1., H, 0.],
    ]);
    v
}

fn pyram_corners() -> [[f64; 3]; 5] {
    [
        [1., 0., 0.],
        [0., 1., 0.],
        [-1., 0., 0.],
        [0., -1., 0.],
        [0., 0., 1.],
    ]
}

fn hexa20_nodes() -> Vec<[f64; 3]> {
    let mut v = HEXA8.to_vec();
    v.extend([
        [0., -1., -1.],
        [1., 0., -1.],
        [0., 1., -1.],
        [-1., 0., -1.],
        [-1., -1., 0.],
        [1., -1., 0.],
        [1., 1., 0.],
        [-1., 1., 0.],
        [0., -1., 1.],
        [1., 0., 1.],
        [0., 1., 1.],
        [-1., 0., 1.],
    ]);
    v
}

/// 1D quadratic Lagrange function on {-1, 0, 1} of the node at `a`.
fn lagrange2(a: f64, u: Ad) -> Ad {
    if a < 0. {
        u * (u - 1.) * 0.5
    } else if a > 0. {
        u * (u + 1.) * 0.5
    } else {
        (1. + u) * (1. - u)
    }
}

/// Shape functions (with their derivatives) at `xi`; `None` for the types
/// this module does not define.
pub fn shape(ty: CellType, xi: [f64; 3]) -> Option<Vec<Ad>> {
    let [x, y, z] = Ad::point(xi);
    Some(match ty {
        CellType::QUAD9 => nodes(ty)
            .iter()
            .map(|p| lagrange2(p[0], x) * lagrange2(p[1], y))
            .collect(),
        CellType::HEXA27 => nodes(ty)
            .iter()
            .map(|p| lagrange2(p[0], x) * lagrange2(p[1], y) * lagrange2(p[2], z))
            .collect(),
        CellType::TRIA7 => {
            // TRIA6 functions corrected by the bubble b = 27 λ₁λ₂λ₃, which
            // is 1 at the centroid and vanishes on the edges.
            let l = 1. - x - y;
            let b = 27. * x * y * l;
            let mut v = vec![
                l * (2. * l - 1.) + b / 9.,
                x * (2. * x - 1.) + b / 9.,
                y * (2. * y - 1.) + b / 9.,
                4. * x * l - b * (4. / 9.),
                4. * x * y - b * (4. / 9.),
                4. * y * l - b * (4. / 9.),
            ];
            v.push(b);
            v
        }
        CellType::TETRA4 => vec![y, z, 1. - x - y - z, x],
        CellType::TETRA10 => {
            let l = 1. - x - y - z;
            vec![
                (2. * y - 1.) * y,
                (2. * z - 1.) * z,
                (2. * l - 1.) * l,
                (2. * x - 1.) * x,
                4. * z * y,
                4. * z * l,
                4. * l * y,
                4. * x * y,
                4. * x * z,
                4. * x * l,
            ]
        }
        CellType::HEXA20 => nodes(ty)
            .iter()
            .map(|p| {
                let f = |a: f64, u: Ad| {
                    if a == 0. {
                        (1. - u) * (1. + u)
                    } else {
                        1. + a * u
                    }
                };
                let g = f(p[0], x) * f(p[1], y) * f(p[2], z);
                if p.iter().all(|&a| a != 0.) {
                    g * (p[0] * x + p[1] * y + p[2] * z - 2.) * 0.125
                } else {
                    g * 0.25
                }
            })
            .collect(),
        CellType::PENTA6 => {
            let l = 1. - y - z;
            let (m, p) = ((1. - x) * 0.5, (1. + x) * 0.5);
            vec![y * m, z * m, l * m, y * p, z * p, l * p]
        }
        CellType::PENTA15 => {
            let l = 1. - y - z;
            let (m, p) = (1. - x, 1. + x);
            let q = (1. - x) * (1. + x);
            vec![
                y * m * (2. * y - 2. - x) * 0.5,
                z * m * (2. * z - 2. - x) * 0.5,
                l * (x - 1.) * (x + 2. * y + 2. * z) * 0.5,
                y * p * (2. * y - 2. + x) * 0.5,
                z * p * (2. * z - 2. + x) * 0.5,
                l * (-1. * x - 1.) * (2. * y + 2. * z - x) * 0.5,
                2. * y * z * m,
                2. * z * l * m,
                2. * y * l * m,
                y * q,
                z * q,
                l * q,
                2. * y * z * p,
                2. * z * l * p,
                2. * y * l * p,
            ]
        }
        CellType::PENTA18 => {
            // Tensor product of the TRIA6 functions in (η, ζ) with the 1D
            // quadratic ones in ξ.
            let l = 1. - y - z;
            let tri = [
                y * (2. * y - 1.),
                z * (2. * z - 1.),
                l * (2. * l - 1.),
                4. * y * z,
                4. * z * l,
                4. * y * l,
            ];
            let (a, b, c) = (lagrange2(-1., x), lagrange2(0., x), lagrange2(1., x));
            vec![
                tri[0] * a,
                tri[1] * a,
                tri[2] * a,
                tri[0] * c,
                tri[1] * c,
                tri[2] * c,
                tri[3] * a,
                tri[4] * a,
                tri[5] * a,
                tri[0] * b,
                tri[1] * b,
                tri[2] * b,
                tri[3] * c,
                tri[4] * c,
                tri[5] * c,
                tri[3] * b,
                tri[4] * b,
                tri[5] * b,
            ]
        }
        CellType::PYRAM5 | CellType::PYRAM13 => {
            let n = ty.node_count();
            if (xi[2] - 1.).abs() < 1e-6 {
                // The apex: the rational functions are singular there.
                let mut v = vec![Ad::constant(0.); n];
                v[4] = Ad::constant(1.);
                return Some(v);
            }
            let f1 = x + y + z - 1.;
            let f2 = -1. * x + y + z - 1.;
            let f3 = -1. * x - y + z - 1.;
            let f4 = x - y + z - 1.;
            let z1 = 1. - z;
            if ty == CellType::PYRAM5 {
                let z4 = z1 * 4.;
                vec![f2 * f3 / z4, f3 * f4 / z4, f1 * f4 / z4, f1 * f2 / z4, z]
            } else {
                let z2 = z1 * 2.;
                vec![
                    f2 * f3 * (x - 0.5) / z2,
                    f3 * f4 * (y - 0.5) / z2,
                    f4 * f1 * (-1. * x - 0.5) / z2,
                    f1 * f2 * (-1. * y - 0.5) / z2,
                    2. * z * (z - 0.5),
                    -1. * f2 * f3 * f4 / z2,
                    -1. * f3 * f4 * f1 / z2,
                    -1. * f4 * f1 * f2 / z2,
                    -1. * f1 * f2 * f3 / z2,
                    z * f2 * f3 / z1,
                    z * f3 * f4 / z1,
                    z * f4 * f1 / z1,
                    z * f1 * f2 / z1,
                ]
            }
        }
        _ => return None,
    })
}
