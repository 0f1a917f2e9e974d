//! The ASTER text mesh format (`.mail`).
//!
//! A file is a sequence of blocks, each a keyword line and its contents,
//! ended by `FINSF`; `FIN` ends the file; `%` starts a comment to the end of
//! the line. Blocks:
//! - `TITRE`: free text;
//! - `COOR_1D` / `COOR_2D` / `COOR_3D`: `name x [y [z]]` per node;
//! - a cell type (`SEG2`, `QUAD4`, `HEXA20`…): `name node…` per cell;
//! - `GROUP_MA` / `GROUP_NO`: the group name (or `NOM=name` on the keyword
//!   line), then member names.
//!
//! The keyword line may carry `KEY=VALUE` options (`NOBJ=12`, `NOM=X`…);
//! only `NOM` is used. Items are whitespace-separated and may span lines.

use crate::error::{suggest, MeshError};
use crate::{Cell, CellId, CellType, Group, Mesh, NodeId};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Read an ASTER `.mail` file.
pub fn read_mail(path: &Path) -> Result<Mesh, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    // Old meshes are often Latin-1: decode bytes one to one when not UTF-8.
    let text = match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    };
    parse_mail(&text, path)
}

/// A word of the file with its 1-based position.
#[derive(Clone, Copy, Debug)]
struct Token<'a> {
    text: &'a str,
    line: usize,
    col: usize,
}

/// Lines of tokens, comments removed, empty lines dropped.
fn tokenize(text: &str) -> Vec<Vec<Token<'_>>> {
    let mut lines = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = match raw.find('%') {
            Some(p) => &raw[..p],
            None => raw,
        };
        let mut toks = Vec::new();
        let mut start = None;
        for (j, ch) in line.char_indices() {
            if ch.is_whitespace() {
                if let Some(s) = start.take() {
                    toks.push(Token {
                        text: &line[s..j],
                        line: i + 1,
                        col: line[..s].chars().count() + 1,
                    });
                }
            } else if start.is_none() {
                start = Some(j);
            }
        }
        if let Some(s) = start {
            toks.push(Token {
                text: &line[s..],
                line: i + 1,
                col: line[..s].chars().count() + 1,
            });
        }
        if !toks.is_empty() {
            lines.push(toks);
        }
    }
    lines
}

const BLOCK_KEYWORDS: [&str; 6] = [
    "TITRE", "COOR_1D", "COOR_2D", "COOR_3D", "GROUP_MA", "GROUP_NO",
];

struct Parser<'a> {
    path: PathBuf,
    mesh: Mesh,
    node_index: HashMap<&'a str, NodeId>,
    cell_index: HashMap<&'a str, CellId>,
}

impl<'a> Parser<'a> {
    fn err(&self, t: &Token<'_>, message: String) -> MeshError {
        MeshError::Mail {
            path: self.path.clone(),
            line: t.line,
            col: t.col,
            message,
        }
    }
}

