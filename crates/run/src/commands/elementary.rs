//! The elementary-vector chain of code_aster 15:
//! CALCUL(OPTION='FORC_NODA_ELEM') → EXTR_TABLE(TYPE_RESU='VECT_ELEM_DEPL_R')
//! → NUME_DDL → ASSE_VECTEUR, and EXTR_TABLE of plain values.

use super::inspect::filter_rows;
use crate::concept::Concept;
use crate::executor::{result_of, store_result, Executor};
use crate::fembridge;
use crate::field::Field;
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Scalar};
use std::rc::Rc;

/// What CALCUL reads (`crate::support`).
pub(crate) const CALCUL: Support = Support {
    values: &[
        Values::new("OPTION", &["FORC_NODA_ELEM"]),
        Values::new("COMPORTEMENT/RELATION", &["ELAS"]),
        Values::new("COMPORTEMENT/DEFORMATION", &["PETIT"]),
    ],
    ..Support::keywords(&[
        "OPTION",
        "PHENOMENE",
        "MODELE",
        "CARA_ELEM",
        "CHAM_MATER",
        "SIGM",
        "VARI",
        "DEPL",
        "INCR_DEPL",
        "EXCIT",
        "EXCIT/CHARGE",
        "EXCIT/FONC_MULT",
        "EXCIT/TYPE_CHARGE",
        "COMPORTEMENT",
        "COMPORTEMENT/RELATION",
        "COMPORTEMENT/DEFORMATION",
        "COMPORTEMENT/TOUT",
        "INCREMENT",
        "INCREMENT/LIST_INST",
        "INCREMENT/NUME_ORDRE",
        "INFO",
    ])
};

