//! Batoz–Tahar's discrete Kirchhoff quadrilateral: code_aster's `DKT`
//! modelisation on QUAD4 (`MEDKQU4`), a flat facet with six DOFs per node
//! (DX DY DZ DRX DRY DRZ). The triangle's companion ([`crate::dkt`]), with
//! the same section, bending unknowns and drilling spring.
//!
//! Following code_aster's routines:
//! - frame `pgl` (`dxqpgl`): x from the middle of side 4–1 to the middle
//!   of side 2–3, z normal to both mid-side lines, y = z × x. A warped
//!   quadrangle is projected on that plane (code_aster only warns when the
//!   fourth node is off the plane of the first three by more than 1e-4 of
//!   |x₁₄|: [`Quad::warping`] gives that ratio);
//! - membrane: the bilinear quadrangle (`dxqbm`) on FPG4;
//! - bending: the DKQ curvature operator (`dkqbf`) on FPG4, on the
//!   unknowns (w, βx, βy) = (DZ, DRY, −DRX) (`dxqloc`, `dkqedg`);
//! - drilling: `COEF_RIGI_DRZ · min(bending rotation diagonal)` on each
//!   DRZ (`dxqloc`; code_aster's alternative drilling formulation, chosen
//!   by a negative `COEF_RIGI_DRZ`, is not reproduced: [`stiffness`]
//!   refuses it);
//! - membrane efforts and moments at the FPG4 points (`dkqedg`,
//!   `EFGE_ELGA`: NXX NYY NXY MXX MYY MXY) in the facet's frame; the
//!   transverse shears (`dkqtxy`) are not computed yet.

use crate::dkt::Generalised;
use crate::dkt::{
    add_bending, add_coupling, add_ctab, bending_dof, coupling, membrane_dof, offset_mass,
    section_matrices, ShellSection,
};
use crate::material::Elastic;
use crate::shape::{rigi_scheme, GaussPoint};
use aster_mesh::CellType;
use nalgebra::{DMatrix, Matrix3, SMatrix, Vector3};

/// 24×24 element matrix, node-major (DX DY DZ DRX DRY DRZ of node 1, …).
pub type Matrix24 = SMatrix<f64, 24, 24>;

/// Generalised efforts at one point: NXX NYY NXY MXX MYY MXY QX QY.
pub type QuadEfforts = [f64; 8];

/// The quadrangular facet: frame, local node coordinates and `gquad4`'s
/// edge data.
#[derive(Clone, Debug)]
pub struct Quad {
    /// Rows are the local axes x, y, z in global coordinates (`pgl`).
    pub pgl: Matrix3<f64>,
    pub(crate) xy: [[f64; 2]; 4],
    pub(crate) c: [f64; 25],
    warping: f64,
}

impl Quad {
    /// Frame and geometry of the quadrangle `xyz` (global coordinates).
    /// Errors on a degenerate quadrangle (zero-length side, first three
    /// nodes aligned, or a non-positive Jacobian at a Gauss point).
    pub fn new(xyz: &[[f64; 3]; 4]) -> Result<Quad, String> {
        let p = |i: usize| Vector3::new(xyz[i][0], xyz[i][1], xyz[i][2]);
        let mid = |a: usize, b: usize| (p(a) + p(b)) / 2.;
        let (i, j, k, l) = (mid(0, 3), mid(2, 1), mid(1, 0), mid(3, 2));
        let size = (p(2) - p(0)).norm().max((p(3) - p(1)).norm());
        let ex = j - i;
        let ez = ex.cross(&(l - k));
        let u = (p(1) - p(0)).cross(&(p(2) - p(0)));
        if !(size > 0. && ex.norm() > 1e-12 * size && ez.norm() > 1e-12 * size * size)
            || u.norm() <= 1e-12 * size * size
        {
            return Err(format!(
                "a DKT quadrangle is degenerate (zero area): nodes {xyz:?}"
            ));
        }
        let ex = ex.normalize();
        let ez = ez.normalize();
        let ey = ez.cross(&ex).normalize();
        let pgl = Matrix3::from_rows(&[ex.transpose(), ey.transpose(), ez.transpose()]);
        let x14 = p(3) - p(0);
        let warping = (u.dot(&x14) / u.norm() / x14.norm()).abs();
        let mut xy = [[0.; 2]; 4];
        for n in 0..4 {
            let d = p(n) - p(0);
            xy[n] = [ex.dot(&d), ey.dot(&d)];
        }
        let quad = Quad {
            pgl,
            xy,
            c: gquad4(&xy),
            warping,
        };
        for g in fpg4() {
            if quad.jacobian(g.xi[0], g.xi[1]).0 <= 0. {
                return Err(format!(
                    "a DKT quadrangle has a non-positive Jacobian (nodes not in order, or a re-entrant corner): nodes {xyz:?}"
                ));
            }
        }
        Ok(quad)
    }

