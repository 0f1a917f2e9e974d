//! Fracture mechanics: in 2D, the energy release rate G by the G-theta
//! method and the stress intensity factors K1, K2 by the interaction
//! integral with the singular auxiliary fields, as code_aster's `CALC_G`
//! computes them on plane elastic elements (`te0096` for option `G`,
//! `te0299`/`gbilin`/`chauxi` for option `K`).
//!
//! The theta field ([`theta_field`], code_aster's `gcou2d`) is the unit
//! crack direction at the nodes closer to the tip than `r_inf`, zero beyond
//! `r_sup`, and linear in the node's distance to the tip in between.
//! G = Σ over the Gauss points (the stiffness family) of
//! w·det J·(σ : (∇u·∇θ) − W div θ), W = ½ σ:ε; K1, K2 the same bilinear
//! form between u and the auxiliary fields of a unit K1 or K2 (Westergaard
//! displacements in the crack's local polar frame), times E/(1−ν²) in
//! plane strain, E in plane stress. Linear elastic cells only, no thermal
//! strain, no initial stress, no loads on the cells theta reaches (the
//! caller checks).
//!
//! In 3D: the crack front DEFI_FOND_FISS builds from a meshed crack
//! ([`front3d`]) and POST_K1_K2_K3's extrapolation of the lips' jump
//! ([`post_k`]).

pub mod front3d;
pub mod post_k;
pub mod theta3d;

use crate::material::{Elastic, Hypothesis};
use crate::shape;
use aster_mesh::CellType;

/// A crack tip in the plane: its position and the unit direction the crack
/// would grow in (code_aster's `BASEFOND` direction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrackTip {
    pub tip: [f64; 2],
    pub dir: [f64; 2],
}

/// One plane cell as the integrals need it.
pub struct PlaneCell<'a> {
    pub ty: CellType,
    pub coords: &'a [[f64; 2]],
    /// Displacement (DX, DY) at each node.
    pub disp: &'a [[f64; 2]],
    /// Theta at each node.
    pub theta: &'a [[f64; 2]],
    pub material: Elastic,
    pub hyp: Hypothesis,
    /// The isotropic free strain α (T − T_ref) at each node (a temperature),
    /// `None` without one.
    pub free_strain: Option<&'a [f64]>,
}

/// The theta vector at a node of coordinates `x` (code_aster's `gcou2d`):
/// `dir` inside `r_inf` (up to 1e-6 relative on the crown's width), 0
/// beyond `r_sup`, `(1 − α)·dir` between, α = (d − r_inf)/(r_sup − r_inf).
pub fn theta_at(tip: &CrackTip, x: [f64; 2], r_inf: f64, r_sup: f64) -> [f64; 2] {
    let eps = 1e-6;
    let d = ((tip.tip[0] - x[0]).powi(2) + (tip.tip[1] - x[1]).powi(2)).sqrt();
    let alpha = (d - r_inf) / (r_sup - r_inf);
    let s = if alpha.abs() <= eps || alpha < 0.0 {
        1.0
    } else if (alpha - 1.0).abs() <= eps || alpha - 1.0 > 0.0 {
        0.0
    } else {
        1.0 - alpha
    };
    [s * tip.dir[0], s * tip.dir[1]]
}

/// The theta field at every node (in order).
pub fn theta_field(tip: &CrackTip, nodes: &[[f64; 2]], r_inf: f64, r_sup: f64) -> Vec<[f64; 2]> {
    nodes
        .iter()
        .map(|&x| theta_at(tip, x, r_inf, r_sup))
        .collect()
}

/// What the K integral gives on a set of cells (code_aster's `te0299`
/// outputs, before the symmetry factor): G, K1/√coef, K2/√coef, K1, K2.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KIntegrals {
    pub g: f64,
    pub fic1: f64,
    pub fic2: f64,
    pub k1: f64,
    pub k2: f64,
}

/// Gradients at one Gauss point: 2×2 gradient of u and theta, theta itself
/// and the weight times det J, and the point.
struct PointData {
    dudm: [[f64; 2]; 2],
    dtdm: [[f64; 2]; 2],
    /// Theta at the point.
    theta: [f64; 2],
    /// The free strain at the point and its gradient (α ∇T).
    eth: f64,
    geth: [f64; 2],
    /// The hoop terms of an axisymmetric cell, u_r/r and θ_r/r (0 in the
    /// plane).
    u_hoop: f64,
    t_hoop: f64,
    /// w·|det J|, times r in axisymmetry (`nmgeom`).
    poids: f64,
    x: [f64; 2],
}

