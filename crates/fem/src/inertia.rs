//! Mass, centre of gravity and inertia tensor (code_aster's `MASS_INER`
//! option and `pemica`, for `POST_ELEM/MASS_INER`).
//!
//! Per cell ([`CellInertia`]): the mass m, the centre g and the inertia
//! about g, as code_aster's elements compute them:
//! - 3D continuum (`te0065`): the cell's `RIGI` family (the stiffness
//!   family, [`Model::stiffness_scheme`]): V = Σ w|J|, g = Σ w|J| x / V,
//!   I = ρ Σ w|J| (x·x 1 − x⊗x) − m (g·g 1 − g⊗g), the products
//!   Ixy = ρ Σ w|J| x y − m gx gy (positive: the tensor's off-diagonal
//!   terms are their opposites). A TETRA4 has one point there: its own
//!   inertia is then zero and the body's is that of its cells' masses at
//!   their centres (code_aster's approximation, reproduced).
//! - D_PLAN, C_PLAN (`te0285`, the `MASS` family, [`shape::mass_scheme`]):
//!   per unit thickness, g = (gx, gy, 0), Ix = ρ∫y² − m gy², Iy = ρ∫x² −
//!   m gx², Iz = Ix + Iy, Ixy = ρ∫xy − m gx gy, Ixz = Iyz = 0.
//! - AXIS (`te0285`): the whole body of revolution about the mesh's y
//!   axis, which the table calls Z: m = 2π ρ ∫ r dA, g = (0, 0, ȳ),
//!   Iz = 2π ρ ∫ r·r² dA, Ix = Iy = 2π ρ ∫ r y² dA + Iz/2 − m ȳ², no
//!   products.
//! - POU_D_E beams (`te0038`, constant section): see [`beam`] (its
//!   products carry the opposite sign of the continuum's, as code_aster's).
//! - Discrete masses of POI1 nodes in the global frame (`te0045`):
//!   see [`discrete`].
//!
//! The sum over a set of cells ([`sum`], `pemica`): M = Σ m, G = Σ m g / M
//! (when |M| > 1e-6), I_G = Σ (I + m (d·d 1 − d⊗d)) with d = g − G (the
//! products Σ (Ixy + m dx dy)), with an origin P (`ORIG_INER`) I_P = I_G +
//! M (p·p 1 − p⊗p), p = G − P. Principal inertias and axes: code_aster's
//! generalised `jacobi` on [[Ixx, −Ixy, −Ixz], [., Iyy, −Iyz], [., ., Izz]]
//! (tolerance 1e-10, dynamic tolerance 1e-2, 12 sweeps), eigenvalues in
//! ascending order (`vpordo`), and the nautical angles (`orien2`, degrees)
//! of the frame whose x is the first eigenvector and whose xy plane holds
//! the second. All six inertias below 1e-12: principal values and angles 0.

use crate::error::FemError;
use crate::mass::{DiscreteMass, MassData};
use crate::material::Hypothesis;
use crate::model::{ElementKind, Model};
use crate::{elga, shape};
use aster_mesh::CellId;
use std::collections::BTreeMap;

/// What one cell contributes (code_aster's `PMASSINE` field): its mass,
/// centre of gravity and inertia about that centre `[Ixx, Iyy, Izz, Ixy,
/// Ixz, Iyz]` (products as ∫ρ x y, not negated).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CellInertia {
    pub mass: f64,
    pub centre: [f64; 3],
    pub inertia: [f64; 6],
}

/// The mass characteristics of a set of cells (`pemica`'s row).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MassInertia {
    pub mass: f64,
    /// Centre of gravity G.
    pub centre: [f64; 3],
    /// Inertia about G: `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`.
    pub inertia: [f64; 6],
    /// Principal inertias about G, ascending.
    pub principal: [f64; 3],
    /// Nautical angles α, β, γ (degrees) of the principal frame.
    pub angles: [f64; 3],
    /// With an origin P: P and the inertia about P.
    pub about: Option<([f64; 3], [f64; 6])>,
}

