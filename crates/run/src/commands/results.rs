//! Results built field by field: CREA_RESU (AFFE, PREP_VARC).
//!
//! - `CREA_RESU(OPERATION='AFFE', TYPE_RESU='EVOL_ELAS'|'EVOL_NOLI')`
//!   (code_aster's `crtype`): each `AFFE` occurrence stores its field
//!   (`CHAM_GD`) under `NOM_CHAM` at each instant of `INST`/`LIST_INST`: at
//!   the NUME_ORDRE already holding that instant (within `PRECISION`,
//!   `CRITERE`), else at a new NUME_ORDRE after the largest (1 for a new
//!   result). `reuse=` with `RESULTAT` adds to a result.
//!
//! - `CREA_RESU(OPERATION='PREP_VARC', TYPE_RESU='EVOL_THER')`: the
//!   temperature through the thickness of shells (TEMP_MIL, TEMP_INF,
//!   TEMP_SUP) for `AFFE_VARC` (code_aster's `crvarc`, `te0408`).
//!
//! - `POST_CHAMP(EXTR_COQUE=_F(NOM_CHAM, NUME_COUCHE, NIVE_COUCHE))`: a
//!   new result whose `SIGM_ELNO`/`SIEF_ELNO` is the shells' stresses at one
//!   level through their thickness (`crate::shells::sigm_elno_at`), at the
//!   selected steps of a result where CALC_CHAMP computed that field;
//!   CALC_CHAMP's `SIGM_NOEU` on it averages that field at the nodes.
//!
//! - `POST_CHAMP(COQU_EXCENT=_F(NOM_CHAM='EFGE_ELNO'|'EFGE_ELGA',
//!   MODI_PLAN='OUI'), GROUP_MA|TOUT)`: the shells' efforts of a result,
//!   which code_aster gives about the cells' plane (the reference surface
//!   of an offset section, `EXCENTREMENT`), moved to the section's
//!   mid-surface: M − e·N (code_aster's `te0452` → `excent('MOY')`), on the
//!   selected cells (`GROUP_MA`, else all), at the selected steps.
//!
//! `RECU_TABLE` (both its `NOM_TABLE` and `NOM_PARA` forms) is in `tables`.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use std::rc::Rc;

/// What CREA_RESU builds (`crate::support`).
pub(crate) const CREA_RESU: Support = Support {
    keywords: &[
        "OPERATION",
        "TYPE_RESU",
        "RESULTAT",
        "AFFE",
        "AFFE/NOM_CHAM",
        "AFFE/CHAM_GD",
        "AFFE/INST",
        "AFFE/LIST_INST",
        "AFFE/PRECISION",
        "AFFE/CRITERE",
        "AFFE/MODELE",
        "AFFE/CHAM_MATER",
        "AFFE/CARA_ELEM",
        "AFFE/CHARGE",
        "PREP_VARC",
        "PREP_VARC/MODELE",
        "PREP_VARC/CARA_ELEM",
        "PREP_VARC/EVOL_THER",
    ],
    values: &[
        Values::new("OPERATION", &["AFFE", "PREP_VARC"]),
        Values::new("TYPE_RESU", &["EVOL_ELAS", "EVOL_NOLI", "EVOL_THER"]),
    ],
    hints: &[],
    reuse: true,
    rules: None,
};

