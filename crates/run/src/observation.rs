//! `STAT_NON_LINE/OBSERVATION`: values of a field at chosen instants,
//! places and components, in the table the result carries under the name
//! `OBSERVATION` (`RECU_TABLE(CO=…, NOM_TABLE='OBSERVATION')`).
//!
//! As code_aster (`nmobsv`, `nmobsz`): one row per observed value, columns
//! `NOM_OBSERVATION` (`TITRE`, else `OBSERVATION_k` for the k-th
//! occurrence), `TYPE_OBJET` ('R'), `NUME_REUSE` (0), `NUME_OBSE` (the
//! row's rank), `INST`, `NOM_CHAM`, `EVAL_CHAM`, `NOM_CMP`, then `NOEUD`
//! (nodal fields) or `MAILLE`, `POINT`, `SOUS_POINT` (element fields; a
//! `_ELEM` field has one point), and `VALE`. With `EVAL_CHAM` ≠ 'VALE'
//! the places are reduced (MIN, MAX, MOY, MAXI_ABS, MINI_ABS) and the
//! place column holds the reduction's name; with `EVAL_ELGA` ≠ 'VALE' the
//! points of a cell are reduced (MIN, MAX) and `EVAL_ELGA` replaces
//! `POINT`/`SOUS_POINT`.
//!
//! Instants: `INST` or `LIST_INST` (matched with `PRECISION`/`CRITERE`),
//! else every `PAS_OBSE`-th computed step (default every step); the
//! initial state too unless `OBSE_ETAT_INIT='NON'`.

use aster_eval::{ExecError, Keywords};
use aster_mesh::{CellId, Mesh, NodeId};

use crate::concept::Step;
use crate::executor::Executor;
use crate::field::{ElemLocation, Field};
use crate::select;
use crate::table::{Column, ColumnType, Table, Value};

/// Fields `STAT_NON_LINE` stores at every step, hence observable.
pub(crate) const FIELDS: [&str; 5] = ["DEPL", "SIEF_ELGA", "VARI_ELGA", "CONT_NOEU", "CONT_ELEM"];

/// One `OBSERVATION` occurrence.
#[derive(Clone, Debug)]
pub struct Observation {
    title: String,
    field: String,
    components: Vec<String>,
    eval_cham: String,
    eval_elga: String,
    initial: bool,
    instants: Option<Vec<f64>>,
    step: usize,
    precision: f64,
    absolute: bool,
    nodes: Vec<NodeId>,
    cells: Vec<CellId>,
    points: Vec<usize>,
    sub_points: Vec<usize>,
}

fn ints(kw: &Keywords, key: &str) -> Vec<usize> {
    kw.simple(key)
        .iter()
        .filter_map(|v| v.as_f64())
        .filter(|v| *v >= 1.0)
        .map(|v| v as usize)
        .collect()
}

