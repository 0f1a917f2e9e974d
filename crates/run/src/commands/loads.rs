//! AFFE_CHAR_CINE, AFFE_CHAR_MECA, DEFI_CONTACT.

use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::select;
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{Mesh, NodeId};
use std::rc::Rc;

/// Displacement components a mechanical condition may name.
const COMPS: [CompName; 6] = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];

fn comp_name(name: &str) -> Option<CompName> {
    COMPS.iter().copied().find(|c| *c == name)
}

/// Checks that a node carries a component in the model (2D models have
/// no DZ; nodes outside the model have nothing).
pub(super) fn check_dof(
    model: &ModelDef,
    mesh: &Mesh,
    carried: &[bool],
    node: NodeId,
    comp: CompName,
    what: &str,
) -> Result<(), ExecError> {
    if !carried.get(node.0 as usize).copied().unwrap_or(false) {
        return Err(ExecError::new(format!(
            "{what}: node {} is not carried by any element of the model, so it has no {comp}",
            mesh.node_name(node)
        )));
    }
    let dim = model.dim();
    let rotations = model
        .rotations
        .get(node.0 as usize)
        .copied()
        .unwrap_or(false);
    let ok = match comp {
        "DX" | "DY" => true,
        "DZ" => dim == 3,
        "DRX" | "DRY" | "DRZ" => rotations,
        _ => false,
    };
    if !ok && model.has_rotations() {
        return Err(ExecError::new(format!(
            "{what}: node {} has no component {comp} (only the nodes of shell, beam and DIS_TR cells carry DRX, DRY, DRZ)",
            mesh.node_name(node)
        )));
    }
    if !ok {
        return Err(ExecError::new(format!(
            "{what}: the model has no component {comp} (a {dim}D model of translations)",
        )));
    }
    Ok(())
}

/// Which nodes carry DOFs: those of the model's cells.
pub fn carried_nodes(model: &ModelDef, mesh: &Mesh) -> Vec<bool> {
    let mut carried = vec![false; mesh.node_count()];
    for c in model.cells.keys() {
        for n in &mesh.cell(*c).nodes {
            carried[n.0 as usize] = true;
        }
    }
    carried
}

/// The imposed (node, component, value) of every occurrence of a
/// DDL_IMPO/MECA_IMPO/FORCE_NODALE keyword, each checked to be a DOF of the
/// model.
fn imposed_values(
    ex: &Executor,
    occurrences: &[Keywords],
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
    comps: &[&str],
    what: &str,
) -> Result<Vec<Imposed>, ExecError> {
    let mut out = Vec::new();
    for occ in occurrences {
        let start = out.len();
        imposed_in(ex, occ, mesh, comps, what, &mut out)?;
        blocked_in(ex, occ, model, mesh, what, &mut out)?;
        for i in &out[start..] {
            check_dof(model, mesh, carried, i.node, i.comp, what)?;
        }
    }
    Ok(out)
}

/// `DDL_IMPO/BLOCAGE`: zero on every degree of freedom of the kinds listed
/// that the nodes carry — 'DEPLACEMENT': the translations of the model
/// (DX, DY, and DZ in 3D); 'ROTATION': DRX DRY DRZ on the nodes of shell
/// cells, nothing elsewhere (code_aster blocks only the DOFs present).
fn blocked_in(
    ex: &Executor,
    occ: &Keywords,
    model: &ModelDef,
    mesh: &Mesh,
    what: &str,
    out: &mut Vec<Imposed>,
) -> Result<(), ExecError> {
    let kinds: Vec<&str> = occ
        .simple("BLOCAGE")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    if kinds.is_empty() {
        return Ok(());
    }
    let nodes =
        select::nodes_without(occ, mesh).map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    for kind in kinds {
        let comps: &[&'static str] = match kind {
            "DEPLACEMENT" if model.dim() == 3 => &["DX", "DY", "DZ"],
            "DEPLACEMENT" => &["DX", "DY"],
            "ROTATION" => &["DRX", "DRY", "DRZ"],
            other => {
                return Err(ex.unsupported(
                    &format!("{what}/BLOCAGE='{other}'"),
                    occ.keyword("BLOCAGE").map(|k| k.span).unwrap_or_default(),
                ))
            }
        };
        for &n in &nodes {
            let rotations = model.rotations.get(n.0 as usize).copied().unwrap_or(false);
            for &comp in comps {
                if comp.starts_with("DR") && !rotations {
                    continue;
                }
                out.push(Imposed {
                    node: n,
                    comp,
                    value: 0.0,
                });
            }
        }
    }
    Ok(())
}

/// One imposed value per node and component in a load, the last one given
/// (code_aster: `ordlrl` drops the earlier single-term relations of an
/// AFFE_CHAR_MECA load, whatever their values; AFFE_CHAR_CINE's `charci`
/// overwrites its field occurrence after occurrence). A DOF on two lines
/// of a boundary, e.g. given by a function on one and 0 on the other,
/// is no conflict.
pub(crate) fn last_per_dof<T>(items: Vec<T>, key: impl Fn(&T) -> (NodeId, CompName)) -> Vec<T> {
    let mut last = std::collections::HashMap::new();
    for (k, item) in items.iter().enumerate() {
        last.insert(key(item), k);
    }
    items
        .into_iter()
        .enumerate()
        .filter(|(k, item)| last.get(&key(item)) == Some(k))
        .map(|(_, item)| item)
        .collect()
}

