//! The contact methods a study compares, with their coefficient.

use serde::Deserialize;
use std::fmt;

/// A family of methods: one series on the charts, one panel of the
/// stability map. Spelled in specs as kebab-case (`discrete-penalisation`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MethodFamily {
    /// `FORMULATION='DISCRETE', ALGO_CONT='CONTRAINTE'`: exact, active set.
    DiscreteContrainte,
    /// `FORMULATION='DISCRETE', ALGO_CONT='PENALISATION'` with `E_N`.
    DiscretePenalisation,
    /// `FORMULATION='DISCRETE', ALGO_CONT='GCP'`: projected conjugate gradient.
    DiscreteGcp,
    /// `FORMULATION='CONTINUE', ALGO_CONT='STANDARD'` with `COEF_CONT`.
    ContinuousStandard,
    /// `FORMULATION='CONTINUE', ALGO_CONT='PENALISATION'` with `COEF_PENA_CONT`.
    ContinuousPenalisation,
    /// `FORMULATION='LIAISON_UNIL', ALGO_CONT='CONTRAINTE'`: fixed
    /// node-wise rows Σ COEF_MULT·u ≤ COEF_IMPO (no pairing), exact.
    LiaisonUnil,
    /// `FORMULATION='LIAISON_UNIL', ALGO_CONT='PENALISATION'` with `COEF_PENA`.
    LiaisonUnilPenalisation,
    /// `FORMULATION='DISCRETE', FROTTEMENT='COULOMB'`: `ALGO_CONT` and
    /// `ALGO_FROT` `'PENALISATION'` (code_aster's only discrete friction),
    /// the tangential penalty `E_T` swept (`E_N` is the scene's).
    DiscreteFrictionPenalisation,
    /// `FORMULATION='CONTINUE', FROTTEMENT='COULOMB'`, `ALGO_FROT=
    /// 'STANDARD'` (augmented Lagrangian) with `COEF_FROT`.
    ContinuousFrictionStandard,
    /// `FORMULATION='CONTINUE', FROTTEMENT='COULOMB'`, `ALGO_FROT=
    /// 'PENALISATION'` with `COEF_PENA_FROT`.
    ContinuousFrictionPenalisation,
}

impl MethodFamily {
    pub const ALL: [MethodFamily; 10] = [
        MethodFamily::DiscreteContrainte,
        MethodFamily::DiscretePenalisation,
        MethodFamily::DiscreteGcp,
        MethodFamily::ContinuousStandard,
        MethodFamily::ContinuousPenalisation,
        MethodFamily::LiaisonUnil,
        MethodFamily::LiaisonUnilPenalisation,
        MethodFamily::DiscreteFrictionPenalisation,
        MethodFamily::ContinuousFrictionStandard,
        MethodFamily::ContinuousFrictionPenalisation,
    ];

    /// The code_aster spelling, e.g. `DISCRETE/PENALISATION`.
    pub fn name(self) -> &'static str {
        match self {
            MethodFamily::DiscreteContrainte => "DISCRETE/CONTRAINTE",
            MethodFamily::DiscretePenalisation => "DISCRETE/PENALISATION",
            MethodFamily::DiscreteGcp => "DISCRETE/GCP",
            MethodFamily::ContinuousStandard => "CONTINUE/STANDARD",
            MethodFamily::ContinuousPenalisation => "CONTINUE/PENALISATION",
            MethodFamily::LiaisonUnil => "LIAISON_UNIL/CONTRAINTE",
            MethodFamily::LiaisonUnilPenalisation => "LIAISON_UNIL/PENALISATION",
            MethodFamily::DiscreteFrictionPenalisation => "DISCRETE/COULOMB PENALISATION",
            MethodFamily::ContinuousFrictionStandard => "CONTINUE/COULOMB STANDARD",
            MethodFamily::ContinuousFrictionPenalisation => "CONTINUE/COULOMB PENALISATION",
        }
    }

    /// The kebab-case spelling used in spec files.
    pub fn spec_name(self) -> &'static str {
        match self {
            MethodFamily::DiscreteContrainte => "discrete-contrainte",
            MethodFamily::DiscretePenalisation => "discrete-penalisation",
            MethodFamily::DiscreteGcp => "discrete-gcp",
            MethodFamily::ContinuousStandard => "continuous-standard",
            MethodFamily::ContinuousPenalisation => "continuous-penalisation",
            MethodFamily::LiaisonUnil => "liaison-unil",
            MethodFamily::LiaisonUnilPenalisation => "liaison-unil-penalisation",
            MethodFamily::DiscreteFrictionPenalisation => "discrete-friction-penalisation",
            MethodFamily::ContinuousFrictionStandard => "continuous-friction-standard",
            MethodFamily::ContinuousFrictionPenalisation => "continuous-friction-penalisation",
        }
    }

    /// The keyword of the swept coefficient, when the family has one.
    pub fn coefficient_name(self) -> Option<&'static str> {
        match self {
            MethodFamily::DiscretePenalisation => Some("E_N"),
            MethodFamily::ContinuousStandard => Some("COEF_CONT"),
            MethodFamily::ContinuousPenalisation => Some("COEF_PENA_CONT"),
            MethodFamily::LiaisonUnilPenalisation => Some("COEF_PENA"),
            MethodFamily::DiscreteFrictionPenalisation => Some("E_T"),
            MethodFamily::ContinuousFrictionStandard => Some("COEF_FROT"),
            MethodFamily::ContinuousFrictionPenalisation => Some("COEF_PENA_FROT"),
            _ => None,
        }
    }

    /// code_aster's default coefficient (used when a spec gives none).
    pub fn default_coefficient(self) -> Option<f64> {
        match self {
            MethodFamily::ContinuousStandard | MethodFamily::ContinuousFrictionStandard => {
                Some(100.0)
            }
            // No default in code_aster: E_N, E_T, COEF_PENA_CONT,
            // COEF_PENA_FROT and COEF_PENA are mandatory.
            _ => None,
        }
    }

    /// Whether the method enforces the contact condition exactly (no
    /// penetration allowed at convergence beyond round-off).
    pub fn is_exact(self) -> bool {
        !matches!(
            self,
            MethodFamily::DiscretePenalisation
                | MethodFamily::ContinuousPenalisation
                | MethodFamily::LiaisonUnilPenalisation
                // code_aster's discrete friction penalises the normal
                // contact too (ALGO_CONT='PENALISATION').
                | MethodFamily::DiscreteFrictionPenalisation
        )
    }

    /// Whether the method carries Coulomb friction (`FROTTEMENT='COULOMB'`):
    /// it runs on frictional scenes only, and they on it only.
    pub fn is_frictional(self) -> bool {
        matches!(
            self,
            MethodFamily::DiscreteFrictionPenalisation
                | MethodFamily::ContinuousFrictionStandard
                | MethodFamily::ContinuousFrictionPenalisation
        )
    }

    /// Whether the method is `LIAISON_UNIL` (fixed rows built by the scene,
    /// no pairing) rather than `DEFI_CONTACT` contact.
    pub fn is_unilateral(self) -> bool {
        matches!(
            self,
            MethodFamily::LiaisonUnil | MethodFamily::LiaisonUnilPenalisation
        )
    }
}

