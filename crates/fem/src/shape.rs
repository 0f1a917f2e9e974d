//! Reference elements: shape functions, their derivatives and Gauss
//! schemes, with code_aster's node ordering and integration families.
//!
//! Reference cells (code_aster's): segments on [-1, 1]; triangles on
//! (0,0) (1,0) (0,1); quadrangles on [-1, 1]²; hexahedra on [-1, 1]³;
//! tetrahedra, pentahedra and pyramids as in `refcells` (code_aster's
//! `elrfno`). The linear and quadratic 2D cells and HEXA8 have closed forms
//! here; the families added later (QUAD9, TRIA7, TETRA4/10, HEXA20/27,
//! PENTA6/15/18, PYRAM5/13) are written once in `refcells` and
//! differentiated automatically.

use crate::{fpg, refcells};
use aster_mesh::vec3::{cross, dot, sub};
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

/// The physical point x = Σ Nᵢ xᵢ of a cell at the shape values `s` and
/// the tangents ∂x/∂ξ, ∂x/∂η (a segment or face's frame).
pub fn point_and_tangents(
    mesh: &aster_mesh::Mesh,
    c: &aster_mesh::Cell,
    s: &ShapeAt,
) -> [[f64; 3]; 3] {
    let mut out = [[0.0; 3]; 3];
    for (i, &n) in c.nodes.iter().enumerate() {
        let p = mesh.coord(n);
        for k in 0..3 {
            out[0][k] += s.n[i] * p[k];
            out[1][k] += s.dn[i][0] * p[k];
            out[2][k] += s.dn[i][1] * p[k];
        }
    }
    out
}

/// Whether we have an isoparametric formulation for this cell type.
pub fn supported(ty: CellType) -> bool {
    !matches!(ty, CellType::POI1 | CellType::SEG4)
}

/// The volume cells a 3D model has elements for, in code_aster's order.
pub const SOLID_CELLS: [CellType; 10] = [
    CellType::HEXA8,
    CellType::HEXA20,
    CellType::HEXA27,
    CellType::PENTA6,
    CellType::PENTA15,
    CellType::PENTA18,
    CellType::TETRA4,
    CellType::TETRA10,
    CellType::PYRAM5,
    CellType::PYRAM13,
];

/// The surface cells a plane or axisymmetric model has elements for
/// (code_aster has no D_PLAN/AXIS element on TRIA7).
pub const PLANE_CELLS: [CellType; 5] = [
    CellType::TRIA3,
    CellType::TRIA6,
    CellType::QUAD4,
    CellType::QUAD8,
    CellType::QUAD9,
];

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
        CellType::HEXA8 => refcells::HEXA8.to_vec(),
        other => refcells::nodes(other),
    }
}

/// code_aster's reference cells (node coordinates and shape functions) for
/// the mesh operations that place nodes in reference space
/// (`CREA_MAILLAGE/DECOUPE_LAC` on 3D faces).
#[derive(Clone, Copy, Debug, Default)]
pub struct ReferenceCells;

impl aster_mesh::ReferenceCells for ReferenceCells {
    fn nodes(&self, ty: CellType) -> Option<Vec<[f64; 3]>> {
        let v = reference_nodes(ty);
        (supported(ty) && v.len() == ty.node_count()).then_some(v)
    }

