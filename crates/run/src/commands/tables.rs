//! CREA_TABLE and CALC_TABLE: tables made from lists or functions, and
//! operations on tables (filter, extract, rename, sort, computed columns).

use super::inspect::filter_rows;
use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::function::Function;
use crate::select;
use crate::support::Support;
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::rc::Rc;

fn strs<'k>(kw: &'k Keywords, name: &str) -> Vec<&'k str> {
    kw.simple(name).iter().filter_map(|s| s.as_str()).collect()
}

/// Text width of a `TYPE_K` (`K8`, `K16`, `K24`…), default K8.
fn text_width(ty: Option<&str>) -> usize {
    ty.and_then(|t| t.strip_prefix('K'))
        .and_then(|n| n.parse().ok())
        .unwrap_or(8)
}

/// What CREA_TABLE reads (`crate::support`).
pub(crate) const CREA_TABLE: Support = Support::keywords(&[
    "LISTE",
    "LISTE/PARA",
    "LISTE/LISTE_R",
    "LISTE/LISTE_I",
    "LISTE/LISTE_K",
    "LISTE/TYPE_K",
    "LISTE/NUME_LIGN",
    "FONCTION",
    "FONCTION/FONCTION",
    "FONCTION/PARA",
    "TYPE_TABLE",
    "TITRE",
]);