/// The contribution of every cell of the model that has one (code_aster's
/// option `MASS_INER` on the model's elements): continuum cells with the
/// density of `data` (a continuum cell without one is an error, as
/// code_aster's `rcvalb`), POU_D_E beams ([`beam`]), the discrete masses
/// of POI1 nodes of `data` ([`discrete`]). Boundary cells and springs
/// without mass contribute nothing; shells and the other discrete masses
/// are errors naming the cell.
pub fn cell_inertias(
    model: &Model,
    data: &MassData,
) -> Result<BTreeMap<CellId, CellInertia>, FemError> {
    let mut out = BTreeMap::new();
    let mesh = model.mesh();
    for el in model.elements() {
        match &el.kind {
            ElementKind::Continuum { hypothesis, .. } => {
                let Some(&rho) = data.density.get(&el.cell) else {
                    return Err(FemError::Model(format!(
                        "cell {} has no density (ELAS/RHO): its mass cannot be computed",
                        model.cell_name(el.cell)
                    )));
                };
                let c = if *hypothesis == Hypothesis::Solid3D {
                    let pts = elga::points(mesh, el.cell, &model.stiffness_scheme(el.cell), false);
                    solid(&pts, rho)
                } else {
                    let axis = *hypothesis == Hypothesis::Axisymmetric;
                    let pts = elga::points(
                        mesh,
                        el.cell,
                        &shape::mass_scheme(mesh.cell(el.cell).ty),
                        axis,
                    );
                    plane(&pts, rho, axis)
                };
                out.insert(el.cell, c);
            }
            ElementKind::Beam { section, .. } => {
                let Some(&rho) = data.density.get(&el.cell) else {
                    return Err(FemError::Model(format!(
                        "cell {} has no density (ELAS/RHO): its mass cannot be computed",
                        model.cell_name(el.cell)
                    )));
                };
                let c = crate::element::beam_coords(mesh, el.cell)
                    .and_then(|[a, b]| beam(a, b, rho, section))
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
                out.insert(el.cell, c);
            }
            ElementKind::Boundary | ElementKind::Spring { .. } => {}
            ElementKind::Bar { .. } => {
                return Err(FemError::Model(format!(
                    "cell {} is a BARRE bar: its MASS_INER contribution is not reproduced",
                    model.cell_name(el.cell)
                )))
            }
            ElementKind::Grid { .. } => {
                return Err(FemError::Model(format!(
                    "cell {} is a reinforcement grid (GRILLE_*): its MASS_INER contribution (te0433) is not reproduced",
                    model.cell_name(el.cell)
                )))
            }
            ElementKind::Shell { section, .. } => {
                let Some(&rho) = data.density.get(&el.cell) else {
                    return Err(FemError::Model(format!(
                        "cell {} has no density (ELAS/RHO): its mass cannot be computed",
                        model.cell_name(el.cell)
                    )));
                };
                let c = shell(mesh, el.cell, rho, section.thickness).map_err(|m| {
                    FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                })?;
                out.insert(el.cell, c);
            }
            ElementKind::Coque3d { section, .. } => {
                let Some(&rho) = data.density.get(&el.cell) else {
                    return Err(FemError::Model(format!(
                        "cell {} has no density (ELAS/RHO): its mass cannot be computed",
                        model.cell_name(el.cell)
                    )));
                };
                let (mass, centre, inertia) = crate::element::coque3d_coords(mesh, el.cell)
                    .and_then(|xyz| crate::coque3d::mass_inertia(&xyz, rho, section.thickness))
                    .map_err(|m| {
                        FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))
                    })?;
                out.insert(
                    el.cell,
                    CellInertia {
                        mass,
                        centre,
                        inertia,
                    },
                );
            }
        }
    }
    for d in &data.discrete {
        let Some(c) = discrete(model, d) else {
            return Err(FemError::Model(format!(
                "cell {}: a discrete mass on a segment, in a local frame or on a 2D_DIS_TR node: its MASS_INER is not computed",
                model.cell_name(d.cell())
            )));
        };
        out.insert(d.cell(), c);
    }
    Ok(out)
}

