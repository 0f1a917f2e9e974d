//! Batoz–Lardeur's discrete shear plates: code_aster's `DST` modelisation,
//! the triangle DST (`MEDSTR3`, TRIA3) and the quadrangle DSQ (`MEDSQU4`,
//! QUAD4), flat facets with six DOFs per node (DX DY DZ DRX DRY DRZ) whose
//! bending allows the transverse shear strain of a Reissner–Mindlin plate.
//!
//! They share with the discrete Kirchhoff facets ([`crate::dkt`],
//! [`crate::dkq`]) the frame `pgl` (`dxtpgl`, `dxqpgl`), the membrane
//! (`dxtbm`, `dxqbm`), the bending unknowns (w, βx, βy) = (DZ, DRY, −DRX),
//! the section (`dxmate`) and the drilling spring (`dxtloc`, `dxqloc`).
//! Their bending follows code_aster's routines, for a homogeneous
//! isotropic section without offset (`EXCENTREMENT`, refused by the
//! runner):
//! - the rotations are linear in the nodal rotations plus a quadratic
//!   term per side, of amplitude α_k (`dstbfb` + `dstbfa`·α, `dsqbfb` +
//!   `dsqbfa`·α); the transverse shear force follows from the moments'
//!   derivatives (`dsxhft`, `dstcis`/`dsqcis`: T = Bcb·u + Bca·α) and the
//!   shear strain is γ = Dc⁻¹·T with `dxmate`'s Dc = 5/6·G·h;
//! - α is eliminated by the discrete shear constraint along each side
//!   (∫ (w,s + β_s − γ_s) ds = 0: `dstcis`'s exact edge terms on the
//!   triangle, `dsqdis` with two Gauss points per side on the
//!   quadrangle), α = A⁻¹·A_w·u;
//! - the stiffness is ∫ (Bfᵀ·Df·Bf + Bcᵀ·Dc⁻¹·Bc) with Bf = Bfb + Bfa·A⁻¹A_w
//!   and Bc = Bcb + Bca·A⁻¹A_w, on FPG3 (DST) or FPG4 (DSQ) (`dstrig`,
//!   `dsqrig`);
//! - the efforts and strains of `EFGE`/`DEGE` at a point (`dstedg`,
//!   `dsqedg`): N = Dm·ε, M = Df·κ, (QX, QY) = T, GA = Dc⁻¹·T/2;
//! - the mass (`dstmas`, `dsqmas`): [`tria_local_mass`], [`quad_local_mass`].
//!
//! As the plate thins, γ → 0 and DST/DSQ tend to DKT/DKQ; for a thick
//! plate they add the shear deflection (a cantilever strip: P·L/(κ·G·A)
//! beside P·L³/(3·E·I)).

use crate::dkq::{fpg4, Matrix24, Quad};
use crate::dkt::{
    add_bending, add_btdb, fpg3, hft2, section_matrices, split_unknowns, Efforts, Facet,
    Generalised, Matrix18, ShellSection,
};
use crate::material::Elastic;
use nalgebra::{Matrix3, Matrix4};

/// The shear compliance Dc⁻¹ (`dxmate`'s `dci`) of a homogeneous
/// isotropic section: 1/(5/6·G·h) on the diagonal; a layered one's
/// ([`crate::laminate`]).
pub(crate) fn shear_compliance(material: &Elastic, section: &ShellSection) -> [[f64; 2]; 2] {
    if let Some(l) = &section.layered {
        return l.dci;
    }
    let g = material.e / 2. / (1. + material.nu);
    let c = 1. / (g * (5. / 6.) * section.thickness);
    [[c, 0.], [0., c]]
}

/// `dstbfb`: the linear part of the triangle's curvatures on (w₁ βx₁ βy₁ …).
fn bfb_t(c: &[f64; 21]) -> [[f64; 9]; 3] {
    let (vj11, vj12, vj21, vj22) = (c[8], c[9], c[10], c[11]);
    let mut b = [[0.; 9]; 3];
    b[0][1] = -vj11 - vj12;
    b[0][4] = vj11;
    b[0][7] = vj12;
    b[1][2] = -vj21 - vj22;
    b[1][5] = vj21;
    b[1][8] = vj22;
    b[2][1] = -vj21 - vj22;
    b[2][2] = -vj11 - vj12;
    b[2][4] = vj21;
    b[2][5] = vj11;
    b[2][7] = vj22;
    b[2][8] = vj12;
    b
}

/// `dstbfb`, shared with Q4G's triangle (`t3grig`).
pub(crate) fn linear_curvatures(facet: &Facet) -> [[f64; 9]; 3] {
    bfb_t(&facet.c)
}

