//! Linear heat conduction: `AFFE_MODELE(PHENOMENE='THERMIQUE')`,
//! `AFFE_CHAR_THER` and `THER_LINEAIRE` (numerics in `aster_fem::thermal`).
//!
//! The result is an `EVOL_THER` holding the nodal field `TEMP` at every
//! instant (numbered from 0, the initial state), which `TEST_RESU`,
//! `CREA_CHAMP(OPERATION='EXTR')` and `AFFE_MATERIAU/AFFE_VARC` read as
//! any other result.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::select;
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::thermal::{SkinLoad, ThermalHypothesis, ThermalProblem, Transient};
use aster_mesh::{CellId, NodeId};
use std::collections::BTreeSet;
use std::rc::Rc;

/// A thermal model: its cells and their geometry.
#[derive(Clone, Debug)]
pub struct ThermalModel {
    pub mesh: u32,
    pub hypothesis: ThermalHypothesis,
    pub cells: BTreeSet<CellId>,
}

/// `AFFE_CHAR_THER`: boundary conditions of a thermal model.
#[derive(Clone, Debug, Default)]
pub struct ThermalLoad {
    pub mesh: u32,
    pub skin: Vec<(CellId, SkinLoad)>,
    pub imposed: Vec<(NodeId, f64)>,
}

/// The thermal modelisations (`AFFE_MODELE/AFFE/MODELISATION` with
/// `PHENOMENE='THERMIQUE'`).
pub(crate) fn hypothesis(name: &str) -> Option<ThermalHypothesis> {
    match name {
        "PLAN" => Some(ThermalHypothesis::Plane),
        "AXIS" => Some(ThermalHypothesis::Axisymmetric),
        "3D" => Some(ThermalHypothesis::Solid),
        _ => None,
    }
}

/// `AFFE_MODELE` with `PHENOMENE='THERMIQUE'` in every occurrence.
pub(crate) fn affe_modele(
    ex: &mut Executor,
    call: &CommandCall,
) -> Result<CommandOutput, ExecError> {
    let cmd = "AFFE_MODELE";
    let kw = &call.keywords;
    let mesh_ref = ex.required(cmd, kw, "MAILLAGE")?;
    let mesh = ex.mesh(mesh_ref)?;
    let mut hyp = None;
    let mut cells = BTreeSet::new();
    for occ in kw.factor("AFFE") {
        let name = occ.str("MODELISATION").unwrap_or("");
        let Some(h) = hypothesis(name) else {
            let span = occ
                .keyword("MODELISATION")
                .map(|k| k.span)
                .unwrap_or_default();
            return Err(ex.unsupported(
                &format!(
                    "AFFE_MODELE/AFFE/MODELISATION='{name}' with PHENOMENE='THERMIQUE' (supported: PLAN, AXIS, 3D)"
                ),
                span,
            ));
        };
        if hyp.is_some_and(|k| k != h) {
            return Err(ex.kw_error(
                cmd,
                occ,
                "MODELISATION",
                "one thermal modelisation per model is supported",
            ));
        }
        hyp = Some(h);
        let sel = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_MODELE/AFFE: {e}")))?;
        // As code_aster, a modelisation goes only to the cells it has an
        // element for; skin cells keep their boundary elements (loads).
        for c in sel {
            let ty = mesh.cell(c).ty;
            if aster_fem::thermal::conducting_cell(ty, h) {
                cells.insert(c);
            }
        }
    }
    let Some(hypothesis) = hyp else {
        return Err(ExecError::new("AFFE_MODELE: AFFE is required"));
    };
    if cells.is_empty() {
        return Err(ExecError::new(
            "AFFE_MODELE: no cell of the mesh received a thermal element",
        ));
    }
    let model = ThermalModel {
        mesh: mesh_ref.id,
        hypothesis,
        cells,
    };
    store_result(ex, call, Concept::ThermalModel(Rc::new(model)))
}

/// What AFFE_CHAR_THER reads (`crate::support`).
pub(crate) const AFFE_CHAR_THER: Support = Support::keywords(&[
    "MODELE",
    "ECHANGE",
    "ECHANGE/GROUP_MA",
    "ECHANGE/MAILLE",
    "ECHANGE/TOUT",
    "ECHANGE/COEF_H",
    "ECHANGE/TEMP_EXT",
    "TEMP_IMPO",
    "TEMP_IMPO/GROUP_NO",
    "TEMP_IMPO/NOEUD",
    "TEMP_IMPO/GROUP_MA",
    "TEMP_IMPO/MAILLE",
    "TEMP_IMPO/TOUT",
    "TEMP_IMPO/TEMP",
    "FLUX_REP",
    "FLUX_REP/GROUP_MA",
    "FLUX_REP/MAILLE",
    "FLUX_REP/TOUT",
    "FLUX_REP/FLUN",
    "INFO",
]);

