//! code_aster's `COQUE_3D` shell on QUAD9 (`MEC3QU9H`) and TRIA7
//! (`MEC3TR7H`): a degenerated solid with a quadratic mid-surface, six DOFs
//! (DX DY DZ DRX DRY DRZ) on the edge nodes and three rotations (DRX DRY
//! DRZ) on the central node, 51 DOFs in all on a QUAD9, 39 on a TRIA7
//! ([`Coque3dCell`]).
//!
//! Transcribed from code_aster's small-strain path of `te0414`
//! (`vdxnlr`, the routine `STAT_NON_LINE` calls for `RELATION='ELAS'`,
//! `DEFORMATION='PETIT'`) and the routines it calls:
//! - reference data (`jni080`): QUAD8 functions for the geometry and the
//!   translations, QUAD9 functions for the rotations, the reduced rule
//!   FPG4 (±1/√3) and the normal rule `FPG9COQ` (3×3 Gauss, code_aster's
//!   point order), the bilinear extrapolation from the four reduced points
//!   to the nine normal ones (with code_aster's literal
//!   `0.577350269189626`); on the TRIA7 (jni080's triangle branch), TRIA6
//!   functions for the geometry and the translations, TRIA7 functions for
//!   the rotations, FPG3 and FPG7, the linear extrapolation written with
//!   the literals 0.166666666666667 and 0.666666666666667, the centre node
//!   at 0.333333333333333;
//! - nodal frames (`vectan`): at each node, the covariant vectors a₁, a₂
//!   of the QUAD8 (TRIA6) geometry, the unit normal n = a₁×a₂/|·|,
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
//!   diagonal over all the nodes, on each normal rotation;
//! - local → global (`tranlg`): the rotation triple of each node turned by
//!   its frame (t₁, t₂, n).
//!
//! Also: `SIEF_ELGA` by layer ([`stresses`]), `SIGM_ELNO` in the user's
//! frame ([`sigm_elno`], `elno_coq3d`) and the pressure load
//! ([`pressure_load`], `fpres`; [`surface_load`], `fsurf`). docs/fem.md lists the routines and the
//! measurements.
//!
//! Numerics only: no keyword is read here. The model carries it as
//! [`crate::ElementKind::Coque3d`] (the central node numbered with its
//! three rotations alone); the runner wires `MODELISATION='COQUE_3D'` on
//! QUAD9 and TRIA7 cells to it.

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
    /// The rule through the thickness of the stiffness ([`ThicknessRule`]).
    pub rule: ThicknessRule,
}

/// The rule through the thickness of the COQUE_3D stiffness: code_aster
/// computes `RIGI_MECA` (`MECA_STATIQUE`: `te0401` → `vdxrig`) and the
/// tangent matrix of `STAT_NON_LINE` (`te0414` → `vdxnlr`) with two
/// different rules. On a flat cell both are exact (the integrand is a
/// polynomial of degree 2 in ξ₃); on a curved one the Jacobian varies
/// through the thickness and they differ (ssls114a's TRIA7 cylinder: 2.6e-5
/// on the displacements).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ThicknessRule {
    /// `vdxnlr`: `COQUE_NCOU` layers, each with Simpson's three points
    /// (weights 1/3, 4/3, 1/3), the layer's thickness in the Jacobian.
    #[default]
    Simpson,
    /// `vdxrig`: two Gauss points ξ₃ = ±0.577350269189626 (code_aster's
    /// literal), weights 1, over the whole thickness (the layers play no
    /// part).
    Gauss2,
}

impl Coque3dSection {
    /// A section of thickness `h` with code_aster's defaults.
    pub fn new(thickness: f64) -> Coque3dSection {
        Coque3dSection {
            thickness,
            drilling: 1e-5,
            shear_factor: DEFAULT_SHEAR_FACTOR,
            layers: 1,
            rule: ThicknessRule::Simpson,
        }
    }
}

/// The two cells of `COQUE_3D`: code_aster's `MEC3QU9H` (QUAD9) and
/// `MEC3TR7H` (TRIA7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coque3dCell {
    /// QUAD9: QUAD8 geometry, QUAD9 rotations, FPG4 / FPG9COQ.
    Quad9,
    /// TRIA7: TRIA6 geometry, TRIA7 rotations, FPG3 / FPG7.
    Tria7,
}

impl Coque3dCell {
    /// The cell whose geometry has `n` edge nodes (8: QUAD9, 6: TRIA7).
    pub fn of_edge_nodes(n: usize) -> Result<Coque3dCell, String> {
        match n {
            8 => Ok(Coque3dCell::Quad9),
            6 => Ok(Coque3dCell::Tria7),
            _ => Err(format!(
                "a COQUE_3D cell has 8 (QUAD9) or 6 (TRIA7) edge nodes, not {n}"
            )),
        }
    }

    /// Edge nodes (`nb1`: the QUAD8 / TRIA6 part).
    pub const fn edge_nodes(self) -> usize {
        match self {
            Coque3dCell::Quad9 => 8,
            Coque3dCell::Tria7 => 6,
        }
    }

    /// All nodes (`nb2`), the centre last.
    pub const fn nodes(self) -> usize {
        self.edge_nodes() + 1
    }

    /// Global DOFs: 6 per edge node, 3 at the centre.
    pub const fn dofs(self) -> usize {
        6 * self.edge_nodes() + 3
    }

    /// Corners (`nso`).
    const fn corners(self) -> usize {
        match self {
            Coque3dCell::Quad9 => 4,
            Coque3dCell::Tria7 => 3,
        }
    }
}

/// Global DOFs of a QUAD9: 6 per edge node, 3 at the centre.
pub const NDDL: usize = Coque3dCell::Quad9.dofs();

/// Values and derivatives of shape functions at one point (at most nine
/// functions; the unused ones stay zero).
#[derive(Clone, Copy)]
struct Shape {
    f: [f64; 9],
    d1: [f64; 9],
    d2: [f64; 9],
}

fn qu8(x: f64, y: f64) -> Shape {
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
            0.,
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
            0.,
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
            0.,
        ],
    }
}