    /// Distance of node 4 to the plane of nodes 1–3 over |x₁₄|
    /// (`dxqpgl`'s warping measure; code_aster warns above 1e-4).
    pub fn warping(&self) -> f64 {
        self.warping
    }

    /// `jquad4`: Jacobian determinant and inverse (vj11 vj12 vj21 vj22) at
    /// (ξ, η).
    pub(crate) fn jacobian(&self, qsi: f64, eta: f64) -> (f64, [f64; 4]) {
        let xy = &self.xy;
        let d = |a: usize, b: usize, k: usize| xy[a][k] - xy[b][k];
        let (x21, x32, x43, x14) = (d(1, 0, 0), d(2, 1, 0), d(3, 2, 0), d(0, 3, 0));
        let (y21, y32, y43, y14) = (d(1, 0, 1), d(2, 1, 1), d(3, 2, 1), d(0, 3, 1));
        let j11 = (x21 - x43 - eta * (x43 + x21)) / 4.;
        let j12 = (y21 - y43 - eta * (y43 + y21)) / 4.;
        let j21 = (x32 - x14 + qsi * (x32 + x14)) / 4.;
        let j22 = (y32 - y14 + qsi * (y32 + y14)) / 4.;
        let det = j11 * j22 - j12 * j21;
        (det, [j22 / det, -j12 / det, -j21 / det, j11 / det])
    }