/// Parse the text of a `.mail` file (`path` is for messages).
pub fn parse_mail(text: &str, path: &Path) -> Result<Mesh, MeshError> {
    let lines = tokenize(text);
    let mut p = Parser {
        path: path.to_path_buf(),
        mesh: Mesh::default(),
        node_index: HashMap::new(),
        cell_index: HashMap::new(),
    };
    let mut i = 0;
    let mut coor_dim: Option<u8> = None;
    while i < lines.len() {
        let header = &lines[i];
        let kw = header[0];
        i += 1;
        let keyword = kw.text.to_ascii_uppercase();
        if keyword == "FIN" {
            break;
        }
        // Options on the keyword line: `NOM=X`, `NOBJ=12`… (a value may hold spaces, as `DATE=…`).
        let mut nom: Option<Token<'_>> = None;
        let mut body: Vec<Token<'_>> = Vec::new();
        let mut options = false;
        for (k, t) in header[1..].iter().enumerate() {
            if let Some((key, value)) = t.text.split_once('=') {
                options = true;
                if key.eq_ignore_ascii_case("NOM") {
                    if value.is_empty() {
                        nom = header.get(k + 2).copied();
                    } else {
                        nom = Some(Token {
                            text: value,
                            line: t.line,
                            col: t.col + key.len() + 1,
                        });
                    }
                }
            } else if !options && keyword != "TITRE" {
                body.push(*t);
            }
        }
        // The block's contents up to FINSF.
        let mut closed = false;
        while i < lines.len() {
            let line = &lines[i];
            i += 1;
            if line[0].text.eq_ignore_ascii_case("FINSF") {
                closed = true;
                break;
            }
            if keyword != "TITRE" {
                body.extend(line.iter().copied());
            }
        }
        if !closed {
            return Err(p.err(&kw, format!("block `{}` is not closed by FINSF", kw.text)));
        }
        match keyword.as_str() {
            "TITRE" => {}
            "COOR_1D" | "COOR_2D" | "COOR_3D" => {
                let dim = keyword.as_bytes()[5] - b'0';
                if let Some(d) = coor_dim {
                    if d != dim {
                        return Err(p.err(
                            &kw,
                            format!("{} after COOR_{d}D: one space dimension per mesh", kw.text),
                        ));
                    }
                }
                coor_dim = Some(dim);
                p.mesh.dim = dim;
                let width = 1 + dim as usize;
                if !body.len().is_multiple_of(width) {
                    let last = body[body.len() - body.len() % width];
                    return Err(p.err(
                        &last,
                        format!(
                            "{}: each node is a name and {dim} coordinate(s); the last node is incomplete",
                            kw.text
                        ),
                    ));
                }
                for node in body.chunks(width) {
                    let name = node[0];
                    let mut xyz = [0.0; 3];
                    for d in 0..dim as usize {
                        xyz[d] = parse_real(node[d + 1].text).ok_or_else(|| {
                            p.err(
                                &node[d + 1],
                                format!(
                                    "expected a coordinate of node `{}`, found `{}`",
                                    name.text,
                                    node[d + 1].text
                                ),
                            )
                        })?;
                    }
                    let id = NodeId(p.mesh.coords.len() as u32);
                    if p.node_index.insert(name.text, id).is_some() {
                        return Err(p.err(&name, format!("node `{}` is defined twice", name.text)));
                    }
                    p.mesh.coords.push(xyz);
                    p.mesh.node_names.push(name.text.to_string());
                }
            }
            "GROUP_MA" | "GROUP_NO" => {
                let mut members = body.into_iter();
                let name = match nom {
                    Some(n) => n,
                    None => members.next().ok_or_else(|| {
                        p.err(&kw, format!("{} block without a group name", kw.text))
                    })?,
                };
                if keyword == "GROUP_MA" {
                    let mut ids = Vec::new();
                    for m in members {
                        let id = *p.cell_index.get(m.text).ok_or_else(|| {
                            p.err(
                                &m,
                                format!(
                                    "group `{}`: no cell named `{}`{}",
                                    name.text,
                                    m.text,
                                    hint(m.text, p.cell_index.keys().copied())
                                ),
                            )
                        })?;
                        ids.push(id);
                    }
                    push_group(&mut p.mesh.groups_ma, name.text, ids)
                        .map_err(|m| p.err(&name, m))?;
                } else {
                    let mut ids = Vec::new();
                    for m in members {
                        let id = *p.node_index.get(m.text).ok_or_else(|| {
                            p.err(
                                &m,
                                format!(
                                    "group `{}`: no node named `{}`{}",
                                    name.text,
                                    m.text,
                                    hint(m.text, p.node_index.keys().copied())
                                ),
                            )
                        })?;
                        ids.push(id);
                    }
                    push_group(&mut p.mesh.groups_no, name.text, ids)
                        .map_err(|m| p.err(&name, m))?;
                }
            }
            _ => {
                let Some(ty) = CellType::from_name(&keyword) else {
                    let candidates = BLOCK_KEYWORDS
                        .iter()
                        .copied()
                        .chain(CellType::ALL.iter().map(|t| t.name()))
                        .chain(["FIN", "FINSF"]);
                    return Err(p.err(
                        &kw,
                        format!(
                            "unknown block `{}`: expected TITRE, COOR_2D/COOR_3D, a cell type (SEG2, QUAD4…), GROUP_MA or GROUP_NO{}",
                            kw.text,
                            hint(&keyword, candidates)
                        ),
                    ));
                };
                let width = 1 + ty.node_count();
                if !body.len().is_multiple_of(width) {
                    let last = body[body.len() - body.len() % width];
                    return Err(p.err(
                        &last,
                        format!(
                            "{}: each cell is a name and {} node names; the last cell is incomplete",
                            ty.name(),
                            ty.node_count()
                        ),
                    ));
                }
                for cell in body.chunks(width) {
                    let name = cell[0];
                    let mut nodes = Vec::with_capacity(ty.node_count());
                    for n in &cell[1..] {
                        let id = *p.node_index.get(n.text).ok_or_else(|| {
                            p.err(
                                n,
                                format!(
                                    "cell `{}`: no node named `{}` (nodes must be defined before the cells that use them){}",
                                    name.text,
                                    n.text,
                                    hint(n.text, p.node_index.keys().copied())
                                ),
                            )
                        })?;
                        nodes.push(id);
                    }
                    let id = CellId(p.mesh.cells.len() as u32);
                    if p.cell_index.insert(name.text, id).is_some() {
                        return Err(p.err(&name, format!("cell `{}` is defined twice", name.text)));
                    }
                    p.mesh.cells.push(Cell { ty, nodes });
                    p.mesh.cell_names.push(name.text.to_string());
                }
            }
        }
    }
    if p.mesh.dim == 0 {
        p.mesh.dim = 3;
    }
    Ok(p.mesh)
}

fn hint<'b>(name: &str, candidates: impl IntoIterator<Item = &'b str>) -> String {
    suggest(name, candidates)
        .map(|s| format!("; did you mean `{s}`?"))
        .unwrap_or_default()
}