/// `te0045` on a discrete mass of a POI1 node in the global frame
/// (`MECA_DIS_T_N`, `MECA_DIS_TR_N`, `MECA_2D_DIS_T_N`): the mass is the
/// translation block's Σ of terms over the dimension (m for `M_T_D_N`),
/// at the node (z = 0 in 2D); a `DIS_TR` node's inertia is its matrix's
/// rotation block ((4,4), (5,5), (6,6), (4,5), (4,6), (5,6)), the point
/// mass's offset included. `None`: a segment, a local frame, a 2D node
/// with rotation (code_aster's `MECA_2D_DIS_TR_N` writes its inertia in
/// the CDG_Z slot: not reproduced).
pub fn discrete(model: &Model, d: &DiscreteMass) -> Option<CellInertia> {
    let mesh = model.mesh();
    let cell = mesh.cell(d.cell());
    if cell.nodes.len() != 1 {
        return None;
    }
    let mut centre = mesh.coord(cell.nodes[0]);
    if model.dim() == 2 {
        centre[2] = 0.0;
    }
    let (mass, inertia) = match d {
        DiscreteMass::Node { mass, .. } => (*mass, [0.0; 6]),
        DiscreteMass::Matrix {
            upper,
            frame: crate::model::Frame::Global,
            ..
        } => match (model.dim(), upper.len()) {
            (3, 6 | 21) => {
                let m = (upper[..6].iter().sum::<f64>() + upper[1] + upper[3] + upper[4]) / 3.0;
                let i = if upper.len() == 21 {
                    [
                        upper[9], upper[14], upper[20], upper[13], upper[18], upper[19],
                    ]
                } else {
                    [0.0; 6]
                };
                (m, i)
            }
            (2, 3) => ((upper.iter().sum::<f64>() + upper[1]) / 2.0, [0.0; 6]),
            _ => return None,
        },
        DiscreteMass::Matrix { .. } => return None,
    };
    Some(CellInertia {
        mass,
        centre,
        inertia,
    })
}

/// `te0065` on the points of a 3D cell's family.
pub fn solid(points: &[elga::ElgaPoint], rho: f64) -> CellInertia {
    let mut volume = 0.0;
    let mut first = [0.0; 3];
    // ∫ x², y², z², xy, xz, yz.
    let mut second = [0.0; 6];
    for p in points {
        let [x, y, z] = p.x;
        let w = p.weight;
        volume += w;
        for k in 0..3 {
            first[k] += w * p.x[k];
        }
        second[0] += w * x * x;
        second[1] += w * y * y;
        second[2] += w * z * z;
        second[3] += w * x * y;
        second[4] += w * x * z;
        second[5] += w * y * z;
    }
    let g = first.map(|v| v / volume);
    let m = volume * rho;
    let [xx, yy, zz, xy, xz, yz] = second;
    CellInertia {
        mass: m,
        centre: g,
        inertia: [
            (yy + zz) * rho - m * (g[1] * g[1] + g[2] * g[2]),
            (xx + zz) * rho - m * (g[0] * g[0] + g[2] * g[2]),
            (xx + yy) * rho - m * (g[0] * g[0] + g[1] * g[1]),
            xy * rho - m * g[0] * g[1],
            xz * rho - m * g[0] * g[2],
            yz * rho - m * g[1] * g[2],
        ],
    }
}

/// `te0038` on a straight beam of constant section (`POU_D_E`, section
/// type 0) from `a` to `b`: m = ρ A L at the middle, the local tensor
/// diag(ρ (Iy + Iz) L, ρ L (Iy + A L²/12), ρ L (Iz + A L²/12)) taken to
/// the global frame (`utpslg`: Pᵀ J P). Its off-diagonal terms are stored
/// as they come out, the tensor's (−∫ρ x y), where the continuum cells
/// store +∫ρ x y: code_aster's sign, kept.
pub fn beam(
    a: [f64; 3],
    b: [f64; 3],
    rho: f64,
    section: &crate::beam::BeamSection,
) -> Result<CellInertia, String> {
    let (p, len) = crate::beam::frame(a, b)?;
    let l2 = len * len;
    let local = [
        rho * (section.iy + section.iz) * len,
        rho * len * (section.iy + section.area * l2 / 12.0),
        rho * len * (section.iz + section.area * l2 / 12.0),
    ];
    let g = |i: usize, j: usize| (0..3).map(|k| p[k][i] * local[k] * p[k][j]).sum::<f64>();
    Ok(CellInertia {
        mass: rho * section.area * len,
        centre: [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0),
        inertia: [g(0, 0), g(1, 1), g(2, 2), g(1, 0), g(2, 0), g(2, 1)],
    })
}

