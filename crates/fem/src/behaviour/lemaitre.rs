//! Lemaitre's viscoplastic law without threshold (`RELATION='LEMAITRE'`,
//! code_aster R5.03.08), small strains, integrated as code_aster's
//! `nmvple` does: a θ-scheme (`PARM_THETA` 0.5 or 1) on the deviatoric
//! stress, the scalar equation of the equivalent stress solved by
//! code_aster's `zerof2` (secant/bisection "DEKKER2", tolerance
//! `RESI_INTE_RELA` on the function value, `ITER_INTE_MAXI` iterations),
//! and its consistent tangent.
//!
//! The flow: ṗ = ((σ_eq / K) / p^(1/M))^N, ε̇ᵖ = 3/2 ṗ s / σ_eq. With
//! `UN_SUR_M = 0` it is Norton's law. VARI: V1 = p (EPSPEQ), V2 = 0
//! (code_aster's `VIDE`).
//!
//! Vectors are in Voigt order (xx, yy, zz, xy, xz, yz), strains with
//! engineering shears, stresses tensor components (as [`super::vmis`]).

use super::vmis::{Mat6, PointState};
use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};

/// `DEFI_MATERIAU/LEMAITRE` with the integration settings of its
/// `COMPORTEMENT` occurrence.
#[derive(Clone, Debug, PartialEq)]
pub struct Lemaitre {
    /// `N`.
    pub n: f64,
    /// `UN_SUR_K` (1/K).
    pub un_sur_k: f64,
    /// `UN_SUR_M` (1/M).
    pub un_sur_m: f64,
    /// `PARM_THETA`: 0.5 (semi-implicit) or 1 (implicit).
    pub theta: f64,
    /// `RESI_INTE_RELA`: the tolerance on the scalar equation.
    pub resi_inte: f64,
    /// `ITER_INTE_MAXI`.
    pub iter_inte_maxi: usize,
}

impl Lemaitre {
    /// Checks code_aster's conditions: θ within 0.01 of 0.5 or 1, N > 0,
    /// UN_SUR_K ≥ 0, UN_SUR_M ≥ 0.
    pub fn new(
        n: f64,
        un_sur_k: f64,
        un_sur_m: f64,
        theta: f64,
        resi_inte: f64,
        iter_inte_maxi: usize,
    ) -> Result<Lemaitre, FemError> {
        if (theta - 0.5).abs() > 0.01 && (theta - 1.0).abs() > 0.01 {
            return Err(FemError::Model(format!(
                "LEMAITRE: PARM_THETA must be 0.5 or 1 (code_aster's semi-implicit or implicit scheme), got {theta}"
            )));
        }
        let valid = n.is_finite() && n > 0.0 && un_sur_k >= 0.0 && un_sur_m >= 0.0;
        if !valid {
            return Err(FemError::Model(format!(
                "LEMAITRE: N must be positive and UN_SUR_K, UN_SUR_M non-negative, got N = {n}, UN_SUR_K = {un_sur_k}, UN_SUR_M = {un_sur_m}"
            )));
        }
        Ok(Lemaitre {
            n,
            un_sur_k,
            un_sur_m,
            theta,
            resi_inte,
            iter_inte_maxi: iter_inte_maxi.max(1),
        })
    }

    /// code_aster's `vpalem`: 3μ Δt g(x) + x − σ_el,eq with
    /// g = θ ((x/K) / (p + (σ_el,eq − x)/3μ)^(1/M))^N.
    fn residual(&self, x: f64, s: &Scalar) -> f64 {
        let g = if self.un_sur_k == 0.0 || x == 0.0 {
            0.0
        } else if self.un_sur_m == 0.0 {
            (self.n * (x * self.un_sur_k).ln()).exp() * self.theta
        } else {
            let p = s.dpc + (s.sieleq - x) / (1.5 * s.deuxmu);
            (self.n * ((x * self.un_sur_k).ln() - self.un_sur_m * p.ln())).exp() * self.theta
        };
        1.5 * s.deuxmu * s.dt * g + x - s.sieleq
    }

    /// code_aster's `ggplem`: g, ∂g/∂σ and ∂g/∂p at (s, dpc).
    fn flow(&self, s: f64, dpc: f64, deuxmu: f64) -> (f64, f64, f64) {
        if s == 0.0 || dpc == 0.0 || self.un_sur_k == 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let (g, dgdst, dgdev) = if self.un_sur_m == 0.0 {
            let g = (self.n * (s * self.un_sur_k).ln()).exp();
            (g, self.n * g / s, 0.0)
        } else {
            let g = (self.n * ((s * self.un_sur_k).ln() - self.un_sur_m * dpc.ln())).exp();
            (
                g,
                self.n * (1.0 / s + self.un_sur_m / (1.5 * deuxmu * dpc)) * g,
                -self.n * g * self.un_sur_m / dpc,
            )
        };
        (g * self.theta, dgdst * self.theta, dgdev * self.theta)
    }
}

