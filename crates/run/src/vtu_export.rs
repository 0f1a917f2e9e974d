//! `aster run --vtu DIR`: every result the program holds when it ends, all
//! its steps and fields (displacements, stresses, contact status
//! `CONT_NOEU`…), written for ParaView with no `IMPR_RESU` in the file:
//! `DIR/<RESULT>.pvd` and `DIR/<RESULT>_<NUME_ORDRE>.vtu` per step
//! (`aster_mesh::write_vtu_series`; Gauss-point fields averaged per cell).

use crate::executor::Executor;
use aster_mesh::ResultStep;
use std::path::{Path, PathBuf};

/// Writes the results; returns the files written. A result whose mesh was
/// destroyed (`DETRUIRE`) is left out.
pub(crate) fn write_results(ex: &Executor, dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("--vtu {}: cannot create: {e}", dir.display()))?;
    let mut written = Vec::new();
    let mut stems: Vec<String> = Vec::new();
    for (id, name, result) in ex.results() {
        let Ok(mesh) = ex.mesh_by_id(result.mesh) else {
            continue;
        };
        // A name given again (a Python loop) keeps each result apart.
        let stem = if stems.iter().any(|s| s == name) {
            format!("{name}_{id}")
        } else {
            name.to_string()
        };
        stems.push(stem.clone());
        let steps: Vec<ResultStep> = result
            .steps
            .iter()
            .map(|s| ResultStep {
                nume_ordre: s.nume_ordre as i32,
                inst: s.inst,
                fields: s
                    .fields
                    .iter()
                    // Fields without components (VARI_ELGA of ELAS) have nothing to show.
                    .filter(|(_, f)| !f.components().is_empty())
                    .map(|(n, f)| crate::output::to_mesh_field(n, f, &mesh))
                    .collect(),
            })
            .collect();
        let files = aster_mesh::write_vtu_series(dir, &stem, &mesh, &steps)
            .map_err(|e| format!("--vtu: result `{name}`: {e}"))?;
        written.extend(files);
    }
    Ok(written)
}
