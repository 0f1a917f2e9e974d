//! Von Mises plasticity with linear kinematic hardening, small strains
//! (`VMIS_CINE_LINE`, code_aster's `nmcine`), integrated by radial return
//! with its consistent tangent.
//!
//! The back stress X (a deviatoric tensor, Prager's rule) follows the
//! plastic strain: X = C εᵖ with C = 2/3 · H, H = E·ET/(E − ET) from
//! `ECRO_LINE=_F(D_SIGM_EPSI=ET, SY)` (`nmcine`'s cpragp =
//! 2/3 · ET/(1 − ET/E)), so that a uniaxial tension follows σ = SY + H εᵖ
//! as with isotropic hardening, and a reversal yields again after a
//! stress range of 2 SY (the Bauschinger effect). The yield surface is
//! √(3/2 (s − X):(s − X)) = SY.
//!
//! With constant elastic constants the trial deviator of `nmcine`
//! (σ⁻ + 2μ Δe) equals the total-strain one 2μ dev(ε − εᵖ) used here.
//! The return: ξ = s_trial − X⁻, q = √(3/2 ξ:ξ), Δp = (q − SY)/(3μ + 3/2 C),
//! n = 3/2 ξ/q, s = s_trial − 2μ Δp n, X = X⁻ + C Δp n, εᵖ += Δp n. The
//! tangent is [`super::vmis`]'s radial-return form on ξ with 3/2 C in
//! place of the isotropic slope; it equals `nmcine`'s DSIDEP (a2·2μ I +
//! coef (s − X)⊗(s − X) and its λ correction, with a1 = SY/q), and at a
//! converged plastic state (the prediction, Δp = 0) the continuum one.
//!
//! VARI in code_aster's order: V1–V6 the back stress (XX, YY, ZZ, XY, XZ,
//! YZ, tensor components; XZ, YZ zero in 2D), V7 the plasticity indicator.

use super::vmis::{deviator, elastic_3d, elastic_trial, lame, tangent_3d, Mat6, PointState};
use crate::error::FemError;
use crate::material::Elastic;

/// Prager's constant C = 2/3 · H of a linear kinematic hardening.
pub fn prager(h: f64) -> f64 {
    2.0 / 3.0 * h
}

/// The return from `prev` for the total strain `eps` (3D, engineering
/// shears), yield stress `sy`, Prager's constant `c`. Returns the new
/// state and the consistent tangent.
pub fn integrate_3d(
    sy: f64,
    c: f64,
    el: &Elastic,
    eps: &[f64; 6],
    prev: &PointState,
) -> Result<(PointState, Mat6), FemError> {
    let d = elastic_3d(el);
    let (_, mu) = lame(el);
    let trial = elastic_trial(&d, eps, &prev.plastic_strain);
    let (s, _) = deviator(&trial);
    let mut xi = [0.0; 6];
    for i in 0..6 {
        xi[i] = s[i] - prev.back[i];
    }
    let q = von_mises(&xi);
    if q - sy <= 0.0 {
        let next = PointState {
            stress: trial,
            plastic: false,
            ..*prev
        };
        return Ok((next, d));
    }
    let denom = 3.0 * mu + 1.5 * c;
    if denom <= 0.0 {
        return Err(FemError::Model(format!(
            "VMIS_CINE_LINE: the hardening constant C = {c} is below −2μ = {}: the local problem has no solution",
            -2.0 * mu
        )));
    }
    let dp = (q - sy) / denom;
    let mut next = PointState {
        p: prev.p + dp,
        plastic: true,
        ..*prev
    };
    for i in 0..6 {
        let n = 1.5 * xi[i] / q;
        next.stress[i] = trial[i] - 2.0 * mu * dp * n;
        next.back[i] = prev.back[i] + c * dp * n;
        // Engineering shears double the off-diagonal plastic strain.
        let f = if i < 3 { 1.0 } else { 2.0 };
        next.plastic_strain[i] += f * dp * n;
    }
    let ratio = 3.0 * mu * dp / q;
    let theta = 1.0 - ratio;
    let theta_bar = 1.0 / (1.0 + 1.5 * c / (3.0 * mu)) - ratio;
    Ok((next, tangent_3d(el, theta, theta_bar, &xi, q)))
}

/// The tangent at a converged state with no increment (RIGI_MECA_TANG):
/// elastic if the last increment was elastic, else the continuum one.
pub fn prediction_tangent_3d(c: f64, el: &Elastic, state: &PointState) -> Mat6 {
    if !state.plastic {
        return elastic_3d(el);
    }
    let (_, mu) = lame(el);
    let (s, _) = deviator(&state.stress);
    let mut xi = [0.0; 6];
    for i in 0..6 {
        xi[i] = s[i] - state.back[i];
    }
    let q = von_mises(&xi);
    tangent_3d(el, 1.0, 1.0 / (1.0 + 1.5 * c / (3.0 * mu)), &xi, q)
}

