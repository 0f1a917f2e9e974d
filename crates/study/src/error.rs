//! Errors that stop a study before or after its runs (a bad spec, an
//! unwritable output). A failing *run* is not an error: it is recorded.

use std::fmt;
use std::path::{Path, PathBuf};

#[derive(Debug)]
pub enum StudyError {
    /// The spec file could not be read.
    Read { path: PathBuf, message: String },
    /// The spec is not valid TOML or does not describe a study.
    Spec { path: PathBuf, message: String },
    /// An unknown scene name, with the known ones.
    UnknownScene {
        name: String,
        known: Vec<&'static str>,
        suggestion: Option<String>,
    },
    /// A scene parameter is missing, unknown or out of range.
    SceneParam(String),
    /// An output file could not be written.
    Write { path: PathBuf, message: String },
    /// A chart could not be drawn.
    Chart { path: PathBuf, message: String },
}

impl StudyError {
    pub fn io(path: &Path, e: std::io::Error) -> StudyError {
        StudyError::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    }
}

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StudyError::Read { path, message } => {
                write!(
                    f,
                    "{}: cannot read the study spec: {message}",
                    path.display()
                )
            }
            StudyError::Spec { path, message } => write!(f, "{}: {message}", path.display()),
            StudyError::UnknownScene {
                name,
                known,
                suggestion,
            } => {
                write!(f, "unknown scene `{name}`")?;
                if let Some(s) = suggestion {
                    write!(f, " (did you mean `{s}`?)")?;
                }
                write!(f, "; built-in scenes: {}", known.join(", "))
            }
            StudyError::SceneParam(m) => write!(f, "{m}"),
            StudyError::Write { path, message } => {
                write!(f, "{}: cannot write: {message}", path.display())
            }
            StudyError::Chart { path, message } => {
                write!(f, "{}: cannot draw the chart: {message}", path.display())
            }
        }
    }
}

impl std::error::Error for StudyError {}
