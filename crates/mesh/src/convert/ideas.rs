//! I-DEAS universal files (`.unv`) as code_aster's `PRE_IDEAS` converts
//! them (`op0047` → `stbast`, `presup`, `inistb`, `cov4v5`, `sleneu`,
//! `ecrneu`, `sleelt`, `lecelt`, `ecrelt`, `slegro`, `slecor`, `slecol`,
//! `snecol`).
//!
//! - Datasets: `2411` (also `781` and the old `15`) nodes, `2412` (also
//!   `780` and the old `71`) elements, `752`, `2417`, `2429`, `2430`,
//!   `2432`, `2435`, `2452`, `2467`, `2477` groups, `2420` (and `18`)
//!   coordinate systems; every other dataset (`151` title, `164` units…)
//!   is skipped, as code_aster does — in particular the units of `164` are
//!   not applied: the coordinates are taken as written. `735` (geometry
//!   of curves and mesh areas) and the trace lines `82`/`2431` are
//!   refused. Records are read in Fortran's fixed columns (`4I10`,
//!   `3E25.16`, `6I10`, `8I10`…).
//! - Nodes: `N<label>`, in file order, all of them (used or not);
//!   coordinates rounded to 15 significant digits as `1PE21.14` writes
//!   them; always `COOR_3D`. A node in a coordinate system whose type
//!   (dataset 2420) is not cartesian is refused, as code_aster stops
//!   (`STBTRIAS_10`); the system's transformation itself is not applied.
//! - Cells: `M<label>`, written type by type in the order of
//!   `PRE_IDEAS`'s graphic codes 1–35 (SEG2, TRIA3, TRIA6, QUAD4, QUAD8,
//!   TETRA4, TETRA10, PENTA6, PENTA15, HEXA8, HEXA20, then the discrete
//!   SEG2/POI1 of springs, dampers, masses and rigid bars, then SEG3), in
//!   file order within a type; the descriptor of each element maps to a
//!   graphic code by `cov4v5`, its nodes are put in code_aster's order by
//!   `inistb`'s permutations (e.g. a parabolic triangle's corner, middle,
//!   corner… → corners then middles). Descriptors that give a type
//!   code_aster's meshes do not have (cubic cells, thick-shell prisms and
//!   bricks) are refused.
//! - Groups: a `GROUP_NO` of the group's nodes (entity type 7) and a
//!   `GROUP_MA` of its elements (entity type 8), both named from the
//!   first 8 characters of the group's name cut at the first character
//!   that cannot continue a name (`lxscan`); a name starting with
//!   `PERMANENT` gives `GRNO<n>`/`GRMA<n>`; a name that does not start
//!   with a letter is skipped (`STBTRIAS_6`); no `GROUP_MA` for a name
//!   starting with `COUL_` (`STBTRIAS_8`).
//! - `CREA_GROUP_COUL='OUI'`: also a `GROUP_NO COUL_<c>` per node colour
//!   after each node dataset and a `GROUP_MA COUL_<c>` per element colour
//!   after each element dataset, colours 0–255 in increasing order.

use super::{fortran_real, numbered, read_back, read_text, Lines, MailText};
use crate::error::MeshError;
use crate::Mesh;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;

/// `inistb`'s cell type of each graphic code 1–35 (`""`: none).
const NOMAIL: [&str; 35] = [
    "SEG2", "TRIA3", "TRIA6", "TRIA9", "QUAD4", "QUAD8", "QUAD12", "PENTAC6", "PENTAC12",
    "PENTAC18", "HEXACE8", "HEXACE16", "HEXACE24", "TETRA4", "TETRA10", "PENTA6", "PENTA15",
    "PENTA24", "HEXA8", "HEXA20", "HEXA32", "", "", "", "", "", "", "", "SEG2", "POI1", "SEG2",
    "POI1", "POI1", "SEG2", "SEG3",
];

