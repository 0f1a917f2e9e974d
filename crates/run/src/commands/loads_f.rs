//! AFFE_CHAR_MECA_F and AFFE_CHAR_CINE_F: loads whose values are functions
//! of the time `INST` and of the coordinates `X`, `Y`, `Z`.
//!
//! Nodal values (`DDL_IMPO`, `MECA_IMPO`, `FORCE_NODALE`) are evaluated at
//! each node's coordinates and at each step's time, as code_aster does.
//! Distributed loads (`FORCE_CONTOUR`, `FORCE_FACE`, `FORCE_INTERNE`,
//! `PRES_REP`) take functions of `INST` and of the coordinates: code_aster
//! evaluates those at the Gauss points of the load's elements (the RIGI
//! family of the skin or volume element) at each time, and so does
//! `fembridge` (a function of both sampled at the solve's instants).
//! `FORCE_COQUE` takes functions of `INST` or of the coordinates, not of
//! both.

use super::loads::{carried_nodes, check_dof};
use crate::concept::*;
use crate::executor::{store_result, Executor};
use crate::select;
use crate::support::Support;
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::Mesh;
use std::rc::Rc;

/// The function a keyword names (`DX=f`), or an error saying what to give.
pub(super) fn function_at(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    key: &str,
) -> Result<Option<LoadFunction>, ExecError> {
    function_of(ex, cmd, occ, key, &[])
}

/// [`function_at`], the parameters `extra` allowed besides INST, X, Y, Z
/// (a pressure may depend on the current coordinates XF, YF, ZF, which
/// only a follower load, `TYPE_CHARGE='SUIV'`, knows:
/// `evalPressureSetFuncPara`).
fn function_of(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    key: &str,
    extra: &[&str],
) -> Result<Option<LoadFunction>, ExecError> {
    let Some(s) = occ.first(key) else {
        return Ok(None);
    };
    let c = s.as_concept().ok_or_else(|| {
        ex.kw_error(
            cmd,
            occ,
            key,
            "a function (DEFI_FONCTION, DEFI_CONSTANTE, FORMULE) is required in a _F load; real values go in the command without _F",
        )
    })?;
    let f = ex.function(c)?;
    for p in f.parameters() {
        if !["INST", "X", "Y", "Z"].contains(&p) && !extra.contains(&p) {
            return Err(ex.kw_error(
                cmd,
                occ,
                key,
                format!("the function depends on {p}; a load function may depend on INST, X, Y, Z"),
            ));
        }
    }
    Ok(Some(LoadFunction(f)))
}

/// (node, component, function) of one nodal occurrence, checked against the
/// model.
fn nodal_functions(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    (model, mesh, carried): (&ModelDef, &Mesh, &[bool]),
    comps: &[(&str, CompName)],
) -> Result<Vec<ImposedFn>, ExecError> {
    let nodes =
        select::nodes_without(occ, mesh).map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
    let mut out = Vec::new();
    for &(key, comp) in comps {
        let Some(function) = function_at(ex, cmd, occ, key)? else {
            continue;
        };
        for &n in &nodes {
            check_dof(model, mesh, carried, n, comp, cmd)?;
            out.push(ImposedFn {
                node: n,
                comp,
                function: function.clone(),
                xyz: mesh.coord(n),
            });
        }
    }
    Ok(out)
}

/// A distributed-load function, refused when it depends on both the time
/// and the coordinates.
fn time_function(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    key: &str,
) -> Result<Option<LoadFunction>, ExecError> {
    let f = function_at(ex, cmd, occ, key)?;
    if let Some(f) = &f {
        let params = f.0.parameters();
        let coord = params.iter().find(|p| **p != "INST");
        if let (Some(p), true) = (coord, params.contains(&"INST")) {
            let span = occ.keyword(key).map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported(
                &format!("{cmd}/{key} as a function of both INST and {p} (distributed loads take functions of INST or of the coordinates)"),
                span,
            ));
        }
    }
    Ok(f)
}

const DISPLACEMENTS: [(&str, CompName); 3] = [("DX", "DX"), ("DY", "DY"), ("DZ", "DZ")];
/// The force components and the DOFs they load (FORCE_NODALE's and
/// FORCE_ARETE's).
const FORCES: [(&str, CompName); 6] = super::loads_more::EDGE_COMPS;