pub fn crea_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    if kw.str("OPERATION") == Some("PREP_VARC") {
        return prep_varc(ex, call);
    }
    let typ = kw
        .str("TYPE_RESU")
        .unwrap_or("EVOL_ELAS")
        .to_ascii_lowercase();
    let mut result = match (&call.reuse, kw.concept("RESULTAT")) {
        (Some(r), _) | (None, Some(r)) => {
            let mut r = (*ex.result(r)?).clone();
            // A result changed by hand no longer matches what computed it.
            r.fem = None;
            r
        }
        (None, None) => EvolResult {
            prep_varc: false,
            typ,
            mesh: u32::MAX,
            steps: Vec::new(),
            fem: None,
            tables: Vec::new(),
            modal: None,
            cases: None,
            thermal: None,
        },
    };
    for occ in kw.factor("AFFE") {
        let name = occ.str("NOM_CHAM").unwrap_or("DEPL").to_string();
        let field_ref = ex.required("CREA_RESU", occ, "CHAM_GD")?;
        // A field of functions (NOEU_TEMP_F) is evaluated at each instant.
        let functions = match ex.concept(field_ref)? {
            Concept::FunctionField(f) => Some(f.clone()),
            _ => None,
        };
        let field = match &functions {
            Some(_) => crate::field::Field::Nodal(crate::field::NodalField::new(Vec::new())),
            None => (*ex.field(field_ref)?).clone(),
        };
        let mesh = match occ.concept("MODELE") {
            Some(m) => ex.model(m)?.mesh,
            None => ex.field_mesh_id(field_ref)?,
        };
        if result.mesh == u32::MAX {
            result.mesh = mesh;
        } else if result.mesh != mesh {
            return Err(ex.kw_error(
                "CREA_RESU",
                occ,
                "CHAM_GD",
                "the field is not on the mesh of the result",
            ));
        }
        let instants: Vec<f64> = match occ.concept("LIST_INST") {
            Some(l) => (*ex.real_list(l)?).clone(),
            None => occ
                .simple("INST")
                .iter()
                .filter_map(|s| s.as_f64())
                .collect(),
        };
        if instants.is_empty() {
            return Err(ExecError::new(
                "CREA_RESU/AFFE: give INST or LIST_INST (NUME_ORDRE ranges are not supported)",
            ));
        }
        let precision = occ.f64("PRECISION").unwrap_or(1e-6);
        let absolute = occ.str("CRITERE") == Some("ABSOLU");
        for t in instants {
            let field = match &functions {
                Some(f) => {
                    let mesh = ex.mesh_by_id(mesh)?;
                    crate::field::Field::Nodal(
                        eval_at(f, &mesh, t)
                            .map_err(|e| ex.kw_error("CREA_RESU", occ, "CHAM_GD", e))?,
                    )
                }
                None => field.clone(),
            };
            let at = result.step_at(t, precision, absolute).map(|s| s.nume_ordre);
            match at {
                Some(n) => {
                    if let Some(s) = result.steps.iter_mut().find(|s| s.nume_ordre == n) {
                        s.fields.insert(name.clone(), field.clone());
                    }
                }
                None => {
                    let n = result.steps.iter().map(|s| s.nume_ordre).max().unwrap_or(0) + 1;
                    let mut fields = crate::field::StepFields::new();
                    fields.insert(name.clone(), field.clone());
                    result.steps.push(Step {
                        nume_ordre: n,
                        inst: t,
                        fields,
                    });
                }
            }
        }
    }
    result.steps.sort_by_key(|s| s.nume_ordre);
    store_result(ex, call, Concept::Result(Rc::new(result)))
}

