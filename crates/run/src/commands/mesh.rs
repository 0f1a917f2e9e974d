//! LIRE_MAILLAGE, PRE_GMSH, PRE_GIBI, PRE_IDEAS, ASSE_MAILLAGE, DEFI_GROUP, MODI_MAILLAGE.

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::select;
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{Along, Group, Mesh, NodeId, NodeKind};
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Arc;

/// Reads a mesh file in the format the command asks for, with the
/// reader's warnings.
pub fn read_mesh_file(
    path: &Path,
    format: &str,
    colour_groups: bool,
) -> Result<(Mesh, Vec<String>), String> {
    crate::meshio::read(path, format, colour_groups)
}

/// What LIRE_MAILLAGE reads (`crate::support`).
pub(crate) const LIRE_MAILLAGE: Support = Support {
    values: &[Values::new(
        "FORMAT",
        &["MED", "ASTER", "GMSH", "GIBI", "IDEAS"],
    )],
    ..Support::keywords(&[
        "FORMAT",
        "CREA_GROUP_COUL",
        "UNITE",
        "NOM_MED",
        "INFO",
        "INFO_MED",
        "VERI_MAIL",
        "VERI_MAIL/*",
        "PARTITIONNEUR",
    ])
};

pub fn lire_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let (format, colour, key) = crate::meshio::requested(kw);
    // code_aster's default unit is 20 whatever the format.
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(20);
    let mesh = read_unit("LIRE_MAILLAGE", ex, unit, &format, colour, &key)?;
    // code_aster 17 partitions the mesh over the MPI processes (a
    // ParallelMesh); on one process it reads the whole mesh, with an
    // alarm (MED_18): aster runs as that one process.
    // The catalog's default, 'SANS', reads a plain mesh everywhere.
    if let Some(p) = kw.str("PARTITIONNEUR").filter(|p| *p != "SANS") {
        ex.write_report(&format!(
            "<A> LIRE_MAILLAGE: PARTITIONNEUR='{p}': one process, the mesh is read whole (code_aster's MED_18)\n"
        ))?;
    }
    store_result(ex, call, Concept::Mesh(mesh))
}

/// Reads the mesh of logical unit `unit` in `format` (`key`: the cache key
/// of [`crate::meshio::requested`]), with the reader's warnings written to
/// the report: `LIRE_MAILLAGE`, and the macros that read their own mesh
/// (`MACR_CARA_POUTRE`).
pub(crate) fn read_unit(
    cmd: &str,
    ex: &mut Executor,
    unit: i64,
    format: &str,
    colour: bool,
    key: &str,
) -> Result<Arc<Mesh>, ExecError> {
    let written = ex.med_written.get(&(unit as u32)).cloned();
    let path = written.or_else(|| ex.input_path(unit as u32).map(Path::to_path_buf)).ok_or_else(|| {
        ExecError::new(format!(
            "{cmd}: no file for unit {unit} (give the mesh with --mesh, or a .export line `F {} mesh-file D {unit}`)",
            match format {
                "MED" => "mmed",
                "GMSH" => "msh",
                "GIBI" => "mgib",
                "IDEAS" => "msup",
                _ => "mail",
            }
        ))
    })?;
    let read = ex
        .read_meshes
        .iter()
        .find(|m| m.path == path && m.format == key)
        .map(|m| (m.mesh.clone(), m.warnings.clone()));
    let (mesh, warnings) = match read {
        Some(m) => m,
        None => {
            let (mesh, warnings) = read_mesh_file(&path, format, colour).map_err(|e| {
                // Reader errors mostly start with the file (and its line): not twice.
                let file = path.display().to_string();
                if e.starts_with(&file) {
                    ExecError::new(format!("{cmd}: {e}"))
                } else {
                    ExecError::new(format!("{cmd}: {file}: {e}"))
                }
            })?;
            (Arc::new(mesh), warnings)
        }
    };
    for w in &warnings {
        ex.write_report(&format!("<A> {cmd}: {}: {w}\n", path.display()))?;
    }
    Ok(mesh)
}

/// What PRE_GMSH reads (`crate::support`).
pub(crate) const PRE_GMSH: Support = Support::keywords(&["UNITE_GMSH", "UNITE_MAILLAGE"]);

