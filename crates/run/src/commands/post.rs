//! CREA_CHAMP, POST_RELEVE_T, IMPR_TABLE, IMPR_RESU.

use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::select;
use crate::support::{Refusal, Support, Values};
use crate::table::{Column, ColumnType, Table, TableFormat, Value};
use aster_eval::{CommandCall, CommandOutput, ConceptRef, ExecError, Keywords};
use aster_mesh::NodeId;
use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::Arc;

/// Relative precision for matching instants (code_aster's default).
pub const INST_PRECISION: f64 = 1e-6;

/// The keywords [`select_steps`] reads: a command that designates steps
/// with them declares them in its `crate::support` table through
/// `crate::support::joined`.
pub(crate) const STEP_SELECTION: &[&str] = &[
    "TOUT_ORDRE",
    "NUME_ORDRE",
    // A mult_elas's load case (MACRO_ELAS_MULT).
    "NOM_CAS",
    "LIST_ORDRE",
    "INST",
    "LIST_INST",
    "PRECISION",
    "CRITERE",
];

/// The steps an occurrence designates (`NUME_ORDRE`, `LIST_ORDRE`, `INST`,
/// `LIST_INST`, `TOUT_ORDRE`, default: every step).
pub fn select_steps<'r>(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    result: &'r EvolResult,
) -> Result<Vec<&'r Step>, ExecError> {
    let absolute = occ.str("CRITERE") == Some("ABSOLU");
    let precision = occ
        .f64("PRECISION")
        .filter(|_| occ.contains("INST") || occ.contains("LIST_INST"))
        .unwrap_or(INST_PRECISION);
    let mut out = Vec::new();
    // LIST_INST (a DEFI_LIST_REEL) designates its instants as INST would.
    let listed: Option<Vec<f64>> = match occ.concept("LIST_INST") {
        Some(l) => Some((*ex.real_list(l)?).clone()),
        None => None,
    };
    let (inst_kw, instants) = match listed {
        Some(v) => ("LIST_INST", v),
        None => (
            "INST",
            occ.simple("INST")
                .iter()
                .filter_map(|s| s.as_f64())
                .collect(),
        ),
    };
    // LIST_ORDRE (a DEFI_LIST_ENTI) designates its numbers as NUME_ORDRE.
    let (order_kw, orders): (&str, Vec<i64>) = match occ.concept("LIST_ORDRE") {
        Some(l) => (
            "LIST_ORDRE",
            ex.real_list(l)?.iter().map(|&x| x.round() as i64).collect(),
        ),
        None => (
            "NUME_ORDRE",
            occ.simple("NUME_ORDRE")
                .iter()
                .filter_map(|s| s.as_i64())
                .collect(),
        ),
    };
    if result.cases.is_some() && (occ.contains("INST") || occ.contains("LIST_INST")) {
        // code_aster's mult_elas has no INST parameter.
        return Err(ex.kw_error(
            cmd,
            occ,
            inst_kw,
            "the result is a MACRO_ELAS_MULT's (mult_elas): its steps are named by NOM_CAS or NUME_ORDRE, it has no instant",
        ));
    }
    if occ.contains("NOM_CAS") {
        for name in occ.simple("NOM_CAS").iter().filter_map(|s| s.as_str()) {
            let order = result
                .case_named(name)
                .and_then(|o| result.step_numbered(o));
            out.push(order.ok_or_else(|| {
                let known: Vec<String> = result
                    .cases
                    .iter()
                    .flat_map(|c| c.cases.iter().map(|k| format!("'{}'", k.name)))
                    .collect();
                let msg = if result.cases.is_some() {
                    format!("the result has no load case '{name}' (its NOM_CAS: {})", known.join(", "))
                } else {
                    format!("'{name}': the result is not a MACRO_ELAS_MULT's (mult_elas), it has no NOM_CAS")
                };
                ex.kw_error(cmd, occ, "NOM_CAS", msg)
            })?);
        }
    } else if let (Some(info), true) = (&result.modal, occ.contains("NUME_MODE")) {
        // A mode_meca's NUME_MODE (the mode's rank in the spectrum).
        for n in occ.simple("NUME_MODE").iter().filter_map(|s| s.as_i64()) {
            let order = info
                .params
                .iter()
                .find(|(_, p)| p.get("NUME_MODE") == Some(&(n as f64)))
                .map(|(o, _)| *o);
            out.push(order.and_then(|o| result.step_numbered(o)).ok_or_else(|| {
                ex.kw_error(
                    cmd,
                    occ,
                    "NUME_MODE",
                    format!("the modes have no NUME_MODE {n}"),
                )
            })?);
        }
    } else if occ.contains("NUME_ORDRE") || occ.contains("LIST_ORDRE") {
        for n in orders {
            out.push(result.step_numbered(n as u32).ok_or_else(|| {
                ex.kw_error(
                    cmd,
                    occ,
                    order_kw,
                    format!(
                        "the result has no NUME_ORDRE {n} (it has 0 to {})",
                        result.steps.len().saturating_sub(1)
                    ),
                )
            })?);
        }
    } else if occ.contains("INST") || occ.contains("LIST_INST") {
        // Instants of a LIST_INST the result does not have are skipped, as
        // code_aster does (an alarm): a list often goes further than the
        // computation's INST_FIN. An instant asked with INST must exist.
        let from_list = inst_kw == "LIST_INST";
        let any = instants
            .iter()
            .any(|&t| result.step_at(t, precision, absolute).is_some());
        for t in instants {
            if from_list && any && result.step_at(t, precision, absolute).is_none() {
                continue;
            }
            out.push(result.step_at(t, precision, absolute).ok_or_else(|| {
                let insts: Vec<String> = result
                    .steps
                    .iter()
                    .map(|s| crate::pyfmt::py_repr(s.inst))
                    .collect();
                ex.kw_error(
                    cmd,
                    occ,
                    inst_kw,
                    format!(
                        "the result has no instant {t} (instants: {})",
                        insts.join(", ")
                    ),
                )
            })?);
        }
    } else {
        out.extend(result.steps.iter());
    }
    Ok(out)
}

/// A field of a result step, by name.
pub fn step_field<'s>(
    step: &'s Step,
    name: &str,
    result_name: &str,
) -> Result<&'s Field, ExecError> {
    step.fields.get(name).ok_or_else(|| {
        let have: Vec<&str> = step.fields.keys().map(String::as_str).collect();
        ExecError::new(format!(
            "result `{result_name}` has no field {name} at NUME_ORDRE {} (it has: {}){}",
            step.nume_ordre,
            have.join(", "),
            if name.ends_with("_NOEU")
                || name == "FORC_NODA"
                || name == "REAC_NODA"
                || name.ends_with("_ELNO")
            {
                "; compute it first with CALC_CHAMP"
            } else {
                ""
            }
        ))
    })
}

/// What CREA_CHAMP reads (`crate::support`).
pub(crate) const CREA_CHAMP: Support = Support {
    values: &[Values::listed(
        "OPERATION",
        &["EXTR", "COMB", "ASSE", "AFFE", "EVAL", "NORMALE", "DISC"],
    )],
    rules: Some(super::crea_champ_elga::rules),
    ..Support::keywords(CREA_CHAMP_KEYWORDS)
};

const CREA_CHAMP_KEYWORDS: &[&str] = &[
    "TYPE_CHAM",
    "PROL_ZERO",
    "CHAM_GD",
    "OPERATION",
    "GROUP_MA",
    "MAILLE",
    "RESULTAT",
    "NOM_CHAM",
    "INST",
    "NUME_ORDRE",
    "NOM_CAS",
    "PRECISION",
    "CRITERE",
    "INFO",
    "TITRE",
    "MAILLAGE",
    "MODELE",
    "COMB",
    "COMB/CHAM_GD",
    "COMB/COEF_R",
    "ASSE",
    "ASSE/TOUT",
    "ASSE/GROUP_NO",
    "ASSE/GROUP_MA",
    "ASSE/CHAM_GD",
    "ASSE/NOM_CMP",
    "ASSE/COEF_R",
    "ASSE/CUMUL",
    "AFFE",
    "AFFE/TOUT",
    "AFFE/GROUP_NO",
    "AFFE/NOEUD",
    "AFFE/GROUP_MA",
    "AFFE/MAILLE",
    "AFFE/NOM_CMP",
    "AFFE/VALE",
    "AFFE/VALE_F",
    "ASSE/NOM_CMP_RESU",
    "CHAM_F",
    "CHAM_PARA",
];

