//! CREA_MAILLAGE: a new mesh made from another (aster-mesh `ops`).

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::select;
use crate::support::Support;
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{CentreNodes, Mesh, Restriction};
use std::sync::Arc;

const CMD: &str = "CREA_MAILLAGE";

/// The operations (factor keywords) this implementation executes.
const OPERATIONS: [&str; 9] = [
    "RESTREINT",
    "RAFFINEMENT",
    "LINE_QUAD",
    "QUAD_LINE",
    "HEXA20_27",
    "PENTA15_18",
    "CREA_POI1",
    "CREA_MAILLE",
    "MODI_MAILLE",
];

/// What CREA_MAILLAGE reads (`crate::support`), DECOUPE_LAC included.
pub(crate) const CREA_MAILLAGE: Support = Support::keywords(&[
    "MAILLAGE",
    "INFO",
    "TITRE",
    "RESTREINT",
    "RESTREINT/GROUP_MA",
    "RESTREINT/GROUP_NO",
    "RESTREINT/TOUT_GROUP_MA",
    "RESTREINT/TOUT_GROUP_NO",
    "RAFFINEMENT",
    "RAFFINEMENT/TOUT",
    "RAFFINEMENT/NIVEAU",
    "LINE_QUAD",
    "LINE_QUAD/TOUT",
    "LINE_QUAD/GROUP_MA",
    "LINE_QUAD/MAILLE",
    "LINE_QUAD/PREF_NOEUD",
    "LINE_QUAD/PREF_NUME",
    "QUAD_LINE",
    "QUAD_LINE/TOUT",
    "QUAD_LINE/GROUP_MA",
    "QUAD_LINE/MAILLE",
    "HEXA20_27",
    "HEXA20_27/TOUT",
    "HEXA20_27/GROUP_MA",
    "HEXA20_27/MAILLE",
    "HEXA20_27/PREF_NOEUD",
    "HEXA20_27/PREF_NUME",
    "PENTA15_18",
    "PENTA15_18/TOUT",
    "PENTA15_18/GROUP_MA",
    "PENTA15_18/MAILLE",
    "PENTA15_18/PREF_NOEUD",
    "PENTA15_18/PREF_NUME",
    "CREA_POI1",
    "CREA_POI1/NOM_GROUP_MA",
    "CREA_POI1/TOUT",
    "CREA_POI1/GROUP_MA",
    "CREA_POI1/GROUP_NO",
    "CREA_POI1/NOEUD",
    "CREA_MAILLE",
    "CREA_MAILLE/NOM",
    "CREA_MAILLE/TOUT",
    "CREA_MAILLE/GROUP_MA",
    "MODI_MAILLE",
    "MODI_MAILLE/TOUT",
    "MODI_MAILLE/GROUP_MA",
    "MODI_MAILLE/MAILLE",
    "MODI_MAILLE/OPTION",
    "MODI_MAILLE/PREF_NOEUD",
    "MODI_MAILLE/PREF_NUME",
    "MODI_MAILLE/PREF_MAILLE",
    "COPIE",
    "DECOUPE_LAC",
    "DECOUPE_LAC/GROUP_MA_ESCL",
    "DECOUPE_LAC/DECOUPE_HEXA",
]);

