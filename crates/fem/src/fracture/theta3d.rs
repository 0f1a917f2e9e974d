//! G and K1, K2, K3 along a 3D crack front by the G-theta method (G its
//! energy term, K the interaction integral), as code_aster 17's
//! `CALC_G(OPTION='G'/'K', THETA=_F(DISCRETISATION='LINEAIRE'|'LEGENDRE',
//! NB_POINT_FOND))` computes them (`op0027`: `cgComputeFactors`,
//! `cgComputeMatrix`, `cgComputeGtheta`, `cgDiscrField`, `create_npf`;
//! the elementary term `te0222` with `thetapdg`, `coor_cyl`, `chauxi`,
//! `gbil3d`; the curvature `xcourb`/`te0398`; the smoothing
//! `gmatc3`/`gsyste`/`hatSmooth`, SEG3 on quadratic lips).
//!
//! - Every mesh node gets the local basis of its nearest point on the front
//!   polyline (`fonbas2`, [`node_bases`]): the projection point, the
//!   front's direction and normal linearly interpolated between the
//!   segment's ends (not normalised), and the projection's curvilinear
//!   abscissa.
//! - theta0 at a node (`cgComputeFactors`, [`theta0`]): 1 closer to its
//!   projection than `r_inf`, 0 beyond `r_sup`, linear in between (1e-6
//!   tolerance on the crown's ends).
//! - One theta field per front node i (`LINEAIRE`): at a node,
//!   hat_i(abscissa)·theta0·dir, the hat linear between the front nodes
//!   i−1, i, i+1 (`thetapdg`); a cell is skipped when no node's theta0
//!   reaches 2.2e-16 or no node's abscissa lies in [s_{i−1}, s_{i+1})
//!   (`te0222`).
//! - At each Gauss point of the stiffness family: the crack's local frame
//!   from the basis interpolated at the point (`coor_cyl`: e1 the
//!   direction, e2 the normal, normalised, e3 = e1 × e2), the polar
//!   coordinates (r, φ) of the point in it, the gradients of the three
//!   auxiliary asymptotic fields of unit K1, K2, K3 in the global frame,
//!   plus uₖ ∂e_k/∂x (`chauxi`, the curvature term: the gradient of the
//!   nodal bases at the cell's *first* Gauss point, as `te0222` reads it
//!   for every point); the bilinear form `gbil3d` between u and each
//!   auxiliary field (elastic, no thermal strain, no initial stress, no
//!   volume force). Per cell the sums times E/(1−ν²) (K1, K2) or 2μ (K3)
//!   and, for G_IRWIN, times √(E/(1−ν²)) and √(2μ).
//! - G per theta field: Σ poids (σ_ik ∂u_i/∂x_m ∂θ_m/∂x_k − W div θ)
//!   (`te0222`'s `tcla`, linear elastic, no load).
//! - Per component, the values of the theta fields (the ends replaced by
//!   the neighbour's times an abscissa ratio, or / 4 on quadratic lips,
//!   `cgComputeGtheta`) are the front's mass matrix (`gmatc3`, SEG2 or
//!   SEG3) times the nodal values: solved by the normal equations
//!   MᵀM k = Mᵀ kθ (`gsyste`), then smoothed by the SEG3 cells' hats on
//!   quadratic lips (`hatSmooth`).
//! - `NB_POINT_FOND` ([`virtual_front`]): the theta fields of points at
//!   equal abscissae, the auxiliary fields' frame staying the crack's.

use crate::element::physical_derivatives;
use crate::material::Elastic;
use crate::shape;
use aster_mesh::vec3::{cross, dot, sub};
use aster_mesh::{CellId, Mesh};

/// code_aster's `r8prem()`.
const R8PREM: f64 = f64::EPSILON;

/// The curvilinear abscissa of the front's nodes (`fonfis2`).
pub fn front_abscissa(coords: &[[f64; 3]]) -> Vec<f64> {
    let mut s = vec![0.0; coords.len()];
    for i in 1..coords.len() {
        let d = sub(coords[i], coords[i - 1]);
        s[i] = s[i - 1] + dot(d, d).sqrt();
    }
    s
}

/// A crack front as CALC_G reads it: its nodes' coordinates, unit normals
/// and directions (`BASEFOND`) and abscissae.
pub struct Front<'a> {
    pub coords: &'a [[f64; 3]],
    pub normal: &'a [[f64; 3]],
    pub dir: &'a [[f64; 3]],
    pub absc: &'a [f64],
    /// A front of SEG3 cells (`fonbas2`'s `QUADRATIQUE`): the nodes are
    /// projected on the segments between the cells' ends (nodes 0, 2, 4…),
    /// the middle nodes only counting in the abscissa.
    pub quadratic: bool,
}

/// The local basis of a mesh node (`BASLOC`, `ABSCUR`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeBasis {
    /// The nearest point of the front.
    pub proj: [f64; 3],
    /// The direction and the normal interpolated there (not normalised).
    pub dir: [f64; 3],
    pub normal: [f64; 3],
    /// The abscissa of the projection.
    pub absc: f64,
}

/// The local basis of every node (`fonbas2`; on a quadratic front the
/// segments run between the cells' ends).
pub fn node_bases(front: &Front, nodes: &[[f64; 3]]) -> Vec<NodeBasis> {
    let eps = 1e-12;
    let step = if front.quadratic { 2 } else { 1 };
    let nseg = front.coords.len().saturating_sub(1) / step;
    nodes
        .iter()
        .map(|&m| {
            let mut dmin = f64::MAX;
            let (mut sn, mut ia, mut proj) = (0.0, 0, front.coords[0]);
            for iseg in 0..nseg {
                let (ja, jb) = (step * iseg, step * (iseg + 1));
                let (a, b) = (front.coords[ja], front.coords[jb]);
                let ab = sub(b, a);
                let am = sub(m, a);
                let mut s = dot(ab, am) / dot(ab, ab);
                if s - 1.0 >= eps {
                    s = 1.0;
                }
                if s <= eps {
                    s = 0.0;
                }
                let n = [s * ab[0] + a[0], s * ab[1] + a[1], s * ab[2] + a[2]];
                let nm = sub(m, n);
                let d = dot(nm, nm).sqrt();
                if d < dmin * (1.0 - R8PREM * 1e4) {
                    dmin = d;
                    sn = s;
                    ia = ja;
                    proj = n;
                }
            }
            let ib = (ia + step).min(front.coords.len() - 1);
            let lerp = |va: [f64; 3], vb: [f64; 3]| {
                [
                    sn * vb[0] + (1.0 - sn) * va[0],
                    sn * vb[1] + (1.0 - sn) * va[1],
                    sn * vb[2] + (1.0 - sn) * va[2],
                ]
            };
            NodeBasis {
                proj,
                dir: lerp(front.dir[ia], front.dir[ib]),
                normal: lerp(front.normal[ia], front.normal[ib]),
                absc: (1.0 - sn) * front.absc[ia] + sn * front.absc[ib],
            }
        })
        .collect()
}

