//! GMSH `.msh` files as code_aster's `PRE_GMSH` converts them (`pregms`,
//! `gmlneu`, `gmlelt`, `gmeneu`, `gmeelt`, `inigms`).
//!
//! - Versions: 1.0 (`$NOD`/`$ELM`, real test files) and 2.x (`$MeshFormat`,
//!   `$Nodes`/`$Elements`; sections before `$Nodes` but `$PhysicalNames`
//!   are skipped), ASCII. 4.x is read too (code_aster 15 cannot:
//!   the same naming rules are applied, see below); binary files are refused.
//! - Nodes: `N<tag>`, in file order; only the nodes some cell uses are kept.
//! - Cells: `M<tag>`, written type by type in the order of GMSH's element
//!   types 1–19 (SEG2, TRIA3, QUAD4, TETRA4, HEXA8, PENTA6, PYRAM5, SEG3,
//!   TRIA6, QUAD8 (from QUAD9: the centre node is dropped), TETRA10, HEXA27,
//!   PENTA18, PYRAM13 (from PYRAM14), POI1, QUAD8, HEXA20, PENTA15,
//!   PYRAM13), in file order within a type, nodes reordered to code_aster's
//!   numbering.
//! - Groups: `GM<physical>` for each physical tag, in the order it first
//!   appears, its cells in file order; a physical group of a single point
//!   cell is also the node group `GM<physical>`. A 2.x file with
//!   `$PhysicalNames` (code_aster 17's `pregms` reads them): one group per
//!   name, in their order, named by the name's first 8 characters, of the
//!   cells (file order) one of whose tags — physical or elementary, as
//!   `gmlelt` compares them all — is the name's tag and whose dimension is
//!   the name's; a tag without a name makes no group (4.x files are read
//!   the same way, with their entities' physical tags). Physical tag 0 (no group)
//!   makes no group (code_aster's reader leaves it undefined).
//! - 4.x: a cell's physical tags are those of its entity (`$Entities`); a
//!   cell is in each of them; groups in the order they first appear among
//!   the cells.

use super::{fortran_real, numbered, read_back, read_text, words, Lines, MailText};
use crate::error::MeshError;
use crate::Mesh;
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// code_aster's cell type for each GMSH element type 1–19 (`inigms`).
const NOMAIL: [&str; 19] = [
    "SEG2", "TRIA3", "QUAD4", "TETRA4", "HEXA8", "PENTA6", "PYRAM5", "SEG3", "TRIA6", "QUAD8",
    "TETRA10", "HEXA27", "PENTA18", "PYRAM13", "POI1", "QUAD8", "HEXA20", "PENTA15", "PYRAM13",
];

/// The number of nodes of each GMSH element type 1–19 (`gmlelt`).
const NBNO: [usize; 19] = [
    2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1, 8, 20, 15, 13,
];

/// code_aster's node `ino` (1-based) of a cell of GMSH type `t` is the
/// GMSH node `nuconn(t, ino)` (`inigms`).
fn nuconn(t: usize, ino: usize) -> usize {
    const HEXA: [(usize, usize); 11] = [
        (10, 12),
        (11, 14),
        (12, 10),
        (13, 11),
        (14, 13),
        (15, 15),
        (16, 16),
        (17, 17),
        (18, 19),
        (19, 20),
        (20, 18),
    ];
    const PENTA: [(usize, usize); 9] = [
        (7, 7),
        (8, 10),
        (9, 8),
        (10, 9),
        (11, 11),
        (12, 12),
        (13, 13),
        (14, 15),
        (15, 14),
    ];
    const PYRAM: [(usize, usize); 8] = [
        (6, 6),
        (7, 9),
        (8, 11),
        (9, 7),
        (10, 8),
        (11, 10),
        (12, 12),
        (13, 13),
    ];
    let table: &[(usize, usize)] = match t {
        11 => &[(9, 10), (10, 9)],
        12 => &[
            (10, 12),
            (11, 14),
            (12, 10),
            (13, 11),
            (14, 13),
            (15, 15),
            (16, 16),
            (17, 17),
            (18, 19),
            (19, 20),
            (20, 18),
            (23, 24),
            (24, 25),
            (25, 23),
        ],
        13 => &[
            (7, 7),
            (8, 10),
            (9, 8),
            (10, 9),
            (11, 11),
            (12, 12),
            (13, 13),
            (14, 15),
            (15, 14),
            (17, 18),
            (18, 17),
        ],
        14 | 19 => &PYRAM,
        17 => &HEXA,
        18 => &PENTA,
        _ => &[],
    };
    table
        .iter()
        .find(|(i, _)| *i == ino)
        .map(|(_, j)| *j)
        .unwrap_or(ino)
}

