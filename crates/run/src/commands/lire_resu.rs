//! `LIRE_RESU(FORMAT='MED')`: a result read from the fields of a MED file
//! (code_aster's `lrcomm` → `lrfmed`).
//!
//! Each `FORMAT_MED` occurrence names one field of the file: `NOM_CHAM_MED`,
//! or `NOM_RESU` padded with '_' to 8 characters followed by `NOM_CHAM`
//! (code_aster's naming, `mdnoch`); failing that, `NOM_RESU` and `NOM_CHAM`
//! joined (how this program's `IMPR_RESU` names them). Every step of the file is
//! read (`TOUT_ORDRE`); a nodal field covers every node with zeros outside
//! its profile under `PROL_ZERO='OUI'` (the default), its profile only
//! under `'NON'`. Fields on cells and the other selections of steps or
//! components are refused.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_mesh::NodeId;
use std::collections::BTreeMap;
use std::rc::Rc;

/// What LIRE_RESU reads (`crate::support`).
pub(crate) const LIRE_RESU: Support = Support {
    keywords: &[
        "TYPE_RESU",
        "FORMAT",
        "UNITE",
        "MODELE",
        "TOUT_ORDRE",
        "FORMAT_MED",
        "FORMAT_MED/NOM_CHAM",
        "FORMAT_MED/NOM_CHAM_MED",
        "FORMAT_MED/NOM_RESU",
        "PROL_ZERO",
        "TITRE",
        "INFO",
    ],
    values: &[
        Values::listed("TYPE_RESU", &["EVOL_NOLI", "EVOL_ELAS"]),
        Values::listed("FORMAT", &["MED"]),
    ],
    ..Support::keywords(&[])
};

pub fn lire_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "LIRE_RESU";
    let kw = &call.keywords;
    let model = ex.model(ex.required(CMD, kw, "MODELE")?)?;
    let mesh = ex.model_mesh(&model)?;
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(81);
    // A file of the study, or one this run wrote on that unit.
    let path = match ex.input_path(unit as u32) {
        Some(p) => p.to_path_buf(),
        None => ex.output_path(unit),
    };
    if !path.exists() {
        return Err(ex.kw_error(
            CMD,
            kw,
            "UNITE",
            format!("no MED file on unit {unit} ({})", path.display()),
        ));
    }
    let (_, info) = aster_mesh::read_med_named(&path, None)
        .map_err(|e| ExecError::new(format!("{CMD}: {e}")))?;
    let steps = aster_mesh::read_med_steps_covered(&path, &mesh, &info.mesh_name)
        .map_err(|e| ExecError::new(format!("{CMD}: {e}")))?;
    let prol_zero = kw.str("PROL_ZERO").unwrap_or("OUI") == "OUI";
    let mut out: BTreeMap<i32, Step> = BTreeMap::new();
    for occ in kw.factor("FORMAT_MED") {
        let Some(nom_cham) = occ.str("NOM_CHAM") else {
            return Err(ex.kw_error(CMD, occ, "NOM_CHAM", "a field name is required"));
        };
        // code_aster's name (`mdnoch`: the result's name padded with '_'
        // to 8 characters, then the field's), then this program's
        // (`IMPR_RESU`: the two joined).
        let names: Vec<String> = match (occ.str("NOM_CHAM_MED"), occ.str("NOM_RESU")) {
            (Some(n), _) => vec![n.trim_end().to_string()],
            (None, Some(r)) => vec![
                format!("{:_<8}{nom_cham}", r.trim_end()),
                format!("{}{nom_cham}", r.trim_end()),
            ],
            (None, None) => vec![nom_cham.to_string()],
        };
        let med_name = names[0].clone();
        let mut found = false;
        for (s, covered) in &steps {
            let pick = |name: &str| s.fields.iter().position(|f| f.name.trim_end() == name);
            let Some(k) = names.iter().find_map(|n| pick(n)) else {
                continue;
            };
            let f = &s.fields[k];
            if f.location != aster_mesh::FieldLocation::Nodes {
                return Err(ex.kw_error(
                    CMD,
                    occ,
                    "NOM_CHAM",
                    format!(
                        "field `{}` of the MED file is not nodal (only nodal fields are read here)",
                        f.name
                    ),
                ));
            }
            found = true;
            let nc = f.components.len();
            let mut nf = NodalField::with_node_count(f.components.clone(), mesh.node_count());
            for n in 0..mesh.node_count() {
                let on = covered
                    .get(k)
                    .and_then(Option::as_ref)
                    .is_none_or(|c: &Vec<bool>| c[n]);
                if !on && !prol_zero {
                    continue;
                }
                let vals = (0..nc).map(|c| Some(if on { f.values[n * nc + c] } else { 0.0 }));
                nf.insert(NodeId(n as u32), vals);
            }
            let step = out.entry(s.nume_ordre).or_insert_with(|| Step {
                nume_ordre: s.nume_ordre.max(0) as u32,
                inst: s.inst,
                fields: Default::default(),
            });
            step.fields.insert(nom_cham.to_string(), Field::Nodal(nf));
        }
        if !found {
            return Err(ex.kw_error(
                CMD,
                occ,
                "NOM_CHAM",
                format!(
                    "the MED file {} has no field `{}` on mesh `{}`",
                    path.display(),
                    med_name.trim_end(),
                    info.mesh_name
                ),
            ));
        }
    }
    let typ = kw.str("TYPE_RESU").unwrap_or("EVOL_NOLI").to_lowercase();
    let evol = EvolResult {
        prep_varc: false,
        typ,
        mesh: model.mesh,
        steps: out.into_values().collect(),
        fem: None,
        tables: Vec::new(),
        modal: None,
        cases: None,
        thermal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(evol)))
}
