//! code_aster's `COQUE_3D` shell on QUAD9 (`MEC3QU9H`): a degenerated
//! solid with a quadratic mid-surface, six DOFs (DX DY DZ DRX DRY DRZ) on
//! the eight edge nodes and three rotations (DRX DRY DRZ) on the central
//! node, 51 DOFs in all.
//!
//! Transcribed from code_aster's small-strain path of `te0414`
//! (`vdxnlr`, the routine `STAT_NON_LINE` calls for `RELATION='ELAS'`,
//! `DEFORMATION='PETIT'`) and the routines it calls:
//! - reference data (`jni080`): QUAD8 functions for the geometry and the
//!   translations, QUAD9 functions for the rotations, the reduced rule
//!   FPG4 (±1/√3) and the normal rule `FPG9COQ` (3×3 Gauss, code_aster's
//!   point order), the bilinear extrapolation from the four reduced points
//!   to the nine normal ones (with code_aster's literal
//!   `0.577350269189626`);
//! - nodal frames (`vectan`): at each of the nine nodes, the covariant
//!   vectors a₁, a₂ of the QUAD8 geometry, the unit normal n = a₁×a₂/|·|,
//!   t₁ = a₁/|a₁|, t₂ = n×t₁; the local rotations of a node are (t₁·θ,
//!   t₂·θ), the normal rotation n·θ only feeds the drilling spring;
//! - through the thickness: `COQUE_NCOU` layers of thickness h/n, each
//!   with Simpson's three points (bottom, middle, top; weights 1/3, 4/3,
//!   1/3), the layer thickness standing for `epais` in the Jacobian
//!   (`vdxnlr` passes `hic`);
//! - at each point: the local frame `vectgt` (the interpolated normal is
//!   *not* normalised), `hfmss` (the strain transformation), `jacbm1`;
//!   the membrane and transverse-shear operators on the reduced points
//!   (`btdmsr`) extrapolated to the normal points (`btdmsn`, the
//!   selective integration), the bending part on the normal points
//!   (`btdfn`);
//! - the section law: plane stress, D = E/(1−ν²)[1 ν 0; ν 1 0; 0 0
//!   (1−ν)/2] and the transverse shears κ·E/(2(1+ν)) (κ = `A_CIS`,
//!   code_aster's default `0.8333333`);
//! - drilling (`matrkb`): `COEF_RIGI_DRZ · min` of the local rotation
//!   diagonal over the nine nodes, on each normal rotation;
//! - local → global (`tranlg`): the rotation triple of each node turned by
//!   its frame (t₁, t₂, n).
//!
//! Also: `SIEF_ELGA` by layer ([`stresses`]), `SIGM_ELNO` in the user's
//! frame ([`sigm_elno`], `elno_coq3d`) and the pressure load
//! ([`pressure_load`], `fpres`). docs/fem.md lists the routines and the
//! measurements.
//!
//! Numerics only: no keyword is read here. The model carries it as
//! [`crate::ElementKind::Coque3d`] (the central node numbered with its
//! three rotations alone); the runner wires `MODELISATION='COQUE_3D'` on
//! QUAD9 cells to it.

use crate::material::Elastic;

/// code_aster's default `A_CIS` (`AFFE_CARA_ELEM/COQUE`), its literal.
pub const DEFAULT_SHEAR_FACTOR: f64 = 0.8333333;

/// The section of a COQUE_3D cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coque3dSection {
    /// `EPAIS`.
    pub thickness: f64,
    /// `COEF_RIGI_DRZ` (`CTOR`; code_aster's default 1e-5).
    pub drilling: f64,
    /// `A_CIS` (κ, the transverse shear factor).
    pub shear_factor: f64,
    /// `COQUE_NCOU`.
    pub layers: u32,
}

impl Coque3dSection {
    /// A section of thickness `h` with code_aster's defaults.
    pub fn new(thickness: f64) -> Coque3dSection {
        Coque3dSection {
            thickness,
            drilling: 1e-5,
            shear_factor: DEFAULT_SHEAR_FACTOR,
            layers: 1,
        }
    }
}

/// Edge nodes (QUAD8 part).
const NB1: usize = 8;
/// All nodes (QUAD9).
const NB2: usize = 9;
/// Reduced points (FPG4).
const NPGSR: usize = 4;
/// Normal points (FPG9COQ).
const NPGSN: usize = 9;
/// Local DOFs before the drilling ones: 5 per edge node, 2 at the centre.
const NDDLE: usize = 5 * NB1 + 2;
/// Global DOFs: 6 per edge node, 3 at the centre.
pub const NDDL: usize = 6 * NB1 + 3;

/// Values and derivatives of shape functions at one point.
#[derive(Clone, Copy)]
struct Shape<const N: usize> {
    f: [f64; N],
    d1: [f64; N],
    d2: [f64; N],
}