/// The node count of a code_aster cell type.
fn aster_count(name: &str) -> usize {
    crate::CellType::from_name(name).map_or(0, |t| t.node_count())
}

/// One element as read.
struct Element {
    tag: i64,
    /// GMSH type, 1–19.
    ty: usize,
    /// Physical tags (one in 1.0/2.x; 0 = none).
    physicals: Vec<i64>,
    /// Every tag of a 2.x line (physical, elementary, partitions…): what
    /// code_aster matches against the `$PhysicalNames` tags.
    tags: Vec<i64>,
    nodes: Vec<i64>,
    line: usize,
}

/// A parsed GMSH file: nodes in file order, elements in file order.
struct Parsed {
    nodes: Vec<(i64, [f64; 3], usize)>,
    elements: Vec<Element>,
    /// 2.x `$PhysicalNames` (dimension, tag, name), in file order.
    names: Option<Vec<(usize, i64, String)>>,
}

/// Reads a GMSH file as `LIRE_MAILLAGE(FORMAT='GMSH')` does.
pub fn read_gmsh(path: &Path) -> Result<Mesh, MeshError> {
    let text = read_text(path)?;
    read_back(&gmsh_to_mail(&text, path)?, path)
}

/// The ASTER text `PRE_GMSH` writes for a GMSH file (`path` is for messages).
pub fn gmsh_to_mail(text: &str, path: &Path) -> Result<String, MeshError> {
    let mut lines = Lines::new(text, path);
    let parsed = parse(&mut lines)?;
    write(&parsed, &lines)
}

fn int(
    lines: &Lines<'_>,
    line: usize,
    (col, w): (usize, &str),
    what: &str,
) -> Result<i64, MeshError> {
    w.parse::<i64>()
        .map_err(|_| lines.error(line, col, format!("expected {what}, found `{w}`")))
}

/// The words of a line that must hold at least `n` of them.
fn need<'a>(
    lines: &Lines<'_>,
    line: usize,
    text: &'a str,
    n: usize,
    what: &str,
) -> Result<Vec<(usize, &'a str)>, MeshError> {
    let w = words(text);
    if w.len() < n {
        let col = text.trim_end().chars().count() + 1;
        return Err(lines.error(
            line,
            col,
            format!("{what}: expected {n} values, found {}", w.len()),
        ));
    }
    Ok(w)
}

/// A count on its own line (`read(…,'(I10)')`).
fn count(lines: &mut Lines<'_>, what: &str) -> Result<usize, MeshError> {
    let (n, l) = lines.next(what)?;
    let w = need(lines, n, l, 1, what)?;
    let v = int(lines, n, w[0], what)?;
    usize::try_from(v).map_err(|_| lines.error(n, w[0].0, format!("{what}: {v} is negative")))
}

/// The next line must start with one of these section markers.
fn expect_marker(lines: &mut Lines<'_>, markers: &[&str]) -> Result<(), MeshError> {
    let (n, l) = lines.next(&format!("`{}`", markers.join("` or `")))?;
    let first = l.split_whitespace().next().unwrap_or("");
    if markers.iter().any(|m| first.starts_with(m)) {
        Ok(())
    } else {
        Err(lines.error(
            n,
            1,
            format!(
                "expected `{}`, found `{}`",
                markers.join("` or `"),
                l.trim()
            ),
        ))
    }
}