/// `dstbfa`: the curvatures of the side terms α₄ α₅ α₆ at (ξ, η).
fn bfa_t(c: &[f64; 21], qsi: f64, eta: f64) -> [[f64; 3]; 3] {
    let lmq = 1. - 2. * qsi - eta;
    let lme = 1. - qsi - 2. * eta;
    let (vj11, vj12, vj21, vj22) = (c[8], c[9], c[10], c[11]);
    let (c4, c5, c6) = (c[15], c[16], c[17]);
    let (s4, s5, s6) = (c[18], c[19], c[20]);
    [
        [
            4. * (vj11 * lmq - vj12 * qsi) * c4,
            4. * (vj11 * eta + vj12 * qsi) * c5,
            4. * (-vj11 * eta + vj12 * lme) * c6,
        ],
        [
            4. * (vj21 * lmq - vj22 * qsi) * s4,
            4. * (vj21 * eta + vj22 * qsi) * s5,
            4. * (-vj21 * eta + vj22 * lme) * s6,
        ],
        [
            4. * (lmq * (vj21 * c4 + vj11 * s4) - qsi * (vj22 * c4 + vj12 * s4)),
            4. * (eta * (vj21 * c5 + vj11 * s5) + qsi * (vj22 * c5 + vj12 * s5)),
            -4. * (eta * (vj21 * c6 + vj11 * s6) - lme * (vj22 * c6 + vj12 * s6)),
        ],
    ]
}

/// The triangle's discrete shear data (`dstcis`): the shear force
/// operator on α (`bca`, 2×3, constant) and α = `an`·u (3×9).
struct TriaShear {
    bca: [[f64; 3]; 2],
    an: [[f64; 9]; 3],
}

/// `dstcis`'s TA matrix from the sides' cosines and sines.
fn dst_ta(co: &[f64; 3], si: &[f64; 3]) -> [[f64; 3]; 6] {
    let mut ta = [[0.; 3]; 6];
    ta[0][0] = -8. * co[0];
    ta[1][2] = -8. * co[2];
    ta[2][0] = -4. * co[0];
    ta[2][1] = 4. * co[1];
    ta[2][2] = -4. * co[2];
    ta[3][0] = -8. * si[0];
    ta[4][2] = -8. * si[2];
    ta[5][0] = -4. * si[0];
    ta[5][1] = 4. * si[1];
    ta[5][2] = -4. * si[2];
    ta
}

fn dstcis(c: &[f64; 21], df: &[[f64; 3]; 3], dci: &[[f64; 2]; 2]) -> Result<TriaShear, String> {
    let hft2 = hft2(df, [c[8], c[9], c[10], c[11]]);
    let (co, si, l) = (
        [c[15], c[16], c[17]],
        [c[18], c[19], c[20]],
        [c[12], c[13], c[14]],
    );
    let (x, y) = ([c[0], c[1], c[2]], [c[3], c[4], c[5]]);
    let ta = dst_ta(&co, &si);
    let mut bca = [[0.; 3]; 2];
    for i in 0..2 {
        for j in 0..3 {
            bca[i][j] = (0..6).map(|k| hft2[i][k] * ta[k][j]).sum();
        }
    }
    let db: [[f64; 3]; 2] = std::array::from_fn(|i| {
        std::array::from_fn(|j| dci[i][0] * bca[0][j] + dci[i][1] * bca[1][j])
    });
    let mut aa = Matrix3::zeros();
    for i in 0..3 {
        for j in 0..3 {
            aa[(i, j)] = -(x[i] * db[0][j] + y[i] * db[1][j]);
        }
        aa[(i, i)] += 2. / 3. * l[i];
    }
    let aai = aa
        .try_inverse()
        .ok_or("a DST triangle's discrete shear system is singular")?;
    let mut aw = [[0.; 9]; 3];
    aw[0][0] = 1.;
    aw[0][1] = -x[0] / 2.;
    aw[0][2] = -y[0] / 2.;
    aw[0][3] = -1.;
    aw[0][4] = -x[0] / 2.;
    aw[0][5] = -y[0] / 2.;
    aw[1][3] = 1.;
    aw[1][4] = -x[1] / 2.;
    aw[1][5] = -y[1] / 2.;
    aw[1][6] = -1.;
    aw[1][7] = -x[1] / 2.;
    aw[1][8] = -y[1] / 2.;
    aw[2][0] = -1.;
    aw[2][1] = -x[2] / 2.;
    aw[2][2] = -y[2] / 2.;
    aw[2][6] = 1.;
    aw[2][7] = -x[2] / 2.;
    aw[2][8] = -y[2] / 2.;
    let an = std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..3).map(|k| aai[(i, k)] * aw[k][j]).sum())
    });
    Ok(TriaShear { bca, an })
}