/// theta0 at a node of coordinates `x` (`cgComputeFactors`).
pub fn theta0(basis: &NodeBasis, x: [f64; 3], r_inf: f64, r_sup: f64) -> f64 {
    let eps = 1e-6;
    let d = sub(basis.proj, x);
    let d = dot(d, d).sqrt();
    let alpha = (d - r_inf) / (r_sup - r_inf);
    if alpha.abs() <= eps || alpha < 0.0 {
        1.0
    } else if (alpha - 1.0).abs() <= eps || alpha - 1.0 > 0.0 {
        0.0
    } else {
        1.0 - alpha
    }
}

/// A 3D continuum cell of the model.
pub struct SolidCell {
    pub cell: CellId,
    pub material: Elastic,
}

/// What the integral reads at the mesh's nodes.
pub struct NodalData<'a> {
    /// The crack's bases (`BASLOC`): the frame of the auxiliary fields
    /// and the curvature.
    pub bases: &'a [NodeBasis],
    /// The bases theta is built from (direction and abscissa): the crack's
    /// own, or those of the `NB_POINT_FOND` front (`npf_baseloc`,
    /// `npf_abscurv`), which `te0222` reads through `PTHETAR` while its
    /// frame stays the crack's `PBASLOR`.
    pub theta: &'a [NodeBasis],
    pub theta0: &'a [f64],
    /// The displacement.
    pub disp: &'a [[f64; 3]],
}

/// The seven values of one theta field, summed over the cells (`te0222`'s
/// outputs): G (`CALC_G`: the energy term `tcla`), K1, K2, K3 and their
/// G_IRWIN factors (`CALC_K_G`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KTheta {
    pub gth: f64,
    pub k: [f64; 3],
    pub g: [f64; 3],
}

/// What the integral computes: G (`OPTION='G'`), K (`OPTION='K'`) or both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Wanted {
    pub g: bool,
    pub k: bool,
}

/// A Gauss point's data, independent of the theta field.
struct Point {
    ff: Vec<f64>,
    dfdi: Vec<[f64; 3]>,
    poids: f64,
    dudm: [[f64; 3]; 3],
    /// The stress of the displacement (`te0222` reads the result's
    /// `SIEF_ELGA`, the same for a linear elastic result) and the elastic
    /// energy ½ σ:ε (`nmelnl`).
    sig: [[f64; 3]; 3],
    energy: f64,
    /// The auxiliary fields' gradients (K1, K2, K3); zero without K.
    aux: [[[f64; 3]; 3]; 3],
}

struct CellData {
    nodes: Vec<usize>,
    points: Vec<Point>,
    c: [f64; 3],
    coeff_k1k2: f64,
    coeff_k3: f64,
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v);
    if n != 0.0 {
        let n = n.sqrt();
        [v[0] / n, v[1] / n, v[2] / n]
    } else {
        v
    }
}

/// The gradients of the auxiliary displacement fields of unit K1, K2, K3
/// (`chauxi`, no curvature radius): `invp` has the local frame's vectors
/// as rows, `courb[k][a][j]` = ∂(e_k)_a/∂x_j.
fn chauxi(
    mu: f64,
    ka: f64,
    r: f64,
    t: f64,
    invp: &[[f64; 3]; 3],
    courb: &[[[f64; 3]; 3]; 3],
) -> [[[f64; 3]; 3]; 3] {
    let two_pi = 2.0 * std::f64::consts::PI;
    let cr1 = 1.0 / (4.0 * mu * (two_pi * r).sqrt());
    let cr2 = (r / two_pi).sqrt() / (2.0 * mu);
    let (h, c, s) = (t * 0.5, t.cos(), t.sin());
    let u1l = [cr2 * (h.cos() * (ka - c)), cr2 * (h.sin() * (ka - c)), 0.0];
    let du1dpo = [
        [
            cr1 * (h.cos() * (ka - c)),
            cr2 * (-0.5 * h.sin() * (ka - c) + h.cos() * s),
        ],
        [
            cr1 * (h.sin() * (ka - c)),
            cr2 * (0.5 * h.cos() * (ka - c) + h.sin() * s),
        ],
        [0.0, 0.0],
    ];
    let u2l = [
        cr2 * h.sin() * (ka + 2.0 + c),
        cr2 * h.cos() * (2.0 - ka - c),
        0.0,
    ];
    let du2dpo = [
        [
            cr1 * (h.sin() * (ka + 2.0 + c)),
            cr2 * (0.5 * h.cos() * (ka + 2.0 + c) - h.sin() * s),
        ],
        [
            cr1 * h.cos() * (2.0 - ka - c),
            cr2 * (-0.5 * h.sin() * (2.0 - ka - c) + h.cos() * s),
        ],
        [0.0, 0.0],
    ];
    let u3l = [0.0, 0.0, 4.0 * cr2 * h.sin()];
    let du3dpo = [
        [0.0, 0.0],
        [0.0, 0.0],
        [4.0 * cr1 * h.sin(), 2.0 * cr2 * h.cos()],
    ];
    let global = |ul: [f64; 3], dpo: [[f64; 2]; 3]| {
        let mut dl = [[0.0; 3]; 3];
        for i in 0..3 {
            dl[i][0] = c * dpo[i][0] - s / r * dpo[i][1];
            dl[i][1] = s * dpo[i][0] + c / r * dpo[i][1];
        }
        let mut dm = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    for l in 0..3 {
                        dm[i][j] += dl[k][l] * invp[l][j] * invp[k][i];
                    }
                    dm[i][j] += ul[k] * courb[k][i][j];
                }
            }
        }
        dm
    };
    [
        global(u1l, du1dpo),
        global(u2l, du2dpo),
        global(u3l, du3dpo),
    ]
}