/// The `$PhysicalNames` section of a 2.x file (`pregms`): `dim tag "name"`
/// lines; code_aster keeps a name's first 8 characters (a `K8`).
fn physical_names(lines: &mut Lines<'_>) -> Result<Vec<(usize, i64, String)>, MeshError> {
    let nb = count(lines, "the number of physical names")?;
    let mut out = Vec::with_capacity(nb.min(1 << 16));
    for _ in 0..nb {
        let (n, l) = lines.next("a physical name (dimension tag \"name\")")?;
        let w = need(lines, n, l, 3, "a physical name (dimension tag \"name\")")?;
        let dim = int(lines, n, w[0], "a dimension")?;
        let dim = usize::try_from(dim)
            .ok()
            .filter(|d| *d <= 3)
            .ok_or_else(|| lines.error(n, w[0].0, format!("dimension {dim} is not 0 to 3")))?;
        let tag = int(lines, n, w[1], "a physical tag")?;
        // Fortran's list-directed read: a quoted string, or one word.
        // The third word is a slice of the line: the rest starts there.
        let rest = &l[w[2].1.as_ptr() as usize - l.as_ptr() as usize..];
        let raw = match rest.strip_prefix('"') {
            Some(r) => r.split('"').next().unwrap_or(""),
            None => rest.split_whitespace().next().unwrap_or(""),
        };
        let name: String = raw.chars().take(8).collect();
        let name = name.trim_end().to_string();
        if name.is_empty() {
            return Err(lines.error(n, w[2].0, "a physical group needs a name".to_string()));
        }
        out.push((dim, tag, name));
    }
    expect_marker(lines, &["$EndPhysicalNames"])?;
    Ok(out)
}

/// The dimension of a GMSH element type 1–19 (`dime` of `gmlelt`).
fn type_dim(ty: usize) -> usize {
    match ty {
        15 => 0,
        1 | 8 => 1,
        2 | 3 | 9 | 10 | 16 => 2,
        _ => 3,
    }
}

