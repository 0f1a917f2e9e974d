//! Results built field by field: CREA_RESU (AFFE).
//!
//! - `CREA_RESU(OPERATION='AFFE', TYPE_RESU='EVOL_ELAS'|'EVOL_NOLI')`
//!   (code_aster's `crtype`): each `AFFE` occurrence stores its field
//!   (`CHAM_GD`) under `NOM_CHAM` at each instant of `INST`/`LIST_INST`: at
//!   the NUME_ORDRE already holding that instant (within `PRECISION`,
//!   `CRITERE`), else at a new NUME_ORDRE after the largest (1 for a new
//!   result). `reuse=` with `RESULTAT` adds to a result.
//!
//! `RECU_TABLE` (both its `NOM_TABLE` and `NOM_PARA` forms) is in `tables`.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use std::collections::BTreeMap;
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
    ],
    values: &[
        Values::new("OPERATION", &["AFFE"]),
        Values::new("TYPE_RESU", &["EVOL_ELAS", "EVOL_NOLI"]),
    ],
    hints: &[],
    reuse: true,
    rules: None,
};

pub fn crea_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
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
            typ,
            mesh: u32::MAX,
            steps: Vec::new(),
            fem: None,
            tables: Vec::new(),
        },
    };
    for occ in kw.factor("AFFE") {
        let name = occ.str("NOM_CHAM").unwrap_or("DEPL").to_string();
        let field_ref = ex.required("CREA_RESU", occ, "CHAM_GD")?;
        let field = (*ex.field(field_ref)?).clone();
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
            let at = result.step_at(t, precision, absolute).map(|s| s.nume_ordre);
            match at {
                Some(n) => {
                    if let Some(s) = result.steps.iter_mut().find(|s| s.nume_ordre == n) {
                        s.fields.insert(name.clone(), field.clone());
                    }
                }
                None => {
                    let n = result.steps.iter().map(|s| s.nume_ordre).max().unwrap_or(0) + 1;
                    let mut fields = BTreeMap::new();
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
