//! What one run of a scene gives back: its measures, or why it failed.

use std::fmt;

/// What a converged run measured. Times are seconds; lengths and forces are
/// in the scene's units.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measures {
    /// The quantity compared with the reference (e.g. the peak pressure).
    pub value: f64,
    /// The analytic reference of `value` for this point, when there is one.
    pub reference: Option<f64>,
    /// A reference that holds whatever the spec's `reference` says: the run
    /// models another problem than the study's first method (LIAISON_UNIL
    /// on a rigid base where the contact runs have a deformable one).
    pub own_reference: Option<f64>,
    /// Characteristic mesh size near the contact.
    pub h: f64,
    /// Number of displacement unknowns.
    pub dofs: usize,
    /// Newton iterations summed over the load steps.
    pub newton_iterations: usize,
    /// Contact (active-set / fixed-point) iterations summed over the steps.
    pub contact_iterations: usize,
    /// CPU seconds spent in the linear solver (factorisation + solves with
    /// the factor), when the scene reports it.
    pub solver_seconds: Option<f64>,
    /// Where the run's CPU time went, when the scene reports it.
    pub phases: Option<Phases>,
    /// Largest penetration at convergence (≥ 0), in length units.
    pub penetration: Option<f64>,
    /// Other named values worth a CSV column (e.g. the contact half-width).
    pub extras: Vec<(String, f64)>,
}

/// Where a run's CPU time went, in seconds (see [`crate::clock`]). The
/// linear solver is `factorisation + solves`; every other phase is outside
/// it. The phases cover the whole run: their sum is the run's CPU time up
/// to the clock's resolution.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Phases {
    /// Mesh generation (for a built-in scene, what reading the mesh file is
    /// for a `.comm`).
    pub mesh: f64,
    /// Model: elements, DOF numbering, loads, contact zones resolved on the
    /// mesh.
    pub model: f64,
    /// Stiffness assembly: sparsity pattern and element matrices.
    pub assembly: f64,
    /// Restriction to the free DOFs, equilibration, ordering, symbolic and
    /// numeric sparse Cholesky.
    pub factorisation: f64,
    /// Solves with the factor: free solutions and the contact algorithm's
    /// columns K⁻¹aⱼ (with their iterative refinement).
    pub solves: f64,
    /// Pairing and linearised contact rows, at every geometric iteration.
    pub pairing: f64,
    /// The rest of the contact algorithm: Schur complements on the active
    /// set, multiplier updates, active-set bookkeeping.
    pub contact: f64,
    /// Post-processing: contact forces, penetration, the measured quantity.
    pub post: f64,
}

impl Phases {
    /// Names and values, in the order of the CSV columns.
    pub fn named(&self) -> [(&'static str, f64); 8] {
        [
            ("mesh", self.mesh),
            ("model", self.model),
            ("assembly", self.assembly),
            ("factorisation", self.factorisation),
            ("solves", self.solves),
            ("pairing", self.pairing),
            ("contact", self.contact),
            ("post", self.post),
        ]
    }

    /// Time in the linear solver: factorisation and solves.
    pub fn solver(&self) -> f64 {
        self.factorisation + self.solves
    }

    /// Sum of all phases.
    pub fn total(&self) -> f64 {
        self.named().iter().map(|p| p.1).sum()
    }
}

/// Why a run did not give a trustworthy answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum FailureKind {
    /// Newton (or the contact loop) did not converge.
    NoConvergence,
    /// The assembled system is singular.
    SingularMatrix,
    /// The linear solve is inaccurate (ill-conditioning).
    PoorSolve,
    /// The active set cycles between states.
    Cycling,
    /// Converged, but the bodies interpenetrate beyond the tolerance.
    Penetration,
    /// Converged, but contact was lost where it should hold.
    LostContact,
    /// Converged, but the measured value is off the reference beyond the
    /// study's tolerance.
    Inaccurate,
    /// The scene cannot run this method (e.g. not implemented yet).
    Unsupported,
    /// The run panicked (a bug in the numerics; recorded, not fatal).
    Panic,
    /// Anything else (model error, pairing error…).
    Other,
}

impl FailureKind {
    pub fn name(self) -> &'static str {
        match self {
            FailureKind::NoConvergence => "no-convergence",
            FailureKind::SingularMatrix => "singular-matrix",
            FailureKind::PoorSolve => "poor-solve",
            FailureKind::Cycling => "cycling",
            FailureKind::Penetration => "penetration",
            FailureKind::LostContact => "lost-contact",
            FailureKind::Inaccurate => "inaccurate",
            FailureKind::Unsupported => "unsupported",
            FailureKind::Panic => "panic",
            FailureKind::Other => "other",
        }
    }

    /// The status a failure of this kind gives its run.
    pub fn status(self) -> Status {
        match self {
            FailureKind::Penetration | FailureKind::LostContact | FailureKind::Inaccurate => {
                Status::Wrong
            }
            FailureKind::Unsupported => Status::Unsupported,
            _ => Status::Failed,
        }
    }
}

impl fmt::Display for FailureKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A failed run: its kind, a message saying what happened, and what it
/// measured when it got that far (a wrong answer still has a time).
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    pub kind: FailureKind,
    pub message: String,
    /// Boxed: failures are rare and `Measures` is large.
    pub measures: Option<Box<Measures>>,
}

impl Failure {
    pub fn new(kind: FailureKind, message: impl Into<String>) -> Failure {
        Failure {
            kind,
            message: message.into(),
            measures: None,
        }
    }

    /// A converged run whose answer is wrong (penetration, lost contact).
    pub fn wrong(kind: FailureKind, message: impl Into<String>, measures: Measures) -> Failure {
        Failure {
            kind,
            message: message.into(),
            measures: Some(Box::new(measures)),
        }
    }
}

/// The verdict on one run, the colour of its cell in the stability map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    /// Converged to an answer within the tolerances.
    Converged,
    /// Converged to a wrong answer (penetration, lost contact, inaccurate).
    Wrong,
    /// Did not converge (no convergence, singular, cycling, panic…).
    Failed,
    /// The scene cannot run this method.
    Unsupported,
}

impl Status {
    pub fn name(self) -> &'static str {
        match self {
            Status::Converged => "converged",
            Status::Wrong => "wrong",
            Status::Failed => "failed",
            Status::Unsupported => "unsupported",
        }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