pub fn crea_champ(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let op = kw.str("OPERATION").unwrap_or("");
    let mut origin = None;
    // The mesh of the new field, when the command tells it.
    let mesh_id = crea_champ_mesh(ex, kw)?;
    let id = crate::executor::result_of(call)?.id;
    match mesh_id {
        Some(m) => ex.field_meshes.insert(id, m),
        None => ex.field_meshes.remove(&id),
    };
    let ty = kw.str("TYPE_CHAM").unwrap_or("");
    match ty.get(5..) {
        Some(q) => ex.field_quantity.insert(id, q.to_string()),
        None => ex.field_quantity.remove(&id),
    };
    let gauss = ty.starts_with("ELGA_");
    if op == "AFFE" && ty.ends_with("_F") {
        if gauss {
            let f = super::crea_champ_elga::affe_functions(ex, call)?;
            return store_result(ex, call, Concept::GaussFunctionField(Rc::new(f)));
        }
        let f = crea_champ_affe_functions(ex, call)?;
        return store_result(ex, call, Concept::FunctionField(Rc::new(f)));
    }
    let field = match op {
        "EXTR" if kw.str("NOM_CHAM") == Some("GEOMETRIE") && !kw.contains("RESULTAT") => {
            // The coordinates of the mesh's nodes (NOEU_GEOM_R: X, Y, Z).
            let mesh = ex.mesh(ex.required("CREA_CHAMP", kw, "MAILLAGE")?)?;
            let mut f = NodalField::new(vec!["X".into(), "Y".into(), "Z".into()]);
            for (i, c) in mesh.coords.iter().enumerate() {
                let n = aster_mesh::NodeId(i as u32);
                for (k, name) in ["X", "Y", "Z"].iter().enumerate() {
                    f.set(n, name, c[k]);
                }
            }
            Field::Nodal(f)
        }
        "EVAL" => {
            let f_ref = ex.required("CREA_CHAMP", kw, "CHAM_F")?;
            match ex.concept(f_ref)? {
                Concept::GaussFunctionField(f) => {
                    let f = f.clone();
                    Field::Elem(super::crea_champ_elga::eval(ex, call, &f)?)
                }
                _ => Field::Nodal(crea_champ_eval(ex, call)?),
            }
        }
        "DISC" => Field::Elem(super::crea_champ_elga::disc(ex, call)?),
        "ASSE" if gauss => Field::Elem(super::crea_champ_elga::asse(ex, call)?),
        "EXTR" => {
            let r = ex.required("CREA_CHAMP", kw, "RESULTAT")?;
            let result = ex.result(r)?;
            let name = kw
                .str("NOM_CHAM")
                .ok_or_else(|| ExecError::new("CREA_CHAMP/EXTR: NOM_CHAM is required"))?;
            let steps = select_steps(ex, "CREA_CHAMP", kw, &result)?;
            let step = match steps.as_slice() {
                [s] => *s,
                _ => {
                    return Err(ExecError::new(
                        "CREA_CHAMP/EXTR: give exactly one INST or NUME_ORDRE",
                    ))
                }
            };
            origin = Some((result.clone(), step.nume_ordre));
            step_field(step, name, &r.name)?.clone()
        }
        "COMB" => {
            let mut acc: Option<NodalField> = None;
            for occ in kw.factor("COMB") {
                let c = ex.required("CREA_CHAMP/COMB", occ, "CHAM_GD")?;
                let coef = occ.f64("COEF_R").unwrap_or(1.0);
                let Field::Nodal(f) = &*ex.field(c)? else {
                    return Err(ex.unsupported("CREA_CHAMP/COMB of element fields", call.span));
                };
                let acc = acc.get_or_insert_with(|| NodalField::new(f.components().to_vec()));
                for (node, vals) in f.iter() {
                    for (i, v) in vals.iter().enumerate() {
                        if let Some(v) = v {
                            let cur = acc.get(node, &f.components()[i]).unwrap_or(0.0);
                            acc.set(node, &f.components()[i], cur + coef * v);
                        }
                    }
                }
            }
            Field::Nodal(acc.ok_or_else(|| ExecError::new("CREA_CHAMP/COMB: no field to combine"))?)
        }
        "ASSE" => {
            let mut acc: Option<NodalField> = None;
            for occ in kw.factor("ASSE") {
                let c = ex.required("CREA_CHAMP/ASSE", occ, "CHAM_GD")?;
                let src = ex.field(c)?;
                let Field::Nodal(f) = &*src else {
                    return Err(ex.unsupported("CREA_CHAMP/ASSE of element fields", call.span));
                };
                let mesh_nodes = if occ.str("TOUT") == Some("OUI") {
                    None
                } else {
                    // Fields do not carry their mesh: take it from MAILLAGE/MODELE.
                    let mesh = if let Some(m) = kw.concept("MAILLAGE") {
                        ex.mesh(m)?
                    } else if let Some(m) = kw.concept("MODELE") {
                        ex.mesh_by_id(ex.model(m)?.mesh)?
                    } else {
                        return Err(ExecError::new(
                            "CREA_CHAMP/ASSE: give MAILLAGE or MODELE to select nodes",
                        ));
                    };
                    Some(
                        select::nodes(occ, &mesh, "")
                            .map_err(|e| ExecError::new(format!("CREA_CHAMP/ASSE: {e}")))?,
                    )
                };
                let cmps: Vec<String> = occ
                    .simple("NOM_CMP")
                    .iter()
                    .filter_map(|s| s.as_str().map(str::to_string))
                    .collect();
                // NOM_CMP_RESU: the i-th component is stored under the i-th name.
                let renamed: Vec<String> = occ
                    .simple("NOM_CMP_RESU")
                    .iter()
                    .filter_map(|s| s.as_str().map(str::to_string))
                    .collect();
                if !renamed.is_empty() && renamed.len() != cmps.len() {
                    return Err(ex.kw_error(
                        "CREA_CHAMP/ASSE",
                        occ,
                        "NOM_CMP_RESU",
                        format!(
                            "{} names for the {} components of NOM_CMP: give one per component",
                            renamed.len(),
                            cmps.len()
                        ),
                    ));
                }
                let target = |name: &String| -> String {
                    match cmps.iter().position(|c| c == name) {
                        Some(i) if !renamed.is_empty() => renamed[i].clone(),
                        _ => name.clone(),
                    }
                };
                let coef = occ.f64("COEF_R").unwrap_or(1.0);
                let cumul = occ.str("CUMUL") == Some("OUI");
                let acc = acc.get_or_insert_with(|| NodalField::new(Vec::new()));
                for (node, vals) in f.iter() {
                    if let Some(sel) = &mesh_nodes {
                        if !sel.contains(&node) {
                            continue;
                        }
                    }
                    for (i, v) in vals.iter().enumerate() {
                        let name = &f.components()[i];
                        if !cmps.is_empty() && !cmps.contains(name) {
                            continue;
                        }
                        if let Some(v) = v {
                            let out = target(name);
                            let base = if cumul {
                                acc.get(node, &out).unwrap_or(0.0)
                            } else {
                                0.0
                            };
                            acc.set(node, &out, base + coef * v);
                        }
                    }
                }
            }
            Field::Nodal(
                acc.ok_or_else(|| ExecError::new("CREA_CHAMP/ASSE: no field to assemble"))?,
            )
        }
        "AFFE" => Field::Nodal(crea_champ_affe(ex, call)?),
        "NORMALE" => Field::Nodal(crea_champ_normale(ex, call)?),
        other => {
            let span = kw.keyword("OPERATION").map(|k| k.span).unwrap_or(call.span);
            return Err(ex.unsupported(&format!("CREA_CHAMP/OPERATION='{other}'"), span));
        }
    };
    match origin {
        Some(o) => ex.field_origin.insert(id, o),
        None => ex.field_origin.remove(&id),
    };
    store_result(ex, call, Concept::Field(Rc::new(field)))
}

