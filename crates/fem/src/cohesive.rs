//! Cohesive laws of the joint elements (`PLAN_JOINT`, [`crate::joint`]):
//! the traction across the joint as a function of the displacement jump
//! (normal, tangential) and of internal variables, with its tangent, as
//! code_aster integrates them in 2D (`ndim = 2`):
//!
//! - `CZM_LIN_REG` (material `RUPT_FRAG`): code_aster's `lcejli` (via
//!   `lc7011`), a regularised linear softening law (R7.02.11): below the
//!   threshold κ the traction is the secant `r(κ)·δ` with
//!   `r(κ) = σc (1 − κ/δc)/κ`, `δc = 2 Gc/σc`, the initial threshold
//!   `κ0 = δc·PENA_ADHERENCE`; closing is penalised by
//!   `rc = r(κ) + PENA_CONTACT·(r(κ0) − r(κ))`; beyond `δc` the joint is
//!   broken. Nine internal variables (`SEUILDEP`, `INDIDISS`, `INDIENDO`,
//!   `PCENERDI`, `DISSIP`, `ENEL_RES`, `SAUT_N`, `SAUT_T1`, `SAUT_T2`).
//! - `CZM_TURON` (material `RUPT_TURON`): code_aster's `lcejtu` (via
//!   `lc7046`), Turon et al. 2006: a penalty stiffness `K`, a damage
//!   `d(r)` with Benzeggagh–Kenane mixed-mode initiation (`CRIT_INIT`
//!   TURON, or YE's elliptic one) and propagation thresholds; sixteen
//!   internal variables (`SAUT_MAX` … `SAUTRUPT`).
//!
//! Both are "total" laws: the traction depends on the jump at the end of
//! the step and on the internal variables at its start. The prediction
//! (code_aster's `RIGI_MECA_TANG`) evaluates the tangent at the start of
//! the step with the start's dissipation and damage indicators.

/// `CZM_LIN_REG`'s material (`RUPT_FRAG`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinReg {
    /// `GC`.
    pub gc: f64,
    /// `SIGM_C`.
    pub sigma_c: f64,
    /// `PENA_ADHERENCE`.
    pub pena_adherence: f64,
    /// `PENA_CONTACT` (code_aster's default 1).
    pub pena_contact: f64,
}

/// The damage initiation criterion of `CZM_TURON` (`CRIT_INIT`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TuronCriterion {
    /// `'TURON'` (code_aster's 0): Benzeggagh–Kenane.
    Turon,
    /// `'YE'` (code_aster's 1): elliptic.
    Ye,
}

/// `CZM_TURON`'s material (`RUPT_TURON`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turon {
    /// `K`: the penalty stiffness.
    pub k: f64,
    /// `SIGM_C_N`, `SIGM_C_T`.
    pub sigma_c_n: f64,
    pub sigma_c_t: f64,
    /// `GC_N`, `GC_T`.
    pub gc_n: f64,
    pub gc_t: f64,
    /// `C_RUPT`: the post-rupture stiffness coefficient.
    pub c_rupt: f64,
    /// `ETA_BK`: Benzeggagh–Kenane's exponent.
    pub eta_bk: f64,
    pub criterion: TuronCriterion,
}

/// A cohesive law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CohesiveLaw {
    LinReg(LinReg),
    Turon(Turon),
}

/// What is asked of a law: code_aster's options.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// `RIGI_MECA_TANG`: the tangent at the start of the step (the jump
    /// increment is not added; the indicators are the start's).
    Prediction,
    /// `FULL_MECA`: traction, internal variables and tangent at the end of
    /// the step.
    Correction,
}

/// A law's answer at one point.
#[derive(Clone, Debug, PartialEq)]
pub struct CohesiveResult {
    /// (normal, tangential) traction; `None` for a prediction.
    pub traction: Option<[f64; 2]>,
    /// The internal variables at the end of the step (prediction: `None`).
    pub vari: Option<Vec<f64>>,
    /// ∂traction/∂jump.
    pub tangent: [[f64; 2]; 2],
}

/// code_aster's `r8prem()`.
const R8PREM: f64 = f64::EPSILON;

impl CohesiveLaw {
    /// Number of internal variables (`nb_vari` of the behaviour's
    /// catalogue).
    pub fn n_vari(&self) -> usize {
        match self {
            CohesiveLaw::LinReg(_) => 9,
            CohesiveLaw::Turon(_) => 16,
        }
    }

