//! Batoz' discrete Kirchhoff triangle: code_aster's `DKT` thin-shell
//! element on TRIA3 (`MEDKTR3`), a flat facet with six DOFs per node
//! (DX DY DZ DRX DRY DRZ).
//!
//! What it computes, following code_aster's routines one to one:
//! - the facet's local frame `pgl` (`dxtpgl`): x along node 1 → node 2, z
//!   the normal (x₂₁ × x₃₁)/|…|, y = z × x;
//! - membrane: the constant-strain triangle (`dxtbm`), integrated exactly
//!   (area · Bmᵀ·Dm·Bm);
//! - bending: the DKT curvature operator (`dktbf`), integrated with FPG3
//!   ((1/6,1/6), (2/3,1/6), (1/6,2/3), weights 1/6), on the bending unknowns
//!   (w, βx, βy) = (DZ, DRY, −DRX) of each node (`dktedg`, `dxtloc`);
//! - the drilling rotation DRZ, which the facet has no stiffness for, gets
//!   code_aster's fictitious spring `COEF_RIGI_DRZ · min(bending rotation
//!   diagonal)` on each node (`dxtloc`, `CARA_ELEM/COQUE/COEF_RIGI_DRZ`,
//!   default 1e-5);
//! - the mass (`dktmas`, [`local_mass`]): the membrane's consistent
//!   linear-triangle mass, ρh ∫ w·w with the cubic w of `dktniw` at FPG3,
//!   no rotary inertia (code_aster's default without `INER_ROTA`), the
//!   drilling term as the stiffness';
//! - generalised efforts at the Gauss points (`dktedg`, option
//!   `EFGE_ELGA`): N = Dm·Bm·u, M = Df·Bf·β, and the transverse shears
//!   (QX, QY) from the moments' derivatives (`dsxhft`, `dkttxy`), in the
//!   facet's frame `pgl`.
//!
//! Section: a homogeneous isotropic elastic thickness h,
//! Dm = E·h/(1−ν²)·[1 ν 0; ν 1 0; 0 0 (1−ν)/2], Df = Dm·h²/12 (`dxmate`);
//! with an offset e (`EXCENTREMENT`) the facet is the reference surface
//! and the section's mid-surface lies at e along the normal: membrane and
//! bending couple through Dmf = e·Dm and the bending becomes
//! Df + e²·Dm (`dxmate`), in the stiffness (`dktrig`'s Bmᵀ·Dmf·Bf), the
//! efforts (N += Dmf·κ, M += Dmf·ε, about the reference surface) and the
//! mass (`dktmas`).
//! The efforts are given in `pgl`; code_aster reports them in the user's
//! frame (`ANGL_REP`/`VECTEUR` of `CARA_ELEM/COQUE`, by default the
//! projection of global X on the facet), a rotation left to the caller.
//!
//! Numerics only: no keyword is read here; the runner maps
//! `AFFE_MODELE/MODELISATION='DKT'` and `AFFE_CARA_ELEM/COQUE` onto
//! [`crate::model::ElementKind::Shell`] and [`ShellSection`].

use crate::material::Elastic;
use crate::shape::{rigi_scheme, GaussPoint};
use aster_mesh::CellType;
use nalgebra::{DMatrix, Matrix3, SMatrix, Vector3};

/// Thin-shell section of `CARA_ELEM/COQUE`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellSection {
    /// `EPAIS`.
    pub thickness: f64,
    /// `COEF_RIGI_DRZ` (code_aster's default 1e-5).
    pub drilling: f64,
    /// `INER_ROTA='OUI'`: the mass has the rotary inertia ρh³/12 ∫ β·β
    /// (`dktnib`, `dkqnib`); the stiffness does not depend on it.
    pub rotary_inertia: bool,
    /// A stack of plies (`DEFI_COMPOSITE`) in this facet's frame: its
    /// matrices replace the homogeneous isotropic ones of the material
    /// ([`crate::laminate`]); `thickness` is then the stack's.
    pub layered: Option<std::sync::Arc<crate::laminate::LayeredSection>>,
    /// `EXCENTREMENT`: the distance e from the cell's plane (the reference
    /// surface, where the nodes are) to the mid-surface of the section,
    /// along the facet's normal. code_aster's `dxmate` then couples
    /// membrane and bending, B = e·A, and stiffens the bending,
    /// D + e²·A ([`coupling`], [`section_matrices`]); the masses gain
    /// e·ρh between the in-plane translations and the rotations and e²·ρh
    /// on the rotations (`dktmas`, `dkqmas`).
    pub offset: f64,
}

impl ShellSection {
    /// A section of thickness `h` with code_aster's default drilling
    /// coefficient, without rotary inertia.
    pub fn new(thickness: f64) -> ShellSection {
        ShellSection {
            thickness,
            drilling: 1e-5,
            rotary_inertia: false,
            layered: None,
            offset: 0.,
        }
    }

    /// ρh³/12 when the rotary inertia is asked for (`dktmas`'s `rof`), else 0.
    pub(crate) fn rotary_density(&self, rho: f64) -> f64 {
        if self.rotary_inertia {
            rho * self.thickness.powi(3) / 12.
        } else {
            0.
        }
    }
}

/// Generalised efforts at one point, code_aster's `EFGE` components in the
/// facet's frame: NXX NYY NXY MXX MYY MXY QX QY.
pub type Efforts = [f64; 8];

/// 18×18 element matrix, node-major (DX DY DZ DRX DRY DRZ of node 1, …).
pub type Matrix18 = SMatrix<f64, 18, 18>;