/// Reads the `OBSERVATION` occurrences of a call.
pub fn parse(ex: &Executor, kw: &Keywords, mesh: &Mesh) -> Result<Vec<Observation>, ExecError> {
    let mut out = Vec::new();
    for (k, occ) in kw.factor("OBSERVATION").iter().enumerate() {
        let at = |key: &str| {
            occ.keyword(key)
                .and_then(|e| ex.location(e.span))
                .map(|l| format!(" ({l})"))
                .unwrap_or_default()
        };
        let field = occ.str("NOM_CHAM").unwrap_or("DEPL").to_string();
        if !FIELDS.contains(&field.as_str()) {
            return Err(ExecError::new(format!(
                "STAT_NON_LINE/OBSERVATION/NOM_CHAM='{field}': not observed (supported: {}){}",
                FIELDS.join(", "),
                at("NOM_CHAM")
            )));
        }
        if occ.keyword("NOM_VARI").is_some_and(|e| !e.defaulted)
            || occ.str("EVAL_CMP").unwrap_or("VALE") != "VALE"
        {
            return Err(ExecError::new(format!(
                "STAT_NON_LINE/OBSERVATION: only named components (NOM_CMP, EVAL_CMP='VALE') \
                 are observed{}",
                at("EVAL_CMP")
            )));
        }
        let components: Vec<String> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|v| v.as_str())
            .map(String::from)
            .collect();
        let nodal = matches!(field.as_str(), "DEPL" | "CONT_NOEU");
        let whole = occ.str("TOUT") == Some("OUI");
        let (nodes, cells) = if nodal {
            let n = select::nodes(occ, mesh, "")
                .map_err(|e| ExecError::new(format!("STAT_NON_LINE/OBSERVATION: {e}")))?;
            (n, Vec::new())
        } else {
            let c = select::cells(occ, mesh, "")
                .map_err(|e| ExecError::new(format!("STAT_NON_LINE/OBSERVATION: {e}")))?;
            (Vec::new(), c)
        };
        if nodes.is_empty() && cells.is_empty() && !whole {
            return Err(ExecError::new(format!(
                "STAT_NON_LINE/OBSERVATION: give where to observe (TOUT, GROUP_NO, NOEUD, \
                 GROUP_MA or MAILLE){}",
                at("NOM_CHAM")
            )));
        }
        let instants = if let Some(l) = occ.concept("LIST_INST") {
            Some((*ex.real_list(l)?).clone())
        } else if occ.keyword("INST").is_some_and(|e| !e.defaulted) {
            Some(
                occ.simple("INST")
                    .iter()
                    .filter_map(|v| v.as_f64())
                    .collect(),
            )
        } else {
            None
        };
        out.push(Observation {
            title: occ
                .str("TITRE")
                .map(String::from)
                .unwrap_or_else(|| format!("OBSERVATION_{}", k + 1)),
            field,
            components,
            eval_cham: occ.str("EVAL_CHAM").unwrap_or("VALE").to_string(),
            eval_elga: occ.str("EVAL_ELGA").unwrap_or("VALE").to_string(),
            initial: occ.str("OBSE_ETAT_INIT").unwrap_or("OUI") == "OUI",
            instants,
            step: occ
                .f64("PAS_OBSE")
                .map(|v| v.max(1.0) as usize)
                .unwrap_or(1),
            precision: occ.f64("PRECISION").unwrap_or(1e-6),
            absolute: occ.str("CRITERE") == Some("ABSOLU"),
            nodes,
            cells,
            points: ints(occ, "POINT"),
            sub_points: ints(occ, "SOUS_POINT"),
        });
    }
    Ok(out)
}

/// A place's values of one component: (place name, point, sub-point, value).
type Sample = (String, Option<(i64, i64)>, f64);

/// Reduces values as `EVAL_CHAM`/`EVAL_ELGA` say.
fn reduce(how: &str, values: &[f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let fold = |f: fn(f64, f64) -> f64| values.iter().copied().reduce(f);
    match how {
        "MIN" => fold(f64::min),
        "MAX" => fold(f64::max),
        "MOY" => Some(values.iter().sum::<f64>() / values.len() as f64),
        "MAXI_ABS" => values
            .iter()
            .copied()
            .reduce(|a, b| if b.abs() > a.abs() { b } else { a }),
        "MINI_ABS" => values
            .iter()
            .copied()
            .reduce(|a, b| if b.abs() < a.abs() { b } else { a }),
        _ => None,
    }
}

impl Observation {
    /// The steps this observation records.
    fn observed<'s>(&self, steps: &'s [Step]) -> Vec<&'s Step> {
        let computed = |i: usize| i > 0;
        steps
            .iter()
            .enumerate()
            .filter(|(i, s)| match &self.instants {
                Some(list) => {
                    list.iter().any(|t| {
                        let d = (s.inst - t).abs();
                        if self.absolute {
                            d <= self.precision
                        } else {
                            d <= self.precision * t.abs() || d == 0.0
                        }
                    }) && (computed(*i) || self.initial)
                }
                None if !computed(*i) => self.initial,
                None => i % self.step == 0,
            })
            .map(|(_, s)| s)
            .collect()
    }

    /// The samples of one component at one step.
    fn samples(&self, mesh: &Mesh, field: &Field, comp: &str) -> Vec<Sample> {
        match field {
            Field::Nodal(f) => {
                let nodes: Vec<NodeId> = if self.nodes.is_empty() {
                    f.nodes().collect()
                } else {
                    self.nodes.clone()
                };
                nodes
                    .iter()
                    .filter_map(|&n| Some((mesh.node_name(n), None, f.get(n, comp)?)))
                    .collect()
            }
            Field::Elem(f) => {
                let cells: Vec<CellId> = if self.cells.is_empty() {
                    f.cells().to_vec()
                } else {
                    self.cells.clone()
                };
                let Some(c) = f.component_index(comp) else {
                    return Vec::new();
                };
                let mut out = Vec::new();
                for cell in cells {
                    let Some(pts) = f.cell(cell) else {
                        continue;
                    };
                    let name = select::cell_name(mesh, cell);
                    let keep = |p: usize| {
                        f.location == ElemLocation::Cell
                            || self.points.is_empty()
                            || self.points.contains(&p)
                    };
                    let vals: Vec<(usize, f64)> = pts
                        .iter()
                        .enumerate()
                        .map(|(i, v)| (i + 1, v.get(c).copied().unwrap_or(f64::NAN)))
                        .filter(|(p, _)| keep(*p))
                        .collect();
                    if self.eval_elga == "VALE" {
                        let sub = self.sub_points.first().copied().unwrap_or(1) as i64;
                        out.extend(
                            vals.iter()
                                .map(|(p, v)| (name.clone(), Some((*p as i64, sub)), *v)),
                        );
                    } else if let Some(v) = reduce(
                        &self.eval_elga,
                        &vals.iter().map(|t| t.1).collect::<Vec<_>>(),
                    ) {
                        out.push((name.clone(), None, v));
                    }
                }
                out
            }
        }
    }
}

