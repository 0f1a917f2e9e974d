//! POST_ERREUR: the L2 error of a computed field against an analytic one,
//! as code_aster's macro-command computes it
//! (`code_aster.MacroCommands.post_erreur_ops`).
//!
//! `OPTION='LAGR_RELA'` (the contact pressure): on the skin cells of each
//! `GROUP_MA`, the nodal `LAGS_C` of `CHAM_GD` (a node without it counts
//! as zero: the macro's `PROL_ZERO='OUI'`) is interpolated at the points
//! of code_aster's skin Gauss family and compared with the group's
//! function of `LAGS_C` (of `X`, `Y`(, `Z`), evaluated on the undeformed
//! mesh; none: zero). Per group, `REFERENCE` = ‖p_exact‖ and `DIFFERENCE`
//! = ‖p_h − p_exact‖ (`POST_ELEM(NORME=_F(TYPE_NORM='L2'))` of the macro);
//! the `TOTAL` row has the square roots of the sums of squares, and
//! `ERREUR RELATIVE` = DIFFERENCE/REFERENCE when REFERENCE > 1e-16.
//!
//! Refused: the options `DEPL_RELA` and `ENER_RELA`, axisymmetric models
//! (code_aster's weights there carry the radius), and cells of the groups
//! that are not skin cells of the model.

use crate::concept::{Concept, Modelisation};
use crate::executor::{store_result, Executor};
use crate::field::Field;
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use std::rc::Rc;

/// What POST_ERREUR computes (`crate::support`).
pub(crate) const POST_ERREUR: Support = Support {
    values: &[Values::new("OPTION", &["LAGR_RELA"])],
    ..Support::keywords(&["OPTION", "MODELE", "GROUP_MA", "CHAM_GD", "LAGS_C"])
};

pub fn post_erreur(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ERREUR";
    let kw = &call.keywords;
    let model = ex.model(ex.required(cmd, kw, "MODELE")?)?;
    let mesh = ex.model_mesh(&model)?;
    let field = ex.field(ex.required(cmd, kw, "CHAM_GD")?)?;
    let Field::Nodal(field) = &*field else {
        return Err(ex.kw_error(cmd, kw, "CHAM_GD", "a nodal field (cham_no) is expected"));
    };
    let lags = field.component_index("LAGS_C");
    let groups: Vec<String> = kw
        .simple("GROUP_MA")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect();
    let functions = kw.simple("LAGS_C");
    if !functions.is_empty() && functions.len() != groups.len() {
        // code_aster PREPOST_12: one function per group.
        return Err(ex.kw_error(
            cmd,
            kw,
            "LAGS_C",
            format!(
                "give one function per group of GROUP_MA ({} groups, {} functions)",
                groups.len(),
                functions.len()
            ),
        ));
    }
    let mut rows: Vec<(String, f64, f64)> = Vec::new();
    let (mut diff_tot, mut ref_tot) = (0.0, 0.0);
    for (g, name) in groups.iter().enumerate() {
        let exact = match functions.get(g) {
            Some(s) => {
                let c = s.as_concept().ok_or_else(|| {
                    ex.kw_error(cmd, kw, "LAGS_C", "a function (FORMULE) is expected")
                })?;
                Some(ex.function(c)?)
            }
            None => None,
        };
        let cells = crate::select::group_ma(&mesh, name)
            .map_err(|e| ex.kw_error(cmd, kw, "GROUP_MA", e))?;
        let (mut diff, mut reference) = (0.0, 0.0);
        for &cell in cells {
            let Some(m) = model.cells.get(&cell) else {
                // Not in the model: the macro's fields have no value there.
                continue;
            };
            if *m == Modelisation::Axisymmetric {
                return Err(ex.unsupported(
                    "POST_ERREUR on an axisymmetric model (code_aster's integration weights there carry the radius)",
                    kw.keyword("MODELE").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            let c = mesh.cell(cell);
            if c.ty.dim() as usize + 1 != model.dim() {
                return Err(ex.unsupported(
                    &format!(
                        "POST_ERREUR/OPTION='LAGR_RELA' on cell {} ({}), not a skin cell of the model (an edge of a plane model, a face of a 3D one)",
                        crate::select::cell_name(&mesh, cell),
                        c.ty.name()
                    ),
                    kw.keyword("GROUP_MA").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            let v: Vec<f64> = c
                .nodes
                .iter()
                .map(|n| lags.and_then(|i| field.get_at(*n, i)).unwrap_or(0.0))
                .collect();
            let dim = model.dim();
            let out = aster_fem::skin_norm::skin_l2_squared(&mesh, cell, &v, |x| match &exact {
                None => Ok(0.0),
                Some(f) => {
                    let args = [("X", x[0]), ("Y", x[1]), ("Z", x[2])];
                    f.eval_named(&args[..dim.max(2)])
                }
            })
            .ok_or_else(|| {
                ex.unsupported(
                    &format!(
                        "POST_ERREUR on cell {} ({}): no skin Gauss family",
                        crate::select::cell_name(&mesh, cell),
                        c.ty.name()
                    ),
                    kw.keyword("GROUP_MA").map(|k| k.span).unwrap_or(call.span),
                )
            })?
            .map_err(|e| ex.kw_error(cmd, kw, "LAGS_C", e.to_string()))?;
            diff += out.0;
            reference += out.1;
        }
        diff_tot += diff;
        ref_tot += reference;
        rows.push((name.clone(), diff.sqrt(), reference.sqrt()));
    }
    let (diff_tot, ref_tot) = (diff_tot.sqrt(), ref_tot.sqrt());
    rows.push(("TOTAL".into(), diff_tot, ref_tot));
    let mut table = Table::new(vec![
        Column {
            name: "GROUP_MA".into(),
            ty: ColumnType::Text(8),
        },
        Column {
            name: "DIFFERENCE".into(),
            ty: ColumnType::Real,
        },
        Column {
            name: "REFERENCE".into(),
            ty: ColumnType::Real,
        },
    ]);
    table.title = vec!["ERREUR EN NORME L2 DE LA PRESSION".into()];
    let last = rows.len() - 1;
    for (i, (g, d, r)) in rows.into_iter().enumerate() {
        let mut row = vec![
            ("GROUP_MA", Value::Text(g)),
            ("DIFFERENCE", Value::Real(d)),
            ("REFERENCE", Value::Real(r)),
        ];
        if i == last && ref_tot > 1e-16 {
            row.push(("ERREUR RELATIVE", Value::Real(diff_tot / ref_tot)));
        }
        table.push_row(row);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}
