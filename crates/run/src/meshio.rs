//! The bridge to the mesh crate: reading and skin orientation.

use aster_mesh::Mesh;
use std::path::Path;

/// Reads a mesh; the format is told from the file itself (HDF5 signature,
/// extension), so `FORMAT=` only has to be consistent with it.
pub fn read(path: &Path, format: &str) -> Result<Mesh, String> {
    let detected = aster_mesh::detect_format(path).map_err(|e| e.to_string())?;
    let want = match format {
        "MED" => aster_mesh::MeshFormat::Med,
        _ => aster_mesh::MeshFormat::Mail,
    };
    if detected != want {
        return Err(format!(
            "FORMAT='{format}' but the file is {} (fix FORMAT or the mesh file)",
            match detected {
                aster_mesh::MeshFormat::Med => "a MED file",
                aster_mesh::MeshFormat::Mail => "an ASTER text mesh",
            }
        ));
    }
    aster_mesh::read_mesh(path).map_err(|e| e.to_string())
}

/// `ORIE_PEAU`: outward normals on the skin cells of the groups.
pub fn orient_skin(mesh: &mut Mesh, groups: &[String]) -> Result<(), String> {
    let names: Vec<&str> = groups.iter().map(String::as_str).collect();
    mesh.orient_skin(&names)
        .map(|_| ())
        .map_err(|e| e.to_string())
}
