//! `POST_K1_K2_K3` on a meshed 3D crack with lips on both sides, on a
//! regular mesh (`TYPE_MAILLAGE='REGLE'`), as code_aster's Python macro
//! (`post_k1_k2_k3_ops.py`) computes it: K1, K2, K3 and G at each front
//! node by extrapolating the jump of displacement across the lips along
//! the lip nodes normal to the front.
//!
//! - the lip nodes used at a front node: those of DEFI_FOND_FISS's normal
//!   lists (`SUPNORM.NOEU`, `INFNORM.NOEU`, the front node first) closer
//!   to it than `hmax (1 + PREC_VIS_A_VIS/10)` (`get_noeuds_perp_regle`),
//!   `hmax` = `ABSC_CURV_MAXI`, else 4 × the largest cell size along the
//!   front; a lower-lip node is kept when it lies within
//!   `PREC_VIS_A_VIS·hmax` of the upper-lip node of the same rank; a
//!   front node with fewer than 3 nodes on either lip is left out;
//! - the jump: at each upper-lip node, sorted by distance r to the front
//!   node, minus the lower-lip node of the same rank (sorted likewise), in
//!   the frame (normal, direction, normal × direction) of the node;
//! - with s_i = (c·jump_i)², c = E√(2π)/(8(1−ν²)) for modes 1 and 2 and
//!   E√(2π)/(8(1+ν)) for mode 3, the sign of each mode that of the jump
//!   at the farthest node, method 1 fits s/r linearly through the nodes
//!   of rank 2, 3, … (K² = |y1 − r1 (y2 − y1)/(r2 − r1)|, y = s/r), method
//!   2 takes K² = |s/r| at each node but the first, method 3 integrates
//!   √s √r by trapezes (K = Σ(√s₂√r₂ + √s₁√r₁)(r₂ − r₁)/r_max²); each
//!   method's K_MAX, K_MIN are the largest and smallest over its points,
//!   G = (1−ν²)/E (K1² + K2²) + (1+ν)/E K3²;
//! - the table keeps method 1's K_MAX and G_MAX as K1, K2, K3, G, and
//!   ERR_Kj = (max over the methods of Kj_MAX − min of Kj_MIN) / the
//!   largest of those maxima.

use super::front3d::{cross, dot, normalize};
use crate::material::Elastic;

/// One lip node as the method reads it: its distance to the front node
/// and its displacement.
#[derive(Clone, Copy, Debug)]
pub struct LipPoint {
    pub r: f64,
    pub u: [f64; 3],
}

/// What POST_K1_K2_K3 gives at one front node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KValues {
    pub k1: f64,
    pub k2: f64,
    pub k3: f64,
    pub g: f64,
    pub err: [f64; 3],
}

/// The lip nodes kept at a front node (`get_noeuds_perp_regle`): the
/// indices into the normal lists (`sup`, `inf`: the nodes' coordinates),
/// upper then lower, or `None` when fewer than 3 remain on a lip. As the
/// macro, a lower node is compared with the last upper node read.
pub fn keep_lip_nodes(
    front: [f64; 3],
    sup: &[[f64; 3]],
    inf: &[[f64; 3]],
    hmax: f64,
    prec_vis_a_vis: f64,
) -> Option<(Vec<usize>, Vec<usize>)> {
    let rmprec = hmax * (1.0 + prec_vis_a_vis / 10.0);
    let precn = prec_vis_a_vis * hmax;
    let dist = |a: [f64; 3], b: [f64; 3]| {
        let v = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        dot(v, v).sqrt()
    };
    let mut keep_sup = Vec::new();
    let mut keep_inf = Vec::new();
    let mut abss = f64::INFINITY;
    let mut psup = front;
    for k in 0..sup.len().max(inf.len()) {
        if let Some(&p) = sup.get(k) {
            psup = p;
            abss = dist(front, p);
            if abss < rmprec {
                keep_sup.push(k);
            }
        }
        if let Some(&q) = inf.get(k) {
            if abss < rmprec && dist(psup, q) <= precn {
                keep_inf.push(k);
            }
        }
    }
    (keep_sup.len() >= 3 && keep_inf.len() >= 3).then_some((keep_sup, keep_inf))
}

