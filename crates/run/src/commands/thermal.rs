//! Linear heat conduction: `AFFE_MODELE(PHENOMENE='THERMIQUE')`,
//! `AFFE_CHAR_THER(_F)` and `THER_LINEAIRE` (numerics in `aster_fem::thermal`).
//!
//! `AFFE_CHAR_THER_F/TEMP_IMPO` gives functions of `INST` and the
//! coordinates, evaluated at each node and instant (code_aster dualises
//! it: the node takes exactly that value).
//!
//! The result is an `EVOL_THER` holding the nodal field `TEMP` at every
//! instant (numbered from 0, the initial state), which `TEST_RESU`,
//! `CREA_CHAMP(OPERATION='EXTR')` and `AFFE_MATERIAU/AFFE_VARC` read as
//! any other result.

use crate::concept::{Concept, EvolResult, LoadFunction, Step};
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::select;
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::thermal::{Imposed, SkinLoad, ThermalHypothesis, ThermalProblem, Transient};
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
    /// `AFFE_CHAR_THER_F` fluxes and exchanges given by functions of
    /// `INST` (evaluated at each instant).
    pub skin_f: Vec<(CellId, SkinLoadF)>,
    pub imposed: Vec<(NodeId, TempImpo)>,
    /// `SOURCE/SOUR`: a constant volume heat source (W/m³) per cell of
    /// the model.
    pub sources: Vec<(CellId, f64)>,
}

/// A boundary condition whose values are functions of `INST`.
#[derive(Clone, Debug, PartialEq)]
pub enum SkinLoadF {
    Exchange {
        h: crate::concept::LoadFunction,
        t_ext: crate::concept::LoadFunction,
    },
    NormalFlux {
        q: crate::concept::LoadFunction,
    },
}

impl SkinLoadF {
    /// Its values at instant `t`.
    pub fn at(&self, t: f64) -> Result<SkinLoad, ExecError> {
        let eval = |f: &crate::concept::LoadFunction| {
            f.0.eval_named(&[("INST", t)])
                .map_err(|e| ExecError::new(format!("a thermal load at INST = {t}: {e}")))
        };
        Ok(match self {
            SkinLoadF::Exchange { h, t_ext } => SkinLoad::Exchange {
                h: eval(h)?,
                t_ext: eval(t_ext)?,
            },
            SkinLoadF::NormalFlux { q } => SkinLoad::NormalFlux { q: eval(q)? },
        })
    }
}

/// A `TEMP_IMPO` temperature: a real (`AFFE_CHAR_THER`) or a function of
/// `INST` and the coordinates, here the node's (`AFFE_CHAR_THER_F`).
#[derive(Clone, Debug, PartialEq)]
pub enum TempImpo {
    Constant(f64),
    Function(crate::concept::LoadFunction, [f64; 3]),
}

impl TempImpo {
    /// The temperature at each instant (`Imposed` for the solver), times
    /// `EXCIT/FONC_MULT`'s f(INST) when given.
    pub(crate) fn at(
        &self,
        instants: &[f64],
        mult: Option<&crate::concept::LoadFunction>,
    ) -> Result<Imposed, ExecError> {
        if let (TempImpo::Constant(t), None) = (self, mult) {
            return Ok(Imposed::Constant(*t));
        }
        let eval = |f: &crate::concept::LoadFunction, t: f64, [x, y, z]: [f64; 3]| {
            f.0.eval_named(&[("INST", t), ("X", x), ("Y", y), ("Z", z)])
                .map_err(|e| {
                    ExecError::new(format!("TEMP_IMPO at ({x}, {y}, {z}), INST = {t}: {e}"))
                })
        };
        let values = instants
            .iter()
            .map(|&t| {
                let v = match self {
                    TempImpo::Constant(v) => *v,
                    TempImpo::Function(f, xyz) => eval(f, t, *xyz)?,
                };
                match mult {
                    Some(m) => Ok(v * eval(m, t, [0.0; 3])?),
                    None => Ok(v),
                }
            })
            .collect::<Result<_, ExecError>>()?;
        Ok(Imposed::PerInstant(values))
    }
}

/// A normal flux varying in time in THER_LINEAIRE: a constant q times
/// `FONC_MULT`, or a function of `INST` (times `FONC_MULT` when given).
enum Varying {
    Scaled(f64, crate::concept::LoadFunction),
    Function(
        crate::concept::LoadFunction,
        Option<crate::concept::LoadFunction>,
    ),
}