/// What PRE_GIBI reads (`crate::support`). The nodes, cells and groups are
/// numbered and named as code_aster's converter does (aster-mesh
/// `convert::gibi`); ssnv104i and ssnv128g run on it.
pub(crate) const PRE_GIBI: Support = Support::keywords(&["UNITE_GIBI", "UNITE_MAILLAGE"]);

/// What ASSE_MAILLAGE does (`crate::support`): `SUPERPOSE` only.
pub(crate) const ASSE_MAILLAGE: Support = Support {
    values: &[super::substructure::ASSE_OPERATIONS],
    ..Support::keywords(&["MAILLAGE_1", "MAILLAGE_2", "OPERATION"])
};

/// What PRE_IDEAS reads (`crate::support`): aster-mesh `convert::ideas`.
pub(crate) const PRE_IDEAS: Support =
    Support::keywords(&["UNITE_IDEAS", "UNITE_MAILLAGE", "CREA_GROUP_COUL"]);

/// `PRE_GMSH` / `PRE_GIBI` / `PRE_IDEAS`: converts the GMSH (`UNITE_GMSH`,
/// default 19), GIBI (`UNITE_GIBI`, default 19) or I-DEAS (`UNITE_IDEAS`,
/// default 19) file into an ASTER text mesh written
/// on `UNITE_MAILLAGE` (default 20, `fort.20` in the output directory),
/// which a later `LIRE_MAILLAGE(FORMAT='ASTER')` reads.
pub fn pre_convert(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let (format, source_kw) = match call.command.as_str() {
        "PRE_GMSH" => ("GMSH", "UNITE_GMSH"),
        "PRE_IDEAS" => ("IDEAS", "UNITE_IDEAS"),
        _ => ("GIBI", "UNITE_GIBI"),
    };
    let kw = &call.keywords;
    let colour = kw.str("CREA_GROUP_COUL") == Some("OUI");
    let source = kw.first(source_kw).and_then(|s| s.as_i64()).unwrap_or(19);
    let target = kw
        .first("UNITE_MAILLAGE")
        .and_then(|s| s.as_i64())
        .unwrap_or(20);
    let path = ex
        .input_path(source as u32)
        .map(Path::to_path_buf)
        .ok_or_else(|| {
            ExecError::new(format!(
                "{}: no file for unit {source} (a .export line `F {} mesh-file D {source}`)",
                call.command,
                match format {
                    "GMSH" => "msh",
                    "IDEAS" => "msup",
                    _ => "mgib",
                }
            ))
        })?;
    let text = crate::meshio::convert(&path, format, colour)
        .map_err(|e| ExecError::new(format!("{}: {e}", call.command)))?;
    let out = ex.output_path(target);
    // The unit's file is written anew (not appended to).
    let _ = std::fs::remove_file(&out);
    crate::commands::append_file(&out, &text)
        .map_err(|e| ExecError::new(format!("{}: {}", call.command, e.message)))?;
    ex.options.units.insert(target as u32, out);
    Ok(CommandOutput::Nothing)
}

/// `ASSE_MAILLAGE(OPERATION='SUPERPOSE')`: the two meshes side by side
/// (aster-mesh `Mesh::superpose`: nodes and cells renumbered N1…, M1…, the
/// second mesh's groups renamed when their name is taken). `COLLAGE` and
/// `SOUS_STR` are refused.
pub fn asse_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    if kw.str("OPERATION") == Some("SOUS_STR") {
        return super::substructure::asse_sous_str(ex, call);
    }
    let a = ex.mesh(ex.required("ASSE_MAILLAGE", kw, "MAILLAGE_1")?)?;
    let b = ex.mesh(ex.required("ASSE_MAILLAGE", kw, "MAILLAGE_2")?)?;
    store_result(ex, call, Concept::Mesh(Arc::new(a.superpose(&b))))
}

/// The mesh updated in place (`reuse=`) or copied into a new concept.
fn mesh_to_modify(ex: &Executor, call: &CommandCall) -> Result<Mesh, ExecError> {
    let src = ex.required(&call.command, &call.keywords, "MAILLAGE")?;
    Ok((*ex.mesh(src)?).clone())
}