    fn shape(&self, ty: CellType, xi: [f64; 3]) -> Option<Vec<f64>> {
        supported(ty).then(|| shape(ty, xi).n)
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
        other => {
            let ad = refcells::shape(other, xi).unwrap_or_default();
            ShapeAt {
                n: ad.iter().map(|a| a.v).collect(),
                dn: ad.iter().map(|a| a.d).collect(),
            }
        }
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
/// SEG2 FPG2, SEG3 FPG3, TRIA3 FPG1, TRIA6 FPG3, TRIA7 FPG6, QUAD4 FPG4
/// (2×2), QUAD8/QUAD9 FPG9 (3×3), TETRA4 FPG1, TETRA10 FPG5, HEXA8 FPG8
/// (2×2×2), HEXA20/HEXA27 FPG27 (3×3×3), PENTA6 FPG6, PENTA15/PENTA18
/// FPG21, PYRAM5 FPG5, PYRAM13 FPG10 (code_aster 17; FPG27 before).
///
/// Point order follows code_aster's `elraga`: QUAD4 counter-clockwise from
/// (-a,-a); QUAD8 corners, then mid-edges, then centre; TRIA6 (1/6,1/6),
/// (2/3,1/6), (1/6,2/3); hexahedra with ξ slowest and ζ fastest;
/// pentahedra ξ slowest, the triangle rule inside.
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
        CellType::QUAD8 | CellType::QUAD9 => {
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
        CellType::TRIA7 => fpg::tria_fpg6(),
        CellType::TETRA4 => vec![gp(0.25, 0.25, 0.25, 1. / 6.)],
        CellType::TETRA10 => fpg::tetra5(),
        CellType::HEXA8 => fpg::hexa(2),
        CellType::HEXA20 | CellType::HEXA27 => fpg::hexa(3),
        CellType::PENTA6 => fpg::penta6(),
        CellType::PENTA15 | CellType::PENTA18 => fpg::penta21(),
        CellType::PYRAM5 => fpg::pyram5(),
        CellType::PYRAM13 => fpg::pyram10(),
        _ => Vec::new(),
    }
}

/// code_aster's `MASS` Gauss family of a continuum cell (mass matrices,
/// kinetic energy): the stiffness family where it integrates N·N exactly
/// on the reference cell, a richer one elsewhere (TRIA3 FPG3, TRIA6 FPG6,
/// QUAD8 FPG9 in every modelisation, TETRA4 FPG4, TETRA10 FPG15).
pub fn mass_scheme(ty: CellType) -> Vec<GaussPoint> {
    match ty {
        CellType::TRIA3 => rigi_scheme(CellType::TRIA6),
        CellType::TRIA6 => fpg::tria_fpg6(),
        CellType::TETRA4 => fpg::tetra4(),
        CellType::TETRA10 => fpg::tetra15(),
        other => rigi_scheme(other),
    }
}

/// The stiffness Gauss family of a continuum element: [`rigi_scheme`],
/// except code_aster's axisymmetric TRIA6 (`MEAXTR6`), integrated with
/// FPG6 where the plane TRIA6 elements use FPG3.
pub fn stiffness_scheme(ty: CellType, hyp: Option<crate::Hypothesis>) -> Vec<GaussPoint> {
    if ty == CellType::TRIA6 && hyp == Some(crate::Hypothesis::Axisymmetric) {
        fpg::tria_fpg6()
    } else {
        rigi_scheme(ty)
    }
}

/// The stiffness family of code_aster's under-integrated elements
/// (`D_PLAN_SI`, `C_PLAN_SI`, `AXIS_SI`, `3D_SI`: `MEDPQS8`, `MECPQS8`,
/// `MEAXQS8`, `MECA_HEXS20`, `MECA_TETRS10`): QUAD8 FPG4 (2×2), HEXA20
/// FPG8 (2×2×2), TETRA10 FPG4, in `elraga` order. `None` for the other
/// cells (code_aster's QUAD4 and HEXA8 `_SI` elements use one point with
/// an hourglass stabilisation, not reproduced). Their mass keeps the full
/// family ([`mass_scheme`]: MASS=FPG9, FPG27, FPG15 as the full elements).
pub fn reduced_scheme(ty: CellType) -> Option<Vec<GaussPoint>> {
    match ty {
        CellType::QUAD8 => Some(rigi_scheme(CellType::QUAD4)),
        CellType::HEXA20 => Some(fpg::hexa(2)),
        CellType::TETRA10 => Some(fpg::tetra4()),
        _ => None,
    }
}

/// Integration scheme for boundary loads on a segment or face: exact for
/// the polynomial degree of the load times the shape functions.
pub fn load_scheme(ty: CellType) -> Vec<GaussPoint> {
    match ty {
        CellType::TRIA6 | CellType::TRIA7 => fpg::tria_fpg6(),
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

/// code_aster's "RIGI" Gauss family of the skin elements (edges of plane
/// models, faces of 3D ones: `MEPLSE2`, `MECA_FACE3`…), where loads given
/// by functions of the coordinates are evaluated: SEG2 FPG2, SEG3 FPG4,
/// TRIA3 FPG3, QUAD4 FPG4, TRIA6/TRIA7 FPG6, QUAD8/QUAD9 FPG9 (`elraga`
/// order: FPG2 (+a, −a), FPG4 (b, −b, c, −c)).
pub fn skin_scheme(ty: CellType) -> Vec<GaussPoint> {
    let gp = |x: f64, w: f64| GaussPoint {
        xi: [x, 0., 0.],
        weight: w,
    };
    match ty {
        CellType::SEG2 => vec![gp(G2, 1.), gp(-G2, 1.)],
        CellType::SEG3 | CellType::SEG4 => {
            let (b, c) = (0.339_981_043_584_856_26, 0.861_136_311_594_052_6);
            let (wb, wc) = (0.652_145_154_862_546_1, 0.347_854_845_137_453_9);
            vec![gp(b, wb), gp(-b, wb), gp(c, wc), gp(-c, wc)]
        }
        CellType::TRIA3 => load_scheme(ty),
        CellType::TRIA6 | CellType::TRIA7 => fpg::tria_fpg6(),
        CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 => rigi_scheme(ty),
        _ => Vec::new(),
    }
}

/// Physical coordinates of the points of a scheme on a cell.
pub fn scheme_points(
    mesh: &aster_mesh::Mesh,
    cell: aster_mesh::CellId,
    scheme: &[GaussPoint],
) -> Vec<[f64; 3]> {
    let c = mesh.cell(cell);
    scheme
        .iter()
        .map(|gp| {
            let s = shape(c.ty, gp.xi);
            let mut x = [0.0; 3];
            for (i, &n) in c.nodes.iter().enumerate() {
                let p = mesh.coord(n);
                for k in 0..3 {
                    x[k] += s.n[i] * p[k];
                }
            }
            x
        })
        .collect()
}

/// Number of corner (vertex) nodes: code_aster numbers them first.
pub fn corner_count(ty: CellType) -> usize {
    match ty {
        CellType::POI1 => 1,
        CellType::SEG2 | CellType::SEG3 | CellType::SEG4 => 2,
        CellType::TRIA3 | CellType::TRIA6 | CellType::TRIA7 => 3,
        CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 => 4,
        CellType::TETRA4 | CellType::TETRA10 => 4,
        CellType::PENTA6 | CellType::PENTA15 | CellType::PENTA18 => 6,
        CellType::HEXA8 | CellType::HEXA20 | CellType::HEXA27 => 8,
        CellType::PYRAM5 | CellType::PYRAM13 => 5,
    }
}

/// Corner nodes of each facet (edges of a 2D cell, faces of a 3D cell),
/// as local indices, before orientation.
fn facet_corner_sets(ty: CellType) -> Vec<Vec<usize>> {
    let v = |s: &[&[usize]]| s.iter().map(|f| f.to_vec()).collect();
    match ty.dim() {
        2 if corner_count(ty) == 3 => v(&[&[0, 1], &[1, 2], &[2, 0]]),
        2 => v(&[&[0, 1], &[1, 2], &[2, 3], &[3, 0]]),
        3 => match corner_count(ty) {
            4 => v(&[&[0, 1, 2], &[0, 1, 3], &[1, 2, 3], &[0, 2, 3]]),
            5 => v(&[
                &[0, 1, 2, 3],
                &[0, 1, 4],
                &[1, 2, 4],
                &[2, 3, 4],
                &[3, 0, 4],
            ]),
            6 => v(&[
                &[0, 1, 2],
                &[3, 4, 5],
                &[0, 1, 4, 3],
                &[1, 2, 5, 4],
                &[2, 0, 3, 5],
            ]),
            _ => v(&[
                &[0, 1, 2, 3],
                &[4, 5, 6, 7],
                &[0, 1, 5, 4],
                &[1, 2, 6, 5],
                &[2, 3, 7, 6],
                &[3, 0, 4, 7],
            ]),
        },
        _ => Vec::new(),
    }
}

/// Facets of a 2D or 3D cell as local node indices, in the node order of
/// the boundary cell they are (corners, then edge midpoints, then the face
/// centre: SEG3, TRIA6/TRIA7, QUAD8/QUAD9), oriented so that the normal of
/// the reference cell points outward (2D: (t_y, −t_x) of the tangent; 3D:
/// ∂x/∂ξ × ∂x/∂η). Mid-nodes are found by position in the reference cell,
/// so the table holds for every family.
pub fn facets(ty: CellType) -> Vec<Vec<usize>> {
    let r = reference_nodes(ty);
    let find = |p: [f64; 3]| {
        r.iter()
            .position(|q| (0..3).all(|k| (q[k] - p[k]).abs() < 1e-12))
    };
    let mut out = Vec::new();
    for corners in facet_corners(ty) {
        let mut f = corners.clone();
        let m = corners.len();
        if m > 1 {
            for k in 0..m {
                let (a, b) = (r[corners[k]], r[corners[(k + 1) % m]]);
                if m == 2 && k == 1 {
                    break;
                }
                if let Some(i) = find(std::array::from_fn(|c| 0.5 * (a[c] + b[c]))) {
                    f.push(i);
                }
            }
            if m > 2 && f.len() > m {
                let pts: Vec<[f64; 3]> = corners.iter().map(|&i| r[i]).collect();
                if let Some(i) = find(mean(&pts)) {
                    f.push(i);
                }
            }
        }
        out.push(f);
    }
    out
}

/// The corner nodes of [`facets`], oriented the same way.
pub fn facet_corners(ty: CellType) -> Vec<Vec<usize>> {
    let r = reference_nodes(ty);
    if r.is_empty() {
        return Vec::new();
    }
    let nc = corner_count(ty);
    let centroid = mean(&r[..nc]);
    let mut out = Vec::new();
    for mut f in facet_corner_sets(ty) {
        let pts: Vec<[f64; 3]> = f.iter().map(|&i| r[i]).collect();
        let fc = mean(&pts);
        let out_dir = sub(fc, centroid);
        let normal = if f.len() == 2 {
            let t = sub(pts[1], pts[0]);
            [t[1], -t[0], 0.]
        } else {
            cross(sub(pts[1], pts[0]), sub(pts[2], pts[0]))
        };
        if dot(normal, out_dir) < 0. {
            if f.len() == 2 {
                f.swap(0, 1);
            } else {
                f[1..].reverse();
            }
        }
        out.push(f);
    }
    out
}

fn mean(p: &[[f64; 3]]) -> [f64; 3] {
    let n = p.len() as f64;
    std::array::from_fn(|k| p.iter().map(|q| q[k]).sum::<f64>() / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [CellType; 18] = [
        CellType::SEG2,
        CellType::SEG3,
        CellType::TRIA3,
        CellType::TRIA6,
        CellType::TRIA7,
        CellType::QUAD4,
        CellType::QUAD8,
        CellType::QUAD9,
        CellType::TETRA4,
        CellType::TETRA10,
        CellType::PENTA6,
        CellType::PENTA15,
        CellType::PENTA18,
        CellType::HEXA8,
        CellType::HEXA20,
        CellType::HEXA27,
        CellType::PYRAM5,
        CellType::PYRAM13,
    ];

    #[test]
    fn shape_functions_are_nodal_and_sum_to_one() {
        for ty in ALL {
            let nodes = reference_nodes(ty);
            assert_eq!(nodes.len(), ty.node_count(), "{ty:?}");
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
            assert!((sum - 1.).abs() < 1e-14, "{ty:?}");
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

    /// Every family reproduces the coordinates (isoparametric completeness):
    /// Σ Nᵢ xᵢ = x and Σ ∂Nᵢ/∂ξ xᵢ = identity.
    #[test]
    fn shape_functions_reproduce_linear_fields() {
        for ty in ALL {
            let nodes = reference_nodes(ty);
            let p = [0.11, 0.23, 0.31];
            let s = shape(ty, p);
            let dim = ty.dim() as usize;
            for c in 0..dim {
                let x: f64 = (0..nodes.len()).map(|i| s.n[i] * nodes[i][c]).sum();
                assert!((x - p[c]).abs() < 1e-13, "{ty:?} x{c}");
                for k in 0..dim {
                    let d: f64 = (0..nodes.len()).map(|i| s.dn[i][k] * nodes[i][c]).sum();
                    let want = if c == k { 1. } else { 0. };
                    assert!((d - want).abs() < 1e-12, "{ty:?} dx{c}/dxi{k}");
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
            (CellType::TRIA7, 0.5),
            (CellType::QUAD4, 4.),
            (CellType::QUAD8, 4.),
            (CellType::QUAD9, 4.),
            (CellType::TETRA4, 1. / 6.),
            (CellType::TETRA10, 1. / 6.),
            (CellType::PENTA6, 1.),
            (CellType::PENTA15, 1.),
            (CellType::PENTA18, 1.),
            (CellType::HEXA8, 8.),
            (CellType::HEXA20, 8.),
            (CellType::HEXA27, 8.),
            (CellType::PYRAM5, 2. / 3.),
            (CellType::PYRAM13, 2. / 3.),
        ] {
            let w: f64 = rigi_scheme(ty).iter().map(|g| g.weight).sum();
            // PYRAM13's FPG27 weights are given to 9 digits by code_aster.
            let tol = if ty == CellType::PYRAM13 { 1e-7 } else { 1e-13 };
            assert!((w - measure).abs() < tol, "{ty:?}: {w}");
        }
    }

    /// Exact integrals of monomials over the reference cells, against the
    /// schemes' stated degrees (the degree a stiffness needs for affine
    /// cells: 2·(order − 1)).
    #[test]
    fn schemes_are_exact_to_their_degree() {
        // ∫ over the simplex of x^a y^b z^c = a! b! c! / (a+b+c+3)!
        fn fact(n: u32) -> f64 {
            (1..=n).map(f64::from).product()
        }
        let tet = |a: u32, b: u32, c: u32| fact(a) * fact(b) * fact(c) / fact(a + b + c + 3);
        let tri = |a: u32, b: u32| fact(a) * fact(b) / fact(a + b + 2);
        let seg = |a: u32| {
            if a % 2 == 1 {
                0.
            } else {
                2. / f64::from(a + 1)
            }
        };
        let integrate = |ty: CellType, f: &dyn Fn([f64; 3]) -> f64| -> f64 {
            rigi_scheme(ty).iter().map(|g| g.weight * f(g.xi)).sum()
        };
        for (ty, deg) in [(CellType::TETRA10, 3u32), (CellType::TETRA4, 1)] {
            for a in 0..=deg {
                for b in 0..=deg - a {
                    for c in 0..=deg - a - b {
                        let got = integrate(ty, &|p| {
                            p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32)
                        });
                        assert!((got - tet(a, b, c)).abs() < 1e-14, "{ty:?} x{a}y{b}z{c}");
                    }
                }
            }
        }
        // Pentahedra: ξ ∈ [-1,1] (Gauss, degree 2n−1) × triangle (η, ζ).
        for (ty, dx, dt) in [(CellType::PENTA6, 3u32, 1u32), (CellType::PENTA15, 5, 5)] {
            for a in 0..=dx {
                for b in 0..=dt {
                    for c in 0..=dt - b {
                        let got = integrate(ty, &|p| {
                            p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32)
                        });
                        let want = seg(a) * tri(b, c);
                        assert!((got - want).abs() < 1e-13, "{ty:?} x{a}y{b}z{c}");
                    }
                }
            }
        }
        for (ty, d) in [(CellType::HEXA8, 3u32), (CellType::HEXA20, 5)] {
            for a in 0..=d {
                for b in 0..=d {
                    for c in 0..=d {
                        let got = integrate(ty, &|p| {
                            p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32)
                        });
                        assert!((got - seg(a) * seg(b) * seg(c)).abs() < 1e-13, "{ty:?}");
                    }
                }
            }
        }
        // Triangle FPG6: degree 4.
        for a in 0..=4u32 {
            for b in 0..=4 - a {
                let got = integrate(CellType::TRIA7, &|p| {
                    p[0].powi(a as i32) * p[1].powi(b as i32)
                });
                assert!((got - tri(a, b)).abs() < 1e-14, "FPG6 x{a}y{b}");
            }
        }
        // Pyramid FPG5 integrates z exactly: ∫ z dV = ∫₀¹ 2(1−z)² z dz = 1/6.
        let got = integrate(CellType::PYRAM5, &|p| p[2]);
        assert!((got - 1. / 6.).abs() < 1e-12, "PYRAM5 z: {got}");
        let got = integrate(CellType::PYRAM13, &|p| p[2]);
        assert!((got - 1. / 6.).abs() < 1e-7, "PYRAM13 z: {got}");
    }

    #[test]
    fn hexa_points_in_code_aster_order() {
        // elraga: ξ slowest, ζ fastest.
        let s = rigi_scheme(CellType::HEXA8);
        assert!(s[0].xi.iter().all(|&v| v < 0.));
        assert!(s[1].xi[2] > 0. && s[1].xi[0] < 0. && s[1].xi[1] < 0.);
        assert!(s[4].xi[0] > 0. && s[4].xi[1] < 0. && s[4].xi[2] < 0.);
    }

    #[test]
    fn facets_carry_their_mid_nodes_and_point_outward() {
        let cases: [(CellType, usize, &[usize]); 8] = [
            (CellType::TRIA6, 3, &[3, 3, 3]),
            (CellType::QUAD9, 4, &[3, 3, 3, 3]),
            (CellType::TETRA10, 4, &[6, 6, 6, 6]),
            (CellType::PENTA15, 5, &[6, 6, 8, 8, 8]),
            (CellType::PENTA18, 5, &[6, 6, 9, 9, 9]),
            (CellType::HEXA20, 6, &[8; 6]),
            (CellType::HEXA27, 6, &[9; 6]),
            (CellType::PYRAM13, 5, &[8, 6, 6, 6, 6]),
        ];
        for (ty, count, sizes) in cases {
            let f = facets(ty);
            assert_eq!(f.len(), count, "{ty:?}");
            let got: Vec<usize> = f.iter().map(|v| v.len()).collect();
            assert_eq!(got, sizes, "{ty:?}");
            // Every node index is distinct within a facet.
            for v in &f {
                let mut s = v.clone();
                s.sort();
                s.dedup();
                assert_eq!(s.len(), v.len(), "{ty:?} {v:?}");
            }
        }
        // HEXA20 bottom face: corners 1 4 3 2 (outward −ζ), then mid-edges.
        assert_eq!(facets(CellType::HEXA20)[0], vec![0, 3, 2, 1, 11, 10, 9, 8]);
        // TRIA6 first edge: nodes 1 2 and its middle 4.
        assert_eq!(facets(CellType::TRIA6)[0], vec![0, 1, 3]);
    }

    /// The reduced families (`_SI`): weights sum to the reference measure
    /// and integrate the monomials of degree ≤ 3 per direction (2-point
    /// Gauss) or the total degree ≤ 2 (TETRA FPG4) exactly.
    #[test]
    fn reduced_families() {
        let q = reduced_scheme(CellType::QUAD8).unwrap();
        assert_eq!(q.len(), 4);
        let h = reduced_scheme(CellType::HEXA20).unwrap();
        assert_eq!(h.len(), 8);
        let t = reduced_scheme(CellType::TETRA10).unwrap();
        assert_eq!(t.len(), 4);
        let sum = |s: &[GaussPoint], f: &dyn Fn([f64; 3]) -> f64| -> f64 {
            s.iter().map(|g| g.weight * f(g.xi)).sum()
        };
        assert!((sum(&q, &|_| 1.0) - 4.0).abs() < 1e-14);
        assert!((sum(&q, &|x| x[0].powi(2) * x[1].powi(2)) - 4.0 / 9.0).abs() < 1e-14);
        assert!(sum(&q, &|x| x[0].powi(3) * x[1]).abs() < 1e-14);
        assert!((sum(&h, &|_| 1.0) - 8.0).abs() < 1e-14);
        assert!((sum(&h, &|x| (x[0] * x[1] * x[2]).powi(2)) - 8.0 / 27.0).abs() < 1e-14);
        assert!((sum(&t, &|_| 1.0) - 1.0 / 6.0).abs() < 1e-14);
        // ∫ x² over the unit tetrahedron = 1/60.
        assert!((sum(&t, &|x| x[0] * x[0]) - 1.0 / 60.0).abs() < 1e-14);
        for ty in [
            CellType::QUAD4,
            CellType::HEXA8,
            CellType::TRIA6,
            CellType::PENTA15,
        ] {
            assert!(reduced_scheme(ty).is_none(), "{ty:?}");
        }
    }
}