impl Varying {
    /// q at each instant.
    fn at(&self, instants: &[f64]) -> Result<Vec<f64>, ExecError> {
        let eval = |f: &crate::concept::LoadFunction, t: f64| {
            f.0.eval_named(&[("INST", t), ("X", 0.0), ("Y", 0.0), ("Z", 0.0)])
                .map_err(|e| ExecError::new(format!("FLUX_REP at INST = {t}: {e}")))
        };
        instants
            .iter()
            .map(|&t| match self {
                Varying::Scaled(q, m) => Ok(q * eval(m, t)?),
                Varying::Function(f, m) => {
                    let q = eval(f, t)?;
                    match m {
                        Some(m) => Ok(q * eval(m, t)?),
                        None => Ok(q),
                    }
                }
            })
            .collect()
    }
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
    "SOURCE",
    "SOURCE/GROUP_MA",
    "SOURCE/MAILLE",
    "SOURCE/TOUT",
    "SOURCE/SOUR",
    "INFO",
]);

/// The skin cells (segments in 2D, faces in 3D) of a boundary condition's
/// occurrence, or an error at its GROUP_MA.
fn skin_cells(
    ex: &Executor,
    cmd: &str,
    occ: &Keywords,
    what: &str,
    model: &ThermalModel,
    mesh: &aster_mesh::Mesh,
) -> Result<Vec<CellId>, ExecError> {
    let cells =
        select::cells(occ, mesh, "").map_err(|e| ExecError::new(format!("{cmd}/{what}: {e}")))?;
    let dim = match model.hypothesis {
        ThermalHypothesis::Solid => 2,
        _ => 1,
    };
    if let Some(bad) = select::misfit(mesh, &cells, |c| c.ty.dim() == dim) {
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
}

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
    let skin_cells = |occ: &Keywords, what: &str| skin_cells(ex, cmd, occ, what, &model, &mesh);
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
    for occ in kw.factor("SOURCE") {
        let q = required(occ, "SOUR", "the heat source SOUR")?;
        let cells = select::cells(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("{cmd}/SOURCE: {e}")))?;
        // code_aster's CHAR_THER_SOUR_R (te0080) exists on the model's
        // conducting cells only: the others of the group take nothing.
        load.sources.extend(
            cells
                .into_iter()
                .filter(|c| model.cells.contains(c))
                .map(|c| (c, q)),
        );
    }
    for occ in kw.factor("TEMP_IMPO") {
        let t = required(occ, "TEMP", "the temperature TEMP")?;
        let nodes = select::nodes(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("{cmd}/TEMP_IMPO: {e}")))?;
        load.imposed
            .extend(nodes.into_iter().map(|n| (n, TempImpo::Constant(t))));
    }
    store_result(ex, call, Concept::ThermalLoad(Rc::new(load)))
}

/// What AFFE_CHAR_THER_F reads (`crate::support`): `TEMP_IMPO`, and
/// `FLUX_REP`/`ECHANGE` given by constant functions (`DEFI_CONSTANTE`) or
/// functions of `INST`; fluxes and exchanges varying in space are refused
/// at their keyword.
pub(crate) const AFFE_CHAR_THER_F: Support = Support::keywords(&[
    "MODELE",
    "ECHANGE",
    "ECHANGE/GROUP_MA",
    "ECHANGE/MAILLE",
    "ECHANGE/TOUT",
    "ECHANGE/COEF_H",
    "ECHANGE/TEMP_EXT",
    "FLUX_REP",
    "FLUX_REP/GROUP_MA",
    "FLUX_REP/MAILLE",
    "FLUX_REP/TOUT",
    "FLUX_REP/FLUN",
    "TEMP_IMPO",
    "TEMP_IMPO/GROUP_NO",
    "TEMP_IMPO/NOEUD",
    "TEMP_IMPO/GROUP_MA",
    "TEMP_IMPO/MAILLE",
    "TEMP_IMPO/TOUT",
    "TEMP_IMPO/TEMP",
    "INFO",
]);

