//! The logarithmic (Hencky) strain of `GDEF_LOG`: code_aster's formulation
//! after Miehe, Apel & Lambrecht (CMAME 2002), routines `deflog`, `deflg2`
//! and `deflg3`.
//!
//! With C = FᵀF = Σ λᵢ Nᵢ⊗Nᵢ, the strain is ε = ½ ln C = Σ f(λᵢ) Nᵢ⊗Nᵢ,
//! f(λ) = ½ ln λ. The behaviour, written in small strains, gives the dual
//! stress T and its tangent ∂T/∂ε; the second Piola–Kirchhoff stress is
//! S = Pᵀ T with P = ∂ε/∂E (E the Green–Lagrange strain), and the tangent
//! ∂S/∂E = Pᵀ (∂T/∂ε) P + T : ∂²ε/∂E².
//!
//! All vectors here are in code_aster's Mandel notation (xx, yy, zz, √2 xy,
//! √2 xz, √2 yz), which makes P and the tangents plain 6×6 matrices.
//!
//! Divided differences of f. code_aster switches to the limit formulas only
//! when two eigenvalues are exactly equal; the divided differences here are
//! written so that nearly equal eigenvalues lose no digits
//! (ln(1+x)/x, its series, and a Taylor expansion for the second divided
//! difference of three close values), which equals code_aster's formulas
//! wherever these are accurate.

use nalgebra::{Matrix3, SymmetricEigen};

/// A symmetric 6×6 matrix in Mandel notation.
pub type Mat6 = [[f64; 6]; 6];

/// The Mandel index of the pair (i, j).
pub(crate) const MANDEL: [[usize; 3]; 3] = [[0, 3, 4], [3, 1, 5], [4, 5, 2]];
/// The pair of each Mandel index.
pub(crate) const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// √2 on the shear rows, 1 on the diagonal ones.
pub(crate) fn mandel_factor(k: usize) -> f64 {
    if k < 3 {
        1.0
    } else {
        std::f64::consts::SQRT_2
    }
}

/// A symmetric tensor as a Mandel vector.
pub(crate) fn to_mandel(t: &Matrix3<f64>) -> [f64; 6] {
    let mut v = [0.0; 6];
    for (k, &(i, j)) in PAIRS.iter().enumerate() {
        v[k] = t[(i, j)] * mandel_factor(k);
    }
    v
}

/// A Mandel vector as a symmetric tensor.
pub(crate) fn from_mandel(v: &[f64; 6]) -> Matrix3<f64> {
    let mut t = Matrix3::zeros();
    for (k, &(i, j)) in PAIRS.iter().enumerate() {
        let x = v[k] / mandel_factor(k);
        t[(i, j)] = x;
        t[(j, i)] = x;
    }
    t
}

/// f(λ) = ½ ln λ and its first divided difference f[a, b].
fn half_ln(l: f64) -> f64 {
    0.5 * l.ln()
}

/// ln(1+x)/x, accurate for small x.
fn l1(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        x.ln_1p() / x
    }
}

/// f[a, b] = (f(a) − f(b)) / (a − b), limit f'(b) = 1/(2b).
fn dd1(a: f64, b: f64) -> f64 {
    l1((a - b) / b) / (2.0 * b)
}

/// f[a, b, b] = (f[a, b] − f'(b)) / (a − b), limit f''(b)/2 = −1/(4b²).
fn dd2_double(a: f64, b: f64) -> f64 {
    let x = (a - b) / b;
    // (L1(x) − 1)/x = Σ_{k≥1} (−1)ᵏ x^{k−1}/(k+1).
    let g = if x.abs() < 1e-2 {
        let mut s = 0.0;
        let mut p = 1.0;
        for k in 1..=12 {
            let sign = if k % 2 == 1 { -1.0 } else { 1.0 };
            s += sign * p / (k as f64 + 1.0);
            p *= x;
        }
        s
    } else {
        (l1(x) - 1.0) / x
    };
    g / (2.0 * b * b)
}