/// The data of the scalar equation (code_aster's common `nmpavp`).
struct Scalar {
    dpc: f64,
    sieleq: f64,
    deuxmu: f64,
    dt: f64,
}

/// code_aster's `zerof2` ("DEKKER2") on [x0, xap], f(x0) < 0: the first
/// point is kept when |f(xap)| < tol; else secant steps until the root is
/// bracketed, then secant steps with a bisection every third one.
fn zerof2(
    f: &dyn Fn(f64) -> f64,
    x0: f64,
    xap: f64,
    tol: f64,
    itmax: usize,
) -> Result<f64, String> {
    let mut n = 1usize;
    let (mut x, mut fx) = (x0, f(x0));
    let (mut y, mut fy) = (xap, f(xap));
    if fy.abs() < tol {
        return Ok(y);
    }
    if (x - y).abs() <= 1e-15 {
        return Err("the interval of the scalar equation is empty".into());
    }
    loop {
        if fy > 0.0 {
            let (mut a, mut b, mut fa, mut fb) = (x, y, fx, fy);
            loop {
                let z = if n.is_multiple_of(3) {
                    (a + b) * 0.5
                } else {
                    (a * fb - b * fa) / (fb - fa)
                };
                n += 1;
                let fz = f(z);
                if fz.abs() < tol || (b - a).abs() <= tol * b {
                    return Ok(z);
                }
                if n > itmax {
                    return Err(format!("no root after ITER_INTE_MAXI = {itmax} iterations"));
                }
                if fz < 0.0 {
                    a = z;
                    fa = fz;
                } else {
                    b = z;
                    fb = fz;
                }
            }
        }
        if fy <= fx {
            return Err("the scalar equation does not rise on its interval".into());
        }
        let z = (x * fy - y * fx) / (fy - fx);
        if (z - y).abs() <= 1e-15 {
            return Err("the secant steps stall".into());
        }
        n += 1;
        x = y;
        fx = fy;
        y = z;
        fy = f(z);
        if fy.abs() < tol {
            return Ok(z);
        }
        if n > itmax {
            return Err(format!("no root after ITER_INTE_MAXI = {itmax} iterations"));
        }
    }
}

