//! Result fields to write with a mesh (IMPR_RESU): plain data the runner
//! fills in.

use crate::error::MeshError;
use crate::Mesh;
use std::borrow::Cow;

/// Where a field's values live.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldLocation {
    /// One value set per node (`DEPL`, `FORC_NODA`, `*_NOEU`).
    Nodes,
    /// One value set per cell (`*_ELEM`).
    Cells,
    /// Values at integration points (`SIEF_ELGA`…): `points_per_cell[i]`
    /// value sets for cell `i` (0 for cells the field does not cover).
    GaussPoints { points_per_cell: Vec<u32> },
}

/// A field: `values` hold, entity after entity (and point after point for
/// Gauss fields), one value per component.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub name: String,
    pub components: Vec<String>,
    pub location: FieldLocation,
    pub values: Vec<f64>,
}

/// The fields of one stored step of a result (NUME_ORDRE, INST).
#[derive(Debug, Clone, PartialEq)]
pub struct ResultStep {
    pub nume_ordre: i32,
    pub inst: f64,
    pub fields: Vec<Field>,
}

impl Field {
    pub fn nodal(name: &str, components: &[&str], values: Vec<f64>) -> Field {
        Field {
            name: name.into(),
            components: components.iter().map(|s| s.to_string()).collect(),
            location: FieldLocation::Nodes,
            values,
        }
    }

    pub fn per_cell(name: &str, components: &[&str], values: Vec<f64>) -> Field {
        Field {
            name: name.into(),
            components: components.iter().map(|s| s.to_string()).collect(),
            location: FieldLocation::Cells,
            values,
        }
    }

    pub fn gauss(
        name: &str,
        components: &[&str],
        points_per_cell: Vec<u32>,
        values: Vec<f64>,
    ) -> Field {
        Field {
            name: name.into(),
            components: components.iter().map(|s| s.to_string()).collect(),
            location: FieldLocation::GaussPoints { points_per_cell },
            values,
        }
    }

    /// Check the value count against the mesh.
    pub fn check(&self, mesh: &Mesh) -> Result<(), MeshError> {
        let nc = self.components.len();
        if nc == 0 {
            return Err(MeshError::Operation(format!(
                "field `{}` has no components",
                self.name
            )));
        }
        let expected = match &self.location {
            FieldLocation::Nodes => mesh.node_count() * nc,
            FieldLocation::Cells => mesh.cells.len() * nc,
            FieldLocation::GaussPoints { points_per_cell } => {
                if points_per_cell.len() != mesh.cells.len() {
                    return Err(MeshError::Operation(format!(
                        "field `{}`: {} Gauss point counts for {} cells",
                        self.name,
                        points_per_cell.len(),
                        mesh.cells.len()
                    )));
                }
                points_per_cell.iter().map(|&p| p as usize).sum::<usize>() * nc
            }
        };
        if self.values.len() != expected {
            return Err(MeshError::Operation(format!(
                "field `{}` has {} values where the mesh needs {expected}",
                self.name,
                self.values.len()
            )));
        }
        Ok(())
    }

    /// Per-cell values: Gauss values averaged over each cell's points
    /// (cells without points get 0). `None` for nodal fields.
    pub fn cell_values(&self) -> Option<Cow<'_, [f64]>> {
        let nc = self.components.len();
        match &self.location {
            FieldLocation::Nodes => None,
            FieldLocation::Cells => Some(Cow::Borrowed(&self.values)),
            FieldLocation::GaussPoints { points_per_cell } => {
                let mut out = Vec::with_capacity(points_per_cell.len() * nc);
                let mut k = 0;
                for &p in points_per_cell {
                    let p = p as usize;
                    for c in 0..nc {
                        let sum: f64 = (0..p).map(|g| self.values[k + g * nc + c]).sum();
                        out.push(if p > 0 { sum / p as f64 } else { 0.0 });
                    }
                    k += p * nc;
                }
                Some(Cow::Owned(out))
            }
        }
    }
}
