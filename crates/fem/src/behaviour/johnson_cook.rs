//! Johnson–Cook viscoplasticity (`VMIS_JOHN_COOK`, material `ECRO_COOK`),
//! as code_aster's `nmtevp` integrates it with `eccook` (the flow stress),
//! `nmcri9` (the scalar equation of the radial return) and `zerofr`
//! (`encadr` then Brent's `zerofb`, `ALGO_INTE='BRENT'`).
//!
//! Flow stress (`eccook`), p the cumulated plastic strain, ṗ = Δp/Δt:
//!
//!   R = (A + B pᴺ) · (1 + C ln(ṗ/ε̇₀) when ṗ > ε̇₀) · (1 − θᴹ when T > T_room),
//!   θ = (T − T_room)/(T_melt − T_room),
//!
//! with p below p₀ = 1e-9 read as p₀ (the hardening's slope is infinite at
//! 0 when N < 1) and the rate factor left out there. code_aster's elastic
//! test uses the *previous* increment's values (`eccook` at pₙ + Δpₙ₋₁,
//! rate Δpₙ₋₁/Δtₙ₋₁: its VARI 1, 3 and 4); the return then solves
//! f(Δp) = R(pₙ + Δp, Δp/Δt) + 3μΔp − σ_eq^trial = 0 as `nmtevp` does
//! ([`JohnsonCook::plastic_increment`]): from the guess Δp₀ = (σ_eq^trial
//! − R_test)/3μ, halved until f < 0, then `zerofr` on [0, Δp_max] stopped
//! at |f| < RESI_INTE × R(pₙ + Δp₀, Δp₀/Δt) within ITER_INTE_MAXI
//! iterations — the same iterates, so the same Δp, as code_aster.
//!
//! The stress update, VARI and tangent are in `vmis` (the radial return
//! shared with the other von Mises laws, `Hardening::JohnsonCook`).

/// `ECRO_COOK`: A, B, N_PUIS, C, EPSP0, M_PUIS, TROOM, TMELT, with the
/// COMPORTEMENT's RESI_INTE and ITER_INTE_MAXI.
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
    /// `RESI_INTE` (code_aster's crit(3)): the return stops at |f| below
    /// it times the flow stress of the first guess.
    pub resi_inte: f64,
    /// `ITER_INTE_MAXI` (crit(1)).
    pub iter_maxi: usize,
}

/// The solved plastic increment: Δp and `nmtevp`'s VARI 2 (the
/// iterations of the search, INDIPLAS).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlasticIncrement {
    pub dp: f64,
    pub iterations: usize,
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
        // dp/dt > ε̇₀ is false for 0/0 (the first increment), as in Fortran.
        if dp / dt > self.epsp0 {
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

    /// `nmtevp`'s plastic branch: Δp from the trial equivalent stress
    /// `sieleq`, the flow stress of the elastic test `r_test`, 3μ, pₙ and
    /// the step's Δt. `Err` when `zerofr` fails (code_aster's iret = 1:
    /// the integration fails and the step is cut).
    pub fn plastic_increment(
        &self,
        sieleq: f64,
        r_test: f64,
        three_mu: f64,
        pm: f64,
        dt: f64,
        temp: Option<f64>,
    ) -> Result<PlasticIncrement, String> {
        let f = |dp: f64| self.flow_stress(pm, dp, dt, temp).0 + three_mu * dp - sieleq;
        let dp0 = (sieleq - r_test) / three_mu;
        let (sigy, _) = self.flow_stress(pm, dp0, dt, temp);
        let precr = self.resi_inte * sigy;
        let niter = self.iter_maxi;
        let mut fmax = sigy;
        let mut dpmax = dp0;
        let found = |dp, iterations| Ok(PlasticIncrement { dp, iterations });
        if fmax.abs() <= precr {
            return found(dpmax, 1);
        } else if fmax > 0.0 {
            for i in 1..=niter {
                dpmax /= 2.0;
                fmax = f(dpmax);
                if fmax.abs() <= precr {
                    return found(dpmax, i);
                } else if fmax < 0.0 {
                    dpmax *= 2.0;
                    break;
                }
            }
        } else {
            for i in 1..=niter {
                fmax = f(dpmax);
                if fmax.abs() <= precr {
                    return found(dpmax, i);
                } else if fmax > 0.0 {
                    break;
                }
                dpmax *= 2.0;
            }
        }
        // zerofr(2, 'BRENT', ...): encadr with a factor 10, then zerofb.
        let (a, b) = encadr(&f, 0.0, dpmax, niter, 10.0).ok_or_else(|| {
            format!("VMIS_JOHN_COOK: the plastic increment could not be bracketed in {niter} iterations (ITER_INTE_MAXI; σ_eq trial = {sieleq:e}, p = {pm:e})")
        })?;
        zerofb(&f, a, b, precr, niter)
            .map(|(dp, iterations)| PlasticIncrement { dp, iterations })
            .ok_or_else(|| {
                format!("VMIS_JOHN_COOK: Brent's search of the plastic increment did not reach RESI_INTE in {niter} iterations (ITER_INTE_MAXI; σ_eq trial = {sieleq:e}, p = {pm:e})")
            })
    }
}

