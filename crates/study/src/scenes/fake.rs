//! A cheap synthetic scene that behaves like contact methods do, for
//! testing the engine, the CSV and the charts without any solver.
//!
//! Its "answer" is `1 + C·h² + penalty error`: discretisation error falls as
//! h², a penalty of coefficient ε lets the bodies penetrate by `1/ε` (scaled
//! by the stiffness ratio) and, past `ε·ratio > 1e12`, the system is taken as
//! numerically singular. GCP stops converging for stiffness ratios above
//! 1e4; LIAISON_UNIL is "unsupported". Every failure kind the engine knows
//! shows up somewhere in a small sweep. The work done (a dense loop) grows
//! as refine², so times are real and ordered.

use crate::error::StudyError;
use crate::method::MethodFamily;
use crate::outcome::{Failure, FailureKind, Measures};
use crate::scene::{Params, Scene};
use crate::spec::Point;
use std::collections::BTreeMap;

pub struct FakeScene {
    /// Iterations of busy work per refine² (tests keep it tiny).
    work: f64,
}

impl FakeScene {
    pub fn from_params(table: &BTreeMap<String, f64>) -> Result<FakeScene, StudyError> {
        let p = Params::new("fake", table, &["work"])?;
        Ok(FakeScene {
            work: p.positive("work", 1000.0)?,
        })
    }
}

impl Scene for FakeScene {
    fn quantity(&self) -> String {
        "synthetic value (1)".into()
    }

    fn describe(&self) -> String {
        "synthetic scene (engine tests): value 1 + h² + penetration".into()
    }

    fn run(&self, p: &Point) -> Result<Measures, Failure> {
        let h = 1.0 / p.refine as f64;
        let n = (self.work * (p.refine as f64).powi(2)) as usize;
        let mut acc = 0.0f64;
        for i in 0..n {
            acc += ((i as f64) * 1e-3).sin();
        }
        // Keeps the loop from being optimised away without changing values.
        let noise = if acc.is_nan() { 1.0 } else { 0.0 };
        let family = p.method.family();
        let coef = p.method.coefficient().unwrap_or(f64::INFINITY);
        let penetration = if family.is_exact() {
            0.0
        } else {
            p.stiffness_ratio / coef
        };
        let mut m = Measures {
            value: 1.0 + 0.3 * h * h + penetration + noise,
            reference: Some(1.0),
            own_reference: None,
            h,
            dofs: 2 * (p.refine as usize + 1).pow(2),
            newton_iterations: p.steps as usize * 2,
            contact_iterations: p.steps as usize * 3,
            solver_seconds: None,
            phases: None,
            penetration: Some(penetration),
            extras: vec![("busy".into(), acc)],
        };
        match family {
            MethodFamily::LiaisonUnil => Err(Failure::new(
                FailureKind::Unsupported,
                "LIAISON_UNIL is not in the fake scene",
            )),
            MethodFamily::DiscreteGcp if p.stiffness_ratio > 1e4 => Err(Failure::new(
                FailureKind::NoConvergence,
                format!(
                    "GCP: no convergence in 100 iterations at ratio {}",
                    p.stiffness_ratio
                ),
            )),
            _ if coef.is_finite() && coef * p.stiffness_ratio > 1e12 => Err(Failure::new(
                FailureKind::SingularMatrix,
                "penalty coefficient × stiffness ratio > 1e12: singular to working precision",
            )),
            _ if penetration > 0.01 => {
                m.newton_iterations += 1;
                Err(Failure::wrong(
                    FailureKind::Penetration,
                    format!("penetration {penetration:.3e} > 1e-2"),
                    m,
                ))
            }
            _ => Ok(m),
        }
    }
}