/// `CREA_CHAMP(OPERATION='NORMALE')` (code_aster's `cnonor`): the unit
/// normal (`NOEU_GEOM_R`: X, Y[, Z]) at the nodes of the boundary cells of
/// `GROUP_MA`/`MAILLE`, on the mesh's current coordinates (`canort`: the
/// normalised sum of each cell's unit normal at the node).
fn crea_champ_normale(ex: &Executor, call: &CommandCall) -> Result<NodalField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/NORMALE";
    if kw.str("TYPE_CHAM") != Some("NOEU_GEOM_R") {
        return Err(ex.kw_error(cmd, kw, "TYPE_CHAM", "the normal is a NOEU_GEOM_R field"));
    }
    let model = ex.model(ex.required(cmd, kw, "MODELE")?)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let cells = select::cells(kw, &mesh, "").map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
    let normals = super::pressure::nodal_normals(&mesh, &cells, &|n| mesh.coord(n))
        .map_err(|e| ExecError::new(format!("{cmd}: {}", e.message)))?;
    let names: &[&str] = if mesh.dim == 3 {
        &["X", "Y", "Z"]
    } else {
        &["X", "Y"]
    };
    let mut out = NodalField::new(names.iter().map(|s| s.to_string()).collect());
    for (node, n) in normals {
        for (d, c) in names.iter().enumerate() {
            out.set(node, c, n[d]);
        }
    }
    Ok(out)
}

/// `CREA_CHAMP(OPERATION='AFFE')` of a nodal field of reals (`NOEU_*_R`):
/// constant values per component on the nodes of each occurrence (later
/// occurrences overwrite earlier ones, as in code_aster).
fn crea_champ_affe(ex: &Executor, call: &CommandCall) -> Result<NodalField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/AFFE";
    let ty = kw.str("TYPE_CHAM").unwrap_or("");
    if !(ty.starts_with("NOEU_") && ty.ends_with("_R")) {
        let span = kw.keyword("TYPE_CHAM").map(|k| k.span).unwrap_or(call.span);
        return Err(ex.unsupported(
            &format!("CREA_CHAMP/OPERATION='AFFE' with TYPE_CHAM='{ty}' (nodal fields of reals, NOEU_*_R, only)"),
            span,
        ));
    }
    let (mesh, model_nodes) = if let Some(m) = kw.concept("MODELE") {
        let model = ex.model(m)?;
        let mesh = ex.mesh_by_id(model.mesh)?;
        let carried = super::loads::carried_nodes(&model, &mesh);
        (mesh, Some(carried))
    } else if let Some(m) = kw.concept("MAILLAGE") {
        (ex.mesh(m)?, None)
    } else {
        return Err(ExecError::new("CREA_CHAMP/AFFE: give MAILLAGE or MODELE"));
    };
    let mut field = NodalField::new(Vec::new());
    for occ in kw.factor("AFFE") {
        let cmps: Vec<&str> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let vals: Vec<f64> = occ
            .simple("VALE")
            .iter()
            .filter_map(|s| s.as_f64())
            .collect();
        if cmps.len() != vals.len() {
            return Err(ex.kw_error(
                cmd,
                occ,
                "VALE",
                format!(
                    "{} values for {} components in NOM_CMP: give one per component",
                    vals.len(),
                    cmps.len()
                ),
            ));
        }
        let mut nodes =
            select::nodes(occ, &mesh, "").map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
        if let Some(carried) = &model_nodes {
            nodes.retain(|n| carried[n.0 as usize]);
        }
        for n in nodes {
            for (c, v) in cmps.iter().zip(&vals) {
                field.set(n, c, *v);
            }
        }
    }
    Ok(field)
}

/// The mesh (id) a CREA_CHAMP's field lives on: `MAILLAGE`, `MODELE`'s,
/// the result's (EXTR), or that of the first field it is made from.
fn crea_champ_mesh(ex: &Executor, kw: &Keywords) -> Result<Option<u32>, ExecError> {
    if let Some(m) = kw.concept("MAILLAGE") {
        return Ok(Some(m.id));
    }
    if let Some(m) = kw.concept("MODELE") {
        return Ok(Some(ex.model(m)?.mesh));
    }
    if let Some(r) = kw.concept("RESULTAT") {
        return Ok(Some(ex.result(r)?.mesh));
    }
    let sources = kw
        .factor("COMB")
        .iter()
        .chain(kw.factor("ASSE"))
        .filter_map(|o| o.concept("CHAM_GD"))
        .chain(kw.concept("CHAM_F"));
    for f in sources {
        if let Some(&m) = ex.field_meshes.get(&f.id) {
            return Ok(Some(m));
        }
        if let Some((r, _)) = ex.field_origin.get(&f.id) {
            return Ok(Some(r.mesh));
        }
    }
    Ok(None)
}

/// `CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_*_F')`: a function per
/// component on the nodes of each occurrence (`VALE_F`).
fn crea_champ_affe_functions(
    ex: &Executor,
    call: &CommandCall,
) -> Result<NodalFunctionField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/AFFE";
    let ty = kw.str("TYPE_CHAM").unwrap_or("");
    if !ty.starts_with("NOEU_") {
        let span = kw.keyword("TYPE_CHAM").map(|k| k.span).unwrap_or(call.span);
        return Err(ex.unsupported(
            &format!("CREA_CHAMP/OPERATION='AFFE' with TYPE_CHAM='{ty}' (nodal fields of functions, NOEU_*_F, only)"),
            span,
        ));
    }
    let mesh = if let Some(m) = kw.concept("MODELE") {
        ex.mesh_by_id(ex.model(m)?.mesh)?
    } else {
        ex.mesh(ex.required("CREA_CHAMP", kw, "MAILLAGE")?)?
    };
    let mut field = NodalFunctionField::default();
    for occ in kw.factor("AFFE") {
        let (cmps, functions) = affe_functions(ex, cmd, occ)?;
        let nodes =
            select::nodes(occ, &mesh, "").map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
        for c in &cmps {
            if !field.components.iter().any(|k| k == c) {
                field.components.push(c.to_string());
            }
        }
        for n in nodes {
            let slot = field.values.entry(n).or_default();
            for (c, f) in cmps.iter().zip(&functions) {
                slot.insert(c.to_string(), f.clone());
            }
        }
    }
    Ok(field)
}

/// An `AFFE` occurrence of a field of functions: its `NOM_CMP` and one
/// `VALE_F` function per component.
pub(crate) fn affe_functions(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
) -> Result<(Vec<String>, Vec<Rc<crate::function::Function>>), ExecError> {
    let cmps: Vec<String> = occ
        .simple("NOM_CMP")
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect();
    let mut functions = Vec::new();
    for s in occ.simple("VALE_F") {
        let Some(c) = s.as_concept() else {
            return Err(ex.kw_error(cmd, occ, "VALE_F", "a function is required"));
        };
        functions.push(ex.function(c)?);
    }
    if cmps.len() != functions.len() {
        return Err(ex.kw_error(
            cmd,
            occ,
            "VALE_F",
            format!(
                "{} functions for {} components in NOM_CMP: give one per component",
                functions.len(),
                cmps.len()
            ),
        ));
    }
    Ok((cmps, functions))
}

