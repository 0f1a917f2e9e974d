//! POST_ELEM/MASS_INER (code_aster's `pemain` → `pemica`): the mass, the
//! centre of gravity, the inertia tensor about it, its principal values
//! and the nautical angles of its axes, of the whole model (`TOUT`: `LIEU`
//! the mesh's name) or of groups (`GROUP_MA`, one row each, then their
//! union `UNION_GROUP_MA` when an occurrence names several; a group the
//! mesh lacks or an empty one gives no row, as code_aster's warnings
//! UTILITAI3_46/47). The numbers come from aster-fem's
//! [`aster_fem::inertia`]: continuum cells and POU_D_E beams with the
//! densities of `CHAM_MATER` (or of the computation of `RESULTAT`),
//! the discrete masses of POI1 nodes of `CARA_ELEM` (global frame).
//!
//! Columns, as `pemain`'s: `LIEU` (K24), `ENTITE` (K8), `MASSE`, `CDG_X`,
//! `CDG_Y`, `CDG_Z`, `IX_G`, `IY_G`, `IZ_G`, `IXY_G`, `IXZ_G`, `IYZ_G`,
//! `IX_PRIN_G`, `IY_PRIN_G`, `IZ_PRIN_G`, `ALPHA`, `BETA`, `GAMMA`, and
//! when an occurrence gives `ORIG_INER` (then on every row: 0 where it has
//! none) `X_P`, `Y_P`, `Z_P`, `IX_P`, `IY_P`, `IZ_P`, `IXY_P`, `IXZ_P`,
//! `IYZ_P`. Every dimension has every column (a 2D model's `CDG_Z`, `IXZ_G`,
//! `IYZ_G` are 0). A `RESULTAT` only names the model, material and
//! characteristics (code_aster's `medomp`): no `NUME_ORDRE` column.
//! `GEOMETRIE='DEFORMEE'` and other discrete masses are refused; DKT
//! shells by `dxiner` (aster-fem's `inertia::shell`), COQUE_3D by `te0417`
//! (`coque3d::mass_inertia`).