/// f[a, b, c], the second divided difference (symmetric in its arguments).
fn dd2(a: f64, b: f64, c: f64) -> f64 {
    let mut v = [a, b, c];
    v.sort_by(f64::total_cmp);
    let [lo, mid, hi] = v;
    let spread = (hi - lo) / mid;
    if spread.abs() < 1e-2 {
        // Taylor expansion about mid: Σ_{n≥2} f⁽ⁿ⁾(m)/n! · h_{n−2}(u, 0, v)
        // with f⁽ⁿ⁾(m)/n! = ½(−1)^{n−1}/(n mⁿ); h the complete homogeneous
        // symmetric polynomials of the relative offsets.
        let u = (lo - mid) / mid;
        let w = (hi - mid) / mid;
        let mut s = 0.0;
        for n in 2..=12usize {
            let m = n - 2;
            let mut h = 0.0;
            for i in 0..=m {
                h += u.powi(i as i32) * w.powi((m - i) as i32);
            }
            let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
            s += 0.5 * sign / n as f64 * h;
        }
        return s / (mid * mid);
    }
    (dd1(hi, mid) - dd1(mid, lo)) / (hi - lo)
}

/// The logarithmic strain of a deformation gradient with what its stress
/// transformation needs.
#[derive(Clone, Debug)]
pub struct LogStrain {
    /// ε = ½ ln FᵀF, Mandel.
    pub eps: [f64; 6],
    /// Eigenvectors of C (columns).
    gn: Matrix3<f64>,
    /// Eigenvalues of C.
    lamb: [f64; 3],
}

/// Why a logarithmic strain cannot be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crushed {
    /// The smallest eigenvalue of FᵀF.
    pub smallest: f64,
}

impl LogStrain {
    /// ε = ½ ln(FᵀF). In 2D (`dim` = 2) the in-plane block is diagonalised
    /// and z is an eigendirection with λ₃ = C₃₃, as code_aster's `deflog`.
    pub fn new(f: &Matrix3<f64>, dim: usize) -> Result<LogStrain, Crushed> {
        let c = f.transpose() * f;
        let (gn, lamb) = if dim == 3 {
            let e = SymmetricEigen::new(c);
            (
                e.eigenvectors,
                [e.eigenvalues[0], e.eigenvalues[1], e.eigenvalues[2]],
            )
        } else {
            let (a, b, d) = (c[(0, 0)], c[(1, 1)], c[(0, 1)]);
            let m = 0.5 * (a + b);
            let r = (0.25 * (a - b) * (a - b) + d * d).sqrt();
            let (l1, l2) = (m + r, m - r);
            // Eigenvector of l1: the better conditioned of (a − l2, d) and
            // (d, b − l2).
            let v1 = [a - l2, d];
            let v2 = [d, b - l2];
            let n1 = v1[0] * v1[0] + v1[1] * v1[1];
            let n2 = v2[0] * v2[0] + v2[1] * v2[1];
            let (x, y, n) = if n1 >= n2 {
                (v1[0], v1[1], n1)
            } else {
                (v2[0], v2[1], n2)
            };
            let mut g = Matrix3::identity();
            if n > 0.0 {
                let n = n.sqrt();
                g[(0, 0)] = x / n;
                g[(1, 0)] = y / n;
                g[(0, 1)] = -y / n;
                g[(1, 1)] = x / n;
            }
            (g, [l1, l2, c[(2, 2)]])
        };
        let smallest = lamb.iter().copied().fold(f64::INFINITY, f64::min);
        if smallest.is_nan() || smallest <= f64::EPSILON {
            return Err(Crushed { smallest });
        }
        let mut e = Matrix3::zeros();
        for k in 0..3 {
            let g = gn.column(k);
            e += half_ln(lamb[k]) * g * g.transpose();
        }
        Ok(LogStrain {
            eps: to_mandel(&e),
            gn,
            lamb,
        })
    }