/// `dxiner` (`te0031`, option `MASS_INER` of the DKT shells) on a TRIA3 or
/// QUAD4 facet of thickness `h`: the area A, first and second moments of
/// the facet integrated on its `MASS` family (FPG3, FPG4: exact on these
/// linear and bilinear cells), m = ρhA at the centroid, the inertia about
/// it in the facet's frame (`dxtpgl`/`dxqpgl`: local x, y in the plane)
/// ρh (∫y² + A h²/12 − A ȳ², ∫x² + A h²/12 − A x̄², ∫(x² + y²) − A(x̄² + ȳ²),
/// products −∫xy + A x̄ȳ) taken to the global frame (`utpslg`: Pᵀ J P);
/// the products stored +∫ρ x y as the continuum cells'.
pub fn shell(
    mesh: &aster_mesh::Mesh,
    cell: CellId,
    rho: f64,
    h: f64,
) -> Result<CellInertia, String> {
    let c = mesh.cell(cell);
    let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let (pgl, points): (nalgebra::Matrix3<f64>, Vec<([f64; 2], f64)>) = match xyz.len() {
        3 => {
            let f = crate::dkt::Facet::new(&[xyz[0], xyz[1], xyz[2]])?;
            let pts = shape::mass_scheme(aster_mesh::CellType::TRIA3)
                .iter()
                .map(|g| ([g.xi[0], g.xi[1]], g.weight))
                .collect();
            (f.pgl, pts)
        }
        4 => {
            let q = crate::dkq::Quad::new(&[xyz[0], xyz[1], xyz[2], xyz[3]])?;
            let pts = shape::mass_scheme(aster_mesh::CellType::QUAD4)
                .iter()
                .map(|g| ([g.xi[0], g.xi[1]], g.weight))
                .collect();
            (q.pgl, pts)
        }
        n => return Err(format!("a DKT facet has 3 or 4 nodes, not {n}")),
    };
    let local = |x: &[f64; 3]| -> [f64; 3] {
        [0, 1, 2].map(|r| (0..3).map(|k| pgl[(r, k)] * x[k]).sum::<f64>())
    };
    let (mut area, mut g, mut l) = (0.0, [0.0; 3], [0.0; 2]);
    let (mut axx, mut ayy, mut axy) = (0.0, 0.0, 0.0);
    for (xi, w) in points {
        let [x, t1, t2] =
            shape::point_and_tangents(mesh, c, &shape::shape(c.ty, [xi[0], xi[1], 0.0]));
        let n = aster_mesh::vec3::cross(t1, t2);
        let sigau = w * aster_mesh::vec3::dot(n, n).sqrt();
        let xl = local(&x);
        area += sigau;
        for k in 0..3 {
            g[k] += x[k] * sigau;
        }
        l[0] += xl[0] * sigau;
        l[1] += xl[1] * sigau;
        axx += xl[0] * xl[0] * sigau;
        ayy += xl[1] * xl[1] * sigau;
        axy += xl[0] * xl[1] * sigau;
    }
    if area.abs() < f64::EPSILON {
        return Err("a shell facet of zero area (code_aster's ELEMENTS_48)".into());
    }
    let g = g.map(|v| v / area);
    let (xl, yl) = (l[0] / area, l[1] / area);
    let roep = rho * h;
    let igxx = ayy + area * h * h / 12. - area * yl * yl;
    let igyy = axx + area * h * h / 12. - area * xl * xl;
    let igxy = axy - area * xl * yl;
    let igzz = axx + ayy - area * (xl * xl + yl * yl);
    let j = nalgebra::Matrix3::new(
        roep * igxx,
        -roep * igxy,
        0.,
        -roep * igxy,
        roep * igyy,
        0.,
        0.,
        0.,
        roep * igzz,
    );
    let gj = pgl.transpose() * j * pgl;
    Ok(CellInertia {
        mass: roep * area,
        centre: g,
        inertia: [
            gj[(0, 0)],
            gj[(1, 1)],
            gj[(2, 2)],
            -gj[(0, 1)],
            -gj[(0, 2)],
            -gj[(1, 2)],
        ],
    })
}