/// What AFFE_CHAR_MECA_F reads (`crate::support`).
pub(crate) const AFFE_CHAR_MECA_F: Support = Support::keywords(&[
    "MODELE",
    "INFO",
    "VERI_NORM",
    "DOUBLE_LAGRANGE",
    "DDL_IMPO",
    "DDL_IMPO/TOUT",
    "DDL_IMPO/GROUP_NO",
    "DDL_IMPO/NOEUD",
    "DDL_IMPO/GROUP_MA",
    "DDL_IMPO/MAILLE",
    "DDL_IMPO/SANS_GROUP_NO",
    "DDL_IMPO/DX",
    "DDL_IMPO/DY",
    "DDL_IMPO/DZ",
    "FORCE_NODALE",
    "FORCE_NODALE/GROUP_NO",
    "FORCE_NODALE/NOEUD",
    "FORCE_NODALE/FX",
    "FORCE_NODALE/FY",
    "FORCE_NODALE/FZ",
    "FORCE_NODALE/MX",
    "FORCE_NODALE/MY",
    "FORCE_NODALE/MZ",
    "FORCE_CONTOUR",
    "FORCE_CONTOUR/GROUP_MA",
    "FORCE_CONTOUR/MAILLE",
    "FORCE_CONTOUR/FX",
    "FORCE_CONTOUR/FY",
    "FORCE_FACE",
    "FORCE_FACE/GROUP_MA",
    "FORCE_FACE/MAILLE",
    "FORCE_FACE/FX",
    "FORCE_FACE/FY",
    "FORCE_FACE/FZ",
    "FORCE_INTERNE",
    "FORCE_INTERNE/TOUT",
    "FORCE_INTERNE/GROUP_MA",
    "FORCE_INTERNE/MAILLE",
    "FORCE_INTERNE/FX",
    "FORCE_INTERNE/FY",
    "FORCE_INTERNE/FZ",
    "PRES_REP",
    "PRES_REP/GROUP_MA",
    "PRES_REP/MAILLE",
    "PRES_REP/TOUT",
    "PRES_REP/PRES",
    "LIAISON_GROUP",
    "LIAISON_GROUP/GROUP_NO_1",
    "LIAISON_GROUP/GROUP_NO_2",
    "LIAISON_GROUP/GROUP_MA_1",
    "LIAISON_GROUP/GROUP_MA_2",
    "LIAISON_GROUP/SANS_GROUP_NO",
    "LIAISON_GROUP/DDL_1",
    "LIAISON_GROUP/DDL_2",
    "LIAISON_GROUP/COEF_MULT_1",
    "LIAISON_GROUP/COEF_MULT_2",
    "LIAISON_GROUP/COEF_IMPO",
    "FORCE_COQUE",
    "FORCE_COQUE/TOUT",
    "FORCE_COQUE/GROUP_MA",
    "FORCE_COQUE/FX",
    "FORCE_COQUE/FY",
    "FORCE_COQUE/FZ",
    "FORCE_COQUE/MX",
    "FORCE_COQUE/MY",
    "FORCE_COQUE/MZ",
    "FORCE_COQUE/PRES",
    "FORCE_COQUE/F3",
    "FORCE_COQUE/PLAN",
    "FORCE_ARETE",
    "FORCE_ARETE/GROUP_MA",
    "FORCE_ARETE/FX",
    "FORCE_ARETE/FY",
    "FORCE_ARETE/FZ",
    "FORCE_ARETE/MX",
    "FORCE_ARETE/MY",
    "FORCE_ARETE/MZ",
    "LIAISON_OBLIQUE",
    "LIAISON_OBLIQUE/GROUP_NO",
    "LIAISON_OBLIQUE/GROUP_MA",
    "LIAISON_OBLIQUE/SANS_GROUP_NO",
    "LIAISON_OBLIQUE/SANS_GROUP_MA",
    "LIAISON_OBLIQUE/ANGL_NAUT",
    "LIAISON_OBLIQUE/DX",
    "LIAISON_OBLIQUE/DY",
    "LIAISON_OBLIQUE/DZ",
    "LIAISON_OBLIQUE/DRX",
    "LIAISON_OBLIQUE/DRY",
    "LIAISON_OBLIQUE/DRZ",
]);

