//! Materials that follow the temperature in STAT_NON_LINE: the cells whose
//! parameters code_aster evaluates at each Gauss point and instant from
//! the temperature there (`ELAS_FO` with E or NU varying, `ECRO_LINE_FO`,
//! and any plastic cell under `AFFE_VARC`), turned into
//! [`aster_fem::ThermoMaterial`]s integrated by `aster_fem`'s
//! `behaviour::thermo` (code_aster's `nmelas`, `nmisot`).
//!
//! A heated cell becomes such a cell in STAT_NON_LINE when its
//! COMPORTEMENT is a plastic law or its ELAS_FO's E or NU do not resolve
//! to one value ([`crate::elas_fo`]); other heated elastic cells keep the
//! thermal strain as a load. Supported: RELATION ELAS, VMIS_ISOT_LINE
//! (ECRO_LINE or ECRO_LINE_FO) and VMIS_ISOT_TRAC (one TRACTION curve,
//! or a nappe of TEMP: `aster_fem::TractionNappe`) in small strains
//! (`DEFORMATION='PETIT'`), with functions of TEMP given as constants or
//! tables interpolated linearly; everything else is refused with the
//! keyword's location.

use crate::concept::{Material, MaterialField, ModelDef};
use crate::elas_fo::FoArg;
use crate::function::{Extension, Function, Scale};
use crate::solve::BehaviourOcc;
use crate::solve::Relation;
use aster_eval::ExecError;
use aster_fem::{CurveEnd, TempFn, ThermoHardening, ThermoMaterial};
use aster_mesh::{CellId, Mesh};
use std::collections::{BTreeMap, HashMap};
use std::rc::Rc;
use std::sync::Arc;

/// What STAT_NON_LINE takes from [`prepare`]: the material field with the
/// temperature-dependent cells given their start values (E, NU finite for
/// the assembled stiffness) and taken out of the thermal-strain loads, and
/// those cells' materials with the temperature history.
pub struct Prepared {
    pub materials: Rc<MaterialField>,
    pub cells: BTreeMap<CellId, Arc<ThermoMaterial>>,
    pub history: Option<Arc<aster_fem::NodalHistory>>,
}

pub(crate) fn extension(e: Extension) -> CurveEnd {
    match e {
        Extension::Linear => CurveEnd::Linear,
        Extension::Constant => CurveEnd::Constant,
        Extension::Excluded => CurveEnd::Excluded,
    }
}

/// A material function of TEMP as fem takes it: a constant, or a table
/// interpolated linearly.
pub fn temp_fn(f: &Function, name: &str) -> Result<TempFn, String> {
    if let Some(c) = crate::elas_fo::constant(f) {
        return Ok(TempFn::Constant(c));
    }
    match f {
        Function::Tabulated(t) => {
            if t.parameter != "TEMP" {
                return Err(format!(
                    "`{name}` is a function of {}: aster gives the behaviour the temperature (TEMP) only",
                    t.parameter
                ));
            }
            if t.scale_x != Scale::Linear || t.scale_y != Scale::Linear {
                return Err(format!(
                    "`{name}` is interpolated on a LOG scale: aster's material functions of TEMP are linear (INTERPOL='LIN')"
                ));
            }
            Ok(TempFn::Table {
                t: t.abscissae().to_vec(),
                v: t.values().to_vec(),
                left: extension(t.left),
                right: extension(t.right),
            })
        }
        _ => Err(format!(
            "`{name}` is a formula or a nappe: aster evaluates material functions of TEMP given by DEFI_FONCTION (or CALC_FONC_INTERP) or DEFI_CONSTANTE"
        )),
    }
}

/// The relation each continuum cell ends with (the last COMPORTEMENT
/// occurrence on it; ELAS in small strains where none is).
fn relations(
    model: &ModelDef,
    occurrences: &[BehaviourOcc],
) -> HashMap<CellId, (Relation, aster_fem::Kinematics)> {
    let mut out = HashMap::new();
    for occ in occurrences {
        let cells: Vec<CellId> = match &occ.cells {
            None => model.cells.keys().copied().collect(),
            Some(c) => c.clone(),
        };
        for c in cells {
            out.insert(c, (occ.relation, occ.kinematics));
        }
    }
    out
}