/// `gbil3d`'s elastic part (coef 1, no thermal strain, no initial stress,
/// no volume force, static): (s2 − s1 div θ / 2)·poids.
fn gbil3d(u: &[[f64; 3]; 3], v: &[[f64; 3]; 3], t: &[[f64; 3]; 3], c: [f64; 3], poids: f64) -> f64 {
    // 1-based accessors as in the Fortran.
    let du = |i: usize, j: usize| u[i - 1][j - 1];
    let dv = |i: usize, j: usize| v[i - 1][j - 1];
    let dt = |i: usize, j: usize| t[i - 1][j - 1];
    let h = |a: (usize, usize), b: (usize, usize)| {
        0.5 * (dv(a.0, a.1) * du(b.0, b.1) + du(a.0, a.1) * dv(b.0, b.1))
    };
    let mut vect = [0.0; 34];
    let pairs: [((usize, usize), (usize, usize)); 33] = [
        ((1, 1), (2, 2)),
        ((1, 1), (1, 2)),
        ((1, 1), (2, 1)),
        ((2, 2), (1, 2)),
        ((2, 2), (2, 1)),
        ((1, 2), (2, 1)),
        ((3, 3), (3, 1)),
        ((1, 1), (1, 3)),
        ((3, 3), (3, 2)),
        ((2, 2), (2, 3)),
        ((1, 1), (3, 3)),
        ((2, 2), (3, 3)),
        ((3, 3), (1, 2)),
        ((3, 3), (2, 1)),
        ((1, 1), (3, 1)),
        ((2, 2), (3, 1)),
        ((1, 1), (3, 2)),
        ((2, 2), (3, 2)),
        ((1, 1), (2, 3)),
        ((3, 3), (2, 3)),
        ((2, 2), (1, 3)),
        ((3, 3), (1, 3)),
        ((1, 3), (3, 1)),
        ((2, 3), (3, 2)),
        ((2, 3), (3, 1)),
        ((3, 2), (3, 1)),
        ((1, 3), (3, 2)),
        ((1, 2), (1, 3)),
        ((2, 1), (1, 3)),
        ((1, 2), (3, 1)),
        ((2, 1), (2, 3)),
        ((2, 1), (3, 2)),
        ((2, 3), (1, 2)),
    ];
    for (k, (a, b)) in pairs.iter().enumerate() {
        vect[k + 1] = h(*a, *b);
    }
    let s11 = du(1, 1) * dv(1, 1) + du(2, 2) * dv(2, 2) + du(3, 3) * dv(3, 3);
    let s12 = du(1, 1) * dv(2, 2)
        + du(2, 2) * dv(1, 1)
        + du(1, 1) * dv(3, 3)
        + du(3, 3) * dv(1, 1)
        + du(2, 2) * dv(3, 3)
        + du(3, 3) * dv(2, 2);
    let s13 = (du(1, 2) + du(2, 1)) * (dv(1, 2) + dv(2, 1))
        + (du(2, 3) + du(3, 2)) * (dv(2, 3) + dv(3, 2))
        + (du(3, 1) + du(1, 3)) * (dv(3, 1) + dv(1, 3));
    let s21 = du(1, 1) * dv(1, 1) * dt(1, 1)
        + du(2, 2) * dv(2, 2) * dt(2, 2)
        + du(3, 3) * dv(3, 3) * dt(3, 3)
        + vect[5] * dt(1, 2)
        + vect[2] * dt(2, 1)
        + vect[7] * dt(1, 3)
        + vect[8] * dt(3, 1)
        + vect[9] * dt(2, 3)
        + vect[10] * dt(3, 2);
    let s22 = vect[1] * (dt(1, 1) + dt(2, 2))
        + vect[11] * (dt(1, 1) + dt(3, 3))
        + vect[12] * (dt(2, 2) + dt(3, 3))
        + (vect[3] + vect[14]) * dt(1, 2)
        + (vect[4] + vect[13]) * dt(2, 1)
        + (vect[15] + vect[16]) * dt(1, 3)
        + (vect[17] + vect[18]) * dt(2, 3)
        + (vect[19] + vect[20]) * dt(3, 2)
        + (vect[21] + vect[22]) * dt(3, 1);
    let s23 = (vect[6] + du(2, 1) * dv(2, 1)) * dt(1, 1)
        + (vect[23] + du(3, 1) * dv(3, 1)) * dt(1, 1)
        + (vect[6] + du(1, 2) * dv(1, 2)) * dt(2, 2)
        + (vect[24] + du(3, 2) * dv(3, 2)) * dt(2, 2)
        + (vect[24] + du(2, 3) * dv(2, 3)) * dt(3, 3)
        + (vect[23] + du(1, 3) * dv(1, 3)) * dt(3, 3)
        + (vect[2] + vect[3]) * dt(1, 2)
        + (vect[25] + vect[26]) * dt(1, 2)
        + (vect[4] + vect[5]) * dt(2, 1)
        + (vect[26] + vect[27]) * dt(2, 1)
        + (vect[28] + vect[29]) * dt(3, 2)
        + (vect[9] + vect[20]) * dt(3, 2)
        + (vect[10] + vect[18]) * dt(2, 3)
        + (vect[28] + vect[30]) * dt(2, 3)
        + (vect[8] + vect[15]) * dt(1, 3)
        + (vect[31] + vect[32]) * dt(1, 3)
        + (vect[31] + vect[33]) * dt(3, 1)
        + (vect[22] + vect[7]) * dt(3, 1);
    let s1 = c[0] * s11 + c[1] * s12 + c[2] * s13;
    let s2 = c[0] * s21 + c[1] * s22 + c[2] * s23;
    let divt = dt(1, 1) + dt(2, 2) + dt(3, 3);
    (s2 - 0.5 * s1 * divt) * poids
}

/// A cell's node indices, `None` when theta0 is below `r8prem` at all of
/// them (te0222 and te0147 skip it).
fn reached_nodes(cell: &aster_mesh::Cell, nodal: &NodalData) -> Option<Vec<usize>> {
    let nodes: Vec<usize> = cell.nodes.iter().map(|n| n.0 as usize).collect();
    nodes
        .iter()
        .any(|&n| nodal.theta0[n] >= R8PREM)
        .then_some(nodes)
}