/// `te0285` on the points of a 2D cell's `MASS` family (the weights times
/// the radius when `axis`).
pub fn plane(points: &[elga::ElgaPoint], rho: f64, axis: bool) -> CellInertia {
    let (mut volume, mut sx, mut sy, mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in points {
        let [x, y, _] = p.x;
        let w = p.weight;
        volume += w;
        sx += w * x;
        sy += w * y;
        xx += w * x * x;
        xy += w * x * y;
        yy += w * y * y;
    }
    let two_pi = 2.0 * std::f64::consts::PI;
    if axis {
        let yg = sy / volume;
        let m = two_pi * volume * rho;
        let iz = xx * rho * two_pi;
        let ix = yy * rho * two_pi + iz / 2.0 - m * yg * yg;
        CellInertia {
            mass: m,
            centre: [0.0, 0.0, yg],
            inertia: [ix, ix, iz, 0.0, 0.0, 0.0],
        }
    } else {
        let m = volume * rho;
        let (xg, yg) = (sx / volume, sy / volume);
        let ix = yy * rho - m * yg * yg;
        let iy = xx * rho - m * xg * xg;
        CellInertia {
            mass: m,
            centre: [xg, yg, 0.0],
            inertia: [ix, iy, ix + iy, xy * rho - m * xg * yg, 0.0, 0.0],
        }
    }
}

/// `pemica`: the sum over `cells` (each counted as given), with the
/// inertia about `origin` when given.
pub fn sum<'a>(
    cells: impl IntoIterator<Item = &'a CellInertia> + Clone,
    origin: Option<[f64; 3]>,
) -> MassInertia {
    let mut mass = 0.0;
    let mut g = [0.0; 3];
    for c in cells.clone() {
        mass += c.mass;
        for k in 0..3 {
            g[k] += c.centre[k] * c.mass;
        }
    }
    if mass.abs() > 1e-6 {
        g = g.map(|v| v / mass);
    }
    let mut i = [0.0; 6];
    for c in cells {
        let m = c.mass;
        let [dx, dy, dz] = [0, 1, 2].map(|k| c.centre[k] - g[k]);
        i[0] += c.inertia[0] + m * (dy * dy + dz * dz);
        i[1] += c.inertia[1] + m * (dx * dx + dz * dz);
        i[2] += c.inertia[2] + m * (dx * dx + dy * dy);
        i[3] += c.inertia[3] + m * dx * dy;
        i[4] += c.inertia[4] + m * dx * dz;
        i[5] += c.inertia[5] + m * dy * dz;
    }
    let about = origin.map(|o| {
        let [px, py, pz] = [0, 1, 2].map(|k| g[k] - o[k]);
        (
            o,
            [
                i[0] + mass * (py * py + pz * pz),
                i[1] + mass * (px * px + pz * pz),
                i[2] + mass * (px * px + py * py),
                i[3] + mass * px * py,
                i[4] + mass * px * pz,
                i[5] + mass * py * pz,
            ],
        )
    });
    let (principal, angles) = if i.iter().all(|v| v.abs() < 1e-12) {
        ([0.0; 3], [0.0; 3])
    } else {
        let a = [i[0], -i[3], -i[4], i[1], -i[5], i[2]];
        let (values, vectors) = jacobi3(a);
        let rad = orien2(vectors[0], vectors[1]);
        (values, rad.map(f64::to_degrees))
    };
    MassInertia {
        mass,
        centre: g,
        inertia: i,
        principal,
        angles,
        about,
    }
}

