//! code_aster's under-integrated 8-node hexahedron of `MODELISATION='3D_SI'`
//! (`MECA_HEXS8`: `te0407` → `nmas3d`, with `cast3d`, `calcdq`, `caatdb`):
//! one Gauss point at the centre for the behaviour, and an assumed-strain
//! hourglass stabilisation evaluated at the eight points of FPG8, carried
//! by 72 generalised hourglass stresses (`FSTAB`) updated incrementally.
//!
//! Reproduced as code_aster writes it, conventions included:
//!
//! - the projection is ASQBI (`proj = 2`, with ν) for `RELATION='ELAS'`
//!   and ADS (`proj = 1`) for every other law;
//! - B₀ (`def`) is the small-strain operator at the centre (`nmgeom`,
//!   shears / √2), the stiffness `KC = B₀ᵀ D B₀ · 8 det J(0)` plus, at each
//!   FPG8 point, `(Bₙᵀ D Bₙ + Bₙᵀ D B₀ + B₀ᵀ D Bₙ) det J` with D the
//!   behaviour's tangent in code_aster's √2 convention and Bₙ (`cast3d`)
//!   built with engineering shears — the stabilisation's shear terms are
//!   thus twice what a consistent energy would give, as in code_aster;
//! - the hourglass derivatives `dh` use the inverse Jacobian as `invjac`
//!   returns it, indexed as `nmas3d` indexes it;
//! - the internal forces are Σ over FPG8 of `(B₀ + Bₙ)ᵀ (σ_hg + σ) det J`,
//!   σ the centre's stress, σ_hg the hourglass stresses of the point from
//!   the generalised ones `Q₊ = Q₋ + ΔQ(D, γ·Δu)` (`calcdq`).
//!
//! Under `PETIT_REAC` every geometric quantity is taken on X + u.

use crate::error::FemError;

/// A 6×6 matrix (`D` in code_aster's √2 convention).
pub type Mat6 = [[f64; 6]; 6];

/// code_aster's four hourglass base vectors `h(8, 4)` (ηζ, ξζ, ξη, ξηζ at
/// the nodes).
const H: [[f64; 8]; 4] = [
    [1., 1., -1., -1., -1., -1., 1., 1.],
    [1., -1., -1., 1., -1., 1., 1., -1.],
    [1., -1., 1., -1., 1., -1., 1., -1.],
    [-1., 1., -1., 1., 1., -1., 1., -1.],
];

const RAC2: f64 = std::f64::consts::SQRT_2;

/// The stabilisation's projection (`proj` of `nmas3d`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// ADS, for every law but ELAS.
    Ads,
    /// ASQBI, for ELAS (uses ν).
    Asqbi,
}

/// The reference HEXA8 (code_aster's node order): ∂Nᵢ/∂ξ at a point.
fn dn_ref(xi: [f64; 3]) -> [[f64; 3]; 8] {
    let mut d = [[0.0; 3]; 8];
    for (a, n) in crate::refcells::HEXA8.iter().enumerate() {
        let f = [1. + n[0] * xi[0], 1. + n[1] * xi[1], 1. + n[2] * xi[2]];
        d[a] = [
            0.125 * n[0] * f[1] * f[2],
            0.125 * n[1] * f[0] * f[2],
            0.125 * n[2] * f[0] * f[1],
        ];
    }
    d
}

/// The FPG8 points in `elraga` order (ξ outermost, ζ innermost).
fn fpg8() -> [[f64; 3]; 8] {
    let a = [-0.577350269189626, 0.577350269189626];
    let mut p = [[0.0; 3]; 8];
    let mut k = 0;
    for &x in &a {
        for &y in &a {
            for &z in &a {
                p[k] = [x, y, z];
                k += 1;
            }
        }
    }
    p
}