/// The Gauss data of the cells theta0 reaches.
fn cell_data(
    mesh: &Mesh,
    cells: &[SolidCell],
    nodal: &NodalData,
    with_k: bool,
) -> Result<Vec<CellData>, String> {
    let mut out = Vec::new();
    for sc in cells {
        let cell = mesh.cell(sc.cell);
        let Some(nodes) = reached_nodes(cell, nodal) else {
            continue;
        };
        let name = || mesh.cell_name(sc.cell);
        if !sc.material.is_isotropic() {
            return Err(format!(
                "cell {}: G and K of an orthotropic material (te0222 reads the isotropic law's E and NU)",
                name()
            ));
        }
        let (e, nu) = (sc.material.e, sc.material.nu);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = nu * e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let ka = 3.0 - 4.0 * nu;
        let scheme = shape::rigi_scheme(cell.ty);
        if scheme.is_empty() || cell.ty.dim() != 3 {
            return Err(format!("cell {}: not a 3D continuum cell", name()));
        }
        // The nodal frames of `xcourb`: e1 the direction, e2 the normal
        // (normalised), e3 = e1 × e2.
        let frames: Vec<[[f64; 3]; 3]> = nodes
            .iter()
            .map(|&n| {
                let b = &nodal.bases[n];
                let e1 = normalized(b.dir);
                let e2 = normalized(b.normal);
                [e1, e2, cross(e1, e2)]
            })
            .collect();
        let mut courb = [[[0.0; 3]; 3]; 3];
        let mut points = Vec::with_capacity(scheme.len());
        for (kp, gp) in scheme.iter().enumerate() {
            let (ff, dfdi, det, x) = physical_derivatives(mesh, sc.cell, 3, gp)
                .map_err(|e| format!("cell {}: {e}", name()))?;
            if kp == 0 && with_k {
                for k in 0..3 {
                    for a in 0..3 {
                        for j in 0..3 {
                            courb[k][a][j] =
                                (0..nodes.len()).map(|i| frames[i][k][a] * dfdi[i][j]).sum();
                        }
                    }
                }
            }
            let mut dudm = [[0.0; 3]; 3];
            let (mut pf, mut dir, mut nor) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            for (i, &n) in nodes.iter().enumerate() {
                let u = nodal.disp[n];
                let b = &nodal.bases[n];
                for j in 0..3 {
                    for k in 0..3 {
                        dudm[j][k] += u[j] * dfdi[i][k];
                    }
                    pf[j] += b.proj[j] * ff[i];
                    dir[j] += b.dir[j] * ff[i];
                    nor[j] += b.normal[j] * ff[i];
                }
            }
            let mut aux = [[[0.0; 3]; 3]; 3];
            if with_k {
                // xbasgl, xcoocy.
                let e1 = normalized(dir);
                let e2 = normalized(nor);
                let e3 = normalized(cross(e1, e2));
                let invp = [e1, e2, e3];
                let og = sub(x, pf);
                let cosi = dot(e1, og);
                let sinu = dot(e2, og);
                let r = (cosi * cosi + sinu * sinu).sqrt();
                if r < 1e-12 {
                    return Err(format!("cell {}: a Gauss point on the crack front", name()));
                }
                let t = sinu.atan2(cosi);
                aux = chauxi(mu, ka, r, t, &invp, &courb);
            }
            // σ = λ tr ε I + 2 μ ε and ½ σ:ε (nmelnl, ELAS).
            let mut eps = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    eps[i][j] = 0.5 * (dudm[i][j] + dudm[j][i]);
                }
            }
            let tr = eps[0][0] + eps[1][1] + eps[2][2];
            let mut sig = [[0.0; 3]; 3];
            let mut energy = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    sig[i][j] = 2.0 * mu * eps[i][j] + if i == j { lambda * tr } else { 0.0 };
                    energy += 0.5 * sig[i][j] * eps[i][j];
                }
            }
            points.push(Point {
                ff,
                dfdi,
                poids: gp.weight * det.abs(),
                dudm,
                sig,
                energy,
                aux,
            });
        }
        out.push(CellData {
            nodes,
            points,
            c: [lambda + 2.0 * mu, lambda, mu],
            coeff_k1k2: e / (1.0 - nu * nu),
            coeff_k3: 2.0 * mu,
        });
    }
    Ok(out)
}

/// The hat of the theta field whose window is [s0, s1, s2] at abscissa
/// `sno` (`thetapdg`, an open front).
fn hat(sno: f64, [s0, s1, s2]: [f64; 3]) -> f64 {
    if sno >= s0 && sno <= s1 && s0 != s1 {
        (sno - s0) / (s1 - s0)
    } else if sno >= s1 && sno <= s2 {
        1.0 - (sno - s1) / (s2 - s1)
    } else {
        0.0
    }
}

/// ∇θ and θ at a Gauss point of a cell of nodes `nodes`, from the shape
/// functions and their derivatives there; `None` skips the cell.
type ThetaGradient<'a> =
    dyn Fn(&[usize], &[f64], &[[f64; 3]]) -> Option<([[f64; 3]; 3], [f64; 3])> + 'a;

/// A face load where theta is not zero (`PRES_REP`, `FORCE_FACE` with
/// real values, its multiplier applied): code_aster's `te0147` on the
/// skin elements.
pub struct FaceLoad {
    pub cell: CellId,
    pub pressure: f64,
    pub force: [f64; 3],
}

/// A Gauss point of a face: ff, the derivatives along (i1, i2) (third
/// column 0), the weight, u.
type FacePoint = (Vec<f64>, Vec<[f64; 3]>, f64, [f64; 3]);

/// A face's Gauss data for `te0147`.
struct FaceData {
    nodes: Vec<usize>,
    points: Vec<FacePoint>,
    i1: [f64; 3],
    i2: [f64; 3],
    /// The traction f − p a3 (a3 the face's normal from its first three
    /// nodes, turned outwards as aster's PRES_REP).
    traction: [f64; 3],
}