/// What DEFI_GROUP reads (`crate::support`).
pub(crate) const DEFI_GROUP: Support = Support::keywords(&[
    "MAILLAGE",
    "INFO",
    "CREA_GROUP_NO",
    "CREA_GROUP_NO/TOUT_GROUP_MA",
    "CREA_GROUP_NO/GROUP_MA",
    "CREA_GROUP_NO/NOM",
    "CREA_GROUP_NO/NOEUD",
    "CREA_GROUP_NO/GROUP_NO",
    "CREA_GROUP_NO/CRIT_NOEUD",
    "CREA_GROUP_NO/OPTION",
    "CREA_GROUP_NO/POINT",
    "CREA_GROUP_NO/RAYON",
    "CREA_GROUP_NO/PRECISION",
    "CREA_GROUP_NO/CRITERE",
    "CREA_GROUP_NO/NOEUD_CENTRE",
    "CREA_GROUP_NO/GROUP_NO_CENTRE",
    "CREA_GROUP_NO/VECT_NORMALE",
    "CREA_GROUP_NO/ANGL_NAUT",
    "CREA_GROUP_NO/GROUP_NO_ORIG",
    "CREA_GROUP_NO/GROUP_NO_EXTR",
    "CREA_GROUP_NO/UNION",
    "CREA_GROUP_NO/INTERSEC",
    "CREA_GROUP_NO/DIFFE",
    "CREA_GROUP_NO/POSITION",
    "CREA_GROUP_NO/NUME_INIT",
    "CREA_GROUP_NO/NUME_FIN",
    "CREA_GROUP_MA/UNION",
    "CREA_GROUP_MA/INTERSEC",
    "CREA_GROUP_MA/DIFFE",
    "CREA_GROUP_MA",
    "CREA_GROUP_MA/NOM",
    "CREA_GROUP_MA/GROUP_MA",
    "CREA_GROUP_MA/MAILLE",
    "CREA_GROUP_MA/TOUT",
    "CREA_GROUP_MA/OPTION",
    "CREA_GROUP_MA/VECT_NORMALE",
    "CREA_GROUP_MA/ANGL_NAUT",
    "CREA_GROUP_MA/ANGL_PREC",
    "CREA_GROUP_MA/VERI_SIGNE",
    "CREA_GROUP_MA/POINT",
    "CREA_GROUP_MA/NOEUD_CENTRE",
    "CREA_GROUP_MA/GROUP_NO_CENTRE",
    "CREA_GROUP_MA/RAYON",
    "CREA_GROUP_MA/CRIT_NOEUD",
    "CREA_GROUP_MA/TYPE_MAILLE",
    "DETR_GROUP_NO",
    "DETR_GROUP_NO/NOM",
    "DETR_GROUP_MA",
    "DETR_GROUP_MA/NOM",
]);

