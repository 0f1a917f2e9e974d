//! Reading the result fields of a MED file (`CHA`), as code_aster's
//! `IMPR_RESU(FORMAT='MED')` and this crate's writer store them:
//!
//! - `CHA/<field>` {MAI: the mesh, NCO, NOM: 16 characters a component}
//! - `<dt><it>` {NDT: NUME_ORDRE, PDT: INST}
//! - `NOE` (one value set per node) or `MAI.<type>` / `NOE.<type>` (per
//!   cell of a MED type, NGA points each: Gauss points, element nodes)
//!   {PFL: the profile, `MED_NO_PROFILE_INTERNAL` for every entity}
//! - `<profile>` {NBR: entities, NGA: points per entity} / `CO`: the values
//!   "no interlace" (component after component, then entity, then point).
//!
//! A profile lists (1-based, `PROFILS/<name>/PFL`) the entities the values
//! are for; entities not covered get 0 for nodes and no points for cells.

use super::celltypes::from_med_name;
use crate::error::MeshError;
use crate::field::{Field, FieldLocation, ResultStep};
use crate::hdf5::{H5Error, H5File, Object};
use crate::Mesh;
use std::collections::BTreeMap;
use std::path::Path;

const NO_PROFILE: &str = "MED_NO_PROFILE_INTERNAL";

/// A step read with the nodes each of its nodal fields covers.
pub type StepCovered = (ResultStep, Vec<Option<Vec<bool>>>);

/// A field read with the nodes it covers (nodal fields).
type FieldCovered = (Field, Option<Vec<bool>>);

/// The steps of the fields stored on mesh `mesh_name` (read as `mesh`),
/// by increasing NUME_ORDRE, each with its fields in file order. Fields on
/// another mesh of the file are left out.
pub fn read_med_steps(
    path: &Path,
    mesh: &Mesh,
    mesh_name: &str,
) -> Result<Vec<ResultStep>, MeshError> {
    Ok(read_med_steps_covered(path, mesh, mesh_name)?
        .into_iter()
        .map(|(s, _)| s)
        .collect())
}

/// [`read_med_steps`] with, for each field of a step (in the same order),
/// the nodes a nodal field has values at (its profiles; `None` for a field
/// on cells).
pub fn read_med_steps_covered(
    path: &Path,
    mesh: &Mesh,
    mesh_name: &str,
) -> Result<Vec<StepCovered>, MeshError> {
    let data = std::fs::read(path).map_err(|e| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let h5 = |error: H5Error| MeshError::Hdf5 {
        path: path.to_path_buf(),
        error,
    };
    let file = H5File::from_bytes(data).map_err(h5)?;
    let r = FieldReader { file: &file, mesh };
    r.steps(mesh_name).map_err(|e| match e {
        Failure::H5(e) => h5(e),
        Failure::Med(message) => MeshError::Med {
            path: path.to_path_buf(),
            message,
        },
    })
}

enum Failure {
    H5(H5Error),
    Med(String),
}

impl From<H5Error> for Failure {
    fn from(e: H5Error) -> Self {
        Failure::H5(e)
    }
}

struct FieldReader<'a> {
    file: &'a H5File,
    mesh: &'a Mesh,
}