    /// θᵢⱼ: f'(λᵢ) on the diagonal, f[λᵢ, λⱼ] off it; ξᵢⱼ = f[λᵢ, λⱼ, λⱼ];
    /// η = f[λ₁, λ₂, λ₃].
    fn coefficients(&self) -> ([[f64; 3]; 3], [[f64; 3]; 3], f64) {
        let l = self.lamb;
        let mut theta = [[0.0; 3]; 3];
        let mut xi = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                theta[i][j] = dd1(l[i], l[j]);
                if i != j {
                    xi[i][j] = dd2_double(l[i], l[j]);
                }
            }
        }
        (theta, xi, dd2(l[0], l[1], l[2]))
    }

    /// Mᵢⱼ = gᵢ⊗gⱼ + gⱼ⊗gᵢ, component (a, b) of each Mandel pair
    /// [`PAIRS`]`[r]`: `table[r][i][j]`, tabulated once for the sums of
    /// [`LogStrain::p`] and [`LogStrain::t_l`] (the same products as
    /// evaluating them in the loops).
    fn m_table(&self) -> [[[f64; 3]; 3]; 6] {
        let g = &self.gn;
        let mut out = [[[0.0; 3]; 3]; 6];
        for (r, &(a, b)) in PAIRS.iter().enumerate() {
            for i in 0..3 {
                for j in 0..3 {
                    out[r][i][j] = g[(a, i)] * g[(b, j)] + g[(a, j)] * g[(b, i)];
                }
            }
        }
        out
    }

    /// P = ∂ε/∂E in Mandel notation (rows: ε, columns: E), code_aster's
    /// `pes`: S = Pᵀ T.
    pub fn p(&self) -> Mat6 {
        let (theta, _, _) = self.coefficients();
        let g = &self.gn;
        let mt = self.m_table();
        let mut p = [[0.0; 6]; 6];
        for (r, &(k, l)) in PAIRS.iter().enumerate() {
            for (c, m) in mt.iter().enumerate() {
                let mut v = 0.0;
                for i in 0..3 {
                    // di/2 · gₖⁱ gₗⁱ Mᵢᵢ with di = 1/λᵢ = 2 f'(λᵢ).
                    v += theta[i][i] * g[(k, i)] * g[(l, i)] * m[i][i];
                    for j in 0..3 {
                        if i != j {
                            v += theta[i][j] * g[(k, i)] * g[(l, j)] * m[i][j];
                        }
                    }
                }
                p[r][c] = v * mandel_factor(r) * mandel_factor(c);
            }
        }
        p
    }

    /// T : ∂²ε/∂E² for the stress T (Mandel), code_aster's `deflg3`
    /// (symmetrised into Mandel notation by `symt46`).
    pub fn t_l(&self, t: &[f64; 6]) -> Mat6 {
        let (_, xi, eta) = self.coefficients();
        let t33 = from_mandel(t);
        let g = &self.gn;
        // ζᵢⱼ = gᵢ · T gⱼ.
        let zeta = g.transpose() * t33 * g;
        // feta(i)/4 = f''(λᵢ) = −1/(2λᵢ²).
        let fpp: [f64; 3] = self.lamb.map(|l| -0.5 / (l * l));
        let zeta: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| zeta[(i, j)]));
        let mt = self.m_table();
        let mut out = [[0.0; 6]; 6];
        for (r, mr) in mt.iter().enumerate() {
            for (c, mc) in mt.iter().enumerate() {
                let mut v = 0.0;
                for i in 0..3 {
                    v += fpp[i] * zeta[i][i] * mr[i][i] * mc[i][i];
                    for j in 0..3 {
                        if j == i {
                            continue;
                        }
                        for k in 0..3 {
                            if k != i && k != j {
                                v += 2.0 * eta * zeta[i][j] * mr[i][k] * mc[j][k];
                            }
                        }
                        v += 2.0 * xi[i][j] * zeta[i][j] * mr[i][j] * mc[j][j];
                        v += 2.0 * xi[i][j] * zeta[i][j] * mr[j][j] * mc[i][j];
                        v += 2.0 * xi[i][j] * zeta[j][j] * mr[i][j] * mc[i][j];
                    }
                }
                out[r][c] = v * mandel_factor(r) * mandel_factor(c);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_f() -> Matrix3<f64> {
        Matrix3::new(1.3, 0.2, -0.1, 0.05, 0.9, 0.15, 0.1, -0.2, 1.1)
    }

    fn gl(f: &Matrix3<f64>) -> [f64; 6] {
        to_mandel(&(0.5 * (f.transpose() * f - Matrix3::identity())))
    }

    /// The log strain as a function of the Green–Lagrange strain E (Mandel):
    /// C = I + 2E, ε = ½ ln C.
    fn eps_of_e(e: &[f64; 6]) -> [f64; 6] {
        let c = Matrix3::identity() + 2.0 * from_mandel(e);
        // F = √C has FᵀF = C.
        let s = SymmetricEigen::new(c);
        let f = s.eigenvectors
            * Matrix3::from_diagonal(&s.eigenvalues.map(f64::sqrt))
            * s.eigenvectors.transpose();
        LogStrain::new(&f, 3).unwrap().eps
    }

    #[test]
    fn log_strain_of_a_stretch_is_ln_of_the_stretch() {
        let f = Matrix3::from_diagonal(&nalgebra::Vector3::new(2.0, 0.5, 1.0));
        let l = LogStrain::new(&f, 3).unwrap();
        assert!((l.eps[0] - 2f64.ln()).abs() < 1e-15);
        assert!((l.eps[1] - 0.5f64.ln()).abs() < 1e-15);
        assert!(l.eps[2].abs() < 1e-15 && l.eps[3].abs() < 1e-15);
        // A rotation leaves the strain at zero.
        let (c, s) = (0.6f64, 0.8f64);
        let r = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let l = LogStrain::new(&(r * f), 2).unwrap();
        assert!((l.eps[0] - 2f64.ln()).abs() < 1e-14, "{:?}", l.eps);
    }

    /// P = ∂ε/∂E and T:∂²ε/∂E² against centred finite differences, for
    /// distinct, double and triple eigenvalues.
    #[test]
    fn p_and_its_derivative_match_finite_differences() {
        let cases = [
            sample_f(),
            Matrix3::from_diagonal(&nalgebra::Vector3::new(1.2, 1.2, 0.8)),
            Matrix3::identity() * 1.1,
        ];
        let t = [3.0, -1.0, 2.0, 0.7, -0.4, 0.9];
        for f in cases {
            let e0 = gl(&f);
            let l = LogStrain::new(&f, 3).unwrap();
            let p = l.p();
            let tl = l.t_l(&t);
            let h = 1e-6;
            for c in 0..6 {
                let mut ep = e0;
                let mut em = e0;
                ep[c] += h;
                em[c] -= h;
                let (a, b) = (eps_of_e(&ep), eps_of_e(&em));
                for r in 0..6 {
                    let fd = (a[r] - b[r]) / (2.0 * h);
                    assert!(
                        (fd - p[r][c]).abs() < 1e-8,
                        "P[{r}][{c}] = {} vs {fd}",
                        p[r][c]
                    );
                }
                // d(Pᵀ T)/dE at fixed T.
                let lp = |e: &[f64; 6]| {
                    let c3 = Matrix3::identity() + 2.0 * from_mandel(e);
                    let s = SymmetricEigen::new(c3);
                    let f = s.eigenvectors
                        * Matrix3::from_diagonal(&s.eigenvalues.map(f64::sqrt))
                        * s.eigenvectors.transpose();
                    let p = LogStrain::new(&f, 3).unwrap().p();
                    let mut out = [0.0; 6];
                    for j in 0..6 {
                        out[j] = (0..6).map(|i| t[i] * p[i][j]).sum();
                    }
                    out
                };
                let (a, b) = (lp(&ep), lp(&em));
                for r in 0..6 {
                    let fd = (a[r] - b[r]) / (2.0 * h);
                    assert!(
                        (fd - tl[r][c]).abs() < 1e-6,
                        "TL[{r}][{c}] = {} vs {fd} (F = {f})",
                        tl[r][c]
                    );
                }
            }
        }
    }

    #[test]
    fn divided_differences_are_smooth_through_equal_eigenvalues() {
        for &d in &[1e-3, 1e-7, 1e-12, 0.0] {
            let (a, b) = (1.3 + d, 1.3);
            assert!((dd1(a, b) - 1.0 / (2.0 * 1.3)).abs() < 0.2 * d + 1e-15);
            let lim = -1.0 / (4.0 * 1.3 * 1.3);
            assert!((dd2_double(a, b) - lim).abs() < d + 1e-14);
            assert!((dd2(a, b, 1.3 - d) - lim).abs() < d + 1e-14);
        }
        // Far apart: the plain formula.
        let (a, b, c) = (2.0f64, 1.0f64, 0.5f64);
        let exact =
            ((half_ln(a) - half_ln(b)) / (a - b) - (half_ln(b) - half_ln(c)) / (b - c)) / (a - c);
        assert!((dd2(a, b, c) - exact).abs() < 1e-15);
    }
}
