//! Logical units of a case: `LIRE_MAILLAGE(UNITE=20)` reads the file the
//! `.export` maps to unit 20 (`F mmed zzzz237a.mmed D 20`).

use crate::error::MeshError;
use crate::{read_mail, read_med, Mesh, MeshFormat};
use std::path::{Path, PathBuf};

/// One `F` line of an `.export` file.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportFile {
    /// The file type (`comm`, `mmed`, `mail`, `rmed`…).
    pub kind: String,
    /// The path, resolved against the `.export` file's directory.
    pub path: PathBuf,
    /// `D` (data), `R` (result) or `DR`.
    pub direction: String,
    pub unit: u32,
}

/// The `F` lines of an `.export` file; other lines (`P`, `A`, comments) are skipped.
pub fn read_export(path: &Path) -> Result<Vec<ExportFile>, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|e| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() != Some(&"F") {
            continue;
        }
        let bad = |message: String| MeshError::Mail {
            path: path.to_path_buf(),
            line: i + 1,
            col: 1,
            message,
        };
        let [_, kind, file, direction, unit] = words[..] else {
            return Err(bad(format!(
                "expected `F <type> <path> <D|R|DR> <unit>`, found `{}`",
                line.trim()
            )));
        };
        let unit = unit
            .parse()
            .map_err(|_| bad(format!("expected a unit number, found `{unit}`")))?;
        let p = Path::new(file);
        out.push(ExportFile {
            kind: kind.to_string(),
            path: if p.is_absolute() {
                p.to_path_buf()
            } else {
                base.join(p)
            },
            direction: direction.to_string(),
            unit,
        });
    }
    Ok(out)
}

/// The file the `.export` gives for a unit, if any.
pub fn unit_path(export: &Path, unit: u32) -> Result<Option<PathBuf>, MeshError> {
    Ok(read_export(export)?
        .into_iter()
        .find(|f| f.unit == unit)
        .map(|f| f.path))
}

/// `LIRE_MAILLAGE(FORMAT=…)`: read a file in a stated format (`MED` or
/// `ASTER`), or tell it from the content when `None`.
pub fn read_mesh_as(path: &Path, format: Option<MeshFormat>) -> Result<Mesh, MeshError> {
    match format {
        Some(MeshFormat::Med) => read_med(path),
        Some(MeshFormat::Mail) => read_mail(path),
        Some(MeshFormat::Gmsh) => crate::read_gmsh(path),
        Some(MeshFormat::Gibi) => crate::read_gibi(path),
        Some(MeshFormat::Ideas) => crate::read_ideas(path),
        None => crate::read_mesh(path),
    }
}

impl MeshFormat {
    /// The format named by `LIRE_MAILLAGE(FORMAT=…)`.
    pub fn from_keyword(s: &str) -> Option<MeshFormat> {
        match s.to_ascii_uppercase().as_str() {
            "MED" => Some(MeshFormat::Med),
            "ASTER" => Some(MeshFormat::Mail),
            "GMSH" => Some(MeshFormat::Gmsh),
            "GIBI" => Some(MeshFormat::Gibi),
            "IDEAS" => Some(MeshFormat::Ideas),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_resolve_beside_the_export() {
        let dir = std::env::temp_dir().join(format!("aster-export-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let export = dir.join("case.export");
        std::fs::write(&export, "P time_limit 60\nF comm case.comm D 1\nF mmed sub/mesh.mmed D 20\nF rmed /abs/out.rmed R 80\n").unwrap();
        assert_eq!(
            unit_path(&export, 20).unwrap(),
            Some(dir.join("sub/mesh.mmed"))
        );
        assert_eq!(
            unit_path(&export, 80).unwrap(),
            Some(PathBuf::from("/abs/out.rmed"))
        );
        assert_eq!(unit_path(&export, 21).unwrap(), None);
        std::fs::write(&export, "F mmed mesh.mmed D twenty\n").unwrap();
        let e = unit_path(&export, 20).unwrap_err();
        assert!(
            e.to_string()
                .ends_with("case.export:1:1: expected a unit number, found `twenty`"),
            "{e}"
        );
    }

    #[test]
    fn format_keywords() {
        assert_eq!(MeshFormat::from_keyword("med"), Some(MeshFormat::Med));
        assert_eq!(MeshFormat::from_keyword("ASTER"), Some(MeshFormat::Mail));
        assert_eq!(MeshFormat::from_keyword("GMSH"), Some(MeshFormat::Gmsh));
        assert_eq!(MeshFormat::from_keyword("IDEAS"), Some(MeshFormat::Ideas));
        assert_eq!(MeshFormat::from_keyword("CASTEM"), None);
    }
}
