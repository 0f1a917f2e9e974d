//! code_aster's `Q4G` modelisation: the Reissner–Mindlin plates with
//! assumed transverse shear strains, Q4γ on QUAD4 (`MEQ4QU4`: `q4grig`,
//! `q4gbc`, `q4gedg`) and its triangle T3γ on TRIA3 (`MET3TR3`:
//! `t3grig`, `t3gbc`, `t3gedg`), flat facets with six DOFs per node.
//!
//! They share with the other plates ([`crate::dkt`], [`crate::dkq`],
//! [`crate::dst`]) the frame, the membrane, the bending unknowns
//! (w, βx, βy) = (DZ, DRY, −DRX), the section (`dxmate`) and the drilling
//! spring. Their bending, for a homogeneous isotropic section without
//! offset:
//! - curvatures of the linear (bilinear) rotations: `dstbfb` on the
//!   triangle, `dsqbfb` on the quadrangle;
//! - transverse shear strains γ = Bc·u interpolated from their tangential
//!   values at the sides' mid-points (`q4gbc` at each point, `t3gbc` at
//!   the centroid), with `dxmate`'s Dc = 5/6·G·h;
//! - stiffness ∫ (Bfᵀ·Df·Bf + Bcᵀ·Dc·Bc): FPG4 on the quadrangle; on the
//!   triangle everything is constant, area·(…) with the shear at the
//!   centroid (its RIGI family is FPG1);
//! - efforts and strains (`q4gedg`, `t3gedg`): N = Dm·ε, M = Df·κ,
//!   (QX, QY) = Dc·γ, GA = γ/2;
//! - the mass: [`quad_local_mass`] (`q4gmas`; the triangle
//!   uses the DKT's `dktmas`, as `te0031` does).

use crate::dkq::{fpg4, Matrix24, Quad};
use crate::dkt::{
    add_bending, add_btdb, add_coupling, add_ctab, coupling, section_matrices, split_unknowns,
    Efforts, Facet, Generalised, Matrix18, ShellSection,
};
use crate::dst::{bfb_q, linear_curvatures, shear_compliance};
use crate::material::Elastic;
use nalgebra::Matrix3;

/// The shear stiffness Dc = 5/6·G·h·I (`dxmate`'s `dc`).
pub(crate) fn shear_stiffness(material: &Elastic, section: &ShellSection) -> [[f64; 2]; 2] {
    if let Some(l) = &section.layered {
        return l.dc;
    }
    let c = 1. / shear_compliance(material, section)[0][0];
    [[c, 0.], [0., c]]
}

/// `q4gbc`: the assumed shear strains (γxz, γyz) at (ξ, η) on the bending
/// unknowns (w₁ βx₁ βy₁ …).
fn q4gbc(c: &[f64; 25], qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 12]; 2] {
    let [vj11, vj12, vj21, vj22] = *vj;
    let (x5, x6, x7, x8) = (c[0], c[1], c[2], c[3]);
    let (y5, y6, y7, y8) = (c[4], c[5], c[6], c[7]);
    let (peta, meta) = ((1. + eta) / 8., (1. - eta) / 8.);
    let (pqsi, mqsi) = ((1. + qsi) / 8., (1. - qsi) / 8.);
    let bqsi = [
        -2. * meta,
        x5 * meta,
        y5 * meta,
        2. * meta,
        x5 * meta,
        y5 * meta,
        2. * peta,
        -x7 * peta,
        -y7 * peta,
        -2. * peta,
        -x7 * peta,
        -y7 * peta,
    ];
    let beta = [
        -2. * mqsi,
        -x8 * mqsi,
        -y8 * mqsi,
        -2. * pqsi,
        x6 * pqsi,
        y6 * pqsi,
        2. * pqsi,
        x6 * pqsi,
        y6 * pqsi,
        2. * mqsi,
        -x8 * mqsi,
        -y8 * mqsi,
    ];
    [
        std::array::from_fn(|j| vj11 * bqsi[j] + vj12 * beta[j]),
        std::array::from_fn(|j| vj21 * bqsi[j] + vj22 * beta[j]),
    ]
}

