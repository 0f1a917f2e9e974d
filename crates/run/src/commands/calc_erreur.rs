//! CALC_ERREUR: code_aster's a-posteriori error estimators on a computed
//! result (`OPTION`), stored in the result as fields of its steps.
//!
//! `ERME_ELEM` (the residual estimator of the mechanics, code_aster's
//! te0377 in 2D and te0375 in 3D, [`aster_fem::error_estimate`]): from the
//! step's `SIGM_ELNO` (computed and stored first when the result lacks it,
//! as code_aster does), the volume forces (`PESANTEUR`, `FORCE_INTERNE`)
//! and the tractions on the model's skin cells (`FORCE_CONTOUR`,
//! `FORCE_FACE`, `PRES_REP`) of the result's loads, each at its charge's
//! value at the step's time without the `EXCIT/FONC_MULT` — code_aster's
//! estimator reads the charges' load maps (`resloc`), not the multipliers
//! of the computation: at the initial state of a ramp the residual is the
//! whole load. A step where a `FONC_MULT` is 0 while the charge is a
//! function (its own value then unknown here) is left without the
//! estimator's fields (a read of them then stops), and the command is
//! refused when every selected step is so.
//! `ERME_ELNO` copies each cell's values to its nodes (te0379),
//! `ERME_NOEU` averages those at the nodes.
//!
//! Refused with a located reason: the thermal estimators (`ERTH_*`) and the
//! other options, loads given point by point that are not uniform over a
//! cell (functions of the coordinates), thermal strains, follower
//! pressures, models with structural elements (shells, beams, discrete),
//! MACRO_ELAS_MULT results. In AXIS, gravity acts along the axis only (the
//! solve's load, te0085), where te0377 would also take a radial component
//! of `DIRECTION`.

use crate::concept::{Concept, EvolResult};
use crate::executor::{store_result, Executor};
use crate::field::{ElemField, ElemLocation, Field};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::error_estimate::{self, EstimatorInput};
use aster_fem::{ElementKind, Load};
use std::rc::Rc;

const OWN: &[&str] = &[
    "RESULTAT",
    "OPTION",
    "TOUT",
    "INFO",
    "TITRE",
    "SOLVEUR",
    "SOLVEUR/*",
];

/// What CALC_ERREUR computes (`crate::support`).
pub(crate) const CALC_ERREUR: Support = Support {
    values: &[Values::listed(
        "OPTION",
        &["ERME_ELEM", "ERME_ELNO", "ERME_NOEU"],
    )],
    ..Support::keywords(&crate::support::joined::<
        _,
        { crate::commands::post::STEP_SELECTION.len() + OWN.len() },
    >(crate::commands::post::STEP_SELECTION, OWN))
};