/// The facet: its frame and code_aster's `carat3` geometric data.
#[derive(Clone, Debug)]
pub struct Facet {
    /// Rows are the local axes x, y, z in global coordinates (`pgl`).
    pub pgl: Matrix3<f64>,
    /// `gtria3`'s 21 values (1-based in the Fortran, 0-based here).
    pub(crate) c: [f64; 21],
}

impl Facet {
    /// Frame and geometry of the triangle `xyz` (global coordinates).
    /// Errors on a degenerate (zero-length side or zero-area) triangle.
    pub fn new(xyz: &[[f64; 3]; 3]) -> Result<Facet, String> {
        let p = |i: usize| Vector3::new(xyz[i][0], xyz[i][1], xyz[i][2]);
        let (x21, x31) = (p(1) - p(0), p(2) - p(0));
        let size = x21.norm().max(x31.norm());
        let n = x21.cross(&x31);
        if !(size > 0. && n.norm() > 1e-12 * size * size) {
            return Err(format!(
                "a DKT triangle is degenerate (zero area): nodes {:?}",
                xyz
            ));
        }
        let ex = x21.normalize();
        let ez = n.normalize();
        let ey = ez.cross(&ex);
        let pgl = Matrix3::from_rows(&[ex.transpose(), ey.transpose(), ez.transpose()]);
        let local: Vec<[f64; 2]> = (0..3)
            .map(|i| {
                let d = p(i) - p(0);
                [ex.dot(&d), ey.dot(&d)]
            })
            .collect();
        Ok(Facet {
            pgl,
            c: gtria3(&local),
        })
    }

    /// Area of the facet.
    pub fn area(&self) -> f64 {
        self.c[7]
    }

    /// Membrane strain operator (`dxtbm`) on (u₁ v₁ u₂ v₂ u₃ v₃):
    /// (εxx, εyy, 2εxy).
    pub(crate) fn bm(&self) -> [[f64; 6]; 3] {
        let (j11, j12, j21, j22) = (self.c[8], self.c[9], self.c[10], self.c[11]);
        [
            [-j11 - j12, 0., j11, 0., j12, 0.],
            [0., -j21 - j22, 0., j21, 0., j22],
            [-j21 - j22, -j11 - j12, j21, j11, j22, j12],
        ]
    }

    /// Bending curvature operator (`dktbf`) at (ξ, η) on the bending
    /// unknowns (w₁ βx₁ βy₁ w₂ …): (βx,x, βy,y, βx,y + βy,x).
    fn bf(&self, qsi: f64, eta: f64) -> [[f64; 9]; 3] {
        let c = &self.c;
        let (vj11, vj12, vj21, vj22) = (c[8], c[9], c[10], c[11]);
        let (l4, l5, l6) = (c[12], c[13], c[14]);
        let (c4, c5, c6) = (c[15], c[16], c[17]);
        let (s4, s5, s6) = (c[18], c[19], c[20]);
        let (cu4, cu5, cu6) = (3. * c4 * c4, 3. * c5 * c5, 3. * c6 * c6);
        let (su4, su5, su6) = (3. * s4 * s4, 3. * s5 * s5, 3. * s6 * s6);
        let (cs4, cs5, cs6) = (3. * c4 * s4, 3. * c5 * s5, 3. * c6 * s6);
        let (cl4, cl5, cl6) = (6. * c4 / l4, 6. * c5 / l5, 6. * c6 / l6);
        let (sl4, sl5, sl6) = (6. * s4 / l4, 6. * s5 / l5, 6. * s6 / l6);
        let lmq = 1. - 2. * qsi - eta;
        let lme = 1. - qsi - 2. * eta;
        let bxq = [
            lmq * cl4 + eta * cl6,
            -1. - lmq * cu4 + eta * cu6,
            -lmq * cs4 + eta * cs6,
            -lmq * cl4 + eta * cl5,
            1. - lmq * cu4 - eta * cu5,
            -lmq * cs4 - eta * cs5,
            -eta * cl6 - eta * cl5,
            eta * cu6 - eta * cu5,
            eta * cs6 - eta * cs5,
        ];
        let byq = [
            lmq * sl4 + eta * sl6,
            bxq[2],
            -1. - lmq * su4 + eta * su6,
            -lmq * sl4 + eta * sl5,
            bxq[5],
            1. - lmq * su4 - eta * su5,
            -eta * sl6 - eta * sl5,
            bxq[8],
            eta * su6 - eta * su5,
        ];
        let bxe = [
            -lme * cl6 - qsi * cl4,
            -1. - lme * cu6 + qsi * cu4,
            -lme * cs6 + qsi * cs4,
            qsi * cl4 + qsi * cl5,
            qsi * cu4 - qsi * cu5,
            qsi * cs4 - qsi * cs5,
            lme * cl6 - qsi * cl5,
            1. - lme * cu6 - qsi * cu5,
            -lme * cs6 - qsi * cs5,
        ];
        let bye = [
            -lme * sl6 - qsi * sl4,
            bxe[2],
            -1. - lme * su6 + qsi * su4,
            qsi * sl4 + qsi * sl5,
            bxe[5],
            qsi * su4 - qsi * su5,
            lme * sl6 - qsi * sl5,
            bxe[8],
            1. - lme * su6 - qsi * su5,
        ];
        let mut bf = [[0.; 9]; 3];
        for i in 0..9 {
            bf[0][i] = vj11 * bxq[i] + vj12 * bxe[i];
            bf[1][i] = vj21 * byq[i] + vj22 * bye[i];
            bf[2][i] = vj11 * byq[i] + vj12 * bye[i] + vj21 * bxq[i] + vj22 * bxe[i];
        }
        bf
    }