/// code_aster's `encadr`: widens [x1, x2] by `xmult` on the side of the
/// smaller |f| until f changes sign, at most `niter` times.
fn encadr(
    f: &dyn Fn(f64) -> f64,
    x1: f64,
    x2: f64,
    niter: usize,
    xmult: f64,
) -> Option<(f64, f64)> {
    let (mut x1, mut x2) = (x1, x2);
    if x1 == x2 {
        return None;
    }
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..niter {
        if f1 * f2 < 0.0 {
            return Some((x1, x2));
        }
        if f1.abs() < f2.abs() {
            x1 += xmult * (x1 - x2);
            f1 = f(x1);
        } else {
            x2 += xmult * (x2 - x1);
            f2 = f(x2);
        }
    }
    None
}

/// code_aster's `zerofb` (Brent): the root of `f` in [x1, x2] to |f| <
/// `tol` (or the bracket at round-off), with the iteration it stopped at.
fn zerofb(
    f: &dyn Fn(f64) -> f64,
    x1: f64,
    x2: f64,
    tol: f64,
    itmax: usize,
) -> Option<(f64, usize)> {
    let eps = f64::EPSILON;
    let (mut a, mut b) = (x1, x2);
    let (mut fa, mut fb) = (f(a), f(b));
    if (fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0) {
        return None;
    }
    let (mut c, mut fc) = (b, fb);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for iter in 1..=itmax {
        if (fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * eps * b.abs();
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb.abs() < tol {
            return Some((b, iter));
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                q = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0));
                q = (q - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        if d.abs() > tol1 {
            b += d;
        } else {
            b += tol1.copysign(xm);
        }
        fb = f(b);
    }
    None
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
            resi_inte: 1e-6,
            iter_maxi: 30,
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
        // Below ε̇₀ no rate factor; at or below p₀ = 1e-9, R(p₀); the
        // first increment (Δp = Δt = 0) has no rate factor either.
        let slow = jc.flow_stress(0.1, 1e-6, 1.0, None).0;
        assert!((slow - (90.0 + 292.0 * (0.1f64 + 1e-6).powf(0.31))).abs() < 1e-12);
        let zero = jc.flow_stress(0.0, 0.0, 1.0, None).0;
        assert!((zero - (90.0 + 292.0 * 1e-9f64.powf(0.31))).abs() < 1e-12);
        let first = jc.flow_stress(0.1, 0.0, 0.0, None).0;
        assert!((first - (90.0 + 292.0 * 0.1f64.powf(0.31))).abs() < 1e-12);
    }

    /// The scalar return: Δp solves R(pₙ + Δp, Δp/Δt) + 3μΔp = σ_eq to
    /// code_aster's stop, |f| < RESI_INTE · R(Δp₀), and lies within that
    /// residual over 3μ of the root found by bisection to round-off.
    #[test]
    fn plastic_increment_solves_the_scalar_equation_to_resi_inte() {
        let jc = copper();
        let three_mu = 1.5 * 117.0e3 / 1.35;
        for &(pm, dt, sieleq) in &[
            (0.0, 5e-8, 400.0),
            (0.05, 5e-8, 1200.0),
            (0.3, 1e-3, 500.0),
            (0.0, 1.0, 100.0),
        ] {
            let r_test = jc.flow_stress(pm, 0.0, 0.0, None).0;
            let inc = jc
                .plastic_increment(sieleq, r_test, three_mu, pm, dt, None)
                .unwrap();
            let f = |dp: f64| jc.flow_stress(pm, dp, dt, None).0 + three_mu * dp - sieleq;
            let dp0 = (sieleq - r_test) / three_mu;
            let precr = 1e-6 * jc.flow_stress(pm, dp0, dt, None).0;
            assert!(
                f(inc.dp).abs() <= precr,
                "{pm} {dt} {sieleq}: f = {}",
                f(inc.dp)
            );
            assert!(inc.iterations >= 1);
            let (mut lo, mut hi) = (0.0, sieleq / three_mu);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if f(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            assert!((inc.dp - lo).abs() <= precr / three_mu, "{} {lo}", inc.dp);
        }
    }

    /// Brent's search (zerofb) on a cubic: the root to the tolerance, and
    /// None without a sign change.
    #[test]
    fn zerofb_finds_a_bracketed_root() {
        let f = |x: f64| x * x * x - 2.0;
        let (x, it) = zerofb(&f, 0.0, 3.0, 1e-12, 100).unwrap();
        assert!((x - 2f64.cbrt()).abs() < 1e-12, "{x}");
        assert!(it < 20);
        assert!(zerofb(&f, 2.0, 3.0, 1e-12, 100).is_none());
        let (a, b) = encadr(&f, 0.0, 0.5, 10, 10.0).unwrap();
        assert!(f(a) * f(b) < 0.0);
    }
}
