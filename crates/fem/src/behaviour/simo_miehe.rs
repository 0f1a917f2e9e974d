//! Von Mises plasticity with isotropic hardening in finite strains, Simo
//! and Miehe's multiplicative formulation (`DEFORMATION='SIMO_MIEHE'` with
//! `VMIS_ISOT_LINE` / `VMIS_ISOT_TRAC`): code_aster's `lcpivm` with
//! `gdsmci`, `gdsmhy`, `gdsmtg` and `lcpitg` (R5.03.21).
//!
//! The state is the cumulated plastic strain p, the plasticity indicator
//! and the elastic strain e = (I − bₑ)/2 (bₑ = Fₑ Fₑᵀ), code_aster's
//! VARI V1, V2 and V3…V8. From the converged gradient F⁻ and the increment
//! ΔF (F = ΔF F⁻), the trial isochoric left Cauchy–Green tensor is
//! b̄ₑᵗʳ = ΔF̄ b̄ₑ⁻ ΔF̄ᵀ (ΔF̄ = (det ΔF)^(−1/3) ΔF); the return on the
//! Kirchhoff deviator μ dev b̄ₑ solves μ q(b̄ₑᵗʳ) − μ tr(b̄ₑᵗʳ) Δp = R(p + Δp),
//! q = √(3/2 dev:dev); the Kirchhoff stress is
//! τ = μ dev b̄ₑ + K/2 (J² − 1) I, and the new elastic strain gets
//! code_aster's hydrostatic correction det bₑ = J².
//!
//! Vectors are in Mandel notation inside (xx, yy, zz, √2 xy, √2 xz, √2 yz),
//! as code_aster's; [`SimoMiehe`] returns tensor components.

use super::vmis::{Hardening, VonMises};
use crate::error::FemError;
use crate::material::Elastic;
use nalgebra::Matrix3;

const SQRT2: f64 = std::f64::consts::SQRT_2;
/// √2 on the shear components.
const RC: [f64; 6] = [1.0, 1.0, 1.0, SQRT2, SQRT2, SQRT2];
/// Kronecker δ in Mandel notation.
const KR: [f64; 6] = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
/// Mandel index → (i, j), code_aster's ind1/ind2 (xy is (2,1) there: the
/// pair order does not matter for symmetric tensors).
const IND: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 0), (2, 0), (2, 1)];
/// (i, j) → Mandel index.
const MANDEL: [[usize; 3]; 3] = [[0, 3, 4], [3, 1, 5], [4, 5, 2]];

fn dot6(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    (0..6).map(|k| a[k] * b[k]).sum()
}

/// What a Gauss point asks of the law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// `FULL_MECA`: the state at the end of the increment and its tangent.
    Correction,
    /// `RIGI_MECA_TANG` (`elastic`: `RIGI_MECA_ELAS`): the tangent at the
    /// converged state, nothing integrated.
    Prediction { elastic: bool },
}

/// The state of a Gauss point (code_aster's VARI V1…V8).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmState {
    /// Cumulated plastic strain (V1).
    pub p: f64,
    /// Whether the last increment was plastic (V2).
    pub plastic: bool,
    /// Elastic strain (I − bₑ)/2, tensor components xx yy zz xy xz yz
    /// (V3…V8).
    pub e: [f64; 6],
}

/// Result of an integration: the Kirchhoff stress (tensor components),
/// the new state and ∂τ/∂ΔF · ΔFᵀ, `dtau[ij][k][l]` (rows ij tensor
/// components).
#[derive(Clone, Debug)]
pub struct SmOutput {
    pub tau: [f64; 6],
    pub state: SmState,
    pub dtau: [[[f64; 3]; 3]; 6],
}

fn det3(m: &Matrix3<f64>) -> f64 {
    m[(0, 0)] * (m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)])
        - m[(1, 0)] * (m[(0, 1)] * m[(2, 2)] - m[(0, 2)] * m[(2, 1)])
        + m[(2, 0)] * (m[(0, 1)] * m[(1, 2)] - m[(0, 2)] * m[(1, 1)])
}