/// B + Bα·an: an operator on (w, βx, βy) with the side terms eliminated.
fn condense<const R: usize, const A: usize, const N: usize>(
    b: &[[f64; N]; R],
    ba: &[[f64; A]; R],
    an: &[[f64; N]; A],
) -> [[f64; N]; R] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| b[i][j] + (0..A).map(|k| ba[i][k] * an[k][j]).sum::<f64>())
    })
}

/// The DST triangle's bending and shear operators at (ξ, η): curvatures
/// (3×9) and shear force T (2×9, constant over the facet).
fn tria_operators(
    facet: &Facet,
    shear: &TriaShear,
    qsi: f64,
    eta: f64,
) -> ([[f64; 9]; 3], [[f64; 9]; 2]) {
    let c = &facet.c;
    let bf = condense(&bfb_t(c), &bfa_t(c, qsi, eta), &shear.an);
    let bc = condense(&[[0.; 9]; 2], &shear.bca, &shear.an);
    (bf, bc)
}

/// Stiffness of a DST triangle in the facet's frame (`dstrig` then
/// `dxtloc`), DOFs node-major DX DY DZ DRX DRY DRZ along the local axes.
pub fn tria_local_stiffness(
    facet: &Facet,
    material: &Elastic,
    section: &ShellSection,
) -> Result<Matrix18, String> {
    let (dm, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    let shear = dstcis(&facet.c, &df, &dci)?;
    let mut flex = [[0.; 9]; 9];
    for g in fpg3() {
        let w = g.weight * facet.c[6];
        let (bf, bc) = tria_operators(facet, &shear, g.xi[0], g.xi[1]);
        add_btdb(&bf, &df, w, &mut flex);
        add_btdb(&bc, &dci, w, &mut flex);
    }
    let mut k = crate::dkt::membrane_stiffness(facet, &dm);
    add_bending(&flex, section.drilling, &mut k);
    Ok(k)
}

/// `dsqbfb`: the bilinear rotations' curvatures at (ξ, η), shared with Q4G.
pub(crate) fn bfb_q(qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 12]; 3] {
    let [vj11, vj12, vj21, vj22] = *vj;
    let (peta, meta) = ((1. + eta) / 4., (1. - eta) / 4.);
    let (pqsi, mqsi) = ((1. + qsi) / 4., (1. - qsi) / 4.);
    let mut b = [[0.; 12]; 3];
    b[0][1] = -meta * vj11 - mqsi * vj12;
    b[0][4] = meta * vj11 - pqsi * vj12;
    b[0][7] = peta * vj11 + pqsi * vj12;
    b[0][10] = -peta * vj11 + mqsi * vj12;
    b[1][2] = -meta * vj21 - mqsi * vj22;
    b[1][5] = meta * vj21 - pqsi * vj22;
    b[1][8] = peta * vj21 + pqsi * vj22;
    b[1][11] = -peta * vj21 + mqsi * vj22;
    b[2][1] = b[1][2];
    b[2][2] = b[0][1];
    b[2][4] = b[1][5];
    b[2][5] = b[0][4];
    b[2][7] = b[1][8];
    b[2][8] = b[0][7];
    b[2][10] = b[1][11];
    b[2][11] = b[0][10];
    b
}

/// `dsqbfa`: the curvatures of the side terms α₅ … α₈ at (ξ, η).
fn bfa_q(c: &[f64; 25], qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 4]; 3] {
    let [vj11, vj12, vj21, vj22] = *vj;
    let (co, si) = ([c[12], c[13], c[14], c[15]], [c[16], c[17], c[18], c[19]]);
    let (peta, meta, pqsi, mqsi) = (1. + eta, 1. - eta, 1. + qsi, 1. - qsi);
    let etac = (1. - eta * eta) / 2.;
    let qsic = (1. - qsi * qsi) / 2.;
    let px = [
        -qsi * meta * vj11 - qsic * vj12,
        -eta * pqsi * vj12 + etac * vj11,
        -qsi * peta * vj11 + qsic * vj12,
        -eta * mqsi * vj12 - etac * vj11,
    ];
    let py = [
        -qsi * meta * vj21 - qsic * vj22,
        -eta * pqsi * vj22 + etac * vj21,
        -qsi * peta * vj21 + qsic * vj22,
        -eta * mqsi * vj22 - etac * vj21,
    ];
    [
        std::array::from_fn(|k| px[k] * co[k]),
        std::array::from_fn(|k| py[k] * si[k]),
        std::array::from_fn(|k| py[k] * co[k] + px[k] * si[k]),
    ]
}