    /// Membrane strain operator (`dxqbm`) on (u₁ v₁ … u₄ v₄).
    pub(crate) fn bm(qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 8]; 3] {
        let [vj11, vj12, vj21, vj22] = *vj;
        let peta = (1. + eta) / 4.;
        let meta = (1. - eta) / 4.;
        let pqsi = (1. + qsi) / 4.;
        let mqsi = (1. - qsi) / 4.;
        let dx = [
            -meta * vj11 - mqsi * vj12,
            meta * vj11 - pqsi * vj12,
            peta * vj11 + pqsi * vj12,
            -peta * vj11 + mqsi * vj12,
        ];
        let dy = [
            -meta * vj21 - mqsi * vj22,
            meta * vj21 - pqsi * vj22,
            peta * vj21 + pqsi * vj22,
            -peta * vj21 + mqsi * vj22,
        ];
        let mut bm = [[0.; 8]; 3];
        for n in 0..4 {
            bm[0][2 * n] = dx[n];
            bm[1][2 * n + 1] = dy[n];
            bm[2][2 * n] = dy[n];
            bm[2][2 * n + 1] = dx[n];
        }
        bm
    }

    /// Bending curvature operator (`dkqbf`) at (ξ, η) on (w₁ βx₁ βy₁ …).
    fn bf(&self, qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 12]; 3] {
        let c = &self.c;
        let [vj11, vj12, vj21, vj22] = *vj;
        let (c5, c6, c7, c8) = (c[12], c[13], c[14], c[15]);
        let (s5, s6, s7, s8) = (c[16], c[17], c[18], c[19]);
        let (l5, l6, l7, l8) = (c[8], c[9], c[10], c[11]);
        let peta = (1. + eta) / 4.;
        let meta = (1. - eta) / 4.;
        let pqsi = (1. + qsi) / 4.;
        let mqsi = (1. - qsi) / 4.;
        let etac = (1. - eta * eta) / 8.;
        let qsic = (1. - qsi * qsi) / 8.;
        let cu = |c: f64| 3. * c * c;
        let cs = |c: f64, s: f64| 3. * c * s;
        let (cu5, cu6, cu7, cu8) = (cu(c5), cu(c6), cu(c7), cu(c8));
        let (su5, su6, su7, su8) = (cu(s5), cu(s6), cu(s7), cu(s8));
        let (cs5, cs6, cs7, cs8) = (cs(c5, s5), cs(c6, s6), cs(c7, s7), cs(c8, s8));
        let (cl5, cl6, cl7, cl8) = (6. * c5 / l5, 6. * c6 / l6, 6. * c7 / l7, 6. * c8 / l8);
        let (sl5, sl6, sl7, sl8) = (6. * s5 / l5, 6. * s6 / l6, 6. * s7 / l7, 6. * s8 / l8);
        let bxq = [
            -qsi * meta * cl5 + etac * cl8,
            -meta + qsi * meta * cu5 + etac * cu8,
            qsi * meta * cs5 + etac * cs8,
            qsi * meta * cl5 + etac * cl6,
            meta + qsi * meta * cu5 - etac * cu6,
            qsi * meta * cs5 - etac * cs6,
            -qsi * peta * cl7 - etac * cl6,
            peta + qsi * peta * cu7 - etac * cu6,
            qsi * peta * cs7 - etac * cs6,
            qsi * peta * cl7 - etac * cl8,
            -peta + qsi * peta * cu7 + etac * cu8,
            qsi * peta * cs7 + etac * cs8,
        ];
        let byq = [
            -qsi * meta * sl5 + etac * sl8,
            bxq[2],
            -meta + qsi * meta * su5 + etac * su8,
            qsi * meta * sl5 + etac * sl6,
            bxq[5],
            meta + qsi * meta * su5 - etac * su6,
            -qsi * peta * sl7 - etac * sl6,
            bxq[8],
            peta + qsi * peta * su7 - etac * su6,
            qsi * peta * sl7 - etac * sl8,
            bxq[11],
            -peta + qsi * peta * su7 + etac * su8,
        ];
        let bxe = [
            eta * mqsi * cl8 - qsic * cl5,
            -mqsi + eta * mqsi * cu8 + qsic * cu5,
            eta * mqsi * cs8 + qsic * cs5,
            -eta * pqsi * cl6 + qsic * cl5,
            -pqsi + eta * pqsi * cu6 + qsic * cu5,
            eta * pqsi * cs6 + qsic * cs5,
            eta * pqsi * cl6 + qsic * cl7,
            pqsi + eta * pqsi * cu6 - qsic * cu7,
            eta * pqsi * cs6 - qsic * cs7,
            -eta * mqsi * cl8 - qsic * cl7,
            mqsi + eta * mqsi * cu8 - qsic * cu7,
            eta * mqsi * cs8 - qsic * cs7,
        ];
        let bye = [
            eta * mqsi * sl8 - qsic * sl5,
            bxe[2],
            -mqsi + eta * mqsi * su8 + qsic * su5,
            -eta * pqsi * sl6 + qsic * sl5,
            bxe[5],
            -pqsi + eta * pqsi * su6 + qsic * su5,
            eta * pqsi * sl6 + qsic * sl7,
            bxe[8],
            pqsi + eta * pqsi * su6 - qsic * su7,
            -eta * mqsi * sl8 - qsic * sl7,
            bxe[11],
            mqsi + eta * mqsi * su8 - qsic * su7,
        ];
        let mut bf = [[0.; 12]; 3];
        for i in 0..12 {
            bf[0][i] = vj11 * bxq[i] + vj12 * bxe[i];
            bf[1][i] = vj21 * byq[i] + vj22 * bye[i];
            bf[2][i] = vj11 * byq[i] + vj12 * bye[i] + vj21 * bxq[i] + vj22 * bxe[i];
        }
        bf
    }

    /// Transverse shear operator at (ξ, η) (`dsxhft` then `dkqtxy`):
    /// (QX, QY) from the bending unknowns (w βx βy per node), the moments'
    /// derivatives of the DKQ field.
    fn shear(&self, df: &[[f64; 3]; 3], qsi: f64, eta: f64, vj: &[f64; 4]) -> [[f64; 12]; 2] {
        let hft2 = crate::dkt::hft2(df, *vj);
        let c = &self.c;
        let (peta, meta, pqsi, mqsi) = (1. + eta, 1. - eta, 1. + qsi, 1. - qsi);
        // codi = (c4 c5 c6 c7 s4 s5 s6 s7) = c[12..20], lcot = c[8..12].
        let mut cl = [0.; 4];
        let mut sl = [0.; 4];
        let mut cs = [0.; 4];
        let mut cu = [0.; 4];
        let mut su = [0.; 4];
        for i in 0..4 {
            let (co, si, l) = (c[12 + i], c[16 + i], c[8 + i]);
            cl[i] = 1.5 * co / l;
            sl[i] = 1.5 * si / l;
            cs[i] = 0.75 * co * si;
            cu[i] = 0.75 * co * co;
            su[i] = 0.75 * si * si;
        }
        let row = |l: &[f64; 4], u: &[f64; 4], v: &[f64; 4]| -> [[f64; 12]; 3] {
            [
                [
                    -meta * l[0],
                    meta * u[0],
                    meta * v[0],
                    meta * l[0],
                    meta * u[0],
                    meta * v[0],
                    -peta * l[2],
                    peta * u[2],
                    peta * v[2],
                    peta * l[2],
                    peta * u[2],
                    peta * v[2],
                ],
                [
                    mqsi * l[3],
                    mqsi * u[3],
                    mqsi * v[3],
                    -pqsi * l[1],
                    pqsi * u[1],
                    pqsi * v[1],
                    pqsi * l[1],
                    pqsi * u[1],
                    pqsi * v[1],
                    -mqsi * l[3],
                    mqsi * u[3],
                    mqsi * v[3],
                ],
                [0.; 12],
            ]
        };
        // Rows 1, 2 (x) and 4, 5 (y) of `tkq`; rows 3 and 6 below.
        let rx = row(&cl, &cu, &cs);
        let ry = row(&sl, &cs, &su);
        let r3 = [
            qsi * cl[0] - eta * cl[3],
            -qsi * cu[0] - eta * cu[3] + 0.25,
            -qsi * cs[0] - eta * cs[3],
            -qsi * cl[0] - eta * cl[1],
            -qsi * cu[0] + eta * cu[1] - 0.25,
            -qsi * cs[0] + eta * cs[1],
            -qsi * cl[2] + eta * cl[1],
            qsi * cu[2] + eta * cu[1] + 0.25,
            qsi * cs[2] + eta * cs[1],
            qsi * cl[2] + eta * cl[3],
            qsi * cu[2] - eta * cu[3] - 0.25,
            qsi * cs[2] - eta * cs[3],
        ];
        let r6 = [
            qsi * sl[0] - eta * sl[3],
            -qsi * cs[0] - eta * cs[3],
            -qsi * su[0] - eta * su[3] + 0.25,
            -qsi * sl[0] - eta * sl[1],
            -qsi * cs[0] + eta * cs[1],
            -qsi * su[0] + eta * su[1] - 0.25,
            -qsi * sl[2] + eta * sl[1],
            qsi * cs[2] + eta * cs[1],
            qsi * su[2] + eta * su[1] + 0.25,
            qsi * sl[2] + eta * sl[3],
            qsi * cs[2] - eta * cs[3],
            qsi * su[2] - eta * su[3] - 0.25,
        ];
        let tkq = [rx[0], rx[1], r3, ry[0], ry[1], r6];
        let mut bc = [[0.; 12]; 2];
        for i in 0..2 {
            for j in 0..12 {
                for (k, t) in tkq.iter().enumerate() {
                    bc[i][j] += hft2[i][k] * t[j];
                }
            }
        }
        bc
    }
}

