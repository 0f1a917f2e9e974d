//! GIBI / Cast3M `SAUVER FORMAT` files (`.mgib`) as code_aster's `PRE_GIBI`
//! converts them (`op0049`, `gilir2`, `gilig0`…`gilig3`, `gilio2`,
//! `gicnx2`, `gidoma`, `giecas`, `giecma`, `giinco`).
//!
//! The file is a sequence of records (`ENREGISTREMENT DE TYPE n`); type 2
//! records are piles of objects: pile 1 the meshes (simple ones: a cell type
//! and its cells; compound ones: a list of sub-meshes), pile 32 the named
//! points and the point → coordinate indirection, pile 33 the coordinates
//! (with a density per point), pile 0 the older form of points.
//!
//! - Nodes: every coordinate index the indirection reaches, in increasing
//!   order, named `N<index>`.
//! - Cells: numbered across all simple meshes in pile order; a cell is
//!   written (as `M<number>`) only if its mesh is named or is a sub-mesh of
//!   a named mesh; a cell with the same nodes in the same order as an
//!   earlier cell is written once (the first written copy), and every group
//!   refers to that copy.
//! - Groups: `GROUP_NO` for each named point, `GROUP_MA` for each name of a
//!   mesh (a mesh may have several), in mesh order, with the cells of the
//!   mesh or of its sub-meshes; names starting with `#` are skipped.
//! - Nodes are reordered to code_aster's numbering (`giinco`).

use super::{fortran_real, read_back, read_text, Lines, MailText};
use crate::error::MeshError;
use crate::Mesh;
use std::collections::HashMap;
use std::path::Path;

/// GIBI cell types: (GIBI code, GIBI name, code_aster name, node order).
/// Node `k` of the code_aster cell is GIBI node `order[k]` (1-based).
const TYPES: [(i64, &str, &str, &[usize]); 17] = [
    (1, "POI1", "POI1", &[1]),
    (2, "SEG2", "SEG2", &[1, 2]),
    (3, "SEG3", "SEG3", &[1, 3, 2]),
    (4, "TRI3", "TRIA3", &[1, 2, 3]),
    (6, "TRI6", "TRIA6", &[1, 3, 5, 2, 4, 6]),
    (8, "QUA4", "QUAD4", &[1, 2, 3, 4]),
    (10, "QUA8", "QUAD8", &[1, 3, 5, 7, 2, 4, 6, 8]),
    (11, "QUA9", "QUAD9", &[1, 3, 5, 7, 2, 4, 6, 8, 9]),
    (14, "CUB8", "HEXA8", &[1, 2, 3, 4, 5, 6, 7, 8]),
    (
        15,
        "CU20",
        "HEXA20",
        &[
            1, 3, 5, 7, 13, 15, 17, 19, 2, 4, 6, 8, 9, 10, 11, 12, 14, 16, 18, 20,
        ],
    ),
    (
        33,
        "CU27",
        "HEXA27",
        &[
            1, 3, 5, 7, 13, 15, 17, 19, 2, 4, 6, 8, 9, 10, 11, 12, 14, 16, 18, 20, 25, 21, 22, 23,
            24, 26, 27,
        ],
    ),
    (16, "PRI6", "PENTA6", &[1, 2, 3, 4, 5, 6]),
    (
        17,
        "PR15",
        "PENTA15",
        &[1, 3, 5, 10, 12, 14, 2, 4, 6, 7, 8, 9, 11, 13, 15],
    ),
    (23, "TET4", "TETRA4", &[1, 2, 3, 4]),
    (24, "TE10", "TETRA10", &[1, 3, 5, 10, 2, 4, 6, 7, 8, 9]),
    (25, "PYR5", "PYRAM5", &[1, 2, 3, 4, 5]),
    (
        26,
        "PY13",
        "PYRAM13",
        &[1, 3, 5, 7, 13, 2, 4, 6, 8, 9, 10, 11, 12],
    ),
];

/// One object of pile 1.
struct Object {
    /// Index in [`TYPES`] (simple meshes).
    ty: Option<usize>,
    sub: Vec<usize>,
    nbno: usize,
    nbele: usize,
    /// Connectivity, `nbno` GIBI point numbers per cell.
    connex: Vec<i64>,
    line: usize,
}