/// VARI of a point: the back stress (tensor components, `ncomp` of the
/// hypothesis kept, the others zero) and the plasticity indicator.
pub fn vari(state: &PointState, ncomp: usize) -> [f64; 7] {
    let mut v = [0.0; 7];
    for (k, x) in state.back.iter().enumerate().take(ncomp.min(6)) {
        v[k] = *x;
    }
    v[6] = if state.plastic { 1.0 } else { 0.0 };
    v
}

/// √(3/2 a:a) of a deviator (tensor shears).
fn von_mises(a: &[f64; 6]) -> f64 {
    let ss =
        a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + 2.0 * (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]);
    (1.5 * ss).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Elastic {
        Elastic::new(200e3, 0.3).unwrap()
    }

    /// Uniaxial stress history by strain control on εxx with the lateral
    /// strains found by Newton (σyy = σzz = 0).
    fn uniaxial(sy: f64, c: f64, path: &[f64]) -> Vec<(f64, PointState)> {
        let el = steel();
        let mut st = PointState::default();
        let mut lateral = 0.0;
        let mut out = Vec::new();
        for &exx in path {
            let mut k = 0;
            let (next, _) = loop {
                let eps = [exx, lateral, lateral, 0.0, 0.0, 0.0];
                let (n, t) = integrate_3d(sy, c, &el, &eps, &st).unwrap();
                let r = n.stress[1];
                if r.abs() < 1e-9 * sy || k > 50 {
                    break (n, t);
                }
                lateral -= r / (t[1][1] + t[1][2]);
                k += 1;
            };
            st = next;
            out.push((exx, st));
        }
        out
    }

    #[test]
    fn uniaxial_tension_follows_the_bilinear_curve_and_reversal_shows_bauschinger() {
        let (e, et, sy) = (200e3, 2e3, 200.0);
        let h = e * et / (e - et);
        let c = prager(h);
        let path: Vec<f64> = (1..=20)
            .map(|i| 0.0002 * i as f64)
            .chain((1..=40).map(|i| 0.004 - 0.0002 * i as f64))
            .collect();
        let hist = uniaxial(sy, c, &path);
        // Loading: σ = SY + ET (ε − SY/E) beyond yield.
        let (e_max, st_max) = hist[19];
        let s_max = sy + et * (e_max - sy / e);
        assert!((st_max.stress[0] - s_max).abs() < 1e-6 * s_max);
        // Back stress X_xx = 2/3 H εᵖ; the deviator of σ is 2/3 σ.
        let ep = e_max - s_max / e;
        assert!((st_max.back[0] - c * ep).abs() < 1e-9 * s_max);
        // Unloading is elastic over a range of 2 SY, then the reversed
        // yield follows the same slope (Bauschinger).
        let reversed_yield = s_max - 2.0 * sy;
        for &(exx, st) in &hist[20..] {
            let elastic = s_max - e * (e_max - exx);
            if elastic >= reversed_yield + 1e-9 {
                assert!((st.stress[0] - elastic).abs() < 1e-6 * sy, "{exx}");
                assert!(!st.plastic);
            }
        }
        let (e_end, st_end) = hist[hist.len() - 1];
        let e_rev = e_max - 2.0 * sy / e;
        let expected = reversed_yield + et * (e_end - e_rev);
        assert!((st_end.stress[0] - expected).abs() < 1e-6 * sy);
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_return() {
        let el = steel();
        let c = prager(2e4);
        let prev = integrate_3d(
            150.0,
            c,
            &el,
            &[2e-3, -5e-4, 1e-4, 6e-4, -2e-4, 3e-4],
            &PointState::default(),
        )
        .unwrap()
        .0;
        let eps = [2.6e-3, -4e-4, 3e-4, 9e-4, -1e-4, 5e-4];
        let (st, t) = integrate_3d(150.0, c, &el, &eps, &prev).unwrap();
        assert!(st.plastic);
        let h = 1e-9;
        for j in 0..6 {
            let (mut ep, mut em) = (eps, eps);
            ep[j] += h;
            em[j] -= h;
            let sp = integrate_3d(150.0, c, &el, &ep, &prev).unwrap().0.stress;
            let sm = integrate_3d(150.0, c, &el, &em, &prev).unwrap().0.stress;
            for i in 0..6 {
                let fd = (sp[i] - sm[i]) / (2.0 * h);
                assert!(
                    (fd - t[i][j]).abs() < 1e-4 * 200e3,
                    "{i} {j}: {fd} {}",
                    t[i][j]
                );
            }
        }
        // At the converged state without increment: the continuum tangent
        // is symmetric and softer than Hooke's along the flow.
        let pt = prediction_tangent_3d(c, &el, &st);
        let d = elastic_3d(&el);
        for i in 0..6 {
            for j in 0..6 {
                assert!((pt[i][j] - pt[j][i]).abs() < 1e-6);
            }
        }
        assert!(pt[0][0] < d[0][0]);
    }

    #[test]
    fn vari_packs_the_back_stress_then_the_indicator() {
        let st = PointState {
            back: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            plastic: true,
            ..PointState::default()
        };
        assert_eq!(vari(&st, 4), [1.0, 2.0, 3.0, 4.0, 0.0, 0.0, 1.0]);
        assert_eq!(vari(&st, 6), [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 1.0]);
    }
}