pub(crate) fn affe_char_ther_f(
    ex: &mut Executor,
    call: &CommandCall,
) -> Result<CommandOutput, ExecError> {
    let cmd = "AFFE_CHAR_THER_F";
    let kw = &call.keywords;
    let model = ex.thermal_model(ex.required(cmd, kw, "MODELE")?)?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let mut load = ThermalLoad {
        mesh: model.mesh,
        ..Default::default()
    };
    // A function of nothing (DEFI_CONSTANTE) is its value; a function of
    // INST is evaluated at each instant by the solver.
    let function = |occ: &Keywords, key: &str, what: &str| -> Result<Option<f64>, ExecError> {
        let f = super::loads_f::function_at(ex, what, occ, key)?
            .ok_or_else(|| ex.kw_error(what, occ, key, format!("a function {key} is required")))?;
        if let Some(p) = f.0.parameters().into_iter().find(|p| *p != "INST") {
            let span = occ.keyword(key).map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported(
                &format!("{what}/{key} as a function of {p} (fluxes and exchanges varying in space; functions of INST are taken)"),
                span,
            ));
        }
        if f.0.parameters().is_empty() {
            return f
                .0
                .eval_named(&[])
                .map(Some)
                .map_err(|e| ex.kw_error(what, occ, key, e.to_string()));
        }
        Ok(None)
    };
    let func = |occ: &Keywords,
                key: &str,
                what: &str|
     -> Result<crate::concept::LoadFunction, ExecError> {
        super::loads_f::function_at(ex, what, occ, key)?
            .ok_or_else(|| ex.kw_error(what, occ, key, format!("a function {key} is required")))
    };
    for occ in kw.factor("ECHANGE") {
        let what = "AFFE_CHAR_THER_F/ECHANGE";
        let cells = skin_cells(ex, cmd, occ, "ECHANGE", &model, &mesh)?;
        match (
            function(occ, "COEF_H", what)?,
            function(occ, "TEMP_EXT", what)?,
        ) {
            (Some(h), Some(t_ext)) => {
                for c in cells {
                    load.skin.push((c, SkinLoad::Exchange { h, t_ext }));
                }
            }
            _ => {
                let l = SkinLoadF::Exchange {
                    h: func(occ, "COEF_H", what)?,
                    t_ext: func(occ, "TEMP_EXT", what)?,
                };
                load.skin_f
                    .extend(cells.into_iter().map(|c| (c, l.clone())));
            }
        }
    }
    for occ in kw.factor("FLUX_REP") {
        let what = "AFFE_CHAR_THER_F/FLUX_REP";
        let cells = skin_cells(ex, cmd, occ, "FLUX_REP", &model, &mesh)?;
        match function(occ, "FLUN", what)? {
            Some(q) => {
                for c in cells {
                    load.skin.push((c, SkinLoad::NormalFlux { q }));
                }
            }
            None => {
                let l = SkinLoadF::NormalFlux {
                    q: func(occ, "FLUN", what)?,
                };
                load.skin_f
                    .extend(cells.into_iter().map(|c| (c, l.clone())));
            }
        }
    }
    for occ in kw.factor("TEMP_IMPO") {
        let what = "AFFE_CHAR_THER_F/TEMP_IMPO";
        let f = super::loads_f::function_at(ex, what, occ, "TEMP")?
            .ok_or_else(|| ex.kw_error(what, occ, "TEMP", "a function TEMP is required"))?;
        let nodes =
            select::nodes(occ, &mesh, "").map_err(|e| ExecError::new(format!("{what}: {e}")))?;
        for n in nodes {
            load.imposed
                .push((n, TempImpo::Function(f.clone(), mesh.coord(n))));
        }
    }
    store_result(ex, call, Concept::ThermalLoad(Rc::new(load)))
}

/// One `EXCIT` occurrence: the occurrence, its load and its `FONC_MULT`.
pub(crate) type ExcitLoad<'k> = (&'k Keywords, Rc<ThermalLoad>, Option<LoadFunction>);

/// The thermal loads of a command's `EXCIT` occurrences, each with its
/// occurrence and its `FONC_MULT`, checked to lie on the model's mesh.
pub(crate) fn excit_loads<'k>(
    ex: &Executor,
    cmd: &str,
    kw: &'k Keywords,
    model: &ThermalModel,
) -> Result<Vec<ExcitLoad<'k>>, ExecError> {
    let mut out = Vec::new();
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
        let mult = super::loads_f::function_at(ex, cmd, occ, "FONC_MULT")?;
        out.push((occ, load, mult));
    }
    Ok(out)
}