/// `dsqcis`'s `tb` (6×12) and `ta` (6×4) at (ξ, η): the second
/// derivatives of the rotations on the nodal unknowns and on α.
fn dsq_t(c: &[f64; 25], qsi: f64, eta: f64) -> ([[f64; 12]; 6], [[f64; 4]; 6]) {
    let (co, si) = ([c[12], c[13], c[14], c[15]], [c[16], c[17], c[18], c[19]]);
    let (peta, meta, pqsi, mqsi) = (1. + eta, 1. - eta, 1. + qsi, 1. - qsi);
    let mut tb = [[0.; 12]; 6];
    for (j, v) in [(1, 0.25), (4, -0.25), (7, 0.25), (10, -0.25)] {
        tb[2][j] = v;
        tb[5][j + 1] = v;
    }
    let mut ta = [[0.; 4]; 6];
    for (r, t) in [(0, &co), (3, &si)] {
        ta[r][0] = -meta * t[0];
        ta[r][2] = -peta * t[2];
        ta[r + 1][1] = -pqsi * t[1];
        ta[r + 1][3] = -mqsi * t[3];
        ta[r + 2][0] = qsi * t[0];
        ta[r + 2][1] = -eta * t[1];
        ta[r + 2][2] = -qsi * t[2];
        ta[r + 2][3] = eta * t[3];
    }
    (tb, ta)
}

/// `dsqcis` (without offset): the shear force operators on the nodal
/// unknowns (`bcb`, 2×12) and on α (`bca`, 2×4) at (ξ, η).
fn dsqcis(
    c: &[f64; 25],
    df: &[[f64; 3]; 3],
    qsi: f64,
    eta: f64,
    vj: &[f64; 4],
) -> ([[f64; 12]; 2], [[f64; 4]; 2]) {
    let hft2 = hft2(df, *vj);
    let (tb, ta) = dsq_t(c, qsi, eta);
    let bcb = std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..6).map(|k| hft2[i][k] * tb[k][j]).sum())
    });
    let bca = std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..6).map(|k| hft2[i][k] * ta[k][j]).sum())
    });
    (bcb, bca)
}

/// `dsqdis`: α = `an`·u (4×12) from the discrete shear constraint of each
/// side, its integrals by the two-point Gauss rule of SE2 (as code_aster).
fn dsqdis(quad: &Quad, df: &[[f64; 3]; 3], dci: &[[f64; 2]; 2]) -> Result<[[f64; 12]; 4], String> {
    let c = &quad.c;
    let (co, si, l) = (
        [c[12], c[13], c[14], c[15]],
        [c[16], c[17], c[18], c[19]],
        [c[8], c[9], c[10], c[11]],
    );
    let (x, y) = ([c[0], c[1], c[2], c[3]], [c[4], c[5], c[6], c[7]]);
    let g = 1. / 3f64.sqrt();
    let se2 = [-g, g];
    let mut aw = [[0.; 12]; 4];
    let mut aa = Matrix4::zeros();
    for ic in 0..4 {
        let mut dib = [[0.; 12]; 2];
        let mut dia = [[0.; 4]; 2];
        for &s in &se2 {
            // code_aster's `dsqdis` reads SE2's weights (1) as the fixed
            // coordinate of the side.
            let (qsi, eta) = match ic {
                0 => (-s, -1.),
                1 => (1., -s),
                2 => (s, 1.),
                _ => (-1., s),
            };
            let (_, vj) = quad.jacobian(qsi, eta);
            let hft2 = hft2(df, vj);
            let (tb, ta) = dsq_t(c, qsi, eta);
            let dt: [[f64; 6]; 2] = std::array::from_fn(|i| {
                std::array::from_fn(|j| dci[i][0] * hft2[0][j] + dci[i][1] * hft2[1][j])
            });
            for i in 0..2 {
                for j in 0..12 {
                    dib[i][j] += (0..6).map(|k| dt[i][k] * tb[k][j]).sum::<f64>();
                }
                for j in 0..4 {
                    dia[i][j] += (0..6).map(|k| dt[i][k] * ta[k][j]).sum::<f64>();
                }
            }
        }
        for j in 0..12 {
            aw[ic][j] = (co[ic] * dib[0][j] + si[ic] * dib[1][j]) * l[ic] / 2.;
        }
        for j in 0..4 {
            aa[(ic, j)] = -(co[ic] * dia[0][j] + si[ic] * dia[1][j]) * l[ic] / 2.;
        }
        aa[(ic, ic)] += 2. / 3. * l[ic];
    }
    let aai = aa
        .try_inverse()
        .ok_or("a DSQ quadrangle's discrete shear system is singular")?;
    for ic in 0..4 {
        let next = (ic + 1) % 4;
        aw[ic][3 * ic] += 1.;
        aw[ic][3 * ic + 1] -= x[ic] / 2.;
        aw[ic][3 * ic + 2] -= y[ic] / 2.;
        aw[ic][3 * next] -= 1.;
        aw[ic][3 * next + 1] -= x[ic] / 2.;
        aw[ic][3 * next + 2] -= y[ic] / 2.;
    }
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..4).map(|k| aai[(i, k)] * aw[k][j]).sum())
    }))
}