/// `g(r, j) = Σ xⱼ ∂N/∂ξᵣ`, its inverse (`matinv`) and determinant.
fn jacobian(geom: &[[f64; 3]; 8], xi: [f64; 3]) -> Result<([[f64; 3]; 3], f64), FemError> {
    let dn = dn_ref(xi);
    let mut g = [[0.0; 3]; 3];
    for (a, d) in dn.iter().enumerate() {
        for r in 0..3 {
            for j in 0..3 {
                g[r][j] += geom[a][j] * d[r];
            }
        }
    }
    let m = [
        [
            g[1][1] * g[2][2] - g[1][2] * g[2][1],
            g[0][2] * g[2][1] - g[0][1] * g[2][2],
            g[0][1] * g[1][2] - g[0][2] * g[1][1],
        ],
        [
            g[2][0] * g[1][2] - g[1][0] * g[2][2],
            g[0][0] * g[2][2] - g[0][2] * g[2][0],
            g[1][0] * g[0][2] - g[1][2] * g[0][0],
        ],
        [
            g[1][0] * g[2][1] - g[2][0] * g[1][1],
            g[0][1] * g[2][0] - g[2][1] * g[0][0],
            g[0][0] * g[1][1] - g[0][1] * g[1][0],
        ],
    ];
    let det = g[0][0] * m[0][0] + g[0][1] * m[1][0] + g[0][2] * m[2][0];
    if det.abs() <= f64::MIN_POSITIVE || !det.is_finite() {
        return Err(FemError::Integration(format!(
            "the element is crushed (det J = {det:.3e})"
        )));
    }
    let mut inv = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            inv[i][j] = m[i][j] / det;
        }
    }
    Ok((inv, det))
}

/// Physical derivatives at a point (`dfdm3d`): rows ∂N/∂x, ∂N/∂y, ∂N/∂z
/// and |det J|.
fn derivatives(geom: &[[f64; 3]; 8], xi: [f64; 3]) -> Result<([[f64; 8]; 3], f64), FemError> {
    let (inv, det) = jacobian(geom, xi)?;
    let dn = dn_ref(xi);
    let mut d = [[0.0; 8]; 3];
    for a in 0..8 {
        for i in 0..3 {
            // ∂N/∂xᵢ = Σᵣ (J⁻¹)ᵢᵣ ∂N/∂ξᵣ
            d[i][a] = (0..3).map(|r| inv[i][r] * dn[a][r]).sum();
        }
    }
    Ok((d, det.abs()))
}

/// The geometry of one cell: the centre's operator, the hourglass
/// coefficients γ and, per FPG8 point, `dh` and |det J|.
pub struct Geometry {
    /// `def` of `nmas3d`: B₀ at the centre, rows XX YY ZZ XY XZ YZ, shears
    /// divided by √2, columns node-major (x, y, z per node).
    pub b0: [[f64; 24]; 6],
    /// 8 |det J(0)| (the centre's weight).
    pub w0: f64,
    /// γ (`gam(4, 8)`).
    gam: [[f64; 8]; 4],
    /// Per FPG8 point: `dh(4, 3)` and |det J|.
    points: [([[f64; 3]; 4], f64); 8],
}

impl Geometry {
    /// The cell on node coordinates `geom` (X, or X + u under PETIT_REAC).
    pub fn new(geom: &[[f64; 3]; 8]) -> Result<Geometry, FemError> {
        let pts = fpg8();
        // bi: the mean of the derivatives over FPG8, weighted by det J.
        let mut bi = [[0.0; 8]; 3];
        let mut den = 0.0;
        for p in &pts {
            let (d, jac) = derivatives(geom, *p)?;
            den += jac;
            for i in 0..3 {
                for a in 0..8 {
                    bi[i][a] += jac * d[i][a];
                }
            }
        }
        for row in bi.iter_mut() {
            for v in row.iter_mut() {
                *v /= den;
            }
        }
        let mut gam = [[0.0; 8]; 4];
        for i in 0..4 {
            let mut hx = [0.0; 3];
            for (k, h) in hx.iter_mut().enumerate() {
                *h = (0..8).map(|j| H[i][j] * geom[j][k]).sum();
            }
            for j in 0..8 {
                let s: f64 = (0..3).map(|k| hx[k] * bi[k][j]).sum();
                gam[i][j] = 0.125 * (H[i][j] - s);
            }
        }
        let (d0, jac0) = derivatives(geom, [0.0; 3])?;
        let mut b0 = [[0.0; 24]; 6];
        for a in 0..8 {
            let (dx, dy, dz) = (d0[0][a], d0[1][a], d0[2][a]);
            let c = 3 * a;
            b0[0][c] = dx;
            b0[1][c + 1] = dy;
            b0[2][c + 2] = dz;
            b0[3][c] = dy / RAC2;
            b0[3][c + 1] = dx / RAC2;
            b0[4][c] = dz / RAC2;
            b0[4][c + 2] = dx / RAC2;
            b0[5][c + 1] = dz / RAC2;
            b0[5][c + 2] = dy / RAC2;
        }
        let mut points = [([[0.0; 3]; 4], 0.0); 8];
        for (k, p) in pts.iter().enumerate() {
            let (inv, det) = jacobian(geom, *p)?;
            let [x, y, z] = *p;
            let mut dh = [[0.0; 3]; 4];
            for i in 0..3 {
                dh[0][i] = y * inv[2][i] + z * inv[1][i];
                dh[1][i] = x * inv[2][i] + z * inv[0][i];
                dh[2][i] = x * inv[1][i] + y * inv[0][i];
                dh[3][i] = x * y * inv[2][i] + y * z * inv[0][i] + x * z * inv[1][i];
            }
            points[k] = (dh, det.abs());
        }
        Ok(Geometry {
            b0,
            w0: 8.0 * jac0,
            gam,
            points,
        })
    }