fn face_data(
    mesh: &Mesh,
    cells: &[SolidCell],
    faces: &[FaceLoad],
    nodal: &NodalData,
) -> Result<Vec<FaceData>, String> {
    let mut out = Vec::new();
    for fl in faces {
        let cell = mesh.cell(fl.cell);
        let Some(nodes) = reached_nodes(cell, nodal) else {
            continue;
        };
        let name = || mesh.cell_name(fl.cell);
        if cell.ty.dim() != 2 || nodes.len() < 3 {
            return Err(format!(
                "cell {}: a face load on a cell that is no face",
                name()
            ));
        }
        let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        // te0147's frame: a1 = x2 − x1, a2 = x3 − x1, a3 = a1 × a2,
        // i2 = a3 × a1.
        let a1 = sub(x[1], x[0]);
        let a2 = sub(x[2], x[0]);
        let mut a3 = cross(a1, a2);
        let i2 = normalized(cross(a3, a1));
        let i1 = normalized(a1);
        a3 = normalized(a3);
        // aster's PRES_REP pushes along the outward normal of the volume
        // cell the face bounds: a3 turned so (code_aster's node order
        // gives the same on an oriented skin).
        let corners = crate::shape::corner_count(cell.ty);
        let owner = cells.iter().find(|sc| {
            let c = mesh.cell(sc.cell);
            cell.nodes[..corners].iter().all(|n| c.nodes.contains(n))
        });
        if let Some(sc) = owner {
            let c = mesh.cell(sc.cell);
            let k = c.nodes.len() as f64;
            let mut ctr = [0.0; 3];
            for n in &c.nodes {
                let p = mesh.coord(*n);
                for j in 0..3 {
                    ctr[j] += p[j] / k;
                }
            }
            if dot(sub(x[0], ctr), a3) < 0.0 {
                a3 = [-a3[0], -a3[1], -a3[2]];
            }
        }
        let traction = [
            fl.force[0] - fl.pressure * a3[0],
            fl.force[1] - fl.pressure * a3[1],
            fl.force[2] - fl.pressure * a3[2],
        ];
        // The nodes in the plane (i1, i2) from node 1 (dfdm2d's coor).
        let local: Vec<[f64; 2]> = x
            .iter()
            .map(|&p| {
                let d = sub(p, x[0]);
                [dot(d, i1), dot(d, i2)]
            })
            .collect();
        let mut points = Vec::new();
        for gp in crate::shape::skin_scheme(cell.ty) {
            let sh = crate::shape::shape(cell.ty, gp.xi);
            let (ff, dff) = (sh.n, sh.dn);
            // dfdm2d: the Jacobian of (ξ, η) → the plane coordinates.
            let mut j = [[0.0; 2]; 2];
            for (a, p) in local.iter().enumerate() {
                for r in 0..2 {
                    for c in 0..2 {
                        j[r][c] += dff[a][r] * p[c];
                    }
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if det.abs() < 1e-300 {
                return Err(format!("cell {}: a degenerate face", name()));
            }
            let dfdi: Vec<[f64; 3]> = dff
                .iter()
                .map(|d| {
                    [
                        (j[1][1] * d[0] - j[0][1] * d[1]) / det,
                        (-j[1][0] * d[0] + j[0][0] * d[1]) / det,
                        0.0,
                    ]
                })
                .collect();
            let mut u = [0.0; 3];
            for (a, &n) in nodes.iter().enumerate() {
                for k in 0..3 {
                    u[k] += ff[a] * nodal.disp[n][k];
                }
            }
            points.push((ff, dfdi, gp.weight * det.abs(), u));
        }
        out.push(FaceData {
            nodes,
            points,
            i1,
            i2,
            traction,
        });
    }
    Ok(out)
}

/// The faces' data, refused with K (te0147's K terms, from the auxiliary
/// displacements `deffk` and the lips' level sets, are not reproduced).
fn face_loads(
    mesh: &Mesh,
    cells: &[SolidCell],
    faces: &[FaceLoad],
    nodal: &NodalData,
    wanted: Wanted,
) -> Result<Vec<FaceData>, String> {
    let data = face_data(mesh, cells, faces, nodal)?;
    if wanted.k && !data.is_empty() {
        let cell = faces
            .iter()
            .find(|fl| {
                mesh.cell(fl.cell)
                    .nodes
                    .iter()
                    .any(|n| nodal.theta0[n.0 as usize] >= R8PREM)
            })
            .map(|fl| mesh.cell_name(fl.cell))
            .unwrap_or_default();
        return Err(format!(
            "K with a load on the face {cell} inside the theta crown (te0147's terms of K are not reproduced; OPTION='G' computes its term)"
        ));
    }
    Ok(data)
}

/// te0147's G term of the face loads for one theta field (real loads:
/// no gradient of the load): Σ poids (t·u) div_s θ, div_s θ the surface
/// divergence ∂(θ·i1)/∂s1 + ∂(θ·i2)/∂s2.
fn integrate_faces(faces: &[FaceData], theta: &ThetaGradient) -> f64 {
    let mut g = 0.0;
    for fd in faces {
        let mut tcla = 0.0;
        let mut skipped = false;
        for (ff, dfdi, poids, u) in &fd.points {
            let Some((t, _)) = theta(&fd.nodes, ff, dfdi) else {
                skipped = true;
                break;
            };
            let dth1d1: f64 = (0..3).map(|j| t[j][0] * fd.i1[j]).sum();
            let dth2d2: f64 = (0..3).map(|j| t[j][1] * fd.i2[j]).sum();
            let divt = dth1d1 + dth2d2;
            for j in 0..3 {
                tcla += poids * (fd.traction[j] * divt) * u[j];
            }
        }
        if !skipped {
            g += tcla;
        }
    }
    g
}

/// G (`tcla`: Σ poids (σ_ik ∂u_i/∂x_m ∂θ_m/∂x_k − W div θ)) and the
/// interaction integrals of one theta field over the cells.
fn integrate(data: &[CellData], dtdm: &ThetaGradient, wanted: Wanted) -> KTheta {
    let mut o = KTheta::default();
    for cd in data {
        let mut k = [0.0; 3];
        let mut tcla = 0.0;
        let mut skipped = false;
        for p in &cd.points {
            let Some((t, _)) = dtdm(&cd.nodes, &p.ff, &p.dfdi) else {
                skipped = true;
                break;
            };
            if wanted.g {
                let mut prod = 0.0;
                for i in 0..3 {
                    for l in 0..3 {
                        for m in 0..3 {
                            prod += p.sig[i][l] * p.dudm[i][m] * t[m][l];
                        }
                    }
                }
                let divt = t[0][0] + t[1][1] + t[2][2];
                tcla += p.poids * (prod - p.energy * divt);
            }
            if wanted.k {
                for (m, km) in k.iter_mut().enumerate() {
                    *km += gbil3d(&p.dudm, &p.aux[m], &t, cd.c, p.poids);
                }
            }
        }
        if skipped {
            continue;
        }
        o.gth += tcla;
        let coeffs = [cd.coeff_k1k2, cd.coeff_k1k2, cd.coeff_k3];
        for m in 0..3 {
            o.k[m] += k[m] * coeffs[m];
            o.g[m] += k[m] * coeffs[m].sqrt();
        }
    }
    o
}

/// The values of the theta fields, one per front node (`LINEAIRE`, an
/// open front), before the smoothing.
pub fn k_theta_fields(
    mesh: &Mesh,
    cells: &[SolidCell],
    faces: &[FaceLoad],
    nodal: &NodalData,
    absfon: &[f64],
    wanted: Wanted,
) -> Result<Vec<KTheta>, String> {
    let data = cell_data(mesh, cells, nodal, wanted.k)?;
    let face_data = face_loads(mesh, cells, faces, nodal, wanted)?;
    let n = absfon.len();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let lag = [
            absfon[i.saturating_sub(1)],
            absfon[i],
            absfon[(i + 1).min(n - 1)],
        ];
        let dtdm = |nodes: &[usize], ff: &[f64], dfdi: &[[f64; 3]]| {
            // te0222, te0147: a cell none of whose nodes lies in [s0, s2).
            if !nodes
                .iter()
                .any(|&m| nodal.theta[m].absc >= lag[0] && nodal.theta[m].absc < lag[2])
            {
                return None;
            }
            let (mut t, mut th) = ([[0.0; 3]; 3], [0.0; 3]);
            for (a, &m) in nodes.iter().enumerate() {
                let b = &nodal.theta[m];
                let w = hat(b.absc, lag) * nodal.theta0[m];
                for j in 0..3 {
                    th[j] += ff[a] * (w * b.dir[j]);
                    for k in 0..3 {
                        t[j][k] += dfdi[a][k] * (w * b.dir[j]);
                    }
                }
            }
            Some((t, th))
        };
        let mut v = integrate(&data, &dtdm, wanted);
        v.gth += integrate_faces(&face_data, &dtdm);
        out.push(v);
    }
    Ok(out)
}

/// The normalised Legendre polynomial of degree `d` on [0, l] and its
/// derivative at `s` (`plegen`, `dplegen`: degree 7 at most).
pub fn legendre(d: usize, s: f64, l: f64) -> Option<(f64, f64)> {
    let x = 2.0 * s / l - 1.0;
    let (p, dp) = match d {
        0 => (1.0, 0.0),
        1 => (x, 1.0),
        2 => ((3.0 * x * x - 1.0) / 2.0, 3.0 * x),
        3 => (
            x * (5.0 * x * x - 3.0) / 2.0,
            (15.0 * x.powi(2) - 3.0) / 2.0,
        ),
        4 => (
            (35.0 * x.powi(4) - 30.0 * x * x + 3.0) / 8.0,
            (35.0 * x.powi(3) - 15.0 * x) / 2.0,
        ),
        5 => (
            x * (63.0 * x.powi(4) - 70.0 * x * x + 15.0) / 8.0,
            15.0 * (21.0 * x.powi(4) - 14.0 * x.powi(2) + 1.0) / 8.0,
        ),
        6 => (
            (231.0 * x.powi(6) - 315.0 * x.powi(4) + 105.0 * x * x - 5.0) / 16.0,
            21.0 * (33.0 * x.powi(5) - 30.0 * x.powi(3) + 5.0 * x) / 8.0,
        ),
        7 => (
            x * (429.0 * x.powi(6) - 693.0 * x.powi(4) + 315.0 * x * x - 35.0) / 16.0,
            7.0 * (429.0 * x.powi(6) - 495.0 * x.powi(4) + 135.0 * x.powi(2) - 5.0) / 16.0,
        ),
        _ => return None,
    };
    let coef = ((2 * d + 1) as f64 / l).sqrt();
    Some((coef * p, 2.0 / l * coef * dp))
}

/// The values of the Legendre theta fields of degrees 0 to `degree`
/// (`DISCRETISATION='LEGENDRE'`): at a Gauss point θ = P_d(s)·theta0·dir,
/// s, theta0 and dir interpolated from the nodes (`thetapdg`), on a front
/// of length `l`.
pub fn k_theta_legendre(
    mesh: &Mesh,
    cells: &[SolidCell],
    faces: &[FaceLoad],
    nodal: &NodalData,
    l: f64,
    degree: usize,
    wanted: Wanted,
) -> Result<Vec<KTheta>, String> {
    if degree > 7 {
        return Err(format!(
            "DEGRE = {degree}: code_aster's Legendre polynomials stop at 7"
        ));
    }
    let data = cell_data(mesh, cells, nodal, wanted.k)?;
    let face_data = face_loads(mesh, cells, faces, nodal, wanted)?;
    let mut out = Vec::with_capacity(degree + 1);
    for d in 0..=degree {
        let dtdm = |nodes: &[usize], ff: &[f64], dfdi: &[[f64; 3]]| {
            let (mut th0, mut s, mut t) = (0.0, 0.0, [0.0; 3]);
            let (mut gth0, mut gs, mut gt) = ([0.0; 3], [0.0; 3], [[0.0; 3]; 3]);
            for (a, &m) in nodes.iter().enumerate() {
                let b = &nodal.theta[m];
                th0 += ff[a] * nodal.theta0[m];
                s += ff[a] * b.absc;
                for j in 0..3 {
                    t[j] += ff[a] * b.dir[j];
                }
                for k in 0..3 {
                    gth0[k] += dfdi[a][k] * nodal.theta0[m];
                    gs[k] += dfdi[a][k] * b.absc;
                    for j in 0..3 {
                        gt[j][k] += dfdi[a][k] * b.dir[j];
                    }
                }
            }
            let (gam, dgam) = legendre(d, s, l)?;
            let mut r = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    r[i][j] = t[i] * (dgam * th0 * gs[j] + gam * gth0[j]) + gam * th0 * gt[i][j];
                }
            }
            Some((r, t.map(|v| gam * th0 * v)))
        };
        let mut v = integrate(&data, &dtdm, wanted);
        v.gth += integrate_faces(&face_data, &dtdm);
        out.push(v);
    }
    Ok(out)
}