/// The Jacobian's determinant and inverse at a point, and the curvature
/// (3×12) and shear force (2×12) operators there.
type QuadOperators = (f64, [f64; 4], [[f64; 12]; 3], [[f64; 12]; 2]);

/// The DSQ quadrangle's curvature (3×12) and shear force (2×12)
/// operators at (ξ, η), and the Jacobian's determinant there.
fn quad_operators(
    quad: &Quad,
    df: &[[f64; 3]; 3],
    an: &[[f64; 12]; 4],
    qsi: f64,
    eta: f64,
) -> QuadOperators {
    let (det, vj) = quad.jacobian(qsi, eta);
    let bf = condense(&bfb_q(qsi, eta, &vj), &bfa_q(&quad.c, qsi, eta, &vj), an);
    let (bcb, bca) = dsqcis(&quad.c, df, qsi, eta, &vj);
    let bc = condense(&bcb, &bca, an);
    (det, vj, bf, bc)
}

/// Stiffness of a DSQ quadrangle in the facet's frame (`dsqrig` then
/// `dxqloc`), DOFs node-major along the local axes.
pub fn quad_local_stiffness(
    quad: &Quad,
    material: &Elastic,
    section: &ShellSection,
) -> Result<Matrix24, String> {
    let (dm, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    let an = dsqdis(quad, &df, &dci)?;
    let mut flex = [[0.; 12]; 12];
    for g in fpg4() {
        let (det, _, bf, bc) = quad_operators(quad, &df, &an, g.xi[0], g.xi[1]);
        let w = g.weight * det;
        add_btdb(&bf, &df, w, &mut flex);
        add_btdb(&bc, &dci, w, &mut flex);
    }
    let mut k = crate::dkq::membrane_stiffness(quad, &dm);
    add_bending(&flex, section.drilling, &mut k);
    Ok(k)
}

/// Global stiffness of a DST triangle (18×18) or a DSQ quadrangle (24×24)
/// with nodes at `xyz`, node-major DX DY DZ DRX DRY DRZ.
pub fn stiffness(
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
) -> Result<nalgebra::DMatrix<f64>, String> {
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let r = crate::dkt::rotation(&facet);
            let k = r.transpose() * tria_local_stiffness(&facet, material, section)? * r;
            Ok(nalgebra::DMatrix::from_column_slice(18, 18, k.as_slice()))
        }
        [a, b, c, d] => {
            crate::dkq::check_drilling(section)?;
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let r = crate::dkq::rotation(&quad);
            let k = r.transpose() * quad_local_stiffness(&quad, material, section)? * r;
            Ok(nalgebra::DMatrix::from_column_slice(24, 24, k.as_slice()))
        }
        _ => Err(format!("no DST element on a cell of {} nodes", xyz.len())),
    }
}

/// Generalised efforts or strains (`what`) at the reference points
/// `points` (ξ, η), in the facet's frame (`dstedg`, `dsqedg`), with the
/// facet's frame `pgl`; `u` the global displacements (6 per node).
pub fn generalised_at(
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    points: &[[f64; 2]],
    what: Generalised,
) -> Result<(Matrix3<f64>, Vec<Efforts>), String> {
    let (dm, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    let apply = |b: &[[f64; 12]], ub: &[f64], n: usize| -> Vec<f64> {
        b.iter()
            .map(|row| (0..n).map(|j| row[j] * ub[j]).sum())
            .collect()
    };
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let ul =
                crate::dkt::rotation(&facet) * nalgebra::SVector::<f64, 18>::from_column_slice(u);
            let (um, ub) = split_unknowns(ul.as_slice());
            let shear = dstcis(&facet.c, &df, &dci)?;
            let bm = facet.bm();
            let eps: [f64; 3] = std::array::from_fn(|i| (0..6).map(|j| bm[i][j] * um[j]).sum());
            let out = points
                .iter()
                .map(|p| {
                    let (bf, bc) = tria_operators(&facet, &shear, p[0], p[1]);
                    let kappa: [f64; 3] =
                        std::array::from_fn(|i| (0..9).map(|j| bf[i][j] * ub[j]).sum());
                    let q: [f64; 2] =
                        std::array::from_fn(|i| (0..9).map(|j| bc[i][j] * ub[j]).sum());
                    what.at_point(material, section, (&dm, &df), eps, kappa, q)
                })
                .collect();
            Ok((facet.pgl, out))
        }
        [a, b, c, d] => {
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let ul =
                crate::dkq::rotation(&quad) * nalgebra::SVector::<f64, 24>::from_column_slice(u);
            let (um, ub) = split_unknowns(ul.as_slice());
            let an = dsqdis(&quad, &df, &dci)?;
            let out = points
                .iter()
                .map(|p| {
                    let (_, vj, bf, bc) = quad_operators(&quad, &df, &an, p[0], p[1]);
                    let bm = Quad::bm(p[0], p[1], &vj);
                    let eps: [f64; 3] =
                        std::array::from_fn(|i| (0..8).map(|j| bm[i][j] * um[j]).sum());
                    let kappa = apply(&bf, &ub, 12);
                    let q = apply(&bc, &ub, 12);
                    what.at_point(
                        material,
                        section,
                        (&dm, &df),
                        eps,
                        [kappa[0], kappa[1], kappa[2]],
                        [q[0], q[1]],
                    )
                })
                .collect();
            Ok((quad.pgl, out))
        }
        _ => Err(format!("no DST element on a cell of {} nodes", xyz.len())),
    }
}

