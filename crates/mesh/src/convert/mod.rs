//! Meshes of other tools as code_aster reads them: `PRE_GMSH`, `PRE_GIBI`
//! and `PRE_IDEAS` convert a GMSH (`.msh`), GIBI/Cast3M (`.mgib`) or I-DEAS
//! universal (`.unv`) file into an ASTER text mesh, which
//! `LIRE_MAILLAGE(FORMAT='ASTER')` then reads
//! (`LIRE_MAILLAGE(FORMAT='GMSH'|'GIBI'|'IDEAS')` does both). The converters here
//! write the same ASTER text code_aster's Fortran writes — the same node and
//! cell names, cell order, groups and the coordinates rounded to 15
//! significant digits by its `1PE21.14` format — so the mesh read back is
//! code_aster's, number for number.

pub mod gibi;
pub mod gmsh;
pub mod ideas;

use crate::error::MeshError;
use crate::Mesh;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub use gibi::{gibi_to_mail, read_gibi};
pub use gmsh::{gmsh_to_mail, read_gmsh};
pub use ideas::{ideas_to_mail, read_ideas, read_ideas_with};

/// Reads a text file (Latin-1 when not UTF-8).
fn read_text(path: &Path) -> Result<String, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    })
}

/// Parses the ASTER text a converter wrote (errors there are the
/// converter's; they name the source file).
fn read_back(text: &str, path: &Path) -> Result<Mesh, MeshError> {
    crate::parse_mail(text, path)
}

/// Lines of a source file with their 1-based numbers, read in order.
struct Lines<'a> {
    path: PathBuf,
    lines: Vec<&'a str>,
    /// Index of the next line.
    pos: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, path: &Path) -> Lines<'a> {
        Lines {
            path: path.to_path_buf(),
            lines: text.lines().collect(),
            pos: 0,
        }
    }

    /// The next line and its number, or an error saying what was expected.
    fn next(&mut self, what: &str) -> Result<(usize, &'a str), MeshError> {
        match self.lines.get(self.pos) {
            Some(l) => {
                self.pos += 1;
                Ok((self.pos, l.trim_end_matches('\r')))
            }
            None => Err(self.error(
                self.lines.len().max(1),
                1,
                format!("the file ends where {what} was expected"),
            )),
        }
    }

    /// The next line, if any.
    fn try_next(&mut self) -> Option<(usize, &'a str)> {
        let l = self.lines.get(self.pos)?;
        self.pos += 1;
        Some((self.pos, l.trim_end_matches('\r')))
    }

    fn error(&self, line: usize, col: usize, message: String) -> MeshError {
        MeshError::Mail {
            path: self.path.clone(),
            line,
            col,
            message,
        }
    }
}

/// The whitespace-separated words of a line with their 1-based columns.
fn words(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in line.char_indices() {
        if c.is_whitespace() {
            if let Some(s) = start.take() {
                out.push((line[..s].chars().count() + 1, &line[s..i]));
            }
        } else if start.is_none() {
            start = Some(i);
        }
    }
    if let Some(s) = start {
        out.push((line[..s].chars().count() + 1, &line[s..]));
    }
    out
}

/// A real as Fortran reads it: `1.5`, `1.5E+00`, `1.5D+00`, and
/// `1.5+100` (the form `E21.14` takes for a 3-digit exponent).
fn fortran_real(s: &str) -> Option<f64> {
    let t = s.replace(['D', 'd'], "E");
    if let Ok(v) = t.parse::<f64>() {
        return v.is_finite().then_some(v);
    }
    // An exponent sign without its letter.
    let bytes = t.as_bytes();
    let at = (1..bytes.len())
        .rev()
        .find(|&i| matches!(bytes[i], b'+' | b'-') && !matches!(bytes[i - 1], b'E' | b'e'))?;
    let v: f64 = format!("{}E{}", &t[..at], &t[at..]).parse().ok()?;
    v.is_finite().then_some(v)
}

/// The ASTER text of a converted mesh, block by block, in the layout
/// code_aster's converters write (names eight characters at most).
struct MailText {
    out: String,
}

impl MailText {
    fn new(title: &str) -> MailText {
        let mut out = String::new();
        let _ = writeln!(out, "TITRE\n {title}\nFINSF\n%");
        MailText { out }
    }

    /// `COOR_nD`: one node per line, coordinates as `1PE21.14` writes them
    /// (15 significant digits: the value code_aster reads back).
    fn coords<'n>(&mut self, dim: usize, nodes: impl Iterator<Item = (String, &'n [f64])>) {
        let _ = writeln!(self.out, "COOR_{dim}D");
        for (name, xyz) in nodes {
            let _ = write!(self.out, "  {name:<8}");
            for x in xyz.iter().take(dim) {
                let _ = write!(self.out, " {x:21.14E}");
            }
            self.out.push('\n');
        }
        self.out.push_str("FINSF\n%\n");
    }

    /// A block of cells of one type: `name node…` per cell.
    fn cells(&mut self, ty: &str, cells: &[(String, Vec<String>)]) {
        let _ = writeln!(self.out, "{ty}");
        for (name, nodes) in cells {
            let _ = write!(self.out, "  {name:<8}");
            for (k, n) in nodes.iter().enumerate() {
                if k > 0 && k % 8 == 0 {
                    self.out.push_str("\n          ");
                }
                let _ = write!(self.out, " {n:<8}");
            }
            self.out.push('\n');
        }
        self.out.push_str("FINSF\n%\n");
    }

    fn group(&mut self, kind: &str, name: &str, members: &[String]) {
        let _ = writeln!(self.out, "{kind}\n  {name}");
        for line in members.chunks(8) {
            let _ = writeln!(self.out, "  {}", line.join("  "));
        }
        self.out.push_str("FINSF\n%\n");
    }

    fn finish(mut self) -> String {
        self.out.push_str("FIN\n");
        self.out
    }
}

/// `N<number>`/`M<number>` as code_aster names them (`codent` in eight
/// characters: numbers up to 9,999,999).
fn numbered(
    prefix: char,
    n: i64,
    lines: &Lines<'_>,
    line: usize,
    col: usize,
) -> Result<String, MeshError> {
    if !(0..=9_999_999).contains(&n) {
        return Err(lines.error(
            line,
            col,
            format!(
                "number {n} cannot name a {} (code_aster names them {prefix}1 to {prefix}9999999)",
                if prefix == 'N' { "node" } else { "cell" }
            ),
        ));
    }
    Ok(format!("{prefix}{n}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_reals() {
        assert_eq!(fortran_real("1.5D+00"), Some(1.5));
        assert_eq!(fortran_real("-2.5E-01"), Some(-0.25));
        assert_eq!(fortran_real("1.00000000000000+100"), Some(1e100));
        assert_eq!(fortran_real("1.0-100"), Some(1e-100));
        assert_eq!(fortran_real("x"), None);
    }

    #[test]
    fn coordinates_keep_fifteen_digits() {
        let mut t = MailText::new("t");
        let x = [0.1f64 + 0.2, 1.0 / 3.0, 0.0];
        t.coords(3, std::iter::once(("N1".to_string(), &x[..])));
        let text = t.finish();
        assert!(text.contains(" 3.00000000000000E-1"), "{text}");
        let m = crate::parse_mail(&text, Path::new("t.mail")).unwrap();
        assert_eq!(m.coords[0][0], 0.3);
        assert_eq!(m.coords[0][1], 0.333333333333333);
    }
}