/// code_aster's `jacobi` on a symmetric 3×3 matrix packed by rows
/// ((1,1), (1,2), (1,3), (2,2), (2,3), (3,3)) against the identity, with
/// `pemica`'s settings (nperm 12, tol 1e-10, toldyn 1e-2), sorted by
/// `vpordo` (ascending, type 0): the eigenvalues and the eigenvectors
/// (`vectors[k]` goes with `values[k]`).
pub fn jacobi3(a: [f64; 6]) -> ([f64; 3], [[f64; 3]; 3]) {
    const N: usize = 3;
    let (nperm, tol, toldyn): (i32, f64, f64) = (12, 1e-10, 1e-2);
    let mut ar = a;
    let mut br = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0];
    // 1-based packed index of (i, j), i ≤ j.
    let idx = |i: usize, j: usize| (i - 1) * N - (i - 1) * i / 2 + j - 1;
    let diag = |ar: &[f64; 6], br: &[f64; 6]| [1, 2, 3].map(|i| ar[idx(i, i)] / br[idx(i, i)]);
    let mut valaux = diag(&ar, &br);
    let mut valpro;
    // vecpro[i][j]: component i of vector j.
    let mut vec = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut niter = 0;
    loop {
        niter += 1;
        let eps = toldyn.powi(niter).powi(2);
        for j in 1..N {
            for k in j + 1..=N {
                let (jj, kk, jk) = (idx(j, j), idx(k, k), idx(j, k));
                let eptola = (ar[jk] * ar[jk]).abs();
                let epcoma = (ar[jj] * ar[kk]).abs() * eps;
                let eptolb = (br[jk] * br[jk]).abs();
                let epcomb = (br[jj] * br[kk]).abs() * eps;
                if eptola == 0.0 && eptolb == 0.0 {
                    continue;
                }
                if eptola <= epcoma && eptolb <= epcomb {
                    continue;
                }
                let akk = ar[kk] * br[jk] - br[kk] * ar[jk];
                let ajj = ar[jj] * br[jk] - br[jj] * ar[jk];
                let ab = ar[jj] * br[kk] - ar[kk] * br[jj];
                let verif = (ab * ab + 4.0 * akk * ajj) / 4.0;
                if verif < 0.0 {
                    continue;
                }
                let raci = verif.sqrt();
                let (d1, d2) = (ab / 2.0 + raci, ab / 2.0 - raci);
                let den = if d2.abs() > d1.abs() { d2 } else { d1 };
                let (ca, cg) = if den == 0.0 {
                    (0.0, -ar[jk] / ar[kk])
                } else {
                    (akk / den, -ajj / den)
                };
                // The other rows and columns (i < j, i > k, j < i < k).
                for i in (1..=N).filter(|&i| i != j && i != k) {
                    let ij = if i < j { idx(i, j) } else { idx(j, i) };
                    let ik = if i < k { idx(i, k) } else { idx(k, i) };
                    let (aj, bj, ak, bk) = (ar[ij], br[ij], ar[ik], br[ik]);
                    ar[ij] = aj + cg * ak;
                    br[ij] = bj + cg * bk;
                    ar[ik] = ak + ca * aj;
                    br[ik] = bk + ca * bj;
                }
                let (ak, bk) = (ar[kk], br[kk]);
                ar[kk] = ak + 2.0 * ca * ar[jk] + ca * ca * ar[jj];
                br[kk] = bk + 2.0 * ca * br[jk] + ca * ca * br[jj];
                ar[jj] += 2.0 * cg * ar[jk] + cg * cg * ak;
                br[jj] += 2.0 * cg * br[jk] + cg * cg * bk;
                ar[jk] = 0.0;
                br[jk] = 0.0;
                for row in vec.iter_mut() {
                    let (xj, xk) = (row[j - 1], row[k - 1]);
                    row[j - 1] = xj + cg * xk;
                    row[k - 1] = xk + ca * xj;
                }
            }
        }
        valpro = diag(&ar, &br);
        let mut converged =
            (0..N).all(|i| (valpro[i] - valaux[i]).abs() <= (tol * valaux[i]).abs());
        if converged {
            let eps = tol * tol;
            'off: for j in 1..N {
                for k in j + 1..=N {
                    let (jj, kk, jk) = (idx(j, j), idx(k, k), idx(j, k));
                    if (ar[jk] * ar[jk]).abs() >= eps * (ar[jj] * ar[kk]).abs()
                        || (br[jk] * br[jk]).abs() >= eps * (br[jj] * br[kk]).abs()
                    {
                        converged = false;
                        break 'off;
                    }
                }
            }
        }
        if converged || niter >= nperm {
            break;
        }
        valaux = valpro;
    }
    for i in 1..=N {
        let b = br[idx(i, i)];
        let bb = if b >= 0.0 { b.sqrt() } else { -b.abs().sqrt() };
        for row in vec.iter_mut() {
            row[i - 1] /= bb;
        }
    }
    // vpordo, type 0, ascending: the last of equal values moves first.
    for i in 0..N {
        let mut iperm = i;
        let mut rperm = valpro[i];
        for (j, &v) in valpro.iter().enumerate().skip(i + 1) {
            if v <= rperm {
                iperm = j;
                rperm = v;
            }
        }
        if iperm != i {
            valpro.swap(i, iperm);
            for row in vec.iter_mut() {
                row.swap(i, iperm);
            }
        }
    }
    let vectors = [0, 1, 2].map(|j| [vec[0][j], vec[1][j], vec[2][j]]);
    (valpro, vectors)
}