fn qu8(x: f64, y: f64) -> Shape<8> {
    let (un, uns4, undemi, deux) = (1., 0.25, 0.5, 2.);
    Shape {
        f: [
            uns4 * (un - x) * (un - y) * (-un - x - y),
            uns4 * (un + x) * (un - y) * (-un + x - y),
            uns4 * (un + x) * (un + y) * (-un + x + y),
            uns4 * (un - x) * (un + y) * (-un - x + y),
            undemi * (un - x * x) * (un - y),
            undemi * (un - y * y) * (un + x),
            undemi * (un - x * x) * (un + y),
            undemi * (un - y * y) * (un - x),
        ],
        d1: [
            -uns4 * (un - y) * (-deux * x - y),
            uns4 * (un - y) * (deux * x - y),
            uns4 * (un + y) * (deux * x + y),
            -uns4 * (un + y) * (-deux * x + y),
            -deux * x * (un - y) * undemi,
            (un - y * y) * undemi,
            -deux * x * (un + y) * undemi,
            -(un - y * y) * undemi,
        ],
        d2: [
            -uns4 * (un - x) * (-deux * y - x),
            -uns4 * (un + x) * (-deux * y + x),
            uns4 * (un + x) * (deux * y + x),
            uns4 * (un - x) * (deux * y - x),
            -(un - x * x) * undemi,
            -deux * y * (un + x) * undemi,
            (un - x * x) * undemi,
            -deux * y * (un - x) * undemi,
        ],
    }
}

fn qu9(x: f64, y: f64) -> Shape<9> {
    let al = |t: f64| [t * (t - 1.) / 2., 1. - t * t, t * (t + 1.) / 2.];
    let dal = |t: f64| [t - 0.5, -2. * t, t + 0.5];
    // (ξ index, η index) of each node: 0 ↔ −1, 1 ↔ 0, 2 ↔ +1.
    const IJ: [(usize, usize); 9] = [
        (0, 0),
        (2, 0),
        (2, 2),
        (0, 2),
        (1, 0),
        (2, 1),
        (1, 2),
        (0, 1),
        (1, 1),
    ];
    let (ax, ay, dx, dy) = (al(x), al(y), dal(x), dal(y));
    let mut s = Shape {
        f: [0.; 9],
        d1: [0.; 9],
        d2: [0.; 9],
    };
    for (n, &(i, j)) in IJ.iter().enumerate() {
        s.f[n] = ax[i] * ay[j];
        s.d1[n] = dx[i] * ay[j];
        s.d2[n] = ax[i] * dy[j];
    }
    s
}

/// The reference data of `MEC3QU9H` (`jni080`).
struct RefQuad9 {
    /// Weights of FPG9COQ.
    wn: [f64; NPGSN],
    /// QUAD8 at the reduced points (geometry, translations).
    g8r: [Shape<8>; NPGSR],
    /// QUAD8 at the normal points.
    g8n: [Shape<8>; NPGSN],
    /// QUAD9 at the reduced points (rotations).
    r9r: [Shape<9>; NPGSR],
    /// QUAD9 at the normal points.
    r9n: [Shape<9>; NPGSN],
    /// QUAD8 at the nine nodes (the nodal frames).
    g8nodes: [Shape<8>; NB2],
    /// Extrapolation from the reduced to the normal points.
    extra: [[f64; NPGSR]; NPGSN],
}

/// The nine nodes of the reference QUAD9, code_aster's order.
const NODES9: [(f64, f64); 9] = [
    (-1., -1.),
    (1., -1.),
    (1., 1.),
    (-1., 1.),
    (0., -1.),
    (1., 0.),
    (0., 1.),
    (-1., 0.),
    (0., 0.),
];

/// `FPG9COQ` (`elraga`): 3×3 Gauss, corners and mid-sides in turn round
/// the square, the centre last.
fn fpg9coq() -> [(f64, f64); 9] {
    let b = (3f64 / 5.).sqrt();
    [
        (-b, -b),
        (0., -b),
        (b, -b),
        (b, 0.),
        (b, b),
        (0., b),
        (-b, b),
        (-b, 0.),
        (0., 0.),
    ]
}

impl RefQuad9 {
    fn new() -> RefQuad9 {
        let a = (1f64 / 3.).sqrt();
        let reduced = [(-a, -a), (a, -a), (a, a), (-a, a)];
        let normal = fpg9coq();
        let (c, m, z) = (25. / 81., 40. / 81., 64. / 81.);
        let aa = 0.577350269189626;
        RefQuad9 {
            wn: [c, m, c, m, c, m, c, m, z],
            g8r: reduced.map(|(x, y)| qu8(x, y)),
            g8n: normal.map(|(x, y)| qu8(x, y)),
            r9r: reduced.map(|(x, y)| qu9(x, y)),
            r9n: normal.map(|(x, y)| qu9(x, y)),
            g8nodes: NODES9.map(|(x, y)| qu8(x, y)),
            extra: normal.map(|(x, y)| {
                [
                    0.75 * (aa - x) * (aa - y),
                    0.75 * (aa + x) * (aa - y),
                    0.75 * (aa + x) * (aa + y),
                    0.75 * (aa - x) * (aa + y),
                ]
            }),
        }
    }
}