pub(crate) fn affe_char_ther(
    ex: &mut Executor,
    call: &CommandCall,
) -> Result<CommandOutput, ExecError> {
    let cmd = "AFFE_CHAR_THER";
    let kw = &call.keywords;
    let model = ex.thermal_model(ex.required(cmd, kw, "MODELE")?)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let mut load = ThermalLoad {
        mesh: model.mesh,
        ..Default::default()
    };
    let skin_cells = |occ: &Keywords, what: &str| -> Result<Vec<CellId>, ExecError> {
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("{cmd}/{what}: {e}")))?;
        let dim = match model.hypothesis {
            ThermalHypothesis::Solid => 2,
            _ => 1,
        };
        if let Some(bad) = select::misfit(&mesh, &cells, |c| c.ty.dim() == dim) {
            return Err(ex.kw_error(
                cmd,
                occ,
                "GROUP_MA",
                format!(
                    "{what} applies to the {} of the model, but {bad}",
                    if dim == 1 {
                        "edges (segments)"
                    } else {
                        "faces"
                    }
                ),
            ));
        }
        Ok(cells)
    };
    let required = |occ: &Keywords, name: &str, what: &str| -> Result<f64, ExecError> {
        occ.f64(name)
            .ok_or_else(|| ex.kw_error(cmd, occ, name, format!("{what} is required")))
    };
    for occ in kw.factor("ECHANGE") {
        let h = required(occ, "COEF_H", "the exchange coefficient COEF_H")?;
        let t_ext = required(occ, "TEMP_EXT", "the exterior temperature TEMP_EXT")?;
        for c in skin_cells(occ, "ECHANGE")? {
            load.skin.push((c, SkinLoad::Exchange { h, t_ext }));
        }
    }
    for occ in kw.factor("FLUX_REP") {
        let q = required(occ, "FLUN", "the normal flux FLUN")?;
        for c in skin_cells(occ, "FLUX_REP")? {
            load.skin.push((c, SkinLoad::NormalFlux { q }));
        }
    }
    for occ in kw.factor("TEMP_IMPO") {
        let t = required(occ, "TEMP", "the temperature TEMP")?;
        let nodes = select::nodes(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("{cmd}/TEMP_IMPO: {e}")))?;
        load.imposed.extend(nodes.into_iter().map(|n| (n, t)));
    }
    store_result(ex, call, Concept::ThermalLoad(Rc::new(load)))
}

/// What THER_LINEAIRE reads (`crate::support`).
pub(crate) const THER_LINEAIRE: Support = Support {
    values: &[Values::new("EXCIT/TYPE_CHARGE", &["FIXE_CSTE"])],
    ..Support::keywords(&[
        "MODELE",
        "CHAM_MATER",
        "EXCIT",
        "EXCIT/CHARGE",
        "EXCIT/TYPE_CHARGE",
        "TYPE_CALCUL",
        "ETAT_INIT",
        "ETAT_INIT/CHAM_NO",
        "ETAT_INIT/VALE",
        "ETAT_INIT/STAT",
        "INCREMENT",
        "INCREMENT/LIST_INST",
        "INCREMENT/INST_INIT",
        "INCREMENT/INST_FIN",
        "INCREMENT/CRITERE",
        "INCREMENT/PRECISION",
        "SCHEMA_TEMPS",
        "SCHEMA_TEMPS/SCHEMA",
        "SCHEMA_TEMPS/THETA",
        "SOLVEUR",
        "SOLVEUR/*",
        "TITRE",
        "INFO",
    ])
};

