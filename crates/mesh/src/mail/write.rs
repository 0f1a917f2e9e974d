//! Writing ASTER `.mail` text meshes.

use crate::error::MeshError;
use crate::Mesh;
use std::fmt::Write as _;
use std::path::Path;

/// Write `mesh` as an ASTER text mesh.
pub fn write_mail(path: &Path, mesh: &Mesh) -> Result<(), MeshError> {
    std::fs::write(path, mail_string(mesh)).map_err(|e| MeshError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// The `.mail` text of a mesh: coordinates in full precision (`{:e}`
/// round-trips every f64), one block per run of cells of the same type,
/// groups with `NOM=` headers, members eight to a line.
pub fn mail_string(mesh: &Mesh) -> String {
    let mut o = String::new();
    let dim = mesh.dim.clamp(1, 3) as usize;
    let _ = writeln!(o, "TITRE\nwritten by aster\nFINSF\n%");
    let _ = writeln!(o, "COOR_{dim}D");
    for (name, c) in mesh.node_names.iter().zip(&mesh.coords) {
        let _ = write!(o, "{name}");
        for x in &c[..dim] {
            let _ = write!(o, " {x:e}");
        }
        o.push('\n');
    }
    let _ = writeln!(o, "FINSF\n%");
    let mut i = 0;
    while i < mesh.cells.len() {
        let ty = mesh.cells[i].ty;
        let _ = writeln!(o, "{}", ty.name());
        while i < mesh.cells.len() && mesh.cells[i].ty == ty {
            let _ = write!(o, "{}", mesh.cell_names[i]);
            for n in &mesh.cells[i].nodes {
                let _ = write!(o, " {}", mesh.node_names[n.0 as usize]);
            }
            o.push('\n');
            i += 1;
        }
        let _ = writeln!(o, "FINSF\n%");
    }
    let mut group = |kind: &str, name: &str, members: Vec<&str>| {
        let _ = writeln!(o, "{kind} NOM={name}");
        for line in members.chunks(8) {
            let _ = writeln!(o, "{}", line.join(" "));
        }
        let _ = writeln!(o, "FINSF\n%");
    };
    for g in &mesh.groups_ma {
        group(
            "GROUP_MA",
            &g.name,
            g.members
                .iter()
                .map(|c| mesh.cell_names[c.0 as usize].as_str())
                .collect(),
        );
    }
    for g in &mesh.groups_no {
        group(
            "GROUP_NO",
            &g.name,
            g.members
                .iter()
                .map(|n| mesh.node_names[n.0 as usize].as_str())
                .collect(),
        );
    }
    let _ = writeln!(o, "FIN");
    o
}