    /// Transverse shear operator (`dsxhft` then `dkttxy`): (QX, QY) from
    /// the bending unknowns, constant over the facet.
    fn shear(&self, df: &[[f64; 3]; 3]) -> [[f64; 9]; 2] {
        let c = &self.c;
        let hft2 = hft2(df, [c[8], c[9], c[10], c[11]]);
        let tkt = self.tkt();
        let mut bc = [[0.; 9]; 2];
        for i in 0..2 {
            for j in 0..9 {
                for k in 0..6 {
                    bc[i][j] += hft2[i][k] * tkt[k][j];
                }
            }
        }
        bc
    }

    /// The moments' derivatives λ (`dsxhlt` then `dktlxy`) from the
    /// bending unknowns `ub`, constant over the facet: what the shear
    /// stresses by ply of a layered section add (`dktsie`).
    pub(crate) fn moment_derivatives(&self, df: &[[f64; 3]; 3], ub: &[f64]) -> [f64; 4] {
        let c = &self.c;
        let hlt2 = crate::laminate::dsxhlt(df, [c[8], c[9], c[10], c[11]]);
        let tkt = self.tkt();
        std::array::from_fn(|i| {
            (0..9)
                .map(|j| (0..6).map(|k| hlt2[i][k] * tkt[k][j]).sum::<f64>() * ub[j])
                .sum()
        })
    }

    /// `dkttxy`'s and `dktlxy`'s TKT: the third derivatives of w on the
    /// bending unknowns.
    fn tkt(&self) -> [[f64; 9]; 6] {
        let c = &self.c;
        // codi = (c4 c5 c6 s4 s5 s6), lcot = (l4 l5 l6).
        let mut cl = [0.; 3];
        let mut sl = [0.; 3];
        let mut cs = [0.; 3];
        let mut cu = [0.; 3];
        let mut su = [0.; 3];
        for i in 0..3 {
            let (co, si, l) = (c[15 + i], c[18 + i], c[12 + i]);
            cl[i] = 6. * co / l;
            sl[i] = 6. * si / l;
            cs[i] = 3. * co * si;
            cu[i] = 3. * co * co;
            su[i] = 3. * si * si;
        }
        let tkt: [[f64; 9]; 6] = [
            [
                -2. * cl[0],
                2. * cu[0],
                2. * cs[0],
                2. * cl[0],
                2. * cu[0],
                2. * cs[0],
                0.,
                0.,
                0.,
            ],
            [
                2. * cl[2],
                2. * cu[2],
                2. * cs[2],
                0.,
                0.,
                0.,
                -2. * cl[2],
                2. * cu[2],
                2. * cs[2],
            ],
            [
                cl[2] - cl[0],
                cu[2] + cu[0],
                cs[2] + cs[0],
                cl[0] + cl[1],
                cu[0] - cu[1],
                cs[0] - cs[1],
                -cl[2] - cl[1],
                cu[2] - cu[1],
                cs[2] - cs[1],
            ],
            [
                -2. * sl[0],
                2. * cs[0],
                2. * su[0],
                2. * sl[0],
                2. * cs[0],
                2. * su[0],
                0.,
                0.,
                0.,
            ],
            [
                2. * sl[2],
                2. * cs[2],
                2. * su[2],
                0.,
                0.,
                0.,
                -2. * sl[2],
                2. * cs[2],
                2. * su[2],
            ],
            [
                sl[2] - sl[0],
                cs[2] + cs[0],
                su[2] + su[0],
                sl[0] + sl[1],
                cs[0] - cs[1],
                su[0] - su[1],
                -sl[2] - sl[1],
                cs[2] - cs[1],
                su[2] - su[1],
            ],
        ];
        tkt
    }
}

/// `dsxhft`: the product H_F·T₂ of the moments' derivatives operator by
/// the second derivatives' change of variables, for the transverse shears
/// of the Kirchhoff plates (DKT `dkttxy`, DKQ `dkqtxy`), from the bending
/// elasticity `df` and the inverse Jacobian (vj11 vj12 vj21 vj22).
pub(crate) fn hft2(df: &[[f64; 3]; 3], vj: [f64; 4]) -> [[f64; 6]; 2] {
    let [vj11, vj12, vj21, vj22] = vj;
    let hf = [
        [
            df[0][0],
            df[2][2],
            2. * df[0][2],
            df[0][2],
            df[1][2],
            df[0][1] + df[2][2],
        ],
        [
            df[0][2],
            df[1][2],
            df[0][1] + df[2][2],
            df[2][2],
            df[1][1],
            2. * df[1][2],
        ],
    ];
    let t2 = [
        [vj11 * vj11, vj12 * vj12, 2. * vj11 * vj12],
        [vj21 * vj21, vj22 * vj22, 2. * vj21 * vj22],
        [vj11 * vj21, vj12 * vj22, vj11 * vj22 + vj12 * vj21],
    ];
    let mut hft2 = [[0.; 6]; 2];
    for r in 0..2 {
        for j in 0..3 {
            for k in 0..3 {
                hft2[r][j] += hf[r][k] * t2[k][j];
                hft2[r][j + 3] += hf[r][k + 3] * t2[k][j];
            }
        }
    }
    hft2
}