type V3 = [f64; 3];

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The frame of each of the nine nodes (`vectan`): rows t₁, t₂, n.
fn nodal_frames(xyz: &[V3; NB1], r: &RefQuad9) -> Result<[[V3; 3]; NB2], String> {
    let mut frames = [[[0.; 3]; 3]; NB2];
    for (i, fr) in frames.iter_mut().enumerate() {
        let s = &r.g8nodes[i];
        let mut a1 = [0.; 3];
        let mut a2 = [0.; 3];
        for k in 0..3 {
            for j in 0..NB1 {
                a1[k] += s.d1[j] * xyz[j][k];
                a2[k] += s.d2[j] * xyz[j][k];
            }
        }
        let n = cross(a1, a2);
        let (rn, r1) = (norm(n), norm(a1));
        if !(rn > 0. && r1 > 0.) {
            return Err(format!(
                "a COQUE_3D quadrangle is degenerate at its node {} (zero covariant vector): nodes {xyz:?}",
                i + 1
            ));
        }
        let n = n.map(|v| v / rn);
        let t1 = a1.map(|v| v / r1);
        let t2 = cross(n, t1);
        *fr = [t1, t2, n];
    }
    Ok(frames)
}

/// `vectgt` + `jacbm1` at one point: the local frame (t₁, t₂, t₃ with t₃
/// the interpolated, non-normalised normal), the inverse Jacobian and its
/// determinant.
fn point_frame(
    s: &Shape<8>,
    xyz: &[V3; NB1],
    normals: &[V3; NB2],
    ksi3s2: f64,
    epais: f64,
) -> ([V3; 3], [[f64; 3]; 3], f64) {
    let mut t3 = [0.; 3];
    let mut g1 = [0.; 3];
    let mut g2 = [0.; 3];
    for k in 0..3 {
        for j in 0..NB1 {
            t3[k] += s.f[j] * normals[j][k];
            let x = xyz[j][k] + ksi3s2 * epais * normals[j][k];
            g1[k] += s.d1[j] * x;
            g2[k] += s.d2[j] * x;
        }
    }
    let r = norm(g1);
    let t1 = g1.map(|v| v / r);
    let t2 = [
        t3[1] * t1[2] - t3[2] * t1[1],
        t3[2] * t1[0] - t3[0] * t1[2],
        t3[0] * t1[1] - t3[1] * t1[0],
    ];
    let m = [g1, g2, t3.map(|v| v * epais / 2.)];
    let det = m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2])
        - m[0][1] * (m[1][0] * m[2][2] - m[2][0] * m[1][2])
        + m[0][2] * (m[1][0] * m[2][1] - m[2][0] * m[1][1]);
    let inv = [
        [
            (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det,
            -(m[0][1] * m[2][2] - m[0][2] * m[2][1]) / det,
            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det,
        ],
        [
            -(m[1][0] * m[2][2] - m[1][2] * m[2][0]) / det,
            (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
            -(m[0][0] * m[1][2] - m[0][2] * m[1][0]) / det,
        ],
        [
            (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det,
            -(m[0][0] * m[2][1] - m[0][1] * m[2][0]) / det,
            (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det,
        ],
    ];
    ([t1, t2, t3], inv, det)
}

/// `hfmss`: the membrane rows (3×9) and, with `shear`, the transverse
/// shear rows (2×9) of the strain transformation, on the nine gradient
/// components (∂uₖ/∂xⱼ, k-major).
fn hfmss(t: &[V3; 3], shear: bool) -> ([[f64; 9]; 3], [[f64; 9]; 2]) {
    let (t1, t2, t3) = (t[0], t[1], t[2]);
    // Products of two axes on the six symmetric components (xx, yy, zz,
    // xy, xz, yz): aᵢaⱼ for one axis, the symmetrised 2·aᵢbⱼ for two
    // (multiplications by 2 and the sums' order are exact: code_aster's
    // values bit for bit).
    let square = |a: V3| {
        [
            a[0] * a[0],
            a[1] * a[1],
            a[2] * a[2],
            a[0] * a[1],
            a[0] * a[2],
            a[1] * a[2],
        ]
    };
    let mixed = |a: V3, b: V3| {
        [
            2. * a[0] * b[0],
            2. * a[1] * b[1],
            2. * a[2] * b[2],
            b[0] * a[1] + a[0] * b[1],
            b[0] * a[2] + a[0] * b[2],
            b[1] * a[2] + a[1] * b[2],
        ]
    };
    let hfm = [square(t1), square(t2), mixed(t1, t2)];
    // (xx, xy, xz, yx, yy, yz, zx, zy, zz) ← (1, 4, 5, 4, 2, 6, 5, 6, 3)
    const MAP: [usize; 9] = [0, 3, 4, 3, 1, 5, 4, 5, 2];
    let sym = |row: &[f64; 6]| MAP.map(|k| row[k]);
    let hm = [sym(&hfm[0]), sym(&hfm[1]), sym(&hfm[2])];
    let mut hs = [[0.; 9]; 2];
    if shear {
        let (s1, s2) = (mixed(t1, t3), mixed(t2, t3));
        hs = [sym(&s1), sym(&s2)];
    }
    (hm, hs)
}

/// H·J⁻¹ block by block (`hsj1ms`, `hsj1f`): column j + 3·jb of the
/// result is Σₖ H(·, k + 3·jb)·J⁻¹(k, j).
fn times_jinv<const R: usize>(h: &[[f64; 9]; R], jm1: &[[f64; 3]; 3]) -> [[f64; 9]; R] {
    let mut out = [[0.; 9]; R];
    for (o, hr) in out.iter_mut().zip(h) {
        for jb in 0..3 {
            for j in 0..3 {
                let mut s = 0.;
                for k in 0..3 {
                    s += hr[k + 3 * jb] * jm1[k][j];
                }
                o[j + 3 * jb] = s;
            }
        }
    }
    out
}

/// The rotation part of the displacement-gradient operator (`dnsds` /
/// `dnsdsf` columns 4, 5 of each node and the two central columns): row
/// 3·k + d is ∂uₖ/∂(ξ₁, ξ₂, ξ₃)[d].
fn rotation_columns(
    s9: &Shape<9>,
    frames: &[[V3; 3]; NB2],
    ksi3s2: f64,
    epais: f64,
) -> Vec<([f64; 9], usize)> {
    let mut cols = Vec::with_capacity(2 * NB2);
    for j in 0..NB2 {
        let (t1, t2) = (frames[j][0], frames[j][1]);
        let base = if j < NB1 { 5 * j + 3 } else { 5 * NB1 };
        let mut ca = [0.; 9];
        let mut cb = [0.; 9];
        for k in 0..3 {
            ca[3 * k] = -ksi3s2 * s9.d1[j] * epais * t2[k];
            cb[3 * k] = ksi3s2 * s9.d1[j] * epais * t1[k];
            ca[3 * k + 1] = -ksi3s2 * s9.d2[j] * epais * t2[k];
            cb[3 * k + 1] = ksi3s2 * s9.d2[j] * epais * t1[k];
            ca[3 * k + 2] = -s9.f[j] / 2. * epais * t2[k];
            cb[3 * k + 2] = s9.f[j] / 2. * epais * t1[k];
        }
        cols.push((ca, base));
        cols.push((cb, base + 1));
    }
    cols
}

/// The 5×42 strain operator at every (layer point, normal point), with
/// its weight: `btdmsr` on the reduced points, `btdfn` on the normal ones,
/// combined by `btdmsn` (IND=1).
fn operators(
    xyz: &[V3; NB1],
    frames: &[[V3; 3]; NB2],
    section: &Coque3dSection,
    r: &RefQuad9,
) -> Vec<(Vec<[f64; NDDLE]>, f64)> {
    let normals = frames.map(|f| f[2]);
    let nbcou = section.layers.max(1) as usize;
    let hic = section.thickness / nbcou as f64;
    let zmin = -section.thickness / 2.;
    let mut out = Vec::with_capacity(nbcou * 3 * NPGSN);
    for icou in 0..nbcou {
        for inte in 0..3 {
            let (zic, coef) = match inte {
                0 => (zmin + icou as f64 * hic, 1. / 3.),
                1 => (zmin + hic / 2. + icou as f64 * hic, 4. / 3.),
                _ => (zmin + hic + icou as f64 * hic, 1. / 3.),
            };
            let ksi3s2 = zic / hic;
            // Reduced points: membrane (translations only) and shear rows.
            let mut btdm = [[[0.; NDDLE]; 3]; NPGSR];
            let mut btds = [[[0.; NDDLE]; 2]; NPGSR];
            for p in 0..NPGSR {
                let s8 = &r.g8r[p];
                let (t, jm1, _) = point_frame(s8, xyz, &normals, ksi3s2, hic);
                let (hm, hs) = hfmss(&t, true);
                let hm = times_jinv(&hm, &jm1);
                let hs = times_jinv(&hs, &jm1);
                for jb in 0..NB1 {
                    for k in 0..3 {
                        let col = 5 * jb + k;
                        // ∂uₖ/∂ξ₁, ∂uₖ/∂ξ₂ at rows 3k, 3k+1.
                        for i in 0..3 {
                            btdm[p][i][col] =
                                hm[i][3 * k] * s8.d1[jb] + hm[i][3 * k + 1] * s8.d2[jb];
                        }
                        for i in 0..2 {
                            btds[p][i][col] =
                                hs[i][3 * k] * s8.d1[jb] + hs[i][3 * k + 1] * s8.d2[jb];
                        }
                    }
                }
                for (c, col) in rotation_columns(&r.r9r[p], frames, ksi3s2, hic) {
                    for i in 0..2 {
                        btds[p][i][col] = (0..9).map(|k| hs[i][k] * c[k]).sum();
                    }
                }
            }
            // Normal points: bending rows and the extrapolated rest.
            for q in 0..NPGSN {
                let (t, jm1, det) = point_frame(&r.g8n[q], xyz, &normals, ksi3s2, hic);
                let (hf, _) = hfmss(&t, false);
                let hf = times_jinv(&hf, &jm1);
                let wgt = coef * (r.wn[q] * det);
                let mut btdf = [[0.; NDDLE]; 3];
                for (c, col) in rotation_columns(&r.r9n[q], frames, ksi3s2, hic) {
                    for (i, row) in btdf.iter_mut().enumerate() {
                        row[col] = (0..9).map(|k| hf[i][k] * c[k]).sum();
                    }
                }
                let e = &r.extra[q];
                let mut b = vec![[0.; NDDLE]; 5];
                for j in 0..NDDLE {
                    for i in 0..2 {
                        let mut m = 0.;
                        let mut s = 0.;
                        for k in 0..NPGSR {
                            m += e[k] * btdm[k][i][j];
                            s += e[k] * btds[k][i][j];
                        }
                        b[i][j] = m + btdf[i][j];
                        b[i + 3][j] = s;
                    }
                    let mut m = 0.;
                    for k in 0..NPGSR {
                        m += e[k] * btdm[k][2][j];
                    }
                    b[2][j] = m + btdf[2][j];
                }
                out.push((b, wgt));
            }
        }
    }
    out
}

/// The 5×5 section law (`vdxnlr`'s `dtild` for `ELAS` in plane stress).
fn dtild(material: &Elastic, kappa: f64) -> [[f64; 5]; 5] {
    let (e, nu) = (material.e, material.nu);
    let c = e / (1. - nu * nu);
    let g = e / (1. + nu);
    let mut d = [[0.; 5]; 5];
    d[0][0] = c;
    d[0][1] = c * nu;
    d[1][0] = c * nu;
    d[1][1] = c;
    d[2][2] = g / 2.;
    d[3][3] = g * kappa / 2.;
    d[4][4] = g * kappa / 2.;
    d
}

/// The element's stiffness in its local rotation frames, 51×51 (`matrkb`
/// on `vdxnlr`'s `ktild`), and the drilling coefficient.
fn local_stiffness(
    xyz: &[V3; NB1],
    frames: &[[V3; 3]; NB2],
    material: &Elastic,
    section: &Coque3dSection,
    r: &RefQuad9,
) -> (Vec<f64>, f64) {
    let d = dtild(material, section.shear_factor);
    let mut kt = vec![0.; NDDLE * NDDLE];
    for (b, wgt) in operators(xyz, frames, section, r) {
        // wmatcb = (wgt·D)·B
        let mut db = vec![[0.; NDDLE]; 5];
        for i in 0..5 {
            for j in 0..NDDLE {
                let mut s = 0.;
                for k in 0..5 {
                    s += d[i][k] * wgt * b[k][j];
                }
                db[i][j] = s;
            }
        }
        for i in 0..NDDLE {
            for j in 0..NDDLE {
                let mut s = 0.;
                for k in 0..5 {
                    s += b[k][i] * db[k][j];
                }
                kt[i * NDDLE + j] += s;
            }
        }
    }
    // matrkb: 5 per edge node (+ a drilling row), 2 (+1) at the centre.
    let mut xmin = 1. / f64::EPSILON;
    for n in 0..NB2 {
        let r0 = if n < NB1 { 5 * n + 3 } else { 5 * NB1 };
        for a in 0..2 {
            xmin = xmin.min(kt[(r0 + a) * NDDLE + r0 + a]);
        }
    }
    let coef = section.drilling * xmin;
    let local_of = |i: usize| {
        if i < 5 * NB1 {
            6 * (i / 5) + i % 5
        } else {
            6 * NB1 + (i - 5 * NB1)
        }
    };
    let mut k = vec![0.; NDDL * NDDL];
    for i in 0..NDDLE {
        for j in 0..NDDLE {
            k[local_of(i) * NDDL + local_of(j)] = kt[i * NDDLE + j];
        }
    }
    for n in 0..NB1 {
        k[(6 * n + 5) * NDDL + 6 * n + 5] = coef;
    }
    k[(NDDL - 1) * NDDL + NDDL - 1] = coef;
    (k, coef)
}

/// The global stiffness of a COQUE_3D QUAD9, row-major 51×51, DOFs
/// node-major: DX DY DZ DRX DRY DRZ of nodes 1–8, then DRX DRY DRZ of the
/// central node. `xyz` are the eight edge nodes (the central node's
/// position plays no part: code_aster's geometry is the QUAD8's).
pub fn stiffness(
    xyz: &[V3; NB1],
    material: &Elastic,
    section: &Coque3dSection,
) -> Result<Vec<f64>, String> {
    if section.drilling < 0. || section.drilling.is_nan() {
        return Err(format!(
            "COEF_RIGI_DRZ = {} < 0 selects code_aster's alternative drilling formulation, which is not reproduced for COQUE_3D",
            section.drilling
        ));
    }
    let r = RefQuad9::new();
    let frames = nodal_frames(xyz, &r)?;
    let (kl, _) = local_stiffness(xyz, &frames, material, section, &r);
    // P: global → local (rotation triples turned by each node's frame).
    let mut p = vec![0.; NDDL * NDDL];
    for n in 0..NB1 {
        for a in 0..3 {
            p[(6 * n + a) * NDDL + 6 * n + a] = 1.;
            for b in 0..3 {
                p[(6 * n + 3 + a) * NDDL + 6 * n + 3 + b] = frames[n][a][b];
            }
        }
    }
    for a in 0..3 {
        for b in 0..3 {
            p[(6 * NB1 + a) * NDDL + 6 * NB1 + b] = frames[NB1][a][b];
        }
    }
    // Pᵀ·K·P (the products skip nothing but exact zeros: `tranlg`'s sums)
    let p = nalgebra::DMatrix::from_row_slice(NDDL, NDDL, &p);
    let kl = nalgebra::DMatrix::from_row_slice(NDDL, NDDL, &kl);
    let kg = p.transpose() * kl * p;
    let kg: Vec<f64> = kg.transpose().iter().copied().collect();
    Ok(kg)
}

/// The local unknowns of `vdxnlr` (`trndgl`): the translations as they
/// are, each node's rotation θ as (t₁·θ, t₂·θ); 42 values.
fn local_unknowns(frames: &[[V3; 3]; NB2], u: &[f64; NDDL]) -> [f64; NDDLE] {
    let mut l = [0.; NDDLE];
    let dot = |t: V3, o: usize| t[0] * u[o] + t[1] * u[o + 1] + t[2] * u[o + 2];
    for n in 0..NB1 {
        l[5 * n..5 * n + 3].copy_from_slice(&u[6 * n..6 * n + 3]);
        l[5 * n + 3] = dot(frames[n][0], 6 * n + 3);
        l[5 * n + 4] = dot(frames[n][1], 6 * n + 3);
    }
    l[5 * NB1] = dot(frames[NB1][0], 6 * NB1);
    l[5 * NB1 + 1] = dot(frames[NB1][1], 6 * NB1);
    l
}

/// The stresses of `SIEF_ELGA` from the global displacements `u` (51
/// values, the order of [`stiffness`]): SIXX SIYY SIZZ SIXY SIXZ SIYZ in
/// each point's local frame (`vectgt`: t₁ along ∂x/∂ξ₁), SIZZ = 0, in
/// code_aster's order — normal point (FPG9COQ) major, then layer, then
/// the layer's bottom, middle and top (`vdxnlr`'s `k1`).
pub fn stresses(
    xyz: &[V3; NB1],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64; NDDL],
) -> Result<Vec<[f64; 6]>, String> {
    let r = RefQuad9::new();
    let frames = nodal_frames(xyz, &r)?;
    let ul = local_unknowns(&frames, u);
    let (e, nu, kappa) = (material.e, material.nu, section.shear_factor);
    let c = e / (1. - nu * nu);
    let g = e / (1. + nu) / 2.;
    let ops = operators(xyz, &frames, section, &r);
    let npge = 3 * section.layers.max(1) as usize;
    let mut out = vec![[0.; 6]; ops.len()];
    for (o, (b, _)) in ops.iter().enumerate() {
        let eps: Vec<f64> = b
            .iter()
            .map(|row| row.iter().zip(&ul).map(|(x, y)| x * y).sum())
            .collect();
        let (lp, q) = (o / NPGSN, o % NPGSN);
        out[q * npge + lp] = [
            c * (eps[0] + nu * eps[1]),
            c * (nu * eps[0] + eps[1]),
            0.,
            g * eps[2],
            kappa * g * eps[3],
            kappa * g * eps[4],
        ];
    }
    Ok(out)
}

/// The load of a pressure on the mid-surface (`te0403` → `fpres`,
/// `CHAR_MECA_PRES_R`): `pres` at the eight edge nodes, acting against
/// each node's normal n (a positive pressure pushes along −n), interpolated
/// with the QUAD8 functions at the FPG9COQ points, times |a₁×a₂| there;
/// forces on the translations only (the nodal moments are zero, and
/// `fpres`'s correction by `kijkm1` reads a part of the reference data no
/// routine writes: zero). 51 values, the order of [`stiffness`].
pub fn pressure_load(xyz: &[V3; NB1], pres: &[f64; NB1]) -> Result<Vec<f64>, String> {
    let r = RefQuad9::new();
    let frames = nodal_frames(xyz, &r)?;
    let mut f = vec![0.; NDDL];
    for q in 0..NPGSN {
        let s = &r.g8n[q];
        let mut a1 = [0.; 3];
        let mut a2 = [0.; 3];
        let mut chg = [0.; 3];
        for k in 0..3 {
            for j in 0..NB1 {
                a1[k] += s.d1[j] * xyz[j][k];
                a2[k] += s.d2[j] * xyz[j][k];
                chg[k] += -pres[j] * frames[j][2][k] * s.f[j];
            }
        }
        let rnormc = norm(cross(a1, a2));
        for i in 0..NB1 {
            for k in 0..3 {
                f[6 * i + k] += r.wn[q] * chg[k] * s.f[i] * rnormc;
            }
        }
    }
    Ok(f)
}

/// `coqrep` then `vdrepe`: the cosine and sine of the user's x axis (the
/// projection of `direction` on the plane of `frame`) in `frame`'s
/// (t₁, t₂), normalised as code_aster does (twice, each time `s` with the
/// already normalised `c`).
fn user_angle(frame: &[V3; 3], direction: V3) -> Result<(f64, f64), String> {
    let n = frame[2];
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let ps = dot(direction, n);
    let pj = [0, 1, 2].map(|k| direction[k] - ps * n[k]);
    let norm_pj = norm(pj);
    if norm_pj <= f64::EPSILON {
        return Err(
            "a COQUE_3D cell whose reference direction (ANGL_REP/VECTEUR) is normal to it at a node: the stresses' frame is undefined".into(),
        );
    }
    let pj = pj.map(|v| v / norm_pj);
    let (mut c, mut s) = (dot(pj, frame[0]), dot(pj, frame[1]));
    for _ in 0..2 {
        c /= (c * c + s * s).sqrt();
        s /= (c * c + s * s).sqrt();
    }
    Ok((c, s))
}

/// `mamagi`: the least-squares extrapolation (12×27, row-major) from the
/// 27 points of a layer (bottom, middle, top × FPG9COQ) to its 12 nodal
/// values (bottom, middle, top × the four corners), bilinear in (ξ₁, ξ₂)
/// and quadratic through the layer.
fn extrapolation() -> Vec<f64> {
    let normal = fpg9coq();
    let psi3 = [-1., 0., 1.];
    let (at, bt3, ct) = ([0.5, -1., 0.5], [-0.5, 0., 0.5], [0., 1., 0.]);
    let (ca, cb, cc, cd) = (
        [0.25, 0.25, 0.25, 0.25],
        [-0.25, 0.25, 0.25, -0.25],
        [-0.25, -0.25, 0.25, 0.25],
        [0.25, -0.25, 0.25, -0.25],
    );
    let mut bt = [[0.; 27]; 12];
    for (integ, &x3) in psi3.iter().enumerate() {
        for (q, &(x1, x2)) in normal.iter().enumerate() {
            let ig = 9 * integ + q;
            for intef in 0..3 {
                for ifon in 0..4 {
                    bt[4 * intef + ifon][ig] = (at[intef] * x3 * x3 + bt3[intef] * x3 + ct[intef])
                        * (ca[ifon] + cb[ifon] * x1 + cc[ifon] * x2 + cd[ifon] * x1 * x2);
                }
            }
        }
    }
    let btb = nalgebra::DMatrix::from_fn(12, 12, |i, j| (0..27).map(|k| bt[i][k] * bt[j][k]).sum());
    let rhs = nalgebra::DMatrix::from_fn(12, 27, |i, k| bt[i][k]);
    // BᵀB is the Gram matrix of 12 independent functions on 27 points:
    // positive definite.
    let x = btb
        .lu()
        .solve(&rhs)
        .unwrap_or_else(|| nalgebra::DMatrix::zeros(12, 27));
    (0..12 * 27).map(|o| x[(o / 27, o % 27)]).collect()
}

/// `SIGM_ELNO` (`te0040` → `elno_coq3d`): at each of the nine nodes, for
/// each layer its bottom, middle and top (`COQUE_NCOU`·3 sub-points),
/// SIXX SIYY SIZZ SIXY SIXZ SIYZ in the user's frame of the node (x the
/// projection of `direction` — `ANGL_REP`/`VECTEUR`, by default global X
/// — on the node's plane (t₁, t₂), `coqrep`/`vdrepe`/`vdsiro`). The
/// layer's 27 point values are extrapolated by least squares to the four
/// corners (`mamagi`), the mid-side nodes take the mean of their two
/// corners, the centre the mean of the four. code_aster stores
/// `SIEF_ELGA` turned into the user's frame of the first reduced point and
/// turns it back before extrapolating (`cosiro` 'IU' then 'UI' with the
/// same 2×2 rotation): the identity up to round-off, not repeated here.
pub fn sigm_elno(
    xyz: &[V3; NB1],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64; NDDL],
    direction: V3,
) -> Result<Vec<Vec<[f64; 6]>>, String> {
    let r = RefQuad9::new();
    let frames = nodal_frames(xyz, &r)?;
    let gauss = stresses(xyz, material, section, u)?;
    let nbcou = section.layers.max(1) as usize;
    let npge = 3 * nbcou;
    let matr = extrapolation();
    let mut out = vec![vec![[0.; 6]; npge]; NB2];
    for icou in 0..nbcou {
        // matpg of the layer: (inte, intsn) → code_aster's point order.
        let layer = |j: usize, ic: usize| {
            let (inte, q) = (j / NPGSN, j % NPGSN);
            gauss[q * npge + 3 * icou + inte][ic]
        };
        for lvl in 0..3 {
            let mut node = [[0.; 6]; NB2];
            for (corner, vals) in node.iter_mut().take(4).enumerate() {
                let i = 4 * lvl + corner;
                for (ic, v) in vals.iter_mut().enumerate() {
                    *v = (0..27).map(|j| matr[27 * i + j] * layer(j, ic)).sum();
                }
            }
            for ic in 0..6 {
                node[4][ic] = (node[0][ic] + node[1][ic]) / 2.;
                node[5][ic] = (node[1][ic] + node[2][ic]) / 2.;
                node[6][ic] = (node[2][ic] + node[3][ic]) / 2.;
                node[7][ic] = (node[3][ic] + node[0][ic]) / 2.;
                node[8][ic] = (node[0][ic] + node[1][ic] + node[2][ic] + node[3][ic]) / 4.;
            }
            for (n, t) in node.iter().enumerate() {
                let (c, s) = user_angle(&frames[n], direction)?;
                // Mᵀ·σ·M with M = [c −s; s c] (`vdsiro` 'IU').
                let (xx, yy, xy) = (t[0], t[1], t[3]);
                let m = [[c, -s], [s, c]];
                let a = [[xx, xy], [xy, yy]];
                let mut res = [[0.; 2]; 2];
                for i in 0..2 {
                    for j in 0..2 {
                        let mut v = 0.;
                        for k in 0..2 {
                            for l in 0..2 {
                                v += m[k][i] * a[k][l] * m[l][j];
                            }
                        }
                        res[i][j] = v;
                    }
                }
                out[n][3 * icou + lvl] = [
                    res[0][0],
                    res[1][1],
                    t[2],
                    res[0][1],
                    t[4] * m[0][0] + t[5] * m[1][0],
                    t[4] * m[0][1] + t[5] * m[1][1],
                ];
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_are_partitions_of_unity_at_code_aster_nodes() {
        for (n, &(x, y)) in NODES9.iter().enumerate() {
            let s9 = qu9(x, y);
            for m in 0..9 {
                let want = if m == n { 1. } else { 0. };
                assert!((s9.f[m] - want).abs() < 1e-15);
            }
            if n < 8 {
                let s8 = qu8(x, y);
                for m in 0..8 {
                    let want = if m == n { 1. } else { 0. };
                    assert!((s8.f[m] - want).abs() < 1e-15);
                }
            }
            let s8 = qu8(0.3, -0.7);
            assert!((s8.d1.iter().sum::<f64>()).abs() < 1e-15);
            assert!((s8.d2.iter().sum::<f64>()).abs() < 1e-15);
        }
        // The extrapolation reproduces the reduced values at the reduced points.
        let r = RefQuad9::new();
        let s: f64 = r.extra.iter().map(|e| e.iter().sum::<f64>()).sum();
        assert!((s - 9.).abs() < 1e-12, "{s}");
    }

    #[test]
    fn extrapolation_is_exact_on_its_own_space() {
        // f = (1 + 2ξ₁ − ξ₂ + 0.5ξ₁ξ₂)·(3 − ζ + 2ζ²): bilinear in the plane,
        // quadratic through the layer, found again at the 4 corners × 3
        // levels from its 27 point values (mamagi's least squares).
        let f = |x: f64, y: f64, z: f64| (1. + 2. * x - y + 0.5 * x * y) * (3. - z + 2. * z * z);
        let matr = extrapolation();
        let pts = fpg9coq();
        let corners = [(-1., -1.), (1., -1.), (1., 1.), (-1., 1.)];
        for (lvl, z) in [-1., 0., 1.].into_iter().enumerate() {
            for (c, &(x, y)) in corners.iter().enumerate() {
                let i = 4 * lvl + c;
                let got: f64 = (0..27)
                    .map(|j| {
                        let (zj, (xj, yj)) = ([-1., 0., 1.][j / 9], pts[j % 9]);
                        matr[27 * i + j] * f(xj, yj, zj)
                    })
                    .sum();
                assert!((got - f(x, y, z)).abs() < 1e-12, "{lvl} {c}: {got}");
            }
        }
    }
}