    /// Internal variable names in code_aster's order.
    pub fn vari_names(&self) -> &'static [&'static str] {
        match self {
            CohesiveLaw::LinReg(_) => &[
                "SEUILDEP", "INDIDISS", "INDIENDO", "PCENERDI", "DISSIP", "ENEL_RES", "SAUT_N",
                "SAUT_T1", "SAUT_T2",
            ],
            CohesiveLaw::Turon(_) => &[
                "SAUT_MAX", "VARSEUIL", "VARIENDO", "INDIDISS", "INDIENDO", "SAUT_N", "SAUT_T1",
                "SAUT_T2", "SAUTEQUI", "SAUTTANG", "PCENERDI", "ENERDISS", "MIXITE_S", "MIXITE_G",
                "SAUTINIT", "SAUTRUPT",
            ],
        }
    }

    /// Integrates the law at one point: `jump_m` the jump at the start of
    /// the step, `djump` its increment, `vim` the internal variables at the
    /// start (zeros initially).
    pub fn integrate(
        &self,
        phase: Phase,
        jump_m: [f64; 2],
        djump: [f64; 2],
        vim: &[f64],
    ) -> CohesiveResult {
        match self {
            CohesiveLaw::LinReg(m) => lin_reg(m, phase, jump_m, djump, vim),
            CohesiveLaw::Turon(m) => turon(m, phase, jump_m, djump, vim),
        }
    }
}

/// code_aster's `lcejli` in 2D.
fn lin_reg(m: &LinReg, phase: Phase, am: [f64; 2], da: [f64; 2], vim: &[f64]) -> CohesiveResult {
    let resi = phase == Phase::Correction;
    let a = if resi {
        [am[0] + da[0], am[1] + da[1]]
    } else {
        am
    };
    let (gc, sc) = (m.gc, m.sigma_c);
    let lc = 2.0 * gc / sc;
    let k0 = lc * m.pena_adherence;
    let r0 = sc * (1.0 - k0 / lc) / k0;
    let beta = m.pena_contact;
    let v = |i: usize| vim.get(i).copied().unwrap_or(0.0);
    let ka = k0.max(v(0));
    let rtan = a[1] * a[1];
    let na = (a[0].max(0.0).powi(2) + rtan).sqrt();
    let rk = sc * (1.0 - ka / lc) / ka;
    let rc = rk + beta * (r0 - rk);
    let (diss, cass, traction, vari);
    if !resi {
        diss = v(1).round() as i32;
        cass = v(2).round() as i32;
        traction = None;
        vari = None;
    } else {
        let mut sigma = [rc * a[0].min(0.0), 0.0];
        if na >= lc || ka >= lc {
            diss = 0;
            cass = 2;
        } else if na <= ka {
            diss = 0;
            cass = if ka > k0 { 1 } else { 0 };
            sigma[0] += rk * a[0].max(0.0);
            sigma[1] += rk * a[1];
        } else {
            diss = 1;
            cass = 1;
            let ra = sc * (1.0 - na / lc) / na;
            sigma[0] += ra * a[0].max(0.0);
            sigma[1] += ra * a[1];
        }
        let kap = ka.max(na);
        let mut vip = vec![0.0; 9];
        vip[0] = kap;
        vip[1] = diss as f64;
        vip[2] = cass as f64;
        vip[3] = (kap / lc).min(1.0);
        vip[4] = gc * vip[3];
        vip[5] = if cass != 2 {
            0.5 * na * na * sc * (1.0 - kap / lc) / kap
        } else {
            0.0
        };
        vip[6] = a[0];
        vip[7] = a[1];
        vip[8] = 0.0;
        traction = Some(sigma);
        vari = Some(vip);
    }
    let mut d = [[0.0; 2]; 2];
    if a[0] <= 0.0 {
        d[0][0] += rc;
    }
    if cass == 2 {
        if a[0] > 0.0 {
            d[0][0] -= 1e-8 * sc / lc;
        }
        d[1][1] -= 1e-8 * sc / lc;
    } else if diss == 0 {
        if a[0] > 0.0 {
            d[0][0] += rk;
        }
        d[1][1] += rk;
    } else {
        let coef = sc * (1.0 / na - 1.0 / lc);
        let coef2 = -sc / na.powi(3);
        if a[0] <= 0.0 {
            d[1][1] += coef + coef2 * a[1] * a[1];
        } else {
            for (i, row) in d.iter_mut().enumerate() {
                row[i] += coef + coef2 * a[i] * a[i];
            }
            d[0][1] += coef2 * a[0] * a[1];
            d[1][0] += coef2 * a[1] * a[0];
        }
    }
    CohesiveResult {
        traction,
        vari,
        tangent: d,
    }
}