fn parse(lines: &mut Lines<'_>) -> Result<Parsed, MeshError> {
    let mut names = None;
    let (n, first) = lines.next("`$NOD` or `$MeshFormat`")?;
    let head = first.split_whitespace().next().unwrap_or("");
    let version = if head.starts_with("$NOD") {
        1
    } else if head.starts_with("$MeshFormat") {
        let (vn, vline) = lines.next("the format version")?;
        let w = need(
            lines,
            vn,
            vline,
            2,
            "the format line (version file-type data-size)",
        )?;
        let v: f64 = w[0].1.parse().map_err(|_| {
            lines.error(
                vn,
                w[0].0,
                format!("expected a version number, found `{}`", w[0].1),
            )
        })?;
        if w[1].1 != "0" {
            return Err(lines.error(
                vn,
                w[1].0,
                "binary GMSH files are not read: save the mesh as ASCII".to_string(),
            ));
        }
        lines.next("`$EndMeshFormat`")?;
        if v >= 4.0 {
            return parse_v4(lines, v);
        }
        // Skip to $Nodes, reading $PhysicalNames on the way (`pregms`).
        loop {
            let (_, l) = lines.next("`$Nodes`")?;
            let l = l.trim_start();
            if l.starts_with("$Nodes") {
                break;
            }
            if l.starts_with("$PhysicalNames") {
                names = Some(physical_names(lines)?);
            }
        }
        2
    } else {
        return Err(lines.error(
            n,
            1,
            format!(
                "not a GMSH file: it starts with `{}`, expected `$NOD` (format 1.0) or `$MeshFormat`",
                first.trim()
            ),
        ));
    };
    let nb = count(lines, "the number of nodes")?;
    let mut nodes = Vec::with_capacity(nb);
    for _ in 0..nb {
        let (n, l) = lines.next("a node line (number x y z)")?;
        let w = need(lines, n, l, 4, "a node (number x y z)")?;
        let tag = int(lines, n, w[0], "a node number")?;
        let mut xyz = [0.0; 3];
        for d in 0..3 {
            xyz[d] = fortran_real(w[d + 1].1).ok_or_else(|| {
                lines.error(
                    n,
                    w[d + 1].0,
                    format!(
                        "expected a coordinate of node {tag}, found `{}`",
                        w[d + 1].1
                    ),
                )
            })?;
        }
        nodes.push((tag, xyz, n));
    }
    expect_marker(lines, &["$ENDNOD", "$EndNodes"])?;
    expect_marker(lines, &["$ELM", "$Elements"])?;
    let ne = count(lines, "the number of elements")?;
    let mut elements = Vec::with_capacity(ne);
    for _ in 0..ne {
        let (n, l) = lines.next("an element line")?;
        let w = need(lines, n, l, 3, "an element")?;
        let tag = int(lines, n, w[0], "an element number")?;
        let ty = element_type(lines, n, w[1])?;
        let mut tags = Vec::new();
        let (physicals, first, count) = if version == 1 {
            // number type reg-phys reg-elem number-of-nodes nodes…
            let w = need(
                lines,
                n,
                l,
                5,
                "an element (number type physical elementary nodes…)",
            )?;
            let phys = int(lines, n, w[2], "a physical tag")?;
            let c = int(lines, n, w[4], "a node count")?;
            let c = usize::try_from(c)
                .map_err(|_| lines.error(n, w[4].0, format!("node count {c} is negative")))?;
            if c < aster_count(NOMAIL[ty - 1]) {
                return Err(lines.error(
                    n,
                    w[4].0,
                    format!(
                        "element {tag} of type {ty} has {c} nodes; a {} needs {}",
                        NOMAIL[ty - 1],
                        aster_count(NOMAIL[ty - 1])
                    ),
                ));
            }
            (vec![phys], 5, c)
        } else {
            // number type ntags tags… nodes…
            let nt = int(lines, n, w[2], "a tag count")?;
            let nt = usize::try_from(nt)
                .map_err(|_| lines.error(n, w[2].0, format!("tag count {nt} is negative")))?;
            let w = need(lines, n, l, 3 + nt, "an element's tags")?;
            let phys = if nt > 0 {
                int(lines, n, w[3], "a physical tag")?
            } else {
                0
            };
            for &word in &w[3..3 + nt] {
                tags.push(int(lines, n, word, "a tag")?);
            }
            (vec![phys], 3 + nt, NBNO[ty - 1])
        };
        let w = need(
            lines,
            n,
            l,
            first + count,
            &format!("element {tag} (type {ty}, {count} nodes)"),
        )?;
        let mut nodes = Vec::with_capacity(count);
        for &word in &w[first..first + count] {
            nodes.push(int(lines, n, word, "a node number")?);
        }
        elements.push(Element {
            tag,
            ty,
            physicals,
            tags,
            nodes,
            line: n,
        });
    }
    expect_marker(lines, &["$ENDELM", "$EndElements"])?;
    Ok(Parsed {
        nodes,
        elements,
        names,
    })
}

fn element_type(lines: &Lines<'_>, n: usize, w: (usize, &str)) -> Result<usize, MeshError> {
    let t = int(lines, n, w, "an element type")?;
    if (1..=19).contains(&t) {
        Ok(t as usize)
    } else {
        Err(lines.error(
            n,
            w.0,
            format!("element type {t} is not one code_aster reads (GMSH types 1 to 19)"),
        ))
    }
}