/// Simo–Miehe integration from `prev` for the converged gradient `fm` and
/// the increment `df` (F = df·fm).
pub fn integrate(
    law: &VonMises,
    el: &Elastic,
    fm: &Matrix3<f64>,
    df: &Matrix3<f64>,
    prev: &SmState,
    phase: Phase,
) -> Result<SmOutput, FemError> {
    let resi = phase == Phase::Correction;
    let el = &law.elastic(el);
    let young = el.e;
    let nu = el.nu;
    let mu = young / (2.0 * (1.0 + nu));
    let troisk = young / (1.0 - 2.0 * nu);
    let unk = troisk / 3.0;
    let pm = prev.p;
    // em: the elastic strain at t−, Mandel.
    let mut em = prev.e;
    for k in 3..6 {
        em[k] *= SQRT2;
    }
    // gdsmci: Jacobians, ΔF̄, b̄ₑ⁻, b̄ₑᵗʳ.
    let jm = det3(fm);
    let dj = det3(df);
    let jp = jm * dj;
    let dfb = df * dj.powf(-1.0 / 3.0);
    let mut bem = [0.0; 6];
    for k in 0..6 {
        bem[k] = (KR[k] - 2.0 * em[k]) / jm.powf(2.0 / 3.0);
    }
    let mut betr = [0.0; 6];
    for ij in 0..6 {
        let (i, j) = IND[ij];
        for kl in 0..6 {
            let (k, l) = IND[kl];
            let pdf =
                RC[ij] * RC[kl] * (dfb[(i, k)] * dfb[(j, l)] + dfb[(j, k)] * dfb[(i, l)]) / 2.0;
            betr[ij] += pdf * bem[kl];
        }
    }
    let trbetr = betr[0] + betr[1] + betr[2];
    let mut dvbetr = [0.0; 6];
    for k in 0..6 {
        dvbetr[k] = betr[k] - trbetr / 3.0 * KR[k];
    }
    let eqbetr = (1.5 * dot6(&dvbetr, &dvbetr)).sqrt();
    // lcpima: R(p⁻) and the hardening slope at p⁻.
    let (rpm, slope_m) = law.yield_stress(pm)?;

    let mut tau = [0.0; 6];
    let mut state = *prev;
    let (dp, line, dvbe, slope);
    if resi {
        let seuil = mu * eqbetr - rpm;
        let mut dvbe_r = dvbetr;
        if seuil <= 0.0 {
            dp = 0.0;
            line = false;
            slope = slope_m;
        } else {
            line = true;
            // R(p + Δp) + μ tr(b̄ₑᵗʳ) Δp = μ q: the small-strain return
            // with 3μ' = μ tr b̄ₑᵗʳ.
            let (d, h) = match &law.hardening {
                Hardening::Linear { h } => (seuil / (h + mu * trbetr), *h),
                Hardening::Curve { .. }
                | Hardening::NonLinear(_)
                | Hardening::JohnsonCook(_)
                | Hardening::Kinematic { .. } => {
                    law.return_increment(mu * eqbetr, pm, mu * trbetr / 3.0)?
                }
            };
            dp = d;
            slope = h;
            let s = 1.0 - dp * trbetr / eqbetr;
            for v in dvbe_r.iter_mut() {
                *v *= s;
            }
        }
        dvbe = dvbe_r;
        let trtau = troisk * (jp * jp - 1.0) / 2.0;
        for k in 0..6 {
            tau[k] = mu * dvbe[k] + trtau / 3.0 * KR[k];
        }
        // Elastic strain with the hydrostatic correction det bₑ = J².
        let mut ep = [0.0; 6];
        let j23 = jp.powf(2.0 / 3.0);
        for k in 0..6 {
            ep[k] = (KR[k] - j23 * (dvbe[k] + trbetr / 3.0 * KR[k])) / 2.0;
        }
        hydrostatic_correction(jp, &mut ep);
        state.p = pm + dp;
        state.plastic = line;
        for k in 0..6 {
            state.e[k] = ep[k] / RC[k];
        }
    } else {
        dp = 0.0;
        line = prev.plastic;
        dvbe = dvbetr;
        slope = slope_m;
    }
    let line = line && phase != (Phase::Prediction { elastic: true });

    // gdsmtg: ∂J/∂ΔF·ΔFᵀ = J I; ∂b̄ₑᵗʳ/∂ΔF·ΔFᵀ.
    let mut dbtrdf = [[[0.0; 3]; 3]; 6];
    for ij in 0..6 {
        let (i, j) = IND[ij];
        for l in 0..3 {
            let il = MANDEL[i][l];
            let jl = MANDEL[j][l];
            dbtrdf[ij][i][l] += RC[ij] * betr[jl] / RC[jl];
            dbtrdf[ij][j][l] += RC[ij] * betr[il] / RC[il];
            dbtrdf[ij][l][l] -= 2.0 / 3.0 * betr[ij];
        }
    }
    // lcpitg.
    let (a2, a3, a4) = if !line {
        (1.0, 0.0, 0.0)
    } else {
        let eqbe = (1.5 * dot6(&dvbe, &dvbe)).sqrt();
        let a2 = 1.0 / (1.0 + trbetr * dp / eqbe);
        let rb = slope;
        let mut a3 = (a2 * dp / eqbe) - mu / (rb + mu * trbetr);
        a3 = 3.0 * trbetr * a3 / (2.0 * eqbe * eqbe);
        let a4 = dp / eqbe * ((mu * trbetr / (rb + mu * trbetr)) - 1.0);
        (a2, a3, a4)
    };
    let mut dvbbtr = [[0.0; 6]; 6];
    for ij in 0..6 {
        for kl in 0..6 {
            let id = if ij == kl { 1.0 } else { 0.0 };
            dvbbtr[ij][kl] = a2 * (id - KR[ij] * KR[kl] / 3.0)
                + a3 * dvbe[ij] * dvbe[kl]
                + a4 * dvbe[ij] * KR[kl];
        }
    }
    let dtaudj = 0.5 * (2.0 * unk * jp);
    let mut dtau = [[[0.0; 3]; 3]; 6];
    for ij in 0..6 {
        for k in 0..3 {
            for l in 0..3 {
                let dvbedf: f64 = (0..6).map(|m| dvbbtr[ij][m] * dbtrdf[m][k][l]).sum();
                let djdf = if k == l { jp } else { 0.0 };
                // Rows back to tensor components (nmgpfi's 1/√2).
                dtau[ij][k][l] = (mu * dvbedf + dtaudj * KR[ij] * djdf) / RC[ij];
            }
        }
    }
    for k in 3..6 {
        tau[k] /= SQRT2;
    }
    Ok(SmOutput { tau, state, dtau })
}

