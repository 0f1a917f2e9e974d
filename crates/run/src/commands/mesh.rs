//! LIRE_MAILLAGE, DEFI_GROUP, MODI_MAILLAGE.

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::select;
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_mesh::{Group, Mesh, NodeId};
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Arc;

/// Reads a mesh file in the format the command asks for.
pub fn read_mesh_file(path: &Path, format: &str) -> Result<Mesh, String> {
    crate::meshio::read(path, format)
}

pub fn lire_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    ex.check_keywords(
        call,
        &[
            "FORMAT",
            "UNITE",
            "NOM_MED",
            "INFO",
            "INFO_MED",
            "VERI_MAIL",
            "VERI_MAIL/*",
        ],
    )?;
    let kw = &call.keywords;
    let format = kw.str("FORMAT").unwrap_or("MED");
    ex.only_values("LIRE_MAILLAGE", kw, "FORMAT", &["MED", "ASTER"])?;
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(20);
    let path = ex.input_path(unit as u32).map(Path::to_path_buf).ok_or_else(|| {
        ExecError::new(format!(
            "LIRE_MAILLAGE: no file for unit {unit} (give the mesh with --mesh, or a .export line `F {} mesh-file D {unit}`)",
            if format == "MED" { "mmed" } else { "mail" }
        ))
    })?;
    let mesh = read_mesh_file(&path, format)
        .map_err(|e| ExecError::new(format!("LIRE_MAILLAGE: {}: {e}", path.display())))?;
    store_result(ex, call, Concept::Mesh(Arc::new(mesh)))
}

/// The mesh updated in place (`reuse=`) or copied into a new concept.
fn mesh_to_modify(ex: &Executor, call: &CommandCall) -> Result<Mesh, ExecError> {
    let src = ex.required(&call.command, &call.keywords, "MAILLAGE")?;
    Ok((*ex.mesh(src)?).clone())
}