/// `gtria3`: edge vectors, twice the area, the inverse Jacobian and the
/// edges' lengths, cosines and sines, from the local (x, y) of the nodes.
fn gtria3(xy: &[[f64; 2]]) -> [f64; 21] {
    let x21 = xy[1][0] - xy[0][0];
    let x32 = xy[2][0] - xy[1][0];
    let x13 = xy[0][0] - xy[2][0];
    let y21 = xy[1][1] - xy[0][1];
    let y32 = xy[2][1] - xy[1][1];
    let y13 = xy[0][1] - xy[2][1];
    let det = -x21 * y13 + y21 * x13;
    let l4 = (x21 * x21 + y21 * y21).sqrt();
    let l5 = (x32 * x32 + y32 * y32).sqrt();
    let l6 = (x13 * x13 + y13 * y13).sqrt();
    [
        x21,
        x32,
        x13,
        y21,
        y32,
        y13,
        det,
        det / 2.,
        -y13 / det,
        -y21 / det,
        x13 / det,
        x21 / det,
        l4,
        l5,
        l6,
        x21 / l4,
        x32 / l5,
        x13 / l6,
        y21 / l4,
        y32 / l5,
        y13 / l6,
    ]
}

/// Membrane and bending elasticity matrices of the section (`dxmate`),
/// about the reference surface: with an offset e (`EXCENTREMENT`) the
/// bending matrix is D + e²·A, as `dxmate` makes it (the coupling e·A is
/// [`coupling`]; a layered section here has no coupling of its own, the
/// runner refuses unsymmetric stacks).
pub(crate) fn section_matrices(
    material: &Elastic,
    section: &ShellSection,
) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let (dm, mut df) = mid_section_matrices(material, section);
    let e = section.offset;
    if e != 0. {
        for i in 0..3 {
            for j in 0..3 {
                df[i][j] += e * e * dm[i][j];
            }
        }
    }
    (dm, df)
}

/// The membrane–bending coupling of the section about the reference
/// surface, e·A (`dxmate`'s `dmf` with `EXCENTREMENT`), or `None` without
/// an offset (`coupmf` false).
pub(crate) fn coupling(material: &Elastic, section: &ShellSection) -> Option<[[f64; 3]; 3]> {
    let e = section.offset;
    (e != 0.).then(|| {
        let (dm, _) = mid_section_matrices(material, section);
        dm.map(|row| row.map(|v| e * v))
    })
}

/// Membrane and bending matrices about the section's own mid-surface.
fn mid_section_matrices(
    material: &Elastic,
    section: &ShellSection,
) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    if let Some(l) = &section.layered {
        return (l.dm, l.df);
    }
    let (e, nu, h) = (material.e, material.nu, section.thickness);
    let a = e * h / (1. - nu * nu);
    let dm = [
        [a, a * nu, 0.],
        [a * nu, a, 0.],
        [0., 0., a * (1. - nu) / 2.],
    ];
    let f = h * h / 12.;
    let df = dm.map(|row| row.map(|v| v * f));
    (dm, df)
}

/// Local index of membrane unknown `k` (u₁ v₁ u₂ …) among the element's
/// DOFs (6 per node).
pub(crate) fn membrane_dof(k: usize) -> usize {
    6 * (k / 2) + k % 2
}

/// Local index and sign of bending unknown `k` (w₁ βx₁ βy₁ …): w = DZ,
/// βx = DRY, βy = −DRX.
pub(crate) fn bending_dof(k: usize) -> (usize, f64) {
    let node = 6 * (k / 3);
    match k % 3 {
        0 => (node + 2, 1.),
        1 => (node + 4, 1.),
        _ => (node + 3, -1.),
    }
}

/// The (ξ, η) of the RIGI family's points (FPG3), where the efforts are
/// computed on a STAT_NON_LINE result.
pub(crate) fn rigi_points() -> Vec<[f64; 2]> {
    fpg3().iter().map(|g| [g.xi[0], g.xi[1]]).collect()
}

/// FPG3, code_aster's `RIGI` family of `MEDKTR3`.
pub(crate) fn fpg3() -> Vec<GaussPoint> {
    rigi_scheme(CellType::TRIA6)
}

/// Stiffness in the facet's frame (`dktrig` then `dxtloc`), DOFs
/// node-major DX DY DZ DRX DRY DRZ along the local axes.
pub fn local_stiffness(facet: &Facet, material: &Elastic, section: &ShellSection) -> Matrix18 {
    let (dm, df) = section_matrices(material, section);
    let dmf = coupling(material, section);
    let mut k = membrane_stiffness(facet, &dm);
    let mut flex = [[0.; 9]; 9];
    let mut mefl = [[0.; 9]; 6];
    let bm = facet.bm();
    for g in fpg3() {
        let w = g.weight * facet.c[6];
        let bf = facet.bf(g.xi[0], g.xi[1]);
        for a in 0..9 {
            for b in 0..9 {
                let mut v = 0.;
                for i in 0..3 {
                    for j in 0..3 {
                        v += bf[i][a] * df[i][j] * bf[j][b];
                    }
                }
                flex[a][b] += w * v;
            }
        }
        // `dktrig`: Bmᵀ·Dmf·Bf at each point (`utctab`).
        if let Some(dmf) = &dmf {
            add_ctab(&bm, dmf, &bf, w, &mut mefl);
        }
    }
    add_bending(&flex, section.drilling, &mut k);
    add_coupling(&mefl, &mut k);
    k
}