/// code_aster's `gdsmhy`: the spherical part eₕ of e = eₕ I + dev e such
/// that det(I − 2e) = J², the root of the cubic nearest the current eₕ.
fn hydrostatic_correction(je: f64, e: &mut [f64; 6]) {
    let eh0 = (e[0] + e[1] + e[2]) / 3.0;
    let mut dve = *e;
    for k in 0..3 {
        dve[k] -= eh0;
    }
    let eqe2 = 1.5 * dot6(&dve, &dve);
    // det of the deviator (Mandel shears).
    let r2 = 1.0 / SQRT2;
    let detdve = dve[0] * dve[1] * dve[2] + r2 * dve[3] * dve[4] * dve[5]
        - (dve[2] * dve[3] * dve[3] + dve[1] * dve[4] * dve[4] + dve[0] * dve[5] * dve[5]) / 2.0;
    // x³ + p1 x + p0 = 0, eₕ = (x + 1)/2.
    let p0 = 8.0 * detdve + je * je;
    let p1 = -4.0 / 3.0 * eqe2;
    let roots = cubic_roots(p1, p0);
    let mut best = eh0;
    let mut dist = f64::INFINITY;
    for x in roots {
        let eh = (x + 1.0) / 2.0;
        if (eh - eh0).abs() < dist {
            dist = (eh - eh0).abs();
            best = eh;
        }
    }
    for k in 0..3 {
        e[k] = best + dve[k];
    }
}