/// code_aster's `orien2` from the origin: the nautical angles (radians)
/// of the frame whose x axis is along `q` and whose xy plane holds `r`.
pub fn orien2(q: [f64; 3], r: [f64; 3]) -> [f64; 3] {
    // orien1
    let d = (q[0] * q[0] + q[1] * q[1]).sqrt();
    let (alpha, beta) = if d != 0.0 {
        (q[1].atan2(q[0]), -q[2].atan2(d))
    } else if q[2] < 0.0 {
        (0.0, std::f64::consts::FRAC_PI_2)
    } else {
        (0.0, -std::f64::consts::FRAC_PI_2)
    };
    let rot = crate::orthotropic::matrot([alpha, beta, 0.0]);
    let local = [0, 1, 2].map(|i| (0..3).map(|j| rot[i][j] * r[j]).sum::<f64>());
    let gamma = if local[1] == 0.0 && local[2] == 0.0 {
        0.0
    } else {
        local[2].atan2(local[1])
    };
    [alpha, beta, gamma]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    /// A diagonal tensor: its values sorted, the identity's axes.
    #[test]
    fn jacobi_of_a_diagonal_tensor_sorts_the_axes() {
        let (v, e) = jacobi3([3.0, 0.0, 0.0, 1.0, 0.0, 2.0]);
        assert_eq!(v, [1.0, 2.0, 3.0]);
        assert_eq!(e[0], [0.0, 1.0, 0.0]);
        assert_eq!(e[1], [0.0, 0.0, 1.0]);
        // x along y: α = 90°, then z in the plane: γ = 90°.
        let a = orien2(e[0], e[1]).map(f64::to_degrees);
        assert!(
            close(a[0], 90.0, 1e-14) && close(a[1], 0.0, 1e-14) && close(a[2], 90.0, 1e-14),
            "{a:?}"
        );
    }

    /// A tensor rotated by 30° about z: its eigenvalues and α = 30°.
    #[test]
    fn jacobi_finds_a_rotated_frame() {
        let t = 30f64.to_radians();
        let (c, s) = (t.cos(), t.sin());
        // R diag(1, 4, 9) Rᵀ, R = rotation by t about z.
        let (l1, l2, l3) = (1.0, 4.0, 9.0);
        let xx = l1 * c * c + l2 * s * s;
        let yy = l1 * s * s + l2 * c * c;
        let xy = (l1 - l2) * c * s;
        let (v, e) = jacobi3([xx, xy, 0.0, yy, 0.0, l3]);
        for (a, b) in v.iter().zip([l1, l2, l3]) {
            assert!(close(*a, b, 1e-12), "{v:?}");
        }
        let a = orien2(e[0], e[1]).map(f64::to_degrees);
        let alpha = if e[0][0] < 0.0 { a[0] + 180.0 } else { a[0] };
        assert!(close(alpha, 30.0, 1e-10), "{a:?} {e:?}");
    }
}