/// What the records hold.
#[derive(Default)]
struct Gibi {
    ndim: usize,
    /// Pile 1: names and the objects they name (1-based), then the objects.
    object_names: Vec<(String, usize)>,
    objects: Vec<Object>,
    /// Named points and their (indirected) coordinate index.
    point_names: Vec<(String, i64)>,
    /// Point number → coordinate index (1-based).
    indirect: Option<Vec<i64>>,
    /// Coordinates, `ndim` per point.
    coords: Vec<f64>,
    /// Level of the file (`NIVEAU`): integer layout of the records.
    niv: i64,
}

/// Reads a GIBI file as `LIRE_MAILLAGE(FORMAT='GIBI')` does.
pub fn read_gibi(path: &Path) -> Result<Mesh, MeshError> {
    let text = read_text(path)?;
    read_back(&gibi_to_mail(&text, path)?, path)
}

/// The ASTER text `PRE_GIBI` writes for a GIBI file (`path` is for messages).
pub fn gibi_to_mail(text: &str, path: &Path) -> Result<String, MeshError> {
    let mut lines = Lines::new(text, path);
    let g = parse(&mut lines)?;
    write(&g, &lines)
}

/// The columns `[start, end)` of a fixed-width field (0-based, in chars).
fn field(line: &str, start: usize, width: usize) -> String {
    line.chars().skip(start).take(width).collect()
}

/// Integers in fixed-width fields (`lead` blank columns, then `per_line`
/// fields of `width`, `gap` blanks after each), `count` of them over as
/// many lines as it takes; a blank field is 0 (Fortran).
fn ints(
    lines: &mut Lines<'_>,
    count: usize,
    layout: (usize, usize, usize, usize),
    what: &str,
) -> Result<Vec<i64>, MeshError> {
    let (lead, per_line, width, gap) = layout;
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let (n, l) = lines.next(what)?;
        for k in 0..per_line.min(count - out.len()) {
            let start = lead + k * (width + gap);
            let f = field(l, start, width);
            let t = f.trim();
            let v = if t.is_empty() {
                0
            } else {
                t.parse::<i64>().map_err(|_| {
                    lines.error(
                        n,
                        start + 1,
                        format!("{what}: expected an integer, found `{t}`"),
                    )
                })?
            };
            out.push(v);
        }
    }
    Ok(out)
}

/// Names in fields `8(1x,a8)`, `count` of them.
fn names(lines: &mut Lines<'_>, count: usize, what: &str) -> Result<Vec<String>, MeshError> {
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let (_, l) = lines.next(what)?;
        for k in 0..8.min(count - out.len()) {
            out.push(field(l, 1 + 9 * k, 8).trim().to_string());
        }
    }
    Ok(out)
}

/// Reals three per line (`3(1x,d21.14)`), `count` of them.
fn reals(lines: &mut Lines<'_>, count: usize) -> Result<Vec<f64>, MeshError> {
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let (n, l) = lines.next("coordinates")?;
        for k in 0..3.min(count - out.len()) {
            let start = 1 + 22 * k;
            let f = field(l, start, 21);
            let t = f.trim();
            let v = if t.is_empty() {
                0.0
            } else {
                fortran_real(t).ok_or_else(|| {
                    lines.error(n, start + 1, format!("expected a coordinate, found `{t}`"))
                })?
            };
            out.push(v);
        }
    }
    Ok(out)
}

impl Gibi {
    /// Integer layout of the piles: 16 fields of 5 at level 3, else 10 of 8.
    fn int_layout(&self) -> (usize, usize, usize, usize) {
        if self.niv == 3 {
            (0, 16, 5, 0)
        } else {
            (0, 10, 8, 0)
        }
    }
}