pub fn crea_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    if kw.keyword("DECOUPE_LAC").is_some_and(|k| !k.defaulted) {
        return decoupe_lac(ex, call);
    }
    let source = ex.required(CMD, kw, "MAILLAGE")?;
    let mut mesh = (*ex.mesh(source)?).clone();
    // Legacy `COPIE=_F()` (code_aster ≤ 11): a plain copy.
    if kw.keyword("COPIE").is_some() {
        return store_result(ex, call, Concept::Mesh(Arc::new(mesh)));
    }
    let present: Vec<&str> = OPERATIONS
        .into_iter()
        .filter(|op| kw.keyword(op).is_some_and(|k| !k.defaulted))
        .collect();
    if present.len() != 1 {
        return Err(ExecError::new(format!(
            "{CMD}: give exactly one operation among {} (found {})",
            OPERATIONS.join(", "),
            if present.is_empty() {
                "none".to_string()
            } else {
                present.join(", ")
            }
        )));
    }
    let op = present[0];
    let err = |e: String| ExecError::new(format!("{CMD}/{op}: {e}"));
    let cells_of = |occ: &Keywords, mesh: &Mesh| select::cells(occ, mesh, "").map_err(err);
    match op {
        "RESTREINT" => {
            let occ = &kw.factor(op)[0];
            let names = |k: &str| -> Vec<&str> {
                occ.simple(k).iter().filter_map(|s| s.as_str()).collect()
            };
            let (gma, gno) = (names("GROUP_MA"), names("GROUP_NO"));
            mesh = mesh
                .restrict(&Restriction {
                    groups_ma: &gma,
                    groups_no: &gno,
                    all_groups_ma: occ.str("TOUT_GROUP_MA") == Some("OUI"),
                    all_groups_no: occ.str("TOUT_GROUP_NO") == Some("OUI"),
                })
                .map_err(|e| err(e.to_string()))?;
        }
        // `Mesh.refine(n)` is this (code_aster's `cmraff`).
        "RAFFINEMENT" => {
            let level = kw.factor(op)[0]
                .first("NIVEAU")
                .and_then(|s| s.as_i64())
                .unwrap_or(1);
            mesh = crate::mesh_methods::refined(&mesh, level).map_err(|e| err(e.message))?;
        }
        "LINE_QUAD" => {
            let cells = cells_of(&kw.factor(op)[0], &mesh)?;
            mesh.line_to_quad(&cells);
        }
        "QUAD_LINE" => {
            let cells = cells_of(&kw.factor(op)[0], &mesh)?;
            mesh.quad_to_line(&cells);
        }
        "HEXA20_27" | "PENTA15_18" => {
            let cells = cells_of(&kw.factor(op)[0], &mesh)?;
            let kind = if op == "HEXA20_27" {
                CentreNodes::Hexa20To27
            } else {
                CentreNodes::Penta15To18
            };
            mesh.add_centre_nodes(&cells, kind);
        }
        "CREA_POI1" => {
            for occ in kw.factor(op) {
                let nodes = select::nodes(occ, &mesh, "").map_err(err)?;
                mesh.add_point_cells(&nodes, occ.str("NOM_GROUP_MA"));
            }
        }
        // Copies of cells on the same nodes (aster-mesh `Mesh::copy_cells`).
        "CREA_MAILLE" => {
            for occ in kw.factor(op) {
                // The catalogue's UN_PARMI("TOUT", "GROUP_MA", TOUT="OUI"):
                // without either, every cell is copied (ssls117b).
                let cells = if occ.contains("GROUP_MA") || occ.contains("TOUT") {
                    cells_of(occ, &mesh)?
                } else {
                    (0..mesh.cells.len() as u32)
                        .map(aster_mesh::CellId)
                        .collect()
                };
                let Some(name) = occ.str("NOM") else {
                    return Err(ex.kw_error(CMD, occ, "NOM", "CREA_MAILLE needs NOM"));
                };
                mesh.copy_cells(&cells, name)
                    .map_err(|e| ex.kw_error(CMD, occ, "NOM", e.to_string()))?;
            }
        }
        _ => {
            for occ in kw.factor(op) {
                let cells = cells_of(occ, &mesh)?;
                match occ.str("OPTION") {
                    Some("QUAD8_9") => {
                        mesh.add_centre_nodes(&cells, CentreNodes::Quad8To9);
                    }
                    Some("TRIA6_7") => {
                        mesh.add_centre_nodes(&cells, CentreNodes::Tria6To7);
                    }
                    Some("QUAD_TRIA3") => {
                        mesh.quad4_to_tria3(&cells)
                            .map_err(|e| ExecError::new(e.to_string()))?;
                    }
                    other => {
                        let span = occ.keyword("OPTION").map(|k| k.span).unwrap_or_default();
                        return Err(ex.unsupported(
                            &format!("{CMD}/MODI_MAILLE/OPTION='{}'", other.unwrap_or("")),
                            span,
                        ));
                    }
                }
            }
        }
    }
    store_result(ex, call, Concept::Mesh(Arc::new(mesh)))
}

/// `DECOUPE_LAC`: the mesh cut for LAC contact; the patches are kept beside
/// it for DEFI_CONTACT(ALGO_CONT='LAC').
fn decoupe_lac(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let source = ex.required(CMD, kw, "MAILLAGE")?;
    let mesh = ex.mesh(source)?;
    let Some(occ) = kw.factor("DECOUPE_LAC").first() else {
        return Err(ExecError::new(format!("{CMD}: DECOUPE_LAC is required")));
    };
    let groups: Vec<&str> = occ
        .simple("GROUP_MA_ESCL")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    // DECOUPE_HEXA (default 'PYRA'): how the quadrangles of hexahedra are cut.
    let hexa = match occ.simple("DECOUPE_HEXA").first().and_then(|v| v.as_str()) {
        Some("HEXA") => aster_mesh::DecoupeHexa::Hexa,
        _ => aster_mesh::DecoupeHexa::Pyra,
    };
    let options = aster_mesh::LacOptions {
        hexa,
        reference: &aster_fem::shape::ReferenceCells,
    };
    let (cut, patches) = aster_mesh::decoupe_lac_with(&mesh, &groups, options)
        .map_err(|e| ex.kw_error(CMD, occ, "GROUP_MA_ESCL", e.to_string()))?;
    let cut = Arc::new(cut);
    ex.lac_patches.push((cut.clone(), Arc::new(patches)));
    store_result(ex, call, Concept::Mesh(cut))
}