use super::{col, model_from_keywords, result_model, ModelRef};
use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::table::{ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::inertia::{self, CellInertia};
use aster_fem::MassData;
use aster_mesh::CellId;
use std::collections::{BTreeMap, BTreeSet};
use std::rc::Rc;

const COLUMNS: [&str; 18] = [
    "LIEU",
    "ENTITE",
    "MASSE",
    "CDG_X",
    "CDG_Y",
    "CDG_Z",
    "IX_G",
    "IY_G",
    "IZ_G",
    "IXY_G",
    "IXZ_G",
    "IYZ_G",
    "IX_PRIN_G",
    "IY_PRIN_G",
    "IZ_PRIN_G",
    "ALPHA",
    "BETA",
    "GAMMA",
];

const ORIGIN_COLUMNS: [&str; 9] = [
    "X_P", "Y_P", "Z_P", "IX_P", "IY_P", "IZ_P", "IXY_P", "IXZ_P", "IYZ_P",
];

pub(super) fn mass_iner(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/MASS_INER";
    let kw = &call.keywords;
    let span = |k: &str| kw.keyword(k).map(|k| k.span).unwrap_or(call.span);
    let (model, mesh_name, mass) = if let Some(r) = kw.concept("RESULTAT") {
        let result = ex.result(r)?;
        let (model, name) = result_model(ex, kw, r, &result)?;
        let mass = match &*model {
            ModelRef::Run(run) if !kw.contains("CHAM_MATER") => {
                run.mass.clone().ok_or_else(|| {
                    ExecError::new(format!(
                        "{cmd}: the densities of `{}`'s computation are not known here: give MODELE and CHAM_MATER",
                        r.name
                    ))
                })?
            }
            _ => mass_data(ex, kw, &model)?,
        };
        (model, name, mass)
    } else {
        if !kw.contains("MODELE") {
            return Err(ExecError::new(format!(
                "{cmd}: give MODELE (with CHAM_MATER, CARA_ELEM) or RESULTAT"
            )));
        }
        let (m, name) = if kw.contains("CHAM_MATER") {
            model_from_keywords(ex, kw)?
        } else {
            // A model of discrete cells needs no material.
            let def = ex.model(ex.required("POST_ELEM", kw, "MODELE")?)?;
            let mesh = ex.model_mesh(&def)?;
            let cara = match kw.concept("CARA_ELEM") {
                Some(c) => Some(ex.cara_elem(c)?),
                None => None,
            };
            let empty = crate::concept::MaterialField {
                mesh: def.mesh,
                cells: Default::default(),
                temperature: None,
            };
            let m = crate::fembridge::build_model(&mesh, &def, &empty, cara.as_deref())?;
            (m, ex.internal_name(def.mesh))
        };
        let model = ModelRef::Own(Box::new(m));
        let mass = mass_data(ex, kw, &model)?;
        (Rc::new(model), name, mass)
    };
    // What aster-fem does not compute is refused before anything else.
    if let Some(d) = mass
        .discrete
        .iter()
        .find(|d| inertia::discrete(&model, d).is_none())
    {
        return Err(ex.unsupported(
            &format!(
                "{cmd} of a discrete mass on a segment (M_T_D_L, M_TR_D_L, M_T_L…), in a local frame (REPERE='LOCAL') or on a 2D_DIS_TR node (cell {}: not reproduced from te0045)",
                model.cell_name(d.cell())
            ),
            span("CARA_ELEM"),
        ));
    }
    let cells: BTreeMap<CellId, CellInertia> =
        inertia::cell_inertias(&model, &mass).map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
    let mesh = model.mesh_arc().clone();
    let occurrences = kw.factor("MASS_INER");
    let with_origin = occurrences.iter().any(|o| o.contains("ORIG_INER"));
    let mut columns: Vec<_> = COLUMNS
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let ty = match k {
                0 => ColumnType::Text(24),
                1 => ColumnType::Text(8),
                _ => ColumnType::Real,
            };
            col(c, ty)
        })
        .collect();
    if with_origin {
        columns.extend(ORIGIN_COLUMNS.iter().map(|c| col(c, ColumnType::Real)));
    }
    let mut table = Table::new(columns);
    for occ in occurrences {
        let origin: Option<[f64; 3]> = if occ.contains("ORIG_INER") {
            let v: Vec<f64> = occ
                .simple("ORIG_INER")
                .iter()
                .filter_map(|s| s.as_f64())
                .collect();
            let [x, y, z] = v[..] else {
                return Err(ex.kw_error(cmd, occ, "ORIG_INER", "three coordinates are needed"));
            };
            Some([x, y, z])
        } else {
            None
        };
        let mut places: Vec<(String, &str, Vec<&CellInertia>)> = Vec::new();
        if occ.contains("TOUT") {
            places.push((mesh_name.clone(), "TOUT", cells.values().collect()));
        }
        let groups: Vec<&str> = occ
            .simple("GROUP_MA")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let mut union: BTreeSet<CellId> = BTreeSet::new();
        for g in &groups {
            // code_aster's UTILITAI3_46 (no such group), UTILITAI3_47
            // (an empty one): an alarm and no row.
            let Ok(group) = crate::select::group_ma(&mesh, g) else {
                continue;
            };
            if group.is_empty() {
                continue;
            }
            union.extend(group.iter().copied());
            let members = group.iter().filter_map(|c| cells.get(c)).collect();
            places.push((g.to_string(), "GROUP_MA", members));
        }
        if groups.len() > 1 && !union.is_empty() {
            let members = union.iter().filter_map(|c| cells.get(c)).collect();
            places.push(("UNION_GROUP_MA".into(), "GROUP_MA", members));
        }
        for (lieu, entite, members) in places {
            let s = inertia::sum(members.iter().copied(), origin);
            let mut values = vec![s.mass];
            values.extend(s.centre);
            values.extend(s.inertia);
            values.extend(s.principal);
            values.extend(s.angles);
            if with_origin {
                let (p, i) = s.about.unwrap_or_default();
                values.extend(p);
                values.extend(i);
            }
            let mut row = vec![
                ("LIEU", Value::Text(lieu)),
                ("ENTITE", Value::Text(entite.into())),
            ];
            let names = COLUMNS[2..].iter().chain(ORIGIN_COLUMNS.iter());
            row.extend(names.zip(values).map(|(c, v)| (*c, Value::Real(v))));
            table.push_row(row);
        }
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// The densities of `CHAM_MATER` on the model's cells and the discrete
/// masses of `CARA_ELEM`.
fn mass_data(
    ex: &Executor,
    kw: &aster_eval::Keywords,
    model: &aster_fem::Model,
) -> Result<MassData, ExecError> {
    let mut data = MassData::default();
    if let Some(m) = kw.concept("CHAM_MATER") {
        let materials = ex.material_field(m)?;
        for el in model.elements() {
            let rho = match materials.cells.get(&el.cell) {
                Some(m) => m.resolved_density().map_err(ExecError::new)?,
                None => None,
            };
            if let Some(rho) = rho {
                data.density.insert(el.cell, rho);
            }
        }
    }
    if let Some(c) = kw.concept("CARA_ELEM") {
        let cara = ex.cara_elem(c)?;
        let def = ex.model(ex.required("POST_ELEM", kw, "MODELE")?)?;
        data.discrete = crate::dyna::discrete_masses(model.mesh(), &def, &cara)?;
    }
    Ok(data)
}