/// Adds a group; a second block of the same name is an error (code_aster
/// refuses it rather than merging the two lists). A member listed twice
/// counts once and a group with no member is not created (code_aster's
/// `lrmast`: an alarm, then the first occurrence is kept).
fn push_group<T: Copy + std::hash::Hash + Eq>(
    groups: &mut Vec<Group<T>>,
    name: &str,
    members: Vec<T>,
) -> Result<(), String> {
    if groups.iter().any(|g| g.name == name) {
        return Err(format!(
            "group `{name}` is defined twice: give each GROUP_MA/GROUP_NO block its own name"
        ));
    }
    let mut seen: std::collections::HashSet<T> = std::collections::HashSet::new();
    let unique: Vec<T> = members.into_iter().filter(|m| seen.insert(*m)).collect();
    if !unique.is_empty() {
        groups.push(Group {
            name: name.to_string(),
            members: unique,
        });
    }
    Ok(())
}

/// A real as Fortran writes it: `1.5`, `1.`, `.5`, `1.5E+00`, `1.5D+00`.
fn parse_real(s: &str) -> Option<f64> {
    if let Ok(v) = s.parse::<f64>() {
        return v.is_finite().then_some(v);
    }
    let fixed = s.replace(['D', 'd'], "E");
    fixed.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Mesh, MeshError> {
        parse_mail(text, Path::new("t.mail"))
    }

    const SQUARE: &str = "TITRE\n square % comment\nFINSF\nCOOR_2D\nN1 0. 0.\nN2 1.0 0.0\nN3 1.0D+00 1.0\n N4 0 1\nFINSF\n\
        QUAD4 NOBJ=1\nM1 N1 N2\n N3 N4\nFINSF\nSEG2\nS1 N1 N2 S2 N3 N4\nFINSF\n\
        GROUP_MA\nBAS S1\nFINSF\nGROUP_MA NOM=TOUT\nM1 S1 S2\nFINSF\nGROUP_NO\nCOIN N1\nFINSF\nFIN\nignored after FIN\n";

    #[test]
    fn reads_nodes_cells_and_groups() {
        let m = parse(SQUARE).unwrap();
        assert_eq!(m.dim, 2);
        assert_eq!(m.coords.len(), 4);
        assert_eq!(m.coords[2], [1.0, 1.0, 0.0]);
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4"]);
        assert_eq!(m.cells.len(), 3);
        assert_eq!(m.cells[0].ty, CellType::QUAD4);
        assert_eq!(
            m.cells[0].nodes,
            [NodeId(0), NodeId(1), NodeId(2), NodeId(3)]
        );
        assert_eq!(m.cell_names, ["M1", "S1", "S2"]);
        assert_eq!(m.group_ma("BAS").unwrap().members, [CellId(1)]);
        assert_eq!(m.group_ma("TOUT").unwrap().members.len(), 3);
        assert_eq!(m.group_no("COIN").unwrap().members, [NodeId(0)]);
    }

    #[test]
    fn unknown_node_is_located_and_suggested() {
        let e = parse("COOR_2D\nN1 0 0\nNA2 1 0\nFINSF\nSEG2\nS1 N1 NA3\nFINSF\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.mail:6:7: cell `S1`: no node named `NA3` (nodes must be defined before the cells that use them); did you mean `NA2`?"
        );
    }

    #[test]
    fn unknown_block_suggests_a_cell_type() {
        let e = parse("COOR_2D\nN1 0 0\nFINSF\nQUAD5\nM1 N1 N1 N1 N1\nFINSF\n").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("t.mail:4:1: unknown block `QUAD5`"),
            "{e}"
        );
        assert!(e.to_string().contains("did you mean"), "{e}");
    }

    #[test]
    fn a_group_defined_twice_is_refused_at_its_second_name() {
        let e = parse(
            "COOR_2D\nN1 0 0\nN2 1 0\nFINSF\nSEG2\nS1 N1 N2\nFINSF\n\
             GROUP_MA\nG S1\nFINSF\nGROUP_MA\nG S1\nFINSF\nFIN\n",
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.mail:12:1: group `G` is defined twice: give each GROUP_MA/GROUP_NO block its own name"
        );
        let e =
            parse("COOR_2D\nN1 0 0\nFINSF\nGROUP_NO NOM=P\nN1\nFINSF\nGROUP_NO NOM=P\nN1\nFINSF\n")
                .unwrap_err();
        assert!(e.to_string().starts_with("t.mail:7:"), "{e}");
    }

    #[test]
    fn unclosed_block_and_bad_coordinate_are_errors() {
        let e = parse("COOR_2D\nN1 0 0\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.mail:1:1: block `COOR_2D` is not closed by FINSF"
        );
        let e = parse("COOR_2D\nN1 0 x\nFINSF\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.mail:2:6: expected a coordinate of node `N1`, found `x`"
        );
        let e = parse("COOR_3D\nN1 0 0 0\nN2 1 1\nFINSF\n").unwrap_err();
        assert!(
            e.to_string().starts_with("t.mail:3:1: COOR_3D: each node"),
            "{e}"
        );
    }
}