/// `inistb`'s permutation of a graphic code: I-DEAS node `i` (1-based) is
/// code_aster node `permut[i - 1]`; `None` keeps the file's order.
fn permutation(codgra: usize) -> Option<&'static [usize]> {
    Some(match codgra {
        3 => &[1, 4, 2, 5, 3, 6],
        6 => &[1, 5, 2, 6, 3, 7, 4, 8],
        15 => &[1, 5, 2, 6, 3, 7, 8, 9, 10, 4],
        17 => &[1, 7, 2, 8, 3, 9, 10, 11, 12, 4, 13, 5, 14, 6, 15],
        20 => &[
            1, 9, 2, 10, 3, 11, 4, 12, 13, 14, 15, 16, 5, 17, 6, 18, 7, 19, 8, 20,
        ],
        35 => &[1, 3, 2],
        _ => return None,
    })
}

/// `cov4v5`: the graphic code of an I-DEAS 5+ element descriptor.
fn graphic_code(descriptor: i64) -> Option<usize> {
    Some(match descriptor {
        171 | 11 | 21 | 23 => 1,
        91 | 61 | 41 | 51 | 74 | 81 => 2,
        22 | 24 | 172 => 35,
        92 | 62 | 42 | 52 | 72 | 82 => 3,
        93 | 63 | 43 | 53 | 73 => 4,
        94 | 64 | 44 | 54 | 71 | 84 => 5,
        95 | 65 | 55 | 45 | 75 | 85 => 6,
        96 | 66 | 46 | 56 | 76 => 7,
        101 => 8,
        102 => 9,
        103 => 10,
        104 => 11,
        105 => 12,
        106 => 13,
        111 => 14,
        118 => 15,
        112 => 16,
        113 => 17,
        114 => 18,
        115 => 19,
        116 => 20,
        117 => 21,
        136 | 137 => 29,
        138 | 139 => 30,
        141 => 31,
        142 => 32,
        161 => 33,
        121 => 34,
        _ => return None,
    })
}

/// Beam descriptors: their element record has a second line (orientation
/// node and cross sections) before the nodes.
fn is_beam(descriptor: i64) -> bool {
    matches!(descriptor, 11 | 21 | 22 | 23 | 24)
}

/// The characters `width` columns from `start` (0-based), blank beyond
/// the end of the line, as a formatted read sees them.
fn field(line: &str, start: usize, width: usize) -> String {
    line.chars().skip(start).take(width).collect()
}

/// An `Iw` field: blanks ignored (code_aster opens files `BLANK='NULL'`),
/// all blank is 0.
fn int_field(
    lines: &Lines<'_>,
    n: usize,
    line: &str,
    start: usize,
    width: usize,
    what: &str,
) -> Result<i64, MeshError> {
    let f: String = field(line, start, width)
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    if f.is_empty() {
        return Ok(0);
    }
    f.parse::<i64>().map_err(|_| {
        lines.error(
            n,
            start + 1,
            format!(
                "expected {what} in columns {}–{}, found `{f}`",
                start + 1,
                start + width
            ),
        )
    })
}

/// An `Ew.d` field (`d` implied decimals when the field has no point).
fn real_field(
    lines: &Lines<'_>,
    n: usize,
    line: &str,
    start: usize,
    width: usize,
    decimals: i32,
    what: &str,
) -> Result<f64, MeshError> {
    let f: String = field(line, start, width)
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    if f.is_empty() {
        return Ok(0.0);
    }
    let bad = || {
        lines.error(
            n,
            start + 1,
            format!(
                "expected {what} in columns {}–{}, found `{f}`",
                start + 1,
                start + width
            ),
        )
    };
    let v = fortran_real(&f).ok_or_else(bad)?;
    if f.contains('.') {
        Ok(v)
    } else {
        // No point: the last `d` digits of the mantissa are decimals.
        Ok(v / 10f64.powi(decimals))
    }
}

/// The first six characters of a line are `    -1` (the dataset
/// delimiter as `presup` compares it).
fn is_delimiter(line: &str) -> bool {
    let mut six = field(line, 0, 6);
    while six.chars().count() < 6 {
        six.push(' ');
    }
    six == "    -1"
}

