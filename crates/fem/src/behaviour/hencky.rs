//! Non-linear (Hencky) elasticity of von Mises type, small strains
//! (`ELAS_VMIS_LINE`, `ELAS_VMIS_TRAC`), as code_aster's `lcelnl`
//! (`lc0078`) computes it: a total law, the stress a function of the
//! current strain alone.
//!
//! With e the deviator of ε − ε_th and ε_eq = √(3/2 e:e), the point is
//! linear (σ = 3K ε_m 1 + 2μ e) while 2μ ε_eq < σ_y; beyond, p solves
//! 2μ ε_eq − 3μ p = R(p) on the hardening curve (ECRO_LINE's
//! R = SY + H p, H = E·ET/(E − ET), or the traction curve's, with
//! Young's modulus σ₁/ε₁ of the curve for ELAS_VMIS_TRAC) and
//! σ = 3K ε_m 1 + (R(p)/ε_eq) e. That is one radial return from the
//! virgin state on the total strain, so [`integrate`] is
//! [`super::vmis::integrate`] from `PointState::default()` whatever the
//! history: unloading follows the same curve back, no residual strain.
//!
//! The tangent is `lcelnl`'s: K 1⊗1 + g P + (2μR'/(3μ + R') − g)
//! (3/(2ε_eq²)) e⊗e with g = R/ε_eq, which is the consistent tangent of
//! that return. VARI has one variable, V1 = p where the point is
//! non-linear, 0 elsewhere (`EPSPEQ`). The prediction (RIGI_MECA_TANG)
//! is the tangent at the converged strain.

use super::vmis::{integrate as radial_return, Mat6, PointState, VonMises};
use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};

/// The state (stress, p in `p`, `plastic` where non-linear) and tangent
/// of the Hencky law `law` at the mechanical strain `eps` (the
/// hypothesis' components, engineering shears). Plane stress (C_PLAN) is
/// not handled here: code_aster solves its εzz by its own scalar search
/// (`nmcri1`), refused by the caller.
pub fn integrate(
    law: &VonMises,
    el: &Elastic,
    hyp: Hypothesis,
    eps: &[f64],
) -> Result<(PointState, Mat6), FemError> {
    if hyp == Hypothesis::PlaneStress {
        return Err(FemError::Model(
            "ELAS_VMIS_* in plane stress (C_PLAN) is not implemented".into(),
        ));
    }
    radial_return(law, el, hyp, eps, &PointState::default(), false, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::behaviour::vmis::CurveEnd;

    fn el() -> Elastic {
        Elastic::new(200_000.0, 0.3).unwrap()
    }

    /// A strain state beyond the elastic limit, loaded then unloaded to
    /// half: the stress is the same function of the strain both ways
    /// (the law has no memory), and zero at zero strain.
    #[test]
    fn unloading_returns_along_the_same_curve() {
        let law = VonMises::linear(200_000.0, 300.0, 20_000.0).unwrap();
        let e = [3e-3, -1e-3, -1e-3, 1e-3, 0.0, 0.0];
        let (s, _) = integrate(&law, &el(), Hypothesis::Solid3D, &e).unwrap();
        assert!(s.plastic && s.p > 0.0);
        let half: Vec<f64> = e.iter().map(|v| v / 2.0).collect();
        let (h, _) = integrate(&law, &el(), Hypothesis::Solid3D, &half).unwrap();
        let (z, _) = integrate(&law, &el(), Hypothesis::Solid3D, &[0.0; 6]).unwrap();
        assert!(z.stress.iter().all(|v| *v == 0.0) && z.p == 0.0 && !z.plastic);
        // The Hencky secant: dev σ = (R(p)/ε_eq) e, R = SY + H p.
        let h_mod = 200_000.0 * 20_000.0 / 180_000.0;
        let mu = 200_000.0 / 2.6;
        let m = (half[0] + half[1] + half[2]) / 3.0;
        let dev = [half[0] - m, half[1] - m, half[2] - m, half[3] / 2.0];
        let eq = (1.5
            * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2] + 2.0 * dev[3] * dev[3]))
            .sqrt();
        if 2.0 * mu * eq >= 300.0 {
            let p = (2.0 * mu * eq - 300.0) / (h_mod + 3.0 * mu);
            let g = (300.0 + h_mod * p) / eq;
            assert!((h.stress[3] - g * dev[3]).abs() < 1e-9 * g * dev[3].abs());
            assert!((h.p - p).abs() < 1e-15);
        } else {
            assert!(!h.plastic);
            assert!((h.stress[3] - 2.0 * mu * dev[3]).abs() < 1e-9);
        }
    }

    /// The tangent against central finite differences of the stress, on a
    /// traction curve (own modulus) in 3D and plane strain.
    #[test]
    fn tangent_matches_finite_differences() {
        let law = VonMises::traction_curve(
            &[0.0015, 0.4, 1.0],
            &[310.0, 600.0, 700.0],
            CurveEnd::Linear,
        )
        .unwrap();
        for (hyp, e) in [
            (
                Hypothesis::Solid3D,
                vec![4e-3, -1e-3, 5e-4, 2e-3, -1e-3, 7e-4],
            ),
            (Hypothesis::PlaneStrain, vec![3e-3, -2e-3, 0.0, 1.5e-3]),
        ] {
            let n = hyp.ncomp();
            let (s0, c) = integrate(&law, &el(), hyp, &e).unwrap();
            assert!(s0.plastic);
            for j in 0..n {
                let h = 1e-8;
                let mut ep = e.clone();
                let mut em = e.clone();
                ep[j] += h;
                em[j] -= h;
                let (sp, _) = integrate(&law, &el(), hyp, &ep).unwrap();
                let (sm, _) = integrate(&law, &el(), hyp, &em).unwrap();
                for i in 0..n {
                    let fd = (sp.stress[i] - sm.stress[i]) / (2.0 * h);
                    assert!(
                        (fd - c[i][j]).abs() < 1e-4 * 200_000.0,
                        "{hyp:?} C[{i}][{j}] = {} vs {fd}",
                        c[i][j]
                    );
                }
            }
        }
    }
}