/// The Gauss point data of a cell (its stiffness family); `axis_ok`: AXIS
/// cells are accepted (G), else only D_PLAN and C_PLAN ones (K).
fn points(cell: &PlaneCell, axis_ok: bool) -> Result<Vec<PointData>, String> {
    let nno = cell.coords.len();
    if cell.disp.len() != nno || cell.theta.len() != nno {
        return Err("node count mismatch".into());
    }
    let axis = cell.hyp == Hypothesis::Axisymmetric;
    if !(matches!(cell.hyp, Hypothesis::PlaneStrain | Hypothesis::PlaneStress) || axis && axis_ok) {
        return Err(format!(
            "{}: G in D_PLAN, C_PLAN and AXIS, K in D_PLAN and C_PLAN only",
            cell.hyp.aster_name()
        ));
    }
    let mut out = Vec::new();
    for gp in shape::stiffness_scheme(cell.ty, Some(cell.hyp)) {
        let s = shape::shape(cell.ty, gp.xi);
        if s.n.len() != nno {
            return Err(format!("{:?}: not a plane cell", cell.ty));
        }
        let mut jac = [[0.0; 2]; 2];
        let mut x = [0.0; 2];
        for i in 0..nno {
            for a in 0..2 {
                x[a] += s.n[i] * cell.coords[i][a];
                for k in 0..2 {
                    jac[k][a] += s.dn[i][k] * cell.coords[i][a];
                }
            }
        }
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        if det.abs() < 1e-300 {
            return Err("degenerate cell".into());
        }
        let inv = [
            [jac[1][1] / det, -jac[0][1] / det],
            [-jac[1][0] / det, jac[0][0] / det],
        ];
        let mut dudm = [[0.0; 2]; 2];
        let mut dtdm = [[0.0; 2]; 2];
        let mut theta = [0.0; 2];
        let mut eth = 0.0;
        let mut geth = [0.0; 2];
        let (mut u_r, mut t_r) = (0.0, 0.0);
        for i in 0..nno {
            u_r += s.n[i] * cell.disp[i][0];
            t_r += s.n[i] * cell.theta[i][0];
            // ∂N/∂x_k = Σ_l inv[k][l] ∂N/∂ξ_l
            let d = [
                inv[0][0] * s.dn[i][0] + inv[0][1] * s.dn[i][1],
                inv[1][0] * s.dn[i][0] + inv[1][1] * s.dn[i][1],
            ];
            for j in 0..2 {
                theta[j] += cell.theta[i][j] * s.n[i];
                for k in 0..2 {
                    dudm[j][k] += cell.disp[i][j] * d[k];
                    dtdm[j][k] += cell.theta[i][j] * d[k];
                }
            }
            if let Some(fs) = cell.free_strain {
                eth += s.n[i] * fs[i];
                geth[0] += d[0] * fs[i];
                geth[1] += d[1] * fs[i];
            }
        }
        let (u_hoop, t_hoop, r) = if axis {
            if x[0] <= 0.0 {
                return Err("an axisymmetric Gauss point on or left of the axis".into());
            }
            (u_r / x[0], t_r / x[0], x[0])
        } else {
            (0.0, 0.0, 1.0)
        };
        out.push(PointData {
            dudm,
            dtdm,
            theta,
            eth,
            geth,
            u_hoop,
            t_hoop,
            poids: gp.weight * det.abs() * r,
            x,
        });
    }
    Ok(out)
}

fn theta_is_zero(cell: &PlaneCell) -> bool {
    cell.theta
        .iter()
        .all(|t| t[0].abs() + t[1].abs() < f64::EPSILON)
}

/// The theta method's closed forms are the isotropic law's.
fn isotropic(material: &crate::material::Elastic) -> Result<(), String> {
    if material.is_isotropic() {
        Ok(())
    } else {
        Err("the energy release rate of an orthotropic material (ELAS_ORTH) is not computed: the theta method here is the isotropic law's".into())
    }
}