/// `CREA_CHAMP(OPERATION='EVAL')`: each function of `CHAM_F` evaluated at
/// each of its nodes, its parameters (`X`, `Y`, `Z`, …) read by name among
/// the components of the `CHAM_PARA` fields at that node.
fn crea_champ_eval(ex: &Executor, call: &CommandCall) -> Result<NodalField, ExecError> {
    let kw = &call.keywords;
    let f_ref = ex.required("CREA_CHAMP", kw, "CHAM_F")?;
    let Concept::FunctionField(functions) = ex.concept(f_ref)? else {
        return Err(ex.kw_error(
            "CREA_CHAMP",
            kw,
            "CHAM_F",
            "a field of functions (CREA_CHAMP AFFE with TYPE_CHAM='NOEU_*_F') is required",
        ));
    };
    let functions = functions.clone();
    let mut params = Vec::new();
    for s in kw.simple("CHAM_PARA") {
        let Some(c) = s.as_concept() else { continue };
        match &*ex.field(c)? {
            Field::Nodal(f) => params.push(f.clone()),
            Field::Elem(_) => {
                return Err(ex.unsupported(
                    "CREA_CHAMP/EVAL with an element field in CHAM_PARA",
                    kw.keyword("CHAM_PARA").map(|k| k.span).unwrap_or(call.span),
                ))
            }
        }
    }
    let mut out = NodalField::new(functions.components.clone());
    for (&node, comps) in &functions.values {
        for (c, f) in comps {
            let mut args: Vec<(&str, f64)> = Vec::new();
            for p in f.parameters() {
                let v = params
                    .iter()
                    .find_map(|field| field.get(node, p))
                    .ok_or_else(|| {
                        ex.kw_error(
                            "CREA_CHAMP",
                            kw,
                            "CHAM_PARA",
                            format!("no field of CHAM_PARA gives {p} at a node of CHAM_F"),
                        )
                    })?;
                args.push((p, v));
            }
            let v = f
                .eval_named(&args)
                .map_err(|e| ExecError::new(format!("CREA_CHAMP/EVAL: {e}")))?;
            out.set(node, c, v);
        }
    }
    Ok(out)
}

/// A node's frame in the plane (x, y): (v₁, v₂).
type Frame = ([f64; 2], [f64; 2]);

/// The polar frame of each node (`REPERE='POLAIRE'`, code_aster's
/// `rvrthe` and `rvcalq`): with r the distance of the node to the z axis,
/// v₁ = (x, y)/r and v₂ = (y, −x)/r (the opposite of the tangent rvrthe
/// gives; (1, 0) and (0, −1) when r < 1e-6).
fn polar_frame(x: [f64; 3]) -> Frame {
    let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
    if r.abs() < 1e-6 {
        ([1.0, 0.0], [0.0, -1.0])
    } else {
        ([x[0] / r, x[1] / r], [x[1] / r, -x[0] / r])
    }
}

/// The local frame of a path of nodes (`REPERE='LOCAL'` without VECT_Y,
/// code_aster's `rvrlln`): at each node v₁ is the unit tangent
/// t = (x₍ᵢ₊₁₎ − xᵢ)/|x₍ᵢ₊₁₎ − xᵢ| of the segment leaving it (the mean of
/// the two unit tangents, not renormalised, at an interior node; the
/// arriving segment's at the last node) and v₂ = (−t_y, t_x) in the plane
/// (x, y). `None` for a path of fewer than two nodes or with two
/// consecutive nodes at the same place (code_aster divides by zero).
fn local_path_frames(points: &[[f64; 3]]) -> Option<Vec<Frame>> {
    if points.len() < 2 {
        return None;
    }
    let mut tangents = Vec::with_capacity(points.len() - 1);
    for w in points.windows(2) {
        let d = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if l == 0.0 {
            return None;
        }
        // rvrlln: l = 1/|d| then t = d·l (the z part is dropped).
        let inv = 1.0 / l;
        tangents.push([d[0] * inv, d[1] * inv]);
    }
    // rvrlln averages the normals too: the normal of the mean tangent.
    let normal = |t: [f64; 2]| [-t[1], t[0]];
    let n = points.len();
    Some(
        (0..n)
            .map(|i| {
                let t = if i == 0 {
                    tangents[0]
                } else if i + 1 < n {
                    let (a, b) = (tangents[i], tangents[i - 1]);
                    [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
                } else {
                    tangents[i - 1]
                };
                (t, normal(t))
            })
            .collect(),
    )
}

/// A nodal field's vectors (DX, DY) and stress tensors (SIXX…SIYZ) in a
/// frame (v₁, v₂) given at each node (code_aster's `rvcalq`):
/// DX' = v₁·u, DY' = v₂·u; SIXX' = v₁·σ·v₁, SIYY' = v₂·σ·v₂,
/// SIXY' = v₁·σ·v₂, SIXZ' = v₁·(σxz, σyz), SIYZ' = v₂·(σxz, σyz); z
/// components and the others unchanged. A missing component counts as 0.
/// Nodes without a frame are left as they are.
fn frame_components(f: &NodalField, frame: impl Fn(NodeId) -> Option<Frame>) -> NodalField {
    let mut out = f.clone();
    let idx = |c: &str| f.component_index(c);
    let vector = (idx("DX"), idx("DY"));
    let tensor = ["SIXX", "SIYY", "SIXY", "SIXZ", "SIYZ"].map(idx);
    for (node, orig) in f.iter() {
        let Some((v1, v2)) = frame(node) else {
            continue;
        };
        let get = |i: Option<usize>| i.and_then(|i| orig.get(i)).unwrap_or(0.0);
        if let (Some(ix), Some(iy)) = vector {
            let u = [get(Some(ix)), get(Some(iy))];
            out.set_at(node, ix, Some(v1[0] * u[0] + v1[1] * u[1]));
            out.set_at(node, iy, Some(v2[0] * u[0] + v2[1] * u[1]));
        }
        if tensor[0].is_some() && tensor[1].is_some() {
            let [sxx, syy, sxy, sxz, syz] = tensor.map(get);
            let quad = |a: [f64; 2], b: [f64; 2]| {
                a[0] * (b[0] * sxx + b[1] * sxy) + a[1] * (b[0] * sxy + b[1] * syy)
            };
            let rotated = [
                quad(v1, v1),
                quad(v2, v2),
                quad(v1, v2),
                v1[0] * sxz + v1[1] * syz,
                v2[0] * sxz + v2[1] * syz,
            ];
            for (i, v) in tensor.iter().zip(rotated) {
                if let Some(i) = i {
                    out.set_at(node, *i, Some(v));
                }
            }
        }
    }
    out
}

pub(crate) fn table_title(name: &str) -> Vec<String> {
    vec![
        format!(
            "ASTER {} CONCEPT {name} CALCULE PAR aster DE TYPE",
            env!("CARGO_PKG_VERSION")
        ),
        "TABLE_SDASTER".to_string(),
    ]
}

/// A field to extract from: (result name, field name, (NUME_ORDRE, INST), field).
type Source = (Option<String>, Option<String>, Option<(u32, f64)>, Field);

/// What POST_RELEVE_T reads (`crate::support`).
pub(crate) const POST_RELEVE_T: Support = Support {
    values: &[
        Values::new("ACTION/REPERE", &["GLOBAL", "POLAIRE", "LOCAL"]),
        Values::new("ACTION/MOYE_NOEUD", &["OUI"]),
        Values::new(
            "ACTION/OPERATION",
            &["EXTRACTION", "MOYENNE", "MOYENNE_ARITH"],
        ),
    ],
    rules: Some(post_releve_t_rules),
    ..Support::keywords(&[
        "ACTION",
        "ACTION/OPERATION",
        "ACTION/INTITULE",
        "ACTION/RESULTAT",
        "ACTION/CHAM_GD",
        "ACTION/NOM_CHAM",
        "ACTION/INST",
        "ACTION/LIST_INST",
        "ACTION/NUME_ORDRE",
        "ACTION/NOM_CAS",
        "ACTION/LIST_ORDRE",
        "ACTION/TOUT_ORDRE",
        "ACTION/CRITERE",
        "ACTION/PRECISION",
        "ACTION/GROUP_NO",
        "ACTION/NOEUD",
        "ACTION/GROUP_MA",
        "ACTION/MAILLE",
        "ACTION/TOUT",
        "ACTION/TOUT_CMP",
        "ACTION/NOM_CMP",
        "ACTION/RESULTANTE",
        "ACTION/REPERE",
        "ACTION/MOYE_NOEUD",
        "INFO",
        "TITRE",
    ])
};

/// One operation per ACTION occurrence (code_aster accepts
/// `('EXTRACTION', 'MOYENNE')` together: not handled).
fn post_releve_t_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    for occ in call.keywords.factor("ACTION") {
        if occ.simple("OPERATION").len() > 1 {
            out.push(Refusal::at(
                "POST_RELEVE_T/ACTION/OPERATION with several operations in one occurrence (give one ACTION per operation)".into(),
                occ,
                "OPERATION",
                call.span,
            ));
        }
        if occ.str("OPERATION") == Some("MOYENNE") {
            for key in ["RESULTANTE", "REPERE"] {
                if occ.keyword(key).is_some_and(|k| !k.defaulted) {
                    out.push(Refusal::at(
                        format!("POST_RELEVE_T/ACTION/{key} with OPERATION='MOYENNE'"),
                        occ,
                        key,
                        call.span,
                    ));
                }
            }
        }
    }
}

