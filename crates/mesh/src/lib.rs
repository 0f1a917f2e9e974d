//! Meshes as code_aster sees them: nodes, cells with code_aster type names
//! and node ordering, and named groups of cells (GROUP_MA) and nodes
//! (GROUP_NO).
//!
//! Reading: [`read_mesh`] (by extension, then by content), [`read_med`],
//! [`read_mail`].

pub mod convert;
mod error;
mod export;
mod field;
pub mod hdf5;
pub mod lac;
mod lac3d;
pub mod mail;
pub mod med;
mod model;
mod ops;
mod summary;
pub mod vec3;
pub mod vtu;

pub use convert::{
    gibi_to_mail, gmsh_to_mail, ideas_to_mail, read_gibi, read_gmsh, read_ideas, read_ideas_with,
};
pub use error::{suggest, GroupKind, MeshError};
pub use export::{read_export, read_mesh_as, unit_path, ExportFile};
pub use field::{Field, FieldLocation, ResultStep};
pub use lac::{decoupe_lac, decoupe_lac_with, LacOptions, LacPatch, LacPatches, LacZonePatches};
pub use lac3d::{DecoupeHexa, LinearCells, ReferenceCells};
pub use mail::{mail_string, parse_mail, read_mail, write_mail};
pub use med::{
    med_bytes, med_bytes_on, read_med, read_med_named, read_med_steps, read_med_steps_covered,
    write_med, write_med_on, Entities, MedInfo,
};
pub use model::*;
pub use ops::{
    positional_name, Along, CellFilter, CentreNodes, CrackFront, CrackReport, DegreeReport,
    NodeKind, OrientReport, Restriction,
};
pub use summary::{CellCounts, MeshSummary};
pub use vtu::{write_vtu, write_vtu_series};

use std::path::Path;

/// The formats a mesh file may have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// MED (HDF5 container).
    Med,
    /// ASTER text mesh.
    Mail,
    /// GMSH `.msh` (read as code_aster's `PRE_GMSH` converts it).
    Gmsh,
    /// GIBI / Cast3M `.mgib` (read as code_aster's `PRE_GIBI` converts it).
    Gibi,
    /// I-DEAS universal file `.unv` (read as code_aster's `PRE_IDEAS`
    /// converts it).
    Ideas,
}

/// Tell a mesh file's format: by the HDF5 signature first, then by extension.
pub fn detect_format(path: &Path) -> Result<MeshFormat, MeshError> {
    let io = |e: std::io::Error| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let mut head = [0u8; 256];
    let n = {
        use std::io::Read;
        let mut f = std::fs::File::open(path).map_err(io)?;
        f.read(&mut head).map_err(io)?
    };
    if n >= 8 && head[..8] == [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'] {
        return Ok(MeshFormat::Med);
    }
    // Text formats by their first word.
    let start = String::from_utf8_lossy(&head[..n]);
    let first_word = start.split_whitespace().next().unwrap_or("");
    if first_word.starts_with("$MeshFormat") || first_word == "$NOD" {
        return Ok(MeshFormat::Gmsh);
    }
    if first_word == "ENREGISTREMENT" {
        return Ok(MeshFormat::Gibi);
    }
    // I-DEAS: a first line `    -1`, then a dataset number.
    let mut first_lines = start.lines().filter(|l| !l.trim().is_empty());
    if first_lines.next().map(str::trim) == Some("-1")
        && first_lines
            .next()
            .and_then(|l| l.split_whitespace().next())
            .is_some_and(|w| w.parse::<u32>().is_ok())
    {
        return Ok(MeshFormat::Ideas);
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("med" | "mmed" | "rmed") => Ok(MeshFormat::Med),
        Some("msh") => Ok(MeshFormat::Gmsh),
        Some("mgib" | "gibi") => Ok(MeshFormat::Gibi),
        Some("unv" | "msup") => Ok(MeshFormat::Ideas),
        Some("mail" | "txt") => Ok(MeshFormat::Mail),
        _ => {
            let text = std::fs::read(path).map_err(io)?;
            let looks_like_mail = text.is_ascii()
                && String::from_utf8_lossy(&text)
                    .split_whitespace()
                    .any(|w| w == "FINSF");
            if looks_like_mail {
                Ok(MeshFormat::Mail)
            } else {
                Err(MeshError::UnknownFormat {
                    path: path.to_path_buf(),
                })
            }
        }
    }
}

/// Read a mesh file as [`read_mesh`] does, with the warnings of what was
/// read but could not be used (MED nodes or cells of undefined families).
pub fn read_mesh_noted(path: &Path) -> Result<(Mesh, Vec<String>), MeshError> {
    match detect_format(path)? {
        MeshFormat::Med => read_med_named(path, None).map(|(m, info)| (m, info.warnings)),
        _ => read_mesh(path).map(|m| (m, Vec::new())),
    }
}

/// Read a mesh file (MED, ASTER, GMSH, GIBI or I-DEAS), telling the format from the content or extension.
pub fn read_mesh(path: &Path) -> Result<Mesh, MeshError> {
    match detect_format(path)? {
        MeshFormat::Med => read_med(path),
        MeshFormat::Mail => read_mail(path),
        MeshFormat::Gmsh => read_gmsh(path),
        MeshFormat::Gibi => read_gibi(path),
        MeshFormat::Ideas => read_ideas(path),
    }
}