    /// The centre's strain B₀ u, engineering shears (the behaviours'
    /// convention).
    pub fn strain(&self, u: &[f64]) -> [f64; 6] {
        let mut e = [0.0; 6];
        for (k, ek) in e.iter_mut().enumerate() {
            let s: f64 = (0..24).map(|p| self.b0[k][p] * u[p]).sum();
            *ek = if k >= 3 { s * RAC2 } else { s };
        }
        e
    }

    /// Bₙ of FPG8 point `k` (`cast3d`), 6 × 24.
    fn bn(&self, k: usize, proj: Projection, nu: f64) -> [[f64; 24]; 6] {
        let dh = &self.points[k].0;
        let g = &self.gam;
        let sum = |ics: &[usize], c: usize, a: usize| -> f64 {
            ics.iter().map(|&ic| dh[ic][c] * g[ic][a]).sum()
        };
        let mut bn = [[0.0; 24]; 6];
        let nub = nu / (1.0 - nu);
        for a in 0..8 {
            let xf = sum(&[0, 1, 2, 3], 0, a);
            let yf = sum(&[0, 1, 2, 3], 1, a);
            let zf = sum(&[0, 1, 2, 3], 2, a);
            let x12 = sum(&[0, 1], 0, a);
            let y12 = sum(&[0, 1], 1, a);
            let x13 = sum(&[0, 2], 0, a);
            let z13 = sum(&[0, 2], 2, a);
            let y23 = sum(&[1, 2], 1, a);
            let z23 = sum(&[1, 2], 2, a);
            let (cx, cy, cz) = (3 * a, 3 * a + 1, 3 * a + 2);
            match proj {
                Projection::Ads => {
                    let (unt, deut) = (1.0 / 3.0, 2.0 / 3.0);
                    bn[0][cx] = deut * xf;
                    bn[1][cy] = deut * yf;
                    bn[2][cz] = deut * zf;
                    bn[1][cx] = -unt * xf;
                    bn[2][cx] = -unt * xf;
                    bn[0][cy] = -unt * yf;
                    bn[2][cy] = -unt * yf;
                    bn[0][cz] = -unt * zf;
                    bn[1][cz] = -unt * zf;
                }
                Projection::Asqbi => {
                    let x14 = sum(&[0, 3], 0, a);
                    let y24 = sum(&[1, 3], 1, a);
                    let z34 = sum(&[2, 3], 2, a);
                    let x2 = dh[1][0] * g[1][a];
                    let x3 = dh[2][0] * g[2][a];
                    let y1 = dh[0][1] * g[0][a];
                    let y3 = dh[2][1] * g[2][a];
                    let z1 = dh[0][2] * g[0][a];
                    let z2 = dh[1][2] * g[1][a];
                    bn[0][cx] = xf;
                    bn[1][cx] = -nub * x3 - nu * x14;
                    bn[2][cx] = -nub * x2 - nu * x14;
                    bn[0][cy] = -nub * y3 - nu * y24;
                    bn[1][cy] = yf;
                    bn[2][cy] = -nub * y1 - nu * y24;
                    bn[0][cz] = -nub * z2 - nu * z34;
                    bn[1][cz] = -nub * z1 - nu * z34;
                    bn[2][cz] = zf;
                }
            }
            bn[3][cx] = y12;
            bn[3][cy] = x12;
            bn[4][cx] = z13;
            bn[4][cz] = x13;
            bn[5][cy] = z23;
            bn[5][cz] = y23;
        }
        bn
    }