fn parse(lines: &mut Lines<'_>) -> Result<Gibi, MeshError> {
    let mut g = Gibi::default();
    // op0049: the first record gives the level.
    let (n1, first) = lines.next("a GIBI record")?;
    let (_, second) = lines.next("a GIBI record")?;
    if field(second, 0, 8) == "MAILLAGE" && field(second, 9, 9) == "PROVENANT" {
        return Err(lines.error(
            2,
            1,
            "a mesh of GIBI's old `SORTIR` format: save it with `SAUVER FORMAT`".to_string(),
        ));
    }
    if field(first, 1, 14) != "ENREGISTREMENT" {
        return Err(lines.error(
            n1,
            2,
            "not a GIBI `SAUVER FORMAT` file: it starts with no `ENREGISTREMENT DE TYPE`"
                .to_string(),
        ));
    }
    if field(second, 1, 6) == "NIVEAU" {
        g.niv = field(second, 7, 4).trim().parse().unwrap_or(0);
    }
    lines.pos = 0;
    let mut named_points_read = false;
    let mut pile_lengths: Option<(usize, usize)> = None;
    while let Some((n, l)) = lines.try_next() {
        if field(l, 1, 14) != "ENREGISTREMENT" || field(l, 19, 4) != "TYPE" {
            continue;
        }
        match field(l, 26, 1).as_str() {
            "4" => {
                let (dn, d) = lines.next("the NIVEAU line")?;
                let ndim = field(d, 39, 4).trim().parse::<usize>().map_err(|_| {
                    lines.error(
                        dn,
                        40,
                        format!("expected the dimension, found `{}`", field(d, 39, 4)),
                    )
                })?;
                if !(1..=3).contains(&ndim) {
                    return Err(lines.error(
                        dn,
                        40,
                        format!("dimension {ndim}: expected 1, 2 or 3"),
                    ));
                }
                g.ndim = ndim;
                lines.next("the DENSITE line")?;
            }
            "7" => {
                lines.next("the record")?;
                lines.next("the record")?;
            }
            "5" => break,
            "2" => {
                let (hn, h) = lines.next("a pile header")?;
                let (w, gap) = if g.niv <= 6 { (5, 11) } else { (8, 11) };
                let pile: i64 = field(h, 12, 4)
                    .trim()
                    .parse()
                    .map_err(|_| lines.error(hn, 13, "expected a pile number".to_string()))?;
                let num = |start: usize| -> Result<usize, MeshError> {
                    field(h, start, w).trim().parse::<usize>().map_err(|_| {
                        lines.error(hn, start + 1, "expected an object count".to_string())
                    })
                };
                let nbobno = num(34)?;
                let nboblu = num(34 + w + gap)?;
                let _ = n;
                match pile {
                    0 => {
                        named_points_read = true;
                        read_points(lines, &mut g, nbobno)?;
                        let values = reals(lines, nboblu * (g.ndim + 1))?;
                        g.coords = strip_density(&values, g.ndim, nboblu);
                        if g.indirect.is_none() {
                            g.indirect = Some((1..=nboblu as i64).collect());
                        }
                    }
                    32 if !named_points_read => {
                        read_points(lines, &mut g, nbobno)?;
                        let layout = g.int_layout();
                        let cn = lines.pos + 1;
                        // Always `10(i8)`, whatever the level (`gilig3`).
                        let nbobj = ints(lines, 1, (0, 10, 8, 0), "the number of points")?[0];
                        if nbobj != nboblu as i64 {
                            return Err(lines.error(
                                cn,
                                1,
                                format!("pile 32 announces {nboblu} points and lists {nbobj}"),
                            ));
                        }
                        let indirect = ints(lines, nboblu, layout, "the point indirection")?;
                        for p in &mut g.point_names {
                            let i = usize::try_from(p.1 - 1)
                                .ok()
                                .filter(|&i| i < indirect.len());
                            p.1 = match i {
                                Some(i) => indirect[i],
                                None => {
                                    return Err(lines.error(
                                        cn,
                                        1,
                                        format!("named point `{}` has no number {}", p.0, p.1),
                                    ))
                                }
                            };
                        }
                        g.indirect = Some(indirect);
                    }
                    33 => {
                        let (vn, v) = lines.next("the number of coordinate values")?;
                        let nbval: usize = field(v, 1, 7).trim().parse().map_err(|_| {
                            lines.error(
                                vn,
                                2,
                                "expected the number of coordinate values".to_string(),
                            )
                        })?;
                        let npoints = nbval / (g.ndim + 1).max(1);
                        let values = reals(lines, nbval)?;
                        g.coords = strip_density(&values, g.ndim, npoints);
                    }
                    1 => {
                        pile_lengths = Some((nbobno, nboblu));
                        read_objects(lines, &mut g, nbobno, nboblu)?;
                    }
                    _ => {}
                }
            }
            _ => {}
        }
    }
    if pile_lengths.is_none() {
        return Err(lines.error(1, 1, "no mesh in the file (no pile 1)".to_string()));
    }
    if g.indirect.is_none() {
        return Err(lines.error(1, 1, "no points in the file (no pile 32 or 0)".to_string()));
    }
    Ok(g)
}