/// `CREA_RESU(OPERATION='PREP_VARC', TYPE_RESU='EVOL_THER',
/// PREP_VARC=_F(MODELE, CARA_ELEM, EVOL_THER))` (code_aster's `crvarc` →
/// option `PREP_VRC`, `te0408`): the temperature through the thickness of
/// the model's shells at every instant of an `evol_ther` holding TEMP_MIL,
/// TEMP_INF, TEMP_SUP. code_aster stores, per shell cell and sub-point
/// (3 per layer of `COQUE_NCOU`), the parabola through the cell's means of
/// the three at −h/2, 0, h/2; what its plates read of it (`dxefgt`,
/// `dxefnt`, `dxsith`) is that parabola, so the result keeps the nodal
/// TEMP_MIL, TEMP_INF, TEMP_SUP (TEMP_INF and TEMP_SUP default to TEMP_MIL,
/// `dxtpif`) and AFFE_VARC builds the parabola of each cell from them
/// (`crate::fembridge`). TEMP_MIL missing at a node of a shell cell is
/// code_aster's ELEMENTS_53, a CARA_ELEM of another model CALCULEL4_15, one
/// without shells CALCULEL4_14.
fn prep_varc(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "CREA_RESU";
    let kw = &call.keywords;
    let [occ] = kw.factor("PREP_VARC") else {
        return Err(ExecError::new(
            "CREA_RESU/PREP_VARC: one occurrence is required",
        ));
    };
    let model_ref = ex.required(CMD, occ, "MODELE")?;
    let model = ex.model(model_ref)?;
    let cara = ex.cara_elem(ex.required(CMD, occ, "CARA_ELEM")?)?;
    let evol_ref = ex.required(CMD, occ, "EVOL_THER")?;
    let evol = ex.result(evol_ref)?;
    if cara.model != model_ref.id {
        return Err(ex.kw_error(
            CMD,
            occ,
            "CARA_ELEM",
            "the CARA_ELEM was made for another model than MODELE (code_aster's CALCULEL4_15)",
        ));
    }
    let shells: Vec<aster_mesh::CellId> = model
        .cells
        .iter()
        .filter(|(_, m)| {
            matches!(
                m,
                crate::concept::Modelisation::Plate(_) | crate::concept::Modelisation::Coque3d
            )
        })
        .map(|(c, _)| *c)
        .collect();
    if shells.is_empty() || cara.shells.is_empty() {
        return Err(ex.kw_error(
            CMD,
            occ,
            "CARA_ELEM",
            "the CARA_ELEM has no shell (COQUE) section: PREP_VARC has nothing to do (code_aster's CALCULEL4_14)",
        ));
    }
    if evol.typ != "evol_ther" {
        return Err(ex.kw_error(CMD, occ, "EVOL_THER", "an evol_ther is expected"));
    }
    let mesh = ex.mesh_by_id(model.mesh)?;
    let comps = ["TEMP_MIL", "TEMP_INF", "TEMP_SUP"];
    let mut steps = Vec::new();
    for step in &evol.steps {
        let Some(field) = step.fields.get("TEMP") else {
            continue;
        };
        let crate::field::Field::Nodal(f) = field else {
            return Err(ex.kw_error(
                CMD,
                occ,
                "EVOL_THER",
                format!(
                    "the TEMP field at NUME_ORDRE {} is not a nodal field (NOEU_TEMP_R)",
                    step.nume_ordre
                ),
            ));
        };
        let mut out = crate::field::NodalField::new(comps.iter().map(|c| c.to_string()).collect());
        for &cell in &shells {
            for &node in &mesh.cell(cell).nodes {
                let Some(mil) = f.get(node, "TEMP_MIL") else {
                    return Err(ex.kw_error(
                        CMD,
                        occ,
                        "EVOL_THER",
                        format!(
                            "the TEMP field at NUME_ORDRE {} has no TEMP_MIL at node {} of shell cell {}: a shell's temperature is TEMP_MIL with TEMP_INF and TEMP_SUP (code_aster's ELEMENTS_53)",
                            step.nume_ordre,
                            mesh.node_name(node),
                            mesh.cell_name(cell)
                        ),
                    ));
                };
                let inf = f.get(node, "TEMP_INF").unwrap_or(mil);
                let sup = f.get(node, "TEMP_SUP").unwrap_or(mil);
                out.set(node, "TEMP_MIL", mil);
                out.set(node, "TEMP_INF", inf);
                out.set(node, "TEMP_SUP", sup);
            }
        }
        let mut fields = crate::field::StepFields::new();
        fields.insert("TEMP".into(), crate::field::Field::Nodal(out));
        steps.push(Step {
            nume_ordre: step.nume_ordre,
            inst: step.inst,
            fields,
        });
    }
    if steps.is_empty() {
        return Err(ex.kw_error(
            CMD,
            occ,
            "EVOL_THER",
            format!("`{}` holds no TEMP field", evol_ref.name),
        ));
    }
    let result = EvolResult {
        prep_varc: true,
        typ: "evol_ther".into(),
        mesh: model.mesh,
        steps,
        fem: None,
        tables: Vec::new(),
        modal: None,
        cases: None,
        thermal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(result)))
}

/// A field of functions evaluated at each of its nodes, at the node's
/// coordinates (`X`, `Y`, `Z`) and instant `INST`.
fn eval_at(
    f: &crate::concept::NodalFunctionField,
    mesh: &aster_mesh::Mesh,
    t: f64,
) -> Result<crate::field::NodalField, String> {
    let mut out = crate::field::NodalField::new(f.components.clone());
    for (&node, comps) in &f.values {
        let p = mesh.coord(node);
        for (c, func) in comps {
            let mut args: Vec<(&str, f64)> = Vec::new();
            for name in func.parameters() {
                let v = match name {
                    "X" => p[0],
                    "Y" => p[1],
                    "Z" => p[2],
                    "INST" => t,
                    other => {
                        return Err(format!(
                        "the function of component {c} depends on {other}: X, Y, Z and INST only"
                    ))
                    }
                };
                args.push((name, v));
            }
            let v = func.eval_named(&args).map_err(|e| e.to_string())?;
            out.set(node, c, v);
        }
    }
    Ok(out)
}

