//! POST_ELEM/MINMAX: the extrema in space of components of a field, code_aster's
//! `pemima` (`pemaxn` for a nodal field, `pemaxe` for an element field).
//!
//! The field: `CHAM_GD` (with `MODELE`) of the first occurrence, once, with
//! `NUME_ORDRE` 0 and `INST` 0 and `CHAMP_GD` the field's name; or the
//! field `NOM_CHAM` of the first occurrence's `RESULTAT` at each step its
//! selection (`NUME_ORDRE`, `INST`, `LIST_*`, `TOUT_ORDRE`, default every
//! step) designates, `CHAMP_GD` = `NOM_CHAM`. As code_aster, the result
//! and the steps of the first occurrence serve every occurrence; each
//! occurrence reads its own `NOM_CHAM`, `NOM_CMP` and places. Rows:
//! occurrence by occurrence, step by step, a row for `TOUT` (`TOUT` =
//! 'TOUT'), one per `GROUP_MA`, then `UNION_GROUP_MA` when there are
//! several groups (a group the mesh lacks, or an empty one, is skipped).
//!
//! - Nodal field: over the mesh's nodes (`TOUT`) or the nodes of the
//!   group's cells, by increasing number, the first node reaching the
//!   largest (smallest) value: columns `MAX_<c>`, `NO_MAX_<c>`, `MIN_<c>`,
//!   `NO_MIN_<c>` per component.
//! - Element field (ELGA, ELNO, ELEM): over the cells (all or the group's)
//!   by increasing number and their points: `MAX_<c>`, `MA_MAX_<c>`,
//!   `PT_MAX_<c>` (the point's number, 1-based), `MIN_<c>`, `MA_MIN_<c>`,
//!   `PT_MIN_<c>`.
//!
//! The node and cell columns hold their numbers as text ("12"), as
//! code_aster 17 writes them (`int_to_char8`), not their names. No value:
//! MAX = −1.797…e308, MIN = +1.797…e308, an empty name and point −1.
//! Columns `CHAMP_GD` (K16), `NUME_ORDRE`, `INST`, then `TOUT` or
//! `GROUP_MA` (K24) and the components' columns as they first appear.
//! Refused: an element field of a result on shell or beam cells (code_aster's
//! layers and fibres are sub-points, which `pemaxe` does not take).

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::field::Field;
use crate::table::{ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{CellId, Mesh};
use std::collections::BTreeSet;
use std::rc::Rc;

pub(super) fn minmax(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/MINMAX";
    let occs = call.keywords.factor("MINMAX");
    let Some(first) = occs.first() else {
        return Err(ExecError::new(format!("{cmd}: no occurrence")));
    };
    let mut table = Table::new(
        [
            ("CHAMP_GD", ColumnType::Text(16)),
            ("NUME_ORDRE", ColumnType::Int),
            ("INST", ColumnType::Real),
        ]
        .into_iter()
        .map(|(n, ty)| super::col(n, ty))
        .collect(),
    );
    // The field of CHAM_GD, or the result and its steps.
    let mut fem_model = None;
    let (source, mesh) = if let Some(f) = first.concept("CHAM_GD") {
        let m = ex.required(cmd, first, "MODELE")?;
        // A mechanical or a thermal model: only its mesh is used.
        let mesh = match ex.thermal_model(m) {
            Ok(t) => ex.mesh_by_id(t.mesh)?,
            Err(_) => ex.model_mesh(&*ex.model(m)?)?,
        };
        (Source::Field(f.name.clone(), ex.field(f)?), mesh)
    } else {
        let r = ex.required(cmd, first, "RESULTAT")?;
        let result = ex.result(r)?;
        fem_model = result.fem.clone();
        let steps = super::super::post::select_steps(ex, "POST_ELEM", first, &result)?
            .iter()
            .map(|s| s.nume_ordre)
            .collect();
        let mesh = ex.mesh_by_id(result.mesh)?;
        (Source::Result(r.name.clone(), result, steps), mesh)
    };
    for occ in occs {
        let cmps: Vec<String> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        let places = places(ex, cmd, occ, &mesh)?;
        for (champ, order, inst, field) in fields(ex, cmd, &source, occ)? {
            if let (Field::Elem(e), Some(run)) = (field, &fem_model) {
                if let Some(c) = e.cells().iter().find(|c| {
                    !matches!(
                        run.model.element_kind(**c),
                        None | Some(aster_fem::ElementKind::Continuum { .. })
                            | Some(aster_fem::ElementKind::Boundary)
                    )
                }) {
                    return Err(ex.unsupported(
                        &format!(
                            "POST_ELEM/MINMAX of element field {champ} on cell {} (a shell, beam or discrete element: code_aster's sub-points are not reproduced)",
                            crate::select::cell_name(&mesh, *c)
                        ),
                        occ.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span),
                    ));
                }
            }
            for (lieu, place, cells) in &places {
                let mut row: Vec<(String, Value)> = vec![
                    ("CHAMP_GD".into(), Value::Text(champ.clone())),
                    ("NUME_ORDRE".into(), Value::Int(order as i64)),
                    ("INST".into(), Value::Real(inst)),
                    (lieu.to_string(), Value::Text(place.clone())),
                ];
                table.ensure_column(lieu, ColumnType::Text(24));
                for cmp in &cmps {
                    let Some(ic) = field.components().iter().position(|c| c == cmp) else {
                        // code_aster's assertion in pemaxn/pemaxe.
                        return Err(ex.kw_error(
                            cmd,
                            occ,
                            "NOM_CMP",
                            format!("field {champ} has no component {cmp}"),
                        ));
                    };
                    match field {
                        Field::Nodal(n) => {
                            let nodes = cells.as_ref().map(|cells| {
                                cells
                                    .iter()
                                    .flat_map(|c| mesh.cell(*c).nodes.iter().map(|n| n.0))
                                    .collect::<BTreeSet<u32>>()
                            });
                            let values = n.iter().filter_map(|(node, v)| {
                                let keep = nodes.as_ref().is_none_or(|s| s.contains(&node.0));
                                keep.then(|| v.get(ic).map(|x| ((node.0, 0), x)))?
                            });
                            let e = Extrema::of(values);
                            let name = |at: Option<(u32, usize)>| {
                                Value::Text(at.map_or(String::new(), |(n, _)| (n + 1).to_string()))
                            };
                            for (col, ty, v) in [
                                (format!("MAX_{cmp}"), ColumnType::Real, Value::Real(e.max)),
                                (
                                    format!("NO_MAX_{cmp}"),
                                    ColumnType::Text(16),
                                    name(e.at_max),
                                ),
                                (format!("MIN_{cmp}"), ColumnType::Real, Value::Real(e.min)),
                                (
                                    format!("NO_MIN_{cmp}"),
                                    ColumnType::Text(16),
                                    name(e.at_min),
                                ),
                            ] {
                                table.ensure_column(&col, ty);
                                row.push((col, v));
                            }
                        }
                        Field::Elem(ef) => {
                            let keep: Option<BTreeSet<CellId>> =
                                cells.as_ref().map(|c| c.iter().copied().collect());
                            let values = ef
                                .iter()
                                .filter(|(c, _)| keep.as_ref().is_none_or(|k| k.contains(c)))
                                .flat_map(|(c, points)| {
                                    points.iter().enumerate().filter_map(move |(p, v)| {
                                        let x = v[ic];
                                        (!x.is_nan()).then_some(((c.0, p), x))
                                    })
                                });
                            let e = Extrema::of(values);
                            let name = |at: Option<(u32, usize)>| {
                                Value::Text(at.map_or(String::new(), |(c, _)| (c + 1).to_string()))
                            };
                            let point = |at: Option<(u32, usize)>| {
                                Value::Int(at.map_or(-1, |(_, p)| p as i64 + 1))
                            };
                            for (col, ty, v) in [
                                (format!("MAX_{cmp}"), ColumnType::Real, Value::Real(e.max)),
                                (
                                    format!("MA_MAX_{cmp}"),
                                    ColumnType::Text(16),
                                    name(e.at_max),
                                ),
                                (format!("PT_MAX_{cmp}"), ColumnType::Int, point(e.at_max)),
                                (format!("MIN_{cmp}"), ColumnType::Real, Value::Real(e.min)),
                                (
                                    format!("MA_MIN_{cmp}"),
                                    ColumnType::Text(16),
                                    name(e.at_min),
                                ),
                                (format!("PT_MIN_{cmp}"), ColumnType::Int, point(e.at_min)),
                            ] {
                                table.ensure_column(&col, ty);
                                row.push((col, v));
                            }
                        }
                    }
                }
                table.push_row(row.iter().map(|(n, v)| (n.as_str(), v.clone())).collect());
            }
        }
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// (CHAMP_GD, NUME_ORDRE, INST, the field) of an occurrence's rows.
fn fields<'s>(
    ex: &Executor,
    cmd: &str,
    source: &'s Source,
    occ: &Keywords,
) -> Result<Vec<(String, u32, f64, &'s Field)>, ExecError> {
    match source {
        Source::Field(name, f) => Ok(vec![(name.clone(), 0, 0.0, &**f)]),
        Source::Result(rname, result, orders) => {
            let Some(nom_cham) = occ.str("NOM_CHAM") else {
                return Err(ex.kw_error(cmd, occ, "NOM_CHAM", "NOM_CHAM is needed with RESULTAT"));
            };
            let mut out = Vec::new();
            for &o in orders {
                let step = result.step_numbered(o).ok_or_else(|| {
                    ExecError::new(format!("{cmd}: no NUME_ORDRE {o} in `{rname}`"))
                })?;
                let f = super::super::post::step_field(step, nom_cham, rname)?;
                out.push((nom_cham.to_string(), o, step.inst, f));
            }
            Ok(out)
        }
    }
}

/// Where the fields come from: a field (its name) or a result (its name,
/// the steps selected).
enum Source {
    Field(String, Rc<Field>),
    Result(String, Rc<crate::concept::EvolResult>, Vec<u32>),
}

/// A row's place: its column (`TOUT` or `GROUP_MA`), its name, its cells
/// (`None`: the whole mesh).
type Place = (&'static str, String, Option<Vec<CellId>>);

/// The rows of an occurrence: `TOUT` (all: `None`), each group of
/// `GROUP_MA` the mesh has and that is not empty, then their union when
/// the occurrence names several groups.
fn places(ex: &Executor, cmd: &str, occ: &Keywords, mesh: &Mesh) -> Result<Vec<Place>, ExecError> {
    let mut out = Vec::new();
    if occ.contains("TOUT") {
        out.push(("TOUT", "TOUT".to_string(), None));
    }
    let groups: Vec<&str> = occ
        .simple("GROUP_MA")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let mut union = BTreeSet::new();
    for g in &groups {
        // code_aster's UTILITAI3_46/47 are alarms: the group is skipped.
        let Ok(cells) = crate::select::group_ma(mesh, g) else {
            continue;
        };
        if cells.is_empty() {
            continue;
        }
        union.extend(cells.iter().copied());
        out.push(("GROUP_MA", g.to_string(), Some(cells.to_vec())));
    }
    if groups.len() > 1 {
        if union.is_empty() {
            return Err(ex.kw_error(cmd, occ, "GROUP_MA", "no cell in these groups"));
        }
        out.push((
            "GROUP_MA",
            "UNION_GROUP_MA".to_string(),
            Some(union.into_iter().collect()),
        ));
    }
    Ok(out)
}

/// The largest and smallest values of a sequence and where each is first
/// reached (strict comparisons, as `pemaxn`/`pemaxe`: ties keep the first).
#[derive(Debug, PartialEq)]
struct Extrema {
    max: f64,
    at_max: Option<(u32, usize)>,
    min: f64,
    at_min: Option<(u32, usize)>,
}

impl Extrema {
    fn of(values: impl Iterator<Item = ((u32, usize), f64)>) -> Extrema {
        let mut e = Extrema {
            max: -f64::MAX,
            at_max: None,
            min: f64::MAX,
            at_min: None,
        };
        for (at, v) in values {
            if e.max < v {
                e.max = v;
                e.at_max = Some(at);
            }
            if e.min > v {
                e.min = v;
                e.at_min = Some(at);
            }
        }
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_keep_the_first_and_nothing_gives_the_sentinels() {
        let v = [
            ((1, 0), 2.0),
            ((2, 1), 5.0),
            ((3, 0), 5.0),
            ((4, 2), -1.0),
            ((5, 0), -1.0),
        ];
        let e = Extrema::of(v.into_iter());
        assert_eq!(
            e,
            Extrema {
                max: 5.0,
                at_max: Some((2, 1)),
                min: -1.0,
                at_min: Some((4, 2)),
            }
        );
        let none = Extrema::of(std::iter::empty());
        assert_eq!(
            (none.max, none.min, none.at_max),
            (-f64::MAX, f64::MAX, None)
        );
    }
}