/// A function of `INST` only (edge forces and relations: aster does not
/// evaluate them at points), refused at the keyword otherwise.
fn inst_function(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    key: &str,
) -> Result<Option<LoadFunction>, ExecError> {
    let f = function_at(ex, cmd, occ, key)?;
    if let Some(p) = f
        .as_ref()
        .and_then(|f| f.0.parameters().into_iter().find(|p| *p != "INST"))
    {
        let span = occ.keyword(key).map(|k| k.span).unwrap_or_default();
        return Err(ex.unsupported(
            &format!("{cmd}/{key} as a function of {p} (only functions of INST)"),
            span,
        ));
    }
    Ok(f)
}

pub fn affe_char_meca_f(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "AFFE_CHAR_MECA_F";
    let kw = &call.keywords;
    let model_ref = ex.required(cmd, kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let carried = carried_nodes(&model, &mesh);
    let ctx = (&*model, &*mesh, carried.as_slice());
    let mut load = MechanicalLoad {
        model: model_ref.id,
        ..MechanicalLoad::default()
    };
    for occ in kw.factor("DDL_IMPO") {
        let what = "AFFE_CHAR_MECA_F/DDL_IMPO";
        load.imposed_fn
            .extend(nodal_functions(ex, what, occ, ctx, &DISPLACEMENTS)?);
    }
    load.imposed_fn =
        super::loads::last_per_dof(std::mem::take(&mut load.imposed_fn), |i| (i.node, i.comp));
    for occ in kw.factor("FORCE_NODALE") {
        let what = "AFFE_CHAR_MECA_F/FORCE_NODALE";
        load.nodal_forces_fn
            .extend(nodal_functions(ex, what, occ, ctx, &FORCES)?);
    }
    for key in ["FORCE_CONTOUR", "FORCE_FACE"] {
        let what = format!("{cmd}/{key}");
        for occ in kw.factor(key) {
            let cells = select::cells(occ, &mesh, "")
                .map_err(|e| ExecError::new(format!("{what}: {e}")))?;
            let force = [
                function_at(ex, &what, occ, "FX")?,
                function_at(ex, &what, occ, "FY")?,
                function_at(ex, &what, occ, "FZ")?,
            ];
            load.boundary_fn.push(BoundaryFn::Force { cells, force });
        }
    }
    for occ in kw.factor("FORCE_INTERNE") {
        let what = "AFFE_CHAR_MECA_F/FORCE_INTERNE";
        let cells =
            select::cells(occ, &mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
        load.volume.push(VolumeForce {
            cells: super::loads::continuum_cells(&model, &mesh, cells),
            force: [0.0; 3],
            functions: [
                function_at(ex, what, occ, "FX")?,
                function_at(ex, what, occ, "FY")?,
                function_at(ex, what, occ, "FZ")?,
            ],
        });
    }
    for occ in kw.factor("PRES_REP") {
        let what = "AFFE_CHAR_MECA_F/PRES_REP";
        let cells =
            select::cells(occ, &mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
        // A function of both INST and the coordinates is refused where a
        // dead load uses it (`fembridge::build_loads`): a follower load
        // evaluates it at each point and time.
        let pressure = function_of(ex, what, occ, "PRES", &["XF", "YF", "ZF"])?
            .ok_or_else(|| ex.kw_error(what, occ, "PRES", "a pressure function is required"))?;
        load.boundary_fn
            .push(BoundaryFn::Pressure { cells, pressure });
    }
    for occ in kw.factor("LIAISON_GROUP") {
        let what = "AFFE_CHAR_MECA_F/LIAISON_GROUP";
        let function = function_at(ex, what, occ, "COEF_IMPO")?
            .ok_or_else(|| ex.kw_error(what, occ, "COEF_IMPO", "a function is required"))?;
        // code_aster evaluates COEF_IMPO of a pair with the time only.
        if let Some(p) = function.0.parameters().into_iter().find(|p| *p != "INST") {
            let span = occ
                .keyword("COEF_IMPO")
                .map(|k| k.span)
                .unwrap_or(call.span);
            return Err(ex.unsupported(
                &format!("{what}/COEF_IMPO as a function of {p} (only functions of INST)"),
                span,
            ));
        }
        let relations = super::loads::liaison_group(ex, what, occ, ctx, 1.0)?;
        load.relations_fn
            .extend(relations.into_iter().map(|relation| RelationFn {
                relation,
                function: function.clone(),
            }));
    }
    for occ in kw.factor("FORCE_ARETE") {
        let what = "AFFE_CHAR_MECA_F/FORCE_ARETE";
        let mut functions: [Option<LoadFunction>; 6] = Default::default();
        for (k, (key, _)) in super::loads_more::EDGE_COMPS.iter().enumerate() {
            functions[k] = inst_function(ex, what, occ, key)?;
        }
        let given = std::array::from_fn(|k| functions[k].is_some());
        let cells = super::loads_more::edge_cells(ex, what, occ, ctx, given)?;
        load.edges.push(EdgeForce {
            cells,
            force: [0.0; 6],
            functions,
        });
    }
    for occ in kw.factor("FORCE_COQUE") {
        let what = "AFFE_CHAR_MECA_F/FORCE_COQUE";
        let (keys, sign) = super::loads_more::shell_comps(occ);
        let mut functions: [Option<LoadFunction>; 7] = Default::default();
        for (f, key) in functions.iter_mut().zip(keys) {
            *f = time_function(ex, what, occ, key)?;
        }
        let shell = super::loads_more::force_coque(
            ex,
            what,
            occ,
            (&model, &mesh),
            [0.0; 7],
            functions,
            sign,
        )?;
        load.shells.push(shell);
    }
    load.shells = super::loads_more::last_per_cell(std::mem::take(&mut load.shells));
    for occ in kw.factor("LIAISON_OBLIQUE") {
        let what = "AFFE_CHAR_MECA_F/LIAISON_OBLIQUE";
        let mut given = Vec::new();
        let mut functions = std::collections::HashMap::new();
        for key in ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"] {
            if let Some(f) = inst_function(ex, what, occ, key)? {
                given.push((key, 1.0));
                functions.insert(key, f);
            }
        }
        for (key, relation) in super::loads_more::liaison_oblique(ex, what, occ, ctx, &given)? {
            let function = functions
                .get(key.as_str())
                .cloned()
                .ok_or_else(|| ExecError::new(format!("{what}: no function for {key}")))?;
            load.relations_fn.push(RelationFn { relation, function });
        }
    }
    store_result(ex, call, Concept::MechanicalLoad(Rc::new(load)))
}

/// What AFFE_CHAR_CINE_F reads (`crate::support`).
pub(crate) const AFFE_CHAR_CINE_F: Support = Support::keywords(&[
    "MODELE",
    "INFO",
    "MECA_IMPO",
    "MECA_IMPO/TOUT",
    "MECA_IMPO/GROUP_NO",
    "MECA_IMPO/NOEUD",
    "MECA_IMPO/GROUP_MA",
    "MECA_IMPO/MAILLE",
    "MECA_IMPO/SANS_GROUP_NO",
    "MECA_IMPO/DX",
    "MECA_IMPO/DY",
    "MECA_IMPO/DZ",
]);

pub fn affe_char_cine_f(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "AFFE_CHAR_CINE_F/MECA_IMPO";
    let kw = &call.keywords;
    let model_ref = ex.required("AFFE_CHAR_CINE_F", kw, "MODELE")?;
    let model = ex.model(model_ref)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let carried = carried_nodes(&model, &mesh);
    let ctx = (&*model, &*mesh, carried.as_slice());
    if kw.factor("MECA_IMPO").is_empty() {
        return Err(ExecError::new(
            "AFFE_CHAR_CINE_F: MECA_IMPO is required (the only condition supported yet)",
        ));
    }
    let mut imposed_fn = Vec::new();
    for occ in kw.factor("MECA_IMPO") {
        imposed_fn.extend(nodal_functions(ex, cmd, occ, ctx, &DISPLACEMENTS)?);
    }
    let imposed_fn = super::loads::last_per_dof(imposed_fn, |i| (i.node, i.comp));
    store_result(
        ex,
        call,
        Concept::KinematicLoad(Rc::new(KinematicLoad {
            model: model_ref.id,
            imposed: Vec::new(),
            imposed_fn,
        })),
    )
}