/// Adds `w`·Cᵀ·D·B to `out` (`utctab`): the coupling of the `M` membrane
/// unknowns (operator `c`) with the `N` bending ones (operator `b`).
pub(crate) fn add_ctab<const M: usize, const N: usize>(
    c: &[[f64; M]; 3],
    d: &[[f64; 3]; 3],
    b: &[[f64; N]; 3],
    w: f64,
    out: &mut [[f64; N]; M],
) {
    let mut db = [[0.; N]; 3];
    for i in 0..3 {
        for j in 0..N {
            db[i][j] = (0..3).map(|k| d[i][k] * b[k][j]).sum();
        }
    }
    for a in 0..M {
        for j in 0..N {
            out[a][j] += w * (0..3).map(|i| c[i][a] * db[i][j]).sum::<f64>();
        }
    }
}

/// Adds the membrane–bending block `mefl` (membrane unknowns u₁ v₁ …
/// by bending unknowns w₁ βx₁ βy₁ …) and its transpose to a local matrix
/// (`dxtloc`, `dxqloc`: the `cfm`/`cmf` terms, with βy = −DRX).
pub(crate) fn add_coupling<const M: usize, const N: usize, const D: usize>(
    mefl: &[[f64; N]; M],
    out: &mut SMatrix<f64, D, D>,
) {
    for (a, row) in mefl.iter().enumerate() {
        let ia = membrane_dof(a);
        for (b, v) in row.iter().enumerate() {
            if *v == 0. {
                continue;
            }
            let (ib, sb) = bending_dof(b);
            out[(ia, ib)] += sb * v;
            out[(ib, ia)] += sb * v;
        }
    }
}

/// The constant-strain membrane (`dxtbm`, area · Bmᵀ·Dm·Bm) on the
/// in-plane translations of a local 18×18 matrix: the membrane part of
/// every plate triangle (DKT, DST, Q4G's T3G).
pub(crate) fn membrane_stiffness(facet: &Facet, dm: &[[f64; 3]; 3]) -> Matrix18 {
    let mut k = Matrix18::zeros();
    let bm = facet.bm();
    let area = facet.area();
    for a in 0..6 {
        for b in 0..6 {
            let mut v = 0.;
            for i in 0..3 {
                for j in 0..3 {
                    v += bm[i][a] * dm[i][j] * bm[j][b];
                }
            }
            k[(membrane_dof(a), membrane_dof(b))] += area * v;
        }
    }
    k
}

/// Adds `w`·Bᵀ·D·B to `out` (`utbtab`), for an operator `b` of `R` rows
/// on `N` unknowns.
pub(crate) fn add_btdb<const R: usize, const N: usize>(
    b: &[[f64; N]; R],
    d: &[[f64; R]; R],
    w: f64,
    out: &mut [[f64; N]; N],
) {
    let mut db = [[0.; N]; R];
    for i in 0..R {
        for j in 0..N {
            db[i][j] = (0..R).map(|k| d[i][k] * b[k][j]).sum();
        }
    }
    for a in 0..N {
        for c in 0..N {
            out[a][c] += w * (0..R).map(|i| b[i][a] * db[i][c]).sum::<f64>();
        }
    }
}

/// The bending unknowns (w₁ βx₁ βy₁ …, [`bending_dof`]) and the in-plane
/// translations (u₁ v₁ …, [`membrane_dof`]) of a facet of `NN` nodes from
/// its local displacements `ul` (6 per node).
pub(crate) fn split_unknowns(ul: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let nn = ul.len() / 6;
    let um = (0..2 * nn).map(|k| ul[membrane_dof(k)]).collect();
    let ub = (0..3 * nn)
        .map(|k| {
            let (i, s) = bending_dof(k);
            s * ul[i]
        })
        .collect();
    (um, ub)
}

/// Adds the bending block `flex` (on the unknowns w βx βy of each node,
/// [`bending_dof`]) and the drilling terms (`COEF_RIGI_DRZ` × the least
/// diagonal term of the bending rotations, on each node's DRZ: `dxtloc`,
/// `dxqloc`) to the local matrix `out` of a DKT (3 nodes) or DKQ (4).
pub(crate) fn add_bending<const B: usize, const D: usize>(
    flex: &[[f64; B]; B],
    drilling: f64,
    out: &mut SMatrix<f64, D, D>,
) {
    for a in 0..B {
        let (ia, sa) = bending_dof(a);
        for b in 0..B {
            let (ib, sb) = bending_dof(b);
            out[(ia, ib)] += sa * sb * flex[a][b];
        }
    }
    let rotation_min = (0..B)
        .filter(|i| i % 3 != 0)
        .map(|i| flex[i][i])
        .fold(f64::INFINITY, f64::min);
    for n in 0..B / 3 {
        out[(6 * n + 5, 6 * n + 5)] = drilling * rotation_min;
    }
}

/// The 18×18 global→local rotation: `pgl` on every translation and
/// rotation triple.
pub fn rotation(facet: &Facet) -> Matrix18 {
    let mut r = Matrix18::zeros();
    for b in 0..6 {
        r.fixed_view_mut::<3, 3>(3 * b, 3 * b).copy_from(&facet.pgl);
    }
    r
}

/// Global stiffness of a DKT triangle with nodes at `xyz` (18×18,
/// node-major DX DY DZ DRX DRY DRZ).
pub fn stiffness(
    xyz: &[[f64; 3]; 3],
    material: &Elastic,
    section: &ShellSection,
) -> Result<DMatrix<f64>, String> {
    let facet = Facet::new(xyz)?;
    let r = rotation(&facet);
    let k = r.transpose() * local_stiffness(&facet, material, section) * r;
    Ok(DMatrix::from_column_slice(18, 18, k.as_slice()))
}