/// Real roots of x³ + p x + q = 0 (code_aster's `zerop3` with no x² term).
fn cubic_roots(p: f64, q: f64) -> Vec<f64> {
    if p == 0.0 {
        return vec![-q.cbrt()];
    }
    let disc = (q / 2.0).powi(2) + (p / 3.0).powi(3);
    if disc > 0.0 {
        let s = disc.sqrt();
        let u = (-q / 2.0 + s).cbrt();
        let v = (-q / 2.0 - s).cbrt();
        vec![u + v]
    } else {
        // Three real roots (trigonometric form).
        let r = (-p / 3.0).sqrt();
        let cos = (-q / 2.0 / (r * r * r)).clamp(-1.0, 1.0);
        let phi = cos.acos();
        (0..3)
            .map(|k| 2.0 * r * ((phi + 2.0 * std::f64::consts::PI * k as f64) / 3.0).cos())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Elastic {
        Elastic::new(200e3, 0.3).unwrap()
    }

    /// Uniaxial stretch λ with the lateral stretch chosen so that τ is
    /// uniaxial: elastic, det bₑ = J², and the stress does not change
    /// under a superposed rotation (objectivity).
    #[test]
    fn elastic_response_is_objective_and_consistent() {
        let law = VonMises::linear(200e3, 1e12, 0.0).unwrap();
        let f = Matrix3::new(1.1, 0.2, 0.0, -0.05, 0.95, 0.1, 0.0, 0.03, 1.02);
        let out = integrate(
            &law,
            &steel(),
            &Matrix3::identity(),
            &f,
            &SmState::default(),
            Phase::Correction,
        )
        .unwrap();
        // Neo-Hookean-type check: τ = μ dev(b̄) + K/2 (J² − 1) I.
        let j = det3(&f);
        let b = f * f.transpose() * j.powf(-2.0 / 3.0);
        let mu = 200e3 / 2.6;
        let k = 200e3 / (3.0 * 0.4);
        let trb = b.trace();
        for (kk, &(i, jj)) in IND.iter().enumerate() {
            let dev = b[(i, jj)] - if i == jj { trb / 3.0 } else { 0.0 };
            let expect = mu * dev
                + if i == jj {
                    k / 2.0 * (j * j - 1.0)
                } else {
                    0.0
                };
            assert!((out.tau[kk] - expect).abs() < 1e-9 * mu, "{kk}");
        }
        // Rotation R: τ(RF) = R τ(F) Rᵀ.
        let (c, s) = (0.8f64, 0.6f64);
        let r = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let rot = integrate(
            &law,
            &steel(),
            &Matrix3::identity(),
            &(r * f),
            &SmState::default(),
            Phase::Correction,
        )
        .unwrap();
        let t = crate::strain::log::from_mandel(&{
            let mut m = out.tau;
            for v in m.iter_mut().skip(3) {
                *v *= SQRT2;
            }
            m
        });
        let tr = r * t * r.transpose();
        for (kk, &(i, jj)) in IND.iter().enumerate() {
            assert!((rot.tau[kk] - tr[(i, jj)]).abs() < 1e-9 * mu);
        }
        // The elastic strain gives det(I − 2e) = J².
        let e = out.state.e;
        let be = Matrix3::new(
            1.0 - 2.0 * e[0],
            -2.0 * e[3],
            -2.0 * e[4],
            -2.0 * e[3],
            1.0 - 2.0 * e[1],
            -2.0 * e[5],
            -2.0 * e[4],
            -2.0 * e[5],
            1.0 - 2.0 * e[2],
        );
        assert!((be.determinant() - j * j).abs() < 1e-12);
    }

    /// ∂τ/∂ΔF·ΔFᵀ against finite differences of τ, elastic and plastic.
    #[test]
    fn tangent_matches_finite_differences() {
        let el = steel();
        for law in [
            VonMises::linear(200e3, 300.0, 2e3).unwrap(),
            VonMises::traction(
                200e3,
                &[1.5e-3, 1e-2, 5e-2],
                &[300.0, 350.0, 420.0],
                super::super::CurveEnd::Linear,
            )
            .unwrap(),
        ] {
            let fm = Matrix3::new(1.01, 0.003, 0.0, 0.001, 0.995, 0.0, 0.0, 0.0, 0.998);
            let prev = SmState {
                p: 2e-3,
                plastic: true,
                e: [1e-3, -5e-4, -4e-4, 2e-4, 0.0, 0.0],
            };
            for df in [
                Matrix3::new(1.0005, 0.0002, 0.0, -0.0001, 0.9998, 0.0, 0.0, 0.0, 1.0001),
                Matrix3::new(1.02, 0.01, 0.003, -0.004, 0.99, 0.002, 0.001, 0.0, 0.995),
            ] {
                let out = integrate(&law, &el, &fm, &df, &prev, Phase::Correction).unwrap();
                let h = 1e-7;
                for k in 0..3 {
                    for l in 0..3 {
                        // δΔF = h eₖ⊗eₗ ΔF (a perturbation of the spatial
                        // gradient): τ' = τ + h dtau[·][k][l].
                        let mut e = Matrix3::zeros();
                        e[(k, l)] = h;
                        let dp = integrate(
                            &law,
                            &el,
                            &fm,
                            &((Matrix3::identity() + e) * df),
                            &prev,
                            Phase::Correction,
                        )
                        .unwrap();
                        let dm = integrate(
                            &law,
                            &el,
                            &fm,
                            &((Matrix3::identity() - e) * df),
                            &prev,
                            Phase::Correction,
                        )
                        .unwrap();
                        for ij in 0..6 {
                            let fd = (dp.tau[ij] - dm.tau[ij]) / (2.0 * h);
                            assert!(
                                (fd - out.dtau[ij][k][l]).abs() < 1e-4 * 200e3,
                                "dtau[{ij}][{k}][{l}] = {} vs {fd} (plastic {})",
                                out.dtau[ij][k][l],
                                out.state.plastic
                            );
                        }
                    }
                }
            }
        }
    }
}