pub fn defi_group(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
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
            filter_by_type(ex, &mut mesh, occ, name)?;
            continue;
        }
        // With OPTION and no selection, every cell is a candidate.
        let given = ["TOUT", "GROUP_MA", "MAILLE"]
            .iter()
            .any(|k| occ.contains(k));
        let mut cells = if given || !occ.contains("OPTION") {
            select::cells(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_MA: {e}")))?
        } else {
            (0..mesh.cells.len() as u32)
                .map(aster_mesh::CellId)
                .collect()
        };
        match occ.str("OPTION") {
            None => {}
            Some("FACE_NORMALE") => {
                let what = "DEFI_GROUP/CREA_GROUP_MA/OPTION='FACE_NORMALE'";
                let vector = normal_vector(occ, what)?;
                cells = mesh
                    .cells_facing(
                        &cells,
                        vector,
                        occ.f64("ANGL_PREC").unwrap_or(0.5),
                        occ.str("VERI_SIGNE").unwrap_or("OUI") == "OUI",
                    )
                    .map_err(|e| ExecError::new(format!("{what}: {e}")))?;
            }
            Some("CYLINDRE") => {
                let what = "DEFI_GROUP/CREA_GROUP_MA/OPTION='CYLINDRE'";
                if mesh.dim != 3 {
                    return Err(ExecError::new(format!("{what}: the mesh must be 3D")));
                }
                let axis = normal_vector(occ, what)?;
                let radius = occ
                    .f64("RAYON")
                    .ok_or_else(|| ExecError::new(format!("{what}: RAYON is required")))?;
                let at_least_one = match occ.str("CRIT_NOEUD").unwrap_or("AU_MOINS_UN") {
                    "AU_MOINS_UN" => true,
                    "TOUS" => false,
                    other => {
                        let span = occ
                            .keyword("CRIT_NOEUD")
                            .map(|k| k.span)
                            .unwrap_or_default();
                        return Err(
                            ex.unsupported(&format!("{what} with CRIT_NOEUD='{other}'"), span)
                        );
                    }
                };
                let inside = mesh
                    .cells_in_cylinder(centre(ex, &mesh, occ)?, axis, radius, at_least_one)
                    .map_err(|e| ExecError::new(format!("{what}: {e}")))?;
                let inside: BTreeSet<aster_mesh::CellId> = inside.into_iter().collect();
                cells.retain(|c| inside.contains(c));
            }
            Some(other) => {
                let span = occ.keyword("OPTION").map(|k| k.span).unwrap_or_default();
                return Err(
                    ex.unsupported(&format!("DEFI_GROUP/CREA_GROUP_MA/OPTION='{other}'"), span)
                );
            }
        }
        put_group(&mut mesh.groups_ma, name, cells);
        filter_by_type(ex, &mut mesh, occ, name)?;
    }
    for occ in kw.factor("CREA_GROUP_NO") {
        if let Some(option) = occ.str("OPTION") {
            let (name, nodes) = geometric_group(ex, &mesh, occ, option)?;
            put_group(&mut mesh.groups_no, &name, nodes);
            continue;
        }
        let kind = match occ.str("CRIT_NOEUD").unwrap_or("TOUS") {
            "TOUS" => NodeKind::All,
            "SOMMET" => NodeKind::Corners,
            "MILIEU" => NodeKind::MidEdges,
            crit => {
                let span = occ
                    .keyword("CRIT_NOEUD")
                    .map(|k| k.span)
                    .unwrap_or_default();
                return Err(ex.unsupported(
                    &format!("DEFI_GROUP/CREA_GROUP_NO/CRIT_NOEUD='{crit}'"),
                    span,
                ));
            }
        };
        if occ.str("TOUT_GROUP_MA") == Some("OUI") {
            // One node group per cell group, same name.
            let groups: Vec<(String, Vec<NodeId>)> = mesh
                .groups_ma
                .iter()
                .map(|g| (g.name.clone(), nodes_of_cells(&mesh, &g.members, kind)))
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
                let nodes = nodes_of_cells(&mesh, &cells, kind);
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
        if set_operation(&mut mesh, occ, name, true)? {
            continue;
        }
        if ["POSITION", "NUME_INIT", "NUME_FIN"]
            .iter()
            .any(|k| occ.contains(k))
        {
            let nodes = part_of_group(&mesh, occ)?;
            put_group(&mut mesh.groups_no, name, nodes);
            continue;
        }
        let only_cells = !occ.contains("GROUP_NO") && !occ.contains("NOEUD");
        let nodes = if (kind != NodeKind::All || only_cells) && !groups_ma.is_empty() {
            let cells = select::cells(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_NO: {e}")))?;
            nodes_of_cells(&mesh, &cells, kind)
        } else {
            select::nodes(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("DEFI_GROUP/CREA_GROUP_NO: {e}")))?
        };
        put_group(&mut mesh.groups_no, name, nodes);
    }
    store_result(ex, call, Concept::Mesh(Arc::new(mesh)))
}

