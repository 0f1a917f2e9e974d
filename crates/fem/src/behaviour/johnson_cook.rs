//! Johnson–Cook viscoplasticity (`VMIS_JOHN_COOK`, material `ECRO_COOK`),
//! as code_aster's `nmtevp` integrates it with `eccook` (the flow stress)
//! and `nmcri9` (the scalar equation of the radial return).
//!
//! Flow stress (`eccook`), p the cumulated plastic strain, ṗ = Δp/Δt:
//!
//!   R = (A + B pᴺ) · (1 + C ln(ṗ/ε̇₀) when ṗ > ε̇₀) · (1 − θᴹ when T > T_room),
//!   θ = (T − T_room)/(T_melt − T_room),
//!
//! with p below p₀ = 1e-9 read as p₀ (the hardening's slope is infinite at
//! 0 when N < 1) and the rate factor left out there. code_aster's elastic
//! test uses the *previous* increment's rate (its VARI 3 and 4: Δp and Δt)
//! and temperature; the return then solves R(pₙ + Δp, Δp/Δt) + 3μΔp =
//! σ_eq^trial for Δp. code_aster brackets the root by halving from the
//! elastic guess and finishes with `zerofr` (secant) to RESI_INTE_RELA × R:
//! its Δp is within that tolerance of the root this module solves to
//! round-off (bracketed Newton), so stresses agree to about RESI_INTE_RELA
//! (1e-6 by default).
//!
//! Vectors are code_aster's: six components xx, yy, zz, √2·xy, √2·xz, √2·yz
//! (3D). Not wired to `COMPORTEMENT` yet: `run` refuses `VMIS_JOHN_COOK`
//! (its only contact case, sdnv103g, also needs GDEF_LOG in dynamics).

/// `ECRO_COOK`: A, B, N_PUIS, C, EPSP0, M_PUIS, TROOM, TMELT.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JohnsonCook {
    pub a: f64,
    pub b: f64,
    pub n: f64,
    /// `C` (0 without rate dependence), with `EPSP0` (1 when C is absent).
    pub c: f64,
    pub epsp0: f64,
    /// `M_PUIS`, `TROOM`, `TMELT`; `None`: no thermal softening.
    pub thermal: Option<(f64, f64, f64)>,
}

/// The internal variables of a Gauss point (code_aster's VARI 1–4: p,
/// plastic indicator — the number of iterations of the return —, Δp and
/// Δt of the last increment).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JcState {
    pub p: f64,
    pub plastic: bool,
    pub dp: f64,
    pub dt: f64,
}

impl JohnsonCook {
    /// code_aster's `eccook`: the flow stress R and dR/dΔp at the plastic
    /// strain `pm + dp` over `dt`, at the temperature `temp`.
    pub fn flow_stress(&self, pm: f64, dp: f64, dt: f64, temp: Option<f64>) -> (f64, f64) {
        const P0: f64 = 1e-9;
        if pm + dp <= P0 {
            return (
                self.a + self.b * P0.powf(self.n),
                self.n * self.b * P0.powf(self.n - 1.0),
            );
        }
        let p = pm + dp;
        let mut r = self.a + self.b * p.powf(self.n);
        let mut rprim = self.n * self.b * p.powf(self.n - 1.0);
        if dt > 0.0 && dp / dt > self.epsp0 {
            let l = (dp / dt / self.epsp0).ln();
            rprim += self.c * (rprim * l + r / dp);
            r *= 1.0 + self.c * l;
        }
        if let (Some((m, troom, tmelt)), Some(t)) = (self.thermal, temp) {
            if t > troom && troom >= -0.5 {
                let f = 1.0 - ((t - troom) / (tmelt - troom)).powf(m);
                r *= f;
                rprim *= f;
            }
        }
        (r, rprim)
    }