/// code_aster's `rvpstm`: the six quantities OPERATION='MOYENNE' gives for
/// one component along a path of nodes with abscissae `absc`, from the
/// values at the nodes (`None` where the node has no value: its segments
/// are skipped). MOMENT_0 is the mean by the trapezoidal rule, MOMENT_1
/// the linear moment 6·(∫v·s ds / L² − MOMENT_0) by Simpson's rule,
/// MOYE_INT/MOYE_EXT = MOMENT_0 ∓ MOMENT_1/2; MINIMUM/MAXIMUM over the
/// ends of the segments counted.
fn path_moments(absc: &[f64], values: &[Option<f64>]) -> [f64; 6] {
    let (mut m1, mut m2, mut xl) = (0.0, 0.0, 0.0);
    let (mut mi, mut ma) = (1.0e50_f64, -1.0e50_f64);
    for k in 0..absc.len().saturating_sub(1) {
        let (Some(t1), Some(t2)) = (values[k], values[k + 1]) else {
            continue;
        };
        let s1 = absc[k] - absc[0];
        let s2 = absc[k + 1] - absc[0];
        let s12 = s2 - s1;
        xl += s12;
        let t12 = (t1 + t2) / 2.0;
        let smil = (s1 + s2) / 2.0;
        m1 += s12 * (t1 + t2);
        m2 += s12 / 3.0 * (t1 * s1 + 4.0 * t12 * smil + t2 * s2);
        ma = ma.max(t1).max(t2);
        mi = mi.min(t1).min(t2);
    }
    m1 /= xl;
    m2 /= xl * xl;
    m1 *= 0.5;
    m2 = 6.0 * (m2 - m1);
    [m1, m2, mi, ma, m1 - 0.5 * m2, m1 + 0.5 * m2]
}

/// The QUANTITE of each row of [`path_moments`], in code_aster's order.
const PATH_QUANTITIES: [&str; 6] = [
    "MOMENT_0", "MOMENT_1", "MINIMUM", "MAXIMUM", "MOYE_INT", "MOYE_EXT",
];