/// `dktniw`: the DKT's cubic interpolation of w on the bending unknowns
/// (w₁ βx₁ βy₁ …) at (ξ, η).
pub(crate) fn wkt(c: &[f64; 21], qsi: f64, eta: f64) -> [f64; 9] {
    let (x4, x6, y4, y6) = (c[0], c[2], c[3], c[5]);
    let n = wkt_n(qsi, eta);
    [
        n[0],
        -x4 * n[1] + x6 * n[2],
        -y4 * n[1] + y6 * n[2],
        n[3],
        -x4 * n[4] + x6 * n[5],
        -y4 * n[4] + y6 * n[5],
        n[6],
        -x4 * n[7] + x6 * n[8],
        -y4 * n[7] + y6 * n[8],
    ]
}

/// `dktniw`'s nine cubic functions N₁ … N₉ at (ξ, η) (also `dstniw`'s).
pub(crate) fn wkt_n(qsi: f64, eta: f64) -> [f64; 9] {
    let lbd = 1. - qsi - eta;
    let qel = qsi * eta * lbd;
    [
        lbd * lbd * (3. - 2. * lbd) + qel * 2.,
        lbd * lbd * qsi + qel / 2.,
        lbd * lbd * eta + qel / 2.,
        qsi * qsi * (3. - 2. * qsi) + qel * 2.,
        qsi * qsi * (-1. + qsi) - qel,
        qsi * qsi * eta + qel / 2.,
        eta * eta * (3. - 2. * eta) + qel * 2.,
        eta * eta * qsi + qel / 2.,
        eta * eta * (-1. + eta) - qel,
    ]
}

/// `dktnib`: the DKT's interpolation of the rotations (βx, βy) on the
/// bending unknowns (w₁ βx₁ βy₁ …) at (ξ, η).
fn nib_t(c: &[f64; 21], qsi: f64, eta: f64) -> ([f64; 9], [f64; 9]) {
    let (l4, l5, l6) = (c[12], c[13], c[14]);
    let (c4, c5, c6) = (c[15], c[16], c[17]);
    let (s4, s5, s6) = (c[18], c[19], c[20]);
    let (n1, n2, n3) = (1. - qsi - eta, qsi, eta);
    let p4 = 4. * qsi * (1. - qsi - eta);
    let p5 = 4. * qsi * eta;
    let p6 = 4. * eta * (1. - qsi - eta);
    let nfx = [
        1.5 * (p4 * c4 / l4 - p6 * c6 / l6),
        n1 - 0.75 * (p4 * c4 * c4 + p6 * c6 * c6),
        -0.75 * (p4 * c4 * s4 + p6 * c6 * s6),
        1.5 * (p5 * c5 / l5 - p4 * c4 / l4),
        n2 - 0.75 * (p5 * c5 * c5 + p4 * c4 * c4),
        -0.75 * (p5 * c5 * s5 + p4 * c4 * s4),
        1.5 * (p6 * c6 / l6 - p5 * c5 / l5),
        n3 - 0.75 * (p6 * c6 * c6 + p5 * c5 * c5),
        -0.75 * (p6 * c6 * s6 + p5 * c5 * s5),
    ];
    let nfy = [
        1.5 * (p4 * s4 / l4 - p6 * s6 / l6),
        nfx[2],
        n1 - 0.75 * (p4 * s4 * s4 + p6 * s6 * s6),
        1.5 * (p5 * s5 / l5 - p4 * s4 / l4),
        nfx[5],
        n2 - 0.75 * (p5 * s5 * s5 + p4 * s4 * s4),
        1.5 * (p6 * s6 / l6 - p5 * s5 / l5),
        nfx[8],
        n3 - 0.75 * (p6 * s6 * s6 + p5 * s5 * s5),
    ];
    (nfx, nfy)
}

/// The mass in the facet's frame (`dktmas` then `dxtloc`, option
/// `MASS_MECA`), DOFs node-major DX DY DZ DRX DRY DRZ along the local axes:
/// - membrane: the linear triangle's consistent mass ρh·A/6 (diagonal),
///   ρh·A/12 (off it) on each in-plane translation;
/// - bending: ρh ∫ w·w with the DKT's cubic w ([`wkt`], `dktniw`) on
///   (w, βx, βy), integrated with the stiffness' FPG3 as code_aster does
///   (not exactly: w·w is of degree 6), plus the rotary inertia
///   ρh³/12 ∫ β·β with the DKT's rotations ([`nib_t`], `dktnib`) when
///   `COQUE/INER_ROTA='OUI'` (code_aster's default: none), and with an
///   offset e (`EXCENTREMENT`) e²·ρh ∫ β·β more and the coupling
///   e·ρh ∫ (u·βx + v·βy) with the linear membrane functions (`dxtnim`);
/// - the drilling DRZ: `COEF_RIGI_DRZ` × the least diagonal term of the
///   bending rotations, as for the stiffness (`dxtloc`).
pub fn local_mass(facet: &Facet, rho: f64, section: &ShellSection) -> Matrix18 {
    local_mass_on(facet, rho, section, &fpg3())
}