/// The nodal values from the Legendre fields' (`glegen`): at front node i,
/// Σ_d value_d · P_d(s_i).
pub fn legendre_nodal(absfon: &[f64], l: f64, fields: &[KTheta]) -> Result<Vec<KTheta>, String> {
    absfon
        .iter()
        .map(|&s| {
            let mut o = KTheta::default();
            for (d, f) in fields.iter().enumerate() {
                let (p, _) = legendre(d, s, l).ok_or("a Legendre degree above 7")?;
                o.gth += f.gth * p;
                for m in 0..3 {
                    o.k[m] += f.k[m] * p;
                    o.g[m] += f.g[m] * p;
                }
            }
            Ok(o)
        })
        .collect()
}

/// The nodal values along an open front from the theta fields'
/// (`cgComputeGtheta`'s end corrections, `gmatc3`, `gsyste`,
/// `hatSmooth`). `milieu`: the lips' cells are quadratic (code_aster's
/// `cgTheta%milieu`, a front of SEG3 cells whose middle nodes have theta
/// fields of their own): the ends' values are their neighbour's / 4, the
/// matrix is the SEG3 cells' mass matrix, and the solution is smoothed by
/// the cells' hats.
pub fn smooth_linear(
    absfon: &[f64],
    fields: &[KTheta],
    milieu: bool,
) -> Result<Vec<KTheta>, String> {
    let n = absfon.len();
    if fields.len() != n || n < 2 {
        return Err("one theta field per front node, two nodes at least".into());
    }
    if milieu && n.is_multiple_of(2) {
        return Err("quadratic lips along a front of an even number of nodes".into());
    }
    if n == 3 && !milieu {
        return Err(
            "a front of 3 nodes: code_aster's end correction reads the abscissa before the first node"
                .into(),
        );
    }
    let mut f: Vec<[f64; 7]> = fields
        .iter()
        .map(|k| [k.gth, k.k[0], k.k[1], k.k[2], k.g[0], k.g[1], k.g[2]])
        .collect();
    if n != 2 {
        let (first, last) = if milieu {
            (f[1].map(|v| v / 4.0), f[n - 2].map(|v| v / 4.0))
        } else {
            let (s1, s2, s3) = (absfon[0], absfon[1], absfon[2]);
            let (sn2, sn1, sn) = (absfon[n - 4], absfon[n - 3], absfon[n - 2]);
            (
                f[1].map(|v| v * (s2 - s1) / (s3 - s1)),
                f[n - 2].map(|v| v * (sn - sn1) / (sn - sn2)),
            )
        };
        f[0] = first;
        f[n - 1] = last;
    }
    // The mass matrix of the front's cells (gmate3's 14 Gauss points
    // integrate it exactly): SEG2 [2 1; 1 2] l/6, SEG3 (ends, middle)
    // [4 −1 2; −1 4 2; 2 2 16] l/30 with l its ends' abscissa gap.
    let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
    if milieu {
        let mele = [[4.0, -1.0, 2.0], [-1.0, 4.0, 2.0], [2.0, 2.0, 16.0]];
        for s in 0..(n - 1) / 2 {
            let conn = [2 * s, 2 * s + 2, 2 * s + 1];
            let l = absfon[conn[1]] - absfon[conn[0]];
            for i in 0..3 {
                for j in 0..3 {
                    m[(conn[i], conn[j])] += mele[i][j] * l / 30.0;
                }
            }
        }
    } else {
        for s in 0..n - 1 {
            let l = absfon[s + 1] - absfon[s];
            m[(s, s)] += l / 3.0;
            m[(s + 1, s + 1)] += l / 3.0;
            m[(s, s + 1)] += l / 6.0;
            m[(s + 1, s)] += l / 6.0;
        }
    }
    let mtm = m.transpose() * &m;
    let lu = mtm.lu();
    let mut x = Vec::with_capacity(7);
    for c in 0..7 {
        let rhs = m.transpose() * nalgebra::DVector::from_iterator(n, f.iter().map(|v| v[c]));
        let mut xc: Vec<f64> = lu
            .solve(&rhs)
            .ok_or(
                "the front's smoothing system is singular (two front nodes at the same abscissa)",
            )?
            .iter()
            .copied()
            .collect();
        if milieu && n / 2 > 1 {
            hat_smooth(absfon, &mut xc);
        }
        x.push(xc);
    }
    Ok((0..n)
        .map(|i| KTheta {
            gth: x[0][i],
            k: [x[1][i], x[2][i], x[3][i]],
            g: [x[4][i], x[5][i], x[6][i]],
        })
        .collect())
}