/// The `OBSERVATION` table of a solve, from the stored steps.
pub fn table(observations: &[Observation], steps: &[Step], mesh: &Mesh) -> Table {
    let text = |n| ColumnType::Text(n);
    let mut t = Table::new(
        [
            ("NOM_OBSERVATION", text(16)),
            ("TYPE_OBJET", text(16)),
            ("NUME_REUSE", ColumnType::Int),
            ("NUME_OBSE", ColumnType::Int),
            ("INST", ColumnType::Real),
            ("NOM_CHAM", text(16)),
            ("EVAL_CHAM", text(8)),
            ("NOM_CMP", text(8)),
        ]
        .into_iter()
        .map(|(name, ty)| Column {
            name: name.into(),
            ty,
        })
        .collect(),
    );
    let mut rank = 0i64;
    for obs in observations {
        let nodal = matches!(obs.field.as_str(), "DEPL" | "CONT_NOEU");
        for step in obs.observed(steps) {
            let Some(field) = step.fields.get(&obs.field) else {
                continue;
            };
            for comp in &obs.components {
                let samples = obs.samples(mesh, field, comp);
                #[allow(clippy::type_complexity)]
                // (label, (point, sub-point), value), as samples gives them
                let mut rows: Vec<(String, Option<(i64, i64)>, f64)> = Vec::new();
                if obs.eval_cham == "VALE" {
                    rows = samples;
                } else if let Some(v) = reduce(
                    &obs.eval_cham,
                    &samples.iter().map(|s| s.2).collect::<Vec<_>>(),
                ) {
                    rows.push((obs.eval_cham.clone(), None, v));
                }
                for (place, point, v) in rows {
                    rank += 1;
                    let mut cells = vec![
                        ("NOM_OBSERVATION", Value::Text(obs.title.clone())),
                        ("TYPE_OBJET", Value::Text("R".into())),
                        ("NUME_REUSE", Value::Int(0)),
                        ("NUME_OBSE", Value::Int(rank)),
                        ("INST", Value::Real(step.inst)),
                        ("NOM_CHAM", Value::Text(obs.field.clone())),
                        ("EVAL_CHAM", Value::Text(obs.eval_cham.clone())),
                        ("NOM_CMP", Value::Text(comp.clone())),
                    ];
                    if obs.eval_cham != "VALE" {
                        // The reduction names the place column.
                    } else if nodal {
                        cells.push(("NOEUD", Value::Text(place)));
                    } else {
                        cells.push(("MAILLE", Value::Text(place)));
                    }
                    if !nodal {
                        match point {
                            Some((p, s)) => {
                                cells.push(("POINT", Value::Int(p)));
                                cells.push(("SOUS_POINT", Value::Int(s)));
                            }
                            None => cells.push(("EVAL_ELGA", Value::Text(obs.eval_elga.clone()))),
                        }
                    }
                    cells.push(("VALE", Value::Real(v)));
                    t.push_row(cells);
                }
            }
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reductions() {
        let v = [1.0, -3.0, 2.0];
        assert_eq!(reduce("MIN", &v), Some(-3.0));
        assert_eq!(reduce("MAX", &v), Some(2.0));
        assert_eq!(reduce("MOY", &v), Some(0.0));
        assert_eq!(reduce("MAXI_ABS", &v), Some(-3.0));
        assert_eq!(reduce("MINI_ABS", &v), Some(1.0));
        assert_eq!(reduce("MAX", &[]), None);
    }
}