/// `CREA_GROUP_MA/TYPE_MAILLE`: the group just made keeps the cells of
/// one dimension (`'1D'`, `'2D'`, `'3D'`) or one type (code_aster's
/// `cgmftm`, applied after every way of selecting, `OPTION` and
/// `UNION`/`INTERSEC`/`DIFFE` included). When the filter keeps no cell,
/// code_aster keeps the group unfiltered (its alarm `SOUSTRUC_36` says the
/// group is empty, then `addGrpMa` creates it with the unfiltered list):
/// aster does the same and writes the alarm in the report.
fn filter_by_type(
    ex: &mut Executor,
    mesh: &mut Mesh,
    occ: &aster_eval::Keywords,
    name: &str,
) -> Result<(), ExecError> {
    let Some(value) = occ.str("TYPE_MAILLE").filter(|v| *v != "TOUT") else {
        return Ok(());
    };
    let Some(filter) = aster_mesh::CellFilter::from_keyword(value) else {
        return Err(ex.kw_error(
            "DEFI_GROUP",
            occ,
            "TYPE_MAILLE",
            format!("TYPE_MAILLE='{value}' is neither a dimension (1D, 2D, 3D) nor a cell type"),
        ));
    };
    let Some(group) = mesh.groups_ma.iter().position(|g| g.name == name) else {
        return Ok(());
    };
    match mesh.filter_cells(&mesh.groups_ma[group].members, filter) {
        Some(kept) => mesh.groups_ma[group].members = kept,
        None => ex.write_report(&format!(
            "<A> DEFI_GROUP/CREA_GROUP_MA: no cell of group `{name}` is of TYPE_MAILLE='{value}': the group keeps its {} cells unfiltered, as code_aster does (SOUSTRUC_36)\n",
            mesh.groups_ma[group].members.len()
        ))?,
    }
    Ok(())
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

fn put_group<T>(groups: &mut Vec<Group<T>>, name: &str, members: Vec<T>) {
    // code_aster refuses an existing name; replacing keeps reruns simple
    // and matches `DETR_GROUP_*` followed by `CREA_GROUP_*`.
    groups.retain(|g| g.name != name);
    groups.push(Group {
        name: name.to_string(),
        members,
    });
}

/// What MODI_MAILLAGE reads (`crate::support`).
pub(crate) const MODI_MAILLAGE: Support = Support {
    values: &[
        Values::new("DEFORME/OPTION", &["TRAN"]),
        Values::new("MODI_MAILLE/OPTION", &["NOEUD_QUART"]),
    ],
    ..Support::keywords(&[
        "MAILLAGE",
        "INFO",
        "ORIE_PEAU",
        "ORIE_PEAU/GROUP_MA_PEAU",
        "ORIE_PEAU/GROUP_MA_INTERNE",
        "ORIE_PEAU_2D",
        "ORIE_PEAU_2D/GROUP_MA",
        "ORIE_FISSURE",
        "ORIE_FISSURE/GROUP_MA",
        "ORIE_NORM_COQUE",
        "ORIE_NORM_COQUE/GROUP_MA",
        "ORIE_NORM_COQUE/VECT_NORM",
        "ORIE_NORM_COQUE/GROUP_NO",
        "ORIE_NORM_COQUE/NOEUD",
        "ORIE_LIGNE",
        "ORIE_LIGNE/GROUP_MA",
        "ORIE_LIGNE/VECT_TANG",
        "ORIE_LIGNE/GROUP_NO",
        "ORIE_LIGNE/NOEUD",
        "DEFORME",
        "DEFORME/OPTION",
        "DEFORME/DEPL",
        "DEFORME/ALEA",
        "ECHELLE",
        "MODI_MAILLE",
        "MODI_MAILLE/OPTION",
        "MODI_MAILLE/GROUP_MA_FOND",
        "MODI_MAILLE/GROUP_NO_FOND",
    ])
};

pub fn modi_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let mut mesh = mesh_to_modify(ex, call)?;
    let kw = &call.keywords;
    // code_aster's op0154 order: ORIE_FISSURE, MODI_MAILLE, DEFORME.
    for occ in kw.factor("ORIE_FISSURE") {
        // conori reads the groups of the first occurrence only (`getvem`
        // with iocc=1); ORIE_FISSURE is not repeatable in the catalog.
        let groups: Vec<&str> = occ
            .simple("GROUP_MA")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        mesh.orient_crack(&groups).map_err(|e| {
            ex.kw_error("MODI_MAILLAGE/ORIE_FISSURE", occ, "GROUP_MA", e.to_string())
        })?;
    }
    for occ in kw.factor("MODI_MAILLE") {
        quarter_points(&mut mesh, occ)?;
    }
    for occ in kw.factor("DEFORME") {
        // ALEA: code_aster's pseudo-random move of every node.
        if let Some(alea) = occ.f64("ALEA") {
            mesh.perturb_randomly(alea);
            continue;
        }
        // OPTION='TRAN': every node moves by the field's DX, DY, DZ.
        let d = ex.required("MODI_MAILLAGE/DEFORME", occ, "DEPL")?;
        let field = ex.field(d)?;
        let crate::field::Field::Nodal(f) = &*field else {
            return Err(ex.kw_error(
                "MODI_MAILLAGE/DEFORME",
                occ,
                "DEPL",
                "a nodal displacement field is required",
            ));
        };
        for node in f.nodes() {
            let Some(x) = mesh.coords.get_mut(node.0 as usize) else {
                return Err(ExecError::new(format!(
                    "MODI_MAILLAGE/DEFORME: field `{}` has node #{} which the mesh does not have",
                    d.name,
                    node.0 + 1
                )));
            };
            for (k, c) in ["DX", "DY", "DZ"].iter().enumerate() {
                x[k] += f.get(node, c).unwrap_or(0.0);
            }
        }
    }
    if let Some(scale) = kw.f64("ECHELLE") {
        for x in &mut mesh.coords {
            for v in x.iter_mut() {
                *v *= scale;
            }
        }
    }
    for (key, vect, along) in [
        ("ORIE_NORM_COQUE", "VECT_NORM", Along::Normal),
        ("ORIE_LIGNE", "VECT_TANG", Along::Tangent),
    ] {
        for occ in kw.factor(key) {
            let what = format!("MODI_MAILLAGE/{key}");
            let cells = select::cells(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("{what}: {e}")))?;
            let v: Vec<f64> = occ.simple(vect).iter().filter_map(|s| s.as_f64()).collect();
            let vector = match v.as_slice() {
                [] => None,
                [x, y] => Some([*x, *y, 0.0]),
                [x, y, z, ..] => Some([*x, *y, *z]),
                _ => return Err(ex.kw_error(&what, occ, vect, "2 or 3 components are needed")),
            };
            let node = if occ.contains("GROUP_NO") || occ.contains("NOEUD") {
                select::single_node(occ, &mesh)
                    .map_err(|e| ExecError::new(format!("{what}: {e}")))?
                    .0
            } else if vector.is_some() {
                return Err(ExecError::new(format!(
                    "{what}: {vect} needs the node where it applies (GROUP_NO or NOEUD)"
                )));
            } else {
                match cells.first() {
                    Some(c) => mesh.cell(*c).nodes[0],
                    None => continue,
                }
            };
            mesh.orient_along(&cells, node, vector, along)
                .map_err(|e| ExecError::new(e.to_string()))?;
        }
    }
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