/// What THER_LINEAIRE reads (`crate::support`).
pub(crate) const THER_LINEAIRE: Support = Support {
    values: &[Values::new("EXCIT/TYPE_CHARGE", &["FIXE_CSTE"])],
    ..Support::keywords(&[
        "MODELE",
        "CHAM_MATER",
        "EXCIT",
        "EXCIT/CHARGE",
        "EXCIT/FONC_MULT",
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
    let mut varying = Vec::new();
    let mut sources = Vec::new();
    for (occ, load, mult) in excit_loads(ex, cmd, kw, &model)? {
        if mult.is_some() && !load.sources.is_empty() {
            let span = occ.keyword("FONC_MULT").map(|k| k.span).unwrap_or_default();
            return Err(ex.unsupported(
                &format!("{cmd}/EXCIT/FONC_MULT on a load with SOURCE"),
                span,
            ));
        }
        sources.extend(load.sources.iter().copied());
        // FONC_MULT scales the imposed temperatures and the normal fluxes
        // at each instant; an exchange varying in time would change the
        // matrix at each step: refused.
        let varying_exchange = load
            .skin_f
            .iter()
            .any(|(_, l)| matches!(l, SkinLoadF::Exchange { .. }))
            || (mult.is_some()
                && load
                    .skin
                    .iter()
                    .any(|(_, l)| matches!(l, SkinLoad::Exchange { .. })));
        if varying_exchange {
            let span = occ
                .keyword(if mult.is_some() {
                    "FONC_MULT"
                } else {
                    "CHARGE"
                })
                .map(|k| k.span)
                .unwrap_or_default();
            return Err(ex.unsupported(
                &format!("{cmd}/EXCIT: an ECHANGE varying in time (a function of INST or FONC_MULT; THER_NON_LINE takes it)"),
                span,
            ));
        }
        for (c, l) in &load.skin {
            match (l, &mult) {
                (SkinLoad::NormalFlux { q }, Some(m)) => {
                    varying.push((*c, Varying::Scaled(*q, m.clone())));
                }
                _ => skin.push((*c, *l)),
            }
        }
        for (c, l) in &load.skin_f {
            if let SkinLoadF::NormalFlux { q } = l {
                varying.push((*c, Varying::Function(q.clone(), mult.clone())));
            }
        }
        imposed.extend(
            load.imposed
                .iter()
                .map(|(n, t)| (*n, t.clone(), mult.clone())),
        );
    }
    // TYPE_CALCUL='TRAN' (the default): from ETAT_INIT (STAT='OUI': the
    // stationary state at the first instant), the θ-scheme over the
    // instants; 'STAT': the stationary state at every instant (only the
    // imposed temperatures vary in time here).
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
    let instants: Vec<f64> = if transient {
        crate::list::select_instants(&list, inc.f64("INST_INIT"), inc.f64("INST_FIN"))
            .map_err(|e| ex.kw_error(cmd, inc, "LIST_INST", e))?
    } else {
        let lo = inc.f64("INST_INIT").unwrap_or(f64::NEG_INFINITY);
        let hi = inc.f64("INST_FIN").unwrap_or(f64::INFINITY);
        list.iter()
            .copied()
            .filter(|&i| i >= lo - 1e-6 * lo.abs() && i <= hi + 1e-6 * hi.abs())
            .collect()
    };
    let imposed = imposed
        .into_iter()
        .map(|(n, t, mult)| Ok((n, t.at(&instants, mult.as_ref())?)))
        .collect::<Result<Vec<_>, ExecError>>()?;
    let varying_flux = varying
        .into_iter()
        .map(|(c, v)| Ok((c, v.at(&instants)?)))
        .collect::<Result<Vec<_>, ExecError>>()?;
    let problem = ThermalProblem {
        mesh: &mesh,
        hypothesis: model.hypothesis,
        cells,
        skin,
        imposed,
        varying_flux,
        sources,
    };
    let temps = if transient {
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
        aster_fem::thermal::transient(&problem, &tr).map_err(fem_err)?
    } else {
        aster_fem::thermal::stationary(&problem, instants.len()).map_err(fem_err)?
    };
    let thermal = {
        let (cells, materials) =
            super::thermal_nl::conductions(ex, cmd, kw, &model, &mater, false)?;
        Some(Rc::new(super::thermal_nl::ThermalRun {
            model: model.clone(),
            cells,
            materials,
        }))
    };
    let steps: Vec<(f64, Vec<f64>)> = instants.into_iter().zip(temps).collect();
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
        prep_varc: false,
        typ: "evol_ther".into(),
        mesh: model.mesh,
        steps,
        fem: None,
        tables: Vec::new(),
        modal: None,
        cases: None,
        thermal,
    };
    store_result(ex, call, Concept::Result(Rc::new(result)))
}