pub fn post_releve_t(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let name = crate::executor::result_of(call)?.name.clone();
    let mut table = Table::new(vec![
        Column {
            name: "INTITULE".into(),
            ty: ColumnType::Text(16),
        },
        Column {
            name: "RESU".into(),
            ty: ColumnType::Text(8),
        },
        Column {
            name: "NOM_CHAM".into(),
            ty: ColumnType::Text(16),
        },
        Column {
            name: "NUME_ORDRE".into(),
            ty: ColumnType::Int,
        },
        Column {
            name: "INST".into(),
            ty: ColumnType::Real,
        },
        Column {
            name: "NOEUD".into(),
            ty: ColumnType::Text(8),
        },
        Column {
            name: "ABSC_CURV".into(),
            ty: ColumnType::Real,
        },
        Column {
            name: "COOR_X".into(),
            ty: ColumnType::Real,
        },
        Column {
            name: "COOR_Y".into(),
            ty: ColumnType::Real,
        },
    ]);
    table.title = table_title(&name);
    // The load cases of the mult_elas results read (`name_load_cases`).
    let mut cases: BTreeMap<(String, u32), String> = BTreeMap::new();
    for occ in kw.factor("ACTION") {
        let ops: Vec<&str> = occ
            .simple("OPERATION")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let (moyenne, arith) = match ops.as_slice() {
            ["EXTRACTION"] => (false, false),
            ["MOYENNE"] => (true, false),
            ["MOYENNE_ARITH"] => (false, true),
            _ => {
                let span = occ
                    .keyword("OPERATION")
                    .map(|k| k.span)
                    .unwrap_or(call.span);
                return Err(ex.unsupported(
                    &format!(
                        "POST_RELEVE_T/ACTION/OPERATION={ops:?} (one of 'EXTRACTION', 'MOYENNE', 'MOYENNE_ARITH')"
                    ),
                    span,
                ));
            }
        };
        let title = occ.str("INTITULE").unwrap_or("").to_string();
        let mut sources: Vec<Source> = Vec::new();
        let mesh;
        if let Some(r) = occ.concept("RESULTAT") {
            let result = ex.result(r)?;
            mesh = ex.mesh_by_id(result.mesh)?;
            let field_name = occ.str("NOM_CHAM").ok_or_else(|| {
                ExecError::new("POST_RELEVE_T/ACTION: NOM_CHAM is required with RESULTAT")
            })?;
            let steps = select_steps(ex, "POST_RELEVE_T/ACTION", occ, &result)?;
            // A step without the field gives no row (code_aster's `rvgchf`:
            // alarm POSTRELE_41), e.g. CALC_PRESSION at one INST of the
            // result; a field no selected step has stays an error.
            let any = steps.iter().any(|s| s.fields.contains_key(field_name));
            for step in steps {
                if any && !step.fields.contains_key(field_name) {
                    continue;
                }
                if let Some(name) = result.case_name(step.nume_ordre) {
                    cases.insert((r.name.clone(), step.nume_ordre), name.to_string());
                }
                let f = step_field(step, field_name, &r.name)?.clone();
                sources.push((
                    Some(r.name.clone()),
                    Some(field_name.to_string()),
                    Some((step.nume_ordre, step.inst)),
                    f,
                ));
            }
        } else if let Some(c) = occ.concept("CHAM_GD") {
            let f = ex.field(c)?;
            let m = occ_mesh(ex, c)?;
            mesh = m;
            sources.push((None, None, None, (*f).clone()));
        } else {
            return Err(ExecError::new(
                "POST_RELEVE_T/ACTION: give RESULTAT or CHAM_GD",
            ));
        }
        if mesh.dim == 3 {
            table.ensure_column("COOR_Z", ColumnType::Real);
        }
        let nodes = select::nodes(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("POST_RELEVE_T/ACTION: {e}")))?;
        if arith {
            let chamgd = occ.concept("CHAM_GD").map(|c| c.name.clone());
            arith_mean_rows(ex, &mut table, occ, &title, chamgd, &sources, &mesh, &nodes)?;
            continue;
        }
        let resultant: Vec<String> = occ
            .simple("RESULTANTE")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        let polar = occ.str("REPERE") == Some("POLAIRE");
        let local = if occ.str("REPERE") == Some("LOCAL") {
            Some(local_frames(
                ex,
                occ,
                &mesh,
                &nodes,
                !resultant.is_empty(),
                call.span,
            )?)
        } else {
            None
        };
        if polar {
            // code_aster (rvchgr) needs a plane mesh: every z equal (to 1e-3,
            // relatively, of the first node's).
            let z0 = mesh.coords.first().map_or(0.0, |c| c[2]);
            if mesh
                .coords
                .iter()
                .any(|c| (c[2] - z0).abs() > 1e-3 * z0.abs().max(1.0))
            {
                return Err(ex.kw_error(
                    "POST_RELEVE_T/ACTION",
                    occ,
                    "REPERE",
                    "REPERE='POLAIRE' needs a plane mesh (z constant)",
                ));
            }
            if !resultant.is_empty() {
                let span = occ.keyword("REPERE").map(|k| k.span).unwrap_or(call.span);
                return Err(ex.unsupported(
                    "POST_RELEVE_T/ACTION/RESULTANTE with REPERE='POLAIRE'",
                    span,
                ));
            }
        }
        if !resultant.is_empty() {
            // One row per instant: the sums of the components over the nodes.
            for (resu, cham, order, field) in &sources {
                let Field::Nodal(f) = field else {
                    return Err(ex.unsupported(
                        "POST_RELEVE_T/ACTION/RESULTANTE of element fields",
                        call.span,
                    ));
                };
                let mut row: Vec<(String, Value)> =
                    vec![("INTITULE".into(), Value::Text(title.clone()))];
                if let Some(r) = resu {
                    row.push(("RESU".into(), Value::Text(r.clone())));
                }
                if let Some(c) = cham {
                    row.push(("NOM_CHAM".into(), Value::Text(c.clone())));
                }
                if let Some((no, t)) = order {
                    row.push(("NUME_ORDRE".into(), Value::Int(*no as i64)));
                    row.push(("INST".into(), Value::Real(*t)));
                }
                for c in &resultant {
                    if f.component_index(c).is_none() {
                        return Err(ExecError::new(format!(
                            "POST_RELEVE_T/ACTION/RESULTANTE: the field has no component {c} (it has {})",
                            f.components().join(", ")
                        )));
                    }
                    let sum: f64 = nodes.iter().filter_map(|&n| f.get(n, c)).sum();
                    table.ensure_column(c, ColumnType::Real);
                    row.push((c.clone(), Value::Real(sum)));
                }
                table.push_row(row.iter().map(|(k, v)| (k.as_str(), v.clone())).collect());
            }
            continue;
        }
        for (resu, cham, order, field) in sources {
            // Element fields at nodes (_ELNO) are averaged at each node
            // (MOYE_NOEUD='OUI'); other element fields are refused.
            let f = match field {
                Field::Nodal(f) => f,
                // code_aster's MOYENNE of an element field works on the
                // cells' values along the path, not on nodal means.
                Field::Elem(_) if moyenne || local.is_some() => {
                    let what = if moyenne {
                        "OPERATION='MOYENNE'"
                    } else {
                        "REPERE='LOCAL'"
                    };
                    return Err(ex.unsupported(
                        &format!("POST_RELEVE_T/ACTION/{what} of an element field"),
                        occ.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span),
                    ));
                }
                Field::Elem(e) => e.nodal_mean(&mesh).ok_or_else(|| {
                    ex.unsupported(
                        "POST_RELEVE_T/ACTION on element fields other than _ELNO",
                        occ.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span),
                    )
                })?,
            };
            let f = if polar {
                frame_components(&f, |n| Some(polar_frame(mesh.coord(n))))
            } else if let Some(frames) = &local {
                frame_components(&f, |n| frames.get(&n).copied())
            } else {
                f
            };
            let cmps: Vec<String> = if occ.str("TOUT_CMP") == Some("OUI") {
                f.components().to_vec()
            } else {
                let wanted: Vec<String> = occ
                    .simple("NOM_CMP")
                    .iter()
                    .filter_map(|s| s.as_str().map(str::to_string))
                    .collect();
                for c in &wanted {
                    if f.component_index(c).is_none() {
                        return Err(ExecError::new(format!(
                            "POST_RELEVE_T/ACTION/NOM_CMP: the field has no component {c} (it has {})",
                            f.components().join(", ")
                        )));
                    }
                }
                wanted
            };
            // ABSC_CURV: length along the nodes in the order given, on the
            // mesh's coordinates (code_aster's abscissa of a node path).
            let mut absc = Vec::with_capacity(nodes.len());
            let mut s = 0.0;
            for (k, &n) in nodes.iter().enumerate() {
                if k > 0 {
                    let (a, b) = (mesh.coord(nodes[k - 1]), mesh.coord(n));
                    s += ((0..3).map(|c| (b[c] - a[c]).powi(2)).sum::<f64>()).sqrt();
                }
                absc.push(s);
            }
            if moyenne {
                if nodes.len() < 2 {
                    return Err(ExecError::new(
                        "POST_RELEVE_T/ACTION: OPERATION='MOYENNE' needs a path of at least two nodes (code_aster POSTRELE_6)",
                    ));
                }
                table.ensure_column("QUANTITE", ColumnType::Text(16));
                let moments: Vec<(String, [f64; 6])> = cmps
                    .iter()
                    .filter_map(|c| {
                        let i = f.component_index(c)?;
                        let vals: Vec<Option<f64>> =
                            nodes.iter().map(|n| f.get_at(*n, i)).collect();
                        Some((c.clone(), path_moments(&absc, &vals)))
                    })
                    .collect();
                for (c, _) in &moments {
                    table.ensure_column(c, ColumnType::Real);
                }
                for (q, quantity) in PATH_QUANTITIES.iter().enumerate() {
                    let mut row: Vec<(String, Value)> =
                        vec![("INTITULE".into(), Value::Text(title.clone()))];
                    if let Some(r) = &resu {
                        row.push(("RESU".into(), Value::Text(r.clone())));
                    }
                    if let Some(c) = &cham {
                        row.push(("NOM_CHAM".into(), Value::Text(c.clone())));
                    }
                    if let Some((no, t)) = order {
                        row.push(("NUME_ORDRE".into(), Value::Int(no as i64)));
                        row.push(("INST".into(), Value::Real(t)));
                    }
                    row.push(("QUANTITE".into(), Value::Text(quantity.to_string())));
                    for (c, m) in &moments {
                        row.push((c.clone(), Value::Real(m[q])));
                    }
                    table.push_row(row.iter().map(|(k, v)| (k.as_str(), v.clone())).collect());
                }
                continue;
            }
            for (&n, &abscissa) in nodes.iter().zip(&absc) {
                // Nodes without the field (outside the model) give no row.
                let Some(vals) = f.node(n) else {
                    continue;
                };
                let x = mesh.coord(n);
                let mut row: Vec<(&str, Value)> = vec![("INTITULE", Value::Text(title.clone()))];
                if let Some(r) = &resu {
                    row.push(("RESU", Value::Text(r.clone())));
                }
                if let Some(c) = &cham {
                    row.push(("NOM_CHAM", Value::Text(c.clone())));
                }
                if let Some((no, t)) = order {
                    row.push(("NUME_ORDRE", Value::Int(no as i64)));
                    row.push(("INST", Value::Real(t)));
                }
                row.push(("NOEUD", Value::Text(mesh.node_name(n))));
                row.push(("ABSC_CURV", Value::Real(abscissa)));
                row.push(("COOR_X", Value::Real(x[0])));
                row.push(("COOR_Y", Value::Real(x[1])));
                if mesh.dim == 3 {
                    row.push(("COOR_Z", Value::Real(x[2])));
                }
                let mut cells: Vec<(String, f64)> = Vec::new();
                for c in &cmps {
                    if let Some(i) = f.component_index(c) {
                        if let Some(v) = vals.get(i) {
                            cells.push((c.clone(), v));
                        }
                    }
                }
                for (c, _) in &cells {
                    table.ensure_column(c, ColumnType::Real);
                }
                let mut owned: Vec<(String, Value)> =
                    row.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
                owned.extend(cells.into_iter().map(|(c, v)| (c, Value::Real(v))));
                table.push_row(owned.iter().map(|(k, v)| (k.as_str(), v.clone())).collect());
            }
        }
    }
    name_load_cases(&mut table, &cases);
    // Columns nobody filled (RESU for a CHAM_GD…) are dropped, as code_aster does.
    drop_empty_columns(&mut table);
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// The rows of a `mult_elas` (MACRO_ELAS_MULT) result: `NOM_CAS` after
/// `NUME_ORDRE` instead of `INST` (code_aster's `rvpara`: such a result
/// has no instant). `cases` maps (RESU, NUME_ORDRE) to the case's name.
fn name_load_cases(table: &mut Table, cases: &BTreeMap<(String, u32), String>) {
    if cases.is_empty() {
        return;
    }
    let (Some(resu), Some(order)) = (table.column_index("RESU"), table.column_index("NUME_ORDRE"))
    else {
        return;
    };
    let inst = table.column_index("INST");
    table.columns.insert(
        order + 1,
        Column {
            name: "NOM_CAS".into(),
            ty: ColumnType::Text(16),
        },
    );
    for row in &mut table.rows {
        let key = match (row.get(resu), row.get(order)) {
            (Some(Some(Value::Text(r))), Some(Some(Value::Int(n)))) => Some((r.clone(), *n as u32)),
            _ => None,
        };
        let name = key.and_then(|k| cases.get(&k)).cloned();
        if name.is_some() {
            if let Some(cell) = inst.and_then(|i| row.get_mut(i)) {
                *cell = None;
            }
        }
        if row.len() > order {
            row.insert(order + 1, name.map(Value::Text));
        }
    }
}

