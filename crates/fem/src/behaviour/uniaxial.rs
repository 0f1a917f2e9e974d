//! Uniaxial plasticity with linear hardening: code_aster's `nm1dis`
//! (isotropic, `GRILLE_ISOT_LINE`) and `nm1dci` (kinematic,
//! `GRILLE_CINE_LINE`), called by `nmco1d` at each point of a
//! reinforcement grid (`te0431`), and the elastic `nmco1d` branch (ELAS
//! with a thermal strain).
//!
//! One stress σ along the bars, from the mechanical strain increment
//! Δε − Δεᵗʰ (`verift`: the thermal strain's increment α·(T⁺ − T⁻) over
//! the step). With E the Young's modulus of `ELAS`, ET = `D_SIGM_EPSI` and
//! SY of `ECRO_LINE` (0 when absent), H = E·ET/(E − ET):
//! - isotropic: σₑ = σ⁻ + E Δε, R = SY + H p⁻; elastic when |σₑ| ≤ R;
//!   else Δp = (|σₑ| − R)/(E + H), σ = σₑ / (1 + E Δp/(SY + H(p⁻ + Δp)))
//!   (= sign σₑ·(SY + H p)); VARI V1 = p, V2 the plasticity indicator;
//! - kinematic: ξ = σ⁻ + E Δε − X⁻; elastic when |ξ| ≤ SY (σ = σ⁻ + E Δε);
//!   else Δp = (|ξ| − SY)/(E + H), X = X⁻ + H Δp sign ξ, σ = X + SY sign ξ;
//!   VARI V1 = X (code_aster names it EPSPEQ), V2 the indicator.
//!
//! The tangent (`FULL_MECA`) is E at an elastic point, ET at a plastic one
//! (the exact derivative for a linear hardening); the prediction
//! (`RIGI_MECA_TANG`) is ET where the last increment was plastic (V2 = 1),
//! else E; `RIGI_MECA_ELAS` / `FULL_MECA_ELAS` always E. The two VARI
//! code_aster adds (V3, V4, "VIDE") are zero.

use crate::error::FemError;

/// Which hardening.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UniaxialHardening {
    /// No plasticity: `nmco1d`'s ELAS branch (σ = σ⁻ + E (Δε − Δεᵗʰ)).
    Elastic,
    /// `nm1dis`, linear isotropic.
    Isotropic,
    /// `nm1dci`, linear kinematic.
    Kinematic,
}

/// A uniaxial law: E, `ECRO_LINE`'s ET and SY, the dilatation
/// coefficient α.
#[derive(Clone, Debug, PartialEq)]
pub struct Uniaxial {
    pub hardening: UniaxialHardening,
    pub young: f64,
    /// `D_SIGM_EPSI` (unused by [`UniaxialHardening::Elastic`]).
    pub et: f64,
    /// `SY` (unused by [`UniaxialHardening::Elastic`]).
    pub sy: f64,
    /// `ELAS/ALPHA` (0 without one).
    pub alpha: f64,
}

/// The state of a point: the stress and code_aster's two VARI.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UniaxialState {
    pub sigma: f64,
    /// V1: p (isotropic) or the back stress X (kinematic).
    pub v1: f64,
    /// V2: whether the last increment was plastic.
    pub plastic: bool,
}

impl UniaxialState {
    /// VARI in code_aster's order (`nb_vari = 4`).
    pub fn vari(&self) -> [f64; 4] {
        [self.v1, if self.plastic { 1.0 } else { 0.0 }, 0.0, 0.0]
    }
}