fn qu9(x: f64, y: f64) -> Shape {
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

/// The TRIA6 (`jni080`'s geometry functions) or TRIA7 (its rotation
/// functions: the TRIA6 ones corrected by the centre's bubble
/// 27·ξ₁ξ₂(1 − ξ₁ − ξ₂)) at (ξ₁, ξ₂), code_aster's node order (1 at
/// (0, 0), 2 at (1, 0), 3 at (0, 1), the mid-sides 1–2, 2–3, 3–1, the
/// centre): [`crate::shape::shape`]'s, which are `jni080`'s polynomials.
fn triangle(ty: aster_mesh::CellType, xi1: f64, xi2: f64) -> Shape {
    let at = crate::shape::shape(ty, [xi1, xi2, 0.]);
    let mut s = Shape {
        f: [0.; 9],
        d1: [0.; 9],
        d2: [0.; 9],
    };
    for (k, (&n, dn)) in at.n.iter().zip(&at.dn).enumerate().take(9) {
        s.f[k] = n;
        s.d1[k] = dn[0];
        s.d2[k] = dn[1];
    }
    s
}

fn tr6(xi1: f64, xi2: f64) -> Shape {
    triangle(aster_mesh::CellType::TRIA6, xi1, xi2)
}

fn tr7(xi1: f64, xi2: f64) -> Shape {
    triangle(aster_mesh::CellType::TRIA7, xi1, xi2)
}

/// The reference data of `MEC3QU9H` / `MEC3TR7H` (`jni080`).
struct RefElement {
    cell: Coque3dCell,
    /// Edge nodes (`nb1`).
    nb1: usize,
    /// All nodes (`nb2`).
    nb2: usize,
    /// The normal points (FPG9COQ, FPG7).
    normal: Vec<(f64, f64)>,
    /// Weights of the normal points.
    wn: Vec<f64>,
    /// Geometry functions (QUAD8, TRIA6) at the reduced points.
    gr: Vec<Shape>,
    /// Geometry functions at the normal points.
    gn: Vec<Shape>,
    /// Rotation functions (QUAD9, TRIA7) at the reduced points.
    rr: Vec<Shape>,
    /// Rotation functions at the normal points.
    rn: Vec<Shape>,
    /// Geometry functions at the nodes (the nodal frames).
    gnodes: Vec<Shape>,
    /// Extrapolation from the reduced to the normal points.
    extra: Vec<Vec<f64>>,
    /// Extrapolation from the reduced points to the edge nodes (`jni080`'s
    /// `fcesnd` 'LI' at the nodes, `.DESR` from 1452: `vdefge`).
    extra_nodes: Vec<Vec<f64>>,
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

/// The seven nodes of the reference TRIA7 as `jni080` writes them (its
/// literal 0.333333333333333 for the centre).
const NODES7: [(f64, f64); 7] = [
    (0., 0.),
    (1., 0.),
    (0., 1.),
    (0.5, 0.),
    (0.5, 0.5),
    (0., 0.5),
    (0.333333333333333, 0.333333333333333),
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

/// `FPG7` of the triangle (`elraga`: the centre, then two orbits of
/// three points), with its weights.
fn fpg7() -> (Vec<(f64, f64)>, Vec<f64>) {
    crate::fpg::tria_fpg7()
        .iter()
        .map(|p| ((p.xi[0], p.xi[1]), p.weight))
        .unzip()
}

/// The functions of one cell family: geometry (QUAD8, TRIA6), rotations
/// (QUAD9, TRIA7).
type ShapeFn = fn(f64, f64) -> Shape;

impl RefElement {
    fn new(cell: Coque3dCell) -> RefElement {
        match cell {
            Coque3dCell::Quad9 => {
                let a = (1f64 / 3.).sqrt();
                let reduced = [(-a, -a), (a, -a), (a, a), (-a, a)];
                let (c, m, z) = (25. / 81., 40. / 81., 64. / 81.);
                let aa = 0.577350269189626;
                let extra = |x: f64, y: f64| {
                    vec![
                        0.75 * (aa - x) * (aa - y),
                        0.75 * (aa + x) * (aa - y),
                        0.75 * (aa + x) * (aa + y),
                        0.75 * (aa - x) * (aa + y),
                    ]
                };
                let normal = fpg9coq().to_vec();
                let wn = vec![c, m, c, m, c, m, c, m, z];
                let shapes: (ShapeFn, ShapeFn) = (qu8, qu9);
                RefElement::of(cell, &reduced, (normal, wn), &NODES9, shapes, extra)
            }
            Coque3dCell::Tria7 => {
                // FPG3 (`elraga`: un/6, deux/3).
                let reduced = [(1. / 6., 1. / 6.), (2. / 3., 1. / 6.), (1. / 6., 2. / 3.)];
                // jni080's linear extrapolation from FPG3, its literals.
                let (a, b) = (0.166666666666667, 0.666666666666667);
                let extra =
                    |x: f64, y: f64| vec![2. * (-(x - b) - (y - a)), 2. * (x - a), 2. * (y - a)];
                let shapes: (ShapeFn, ShapeFn) = (tr6, tr7);
                RefElement::of(cell, &reduced, fpg7(), &NODES7, shapes, extra)
            }
        }
    }

    /// The reference data from the reduced points, the normal points and
    /// their weights, the nodes, the geometry and rotation functions and
    /// the extrapolation from the reduced to a normal point.
    fn of(
        cell: Coque3dCell,
        reduced: &[(f64, f64)],
        (normal, wn): (Vec<(f64, f64)>, Vec<f64>),
        nodes: &[(f64, f64)],
        (geometry, rotation): (ShapeFn, ShapeFn),
        extra: impl Fn(f64, f64) -> Vec<f64>,
    ) -> RefElement {
        let at = |f: ShapeFn, pts: &[(f64, f64)]| pts.iter().map(|&(x, y)| f(x, y)).collect();
        RefElement {
            cell,
            nb1: cell.edge_nodes(),
            nb2: cell.nodes(),
            wn,
            gr: at(geometry, reduced),
            gn: at(geometry, &normal),
            rr: at(rotation, reduced),
            rn: at(rotation, &normal),
            gnodes: at(geometry, nodes),
            extra: normal.iter().map(|&(x, y)| extra(x, y)).collect(),
            extra_nodes: nodes[..cell.edge_nodes()]
                .iter()
                .map(|&(x, y)| extra(x, y))
                .collect(),
            normal,
        }
    }

    /// Reduced points (`npgsr`).
    fn npgsr(&self) -> usize {
        self.gr.len()
    }

    /// Normal points (`npgsn`).
    fn npgsn(&self) -> usize {
        self.gn.len()
    }

    /// Local DOFs before the drilling ones: 5 per edge node, 2 at the
    /// centre (`nddle`).
    fn nddle(&self) -> usize {
        5 * self.nb1 + 2
    }

    /// Global DOFs.
    fn nddl(&self) -> usize {
        6 * self.nb1 + 3
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
fn nodal_frames(xyz: &[V3], r: &RefElement) -> Result<Vec<[V3; 3]>, String> {
    let mut frames = vec![[[0.; 3]; 3]; r.nb2];
    for (i, fr) in frames.iter_mut().enumerate() {
        let s = &r.gnodes[i];
        let mut a1 = [0.; 3];
        let mut a2 = [0.; 3];
        for k in 0..3 {
            for j in 0..r.nb1 {
                a1[k] += s.d1[j] * xyz[j][k];
                a2[k] += s.d2[j] * xyz[j][k];
            }
        }
        let n = cross(a1, a2);
        let (rn, r1) = (norm(n), norm(a1));
        if !(rn > 0. && r1 > 0.) {
            return Err(format!(
                "a COQUE_3D cell is degenerate at its node {} (zero covariant vector): nodes {xyz:?}",
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
    s: &Shape,
    xyz: &[V3],
    normals: &[V3],
    ksi3s2: f64,
    epais: f64,
) -> ([V3; 3], [[f64; 3]; 3], f64) {
    let mut t3 = [0.; 3];
    let mut g1 = [0.; 3];
    let mut g2 = [0.; 3];
    for k in 0..3 {
        for j in 0..xyz.len() {
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
    s9: &Shape,
    frames: &[[V3; 3]],
    ksi3s2: f64,
    epais: f64,
) -> Vec<([f64; 9], usize)> {
    let nb1 = frames.len() - 1;
    let mut cols = Vec::with_capacity(2 * frames.len());
    for (j, frame) in frames.iter().enumerate() {
        let (t1, t2) = (frame[0], frame[1]);
        let base = if j < nb1 { 5 * j + 3 } else { 5 * nb1 };
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

/// The 5×`nddle` strain operator (5×42 on a QUAD9, 5×32 on a TRIA7) at
/// every (layer point, normal point), with its weight: `btdmsr` on the
/// reduced points, `btdfn` on the normal ones, combined by `btdmsn`
/// (IND=1); through the thickness by `rule` ([`ThicknessRule`]).
fn operators(
    xyz: &[V3],
    frames: &[[V3; 3]],
    section: &Coque3dSection,
    r: &RefElement,
    rule: ThicknessRule,
) -> Vec<(Vec<Vec<f64>>, f64)> {
    let normals: Vec<V3> = frames.iter().map(|f| f[2]).collect();
    let gauss2 = rule == ThicknessRule::Gauss2;
    // vdxrig: one "layer", the whole thickness.
    let nbcou = if gauss2 {
        1
    } else {
        section.layers.max(1) as usize
    };
    let hic = section.thickness / nbcou as f64;
    let zmin = -section.thickness / 2.;
    let (nddle, npgsr) = (r.nddle(), r.npgsr());
    let npge = if gauss2 { 2 } else { 3 };
    let mut out = Vec::with_capacity(nbcou * npge * r.npgsn());
    for icou in 0..nbcou {
        for inte in 0..npge {
            let (ksi3s2, coef) = if gauss2 {
                // vdxrig's epsval, weight 1.
                ([-0.577350269189626, 0.577350269189626][inte] / 2., 1.)
            } else {
                let (zic, coef) = match inte {
                    0 => (zmin + icou as f64 * hic, 1. / 3.),
                    1 => (zmin + hic / 2. + icou as f64 * hic, 4. / 3.),
                    _ => (zmin + hic + icou as f64 * hic, 1. / 3.),
                };
                (zic / hic, coef)
            };
            // Reduced points: membrane (translations only) and shear rows.
            let mut btdm = vec![[vec![0.; nddle], vec![0.; nddle], vec![0.; nddle]]; npgsr];
            let mut btds = vec![[vec![0.; nddle], vec![0.; nddle]]; npgsr];
            for p in 0..npgsr {
                let s8 = &r.gr[p];
                let (t, jm1, _) = point_frame(s8, xyz, &normals, ksi3s2, hic);
                let (hm, hs) = hfmss(&t, true);
                let hm = times_jinv(&hm, &jm1);
                let hs = times_jinv(&hs, &jm1);
                for jb in 0..r.nb1 {
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
                for (c, col) in rotation_columns(&r.rr[p], frames, ksi3s2, hic) {
                    for i in 0..2 {
                        btds[p][i][col] = (0..9).map(|k| hs[i][k] * c[k]).sum();
                    }
                }
            }
            // Normal points: bending rows and the extrapolated rest.
            for q in 0..r.npgsn() {
                let (t, jm1, det) = point_frame(&r.gn[q], xyz, &normals, ksi3s2, hic);
                let (hf, _) = hfmss(&t, false);
                let hf = times_jinv(&hf, &jm1);
                let wgt = coef * (r.wn[q] * det);
                let mut btdf = [vec![0.; nddle], vec![0.; nddle], vec![0.; nddle]];
                for (c, col) in rotation_columns(&r.rn[q], frames, ksi3s2, hic) {
                    for (i, row) in btdf.iter_mut().enumerate() {
                        row[col] = (0..9).map(|k| hf[i][k] * c[k]).sum();
                    }
                }
                let e = &r.extra[q];
                let mut b = vec![vec![0.; nddle]; 5];
                for j in 0..nddle {
                    for i in 0..2 {
                        let mut m = 0.;
                        let mut s = 0.;
                        for k in 0..npgsr {
                            m += e[k] * btdm[k][i][j];
                            s += e[k] * btds[k][i][j];
                        }
                        b[i][j] = m + btdf[i][j];
                        b[i + 3][j] = s;
                    }
                    let mut m = 0.;
                    for k in 0..npgsr {
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

/// The element's stiffness in its local rotation frames, `nddl`² (51×51
/// on a QUAD9, 39×39 on a TRIA7: `matrkb` on `vdxnlr`'s `ktild`), and the
/// drilling coefficient.
fn local_stiffness(
    xyz: &[V3],
    frames: &[[V3; 3]],
    material: &Elastic,
    section: &Coque3dSection,
    r: &RefElement,
) -> (Vec<f64>, f64) {
    let d = dtild(material, section.shear_factor);
    let (nb1, nddle, nddl) = (r.nb1, r.nddle(), r.nddl());
    let mut kt = vec![0.; nddle * nddle];
    for (b, wgt) in operators(xyz, frames, section, r, section.rule) {
        // wmatcb = (wgt·D)·B
        let mut db = vec![vec![0.; nddle]; 5];
        for i in 0..5 {
            for j in 0..nddle {
                let mut s = 0.;
                for k in 0..5 {
                    s += d[i][k] * wgt * b[k][j];
                }
                db[i][j] = s;
            }
        }
        for i in 0..nddle {
            for j in 0..nddle {
                let mut s = 0.;
                for k in 0..5 {
                    s += b[k][i] * db[k][j];
                }
                kt[i * nddle + j] += s;
            }
        }
    }
    // matrkb: 5 per edge node (+ a drilling row), 2 (+1) at the centre.
    let mut xmin = 1. / f64::EPSILON;
    for n in 0..r.nb2 {
        let r0 = if n < nb1 { 5 * n + 3 } else { 5 * nb1 };
        for a in 0..2 {
            xmin = xmin.min(kt[(r0 + a) * nddle + r0 + a]);
        }
    }
    let coef = section.drilling * xmin;
    let local_of = |i: usize| {
        if i < 5 * nb1 {
            6 * (i / 5) + i % 5
        } else {
            6 * nb1 + (i - 5 * nb1)
        }
    };
    let mut k = vec![0.; nddl * nddl];
    for i in 0..nddle {
        for j in 0..nddle {
            k[local_of(i) * nddl + local_of(j)] = kt[i * nddle + j];
        }
    }
    for n in 0..nb1 {
        k[(6 * n + 5) * nddl + 6 * n + 5] = coef;
    }
    k[(nddl - 1) * nddl + nddl - 1] = coef;
    (k, coef)
}

/// The reference data of the cell whose edge nodes are `xyz`.
/// code_aster's alternative drilling formulation (a negative
/// `COEF_RIGI_DRZ`) is not reproduced for COQUE_3D: an error.
fn check_drilling(section: &Coque3dSection) -> Result<(), String> {
    if section.drilling < 0. || section.drilling.is_nan() {
        return Err(format!(
            "COEF_RIGI_DRZ = {} < 0 selects code_aster's alternative drilling formulation, which is not reproduced for COQUE_3D",
            section.drilling
        ));
    }
    Ok(())
}

fn reference(xyz: &[V3]) -> Result<RefElement, String> {
    Ok(RefElement::new(Coque3dCell::of_edge_nodes(xyz.len())?))
}

/// The global stiffness of a COQUE_3D cell, row-major `nddl`² (51×51 on
/// a QUAD9, 39×39 on a TRIA7), DOFs node-major: DX DY DZ DRX DRY DRZ of
/// the edge nodes, then DRX DRY DRZ of the central node. `xyz` are the
/// edge nodes (8 for a QUAD9, 6 for a TRIA7; the central node's position
/// plays no part: code_aster's geometry is the QUAD8's / TRIA6's).
pub fn stiffness(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
) -> Result<Vec<f64>, String> {
    check_drilling(section)?;
    let r = reference(xyz)?;
    let frames = nodal_frames(xyz, &r)?;
    let (kl, _) = local_stiffness(xyz, &frames, material, section, &r);
    let (nb1, nddl) = (r.nb1, r.nddl());
    // P: global → local (rotation triples turned by each node's frame).
    let mut p = vec![0.; nddl * nddl];
    for n in 0..nb1 {
        for a in 0..3 {
            p[(6 * n + a) * nddl + 6 * n + a] = 1.;
            for b in 0..3 {
                p[(6 * n + 3 + a) * nddl + 6 * n + 3 + b] = frames[n][a][b];
            }
        }
    }
    for a in 0..3 {
        for b in 0..3 {
            p[(6 * nb1 + a) * nddl + 6 * nb1 + b] = frames[nb1][a][b];
        }
    }
    // Pᵀ·K·P (the products skip nothing but exact zeros: `tranlg`'s sums)
    let p = nalgebra::DMatrix::from_row_slice(nddl, nddl, &p);
    let kl = nalgebra::DMatrix::from_row_slice(nddl, nddl, &kl);
    let kg = p.transpose() * kl * p;
    let kg: Vec<f64> = kg.transpose().iter().copied().collect();
    Ok(kg)
}

/// The global mass of a COQUE_3D cell of density `rho` (code_aster's
/// `te0406`, option `MASS_MECA`), row-major `nddl`², the DOFs of
/// [`stiffness`]: ρ ∫ Nᵀ N over two points through the thickness
/// (ξ₃ = ±1/√3) and the normal points, N (`matrn`) the displacement
/// u = Σ Nⱼ uⱼ + h ξ₃/2 Σ Rⱼ θⱼ × nⱼ (serendipity functions on the
/// translations, QUAD9/TRIA7 ones on the rotations, nⱼ the nodal normals),
/// weighted by the 3D Jacobian at that level (`jacbm1`); then the drilling
/// term `COEF_RIGI_DRZ` × the least in-plane rotational diagonal (each
/// node's rotation block turned to its frame t₁, t₂, n) added as that
/// value times n nᵀ on every node's rotations.
pub fn mass(xyz: &[V3], rho: f64, section: &Coque3dSection) -> Result<Vec<f64>, String> {
    check_drilling(section)?;
    let r = reference(xyz)?;
    let frames = nodal_frames(xyz, &r)?;
    let normals: Vec<V3> = frames.iter().map(|f| f[2]).collect();
    let (nb1, nddl, h) = (r.nb1, r.nddl(), section.thickness);
    let mut mas = nalgebra::DMatrix::<f64>::zeros(nddl, nddl);
    let mut matn = nalgebra::DMatrix::<f64>::zeros(3, nddl);
    for level in [-1. / 3f64.sqrt(), 1. / 3f64.sqrt()] {
        let ksi3s2 = level / 2.;
        for q in 0..r.npgsn() {
            let (_, _, det) = point_frame(&r.gn[q], xyz, &normals[..nb1], ksi3s2, h);
            matn.fill(0.);
            for (jn, n) in normals.iter().enumerate() {
                // antisy(n): n × θ.
                let anti = [[0., -n[2], n[1]], [n[2], 0., -n[0]], [-n[1], n[0], 0.]];
                let c = -h * ksi3s2 * r.rn[q].f[jn];
                let rot = if jn < nb1 {
                    for k in 0..3 {
                        matn[(k, 6 * jn + k)] = r.gn[q].f[jn];
                    }
                    6 * jn + 3
                } else {
                    6 * nb1
                };
                for i in 0..3 {
                    for j in 0..3 {
                        matn[(i, rot + j)] = c * anti[i][j];
                    }
                }
            }
            mas += matn.transpose() * &matn * (rho * r.wn[q] * det);
        }
    }
    let block = |n: usize| if n < nb1 { 6 * n + 3 } else { 6 * nb1 };
    let mut xmin = f64::INFINITY;
    for (n, fr) in frames.iter().enumerate() {
        let b = block(n);
        let masrg = mas.fixed_view::<3, 3>(b, b).into_owned();
        for t in &fr[..2] {
            let t = nalgebra::Vector3::from(*t);
            xmin = xmin.min((t.transpose() * masrg * t)[(0, 0)]);
        }
    }
    let mnn = section.drilling * xmin;
    for (n, fr) in frames.iter().enumerate() {
        let (b, v) = (block(n), fr[2]);
        for i in 0..3 {
            for j in 0..3 {
                mas[(b + i, b + j)] += mnn * v[i] * v[j];
            }
        }
    }
    Ok(mas.transpose().iter().copied().collect())
}

/// The mass, centre of gravity and inertia about it (`[Ixx, Iyy, Izz, Ixy,
/// Ixz, Iyz]`, products +∫ρ x y) of a COQUE_3D cell (code_aster's
/// `te0417`, option `MASS_INER`): on the normal points, the mid-surface
/// point x and the interpolated nodal normal n (not normalised), weights
/// w |a₁ × a₂| (`vectci`); volume Σ h w, first moments Σ h w x, second
/// moments Σ w (h xᵢxⱼ + h³/12 nᵢnⱼ).
pub fn mass_inertia(xyz: &[V3], rho: f64, h: f64) -> Result<(f64, V3, [f64; 6]), String> {
    let r = reference(xyz)?;
    let frames = nodal_frames(xyz, &r)?;
    let mut volume = 0.;
    let mut first = [0.; 3];
    let mut second = [[0.; 3]; 3];
    for q in 0..r.npgsn() {
        let s = &r.gn[q];
        let (mut a1, mut a2, mut x, mut n) = ([0.; 3], [0.; 3], [0.; 3], [0.; 3]);
        for k in 0..3 {
            for j in 0..r.nb1 {
                a1[k] += s.d1[j] * xyz[j][k];
                a2[k] += s.d2[j] * xyz[j][k];
                x[k] += s.f[j] * xyz[j][k];
                n[k] += s.f[j] * frames[j][2][k];
            }
        }
        let wgt = r.wn[q] * norm(cross(a1, a2));
        volume += h * wgt;
        for k in 0..3 {
            first[k] += h * wgt * x[k];
            for l in 0..3 {
                second[k][l] += h * wgt * x[k] * x[l] + h.powi(3) / 12. * wgt * n[k] * n[l];
            }
        }
    }
    if volume.is_nan() || volume <= 0. {
        return Err("a COQUE_3D cell of zero area".into());
    }
    let m = rho * volume;
    let g = first.map(|v| v / volume);
    let ii = |k: usize| rho * second[k][k];
    Ok((
        m,
        g,
        [
            ii(1) + ii(2) - m * (g[1] * g[1] + g[2] * g[2]),
            ii(0) + ii(2) - m * (g[0] * g[0] + g[2] * g[2]),
            ii(0) + ii(1) - m * (g[0] * g[0] + g[1] * g[1]),
            rho * second[0][1] - m * g[0] * g[1],
            rho * second[0][2] - m * g[0] * g[2],
            rho * second[1][2] - m * g[1] * g[2],
        ],
    ))
}

/// The local unknowns of `vdxnlr` (`trndgl`): the translations as they
/// are, each node's rotation θ as (t₁·θ, t₂·θ); `nddle` values.
fn local_unknowns(frames: &[[V3; 3]], u: &[f64]) -> Vec<f64> {
    let nb1 = frames.len() - 1;
    let mut l = vec![0.; 5 * nb1 + 2];
    let dot = |t: V3, o: usize| t[0] * u[o] + t[1] * u[o + 1] + t[2] * u[o + 2];
    for n in 0..nb1 {
        l[5 * n..5 * n + 3].copy_from_slice(&u[6 * n..6 * n + 3]);
        l[5 * n + 3] = dot(frames[n][0], 6 * n + 3);
        l[5 * n + 4] = dot(frames[n][1], 6 * n + 3);
    }
    l[5 * nb1] = dot(frames[nb1][0], 6 * nb1);
    l[5 * nb1 + 1] = dot(frames[nb1][1], 6 * nb1);
    l
}

/// Checks that `u` has the cell's `nddl` values.
fn check_dofs(r: &RefElement, u: &[f64]) -> Result<(), String> {
    if u.len() == r.nddl() {
        Ok(())
    } else {
        Err(format!(
            "a COQUE_3D {:?} cell has {} DOFs, {} values given",
            r.cell,
            r.nddl(),
            u.len()
        ))
    }
}

/// `vdesga`/`matrc` for `ELAS`: the stresses SIXX SIYY SIZZ SIXY SIXZ SIYZ
/// (SIZZ = 0) of the five strains of the operator (engineering shears), the
/// transverse shears weighted by `A_CIS` (`kappa`).
fn layer_stress(material: &Elastic, kappa: f64, eps: &[f64]) -> [f64; 6] {
    let (e, nu) = (material.e, material.nu);
    let c = e / (1. - nu * nu);
    let g = e / (1. + nu) / 2.;
    [
        c * (eps[0] + nu * eps[1]),
        c * (nu * eps[0] + eps[1]),
        0.,
        g * eps[2],
        kappa * g * eps[3],
        kappa * g * eps[4],
    ]
}

/// The stresses of `SIEF_ELGA` from the global displacements `u` (the
/// order of [`stiffness`]): SIXX SIYY SIZZ SIXY SIXZ SIYZ in each point's
/// local frame (`vectgt`: t₁ along ∂x/∂ξ₁), SIZZ = 0, in code_aster's
/// order — normal point (FPG9COQ, FPG7) major, then layer, then the
/// layer's bottom, middle and top (`vdxnlr`'s `k1`).
pub fn stresses(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64],
) -> Result<Vec<[f64; 6]>, String> {
    let r = reference(xyz)?;
    check_dofs(&r, u)?;
    let frames = nodal_frames(xyz, &r)?;
    let ul = local_unknowns(&frames, u);
    let kappa = section.shear_factor;
    let ops = operators(xyz, &frames, section, &r, ThicknessRule::Simpson);
    let npge = 3 * section.layers.max(1) as usize;
    let npgsn = r.npgsn();
    let mut out = vec![[0.; 6]; ops.len()];
    for (o, (b, _)) in ops.iter().enumerate() {
        let eps: Vec<f64> = b
            .iter()
            .map(|row| row.iter().zip(&ul).map(|(x, y)| x * y).sum())
            .collect();
        let (lp, q) = (o / npgsn, o % npgsn);
        out[q * npge + lp] = layer_stress(material, kappa, &eps);
    }
    Ok(out)
}

/// The load of a pressure on the mid-surface (`te0403` → `fpres`,
/// `CHAR_MECA_PRES_R`): `pres` at the edge nodes, acting against each
/// node's normal n (a positive pressure pushes along −n): the force
/// −pᵢ nᵢ at each node, integrated as [`surface_load`]. `nddl` values, the
/// order of [`stiffness`].
pub fn pressure_load(xyz: &[V3], pres: &[f64]) -> Result<Vec<f64>, String> {
    let r = reference(xyz)?;
    if pres.len() != r.nb1 {
        return Err(format!(
            "a COQUE_3D pressure needs {} nodal values, {} given",
            r.nb1,
            pres.len()
        ));
    }
    let frames = nodal_frames(xyz, &r)?;
    let forces: Vec<V3> = (0..r.nb1)
        .map(|j| frames[j][2].map(|n| -pres[j] * n))
        .collect();
    surface_load(xyz, &forces)
}

/// The normal at each edge node of a COQUE_3D cell (`vectan`'s `vectn`),
/// the direction a pressure acts against ([`pressure_load`]).
pub fn node_normals(xyz: &[V3]) -> Result<Vec<V3>, String> {
    let r = reference(xyz)?;
    Ok(nodal_frames(xyz, &r)?
        .iter()
        .take(r.nb1)
        .map(|f| f[2])
        .collect())
}

/// The load of a force per unit area on the mid-surface (`te0403` →
/// `fsurf`, `CHAR_MECA_FRCO3D` with global components; `fpres` is the
/// same with −p n): `forces` (global) at the edge nodes, interpolated
/// with the QUAD8 / TRIA6 functions at the normal points (FPG9COQ, FPG7),
/// times |a₁×a₂| there, on the translations only (`forsrg`'s correction
/// by `kijkm1` reads a part of the reference data no routine writes:
/// zero). `nddl` values, the order of [`stiffness`].
pub fn surface_load(xyz: &[V3], forces: &[V3]) -> Result<Vec<f64>, String> {
    let r = reference(xyz)?;
    if forces.len() != r.nb1 {
        return Err(format!(
            "a COQUE_3D surface load needs {} nodal values, {} given",
            r.nb1,
            forces.len()
        ));
    }
    let mut f = vec![0.; r.nddl()];
    for q in 0..r.npgsn() {
        let s = &r.gn[q];
        let mut a1 = [0.; 3];
        let mut a2 = [0.; 3];
        let mut chg = [0.; 3];
        for k in 0..3 {
            for j in 0..r.nb1 {
                a1[k] += s.d1[j] * xyz[j][k];
                a2[k] += s.d2[j] * xyz[j][k];
                chg[k] += forces[j][k] * s.f[j];
            }
        }
        let rnormc = norm(cross(a1, a2));
        for i in 0..r.nb1 {
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

/// The factor of code_aster's round trip of `SIEF_ELGA` through the
/// user's frame (`postcoq3d` stores it turned 'IU', `te0040`'s `cosiro`
/// turns it back 'UI' before `elno_coq3d`, both with the 2×2 matrix
/// [c −s; s c] of the first reduced point, `vdrepe`): that matrix comes
/// from `vectgt`'s frame at the point (ξ₃ = 0), whose t₃ is the
/// interpolated normal, not normalised, and t₂ = t₃×t₁ — not unit on a
/// curved cell. `coqrep` projects the direction with that t₃, takes
/// c = p·t₁, s = p·t₂ and normalises (c, s) twice as `user_angle` does,
/// which leaves c² + s² = λ ≠ 1; the round trip multiplies the in-plane
/// stresses by λ² and the transverse shears by λ. λ = 1 on a flat cell
/// and where the direction projects onto t₁ (s = 0).
fn round_trip_scale(
    xyz: &[V3],
    r: &RefElement,
    frames: &[[V3; 3]],
    direction: V3,
) -> Result<f64, String> {
    let normals: Vec<V3> = frames.iter().map(|f| f[2]).collect();
    // vectgt(0, …, ksi3s2 = 0, intsr = 1): epais plays no part at ξ₃ = 0.
    let (t, _, _) = point_frame(&r.gr[0], xyz, &normals, 0., 1.);
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let ps = dot(direction, t[2]);
    let pj = [0, 1, 2].map(|k| direction[k] - ps * t[2][k]);
    let norm_pj = norm(pj);
    if norm_pj <= f64::EPSILON {
        return Err(
            "a COQUE_3D cell whose reference direction (ANGL_REP/VECTEUR) is normal to it at its first reduced point: the stresses' frame is undefined".into(),
        );
    }
    let pj = pj.map(|v| v / norm_pj);
    let (mut c, mut s) = (dot(pj, t[0]), dot(pj, t[1]));
    // coqrep's normalisation, then vdrepe's: each `s` with the new `c`.
    for _ in 0..2 {
        c /= (c * c + s * s).sqrt();
        s /= (c * c + s * s).sqrt();
    }
    Ok(c * c + s * s)
}

/// `mamagi`: the least-squares extrapolation (3·nso × 3·npgsn, row-major)
/// from the points of a layer (bottom, middle, top × the normal points)
/// to its nodal values (bottom, middle, top × the corners), bilinear in
/// (ξ₁, ξ₂) on the QUAD9 (12×27), linear on the TRIA7 (9×21), quadratic
/// through the layer.
fn extrapolation(r: &RefElement) -> Vec<f64> {
    let psi3 = [-1., 0., 1.];
    let (at, bt3, ct) = ([0.5, -1., 0.5], [-0.5, 0., 0.5], [0., 1., 0.]);
    // coefa..coefd of each corner function.
    let coefs: &[[f64; 4]] = match r.cell {
        Coque3dCell::Quad9 => &[
            [0.25, -0.25, -0.25, 0.25],
            [0.25, 0.25, -0.25, -0.25],
            [0.25, 0.25, 0.25, 0.25],
            [0.25, -0.25, 0.25, -0.25],
        ],
        Coque3dCell::Tria7 => &[[1., -1., -1., 0.], [0., 1., 0., 0.], [0., 0., 1., 0.]],
    };
    let nso = coefs.len();
    let npgsn = r.normal.len();
    let (nrow, ncol) = (3 * nso, 3 * npgsn);
    let mut bt = vec![vec![0.; ncol]; nrow];
    for (integ, &x3) in psi3.iter().enumerate() {
        for (q, &(x1, x2)) in r.normal.iter().enumerate() {
            let ig = npgsn * integ + q;
            for intef in 0..3 {
                for (ifon, c) in coefs.iter().enumerate() {
                    bt[nso * intef + ifon][ig] =
                        (at[intef] * x3 * x3 + bt3[intef] * x3 + ct[intef])
                            * (c[0] + c[1] * x1 + c[2] * x2 + c[3] * x1 * x2);
                }
            }
        }
    }
    let btb = nalgebra::DMatrix::from_fn(nrow, nrow, |i, j| {
        (0..ncol).map(|k| bt[i][k] * bt[j][k]).sum()
    });
    let rhs = nalgebra::DMatrix::from_fn(nrow, ncol, |i, k| bt[i][k]);
    // BᵀB is the Gram matrix of independent functions on more points:
    // positive definite.
    let x = btb
        .lu()
        .solve(&rhs)
        .unwrap_or_else(|| nalgebra::DMatrix::zeros(nrow, ncol));
    (0..nrow * ncol).map(|o| x[(o / ncol, o % ncol)]).collect()
}

/// `SIGM_ELNO` (`te0040` → `elno_coq3d`): at each node (nine on a QUAD9,
/// seven on a TRIA7), for each layer its bottom, middle and top
/// (`COQUE_NCOU`·3 sub-points), SIXX SIYY SIZZ SIXY SIXZ SIYZ in the
/// user's frame of the node (x the projection of `direction` —
/// `ANGL_REP`/`VECTEUR`, by default global X — on the node's plane (t₁,
/// t₂), `coqrep`/`vdrepe`/`vdsiro`). The layer's point values are
/// extrapolated by least squares to the corners (`mamagi`), the mid-side
/// nodes take the mean of their two corners, the centre the mean of the
/// corners. code_aster stores `SIEF_ELGA` turned into the user's frame of
/// the first reduced point and turns it back before extrapolating
/// (`cosiro` 'IU' then 'UI' with the same 2×2 matrix): not the identity
/// on a curved cell ([`round_trip_scale`]), whose factor λ this applies
/// (λ² on SIXX SIYY SIXY, λ on SIXZ SIYZ).
pub fn sigm_elno(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64],
    direction: V3,
) -> Result<Vec<Vec<[f64; 6]>>, String> {
    let r = reference(xyz)?;
    let frames = nodal_frames(xyz, &r)?;
    let lambda = round_trip_scale(xyz, &r, &frames, direction)?;
    let gauss = stresses(xyz, material, section, u)?;
    let nbcou = section.layers.max(1) as usize;
    let npge = 3 * nbcou;
    let matr = extrapolation(&r);
    let (nso, npgsn) = (r.cell.corners(), r.npgsn());
    let ncol = 3 * npgsn;
    let mut out = vec![vec![[0.; 6]; npge]; r.nb2];
    for icou in 0..nbcou {
        // matpg of the layer: (inte, intsn) → code_aster's point order.
        let layer = |j: usize, ic: usize| {
            let (inte, q) = (j / npgsn, j % npgsn);
            gauss[q * npge + 3 * icou + inte][ic]
        };
        for lvl in 0..3 {
            let mut node = vec![[0.; 6]; r.nb2];
            for (corner, vals) in node.iter_mut().take(nso).enumerate() {
                let i = nso * lvl + corner;
                for (ic, v) in vals.iter_mut().enumerate() {
                    *v = (0..ncol).map(|j| matr[ncol * i + j] * layer(j, ic)).sum();
                }
            }
            for ic in 0..6 {
                match r.cell {
                    Coque3dCell::Quad9 => {
                        node[4][ic] = (node[0][ic] + node[1][ic]) / 2.;
                        node[5][ic] = (node[1][ic] + node[2][ic]) / 2.;
                        node[6][ic] = (node[2][ic] + node[3][ic]) / 2.;
                        node[7][ic] = (node[3][ic] + node[0][ic]) / 2.;
                        node[8][ic] = (node[0][ic] + node[1][ic] + node[2][ic] + node[3][ic]) / 4.;
                    }
                    Coque3dCell::Tria7 => {
                        node[3][ic] = (node[0][ic] + node[1][ic]) / 2.;
                        node[4][ic] = (node[1][ic] + node[2][ic]) / 2.;
                        node[5][ic] = (node[2][ic] + node[0][ic]) / 2.;
                        node[6][ic] = (node[0][ic] + node[1][ic] + node[2][ic]) / 3.;
                    }
                }
            }
            for (n, t) in node.iter().enumerate() {
                let (c, s) = user_angle(&frames[n], direction)?;
                let (xx, yy, xy) = turn_plane(t[0], t[1], t[3], c, s);
                let (xz, yz) = turn_shear(t[4], t[5], c, s);
                let l2 = lambda * lambda;
                out[n][3 * icou + lvl] =
                    [l2 * xx, l2 * yy, t[2], l2 * xy, lambda * xz, lambda * yz];
            }
        }
    }
    Ok(out)
}

/// The efforts of a layer's three levels (bottom, middle, top: SIXX SIYY
/// SIZZ SIXY SIXZ SIYZ) integrated through the thicknesses `hic` of the
/// layers whose bottoms are at `zic` from the mid-surface, with Simpson's
/// weights `w` (times `hic`): NXX NYY NXY MXX MYY MXY QX QY, M = ∫ σ z dz
/// (z along the normal, from −h/2 at the bottom).
fn through_thickness(
    section: &Coque3dSection,
    w: [f64; 3],
    level: &dyn Fn(usize, usize) -> [f64; 6],
) -> [f64; 8] {
    let nbcou = section.layers.max(1) as usize;
    let hic = section.thickness / nbcou as f64;
    let mut e = [0.; 8];
    for icou in 0..nbcou {
        let zic = -section.thickness / 2. + icou as f64 * hic;
        for (lvl, wl) in w.iter().enumerate() {
            let s = level(icou, lvl);
            let (c, z) = (wl * hic, zic + lvl as f64 * hic / 2.);
            for (k, ic) in [0, 1, 3].into_iter().enumerate() {
                e[k] += c * s[ic];
                e[k + 3] += c * z * s[ic];
            }
            e[6] += c * s[4];
            e[7] += c * s[5];
        }
    }
    e
}

/// `EFGE_ELGA` (`te0451`): at each normal point (FPG9COQ, FPG7: the
/// points of `SIEF_ELGA`), the stresses of [`stresses`] integrated
/// through the layers (Simpson: h/6, 4h/6, h/6 per layer), NXX NYY NXY
/// MXX MYY MXY QX QY, in the frame code_aster stores `SIEF_ELGA` in: the
/// user's frame (`direction`) of the first reduced point (`cosiro` 'IU'
/// with `vdrepe`'s `matevg(·, ·, 1)` for every point, `vdsiro`), the same
/// rotation for all the points of the cell.
pub fn efge_elga(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64],
    direction: V3,
) -> Result<Vec<[f64; 8]>, String> {
    let r = reference(xyz)?;
    let frames = nodal_frames(xyz, &r)?;
    let normals: Vec<V3> = frames.iter().map(|f| f[2]).collect();
    // `vdxrep`: vectgt at the first reduced point on the mid-surface.
    let (t, _, _) = point_frame(&r.gr[0], xyz, &normals, 0., section.thickness);
    let (c, s) = user_angle(&t, direction)?;
    let gauss = stresses(xyz, material, section, u)?;
    let npge = 3 * section.layers.max(1) as usize;
    let w = [1. / 6., 4. / 6., 1. / 6.];
    Ok((0..r.npgsn())
        .map(|q| {
            let e = through_thickness(section, w, &|icou, lvl| gauss[q * npge + 3 * icou + lvl]);
            to_user(&e, c, s)
        })
        .collect())
}

/// `EFGE_ELNO` of a non-linear result (`te0185` → `ef0415` →
/// `efcoq3d`): per layer, the three levels of [`sigm_elno`] at each node
/// (least-squares extrapolation to the corners, mid-side nodes and centre
/// the means of the corners, in the node's user frame) integrated by
/// `vdefgn` (Simpson with its literals 0.33333333333333 and
/// 1.33333333333333 times half the layer's thickness). code_aster
/// averages the corners' efforts in the element's frame and then turns
/// each node's (`vdefro`): the same, the rotation being linear.
pub fn efge_elno(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64],
    direction: V3,
) -> Result<Vec<[f64; 8]>, String> {
    let nodes = sigm_elno(xyz, material, section, u, direction)?;
    let (w1, w2) = (0.33333333333333 / 2., 1.33333333333333 / 2.);
    Ok(nodes
        .iter()
        .map(|n| through_thickness(section, [w1, w2, w1], &|icou, lvl| n[3 * icou + lvl]))
        .collect())
}

/// `EFGE_ELNO` of a linear result (`te0185` → `ef0410` → `vdxsig`,
/// `vdefge`, `vdefro`): the whole thickness as one layer whatever
/// `COQUE_NCOU`, the strains at the reduced points (2×2 Gauss on a QUAD9,
/// FPG3 on a TRIA7) at its bottom, middle and top (ξ₃/2 = −½, 0, ½), every
/// row of the operator taken there (`btdmsn` with IND=0: membrane,
/// bending and shear all at the reduced point), integrated by Simpson
/// with `vdefge`'s literals (0.33333333333333, 1.33333333333333 times
/// h/2), extrapolated to the edge nodes by the reduced points' linear
/// functions (`fcesnd` 'LI'), the centre the mean of the mid-side nodes
/// (QUAD9) or of the corners (TRIA7), each node turned into its user
/// frame (`vdefro`).
pub fn efge_elno_linear(
    xyz: &[V3],
    material: &Elastic,
    section: &Coque3dSection,
    u: &[f64],
    direction: V3,
) -> Result<Vec<[f64; 8]>, String> {
    let r = reference(xyz)?;
    check_dofs(&r, u)?;
    let frames = nodal_frames(xyz, &r)?;
    let normals: Vec<V3> = frames.iter().map(|f| f[2]).collect();
    let ul = local_unknowns(&frames, u);
    let kappa = section.shear_factor;
    let h = section.thickness;
    let (nb1, nddle, npgsr) = (r.nb1, r.nddle(), r.npgsr());
    // sig[level][p]: SIXX SIYY SIZZ SIXY SIXZ SIYZ in the point's frame.
    let mut sig = [
        vec![[0.; 6]; npgsr],
        vec![[0.; 6]; npgsr],
        vec![[0.; 6]; npgsr],
    ];
    for (lvl, ksi3s2) in [-0.5, 0., 0.5].into_iter().enumerate() {
        for p in 0..npgsr {
            let s8 = &r.gr[p];
            let (t, jm1, _) = point_frame(s8, xyz, &normals, ksi3s2, h);
            let (hm, hs) = hfmss(&t, true);
            let (hm, hs) = (times_jinv(&hm, &jm1), times_jinv(&hs, &jm1));
            let mut b = vec![vec![0.; nddle]; 5];
            for jb in 0..nb1 {
                for k in 0..3 {
                    let col = 5 * jb + k;
                    for i in 0..3 {
                        b[i][col] = hm[i][3 * k] * s8.d1[jb] + hm[i][3 * k + 1] * s8.d2[jb];
                    }
                    for i in 0..2 {
                        b[3 + i][col] = hs[i][3 * k] * s8.d1[jb] + hs[i][3 * k + 1] * s8.d2[jb];
                    }
                }
            }
            for (cl, col) in rotation_columns(&r.rr[p], &frames, ksi3s2, h) {
                for i in 0..3 {
                    b[i][col] = (0..9).map(|k| hm[i][k] * cl[k]).sum();
                }
                for i in 0..2 {
                    b[3 + i][col] = (0..9).map(|k| hs[i][k] * cl[k]).sum();
                }
            }
            let eps: Vec<f64> = b
                .iter()
                .map(|row| row.iter().zip(&ul).map(|(x, y)| x * y).sum())
                .collect();
            sig[lvl][p] = layer_stress(material, kappa, &eps);
        }
    }
    // vdefge: Simpson over the thickness at each reduced point.
    let demiep = h / 2.;
    let w = [0.33333333333333, 1.33333333333333, 0.33333333333333];
    let z = [-h / 2., -h / 2. + demiep, -h / 2. + 2. * demiep];
    let at_point: Vec<[f64; 8]> = (0..npgsr)
        .map(|p| {
            let int = |ic: usize, zw: bool| {
                demiep
                    * (0..3)
                        .map(|l| w[l] * if zw { z[l] } else { 1. } * sig[l][p][ic])
                        .sum::<f64>()
            };
            [
                int(0, false),
                int(1, false),
                int(3, false),
                int(0, true),
                int(1, true),
                int(3, true),
                int(4, false),
                int(5, false),
            ]
        })
        .collect();
    let mut nodes = vec![[0.; 8]; r.nb2];
    for (node, f) in nodes.iter_mut().zip(&r.extra_nodes) {
        for (p, e) in at_point.iter().enumerate() {
            for k in 0..8 {
                node[k] += e[k] * f[p];
            }
        }
    }
    let (from, count) = match r.cell {
        Coque3dCell::Quad9 => (4, 4),
        Coque3dCell::Tria7 => (0, 3),
    };
    for k in 0..8 {
        nodes[r.nb2 - 1][k] = (from..from + count).map(|n| nodes[n][k]).sum::<f64>() / count as f64;
    }
    nodes
        .iter()
        .zip(&frames)
        .map(|(e, frame)| {
            let (c, s) = user_angle(frame, direction)?;
            Ok(to_user(e, c, s))
        })
        .collect()
}

/// Mᵀ·T·M of the in-plane tensor (xx, yy, xy) with M = [c −s; s c]
/// (`vdsiro`/`vdefro` 'IU', `utbtab`).
fn turn_plane(xx: f64, yy: f64, xy: f64, c: f64, s: f64) -> (f64, f64, f64) {
    let m = [[c, -s], [s, c]];
    let a = [[xx, xy], [xy, yy]];
    let at = |i: usize, j: usize| -> f64 {
        let mut v = 0.;
        for k in 0..2 {
            for l in 0..2 {
                v += m[k][i] * a[k][l] * m[l][j];
            }
        }
        v
    };
    (at(0, 0), at(1, 1), at(0, 1))
}

/// (q₁, q₂)·M with M = [c −s; s c] (the transverse shears of `vdsiro`,
/// `vdefro`).
fn turn_shear(q1: f64, q2: f64, c: f64, s: f64) -> (f64, f64) {
    (q1 * c + q2 * s, -q1 * s + q2 * c)
}

/// NXX NYY NXY MXX MYY MXY QX QY turned into the user's frame (c, s).
fn to_user(e: &[f64; 8], c: f64, s: f64) -> [f64; 8] {
    let (nxx, nyy, nxy) = turn_plane(e[0], e[1], e[2], c, s);
    let (mxx, myy, mxy) = turn_plane(e[3], e[4], e[5], c, s);
    let (qx, qy) = turn_shear(e[6], e[7], c, s);
    [nxx, nyy, nxy, mxx, myy, mxy, qx, qy]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// code_aster's round trip of SIEF_ELGA through the user's frame
    /// (`cosiro` 'IU' then 'UI' with `vectgt`'s frame, whose t₂ = t₃×t₁ is
    /// not unit where the interpolated normal t₃ is not): the identity on a
    /// flat cell and where the direction projects onto t₁, a factor
    /// λ = c² + s² ≠ 1 on a curved cell otherwise.
    #[test]
    fn round_trip_scale_is_one_on_flat_cells_only() {
        let flat: Vec<V3> = [
            [0., 0., 0.],
            [2.1, 0.2, 0.],
            [0.4, 1.9, 0.],
            [1.1, 0.2, 0.],
            [1.2, 1.1, 0.],
            [0.1, 0.9, 0.],
        ]
        .to_vec();
        // A cylinder (radius 1, axis z) patch, mid-sides on the cylinder.
        let on = |t: f64, z: f64| [t.cos(), t.sin(), z];
        let curved: Vec<V3> = vec![
            on(0., 0.),
            on(0.5, 0.),
            on(0., 0.5),
            on(0.25, 0.),
            on(0.25, 0.25),
            on(0., 0.25),
        ];
        let r = RefElement::new(Coque3dCell::Tria7);
        let scale = |xyz: &[V3], d: V3| {
            let frames = nodal_frames(xyz, &r).unwrap();
            round_trip_scale(xyz, &r, &frames, d).unwrap()
        };
        for d in [[1., 0., 0.], [0.3, 0.8, 0.2], [0., 1., 0.]] {
            assert!((scale(&flat, d) - 1.).abs() < 1e-15);
        }
        // Along z the direction is t₂'s (s only, c = 0): one normalisation
        // brings s to 1. Obliquely, λ ≠ 1.
        assert!((scale(&curved, [0., 0., 1.]) - 1.).abs() < 1e-15);
        let lambda = scale(&curved, [0., 0.6, 0.8]);
        assert!(
            (lambda - 1.).abs() > 1e-6 && (lambda - 1.).abs() < 1e-2,
            "{lambda}"
        );
    }

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
        let r = RefElement::new(Coque3dCell::Quad9);
        let s: f64 = r.extra.iter().map(|e| e.iter().sum::<f64>()).sum();
        assert!((s - 9.).abs() < 1e-12, "{s}");
    }

    #[test]
    fn extrapolation_is_exact_on_its_own_space() {
        // f = (1 + 2ξ₁ − ξ₂ + 0.5ξ₁ξ₂)·(3 − ζ + 2ζ²): bilinear in the plane,
        // quadratic through the layer, found again at the 4 corners × 3
        // levels from its 27 point values (mamagi's least squares).
        let f = |x: f64, y: f64, z: f64| (1. + 2. * x - y + 0.5 * x * y) * (3. - z + 2. * z * z);
        let matr = extrapolation(&RefElement::new(Coque3dCell::Quad9));
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

    #[test]
    fn triangle_functions_interpolate_at_code_aster_nodes() {
        for (n, &(x, y)) in NODES7.iter().enumerate() {
            // The centre's literal 0.333333333333333 is 1/3 to 3e-16.
            let s7 = tr7(x, y);
            for m in 0..7 {
                let want = if m == n { 1. } else { 0. };
                assert!((s7.f[m] - want).abs() < 1e-14, "{n} {m} {}", s7.f[m]);
            }
            if n < 6 {
                let s6 = tr6(x, y);
                for m in 0..6 {
                    let want = if m == n { 1. } else { 0. };
                    assert!((s6.f[m] - want).abs() < 1e-15);
                }
            }
        }
        // Derivatives against central differences; the sums vanish.
        let (x, y, h) = (0.21, 0.37, 1e-6);
        for sh in [tr6, tr7] {
            let (s, sx, sy) = (sh(x, y), sh(x + h, y), sh(x, y + h));
            let (mx, my) = (sh(x - h, y), sh(x, y - h));
            for m in 0..7 {
                assert!((s.d1[m] - (sx.f[m] - mx.f[m]) / (2. * h)).abs() < 1e-8);
                assert!((s.d2[m] - (sy.f[m] - my.f[m]) / (2. * h)).abs() < 1e-8);
            }
            assert!(s.d1.iter().sum::<f64>().abs() < 1e-14);
            assert!((s.f.iter().sum::<f64>() - 1.).abs() < 1e-15);
        }
    }

    #[test]
    fn triangle_rules_and_extrapolation() {
        // FPG7 integrates degree 5 exactly: ∫ x⁵ = 5!/7! = 1/42 on the
        // reference triangle, ∫ x²y² = 2!2!/6! = 1/180.
        let (pts, w) = fpg7();
        let int = |f: &dyn Fn(f64, f64) -> f64| -> f64 {
            pts.iter().zip(&w).map(|(&(x, y), w)| w * f(x, y)).sum()
        };
        assert!((int(&|_, _| 1.) - 0.5).abs() < 1e-15);
        assert!((int(&|x, _| x.powi(5)) - 1. / 42.).abs() < 1e-15);
        assert!((int(&|x, y| x * x * y * y) - 1. / 180.).abs() < 1e-15);
        // The FPG3 → FPG7 extrapolation is linear and exact on linear
        // fields (to the 1e-15 of jni080's literals).
        let r = RefElement::new(Coque3dCell::Tria7);
        let red = [(1. / 6., 1. / 6.), (2. / 3., 1. / 6.), (1. / 6., 2. / 3.)];
        let f = |x: f64, y: f64| 2. - 3. * x + 5. * y;
        for (q, &(x, y)) in r.normal.iter().enumerate() {
            let got: f64 = (0..3).map(|k| r.extra[q][k] * f(red[k].0, red[k].1)).sum();
            assert!((got - f(x, y)).abs() < 1e-13, "{q}: {got}");
        }
        // mamagi: linear in the plane × quadratic through the layer, found
        // at the 3 corners × 3 levels from its 21 point values.
        let g = |x: f64, y: f64, z: f64| (1. + 2. * x - y) * (3. - z + 2. * z * z);
        let matr = extrapolation(&r);
        let corners = [(0., 0.), (1., 0.), (0., 1.)];
        for (lvl, z) in [-1., 0., 1.].into_iter().enumerate() {
            for (c, &(x, y)) in corners.iter().enumerate() {
                let i = 3 * lvl + c;
                let got: f64 = (0..21)
                    .map(|j| {
                        let (zj, (xj, yj)) = ([-1., 0., 1.][j / 7], r.normal[j % 7]);
                        matr[21 * i + j] * g(xj, yj, zj)
                    })
                    .sum();
                assert!((got - g(x, y, z)).abs() < 1e-12, "{lvl} {c}: {got}");
            }
        }
    }
}