/// `MODI_MAILLE=_F(OPTION='NOEUD_QUART', GROUP_MA_FOND | GROUP_NO_FOND)`:
/// Barsoum's quarter-point cells at a crack front (aster-mesh's
/// `move_to_quarter_points`, code_aster's `momaba`). The cells are read
/// first when both are given, as code_aster does.
fn quarter_points(mesh: &mut Mesh, occ: &aster_eval::Keywords) -> Result<(), ExecError> {
    let what = "MODI_MAILLAGE/MODI_MAILLE";
    let mut done = false;
    if let Some(g) = occ.str("GROUP_MA_FOND") {
        let cells = select::group_ma(mesh, g)
            .map_err(|e| ExecError::new(format!("{what}/GROUP_MA_FOND: {e}")))?
            .to_vec();
        mesh.move_to_quarter_points(aster_mesh::CrackFront::Cells(&cells))
            .map_err(|e| ExecError::new(e.to_string()))?;
        done = true;
    }
    if let Some(g) = occ.str("GROUP_NO_FOND") {
        let nodes = select::group_no(mesh, g)
            .map_err(|e| ExecError::new(format!("{what}/GROUP_NO_FOND: {e}")))?
            .to_vec();
        mesh.move_to_quarter_points(aster_mesh::CrackFront::Nodes(&nodes))
            .map_err(|e| ExecError::new(e.to_string()))?;
        done = true;
    }
    if !done {
        return Err(ExecError::new(format!(
            "{what}: GROUP_MA_FOND or GROUP_NO_FOND is needed"
        )));
    }
    Ok(())
}