pub fn defi_group(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    ex.check_keywords(
        call,
        &[
            "MAILLAGE",
            "INFO",
            "CREA_GROUP_NO",
            "CREA_GROUP_NO/TOUT_GROUP_MA",
            "CREA_GROUP_NO/GROUP_MA",
            "CREA_GROUP_NO/NOM",
            "CREA_GROUP_NO/NOEUD",
            "CREA_GROUP_NO/GROUP_NO",
            "CREA_GROUP_NO/CRIT_NOEUD",
            "CREA_GROUP_NO/UNION",
            "CREA_GROUP_NO/INTERSEC",
            "CREA_GROUP_NO/DIFFE",
            "CREA_GROUP_MA/UNION",
            "CREA_GROUP_MA/INTERSEC",
            "CREA_GROUP_MA/DIFFE",
            "CREA_GROUP_MA",
            "CREA_GROUP_MA/NOM",
            "CREA_GROUP_MA/GROUP_MA",
            "CREA_GROUP_MA/MAILLE",
            "CREA_GROUP_MA/TOUT",
            "DETR_GROUP_NO",
            "DETR_GROUP_NO/NOM",
            "DETR_GROUP_MA",
            "DETR_GROUP_MA/NOM",
        ],
    )?;
    let mut mesh = mesh_to_modify(ex, call)?;
    let kw = &call.keywords;
    let names = |k: &aster_eval::Keywords, n: &str| -> Vec<String> {
        k.simple(n)
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect()
    };
    for occ in kw.factor("DETR_GROUP_NO") {
        let drop: BTreeSet<String> = names(occ, "NOM").into_iter().collect();
        mesh.groups_no.retain(|g| !drop.contains(&g.name));
    }
    for occ in kw.factor("DETR_GROUP_MA") {
        let drop: BTreeSet<String> = names(occ, "NOM").into_iter().collect();
        mesh.groups_ma.retain(|g| !drop.contains(&g.name));
    }
    for occ in kw.factor("CREA_GROUP_MA") {
        let Some(name) = occ.str("NOM") else {
            return Err(ex.kw_error("DEFI_GROUP", occ, "NOM", "CREA_GROUP_MA needs NOM"));
        };
        if set_operation(&mut mesh, occ, name, false)? {
            continue;
        }
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_MA: {e}")))?;
        put_group(&mut mesh.groups_ma, name, cells);
    }
    for occ in kw.factor("CREA_GROUP_NO") {
        if let Some(crit) = occ.str("CRIT_NOEUD") {
            if crit != "TOUS" {
                let span = occ
                    .keyword("CRIT_NOEUD")
                    .map(|k| k.span)
                    .unwrap_or_default();
                return Err(ex.unsupported(
                    &format!("DEFI_GROUP/CREA_GROUP_NO/CRIT_NOEUD='{crit}'"),
                    span,
                ));
            }
        }
        if occ.str("TOUT_GROUP_MA") == Some("OUI") {
            // One node group per cell group, same name, nodes in cell order.
            let groups: Vec<(String, Vec<NodeId>)> = mesh
                .groups_ma
                .iter()
                .map(|g| (g.name.clone(), nodes_of_cells(&mesh, &g.members)))
                .collect();
            for (name, nodes) in groups {
                put_group(&mut mesh.groups_no, &name, nodes);
            }
            continue;
        }
        let groups_ma = names(occ, "GROUP_MA");
        if !groups_ma.is_empty() && !occ.contains("NOM") {
            for g in groups_ma {
                let cells = select::group_ma(&mesh, &g)
                    .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_NO: {e}")))?
                    .to_vec();
                let nodes = nodes_of_cells(&mesh, &cells);
                put_group(&mut mesh.groups_no, &g, nodes);
            }
            continue;
        }
        let Some(name) = occ.str("NOM") else {
            return Err(ex.kw_error(
                "DEFI_GROUP",
                occ,
                "NOM",
                "CREA_GROUP_NO needs NOM (or TOUT_GROUP_MA/GROUP_MA)",
            ));
        };
        let nodes = select::nodes(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_NO: {e}")))?;
        put_group(&mut mesh.groups_no, name, nodes);
    }
    store_result(ex, call, Concept::Mesh(Arc::new(mesh)))
}

/// `UNION`/`INTERSEC`/`DIFFE` of groups (aster-mesh); false when the
/// occurrence has none of them.
fn set_operation(
    mesh: &mut Mesh,
    occ: &aster_eval::Keywords,
    name: &str,
    nodes: bool,
) -> Result<bool, ExecError> {
    for op in ["UNION", "INTERSEC", "DIFFE"] {
        let groups: Vec<&str> = occ.simple(op).iter().filter_map(|s| s.as_str()).collect();
        if groups.is_empty() {
            continue;
        }
        let r = match (op, nodes) {
            ("UNION", true) => mesh.crea_group_no_union(name, &groups),
            ("INTERSEC", true) => mesh.crea_group_no_intersec(name, &groups),
            ("DIFFE", true) => mesh.crea_group_no_diffe(name, &groups),
            ("UNION", false) => mesh.crea_group_ma_union(name, &groups),
            ("INTERSEC", false) => mesh.crea_group_ma_intersec(name, &groups),
            _ => mesh.crea_group_ma_diffe(name, &groups),
        };
        let kind = if nodes {
            "CREA_GROUP_NO"
        } else {
            "CREA_GROUP_MA"
        };
        r.map_err(|e| ExecError::new(format!("DEFI_GROUP/{kind}/{op}: {e}")))?;
        return Ok(true);
    }
    Ok(false)
}

/// Nodes of cells, in order of first appearance.
pub fn nodes_of_cells(mesh: &Mesh, cells: &[aster_mesh::CellId]) -> Vec<NodeId> {
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for &c in cells {
        for &n in &mesh.cell(c).nodes {
            if seen.insert(n) {
                out.push(n);
            }
        }
    }
    out
}

fn put_group<T>(groups: &mut Vec<Group<T>>, name: &str, members: Vec<T>) {
    // code_aster refuses an existing name; replacing keeps reruns simple
    // and matches `DETR_GROUP_*` followed by `CREA_GROUP_*`.
    groups.retain(|g| g.name != name);
    groups.push(Group {
        name: name.to_string(),
        members,
    });
}

pub fn modi_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    ex.check_keywords(
        call,
        &[
            "MAILLAGE",
            "INFO",
            "ORIE_PEAU",
            "ORIE_PEAU/GROUP_MA_PEAU",
            "ORIE_PEAU/GROUP_MA_INTERNE",
            "ORIE_PEAU_2D",
            "ORIE_PEAU_2D/GROUP_MA",
        ],
    )?;
    let mut mesh = mesh_to_modify(ex, call)?;
    let kw = &call.keywords;
    let mut groups: Vec<String> = Vec::new();
    for occ in kw
        .factor("ORIE_PEAU")
        .iter()
        .chain(kw.factor("ORIE_PEAU_2D"))
    {
        for key in ["GROUP_MA_PEAU", "GROUP_MA"] {
            groups.extend(
                occ.simple(key)
                    .iter()
                    .filter_map(|s| s.as_str().map(str::to_string)),
            );
        }
    }
    for g in &groups {
        select::group_ma(&mesh, g)
            .map_err(|e| ExecError::new(format!("MODI_MAILLAGE/ORIE_PEAU: {e}")))?;
    }
    crate::meshio::orient_skin(&mut mesh, &groups)
        .map_err(|e| ExecError::new(format!("MODI_MAILLAGE/ORIE_PEAU: {e}")))?;
    store_result(ex, call, Concept::Mesh(Arc::new(mesh)))
}
