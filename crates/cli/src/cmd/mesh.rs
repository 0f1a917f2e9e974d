//! `aster mesh FILE [--json] [--to mail|med|vtu --out PATH]`.
//!
//! On a MED result file (one written by `IMPR_RESU(FORMAT='MED')`) the
//! description also lists the fields and their steps, and `--to vtu` keeps
//! them: one `.vtu` per step and a `.pvd` collection for ParaView.

use aster_mesh::{FieldLocation, Mesh, MeshFormat, ResultStep};
use std::path::Path;

pub fn run(file: &Path, json: bool, to: Option<&str>, out: Option<&Path>) -> u8 {
    let (mesh, steps) = match read(file) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    if let Some(format) = to {
        let Some(out) = out else {
            eprintln!("error: --to {format} needs --out PATH");
            return 2;
        };
        if let Err(e) = convert(&mesh, &steps, format, out) {
            eprintln!("error: {e}");
            return 2;
        }
    }
    if json {
        let summary = Summary {
            mesh: mesh.summary(),
            fields: (!steps.is_empty()).then(|| fields_json(&steps)),
        };
        match serde_json::to_string(&summary) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("error: {e}");
                return 2;
            }
        }
    } else if to.is_none() {
        print!("{}", mesh.info());
        print!("{}", fields_text(&steps));
    }
    0
}

/// `--json`: the mesh summary, then (result files) each field and its steps.
#[derive(serde::Serialize)]
struct Summary {
    #[serde(flatten)]
    mesh: aster_mesh::MeshSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    fields: Option<serde_json::Value>,
}

/// The mesh and, for a MED file, the result steps it holds.
fn read(file: &Path) -> Result<(Mesh, Vec<ResultStep>), aster_mesh::MeshError> {
    if aster_mesh::detect_format(file)? == MeshFormat::Med {
        let (mesh, info) = aster_mesh::read_med_named(file, None)?;
        for w in &info.warnings {
            eprintln!("warning: {}: {w}", file.display());
        }
        let steps = aster_mesh::read_med_steps(file, &mesh, &info.mesh_name)?;
        return Ok((mesh, steps));
    }
    let (mesh, warnings) = aster_mesh::read_mesh_noted(file)?;
    for w in warnings {
        eprintln!("warning: {}: {w}", file.display());
    }
    Ok((mesh, Vec::new()))
}

/// Each field once, in the order first met: its location, components and
/// the (NUME_ORDRE, INST) of the steps that hold it.
/// A field: name, location, components, (NUME_ORDRE, INST) of its steps.
type FieldRow<'a> = (&'a str, &'static str, &'a [String], Vec<(i32, f64)>);

fn field_table(steps: &[ResultStep]) -> Vec<FieldRow<'_>> {
    let mut table: Vec<FieldRow<'_>> = Vec::new();
    for s in steps {
        for f in &s.fields {
            let at = match f.location {
                FieldLocation::Nodes => "nodes",
                FieldLocation::Cells => "cells",
                FieldLocation::GaussPoints { .. } => "points",
            };
            match table.iter_mut().find(|t| t.0 == f.name) {
                Some(t) => t.3.push((s.nume_ordre, s.inst)),
                None => table.push((&f.name, at, &f.components, vec![(s.nume_ordre, s.inst)])),
            }
        }
    }
    table
}

fn fields_text(steps: &[ResultStep]) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let table = field_table(steps);
    if table.is_empty() {
        return o;
    }
    let _ = writeln!(o, "fields: {}", table.len());
    for (name, at, comps, st) in &table {
        let insts: Vec<String> = st.iter().map(|(_, i)| format!("{i}")).collect();
        let _ = writeln!(
            o,
            "  {name} (on {at}; {}): {} step{}, NUME_ORDRE {}..{}, INST {}",
            comps.join(" "),
            st.len(),
            if st.len() == 1 { "" } else { "s" },
            st.first().map_or(0, |s| s.0),
            st.last().map_or(0, |s| s.0),
            insts.join(" ")
        );
    }
    o
}

fn fields_json(steps: &[ResultStep]) -> serde_json::Value {
    field_table(steps)
        .into_iter()
        .map(|(name, at, comps, st)| {
            serde_json::json!({
                "name": name,
                "location": at,
                "components": comps,
                "steps": st.iter().map(|(n, i)| serde_json::json!({"nume_ordre": n, "inst": i})).collect::<Vec<_>>(),
            })
        })
        .collect()
}

fn convert(mesh: &Mesh, steps: &[ResultStep], format: &str, out: &Path) -> Result<(), String> {
    let written = match format.to_ascii_lowercase().as_str() {
        "mail" | "aster" => aster_mesh::write_mail(out, mesh),
        "med" => {
            let name = out
                .file_stem()
                .and_then(|s| s.to_str())
                .filter(|s| !s.is_empty() && s.len() <= 64)
                .unwrap_or("MAIL");
            aster_mesh::write_med(out, mesh, name, steps)
        }
        "vtu" | "vtk" if steps.is_empty() => aster_mesh::write_vtu(out, mesh, None),
        "vtu" | "vtk" => {
            // Every step: `<stem>_<NUME_ORDRE>.vtu` beside OUT and `<stem>.pvd`.
            let dir = out.parent().filter(|d| !d.as_os_str().is_empty());
            let dir = dir.unwrap_or(Path::new("."));
            let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("result");
            aster_mesh::write_vtu_series(dir, stem, mesh, steps).map(|files| {
                for f in files {
                    eprintln!("wrote {}", f.display());
                }
            })
        }
        other => {
            return Err(format!(
                "unknown output format `{other}`: expected `mail`, `med` or `vtu`"
            ))
        }
    };
    written.map_err(|e| e.to_string())
}