pub fn calc_erreur(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "CALC_ERREUR";
    let kw = &call.keywords;
    let r = ex.required(CMD, kw, "RESULTAT")?;
    let mut result: Rc<EvolResult> = ex.result(r)?;
    let options: Vec<String> = kw
        .simple("OPTION")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect();
    let at = kw.keyword("RESULTAT").map(|k| k.span).unwrap_or(call.span);
    let Some(run) = result.fem.clone() else {
        return Err(ex.unsupported(
            "CALC_ERREUR on a result not computed by MECA_STATIQUE/STAT_NON_LINE in this run (the estimator needs its model and loads)",
            at,
        ));
    };
    if result.cases.is_some() {
        // MACRO_ELAS_MULT: each case has its own loads.
        return Err(ex.unsupported(
            "CALC_ERREUR on a MACRO_ELAS_MULT result (each load case has its own loads)",
            at,
        ));
    }
    let model = &run.model;
    for el in model.elements() {
        if !matches!(
            el.kind,
            ElementKind::Continuum { .. } | ElementKind::Boundary
        ) {
            return Err(ex.unsupported(
                &format!(
                    "CALC_ERREUR/OPTION='ERME_ELEM' on a model with structural or discrete elements (cell {}): code_aster's estimator exists for continuum cells only",
                    model.cell_name(el.cell)
                ),
                at,
            ));
        }
    }
    if !run.follower.is_empty() {
        return Err(ex.unsupported(
            "CALC_ERREUR on a result with follower pressures (TYPE_CHARGE='SUIV')",
            at,
        ));
    }
    let steps: Vec<u32> = crate::commands::select_steps_pub(ex, CMD, kw, &result)?;
    // SIGM_ELNO first, stored in the result (code_aster computes it there).
    let missing: Vec<u32> = result
        .steps
        .iter()
        .filter(|s| steps.contains(&s.nume_ordre) && !s.fields.contains_key("SIGM_ELNO"))
        .map(|s| s.nume_ordre)
        .collect();
    if !missing.is_empty() {
        result = Rc::new(crate::fembridge::calc_champ(
            ex,
            call,
            &result,
            &["SIGM_ELNO".to_string()],
            &missing,
            None,
        )?);
    }
    let mesh = model.mesh_arc().clone();
    let mut out = (*result).clone();
    let (mut computed, mut refused) = (0usize, None::<String>);
    for step in out
        .steps
        .iter_mut()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let raw = run.state(CMD, step.nume_ordre)?;
        let time = raw.time;
        let mut input = EstimatorInput::default();
        let mut skipped: Option<String> = None;
        let Some(Field::Elem(elno)) = step.fields.get("SIGM_ELNO") else {
            return Err(ExecError::new(format!(
                "CALC_ERREUR: no SIGM_ELNO at NUME_ORDRE {}",
                step.nume_ordre
            )));
        };
        let idx: Vec<Option<usize>> = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]
            .iter()
            .map(|c| elno.component_index(c))
            .collect();
        for (cell, points) in elno.iter() {
            if !matches!(
                model.element_kind(cell),
                Some(ElementKind::Continuum { .. })
            ) {
                continue;
            }
            let v: Vec<[f64; 6]> = points
                .iter()
                .map(|p| {
                    std::array::from_fn(|k| {
                        idx[k]
                            .and_then(|i| p.get(i).copied())
                            .filter(|x| !x.is_nan())
                            .unwrap_or(0.0)
                    })
                })
                .collect();
            input.stress.insert(cell, v);
        }
        for (i, item) in run.loads.items.iter().enumerate() {
            let uniform = |v: &[[f64; 3]]| v.windows(2).all(|w| w[0] == w[1]);
            // The charge's own value at this time: the item's multiplier
            // without its EXCIT/FONC_MULT (code_aster's estimator reads the
            // load maps, the functions of INST of AFFE_CHAR_MECA_F at the
            // step's time).
            let mut scale = 1.0;
            if matches!(
                item.load,
                Load::VolumeForce { .. }
                    | Load::VolumeForceAt { .. }
                    | Load::SurfaceForce { .. }
                    | Load::SurfaceForceAt { .. }
                    | Load::Pressure { .. }
                    | Load::PressureAt { .. }
            ) {
                let eval = |m: &aster_fem::Multiplier| {
                    m.eval(time)
                        .map_err(|e| ExecError::new(format!("CALC_ERREUR: {e}")))
                };
                let m = eval(&item.mult)?;
                scale = m;
                if let Some((_, fm)) = run.excit.iter().find(|(r, _)| r.contains(&i)) {
                    let f = eval(fm)?;
                    if f == 0.0 {
                        skipped = Some(format!(
                            "CALC_ERREUR at INST {time}: the FONC_MULT of a load is 0 there (code_aster's estimator takes the charges without their FONC_MULT: their values at this time are not known here)"
                        ));
                    } else {
                        scale = m / f;
                    }
                }
            }
            let not_uniform = |what: &str| {
                ex.unsupported(
                    &format!(
                        "CALC_ERREUR with a {what} that varies over a cell (a function of the coordinates: code_aster's estimator evaluates it otherwise)"
                    ),
                    at,
                )
            };
            match &item.load {
                Load::VolumeForce { cell, force } => {
                    let f = input.volume_force.entry(*cell).or_insert([0.0; 3]);
                    for k in 0..3 {
                        f[k] += scale * force[k];
                    }
                }
                Load::VolumeForceAt { cell, forces } => {
                    if !uniform(forces) {
                        return Err(not_uniform("FORCE_INTERNE"));
                    }
                    if let Some(force) = forces.first() {
                        let f = input.volume_force.entry(*cell).or_insert([0.0; 3]);
                        for k in 0..3 {
                            f[k] += force[k];
                        }
                    }
                }
                Load::SurfaceForce { cell, force } => {
                    let f = input.skin_forces.entry(*cell).or_insert([0.0; 3]);
                    for k in 0..3 {
                        f[k] += scale * force[k];
                    }
                }
                Load::SurfaceForceAt { cell, forces } => {
                    if !uniform(forces) {
                        return Err(not_uniform("FORCE_CONTOUR/FORCE_FACE"));
                    }
                    if let Some(force) = forces.first() {
                        let f = input.skin_forces.entry(*cell).or_insert([0.0; 3]);
                        for k in 0..3 {
                            f[k] += force[k];
                        }
                    }
                }
                Load::Pressure { cell, pressure } => {
                    *input.skin_pressures.entry(*cell).or_insert(0.0) += scale * pressure;
                }
                Load::PressureAt { cell, pressures } => {
                    if !pressures.windows(2).all(|w| w[0] == w[1]) {
                        return Err(not_uniform("PRES_REP"));
                    }
                    if let Some(p) = pressures.first() {
                        *input.skin_pressures.entry(*cell).or_insert(0.0) += scale * p;
                    }
                }
                // Not in code_aster's estimator: nodal forces and the
                // kinematic conditions (no load map of resloc).
                Load::Eliminated { .. }
                | Load::Imposed { .. }
                | Load::Relation { .. }
                | Load::NodalForce { .. } => {}
                Load::FreeStrain { .. } => {
                    return Err(ex.unsupported(
                        "CALC_ERREUR on a result with a thermal strain (AFFE_VARC)",
                        at,
                    ));
                }
                Load::EdgeForce { .. } | Load::ShellForce { .. } | Load::ShellThermal { .. } => {
                    return Err(ex.unsupported(
                        "CALC_ERREUR with edge or shell loads (FORCE_ARETE, FORCE_COQUE)",
                        at,
                    ));
                }
            }
        }
        if let Some(why) = skipped {
            // Not computed at this step: a later read of its fields finds
            // none (no number printed); every step so: refused here.
            refused.get_or_insert(why);
            continue;
        }
        computed += 1;
        let values = error_estimate::residual_estimate(model, &input)
            .map_err(|e| ex.unsupported(&format!("CALC_ERREUR/OPTION='ERME_ELEM': {e}"), at))?;
        let names: Vec<String> = error_estimate::COMPONENTS
            .iter()
            .map(|s| s.to_string())
            .collect();
        let mut elem = ElemField::new(ElemLocation::Cell, names.clone());
        let mut nodes = ElemField::new(ElemLocation::Nodes, names.clone());
        for (cell, v) in &values {
            elem.insert(*cell, [v.as_slice()]);
            let n = mesh.cell(*cell).nodes.len();
            nodes.insert(*cell, std::iter::repeat_n(v.as_slice(), n));
        }
        for opt in &options {
            match opt.as_str() {
                "ERME_ELEM" => step.fields.insert(opt.clone(), Field::Elem(elem.clone())),
                "ERME_ELNO" => step.fields.insert(opt.clone(), Field::Elem(nodes.clone())),
                "ERME_NOEU" => {
                    let noeu = nodes.nodal_mean(&mesh).ok_or_else(|| {
                        ExecError::new("CALC_ERREUR: ERME_NOEU from a field not at nodes")
                    })?;
                    step.fields.insert(opt.clone(), Field::Nodal(noeu))
                }
                other => {
                    return Err(ex.kw_error(
                        CMD,
                        kw,
                        "OPTION",
                        format!("'{other}' is not computed here"),
                    ))
                }
            }
        }
    }
    if computed == 0 {
        if let Some(why) = refused {
            return Err(ex.unsupported(&why, at));
        }
    }
    store_result(ex, call, Concept::Result(Rc::new(out)))
}
