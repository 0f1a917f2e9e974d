//! POST_ELEM/INTEGRALE: where the integrated fields come from (code_aster's
//! `peeint`): a result's steps (`RESULTAT`, the model it was computed with
//! or `MODELE` + `CHAM_MATER`), or one field (`CHAM_GD` with `MODELE`).
//!
//! A field gives one row per place with the columns `CHAM_GD` (the field's
//! name), `VOL`, the place's, `INTE_<cmp>`… then `MOYE_<cmp>`… (`peecal`
//! without `NOM_CHAM`, `NUME_ORDRE`, `INST`); its weights are the model's
//! `COOR_ELGA` ones (the Gauss layout of [`crate::commands::crea_champ_elga`],
//! continuum models only), a nodal field spread to its cells' nodes as for
//! a result's.

use super::{col, result_model, ModelRef};
use crate::commands::crea_champ_elga::{layout, Layout};
use crate::concept::{EvolResult, ModelDef};
use crate::executor::Executor;
use crate::field::Field;
use crate::table::{ColumnType, Table};
use aster_eval::{CommandCall, ExecError};
use aster_mesh::{CellId, Mesh};
use aster_syntax::Span;
use std::rc::Rc;
use std::sync::Arc;

/// A field to integrate and its (NUME_ORDRE, INST) in a result.
pub(super) type StepField<'s> = (Option<(u32, f64)>, &'s Field);

/// The fields integrated.
pub(super) enum Source {
    /// A result's name, the result, the NUME_ORDRE selected and its model.
    Result(String, Rc<EvolResult>, Vec<u32>, Rc<ModelRef>),
    /// A field's name, the field, its model and that model's Gauss layout.
    Field(String, Rc<Field>, Rc<ModelDef>, Layout),
}

/// The source of the command, its mesh and whether the result's model is
/// axisymmetric (the weights' r).
pub(super) fn source(
    ex: &Executor,
    call: &CommandCall,
) -> Result<(Source, Arc<Mesh>, bool), ExecError> {
    let cmd = "POST_ELEM/INTEGRALE";
    let kw = &call.keywords;
    if let Some(f) = kw.concept("CHAM_GD") {
        let model = ex.model(ex.required(cmd, kw, "MODELE")?)?;
        let mesh = ex.model_mesh(&model)?;
        let at = kw.keyword("MODELE").map(|k| k.span).unwrap_or(call.span);
        let layout = layout(ex, &model, &mesh, at)?;
        let field = ex.field(f)?;
        return Ok((
            Source::Field(f.name.clone(), field, model, layout),
            mesh,
            false,
        ));
    }
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let orders = super::super::post::select_steps(ex, "POST_ELEM", kw, &result)?
        .iter()
        .map(|s| s.nume_ordre)
        .collect();
    let (model, _) = result_model(ex, kw, r, &result)?;
    let mesh = model.mesh_arc().clone();
    let axis = model.hypothesis() == Some(aster_fem::Hypothesis::Axisymmetric);
    Ok((
        Source::Result(r.name.clone(), result, orders, model),
        mesh,
        axis,
    ))
}

/// The table's first columns (`peeint`): a result's `NOM_CHAM`,
/// `NUME_ORDRE`, `INST`, `VOL`; a field's `CHAM_GD`, `VOL`.
pub(super) fn table(source: &Source) -> Table {
    let columns = match source {
        Source::Result(..) => vec![
            col("NOM_CHAM", ColumnType::Text(16)),
            col("NUME_ORDRE", ColumnType::Int),
            col("INST", ColumnType::Real),
            col("VOL", ColumnType::Real),
        ],
        Source::Field(..) => vec![
            col("CHAM_GD", ColumnType::Text(16)),
            col("VOL", ColumnType::Real),
        ],
    };
    Table::new(columns)
}

impl Source {
    /// Whether the model has an element on cell `c`.
    pub(super) fn in_model(&self, c: CellId) -> bool {
        match self {
            Source::Result(.., model) => model.element_kind(c).is_some() || model.is_edge(c),
            Source::Field(_, _, model, _) => model.cells.contains_key(&c),
        }
    }

    /// The model's cells (`TOUT`).
    pub(super) fn model_cells(&self) -> Vec<CellId> {
        match self {
            Source::Result(.., model) => {
                let mut cells: Vec<CellId> = model.elements().iter().map(|e| e.cell).collect();
                cells.extend(model.edge_cells());
                cells
            }
            Source::Field(_, _, model, _) => model.cells.keys().copied().collect(),
        }
    }

    /// The weights of cell `c`'s points (`COOR_ELGA`); `None`: a cell
    /// without Gauss points (skipped). Structural and discrete elements of
    /// a result are refused at `at`.
    pub(super) fn weights(
        &self,
        ex: &Executor,
        c: CellId,
        axis: bool,
        at: Span,
    ) -> Result<Option<Vec<f64>>, ExecError> {
        let model = match self {
            Source::Field(.., layout) => {
                return Ok(layout
                    .cells
                    .get(&c)
                    .map(|g| g.points.iter().map(|p| p.weight).collect()))
            }
            Source::Result(.., model) => model,
        };
        let mesh = model.mesh_arc();
        let ty = mesh.cell(c).ty;
        // Skin cells, and segments of a 3D model (MECA_ARETE*).
        let skin = matches!(
            model.element_kind(c),
            Some(aster_fem::ElementKind::Boundary)
        ) || model.is_edge(c);
        let scheme = match model.element_kind(c) {
            Some(aster_fem::ElementKind::Continuum { .. }) => model.stiffness_scheme(c),
            _ if skin => {
                let role = aster_fem::elga::CellRole::of(ty.dim() as usize, model.dim());
                match role.and_then(|r| aster_fem::elga::family(ty, r, axis)) {
                    Some(s) => s,
                    None => return Ok(None),
                }
            }
            _ => {
                return Err(ex.unsupported(
                    &format!(
                        "POST_ELEM/INTEGRALE over cell {} (a structural or discrete element): continuum and skin cells only",
                        crate::select::cell_name(mesh, c)
                    ),
                    at,
                ))
            }
        };
        Ok(Some(
            aster_fem::elga::points(mesh, c, &scheme, axis)
                .iter()
                .map(|p| p.weight)
                .collect(),
        ))
    }

    /// The fields of an occurrence's rows: a result's `nom_cham` at each
    /// step selected (with its NUME_ORDRE and INST), or the one field.
    pub(super) fn fields(&self, nom_cham: &str) -> Result<Vec<StepField<'_>>, ExecError> {
        match self {
            Source::Field(_, f, ..) => Ok(vec![(None, &**f)]),
            Source::Result(name, result, orders, _) => orders
                .iter()
                .map(|&o| {
                    let step = result.step_numbered(o).ok_or_else(|| {
                        ExecError::new(format!("POST_ELEM: no NUME_ORDRE {o} in `{name}`"))
                    })?;
                    let f = super::super::post::step_field(step, nom_cham, name)?;
                    Ok((Some((o, step.inst)), f))
                })
                .collect(),
        }
    }
}