/// Coordinates without the density that follows each point.
fn strip_density(values: &[f64], ndim: usize, npoints: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(npoints * ndim);
    for p in 0..npoints {
        out.extend_from_slice(&values[p * (ndim + 1)..p * (ndim + 1) + ndim]);
    }
    out
}

/// Named points: names, then their numbers.
fn read_points(lines: &mut Lines<'_>, g: &mut Gibi, count: usize) -> Result<(), MeshError> {
    if count == 0 {
        return Ok(());
    }
    let ns = names(lines, count, "point names")?;
    let nums = ints(lines, count, g.int_layout(), "point numbers")?;
    g.point_names = ns.into_iter().zip(nums).collect();
    Ok(())
}

/// Pile 1: object names, their numbers, then each object (`gilig0`, `gilio2`).
fn read_objects(
    lines: &mut Lines<'_>,
    g: &mut Gibi,
    nbobno: usize,
    nbobj: usize,
) -> Result<(), MeshError> {
    let ns = names(lines, nbobno, "mesh names")?;
    // `16(1x,i4)` at level 3, else `1x,10(i7,1x)`.
    let layout = if g.niv == 3 {
        (1, 16, 4, 1)
    } else {
        (1, 10, 7, 1)
    };
    let nums = ints(lines, nbobno, layout, "mesh numbers")?;
    for (name, num) in ns.into_iter().zip(nums) {
        let i = usize::try_from(num)
            .ok()
            .filter(|&i| (1..=nbobj).contains(&i));
        let Some(i) = i else {
            return Err(lines.error(
                lines.pos,
                1,
                format!("mesh `{name}` is object {num}; pile 1 has {nbobj}"),
            ));
        };
        g.object_names.push((name, i));
    }
    let layout = g.int_layout();
    for _ in 0..nbobj {
        let line = lines.pos + 1;
        let h = ints(lines, 5, layout, "a mesh header")?;
        let (itypel, nbsoob, nbref, nbno, nbele) = (h[0], h[1], h[2], h[3], h[4]);
        let count = |v: i64| usize::try_from(v).unwrap_or(0);
        if itypel == 0 && nbsoob == 0 {
            return Err(lines.error(
                line,
                1,
                "a mesh with no cell type and no sub-mesh".to_string(),
            ));
        }
        let ty = if itypel == 0 {
            None
        } else {
            let Some(t) = TYPES.iter().position(|t| t.0 == itypel) else {
                return Err(lines.error(
                    line,
                    1,
                    format!("GIBI cell type {itypel} is not one code_aster reads"),
                ));
            };
            if count(nbno) != TYPES[t].3.len() && nbsoob == 0 {
                return Err(lines.error(
                    line,
                    1,
                    format!(
                        "a {} mesh with {nbno} nodes per cell (expected {})",
                        TYPES[t].1,
                        TYPES[t].3.len()
                    ),
                ));
            }
            Some(t)
        };
        let mut obj = Object {
            ty,
            sub: Vec::new(),
            nbno: count(nbno),
            nbele: count(nbele),
            connex: Vec::new(),
            line,
        };
        if nbsoob > 0 {
            for s in ints(lines, count(nbsoob), layout, "sub-mesh numbers")? {
                match usize::try_from(s)
                    .ok()
                    .filter(|&s| (1..=nbobj).contains(&s))
                {
                    Some(s) => obj.sub.push(s),
                    None => {
                        return Err(lines.error(
                            line,
                            1,
                            format!("sub-mesh {s}: pile 1 has {nbobj} objects"),
                        ))
                    }
                }
            }
            if nbref > 0 {
                ints(lines, count(nbref), layout, "references")?;
            }
        } else {
            if nbref > 0 {
                ints(lines, count(nbref), layout, "references")?;
            }
            if nbele > 0 {
                ints(lines, count(nbele), layout, "cell colours")?;
                obj.connex = ints(lines, count(nbele) * count(nbno), layout, "a connectivity")?;
            }
        }
        g.objects.push(obj);
    }
    Ok(())
}