/// `t3gbc` at the centroid (ξ = η = 1/3, where `t3grig` and `t3gedg`
/// evaluate it): the triangle's assumed shear strains on (w₁ βx₁ βy₁ …),
/// from `gtria3`'s edge vectors (x₂₁, x₃₂, x₁₃ …) of the facet.
fn t3gbc(c: &[f64; 21]) -> [[f64; 9]; 2] {
    let (qsi, eta) = (1. / 3., 1. / 3.);
    let (x12, y12) = (-c[0], -c[3]);
    let (x23, y23) = (-c[1], -c[4]);
    let (x31, y31) = (-c[2], -c[5]);
    let l1 = (x12 * x12 + y12 * y12).sqrt();
    let l2 = (x23 * x23 + y23 * y23).sqrt();
    let (c2, s2) = (-x23 / l2, -y23 / l2);
    let l3 = (x31 * x31 + y31 * y31).sqrt();
    let (c3, s3) = (-x31 / l3, -y31 / l3);
    let q = 1. / (c2 - s2 * c3 / s3);
    let (s2ss3, c3ss3) = (s2 / s3, c3 / s3);
    let bct1 = [
        [1. - eta, q * eta, -s2ss3 * q * eta],
        [
            -c3ss3 - qsi / (q * s2) + c3ss3 * eta,
            qsi / s2 - c3ss3 * q * eta,
            1. / s3 - qsi / s3 + c3ss3 * s2ss3 * q * eta,
        ],
    ];
    let bct2 = [
        [-1. / l1, 0.5, 0., 1. / l1, 0.5, 0., 0., 0., 0.],
        [
            0.,
            0.,
            0.,
            -1. / l2,
            0.5 * c2,
            0.5 * s2,
            1. / l2,
            0.5 * c2,
            0.5 * s2,
        ],
        [
            1. / l3,
            0.5 * c3,
            0.5 * s3,
            0.,
            0.,
            0.,
            -1. / l3,
            0.5 * c3,
            0.5 * s3,
        ],
    ];
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| bct1[i][k] * bct2[k][j]).sum()))
}

/// Stiffness of a T3γ triangle in the facet's frame (`t3grig` then
/// `dxtloc`). With an offset (a `Q4GG` facet: [`crate::plate::check_offset`]
/// lets no other through) the membrane–bending coupling
/// area·Bmᵀ·Dmf·Bf of `te0409` on its FPG1.
pub fn tria_local_stiffness(facet: &Facet, material: &Elastic, section: &ShellSection) -> Matrix18 {
    let (dm, df) = section_matrices(material, section);
    let dc = shear_stiffness(material, section);
    let bf = linear_curvatures(facet);
    let mut flex = [[0.; 9]; 9];
    add_btdb(&bf, &df, facet.area(), &mut flex);
    add_btdb(&t3gbc(&facet.c), &dc, facet.area(), &mut flex);
    let mut k = crate::dkt::membrane_stiffness(facet, &dm);
    add_bending(&flex, section.drilling, &mut k);
    if let Some(dmf) = coupling(material, section) {
        let mut mefl = [[0.; 9]; 6];
        add_ctab(&facet.bm(), &dmf, &bf, facet.area(), &mut mefl);
        add_coupling(&mefl, &mut k);
    }
    k
}