/// Format 4.x: entities, then nodes and elements by entity block.
fn parse_v4(lines: &mut Lines<'_>, version: f64) -> Result<Parsed, MeshError> {
    // (dim, entity tag) → physical tags.
    let mut physicals: HashMap<(i64, i64), Vec<i64>> = HashMap::new();
    let mut nodes = Vec::new();
    let mut elements = Vec::new();
    let mut seen_elements = false;
    let mut names = None;
    while let Some((n, l)) = lines.try_next() {
        match l.trim() {
            // Read as for 2.x (code_aster reads no 4.x file: the same rules).
            "$PhysicalNames" => names = Some(physical_names(lines)?),
            "$Entities" => {
                let (hn, h) = lines.next("the entity counts")?;
                let w = need(
                    lines,
                    hn,
                    h,
                    4,
                    "the entity counts (points curves surfaces volumes)",
                )?;
                for dim in 0..4 {
                    let c = int(lines, hn, w[dim], "an entity count")?;
                    for _ in 0..c.max(0) {
                        let (en, e) = lines.next("an entity line")?;
                        // Points: tag X Y Z (4.1; 4.0 gives a box) then physicals.
                        let skip = if dim == 0 && version >= 4.1 { 4 } else { 7 };
                        let w = need(lines, en, e, skip + 1, "an entity")?;
                        let tag = int(lines, en, w[0], "an entity tag")?;
                        let np = int(lines, en, w[skip], "a physical tag count")?;
                        let np = usize::try_from(np).unwrap_or(0);
                        let w = need(lines, en, e, skip + 1 + np, "an entity's physical tags")?;
                        let mut tags = Vec::with_capacity(np);
                        for &word in &w[skip + 1..skip + 1 + np] {
                            tags.push(int(lines, en, word, "a physical tag")?.abs());
                        }
                        physicals.insert((dim as i64, tag), tags);
                    }
                }
                expect_marker(lines, &["$EndEntities"])?;
            }
            "$Nodes" => {
                let (hn, h) = lines.next("the node block counts")?;
                let w = need(lines, hn, h, 4, "the node counts (blocks nodes min max)")?;
                let blocks = int(lines, hn, w[0], "a block count")?;
                for _ in 0..blocks.max(0) {
                    let (bn, b) = lines.next("a node block header")?;
                    let w = need(
                        lines,
                        bn,
                        b,
                        4,
                        "a node block (dim entity parametric count)",
                    )?;
                    let parametric = int(lines, bn, w[2], "the parametric flag")? != 0;
                    if parametric {
                        return Err(lines.error(
                            bn,
                            w[2].0,
                            "parametric node coordinates are not read: save the mesh without them"
                                .to_string(),
                        ));
                    }
                    let c = usize::try_from(int(lines, bn, w[3], "a node count")?).unwrap_or(0);
                    let mut tags = Vec::with_capacity(c);
                    for _ in 0..c {
                        let (tn, t) = lines.next("a node tag")?;
                        let w = need(lines, tn, t, 1, "a node tag")?;
                        tags.push(int(lines, tn, w[0], "a node tag")?);
                    }
                    for tag in tags {
                        let (cn, c) = lines.next("node coordinates")?;
                        let w = need(lines, cn, c, 3, "node coordinates (x y z)")?;
                        let mut xyz = [0.0; 3];
                        for d in 0..3 {
                            xyz[d] = fortran_real(w[d].1).ok_or_else(|| {
                                lines.error(
                                    cn,
                                    w[d].0,
                                    format!(
                                        "expected a coordinate of node {tag}, found `{}`",
                                        w[d].1
                                    ),
                                )
                            })?;
                        }
                        nodes.push((tag, xyz, cn));
                    }
                }
                expect_marker(lines, &["$EndNodes"])?;
            }
            "$Elements" => {
                seen_elements = true;
                let (hn, h) = lines.next("the element block counts")?;
                let w = need(
                    lines,
                    hn,
                    h,
                    4,
                    "the element counts (blocks elements min max)",
                )?;
                let blocks = int(lines, hn, w[0], "a block count")?;
                for _ in 0..blocks.max(0) {
                    let (bn, b) = lines.next("an element block header")?;
                    let w = need(lines, bn, b, 4, "an element block (dim entity type count)")?;
                    let dim = int(lines, bn, w[0], "an entity dimension")?;
                    let entity = int(lines, bn, w[1], "an entity tag")?;
                    let ty = element_type(lines, bn, w[2])?;
                    let c = usize::try_from(int(lines, bn, w[3], "an element count")?).unwrap_or(0);
                    let phys = physicals.get(&(dim, entity)).cloned().unwrap_or_default();
                    for _ in 0..c {
                        let (en, e) = lines.next("an element line")?;
                        let k = NBNO[ty - 1];
                        let w = need(
                            lines,
                            en,
                            e,
                            1 + k,
                            &format!("an element of type {ty} (tag and {k} nodes)"),
                        )?;
                        let tag = int(lines, en, w[0], "an element tag")?;
                        let mut ns = Vec::with_capacity(k);
                        for &word in &w[1..1 + k] {
                            ns.push(int(lines, en, word, "a node tag")?);
                        }
                        elements.push(Element {
                            tag,
                            ty,
                            physicals: phys.clone(),
                            tags: phys.clone(),
                            nodes: ns,
                            line: en,
                        });
                    }
                }
                expect_marker(lines, &["$EndElements"])?;
            }
            s if s.starts_with('$') && !s.starts_with("$End") => {
                // Another section ($PhysicalNames, $NodeData…): skipped.
                let end = format!("$End{}", &s[1..]);
                loop {
                    let (_, l) = lines.next(&format!("`{end}`"))?;
                    if l.trim() == end {
                        break;
                    }
                }
            }
            "" => {}
            other => {
                return Err(lines.error(
                    n,
                    1,
                    format!("expected a section (`$Nodes`, `$Elements`…), found `{other}`"),
                ));
            }
        }
    }
    if !seen_elements {
        return Err(lines.error(
            lines.lines.len().max(1),
            1,
            "no `$Elements` section".to_string(),
        ));
    }
    Ok(Parsed {
        nodes,
        elements,
        names,
    })
}