/// The ASTER text, as `giecas` and `giecma` write it.
fn write(g: &Gibi, lines: &Lines<'_>) -> Result<String, MeshError> {
    let indirect = g.indirect.as_deref().unwrap_or(&[]);
    let npoints = g.coords.len() / g.ndim.max(1);
    let coord_of =
        |c: i64| -> Option<usize> { usize::try_from(c - 1).ok().filter(|&i| i < npoints) };
    // Cells of the simple meshes, numbered across the piles' objects
    // (`CUMUL_ELE`): every object counts its cells.
    let mut cumul = Vec::with_capacity(g.objects.len() + 1);
    cumul.push(0usize);
    for o in &g.objects {
        cumul.push(cumul.last().copied().unwrap_or(0) + o.nbele);
    }
    let total = *cumul.last().unwrap_or(&0);
    // Connectivity per global cell number (simple meshes only).
    let mut cells: Vec<&[i64]> = vec![&[]; total];
    for (i, o) in g.objects.iter().enumerate() {
        if o.sub.is_empty() && o.nbno > 0 {
            for (k, c) in o.connex.chunks(o.nbno).enumerate() {
                cells[cumul[i] + k] = c;
            }
        }
    }
    // gidoma: a cell equal (same nodes, same order) to an earlier cell with
    // the same first node is that cell.
    let mut numanew: Vec<usize> = (0..total).collect();
    let mut by_first: HashMap<i64, Vec<usize>> = HashMap::new();
    for (c, nodes) in cells.iter().enumerate() {
        if let Some(&f) = nodes.first() {
            by_first.entry(f).or_default().push(c);
        }
    }
    for list in by_first.values() {
        for (j, &cj) in list.iter().enumerate() {
            if let Some(&ck) = list[..j].iter().find(|&&ck| cells[ck] == cells[cj]) {
                numanew[cj] = numanew[ck];
            }
        }
    }
    // Which objects are written: named ones and the sub-meshes of named ones.
    let mut written = vec![false; g.objects.len()];
    for &(_, i) in &g.object_names {
        written[i - 1] = true;
    }
    for &(_, i) in &g.object_names {
        for &s in &g.objects[i - 1].sub {
            written[s - 1] = true;
        }
    }
    let mut text = MailText::new("%  GIBI FECIT");
    // Nodes: the coordinate indices the indirection reaches, sorted, unique.
    let mut nodes: Vec<i64> = indirect.to_vec();
    nodes.sort_unstable();
    nodes.dedup();
    let mut node_list = Vec::with_capacity(nodes.len());
    for &c in &nodes {
        let Some(i) = coord_of(c) else {
            return Err(lines.error(1, 1, format!("point coordinates {c} are not in pile 33")));
        };
        node_list.push((format!("N{c}"), &g.coords[i * g.ndim..(i + 1) * g.ndim]));
    }
    text.coords(g.ndim, node_list.into_iter());
    // giecma: the cells of the written meshes.
    let mut written_cell = vec![false; total];
    let mut first_copy: Vec<Option<usize>> = vec![None; total];
    let mut icoma = 0usize;
    for (i, o) in g.objects.iter().enumerate() {
        if o.nbele == 0 {
            continue;
        }
        if !written[i] || !o.sub.is_empty() {
            icoma += o.nbele;
            continue;
        }
        let Some(t) = o.ty else {
            icoma += o.nbele;
            continue;
        };
        let (_, _, aster, order) = TYPES[t];
        let mut block = Vec::new();
        for k in 0..o.nbele {
            let me = icoma;
            icoma += 1;
            let maille = numanew[me];
            if maille != me && written_cell[maille] {
                continue;
            }
            if maille != me {
                // The first copy written stands for the others.
                let copy = *first_copy[maille].get_or_insert(me);
                for m in numanew.iter_mut() {
                    if *m == maille {
                        *m = copy;
                        written_cell[copy] = true;
                    }
                }
            }
            written_cell[maille] = true;
            let conn = &o.connex[k * o.nbno..(k + 1) * o.nbno];
            let mut ns = Vec::with_capacity(order.len());
            for &pos in order.iter() {
                let p = conn[pos - 1];
                let c = usize::try_from(p - 1)
                    .ok()
                    .and_then(|i| indirect.get(i))
                    .copied()
                    .ok_or_else(|| {
                        lines.error(
                            o.line,
                            1,
                            format!("a cell uses point {p}, which pile 32 does not number"),
                        )
                    })?;
                ns.push(format!("N{c}"));
            }
            block.push((format!("M{}", me + 1), ns));
        }
        text.cells(aster, &block);
    }
    for (name, c) in &g.point_names {
        if name.starts_with('#') || name.is_empty() {
            continue;
        }
        text.group("GROUP_NO", name, &[format!("N{c}")]);
    }
    for (i, o) in g.objects.iter().enumerate() {
        for (name, _) in g.object_names.iter().filter(|(_, k)| *k == i + 1) {
            if name.starts_with('#') || name.is_empty() {
                continue;
            }
            let parts: Vec<usize> = if o.sub.is_empty() {
                vec![i]
            } else {
                o.sub.iter().map(|s| s - 1).collect()
            };
            let mut members = Vec::new();
            for j in parts {
                let cells = numanew.iter().skip(cumul[j]).take(g.objects[j].nbele);
                members.extend(cells.map(|c| format!("M{}", c + 1)));
            }
            text.group("GROUP_MA", name, &members);
        }
    }
    Ok(text.finish())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two QUA4 (one named `BLOC`), a SEG2 mesh `BAS` whose cell repeats a
    /// cell of an unnamed SEG2 mesh, a compound `TOUT` of the quads, and a
    /// named point; level 8 layout.
    const SAMPLE: &str = concat!(
        " ENREGISTREMENT DE TYPE   4\n",
        " NIVEAU   8 NIVEAU ERREUR   0 DIMENSION   2\n",
        " DENSITE 0.00000E+00\n",
        " ENREGISTREMENT DE TYPE   2\n",
        " PILE NUMERO   1NBRE OBJETS NOMMES       3NBRE OBJETS       4\n",
        " BLOC     BAS      TOUT    \n",
        "       1       3       4\n",
        "       8       0       0       4       2\n",
        "       0       0\n",
        "       1       2       5       4       2       3       6       5\n",
        "       2       0       0       2       1\n",
        "       0\n",
        "       1       2\n",
        "       2       0       0       2       1\n",
        "       0\n",
        "       1       2\n",
        "       0       1       0       0       0\n",
        "       1\n",
        " ENREGISTREMENT DE TYPE   2\n",
        " PILE NUMERO  32NBRE OBJETS NOMMES       1NBRE OBJETS       6\n",
        " PA      \n",
        "       6\n",
        "       6\n",
        "       1       2       3       4       5       6\n",
        " ENREGISTREMENT DE TYPE   2\n",
        " PILE NUMERO  33NBRE OBJETS NOMMES       0NBRE OBJETS       1\n",
        "      18\n",
        "  0.00000000000000E+00  0.00000000000000E+00  0.00000000000000E+00\n",
        "  1.00000000000000E+00  0.00000000000000E+00  0.00000000000000E+00\n",
        "  2.00000000000000E+00  0.00000000000000E+00  0.00000000000000E+00\n",
        "  0.00000000000000E+00  1.00000000000000E+00  0.00000000000000E+00\n",
        "  1.00000000000000E+00  1.00000000000000E+00  0.00000000000000E+00\n",
        "  2.00000000000000E+00  1.00000000000000E+00  0.00000000000000E+00\n",
        " ENREGISTREMENT DE TYPE   5\n",
        "LABEL AUTOMATIQUE :   1\n",
    );

    #[test]
    fn named_meshes_cells_and_duplicates() {
        let mail = gibi_to_mail(SAMPLE, Path::new("t.mgib")).unwrap();
        let m = crate::parse_mail(&mail, Path::new("t.mgib")).unwrap();
        assert_eq!(m.dim, 2);
        assert_eq!(m.node_names, ["N1", "N2", "N3", "N4", "N5", "N6"]);
        // Cells 1-2 (BLOC), cell 3 (unnamed SEG2: not written), cell 4
        // (BAS: the same segment, written as M4).
        assert_eq!(m.cell_names, ["M1", "M2", "M4"]);
        let names: Vec<&str> = m.groups_ma.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["BLOC", "BAS", "TOUT"]);
        assert_eq!(m.group_ma("TOUT").unwrap().members.len(), 2);
        assert_eq!(m.group_no("PA").unwrap().members.len(), 1);
        assert_eq!(
            m.node_names[m.group_no("PA").unwrap().members[0].0 as usize],
            "N6"
        );
    }

    #[test]
    fn a_bad_field_is_located() {
        let bad = SAMPLE.replace(
            "       1       2       5       4",
            "       1       x       5       4",
        );
        let e = gibi_to_mail(&bad, Path::new("t.mgib")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.mgib:10:9: a connectivity: expected an integer, found `x`"
        );
    }
}