/// A point given by `POINT` (2 or 3 coordinates), `NOEUD_CENTRE` or
/// `GROUP_NO_CENTRE`.
fn centre(ex: &Executor, mesh: &Mesh, occ: &aster_eval::Keywords) -> Result<[f64; 3], ExecError> {
    let p: Vec<f64> = occ
        .simple("POINT")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    if !p.is_empty() {
        return Ok([
            p[0],
            p.get(1).copied().unwrap_or(0.0),
            p.get(2).copied().unwrap_or(0.0),
        ]);
    }
    if let Some(n) = occ.str("NOEUD_CENTRE") {
        let id = select::node_named(mesh, n).map_err(ExecError::new)?;
        return Ok(mesh.coord(id));
    }
    if let Some(g) = occ.str("GROUP_NO_CENTRE") {
        let members = select::group_no(mesh, g).map_err(ExecError::new)?;
        if let [n] = members {
            return Ok(mesh.coord(*n));
        }
        return Err(ex.kw_error(
            "DEFI_GROUP/CREA_GROUP_NO",
            occ,
            "GROUP_NO_CENTRE",
            format!("group `{g}` has {} nodes; one is needed", members.len()),
        ));
    }
    Err(ExecError::new(
        "DEFI_GROUP/CREA_GROUP_NO: give the point (POINT, NOEUD_CENTRE or GROUP_NO_CENTRE)",
    ))
}

/// The single node of a one-node group.
fn one_node(mesh: &Mesh, group: &str, what: &str) -> Result<NodeId, ExecError> {
    match select::group_no(mesh, group).map_err(|e| ExecError::new(format!("{what}: {e}")))? {
        [n] => Ok(*n),
        many => Err(ExecError::new(format!(
            "{what}: group `{group}` has {} nodes; one is needed",
            many.len()
        ))),
    }
}

/// `CREA_GROUP_NO` with `GROUP_NO` (one group) and `POSITION` or
/// `NUME_INIT`/`NUME_FIN` (code_aster's `sscgno`): the group's first
/// (`INIT`), last (`FIN`) or middle (`MILIEU`: the ((n + 1) / 2)-th) node,
/// or its nodes NUME_INIT to NUME_FIN (1-based, defaults 1 and n), in the
/// group's order.
fn part_of_group(mesh: &Mesh, occ: &Keywords) -> Result<Vec<NodeId>, ExecError> {
    let what = "DEFI_GROUP/CREA_GROUP_NO";
    let groups: Vec<&str> = occ
        .simple("GROUP_NO")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let g = match groups.as_slice() {
        [g] => *g,
        _ => {
            return Err(ExecError::new(format!(
                "{what}: POSITION, NUME_INIT and NUME_FIN take one GROUP_NO"
            )))
        }
    };
    let members = select::group_no(mesh, g).map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    let n = members.len();
    if n == 0 {
        return Err(ExecError::new(format!("{what}: group `{g}` is empty")));
    }
    if let Some(p) = occ.str("POSITION") {
        let i = match p {
            "INIT" => 1,
            "FIN" => n,
            "MILIEU" => n.div_ceil(2),
            other => {
                return Err(ExecError::new(format!("{what}: POSITION='{other}'")));
            }
        };
        return Ok(vec![members[i - 1]]);
    }
    let index = |k: &str, default: usize| -> Result<usize, ExecError> {
        match occ.first(k).and_then(|v| v.as_i64()) {
            None => Ok(default),
            Some(i) if i >= 1 && (i as usize) <= n => Ok(i as usize),
            Some(i) => Err(ExecError::new(format!(
                "{what}: {k}={i} outside group `{g}` (1 to {n})"
            ))),
        }
    };
    let (a, b) = (index("NUME_INIT", 1)?, index("NUME_FIN", n)?);
    if b < a {
        return Err(ExecError::new(format!("{what}: NUME_FIN < NUME_INIT")));
    }
    Ok(members[a - 1..b].to_vec())
}

