//! code_aster's message ids of the errors aster raises for the same cause
//! (what a program's `except CA.AsterError as err` reads as
//! `err.id_message`; `aster_eval::ExecError::id_message`).
//!
//! Only errors whose cause is the one code_aster names get an id:
//!
//! | id | code_aster | aster |
//! | --- | --- | --- |
//! | `MECANONLINE9_7` | `nmerro`: Newton reached `ITER_GLOB_MAXI` without converging, the step cutting (`DEFI_LIST_INST/ECHEC`) exhausted or absent (event `ITER_MAXI`) | [`FemError::NoConvergence`] with no status cycling, alone or as the last failure of [`FemError::StepCutting`] |
//! | `CONTACT_93` | `cfsans`: a `RESOLUTION='NON'` contact zone with `STOP_INTERP='OUI'` finds slave nodes interpenetrating beyond `TOLE_INTERP` at a converged step | [`FemError::Interpenetration`] |
//!
//! A Newton failure with contact or friction statuses still cycling is left
//! without an id: aster does not reproduce code_aster's treatment of the
//! cycling, so code_aster may converge there.

use aster_fem::FemError;

/// The code_aster message id of a numerical error, when its cause is the
/// one code_aster raises that message for.
pub(crate) fn fem_error_id(e: &FemError) -> Option<&'static str> {
    match e {
        FemError::NoConvergence { cycling: None, .. } => Some("MECANONLINE9_7"),
        FemError::StepCutting { cause, .. } => match **cause {
            FemError::NoConvergence { cycling: None, .. } => Some("MECANONLINE9_7"),
            _ => None,
        },
        FemError::Interpenetration { .. } => Some("CONTACT_93"),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_convergence(cycling: Option<&str>) -> FemError {
        FemError::NoConvergence {
            time: 1.0,
            iterations: 3,
            resi_rela: 1e-2,
            resi_maxi: 1.0,
            cycling: cycling.map(str::to_string),
        }
    }

    #[test]
    fn ids_of_the_causes_code_aster_names() {
        assert_eq!(fem_error_id(&no_convergence(None)), Some("MECANONLINE9_7"));
        assert_eq!(fem_error_id(&no_convergence(Some("contact"))), None);
        let cut = |cause: FemError| FemError::StepCutting {
            from: 0.0,
            to: 1.0,
            levels: 2,
            pieces: 4,
            smallest: 0.0625,
            limit: "SUBD_NIVEAU = 2 reached".to_string(),
            cause: Box::new(cause),
        };
        assert_eq!(
            fem_error_id(&cut(no_convergence(None))),
            Some("MECANONLINE9_7")
        );
        assert_eq!(fem_error_id(&cut(FemError::Integration("x".into()))), None);
        assert_eq!(
            fem_error_id(&FemError::Interpenetration {
                time: 2.0,
                nodes: 5
            }),
            Some("CONTACT_93")
        );
        assert_eq!(fem_error_id(&FemError::Model("x".into())), None);
    }
}