/// The ASTER text, as `gmeneu` and `gmeelt` write it.
fn write(p: &Parsed, lines: &Lines<'_>) -> Result<String, MeshError> {
    // Nodes: defined once; the ones some cell uses are kept.
    let mut index: HashMap<i64, usize> = HashMap::with_capacity(p.nodes.len());
    for (i, (tag, _, line)) in p.nodes.iter().enumerate() {
        if index.insert(*tag, i).is_some() {
            return Err(lines.error(*line, 1, format!("node {tag} is defined twice")));
        }
    }
    let mut used = vec![false; p.nodes.len()];
    // Cells by code_aster type block (GMSH type order), connectivity remapped.
    let mut blocks: Vec<Vec<(String, Vec<String>)>> = vec![Vec::new(); 19];
    let mut cell_names = HashSet::new();
    for e in &p.elements {
        let name = numbered('M', e.tag, lines, e.line, 1)?;
        if !cell_names.insert(e.tag) {
            return Err(lines.error(e.line, 1, format!("element {} is defined twice", e.tag)));
        }
        let aster = NOMAIL[e.ty - 1];
        let mut nodes = Vec::with_capacity(aster_count(aster));
        for ino in 1..=aster_count(aster) {
            let tag = e.nodes[nuconn(e.ty, ino) - 1];
            let Some(&i) = index.get(&tag) else {
                return Err(lines.error(
                    e.line,
                    1,
                    format!(
                        "element {} uses node {tag}, which the file does not define",
                        e.tag
                    ),
                ));
            };
            used[i] = true;
            nodes.push(numbered('N', tag, lines, e.line, 1)?);
        }
        blocks[e.ty - 1].push((name, nodes));
    }
    let mut text = MailText::new("AUTEUR=INTERFACE_GMSH");
    let mut kept = Vec::new();
    for (i, (tag, xyz, line)) in p.nodes.iter().enumerate() {
        if used[i] {
            kept.push((numbered('N', *tag, lines, *line, 1)?, &xyz[..]));
        }
    }
    text.coords(3, kept.into_iter());
    for (t, cells) in blocks.iter().enumerate() {
        if !cells.is_empty() {
            text.cells(NOMAIL[t], cells);
        }
    }
    for (name, elements) in groups(p, lines)? {
        let members: Vec<String> = elements
            .iter()
            .map(|&k| format!("M{}", p.elements[k].tag))
            .collect();
        text.group("GROUP_MA", &name, &members);
        // A group of one point cell is also a node group.
        if let [k] = elements.as_slice() {
            let e = &p.elements[*k];
            if e.nodes.len() == 1 {
                text.group("GROUP_NO", &name, &[format!("N{}", e.nodes[0])]);
            }
        }
    }
    Ok(text.finish())
}

