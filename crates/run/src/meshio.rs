//! The bridge to the mesh crate: reading and skin orientation.

use aster_mesh::Mesh;
use std::path::Path;

/// The format `LIRE_MAILLAGE` reads, whether it makes I-DEAS colour
/// groups, and the key the read meshes are cached under (the same file
/// read with and without colour groups is two meshes).
pub fn requested(kw: &aster_eval::Keywords) -> (String, bool, String) {
    let format = kw.str("FORMAT").unwrap_or("MED").to_string();
    let colour = format == "IDEAS" && kw.str("CREA_GROUP_COUL") == Some("OUI");
    let key = if colour {
        format!("{format}/CREA_GROUP_COUL")
    } else {
        format.clone()
    };
    (format, colour, key)
}

/// Reads a mesh in the format `LIRE_MAILLAGE(FORMAT=…)` names. MED and
/// ASTER files must be what they claim (the format is told from the file
/// itself); GMSH and GIBI files are converted to ASTER text as code_aster's
/// `PRE_GMSH`/`PRE_GIBI` do, then read. With the mesh, the reader's
/// warnings (MED entities of undefined families: their groups are missing).
/// `colour_groups`: I-DEAS's `CREA_GROUP_COUL='OUI'`.
pub fn read(path: &Path, format: &str, colour_groups: bool) -> Result<(Mesh, Vec<String>), String> {
    use aster_mesh::MeshFormat;
    let detected = aster_mesh::detect_format(path).map_err(|e| e.to_string())?;
    let want = match format {
        "MED" => MeshFormat::Med,
        "GMSH" => MeshFormat::Gmsh,
        "GIBI" => MeshFormat::Gibi,
        "IDEAS" => MeshFormat::Ideas,
        _ => MeshFormat::Mail,
    };
    if detected != want {
        return Err(format!(
            "FORMAT='{format}' but the file is {} (fix FORMAT or the mesh file)",
            match detected {
                MeshFormat::Med => "a MED file",
                MeshFormat::Mail => "an ASTER text mesh",
                MeshFormat::Gmsh => "a GMSH mesh",
                MeshFormat::Gibi => "a GIBI mesh",
                MeshFormat::Ideas => "an I-DEAS universal file",
            }
        ));
    }
    if want == MeshFormat::Ideas {
        return aster_mesh::read_ideas_with(path, colour_groups)
            .map(|m| (m, Vec::new()))
            .map_err(|e| e.to_string());
    }
    aster_mesh::read_mesh_noted(path).map_err(|e| e.to_string())
}

/// `PRE_GMSH`/`PRE_GIBI`/`PRE_IDEAS`: the ASTER text code_aster's
/// converter writes for a GMSH, GIBI or I-DEAS file.
pub fn convert(path: &Path, format: &str, colour_groups: bool) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let text = aster_syntax::decode(&bytes);
    match format {
        "GMSH" => aster_mesh::gmsh_to_mail(&text, path),
        "IDEAS" => aster_mesh::ideas_to_mail(&text, path, colour_groups),
        _ => aster_mesh::gibi_to_mail(&text, path),
    }
    .map_err(|e| e.to_string())
}

/// `ORIE_PEAU`: outward normals on the skin cells of the groups.
pub fn orient_skin(mesh: &mut Mesh, groups: &[String]) -> Result<(), String> {
    let names: Vec<&str> = groups.iter().map(String::as_str).collect();
    mesh.orient_skin(&names)
        .map(|_| ())
        .map_err(|e| e.to_string())
}