impl FieldReader<'_> {
    fn string(&self, obj: &Object, name: &str) -> Result<Option<String>, H5Error> {
        Ok(self.file.attribute(obj, name)?.and_then(|a| a.as_string()))
    }

    fn int(&self, obj: &Object, name: &str) -> Result<Option<i64>, H5Error> {
        Ok(self.file.attribute(obj, name)?.and_then(|a| a.as_i64()))
    }

    fn steps(&self, mesh_name: &str) -> Result<Vec<StepCovered>, Failure> {
        let Some(cha) = self.file.get("CHA")? else {
            return Ok(Vec::new());
        };
        // NUME_ORDRE → (INST, fields).
        #[allow(clippy::type_complexity)]
        let mut steps: BTreeMap<i64, (f64, Vec<Field>, Vec<Option<Vec<bool>>>)> = BTreeMap::new();
        for (name, addr) in self.file.links(&cha)? {
            let fobj = self.file.object_at(addr)?;
            if self.string(&fobj, "MAI")?.is_some_and(|m| m != mesh_name) {
                continue;
            }
            let nco = self.int(&fobj, "NCO")?.unwrap_or(0).max(0) as usize;
            let noms = self.string(&fobj, "NOM")?.unwrap_or_default();
            let components: Vec<String> = (0..nco)
                .map(|c| {
                    noms.get(c * 16..((c + 1) * 16).min(noms.len()))
                        .unwrap_or("")
                        .trim()
                        .to_string()
                })
                .collect();
            if nco == 0 {
                continue;
            }
            for (_, saddr) in self.file.links(&fobj)? {
                let sobj = self.file.object_at(saddr)?;
                if sobj.is_dataset() {
                    continue;
                }
                let nume = self.int(&sobj, "NDT")?.unwrap_or(0);
                let inst = self
                    .file
                    .attribute(&sobj, "PDT")?
                    .and_then(|a| a.as_f64())
                    .unwrap_or(0.0);
                if let Some((field, covered)) = self.field(&name, &components, &sobj)? {
                    let entry = steps.entry(nume).or_insert((inst, Vec::new(), Vec::new()));
                    entry.1.push(field);
                    entry.2.push(covered);
                }
            }
        }
        Ok(steps
            .into_iter()
            .map(|(nume, (inst, fields, covered))| {
                (
                    ResultStep {
                        nume_ordre: nume as i32,
                        inst,
                        fields,
                    },
                    covered,
                )
            })
            .collect())
    }

    /// The values of one support: (entity indices, 0-based, in the MED
    /// numbering of the support; points per entity; values no interlace).
    fn support(
        &self,
        sup: &Object,
        count: usize,
    ) -> Result<(Vec<usize>, usize, Vec<f64>), Failure> {
        let pfl = self
            .string(sup, "PFL")?
            .filter(|p| !p.is_empty())
            .unwrap_or_else(|| NO_PROFILE.to_string());
        let Some(pobj) = self.file.child(sup, &pfl)? else {
            return Err(Failure::Med(format!(
                "field support without its `{pfl}` values"
            )));
        };
        let nga = self.int(&pobj, "NGA")?.unwrap_or(1).max(1) as usize;
        let co = match self.file.child(&pobj, "CO")? {
            Some(o) => self.file.read(&o)?.to_f64()?,
            None => Vec::new(),
        };
        let ids: Vec<usize> = if pfl == NO_PROFILE {
            (0..count).collect()
        } else {
            let list = self
                .file
                .get(&format!("PROFILS/{pfl}"))?
                .and_then(|p| self.file.child(&p, "PFL").ok().flatten())
                .ok_or_else(|| Failure::Med(format!("profile `{pfl}` is not in `PROFILS`")))?;
            let raw = self.file.read(&list)?.to_i64()?;
            raw.iter()
                .map(|&i| {
                    usize::try_from(i - 1)
                        .ok()
                        .filter(|&i| i < count)
                        .ok_or_else(|| {
                            Failure::Med(format!(
                                "profile `{pfl}` names entity {i}, outside 1..{count}"
                            ))
                        })
                })
                .collect::<Result<_, _>>()?
        };
        Ok((ids, nga, co))
    }

    fn field(
        &self,
        name: &str,
        components: &[String],
        step: &Object,
    ) -> Result<Option<FieldCovered>, Failure> {
        let nc = components.len();
        let mut covered: Option<Vec<bool>> = None;
        let mesh = self.mesh;
        let bad = |what: &str, got: usize, want: usize| {
            Failure::Med(format!(
                "field `{name}` on {what}: {got} values where {want} were expected"
            ))
        };
        let mut nodal: Option<Vec<f64>> = None;
        // Per cell of the mesh: its points, each `nc` values.
        let mut per_cell: Vec<Vec<f64>> = vec![Vec::new(); mesh.cells.len()];
        let mut points: Vec<usize> = vec![0; mesh.cells.len()];
        let mut any_cell = false;
        for (sname, saddr) in self.file.links(step)? {
            let sobj = self.file.object_at(saddr)?;
            if sname == "NOE" {
                let (ids, _, co) = self.support(&sobj, mesh.node_count())?;
                if co.len() != ids.len() * nc {
                    return Err(bad("nodes", co.len(), ids.len() * nc));
                }
                let values = nodal.get_or_insert_with(|| vec![0.0; mesh.node_count() * nc]);
                let seen = covered.get_or_insert_with(|| vec![false; mesh.node_count()]);
                for &n in &ids {
                    seen[n] = true;
                }
                for c in 0..nc {
                    for (k, &n) in ids.iter().enumerate() {
                        values[n * nc + c] = co[c * ids.len() + k];
                    }
                }
                continue;
            }
            let Some(ty) = sname.split_once('.').and_then(|(_, t)| from_med_name(t)) else {
                continue; // faces/edges of a descending connectivity: not a cell of the mesh
            };
            let cells: Vec<usize> = (0..mesh.cells.len())
                .filter(|&i| mesh.cells[i].ty == ty)
                .collect();
            let (ids, nga, co) = self.support(&sobj, cells.len())?;
            let per = nga * nc;
            if co.len() != ids.len() * per {
                return Err(bad(&sname, co.len(), ids.len() * per));
            }
            any_cell = true;
            let n = ids.len();
            for (k, &local) in ids.iter().enumerate() {
                let cell = cells[local];
                points[cell] = nga;
                let mut set = vec![0.0; per];
                for g in 0..nga {
                    for c in 0..nc {
                        set[g * nc + c] = co[c * n * nga + k * nga + g];
                    }
                }
                per_cell[cell] = set;
            }
        }
        let nodes = nodal.is_some();
        let field = if let Some(values) = nodal {
            Field {
                name: name.to_string(),
                components: components.to_vec(),
                location: FieldLocation::Nodes,
                values,
            }
        } else if !any_cell {
            return Ok(None);
        } else if points.iter().all(|&p| p == 1) {
            Field {
                name: name.to_string(),
                components: components.to_vec(),
                location: FieldLocation::Cells,
                values: per_cell.concat(),
            }
        } else {
            Field {
                name: name.to_string(),
                components: components.to_vec(),
                location: FieldLocation::GaussPoints {
                    points_per_cell: points.iter().map(|&p| p as u32).collect(),
                },
                values: per_cell.concat(),
            }
        };
        Ok(Some((field, covered.filter(|_| nodes))))
    }
}