/// The cell groups of a parsed file, each a name and its elements (indices
/// into `p.elements`, in file order); empty groups are left out.
/// - 2.x with `$PhysicalNames` (`gmlelt`, `gmeelt`): one group per name, in
///   their order, of the cells one of whose tags is the name's and whose
///   dimension is the name's; a tag without a name makes no group.
/// - Otherwise `GM<physical>` for each physical tag, in the order it first
///   appears.
fn groups(p: &Parsed, lines: &Lines<'_>) -> Result<Vec<(String, Vec<usize>)>, MeshError> {
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    if let Some(names) = &p.names {
        for (dim, tag, name) in names {
            let ks: Vec<usize> = p
                .elements
                .iter()
                .enumerate()
                .filter(|(_, e)| type_dim(e.ty) == *dim && e.tags.contains(tag))
                .map(|(k, _)| k)
                .collect();
            groups.push((name.clone(), ks));
        }
    } else {
        let mut tags: Vec<i64> = Vec::new();
        for (k, e) in p.elements.iter().enumerate() {
            for &phys in &e.physicals {
                if phys == 0 {
                    continue;
                }
                if phys >= 1_000_000 {
                    return Err(lines.error(
                        e.line,
                        1,
                        format!("physical group {phys}: code_aster names groups GM1 to GM999999"),
                    ));
                }
                match tags.iter().position(|&t| t == phys) {
                    Some(g) => groups[g].1.push(k),
                    None => {
                        tags.push(phys);
                        groups.push((format!("GM{phys}"), vec![k]));
                    }
                }
            }
        }
    }
    groups.retain(|(_, ks)| !ks.is_empty());
    Ok(groups)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(text: &str) -> Result<Mesh, MeshError> {
        let mail = gmsh_to_mail(text, Path::new("t.msh"))?;
        crate::parse_mail(&mail, Path::new("t.msh"))
    }

    #[test]
    fn node_permutations_are_code_asters() {
        assert_eq!(nuconn(11, 9), 10);
        assert_eq!(nuconn(11, 10), 9);
        assert_eq!(nuconn(17, 12), 10);
        assert_eq!(nuconn(12, 25), 23);
        assert_eq!(nuconn(19, 7), 9);
        assert_eq!(nuconn(3, 4), 4);
    }

    #[test]
    fn version_1_cells_by_type_groups_by_first_appearance() {
        // Two quads (physical 7), a segment (physical 3) written after
        // them, a point (physical 9): the segment block comes first.
        let text = "$NOD\n7\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 2 0 0\n6 2 1 0\n99 5 5 5\n$ENDNOD\n\
            $ELM\n4\n10 3 7 1 4 1 2 3 4\n11 3 7 1 4 2 5 6 3\n12 1 3 2 2 1 2\n13 15 9 3 1 6\n$ENDELM\n";
        let m = mesh(text).unwrap();
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N6"]);
        assert_eq!(m.cell_names, ["M12", "M10", "M11", "M13"]);
        let names: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["GM7", "GM3", "GM9"]);
        assert_eq!(m.groups_no.len(), 1);
        assert_eq!(m.groups_no[0].name, "GM9");
        assert_eq!(m.node_names[m.groups_no[0].members[0].0 as usize], "N6");
        assert_eq!(m.dim, 3);
    }

    #[test]
    fn version_2_reads_the_first_tag_and_drops_the_quad9_centre() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 5 \"skin\"\n$EndPhysicalNames\n\
            $Nodes\n9\n1 0 0 0\n2 2 0 0\n3 2 2 0\n4 0 2 0\n5 1 0 0\n6 2 1 0\n7 1 2 0\n8 0 1 0\n9 1 1 0\n$EndNodes\n\
            $Elements\n1\n1 10 2 5 1 1 2 3 4 5 6 7 8 9\n$EndElements\n";
        let m = mesh(text).unwrap();
        assert_eq!(m.node_count(), 8);
        assert_eq!(m.cells[0].ty, crate::CellType::QUAD8);
        // $PhysicalNames name the group (pregms reads them for 2.x).
        assert_eq!(m.groups_ma[0].name, "skin");
        // Without them, the physical tag names it.
        let bare = text.replace("$PhysicalNames\n1\n2 5 \"skin\"\n$EndPhysicalNames\n", "");
        assert!(!bare.contains("PhysicalNames"));
        assert_eq!(mesh(&bare).unwrap().groups_ma[0].name, "GM5");
    }

    #[test]
    fn version_2_physical_names_as_gmlelt_matches_them() {
        // code_aster keeps 8 characters of a name, takes a cell into a named
        // group when one of its tags (physical or elementary) is the name's
        // and its dimension is the name's, in the order of $PhysicalNames;
        // a physical tag without a name makes no group; a named point
        // alone is also a node group.
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n4\n\
            1 3 \"bottom_edge_long\"\n2 7 \"plate\"\n2 3 \"face3\"\n0 9 \"P\"\n$EndPhysicalNames\n\
            $Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n\
            $Elements\n4\n1 3 2 7 3 1 2 3 4\n2 1 2 3 1 1 2\n3 1 2 8 3 3 4\n4 15 2 9 9 2\n$EndElements\n";
        let m = mesh(text).unwrap();
        let names: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["bottom_e", "plate", "face3", "P"]);
        let cells = |g: &str| -> Vec<String> {
            let g = m.groups_ma.iter().find(|x| x.name == g).unwrap();
            g.members
                .iter()
                .map(|c| m.cell_names[c.0 as usize].clone())
                .collect()
        };
        // Segment 3 (physical 8, elementary 3) is in the dimension-1 group
        // of tag 3; the quad (elementary 3) is in the dimension-2 one.
        assert_eq!(cells("bottom_e"), ["M2", "M3"]);
        assert_eq!(cells("face3"), ["M1"]);
        assert_eq!(cells("P"), ["M4"]);
        assert_eq!(m.groups_no.len(), 1);
        assert_eq!(m.groups_no[0].name, "P");
    }

    #[test]
    fn bad_lines_are_located() {
        let e = mesh("$NOD\n2\n1 0 0 0\n2 x 0 0\n$ENDNOD\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.msh:4:3: expected a coordinate of node 2, found `x`"
        );
        let e = mesh("$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 42 1 1 1 1\n$ENDELM\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.msh:7:3: element type 42 is not one code_aster reads (GMSH types 1 to 19)"
        );
        let e = mesh("$NOD\n1\n1 0 0 0\n$ENDNOD\n$ELM\n1\n1 1 1 1 2 1 5\n$ENDELM\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.msh:7:1: element 1 uses node 5, which the file does not define"
        );
        let e = mesh("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n").unwrap_err();
        assert!(e.to_string().starts_with("t.msh:2:5: binary"), "{e}");
    }
}