const POST_CHAMP_OWN: &[&str] = &[
    "RESULTAT",
    "TOUT",
    "GROUP_MA",
    "EXTR_COQUE",
    "EXTR_COQUE/NOM_CHAM",
    "EXTR_COQUE/NUME_COUCHE",
    "EXTR_COQUE/NIVE_COUCHE",
    "COQU_EXCENT",
    "COQU_EXCENT/NOM_CHAM",
    "COQU_EXCENT/MODI_PLAN",
];

/// What POST_CHAMP reads (`crate::support`): the shells' layer extraction
/// and the step selection ([`super::post::STEP_SELECTION`]).
pub(crate) const POST_CHAMP: Support = Support {
    keywords: &crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + POST_CHAMP_OWN.len() },
    >(super::post::STEP_SELECTION, POST_CHAMP_OWN),
    values: &[Values::new(
        "EXTR_COQUE/NOM_CHAM",
        &["SIGM_ELNO", "SIEF_ELNO"],
    )],
    hints: &[],
    reuse: false,
    rules: None,
};

pub fn post_champ(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let r = ex.required("POST_CHAMP", kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let excent = kw.factor("COQU_EXCENT");
    if !excent.is_empty() {
        let mesh = ex.mesh_by_id(result.mesh)?;
        let only = if kw.contains("GROUP_MA") {
            let cells = crate::select::cells(kw, &mesh, "")
                .map_err(|e| ExecError::new(format!("POST_CHAMP: {e}")))?;
            Some(cells.into_iter().collect::<std::collections::BTreeSet<_>>())
        } else {
            None
        };
        let names: Vec<String> = excent
            .iter()
            .filter_map(|occ| occ.str("NOM_CHAM").map(str::to_string))
            .collect();
        let steps = crate::commands::select_steps_pub(ex, "POST_CHAMP", kw, &result)?;
        let out =
            crate::fembridge::shell_efforts_to_mid_surface(&result, &names, &steps, only.as_ref())?;
        return store_result(ex, call, Concept::Result(Rc::new(out)));
    }
    if kw.contains("GROUP_MA") {
        return Err(ex.unsupported(
            "POST_CHAMP/GROUP_MA with EXTR_COQUE (the layer extraction covers every shell cell)",
            kw.keyword("GROUP_MA").map(|k| k.span).unwrap_or(call.span),
        ));
    }
    let extr = kw.factor("EXTR_COQUE");
    let Some(occ) = extr.first() else {
        return Err(ex.unsupported("POST_CHAMP other than EXTR_COQUE", call.span));
    };
    let names: Vec<String> = occ
        .simple("NOM_CHAM")
        .iter()
        .filter_map(|v| v.as_str().map(str::to_string))
        .collect();
    let layer = occ
        .first("NUME_COUCHE")
        .and_then(|v| v.as_i64())
        .filter(|&n| n >= 1 && n <= i64::from(u32::MAX))
        .ok_or_else(|| {
            ex.kw_error(
                "POST_CHAMP",
                occ,
                "NUME_COUCHE",
                "a layer number (>= 1) is required",
            )
        })? as u32;
    let position = match occ.str("NIVE_COUCHE") {
        Some("INF") => 0.0,
        Some("MOY") => 0.5,
        Some("SUP") => 1.0,
        _ => {
            return Err(ex.kw_error(
                "POST_CHAMP",
                occ,
                "NIVE_COUCHE",
                "NIVE_COUCHE is one of INF, MOY, SUP",
            ))
        }
    };
    let level = aster_fem::post::ShellLevel { layer, position };
    let steps = crate::commands::select_steps_pub(ex, "POST_CHAMP", kw, &result)?;
    let out = crate::fembridge::extract_shell_level(&result, &names, &steps, level)?;
    store_result(ex, call, Concept::Result(Rc::new(out)))
}
