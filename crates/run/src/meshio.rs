//! The bridge to the mesh crate: reading and skin orientation.

use aster_mesh::Mesh;
use std::path::Path;

pub fn read(path: &Path, format: &str) -> Result<Mesh, String> {
    let _ = (path, format);
    Err("mesh reading is not available in this build yet".into())
}

pub fn orient_skin(mesh: &mut Mesh, groups: &[String]) -> Result<(), String> {
    let _ = (mesh, groups);
    Err("skin orientation is not available in this build yet".into())
}