/// K1, K2, K3, G at a front node from its upper- and lower-lip points
/// (each sorted by distance), its normal and direction.
pub fn k_at_node(
    sup: &[LipPoint],
    inf: &[LipPoint],
    normal: [f64; 3],
    dir: [f64; 3],
    mat: Elastic,
) -> Result<KValues, String> {
    if !mat.is_isotropic() {
        return Err("the stress intensity factors of an orthotropic material (ELAS_ORTH) are not computed: the displacement extrapolation here is the isotropic law's".into());
    }
    let n = sup.len();
    if n < 3 || inf.len() < n {
        return Err(format!(
            "{} upper-lip and {} lower-lip nodes: the method needs at least 3 on each, as many below as above",
            n,
            inf.len()
        ));
    }
    let v1 = normalize(normal);
    let v2 = normalize(dir);
    let v3 = normalize(cross(v1, v2));
    let pgl = [v1, v2, v3];
    let (e, nu) = (mat.e, mat.nu);
    let two_pi = (2.0 * std::f64::consts::PI).sqrt();
    let coefd = e * two_pi / (8.0 * (1.0 - nu * nu));
    let coefd3 = e * two_pi / (8.0 * (1.0 + nu));
    let coefg = (1.0 - nu * nu) / e;
    let coefg3 = (1.0 + nu) / e;
    let r: Vec<f64> = sup.iter().map(|p| p.r).collect();
    // saut[c][i]
    let mut saut = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for i in 0..n {
        for c in 0..3 {
            saut[c][i] = dot(pgl[c], sup[i].u) - dot(pgl[c], inf[i].u);
        }
    }
    let sign = |x: f64| {
        let s = if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        };
        let t = s + 0.001;
        if t > 0.0 {
            1.0
        } else {
            -1.0
        }
    };
    let isig = [
        sign(saut[0][n - 1]),
        sign(saut[1][n - 1]),
        sign(saut[2][n - 1]),
    ];
    let coef = [coefd, coefd, coefd3];
    let s2: Vec<Vec<f64>> = (0..3)
        .map(|c| saut[c].iter().map(|x| (x * coef[c]).powi(2)).collect())
        .collect();
    let maxmin = |v: &[f64]| {
        let mx = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mn = v.iter().copied().fold(f64::INFINITY, f64::min);
        (mx, mn)
    };
    // [K1max, K1min, K2max, K2min, K3max, K3min, Gmax, Gmin] per method
    let finish = |k: [Vec<f64>; 3]| {
        let g: Vec<f64> = (0..k[0].len())
            .map(|i| coefg * (k[0][i] + k[1][i]) + coefg3 * k[2][i])
            .collect();
        let mut out = [0.0; 8];
        for c in 0..3 {
            let (mx, mn) = maxmin(&k[c]);
            out[2 * c] = mx.sqrt() * isig[c];
            out[2 * c + 1] = mn.sqrt() * isig[c];
        }
        let (gx, gn) = maxmin(&g);
        out[6] = gx;
        out[7] = gn;
        out
    };
    // method 1
    let m1 = finish(std::array::from_fn(|c| {
        (1..n - 1)
            .map(|i| {
                let (x1, x2) = (r[i], r[i + 1]);
                let y1 = s2[c][i] / x1;
                let y2 = s2[c][i + 1] / x2;
                (y1 - x1 * (y2 - y1) / (x2 - x1)).abs()
            })
            .collect()
    }));
    // method 2
    let m2 = finish(std::array::from_fn(|c| {
        (1..n).map(|i| (s2[c][i] / r[i]).abs()).collect()
    }));
    // method 3
    let de = r[n - 1];
    let vk: [f64; 3] = std::array::from_fn(|c| {
        let mut k = 0.0;
        for i in 0..n - 1 {
            let (x1, x2) = (r[i], r[i + 1]);
            k += (s2[c][i + 1].sqrt() * x2.sqrt() + s2[c][i].sqrt() * x1.sqrt()) * (x2 - x1);
        }
        k / (de * de) * isig[c]
    });
    let g3 = coefg * (vk[0] * vk[0] + vk[1] * vk[1]) + coefg3 * vk[2] * vk[2];
    let m3 = [vk[0], vk[0], vk[1], vk[1], vk[2], vk[2], g3, g3];
    let methods = [m1, m2, m3];
    let mut kmax = [0.0; 3];
    let mut kmin = [0.0; 3];
    for j in 0..3 {
        kmax[j] = methods
            .iter()
            .map(|m| m[2 * j])
            .fold(f64::NEG_INFINITY, f64::max);
        kmin[j] = methods
            .iter()
            .map(|m| m[2 * j + 1])
            .fold(f64::INFINITY, f64::min);
    }
    let kmaxmax = kmax.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut err = [0.0; 3];
    if kmaxmax.abs() > 1e-15 {
        for j in 0..3 {
            err[j] = (kmax[j] - kmin[j]) / kmaxmax;
        }
    }
    Ok(KValues {
        k1: m1[0],
        k2: m1[2],
        k3: m1[4],
        g: m1[6],
        err,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plane-strain mode I near-tip jump: [u_n] = 8(1−ν²)/E K √(r/2π);
    /// every method gives K back exactly.
    #[test]
    fn pure_mode_one_jump() {
        let mat = Elastic::new(2e11, 0.3).unwrap();
        let k = 1.0e7;
        let jump =
            |r: f64| 8.0 * (1.0 - 0.09) / 2e11 * k * (r / (2.0 * std::f64::consts::PI)).sqrt();
        let rs = [0.0, 0.1, 0.2, 0.35, 0.5];
        let sup: Vec<LipPoint> = rs
            .iter()
            .map(|&r| LipPoint {
                r,
                u: [0.0, 0.0, jump(r) / 2.0],
            })
            .collect();
        let inf: Vec<LipPoint> = rs
            .iter()
            .map(|&r| LipPoint {
                r,
                u: [0.0, 0.0, -jump(r) / 2.0],
            })
            .collect();
        let kv = k_at_node(&sup, &inf, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], mat).unwrap();
        assert!((kv.k1 / k - 1.0).abs() < 1e-12, "{kv:?}");
        assert!(kv.k2.abs() < 1e-6 && kv.k3.abs() < 1e-6);
        let g = (1.0 - 0.09) / 2e11 * k * k;
        assert!((kv.g / g - 1.0).abs() < 1e-12);
    }
}