/// G by the theta method on linear elastic cells (`te0096`, elastic,
/// small strains): Σ w det J (σᵢₖ ∂uᵢ/∂xₘ ∂θₘ/∂xₖ − W div θ).
pub fn g_theta(cells: &[PlaneCell]) -> Result<f64, String> {
    let mut g = 0.0;
    for cell in cells {
        if theta_is_zero(cell) {
            continue;
        }
        isotropic(&cell.material)?;
        let (e, nu) = (cell.material.e, cell.material.nu);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let troisk = e / (1.0 - 2.0 * nu);
        let thermal = cell.free_strain.is_some();
        if cell
            .free_strain
            .is_some_and(|f| f.len() != cell.coords.len())
        {
            return Err("free strain: node count mismatch".into());
        }
        for p in points(cell, true)? {
            let ther = p.eth;
            // The total strain (tensor), εzz as nmelnl fills it (the hoop
            // strain u_r/r in axisymmetry).
            let e33 = match cell.hyp {
                Hypothesis::PlaneStress => {
                    -nu / (1.0 - nu) * (p.dudm[0][0] + p.dudm[1][1])
                        + (1.0 + nu) / (1.0 - nu) * ther
                }
                Hypothesis::Axisymmetric => p.u_hoop,
                _ => 0.0,
            };
            let exy = 0.5 * (p.dudm[0][1] + p.dudm[1][0]);
            // The mechanical strain ε − ε_th.
            let em = [p.dudm[0][0] - ther, p.dudm[1][1] - ther, e33 - ther];
            let divu = em[0] + em[1] + em[2];
            let sig = [
                lambda * divu + 2.0 * mu * em[0],
                lambda * divu + 2.0 * mu * em[1],
                lambda * divu + 2.0 * mu * em[2],
                2.0 * mu * exy,
            ];
            // ½ σ : (ε − ε_th) (tensor: the shear counts twice).
            let energy = 0.5 * (sig[0] * em[0] + sig[1] * em[1] + sig[2] * em[2]) + sig[3] * exy;
            let sr = [[sig[0], sig[3]], [sig[3], sig[1]]];
            let mut prod = 0.0;
            for i in 0..2 {
                for k in 0..2 {
                    for m in 0..2 {
                        prod += sr[i][k] * p.dudm[i][m] * p.dtdm[m][k];
                    }
                }
            }
            // The hoop term σθθ (u_r/r)(θ_r/r) of te0096 (0 in the plane).
            prod += sig[2] * p.u_hoop * p.t_hoop;
            let divt = p.dtdm[0][0] + p.dtdm[1][1] + p.t_hoop;
            g += p.poids * (prod - energy * divt);
            if thermal {
                // −poids (∇T·θ) ∂W/∂T, ∂W/∂T = −3k α div(u − u_th).
                let gt = p.geth[0] * p.theta[0] + p.geth[1] * p.theta[1];
                g += p.poids * gt * troisk * divu;
            }
        }
    }
    Ok(g)
}

/// The bilinear form of `gbilin` (plane, no thermal, no initial stress,
/// no forces): (−div θ/2 · s1 + s2)·poids.
struct Bilin {
    c: [f64; 3],
    th: f64,
    /// E / (1 − 2ν).
    troisk: f64,
}