/// A group of a group dataset, as `slegro` writes it.
struct IdeasGroup {
    name: GroupName,
    line: usize,
    nodes: Vec<(String, i64)>,
    cells: Vec<(String, i64)>,
    write_cells: bool,
}

/// A cell as written: its name and its nodes' names.
type NamedCell = (String, Vec<String>);

/// What the conversion has collected, in the order code_aster writes it.
enum Block {
    Nodes(Vec<(String, [f64; 3])>),
    /// The cells of an element dataset by graphic code.
    Cells(Vec<(usize, Vec<NamedCell>)>),
    NodeGroup(String, Vec<String>),
    CellGroup(String, Vec<String>),
}

/// Reads an I-DEAS universal file as `LIRE_MAILLAGE(FORMAT='IDEAS')` does.
pub fn read_ideas(path: &Path) -> Result<Mesh, MeshError> {
    read_ideas_with(path, false)
}

/// Reads an I-DEAS universal file, with `CREA_GROUP_COUL='OUI'`'s colour
/// groups when `colour_groups`.
pub fn read_ideas_with(path: &Path, colour_groups: bool) -> Result<Mesh, MeshError> {
    let text = read_text(path)?;
    read_back(&ideas_to_mail(&text, path, colour_groups)?, path)
}

/// The ASTER text `PRE_IDEAS` writes for an I-DEAS universal file (`path`
/// is for messages).
pub fn ideas_to_mail(text: &str, path: &Path, colour_groups: bool) -> Result<String, MeshError> {
    let mut lines = Lines::new(text, path);
    // The first delimiter.
    loop {
        match lines.try_next() {
            Some((_, l)) if is_delimiter(l) => break,
            Some(_) => {}
            None => {
                return Err(lines.error(
                    1,
                    1,
                    "not an I-DEAS universal file: no line `    -1` opens a dataset".into(),
                ))
            }
        }
    }
    let mut conv = Conversion {
        colour_groups,
        ..Conversion::default()
    };
    let mut read_any = false;
    while let Some((n, l)) = lines.try_next() {
        // `read(iunv,'(I6)')`: a line that is not a number is dataset 0.
        let dataset = int_field(&lines, n, l, 0, 6, "a dataset number").unwrap_or(0);
        match dataset {
            -1 => {}
            18 | 2420 => conv.systems(&mut lines, dataset)?,
            15 | 781 | 2411 => {
                conv.nodes(&mut lines, dataset)?;
                read_any = true;
            }
            71 | 780 | 2412 => {
                conv.elements(&mut lines, dataset)?;
                read_any = true;
            }
            82 | 2431 => {
                return Err(lines.error(
                    n,
                    1,
                    format!("dataset {dataset} (trace lines) is not supported: mesh the lines as elements (dataset 2412)"),
                ))
            }
            735 => {
                return Err(lines.error(
                    n,
                    1,
                    "dataset 735 (nodes and elements attached to curves, mesh areas and volumes) is not supported: export groups (dataset 2467 or 2477)".into(),
                ))
            }
            752 | 2417 | 2428 | 2429 | 2430 | 2432 | 2435 | 2452 | 2467 | 2477 => {
                if dataset == 2428 {
                    return Err(lines.error(
                        n,
                        1,
                        "dataset 2428 is one code_aster lists but does not read: export groups as dataset 2467 or 2477".into(),
                    ));
                }
                conv.groups(&mut lines, dataset)?;
                read_any = true;
            }
            _ => {
                // An unknown dataset: skipped up to its delimiter.
                while let Some((_, l)) = lines.try_next() {
                    if is_delimiter(l) {
                        break;
                    }
                }
            }
        }
    }
    if !read_any {
        return Err(lines.error(
            lines.lines.len().max(1),
            1,
            "no node, element or group dataset (2411, 2412, 2467, 2477…) in the file (code_aster's STBTRIAS_1)".into(),
        ));
    }
    conv.write()
}

