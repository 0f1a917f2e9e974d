//! POST_ERREUR: the L2 error of a computed field against an analytic one,
//! as code_aster 17's macro-command computes it
//! (`code_aster/MacroCommands/post_erreur_ops.py`).
//!
//! Reproduced: `OPTION='LAGR_RELA'`, the contact pressure `LAGS_C` of a
//! displacement field (`CHAM_GD`, a `NOEU_DEPL_R` field) against one
//! function of the coordinates per group (`LAGS_C`, the zero function when
//! absent), on line cells (SEG2, SEG3) of plane models (`D_PLAN`,
//! `C_PLAN`). code_aster interpolates the nodal `LAGS_C` to the Gauss points
//! of the model's skin elements (`CREA_CHAMP(OPERATION='DISC')`; family
//! `RIGI`: FPG2 on SEG2, FPG3 on SEG3), evaluates the function there on the
//! initial coordinates (`CREA_CHAMP(OPERATION='EVAL')`) and integrates the
//! squares with `POST_ELEM(NORME=_F(TYPE_NORM='L2'))` on the initial
//! geometry. The table has one row per group and a `TOTAL` row:
//! `GROUP_MA`, `DIFFERENCE` (‖λ_h − λ‖), `REFERENCE` (‖λ‖), and on `TOTAL`
//! `ERREUR RELATIVE` (their ratio, when the reference exceeds 1e-16; the
//! totals are the square roots of the sums of the groups' squares).
//!
//! Refused with their keyword: `OPTION='DEPL_RELA'`/`'ENER_RELA'`, and
//! axisymmetric or 3D models (the weighting of code_aster's skin elements
//! there is not reproduced).

use std::rc::Rc;

use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_mesh::{CellType, Mesh};

use crate::concept::{Concept, Modelisation};
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::function::Function;
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};

/// What POST_ERREUR computes (`crate::support`).
pub(crate) const POST_ERREUR: Support = Support {
    keywords: &["OPTION", "CHAM_GD", "MODELE", "GROUP_MA", "LAGS_C"],
    values: &[Values::new("OPTION", &["LAGR_RELA"])
        .why("(the L2 error of the displacement and the energy error)")],
    hints: &[],
    reuse: false,
    rules: None,
};

/// Gauss points and weights on [−1, 1] of code_aster's skin family
/// `RIGI` for a line cell.
fn gauss(ty: CellType) -> Option<&'static [(f64, f64)]> {
    const FPG2: [(f64, f64); 2] = [
        (-0.577_350_269_189_625_8, 1.0),
        (0.577_350_269_189_625_8, 1.0),
    ];
    const FPG3: [(f64, f64); 3] = [
        (-0.774_596_669_241_483_4, 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        (0.774_596_669_241_483_4, 5.0 / 9.0),
    ];
    match ty {
        CellType::SEG2 => Some(&FPG2),
        CellType::SEG3 => Some(&FPG3),
        _ => None,
    }
}

/// Shape functions and their derivatives at ξ (code_aster node order: the
/// two ends, then the middle).
fn shape(ty: CellType, xi: f64) -> (Vec<f64>, Vec<f64>) {
    match ty {
        CellType::SEG3 => (
            vec![xi * (xi - 1.0) / 2.0, xi * (xi + 1.0) / 2.0, 1.0 - xi * xi],
            vec![xi - 0.5, xi + 0.5, -2.0 * xi],
        ),
        _ => (vec![(1.0 - xi) / 2.0, (1.0 + xi) / 2.0], vec![-0.5, 0.5]),
    }
}

/// ∫ (λ_h − λ)² and ∫ λ² over the cells of a group.
fn group_squares(
    mesh: &Mesh,
    cells: &[aster_mesh::CellId],
    field: &NodalField,
    exact: Option<&Function>,
    dim: usize,
) -> Result<(f64, f64), String> {
    let (mut diff, mut refe) = (0.0, 0.0);
    for &c in cells {
        let cell = mesh.cell(c);
        let Some(points) = gauss(cell.ty) else {
            return Err(format!(
                "a {:?} cell ({}): LAGR_RELA is reproduced on line cells (SEG2, SEG3) of plane models",
                cell.ty, mesh.cell_names[c.0 as usize]
            ));
        };
        for &(xi, w) in points {
            let (n, dn) = shape(cell.ty, xi);
            let mut x = [0.0; 3];
            let mut t = [0.0; 3];
            let mut lam = 0.0;
            for (k, &node) in cell.nodes.iter().enumerate() {
                let p = mesh.coord(node);
                for d in 0..3 {
                    x[d] += n[k] * p[d];
                    t[d] += dn[k] * p[d];
                }
                // PROL_ZERO: a node without LAGS_C counts as 0.
                lam += n[k] * field.get(node, "LAGS_C").unwrap_or(0.0);
            }
            let jac = t.iter().map(|v| v * v).sum::<f64>().sqrt();
            let mut args = vec![("X", x[0]), ("Y", x[1])];
            if dim == 3 {
                args.push(("Z", x[2]));
            }
            let value = match exact {
                Some(f) => f.eval_named(&args).map_err(|e| e.to_string())?,
                None => 0.0,
            };
            diff += w * jac * (lam - value).powi(2);
            refe += w * jac * value * value;
        }
    }
    Ok((diff, refe))
}

