//! Speed against accuracy studies of contact methods.
//!
//! A study ([`spec::StudySpec`], read from TOML) names a [`scene::Scene`],
//! the contact methods to compare and the parameters to sweep. The
//! [`engine`] runs every point of the sweep, timing it and recording its
//! measures or the reason it failed (a failing run never aborts the study),
//! then resolves errors against the reference (analytic, or the finest run).
//! The results go to a CSV ([`csv_out`]), three charts ([`charts`]: the
//! error/time Pareto front, the convergence in mesh size, the stability
//! map) and a Markdown summary ([`summary`]).

pub mod charts;
pub mod clock;
pub mod csv_out;
pub mod engine;
pub mod error;
pub mod memory;
pub mod method;
pub mod outcome;
pub mod scene;
pub mod scenes;
pub mod spec;
pub mod stats;
pub mod summary;

pub use engine::{run_study, Progress, RunRecord, StudyResult};
pub use error::StudyError;
pub use method::{Method, MethodFamily};
pub use outcome::{Failure, FailureKind, Measures, Phases, Status};
pub use scene::{builtin_scene, Scene};
pub use spec::{Point, Reference, StudySpec};

use std::path::{Path, PathBuf};

/// Everything a study writes, as paths.
#[derive(Clone, Debug, PartialEq)]
pub struct Outputs {
    pub csv: PathBuf,
    pub charts: Vec<PathBuf>,
    pub summary: PathBuf,
}

/// Runs a study end to end: builds its scene, sweeps, writes the CSV, the
/// charts (SVG and PNG) and the summary into `out`, named after the study.
pub fn run_and_write(
    spec: &StudySpec,
    out: &Path,
    progress: Progress,
) -> Result<(StudyResult, Outputs), StudyError> {
    let scene = builtin_scene(&spec.scene, &spec.scene_params)?;
    let result = run_study(spec, scene.as_ref(), progress);
    std::fs::create_dir_all(out).map_err(|e| StudyError::io(out, e))?;
    let csv = out.join(format!("{}.csv", spec.name));
    csv_out::write_csv(&result, &csv)?;
    let charts = charts::write_all(&result, out)?;
    let summary = out.join(format!("{}-summary.md", spec.name));
    std::fs::write(&summary, summary::markdown(&result))
        .map_err(|e| StudyError::io(&summary, e))?;
    Ok((
        result,
        Outputs {
            csv,
            charts,
            summary,
        },
    ))
}