/// code_aster's `lcejtu` in 2D (`type_comp = 'COMP_ELAS'`).
fn turon(m: &Turon, phase: Phase, epsm: [f64; 2], deps: [f64; 2], vim: &[f64]) -> CohesiveResult {
    let resi = phase == Phase::Correction;
    let v = |i: usize| vim.get(i).copied().unwrap_or(0.0);
    let delta = if resi {
        [epsm[0] + deps[0], epsm[1] + deps[1]]
    } else {
        epsm
    };
    let k = m.k;
    let dn0 = m.sigma_c_n / k;
    let dt0 = m.sigma_c_t / k;
    let dnf = 2.0 * m.gc_n / (k * dn0);
    let dtf = 2.0 * m.gc_t / (k * dt0);
    let c = m.c_rupt;
    let eta = m.eta_bk;
    let dn_pos = delta[0].max(0.0);
    let d_t = delta[1].abs();
    let lambda = (dn_pos * dn_pos + d_t * d_t).sqrt();
    let lambda0 = lambda < R8PREM;
    let (beta, b, mut delta_0, mut delta_f);
    if !lambda0 {
        beta = d_t / (d_t + dn_pos);
        b = beta * beta / (1.0 - 2.0 * beta + 2.0 * beta * beta);
        delta_0 = match m.criterion {
            TuronCriterion::Turon => (dn0 * dn0 + (dt0 * dt0 - dn0 * dn0) * b.powf(eta)).sqrt(),
            TuronCriterion::Ye => {
                let t = if dn_pos < R8PREM {
                    std::f64::consts::FRAC_PI_2
                } else {
                    (dn0 / dt0 * d_t / dn_pos).atan()
                };
                ((dn0 * t.cos()).powi(2) + (dt0 * t.sin()).powi(2)).sqrt()
            }
        };
        delta_f = 1.0 / delta_0 * (dn0 * dnf + (dt0 * dtf - dn0 * dnf) * b.powf(eta));
    } else {
        beta = v(12);
        b = v(13);
        delta_0 = v(14);
        delta_f = v(15);
        if delta_0 < R8PREM {
            delta_0 = dn0.min(dt0);
            delta_f = dnf.min(dtf);
        }
    }
    let r = delta_0.max(v(0));
    let (mut diss, mut cass) = (0, 0);
    if !resi {
        diss = v(3).round() as i32;
        cass = v(4).round() as i32;
    }
    let (mut traction, mut vari) = (None, None);
    if resi {
        let zero = R8PREM;
        let (d, g);
        if lambda - delta_f >= zero || r - delta_f >= zero {
            diss = 0;
            cass = 2;
            d = 1.0;
            g = 1.0;
        } else {
            g = if delta_0 - lambda >= zero {
                lambda * lambda / delta_0 / delta_f
            } else {
                1.0 - (delta_f - lambda) * (delta_f - lambda) / (delta_f - delta_0) / delta_f
            };
            if r - lambda > zero {
                diss = 0;
                cass = if r - delta_0 >= zero { 1 } else { 0 };
                d = delta_f * (r - delta_0) / (r * (delta_f - delta_0));
            } else {
                diss = 1;
                cass = 1;
                d = if !lambda0 {
                    delta_f * (lambda - delta_0) / (lambda * (delta_f - delta_0))
                } else {
                    v(2)
                };
            }
        }
        let s0 = -d * k * (-delta[0]).max(0.0) + (1.0 - d) * k * delta[0];
        let s1 = (1.0 - d) * k * delta[1];
        traction = Some([s0, s1]);
        vari = Some(vec![
            lambda.max(v(0)),
            r,
            d,
            diss as f64,
            cass as f64,
            delta[0],
            delta[1],
            0.0,
            lambda,
            d_t,
            g,
            g * 0.5 * k * delta_0 * delta_f,
            beta,
            b,
            delta_0,
            delta_f,
        ]);
    }
    let mut t = [[0.0; 2]; 2];
    if cass == 2 {
        t[0][0] = if delta[0] > R8PREM {
            c * m.sigma_c_n / dnf
        } else {
            k
        };
        t[1][1] = c * m.sigma_c_t / dtf;
    } else {
        let quot = if delta[0].abs() > R8PREM {
            (-delta[0]).max(0.0) / delta[0].abs()
        } else {
            1.0
        };
        let d = if diss == 0 {
            delta_f * (r - delta_0) / (r * (delta_f - delta_0))
        } else {
            delta_f * (lambda - delta_0) / (lambda * (delta_f - delta_0))
        };
        let mut a = [[0.0; 2]; 2];
        a[0][0] = 1.0 - d + d * quot;
        a[1][1] = 1.0 - d;
        for (i, row) in a.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                t[i][j] = x * k;
            }
        }
        if diss == 1 {
            let neg = (-delta[0]).max(0.0);
            let mut aa = [[0.0; 2]; 2];
            for (i, row) in aa.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = delta[i] * delta[j];
                }
                row[0] += delta[i] * neg;
            }
            for j in 0..2 {
                aa[0][j] += delta[j] * neg;
            }
            aa[0][0] += neg * neg;
            let f = k * delta_f * delta_0 / (delta_f - delta_0) / lambda.powi(3);
            for i in 0..2 {
                for j in 0..2 {
                    t[i][j] -= aa[i][j] * f;
                }
            }
        }
    }
    CohesiveResult {
        traction,
        vari,
        tangent: t,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lin() -> LinReg {
        LinReg {
            gc: 1000.0,
            sigma_c: 30e6,
            pena_adherence: 0.077,
            pena_contact: 1.0,
        }
    }

    /// Mode II (pure shear) with a growing jump: below κ0 the traction is
    /// r(κ0)·δ; beyond it, the linear softening σc (1 − δ/δc); beyond δc,
    /// zero — at every step, from the internal variables of the last.
    #[test]
    fn lin_reg_follows_linear_softening_in_shear_and_opening() {
        let m = lin();
        let law = CohesiveLaw::LinReg(m);
        let lc = 2.0 * m.gc / m.sigma_c;
        let k0 = lc * m.pena_adherence;
        for mode in [0usize, 1] {
            let mut vim = vec![0.0; 9];
            let mut jm = [0.0; 2];
            for s in 1..=40 {
                let delta = lc * 1.2 * s as f64 / 40.0;
                let mut j = [0.0; 2];
                j[mode] = delta;
                let dj = [j[0] - jm[0], j[1] - jm[1]];
                let out = law.integrate(Phase::Correction, jm, dj, &vim);
                let t = out.traction.unwrap()[mode];
                let expected = if delta <= k0 {
                    m.sigma_c * (1.0 - k0 / lc) / k0 * delta
                } else if delta < lc {
                    m.sigma_c * (1.0 - delta / lc)
                } else {
                    0.0
                };
                assert!(
                    (t - expected).abs() <= 1e-9 * m.sigma_c,
                    "mode {mode} δ={delta}: {t} vs {expected}"
                );
                // The tangent is the derivative of the traction.
                if delta > k0 * 1.01 && delta < lc * 0.99 {
                    let h = delta * 1e-6;
                    let mut dj2 = dj;
                    dj2[mode] += h;
                    let t2 = law
                        .integrate(Phase::Correction, jm, dj2, &vim)
                        .traction
                        .unwrap()[mode];
                    let fd = (t2 - t) / h;
                    assert!(
                        (out.tangent[mode][mode] - fd).abs() <= 1e-4 * fd.abs(),
                        "{} vs {fd}",
                        out.tangent[mode][mode]
                    );
                }
                vim = out.vari.unwrap();
                jm = j;
            }
            assert_eq!(vim[2], 2.0, "broken");
            assert_eq!(vim[3], 1.0, "all the energy dissipated");
        }
    }

    #[test]
    fn lin_reg_unloads_on_the_secant_and_penalises_closing() {
        let m = lin();
        let law = CohesiveLaw::LinReg(m);
        let lc = 2.0 * m.gc / m.sigma_c;
        let k0 = lc * m.pena_adherence;
        let up = law.integrate(Phase::Correction, [0.0; 2], [0.0, 0.5 * lc], &[0.0; 9]);
        let vim = up.vari.unwrap();
        assert_eq!(vim[1], 1.0);
        let back = law.integrate(Phase::Correction, [0.0, 0.5 * lc], [0.0, -0.25 * lc], &vim);
        let secant = m.sigma_c * 0.5 / (0.5 * lc);
        assert!((back.traction.unwrap()[1] - secant * 0.25 * lc).abs() < 1e-6);
        assert_eq!(back.vari.unwrap()[1], 0.0);
        let closed = law.integrate(Phase::Correction, [0.0; 2], [-1e-6, 0.0], &vim);
        let r0 = m.sigma_c * (1.0 - k0 / lc) / k0;
        assert!((closed.traction.unwrap()[0] + r0 * 1e-6).abs() < 1e-6 * r0 * 1e-6);
    }

    fn tur() -> Turon {
        let (sigreg, gcreg, pen) = (30e6, 1000.0, 0.077);
        Turon {
            k: sigreg * sigreg * (1.0 - pen) / (2.0 * gcreg * pen),
            sigma_c_n: 10e6,
            sigma_c_t: sigreg * (1.0 - pen),
            gc_n: 200.0,
            gc_t: gcreg * (1.0 - pen),
            c_rupt: 0.001,
            eta_bk: 2.3,
            criterion: TuronCriterion::Turon,
        }
    }

    /// Pure modes: bilinear law, K δ up to δ0 = σc/K, then linear softening
    /// to zero at δf = 2 Gc/σc.
    #[test]
    fn turon_is_bilinear_in_pure_modes() {
        let m = tur();
        let law = CohesiveLaw::Turon(m);
        for (mode, sc, gc) in [(0usize, m.sigma_c_n, m.gc_n), (1, m.sigma_c_t, m.gc_t)] {
            let d0 = sc / m.k;
            let df = 2.0 * gc / sc;
            let mut vim = vec![0.0; 16];
            let mut jm = [0.0; 2];
            for s in 1..=50 {
                let delta = df * 1.1 * s as f64 / 50.0;
                let mut j = [0.0; 2];
                j[mode] = delta;
                let dj = [j[0] - jm[0], j[1] - jm[1]];
                let out = law.integrate(Phase::Correction, jm, dj, &vim);
                let t = out.traction.unwrap()[mode];
                let expected = if delta <= d0 {
                    m.k * delta
                } else if delta < df {
                    sc * (df - delta) / (df - d0)
                } else {
                    0.0
                };
                assert!(
                    (t - expected).abs() <= 1e-9 * sc,
                    "mode {mode} δ={delta}: {t} vs {expected}"
                );
                if delta > d0 * 1.01 && delta < df * 0.99 {
                    let h = delta * 1e-7;
                    let mut dj2 = dj;
                    dj2[mode] += h;
                    let t2 = law
                        .integrate(Phase::Correction, jm, dj2, &vim)
                        .traction
                        .unwrap()[mode];
                    let fd = (t2 - t) / h;
                    assert!(
                        (out.tangent[mode][mode] - fd).abs() <= 1e-4 * fd.abs(),
                        "{} vs {fd}",
                        out.tangent[mode][mode]
                    );
                }
                vim = out.vari.unwrap();
                jm = j;
            }
            assert_eq!(vim[4], 2.0);
        }
    }

    /// With the equivalent parameters of ssnv110e (K = σ²(1 − p)/(2 Gc p),
    /// σcT = σ(1 − p), GcT = Gc(1 − p)), CZM_TURON in mode II is
    /// CZM_LIN_REG's law shifted: the same traction once softening.
    #[test]
    fn turon_in_mode_ii_matches_lin_reg_with_equivalent_parameters() {
        let t = CohesiveLaw::Turon(tur());
        let l = CohesiveLaw::LinReg(lin());
        let lc = 2.0 * 1000.0 / 30e6;
        for s in 1..20 {
            let delta = lc * s as f64 / 20.0;
            let a = t.integrate(Phase::Correction, [0.0; 2], [0.0, delta], &[0.0; 16]);
            let b = l.integrate(Phase::Correction, [0.0; 2], [0.0, delta], &[0.0; 9]);
            let (ta, tb) = (a.traction.unwrap()[1], b.traction.unwrap()[1]);
            assert!((ta - tb).abs() < 1e-6 * 30e6, "δ={delta}: {ta} vs {tb}");
        }
    }
}