fn gbilin(u: &[[f64; 2]; 2], v: &[[f64; 2]; 2], p: &PointData, b: &Bilin, coef: f64) -> f64 {
    let (dudm, dvdm, dtdm, c, poids) = (u, v, &p.dtdm, b.c, p.poids);
    let vect = [
        0.5 * (dvdm[0][0] * dudm[1][1] + dudm[0][0] * dvdm[1][1]),
        0.5 * (dvdm[0][0] * dudm[0][1] + dudm[0][0] * dvdm[0][1]),
        0.5 * (dvdm[0][0] * dudm[1][0] + dudm[0][0] * dvdm[1][0]),
        0.5 * (dvdm[1][1] * dudm[0][1] + dudm[1][1] * dvdm[0][1]),
        0.5 * (dvdm[1][1] * dudm[1][0] + dudm[1][1] * dvdm[1][0]),
        0.5 * (dvdm[0][1] * dudm[1][0] + dudm[0][1] * dvdm[1][0]),
    ];
    let s11 = dudm[0][0] * dvdm[0][0] + dudm[1][1] * dvdm[1][1];
    let s12 = dudm[0][0] * dvdm[1][1] + dudm[1][1] * dvdm[0][0];
    let s13 = (dudm[0][1] + dudm[1][0]) * (dvdm[0][1] + dvdm[1][0]);
    let s21 = dudm[0][0] * dvdm[0][0] * dtdm[0][0]
        + dudm[1][1] * dvdm[1][1] * dtdm[1][1]
        + vect[4] * dtdm[0][1]
        + vect[1] * dtdm[1][0];
    let s22 = vect[0] * (dtdm[0][0] + dtdm[1][1]) + vect[2] * dtdm[0][1] + vect[3] * dtdm[1][0];
    let s23 = (vect[5] + dudm[1][0] * dvdm[1][0]) * dtdm[0][0]
        + (vect[5] + dudm[0][1] * dvdm[0][1]) * dtdm[1][1]
        + (vect[1] + vect[2]) * dtdm[0][1]
        + (vect[3] + vect[4]) * dtdm[1][0];
    let s1 = c[0] * s11 + c[1] * s12 + c[2] * s13;
    let s2 = c[0] * s21 + c[1] * s22 + c[2] * s23;
    let divt = dtdm[0][0] + dtdm[1][1];
    let divv = b.th * (dvdm[0][0] + dvdm[1][1]);
    let s1th = coef * p.eth * divv * b.troisk;
    let mut prod = 0.0;
    for i in 0..2 {
        for j in 0..2 {
            prod += dvdm[i][j] * dtdm[j][i];
        }
    }
    let s2th = 0.5 * b.th * coef * p.eth * prod * b.troisk;
    let tcla = (-divt / 2.0 * (s1 - s1th) + (s2 - s2th)) * poids;
    let gt = p.geth[0] * p.theta[0] + p.geth[1] * p.theta[1];
    let tthe = poids * gt * divv * coef * b.troisk / 2.0;
    tcla + tthe
}

/// The gradients (global frame) of the auxiliary fields of a unit K1 and
/// K2 at polar coordinates (r, t) of the crack's local frame whose axes
/// are the columns of `p` (`chauxi`, 2D).
fn auxiliary(mu: f64, ka: f64, r: f64, t: f64, p: [[f64; 2]; 2]) -> ([[f64; 2]; 2], [[f64; 2]; 2]) {
    let two_pi = 2.0 * std::f64::consts::PI;
    let cr1 = 1.0 / (4.0 * mu * (two_pi * r).sqrt());
    let cr2 = (r / two_pi).sqrt() / (2.0 * mu);
    let (h, c, s) = (t * 0.5, t.cos(), t.sin());
    let du1dpo = [
        [
            cr1 * (h.cos() * (ka - c)),
            cr2 * (-0.5 * h.sin() * (ka - c) + h.cos() * s),
        ],
        [
            cr1 * (h.sin() * (ka - c)),
            cr2 * (0.5 * h.cos() * (ka - c) + h.sin() * s),
        ],
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
    ];
    let to_global = |dpo: [[f64; 2]; 2]| {
        let mut dl = [[0.0; 2]; 2];
        for i in 0..2 {
            dl[i][0] = c * dpo[i][0] - s / r * dpo[i][1];
            dl[i][1] = s * dpo[i][0] + c / r * dpo[i][1];
        }
        // invp = pᵀ: du/dm(i,j) = Σ_kl dl(k,l) invp(l,j) invp(k,i) = Σ p(j,l) p(i,k) dl(k,l)
        let mut dm = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                for k in 0..2 {
                    for l in 0..2 {
                        dm[i][j] += dl[k][l] * p[j][l] * p[i][k];
                    }
                }
            }
        }
        dm
    };
    (to_global(du1dpo), to_global(du2dpo))
}