/// `gquad4`: edge vectors, lengths, cosines and sines, and areas, from the
/// local (x, y) of the nodes (0-based).
fn gquad4(xy: &[[f64; 2]; 4]) -> [f64; 25] {
    let d = |a: usize, b: usize, k: usize| xy[a][k] - xy[b][k];
    let (x21, x32, x43, x14) = (d(1, 0, 0), d(2, 1, 0), d(3, 2, 0), d(0, 3, 0));
    let (y21, y32, y43, y14) = (d(1, 0, 1), d(2, 1, 1), d(3, 2, 1), d(0, 3, 1));
    let (x31, x42, y31, y42) = (d(2, 0, 0), d(3, 1, 0), d(2, 0, 1), d(3, 1, 1));
    let l = [
        (x21 * x21 + y21 * y21).sqrt(),
        (x32 * x32 + y32 * y32).sqrt(),
        (x43 * x43 + y43 * y43).sqrt(),
        (x14 * x14 + y14 * y14).sqrt(),
    ];
    [
        x21,
        x32,
        x43,
        x14,
        y21,
        y32,
        y43,
        y14,
        l[0],
        l[1],
        l[2],
        l[3],
        x21 / l[0],
        x32 / l[1],
        x43 / l[2],
        x14 / l[3],
        y21 / l[0],
        y32 / l[1],
        y43 / l[2],
        y14 / l[3],
        (x31 * y42 - y31 * x42) / 2.,
        (-x21 * y14 + y21 * x14) / 2.,
        (-x32 * y21 + y32 * x21) / 2.,
        (-x43 * y32 + y43 * x32) / 2.,
        (-x14 * y43 + y14 * x43) / 2.,
    ]
}