    /// The tangent stiffness (24 × 24, row-major): KC + the stabilisation,
    /// for the tangent `d` (√2 convention).
    pub fn stiffness(&self, d: &Mat6, proj: Projection, nu: f64) -> Vec<f64> {
        let mut k = vec![0.0; 24 * 24];
        add_atdb(&mut k, &self.b0, d, &self.b0, self.w0);
        for p in 0..8 {
            let bn = self.bn(p, proj, nu);
            let jac = self.points[p].1;
            add_atdb(&mut k, &bn, d, &bn, jac);
            add_atdb(&mut k, &bn, d, &self.b0, jac);
            add_atdb(&mut k, &self.b0, d, &bn, jac);
        }
        // caatdb stores the lower triangle of a symmetric matrix.
        for i in 0..24 {
            for j in 0..i {
                k[j * 24 + i] = k[i * 24 + j];
            }
        }
        k
    }

    /// The generalised hourglass stresses at the end of the increment
    /// `du` (`calcdq`): `q_prev + ΔQ`.
    pub fn hourglass_stresses(
        &self,
        d: &Mat6,
        proj: Projection,
        nu: f64,
        du: &[f64],
        q_prev: &[f64; 72],
    ) -> [f64; 72] {
        let mut pq = [[0.0; 4]; 3];
        for (ia, g) in self.gam.iter().enumerate() {
            for (c, row) in pq.iter_mut().enumerate() {
                row[ia] = (0..8).map(|kl| g[kl] * du[3 * kl + c]).sum();
            }
        }
        let [px, py, pz] = pq;
        let nub = nu / (1.0 - nu);
        let mut q = *q_prev;
        for i in 0..6 {
            let ii = 12 * i;
            let di = &d[i];
            let dq: [f64; 12] = match proj {
                Projection::Ads => {
                    let dx = (2.0 * di[0] - di[1] - di[2]) / 3.0;
                    let dy = (-di[0] + 2.0 * di[1] - di[2]) / 3.0;
                    let dz = (-di[0] - di[1] + 2.0 * di[2]) / 3.0;
                    [
                        dx * px[0] + di[3] * py[0] + di[4] * pz[0],
                        di[3] * px[0] + dy * py[0],
                        di[4] * px[0] + dz * pz[0],
                        dx * px[1] + di[3] * py[1],
                        di[3] * px[1] + dy * py[1] + di[5] * pz[1],
                        di[5] * py[1] + dz * pz[1],
                        dx * px[2] + di[4] * pz[2],
                        dy * py[2] + di[5] * pz[2],
                        di[4] * px[2] + di[5] * py[2] + dz * pz[2],
                        dx * px[3],
                        dy * py[3],
                        dz * pz[3],
                    ]
                }
                Projection::Asqbi => {
                    let dx = di[0] - nu * di[1] - nu * di[2];
                    let dy = -nu * di[0] + di[1] - nu * di[2];
                    let dz = -nu * di[0] - nu * di[1] + di[2];
                    [
                        dx * px[0] + di[3] * py[0] + di[4] * pz[0],
                        di[3] * px[0] + (di[1] - di[2] * nub) * py[0],
                        di[4] * px[0] + (di[2] - di[1] * nub) * pz[0],
                        (di[0] - di[2] * nub) * px[1] + di[3] * py[1],
                        di[3] * px[1] + dy * py[1] + di[5] * pz[1],
                        di[5] * py[1] + (di[2] - di[0] * nub) * pz[1],
                        (di[0] - di[1] * nub) * px[2] + di[4] * pz[2],
                        (di[1] - di[0] * nub) * py[2] + di[5] * pz[2],
                        di[4] * px[2] + di[5] * py[2] + dz * pz[2],
                        dx * px[3],
                        dy * py[3],
                        dz * pz[3],
                    ]
                }
            };
            for (k, v) in dq.iter().enumerate() {
                q[ii + k] += v;
            }
        }
        q
    }

    /// The internal forces (24) for the centre's stress `sigma` (tensor
    /// shears) and the generalised hourglass stresses `q`.
    pub fn forces(&self, sigma: &[f64; 6], q: &[f64; 72], proj: Projection, nu: f64) -> Vec<f64> {
        let mut f = vec![0.0; 24];
        for p in 0..8 {
            let (dh, jac) = &self.points[p];
            let bn = self.bn(p, proj, nu);
            let mut sigas = [0.0; 6];
            for (i, s) in sigas.iter_mut().enumerate() {
                for (ia, dha) in dh.iter().enumerate() {
                    for j in 0..3 {
                        *s += q[12 * i + 3 * ia + j] * dha[j];
                    }
                }
            }
            for (c, fc) in f.iter_mut().enumerate() {
                let mut v = 0.0;
                for kl in 0..3 {
                    v += (self.b0[kl][c] + bn[kl][c]) * (sigas[kl] + sigma[kl]);
                    v += (RAC2 * self.b0[kl + 3][c] + bn[kl + 3][c])
                        * (sigas[kl + 3] + sigma[kl + 3]);
                }
                *fc += v * jac;
            }
        }
        f
    }
}