/// `dstniw`: the DST's w on the bending unknowns at (ξ, η), the DKT's
/// cubic w ([`crate::dkt::wkt`]) plus the shear strains' contribution
/// (`dba` = Dc⁻¹·T, 2×9).
fn w_tria(c: &[f64; 21], qsi: f64, eta: f64, dba: &[[f64; 9]; 2]) -> [f64; 9] {
    let (x4, x6, y4, y6) = (c[0], c[2], c[3], c[5]);
    let n = crate::dkt::wkt_n(qsi, eta);
    let mut w = crate::dkt::wkt(c, qsi, eta);
    for j in 0..9 {
        w[j] += (dba[0][j] * x4 + dba[1][j] * y4) * (n[1] + n[4] + n[7])
            - (dba[0][j] * x6 + dba[1][j] * y6) * (n[2] + n[5] + n[8]);
    }
    w
}

/// `dsqniw`/`q4gniw`: the quadrangle's w on the bending unknowns at
/// (ξ, η), the DKQ's w ([`crate::dkq::wkq`]) plus the shear strains'
/// contribution (`dba`, 2×12), code_aster's expression term for term.
pub(crate) fn w_quad(c: &[f64; 25], qsi: f64, eta: f64, dba: &[[f64; 12]; 2]) -> [f64; 12] {
    let (x5, x6, x7, x8) = (c[0], c[1], c[2], c[3]);
    let (y5, y6, y7, y8) = (c[4], c[5], c[6], c[7]);
    let n = crate::dkq::wkq_n(qsi, eta);
    let mut w = crate::dkq::wkq(c, qsi, eta);
    for j in 0..12 {
        let (a, b) = (dba[0][j], dba[1][j]);
        w[j] += (-a * x5 + b * x8) * n[1]
            + (-a * y5 + b * y8) * n[1]
            + (-a * x5 - b * x6) * n[4]
            + (-a * y5 - b * y6) * n[4]
            + (a * x7 - b * x6) * n[7]
            + (a * y7 - b * y6) * n[7]
            + (a * x7 + b * x8) * n[10]
            + (a * y7 + b * y8) * n[10];
    }
    w
}

/// `dstnib`/`dsqnib`: the rotations (βx, βy) on the bending unknowns,
/// linear (`lin`: the nodes' functions) plus the side terms
/// P_k·(c_k, s_k)·α_k with α = `an`·u.
fn rotations<const S: usize, const N: usize>(
    lin: [f64; S],
    p: [f64; S],
    (co, si): ([f64; S], [f64; S]),
    an: &[[f64; N]; S],
) -> ([f64; N], [f64; N]) {
    let mut nfx: [f64; N] = std::array::from_fn(|j| (0..S).map(|k| p[k] * co[k] * an[k][j]).sum());
    let mut nfy: [f64; N] = std::array::from_fn(|j| (0..S).map(|k| p[k] * si[k] * an[k][j]).sum());
    for k in 0..S {
        nfx[3 * k + 1] += lin[k];
        nfy[3 * k + 2] += lin[k];
    }
    (nfx, nfy)
}