/// Stiffness of a Q4γ quadrangle in the facet's frame (`q4grig` then
/// `dxqloc`). With an offset (a `Q4GG` facet) the membrane–bending
/// coupling Σ w·Bmᵀ·Dmf·Bf of `te0409` on FPG4.
pub fn quad_local_stiffness(quad: &Quad, material: &Elastic, section: &ShellSection) -> Matrix24 {
    let (dm, df) = section_matrices(material, section);
    let dc = shear_stiffness(material, section);
    let dmf = coupling(material, section);
    let mut flex = [[0.; 12]; 12];
    let mut mefl = [[0.; 12]; 8];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let (det, vj) = quad.jacobian(qsi, eta);
        let w = g.weight * det;
        let bf = bfb_q(qsi, eta, &vj);
        add_btdb(&bf, &df, w, &mut flex);
        add_btdb(&q4gbc(&quad.c, qsi, eta, &vj), &dc, w, &mut flex);
        if let Some(dmf) = &dmf {
            add_ctab(&Quad::bm(qsi, eta, &vj), dmf, &bf, w, &mut mefl);
        }
    }
    let mut k = crate::dkq::membrane_stiffness(quad, &dm);
    add_bending(&flex, section.drilling, &mut k);
    add_coupling(&mefl, &mut k);
    k
}

/// Global stiffness of a Q4G cell (T3γ on 3 nodes, Q4γ on 4) with nodes
/// at `xyz`, node-major DX DY DZ DRX DRY DRZ.
pub fn stiffness(
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
) -> Result<nalgebra::DMatrix<f64>, String> {
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let r = crate::dkt::rotation(&facet);
            let k = r.transpose() * tria_local_stiffness(&facet, material, section) * r;
            Ok(nalgebra::DMatrix::from_column_slice(18, 18, k.as_slice()))
        }
        [a, b, c, d] => {
            crate::dkq::check_drilling(section)?;
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let r = crate::dkq::rotation(&quad);
            let k = r.transpose() * quad_local_stiffness(&quad, material, section) * r;
            Ok(nalgebra::DMatrix::from_column_slice(24, 24, k.as_slice()))
        }
        _ => Err(format!("no Q4G element on a cell of {} nodes", xyz.len())),
    }
}

/// Generalised efforts or strains (`what`) at the reference points
/// `points` (ξ, η) in the facet's frame (`q4gedg`, `t3gedg`: on the
/// triangle every value is constant), with the facet's frame `pgl`.
pub fn generalised_at(
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    points: &[[f64; 2]],
    what: Generalised,
) -> Result<(Matrix3<f64>, Vec<Efforts>), String> {
    let (dm, df) = section_matrices(material, section);
    let dc = shear_stiffness(material, section);
    let shear = |g: [f64; 2]| {
        [
            dc[0][0] * g[0] + dc[0][1] * g[1],
            dc[1][0] * g[0] + dc[1][1] * g[1],
        ]
    };
    match xyz {
        [a, b, c] => {
            let facet = Facet::new(&[*a, *b, *c])?;
            let ul =
                crate::dkt::rotation(&facet) * nalgebra::SVector::<f64, 18>::from_column_slice(u);
            let (um, ub) = split_unknowns(ul.as_slice());
            let bm = facet.bm();
            let bf = linear_curvatures(&facet);
            let bc = t3gbc(&facet.c);
            let eps: [f64; 3] = std::array::from_fn(|i| (0..6).map(|j| bm[i][j] * um[j]).sum());
            let kappa: [f64; 3] = std::array::from_fn(|i| (0..9).map(|j| bf[i][j] * ub[j]).sum());
            let gamma: [f64; 2] = std::array::from_fn(|i| (0..9).map(|j| bc[i][j] * ub[j]).sum());
            let e = what.at_point(material, section, (&dm, &df), eps, kappa, shear(gamma));
            Ok((facet.pgl, vec![e; points.len()]))
        }
        [a, b, c, d] => {
            let quad = Quad::new(&[*a, *b, *c, *d])?;
            let ul =
                crate::dkq::rotation(&quad) * nalgebra::SVector::<f64, 24>::from_column_slice(u);
            let (um, ub) = split_unknowns(ul.as_slice());
            let out = points
                .iter()
                .map(|p| {
                    let (qsi, eta) = (p[0], p[1]);
                    let (_, vj) = quad.jacobian(qsi, eta);
                    let bm = Quad::bm(qsi, eta, &vj);
                    let bf = bfb_q(qsi, eta, &vj);
                    let bc = q4gbc(&quad.c, qsi, eta, &vj);
                    let eps: [f64; 3] =
                        std::array::from_fn(|i| (0..8).map(|j| bm[i][j] * um[j]).sum());
                    let kappa: [f64; 3] =
                        std::array::from_fn(|i| (0..12).map(|j| bf[i][j] * ub[j]).sum());
                    let gamma: [f64; 2] =
                        std::array::from_fn(|i| (0..12).map(|j| bc[i][j] * ub[j]).sum());
                    what.at_point(material, section, (&dm, &df), eps, kappa, shear(gamma))
                })
                .collect();
            Ok((quad.pgl, out))
        }
        _ => Err(format!("no Q4G element on a cell of {} nodes", xyz.len())),
    }
}