#[derive(Default)]
struct Conversion {
    colour_groups: bool,
    /// Coordinate system label → type (0 cartesian, 1 cylindrical, 2
    /// spherical), once a system dataset was read.
    systems: Option<HashMap<i64, i64>>,
    blocks: Vec<Block>,
    node_labels: HashSet<i64>,
    cell_labels: HashSet<i64>,
    group_ma_names: HashSet<String>,
    group_no_names: HashSet<String>,
}

impl Conversion {
    /// `slecor`: the type of each coordinate system.
    fn systems(&mut self, lines: &mut Lines<'_>, dataset: i64) -> Result<(), MeshError> {
        let mut systems = HashMap::new();
        let mut first = true;
        loop {
            let (n, l) = lines.next("a coordinate system or `    -1`")?;
            if is_delimiter(l) {
                break;
            }
            let (n, l) = if first && dataset == 2420 {
                // The part's UID line, then its name, then the record.
                lines.next("the part name")?;
                lines.next("a coordinate system record")?
            } else {
                (n, l)
            };
            let label = int_field(lines, n, l, 0, 10, "a coordinate system label")?;
            let kind = int_field(lines, n, l, 10, 10, "a coordinate system type")?;
            systems.insert(label, kind);
            let extra = if dataset == 2420 { 5 } else { 3 };
            for _ in 0..extra {
                lines.next("the coordinate system's name and transformation")?;
            }
            first = false;
        }
        self.systems = Some(systems);
        Ok(())
    }

    /// `sleneu` + `ecrneu` (+ `snecol`).
    fn nodes(&mut self, lines: &mut Lines<'_>, dataset: i64) -> Result<(), MeshError> {
        let mut nodes = Vec::new();
        let mut colours: BTreeMap<i64, Vec<String>> = BTreeMap::new();
        loop {
            let (n, l) = lines.next("a node record or `    -1`")?;
            if int_field(lines, n, l, 4, 2, "a node record").ok() == Some(-1) {
                break;
            }
            let label = int_field(lines, n, l, 0, 10, "a node label")?;
            let system = int_field(lines, n, l, 10, 10, "a coordinate system label")?;
            let colour = int_field(lines, n, l, 30, 10, "a colour")?;
            let xyz = if dataset == 15 {
                let mut xyz = [0.0; 3];
                for (k, x) in xyz.iter_mut().enumerate() {
                    *x = real_field(lines, n, l, 40 + 13 * k, 13, 6, "a coordinate")?;
                }
                xyz
            } else {
                let (m, c) = lines.next("the coordinates of a node")?;
                let mut xyz = [0.0; 3];
                for (k, x) in xyz.iter_mut().enumerate() {
                    *x = real_field(lines, m, c, 25 * k, 25, 16, "a coordinate")?;
                }
                xyz
            };
            if let Some(systems) = &self.systems {
                let kind = systems.get(&system).copied().unwrap_or(0);
                if kind != 0 {
                    return Err(lines.error(
                        n,
                        11,
                        format!(
                            "node {label} is given in coordinate system {system}, which is {}: code_aster reads cartesian coordinates only (STBTRIAS_10)",
                            match kind {
                                1 => "cylindrical",
                                2 => "spherical",
                                _ => "not cartesian",
                            }
                        ),
                    ));
                }
            }
            let name = numbered('N', label, lines, n, 1)?;
            if !self.node_labels.insert(label) {
                return Err(lines.error(n, 1, format!("node {label} is defined twice")));
            }
            if (0..256).contains(&colour) {
                colours.entry(colour).or_default().push(name.clone());
            }
            nodes.push((name, xyz));
        }
        self.blocks.push(Block::Nodes(nodes));
        if self.colour_groups {
            for (c, members) in colours {
                self.colour_group(false, c, members);
            }
        }
        Ok(())
    }