/// `OPERATION='MOYENNE_ARITH'` (code_aster's `rvmoye` and `prmono`): per
/// instant and component, the sum of the component over the selected nodes
/// (all the mesh's nodes when none is selected) that carry it, divided by
/// the number of selected nodes — nodes without the component count in the
/// divisor (code_aster's arithmetic, e.g. the middle nodes of quadratic
/// cells for `LAGS_C`). One row per component: `CMP`, `MOYENNE`.
#[allow(clippy::too_many_arguments)]
fn arith_mean_rows(
    ex: &Executor,
    table: &mut Table,
    occ: &Keywords,
    title: &str,
    chamgd: Option<String>,
    sources: &[Source],
    mesh: &aster_mesh::Mesh,
    nodes: &[NodeId],
) -> Result<(), ExecError> {
    let all: Vec<NodeId>;
    let nodes = if nodes.is_empty() {
        all = (0..mesh.node_count() as u32).map(NodeId).collect();
        &all
    } else {
        nodes
    };
    if chamgd.is_some() {
        table.ensure_column("CHAM_GD", ColumnType::Text(8));
    }
    table.ensure_column("CMP", ColumnType::Text(8));
    table.ensure_column("MOYENNE", ColumnType::Real);
    for (resu, cham, order, field) in sources {
        let Field::Nodal(f) = field else {
            // code_aster: ALGORITH17_5, a nodal field only.
            return Err(ex.kw_error(
                "POST_RELEVE_T/ACTION",
                occ,
                if chamgd.is_some() {
                    "CHAM_GD"
                } else {
                    "NOM_CHAM"
                },
                "OPERATION='MOYENNE_ARITH' needs a nodal field (code_aster ALGORITH17_5)",
            ));
        };
        let cmps: Vec<String> = if occ.contains("NOM_CMP") {
            occ.simple("NOM_CMP")
                .iter()
                .filter_map(|s| s.as_str().map(str::to_string))
                .collect()
        } else {
            f.components().to_vec()
        };
        for c in &cmps {
            let Some(i) = f.component_index(c) else {
                return Err(ex.kw_error(
                    "POST_RELEVE_T/ACTION",
                    occ,
                    "NOM_CMP",
                    format!(
                        "the field has no component {c} (it has {})",
                        f.components().join(", ")
                    ),
                ));
            };
            let sum: f64 = nodes.iter().filter_map(|n| f.get_at(*n, i)).sum();
            let mean = sum / nodes.len() as f64;
            let mut row: Vec<(&str, Value)> = vec![("INTITULE", Value::Text(title.to_string()))];
            if let Some(g) = &chamgd {
                row.push(("CHAM_GD", Value::Text(g.clone())));
            }
            if let Some(r) = resu {
                row.push(("RESU", Value::Text(r.clone())));
            }
            if let Some(ch) = cham {
                row.push(("NOM_CHAM", Value::Text(ch.clone())));
            }
            if let Some((no, t)) = order {
                row.push(("NUME_ORDRE", Value::Int(*no as i64)));
                row.push(("INST", Value::Real(*t)));
            }
            row.push(("CMP", Value::Text(c.clone())));
            row.push(("MOYENNE", Value::Real(mean)));
            table.push_row(row);
        }
    }
    Ok(())
}

/// The frame of each node of an ACTION's path for `REPERE='LOCAL'`
/// (code_aster's `rvchgr`/`rvrlln`), refusing what code_aster would not
/// compute the same way: a path whose order code_aster builds differently
/// (`rvgnoe`: the NOEUD list, then each GROUP_NO's nodes in the group's
/// order, consecutive repeats dropped), `VECT_Y`, a path off the plane z of
/// the mesh's first node (code_aster then gives nothing), fewer than two
/// nodes, and RESULTANTE.
fn local_frames(
    ex: &Executor,
    occ: &Keywords,
    mesh: &aster_mesh::Mesh,
    nodes: &[NodeId],
    resultant: bool,
    fallback: aster_syntax::Span,
) -> Result<std::collections::HashMap<NodeId, Frame>, ExecError> {
    let refuse = |why: &str| {
        let span = occ.keyword("REPERE").map(|k| k.span).unwrap_or(fallback);
        ex.unsupported(&format!("POST_RELEVE_T/ACTION/REPERE='LOCAL' {why}"), span)
    };
    if resultant {
        return Err(refuse("with RESULTANTE"));
    }
    if occ.contains("GROUP_MA") || occ.contains("MAILLE") || occ.str("TOUT") == Some("OUI") {
        return Err(refuse(
            "on cells (the local frame of a path of nodes, GROUP_NO/NOEUD, only)",
        ));
    }
    // rvgnoe's order.
    let mut path: Vec<NodeId> = Vec::new();
    let mut push = |n: NodeId| {
        if path.last() != Some(&n) {
            path.push(n);
        }
    };
    for name in occ.simple("NOEUD").iter().filter_map(|s| s.as_str()) {
        push(select::node_named(mesh, name).map_err(ExecError::new)?);
    }
    for g in occ.simple("GROUP_NO").iter().filter_map(|s| s.as_str()) {
        for &n in select::group_no(mesh, g).map_err(ExecError::new)? {
            push(n);
        }
    }
    if path != nodes {
        return Err(refuse(
            "on a path given by several NOEUD/GROUP_NO lists or repeating a node (code_aster's node order for it is not reproduced)",
        ));
    }
    // rvchgr: every z equal to the first mesh node's (rvegal, relative 1e-3).
    let z0 = mesh.coords.first().map_or(0.0, |c| c[2]);
    let seuil = if z0.abs() >= 1e-3 {
        1e-3 * z0.abs()
    } else {
        1e-3
    };
    if path.iter().any(|&n| (z0 - mesh.coord(n)[2]).abs() >= seuil) {
        return Err(refuse(
            "on a path off the plane z of the mesh's first node (code_aster computes no frame: alarm POSTRELE_28)",
        ));
    }
    let points: Vec<[f64; 3]> = path.iter().map(|&n| mesh.coord(n)).collect();
    let frames = local_path_frames(&points).ok_or_else(|| {
        refuse("on a path of fewer than two nodes or with two consecutive nodes at the same place")
    })?;
    Ok(path.into_iter().zip(frames).collect())
}

fn occ_mesh(ex: &Executor, field: &ConceptRef) -> Result<Arc<aster_mesh::Mesh>, ExecError> {
    // A field does not record its mesh: that of its result, or the only one.
    ex.field_mesh(field)
}

fn drop_empty_columns(t: &mut Table) {
    let keep: Vec<bool> = (0..t.columns.len())
        .map(|i| t.rows.iter().any(|r| r.get(i).is_some_and(Option::is_some)))
        .collect();
    let mut i = 0;
    t.columns.retain(|_| {
        i += 1;
        keep[i - 1]
    });
    for row in &mut t.rows {
        let mut j = 0;
        row.retain(|_| {
            j += 1;
            keep.get(j - 1).copied().unwrap_or(false)
        });
    }
}

/// What IMPR_TABLE reads (`crate::support`).
pub(crate) const IMPR_TABLE: Support = Support {
    values: &[
        Values::new("FORMAT", &["TABLEAU", "AGRAF", "XMGRACE"]),
        Values::new("IMPR_FONCTION", &["NON"])
            .why("(the functions named in a FONCTION column are not printed)"),
    ],
    rules: Some(impr_table_rules),
    ..Support::keywords(&[
        "TABLE",
        "FORMAT",
        "UNITE",
        "NOM_PARA",
        "TITRE",
        "INFO",
        "TRI",
        "TRI/NOM_PARA",
        "TRI/ORDRE",
        "FORMAT_R",
        "IMPR_FONCTION",
        "FILTRE",
        "FILTRE/NOM_PARA",
        "FILTRE/CRIT_COMP",
        "FILTRE/VALE",
        "FILTRE/VALE_I",
        "FILTRE/VALE_K",
        "FILTRE/CRITERE",
        "FILTRE/PRECISION",
        // FORMAT='XMGRACE': the graph's legends and bounds are written;
        // its look (grid, colour, style, marker) is not drawn.
        "PILOTE",
        "LEGENDE",
        "LEGENDE_X",
        "LEGENDE_Y",
        "BORNE_X",
        "BORNE_Y",
        "ECHELLE_X",
        "ECHELLE_Y",
        "GRILLE_X",
        "GRILLE_Y",
        "COULEUR",
        "STYLE",
        "MARQUEUR",
        "FREQ_MARQUEUR",
    ])
};

