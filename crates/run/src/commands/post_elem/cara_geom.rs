//! POST_ELEM/CARA_GEOM (code_aster's `pecage`): the geometric properties
//! of a plane section meshed in 2D — area, centroid, inertias about it, the
//! principal ones and their angle `ALPHA`, inertias about `ORIG_INER`, the
//! extents in the principal frame, the third moments `IYR2`/`IZR2` —, of the
//! whole model (`TOUT`: `LIEU` the mesh's name, `ENTITE` `TOUT`) and of each
//! group (`GROUP_MA`), with the symmetries `SYME_X`/`SYME_Y`. The numbers
//! come from aster-fem's [`aster_fem::section::cara_geom`], shared with
//! `MACR_CARA_POUTRE` (`crate::commands::macr_cara_poutre`).
//!
//! code_aster names the mesh by its internal name (`00000001` for the first
//! object of a study): so does `LIEU` here (`Executor::internal_name`).

use crate::commands::macr_cara_poutre::cara_geom_rows;
use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::section::Symmetry;
use std::rc::Rc;

pub(super) fn cara_geom(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/CARA_GEOM";
    let kw = &call.keywords;
    let model = ex.model(ex.required("POST_ELEM", kw, "MODELE")?)?;
    let mesh = ex.model_mesh(&model)?;
    let mesh_name = ex.internal_name(model.mesh);
    let mut table: Option<Table> = None;
    for occ in kw.factor("CARA_GEOM") {
        let sym = Symmetry {
            x: occ.str("SYME_X") == Some("OUI"),
            y: occ.str("SYME_Y") == Some("OUI"),
        };
        let v: Vec<f64> = occ
            .simple("ORIG_INER")
            .iter()
            .filter_map(|s| s.as_f64())
            .collect();
        let origin = match v[..] {
            [] => None,
            [x, y] => Some([x, y]),
            _ => return Err(ex.kw_error(cmd, occ, "ORIG_INER", "two coordinates are needed")),
        };
        let groups: Vec<&str> = occ
            .simple("GROUP_MA")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let all = occ.contains("TOUT").then_some(mesh_name.as_str());
        let rows = cara_geom_rows(ex, cmd, occ, &mesh, all, &groups, (sym, origin))?;
        for (lieu, entite, g) in rows {
            let t = table.get_or_insert_with(|| {
                let mut cols = vec![
                    Column {
                        name: "LIEU".into(),
                        ty: ColumnType::Text(24),
                    },
                    Column {
                        name: "ENTITE".into(),
                        ty: ColumnType::Text(8),
                    },
                ];
                cols.extend(g.values.iter().map(|(n, _)| Column {
                    name: n.to_string(),
                    ty: ColumnType::Real,
                }));
                Table::new(cols)
            });
            let mut row = vec![
                ("LIEU", Value::Text(lieu)),
                ("ENTITE", Value::Text(entite.into())),
            ];
            row.extend(g.values.iter().map(|(n, v)| (*n, Value::Real(*v))));
            t.push_row(row);
        }
    }
    let table = table.ok_or_else(|| ExecError::new(format!("{cmd}: no place to compute")))?;
    store_result(ex, call, Concept::Table(Rc::new(table)))
}
