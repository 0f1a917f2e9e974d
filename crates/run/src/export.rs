//! `.export` files: which file is the command file and which files stand
//! for which logical units (`F mmed zzzz237a.mmed D 20`: unit 20, read).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One `F`/`R` line.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportFile {
    /// `comm`, `mmed`, `mail`, `resu`, `rmed`…
    pub kind: String,
    pub path: PathBuf,
    /// `D` (data, read), `R` (result, written) or both.
    pub data: bool,
    pub result: bool,
    pub unit: u32,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Export {
    pub files: Vec<ExportFile>,
    /// `P name value…` parameters.
    pub params: BTreeMap<String, String>,
}

impl Export {
    /// Parses an export's text; paths are resolved against `base`.
    pub fn parse(text: &str, base: &Path) -> Result<Export, String> {
        let mut export = Export::default();
        for (n, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let parts: Vec<&str> = line.split_whitespace().collect();
            match parts[0] {
                "F" | "R" => {
                    if parts.len() < 5 {
                        return Err(format!(
                            "line {}: expected `F <type> <path> <D|R|DR> <unit>`, found `{line}`",
                            n + 1
                        ));
                    }
                    let unit: u32 = parts[4].parse().map_err(|_| {
                        format!("line {}: unit `{}` is not a number", n + 1, parts[4])
                    })?;
                    let mode = parts[3];
                    let path = Path::new(parts[2]);
                    export.files.push(ExportFile {
                        kind: parts[1].to_string(),
                        path: if path.is_absolute() {
                            path.to_path_buf()
                        } else {
                            base.join(path)
                        },
                        data: mode.contains('D'),
                        result: mode.contains('R'),
                        unit,
                    });
                }
                "P" | "A" if parts.len() >= 2 => {
                    export
                        .params
                        .insert(parts[1].to_string(), parts[2..].join(" "));
                }
                _ => {}
            }
        }
        Ok(export)
    }

    /// Reads an `.export`: UTF-8, else Latin-1 (comments of old exports),
    /// as command files are read.
    pub fn read(path: &Path) -> Result<Export, String> {
        let bytes =
            std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        let text = aster_syntax::decode(&bytes);
        let base = path.parent().unwrap_or(Path::new("."));
        Export::parse(&text, base).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// The command files (`F comm … D 1`), in order.
    pub fn comm_files(&self) -> Vec<&Path> {
        self.files
            .iter()
            .filter(|f| f.kind == "comm" && f.data)
            .map(|f| f.path.as_path())
            .collect()
    }

    /// The Python modules of the study (`F nom module.py D 0`), in order.
    /// Other `nom` files (a `.med`, a Fortran or MFront source, a `.json`)
    /// are data the study opens by name, not modules.
    pub fn modules(&self) -> Vec<&Path> {
        self.files
            .iter()
            .filter(|f| f.kind == "nom" && f.data)
            .filter(|f| f.path.extension().is_some_and(|e| e == "py"))
            .map(|f| f.path.as_path())
            .collect()
    }

    /// The file read as a logical unit.
    pub fn data_unit(&self, unit: u32) -> Option<&Path> {
        self.files
            .iter()
            .find(|f| f.unit == unit && f.data && is_unit_file(f))
            .map(|f| f.path.as_path())
    }

    /// Data units other than command files and modules.
    pub fn data_units(&self) -> BTreeMap<u32, PathBuf> {
        self.files
            .iter()
            .filter(|f| f.data && is_unit_file(f))
            .map(|f| (f.unit, f.path.clone()))
            .collect()
    }

    /// The first file written with one of these kinds (`resu`, `mess`).
    pub fn result_file(&self, kind: &str) -> Option<&Path> {
        self.files
            .iter()
            .find(|f| f.result && f.kind == kind)
            .map(|f| f.path.as_path())
    }
}

/// A line that stands for a logical unit (not a command file, a module, or
/// a database directory).
fn is_unit_file(f: &ExportFile) -> bool {
    !matches!(f.kind.as_str(), "comm" | "nom" | "base" | "bhdf")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_units() {
        let text = "P time_limit 60\nP testlist verification\nF comm case.comm D 1\nF mmed mesh.mmed D 20\nF resu out.resu R 8\n";
        let e = Export::parse(text, Path::new("/cases/x")).unwrap();
        assert_eq!(e.comm_files(), vec![Path::new("/cases/x/case.comm")]);
        assert_eq!(e.data_unit(20), Some(Path::new("/cases/x/mesh.mmed")));
        assert_eq!(e.data_unit(8), None);
        assert_eq!(
            e.params.get("testlist").map(String::as_str),
            Some("verification")
        );
    }

    #[test]
    fn several_command_files_and_modules() {
        let text = "# ssnv219x\nF comm s.comm D 1\nF comm s.com1 D 1\nF nom m.py D 0\nF nom s.med D 0\nF nom u.f D 0\nF mmed s.mmed D 20\nF resu s.resu R 8\n";
        let e = Export::parse(text, Path::new("/c")).unwrap();
        assert_eq!(
            e.comm_files(),
            vec![Path::new("/c/s.comm"), Path::new("/c/s.com1")]
        );
        assert_eq!(e.modules(), vec![Path::new("/c/m.py")]);
        assert_eq!(e.data_units().keys().copied().collect::<Vec<_>>(), [20]);
        assert_eq!(e.result_file("resu"), Some(Path::new("/c/s.resu")));
    }

    #[test]
    fn latin1_comments_are_read() {
        let dir = std::env::temp_dir().join(format!("aster-export-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("l.export");
        std::fs::write(&path, b"# donn\xe9es\nF comm l.comm D 1\n").unwrap();
        let e = Export::read(&path).unwrap();
        assert_eq!(e.comm_files(), vec![dir.join("l.comm").as_path()]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn bad_unit_is_reported_with_its_line() {
        let err = Export::parse("F mmed m.mmed D twenty\n", Path::new(".")).unwrap_err();
        assert!(err.starts_with("line 1:"), "{err}");
    }
}