/// [`local_mass`] integrated on `scheme`: `dktmas` reads the element's
/// RIGI family, FPG3 on the DKT, FPG1 on Q4G's triangle (`MET3TR3`).
pub(crate) fn local_mass_on(
    facet: &Facet,
    rho: f64,
    section: &ShellSection,
    scheme: &[GaussPoint],
) -> Matrix18 {
    let roe = rho * section.thickness;
    let mut m = membrane_mass(facet, roe);
    let e = section.offset;
    // `dktmas`: the rotations' density ρh³/12 (INER_ROTA) + e²·ρh.
    let rof = section.rotary_density(rho) + e * e * roe;
    let mut flex = [[0.; 9]; 9];
    let mut mefl = [[0.; 9]; 6];
    for g in scheme {
        let (qsi, eta) = (g.xi[0], g.xi[1]);
        let w = wkt(&facet.c, qsi, eta);
        let wgt = g.weight * facet.c[6] * roe;
        let (nfx, nfy) = nib_t(&facet.c, qsi, eta);
        let wgtf = g.weight * facet.c[6] * rof;
        for a in 0..9 {
            for b in 0..9 {
                flex[a][b] += w[a] * w[b] * wgt + (nfx[a] * nfx[b] + nfy[a] * nfy[b]) * wgtf;
            }
        }
        if e != 0. {
            // `dxtnim`: the linear membrane functions; u with βx, v with
            // βy, weighted by e·ρh.
            let nmi = [1. - qsi - eta, qsi, eta];
            let wgtmf = g.weight * facet.c[6] * e * roe;
            offset_mass(&nmi, &nfx, &nfy, wgtmf, &mut mefl);
        }
    }
    add_bending(&flex, section.drilling, &mut m);
    add_coupling(&mefl, &mut m);
    m
}

/// The membrane–rotation mass of an offset facet at one point (`dktmas`,
/// `dkqmas`): `nmi` the membrane functions, (`nfx`, `nfy`) the rotations'.
pub(crate) fn offset_mass<const K: usize, const M: usize, const N: usize>(
    nmi: &[f64; K],
    nfx: &[f64; N],
    nfy: &[f64; N],
    wgtmf: f64,
    mefl: &mut [[f64; N]; M],
) {
    for k in 0..K {
        for j in 0..N {
            mefl[2 * k][j] += nmi[k] * nfx[j] * wgtmf;
            mefl[2 * k + 1][j] += nmi[k] * nfy[j] * wgtmf;
        }
    }
}

/// The linear triangle's consistent membrane mass ρh·A/6 (diagonal),
/// ρh·A/12 (off it) on each in-plane translation of a local 18×18 matrix
/// (`dktmas`, `dstmas`; `roe` = ρh).
pub(crate) fn membrane_mass(facet: &Facet, roe: f64) -> Matrix18 {
    let area = facet.area();
    let mut m = Matrix18::zeros();
    for a in 0..6 {
        for b in 0..6 {
            if a % 2 == b % 2 {
                let v = if a == b {
                    area * roe / 6.
                } else {
                    area * roe / 12.
                };
                m[(membrane_dof(a), membrane_dof(b))] = v;
            }
        }
    }
    m
}

/// Global mass of a DKT triangle of density `rho` ([`local_mass`] turned
/// by the facet's frame; 18×18, node-major DX DY DZ DRX DRY DRZ), and the
/// facet's mass ρh·A (`dialum`'s weight when lumped).
pub fn mass(
    xyz: &[[f64; 3]; 3],
    rho: f64,
    section: &ShellSection,
) -> Result<(DMatrix<f64>, f64), String> {
    mass_on(xyz, rho, section, &fpg3())
}

/// [`mass`] integrated on `scheme` ([`local_mass_on`]).
pub(crate) fn mass_on(
    xyz: &[[f64; 3]; 3],
    rho: f64,
    section: &ShellSection,
    scheme: &[GaussPoint],
) -> Result<(DMatrix<f64>, f64), String> {
    let facet = Facet::new(xyz)?;
    let r = rotation(&facet);
    let m = r.transpose() * local_mass_on(&facet, rho, section, scheme) * r;
    Ok((
        DMatrix::from_column_slice(18, 18, m.as_slice()),
        facet.area() * rho * section.thickness,
    ))
}

/// The nodes of the reference triangle, code_aster's `NOEU` family of
/// `MEDKTR3` (where `dktedg` evaluates `EFGE_ELNO` of a linear result).
pub const NODES: [[f64; 2]; 3] = [[0., 0.], [1., 0.], [0., 1.]];

/// Generalised efforts at the FPG3 points from the global displacements
/// `u` (18 values, node-major DX DY DZ DRX DRY DRZ), in the facet's frame
/// (`dktedg`, `EFGE_ELGA`).
pub fn efforts(
    xyz: &[[f64; 3]; 3],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64; 18],
) -> Result<Vec<Efforts>, String> {
    let points = rigi_points();
    generalised_at(xyz, material, section, u, &points, Generalised::Efforts)
}