/// code_aster's `ordlrl` on the relations of one keyword (`aflrch` calls
/// it on each keyword's list): of relations with two or more terms on the
/// same DOFs with proportional coefficients (within 1e4·ε of the largest),
/// only the last is kept, whatever their right-hand sides. A node on two
/// occurrences of LIAISON_GROUP (sections sharing a line) gets its
/// relation once, not twice (a singular system).
pub(crate) fn drop_redundant(relations: Vec<LinearRelation>) -> Vec<LinearRelation> {
    let eps = 1.0e4 * f64::EPSILON;
    let order = |c: CompName| COMPS.iter().position(|x| *x == c).unwrap_or(usize::MAX);
    let sorted: Vec<Vec<(NodeId, usize, f64)>> = relations
        .iter()
        .map(|r| {
            let mut t: Vec<_> = r.terms.iter().map(|&(n, c, a)| (n, order(c), a)).collect();
            t.sort_by_key(|&(n, c, _)| (n, c));
            t
        })
        .collect();
    let mut by_dofs: std::collections::HashMap<Vec<(NodeId, usize)>, Vec<usize>> =
        Default::default();
    for (k, t) in sorted.iter().enumerate() {
        if t.len() >= 2 {
            by_dofs
                .entry(t.iter().map(|&(n, c, _)| (n, c)).collect())
                .or_default()
                .push(k);
        }
    }
    let mut dropped = vec![false; relations.len()];
    for same in by_dofs.values() {
        for (i, &k1) in same.iter().enumerate() {
            let t1 = &sorted[k1];
            let (imax, amax) = t1
                .iter()
                .enumerate()
                .map(|(i, t)| (i, t.2.abs()))
                .fold((0, 0.0), |m, x| if x.1 > m.1 { x } else { m });
            if amax == 0.0 {
                continue;
            }
            // Every earlier relation proportional to this one goes.
            for &k2 in &same[..i] {
                let t2 = &sorted[k2];
                let ratio = t2[imax].2 / t1[imax].2;
                if t1
                    .iter()
                    .zip(t2)
                    .all(|(a, b)| (b.2 - ratio * a.2).abs() <= eps * amax)
                {
                    dropped[k2] = true;
                }
            }
        }
    }
    relations
        .into_iter()
        .zip(dropped)
        .filter(|(_, d)| !d)
        .map(|(r, _)| r)
        .collect()
}

/// The real value of `key` in `occ`, if given; a function there (which
/// AFFE_CHAR_MECA_F takes) is an error at the keyword.
pub(super) fn real_value(
    ex: &Executor,
    what: &str,
    occ: &Keywords,
    key: &str,
) -> Result<Option<f64>, ExecError> {
    occ.first(key)
        .map(|s| {
            s.as_f64().ok_or_else(|| {
                ex.kw_error(
                    what,
                    occ,
                    key,
                    "a real value is required (functions need AFFE_CHAR_MECA_F)",
                )
            })
        })
        .transpose()
}

/// The imposed values of one occurrence, appended to `out`.
fn imposed_in(
    ex: &Executor,
    occ: &Keywords,
    mesh: &Mesh,
    comps: &[&str],
    what: &str,
    out: &mut Vec<Imposed>,
) -> Result<(), ExecError> {
    let nodes =
        select::nodes_without(occ, mesh).map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    for &c in comps {
        if let Some(v) = real_value(ex, what, occ, c)? {
            let name: &'static str = match c {
                "DX" => "DX",
                "DY" => "DY",
                "DZ" => "DZ",
                "FX" => "DX",
                "FY" => "DY",
                "FZ" => "DZ",
                // Rotations and moments: the shells' nodes carry them
                // (`check_dof` refuses them elsewhere).
                "DRX" | "MX" => "DRX",
                "DRY" | "MY" => "DRY",
                "DRZ" | "MZ" => "DRZ",
                _ => {
                    return Err(ex.unsupported(
                        &format!("{what}/{c}"),
                        occ.keyword(c).map(|k| k.span).unwrap_or_default(),
                    ))
                }
            };
            for &n in &nodes {
                out.push(Imposed {
                    node: n,
                    comp: name,
                    value: v,
                });
            }
        }
    }
    Ok(())
}

/// What AFFE_CHAR_CINE reads (`crate::support`).
pub(crate) const AFFE_CHAR_CINE: Support = Support::keywords(&[
    "MODELE",
    "INFO",
    "MECA_IMPO",
    "MECA_IMPO/TOUT",
    "MECA_IMPO/GROUP_NO",
    "MECA_IMPO/NOEUD",
    "MECA_IMPO/GROUP_MA",
    "MECA_IMPO/MAILLE",
    "MECA_IMPO/SANS_GROUP_NO",
    "MECA_IMPO/DX",
    "MECA_IMPO/DY",
    "MECA_IMPO/DZ",
    "MECA_IMPO/DRX",
    "MECA_IMPO/DRY",
    "MECA_IMPO/DRZ",
]);