pub(crate) fn ther_lineaire(
    ex: &mut Executor,
    call: &CommandCall,
) -> Result<CommandOutput, ExecError> {
    let cmd = "THER_LINEAIRE";
    let kw = &call.keywords;
    let model = ex.thermal_model(ex.required(cmd, kw, "MODELE")?)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let mater = ex.material_field(ex.required(cmd, kw, "CHAM_MATER")?)?;
    let mut cells = Vec::with_capacity(model.cells.len());
    for &c in &model.cells {
        let m = mater.cells.get(&c).ok_or_else(|| {
            ex.kw_error(
                cmd,
                kw,
                "CHAM_MATER",
                format!("cell {} of the model has no material", mesh.cell_name(c)),
            )
        })?;
        let th = m.thermal.ok_or_else(|| {
            ex.kw_error(
                cmd,
                kw,
                "CHAM_MATER",
                format!(
                    "the material of cell {} has no THER (LAMBDA, RHO_CP)",
                    mesh.cell_name(c)
                ),
            )
        })?;
        cells.push((c, th));
    }
    let mut skin = Vec::new();
    let mut imposed = Vec::new();
    for occ in kw.factor("EXCIT") {
        let load = ex.thermal_load(ex.required(cmd, occ, "CHARGE")?)?;
        if load.mesh != model.mesh {
            return Err(ex.kw_error(
                cmd,
                occ,
                "CHARGE",
                "the load is defined on another mesh than the model",
            ));
        }
        skin.extend(load.skin.iter().copied());
        imposed.extend(load.imposed.iter().copied());
    }
    let problem = ThermalProblem {
        mesh: &mesh,
        hypothesis: model.hypothesis,
        cells,
        skin,
        imposed,
    };
    // TYPE_CALCUL='TRAN' (the default): from ETAT_INIT (STAT='OUI': the
    // stationary state at the first instant), the θ-scheme over the
    // instants; 'STAT': the stationary state at every instant (the loads
    // are constant in time here, so it is one field).
    let transient = kw.str("TYPE_CALCUL") != Some("STAT");
    let init = kw.factor("ETAT_INIT");
    let init = init.first();
    let initial = match init {
        Some(occ) if occ.contains("CHAM_NO") => {
            let f = ex.field(ex.required(cmd, occ, "CHAM_NO")?)?;
            let Field::Nodal(f) = &*f else {
                return Err(ex.kw_error(
                    cmd,
                    occ,
                    "CHAM_NO",
                    "the initial temperature is a nodal field (NOEU_TEMP_R)",
                ));
            };
            Some(f.per_node("TEMP", mesh.node_count()))
        }
        Some(occ) if occ.contains("VALE") => {
            let v = occ.f64("VALE").unwrap_or(0.0);
            Some(vec![v; mesh.node_count()])
        }
        _ => None,
    };
    let fem_err = |e: aster_fem::FemError| ExecError::new(format!("{cmd}: {e}"));
    let Some(inc) = kw.factor("INCREMENT").first() else {
        return Err(ex.kw_error(cmd, kw, "INCREMENT", "INCREMENT is required"));
    };
    let list = ex.real_list(ex.required(cmd, inc, "LIST_INST")?)?;
    let steps: Vec<(f64, Vec<f64>)> = if transient {
        let instants =
            crate::list::select_instants(&list, inc.f64("INST_INIT"), inc.f64("INST_FIN"))
                .map_err(|e| ex.kw_error(cmd, inc, "LIST_INST", e))?;
        let theta = kw
            .factor("SCHEMA_TEMPS")
            .first()
            .and_then(|s| s.f64("THETA"))
            .unwrap_or(0.57);
        let tr = Transient {
            theta,
            instants: instants.clone(),
            initial,
        };
        let temps = aster_fem::thermal::transient(&problem, &tr).map_err(fem_err)?;
        instants.into_iter().zip(temps).collect()
    } else {
        let lo = inc.f64("INST_INIT").unwrap_or(f64::NEG_INFINITY);
        let hi = inc.f64("INST_FIN").unwrap_or(f64::INFINITY);
        let t = aster_fem::thermal::stationary(&problem).map_err(fem_err)?;
        list.iter()
            .filter(|&&i| i >= lo - 1e-6 * lo.abs() && i <= hi + 1e-6 * hi.abs())
            .map(|&i| (i, t.clone()))
            .collect()
    };
    // code_aster's storage (ther_lineaire_ops: `first_index`): a transient
    // result numbers its initial state 0, a stationary one stores its first
    // instant at 1 (tplp01a: `NUME_ORDRE=1` of a list of one instant).
    let first = u32::from(!transient);
    let steps = steps
        .into_iter()
        .enumerate()
        .map(|(i, (inst, t))| {
            let mut field = NodalField::new(vec!["TEMP".into()]);
            for (node, v) in t.iter().enumerate() {
                if v.is_finite() {
                    field.set(NodeId(node as u32), "TEMP", *v);
                }
            }
            Step {
                nume_ordre: first + i as u32,
                inst,
                fields: [("TEMP".to_string(), Field::Nodal(field))].into(),
            }
        })
        .collect();
    let result = EvolResult {
        typ: "evol_ther".into(),
        mesh: model.mesh,
        steps,
        fem: None,
        tables: Vec::new(),
        modal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(result)))
}