pub fn crea_table(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "CREA_TABLE";
    let kw = &call.keywords;
    let mut table = Table::default();
    for occ in kw.factor("LISTE") {
        if occ.contains("NUME_LIGN") {
            let span = occ.keyword("NUME_LIGN").map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported("CREA_TABLE/LISTE/NUME_LIGN", span));
        }
        let para = occ
            .str("PARA")
            .ok_or_else(|| ExecError::new(format!("{cmd}/LISTE: PARA is required")))?;
        let (ty, values): (ColumnType, Vec<Value>) = if occ.contains("LISTE_R") {
            (
                ColumnType::Real,
                occ.simple("LISTE_R")
                    .iter()
                    .filter_map(|s| s.as_f64())
                    .map(Value::Real)
                    .collect(),
            )
        } else if occ.contains("LISTE_I") {
            (
                ColumnType::Int,
                occ.simple("LISTE_I")
                    .iter()
                    .filter_map(|s| s.as_i64())
                    .map(Value::Int)
                    .collect(),
            )
        } else if occ.contains("LISTE_K") {
            (
                ColumnType::Text(text_width(occ.str("TYPE_K"))),
                strs(occ, "LISTE_K")
                    .into_iter()
                    .map(|s| Value::Text(s.to_string()))
                    .collect(),
            )
        } else {
            return Err(ex.kw_error(
                cmd,
                occ,
                "PARA",
                "give the column's values (LISTE_R, LISTE_I or LISTE_K)",
            ));
        };
        if table.column_index(para).is_some() {
            return Err(ex.kw_error(cmd, occ, "PARA", format!("column {para} is given twice")));
        }
        let col = table.ensure_column(para, ty);
        while table.rows.len() < values.len() {
            table.rows.push(vec![None; table.columns.len()]);
        }
        for (row, v) in table.rows.iter_mut().zip(values) {
            row[col] = Some(v);
        }
    }
    if let Some(occ) = kw.factor("FONCTION").first() {
        let f = ex.function(ex.required(cmd, occ, "FONCTION")?)?;
        let Function::Tabulated(t) = &*f else {
            return Err(ex.kw_error(cmd, occ, "FONCTION", "a tabulated function (DEFI_FONCTION, RECU_FONCTION…) is required: a formula has no points"));
        };
        let names = strs(occ, "PARA");
        let (px, py) = match names.as_slice() {
            [x, y] => (x.to_string(), y.to_string()),
            _ => (
                t.parameter.clone(),
                t.result.clone().unwrap_or_else(|| "TOUTRESU".to_string()),
            ),
        };
        table.columns = vec![
            Column {
                name: px,
                ty: ColumnType::Real,
            },
            Column {
                name: py,
                ty: ColumnType::Real,
            },
        ];
        table.rows = t
            .abscissae()
            .iter()
            .zip(t.values())
            .map(|(&x, &y)| vec![Some(Value::Real(x)), Some(Value::Real(y))])
            .collect();
    }
    if let Some(title) = kw.str("TITRE") {
        table.title = title.lines().map(str::to_string).collect();
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

fn column(table: &Table, name: &str, what: &str) -> Result<usize, ExecError> {
    table.column_index(name).ok_or_else(|| {
        ExecError::new(format!(
            "CALC_TABLE/{what}: the table has no column {name}{}",
            select::did_you_mean(name, table.columns.iter().map(|c| c.name.as_str()))
        ))
    })
}

/// What CALC_TABLE reads (`crate::support`).
pub(crate) const CALC_TABLE: Support = Support::keywords(&[
    "TABLE",
    "ACTION",
    "ACTION/OPERATION",
    "ACTION/NOM_PARA",
    "ACTION/CRIT_COMP",
    "ACTION/VALE",
    "ACTION/VALE_I",
    "ACTION/VALE_K",
    "ACTION/CRITERE",
    "ACTION/PRECISION",
    "ACTION/ORDRE",
    "ACTION/FORMULE",
    "TITRE",
    "INFO",
]);

pub fn calc_table(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "CALC_TABLE";
    let kw = &call.keywords;
    let mut table = (*ex.table(ex.required(cmd, kw, "TABLE")?)?).clone();
    for occ in kw.factor("ACTION") {
        let op = occ.str("OPERATION").unwrap_or("");
        let names = strs(occ, "NOM_PARA");
        match op {
            "FILTRE" => {
                let rows = filter_rows(&table, std::slice::from_ref(occ))
                    .map_err(|e| ExecError::new(format!("{cmd}/FILTRE: {e}")))?;
                table.rows = rows.into_iter().map(|r| table.rows[r].clone()).collect();
            }
            "EXTR" => {
                let keep = names
                    .iter()
                    .map(|n| column(&table, n, "EXTR"))
                    .collect::<Result<Vec<_>, _>>()?;
                table.keep_columns(&keep);
            }
            "SUPPRIME" => {
                let drop = names
                    .iter()
                    .map(|n| column(&table, n, "SUPPRIME"))
                    .collect::<Result<Vec<_>, _>>()?;
                let keep: Vec<usize> = (0..table.columns.len())
                    .filter(|c| !drop.contains(c))
                    .collect();
                table.keep_columns(&keep);
            }
            "RENOMME" => {
                let [old, new] = names.as_slice() else {
                    return Err(ex.kw_error(
                        cmd,
                        occ,
                        "NOM_PARA",
                        "RENOMME takes (old name, new name)",
                    ));
                };
                let c = column(&table, old, "RENOMME")?;
                table.columns[c].name = new.to_string();
            }
            "TRI" => {
                let keys = names
                    .iter()
                    .map(|n| column(&table, n, "TRI"))
                    .collect::<Result<Vec<_>, _>>()?;
                let descending = occ.str("ORDRE") == Some("DECROISSANT");
                table.rows.sort_by(|a, b| {
                    let mut o = std::cmp::Ordering::Equal;
                    for &k in &keys {
                        o = o.then_with(|| compare(&a[k], &b[k]));
                    }
                    if descending {
                        o.reverse()
                    } else {
                        o
                    }
                });
            }
            "OPER" => {
                let f = ex.function(ex.required(cmd, occ, "FORMULE")?)?;
                let [name] = names.as_slice() else {
                    return Err(ex.kw_error(
                        cmd,
                        occ,
                        "NOM_PARA",
                        "OPER takes the name of the new column",
                    ));
                };
                let params: Vec<String> = f.parameters().iter().map(|p| p.to_string()).collect();
                let cols = params
                    .iter()
                    .map(|p| column(&table, p, "OPER"))
                    .collect::<Result<Vec<_>, _>>()?;
                let mut values = Vec::with_capacity(table.rows.len());
                for row in &table.rows {
                    let args: Option<Vec<(&str, f64)>> = params
                        .iter()
                        .zip(&cols)
                        .map(|(p, &c)| {
                            row[c]
                                .as_ref()
                                .and_then(Value::as_f64)
                                .map(|v| (p.as_str(), v))
                        })
                        .collect();
                    // A row missing a parameter gets an empty cell, as
                    // code_aster leaves it.
                    values.push(match args {
                        Some(a) => Some(Value::Real(
                            f.eval_named(&a)
                                .map_err(|e| ExecError::new(format!("{cmd}/OPER: {e}")))?,
                        )),
                        None => None,
                    });
                }
                let c = table.ensure_column(name, ColumnType::Real);
                for (row, v) in table.rows.iter_mut().zip(values) {
                    row[c] = v;
                }
            }
            other => {
                let span = occ.keyword("OPERATION").map(|k| k.span).unwrap_or_default();
                return Err(ex.unsupported(&format!("{cmd}/ACTION/OPERATION='{other}'"), span));
            }
        }
    }
    if let Some(title) = kw.str("TITRE") {
        table.title = title.lines().map(str::to_string).collect();
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

fn compare(a: &Option<Value>, b: &Option<Value>) -> std::cmp::Ordering {
    use std::cmp::Ordering;
    match (a, b) {
        (Some(Value::Text(x)), Some(Value::Text(y))) => x.cmp(y),
        (Some(x), Some(y)) => x
            .as_f64()
            .unwrap_or(f64::NAN)
            .total_cmp(&y.as_f64().unwrap_or(f64::NAN)),
        (None, Some(_)) => Ordering::Greater,
        (Some(_), None) => Ordering::Less,
        (None, None) => Ordering::Equal,
    }
}

/// What RECU_TABLE reads (`crate::support`): a table a computation made.
pub(crate) const RECU_TABLE: Support = Support {
    values: &[crate::support::Values::listed(
        "NOM_TABLE",
        &["OBSERVATION", "PARA_CALC", "STAT"],
    )],
    ..Support::keywords(&["CO", "NOM_TABLE", "NOM_PARA", "TITRE"])
};

/// `RECU_TABLE(CO=result, NOM_TABLE=...)`: a table carried by a result
/// (`STAT_NON_LINE/OBSERVATION` makes 'OBSERVATION').
pub fn recu_table(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    if kw.get("NOM_PARA").is_some() {
        return recu_parameters(ex, call);
    }
    let co = ex.required("RECU_TABLE", kw, "CO")?;
    let name = kw.str("NOM_TABLE").unwrap_or("");
    let result = ex.result(co)?;
    let Some((_, t)) = result.tables.iter().find(|(n, _)| n == name) else {
        return Err(ExecError::new(format!(
            "RECU_TABLE: `{}` has no table '{name}' (it has: {})",
            co.name,
            if result.tables.is_empty() {
                "none; STAT_NON_LINE makes 'OBSERVATION' with OBSERVATION=_F(...)".to_string()
            } else {
                result
                    .tables
                    .iter()
                    .map(|(n, _)| format!("'{n}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        )));
    };
    let table = (**t).clone();
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// `RECU_TABLE(CO=result, NOM_PARA=...)`: the result's parameters per
/// step (NUME_ORDRE and, here, INST).
fn recu_parameters(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let co = ex.required("RECU_TABLE", kw, "CO")?;
    let result = ex.result(co)?;
    let params: Vec<&str> = kw
        .simple("NOM_PARA")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let mut columns = vec![Column {
        name: "NUME_ORDRE".into(),
        ty: ColumnType::Int,
    }];
    for p in &params {
        if *p != "INST" {
            return Err(ex.kw_error(
                "RECU_TABLE",
                kw,
                "NOM_PARA",
                format!(
                    "result `{}` has no parameter {p} here (its steps store INST)",
                    co.name
                ),
            ));
        }
        columns.push(Column {
            name: p.to_string(),
            ty: ColumnType::Real,
        });
    }
    let mut table = Table::new(columns);
    for s in &result.steps {
        let mut row = vec![("NUME_ORDRE", Value::Int(s.nume_ordre as i64))];
        for p in &params {
            row.push((p, Value::Real(s.inst)));
        }
        table.push_row(row);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}
