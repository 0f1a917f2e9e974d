//! Selecting nodes and cells of a mesh from keywords (`GROUP_NO`, `NOEUD`,
//! `GROUP_MA`, `MAILLE`, `TOUT`), with did-you-mean on unknown names.

use aster_eval::Keywords;
use aster_mesh::{Cell, CellId, Mesh, NodeId};
use std::collections::BTreeSet;

/// "did you mean `X`?" for a misspelt name among candidates.
pub fn did_you_mean<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    let best = candidates
        .map(|c| (strsim::jaro_winkler(name, c), c))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match best {
        Some((_, c)) => format!(" (did you mean `{c}`?)"),
        None => String::new(),
    }
}

pub fn group_no<'m>(mesh: &'m Mesh, name: &str) -> Result<&'m [NodeId], String> {
    match mesh.group_no(name) {
        Some(g) => Ok(&g.members),
        None => Err(format!(
            "the mesh has no node group `{name}`{}",
            did_you_mean(name, mesh.groups_no.iter().map(|g| g.name.as_str()))
        )),
    }
}

pub fn group_ma<'m>(mesh: &'m Mesh, name: &str) -> Result<&'m [CellId], String> {
    match mesh.group_ma(name) {
        Some(g) => Ok(&g.members),
        None => Err(format!(
            "the mesh has no cell group `{name}`{}",
            did_you_mean(name, mesh.groups_ma.iter().map(|g| g.name.as_str()))
        )),
    }
}

pub fn node_named(mesh: &Mesh, name: &str) -> Result<NodeId, String> {
    // code_aster 17 keeps no node names: `N<k>` is its k-th node, even
    // where the file names another node so (a GMSH mesh named by its
    // tags: ssns107c's references sit at the positional nodes).
    if let Some(k) = name
        .strip_prefix('N')
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|d| d.parse::<usize>().ok())
        .filter(|&k| k >= 1 && k <= mesh.node_names.len())
    {
        return Ok(NodeId((k - 1) as u32));
    }
    positional(&mesh.node_names, name, 'N', "node").map(|i| NodeId(i as u32))
}

pub fn cell_named(mesh: &Mesh, name: &str) -> Result<CellId, String> {
    positional(&mesh.cell_names, name, 'M', "cell").map(|i| CellId(i as u32))
}

/// A node or cell by name, with code_aster 17's positional names
/// ([`aster_mesh::positional_name`]).
fn positional(names: &[String], name: &str, prefix: char, what: &str) -> Result<usize, String> {
    aster_mesh::positional_name(names, name, prefix).ok_or_else(|| {
        format!(
            "the mesh has no {what} `{name}`{}",
            did_you_mean(name, names.iter().map(String::as_str))
        )
    })
}

fn names<'k>(kw: &'k Keywords, key: &str) -> impl Iterator<Item = &'k str> {
    kw.simple(key).iter().filter_map(|s| s.as_str())
}

fn push_unique<T: Copy + Ord>(out: &mut Vec<T>, seen: &mut BTreeSet<T>, item: T) {
    if seen.insert(item) {
        out.push(item);
    }
}

/// The cells named by `TOUT`/`GROUP_MA`/`MAILLE` (prefix the keyword names
/// with `prefix`, e.g. `"SANS_"`), in order of appearance, without repeats.
pub fn cells(kw: &Keywords, mesh: &Mesh, prefix: &str) -> Result<Vec<CellId>, String> {
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    if prefix.is_empty() && kw.str("TOUT") == Some("OUI") {
        return Ok((0..mesh.cells.len() as u32).map(CellId).collect());
    }
    for g in names(kw, &format!("{prefix}GROUP_MA")) {
        for &c in group_ma(mesh, g)? {
            push_unique(&mut out, &mut seen, c);
        }
    }
    for m in names(kw, &format!("{prefix}MAILLE")) {
        push_unique(&mut out, &mut seen, cell_named(mesh, m)?);
    }
    Ok(out)
}