/// The located refusal of a function.
fn refuse(arg: &FoArg, why: String, locate: &dyn Fn(aster_syntax::Span) -> String) -> ExecError {
    ExecError::new(format!(
        "not supported yet: DEFI_MATERIAU/{}: {why} ({})",
        arg.keyword,
        locate(arg.span)
    ))
}

/// The temperature-dependent material of a cell with material `mat`,
/// relation `relation` and reference temperature `tref`.
fn thermo_material(
    mat: &Material,
    relation: Relation,
    tref: f64,
    cell: &str,
    locate: &dyn Fn(aster_syntax::Span) -> String,
) -> Result<ThermoMaterial, ExecError> {
    let fo_fn =
        |arg: &FoArg| temp_fn(&arg.function.0, &arg.name).map_err(|w| refuse(arg, w, locate));
    let (e, nu, alpha) = match &mat.elas_fo {
        Some(fo) => {
            let alpha = match &fo.alpha {
                None => None,
                Some(a) => {
                    let f = &a.function.0;
                    match (crate::elas_fo::constant(f), fo.temp_def_alpha) {
                        (Some(c), _) => Some(TempFn::Constant(c)),
                        (None, Some(tdef)) => {
                            match crate::elas_fo::alfint(f, tref, tdef, fo.precision)
                                .map_err(|w| refuse(a, format!("`{}`: {w}", a.name), locate))?
                            {
                                Some(t) => Some(
                                    temp_fn(&Function::Tabulated(t), &a.name)
                                        .map_err(|w| refuse(a, w, locate))?,
                                ),
                                None => Some(fo_fn(a)?),
                            }
                        }
                        (None, None) => Some(fo_fn(a)?),
                    }
                }
            };
            (fo_fn(&fo.e)?, fo_fn(&fo.nu)?, alpha)
        }
        None => (
            TempFn::Constant(mat.young),
            TempFn::Constant(mat.poisson),
            mat.alpha.map(TempFn::Constant),
        ),
    };
    let missing = |what: &str| {
        ExecError::new(format!(
            "STAT_NON_LINE/COMPORTEMENT: RELATION='{}' on cell {cell} needs {what} in its material's DEFI_MATERIAU",
            relation.keyword()
        ))
    };
    let hardening = match relation {
        Relation::Elas => None,
        Relation::VmisIsotLine => Some(match (&mat.ecro_line_fo, &mat.ecro_line) {
            (Some(fo), _) => ThermoHardening::Linear {
                d_sigm_epsi: fo_fn(&fo.d_sigm_epsi)?,
                sy: fo_fn(&fo.sy)?,
            },
            (None, Some(c)) => ThermoHardening::Linear {
                d_sigm_epsi: TempFn::Constant(c.d_sigm_epsi),
                sy: TempFn::Constant(c.sy),
            },
            (None, None) => return Err(missing("ECRO_LINE or ECRO_LINE_FO")),
        }),
        Relation::VmisIsotTrac if mat.traction_nappe.is_some() => {
            let n = mat.traction_nappe.as_deref().cloned().ok_or_else(|| missing("TRACTION"))?;
            Some(ThermoHardening::Nappe(n))
        }
        Relation::VmisIsotTrac => {
            let t = mat
                .traction
                .as_ref()
                .ok_or_else(|| missing("TRACTION=_F(SIGM=...)"))?;
            let law = aster_fem::VonMises::traction_curve(t.abscissae(), t.values(), extension(t.right))
                .map_err(|e| ExecError::new(format!("DEFI_MATERIAU/TRACTION: {e}")))?;
            Some(ThermoHardening::Curve(law))
        }
        other => {
            return Err(ExecError::new(format!(
                "not supported yet: STAT_NON_LINE/COMPORTEMENT RELATION='{}' on cell {cell} with a temperature (AFFE_VARC): aster integrates ELAS, VMIS_ISOT_LINE and VMIS_ISOT_TRAC with parameters that follow the temperature",
                other.keyword()
            )))
        }
    };
    Ok(ThermoMaterial {
        e,
        nu,
        alpha,
        tref,
        hardening,
    })
}