impl fmt::Display for MethodFamily {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One method with its coefficient fixed. Made by [`Method::new`], which
/// refuses a coefficient on a family without one and a missing mandatory one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    family: MethodFamily,
    coefficient: Option<f64>,
}

impl Method {
    pub fn new(family: MethodFamily, coefficient: Option<f64>) -> Result<Method, String> {
        match (family.coefficient_name(), coefficient) {
            (None, Some(_)) => Err(format!("{} takes no coefficient", family.spec_name())),
            (Some(name), None) => match family.default_coefficient() {
                Some(c) => Ok(Method {
                    family,
                    coefficient: Some(c),
                }),
                None => Err(format!(
                    "{} needs its coefficient {name}: give `coefficients = [...]`",
                    family.spec_name()
                )),
            },
            (Some(name), Some(c)) if !(c.is_finite() && c > 0.0) => Err(format!(
                "{name} = {c} for {}: must be a positive number",
                family.spec_name()
            )),
            (_, c) => Ok(Method {
                family,
                coefficient: c,
            }),
        }
    }

    pub fn family(&self) -> MethodFamily {
        self.family
    }

    pub fn coefficient(&self) -> Option<f64> {
        self.coefficient
    }

    /// A short label, e.g. `DISCRETE/PENALISATION E_N=1e6`.
    pub fn label(&self) -> String {
        match (self.family.coefficient_name(), self.coefficient) {
            (Some(name), Some(c)) => format!("{} {name}={}", self.family.name(), short_number(c)),
            _ => self.family.name().to_string(),
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.label())
    }
}

/// `1e6`, `100`, `0.5`, `2.5e-3`: compact, exact enough for labels.
pub fn short_number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let exp = x.abs().log10().floor() as i32;
    if (-2..=3).contains(&exp) {
        let s = format!("{x:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        let mantissa = x / 10f64.powi(exp);
        if (mantissa - mantissa.round()).abs() < 1e-9 && mantissa.round() == 1.0 {
            format!("1e{exp}")
        } else if (mantissa - mantissa.round()).abs() < 1e-9 {
            format!("{}e{exp}", mantissa.round())
        } else {
            format!("{mantissa:.2}e{exp}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_carry_the_coefficient() {
        let m = Method::new(MethodFamily::DiscretePenalisation, Some(1e6)).unwrap();
        assert_eq!(m.label(), "DISCRETE/PENALISATION E_N=1e6");
        let s = Method::new(MethodFamily::ContinuousStandard, None).unwrap();
        assert_eq!(s.coefficient(), Some(100.0));
        assert_eq!(s.label(), "CONTINUE/STANDARD COEF_CONT=100");
    }

    #[test]
    fn liaison_unil_has_an_exact_and_a_penalised_variant() {
        let exact = Method::new(MethodFamily::LiaisonUnil, None).unwrap();
        assert_eq!(exact.label(), "LIAISON_UNIL/CONTRAINTE");
        assert!(exact.family().is_exact() && exact.family().is_unilateral());
        assert!(Method::new(MethodFamily::LiaisonUnil, Some(1e6)).is_err());
        let e = Method::new(MethodFamily::LiaisonUnilPenalisation, None).unwrap_err();
        assert!(e.contains("COEF_PENA"), "{e}");
        let pen = Method::new(MethodFamily::LiaisonUnilPenalisation, Some(1e6)).unwrap();
        assert_eq!(pen.label(), "LIAISON_UNIL/PENALISATION COEF_PENA=1e6");
        assert!(!pen.family().is_exact());
    }

    #[test]
    fn coefficients_are_checked() {
        assert!(Method::new(MethodFamily::DiscreteContrainte, Some(1.0)).is_err());
        let e = Method::new(MethodFamily::DiscretePenalisation, None).unwrap_err();
        assert!(e.contains("E_N"), "{e}");
        assert!(Method::new(MethodFamily::ContinuousPenalisation, Some(-1.0)).is_err());
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short_number(1e6), "1e6");
        assert_eq!(short_number(2e-5), "2e-5");
        assert_eq!(short_number(100.0), "100");
        assert_eq!(short_number(0.5), "0.5");
        assert_eq!(short_number(2.5e7), "2.50e7");
    }
}