    /// The radial return of `nmtevp` (RAPH_MECA): from the stress `sig`
    /// and state `prev` at the start of the increment, the strain
    /// increment `deps` over `dt`, with `moduli` = (2μ, 3K) (constant
    /// elastic coefficients). Returns the stress and the state.
    pub fn integrate(
        &self,
        moduli: (f64, f64),
        sig: &[f64; 6],
        deps: &[f64; 6],
        prev: &JcState,
        dt: f64,
        temp: Option<f64>,
    ) -> ([f64; 6], JcState) {
        let (two_mu, three_k) = moduli;
        let kron = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
        let depsmo = (deps[0] + deps[1] + deps[2]) / 3.0;
        let sigmo = (sig[0] + sig[1] + sig[2]) / 3.0;
        let mut sigel = [0.0; 6];
        let mut sdev = [0.0; 6];
        for k in 0..6 {
            sdev[k] = sig[k] - sigmo * kron[k];
            sigel[k] = sdev[k] + two_mu * (deps[k] - depsmo * kron[k]);
        }
        let sieleq = (1.5 * sigel.iter().map(|v| v * v).sum::<f64>()).sqrt();
        // The elastic test with the previous increment's rate.
        let (rp, _) = self.flow_stress(prev.p, prev.dp, prev.dt, temp);
        let sigpmo = sigmo + three_k * depsmo;
        if sieleq - rp <= 0.0 {
            let mut out = [0.0; 6];
            for k in 0..6 {
                out[k] = sigel[k] + sigpmo * kron[k];
            }
            return (
                out,
                JcState {
                    p: prev.p,
                    plastic: false,
                    dp: 0.0,
                    dt,
                },
            );
        }
        // nmcri9: f(Δp) = R(pₙ + Δp, Δp/Δt) + 3μΔp − σ_eq^trial, increasing
        // in Δp, f(0) < 0 < f(σ_eq^trial / 3μ).
        let f = |dp: f64| {
            let (r, rprim) = self.flow_stress(prev.p, dp, dt, temp);
            (r + 1.5 * two_mu * dp - sieleq, rprim + 1.5 * two_mu)
        };
        let (mut lo, mut hi) = (0.0f64, sieleq / (1.5 * two_mu));
        let mut dp = 0.5 * (lo + hi);
        for _ in 0..200 {
            let (v, d) = f(dp);
            if v > 0.0 {
                hi = dp;
            } else {
                lo = dp;
            }
            let newton = dp - v / d;
            let next = if d > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - dp).abs() <= 1e-15 * dp.abs().max(1e-300) || hi - lo <= 1e-16 * hi {
                dp = next;
                break;
            }
            dp = next;
        }
        let (r, _) = self.flow_stress(prev.p, dp, dt, temp);
        let scale = r / (r + 1.5 * two_mu * dp);
        let mut out = [0.0; 6];
        for k in 0..6 {
            out[k] = sigel[k] * scale + sigpmo * kron[k];
        }
        (
            out,
            JcState {
                p: prev.p + dp,
                plastic: true,
                dp,
                dt,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sdnv103g's copper: A = 90, B = 292, N = 0.31, C = 0.025, ε̇₀ = 1.
    fn copper() -> JohnsonCook {
        JohnsonCook {
            a: 90.0,
            b: 292.0,
            n: 0.31,
            c: 0.025,
            epsp0: 1.0,
            thermal: Some((1.09, 298.0, 1083.0)),
        }
    }

    #[test]
    fn flow_stress_is_the_johnson_cook_product() {
        let jc = copper();
        let (p, dp, dt): (f64, f64, f64) = (0.1, 0.02, 1e-3);
        let rate = dp / dt;
        let theta: f64 = (500.0 - 298.0) / (1083.0 - 298.0);
        let expected = (90.0 + 292.0 * (p + dp).powf(0.31))
            * (1.0 + 0.025 * rate.ln())
            * (1.0 - theta.powf(1.09));
        let (r, rprim) = jc.flow_stress(p, dp, dt, Some(500.0));
        assert!((r - expected).abs() <= 1e-12 * expected, "{r} {expected}");
        // dR/dΔp against centred differences.
        let h = 1e-7;
        let fd = (jc.flow_stress(p, dp + h, dt, Some(500.0)).0
            - jc.flow_stress(p, dp - h, dt, Some(500.0)).0)
            / (2.0 * h);
        assert!((rprim - fd).abs() <= 1e-6 * fd.abs(), "{rprim} {fd}");
        // Below ε̇₀ no rate factor; at or below p₀ = 1e-9, R(p₀).
        let slow = jc.flow_stress(0.1, 1e-6, 1.0, None).0;
        assert!((slow - (90.0 + 292.0 * (0.1f64 + 1e-6).powf(0.31))).abs() < 1e-12);
        let zero = jc.flow_stress(0.0, 0.0, 1.0, None).0;
        assert!((zero - (90.0 + 292.0 * 1e-9f64.powf(0.31))).abs() < 1e-12);
    }

    /// One increment of uniaxial-stress-like deviatoric loading by hand:
    /// a pure shear strain increment γ (Mandel component √2·ε_xy = γ/√2)
    /// gives σ_eq^trial = √3 μ γ; the return's Δp solves
    /// R(Δp, Δp/Δt) + 3μΔp = σ_eq^trial, and the shear stress is
    /// σ_eq/√3 with σ_eq = R(Δp).
    #[test]
    fn radial_return_in_shear_matches_the_scalar_equation() {
        let jc = JohnsonCook {
            thermal: None,
            ..copper()
        };
        let (e, nu) = (117.0e3, 0.35);
        let two_mu = e / (1.0 + nu);
        let three_k = e / (1.0 - 2.0 * nu);
        let gamma = 0.02;
        let dt = 1e-4;
        let mut deps = [0.0; 6];
        deps[3] = gamma / 2.0 * 2f64.sqrt();
        let (sig, st) = jc.integrate(
            (two_mu, three_k),
            &[0.0; 6],
            &deps,
            &JcState::default(),
            dt,
            None,
        );
        assert!(st.plastic);
        let mu = two_mu / 2.0;
        let trial = 3f64.sqrt() * mu * gamma;
        let (r, _) = jc.flow_stress(0.0, st.dp, dt, None);
        assert!((r + 3.0 * mu * st.dp - trial).abs() <= 1e-10 * trial);
        let tau = sig[3] / 2f64.sqrt();
        assert!((tau - r / 3f64.sqrt()).abs() <= 1e-10 * r, "{tau} {r}");
        assert!(sig[0].abs() < 1e-9 && sig[1].abs() < 1e-9 && sig[2].abs() < 1e-9);
        // An elastic increment: below the yield stress of the previous rate.
        let small = {
            let mut d = [0.0; 6];
            d[3] = 1e-5;
            d
        };
        let (sig, st) = jc.integrate(
            (two_mu, three_k),
            &[0.0; 6],
            &small,
            &JcState::default(),
            dt,
            None,
        );
        assert!(!st.plastic);
        assert!((sig[3] - two_mu * 1e-5).abs() < 1e-12);
    }
}