impl Uniaxial {
    /// Checks the constants: E > 0, and ET < E for the plastic laws (the
    /// hardening modulus H = E·ET/(E − ET) is then finite); `nm1dci`
    /// refuses ET ≤ 0 (COMPOR1_53).
    pub fn check(&self) -> Result<(), String> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(format!(
                "the Young's modulus E = {} is not positive",
                self.young
            ));
        }
        if !self.alpha.is_finite() {
            return Err("ALPHA is not finite".into());
        }
        if self.hardening == UniaxialHardening::Elastic {
            return Ok(());
        }
        if !(self.et.is_finite() && self.sy.is_finite()) {
            return Err("ECRO_LINE's D_SIGM_EPSI and SY must be finite".into());
        }
        if self.et >= self.young {
            return Err(format!(
                "ECRO_LINE/D_SIGM_EPSI = {} is not below E = {}: the hardening modulus E·ET/(E − ET) is not finite",
                self.et, self.young
            ));
        }
        if self.hardening == UniaxialHardening::Kinematic && self.et <= 0.0 {
            return Err(format!(
                "GRILLE_CINE_LINE needs D_SIGM_EPSI > 0 (code_aster's COMPOR1_53), not {}",
                self.et
            ));
        }
        Ok(())
    }

    /// The hardening modulus H = E·ET/(E − ET).
    pub fn modulus(&self) -> f64 {
        self.young * self.et / (self.young - self.et)
    }

    /// `RAPH_MECA`/`FULL_MECA`: the state after the mechanical strain
    /// increment `deps` (the thermal one taken out) from `prev`, and the
    /// tangent dσ/dε (`elastic_tangent`: FULL_MECA_ELAS, always E).
    pub fn integrate(
        &self,
        prev: &UniaxialState,
        deps: f64,
        elastic_tangent: bool,
    ) -> Result<(UniaxialState, f64), FemError> {
        let e = self.young;
        let sige = prev.sigma + e * deps;
        let (next, et) = match self.hardening {
            UniaxialHardening::Elastic => (
                UniaxialState {
                    sigma: sige,
                    v1: 0.0,
                    plastic: false,
                },
                e,
            ),
            UniaxialHardening::Isotropic => {
                let h = self.modulus();
                let rm = h * prev.v1 + self.sy;
                if sige.abs() <= rm {
                    (
                        UniaxialState {
                            sigma: sige,
                            v1: prev.v1,
                            plastic: false,
                        },
                        e,
                    )
                } else {
                    let dp = (sige.abs() - rm) / (h + e);
                    let rp = self.sy + h * (prev.v1 + dp);
                    (
                        UniaxialState {
                            sigma: sige / (1.0 + e * dp / rp),
                            v1: prev.v1 + dp,
                            plastic: true,
                        },
                        self.et,
                    )
                }
            }
            UniaxialHardening::Kinematic => {
                let h = self.modulus();
                let xi = sige - prev.v1;
                if xi.abs() <= self.sy {
                    (
                        UniaxialState {
                            sigma: sige,
                            v1: prev.v1,
                            plastic: false,
                        },
                        e,
                    )
                } else {
                    let dp = (xi.abs() - self.sy) / (e + h);
                    let x = prev.v1 + h * dp * xi / xi.abs();
                    (
                        UniaxialState {
                            sigma: x + self.sy * xi / xi.abs(),
                            v1: x,
                            plastic: true,
                        },
                        self.et,
                    )
                }
            }
        };
        if !next.sigma.is_finite() {
            return Err(FemError::Model(
                "the uniaxial behaviour gave a non-finite stress".into(),
            ));
        }
        Ok((
            next,
            if elastic_tangent || !next.plastic {
                e
            } else {
                et
            },
        ))
    }

    /// `RIGI_MECA_TANG` at the converged state (`elastic`:
    /// RIGI_MECA_ELAS): ET where the last increment was plastic, else E.
    pub fn prediction_tangent(&self, state: &UniaxialState, elastic: bool) -> f64 {
        if elastic || !state.plastic || self.hardening == UniaxialHardening::Elastic {
            self.young
        } else {
            self.et
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(hardening: UniaxialHardening) -> Uniaxial {
        Uniaxial {
            hardening,
            young: 2e11,
            et: 2e10,
            sy: 2e8,
            alpha: 0.0,
        }
    }

    #[test]
    fn tension_beyond_yield_follows_sy_plus_h_times_plastic_strain() {
        for h in [UniaxialHardening::Isotropic, UniaxialHardening::Kinematic] {
            let l = law(h);
            let mut s = UniaxialState::default();
            // Three increments to ε = 3e-3: σ = SY + ET (ε − SY/E).
            for _ in 0..3 {
                s = l.integrate(&s, 1e-3, false).unwrap().0;
            }
            let expect = 2e8 + 2e10 * (3e-3 - 1e-3);
            assert!(
                (s.sigma - expect).abs() < 1e-6 * expect,
                "{h:?} {}",
                s.sigma
            );
            assert!(s.plastic);
            let hmod = l.modulus();
            let ep = (expect - 2e8) / hmod;
            match h {
                UniaxialHardening::Isotropic => assert!((s.v1 - ep).abs() < 1e-12),
                _ => assert!((s.v1 - hmod * ep).abs() < 1e-6 * hmod * ep),
            }
        }
    }

    #[test]
    fn unloading_is_elastic_and_reversal_shows_the_hardening_kind() {
        // Load to ε = 3e-3 (σ = 2.4e8), then reverse by Δε = −3e-3.
        for (h, expect) in [
            // Isotropic: the surface has grown to 2.4e8, reverse yield at
            // −2.4e8: the elastic range 4.8e8 covers Δε = 2.4e-3, then
            // 0.6e-3 plastic at ET: σ = −2.4e8 − 0.6e-3·ET... per
            // increment below.
            (
                UniaxialHardening::Isotropic,
                -2.4e8 - 2e10 * (3e-3 - 4.8e8 / 2e11),
            ),
            // Kinematic: X = 0.4e8, reverse yield at X − SY = −1.6e8 after
            // an elastic range of 2 SY = 4e8 (Δε = 2e-3); then 1e-3 at ET.
            (
                UniaxialHardening::Kinematic,
                -1.6e8 - 2e10 * (3e-3 - 4e8 / 2e11),
            ),
        ] {
            let l = law(h);
            let mut s = UniaxialState::default();
            s = l.integrate(&s, 3e-3, false).unwrap().0;
            // A small unloading stays elastic.
            let (u, t) = l.integrate(&s, -1e-4, false).unwrap();
            assert!(!u.plastic && t == 2e11);
            assert!((u.sigma - (s.sigma - 2e7)).abs() < 1e-3);
            let (r, t) = l.integrate(&s, -3e-3, false).unwrap();
            assert!(r.plastic && t == 2e10);
            // One increment returns on the line through the reverse yield
            // point of slope ET.
            assert!(
                (r.sigma - expect).abs() < 1e-6 * expect.abs(),
                "{h:?}: {} vs {expect}",
                r.sigma
            );
        }
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_stress() {
        for h in [
            UniaxialHardening::Elastic,
            UniaxialHardening::Isotropic,
            UniaxialHardening::Kinematic,
        ] {
            let l = law(h);
            let mut s = UniaxialState::default();
            s = l.integrate(&s, 1.5e-3, false).unwrap().0;
            for deps in [2e-4, -2e-4, -3e-3, 1e-3] {
                let (a, t) = l.integrate(&s, deps, false).unwrap();
                let d = 1e-9;
                let (b, _) = l.integrate(&s, deps + d, false).unwrap();
                let fd = (b.sigma - a.sigma) / d;
                assert!((fd - t).abs() < 1e-4 * l.young, "{h:?} {deps}: {fd} {t}");
            }
        }
    }

    #[test]
    fn constants_out_of_range_are_refused() {
        let mut l = law(UniaxialHardening::Isotropic);
        l.et = 2e11;
        assert!(l.check().is_err());
        let mut l = law(UniaxialHardening::Kinematic);
        l.et = 0.0;
        assert!(l.check().is_err());
        assert!(law(UniaxialHardening::Isotropic).check().is_ok());
    }
}