/// The mass of a Q4γ quadrangle in its frame (`q4gmas` then `dxqloc`):
/// `dkqmas`'s membrane mass and ρh ∫ w·w with `q4gniw`'s w (the DKQ's w
/// plus `dsqniw`'s shear term with the assumed strains γ = Bc·u), on
/// FPG4, no rotary inertia (`q4gmas` has none, `INER_ROTA` or not); the
/// drilling term as the stiffness'.
pub fn quad_local_mass(quad: &Quad, rho: f64, section: &ShellSection) -> Matrix24 {
    let roe = rho * section.thickness;
    let mut flex = [[0.; 12]; 12];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let (det, vj) = quad.jacobian(qsi, eta);
        let bc = q4gbc(&quad.c, qsi, eta, &vj);
        let w = crate::dst::w_quad(&quad.c, qsi, eta, &bc);
        let wgt = g.weight * det * roe;
        for a in 0..12 {
            for b in 0..12 {
                flex[a][b] += w[a] * w[b] * wgt;
            }
        }
    }
    let mut m = crate::dkq::membrane_mass(quad, roe);
    add_bending(&flex, section.drilling, &mut m);
    m
}

/// Global mass of a Q4γ quadrangle of density `rho` (24×24, node-major)
/// and its mass ρh·A. (Q4G's triangle takes the DKT's mass, `te0031`.)
pub fn quad_mass(
    xyz: &[[f64; 3]; 4],
    rho: f64,
    section: &ShellSection,
) -> Result<(nalgebra::DMatrix<f64>, f64), String> {
    crate::dkq::check_drilling(section)?;
    let quad = Quad::new(xyz)?;
    let r = crate::dkq::rotation(&quad);
    let m = r.transpose() * quad_local_mass(&quad, rho, section) * r;
    Ok((
        nalgebra::DMatrix::from_column_slice(24, 24, m.as_slice()),
        quad.c[20] * rho * section.thickness,
    ))
}

/// The moments' derivatives λ at `points` of a Q4γ quadrangle (`dsxhlt`
/// at the point, `q4glxy`: the nodal rotations' part only), for the shear
/// stresses by ply of a layered section (`q4gsie`).
pub(crate) fn moment_derivatives(
    xyz: &[[f64; 3]; 4],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    points: &[[f64; 2]],
) -> Result<Vec<[f64; 4]>, String> {
    let (_, df) = section_matrices(material, section);
    let quad = Quad::new(xyz)?;
    let ul = crate::dkq::rotation(&quad) * nalgebra::SVector::<f64, 24>::from_column_slice(u);
    let (_, ub) = split_unknowns(ul.as_slice());
    let tb = crate::dst::quad_tb();
    Ok(points
        .iter()
        .map(|p| {
            let (_, vj) = quad.jacobian(p[0], p[1]);
            let hlt2 = crate::laminate::dsxhlt(&df, vj);
            std::array::from_fn(|i| {
                (0..12)
                    .map(|j| (0..6).map(|k| hlt2[i][k] * tb[k][j]).sum::<f64>() * ub[j])
                    .sum()
            })
        })
        .collect())
}