/// `hatSmooth`: the values at the ends of the SEG3 cells of a front of
/// `v.len()` (odd) nodes replaced by a weighted mean with the middle
/// nodes beside them, the middle nodes by the mean of their ends.
fn hat_smooth(absfon: &[f64], v: &mut [f64]) {
    let nno = v.len();
    let nnos = nno / 2 + 1;
    // le: the cells' lengths; lg, ld: the weights of the middle nodes
    // before and after an inner end.
    let le: Vec<f64> = (0..nnos - 1)
        .map(|i| (absfon[2 * i + 2] - absfon[2 * i]).abs())
        .collect();
    let mut smooth = vec![0.0; nnos];
    smooth[0] = (2.0 * v[0] + v[1]) / 3.0;
    for j in 1..nnos - 1 {
        let lg = 2.0 * le[j - 1] / (le[j - 1] + le[j]);
        let ld = 2.0 * le[j] / (le[j - 1] + le[j]);
        smooth[j] = (lg * v[2 * j - 1] + v[2 * j] + ld * v[2 * j + 1]) / 3.0;
    }
    smooth[nnos - 1] = (v[nno - 2] + 2.0 * v[nno - 1]) / 3.0;
    for j in 0..nnos {
        v[2 * j] = smooth[j];
    }
    for j in 0..nnos - 1 {
        v[2 * j + 1] = (smooth[j] + smooth[j + 1]) / 2.0;
    }
}

/// The `NB_POINT_FOND` front (`create_npf`): `npf` points at equal
/// abscissae along the front, its first and last nodes at the ends, the
/// points between with the coordinates and basis (`BASNOF`) linearly
/// interpolated on the front's segment holding them (the first node whose
/// abscissa exceeds theirs ends it).
pub struct VirtualFront {
    pub coords: Vec<[f64; 3]>,
    pub normal: Vec<[f64; 3]>,
    pub dir: Vec<[f64; 3]>,
    pub absc: Vec<f64>,
}