pub fn post_erreur(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "POST_ERREUR";
    let model_ref = ex.required(cmd, kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    if model
        .cells
        .values()
        .any(|m| !matches!(m, Modelisation::PlaneStrain | Modelisation::PlaneStress))
    {
        return Err(ex.kw_error(
            cmd,
            kw,
            "MODELE",
            "not supported yet: POST_ERREUR on a model other than D_PLAN or C_PLAN (the weighting of code_aster's axisymmetric and 3D skin elements is not reproduced)",
        ));
    }
    let mesh = ex.model_mesh(&model)?;
    let field_ref = ex.required(cmd, kw, "CHAM_GD")?;
    let field = ex.field(field_ref)?;
    let Field::Nodal(depl) = &*field else {
        return Err(ex.kw_error(
            cmd,
            kw,
            "CHAM_GD",
            "LAGR_RELA needs a displacement field on nodes (NOEU_DEPL_R) carrying LAGS_C",
        ));
    };
    let groups: Vec<String> = kw
        .simple("GROUP_MA")
        .iter()
        .filter_map(|v| v.as_str().map(str::to_string))
        .collect();
    let functions: Vec<Option<Rc<Function>>> = match kw.simple("LAGS_C") {
        [] => vec![None; groups.len()],
        values => values
            .iter()
            .map(|v| match v.as_concept() {
                Some(c) => ex.function(c).map(Some),
                None => Err(ex.kw_error(cmd, kw, "LAGS_C", "expected a function")),
            })
            .collect::<Result<_, _>>()?,
    };
    if functions.len() != groups.len() {
        // code_aster's PREPOST_12.
        return Err(ex.kw_error(
            cmd,
            kw,
            "LAGS_C",
            format!(
                "give one function per group: {} groups, {} functions",
                groups.len(),
                functions.len()
            ),
        ));
    }
    let dim = model.cells.values().next().map_or(2, |m| m.dim());
    let mut diffs = Vec::new();
    let mut refs = Vec::new();
    for (g, f) in groups.iter().zip(&functions) {
        let cells =
            crate::select::group_ma(&mesh, g).map_err(|e| ex.kw_error(cmd, kw, "GROUP_MA", e))?;
        let (d, r) = group_squares(&mesh, cells, depl, f.as_deref(), dim)
            .map_err(|e| ex.kw_error(cmd, kw, "GROUP_MA", format!("not supported yet: {e}")))?;
        diffs.push(d);
        refs.push(r);
    }
    let diff_tot = diffs.iter().sum::<f64>().sqrt();
    let ref_tot = refs.iter().sum::<f64>().sqrt();
    let long = groups.iter().any(|g| g.len() > 8);
    let mut columns = vec![
        Column {
            name: "GROUP_MA".into(),
            ty: ColumnType::Text(if long { 24 } else { 8 }),
        },
        Column {
            name: "DIFFERENCE".into(),
            ty: ColumnType::Real,
        },
        Column {
            name: "REFERENCE".into(),
            ty: ColumnType::Real,
        },
    ];
    let relative = (ref_tot > 1e-16).then(|| diff_tot / ref_tot);
    if relative.is_some() {
        columns.push(Column {
            name: "ERREUR RELATIVE".into(),
            ty: ColumnType::Real,
        });
    }
    let mut table = Table::new(columns);
    table.title = vec!["ERREUR EN NORME L2 DE LA PRESSION".into()];
    for ((g, d), r) in groups.iter().zip(&diffs).zip(&refs) {
        table.push_row(vec![
            ("GROUP_MA", Value::Text(g.clone())),
            ("DIFFERENCE", Value::Real(d.sqrt())),
            ("REFERENCE", Value::Real(r.sqrt())),
        ]);
    }
    let mut total = vec![
        ("GROUP_MA", Value::Text("TOTAL".into())),
        ("DIFFERENCE", Value::Real(diff_tot)),
        ("REFERENCE", Value::Real(ref_tot)),
    ];
    if let Some(e) = relative {
        total.push(("ERREUR RELATIVE", Value::Real(e)));
    }
    table.push_row(total);
    store_result(ex, call, Concept::Table(Rc::new(table)))
}