/// The mass of a DST triangle in its frame (`dstmas` then `dxtloc`):
/// the linear triangle's membrane mass, ρh ∫ w·w with `dstniw`'s w and —
/// always, `dstmas` does not read `INER_ROTA` — the rotary inertia
/// ρh³/12 ∫ β·β with `dstnib`'s rotations, on FPG3; the drilling term
/// as the stiffness'.
pub fn tria_local_mass(
    facet: &Facet,
    material: &Elastic,
    rho: f64,
    section: &ShellSection,
) -> Result<Matrix18, String> {
    let roe = rho * section.thickness;
    let rof = rho * section.thickness.powi(3) / 12.;
    let (_, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    let shear = dstcis(&facet.c, &df, &dci)?;
    let c = &facet.c;
    let bc = condense(&[[0.; 9]; 2], &shear.bca, &shear.an);
    let dba: [[f64; 9]; 2] = std::array::from_fn(|i| {
        std::array::from_fn(|j| dci[i][0] * bc[0][j] + dci[i][1] * bc[1][j])
    });
    let mut flex = [[0.; 9]; 9];
    for g in fpg3() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let w = w_tria(c, qsi, eta, &dba);
        let l = 1. - qsi - eta;
        let (nfx, nfy) = rotations(
            [l, qsi, eta],
            [4. * qsi * l, 4. * qsi * eta, 4. * eta * l],
            ([c[15], c[16], c[17]], [c[18], c[19], c[20]]),
            &shear.an,
        );
        let wgt = g.weight * c[6];
        for a in 0..9 {
            for b in 0..9 {
                flex[a][b] +=
                    w[a] * w[b] * wgt * roe + (nfx[a] * nfx[b] + nfy[a] * nfy[b]) * wgt * rof;
            }
        }
    }
    let mut m = crate::dkt::membrane_mass(facet, roe);
    add_bending(&flex, section.drilling, &mut m);
    Ok(m)
}

/// The mass of a DSQ quadrangle in its frame (`dsqmas` then `dxqloc`):
/// `dkqmas`'s membrane mass, ρh ∫ w·w with `dsqniw`'s w, and with
/// `INER_ROTA='OUI'` the rotary inertia ρh³/12 ∫ β·β with `dsqnib`'s
/// rotations, on FPG4; the drilling term as the stiffness'. (`dsqniw`
/// computes its second shear row as Dc⁻¹₂₁·T₂ + Dc⁻¹₂₂·T₂: the same as
/// the intended row for the isotropic section's diagonal Dc⁻¹.)
pub fn quad_local_mass(
    quad: &Quad,
    material: &Elastic,
    rho: f64,
    section: &ShellSection,
) -> Result<Matrix24, String> {
    let roe = rho * section.thickness;
    let rof = section.rotary_density(rho);
    let (_, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    let an = dsqdis(quad, &df, &dci)?;
    let c = &quad.c;
    let mut flex = [[0.; 12]; 12];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let (det, vj) = quad.jacobian(qsi, eta);
        let (bcb, bca) = dsqcis(c, &df, qsi, eta, &vj);
        let bn = condense(&bcb, &bca, &an);
        let dba: [[f64; 12]; 2] = [
            std::array::from_fn(|j| dci[0][0] * bn[0][j] + dci[0][1] * bn[1][j]),
            std::array::from_fn(|j| dci[1][0] * bn[1][j] + dci[1][1] * bn[1][j]),
        ];
        let w = w_quad(c, qsi, eta, &dba);
        let (nfx, nfy) = rotations(
            [
                0.25 * (1. - qsi) * (1. - eta),
                0.25 * (1. + qsi) * (1. - eta),
                0.25 * (1. + qsi) * (1. + eta),
                0.25 * (1. - qsi) * (1. + eta),
            ],
            [
                0.5 * (1. - qsi * qsi) * (1. - eta),
                0.5 * (1. - eta * eta) * (1. + qsi),
                0.5 * (1. - qsi * qsi) * (1. + eta),
                0.5 * (1. - eta * eta) * (1. - qsi),
            ],
            ([c[12], c[13], c[14], c[15]], [c[16], c[17], c[18], c[19]]),
            &an,
        );
        let wgt = g.weight * det;
        for a in 0..12 {
            for b in 0..12 {
                flex[a][b] +=
                    w[a] * w[b] * wgt * roe + (nfx[a] * nfx[b] + nfy[a] * nfy[b]) * wgt * rof;
            }
        }
    }
    let mut m = crate::dkq::membrane_mass(quad, roe);
    add_bending(&flex, section.drilling, &mut m);
    Ok(m)
}

/// Global mass of a DST triangle or DSQ quadrangle of density `rho`
/// (node-major DX DY DZ DRX DRY DRZ) and its mass ρh·A (`dialum`'s weight
/// when lumped).
pub fn mass(
    xyz: &[[f64; 3]],
    material: &Elastic,
    rho: f64,
    section: &ShellSection,
) -> Result<(nalgebra::DMatrix<f64>, f64), String> {
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let r = crate::dkt::rotation(&facet);
            let m = r.transpose() * tria_local_mass(&facet, material, rho, section)? * r;
            Ok((
                nalgebra::DMatrix::from_column_slice(18, 18, m.as_slice()),
                facet.area() * rho * section.thickness,
            ))
        }
        [a, b, c, d] => {
            crate::dkq::check_drilling(section)?;
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let r = crate::dkq::rotation(&quad);
            let m = r.transpose() * quad_local_mass(&quad, material, rho, section)? * r;
            Ok((
                nalgebra::DMatrix::from_column_slice(24, 24, m.as_slice()),
                quad.c[20] * rho * section.thickness,
            ))
        }
        _ => Err(format!("no DST element on a cell of {} nodes", xyz.len())),
    }
}