/// FORMAT_R is a Fortran real edit descriptor code_aster's `fmtF2PY`
/// reads: `[nP]Ew.d` (or `D`) is handled.
fn impr_table_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    if let Some(f) = kw.str("FORMAT_R") {
        if TableFormat::real_from_fortran(f).is_none() {
            out.push(Refusal::at(
                format!("IMPR_TABLE/FORMAT_R='{f}' (only the E and D edit descriptors [nP]Ew.d)"),
                kw,
                "FORMAT_R",
                call.span,
            ));
        }
    }
}

pub fn impr_table(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let t = ex.required("IMPR_TABLE", kw, "TABLE")?;
    let mut table = (*ex.table(t)?).clone();
    let mut format = TableFormat {
        agraf: kw.str("FORMAT") == Some("AGRAF"),
        ..TableFormat::default()
    };
    if let Some(f) = kw.str("FORMAT_R") {
        let (lead, width, precision) = TableFormat::real_from_fortran(f).ok_or_else(|| {
            ex.kw_error(
                "IMPR_TABLE",
                kw,
                "FORMAT_R",
                "a real edit descriptor [nP]Ew.d",
            )
        })?;
        format.real_lead = lead;
        format.real_width = width;
        format.real_precision = precision;
    }
    // Filtered, then sorted, before the columns are chosen (code_aster's
    // impr_table_ops: FILTRE and TRI act on the whole table).
    let filters = kw.factor("FILTRE");
    if !filters.is_empty() {
        let rows = super::inspect::filter_rows(&table, filters)
            .map_err(|e| ExecError::new(format!("IMPR_TABLE/{e}")))?;
        table.rows = rows.into_iter().map(|r| table.rows[r].clone()).collect();
    }
    if let Some(tri) = kw.factor("TRI").first() {
        let keys: Vec<usize> = tri
            .simple("NOM_PARA")
            .iter()
            .filter_map(|s| s.as_str())
            .map(|k| {
                table
                    .column_index(k)
                    .ok_or_else(|| ExecError::new(format!("IMPR_TABLE/TRI: no column {k}")))
            })
            .collect::<Result<_, _>>()?;
        let descending = tri.str("ORDRE") == Some("DECROISSANT");
        table.rows.sort_by(|a, b| {
            let ord = keys
                .iter()
                .map(|&k| compare_cells(&a[k], &b[k]))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal);
            if descending {
                ord.reverse()
            } else {
                ord
            }
        });
    }
    let wanted: Vec<&str> = kw
        .simple("NOM_PARA")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    if !wanted.is_empty() {
        let mut cols = Vec::new();
        for w in &wanted {
            let i = table.column_index(w).ok_or_else(|| {
                ExecError::new(format!(
                    "IMPR_TABLE/NOM_PARA: the table has no column {w}{}",
                    select::did_you_mean(w, table.columns.iter().map(|c| c.name.as_str()))
                ))
            })?;
            cols.push(i);
        }
        table.columns = cols.iter().map(|&i| table.columns[i].clone()).collect();
        table.rows = table
            .rows
            .iter()
            .map(|r| cols.iter().map(|&i| r[i].clone()).collect())
            .collect();
    }
    if kw.str("FORMAT") == Some("XMGRACE") {
        let text = super::functions::xmgrace(kw, &table_curves(kw, &table)?);
        super::functions::write_xmgrace(ex, kw, "IMPR_TABLE", &text)?;
        return Ok(CommandOutput::Nothing);
    }
    if let Some(title) = kw.str("TITRE") {
        table.title = title.lines().map(str::to_string).collect();
    }
    let text = table.render_as(&format);
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(8);
    if unit == 8 || unit == 6 {
        ex.write_report(&text)?;
        ex.write_report("\n")?;
    } else {
        ex.append_unit(unit, &(text + "\n"))?;
    }
    Ok(CommandOutput::Nothing)
}

/// IMPR_TABLE(FORMAT='XMGRACE'): code_aster's `Table.Impr` draws the first
/// column (of NOM_PARA) as the abscissa and each further column as a curve
/// (named LEGENDE, else the column), over the rows where both are reals.
fn table_curves(kw: &Keywords, table: &Table) -> Result<Vec<super::functions::Curve>, ExecError> {
    if table.columns.len() < 2 {
        return Err(ExecError::new(
            "IMPR_TABLE/FORMAT='XMGRACE': give NOM_PARA with an abscissa and at least one ordinate",
        ));
    }
    let real = |c: &Option<Value>| c.as_ref()?.as_f64();
    let legend = kw.str("LEGENDE").map(str::to_string);
    Ok((1..table.columns.len())
        .map(|j| super::functions::Curve {
            x_name: table.columns[0].name.clone(),
            y_name: legend
                .clone()
                .unwrap_or_else(|| table.columns[j].name.clone()),
            legend: legend.clone(),
            points: table
                .rows
                .iter()
                .filter_map(|r| Some((real(&r[0])?, real(&r[j])?)))
                .collect(),
        })
        .collect())
}

fn compare_cells(a: &Option<Value>, b: &Option<Value>) -> std::cmp::Ordering {
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

pub(crate) fn append(path: &std::path::Path, text: &str) -> Result<(), ExecError> {
    use std::io::Write;
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| ExecError::new(format!("cannot create {}: {e}", dir.display())))?;
    }
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(|e| ExecError::new(format!("cannot write {}: {e}", path.display())))?;
    f.write_all(text.as_bytes())
        .map_err(|e| ExecError::new(format!("cannot write {}: {e}", path.display())))
}

pub fn impr_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    crate::output::impr_resu(ex, call)
}

#[cfg(test)]
mod moyenne_tests {
    use super::path_moments;

    #[test]
    fn a_linear_distribution_gives_its_mean_and_its_end_values() {
        // v = 2 + 3 s on s in [0, 2]: mean 5, linear moment 3·2 = 6,
        // MOYE_INT = v(0) = 2, MOYE_EXT = v(2) = 8.
        let m = path_moments(&[0.0, 1.0, 2.0], &[Some(2.0), Some(5.0), Some(8.0)]);
        let want = [5.0, 6.0, 2.0, 8.0, 2.0, 8.0];
        for (g, w) in m.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{m:?}");
        }
    }

    #[test]
    fn segments_with_a_missing_value_are_skipped() {
        // Only the segment [0, 1] counts: mean of 1 and 3, moment 2.
        let m = path_moments(&[0.0, 1.0, 3.0], &[Some(1.0), Some(3.0), None]);
        assert!(
            (m[0] - 2.0).abs() < 1e-12 && (m[1] - 2.0).abs() < 1e-12,
            "{m:?}"
        );
        assert_eq!((m[2], m[3]), (1.0, 3.0));
    }
}

#[cfg(test)]
mod local_frame_tests {
    use super::local_path_frames;

    #[test]
    fn a_straight_path_has_its_direction_and_the_left_normal_everywhere() {
        // Along (0.8, 0.6) with a z step (dropped from the tangent but
        // counted in the length, as rvrlln does): t = (0.8, 0.6)·5/√26.
        let f = local_path_frames(&[[0.0, 0.0, 0.0], [4.0, 3.0, 0.0], [8.0, 6.0, 0.0]]).unwrap();
        for (t, n) in &f {
            assert!(
                (t[0] - 0.8).abs() < 1e-15 && (t[1] - 0.6).abs() < 1e-15,
                "{f:?}"
            );
            assert!(
                (n[0] + 0.6).abs() < 1e-15 && (n[1] - 0.8).abs() < 1e-15,
                "{f:?}"
            );
        }
        let g = local_path_frames(&[[0.0, 0.0, 0.0], [4.0, 3.0, 1.0]]).unwrap();
        let s = 5.0 / 26f64.sqrt();
        assert!((g[0].0[0] - 0.8 * s).abs() < 1e-15 && (g[1].0[1] - 0.6 * s).abs() < 1e-15);
    }

    #[test]
    fn paths_without_a_frame() {
        assert!(local_path_frames(&[[1.0, 2.0, 0.0]]).is_none());
        assert!(local_path_frames(&[[0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]).is_none());
    }
}