/// The (ξ, η) of the RIGI family's points (FPG4), where the efforts are
/// computed on a STAT_NON_LINE result.
pub(crate) fn rigi_points() -> Vec<[f64; 2]> {
    fpg4().iter().map(|g| [g.xi[0], g.xi[1]]).collect()
}

/// FPG4, code_aster's `RIGI` family of `MEDKQU4`.
pub(crate) fn fpg4() -> Vec<GaussPoint> {
    rigi_scheme(CellType::QUAD4)
}

/// Stiffness in the facet's frame (`dkqrig` then `dxqloc`), DOFs
/// node-major DX DY DZ DRX DRY DRZ along the local axes.
pub fn local_stiffness(quad: &Quad, material: &Elastic, section: &ShellSection) -> Matrix24 {
    let (dm, df) = section_matrices(material, section);
    let dmf = coupling(material, section);
    let mut flex = [[0.; 12]; 12];
    let mut mefl = [[0.; 12]; 8];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let (det, vj) = quad.jacobian(qsi, eta);
        let w = g.weight * det;
        let bf = quad.bf(qsi, eta, &vj);
        for a in 0..12 {
            for b in 0..12 {
                let mut v = 0.;
                for i in 0..3 {
                    for j in 0..3 {
                        v += bf[i][a] * df[i][j] * bf[j][b];
                    }
                }
                flex[a][b] += w * v;
            }
        }
        // `dkqrig`: Bmᵀ·Dmf·Bf at each point (`utctab`).
        if let Some(dmf) = &dmf {
            let bm = Quad::bm(qsi, eta, &vj);
            add_ctab(&bm, dmf, &bf, w, &mut mefl);
        }
    }
    let mut k = membrane_stiffness(quad, &dm);
    add_bending(&flex, section.drilling, &mut k);
    add_coupling(&mefl, &mut k);
    k
}

/// The bilinear membrane (`dxqbm` on FPG4, Σ w·det·Bmᵀ·Dm·Bm) on the
/// in-plane translations of a local 24×24 matrix: the membrane part of
/// every plate quadrangle (DKQ, DSQ, Q4G).
pub(crate) fn membrane_stiffness(quad: &Quad, dm: &[[f64; 3]; 3]) -> Matrix24 {
    let mut memb = [[0.; 8]; 8];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let (det, vj) = quad.jacobian(qsi, eta);
        let bm = Quad::bm(qsi, eta, &vj);
        crate::dkt::add_btdb(&bm, dm, g.weight * det, &mut memb);
    }
    let mut k = Matrix24::zeros();
    for a in 0..8 {
        for b in 0..8 {
            k[(membrane_dof(a), membrane_dof(b))] += memb[a][b];
        }
    }
    k
}

/// The 24×24 global→local rotation: `pgl` on every translation and
/// rotation triple.
pub fn rotation(quad: &Quad) -> Matrix24 {
    let mut r = Matrix24::zeros();
    for b in 0..8 {
        r.fixed_view_mut::<3, 3>(3 * b, 3 * b).copy_from(&quad.pgl);
    }
    r
}

/// code_aster's alternative drilling formulation of the DKQ (a negative
/// `COEF_RIGI_DRZ`) is not reproduced: an error.
pub(crate) fn check_drilling(section: &ShellSection) -> Result<(), String> {
    if section.drilling < 0. {
        return Err(format!(
            "COEF_RIGI_DRZ = {} < 0 selects code_aster's alternative drilling formulation for DKQ, which is not reproduced",
            section.drilling
        ));
    }
    Ok(())
}