/// The nodes named by `TOUT`/`GROUP_NO`/`NOEUD`/`GROUP_MA`/`MAILLE` (nodes
/// of the cells), in order of appearance, without repeats.
pub fn nodes(kw: &Keywords, mesh: &Mesh, prefix: &str) -> Result<Vec<NodeId>, String> {
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    if prefix.is_empty() && kw.str("TOUT") == Some("OUI") {
        return Ok((0..mesh.node_count() as u32).map(NodeId).collect());
    }
    for g in names(kw, &format!("{prefix}GROUP_NO")) {
        for &n in group_no(mesh, g)? {
            push_unique(&mut out, &mut seen, n);
        }
    }
    for n in names(kw, &format!("{prefix}NOEUD")) {
        push_unique(&mut out, &mut seen, node_named(mesh, n)?);
    }
    let cell_kw = [format!("{prefix}GROUP_MA"), format!("{prefix}MAILLE")];
    if cell_kw.iter().any(|k| kw.contains(k)) {
        for c in cells(kw, mesh, prefix)? {
            for &n in &mesh.cell(c).nodes {
                push_unique(&mut out, &mut seen, n);
            }
        }
    }
    Ok(out)
}

/// Nodes minus the excluded ones (`SANS_GROUP_NO`, `SANS_NOEUD`).
pub fn nodes_without(kw: &Keywords, mesh: &Mesh) -> Result<Vec<NodeId>, String> {
    let all = nodes(kw, mesh, "")?;
    let excluded: BTreeSet<NodeId> = nodes(kw, mesh, "SANS_")?.into_iter().collect();
    Ok(all.into_iter().filter(|n| !excluded.contains(n)).collect())
}

/// The single node a test designates (`NOEUD` or a one-node `GROUP_NO`).
pub fn single_node(kw: &Keywords, mesh: &Mesh) -> Result<(NodeId, Option<String>), String> {
    if let Some(n) = kw.str("NOEUD") {
        return Ok((node_named(mesh, n)?, None));
    }
    if let Some(g) = kw.str("GROUP_NO") {
        let members = group_no(mesh, g)?;
        return match members {
            [n] => Ok((*n, Some(g.to_string()))),
            [] => Err(format!("node group `{g}` is empty")),
            _ => Err(format!(
                "node group `{g}` has {} nodes; a test needs exactly one (use NOEUD= or a one-node group)",
                members.len()
            )),
        };
    }
    Err("no node given (NOEUD or GROUP_NO)".into())
}

/// The node a `RECU_FONCTION` reads (`NOEUD`, or the first node of
/// `GROUP_NO`: code_aster's `utnono` takes the group's first node, with an
/// alarm, when it has several).
pub fn first_node(kw: &Keywords, mesh: &Mesh) -> Result<NodeId, String> {
    if let Some(g) = kw.str("GROUP_NO").filter(|_| kw.str("NOEUD").is_none()) {
        return group_no(mesh, g)?
            .first()
            .copied()
            .ok_or_else(|| format!("node group `{g}` is empty"));
    }
    single_node(kw, mesh).map(|(n, _)| n)
}

/// The first of `cells` that `fits` rejects, said as `cell M12 is a QUAD4`
/// (for messages "… applies to SEG2 cells, but cell M12 is a QUAD4").
pub fn misfit(mesh: &Mesh, cells: &[CellId], fits: impl Fn(&Cell) -> bool) -> Option<String> {
    let &bad = cells.iter().find(|&&c| !fits(mesh.cell(c)))?;
    Some(format!(
        "cell {} is a {}",
        cell_name(mesh, bad),
        mesh.cell(bad).ty.name()
    ))
}

pub fn cell_name(mesh: &Mesh, c: CellId) -> String {
    mesh.cell_names
        .get(c.0 as usize)
        .cloned()
        .unwrap_or_else(|| format!("M{}", c.0 + 1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::CellType;

    #[test]
    fn misfit_names_the_first_cell_of_another_kind() {
        let text = "COOR_2D\nN1 0.0 0.0\nN2 1.0 0.0\nN3 1.0 1.0\nN4 0.0 1.0\nFINSF\n\
                    SEG2\nS1 N1 N2\nFINSF\nQUAD4\nQ1 N1 N2 N3 N4\nFINSF\nSEG2\nS2 N3 N4\nFINSF\nFIN\n";
        let mesh = aster_mesh::parse_mail(text, std::path::Path::new("t.mail")).expect("mesh");
        let all: Vec<CellId> = (0..3).map(CellId).collect();
        let seg = |c: &Cell| c.ty == CellType::SEG2;
        assert_eq!(
            misfit(&mesh, &all, seg).as_deref(),
            Some("cell Q1 is a QUAD4")
        );
        assert_eq!(misfit(&mesh, &[CellId(0), CellId(2)], seg), None);
    }
}
