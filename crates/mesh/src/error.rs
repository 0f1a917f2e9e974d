//! Errors of mesh reading, writing and operations: values with messages
//! that say where, what was expected and, when it helps, what was meant.

use crate::hdf5::H5Error;
use std::fmt;
use std::path::PathBuf;

#[derive(Debug, Clone, PartialEq)]
pub enum MeshError {
    /// The file could not be opened or read.
    Io { path: PathBuf, message: String },
    /// The HDF5 container is not readable (not HDF5, truncated, corrupt…).
    Hdf5 { path: PathBuf, error: H5Error },
    /// The HDF5 file is readable but is not a MED mesh file as expected.
    Med { path: PathBuf, message: String },
    /// A syntax error in an ASTER `.mail` file.
    Mail {
        path: PathBuf,
        line: usize,
        col: usize,
        message: String,
    },
    /// A cell type the reader does not know.
    UnknownCellType {
        path: PathBuf,
        name: String,
        suggestion: Option<String>,
    },
    /// A file whose format cannot be told from its extension or content.
    UnknownFormat { path: PathBuf },
    /// A group name that is not in the mesh.
    UnknownGroup {
        kind: GroupKind,
        name: String,
        suggestion: Option<String>,
    },
    /// A node or cell name that is not in the mesh.
    UnknownName {
        kind: &'static str,
        name: String,
        suggestion: Option<String>,
    },
    /// An operation that cannot be done on this mesh (with the reason).
    Operation(String),
    /// A write failed.
    Write { path: PathBuf, message: String },
}

/// Which kind of group a name refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupKind {
    Cells,
    Nodes,
}

impl GroupKind {
    pub fn keyword(self) -> &'static str {
        match self {
            GroupKind::Cells => "GROUP_MA",
            GroupKind::Nodes => "GROUP_NO",
        }
    }
}

fn did_you_mean(s: &Option<String>) -> String {
    match s {
        Some(s) => format!("; did you mean `{s}`?"),
        None => String::new(),
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Io { path, message } => {
                write!(f, "{}: cannot read the mesh file: {message}", path.display())
            }
            MeshError::Hdf5 { path, error } => write!(
                f,
                "{}: cannot read as a MED file: {error}",
                path.display()
            ),
            MeshError::Med { path, message } => write!(f, "{}: {message}", path.display()),
            MeshError::Mail {
                path,
                line,
                col,
                message,
            } => write!(f, "{}:{line}:{col}: {message}", path.display()),
            MeshError::UnknownCellType {
                path,
                name,
                suggestion,
            } => write!(
                f,
                "{}: unknown cell type `{name}`{}",
                path.display(),
                did_you_mean(suggestion)
            ),
            MeshError::UnknownFormat { path } => write!(
                f,
                "{}: unknown mesh format: expected a MED file (.med, .mmed, .rmed: HDF5) or an ASTER text mesh (.mail, .mgib)",
                path.display()
            ),
            MeshError::UnknownGroup {
                kind,
                name,
                suggestion,
            } => write!(
                f,
                "no {} named `{name}` in the mesh{}",
                kind.keyword(),
                did_you_mean(suggestion)
            ),
            MeshError::UnknownName {
                kind,
                name,
                suggestion,
            } => write!(
                f,
                "no {kind} named `{name}` in the mesh{}",
                did_you_mean(suggestion)
            ),
            MeshError::Operation(m) => f.write_str(m),
            MeshError::Write { path, message } => {
                write!(f, "{}: cannot write: {message}", path.display())
            }
        }
    }
}

impl std::error::Error for MeshError {}

/// The closest candidate to `name` (Jaro-Winkler, case-insensitive), when close enough.
pub fn suggest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<String> {
    let upper = name.to_uppercase();
    candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(&upper, &c.to_uppercase()), c))
        .filter(|(score, _)| *score >= 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c.to_string())
}