/// Global stiffness of a DKQ quadrangle with nodes at `xyz` (24×24,
/// node-major DX DY DZ DRX DRY DRZ).
pub fn stiffness(
    xyz: &[[f64; 3]; 4],
    material: &Elastic,
    section: &ShellSection,
) -> Result<DMatrix<f64>, String> {
    check_drilling(section)?;
    let quad = Quad::new(xyz)?;
    let r = rotation(&quad);
    let k = r.transpose() * local_stiffness(&quad, material, section) * r;
    Ok(DMatrix::from_column_slice(24, 24, k.as_slice()))
}

/// `dkqniw`: the DKQ's interpolation of w on the bending unknowns
/// (w₁ βx₁ βy₁ …) at (ξ, η), from `gquad4`'s edge vectors.
pub(crate) fn wkq(c: &[f64; 25], qsi: f64, eta: f64) -> [f64; 12] {
    let (x5, x6, x7, x8) = (c[0], c[1], c[2], c[3]);
    let (y5, y6, y7, y8) = (c[4], c[5], c[6], c[7]);
    let n = wkq_n(qsi, eta);
    [
        n[0],
        (-x5 * n[1] + x8 * n[2]) / 2.,
        (-y5 * n[1] + y8 * n[2]) / 2.,
        n[3],
        (-x5 * n[4] - x6 * n[5]) / 2.,
        (-y5 * n[4] - y6 * n[5]) / 2.,
        n[6],
        (x7 * n[7] - x6 * n[8]) / 2.,
        (y7 * n[7] - y6 * n[8]) / 2.,
        n[9],
        (x7 * n[10] + x8 * n[11]) / 2.,
        (y7 * n[10] + y8 * n[11]) / 2.,
    ]
}

/// `dkqniw`'s twelve functions N₁ … N₁₂ at (ξ, η) (also `dsqniw`'s and
/// `q4gniw`'s).
pub(crate) fn wkq_n(qsi: f64, eta: f64) -> [f64; 12] {
    let (peta, meta, pqsi, mqsi) = (1. + eta, 1. - eta, 1. + qsi, 1. - qsi);
    let (etac, qsic) = (1. - eta * eta, 1. - qsi * qsi);
    [
        mqsi * meta / 8. * (qsic + etac - qsi - eta),
        mqsi * meta / 8. * qsic,
        mqsi * meta / 8. * etac,
        pqsi * meta / 8. * (qsic + etac + qsi - eta),
        -pqsi * meta / 8. * qsic,
        pqsi * meta / 8. * etac,
        pqsi * peta / 8. * (qsic + etac + qsi + eta),
        -pqsi * peta / 8. * qsic,
        -pqsi * peta / 8. * etac,
        mqsi * peta / 8. * (qsic + etac - qsi + eta),
        mqsi * peta / 8. * qsic,
        -mqsi * peta / 8. * etac,
    ]
}

/// `dkqnib`: the DKQ's interpolation of the rotations (βx, βy) on the
/// bending unknowns (w₁ βx₁ βy₁ …) at (ξ, η).
fn nib_q(c: &[f64; 25], qsi: f64, eta: f64) -> ([f64; 12], [f64; 12]) {
    let l = [c[8], c[9], c[10], c[11]];
    let co = [c[12], c[13], c[14], c[15]];
    let si = [c[16], c[17], c[18], c[19]];
    let n = [
        0.25 * (1. - qsi) * (1. - eta),
        0.25 * (1. + qsi) * (1. - eta),
        0.25 * (1. + qsi) * (1. + eta),
        0.25 * (1. - qsi) * (1. + eta),
    ];
    // The mid-side functions of sides 5 (1–2), 6 (2–3), 7 (3–4), 8 (4–1).
    let p = [
        0.5 * (1. - qsi * qsi) * (1. - eta),
        0.5 * (1. - eta * eta) * (1. + qsi),
        0.5 * (1. - qsi * qsi) * (1. + eta),
        0.5 * (1. - eta * eta) * (1. - qsi),
    ];
    let mut nfx = [0.; 12];
    let mut nfy = [0.; 12];
    for k in 0..4 {
        // Node k + 1 lies between side k (after it) and side k − 1 (before).
        let (a, b) = (k, (k + 3) % 4);
        nfx[3 * k] = 1.5 * (p[a] * co[a] / l[a] - p[b] * co[b] / l[b]);
        nfx[3 * k + 1] = n[k] - 0.75 * (p[a] * co[a] * co[a] + p[b] * co[b] * co[b]);
        nfx[3 * k + 2] = -0.75 * (p[a] * co[a] * si[a] + p[b] * co[b] * si[b]);
        nfy[3 * k] = 1.5 * (p[a] * si[a] / l[a] - p[b] * si[b] / l[b]);
        nfy[3 * k + 1] = nfx[3 * k + 2];
        nfy[3 * k + 2] = n[k] - 0.75 * (p[a] * si[a] * si[a] + p[b] * si[b] * si[b]);
    }
    (nfx, nfy)
}

