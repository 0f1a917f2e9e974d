//! `aster mesh FILE [--json] [--to mail|med|vtu --out PATH]`.

use std::path::Path;

pub fn run(file: &Path, json: bool, to: Option<&str>, out: Option<&Path>) -> u8 {
    let mesh = match aster_mesh::read_mesh_noted(file) {
        Ok((m, warnings)) => {
            for w in warnings {
                eprintln!("warning: {}: {w}", file.display());
            }
            m
        }
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
        if let Err(e) = convert(&mesh, format, out) {
            eprintln!("error: {e}");
            return 2;
        }
    }
    if json {
        match serde_json::to_string(&mesh.summary()) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("error: {e}");
                return 2;
            }
        }
    } else if to.is_none() {
        print!("{}", mesh.info());
    }
    0
}

fn convert(mesh: &aster_mesh::Mesh, format: &str, out: &Path) -> Result<(), String> {
    let written = match format.to_ascii_lowercase().as_str() {
        "mail" | "aster" => aster_mesh::write_mail(out, mesh),
        "med" => {
            let name = out
                .file_stem()
                .and_then(|s| s.to_str())
                .filter(|s| !s.is_empty() && s.len() <= 64)
                .unwrap_or("MAIL");
            aster_mesh::write_med(out, mesh, name, &[])
        }
        "vtu" | "vtk" => aster_mesh::write_vtu(out, mesh, None),
        other => {
            return Err(format!(
                "unknown output format `{other}`: expected `mail`, `med` or `vtu`"
            ))
        }
    };
    written.map_err(|e| e.to_string())
}