    fn colour_group(&mut self, cells: bool, colour: i64, members: Vec<String>) {
        let name = format!("COUL_{colour}");
        if cells {
            self.group_ma_names.insert(name.clone());
            self.blocks.push(Block::CellGroup(name, members));
        } else {
            self.group_no_names.insert(name.clone());
            self.blocks.push(Block::NodeGroup(name, members));
        }
    }

    /// `sleelt` + `lecelt` + `ecrelt` (+ `slecol`).
    fn elements(&mut self, lines: &mut Lines<'_>, dataset: i64) -> Result<(), MeshError> {
        let mut by_type: BTreeMap<usize, Vec<NamedCell>> = BTreeMap::new();
        let mut colours: BTreeMap<i64, Vec<String>> = BTreeMap::new();
        loop {
            let (n, l) = lines.next("an element record or `    -1`")?;
            if int_field(lines, n, l, 0, 6, "an element record").ok() == Some(-1) {
                break;
            }
            let label = int_field(lines, n, l, 0, 10, "an element label")?;
            let (codgra, colour, count, descriptor) = match dataset {
                71 => {
                    let g = int_field(lines, n, l, 10, 10, "a graphic code")?;
                    (
                        usize::try_from(g).ok().filter(|g| (1..=35).contains(g)),
                        int_field(lines, n, l, 50, 10, "a colour")?,
                        int_field(lines, n, l, 60, 10, "a node count")?,
                        g,
                    )
                }
                _ => {
                    let d = int_field(lines, n, l, 10, 10, "an element descriptor")?;
                    let (colour_at, count_at) = if dataset == 780 { (60, 70) } else { (40, 50) };
                    (
                        graphic_code(d),
                        int_field(lines, n, l, colour_at, 10, "a colour")?,
                        int_field(lines, n, l, count_at, 10, "a node count")?,
                        d,
                    )
                }
            };
            let Some(codgra) = codgra else {
                return Err(lines.error(
                    n,
                    11,
                    format!(
                        "element {label}: {} {descriptor} is not one code_aster's PRE_IDEAS converts",
                        if dataset == 71 { "graphic code" } else { "descriptor" }
                    ),
                ));
            };
            if dataset != 71 && is_beam(descriptor) {
                lines.next("the beam record of an element")?;
            }
            let ty = NOMAIL[codgra - 1];
            let Some(cell_type) = crate::CellType::from_name(ty) else {
                return Err(lines.error(
                    n,
                    11,
                    format!(
                        "element {label}: {} {descriptor} is PRE_IDEAS's {}, a cell type code_aster's meshes do not have",
                        if dataset == 71 { "graphic code" } else { "descriptor" },
                        if ty.is_empty() { "ignored type" } else { ty }
                    ),
                ));
            };
            if count != cell_type.node_count() as i64 {
                return Err(lines.error(
                    n,
                    match dataset {
                        780 => 71,
                        71 => 61,
                        _ => 51,
                    },
                    format!(
                        "element {label}: {count} nodes, but its descriptor {descriptor} makes a {ty} ({} nodes)",
                        cell_type.node_count()
                    ),
                ));
            }
            // `read(iunv,'(8I10)')`: eight labels a line.
            let count = count as usize;
            let mut read = Vec::with_capacity(count);
            while read.len() < count {
                let (m, c) = lines.next("the nodes of an element")?;
                for k in 0..8.min(count - read.len()) {
                    read.push((
                        int_field(lines, m, c, 10 * k, 10, "a node label")?,
                        m,
                        10 * k + 1,
                    ));
                }
            }
            let mut nodes = vec![String::new(); count];
            for (i, &(node, m, col)) in read.iter().enumerate() {
                if !self.node_labels.contains(&node) {
                    return Err(lines.error(
                        m,
                        col,
                        format!("element {label} uses node {node}, which no earlier node dataset defines"),
                    ));
                }
                let at = permutation(codgra).map_or(i, |p| p[i] - 1);
                nodes[at] = numbered('N', node, lines, m, col)?;
            }
            let name = numbered('M', label, lines, n, 1)?;
            if !self.cell_labels.insert(label) {
                return Err(lines.error(n, 1, format!("element {label} is defined twice")));
            }
            if (0..256).contains(&colour) {
                colours.entry(colour).or_default().push(name.clone());
            }
            by_type.entry(codgra).or_default().push((name, nodes));
        }
        self.blocks
            .push(Block::Cells(by_type.into_iter().collect()));
        if self.colour_groups {
            for (c, members) in colours {
                self.colour_group(true, c, members);
            }
        }
        Ok(())
    }