/// `CREA_GROUP_NO/OPTION`: (name, nodes) of a group defined by geometry.
fn geometric_group(
    ex: &Executor,
    mesh: &Mesh,
    occ: &aster_eval::Keywords,
    option: &str,
) -> Result<(String, Vec<NodeId>), ExecError> {
    let what = format!("DEFI_GROUP/CREA_GROUP_NO/OPTION='{option}'");
    let name = occ
        .str("NOM")
        .ok_or_else(|| ExecError::new(format!("{what}: NOM is required")))?
        .to_string();
    let precision = || {
        occ.f64("PRECISION")
            .ok_or_else(|| ExecError::new(format!("{what}: PRECISION is required")))
    };
    let err = |e: aster_mesh::MeshError| ExecError::new(format!("{what}: {e}"));
    let nodes = match option {
        "ENV_SPHERE" => {
            let radius = occ
                .f64("RAYON")
                .ok_or_else(|| ExecError::new(format!("{what}: RAYON is required")))?;
            mesh.nodes_on_sphere(centre(ex, mesh, occ)?, radius, precision()?)
        }
        "PLAN" => {
            let normal = normal_vector(occ, &what)?;
            mesh.nodes_on_plane(centre(ex, mesh, occ)?, normal, precision()?)
                .map_err(err)?
        }
        "SEGM_DROI_ORDO" => {
            let a = one_node(mesh, occ.str("GROUP_NO_ORIG").unwrap_or(""), &what)?;
            let b = one_node(mesh, occ.str("GROUP_NO_EXTR").unwrap_or(""), &what)?;
            let candidates = if occ.contains("GROUP_NO") || occ.contains("NOEUD") {
                select::nodes(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?
            } else {
                (0..mesh.node_count() as u32).map(NodeId).collect()
            };
            let mut tol = precision()?;
            if occ.str("CRITERE") != Some("ABSOLU") {
                let d: f64 = (0..3)
                    .map(|k| (mesh.coord(b)[k] - mesh.coord(a)[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                tol *= d;
            }
            mesh.nodes_on_segment(&candidates, a, b, tol).map_err(err)?
        }
        "NOEUD_ORDO" => {
            let cells =
                select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
            let origin = occ
                .str("GROUP_NO_ORIG")
                .map(|g| one_node(mesh, g, &what))
                .transpose()?;
            let end = occ
                .str("GROUP_NO_EXTR")
                .map(|g| one_node(mesh, g, &what))
                .transpose()?;
            mesh.nodes_along_line(&cells, origin, end).map_err(err)?
        }
        other => {
            let span = occ.keyword("OPTION").map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported(&format!("DEFI_GROUP/CREA_GROUP_NO/OPTION='{other}'"), span));
        }
    };
    Ok((name, nodes))
}

/// The direction an occurrence gives by `VECT_NORMALE` (missing components
/// are 0) or by nautical angles `ANGL_NAUT` in degrees (the rotated x axis).
fn normal_vector(occ: &Keywords, what: &str) -> Result<[f64; 3], ExecError> {
    let v: Vec<f64> = occ
        .simple("VECT_NORMALE")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    let a: Vec<f64> = occ
        .simple("ANGL_NAUT")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    if !v.is_empty() {
        Ok([
            v[0],
            v.get(1).copied().unwrap_or(0.0),
            v.get(2).copied().unwrap_or(0.0),
        ])
    } else if !a.is_empty() {
        let (al, be) = (
            a[0].to_radians(),
            a.get(1).copied().unwrap_or(0.0).to_radians(),
        );
        Ok([al.cos() * be.cos(), al.sin() * be.cos(), -be.sin()])
    } else {
        Err(ExecError::new(format!(
            "{what}: give VECT_NORMALE or ANGL_NAUT"
        )))
    }
}

/// The nodes of cells as code_aster's `gmgnre` lists them for a node group
/// made from cells (`CREA_GROUP_NO` with `GROUP_MA`/`TOUT_GROUP_MA`): each
/// once, in the order of the node numbers (not of the cells). The order
/// matters where a group is read as a path (POST_RELEVE_T's abscissa, its
/// local frame, MOYENNE).
fn nodes_of_cells(
    mesh: &aster_mesh::Mesh,
    cells: &[aster_mesh::CellId],
    kind: NodeKind,
) -> Vec<NodeId> {
    let mut nodes = mesh.nodes_of_cells_kind(cells, kind);
    nodes.sort_unstable();
    nodes
}
