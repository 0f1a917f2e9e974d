//! Errors of the numerical core. Every failure a user can provoke (a missing
//! support, a bad cell, a non-converging Newton…) is a value of [`FemError`]
//! whose message says what failed and, where possible, where.

use std::fmt;

/// An error of model building, assembly, solving or post-processing.
#[derive(Clone, Debug, PartialEq)]
pub enum FemError {
    /// The model or its data are inconsistent (bad cell type for an element,
    /// degenerate cell, missing material, unknown DOF…).
    Model(String),
    /// The assembled system is singular: the listed DOFs (e.g. `N3 DX`) are
    /// not held by anything.
    Singular { free_dofs: Vec<String> },
    /// The linear solve finished but its residual is poor (ill-conditioning).
    PoorSolve { relative_residual: f64 },
    /// Newton did not converge within the allowed iterations.
    NoConvergence {
        time: f64,
        iterations: usize,
        resi_rela: f64,
        resi_maxi: f64,
        /// The force sources whose statuses (contact open/closed, stick/
        /// slip) still changed at the last iteration: the likely cause.
        cycling: Option<String>,
    },
    /// The active-set iterations on unilateral conditions cycle or exceed
    /// their bound.
    ActiveSet { time: f64, message: String },
    /// An error raised by a unilateral source (e.g. contact pairing).
    Source(String),
    /// A unilateral source's own loop did not converge within its bound
    /// (contact's geometric loop at ITER_GEOM_MAXI): an increment failure,
    /// cut like a Newton failure (code_aster's event ERRE_CTCG).
    SourceLoop(String),
    /// The behaviour could not be integrated at a Gauss point of the
    /// iterate (a crushed or inverted element, a Jacobian increment out of
    /// bounds): code_aster's integration failure, which a smaller increment
    /// may avoid (step cutting applies).
    Integration(String),
    /// A contact zone that only checks (never enforces) contact found slave
    /// nodes interpenetrating the master surface beyond its tolerance at a
    /// converged increment, and asks the analysis to stop there (code_aster's
    /// `RESOLUTION='NON'` with `STOP_INTERP='OUI'`, `cfsans`). Not a failure
    /// a smaller increment avoids: never cut.
    Interpenetration {
        time: f64,
        /// How many slave nodes interpenetrate.
        nodes: usize,
    },
    /// An increment still failed once cut as far as `DEFI_LIST_INST/ECHEC`
    /// allows (`SUBD_NIVEAU` levels of `SUBD_PAS` pieces, or a piece below
    /// `SUBD_PAS_MINI`).
    StepCutting {
        /// The increment that failed (from, to).
        from: f64,
        to: f64,
        /// Levels of cutting done, pieces per cut, and the smallest piece.
        levels: usize,
        pieces: usize,
        smallest: f64,
        /// Why: `SUBD_NIVEAU` reached, or the next piece below `SUBD_PAS_MINI`.
        limit: String,
        /// The failure of the last piece tried.
        cause: Box<FemError>,
    },
    /// An increment failed where cutting it is known not to reproduce the
    /// reference (`StaticNonLinear::cut_refused`): the analysis stops
    /// instead of cutting, with the reason.
    CutNotReproduced {
        from: f64,
        to: f64,
        reason: String,
        cause: Box<FemError>,
    },
}

impl fmt::Display for FemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FemError::Model(m) => write!(f, "{m}"),
            FemError::Singular { free_dofs } if free_dofs.is_empty() => write!(
                f,
                "singular system: the factorisation found a zero pivot it cannot locate (a rigid-body mode, or redundant conditions: e.g. contact or friction multipliers on nodes that DDL_IMPO also holds — exclude them with SANS_GROUP_NO / SANS_GROUP_NO_FR)"
            ),
            FemError::Singular { free_dofs } => {
                const SHOWN: usize = 12;
                write!(
                    f,
                    "singular system: the model is not held; free degrees of freedom: "
                )?;
                let shown: Vec<&str> = free_dofs.iter().take(SHOWN).map(|s| s.as_str()).collect();
                write!(f, "{}", shown.join(", "))?;
                if free_dofs.len() > SHOWN {
                    write!(f, " and {} more", free_dofs.len() - SHOWN)?;
                }
                write!(
                    f,
                    " (add a DDL_IMPO / MECA_IMPO or a spring on these degrees of freedom)"
                )
            }
            FemError::PoorSolve { relative_residual } => write!(
                f,
                "linear solve inaccurate: relative residual {relative_residual:.3e} after refinement (system badly conditioned)"
            ),
            FemError::NoConvergence {
                time,
                iterations,
                resi_rela,
                resi_maxi,
                cycling,
            } => {
                write!(
                    f,
                    "Newton did not converge at time {time}: after {iterations} iterations RESI_GLOB_RELA = {resi_rela:.3e}, RESI_GLOB_MAXI = {resi_maxi:.3e}"
                )?;
                match cycling {
                    Some(who) => write!(
                        f,
                        "; the statuses or pairing of {who} still changed at the last iteration (contact open/closed or stick/slip cycling; code_aster's ADAPTATION treatment of cycling is not reproduced): cut the step (DEFI_LIST_INST), raise ITER_GLOB_MAXI, or raise COEF_CONT/COEF_FROT"
                    ),
                    None => write!(f, " (raise ITER_GLOB_MAXI or check the loading)"),
                }
            }
            FemError::ActiveSet { time, message } => {
                write!(f, "unilateral conditions at time {time}: {message}")
            }
            FemError::Source(m) | FemError::SourceLoop(m) => write!(f, "{m}"),
            FemError::Integration(m) => write!(f, "behaviour integration failed: {m}"),
            FemError::Interpenetration { time, nodes } => write!(
                f,
                "contact verification at time {time}: {nodes} slave node(s) interpenetrate the master surface by more than TOLE_INTERP, and STOP_INTERP='OUI' stops the analysis there"
            ),
            FemError::StepCutting {
                from,
                to,
                levels,
                pieces,
                smallest,
                limit,
                cause,
            } => write!(
                f,
                "the increment from t = {from} to t = {to} fails even cut {levels} time(s) in {pieces} pieces (smallest piece {smallest:e}; {limit}); last failure: {cause}"
            ),
            FemError::CutNotReproduced {
                from,
                to,
                reason,
                cause,
            } => write!(
                f,
                "not supported yet: the increment from t = {from} to t = {to} fails ({cause}) and is not cut: {reason}"
            ),
        }
    }
}

impl std::error::Error for FemError {}

#[cfg(test)]
mod tests {
    use super::FemError;

    #[test]
    fn no_convergence_names_cycling_statuses_and_their_remedy() {
        let e = |cycling: Option<&str>| FemError::NoConvergence {
            time: 1.0,
            iterations: 20,
            resi_rela: 0.5,
            resi_maxi: 3.0,
            cycling: cycling.map(str::to_string),
        };
        let plain = e(None).to_string();
        assert!(
            plain.ends_with("(raise ITER_GLOB_MAXI or check the loading)"),
            "{plain}"
        );
        let cyc = e(Some("contact with friction (A on B)")).to_string();
        assert!(
            cyc.contains("the statuses or pairing of contact with friction (A on B) still changed"),
            "{cyc}"
        );
        assert!(cyc.contains("raise COEF_CONT/COEF_FROT"), "{cyc}");
    }
}