    /// `slegro`: the groups of a group dataset.
    fn groups(&mut self, lines: &mut Lines<'_>, dataset: i64) -> Result<(), MeshError> {
        let (count_at, per_line) = match dataset {
            752 => (50, 4),
            2417 => (60, 4),
            2429 | 2430 | 2432 => (70, 4),
            _ => (70, 2),
        };
        loop {
            let (n, l) = lines.next("a group record or `    -1`")?;
            if int_field(lines, n, l, 0, 6, "a group record").ok() == Some(-1) {
                break;
            }
            let number = int_field(lines, n, l, 0, 10, "a group number")?;
            let entities = int_field(lines, n, l, count_at, 10, "an entity count")?;
            let (name_line, raw) = lines.next("the name of a group")?;
            let mut members: Vec<(i64, i64, usize, usize)> = Vec::new();
            let entities = usize::try_from(entities).map_err(|_| {
                lines.error(
                    n,
                    count_at + 1,
                    format!("group {number}: {entities} entities"),
                )
            })?;
            let mut left = entities;
            while left > 0 {
                let (m, c) = lines.next("the entities of a group")?;
                for k in 0..per_line.min(left) {
                    let start = if per_line == 4 { 20 * k } else { 40 * k };
                    let kind = int_field(lines, m, c, start, 10, "an entity type")?;
                    let tag = int_field(lines, m, c, start + 10, 10, "an entity tag")?;
                    members.push((kind, tag, m, start + 11));
                }
                left -= per_line.min(left);
            }
            let Some(name) = group_name(lines, name_line, raw, number)? else {
                continue;
            };
            let write_cells = !matches!(&name, GroupName::Named(n) if n.starts_with("COUL_"));
            let mut group = IdeasGroup {
                name,
                line: name_line,
                nodes: Vec::new(),
                cells: Vec::new(),
                write_cells,
            };
            for (kind, tag, m, col) in members {
                match kind {
                    7 => {
                        if !self.node_labels.contains(&tag) {
                            return Err(lines.error(
                                m,
                                col,
                                format!(
                                    "group `{}`: no node {tag} in the file",
                                    group.name.node_group()
                                ),
                            ));
                        }
                        group.nodes.push((numbered('N', tag, lines, m, col)?, tag));
                    }
                    8 => {
                        if !self.cell_labels.contains(&tag) {
                            return Err(lines.error(
                                m,
                                col,
                                format!(
                                    "group `{}`: no element {tag} in the file",
                                    group.name.cell_group()
                                ),
                            ));
                        }
                        group.cells.push((numbered('M', tag, lines, m, col)?, tag));
                    }
                    _ => {}
                }
            }
            self.push_group(lines, group)?;
        }
        Ok(())
    }

    fn push_group(&mut self, lines: &Lines<'_>, g: IdeasGroup) -> Result<(), MeshError> {
        if !g.nodes.is_empty() {
            let name = g.name.node_group();
            if !self.group_no_names.insert(name.clone()) {
                return Err(lines.error(g.line, 1, format!("node group `{name}` is defined twice (code_aster refuses a second group of the same name)")));
            }
            let members = g.nodes.iter().map(|(s, _)| s.clone()).collect();
            self.blocks.push(Block::NodeGroup(name, members));
        }
        if !g.cells.is_empty() && g.write_cells {
            let name = g.name.cell_group();
            if !self.group_ma_names.insert(name.clone()) {
                return Err(lines.error(g.line, 1, format!("cell group `{name}` is defined twice (code_aster refuses a second group of the same name)")));
            }
            let members = g.cells.iter().map(|(s, _)| s.clone()).collect();
            self.blocks.push(Block::CellGroup(name, members));
        }
        Ok(())
    }