/// G, K1 and K2 by the interaction integral (`te0299`), summed over the
/// cells.
pub fn k_theta(cells: &[PlaneCell], tip: &CrackTip) -> Result<KIntegrals, String> {
    let norm = (tip.dir[0].powi(2) + tip.dir[1].powi(2)).sqrt();
    if norm < 1e-300 {
        return Err("no crack direction".into());
    }
    let e1 = [tip.dir[0] / norm, tip.dir[1] / norm];
    // The normal (−dir_y, dir_x) (cakg2d's XNORM, YNORM), normalised.
    let e2 = [-e1[1], e1[0]];
    // p's columns are e1, e2.
    let p = [[e1[0], e2[0]], [e1[1], e2[1]]];
    let mut out = KIntegrals::default();
    for cell in cells {
        if theta_is_zero(cell) {
            continue;
        }
        isotropic(&cell.material)?;
        let (e, nu) = (cell.material.e, cell.material.nu);
        let c3 = e / (2.0 * (1.0 + nu));
        let mu = c3;
        let (ka, c1, c2, coefk, th) = if cell.hyp == Hypothesis::PlaneStrain {
            let c1 = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
            (
                3.0 - 4.0 * nu,
                c1,
                nu / (1.0 - nu) * c1,
                e / (1.0 - nu * nu),
                1.0,
            )
        } else {
            let c1 = e / (1.0 - nu * nu);
            let th = (1.0 - 2.0 * nu) / (1.0 - nu);
            ((3.0 - nu) / (1.0 + nu), c1, nu * c1, e, th)
        };
        let b = Bilin {
            c: [c1, c2, c3],
            th,
            troisk: e / (1.0 - 2.0 * nu),
        };
        let (mut g, mut k1, mut k2) = (0.0, 0.0, 0.0);
        for pt in points(cell, false)? {
            let og = [pt.x[0] - tip.tip[0], pt.x[1] - tip.tip[1]];
            let cosi = e1[0] * og[0] + e1[1] * og[1];
            let sinu = e2[0] * og[0] + e2[1] * og[1];
            let r = (cosi * cosi + sinu * sinu).sqrt();
            let t = sinu.atan2(cosi);
            let (du1, du2) = auxiliary(mu, ka, r, t, p);
            g += gbilin(&pt.dudm, &pt.dudm, &pt, &b, 2.0);
            k1 += gbilin(&pt.dudm, &du1, &pt, &b, 1.0);
            k2 += gbilin(&pt.dudm, &du2, &pt, &b, 1.0);
        }
        // Per cell, with the cell's own moduli (te0299's outputs, summed
        // over the cells by mesomm).
        let (k1, k2) = (k1 * coefk, k2 * coefk);
        out.g += g;
        out.fic1 += k1 / coefk.sqrt();
        out.fic2 += k2 / coefk.sqrt();
        out.k1 += k1;
        out.k2 += k2;
    }
    Ok(out)
}

/// The characteristic cell size at the tip (code_aster's `fonno7`): over
/// the edges of the plane cells that hold the tip node and end at it, the
/// largest projection of the edge on the crack direction among the edges
/// within 70° of it (or of its opposite). `edges` are the vectors from the
/// tip to the other end of each such edge.
pub fn tip_cell_size(edges: &[[f64; 2]], dir: [f64; 2]) -> f64 {
    let cos70 = (70.0_f64).to_radians().cos();
    let mut hmax = f64::EPSILON;
    for v in edges {
        let p = v[0] * dir[0] + v[1] * dir[1];
        let normv = (v[0] * v[0] + v[1] * v[1]).sqrt();
        if normv == 0.0 || (p / normv).abs() < cos70 {
            continue;
        }
        if p.abs() >= hmax {
            hmax = p.abs();
        }
    }
    hmax
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn theta_crown() {
        let tip = CrackTip {
            tip: [0.0, 0.0],
            dir: [1.0, 0.0],
        };
        assert_eq!(theta_at(&tip, [0.5, 0.0], 1.0, 2.0), [1.0, 0.0]);
        assert_eq!(theta_at(&tip, [3.0, 0.0], 1.0, 2.0), [0.0, 0.0]);
        let t = theta_at(&tip, [0.0, 1.5], 1.0, 2.0);
        assert!((t[0] - 0.5).abs() < 1e-15 && t[1] == 0.0);
    }

    /// The auxiliary mode-I field's interaction with itself on a uniform
    /// theta crown gives back K1 = 1: u = the exact K1 field on a disc of
    /// QUAD4 cells would, but a single check of the Westergaard gradient
    /// is enough here: the displacement of a unit K1 at t = 0 is
    /// (κ−1)√(r/2π)/(2μ) along the crack.
    #[test]
    fn auxiliary_field_along_the_crack() {
        let (mu, ka) = (1.0, 2.0);
        let p = [[1.0, 0.0], [0.0, 1.0]];
        let r = 0.3;
        let (du1, _) = auxiliary(mu, ka, r, 0.0, p);
        // ∂u_x/∂x at t = 0: d/dr of (κ−1)√(r/2π)/(2μ) = (κ−1)/(4μ√(2πr))
        let expected = (ka - 1.0) / (4.0 * mu * (2.0 * std::f64::consts::PI * r).sqrt());
        assert!((du1[0][0] - expected).abs() < 1e-14);
    }
}