/// Integrates the law at a point over a step of length `dt` to the total
/// strain `eps` (the hypothesis' components: 4 in 2D with zz, 6 in 3D) from
/// the converged state `prev`. `prediction`: code_aster's RIGI_MECA_TANG,
/// the tangent at a zero strain increment (the state is `prev`). Plane
/// stress is refused, as by code_aster.
pub fn integrate(
    law: &Lemaitre,
    el: &Elastic,
    hyp: Hypothesis,
    eps: &[f64],
    prev: &PointState,
    dt: f64,
    prediction: bool,
) -> Result<(PointState, Mat6), FemError> {
    if hyp == Hypothesis::PlaneStress {
        return Err(FemError::Model(
            "LEMAITRE is not available in plane stress (C_PLAN), as in code_aster".into(),
        ));
    }
    let n = hyp.ncomp();
    let theta = law.theta;
    let deuxmu = el.e / (1.0 + el.nu);
    let troisk = el.e / (1.0 - 2.0 * el.nu);
    // Tensor components (shears halved).
    let tensor = |v: &[f64; 6]| {
        let mut t = *v;
        for s in t.iter_mut().skip(3) {
            *s *= 0.5;
        }
        t
    };
    let mut e6 = [0.0; 6];
    if !prediction {
        e6[..n].copy_from_slice(&eps[..n]);
    }
    let sigm = prev.stress;
    let sigmo = (sigm[0] + sigm[1] + sigm[2]) / 3.0;
    let dev = |v: &[f64; 6], m: f64| {
        let mut d = *v;
        for x in d.iter_mut().take(3) {
            *x -= m;
        }
        d
    };
    let sdev = dev(&sigm, sigmo);
    // The strain increment: ε − εᵖ − D⁻¹σ⁻ (the elastic strain of the
    // converged state is D⁻¹σ⁻); none in the prediction.
    let deps = if prediction {
        [0.0; 6]
    } else {
        let ee = tensor(&e6);
        let ep = tensor(&prev.plastic_strain);
        let mut d = [0.0; 6];
        for k in 0..6 {
            let kron = if k < 3 { 1.0 } else { 0.0 };
            d[k] = ee[k] - ep[k] - (sdev[k] / deuxmu + kron * sigmo / troisk);
        }
        d
    };
    let epsmo = theta * (deps[0] + deps[1] + deps[2]) / 3.0;
    let mut sigel = [0.0; 6];
    let mut sq = 0.0;
    for k in 0..6 {
        let kron = if k < 3 { 1.0 } else { 0.0 };
        sigel[k] = sdev[k] + deuxmu * (theta * deps[k] - epsmo * kron);
        sq += if k < 3 { 1.0 } else { 2.0 } * sigel[k] * sigel[k];
    }
    let sieleq = (1.5 * sq).sqrt();
    let scalar = Scalar {
        dpc: prev.p,
        sieleq,
        deuxmu,
        dt,
    };
    let x = if sieleq <= law.resi_inte {
        0.0
    } else {
        let xap = sieleq - sieleq * 1e-12;
        zerof2(
            &|x| law.residual(x, &scalar),
            0.0,
            xap,
            law.resi_inte,
            law.iter_inte_maxi,
        )
        .map_err(|m| {
            FemError::Integration(format!(
                "LEMAITRE: the local integration failed ({m}; equivalent stress {sieleq:e})"
            ))
        })?
    };
    let (fg, fdgdst, fdgdev) = if x != 0.0 {
        law.flow(x, prev.p + (sieleq - x) / (1.5 * deuxmu), deuxmu)
    } else {
        (0.0, 0.0, 0.0)
    };
    let coef1 = if x != 0.0 {
        1.0 / (1.0 + 1.5 * deuxmu * dt * fg / x)
    } else {
        1.0
    };
    let mut state = *prev;
    if !prediction {
        let mut dp2 = 0.0;
        for k in 0..6 {
            let kron = if k < 3 { 1.0 } else { 0.0 };
            let sdv = sigel[k] * coef1;
            let s_theta = sdv + (sigmo + troisk * epsmo) * kron;
            state.stress[k] = (s_theta - sigm[k]) / theta + sigm[k];
            let dev_p = (sigel[k] - sdv) / (deuxmu * theta);
            dp2 += if k < 3 { 1.0 } else { 2.0 } * dev_p * dev_p;
            state.plastic_strain[k] += if k < 3 { dev_p } else { 2.0 * dev_p };
        }
        if hyp.dim() == 2 {
            for k in 4..6 {
                state.stress[k] = 0.0;
                state.plastic_strain[k] = 0.0;
            }
        }
        state.p = prev.p + (2.0 * dp2 / 3.0).sqrt();
        state.plastic = false;
    }
    let coef2 = if x != 0.0 {
        let c = sieleq * (1.0 - dt * fdgdev) / (1.0 + 1.5 * deuxmu * dt * fdgdst) - x;
        c * 1.5 / sieleq.powi(3)
    } else {
        0.0
    };
    // code_aster's dsidep (√2 shears) read with tensor stresses and
    // engineering shear strains: the shear rows and columns halve.
    let mut c = [[0.0; 6]; 6];
    for (k, row) in c.iter_mut().enumerate() {
        for (l, v) in row.iter_mut().enumerate() {
            let kk = if k < 3 { 1.0 } else { 0.0 };
            let kl = if l < 3 { 1.0 } else { 0.0 };
            let delta = if k == l {
                if k < 3 {
                    1.0
                } else {
                    0.5
                }
            } else {
                0.0
            };
            *v = deuxmu * (coef1 * (delta - kk * kl / 3.0) + coef2 * sigel[k] * sigel[l])
                + troisk * kk * kl / 3.0;
        }
    }
    if hyp.dim() == 2 {
        for (k, row) in c.iter_mut().enumerate() {
            for (l, v) in row.iter_mut().enumerate() {
                if k >= 4 || l >= 4 {
                    *v = 0.0;
                }
            }
        }
    }
    Ok((state, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(n: f64, theta: f64) -> Lemaitre {
        Lemaitre::new(n, 1.0 / 50.0, 0.0, theta, 1e-12, 100).unwrap()
    }

    /// Creep under a constant uniaxial stress: imposing the strain history
    /// of Norton's closed form (ε = σ/E + (σ/K)^N t) keeps σ constant and
    /// p = (σ/K)^N t with the implicit scheme for N = 1 (linear, exact in
    /// one step); with θ = 0.5 the relaxation of a held strain follows
    /// the trapezoidal rule.
    #[test]
    fn relaxation_follows_the_theta_scheme() {
        let el = Elastic::new(1000.0, 0.3).unwrap();
        let e0 = 0.01;
        // Uniaxial strain held (3D, lateral strains free is not a point
        // test: use pure shear, σxy relaxes as dτ/dt = −μ (3/2)·2τ/… ).
        // Pure shear γ held: s_xy = τ, σ_eq = √3 τ, ε̇ᵖ_xy = 3/2 ṗ τ/σ_eq
        // with ṗ = σ_eq/K (N = 1): τ̇ = −2μ ε̇ᵖ_xy = −3μ τ / K.
        for theta in [0.5, 1.0] {
            let l = law(1.0, theta);
            let mu = el.e / (2.0 * (1.0 + el.nu));
            let rate = 3.0 * mu * l.un_sur_k;
            let dt = 0.01;
            let mut st = PointState::default();
            let eps = [0.0, 0.0, 0.0, e0, 0.0, 0.0];
            // First load instantaneously (dt = 0).
            st = integrate(&l, &el, Hypothesis::Solid3D, &eps, &st, 0.0, false)
                .unwrap()
                .0;
            assert!((st.stress[3] - mu * e0).abs() < 1e-12);
            let mut tau = mu * e0;
            for _ in 0..20 {
                st = integrate(&l, &el, Hypothesis::Solid3D, &eps, &st, dt, false)
                    .unwrap()
                    .0;
                // θ-scheme for τ̇ = −r τ.
                tau *= (1.0 - (1.0 - theta) * rate * dt) / (1.0 + theta * rate * dt);
                assert!(
                    (st.stress[3] - tau).abs() < 1e-10 * mu * e0,
                    "θ = {theta}: {} vs {tau}",
                    st.stress[3]
                );
            }
            // The exact relaxation after 0.2 (τ/τ₀ = e^(−4.6) ≈ 0.010 at
            // r·Δt ≈ 0.23): the trapezoidal rule ends 2.2e-4 τ₀ from it,
            // backward Euler 5.9e-3 τ₀.
            let exact = mu * e0 * (-rate * 0.2).exp();
            let tol = if theta == 0.5 { 3e-4 } else { 7e-3 };
            assert!((st.stress[3] - exact).abs() < tol * mu * e0);
        }
    }

    /// The tangent against centred differences of the stress (N = 3,
    /// with UN_SUR_M), θ = 1 and 0.5.
    #[test]
    fn tangent_matches_finite_differences() {
        let el = Elastic::new(1000.0, 0.3).unwrap();
        for theta in [0.5, 1.0] {
            let l = Lemaitre::new(3.0, 1.0 / 5.0, 0.2, theta, 1e-14, 200).unwrap();
            let prev = PointState {
                stress: [2.0, -1.0, 0.5, 0.7, 0.0, 0.0],
                plastic_strain: [1e-3, -5e-4, -5e-4, 2e-4, 0.0, 0.0],
                p: 2e-3,
                ..Default::default()
            };
            // Elastic strain of prev plus εᵖ plus an increment.
            let mut eps = [0.0; 6];
            let mu2 = el.e / (1.0 + el.nu);
            let k3 = el.e / (1.0 - 2.0 * el.nu);
            let m = (prev.stress[0] + prev.stress[1] + prev.stress[2]) / 3.0;
            for k in 0..6 {
                let kron = if k < 3 { 1.0 } else { 0.0 };
                let dev = prev.stress[k] - m * kron;
                let e_el = dev / mu2 + kron * m / k3;
                eps[k] = prev.plastic_strain[k] + if k < 3 { e_el } else { 2.0 * e_el };
            }
            let inc = [2e-3, -1e-3, 4e-4, 1e-3, 0.0, 0.0];
            for (e, d) in eps.iter_mut().zip(inc) {
                *e += d;
            }
            let dt = 0.05;
            let (_, c) = integrate(&l, &el, Hypothesis::Solid3D, &eps, &prev, dt, false).unwrap();
            let h = 1e-7;
            for j in 0..4 {
                let mut ep = eps;
                let mut em = eps;
                ep[j] += h;
                em[j] -= h;
                let sp = integrate(&l, &el, Hypothesis::Solid3D, &ep, &prev, dt, false)
                    .unwrap()
                    .0
                    .stress;
                let sm = integrate(&l, &el, Hypothesis::Solid3D, &em, &prev, dt, false)
                    .unwrap()
                    .0
                    .stress;
                for i in 0..4 {
                    let fd = (sp[i] - sm[i]) / (2.0 * h);
                    assert!(
                        (fd - c[i][j]).abs() < 1e-4 * el.e,
                        "θ = {theta}, C[{i}][{j}] = {} vs {fd}",
                        c[i][j]
                    );
                }
            }
        }
    }

    #[test]
    fn refuses_other_schemes_and_plane_stress() {
        assert!(Lemaitre::new(1.0, 1.0, 0.0, 0.7, 1e-6, 10).is_err());
        let el = Elastic::new(1.0, 0.3).unwrap();
        let l = law(1.0, 1.0);
        let e = integrate(
            &l,
            &el,
            Hypothesis::PlaneStress,
            &[0.0; 4],
            &PointState::default(),
            1.0,
            false,
        );
        assert!(e.is_err());
    }
}