/// Generalised efforts or strains (`what`) at the reference points
/// `points` (ξ, η), in the facet's frame (`dktedg`: the membrane and
/// transverse shear are constant, the moments follow the curvature at each
/// point; at [`NODES`] it is `EFGE_ELNO` of a linear result and
/// `DEGE_ELNO`).
pub fn generalised_at(
    xyz: &[[f64; 3]; 3],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64; 18],
    points: &[[f64; 2]],
    what: Generalised,
) -> Result<Vec<Efforts>, String> {
    let facet = Facet::new(xyz)?;
    let ul = rotation(&facet) * SMatrix::<f64, 18, 1>::from_column_slice(u);
    let (dm, df) = section_matrices(material, section);
    let um: Vec<f64> = (0..6).map(|k| ul[membrane_dof(k)]).collect();
    let ub: Vec<f64> = (0..9)
        .map(|k| {
            let (i, s) = bending_dof(k);
            s * ul[i]
        })
        .collect();
    let bm = facet.bm();
    let eps: Vec<f64> = (0..3)
        .map(|i| (0..6).map(|j| bm[i][j] * um[j]).sum())
        .collect();
    let eps = [eps[0], eps[1], eps[2]];
    let bc = facet.shear(&df);
    let q: [f64; 2] = std::array::from_fn(|i| (0..9).map(|j| bc[i][j] * ub[j]).sum());
    Ok(points
        .iter()
        .map(|g| {
            let bf = facet.bf(g[0], g[1]);
            let kappa: [f64; 3] = std::array::from_fn(|i| (0..9).map(|j| bf[i][j] * ub[j]).sum());
            what.at_point(material, section, (&dm, &df), eps, kappa, q)
        })
        .collect())
}

/// What [`generalised_at`] gives at a point of a Kirchhoff facet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Generalised {
    /// `EFGE`: NXX NYY NXY MXX MYY MXY QX QY (N = Dm·ε, M = Df·κ, Q the
    /// moments' derivatives; with an offset N += Dmf·κ, M += Dmf·ε — the
    /// path of a STAT_NON_LINE result and of the layer stresses, whose
    /// strains at a height read the facet's own κ).
    Efforts,
    /// The efforts of a MECA_STATIQUE result (`dkqedg` with an `EFGE_*`
    /// option): as [`Generalised::Efforts`] except that on the DKQ the
    /// offset's term Dmf·κ of N reads the curvature of the bilinear
    /// rotations (`dsqbfb`); the same on the DKT (`dktedg`).
    EffortsLinear,
    /// `DEGE` (`dktedg`/`dkqedg` with a `DEGE_*` option): EXX EYY EXY KXX
    /// KYY KXY GAX GAY — the membrane strains and curvatures with their
    /// shear halved (tensor components), and GA = Dc⁻¹·Q/2, Dc = 5/6·G·h
    /// (`dxmate`'s shear stiffness, the shear a Kirchhoff plate's moments
    /// imply).
    Strains,
}

impl Generalised {
    /// The point's values from its membrane strains `eps`, curvatures
    /// `kappa` (engineering shears) and transverse shear forces `q`.
    pub(crate) fn at_point(
        self,
        material: &Elastic,
        section: &ShellSection,
        (dm, df): (&[[f64; 3]; 3], &[[f64; 3]; 3]),
        eps: [f64; 3],
        kappa: [f64; 3],
        q: [f64; 2],
    ) -> Efforts {
        self.at_point_coupled(material, section, (dm, df), eps, (kappa, kappa), q)
    }

    /// [`Generalised::at_point`] with the curvature the offset's coupling
    /// reads apart: `kappas` = (κ of the moments, κ of N's coupling term)
    /// — the same on the DKT; `dkqedg` takes the second from the bilinear
    /// rotations (`dsqbfb`).
    pub(crate) fn at_point_coupled(
        self,
        material: &Elastic,
        section: &ShellSection,
        (dm, df): (&[[f64; 3]; 3], &[[f64; 3]; 3]),
        eps: [f64; 3],
        (kappa, kappa_mf): ([f64; 3], [f64; 3]),
        q: [f64; 2],
    ) -> Efforts {
        match self {
            Generalised::Efforts | Generalised::EffortsLinear => {
                let mut n: [f64; 3] =
                    std::array::from_fn(|i| (0..3).map(|j| dm[i][j] * eps[j]).sum());
                let mut m: [f64; 3] =
                    std::array::from_fn(|i| (0..3).map(|j| df[i][j] * kappa[j]).sum());
                // `dktedg`/`dkqedg`: with an offset, N += Dmf·κ and
                // M += Dmf·ε — the efforts about the reference surface.
                if let Some(dmf) = coupling(material, section) {
                    for i in 0..3 {
                        n[i] += (0..3).map(|j| dmf[i][j] * kappa_mf[j]).sum::<f64>();
                        m[i] += (0..3).map(|j| dmf[i][j] * eps[j]).sum::<f64>();
                    }
                }
                [n[0], n[1], n[2], m[0], m[1], m[2], q[0], q[1]]
            }
            Generalised::Strains => {
                let dci = crate::dst::shear_compliance(material, section);
                [
                    eps[0],
                    eps[1],
                    eps[2] / 2.,
                    kappa[0],
                    kappa[1],
                    kappa[2] / 2.,
                    (dci[0][0] * q[0] + dci[0][1] * q[1]) / 2.,
                    (dci[1][0] * q[0] + dci[1][1] * q[1]) / 2.,
                ]
            }
        }
    }
}

/// The moments' derivatives λ of a DKT triangle at `xyz` (constant),
/// for the shear stresses by ply of a layered section (`dktsie`).
pub(crate) fn moment_derivatives(
    xyz: &[[f64; 3]; 3],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
) -> Result<[f64; 4], String> {
    let facet = Facet::new(xyz)?;
    let ul = rotation(&facet) * SMatrix::<f64, 18, 1>::from_column_slice(u);
    let (_, df) = section_matrices(material, section);
    let (_, ub) = split_unknowns(ul.as_slice());
    Ok(facet.moment_derivatives(&df, &ub))
}