/// Chooses and builds the temperature-dependent cells of a STAT_NON_LINE
/// (see the module's documentation); `Ok(None)` when there are none.
pub fn prepare(
    mesh: &Mesh,
    model: &ModelDef,
    occurrences: &[BehaviourOcc],
    materials: &MaterialField,
    dynamics: bool,
    locate: &dyn Fn(aster_syntax::Span) -> String,
) -> Result<Option<Prepared>, ExecError> {
    let Some(temp) = materials
        .temperature
        .as_ref()
        .filter(|t| !t.fields.is_empty())
    else {
        return Ok(None);
    };
    let relations = relations(model, occurrences);
    let mut cells = BTreeMap::new();
    let mut field = materials.clone();
    let mut heated = (**temp).clone();
    // One temperature-dependent material (and start material) per
    // (material, relation), shared by its cells.
    type Shared = (*const Material, Relation, Arc<ThermoMaterial>, Rc<Material>);
    let mut shared: Vec<Shared> = Vec::new();
    for (&cell, m) in &model.cells {
        use crate::concept::Modelisation as M;
        if !matches!(
            m,
            M::PlaneStrain | M::PlaneStress | M::Axisymmetric | M::Solid3D
        ) {
            continue;
        }
        if !temp.cells.contains(&cell) {
            continue;
        }
        let Some(mat) = materials.cells.get(&cell) else {
            continue;
        };
        let (relation, kinematics) = relations
            .get(&cell)
            .copied()
            .unwrap_or((Relation::Elas, aster_fem::Kinematics::Small));
        let varying_elas = mat.unresolved.is_some() && mat.elas_fo.is_some();
        if relation == Relation::Elas && kinematics == aster_fem::Kinematics::Small && !varying_elas
        {
            continue;
        }
        let name = mesh.cell_name(cell);
        if dynamics || kinematics != aster_fem::Kinematics::Small || mat.orthotropic.is_some() {
            let what = if dynamics {
                "DYNA_NON_LINE".to_string()
            } else if mat.orthotropic.is_some() {
                "an orthotropic material (ELAS_ORTH)".to_string()
            } else {
                format!("DEFORMATION='{}'", kinematics.aster_name())
            };
            if !varying_elas && relation == Relation::Elas && dynamics {
                // The thermal strain as a load: refused later with its own
                // reason.
                continue;
            }
            return Err(ExecError::new(format!(
                "not supported yet: a temperature (AFFE_VARC, {}) on cell {name} with {what}: aster integrates temperature-dependent and thermo-plastic cells in small strains (DEFORMATION='PETIT') in STAT_NON_LINE",
                temp.at
            )));
        }
        let key = (Rc::as_ptr(mat), relation);
        let (thermo, start) = match shared.iter().find(|s| (s.0, s.1) == key) {
            Some(s) => (s.2.clone(), s.3.clone()),
            None => {
                let t = Arc::new(thermo_material(mat, relation, temp.tref, &name, locate)?);
                // E and NU at the reference temperature for the assembled
                // stiffness (the behaviour corrects it at each point).
                let el = t
                    .elastic_at(temp.tref)
                    .or_else(|_| {
                        let first = mesh.cell(cell).nodes[0].0 as usize;
                        t.elastic_at(temp.fields[0].1[first])
                    })
                    .map_err(|e| {
                        ExecError::new(format!("DEFI_MATERIAU: the material of cell {name}: {e}"))
                    })?;
                let start = Rc::new(Material {
                    young: el.e,
                    poisson: el.nu,
                    unresolved: None,
                    ..(**mat).clone()
                });
                shared.push((key.0, key.1, t.clone(), start.clone()));
                (t, start)
            }
        };
        cells.insert(cell, thermo);
        field.cells.insert(cell, start);
        heated.cells.remove(&cell);
    }
    if cells.is_empty() {
        return Ok(None);
    }
    field.temperature = Some(Rc::new(heated));
    let history = aster_fem::NodalHistory {
        knots: temp
            .fields
            .iter()
            .map(|(t, v)| (*t, Arc::new(v.to_vec())))
            .collect(),
        constant_before: temp.constant_before,
        constant_after: temp.constant_after,
    };
    Ok(Some(Prepared {
        materials: Rc::new(field),
        cells,
        history: Some(Arc::new(history)),
    }))
}