pub fn virtual_front(front: &Front, npf: usize) -> Result<VirtualFront, String> {
    let nb = front.coords.len();
    if npf < 2 || nb < 2 {
        return Err(format!("NB_POINT_FOND = {npf}: two points at least"));
    }
    let smax = front.absc[nb - 1];
    let mut out = VirtualFront {
        coords: vec![front.coords[0]; npf],
        normal: vec![front.normal[0]; npf],
        dir: vec![front.dir[0]; npf],
        absc: vec![0.0; npf],
    };
    out.coords[npf - 1] = front.coords[nb - 1];
    out.normal[npf - 1] = front.normal[nb - 1];
    out.dir[npf - 1] = front.dir[nb - 1];
    out.absc[npf - 1] = smax;
    // create_npf's a + (b − a)(s − s1)/(s2 − s1), in its order.
    let lerp = |a: [f64; 3], b: [f64; 3], num: f64, den: f64| {
        [
            a[0] + (b[0] - a[0]) * num / den,
            a[1] + (b[1] - a[1]) * num / den,
            a[2] + (b[2] - a[2]) * num / den,
        ]
    };
    for i in 1..npf - 1 {
        let s = i as f64 * smax / (npf - 1) as f64;
        let k = (0..nb)
            .find(|&k| front.absc[k] > s)
            .filter(|&k| k > 0)
            .ok_or_else(|| format!("NB_POINT_FOND: no front segment holds the abscissa {s}"))?;
        let (s1, s2) = (front.absc[k - 1], front.absc[k]);
        let (num, den) = (s - s1, s2 - s1);
        out.coords[i] = lerp(front.coords[k - 1], front.coords[k], num, den);
        out.normal[i] = lerp(front.normal[k - 1], front.normal[k], num, den);
        out.dir[i] = lerp(front.dir[k - 1], front.dir[k], num, den);
        out.absc[i] = s;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn abscissa_and_projection() {
        let coords = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 3.0]];
        let s = front_abscissa(&coords);
        assert_eq!(s, vec![0.0, 1.0, 3.0]);
        let normal = [[0.0, 1.0, 0.0]; 3];
        let dir = [[1.0, 0.0, 0.0]; 3];
        let front = Front {
            coords: &coords,
            normal: &normal,
            dir: &dir,
            absc: &s,
            quadratic: false,
        };
        let b = node_bases(&front, &[[2.0, 0.5, 2.0], [1.0, 0.0, 5.0]]);
        assert_eq!(b[0].proj, [0.0, 0.0, 2.0]);
        assert!((b[0].absc - 2.0).abs() < 1e-15);
        // Beyond the end: clamped to the last node.
        assert_eq!(b[1].proj, [0.0, 0.0, 3.0]);
        assert_eq!(b[1].absc, 3.0);
        let t = theta0(&b[0], [2.0, 0.5, 2.0], 1.0, 3.0);
        assert!((t - (1.0 - ((4.25f64).sqrt() - 1.0) / 2.0)).abs() < 1e-15);
    }

    /// The smoothing of a constant field on a uniform front gives it back
    /// at the inner nodes (M 1 = row sums; the ends get half of their
    /// neighbour's value before the solve).
    #[test]
    fn smoothing_constant() {
        let absfon: Vec<f64> = (0..6).map(|i| i as f64 * 0.5).collect();
        // Theta-field values of a constant K = 2: M·[2…] = row sums × 2.
        let mut fields = vec![KTheta::default(); 6];
        for (i, f) in fields.iter_mut().enumerate() {
            let w = if i == 0 || i == 5 { 0.25 } else { 0.5 };
            f.k = [2.0 * w, 0.0, 0.0];
        }
        let out = smooth_linear(&absfon, &fields, false).unwrap();
        for o in &out {
            assert!((o.k[0] - 2.0).abs() < 1e-12, "{o:?}");
        }
    }

    /// On a quadratic front (`milieu`) a hat sampled at the nodes of
    /// quadratic cells is, along the front, the SEG3 shape function of its
    /// node: the theta-field values of a constant K are K times their
    /// integrals (L/6 at a cell's end, 2L/3 at its middle). The ends'
    /// correction (a quarter of the middle's: L/6 again), the SEG3 system
    /// and `hatSmooth` give K back at every node, on unequal cells too.
    #[test]
    fn quadratic_smoothing_constant() {
        // Three SEG3 cells of lengths 0.2, 0.4, 0.2: 7 nodes.
        let absfon = [0.0, 0.1, 0.2, 0.4, 0.6, 0.7, 0.8];
        let mut fields = vec![KTheta::default(); 7];
        for c in 0..3 {
            let l = absfon[2 * c + 2] - absfon[2 * c];
            for (node, w) in [
                (2 * c, l / 6.0),
                (2 * c + 1, 2.0 * l / 3.0),
                (2 * c + 2, l / 6.0),
            ] {
                fields[node].gth += 3.0 * w;
                fields[node].k[0] += 2.0 * w;
            }
        }
        // The ends' own values are replaced.
        fields[0].gth = 100.0;
        fields[6].k[0] = -7.0;
        let out = smooth_linear(&absfon, &fields, true).unwrap();
        for o in &out {
            assert!((o.gth - 3.0).abs() < 1e-12, "{o:?}");
            assert!((o.k[0] - 2.0).abs() < 1e-12, "{o:?}");
        }
        // An even number of nodes cannot be SEG3 cells.
        assert!(smooth_linear(&absfon[..6], &fields[..6], true).is_err());
    }

    /// hatSmooth on a linear field along equal cells keeps it (the weights
    /// are 1 and the means of neighbours are exact), the middle nodes
    /// becoming their ends' mean.
    #[test]
    fn hat_smoothing_keeps_a_linear_field() {
        let absfon = [0.0, 0.5, 1.0, 1.5, 2.0];
        let mut v = [1.0, 7.0, 3.0, -2.0, 5.0];
        hat_smooth(&absfon, &mut v);
        // Corners: (2·1 + 7)/3, (7 + 3 − 2)/3, (−2 + 2·5)/3.
        let c = [3.0, 8.0 / 3.0, 8.0 / 3.0];
        assert!((v[0] - c[0]).abs() < 1e-15);
        assert!((v[2] - c[1]).abs() < 1e-15);
        assert!((v[4] - c[2]).abs() < 1e-15);
        assert!((v[1] - (c[0] + c[1]) / 2.0).abs() < 1e-15);
        assert!((v[3] - (c[1] + c[2]) / 2.0).abs() < 1e-15);
    }

    /// create_npf: points at equal abscissae along a bent front, the
    /// coordinates and bases interpolated on the segment holding them.
    #[test]
    fn nb_point_fond_points() {
        let coords = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        let absc = front_abscissa(&coords);
        let normal = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let dir = [[1.0, 0.0, 0.0]; 3];
        let front = Front {
            coords: &coords,
            normal: &normal,
            dir: &dir,
            absc: &absc,
            quadratic: false,
        };
        let v = virtual_front(&front, 5).unwrap();
        assert_eq!(v.absc, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(v.coords[1], [0.0, 0.0, 0.5]);
        // s = 1 lies on the second segment (the first node beyond it).
        assert_eq!(v.coords[2], [0.0, 0.0, 1.0]);
        assert_eq!(v.coords[3], [0.0, 0.5, 1.0]);
        assert_eq!(v.normal[3], [0.0, 0.5, 0.5]);
        assert_eq!(v.coords[4], coords[2]);
        assert!(virtual_front(&front, 1).is_err());
    }

    /// fonbas2 on a quadratic front projects on the segments between the
    /// cells' ends: a middle node off the chord changes nothing.
    #[test]
    fn quadratic_front_projects_on_the_chords() {
        let coords = [[0.0, 0.0, 0.0], [0.3, 0.0, 1.0], [0.0, 0.0, 2.0]];
        let absc = front_abscissa(&coords);
        let normal = [[0.0, 1.0, 0.0]; 3];
        let dir = [[1.0, 0.0, 0.0]; 3];
        let mut front = Front {
            coords: &coords,
            normal: &normal,
            dir: &dir,
            absc: &absc,
            quadratic: true,
        };
        let b = node_bases(&front, &[[1.0, 0.0, 1.0]]);
        assert_eq!(b[0].proj, [0.0, 0.0, 1.0]);
        assert!((b[0].absc - absc[2] / 2.0).abs() < 1e-15);
        front.quadratic = false;
        let b = node_bases(&front, &[[1.0, 0.0, 1.0]]);
        assert_eq!(b[0].proj, [0.3, 0.0, 1.0]);
    }

    /// plegen's polynomials are orthonormal on [0, l] (Simpson on a fine
    /// grid) and dplegen's derivatives match finite differences.
    #[test]
    fn legendre_orthonormal() {
        let l = 2.5;
        let n = 2000;
        for d in 0..=7 {
            for e in 0..=7 {
                let mut sum = 0.0;
                for i in 0..=n {
                    let s = l * i as f64 / n as f64;
                    let w = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    sum += w * legendre(d, s, l).unwrap().0 * legendre(e, s, l).unwrap().0;
                }
                sum *= l / n as f64 / 3.0;
                let expected = if d == e { 1.0 } else { 0.0 };
                assert!((sum - expected).abs() < 1e-8, "{d} {e} {sum}");
            }
            let (s, h) = (0.7, 1e-6);
            let fd =
                (legendre(d, s + h, l).unwrap().0 - legendre(d, s - h, l).unwrap().0) / (2.0 * h);
            assert!((fd - legendre(d, s, l).unwrap().1).abs() < 1e-6, "{d}");
        }
        assert!(legendre(8, 0.0, l).is_none());
    }

    /// The auxiliary mode-I field ahead of a straight front: ∂u_x/∂x =
    /// (κ−1)/(4μ√(2πr)) at φ = 0.
    #[test]
    fn auxiliary_mode_one_ahead() {
        let (mu, ka) = (1.5, 1.8);
        let invp = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let courb = [[[0.0; 3]; 3]; 3];
        let r = 0.2;
        let aux = chauxi(mu, ka, r, 0.0, &invp, &courb);
        let expected = (ka - 1.0) / (4.0 * mu * (2.0 * std::f64::consts::PI * r).sqrt());
        assert!((aux[0][0][0] - expected).abs() < 1e-14);
        // Mode III: u_z = 4 cr2 sin(φ/2): ∂u_z/∂y at φ = 0 is 2 cr2 / r.
        let cr2 = (r / (2.0 * std::f64::consts::PI)).sqrt() / (2.0 * mu);
        assert!((aux[2][2][1] - 2.0 * cr2 / r).abs() < 1e-14);
    }
}