pub fn affe_char_cine(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("AFFE_CHAR_CINE", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let carried = carried_nodes(&model, &mesh);
    let imposed = imposed_values(
        ex,
        kw.factor("MECA_IMPO"),
        (&model, &mesh, &carried),
        &COMPS,
        "AFFE_CHAR_CINE/MECA_IMPO",
    )?;
    if kw.factor("MECA_IMPO").is_empty() {
        return Err(ExecError::new(
            "AFFE_CHAR_CINE: MECA_IMPO is required (the only condition supported yet)",
        ));
    }
    let imposed = last_per_dof(imposed, |i| (i.node, i.comp));
    store_result(
        ex,
        call,
        Concept::KinematicLoad(Rc::new(KinematicLoad {
            model: model_ref.id,
            imposed,
            imposed_fn: Vec::new(),
        })),
    )
}

/// What AFFE_CHAR_MECA reads (`crate::support`).
pub(crate) const AFFE_CHAR_MECA: Support = Support {
    keywords: &[
        "MODELE",
        "INFO",
        "VERI_NORM",
        "DOUBLE_LAGRANGE",
        "DDL_IMPO",
        "DDL_IMPO/TOUT",
        "DDL_IMPO/GROUP_NO",
        "DDL_IMPO/NOEUD",
        "DDL_IMPO/GROUP_MA",
        "DDL_IMPO/MAILLE",
        "DDL_IMPO/SANS_GROUP_NO",
        "DDL_IMPO/SANS_GROUP_MA",
        "DDL_IMPO/DX",
        "DDL_IMPO/DY",
        "DDL_IMPO/DZ",
        "DDL_IMPO/DRX",
        "DDL_IMPO/DRY",
        "DDL_IMPO/DRZ",
        "DDL_IMPO/BLOCAGE",
        "FORCE_NODALE",
        "FORCE_NODALE/GROUP_NO",
        "FORCE_NODALE/NOEUD",
        "FORCE_NODALE/FX",
        "FORCE_NODALE/FY",
        "FORCE_NODALE/FZ",
        "FORCE_NODALE/MX",
        "FORCE_NODALE/MY",
        "FORCE_NODALE/MZ",
        "FORCE_CONTOUR",
        "FORCE_CONTOUR/GROUP_MA",
        "FORCE_CONTOUR/MAILLE",
        "FORCE_CONTOUR/FX",
        "FORCE_CONTOUR/FY",
        "FORCE_FACE",
        "FORCE_FACE/GROUP_MA",
        "FORCE_FACE/MAILLE",
        "FORCE_FACE/FX",
        "FORCE_FACE/FY",
        "FORCE_FACE/FZ",
        "PRES_REP",
        "PRES_REP/GROUP_MA",
        "PRES_REP/MAILLE",
        "PRES_REP/TOUT",
        "PRES_REP/PRES",
        "FORCE_INTERNE",
        "FORCE_INTERNE/TOUT",
        "FORCE_INTERNE/GROUP_MA",
        "FORCE_INTERNE/MAILLE",
        "FORCE_INTERNE/FX",
        "FORCE_INTERNE/FY",
        "FORCE_INTERNE/FZ",
        "FACE_IMPO",
        "FACE_IMPO/GROUP_MA",
        "FACE_IMPO/MAILLE",
        "FACE_IMPO/SANS_GROUP_NO",
        "FACE_IMPO/DX",
        "FACE_IMPO/DY",
        "FACE_IMPO/DZ",
        "FACE_IMPO/DNOR",
        "FACE_IMPO/SANS_GROUP_MA",
        "LIAISON_GROUP",
        "LIAISON_GROUP/GROUP_NO_1",
        "LIAISON_GROUP/GROUP_NO_2",
        "LIAISON_GROUP/GROUP_MA_1",
        "LIAISON_GROUP/GROUP_MA_2",
        "LIAISON_GROUP/SANS_GROUP_NO",
        "LIAISON_GROUP/DDL_1",
        "LIAISON_GROUP/DDL_2",
        "LIAISON_GROUP/COEF_MULT_1",
        "LIAISON_GROUP/COEF_MULT_2",
        "LIAISON_GROUP/COEF_IMPO",
        "LIAISON_ELEM",
        "LIAISON_ELEM/OPTION",
        "LIAISON_ELEM/GROUP_MA_1",
        "LIAISON_ELEM/GROUP_NO_2",
        "LIAISON_ELEM/GROUP_MA_2",
        "LIAISON_ELEM/ANGL_MAX",
        "LIAISON_UNIF",
        "LIAISON_UNIF/GROUP_NO",
        "LIAISON_UNIF/NOEUD",
        "LIAISON_UNIF/GROUP_MA",
        "LIAISON_UNIF/MAILLE",
        "LIAISON_UNIF/SANS_GROUP_NO",
        "LIAISON_UNIF/DDL",
        "LIAISON_DDL",
        "LIAISON_DDL/GROUP_NO",
        "LIAISON_DDL/NOEUD",
        "LIAISON_DDL/DDL",
        "LIAISON_DDL/COEF_MULT",
        "LIAISON_DDL/COEF_IMPO",
        "LIAISON_MAIL",
        "LIAISON_MAIL/GROUP_MA_MAIT",
        "LIAISON_MAIL/GROUP_MA_ESCL",
        "LIAISON_MAIL/GROUP_NO_ESCL",
        "LIAISON_MAIL/DISTANCE_MAX",
        "LIAISON_MAIL/DISTANCE_ALARME",
        "LIAISON_MAIL/TYPE_RACCORD",
        "LIAISON_MAIL/ELIM_MULT",
        "LIAISON_MAIL/DDL",
        "PESANTEUR",
        "PESANTEUR/GROUP_MA",
        "PESANTEUR/GRAVITE",
        "PESANTEUR/DIRECTION",
        "FORCE_COQUE",
        "FORCE_COQUE/TOUT",
        "FORCE_COQUE/GROUP_MA",
        "FORCE_COQUE/FX",
        "FORCE_COQUE/FY",
        "FORCE_COQUE/FZ",
        "FORCE_COQUE/MX",
        "FORCE_COQUE/MY",
        "FORCE_COQUE/MZ",
        "FORCE_COQUE/PRES",
        "FORCE_COQUE/F3",
        "FORCE_COQUE/PLAN",
        "FORCE_ARETE",
        "FORCE_ARETE/GROUP_MA",
        "FORCE_ARETE/FX",
        "FORCE_ARETE/FY",
        "FORCE_ARETE/FZ",
        "FORCE_ARETE/MX",
        "FORCE_ARETE/MY",
        "FORCE_ARETE/MZ",
        "LIAISON_OBLIQUE",
        "LIAISON_OBLIQUE/GROUP_NO",
        "LIAISON_OBLIQUE/GROUP_MA",
        "LIAISON_OBLIQUE/SANS_GROUP_NO",
        "LIAISON_OBLIQUE/SANS_GROUP_MA",
        "LIAISON_OBLIQUE/ANGL_NAUT",
        "LIAISON_OBLIQUE/DX",
        "LIAISON_OBLIQUE/DY",
        "LIAISON_OBLIQUE/DZ",
        "LIAISON_OBLIQUE/DRX",
        "LIAISON_OBLIQUE/DRY",
        "LIAISON_OBLIQUE/DRZ",
    ],
    values: &[
        Values::new("DDL_IMPO/BLOCAGE", &["DEPLACEMENT", "ROTATION"]),
        // LIAISON_MAIL: solids only (crate::commands::liaison_mail).
        Values::new("LIAISON_MAIL/TYPE_RACCORD", &["MASSIF"]),
        Values::new("LIAISON_MAIL/DDL", &["DX", "DY", "DZ"]),
        Values::new("LIAISON_ELEM/OPTION", &["3D_POU"]),
    ],
    hints: &[],
    reuse: true,
    rules: None,
};

pub fn affe_char_meca(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("AFFE_CHAR_MECA", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let carried = carried_nodes(&model, &mesh);
    let mut load = MechanicalLoad {
        model: model_ref.id,
        ..MechanicalLoad::default()
    };
    load.imposed = imposed_values(
        ex,
        kw.factor("DDL_IMPO"),
        (&model, &mesh, &carried),
        &COMPS,
        "AFFE_CHAR_MECA/DDL_IMPO",
    )?;
    // FACE_IMPO with DX/DY/DZ imposes them on the nodes of the faces.
    load.imposed.extend(imposed_values(
        ex,
        kw.factor("FACE_IMPO"),
        (&model, &mesh, &carried),
        &["DX", "DY", "DZ"],
        "AFFE_CHAR_MECA/FACE_IMPO",
    )?);
    load.imposed = last_per_dof(std::mem::take(&mut load.imposed), |i| (i.node, i.comp));
    for occ in kw.factor("FORCE_INTERNE") {
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CHAR_MECA/FORCE_INTERNE: {e}")))?;
        let force = [
            occ.f64("FX").unwrap_or(0.0),
            occ.f64("FY").unwrap_or(0.0),
            occ.f64("FZ").unwrap_or(0.0),
        ];
        load.volume.push(VolumeForce {
            cells: continuum_cells(&model, &mesh, cells),
            force,
            functions: [None, None, None],
        });
    }
    for occ in kw.factor("FACE_IMPO") {
        if occ.contains("DNOR") {
            load.relations
                .extend(face_dnor(ex, occ, (&model, &mesh, &carried))?);
        }
    }
    let mut grouped = Vec::new();
    for occ in kw.factor("LIAISON_GROUP") {
        let rhs = occ.f64("COEF_IMPO").unwrap_or(0.0);
        grouped.extend(liaison_group(
            ex,
            "AFFE_CHAR_MECA/LIAISON_GROUP",
            occ,
            (&model, &mesh, &carried),
            rhs,
        )?);
    }
    load.relations.extend(drop_redundant(grouped));
    for occ in kw.factor("LIAISON_ELEM") {
        load.relations
            .extend(liaison_elem_3d_pou(ex, occ, (&model, &mesh, &carried))?);
    }
    for occ in kw.factor("LIAISON_UNIF") {
        let what = "AFFE_CHAR_MECA/LIAISON_UNIF";
        let nodes = select::nodes_without(occ, &mesh)
            .map_err(|e| ExecError::new(format!("{what}: {e}")))?;
        for d in occ.simple("DDL").iter().filter_map(|s| s.as_str()) {
            let comp = comp_name(d)
                .ok_or_else(|| ExecError::new(format!("{what}: unknown component `{d}`")))?;
            let Some((&first, rest)) = nodes.split_first() else {
                continue;
            };
            check_dof(&model, &mesh, &carried, first, comp, what)?;
            for &n in rest {
                check_dof(&model, &mesh, &carried, n, comp, what)?;
                load.relations.push(LinearRelation {
                    terms: vec![(n, comp, 1.0), (first, comp, -1.0)],
                    rhs: 0.0,
                });
            }
        }
    }
    let ctx = (&*model, &*mesh, carried.as_slice());
    for occ in kw.factor("PESANTEUR") {
        load.gravity
            .push(super::loads_more::pesanteur(ex, kw, occ, (&model, &mesh))?);
    }
    for occ in kw.factor("FORCE_ARETE") {
        load.edges
            .push(super::loads_more::force_arete(ex, occ, ctx)?);
    }
    for occ in kw.factor("FORCE_COQUE") {
        let what = "AFFE_CHAR_MECA/FORCE_COQUE";
        let (keys, sign) = super::loads_more::shell_comps(occ);
        let mut values = [0.0; 7];
        for (v, key) in values.iter_mut().zip(keys) {
            *v = real_value(ex, what, occ, key)?.unwrap_or(0.0);
        }
        let shell = super::loads_more::force_coque(
            ex,
            what,
            occ,
            (&model, &mesh),
            values,
            Default::default(),
            sign,
        )?;
        load.shells.push(shell);
    }
    load.shells = super::loads_more::last_per_cell(std::mem::take(&mut load.shells));
    let mut oblique = Vec::new();
    for occ in kw.factor("LIAISON_OBLIQUE") {
        let what = "AFFE_CHAR_MECA/LIAISON_OBLIQUE";
        let mut given = Vec::new();
        for key in ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"] {
            if let Some(v) = real_value(ex, what, occ, key)? {
                given.push((key, v));
            }
        }
        let rows = super::loads_more::liaison_oblique(ex, what, occ, ctx, &given)?;
        oblique.extend(rows.into_iter().map(|(_, r)| r));
    }
    load.relations.extend(drop_redundant(oblique));
    load.nodal_forces = imposed_values(
        ex,
        kw.factor("FORCE_NODALE"),
        (&model, &mesh, &carried),
        &["FX", "FY", "FZ", "MX", "MY", "MZ"],
        "AFFE_CHAR_MECA/FORCE_NODALE",
    )?;
    let surface = kw
        .factor("FORCE_CONTOUR")
        .iter()
        .map(|o| ("FORCE_CONTOUR", o))
        .chain(kw.factor("FORCE_FACE").iter().map(|o| ("FORCE_FACE", o)));
    for (key, occ) in surface {
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CHAR_MECA/{key}: {e}")))?;
        crate::shells::refuse_loads_on_shells(ex, key, occ, &model, &mesh, &cells)?;
        let force = [
            occ.f64("FX").unwrap_or(0.0),
            occ.f64("FY").unwrap_or(0.0),
            occ.f64("FZ").unwrap_or(0.0),
        ];
        load.boundary.push(BoundaryLoad::Force { cells, force });
    }
    for occ in kw.factor("PRES_REP") {
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CHAR_MECA/PRES_REP: {e}")))?;
        let pressure = occ.f64("PRES").ok_or_else(|| {
            ex.kw_error(
                "AFFE_CHAR_MECA/PRES_REP",
                occ,
                "PRES",
                "a real pressure is required",
            )
        })?;
        load.boundary
            .push(BoundaryLoad::Pressure { cells, pressure });
    }
    for occ in kw.factor("LIAISON_DDL") {
        // Nodes are listed one per term, in order (GROUP_NO groups of one
        // node each, or NOEUD names).
        let mut nodes = Vec::new();
        for g in occ.simple("GROUP_NO").iter().filter_map(|s| s.as_str()) {
            let members = select::group_no(&mesh, g)
                .map_err(|e| ExecError::new(format!("AFFE_CHAR_MECA/LIAISON_DDL: {e}")))?;
            nodes.extend_from_slice(members);
        }
        for n in occ.simple("NOEUD").iter().filter_map(|s| s.as_str()) {
            nodes.push(
                select::node_named(&mesh, n)
                    .map_err(|e| ExecError::new(format!("AFFE_CHAR_MECA/LIAISON_DDL: {e}")))?,
            );
        }
        let ddl: Vec<&str> = occ
            .simple("DDL")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let coefs: Vec<f64> = occ
            .simple("COEF_MULT")
            .iter()
            .filter_map(|s| s.as_f64())
            .collect();
        if nodes.len() != ddl.len() || ddl.len() != coefs.len() {
            return Err(ExecError::new(format!(
                "AFFE_CHAR_MECA/LIAISON_DDL: {} nodes, {} DDL and {} COEF_MULT: they must match one to one",
                nodes.len(),
                ddl.len(),
                coefs.len()
            )));
        }
        let mut terms = Vec::new();
        for ((node, d), c) in nodes.into_iter().zip(ddl).zip(coefs) {
            let comp = comp_name(d).ok_or_else(|| {
                ExecError::new(format!(
                    "AFFE_CHAR_MECA/LIAISON_DDL: unknown component `{d}`"
                ))
            })?;
            check_dof(
                &model,
                &mesh,
                &carried,
                node,
                comp,
                "AFFE_CHAR_MECA/LIAISON_DDL",
            )?;
            terms.push((node, comp, c));
        }
        let rhs = occ.f64("COEF_IMPO").unwrap_or(0.0);
        load.relations.push(LinearRelation { terms, rhs });
    }
    load.relations.extend(super::liaison_mail::relations(
        kw.factor("LIAISON_MAIL"),
        &model,
        &mesh,
        &carried,
    )?);
    store_result(ex, call, Concept::MechanicalLoad(Rc::new(load)))
}

pub fn defi_contact(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model_ref = ex.required("DEFI_CONTACT", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let formulation = kw.str("FORMULATION").unwrap_or("DISCRETE");
    if formulation != "LIAISON_UNIL" {
        // Check the keywords now (errors at the command that has them);
        // zones are resolved on the mesh at the solve.
        crate::contactbridge::definition(ex, kw)?;
        let def = ContactDef::Zones {
            model: model_ref.id,
            keywords: kw.clone(),
        };
        return store_result(ex, call, Concept::Contact(Rc::new(def)));
    }
    let mesh = ex.mesh_by_id(model.mesh)?;
    let carried = carried_nodes(&model, &mesh);
    let mut zones = Vec::new();
    let mut algo = UnilateralAlgo::Constraint;
    for occ in kw.factor("ZONE") {
        let nodes = select::nodes_without(occ, &mesh)
            .map_err(|e| ExecError::new(format!("DEFI_CONTACT/ZONE: {e}")))?;
        let comps: Vec<CompName> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str())
            .map(|c| {
                comp_name(c).ok_or_else(|| {
                    ex.kw_error(
                        "DEFI_CONTACT/ZONE",
                        occ,
                        "NOM_CMP",
                        format!("unknown component `{c}`"),
                    )
                })
            })
            .collect::<Result<_, _>>()?;
        let mut coef_mult = Vec::new();
        for s in occ.simple("COEF_MULT") {
            let c = s.as_concept().ok_or_else(|| {
                ex.kw_error(
                    "DEFI_CONTACT/ZONE",
                    occ,
                    "COEF_MULT",
                    "a function (DEFI_CONSTANTE, DEFI_FONCTION, FORMULE) is required",
                )
            })?;
            coef_mult.push(ex.function(c)?);
        }
        if coef_mult.len() != comps.len() {
            return Err(ex.kw_error(
                "DEFI_CONTACT/ZONE",
                occ,
                "COEF_MULT",
                format!(
                    "{} coefficients for {} components in NOM_CMP: give one per component",
                    coef_mult.len(),
                    comps.len()
                ),
            ));
        }
        let impo = ex.required("DEFI_CONTACT/ZONE", occ, "COEF_IMPO")?;
        let coef_impo = ex.function(impo)?;
        for &n in &nodes {
            for &c in &comps {
                check_dof(&model, &mesh, &carried, n, c, "DEFI_CONTACT/ZONE")?;
            }
        }
        algo = match occ.str("ALGO_CONT").unwrap_or("CONTRAINTE") {
            "PENALISATION" => UnilateralAlgo::Penalty(occ.f64("COEF_PENA").ok_or_else(|| {
                ex.kw_error(
                    "DEFI_CONTACT/ZONE",
                    occ,
                    "COEF_PENA",
                    "COEF_PENA is required with ALGO_CONT='PENALISATION'",
                )
            })?),
            _ => UnilateralAlgo::Constraint,
        };
        zones.push(UnilateralZone {
            nodes,
            comps,
            coef_mult,
            coef_impo,
        });
    }
    let def = ContactDef::Unilateral {
        model: model_ref.id,
        zones,
        algo,
    };
    store_result(ex, call, Concept::Contact(Rc::new(def)))
}

/// The cells of a selection that carry a continuum element of the model
/// (`FORCE_INTERNE` on `TOUT='OUI'` skips boundary and discrete cells).
pub(super) fn continuum_cells(
    model: &ModelDef,
    mesh: &Mesh,
    cells: Vec<aster_mesh::CellId>,
) -> Vec<aster_mesh::CellId> {
    cells
        .into_iter()
        .filter(|c| {
            model
                .cells
                .get(c)
                .is_some_and(|m| !m.is_discrete() && mesh.cell(*c).ty.dim() as usize == m.dim())
        })
        .collect()
}

/// `FACE_IMPO/DNOR`: at each node of the cells, u·n = DNOR, with n the
/// nodal normal of code_aster's `canort` — each cell's unit normal at the
/// node, from the derivatives of its shape functions there (segments:
/// (t_y, −t_x); faces: t_ξ × t_η, in the cell's node order), averaged over
/// the cells of the occurrence and normalised. A dualised relation per
/// node, as code_aster's `afrela`.
fn face_dnor(
    ex: &Executor,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
) -> Result<Vec<LinearRelation>, ExecError> {
    let what = "AFFE_CHAR_MECA/FACE_IMPO";
    let value = occ
        .f64("DNOR")
        .ok_or_else(|| ex.kw_error(what, occ, "DNOR", "a real value is required"))?;
    for other in ["DX", "DY", "DZ"] {
        if occ.contains(other) {
            return Err(ex.kw_error(
                what,
                occ,
                other,
                "DNOR and DX/DY/DZ cannot be given together (code_aster CHARGES2_63)",
            ));
        }
    }
    let cells = select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    let nodes =
        select::nodes_without(occ, mesh).map_err(|e| ExecError::new(format!("{what}: {e}")))?;
    let dim = model.dim();
    let mut sum: std::collections::BTreeMap<NodeId, ([f64; 3], usize)> = Default::default();
    for &c in &cells {
        let cell = mesh.cell(c);
        let kind = aster_contact::SurfaceKind::of(cell.ty)
            .filter(|k| k.dim() + 1 == dim)
            .ok_or_else(|| {
                ex.kw_error(
                    what,
                    occ,
                    "GROUP_MA",
                    format!(
                        "cell {} is a {}; DNOR needs boundary cells (segments in 2D, faces in 3D)",
                        select::cell_name(mesh, c),
                        cell.ty.name()
                    ),
                )
            })?;
        let xyz: Vec<[f64; 3]> = cell.nodes.iter().map(|n| mesh.coord(*n)).collect();
        for (&node, xi) in cell.nodes.iter().zip(kind.node_coords()) {
            let p = aster_contact::interpolate(kind, &xyz, xi);
            let [t, s] = p.tangents;
            let n = if dim == 2 {
                [t[1], -t[0], 0.0]
            } else {
                [
                    t[1] * s[2] - t[2] * s[1],
                    t[2] * s[0] - t[0] * s[2],
                    t[0] * s[1] - t[1] * s[0],
                ]
            };
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if !(l > 0.0 && l.is_finite()) {
                return Err(ExecError::new(format!(
                    "{what}: cell {} is degenerate at node {} (no normal)",
                    select::cell_name(mesh, c),
                    mesh.node_name(node)
                )));
            }
            let e = sum.entry(node).or_insert(([0.0; 3], 0));
            for (acc, nd) in e.0.iter_mut().zip(n.iter()) {
                *acc += nd / l;
            }
            e.1 += 1;
        }
    }
    let mut out = Vec::new();
    for n in nodes {
        let Some((v, _)) = sum.get(&n) else { continue };
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l < 1e-2 {
            return Err(ExecError::new(format!(
                "{what}: the normals of the cells meeting at node {} cancel out (code_aster CHARGES2_30)",
                mesh.node_name(n)
            )));
        }
        let mut terms = Vec::new();
        for (d, &comp) in COMPS[..dim].iter().enumerate() {
            check_dof(model, mesh, carried, n, comp, what)?;
            if v[d] != 0.0 {
                terms.push((n, comp, v[d] / l));
            }
        }
        out.push(LinearRelation { terms, rhs: value });
    }
    Ok(out)
}

/// `LIAISON_GROUP`: each node of side 1 is paired with the nearest node of
/// side 2 (code_aster's pairing without a transformation), and each pair
/// gets Σ COEF_MULT_1·DDL_1(n₁) + Σ COEF_MULT_2·DDL_2(n₂) = COEF_IMPO. A
/// node paired with itself gets no relation; two nodes of side 1 paired
/// with one node of side 2 is an error. `rhs` is COEF_IMPO (1 for
/// AFFE_CHAR_MECA_F, whose function then multiplies the relation's
/// right-hand side).
pub(super) fn liaison_group(
    ex: &Executor,
    what: &str,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
    rhs: f64,
) -> Result<Vec<LinearRelation>, ExecError> {
    let err = |e: String| ExecError::new(format!("{what}: {e}"));
    let excluded: std::collections::BTreeSet<NodeId> = select::nodes(occ, mesh, "SANS_")
        .map_err(err)?
        .into_iter()
        .collect();
    let side = |k: &str| -> Result<Vec<NodeId>, ExecError> {
        let mut out = Vec::new();
        for g in occ
            .simple(&format!("GROUP_NO_{k}"))
            .iter()
            .filter_map(|s| s.as_str())
        {
            out.extend_from_slice(select::group_no(mesh, g).map_err(err)?);
        }
        for g in occ
            .simple(&format!("GROUP_MA_{k}"))
            .iter()
            .filter_map(|s| s.as_str())
        {
            let cells = select::group_ma(mesh, g).map_err(err)?;
            out.extend(mesh.nodes_of_cells(cells));
        }
        let mut seen = std::collections::BTreeSet::new();
        out.retain(|n| !excluded.contains(n) && seen.insert(*n));
        Ok(out)
    };
    let (one, two) = (side("1")?, side("2")?);
    let terms = |k: &str| -> Result<Vec<(CompName, f64)>, ExecError> {
        let ddl: Vec<&str> = occ
            .simple(&format!("DDL_{k}"))
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let coef: Vec<f64> = occ
            .simple(&format!("COEF_MULT_{k}"))
            .iter()
            .filter_map(|s| s.as_f64())
            .collect();
        if ddl.len() != coef.len() {
            return Err(ex.kw_error(
                what,
                occ,
                &format!("COEF_MULT_{k}"),
                format!(
                    "{} coefficients for {} DDL_{k}: give one per component",
                    coef.len(),
                    ddl.len()
                ),
            ));
        }
        ddl.into_iter()
            .zip(coef)
            .map(|(d, c)| {
                comp_name(d)
                    .map(|d| (d, c))
                    .ok_or_else(|| err(format!("unknown component `{d}`")))
            })
            .collect()
    };
    let (t1, t2) = (terms("1")?, terms("2")?);
    let dist2 = |a: NodeId, b: NodeId| {
        let (p, q) = (mesh.coord(a), mesh.coord(b));
        (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
    };
    let mut used: std::collections::BTreeMap<NodeId, NodeId> = std::collections::BTreeMap::new();
    let mut out = Vec::new();
    for &n1 in &one {
        let Some(&n2) = two
            .iter()
            .min_by(|a, b| dist2(n1, **a).total_cmp(&dist2(n1, **b)))
        else {
            return Err(err("GROUP_NO_2/GROUP_MA_2 holds no node".into()));
        };
        if let Some(prev) = used.insert(n2, n1) {
            return Err(err(format!(
                "nodes {} and {} are both paired with node {} (the pairing must be one to one)",
                mesh.node_name(prev),
                mesh.node_name(n1),
                mesh.node_name(n2)
            )));
        }
        if n1 == n2 {
            continue;
        }
        let mut terms = Vec::new();
        for &(c, a) in &t1 {
            check_dof(model, mesh, carried, n1, c, what)?;
            terms.push((n1, c, a));
        }
        for &(c, a) in &t2 {
            check_dof(model, mesh, carried, n2, c, what)?;
            terms.push((n2, c, a));
        }
        out.push(LinearRelation { terms, rhs });
    }
    Ok(out)
}

/// `LIAISON_ELEM(OPTION='3D_POU')`: the six relations tying the solid's
/// face `GROUP_MA_1` to the node `GROUP_NO_2` (or the POI1 cell
/// `GROUP_MA_2`), which must carry rotations (a `DIS_TR` or beam node):
/// aster-fem's `coupling::solid_to_beam`, code_aster's `rapo3d`. The
/// face's planarity check (`ANGL_MAX`) is not made.
fn liaison_elem_3d_pou(
    ex: &Executor,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
) -> Result<Vec<LinearRelation>, ExecError> {
    let what = "AFFE_CHAR_MECA/LIAISON_ELEM";
    let err = |key: &str, m: String| ex.kw_error(what, occ, key, m);
    let mut faces = Vec::new();
    for g in occ.simple("GROUP_MA_1").iter().filter_map(|s| s.as_str()) {
        let cells = select::group_ma(mesh, g).map_err(|e| err("GROUP_MA_1", e.to_string()))?;
        faces.extend_from_slice(cells);
    }
    if faces.is_empty() {
        return Err(err(
            "GROUP_MA_1",
            "3D_POU needs the solid's face (GROUP_MA_1)".into(),
        ));
    }
    let mut nodes: Vec<NodeId> = Vec::new();
    if let Some(g) = occ.str("GROUP_NO_2") {
        nodes.extend_from_slice(
            select::group_no(mesh, g).map_err(|e| err("GROUP_NO_2", e.to_string()))?,
        );
    }
    if let Some(g) = occ.str("GROUP_MA_2") {
        for &c in select::group_ma(mesh, g).map_err(|e| err("GROUP_MA_2", e.to_string()))? {
            nodes.extend_from_slice(&mesh.cell(c).nodes);
        }
    }
    nodes.sort();
    nodes.dedup();
    let key = if occ.contains("GROUP_NO_2") {
        "GROUP_NO_2"
    } else {
        "GROUP_MA_2"
    };
    let [node] = nodes[..] else {
        return Err(err(
            key,
            format!(
                "3D_POU ties the face to one beam node; {} nodes given (code_aster's MODELISA6_40)",
                nodes.len()
            ),
        ));
    };
    let rows = aster_fem::coupling::solid_to_beam(mesh, &faces, node)
        .map_err(|e| err("GROUP_MA_1", e.to_string()))?;
    const ORDER: [&str; 6] = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];
    let mut out = Vec::with_capacity(rows.len());
    for row in rows {
        let mut terms = Vec::with_capacity(row.len());
        for (n, k, c) in row {
            let comp = comp_name(ORDER[k])
                .ok_or_else(|| ExecError::new(format!("{what}: unknown component {}", ORDER[k])))?;
            check_dof(model, mesh, carried, n, comp, what)?;
            terms.push((n, comp, c));
        }
        out.push(LinearRelation { terms, rhs: 0.0 });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn proportional_relations_of_a_keyword_are_kept_once_the_last() {
        let r = |terms: Vec<(u32, CompName, f64)>, rhs: f64| LinearRelation {
            terms: terms
                .into_iter()
                .map(|(n, c, a)| (NodeId(n), c, a))
                .collect(),
            rhs,
        };
        let kept = drop_redundant(vec![
            r(vec![(1, "DX", 1.0), (2, "DX", -1.0)], 0.0),
            r(vec![(3, "DY", 1.0), (4, "DY", -1.0)], 0.0),
            // The first, written the other way round and doubled.
            r(vec![(2, "DX", 2.0), (1, "DX", -2.0)], 5.0),
            // Same DOFs, not proportional: kept.
            r(vec![(3, "DY", 1.0), (4, "DY", 1.0)], 0.0),
        ]);
        assert_eq!(
            kept,
            vec![
                r(vec![(3, "DY", 1.0), (4, "DY", -1.0)], 0.0),
                r(vec![(2, "DX", 2.0), (1, "DX", -2.0)], 5.0),
                r(vec![(3, "DY", 1.0), (4, "DY", 1.0)], 0.0),
            ]
        );
    }

    #[test]
    fn a_dof_given_twice_in_a_load_keeps_its_last_value() {
        let i = |n: u32, comp: CompName, value: f64| Imposed {
            node: NodeId(n),
            comp,
            value,
        };
        // SSNP167E: a node on the loaded arc (DX = -4.8e-19 by a function)
        // and on the symmetry line (DX = 0).
        let kept = last_per_dof(
            vec![
                i(4, "DX", -4.8e-19),
                i(4, "DY", 1.0),
                i(5, "DX", 2.0),
                i(4, "DX", 0.0),
            ],
            |i| (i.node, i.comp),
        );
        assert_eq!(
            kept,
            vec![i(4, "DY", 1.0), i(5, "DX", 2.0), i(4, "DX", 0.0)]
        );
    }
}