/// `caatdb`: k += w Aᵀ D B (full; the caller keeps the lower triangle).
fn add_atdb(k: &mut [f64], a: &[[f64; 24]; 6], d: &Mat6, b: &[[f64; 24]; 6], w: f64) {
    for p in 0..24 {
        let mut ad = [0.0; 6];
        for (kl, v) in ad.iter_mut().enumerate() {
            *v = (0..6).map(|m| a[m][p] * d[m][kl]).sum();
        }
        for q in 0..=p {
            let v: f64 = (0..6).map(|m| ad[m] * b[m][q]).sum();
            k[p * 24 + q] += v * w;
        }
    }
}

/// An engineering-shear tangent (σ = C γ) in code_aster's √2 convention.
pub fn to_sqrt2(c: &Mat6) -> Mat6 {
    let t = [1.0, 1.0, 1.0, RAC2, RAC2, RAC2];
    let mut d = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            d[i][j] = t[i] * t[j] * c[i][j];
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brick(lx: f64, ly: f64, lz: f64) -> [[f64; 3]; 8] {
        [
            [0., 0., 0.],
            [lx, 0., 0.],
            [lx, ly, 0.],
            [0., ly, 0.],
            [0., 0., lz],
            [lx, 0., lz],
            [lx, ly, lz],
            [0., ly, lz],
        ]
    }

    fn hooke(e: f64, nu: f64) -> Mat6 {
        let l = e * nu / ((1. + nu) * (1. - 2. * nu));
        let m = e / (2. * (1. + nu));
        let mut c = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = l;
            }
            c[i][i] = l + 2. * m;
            c[i + 3][i + 3] = m;
        }
        c
    }

    /// A linear displacement field has no hourglass part: γ·u = 0, the
    /// forces are V B₀ᵀσ and equal K u.
    #[test]
    fn linear_fields_have_no_hourglass() {
        let geom = brick(2.0, 1.0, 3.0);
        let g = Geometry::new(&geom).unwrap();
        let grad = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
        let mut u = [0.0; 24];
        for a in 0..8 {
            for i in 0..3 {
                u[3 * a + i] = (0..3).map(|j| grad[i][j] * geom[a][j]).sum();
            }
        }
        let c = hooke(2e5, 0.3);
        let d = to_sqrt2(&c);
        for proj in [Projection::Ads, Projection::Asqbi] {
            let q = g.hourglass_stresses(&d, proj, 0.3, &u, &[0.0; 72]);
            assert!(q.iter().all(|v| v.abs() < 1e-9), "{q:?}");
            let eps = g.strain(&u);
            let mut sigma = [0.0; 6];
            for i in 0..6 {
                sigma[i] = (0..6).map(|j| c[i][j] * eps[j]).sum();
            }
            let f = g.forces(&sigma, &q, proj, 0.3);
            let k = g.stiffness(&d, proj, 0.3);
            for p in 0..24 {
                let ku: f64 = (0..24).map(|q| k[p * 24 + q] * u[q]).sum();
                assert!((ku - f[p]).abs() < 1e-9 * 1e3, "{p}: {ku} {}", f[p]);
            }
            // Resultant on the face x = lx: σxx · area.
            let fx: f64 = [1, 2, 5, 6].iter().map(|&a| f[3 * a]).sum();
            assert!((fx - sigma[0] * 3.0).abs() < 1e-9 * sigma[0].abs().max(1.0));
        }
    }

    /// The stabilisation gives the hourglass modes stiffness (one point
    /// alone would leave them free): K has exactly six zero eigenvalues.
    #[test]
    fn only_rigid_modes_are_free() {
        let g = Geometry::new(&brick(1.0, 1.0, 1.0)).unwrap();
        let d = to_sqrt2(&hooke(1.0, 0.3));
        for proj in [Projection::Ads, Projection::Asqbi] {
            let k = g.stiffness(&d, proj, 0.3);
            let m = nalgebra::DMatrix::from_row_slice(24, 24, &k);
            let ev = m.symmetric_eigenvalues();
            let zero = ev.iter().filter(|v| v.abs() < 1e-10).count();
            assert_eq!(zero, 6, "{ev:?}");
            assert!(ev.iter().all(|&v| v > -1e-10));
        }
    }
}