/// The mass in the facet's frame (`dkqmas` then `dxqloc`, option
/// `MASS_MECA`), DOFs node-major DX DY DZ DRX DRY DRZ along the local axes:
/// - membrane: ρh·A/9 × (1 on a node, ½ between neighbouring nodes, ¼
///   between opposite ones) on each in-plane translation — `dkqmas`'s
///   literal pattern, the bilinear consistent mass of a parallelogram
///   (not of a general quadrangle: code_aster uses it for every shape);
/// - bending: ρh ∫ w·w with the DKQ's w ([`wkq`], `dkqniw`) on
///   (w, βx, βy), integrated with the stiffness' FPG4 as code_aster does,
///   plus the rotary inertia ρh³/12 ∫ β·β ([`nib_q`], `dkqnib`) when
///   `COQUE/INER_ROTA='OUI'`;
/// - the drilling DRZ: `COEF_RIGI_DRZ` × the least diagonal term of the
///   bending rotations, as for the stiffness (`dxqloc`).
pub fn local_mass(quad: &Quad, rho: f64, section: &ShellSection) -> Matrix24 {
    let roe = rho * section.thickness;
    let mut m = membrane_mass(quad, roe);
    let e = section.offset;
    // `dkqmas`: the rotations' density ρh³/12 (INER_ROTA) + e²·ρh.
    let rof = section.rotary_density(rho) + e * e * roe;
    let mut flex = [[0.; 12]; 12];
    let mut mefl = [[0.; 12]; 8];
    for g in fpg4() {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let w = wkq(&quad.c, qsi, eta);
        let det = quad.jacobian(qsi, eta).0;
        let wgt = g.weight * det * roe;
        let (nfx, nfy) = nib_q(&quad.c, qsi, eta);
        let wgtf = g.weight * det * rof;
        for a in 0..12 {
            for b in 0..12 {
                flex[a][b] += w[a] * w[b] * wgt + (nfx[a] * nfx[b] + nfy[a] * nfy[b]) * wgtf;
            }
        }
        if e != 0. {
            // `dxqnim`: the bilinear membrane functions, weighted by e·ρh.
            let nmi = [
                0.25 * (1. - qsi) * (1. - eta),
                0.25 * (1. + qsi) * (1. - eta),
                0.25 * (1. + qsi) * (1. + eta),
                0.25 * (1. - qsi) * (1. + eta),
            ];
            offset_mass(&nmi, &nfx, &nfy, g.weight * det * e * roe, &mut mefl);
        }
    }
    add_bending(&flex, section.drilling, &mut m);
    add_coupling(&mefl, &mut m);
    m
}

/// `dkqmas`'s membrane mass ρh·A/9 × (1 on a node, ½ between
/// neighbouring nodes, ¼ between opposite ones) on each in-plane
/// translation of a local 24×24 matrix (also `dsqmas`'s and `q4gmas`'s;
/// `roe` = ρh).
pub(crate) fn membrane_mass(quad: &Quad, roe: f64) -> Matrix24 {
    let coefm = quad.c[20] * roe / 9.;
    let mut m = Matrix24::zeros();
    for a in 0..8 {
        for b in 0..8 {
            if a % 2 == b % 2 {
                let factor = match (a / 2usize).abs_diff(b / 2) {
                    0 => 1.,
                    2 => 0.25,
                    _ => 0.5,
                };
                m[(membrane_dof(a), membrane_dof(b))] = coefm * factor;
            }
        }
    }
    m
}

