//! Errors of contact definition, pairing and resolution. They are values:
//! nothing in this crate panics on user input.

use std::fmt;

/// Everything that can go wrong in a contact computation.
#[derive(Clone, Debug, PartialEq)]
pub enum ContactError {
    /// A group named in a zone does not exist in the mesh.
    UnknownGroup {
        keyword: &'static str,
        name: String,
        suggestion: Option<String>,
    },
    /// A group exists but holds cells the zone cannot use (e.g. a volume
    /// cell in GROUP_MA_MAIT of a 2D problem).
    BadCell {
        keyword: &'static str,
        group: String,
        cell: String,
        found: &'static str,
        expected: &'static str,
    },
    /// A keyword value that code_aster accepts but this implementation does not.
    Unsupported { feature: String, hint: String },
    /// A keyword value that is wrong in itself.
    Invalid {
        keyword: &'static str,
        message: String,
    },
    /// A degree of freedom of a contact row is not carried by the model.
    MissingDof {
        node: String,
        component: &'static str,
    },
    /// The active set came back to a set it had already visited.
    Cycling { iterations: usize, points: usize },
    /// An iterative contact loop hit its limit.
    NotConverged {
        what: &'static str,
        iterations: usize,
        residual: f64,
    },
    /// The linear solver failed (singular system…).
    Solver(String),
    /// The contact rows are redundant: the Schur complement is singular.
    SingularContact { point: usize },
    /// No slave face of a Nitsche zone lies on a volume cell (code_aster's
    /// `MeshPairing::buildSlaveCellsVolu` map is empty: CONTACT1_3).
    SlaveWithoutVolume { zone: usize },
}

impl fmt::Display for ContactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ContactError::UnknownGroup {
                keyword,
                name,
                suggestion,
            } => {
                write!(f, "{keyword}: the mesh has no group '{name}'")?;
                if let Some(s) = suggestion {
                    write!(f, " (did you mean '{s}'?)")?;
                }
                Ok(())
            }
            ContactError::BadCell {
                keyword,
                group,
                cell,
                found,
                expected,
            } => write!(
                f,
                "{keyword}: cell {cell} of group '{group}' is a {found}; expected {expected}"
            ),
            ContactError::Unsupported { feature, hint } => {
                write!(f, "{feature} is not supported yet")?;
                if !hint.is_empty() {
                    write!(f, ": {hint}")?;
                }
                Ok(())
            }
            ContactError::Invalid { keyword, message } => write!(f, "{keyword}: {message}"),
            ContactError::MissingDof { node, component } => write!(
                f,
                "contact needs degree of freedom {component} of node {node}, which no element of the model carries"
            ),
            ContactError::Cycling { iterations, points } => write!(
                f,
                "contact active set is cycling after {iterations} iterations ({points} contact points): \
                 the same set of active points came back; try smaller load steps or ALGO_CONT='PENALISATION'"
            ),
            ContactError::NotConverged {
                what,
                iterations,
                residual,
            } => write!(
                f,
                "{what} did not converge in {iterations} iterations (residual {residual:.3e}); \
                 raise the iteration limit or refine the load steps"
            ),
            ContactError::Solver(m) => write!(f, "linear solve failed during contact: {m}"),
            ContactError::SingularContact { point } => write!(
                f,
                "contact point {point} is redundant with other active points (singular contact matrix); \
                 remove duplicated slave nodes with SANS_GROUP_NO or use ALGO_CONT='PENALISATION'"
            ),
            ContactError::SlaveWithoutVolume { zone } => write!(
                f,
                "GROUP_MA_ESCL: no slave cell of zone {zone} lies on a volume cell (its nodes are held by the cell itself only, or it is inserted inside the volume): the Nitsche method needs the cell under each contact cell; either the volume cells under the skin are missing or the skin group is inside a volume"
            ),
        }
    }
}

impl std::error::Error for ContactError {}

/// The closest name among `candidates`, if it is close enough to be a
/// plausible typo.
pub(crate) fn did_you_mean<'a>(
    name: &str,
    candidates: impl Iterator<Item = &'a str>,
) -> Option<String> {
    let upper = name.to_uppercase();
    candidates
        .map(|c| (strsim::jaro_winkler(&upper, &c.to_uppercase()), c))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c.to_string())
}
