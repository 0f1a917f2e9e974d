//! `AFFE_CHAR_MECA/LIAISON_MAIL` with `TYPE_RACCORD='MASSIF'` (code_aster's
//! `kineLoadGlueMeshMeca`): each slave node is glued to the master cells by
//! one linear relation per displacement component, u_s = Σ cᵢ u_mᵢ, the cᵢ
//! being the master cell's shape functions at the node — located as
//! PROJ_CHAMP's collocation locates it (`pj2dco`/`pj3dco`, here
//! aster-fem's [`aster_fem::projection`]).
//!
//! Slave nodes: `GROUP_NO_ESCL` and the nodes of `GROUP_MA_ESCL`; master
//! cells: those of `GROUP_MA_MAIT` in the model (volumes in 3D, faces in
//! 2D). With `ELIM_MULT='OUI'` (default) a node already slave in an earlier
//! occurrence of the load is dropped (`kineLoadElimMult`; none left is
//! code_aster's CHARGES7_48). A node located nowhere (beyond
//! `DISTANCE_MAX`) gets no relation; a slave node that is its own master
//! with a coefficient 1 (to 1e-2) gets none either (code_aster's alarm
//! CHARGES7_1). `DDL` restricts the components (`DNOR` is refused by the
//! value table). Not reproduced, so refused by the support table: the
//! other `TYPE_RACCORD`s (shells), `TRAN`/`ANGL_NAUT`/`CENTRE`.

use super::loads::check_dof;
use crate::concept::{LinearRelation, ModelDef};
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_fem::projection::{case_of, Case, Correspondence, Options};
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeSet;

fn names(occ: &Keywords, key: &str) -> Vec<String> {
    occ.simple(key)
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect()
}

/// The relations of every LIAISON_MAIL occurrence of one AFFE_CHAR_MECA.
pub(crate) fn relations(
    occurrences: &[Keywords],
    model: &ModelDef,
    mesh: &Mesh,
    carried: &[bool],
) -> Result<Vec<LinearRelation>, ExecError> {
    let what = "AFFE_CHAR_MECA/LIAISON_MAIL";
    let fail = |e: String| ExecError::new(format!("{what}: {e}"));
    let mut out = Vec::new();
    let mut slaves_before: BTreeSet<NodeId> = BTreeSet::new();
    for (i, occ) in occurrences.iter().enumerate() {
        let mut masters: Vec<CellId> = Vec::new();
        for g in names(occ, "GROUP_MA_MAIT") {
            masters.extend(
                select::group_ma(mesh, &g)
                    .map_err(fail)?
                    .iter()
                    .filter(|c| model.cells.contains_key(c)),
            );
        }
        let mut slaves: BTreeSet<NodeId> = BTreeSet::new();
        for g in names(occ, "GROUP_NO_ESCL") {
            slaves.extend(select::group_no(mesh, &g).map_err(fail)?.iter().copied());
        }
        for g in names(occ, "GROUP_MA_ESCL") {
            for &c in select::group_ma(mesh, &g).map_err(fail)? {
                slaves.extend(mesh.cell(c).nodes.iter().copied());
            }
        }
        if occ.str("ELIM_MULT").unwrap_or("OUI") == "OUI" {
            slaves.retain(|n| !slaves_before.contains(n));
            if slaves.is_empty() {
                return Err(fail(format!(
                    "occurrence {}: every slave node is already glued by an earlier occurrence (code_aster's CHARGES7_48)",
                    i + 1
                )));
            }
        }
        slaves_before.extend(slaves.iter().copied());
        let case = match case_of(mesh, &masters) {
            Some(c @ (Case::Volume | Case::Plane)) => c,
            _ => {
                return Err(fail(format!(
                    "occurrence {}: GROUP_MA_MAIT has no {} cell of the model to glue to (TYPE_RACCORD='MASSIF' projects on the master's {})",
                    i + 1,
                    if mesh.dim == 3 { "volume" } else { "surface" },
                    if mesh.dim == 3 { "volumes" } else { "faces" },
                )))
            }
        };
        let options = Options {
            distance_max: occ.f64("DISTANCE_MAX"),
            distance_alarme: occ.f64("DISTANCE_ALARME"),
        };
        let nodes: Vec<NodeId> = slaves.into_iter().collect();
        let mut corr = Correspondence::new(mesh, options);
        corr.add(mesh, &masters, mesh, &nodes, case)
            .map_err(|e| fail(e.to_string()))?;
        let dofs: Vec<&'static str> = match names(occ, "DDL").as_slice() {
            [] if model.dim() == 3 => vec!["DX", "DY", "DZ"],
            [] => vec!["DX", "DY"],
            given => ["DX", "DY", "DZ"]
                .into_iter()
                .filter(|d| given.iter().any(|g| g == d))
                .collect(),
        };
        for &s in &nodes {
            let Some(Some(link)) = corr.links.get(s.0 as usize) else {
                continue;
            };
            // CHARGES7_1: the slave node is its own master.
            if link
                .nodes
                .iter()
                .zip(&link.coefs)
                .any(|(&m, &c)| m == s && (c - 1.0).abs() < 1e-2)
            {
                continue;
            }
            for &d in &dofs {
                let mut terms = vec![(s, d, -1.0)];
                for (&m, &c) in link.nodes.iter().zip(&link.coefs) {
                    check_dof(model, mesh, carried, m, d, what)?;
                    terms.push((m, d, c));
                }
                check_dof(model, mesh, carried, s, d, what)?;
                out.push(LinearRelation { terms, rhs: 0.0 });
            }
        }
    }
    Ok(out)
}