/// Global mass of a DKQ quadrangle of density `rho` ([`local_mass`] turned
/// by the facet's frame; 24×24, node-major DX DY DZ DRX DRY DRZ), and the
/// facet's mass ρh·A (`dialum`'s weight when lumped).
pub fn mass(
    xyz: &[[f64; 3]; 4],
    rho: f64,
    section: &ShellSection,
) -> Result<(DMatrix<f64>, f64), String> {
    check_drilling(section)?;
    let quad = Quad::new(xyz)?;
    let r = rotation(&quad);
    let m = r.transpose() * local_mass(&quad, rho, section) * r;
    Ok((
        DMatrix::from_column_slice(24, 24, m.as_slice()),
        quad.c[20] * rho * section.thickness,
    ))
}

/// The nodes of the reference square, code_aster's `NOEU` family of
/// `MEDKQU4` (where `dkqedg` evaluates `EFGE_ELNO` of a linear result).
pub const NODES: [[f64; 2]; 4] = [[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]];

/// Generalised efforts at the FPG4 points from the global
/// displacements `u` (24 values, node-major), in the facet's frame
/// (`dkqedg`, `EFGE_ELGA`: the transverse shears from the moments'
/// derivatives, `dkqtxy`).
pub fn efforts(
    xyz: &[[f64; 3]; 4],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64; 24],
) -> Result<Vec<QuadEfforts>, String> {
    let points = rigi_points();
    generalised_at(xyz, material, section, u, &points, Generalised::Efforts)
}

/// Generalised efforts or strains (`what`) at the reference points
/// `points` (ξ, η) (`dkqedg`; at [`NODES`] it is `EFGE_ELNO` of a linear
/// result and `DEGE_ELNO`).
pub fn generalised_at(
    xyz: &[[f64; 3]; 4],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64; 24],
    points: &[[f64; 2]],
    what: Generalised,
) -> Result<Vec<QuadEfforts>, String> {
    let quad = Quad::new(xyz)?;
    let ul = rotation(&quad) * SMatrix::<f64, 24, 1>::from_column_slice(u);
    let (dm, df) = section_matrices(material, section);
    let um: Vec<f64> = (0..8).map(|k| ul[membrane_dof(k)]).collect();
    let ub: Vec<f64> = (0..12)
        .map(|k| {
            let (i, s) = bending_dof(k);
            s * ul[i]
        })
        .collect();
    Ok(points
        .iter()
        .map(|g| {
            let (qsi, eta) = (g[0], g[1]);
            let (_, vj) = quad.jacobian(qsi, eta);
            let bm = Quad::bm(qsi, eta, &vj);
            let bf = quad.bf(qsi, eta, &vj);
            let eps: [f64; 3] = std::array::from_fn(|i| (0..8).map(|j| bm[i][j] * um[j]).sum());
            let kappa: [f64; 3] = std::array::from_fn(|i| (0..12).map(|j| bf[i][j] * ub[j]).sum());
            let bc = quad.shear(&df, qsi, eta, &vj);
            let q: [f64; 2] = std::array::from_fn(|i| (0..12).map(|j| bc[i][j] * ub[j]).sum());
            // `dkqedg` (a MECA_STATIQUE result's efforts): N's coupling
            // term reads the curvature of the bilinear rotations (`dsqbfb`,
            // Bm on the nodes' βx βy), the moments the DKQ's; `dktnli`'s
            // layers (STAT_NON_LINE) and `dkqsie` read the DKQ's.
            let beta: Vec<f64> = (0..4)
                .flat_map(|n| [ub[3 * n + 1], ub[3 * n + 2]])
                .collect();
            let kappa_b: [f64; 3] =
                std::array::from_fn(|i| (0..8).map(|j| bm[i][j] * beta[j]).sum());
            let kappa_mf = if what == Generalised::EffortsLinear {
                kappa_b
            } else {
                kappa
            };
            what.at_point_coupled(material, section, (&dm, &df), eps, (kappa, kappa_mf), q)
        })
        .collect())
}
