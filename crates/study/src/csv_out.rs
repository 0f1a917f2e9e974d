//! The CSV of every run: one row per point, failures included.

use crate::engine::{RunRecord, StudyResult};
use crate::error::StudyError;
use std::path::Path;

/// The CSV's columns, in order.
pub const COLUMNS: [&str; 34] = [
    "run",
    "scene",
    "method",
    "family",
    "coefficient",
    "refine",
    "h",
    "stiffness_ratio",
    "steps",
    "coulomb",
    "status",
    "failure",
    "reason",
    "value",
    "reference",
    "error",
    "wall_s",
    "cpu_s",
    "solver_s",
    "outside_solver_fraction",
    "mesh_s",
    "model_s",
    "assembly_s",
    "factorisation_s",
    "solves_s",
    "pairing_s",
    "contact_s",
    "post_s",
    "newton_iterations",
    "contact_iterations",
    "dofs",
    "penetration",
    "peak_rss_kib",
    "extras",
];

pub fn write_csv(result: &StudyResult, path: &Path) -> Result<(), StudyError> {
    let mut w = csv::Writer::from_path(path).map_err(|e| csv_error(path, e))?;
    w.write_record(COLUMNS).map_err(|e| csv_error(path, e))?;
    for r in &result.records {
        w.write_record(row(&result.spec.scene, r))
            .map_err(|e| csv_error(path, e))?;
    }
    w.flush().map_err(|e| StudyError::io(path, e))
}

fn csv_error(path: &Path, e: csv::Error) -> StudyError {
    StudyError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map(|v| v.to_string()).unwrap_or_default()
}

fn row(scene: &str, r: &RunRecord) -> Vec<String> {
    let p = &r.point;
    let m = r.measures.as_ref();
    let mut out = vec![
        p.index.to_string(),
        scene.to_string(),
        p.method.label(),
        p.method.family().spec_name().to_string(),
        opt(p.method.coefficient()),
        p.refine.to_string(),
        opt(m.map(|m| m.h)),
        p.stiffness_ratio.to_string(),
        p.steps.to_string(),
        p.coulomb.to_string(),
        r.status.name().to_string(),
        opt(r.kind.map(|k| k.name())),
        r.reason.clone().unwrap_or_default(),
        opt(m.map(|m| m.value)),
        opt(r.reference),
        opt(r.error),
        format!("{:.6}", r.wall_seconds),
        format!("{:.6}", r.cpu_seconds),
        opt(m.and_then(|m| m.solver_seconds).map(|s| format!("{s:.6}"))),
        opt(r.outside_solver_fraction().map(|f| format!("{f:.4}"))),
    ];
    let phases = m.and_then(|m| m.phases);
    for i in 0..8 {
        out.push(opt(phases.map(|p| format!("{:.6}", p.named()[i].1))));
    }
    out.extend([
        opt(m.map(|m| m.newton_iterations)),
        opt(m.map(|m| m.contact_iterations)),
        opt(m.map(|m| m.dofs)),
        opt(m.and_then(|m| m.penetration)),
        opt(r.peak_rss_kib),
        m.map(|m| {
            m.extras
                .iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect::<Vec<_>>()
                .join(";")
        })
        .unwrap_or_default(),
    ]);
    out
}