pub fn calcul(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model = ex.model(ex.required("CALCUL", kw, "MODELE")?)?;
    let materials = ex.material_field(ex.required("CALCUL", kw, "CHAM_MATER")?)?;
    let cara = match kw.concept("CARA_ELEM") {
        Some(c) => Some(ex.cara_elem(c)?),
        None => None,
    };
    let depl = ex.required("CALCUL", kw, "DEPL")?;
    let Field::Nodal(depl) = &*ex.field(depl)? else {
        return Err(ExecError::new(
            "CALCUL/DEPL: a nodal displacement field is required",
        ));
    };
    let mesh = ex.mesh_by_id(model.mesh)?;
    let fem_model = fembridge::build_model(&mesh, &model, &materials, cara.as_deref())?;
    // Linear elasticity: the stresses SIGM are those of DEPL, and the
    // internal forces are Bᵀσ(DEPL) (+ the springs' forces).
    let u: Vec<f64> = fem_model
        .dofs()
        .dofs()
        .iter()
        .map(|d| depl.get(d.node, d.comp.name()).unwrap_or(0.0))
        .collect();
    let f = aster_fem::post::forc_noda(&fem_model, &u)
        .map_err(|e| ExecError::new(format!("CALCUL: {e}")))?;
    let vect = fembridge::nodal_from_dofs(&fem_model, &f);
    let name = result_of(call)?.name.clone();
    let sd = format!("{name}.FORC_NODA_ELEM");
    ex.objects
        .insert(sd.clone(), Concept::VectElem(Rc::new(vect)));
    let mut table = Table::new(vec![
        Column {
            name: "NOM_OBJET".into(),
            ty: ColumnType::Text(16),
        },
        Column {
            name: "TYPE_OBJET".into(),
            ty: ColumnType::Text(16),
        },
        Column {
            name: "NOM_SD".into(),
            ty: ColumnType::Text(24),
        },
    ]);
    table.push_row(vec![
        ("NOM_OBJET", Value::Text("FORC_NODA_ELEM".into())),
        ("TYPE_OBJET", Value::Text("VECT_ELEM_DEPL_R".into())),
        ("NOM_SD", Value::Text(sd)),
    ]);
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// What CALC_VECT_ELEM reads (`crate::support`).
pub(crate) const CALC_VECT_ELEM: Support = Support {
    values: &[Values::new("OPTION", &["FORC_NODA"])],
    ..Support::keywords(&[
        "OPTION",
        "MODELE",
        "SIEF_ELGA",
        "CARA_ELEM",
        "CHAM_MATER",
        "INST",
    ])
};

/// Legacy `CALC_VECT_ELEM(OPTION='FORC_NODA', SIEF_ELGA=…)` (code_aster
/// ≤ 14): the nodal forces of a stress field. The field must have been
/// extracted from a computed result (CREA_CHAMP/EXTR): its step's
/// displacement gives the same Bᵀσ in linear elasticity, springs included.
pub fn calc_vect_elem(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let model = ex.required("CALC_VECT_ELEM", kw, "MODELE")?;
    ex.model(model)?;
    let sigma = ex.required("CALC_VECT_ELEM", kw, "SIEF_ELGA")?;
    let Some((result, order)) = ex.field_origin.get(&sigma.id).cloned() else {
        let span = kw.keyword("SIEF_ELGA").map(|k| k.span).unwrap_or(call.span);
        return Err(ex.unsupported(
            "CALC_VECT_ELEM/SIEF_ELGA not extracted from a computed result (CREA_CHAMP/EXTR)",
            span,
        ));
    };
    let Some(run) = result.fem.clone() else {
        return Err(ExecError::new(
            "CALC_VECT_ELEM: the stresses' result was not computed in this run",
        ));
    };
    let step = run.state("CALC_VECT_ELEM", order)?;
    let f = aster_fem::post::forc_noda(&run.model, &step.displacement)
        .map_err(|e| ExecError::new(format!("CALC_VECT_ELEM: {e}")))?;
    let vect = fembridge::nodal_from_dofs(&run.model, &f);
    store_result(ex, call, Concept::VectElem(Rc::new(vect)))
}

/// What EXTR_TABLE reads (`crate::support`).
pub(crate) const EXTR_TABLE: Support = Support::keywords(&[
    "TYPE_RESU",
    "TABLE",
    "NOM_PARA",
    "FILTRE",
    "FILTRE/NOM_PARA",
    "FILTRE/CRIT_COMP",
    "FILTRE/VALE",
    "FILTRE/VALE_I",
    "FILTRE/VALE_K",
    "FILTRE/CRITERE",
    "FILTRE/PRECISION",
    "TITRE",
]);

pub fn extr_table(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let t = ex.required("EXTR_TABLE", kw, "TABLE")?;
    let table = ex.table(t)?;
    let para = kw
        .str("NOM_PARA")
        .ok_or_else(|| ExecError::new("EXTR_TABLE: NOM_PARA is required"))?;
    let col = table.column_index(para).ok_or_else(|| {
        ExecError::new(format!(
            "EXTR_TABLE: table `{}` has no column {para}",
            t.name
        ))
    })?;
    let rows = filter_rows(&table, kw.factor("FILTRE"))
        .map_err(|e| ExecError::new(format!("EXTR_TABLE: {e}")))?;
    let values: Vec<&Value> = rows
        .iter()
        .filter_map(|&r| table.rows[r][col].as_ref())
        .collect();
    let [value] = values.as_slice() else {
        return Err(ExecError::new(format!(
            "EXTR_TABLE: {} values of {para} match in `{}` (exactly one is needed; refine FILTRE)",
            values.len(),
            t.name
        )));
    };
    let typ = kw.str("TYPE_RESU").unwrap_or("");
    match typ {
        "REEL" | "ENTIER" | "CHAINE" => Ok(CommandOutput::Value(match value {
            Value::Int(i) => Scalar::Int(*i),
            Value::Real(r) => Scalar::Real(*r),
            Value::Text(s) => Scalar::Str(s.clone()),
        })),
        "VECT_ELEM_DEPL_R" => {
            let Value::Text(sd) = value else {
                return Err(ExecError::new(format!(
                    "EXTR_TABLE: {para} does not name an object"
                )));
            };
            let obj = ex.objects.get(sd.trim()).cloned().ok_or_else(|| {
                ExecError::new(format!(
                    "EXTR_TABLE: no object `{sd}` (made by CALCUL in this run)"
                ))
            })?;
            store_result(ex, call, obj)
        }
        other => {
            let span = kw.keyword("TYPE_RESU").map(|k| k.span).unwrap_or(call.span);
            Err(ex.unsupported(&format!("EXTR_TABLE/TYPE_RESU='{other}'"), span))
        }
    }
}

/// What NUME_DDL reads (`crate::support`).
pub(crate) const NUME_DDL: Support =
    Support::keywords(&["MODELE", "CHARGE", "MATR_RIGI", "INFO", "METHODE", "RENUM"]);

pub fn nume_ddl(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    // MATR_RIGI: the numbering of the matrices' model (aster numbers the
    // DOFs of a model one way; the conditions are eliminated, not
    // numbered).
    if let Some(r) = call.keywords.concept("MATR_RIGI") {
        let id = super::modal::numbering_of(ex, r)?;
        return store_result(ex, call, Concept::Numbering(id));
    }
    let m = ex.required("NUME_DDL", &call.keywords, "MODELE")?;
    ex.model(m)?;
    let id = m.id;
    store_result(ex, call, Concept::Numbering(id))
}

/// What ASSE_VECTEUR reads (`crate::support`).
pub(crate) const ASSE_VECTEUR: Support = Support::keywords(&["VECT_ELEM", "NUME_DDL", "INFO"]);

pub fn asse_vecteur(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let n = ex.required("ASSE_VECTEUR", kw, "NUME_DDL")?;
    if !matches!(ex.concept(n)?, Concept::Numbering(_)) {
        return Err(ExecError::new(format!(
            "ASSE_VECTEUR/NUME_DDL: `{}` is not a NUME_DDL",
            n.name
        )));
    }
    let mut sum: Option<crate::field::NodalField> = None;
    for s in kw.simple("VECT_ELEM") {
        let Some(c) = s.as_concept() else { continue };
        let Concept::VectElem(v) = ex.concept(c)? else {
            return Err(ExecError::new(format!(
                "ASSE_VECTEUR/VECT_ELEM: `{}` is not a vect_elem",
                c.name
            )));
        };
        match &mut sum {
            None => sum = Some((**v).clone()),
            Some(acc) => {
                for (node, vals) in v.iter() {
                    for (i, x) in vals.iter().enumerate() {
                        if let Some(x) = x {
                            let name = &v.components()[i];
                            let cur = acc.get(node, name).unwrap_or(0.0);
                            acc.set(node, name, cur + x);
                        }
                    }
                }
            }
        }
    }
    let sum = sum.ok_or_else(|| ExecError::new("ASSE_VECTEUR: no VECT_ELEM"))?;
    store_result(ex, call, Concept::Field(Rc::new(Field::Nodal(sum))))
}