    fn write(self) -> Result<String, MeshError> {
        let mut text = MailText::new("AUTEUR=INTERFACE_IDEAS");
        for b in &self.blocks {
            match b {
                Block::Nodes(nodes) => {
                    text.coords(3, nodes.iter().map(|(n, xyz)| (n.clone(), &xyz[..])));
                }
                Block::Cells(types) => {
                    for (codgra, cells) in types {
                        text.cells(NOMAIL[codgra - 1], cells);
                    }
                }
                Block::NodeGroup(name, members) => text.group("GROUP_NO", name, members),
                Block::CellGroup(name, members) => text.group("GROUP_MA", name, members),
            }
        }
        Ok(text.finish())
    }
}

/// A group's name: `PERMANENT…` groups are named from their number.
#[derive(Debug, PartialEq)]
enum GroupName {
    Permanent(i64),
    Named(String),
}

impl GroupName {
    fn node_group(&self) -> String {
        match self {
            GroupName::Permanent(n) => format!("GRNO{n}"),
            GroupName::Named(s) => s.clone(),
        }
    }

    fn cell_group(&self) -> String {
        match self {
            GroupName::Permanent(n) => format!("GRMA{n}"),
            GroupName::Named(s) => s.clone(),
        }
    }
}

/// `slegro`'s group name: `GRNO<number>`/`GRMA<number>` for a `PERMANENT…` group, else the name's first eight characters cut at the
/// first character that does not continue a name (`lxscan`), `None` for
/// a name that does not start with a letter (skipped, `STBTRIAS_6`).
fn group_name(
    lines: &Lines<'_>,
    line: usize,
    raw: &str,
    number: i64,
) -> Result<Option<GroupName>, MeshError> {
    let full = field(raw, 0, 20);
    if full.starts_with("PERMANENT") {
        if !(0..=9999).contains(&number) {
            return Err(lines.error(line, 1, format!("group {number}: code_aster names a PERMANENT group GRNO/GRMA with at most 4 digits")));
        }
        return Ok(Some(GroupName::Permanent(number)));
    }
    let eight: Vec<char> = full.chars().take(8).collect();
    let first = eight.iter().position(|c| *c != ' ' && *c != '\t');
    let Some(first) = first else {
        return Ok(None);
    };
    if !eight[first].is_ascii_alphabetic() {
        return Ok(None);
    }
    let mut len = 0;
    for &c in &eight[first..] {
        if c.is_ascii_alphanumeric() || c == '_' {
            len += 1;
        } else if c == '\'' || !(c == ' ' || c == '\t' || "+-.=():;,%&*/!".contains(c)) {
            // A quote or a character outside the lexer's classes: not a name.
            return Ok(None);
        } else {
            break;
        }
    }
    if first > 0 {
        return Err(lines.error(
            line,
            1,
            "a group name that starts with blanks: code_aster names it from the blanks (rename the group)".into(),
        ));
    }
    Ok(Some(GroupName::Named(eight[..len].iter().collect())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CellType;

    fn mesh(text: &str) -> Result<Mesh, MeshError> {
        let mail = ideas_to_mail(text, Path::new("t.unv"), false)?;
        crate::parse_mail(&mail, Path::new("t.unv"))
    }

    const NODES: &str = "    -1\n  2411\n         1         1         1        11\n   0.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00\n         2         1         1        11\n   1.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00\n         3         1         1        11\n   1.0000000000000000D+00   1.0000000000000000D+00   0.0000000000000000D+00\n         4         1         1        11\n   0.0000000000000000D+00   1.0000000000000000D+00   0.0000000000000000D+00\n         5         1         1        11\n   5.0000000000000000D-01   0.0000000000000000D+00   0.0000000000000000D+00\n    -1\n";

    #[test]
    fn permutations_put_middles_after_corners() {
        // A parabolic triangle 1 5 2 . . . in I-DEAS order: corner, middle, corner…
        let text = format!(
            "{NODES}    -1\n  2412\n         7        92         1         1         7         6\n         1         5         2         3         4         4\n         8        21         1         1         7         2\n         0         1         1\n         2         3\n    -1\n"
        );
        let m = mesh(&text).unwrap();
        // SEG2 (code 1) before TRIA6 (code 3).
        assert_eq!(m.cell_names, ["M8", "M7"]);
        assert_eq!(m.cells[1].ty, CellType::TRIA6);
        let names: Vec<&str> = m.cells[1]
            .nodes
            .iter()
            .map(|n| m.node_names[n.0 as usize].as_str())
            .collect();
        assert_eq!(names, ["N1", "N2", "N4", "N5", "N3", "N4"]);
    }

    #[test]
    fn group_names_as_slegro_makes_them() {
        let l = Lines::new("", Path::new("t"));
        let named = |raw: &str| match group_name(&l, 1, raw, 12).unwrap() {
            Some(GroupName::Named(s)) => Some(s),
            Some(GroupName::Permanent(n)) => Some(format!("#{n}")),
            None => None,
        };
        assert_eq!(named("BORD_GAU").as_deref(), Some("BORD_GAU"));
        assert_eq!(named("TRIA ").as_deref(), Some("TRIA"));
        assert_eq!(named("LONGNAME_IS_CUT").as_deref(), Some("LONGNAME"));
        assert_eq!(named("A.B").as_deref(), Some("A"));
        assert_eq!(named("1ABC"), None);
        assert_eq!(named("A#B"), None);
        assert_eq!(named("PERMANENT GROUP").as_deref(), Some("#12"));
        assert!(group_name(&l, 1, " AB", 1).is_err());
    }

    #[test]
    fn delimiters_compare_six_characters() {
        assert!(is_delimiter("    -1"));
        assert!(is_delimiter("    -1   trailing"));
        assert!(!is_delimiter("   -1"));
    }

    #[test]
    fn malformed_records_are_located() {
        // Fixed columns: the second field is columns 26–50, blanks ignored.
        let e = mesh("    -1\n  2411\n         1         1         1        11\n   0.0000000000000000D+00   x.0   0.0\n    -1\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.unv:4:26: expected a coordinate in columns 26–50, found `x.00.0`"
        );
        let e = mesh("    -1\n  2411\n         1         1         1        11\n").unwrap_err();
        assert!(
            e.to_string()
                .contains("the file ends where the coordinates of a node was expected"),
            "{e}"
        );
        let text = format!(
            "{NODES}    -1\n  2412\n         1        93         1         1         7         9\n"
        );
        let e = mesh(&text).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.unv:16:11: element 1: descriptor 93 is PRE_IDEAS's TRIA9, a cell type code_aster's meshes do not have"
        );
        let text = format!("{NODES}    -1\n  2412\n         1        94         1         1         7         4\n         1         2         3         9\n    -1\n");
        let e = mesh(&text).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.unv:17:31: element 1 uses node 9, which no earlier node dataset defines"
        );
        let e = mesh("    -1\n   151\ntitle\n    -1\n").unwrap_err();
        assert!(e.to_string().contains("STBTRIAS_1"), "{e}");
        let e = mesh("hello\n").unwrap_err();
        assert!(
            e.to_string().contains("not an I-DEAS universal file"),
            "{e}"
        );
    }

    #[test]
    fn cylindrical_nodes_are_refused() {
        let text = "    -1\n  2420\n         1\nPart\n         1         1         8\nCS1\n 1\n 2\n 3\n 4\n    -1\n    -1\n  2411\n         1         1         1        11\n                      0.0\n    -1\n";
        let e = mesh(text).unwrap_err();
        assert!(e.to_string().contains("cylindrical"), "{e}");
    }
}