/// `hlt2·ta` on the side unknowns α (`an`·u) and `hlt2·tb` on the nodal
/// unknowns: the 4 derivatives λ of the moments (`dstlxy`, `dsqlxy`).
fn lambda_of<const S: usize, const N: usize>(
    hlt2: &[[f64; 6]; 4],
    ta: &[[f64; S]; 6],
    tb: &[[f64; N]; 6],
    an: &[[f64; N]; S],
    ub: &[f64],
) -> [f64; 4] {
    std::array::from_fn(|i| {
        (0..N)
            .map(|j| {
                let blb: f64 = (0..6).map(|k| hlt2[i][k] * tb[k][j]).sum();
                let bln: f64 = (0..S)
                    .map(|l| (0..6).map(|k| hlt2[i][k] * ta[k][l]).sum::<f64>() * an[l][j])
                    .sum();
                (blb + bln) * ub[j]
            })
            .sum()
    })
}

/// The moments' derivatives λ at `points` (ξ, η) of a DST triangle
/// (`dsxhlt` + `dstlxy`: constant on the cell) or a DSQ quadrangle
/// (`dsxhlt` at the point + `dsqlxy`), with the facet's shear forces
/// (QX, QY) there: what the shear stresses by ply of a layered section
/// add to the d1i·Q of a homogeneous one (`dstsie`, `dsqsie`).
pub(crate) fn moment_derivatives(
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    points: &[[f64; 2]],
) -> Result<Vec<[f64; 4]>, String> {
    let (_, df) = section_matrices(material, section);
    let dci = shear_compliance(material, section);
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let ul =
                crate::dkt::rotation(&facet) * nalgebra::SVector::<f64, 18>::from_column_slice(u);
            let (_, ub) = split_unknowns(ul.as_slice());
            let shear = dstcis(&facet.c, &df, &dci)?;
            let k = &facet.c;
            let hlt2 = crate::laminate::dsxhlt(&df, [k[8], k[9], k[10], k[11]]);
            let (co, si) = ([k[15], k[16], k[17]], [k[18], k[19], k[20]]);
            let ta = dst_ta(&co, &si);
            let lambda = lambda_of(&hlt2, &ta, &[[0.; 9]; 6], &shear.an, &ub);
            Ok(vec![lambda; points.len()])
        }
        [a, b, c, d] => {
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let ul =
                crate::dkq::rotation(&quad) * nalgebra::SVector::<f64, 24>::from_column_slice(u);
            let (_, ub) = split_unknowns(ul.as_slice());
            let an = dsqdis(&quad, &df, &dci)?;
            let k = &quad.c;
            let (co, si) = ([k[12], k[13], k[14], k[15]], [k[16], k[17], k[18], k[19]]);
            Ok(points
                .iter()
                .map(|p| {
                    let (qsi, eta) = (p[0], p[1]);
                    let (_, vj) = quad.jacobian(qsi, eta);
                    let hlt2 = crate::laminate::dsxhlt(&df, vj);
                    let (peta, meta, pqsi, mqsi) = (1. + eta, 1. - eta, 1. + qsi, 1. - qsi);
                    let mut ta = [[0.; 4]; 6];
                    ta[0][0] = -meta * co[0];
                    ta[0][2] = -peta * co[2];
                    ta[1][1] = -pqsi * co[1];
                    ta[1][3] = -mqsi * co[3];
                    ta[2][0] = qsi * co[0];
                    ta[2][1] = -eta * co[1];
                    ta[2][2] = -qsi * co[2];
                    ta[2][3] = eta * co[3];
                    ta[3][0] = -meta * si[0];
                    ta[3][2] = -peta * si[2];
                    ta[4][1] = -pqsi * si[1];
                    ta[4][3] = -mqsi * si[3];
                    ta[5][0] = qsi * si[0];
                    ta[5][1] = -eta * si[1];
                    ta[5][2] = -qsi * si[2];
                    ta[5][3] = eta * si[3];
                    lambda_of(&hlt2, &ta, &quad_tb(), &an, &ub)
                })
                .collect())
        }
        _ => Err(format!("no DST element on a cell of {} nodes", xyz.len())),
    }
}

/// `dsqlxy`'s and `q4glxy`'s `tb`: the nodal rotations' part of the
/// curvature derivatives on a quadrangle.
pub(crate) fn quad_tb() -> [[f64; 12]; 6] {
    let mut tb = [[0.; 12]; 6];
    for (j, v) in [(1, 0.25), (4, -0.25), (7, 0.25), (10, -0.25)] {
        tb[2][j] = v;
        tb[5][j + 1] = v;
    }
    tb
}
